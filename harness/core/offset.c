/*
 * offset.c: offset curves and evolutes of cubic Bezier arcs and of ellipses
 * (aabench.h, aa_offset_curve), the exact boundaries of the stroke of a
 * Bezier arc or an elliptical arc: their points and derivatives, the turns
 * of either coordinate, and the one root of a coordinate on a part where it
 * is monotone.
 *
 * With B' = B'(t), B'' and B''' its derivatives, L = |B'|, the unit normal
 * N = (-B'y, B'x)/L and the curvature k = c/L^3, c = B' x B'':
 *  - the offset P = B + d N has P' = B' (1 - d k) (N' = -k L T, T = B'/L):
 *    parallel to B', vanishing only where d k = 1 (a fold of the offset);
 *  - the evolute E = B + N/k = B + N L^3/c has E' = (1/k)' N, with
 *        (1/k)' = L (3 (B' . B'') c - L^2 c')/c^2,  c' = B' x B''',
 *    which vanishes at the extremes of the curvature (cusps of E).
 * So on a part without folds (offsets) or curvature extremes (evolutes) the
 * turns of a coordinate of m(P) are those of m(B'), and of m(E) those of
 * m(N) L, in closed form: for a cubic B' is a quadratic in t; for the
 * ellipse B = c + u cos t + v sin t, B' = -u sin t + v cos t, B'' = -(B -
 * c), B''' = -B', so c = u x v is constant, c' = 0, and a coordinate of
 * m(B') or m(N) L is a cos t + b sin t, zero at atan2(b, a) + pi/2 + k pi.
 * Everything is evaluated in long double.
 *
 * A cubic whose B' vanishes at an end te (a control point on its end
 * point; the stroker splits a cusp into two such arcs; |B'(te)| within
 * 1e-12 of the sum of the coefficients' magnitudes, so that the rounding
 * of B' at a cusp counts as 0: aa__offset_stop) is evaluated on the half of
 * [0, 1] next to te in the factored form B' = (t - te) Q, Q = B''(te) +
 * (t - te) Q' (Q' = 3 b3; the remainder B'(te) dropped), where B' itself
 * would lose its direction to rounding near te: with s = t - te, sg its
 * sign on the curve (1 for te = 0, -1 for te = 1) and X = Q x Q' (a
 * constant), L = |s| |Q|, N = sg perp(Q)/|Q| (perp(a) = (-ay, ax)),
 * k = X/(|s| |Q|^3), so
 *  - the offset P = B + d N has P' = s Q - d sg X Q/|Q|^3;
 *  - the evolute E = B + N/k = B + s |Q|^2 perp(Q)/X has
 *    E' = (|Q|^2 + 3 s (Q . Q')) perp(Q)/X,
 * all finite at te: the normal there is the limit of those beside it (SVG
 * 2: the direction to the next distinct control point), the evolute meets
 * the curve.  Where Q vanishes too (B''(te) = 0) the arc is straight near
 * te: N = perp(Q')/|Q'|, k = 0.
 */
#include "core.h"

#include <float.h>
#include <immintrin.h>
#include <math.h>
#include <string.h>

/* B, B', B'', B''' (x in [0], y in [1]) of the base curve at t. */
static void base_eval(const aa_offset_curve *oc, long double t, long double B[2],
                      long double B1[2], long double B2[2], long double B3[2])
{
    const double *b = oc->b;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        long double ct = cosl(t), st = sinl(t);
        long double px = b[2] * ct + b[4] * st, py = b[3] * ct + b[5] * st; /* B - c */
        B[0] = b[0] + px, B[1] = b[1] + py;
        B1[0] = -b[2] * st + b[4] * ct, B1[1] = -b[3] * st + b[5] * ct;
        B2[0] = -px, B2[1] = -py;
        B3[0] = -B1[0], B3[1] = -B1[1];
        return;
    }
    B[0] = b[0] + t * (b[1] + t * (b[2] + t * (long double)b[3]));
    B[1] = b[4] + t * (b[5] + t * (b[6] + t * (long double)b[7]));
    B1[0] = b[1] + t * (2 * b[2] + 3 * t * (long double)b[3]);
    B1[1] = b[5] + t * (2 * b[6] + 3 * t * (long double)b[7]);
    B2[0] = 2 * b[2] + 6 * t * (long double)b[3];
    B2[1] = 2 * b[6] + 6 * t * (long double)b[7];
    B3[0] = 6 * (long double)b[3], B3[1] = 6 * (long double)b[7];
}

/* base_eval in double: the solver's first steps. */
static void base_eval_d(const aa_offset_curve *oc, double t, double B[2], double B1[2],
                        double B2[2], double B3[2])
{
    const double *b = oc->b;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        double ct = cos(t), st = sin(t);
        double px = b[2] * ct + b[4] * st, py = b[3] * ct + b[5] * st;
        B[0] = b[0] + px, B[1] = b[1] + py;
        B1[0] = -b[2] * st + b[4] * ct, B1[1] = -b[3] * st + b[5] * ct;
        B2[0] = -px, B2[1] = -py;
        B3[0] = -B1[0], B3[1] = -B1[1];
        return;
    }
    B[0] = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
    B[1] = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
    B1[0] = b[1] + t * (2 * b[2] + 3 * t * b[3]), B1[1] = b[5] + t * (2 * b[6] + 3 * t * b[7]);
    B2[0] = 2 * b[2] + 6 * t * b[3], B2[1] = 2 * b[6] + 6 * t * b[7];
    B3[0] = 6 * b[3], B3[1] = 6 * b[7];
}

/* aa__offset_stop, inline for the evaluations here: every evaluation asks
 * it (a tenth of area's time on stroked cubics as a call). */
static inline int offset_stop(const aa_offset_curve *oc, double t, double *te, double q[4])
{
    if (oc->base != AA_OFFSET_CUBIC)
        return 0;
    const double *b = oc->b;
    double scale = fabs(b[1]) + fabs(b[2]) + fabs(b[3]) + fabs(b[5]) + fabs(b[6]) + fabs(b[7]);
    if (t < 0.5) {
        double tol = 1e-12 * scale;
        if (!(b[1] * b[1] + b[5] * b[5] <= tol * tol))
            return 0;
        *te = 0;
        q[0] = 2 * b[2], q[2] = 2 * b[6];
    } else {
        double ex = b[1] + (2 * b[2] + 3 * b[3]), ey = b[5] + (2 * b[6] + 3 * b[7]);
        double tol = 1e-12 * scale;
        if (!(ex * ex + ey * ey <= tol * tol))
            return 0;
        *te = 1;
        q[0] = 2 * b[2] + 3 * b[3], q[2] = 2 * b[6] + 3 * b[7];
    }
    q[1] = 3 * b[3], q[3] = 3 * b[7];
    return 1;
}

int aa__offset_stop(const aa_offset_curve *oc, double t, double *te, double q[4])
{
    return offset_stop(oc, t, te, q);
}

/* offset_stop's answer at either end at once (bit 0: at t = 0, for t <
 * 0.5; bit 1: at t = 1), its tests in the same arithmetic: for a solver
 * that evaluates the curve several times (the magnitudes' sum once). */
#define STOP_ASK 3 /* both bits: offset_stop asked at each evaluation */
static inline int stop_ends(const aa_offset_curve *oc)
{
    if (oc->base != AA_OFFSET_CUBIC)
        return 0;
    const double *b = oc->b;
    double scale = fabs(b[1]) + fabs(b[2]) + fabs(b[3]) + fabs(b[5]) + fabs(b[6]) + fabs(b[7]);
    double tol = 1e-12 * scale;
    double ex = b[1] + (2 * b[2] + 3 * b[3]), ey = b[5] + (2 * b[6] + 3 * b[7]);
    return (b[1] * b[1] + b[5] * b[5] <= tol * tol) | (ex * ex + ey * ey <= tol * tol) << 1;
}

/* The point and derivative (unmapped) of a cubic's offset or evolute in
 * the factored form about te (see the header). */
static void stop_eval(const aa_offset_curve *oc, long double t, double te, const double *q,
                      long double *px, long double *py, long double *qx, long double *qy)
{
    const double *b = oc->b;
    long double bx = b[0] + t * (b[1] + t * (b[2] + t * (long double)b[3]));
    long double by = b[4] + t * (b[5] + t * (b[6] + t * (long double)b[7]));
    long double s = t - te, sg = te == 0 ? 1 : -1;
    long double Qx = q[0] + q[1] * t, Qy = q[2] + q[3] * t, q2 = Qx * Qx + Qy * Qy;
    long double X = Qx * (long double)q[3] - Qy * (long double)q[1];
    if (q2 == 0 || X == 0) {
        /* straight near te: N along perp(Q) (or perp(Q') where Q = 0), k = 0 */
        long double nx = q2 == 0 ? q[1] : sg * Qx, ny = q2 == 0 ? q[3] : sg * Qy;
        long double l = sqrtl(nx * nx + ny * ny);
        *px = bx - (oc->evolute ? 0 : oc->d) * ny / l;
        *py = by + (oc->evolute ? 0 : oc->d) * nx / l;
        *qx = s * Qx, *qy = s * Qy;
        return;
    }
    long double lq = sqrtl(q2);
    if (!oc->evolute) {
        long double f = oc->d * sg * X / (q2 * lq);
        *px = bx - oc->d * sg * Qy / lq;
        *py = by + oc->d * sg * Qx / lq;
        *qx = (s - f) * Qx, *qy = (s - f) * Qy;
    } else {
        long double r = s * q2 / X, g = (q2 + 3 * s * (Qx * q[1] + Qy * q[3])) / X;
        *px = bx - r * Qy, *py = by + r * Qx;
        *qx = -g * Qy, *qy = g * Qx;
    }
}

/* offset_eval's common case, a cubic's offset away from a stop: the same
 * operations in the same order as offset_eval_any's, without B''' (unused)
 * and without B'' where the derivative is not asked (the parts' ends);
 * inline in the roots' solvers. */
static __attribute__((always_inline)) inline void
cubic_offset_eval(const aa_offset_curve *oc, long double t, long double *x, long double *y,
                  long double *dx, long double *dy)
{
    const double *b = oc->b, *m = oc->m;
    long double Bx = b[0] + t * (b[1] + t * (b[2] + t * (long double)b[3]));
    long double By = b[4] + t * (b[5] + t * (b[6] + t * (long double)b[7]));
    long double ux = b[1] + t * (2 * b[2] + 3 * t * (long double)b[3]);
    long double uy = b[5] + t * (2 * b[6] + 3 * t * (long double)b[7]);
    long double L = sqrtl(ux * ux + uy * uy);
    long double px = Bx - oc->d * uy / L, py = By + oc->d * ux / L;
    *x = m[0] * px + m[2] * py + m[4];
    *y = m[1] * px + m[3] * py + m[5];
    if (!dx && !dy)
        return;
    long double vx = 2 * b[2] + 6 * t * (long double)b[3];
    long double vy = 2 * b[6] + 6 * t * (long double)b[7];
    long double c = ux * vy - uy * vx, k = c / (L * L * L), f = 1 - oc->d * k;
    long double qx = ux * f, qy = uy * f;
    if (dx)
        *dx = m[0] * qx + m[2] * qy;
    if (dy)
        *dy = m[1] * qx + m[3] * qy;
}

