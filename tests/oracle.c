/*
 * oracle.c - the `crow` pattern, derived a second time for the tests.
 *
 * Source: patterns/README.md, `crow` (Crow 1976, fig. 2.9-2.14).  With
 * t = y - 1/2 the arcs are x_k = a_k + c_k t^2 on -1/2 <= t <= 1/2, where
 *
 *     a_k = a_0 + sum_{m<k} g_m = a_0 + k gap0 + (gap1 - gap0) k(k-1) / (2(N-2))
 *     a_0 = (1 - S)/2,  S = (N-1)(gap0 + gap1)/2   (N = 2: S = gap0)
 *     c_k = C (N-1-k)/(N-1)
 *
 * (closed forms of that definition's recursion; the sum of an arithmetic series).
 * Neighbouring arcs differ by g_k - C t^2/(N-1), so they are ordered at every
 * y when the pattern is valid, and I = sum_k (-1)^k H(x - x_k(y)) inside the
 * unit square.
 *
 * Box: the value is W H times the white area in the pixel, i.e. the
 * alternating sum over arcs of the area right of arc k, which is the integral
 * over the pixel's rows of x1 - clamp(x_k(t), x0, x1).  The clamp breaks at
 * c t^2 = x0 - a and c t^2 = x1 - a; in t the quadratic has no linear term, so
 * its roots +-sqrt((L - a)/c) involve no cancellation.  Between breaks the
 * integrand is a constant or x1 - a - c t^2, whose integral over [p, q] is
 * (q - p)((x1 - a) - c (p^2 + p q + q^2)/3) (difference form, no q^3 - p^3).
 * Arcs wholly left of the pixel form a prefix and arcs wholly right a suffix
 * (the arcs are ordered), found by bisection; only the arcs between cost more
 * than O(1).  Everything runs in long double (64-bit mantissa on x86-64), so
 * the result is limited by the double inputs, not by this arithmetic.
 *
 * Tent and Gaussian: the filters are separable, so
 *
 *     P = integral dv w(v - vc) h(v),  h(v) = sum over white bands m of
 *         integral of w(u - uc) over [W x_2m, W x_2m+1] clipped to [0, W],
 *
 * h in closed form from the filter's antiderivative.  Summing band masses
 * rather than the alternating sum of per-arc tail masses avoids adding and
 * cancelling N terms near 1; each mass takes both tails on the side where
 * they are small.  The v integral runs over the filter's support clipped to
 * [0, H], split at the tent's apex, by composite Simpson on a uniform grid;
 * five nested trapezoid sums give Simpson on n, n/2, n/4 and n/8 panels, the
 * result is the n one and the error estimate the sum of successive
 * differences (three
 * for the tent, two for the Gaussian; see simpson()).  For the tent, h has
 * jumps in its second derivative wherever an arc crosses u = uc or uc +- R,
 * so the convergence is only O(n^-3) and irregular (each kink's error depends
 * on where it falls in its panel); the Gaussian integrand is smooth (O(n^-4)).
 *
 * Known answer (checked by the tests): a 1 x 1 image's box value is the white
 * area N(gap0 + gap1)/4 - N C/(24(N-1)) = 0.39661184210526316 for the
 * defaults (valid for N >= 4 and arcs inside the unit square).
 */
#include "oracle.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Precision choices.  The box closed form is cheap and runs in ext; the brute
 * force evaluates millions of arc positions and runs in double (its own
 * discretisation error is far larger than double rounding). */
typedef long double ext;

static const double sqrt2 = 1.41421356237309504880;
static const double sqrt2pi = 2.50662827463100050242;

/* The Gaussian is truncated at TAU standard deviations, in both u and v;
 * the mass left out, erfc(TAU/sqrt 2) = 2.3e-19 per axis, goes into *err. */
#define TAU 9.0

