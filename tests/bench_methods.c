/*
 * bench_methods.c: speed of the methods (`make bench`).
 *
 * For each method spec, renders the pattern into an image allocated and
 * touched once, `reps` times after one untimed init, and prints the median
 * with min and max, ns per pixel and per sample, the expensive pixels, and
 * the ratio to `point` measured in the same run with the same thread count.
 * Figures are read, not asserted.
 *
 * usage: bench_methods [-p PATTERN] [-s WxH] [-f FILTER] [-t 1,2] [-r REPS] [SPEC...]
 */
#include "aabench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    const char *pattern = "crow", *size = "1024x1024", *filter = "box", *threads = "1,2";
    int reps = 15, first = 1;
    static const char *defaults[] = {"point", "supersample:n=3", "supersample:n=4",
                                     "supersample:pattern=msaa8", "jitter:spp=16",
                                     "jitter:spp=16,seq=sobol", "jitter:spp=64", "hexagon",
                                     "trio", "trio:variant=sancha", "trio:variant=recursive",
                                     "area", NULL};
    while (first + 1 < argc && argv[first][0] == '-') {
        const char *o = argv[first], *v = argv[first + 1];
        if (!strcmp(o, "-p")) pattern = v;
        else if (!strcmp(o, "-s")) size = v;
        else if (!strcmp(o, "-f")) filter = v;
        else if (!strcmp(o, "-t")) threads = v;
        else if (!strcmp(o, "-r")) reps = atoi(v);
        else break;
        first += 2;
    }
    const char **specs = first < argc ? (const char **)argv + first : defaults;
    size_t nspecs = 0;
    while (specs[nspecs] && (specs != defaults || defaults[nspecs]))
        nspecs++;
    if (specs != defaults)
        nspecs = (size_t)(argc - first);
    if (reps < 1 || reps > 1000)
        reps = 15;
    aa_spec pspec;
    aa_scene *scene;
    aa_filter f;
    int w, h;
    if (aa_pattern_parse(pattern, &pspec) || aa_pattern_scene(&pspec, &scene) ||
        aa_size_parse(size, &w, &h) || aa_filter_parse(filter, &f)) {
        fprintf(stderr, "bench_methods: %s\n", aa_last_error());
        return 2;
    }
    aa_image img;
    if (aa_image_alloc(&img, w, h, 3))
        return 3;
    double *t = malloc((size_t)reps * sizeof *t);
    printf("%s %dx%d %s, median of %d renders (min max), one untimed init\n", pattern, w, h,
           filter, reps);
    char tbuf[64];
    snprintf(tbuf, sizeof tbuf, "%s", threads);
    for (char *ts = strtok(tbuf, ","); ts; ts = strtok(NULL, ",")) {
        int nt = atoi(ts);
        double point = 0;
        aa_job job;
        if (nt < 1 || aa_job_init(&job, scene, w, h, 0, 0, 0, &f, 1, nt))
            return 2;
        for (size_t k = 0; k < nspecs; k++) {
            aa_spec m;
            aa_counters c;
            if (aa_method_parse(specs[k], &f, &m)) {
                printf("  %-28s refused: %s\n", specs[k], aa_last_error());
                continue;
            }
            if (aa_method_run(&m, &job, reps, &img, &c, t)) {
                printf("  %-28s failed: %s\n", specs[k], aa_last_error());
                continue;
            }
            qsort(t, (size_t)reps, sizeof *t, cmp);
            double med = t[reps / 2];
            if (!strcmp(specs[k], "point"))
                point = med;
            printf("  %-28s %d thr %9.3f ms (%.3f %.3f) %7.2f ns/px %7.2f ns/sample  "
                   "expensive %5.1f%%",
                   specs[k], nt, med * 1e3, t[0] * 1e3, t[reps - 1] * 1e3,
                   med * 1e9 / ((double)w * h), c.samples ? med * 1e9 / (double)c.samples : 0.0,
                   100.0 * (double)c.expensive_pixels / ((double)w * h));
            if (point > 0 && strcmp(specs[k], "point"))
                printf("  %6.2fx point", med / point);
            printf("\n");
            fflush(stdout);
        }
        aa_job_free(&job);
    }
    free(t);
    aa_image_free(&img);
    aa_scene_free(scene);
    return 0;
}
