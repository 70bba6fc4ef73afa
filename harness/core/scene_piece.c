/*
 * scene_piece.c: the geometry of one piece, a y-monotone line, parabolic
 * or cubic arc (aabench.h, aa_piece): its x and parameter at a height, its
 * x extent over a band, where it meets a vertical line, and where two
 * pieces meet.  Pure functions of the pieces: no scene is read here.
 *
 * Cubics.  The roots of a cubic polynomial in t on an interval are found
 * robustly, never by the closed form alone: the interval is cut at the
 * roots of the derivative (GSL's quadratic solver), so that the polynomial
 * is monotone on each part; a part whose ends differ in sign holds exactly
 * one root, which is bracketed and polished by Newton's method safeguarded
 * by bisection until the bracket is two adjacent doubles or the value is
 * zero: full double precision.  The parameter at a height is such a root
 * on a y-monotone piece (one part, [0, 1]).
 */
#include "scene_internal.h"

#include <float.h>
#include <gsl/gsl_poly.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* fmax and fmin written out (the library's are calls: about 1.5 million a
 * render of tests/bench_bezstroke.c's scene at 256 px in the meetings),
 * the same values, a NaN argument ignored as theirs are */
static inline double dmax(double a, double b)
{
    return a > b || b != b ? a : b;
}

static inline double dmin(double a, double b)
{
    return a < b || b != b ? a : b;
}

/* ---- roots of cubics ---- */

/* Roots of the derivative k1 + 2 k2 t + 3 k3 t^2 of a cubic's coordinate
 * strictly inside (0, 1), ascending, distinct (GSL's quadratic solver,
 * cancellation-free); returns how many. */
int aa__cubic_turns(double k1, double k2, double k3, double t[2])
{
    double r[2];
    int n = gsl_poly_solve_quadratic(3.0 * k3, 2.0 * k2, k1, &r[0], &r[1]), m = 0;
    for (int k = 0; k < n; k++)
        if (r[k] > 0.0 && r[k] < 1.0 && (m == 0 || r[k] > t[m - 1]))
            t[m++] = r[k];
    return m;
}

static inline double poly3(const double c[4], double t)
{
    return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
}

/* The root of the cubic c in [a, b], where fa = c(a) and fb = c(b) differ in
 * sign and c is monotone: Newton's method kept inside the bracket, bisection
 * where a step would leave it or shrink it too slowly. */
double aa__poly3_bracketed(const double c[4], double a, double b, double fa, double fb)
{
    if (fa == 0.0)
        return a;
    if (fb == 0.0)
        return b;
    double sa = fa < 0.0 ? -1.0 : 1.0;
    double t = a - fa * (b - a) / (fb - fa); /* regula falsi to start */
    if (!(t > a && t < b))
        t = 0.5 * (a + b);
    double prev = b - a;
    for (int it = 0; it < 200; it++) {
        double f = poly3(c, t);
        if (f == 0.0)
            return t;
        if ((f < 0.0 ? -1.0 : 1.0) == sa)
            a = t;
        else
            b = t;
        double m = 0.5 * (a + b);
        if (!(m > a && m < b))
            break; /* a and b adjacent doubles */
        double df = c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]);
        double next = df != 0.0 ? t - f / df : m;
        /* converged: the error left after this step, |c''/(2c')| step^2,
         * below 2^-54 of the root (or of 2^-10 near zero) */
        if (next >= a && next <= b && df != 0.0 &&
            fabs(c[2] + 3.0 * t * c[3]) * (next - t) * (next - t) <=
                0x1p-54 * fabs(df) * dmax(fabs(next), 0x1p-10))
            return next;
        if (!(next > a && next < b) || fabs(next - t) > 0.5 * prev)
            next = m;
        prev = fabs(next - t);
        t = next;
    }
    /* the end of the last bracket nearer the root */
    return fabs(poly3(c, a)) <= fabs(poly3(c, b)) ? a : b;
}

/* The real roots of c[0] + c[1] t + c[2] t^2 + c[3] t^3 in [lo, hi],
 * ascending, at most 3 (a cubic that vanishes identically has none). */
int aa__poly3_roots(const double c[4], double lo, double hi, double *t)
{
    double cut[4], r[2];
    int nc = 0, n = 0;
    cut[nc++] = lo;
    int nr = gsl_poly_solve_quadratic(3.0 * c[3], 2.0 * c[2], c[1], &r[0], &r[1]);
    for (int k = 0; k < nr; k++)
        if (r[k] > cut[nc - 1] && r[k] < hi)
            cut[nc++] = r[k];
    cut[nc++] = hi;
    double fa = poly3(c, lo);
    for (int k = 0; k + 1 < nc; k++) {
        double a = cut[k], b = cut[k + 1], fb = poly3(c, b);
        double root = NAN;
        if (fa == 0.0)
            root = a;
        else if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0))
            root = aa__poly3_bracketed(c, a, b, fa, fb);
        if (root == root && (n == 0 || root > t[n - 1]) && n < 3)
            t[n++] = root;
        fa = fb;
    }
    if (fa == 0.0 && (n == 0 || hi > t[n - 1]) && n < 3)
        t[n++] = hi;
    return n;
}

/* ---- conic pieces ----
 *
 * y = ey - er cos s, x = ex + ea cos s + eb sin s, s in [s0, s1] within
 * [0, pi] (aabench.h, aa_piece).  At a height y, with dt = y - (ey - er) and
 * db = (ey + er) - y its distances to the ellipse's top and bottom,
 *     cos s = (db - dt)/(2 er),   sin s = sqrt(dt db)/er,
 * both without cancellation near either end, and
 *     s = 2 asin(sqrt(dt/(2 er)))  (from sin^2(s/2) = (1 - cos s)/2),
 * or pi less the same in db, whichever is smaller.  x turns where
 * dx/ds = -ea sin s + eb cos s vanishes: x = ex + R cos(s - alpha),
 * R = |(ea, eb)|, alpha = atan2(eb, ea), a maximum ex + R at s = alpha and
 * a minimum ex - R at alpha + pi. */

static void conic_cs(const aa_piece *p, double y, double *c, double *sn)
{
    double dt = dmax(y - (p->ey - p->er), 0.0), db = dmax((p->ey + p->er) - y, 0.0);
    *c = dmin(1.0, dmax(-1.0, (db - dt) / (2.0 * p->er)));
    *sn = dmin(1.0, sqrt(dt * db) / p->er);
}

double aa__conic_s_at(const aa_piece *p, double y)
{
    if (!(y > p->y0))
        return p->s0;
    if (!(y < p->y1))
        return p->s1;
    double dt = dmax(y - (p->ey - p->er), 0.0), db = dmax((p->ey + p->er) - y, 0.0);
    double s = dt <= db ? 2.0 * asin(dmin(1.0, sqrt(dt / (2.0 * p->er))))
                        : M_PI - 2.0 * asin(dmin(1.0, sqrt(db / (2.0 * p->er))));
    return dmin(dmax(s, p->s0), p->s1);
}

static double conic_x_at(const aa_piece *p, double y)
{
    if (!(y > p->y0))
        return p->x0;
    if (!(y < p->y1))
        return p->x1;
    double c, sn;
    conic_cs(p, y, &c, &sn);
    return p->ex + p->ea * c + p->eb * sn;
}

/* The extent over [sa, sb] given x at its ends. */
static void conic_range(const aa_piece *p, double sa, double xa, double sb, double xb,
                        double *xmin, double *xmax)
{
    *xmin = dmin(xa, xb);
    *xmax = dmax(xa, xb);
    double R = hypot(p->ea, p->eb), alpha = atan2(p->eb, p->ea);
    if (alpha > sa && alpha < sb)
        *xmax = dmax(*xmax, p->ex + R);
    if (alpha + M_PI > sa && alpha + M_PI < sb)
        *xmin = dmin(*xmin, p->ex - R);
}

void aa__conic_xrange(const aa_piece *p, double sa, double sb, double *xmin, double *xmax)
{
    double xa = sa <= p->s0 ? p->x0 : p->ex + p->ea * cos(sa) + p->eb * sin(sa);
    double xb = sb >= p->s1 ? p->x1 : p->ex + p->ea * cos(sb) + p->eb * sin(sb);
    conic_range(p, sa, xa, sb, xb, xmin, xmax);
}

/* Heights strictly inside (y0, y1) where the conic piece meets the
 * vertical line x: R cos(s - alpha) = x - ex. */
static int conic_meet_x(const aa_piece *p, double x, double ys[3])
{
    double R = hypot(p->ea, p->eb), alpha = atan2(p->eb, p->ea);
    if (!(R > 0.0) || fabs(x - p->ex) > R)
        return 0;
    double d = acos(dmin(1.0, dmax(-1.0, (x - p->ex) / R)));
    double cand[6] = {alpha + d, alpha - d, alpha + d - 2.0 * M_PI,
                      alpha - d + 2.0 * M_PI, alpha + d + 2.0 * M_PI, alpha - d - 2.0 * M_PI};
    int m = 0;
    for (int k = 0; k < 6 && m < 2; k++) {
        double sv = cand[k];
        if (!(sv > p->s0 && sv < p->s1))
            continue;
        double y = p->ey - p->er * cos(sv);
        if (!(y > p->y0 && y < p->y1))
            continue;
        int dup = 0;
        for (int j = 0; j < m; j++)
            dup |= ys[j] == y;
        if (!dup)
            ys[m++] = y;
    }
    if (m == 2 && ys[0] > ys[1]) {
        double t = ys[0];
        ys[0] = ys[1];
        ys[1] = t;
    }
    return m;
}

/* ---- offset pieces ---- */

/* The parameter of offset piece p at height y (inside its rows). */
static double offset_t_at(const aa_piece *p, double y)
{
    if (!(y > p->y0))
        return p->ot0;
    if (!(y < p->y1))
        return p->ot1;
    return aa__offset_solve_d(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y);
}

static double offset_x(const aa_piece *p, double t)
{
    if (t == p->ot0)
        return p->x0;
    if (t == p->ot1)
        return p->x1;
    double x, y;
    aa_offset_point(&p->oc, t, &x, &y, NULL, NULL);
    return x;
}

/* x extent between parameters ta and tb of p, where x is xa and xb: the
 * ends and the x turns between (closed form). */
static void offset_range_x(const aa_piece *p, double ta, double tb, double xa, double xb,
                           double *xmin, double *xmax)
{
    double lo = dmin(ta, tb), hi = dmax(ta, tb), ts[2];
    *xmin = dmin(xa, xb);
    *xmax = dmax(xa, xb);
    int n = aa__offset_turns(&p->oc, 0, lo, hi, ts);
    for (int k = 0; k < n; k++) {
        double x = offset_x(p, ts[k]);
        *xmin = dmin(*xmin, x);
        *xmax = dmax(*xmax, x);
    }
}

static void offset_range(const aa_piece *p, double ta, double tb, double *xmin, double *xmax)
{
    offset_range_x(p, ta, tb, offset_x(p, ta), offset_x(p, tb), xmin, xmax);
}

/* The heights where p meets the vertical line x: on each part between its
 * x turns, x is monotone and the root is solved for. */