/* Brute-force grid: the finest trapezoid grid along v has this many steps
 * per unit of (filter scale / steepest arc slope).  Chosen by measurement on
 * the default pattern: *err <= 3.2e-11 (tent R = 0.5, 1; Gaussian S = 0.5,
 * 1) on 64 x 64 and 256 x 256 images, at 0.5-0.6 ms (tent) and 0.8-3.3 ms
 * (Gaussian) per pixel on average, 13 ms at worst; the true error, against
 * grids 16 times finer, stayed below 1e-13.  Overridable so that an
 * experiment can vary them. */
#ifndef PANELS_TENT
#define PANELS_TENT 8000.0
#endif
#ifndef PANELS_GAUSS
#define PANELS_GAUSS 400.0
#endif

oracle_crow oracle_crow_defaults(void)
{
	oracle_crow p = { 96, 0.6, 4.0 / 256, 0.5 / 256 };
	return p;
}

int oracle_crow_valid(const oracle_crow *p)
{
	if (!p || p->curves < 2 || p->curves % 2 != 0)
		return 0;
	if (!isfinite(p->kmax) || !isfinite(p->gap0) || !isfinite(p->gap1))
		return 0;
	/* g_k is linear in k, so the smallest gap is g_0 or g_{N-2}; the gap at
	 * height t is g_k - C t^2/(N-1), smallest at t^2 = 1/4 (C >= 0) or at
	 * t = 0 (C < 0). */
	ext close = (ext)p->kmax / (4 * ((ext)p->curves - 1));
	ext g[2] = { p->gap0, p->curves == 2 ? p->gap0 : p->gap1 };
	for (int e = 0; e < 2; e++)
		if (!(g[e] - close > 0) || !(g[e] > 0))
			return 0;
	return 1;
}

/* ---- the arcs ------------------------------------------------------------ */

struct arcs {
	long n;    /* N */
	ext a0;    /* a_0 */
	ext gap0;  /* g_0 */
	ext dgap;  /* g_{k+1} - g_k = (gap1 - gap0)/(N-2); 0 when N = 2 */
	ext cstep; /* C/(N-1): c_k = (N-1-k) cstep */
};

static void arcs_init(struct arcs *A, const oracle_crow *p)
{
	ext n = p->curves;
	ext s = p->curves > 2 ? (n - 1) * ((ext)p->gap0 + p->gap1) / 2 : (ext)p->gap0;
	A->n = p->curves;
	A->gap0 = p->gap0;
	A->dgap = p->curves > 2 ? ((ext)p->gap1 - p->gap0) / (n - 2) : 0;
	A->a0 = (1 - s) / 2;
	A->cstep = (ext)p->kmax / (n - 1);
}

static ext arc_a(const struct arcs *A, long k)
{
	ext kk = k;
	return A->a0 + kk * A->gap0 + A->dgap * (kk * (kk - 1) / 2);
}

static ext arc_c(const struct arcs *A, long k)
{
	return (ext)(A->n - 1 - k) * A->cstep;
}

int oracle_crow_point(const oracle_crow *p, double x, double y)
{
	if (!oracle_crow_valid(p) || !(x >= 0 && x <= 1 && y >= 0 && y <= 1))
		return 0;
	struct arcs A;
	arcs_init(&A, p);
	ext t = (ext)y - 0.5L;
	/* The arcs are ordered at every y: the number of arcs left of x is the
	 * first k with x_k(y) >= x. */
	long lo = 0, hi = A.n;
	while (lo < hi) {
		long mid = lo + (hi - lo) / 2;
		if (arc_a(&A, mid) + arc_c(&A, mid) * t * t < x)
			lo = mid + 1;
		else
			hi = mid;
	}
	return (int)(lo & 1);
}

/* ---- box: closed form ---------------------------------------------------- */

static ext clamp01(ext x)
{
	return x < 0 ? 0 : x > 1 ? 1 : x;
}

