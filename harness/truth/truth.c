/*
 * truth.c: the ground truth (DESIGN.md, "Ground truth").
 *
 * The reference value of pixel (i, j) is the scene convolved with the
 * filter at the pixel centre (uc, vc) (PATTERNS.md):
 *
 *     P = integral dv w(v - vc) integral du w(u - uc) I(u, v).
 *
 * The inner integral along u is exact: along the line v the scene is a
 * sequence of spans of constant colour bounded by the pieces' crossings,
 * and the filter's integral over a span is a difference of its cdf.
 *
 * Box and tent: the outer integral along v is done interval by interval
 * with GSL's adaptive Gauss-Kronrod (QAG), between breakpoints placed
 * wherever that inner function is not smooth: the ends of pieces (vertices,
 * and the turning points where arcs are split), horizontal edges, the
 * heights where a piece crosses a vertical line at which the filter has a
 * kink (the window's sides for the box; r, 0, -r for the tent), the
 * filter's own kinks along v, and the heights where two pieces meet.
 * Between breakpoints the integrand is smooth; for `crow` and the box it is
 * a polynomial of degree 2 and the first 21-point pass is exact.  Next to
 * a turning point x moves like the square root of the height, so there the
 * half interval is integrated in u = sqrt(|v - v_turn|).
 *
 * The Gaussian (untruncated; the window is the square of half-side R =
 * f->radius outside which its mass is below 1e-14): QAG alone needs some
 * 170 evaluations of the inner integral a pixel, as the integrand is
 * nowhere a polynomial.  But the filter is separable, so
 *
 *     P(i, j) = integral dv w(v - vc_j) G_i(v),
 *     G_i(v)  = integral du w(u - uc_i) I(u, v),
 *
 * and G_i, the inner integral of column i, does not depend on the row.  So
 * v is cut into panels of height h (2 s at most, aligned with the pixel
 * grid: h = 1/n or n pixels), G_i is computed once at the 21 Kronrod nodes
 * of each panel, and each pixel is a dot product of those values, over the
 * panels that cover [vc - R, vc + R], with a table of w(node - vc) times
 * the Kronrod weights that is the same for every row (one table per row
 * phase when h > 1; if 2 R < 1, s < 1/16, rows share no panel and QAG
 * does it all).  The 10-point Gauss rule embedded in the same nodes
 * gives the error estimate, |K21 - G10| summed over the panels: pessimistic
 * (it is G10's error; K21's is at the rounding level), measured below 1e-15
 * a panel for slopes up to 0.6 (crow's steepest).  A thread renders a block
 * of rows and keeps a ring of the panels its current row needs: memory
 * O(width), nothing allocated per pixel; a panel's values are a function
 * of the panel alone, so the image does not depend on the threads.
 *
 * The fixed rule is exact only where G_i is analytic on the panel.  It is
 * computed as the integral over the whole line of the colours defined by
 * the pieces near column i (those whose extent in the panel meets the
 * window [uc - R, uc + R]), extended beyond the window on either side:
 * that differs from the true inner integral by at most the filter's mass
 * outside the window, and is a smooth function of those pieces' crossings
 * as long as none of them begins or ends inside the panel, none is flat
 * there, none meets another piece there (tested exactly for pieces whose x
 * is quadratic in y, conservatively for others), none is steeper than
 * |dx/dy| = 1 (a nearly horizontal edge makes G_i change on a scale s /
 * |dx/dy|, too fast for the panel) and they are ordered consistently with
 * the pieces outside.  A column for which any of this fails in a panel
 * marks that panel, and every pixel that needs a marked panel, or whose
 * bound comes out above AA_TRUTH_BOUND / 4, is integrated by QAG as for
 * the other filters.  Uniform pixels are filled in both cases.  On crow
 * (1024 x 1024, s = 0.5) every non-uniform pixel takes the fixed rule; its
 * error bound is the estimate, plus twice the truncated mass (x and v),
 * plus rounding.  The cdf at a crossing comes from a table of Phi and its
 * Taylor coefficients (7 terms, steps of 1/32 standard deviation, error at
 * the rounding level), laid out so that one offset serves every column a
 * crossing is near.  Under QAG, the Gaussian adds as breakpoints the
 * heights where a piece crosses x = uc + k s (without them QAG can miss
 * the steep step of a nearly horizontal edge and still report a small
 * error) and where two arcs meet.
 *
 * The integration runs in coordinates relative to the pixel centre (or,
 * for panels, with crossings split into an exact part and a small one), and
 * the crossings are evaluated in extended precision (long double) from the
 * pieces' control points, so that at 4096 pixels, where an absolute
 * coordinate's last bit is 5e-13 px, the inner integral still carries only
 * rounding of the order of 1e-16.
 *
 * The cone (radial, not separable; filter.c) takes the QAG path with the
 * row's integral in place of the cdf difference: at height s the spans
 * between crossings are weighed by the closed-form integral of the row
 * over them (aa_filter_row_cdf, which clips them to the disc's chord), so
 * the inner integral stays exact.  Its breakpoints add v = 0, where the
 * row integral has a v^2 log|v| term, the heights where a piece crosses
 * the circle of radius R around the centre (the span's end leaves the
 * chord there and the integrand's second derivative jumps), and v = +-R,
 * where the chord closes like sqrt(R - |v|): the half intervals next to
 * them are integrated in u = sqrt(R - |v|), as at turning points, where
 * the integrand (about (R - |v|)^(3/2)) becomes smooth.
 *
 * Each pixel carries an error bound: QAG's estimate or the fixed rule's,
 * plus the weight of the Gaussian outside its truncation square, plus the
 * rounding.  Pixels whose window meets no piece are uniform: they take the
 * colour of their centre with no integration.  This path shares nothing
 * with the methods beyond the scene's own queries (the strip tells which
 * pieces are near a window and the winding numbers left of it).
 */
#include "aabench.h"
#include "truth_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_poly.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* QAG is asked for this absolute accuracy per pixel and channel: above its
 * rounding floor (50 eps times the integral of |f|, about 1e-14 here) and
 * well below AA_TRUTH_BOUND. */
#define TRUTH_EPSABS 2e-13
/* Pairwise intersections are breakpoints only up to this many local pieces;
 * beyond it the adaptive bisection finds the kinks by itself. */
#define TRUTH_MAX_PAIRS 48

/* A local piece in coordinates relative to the pixel centre (uc, vc):
 * y(t) - vc = y0 + t (by + t ay), x(t) - uc = x0 + t (bx + t ax). */
typedef struct local_piece {
    long double y0, y1, x0, ax, bx, ay, by;
    int dir, layer;
} local_piece;

typedef struct crossing {
    double x;
    int dir, layer;
} crossing;

typedef struct worker {
    const aa_scene *scene;
    const aa_filter *f;
    aa_strip *strip;
    gsl_integration_workspace *ws;
    size_t limit;
    double *pts;
    size_t npts, cap_pts;
    double sing[64]; /* heights (relative) where a piece turns: x ~ sqrt */
    size_t nsing;
    local_piece *lp;
    crossing *cross;
    size_t nlp, cap_lp;
    int *wind;
    double uc, vc, R;
    int channel;
    int box;
    int radial; /* not separable (cone): rows weighed by aa_filter_row_cdf */
    gsl_poly_complex_workspace *poly; /* radial: the circle's crossings */
} worker;

static void worker_free(worker *w)
{
    aa_strip_free(w->strip);
    if (w->ws)
        gsl_integration_workspace_free(w->ws);
    if (w->poly)
        gsl_poly_complex_workspace_free(w->poly);
    free(w->pts);
    free(w->lp);
    free(w->cross);
    free(w->wind);
}

/* On failure the worker is left empty, so worker_free is always safe. */
static int worker_init(worker *w, const aa_scene *scene, const aa_filter *f)
{
    memset(w, 0, sizeof *w);
    w->scene = scene;
    w->f = f;
    w->box = aa_filter_is_box(f);
    w->radial = !aa_filter_is_separable(f);
    w->R = f->radius;
    w->limit = 1024;
    w->strip = aa_strip_new(scene);
    w->ws = gsl_integration_workspace_alloc(w->limit);
    int nl = aa_scene_layer_count(scene);
    w->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *w->wind);
    if (w->radial)
        w->poly = gsl_poly_complex_workspace_alloc(5);
    if (!w->strip || !w->ws || !w->wind || (w->radial && !w->poly)) {
        worker_free(w);
        memset(w, 0, sizeof *w);
        return aa_fail(AA_ENOMEM, "out of memory for a reference worker");
    }
    return AA_OK;
}

/* Record breakpoint s (relative to vc) if it is inside (-R, R). */
static int add_point(worker *w, double s)
{
    if (!(s > -w->R && s < w->R))
        return AA_OK;
    if (w->npts == w->cap_pts) {
        size_t n = w->cap_pts ? 2 * w->cap_pts : 64;
        double *p = realloc(w->pts, n * sizeof *p);
        if (!p)
            return aa_fail(AA_ENOMEM, "out of memory for breakpoints");
        w->pts = p;
        w->cap_pts = n;
    }
    w->pts[w->npts++] = s;
    return AA_OK;
}

/* Record the absolute height y if it lies in (lo, hi). */
static int add_abs(worker *w, double y, double lo, double hi)
{
    return y > lo && y < hi ? add_point(w, y - w->vc) : AA_OK;
}

