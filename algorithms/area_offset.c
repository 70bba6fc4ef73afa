/*
 * area_offset.c: the exact area method's (area.c) integral over a part of
 * an offset curve or evolute of a Bezier arc or an ellipse
 * (AA_PIECE_OFFSET, aa_offset_curve): the segment between the part and its
 * chord,
 *
 *     seg = 1/2 integral of (P(t) - P(ta)) x P'(t) dt  from ta to tb,
 *
 * by Gauss-Legendre quadrature with a proven bound on its error.  It is
 * quadrature, not a closed form: with L = |B'| the offset's coordinates
 * carry 1/L, and the integral of B'y^2/L alone is an elliptic integral.
 *
 * The integrand.  In the curve's own coordinates (the map m multiplies
 * every cross product by det m), with D = B(t) - Pa, c = B' x B'':
 *  - offset P = B + d N, N = (-B'y, B'x)/L, P' = B' (1 - d c/L^3), and
 *    N x B' = -L, so  f = (D x B' - d L) (1 - d c/L^3);
 *  - evolute P = B + r N, r = L^3/c, P' = r' N with r' = L (3 (B'.B'') c -
 *    L^2 c')/c^2 (offset.c), and v x N = (v . B')/L, so
 *    f = (3 (B'.B'') c - L^2 c') (D . B')/c^2, a rational function.
 * Both are analytic wherever L^2 (a quartic in t) resp. c (a quadratic) has
 * no zero.
 *
 * The bound.  n-point Gauss-Legendre on [m - h, m + h] errs by at most
 *
 *     h 64 M / (15 (1 - rho^-2) rho^(2n))
 *
 * where f is analytic in the Bernstein ellipse m + h E_rho (foci m +- h,
 * semi-axes summing to h rho) with |f| <= M there (Trefethen,
 * "Approximation Theory and Approximation Practice", 2013, Theorem 19.3,
 * for n points).  That ellipse lies in the disc |z - m| <= R,
 * R = h (rho + 1/rho)/2, and on the disc every polynomial p(m + s) =
 * sum p_k s^k of the integrand is bounded by sum |p_k| R^k, and a
 * denominator from below by |p_0| - sum_{k>=1} |p_k| R^k, which, when
 * positive, also proves the disc free of zeros (so L = sqrt(L^2) has an
 * analytic branch there).  Hence M from the Taylor coefficients of B', L^2,
 * c, D x B' (offsets) or B'.B'', c', D . B' (evolutes) about m, with |Pa -
 * B(m)| bounded by sum_{k>=1} |B_k| h^k plus |d| (or the largest |r| on the
 * part, L^3/|c| bounded the same way).
 *
 * The ellipse B = c + u cos t + v sin t (AA_OFFSET_ELLIPSE) is not a
 * polynomial: about m, with u' = B(m) - c, v' = B'(m) and s = t - m,
 * B - B(m) = u' (cos s - 1) + v' sin s, B' = -u' sin s + v' cos s,
 * B'' = -(u' cos s + v' sin s), c = u x v = J is constant and c' = 0, so
 *  - offset: (B - B(m)) x B' = J (1 - cos s), and f as above;
 *  - evolute: f = 3 (B'.B'') (D . B')/J;
 *  - L^2 - |v'|^2 = (|u'|^2 - |v'|^2) sin^2 s - 2 (u'.v') sin s cos s.
 * On the disc |s| <= R, |cos s| <= cosh R, |sin s| <= sinh R and
 * |cos s - 1| <= cosh R - 1 (term by term in their series), which bound
 * every factor as the Taylor sums do for a cubic (complex vectors: |a . b|
 * <= |a| |b|), L^2 from below by |v'|^2 less the bound on the difference.
 *
 * A cubic whose B' vanishes at an end te (a cusp split off, a control
 * point on an end) has, next to te, the factored form B' = (t - te) Q of
 * offset.c (aa__offset_stop), in which the integrand is analytic through
 * te: with sg the sign of t - te on the curve, X = Q x Q' (constant) and
 * perp(Q) x Q = -|Q|^2, Q . perp(Q) = 0,
 *  - offset: f = ((B - Pa) x Q - d sg |Q|) (t - te - d sg X/|Q|^3);
 *  - evolute: f = ((B - Pa) . Q) (|Q|^2 + 3 (t - te) (Q . Q'))/X;
 * bounded on the disc by the Taylor sums of B - B(m), Q (linear) and |Q|^2
 * (|Q|^2 from below), |t - te| by |m - te| + R.
 *
 * Panels.  A piece's parameter range is cut in halves until on each panel
 * some rho of a fixed list gives a bound of at most AR_QUAD_TOL with
 * AR_QUAD_NMAX points; the panel keeps its disc (m, R) and M, searched
 * from the one the last panel of its width kept.  A part [ta, tb] of the
 * piece is integrated panel by panel: on each panel's share [alpha, beta]
 * from its own start point, the shares joined by the polygon
 * of their end points (seg = sum of the shares' segments + 1/2 sum (P(alpha)
 * - Pa) x (P(beta) - P(alpha))).  A share of half width h' about m' lies in
 * the disc |z - m'| <= R - |m' - m| inside the panel's, where M still
 * holds; its rho' is larger than the panel's (rho falls as h grows at fixed
 * slack R - h), so its bound is at most the panel's, and the fewest points
 * of AR_QUAD_RULES whose bound is within AR_QUAD_TOL are used: 8, 12 or
 * 16, whole groups of the four lanes a cubic's nodes are taken in (no
 * 4: ar_quad_order).  A part reaching past its first panel is one share
 * of that panel where its own ellipse still lies in the panel's disc (R -
 * |m' - m| > h': M holds there for start points on the panel, and the
 * panel's Taylor form is the curve's everywhere) and 8 or 12 points meet
 * the bound, checked (there the panel's own bound does not cover 16).  On
 * the 1,000 stroked cubics of tests/bench_bezstroke.c at 1024 px: 8
 * points for 86% of the shares, 12 for 12%, 16 for 2% (91,219 shares a
 * render; those of 4 points before, 11,738, now of 8).  The
 * bound holds up to the rounding of the bound's own terms (a relative
 * 1e-12 margin is added) and of the sum itself (about 1e-16 of the
 * integrand's size times h).
 *
 * Refused (AA_EINVAL): a piece whose panels would be narrower than 1e-12 of
 * its parameter range (B' or c within rounding of 0 on it; the stroker
 * refuses such Bezier arcs first).
 */
#include "area_internal.h"