/* aa__offset_eval given stop_ends' bits (stops): an evaluation asks
 * offset_stop only where the bit of its half of [0, 1] is set (the same
 * test in the same arithmetic, so the same answer), and the curvature
 * only where the derivative is wanted (the roots' long double phase; not
 * the parts' ends, which take the point alone). */
static __attribute__((noinline)) void offset_eval_any(const aa_offset_curve *oc, int stops,
                                                      long double t, long double *x,
                                                      long double *y, long double *dx,
                                                      long double *dy)
{
    const double *m = oc->m;
    long double px, py, qx = 0, qy = 0; /* the point and its derivative, unmapped */
    double te, q[4];
    if ((stops & ((double)t < 0.5 ? 1 : 2)) && offset_stop(oc, (double)t, &te, q)) {
        stop_eval(oc, t, te, q, &px, &py, &qx, &qy);
    } else {
        long double B[2], U[2], V[2], W[2];
        base_eval(oc, t, B, U, V, W);
        long double ux = U[0], uy = U[1], vx = V[0], vy = V[1];
        long double L = sqrtl(ux * ux + uy * uy);
        if (!oc->evolute) {
            px = B[0] - oc->d * uy / L;
            py = B[1] + oc->d * ux / L;
            if (dx || dy) {
                long double c = ux * vy - uy * vx, k = c / (L * L * L), f = 1 - oc->d * k;
                qx = ux * f;
                qy = uy * f;
            }
        } else {
            long double c = ux * vy - uy * vx;
            long double cp = ux * W[1] - uy * W[0], dot = ux * vx + uy * vy, L2 = L * L;
            long double r = L2 * L / c; /* 1/k */
            long double rp = L * (3 * dot * c - L2 * cp) / (c * c);
            px = B[0] - r * uy / L;
            py = B[1] + r * ux / L;
            qx = -rp * uy / L;
            qy = rp * ux / L;
        }
    }
    *x = m[0] * px + m[2] * py + m[4];
    *y = m[1] * px + m[3] * py + m[5];
    if (dx)
        *dx = m[0] * qx + m[2] * qy;
    if (dy)
        *dy = m[1] * qx + m[3] * qy;
}

/* offset_eval: a cubic's offset away from a stop (a stop's bit set for
 * t's half of [0, 1] is offset_stop's answer there) by cubic_offset_eval,
 * the rest by offset_eval_any; chosen where it is called. */
static __attribute__((always_inline)) inline void offset_eval(const aa_offset_curve *oc,
                                                             int stops, long double t,
                                                             long double *x, long double *y,
                                                             long double *dx, long double *dy)
{
    if (oc->base == AA_OFFSET_CUBIC && !oc->evolute && !(stops & ((double)t < 0.5 ? 1 : 2)))
        cubic_offset_eval(oc, t, x, y, dx, dy);
    else
        offset_eval_any(oc, stops, t, x, y, dx, dy);
}

void aa__offset_eval(const aa_offset_curve *oc, long double t, long double *x, long double *y,
                     long double *dx, long double *dy)
{
    offset_eval(oc, STOP_ASK, t, x, y, dx, dy);
}

int aa__offset_stops(const aa_offset_curve *oc)
{
    return stop_ends(oc);
}

/* The terms' sizes solve_double takes for its rounding test: a cubic's x
 * and y coefficients, an ellipse's centre and semi-diameters (x in b[0],
 * b[2], b[4], y in the others), each the sum of their magnitudes. */
static inline void term_sizes(const aa_offset_curve *oc, double *sx, double *sy)
{
    const double *c = oc->b;
    int ell = oc->base == AA_OFFSET_ELLIPSE;
    *sx = ell ? fabs(c[0]) + fabs(c[2]) + fabs(c[4])
              : fabs(c[0]) + fabs(c[1]) + fabs(c[2]) + fabs(c[3]);
    *sy = ell ? fabs(c[1]) + fabs(c[3]) + fabs(c[5])
              : fabs(c[4]) + fabs(c[5]) + fabs(c[6]) + fabs(c[7]);
}

/* The root solver's parts (fix_init, eval_parts, eval_d, solve_double,
 * offset_root) are forced inline: a root takes about 650 instructions, and
 * as calls their arguments, out-parameters through memory and long double
 * values passed twice cost about 120 of them (algorithms/README.md, the
 * offset pieces' roots).  Inlined, the operations and their order are the
 * same, so are the roots, bit for bit. */
static __attribute__((always_inline)) inline void fix_init(const aa_offset_curve *oc,
                                                          aa__offset_fix *fx)
{
    fx->stops = stop_ends(oc);
    term_sizes(oc, &fx->sx, &fx->sy);
    fx->dd = 0;
}

void aa__offset_fix_init(const aa_offset_curve *oc, aa__offset_fix *fx)
{
    fix_init(oc, fx);
}

void aa__offset_eval_s(const aa_offset_curve *oc, int stops, long double t, long double *x,
                       long double *y, long double *dx, long double *dy)
{
    offset_eval(oc, stops, t, x, y, dx, dy);
}

/* The double-double form of a cubic's offset without stops
 * (aa__offset_fix_dd), for `area`'s roots and points, in double alone:
 * coordinate c of the point is the mapped base cubic r.B(t) + m[4 + c]
 * (r = (m[c], m[2 + c]); up to the scene's size, 1e3 px and more, where a
 * double's last bit is 1.1e-13 px) plus the normal term d w / L (w = r1
 * B'x - r0 B'y; at most the half width).  The base cubic's coefficients
 * r.b_k (and m[4 + c]) are kept as unevaluated sums hi + lo (exact
 * products and sums: TwoProduct, TwoSum; Dekker 1971, Ogita, Rump and
 * Oishi 2005), and Horner's scheme on them at a double t gives r.B(t) +
 * m[4 + c] as hi + lo to about 2^-104 of its terms (each step's product
 * sh t exact, sl t and the sums' errors carried in lo).  The normal term
 * the same way (dd_normal_pt: B' from its coefficients hi + lo, L^2 and w
 * from exact products, L and w / L each with a Newton correction whose
 * residual is exact): in double alone it was off by up to 8 units of its
 * last place, 1e-15 px at a half width of 1.25 px on
 * tests/bench_bezstroke.c's scene (B' rounded where its terms cancel,
 * then the root, the quotient and the products), which put the sum of
 * the image's errors 4% higher at 1024 px and 16% at 256 px (`--check`)
 * and roots up to 8e-14 px off at a half width of 154 px.  The
 * coordinate less a target is then ((hi - target) + normal) + (lo +
 * normal's lo): near the root hi - target is about the normal term
 * (exact where the two are within a factor of 2, Sterbenz), so the value
 * is known to about its own last place, and Newton's method in double
 * finds the root as the long double phase did (root_dd).  The point in
 * long double from the parts ((hi + normal) + (lo + normal's lo): its
 * last bit 5.6e-17 px at 1000 px), for the callers that subtract the
 * cell and the band.  An evolute's normal term, w L^2 / c, is left to
 * the long double form (5% of the pieces there).  TwoProduct by fma where
 * the processor has it (dd 2, a function built for it), else by Dekker's
 * split (dd 1): both exact, so the same values bit for bit (the file is
 * built without contraction, -std=c11, so no other product and sum is
 * fused). */
static inline double dd_two_sum(double a, double b, double *e)
{
    double s = a + b, bb = s - a;
    *e = (a - (s - bb)) + (b - bb);
    return s;
}

static __attribute__((always_inline)) inline double dd_two_prod(double a, double b, double *e,
                                                                 int fma)
{
    double p = a * b;
    if (fma) {
        *e = __builtin_fma(a, b, -p);
        return p;
    }
    /* Dekker's split into halves of 26 bits (Veltkamp's constant 2^27 + 1) */
    double ca = 134217729.0 * a, cb = 134217729.0 * b;
    double ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
    *e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return p;
}

/* The two coordinates at once, x in lane 0 and y in lane 1 (SSE2's
 * packed doubles, GCC's vector extension): each lane's operations those
 * of the scalar forms above in the same order, so the same values bit
 * for bit, in half the instructions.  Loads and stores by memcpy (fx's
 * arrays are 8-byte aligned). */
typedef double dd_v2 __attribute__((vector_size(16)));
typedef long long dd_i2 __attribute__((vector_size(16))); /* a shuffle's lanes */

static inline dd_v2 dd_ld(const double *p)
{
    dd_v2 v;
    memcpy(&v, p, sizeof v);
    return v;
}

static inline dd_v2 dd_two_sum_v(dd_v2 a, dd_v2 b, dd_v2 *e)
{
    dd_v2 s = a + b, bb = s - a;
    *e = (a - (s - bb)) + (b - bb);
    return s;
}

static __attribute__((always_inline)) inline dd_v2 dd_two_prod_v(dd_v2 a, dd_v2 b, dd_v2 *e,
                                                                  int fma)
{
    dd_v2 p = a * b;
    if (fma) {
        /* lane by lane: the compiler joins the two (vfmsub132pd) */
        *e = (dd_v2){__builtin_fma(a[0], b[0], -p[0]), __builtin_fma(a[1], b[1], -p[1])};
        return p;
    }
    dd_v2 ca = 134217729.0 * a, cb = 134217729.0 * b;
    dd_v2 ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
    *e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return p;
}

/* r.B(t) + m[4 + c] as hi + lo for both coordinates (*hi, *lo: lane c
 * coordinate c's): Horner's scheme on fx's coefficients */
static __attribute__((always_inline)) inline void dd_base(const aa__offset_fix *fx, double t,
                                                         int fma, dd_v2 *hi, dd_v2 *lo)
{
    dd_v2 sh = dd_ld(fx->dc[3][0]), sl = dd_ld(fx->dc[3][1]);
    /* unrolled: 14 instructions fewer a root (the loop's counter and
     * tests, the coefficients' addresses) */
#pragma GCC unroll 3
    for (int k = 2; k >= 0; k--) {
        /* (sh, sl) left unnormalised: sl may exceed half an ulp of sh
         * (where p and c[k] cancel), and sl t is then still within 2^-53
         * of a term 2^-53 of sh's size */
        dd_v2 e, p = dd_two_prod_v(sh, (dd_v2){t, t}, &e, fma), e2;
        sh = dd_two_sum_v(p, dd_ld(fx->dc[k][0]), &e2);
        sl = e2 + (e + (sl * t + dd_ld(fx->dc[k][1])));
    }
    *hi = sh, *lo = sl;
}

/* The offset's normal terms d w / L for the point, as hi + lo (x in
 * n[0], y in n[1]), and its first and second derivatives (dp[0], dp[1],
 * x and y the lanes, in double; NULL: not wanted): in double, d w / L
 * is off by up to 8 units of its last place (1e-15 px at a half width of 1.25 px
 * on tests/bench_bezstroke.c's scene: B' rounded where its terms cancel,
 * then the square root, the division and the products), so here each
 * step is exact or carries its error: B' by Horner's scheme on fx->du,
 * L^2 = B'.B' and w = r1 B'x - r0 B'y from exact products and sums, L =
 * sqrt(L^2) and w / L each with one Newton correction (their residuals
 * exact by TwoProduct), 1 / L the one division. */
