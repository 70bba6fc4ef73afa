/*
 * supersample.c: a fixed pattern of point samples per pixel, weighted by
 * the filter (Crow 1976, ch. 2, "Evaluating convolutional filters").
 *
 * pattern=grid (the default): a regular n x n grid spread evenly over the
 * filter's support [-R, R]^2 (R = aa_filter_support: box 1/2, tent r,
 * Gaussian 3s), sample (a, b) at offset R ((2a+1)/n - 1) in each axis from
 * the pixel centre, with weight w(dx) w(dy) and the pixel the weighted mean
 *
 *     P = sum_ab w(dx_a) w(dy_b) I(x_a, y_b) / sum_ab w(dx_a) w(dy_b).
 *
 * With the box this is Crow's fig. 2.11 for n = 3 ("nine equally weighted
 * samples taken per image dot"); n = 5 with -f tent:r=1 is fig. 2.12 ("25
 * unequally weighted samples"): offsets 0, +-0.4, +-0.8 pixel, 1-D weights
 * 1, 0.6, 0.2, so the centre sample weighs 1/2.6^2 and a corner one
 * 0.04/2.6^2.  With -f cone:r=R, which is not separable, sample (a, b)
 * weighs the cone's 2-D weight w(dx_a, dy_b) (the corners of the grid, outside
 * the disc, weigh 0).  The Pfenning slides (slide 25) describe the same thing:
 * render a 3x3 grid of mini-pixels, average the results using a filter.
 *
 * pattern=msaa2|msaa4|msaa8|msaa16: the standard Direct3D/Vulkan
 * multisample positions (algorithms/README.md, "Standard multisample
 * positions"), v/16 pixel from the centre, all inside the pixel.  Their weights are the
 * filter's at those positions, normalised; positions where it is zero
 * (tent:r=0.5 at the pixel's edge) are not evaluated.  n is the grid's side
 * only: with an msaa pattern it must stay at its default (3) and is
 * otherwise refused, since the pattern fixes the number of samples.
 *
 * Cost: a pixel whose samples' footprint (the filter support for the grid,
 * the pixel for msaa) meets no edge is filled with its colour without
 * sampling: the row's strip says so (aa_strip_window returns no local
 * piece).  Elsewhere a grid row of samples shares one line: the local
 * pieces' crossings of that line are found once (one root per piece, one or
 * two pieces on crow) and the n samples are compared with them, so a grid
 * pixel costs n roots per local piece plus n^2 comparisons.  In a row where
 * no piece ends (all but the top and bottom rows on crow) a sample's colour
 * is that of the subset of local pieces left of it, found once per pixel;
 * elsewhere the strip gives the winding left of the window per line.
 * Counters: samples = positions evaluated, expensive_pixels = pixels that
 * were sampled.  On a field scene (the zone plate) every pixel is sampled
 * and every sample is the point function; so on a scene with gradient
 * paint (aa_scene_colour_at at every sample).  The workers, the row loop and the by-subset colouring are
 * shared with jitter (sampling.h); this file has the plans and weights.
 *
 * Limits.  The grid is regular, so it aliases: detail near the grid's own
 * frequency (n samples per pixel) still makes moire, only finer than point
 * sampling's, and along edges aligned with the grid the error falls like
 * N^-1/2 in N = n^2 and is structured, not noise (algorithms/README.md,
 * "Convergence rates").  The weighted mean is a ratio estimator, normalised by its own weights rather
 * than the filter's integral, which keeps constant regions exact; the
 * Gaussian is truncated at 3s (its mass outside, about 0.5% in 2-D, is
 * never sampled); the msaa patterns see only the pixel,
 * whatever the filter's support.  A sample exactly on an edge takes the
 * colour left of it, except on the footprint's left border, where a piece
 * ending exactly there counts as left of the window (patterns/README.md,
 * "Boundaries": no result may depend on it).
 */
#include "methods.h"
#include "sampling.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define SS_MAX_N 64   /* grid side */
#define SS_MAX_POS 16 /* msaa positions */

