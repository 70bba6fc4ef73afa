/*
 * plugin_example.c: a method loaded at run time (aabench --plugin).
 *
 * Built as a shared library against the public header only.  `centre4`
 * takes the mean of four point samples at (1/4, 1/4), (3/4, 1/4), (1/4, 3/4)
 * and (3/4, 3/4) of each pixel, asking the scene directly: a deliberately
 * plain method, to show the contract (a type struct, state sized by the
 * harness, counters, refusing filters it cannot honour) and to be tested
 * like every built-in method.
 */
#include "aabench.h"

static const aa_param centre4_params[] = {{0}};

static int centre4_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "centre4 averages four samples with equal weights: box only");
    return AA_OK;
}

static int centre4_render(void *state, const double *p, const aa_job *job, aa_image *out,
                          aa_counters *counters)
{
    (void)state, (void)p;
    for (int j = 0; j < job->h; j++)
        for (int i = 0; i < job->w; i++) {
            double *px = aa_pixel(out, i, j);
            px[0] = px[1] = px[2] = 0;
            for (int k = 0; k < 4; k++) {
                aa_rgb c = aa_scene_colour_at(job->placed, i + 0.25 + 0.5 * (k & 1),
                                              j + 0.25 + 0.5 * (k >> 1));
                for (int ch = 0; ch < 3; ch++)
                    px[ch] += 0.25 * c.c[ch];
            }
        }
    counters->samples = 4 * (uint64_t)job->w * (uint64_t)job->h;
    counters->expensive_pixels = (uint64_t)job->w * (uint64_t)job->h;
    return AA_OK;
}

static const aa_method_type centre4 = {
    {"centre4", "plug-in example: mean of four point samples per pixel", centre4_params},
    0,
    0,
    centre4_check,
    NULL,
    centre4_render,
    NULL};

const int aa_plugin_abi = AA_PLUGIN_ABI;
const aa_method_type *const aa_plugin_methods[] = {&centre4, NULL};
