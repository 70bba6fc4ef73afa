/*
 * truth_local.c: the pieces of a pixel's window in extended precision,
 * which the three integration paths of the reference share (truth.c,
 * truth_crowd.c, truth_gauss.c; truth_internal.h): a piece relative to the
 * pixel's centre (a conic piece in its angle form), where it meets a line,
 * where it crosses a circle and where it passes closest to the centre
 * (radial filters), which of its ends turn, the size of its numbers; a
 * conic piece as a rational quadratic in the tangent of the half angle;
 * the sign changes of a polynomial; and whether long double is wider than
 * double here.
 */
#include "truth_internal.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>
#include <math.h>

int aa_long_double_is_extended(void)
{
    volatile long double one = 1.0L, tiny = 0x1p-60L;
    return one + tiny != one;
}

int truth_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

static long double peval(const long double *p, int d, long double t)
{
    long double r = p[d];
    for (int k = d - 1; k >= 0; k--)
        r = r * t + p[k];
    return r;
}

/* truth_sign_roots: between consecutive extrema (the roots of its
 * derivative, found the same way) the polynomial is monotone, and
 * bisection in long double finds each crossing. */
int truth_sign_roots(const long double *p, int d, long double lo, long double hi,
                     long double *r)
{
    while (d > 0 && p[d] == 0)
        d--;
    if (d == 0)
        return 0;
    long double dp[6], crit[6];
    for (int k = 0; k < d; k++)
        dp[k] = (k + 1) * p[k + 1];
    int m = d > 1 ? truth_sign_roots(dp, d - 1, lo, hi, crit) : 0, n = 0;
    long double a = lo, fa = peval(p, d, lo);
    for (int k = 0; k <= m; k++) {
        long double b = k < m ? crit[k] : hi, fb = peval(p, d, b);
        if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
            long double x = a, y = b, fx = fa;
            for (int it = 0; it < 128; it++) {
                long double mid = 0.5L * (x + y);
                if (!(mid > x && mid < y))
                    break;
                long double fm = peval(p, d, mid);
                if (fm == 0) {
                    x = y = mid;
                    break;
                }
                if ((fm < 0) == (fx < 0))
                    x = mid, fx = fm;
                else
                    y = mid;
            }
            r[n++] = 0.5L * (x + y);
        }
        a = b, fa = fb;
    }
    return n;
}

/* A conic end counts as a turning point within this angle of the
 * ellipse's extreme (0 or pi): there x - x_end ~ sqrt(|y - y_end|), and
 * near it nearly so; integrating in u = sqrt(|v - v_end|) is harmless
 * where x is smooth in v (x(v_end + u^2) is then smooth in u). */
#define TURN_ANGLE 1e-2

void truth_turns(const aa_piece *p, int *lo, int *hi)
{
    *lo = *hi = 0;
    if (p->kind == AA_PIECE_QUAD || p->kind == AA_PIECE_CUBIC) {
        double tiny = 1e-12 * (p->y1 - p->y0);
        *lo = fabs(p->by) <= tiny;
        *hi = fabs(p->by + 2.0 * p->ay + 3.0 * p->dy) <= tiny;
    } else if (p->kind == AA_PIECE_CONIC) {
        *lo = p->s0 <= TURN_ANGLE;
        *hi = p->s1 >= M_PI - TURN_ANGLE;
    } else if (p->kind == AA_PIECE_OFFSET) {
        /* an end at a y turn, a fold of the offset or a cusp of the
         * evolute: dy/dt vanishes there (to rounding) */
        double x, y, dx, dy, slope = (p->y1 - p->y0) / fabs(p->ot1 - p->ot0);
        aa_offset_point(&p->oc, p->ot0, &x, &y, &dx, &dy);
        *lo = fabs(dy) <= 1e-6 * slope;
        aa_offset_point(&p->oc, p->ot1, &x, &y, &dx, &dy);
        *hi = fabs(dy) <= 1e-6 * slope;
    }
}

