/*
 * test_oracle.c - checks the independent `crow` oracle (oracle.c) against
 * facts derived by hand from patterns/README.md, `crow`.  Each expected value
 * says where it comes from.  The arcs the tests use are built by that
 * definition's literal recursion a_{k+1} = a_k + g_k, not by the oracle's
 * closed form.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

/* The closed form's 1e-15 tolerances count on long double's 64-bit
 * mantissa; where long double is no wider than double (valgrind emulates
 * the x87 unit in double) those checks are skipped. */
static void needs_extended_precision(void)
{
    volatile long double one = 1.0L, tiny = 0x1p-60L;
    if (one + tiny == one) {
        print_message("long double is not extended here: skipped\n");
        skip();
    }
}

#include "oracle.h"

#define CHECK_NEAR(got, want, tol)                                             \
	do {                                                                   \
		double got_ = (got), want_ = (want), tol_ = (tol);             \
		if (!(fabs(got_ - want_) <= tol_))                             \
			fail_msg("%s = %.17g, expected %.17g within %.3g "     \
				 "(off by %.3g)",                              \
				 #got, got_, want_, tol_, fabs(got_ - want_)); \
	} while (0)

static const double pi = 3.14159265358979323846;

/* ---- facts derived from patterns/README.md ------------------------------- */

#define MAXARCS 128

/* The arcs x_k = a_k + c_k (y - 1/2)^2 by patterns/README.md's recursion. */
struct arcs {
	int n;
	double a[MAXARCS], c[MAXARCS];
};

static void literal_arcs(const oracle_crow *p, struct arcs *A)
{
	int n = p->curves;
	double g[MAXARCS], s = 0;
	assert_true(n >= 2 && n <= MAXARCS);
	for (int k = 0; k <= n - 2; k++) {
		g[k] = n == 2 ? p->gap0 : p->gap0 + (p->gap1 - p->gap0) * k / (n - 2);
		s += g[k];
	}
	A->n = n;
	A->a[0] = (1 - s) / 2;
	for (int k = 0; k + 1 < n; k++)
		A->a[k + 1] = A->a[k] + g[k];
	for (int k = 0; k < n; k++)
		A->c[k] = p->kmax * (1 - (double)k / (n - 1));
}

/* Total white area, for arcs inside the unit square.  Band m lies between
 * arcs 2m and 2m+1, width x_{2m+1} - x_{2m} = g_{2m} - C t^2/(N-1) with
 * t = y - 1/2 (c_{k+1} - c_k = -C/(N-1)); the integral of t^2 over
 * [-1/2, 1/2] is 1/12, and sum_{m < N/2} g_{2m} = (N/2) gap0 + (gap1 - gap0)
 * (2/(N-2)) (N/2)(N/2 - 1)/2 = N (gap0 + gap1)/4.  So
 *     A = N (gap0 + gap1)/4 - N C/(24 (N-1))        (N >= 4)
 *     A = gap0 - C/12                                (N = 2, g_0 = gap0). */
static double white_area(const oracle_crow *p)
{
	double n = p->curves;
	if (p->curves == 2)
		return p->gap0 - p->kmax / 12;
	return n * (p->gap0 + p->gap1) / 4 - n * p->kmax / (24 * (n - 1));
}

/* Antiderivatives of the one-dimensional filters (patterns/README.md, "Filters"):
 * the tent (1 - |t|/R)/R integrates to (t+R)^2/(2R^2) on [-R, 0] and
 * 1 - (R-t)^2/(2R^2) on [0, R]; the Gaussian to erfc(-t/(S sqrt 2))/2. */
static double tent_cdf(double t, double r)
{
	if (t <= -r)
		return 0;
	if (t >= r)
		return 1;
	return t <= 0 ? (t + r) * (t + r) / (2 * r * r)
		      : 1 - (r - t) * (r - t) / (2 * r * r);
}

static double gauss_cdf(double t, double s)
{
	return 0.5 * erfc(-t / (s * sqrt(2.0)));
}

/* A pattern with C = 0 is vertical stripes [a_2m, a_2m+1] x [0, 1], so with a
 * separable filter P = (sum over bands of the u-mass) * (v-mass over [0, H]),
 * each mass a difference of antiderivatives. */
static double stripes_value(const struct arcs *A, int W, int H, int i, int j,
			    double (*cdf)(double, double), double r)
{
	double uc = i + 0.5, vc = j + 0.5, across = 0;
	for (int m = 0; m + 1 < A->n; m += 2) {
		double u0 = fmax(W * A->a[m], 0), u1 = fmin(W * A->a[m + 1], W);
		if (u1 > u0)
			across += cdf(u1 - uc, r) - cdf(u0 - uc, r);
	}
	return across * (cdf(H - vc, r) - cdf(-vc, r));
}

static const oracle_crow crow_default = { 96, 0.6, 4.0 / 256, 0.5 / 256 };
/* N = 2: a_0 = -0.1, a_1 = 1.1, so arc 1 lies right of the square and arc 0
 * (vertex -0.1, ends 0.9) leaves it through x = 0: the square clips the band. */
static const oracle_crow crow_clipped = { 2, 4.0, 1.2, 0 };
/* C < 0: arcs bend left; gaps 0.1 down to 0.02, closest at mid-height. */
static const oracle_crow crow_bent_left = { 8, -0.3, 0.1, 0.02 };
/* N = 2: arc 0 from 0.35 (vertex) to 0.5, arc 1 the vertical line x = 0.65. */
static const oracle_crow crow_pair = { 2, 0.6, 0.3, 0 };

/* ---- parameters and the pattern ------------------------------------------ */

static void test_defaults(void **state)
{
	(void)state;
	oracle_crow p = oracle_crow_defaults(); /* patterns/README.md's table */
	assert_int_equal(p.curves, 96);
	assert_true(p.kmax == 0.6 && p.gap0 == 4.0 / 256 && p.gap1 == 0.5 / 256);
	assert_true(oracle_crow_valid(&p));
}

static void test_valid(void **state)
{
	(void)state;
	oracle_crow p = crow_default;
	assert_true(oracle_crow_valid(&p));
	int bad_n[] = { 95, 3, 1, 0, -2 }; /* "even, at least 2" */
	for (size_t k = 0; k < sizeof bad_n / sizeof *bad_n; k++) {
		p = crow_default;
		p.curves = bad_n[k];
		assert_false(oracle_crow_valid(&p));
	}
	/* Touching: the last gap is gap1 and the rule is gap1 - C/(4(N-1)) > 0;
	 * C = 4 * 95 * 0.5/256 = 0.7421875 (exact in binary) makes it 0. */
	p = crow_default;
	p.kmax = 0.7421875;
	assert_false(oracle_crow_valid(&p));
	p.kmax = 0.742; /* just below: valid */
	assert_true(oracle_crow_valid(&p));
	/* N = 2: g_0 = gap0 = C/4 touches at y = 0 and 1. */
	oracle_crow two = { 2, 0.25, 1.0 / 16, 0 };
	assert_false(oracle_crow_valid(&two));
	two.gap0 = 0.0625 + 1.0 / 1024;
	assert_true(oracle_crow_valid(&two));
	/* C < 0 with negative gaps: the literal rule g - C/(4(N-1)) > 0 holds
	 * (-0.001 + 1/380 > 0), but the arcs cross at mid-height, where the gap
	 * is g itself; an oracle_crow_valid() refuses it. */
	oracle_crow crossing = { 96, -1.0, -0.001, -0.001 };
	assert_false(oracle_crow_valid(&crossing));
	assert_true(oracle_crow_valid(&crow_bent_left));
	assert_true(oracle_crow_valid(&crow_clipped));
	assert_true(oracle_crow_valid(&crow_pair));
	oracle_crow stripes = { 96, 0, 4.0 / 256, 0.5 / 256 };
	assert_true(oracle_crow_valid(&stripes));
	p = crow_default;
	p.gap1 = NAN;
	assert_false(oracle_crow_valid(&p));
	p = crow_default;
	p.kmax = INFINITY;
	assert_false(oracle_crow_valid(&p));
	assert_false(oracle_crow_valid(NULL));
}

static void test_point(void **state)
{
	(void)state;
	struct arcs A;
	literal_arcs(&crow_default, &A);
	const oracle_crow *p = &crow_default;
	/* At mid-height x_k = a_k: left of arc 0 black, band 0 white, the band
	 * between arcs 1 and 2 black, right of arc N-1 black. */
	assert_int_equal(oracle_crow_point(p, A.a[0] / 2, 0.5), 0);
	assert_int_equal(oracle_crow_point(p, (A.a[0] + A.a[1]) / 2, 0.5), 1);
	assert_int_equal(oracle_crow_point(p, (A.a[1] + A.a[2]) / 2, 0.5), 0);
	assert_int_equal(oracle_crow_point(p, (A.a[94] + A.a[95]) / 2, 0.5), 1);
	assert_int_equal(oracle_crow_point(p, (A.a[95] + 1) / 2, 0.5), 0);
	/* At y = 0 arc 0 is at a_0 + C/4: a point between a_0 and that is black. */
	assert_int_equal(oracle_crow_point(p, A.a[0] + 0.1, 0.0), 0);
	/* Outside the unit square: black. */
	assert_int_equal(oracle_crow_point(p, (A.a[0] + A.a[1]) / 2, -0.001), 0);
	assert_int_equal(oracle_crow_point(p, (A.a[0] + A.a[1]) / 2, 1.001), 0);
	/* crow_clipped: between the arcs is white inside the square only. */
	assert_int_equal(oracle_crow_point(&crow_clipped, 0.5, 0.5), 1);
	assert_int_equal(oracle_crow_point(&crow_clipped, 0.01, 0.5), 1);
	assert_int_equal(oracle_crow_point(&crow_clipped, -0.01, 0.5), 0);
	assert_int_equal(oracle_crow_point(&crow_clipped, 1.05, 0.5), 0);
	/* y = 0.02: arc 0 at -0.1 + 4 * 0.48^2 = 0.8216. */
	assert_int_equal(oracle_crow_point(&crow_clipped, 0.95, 0.02), 1);
	assert_int_equal(oracle_crow_point(&crow_clipped, 0.5, 0.02), 0);
	/* Mirror symmetry about y = 1/2 (x_k depends on (y - 1/2)^2), on a grid
	 * that avoids the arcs with probability 1. */
	for (int j = 0; j < 101; j++)
		for (int i = 0; i < 997; i++) {
			double x = (i + 0.37) / 997, y = (j + 0.21) / 203;
			assert_int_equal(oracle_crow_point(p, x, y),
					 oracle_crow_point(p, x, 1 - y));
		}
	oracle_crow odd = crow_default;
	odd.curves = 7;
	assert_int_equal(oracle_crow_point(&odd, 0.5, 0.5), 0);
}

/* ---- box ------------------------------------------------------------------ */

/* White area of crow_clipped: white where max(0, x_0) < x < 1, x_0 = -0.1 +
 * 4 t^2 (arc 1 at 1.1 is outside; arc 0 stays below 0.9 < 1).  x_0 > 0 for
 * |t| > r = sqrt(0.025), so A = 1 - 2 * integral_r^{1/2} (4 t^2 - 0.1) dt
 * = 1 - 2 ((4/3)(1/8 - r^3) - 0.1 (1/2 - r)). */
static double clipped_area(void)
{
	double r = sqrt(0.025);
	return 1 - 2 * ((4.0 / 3) * (0.125 - r * r * r) - 0.1 * (0.5 - r));
}

static void test_box_one_pixel(void **state)
{
	(void)state;
	/* A 1 x 1 image's pixel is the unit square: its box value is the area.
	 * Defaults: 96 * 4.5/256 / 4 - 96 * 0.6/(24 * 95) = 0.421875 -
	 * 0.0252631578947368... = 0.39661184210526316. */
	CHECK_NEAR(white_area(&crow_default), 0.39661184210526316, 1e-16);
	CHECK_NEAR(oracle_crow_box(&crow_default, 1, 1, 0, 0), 0.39661184210526316, 2e-16);
	CHECK_NEAR(oracle_crow_box(&crow_pair, 1, 1, 0, 0), 0.3 - 0.6 / 12, 2e-16);
	CHECK_NEAR(oracle_crow_box(&crow_bent_left, 1, 1, 0, 0), white_area(&crow_bent_left), 2e-16);
	CHECK_NEAR(oracle_crow_box(&crow_clipped, 1, 1, 0, 0), clipped_area(), 4e-16);
}

/* Sum of box values / (W H) = mean over pixels = white area. */
static void check_box_sum(const oracle_crow *p, double area, int W, int H)
{
	long double sum = 0;
	for (int j = 0; j < H; j++)
		for (int i = 0; i < W; i++) {
			double v = oracle_crow_box(p, W, H, i, j);
			if (!(v >= 0 && v <= 1))
				fail_msg("box(%d, %d) = %.17g outside [0, 1]", i, j, v);
			sum += v;
		}
	/* each value good to ~1e-16 */
	CHECK_NEAR((double)(sum / ((long double)W * H)), area, 2e-15);
}

static void test_box_sums(void **state)
{
    needs_extended_precision();
	(void)state;
	const int size[][2] = { { 2, 3 }, { 7, 5 }, { 16, 16 }, { 33, 17 },
				{ 64, 64 }, { 256, 256 }, { 1000, 3 }, { 3, 1000 } };
	for (size_t s = 0; s < sizeof size / sizeof *size; s++)
		check_box_sum(&crow_default, white_area(&crow_default), size[s][0], size[s][1]);
	check_box_sum(&crow_clipped, clipped_area(), 13, 11);
	check_box_sum(&crow_bent_left, white_area(&crow_bent_left), 29, 31);
	check_box_sum(&crow_pair, white_area(&crow_pair), 40, 9);
}

static void test_box_uniform(void **state)
{
	(void)state;
	/* 256 x 256, rows 127 and 128 (|t| <= 1/256): arc 0 is left of
	 * a_0 + 0.6/256^2 = 0.0825287 and arc 1 right of a_1 = 0.0981445, so
	 * column 22, [0.0859375, 0.0898438], is wholly white. */
	assert_true(oracle_crow_box(&crow_default, 256, 256, 22, 127) == 1.0);
	assert_true(oracle_crow_box(&crow_default, 256, 256, 22, 128) == 1.0);
	/* Left of a_0 = 0.0825195 (column 21 ends at 0.0859375 > a_0, so up to
	 * column 20) and right of a_95 = 0.9174805 (column 235 starts at
	 * 0.9179688): black on every row. */
	for (int j = 0; j < 256; j++) {
		for (int i = 0; i <= 20; i++)
			assert_true(oracle_crow_box(&crow_default, 256, 256, i, j) == 0.0);
		for (int i = 235; i < 256; i++)
			assert_true(oracle_crow_box(&crow_default, 256, 256, i, j) == 0.0);
	}
	/* Pixels outside the image see the black background. */
	assert_true(oracle_crow_box(&crow_default, 64, 64, -1, 30) == 0.0);
	assert_true(oracle_crow_box(&crow_default, 64, 64, 30, 64) == 0.0);
	assert_true(oracle_crow_box(&crow_clipped, 1, 1, 1, 0) == 0.0);
}

static void test_box_symmetry(void **state)
{
    needs_extended_precision();
	(void)state;
	/* I(x, y) = I(x, 1 - y) and row H-1-j is the mirror of row j. */
	const int size[][2] = { { 64, 64 }, { 37, 23 }, { 256, 10 } };
	for (size_t s = 0; s < sizeof size / sizeof *size; s++) {
		int W = size[s][0], H = size[s][1];
		for (int j = 0; j < H / 2; j++)
			for (int i = 0; i < W; i++)
				CHECK_NEAR(oracle_crow_box(&crow_default, W, H, i, j),
					   oracle_crow_box(&crow_default, W, H, i, H - 1 - j), 1e-15);
	}
}

static void test_box_stripes(void **state)
{
    needs_extended_precision();
	(void)state;
	/* C = 0: box value = W * (white length of the column), rows full. */
	oracle_crow p = { 96, 0, 4.0 / 256, 0.5 / 256 };
	struct arcs A;
	literal_arcs(&p, &A);
	const int W = 50, H = 7;
	for (int i = 0; i < W; i++) {
		double x0 = (double)i / W, x1 = (double)(i + 1) / W, len = 0;
		for (int m = 0; m < A.n; m += 2)
			len += fmax(0, fmin(A.a[m + 1], x1) - fmax(A.a[m], x0));
		for (int j = 0; j < H; j++)
			CHECK_NEAR(oracle_crow_box(&p, W, H, i, j), W * len, 1e-14);
	}
}

/* ---- tent and Gaussian ---------------------------------------------------- */

static void test_filtered_stripes(void **state)
{
	(void)state;
	/* C = 0 (stripes) and crow_pair near its vertical arc 1: exact separable
	 * values from stripes_value().  For crow_pair, column 41 of 64 (u in
	 * [40.5, 42.5] for R = 1, [37, 46] for the truncated S = 0.5 Gaussian)
	 * sees only arc 1 at u = 41.6; arc 0 is left of u = 32. */
	oracle_crow stripes = { 96, 0, 4.0 / 256, 0.5 / 256 };
	struct arcs A;
	const int W = 64, H = 48;
	const int px[][2] = { { 10, 20 }, { 33, 0 }, { 50, 47 }, { 62, 1 }, { 20, 24 } };
	const double tent_r[] = { 0.5, 1, 2 }, gauss_s[] = { 0.5, 1 };
	literal_arcs(&stripes, &A);
	for (size_t q = 0; q < sizeof px / sizeof *px; q++) {
		int i = px[q][0], j = px[q][1];
		double err;
		for (size_t r = 0; r < 3; r++) {
			double v = oracle_crow_tent(&stripes, W, H, i, j, tent_r[r], &err);
			CHECK_NEAR(v, stripes_value(&A, W, H, i, j, tent_cdf, tent_r[r]), err + 1e-14);
		}
		for (size_t r = 0; r < 2; r++) {
			double v = oracle_crow_gauss(&stripes, W, H, i, j, gauss_s[r], &err);
			CHECK_NEAR(v, stripes_value(&A, W, H, i, j, gauss_cdf, gauss_s[r]), err + 1e-14);
		}
	}
	literal_arcs(&crow_pair, &A);
	A.n = 2;
	A.a[0] = -1; /* only arc 1 matters in this column */
	for (int j = 0; j < H; j += 5) {
		double err;
		double v = oracle_crow_tent(&crow_pair, W, H, 41, j, 1, &err);
		CHECK_NEAR(v, stripes_value(&A, W, H, 41, j, tent_cdf, 1), err + 1e-14);
		v = oracle_crow_gauss(&crow_pair, W, H, 41, j, 0.5, &err);
		CHECK_NEAR(v, stripes_value(&A, W, H, 41, j, gauss_cdf, 0.5), err + 1e-14);
	}
}

static void test_filtered_uniform(void **state)
{
	(void)state;
	double err;
	/* Column 0 of 64: u in [-0.5, 1.5] (tent R = 1) or [-4, 5] (Gaussian at
	 * 9 S, S = 0.5), x < 0.079 < a_0 = 0.0825: black. */
	for (int j = 0; j < 64; j += 9) {
		CHECK_NEAR(oracle_crow_tent(&crow_default, 64, 64, 0, j, 1, &err), 0, err);
		CHECK_NEAR(oracle_crow_gauss(&crow_default, 64, 64, 0, j, 0.5, &err), 0, err);
	}
	/* N = 2, C = 0.2, gap0 = 0.5: white between x_0 <= 0.3 and x_1 = 0.75
	 * on every row; pixel (32, 32) of 64 sees x in [0.43, 0.58], y likewise. */
	oracle_crow wide = { 2, 0.2, 0.5, 0 };
	CHECK_NEAR(oracle_crow_tent(&wide, 64, 64, 32, 32, 1, &err), 1, err);
	CHECK_NEAR(oracle_crow_tent(&wide, 64, 64, 32, 32, 0.5, &err), 1, err);
	CHECK_NEAR(oracle_crow_gauss(&wide, 64, 64, 32, 32, 0.5, &err), 1, err);
}

static void test_filtered_symmetry(void **state)
{
	(void)state;
	/* Mirror symmetry about y = 1/2, as for the box; odd and even H. */
	const int size[][2] = { { 64, 64 }, { 37, 23 } };
	for (size_t s = 0; s < 2; s++) {
		int W = size[s][0], H = size[s][1];
		for (int j = 0; j < H / 2; j += 3)
			for (int i = 1; i < W; i += 5) {
				double e0, e1;
				double a = oracle_crow_tent(&crow_default, W, H, i, j, 1, &e0);
				double b = oracle_crow_tent(&crow_default, W, H, i, H - 1 - j, 1, &e1);
				CHECK_NEAR(a, b, e0 + e1);
				a = oracle_crow_gauss(&crow_default, W, H, i, j, 0.5, &e0);
				b = oracle_crow_gauss(&crow_default, W, H, i, H - 1 - j, 0.5, &e1);
				CHECK_NEAR(a, b, e0 + e1);
			}
	}
}

static void test_filtered_error_small(void **state)
{
	(void)state;
	/* The accuracy the oracle promises on 64 x 64 images, and values in
	 * [0, 1] up to that error. */
	for (int j = 0; j < 64; j += 7)
		for (int i = 0; i < 64; i += 5) {
			double e;
			double v = oracle_crow_tent(&crow_default, 64, 64, i, j, 1, &e);
			assert_true(e > 0 && e <= 1e-10);
			assert_true(v >= -e && v <= 1 + e);
			v = oracle_crow_gauss(&crow_default, 64, 64, i, j, 0.5, &e);
			assert_true(e > 0 && e <= 1e-10);
			assert_true(v >= -e && v <= 1 + e);
		}
}

static void test_tent_sums(void **state)
{
	(void)state;
	const oracle_crow *p = &crow_default;
	const int W = 24, H = 20;
	double A = white_area(p);
	/* The tent with R = 1 is a partition of unity: sum over all integers j
	 * of w(v - j - 1/2) = 1 (neighbouring hats add to 1).  Summing over every
	 * pixel that sees the image, i in [-1, W] and j in [-1, H], gives
	 * integral of I du dv = W H A in pixel units. */
	long double sum = 0, err = 0;
	/* the image's own pixels, below, are among these: their values are
	 * summed here too (in the same order as on their own), not computed
	 * again */
	long double own = 0, own_err = 0;
	for (int j = -1; j <= H; j++)
		for (int i = -1; i <= W; i++) {
			double e, v = oracle_crow_tent(p, W, H, i, j, 1, &e);
			sum += v;
			err += e;
			if (i >= 0 && i < W && j >= 0 && j < H) {
				own += v;
				own_err += e;
			}
		}
	CHECK_NEAR((double)sum, W * H * A, (double)err + 1e-12);

	/* Only the image's own pixels: the hats of rows -1 and H are missing.
	 * For 0 <= v <= 1/2 the rows' hats add to 1/2 + v, a deficit 1/2 - v
	 * (likewise at the bottom); columns lose nothing because x < a_0 and
	 * x > a_95 are black and a_0 W = 1.98 > 1/2.  The white length in row v is
	 * W (G - K t^2), t = v/H - 1/2, with G = N (gap0 + gap1)/4 and
	 * K = (N/2) C/(N-1) (see white_area), and
	 * integral_0^{1/2} (1/2 - v)(v/H - 1/2)^2 dv = 1/32 - 1/(48 H) + 1/(192 H^2),
	 * integral_0^{1/2} (1/2 - v) dv = 1/8, so the deficit (both ends) is
	 * D = 2 W (G/8 - K (1/32 - 1/(48 H) + 1/(192 H^2))). */
	double n = p->curves, G = n * (p->gap0 + p->gap1) / 4, K = n / 2 * p->kmax / (n - 1);
	double D = 2 * W * (G / 8 - K * (1.0 / 32 - 1.0 / (48 * H) + 1.0 / (192.0 * H * H)));
	CHECK_NEAR((double)own, W * H * A - D, (double)own_err + 1e-12);
}

static void test_gauss_sums(void **state)
{
	(void)state;
	const oracle_crow *p = &crow_default;
	const int W = 4, H = 4, M = 13;
	const double S = 1.25;
	double A = white_area(p);
	/* By Poisson summation, sum over all integers i of w(u - i - 1/2) =
	 * 1 + 2 sum_{k>=1} exp(-2 pi^2 S^2 k^2) cos(2 pi k (u - 1/2)), within
	 * eps = 2.1 exp(-2 pi^2 S^2) = 8.4e-14 of 1 for S = 1.25.  Pixels more
	 * than 9 S + 1/2 from the image (M = 13 > 11.75) see at most the mass
	 * beyond 9 S, about 1e-19 each.  So the sum over i, j in [-M, W+M) is
	 * W H A within W H A (2 eps + eps^2) plus the oracle's errors. */
	double eps = 2.1 * exp(-2 * pi * pi * S * S);
	long double sum = 0, err = 0;
	for (int j = -M; j < H + M; j++)
		for (int i = -M; i < W + M; i++) {
			double e;
			sum += oracle_crow_gauss(p, W, H, i, j, S, &e);
			err += e;
		}
	CHECK_NEAR((double)sum, W * H * A, (double)err + W * H * A * (2 * eps + eps * eps) + 1e-14);
}

/* Two-dimensional midpoint rule for the tent value of pixel (i, j), sampling
 * oracle_crow_point on a grid of step h = 1/(2q) pixels, which puts the
 * tent's kinks (pixel centre, support ends at half-integers for R = 1) and
 * the square's edges (integers) on grid lines.  A cell that no arc crosses
 * holds a constant I and a bilinear weight, where the midpoint rule is exact;
 * on a crossed cell the error is at most h^2 max f = h^2/R^2.  *bound is that
 * times the number of crossed cells, counted row by row from each arc's
 * u-extent (an arc is monotone in v on each side of y = 1/2). */
static double tent_midpoint(const oracle_crow *p, int W, int H, int i, int j,
			    int q, double *bound)
{
	const double R = 1;
	struct arcs A;
	literal_arcs(p, &A);
	double h = 1.0 / (2 * q), uc = i + 0.5, vc = j + 0.5;
	double ulo = fmax(uc - R, 0), uhi = fmin(uc + R, W);
	double vlo = fmax(vc - R, 0), vhi = fmin(vc + R, H);
	long nu = lround((uhi - ulo) / h), nv = lround((vhi - vlo) / h);
	long double sum = 0;
	long crossed = 0;
	for (long b = 0; b < nv; b++) {
		double v = vlo + (b + 0.5) * h;
		double wv = fmax(0, 1 - fabs(v - vc) / R) / R;
		for (long a = 0; a < nu; a++) {
			double u = ulo + (a + 0.5) * h;
			double wu = fmax(0, 1 - fabs(u - uc) / R) / R;
			sum += wu * wv * oracle_crow_point(p, u / W, v / H);
		}
		double v0 = vlo + b * h, v1 = v0 + h;
		for (int k = 0; k < A.n; k++) {
			double t0 = v0 / H - 0.5, t1 = v1 / H - 0.5;
			double x0 = A.a[k] + A.c[k] * t0 * t0, x1 = A.a[k] + A.c[k] * t1 * t1;
			double lo = fmin(x0, x1), hi = fmax(x0, x1);
			if (t0 < 0 && t1 > 0) {
				lo = fmin(lo, A.a[k]);
				hi = fmax(hi, A.a[k]);
			}
			long c0 = (long)floor((W * lo - ulo) / h), c1 = (long)floor((W * hi - ulo) / h);
			c0 = c0 < 0 ? 0 : c0;
			c1 = c1 > nu - 1 ? nu - 1 : c1;
			if (c1 >= c0)
				crossed += c1 - c0 + 1;
		}
	}
	*bound = crossed * h * h / (R * R);
	return (double)(sum * h * h);
}

static void test_tent_midpoint(void **state)
{
	(void)state;
	double bound, err;
	/* crow_pair on a 1 x 1 image: the whole pattern under one tent. */
	double mid = tent_midpoint(&crow_pair, 1, 1, 0, 0, 2000, &bound);
	double v = oracle_crow_tent(&crow_pair, 1, 1, 0, 0, 1, &err);
	print_message("midpoint %.12f oracle %.12f (bound %.2g, observed %.2g)\n",
		      mid, v, bound, fabs(mid - v));
	CHECK_NEAR(v, mid, bound + err);
	/* The defaults on an 8 x 8 image, a left-side pixel with few arcs. */
	mid = tent_midpoint(&crow_default, 8, 8, 1, 3, 400, &bound);
	v = oracle_crow_tent(&crow_default, 8, 8, 1, 3, 1, &err);
	print_message("midpoint %.12f oracle %.12f (bound %.2g, observed %.2g)\n",
		      mid, v, bound, fabs(mid - v));
	CHECK_NEAR(v, mid, bound + err);
}

static void test_invalid(void **state)
{
	(void)state;
	oracle_crow bad = crow_default;
	bad.curves = 95;
	double err = 0;
	assert_true(isnan(oracle_crow_box(&bad, 8, 8, 0, 0)));
	assert_true(isnan(oracle_crow_box(&crow_default, 0, 8, 0, 0)));
	assert_true(isnan(oracle_crow_tent(&bad, 8, 8, 0, 0, 1, &err)) && isinf(err));
	assert_true(isnan(oracle_crow_tent(&crow_default, 8, 8, 0, 0, 0, &err)) && isinf(err));
	assert_true(isnan(oracle_crow_gauss(&crow_default, 8, 8, 0, 0, -1, &err)) && isinf(err));
	assert_true(isnan(oracle_crow_gauss(&crow_default, 8, 0, 0, 0, 1, NULL)));
	assert_int_equal(oracle_crow_point(&bad, 0.09, 0.5), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_defaults),
		cmocka_unit_test(test_valid),
		cmocka_unit_test(test_point),
		cmocka_unit_test(test_box_one_pixel),
		cmocka_unit_test(test_box_sums),
		cmocka_unit_test(test_box_uniform),
		cmocka_unit_test(test_box_symmetry),
		cmocka_unit_test(test_box_stripes),
		cmocka_unit_test(test_filtered_stripes),
		cmocka_unit_test(test_filtered_uniform),
		cmocka_unit_test(test_filtered_symmetry),
		cmocka_unit_test(test_filtered_error_small),
		cmocka_unit_test(test_tent_sums),
		cmocka_unit_test(test_gauss_sums),
		cmocka_unit_test(test_tent_midpoint),
		cmocka_unit_test(test_invalid),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
