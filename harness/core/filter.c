/*
 * filter.c: the reconstruction filters of patterns/README.md ("Filters"), in
 * pixel units.
 *
 * The separable filters are w(u) w(v), with a 1-D weight normalised to
 * integral 1, so exact methods and the ground truth need only the 1-D
 * weight and its integral (the cdf): the integral of the filter over a span
 * [x0, x1] of constant colour along a line is cdf(x1 - uc) - cdf(x0 - uc).
 *
 *   box        1 on [-1/2, 1/2]                        (area sampling)
 *   tent:r=R   max(0, 1 - |t|/R) / R                   (Crow fig. 2.13, 2.14)
 *   gauss:s=S  exp(-t^2 / (2 S^2)) / (S sqrt(2 pi))    (untruncated)
 *   bspline:order=2   quadratic B-spline, support [-3/2, 3/2]:
 *              3/4 - t^2 (|t| < 1/2), (3/2 - |t|)^2 / 2 (|t| < 3/2)
 *   bspline:order=3   cubic B-spline, support [-2, 2]:
 *              (4 - 6 t^2 + 3 |t|^3) / 6 (|t| < 1), (2 - |t|)^3 / 6 (|t| < 2)
 *   mitchell:b=B,c=C  Mitchell and Netravali (1988), support [-2, 2]:
 *              ((12 - 9B - 6C)|t|^3 + (-18 + 12B + 6C) t^2 + (6 - 2B)) / 6 (|t| < 1)
 *              ((-B - 6C)|t|^3 + (6B + 30C) t^2 + (-12B - 48C)|t| + (8B + 24C)) / 6
 *              (|t| < 2); with z = 2 - |t| the outer piece is
 *              ((B + 6C) z^3 - 6C z^2) / 6, whose integral from 0 is
 *              T(z) = ((B + 6C) z^4 / 4 - 2C z^3) / 6
 *   catrom     mitchell:b=0,c=0.5 (Catmull-Rom)
 *   lanczos:a=A  sinc(t) sinc(t / A) / M on |t| < A, sinc(t) = sin(pi t) / (pi t),
 *              M its integral over [-A, A] (A = 2: 1.00979, A = 3: 0.99706)
 *
 * For each the cdf is C(t) = 1/2 + sign(t) P(|t|) with P the integral of
 * the weight from 0, and the tails (C(t) for t < -1, a few 1e-2) come from
 * the outer piece's own antiderivative, so that no 1/2 - P cancels there.
 * The polynomial filters integrate to 1 exactly: for Mitchell,
 * T(1) = (B - 2C) / 24 and P(1) = 1/2 - B/24 + C/12 sum to 1/2.  Lanczos's
 * weight is a / (2 pi^2 t^2) (cos(alpha t) - cos(beta t)), alpha =
 * pi (1 - 1/A), beta = pi (1 + 1/A), and int (1 - cos k t) / t^2 dt =
 * k Si(k t) - (1 - cos k t) / t, so
 *     P(t) = A / (2 pi^2) (F_beta(t) - F_alpha(t)),
 *     F_k(t) = k Si(k t) - 2 sin^2(k t / 2) / t,
 * with GSL's sine integral Si (relative error a few eps), M = 2 P(A).
 * Mitchell with C > 0 and Lanczos have negative lobes: a filtered image of
 * values in [0, 1] can take values in [-N, 1 + N], N the 2-D negative mass
 * (aa_filter_range).
 *
 * The radial filters are not separable: the cone (Feibush, Levoy and Cook
 * 1980, fig. 2f and 3a, the cone their circular filter table is drawn
 * for), and the truncated filters below:
 *
 *   cone:r=R   3 / (pi R^2) max(0, 1 - sqrt(u^2 + v^2) / R)   (volume 1)
 *
 * For it the inner integral along a line is the integral of a row, in
 * closed form: with x = u / R, y = v / R and rho = sqrt(x^2 + y^2),
 * int (1 - rho) dx = G(x) = x - (x rho + y^2 asinh(x / |y|)) / 2 (from
 * int sqrt(x^2 + y^2) dx = (x rho + y^2 asinh(x / |y|)) / 2; at y = 0,
 * G = x - x |x| / 2), odd in x.  The row meets the disc on the chord
 * |x| <= c = sqrt(1 - y^2), so the row's integral up to u is
 * R 3 / (pi R^2) (G(clamp(x, -c, c)) + G(c)).  Its y^2 log|y| term makes
 * it not smooth at v = 0 (a kink for the reference's breakpoints), as are
 * v = +-R, where the chord closes like a square root.  Integrating 2 G(c)
 * over y in [-1, 1] gives pi / 3, the volume of the unit cone: the weight
 * is normalised.
 * Truncated and renormalised radial filters (the masks of Feibush, Levoy
 * and Cook 1980, sec. 3, fig. 4d: "a Gaussian weighting function that has
 * a standard deviation equal to the distance between adjacent display
 * pixels. The convolution mask is a circle whose radius is equal to twice
 * the standard deviation"; the weights inside the mask are divided by their
 * volume, "the ratio of the shaded volume to the total volume", fig. 3a):
 *
 *   gauss:s=S,cut=K (K > 0)  exp(-(u^2 + v^2) / (2 S^2)) / Z inside the
 *              circle of radius Rc = K S, Z = 2 pi S^2 (1 - exp(-K^2 / 2)):
 *              radial, not separable (the type aa_filter_gauss_mask).  Its
 *              row, with c = sqrt(Rc^2 - v^2) the chord's half length, has
 *              the integral up to u
 *              exp(-v^2 / (2 S^2)) / Z S sqrt(pi / 2)
 *                  (erf(clamp(u, -c, c) / (S sqrt 2)) + erf(c / (S sqrt 2))).
 *   cone:r=R,cut=K (K < 1)   the cone 1 - d / R cut off at d = Rc = K R,
 *              divided by its volume there, V = 2 pi R^2 (K^2 / 2 - K^3 / 3);
 *              its row integral is R / V (G(clamp(x, -c, c)) + G(c)) with
 *              G as above and c = sqrt(K^2 - y^2) (K = 1: the whole cone,
 *              V = pi R^2 / 3, computed as before).  A frustum's wall at the
 *              mask: the rows close like a square root there, as the
 *              cone's do at R.
 *
 * Radially symmetric polynomial filters (Manson and Schaefer 2013 rasterize
 * with "radial" filters besides separable ones; their paper's own radial
 * polynomials were not at hand, so this family is a variant of our choice:
 * the polynomials in r^2 on a disc, whose every power is a polynomial in u
 * and v, so their exact method applies to it):
 *
 *   radial:k=K,r=R   c_K (1 - (u^2 + v^2) / R^2)^K inside the disc
 *              u^2 + v^2 < R^2, 0 outside, K = 1, 2, 3; volume 1 with
 *              c_K = (K + 1) / (pi R^2), since in polar coordinates
 *              int_0^R (1 - r^2/R^2)^K 2 pi r dr = pi R^2 / (K + 1)
 *              (t = r^2 / R^2: pi R^2 int_0^1 (1 - t)^K dt).
 *
 * Its row at height v, with y = v / R, x = u / R, a^2 = 1 - y^2 (taken
 * as (1 - y)(1 + y)), is c_K (a^2 - x^2)^K on the chord |x| < a, and
 *     H_K(x) = int_0^x (a^2 - t^2)^K dt
 *            = sum_j binom(K, j) (-1)^j a^(2(K-j)) x^(2j+1) / (2j + 1)
 * (K = 1: a^2 x - x^3/3; K = 2: a^4 x - 2 a^2 x^3/3 + x^5/5; K = 3:
 * a^6 x - a^4 x^3 + 3 a^2 x^5/5 - x^7/7), odd in x, so the row's integral
 * up to u is c_K R (H_K(clamp(x, -a, a)) + H_K(a)), a polynomial in u and
 * a.  The row's whole integral is 2 c_K R H_K(a) = c_K R B_K a^(2K+1),
 * B_K = int_-1^1 (1 - t^2)^K dt = 4/3, 16/15, 32/35: like a power
 * (R - |v|)^(K + 1/2) at v = +-R, where the chord closes (the
 * reference's breakpoints there, with v = 0 for symmetry); smooth
 * elsewhere.  The weight is continuous for every K; its derivative at the
 * rim is 0 for K >= 2.
 *
 * The Gaussian has unbounded support; users of `radius` truncate it where
 * the 2-D mass outside the square [-R, R]^2 is below a stated tail, and
 * that mass is reported so it can enter an error bound.
 */
