/*
 * test_export_arc.c: elliptical arcs written as SVG A commands
 * (harness/core/svg.c, aa_scene_svg).
 *
 * Known answer, independent of the writer: the SVG implementation notes'
 * endpoint-to-centre conversion (SVG 1.1 F.6.5, written out here from the
 * notes) turns each A command back into a centre, radii, a start angle and
 * a signed sweep; every point of the scene's arc, c + u cos t + v sin t at
 * several t of the piece the command covers, must lie on that ellipse
 * (within 1e-12 of its size), at its place along the swept angle, and
 * the centre must be the arc's.  The place: with M = [u v] = R(phi)
 * diag(p, q) R(theta0) (its singular value decomposition), the arc's point
 * at t is c + R(phi) diag(p, q) (cos(t + theta0), sin(t + theta0)), so the
 * SVG ellipse's own angle is t + theta0 (or its negative when q < 0): the
 * points of t evenly spaced over the piece are evenly spaced over the
 * command's sweep, which is as wide as the piece.  The pieces: an arc of |t1 - t0| is written as
 * ceil(|t1 - t0| / 90 degrees) commands of equal angle, none large, ending
 * at the edge's own end exactly.
 */
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 200
#define H 160

/* A scene of arcs in pattern units: a circle of two halves, a slanted
 * ellipse in one whole turn with t decreasing, a mirrored ellipse
 * (det [u v] < 0) in three arcs, an ellipse along the axes whose u points
 * to -x (a turn), and a pie slice (an arc of 250 degrees and two lines). */
