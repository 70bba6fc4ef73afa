/*
 * test_gradient_crowd.c: the exact reference of gradient paint in crowded
 * windows (more than 48 pieces near a pixel: the sum over spans with the
 * crowd path's sweep for the meetings, harness/truth/truth.c) and on
 * offset curves (strokes of Bezier arcs).
 *
 * Known answers, derived here and not from the code under test:
 *  - two regular polygons of 80 and 70 sides, each smaller than a pixel
 *    and crossing each other, painted by linear gradients whose encoded
 *    values stay below the decoding's threshold 0.04045, where the
 *    decoding is e / 12.92, so that the linear colour is affine in x and
 *    y: under the box filter a pixel is the integral of an affine
 *    function over convex polygons, sum over the front polygon's part in
 *    the pixel (layers are added front to back) plus the back one's
 *    minus the back one's part under the front (each part clipped here
 *    by Sutherland and Hodgman's
 *    algorithm; the integral of a + b x + c y over a polygon from its
 *    area and first moments by the shoelace formulas);
 *  - the same with two equal stops against the flat colour's reference,
 *    which takes the crowd path proper (colour jumps piece by piece,
 *    truth_crowd.c: another derivation) under box, tent:r=1 and the cone;
 *  - a stroke of a cubic Bezier arc (a tube: butt caps, its curvature
 *    radius above the half width everywhere, so the stroke is the set of
 *    B(t) + s N(t), |s| <= h, and its outline the two offset curves B +-
 *    h N and the caps) painted by a linear gradient of three stops whose
 *    encoded values stay below the threshold (the colour piecewise affine
 *    in x and y, with a kink along the middle stop's line, which crosses
 *    the offset curves): under the box filter, single pixels by an outer
 *    GSL QAGS over the rows, cut at the pixel's edges, the offset curves'
 *    extremes in y (where B'y = 0: the offset's derivative is B' (1 - h
 *    k)), the caps' ends and where the outline crosses the pixel's sides
 *    and the middle stop's line, and an inner integral exact along each
 *    row: the outline's crossings found here by bisection in t on the
 *    offset curves written out from B, and the affine colour's integral
 *    over each part between them and the stop's line in closed form;
 *  - constant gradients (linear and radial, repeating: their stop lines
 *    and circles cross the stroke) against the flat colour's reference
 *    on that stroke, under box, tent:r=1 and the cone;
 *  - every pixel's bound within 1e-12.
 */
#include "core.h"
#include "path.h"
#include "support.h"
#include "truth.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#define W 4
#define H 4

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---- the polygons ---- */

#define NA 80
#define NB 70
#define MAXV 512

typedef struct poly {
    int n;
    double x[MAXV], y[MAXV];
} poly;

static poly regular(int n, double cx, double cy, double r, double phase)
{
    poly p;
    p.n = n;
    for (int k = 0; k < n; k++) {
        double a = phase + 2.0 * M_PI * k / n;
        p.x[k] = cx + r * cos(a), p.y[k] = cy + r * sin(a);
    }
    return p;
}

/* p clipped to the half plane left of the directed edge (ax, ay) -> (bx,
 * by) of a counter-clockwise convex polygon (Sutherland and Hodgman). */
static poly clip_edge(const poly *p, double ax, double ay, double bx, double by)
{
    poly o;
    o.n = 0;
    for (int k = 0; k < p->n; k++) {
        int j = (k + 1) % p->n;
        double sk = (bx - ax) * (p->y[k] - ay) - (by - ay) * (p->x[k] - ax);
        double sj = (bx - ax) * (p->y[j] - ay) - (by - ay) * (p->x[j] - ax);
        if (sk >= 0)
            o.x[o.n] = p->x[k], o.y[o.n++] = p->y[k];
        if ((sk >= 0) != (sj >= 0)) {
            double t = sk / (sk - sj);
            o.x[o.n] = p->x[k] + t * (p->x[j] - p->x[k]);
            o.y[o.n++] = p->y[k] + t * (p->y[j] - p->y[k]);
        }
    }
    return o;
}