static __attribute__((always_inline)) inline void dd_normal_pt(const aa_offset_curve *oc,
                                                              const aa__offset_fix *fx,
                                                              double t, int fma, dd_v2 *nh,
                                                              dd_v2 *nl, dd_v2 dp[2])
{
    /* B'x, B'y (the lanes) as hi (uh) + lo (ul) */
    dd_v2 tv = {t, t}, e, e2, ul;
    dd_v2 p = dd_two_prod_v(dd_ld(fx->du[2][0]), tv, &e, fma);
    dd_v2 sh = dd_two_sum_v(p, dd_ld(fx->du[1][0]), &e2), sl = e2 + (e + dd_ld(fx->du[2][1]) * t);
    p = dd_two_prod_v(sh, tv, &e, fma);
    dd_v2 s2 = dd_two_sum_v(p, dd_ld(fx->du[0][0]), &e2);
    dd_v2 uh = dd_two_sum_v(s2, e2 + (e + sl * t), &ul);
    /* L^2 and L */
    double e1, e3, e4, p1 = dd_two_prod(uh[0], uh[0], &e1, fma);
    double p2 = dd_two_prod(uh[1], uh[1], &e4, fma), s = dd_two_sum(p1, p2, &e3);
    double ql = e3 + e1 + e4 + 2 * (uh[0] * ul[0] + uh[1] * ul[1]);
    double qh = dd_two_sum(s, ql, &ql);
    double lh = sqrt(qh), il = 1 / lh, el, pl = dd_two_prod(lh, lh, &el, fma);
    double ll = (((qh - pl) - el) + ql) * (0.5 * il);
    /* w = r1 B'x - r0 B'y for both rows of the map (the lanes: r0 = m[c],
     * r1 = m[2 + c]) */
    const double *m = oc->m;
    dd_v2 r0 = {m[0], m[1]}, r1 = {m[2], m[3]}, ea, eb, es, wl2;
    dd_v2 a = dd_two_prod_v(r1, (dd_v2){uh[0], uh[0]}, &ea, fma);
    dd_v2 b = dd_two_prod_v(-r0, (dd_v2){uh[1], uh[1]}, &eb, fma);
    dd_v2 ws = dd_two_sum_v(a, b, &es), wl = es + ea + eb + (r1 * ul[0] - r0 * ul[1]);
    dd_v2 wh = dd_two_sum_v(ws, wl, &wl2);
    /* w / L: the quotient by 1 / L (within an ulp or two), then the
     * remainder's (w - fh L, exact by TwoProduct and Sterbenz) */
    dd_v2 fh = wh * il, ef, pf = dd_two_prod_v(fh, (dd_v2){lh, lh}, &ef, fma);
    dd_v2 fl = (((wh - pf) - ef) + (wl2 - fh * ll)) * il, eh;
    *nh = dd_two_prod_v((dd_v2){oc->d, oc->d}, fh, &eh, fma);
    *nl = eh + oc->d * fl;
    if (dp) {
        /* the derivative and the second, in double: P' = B' g, g = 1 - d
         * k, k = c / L^3, and P'' = B'' g + B' g', g' = -d k', k' = c' /
         * L^3 - 3 c (B'.B'') / L^5, c' = B' x B''' */
        const double *bc = oc->b;
        /* B'' (v) and the products by x and y (lanes) side by side, each
         * lane's operations the scalar ones in their order: 2 b2 is
         * fx->du[1]'s (exact); c and c' / 6 from one subtraction */
        dd_v2 b3 = {bc[3], bc[7]}, v = dd_ld(fx->du[1][0]) + (6 * t) * b3;
        dd_v2 ux = {uh[0], uh[0]}, uy = {uh[1], uh[1]};
        dd_v2 cv = ux * (dd_v2){v[1], bc[7]} - uy * (dd_v2){v[0], bc[3]}, uv = uh * v;
        double cc = cv[0], cp = 6 * cv[1], dot = uv[0] + uv[1];
        double il3 = il * il * il, g = 1 - oc->d * cc * il3;
        dd_v2 q = uh * g;
        double gp = -oc->d * il3 * (cp - 3 * cc * dot * (il * il));
        dd_v2 rv = v * g + uh * gp;
        dp[0] = r0 * q[0] + r1 * q[1], dp[1] = r0 * rv[0] + r1 * rv[1];
    }
}

/* The point at t, both coordinates (the lanes) as the base's hi + lo plus
 * the normal term's (p[0..3]: base hi, normal hi, base lo, normal lo),
 * and its first and second derivatives dp in double (dd_normal_pt's;
 * NULL: not wanted) */
static __attribute__((always_inline)) inline void dd_point_parts(const aa_offset_curve *oc,
                                                                const aa__offset_fix *fx,
                                                                double t, int fma, dd_v2 p[4],
                                                                dd_v2 dp[2])
{
    dd_normal_pt(oc, fx, t, fma, &p[1], &p[3], dp);
    dd_base(fx, t, fma, &p[0], &p[2]);
}

/* v's lanes swapped (clang, which `make fuzz` builds with, names GCC's
 * __builtin_shuffle __builtin_shufflevector) */
static inline dd_v2 dd_swap(dd_v2 v)
{
#ifdef __clang__
    return __builtin_shufflevector(v, v, 1, 0);
#else
    return __builtin_shuffle(v, (dd_i2){1, 0});
#endif
}

/* Lane c of v (c 0 or 1, known only at run time): by a test, so that v
 * stays in its register, not stored to the stack to be indexed */
static inline double dd_lane(dd_v2 v, int c)
{
    return c ? v[1] : v[0];
}

/* The point's coordinate from dd_point_parts' parts, moved by h along
 * its Taylor series to the second order (s, s2: its first and second
 * derivatives; h the step from t to the root, at most about 1e-7: the
 * third order's term then at most 1.7e-22 of the third derivative), in
 * long double (its last bit 5.6e-17 at 1000 px) for callers that
 * subtract the cell and the band from it */
static inline long double dd_coord(const dd_v2 *p, int c, double s, double s2, double h)
{
    return ((long double)dd_lane(p[0], c) + dd_lane(p[1], c)) +
           (dd_lane(p[2], c) + (dd_lane(p[3], c) + h * (s + 0.5 * s2 * h)));
}

/* Coordinate coord of oc at t as the base curve's mapped coordinate
 * (*base0) plus the normal term (*nrm: d w / L or w L^2 / c, below; in the
 * factored form next to a cusp the point's coordinate and 0), its
 * derivative (*df) and the size of its normal term (*dn), in double: the
 * solver's first steps (eval_d: the value less a target).  Only the wanted row of the map is
 * applied, and each form takes one division: with r = (m[coord],
 * m[2 + coord]) and w = r1 B'x - r0 B'y (the row applied to L N),
 *  - the offset: r.B + m[4 + coord] + d w / L, slope (r.B') (1 - d c / L^3);
 *  - the evolute (N / k = N L^3 / c = L N (L^2 / c), no square root):
 *    r.B + m[4 + coord] + w L^2 / c, slope w (1/k)' / L =
 *    w (3 (B'.B'') c - L^2 c') / c^2. */
static __attribute__((always_inline)) inline void eval_parts(const aa_offset_curve *oc, int coord,
                                                            double t, int stops, double *base0,
                                                            double *nrm, double *df, double *dn)
{
    double te, q[4];
    if (oc->base == AA_OFFSET_CUBIC && (stops & (t < 0.5 ? 1 : 2)) &&
        offset_stop(oc, t, &te, q)) {
        /* next to a cubic's end where B' = 0 (the factored form, in long
         * double): the point, its derivative and the base point, the row
         * applied to each */
        long double X, Y, DX, DY;
        aa__offset_eval(oc, t, &X, &Y, &DX, &DY);
        double B[2], U[2], V[2], W[2];
        base_eval_d(oc, t, B, U, V, W);
        double at = (double)(coord ? Y : X);
        double bm = oc->m[coord] * B[0] + oc->m[2 + coord] * B[1] + oc->m[4 + coord];
        *base0 = at, *nrm = 0.0;
        *df = (double)(coord ? DY : DX);
        *dn = fabs(at - bm);
        return;
    }
    const double *b = oc->b;
    double r0 = oc->m[coord], r1 = oc->m[2 + coord], bx, by, ux, uy, vx, vy, cp = 0.0;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        /* B, B', B'' from cos t and sin t in double (each within an ulp),
         * B''' = -B': c' = B' x B''' = 0 */
        double B[2], U[2], V[2], W[2];
        base_eval_d(oc, t, B, U, V, W);
        bx = B[0], by = B[1], ux = U[0], uy = U[1], vx = V[0], vy = V[1];
        cp = ux * W[1] - uy * W[0];
        *base0 = r0 * bx + r1 * by + oc->m[4 + coord];
    } else {
        /* the row's base point: where the map keeps the axes (r0 or r1
         * 0, as a scene's placement does) the other coordinate of B is
         * not evaluated, its product 0 dropped from the sum (the same
         * value: 0 + p = p, up to the sign of a zero) */
        if (r0 == 0) {
            by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
            *base0 = r1 * by + oc->m[4 + coord];
        } else if (r1 == 0) {
            bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
            *base0 = r0 * bx + oc->m[4 + coord];
        } else {
            bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
            by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
            *base0 = r0 * bx + r1 * by + oc->m[4 + coord];
        }
        ux = b[1] + t * (2 * b[2] + 3 * t * b[3]), uy = b[5] + t * (2 * b[6] + 3 * t * b[7]);
        vx = 2 * b[2] + 6 * t * b[3], vy = 2 * b[6] + 6 * t * b[7];
        if (oc->evolute) /* c' only there */
            cp = ux * 6 * b[7] - uy * 6 * b[3];
    }
    double c = ux * vy - uy * vx, L2 = ux * ux + uy * uy, w = r1 * ux - r0 * uy;
    if (!oc->evolute) {
        double il = 1 / sqrt(L2);
        *nrm = oc->d * w * il;
        *df = (r0 * ux + r1 * uy) * (1 - oc->d * c * (il * il * il));
    } else {
        double ic = 1 / c, dot = ux * vx + uy * vy;
        *nrm = w * L2 * ic;
        *df = w * (3 * dot * c - L2 * cp) * (ic * ic);
    }
    *dn = fabs(*nrm);
}

/* The value less tgt from eval_parts' terms: (base - tgt) + normal term,
 * in this order (the factored form's normal term is 0 and its base the
 * point's coordinate). */
static inline double parts_f(double base0, double nrm, double tgt)
{
    return (base0 - tgt) + nrm;
}

static __attribute__((always_inline)) inline void eval_d(const aa_offset_curve *oc, int coord,
                                                         double t, int stops, double tgt,
                                                         double *f, double *df, double *dn)
{
    double base0, nrm;
    eval_parts(oc, coord, t, stops, &base0, &nrm, df, dn);
    *f = parts_f(base0, nrm, tgt);
}

/* eval_d on the double-double form's curves (aa__offset_fix_dd: a cubic's
 * offset without stops): eval_parts' operations there in the same order,
 * the same values, without its tests of the base curve, the evolute and
 * the stops at each evaluation. */
