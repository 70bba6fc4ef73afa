/*
 * zoneplate.c: the zone plate, exactly as patterns/README.md, `zoneplate`, defines
 * it: I(x, y) = (1 + cos(k r^2))/2, grey, r^2 = (x - 1/2)^2 + (y - 1/2)^2,
 * on the whole plane (no background).  The local frequency is k r/pi cycles
 * per unit, so with the default k = 256 pi it reaches 128 cycles per unit,
 * the Nyquist limit of a 256-pixel image, at r = 1/2 (the middle of each
 * side); toward the corners (r up to 0.71) it passes it and the rings alias
 * into false plates, which is what the pattern is for.
 *
 * The scene is a field (core.h, "Fields"): this point function plus its
 * own exact pixel integral.  Placed by (sx, sy, tx, ty) (aa_scene_place:
 * sx = W, tx = t vx), pixel (i, j) under the separable filter w(u) w(v) is
 *
 *     P = 1/2 + 1/2 Re[Gx(i) Gy(j)],   Gx(i) = int w(s) exp(i a (c + s)^2) ds,
 *
 * with a = k/sx^2 and c = i + 1/2 - tx - sx/2 the pixel centre's offset
 * from the plate's centre (and the same in y), because
 * cos(a(X^2 + Y^2)) = Re[exp(i a X^2) exp(i a Y^2)].  So an image costs
 * W + H one-dimensional integrals, each in closed form:
 *
 *  - Gaussian (untruncated): a Gaussian times a complex Gaussian,
 *    G = (1 - 2 i a S^2)^(-1/2) exp(i a c^2 / (1 - 2 i a S^2)).
 *  - box and tent, where the phase over the support is small (a R^2 <= 1
 *    and 2 a |c| R <= 3, R the support's half-width): G = exp(i a c^2)
 *    times the double Taylor series of exp(i (2 a c s + a s^2)) against
 *    the filter's moments, every term a closed-form moment, no
 *    cancellation (its terms' magnitudes sum to at most e cosh 3).
 *  - elsewhere, Fresnel integrals: with P(z) = int_0^z exp(i a u^2) du =
 *    sqrt(pi/(2a)) E(z sqrt(2a/pi)), E = C + i S, the box is
 *    P(c + 1/2) - P(c - 1/2), and the tent, integrated by parts,
 *    [(r+c) P(c+r) - 2c P(c) - (r-c) P(c-r)]/r^2 plus the elementary
 *    (2 e(c) - e(c-r) - e(c+r))/(2 i a r^2), e(z) = exp(i a z^2).
 *    E(t) is its power series for |t| < 1.5 (terms below 4 in size) and
 *    (1+i)/2 - Q(t) exp(i pi t^2/2) beyond, Q from the continued fraction
 *    of the complementary error function (modified Lentz), so that the
 *    constant (1+i)/2 is never subtracted from itself: two ends on the
 *    same side cancel it symbolically and only the small O(1/t) parts are
 *    subtracted.
 *
 * Every phase a z^2 is formed in double-double arithmetic from a and z held
 * as unevaluated sums, and reduced modulo 2 pi in double-double, so a large
 * phase (far corners, large k, motion) costs no accuracy.  Each 1-D value
 * carries a bound (a few ulp per operation of the magnitudes it handles,
 * one per iteration of the continued fraction), and a pixel the bound of
 * the product.
 *
 * Domain: 0 < k <= 1e6 (AA__ZONEPLATE_KMAX).  At the limit the plate has
 * 1.6e5 cycles per unit at r = 1/2, aliasing even on the largest image
 * (65536 pixels); the reference stays exact, but the point function,
 * evaluated in plain double as methods sample it, loses about k 1e-16 in
 * phase, and nothing is gained by going further.
 *
 * Known answers (tests/test_zoneplate.c): the 1-D integrals against GSL's
 * adaptive quadrature, whole pixels against 2-D quadrature, the centre
 * pixel of a low-k plate against its Taylor expansion, and motion against
 * the pattern shifted by hand.
 */