static poly clip(const poly *p, const poly *by)
{
    poly o = *p;
    for (int k = 0; k < by->n && o.n; k++) {
        int j = (k + 1) % by->n;
        o = clip_edge(&o, by->x[k], by->y[k], by->x[j], by->y[j]);
    }
    return o;
}

/* The integral of a + b x + c y over p: a A + b Mx + c My, the area and
 * first moments by the shoelace formulas (long double). */
static long double affine_integral(const poly *p, double a, double b, double c)
{
    long double A = 0, Mx = 0, My = 0;
    for (int k = 0; k < p->n; k++) {
        int j = (k + 1) % p->n;
        long double cr = (long double)p->x[k] * p->y[j] - (long double)p->x[j] * p->y[k];
        A += cr;
        Mx += ((long double)p->x[k] + p->x[j]) * cr;
        My += ((long double)p->y[k] + p->y[j]) * cr;
    }
    A /= 2, Mx /= 6, My /= 6;
    return a * A + b * Mx + c * My;
}

/* Polygon p as a layer of s (pattern units). */
static void add_poly(aa_scene *s, const poly *p, aa_rgb col)
{
    assert_int_equal(aa_scene_layer(s, col, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, p->x[0] / W, p->y[0] / H), AA_OK);
    for (int k = 1; k < p->n; k++)
        assert_int_equal(aa_scene_line_to(s, p->x[k] / W, p->y[k] / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* A linear gradient in pixels from (x1, y1) to (x2, y2), stops st. */
static void set_linear(aa_scene *s, double x1, double y1, double x2, double y2,
                       const aa_gradient_stop *st)
{
    aa_gradient g = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {x1, y1, x2, y2, 0, 0},
                     {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, st};
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
}

/* Stop colours in linear light whose encoded values are e[0..2] (each
 * below 0.04045: the encoded value is 12.92 times the linear one). */
static aa_gradient_stop stop_enc(double offset, double r, double g, double b)
{
    aa_gradient_stop s = {offset, {{r / 12.92, g / 12.92, b / 12.92}}, 1.0};
    return s;
}

static const double A1[4] = {0.2, 0.3, 3.9, 3.4}, A2[4] = {3.5, 0.1, 0.6, 3.8};

static void reference(const aa_scene *s, const char *filter, aa_image *ref, aa_image *bound,
                      aa_truth_stats *stats)
{
    support_view v = {W, H, 0, 0, 0, filter, 1, 1, 0};
    support_reference(s, &v, ref, bound, stats);
}

/* The affine coefficients (a + b x + c y) of channel ch of the linear
 * colour of a gradient from P1 to P2 with stops s0 and s1 (t inside [0,
 * 1] over the polygons: no clamping). */
static void affine_of(const double P[4], const aa_gradient_stop *st, int ch, double *a,
                      double *b, double *c)
{
    double dx = P[2] - P[0], dy = P[3] - P[1], l2 = dx * dx + dy * dy;
    double c0 = st[0].colour.c[ch], c1 = st[1].colour.c[ch];
    /* t = ((x - x1) dx + (y - y1) dy) / l2; colour c0 + t (c1 - c0) */
    *b = (c1 - c0) * dx / l2, *c = (c1 - c0) * dy / l2;
    *a = c0 - (c1 - c0) * (P[0] * dx + P[1] * dy) / l2;
}

static void test_crowded_box(void **state)
{
    (void)state;
    poly pa = regular(NA, 1.5, 1.5, 0.42, 0.1), pb = regular(NB, 1.62, 1.58, 0.33, 0.37);
    const aa_gradient_stop s1[2] = {stop_enc(0, 0.0, 0.03, 0.02), stop_enc(1, 0.04, 0.0, 0.02)};
    const aa_gradient_stop s2[2] = {stop_enc(0, 0.035, 0.004, 0.0), stop_enc(1, 0.001, 0.039, 0.03)};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    add_poly(s, &pa, (aa_rgb){{0, 0, 0}});
    set_linear(s, A1[0], A1[1], A1[2], A1[3], s1);
    add_poly(s, &pb, (aa_rgb){{0, 0, 0}});
    set_linear(s, A2[0], A2[1], A2[2], A2[3], s2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, "box", &ref, &bound, &stats);
    print_message("crowded windows, box: %zu pixels integrated, largest bound %.2g\n",
                  stats.integrated, stats.max_bound);
    /* the polygons' edges: 150 pieces near pixel (1, 1) */
    {
        aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
        size_t np;
        aa_scene_pieces(placed, &np);
        assert_true(np >= NA + NB);
        aa_scene_free(placed);
    }
    assert_true(stats.max_bound <= 1e-12);
    double worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            poly sq = {4, {i, i + 1, i + 1, i}, {j, j, j + 1, j + 1}};
            poly qa = clip(&pa, &sq), qb = clip(&pb, &sq), qab = clip(&qb, &pa);
            for (int ch = 0; ch < 3; ch++) {
                double a, b, c, a2, b2, c2;
                affine_of(A1, s1, ch, &a, &b, &c);
                affine_of(A2, s2, ch, &a2, &b2, &c2);
                /* pa in front (added first) */
                long double want = affine_integral(&qa, a, b, c) +
                                   affine_integral(&qb, a2, b2, c2) -
                                   affine_integral(&qab, a2, b2, c2);
                double got = aa_pixel(&ref, i, j)[ch], bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - (double)want));
                if (!(fabs(got - (double)want) <= bd + 1e-16))
                    fail_msg("pixel (%d, %d) channel %d: %.17g, the polygons' closed form "
                             "%.17Lg (bound %.3g)",
                             i, j, ch, got, want, bd);
            }
        }
    print_message("crowded windows, box: largest difference from the closed form %.2g\n", worst);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* Two equal stops against the flat colours, which take the crowd path. */
static void test_crowded_constant(void **state)
{
    (void)state;
    poly pa = regular(NA, 1.5, 1.5, 0.42, 0.1), pb = regular(NB, 1.62, 1.58, 0.33, 0.37);
    const aa_rgb ca = {{0.7, 0.2, 0.05}}, cb = {{0.1, 0.5, 0.9}};
    const aa_gradient_stop sa[2] = {{0, ca, 1.0}, {1, ca, 1.0}}, sb[2] = {{0, cb, 1.0}, {1, cb, 1.0}};
    aa_scene *g = aa_scene_new((aa_rgb){{0.2, 0.2, 0.2}}), *flat = aa_scene_new((aa_rgb){{0.2, 0.2, 0.2}});
    add_poly(g, &pa, ca);
    set_linear(g, A1[0], A1[1], A1[2], A1[3], sa);
    add_poly(g, &pb, cb);
    set_linear(g, A2[0], A2[1], A2[2], A2[3], sb);
    add_poly(flat, &pa, ca);
    add_poly(flat, &pb, cb);
    assert_int_equal(aa_scene_finish(g), AA_OK);
    assert_int_equal(aa_scene_finish(flat), AA_OK);
    static const char *const filters[] = {"box", "tent:r=1", "cone:r=1"};
    for (int k = 0; k < 3; k++) {
        aa_image rg, rf, bg, bf;
        aa_truth_stats sg, sf;
        reference(g, filters[k], &rg, &bg, &sg);
        reference(flat, filters[k], &rf, &bf, &sf);
        double worst = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                for (int ch = 0; ch < 3; ch++)
                    worst = fmax(worst, fabs(aa_pixel(&rg, i, j)[ch] - aa_pixel(&rf, i, j)[ch]));
        print_message("%-9s crowded: constant gradients against the flat colours (%zu pixels "
                      "crowded there): %.2g (bounds %.2g, %.2g)\n",
                      filters[k], sf.crowded, worst, sg.max_bound, sf.max_bound);
        assert_true(sf.crowded > 0); /* the flat colours did take the crowd path */
        assert_true(sg.max_bound <= 1e-12);
        if (!(worst <= sg.max_bound + sf.max_bound + 1e-15))
            fail_msg("%s: constant gradients %.3g off the flat colours in crowded windows",
                     filters[k], worst);
        aa_image_free(&rg);
        aa_image_free(&rf);
        aa_image_free(&bg);
        aa_image_free(&bf);
    }
    aa_scene_free(g);
    aa_scene_free(flat);
}

/* ---- strokes of curves (offset pieces) ---- */

#define SW 8
#define SH 6

/* The tube: the cubic's control points (pixels), half width h. */
static const double TC[8] = {0.8, 4.9, 2.6, 0.4, 5.2, 5.6, 7.3, 1.2};
static const double TH = 0.45;

static void bez(double t, double *x, double *y, double *dx, double *dy)
{
    double u = 1 - t;
    *x = u * u * u * TC[0] + 3 * u * u * t * TC[2] + 3 * u * t * t * TC[4] + t * t * t * TC[6];
    *y = u * u * u * TC[1] + 3 * u * u * t * TC[3] + 3 * u * t * t * TC[5] + t * t * t * TC[7];
    *dx = 3 * (u * u * (TC[2] - TC[0]) + 2 * u * t * (TC[4] - TC[2]) + t * t * (TC[6] - TC[4]));
    *dy = 3 * (u * u * (TC[3] - TC[1]) + 2 * u * t * (TC[5] - TC[3]) + t * t * (TC[7] - TC[5]));
}

/* The offset curve B + side h N, N = (-B'y, B'x) / |B'|. */
static void off(int side, double t, double *x, double *y)
{
    double bx, by, dx, dy;
    bez(t, &bx, &by, &dx, &dy);
    double l = hypot(dx, dy);
    *x = bx - side * TH * dy / l, *y = by + side * TH * dx / l;
}

/* The outline as four curves in a parameter u in [0, 1]: the offsets
 * (sides +1, -1) and the caps at t = 0 and 1 (segments between them). */
static void outline(int c, double u, double *x, double *y)
{
    if (c < 2) {
        off(c ? -1 : 1, u, x, y);
        return;
    }
    double t = c == 2 ? 0.0 : 1.0, xa, ya, xb, yb;
    off(1, t, &xa, &ya);
    off(-1, t, &xb, &yb);
    *x = xa + u * (xb - xa), *y = ya + u * (yb - ya);
}

/* The u where ax x + ay y - at along curve c changes sign; count into out
 * (at most cap).  On an offset curve the derivative of (ax, ay).P is
 * (ax, ay).B' (1 - h k), so between the roots of the quadratic (ax,
 * ay).B'(t) (and the ends) it is monotone: each part holds one root at
 * most, found by bisection; the caps are segments. */
static int roots_dir(int c, double ax, double ay, double at, double *out, int cap)
{
    double cut[4], x, y;
    int nc = 0, n = 0;
    cut[nc++] = 0;
    if (c < 2) {
        double d0 = ax * (TC[2] - TC[0]) + ay * (TC[3] - TC[1]);
        double d1 = ax * (TC[4] - TC[2]) + ay * (TC[5] - TC[3]);
        double d2 = ax * (TC[6] - TC[4]) + ay * (TC[7] - TC[5]);
        double qa = d0 - 2 * d1 + d2, qb = 2 * (d1 - d0), qc = d0, r[2];
        int nr = 0;
        if (qa != 0) {
            double disc = qb * qb - 4 * qa * qc;
            if (disc > 0) {
                r[0] = (-qb - sqrt(disc)) / (2 * qa), r[1] = (-qb + sqrt(disc)) / (2 * qa);
                if (r[0] > r[1]) {
                    double t = r[0];
                    r[0] = r[1], r[1] = t;
                }
                nr = 2;
            }
        } else if (qb != 0)
            r[0] = -qc / qb, nr = 1;
        for (int k = 0; k < nr; k++)
            if (r[k] > 0 && r[k] < 1)
                cut[nc++] = r[k];
    }
    cut[nc++] = 1;
    for (int k = 0; k + 1 < nc && n < cap; k++) {
        double a = cut[k], b = cut[k + 1];
        outline(c, a, &x, &y);
        double fa = ax * x + ay * y - at;
        outline(c, b, &x, &y);
        double fb = ax * x + ay * y - at;
        if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0)))
            continue;
        for (int it = 0; it < 200; it++) {
            double m = 0.5 * (a + b);
            if (!(m > a && m < b))
                break;
            outline(c, m, &x, &y);
            double fm = ax * x + ay * y - at;
            if ((fm < 0) == (fa < 0))
                a = m, fa = fm;
            else
                b = m;
        }
        out[n++] = 0.5 * (a + b);
    }
    return n;
}

