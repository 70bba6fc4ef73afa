/*
 * test_zoneplate.c: the zone plate field (patterns/zoneplate.c) and its
 * exact reference, against answers that do not come from that code:
 *
 *  - the 1-D integrals int w(s) exp(i a (c+s)^2) ds for box, tent and the
 *    untruncated Gaussian, against GSL's adaptive quadrature (QAG with many
 *    subintervals on the bounded supports, QAGI on the whole line for the
 *    Gaussian) of exp(i a (2cs + s^2)) times exp(i a c^2) in long double,
 *    within GSL's own error estimate, at many arguments including large
 *    phases;
 *  - whole pixels of the reference against a 2-D brute-force integration
 *    (QAG nested in QAG of the point function (1 + cos(k r^2))/2 written
 *    here, times the filter weights), within the nested estimates;
 *  - the centre pixel of a low-k plate against its Taylor expansion:
 *    the mean of cos(k (X^2 + Y^2)) over a square [-h, h]^2 is a series in
 *    the moments of the uniform square, in closed form;
 *  - motion: the reference at time t moving (vx, vy) by whole pixels equals
 *    the still reference shifted by hand;
 *  - the scene queries on a field scene, the domain of k, the cache key.
 */
#include "bench.h"
#include "zoneplate.h"
#include "scenes.h"
#include "support.h"

#include <complex.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

static aa_filter filter(const char *text)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(text, &f), AA_OK);
    return f;
}

/* ---- 1-D against quadrature ---- */

typedef struct one_d {
    const aa_filter *f;
    double a, c;
    int imag;
} one_d;

/* w(s) times cos or sin of a (2 c s + s^2): the phase relative to the
 * centre's, small enough to be exact in double. */
static double integrand_1d(double s, void *vp)
{
    const one_d *p = vp;
    double ph = p->a * s * (2.0 * p->c + s);
    return aa_filter_weight(p->f, s) * (p->imag ? sin(ph) : cos(ph));
}

/* GSL's value of one part, and its error estimate. */
static double quad_part(const aa_filter *f, double a, double c, int imag, double *err)
{
    enum { LIMIT = 20000 };
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(LIMIT);
    one_d p = {f, a, c, imag};
    gsl_function F = {integrand_1d, &p};
    double res = 0.0;
    int st;
    if (f->type == &aa_filter_gauss) {
        st = gsl_integration_qagi(&F, 1e-15, 1e-13, LIMIT, ws, &res, err);
    } else {
        double r = f->type == &aa_filter_box ? 0.5 : f->spec.v[0], res2, err2;
        /* the tent's kink at 0 is a breakpoint */
        st = gsl_integration_qag(&F, -r, 0.0, 1e-15, 1e-13, LIMIT, GSL_INTEG_GAUSS61, ws, &res,
                                 err);
        st |= gsl_integration_qag(&F, 0.0, r, 1e-15, 1e-13, LIMIT, GSL_INTEG_GAUSS61, ws, &res2,
                                  &err2);
        res += res2, *err += err2;
    }
    gsl_integration_workspace_free(ws);
    assert_true(st == GSL_SUCCESS || *err < 1e-12);
    return res;
}

/* exp(i a c^2) int w(s) exp(i a (2cs + s^2)) ds, the factor in long double
 * (a c^2 up to 1e4 here: its rounding stays near 1e-15). */
static double complex quad_1d(const aa_filter *f, double a, double c, double *er, double *ei)
{
    double re = quad_part(f, a, c, 0, er), im = quad_part(f, a, c, 1, ei);
    long double ph = (long double)a * c * c;
    double complex rot = CMPLX((double)cosl(ph), (double)sinl(ph));
    double e = fmax(*er, *ei);
    *er = *ei = e + 4e-16; /* the rotation mixes the parts */
    return rot * CMPLX(re, im);
}

