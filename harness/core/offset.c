/*
 * offset.c: offset curves and evolutes of cubic Bezier arcs (aabench.h,
 * aa_offset_curve), the exact boundaries of a Bezier arc's stroke: their
 * points and derivatives, the turns of either coordinate, and the one root
 * of a coordinate on a part where it is monotone.
 *
 * With B' = B'(t), B'' and B''' its derivatives, L = |B'|, the unit normal
 * N = (-B'y, B'x)/L and the curvature k = c/L^3, c = B' x B'':
 *  - the offset P = B + d N has P' = B' (1 - d k) (N' = -k L T, T = B'/L):
 *    parallel to B', vanishing only where d k = 1 (a fold of the offset);
 *  - the evolute E = B + N/k = B + N L^3/c has E' = (1/k)' N, with
 *        (1/k)' = L (3 (B' . B'') c - L^2 c') / c^2,  c' = B' x B''',
 *    which vanishes at the extremes of the curvature (cusps of E).
 * So on a part without folds (offsets) or curvature extremes (evolutes) the
 * turns of a coordinate of m(P) are those of m(B') (a quadratic in t), and
 * of m(E) those of m(N) L (a quadratic), in closed form.  Everything is
 * evaluated in long double.
 */
#include "core.h"

#include <float.h>
#include <math.h>

void aa__offset_eval(const aa_offset_curve *oc, long double t, long double *x, long double *y,
                     long double *dx, long double *dy)
{
    const double *b = oc->b, *m = oc->m;
    long double bx = b[0] + t * (b[1] + t * (b[2] + t * (long double)b[3]));
    long double by = b[4] + t * (b[5] + t * (b[6] + t * (long double)b[7]));
    long double ux = b[1] + t * (2 * b[2] + 3 * t * (long double)b[3]);
    long double uy = b[5] + t * (2 * b[6] + 3 * t * (long double)b[7]);
    long double vx = 2 * b[2] + 6 * t * (long double)b[3];
    long double vy = 2 * b[6] + 6 * t * (long double)b[7];
    long double L = sqrtl(ux * ux + uy * uy), c = ux * vy - uy * vx;
    long double px, py, qx, qy; /* the point and its derivative, unmapped */
    if (!oc->evolute) {
        long double k = c / (L * L * L), f = 1 - oc->d * k;
        px = bx - oc->d * uy / L;
        py = by + oc->d * ux / L;
        qx = ux * f;
        qy = uy * f;
    } else {
        long double wx = 6 * (long double)b[3], wy = 6 * (long double)b[7];
        long double cp = ux * wy - uy * wx, dot = ux * vx + uy * vy, L2 = L * L;
        long double r = L2 * L / c; /* 1/k */
        long double rp = L * (3 * dot * c - L2 * cp) / (c * c);
        px = bx - r * uy / L;
        py = by + r * ux / L;
        qx = -rp * uy / L;
        qy = rp * ux / L;
    }
    *x = m[0] * px + m[2] * py + m[4];
    *y = m[1] * px + m[3] * py + m[5];
    if (dx)
        *dx = m[0] * qx + m[2] * qy;
    if (dy)
        *dy = m[1] * qx + m[3] * qy;
}

/* aa__offset_eval in double: the solver's first steps. */
static void eval_d(const aa_offset_curve *oc, double t, double *x, double *y, double *dx,
                   double *dy)
{
    const double *b = oc->b, *m = oc->m;
    double bx = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
    double by = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
    double ux = b[1] + t * (2 * b[2] + 3 * t * b[3]), uy = b[5] + t * (2 * b[6] + 3 * t * b[7]);
    double vx = 2 * b[2] + 6 * t * b[3], vy = 2 * b[6] + 6 * t * b[7];
    double L = sqrt(ux * ux + uy * uy), c = ux * vy - uy * vx, px, py, qx, qy;
    if (!oc->evolute) {
        double f = 1 - oc->d * c / (L * L * L);
        px = bx - oc->d * uy / L, py = by + oc->d * ux / L;
        qx = ux * f, qy = uy * f;
    } else {
        double cp = ux * 6 * b[7] - uy * 6 * b[3], dot = ux * vx + uy * vy, L2 = L * L;
        double r = L2 * L / c, rp = L * (3 * dot * c - L2 * cp) / (c * c);
        px = bx - r * uy / L, py = by + r * ux / L;
        qx = -rp * uy / L, qy = rp * ux / L;
    }
    *x = m[0] * px + m[2] * py + m[4];
    *y = m[1] * px + m[3] * py + m[5];
    *dx = m[0] * qx + m[2] * qy;
    *dy = m[1] * qx + m[3] * qy;
}