long double truth_offset_part(const local_piece *q, long double s)
{
    const aa_piece *p = q->src;
    if (!(s > q->y0))
        return p->x0 - q->uc;
    if (!(s < q->y1))
        return p->x1 - q->uc;
    long double y = q->vc + s, x;
    /* the start: the last crossing's parameter moved by its dt/dy times
     * the change of height (one Newton step ahead, and none evaluated) */
    double slope = 0, guess = q->hint + (double)(s - q->hint_s) / q->hint_slope;
    long double t = aa__offset_root(&p->oc, 1, p->ot0, p->ot1, (long double)p->y0 - y, y,
                                    isfinite(guess) ? guess : q->hint, &x, &slope);
    /* q belongs to the calling thread's window (not const there) */
    local_piece *w = (local_piece *)q;
    w->hint = (double)t;
    w->hint_s = (double)s;
    w->hint_slope = slope;
    return x - q->uc;
}

/* An offset piece's point at parameter t relative to (uc, vc). */
static void offset_local(const local_piece *q, long double t, long double *x, long double *y)
{
    aa__offset_eval(&q->src->oc, t, x, y, NULL, NULL);
    *x -= q->uc;
    *y -= q->vc;
}

/* An offset piece's part in the rows [lo, hi] (relative): its parameters. */
static int offset_span(const local_piece *q, double lo, double hi, long double *ta,
                       long double *tb)
{
    const aa_piece *p = q->src;
    long double a = fmaxl(lo, q->y0), b = fminl(hi, q->y1);
    if (!(a < b))
        return 0;
    *ta = a <= q->y0 ? p->ot0
                     : aa__offset_solve(&p->oc, 1, p->ot0, p->ot1, p->y0 - (q->vc + a), q->vc + a);
    *tb = b >= q->y1 ? p->ot1
                     : aa__offset_solve(&p->oc, 1, p->ot0, p->ot1, p->y0 - (q->vc + b), q->vc + b);
    return 1;
}

/* truth_offset_side: y is monotone along the piece, so its part in the
 * rows is the parameters between those at lo and hi (solved for to long
 * double precision, as its crossings are), and its x extent there is that
 * at those ends and at the x turns between (closed form).  Its crossings
 * on those rows are x at parameters inside.  An extent that reaches the
 * window's side within 4 DBL_EPSILON still counts (a row's ends are often
 * where the piece crosses the side, a breakpoint): a crossing taken for
 * outside is then within that of the side, and over the rows (at most 2R
 * high) moves the pixel by at most 8 DBL_EPSILON R times the filter's
 * peak, within the 8 DBL_EPSILON max(R, 1) times the peak its bound
 * already allows each piece (truth.c, integrate_pixel: a crossing's
 * rounding to double); the extent's own rounding is that of the
 * crossings, in long double, which the bound allows too. */
/* An offset piece's parameter and x (relative) at relative height s in its
 * rows, for truth_offset_side: its ends as they are, else solved for from
 * its last crossing, the last height asked kept (the next rows start
 * there). */
static void offset_end(local_piece *q, long double s, long double *t, long double *x)
{
    const aa_piece *p = q->src;
    if (!(s > q->y0)) {
        *t = p->ot0, *x = p->x0 - q->uc;
    } else if (!(s < q->y1)) {
        *t = p->ot1, *x = p->x1 - q->uc;
    } else if (s == q->end_s) {
        *t = q->end_t, *x = q->end_x;
    } else {
        long double y = q->vc + s;
        *t = aa__offset_root(&p->oc, 1, p->ot0, p->ot1, (long double)p->y0 - y, y, q->hint, x,
                             NULL);
        *x -= q->uc;
        q->end_s = s, q->end_t = *t, q->end_x = *x;
    }
}

int truth_offset_side(local_piece *q, double lo, double hi, double R)
{
    long double a = fmaxl(lo, q->y0), b = fminl(hi, q->y1), ta, tb, xa, xb, x, y;
    if (!(a < b))
        return 0;
    offset_end(q, a, &ta, &xa);
    offset_end(q, b, &tb, &xb);
    long double xmin = fminl(xa, xb), xmax = fmaxl(xa, xb);
    double ts[2];
    int n = aa__offset_turns(&q->src->oc, 0, (double)fminl(ta, tb), (double)fmaxl(ta, tb), ts);
    for (int k = 0; k < n; k++) {
        offset_local(q, ts[k], &x, &y);
        xmin = fminl(xmin, x), xmax = fmaxl(xmax, x);
    }
    long double margin = 4 * DBL_EPSILON;
    if (xmax <= -R + margin)
        return -1;
    if (xmin >= R - margin)
        return 1;
    return 0;
}