#include <gsl/gsl_integration.h>
#include <immintrin.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Gauss-Legendre orders tried, ascending; the last is the panels' own.
 * Multiples of 4: a cubic's nodes go four at a time (nodes_avx), so 6 and
 * 11 points took as many groups as 8 and 12.  No 4-point rule: a pass of
 * AVX-512F's eight lanes holds 8 points, and the choice between 4 and 8
 * (12.9% and 73.4% of the 91,219 shares at 1024 px on
 * tests/bench_bezstroke.c) took more time than the four nodes saved
 * (algorithms/README.md); 8 points where 4 met the bound meet it too (a
 * rule's bound falls as n grows). */
static const int ar_quad_order[AR_QUAD_RULES] = {8, 12, 16}; /* rule writes them out */

int area_quad_init(ar_quad *q)
{
    int at = 0;
    for (int r = 0; r < AR_QUAD_RULES; r++) {
        int n = ar_quad_order[r];
        gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc((size_t)n);
        if (!t)
            return aa_fail(AA_ENOMEM, "out of memory for a Gauss-Legendre table");
        q->n[r] = n;
        q->at[r] = at;
        for (int i = 0; i < n; i++)
            gsl_integration_glfixed_point(-1.0, 1.0, (size_t)i, &q->x[at + i], &q->w[at + i], t);
        gsl_integration_glfixed_table_free(t);
        /* padded to a multiple of 4 with the last node of weight 0 (the
         * nodes are taken four at a time, and the copies add w f = 0) */
        for (int i = n; i % 4; i++)
            q->x[at + i] = q->x[at + n - 1], q->w[at + i] = 0.0;
        at += (n + 3) & ~3;
    }
    /* 2, 1 or 0 (__builtin_cpu_supports returns the feature's bit, not 1) */
    __builtin_cpu_init();
    q->avx = __builtin_cpu_supports("avx512f") ? 2 : __builtin_cpu_supports("avx") ? 1 : 0;
    return AA_OK;
}

/* ---- small polynomials in s = t - m (coefficients ascending) ----
 *
 * Their sizes are constants where they are used: the loops unrolled there
 * (the panels' bounds take them at every panel and disc: 25 M of the
 * init's 163 M instructions at 256 px on tests/bench_bezstroke.c), the same
 * operations in the same order. */

static inline void pmul(const double *a, int na, const double *b, int nb, double *out)
{
#pragma GCC unroll 8
    for (int k = 0; k < na + nb - 1; k++)
        out[k] = 0.0;
#pragma GCC unroll 4
    for (int i = 0; i < na; i++)
#pragma GCC unroll 4
        for (int j = 0; j < nb; j++)
            out[i + j] += a[i] * b[j];
}

/* pmul(a0, b0) plus pmul(a1, b1) (sub: less it), the two products in
 * SSE2's two lanes: the same operations in the same order as the two pmul
 * and the sum after, so the same bits (speed_polys' and a panel's
 * polynomials: the init 71.5 M to 67.5 M instructions on
 * tests/bench_bezstroke.c's scene at 1024 px) */
static inline void pmul_pair(const double *a0, const double *a1, int na, const double *b0,
                             const double *b1, int nb, int sub, double *out)
{
    __m128d acc[8];
#pragma GCC unroll 8
    for (int k = 0; k < na + nb - 1; k++)
        acc[k] = _mm_setzero_pd();
#pragma GCC unroll 4
    for (int i = 0; i < na; i++) {
        __m128d a = _mm_set_pd(a1[i], a0[i]);
#pragma GCC unroll 4
        for (int j = 0; j < nb; j++)
            acc[i + j] = _mm_add_pd(acc[i + j], _mm_mul_pd(a, _mm_set_pd(b1[j], b0[j])));
    }
#pragma GCC unroll 8
    for (int k = 0; k < na + nb - 1; k++) {
        __m128d hi = _mm_unpackhi_pd(acc[k], acc[k]);
        _mm_store_sd(&out[k], sub ? _mm_sub_sd(acc[k], hi) : _mm_add_sd(acc[k], hi));
    }
}

/* sum |p_k| R^k over k >= from */
static inline double pabs(const double *p, int n, int from, double R)
{
    double s = 0.0, r = 1.0;
#pragma GCC unroll 6
    for (int k = 0; k < n; k++) {
        if (k >= from)
            s += fabs(p[k]) * r;
        r *= R;
    }
    return s;
}

/* From a cubic's Taylor coefficients about m (bx, by: B(m + s) = sum b_k
 * s^k): B' (ux, uy) and B'' (vx, vy) in s, |B'|^2 (L2) and the cross
 * product B' x B'' (c), the polynomials the speed's bounds are made of. */
static void speed_polys(const double *bx, const double *by, double ux[3], double uy[3],
                        double vx[2], double vy[2], double L2[5], double c[4])
{
    ux[0] = bx[1], ux[1] = 2 * bx[2], ux[2] = 3 * bx[3];
    uy[0] = by[1], uy[1] = 2 * by[2], uy[2] = 3 * by[3];
    vx[0] = 2 * bx[2], vx[1] = 6 * bx[3];
    vy[0] = 2 * by[2], vy[1] = 6 * by[3];
    pmul_pair(ux, uy, 3, ux, uy, 3, 0, L2);
    pmul_pair(ux, uy, 3, vy, vx, 2, 1, c);
}

/* |p| on the disc of radius R: at most pabs(p, 0), at least this (<= 0:
 * no bound, a zero may be inside) */
static double plow(const double *p, int n, double R)
{
    return fabs(p[0]) - pabs(p, n, 1, R);
}

/* The Taylor coefficients of B about m: B(m + s) - B(m) = s (b1 + s (b2 +
 * s b3)), x in bx[1..3], y in by[1..3] (bx[0] = by[0] = 0). */
static void taylor(const aa_offset_curve *oc, double m, double *bx, double *by)
{
    const double *b = oc->b;
    long double M = m;
    bx[0] = by[0] = 0.0;
    bx[1] = (double)(b[1] + M * (2.0L * b[2] + 3.0L * M * b[3]));
    bx[2] = (double)(b[2] + 3.0L * M * b[3]);
    bx[3] = b[3];
    by[1] = (double)(b[5] + M * (2.0L * b[6] + 3.0L * M * b[7]));
    by[2] = (double)(b[6] + 3.0L * M * b[7]);
    by[3] = b[7];
}

/* The length of (a, b) for the bounds: sqrt of the sum of squares, not
 * hypot (a library call, a sixth of a disc's bound); its rounding, a few
 * units in the last place, within the bound's 1e-12 margin. */
static inline double len2(double a, double b)
{
    return sqrt(a * a + b * b);
}

/* The bound on |f| (the curve's own units) over the disc |s| <= R of a
 * panel of half width h, for start points on the panel; INFINITY if a
 * denominator may vanish there.  Made in two steps: panel_pre, once per
 * panel, the polynomials in s and the terms that do not depend on R (the
 * panel tries up to a dozen discs), and panel_M, per disc, their sums. */
typedef struct panel_pre {
    int kind; /* 0 offset, 1 evolute, 2 stop offset, 3 stop evolute, -1 none */
    double ux[3], uy[3], L2[5], c[4], G[6], dd[4], cp[3];
    double Qx[2], Qy[2], Q2[3], QQ[2], X, mte;
    double A, d;
} panel_pre;

static void panel_pre_cubic(const aa_offset_curve *oc, const double *bx, const double *by,
                            double h, panel_pre *P)
{
    double vx[2], vy[2];
    speed_polys(bx, by, P->ux, P->uy, vx, vy, P->L2, P->c);
    const double *ux = P->ux, *uy = P->uy;
    /* the start point's distance from B(m): |B(t) - B(m)| on the panel,
     * plus the normal's length */
    P->A = len2(pabs(bx, 4, 1, h), pabs(by, 4, 1, h));
    if (!oc->evolute) {
        P->kind = 0;
        P->d = fabs(oc->d);
        P->A += P->d;
        /* D x B' with D = B - B(m): Bx B'y - By B'x */
        pmul_pair(bx, by, 4, uy, ux, 3, 1, P->G);
        return;
    }
    double ch = plow(P->c, 4, h);
    if (!(ch > 0.0)) {
        P->kind = -1;
        return;
    }
    P->kind = 1;
    double L2h = pabs(P->L2, 5, 0, h);
    P->A += L2h * sqrt(L2h) / ch; /* |r| = L^3/|c| on the panel */
    double w[2] = {6 * bx[3], 6 * by[3]};
    pmul_pair(ux, uy, 3, vx, vy, 2, 0, P->dd);
    for (int k = 0; k < 3; k++)
        P->cp[k] = ux[k] * w[1] - uy[k] * w[0];
    pmul_pair(bx, by, 4, ux, uy, 3, 0, P->G); /* D . B' */
}

/* panel_pre for a cubic in the factored form about te (q: Q's
 * coefficients, aa__offset_stop). */
static void panel_pre_stop(const aa_offset_curve *oc, const double *bx, const double *by,
                           double m, double te, const double *q, double h, panel_pre *P)
{
    double *Qx = P->Qx, *Qy = P->Qy, *Q2 = P->Q2, t1[3], t2[5];
    Qx[0] = q[0] + q[1] * m, Qx[1] = q[1];
    Qy[0] = q[2] + q[3] * m, Qy[1] = q[3];
    pmul(Qx, 2, Qx, 2, Q2);
    pmul(Qy, 2, Qy, 2, t1);
    for (int k = 0; k < 3; k++)
        Q2[k] += t1[k];
    P->X = fabs(Qx[0] * q[3] - Qy[0] * q[1]), P->mte = fabs(m - te);
    double Bdh = len2(pabs(bx, 4, 1, h), pabs(by, 4, 1, h));
    if (!oc->evolute) {
        P->kind = 2;
        P->d = fabs(oc->d);
        P->A = Bdh;
        pmul(bx, 4, Qy, 2, P->G); /* (B - B(m)) x Q */
        pmul(by, 4, Qx, 2, t2);
        for (int k = 0; k < 5; k++)
            P->G[k] -= t2[k];
        return;
    }
    if (!(P->X > 0.0)) {
        P->kind = -1;
        return;
    }
    P->kind = 3;
    pmul(bx, 4, Qx, 2, P->G); /* (B - B(m)) . Q */
    pmul(by, 4, Qy, 2, t2);
    for (int k = 0; k < 5; k++)
        P->G[k] += t2[k];
    P->QQ[0] = Qx[0] * q[1] + Qy[0] * q[3], P->QQ[1] = q[1] * q[1] + q[3] * q[3];
    /* |Ea - B(m)|: |B(ta) - B(m)| + |ta - te| |Q(ta)|^2/|X| on the panel */
    P->A = Bdh + (P->mte + h) * pabs(Q2, 3, 0, h) / P->X;
}

static double panel_M(const panel_pre *P, double R)
{
    if (P->kind < 0)
        return INFINITY;
    if (P->kind >= 2) {
        double sd = P->mte + R, Qmax = sqrt(pabs(P->Q2, 3, 0, R)), X = P->X;
        if (P->kind == 2) {
            double lo = plow(P->Q2, 3, R), d = P->d;
            if (!(lo > 0.0))
                return INFINITY;
            return (pabs(P->G, 5, 0, R) + (P->A + d) * Qmax + d * Qmax) *
                   (sd + d * X / (lo * sqrt(lo)));
        }
        return (pabs(P->G, 5, 0, R) + P->A * Qmax) *
               (pabs(P->Q2, 3, 0, R) + 3 * sd * pabs(P->QQ, 2, 0, R)) / X;
    }
    /* the denominators first: a disc holding a zero is refused at once */
    double lo = P->kind == 0 ? plow(P->L2, 5, R) : plow(P->c, 4, R);
    if (!(lo > 0.0))
        return INFINITY;
    double Uux = pabs(P->ux, 3, 0, R), Uuy = pabs(P->uy, 3, 0, R), Uu = len2(Uux, Uuy);
    if (P->kind == 0) {
        double d = P->d;
        return (pabs(P->G, 6, 0, R) + P->A * Uu + d * sqrt(pabs(P->L2, 5, 0, R))) *
               (1.0 + d * pabs(P->c, 4, 0, R) / (lo * sqrt(lo)));
    }
    double cl = lo;
    return (3 * pabs(P->dd, 4, 0, R) * pabs(P->c, 4, 0, R) +
            pabs(P->L2, 5, 0, R) * pabs(P->cp, 3, 0, R)) *
           (pabs(P->G, 6, 0, R) + P->A * Uu) / (cl * cl);
}

/* panel_M for the ellipse: u', v' its semi-diameters at m (B(m) - c and
 * B'(m)). */
static double panel_M_ellipse(const aa_offset_curve *oc, const double *up, const double *vp,
                              double h, double R)
{
    double ch = cosh(R), sh = sinh(R);
    double uu = up[0] * up[0] + up[1] * up[1], vv = vp[0] * vp[0] + vp[1] * vp[1];
    double uv = fabs(up[0] * vp[0] + up[1] * vp[1]), J = fabs(up[0] * vp[1] - up[1] * vp[0]);
    double lu = sqrt(uu), lv = sqrt(vv);
    double Bd = lu * (ch - 1.0) + lv * sh; /* |B - B(m)| on the disc */
    double Uu = lu * sh + lv * ch;         /* |B'| */
    double dL = fabs(uu - vv) * sh * sh + 2.0 * uv * sh * ch, lo = vv - dL, hi = vv + dL;
    /* on the real panel (|s| <= h) */
    double Bdh = lu * (1.0 - cos(fmin(h, M_PI))) + lv * sin(fmin(h, 0.5 * M_PI));
    double dLh = fabs(uu - vv) * fmin(sinh(h) * sinh(h), 1.0) + 2.0 * uv * sinh(h) * cosh(h);
    if (!(lo > 0.0) || !(J > 0.0))
        return INFINITY;
    if (!oc->evolute) {
        double d = fabs(oc->d), A = Bdh + d;
        return (J * (ch - 1.0) + A * Uu + d * sqrt(hi)) * (1.0 + d * J / (lo * sqrt(lo)));
    }
    double L2h = vv + dLh, A = Bdh + L2h * sqrt(L2h) / J;
    double dot = fabs(uu - vv) * sh * ch + uv * (sh * sh + ch * ch); /* |B'.B''| */
    return 3.0 * dot * (Bd + A) * Uu / J;
}

/* The ellipse's semi-diameters at m: u' = B(m) - c, v' = B'(m). */
static void ellipse_at(const aa_offset_curve *oc, double m, double *up, double *vp)
{
    const double *b = oc->b;
    double cm = cos(m), sm = sin(m);
    up[0] = b[2] * cm + b[4] * sm, up[1] = b[3] * cm + b[5] * sm;
    vp[0] = -b[2] * sm + b[4] * cm, vp[1] = -b[3] * sm + b[5] * cm;
}

/* B(m) mapped into the image, each coordinate as hi + lo (x[0] + x[1]):
 * evaluated in long double (a relative 1e-19 or so: about 1e-16 px on an
 * image of 1024 px, where long double is x87's; where it is no wider than
 * double, lo is 0 and area's rows pass no point: ar_piece's rowpt), then
 * rounded twice */
static void image_point(const aa_offset_curve *oc, double m, double *x, double *y)
{
    const double *b = oc->b, *mp = oc->m;
    long double M = m, X, Y;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        long double cm = cosl(M), sm = sinl(M);
        X = b[0] + (b[2] * cm + b[4] * sm), Y = b[1] + (b[3] * cm + b[5] * sm);
    } else {
        X = b[0] + M * (b[1] + M * (b[2] + M * (long double)b[3]));
        Y = b[4] + M * (b[5] + M * (b[6] + M * (long double)b[7]));
    }
    long double x1 = mp[4] + ((long double)mp[0] * X + (long double)mp[2] * Y);
    long double y1 = mp[5] + ((long double)mp[1] * X + (long double)mp[3] * Y);
    x[0] = (double)x1, x[1] = (double)(x1 - x[0]);
    y[0] = (double)y1, y[1] = (double)(y1 - y[0]);
}