static int offset_meet_x(const aa_piece *p, double x, double ys[3])
{
    double lo = dmin(p->ot0, p->ot1), hi = dmax(p->ot0, p->ot1), ts[4];
    int n = aa__offset_turns(&p->oc, 0, lo, hi, ts + 1), m = 0;
    /* in the order of y: from ot0 */
    if (p->ot0 > p->ot1) {
        double t = ts[1];
        if (n == 2)
            ts[1] = ts[2], ts[2] = t;
    }
    ts[0] = p->ot0;
    ts[n + 1] = p->ot1;
    for (int k = 0; k <= n && m < 3; k++) {
        double fa = offset_x(p, ts[k]) - x, fb = offset_x(p, ts[k + 1]) - x;
        if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0)))
            continue;
        double t = aa__offset_solve_d(&p->oc, 0, ts[k], ts[k + 1], fa, x), X, y;
        aa_offset_point(&p->oc, t, &X, &y, NULL, NULL);
        if (y > p->y0 && y < p->y1 && (m == 0 || y > ys[m - 1]))
            ys[m++] = y;
    }
    return m;
}

/* ---- piece geometry ---- */

double aa_piece_t_at(const aa_piece *p, double y)
{
    double d = y - p->y0, t;
    if (p->kind == AA_PIECE_FLAT || !(d > 0.0))
        return 0.0;
    if (y >= p->y1)
        return 1.0;
    if (p->kind == AA_PIECE_CONIC)
        return (aa__conic_s_at(p, y) - p->s0) / (p->s1 - p->s0);
    if (p->kind == AA_PIECE_OFFSET)
        return (offset_t_at(p, y) - p->ot0) / (p->ot1 - p->ot0);
    if (p->kind == AA_PIECE_CUBIC) {
        /* the one root of y(t) - y on [0, 1]: y is monotone there */
        double c[4] = {-d, p->by, p->ay, p->dy};
        double f1 = poly3(c, 1.0);
        if (!(f1 > 0.0))
            return 1.0;
        return aa__poly3_bracketed(c, 0.0, 1.0, -d, f1);
    }
    if (p->ay == 0.0) {
        t = d / p->by;
    } else {
        /* Root of ay t^2 + by t - d = 0 in [0, 1]: by >= 0 on a monotone
         * piece, so 2d / (by + sqrt(by^2 + 4 ay d)) has no cancellation. */
        double disc = fma(p->by, p->by, 4.0 * p->ay * d);
        double den = p->by + sqrt(disc > 0.0 ? disc : 0.0);
        t = den > 0.0 ? 2.0 * d / den : 0.0;
    }
    return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
}

double aa_piece_x_at(const aa_piece *p, double y)
{
    if (p->kind == AA_PIECE_LINE) {
        /* Interpolate from the nearer end: exact at both ends. */
        double h = p->y1 - p->y0;
        if (!(h > 0.0))
            return p->x0;
        if (y - p->y0 <= p->y1 - y)
            return p->x0 + (y - p->y0) / h * p->bx;
        return p->x1 - (p->y1 - y) / h * p->bx;
    }
    if (p->kind == AA_PIECE_FLAT)
        return p->x0;
    if (p->kind == AA_PIECE_CONIC)
        return conic_x_at(p, y);
    if (p->kind == AA_PIECE_OFFSET)
        return offset_x(p, offset_t_at(p, y));
    double t = aa_piece_t_at(p, y);
    if (p->kind == AA_PIECE_CUBIC)
        return p->x0 + t * (p->bx + t * (p->ax + t * p->dx));
    return p->x0 + t * (p->bx + t * p->ax);
}

void aa_piece_xrange(const aa_piece *p, double ya, double yb, double *xmin, double *xmax)
{
    if (p->kind == AA_PIECE_FLAT || (ya <= p->y0 && yb >= p->y1)) {
        *xmin = p->xmin;
        *xmax = p->xmax;
        return;
    }
    double a = ya > p->y0 ? ya : p->y0, b = yb < p->y1 ? yb : p->y1;
    if (a > b)
        a = b;
    if (p->kind == AA_PIECE_LINE) {
        double xa = aa_piece_x_at(p, a), xb = aa_piece_x_at(p, b);
        *xmin = dmin(xa, xb);
        *xmax = dmax(xa, xb);
        return;
    }
    if (p->kind == AA_PIECE_CONIC) {
        conic_range(p, aa__conic_s_at(p, a), conic_x_at(p, a), aa__conic_s_at(p, b),
                    conic_x_at(p, b), xmin, xmax);
        return;
    }
    if (p->kind == AA_PIECE_OFFSET) {
        offset_range(p, offset_t_at(p, a), offset_t_at(p, b), xmin, xmax);
        return;
    }
    double ta = aa_piece_t_at(p, a), tb = aa_piece_t_at(p, b);
    if (p->kind == AA_PIECE_CUBIC) {
        double c[4] = {p->x0, p->bx, p->ax, p->dx}, ts[2];
        *xmin = dmin(poly3(c, ta), poly3(c, tb));
        *xmax = dmax(poly3(c, ta), poly3(c, tb));
        int n = aa__cubic_turns(p->bx, p->ax, p->dx, ts);
        for (int k = 0; k < n; k++)
            if (ts[k] > ta && ts[k] < tb) {
                *xmin = dmin(*xmin, poly3(c, ts[k]));
                *xmax = dmax(*xmax, poly3(c, ts[k]));
            }
        return;
    }
    double xa = p->x0 + ta * (p->bx + ta * p->ax), xb = p->x0 + tb * (p->bx + tb * p->ax);
    *xmin = dmin(xa, xb);
    *xmax = dmax(xa, xb);
    if (p->ax != 0.0) {
        double t = -p->bx / (2.0 * p->ax);
        if (t > ta && t < tb) {
            double x = p->x0 + t * (p->bx + t * p->ax);
            *xmin = dmin(*xmin, x);
            *xmax = dmax(*xmax, x);
        }
    }
}

/* b^2 - 4ac with the products' rounding errors compensated (Kahan). */
static double discriminant(double a, double b, double c)
{
    double p = b * b, q = 4.0 * a * c;
    double dp = fma(b, b, -p), dq = fma(4.0 * a, c, -q);
    return (p - q) + (dp - dq);
}

/* The heights of the roots ts[0..n) of a cubic piece (ascending in t, so in
 * y), strictly inside (y0, y1), distinct. */
static int heights(const aa_piece *p, const double *ts, int n, double *ys)
{
    int m = 0;
    for (int k = 0; k < n; k++) {
        if (!(ts[k] > 0.0 && ts[k] < 1.0))
            continue;
        double y = p->y0 + ts[k] * (p->by + ts[k] * (p->ay + ts[k] * p->dy));
        if (y > p->y0 && y < p->y1 && (m == 0 || y > ys[m - 1]))
            ys[m++] = y;
    }
    return m;
}

int aa_piece_meet_x(const aa_piece *p, double x, double ys[3])
{
    double ts[3];
    int n = 0;
    if (p->kind == AA_PIECE_FLAT || x < p->xmin || x > p->xmax)
        return 0;
    double c = p->x0 - x;
    if (p->kind == AA_PIECE_CONIC)
        return conic_meet_x(p, x, ys);
    if (p->kind == AA_PIECE_OFFSET)
        return offset_meet_x(p, x, ys);
    if (p->kind == AA_PIECE_CUBIC) {
        double k[4] = {c, p->bx, p->ax, p->dx};
        return heights(p, ts, aa__poly3_roots(k, 0.0, 1.0, ts), ys);
    }
    if (p->ax == 0.0) {
        if (p->bx != 0.0)
            ts[n++] = -c / p->bx;
    } else {
        double d = discriminant(p->ax, p->bx, c);
        if (d < 0.0)
            return 0;
        double q = -0.5 * (p->bx + copysign(sqrt(d), p->bx));
        if (q != 0.0)
            ts[n++] = c / q;
        ts[n++] = q / p->ax;
    }
    int m = 0;
    for (int k = 0; k < n; k++) {
        if (!(ts[k] > 0.0 && ts[k] < 1.0))
            continue;
        double y = p->y0 + ts[k] * (p->by + ts[k] * p->ay);
        if (y > p->y0 && y < p->y1)
            ys[m++] = y;
    }
    if (m == 2 && ys[0] > ys[1]) {
        double t = ys[0];
        ys[0] = ys[1];
        ys[1] = t;
    }
    if (m == 2 && ys[0] == ys[1])
        m = 1;
    return m;
}

/* ---- where two pieces meet ---- */

/* x as a quadratic in u = y - lo, for a piece whose y is linear in its
 * parameter (lines, and arcs with ay = 0 such as crow's). */
static void x_in_u(const aa_piece *p, double lo, double *c0, double *c1, double *c2)
{
    double t = (lo - p->y0) / p->by;
    *c0 = p->x0 + t * (p->bx + t * p->ax);
    *c1 = (p->bx + 2.0 * p->ax * t) / p->by;
    *c2 = p->ax / (p->by * p->by);
}

/* Roots of a u^2 + b u + c in (0, len), cancellation-free. */
static int quadratic_roots(double a, double b, double c, double len, double *u)
{
    double r[2];
    int n = 0, m = 0;
    if (a == 0.0) {
        if (b != 0.0)
            r[n++] = -c / b;
    } else {
        double d = discriminant(a, b, c);
        if (d < 0.0)
            return 0;
        double h = -0.5 * (b + copysign(sqrt(d), b));
        if (h != 0.0)
            r[n++] = c / h;
        r[n++] = h / a;
    }
    for (int k = 0; k < n; k++)
        if (r[k] > 0.0 && r[k] < len)
            u[m++] = r[k];
    return m;
}

/* A line p, x = x0 + (y - y0) m, against a conic piece q: in q's c = cos s,
 * y = ey - er c, the line is x = K + M c (K = x0 + (ey - y0) m, M = -er m),
 * so eb sin s = g + h c with g = K - ex, h = M - ea; squared,
 *     (h^2 + eb^2) c^2 + 2 g h c + (g^2 - eb^2) = 0,
 * whose roots are meetings where g + h c has the sign of eb (sin s >= 0). */
static int line_conic(const aa_piece *p, const aa_piece *q, double lo, double hi, double *ys,
                      int max)
{
    double m = p->bx / p->by;
    double g = p->x0 + (q->ey - p->y0) * m - q->ex, h = -q->er * m - q->ea;
    double a = h * h + q->eb * q->eb, b = 2.0 * g * h, c = (g - q->eb) * (g + q->eb);
    double r[2], y[2];
    int n = 0, k2 = 0;
    if (a == 0.0)
        return 0;
    double d = discriminant(a, b, c);
    if (d < 0.0)
        return 0;
    double hh = -0.5 * (b + copysign(sqrt(d), b));
    if (hh != 0.0)
        r[n++] = c / hh;
    r[n++] = hh / a;
    for (int k = 0; k < n; k++) {
        double side = g + h * r[k];
        if (side * q->eb < 0.0 && fabs(side) > 1e-12 * (fabs(g) + fabs(h) + fabs(q->eb)))
            continue; /* the root of the squared equation only */
        double v = q->ey - q->er * r[k];
        if (v > lo && v < hi && (k2 == 0 || v != y[0]))
            y[k2++] = v;
    }
    if (k2 == 2 && y[0] > y[1]) {
        double t = y[0];
        y[0] = y[1], y[1] = t;
    }
    for (int k = 0; k < k2 && k < max; k++)
        ys[k] = y[k];
    return k2 < max ? k2 : max;
}