#define OFFSET_SAMPLES 64

/* Radial filters on an offset piece: the heights where it crosses the
 * circle of radius R, by the sign changes of |P|^2 - R^2 at OFFSET_SAMPLES
 * points of its part in the disc's rows, each bisected in long double.  A
 * pair of crossings closer than the sampling is missed; the kink is then
 * left inside an interval, where QAG's bisection still finds it. */
static int circle_heights_offset(const local_piece *q, double R, double out[4])
{
    long double ta, tb;
    if (!offset_span(q, -R, R, &ta, &tb))
        return 0;
    int m = 0;
    long double x, y, pt = ta;
    offset_local(q, ta, &x, &y);
    long double pf = x * x + y * y - (long double)R * R;
    for (int k = 1; k <= OFFSET_SAMPLES && m < 4; k++) {
        long double t = ta + (tb - ta) * k / OFFSET_SAMPLES;
        offset_local(q, t, &x, &y);
        long double f = x * x + y * y - (long double)R * R;
        if ((pf < 0 && f > 0) || (pf > 0 && f < 0)) {
            long double a = pt, b = t, fa = pf;
            for (int it = 0; it < 80; it++) {
                long double mid = 0.5L * (a + b), fm;
                offset_local(q, mid, &x, &y);
                fm = x * x + y * y - (long double)R * R;
                if ((fm < 0) == (fa < 0))
                    a = mid, fa = fm;
                else
                    b = mid;
            }
            offset_local(q, 0.5L * (a + b), &x, &y);
            out[m++] = (double)y;
        }
        pt = t, pf = f;
    }
    return m;
}

/* The height where an offset piece passes closest to the centre inside
 * (lo, hi) and within R: the least of |P|^2 at OFFSET_SAMPLES points,
 * refined by golden-section search between its neighbours. */
static double nearest_offset(const local_piece *q, double lo, double hi, double R)
{
    long double ta, tb, x, y;
    if (!offset_span(q, lo, hi, &ta, &tb))
        return NAN;
    int best = 0;
    long double bd = INFINITY;
    for (int k = 0; k <= OFFSET_SAMPLES; k++) {
        offset_local(q, ta + (tb - ta) * k / OFFSET_SAMPLES, &x, &y);
        long double d = x * x + y * y;
        if (d < bd)
            bd = d, best = k;
    }
    long double a = ta + (tb - ta) * (best > 0 ? best - 1 : 0) / OFFSET_SAMPLES;
    long double b = ta + (tb - ta) * (best < OFFSET_SAMPLES ? best + 1 : best) / OFFSET_SAMPLES;
    const long double g = 0.6180339887498948482L;
    for (int it = 0; it < 100; it++) {
        long double c = b - g * (b - a), d = a + g * (b - a), xc, yc, xd, yd;
        offset_local(q, c, &xc, &yc);
        offset_local(q, d, &xd, &yd);
        if (xc * xc + yc * yc < xd * xd + yd * yd)
            b = d;
        else
            a = c;
    }
    offset_local(q, 0.5L * (a + b), &x, &y);
    if (!(x * x + y * y < (long double)R * R) || !(y > lo && y < hi) || y == 0)
        return NAN;
    return (double)y;
}

/* The angle of conic q at relative height s (inside its rows): a =
 * 2 atan(sqrt((1 - c)/(1 + c))), the two factors taken directly. */
static long double conic_angle(const local_piece *q, long double s)
{
    long double lo = s - q->top, hi = q->bot - s;
    return 2 * atan2l(sqrtl(lo > 0 ? lo : 0), sqrtl(hi > 0 ? hi : 0));
}

/* With a = am + phi and t = tan(phi/2), w = 1 + t^2:
 *     w cos a = C (1 - t^2) - 2 S t,   w sin a = S (1 - t^2) + 2 C t
 * (C = cos am, S = sin am), so
 *     w (x0 + ea cos a + eb sin a) = (x0 + ea C + eb S) + 2 (eb C - ea S) t
 *                                    + (x0 - ea C - eb S) t^2,
 *     w (ey - er cos a) = (ey - er C) + 2 er S t + (ey + er C) t^2.
 * |phi| <= (a_hi - a_lo)/2 <= pi/2, so |t| <= 1. */