static aa_scene *arc_scene(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_EVENODD), AA_OK);
    const struct {
        double c[6];
        double t[4];
        int n;
    } ells[] = {
        {{0.25, 0.25, 0.2, 0.0, 0.0, 0.2}, {0.0, M_PI, 2 * M_PI}, 2},
        {{0.7, 0.3, 0.2, 0.07, 0.04, 0.15}, {0.3, 0.3 - 2 * M_PI}, 1},
        {{0.3, 0.7, 0.18, 0.02, 0.05, -0.15}, {-1.0, 0.5, 2.0, 2 * M_PI - 1.0}, 3},
        {{0.5, 0.5, -0.08, 0.0, 0.0, 0.06}, {0.4, 0.4 + 2 * M_PI}, 1},
    };
    for (size_t k = 0; k < sizeof ells / sizeof ells[0]; k++) {
        const double *c = ells[k].c, *t = ells[k].t;
        assert_int_equal(aa_scene_move_to(s, c[0] + c[2] * cos(t[0]) + c[4] * sin(t[0]),
                                          c[1] + c[3] * cos(t[0]) + c[5] * sin(t[0])),
                         AA_OK);
        for (int q = 0; q < ells[k].n; q++) {
            double tt = q + 1 == ells[k].n ? t[0] : t[q + 1];
            int st = aa_scene_arc_to(s, c[0], c[1], c[2], c[3], c[4], c[5], t[q], t[q + 1],
                                     c[0] + c[2] * cos(tt) + c[4] * sin(tt),
                                     c[1] + c[3] * cos(tt) + c[5] * sin(tt));
            if (st)
                fail_msg("aa_scene_arc_to: %s", aa_last_error());
        }
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    /* the pie: centre, arc of 250 degrees of a circle of radius 0.15 */
    double px = 0.72, py = 0.72, r = 0.15, a0 = 0.2, a1 = 0.2 + 250 * M_PI / 180;
    assert_int_equal(aa_scene_move_to(s, px, py), AA_OK);
    assert_int_equal(aa_scene_line_to(s, px + r * cos(a0), py + r * sin(a0)), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, px, py, r, 0, 0, r, a0, a1, px + r * cos(a1),
                                     py + r * sin(a1)),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* ---- the path data's tokens ---- */

typedef struct reader {
    const char *p;
} reader;

static char next_command(reader *r)
{
    while (*r->p == ' ' || *r->p == '\n')
        r->p++;
    return *r->p ? *r->p++ : '\0';
}

static double next_number(reader *r)
{
    char *end;
    double v = strtod(r->p, &end);
    if (end == r->p)
        fail_msg("a number expected at \"%.20s\"", r->p);
    r->p = end;
    return v;
}

/* ---- SVG 1.1 F.6.5: endpoint to centre parametrisation ---- */

typedef struct svg_arc {
    double cx, cy, rx, ry, phi; /* phi in radians */
    double theta1, dtheta;      /* start angle, signed sweep */
} svg_arc;

/* The angle from (ux, uy) to (vx, vy), in (-pi, pi]. */
static double angle_between(double ux, double uy, double vx, double vy)
{
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

static svg_arc endpoint_to_centre(double x1, double y1, double rx, double ry, double phi_deg,
                                  int fa, int fs, double x2, double y2)
{
    svg_arc a;
    double phi = phi_deg * M_PI / 180, cp = cos(phi), sp = sin(phi);
    double hx = (x1 - x2) / 2, hy = (y1 - y2) / 2;
    double x1p = cp * hx + sp * hy, y1p = -sp * hx + cp * hy;
    rx = fabs(rx), ry = fabs(ry);
    double lambda = x1p * x1p / (rx * rx) + y1p * y1p / (ry * ry);
    if (lambda > 1)
        rx *= sqrt(lambda), ry *= sqrt(lambda);
    double num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p;
    double den = rx * rx * y1p * y1p + ry * ry * x1p * x1p;
    double co = sqrt(fmax(0.0, num / den)) * (fa != fs ? 1 : -1);
    double cxp = co * rx * y1p / ry, cyp = -co * ry * x1p / rx;
    a.cx = cp * cxp - sp * cyp + (x1 + x2) / 2;
    a.cy = sp * cxp + cp * cyp + (y1 + y2) / 2;
    a.rx = rx, a.ry = ry, a.phi = phi;
    a.theta1 = angle_between(1, 0, (x1p - cxp) / rx, (y1p - cyp) / ry);
    double d = angle_between((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx,
                             (-y1p - cyp) / ry);
    if (!fs && d > 0)
        d -= 2 * M_PI;
    else if (fs && d < 0)
        d += 2 * M_PI;
    a.dtheta = d;
    return a;
}

/* Point (x, y) on the SVG arc: its ellipse's "radius" (1 on it) and its
 * angle's place along the sweep (0 at the start, 1 at the end). */
static void on_arc(const svg_arc *a, double x, double y, double *radius, double *along)
{
    double dx = x - a->cx, dy = y - a->cy, cp = cos(a->phi), sp = sin(a->phi);
    double X = (cp * dx + sp * dy) / a->rx, Y = (-sp * dx + cp * dy) / a->ry;
    *radius = hypot(X, Y);
    double rel = angle_between(cos(a->theta1), sin(a->theta1), X, Y);
    /* the angle from the start, measured the sweep's way, in [0, 2 pi) */
    if (a->dtheta < 0)
        rel = -rel;
    if (rel < 0)
        rel += 2 * M_PI;
    *along = rel / fabs(a->dtheta);
}

/* Edge e (placed, quad == 3) against the A commands that follow in r,
 * from the pen (x, y). */
static void check_arc_edge(reader *r, const aa_edge *e, double *x, double *y, int *commands)
{
    double dt = e->t1 - e->t0;
    int n = (int)ceil(fabs(dt) / (M_PI / 2) - 1e-9);
    double size = hypot(e->ux, e->uy) + hypot(e->vx, e->vy), tol = 1e-12 * size;
    for (int k = 0; k < n; k++) {
        char c = next_command(r);
        if (c != 'A')
            fail_msg("piece %d of %d of an arc: command %c, not A", k + 1, n, c);
        double rx = next_number(r), ry = next_number(r), phi = next_number(r);
        int fa = (int)next_number(r), fs = (int)next_number(r);
        double x2 = next_number(r), y2 = next_number(r);
        assert_int_equal(fa, 0); /* pieces of at most 90 degrees */
        svg_arc a = endpoint_to_centre(*x, *y, rx, ry, phi, fa, fs, x2, y2);
        if (!(fabs(a.cx - e->cx) <= tol && fabs(a.cy - e->cy) <= tol))
            fail_msg("centre (%.17g, %.17g), the arc's (%.17g, %.17g)", a.cx, a.cy, e->cx,
                     e->cy);
        /* the piece covers t from ta to tb; sample it inside and at its ends */
        double ta = e->t0 + k * dt / n, tb = e->t0 + (k + 1) * dt / n;
        for (int s = 0; s <= 8; s++) {
            double t = ta + (tb - ta) * s / 8.0;
            double px = e->cx + e->ux * cos(t) + e->vx * sin(t);
            double py = e->cy + e->uy * cos(t) + e->vy * sin(t);
            double radius, along;
            on_arc(&a, px, py, &radius, &along);
            if (!(fabs(radius - 1) <= 1e-12))
                fail_msg("t = %.17g: off the A command's ellipse by %.3e of its radius", t,
                         radius - 1);
            double want = s / 8.0;
            if (along > 1.5) /* the start, reached from just below 0 */
                along -= 2 * M_PI / fabs(a.dtheta);
            if (!(fabs(along - want) <= 1e-9))
                fail_msg("t = %.17g: at %.6f of the A command's sweep, not near %.6f", t,
                         along, want);
            if (s > 0 && s < 8 && !(along > 0 && along < 1))
                fail_msg("t = %.17g: outside the A command's sweep (%.6f)", t, along);
        }
        /* the sweep is the piece's angle */
        if (!(fabs(fabs(a.dtheta) - fabs(tb - ta)) <= 1e-12))
            fail_msg("the A command sweeps %.17g, the piece %.17g", a.dtheta, tb - ta);
        *x = x2, *y = y2;
        (*commands)++;
    }
    assert_true(*x == e->x1 && *y == e->y1);
}

static void test_export_arcs(void **state)
{
    (void)state;
    aa_scene *s = arc_scene();
    aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
    assert_non_null(placed);
    char *text;
    size_t len;
    assert_int_equal(aa_scene_svg(placed, W, H, AA_SVG_MASK, NULL, &text, &len), AA_OK);
    const char *d = strstr(text, " d=\"");
    assert_non_null(d);
    reader r = {d + 4};
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(placed, &ne);
    const size_t *start = aa_scene_contours(placed, &nc);
    int arcs = 0, commands = 0;
    for (size_t c = 0; c < nc; c++) {
        assert_int_equal(next_command(&r), 'M');
        double x = next_number(&r), y = next_number(&r);
        assert_true(x == e[start[c]].x0 && y == e[start[c]].y0);
        for (size_t k = start[c]; k < start[c + 1]; k++) {
            if (e[k].quad == 3) {
                check_arc_edge(&r, &e[k], &x, &y, &commands);
                arcs++;
                continue;
            }
            assert_int_equal(e[k].quad, 0);
            assert_int_equal(next_command(&r), 'L');
            x = next_number(&r), y = next_number(&r);
            assert_true(x == e[k].x1 && y == e[k].y1);
        }
        assert_int_equal(next_command(&r), 'Z');
    }
    assert_int_equal(next_command(&r), '"');
    /* 2 + 1 + 3 + 1 + 1 arcs, in pieces of at most 90 degrees: 2 x 2 (half
     * turns), 4 (a turn), 1 + 1 + 3 (1.5, 1.5 and 3.28 radians), 4 (a
     * turn), 3 (250 degrees) */
    assert_int_equal(arcs, 8);
    assert_int_equal(commands, 4 + 4 + 5 + 4 + 3);
    print_message("%d arcs written as %d A commands, each on its arc to 1e-12\n", arcs,
                  commands);
    free(text);
    aa_scene_free(placed);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_export_arcs))