/* Smallest and largest value of a + c t^2 on [t0, t1]. */
static void quad_range(ext a, ext c, ext t0, ext t1, ext *lo, ext *hi)
{
	ext s0 = t0 * t0, s1 = t1 * t1;
	ext smax = s0 > s1 ? s0 : s1;
	ext smin = (t0 <= 0 && t1 >= 0) ? 0 : (s0 < s1 ? s0 : s1);
	*lo = a + c * (c >= 0 ? smin : smax);
	*hi = a + c * (c >= 0 ? smax : smin);
}

/* Integral over [t0, t1] of x1 - clamp(a + c t^2, x0, x1). */
static ext area_right(ext a, ext c, ext x0, ext x1, ext t0, ext t1)
{
	ext cut[6];
	int n = 0;
	cut[n++] = t0;
	if (c != 0) {
		const ext level[2] = { x0, x1 };
		for (int l = 0; l < 2; l++) {
			ext s = (level[l] - a) / c;
			if (!(s > 0))
				continue;
			ext r = sqrtl(s);
			if (-r > t0 && -r < t1)
				cut[n++] = -r;
			if (r > t0 && r < t1)
				cut[n++] = r;
		}
	}
	cut[n++] = t1;
	for (int m = 1; m < n; m++) /* insertion sort of at most 6 */
		for (int q = m; q > 0 && cut[q - 1] > cut[q]; q--) {
			ext tmp = cut[q];
			cut[q] = cut[q - 1];
			cut[q - 1] = tmp;
		}
	ext sum = 0;
	for (int m = 0; m + 1 < n; m++) {
		ext p = cut[m], q = cut[m + 1];
		if (!(q > p))
			continue;
		ext tm = (p + q) / 2;
		ext xm = a + c * tm * tm;
		if (xm <= x0) /* clamped to x0: the whole column is right of it */
			sum += (x1 - x0) * (q - p);
		else if (xm < x1) /* inside the column */
			sum += (q - p) * ((x1 - a) - c * (p * p + p * q + q * q) / 3);
	}
	return sum;
}

double oracle_crow_box(const oracle_crow *p, int W, int H, int i, int j)
{
	if (!oracle_crow_valid(p) || W < 1 || H < 1)
		return NAN;
	ext x0 = clamp01((ext)i / W), x1 = clamp01(((ext)i + 1) / W);
	ext y0 = clamp01((ext)j / H), y1 = clamp01(((ext)j + 1) / H);
	if (!(x1 > x0 && y1 > y0))
		return 0;
	ext t0 = y0 - 0.5L, t1 = y1 - 0.5L;
	struct arcs A;
	arcs_init(&A, p);

	/* first = the first arc not wholly left of the column */
	long lo = 0, hi = A.n;
	while (lo < hi) {
		long mid = lo + (hi - lo) / 2;
		ext qlo, qhi;
		quad_range(arc_a(&A, mid), arc_c(&A, mid), t0, t1, &qlo, &qhi);
		if (qhi <= x0)
			lo = mid + 1;
		else
			hi = mid;
	}
	long first = lo;
	/* end = the first arc wholly right of the column */
	hi = A.n;
	while (lo < hi) {
		long mid = lo + (hi - lo) / 2;
		ext qlo, qhi;
		quad_range(arc_a(&A, mid), arc_c(&A, mid), t0, t1, &qlo, &qhi);
		if (qlo >= x1)
			hi = mid;
		else
			lo = mid + 1;
	}
	long end = lo;

	/* Arcs wholly left each add +-(full area): they cancel in pairs. */
	ext sum = (first & 1) ? (x1 - x0) * (t1 - t0) : 0;
	for (long k = first; k < end; k++) {
		ext r = area_right(arc_a(&A, k), arc_c(&A, k), x0, x1, t0, t1);
		sum += (k & 1) ? -r : r;
	}
	return (double)(sum * W * H);
}

/* ---- tent and Gaussian: brute force -------------------------------------- */

enum filter_kind { TENT, GAUSS };

/* One pixel under one filter, everything in pixel units and double. */
struct field {
	enum filter_kind kind;
	double r;     /* R or S */
	double reach; /* half-width of the (truncated) support */
	double a0, gap0, dgap, cstep;
	long n;
	int W, H;
	double uc, vc; /* the pixel's centre */
};