int truth_conic_rational(const local_piece *q, long double lo, long double hi,
                         conic_rational *r)
{
    lo = lo > q->y0 ? lo : q->y0;
    hi = hi < q->y1 ? hi : q->y1;
    if (!(lo < hi))
        return 0;
    long double al = lo <= q->y0 ? q->a0 : conic_angle(q, lo);
    long double ah = hi >= q->y1 ? q->a1 : conic_angle(q, hi);
    if (!(al < ah))
        return 0;
    long double am = 0.5L * (al + ah), C = cosl(am), S = sinl(am);
    long double ec = q->ea * C + q->eb * S, ez = q->er * C;
    r->am = am;
    r->T = tanl(0.25L * (ah - al));
    r->qx[0] = q->x0 + ec;
    r->qx[1] = 2 * (q->eb * C - q->ea * S);
    r->qx[2] = q->x0 - ec;
    r->qy[0] = q->ey - ez;
    r->qy[1] = 2 * q->er * S;
    r->qy[2] = q->ey + ez;
    return 1;
}

/* A conic piece: |(x, y) - centre|^2 = R^2 times (1 + t^2)^2 is
 *     qx(t)^2 + qy(t)^2 - R^2 (1 + t^2)^2 = 0,
 * a quartic in t on [-T, T] (truth_conic_rational over the disc's rows),
 * whose sign changes truth_sign_roots brackets and bisects; the heights
 * are qy(t)/(1 + t^2).  A touch (a double root) is no kink. */
static int circle_heights_conic(const aa_piece *p, double uc, double vc, double R,
                                double out[4])
{
    local_piece q;
    conic_rational cr;
    truth_set_local(&q, p, uc, vc);
    if (!truth_conic_rational(&q, -(long double)R, (long double)R, &cr))
        return 0;
    long double f[5] = {0}, RR = (long double)R * R, t[4];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            f[i + j] += cr.qx[i] * cr.qx[j] + cr.qy[i] * cr.qy[j];
    f[0] -= RR, f[2] -= 2 * RR, f[4] -= RR;
    int n = truth_sign_roots(f, 4, -cr.T, cr.T, t);
    for (int k = 0; k < n; k++)
        out[k] = (double)((cr.qy[0] + t[k] * (cr.qy[1] + t[k] * cr.qy[2])) / (1 + t[k] * t[k]));
    return n;
}

/* truth_nearest_height for a line, a quadratic or a cubic: D(t) = x^2 +
 * y^2 has D'/2 = c3 t^3 + c2 t^2 + c1 t + c0 (of degree 5 for a cubic). */