#include "patterns.h"
#include "zoneplate.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef CMPLX
/* glibc defines CMPLX only for compilers that have __builtin_complex (not
 * clang 14); C11 6.2.5 lays a complex number out as an array of its real
 * and imaginary parts, so this builds the same value, signed zeros and
 * infinities included. */
static inline double complex zp_cmplx(double re, double im)
{
    union {
        double complex z;
        double part[2];
    } u;
    u.part[0] = re;
    u.part[1] = im;
    return u.z;
}
#define CMPLX(re, im) zp_cmplx((re), (im))
#endif

#ifdef _OPENMP
#include <omp.h>
#endif

enum { P_K };

static const aa_param zoneplate_params[] = {
    {"k", AA_PARAM_REAL, 256.0 * M_PI, 0.0, AA__ZONEPLATE_KMAX, 1, NULL,
     "k in cos(k r^2): 0 < k <= 1e6 (default 256 pi: Nyquist of 256 px at r = 1/2)"},
    {0}};

/* ---- double-double ---- */

typedef struct dd {
    double hi, lo;
} dd;

static dd two_sum(double a, double b)
{
    double s = a + b, bb = s - a;
    return (dd){s, (a - (s - bb)) + (b - bb)};
}

static dd quick(double hi, double lo)
{
    double s = hi + lo;
    return (dd){s, lo - (s - hi)};
}

static dd dd_add(dd x, dd y)
{
    dd s = two_sum(x.hi, y.hi);
    return quick(s.hi, s.lo + (x.lo + y.lo));
}

static dd dd_mul(dd x, dd y)
{
    double p = x.hi * y.hi, e = fma(x.hi, y.hi, -p);
    return quick(p, e + (x.hi * y.lo + x.lo * y.hi));
}

static dd dd_div(dd x, dd y)
{
    double q1 = x.hi / y.hi;
    dd r = dd_add(x, dd_mul((dd){-q1, 0.0}, y));
    return quick(q1, r.hi / y.hi);
}

/* exp(i theta) with theta reduced modulo 2 pi in double-double. */
static double complex expi_dd(dd th)
{
    static const dd two_pi = {6.283185307179586232, 2.4492935982947064e-16};
    double n = nearbyint(th.hi / two_pi.hi);
    dd p = dd_mul((dd){n, 0.0}, two_pi);
    dd r = dd_add(th, (dd){-p.hi, -p.lo});
    double x = r.hi + r.lo;
    return CMPLX(cos(x), sin(x));
}

/* exp(i a z^2). */
static double complex expi_sq(dd a, dd z)
{
    return expi_dd(dd_mul(a, dd_mul(z, z)));
}

/* ---- Fresnel integrals ---- */

#define FRESNEL_T 1.5 /* series below, continued fraction above */

/* P(z) = int_0^z exp(i a u^2) du = z sum_n (i a z^2)^n / (n! (2n+1)), for
 * a z^2 <= pi/2 FRESNEL_T^2 (terms below 4); *mag: sum of |terms|. */
static double complex prim_series(double a, double z, double *mag)
{
    double th = a * z * z, m = 0.0;
    double complex term = 1.0, sum = 0.0;
    for (int n = 0; n < 60; n++) {
        double complex t = term / (2 * n + 1);
        sum += t;
        m += cabs(t);
        if (cabs(t) < 1e-20 * m)
            break;
        term *= CMPLX(0.0, th) / (n + 1);
    }
    *mag = m * fabs(z);
    return z * sum;
}

/* Q(t), t >= FRESNEL_T: E(t) = (1+i)/2 - Q(t) exp(i pi t^2/2).  Q(t) = t h
 * with h the continued fraction of erfc at the point sqrt(pi)/2 (1 - i) t,
 * evaluated by the modified Lentz method. */
static double complex fresnel_q(double t, int *iters)
{
    const double tiny = 1e-300;
    double complex b = CMPLX(1.0, -M_PI * t * t), c = 1.0 / tiny, d = 1.0 / b, h = d;
    double n = -1.0;
    for (int k = 2; k < 10000; k++) {
        n += 2.0;
        double an = -n * (n + 1.0);
        b += 4.0;
        d = an * d + b;
        if (cabs(d) < tiny)
            d = tiny;
        d = 1.0 / d;
        c = b + an / c;
        if (cabs(c) < tiny)
            c = tiny;
        double complex del = c * d;
        h *= del;
        *iters = k;
        if (cabs(del - 1.0) < 0.5 * DBL_EPSILON)
            break;
    }
    return t * h;
}

