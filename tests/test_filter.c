/*
 * test_filter.c: the filters of patterns/README.md ("Filters").  For every
 * filter in the table
 * the cdf is the integral of the weight (checked by composite Simpson
 * between the kinks, where the weight is smooth), it runs from 0 to 1, it is
 * symmetric, and the declared support holds all but the stated tail.  The
 * cone, which is not separable, has no 1-D weight: its row integral
 * (row_cdf) is checked against Simpson on its 2-D weight along rows, the
 * rows' masses against Simpson across v (volume 1), and known values.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

static const char *const specs[] = {"box", "tent", "tent:r=0.5", "tent:r=2.5", "gauss",
                                    "gauss:s=1", "gauss:s=0.05", NULL};

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

static void test_refusals(void **state)
{
    (void)state;
    aa_filter f;
    const char *bad[] = {"tent:r=-1", "tent:r=0", "tent:r=nan", "gauss:s=-0.5", "gauss:s=inf",
                         "cone:r=0", "cone:r=-1", "cone:r=nan", "cone:r=inf", "cone:r=8.01",
                         "cone:s=1", "tent:s=1", "box:r=1", "gauss:s=100", "lanczos"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        if (aa_filter_parse(bad[k], &f) != AA_EINVAL)
            fail_msg("filter \"%s\" accepted", bad[k]);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_cdf_is_integral),
             cmocka_unit_test(test_known_values),
             cmocka_unit_test(test_cone_rows),
             cmocka_unit_test(test_refusals))