typedef struct meet_ctx {
    const aa_piece *p, *q;
    double *ys;
    int n, max, budget;
    /* offset pairs: the pieces share their end point at lo (at hi) */
    double lo, hi;
    int lo_shared, hi_shared;
    /* the heights of the end points both pieces share at their common
     * rows' bottom and top, at or beyond lo and hi (-inf, +inf: none) */
    double end_lo, end_hi;
    /* 1: polish_meet starts at the chord's root and stops by its error
     * estimate (area's aa__piece_meet_at); 0: as aa_piece_meet always did */
    int quick;
} meet_ctx;

/* 1 if [a, b] (narrower than 1e-6 of the scale, or a point) lies within
 * that of an end point both pieces share: a meeting there that x_p - x_q
 * does not prove by a change of sign beyond rounding (crosses_beyond) is
 * the end itself (a breakpoint already), not bisected on to 1e-12.  The
 * end may lie beyond the interval asked about: two arcs leaving a common
 * end point tangent to each other (the two halves of a crescent) differ
 * in x by the square of the distance to it, within rounding over a band
 * of heights near it, where the rounding of x also changes the sign of
 * their difference at random.  A band of the visible parts cut inside
 * that band (a window's side crossing the pieces there) was otherwise
 * bisected to 1e-12 and reported a meeting, and so was every band after
 * it, each narrowed to that meeting, about 1e-12 on: millions of
 * bisections (arcs.svg at 20 x 20 under tent:r=2.3 took minutes). */
static int near_shared_end(const meet_ctx *c, double a, double b, double scale)
{
    return (a == c->lo && c->lo_shared) || (b == c->hi && c->hi_shared) ||
           c->end_hi - a <= 1e-6 * scale || b - c->end_lo <= 1e-6 * scale;
}

/* 1 if differences fa and fb of x (rounding margin tol) are of opposite
 * signs beyond rounding. */
static int crosses_beyond(double fa, double fb, double tol)
{
    return (fa < -tol && fb > tol) || (fa > tol && fb < -tol);
}

/* 1 if [a, b] is still worth bisecting: room and budget are left and the
 * two pieces' exact x extents there overlap (an interval holding a meeting
 * always overlaps, so none is missed). */
static int extents_meet(meet_ctx *c, double a, double b)
{
    double pa, pb, qa, qb;
    if (c->n >= c->max || --c->budget < 0)
        return 0;
    aa_piece_xrange(c->p, a, b, &pa, &pb);
    aa_piece_xrange(c->q, a, b, &qa, &qb);
    /* a margin of rounding: a meeting at an end of the interval must not
     * look disjoint in both halves */
    double tol = 8.0 * DBL_EPSILON *
                 dmax(1.0, dmax(dmax(fabs(pa), fabs(pb)), dmax(fabs(qa), fabs(qb))));
    return !(pb < qa - tol || qb < pa - tol);
}

/* A meeting at height y, unless it is within the resolution of the last. */
static void record_meet(meet_ctx *c, double y, double scale)
{
    if (c->n == 0 || y - c->ys[c->n - 1] > 1e-12 * scale)
        c->ys[c->n++] = y;
}

/* Bisect [a, b] while the extents meet; an interval narrower than the
 * resolution is reported by its middle. */
static void subdivide(meet_ctx *c, double a, double b, int depth)
{
    if (!extents_meet(c, a, b))
        return;
    double m = 0.5 * (a + b), scale = dmax(1.0, fabs(m));
    if (depth >= 60 || b - a <= 1e-12 * scale || !(m > a && m < b)) {
        record_meet(c, m, scale);
        return;
    }
    subdivide(c, a, m, depth + 1);
    subdivide(c, m, b, depth + 1);
}

/* An offset piece's last solve in polish_meet: its height y, parameter t
 * and dy/dt there (d; NaN: none yet). */
typedef struct last_solve {
    double y, t, d;
} last_solve;

/* x of the piece at y and dx/dy there (infinite where it is horizontal);
 * an offset piece's parameter there is t, solved for between the
 * parameters tab[0] and tab[1] it has at heights ya < y and yb > y (its
 * whole range where tab is NULL), started from the tangent's step from
 * its last solve ls (Newton's first step: once polish_meet's steps in y
 * shrink, within the solver's tolerance of the root, one evaluation where
 * a solve from the bracket took three or four; the same root within
 * double's rounding). */
static double x_slope(const aa_piece *p, double y, double *slope, double ya, const double *tab,
                      double *t_out, last_solve *ls)
{
    if (p->kind == AA_PIECE_CONIC) {
        double c, sn;
        conic_cs(p, y, &c, &sn);
        *slope = (p->eb * c - p->ea * sn) / (p->er * sn);
        return conic_x_at(p, y);
    }
    if (p->kind == AA_PIECE_OFFSET) {
        double guess = ls->t + (y - ls->y) / ls->d; /* NaN: none */
        double t;
        if (!(y > p->y0))
            t = p->ot0;
        else if (!(y < p->y1))
            t = p->ot1;
        else if (!tab || tab[0] == tab[1])
            t = aa__offset_solve_dg(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y, guess);
        else
            t = aa__offset_solve_dg(&p->oc, 1, tab[0], tab[1], ya - y, y, guess);
        double x, yy, dx, dy;
        aa_offset_point(&p->oc, t, &x, &yy, &dx, &dy);
        *slope = dx / dy;
        *t_out = t;
        ls->y = y, ls->t = t, ls->d = dy;
        return t == p->ot0 ? p->x0 : t == p->ot1 ? p->x1 : x; /* offset_x(p, t) */
    }
    double t = aa_piece_t_at(p, y);
    double dx = p->bx + t * (2.0 * p->ax + 3.0 * t * p->dx);
    double dy = p->by + t * (2.0 * p->ay + 3.0 * t * p->dy);
    *slope = dx / dy;
    return p->x0 + t * (p->bx + t * (p->ax + t * p->dx));
}

/* Area's polish_meet of a line p and an offset piece q, whose parameters
 * at a and b are tq: Newton's method on q's parameter t, g(t) = (Q(t) -
 * P0) x B (B = (bx, by) the line's direction, by > 0, so g = -by (x_p -
 * x_q) at q's height), kept inside the bracket, started where the chord
 * through the ends' differences meets 0, and stopped by the same error
 * estimate as polish_meet's, its step's height within the rounding of y:
 * one evaluation of q a step (its point and derivative), where a step in
 * y solved for q's parameter first.  The height is q's at the last
 * evaluation moved by its derivative over the last step.  NaN where it
 * left [a, b] (polish_meet then polishes in y).  On the 1,000 stroked
 * cubics of tests/bench_bezstroke.c at 256 px, 5,702 of a render's 7,782
 * polishes, the meetings' instructions 164.7 M to 154.8 M (callgrind);
 * 46 heights moved by more than 1e-12 of y (at most 1.4e-9 of it), each
 * where the two cross at slopes about 1e-7 apart and x_p - x_q is within
 * 1.5e-14 of 0 at both heights: either is a root. */
static double polish_line_offset(const aa_piece *p, const aa_piece *q, double a, double b,
                                 double fa, double fb, const double tq[2])
{
    double ta = tq[0], tb = tq[1], t = ta + (tb - ta) * (fa / (fa - fb)), h1 = NAN, prev;
    int neg = fa > 0.0; /* the sign of g at a: g = -by (x_p - x_q) */
    if (!(dmin(ta, tb) < t && t < dmax(ta, tb)))
        t = 0.5 * (ta + tb);
    prev = fabs(tb - ta);
    for (int it = 0; it < 100; it++) {
        double x, y, dx, dy;
        aa_offset_point(&q->oc, t, &x, &y, &dx, &dy);
        double g = (x - p->x0) * p->by - (y - p->y0) * p->bx, dg = dx * p->by - dy * p->bx;
        if (g == 0.0)
            return y > a && y < b ? y : NAN;
        if ((g < 0.0) == neg)
            ta = t;
        else
            tb = t;
        double mid = 0.5 * (ta + tb);
        if (!(dmin(ta, tb) < mid && mid < dmax(ta, tb)))
            return y > a && y < b ? y : NAN;
        double next = dg != 0.0 && isfinite(dg) ? t - g / dg : mid;
        double h = fabs(next - t), hy = fabs(dy) * h, r = 4.0 * DBL_EPSILON * fabs(y);
        int inside = dmin(ta, tb) < next && next < dmax(ta, tb);
        if (inside && (hy <= r || (h < h1 && hy * h * h <= r * h1 * h1))) {
            double v = y + dy * (next - t);
            return v > a && v < b ? v : NAN;
        }
        h1 = h;
        if (!inside || h > 0.5 * prev)
            next = mid, h1 = NAN;
        prev = fabs(next - t);
        t = next;
    }
    return NAN;
}

/* Area's polish_meet of two offset pieces p and q, whose parameters at a
 * and b are tp and tq: Newton's method on both parameters at once, F(s,
 * t) = P(s) - Q(t) = 0 (two equations, the Jacobian's columns P'(s) and
 * -Q'(t)), started where the chord through the ends' differences meets 0
 * (each parameter at that fraction of its bracket), and stopped by
 * polish_line_offset's error estimate on the step in p's height.  One
 * evaluation of each piece a step (its point and derivative), where a step
 * in y solved for both parameters first (x_slope: two solves of a few
 * evaluations each).  Both parameters stay inside their brackets, so the
 * point found lies on both pieces between heights a and b, where they
 * meet once (the caller's proof): that meeting.  The height is p's at the
 * last evaluation moved by its derivative over the last step.  NaN where
 * a step leaves a bracket, the tangents are parallel, or 40 steps do not
 * converge (polish_meet then polishes in y).  On the 1,000 stroked cubics
 * of tests/bench_bezstroke.c at 256 px, 2,055 polishes a render, 6 of them
 * left to polish_meet, 6,300 steps in all; none of the heights moved from
 * polish_meet's by more than 1e-12 of y (1.3e-10 px at most; at 1024 px
 * 1,032 polishes, 15 left, 6.7e-10 px at most). */
static double polish_offsets(const aa_piece *p, const aa_piece *q, double a, double b,
                             double fa, double fb, const double tp[2], const double tq[2])
{
    double sl = dmin(tp[0], tp[1]), sh = dmax(tp[0], tp[1]);
    double tl = dmin(tq[0], tq[1]), th = dmax(tq[0], tq[1]), f = fa / (fa - fb), h1 = NAN;
    double s = tp[0] + (tp[1] - tp[0]) * f, t = tq[0] + (tq[1] - tq[0]) * f;
    if (!(sl < s && s < sh && tl < t && t < th))
        return NAN;
    for (int it = 0; it < 40; it++) {
        double px, py, pdx, pdy, qx, qy, qdx, qdy;
        aa_offset_point(&p->oc, s, &px, &py, &pdx, &pdy);
        aa_offset_point(&q->oc, t, &qx, &qy, &qdx, &qdy);
        double fx = px - qx, fy = py - qy, det = qdx * pdy - pdx * qdy;
        if (!(fabs(det) > 1e-12 * (fabs(qdx * pdy) + fabs(pdx * qdy))))
            return NAN;
        double ds = (fx * qdy - qdx * fy) / det, dt = (fx * pdy - pdx * fy) / det;
        double ns = s + ds, nt = t + dt;
        if (!(sl < ns && ns < sh && tl < nt && nt < th))
            return NAN;
        double hy = fabs(pdy * ds), r = 4.0 * DBL_EPSILON * fabs(py);
        if (hy <= r || (hy < h1 && hy * hy * hy <= r * h1 * h1)) {
            double v = py + pdy * ds;
            return v > a && v < b ? v : NAN;
        }
        h1 = hy, s = ns, t = nt;
    }
    return NAN;
}