static __attribute__((always_inline)) inline void eval_dd(const aa_offset_curve *oc, int coord,
                                                          double t, double tgt, double *f,
                                                          double *df, double *dn)
{
    const double *b = oc->b;
    double r0 = oc->m[coord], r1 = oc->m[2 + coord], base0;
    if (r0 == 0) {
        double by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
        base0 = r1 * by + oc->m[4 + coord];
    } else if (r1 == 0) {
        double bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
        base0 = r0 * bx + oc->m[4 + coord];
    } else {
        double bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
        double by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
        base0 = r0 * bx + r1 * by + oc->m[4 + coord];
    }
    double ux = b[1] + t * (2 * b[2] + 3 * t * b[3]), uy = b[5] + t * (2 * b[6] + 3 * t * b[7]);
    double vx = 2 * b[2] + 6 * t * b[3], vy = 2 * b[6] + 6 * t * b[7];
    double c = ux * vy - uy * vx, L2 = ux * ux + uy * uy, w = r1 * ux - r0 * uy;
    double il = 1 / sqrt(L2), nrm = oc->d * w * il;
    *df = (r0 * ux + r1 * uy) * (1 - oc->d * c * (il * il * il));
    *dn = fabs(nrm);
    *f = parts_f(base0, nrm, tgt);
}

void aa__offset_end(const aa_offset_curve *oc, int coord, double t, double e[4])
{
    eval_parts(oc, coord, t, STOP_ASK, &e[0], &e[1], &e[2], &e[3]);
}

/* aa__offset_end's e[0] + e[1] and e[2] on the double-double form's curves
 * (aa__offset_fix_dd: a cubic's offset without stops, where offset_stop
 * never holds and eval_parts takes the cubic's plain path): eval_dd's
 * value at the target 0, (e[0] - 0) + e[1], the same sum bit for bit (x -
 * 0 is x, a zero's sign kept), and its slope, without the stops' and the
 * base's tests at each evaluation. */
void aa__offset_end_dd(const aa_offset_curve *oc, int coord, double t, double *at,
                       double *slope)
{
    double dn;
    eval_dd(oc, coord, t, 0.0, at, slope, &dn);
}

void aa_offset_point(const aa_offset_curve *oc, double t, double *x, double *y, double *dx,
                     double *dy)
{
    long double X, Y, DX, DY;
    offset_eval(oc, STOP_ASK, t, &X, &Y, dx ? &DX : NULL, dy ? &DY : NULL);
    *x = (double)X, *y = (double)Y;
    if (dx)
        *dx = (double)DX;
    if (dy)
        *dy = (double)DY;
}

/* Roots of a + b t + c t^2 in (lo, hi), ascending, cancellation-free. */
static int quad_roots(double a, double b, double c, double lo, double hi, double *t)
{
    double r[2];
    int n = 0, m = 0;
    if (c == 0) {
        if (b != 0)
            r[n++] = -a / b;
    } else {
        double d = b * b - 4 * a * c;
        if (d < 0)
            return 0;
        double q = -0.5 * (b + copysign(sqrt(d), b));
        if (q != 0)
            r[n++] = a / q;
        r[n++] = q / c;
    }
    if (n == 2 && r[0] > r[1]) {
        double s = r[0];
        r[0] = r[1], r[1] = s;
    }
    for (int k = 0; k < n; k++)
        if (r[k] > lo && r[k] < hi && (m == 0 || r[k] > t[m - 1]))
            t[m++] = r[k];
    return m;
}

/* Zeros of a cos t + b sin t in (lo, hi), ascending (at most 2: the range
 * is at most 2 pi long): a cos t + b sin t = r cos(t - phi), phi =
 * atan2(b, a), zero at phi + pi/2 + k pi. */
static int trig_roots(double a, double b, double lo, double hi, double *t)
{
    if (a == 0 && b == 0)
        return 0;
    double z = atan2(b, a) + 0.5 * M_PI;
    double k = ceil((lo - z) / M_PI);
    int m = 0;
    for (int j = -1; j < 3 && m < 2; j++) {
        double r = z + (k + j) * M_PI;
        if (r > lo && r < hi && (m == 0 || r > t[m - 1]))
            t[m++] = r;
    }
    return m;
}

int aa__offset_turns(const aa_offset_curve *oc, int coord, double lo, double hi, double t[2])
{
    const double *b = oc->b;
    /* the row of m for this coordinate: m(v)_coord = ra vx + rb vy */
    double ra = oc->m[coord], rb = oc->m[2 + coord];
    if (oc->base == AA_OFFSET_ELLIPSE) {
        /* B' = v cos t - u sin t, N L = (-B'y, B'x) */
        if (!oc->evolute) /* ra B'x + rb B'y */
            return trig_roots(ra * b[4] + rb * b[5], -(ra * b[2] + rb * b[3]), lo, hi, t);
        /* rb B'x - ra B'y */
        return trig_roots(rb * b[4] - ra * b[5], -(rb * b[2] - ra * b[3]), lo, hi, t);
    }
    /* B' = (b1 + 2 b2 t + 3 b3 t^2, b5 + 2 b6 t + 3 b7 t^2) */
    if (!oc->evolute) /* ra B'x + rb B'y */
        return quad_roots(ra * b[1] + rb * b[5], 2 * (ra * b[2] + rb * b[6]),
                          3 * (ra * b[3] + rb * b[7]), lo, hi, t);
    /* m(N) L = ra (-B'y) + rb B'x */
    return quad_roots(rb * b[1] - ra * b[5], 2 * (rb * b[2] - ra * b[6]),
                      3 * (rb * b[3] - ra * b[7]), lo, hi, t);
}

long double aa__offset_solve(const aa_offset_curve *oc, int coord, long double ta, long double tb,
                             long double fa, long double target)
{
    return aa__offset_solve_from(oc, coord, ta, tb, fa, target, NAN);
}

/* The double phase of the solver: Newton's method from the guess or where
 * the chord meets the target, kept inside the bracket, bisection where a
 * step leaves it or shrinks it by less than half, until a step is within
 * tol (SOLVE_D_STEP or ROOT_D_STEP; *last: that step, or the Newton step
 * that reached the point returned, NaN if a bisection's or a start's;
 * it leaves an error of the order of its square: quadratic
 * convergence) or the coordinate is within double's rounding of the target
 * (twice the unit roundoff times the size of its terms: the polynomials'
 * coefficients, the map's, the normal term and the target); the bracket
 * left in *pa, *pb.  A last step that leaves the bracket by a rounding
 * (a root at an end) ends on that end.  Without the second test a root
 * whose rounding exceeds the step tolerance (|y'| small: 1e-15 / 8e-4 =
 * 1e-12 next to a y turn) was bisected down to two adjacent doubles;
 * without the third, a step of 0 from an end, or past an end at 0, started
 * bisection from the middle of the bracket (towards 0: a hundred steps):
 * both twice the evaluations in the reference's inner loop.  For the same
 * reason a root at the far end b (within rounding) is taken there: where b
 * was evaluated first, at once, and where it was not (a guess given), when
 * a step goes past it.  dd (a constant where it is called): the curve is
 * one of the double-double form's, evaluated by eval_dd. */
#define SOLVE_D_STEP 1e-12
/* aa__offset_root's: it stops the double phase at a larger step, and its
 * long double phase judges the error left by the two last steps (below). */
#define ROOT_D_STEP 1e-6
/* The long double phase's evaluations at most: enough for a bisection of
 * any bracket of the parameter (a few units wide) to reach two adjacent
 * long doubles, 64 halvings and more */
#define ROOT_LD_STEPS 200
/* g strictly inside the bracket [a, b] (either order; a NaN is not): a
 * caller's start the solvers take */
static inline int in_bracket(double g, double a, double b)
{
    return a < b ? (g > a && g < b) : (g < a && g > b);
}
/* One step of solve_double's loop, given the evaluation at *t (f less
 * the target, df, dn) and its state (the bracket *a, *b, the step before
 * *prev, *unseen, *last): 1 where the loop stops there (*t the result),
 * else 0 (*t the next point). */
static __attribute__((always_inline)) inline int
solve_step(double f, double df, double dn, double size, double tol, int neg, double *t,
           double *a, double *b, double *prev, int *unseen, double *last)
{
    if (fabs(f) <= 2 * DBL_EPSILON * (size + dn))
        return 1;
    if ((f < 0) == neg)
        *a = *t;
    else
        *b = *t, *unseen = 0;
    double mid = 0.5 * (*a + *b);
    if (!(mid != *a && mid != *b))
        return 1;
    double next = df != 0 && isfinite(df) ? *t - f / df : mid;
    if (fabs(next - *t) <= tol * (fabs(*t) > 1.0 ? fabs(*t) : 1.0)) { /* fmax, not a call */
        /* a root at an end comes out a rounding beyond it */
        double lo = *a < *b ? *a : *b, hi = *a < *b ? *b : *a; /* no calls */
        double cl = next > lo ? next : lo;
        cl = cl < hi ? cl : hi;
        *last = cl == next ? fabs(next - *t) : NAN;
        *t = cl;
        return 1;
    }
    int inside = in_bracket(next, *a, *b);
    int newton = 1;
    if (!inside && *unseen && (*a < *b ? next >= *b : next <= *b))
        next = *b, *unseen = 0, newton = 0;
    else if (!inside || fabs(next - *t) > 0.5 * *prev)
        next = mid, newton = 0;
    *prev = fabs(next - *t);
    *last = newton ? *prev : NAN;
    *t = next;
    return 0;
}

/* solve_double's loop from its iteration it0 (at t, the state as
 * solve_step leaves it). */
static __attribute__((always_inline)) inline double
solve_double_loop(const aa_offset_curve *oc, const aa__offset_fix *fx, int dd, int coord,
                  double a, double b, int neg, double tgt, double t, double prev, int unseen,
                  double size, double tol, int it0, double *pa, double *pb, double *last)
{
    int stops = fx->stops;
    double f, df, dn;
    for (int it = it0; it < 100; it++) {
        if (dd)
            eval_dd(oc, coord, t, tgt, &f, &df, &dn);
        else
            eval_d(oc, coord, t, stops, tgt, &f, &df, &dn);
        if (solve_step(f, df, dn, size, tol, neg, &t, &a, &b, &prev, &unseen, last))
            break;
    }
    *pa = a, *pb = b;
    return t;
}

