/*
 * fuzz_stroke.c: libFuzzer target for the stroker and the SVG arc
 * conversion (harness/core/stroke.c, path.c; `make fuzz`).
 *
 * The input is read as a stroke style and then a path: a byte chooses each
 * command (move, line, a circle's arc, an SVG arc through
 * aa_arc_endpoints, close, a repeat of the pen: a zero-length line, a
 * quadratic or a cubic Bezier arc) and
 * the bytes after it its numbers, each a 16-bit mantissa scaled by a power
 * of two from 2^-24 to 2^24, or one of 0, 1, -1.  What the builder refuses
 * is skipped.  Then:
 *  - aa_arc_endpoints: refused only for a non-finite number; an arc (0)
 *    starts and ends at the given ends (to 1e-9 of the ellipse's size and
 *    the ends' magnitude), with |t1 - t0| <= 2 pi;
 *  - aa_stroke_outline: refused only with AA_EINVAL (and a message), and
 *    then `out` as it was; accepted, every number of the outline is
 *    finite, every contour is a move, lines, arcs and offset curves and a
 *    close, and each without offset curves has positive signed area (its
 *    exact value, (1/2) integral of x dy - y dx, with rounding allowed for
 *    relative to the contour's size): the contours all turn the same way;
 *    an offset curve starts at the pen and ends at its end (to 1e-9); the
 *    outline fills into a scene (aa_path_fill, aa_scene_finish) unless a
 *    number overflows there.
 * A broken invariant aborts.
 */
#include "path.h"
#include "fuzz.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned byte(reader *r)
{
    if (!r->n)
        return 0;
    r->n--;
    return *r->p++;
}

/* A number: 0, 1, -1, or a signed 16-bit mantissa times 2^(e - 24 - 15). */
static double number(reader *r)
{
    unsigned k = byte(r);
    if (k == 0)
        return 0;
    if (k == 1)
        return 1;
    if (k == 2)
        return -1;
    unsigned hi = byte(r), lo = byte(r);
    int m = (int)(hi << 8 | lo) - 32768;
    int e = (int)(k % 49) - 24;
    return ldexp((double)m, e - 15);
}

static void check_arc_endpoints(reader *r)
{
    double x0 = number(r), y0 = number(r), rx = number(r), ry = number(r), phi = number(r);
    unsigned f = byte(r);
    double x1 = number(r), y1 = number(r), c[8];
    aa_arc_kind st;
    if (aa_arc_endpoints(x0, y0, rx, ry, phi * 90, f & 1, (f >> 1) & 1, x1, y1, c, &st))
        return; /* finite numbers whose ellipse overflows: refused, as said */
    if ((st == AA_ARC_NONE) != (x0 == x1 && y0 == y1))
        abort();
    if (st == AA_ARC_LINE && !(rx == 0 || ry == 0))
        abort();
    if (st != AA_ARC_CURVE)
        return;
    double size = hypot(c[2], c[3]) + hypot(c[4], c[5]);
    double tol = 1e-9 * (size + fabs(x0) + fabs(y0) + fabs(x1) + fabs(y1));
    double ax = c[0] + c[2] * cos(c[6]) + c[4] * sin(c[6]);
    double ay = c[1] + c[3] * cos(c[6]) + c[5] * sin(c[6]);
    double bx = c[0] + c[2] * cos(c[7]) + c[4] * sin(c[7]);
    double by = c[1] + c[3] * cos(c[7]) + c[5] * sin(c[7]);
    if (!(hypot(ax - x0, ay - y0) <= tol) || !(hypot(bx - x1, by - y1) <= tol))
        abort();
    if (!(fabs(c[7] - c[6]) <= 2 * M_PI * (1 + 1e-15)))
        abort();
}