static void field_init(struct field *F, const oracle_crow *p, int W, int H,
		       int i, int j, enum filter_kind kind, double r)
{
	struct arcs A;
	arcs_init(&A, p);
	F->kind = kind;
	F->r = r;
	F->reach = kind == TENT ? r : TAU * r;
	F->a0 = (double)A.a0;
	F->gap0 = (double)A.gap0;
	F->dgap = (double)A.dgap;
	F->cstep = (double)A.cstep;
	F->n = A.n;
	F->W = W;
	F->H = H;
	F->uc = i + 0.5;
	F->vc = j + 0.5;
}

/* u_k - uc for arc k at t^2 = tt. */
static double field_arc(const struct field *F, long k, double tt)
{
	double kk = (double)k;
	double a = F->a0 + kk * F->gap0 + F->dgap * (kk * (kk - 1) / 2);
	double c = (double)(F->n - 1 - k) * F->cstep;
	return F->W * (a + c * tt) - F->uc;
}

/* One-dimensional weight w(s). */
static double weight(const struct field *F, double s)
{
	if (F->kind == TENT) {
		double d = 1 - fabs(s) / F->r;
		return d > 0 ? d / F->r : 0;
	}
	double z = s / F->r;
	return exp(-0.5 * z * z) / (F->r * sqrt2pi);
}

/* Tent antiderivative from -infinity (below = 1) or to +infinity (below = 0). */
static double tent_tail(double s, double r, int below)
{
	if (!below)
		s = -s;
	if (s <= -r)
		return 0;
	if (s >= r)
		return 1;
	double z = s <= 0 ? (s + r) / r : (r - s) / r;
	return s <= 0 ? 0.5 * z * z : 1 - 0.5 * z * z;
}

/* Integral of w over [s0, s1], s0 <= s1, each tail taken on its own side so
 * that no 1 - (1 - small) appears. */
static double weight_mass(const struct field *F, double s0, double s1)
{
	if (F->kind == TENT) {
		if (s0 >= 0)
			return tent_tail(s0, F->r, 0) - tent_tail(s1, F->r, 0);
		return tent_tail(s1, F->r, 1) - tent_tail(s0, F->r, 1);
	}
	double z0 = s0 / (F->r * sqrt2), z1 = s1 / (F->r * sqrt2);
	if (z0 >= 0)
		return 0.5 * (erfc(z0) - erfc(z1));
	if (z1 <= 0)
		return 0.5 * (erfc(-z1) - erfc(-z0));
	return 0.5 * (erf(z1) - erf(z0));
}

/* h(v): the filter mass along u over the white part of row v.  *bands gets
 * the number of bands summed (for the rounding estimate). */
static double row_mass(const struct field *F, double v, int *bands)
{
	*bands = 0;
	if (!(v >= 0 && v <= F->H))
		return 0;
	double t = v / F->H - 0.5, tt = t * t;
	double left = -F->uc, right = F->W - F->uc; /* x = 0 and x = 1 */
	/* The first arc right of the support's left end; bands wholly left of
	 * the support contribute nothing. */
	long lo = 0, hi = F->n;
	while (lo < hi) {
		long mid = lo + (hi - lo) / 2;
		if (field_arc(F, mid, tt) > -F->reach)
			hi = mid;
		else
			lo = mid + 1;
	}
	double sum = 0;
	for (long k = lo & ~1L; k < F->n; k += 2) {
		double s0 = field_arc(F, k, tt);
		if (s0 >= F->reach || s0 >= right)
			break;
		double s1 = field_arc(F, k + 1, tt);
		s0 = s0 > left ? s0 : left;
		s1 = s1 < right ? s1 : right;
		if (s1 > s0) {
			sum += weight_mass(F, s0, s1);
			++*bands;
		}
	}
	return sum;
}