static double nearest_poly(const local_piece *q, double lo, double hi, double R)
{
    double near = NAN;
    long double c3 = 2 * (q->ax * q->ax + q->ay * q->ay);
    long double c2 = 3 * (q->ax * q->bx + q->ay * q->by);
    long double c1 = q->bx * q->bx + q->by * q->by + 2 * (q->x0 * q->ax + q->y0 * q->ay);
    long double c0 = q->x0 * q->bx + q->y0 * q->by;
    double t[5], best = INFINITY;
    int m = 0;
    if (q->cubic) {
        /* a cubic: D'/2 = P . P' of degree 5, by GSL's companion matrix */
        long double P[2][4] = {{q->x0, q->bx, q->ax, q->dx}, {q->y0, q->by, q->ay, q->dy}};
        long double e[6] = {0};
        for (int i = 0; i < 2; i++)
            for (int a = 0; a < 4; a++)
                for (int b = 1; b < 4; b++)
                    e[a + b - 1] += P[i][a] * b * P[i][b];
        double ec[6], z[10];
        int deg = 5;
        for (int a = 0; a < 6; a++)
            ec[a] = (double)e[a];
        while (deg > 0 && ec[deg] == 0.0)
            deg--;
        gsl_poly_complex_workspace *ws =
            deg > 0 ? gsl_poly_complex_workspace_alloc((size_t)deg + 1) : NULL;
        if (ws && gsl_poly_complex_solve(ec, (size_t)deg + 1, ws, z) == GSL_SUCCESS)
            for (int a = 0; a < deg; a++)
                if (fabs(z[2 * a + 1]) <= 1e-6 * (1.0 + fabs(z[2 * a])))
                    t[m++] = z[2 * a];
        if (ws)
            gsl_poly_complex_workspace_free(ws);
    } else if (c3 != 0)
        m = gsl_poly_solve_cubic((double)(c2 / c3), (double)(c1 / c3), (double)(c0 / c3), &t[0],
                                 &t[1], &t[2]);
    else if (c2 != 0)
        m = gsl_poly_solve_quadratic((double)c2, (double)c1, (double)c0, &t[0], &t[1]);
    else if (c1 != 0)
        t[m++] = (double)(-c0 / c1);
    for (int j = 0; j < m; j++) {
        long double u = t[j];
        if (!(u > 0 && u < 1))
            continue;
        long double x = q->cubic ? q->x0 + u * (q->bx + u * (q->ax + u * q->dx))
                                 : q->x0 + u * (q->bx + u * q->ax);
        long double y = q->cubic ? q->y0 + u * (q->by + u * (q->ay + u * q->dy))
                                 : q->y0 + u * (q->by + u * q->ay);
        double d2 = (double)(x * x + y * y);
        if (d2 < best && d2 < R * R && y > lo && y < hi && y != 0) {
            best = d2;
            near = (double)y;
        }
    }
    return near;
}

/* The same for a conic piece, as the rational quadratic P(t) = Q(t)/w(t),
 * w = 1 + t^2, of truth_conic_rational over the piece's rows: P . P' =
 * Q . (Q' w - 2 t Q) / w^3, so D' vanishes where the quintic
 *     g(t) = w (Q . Q') - 2 t (Q . Q)
 * does; its sign changes on [-T, T] are D's minima and maxima. */
static double nearest_conic(const local_piece *q, double lo, double hi, double R)
{
    conic_rational cr;
    double near = NAN;
    if (!truth_conic_rational(q, lo, hi, &cr))
        return near;
    const long double *Q[2] = {cr.qx, cr.qy};
    long double qq[5] = {0}, qd[4] = {0}, g[6] = {0}, t[5];
    for (int i = 0; i < 2; i++)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                qq[a + b] += Q[i][a] * Q[i][b];
                if (b > 0)
                    qd[a + b - 1] += Q[i][a] * b * Q[i][b];
            }
    for (int a = 0; a < 4; a++) {
        g[a] += qd[a];     /* Q . Q' */
        g[a + 2] += qd[a]; /* t^2 Q . Q' */
    }
    for (int a = 0; a < 5; a++)
        g[a + 1] -= 2 * qq[a];
    int m = truth_sign_roots(g, 5, -cr.T, cr.T, t);
    double best = INFINITY;
    for (int j = 0; j < m; j++) {
        long double u = t[j], w = 1 + u * u;
        long double x = (cr.qx[0] + u * (cr.qx[1] + u * cr.qx[2])) / w;
        long double y = (cr.qy[0] + u * (cr.qy[1] + u * cr.qy[2])) / w;
        double d2 = (double)(x * x + y * y);
        if (d2 < best && d2 < R * R && y > lo && y < hi && y != 0) {
            best = d2;
            near = (double)y;
        }
    }
    return near;
}

double truth_nearest_height(const local_piece *q, double lo, double hi, double R)
{
    if (q->offset)
        return nearest_offset(q, lo, hi, R);
    return q->conic ? nearest_conic(q, lo, hi, R) : nearest_poly(q, lo, hi, R);
}

double truth_piece_scale(const local_piece *q)
{
    if (q->offset)
        return (double)q->oscale;
    return (double)(fabsl(q->x0) + fabsl(q->bx) + fabsl(q->ax) + fabsl(q->dx) + fabsl(q->ea) +
                    fabsl(q->eb));
}