enum { P_N, P_PATTERN };
enum { PAT_GRID, PAT_MSAA2, PAT_MSAA4, PAT_MSAA8, PAT_MSAA16 };

static const aa_param supersample_params[] = {
    {"n", AA_PARAM_INT, 3, 1, SS_MAX_N, 0, NULL,
     "grid side: n x n samples over the filter's support (pattern=grid only)"},
    {"pattern", AA_PARAM_CHOICE, PAT_GRID, 0, 0, 0, "grid|msaa2|msaa4|msaa8|msaa16",
     "sample positions: a regular n x n grid, or the standard multisample positions"},
    {0}};

/* The standard multisample positions in 1/16 pixel from the centre, y down
 * (the Direct3D and Vulkan standard sample patterns: algorithms/README.md,
 * "Standard multisample positions"); cycle.c visits them too. */
static const signed char msaa2[][2] = {{4, 4}, {-4, -4}};
static const signed char msaa4[][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
static const signed char msaa8[][2] = {{1, -3}, {-1, 3}, {5, 1},  {-3, -5},
                                       {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
static const signed char msaa16[][2] = {{1, 1},   {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                        {5, 3},   {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                        {-8, 0},  {7, -4},  {6, 7},  {-7, -8}};

const signed char (*aa_msaa_positions(int count))[2]
{
    switch (count) {
    case 2: return msaa2;
    case 4: return msaa4;
    case 8: return msaa8;
    case 16: return msaa16;
    default: return NULL;
    }
}

/* pattern=msaaN: N = 2, 4, 8, 16 */
static const signed char (*msaa_positions(int pattern, int *count))[2]
{
    *count = 2 << (pattern - PAT_MSAA2);
    return aa_msaa_positions(*count);
}

/* Where the samples of a pixel lie and what they weigh. */
typedef struct ss_plan {
    int grid;    /* 1: n x n grid; 0: a list of positions */
    int n;       /* grid side, or the number of positions kept */
    double half; /* the samples lie in the centre's square of this half-width */
    /* grid: sample a of a row or column lies at (centre - half) + at[a];
     * sample (a, b) weighs rf[b] rw[b n + a]: for a separable filter
     * w1[b] w1[a] (a row's sum times its factor), else the 2-D weight
     * with rf[b] = 1 */
    double at[SS_MAX_N], rf[SS_MAX_N], rw[SS_MAX_N * SS_MAX_N];
    /* list: offsets from the centre and 2-D weights */
    double dx[SS_MAX_POS], dy[SS_MAX_POS], w[SS_MAX_POS];
    double total; /* sum of the 2-D weights, summed as the samples are */
    uint64_t count;
} ss_plan;

static int plan_make(ss_plan *pl, const double *p, const aa_filter *f)
{
    memset(pl, 0, sizeof *pl);
    if ((int)p[P_PATTERN] == PAT_GRID) {
        double r = aa_filter_support(f);
        int n = (int)p[P_N], sep = aa_filter_is_separable(f);
        pl->grid = 1;
        pl->n = n;
        pl->half = r;
        for (int a = 0; a < n; a++)
            /* for the box, (2a+1)/2 / n = (a + 1/2)/n exactly */
            pl->at[a] = (2 * a + 1) * r / n;
        for (int b = 0; b < n; b++) {
            double rowsum = 0.0;
            pl->rf[b] = sep ? aa_filter_weight(f, pl->at[b] - r) : 1.0;
            for (int a = 0; a < n; a++) {
                double w = sep ? aa_filter_weight(f, pl->at[a] - r)
                               : aa_filter_weight2(f, pl->at[a] - r, pl->at[b] - r);
                pl->rw[b * n + a] = w;
                rowsum += w;
            }
            /* the weighted sum is accumulated row by row as rf[b] * (row sum) */
            pl->total += pl->rf[b] * rowsum;
        }
        pl->count = (uint64_t)pl->n * (uint64_t)pl->n;
    } else {
        int m;
        const signed char(*v)[2] = msaa_positions((int)p[P_PATTERN], &m);
        pl->half = 0.5;
        for (int k = 0; k < m; k++) {
            double dx = v[k][0] / 16.0, dy = v[k][1] / 16.0;
            double w = aa_filter_weight2(f, dx, dy);
            if (!(w > 0.0))
                continue;
            pl->dx[pl->n] = dx;
            pl->dy[pl->n] = dy;
            pl->w[pl->n++] = w;
            pl->total += w;
        }
        pl->count = (uint64_t)pl->n;
    }
    if (!(pl->total > 0.0) || !isfinite(pl->total))
        return aa_fail(AA_EINVAL, "the filter weighs every sample position zero; use a wider "
                                  "filter or pattern=grid");
    return AA_OK;
}

static int supersample_check(const double *p, const aa_filter *f)
{
    if ((int)p[P_PATTERN] != PAT_GRID && (int)p[P_N] != 3)
        return aa_fail(AA_EINVAL, "n=%d sets the side of pattern=grid; an msaa pattern has its "
                                  "own positions (leave n out)",
                       (int)p[P_N]);
    ss_plan pl;
    return plan_make(&pl, p, f);
}

/* ---- sampling a pixel ---- */

/* A crossing of a sample line by a local piece. */
typedef struct ss_cross {
    double x;
    int dir, layer;
} ss_cross;

typedef struct ss_state {
    ss_plan plan;
    aa__sampler sampler; /* workers; own scratch: ss_cross for every piece */
} ss_state;

/* What a render's pixels read. */
typedef struct ss_render {
    const ss_plan *plan;
    const aa_scene *scene; /* placed */
} ss_render;

/* Grid pixel, by subsets; footprint's left and top at (x0, y0). */
static void grid_subsets(aa__sampler_worker *wk, const ss_plan *pl, const aa_scene *s,
                         const aa_piece *const *pcs, int np, double x0, double y0, double *px)
{
    double wsum[1 << AA__SAMPLER_SUBSET_MAX] = {0};
    for (int b = 0; b < pl->n; b++) {
        double y = y0 + pl->at[b], xs[AA__SAMPLER_SUBSET_MAX];
        const double *w1 = pl->rw + b * pl->n;
        for (int q = 0; q < np; q++)
            xs[q] = aa_piece_x_at(pcs[q], y);
        if (np == 1) {
            /* one piece (crow's usual case): two sums kept in registers */
            double r0 = 0, r1 = 0;
            for (int a = 0; a < pl->n; a++) {
                int right = xs[0] < x0 + pl->at[a];
                r0 += right ? 0.0 : w1[a];
                r1 += right ? w1[a] : 0.0;
            }
            wsum[0] += pl->rf[b] * r0, wsum[1] += pl->rf[b] * r1;
        } else {
            double row[1 << AA__SAMPLER_SUBSET_MAX] = {0};
            for (int a = 0; a < pl->n; a++) {
                unsigned m = 0;
                for (int q = 0; q < np; q++)
                    m |= (unsigned)(xs[q] < x0 + pl->at[a]) << q;
                row[m] += w1[a];
            }
            for (unsigned m = 0; m < (1u << np); m++)
                wsum[m] += pl->rf[b] * row[m];
        }
    }
    aa__sampler_by_subsets(wk, s, y0 + pl->half, pcs, np, wsum, px);
}

/* Listed positions around the centre (cx, cy), by subsets. */
static void list_subsets(aa__sampler_worker *wk, const ss_plan *pl, const aa_scene *s,
                         const aa_piece *const *pcs, int np, double cx, double cy, double *px)
{
    double wsum[1 << AA__SAMPLER_SUBSET_MAX] = {0};
    for (int k = 0; k < pl->n; k++) {
        double x = cx + pl->dx[k], y = cy + pl->dy[k];
        unsigned m = 0;
        for (int q = 0; q < np; q++)
            m |= (unsigned)(aa_piece_x_at(pcs[q], y) < x) << q;
        wsum[m] += pl->w[k];
    }
    aa__sampler_by_subsets(wk, s, cy, pcs, np, wsum, px);
}

/* The local pieces' crossings of line y, sorted by x; returns the count. */
static size_t line_crossings(const aa_piece *const *loc, size_t nloc, double y, ss_cross *out)
{
    size_t m = 0;
    for (size_t k = 0; k < nloc; k++) {
        const aa_piece *p = loc[k];
        if (!p->dir || !(p->y0 <= y && y < p->y1))
            continue;
        double x = aa_piece_x_at(p, y);
        size_t at = m++;
        while (at > 0 && out[at - 1].x > x) { /* a window holds few crossings */
            out[at] = out[at - 1];
            at--;
        }
        out[at].x = x;
        out[at].dir = p->dir;
        out[at].layer = p->layer;
    }
    return m;
}

/* The weighted mean acc / total, or the samples' one colour exactly. */
static void put(double *px, const double acc[3], double total, aa_rgb first, int uniform)
{
    for (int ch = 0; ch < 3; ch++) {
        double v = acc[ch] / total;
        /* grouping the weights by colour may round a hair past the range */
        v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
        px[ch] = uniform ? first.c[ch] : v;
    }
}

/* Grid pixel, general path; footprint's left and top at (x0, y0).  Along
 * a row of samples the colour changes only at the local pieces' crossings,
 * so the weights of the samples between two crossings are summed and the
 * colour applied once. */
static void grid_general(aa__sampler_worker *wk, const ss_plan *pl, const aa_scene *s,
                         const aa_piece *const *loc, size_t nloc, double x0, double y0,
                         double *px)
{
    ss_cross *cross = wk->own;
    double acc[3] = {0, 0, 0};
    aa_rgb first = {{0, 0, 0}};
    int uniform = 1;
    for (int b = 0; b < pl->n; b++) {
        double y = y0 + pl->at[b], r0 = 0, r1 = 0, r2 = 0, seg = 0;
        const double *w1 = pl->rw + b * pl->n;
        aa_strip_winding_left(wk->strip, y, wk->wind);
        size_t m = line_crossings(loc, nloc, y, cross), q = 0;
        aa_rgb c = aa_scene_colour_of(s, wk->wind);
        int a = 0;
        for (;;) {
            /* the samples left of the next crossing take colour c */
            double stop = q < m ? cross[q].x : INFINITY;
            int a0 = a;
            while (a < pl->n && x0 + pl->at[a] <= stop)
                seg += w1[a++];
            if (a > a0) {
                if (b == 0 && a0 == 0)
                    first = c;
                uniform = uniform && aa__sampler_same_rgb(c, first);
                r0 += seg * c.c[0], r1 += seg * c.c[1], r2 += seg * c.c[2];
                seg = 0;
            }
            if (a == pl->n)
                break;
            /* pass every crossing left of sample a (strictly: a sample on
             * a crossing keeps the colour left of it) */
            double x = x0 + pl->at[a];
            while (q < m && cross[q].x < x) {
                wk->wind[cross[q].layer] += cross[q].dir;
                q++;
            }
            c = aa_scene_colour_of(s, wk->wind);
        }
        acc[0] += pl->rf[b] * r0, acc[1] += pl->rf[b] * r1, acc[2] += pl->rf[b] * r2;
    }
    put(px, acc, pl->total, first, uniform);
}

/* Listed positions around the centre (cx, cy), general path. */
static void list_general(aa__sampler_worker *wk, const ss_plan *pl, const aa_scene *s,
                         const aa_piece *const *loc, size_t nloc, double cx, double cy,
                         double *px)
{
    double a0 = 0, a1 = 0, a2 = 0;
    aa_rgb first = {{0, 0, 0}};
    int uniform = 1;
    for (int k = 0; k < pl->n; k++) {
        aa_rgb c = aa__sampler_colour_at(wk, s, loc, nloc, cx + pl->dx[k], cy + pl->dy[k]);
        if (k == 0)
            first = c;
        uniform = uniform && aa__sampler_same_rgb(c, first);
        a0 += pl->w[k] * c.c[0], a1 += pl->w[k] * c.c[1], a2 += pl->w[k] * c.c[2];
    }
    const double acc[3] = {a0, a1, a2};
    put(px, acc, pl->total, first, uniform);
}

/* Grid pixel on a field scene: every sample from the point function. */
static void grid_field(const ss_plan *pl, const aa_scene *s, double x0, double y0, double *px)
{
    double acc[3] = {0, 0, 0};
    for (int b = 0; b < pl->n; b++) {
        double r0 = 0, r1 = 0, r2 = 0, y = y0 + pl->at[b];
        const double *w1 = pl->rw + b * pl->n;
        for (int a = 0; a < pl->n; a++) {
            aa_rgb c = aa_scene_colour_at(s, x0 + pl->at[a], y);
            r0 += w1[a] * c.c[0], r1 += w1[a] * c.c[1], r2 += w1[a] * c.c[2];
        }
        acc[0] += pl->rf[b] * r0, acc[1] += pl->rf[b] * r1, acc[2] += pl->rf[b] * r2;
    }
    aa_rgb none = {{0, 0, 0}};
    put(px, acc, pl->total, none, 0);
}

/* Pixel (i, j), whose footprint holds local pieces (aa__sampler_shade_fn),
 * or any pixel of a field scene. */
static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const ss_render *R = ctx;
    const ss_plan *pl = R->plan;
    double cx = i + 0.5, cy = j + 0.5;
    if (wk->field && pl->grid) {
        grid_field(pl, R->scene, cx - pl->half, cy - pl->half, px);
        return;
    }
    const aa_piece *const *loc, *pcs[AA__SAMPLER_SUBSET_MAX];
    size_t nloc;
    int np = aa__sampler_subsets(wk, &loc, &nloc, pcs);
    if (np >= 0 && pl->grid)
        grid_subsets(wk, pl, R->scene, pcs, np, cx - pl->half, cy - pl->half, px);
    else if (np >= 0)
        list_subsets(wk, pl, R->scene, pcs, np, cx, cy, px);
    else if (pl->grid)
        grid_general(wk, pl, R->scene, loc, nloc, cx - pl->half, cy - pl->half, px);
    else
        list_general(wk, pl, R->scene, loc, nloc, cx, cy, px);
}

/* One row of pixels (aa__sampler_row_fn): the footprint is the square of
 * half-width plan.half around the centre. */
static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    const ss_render *R = ctx;
    return aa__sampler_row(wk, j, R->plan->half, R->plan->count, shade, ctx, out, samples,
                           expensive);
}

/* ---- the method ---- */

static int prepare(ss_state *S, const double *p, const aa_job *job)
{
    size_t npieces;
    aa_scene_pieces(job->placed, &npieces);
    int st = plan_make(&S->plan, p, &job->filter);
    if (!st)
        st = aa__sampler_ready(&S->sampler, job, (npieces + 1) * sizeof(ss_cross));
    return st;
}

static int supersample_init(void *state, const double *p, const aa_job *job)
{
    return prepare(state, p, job);
}

static int supersample_render(void *state, const double *p, const aa_job *job, aa_image *out,
                              aa_counters *counters)
{
    ss_state *S = state;
    int st = prepare(S, p, job);
    if (st)
        return st;
    const ss_render R = {&S->plan, job->placed};
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void supersample_release(void *state)
{
    ss_state *S = state;
    aa__sampler_free(&S->sampler);
}

const aa_method_type aa_method_supersample = {
    {"supersample",
     "n x n grid (Crow figs. 2.11-2.12) or msaa positions per pixel, filter-weighted",
     supersample_params},
    sizeof(ss_state),
    AA_METHOD_FIELDS | AA_METHOD_GRADIENTS,
    supersample_check,
    supersample_init,
    supersample_render,
    supersample_release};