/* Heights where pieces p and q meet inside the window: every kind of pair,
 * every filter (aa_piece_meet: closed forms, or bisection on exact extents
 * for two general arcs).  Where two edges cross, the inner integral has a
 * kink that QAG's error estimate does not always see. */
static int add_intersections(worker *w, const aa_piece *p, const aa_piece *q)
{
    double ys[16];
    int n = aa_piece_meet(p, q, w->vc - w->R, w->vc + w->R, ys, 16), st = AA_OK;
    for (int k = 0; k < n && !st; k++)
        st = add_abs(w, ys[k], -INFINITY, INFINITY);
    return st;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

/* Remember a turning point s (relative) inside [-R, R]. */
static void note_turn(worker *w, double s)
{
    if (s >= -w->R && s <= w->R && w->nsing < sizeof w->sing / sizeof *w->sing)
        w->sing[w->nsing++] = s;
}

static int is_turn(const worker *w, double s)
{
    for (size_t k = 0; k < w->nsing; k++)
        if (w->sing[k] == s)
            return 1;
    return 0;
}

/* Radial filter: heights where piece p crosses the circle of radius R
 * around (uc, vc).  The piece's part in the disc's rows is taken as
 * t = ta + (tb - ta) tau, tau in [0, 1], so that the coefficients are of
 * the order of R; the crossings are the real roots in [0, 1] of the
 * quartic |(x(tau), y(tau)) - centre|^2 - R^2 (a quadratic for a line;
 * GSL's companion matrix, then Newton in long double).  A root that is a
 * little off only leaves the kink inside an interval, where QAG's
 * bisection still finds it. */
static int add_circle(worker *w, const aa_piece *p)
{
    if (p->kind == AA_PIECE_FLAT)
        return AA_OK;
    double lo = fmax(w->vc - w->R, p->y0), hi = fmin(w->vc + w->R, p->y1);
    if (!(lo < hi))
        return AA_OK;
    long double ta = lo <= p->y0 ? 0.0 : aa_piece_t_at(p, lo);
    long double tb = hi >= p->y1 ? 1.0 : aa_piece_t_at(p, hi), h = tb - ta;
    if (!(h > 0))
        return AA_OK;
    long double X = p->x0 + ta * (p->bx + ta * p->ax) - (long double)w->uc;
    long double Y = p->y0 + ta * (p->by + ta * p->ay) - (long double)w->vc;
    long double bx = h * (p->bx + 2 * ta * p->ax), ax = h * h * p->ax;
    long double by = h * (p->by + 2 * ta * p->ay), ay = h * h * p->ay, R = w->R;
    double c[5] = {(double)(X * X + Y * Y - R * R), (double)(2 * (X * bx + Y * by)),
                   (double)(bx * bx + by * by + 2 * (X * ax + Y * ay)),
                   (double)(2 * (ax * bx + ay * by)), (double)(ax * ax + ay * ay)};
    double t[4], z[8];
    int n = 0;
    if (c[4] == 0.0) { /* then c[3] = 0 too: a line */
        n = gsl_poly_solve_quadratic(c[2], c[1], c[0], &t[0], &t[1]);
    } else if (gsl_poly_complex_solve(c, 5, w->poly, z) == GSL_SUCCESS) {
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
            long double g = x * x + y * y - R * R;
            long double dg = 2 * (x * (bx + 2 * u * ax) + y * (by + 2 * u * ay));
            if (dg == 0)
                break;
            u -= g / dg;
        }
        if (!(u >= 0 && u <= 1))
            continue;
        int st = add_point(w, (double)(Y + u * (by + u * ay)));
        if (st)
            return st;
    }
    return AA_OK;
}

/* Breakpoints of the current pixel, relative to vc, sorted, from -R to R. */
static int breakpoints(worker *w, const aa_piece *const *local, size_t n)
{
    double kink[8];
    int nk = w->f->type->kinks(w->f->spec.v, kink), st = AA_OK;
    w->npts = 0;
    for (int k = 0; k < nk && !st; k++)
        st = add_point(w, kink[k]);
    if (w->f->type == &aa_filter_gauss) {
        /* Start QAG on panels two standard deviations wide, where one
         * 21-point pass integrates the Gaussian factor to rounding. */
        double sd = w->f->spec.v[0];
        for (double z = -w->R + 2.0 * sd; z < w->R && !st; z += 2.0 * sd)
            st = add_point(w, z);
    }
    w->nsing = 0;
    if (w->radial) {
        /* the chord closes like a square root at both ends */
        note_turn(w, -w->R);
        note_turn(w, w->R);
        /* and the v^2 log|v| term at 0 becomes u^5 log u, smooth enough
         * for one Gauss-Kronrod pass where in v QAG bisects a dozen times */
        note_turn(w, 0.0);
    }
    for (size_t k = 0; k < n && !st; k++) {
        const aa_piece *p = local[k];
        double ys[2];
        if ((st = add_abs(w, p->y0, -INFINITY, INFINITY)) ||
            (st = add_abs(w, p->y1, -INFINITY, INFINITY)))
            break;
        if (p->kind == AA_PIECE_FLAT)
            continue;
        if (p->kind == AA_PIECE_QUAD) {
            /* an end where dy/dt = 0 (an arc's turning point in y, where
             * edges are split): there x - x_end grows like sqrt(y - y_end) */
            double tiny = 1e-12 * (p->y1 - p->y0);
            if (fabs(p->by) <= tiny)
                note_turn(w, p->y0 - w->vc);
            if (fabs(p->by + 2.0 * p->ay) <= tiny)
                note_turn(w, p->y1 - w->vc);
        }
        if (w->radial) {
            /* where the piece crosses the disc's rim: a span's end leaves
             * the chord there (the row integral has no kink in u inside) */
            st = add_circle(w, p);
        } else {
            /* where the piece crosses a vertical line at which the filter's
             * cdf has a kink (the window's sides for the box) */
            for (int j = 0; j < nk && !st; j++) {
                int m = aa_piece_meet_x(p, w->uc + kink[j], ys);
                for (int q = 0; q < m && !st; q++)
                    st = add_abs(w, ys[q], -INFINITY, INFINITY);
            }
        }
        /* Gaussian: where it crosses x = uc + k s.  A steep piece sweeps
         * the window in a short stretch of v, where the inner integral
         * rises like Phi on a scale s / |dx/dy|; without these points QAG
         * can miss such a step and still report a small error (seen with
         * a nearly horizontal edge: an error of 1e-12 against an estimate
         * of 2e-14).  Between them the piece moves by s along x. */
        if (w->f->type == &aa_filter_gauss) {
            double sd = w->f->spec.v[0];
            for (double t = -floor(w->R / sd) * sd; t <= w->R && !st; t += sd) {
                int m = aa_piece_meet_x(p, w->uc + t, ys);
                for (int q = 0; q < m && !st; q++)
                    st = add_abs(w, ys[q], -INFINITY, INFINITY);
            }
        }
        if (n <= TRUTH_MAX_PAIRS)
            for (size_t q = k + 1; q < n && !st; q++)
                st = add_intersections(w, p, local[q]);
    }
    if (st)
        return st;
    /* make room for both ends: add_point only grows inside (-R, R) */
    if ((st = add_point(w, 0.0)) || (st = add_point(w, 0.0)))
        return st;
    w->npts -= 2;
    qsort(w->pts, w->npts, sizeof *w->pts, cmp_double);
    memmove(w->pts + 1, w->pts, w->npts * sizeof *w->pts);
    w->pts[0] = -w->R;
    size_t m = 1;
    for (size_t k = 1; k <= w->npts; k++)
        if (w->pts[k] > w->pts[m - 1])
            w->pts[m++] = w->pts[k];
    w->pts[m++] = w->R;
    w->npts = m;
    return AA_OK;
}

/* Piece p in extended precision relative to (uc, vc). */
static void set_local(local_piece *q, const aa_piece *p, long double uc, long double vc)
{
    long double x0 = p->x0, cx = p->cx, x1 = p->x1;
    long double y0 = p->y0, cy = p->cy, y1 = p->y1;
    q->y0 = y0 - vc;
    q->y1 = y1 - vc;
    q->x0 = x0 - uc;
    if (p->kind == AA_PIECE_QUAD) {
        q->ax = x0 - 2 * cx + x1, q->bx = 2 * (cx - x0);
        q->ay = y0 - 2 * cy + y1, q->by = 2 * (cy - y0);
    } else {
        q->ax = 0, q->bx = x1 - x0;
        q->ay = 0, q->by = y1 - y0;
    }
    q->dir = p->dir;
    q->layer = p->layer;
}

/* Set up the local pieces of the current window relative to (uc, vc). */
static int load_local(worker *w, const aa_piece *const *local, size_t n)
{
    if (n > w->cap_lp) {
        size_t cap = 2 * n;
        local_piece *lp = realloc(w->lp, cap * sizeof *lp);
        if (lp)
            w->lp = lp;
        crossing *cr = realloc(w->cross, cap * sizeof *cr);
        if (cr)
            w->cross = cr;
        if (!lp || !cr)
            return aa_fail(AA_ENOMEM, "out of memory for %zu local pieces", n);
        w->cap_lp = cap;
    }
    w->nlp = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *p = local[k];
        if (!p->dir)
            continue; /* flat: no crossing, only a breakpoint */
        set_local(&w->lp[w->nlp++], p, w->uc, w->vc);
    }
    return AA_OK;
}

