/*
 * bench_methods.c: speed of the methods against each other and against the
 * peer rasterizers (`make bench`).
 *
 * One run, one table.  For each method spec (and the reference, "reference":
 * aa_truth_render), on one pattern, size and filter: the median render time
 * with 1 and 2 threads and the relative half-width of its 95% CI (after one
 * untimed init and one untimed warm-up render per thread count, into an
 * image allocated and touched once, repeated until both CIs are within the
 * target, --target-ci PCT (default 2), or the budget runs out, --budget S
 * (default 1 s per thread count), or exactly -r N times; the 1- and
 * 2-thread renders take turns, so a load that comes and goes on a shared
 * machine falls on both alike; aa_timing_measure), a mark on a noisy
 * timing (CI target missed, many outliers, other processes busy on the
 * cores: no ratio built on it is judged), the ratio of each to `point` at the
 * same thread count, the speed-up of 2 threads over 1, the largest error
 * against the reference (rendered once beforehand; for the reference its
 * own error bound), and the peak memory of a render at a larger size.
 *
 * Peak memory: each method renders once (init and render, 2 threads) in a
 * fresh process (this program run again with --peak) that first allocates
 * and touches the W x H x 3 output image; its peak is its own VmHWM
 * (/proc/self/status).  A baseline process that only allocates and touches the image
 * is subtracted, so "extra" is what
 * the method needs beyond its output; "total/image" is (image + extra) /
 * image, the figure the target "at most twice the output image" reads.
 *
 * Then the ratios the targets name, each from this run's medians.
 * Figures are read, not asserted.
 *
 * usage: bench_methods [-p PATTERN] [-s WxH] [-f FILTER] [-r REPS] [--target-ci PCT]
 *                      [--budget S] [-m WxH|none] [SPEC...]
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAXSPECS 64

typedef struct row {
    const char *spec;
    int ok;
    char note[256];
    double med[2], ci[2], err; /* medians, their CIs' relative half-widths */
    unsigned noisy[2];
    double extra_mb, total_ratio;
} row;

static int is_reference(const char *spec) { return !strcmp(spec, "reference"); }

/* A verdict on a target from timings: never judged on a noisy one. */
static const char *judge(int met, const row *a, const row *b)
{
    if (a->noisy[0] || a->noisy[1] || (b && (b->noisy[0] || b->noisy[1])))
        return "not judged: noisy timing";
    return met ? "met" : "NOT met";
}

/* "12.345 +-1.2%*": a median in ms, its CI and a star if noisy */
static void ms_text(const row *r, int th, char *buf, size_t len)
{
    if (isfinite(r->ci[th]))
        snprintf(buf, len, "%.3f +-%.1f%%%s", r->med[th] * 1e3, 100 * r->ci[th],
                 r->noisy[th] ? "*" : "");
    else
        snprintf(buf, len, "%.3f%s", r->med[th] * 1e3, r->noisy[th] ? "*" : "");
}

/* One render of spec (or the reference) with instance m (unused for the
 * reference) into img. */
typedef struct render_ctx {
    const char *spec;
    aa_method *m;
    const aa_job *job;
    aa_image *img;
} render_ctx;

static int render_once(void *vctx)
{
    render_ctx *c = vctx;
    aa_counters counters;
    return is_reference(c->spec) ? aa_truth_render(c->job->placed, &c->job->filter,
                                                   c->job->threads, c->img, NULL, NULL)
                                 : aa_method_render(c->m, c->job, c->img, &counters);
}

/* Time spec with 1 and with 2 threads (jobs[0], jobs[1]), taking turns, so
 * that both thread counts see the same load of a shared machine, by the
 * plan: t[0], t[1].  One untimed init per thread count. */
static int time_spec2(const char *spec, const aa_job *jobs, const aa_timing_plan *plan,
                      aa_image *img, aa_timing *t)
{
    aa_method m[2] = {{0}, {0}};
    aa_spec ms;
    int st = AA_OK;
    if (!is_reference(spec))
        if ((st = aa_method_parse(spec, &jobs[0].filter, &ms)) ||
            (st = aa_method_init(&m[0], &ms, &jobs[0])) ||
            (st = aa_method_init(&m[1], &ms, &jobs[1])))
            goto done;
    render_ctx c[2] = {{spec, &m[0], &jobs[0], img}, {spec, &m[1], &jobs[1], img}};
    aa_timed_fn fn[2] = {render_once, render_once};
    void *ctx[2] = {&c[0], &c[1]};
    int threads[2] = {jobs[0].threads, jobs[1].threads};
    st = aa_timing_measure(plan, 2, fn, ctx, threads, t);
done:
    if (!is_reference(spec)) {
        if (m[0].type)
            aa_method_free(&m[0]);
        if (m[1].type)
            aa_method_free(&m[1]);
    }
    return st;
}