static void check_1d(const char *ftext, double a, double c)
{
    aa_filter f = filter(ftext);
    double complex g;
    double bound, er, ei;
    assert_int_equal(aa__zoneplate_1d(&f, a, 0.0, c, 0.0, &g, &bound), AA_OK);
    double complex q = quad_1d(&f, a, c, &er, &ei);
    double re = creal(q), im = cimag(q);
    double tol_r = er + bound + 2e-15, tol_i = ei + bound + 2e-15;
    if (!(fabs(creal(g) - re) <= tol_r && fabs(cimag(g) - im) <= tol_i))
        fail_msg("%s a=%g c=%g: (%.17g, %.17g) vs quadrature (%.17g, %.17g), errors %g %g, "
                 "bound %g",
                 ftext, a, c, creal(g), cimag(g), re, im, er, ei, bound);
    /* the tent's Fresnel form (2 a |c| r > 3 with a small) subtracts terms
     * of size |c|/(a r^2): its bound grows there, past 1e-12 for a < 0.02
     * and |c| > 100 (patterns/README.md, `zoneplate`) */
    assert_true(bound < (f.type == &aa_filter_tent ? 1e-11 : 1e-13));
}

static void test_1d_against_quadrature(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const char *filters[] = {"box", "tent:r=1", "tent:r=0.5", "tent:r=2.5", "gauss:s=0.5",
                             "gauss:s=1"};
    /* a from tiny (almost constant integrand) to large (many turns per
     * pixel); c across both regimes of the code, through 0 and far out */
    const double as[] = {1e-6, 3e-3, 0.0122718, 0.3, 2.0, 7.5, 60.0};
    const double cs[] = {0.0, 0.3, -1.7, 5.25, -40.5, 127.5, 900.0};
    for (size_t fi = 0; fi < sizeof filters / sizeof *filters; fi++)
        for (size_t ai = 0; ai < sizeof as / sizeof *as; ai++)
            for (size_t ci = 0; ci < sizeof cs / sizeof *cs; ci++) {
                /* the quadrature itself cannot follow phases of tens of
                 * thousands of turns per pixel: keep a (c + R) below that */
                if (as[ai] * (fabs(cs[ci]) + 3.0) > 2000.0)
                    continue;
                check_1d(filters[fi], as[ai], cs[ci]);
            }
    /* near the switch of the box and tent between series and Fresnel
     * (a R^2 = 1, 2 a c R = 3) and of Fresnel's series and continued
     * fraction (|t| = 1.5) */
    check_1d("box", 4.0, 0.0);
    check_1d("box", 4.0001, 0.37);
    check_1d("box", 0.5, 3.0);
    check_1d("box", 0.5, 3.0001);
    check_1d("tent:r=1", 1.0, 1.5);
    check_1d("tent:r=1", 0.9999, 1.5001);
    check_1d("box", M_PI / 2 * 2.25 / 4.0, 1.5);
}

/* ---- whole pixels against 2-D quadrature ---- */

typedef struct two_d {
    const aa_filter *f;
    double k, cx, cy, sx, sy, tx, ty; /* pixel centre, placement */
    double u;                         /* outer variable */
    gsl_integration_workspace *inner;
} two_d;

/* The point function of patterns/README.md, `zoneplate`, written here, at
 * pixel-unit (u, v). */
static double plate(const two_d *p, double u, double v)
{
    double x = (u - p->tx) / p->sx - 0.5, y = (v - p->ty) / p->sy - 0.5;
    return 0.5 * (1.0 + cos(p->k * (x * x + y * y)));
}

static double inner_2d(double v, void *vp)
{
    const two_d *p = vp;
    return aa_filter_weight(p->f, v - p->cy) * plate(p, p->u, v);
}

