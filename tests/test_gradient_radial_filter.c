/*
 * test_gradient_radial_filter.c: the exact reference of gradient paint
 * under the radial filters (harness/truth/truth.c, "the radial filters:
 * the weight along a row"): cone (whole and truncated), the Gaussian in a
 * circular mask (gauss with cut) and the radial polynomials (radial:k).
 *
 * Known answers, derived here and not from the code under test:
 *  - a gradient that varies along x only, over the whole plane: the pixel
 *    is the 1-D integral of the filter's marginal m(u) = int w(sqrt(u^2 +
 *    v^2)) dv times dec(t(x)), u = x - uc.  The marginals in closed form,
 *    from the filters' definitions (patterns/README.md, "Filters") with c
 *    = sqrt(Rc^2 - u^2) the half chord inside the support Rc:
 *        cone (radius r, normalised by N):  N (2 c - (c Rc + u^2
 *            asinh(c / |u|)) / r), from int sqrt(u^2 + v^2) dv = (v
 *            sqrt(u^2 + v^2) + u^2 asinh(v / |u|)) / 2;
 *        Gaussian (S, in a mask):  N exp(-u^2 / (2 S^2)) S sqrt(2 pi)
 *            erf(c / (S sqrt 2));
 *        radial (k, r):  N c^(2k + 1) B_k / r^(2k), B_k = int_{-1}^{1} (1
 *            - t^2)^k dt = 4/3, 16/15, 32/35;
 *    the normalisations N from the volumes in polar coordinates (cone: 1
 *    / (2 pi r^2 (K^2/2 - K^3/3)), K = Rc / r; Gaussian: 1 / (2 pi S^2 (1
 *    - exp(-K^2/2))); radial: (k + 1) / (pi r^2)).  The 1-D integral of
 *    the marginal times the decoded ramp by GSL's QAGS between the ramp's
 *    ends, the threshold's x, uc and uc +- Rc;
 *  - a constant gradient (two equal stops) is the flat colour: its
 *    reference equals the flat-colour reference (the rows' closed-form
 *    integrals, a different path) to rounding;
 *  - single pixels by GSL's adaptive quadrature in two dimensions (outer
 *    rows, inner along the row's chord), the filter written out here and
 *    the picture in tests/gradient_oracle.c: a centred radial gradient
 *    over the whole plane (t = distance / r, the root below with F = C),
 *    and a focal one (F off the centre, fr = 0: t the positive root of
 *    (r^2 - |D|^2) t^2 + 2 (q - F).D t - |q - F|^2 = 0), cut at the
 *    support's centre row and column, the focus's, and where each circle
 *    t = 0, T, 1 crosses the support's circle and meets the rows; and an
 *    oblique linear ramp on a rectangle, cut at the rectangle's sides and
 *    the lines t = 0, T, 1.
 * Each pixel must lie within its own bound of the oracle, and every bound
 * within 1e-12.
 */
#include "core.h"
#include "gradient_oracle.h"
#include "support.h"
#include "tier.h"
#include "truth.h"

#include <float.h>
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
#include <gsl/gsl_sf_erf.h>

#define W 14
#define H 10

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return 0;
}

/* ---- the radial filters, from their definitions ---- */

enum { F_CONE, F_GAUSS, F_RADIAL };

typedef struct filt {
    int kind;
    const char *spec;
    double r, K, S, k; /* cone: r, K; gauss: S, K; radial: k, r */
    double Rc, N;      /* the support's radius, the normalisation */
} filt;

static filt make_filt(const char *spec, int kind, double a, double b)
{
    filt f = {kind, spec, 0, 0, 0, 0, 0, 0};
    if (kind == F_CONE) {
        f.r = a, f.K = b, f.Rc = a * b;
        f.N = 1.0 / (2.0 * M_PI * a * a * (b * b / 2.0 - b * b * b / 3.0));
    } else if (kind == F_GAUSS) {
        f.S = a, f.K = b, f.Rc = a * b;
        f.N = 1.0 / (2.0 * M_PI * a * a * (1.0 - exp(-b * b / 2.0)));
    } else {
        f.k = a, f.r = b, f.Rc = b;
        f.N = (a + 1.0) / (M_PI * b * b);
    }
    return f;
}

static const char *const specs[] = {"cone:r=1", "cone:r=2,cut=0.55", "gauss:s=0.5,cut=2",
                                    "radial:k=1,r=1", "radial:k=3,r=1.5"};