#include "core.h"

#include <math.h>

#include <gsl/gsl_sf_expint.h>

static const aa_param no_params[] = {{0}};

static const aa_param tent_params[] = {
    {"r", AA_PARAM_REAL, 1.0, 0.01, 16.0, 0, NULL,
     "half-width in pixels: the weight falls linearly to zero at |t| = r"},
    {0}};

static const aa_param gauss_params[] = {
    {"s", AA_PARAM_REAL, 0.5, 0.01, 8.0, 0, NULL, "standard deviation in pixels"},
    {"cut", AA_PARAM_REAL, 0.0, 0.0, 40.0, 0, NULL,
     "radius of a circular mask in units of s, the weight renormalised inside it (radial, "
     "not separable; Feibush et al. fig. 4d: 2); 0: untruncated and separable"},
    {0}};

static const aa_param cone_params[] = {
    {"r", AA_PARAM_REAL, 1.0, 0.01, 8.0, 0, NULL,
     "radius in pixels: the weight falls linearly to zero at distance r from the centre"},
    {"cut", AA_PARAM_REAL, 1.0, 0.0, 1.0, 1, NULL,
     "radius of the mask in units of r, the weight renormalised inside it (below 1: a "
     "truncated cone)"},
    {0}};

static const aa_param radial_params[] = {
    {"k", AA_PARAM_INT, 2.0, 1.0, 3.0, 0, NULL,
     "the power: the weight is (1 - d^2/r^2)^k inside the disc d < r (1, 2, 3)"},
    {"r", AA_PARAM_REAL, 1.5, 0.01, 8.0, 0, NULL,
     "radius in pixels: the weight falls to zero at distance r from the centre"},
    {0}};