static __attribute__((always_inline)) inline double
solve_double(const aa_offset_curve *oc, const aa__offset_fix *fx, int dd, int coord, double a,
             double b, double fa, double tgt, double guess, double tol, const double *endb,
             double *pa, double *pb, double *last)
{
    int neg = fa < 0, stops = fx->stops;
    double t = 0.5 * (a + b), prev = fabs(b - a), f, df, dn;
    /* the terms' size (term_sizes, the curve's, once) */
    double size = fabs(oc->m[coord]) * fx->sx + fabs(oc->m[2 + coord]) * fx->sy +
                  fabs(oc->m[4 + coord]) + fabs(tgt);
    /* b unseen: the caller's end, its sign taken on trust and not
     * evaluated (with a guess); a Newton step past it goes to it */
    int unseen = 0;
    *last = NAN; /* the step that reached t, where Newton's; none at a start */
    if (in_bracket(guess, a, b)) {
        t = guess; /* a caller's start: the root on a nearby line */
        unseen = 1;
    } else {
        /* the root of the quadratic through fa at a and f at b with the
         * slope df at b (h = t - b: f + df h + k h^2), exact where the
         * coordinate is quadratic, as next to a turn at either end (a
         * piece's end, where the chord's root is far off and Newton's
         * steps only halve the distance); else the chord's */
        if (endb) /* the caller's eval_parts at b (aa__offset_end) */
            f = parts_f(endb[0], endb[1], tgt), df = endb[2], dn = endb[3];
        else if (dd)
            eval_dd(oc, coord, b, tgt, &f, &df, &dn);
        else
            eval_d(oc, coord, b, stops, tgt, &f, &df, &dn);
        if (fabs(f) <= 2 * DBL_EPSILON * (size + dn)) {
            *pa = a, *pb = b; /* the root at b, within rounding */
            return b;
        }
        if ((f < 0) != neg && f != fa) {
            double e = a - b, k = (fa - f - df * e) / (e * e), h = NAN;
            double disc = df * df - 4 * k * f;
            if (isfinite(k) && disc >= 0) {
                /* the root between e and 0, cancellation-free */
                double q = -0.5 * (df + copysign(sqrt(disc), df));
                double h1 = q != 0 ? f / q : NAN, h2 = k != 0 ? q / k : NAN;
                h = (e < 0 ? h1 > e && h1 < 0 : h1 < e && h1 > 0) ? h1 : h2;
            }
            double r = h / e; /* its place in the bracket: 0 at b, 1 at a */
            if (r > 0.001 && r < 0.999)
                t = b + h;
            else if ((r = fa / (fa - f)) > 0.01 && r < 0.99)
                t = a + r * (b - a);
        }
    }
    return solve_double_loop(oc, fx, dd, coord, a, b, neg, tgt, t, prev, unseen, size, tol, 0,
                             pa, pb, last);
}

double aa__offset_solve_d(const aa_offset_curve *oc, int coord, double ta, double tb, double fa,
                          double target)
{
    double a, b, last;
    aa__offset_fix fx;
    if (fa == 0)
        return ta;
    fix_init(oc, &fx);
    return solve_double(oc, &fx, 0, coord, ta, tb, fa, target, NAN, SOLVE_D_STEP, NULL, &a, &b,
                        &last);
}

double aa__offset_solve_dg(const aa_offset_curve *oc, int coord, double ta, double tb, double fa,
                           double target, double guess)
{
    double a, b, last;
    aa__offset_fix fx;
    if (fa == 0)
        return ta;
    fix_init(oc, &fx);
    return solve_double(oc, &fx, 0, coord, ta, tb, fa, target, guess, SOLVE_D_STEP, NULL, &a,
                        &b, &last);
}

long double aa__offset_solve_from(const aa_offset_curve *oc, int coord, long double ta,
                                  long double tb, long double fa, long double target, double guess)
{
    return aa__offset_root(oc, coord, ta, tb, fa, target, guess, NULL, NULL);
}

static inline long double offset_root(const aa_offset_curve *oc, const aa__offset_fix *fx,
                                      int coord, long double ta, long double tb, long double fa,
                                      long double target, double guess, const double *endb,
                                      long double *other, double *slope, long double *xy);

long double aa__offset_root(const aa_offset_curve *oc, int coord, long double ta, long double tb,
                            long double fa, long double target, double guess, long double *other,
                            double *slope)
{
    aa__offset_fix fx;
    fix_init(oc, &fx);
    return offset_root(oc, &fx, coord, ta, tb, fa, target, guess, NULL, other, slope, NULL);
}

long double aa__offset_root_fix(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                                long double ta, long double tb, long double fa,
                                long double target, double guess, const double *endb,
                                long double *other, double *slope)
{
    return offset_root(oc, fx, coord, ta, tb, fa, target, guess, endb, other, slope, NULL);
}

long double aa__offset_solve_end(const aa_offset_curve *oc, int coord, double ta, double tb,
                                 long double fa, long double target, const double endb[4])
{
    aa__offset_fix fx;
    fix_init(oc, &fx);
    return offset_root(oc, &fx, coord, ta, tb, fa, target, NAN, endb, NULL, NULL, NULL);
}

double aa__offset_root_xy(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                          long double ta, long double tb, long double fa, long double target,
                          double guess, const double *endb, long double xy[2])
{
    return (double)offset_root(oc, fx, coord, ta, tb, fa, target, guess, endb, NULL, NULL, xy);
}

/* The root in the double-double form (fx->dd set): Newton's method in
 * double (solve_double, to a step within DD_D_STEP: from the table's
 * start, one evaluation), then on the value evaluated as hi + lo
 * (dd_point_parts), still bracketed by the caller's [ta, tb], each step
 * taken to the second order (h = h2 - c2 h2^2 for the Newton step h2 =
 * -f / f', c2 = f'' / (2 f'): the series of the inverse), which leaves
 * an error of about 2 c2^2 h2^3 (f''' / (6 f') taken as of the order of
 * c2^2): the step is the last where that is within DD_EST max(|t|, 1)
 * (1e-5 of an ulp of t in [0.5, 1), so that the root rounded to double
 * is the nearest but within about that of a midpoint) and h2 within
 * 1e-7, or where it rounds to t itself, or where the bracket is two
 * adjacent doubles.  Below |t| = 1 that bound stays 1e-21, not relative
 * to t: near t = 0 (a line within rounding of a piece's start, t about
 * 1e-15, whose ulps are 2e-31) the returned double is within about
 * 1e-21 of the exact root, not always the nearest double (on
 * tests/bench_bezstroke.c's scene at 256 px, lines inside both ends'
 * heights among them, 16,464 of 398,868 roots, every one below t = 1e-5,
 * each within half an ulp of t plus 3.5e-30 of the root), and two starts'
 * last steps may round it to different doubles there (area.c's sub_key
 * from another start, three renders at 256 px: 120 of 39,744 roots a
 * double away, those not the nearest all below t = 1e-9;
 * tests/test_area_offset.c, test_root_starts).  Where a step stayed at
 * t, offset_root's rule (a step onto the bracket's end bisects) bisected
 * from there and ended an ulp off on 5% of the roots of
 * tests/bench_bezstroke.c's scene (303 pixels beyond the reference's
 * bound against 279).  The point at the
 * root rounded to double (xy) is the last evaluation's moved along its
 * Taylor series to the second order over the step to it (dd_coord), and
 * the other coordinate (other) over the step unrounded, to where
 * coordinate coord is the target (offset_root's, which its callers pair
 * with the target).  Built twice, for Dekker's products and for fma's. */
#define DD_EST 1e-21
#define DD_D_STEP 1e-4
/* One step of root_dd's loop on the double-double value at *t
 * (dd_point_parts' p and dp there), the caller's bracket [*la, *lb]: 1
 * where the loop stops there (*t the root, *h the step from the point
 * evaluated to it, *hx the step unrounded), else 0 (*t the next point). */
static __attribute__((always_inline)) inline int dd_step(const dd_v2 p[4], const dd_v2 dp[2],
                                                         dd_v2 tv, int coord, int neg, double *t,
                                                         double *la, double *lb, double *h,
                                                         double *hx)
{
    /* both lanes (each lane's operations the scalar ones), coord's moved
     * to lane 0 by one test: the value less the target, the slope and the
     * second derivative, not three parts and two derivatives indexed by
     * coord in memory */
    dd_v2 fv = ((p[0] - tv) + p[1]) + (p[2] + p[3]), d1 = dp[0], d2 = dp[1];
    if (coord)
        fv = dd_swap(fv), d1 = dd_swap(d1), d2 = dd_swap(d2);
    double f = fv[0], df = d1[0];
    if (f == 0)
        return 1;
    if ((f < 0) == neg)
        *la = *t;
    else
        *lb = *t;
    double mid = 0.5 * (*la + *lb);
    if (!(mid != *la && mid != *lb))
        return 1;
    if (!(df != 0 && isfinite(df))) {
        *t = mid;
        return 0;
    }
    double idf = 1 / df, h2 = -f * idf, c2 = 0.5 * d2[0] * idf;
    double ch = c2 * h2;
    double step = h2 - ch * h2, next = *t + step;
    if (next == *t) { /* within half an ulp of t: t is the root rounded */
        *hx = step;
        return 1;
    }
    int inside = in_bracket(next, *la, *lb);
    double sc = fabs(*t) > 1.0 ? fabs(*t) : 1.0;
    if (inside && fabs(h2) <= 1e-7 && 2 * ch * ch * fabs(h2) <= DD_EST * sc) {
        *h = next - *t, *hx = step, *t = next;
        return 1;
    }
    *t = inside ? next : mid;
    return 0;
}

/* root_dd's outputs from the last evaluation (p, dp) and the steps from
 * it to the root rounded (h) and unrounded (hx) */
static __attribute__((always_inline)) inline void dd_out(const dd_v2 p[4], const dd_v2 dp[2],
                                                         int coord, double h, double hx,
                                                         long double xy[2], long double *other)
{
    if (xy) { /* dd_coord's sum in double for both lanes at once (the same operations) */
        dd_v2 hv = {h, h}, lo = p[2] + (p[3] + hv * (dp[0] + 0.5 * dp[1] * hv));
        xy[0] = ((long double)p[0][0] + p[1][0]) + lo[0];
        xy[1] = ((long double)p[0][1] + p[1][1]) + lo[1];
    }
    if (other) /* at the root itself, where coordinate coord is the target */
        *other = dd_coord(p, 1 - coord, dd_lane(dp[0], 1 - coord), dd_lane(dp[1], 1 - coord),
                          hx);
}

/* root_dd's loop on the double-double value from its iteration it0 at t,
 * the caller's bracket [la, lb], and its outputs */
static __attribute__((always_inline)) inline double
root_dd_loop(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double target,
             int neg, double t, double la, double lb, int it0, long double xy[2],
             long double *other, int fma)
{
    dd_v2 p[4], dp[2], tv = {target, target};
    double h = 0.0, hx = 0.0;
    for (int it = it0; it < ROOT_LD_STEPS; it++) {
        dd_point_parts(oc, fx, t, fma, p, dp);
        if (dd_step(p, dp, tv, coord, neg, &t, &la, &lb, &h, &hx)) {
            dd_out(p, dp, coord, h, hx, xy, other);
            return t;
        }
    }
    dd_point_parts(oc, fx, t, fma, p, NULL); /* t not evaluated */
    dp[0] = dp[1] = (dd_v2){0.0, 0.0};
    dd_out(p, dp, coord, 0.0, 0.0, xy, other);
    return t;
}

/* root_dd where the caller gives no start inside the bracket (the double
 * phase from the bracket's ends) or fa is 0 */
static __attribute__((always_inline)) inline double
root_dd_ends(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta,
             double tb, double fa, double target, double guess, const double *endb,
             long double xy[2], long double *other, int fma)
{
    if (fa == 0) {
        dd_v2 p[4], dp[2] = {{0.0, 0.0}, {0.0, 0.0}};
        dd_point_parts(oc, fx, ta, fma, p, NULL);
        dd_out(p, dp, coord, 0.0, 0.0, xy, other);
        return ta;
    }
    double a, b, h1;
    double t = solve_double(oc, fx, 1, coord, ta, tb, fa, target, guess, DD_D_STEP, endb, &a,
                            &b, &h1);
    return root_dd_loop(oc, fx, coord, target, fa < 0, t, ta, tb, 0, xy, other, fma);
}