/* The height in [a, b] where x_p - x_q, of opposite signs fa and fb at a
 * and b, vanishes: Newton's method on y kept inside the bracket, bisection
 * where a step would leave it or shrink it too slowly, until the bracket
 * is two adjacent doubles or the difference is zero.  tp, tq (NULL: not
 * known): offset pieces' parameters at a and b, each solve for the
 * parameter at y then bracketed by those at the bracket's ends, kept as it
 * shrinks (from the whole piece, each took twice the evaluations), and
 * started from the last (x_slope).
 *
 * quick (area's): started where the chord through (a, fa) and (b, fb)
 * meets 0, not at the middle, and stopped at the first step h whose
 * error, estimated h^3/h1^2 from the Newton step h1 before it (quadratic
 * convergence: e' = C e^2, C about h/h1^2), is within the rounding of y.
 * Without it, once within the rounding of x_p - x_q (about 1e-13 px), the
 * steps were of the noise's size, often longer than half the last, and
 * bisected down to one within 4 ulps of y: on the 1,000 stroked cubics
 * of tests/bench_bezstroke.c at 256 px, 68,601 steps (31,835 of them
 * bisections) for 7,757 meetings, now 24,113 (866); at 1024 px 7,002
 * (1,287) for 1,448, now 3,515 (5).  The height moves by rounding: by
 * at most 8e-14 of it at 1024 px; at 256 px 40 of the 7,757 by more than
 * 1e-12 of it (at most 2.9e-7 px), each where a line leaves a round
 * join's arc tangent to it, x_p - x_q within its rounding (3e-14 px)
 * over that stretch, where either height is a root.  A line and an
 * offset piece: polish_line_offset, in the offset's parameter; two offset
 * pieces: polish_offsets, in both parameters. */
static double polish_meet(const aa_piece *p, const aa_piece *q, double a, double b, double fa,
                          double fb, const double *tp, const double *tq, int quick)
{
    if (quick && p->kind == AA_PIECE_LINE && q->kind == AA_PIECE_OFFSET && tq && p->by > 0.0) {
        double v = polish_line_offset(p, q, a, b, fa, fb, tq);
        if (v == v)
            return v;
    }
    if (quick && p->kind == AA_PIECE_OFFSET && q->kind == AA_PIECE_OFFSET && tp && tq) {
        double v = polish_offsets(p, q, a, b, fa, fb, tp, tq);
        if (v == v)
            return v;
    }
    double y = 0.5 * (a + b), prev = b - a, h1 = NAN;
    if (quick) {
        double yc = a + (b - a) * (fa / (fa - fb));
        if (yc > a && yc < b)
            y = yc;
    }
    double bp[2] = {0.0, 0.0}, bq[2] = {0.0, 0.0};
    last_solve lp = {NAN, NAN, NAN}, lq = {NAN, NAN, NAN};
    if (tp)
        bp[0] = tp[0], bp[1] = tp[1];
    if (tq)
        bq[0] = tq[0], bq[1] = tq[1];
    for (int it = 0; it < 200; it++) {
        double sp, sq, up = 0.0, uq = 0.0;
        double f = x_slope(p, y, &sp, a, tp ? bp : NULL, &up, &lp) -
                   x_slope(q, y, &sq, a, tq ? bq : NULL, &uq, &lq);
        if (f == 0.0)
            return y;
        if ((f < 0.0) == (fa < 0.0))
            a = y, bp[0] = up, bq[0] = uq;
        else
            b = y, bp[1] = up, bq[1] = uq;
        double m = 0.5 * (a + b);
        if (!(m > a && m < b))
            break;
        double df = sp - sq, next = df != 0.0 && isfinite(df) ? y - f / df : m;
        double h = fabs(next - y), r = 4.0 * DBL_EPSILON * fabs(y);
        if (next > a && next < b && (h <= r || (quick && h < h1 && h * h * h <= r * h1 * h1)))
            return next; /* a step within rounding: converged */
        h1 = h;
        if (!(next > a && next < b) || fabs(next - y) > 0.5 * prev)
            next = m, h1 = NAN;
        prev = fabs(next - y);
        y = next;
    }
    return y;
}

/* Two pieces of which one at least is a cubic: the same bisection on exact
 * extents, but an interval narrower than 1e-6 of the scale in which the
 * difference of their x changes sign holds a crossing, which is polished
 * to full precision (polish_meet); one without a change (a touch, or two
 * crossings closer than that) is bisected on to 1e-12 and reported by its
 * middle. */
static void subdivide_cubic(meet_ctx *c, double a, double b, int depth)
{
    if (!extents_meet(c, a, b))
        return;
    double m = 0.5 * (a + b), scale = dmax(1.0, fabs(m));
    if (b - a <= 1e-6 * scale) {
        double xpa = aa_piece_x_at(c->p, a), xqa = aa_piece_x_at(c->q, a);
        double xpb = aa_piece_x_at(c->p, b), xqb = aa_piece_x_at(c->q, b);
        double fa = xpa - xqa, fb = xpb - xqb;
        double tol = 8.0 * DBL_EPSILON *
                     dmax(1.0, dmax(dmax(fabs(xpa), fabs(xqa)), dmax(fabs(xpb), fabs(xqb))));
        /* a common end point of both pieces at or just beyond the
         * interval's end, and no crossing after it this close: the end
         * itself (near_shared_end) */
        if (near_shared_end(c, a, b, scale) && !crosses_beyond(fa, fb, tol))
            return;
        if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
            record_meet(c, polish_meet(c->p, c->q, a, b, fa, fb, NULL, NULL, c->quick), scale);
            return;
        }
    }
    if (depth >= 60 || b - a <= 1e-12 * scale || !(m > a && m < b)) {
        record_meet(c, m, scale);
        return;
    }
    subdivide_cubic(c, a, m, depth + 1);
    subdivide_cubic(c, m, b, depth + 1);
}

/* Pairs with an offset piece: subdivide_cubic with each offset piece's
 * parameters at the interval's ends carried down (one root-finding per
 * piece and split, not four). */
static double param_at(const aa_piece *p, double y)
{
    return p->kind == AA_PIECE_OFFSET ? offset_t_at(p, y) : 0.0;
}

/* The parameter at height y in (a, b) of an offset piece whose parameters
 * at a and b are t[0] and t[1]: solved in that bracket, not the piece's. */
static double param_within(const aa_piece *p, double y, double a, const double t[2])
{
    if (p->kind != AA_PIECE_OFFSET)
        return 0.0;
    if (!(y > p->y0) || !(y < p->y1) || t[0] == t[1])
        return offset_t_at(p, y);
    return aa__offset_solve_d(&p->oc, 1, t[0], t[1], a - y, y);
}

/* x of p at height y, its parameter there t (offset pieces): what
 * slopes_say and range_at take at an interval's ends. */
static double end_x(const aa_piece *p, double y, double t)
{
    return p->kind == AA_PIECE_OFFSET ? offset_x(p, t) : aa_piece_x_at(p, y);
}

static void range_at(const aa_piece *p, double a, double b, const double t[2], const double x[2],
                     double *lo, double *hi)
{
    if (p->kind == AA_PIECE_OFFSET)
        offset_range_x(p, t[0], t[1], x[0], x[1], lo, hi);
    else
        aa_piece_xrange(p, a, b, lo, hi);
}

/* The range [*lo, *hi] of A/C between t = ta and tb, A and C quadratics
 * (coefficients ascending): at the ends and where A'C - AC' (a quadratic)
 * vanishes; 0 if C vanishes on [ta, tb]. */
static int ratio_range(const double *A, const double *C, double ta, double tb, double *lo,
                       double *hi)
{
    double t0 = dmin(ta, tb), len = fabs(tb - ta), r[2];
    /* about t0: A(t0 + u), C(t0 + u) */
    double c0 = C[0] + t0 * (C[1] + t0 * C[2]), c1 = C[1] + 2.0 * t0 * C[2], c2 = C[2];
    double a0 = A[0] + t0 * (A[1] + t0 * A[2]), a1 = A[1] + 2.0 * t0 * A[2], a2 = A[2];
    double cend = c0 + len * (c1 + len * c2);
    if (!(c0 != 0.0 && cend != 0.0 && (c0 > 0.0) == (cend > 0.0)) ||
        quadratic_roots(c2, c1, c0, len, r) > 0)
        return 0;
    double s0 = a0 / c0, s1 = (a0 + len * (a1 + len * a2)) / cend;
    *lo = dmin(s0, s1), *hi = dmax(s0, s1);
    int n = quadratic_roots(a2 * c1 - a1 * c2, 2.0 * (a2 * c0 - a0 * c2), a1 * c0 - a0 * c1, len,
                            r);
    for (int k = 0; k < n; k++) {
        double sk = (a0 + r[k] * (a1 + r[k] * a2)) / (c0 + r[k] * (c1 + r[k] * c2));
        *lo = dmin(*lo, sk), *hi = dmax(*hi, sk);
    }
    return 1;
}

/* The range [*lo, *hi] of dx/dy along p over heights [a, b] (t: an offset
 * piece's parameters there).  A line's slope; a Bezier piece's x'/y', a
 * ratio of quadratics in its t; on an offset piece P' is m(B') (1 - d k),
 * on an evolute m(N) (1/k)', so dx/dy is the ratio of the rows of m
 * applied to B' (or to N |B'| = (-B'y, B'x)), quadratics in t (for the
 * offsets of an ellipse, B' = v cos t - u sin t: a ratio of two forms
 * a cos t + b sin t, monotone in t where the lower has no zero, its
 * derivative's numerator the constant a2 c1 - a1 c2); on a conic
 * -ea/er + (eb/er) cot s, monotone in s.  0 where it is not bounded (the
 * piece turns horizontal on [a, b]). */