/* x(t) - x0 where the piece meets the line at height s (relative to the
 * same origin as q->y0; the piece active there). */
static long double crossing_part(const local_piece *q, long double s)
{
    long double d = s - q->y0, t;
    if (q->ay == 0) {
        t = d / q->by;
    } else {
        /* the cancellation-free root of ay t^2 + by t - d = 0 (by >= 0) */
        long double disc = q->by * q->by + 4 * q->ay * d;
        long double den = q->by + sqrtl(disc > 0 ? disc : 0);
        t = den > 0 ? 2 * d / den : 0;
    }
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return t * (q->bx + t * q->ax);
}

/* x - uc where the piece meets the line at height s = y - vc (active). */
static long double crossing_at(const local_piece *q, long double s)
{
    return q->x0 + crossing_part(q, s);
}

/* The inner integral along u at height s = v - vc, for one channel, times
 * w(s) (for a radial filter, the rows' own integrals).  Coordinates are
 * relative to the pixel centre; the window is [-R, R]. */
static double integrand(double s, void *params)
{
    worker *w = params;
    double ws = w->box || w->radial ? 1.0 : aa_filter_weight(w->f, s);
    if (ws == 0.0)
        return 0.0;
    double R = w->R;
    size_t nc = 0;
    aa_strip_winding_left(w->strip, w->vc + s, w->wind);
    for (size_t k = 0; k < w->nlp; k++) {
        const local_piece *q = &w->lp[k];
        if (!(s >= q->y0 && s < q->y1))
            continue;
        long double xl = crossing_at(q, s);
        if (xl < -R) {
            w->wind[q->layer] += q->dir;
            continue;
        }
        if (xl >= R)
            continue;
        double x = (double)xl;
        size_t at = nc++;
        while (at > 0 && w->cross[at - 1].x > x) {
            w->cross[at] = w->cross[at - 1];
            at--;
        }
        w->cross[at].x = x;
        w->cross[at].dir = q->dir;
        w->cross[at].layer = q->layer;
    }
    double sum = 0.0, cur = -R, fcur = 0.0;
    for (size_t k = 0; k <= nc; k++) {
        double next = k < nc ? w->cross[k].x : R;
        if (next > cur) {
            double c = aa_scene_colour_of(w->scene, w->wind).c[w->channel];
            double fnext = w->box      ? next
                           : w->radial ? aa_filter_row_cdf(w->f, s, next)
                                       : aa_filter_cdf(w->f, next);
            if (c != 0.0)
                sum += c * (w->box ? next - cur : fnext - fcur);
            cur = next;
            fcur = fnext;
        }
        if (k < nc)
            w->wind[w->cross[k].layer] += w->cross[k].dir;
    }
    return ws * sum;
}

/* The integrand near a turning point e, in u with s = e + sign u^2: the
 * square root becomes smooth, and ds = 2 u du. */
typedef struct turn_ctx {
    worker *w;
    double e, sign;
} turn_ctx;

static double integrand_turn(double u, void *params)
{
    const turn_ctx *t = params;
    return 2.0 * u * integrand(t->e + t->sign * u * u, t->w);
}

/* One interval: a single 21-point Gauss-Kronrod pass, which is what QAG
 * starts with and is enough between breakpoints nearly always (for crow
 * under the box it is exact), then QAG's bisection only if its estimate is
 * above eps.  Calling the pass directly saves QAG's set-up per interval. */
static void qag(worker *w, gsl_function *F, double a, double b, double eps, double *res,
                double *err)
{
    double r = 0.0, e = 0.0, resabs, resasc;
    gsl_integration_qk21(F, a, b, &r, &e, &resabs, &resasc);
    if (!(e <= eps))
        gsl_integration_qag(F, a, b, eps, 0.0, w->limit, GSL_INTEG_GAUSS21, w->ws, &r, &e);
    *res += r;
    *err += e;
}

/* The outer integral as a sum over the breakpoints' intervals, each by
 * adaptive Gauss-Kronrod (QAG) on its own.  Between breakpoints the
 * integrand is smooth, so no extrapolation is wanted: QAG's, across all
 * the intervals at once, was seen to return a wrong value (2.6e-7 off)
 * with an estimate of 9e-15 on a pixel where two arcs turn.  A half
 * interval next to a turning point is integrated in u = sqrt(|s - e|). */
static void integrate_intervals(worker *w, double *result, double *abserr)
{
    gsl_function F = {integrand, w};
    double span = w->pts[w->npts - 1] - w->pts[0];
    *result = *abserr = 0.0;
    for (size_t k = 0; k + 1 < w->npts; k++) {
        double a = w->pts[k], b = w->pts[k + 1];
        double eps = fmax(TRUTH_EPSABS * (b - a) / span, 1e-17);
        int ta = is_turn(w, a), tb = is_turn(w, b);
        if (!ta && !tb) {
            qag(w, &F, a, b, eps, result, abserr);
            continue;
        }
        double m = 0.5 * (a + b);
        turn_ctx lo = {w, a, 1.0}, hi = {w, b, -1.0};
        gsl_function G = {integrand_turn, &lo}, H = {integrand_turn, &hi};
        if (ta)
            qag(w, &G, 0.0, sqrt(m - a), 0.5 * eps, result, abserr);
        else
            qag(w, &F, a, m, 0.5 * eps, result, abserr);
        if (tb)
            qag(w, &H, 0.0, sqrt(b - m), 0.5 * eps, result, abserr);
        else
            qag(w, &F, m, b, 0.5 * eps, result, abserr);
    }
}

static int reserve_workspace(worker *w, size_t npts)
{
    if (npts + 64 <= w->limit)
        return AA_OK;
    size_t limit = 2 * (npts + 64);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(limit);
    if (!ws)
        return aa_fail(AA_ENOMEM, "out of memory for a quadrature workspace");
    gsl_integration_workspace_free(w->ws);
    w->ws = ws;
    w->limit = limit;
    return AA_OK;
}

/* Integrate one non-uniform pixel; writes its channels and error bound. */
static int integrate_pixel(worker *w, int grey, double *value, double *bound)
{
    size_t n;
    const aa_piece *const *local = aa_strip_local(w->strip, &n);
    int st;
    if ((st = load_local(w, local, n)) || (st = breakpoints(w, local, n)) ||
        (st = reserve_workspace(w, w->npts)))
        return st;
    double worst = 0.0;
    for (int ch = 0; ch < (grey ? 1 : 3); ch++) {
        double result = 0.0, abserr = 0.0;
        w->channel = ch;
        integrate_intervals(w, &result, &abserr);
        value[ch] = result;
        worst = fmax(worst, abserr);
    }
    if (grey)
        value[1] = value[2] = value[0];
    /* Rounding: relative crossings are within a few ulps of R (long double
     * arithmetic, then one rounding to double); each moves the inner
     * integral by at most that times the filter's peak (for the cone, the
     * integral over v of the largest weight of a row, 3 / (pi R)). */
    double peak = w->box      ? 1.0
                  : w->radial ? aa_filter_weight2(w->f, 0.0, 0.0) * w->R
                              : aa_filter_weight(w->f, 0.0);
    *bound = worst + w->f->lost + 8.0 * DBL_EPSILON * fmax(w->R, 1.0) * peak * (double)n;
    return AA_OK;
}

/* ------------------------------------------------------------------------
 * The Gaussian: one fixed rule on panels shared by the rows
 * ------------------------------------------------------------------------ */

#define GK_N 21 /* Gauss-Kronrod 10/21 (GSL's qk21) */
#define GK_S 24 /* stored per panel and column: the nodes, then zeros */
#define GL_N 10
/* Pieces steeper than this (|dx/dy|) make G vary on a scale below s and
 * leave the panel to QAG: measured, |K21 - G10| on a panel of 2 s grows
 * from 8e-16 at slope 0.6 to 3e-14 at 1 and 2e-12 at 1.5 (s = 0.5). */
#define FAST_SLOPE 1.0
/* A fixed-rule pixel whose bound exceeds this goes to QAG instead. */
#define FAST_LIMIT (AA_TRUTH_BOUND / 4)
/* Slack on x extents and on the tests for meeting pieces, in pixels. */
#define FAST_TOL 1e-9
/* Pairs tested per piece before a crowd of overlapping pieces is simply
 * left to QAG. */
#define FAST_PAIRS 64
/* Per-thread panel buffers above this many bytes (22 MB for a colour image
 * 4096 wide, s = 0.5): QAG for every pixel. */
#define FAST_MAX_BYTES ((size_t)256 << 20)

enum { PANEL_CONST = 0, PANEL_NODES = 1, PANEL_BAD = 2 };

/* Taylor terms of the tabulated cdf: with steps of at most 1/32 standard
 * deviation, 7 terms leave a truncation error below 1e-18 (6 leave 4e-16;
 * measured against erfcl over |z| <= 10.5: largest error 1.1e-16, the
 * rounding of values near 1). */
#define CDF_TERMS 7
#define CDF_STEPS 32
_Static_assert(CDF_TERMS == 7, "node_crossings writes seven powers");

/* What every thread shares: the rule, the panel grid and the weight tables.
 * Panels have height h = num/den pixels (one of the two is 1) and panel p
 * covers [p h, (p+1) h].  Row j has phase j mod num; its window is covered
 * by np[phase] panels from base(j) + r0[phase], base(j) = (j div num) den. */
