/*
 * filter.c: the reconstruction filters of patterns/README.md ("Filters"), in
 * pixel units.
 *
 * Every filter is separable, w(u) w(v), with a 1-D weight normalised to
 * integral 1, so exact methods and the ground truth need only the 1-D
 * weight and its integral (the cdf): the integral of the filter over a span
 * [x0, x1] of constant colour along a line is cdf(x1 - uc) - cdf(x0 - uc).
 *
 *   box        1 on [-1/2, 1/2]                        (area sampling)
 *   tent:r=R   max(0, 1 - |t|/R) / R                   (Crow fig. 2.13, 2.14)
 *   gauss:s=S  exp(-t^2 / (2 S^2)) / (S sqrt(2 pi))    (untruncated)
 *
 * and one radial filter that is not separable (added to the three separable
 * ones: Feibush, Levoy and Cook 1980, fig. 2f and 3a, the cone their
 * circular filter table is drawn for):
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
 * The Gaussian has unbounded support; users of `radius` truncate it where
 * the 2-D mass outside the square [-R, R]^2 is below a stated tail, and
 * that mass is reported so it can enter an error bound.
 */
#include "core.h"

#include <math.h>

static const aa_param no_params[] = {{0}};

static const aa_param tent_params[] = {
    {"r", AA_PARAM_REAL, 1.0, 0.01, 16.0, 0, NULL,
     "half-width in pixels: the weight falls linearly to zero at |t| = r"},
    {0}};

static const aa_param gauss_params[] = {
    {"s", AA_PARAM_REAL, 0.5, 0.01, 8.0, 0, NULL, "standard deviation in pixels"},
    {0}};

static const aa_param cone_params[] = {
    {"r", AA_PARAM_REAL, 1.0, 0.01, 8.0, 0, NULL,
     "radius in pixels: the weight falls linearly to zero at distance r from the centre"},
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

/* ---- cone (radial, not separable) ---- */

static double cone_weight2(const double *p, double u, double v)
{
    double r = p[0], d = hypot(u, v);
    return d >= r ? 0.0 : 3.0 / (M_PI * r * r) * (1.0 - d / r);
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
    double r = p[0], y = v / r;
    if (!(fabs(y) < 1.0))
        return 0.0;
    double c = sqrt((1.0 - y) * (1.0 + y)), x = u / r;
    if (x <= -c)
        return 0.0;
    x = x >= c ? c : x;
    return 3.0 / (M_PI * r) * (cone_g(x, y) + cone_g(c, y));
}

const aa_filter_type aa_filter_cone = {
    {"cone",
     "radial cone of radius r pixels, not separable (Feibush et al. fig. 2f, 3a)",
     cone_params},
    NULL,
    NULL,
    tent_radius, /* r, nothing lost */
    tent_kinks,  /* -r, 0, r */
    cone_weight2,
    cone_row_cdf};

const aa_filter_type aa_filter_box = {
    {"box", "1 on [-1/2, 1/2]^2: area sampling (the default)", no_params},
    box_weight, box_cdf, box_radius, box_kinks, NULL, NULL};

const aa_filter_type aa_filter_tent = {
    {"tent", "separable pyramid of half-width r pixels (Crow fig. 2.13: r=0.5, 2.14: r=1)",
     tent_params},
    tent_weight, tent_cdf, tent_radius, tent_kinks, NULL, NULL};

const aa_filter_type aa_filter_gauss = {
    {"gauss", "separable untruncated Gaussian of standard deviation s pixels", gauss_params},
    gauss_weight, gauss_cdf, gauss_radius, gauss_kinks, NULL, NULL};

const aa_filter_type *const aa_filter_types[] = {&aa_filter_box, &aa_filter_tent,
                                                 &aa_filter_gauss, &aa_filter_cone, NULL};

/* The tail of the 2-D weight a user may neglect (well under the 1e-12
 * bound of the reference). */
#define FILTER_TAIL 1e-14

static void filter_init(aa_filter *f)
{
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
