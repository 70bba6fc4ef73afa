/*
 * test_filter.c: the filters of PATTERNS.md.  For every filter in the table
 * the cdf is the integral of the weight (checked by composite Simpson
 * between the kinks, where the weight is smooth), it runs from 0 to 1, it is
 * symmetric, and the declared support holds all but the stated tail.
 */
#include "aabench.h"

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
                         "cone", "tent:s=1", "box:r=1", "gauss:s=100"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        if (aa_filter_parse(bad[k], &f) != AA_EINVAL)
            fail_msg("filter \"%s\" accepted", bad[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cdf_is_integral),
        cmocka_unit_test(test_known_values),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