typedef struct panel_buf {
    ar_panel *p;
    size_t n, cap;
    int stops; /* aa__offset_stops: the ends where aa__offset_stop may hold */
} panel_buf;

/* The Bernstein ellipses' rho tried on a panel, ascending; NRHO of them */
#define NRHO 12
#define PANEL_DEPTH 60 /* the deepest halving */
static const double rhos[NRHO] = {1.25, 1.5, 2, 3, 4, 6, 8, 12, 16, 32, 64, 128};

/* Each rho's factor in the AR_QUAD_NMAX-point bound, 64/(15 (1 - rho^-2)
 * rho^2n) (disc_e), with rho^32 as five squarings */
_Static_assert(AR_QUAD_NMAX == 16, "disc_cf's rho^32 is rho^(2 AR_QUAD_NMAX)");
#define CF_SQ(x) ((x) * (x))
#define CF(r) (64.0 / (15.0 * (1.0 - 1.0 / ((r) * (r))) * CF_SQ(CF_SQ(CF_SQ(CF_SQ(CF_SQ(r)))))))
static const double disc_cf[NRHO] = {CF(1.25), CF(1.5), CF(2.0),  CF(3.0),  CF(4.0),  CF(6.0),
                                     CF(8.0),  CF(12.0), CF(16.0), CF(32.0), CF(64.0), CF(128.0)};
#undef CF
#undef CF_SQ

/* The panel's bound with AR_QUAD_NMAX points on disc k, h M cf[k] (cf[k]
 * = 64/(15 (1 - rho^-2) rho^2n), rho = rhos[k]); INFINITY if the disc may
 * hold a zero of a denominator.  Its rounding, a few units in the last
 * place, is within the 1e-12 margin on M. */
static double disc_e(const aa_offset_curve *oc, const panel_pre *pre, const double *up,
                     const double *vp, int ell, double h, double det2, const double *cf, int k,
                     double *Rk, double *Mk)
{
    double rho = rhos[k], R = 0.5 * h * (rho + 1.0 / rho);
    double M = (ell ? panel_M_ellipse(oc, up, vp, h, R) : panel_M(pre, R)) * det2 *
               (1.0 + 1e-12);
    *Rk = R, *Mk = M;
    if (!(M < INFINITY))
        return INFINITY;
    return h * M * cf[k];
}

/* cf: the bound's factor for each rho (disc_cf); hint[d]: the disc of
 * least bound on the last panel at depth d (-1 before one), where the
 * search at that depth starts */
static int panels_rec(const aa_offset_curve *oc, double a, double b, double det2, double width,
                      const double *cf, int *hint, int depth, panel_buf *out)
{
    double m = 0.5 * (a + b), h = 0.5 * (b - a), bx[4] = {0}, by[4] = {0};
    int ell = oc->base == AA_OFFSET_ELLIPSE;
    double up[2], vp[2], te, q[4];
    /* asked only at an end with a stop (aa__offset_stops' bit for the
     * half of m: the same test in the same arithmetic, so the same answer;
     * a call of 45 instructions on each of the 35,000 panels tried at
     * 1024 px otherwise) */
    int stop = (out->stops & (m < 0.5 ? 1 : 2)) && aa__offset_stop(oc, m, &te, q);
    if (ell) {
        ellipse_at(oc, m, up, vp);
        bx[1] = up[0], by[1] = up[1], bx[2] = vp[0], by[2] = vp[1];
    } else {
        taylor(oc, m, bx, by);
    }
    panel_pre pre;
    if (stop && !ell)
        panel_pre_stop(oc, bx, by, m, te, q, h, &pre);
    else if (!ell)
        panel_pre_cubic(oc, bx, by, h, &pre);
    /* The disc, searched from the hint: down while the disc holds a zero
     * of a denominator (so does every larger one); the first finite bound
     * kept if it meets the tolerance, else towards the smaller bound while
     * it falls (a local least) */
    int k = NRHO / 4; /* a piece's first panel */
    if (hint[depth] >= 0)
        k = hint[depth];
    else if (depth > 0 && hint[depth - 1] >= 0) /* half the width: a larger rho */
        k = hint[depth - 1] + 1 < NRHO ? hint[depth - 1] + 1 : NRHO - 1;
    double bR, bM, best = disc_e(oc, &pre, up, vp, ell, h, det2, cf, k, &bR, &bM);
    int down = 0;
    while (!(best < INFINITY) && k > 0) {
        k--, down = 1;
        best = disc_e(oc, &pre, up, vp, ell, h, det2, cf, k, &bR, &bM);
    }
    if (best < INFINITY) {
        double R, M, e;
        int kept = best <= AR_QUAD_TOL, up1 = 0;
        while (!down && !kept && k + 1 < NRHO &&
               (e = disc_e(oc, &pre, up, vp, ell, h, det2, cf, k + 1, &R, &M)) < best)
            k++, best = e, bR = R, bM = M, up1 = 1;
        while (!kept && !up1 && k > 0 &&
               (e = disc_e(oc, &pre, up, vp, ell, h, det2, cf, k - 1, &R, &M)) < best)
            k--, best = e, bR = R, bM = M;
        hint[depth] = k;
    }
    if (best <= AR_QUAD_TOL) {
        if (out->n == out->cap) {
            size_t cap = out->cap ? 2 * out->cap : 8;
            ar_panel *p = realloc(out->p, cap * sizeof *p);
            if (!p)
                return aa_fail(AA_ENOMEM, "out of memory for an offset curve's panels");
            out->p = p, out->cap = cap;
        }
        ar_panel *p = &out->p[out->n++];
        p->a = a, p->b = b, p->m = m, p->R = bR, p->M = bM;
        p->stop = stop, p->te = stop ? te : 0.0;
        for (int j = 0; j < 4; j++)
            p->q[j] = stop ? q[j] : 0.0;
        memcpy(p->bx, bx, sizeof bx);
        memcpy(p->by, by, sizeof by);
        image_point(oc, m, p->qx, p->qy);
        return AA_OK;
    }
    if (depth >= PANEL_DEPTH || b - a <= 1e-12 * width || !(m > a && m < b))
        return aa_fail(AA_EINVAL,
                       "area: an offset curve of a Bezier arc or ellipse near t = %.17g whose "
                       "quadrature "
                       "bound (%g px^2) it cannot meet (its speed or curvature within rounding "
                       "of 0 there)",
                       m, AR_QUAD_TOL);
    int st = panels_rec(oc, a, m, det2, width, cf, hint, depth + 1, out);
    return st ? st : panels_rec(oc, m, b, det2, width, cf, hint, depth + 1, out);
}

