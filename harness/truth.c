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
 * and the filter's integral over a span is a difference of its cdf.  The
 * outer integral along v is done by GSL's QAGP with breakpoints wherever
 * that inner function is not smooth: the ends of pieces (vertices),
 * horizontal edges, the heights where a piece crosses a vertical line at
 * which the filter has a kink (the window's sides for the box; r, 0, -r for
 * the tent), the filter's own kinks along v, and the intersections of
 * pieces with lines.  Between breakpoints the integrand is smooth; for
 * `crow` and the box it is a polynomial of degree 2 and the first 21-point
 * Gauss-Kronrod pass is exact.
 *
 * The integration runs in coordinates relative to the pixel centre, and the
 * crossings are evaluated in extended precision (long double) from the
 * pieces' control points, so that at 4096 pixels, where an absolute
 * coordinate's last bit is 5e-13 px, the inner integral still carries only
 * rounding of the order of 1e-16.
 *
 * Each pixel carries an error bound: QAGP's estimate, plus the weight of
 * the Gaussian outside its truncation square, plus the rounding of the
 * relative crossings.  Pixels whose window meets no piece are uniform: they
 * take the colour of their centre with no integration.  This path shares
 * nothing with the methods beyond the scene's own queries (the strip tells
 * which pieces are near a window and the winding numbers left of it).
 */
#include "aabench.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* QAGP is asked for this absolute accuracy per pixel and channel: above its
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
    local_piece *lp;
    crossing *cross;
    size_t nlp, cap_lp;
    int *wind;
    double uc, vc, R;
    int channel;
    int box;
} worker;