/* Piece p in extended precision relative to (uc, vc). */
void truth_set_local(local_piece *q, const aa_piece *p, long double uc, long double vc)
{
    long double x0 = p->x0, cx = p->cx, x1 = p->x1;
    long double y0 = p->y0, cy = p->cy, y1 = p->y1;
    q->y0 = y0 - vc;
    q->y1 = y1 - vc;
    q->x0 = x0 - uc;
    q->dx = q->dy = 0;
    q->cubic = p->kind == AA_PIECE_CUBIC;
    q->conic = p->kind == AA_PIECE_CONIC;
    q->offset = p->kind == AA_PIECE_OFFSET;
    q->src = p;
    q->uc = uc, q->vc = vc, q->oscale = 0, q->hint = NAN, q->hint_s = 0, q->hint_slope = NAN, q->side = 0;
    q->end_s = NAN;
    if (q->offset) {
        q->x0 = q->ax = q->bx = q->ay = q->by = 0;
        q->ey = q->er = q->ea = q->eb = q->top = q->bot = q->a0 = q->a1 = 0;
        /* its crossing in long double is off by a few epsilons of the
         * absolute coordinates, and by the root's (Newton's last step) */
        q->oscale = fabsl(uc) + fabs(p->xmin) + fabs(p->xmax) + fabs(p->y0) + fabs(p->y1);
        q->dir = p->dir;
        q->layer = p->layer;
        return;
    }
    q->ey = q->er = q->ea = q->eb = q->top = q->bot = q->a0 = q->a1 = 0;
    if (q->conic) {
        /* the centre's coordinates relative to (uc, vc): exact in long
         * double unless they are 2^11 times apart */
        q->ax = q->bx = q->ay = q->by = 0;
        q->x0 = p->ex - uc;
        q->ey = p->ey - vc;
        q->er = p->er;
        q->ea = p->ea;
        q->eb = p->eb;
        q->top = q->ey - q->er;
        q->bot = q->ey + q->er;
        q->a0 = p->s0;
        q->a1 = p->s1;
    } else if (q->cubic) {
        long double c1x = cx, c1y = cy, c2x = p->c2x, c2y = p->c2y;
        q->bx = 3 * (c1x - x0), q->ax = 3 * (x0 - 2 * c1x + c2x), q->dx = (x1 - x0) + 3 * (c1x - c2x);
        q->by = 3 * (c1y - y0), q->ay = 3 * (y0 - 2 * c1y + c2y), q->dy = (y1 - y0) + 3 * (c1y - c2y);
    } else if (p->kind == AA_PIECE_QUAD) {
        q->ax = x0 - 2 * cx + x1, q->bx = 2 * (cx - x0);
        q->ay = y0 - 2 * cy + y1, q->by = 2 * (cy - y0);
    } else {
        q->ax = 0, q->bx = x1 - x0;
        q->ay = 0, q->by = y1 - y0;
    }
    q->dir = p->dir;
    q->layer = p->layer;
}

/* x(t) - x0 where the piece meets the line at height s (relative to the
 * same origin as q->y0; the piece active there). */