static double outer_2d(double u, void *vp)
{
    two_d *p = vp;
    p->u = u;
    gsl_function F = {inner_2d, p};
    double r = p->f->type == &aa_filter_gauss ? 12.0 * p->f->spec.v[0] : p->f->radius;
    double res = 0, err = 0, res2 = 0, err2 = 0;
    gsl_integration_qag(&F, p->cy - r, p->cy, 1e-15, 1e-14, 2000, GSL_INTEG_GAUSS61, p->inner,
                        &res, &err);
    gsl_integration_qag(&F, p->cy, p->cy + r, 1e-15, 1e-14, 2000, GSL_INTEG_GAUSS61, p->inner,
                        &res2, &err2);
    return aa_filter_weight(p->f, u - p->cx) * (res + res2);
}

/* The pixel (i, j) of a W x H view by brute force; *err: the outer
 * estimate (the inner ones are ten times tighter than the tolerance). */
static double brute_pixel(const aa_filter *f, double k, int w, int h, double t, double vx,
                          double vy, int i, int j, double *err)
{
    two_d p = {f, k, i + 0.5, j + 0.5, w, h, t * vx, t * vy, 0, NULL};
    p.inner = gsl_integration_workspace_alloc(2000);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(2000);
    gsl_function F = {outer_2d, &p};
    /* the Gaussian's weight beyond 12 s is below 1e-31 */
    double r = f->type == &aa_filter_gauss ? 12.0 * f->spec.v[0] : f->radius;
    double res = 0, res2 = 0, e1 = 0, e2 = 0;
    gsl_integration_qag(&F, p.cx - r, p.cx, 1e-15, 1e-13, 2000, GSL_INTEG_GAUSS61, ws, &res,
                        &e1);
    gsl_integration_qag(&F, p.cx, p.cx + r, 1e-15, 1e-13, 2000, GSL_INTEG_GAUSS61, ws, &res2,
                        &e2);
    gsl_integration_workspace_free(ws);
    gsl_integration_workspace_free(p.inner);
    *err = e1 + e2 + 1e-14;
    return res + res2;
}

static void reference(const char *pattern, int w, int h, const char *ftext, double t,
                      double vx, double vy, aa_image *out, aa_image *bound,
                      aa_truth_stats *stats)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .filter = ftext,
                            .threads = 2};
    support_pattern_reference(pattern, &v, out, bound, stats);
}

static void test_pixels_against_brute_force(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const char *filters[] = {"box", "tent:r=1", "gauss:s=0.5"};
    /* corner (aliasing), edge, centre and between, of a 64 x 48 plate with
     * k = 100 (about 16 px per ring at the corner), moving a fraction */
    const int px[][2] = {{0, 0}, {63, 47}, {31, 23}, {10, 40}, {50, 5}};
    double maxdiff = 0.0;
    for (size_t fi = 0; fi < 3; fi++) {
        aa_filter f = filter(filters[fi]);
        aa_image ref, bnd;
        aa_truth_stats stats;
        reference("zoneplate:k=100", 64, 48, filters[fi], 0.25, 1.3, -0.7, &ref, &bnd, &stats);
        assert_true(stats.max_bound < AA_TRUTH_BOUND);
        for (size_t q = 0; q < sizeof px / sizeof *px; q++) {
            double err, want = brute_pixel(&f, 100.0, 64, 48, 0.25, 1.3, -0.7, px[q][0],
                                           px[q][1], &err);
            double got = aa_pixel(&ref, px[q][0], px[q][1])[0];
            double d = fabs(got - want);
            maxdiff = fmax(maxdiff, d);
            if (!(d <= err + *aa_pixel(&bnd, px[q][0], px[q][1])))
                fail_msg("%s pixel (%d, %d): %.17g vs brute force %.17g (error %g)",
                         filters[fi], px[q][0], px[q][1], got, want, err);
        }
        aa_image_free(&ref);
        aa_image_free(&bnd);
    }
    print_message("max |reference - brute force| over the pixels: %.3g\n", maxdiff);
}

