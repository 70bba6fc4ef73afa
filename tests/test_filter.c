/*
 * test_filter.c: the filters of patterns/README.md ("Filters").  For every
 * filter in the table
 * the cdf is the integral of the weight (checked by composite Simpson
 * between the kinks, where the weight is smooth), it runs from 0 to 1, it is
 * symmetric, and the declared support holds all but the stated tail.  The
 * cone, which is not separable, has no 1-D weight: its row integral
 * (row_cdf) is checked against Simpson on its 2-D weight along rows, the
 * rows' masses against Simpson across v (volume 1), and known values.
 * The Gaussian in a circular mask and the truncated cone likewise, their
 * volumes 1 by Gauss-Legendre in polar coordinates, their peaks in closed
 * form.  The polynomial filters' masses are 1 from their published pieces
 * integrated here; the cubic B-spline is mitchell:b=1,c=0; Lanczos's
 * normalisation agrees with GSL's quadrature of sinc(t) sinc(t / a); the
 * negative masses aa_filter_range states agree with closed forms.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <cmocka.h>

static const char *const specs[] = {"box",
                                    "tent",
                                    "tent:r=0.5",
                                    "tent:r=2.5",
                                    "gauss",
                                    "gauss:s=1",
                                    "gauss:s=0.05",
                                    "bspline:order=2",
                                    "bspline",
                                    "mitchell",
                                    "mitchell:b=1,c=0",
                                    "mitchell:b=0.5,c=0.75",
                                    "mitchell:b=0,c=1",
                                    "catrom",
                                    "lanczos:a=2",
                                    "lanczos",
                                    NULL};

/* Simpson's rule on [a, b] with n panels (n even): exact for cubics. */
static double simpson(const aa_filter *f, double a, double b, int n)
{
    double h = (b - a) / n, sum = aa_filter_weight(f, a) + aa_filter_weight(f, b);
    for (int k = 1; k < n; k++)
        sum += (k % 2 ? 4 : 2) * aa_filter_weight(f, a + k * h);
    return sum * h / 3;
}

static void test_cdf_is_integral(void **state)
{
    (void)state;
    for (const char *const *s = specs; *s; s++) {
        aa_filter f;
        assert_int_equal(aa_filter_parse(*s, &f), AA_OK);
        assert_true(aa_filter_is_separable(&f));
        double kink[8], pts[16];
        int nk = f.type->kinks(f.spec.v, kink), np = 0;
        double R = f.radius;
        pts[np++] = -R;
        for (int k = 0; k < nk; k++)
            if (kink[k] > -R && kink[k] < R)
                pts[np++] = kink[k];
        pts[np++] = R;
        /* between kinks the weight is a polynomial (box, tent) or smooth
         * (Gaussian): Simpson with 4000 panels is exact or ~1e-14 */
        for (int k = 0; k + 1 < np; k++) {
            double a = pts[k], b = pts[k + 1], half = 0.5 * (a + b);
            double num = simpson(&f, a + 1e-300, half, 4000) + simpson(&f, half, b - 1e-300, 4000);
            double exact = aa_filter_cdf(&f, b) - aa_filter_cdf(&f, a);
            if (fabs(num - exact) > 1e-12)
                fail_msg("%s on [%g, %g]: Simpson %.17g, cdf %.17g", *s, a, b, num, exact);
        }
        assert_true(aa_filter_cdf(&f, -1e9) == 0.0);
        assert_true(aa_filter_cdf(&f, 1e9) == 1.0);
        for (double t = -3; t <= 3; t += 0.125)
            assert_true(fabs(aa_filter_cdf(&f, t) + aa_filter_cdf(&f, -t) - 1.0) < 1e-15);
        /* the 1-D mass outside the support is within the stated 2-D loss */
        double outside = aa_filter_cdf(&f, -R) + 1.0 - aa_filter_cdf(&f, R);
        assert_true(outside <= f.lost + 1e-300 && f.lost <= 1e-14);
    }
}

/* Simpson on u in [a, b] of the 2-D weight at height v. */
static double simpson_row(const aa_filter *f, double v, double a, double b, int n)
{
    double h = (b - a) / n, sum = aa_filter_weight2(f, a, v) + aa_filter_weight2(f, b, v);
    for (int k = 1; k < n; k++)
        sum += (k % 2 ? 4 : 2) * aa_filter_weight2(f, a + k * h, v);
    return sum * h / 3;
}