typedef struct gauss_plan {
    double x[GK_N], wk[GK_N], wg[GK_N]; /* on [-1, 1], x ascending */
    int num, den, np_max;
    int *np, *r0;         /* per phase */
    double *a, *d, *mass; /* [phase][k][node], [phase][k] */
    double R, lost, peak, s, inv_s;
    double node_err; /* (h + R/2) R / s^2: node heights in the weights */
    /* The cdf in z = t/s, tabulated at z_k = k dz, |k| <= kt, as Phi(z_k)
     * and the Taylor coefficients Phi^(n)(z_k)/n!, n = 1..CDF_TERMS, with
     * dz = 1/(s M): a column to the right is M entries down, so one offset
     * from the grid serves every column a crossing is near. */
    int M;
    long kt;
    double *cdf_tab; /* [2 kt + 1][CDF_TERMS + 1] */
} gauss_plan;

typedef struct probe {
    double x[32];
    int n;
} probe;

static double probe_record(double x, void *params)
{
    probe *pr = params;
    if (pr->n < 32)
        pr->x[pr->n] = x;
    pr->n++;
    return 0.0;
}

static double probe_indicator(double x, void *params)
{
    return x == *(const double *)params ? 1.0 : 0.0;
}

/* The 21-point Kronrod rule and its embedded 10-point Gauss rule, read from
 * GSL itself: the nodes where qk21 evaluates on [-1, 1], each weight as
 * qk21's value for the indicator of its node, and the Gauss weights from
 * GSL's Gauss-Legendre table. */
static int gauss_rule(gauss_plan *pl)
{
    probe pr = {{0}, 0};
    gsl_function F = {probe_record, &pr};
    double res, err, rabs, rasc;
    gsl_integration_qk21(&F, -1.0, 1.0, &res, &err, &rabs, &rasc);
    if (pr.n != GK_N)
        return aa_fail(AA_EFAIL, "qk21 evaluated %d points, not %d", pr.n, GK_N);
    qsort(pr.x, GK_N, sizeof *pr.x, cmp_double);
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(GL_N);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for a Gauss-Legendre table");
    int ng = 0;
    double sk = 0.0, sg = 0.0;
    for (int k = 0; k < GK_N; k++) {
        double x = pr.x[k];
        gsl_function G = {probe_indicator, &x};
        pl->x[k] = x;
        gsl_integration_qk21(&G, -1.0, 1.0, &pl->wk[k], &err, &rabs, &rasc);
        pl->wg[k] = 0.0;
        for (size_t i = 0; i < GL_N; i++) {
            double xi, wi;
            gsl_integration_glfixed_point(-1.0, 1.0, i, &xi, &wi, t);
            if (fabs(xi - x) < 1e-14)
                pl->wg[k] = wi, ng++;
        }
        sk += pl->wk[k];
        sg += pl->wg[k];
    }
    gsl_integration_glfixed_table_free(t);
    if (ng != GL_N || fabs(sk - 2.0) > 1e-14 || fabs(sg - 2.0) > 1e-14)
        return aa_fail(AA_EFAIL, "the Gauss-Kronrod 10/21 rule read from GSL is inconsistent");
    return AA_OK;
}

static void plan_free(gauss_plan *pl)
{
    free(pl->cdf_tab);
    free(pl->np);
    free(pl->r0);
    free(pl->a);
    free(pl->d);
    free(pl->mass);
    memset(pl, 0, sizeof *pl);
}

static double panel_edge(const gauss_plan *pl, long p)
{
    return (double)p * pl->num / pl->den;
}

/* Height of node m of panel p, in extended precision. */
static long double node_height(const gauss_plan *pl, long p, int m)
{
    return ((long double)p * pl->num + (1.0L + pl->x[m]) * 0.5L * pl->num) / pl->den;
}

/* The tabulated cdf (see gauss_plan), over the z a near crossing can have:
 * |x - uc| <= R + the widest extent of a piece that is not steep. */
static int cdf_table(gauss_plan *pl, double h)
{
    double s = pl->s;
    pl->M = 1;
    while (pl->M < CDF_STEPS / s && pl->M < (1 << 24))
        pl->M *= 2; /* a power of two: k / M is exact */
    long double dz = 1.0L / ((long double)s * pl->M);
    double zmax = (pl->R + FAST_SLOPE * h + 1.0) / s;
    pl->kt = (long)ceil(zmax / (double)dz) + 2;
    size_t rows = 2 * (size_t)pl->kt + 1;
    pl->cdf_tab = malloc(rows * (CDF_TERMS + 1) * sizeof *pl->cdf_tab);
    if (!pl->cdf_tab)
        return aa_fail(AA_ENOMEM, "out of memory for the cdf table");
    for (size_t r = 0; r < rows; r++) {
        long double z = ((long double)r - pl->kt) * dz;
        long double phi = expl(-0.5L * z * z) / sqrtl(2.0L * 3.141592653589793238462643L);
        double *t = pl->cdf_tab + r * (CDF_TERMS + 1);
        t[0] = (double)(0.5L * erfcl(-z / sqrtl(2.0L)));
        /* Phi^(n) = (-1)^(n-1) He_(n-1)(z) phi(z), Hermite by recurrence */
        long double he0 = 1.0L, he1 = z, fact = 1.0L;
        for (int n = 1; n <= CDF_TERMS; n++) {
            fact *= n;
            long double he = n == 1 ? he0 : he1;
            t[n] = (double)((n % 2 ? 1.0L : -1.0L) * he * phi / fact);
            if (n >= 2) {
                long double next = z * he1 - (n - 1) * he0;
                he0 = he1;
                he1 = next;
            }
        }
    }
    return AA_OK;
}

static int plan_init(gauss_plan *pl, const aa_filter *f)
{
    memset(pl, 0, sizeof *pl);
    int st = gauss_rule(pl);
    if (st)
        return st;
    /* Panels of at most 2 s, aligned with the pixel grid: |K21 - G10| is
     * then below 1e-15 a panel for slopes up to 0.6 (crow's steepest). */
    double two_s = 2.0 * f->spec.v[0];
    if (two_s >= 1.0)
        pl->num = (int)floor(two_s), pl->den = 1;
    else
        pl->num = 1, pl->den = (int)ceil(1.0 / two_s);
    pl->R = f->radius;
    pl->s = f->spec.v[0];
    pl->inv_s = 1.0 / pl->s;
    pl->lost = f->lost;
    pl->peak = aa_filter_weight(f, 0.0);
    double h = (double)pl->num / pl->den;
    pl->node_err = (h + 0.5 * pl->R) * pl->R / (pl->s * pl->s);
    int phases = pl->num;
    pl->np = calloc((size_t)phases, sizeof *pl->np);
    pl->r0 = calloc((size_t)phases, sizeof *pl->r0);
    if (!pl->np || !pl->r0) {
        plan_free(pl);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian plan");
    }
    for (int ph = 0; ph < phases; ph++) {
        double vrel = ph + 0.5; /* the centre, relative to (j div num) num */
        double lo = floor((vrel - pl->R) / h), hi = ceil((vrel + pl->R) / h) - 1.0;
        pl->r0[ph] = (int)lo;
        pl->np[ph] = (int)(hi - lo) + 1;
        if (pl->np[ph] > pl->np_max)
            pl->np_max = pl->np[ph];
    }
    size_t cells = (size_t)phases * (size_t)pl->np_max;
    pl->a = calloc(cells * GK_S, sizeof *pl->a);
    pl->d = calloc(cells * GK_S, sizeof *pl->d);
    pl->mass = calloc(cells, sizeof *pl->mass);
    if (!pl->a || !pl->d || !pl->mass) {
        plan_free(pl);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian plan");
    }
    if ((st = cdf_table(pl, h))) {
        plan_free(pl);
        return st;
    }
    for (int ph = 0; ph < phases; ph++) {
        double vrel = ph + 0.5;
        for (int k = 0; k < pl->np[ph]; k++) {
            size_t cell = (size_t)ph * (size_t)pl->np_max + (size_t)k;
            long r = pl->r0[ph] + k;
            double start = panel_edge(pl, r) - vrel, end = panel_edge(pl, r + 1) - vrel;
            pl->mass[cell] = aa_filter_cdf(f, end) - aa_filter_cdf(f, start);
            for (int m = 0; m < GK_N; m++) {
                double rel = start + (1.0 + pl->x[m]) * 0.5 * h;
                double wv = 0.5 * h * aa_filter_weight(f, rel);
                pl->a[cell * GK_S + m] = pl->wk[m] * wv;
                pl->d[cell * GK_S + m] = (pl->wk[m] - pl->wg[m]) * wv;
            }
        }
    }
    return AA_OK;
}

/* A piece meeting the current panel, in extended precision (absolute
 * coordinates), with the x extent of its part in the panel and the columns
 * whose window that extent meets (c0 > c1: none). */
typedef struct band_piece {
    local_piece q;
    double xmin, xmax;
    int c0, c1;
} band_piece;

typedef struct node_cross {
    double x;             /* rounded: for sorting and searching */
    int k;                /* band piece */
    int c0, c1;           /* its columns */
    long base;            /* cdf table row for column 0 (x - 1/2 near base/M) */
    double pw[CDF_TERMS]; /* powers of the offset from that row, in z */
} node_cross;

typedef struct key_index {
    double key;
    size_t k;
} key_index;