static const aa_param bspline_params[] = {
    {"order", AA_PARAM_INT, 3.0, 2.0, 3.0, 0, NULL,
     "2: quadratic (support 3 pixels), 3: cubic (support 4 pixels)"},
    {0}};

static const aa_param mitchell_params[] = {
    {"b", AA_PARAM_REAL, 1.0 / 3.0, 0.0, 1.0, 0, NULL, "Mitchell and Netravali's B"},
    {"c", AA_PARAM_REAL, 1.0 / 3.0, 0.0, 1.0, 0, NULL, "Mitchell and Netravali's C"},
    {0}};

static const aa_param lanczos_params[] = {
    {"a", AA_PARAM_INT, 3.0, 2.0, 3.0, 0, NULL, "lobes: the support is [-a, a] pixels"},
    {0}};

/* ---- box ---- */

static double box_weight(const double *p, double t)
{
    (void)p;
    return fabs(t) <= 0.5 ? 1.0 : 0.0;
}

static double box_cdf(const double *p, double t)
{
    (void)p;
    return t <= -0.5 ? 0.0 : (t >= 0.5 ? 1.0 : t + 0.5);
}

static double box_radius(const double *p, double tail, double *lost)
{
    (void)p, (void)tail;
    *lost = 0.0;
    return 0.5;
}

static int box_kinks(const double *p, double *t)
{
    (void)p;
    t[0] = -0.5;
    t[1] = 0.5;
    return 2;
}

/* ---- tent ---- */

static double tent_weight(const double *p, double t)
{
    double r = p[0], a = fabs(t);
    return a >= r ? 0.0 : (1.0 - a / r) / r;
}

static double tent_cdf(const double *p, double t)
{
    double r = p[0];
    if (t <= -r)
        return 0.0;
    if (t >= r)
        return 1.0;
    double d = t <= 0.0 ? t + r : r - t; /* distance to the nearer end */
    double tail = 0.5 * (d / r) * (d / r);
    return t <= 0.0 ? tail : 1.0 - tail;
}

static double tent_radius(const double *p, double tail, double *lost)
{
    (void)tail;
    *lost = 0.0;
    return p[0];
}