static int slope_range(const aa_piece *p, double a, double b, const double t[2], double *lo,
                       double *hi)
{
    int ok = 0;
    if (p->kind == AA_PIECE_LINE) {
        *lo = *hi = (p->x1 - p->x0) / (p->y1 - p->y0);
        ok = 1;
    } else if (p->kind == AA_PIECE_CONIC) {
        double sa = aa__conic_s_at(p, a), sb = aa__conic_s_at(p, b);
        if (!(sa > 0.0 && sb < M_PI && p->er > 0.0))
            return 0;
        double ka = -p->ea / p->er + p->eb / (p->er * tan(sa));
        double kb = -p->ea / p->er + p->eb / (p->er * tan(sb));
        *lo = dmin(ka, kb), *hi = dmax(ka, kb);
        ok = 1;
    } else if (p->kind == AA_PIECE_OFFSET && p->oc.base == AA_OFFSET_ELLIPSE) {
        const double *c = p->oc.b, *m = p->oc.m;
        /* the direction's cos t and sin t coefficients: B' = v cos t - u sin t */
        double ex[2] = {c[4], -c[2]}, ey[2] = {c[5], -c[3]}, A[2], C[2];
        for (int k = 0; k < 2; k++) {
            double vx = p->oc.evolute ? -ey[k] : ex[k], vy = p->oc.evolute ? ex[k] : ey[k];
            A[k] = m[0] * vx + m[2] * vy;
            C[k] = m[1] * vx + m[3] * vy;
        }
        double ta = dmin(t[0], t[1]), tb = dmax(t[0], t[1]);
        double ca = C[0] * cos(ta) + C[1] * sin(ta), cb = C[0] * cos(tb) + C[1] * sin(tb);
        /* C's zeros are pi apart: none inside if its ends agree in sign on
         * a range shorter than pi */
        if (!(tb - ta < M_PI && ((ca > 0.0 && cb > 0.0) || (ca < 0.0 && cb < 0.0))))
            return 0;
        double ka = (A[0] * cos(ta) + A[1] * sin(ta)) / ca;
        double kb = (A[0] * cos(tb) + A[1] * sin(tb)) / cb;
        *lo = dmin(ka, kb), *hi = dmax(ka, kb);
        ok = 1;
    } else if (p->kind == AA_PIECE_OFFSET) {
        const double *c = p->oc.b, *m = p->oc.m;
        double ux[3] = {c[1], 2.0 * c[2], 3.0 * c[3]}, uy[3] = {c[5], 2.0 * c[6], 3.0 * c[7]};
        double A[3], C[3];
        for (int k = 0; k < 3; k++) {
            double vx = p->oc.evolute ? -uy[k] : ux[k], vy = p->oc.evolute ? ux[k] : uy[k];
            A[k] = m[0] * vx + m[2] * vy;
            C[k] = m[1] * vx + m[3] * vy;
        }
        ok = ratio_range(A, C, t[0], t[1], lo, hi);
    } else if (p->kind == AA_PIECE_QUAD || p->kind == AA_PIECE_CUBIC) {
        double A[3] = {p->bx, 2.0 * p->ax, 3.0 * p->dx}, C[3] = {p->by, 2.0 * p->ay, 3.0 * p->dy};
        ok = ratio_range(A, C, aa_piece_t_at(p, a), aa_piece_t_at(p, b), lo, hi);
    }
    if (!ok)
        return 0;
    /* the rounding of the quotients, of the roots and of the parameters */
    double e = 1e-9 * (fabs(*lo) + fabs(*hi)) + 1e-300;
    *lo -= e, *hi += e;
    return isfinite(*lo) && isfinite(*hi);
}

/* What the slopes tell of p and q on [a, b] (tp, tq their parameters at a
 * and b), with D = x_p - x_q, D' = dx_p/dy - dx_q/dy within [slo, shi]
 * (slope_range) and tol the rounding margin of x (by the mean value
 * theorem):
 *  - |D| <= tol at both ends, and the region between the pieces over
 *    [a, b] below `sliver` in area (NEAR): the pieces are within rounding
 *    of each other at a and b, so |D| <= 2 tol there (the margin and the
 *    rounding of the evaluation) and, with |D'| <= M = max(|slo|, |shi|),
 *    |D(y)| <= 2 tol + M min(y - a, b - y) between, whose integral is at
 *    most 2 tol (b - a) + M (b - a)^2 / 4.  Whatever meetings they have
 *    there order them wrongly over part of that region at most, so none
 *    is reported;
 *  - D' of one sign (D strictly monotone): no meeting if D(a) and D(b) are
 *    of one sign beyond tol (APART), exactly one if of opposite signs
 *    beyond tol (ONE: *fa is D(a)), else a meeting at the end where
 *    |D| <= tol (AT_A, AT_B) if the meeting is then within res of it (it
 *    is within w = 2 tol/min |D'|), or if the region between the pieces
 *    from that end to the meeting, where |D| <= 2 tol (D is monotone), is
 *    below `sliver` (2 tol w), else UNKNOWN;
 *  - else D lies above both D(a) + slo (y - a) and D(b) - shi (b - y) (for
 *    D > 0 at both ends), whose larger is least where they cross (clamped
 *    to [a, b]): no meeting if that least value exceeds tol (APART).
 * For two pieces that run side by side (offsets of consecutive arcs near
 * their join, a normal line and the offset it ends) this ends the
 * bisection at once, where their boxes in x overlap down to a small
 * fraction of their distance.  UNKNOWN where a slope is not bounded (a
 * piece turning horizontal) or nothing is proven.
 *
 * Pieces that cross at a small angle, or touch, within rounding of each
 * other: the evaluated D changes sign at random over a band of heights
 * about the meeting, and before NEAR and the sliver's test the bisection
 * reported a meeting in every 1e-12 of it, and the visible parts' sweep
 * (visible.c), which starts each band at the last meeting, asked again
 * from there.  The normal line that ends a folding offset's region and
 * the evolute that ends on it (tangent to it there, and convex) meet
 * only at that end, but their two copies of the end point, each rounded
 * its own way, are 1.4e-14 px apart, so they cross next to it, where D
 * grows as 0.27 u^2 (u px from the end) and stays within rounding over
 * some 1e-7 px: 439 meetings were reported within 4e-8 px there (the
 * folding SVG of tests/test_analytic_stroke.c at 96 px, whose visible
 * parts took 27.4 s of CPU).  The region such a meeting could misplace
 * lies within 2 tol of a piece: with `sliver` 1e-15 (square pixels, the
 * units of the placed scenes the methods and the reference take), a
 * pixel's value under the box filter moves by at most that, a thousandth
 * of the 1e-12 to which the reference is exact. */
enum { UNKNOWN, APART, ONE, AT_A, AT_B, NEAR };
static int slopes_say(const aa_piece *p, const aa_piece *q, double a, double b,
                      const double tp[2], const double tq[2], const double xp[2],
                      const double xq[2], double tol, double res, double sliver, double *fa)
{
    double plo, phi, qlo, qhi;
    if (!slope_range(p, a, b, tp, &plo, &phi) || !slope_range(q, a, b, tq, &qlo, &qhi))
        return UNKNOWN;
    double da = xp[0] - xq[0], db = xp[1] - xq[1], slo = plo - qhi, shi = phi - qlo;
    *fa = da;
    if (fabs(da) <= tol && fabs(db) <= tol) {
        double h = b - a, M = dmax(fabs(slo), fabs(shi));
        if (2.0 * tol * h + 0.25 * M * h * h <= sliver)
            return NEAR;
    }
    if (slo > 0.0 || shi < 0.0) {
        if ((da > tol && db > tol) || (da < -tol && db < -tol))
            return APART;
        if ((da < -tol && db > tol) || (da > tol && db < -tol))
            return ONE;
        /* an end within tol: |D'| >= g, so a meeting is within tol/g of
         * it (2 tol/g with the rounding of D there); said to be there if
         * that is within the resolution, or if the region between the
         * pieces up to it, 2 tol wide at most, is below `sliver` */
        double g = slo > 0.0 ? slo : -shi;
        if (!(tol <= res * g || 4.0 * tol * tol <= sliver * g))
            return UNKNOWN;
        return fabs(da) <= fabs(db) ? AT_A : AT_B;
    }
    if (!((da > tol && db > tol) || (da < -tol && db < -tol)))
        return UNKNOWN;
    if (da < 0.0) { /* D -> -D */
        double t = slo;
        da = -da, db = -db, slo = -shi, shi = -t;
    }
    double h = b - a, u = dmin(dmax((db - da - shi * h) / (slo - shi), 0.0), h);
    return dmax(da + slo * u, db - shi * (h - u)) > tol ? APART : UNKNOWN;
}

/* 1 if p's x is strictly monotone over [a, b] (t: an offset piece's
 * parameters there): a line; an offset piece without an x turn inside
 * (aa__offset_turns, closed form).  0 where not proven (other kinds). */
static int x_monotone(const aa_piece *p, const double t[2])
{
    double ts[2];
    if (p->kind == AA_PIECE_LINE)
        return 1;
    if (p->kind != AA_PIECE_OFFSET)
        return 0;
    return aa__offset_turns(&p->oc, 0, dmin(t[0], t[1]), dmax(t[0], t[1]), ts) == 0;
}

/* 1 if p and q, leaving the end point they share at an end of [a, b]
 * (x there: X), part in x for good: both strictly monotone in x there
 * (x_monotone) and at the other end one left of X and the other right of
 * it beyond the rounding margin tol.  Then one's x stays below X and the
 * other's above on the whole interval, and they meet nowhere but where
 * both are within rounding of X next to the shared end, which is the end
 * itself as for the shared ends below (b - a <= 1e-6 scale).  Two parts
 * of one offset curve split at its top or bottom (a y turn, where both
 * run horizontally and slope_range bounds neither slope) were bisected
 * down to that width, ten or more levels of two solves each, in every
 * band that held the shared end. */
static int part_at_end(const meet_ctx *c, double a, double b, const double tp[2],
                       const double tq[2], const double xp[2], const double xq[2], double tol)
{
    int e = a == c->lo && c->lo_shared ? 0 : (b == c->hi && c->hi_shared ? 1 : -1);
    if (e < 0)
        return 0;
    double dp = xp[1 - e] - xp[e], dq = xq[1 - e] - xq[e];
    if (!((dp < -tol && dq > tol) || (dp > tol && dq < -tol)))
        return 0;
    return x_monotone(c->p, tp) && x_monotone(c->q, tq);
}

/* An offset piece's parameters t (at an interval's ends) for polish_meet;
 * NULL for other kinds (subdivide_offset carries zeros for them). */
static const double *offset_t(const aa_piece *p, const double t[2])
{
    return p->kind == AA_PIECE_OFFSET ? t : NULL;
}

static void subdivide_offset(meet_ctx *c, double a, double b, const double tp[2],
                             const double tq[2], const double xp[2], const double xq[2],
                             int depth);

/* Offset piece p's parameter *t_out, height *y_out and x *x_out near the
 * end e of [a, b] (its parameters there t[0], t[1]), within 2 cut of that
 * end: stepped from it along the chord of t over [a, b] by cut / (b - a)
 * of the way, and where the point lands farther than 2 cut away, once
 * more by that step shrunk in proportion; nearer than cut / 4 (where y
 * turns at the end, dy/dt 0 at a cusp of an evolute or at the fold of an
 * offset, where such ends lie, y moves as the step's square), once more
 * by the step grown by the square root of the shortfall.  One evaluation,
 * sometimes two.  0 (none) where no point was found so. */
static int step_in(const aa_piece *p, double a, double b, const double t[2], int e, double cut,
                   double *t_out, double *y_out, double *x_out)
{
    double end = e ? b : a, f = cut / (b - a);
    if (p->kind != AA_PIECE_OFFSET || t[0] == t[1])
        return 0;
    for (int k = 0; k < 2; k++) {
        double ts = t[e] + (t[1 - e] - t[e]) * f, xs, ys;
        if (!(ts > dmin(t[0], t[1]) && ts < dmax(t[0], t[1])))
            return 0;
        aa_offset_point(&p->oc, ts, &xs, &ys, NULL, NULL);
        double d = fabs(ys - end);
        if (!(ys > a && ys < b))
            return 0;
        if (d <= 2.0 * cut && (d >= 0.25 * cut || k == 1)) {
            *t_out = ts, *y_out = ys, *x_out = xs;
            return 1;
        }
        f *= d > cut ? cut / d : sqrt(cut / d);
    }
    return 0;
}

