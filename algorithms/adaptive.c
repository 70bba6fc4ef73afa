/*
 * adaptive.c: adaptive scanline antialiasing (Ramos and Borges, "Anti-aliasing
 * rapido para algoritmo de scan line", secs. 3 and 5, figs. 1 and 2; after
 * Wyvill and Sharp 1989).
 *
 * The image is sampled at pixel corners, not centres: a row of W + 1 corner
 * colours is kept from the previous scanline (their "historico da linha
 * anterior"), so each corner is shared by the four pixels that meet there.
 * A pixel whose four corners agree (no channel differs by more than
 * `threshold`) and which no edge touches is painted their colour with no
 * further work.  Otherwise, on each border whose two corners differ, a
 * binary search of `depth` steps finds where the colour changes (one change
 * per border, as in the paper), and the pixel's value is integrated over
 * the fan of triangles that join the pixel's boundary, cut at the found
 * points, to the centroid of the found points (fig. 2): the part of the
 * boundary from a corner to a found point has that corner's colour, a
 * border with no change the mean of its corners.  With a single straight
 * edge the centroid lies on the edge and the fan is exact but for the
 * search's resolution (the paper's remark); a curved edge is replaced by
 * its chord.
 *
 * `tag=0`, the default, is the paper's method as published (secs. 3 and 5):
 * a pixel whose corners agree takes their mean, whatever lies between them.
 * The paper says what this misses (sec. 6: a polygon inside a pixel, 6a;
 * vertices inside a pixel with the edges on one border, 6b; two edges on
 * one border, 6c; a polygon thinner than a pixel across it, 6d) and offers
 * preprocessing of the polygons (6a, 6d), not a change to the method.
 *
 * `tag=1` is an extension, not in the paper: tagging (Crow 1976, ch. 3:
 * the pixels an edge touches are known from the scan conversion) with
 * Wyvill and Sharp's subdivision.  A pixel that the scene's scanline strip
 * says holds an edge but whose corners all agree, or that holds more than
 * one edge piece, is refined: it is split into 2^levels x 2^levels cells
 * and the same corner method runs on each cell.  It finds the bands
 * thinner than a pixel that cross no corner and splits pixels with two
 * edges (cases 6a, 6c, 6d, as far as a cell's corners see them).
 *
 * Measured (aabench run, 256x256, box; samples as counted, see below):
 *
 *     crow  adaptive (tag=0)        RMSE 0.0863   321 259 samples
 *           adaptive:tag=1          RMSE 0.0251   376 119
 *           adaptive:tag=1,levels=2 RMSE 0.0123   471 693
 *           supersample:n=3         RMSE 0.0433   238 320
 *           supersample:n=4         RMSE 0.0291   423 680
 *     star  adaptive (tag=0)        RMSE 0.0275   177 569
 *           adaptive:tag=1          RMSE 0.0086   189 509
 *           supersample:n=4         RMSE 0.0129   176 896
 *
 * So the paper's method is worse than supersampling at equal samples on
 * both (crow's bands are from 0.5 to 4 pixels wide, and its thin end is
 * case 6d; star's spokes meet in the centre, cases 6a and 6c), while the
 * extension beats it with fewer samples on crow and about equal ones on
 * star.  The paper reports no error measurements, only that the result is
 * "in general" better than "usual implementations of non-adaptive
 * supersampling" (abstract), and that the time grew by under 30% (sec. 7).
 *
 * Counters: `samples` are the point evaluations of one pass over the image
 * (the (W+1)(H+1) corners, every search step, every cell corner); threads
 * that start inside the image evaluate their first corner row again, which
 * is not counted.  `expensive_pixels` are the pixels that took a search or
 * were refined.
 *
 * Limits.  The box filter only.  One change per border, found to 2^-depth
 * of the border; the fan replaces curves by chords; with tag=0, whatever
 * crosses no corner of its pixel is lost (the paper's sec. 6); with tag=1,
 * features smaller than a refined cell that miss its corners.  Colours come from the
 * scanline strips (aa_strip_colour_at), so a sample costs the local pieces
 * of its pixel, not the scene.
 */
#include "methods.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

enum { P_THRESHOLD, P_DEPTH, P_TAG, P_LEVELS };

static const aa_param adaptive_params[] = {
    {"threshold", AA_PARAM_REAL, 1.0 / 64.0, 0.0, 1.0, 0, NULL,
     "largest channel difference of two corners taken as the same colour"},
    {"depth", AA_PARAM_INT, 5, 1, 40, 0, NULL, "binary search steps along a border"},
    {"tag", AA_PARAM_INT, 0, 0, 1, 0, NULL,
     "0: the paper's method; 1 (an extension): refine pixels the scene's edges touch that "
     "the corners cannot resolve"},
    {"levels", AA_PARAM_INT, 1, 0, 4, 0, NULL,
     "tag=1: a refined pixel is split into 2^levels cells a side"},
    {0}};

#define MAX_SIDE 17 /* 2^4 + 1 cell corners a side */

typedef struct ad_worker {
    aa_strip *strip;
    aa_rgb *top, *bottom; /* corner rows, W + 1 each */
    uint64_t samples, expensive;
    int failed; /* a strip could not be built */
} ad_worker;