long double truth_t_at(const local_piece *q, long double s)
{
    long double d = s - q->y0, t;
    if (q->offset) {
        const aa_piece *p = q->src;
        if (!(d > 0))
            return 0;
        if (!(s < q->y1))
            return 1;
        long double y = q->vc + s;
        t = aa__offset_solve(&p->oc, 1, p->ot0, p->ot1, (long double)p->y0 - y, y);
        return (t - p->ot0) / ((long double)p->ot1 - p->ot0);
    }
    if (q->conic) {
        t = (conic_angle(q, s) - q->a0) / (q->a1 - q->a0);
        return t < 0 ? 0 : (t > 1 ? 1 : t);
    }
    if (q->cubic) {
        /* y(t) - s = t (by + t (ay + t dy)) - d, increasing on [0, 1]:
         * Newton's method kept inside the bracket [a, b], bisection where
         * a step would leave it, until the error left after a step,
         * |y''/(2y')| step^2, is below 2^-66 (long double's last bit at
         * t = 1 is 2^-64) or the bracket cannot shrink */
        long double a = 0, b = 1, fb = q->by + q->ay + q->dy - d;
        if (!(d > 0))
            return 0;
        if (!(fb > 0))
            return 1;
        /* a start from Newton's method in double, a few fast steps (and
         * bisection where a step would leave [0, 1]); then long double */
        double td = (double)(d / (q->y1 - q->y0)), lo = 0.0, hi = 1.0;
        double dd = (double)d, k1 = (double)q->by, k2 = (double)q->ay, k3 = (double)q->dy;
        td = td > 0.0 && td < 1.0 ? td : 0.5;
        for (int it = 0; it < 40; it++) {
            double f = td * (k1 + td * (k2 + td * k3)) - dd;
            if (f < 0.0)
                lo = td;
            else
                hi = td;
            double df = k1 + td * (2.0 * k2 + 3.0 * td * k3);
            double step = df > 0.0 ? f / df : 1.0;
            if (fabs(step) <= 0x1p-50) { /* converged, to the last bits */
                td = fmin(fmax(td - step, lo), hi);
                break;
            }
            double next = td - step;
            td = next > lo && next < hi ? next : 0.5 * (lo + hi);
            if (!(hi - lo > 0x1p-50))
                break;
        }
        t = td;
        for (int it = 0; it < 100; it++) {
            long double f = t * (q->by + t * (q->ay + t * q->dy)) - d;
            if (f == 0)
                return t;
            if (f < 0)
                a = t;
            else
                b = t;
            long double m = 0.5L * (a + b);
            if (!(m > a && m < b))
                break;
            long double df = q->by + t * (2 * q->ay + 3 * t * q->dy);
            long double step = df > 0 ? f / df : 0, next = df > 0 ? t - step : m;
            if (df > 0 && next >= a && next <= b &&
                fabsl(q->ay + 3 * t * q->dy) * step * step <= 0x1p-66L * df)
                return next;
            t = next > a && next < b ? next : m;
        }
        return t;
    }
    if (q->ay == 0) {
        t = d / q->by;
    } else {
        /* the cancellation-free root of ay t^2 + by t - d = 0 (by >= 0) */
        long double disc = q->by * q->by + 4 * q->ay * d;
        long double den = q->by + sqrtl(disc > 0 ? disc : 0);
        t = den > 0 ? 2 * d / den : 0;
    }
    return t < 0 ? 0 : (t > 1 ? 1 : t);
}

/* The same for a cubic piece: |P(tau) - centre|^2 - R^2 is of degree 6
 * (GSL's companion matrix in a workspace of its own, then Newton in long
 * double); the part of the piece in the disc's rows is t = ta + h tau. */