/* Box over the square [-h, h]^2 around the plate's centre: with R =
 * X^2 + Y^2 and X, Y independent uniform on [-h, h], <X^(2n)> =
 * h^(2n)/(2n+1), <R^p> = sum_j C(p, j) <X^(2j)> <Y^(2(p-j))>, and the mean
 * of cos(k R) is its Taylor series sum_q (-1)^q k^(2q) <R^(2q)>/(2q)!,
 * summed here to q = 30 (for k h^2 <= 1 the rest is below 1e-40). */
static double centre_mean_cos(double k, double h)
{
    double sum = 0.0, fact = 1.0; /* (2q)! */
    for (int q = 0; q <= 30; q++) {
        int p = 2 * q;
        double moment = 0.0, binom = 1.0;
        for (int j = 0; j <= p; j++) {
            moment += binom * pow(h, 2 * j) / (2 * j + 1) * pow(h, 2 * (p - j)) / (2 * (p - j) + 1);
            binom = binom * (p - j) / (j + 1);
        }
        if (q > 0)
            fact *= (double)(2 * q - 1) * (2 * q);
        sum += (q % 2 ? -1.0 : 1.0) * pow(k, p) * moment / fact;
    }
    return sum;
}

static void test_centre_taylor(void **state)
{
    (void)state;
    /* one pixel of a 1 x 1 image is the whole unit square (h = 1/2); a
     * 3 x 3 image's centre pixel is the square of h = 1/6 */
    const double ks[] = {0.5, 3.0, 4.0};
    for (int q = 0; q < 3; q++) {
        aa_image ref;
        char pat[64];
        snprintf(pat, sizeof pat, "zoneplate:k=%g", ks[q]);
        reference(pat, 1, 1, "box", 0, 0, 0, &ref, NULL, NULL);
        assert_true(fabs(aa_pixel(&ref, 0, 0)[0] - 0.5 * (1 + centre_mean_cos(ks[q], 0.5))) <
                    1e-14);
        aa_image_free(&ref);
        reference(pat, 3, 3, "box", 0, 0, 0, &ref, NULL, NULL);
        assert_true(fabs(aa_pixel(&ref, 1, 1)[0] -
                         0.5 * (1 + centre_mean_cos(ks[q], 1.0 / 6.0))) < 1e-14);
        aa_image_free(&ref);
    }
}

/* I_t(x, y) = I(x - t vx/W, y - t vy/H): moving by whole pixels, pixel
 * (i, j) at time t is pixel (i - t vx, j - t vy) at rest; the still image
 * of a larger canvas would be needed at the borders, so compare inside. */
static void test_motion_is_translation(void **state)
{
    (void)state;
    const char *filters[] = {"box", "tent:r=1", "gauss:s=0.5"};
    for (size_t fi = 0; fi < 3; fi++) {
        aa_image still, moved;
        reference("zoneplate", 96, 80, filters[fi], 0, 0, 0, &still, NULL, NULL);
        reference("zoneplate", 96, 80, filters[fi], 3, 2, -1, &moved, NULL, NULL);
        double worst = 0;
        for (int j = 3; j < 80; j++)
            for (int i = 0; i < 96 - 6; i++)
                worst = fmax(worst, fabs(aa_pixel(&moved, i + 6, j - 3)[0] -
                                         aa_pixel(&still, i, j)[0]));
        assert_true(worst < 1e-12);
        aa_image_free(&still);
        aa_image_free(&moved);
    }
}

/* ---- the scene, the pattern, the key ---- */