static __attribute__((noinline)) double root_dd_ends_split(const aa_offset_curve *oc,
                                                           const aa__offset_fix *fx, int coord,
                                                           double ta, double tb, double fa,
                                                           double target, double guess,
                                                           const double *endb,
                                                           long double xy[2], long double *other)
{
    return root_dd_ends(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other, 0);
}

static __attribute__((noinline, target("fma"))) double
root_dd_ends_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta,
                 double tb, double fa, double target, double guess, const double *endb,
                 long double xy[2], long double *other)
{
    return root_dd_ends(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other, 1);
}

static __attribute__((noinline)) double root_dd_more_split(const aa_offset_curve *oc,
                                                           const aa__offset_fix *fx, int coord,
                                                           double target, int neg, double t,
                                                           double la, double lb,
                                                           long double xy[2], long double *other)
{
    return root_dd_loop(oc, fx, coord, target, neg, t, la, lb, 1, xy, other, 0);
}

static __attribute__((noinline, target("fma"))) double
root_dd_more_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double target,
                 int neg, double t, double la, double lb, long double xy[2], long double *other)
{
    return root_dd_loop(oc, fx, coord, target, neg, t, la, lb, 1, xy, other, 1);
}

/* The double phase's loop after its evaluation it0 - 1 (solve_step's
 * state at t), then root_dd_loop from the start, and the outputs: a jump
 * from root_dd or from a batch's lane (after its second evaluation, it0
 * 2), which then makes no call it returns from (no registers of its
 * caller's saved, no frame) */
static __attribute__((always_inline)) inline double
root_d_more(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta, double tb,
            double a, double b, int neg, double target, double t, double prev, int unseen,
            double size, long double xy[2], long double *other, int it0, int fma)
{
    double pa, pb, last;
    t = solve_double_loop(oc, fx, 1, coord, a, b, neg, target, t, prev, unseen, size,
                          DD_D_STEP, it0, &pa, &pb, &last);
    return root_dd_loop(oc, fx, coord, target, neg, t, ta, tb, 0, xy, other, fma);
}

/* root_dd's (Dekker's products), from the third evaluation; the lanes
 * run with FMA and go on by root_d_more2_fma alone */
static __attribute__((noinline)) double
root_d_more2_split(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta,
                  double tb, double a, double b, int neg, double target, double t, double prev,
                  int unseen, double size, long double xy[2], long double *other)
{
    return root_d_more(oc, fx, coord, ta, tb, a, b, neg, target, t, prev, unseen, size, xy, other,
                       2, 0);
}

/* root_dd's and a batch's lanes' (offset_lanes.h) */
static __attribute__((noinline, target("fma"))) double
root_d_more2_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta,
                 double tb, double a, double b, int neg, double target, double t, double prev,
                 int unseen, double size, long double xy[2], long double *other)
{
    return root_d_more(oc, fx, coord, ta, tb, a, b, neg, target, t, prev, unseen, size, xy, other,
                       2, 1);
}

/* root_dd: the common case in one straight line, a start strictly inside
 * the bracket whose first double evaluation takes a Newton step within
 * DD_D_STEP and whose first double-double step is the last (on
 * tests/bench_bezstroke.c's scene at 1024 px 82% of the 100,812 roots a
 * render); the rest by a jump out of line, with the state as it stands
 * (root_dd_ends_*: no start or fa 0, 2%; root_d_more2_*: the double
 * phase on past its second step; root_dd_more_*: a second double-double
 * step, 0.1%).
 * The double phase's second step is inline too: of the 45,069 single
 * roots a render at 1024 px 13,520 took it out of line (by a
 * continuation from the second evaluation, 544 instructions each, since
 * gone), 433 now go on past it (root_d_more2_*), and a root takes 537.5
 * instructions against 552.7 (algorithms/README.md).
 * The operations are solve_double's and root_dd_loop's from the start,
 * in the same order, so the roots and points are the same bit for bit.
 * As one function with its loops (each evaluation inline in them) the
 * solver's constants and the loops' invariants were spilled to the
 * stack once a root and read back as operands, its registers saved and
 * its frame set up on every root: 591 instructions a root against 529
 * (algorithms/README.md). */
static __attribute__((always_inline)) inline double
root_dd(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta, double tb,
        double fa, double target, double guess, const double *endb, long double xy[2],
        long double *other, int fma)
{
    if (fa == 0 || !in_bracket(guess, ta, tb)) {
        if (fma)
            return root_dd_ends_fma(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other);
        return root_dd_ends_split(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other);
    }
    int neg = fa < 0, unseen = 1;
    /* solve_double's set-up and first step from the guess */
    double size = fx->dsize[coord] + fabs(target);
    double t = guess, a = ta, b = tb, prev = fabs(tb - ta), last = NAN, f, df, dn;
    eval_dd(oc, coord, t, target, &f, &df, &dn);
    int stop = solve_step(f, df, dn, size, DD_D_STEP, neg, &t, &a, &b, &prev, &unseen, &last);
    if (!stop) { /* its second step (30% of the single roots) */
        eval_dd(oc, coord, t, target, &f, &df, &dn);
        stop = solve_step(f, df, dn, size, DD_D_STEP, neg, &t, &a, &b, &prev, &unseen, &last);
    }
    if (!stop) {
        if (fma)
            return root_d_more2_fma(oc, fx, coord, ta, tb, a, b, neg, target, t, prev, unseen,
                                    size, xy, other);
        return root_d_more2_split(oc, fx, coord, ta, tb, a, b, neg, target, t, prev, unseen,
                                  size, xy, other);
    }
    /* the curve's coefficients loaded again below, not kept from above
     * (on the stack: the registers are the double-double form's) */
    __asm__ volatile("" ::: "memory");
    /* root_dd_loop's first step */
    dd_v2 p[4], dp[2];
    double la = ta, lb = tb, h = 0.0, hx = 0.0;
    dd_point_parts(oc, fx, t, fma, p, dp);
    if (!dd_step(p, dp, (dd_v2){target, target}, coord, neg, &t, &la, &lb, &h, &hx)) {
        if (fma)
            return root_dd_more_fma(oc, fx, coord, target, neg, t, la, lb, xy, other);
        return root_dd_more_split(oc, fx, coord, target, neg, t, la, lb, xy, other);
    }
    dd_out(p, dp, coord, h, hx, xy, other);
    return t;
}

static __attribute__((noinline)) double root_dd_split(const aa_offset_curve *oc,
                                                      const aa__offset_fix *fx, int coord,
                                                      double ta, double tb, double fa,
                                                      double target, double guess,
                                                      const double *endb, long double xy[2],
                                                      long double *other)
{
    return root_dd(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other, 0);
}

static __attribute__((noinline, target("fma"))) double
root_dd_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta, double tb,
            double fa, double target, double guess, const double *endb, long double xy[2],
            long double *other)
{
    return root_dd(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other, 1);
}

/* root_dd_fma built for AVX-512F and VL, taken where the processor has
 * them (root_wide): the same operations (no more fused than fma's, the
 * file built without contraction), compiled with 32 vector registers, not
 * 16, so fewer of the solver's constants and invariants spilled to the
 * stack (88 stack accesses in its code against 124); the same roots and
 * points bit for bit (tests/test_area_offset.c, test_roots_batch, against
 * aa__offset_root_dd_fma).  By a CPU profile of tests/bench_bezstroke.c
 * at 1024 px root_dd's share 7.24% to 6.85% (algorithms/README.md);
 * valgrind's processor has no AVX-512F, so callgrind counts root_dd_fma. */
static __attribute__((noinline, target("avx512f,avx512vl,fma"))) double
root_dd_512(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, double ta, double tb,
            double fa, double target, double guess, const double *endb, long double xy[2],
            long double *other)
{
    return root_dd(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other, 1);
}

/* AVX-512VL's bit alone (a processor with VL has F) */
static inline int root_wide(void)
{
    return __builtin_cpu_supports("avx512vl");
}

double aa__offset_root_dd_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                              double ta, double tb, double fa, double target, double guess,
                              const double *endb, long double xy[2], long double *other)
{
    return root_dd_fma(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, other);
}

/* root_dd on four (or eight) requests at once, one a lane of AVX's
 * packed doubles (__m256d; the double-double form's pairs of x and y as
 * two vectors, not one dd_v2): each lane the operations of root_dd's
 * common path (eval_dd, solve_step's stop at the first evaluation or,
 * where a lane does not stop there, its next point and second step, as
 * root_dd takes it inline; dd_point_parts, dd_step's stop at the first
 * step, dd_out) in their order, where the scalar form chooses by a test
 * both results computed and one blended in (no lane's operation takes
 * another lane's value), fma only where dd_two_prod has it: each root and
 * point the scalar one bit for bit (tests/test_area_offset.c,
 * test_roots_batch).  A lane that leaves the common path is finished one
 * by one by root_dd's continuations from its own state (solve_step again
 * on its lane's second evaluation, then root_d_more2_fma; dd_step again
 * on its lane's parts, then root_dd_more_fma).  The second step in the
 * lanes took the lanes sent on alone from 6,309 of 77,326 a render at
 * 1024 px to 9 (algorithms/README.md).  The four curves' coefficients
 * are loaded and transposed once a batch.  It replaced two requests
 * interleaved in scalar registers (roots2_fma, whose state spilled to
 * the stack, 565 stack accesses): one render of tests/bench_bezstroke.c
 * at 1024 px 206.3 M instructions to 191.8 M, at 256 px 244.7 M to 241.9
 * M (algorithms/README.md).  Built for AVX2 and FMA (roots4_avx2), and for
 * AVX-512F on eight requests at once (roots8_512: the same operations in
 * __m512d's lanes, its masks __mmask8), from one source
 * (offset_lanes.h); aa__offset_roots takes eight where the processor
 * has AVX-512F and a batch holds more than four, else four where it has
 * AVX2.  Eight lanes on this benchmark's band lines (nearly every batch
 * of band_roots' eight requests full) took the batches' share of a CPU
 * profile 5.6% to 5.1% (algorithms/README.md): valgrind's processor has
 * no AVX-512F, so callgrind counts the four. */
#define V4 __attribute__((target("avx2,fma"), always_inline)) static inline

/* the four lanes' values a[k] (one each) */
V4 __m256d v4_set(double a0, double a1, double a2, double a3)
{
    return _mm256_set_pd(a3, a2, a1, a0);
}

V4 __m256d v4_set1(double a)
{
    return _mm256_set1_pd(a);
}

V4 void v4_st(double *p, __m256d v)
{
    _mm256_storeu_pd(p, v);
}

V4 __m256d v4_sqrt(__m256d a)
{
    return _mm256_sqrt_pd(a);
}

V4 __m256d v4_abs(__m256d a)
{
    return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a);
}

V4 __m256d v4_min(__m256d a, __m256d b)
{
    return _mm256_min_pd(a, b);
}

V4 __m256d v4_max(__m256d a, __m256d b)
{
    return _mm256_max_pd(a, b);
}

