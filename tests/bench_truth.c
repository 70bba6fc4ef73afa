/*
 * bench_truth.c: speed of the ground truth (`make bench`).
 *
 * Renders the reference of a pattern at each size, filter and thread count
 * into an image allocated and touched once (page faults are not the
 * reference's cost), after one untimed warm-up render, until the 95% CI of
 * the median is within --target-ci PCT (default 2) or --budget S seconds
 * (default 1) have passed, at least 5 times (or exactly -r N times;
 * aa_timing_measure), and prints the median with the CI's relative
 * half-width, min and max, a mark when the timing is noisy (target missed,
 * many outliers, other processes busy on the cores: a 2-thread figure taken
 * so is no speed-up or loss), and the cost per integrated (edge) pixel; for
 * the Gaussian, the share of those pixels that took the fixed rule rather
 * than QAG (truth.c).  Nothing here is a test: the figures are read, not
 * asserted.
 *
 * usage: bench_truth [-p PATTERN] [-s WxH,...] [-f FILTER;...] [-t 1,2] [-r REPS]
 *                    [--target-ci PCT] [--budget S]
 */
#include "bench.h"
#include "truth_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


typedef struct render_ctx {
    const aa_scene *placed;
    const aa_filter *f;
    int threads;
    aa_image *img;
    aa_truth_stats *st;
    size_t *fast;
} render_ctx;

static int render_once(void *vctx)
{
    render_ctx *c = vctx;
    return aa__truth_render_mode(c->placed, c->f, c->threads, 0, c->img, NULL, c->st, c->fast);
}

static size_t noisy_count;

/* box_median[t]: the box median with t threads, for the ratio column */
static int bench(const aa_scene *pattern, int w, int h, const char *fspec, int threads,
                 const aa_timing_plan *plan, double *box_median)
{
    aa_filter f;
    aa_image img;
    aa_truth_stats st;
    size_t fast = 0;
    static aa_timing tm;
    if (aa_filter_parse(fspec, &f) || aa_image_alloc(&img, w, h, 3)) {
        fprintf(stderr, "bench_truth: %s\n", aa_last_error());
        return 1;
    }
    aa_scene *placed = aa_scene_place(pattern, w, h, 0, 0, 0);
    if (!placed)
        return 1;
    memset(img.v, 0, (size_t)w * h * 3 * sizeof *img.v); /* touch once */
    render_ctx c = {placed, &f, threads, &img, &st, &fast};
    aa_timed_fn fn = render_once;
    void *ctx = &c;
    if (aa_timing_measure(plan, 1, &fn, &ctx, &threads, &tm)) {
        fprintf(stderr, "bench_truth: %s\n", aa_last_error());
        return 1;
    }
    double med = tm.stats.median;
    if (!strcmp(fspec, "box"))
        box_median[threads] = med;
    char ci[32] = "+-?", why[64] = "";
    if (isfinite(tm.ci_rel))
        snprintf(ci, sizeof ci, "+-%.1f%%", 100 * tm.ci_rel);
    aa_noisy_text(tm.noisy, why, sizeof why);
    noisy_count += tm.noisy != 0;
    printf("%5dx%-5d %-10s %d thr  median %8.3f s %-7s%s (n %d, min %.3f max %.3f)  edge px %8zu  "
           "%6.0f ns/edge px  bound %.1e",
           w, h, fspec, threads, med, ci, tm.noisy ? "*" : " ", tm.n, tm.stats.min, tm.stats.max,
           st.integrated,
           med * threads * 1e9 / (double)(st.integrated ? st.integrated : 1), st.max_bound);
    if (box_median[threads] > 0 && strcmp(fspec, "box"))
        printf("  %.2fx box", med / box_median[threads]);
    if (f.type == &aa_filter_gauss)
        printf("  fixed rule %.1f%%",
               100.0 * (double)fast / (double)(st.integrated ? st.integrated : 1));
    if (tm.noisy)
        printf("  noisy: %s (others used %.2f cores)", why, tm.others_cores);
    printf("\n");
    fflush(stdout);
    aa_scene_free(placed);
    aa_image_free(&img);
    return 0;
}

int main(int argc, char **argv)
{
    const char *pattern = "crow", *sizes = "1024x1024,4096x4096";
    const char *filters = "box;tent:r=0.5;tent:r=1;gauss", *threads = "1,2";
    int reps = 0;
    aa_timing_plan plan = {0};
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "-p")) pattern = argv[k + 1];
        else if (!strcmp(argv[k], "-s")) sizes = argv[k + 1];
        else if (!strcmp(argv[k], "-f")) filters = argv[k + 1];
        else if (!strcmp(argv[k], "-t")) threads = argv[k + 1];
        else if (!strcmp(argv[k], "-r")) reps = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "--target-ci")) plan.target_ci = atof(argv[k + 1]) / 100;
        else if (!strcmp(argv[k], "--budget")) plan.budget = atof(argv[k + 1]);
    }
    if (reps < 0 || reps > AA_TIMING_MAX_REPS)
        reps = 0;
    plan.reps = reps;
    if (!(plan.target_ci >= 0 && plan.target_ci < 1) || !(plan.budget >= 0))
        return 2;
    aa_spec spec;
    aa_scene *scene;
    if (aa_pattern_parse(pattern, &spec) || aa_pattern_scene(&spec, &scene)) {
        fprintf(stderr, "bench_truth: %s\n", aa_last_error());
        return 2;
    }
    char sbuf[256], fbuf[256], tbuf[64];
    snprintf(sbuf, sizeof sbuf, "%s", sizes);
    for (char *sz = strtok(sbuf, ","); sz; sz = strtok(NULL, ",")) {
        int w, h;
        if (aa_size_parse(sz, &w, &h))
            return 2;
        double box_median[65] = {0};
        snprintf(fbuf, sizeof fbuf, "%s", filters);
        char *fsave, *tsave;
        for (char *f = strtok_r(fbuf, ";", &fsave); f; f = strtok_r(NULL, ";", &fsave)) {
            snprintf(tbuf, sizeof tbuf, "%s", threads);
            for (char *t = strtok_r(tbuf, ",", &tsave); t; t = strtok_r(NULL, ",", &tsave)) {
                int nthreads = atoi(t);
                if (nthreads < 1 || nthreads > 64)
                    return 2;
                if (bench(scene, w, h, f, nthreads, &plan, box_median))
                    return 3;
            }
        }
    }
    aa_scene_free(scene);
    if (noisy_count)
        printf("warning: %zu timings are noisy (*): no speed-up or loss of 2 threads over 1 "
               "is to be read from them\n",
               noisy_count);
    return 0;
}