typedef struct ad_state {
    const aa_scene *scene;
    int w, nworkers;
    ad_worker *workers;
} ad_state;

typedef struct ad_ctx {
    const aa_strip *strip;
    double threshold;
    int depth;
    uint64_t samples;
} ad_ctx;

static int adaptive_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "adaptive estimates box-filtered pixel areas and no other "
                                  "filter (use -f box)");
    return AA_OK;
}

static void state_free(ad_state *S)
{
    for (int t = 0; t < S->nworkers; t++) {
        aa_strip_free(S->workers[t].strip);
        free(S->workers[t].top);
        free(S->workers[t].bottom);
    }
    free(S->workers);
    S->workers = NULL;
    S->nworkers = 0;
}

static int state_ready(ad_state *S, const aa_job *job)
{
    if (S->workers && S->scene == job->placed && S->w == job->w && S->nworkers >= job->threads)
        return AA_OK;
    state_free(S);
    S->workers = calloc((size_t)job->threads, sizeof *S->workers);
    if (!S->workers)
        return aa_fail(AA_ENOMEM, "adaptive: out of memory");
    S->nworkers = job->threads;
    for (int t = 0; t < job->threads; t++) {
        ad_worker *wk = &S->workers[t];
        wk->strip = aa_strip_new(job->placed);
        wk->top = malloc((size_t)(job->w + 1) * sizeof *wk->top);
        wk->bottom = malloc((size_t)(job->w + 1) * sizeof *wk->bottom);
        if (!wk->strip || !wk->top || !wk->bottom) {
            state_free(S);
            return aa_fail(AA_ENOMEM, "adaptive: out of memory");
        }
    }
    S->scene = job->placed, S->w = job->w;
    return AA_OK;
}

static inline int differ(aa_rgb a, aa_rgb b, double threshold)
{
    for (int c = 0; c < 3; c++)
        if (fabs(a.c[c] - b.c[c]) > threshold)
            return 1;
    return 0;
}

static inline aa_rgb sample(ad_ctx *cx, double x, double y)
{
    cx->samples++;
    return aa_strip_colour_at(cx->strip, x, y);
}

/* The corner method on the square cell with corners q[0..3] (counter-
 * clockwise along the boundary: (x0,y0), (x0+s,y0), (x0+s,y0+s), (x0,y0+s))
 * of colours c[0..3]: adds the cell's mean colour times `weight` to acc;
 * returns 1 if a border was searched. */
static int cell(ad_ctx *cx, double x0, double y0, double s, const aa_rgb c[4], double weight,
                double acc[3])
{
    const double qx[4] = {x0, x0 + s, x0 + s, x0}, qy[4] = {y0, y0, y0 + s, y0 + s};
    double px[4], py[4], gx = 0.0, gy = 0.0;
    int found[4], nfound = 0;
    for (int k = 0; k < 4; k++) {
        int n = (k + 1) & 3;
        found[k] = differ(c[k], c[n], cx->threshold);
        if (!found[k])
            continue;
        double lo = 0.0, hi = 1.0, dx = qx[n] - qx[k], dy = qy[n] - qy[k];
        for (int step = 0; step < cx->depth; step++) {
            double mid = 0.5 * (lo + hi);
            aa_rgb m = sample(cx, qx[k] + mid * dx, qy[k] + mid * dy);
            if (differ(m, c[k], cx->threshold))
                hi = mid;
            else
                lo = mid;
        }
        double t = 0.5 * (lo + hi);
        px[k] = qx[k] + t * dx, py[k] = qy[k] + t * dy;
        gx += px[k], gy += py[k];
        nfound++;
    }
    if (!nfound) {
        for (int ch = 0; ch < 3; ch++)
            acc[ch] += weight * 0.25 * (c[0].c[ch] + c[1].c[ch] + c[2].c[ch] + c[3].c[ch]);
        return 0;
    }
    gx /= nfound, gy /= nfound;
    /* the fan from the centroid over the boundary, cut at the found points */
    double sum[3] = {0, 0, 0}, area = 0.0;
    for (int k = 0; k < 4; k++) {
        int n = (k + 1) & 3;
        double ax = qx[k], ay = qy[k];
        if (found[k]) {
            double a1 = 0.5 * fabs((px[k] - ax) * (gy - ay) - (py[k] - ay) * (gx - ax));
            double a2 = 0.5 * fabs((qx[n] - px[k]) * (gy - py[k]) - (qy[n] - py[k]) * (gx - px[k]));
            for (int ch = 0; ch < 3; ch++)
                sum[ch] += a1 * c[k].c[ch] + a2 * c[n].c[ch];
            area += a1 + a2;
        } else {
            double a = 0.5 * fabs((qx[n] - ax) * (gy - ay) - (qy[n] - ay) * (gx - ax));
            for (int ch = 0; ch < 3; ch++)
                sum[ch] += a * 0.5 * (c[k].c[ch] + c[n].c[ch]);
            area += a;
        }
    }
    for (int ch = 0; ch < 3; ch++)
        acc[ch] += weight * sum[ch] / area;
    return 1;
}