/* Composite Simpson of w(v - vc) h(v) over [lo, hi] on n, n/2, n/4 and n/8
 * panels (five nested trapezoid sums on one grid); returns the n-panel value.
 * *err = |S_n - S_n/2| + |S_n/2 - S_n/4| (+ |S_n/4 - S_n/8| for the tent)
 * plus rounding.  The tent's kinks in h make the local errors depend on where
 * each kink falls in its panel, so one difference can be small by accident:
 * on grids 16 times coarser than the default, |S_n - S_n/2| alone was up to
 * 1.7 times too small and the first two differences up to 1.2 times; the
 * three together were never above 0.17 of the true error, over 10000 pixels.
 * For the smooth Gaussian integrand two differences exceed the true error
 * 250-fold. */
static double simpson(const struct field *F, double lo, double hi, double *err)
{
	*err = 0;
	if (!(hi > lo))
		return 0;
	/* h changes on the scale of the filter divided by the arcs' steepest
	 * slope du/dv = 2 |c| |t| W/H <= |C| W/H. */
	double slope = fabs(F->cstep * (double)(F->n - 1)) * F->W / F->H;
	double scale = F->r / (slope > 1 ? slope : 1);
	double per = F->kind == TENT ? PANELS_TENT : PANELS_GAUSS;
	long m = 16 * (long)ceil((hi - lo) / scale * per / 16); /* finest grid */
	if (m < 32)
		m = 32;
	double step = (hi - lo) / (double)m;
	long double t[5] = { 0, 0, 0, 0, 0 }; /* trapezoid sums, spacing step << l */
	int maxbands = 0;
	for (long k = 0; k <= m; k++) {
		double v = k == m ? hi : lo + (double)k * step;
		int bands;
		double g = weight(F, v - F->vc) * row_mass(F, v, &bands);
		if (bands > maxbands)
			maxbands = bands;
		if (k == 0 || k == m)
			g *= 0.5;
		for (int l = 0; l < 5 && k % (1L << l) == 0; l++)
			t[l] += g;
	}
	long double s[4];
	for (int l = 0; l < 4; l++) /* Simpson = (4 T_h - T_2h)/3 */
		s[l] = (4 * t[l] - 2 * t[l + 1]) * (step * (1L << l)) / 3;
	/* Rounding: each band mass is good to a few ulps of 1, and the weights
	 * over [lo, hi] integrate to at most 1. */
	long double diff = fabsl(s[0] - s[1]) + fabsl(s[1] - s[2]);
	if (F->kind == TENT)
		diff += fabsl(s[2] - s[3]);
	*err = (double)diff + 8 * DBL_EPSILON * (maxbands + 2);
	return (double)s[0];
}

static double filtered(const oracle_crow *p, int W, int H, int i, int j,
		       enum filter_kind kind, double r, double *err)
{
	double e0 = 0, e1 = 0, value;
	if (err)
		*err = INFINITY;
	if (!oracle_crow_valid(p) || W < 1 || H < 1 || !(r > 0) || !isfinite(r))
		return NAN;
	struct field F;
	field_init(&F, p, W, H, i, j, kind, r);
	double lo = F.vc - F.reach, hi = F.vc + F.reach;
	lo = lo > 0 ? lo : 0;
	hi = hi < H ? hi : H;
	if (kind == TENT) {
		/* split at the apex, where w has a kink */
		double mid = F.vc < lo ? lo : F.vc > hi ? hi : F.vc;
		value = simpson(&F, lo, mid, &e0) + simpson(&F, mid, hi, &e1);
	} else {
		value = simpson(&F, lo, hi, &e0);
		e1 = 2 * erfc(TAU / sqrt2); /* mass beyond TAU S in u and in v */
	}
	if (err)
		*err = e0 + e1;
	return value;
}

double oracle_crow_tent(const oracle_crow *p, int W, int H, int i, int j,
			double R, double *err)
{
	return filtered(p, W, H, i, j, TENT, R, err);
}

double oracle_crow_gauss(const oracle_crow *p, int W, int H, int i, int j,
			 double S, double *err)
{
	return filtered(p, W, H, i, j, GAUSS, S, err);
}