static void test_field_scene_queries(void **state)
{
    (void)state;
    aa_spec spec;
    aa_scene *s = scenes_pattern("zoneplate:k=10"), *placed;
    const double *p;
    int n;
    double map[4];
    assert_non_null(aa_scene_field(s, &p, &n, map));
    assert_int_equal(n, 1);
    assert_true(p[0] == 10.0);
    /* colour_at is the definition: (1 + cos(k r^2))/2, also outside the
     * unit square (no background) */
    const double pts[][2] = {{0.5, 0.5}, {0.1, 0.9}, {-3.0, 2.5}};
    for (int q = 0; q < 3; q++) {
        double X = pts[q][0] - 0.5, Y = pts[q][1] - 0.5;
        aa_rgb c = aa_scene_colour_at(s, pts[q][0], pts[q][1]);
        assert_true(fabs(c.c[0] - 0.5 * (1 + cos(10 * (X * X + Y * Y)))) < 1e-15);
        assert_true(c.c[0] == c.c[1] && c.c[1] == c.c[2]);
    }
    assert_true(aa_scene_is_grey(s));
    assert_int_equal(aa_scene_layer_count(s), 0);
    double x0, y0, x1, y1;
    assert_int_equal(aa_scene_bounds(s, &x0, &y0, &x1, &y1), 1);
    assert_true(isinf(x0) && x0 < 0 && isinf(y0) && y0 < 0 && isinf(x1) && isinf(y1));
    aa_crossing cr[4];
    size_t idx[4];
    assert_int_equal(aa_scene_crossings(s, 0.5, cr, 4), 0);
    assert_int_equal(aa_scene_touching(s, 0, 0, 1, 1, idx, 4), 0);
    /* placed at 40 x 20, time 2 moving (3, -1): pixel point (u, v) shows
     * pattern point ((u - 6)/40, (v + 2)/20) */
    assert_non_null(placed = aa_scene_place(s, 40, 20, 2, 3, -1));
    aa_rgb a = aa_scene_colour_at(placed, 17.25, 3.5), b = aa_scene_colour_at(s, 11.25 / 40,
                                                                               5.5 / 20);
    assert_true(fabs(a.c[0] - b.c[0]) < 1e-14);
    aa_scene_free(placed);
    /* a field scene takes no layers */
    aa_rgb white = {{1, 1, 1}};
    aa_scene *t = aa_scene_new(white);
    assert_int_equal(aa_pattern_parse("zoneplate", &spec), AA_OK);
    const aa_pattern_type *type = (const aa_pattern_type *)spec.info;
    assert_int_equal(type->build(spec.v, t), AA_OK);
    assert_int_equal(aa_scene_layer(t, white, AA_FILL_NONZERO), AA_EINVAL);
    aa_scene_free(t);
    aa_scene_free(s);
}

static void test_domain_and_key(void **state)
{
    (void)state;
    aa_spec spec;
    assert_int_equal(aa_pattern_parse("zoneplate:k=0", &spec), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("zoneplate:k=-1", &spec), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("zoneplate:k=2e6", &spec), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("zoneplate:k=inf", &spec), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("zoneplate:k=1e6", &spec), AA_OK);
    assert_int_equal(aa_pattern_parse("zoneplate", &spec), AA_OK);
    assert_true(spec.v[0] == 256.0 * M_PI);
    /* the key names the field, its version and its parameters */
    aa_view v1, v2;
    memset(&v1, 0, sizeof v1);
    memset(&v2, 0, sizeof v2);
    assert_int_equal(aa_pattern_parse("zoneplate:k=100", &v1.pattern), AA_OK);
    assert_int_equal(aa_pattern_parse("zoneplate:k=100.5", &v2.pattern), AA_OK);
    v1.w = v2.w = v1.h = v2.h = 8;
    v1.filter = v2.filter = filter("box");
    char k1[2048], k2[2048];
    assert_int_equal(aa_view_key(&v1, k1, sizeof k1), AA_OK);
    assert_int_equal(aa_view_key(&v2, k2, sizeof k2), AA_OK);
    assert_non_null(strstr(k1, "field zoneplate 1 100\n"));
    assert_non_null(strstr(k2, "field zoneplate 1 100.5\n"));
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_1d_against_quadrature),
             cmocka_unit_test(test_pixels_against_brute_force),
             cmocka_unit_test(test_centre_taylor),
             cmocka_unit_test(test_motion_is_translation),
             cmocka_unit_test(test_field_scene_queries),
             cmocka_unit_test(test_domain_and_key))