/* [a, b] with an end point both pieces share at its end e (0: a, 1: b),
 * where they may leave it tangent to each other (where a stroke's offset
 * folds, an evolute and the normal line that ends on it, which is its
 * tangent there; two evolutes of consecutive arcs) and differ in x by
 * about the square of the distance from it, so that neither their slopes
 * nor their difference at the ends part them on an interval touching it.
 * A meeting within 1e-6 of the scale of that end is the end itself
 * (near_shared_end): there x_p - x_q, 0 at the end, never changes sign
 * beyond rounding between the ends of an interval (crosses_beyond), and
 * subdivide_offset reported nothing inside the part cut off next to it
 * (at most 1/2 of that width), so that part is not asked at all; the
 * rest, away from the end, is subdivided (their slopes there are of one
 * sign, and part them at once), and what it holds within 2 cut of the end
 * dropped by the same rule.  The cut's height m comes from an offset
 * piece stepped in from the end (step_in: one evaluation, where a solve
 * for the parameter at a given height took five times as many
 * instructions; m then within 2 cut of the end), the other piece's
 * parameter there solved for; else m is `cut` from the end and both are
 * solved for.  On the 1,000 stroked cubics of tests/bench_bezstroke.c at
 * 256x256, 17,740 such ends a render: the meetings 207.8 M instructions
 * a render to 164.7 M (callgrind). */
static void shared_end_cut(meet_ctx *c, double a, double b, const double tp[2],
                           const double tq[2], const double xp[2], const double xq[2], int e,
                           double cut, int depth)
{
    double m = e ? b - cut : a + cut, pm, qm, xpm, xqm;
    if (step_in(c->q, a, b, tq, e, cut, &qm, &m, &xqm)) {
        pm = param_within(c->p, m, a, tp);
        xpm = end_x(c->p, m, pm);
    } else if (step_in(c->p, a, b, tp, e, cut, &pm, &m, &xpm)) {
        qm = param_within(c->q, m, a, tq);
        xqm = end_x(c->q, m, qm);
    } else {
        pm = param_within(c->p, m, a, tp), qm = param_within(c->q, m, a, tq);
        xpm = end_x(c->p, m, pm), xqm = end_x(c->q, m, qm);
    }
    int n0 = c->n;
    if (e == 0) {
        const double rp[2] = {pm, tp[1]}, rq[2] = {qm, tq[1]};
        const double rxp[2] = {xpm, xp[1]}, rxq[2] = {xqm, xq[1]};
        subdivide_offset(c, m, b, rp, rq, rxp, rxq, depth + 1);
    } else {
        const double lp[2] = {tp[0], pm}, lq[2] = {tq[0], qm};
        const double lxp[2] = {xp[0], xpm}, lxq[2] = {xq[0], xqm};
        subdivide_offset(c, a, m, lp, lq, lxp, lxq, depth + 1);
    }
    /* a meeting the rest holds within 2 cut of the end is the end itself */
    int k2 = n0;
    for (int k = n0; k < c->n; k++)
        if (fabs(c->ys[k] - (e ? b : a)) > 2.0 * cut)
            c->ys[k2++] = c->ys[k];
    c->n = k2;
}

/* The control vectors v of cubic c's B' over [ta, tb] (its x and y
 * coefficients c[0..3], c[4..7]): B'(ta), B'(ta) + (tb - ta) B''(ta)/2,
 * B'(tb), a quadratic Bezier curve inside the cone they span; returns a
 * bound of the sum of their coordinates' magnitudes and of the terms they
 * were summed from. */
static inline __attribute__((always_inline)) double hodograph_cone(const double *c, double ta,
                                                                  double tb, double v[3][2])
{
    double h = tb - ta;
    for (int k = 0; k < 2; k++) {
        const double *b = c + 4 * k; /* x, then y */
        double d1 = b[1] + ta * (2.0 * b[2] + 3.0 * b[3] * ta);
        v[0][k] = d1;
        v[1][k] = d1 + 0.5 * h * (2.0 * b[2] + 6.0 * b[3] * ta);
        v[2][k] = b[1] + tb * (2.0 * b[2] + 3.0 * b[3] * tb);
    }
    double T = dmax(1.0, dmax(fabs(ta), fabs(tb))), mag = 0.0;
    for (int k = 0; k < 2; k++) {
        const double *b = c + 4 * k;
        mag += fabs(b[1]) + T * (4.0 * fabs(b[2]) + 9.0 * T * fabs(b[3]));
    }
    return mag;
}

/* Generators g[k] (k < the count returned) of a cone holding the
 * direction of p's tangent, up to a sign fixed along the piece, over its
 * parameters between t[0] and t[1] (an offset piece), and *s a bound of
 * the sum of their coordinates' magnitudes and of the terms they were
 * summed from.  A line's is its chord.  An offset piece's tangent is
 * m(B') (1 - d k), or m(N) (1/k)' on an evolute, N = (-B'y, B'x)/|B'|
 * (aabench.h): the factors (1 - d k) and (1/k)'/|B'| keep one sign on a
 * piece (no fold or cusp inside), so the tangent is parallel to m(B') or
 * to m(-B'y, B'x) with one sign along it.  Over [ta, tb] a cubic's B' is
 * the quadratic Bezier curve of control points B'(ta), B'(ta) + (tb -
 * ta) B''(ta)/2 and B'(tb), inside the cone they span (its Bernstein
 * weights are >= 0); an ellipse's B' = v cos t - u sin t over less than
 * pi of t is inside the cone of its two ends.  The range is widened by
 * 1e-9 of itself and a few ulps (the rounding of the parameters solved
 * for), and within 1e-6 of the piece's own range of an end of it reaches
 * that end (where the piece's y turns, at a fold or a cusp, the solve for
 * a height is least sure of t), but never beyond.  0 for other kinds or
 * where nothing is bounded. */
static int tangent_cone(const aa_piece *p, const double t[2], double g[3][2], double *s)
{
    if (p->kind == AA_PIECE_LINE) {
        g[0][0] = p->x1 - p->x0, g[0][1] = p->y1 - p->y0;
        *s = fabs(g[0][0]) + fabs(g[0][1]);
        return 1;
    }
    if (p->kind != AA_PIECE_OFFSET || t[0] != t[0] || t[1] != t[1])
        return 0;
    const double *c = p->oc.b, *m = p->oc.m;
    double pl = dmin(p->ot0, p->ot1), ph = dmax(p->ot0, p->ot1);
    double ta = dmin(t[0], t[1]), tb = dmax(t[0], t[1]);
    double w = 1e-9 * (tb - ta) + 1e-15 * (fabs(ta) + fabs(tb)), near = 1e-6 * (ph - pl);
    ta = ta - w - pl <= near ? pl : ta - w;
    tb = ph - (tb + w) <= near ? ph : tb + w;
    double v[3][2], mag;
    int n;
    if (p->oc.base == AA_OFFSET_ELLIPSE) {
        if (!(tb - ta < 3.0))
            return 0;
        double ca = cos(ta), sa = sin(ta), cb = cos(tb), sb = sin(tb);
        v[0][0] = c[4] * ca - c[2] * sa, v[0][1] = c[5] * ca - c[3] * sa;
        v[1][0] = c[4] * cb - c[2] * sb, v[1][1] = c[5] * cb - c[3] * sb;
        mag = fabs(c[2]) + fabs(c[3]) + fabs(c[4]) + fabs(c[5]);
        n = 2;
    } else {
        mag = hodograph_cone(c, ta, tb, v);
        n = 3;
    }
    for (int k = 0; k < n; k++) {
        double vx = p->oc.evolute ? -v[k][1] : v[k][0], vy = p->oc.evolute ? v[k][0] : v[k][1];
        g[k][0] = m[0] * vx + m[2] * vy;
        g[k][1] = m[1] * vx + m[3] * vy;
    }
    *s = mag * (fabs(m[0]) + fabs(m[1]) + fabs(m[2]) + fabs(m[3]));
    return n;
}

/* 1 if x_p - x_q is strictly monotone over the heights where p's
 * parameters lie between tp[0] and tp[1] and q's between tq[0] and
 * tq[1]: the cones of their tangents (tangent_cone) lie strictly on
 * either side of each other, every generator of one turning the same way
 * to every generator of the other (cross products of one sign, beyond
 * 1e-9 of the product of their bounds: far beyond their rounding).  Then
 * dx_p/dy - dx_q/dy, the cross product of the two tangents over the
 * product of their y components (each of one sign inside a piece), keeps
 * one sign. */
static int cones_apart(const aa_piece *p, const aa_piece *q, const double tp[2],
                       const double tq[2])
{
    double gp[3][2], gq[3][2], sp, sq;
    int np = tangent_cone(p, tp, gp, &sp), nq = np ? tangent_cone(q, tq, gq, &sq) : 0;
    if (!nq)
        return 0;
    double e = 1e-9 * sp * sq;
    int pos = 0, neg = 0;
    for (int i = 0; i < np; i++)
        for (int k = 0; k < nq; k++) {
            double x = gp[i][0] * gq[k][1] - gp[i][1] * gq[k][0];
            pos += x > e, neg += x < -e;
        }
    return pos == np * nq || neg == np * nq;
}

int aa__piece_cones_apart(const aa_piece *p, const aa_piece *q, const double tp[2],
                          const double tq[2])
{
    return cones_apart(p, q, tp, tq);
}

/* 1 if offset pieces p and q are the two sides of one stroke, proven never
 * to meet: the offsets O+ = B + d N and O- = B - d N (aabench.h; the same
 * base cubic b and map m, distances d and -d, d != 0, neither an evolute)
 * over parameter ranges whose hull [ta, tb] has B' inside a cone narrower
 * than pi/2.  The proof, in the base's own coordinates (m is one to one:
 * its determinant is not 0, so it keeps meetings): if O+(s) = O-(t), then
 * B(t) - B(s) = d (N(s) + N(t)); s = t would give 2 d N(s) = 0, so s !=
 * t.  With theta(u) the angle of B'(u) (continuous: B' is never 0 in the
 * cone) and phi = (theta(s) + theta(t))/2, N(s) + N(t) = 2 cos((theta(t)
 * - theta(s))/2) N(phi) is normal to T(phi) = (cos phi, sin phi), while
 * (B(t) - B(s)) . T(phi) is the integral over [s, t] of |B'(u)|
 * cos(theta(u) - phi).  Every theta(u) on [ta, tb], theta(s) and
 * theta(t) among them, lies in the cone's range of angles, narrower than
 * pi/2, so |theta(u) - phi| < pi/2 and the integral is not 0: no meeting.
 * B' over [ta, tb] is the quadratic Bezier curve of control vectors
 * B'(ta), B'(ta) + (tb - ta) B''(ta)/2, B'(tb) (hodograph_cone's), inside
 * the cone they span (its Bernstein weights are >= 0), which is narrower
 * than pi/2 when each two of them have a positive dot product (three
 * vectors so, the angles between them each below pi/2, do not go round
 * the origin, and the widest angle between two of them is the cone's):
 * asked beyond 1e-9 of the square of the bound of the terms they were
 * summed from (cones_apart's margin), far beyond their rounding, and m's
 * determinant beyond 1e-12 of its terms.  A stroke's two sides come this
 * near (their x extents overlapping in a band) only where it is narrower
 * than a band is high (a pixel): at 2.5 px, as tests/bench_bezstroke.c's,
 * such a pair is never asked (counted at 32 to 1024 px); at 0.5 px 9,458
 * asks a render at 1024 px (2,727 at 256 px), which the tangents' cones,
 * nearly parallel on the two sides, seldom part (11,154 calls of
 * subdivide_offset a render, 3,423 at 256 px).  Asked by
 * subdivide_offset where the cones decide nothing over the pair's common
 * heights. */