static int roots(int c, int coord, double at, double *out, int cap)
{
    return roots_dir(c, coord ? 0.0 : 1.0, coord ? 1.0 : 0.0, at, out, cap);
}

/* The gradient: t = gx x + gy y + g0 (pixels), stops 0, 0.5, 1 with
 * encoded values ge[k][ch] below the threshold. */
static const double GP[4] = {0.5, 0.7, 7.4, 5.1};
static const double ge[3][3] = {{0.0, 0.03, 0.012}, {0.04, 0.002, 0.03}, {0.01, 0.035, 0.0}};

static double grad_t(double x, double y)
{
    double dx = GP[2] - GP[0], dy = GP[3] - GP[1];
    return ((x - GP[0]) * dx + (y - GP[1]) * dy) / (dx * dx + dy * dy);
}

static double lin_colour(int ch, double x, double y)
{
    double t = grad_t(x, y);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double e = t < 0.5 ? ge[0][ch] + 2 * t * (ge[1][ch] - ge[0][ch])
                       : ge[1][ch] + 2 * (t - 0.5) * (ge[2][ch] - ge[1][ch]);
    return e / 12.92;
}

/* The x where row y meets the line t = tau. */
static double tau_x(double tau, double y)
{
    double dx = GP[2] - GP[0], dy = GP[3] - GP[1];
    return GP[0] + (tau * (dx * dx + dy * dy) - (y - GP[1]) * dy) / dx;
}