/* a b - c by one rounding */
V4 __m256d v4_fmsub(__m256d a, __m256d b, __m256d c)
{
    return _mm256_fmsub_pd(a, b, c);
}

/* where m (all ones or zeros a lane): b, else a */
V4 __m256d v4_sel(__m256d m, __m256d a, __m256d b)
{
    return _mm256_blendv_pd(a, b, m);
}

V4 __m256d v4_lt(__m256d a, __m256d b)
{
    return _mm256_cmp_pd(a, b, _CMP_LT_OQ);
}

V4 __m256d v4_le(__m256d a, __m256d b)
{
    return _mm256_cmp_pd(a, b, _CMP_LE_OQ);
}

V4 __m256d v4_gt(__m256d a, __m256d b)
{
    return _mm256_cmp_pd(a, b, _CMP_GT_OQ);
}

V4 __m256d v4_eq(__m256d a, __m256d b)
{
    return _mm256_cmp_pd(a, b, _CMP_EQ_OQ);
}

V4 __m256d v4_ne(__m256d a, __m256d b)
{
    return _mm256_cmp_pd(a, b, _CMP_NEQ_OQ);
}

V4 __m256d v4_and(__m256d a, __m256d b)
{
    return _mm256_and_pd(a, b);
}

V4 __m256d v4_or(__m256d a, __m256d b)
{
    return _mm256_or_pd(a, b);
}

V4 __m256d v4_xor(__m256d a, __m256d b)
{
    return _mm256_xor_pd(a, b);
}

/* ~a & b */
V4 __m256d v4_andnot(__m256d a, __m256d b)
{
    return _mm256_andnot_pd(a, b);
}

V4 int v4_bits(__m256d m)
{
    return _mm256_movemask_pd(m);
}

/* the lanes whose request's coordinate is y */
V4 __m256d v4_coord(const aa__offset_rootq *const R[4])
{
    return _mm256_castsi256_pd(_mm256_set_epi64x(-(long long)R[3]->coord, -(long long)R[2]->coord,
                                                 -(long long)R[1]->coord,
                                                 -(long long)R[0]->coord));
}

/* the pairs (x, y) at p[k] (lane k's: fx's arrays, 8-byte aligned) as
 * four x's (*x) and four y's (*y) */
V4 void v4_pairs(const double *p0, const double *p1, const double *p2, const double *p3,
                 __m256d *x, __m256d *y)
{
    __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p0)),
                                     _mm_loadu_pd(p2), 1);
    __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p1)),
                                     _mm_loadu_pd(p3), 1);
    *x = _mm256_unpacklo_pd(a, b), *y = _mm256_unpackhi_pd(a, b);
}

/* four values at p[k][0..3] as their transpose: c[j] lane k p[k][j] */
V4 void v4_rows(const double *p0, const double *p1, const double *p2, const double *p3,
                __m256d c[4])
{
    __m256d a0 = _mm256_loadu_pd(p0), a1 = _mm256_loadu_pd(p1);
    __m256d a2 = _mm256_loadu_pd(p2), a3 = _mm256_loadu_pd(p3);
    __m256d l01 = _mm256_unpacklo_pd(a0, a1), h01 = _mm256_unpackhi_pd(a0, a1);
    __m256d l23 = _mm256_unpacklo_pd(a2, a3), h23 = _mm256_unpackhi_pd(a2, a3);
    c[0] = _mm256_permute2f128_pd(l01, l23, 0x20), c[1] = _mm256_permute2f128_pd(h01, h23, 0x20);
    c[2] = _mm256_permute2f128_pd(l01, l23, 0x31), c[3] = _mm256_permute2f128_pd(h01, h23, 0x31);
}

/* The same on eight lanes in AVX-512F's registers (__m512d; its masks
 * __mmask8, a bit a lane): the transposes two of four joined */
#define V8 __attribute__((target("avx512f,avx2,fma"), always_inline)) static inline

V8 __m512d v8_set(double a0, double a1, double a2, double a3, double a4, double a5, double a6,
                  double a7)
{
    return _mm512_set_pd(a7, a6, a5, a4, a3, a2, a1, a0);
}

V8 __m512d v8_set1(double a)
{
    return _mm512_set1_pd(a);
}

V8 void v8_st(double *p, __m512d v)
{
    _mm512_storeu_pd(p, v);
}

V8 __m512d v8_sqrt(__m512d a)
{
    return _mm512_sqrt_pd(a);
}

V8 __m512d v8_abs(__m512d a)
{
    return _mm512_abs_pd(a);
}

V8 __m512d v8_min(__m512d a, __m512d b)
{
    return _mm512_min_pd(a, b);
}

V8 __m512d v8_max(__m512d a, __m512d b)
{
    return _mm512_max_pd(a, b);
}

V8 __m512d v8_fmsub(__m512d a, __m512d b, __m512d c)
{
    return _mm512_fmsub_pd(a, b, c);
}

V8 __m512d v8_sel(__mmask8 m, __m512d a, __m512d b)
{
    return _mm512_mask_blend_pd(m, a, b);
}

V8 __mmask8 v8_lt(__m512d a, __m512d b)
{
    return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ);
}

V8 __mmask8 v8_le(__m512d a, __m512d b)
{
    return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ);
}

V8 __mmask8 v8_gt(__m512d a, __m512d b)
{
    return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ);
}

V8 __mmask8 v8_eq(__m512d a, __m512d b)
{
    return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ);
}

V8 __mmask8 v8_ne(__m512d a, __m512d b)
{
    return _mm512_cmp_pd_mask(a, b, _CMP_NEQ_OQ);
}

V8 __mmask8 v8_and(__mmask8 a, __mmask8 b)
{
    return a & b;
}

V8 __mmask8 v8_or(__mmask8 a, __mmask8 b)
{
    return a | b;
}

V8 __mmask8 v8_xor(__mmask8 a, __mmask8 b)
{
    return a ^ b;
}

V8 __mmask8 v8_andnot(__mmask8 a, __mmask8 b)
{
    return (__mmask8)(~a & b);
}

V8 int v8_bits(__mmask8 m)
{
    return m;
}

V8 __mmask8 v8_coord(const aa__offset_rootq *const R[8])
{
    int c = 0;
    for (int k = 0; k < 8; k++)
        c |= R[k]->coord << k;
    return (__mmask8)c;
}

V8 __m512d v8_join(__m256d lo, __m256d hi)
{
    return _mm512_insertf64x4(_mm512_castpd256_pd512(lo), hi, 1);
}

V8 void v8_pairs(const double *p0, const double *p1, const double *p2, const double *p3,
                 const double *p4, const double *p5, const double *p6, const double *p7,
                 __m512d *x, __m512d *y)
{
    __m256d x0, y0, x1, y1;
    v4_pairs(p0, p1, p2, p3, &x0, &y0);
    v4_pairs(p4, p5, p6, p7, &x1, &y1);
    *x = v8_join(x0, x1), *y = v8_join(y0, y1);
}

V8 void v8_rows(const double *p0, const double *p1, const double *p2, const double *p3,
                const double *p4, const double *p5, const double *p6, const double *p7,
                __m512d c[4])
{
    __m256d lo[4], hi[4];
    v4_rows(p0, p1, p2, p3, lo);
    v4_rows(p4, p5, p6, p7, hi);
    for (int j = 0; j < 4; j++)
        c[j] = v8_join(lo[j], hi[j]);
}

/* A request's other coordinate, where it asks it: not beside its point
 * (xy), which aa__offset_root_xyd gives alone */
static inline long double *rq_other(const aa__offset_rootq *q)
{
    return q->xy ? NULL : q->other;
}

#define VN 4
#define VD __m256d
#define VM __m256d
#define VF(name) v4_##name
#define V_ALL(E) E(0), E(1), E(2), E(3)
#define VATTR V4
#define VTARGET "avx2,fma"
#define VROOTS roots4_avx2
#include "offset_lanes.h"
#undef VN
#undef VD
#undef VM
#undef VF
#undef V_ALL
#undef VATTR
#undef VTARGET
#undef VROOTS

#define VN 8
#define VD __m512d
#define VM __mmask8
#define VF(name) v8_##name
#define V_ALL(E) E(0), E(1), E(2), E(3), E(4), E(5), E(6), E(7)
#define VATTR V8
#define VTARGET "avx512f,avx2,fma"
#define VROOTS roots8_512
#include "offset_lanes.h"
#undef VN
#undef VD
#undef VM
#undef VF
#undef V_ALL
#undef VATTR
#undef VTARGET
#undef VROOTS

/* A request outside root_dd's common start (no guess inside, fa 0, no
 * double-double form) or alone: aa__offset_root_fixd / _xyd's own way */
static void root_one(aa__offset_rootq *r)
{
    if (r->xy)
        r->t = aa__offset_root_xyd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa, r->target,
                                   r->guess, r->endb, r->xy);
    else
        r->t = aa__offset_root_fixd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa, r->target,
                                    r->guess, r->other);
}

static inline int root_common(const aa__offset_rootq *r)
{
    return r->fx->dd == 2 && r->fa != 0 && in_bracket(r->guess, r->ta, r->tb);
}

/* a batch of m common requests: eight lanes where more than four (the
 * caller's lanes 8), else four; one alone by itself */
static void roots_batch(aa__offset_rootq *const *c, int m)
{
    if (m > 4)
        roots8_512(c, m);
    else if (m > 1)
        roots4_avx2(c, m);
    else if (m)
        root_one(c[0]);
}

static __attribute__((always_inline)) inline void roots_lanes(aa__offset_rootq *q, size_t n,
                                                             int lanes)
{
    aa__offset_rootq *c[8]; /* common requests waiting for a batch */
    int m = 0;
    if (lanes >= 8 && !__builtin_cpu_supports("avx512f"))
        lanes = 4;
    if (lanes >= 4 && !__builtin_cpu_supports("avx2"))
        lanes = 1;
    if (lanes < 4) {
        for (size_t k = 0; k < n; k++)
            root_one(&q[k]);
        return;
    }
    lanes = lanes >= 8 ? 8 : 4;
    for (size_t k = 0; k < n; k++) {
        if (!root_common(&q[k])) {
            root_one(&q[k]);
            continue;
        }
        c[m++] = &q[k];
        if (m == lanes) {
            roots_batch(c, m);
            m = 0;
        }
    }
    roots_batch(c, m);
}

void aa__offset_roots(aa__offset_rootq *q, size_t n)
{
    roots_lanes(q, n, 8);
}

void aa__offset_roots_lanes(aa__offset_rootq *q, size_t n, int lanes)
{
    roots_lanes(q, n, lanes);
}

static __attribute__((noinline)) void point_dd_split(const aa_offset_curve *oc,
                                                     const aa__offset_fix *fx, double t,
                                                     long double xy[2])
{
    dd_v2 p[4];
    dd_point_parts(oc, fx, t, 0, p, NULL);
    xy[0] = dd_coord(p, 0, 0.0, 0.0, 0.0), xy[1] = dd_coord(p, 1, 0.0, 0.0, 0.0);
}

static __attribute__((noinline, target("fma"))) void
point_dd_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, double t, long double xy[2])
{
    dd_v2 p[4];
    dd_point_parts(oc, fx, t, 1, p, NULL);
    xy[0] = dd_coord(p, 0, 0.0, 0.0, 0.0), xy[1] = dd_coord(p, 1, 0.0, 0.0, 0.0);
}