static int tent_kinks(const double *p, double *t)
{
    t[0] = -p[0];
    t[1] = 0.0;
    t[2] = p[0];
    return 3;
}

/* ---- Gaussian ---- */

static double gauss_weight(const double *p, double t)
{
    double s = p[0], z = t / s;
    return exp(-0.5 * z * z) / (s * 2.5066282746310002);
}

static double gauss_cdf(const double *p, double t)
{
    return 0.5 * erfc(-t / (p[0] * M_SQRT2));
}

/* The square [-R, R]^2 misses 1 - (1 - e)^2 <= 2e of the mass, with
 * e = erfc(R / (s sqrt 2)) the 1-D mass outside [-R, R]. */
static double gauss_radius(const double *p, double tail, double *lost)
{
    double k = 1.0;
    while (2.0 * erfc(k / M_SQRT2) > tail && k < 40.0)
        k += 0.25;
    *lost = 2.0 * erfc(k / M_SQRT2);
    return k * p[0];
}

static int gauss_kinks(const double *p, double *t)
{
    (void)p, (void)t;
    return 0;
}

/* ---- cone (radial, not separable), whole or truncated ---- */

/* 1 / V, V the volume of the cone of radius r inside its mask K r:
 * 2 pi r^2 (K^2 / 2 - K^3 / 3); K = 1 as the whole cone always was. */
static double cone_norm(double r, double k)
{
    if (k == 1.0)
        return 3.0 / (M_PI * r * r);
    return 1.0 / (2.0 * M_PI * r * r * k * k * (0.5 - k / 3.0));
}

static double cone_weight2(const double *p, double u, double v)
{
    double r = p[0], d = hypot(u, v);
    return d >= r * p[1] ? 0.0 : cone_norm(r, p[1]) * (1.0 - d / r);
}

/* G(x) = int_0^x (1 - sqrt(t^2 + y^2)) dt, |x| <= 1, |y| <= 1.  Below
 * |y| = 1e-150 the y^2 asinh term is under 1e-297 (and asinh(x / |y|)
 * would overflow): it is dropped. */
static double cone_g(double x, double y)
{
    double ay = fabs(y), rho = hypot(x, y);
    double log_term = ay > 1e-150 ? y * y * asinh(x / ay) : 0.0;
    return x - 0.5 * (x * rho + log_term);
}

static double cone_row_cdf(const double *p, double v, double u)
{
    double r = p[0], k = p[1], y = v / r;
    if (!(fabs(y) < k))
        return 0.0;
    double c = sqrt((k - y) * (k + y)), x = u / r;
    if (x <= -c)
        return 0.0;
    x = x >= c ? c : x;
    if (k == 1.0)
        return 3.0 / (M_PI * r) * (cone_g(x, y) + cone_g(c, y));
    return r * cone_norm(r, k) * (cone_g(x, y) + cone_g(c, y));
}

/* The radial filters in a mask (the cone, the Gaussian with cut > 0): the
 * mask's radius is p[0] p[1] (r cut, s cut), nothing lost outside it, and
 * the kinks of a row or column at its edges and centre. */
static double mask_radius(const double *p, double tail, double *lost)
{
    (void)tail;
    *lost = 0.0;
    return p[0] * p[1];
}

static int mask_kinks(const double *p, double *t)
{
    double rc = p[0] * p[1];
    t[0] = -rc;
    t[1] = 0.0;
    t[2] = rc;
    return 3;
}

const aa_filter_type aa_filter_cone = {
    {"cone",
     "radial cone of radius r pixels, not separable (Feibush et al. fig. 2f, 3a); cut<1: "
     "truncated at cut r and renormalised",
     cone_params},
    NULL,
    NULL,
    mask_radius, /* r cut, nothing lost */
    mask_kinks,  /* -r cut, 0, r cut */
    cone_weight2,
    cone_row_cdf};

/* ---- the Gaussian in a circular mask (radial, not separable) ---- */

/* 1 / Z, Z = 2 pi s^2 (1 - exp(-K^2 / 2)) the volume inside the mask. */
static double gmask_norm(double s, double k)
{
    return 1.0 / (2.0 * M_PI * s * s * -expm1(-0.5 * k * k));
}