typedef struct row_ctx {
    int i, ch;
} row_ctx;

/* The row y's integral over [i, i + 1] of the colour inside the stroke:
 * the outline's crossings in order (inside between the first and second,
 * third and fourth...), each part cut at the stops' lines, the affine
 * colour's integral its length times its value at the middle. */
static double stroke_row(double y, void *v)
{
    const row_ctx *r = v;
    double xs[64], us[32];
    int nx = 0;
    for (int c = 0; c < 4; c++) {
        int n = roots(c, 1, y, us, 32);
        for (int k = 0; k < n && nx < 64; k++) {
            double x, yy;
            outline(c, us[k], &x, &yy);
            xs[nx++] = x;
        }
    }
    qsort(xs, (size_t)nx, sizeof *xs, cmp_dbl);
    assert_true(nx % 2 == 0);
    double sum = 0;
    for (int k = 0; k + 1 < nx; k += 2) {
        double a = fmax(xs[k], r->i), b = fmin(xs[k + 1], r->i + 1.0), cut[8];
        if (!(b > a))
            continue;
        int n = 0;
        cut[n++] = a;
        for (int q = 0; q < 3; q++) {
            double x = tau_x(0.5 * q, y);
            if (x > a && x < b)
                cut[n++] = x;
        }
        cut[n++] = b;
        qsort(cut, (size_t)n, sizeof *cut, cmp_dbl);
        for (int q = 0; q + 1 < n; q++)
            sum += (cut[q + 1] - cut[q]) * lin_colour(r->ch, 0.5 * (cut[q] + cut[q + 1]), y);
    }
    return sum;
}