/* P(z) = kappa K + v, K = sqrt(pi/(2a)) (1+i)/2: the constant kept apart;
 * err bounds the rounding error of v: each operation of the series or of
 * the continued fraction (one per iteration, a handful of products after)
 * costs at most a few ulp of the magnitudes it handles. */
typedef struct prim {
    int kappa;
    double complex v;
    double err;
} prim;

static prim primitive(dd a, dd z)
{
    double zz = z.hi + z.lo, sq = sqrt(M_PI / (2.0 * a.hi)), t = fabs(zz) / sq;
    prim P = {0, 0.0, 0.0};
    if (t < FRESNEL_T) {
        double mag;
        P.v = prim_series(a.hi, zz, &mag);
        P.err = 64.0 * DBL_EPSILON * mag; /* at most 30 terms of 2 roundings */
        return P;
    }
    int iters = 0;
    P.kappa = zz > 0 ? 1 : -1;
    P.v = -P.kappa * sq * fresnel_q(t, &iters) * expi_sq(a, z);
    P.err = (4.0 * iters + 16.0) * DBL_EPSILON * cabs(P.v);
    return P;
}

/* ---- the one-dimensional integrals ---- */

/* int w(s) s^(2q) ds over the support, divided by R^(2q). */
static double moment(int tent, int q)
{
    return tent ? 2.0 / ((2.0 * q + 1.0) * (2.0 * q + 2.0)) : 1.0 / (2.0 * q + 1.0);
}

/* Small phase over the support [-R, R]: exp(i a c^2) sum_nm (i a)^n/n!
 * (-(2ac)^2)^m/(2m)! mu_(n+m), with A = a R^2 <= 1, B = 2 a |c| R <= 3:
 * truncating at n = 22, m = 16 leaves less than 1e-20. */
static double complex local_series(int tent, double R, dd a, dd c, double *err)
{
    double A = a.hi * R * R, B = 2.0 * a.hi * (c.hi + c.lo) * R;
    double pb[17];
    pb[0] = 1.0;
    for (int m = 1; m <= 16; m++)
        pb[m] = pb[m - 1] * (-B * B) / ((2.0 * m - 1.0) * (2.0 * m));
    double complex pa = 1.0, sum = 0.0;
    double m_abs = 0.0;
    for (int n = 0; n <= 22; n++) {
        double complex inner = 0.0;
        double inner_abs = 0.0;
        for (int m = 16; m >= 0; m--) {
            double t = pb[m] * moment(tent, n + m);
            inner += t;
            inner_abs += fabs(t);
        }
        sum += pa * inner;
        m_abs += cabs(pa) * inner_abs;
        pa *= CMPLX(0.0, A) / (n + 1);
    }
    /* 17 + 23 additions, a product per term, and the phase */
    *err = 48.0 * DBL_EPSILON * m_abs;
    return expi_sq(a, c) * sum;
}

static double complex box_fresnel(dd a, dd c, double *err)
{
    prim p1 = primitive(a, dd_add(c, (dd){0.5, 0.0}));
    prim p0 = primitive(a, dd_add(c, (dd){-0.5, 0.0}));
    double sq = sqrt(M_PI / (2.0 * a.hi));
    double complex K = CMPLX(0.5 * sq, 0.5 * sq);
    int kk = p1.kappa - p0.kappa;
    *err = p1.err + p0.err + 4.0 * DBL_EPSILON * (abs(kk) * cabs(K) + cabs(p1.v) + cabs(p0.v));
    return kk * K + (p1.v - p0.v);
}