static double gmask_weight2(const double *p, double u, double v)
{
    double s = p[0], rc = s * p[1], d2 = u * u + v * v;
    return d2 >= rc * rc ? 0.0 : gmask_norm(s, p[1]) * exp(-0.5 * d2 / (s * s));
}

static double gmask_row_cdf(const double *p, double v, double u)
{
    double s = p[0], rc = s * p[1];
    if (!(fabs(v) < rc))
        return 0.0;
    double c = sqrt((rc - v) * (rc + v));
    if (u <= -c)
        return 0.0;
    double x = u >= c ? c : u, q = 1.0 / (s * M_SQRT2);
    return gmask_norm(s, p[1]) * exp(-0.5 * (v / s) * (v / s)) * s * 1.2533141373155002512 *
           (erf(x * q) + erf(c * q));
}

/* Not in the registry: a `gauss` spec with cut > 0 takes this type (its
 * name and parameters are the Gaussian's, so its text is the same). */
const aa_filter_type aa_filter_gauss_mask = {
    {"gauss", "the Gaussian of standard deviation s pixels in a circular mask of radius cut s",
     gauss_params},
    NULL,
    NULL,
    mask_radius,
    mask_kinks,
    gmask_weight2,
    gmask_row_cdf};

/* ---- radially symmetric polynomials (1 - d^2/r^2)^k on a disc ---- */

/* c_k = (k + 1) / (pi r^2) */
static double radial_norm(double k, double r)
{
    return (k + 1.0) / (M_PI * r * r);
}

static double radial_weight2(const double *p, double u, double v)
{
    double k = p[0], r = p[1], x = u / r, y = v / r, q = 1.0 - (x * x + y * y);
    if (!(q > 0.0))
        return 0.0;
    double w = q;
    for (int i = 1; i < (int)k; i++)
        w *= q;
    return radial_norm(k, r) * w;
}

/* H_k(x) = int_0^x (a2 - t^2)^k dt (header), by Horner in x^2. */
static double radial_h(int k, double a2, double x)
{
    double z = x * x;
    switch (k) {
    case 1:
        return x * (a2 - z / 3.0);
    case 2:
        return x * (a2 * a2 + z * (-2.0 / 3.0 * a2 + z / 5.0));
    default:
        return x * (a2 * a2 * a2 + z * (-a2 * a2 + z * (0.6 * a2 - z / 7.0)));
    }
}

static double radial_row_cdf(const double *p, double v, double u)
{
    double r = p[1], y = v / r;
    int k = (int)p[0];
    if (!(fabs(y) < 1.0))
        return 0.0;
    double a2 = (1.0 - y) * (1.0 + y), a = sqrt(a2), x = u / r;
    if (x <= -a)
        return 0.0;
    x = x >= a ? a : x;
    return radial_norm(k, r) * r * (radial_h(k, a2, x) + radial_h(k, a2, a));
}

static double radial_radius(const double *p, double tail, double *lost)
{
    (void)tail;
    *lost = 0.0;
    return p[1];
}

static int radial_kinks(const double *p, double *t)
{
    t[0] = -p[1];
    t[1] = 0.0;
    t[2] = p[1];
    return 3;
}

const aa_filter_type aa_filter_radial = {
    {"radial",
     "radial polynomial (1 - d^2/r^2)^k on the disc of radius r pixels, k = 1, 2, 3, not "
     "separable (of Manson and Schaefer's radial kind; a family of our choice)",
     radial_params},
    NULL,
    NULL,
    radial_radius, /* r, nothing lost */
    radial_kinks,  /* -r, 0, r */
    radial_weight2,
    radial_row_cdf};