int area_offset_panels_append(const aa_offset_curve *oc, double t0, double t1, ar_panel **arr,
                              size_t *n, size_t *cap)
{
    panel_buf buf = {*arr, *n, *cap, aa__offset_stops(oc)};
    double a = fmin(t0, t1), b = fmax(t0, t1);
    double det2 = 0.5 * fabs(oc->m[0] * oc->m[3] - oc->m[2] * oc->m[1]);
    int hint[PANEL_DEPTH + 1];
    for (int k = 0; k <= PANEL_DEPTH; k++)
        hint[k] = -1;
    int st = panels_rec(oc, a, b, det2, b - a, disc_cf, hint, 0, &buf);
    *arr = buf.p, *cap = buf.cap; /* grown, even on a failure */
    if (!st)
        *n = buf.n;
    return st;
}

int area_offset_panels(const aa_offset_curve *oc, double t0, double t1, ar_panel **out,
                       size_t *n)
{
    ar_panel *p = NULL;
    size_t np = 0, cap = 0;
    int st = area_offset_panels_append(oc, t0, t1, &p, &np, &cap);
    if (st) {
        free(p);
        return st;
    }
    *out = p;
    *n = np;
    return AA_OK;
}

/* The point of the curve at t, less B(m) of panel p (its own coordinates),
 * and B' there. */
static __attribute__((always_inline)) inline void rel_point(const aa_offset_curve *oc,
                                                           const ar_panel *p, double t,
                                                           double *x, double *y)
{
    double s = t - p->m;
    const double *bx = p->bx, *by = p->by;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        /* B - B(m) = u' (cos s - 1) + v' sin s, cos s - 1 = -2 sin^2(s/2) */
        double h2 = sin(0.5 * s), c1 = -2.0 * h2 * h2, sn = sin(s);
        double ux = -bx[1] * sn + bx[2] * (1.0 + c1), uy = -by[1] * sn + by[2] * (1.0 + c1);
        double L = sqrt(ux * ux + uy * uy), r = oc->d;
        if (oc->evolute)
            r = L * L * L / (bx[1] * by[2] - by[1] * bx[2]);
        *x = bx[1] * c1 + bx[2] * sn - r * uy / L;
        *y = by[1] * c1 + by[2] * sn + r * ux / L;
        return;
    }
    if (p->stop) {
        /* the factored form: P = B + d sg perp(Q)/|Q|, E = B + (t - te)
         * |Q|^2 perp(Q)/X */
        const double *q = p->q, te = p->te;
        double Qx = q[0] + q[1] * t, Qy = q[2] + q[3] * t, q2 = Qx * Qx + Qy * Qy;
        double r = oc->evolute ? (t - te) * q2 / (Qx * q[3] - Qy * q[1])
                               : oc->d * (te == 0 ? 1 : -1) / sqrt(q2);
        *x = s * (bx[1] + s * (bx[2] + s * bx[3])) - r * Qy;
        *y = s * (by[1] + s * (by[2] + s * by[3])) + r * Qx;
        return;
    }
    double ux = bx[1] + s * (2 * bx[2] + 3 * s * bx[3]);
    double uy = by[1] + s * (2 * by[2] + 3 * s * by[3]);
    double L = sqrt(ux * ux + uy * uy), r = oc->d;
    if (oc->evolute) {
        double vx = 2 * bx[2] + 6 * s * bx[3], vy = 2 * by[2] + 6 * s * by[3];
        r = L * L * L / (ux * vy - uy * vx);
    }
    *x = s * (bx[1] + s * (bx[2] + s * bx[3])) - r * uy / L;
    *y = s * (by[1] + s * (by[2] + s * by[3])) + r * ux / L;
}

/* share's w f at the n nodes x (weights w) of a cubic's offset or evolute
 * (not next to a stop), four at a time, summed lane by lane (lane j: nodes
 * j, j + 4, j + 8, ... in order), the lanes then as (0 + 2) + (1 + 3):
 * each lane the operations of share's two-at-a-time loop below in their
 * order (AVX without FMA: nothing fused, sqrt and the divisions correctly
 * rounded), so each w f and each lane's sum the same double; the rules'
 * tables are padded to a multiple of 4 with the last node of weight 0. */
__attribute__((target("avx"), always_inline)) static inline double
nodes_avx_k(const double *qx, const double *qw, int n, double sm, double h,
            const double *bx, const double *by, const double *d, double ax, double ay,
            const int evolute)
{
    /* the panel's numbers broadcast from memory (one instruction each),
     * 2 b2 as b2 + b2 (exact) */
    const __m256d vsm = _mm256_set1_pd(sm), vh = _mm256_set1_pd(h);
    const __m256d b1x = _mm256_broadcast_sd(bx + 1), b2x = _mm256_broadcast_sd(bx + 2);
    const __m256d b3x = _mm256_broadcast_sd(bx + 3), b1y = _mm256_broadcast_sd(by + 1);
    const __m256d b2y = _mm256_broadcast_sd(by + 2), b3y = _mm256_broadcast_sd(by + 3);
    const __m256d b2x2 = _mm256_add_pd(b2x, b2x), b2y2 = _mm256_add_pd(b2y, b2y);
    const __m256d three = _mm256_set1_pd(3.0), six = _mm256_set1_pd(6.0);
    const __m256d one = _mm256_set1_pd(1.0), vd = _mm256_broadcast_sd(d);
    const __m256d vax = _mm256_set1_pd(ax), vay = _mm256_set1_pd(ay);
    __m256d sum = _mm256_setzero_pd();
    for (int i = 0; i < n; i += 4) {
        __m256d x = _mm256_loadu_pd(qx + i), w = _mm256_loadu_pd(qw + i);
        __m256d s = _mm256_add_pd(vsm, _mm256_mul_pd(vh, x));
        __m256d s3 = _mm256_mul_pd(three, s), s6 = _mm256_mul_pd(six, s);
        __m256d ux =
            _mm256_add_pd(b1x, _mm256_mul_pd(s, _mm256_add_pd(b2x2, _mm256_mul_pd(s3, b3x))));
        __m256d uy =
            _mm256_add_pd(b1y, _mm256_mul_pd(s, _mm256_add_pd(b2y2, _mm256_mul_pd(s3, b3y))));
        __m256d vx = _mm256_add_pd(b2x2, _mm256_mul_pd(s6, b3x));
        __m256d vy = _mm256_add_pd(b2y2, _mm256_mul_pd(s6, b3y));
        __m256d Dx = _mm256_sub_pd(
            _mm256_mul_pd(
                s, _mm256_add_pd(b1x, _mm256_mul_pd(s, _mm256_add_pd(b2x, _mm256_mul_pd(s, b3x))))),
            vax);
        __m256d Dy = _mm256_sub_pd(
            _mm256_mul_pd(
                s, _mm256_add_pd(b1y, _mm256_mul_pd(s, _mm256_add_pd(b2y, _mm256_mul_pd(s, b3y))))),
            vay);
        __m256d L2 = _mm256_add_pd(_mm256_mul_pd(ux, ux), _mm256_mul_pd(uy, uy));
        __m256d c = _mm256_sub_pd(_mm256_mul_pd(ux, vy), _mm256_mul_pd(uy, vx)), f;
        if (!evolute) {
            __m256d L = _mm256_sqrt_pd(L2);
            __m256d g = _mm256_sub_pd(_mm256_sub_pd(_mm256_mul_pd(Dx, uy), _mm256_mul_pd(Dy, ux)),
                                      _mm256_mul_pd(vd, L));
            f = _mm256_mul_pd(g, _mm256_sub_pd(one, _mm256_div_pd(_mm256_mul_pd(vd, c),
                                                               _mm256_mul_pd(L2, L))));
        } else {
            __m256d cp =
                _mm256_mul_pd(six, _mm256_sub_pd(_mm256_mul_pd(ux, b3y), _mm256_mul_pd(uy, b3x)));
            __m256d dd = _mm256_add_pd(_mm256_mul_pd(ux, vx), _mm256_mul_pd(uy, vy));
            __m256d num =
                _mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(three, dd), c), _mm256_mul_pd(L2, cp));
            f = _mm256_div_pd(
                _mm256_mul_pd(num, _mm256_add_pd(_mm256_mul_pd(Dx, ux), _mm256_mul_pd(Dy, uy))),
                _mm256_mul_pd(c, c));
        }
        sum = _mm256_add_pd(sum, _mm256_mul_pd(w, f));
    }
    __m128d s2 = _mm_add_pd(_mm256_castpd256_pd128(sum), _mm256_extractf128_pd(sum, 1));
    return _mm_cvtsd_f64(_mm_add_sd(s2, _mm_unpackhi_pd(s2, s2)));
}