static int circle_heights_cubic(const aa_piece *p, long double ta, long double h, double uc,
                                double vc, double R, double out[4])
{
    /* Taylor coefficients of x and y in tau: X + tau (b + tau (a + tau d)) */
    long double c3[2] = {p->dx, p->dy}, c2[2] = {p->ax, p->ay}, c1[2] = {p->bx, p->by};
    long double c0[2] = {p->x0 - (long double)uc, p->y0 - (long double)vc};
    long double k[2][4];
    for (int i = 0; i < 2; i++) {
        k[i][0] = c0[i] + ta * (c1[i] + ta * (c2[i] + ta * c3[i]));
        k[i][1] = h * (c1[i] + ta * (2 * c2[i] + 3 * ta * c3[i]));
        k[i][2] = h * h * (c2[i] + 3 * ta * c3[i]);
        k[i][3] = h * h * h * c3[i];
    }
    long double g[7] = {0};
    for (int i = 0; i < 2; i++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                g[a + b] += k[i][a] * k[i][b];
    g[0] -= (long double)R * R;
    double c[7], z[12], t[6];
    int deg = 6, n = 0, m = 0;
    for (int a = 0; a < 7; a++)
        c[a] = (double)g[a];
    while (deg > 0 && c[deg] == 0.0)
        deg--;
    if (deg < 1)
        return 0;
    gsl_poly_complex_workspace *ws = gsl_poly_complex_workspace_alloc((size_t)deg + 1);
    if (ws && gsl_poly_complex_solve(c, (size_t)deg + 1, ws, z) == GSL_SUCCESS)
        for (int a = 0; a < deg; a++)
            if (fabs(z[2 * a + 1]) <= 1e-6 * (1.0 + fabs(z[2 * a])))
                t[n++] = z[2 * a];
    if (ws)
        gsl_poly_complex_workspace_free(ws);
    for (int a = 0; a < n && m < 4; a++) {
        long double u = t[a];
        if (!(u > -0.01 && u < 1.01))
            continue;
        for (int it = 0; it < 6; it++) {
            long double f = g[6], df = 0;
            for (int b = 5; b >= 0; b--)
                df = df * u + f, f = f * u + g[b];
            if (df == 0)
                break;
            u -= f / df;
        }
        if (!(u >= 0 && u <= 1))
            continue;
        out[m++] = (double)(k[1][0] + u * (k[1][1] + u * (k[1][2] + u * k[1][3])));
    }
    return m;
}

/* Radial filter: heights where piece p crosses the circle of radius R
 * around (uc, vc).  The piece's part in the disc's rows is taken as
 * t = ta + (tb - ta) tau, tau in [0, 1], so that the coefficients are of
 * the order of R; the crossings are the real roots in [0, 1] of the
 * quartic |(x(tau), y(tau)) - centre|^2 - R^2 (a quadratic for a line;
 * GSL's companion matrix, then Newton in long double).  A root that is a
 * little off only leaves the kink inside an interval, where QAG's
 * bisection still finds it.  Writes the heights relative to vc (at most
 * 4, in the order found) and returns how many. */
int truth_circle_heights(const aa_piece *p, double uc, double vc, double R,
                         gsl_poly_complex_workspace *poly, double out[4])
{
    if (p->kind == AA_PIECE_FLAT)
        return 0;
    if (p->kind == AA_PIECE_CONIC)
        return circle_heights_conic(p, uc, vc, R, out);
    if (p->kind == AA_PIECE_OFFSET) {
        local_piece q;
        truth_set_local(&q, p, uc, vc);
        return circle_heights_offset(&q, R, out);
    }
    double lo = fmax(vc - R, p->y0), hi = fmin(vc + R, p->y1);
    if (!(lo < hi))
        return 0;
    long double ta = lo <= p->y0 ? 0.0 : aa_piece_t_at(p, lo);
    long double tb = hi >= p->y1 ? 1.0 : aa_piece_t_at(p, hi), h = tb - ta;
    if (!(h > 0))
        return 0;
    if (p->kind == AA_PIECE_CUBIC)
        return circle_heights_cubic(p, ta, h, uc, vc, R, out);
    long double X = p->x0 + ta * (p->bx + ta * p->ax) - (long double)uc;
    long double Y = p->y0 + ta * (p->by + ta * p->ay) - (long double)vc;
    long double bx = h * (p->bx + 2 * ta * p->ax), ax = h * h * p->ax;
    long double by = h * (p->by + 2 * ta * p->ay), ay = h * h * p->ay, RR = R;
    double c[5] = {(double)(X * X + Y * Y - RR * RR), (double)(2 * (X * bx + Y * by)),
                   (double)(bx * bx + by * by + 2 * (X * ax + Y * ay)),
                   (double)(2 * (ax * bx + ay * by)), (double)(ax * ax + ay * ay)};
    double t[4], z[8];
    int n = 0, m = 0;
    if (c[4] == 0.0) { /* then c[3] = 0 too: a line */
        n = gsl_poly_solve_quadratic(c[2], c[1], c[0], &t[0], &t[1]);
    } else if (gsl_poly_complex_solve(c, 5, poly, z) == GSL_SUCCESS) {
        for (int k = 0; k < 4; k++)
            if (fabs(z[2 * k + 1]) <= 1e-6 * (1.0 + fabs(z[2 * k])))
                t[n++] = z[2 * k];
    }
    for (int k = 0; k < n; k++) {
        long double u = t[k];
        if (!(u > -0.01 && u < 1.01))
            continue;
        for (int it = 0; it < 4; it++) {
            long double x = X + u * (bx + u * ax), y = Y + u * (by + u * ay);
            long double g = x * x + y * y - RR * RR;
            long double dg = 2 * (x * (bx + 2 * u * ax) + y * (by + 2 * u * ay));
            if (dg == 0)
                break;
            u -= g / dg;
        }
        if (!(u >= 0 && u <= 1))
            continue;
        out[m++] = (double)(Y + u * (by + u * ay));
    }
    return m;
}