/* A path from the rest of the input (refused commands skipped). */
static void read_path(reader *r, aa_path *p)
{
    while (r->n > 0 && p->n < 64) {
        unsigned op = byte(r) % 8;
        switch (op) {
        case 0:
            aa_path_move_to(p, number(r), number(r));
            break;
        case 1:
            aa_path_line_to(p, number(r), number(r));
            break;
        case 2: {
            /* a circle's arc from the pen: radius, start angle, sweep, turn */
            double rad = number(r), a = number(r), sw = number(r) * 6.5;
            unsigned f = byte(r);
            double s = f & 1 ? 1 : -1;
            if (!(fabs(rad) > 0) || !p->open)
                break;
            double cx = p->penx - rad * cos(a), cy = p->peny - s * rad * sin(a);
            double b = a + fmax(-2 * M_PI, fmin(2 * M_PI, sw));
            aa_path_arc_to(p, cx, cy, rad, 0, 0, s * rad, a, b, cx + rad * cos(b),
                           cy + s * rad * sin(b));
            break;
        }
        case 3: {
            /* an SVG arc with equal radii (a circle) or not (an ellipse,
             * whose offsets are offset curves) */
            double rx = number(r), ry = byte(r) & 1 ? rx : number(r), phi = number(r) * 90;
            unsigned f = byte(r);
            double x = number(r), y = number(r), c[8];
            if (!p->open)
                break;
            aa_arc_kind st;
            if (aa_arc_endpoints(p->penx, p->peny, rx, ry, phi, f & 1, (f >> 1) & 1, x, y, c, &st))
                break;
            if (st == AA_ARC_CURVE)
                aa_path_arc_to(p, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], x, y);
            else if (st == AA_ARC_LINE)
                aa_path_line_to(p, x, y);
            break;
        }
        case 4:
            aa_path_close(p);
            break;
        case 6: {
            double cx = number(r), cy = number(r);
            aa_path_quad_to(p, cx, cy, number(r), number(r));
            break;
        }
        case 7: {
            double c[6];
            for (int k = 0; k < 6; k++)
                c[k] = number(r);
            aa_path_cubic_to(p, c[0], c[1], c[2], c[3], c[4], c[5]);
            break;
        }
        default:
            if (p->open)
                aa_path_line_to(p, p->penx, p->peny);
            break;
        }
    }
}

static void arc_point(const double *c, double t, double *x, double *y)
{
    *x = c[0] + c[2] * cos(t) + c[4] * sin(t);
    *y = c[1] + c[3] * cos(t) + c[5] * sin(t);
}

/* Every contour a move, lines and arcs, a close, each of positive signed
 * area: (1/2) [sum over lines of a x b + over arcs of
 * c x (P(t1) - P(t0)) + (u x v)(t1 - t0)], about the contour's start.  The
 * rounding allowed for: each point is off by a few ulps of its magnitude
 * m, which moves the area by about that times the contour's size s, so
 * 1e-13 s (s + m) (a sliver far from the origin, a few ulps wide, has an
 * area of either sign at that level). */