/* The cone: the row integral is the integral of the 2-D weight along the
 * row (Simpson between the row's kinks: the chord's ends and u = 0, where
 * sqrt(u^2 + v^2) is not smooth at v = 0), zero left of the chord and the
 * row's mass right of it; the masses of the rows integrate to 1 (Simpson
 * in v on [-r, 0] and [0, r], where the mass has its v^2 log|v| term: 1e-9
 * with 20000 panels); separable filters give w(v) cdf(u) through the same
 * call. */
static void test_cone_rows(void **state)
{
    (void)state;
    const char *cones[] = {"cone", "cone:r=0.5", "cone:r=2.5", "cone:r=8"};
    for (int k = 0; k < 4; k++) {
        aa_filter f;
        assert_int_equal(aa_filter_parse(cones[k], &f), AA_OK);
        assert_false(aa_filter_is_separable(&f));
        double r = f.spec.v[0];
        assert_true(f.radius == r && f.lost == 0.0);
        for (double y = -0.95; y < 1.0; y += 0.1375) {
            double v = y * r, c = r * sqrt(1.0 - y * y);
            const double us[] = {-c, -0.4 * c, 0.0, 0.3 * c, c};
            assert_true(aa_filter_row_cdf(&f, v, -c - 1e-9) == 0.0);
            for (int q = 0; q < 5; q++) {
                double u = us[q], num = 0.0;
                if (u > 0.0)
                    num = simpson_row(&f, v, -c, 0.0, 4000) + simpson_row(&f, v, 0.0, u, 4000);
                else
                    num = simpson_row(&f, v, -c, u, 4000);
                double got = aa_filter_row_cdf(&f, v, u);
                if (fabs(num - got) > 1e-11 / r)
                    fail_msg("%s v=%g u=%g: Simpson %.17g, row_cdf %.17g", cones[k], v, u, num,
                             got);
            }
            assert_true(aa_filter_row_cdf(&f, v, c + 1.0) == aa_filter_row_cdf(&f, v, 1e9));
        }
        /* the volume: Simpson across v of the rows' masses */
        const int n = 20000;
        double h = r / n, vol = 0.0;
        for (int m = 0; m <= n; m++) {
            double wgt = (m == 0 || m == n) ? 1.0 : (m % 2 ? 4.0 : 2.0);
            vol += 2.0 * wgt * aa_filter_row_cdf(&f, m * h, 2.0 * r);
        }
        vol *= h / 3.0;
        if (fabs(vol - 1.0) > 1e-9)
            fail_msg("%s: volume %.17g", cones[k], vol);
        /* outside the disc the weight is 0, the rows are empty */
        assert_true(aa_filter_weight2(&f, 0.8 * r, 0.61 * r) == 0.0);
        assert_true(aa_filter_row_cdf(&f, r, 0.0) == 0.0 && aa_filter_row_cdf(&f, -2 * r, 0.0) == 0.0);
    }
    /* known values, r = 1: the peak 3/pi; the row through the centre has
     * mass (3/pi) int_-1^1 (1 - |u|) du = 3/pi, half of it left of 0 */
    aa_filter f;
    assert_int_equal(aa_filter_parse("cone", &f), AA_OK);
    assert_true(fabs(aa_filter_weight2(&f, 0.0, 0.0) - 0.95492965855137202) < 1e-16);
    assert_true(fabs(aa_filter_weight2(&f, 0.3, 0.4) - 0.5 * 0.95492965855137202) < 1e-16);
    assert_true(fabs(aa_filter_row_cdf(&f, 0.0, 0.0) - 0.47746482927568601) < 1e-16);
    assert_true(fabs(aa_filter_row_cdf(&f, 0.0, 5.0) - 0.95492965855137202) < 1e-16);
    /* the generic calls on a separable filter: w(v) cdf(u), w(u) w(v) */
    assert_int_equal(aa_filter_parse("tent", &f), AA_OK);
    assert_true(aa_filter_row_cdf(&f, 0.5, 0.5) == 0.5 * 0.875);
    assert_true(aa_filter_weight2(&f, 0.5, 0.25) == 0.5 * 0.75);
}