/* One thread's state for the fixed rule: a ring of `ring` panels, each
 * with per column a kind, the most crossings one node saw, the constant
 * colour (PANEL_CONST) or the inner integral at the nodes (PANEL_NODES). */
typedef struct panel_worker {
    const gauss_plan *plan;
    const aa_filter *f;
    const aa_scene *scene;
    aa_strip *strip;
    int w, nc, ring;
    long lo, hi;
    int valid;
    unsigned char *kind;   /* [ring][w] */
    unsigned short *nnear; /* [ring][w] */
    double *cst;           /* [ring][w][nc] */
    double *g;             /* [ring][w][nc][GK_S] */
    int *near_diff, *bad_diff, *runs;
    size_t nruns;
    size_t *row_cells; /* first cell of each panel of the current row */
    band_piece *bp;
    node_cross *cr; /* [GK_N][cap]: the crossings of each node line */
    double *col;    /* [GK_N][cap][3]: the colour after each */
    size_t nx[GK_N], at[GK_N][2];
    key_index *keys;
    size_t *act;
    int *tail_c0;
    size_t cap;
    int *wind;
    double col_empty[3];
} panel_worker;

static void fast_free(panel_worker *fs)
{
    aa_strip_free(fs->strip);
    free(fs->kind);
    free(fs->nnear);
    free(fs->cst);
    free(fs->g);
    free(fs->row_cells);
    free(fs->near_diff);
    free(fs->bad_diff);
    free(fs->runs);
    free(fs->bp);
    free(fs->cr);
    free(fs->keys);
    free(fs->act);
    free(fs->tail_c0);
    free(fs->col);
    free(fs->wind);
    memset(fs, 0, sizeof *fs);
}

/* Bytes a thread's panel buffers take. */
static size_t fast_bytes(const gauss_plan *pl, int w, int nc)
{
    size_t cells = (size_t)pl->np_max * (size_t)w;
    return cells * (1 + sizeof(unsigned short) + (size_t)nc * (GK_S + 1) * sizeof(double));
}

static int fast_init(panel_worker *fs, const gauss_plan *pl, const aa_filter *f,
                     const aa_scene *scene, int w)
{
    memset(fs, 0, sizeof *fs);
    fs->plan = pl;
    fs->f = f;
    fs->scene = scene;
    fs->w = w;
    fs->nc = aa_scene_is_grey(scene) ? 1 : 3;
    fs->ring = pl->np_max;
    size_t cells = (size_t)fs->ring * (size_t)w, nc = (size_t)fs->nc;
    int nl = aa_scene_layer_count(scene);
    fs->strip = aa_strip_new(scene);
    fs->kind = malloc(cells);
    fs->nnear = malloc(cells * sizeof *fs->nnear);
    fs->cst = malloc(cells * nc * sizeof *fs->cst);
    fs->g = malloc(cells * nc * GK_S * sizeof *fs->g);
    fs->row_cells = malloc((size_t)fs->ring * sizeof *fs->row_cells);
    fs->near_diff = malloc(((size_t)w + 1) * sizeof *fs->near_diff);
    fs->bad_diff = malloc(((size_t)w + 1) * sizeof *fs->bad_diff);
    fs->runs = malloc(((size_t)w + 1) * sizeof *fs->runs);
    fs->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *fs->wind);
    if (!fs->strip || !fs->kind || !fs->nnear || !fs->cst || !fs->g || !fs->row_cells ||
        !fs->near_diff || !fs->bad_diff || !fs->runs || !fs->wind) {
        fast_free(fs);
        return aa_fail(AA_ENOMEM, "out of memory for the Gaussian panels");
    }
    aa_rgb c = aa_scene_colour_of(scene, fs->wind);
    memcpy(fs->col_empty, c.c, sizeof fs->col_empty);
    return AA_OK;
}

static int fast_reserve(panel_worker *fs, size_t n)
{
    if (n < 16)
        n = 16; /* never empty: no null arrays for qsort and friends */
    if (n <= fs->cap)
        return AA_OK;
    size_t cap = 2 * n;
    void *p[6];
    p[0] = realloc(fs->bp, cap * sizeof *fs->bp);
    if (p[0])
        fs->bp = p[0];
    p[1] = realloc(fs->cr, GK_N * cap * sizeof *fs->cr);
    if (p[1])
        fs->cr = p[1];
    p[2] = realloc(fs->keys, cap * sizeof *fs->keys);
    if (p[2])
        fs->keys = p[2];
    p[3] = realloc(fs->act, cap * sizeof *fs->act);
    if (p[3])
        fs->act = p[3];
    p[4] = realloc(fs->col, GK_N * 3 * cap * sizeof *fs->col);
    if (p[4])
        fs->col = p[4];
    p[5] = realloc(fs->tail_c0, cap * sizeof *fs->tail_c0);
    if (p[5])
        fs->tail_c0 = p[5];
    for (int k = 0; k < 6; k++)
        if (!p[k])
            return aa_fail(AA_ENOMEM, "out of memory for a panel of %zu pieces", n);
    fs->cap = cap;
    return AA_OK;
}

static size_t ring_slot(const panel_worker *fs, long p)
{
    long r = p % fs->ring;
    return (size_t)(r < 0 ? r + fs->ring : r);
}

/* The columns whose window [i + 1/2 - R, i + 1/2 + R] meets [a, b]: from
 * c0, the first whose window reaches a, to c1, the last whose window starts
 * before b.  So a piece is wholly left of column i's window when c1 < i and
 * wholly right when c0 > i, also when it falls between two windows (c0 =
 * c1 + 1).  Clamped to [-1, w]. */
static void column_range(const panel_worker *fs, double a, double b, int *c0, int *c1)
{
    double lo = ceil(a - FAST_TOL - fs->plan->R - 0.5);
    double hi = floor(b + FAST_TOL + fs->plan->R - 0.5);
    *c0 = (int)fmin(fmax(lo, -1.0), (double)fs->w);
    *c1 = (int)fmin(fmax(hi, -1.0), (double)fs->w);
}

/* Count the columns c0..c1 (those in the image) in a difference array. */
static void mark(const panel_worker *fs, int *diff, int c0, int c1)
{
    c0 = c0 < 0 ? 0 : c0;
    c1 = c1 > fs->w - 1 ? fs->w - 1 : c1;
    if (c0 <= c1)
        diff[c0]++, diff[c1 + 1]--;
}

/* Steeper than FAST_SLOPE anywhere on [lo, hi]?  dx/dy is a ratio of
 * linear functions of t, so monotone between the piece's ends. */
static int steep(const aa_piece *p, double lo, double hi)
{
    double ts[2] = {aa_piece_t_at(p, lo), aa_piece_t_at(p, hi)};
    for (int k = 0; k < 2; k++) {
        double dy = p->by + 2.0 * p->ay * ts[k], dx = p->bx + 2.0 * p->ax * ts[k];
        if (!(dy > 0.0) || !(fabs(dx) <= FAST_SLOPE * dy))
            return 1;
    }
    return 0;
}

/* x(v) = X + S tau + Q tau^2 with tau = v - lo, for a piece whose y is
 * linear in its parameter (lines; arcs with ay = 0, such as crow's). */
static void as_quadratic(const local_piece *q, long double lo, long double *X, long double *S,
                         long double *Q)
{
    long double u = (lo - q->y0) / q->by;
    *X = q->x0 + u * (q->bx + q->ax * u);
    *S = (q->bx + 2 * q->ax * u) / q->by;
    *Q = q->ax / (q->by * q->by);
}

static int sign_tol(long double d)
{
    return d > FAST_TOL ? 1 : (d < -FAST_TOL ? -1 : 0);
}

/* May pieces a and b meet strictly inside the panel (va, vb), where both
 * are present?  Exact for pieces with x quadratic in y; any other pair
 * whose extents overlap is assumed to meet. */
static int may_meet(const band_piece *a, const band_piece *b, double va, double vb)
{
    long double lo = fmaxl(va, fmaxl(a->q.y0, b->q.y0));
    long double hi = fminl(vb, fminl(a->q.y1, b->q.y1));
    if (!(lo < hi))
        return 0;
    if (a->q.ay != 0 || b->q.ay != 0)
        return 1;
    long double Xa, Sa, Qa, Xb, Sb, Qb;
    as_quadratic(&a->q, lo, &Xa, &Sa, &Qa);
    as_quadratic(&b->q, lo, &Xb, &Sb, &Qb);
    long double X = Xb - Xa, S = Sb - Sa, Q = Qb - Qa, L = hi - lo;
    int s0 = sign_tol(X), s1 = sign_tol(X + L * (S + L * Q));
    if (s0 * s1 < 0 || (s0 == 0 && s1 == 0))
        return 1;
    if (Q != 0) {
        long double t = -S / (2 * Q);
        if (t > 0 && t < L) {
            int sm = sign_tol(X + t * (S + t * Q));
            if (sm == 0 || (s0 && sm != s0) || (s1 && sm != s1))
                return 1;
        }
    }
    return 0;
}

static int cmp_key(const void *a, const void *b)
{
    const key_index *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->k < q->k ? -1 : (p->k > q->k);
}

/* Mark the columns near pieces that may meet inside the panel: a sweep over
 * the x extents, testing the pairs that overlap. */