static void check_outline(const aa_path *out)
{
    double sx = 0, sy = 0, px = 0, py = 0, a = 0, size = 0, mag = 0;
    int open = 0, offset = 0;
    for (size_t k = 0; k < out->n; k++) {
        const aa_path_seg *g = &out->seg[k];
        for (int i = 0; i < 15; i++)
            if (!isfinite(g->p[i]))
                abort();
        switch (g->op) {
        case AA_PATH_MOVE:
            if (open)
                abort();
            open = 1;
            sx = px = g->p[0], sy = py = g->p[1], a = 0, size = 0;
            mag = fmax(fabs(sx), fabs(sy));
            break;
        case AA_PATH_LINE:
            if (!open)
                abort();
            a += (px - sx) * (g->p[1] - sy) - (py - sy) * (g->p[0] - sx);
            px = g->p[0], py = g->p[1];
            size = fmax(size, fmax(fabs(px - sx), fabs(py - sy)));
            mag = fmax(mag, fmax(fabs(px), fabs(py)));
            break;
        case AA_PATH_ARC: {
            if (!open)
                abort();
            const double *c = g->p;
            double x0, y0, x1, y1;
            arc_point(c, c[6], &x0, &y0);
            arc_point(c, c[7], &x1, &y1);
            a += (px - sx) * (y0 - sy) - (py - sy) * (x0 - sx);
            a += (c[0] - sx) * (y1 - y0) - (c[1] - sy) * (x1 - x0) +
                 (c[2] * c[5] - c[3] * c[4]) * (c[7] - c[6]);
            a += (x1 - sx) * (c[9] - sy) - (y1 - sy) * (c[8] - sx);
            px = c[8], py = c[9];
            size = fmax(size, fabs(c[0] - sx) + fabs(c[1] - sy) + hypot(c[2], c[3]) +
                                  hypot(c[4], c[5]));
            mag = fmax(mag, fmax(fabs(c[0]), fabs(c[1])) + hypot(c[2], c[3]) + hypot(c[4], c[5]));
            break;
        }
        case AA_PATH_OFFSET: {
            /* a Bezier arc's offset or evolute: its ends are its points */
            if (!open)
                abort();
            const double *c = g->p;
            aa_offset_curve oc = {{0}, {1, 0, 0, 1, 0, 0}, c[8], c[9] != 0, (int)c[14]};
            memcpy(oc.b, c, sizeof oc.b);
            double x0, y0, x1, y1, scale = 0;
            aa_offset_point(&oc, c[10], &x0, &y0, NULL, NULL);
            aa_offset_point(&oc, c[11], &x1, &y1, NULL, NULL);
            scale = fabs(x0) + fabs(y0) + fabs(x1) + fabs(y1) + hypot(x1 - x0, y1 - y0);
            if (!(hypot(x0 - px, y0 - py) <= 1e-9 * scale) ||
                !(hypot(x1 - c[12], y1 - c[13]) <= 1e-9 * scale))
                abort();
            px = c[12], py = c[13];
            offset = 1;
            break;
        }
        case AA_PATH_CLOSE:
            if (!open)
                abort();
            open = 0;
            /* a contour with offset curves winds about each point a
             * non-negative number of times, its signed area not checked
             * here (it is the area of its region: positive where the
             * Jacobian is, negative where it is not) */
            if (!offset && !(a > -1e-13 * size * (size + mag)))
                abort();
            offset = 0;
            break;
        default:
            abort();
        }
    }
    if (open)
        abort();
}

int aa_fuzz_stroke(const uint8_t *data, size_t size)
{
    reader r = {data, size};
    check_arc_endpoints(&r);
    /* the style: width, join, cap, limit, up to 4 dash lengths, offset */
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    double dash[4];
    st.width = fabs(number(&r));
    unsigned f = byte(&r);
    /* miter, round, bevel; 3 picks SVG 2's miter-clip or arcs */
    st.join = (aa_line_join)(f % 4 == 3 ? 3 + (f / 60) % 2 : f % 4);
    st.cap = (aa_line_cap)((f / 4) % 3);
    st.miterlimit = 1 + (double)byte(&r) / 16;
    st.ndash = (f / 12) % 5;
    for (size_t i = 0; i < st.ndash; i++)
        dash[i] = fabs(number(&r));
    st.dash = st.ndash ? dash : NULL;
    st.dashoffset = number(&r);
    aa_path p = {0}, out = {0};
    read_path(&r, &p);
    /* something in out already, which a refusal must leave */
    aa_path_move_to(&out, 0, 0);
    aa_path_line_to(&out, 1, 0);
    aa_path_line_to(&out, 0, 1);
    aa_path_close(&out);
    size_t keep = out.n;
    int s = aa_stroke_outline(&p, &st, &out);
    if (s != AA_OK) {
        if (s != AA_EINVAL || !*aa_last_error() || out.n != keep)
            abort();
    } else {
        check_outline(&out);
        /* the outline fills into a scene, which checks it again */
        aa_scene *sc = aa_scene_new((aa_rgb){{0, 0, 0}});
        if (sc && (aa_scene_layer(sc, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) ||
                   aa_path_fill(&out, NULL, sc) || aa_scene_finish(sc)) &&
            aa_last_error()[0] && !strstr(aa_last_error(), "not finite") &&
            !strstr(aa_last_error(), "memory"))
            abort();
        aa_scene_free(sc);
    }
    aa_path_free(&p);
    aa_path_free(&out);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_stroke)