static void test_known_values(void **state)
{
    (void)state;
    aa_filter f;
    /* tent r = 1: the area left of 1/2 is 1 minus the triangle from 1/2 to 1,
     * 1 - (1/2)(1/2)(1/2) = 7/8; weight at 0 is 1/r = 1 */
    assert_int_equal(aa_filter_parse("tent", &f), AA_OK);
    assert_true(fabs(aa_filter_cdf(&f, 0.5) - 0.875) < 1e-16);
    assert_true(aa_filter_cdf(&f, 0.0) == 0.5 && aa_filter_weight(&f, 0.0) == 1.0);
    assert_true(f.radius == 1.0);
    /* tent r = 0.5 (Crow fig. 2.13, base one pixel): weight 2 at the centre */
    assert_int_equal(aa_filter_parse("tent:r=0.5", &f), AA_OK);
    assert_true(aa_filter_weight(&f, 0.0) == 2.0 && aa_filter_weight(&f, 0.25) == 1.0);
    /* Gaussian s: cdf(s) = Phi(1) = 0.841344746068542948... (normal tables) */
    assert_int_equal(aa_filter_parse("gauss:s=0.5", &f), AA_OK);
    assert_true(fabs(aa_filter_cdf(&f, 0.5) - 0.84134474606854295) < 1e-15);
    assert_true(fabs(aa_filter_weight(&f, 0.0) - 0.79788456080286536) < 1e-15); /* 1/(s sqrt(2 pi)) */
    /* box: area sampling */
    aa_filter_default(&f);
    assert_true(aa_filter_is_box(&f) && f.radius == 0.5 && f.lost == 0.0);
    assert_true(aa_filter_cdf(&f, 0.25) == 0.75);
}

/* Mitchell and Netravali (1988), eq. 8, in x = |t|: the inner piece's and
 * the outer piece's monomial coefficients; their integrals from 0 to 1 and
 * 1 to 2 term by term. */
static double mitchell_half_mass(double B, double C, double *outer_neg)
{
    const double in[4] = {(6 - 2 * B) / 6, 0, (-18 + 12 * B + 6 * C) / 6, (12 - 9 * B - 6 * C) / 6};
    const double out[4] = {(8 * B + 24 * C) / 6, (-12 * B - 48 * C) / 6, (6 * B + 30 * C) / 6,
                           (-B - 6 * C) / 6};
    double m = 0;
    for (int d = 0; d < 4; d++)
        m += in[d] / (d + 1) + out[d] * (pow(2, d + 1) - 1) / (d + 1);
    /* the outer piece is negative from its root x0 in (1, 2) to 2, where it
     * has a double root: (x - 2)^2 (c3 x + e), e = c0 / 4 */
    double e = out[0] / 4, x0 = out[3] != 0 ? -e / out[3] : 2;
    *outer_neg = 0;
    if (x0 < 2) {
        x0 = fmax(x0, 1);
        for (int d = 0; d < 4; d++)
            *outer_neg -= out[d] * (pow(2, d + 1) - pow(x0, d + 1)) / (d + 1);
    }
    return m;
}

static void test_polynomial_filters(void **state)
{
    (void)state;
    const double bc[][2] = {{1.0 / 3, 1.0 / 3}, {1, 0}, {0, 0.5}, {0.5, 0.75}, {0, 1}, {1, 1}};
    for (size_t k = 0; k < sizeof bc / sizeof *bc; k++) {
        double neg, half = mitchell_half_mass(bc[k][0], bc[k][1], &neg);
        if (fabs(2 * half - 1) > 1e-15)
            fail_msg("mitchell b=%g c=%g: mass %.17g", bc[k][0], bc[k][1], 2 * half);
        char spec[64];
        snprintf(spec, sizeof spec, "mitchell:b=%.17g,c=%.17g", bc[k][0], bc[k][1]);
        aa_filter f;
        assert_int_equal(aa_filter_parse(spec, &f), AA_OK);
        double lo, hi, n = 2 * neg, N = 2 * n * (1 + n);
        aa_filter_range(&f, &lo, &hi);
        if (!(lo <= -N && lo >= -N * 1.0025 - 1e-15 && hi == 1 - lo))
            fail_msg("%s: range [%.17g, %.17g], negative mass %.17g", spec, lo, hi, N);
    }
    /* quadratic B-spline: 3/4 - x^2 on [0, 1/2], (x - 3/2)^2 / 2 on [1/2, 3/2]:
     * 3/8 - 1/24 + 1/6 = 1/2 */
    aa_filter f, g;
    assert_int_equal(aa_filter_parse("bspline:order=2", &f), AA_OK);
    assert_true(fabs(aa_filter_cdf(&f, -0.5) - 1.0 / 6) < 1e-16);
    assert_true(aa_filter_weight(&f, 0) == 0.75 && f.radius == 1.5);
    /* the cubic B-spline: 1/24 left of -1, weight 2/3 at 0, and it is
     * mitchell:b=1,c=0 */
    assert_int_equal(aa_filter_parse("bspline", &f), AA_OK);
    assert_int_equal(aa_filter_parse("mitchell:b=1,c=0", &g), AA_OK);
    assert_true(fabs(aa_filter_cdf(&f, -1) - 1.0 / 24) < 1e-17);
    assert_true(fabs(aa_filter_weight(&f, 0) - 2.0 / 3) < 1e-16 && f.radius == 2);
    for (double t = -2.5; t <= 2.5; t += 0.0625) {
        assert_true(fabs(aa_filter_weight(&f, t) - aa_filter_weight(&g, t)) < 1e-16);
        assert_true(fabs(aa_filter_cdf(&f, t) - aa_filter_cdf(&g, t)) < 1e-16);
    }
    /* Catmull-Rom: mitchell:b=0,c=0.5, weight 1 at 0, 0 at +-1 and +-2 */
    assert_int_equal(aa_filter_parse("catrom", &f), AA_OK);
    assert_int_equal(aa_filter_parse("mitchell:b=0,c=0.5", &g), AA_OK);
    assert_true(aa_filter_weight(&f, 0) == 1 && aa_filter_weight(&f, 1) == 0);
    for (double t = -2.5; t <= 2.5; t += 0.0625)
        assert_true(aa_filter_cdf(&f, t) == aa_filter_cdf(&g, t));
    /* no negative lobes: [0, 1] */
    const char *pos[] = {"box", "tent", "gauss", "bspline", "bspline:order=2", "cone",
                         "gauss:s=1,cut=2", "mitchell:b=1,c=0"};
    for (size_t k = 0; k < sizeof pos / sizeof *pos; k++) {
        double lo, hi;
        assert_int_equal(aa_filter_parse(pos[k], &f), AA_OK);
        aa_filter_range(&f, &lo, &hi);
        if (!(lo == 0 && hi == 1))
            fail_msg("%s: range [%g, %g]", pos[k], lo, hi);
    }
}

