/*
 * sampling.c: the workers, the parallel row loop and the by-subset colour
 * shared by supersample and jitter (sampling.h says what and why).
 */
#include "core.h"
#include "sampling.h"

#include <omp.h>
#include <stdalign.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define CACHE_LINE 64

void aa__sampler_free(aa__sampler *sm)
{
    for (int t = 0; t < sm->nworkers; t++) {
        aa_strip_free(sm->workers[t].strip);
        free(sm->workers[t].block);
    }
    free(sm->workers);
    sm->workers = NULL;
    sm->nworkers = 0;
    sm->scene = NULL;
    sm->own_size = 0;
}

/* One thread's workspace.  Its scratch is one block of whole cache lines,
 * and it is made by the thread that will use it, so glibc serves it (and
 * the strip's own small state) from that thread's arena: no two threads
 * write to one cache line, as they would to neighbouring small
 * allocations (a few bytes of winding numbers each). */
static int worker_make(aa__sampler_worker *wk, const aa_scene *scene, size_t own_size)
{
    int nl = aa_scene_layer_count(scene);
    size_t nw = (size_t)(nl > 0 ? nl : 1), align = alignof(max_align_t);
    size_t o_wind = (own_size + align - 1) / align * align, size = o_wind + 2 * nw * sizeof(int);
    size = (size + CACHE_LINE - 1) / CACHE_LINE * CACHE_LINE;
    wk->strip = aa_strip_new(scene);
    char *b = wk->block = aligned_alloc(CACHE_LINE, size);
    if (!wk->strip || !b)
        return AA_ENOMEM;
    memset(b, 0, size);
    wk->own = b;
    wk->wind = (int *)(b + o_wind), wk->wind2 = wk->wind + nw;
    /* a field, or gradient paint (whose colour changes inside the spans
     * between edges): no uniform runs, every sample from the point
     * function (aa_scene_colour_at) */
    wk->field = aa_scene_field(scene, NULL, NULL, NULL) != NULL || aa_scene_has_gradients(scene);
    return AA_OK;
}

int aa__sampler_ready(aa__sampler *sm, const aa_job *job, size_t own_size)
{
    const aa_scene *scene = job->placed;
    int threads = job->threads;
    if (sm->scene == scene && sm->nworkers >= threads && sm->own_size >= own_size)
        return AA_OK;
    aa__sampler_free(sm);
    if (!(sm->workers = calloc((size_t)threads, sizeof *sm->workers)))
        return aa_fail(AA_ENOMEM, "out of memory for %d workers", threads);
    sm->nworkers = threads;
    sm->scene = scene;
    sm->own_size = own_size;
    int failed = 0;
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (int t = 0; t < threads; t++)
        if (worker_make(&sm->workers[t], scene, own_size)) {
#pragma omp atomic write
            failed = 1;
        }
    if (failed) {
        aa__sampler_free(sm);
        return aa_fail(AA_ENOMEM, "out of memory for the workspaces of %d threads", threads);
    }
    return AA_OK;
}

int aa__sampler_render(aa__sampler *sm, const aa_job *job, aa_image *out, aa__sampler_row_fn *row,
                       const void *ctx, aa_counters *counters)
{
    uint64_t samples = 0, expensive = 0;
    int failed = 0;
#pragma omp parallel num_threads(job->threads) reduction(+ : samples, expensive)
    {
        aa__sampler_worker *wk = &sm->workers[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 4)
        for (int j = 0; j < job->h; j++) {
            int stop;
#pragma omp atomic read
            stop = failed;
            if (!stop && row(ctx, wk, j, out, &samples, &expensive)) {
#pragma omp atomic write
                failed = 1;
            }
        }
    }
    if (failed)
        return aa_fail(AA_ENOMEM, "out of memory for a strip of the scene");
    counters->samples = samples;
    counters->expensive_pixels = expensive;
    return AA_OK;
}

void aa__sampler_by_subsets(aa__sampler_worker *wk, const aa_scene *s, double y,
                            const aa_piece *const *pcs, int np, const double *wsum, double *px)
{
    aa_strip_winding_left(wk->strip, y, wk->wind); /* the same on every line here */
    int nl = aa_scene_layer_count(s);
    double a0 = 0, a1 = 0, a2 = 0, total = 0;
    aa_rgb first = {{0, 0, 0}};
    int uniform = 1, any = 0;
    /* One opaque layer (crow): a subset's colour is the layer's where its rule
     * holds for the winding left of the window plus the subset's
     * directions, else the background (aa_scene_colour_of, without copying
     * winding arrays per subset). */
    aa_rgb one[2];
    int evenodd = 0;
    const int single = nl == 1 && aa_scene_is_opaque(s);
    if (single) {
        one[0] = aa_scene_background(s), one[1] = aa_scene_layer_colour(s, 0);
        evenodd = aa_scene_layer_rule(s, 0) == AA_FILL_EVENODD;
    }
    for (unsigned m = 0; m < (1u << np); m++) {
        if (!(wsum[m] > 0.0)) /* no sample */
            continue;
        aa_rgb c;
        if (single) {
            int w = wk->wind[0];
            for (int q = 0; q < np; q++)
                w += (m >> q & 1u) ? pcs[q]->dir : 0;
            c = one[evenodd ? (w & 1) : w != 0];
        } else {
            memcpy(wk->wind2, wk->wind, (size_t)(nl > 0 ? nl : 1) * sizeof *wk->wind2);
            for (int q = 0; q < np; q++)
                if (m >> q & 1u)
                    wk->wind2[pcs[q]->layer] += pcs[q]->dir;
            c = aa_scene_colour_of(s, wk->wind2);
        }
        if (!any)
            first = c, any = 1;
        uniform = uniform && aa__sampler_same_rgb(c, first);
        a0 += wsum[m] * c.c[0], a1 += wsum[m] * c.c[1], a2 += wsum[m] * c.c[2];
        total += wsum[m];
    }
    /* a sum of w c over colours in [0, 1] never rounds past the sum of w,
     * so the value stays in range */
    const double acc[3] = {a0, a1, a2};
    for (int ch = 0; ch < 3; ch++)
        px[ch] = uniform ? first.c[ch] : acc[ch] / total;
}
