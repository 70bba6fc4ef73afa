/*
 * test_gradient_filter.c: the exact reference of gradient paint under the
 * separable filters other than the box (harness/truth/truth.c, "the other
 * separable filters"): tent, gauss, bspline (orders 2 and 3), mitchell,
 * catrom, lanczos.
 *
 * Known answers, derived here and not from the code under test:
 *  - a gradient that varies along x only, over the whole plane: the 2-D
 *    weight is w(u) w(v) and w integrates to 1, so each pixel is the 1-D
 *    integral of w(x - uc) dec(t(x)).  For a black-to-white ramp from x =
 *    a to x = b (encoded value t, clamped) and a polynomial filter, that
 *    is a closed form: on each piece between the filter's knots, the ramp's
 *    ends and the decoding's threshold T = 0.04045, the weight is a
 *    polynomial p(x - uc), and with v = (x - a)/(b - a)
 *        below T:  int p dec = (b - a) int p(a - uc + (b - a) v) v / 12.92 dv,
 *        above T:  u = (v + 0.055)/1.055, x = a + (b - a)(1.055 u - 0.055),
 *                  int p dec = 1.055 (b - a) sum_j r_j u^(j + 3.4) / (j + 3.4),
 *    r_j the coefficients of p in u (integration of (a x + b)^2.4 against a
 *    polynomial), the weights written here from their definitions
 *    (Mitchell and Netravali 1988; the B-splines; the tent), evaluated in
 *    long double.  Lanczos and the Gaussian, whose pieces are not
 *    polynomials: the same 1-D integral by GSL's QAG between the same cuts
 *    (Lanczos normalised by its own QAG integral);
 *  - a constant gradient (two equal stops) is the flat colour: its
 *    reference equals the flat-colour reference (cdf differences, a
 *    different path; the Gaussian's by QAG, as the gradient's, not by its
 *    fixed rule) to rounding, 1e-15, plus for the Gaussian its mass outside
 *    the window (the flat colour's pixels clear of edges are its colour);
 *  - an oblique black-to-white linear gradient on a rectangle over a grey
 *    background, under tent:r=1 and the cubic B-spline: single pixels by
 *    GSL's adaptive quadrature in two dimensions (outer rows, inner along
 *    the row), the filter's weight written out here and the picture in
 *    tests/gradient_oracle.c, cut at the filter's knots, the rectangle's
 *    sides and the lines where t passes 0, 1 and the threshold;
 *  - a centred radial gradient black to white over the whole plane under
 *    tent:r=1: single pixels by the same 2-D quadrature in the picture's
 *    own polar form (t = distance / r), cut at the circles t = 1 and t =
 *    T's chords and tangent rows, the centre's row and column and the
 *    filter's knots.
 * The radial filters: tests/test_gradient_radial_filter.c.
 */
#include "core.h"
#include "gradient_oracle.h"
#include "support.h"
#include "tier.h"
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

#define W 16
#define H 12

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return 0;
}

/* ---- the filters, from their definitions (patterns/README.md, "Filters") ---- */

enum { F_TENT, F_BSPLINE2, F_BSPLINE3, F_MITCHELL, F_CATROM, F_LANCZOS2, F_LANCZOS3, F_GAUSS };

typedef struct filt {
    int kind;
    const char *spec;
    double R;         /* support (the Gaussian: where the test integrates to) */
    double knots[8];  /* where a polynomial piece ends */
    int nknots;
    double M;         /* Lanczos: its integral */
} filt;

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) the two cases that take every filter on one scene run
 * a declared subset: the ramp along x and the constant radial gradient
 * take bspline:order=2, mitchell, lanczos:a=2 and gauss:s=0.5 (the filters
 * of odd n), the constant linear gradient and the flat colour every
 * filter, so that each filter meets a linear gradient and each kind of
 * filter (B-spline, cubic, Lanczos, Gaussian) a radial one.  The
 * sanitizers find memory and undefined-behaviour errors along the paths
 * taken, and another filter on the same scene takes the same paths with
 * other numbers (tests/README.md, "Tiers", says how that was checked); the
 * plain build runs every case. */

/* Whether the ramp along x and the constant radial gradient leave filter
 * n out (the subset above). */
static int san_skips(int n)
{
    return SAN_SUBSET && n % 2 == 0;
}

/* A polynomial filter's piece containing t (knots[k] <= t <= knots[k + 1])
 * as coefficients c[0..3] of t. */