/* w f at the eight nodes qx[0..7] (weights qw; the lanes outside `mask`
 * load x = w = 0, their w f not used) in AVX-512F's eight lanes: each
 * lane the operations of nodes_avx_k's in their order (nothing fused:
 * target avx512f includes FMA, but the file is built without contraction,
 * -std=c11), so each w f the same double */
__attribute__((target("avx512f"), always_inline)) static inline __m512d
wf_512(const double *qx, const double *qw, __mmask8 mask, double sm, double h,
       const double *bx, const double *by, const double *d, double ax, double ay,
       const int evolute)
{
    const __m512d vsm = _mm512_set1_pd(sm), vh = _mm512_set1_pd(h);
    const __m512d b1x = _mm512_set1_pd(bx[1]), b2x = _mm512_set1_pd(bx[2]);
    const __m512d b3x = _mm512_set1_pd(bx[3]), b1y = _mm512_set1_pd(by[1]);
    const __m512d b2y = _mm512_set1_pd(by[2]), b3y = _mm512_set1_pd(by[3]);
    const __m512d b2x2 = _mm512_add_pd(b2x, b2x), b2y2 = _mm512_add_pd(b2y, b2y);
    const __m512d three = _mm512_set1_pd(3.0), six = _mm512_set1_pd(6.0);
    const __m512d one = _mm512_set1_pd(1.0), vd = _mm512_set1_pd(*d);
    const __m512d vax = _mm512_set1_pd(ax), vay = _mm512_set1_pd(ay);
    __m512d x = _mm512_maskz_loadu_pd(mask, qx), w = _mm512_maskz_loadu_pd(mask, qw);
    __m512d s = _mm512_add_pd(vsm, _mm512_mul_pd(vh, x));
    __m512d s3 = _mm512_mul_pd(three, s), s6 = _mm512_mul_pd(six, s);
    __m512d ux = _mm512_add_pd(b1x, _mm512_mul_pd(s, _mm512_add_pd(b2x2, _mm512_mul_pd(s3, b3x))));
    __m512d uy = _mm512_add_pd(b1y, _mm512_mul_pd(s, _mm512_add_pd(b2y2, _mm512_mul_pd(s3, b3y))));
    __m512d vx = _mm512_add_pd(b2x2, _mm512_mul_pd(s6, b3x));
    __m512d vy = _mm512_add_pd(b2y2, _mm512_mul_pd(s6, b3y));
    __m512d Dx = _mm512_sub_pd(
        _mm512_mul_pd(
            s, _mm512_add_pd(b1x, _mm512_mul_pd(s, _mm512_add_pd(b2x, _mm512_mul_pd(s, b3x))))),
        vax);
    __m512d Dy = _mm512_sub_pd(
        _mm512_mul_pd(
            s, _mm512_add_pd(b1y, _mm512_mul_pd(s, _mm512_add_pd(b2y, _mm512_mul_pd(s, b3y))))),
        vay);
    __m512d L2 = _mm512_add_pd(_mm512_mul_pd(ux, ux), _mm512_mul_pd(uy, uy));
    __m512d c = _mm512_sub_pd(_mm512_mul_pd(ux, vy), _mm512_mul_pd(uy, vx)), f;
    if (!evolute) {
        __m512d L = _mm512_sqrt_pd(L2);
        __m512d g = _mm512_sub_pd(_mm512_sub_pd(_mm512_mul_pd(Dx, uy), _mm512_mul_pd(Dy, ux)),
                                  _mm512_mul_pd(vd, L));
        f = _mm512_mul_pd(g, _mm512_sub_pd(one, _mm512_div_pd(_mm512_mul_pd(vd, c),
                                                           _mm512_mul_pd(L2, L))));
    } else {
        __m512d cp =
            _mm512_mul_pd(six, _mm512_sub_pd(_mm512_mul_pd(ux, b3y), _mm512_mul_pd(uy, b3x)));
        __m512d dd = _mm512_add_pd(_mm512_mul_pd(ux, vx), _mm512_mul_pd(uy, vy));
        __m512d num =
            _mm512_sub_pd(_mm512_mul_pd(_mm512_mul_pd(three, dd), c), _mm512_mul_pd(L2, cp));
        f = _mm512_div_pd(
            _mm512_mul_pd(num, _mm512_add_pd(_mm512_mul_pd(Dx, ux), _mm512_mul_pd(Dy, uy))),
            _mm512_mul_pd(c, c));
    }
    return _mm512_mul_pd(w, f);
}

/* nodes_avx_k's sum with eight nodes a pass (wf_512) where n >= 8: lane j
 * of the four, (((0 + wf_j) + wf_j+4) + wf_j+8) + wf_j+12, as the low and
 * high halves of the passes added in turn, then (0 + 2) + (1 + 3): the
 * same operations on the same numbers as nodes_avx_k's, so the same sum
 * bit for bit (test_area_offset's test_nodes); below 8 points (no rule of
 * ar_quad_order's now) four lanes, a guard */
__attribute__((target("avx512f"), always_inline)) static inline double
nodes_512_k(const double *qx, const double *qw, int n, double sm, double h,
            const double *bx, const double *by, const double *d, double ax, double ay,
            const int evolute)
{
    if (n < 8)
        return nodes_avx_k(qx, qw, n, sm, h, bx, by, d, ax, ay, evolute);
    __m512d a = wf_512(qx, qw, 0xff, sm, h, bx, by, d, ax, ay, evolute);
    __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_setzero_pd(), _mm512_castpd512_pd256(a)),
                                _mm512_extractf64x4_pd(a, 1));
    const int n4 = (n + 3) & ~3; /* the table's padded count */
    for (int i = 8; i < n4; i += 8) {
        a = wf_512(qx + i, qw + i, n4 - i < 8 ? 0x0f : 0xff, sm, h, bx, by, d, ax, ay, evolute);
        sum = _mm256_add_pd(sum, _mm512_castpd512_pd256(a));
        if (n4 - i >= 8)
            sum = _mm256_add_pd(sum, _mm512_extractf64x4_pd(a, 1));
    }
    __m128d s2 = _mm_add_pd(_mm256_castpd256_pd128(sum), _mm256_extractf128_pd(sum, 1));
    return _mm_cvtsd_f64(_mm_add_sd(s2, _mm_unpackhi_pd(s2, s2)));
}

/* nodes_512_k for an offset or an evolute */
__attribute__((target("avx512f"))) static double
nodes_512(const double *qx, const double *qw, int n, double sm, double h,
          const double *bx, const double *by, const double *d, double ax, double ay, int evolute)
{
    if (evolute)
        return nodes_512_k(qx, qw, n, sm, h, bx, by, d, ax, ay, 1);
    return nodes_512_k(qx, qw, n, sm, h, bx, by, d, ax, ay, 0);
}

/* nodes_avx_k for an offset or an evolute (a loop each) */
__attribute__((target("avx"))) static double
nodes_avx(const double *qx, const double *qw, int n, double sm, double h,
          const double *bx, const double *by, const double *d, double ax, double ay, int evolute)
{
    if (evolute)
        return nodes_avx_k(qx, qw, n, sm, h, bx, by, d, ax, ay, 1);
    return nodes_avx_k(qx, qw, n, sm, h, bx, by, d, ax, ay, 0);
}