static double complex tent_fresnel(double r, dd a, dd c, double *err)
{
    double cc = c.hi + c.lo;
    prim pp = primitive(a, dd_add(c, (dd){r, 0.0}));
    prim p0 = primitive(a, c);
    prim pm = primitive(a, dd_add(c, (dd){-r, 0.0}));
    double sq = sqrt(M_PI / (2.0 * a.hi)), r2 = r * r;
    double wp = (r + cc) / r2, w0 = -2.0 * cc / r2, wm = -(r - cc) / r2;
    double complex K = CMPLX(0.5 * sq, 0.5 * sq);
    /* the constant's weight, in integers where they cancel (it is 0 when
     * all three ends are on one side) */
    double kk = (r * (pp.kappa - pm.kappa) + cc * (pp.kappa - 2 * p0.kappa + pm.kappa)) / r2;
    double complex e0 = expi_sq(a, c), ep = expi_sq(a, dd_add(c, (dd){r, 0.0})),
                   em = expi_sq(a, dd_add(c, (dd){-r, 0.0}));
    double complex den = CMPLX(0.0, 2.0 * a.hi * r2);
    double complex elem = (2.0 * e0 - em - ep) / den;
    double terms = fabs(wp) * cabs(pp.v) + fabs(w0) * cabs(p0.v) + fabs(wm) * cabs(pm.v) +
                   fabs(kk) * cabs(K) + 4.0 / cabs(den);
    *err = fabs(wp) * pp.err + fabs(w0) * p0.err + fabs(wm) * pm.err +
           8.0 * DBL_EPSILON * terms;
    return kk * K + (wp * pp.v + w0 * p0.v + wm * pm.v) + elem;
}

/* int N(s; 0, S^2) exp(i a (c+s)^2) ds = (1 - 2 i a S^2)^(-1/2)
 * exp(i a c^2 / (1 - 2 i a S^2)); with q = 4 a^2 S^4 the exponent is
 * (i a c^2 - 2 a^2 S^2 c^2)/(1 + q): the phase a c^2/(1 + q) is formed
 * in double-double. */
static double complex gauss_closed(double S, dd a, dd c, double *err)
{
    double s2 = S * S, q = 4.0 * a.hi * a.hi * s2 * s2;
    dd th = dd_mul(a, dd_mul(c, c));
    dd phase = dd_div(th, two_sum(1.0, q));
    double decay = exp(-2.0 * a.hi * s2 * (th.hi + th.lo) / (1.0 + q));
    double complex g = csqrt(1.0 / CMPLX(1.0, -2.0 * a.hi * s2)) * decay * expi_dd(phase);
    *err = 16.0 * DBL_EPSILON * cabs(g) + DBL_MIN;
    return g;
}

int aa__zoneplate_1d(const aa_filter *f, double a_hi, double a_lo, double c_hi, double c_lo,
                     double complex *g, double *bound)
{
    dd a = quick(a_hi, a_lo), c = quick(c_hi, c_lo);
    double err = 0.0;
    if (!(a.hi > 0.0) || !isfinite(a.hi) || !isfinite(c.hi))
        return aa_fail(AA_EINVAL, "zone plate integral needs a > 0 and c finite");
    if (f->type == &aa_filter_gauss) {
        *g = gauss_closed(f->spec.v[0], a, c, &err);
    } else if (f->type == &aa_filter_box || f->type == &aa_filter_tent) {
        int tent = f->type == &aa_filter_tent;
        double R = tent ? f->spec.v[0] : 0.5;
        double A = a.hi * R * R, B = 2.0 * a.hi * fabs(c.hi + c.lo) * R;
        if (A <= 1.0 && B <= 3.0)
            *g = local_series(tent, R, a, c, &err);
        else
            *g = tent ? tent_fresnel(R, a, c, &err) : box_fresnel(a, c, &err);
    } else {
        /* (gauss with cut > 0 is the Gaussian in a mask: its own type) */
        char text[256];
        if (aa_spec_format(&f->spec, text, sizeof text))
            snprintf(text, sizeof text, "%s", f->type->info.name);
        return aa_fail(AA_EINVAL, "zone plate: no exact integral for filter %s", text);
    }
    if (bound)
        *bound = err;
    return AA_OK;
}

/* ---- the field ---- */

