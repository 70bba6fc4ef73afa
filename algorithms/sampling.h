/*
 * sampling.h: the core that the point-sampling methods `supersample` and
 * `jitter` share (internal to algorithms/).
 *
 * Both methods weigh point samples over a square window around each pixel
 * centre, and both get a sample's colour the same way: from the strip of
 * the pixel's row (aa_strip in aabench.h), the winding left of the window
 * plus the crossings of the window's few local pieces.  They differ only in
 * where the samples lie and what they weigh (supersample: a fixed grid or
 * the msaa positions; jitter: random or scrambled quasi-random points per
 * pixel).  What does not depend on that lives here, written once:
 *
 *  - the per-thread workers: a strip, the winding arrays and the method's
 *    own scratch, in one block of whole cache lines made by the thread that
 *    uses it (aa__sampler_ready);
 *  - the parallel row loop: rows shared among threads, runs of uniform
 *    windows filled through aa_strip_uniform_run without sampling, the
 *    method's shading for the other pixels, counters by reduction, and a
 *    failure flag that stops the rows when a strip cannot be built
 *    (aa__sampler_render, aa__sampler_row);
 *  - the colour of a point from the worker's strip (aa__sampler_colour_at);
 *  - a field scene (core.h, "Fields"), which has no edges: no uniform
 *    runs, every pixel shaded, every sample's colour from the point
 *    function (the worker's `field` flag);
 *  - the by-subset colouring of a pixel in a band that no piece ends in:
 *    there a sample's colour depends only on which local pieces lie left of
 *    it, so a method sums its samples' weights per subset and the colours
 *    are found once per subset seen, with a pixel whose samples all saw one
 *    colour given that colour exactly (aa__sampler_subsets,
 *    aa__sampler_by_subsets).
 *
 * The per-pixel calls are static inline: aa__sampler_row takes the method's
 * shading as a function pointer, and each method calls it with a constant
 * one from a row function of its own, so the compiler inlines the loop and
 * calls the shading directly (no indirect call per pixel; bench_methods
 * measures the same speed as when each method had its own loop).
 */
#ifndef AA_SAMPLING_H
#define AA_SAMPLING_H

#include "aabench.h"

#include <stddef.h>
#include <stdint.h>

/* Local pieces the by-subset path handles: 2^4 subsets per pixel. */
#define AA__SAMPLER_SUBSET_MAX 4

/* One thread's workspace. */
typedef struct aa__sampler_worker {
    aa_strip *strip;
    void *own;         /* the method's scratch (own_size bytes, cache-line aligned) */
    int *wind, *wind2; /* one per layer each */
    int field;         /* the scene is a field or has gradient paint: every sample
                        * from its point function (aa_scene_colour_at) */
    void *block;       /* all of the above but the strip, in whole cache lines */
} aa__sampler_worker;

/* The workers of a method instance (zeroed state: none yet). */
typedef struct aa__sampler {
    const aa_scene *scene; /* the scene the strips read */
    size_t own_size;
    aa__sampler_worker *workers;
    int nworkers;
} aa__sampler;

/* Workers for job->threads threads on job->placed, each with own_size bytes
 * of scratch for the method; kept while a render asks for the same scene,
 * no more threads and no more scratch, else made again.  Call it in init
 * (outside any timing) and at the start of each render. */
int aa__sampler_ready(aa__sampler *sm, const aa_job *job, size_t own_size);
void aa__sampler_free(aa__sampler *sm);

/* The method's row: aa__sampler_row with its shading (see below); returns
 * non-zero if the strip could not be built. */
typedef int aa__sampler_row_fn(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                               uint64_t *samples, uint64_t *expensive);

/* Every row of out (job->h rows), shared among job->threads threads, one
 * worker each; fills the counters.  The image does not depend on how the
 * rows are shared: a pixel depends only on its row's strip. */
int aa__sampler_render(aa__sampler *sm, const aa_job *job, aa_image *out, aa__sampler_row_fn *row,
                       const void *ctx, aa_counters *counters);

/* The shading of pixel (i, j), whose window holds local pieces (the
 * strip's current window): writes px[0..3). */
typedef void aa__sampler_shade_fn(const void *ctx, aa__sampler_worker *wk, int i, int j,
                                  double *px);