static void worker_free(worker *w)
{
    aa_strip_free(w->strip);
    if (w->ws)
        gsl_integration_workspace_free(w->ws);
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
    w->R = f->radius;
    w->limit = 1024;
    w->strip = aa_strip_new(scene);
    w->ws = gsl_integration_workspace_alloc(w->limit);
    int nl = aa_scene_layer_count(scene);
    w->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *w->wind);
    if (!w->strip || !w->ws || !w->wind) {
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

/* Heights where pieces p and q meet, for lines and a line with an arc (an
 * arc with an arc would need a quartic: left to QAGP's bisection). */
static int add_intersections(worker *w, const aa_piece *p, const aa_piece *q)
{
    if (!p->dir || !q->dir)
        return AA_OK;
    if (p->kind == AA_PIECE_QUAD) {
        const aa_piece *t = p;
        p = q;
        q = t;
    }
    if (p->kind == AA_PIECE_QUAD)
        return AA_OK;
    double lo = fmax(p->y0, q->y0), hi = fmin(p->y1, q->y1);
    if (!(lo < hi))
        return AA_OK;
    /* line p: x = p.x0 + (y - p.y0) s */
    double s = p->bx / p->by;
    if (q->kind == AA_PIECE_LINE) {
        double r = q->bx / q->by;
        if (s == r)
            return AA_OK;
        double y = (q->x0 - p->x0 + p->y0 * s - q->y0 * r) / (s - r);
        return add_abs(w, y, lo, hi);
    }
    /* arc q(t) against line p: (ax - s ay) t^2 + (bx - s by) t + c = 0 */
    double a = q->ax - s * q->ay, b = q->bx - s * q->by;
    double c = q->x0 - p->x0 - (q->y0 - p->y0) * s;
    double ts[2];
    int n = 0;
    if (a == 0.0) {
        if (b != 0.0)
            ts[n++] = -c / b;
    } else {
        double d = b * b - 4.0 * a * c;
        if (d < 0.0)
            return AA_OK;
        double h = -0.5 * (b + copysign(sqrt(d), b));
        if (h != 0.0)
            ts[n++] = c / h;
        ts[n++] = h / a;
    }
    for (int k = 0; k < n; k++) {
        int st;
        if (ts[k] > 0.0 && ts[k] < 1.0 &&
            (st = add_abs(w, q->y0 + ts[k] * (q->by + ts[k] * q->ay), lo, hi)))
            return st;
    }
    return AA_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
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
        /* Start QAGP on panels two standard deviations wide, where one
         * 21-point pass integrates the Gaussian factor to rounding. */
        double sd = w->f->spec.v[0];
        for (double z = -w->R + 2.0 * sd; z < w->R && !st; z += 2.0 * sd)
            st = add_point(w, z);
    }
    for (size_t k = 0; k < n && !st; k++) {
        const aa_piece *p = local[k];
        double ys[2];
        if ((st = add_abs(w, p->y0, -INFINITY, INFINITY)) ||
            (st = add_abs(w, p->y1, -INFINITY, INFINITY)))
            break;
        if (p->kind == AA_PIECE_FLAT)
            continue;
        /* where the piece crosses a vertical line at which the filter's
         * cdf has a kink (the window's sides for the box) */
        for (int j = 0; j < nk && !st; j++) {
            int m = aa_piece_meet_x(p, w->uc + kink[j], ys);
            for (int q = 0; q < m && !st; q++)
                st = add_abs(w, ys[q], -INFINITY, INFINITY);
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
    long double uc = w->uc, vc = w->vc;
    w->nlp = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *p = local[k];
        if (!p->dir)
            continue; /* flat: no crossing, only a breakpoint */
        local_piece *q = &w->lp[w->nlp++];
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
    return AA_OK;
}

/* x - uc where the piece meets the line at height s = y - vc (active). */
static long double crossing_at(const local_piece *q, long double s)
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
    return q->x0 + t * (q->bx + t * q->ax);
}

/* The inner integral along u at height s = v - vc, for one channel, times
 * w(s).  Coordinates are relative to the pixel centre; the window is
 * [-R, R]. */
static double integrand(double s, void *params)
{
    worker *w = params;
    double ws = w->box ? 1.0 : aa_filter_weight(w->f, s);
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
            double fnext = w->box ? next : aa_filter_cdf(w->f, next);
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
    gsl_function F = {integrand, w};
    double worst = 0.0;
    for (int ch = 0; ch < (grey ? 1 : 3); ch++) {
        double result = 0.0, abserr = 0.0;
        w->channel = ch;
        gsl_integration_qagp(&F, w->pts, w->npts, TRUTH_EPSABS, 0.0, w->limit, w->ws,
                             &result, &abserr);
        value[ch] = result;
        worst = fmax(worst, abserr);
    }
    if (grey)
        value[1] = value[2] = value[0];
    /* Rounding: relative crossings are within a few ulps of R (long double
     * arithmetic, then one rounding to double); each moves the inner
     * integral by at most that times the filter's peak. */
    double peak = w->box ? 1.0 : aa_filter_weight(w->f, 0.0);
    *bound = worst + w->f->lost + 8.0 * DBL_EPSILON * fmax(w->R, 1.0) * peak * (double)n;
    return AA_OK;
}

typedef struct row_stats {
    size_t integrated, filled;
    double max_bound;
    int worst_i, worst_j;
} row_stats;

static int render_row(worker *w, int j, aa_image *out, aa_image *bound, row_stats *rs)
{
    double R = w->R;
    int grey = aa_scene_is_grey(w->scene);
    w->vc = j + 0.5;
    int st = aa_strip_begin(w->strip, w->vc - R, w->vc + R);
    if (st)
        return st;
    size_t events = (size_t)-1;
    aa_rgb uniform = {{0, 0, 0}};
    for (int i = 0; i < out->w; i++) {
        double *px = aa_pixel(out, i, j), b;
        w->uc = i + 0.5;
        if (aa_strip_window(w->strip, w->uc - R, w->uc + R) == 0) {
            /* A run of uniform windows with no piece entering or leaving
             * between them has one colour. */
            if (aa_strip_events(w->strip) != events) {
                uniform = aa_strip_colour_at(w->strip, w->uc, w->vc);
                events = aa_strip_events(w->strip);
            }
            px[0] = uniform.c[0], px[1] = uniform.c[1], px[2] = uniform.c[2];
            b = w->f->lost;
            rs->filled++;
        } else {
            events = (size_t)-1;
            if ((st = integrate_pixel(w, grey, px, &b)))
                return st;
            rs->integrated++;
        }
        if (bound)
            *aa_pixel(bound, i, j) = b;
        if (b > rs->max_bound) {
            rs->max_bound = b;
            rs->worst_i = i;
            rs->worst_j = j;
        }
    }
    return AA_OK;
}

int aa_truth_render(const aa_scene *placed, const aa_filter *f, int threads, aa_image *out,
                    aa_image *bound, aa_truth_stats *stats)
{
    if (!out || !out->v || out->c != 3)
        return aa_fail(AA_EINVAL, "reference needs a 3-channel image");
    if (bound && (bound->w != out->w || bound->h != out->h || bound->c != 1))
        return aa_fail(AA_EINVAL, "reference bound image must be %dx%dx1", out->w, out->h);
    gsl_set_error_handler_off(); /* QAGP's status is judged by its error estimate */
    int status = AA_OK;
    char message[1024] = "";
    row_stats total = {0, 0, 0.0, -1, -1};
#ifdef _OPENMP
    int nthreads = threads > 0 ? threads : omp_get_max_threads();
#else
    int nthreads = 1;
    (void)threads;
#endif
#pragma omp parallel num_threads(nthreads)
    {
        worker w;
        row_stats rs = {0, 0, 0.0, -1, -1};
        int st = worker_init(&w, placed, f);
#pragma omp for schedule(dynamic, 1)
        for (int j = 0; j < out->h; j++) {
            if (st == AA_OK)
                st = render_row(&w, j, out, bound, &rs);
        }
        worker_free(&w);
#pragma omp critical(aa_truth_merge)
        {
            if (st && !status) {
                status = st;
                /* messages are per thread: carry this one to the caller's */
                snprintf(message, sizeof message, "%s", aa_last_error());
            }
            total.integrated += rs.integrated;
            total.filled += rs.filled;
            if (rs.max_bound > total.max_bound ||
                (rs.max_bound == total.max_bound && rs.worst_j >= 0 &&
                 (total.worst_j < 0 || rs.worst_j < total.worst_j))) {
                total.max_bound = rs.max_bound;
                total.worst_i = rs.worst_i;
                total.worst_j = rs.worst_j;
            }
        }
    }
    if (status)
        aa_fail(status, "%s", message);
    if (stats) {
        stats->integrated = total.integrated;
        stats->filled = total.filled;
        stats->max_bound = total.max_bound;
        stats->worst_i = total.worst_i;
        stats->worst_j = total.worst_j;
    }
    return status;
}