static __attribute__((noinline)) int sides_apart(const aa_piece *p, const aa_piece *q)
{
    if (p->kind != AA_PIECE_OFFSET || q->kind != AA_PIECE_OFFSET || p->oc.d != -q->oc.d ||
        p->oc.d == 0.0 || p->oc.evolute || q->oc.evolute || p->oc.base != AA_OFFSET_CUBIC ||
        q->oc.base != AA_OFFSET_CUBIC || memcmp(p->oc.b, q->oc.b, sizeof p->oc.b) ||
        memcmp(p->oc.m, q->oc.m, sizeof p->oc.m))
        return 0;
    const double *c = p->oc.b, *m = p->oc.m;
    double det = m[0] * m[3] - m[1] * m[2];
    if (!(fabs(det) > 1e-12 * (fabs(m[0] * m[3]) + fabs(m[1] * m[2]))))
        return 0;
    double ta = dmin(dmin(p->ot0, p->ot1), dmin(q->ot0, q->ot1));
    double tb = dmax(dmax(p->ot0, p->ot1), dmax(q->ot0, q->ot1)), v[3][2];
    double mag = hodograph_cone(c, ta, tb, v), e = 1e-9 * mag * mag;
    return v[0][0] * v[1][0] + v[0][1] * v[1][1] > e && v[0][0] * v[2][0] + v[0][1] * v[2][1] > e &&
           v[1][0] * v[2][0] + v[1][1] * v[2][1] > e;
}

int aa__piece_sides_apart(const aa_piece *p, const aa_piece *q)
{
    return sides_apart(p, q);
}

/* What the tangents' cones tell of p and q on [a, b] (area's form), with
 * x_p - x_q strictly monotone there (cones_apart): 1 if they meet nowhere
 * but at an end point they share there (x_p - x_q exactly 0 at that end,
 * the shared vertex) or x_p - x_q is of one sign beyond the rounding
 * margin of x at both ends; 2 if of opposite signs beyond it at the two
 * ends (exactly one meeting, polished as slopes_say's ONE); 0 if nothing
 * is proven; 3 at an end point they share where they are not tested (see
 * below).  One test of at most 3 x 3 generators where range_at's and
 * slopes_say's extents and slopes (the x turns and the roots of two
 * quadratics a piece) took several times the instructions, and decides
 * too where a piece turns horizontal at an end, its slope unbounded.  At
 * an end point they share only a line and an offset piece that is not an
 * evolute are tested: the outline's other pieces leave the vertices they
 * share tangent to each other (smooth and round joins, an evolute and the
 * normal line that ends on it, two evolutes at a cusp), where no cone
 * parts them (on tests/bench_bezstroke.c's scene at 256 px 8 of 8,288
 * pairs of a line and an evolute were parted there, none of 2,002 pairs
 * of offset pieces), nor their extents or slopes: subdivide_offset cuts
 * that end off at once (shared_end_cut), and the rest, away from the end,
 * is parted by the cones (two asks a pair, where the extents' and slopes'
 * tests before the cut took a third of the time). */
static int cones_decide(const meet_ctx *c, double a, double b, const double tp[2],
                        const double tq[2], const double xp[2], const double xq[2])
{
    int shared = (a == c->lo && c->lo_shared) || (b == c->hi && c->hi_shared);
    if (shared && !(c->p->kind == AA_PIECE_LINE && c->q->kind == AA_PIECE_OFFSET &&
                    !c->q->oc.evolute))
        return 3;
    int one = 0;
    if (!shared) {
        double da = xp[0] - xq[0], db = xp[1] - xq[1];
        double tol = 8.0 * DBL_EPSILON * dmax(1.0, dmax(dmax(fabs(xp[0]), fabs(xp[1])),
                                                        dmax(fabs(xq[0]), fabs(xq[1]))));
        one = (da > tol && db < -tol) || (da < -tol && db > tol);
        if (!((da > tol && db > tol) || (da < -tol && db < -tol) || one))
            return 0;
    }
    return cones_apart(c->p, c->q, tp, tq) ? 1 + one : 0;
}

/* 1 if line p and evolute q (c's) both end within rounding of an end of
 * their common heights where their x (xp, xq at lo and hi) are within
 * rounding of each other, that end not yet taken as shared: the end point
 * they share, each copy rounded its own way; it is then taken as shared
 * (c->lo_shared, c->hi_shared).  The normal line that ends a folding
 * offset's region ends on its evolute, tangent to it there, and where the
 * two copies of that point are an ulp apart (in y or in x: the line's end
 * and the evolute piece's, found apart), the two cross next to it (the
 * line leaves the evolute's tangent by the ulp, the evolute leaves the
 * tangent as the square of the distance), where no cone or slope parts
 * them: such a pair was halved down to 1e-6 of the scale, 13 to 45 calls
 * to depth 6 to 22, and reported that crossing, 1e-11 to 9e-7 px from the
 * end.  Taken as shared, the end is cut off at once (shared_end_cut), and
 * a meeting within 2 cut of it is the end itself, as at an end both
 * pieces copy exactly.  Asked by subdivide_offset (area's form) where the
 * cones decide nothing over the pair's common heights.  On the 1,000
 * stroked cubics of tests/bench_bezstroke.c at 256 px, 158 such pairs a
 * render, their calls of subdivide_offset 5,230 to 316 (none at 1024 px). */
static __attribute__((noinline)) int ends_touch(meet_ctx *c, const double xp[2],
                                                const double xq[2])
{
    const aa_piece *p = c->p, *q = c->q;
    int n = 0;
    for (int e = 0; e < 2; e++) {
        double y = e ? c->hi : c->lo;
        double tol = 8.0 * DBL_EPSILON * dmax(1.0, dmax(fabs(y), fabs(xq[e])));
        int *shared = e ? &c->hi_shared : &c->lo_shared;
        if (!*shared && fabs(xp[e] - xq[e]) <= tol &&
            (fabs(p->y0 - y) <= tol || fabs(p->y1 - y) <= tol) &&
            (fabs(q->y0 - y) <= tol || fabs(q->y1 - y) <= tol))
            *shared = 1, n++;
    }
    return n > 0;
}

static void subdivide_offset(meet_ctx *c, double a, double b, const double tp[2],
                             const double tq[2], const double xp[2], const double xq[2],
                             int depth)
{
    double pa, pb, qa, qb;
    if (c->n >= c->max || --c->budget < 0)
        return;
    /* area's form: the tangents' cones first (cones_decide), and an end
     * point shared by pieces tangent there cut off at once */
    int cd = c->quick ? cones_decide(c, a, b, tp, tq, xp, xq) : 0;
    /* a stroke's two sides where the cones part nothing: proven apart */
    if (cd == 1 || (cd == 0 && c->quick && depth == 0 && c->p->oc.d == -c->q->oc.d &&
                    c->p->oc.d != 0.0 && sides_apart(c->p, c->q)))
        return;
    if (cd == 0 && depth == 0 && c->quick && c->p->kind == AA_PIECE_LINE &&
        c->q->kind == AA_PIECE_OFFSET && c->q->oc.evolute && ends_touch(c, xp, xq))
        cd = 3;
    if (cd == 2) {
        record_meet(c, polish_meet(c->p, c->q, a, b, xp[0] - xq[0], xp[1] - xq[1],
                                   offset_t(c->p, tp), offset_t(c->q, tq), c->quick),
                    dmax(1.0, fabs(0.5 * (a + b))));
        return;
    }
    if (cd == 3) {
        double cut = 0.5e-6 * dmax(1.0, dmin(fabs(a), fabs(b)));
        int e = a == c->lo && c->lo_shared && a + cut > a
                    ? 0
                    : (b == c->hi && c->hi_shared && b - cut < b ? 1 : -1);
        if (e >= 0 && b - a > 4.0 * cut && depth < 60) {
            shared_end_cut(c, a, b, tp, tq, xp, xq, e, cut, depth);
            return;
        }
    }
    range_at(c->p, a, b, tp, xp, &pa, &pb);
    range_at(c->q, a, b, tq, xq, &qa, &qb);
    double tol = 8.0 * DBL_EPSILON *
                 dmax(1.0, dmax(dmax(fabs(pa), fabs(pb)), dmax(fabs(qa), fabs(qb))));
    if (pb < qa - tol || qb < pa - tol || part_at_end(c, a, b, tp, tq, xp, xq, tol))
        return;
    double m = 0.5 * (a + b), scale = dmax(1.0, fabs(m)), da;
    switch (slopes_say(c->p, c->q, a, b, tp, tq, xp, xq, tol, 1e-12 * scale, 1e-15, &da)) {
    case APART:
    case NEAR:
        return;
    case ONE:
        record_meet(c, polish_meet(c->p, c->q, a, b, da, xp[1] - xq[1], offset_t(c->p, tp),
                                   offset_t(c->q, tq), c->quick),
                    scale);
        return;
    case AT_A: /* within rounding of a: a shared end, or a meeting there */
        if (!near_shared_end(c, a, a, scale))
            record_meet(c, a, scale);
        return;
    case AT_B:
        if (!near_shared_end(c, b, b, scale))
            record_meet(c, b, scale);
        return;
    default:
        break;
    }
    if (b - a <= 1e-6 * scale) {
        double fa = xp[0] - xq[0], fb = xp[1] - xq[1];
        if (near_shared_end(c, a, b, scale) && !crosses_beyond(fa, fb, tol))
            return;
        if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
            record_meet(c, polish_meet(c->p, c->q, a, b, fa, fb, offset_t(c->p, tp),
                                       offset_t(c->q, tq), c->quick),
                        scale);
            return;
        }
    }
    if (depth >= 60 || b - a <= 1e-12 * scale || !(m > a && m < b)) {
        record_meet(c, m, scale);
        return;
    }
    /* Next to an end point both pieces share, cut off the interval of 1/2
     * the resolution next to it instead of halving.  Two pieces leaving it
     * tangent to each other (where a stroke's offset folds, an evolute and
     * the normal line that ends on it, which is its tangent there; two
     * evolutes of consecutive arcs) differ in x by about the square of the
     * distance from it, so neither their slopes nor their difference at
     * the ends part them on an interval touching it, and halving took ten
     * levels (two solves each) to reach the width at which the end itself
     * is known (b - a <= 1e-6 scale, above).  That width is cut off at
     * once (the same rule decides it), and the rest, away from the end, is
     * parted by the slopes, now of one sign there.  Area's form
     * (c->quick) does not ask the part cut off at all (shared_end_cut). */
    double cut = 0.5e-6 * dmax(1.0, dmin(fabs(a), fabs(b)));
    if (b - a > 4.0 * cut) {
        int e = a == c->lo && c->lo_shared && a + cut > a
                    ? 0
                    : (b == c->hi && c->hi_shared && b - cut < b ? 1 : -1);
        if (e >= 0 && c->quick) {
            shared_end_cut(c, a, b, tp, tq, xp, xq, e, cut, depth);
            return;
        }
        if (e >= 0)
            m = e ? b - cut : a + cut;
    }
    double pm = param_within(c->p, m, a, tp), qm = param_within(c->q, m, a, tq);
    double xpm = end_x(c->p, m, pm), xqm = end_x(c->q, m, qm);
    const double lp[2] = {tp[0], pm}, rp[2] = {pm, tp[1]};
    const double lq[2] = {tq[0], qm}, rq[2] = {qm, tq[1]};
    const double lxp[2] = {xp[0], xpm}, rxp[2] = {xpm, xp[1]};
    const double lxq[2] = {xq[0], xqm}, rxq[2] = {xqm, xq[1]};
    subdivide_offset(c, a, m, lp, lq, lxp, lxq, depth + 1);
    subdivide_offset(c, m, b, rp, rq, rxp, rxq, depth + 1);
}