/* The 8 points' test of rule_or_none without z's division and square
 * root, where it can tell: 1 where the 8 points' bound surely holds (the
 * exact test says 8 too, so the rule is the same), 0 where it cannot
 * tell; t = h K M, K = 64 (1 + 1e-12) / (15 AR_QUAD_TOL) (the exact test's
 * product, the same operations).  With a = Rs^2, b = h^2, z^2 = a/b:
 * sqrt(z^2 - 1) >= z - 1/z (the right side's square is z^2 - 2 + 1/z^2),
 * so r2 = rho^2 = 2 z^2 - 1 + 2 z sqrt(z^2 - 1) >= 4 z^2 - 3 and r2 - 1 >=
 * 4 (z^2 - 1); the exact test's r2^7 (r2 - 1) >= t then follows from
 *
 *     (4a - 3b)^7 4 (a - b) >= b^8 t,
 *
 * all positive where Rs > h, no division; 4a - 3b = 4X + b, X = a - b =
 * (Rs - h)(Rs + h), a sum of positives, so neither side cancels.  Rounding
 * (u the unit in the last place, 2^-53): the left side within a relative
 * 40 u of its value, the right 20 u.  At z = 2 the left side over b^8 is
 * 13^7 12 < 2^30, so t >= 2^30 makes z > 2 where this test passes, and
 * there the exact test's z - 1 does not cancel either: its left side within
 * 110 u, its right 15 u (a guard of the proof: near z = 1 this test's bound
 * is looser than the exact one by far more than that rounding, and no test
 * tells the guard apart).  The left side times 1 - 1e-12 (about 9,000 u)
 * covers the four, so the exact test's rounded sides pass wherever these
 * do.  With 2^-24 <= h < Rs <= 2^20 the powers stay finite and b^8 t
 * normal (b^8 within 2^-384 and 2^320, the left side, at most (4a -
 * 3b)^8, at most 2^336); where the left side underflows or b^8 t
 * overflows, this test fails, as it should.  Outside those (and for a NaN)
 * the exact test decides.  On the stroke benchmark it decides 83,832 of
 * the 83,961 shares a render that take 8 points at 1024 px, 15,990 of
 * 16,098 at 256 px. */
/* t = h K M of a share of half width h in panel p, K = 64 (1 + 1e-12) /
 * (15 AR_QUAD_TOL): the product both tests compare against */
static __attribute__((always_inline)) inline double rule_t(const ar_panel *p, double h)
{
    return h * (64.0 / (15.0 * AR_QUAD_TOL) * (1.0 + 1e-12)) * p->M;
}

static __attribute__((always_inline)) inline int rule8_sure(double Rs, double h, double t)
{
    if (!(t >= 0x1p30 && h >= 0x1p-24 && Rs <= 0x1p20))
        return 0;
    double X = (Rs - h) * (Rs + h), b = h * h, Y = 4.0 * X + b;
    double y2 = Y * Y, y4 = y2 * y2, b4 = (b * b) * (b * b);
    return (y4 * (y2 * Y)) * ((4.0 * (1.0 - 1e-12)) * X) >= (b4 * b4) * t;
}

/* The rule a share of half width h about mm inside panel p takes (an
 * index into ar_quad): the fewest points whose bound is within
 * AR_QUAD_TOL; the panel's own (the last) where its disc leaves no room
 * (rule; rule_or_none: -1 there, the last where the two before it fail,
 * which a share inside the panel may take, its bound at most the panel's,
 * but one reaching past the panel may not: segment). */
static __attribute__((always_inline)) inline int rule_or_none(const ar_panel *p, double h,
                                                              double mm)
{
    int r = -1;
    double Rs = p->R - fabs(mm - p->m);
    if (Rs > h && p->M > 0.0) {
        r = AR_QUAD_RULES - 1;
        /* the fewest points n with h 64 M / (15 (1 - rho^-2) rho^(2n)) <=
         * AR_QUAD_TOL, as r2^n (r2 - 1) >= h K r2, r2 = rho^2, K = 64 M
         * (1 + 1e-12) / (15 AR_QUAD_TOL): no division but z's, the powers
         * by products (no logarithms: two a share were a tenth of its
         * time) in the same order whatever the share, written out (a
         * loop's own instructions were a third of the choice's); their
         * rounding (a few units in the last place) within the 1e-12
         * margin.  The orders 8, 12 (ar_quad_order): r2^4 apart, r2^8
         * (r2 - 1) as (r2^4 (r2 - 1)) r2^4.  8 points first by rule8_sure
         * where it can tell (the same rule, without z's division and
         * square root, whose chain the share waited on). */
        double t = rule_t(p, h);
        if (rule8_sure(Rs, h, t))
            return 0;
        double z = Rs / h, rho = z + sqrt((z - 1.0) * (z + 1.0)), r2 = rho * rho;
        double need = t * r2;
        double p4 = r2 * r2 * (r2 * r2), pw = p4 * (r2 - 1.0) * p4;
        if (pw >= need)
            r = 0;
        else if ((pw = pw * p4) >= need)
            r = 1;
    }
    return r;
}

static __attribute__((always_inline)) inline int rule(const ar_panel *p, double h, double mm)
{
    int r = rule_or_none(p, h, mm);
    return r < 0 ? AR_QUAD_RULES - 1 : r;
}

int area_offset_rule(const ar_panel *p, double al, double be)
{
    double h = 0.5 * (be - al), mm = 0.5 * (al + be);
    return h > 0.0 ? rule(p, h, mm) : AR_QUAD_RULES - 1;
}

int area_offset_rule_sure(const ar_panel *p, double al, double be)
{
    double h = 0.5 * (be - al), mm = 0.5 * (al + be), Rs = p->R - fabs(mm - p->m);
    if (!(h > 0.0 && Rs > h && p->M > 0.0))
        return 0;
    return rule8_sure(Rs, h, rule_t(p, h));
}

/* 1/2 the integral of (P - P(al)) x P' over [al, be] inside panel p, in
 * the curve's own units, by the fewest points whose bound holds; `avx` (a
 * constant where it is inlined, area_offset_segment's choice): a cubic's
 * nodes eight a pass (nodes_512) where it is 2, four at a time (nodes_avx,
 * then inline) where 1, else two. */