static void piece_poly(const filt *f, double t, long double c[4])
{
    double a = fabs(t), B = 1.0 / 3, C = 1.0 / 3;
    long double q[4] = {0, 0, 0, 0}; /* in |t| */
    if (f->kind == F_TENT) {
        if (a < 1)
            q[0] = 1, q[1] = -1;
    } else if (f->kind == F_BSPLINE2) {
        if (a < 0.5)
            q[0] = 0.75L, q[2] = -1;
        else if (a < 1.5) /* (3/2 - a)^2 / 2 */
            q[0] = 1.125L, q[1] = -1.5L, q[2] = 0.5L;
    } else if (f->kind == F_BSPLINE3) {
        if (a < 1)
            q[0] = 4.0L / 6, q[2] = -1, q[3] = 0.5L;
        else if (a < 2) /* (2 - a)^3 / 6 */
            q[0] = 8.0L / 6, q[1] = -2, q[2] = 1, q[3] = -1.0L / 6;
    } else {
        if (f->kind == F_CATROM)
            B = 0, C = 0.5;
        long double Bl = B, Cl = C;
        if (a < 1)
            q[0] = (6 - 2 * Bl) / 6, q[2] = (-18 + 12 * Bl + 6 * Cl) / 6,
            q[3] = (12 - 9 * Bl - 6 * Cl) / 6;
        else if (a < 2)
            q[0] = (8 * Bl + 24 * Cl) / 6, q[1] = (-12 * Bl - 48 * Cl) / 6,
            q[2] = (6 * Bl + 30 * Cl) / 6, q[3] = (-Bl - 6 * Cl) / 6;
    }
    for (int k = 0; k < 4; k++)
        c[k] = t < 0 && (k & 1) ? -q[k] : q[k];
}

static double sinc(double x)
{
    return x == 0 ? 1 : sin(M_PI * x) / (M_PI * x);
}

static double lanczos_raw(double t, void *v)
{
    double a = *(const double *)v;
    return fabs(t) < a ? sinc(t) * sinc(t / a) : 0;
}

static double weight(const filt *f, double t)
{
    if (f->kind == F_GAUSS)
        return exp(-0.5 * (t / 0.5) * (t / 0.5)) / (0.5 * sqrt(2 * M_PI));
    if (f->kind == F_LANCZOS2 || f->kind == F_LANCZOS3) {
        double a = f->kind == F_LANCZOS2 ? 2 : 3;
        return lanczos_raw(t, &a) / f->M;
    }
    if (!(fabs(t) < f->R))
        return 0;
    long double c[4];
    piece_poly(f, t, c);
    return (double)(c[0] + t * (c[1] + t * (c[2] + t * c[3])));
}

static filt make_filt(int kind)
{
    filt f = {kind, NULL, 0, {0}, 0, 1};
    switch (kind) {
    case F_TENT:
        f.spec = "tent:r=1", f.R = 1;
        break;
    case F_BSPLINE2:
        f.spec = "bspline:order=2", f.R = 1.5;
        break;
    case F_BSPLINE3:
        f.spec = "bspline:order=3", f.R = 2;
        break;
    case F_MITCHELL:
        f.spec = "mitchell", f.R = 2;
        break;
    case F_CATROM:
        f.spec = "catrom", f.R = 2;
        break;
    case F_LANCZOS2:
        f.spec = "lanczos:a=2", f.R = 2;
        break;
    case F_LANCZOS3:
        f.spec = "lanczos:a=3", f.R = 3;
        break;
    default:
        f.spec = "gauss:s=0.5", f.R = 20; /* 40 standard deviations */
    }
    if (kind == F_GAUSS)
        return f;
    if (kind == F_BSPLINE2) {
        double k[4] = {-1.5, -0.5, 0.5, 1.5};
        memcpy(f.knots, k, sizeof k), f.nknots = 4;
    } else
        for (double t = -f.R; t <= f.R; t++)
            f.knots[f.nknots++] = t;
    if (kind == F_LANCZOS2 || kind == F_LANCZOS3) {
        /* the normalisation by QAG here: int over [-a, a] */
        double a = f.R, res, err, sum = 0;
        gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
        gsl_function F = {lanczos_raw, &a};
        for (double t = -a; t < a; t++) {
            gsl_integration_qag(&F, t, t + 1, 1e-16, 1e-15, 1000, GSL_INTEG_GAUSS61, ws, &res,
                                &err);
            sum += res;
        }
        gsl_integration_workspace_free(ws);
        f.M = sum;
    }
    return f;
}