/* aa__offset_fix_dd's coefficients, hi + lo; fma: TwoProduct by fma, else
 * by Dekker's split (both exact: the same errors, so the same values bit
 * for bit; by fma, where the processor has it, 3.7 M to 1.8 M instructions
 * of the init at 1024 px: 18 products a piece) */
static __attribute__((always_inline)) inline void fix_coefs(const aa_offset_curve *oc,
                                                           aa__offset_fix *fx, int fma)
{
    const double *b = oc->b, *m = oc->m;
    for (int c = 0; c < 2; c++)
        for (int k = 0; k < 4; k++) {
            /* m[c] b[k] + m[2 + c] b[4 + k] (+ m[4 + c]) exactly, then
             * rounded to hi + lo */
            double e1, e2, e3, e4 = 0.0;
            double p1 = dd_two_prod(m[c], b[k], &e1, fma);
            double p2 = dd_two_prod(m[2 + c], b[4 + k], &e2, fma);
            double sum = dd_two_sum(p1, p2, &e3);
            if (k == 0)
                sum = dd_two_sum(sum, m[4 + c], &e4), e4 += e3;
            else
                e4 = e3;
            fx->dc[k][0][c] = dd_two_sum(sum, e1 + e2 + e4, &fx->dc[k][1][c]);
        }
    for (int c = 0; c < 2; c++) { /* B': b1 + 2 b2 t + 3 b3 t^2 */
        fx->du[0][0][c] = b[4 * c + 1], fx->du[0][1][c] = 0.0;
        fx->du[1][0][c] = 2 * b[4 * c + 2], fx->du[1][1][c] = 0.0;
        fx->du[2][0][c] = dd_two_prod(3.0, b[4 * c + 3], &fx->du[2][1][c], fma);
    }
}

static __attribute__((noinline, target("fma"))) void fix_coefs_fma(const aa_offset_curve *oc,
                                                                   aa__offset_fix *fx)
{
    fix_coefs(oc, fx, 1);
}

void aa__offset_fix_dd(const aa_offset_curve *oc, aa__offset_fix *fx, int fma)
{
    fix_init(oc, fx);
    if (oc->base != AA_OFFSET_CUBIC || oc->evolute || fx->stops)
        return;
    int f = fma && __builtin_cpu_supports("fma");
    if (f)
        fix_coefs_fma(oc, fx);
    else
        fix_coefs(oc, fx, 0);
    const double *m = oc->m;
    for (int c = 0; c < 2; c++)
        fx->dsize[c] = fabs(m[c]) * fx->sx + fabs(m[2 + c]) * fx->sy + fabs(m[4 + c]);
    fx->dd = f ? 2 : 1;
}

void aa__offset_point_fix(const aa_offset_curve *oc, const aa__offset_fix *fx, double t,
                          long double *x, long double *y)
{
    long double xy[2];
    if (fx->dd == 2)
        point_dd_fma(oc, fx, t, xy);
    else if (fx->dd)
        point_dd_split(oc, fx, t, xy);
    else
        offset_eval(oc, fx->stops, t, &xy[0], &xy[1], NULL, NULL);
    *x = xy[0], *y = xy[1];
}

/* The long double form of the two below, out of line: inline there, its
 * frame (six registers saved, 456 bytes) was set up before the test of
 * fx->dd, on every root, about 20 instructions a call. */
static __attribute__((noinline)) double root_ld(const aa_offset_curve *oc,
                                                const aa__offset_fix *fx, int coord, double ta,
                                                double tb, double fa, double target,
                                                double guess, const double *endb,
                                                long double xy[2], long double *other)
{
    return (double)offset_root(oc, fx, coord, ta, tb, fa, target, guess, endb, other, NULL, xy);
}

/* The same two with arguments in double (converted exactly: the same
 * roots), for callers whose brackets and targets are doubles: long double
 * arguments go through memory, at both ends of the call.  Each passes its
 * arguments on in registers (a jump, not a call). */
double aa__offset_root_fixd(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                            double ta, double tb, double fa, double target, double guess,
                            long double *other)
{
    if (fx->dd == 2)
        return root_wide()
                   ? root_dd_512(oc, fx, coord, ta, tb, fa, target, guess, NULL, NULL, other)
                   : root_dd_fma(oc, fx, coord, ta, tb, fa, target, guess, NULL, NULL, other);
    if (fx->dd)
        return root_dd_split(oc, fx, coord, ta, tb, fa, target, guess, NULL, NULL, other);
    return root_ld(oc, fx, coord, ta, tb, fa, target, guess, NULL, NULL, other);
}

double aa__offset_root_xyd(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                           double ta, double tb, double fa, double target, double guess,
                           const double *endb, long double xy[2])
{
    if (fx->dd == 2)
        return root_wide()
                   ? root_dd_512(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, NULL)
                   : root_dd_fma(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, NULL);
    if (fx->dd)
        return root_dd_split(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, NULL);
    return root_ld(oc, fx, coord, ta, tb, fa, target, guess, endb, xy, NULL);
}

static __attribute__((always_inline)) inline long double
offset_root(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord, long double ta,
            long double tb, long double fa, long double target, double guess, const double *endb,
            long double *other, double *slope, long double *xy)
{
    /* f(t) = coord(t) - target: of the sign of fa at ta, the other at tb
     * (either may be 0).  Newton's method in double (solve_double, to a
     * step within ROOT_D_STEP), then in long double, still bracketed: a
     * step h within 1e-13 is the last (the error after it is of the order
     * of its square), and so is one whose error is judged from the step
     * h1 before it: Newton's error after a step is C times the square of
     * the error before (C = f''/(2 f'), about the root), and the error
     * before a step is about the step, so h ~ C h1^2, C ~ h/h1^2 and the
     * error after h ~ C h^2 = h^3/h1^2; taken as the last where that is
     * at most 1e-21 max(|t|, 1) (below long double's rounding of t, about
     * 5e-20 for t in [0, 1]), h is at most 1e-3 h1 (the steps shrinking
     * as Newton's do, not as a bisection's or near a double root) and at
     * most 1e-11.  Double's step to within 1e-6 then long double's one
     * step (h ~ 1e-12) replace a third double evaluation (a step to within
     * 1e-12) a root.  Else on until the bracket is two adjacent numbers.
     * The other coordinate at the root is the last evaluation's moved by
     * its derivative times that last step h: off by half its second
     * derivative times h^2, the order of the error the root itself is left
     * with (coordinate coord's second derivative over twice its first,
     * times h^2, moves the other coordinate by its first derivative times
     * that), and at |h| <= 1e-11 (t is in [0, 1]) about 1e-22 of that
     * second derivative.  The point at the root rounded to double (xy,
     * aa__offset_root_xy) the same way: the last evaluation moved by its
     * derivative over the step from there to the rounded root (at most h
     * plus half an ulp of t), where the caller would evaluate it again;
     * evaluated there where no evaluation was made.  Rounded to double
     * (root_ld: the evolutes and the pieces with stops), the root is the
     * nearest double but where it lies within the long double
     * evaluation's rounding of the middle between two (about 1e-17 px at
     * 256 px, over the slope: a few hundredths of an ulp of t at |y'|
     * about 1 px, the whole piece where the piece is nearly flat in the
     * coordinate, as small evolutes are), and there the double follows
     * where the last evaluation was made, so the start: on
     * tests/bench_bezstroke.c's scene at 256 px 23,876 of 108,856 roots
     * from four starts differ (23,672 where |y'| < 1e-3 px), the point at
     * each at most 2.67e-17 px farther from the line than |y'| times half
     * an ulp of t (tests/test_area_offset.c, test_root_starts). */
    long double X, Y, DX = 0, DY = 0, lt = ta;
    int neg = fa < 0, stops = fx->stops; /* asked once a curve (aa__offset_fix_init) */
    if (fa == 0)
        goto at_lt;
    double a, b, h1;
    lt = solve_double(oc, fx, 0, coord, (double)ta, (double)tb, (double)fa, (double)target,
                      guess, ROOT_D_STEP, endb, &a, &b, &h1);
    /* long double: the bracket is the caller's, [ta, tb], not what the
     * double phase left: the signs that shrank it are double's, wrong
     * within its rounding of the root, where long double's Newton steps
     * then left it and were bisected, one bit an evaluation */
    long double la = ta, lb = tb;
    /* Newton's steps, or a bisection where a step leaves the bracket: at
     * most ROOT_LD_STEPS, which a bisection alone needs to take any
     * bracket in the piece's parameter to two adjacent long doubles (a
     * cap of 8, as this once had, returned roots 3.5e-4 px off near a
     * turn, where Newton's steps left the bracket and the halvings had
     * not yet closed it) */
    for (int it = 0; it < ROOT_LD_STEPS; it++) {
        offset_eval(oc, stops, lt, &X, &Y, &DX, &DY);
        long double f = (coord ? Y : X) - target, df = coord ? DY : DX;
        if (f == 0)
            goto done;
        if ((f < 0) == neg)
            la = lt;
        else
            lb = lt;
        long double mid = 0.5L * (la + lb);
        /* two adjacent numbers, or a bracket of 1e-30 about a root at 0
         * (where adjacent numbers are denormals apart) */
        if (!(mid != la && mid != lb) || fabsl(lb - la) <= 1e-30L)
            goto done;
        long double next = df != 0 && isfinite(df) ? lt - f / df : mid;
        /* strictly inside: a step onto an end of the bracket (Newton's
         * steps between its two ends, each onto the other, the bracket
         * never shrinking, were seen within 1e-13 of a root) bisects */
        int inside = la < lb ? (next > la && next < lb) : (next < la && next > lb);
        long double h = fabsl(next - lt);
        if (!inside) {
            next = mid;
        } else if (h <= 1e-13L * fabsl(lt) + 1e-30L ||
                   (h1 > 0 && h <= 1e-11L && h <= 1e-3L * h1 &&
                    h * h * h <= 1e-21L * h1 * h1 * (fabsl(lt) > 1 ? fabsl(lt) : 1))) {
            if (other)
                *other = (coord ? X + DX * (next - lt) : Y + DY * (next - lt));
            if (slope)
                *slope = (double)df;
            if (xy) {
                long double hd = (long double)(double)next - lt;
                xy[0] = X + DX * hd, xy[1] = Y + DY * hd;
            }
            return next;
        }
        lt = next;
        h1 = inside ? (double)h : NAN;
    }
at_lt: /* lt not evaluated yet */
    if (xy) /* the point at the rounded root, as the caller would evaluate it */
        offset_eval(oc, stops, (double)lt, &xy[0], &xy[1], NULL, NULL);
    if (!other && !slope)
        return lt;
    offset_eval(oc, stops, lt, &X, &Y, &DX, &DY);
    if (other)
        *other = coord ? X : Y;
    if (slope)
        *slope = (double)(coord ? DY : DX);
    return lt;
done: /* lt evaluated */
    if (other)
        *other = coord ? X : Y;
    if (slope)
        *slope = (double)(coord ? DY : DX);
    if (xy) {
        long double hd = (long double)(double)lt - lt;
        xy[0] = X + DX * hd, xy[1] = Y + DY * hd;
    }
    return lt;
}