void aa_offset_point(const aa_offset_curve *oc, double t, double *x, double *y, double *dx,
                     double *dy)
{
    long double X, Y, DX, DY;
    aa__offset_eval(oc, t, &X, &Y, &DX, &DY);
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

int aa__offset_turns(const aa_offset_curve *oc, int coord, double lo, double hi, double t[2])
{
    const double *b = oc->b;
    /* the row of m for this coordinate: m(v)_coord = ra vx + rb vy */
    double ra = oc->m[coord], rb = oc->m[2 + coord];
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

/* The double phase of aa__offset_solve_from: the root to about 1e-15,
 * the bracket left in *pa, *pb. */
static double solve_double(const aa_offset_curve *oc, int coord, double a, double b, double fa,
                           double tgt, double guess, double *pa, double *pb)
{
    int neg = fa < 0;
    double t = 0.5 * (a + b), prev = fabs(b - a), x, y, dx, dy;
    eval_d(oc, b, &x, &y, &dx, &dy);
    double fb = (coord ? y : x) - tgt;
    if (a < b ? (guess > a && guess < b) : (guess < a && guess > b)) {
        t = guess; /* a caller's start: the last root on a nearby line */
    } else if ((fb < 0) != neg && fb != fa) {
        double r = fa / (fa - fb);
        if (r > 0.01 && r < 0.99)
            t = a + r * (b - a);
    }
    for (int it = 0; it < 100; it++) {
        eval_d(oc, t, &x, &y, &dx, &dy);
        double f = (coord ? y : x) - tgt, df = coord ? dy : dx;
        if (f == 0)
            break;
        if ((f < 0) == neg)
            a = t;
        else
            b = t;
        double mid = 0.5 * (a + b);
        if (!(mid != a && mid != b))
            break;
        double next = df != 0 && isfinite(df) ? t - f / df : mid;
        int inside = a < b ? (next > a && next < b) : (next < a && next > b);
        if (inside && fabs(next - t) <= 1e-15 * fabs(t) + 1e-300) {
            t = next;
            break;
        }
        if (!inside || fabs(next - t) > 0.5 * prev)
            next = mid;
        prev = fabs(next - t);
        t = next;
    }
    *pa = a, *pb = b;
    return t;
}

double aa__offset_solve_d(const aa_offset_curve *oc, int coord, double ta, double tb, double fa,
                          double target)
{
    double a, b;
    if (fa == 0)
        return ta;
    return solve_double(oc, coord, ta, tb, fa, target, NAN, &a, &b);
}

long double aa__offset_solve_from(const aa_offset_curve *oc, int coord, long double ta,
                                  long double tb, long double fa, long double target, double guess)
{
    /* f(t) = coord(t) - target: of the sign of fa at ta, the other at tb
     * (either may be 0).  Newton's method in double from the guess or
     * where the chord meets the target, kept inside the bracket, bisection
     * where a step leaves it or shrinks it too slowly, until a step is
     * within 1e-15; then Newton in long double, still bracketed: a step
     * within 1e-13 is the last (the error after it is of the order of its
     * square), else on until the bracket is two adjacent numbers. */
    if (fa == 0)
        return ta;
    int neg = fa < 0;
    double a, b;
    double t = solve_double(oc, coord, (double)ta, (double)tb, (double)fa, (double)target, guess,
                            &a, &b);
    /* long double: the bracket is [a, b] (as double) or what is left */
    long double la = a, lb = b, lt = t;
    for (int it = 0; it < 8; it++) {
        long double X, Y, DX, DY;
        aa__offset_eval(oc, lt, &X, &Y, &DX, &DY);
        long double f = (coord ? Y : X) - target, df = coord ? DY : DX;
        if (f == 0)
            return lt;
        if ((f < 0) == neg)
            la = lt;
        else
            lb = lt;
        long double mid = 0.5L * (la + lb);
        if (!(mid != la && mid != lb))
            break;
        long double next = df != 0 && isfinite(df) ? lt - f / df : mid;
        int inside = la < lb ? (next >= la && next <= lb) : (next <= la && next >= lb);
        if (!inside)
            next = mid;
        else if (fabsl(next - lt) <= 1e-13L * fabsl(lt) + 1e-30L)
            return next;
        lt = next;
    }
    return lt;
}