static double sinc2(double t, void *pa)
{
    double a = *(double *)pa, x = M_PI * t, y = x / a;
    return (x == 0 ? 1 : sin(x) / x) * (y == 0 ? 1 : sin(y) / y);
}

/* Lanczos: 1 / weight(0) is the integral of sinc(t) sinc(t / a), here by
 * GSL's QAG between the integers; its negative mass (1 < |t| < 2, and for
 * a = 3 nothing else) against aa_filter_range. */
static void test_lanczos(void **state)
{
    (void)state;
    gsl_set_error_handler_off(); /* judged by the estimate */
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
    for (double a = 2; a <= 3; a++) {
        gsl_function F = {sinc2, &a};
        double whole = 0, neg = 0, err = 0;
        for (int k = 0; k < (int)a; k++) {
            double r, e;
            gsl_integration_qag(&F, k, k + 1, 1e-16, 1e-15, 100, GSL_INTEG_GAUSS61, ws, &r, &e);
            err += 2 * e;
            whole += 2 * r;
            if (r < 0)
                neg -= 2 * r;
        }
        char spec[32];
        snprintf(spec, sizeof spec, "lanczos:a=%g", a);
        aa_filter f;
        assert_int_equal(aa_filter_parse(spec, &f), AA_OK);
        double got = 1 / aa_filter_weight(&f, 0);
        assert_true(err < 1e-13);
        if (fabs(got - whole) > err + 1e-15)
            fail_msg("%s: mass %.17g, quadrature %.17g +- %.2e", spec, got, whole, err);
        double lo, hi, n = neg / whole, N = 2 * n * (1 + n);
        aa_filter_range(&f, &lo, &hi);
        if (!(lo <= -N && lo >= -N * 1.0025))
            fail_msg("%s: range [%.17g, %.17g], negative mass %.17g", spec, lo, hi, N);
        print_message("%s: mass %.17g (quadrature %.17g +- %.1e), negative mass %.6f\n", spec,
                      got, whole, err, N);
    }
    gsl_integration_workspace_free(ws);
}

/* The volume of a radial filter, 2 pi int_0^R w(rho, 0) rho drho, by
 * GSL's 20-point Gauss-Legendre rule. */
static double radial_volume(const aa_filter *f)
{
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(20);
    double R = f->radius, vol = 0;
    for (int k = 0; k < 20; k++) {
        double x, w;
        gsl_integration_glfixed_point(0, R, (size_t)k, &x, &w, t);
        vol += 2 * M_PI * w * x * aa_filter_weight2(f, x, 0);
    }
    gsl_integration_glfixed_table_free(t);
    return vol;
}