static void mark_meetings(panel_worker *fs, size_t nb, double va, double vb)
{
    if (nb < 2)
        return;
    for (size_t k = 0; k < nb; k++)
        fs->keys[k].key = fs->bp[k].xmin, fs->keys[k].k = k;
    qsort(fs->keys, nb, sizeof *fs->keys, cmp_key);
    size_t nact = 0;
    for (size_t s = 0; s < nb; s++) {
        const band_piece *b = &fs->bp[fs->keys[s].k];
        size_t keep = 0, tested = 0;
        int crowd = 0;
        for (size_t t = 0; t < nact; t++) {
            const band_piece *a = &fs->bp[fs->act[t]];
            if (a->xmax < b->xmin - FAST_TOL)
                continue; /* left behind for good: extents sorted by xmin */
            fs->act[keep++] = fs->act[t];
            if (crowd || ++tested > FAST_PAIRS) {
                crowd = 1;
                mark(fs, fs->bad_diff, a->c0, a->c1);
            } else if (may_meet(a, b, va, vb)) {
                mark(fs, fs->bad_diff, a->c0, a->c1);
                mark(fs, fs->bad_diff, b->c0, b->c1);
            }
        }
        if (crowd)
            mark(fs, fs->bad_diff, b->c0, b->c1);
        nact = keep;
        fs->act[nact++] = fs->keys[s].k;
    }
}

static int cmp_cross(const node_cross *a, const node_cross *b)
{
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    return a->k < b->k ? -1 : (a->k > b->k);
}

static int cmp_cross_q(const void *a, const void *b)
{
    return cmp_cross(a, b);
}

/* The crossings of node line m (height v) by the panel's pieces, sorted by
 * (x, piece), the colour after each, and where each falls in the cdf
 * table.  Pieces come sorted by their left end, so the crossings are nearly
 * sorted: insertion sort, or qsort past a budget of moves. */
static void node_crossings(panel_worker *fs, size_t nb, int m, long double v)
{
    node_cross *cr = fs->cr + (size_t)m * fs->cap;
    double *col = fs->col + (size_t)m * 3 * fs->cap;
    const gauss_plan *pl = fs->plan;
    size_t n = 0;
    for (size_t k = 0; k < nb; k++) {
        const band_piece *b = &fs->bp[k];
        if (!(v >= b->q.y0 && v < b->q.y1))
            continue;
        node_cross *c = &cr[n++];
        long double part = crossing_part(&b->q, v);
        c->x = (double)(b->q.x0 + part);
        c->k = (int)k;
        c->c0 = b->c0;
        c->c1 = b->c1;
        /* x - 1/2 = base/M + s dz.  x0 - (1/2 + base/M) is exact in long
         * double (both have few bits), so dz carries one rounding of x's
         * small part and none of its magnitude. */
        double xr = (c->x - 0.5) * pl->M + 0.5;
        long base = fabs(xr) < 1e15 ? (long)xr : 0;
        c->base = base - (xr < (double)base); /* floor */
        long double off = (b->q.x0 - (0.5L + (long double)c->base / pl->M)) + part;
        double dz = (double)off * pl->inv_s, dz2 = dz * dz, dz4 = dz2 * dz2;
        c->pw[0] = dz, c->pw[1] = dz2, c->pw[2] = dz2 * dz, c->pw[3] = dz4;
        c->pw[4] = dz4 * dz, c->pw[5] = dz4 * dz2, c->pw[6] = dz4 * c->pw[2];
    }
    size_t moves = 0, budget = 8 * n + 64;
    for (size_t k = 1; k < n; k++) {
        node_cross c = cr[k];
        size_t at = k;
        while (at > 0 && cmp_cross(&cr[at - 1], &c) > 0) {
            cr[at] = cr[at - 1];
            at--;
            moves++;
        }
        cr[at] = c;
        if (moves > budget) {
            qsort(cr, n, sizeof *cr, cmp_cross_q);
            break;
        }
    }
    int nl = aa_scene_layer_count(fs->scene);
    memset(fs->wind, 0, (size_t)(nl > 0 ? nl : 1) * sizeof *fs->wind);
    for (size_t k = 0; k < n; k++) {
        const local_piece *q = &fs->bp[cr[k].k].q;
        fs->wind[q->layer] += q->dir;
        aa_rgb c = aa_scene_colour_of(fs->scene, fs->wind);
        memcpy(col + 3 * k, c.c, sizeof c.c);
    }
    fs->nx[m] = n;
}

/* The cdf at x - uc for crossing c and column i: from the table, or (far
 * outside it, where it is 0 or 1 to within 1e-20, and which a near
 * crossing never is) from the filter itself. */
static double cross_cdf(const panel_worker *fs, const node_cross *c, int i)
{
    const gauss_plan *pl = fs->plan;
    long row = c->base - (long)i * pl->M + pl->kt;
    if (row >= 0 && row <= 2 * pl->kt) {
        const double *t = pl->cdf_tab + (size_t)row * (CDF_TERMS + 1);
        double sum = 0.0;
        for (int n = CDF_TERMS; n >= 1; n--)
            sum += t[n] * c->pw[n - 1];
        return t[0] + sum;
    }
    return aa_filter_cdf(fs->f, c->x - (i + 0.5));
}

/* The pieces near column i (their extent in the panel meets the window)
 * among the crossings cr[a..b) of a node line, sorted: they must be a run
 * cr[e..f), every crossing before it of a piece wholly left of the window
 * and every one after it (to b) of a piece wholly right.  Then the colours
 * after each crossing are those of the full line.  Returns 0 if the pieces
 * are not so ordered (the column then goes to QAG). */
static int near_run(const node_cross *cr, size_t a, size_t b, int i, size_t *e, size_t *f)
{
    size_t s = a;
    while (s < b && cr[s].c1 < i)
        s++;
    size_t t = s;
    while (t < b && cr[t].c0 <= i && i <= cr[t].c1)
        t++;
    for (size_t u = t; u < b; u++)
        if (cr[u].c0 <= i)
            return 0;
    *e = s, *f = t;
    return 1;
}

/* The inner integral of column i on node line m, whose near crossings are
 * cr[e..f): the integral over the whole line of the colours the near run
 * defines (the window's colours, extended beyond it on either side), a
 * smooth function of the near crossings.  Writes it to g[ch * GK_S]. */
static void node_value(const panel_worker *fs, int m, size_t e, size_t f, int i, double *g)
{
    const node_cross *cr = fs->cr + (size_t)m * fs->cap;
    const double *col = fs->col + (size_t)m * 3 * fs->cap;
    const double *cb = e > 0 ? col + 3 * (e - 1) : fs->col_empty;
    if (fs->nc == 1) {
        double acc = cb[0];
        if (e < f) {
            double prev = cross_cdf(fs, &cr[e], i);
            acc = cb[0] * prev;
            for (size_t t = e + 1; t <= f; t++) {
                double next = t < f ? cross_cdf(fs, &cr[t], i) : 1.0;
                acc += col[3 * (t - 1)] * (next - prev);
                prev = next;
            }
        }
        g[0] = acc;
        return;
    }
    double acc[3] = {cb[0], cb[1], cb[2]};
    if (e < f) {
        double prev = cross_cdf(fs, &cr[e], i);
        for (int ch = 0; ch < 3; ch++)
            acc[ch] = cb[ch] * prev;
        for (size_t t = e + 1; t <= f; t++) {
            double next = t < f ? cross_cdf(fs, &cr[t], i) : 1.0;
            for (int ch = 0; ch < 3; ch++)
                acc[ch] += col[3 * (t - 1) + ch] * (next - prev);
            prev = next;
        }
    }
    for (int ch = 0; ch < 3; ch++)
        g[ch * GK_S] = acc[ch];
}

static void zero_pad(const panel_worker *fs, double *gi)
{
    for (int ch = 0; ch < fs->nc; ch++)
        for (int m = GK_N; m < GK_S; m++)
            gi[ch * GK_S + m] = 0.0;
}

/* Do all node lines of the panel cross the same pieces in the same order?
 * (No piece begins or ends inside, none meets another: the usual case.) */
static int same_order(const panel_worker *fs)
{
    size_t n = fs->nx[0];
    for (int m = 1; m < GK_N; m++) {
        if (fs->nx[m] != n)
            return 0;
        const node_cross *a = fs->cr, *b = fs->cr + (size_t)m * fs->cap;
        for (size_t t = 0; t < n; t++)
            if (a[t].k != b[t].k)
                return 0;
    }
    return 1;
}

/* The node columns when every node line has the same order: the near run
 * of a column is then the same on every line, found once per column by
 * pointers that only move right.  Same values as columns_general. */
static void columns_same_order(panel_worker *fs, unsigned char *kind, unsigned short *nnear,
                               double *g)
{
    const node_cross *cr = fs->cr;
    size_t n = fs->nx[0], e = 0, f = 0;
    /* the smallest c0 from each position on: the pieces after a run must
     * all be wholly right of the window */
    int *tail = fs->tail_c0;
    for (size_t t = n; t-- > 0;)
        tail[t] = t + 1 < n && tail[t + 1] < cr[t].c0 ? tail[t + 1] : cr[t].c0;
    for (size_t r = 0; r + 1 < fs->nruns; r += 2) {
        for (int i = fs->runs[r]; i < fs->runs[r + 1]; i++) {
            while (e < n && cr[e].c1 < i)
                e++;
            if (f < e)
                f = e;
            while (f < n && cr[f].c0 <= i)
                f++;
            int ok = f >= n || tail[f] > i;
            for (size_t t = e; t < f && ok; t++)
                ok = cr[t].c1 >= i;
            if (!ok || kind[i] != PANEL_NODES) {
                kind[i] = ok ? kind[i] : PANEL_BAD;
                continue;
            }
            double *gi = g + (size_t)i * (size_t)fs->nc * GK_S;
            for (int m = 0; m < GK_N; m++)
                node_value(fs, m, e, f, i, gi + m);
            zero_pad(fs, gi);
            nnear[i] = (unsigned short)(f - e < 65535 ? f - e : 65535);
        }
    }
}