static filt filt_of(int n)
{
    switch (n) {
    case 0:
        return make_filt(specs[0], F_CONE, 1, 1);
    case 1:
        return make_filt(specs[1], F_CONE, 2, 0.55);
    case 2:
        return make_filt(specs[2], F_GAUSS, 0.5, 2);
    case 3:
        return make_filt(specs[3], F_RADIAL, 1, 1);
    default:
        return make_filt(specs[4], F_RADIAL, 3, 1.5);
    }
}
#define NFILT 5

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) the cases that take every filter on one scene
 * (test_along_x, test_constant and the 2-D pixels' three) run a declared
 * subset: case c takes the filters n with n + c even, the first, third and
 * fifth (c = 0: the constant linear gradient, the focal ramp, the oblique
 * ramp) or the second and fourth (c = 1: the ramp along x, the constant
 * radial gradient, the centred ramp), so that a linear and a radial
 * gradient meet each filter, and the flat colour every filter (the rows'
 * closed forms, test_constant).  The sanitizers find memory and
 * undefined-behaviour errors along the paths taken, and another filter on
 * the same scene takes the same paths with other numbers (tests/README.md,
 * "Tiers", says how that was checked); the plain build runs every case.
 * The mixed pictures' checks (mix_check) take there the reference of the
 * bounding box of the pixels they check against the 2-D quadrature alone,
 * a part made by aa_scene_transform (support_reference_part), and hold
 * its bounds and its count of scanned pixels, not the whole view's. */

/* Whether case c leaves filter n out (the subset above). */
static int san_skips(int c, int n)
{
    return SAN_SUBSET && (n + c) % 2;
}

static double weight2(const filt *f, double u, double v)
{
    double d = hypot(u, v);
    if (!(d < f->Rc))
        return 0.0;
    if (f->kind == F_CONE)
        return f->N * (1.0 - d / f->r);
    if (f->kind == F_GAUSS)
        return f->N * exp(-d * d / (2.0 * f->S * f->S));
    return f->N * pow(1.0 - d * d / (f->r * f->r), f->k);
}

/* The marginal int w dv at u (the header's closed forms). */
static double marginal(const filt *f, double u)
{
    double au = fabs(u);
    if (!(au < f->Rc))
        return 0.0;
    double c = sqrt((f->Rc - au) * (f->Rc + au));
    if (f->kind == F_CONE)
        return f->N * (2.0 * c - (c * f->Rc + (au > 0 ? u * u * asinh(c / au) : 0.0)) / f->r);
    if (f->kind == F_GAUSS)
        return f->N * exp(-u * u / (2.0 * f->S * f->S)) * f->S * sqrt(2.0 * M_PI) *
               erf(c / (f->S * M_SQRT2));
    static const double B[4] = {2.0, 4.0 / 3.0, 16.0 / 15.0, 32.0 / 35.0};
    return f->N * pow(c, 2.0 * f->k + 1.0) * B[(int)f->k] / pow(f->r, 2.0 * f->k);
}

/* ---- scenes (pattern units: the unit square is W x H pixels) ---- */

static void rect_px(aa_scene *s, double x0, double y0, double x1, double y1, aa_rgb col)
{
    assert_int_equal(aa_scene_layer(s, col, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

static void set_grad(aa_scene *s, int kind, int spread, const double p[6],
                     const aa_gradient_stop *st, int n)
{
    aa_gradient g = {kind, spread, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0}, n, st};
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

/* ---- a ramp along x against the marginal's 1-D integral ---- */

typedef struct ramp_ctx {
    const filt *f;
    double uc, a, L;
} ramp_ctx;

static double ramp_integrand(double x, void *v)
{
    const ramp_ctx *c = v;
    return marginal(c->f, x - c->uc) * go_dec((x - c->a) / c->L);
}

static double ramp_1d(const filt *f, double uc, double a, double b)
{
    double L = b - a, cut[8] = {uc - f->Rc, uc, uc + f->Rc, a, b, a + GO_T0 * L};
    int n = 6;
    qsort(cut, (size_t)n, sizeof *cut, go_cmp_double);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    ramp_ctx rc = {f, uc, a, L};
    gsl_function F = {ramp_integrand, &rc};
    double sum = 0;
    for (int k = 0; k + 1 < n; k++) {
        double x0 = fmax(cut[k], uc - f->Rc), x1 = fmin(cut[k + 1], uc + f->Rc), res, err;
        if (!(x1 > x0))
            continue;
        gsl_integration_qags(&F, x0, x1, 1e-17, 1e-15, 1000, ws, &res, &err);
        sum += res;
    }
    gsl_integration_workspace_free(ws);
    return sum;
}

static void test_along_x(void **state)
{
    (void)state;
    const double a = 2.3, b = 10.05;
    aa_scene *s = aa_scene_new((aa_rgb){{0.5, 0.5, 0.5}});
    rect_px(s, -8, -8, W + 8, H + 8, (aa_rgb){{0, 0, 0}});
    set_grad(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){a, 0, b, 0, 0, 0},
             black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    for (int n = 0; n < NFILT; n++) {
        if (san_skips(1, n))
            continue;
        filt f = filt_of(n);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, f.spec, &ref, &bound, &stats);
        double worst = 0, wb = 0;
        for (int i = 0; i < W; i++) {
            double want = ramp_1d(&f, i + 0.5, a, b);
            for (int j = 0; j < H; j += 4) {
                double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - want));
                wb = fmax(wb, bd);
                if (!(fabs(got - want) <= bd + 1e-15 && bd <= 1e-12))
                    fail_msg("%s: pixel (%d, %d) is %.17g, the marginal's 1-D integral %.17g "
                             "(bound %.3g)",
                             f.spec, i, j, got, want, bd);
            }
        }
        print_message("%-18s along x: largest difference from the marginal's integral %.2g, "
                      "largest bound %.2g\n",
                      f.spec, worst, wb);
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* ---- two equal stops: the flat colour ---- */

static void test_constant(void **state)
{
    (void)state;
    const aa_rgb col = {{0.3, 0.62, 0.05}}, bg = {{0.1, 0.2, 0.9}};
    const aa_gradient_stop same[2] = {{0.0, col, 1.0}, {1.0, col, 1.0}};
    for (int n = 0; n < NFILT; n++) {
        filt f = filt_of(n);
        for (int radial = 0; radial < 2; radial++) {
            if (san_skips(radial, n))
                continue;
            aa_scene *g = aa_scene_new(bg), *flat = aa_scene_new(bg);
            rect_px(g, 2.25, 3.5, 11.75, 8.1, col);
            static const double at[2][6] = {{1, 2, 11, 7, 0, 0}, {7, 6, 4, 6.5, 5.5, 0}};
            set_grad(g, radial ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                     at[radial], same, 2);
            rect_px(flat, 2.25, 3.5, 11.75, 8.1, col);
            assert_int_equal(aa_scene_finish(g), AA_OK);
            assert_int_equal(aa_scene_finish(flat), AA_OK);
            aa_image rg, rf, bg_, bf;
            aa_truth_stats sg, sf;
            reference(g, f.spec, &rg, &bg_, &sg);
            reference(flat, f.spec, &rf, &bf, &sf);
            double worst = 0;
            for (int j = 0; j < H; j++)
                for (int i = 0; i < W; i++)
                    for (int ch = 0; ch < 3; ch++)
                        worst = fmax(worst, fabs(aa_pixel(&rg, i, j)[ch] - aa_pixel(&rf, i, j)[ch]));
            print_message("%-18s constant %s gradient against the flat colour: %.2g (bound "
                          "%.2g)\n",
                          f.spec, radial ? "radial" : "linear", worst, sg.max_bound);
            /* the flat colour's own bound and the gradient's: each is
             * within its bound of the true value */
            if (!(worst <= sg.max_bound + sf.max_bound + 1e-15))
                fail_msg("%s: a constant %s gradient is %.3g off the flat colour (bounds %.3g, "
                         "%.3g)",
                         f.spec, radial ? "radial" : "linear", worst, sg.max_bound, sf.max_bound);
            assert_true(sg.max_bound <= 1e-12);
            aa_image_free(&rg);
            aa_image_free(&rf);
            aa_image_free(&bg_);
            aa_image_free(&bf);
            aa_scene_free(g);
            aa_scene_free(flat);
        }
    }
}

/* ---- single pixels by 2-D quadrature ---- */

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
    return weight2(p->f, x - p->uc, p->y - p->vc) * go_pic_at(&p->g, x, p->y);
}

static double pic_y(double y, void *v)
{
    pic *p = v;
    p->y = y;
    double dv = y - p->vc, h2 = p->f->Rc * p->f->Rc - dv * dv;
    if (!(h2 > 0))
        return 0;
    double c = sqrt(h2), cut[16];
    int n = 0;
    cut[n++] = p->uc - c, cut[n++] = p->uc + c, cut[n++] = p->uc;
    if (!p->g.radial)
        cut[n++] = p->g.rc[0], cut[n++] = p->g.rc[2];
    else
        cut[n++] = p->g.fx; /* t's cone at the focus */
    for (int q = 0; q < 3; q++)
        n += go_tau_meet(&p->g, go_taus[q], 0, y, cut + n);
    gsl_function F = {pic_x, p};
    double sum = go_qags_cuts(&F, cut, n, p->uc - c, p->uc + c, 1e-17, 1e-14, p->wi);
    return sum;
}

/* The heights where the curve t = tau crosses the circle of radius Rc
 * about the pixel's centre, and where it passes closest to the centre. */
static int tau_circle(const pic *p, double tau, double *out)
{
    double Rc = p->f->Rc;
    int n = 0;
    if (p->g.radial) {
        /* two circles: centres distance D apart, radii rr and Rc */
        double ccx = p->g.fx + tau * (p->g.cx - p->g.fx);
        double ccy = p->g.fy + tau * (p->g.cy - p->g.fy);
        double rr = tau * p->g.r, ex = p->uc - ccx, ey = p->vc - ccy, D = hypot(ex, ey);
        if (!(D > 0))
            return 0;
        double l = (rr * rr - Rc * Rc + D * D) / (2 * D), h2 = rr * rr - l * l;
        if (h2 > 0) {
            double mx = ex / D, my = ey / D, h = sqrt(h2);
            out[n++] = ccy + l * my + h * mx, out[n++] = ccy + l * my - h * mx;
        }
        out[n++] = ccy + rr * ey / D; /* nearest the centre, on the ray */
        return n;
    }
    double dx = p->g.x2 - p->g.x1, dy = p->g.y2 - p->g.y1, L = hypot(dx, dy);
    /* the line: points whose projection is tau L along (dx, dy) / L */
    double d = ((p->uc - p->g.x1) * dx + (p->vc - p->g.y1) * dy) / L - tau * L;
    double fy = p->vc - d * dy / L;
    out[n++] = fy;
    if (fabs(d) < Rc) {
        double h = sqrt(Rc * Rc - d * d);
        out[n++] = fy + h * dx / L, out[n++] = fy - h * dx / L;
    }
    return n;
}

static double pic_pixel(pic *p, int i, int j)
{
    p->uc = i + 0.5, p->vc = j + 0.5;
    double R = p->f->Rc, cut[64];
    int n = 0;
    cut[n++] = p->vc - R, cut[n++] = p->vc + R, cut[n++] = p->vc;
    if (!p->g.radial) {
        cut[n++] = p->g.rc[1], cut[n++] = p->g.rc[3];
        /* the rectangle's sides against the support's circle */
        for (int k = 0; k < 4; k += 2) {
            double d = p->g.rc[k] - p->uc;
            if (fabs(d) < R)
                cut[n++] = p->vc - sqrt(R * R - d * d), cut[n++] = p->vc + sqrt(R * R - d * d);
        }
    } else {
        cut[n++] = p->g.fy; /* the focus's row */
        for (int q = 0; q < 3; q++) {
            double ccy = p->g.fy + go_taus[q] * (p->g.cy - p->g.fy);
            cut[n++] = ccy - go_taus[q] * p->g.r, cut[n++] = ccy + go_taus[q] * p->g.r;
        }
    }
    for (int q = 0; q < 3; q++)
        n += tau_circle(p, go_taus[q], cut + n);
    p->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {pic_y, p};
    double sum = go_qags_cuts(&F, cut, n, p->vc - R, p->vc + R, 1e-17, 1e-13, wo);
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
        if (!(fabs(got - want) <= bd + 2e-15 && bd <= 1e-12))
            fail_msg("%s under %s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)",
                     what, p->f->spec, i, j, got, want, bd);
    }
    print_message("%-18s %s: %d pixels, largest difference from 2-D quadrature %.2g\n",
                  p->f->spec, what, npx, worst);
}

/* The reference of s under each radial filter (case c: the subset above
 * under the sanitizers): every bound within 1e-12 and the pixels px
 * against p's 2-D quadrature. */
static void check_filters(const aa_scene *s, const char *what, pic *p, const int (*px)[2],
                          int npx, int c)
{
    for (int n = 0; n < NFILT; n++) {
        if (san_skips(c, n))
            continue;
        filt f = filt_of(n);
        p->f = &f;
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, f.spec, &ref, &bound, &stats);
        assert_true(stats.max_bound <= 1e-12);
        check_pixels(what, p, &ref, &bound, px, npx);
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    p->f = NULL;
}

/* A radial gradient centred at C = (7.3, 5.1), radius 4.2, focus F (fr =
 * 0), black to white over the whole plane, against 2-D quadrature at the
 * pixels px under each radial filter. */
static void radial_2d(const char *what, double fx, double fy, const int (*px)[2], int npx, int c)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    pic p = {0};
    p.g.radial = 1, p.g.focal = 1, p.g.cx = 7.3, p.g.cy = 5.1, p.g.r = 4.2;
    p.g.fx = fx, p.g.fy = fy;
    rect_px(s, -8, -8, W + 8, H + 8, (aa_rgb){{0, 0, 0}});
    set_grad(s, AA_GRADIENT_RADIAL, AA_SPREAD_PAD,
             (const double[6]){p.g.cx, p.g.cy, p.g.r, p.g.fx, p.g.fy, 0}, black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_filters(s, what, &p, px, npx, c);
    aa_scene_free(s);
}

/* The focus at the centre (t = |q - C| / r by the focal form). */
static void test_radial_2d(void **state)
{
    (void)state;
    /* the rim's top row, the rim's crossing, the centre with the
     * threshold's circle (radius 0.17), inside and outside */
    static const int px[][2] = {{7, 0}, {7, 1}, {11, 4}, {3, 6}, {7, 5}, {6, 4}, {9, 6}, {1, 1}};
    radial_2d("centred radial ramp", 7.3, 5.1, px, (int)(sizeof px / sizeof *px), 1);
}

/* A focal radial gradient (F off the centre, fr = 0: t has a cone at F),
 * its stop circles not concentric. */
static void test_focal_2d(void **state)
{
    (void)state;
    /* the focus's pixel and its neighbours, the rim's crossings, the
     * threshold's circle near F */
    static const int px[][2] = {{5, 4}, {6, 4}, {5, 3}, {7, 5}, {11, 4}, {3, 2}, {7, 9}, {2, 8}};
    radial_2d("focal radial ramp", 5.9, 4.2, px, (int)(sizeof px / sizeof *px), 0);
}

static void test_linear_2d(void **state)
{
    (void)state;
    const double bgl = 0.2;
    aa_scene *s = aa_scene_new((aa_rgb){{bgl, bgl, bgl}});
    pic p = {0};
    p.g.rc[0] = 1.5, p.g.rc[1] = 2.25, p.g.rc[2] = 12.75, p.g.rc[3] = 8.5, p.g.bg = bgl;
    p.g.x1 = 3.1, p.g.y1 = 2.0, p.g.x2 = 11.4, p.g.y2 = 8.7;
    rect_px(s, p.g.rc[0], p.g.rc[1], p.g.rc[2], p.g.rc[3], (aa_rgb){{0, 0, 0}});
    set_grad(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
             (const double[6]){p.g.x1, p.g.y1, p.g.x2, p.g.y2, 0, 0}, black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    /* corners and sides of the rectangle, the ramp's ends, the
     * threshold's line and the middle */
    static const int px[][2] = {{1, 2}, {12, 8}, {3, 3}, {4, 2}, {10, 7}, {7, 5}, {2, 6}, {8, 8}};
    check_filters(s, "linear ramp on a rectangle", &p, px, (int)(sizeof px / sizeof *px), 0);
    aa_scene_free(s);
}

/* ---- translucent layers of different t: the threshold's slivers ----
 *
 * test_gradient.c's test_mixed_tangent picture moved by (-1, -4): a radial
 * gradient about C = (6.5, 7), radius 4, at alpha 0.6 over a linear one
 * along y (t = (y + 2) / 12), both over the whole view, black behind.
 * Encoded, E = 0.6 CR(tR) + 0.4 CL(tL): CR falls from 0.2 at tR = 0 to 0
 * at 1 (0 beyond), CL rises from 0 to 0.0451 at the stop line tL = 0.48
 * (y = 3.76) and falls to 0 at tL = 1 (the stops' linear values encoded
 * here).  On a row CL is one number, so the threshold's curve E =
 * 0.04045 meets it where |q - C| = 4 tR, tR = 1 - (0.04045 - 0.4 CL) /
 * 0.12: x = 6.5 +- sqrt((4 tR)^2 - (y - 7)^2), in closed form (outside
 * the circle tR = 1, E <= 0.4 CL < 0.04045: no crossing there); its
 * lowest point, a horizontal tangent, is near (6.5, 3.75).  The pixel is
 * the 2-D integral of dec(E) times the filter's weight (written out
 * above): GSL's QAGS along each row's chord, cut at those crossings, the
 * window's centre, C's column and the circle tR = 1, and over the rows,
 * cut at the window's top, centre and bottom, the stop line, the ramp's
 * ends, the circle's top and bottom, C's row and every height where the
 * count of crossings inside the chord changes (the curve tangent to a row
 * or crossing the filter's circle: 256 heights a window, bisected to
 * rounding).  Slivers that took 4 R times the weight's peak a unit of
 * height (truth.c before its radial sliver bound) gave a largest bound of
 * 1.8e-7 under cone:r=1 here. */

static double mix_enc(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static const aa_gradient_stop mix_r[2] = {{0.0, {{0.033104766570885055, 0.033104766570885055,
                                                   0.033104766570885055}}, 1.0},
                                          {1.0, {{0, 0, 0}}, 1.0}};
static const aa_gradient_stop mix_l[3] = {{0.0, {{0, 0, 0}}, 1.0},
                                          {0.48, {{0.003511466425239878, 0.003511466425239878,
                                                   0.003511466425239878}}, 1.0},
                                          {1.0, {{0, 0, 0}}, 1.0}};

typedef struct mix {
    const filt *f;
    double uc, vc, y, cr0, cl; /* cr0: CR at tR = 0; cl: CL at the stop */
    double edge;               /* the radial layer's right side (x) */
    gsl_integration_workspace *wi;
} mix;

static double mix_cl(const mix *m, double y)
{
    double t = (y + 2.0) / 12.0;
    if (t <= 0.0 || t >= 1.0)
        return 0.0;
    return t < 0.48 ? m->cl * t / 0.48 : m->cl * (1.0 - t) / 0.52;
}

static double mix_e(const mix *m, double x, double y)
{
    double tr = hypot(x - 6.5, y - 7.0) / 4.0;
    if (x >= m->edge)
        return mix_cl(m, y);
    return 0.6 * (tr < 1.0 ? m->cr0 * (1.0 - tr) : 0.0) + 0.4 * mix_cl(m, y);
}

/* The curve's crossings of row y left of the edge (at most 2, into x),
 * in closed form (right of it E = CL is one number along the row). */
static int mix_cross(const mix *m, double y, double *x)
{
    double tr = 1.0 - (GO_T0 - 0.4 * mix_cl(m, y)) / (0.6 * m->cr0);
    double h2 = 16.0 * tr * tr - (y - 7.0) * (y - 7.0);
    if (!(tr > 0.0 && tr < 1.0 && h2 > 0.0))
        return 0;
    x[0] = 6.5 - sqrt(h2), x[1] = 6.5 + sqrt(h2);
    return (x[0] < m->edge) + (x[1] < m->edge);
}

/* Those inside the chord of the window's row y. */
static int mix_count(const mix *m, double y)
{
    double dv = y - m->vc, h2 = m->f->Rc * m->f->Rc - dv * dv, x[2];
    int n = mix_cross(m, y, x), k = 0;
    for (int i = 0; i < n && h2 > 0.0; i++)
        k += fabs(x[i] - m->uc) < sqrt(h2);
    return k;
}

static double mix_x(double x, void *v)
{
    const mix *m = v;
    return weight2(m->f, x - m->uc, m->y - m->vc) * go_dec(mix_e(m, x, m->y));
}

static double mix_y(double y, void *v)
{
    mix *m = v;
    m->y = y;
    double dv = y - m->vc, h2 = m->f->Rc * m->f->Rc - dv * dv;
    if (!(h2 > 0))
        return 0;
    double c = sqrt(h2), cut[16], q = 16.0 - (y - 7.0) * (y - 7.0);
    int n = 0;
    cut[n++] = m->uc - c, cut[n++] = m->uc + c, cut[n++] = m->uc, cut[n++] = 6.5;
    cut[n++] = fmin(m->edge, 1e3);
    if (q > 0.0)
        cut[n++] = 6.5 - sqrt(q), cut[n++] = 6.5 + sqrt(q);
    n += mix_cross(m, y, cut + n);
    gsl_function F = {mix_x, m};
    return go_qags_cuts(&F, cut, n, m->uc - c, m->uc + c, 1e-17, 1e-14, m->wi);
}

static double mix_pixel(mix *m, int i, int j)
{
    m->uc = i + 0.5, m->vc = j + 0.5;
    double R = m->f->Rc, cut[64];
    int n = 0;
    cut[n++] = m->vc - R, cut[n++] = m->vc + R, cut[n++] = m->vc, cut[n++] = 3.76;
    cut[n++] = 3.0, cut[n++] = 7.0, cut[n++] = 11.0, cut[n++] = -2.0, cut[n++] = 10.0;
    /* right of the edge: the rows where CL = 0.04045, and the edge's
     * crossings of the filter's circle */
    cut[n++] = 12.0 * 0.48 * GO_T0 / m->cl - 2.0;
    cut[n++] = 12.0 * (1.0 - 0.52 * GO_T0 / m->cl) - 2.0;
    if (fabs(m->edge - m->uc) < R) {
        double e = m->edge - m->uc, h = sqrt((R - e) * (R + e));
        cut[n++] = m->vc - h, cut[n++] = m->vc + h;
    }
    const int N = 256;
    int na = mix_count(m, m->vc - R);
    for (int k = 1; k <= N && n < 60; k++) {
        double a = m->vc - R + 2.0 * R * (k - 1) / N, b = m->vc - R + 2.0 * R * k / N;
        int nb = mix_count(m, b);
        if (nb != na) { /* one change between a and b */
            while (b - a > 4.0 * DBL_EPSILON * fabs(b)) {
                double c = 0.5 * (a + b);
                if (mix_count(m, c) == na)
                    a = c;
                else
                    b = c;
            }
            cut[n++] = b;
        }
        na = nb;
    }
    m->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {mix_y, m};
    double sum = go_qags_cuts(&F, cut, n, m->vc - R, m->vc + R, 1e-17, 1e-13, wo);
    gsl_integration_workspace_free(m->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* aa_filter_radial_slope, which the slivers' bound takes, against the
 * weights written out above: the largest difference quotient of W(d)
 * over 20000 steps across [0, Rc) at most its slope (with the
 * quotients' rounding) and above 0.999 of it (the slope is the least
 * such bound, up to the sampling), and its
 * drop W just inside Rc (0 for the whole cone and the polynomials). */
static void test_slope(void **state)
{
    (void)state;
    for (int n = 0; n < NFILT; n++) {
        filt f = filt_of(n);
        aa_filter af;
        double L, J, q = 0;
        assert_int_equal(aa_filter_parse(f.spec, &af), AA_OK);
        assert_true(aa_filter_radial_slope(&af, &L, &J));
        const int N = 20000;
        double h = f.Rc / N;
        for (int k = 0; k + 1 < N; k++)
            q = fmax(q, fabs(weight2(&f, (k + 1) * h, 0) - weight2(&f, k * h, 0)) / h);
        double jump = weight2(&f, f.Rc * (1 - 1e-12), 0);
        print_message("%-18s slope %.6g (difference quotients up to %.6g), drop %.6g (%.6g)\n",
                      f.spec, L, q, J, jump);
        assert_true(q <= L + 1e-9 && q > 0.999 * L); /* the quotients' rounding: 1e-11 */
        assert_true(fabs(J - jump) <= 1e-9 * (f.N + jump));
    }
    aa_filter box;
    double L, J;
    aa_filter_default(&box);
    assert_false(aa_filter_radial_slope(&box, &L, &J));
}

/* The picture's scene, the radial layer's rectangle ending at x = edge. */
static aa_scene *mix_scene(double edge)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_px(s, -8, -8, edge, H + 8, (aa_rgb){{0, 0, 0}}); /* front: the radial layer */
    set_grad(s, AA_GRADIENT_RADIAL, AA_SPREAD_PAD, (const double[6]){6.5, 7, 4, 6.5, 7, 0},
             mix_r, 2);
    assert_int_equal(aa_scene_set_alpha(s, 0.6), AA_OK);
    rect_px(s, -8, -8, W + 8, H + 8, (aa_rgb){{0, 0, 0}});
    set_grad(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){6.5, -2, 6.5, 10, 0, 0},
             mix_l, 3);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The reference of the picture with the edge at x = edge under the
 * filters fn (nf of them): every bound within 1e-12, no pixel scanned,
 * and the pixels px within their bounds of the 2-D quadrature. */
static void mix_check(const char *what, double edge, const int *fn, int nf, const int (*px)[2],
                      int npx)
{
    aa_scene *s = mix_scene(edge < W + 8 ? edge : W + 8);
    mix m = {0};
    m.cr0 = mix_enc(mix_r[0].colour.c[0]), m.cl = mix_enc(mix_l[1].colour.c[0]);
    m.edge = edge;
    /* the view, or under the sanitizers the pixels' bounding box alone */
    int x0 = 0, y0 = 0, x1 = W - 1, y1 = H - 1;
    if (SAN_SUBSET) {
        x0 = x1 = px[0][0], y0 = y1 = px[0][1];
        for (int k = 1; k < npx; k++) {
            x0 = px[k][0] < x0 ? px[k][0] : x0, x1 = px[k][0] > x1 ? px[k][0] : x1;
            y0 = px[k][1] < y0 ? px[k][1] : y0, y1 = px[k][1] > y1 ? px[k][1] : y1;
        }
        print_message("%s: pixels [%d, %d] x [%d, %d] alone\n", what, x0, x1, y0, y1);
    }
    for (int q = 0; q < nf; q++) {
        filt f = filt_of(fn[q]);
        m.f = &f;
        aa_image ref, bound;
        aa_truth_stats stats;
        if (SAN_SUBSET)
            support_reference_part(s, W, H, x0, y0, x1 - x0 + 1, y1 - y0 + 1, f.spec, &ref,
                                   &bound, &stats);
        else
            reference(s, f.spec, &ref, &bound, &stats);
        print_message("%-18s %s: largest bound %.2g, %zu of %zu pixels scanned\n", f.spec, what,
                      stats.max_bound, stats.scanned, stats.integrated);
        assert_true(stats.max_bound <= 1e-12);
        assert_int_equal(stats.scanned, 0);
        double worst = 0;
        for (int k = 0; k < npx; k++) {
            int i = px[k][0], j = px[k][1];
            double want = mix_pixel(&m, i, j), got = aa_pixel(&ref, i - x0, j - y0)[0];
            double bd = *aa_pixel(&bound, i - x0, j - y0);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd))
                fail_msg("%s under %s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound "
                         "%.3g)",
                         what, f.spec, i, j, got, want, bd);
        }
        print_message("%-18s %s: largest difference from 2-D quadrature %.2g\n", f.spec, what,
                      worst);
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* Under cone:r=1, gauss:s=0.5,cut=2 (a drop at its mask's edge) and
 * radial:k=1,r=1: the pixels where those slivers were widest, the curve's
 * tangency (pixel (6, 3)) and their neighbours. */
static void test_mixed_slivers(void **state)
{
    (void)state;
    static const int fn[3] = {0, 2, 3};
    static const int px[][2] = {{8, 6}, {4, 6}, {8, 8}, {8, 4}, {6, 3}, {5, 3}};
    mix_check("translucent radial over linear", INFINITY, fn, 3, px, 6);
}

/* The radial layer's rectangle ending at x = 7.2, across the curve's
 * lower part (it meets x = 7.2 near y = 3.83): the windows of columns 6
 * and 7 hold that edge, where the composite steps from 0.6 CR + 0.4 CL to
 * CL; under cone:r=1 and radial:k=3,r=1.5 (those windows were scanned
 * under a radial filter before its slivers took a fine bound: 20 pixels
 * under cone:r=1).  The pixels about the curve's meeting with the edge. */
static void test_mixed_edge(void **state)
{
    (void)state;
    static const int fn[2] = {0, 4};
    static const int px[][2] = {{7, 3}, {6, 3}, {7, 4}, {7, 2}, {6, 4}};
    mix_check("the radial layer ending at x = 7.2", 7.2, fn, 2, px, 5);
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_along_x),
        cmocka_unit_test(test_constant),
        cmocka_unit_test(test_radial_2d),
        cmocka_unit_test(test_focal_2d),
        cmocka_unit_test(test_linear_2d),
        cmocka_unit_test(test_slope),
        cmocka_unit_test(test_mixed_slivers),
        cmocka_unit_test(test_mixed_edge),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