/* Pixel (i, j), channel ch, by the outer QAGS between the cuts. */
static double stroke_pixel(int i, int j, int ch)
{
    double cut[256], us[32], x, y;
    int n = 0;
    cut[n++] = j, cut[n++] = j + 1.0;
    /* the offsets' extremes in y: B'y = 0, a quadratic in t */
    double a0 = TC[3] - TC[1], a1 = TC[5] - TC[3], a2 = TC[7] - TC[5];
    double qa = a0 - 2 * a1 + a2, qb = 2 * (a1 - a0), qc = a0, disc = qb * qb - 4 * qa * qc;
    if (disc > 0)
        for (int sg = -1; sg <= 1; sg += 2) {
            double t = (-qb + sg * sqrt(disc)) / (2 * qa);
            if (t > 0 && t < 1)
                for (int c = 0; c < 2; c++)
                    outline(c, t, &x, &y), cut[n++] = y;
        }
    for (int c = 2; c < 4; c++) /* the caps' ends */
        for (int e = 0; e < 2; e++)
            outline(c, e, &x, &y), cut[n++] = y;
    for (int c = 0; c < 4; c++) {
        /* the pixel's sides */
        for (int side = 0; side < 2; side++) {
            int m = roots(c, 0, i + side, us, 32);
            for (int k = 0; k < m; k++)
                outline(c, us[k], &x, &y), cut[n++] = y;
        }
    }
    /* the stops' lines against the outline: t = ((x, y) - P1).(P2 - P1) /
     * |P2 - P1|^2 = tau */
    {
        double dx = GP[2] - GP[0], dy = GP[3] - GP[1], l2 = dx * dx + dy * dy;
        for (int c = 0; c < 4; c++)
            for (int q = 0; q < 3; q++) {
                int m = roots_dir(c, dx / l2, dy / l2, 0.5 * q + (GP[0] * dx + GP[1] * dy) / l2,
                                  us, 32);
                for (int k = 0; k < m; k++)
                    outline(c, us[k], &x, &y), cut[n++] = y;
            }
    }
    qsort(cut, (size_t)n, sizeof *cut, cmp_dbl);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    row_ctx r = {i, ch};
    gsl_function F = {stroke_row, &r};
    double sum = 0, res, err;
    for (int k = 0; k + 1 < n; k++) {
        double a = fmax(cut[k], j), b = fmin(cut[k + 1], j + 1.0);
        if (!(b > a))
            continue;
        gsl_integration_qags(&F, a, b, 1e-17, 1e-14, 1000, ws, &res, &err);
        sum += res;
    }
    gsl_integration_workspace_free(ws);
    return sum;
}

