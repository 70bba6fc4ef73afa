/*
 * plugin_example.c: a method loaded at run time (aabench --plugin).
 *
 * Built from this one file against the plug-in header alone:
 *
 *     cc -std=c11 -O2 -fPIC -shared -Iharness tests/plugin_example.c -o centre4.so
 *     aabench render --plugin ./centre4.so -m centre4 -p crow -s 256x256 -o c.png
 *     make check-plugin PLUGIN=centre4.so      (the contract tests of every method)
 *
 * `centre4` takes the mean of four point samples per pixel, at (1/4, 1/4),
 * (3/4, 1/4), (1/4, 3/4) and (3/4, 3/4), as a 2 x 2 ordered grid.  It shows
 * the contract: a type with named fields, per-job state made in init and
 * freed in release, a filter refused with a reason, counters, and the fast
 * scene query: each sample row asks the scene once for the sorted crossings
 * of its line (aa_scene_crossings), then walks them left to right keeping
 * the winding numbers, so a sample costs a step along the row instead of a
 * search of the whole scene (aa_scene_colour_at, about 200 times slower).
 */
#include "aabench.h"

#include <stdlib.h>
#include <string.h>

typedef struct centre4_state {
    aa_crossing *cross; /* the crossings of one line */
    size_t cap;
    int *wind; /* winding number per layer */
} centre4_state;

static const aa_param centre4_params[] = {{0}};

static int centre4_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "centre4 averages four samples with equal weights: box only");
    return AA_OK;
}

static int centre4_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    centre4_state *st = state;
    int nl = aa_scene_layer_count(job->placed);
    st->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *st->wind);
    st->cap = 64;
    st->cross = malloc(st->cap * sizeof *st->cross);
    if (!st->wind || !st->cross)
        return aa_fail(AA_ENOMEM, "centre4: out of memory");
    return AA_OK;
}

static void centre4_release(void *state)
{
    centre4_state *st = state;
    free(st->cross);
    free(st->wind);
}

/* Add the colours of the samples x = i + dx (i = 0 .. w-1) on line y to row. */
static int sample_line(centre4_state *st, const aa_scene *s, double y, double dx, int w,
                       double *row)
{
    size_t n = aa_scene_crossings(s, y, st->cross, st->cap);
    if (n > st->cap) { /* once per line at most, never per sample */
        aa_crossing *c = realloc(st->cross, n * sizeof *c);
        if (!c)
            return aa_fail(AA_ENOMEM, "centre4: out of memory");
        st->cross = c, st->cap = n;
        aa_scene_crossings(s, y, st->cross, st->cap);
    }
    memset(st->wind, 0, (size_t)aa_scene_layer_count(s) * sizeof *st->wind);
    size_t k = 0;
    for (int i = 0; i < w; i++) {
        double x = i + dx;
        for (; k < n && st->cross[k].x <= x; k++) /* crossings left of the sample */
            st->wind[st->cross[k].layer] += st->cross[k].dir;
        aa_rgb c = aa_scene_colour_of(s, st->wind);
        for (int ch = 0; ch < 3; ch++)
            row[3 * i + ch] += 0.25 * c.c[ch];
    }
    return AA_OK;
}

static int centre4_render(void *state, const double *p, const aa_job *job, aa_image *out,
                          aa_counters *counters)
{
    (void)p;
    centre4_state *st = state;
    for (int j = 0; j < job->h; j++) {
        double *row = aa_pixel(out, 0, j);
        memset(row, 0, 3 * (size_t)job->w * sizeof *row);
        for (int k = 0; k < 4; k++) {
            int st_ = sample_line(st, job->placed, j + 0.25 + 0.5 * (k >> 1),
                                  0.25 + 0.5 * (k & 1), job->w, row);
            if (st_)
                return st_;
        }
    }
    counters->samples = 4 * (uint64_t)job->w * (uint64_t)job->h;
    counters->expensive_pixels = (uint64_t)job->w * (uint64_t)job->h;
    return AA_OK;
}

static const aa_method_type centre4 = {
    .info = {"centre4", "plug-in example: mean of a 2 x 2 grid of point samples per pixel",
             centre4_params},
    .size = sizeof(centre4_state),
    .flags = 0,
    .check = centre4_check,
    .init = centre4_init,
    .render = centre4_render,
    .release = centre4_release,
};

const int aa_plugin_abi = AA_PLUGIN_ABI;
const aa_method_type *const aa_plugin_methods[] = {&centre4, NULL};