/* 1 if p and q are the same curve over the same heights (a path tracing an
 * arc twice): their x agree at every height, so no meeting separates them,
 * and their windings simply add wherever they lie. */
static int same_curve(const aa_piece *p, const aa_piece *q)
{
    if (p->kind != q->kind || p->y0 != q->y0 || p->y1 != q->y1 || p->x0 != q->x0 ||
        p->x1 != q->x1)
        return 0;
    switch (p->kind) {
    case AA_PIECE_LINE:
        return 1;
    case AA_PIECE_QUAD:
        return p->cx == q->cx && p->cy == q->cy;
    case AA_PIECE_CUBIC:
        return p->cx == q->cx && p->cy == q->cy && p->c2x == q->c2x && p->c2y == q->c2y;
    case AA_PIECE_CONIC:
        return p->ex == q->ex && p->ey == q->ey && p->er == q->er && p->ea == q->ea &&
               p->eb == q->eb;
    case AA_PIECE_OFFSET: /* one curve over the same parameters */
        return p->ot0 == q->ot0 && p->ot1 == q->ot1 && !memcmp(&p->oc, &q->oc, sizeof p->oc);
    default:
        return 0;
    }
}

static int meet_pair(const aa_piece *p, const aa_piece *q, double ya, double yb,
                     const double tpa[2], const double tqa[2], const double xpa[2],
                     const double xqa[2], double *ys, int max, int quick);

int aa_piece_meet(const aa_piece *p, const aa_piece *q, double ya, double yb, double *ys, int max)
{
    const double none[2] = {NAN, NAN};
    return meet_pair(p, q, ya, yb, none, none, none, none, ys, max, 0);
}

int aa__piece_meet_at(const aa_piece *p, const aa_piece *q, double ya, double yb,
                      const double tpa[2], const double tqa[2], double *ys, int max)
{
    const double none[2] = {NAN, NAN};
    return meet_pair(p, q, ya, yb, tpa, tqa, none, none, ys, max, 1);
}

int aa__piece_meet_atx(const aa_piece *p, const aa_piece *q, double ya, double yb,
                       const double tpa[2], const double tqa[2], const double xpa[2],
                       const double xqa[2], double *ys, int max)
{
    return meet_pair(p, q, ya, yb, tpa, tqa, xpa, xqa, ys, max, 1);
}

double aa__piece_end_x(const aa_piece *p, double y, double t)
{
    return end_x(p, y, t);
}

/* An offset piece's parameter at height y, lo or hi of the pair's common
 * heights: at[0] where y is ya, at[1] where it is yb, if known (not NaN),
 * else solved for (param_at). */
static double param_known(const aa_piece *p, double y, double ya, double yb, const double at[2])
{
    if (p->kind != AA_PIECE_OFFSET)
        return 0.0;
    if (y == ya && at[0] == at[0])
        return at[0];
    if (y == yb && at[1] == at[1])
        return at[1];
    return param_at(p, y);
}

/* x of p at height y, lo or hi of the pair's common heights, its
 * parameter there t: at[0] where y is ya, at[1] where it is yb, if known
 * (not NaN; the caller's end_x at the parameter it passed there, so the
 * same bits), else end_x. */
static inline double x_known(const aa_piece *p, double y, double t, double ya, double yb,
                             const double at[2])
{
    if (y == ya && at[0] == at[0])
        return at[0];
    if (y == yb && at[1] == at[1])
        return at[1];
    return end_x(p, y, t);
}

static int meet_pair(const aa_piece *p, const aa_piece *q, double ya, double yb,
                     const double tpa[2], const double tqa[2], const double xpa[2],
                     const double xqa[2], double *ys, int max, int quick)
{
    if (!p->dir || !q->dir || max < 1)
        return 0;
    double lo = dmax(dmax(p->y0, q->y0), ya), hi = dmin(dmin(p->y1, q->y1), yb);
    if (!(lo < hi))
        return 0;
    int conic = p->kind == AA_PIECE_CONIC || q->kind == AA_PIECE_CONIC;
    int cubic = p->kind == AA_PIECE_CUBIC || q->kind == AA_PIECE_CUBIC || conic ||
                p->kind == AA_PIECE_OFFSET || q->kind == AA_PIECE_OFFSET;
    if (p->ay == 0.0 && q->ay == 0.0 && !cubic) {
        /* both x quadratic in y: their difference is a quadratic */
        double a0, a1, a2, b0, b1, b2, u[2];
        x_in_u(p, lo, &a0, &a1, &a2);
        x_in_u(q, lo, &b0, &b1, &b2);
        int n = quadratic_roots(a2 - b2, a1 - b1, a0 - b0, hi - lo, u), m = 0;
        if (n == 2 && u[0] > u[1]) {
            double t = u[0];
            u[0] = u[1], u[1] = t;
        }
        for (int k = 0; k < n && m < max; k++)
            ys[m++] = lo + u[k];
        return m;
    }
    if (p->kind != AA_PIECE_LINE && q->kind == AA_PIECE_LINE) {
        const aa_piece *t = p;
        const double *ta = tpa, *xa = xpa;
        p = q, q = t;
        tpa = tqa, tqa = ta;
        xpa = xqa, xqa = xa;
    }
    if (same_curve(p, q))
        return 0; /* they meet everywhere: no meeting isolates them */
    meet_ctx c = {p, q, ys, 0, max, 4096, lo, hi, 0, 0, -INFINITY, INFINITY, quick};
    /* pieces of one outline meet end to end at its vertices */
    int lo_ends = (lo == p->y0 || lo == p->y1) && (lo == q->y0 || lo == q->y1);
    int hi_ends = (hi == p->y0 || hi == p->y1) && (hi == q->y0 || hi == q->y1);
    /* the same at the common rows' ends when [ya, yb] stops short of them */
    double top = dmax(p->y0, q->y0), bot = dmin(p->y1, q->y1);
    if (top == p->y0 && top == q->y0 && aa_piece_x_at(p, top) == aa_piece_x_at(q, top))
        c.end_lo = top;
    if (bot == p->y1 && bot == q->y1 && aa_piece_x_at(p, bot) == aa_piece_x_at(q, bot))
        c.end_hi = bot;
    int near_end = lo - c.end_lo <= 1e-6 * dmax(1.0, fabs(lo)) ||
                   c.end_hi - hi <= 1e-6 * dmax(1.0, fabs(hi));
    if (p->kind == AA_PIECE_OFFSET || q->kind == AA_PIECE_OFFSET) {
        /* the ends' parameters and x, found once (aa_piece_x_at of an
         * offset piece is offset_x at offset_t_at, param_at's parameter) */
        const double tp[2] = {param_known(p, lo, ya, yb, tpa), param_known(p, hi, ya, yb, tpa)};
        const double tq[2] = {param_known(q, lo, ya, yb, tqa), param_known(q, hi, ya, yb, tqa)};
        const double xp[2] = {x_known(p, lo, tp[0], ya, yb, xpa),
                              x_known(p, hi, tp[1], ya, yb, xpa)};
        const double xq[2] = {x_known(q, lo, tq[0], ya, yb, xqa),
                              x_known(q, hi, tq[1], ya, yb, xqa)};
        c.lo_shared = lo_ends && xp[0] == xq[0];
        c.hi_shared = hi_ends && xp[1] == xq[1];
        subdivide_offset(&c, lo, hi, tp, tq, xp, xq, 0);
        return c.n;
    }
    c.lo_shared = lo_ends && aa_piece_x_at(p, lo) == aa_piece_x_at(q, lo);
    c.hi_shared = hi_ends && aa_piece_x_at(p, hi) == aa_piece_x_at(q, hi);
    if (p->kind == AA_PIECE_LINE && q->kind == AA_PIECE_CONIC)
        return line_conic(p, q, lo, hi, ys, max);
    if (p->kind == AA_PIECE_LINE && q->kind == AA_PIECE_CUBIC) {
        /* cubic q(t) against line p, x = p.x0 + (y - p.y0) s: a cubic in t */
        double s = p->bx / p->by, ts[3], y[3];
        double k[4] = {q->x0 - p->x0 - (q->y0 - p->y0) * s, q->bx - s * q->by,
                       q->ax - s * q->ay, q->dx - s * q->dy};
        int n = aa__poly3_roots(k, 0.0, 1.0, ts), m = 0;
        n = heights(q, ts, n, y);
        for (int j = 0; j < n && m < max; j++)
            if (y[j] > lo && y[j] < hi)
                ys[m++] = y[j];
        return m;
    }
    if (p->kind == AA_PIECE_LINE) {
        /* arc q(t) against line p, x = p.x0 + (y - p.y0) s: a quadratic in t */
        double s = p->bx / p->by, ts[2];
        double a = q->ax - s * q->ay, b = q->bx - s * q->by;
        double k0 = q->x0 - p->x0 - (q->y0 - p->y0) * s;
        int n = quadratic_roots(a, b, k0, 1.0, ts), m = 0;
        double y[2];
        for (int k = 0; k < n; k++) {
            double v = q->y0 + ts[k] * (q->by + ts[k] * q->ay);
            if (v > lo && v < hi)
                y[m++] = v;
        }
        if (m == 2 && y[0] > y[1]) {
            double t = y[0];
            y[0] = y[1], y[1] = t;
        }
        for (int k = 0; k < m && k < max; k++)
            ys[k] = y[k];
        return m < max ? m : max;
    }
    /* two general arcs (a quartic): bisection on exact extents; but arcs
     * that leave a common end point tangent to each other run side by side
     * near it, within rounding in x over a band of heights whose boxes in
     * x always overlap: the slopes' test of offset pairs parts them */
    if (c.lo_shared || c.hi_shared || near_end) {
        const double t0[2] = {0.0, 0.0};
        const double xp[2] = {aa_piece_x_at(p, lo), aa_piece_x_at(p, hi)};
        const double xq[2] = {aa_piece_x_at(q, lo), aa_piece_x_at(q, hi)};
        subdivide_offset(&c, lo, hi, t0, t0, xp, xq, 0);
    } else if (cubic)
        subdivide_cubic(&c, lo, hi, 0);
    else
        subdivide(&c, lo, hi, 0);
    return c.n;
}