static void test_masks(void **state)
{
    (void)state;
    const char *masks[] = {"gauss:s=1,cut=2", "gauss:s=0.5,cut=3", "gauss:s=2,cut=0.5",
                           "cone:r=2,cut=0.5", "cone:r=1,cut=0.9", "cone:r=0.7"};
    for (size_t k = 0; k < sizeof masks / sizeof *masks; k++) {
        aa_filter f;
        assert_int_equal(aa_filter_parse(masks[k], &f), AA_OK);
        assert_false(aa_filter_is_separable(&f));
        int cone = f.type == &aa_filter_cone;
        assert_true(cone || f.type == &aa_filter_gauss_mask);
        double s = f.spec.v[0], K = f.spec.v[1], rc = s * K;
        assert_true(f.radius == rc && f.lost == 0 && aa_filter_support(&f) == rc);
        /* the peak: 1 / volume inside the mask, in closed form */
        double peak = cone ? 1 / (2 * M_PI * s * s * (K * K / 2 - K * K * K / 3))
                           : 1 / (2 * M_PI * s * s * (1 - exp(-K * K / 2)));
        assert_true(fabs(aa_filter_weight2(&f, 0, 0) - peak) < 1e-15 * peak);
        /* the volume (Gauss-Legendre is exact for the cone's polynomial
         * and within 1e-15 for the Gaussian on the disc) */
        double vol = radial_volume(&f);
        if (fabs(vol - 1) > 1e-14)
            fail_msg("%s: volume %.17g", masks[k], vol);
        /* outside the mask nothing, the rows there empty */
        assert_true(aa_filter_weight2(&f, 0.8 * rc, 0.61 * rc) == 0);
        assert_true(aa_filter_row_cdf(&f, rc, 0) == 0 && aa_filter_row_cdf(&f, -2 * rc, 5) == 0);
        /* the rows: Simpson on the weight between the chord's ends and 0 */
        for (double y = -0.95; y < 1.0; y += 0.1375) {
            /* the weight jumps at the mask: Simpson from just inside it */
            double v = y * rc, c = rc * sqrt(1 - y * y), ci = c * (1 - 1e-13);
            const double us[] = {-ci, -0.4 * c, 0.0, 0.3 * c, ci};
            assert_true(aa_filter_row_cdf(&f, v, -c - 1e-9) == 0);
            for (int q = 0; q < 5; q++) {
                double u = us[q];
                double num = u > 0 ? simpson_row(&f, v, -ci, 0, 4000) + simpson_row(&f, v, 0, u, 4000)
                                   : simpson_row(&f, v, -ci, u, 4000);
                double got = aa_filter_row_cdf(&f, v, u);
                if (fabs(num - got) > 1e-11 / rc)
                    fail_msg("%s v=%g u=%g: Simpson %.17g, row_cdf %.17g", masks[k], v, u, num,
                             got);
            }
        }
    }
    /* the whole cone is as it was: cut=1 the default */
    aa_filter f;
    assert_int_equal(aa_filter_parse("cone:r=1,cut=1", &f), AA_OK);
    assert_true(aa_filter_weight2(&f, 0, 0) == 3 / M_PI);
    /* cut=0: the untruncated, separable Gaussian */
    assert_int_equal(aa_filter_parse("gauss:s=1,cut=0", &f), AA_OK);
    assert_true(f.type == &aa_filter_gauss && aa_filter_is_separable(&f));
}

static void test_refusals(void **state)
{
    (void)state;
    aa_filter f;
    const char *bad[] = {"tent:r=-1", "tent:r=0", "tent:r=nan", "gauss:s=-0.5", "gauss:s=inf",
                         "cone:r=0", "cone:r=-1", "cone:r=nan", "cone:r=inf", "cone:r=8.01",
                         "cone:s=1", "tent:s=1", "box:r=1", "gauss:s=100", "lanczos:a=4",
                         "lanczos:a=1", "lanczos:a=2.5", "bspline:order=1", "bspline:order=4",
                         "mitchell:b=-0.1", "mitchell:c=1.5", "catrom:b=0", "gauss:cut=-1",
                         "gauss:cut=41", "cone:cut=0", "cone:cut=1.5", "cone:cut=-1"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        if (aa_filter_parse(bad[k], &f) != AA_EINVAL)
            fail_msg("filter \"%s\" accepted", bad[k]);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_cdf_is_integral),
             cmocka_unit_test(test_known_values),
             cmocka_unit_test(test_cone_rows),
             cmocka_unit_test(test_polynomial_filters),
             cmocka_unit_test(test_lanczos),
             cmocka_unit_test(test_masks),
             cmocka_unit_test(test_refusals))