static aa_rgb zoneplate_value(const double *p, double x, double y)
{
    double X = x - 0.5, Y = y - 0.5;
    double v = 0.5 + 0.5 * cos(p[P_K] * (X * X + Y * Y));
    return (aa_rgb){{v, v, v}};
}

/* The integrals of every column (n = W, scale s, shift t) into g, their
 * bounds into b and their magnitudes into m. */
static int axis_integrals(double k, double s, double t, int n, const aa_filter *f,
                          double complex *g, double *b, double *m, int threads)
{
    dd a = dd_div((dd){k, 0.0}, dd_mul((dd){s, 0.0}, (dd){s, 0.0}));
    dd o = two_sum(t, 0.5 * s); /* the plate's centre in pixel units */
    int status = AA_OK;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = 0; i < n; i++) {
        dd c = dd_add(two_sum(i + 0.5, -o.hi), (dd){-o.lo, 0.0});
        int st = aa__zoneplate_1d(f, a.hi, a.lo, c.hi, c.lo, &g[i], &b[i]);
        m[i] = cabs(g[i]);
        if (st) {
#pragma omp atomic write
            status = st;
        }
    }
    return status;
}

static int zoneplate_pixels(const double *p, const double map[4], const aa_filter *f,
                            int threads, aa_image *out, aa_image *bound, double *max_bound,
                            int worst[2])
{
#ifdef _OPENMP
    int nt = aa_thread_count(threads);
#else
    int nt = 1;
    (void)threads;
#endif
    int W = out->w, H = out->h;
    double complex *gx = malloc(((size_t)W + (size_t)H) * sizeof *gx), *gy = gx ? gx + W : NULL;
    size_t n = (size_t)W + (size_t)H;
    double *bx = malloc(2 * n * sizeof *bx), *by = bx ? bx + W : NULL;
    double *mx = bx ? bx + n : NULL, *my = bx ? mx + W : NULL;
    int st = AA_OK;
    if (!gx || !bx)
        st = aa_fail(AA_ENOMEM, "out of memory for the zone plate's %d + %d integrals", W, H);
    if (!st)
        st = axis_integrals(p[P_K], map[0], map[2], W, f, gx, bx, mx, nt);
    if (!st)
        st = axis_integrals(p[P_K], map[1], map[3], H, f, gy, by, my, nt);
    double worst_b = 0.0;
    int wi = -1, wj = -1;
    if (!st) {
#pragma omp parallel num_threads(nt)
        {
            double tb = 0.0;
            int ti = -1, tj = -1;
#pragma omp for schedule(static)
            for (int j = 0; j < H; j++) {
                for (int i = 0; i < W; i++) {
                    double v = 0.5 + 0.5 * creal(gx[i] * gy[j]);
                    double e = 0.5 * (my[j] * bx[i] + mx[i] * by[j] + bx[i] * by[j]) +
                               2.0 * DBL_EPSILON;
                    v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
                    double *px = aa_pixel(out, i, j);
                    px[0] = px[1] = px[2] = v;
                    if (bound)
                        *aa_pixel(bound, i, j) = e;
                    if (e > tb)
                        tb = e, ti = i, tj = j;
                }
            }
#pragma omp critical(aa_zoneplate_worst)
            if (tb > worst_b || (tb == worst_b && tj >= 0 && (wj < 0 || tj < wj ||
                                                              (tj == wj && ti < wi))))
                worst_b = tb, wi = ti, wj = tj;
        }
    }
    free(gx);
    free(bx);
    if (max_bound)
        *max_bound = worst_b;
    if (worst)
        worst[0] = wi, worst[1] = wj;
    return st;
}

static const aa_field_type zoneplate_field = {"zoneplate", 1, 1, zoneplate_value,
                                              zoneplate_pixels};

static int zoneplate_build(const double *p, aa_scene *s)
{
    return aa_scene_set_field(s, &zoneplate_field, p, 1);
}

const aa_pattern_type aa_pattern_zoneplate = {
    {"zoneplate", "zone plate (1 + cos(k r^2))/2: rings up to and past Nyquist at the corners",
     zoneplate_params},
    NULL,
    zoneplate_build,
    {{0, 0, 0}}};