/* One untimed render (the memory child). */
static int time_spec(const char *spec, const aa_job *job, int reps, aa_image *img,
                     double *t)
{
    (void)reps;
    if (is_reference(spec))
        return aa_truth_render(job->placed, &job->filter, job->threads, img, NULL, NULL);
    aa_spec m;
    aa_counters c;
    return aa_method_parse(spec, &job->filter, &m) || aa_method_run(&m, job, 1, img, &c, t);
}

/* The child: allocate and touch a W x H x 3 image and then, unless spec is
 * "-", render spec into it once (2 threads).  Exit status 0 on success. */
static int peak_child(const char *spec, const char *pattern, const char *size,
                      const char *filter)
{
    aa_spec pspec;
    aa_scene *scene;
    aa_filter f;
    aa_image img;
    aa_job job;
    int w, h;
    if (aa_pattern_parse(pattern, &pspec) || aa_pattern_scene(&pspec, &scene) ||
        aa_size_parse(size, &w, &h) || aa_filter_parse(filter, &f) ||
        aa_image_alloc(&img, w, h, 3) || aa_job_init(&job, scene, w, h, 0, 0, 0, &f, 1, 2))
        return 3;
    memset(img.v, 0, (size_t)w * h * 3 * sizeof *img.v);
    double t;
    if (strcmp(spec, "-") && time_spec(spec, &job, 1, &img, &t))
        return 3;
    FILE *st = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (st && fgets(line, sizeof line, st))
        if (sscanf(line, "VmHWM: %ld", &kb) == 1)
            break;
    if (st)
        fclose(st);
    printf("%ld\n", kb);
    return kb < 0 ? 3 : 0;
}

/* Peak resident memory (kB) of a fresh process (this program run again
 * with --peak: nothing of our memory or OpenMP state carried over) running
 * peak_child, read from its own /proc/self/status VmHWM (a process that
 * forks or spawns starts from a copy of its parent's memory, which
 * ru_maxrss would count). */
static long child_peak_kb(const char *spec, const char *pattern, const char *size,
                          const char *filter)
{
    char exe[4096], cmd[8192];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return -1;
    exe[n] = '\0';
    snprintf(cmd, sizeof cmd, "'%s' --peak '%s' '%s' '%s' '%s'", exe, spec, pattern, size,
             filter);
    fflush(stdout);
    FILE *p = popen(cmd, "r");
    long kb = -1;
    if (!p)
        return -1;
    if (fscanf(p, "%ld", &kb) != 1)
        kb = -1;
    if (pclose(p) != 0)
        kb = -1;
    return kb;
}