/* The node columns in general: per column and node line, the crossings
 * within `reach` of the window, then their near run. */
static void columns_general(panel_worker *fs, double reach, unsigned char *kind,
                            unsigned short *nnear, double *g)
{
    for (int m = 0; m < GK_N; m++)
        fs->at[m][0] = fs->at[m][1] = 0;
    for (size_t r = 0; r + 1 < fs->nruns; r += 2) {
        for (int i = fs->runs[r]; i < fs->runs[r + 1]; i++) {
            double uc = i + 0.5;
            double *gi = g + (size_t)i * (size_t)fs->nc * GK_S;
            zero_pad(fs, gi);
            for (int m = 0; m < GK_N; m++) {
                const node_cross *cr = fs->cr + (size_t)m * fs->cap;
                size_t nx = fs->nx[m], a = fs->at[m][0], b = fs->at[m][1], e, f;
                while (a < nx && cr[a].x < uc - reach)
                    a++;
                if (b < a)
                    b = a;
                while (b < nx && cr[b].x <= uc + reach)
                    b++;
                fs->at[m][0] = a, fs->at[m][1] = b;
                if (kind[i] != PANEL_NODES)
                    continue;
                if (!near_run(cr, a, b, i, &e, &f)) {
                    kind[i] = PANEL_BAD;
                    continue;
                }
                node_value(fs, m, e, f, i, gi + m);
                if (f - e > nnear[i])
                    nnear[i] = (unsigned short)(f - e < 65535 ? f - e : 65535);
            }
        }
    }
}

/* Compute panel p into its ring slot. */
static int fast_panel(panel_worker *fs, long p)
{
    const gauss_plan *pl = fs->plan;
    int w = fs->w, nc = fs->nc;
    size_t slot = ring_slot(fs, p), base = slot * (size_t)w;
    unsigned char *kind = fs->kind + base;
    unsigned short *nnear = fs->nnear + base;
    double *cst = fs->cst + base * (size_t)nc;
    double *g = fs->g + base * (size_t)nc * GK_S;
    double va = panel_edge(pl, p), vb = panel_edge(pl, p + 1);
    int st = aa_strip_begin(fs->strip, va, vb);
    if (st)
        return st;
    aa_strip_window(fs->strip, -INFINITY, INFINITY);
    size_t n;
    const aa_piece *const *list = aa_strip_local(fs->strip, &n);
    if ((st = fast_reserve(fs, n)))
        return st;
    memset(fs->near_diff, 0, ((size_t)w + 1) * sizeof *fs->near_diff);
    memset(fs->bad_diff, 0, ((size_t)w + 1) * sizeof *fs->bad_diff);
    /* The inner integral G of a column is analytic on the panel unless a
     * piece near it ends inside, is flat inside, is steep, or meets
     * another; those columns are marked for QAG. */
    size_t nb = 0;
    double reach = 0.0; /* widest extent of a piece that is not marked */
    for (size_t k = 0; k < n; k++) {
        const aa_piece *q = list[k];
        int c0, c1;
        if (!q->dir) { /* flat strictly inside the panel */
            column_range(fs, q->xmin, q->xmax, &c0, &c1);
            mark(fs, fs->bad_diff, c0, c1);
            continue;
        }
        double lo = fmax(va, q->y0), hi = fmin(vb, q->y1);
        if (!(lo < hi))
            continue; /* begins at the panel's bottom: meets no node line */
        band_piece *b = &fs->bp[nb++];
        aa_piece_xrange(q, lo, hi, &b->xmin, &b->xmax);
        column_range(fs, b->xmin, b->xmax, &b->c0, &b->c1);
        set_local(&b->q, q, 0, 0);
        mark(fs, fs->near_diff, b->c0, b->c1);
        if ((q->y0 > va && q->y0 < vb) || (q->y1 > va && q->y1 < vb) || steep(q, lo, hi))
            mark(fs, fs->bad_diff, b->c0, b->c1);
        else
            reach = fmax(reach, b->xmax - b->xmin);
    }
    mark_meetings(fs, nb, va, vb);
    int nearc = 0, badc = 0, prev = PANEL_CONST;
    fs->nruns = 0;
    for (int i = 0; i < w; i++) {
        nearc += fs->near_diff[i];
        badc += fs->bad_diff[i];
        kind[i] = badc ? PANEL_BAD : (nearc ? PANEL_NODES : PANEL_CONST);
        nnear[i] = 0;
        if (kind[i] == PANEL_NODES && prev != PANEL_NODES)
            fs->runs[fs->nruns++] = i;
        if (kind[i] != PANEL_NODES && prev == PANEL_NODES)
            fs->runs[fs->nruns++] = i;
        prev = kind[i];
    }
    if (prev == PANEL_NODES)
        fs->runs[fs->nruns++] = w;
    reach += pl->R + 2 * FAST_TOL;
    for (int m = 0; m < GK_N; m++)
        node_crossings(fs, nb, m, node_height(pl, p, m));
    /* constant columns: no piece near, one colour on the window */
    const node_cross *mid = fs->cr + (size_t)(GK_N / 2) * fs->cap;
    const double *midcol = fs->col + (size_t)(GK_N / 2) * 3 * fs->cap;
    size_t at = 0, nmid = fs->nx[GK_N / 2];
    for (int i = 0; i < w; i++) {
        if (kind[i] != PANEL_CONST)
            continue;
        while (at < nmid && mid[at].x < i + 0.5)
            at++;
        const double *c = at > 0 ? midcol + 3 * (at - 1) : fs->col_empty;
        for (int ch = 0; ch < nc; ch++)
            cst[(size_t)i * nc + ch] = c[ch];
    }
    /* the others, column by column so that each writes its own block */
    if (same_order(fs))
        columns_same_order(fs, kind, nnear, g);
    else
        columns_general(fs, reach, kind, nnear, g);
    return AA_OK;
}

/* Make sure the panels of row j are in the ring, and note where. */
static int fast_row(panel_worker *fs, int j, int *phase)
{
    const gauss_plan *pl = fs->plan;
    int ph = j % pl->num;
    long lo = (long)(j / pl->num) * pl->den + pl->r0[ph], hi = lo + pl->np[ph] - 1;
    if (!fs->valid || lo < fs->lo || lo > fs->hi + 1) {
        fs->lo = lo;
        fs->hi = lo - 1;
        fs->valid = 1;
    }
    while (fs->hi < hi) {
        long p = fs->hi + 1;
        if (p - fs->lo + 1 > fs->ring)
            fs->lo = p - fs->ring + 1; /* its slot is reused */
        int st = fast_panel(fs, p);
        if (st) {
            fs->valid = 0;
            return st;
        }
        fs->hi = p;
    }
    for (int k = 0; k < pl->np[ph]; k++)
        fs->row_cells[k] = ring_slot(fs, lo + k) * (size_t)fs->w;
    *phase = ph;
    return AA_OK;
}

/* sum a[m] g[m] and sum d[m] g[m] over GK_S values: pairs of doubles in
 * three independent chains each (the order is fixed, so the result does
 * not depend on where or by whom it is computed). */
typedef double v2d __attribute__((vector_size(16)));

static void dot2(const double *a, const double *d, const double *g, double *s, double *e)
{
    v2d sa[3] = {{0, 0}, {0, 0}, {0, 0}}, sd[3] = {{0, 0}, {0, 0}, {0, 0}};
    for (int m = 0; m < GK_S; m += 6) {
        for (int c = 0; c < 3; c++) {
            v2d av, dv, gv;
            memcpy(&av, a + m + 2 * c, sizeof av);
            memcpy(&dv, d + m + 2 * c, sizeof dv);
            memcpy(&gv, g + m + 2 * c, sizeof gv);
            sa[c] += av * gv;
            sd[c] += dv * gv;
        }
    }
    v2d ts = sa[0] + sa[1] + sa[2], td = sd[0] + sd[1] + sd[2];
    *s = ts[0] + ts[1];
    *e = td[0] + td[1];
}

/* Pixel i of the current row: the fixed rule's value and bound, or 0 if a
 * panel is marked or the bound is too large for it. */