static __attribute__((always_inline)) inline double share_by(const ar_piece *pc,
                                                             const ar_panel *p, double al,
                                                             double be, double ax, double ay,
                                                             const int r, const int avx)
{
    const aa_offset_curve *oc = &pc->src->oc;
    const ar_quad *q = pc->quad;
    double h = 0.5 * (be - al), mm = 0.5 * (al + be);
    const double *bx = p->bx, *by = p->by, d = oc->d;
    double sum = 0.0;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        double J = bx[1] * by[2] - by[1] * bx[2];
        for (int i = 0; i < q->n[r]; i++) {
            double s = mm + h * q->x[q->at[r] + i] - p->m;
            double h2 = sin(0.5 * s), c1 = -2.0 * h2 * h2, sn = sin(s), cs = 1.0 + c1;
            double ux = -bx[1] * sn + bx[2] * cs, uy = -by[1] * sn + by[2] * cs;
            double Dx = bx[1] * c1 + bx[2] * sn - ax, Dy = by[1] * c1 + by[2] * sn - ay;
            double L2 = ux * ux + uy * uy, f;
            if (!oc->evolute) {
                double L = sqrt(L2);
                f = (Dx * uy - Dy * ux - d * L) * (1.0 - d * J / (L2 * L));
            } else {
                double vx = -(bx[1] * cs + bx[2] * sn), vy = -(by[1] * cs + by[2] * sn);
                f = 3 * (ux * vx + uy * vy) * (Dx * ux + Dy * uy) / J;
            }
            sum += q->w[q->at[r] + i] * f;
        }
        return 0.5 * h * sum;
    }
    if (p->stop) {
        const double *qs = p->q, te = p->te, sg = te == 0 ? 1 : -1;
        for (int i = 0; i < q->n[r]; i++) {
            double t = mm + h * q->x[q->at[r] + i], s = t - p->m;
            double Dx = s * (bx[1] + s * (bx[2] + s * bx[3])) - ax;
            double Dy = s * (by[1] + s * (by[2] + s * by[3])) - ay;
            double Qx = qs[0] + qs[1] * t, Qy = qs[2] + qs[3] * t, q2 = Qx * Qx + Qy * Qy;
            double X = Qx * qs[3] - Qy * qs[1], f;
            if (!oc->evolute) {
                double lq = sqrt(q2);
                f = (Dx * Qy - Dy * Qx - d * sg * lq) * (t - te - d * sg * X / (q2 * lq));
            } else {
                f = (Dx * Qx + Dy * Qy) * (q2 + 3 * (t - te) * (Qx * qs[1] + Qy * qs[3])) / X;
            }
            sum += q->w[q->at[r] + i] * f;
        }
        return 0.5 * h * sum;
    }
    /* Two nodes at a time (SSE2), the pairs' sums in two accumulators
     * taken in turn, so that each of the four lanes sums the nodes AVX's
     * lane does (nodes_avx), in its order, padding and all; each lane the
     * same operations in the same order as one node's scalar expression,
     * with sqrt and the divisions correctly rounded in both, so each w f
     * is the same double.  The lanes then added as (0 + 2) + (1 + 3), the
     * sum the same bit for bit in both forms (test_area_offset's
     * test_nodes). */
    const int n = q->n[r];
    const double *qx = q->x + q->at[r], *qw = q->w + q->at[r];
    if (avx == 2) {
        sum = nodes_512(qx, qw, n, mm - p->m, h, bx, by, &oc->d, ax, ay, oc->evolute);
        return 0.5 * h * sum;
    }
    if (avx) {
        sum = nodes_avx(qx, qw, n, mm - p->m, h, bx, by, &oc->d, ax, ay, oc->evolute);
        return 0.5 * h * sum;
    }
    const __m128d vsm = _mm_set1_pd(mm - p->m), vh = _mm_set1_pd(h);
    const __m128d b1x = _mm_set1_pd(bx[1]), b2x = _mm_set1_pd(bx[2]), b3x = _mm_set1_pd(bx[3]);
    const __m128d b1y = _mm_set1_pd(by[1]), b2y = _mm_set1_pd(by[2]), b3y = _mm_set1_pd(by[3]);
    const __m128d b2x2 = _mm_set1_pd(2 * bx[2]), b2y2 = _mm_set1_pd(2 * by[2]);
    const __m128d three = _mm_set1_pd(3.0), six = _mm_set1_pd(6.0);
    const __m128d one = _mm_set1_pd(1.0), vd = _mm_set1_pd(d);
    const __m128d vax = _mm_set1_pd(ax), vay = _mm_set1_pd(ay);
    __m128d sum2[2] = {_mm_setzero_pd(), _mm_setzero_pd()};
    for (int i = 0; i < ((n + 3) & ~3); i += 2) {
        __m128d x = _mm_loadu_pd(qx + i), w = _mm_loadu_pd(qw + i);
        __m128d s = _mm_add_pd(vsm, _mm_mul_pd(vh, x));
        __m128d s3 = _mm_mul_pd(three, s), s6 = _mm_mul_pd(six, s);
        __m128d ux = _mm_add_pd(b1x, _mm_mul_pd(s, _mm_add_pd(b2x2, _mm_mul_pd(s3, b3x))));
        __m128d uy = _mm_add_pd(b1y, _mm_mul_pd(s, _mm_add_pd(b2y2, _mm_mul_pd(s3, b3y))));
        __m128d vx = _mm_add_pd(b2x2, _mm_mul_pd(s6, b3x));
        __m128d vy = _mm_add_pd(b2y2, _mm_mul_pd(s6, b3y));
        __m128d Dx = _mm_sub_pd(
            _mm_mul_pd(s, _mm_add_pd(b1x, _mm_mul_pd(s, _mm_add_pd(b2x, _mm_mul_pd(s, b3x))))),
            vax);
        __m128d Dy = _mm_sub_pd(
            _mm_mul_pd(s, _mm_add_pd(b1y, _mm_mul_pd(s, _mm_add_pd(b2y, _mm_mul_pd(s, b3y))))),
            vay);
        __m128d L2 = _mm_add_pd(_mm_mul_pd(ux, ux), _mm_mul_pd(uy, uy));
        __m128d c = _mm_sub_pd(_mm_mul_pd(ux, vy), _mm_mul_pd(uy, vx)), f;
        if (!oc->evolute) {
            /* (Dx uy - Dy ux - d L) (1 - d c / (L2 L)) */
            __m128d L = _mm_sqrt_pd(L2);
            __m128d g = _mm_sub_pd(_mm_sub_pd(_mm_mul_pd(Dx, uy), _mm_mul_pd(Dy, ux)),
                                   _mm_mul_pd(vd, L));
            f = _mm_mul_pd(g, _mm_sub_pd(one, _mm_div_pd(_mm_mul_pd(vd, c),
                                                         _mm_mul_pd(L2, L))));
        } else {
            /* (3 dd c - L2 cp) (Dx ux + Dy uy) / (c c), cp = 6 (ux by3 - uy bx3) */
            __m128d cp = _mm_mul_pd(six, _mm_sub_pd(_mm_mul_pd(ux, b3y), _mm_mul_pd(uy, b3x)));
            __m128d dd = _mm_add_pd(_mm_mul_pd(ux, vx), _mm_mul_pd(uy, vy));
            __m128d num = _mm_sub_pd(_mm_mul_pd(_mm_mul_pd(three, dd), c), _mm_mul_pd(L2, cp));
            f = _mm_div_pd(_mm_mul_pd(num, _mm_add_pd(_mm_mul_pd(Dx, ux), _mm_mul_pd(Dy, uy))),
                           _mm_mul_pd(c, c));
        }
        sum2[(i >> 1) & 1] = _mm_add_pd(sum2[(i >> 1) & 1], _mm_mul_pd(w, f));
    }
    __m128d s2 = _mm_add_pd(sum2[0], sum2[1]);
    sum = _mm_cvtsd_f64(_mm_add_sd(s2, _mm_unpackhi_pd(s2, s2)));
    return 0.5 * h * sum;
}

/* The point (x0 + u, y0 + v) of the image (the row's: x0 and y0 its
 * cell's corner, u and v in the cell), less panel p's B(m), in the curve's
 * own coordinates: the difference in the image from B(m)'s hi + lo
 * (image_point), then the map's inverse (det: the map's determinant).
 * Its rounding: a few units in the last place of the difference, B(m)'s
 * own in long double (about 1e-19 of the image's coordinate: 1e-16 px at
 * 1024 px, 1e-13 px a million px from the origin), and the inverse's,
 * which grows with the map's condition number: area takes the row's point
 * only where that is at most 4 and long double is wider than double
 * (ar_piece's rowpt), else passes none (rel_point's start). */
static __attribute__((always_inline)) inline void start_at(const aa_offset_curve *oc,
                                                           const ar_panel *p, double det,
                                                           double x0, double u, double y0,
                                                           double v, double *ax, double *ay)
{
    double ex = ((x0 - p->qx[0]) + u) - p->qx[1], ey = ((y0 - p->qy[0]) + v) - p->qy[1];
    const double *m = oc->m;
    *ax = (m[3] * ex - m[2] * ey) / det;
    *ay = (m[0] * ey - m[1] * ex) / det;
}

static __attribute__((always_inline)) inline double segment(const ar_piece *pc, double ta,
                                                            double tb, double px, double u,
                                                            double py, double v, const int avx)
{
    double lo = ta < tb ? ta : tb, hi = ta < tb ? tb : ta;
    if (!(hi > lo))
        return 0.0;
    const aa_offset_curve *oc = &pc->src->oc;
    const double det = oc->m[0] * oc->m[3] - oc->m[2] * oc->m[1];
    const ar_panel *pan = pc->pan;
    /* the last panel starting at or before lo (the first if none): among
     * a few, the first ending after it, in order (loads the processor
     * issues ahead, where a halving's wait on each), else by halving */
    size_t n = pc->npan, k = 0, top = n;
    if (n <= 8) {
        while (k + 1 < n && pan[k].b <= lo)
            k++;
    } else {
        while (k + 1 < top) {
            size_t mid = (k + top) / 2;
            if (pan[mid].a <= lo)
                k = mid;
            else
                top = mid;
        }
    }
    double seg, ax, ay;
    int r;
    if (hi <= pan[k].b || k + 1 == n) {
        /* one share, about the point given where there is one (the
         * integral about P(tb) the same as about P(ta): (P(tb) - P(ta)) x
         * (P(tb) - P(ta)) = 0) */
        double h = 0.5 * (hi - lo), mm = 0.5 * (lo + hi);
        seg = 0.0;
        if (h > 0.0) {
            if (u == u)
                start_at(oc, &pan[k], det, px, u, py, v, &ax, &ay);
            else
                rel_point(oc, &pan[k], lo, &ax, &ay);
            seg = share_by(pc, &pan[k], lo, hi, ax, ay, rule(&pan[k], h, mm), avx);
        }
    } else if ((r = rule_or_none(&pan[k], 0.5 * (hi - lo), 0.5 * (lo + hi))) >= 0 &&
               r < AR_QUAD_RULES - 1 &&
               !(u == u && ta > tb && (ta == pc->ot0 || ta == pc->ot1))) {
        /* a part reaching past its first panel whose Bernstein ellipse
         * still lies in that panel's disc, where M bounds the integrand
         * for start points on the panel (the panel's Taylor form is the
         * curve's everywhere): one share, its rule's bound met (8 or 12
         * points; the 16 of a share inside a panel hold by the panel's
         * own bound, which this one's is not under); about the point
         * given at lo, else about P(lo), the same as about P(hi) (a point
         * given at hi is off the panel; at the piece's end, the outline's
         * vertex, off the curve: the polygon below) */
        if (u == u && ta < tb)
            start_at(oc, &pan[k], det, px, u, py, v, &ax, &ay);
        else
            rel_point(oc, &pan[k], lo, &ax, &ay);
        seg = share_by(pc, &pan[k], lo, hi, ax, ay, r, avx);
    } else {
        /* shares joined by the polygon of their ends about P(lo), or
         * about the point given where ta is the piece's end (the
         * outline's vertex Q, off the curve: the polygon's edges (P_k - Q)
         * x (P_k+1 - P_k) / 2 hold about any Q), the ends relative to the
         * first panel's B(m): each share's start relative to its own
         * panel's plus the two B(m) apart, the part's end by the first
         * panel's form (a cubic's Taylor form and an ellipse's form about m
         * are exact everywhere) */
        const ar_panel *p0 = &pan[k];
        double x0, y0, xa, ya, xb, yb;
        rel_point(oc, p0, lo, &ax, &ay);
        x0 = xa = ax, y0 = ya = ay;
        if (u == u && (ta == pc->ot0 || ta == pc->ot1))
            start_at(oc, p0, det, px, u, py, v, &x0, &y0);
        seg = 0.0;
        for (double al = lo; k < n && al < hi; k++) {
            double be = k + 1 < n && pan[k].b < hi ? pan[k].b : hi;
            double h = 0.5 * (be - al), mm = 0.5 * (al + be);
            if (h > 0.0)
                seg += share_by(pc, &pan[k], al, be, ax, ay, rule(&pan[k], h, mm), avx);
            if (be < hi) /* the next share's start, relative to its panel's B(m) */
                rel_point(oc, &pan[k + 1], be, &ax, &ay);
            if (be < hi && pc->rowpt) {
                /* the vertex: that start, relative to the first panel's
                 * B(m) by the two B(m) in the image */
                const ar_panel *q = &pan[k + 1];
                double dx = (q->qx[0] - p0->qx[0]) + (q->qx[1] - p0->qx[1]);
                double dy = (q->qy[0] - p0->qy[0]) + (q->qy[1] - p0->qy[1]);
                const double *m = oc->m;
                xb = ax + (m[3] * dx - m[2] * dy) / det;
                yb = ay + (m[0] * dy - m[1] * dx) / det;
            } else {
                /* the part's end, or the map's inverse not trusted
                 * (ar_piece's rowpt): by the first panel's form */
                rel_point(oc, p0, be, &xb, &yb);
            }
            seg += 0.5 * ((xa - x0) * (yb - ya) - (ya - y0) * (xb - xa));
            xa = xb, ya = yb, al = be;
        }
    }
    return ta < tb ? det * seg : -det * seg;
}