/* The tube's outline as a layer of a new scene (pixels mapped to pattern
 * units), painted by g (NULL: the flat colour col); *noff its offset
 * pieces. */
static aa_scene *tube_scene(const aa_gradient *g, aa_rgb col, size_t *noff)
{
    aa_path in = {0}, out = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 2 * TH;
    assert_int_equal(aa_path_move_to(&in, TC[0], TC[1]), AA_OK);
    assert_int_equal(aa_path_cubic_to(&in, TC[2], TC[3], TC[4], TC[5], TC[6], TC[7]), AA_OK);
    assert_int_equal(aa_stroke_outline(&in, &st, &out), AA_OK);
    const double m[6] = {1.0 / SW, 0, 0, 1.0 / SH, 0, 0};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, col, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_path_fill(&out, m, s), AA_OK);
    if (g)
        assert_int_equal(aa_scene_set_gradient(s, g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    *noff = 0;
    for (size_t k = 0; k < n; k++)
        *noff += pc[k].kind == AA_PIECE_OFFSET;
    aa_path_free(&in);
    aa_path_free(&out);
    return s;
}

static void test_stroke_box(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    /* the curvature radius above the half width (a tube) */
    for (int k = 0; k <= 2000; k++) {
        double t = k / 2000.0, u = 1 - t, x, y, dx, dy;
        bez(t, &x, &y, &dx, &dy);
        double ddx = 6 * (u * (TC[4] - 2 * TC[2] + TC[0]) + t * (TC[6] - 2 * TC[4] + TC[2]));
        double ddy = 6 * (u * (TC[5] - 2 * TC[3] + TC[1]) + t * (TC[7] - 2 * TC[5] + TC[3]));
        double kappa = fabs(dx * ddy - dy * ddx) / pow(hypot(dx, dy), 3);
        assert_true(kappa * TH < 0.95);
    }
    aa_gradient_stop st[3];
    for (int k = 0; k < 3; k++) {
        st[k].offset = 0.5 * k, st[k].opacity = 1;
        for (int ch = 0; ch < 3; ch++)
            st[k].colour.c[ch] = ge[k][ch] / 12.92;
    }
    aa_gradient g = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {GP[0], GP[1], GP[2], GP[3], 0, 0},
                     {1.0 / SW, 0, 0, 1.0 / SH, 0, 0}, 3, st};
    size_t noff;
    aa_scene *s = tube_scene(&g, (aa_rgb){{0, 0, 0}}, &noff);
    assert_true(noff > 0);
    aa_image ref, bound;
    aa_truth_stats stats;
    support_view v = {SW, SH, 0, 0, 0, "box", 1, 1, 0};
    support_reference(s, &v, &ref, &bound, &stats);
    assert_true(stats.max_bound <= 1e-12);
    double worst = 0;
    int checked = 0;
    for (int j = 0; j < SH; j++)
        for (int i = 0; i < SW; i++)
            for (int ch = 0; ch < 3; ch++) {
                double want = stroke_pixel(i, j, ch), got = aa_pixel(&ref, i, j)[ch];
                double bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - want));
                checked++;
                if (!(fabs(got - want) <= bd + 1e-15))
                    fail_msg("stroke: pixel (%d, %d) channel %d is %.17g, the rows' integral "
                             "%.17g (bound %.3g)",
                             i, j, ch, got, want, bd);
            }
    print_message("stroke of a cubic (%zu offset pieces) under a linear gradient, box: %d "
                  "values, largest difference from the rows' integral %.2g, largest bound "
                  "%.2g\n",
                  noff, checked, worst, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

static void test_stroke_constant(void **state)
{
    (void)state;
    const aa_rgb col = {{0.65, 0.3, 0.1}};
    const aa_gradient_stop same[2] = {{0, col, 1.0}, {1, col, 1.0}};
    size_t noff;
    aa_scene *flat = tube_scene(NULL, col, &noff);
    static const char *const filters[] = {"box", "tent:r=1", "cone:r=1"};
    for (int radial = 0; radial < 2; radial++) {
        aa_gradient g = {radial ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                         {0}, {1.0 / SW, 0, 0, 1.0 / SH, 0, 0}, 2, same};
        static const double at[2][6] = {{1.0, 1.5, 2.2, 2.1, 0, 0}, {4.1, 3.0, 1.3, 3.6, 2.7, 0.2}};
        memcpy(g.p, at[radial], sizeof g.p);
        aa_scene *s = tube_scene(&g, col, &noff);
        for (int k = 0; k < 3; k++) {
            support_view v = {SW, SH, 0, 0, 0, filters[k], 1, 1, 0};
            aa_image rg, rf, bg, bf;
            aa_truth_stats sg, sf;
            support_reference(s, &v, &rg, &bg, &sg);
            support_reference(flat, &v, &rf, &bf, &sf);
            double worst = 0;
            for (int j = 0; j < SH; j++)
                for (int i = 0; i < SW; i++)
                    for (int ch = 0; ch < 3; ch++)
                        worst = fmax(worst, fabs(aa_pixel(&rg, i, j)[ch] - aa_pixel(&rf, i, j)[ch]));
            print_message("%-9s stroke: a constant %s gradient against the flat colour: %.2g "
                          "(bounds %.2g, %.2g)\n",
                          filters[k], radial ? "radial" : "linear", worst, sg.max_bound,
                          sf.max_bound);
            assert_true(sg.max_bound <= 1e-12);
            if (!(worst <= sg.max_bound + sf.max_bound + 1e-15))
                fail_msg("%s: a constant %s gradient on a stroke %.3g off the flat colour",
                         filters[k], radial ? "radial" : "linear", worst);
            aa_image_free(&rg);
            aa_image_free(&rf);
            aa_image_free(&bg);
            aa_image_free(&bf);
        }
        aa_scene_free(s);
    }
    aa_scene_free(flat);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crowded_box),
        cmocka_unit_test(test_crowded_constant),
        cmocka_unit_test(test_stroke_box),
        cmocka_unit_test(test_stroke_constant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