static int fast_pixel(const panel_worker *fs, int j, int phase, int i, int grey, double *value,
                      double *bound)
{
    const gauss_plan *pl = fs->plan;
    int np = pl->np[phase], nc = fs->nc, nmax = 0;
    size_t cell0 = (size_t)phase * (size_t)pl->np_max;
    for (int k = 0; k < np; k++)
        if (fs->kind[fs->row_cells[k] + (size_t)i] == PANEL_BAD)
            return 0;
    double val[3] = {0, 0, 0}, est[3] = {0, 0, 0};
    for (int k = 0; k < np; k++) {
        size_t cell = fs->row_cells[k] + (size_t)i;
        if (fs->kind[cell] == PANEL_CONST) {
            for (int ch = 0; ch < nc; ch++)
                val[ch] += pl->mass[cell0 + (size_t)k] * fs->cst[cell * (size_t)nc + (size_t)ch];
            continue;
        }
        if (fs->nnear[cell] > nmax)
            nmax = fs->nnear[cell];
        const double *a = pl->a + (cell0 + (size_t)k) * GK_S;
        const double *d = pl->d + (cell0 + (size_t)k) * GK_S;
        for (int ch = 0; ch < nc; ch++) {
            const double *g = fs->g + (cell * (size_t)nc + (size_t)ch) * GK_S;
            double s, e;
            dot2(a, d, g, &s, &e);
            val[ch] += s;
            est[ch] += fabs(e);
        }
    }
    double worst = fmax(est[0], fmax(est[1], est[2]));
    /* Rounding (colours in [0, 1], weights summing to 1): the dot products
     * and the weights; per node value, 2 ulps per tabulated cdf and the
     * sum over the near crossings; the node heights, exact within a few
     * ulps in the weights and an ulp of long double in G. */
    double rnd = DBL_EPSILON * ((double)(np * (GK_N + 1) + 4 + 3 * (nmax + 1)) + pl->node_err) +
                 LDBL_EPSILON * (j + pl->R + 2.0) * (double)(nmax + 1) * pl->peak * FAST_SLOPE;
    double b = worst + 2.0 * pl->lost + rnd;
    if (!(b <= FAST_LIMIT))
        return 0;
    for (int ch = 0; ch < 3; ch++)
        value[ch] = val[grey ? 0 : ch];
    *bound = b;
    return 1;
}

/* ------------------------------------------------------------------------
 * Rows and the whole image
 * ------------------------------------------------------------------------ */

typedef struct row_stats {
    size_t integrated, filled, fast;
    double max_bound;
    int worst_i, worst_j;
} row_stats;

/* Row j.  fs, if not NULL, offers the fixed rule to the non-uniform
 * pixels (Gaussian); the others, or those it declines, take QAG. */
static int render_row(worker *w, panel_worker *fs, int j, aa_image *out, aa_image *bound,
                      row_stats *rs)
{
    double R = w->R;
    int grey = aa_scene_is_grey(w->scene);
    w->vc = j + 0.5;
    int st = aa_strip_begin(w->strip, w->vc - R, w->vc + R);
    if (st)
        return st;
    int phase = 0, panels = 0;
    for (int i = 0; i < out->w;) {
        double *px = aa_pixel(out, i, j), b;
        w->uc = i + 0.5;
        if (aa_strip_window(w->strip, w->uc - R, w->uc + R) == 0) {
            /* a run of uniform windows: one colour, no integration */
            aa_rgb c;
            int end = aa_strip_uniform_run(w->strip, i, out->w, R, w->vc, w->wind, &c);
            b = w->f->lost;
            for (int k = i; k < end; k++, px += 3) {
                px[0] = c.c[0], px[1] = c.c[1], px[2] = c.c[2];
                if (bound)
                    *aa_pixel(bound, k, j) = b;
            }
            rs->filled += (size_t)(end - i);
            if (b > rs->max_bound) {
                rs->max_bound = b;
                rs->worst_i = i;
                rs->worst_j = j;
            }
            i = end;
            continue;
        }
        /* the row's panels, computed when a pixel first needs them */
        if (fs && !panels && (st = fast_row(fs, j, &phase)))
            return st;
        panels = 1;
        if (fs && fast_pixel(fs, j, phase, i, grey, px, &b))
            rs->fast++;
        else if ((st = integrate_pixel(w, grey, px, &b)))
            return st;
        rs->integrated++;
        if (bound)
            *aa_pixel(bound, i, j) = b;
        if (b > rs->max_bound) {
            rs->max_bound = b;
            rs->worst_i = i;
            rs->worst_j = j;
        }
        i++;
    }
    return AA_OK;
}

/* A field scene: the field's own exact pixel integral (aabench.h,
 * "Fields"); every pixel counts as integrated. */
static int field_render(const aa_scene *placed, const aa_filter *f, int threads, aa_image *out,
                        aa_image *bound, aa_truth_stats *stats, size_t *nfast)
{
    const double *p;
    double map[4], max_bound = 0.0;
    int worst[2] = {-1, -1};
    const aa_field_type *field = aa_scene_field(placed, &p, NULL, map);
    int st = field->pixels(p, map, f, threads, out, bound, &max_bound, worst);
    if (st)
        return aa_fail_context(st, "field %s", field->name);
    if (stats) {
        stats->integrated = (size_t)out->w * (size_t)out->h;
        stats->filled = 0;
        stats->max_bound = max_bound;
        stats->worst_i = worst[0];
        stats->worst_j = worst[1];
    }
    if (nfast)
        *nfast = 0;
    return AA_OK;
}

int aa_long_double_is_extended(void)
{
    volatile long double one = 1.0L, tiny = 0x1p-60L;
    return one + tiny != one;
}

int aa__truth_render_mode(const aa_scene *placed, const aa_filter *f, int threads, int mode,
                          aa_image *out, aa_image *bound, aa_truth_stats *stats, size_t *nfast)
{
    if (!out || !out->v || out->c != 3)
        return aa_fail(AA_EINVAL, "reference needs a 3-channel image");
    if (bound && (bound->w != out->w || bound->h != out->h || bound->c != 1))
        return aa_fail(AA_EINVAL, "reference bound image must be %dx%dx1", out->w, out->h);
    if (aa_scene_field(placed, NULL, NULL, NULL))
        return field_render(placed, f, threads, out, bound, stats, nfast);
    gsl_set_error_handler_off(); /* QAG's status is judged by its error estimate */
    int status = AA_OK;
    char message[1024] = "";
    row_stats total = {0, 0, 0, 0.0, -1, -1};
#ifdef _OPENMP
    int nthreads = threads > 0 ? threads : omp_get_max_threads();
#else
    int nthreads = 1;
    (void)threads;
#endif
    /* The Gaussian takes the fixed rule, unless asked not to, or its panel
     * buffers would be unreasonably large, or the windows of neighbouring
     * rows do not overlap (s < 1/16: no panel to share, and QAG is then
     * as fast: measured on crow 256x256, s = 0.05), or long double is no
     * wider than double where it runs (the rule's node heights count on
     * the 64-bit mantissa; valgrind, for one, emulates the x87 in double:
     * its error then reached 1.2e-12 on a half-plane at s = 0.07). */
    gauss_plan plan;
    int use_fast = 0;
    if (f->type == &aa_filter_gauss && mode != AA__TRUTH_QAG && 2.0 * f->radius >= 1.0 &&
        aa_long_double_is_extended()) {
        if ((status = plan_init(&plan, f)))
            return status;
        use_fast = fast_bytes(&plan, out->w, aa_scene_is_grey(placed) ? 1 : 3) <= FAST_MAX_BYTES;
        if (!use_fast)
            plan_free(&plan);
    }
    /* Rows go to threads in blocks, so that a thread's panels serve many
     * rows; a panel's values do not depend on who computes it, so the image
     * does not depend on the blocks. */
    int rows = 1;
    if (use_fast)
        rows = nthreads == 1 ? out->h : (out->h + 4 * nthreads - 1) / (4 * nthreads);
    int nblocks = (out->h + rows - 1) / rows;
#pragma omp parallel num_threads(nthreads)
    {
        worker w;
        panel_worker fs;
        row_stats rs = {0, 0, 0, 0.0, -1, -1};
        int st = worker_init(&w, placed, f);
        memset(&fs, 0, sizeof fs);
        if (!st && use_fast)
            st = fast_init(&fs, &plan, f, placed, out->w);
#pragma omp for schedule(dynamic, 1)
        for (int blk = 0; blk < nblocks; blk++) {
            fs.valid = 0;
            int j1 = (blk + 1) * rows < out->h ? (blk + 1) * rows : out->h;
            for (int j = blk * rows; j < j1 && st == AA_OK; j++)
                st = render_row(&w, use_fast ? &fs : NULL, j, out, bound, &rs);
        }
        worker_free(&w);
        fast_free(&fs);
#pragma omp critical(aa_truth_merge)
        {
            if (st && !status) {
                status = st;
                /* messages are per thread: carry this one to the caller's */
                snprintf(message, sizeof message, "%s", aa_last_error());
            }
            total.integrated += rs.integrated;
            total.filled += rs.filled;
            total.fast += rs.fast;
            if (rs.max_bound > total.max_bound ||
                (rs.max_bound == total.max_bound && rs.worst_j >= 0 &&
                 (total.worst_j < 0 || rs.worst_j < total.worst_j))) {
                total.max_bound = rs.max_bound;
                total.worst_i = rs.worst_i;
                total.worst_j = rs.worst_j;
            }
        }
    }
    if (use_fast)
        plan_free(&plan);
    if (status)
        aa_fail(status, "%s", message);
    if (stats) {
        stats->integrated = total.integrated;
        stats->filled = total.filled;
        stats->max_bound = total.max_bound;
        stats->worst_i = total.worst_i;
        stats->worst_j = total.worst_j;
    }
    if (nfast)
        *nfast = total.fast;
    return status;
}

int aa_truth_render(const aa_scene *placed, const aa_filter *f, int threads, aa_image *out,
                    aa_image *bound, aa_truth_stats *stats)
{
    return aa__truth_render_mode(placed, f, threads, 0, out, bound, stats, NULL);
}