/* ---- the radial filters' slopes ----
 *
 * Each radial weight is W(d) of the distance d from the centre, not
 * increasing in d, with |W'(d)| <= L inside its mask and a drop J at the
 * mask's edge (0 where W is continuous there), from the weights above:
 *   cone:r=R,cut=K  W = n (1 - d / R): L = n / R, J = n (1 - K);
 *   gauss:s=S,cut=K W = n exp(-d^2 / (2 S^2)), |W'| = n d / S^2 exp(..),
 *                   largest at d = S: L = n / (S sqrt e) (at d = K S if
 *                   K < 1), J = n exp(-K^2 / 2);
 *   radial:k=K,r=R  W = n (1 - u^2)^K, u = d / R, |W'| = n 2 K u (1 -
 *                   u^2)^(K-1) / R, largest at u = 1, 1/sqrt 3, 1/sqrt 5
 *                   (its derivative's roots): L = 2 n / R, 8 n / (3
 *                   sqrt(3) R), 96 n / (25 sqrt(5) R); J = 0.
 * n is the weight's normalisation.  Each is widened by 1e-12 of itself
 * for the rounding of its few operations. */
int aa_filter_radial_slope(const aa_filter *f, double *slope, double *jump)
{
    const double *p = f->spec.v;
    double L, J;
    if (f->type == &aa_filter_cone) {
        double n = cone_norm(p[0], p[1]);
        L = n / p[0], J = p[1] == 1.0 ? 0.0 : n * (1.0 - p[1]);
    } else if (f->type == &aa_filter_gauss_mask) {
        double n = gmask_norm(p[0], p[1]), s = p[0], k = p[1];
        L = k >= 1.0 ? n / (s * sqrt(M_E)) : n * k / s * exp(-0.5 * k * k);
        J = n * exp(-0.5 * k * k);
    } else if (f->type == &aa_filter_radial) {
        int k = (int)p[0];
        double n = radial_norm(k, p[1]), r = p[1];
        L = k == 1   ? 2.0 * n / r
            : k == 2 ? 8.0 * n / (3.0 * sqrt(3.0) * r)
                     : 96.0 * n / (25.0 * sqrt(5.0) * r);
        J = 0.0;
    } else
        return 0;
    *slope = L * (1.0 + 1e-12), *jump = J * (1.0 + 1e-12);
    return 1;
}

/* ---- B-splines ---- */

static double bspline_weight(const double *p, double t)
{
    double a = fabs(t);
    if (p[0] == 2.0) {
        if (a < 0.5)
            return 0.75 - a * a;
        double z = 1.5 - a;
        return a < 1.5 ? 0.5 * z * z : 0.0;
    }
    if (a < 1.0)
        return (4.0 + a * a * (3.0 * a - 6.0)) / 6.0;
    double z = 2.0 - a;
    return a < 2.0 ? z * z * z / 6.0 : 0.0;
}

/* The mass left of -|t| (the tail), then C(t). */
static double bspline_cdf(const double *p, double t)
{
    double a = fabs(t), tail;
    if (p[0] == 2.0) {
        double z = 1.5 - a;
        tail = a >= 1.5 ? 0.0 : a >= 0.5 ? z * z * z / 6.0 : 0.5 - a * (0.75 - a * a / 3.0);
    } else {
        double z = 2.0 - a;
        tail = a >= 2.0   ? 0.0
               : a >= 1.0 ? z * z * z * z / 24.0
                          : 0.5 - a * (4.0 + a * a * (0.75 * a - 2.0)) / 6.0;
    }
    return t < 0.0 ? tail : 1.0 - tail;
}

static double bspline_radius(const double *p, double tail, double *lost)
{
    (void)tail;
    *lost = 0.0;
    return p[0] == 2.0 ? 1.5 : 2.0;
}

static int bspline_kinks(const double *p, double *t)
{
    if (p[0] == 2.0) {
        t[0] = -1.5, t[1] = -0.5, t[2] = 0.5, t[3] = 1.5;
        return 4;
    }
    for (int k = 0; k < 5; k++)
        t[k] = k - 2.0;
    return 5;
}

const aa_filter_type aa_filter_bspline = {
    {"bspline", "separable B-spline: order=2 quadratic, order=3 cubic (the default)",
     bspline_params},
    bspline_weight, bspline_cdf, bspline_radius, bspline_kinks, NULL, NULL};

/* ---- Mitchell-Netravali and Catmull-Rom ---- */