double oracle_cone_cut(double delta)
{
    if (delta >= 1.0)
        return 0.0;
    if (delta < 0.0)
        return 1.0 - oracle_cone_cut(-delta);
    double s = sqrt((1.0 - delta) * (1.0 + delta));
    double tail = delta > 0.0 ? delta * delta * delta * log((1.0 + s) / delta) : 0.0;
    return (acos(delta) - 2.0 * delta * s + tail) / M_PI;
}

/* ---- polygons (oracle.h): Sutherland-Hodgman and the shoelace formula ---- */

static void poly_put(oracle_poly *out, double x, double y)
{
    if (out->n >= ORACLE_POLY_MAX) {
        fprintf(stderr, "oracle_poly: more than %d vertices\n", ORACLE_POLY_MAX);
        abort();
    }
    out->x[out->n] = x;
    out->y[out->n++] = y;
}

oracle_poly oracle_poly_clip(const oracle_poly *in, double a, double b, double c)
{
    oracle_poly out = {0};
    for (int k = 0; k < in->n; k++) {
        int m = (k + 1) % in->n;
        double dk = a * in->x[k] + b * in->y[k] - c, dm = a * in->x[m] + b * in->y[m] - c;
        if (dk <= 0)
            poly_put(&out, in->x[k], in->y[k]);
        if ((dk < 0 && dm > 0) || (dk > 0 && dm < 0)) {
            double t = dk / (dk - dm);
            poly_put(&out, in->x[k] + t * (in->x[m] - in->x[k]),
                     in->y[k] + t * (in->y[m] - in->y[k]));
        }
    }
    return out;
}

oracle_poly oracle_poly_intersect(const oracle_poly *p, const oracle_poly *q)
{
    oracle_poly out = *p;
    for (int k = 0; k < q->n; k++) {
        int m = (k + 1) % q->n, o = (k + 2) % q->n;
        double a = q->y[m] - q->y[k], b = q->x[k] - q->x[m];
        double c = a * q->x[k] + b * q->y[k];
        if (a * q->x[o] + b * q->y[o] > c) /* keep the side holding vertex o */
            a = -a, b = -b, c = -c;
        out = oracle_poly_clip(&out, a, b, c);
    }
    return out;
}

void oracle_hexagon_vertex(double r, double angle, int v, double *dx, double *dy)
{
    const double pi = 3.14159265358979323846, c = 0.5, s = sqrt(3.0) / 2;
    double x = r * cos(angle * pi / 180), y = r * sin(angle * pi / 180);
    for (int k = 0; k < v; k++) {
        double nx = c * x - s * y, ny = s * x + c * y;
        x = nx, y = ny;
    }
    *dx = x, *dy = y;
}

oracle_poly oracle_poly_scaled(const oracle_poly *p, double sx, double sy)
{
    oracle_poly out = *p;
    for (int k = 0; k < out.n; k++)
        out.x[k] *= sx, out.y[k] *= sy;
    return out;
}

double oracle_poly_area(const oracle_poly *p)
{
    double s = 0;
    for (int k = 0; k < p->n; k++) {
        int m = (k + 1) % p->n;
        s += p->x[k] * p->y[m] - p->x[m] * p->y[k];
    }
    return 0.5 * fabs(s);
}

double oracle_poly_area_in_rect(const oracle_poly *p, double x0, double y0, double x1, double y1)
{
    oracle_poly q = oracle_poly_clip(p, -1, 0, -x0);
    q = oracle_poly_clip(&q, 1, 0, x1);
    q = oracle_poly_clip(&q, 0, -1, -y0);
    q = oracle_poly_clip(&q, 0, 1, y1);
    return oracle_poly_area(&q);
}

/* ---- cubic Bezier arcs ---- */