/* Pixel (i, j) split into m x m cells, its corners c[0..3] known. */
static void refine(ad_ctx *cx, int i, int j, int m, const aa_rgb c[4], double acc[3])
{
    aa_rgb g[MAX_SIDE][MAX_SIDE];
    const double s = 1.0 / m;
    for (int b = 0; b <= m; b++)
        for (int a = 0; a <= m; a++) {
            if ((a == 0 || a == m) && (b == 0 || b == m))
                continue;
            g[b][a] = sample(cx, i + a * s, j + b * s);
        }
    g[0][0] = c[0], g[0][m] = c[1], g[m][m] = c[2], g[m][0] = c[3];
    const double weight = 1.0 / ((double)m * m);
    for (int b = 0; b < m; b++)
        for (int a = 0; a < m; a++) {
            const aa_rgb q[4] = {g[b][a], g[b][a + 1], g[b + 1][a + 1], g[b + 1][a]};
            cell(cx, i + a * s, j + b * s, s, q, weight, acc);
        }
}

/* Row j; top[] holds the corners of line j (filled here if `fresh`). */
static void render_row(ad_worker *wk, const double *p, int j, int w, int fresh, aa_image *out)
{
    const double threshold = p[P_THRESHOLD];
    const int tag = (int)p[P_TAG], m = 1 << (int)p[P_LEVELS];
    ad_ctx cx = {wk->strip, threshold, (int)p[P_DEPTH], 0};
    uint64_t top_samples = 0;
    if (aa_strip_begin(wk->strip, j, j + 1.0)) {
        wk->failed = 1;
        return;
    }
    for (int i = 0; i < w; i++) {
        size_t nloc = aa_strip_window(wk->strip, i, i + 1.0);
        if (i == 0) {
            if (fresh)
                wk->top[0] = aa_strip_colour_at(wk->strip, 0.0, j), top_samples++;
            wk->bottom[0] = sample(&cx, 0.0, j + 1.0);
        }
        if (fresh)
            wk->top[i + 1] = aa_strip_colour_at(wk->strip, i + 1.0, j), top_samples++;
        wk->bottom[i + 1] = sample(&cx, i + 1.0, j + 1.0);
        const aa_rgb c[4] = {wk->top[i], wk->top[i + 1], wk->bottom[i + 1], wk->bottom[i]};
        double *px = aa_pixel(out, i, j);
        if (nloc == 0) {
            /* no edge: the window is one colour, the corners' */
            px[0] = c[0].c[0], px[1] = c[0].c[1], px[2] = c[0].c[2];
            continue;
        }
        int agree = !differ(c[0], c[1], threshold) && !differ(c[1], c[2], threshold) &&
                    !differ(c[2], c[3], threshold) && !differ(c[3], c[0], threshold);
        double acc[3] = {0, 0, 0};
        if (tag && m > 1 && (agree || nloc > 1)) {
            refine(&cx, i, j, m, c, acc);
            wk->expensive++;
        } else if (cell(&cx, i, j, 1.0, c, 1.0, acc)) {
            wk->expensive++;
        }
        px[0] = acc[0], px[1] = acc[1], px[2] = acc[2];
    }
    /* the first row's top corners are counted once, by the row that owns
     * line 0; other threads' fresh rows repeat their neighbour's line */
    wk->samples += cx.samples + (j == 0 ? top_samples : 0);
    aa_rgb *t = wk->top;
    wk->top = wk->bottom, wk->bottom = t;
}

static int adaptive_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    return state_ready(state, job);
}

static int adaptive_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    ad_state *S = state;
    int st = state_ready(S, job);
    if (st)
        return st;
    uint64_t samples = 0, expensive = 0;
    const int h = job->h, w = job->w;
#pragma omp parallel num_threads(job->threads) reduction(+ : samples, expensive)
    {
        /* contiguous blocks of rows, so that each thread passes its bottom
         * corners on as the next row's top corners */
        int t = omp_get_thread_num(), nt = omp_get_num_threads();
        int j0 = (int)((long long)h * t / nt), j1 = (int)((long long)h * (t + 1) / nt);
        ad_worker *wk = &S->workers[t];
        wk->samples = wk->expensive = 0;
        wk->failed = 0;
        for (int j = j0; j < j1 && !wk->failed; j++)
            render_row(wk, p, j, w, j == j0, out);
        samples += wk->samples;
        expensive += wk->expensive;
    }
    for (int t = 0; t < S->nworkers; t++)
        if (S->workers[t].failed)
            return aa_fail(AA_ENOMEM, "adaptive: out of memory for a scanline strip");
    counters->samples = samples;
    counters->expensive_pixels = expensive;
    return AA_OK;
}

static void adaptive_release(void *state)
{
    state_free(state);
}

const aa_method_type aa_method_adaptive = {
    {"adaptive",
     "Ramos and Borges' adaptive scanline: corner samples, border search, centroid fan",
     adaptive_params},
    sizeof(ad_state),
    0,
    adaptive_check,
    adaptive_init,
    adaptive_render,
    adaptive_release};