static double mitchell_weight(const double *p, double t)
{
    double B = p[0], C = p[1], a = fabs(t);
    if (a < 1.0)
        return ((12.0 - 9.0 * B - 6.0 * C) * a * a * a + (-18.0 + 12.0 * B + 6.0 * C) * a * a +
                (6.0 - 2.0 * B)) /
               6.0;
    if (a >= 2.0)
        return 0.0;
    double z = 2.0 - a;
    return z * z * ((B + 6.0 * C) * z - 6.0 * C) / 6.0;
}

static double mitchell_cdf(const double *p, double t)
{
    double B = p[0], C = p[1], a = fabs(t), tail;
    if (a >= 2.0) {
        tail = 0.0;
    } else if (a >= 1.0) {
        double z = 2.0 - a;
        tail = z * z * z * ((B + 6.0 * C) * 0.25 * z - 2.0 * C) / 6.0;
    } else {
        double in = a * (((12.0 - 9.0 * B - 6.0 * C) * 0.25 * a + (-18.0 + 12.0 * B + 6.0 * C) /
                                                                      3.0) *
                             a * a +
                         (6.0 - 2.0 * B)) /
                    6.0;
        tail = 0.5 - in;
    }
    return t < 0.0 ? tail : 1.0 - tail;
}

static double mitchell_radius(const double *p, double tail, double *lost)
{
    (void)p, (void)tail;
    *lost = 0.0;
    return 2.0;
}

static int mitchell_kinks(const double *p, double *t)
{
    (void)p;
    for (int k = 0; k < 5; k++)
        t[k] = k - 2.0;
    return 5;
}

const aa_filter_type aa_filter_mitchell = {
    {"mitchell", "separable Mitchell-Netravali cubic, b=B, c=C (1/3, 1/3), support 4 pixels",
     mitchell_params},
    mitchell_weight, mitchell_cdf, mitchell_radius, mitchell_kinks, NULL, NULL};

static const double catrom_bc[2] = {0.0, 0.5};

static double catrom_weight(const double *p, double t)
{
    (void)p;
    return mitchell_weight(catrom_bc, t);
}

static double catrom_cdf(const double *p, double t)
{
    (void)p;
    return mitchell_cdf(catrom_bc, t);
}

const aa_filter_type aa_filter_catrom = {
    {"catrom", "separable Catmull-Rom spline: mitchell:b=0,c=0.5", no_params},
    catrom_weight, catrom_cdf, mitchell_radius, mitchell_kinks, NULL, NULL};

/* ---- Lanczos ---- */

/* sin(x) / x */
static double sinc_x(double x)
{
    return fabs(x) < 1e-5 ? 1.0 - x * x / 6.0 : sin(x) / x;
}

/* F_k(t) = k Si(k t) - 2 sin^2(k t / 2) / t, 0 at t = 0. */
static double lanczos_f(double k, double t)
{
    if (t == 0.0)
        return 0.0;
    double h = sin(0.5 * k * t);
    return k * gsl_sf_Si(k * t) - 2.0 * h * h / t;
}

/* P(t) = int_0^t sinc(s) sinc(s / a) ds, unnormalised. */
static double lanczos_p(double a, double t)
{
    return a / (2.0 * M_PI * M_PI) *
           (lanczos_f(M_PI * (1.0 + 1.0 / a), t) - lanczos_f(M_PI * (1.0 - 1.0 / a), t));
}

/* M = 2 P(a), the integral over [-a, a], from the closed form above in
 * 40-digit arithmetic (mpmath's si; its own quadrature of the weight
 * agrees to every digit); tests/test_filter.c checks them against GSL's
 * quadrature of the weight and against 2 lanczos_p(a, a). */
static double lanczos_mass(double a)
{
    return a == 2.0 ? 1.0097898406187323125 : 0.99705534595433968251;
}

static double lanczos_weight(const double *p, double t)
{
    double a = p[0];
    if (!(fabs(t) < a))
        return 0.0;
    return sinc_x(M_PI * t) * sinc_x(M_PI * t / a) / lanczos_mass(a);
}

static double lanczos_cdf(const double *p, double t)
{
    double a = p[0];
    if (t <= -a)
        return 0.0;
    if (t >= a)
        return 1.0;
    return 0.5 + lanczos_p(a, t) / lanczos_mass(a);
}