/* ---- scenes (pattern units: the unit square is W x H pixels) ---- */

static void rect_px(aa_scene *s, double x0, double y0, double x1, double y1)
{
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

static void set_grad(aa_scene *s, int kind, const double p[6], const aa_gradient_stop *st, int n)
{
    aa_gradient g = {kind, AA_SPREAD_PAD, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0}, n, st};
    memcpy(g.p, p, sizeof g.p);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
}

static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};

static void reference(const aa_scene *s, const char *filter, aa_image *ref, aa_image *bound,
                      aa_truth_stats *stats)
{
    support_view v = {W, H, 0, 0, 0, filter, 1, 1, 0};
    support_reference(s, &v, ref, bound, stats);
}

/* ---- the 1-D closed form along x ---- */

/* int_{x0}^{x1} p(x - uc) dec(v(x)) dx on one piece (no knot, ramp end or
 * threshold inside), v = (x - a) / L, p = c (coefficients in t). */
static long double piece_1d(const long double c[4], double uc, double a, double L, double x0,
                            double x1)
{
    long double vm = ((long double)(0.5 * (x0 + x1)) - a) / L;
    if (vm <= 0)
        return 0;
    if (vm >= 1) { /* dec = 1: the polynomial's antiderivative */
        long double s = 0;
        for (int k = 3; k >= 0; k--) {
            long double t1 = (long double)x1 - uc, t0 = (long double)x0 - uc;
            s += c[k] * (powl(t1, k + 1) - powl(t0, k + 1)) / (k + 1);
        }
        return s;
    }
    /* t = alpha + beta z for z = v (below T) or u (above) */
    int above = vm > GO_T0;
    long double alpha = above ? (long double)a - uc - 0.055L * L : (long double)a - uc,
                beta = above ? 1.055L * L : (long double)L;
    long double r[4] = {0, 0, 0, 0}; /* p in z: sum c_k (alpha + beta z)^k */
    long double binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    for (int k = 0; k < 4; k++)
        for (int j = 0; j <= k; j++)
            r[j] += c[k] * binom[k][j] * powl(alpha, k - j) * powl(beta, j);
    long double z0 = above ? (((long double)x0 - a) / L + 0.055L) / 1.055L : ((long double)x0 - a) / L;
    long double z1 = above ? (((long double)x1 - a) / L + 0.055L) / 1.055L : ((long double)x1 - a) / L;
    long double s = 0;
    if (above) {
        for (int j = 0; j < 4; j++)
            s += r[j] * (powl(z1, j + 3.4L) - powl(z0, j + 3.4L)) / (j + 3.4L);
        return 1.055L * L * s;
    }
    for (int j = 0; j < 4; j++)
        s += r[j] * (powl(z1, j + 2) - powl(z0, j + 2)) / (j + 2);
    return L * s / 12.92L;
}

typedef struct ramp_ctx {
    const filt *f;
    double uc, a, L;
} ramp_ctx;

static double ramp_integrand(double x, void *v)
{
    const ramp_ctx *c = v;
    return weight(c->f, x - c->uc) * go_dec((x - c->a) / c->L);
}

/* The 1-D integral of w(x - uc) dec(ramp) over the filter's support. */
static double ramp_1d(const filt *f, double uc, double a, double b)
{
    double cut[256];
    int n = 0;
    cut[n++] = uc - f->R;
    cut[n++] = uc + f->R;
    for (int k = 0; k < f->nknots; k++)
        cut[n++] = uc + f->knots[k];
    double L = b - a, ends[3] = {a, b, a + GO_T0 * L};
    for (int k = 0; k < 3; k++)
        if (ends[k] > uc - f->R && ends[k] < uc + f->R)
            cut[n++] = ends[k];
    if (f->kind == F_LANCZOS2 || f->kind == F_LANCZOS3 || f->kind == F_GAUSS)
        for (double t = -f->R; t <= f->R; t += 0.5)
            cut[n++] = uc + t;
    qsort(cut, (size_t)n, sizeof *cut, go_cmp_double);
    long double sum = 0;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    ramp_ctx rc = {f, uc, a, L};
    gsl_function F = {ramp_integrand, &rc};
    for (int k = 0; k + 1 < n; k++) {
        double x0 = cut[k], x1 = cut[k + 1];
        if (!(x1 > x0))
            continue;
        if (f->kind == F_LANCZOS2 || f->kind == F_LANCZOS3 || f->kind == F_GAUSS) {
            double res, err;
            gsl_integration_qag(&F, x0, x1, 1e-17, 1e-15, 1000, GSL_INTEG_GAUSS61, ws, &res,
                                &err);
            sum += res;
            continue;
        }
        long double c[4];
        piece_poly(f, 0.5 * (x0 + x1) - uc, c);
        sum += piece_1d(c, uc, a, L, x0, x1);
    }
    gsl_integration_workspace_free(ws);
    return (double)sum;
}