static inline int aa__sampler_same_rgb(aa_rgb a, aa_rgb b)
{
    return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

/* Row j, the windows of pixel (i, j) being the square of half-width r
 * around its centre: uniform runs are filled, every other pixel counts
 * `count` samples and is shaded.  Returns non-zero if the strip could not
 * be built. */
static inline int aa__sampler_row(aa__sampler_worker *wk, int j, double r, uint64_t count,
                                  aa__sampler_shade_fn *shade, const void *ctx, aa_image *out,
                                  uint64_t *samples, uint64_t *expensive)
{
    double cy = j + 0.5;
    if (wk->field) {
        /* a field has no edges to find uniform runs by: every pixel is
         * sampled (the shading reads the point function) */
        for (int i = 0; i < out->w; i++) {
            ++*expensive;
            *samples += count;
            shade(ctx, wk, i, j, aa_pixel(out, i, j));
        }
        return 0;
    }
    if (aa_strip_begin(wk->strip, cy - r, cy + r))
        return 1;
    for (int i = 0; i < out->w;) {
        double cx = i + 0.5, *px = aa_pixel(out, i, j);
        if (aa_strip_window(wk->strip, cx - r, cx + r) == 0) {
            /* a run of uniform windows: one colour, no samples */
            aa_rgb c;
            int end = aa_strip_uniform_run(wk->strip, i, out->w, r, cy, wk->wind, &c);
            for (; i < end; i++, px += 3)
                px[0] = c.c[0], px[1] = c.c[1], px[2] = c.c[2];
            continue;
        }
        ++*expensive;
        *samples += count;
        shade(ctx, wk, i, j, px);
        i++;
    }
    return 0;
}

/* The local pieces of the current window (*loc, *nloc), and whether the
 * by-subset path applies: a band no piece ends in (aa_strip_all_full) and
 * at most AA__SAMPLER_SUBSET_MAX local pieces.  Returns the number of
 * them that cross lines, put in pcs (bit q of a subset is pcs[q]), or -1
 * when every sample's colour must come from the strip (or, on a field, no
 * local pieces and -1: every sample from the point function). */
static inline int aa__sampler_subsets(aa__sampler_worker *wk, const aa_piece *const **loc,
                                      size_t *nloc, const aa_piece *pcs[AA__SAMPLER_SUBSET_MAX])
{
    if (wk->field) {
        *loc = NULL;
        *nloc = 0;
        return -1;
    }
    int ragged = !aa_strip_all_full(wk->strip);
    *loc = aa_strip_local(wk->strip, nloc);
    if (ragged || *nloc > AA__SAMPLER_SUBSET_MAX)
        return -1;
    int np = 0;
    for (size_t k = 0; k < *nloc; k++)
        if ((*loc)[k]->dir)
            pcs[np++] = (*loc)[k];
    return np;
}

/* The pixel from the weights of its samples per subset of local pieces
 * (wsum[m], 2^np of them; a sample weighs more than zero): the weighted
 * mean of the subsets' colours, each found once, or exactly the one colour
 * all samples saw.  y: a line of the band (the winding left of the window
 * is the same on all of them). */
void aa__sampler_by_subsets(aa__sampler_worker *wk, const aa_scene *s, double y,
                            const aa_piece *const *pcs, int np, const double *wsum, double *px);

/* The colour at (x, y) in the strip's current window: the winding left of
 * the window plus the local pieces crossing line y left of x (as
 * aa_strip_colour_at, with the worker's own winding array); on a field, the
 * point function. */
static inline aa_rgb aa__sampler_colour_at(aa__sampler_worker *wk, const aa_scene *s,
                                           const aa_piece *const *loc, size_t nloc, double x,
                                           double y)
{
    if (wk->field)
        return aa_scene_colour_at(s, x, y);
    aa_strip_winding_left(wk->strip, y, wk->wind);
    for (size_t k = 0; k < nloc; k++) {
        const aa_piece *p = loc[k];
        if (p->dir && p->y0 <= y && y < p->y1 && aa_piece_x_at(p, y) < x)
            wk->wind[p->layer] += p->dir;
    }
    return aa_scene_colour_of(s, wk->wind);
}

#endif