void oracle_cubic_at(const double c[8], double t, double *x, double *y, double *dx, double *dy)
{
    double s = 1 - t, v[2], d[2];
    for (int k = 0; k < 2; k++) {
        double p0 = c[k], p1 = c[2 + k], p2 = c[4 + k], p3 = c[6 + k];
        v[k] = s * s * s * p0 + 3 * s * s * t * p1 + 3 * s * t * t * p2 + t * t * t * p3;
        d[k] = 3 * (s * s * (p1 - p0) + 2 * s * t * (p2 - p1) + t * t * (p3 - p2));
    }
    *x = v[0], *y = v[1], *dx = d[0], *dy = d[1];
}

double oracle_cubic_curvature(const double c[8], double t)
{
    double s = 1 - t, d[2], e[2];
    for (int k = 0; k < 2; k++) {
        d[k] = 3 * (s * s * (c[2 + k] - c[k]) + 2 * s * t * (c[4 + k] - c[2 + k]) +
                    t * t * (c[6 + k] - c[4 + k]));
        e[k] = 6 * (s * (c[4 + k] - 2 * c[2 + k] + c[k]) + t * (c[6 + k] - 2 * c[4 + k] + c[2 + k]));
    }
    double l = hypot(d[0], d[1]);
    return (d[0] * e[1] - d[1] * e[0]) / (l * l * l);
}

static double cubic_speed(double t, void *p)
{
    double x, y, dx, dy;
    oracle_cubic_at(p, t, &x, &y, &dx, &dy);
    return hypot(dx, dy);
}

double oracle_cubic_length(const double c[8], double a, double b)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    if (!w)
        return NAN;
    gsl_function f = {cubic_speed, (void *)c};
    double r = NAN, err = INFINITY;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int st = gsl_integration_qag(&f, a, b, 1e-13, 0, 1000, GSL_INTEG_GAUSS61, w, &r, &err);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    return st || !(err < 1e-13) ? NAN : r;
}

double oracle_ellipse_perimeter(double a, double b)
{
    double q = (a - b) / (a + b), h = q * q, c = 1, sum = 1, hn = 1;
    for (int n = 1; n < 2000; n++) {
        c *= (0.5 - (n - 1)) / n;
        hn *= h;
        double term = c * c * hn;
        sum += term;
        if (term < 1e-20 * sum)
            break;
    }
    return M_PI * (a + b) * sum;
}

double oracle_curve_feet(oracle_curve_fn at, const void *ctx, double t0, double t1, int n,
                         double px, double py, int ends, double h, int *unsure)
{
    double best = INFINITY, x, y, dx, dy;
    at(ctx, t0, &x, &y, &dx, &dy);
    double pg = (px - x) * dx + (py - y) * dy, pt = t0;
    if (ends)
        best = fmin(best, hypot(px - x, py - y));
    else if (fabs(pg) / hypot(dx, dy) < 1e-7 && hypot(px - x, py - y) < h + 1e-7)
        *unsure = 1;
    for (int k = 1; k <= n; k++) {
        double t = t0 + (t1 - t0) * k / n;
        at(ctx, t, &x, &y, &dx, &dy);
        double g = (px - x) * dx + (py - y) * dy;
        if ((pg < 0 && g >= 0) || (pg > 0 && g <= 0)) {
            double lo = pt, hi = t, glo = pg;
            for (int it = 0; it < 60; it++) {
                double m = 0.5 * (lo + hi), gm;
                at(ctx, m, &x, &y, &dx, &dy);
                gm = (px - x) * dx + (py - y) * dy;
                if ((gm < 0) == (glo < 0))
                    lo = m, glo = gm;
                else
                    hi = m;
            }
            at(ctx, 0.5 * (lo + hi), &x, &y, &dx, &dy);
            best = fmin(best, hypot(px - x, py - y));
        }
        pg = g, pt = t;
    }
    at(ctx, t1, &x, &y, &dx, &dy);
    if (ends)
        best = fmin(best, hypot(px - x, py - y));
    else if (fabs(pg) / hypot(dx, dy) < 1e-7 && hypot(px - x, py - y) < h + 1e-7)
        *unsure = 1;
    return best;
}