/* A ramp along x from a to b over the whole plane (a rectangle far
 * beyond the image): every pixel of a column is the 1-D integral. */
static void test_along_x(void **state)
{
    (void)state;
    const double a = 3.3, b = 9.05;
    aa_scene *s = aa_scene_new((aa_rgb){{0.5, 0.5, 0.5}});
    rect_px(s, -8, -8, W + 8, H + 8);
    set_grad(s, AA_GRADIENT_LINEAR, (const double[6]){a, 0, b, 0, 0, 0}, black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    for (int kind = F_TENT; kind <= F_GAUSS; kind++) {
        if (san_skips(kind))
            continue;
        filt f = make_filt(kind);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, f.spec, &ref, &bound, &stats);
        double worst = 0, wb = 0;
        for (int i = 0; i < W; i++) {
            double want = ramp_1d(&f, i + 0.5, a, b);
            for (int j = 0; j < H; j += 5) {
                double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - want));
                wb = fmax(wb, bd);
                if (!(fabs(got - want) <= fmax(bd, 1e-15) && bd <= 1e-12))
                    fail_msg("%s: pixel (%d, %d) is %.17g, the 1-D %s %.17g (bound %.3g)",
                             f.spec, i, j, got,
                             kind >= F_LANCZOS2 ? "quadrature" : "closed form", want, bd);
            }
        }
        print_message("%-16s along x: largest difference %.2g, largest bound %.2g (%s)\n",
                      f.spec, worst, wb, kind >= F_LANCZOS2 ? "GSL 1-D" : "closed form");
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* Two equal stops: the flat colour's reference, to rounding. */
static void test_constant(void **state)
{
    (void)state;
    const aa_rgb col = {{0.3, 0.62, 0.05}};
    const aa_gradient_stop same[2] = {{0.0, col, 1.0}, {1.0, col, 1.0}};
    for (int kind = F_TENT; kind <= F_GAUSS; kind++) {
        filt f = make_filt(kind);
        for (int radial = 0; radial < 2; radial++) {
            if (radial && san_skips(kind))
                continue;
            aa_scene *g = aa_scene_new((aa_rgb){{0.1, 0.2, 0.9}});
            aa_scene *flat = aa_scene_new((aa_rgb){{0.1, 0.2, 0.9}});
            rect_px(g, 2.25, 3.5, 12.75, 9.1);
            /* the stops' lines and circles cross the image */
            static const double at[2][6] = {{1, 2, 11, 7, 0, 0}, {7, 6, 4, 6.5, 5.5, 0}};
            set_grad(g, radial ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR, at[radial], same, 2);
            assert_int_equal(aa_scene_layer(flat, col, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(flat, 2.25 / W, 3.5 / H), AA_OK);
            assert_int_equal(aa_scene_line_to(flat, 12.75 / W, 3.5 / H), AA_OK);
            assert_int_equal(aa_scene_line_to(flat, 12.75 / W, 9.1 / H), AA_OK);
            assert_int_equal(aa_scene_line_to(flat, 2.25 / W, 9.1 / H), AA_OK);
            assert_int_equal(aa_scene_close(flat), AA_OK);
            assert_int_equal(aa_scene_finish(g), AA_OK);
            assert_int_equal(aa_scene_finish(flat), AA_OK);
            aa_image rg, rf, bound;
            aa_truth_stats stats;
            reference(g, f.spec, &rg, &bound, &stats);
            /* the flat colour by QAG, as the gradient is (the Gaussian's
             * fixed rule for flat scenes is another quadrature) */
            aa_filter ff;
            assert_int_equal(aa_filter_parse(f.spec, &ff), AA_OK);
            aa_scene *placed = aa_scene_place(flat, W, H, 0, 0, 0);
            assert_int_equal(aa_image_alloc(&rf, W, H, 3), AA_OK);
            assert_int_equal(aa__truth_render_mode(placed, &ff, 1, AA__TRUTH_QAG, &rf, NULL, NULL,
                                                   NULL),
                             AA_OK);
            aa_scene_free(placed);
            double worst = 0;
            for (int j = 0; j < H; j++)
                for (int i = 0; i < W; i++)
                    for (int ch = 0; ch < 3; ch++)
                        worst = fmax(worst, fabs(aa_pixel(&rg, i, j)[ch] - aa_pixel(&rf, i, j)[ch]));
            /* and the flat colour's pixels whose window meets no edge are
             * its colour, the gradient's are integrated over the window:
             * the Gaussian's mass outside it (ff.lost) apart */
            double tol = 1e-15 + ff.lost;
            print_message("%-16s constant %s gradient against the flat colour: %.2g (bound %.2g, "
                          "tolerance %.2g)\n",
                          f.spec, radial ? "radial" : "linear", worst, stats.max_bound, tol);
            if (!(worst <= tol))
                fail_msg("%s: a constant %s gradient is %.3g off the flat colour", f.spec,
                         radial ? "radial" : "linear", worst);
            assert_true(stats.max_bound <= 1e-12);
            aa_image_free(&rg);
            aa_image_free(&rf);
            aa_image_free(&bound);
            aa_scene_free(g);
            aa_scene_free(flat);
        }
    }
}

/* ---- 2-D quadrature of single pixels ---- */

/* The picture (tests/gradient_oracle.h) under the filter f about the
 * pixel's centre (uc, vc), at the row y of the outer integral. */
typedef struct pic {
    go_pic g;
    const filt *f;
    double uc, vc, y;
    gsl_integration_workspace *wi;
} pic;

static double pic_x(double x, void *v)
{
    const pic *p = v;
    return weight(p->f, x - p->uc) * go_pic_at(&p->g, x, p->y);
}

static double pic_y(double y, void *v)
{
    pic *p = v;
    p->y = y;
    double cut[32], R = p->f->R;
    int n = 0;
    cut[n++] = p->uc - R, cut[n++] = p->uc + R;
    for (int k = 0; k < p->f->nknots; k++)
        cut[n++] = p->uc + p->f->knots[k];
    if (!p->g.radial)
        cut[n++] = p->g.rc[0], cut[n++] = p->g.rc[2];
    else
        cut[n++] = p->g.cx;
    for (int q = 0; q < 3; q++)
        n += go_tau_meet(&p->g, go_taus[q], 0, y, cut + n);
    gsl_function F = {pic_x, p};
    double sum = go_qags_cuts(&F, cut, n, p->uc - R, p->uc + R, 1e-16, 1e-14, p->wi);
    return weight(p->f, y - p->vc) * sum;
}

/* Pixel (i, j) of the picture under p->f by 2-D quadrature. */
static double pic_pixel(pic *p, int i, int j)
{
    p->uc = i + 0.5, p->vc = j + 0.5;
    double R = p->f->R, cut[256], X[32];
    int n = 0, nx = 0;
    cut[n++] = p->vc - R, cut[n++] = p->vc + R;
    for (int k = 0; k < p->f->nknots; k++)
        cut[n++] = p->vc + p->f->knots[k], X[nx++] = p->uc + p->f->knots[k];
    X[nx++] = p->uc - R, X[nx++] = p->uc + R;
    if (!p->g.radial) {
        cut[n++] = p->g.rc[1], cut[n++] = p->g.rc[3];
        X[nx++] = p->g.rc[0], X[nx++] = p->g.rc[2];
    } else {
        cut[n++] = p->g.cy;
        X[nx++] = p->g.cx;
        for (int q = 0; q < 3; q++) /* the circles' top and bottom rows */
            cut[n++] = p->g.cy - go_taus[q] * p->g.r, cut[n++] = p->g.cy + go_taus[q] * p->g.r;
    }
    /* where each curve t = tau crosses each of those vertical lines */
    for (int q = 0; q < 3; q++)
        for (int k = 0; k < nx; k++)
            n += go_tau_meet(&p->g, go_taus[q], 1, X[k], cut + n);
    p->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {pic_y, p};
    double sum = go_qags_cuts(&F, cut, n, p->vc - R, p->vc + R, 1e-16, 1e-13, wo);
    gsl_integration_workspace_free(p->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

static void check_pixels(const char *what, pic *p, const aa_image *ref, const aa_image *bound,
                         const int (*px)[2], int npx)
{
    double worst = 0;
    for (int k = 0; k < npx; k++) {
        int i = px[k][0], j = px[k][1];
        double want = pic_pixel(p, i, j), got = aa_pixel(ref, i, j)[0];
        double bd = *aa_pixel(bound, i, j);
        worst = fmax(worst, fabs(got - want));
        print_message("  (%d, %d): %.17g, quadrature %.17g, difference %.2g, bound %.2g\n", i, j,
                      got, want, got - want, bd);
        /* within the pixel's own bound (the quadrature here is good to
         * 1e-15: its tolerances tightened a hundredfold moved nothing) */
        if (!(fabs(got - want) <= bd + 1e-15 && bd <= 1e-12))
            fail_msg("%s under %s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)",
                     what, p->f->spec, i, j, got, want, bd);
    }
    print_message("%s under %s: %d pixels, largest difference from 2-D quadrature %.2g\n", what,
                  p->f->spec, npx, worst);
}

/* An oblique black-to-white ramp on a rectangle, under tent and the
 * cubic B-spline. */
static void test_linear_2d(void **state)
{
    (void)state;
    const double bgl = 0.2;
    aa_scene *s = aa_scene_new((aa_rgb){{bgl, bgl, bgl}});
    pic p = {0};
    p.g.rc[0] = 1.5, p.g.rc[1] = 2.25, p.g.rc[2] = 14.75, p.g.rc[3] = 10.5, p.g.bg = bgl;
    p.g.x1 = 3.1, p.g.y1 = 2.0, p.g.x2 = 13.4, p.g.y2 = 9.7;
    rect_px(s, p.g.rc[0], p.g.rc[1], p.g.rc[2], p.g.rc[3]);
    set_grad(s, AA_GRADIENT_LINEAR, (const double[6]){p.g.x1, p.g.y1, p.g.x2, p.g.y2, 0, 0},
             black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    /* corners and sides of the rectangle, the ramp's ends (t = 0 near (3,
     * 2), t = 1 near (13, 10)), the threshold's line and the middle */
    static const int px[][2] = {{1, 2}, {14, 10}, {3, 3}, {4, 2}, {12, 9}, {13, 8},
                                {8, 6}, {5, 5}, {2, 7}, {9, 10}};
    for (int kind = F_TENT; kind <= F_BSPLINE3; kind += F_BSPLINE3 - F_TENT) {
        filt f = make_filt(kind);
        p.f = &f;
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, f.spec, &ref, &bound, &stats);
        print_message("%s: largest bound %.2g\n", f.spec, stats.max_bound);
        assert_true(stats.max_bound <= 1e-12);
        check_pixels("linear ramp on a rectangle", &p, &ref, &bound, px,
                     (int)(sizeof px / sizeof *px));
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* A centred radial gradient over the whole plane under tent:r=1. */
static void test_radial_2d(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    pic p = {0};
    p.g.radial = 1, p.g.cx = 8.3, p.g.cy = 6.1, p.g.r = 5.2, p.g.fx = p.g.cx, p.g.fy = p.g.cy;
    rect_px(s, -8, -8, W + 8, H + 8);
    set_grad(s, AA_GRADIENT_RADIAL, (const double[6]){p.g.cx, p.g.cy, p.g.r, p.g.cx, p.g.cy, 0},
             black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    filt f = make_filt(F_TENT);
    p.f = &f;
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, f.spec, &ref, &bound, &stats);
    print_message("radial under %s: largest bound %.2g\n", f.spec, stats.max_bound);
    assert_true(stats.max_bound <= 1e-12);
    /* the rim's top row (y = 0.9), the rim crossing, the centre with the
     * threshold's circle (radius 0.21), inside and outside */
    static const int px[][2] = {{8, 0}, {8, 1}, {13, 4}, {3, 7}, {8, 6}, {7, 5}, {10, 7}, {1, 1}};
    check_pixels("centred radial ramp", &p, &ref, &bound, px, (int)(sizeof px / sizeof *px));
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_along_x),   cmocka_unit_test(test_constant),
        cmocka_unit_test(test_linear_2d), cmocka_unit_test(test_radial_2d),
    };
    SAN_CASES_PRINT();
    return cmocka_run_group_tests(tests, setup, NULL);
}