/* segment compiled for AVX, flattened (its shares, start points and nodes
 * inline: no call of 13 arguments a share; its scalar arithmetic the same
 * operations, VEX-encoded: the same numbers) and without, chosen once a
 * part by the processor (ar_quad's avx: 1; 2 takes segment_512, its
 * AVX-512F form, below); segment_sse out of line (inlined into
 * area_offset_segment, its register saves came before the choice) */
__attribute__((target("avx"), flatten)) static double
segment_avx(const ar_piece *pc, double ta, double tb, double x0, double u, double y0, double v)
{
    return segment(pc, ta, tb, x0, u, y0, v, 1);
}

/* segment_avx with AVX-512F's eight lanes (nodes_512) */
__attribute__((target("avx512f"), flatten)) static double
segment_512(const ar_piece *pc, double ta, double tb, double x0, double u, double y0, double v)
{
    return segment(pc, ta, tb, x0, u, y0, v, 2);
}

__attribute__((noinline)) static double segment_sse(const ar_piece *pc, double ta, double tb,
                                                    double x0, double u, double y0, double v)
{
    return segment(pc, ta, tb, x0, u, y0, v, 0);
}

double area_offset_segment_at(const ar_piece *pc, double ta, double tb, double x0, double u,
                              double y0, double v)
{
    int avx = pc->quad->avx;
    return avx == 2 ? segment_512(pc, ta, tb, x0, u, y0, v)
           : avx    ? segment_avx(pc, ta, tb, x0, u, y0, v)
                    : segment_sse(pc, ta, tb, x0, u, y0, v);
}

double area_offset_segment(const ar_piece *pc, double ta, double tb)
{
    return area_offset_segment_at(pc, ta, tb, 0.0, NAN, 0.0, 0.0);
}

/* ---- the speed of the curve on a disc (for `analytic`) ----
 *
 * A bound on |P'| (the Euclidean norm of the complex vector, unmapped: the
 * curve's own coordinates) on the disc |t - m| <= R, from the same Taylor
 * sums as panel_M's factors, in the form aa__offset_eval takes at m:
 *  - offset of a cubic: P' = B' (1 - d c/L^3), at most
 *    |B'| (1 + |d| |c| / lo^(3/2)), lo the lower bound of |L^2|;
 *  - evolute of a cubic: E' = (3 (B'.B'') c - L^2 c')/c^2 perp(B'), at most
 *    (3 |B'.B''| |c| + |L^2| |c'|) |B'| / cl^2, cl the lower bound of |c|;
 *  - the ellipse's: c = J constant, c' = 0, |B'| <= |u'| sinh R + |v'|
 *    cosh R, |B'.B''| as in panel_M_ellipse;
 *  - the factored form about a stop te (sd = |m - te| + R): the offset's
 *    P' = (t - te - d sg X/|Q|^3) Q, at most (sd + |d| |X| / lo^(3/2))
 *    |Q|, lo the lower bound of |Q|^2; the evolute's E' = (|Q|^2 + 3 (t -
 *    te) (Q . Q')) perp(Q)/X; where X = 0 (straight next to te) P' = (t -
 *    te) Q.
 * Where a lower bound is not positive the disc may hold a zero of a
 * denominator (or of L^2, whose square root then has no analytic branch):
 * INFINITY, and the larger discs after it too. */
void area_offset_speed(const aa_offset_curve *oc, double m, int n, const double *R, double *V)
{
    double bx[4] = {0}, by[4] = {0}, te = 0.0, q[4] = {0.0, 0.0, 0.0, 0.0};
    int ell = oc->base == AA_OFFSET_ELLIPSE, stop = aa__offset_stop(oc, m, &te, q), dead = 0;
    double up[2], vp[2];
    if (ell)
        ellipse_at(oc, m, up, vp);
    else
        taylor(oc, m, bx, by);
    double ux[3], uy[3], vx[2], vy[2], L2[5], t1[5], c[4], t2[4], dd[4], cp[3];
    speed_polys(bx, by, ux, uy, vx, vy, L2, c);
    pmul(ux, 3, vx, 2, dd);
    pmul(uy, 3, vy, 2, t2);
    for (int k = 0; k < 4; k++)
        dd[k] += t2[k];
    for (int k = 0; k < 3; k++)
        cp[k] = ux[k] * 6 * by[3] - uy[k] * 6 * bx[3];
    double Qx[2] = {q[0] + q[1] * m, q[1]}, Qy[2] = {q[2] + q[3] * m, q[3]};
    double Q2[3] = {0.0, 0.0, 0.0}, QQ[2] = {0.0, 0.0};
    if (stop) {
        pmul(Qx, 2, Qx, 2, Q2);
        pmul(Qy, 2, Qy, 2, t1);
        for (int k = 0; k < 3; k++)
            Q2[k] += t1[k];
        QQ[0] = Qx[0] * q[1] + Qy[0] * q[3], QQ[1] = q[1] * q[1] + q[3] * q[3];
    }
    const double d = fabs(oc->d);
    for (int k = 0; k < n; k++) {
        double r = R[k], v = INFINITY;
        if (dead) {
            V[k] = INFINITY;
            continue;
        }
        if (ell) {
            double ch = cosh(r), sh = sinh(r);
            double uu = up[0] * up[0] + up[1] * up[1], vv = vp[0] * vp[0] + vp[1] * vp[1];
            double uv = fabs(up[0] * vp[0] + up[1] * vp[1]);
            double J = fabs(up[0] * vp[1] - up[1] * vp[0]);
            double Uu = sqrt(uu) * sh + sqrt(vv) * ch;
            double lo = vv - (fabs(uu - vv) * sh * sh + 2.0 * uv * sh * ch);
            if (J > 0.0 && lo > 0.0) {
                if (!oc->evolute)
                    v = Uu * (1.0 + d * J / (lo * sqrt(lo)));
                else
                    v = 3.0 * (fabs(uu - vv) * sh * ch + uv * (sh * sh + ch * ch)) * Uu / J;
            }
        } else if (stop) {
            double X = fabs(Qx[0] * q[3] - Qy[0] * q[1]), sd = fabs(m - te) + r;
            double Qmax = sqrt(pabs(Q2, 3, 0, r)), lo = plow(Q2, 3, r);
            if (X == 0.0)
                v = sd * Qmax;
            else if (!oc->evolute && lo > 0.0)
                v = (sd + d * X / (lo * sqrt(lo))) * Qmax;
            else if (oc->evolute)
                v = (pabs(Q2, 3, 0, r) + 3 * sd * pabs(QQ, 2, 0, r)) * Qmax / X;
        } else {
            double Uu = hypot(pabs(ux, 3, 0, r), pabs(uy, 3, 0, r));
            if (!oc->evolute) {
                double lo = plow(L2, 5, r);
                if (lo > 0.0)
                    v = Uu * (1.0 + d * pabs(c, 4, 0, r) / (lo * sqrt(lo)));
            } else {
                double cl = plow(c, 4, r);
                if (cl > 0.0)
                    v = (3 * pabs(dd, 4, 0, r) * pabs(c, 4, 0, r) +
                         pabs(L2, 5, 0, r) * pabs(cp, 3, 0, r)) *
                        Uu / (cl * cl);
            }
        }
        V[k] = v * (1.0 + 1e-12); /* the bound's own rounding */
        dead = !(v < INFINITY);
    }
}
