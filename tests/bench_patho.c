/*
 * bench_patho.c: speed on pathological scenes (`make bench`).
 *
 * Scenes whose pixels thousands of edges cross: `crow` with 65536 arcs
 * 1e-5 pattern units apart (kmax 0.1), `feibush` with 65536 stripes.  The
 * ground truth's cost must grow with the crossings a pixel sees, not as
 * their square: the sum over spans took minutes for 2 x 2 pixels of that
 * crow, where a pixel now goes one piece at a time (harness/truth/
 * truth_crowd.c); the exact `area` method tested every pair of a row's
 * overlapping segs for crossings, where a crowded cluster now tests
 * neighbours along x (algorithms/area.c).  For each case and thread count:
 * the time of one render (the scene built and placed beforehand, untimed),
 * the pixels integrated and those taken one piece at a time, the largest
 * error bound.  Nothing here is a test: the figures are read, not
 * asserted (the exactness of these paths is tests/test_truth.c's and
 * tests/test_area.c's).
 *
 * usage: bench_patho [-t 1,2] [-r REPS] [-c CASE,...]   (cases 1..4, default all)
 */
#include "bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CROW "crow:curves=65536,gap0=1e-5,gap1=1e-5,kmax=0.1"

static const struct {
    const char *what, *pattern, *method; /* method NULL: the reference */
    int w, h;
} cases[] = {
    {"reference", CROW, NULL, 16, 16},
    {"reference", CROW, NULL, 64, 64},
    {"reference", "feibush:stripes=65536", NULL, 64, 64},
    {"area", CROW, "area", 1024, 1024},
};

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int run(int k, int threads, int reps)
{
    aa_spec spec;
    aa_scene *scene;
    aa_filter f;
    aa_image img;
    aa_truth_stats st = {0};
    double times[16], t0 = aa_now();
    int w = cases[k].w, h = cases[k].h;
    aa_filter_default(&f);
    if (aa_pattern_parse(cases[k].pattern, &spec) || aa_pattern_scene(&spec, &scene) ||
        aa_image_alloc(&img, w, h, 3)) {
        fprintf(stderr, "bench_patho: %s\n", aa_last_error());
        return 1;
    }
    double build = aa_now() - t0;
    if (!cases[k].method) {
        aa_scene *placed = aa_scene_place(scene, w, h, 0, 0, 0);
        if (!placed)
            return 1;
        memset(img.v, 0, (size_t)w * h * 3 * sizeof *img.v); /* touch once */
        for (int r = 0; r < reps; r++) {
            double t = aa_now();
            if (aa_truth_render(placed, &f, threads, &img, NULL, &st)) {
                fprintf(stderr, "bench_patho: %s\n", aa_last_error());
                return 1;
            }
            times[r] = aa_now() - t;
        }
        aa_scene_free(placed);
    } else {
        aa_spec m;
        aa_job job;
        aa_counters c;
        if (aa_method_parse(cases[k].method, &f, &m) ||
            aa_job_init(&job, scene, w, h, 0, 0, 0, &f, 1, threads) ||
            aa_method_run(&m, &job, reps, &img, &c, times)) {
            fprintf(stderr, "bench_patho: %s\n", aa_last_error());
            return 1;
        }
        st.integrated = c.expensive_pixels;
        aa_job_free(&job);
    }
    qsort(times, (size_t)reps, sizeof *times, cmp);
    printf("%-9s %-22s %5dx%-5d %d thr  %8.2f s", cases[k].what,
           strncmp(cases[k].pattern, "crow:", 5) ? cases[k].pattern : "crow (above)", w, h,
           threads, times[reps / 2]);
    if (reps > 1)
        printf(" (min %.2f max %.2f)", times[0], times[reps - 1]);
    if (cases[k].method)
        printf("  %zu expensive px", st.integrated);
    else
        printf("  %zu integrated, %zu one piece at a time, bound %.1e", st.integrated,
               st.crowded, st.max_bound);
    printf("  (scene built in %.2f s)\n", build);
    fflush(stdout);
    aa_image_free(&img);
    aa_scene_free(scene);
    return 0;
}

int main(int argc, char **argv)
{
    /* statically linked: register the built-in methods (core.h) */
    if (aa_method_add_builtin()) {
        fprintf(stderr, "%s\n", aa_last_error());
        return 1;
    }
    const char *threads = "1,2", *which = NULL;
    int reps = 1;
    for (int k = 1; k + 1 < argc; k += 2) {
        if (!strcmp(argv[k], "-t"))
            threads = argv[k + 1];
        else if (!strcmp(argv[k], "-r"))
            reps = atoi(argv[k + 1]);
        else if (!strcmp(argv[k], "-c"))
            which = argv[k + 1];
    }
    if (reps < 1 || reps > 16)
        reps = 1;
    int ncases = (int)(sizeof cases / sizeof *cases), want[16] = {0};
    if (which) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s", which);
        for (char *c = strtok(buf, ","); c; c = strtok(NULL, ","))
            if (atoi(c) >= 1 && atoi(c) <= ncases)
                want[atoi(c) - 1] = 1;
    } else {
        for (int k = 0; k < ncases; k++)
            want[k] = 1;
    }
    printf("crow = %s\n", CROW);
    for (int k = 0; k < ncases; k++) {
        if (!want[k])
            continue;
        char tbuf[64], *save;
        snprintf(tbuf, sizeof tbuf, "%s", threads);
        for (char *t = strtok_r(tbuf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
            int n = atoi(t);
            if (n < 1 || n > 64)
                return 2;
            if (run(k, n, reps))
                return 3;
        }
    }
    return 0;
}