static double lanczos_radius(const double *p, double tail, double *lost)
{
    (void)tail;
    *lost = 0.0;
    return p[0];
}

/* Not smooth at +-a only; the integers between, where it changes sign,
 * are breakpoints for the quadrature too. */
static int lanczos_kinks(const double *p, double *t)
{
    int a = (int)p[0], n = 0;
    for (int k = -a; k <= a; k++)
        t[n++] = k;
    return n;
}

const aa_filter_type aa_filter_lanczos = {
    {"lanczos", "separable Lanczos window sinc(t) sinc(t/a) on |t| < a, normalised",
     lanczos_params},
    lanczos_weight, lanczos_cdf, lanczos_radius, lanczos_kinks, NULL, NULL};

const aa_filter_type aa_filter_box = {
    {"box", "1 on [-1/2, 1/2]^2: area sampling (the default)", no_params},
    box_weight, box_cdf, box_radius, box_kinks, NULL, NULL};

const aa_filter_type aa_filter_tent = {
    {"tent", "separable pyramid of half-width r pixels (Crow fig. 2.13: r=0.5, 2.14: r=1)",
     tent_params},
    tent_weight, tent_cdf, tent_radius, tent_kinks, NULL, NULL};

const aa_filter_type aa_filter_gauss = {
    {"gauss",
     "separable untruncated Gaussian of standard deviation s pixels; cut=K > 0: radial, in "
     "a circular mask of radius K s and renormalised (Feibush et al. fig. 4d: cut=2)",
     gauss_params},
    gauss_weight, gauss_cdf, gauss_radius, gauss_kinks, NULL, NULL};

const aa_filter_type *const aa_filter_types[] = {
    &aa_filter_box,      &aa_filter_tent,     &aa_filter_gauss,   &aa_filter_cone,
    &aa_filter_radial,   &aa_filter_bspline,  &aa_filter_mitchell, &aa_filter_catrom,
    &aa_filter_lanczos,  NULL};

/* The tail of the 2-D weight a user may neglect (well under the 1e-12
 * bound of the reference). */
#define FILTER_TAIL 1e-14

static void filter_init(aa_filter *f)
{
    /* the Gaussian in a mask is radial: its own type, the same spec */
    if (f->type == &aa_filter_gauss && f->spec.v[1] > 0.0)
        f->type = &aa_filter_gauss_mask;
    f->radius = f->type->radius(f->spec.v, FILTER_TAIL, &f->lost);
}

int aa_filter_parse(const char *text, aa_filter *out)
{
    aa_spec spec;
    int st = aa_spec_parse(text, (const void *const *)aa_filter_types, "filter", &spec);
    if (st)
        return st;
    out->type = (const aa_filter_type *)spec.info;
    out->spec = spec;
    filter_init(out);
    return AA_OK;
}

void aa_filter_default(aa_filter *out)
{
    out->type = &aa_filter_box;
    aa_spec_default(&aa_filter_box.info, &out->spec);
    filter_init(out);
}

int aa_filter_is_box(const aa_filter *f)
{
    return f->type == &aa_filter_box;
}

/* N, the 2-D negative mass: for a separable weight with 1-D negative mass
 * n (and positive mass 1 + n), the product is negative where one factor
 * is, N = 2 n (1 + n).  n by the midpoint rule on 8192 cells over the
 * support (the lobes are smooth: error under 1e-6 of n), widened by 1e-3
 * of itself; radial filters here are non-negative. */
void aa_filter_range(const aa_filter *f, double *lo, double *hi)
{
    double n = 0.0;
    if (aa_filter_is_separable(f) && f->type != &aa_filter_box && f->type != &aa_filter_tent &&
        f->type != &aa_filter_gauss && f->type != &aa_filter_bspline) {
        const int cells = 8192;
        double R = f->radius, h = 2.0 * R / cells;
        for (int k = 0; k < cells; k++) {
            double w = aa_filter_weight(f, -R + (k + 0.5) * h);
            if (w < 0.0)
                n -= w * h;
        }
        n *= 1.001;
    }
    double N = 2.0 * n * (1.0 + n);
    *lo = N > 0.0 ? -N : 0.0;
    *hi = 1.0 + N;
}
