/*
 * bench_truth.c: speed of the ground truth (`make bench`).
 *
 * Renders the reference of a pattern at each size, filter and thread count
 * into an image allocated and touched once (page faults are not the
 * reference's cost), several times, and prints the median with min and max,
 * and the cost per integrated (edge) pixel; for the Gaussian, the share of
 * those pixels that took the fixed rule rather than QAG (truth.c).
 * Nothing here is a test: the figures are read, not asserted.
 *
 * usage: bench_truth [-p PATTERN] [-s WxH,...] [-f FILTER;...] [-t 1,2] [-r REPS]
 */
#include "bench.h"
#include "truth_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* box_median[t]: the box median with t threads, for the ratio column */
static int bench(const aa_scene *pattern, int w, int h, const char *fspec, int threads,
                 int reps, double *box_median)
{
    aa_filter f;
    aa_image img;
    aa_truth_stats st;
    size_t fast = 0;
    double times[64];
    if (aa_filter_parse(fspec, &f) || aa_image_alloc(&img, w, h, 3)) {
        fprintf(stderr, "bench_truth: %s\n", aa_last_error());
        return 1;
    }
    aa_scene *placed = aa_scene_place(pattern, w, h, 0, 0, 0);
    if (!placed)
        return 1;
    memset(img.v, 0, (size_t)w * h * 3 * sizeof *img.v); /* touch once */
    for (int r = 0; r < reps; r++) {
        double t0 = aa_now();
        if (aa__truth_render_mode(placed, &f, threads, 0, &img, NULL, &st, &fast)) {
            fprintf(stderr, "bench_truth: %s\n", aa_last_error());
            return 1;
        }
        times[r] = aa_now() - t0;
    }
    qsort(times, (size_t)reps, sizeof *times, cmp);
    double med = times[reps / 2];
    if (!strcmp(fspec, "box"))
        box_median[threads] = med;
    printf("%5dx%-5d %-10s %d thr  median %8.3f s  (min %.3f max %.3f)  edge px %8zu  "
           "%6.0f ns/edge px  bound %.1e",
           w, h, fspec, threads, med, times[0], times[reps - 1], st.integrated,
           med * threads * 1e9 / (double)(st.integrated ? st.integrated : 1), st.max_bound);
    if (box_median[threads] > 0 && strcmp(fspec, "box"))
        printf("  %.2fx box", med / box_median[threads]);
    if (f.type == &aa_filter_gauss)
        printf("  fixed rule %.1f%%",
               100.0 * (double)fast / (double)(st.integrated ? st.integrated : 1));
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
    int reps = 5;
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "-p")) pattern = argv[k + 1];
        else if (!strcmp(argv[k], "-s")) sizes = argv[k + 1];
        else if (!strcmp(argv[k], "-f")) filters = argv[k + 1];
        else if (!strcmp(argv[k], "-t")) threads = argv[k + 1];
        else if (!strcmp(argv[k], "-r")) reps = atoi(argv[k + 1]);
    }
    if (reps < 1 || reps > 64)
        reps = 5;
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
                if (bench(scene, w, h, f, nthreads, w * h > 4000000 ? (reps + 1) / 2 : reps,
                          box_median))
                    return 3;
            }
        }
    }
    aa_scene_free(scene);
    return 0;
}