int main(int argc, char **argv)
{
    /* statically linked: register the built-in methods (core.h) */
    if (aa_method_add_builtin()) {
        fprintf(stderr, "%s\n", aa_last_error());
        return 1;
    }
    const char *pattern = "crow", *size = "1024x1024", *filter = "box", *msize = "4096x4096";
    int reps = 0, first = 1;
    aa_timing_plan plan = {0};
    if (argc == 6 && !strcmp(argv[1], "--peak"))
        return peak_child(argv[2], argv[3], argv[4], argv[5]);
    static const char *defaults[] = {
        "point", "area", "freetype", "stb", "stb:flatness=0.01", "cairo",
        "cairo:aa=best,tolerance=0.01", "jitter:spp=16", "jitter:spp=16,seq=sobol",
        "jitter:spp=64", "supersample:n=3", "supersample:n=4", "supersample:pattern=msaa8",
        "hexagon", "trio", "trio:variant=sancha", "trio:variant=recursive", "mlaa", "fxaa",
        "smaa", "reference"};
    while (first + 1 < argc && argv[first][0] == '-') {
        const char *o = argv[first], *v = argv[first + 1];
        if (!strcmp(o, "-p")) pattern = v;
        else if (!strcmp(o, "-s")) size = v;
        else if (!strcmp(o, "-f")) filter = v;
        else if (!strcmp(o, "-r")) reps = atoi(v);
        else if (!strcmp(o, "--target-ci")) plan.target_ci = atof(v) / 100;
        else if (!strcmp(o, "--budget")) plan.budget = atof(v);
        else if (!strcmp(o, "-m")) msize = v;
        else break;
        first += 2;
    }
    const char *const *specs = defaults;
    size_t nspecs = sizeof defaults / sizeof defaults[0];
    if (first < argc) {
        specs = (const char *const *)argv + first;
        nspecs = (size_t)(argc - first);
    }
    if (nspecs > MAXSPECS)
        nspecs = MAXSPECS;
    if (reps < 0 || reps > AA_TIMING_MAX_REPS)
        reps = 0;
    plan.reps = reps;
    if (!(plan.target_ci >= 0 && plan.target_ci < 1) || !(plan.budget >= 0)) {
        fprintf(stderr, "bench_methods: --target-ci PCT (0 to 100), --budget S (>= 0)\n");
        return 2;
    }
    aa_spec pspec;
    aa_scene *scene;
    aa_filter f;
    int w, h, mw = 0, mh = 0;
    if (aa_pattern_parse(pattern, &pspec) || aa_pattern_scene(&pspec, &scene) ||
        aa_size_parse(size, &w, &h) || aa_filter_parse(filter, &f) ||
        (strcmp(msize, "none") && aa_size_parse(msize, &mw, &mh))) {
        fprintf(stderr, "bench_methods: %s\n", aa_last_error());
        return 2;
    }
    aa_image img, ref;
    aa_job job[2];
    if (aa_image_alloc(&img, w, h, 3) || aa_image_alloc(&ref, w, h, 3))
        return 3;
    for (int t = 0; t < 2; t++)
        if (aa_job_init(&job[t], scene, w, h, 0, 0, 0, &f, 1, t + 1))
            return 2;
    aa_truth_stats tstats;
    if (aa_truth_render(job[1].placed, &f, 2, &ref, NULL, &tstats))
        return 3;
    aa_timing *t = malloc(2 * sizeof *t);
    if (!t)
        return 3;
    memset(img.v, 0, (size_t)w * h * 3 * sizeof *img.v); /* page faults are no method's cost */
    row rows[MAXSPECS] = {{0}};
    long base_kb = mw ? child_peak_kb("-", pattern, msize, filter) : 0;
    double image_mb = (double)mw * mh * 3 * sizeof(double) / 1048576.0;

    for (size_t k = 0; k < nspecs; k++) {
        row *r = &rows[k];
        r->spec = specs[k];
        r->ok = 1;
        if (time_spec2(r->spec, job, &plan, &img, t)) {
            snprintf(r->note, sizeof r->note, "%s", aa_last_error());
            r->ok = 0;
        } else {
            for (int th = 0; th < 2; th++) {
                r->med[th] = t[th].stats.median;
                r->ci[th] = t[th].ci_rel;
                r->noisy[th] = t[th].noisy;
            }
        }
        if (!r->ok)
            continue;
        aa_metrics m;
        if (is_reference(r->spec))
            r->err = tstats.max_bound;
        else if (!aa_metrics_compute(&ref, &img, NULL, &m))
            r->err = m.max_err;
        if (mw) {
            long kb = child_peak_kb(r->spec, pattern, msize, filter);
            r->extra_mb = kb < 0 || base_kb < 0 ? NAN : (double)(kb - base_kb) / 1024.0;
            r->total_ratio = (image_mb + r->extra_mb) / image_mb;
        }
    }

    const row *pt = NULL;
    for (size_t k = 0; k < nspecs; k++)
        if (!strcmp(rows[k].spec, "point") && rows[k].ok)
            pt = &rows[k];
    char how[128];
    if (reps)
        snprintf(how, sizeof how, "%d timed renders", reps);
    else
        snprintf(how, sizeof how, "renders until the 95%% CI is within %g%% or %g s",
                 100 * (plan.target_ci > 0 ? plan.target_ci : AA_TIMING_TARGET),
                 plan.budget > 0 ? plan.budget : AA_TIMING_BUDGET);
    printf("%s %dx%d %s: median and the relative half-width of its 95%% CI (%s, after\n"
           "one untimed init and warm-up; * noisy: target missed, many outliers or other\n"
           "processes busy on the cores); max error against the reference (for the\n"
           "reference, its error bound); peak memory of one render at %s, 2 threads,\n"
           "beyond the %.0f MB output image (baseline: a child that only allocates it)\n\n",
           pattern, w, h, filter, how, mw ? msize : "(not measured)", image_mb);
    printf("%-30s %10s %18s %18s %8s %8s %7s %10s %8s\n", "method", "max error", "1 thr ms",
           "2 thr ms", "/point 1", "/point 2", "2t/1t", "extra MB", "tot/img");
    for (size_t k = 0; k < nspecs; k++) {
        const row *r = &rows[k];
        if (!r->ok) {
            printf("%-30s refused or failed: %s\n", r->spec, r->note);
            continue;
        }
        char m1[48], m2[48];
        ms_text(r, 0, m1, sizeof m1);
        ms_text(r, 1, m2, sizeof m2);
        printf("%-30s %10.2e %18s %18s", r->spec, r->err, m1, m2);
        if (pt)
            printf(" %8.2f %8.2f", r->med[0] / pt->med[0], r->med[1] / pt->med[1]);
        else
            printf(" %8s %8s", "-", "-");
        printf(" %6.2f%s", r->med[0] / r->med[1], r->noisy[0] || r->noisy[1] ? "*" : " ");
        if (mw)
            printf(" %10.1f %8.3f", r->extra_mb, r->total_ratio);
        printf("\n");
    }

    /* the ratios the targets name */
    const row *area = NULL;
    for (size_t k = 0; k < nspecs; k++)
        if (!strcmp(rows[k].spec, "area") && rows[k].ok)
            area = &rows[k];
    if (area) {
        printf("\nratios (this run's medians; 1 thread, 2 threads):\n");
        if (pt)
            printf("  %-40s %6.2f %6.2f   target <= 1.5: %s\n", "area / point",
                   area->med[0] / pt->med[0], area->med[1] / pt->med[1],
                   judge(area->med[0] / pt->med[0] <= 1.5 && area->med[1] / pt->med[1] <= 1.5,
                         area, pt));
        for (size_t k = 0; k < nspecs; k++) {
            const row *r = &rows[k];
            if (!r->ok || (strncmp(r->spec, "freetype", 8) && strncmp(r->spec, "stb", 3) &&
                           strncmp(r->spec, "cairo", 5)))
                continue;
            char name[128];
            snprintf(name, sizeof name, "area / %s", r->spec);
            double er = area->err > 0 ? r->err / area->err : INFINITY;
            printf("  %-40s %6.2f %6.2f   its error / area's: %.1e  (faster and >= 1e6: "
                   "%s)\n",
                   name, area->med[0] / r->med[0], area->med[1] / r->med[1], er,
                   judge(area->med[0] < r->med[0] && area->med[1] < r->med[1] && er >= 1e6,
                         area, r));
        }
        for (size_t k = 0; k < nspecs && pt; k++) {
            const row *r = &rows[k];
            if (!r->ok || !(!strcmp(r->spec, "jitter:spp=16") ||
                            !strcmp(r->spec, "supersample:n=4") || is_reference(r->spec)))
                continue;
            char name[128];
            snprintf(name, sizeof name, "%s / point", r->spec);
            printf("  %-40s %6.2f %6.2f", name, r->med[0] / pt->med[0],
                   r->med[1] / pt->med[1]);
            if (!strcmp(r->spec, "jitter:spp=16"))
                printf("   target <= 8: %s",
                       judge(r->med[0] / pt->med[0] <= 8 && r->med[1] / pt->med[1] <= 8, r, pt));
            printf("\n");
        }
        printf("\n2 threads over 1 (target >= 1.7 for area, point, jitter:spp=16, "
               "reference):\n");
        for (size_t k = 0; k < nspecs; k++) {
            const row *r = &rows[k];
            if (r->ok && (!strcmp(r->spec, "area") || !strcmp(r->spec, "point") ||
                          !strcmp(r->spec, "jitter:spp=16") || is_reference(r->spec)))
                printf("  %-40s %6.2f   %s\n", r->spec, r->med[0] / r->med[1],
                       judge(r->med[0] / r->med[1] >= 1.7, r, NULL));
        }
        if (mw) {
            printf("\npeak memory at %s (target: total <= 2 x image + O(width) per "
                   "thread):\n", msize);
            for (size_t k = 0; k < nspecs; k++) {
                const row *r = &rows[k];
                if (r->ok)
                    printf("  %-40s %8.1f MB extra, %.3f x image   %s\n", r->spec,
                           r->extra_mb, r->total_ratio,
                           r->total_ratio <= 2.0 ? "met" : "NOT met");
            }
        }
    }
    size_t noisy = 0;
    for (size_t k = 0; k < nspecs; k++)
        noisy += rows[k].ok && (rows[k].noisy[0] || rows[k].noisy[1]);
    if (noisy) {
        printf("\nwarning: %zu of %zu methods have a noisy timing (*); no speed-up, loss or "
               "target\nbuilt on one is judged:", noisy, nspecs);
        for (size_t k = 0; k < nspecs; k++)
            if (rows[k].ok && (rows[k].noisy[0] || rows[k].noisy[1])) {
                char a[64], b[64];
                aa_noisy_text(rows[k].noisy[0], a, sizeof a);
                aa_noisy_text(rows[k].noisy[1], b, sizeof b);
                printf("\n  %-30s 1 thread: %s; 2 threads: %s", rows[k].spec, *a ? a : "quiet",
                       *b ? b : "quiet");
            }
        printf("\n");
    }
    free(t);
    for (int th = 0; th < 2; th++)
        aa_job_free(&job[th]);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(scene);
    return 0;
}
