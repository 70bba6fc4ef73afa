/*
 * run.c: running a suite: every method on every view, timed and measured.
 *
 * For each pattern x size x filter the reference comes from the cache (or
 * is computed once and stored); then each method is initialised once,
 * rendered once untimed (warm-up) and then timed into an image touched
 * beforehand, `reps` times or until its median is known to the target
 * precision (aa_method_time; only the render is timed, not set-up or file
 * output), and measured against the reference; a stochastic method's error
 * is also measured over `seeds` seeds.
 * Everything is checked before any work, so a typo in the last method of a
 * long suite is refused at once.  A method that fails a case (an error, a
 * value outside [0, 1] or not finite, and when the case is isolated a crash
 * or a time-out: isolate.c) gives a failed row, and the run goes on.
 * A case run in this process (not isolated) is guarded too: the method's
 * exit() ends the run with status 3 and a message, never 0 with cases
 * lost; its image has guard zones either side, so a write past it fails
 * the case before the row is kept; and the floating-point environment is
 * restored after it, so a changed rounding mode cannot change later rows.
 */
#include "bench.h"
#include "isolate_internal.h"

#include <fenv.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

static int check_list(const void *list, size_t n, const char *what)
{
    if (n == 0 || !list)
        return aa_fail(AA_EINVAL, "no %s given", what);
    return AA_OK;
}

/* A spec whose type is the one of that name in `table`. */
static int check_type(const aa_info *info, const void *const *table, const char *what)
{
    if (!info || !info->name || aa_table_find(table, info->name) != info)
        return aa_fail(AA_EINVAL, "%s %s is not a known %s", what,
                       info && info->name ? info->name : "(none)", what);
    return AA_OK;
}

int aa_run_check(const aa_run_config *cfg)
{
    int st;
    if ((st = check_list(cfg->patterns, cfg->npatterns, "pattern")) ||
        (st = check_list(cfg->sizes, cfg->nsizes, "size")) ||
        (st = check_list(cfg->filters, cfg->nfilters, "filter")) ||
        (st = check_list(cfg->methods, cfg->nmethods, "method")))
        return st;
    if (cfg->frames < 0 || cfg->frames == 1 || cfg->frames > AA_TEMPORAL_MAX_FRAMES)
        return aa_fail(AA_EINVAL, "frames %d out of range (2 to %d)", cfg->frames,
                       AA_TEMPORAL_MAX_FRAMES);
    if (cfg->window < 0 || cfg->window > (cfg->frames > 0 ? cfg->frames : 24))
        return aa_fail(AA_EINVAL, "eye window %d out of range (1 to the %d frames)",
                       cfg->window, cfg->frames > 0 ? cfg->frames : 24);
    if (cfg->reps < 0 || cfg->reps > AA_TIMING_MAX_REPS)
        return aa_fail(AA_EINVAL, "reps %d out of range (1 to %d; 0: by precision)", cfg->reps,
                       AA_TIMING_MAX_REPS);
    if (!(cfg->target_ci >= 0 && cfg->target_ci < 1) || !(cfg->budget >= 0 && cfg->budget <= 3600))
        return aa_fail(AA_EINVAL, "timing target %g or budget %g s out of range (0 to 1; 0 to "
                                  "3600 s)",
                       cfg->target_ci, cfg->budget);
    if (cfg->seeds < 0 || cfg->seeds > 1000)
        return aa_fail(AA_EINVAL, "seeds %d out of range (1 to 1000)", cfg->seeds);
    if (cfg->isolate < AA_ISOLATE_NONE || cfg->isolate > AA_ISOLATE_ALL)
        return aa_fail(AA_EINVAL, "isolation %d out of range (%d to %d)", cfg->isolate,
                       AA_ISOLATE_NONE, AA_ISOLATE_ALL);
    if (!(cfg->case_timeout >= 0 && cfg->case_timeout <= 1e9))
        return aa_fail(AA_EINVAL, "case time-out %g s out of range (0, the default, to 1e9)",
                       cfg->case_timeout);
    for (size_t k = 0; k < cfg->npatterns; k++) {
        const aa_spec *p = &cfg->patterns[k].spec;
        if ((st = check_type(p->info, (const void *const *)aa_pattern_types, "pattern")))
            return st;
        const aa_pattern_type *type = (const aa_pattern_type *)p->info;
        if (type->check && (st = type->check(p->v)))
            return st;
    }
    for (size_t k = 0; k < cfg->nsizes; k++)
        if ((st = aa_size_check(cfg->sizes[k].w, cfg->sizes[k].h, 3, 4)))
            return st;
    /* a method must be known; whether it accepts each filter is a result */
    for (size_t k = 0; k < cfg->nfilters; k++) {
        const aa_filter *f = &cfg->filters[k].filter;
        if ((st = check_type(f->spec.info, (const void *const *)aa_filter_types, "filter")))
            return st;
        /* (a gauss spec with cut > 0 takes the type aa_filter_gauss_mask,
         * whose name and parameters are gauss's) */
        if (strcmp(f->spec.info->name, f->type->info.name) != 0)
            return aa_fail(AA_EINVAL, "filter %s: its spec is of another filter",
                           f->type->info.name);
    }
    for (size_t k = 0; k < cfg->nmethods; k++)
        if ((st = check_type(cfg->methods[k].spec.info, aa_method_table(), "method")))
            return st;
    return AA_OK;
}

/* The text a run shows for a spec: as given, else its canonical text. */
static const char *shown(const char *text, const aa_spec *spec, char *buf, size_t len)
{
    if (text)
        return text;
    if (aa_spec_format(spec, buf, len))
        snprintf(buf, len, "%s", spec->info->name);
    return buf;
}

void aa_spec_slug(const char *text, char *buf, size_t len)
{
    size_t n = 0;
    for (const char *c = text; *c && n + 1 < len; c++) {
        int keep = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                   (*c >= '0' && *c <= '9') || *c == '.' || *c == '-';
        buf[n++] = keep ? *c : '_';
    }
    buf[n] = '\0';
}

/* The error map (signed, auto-scaled, with its colour bar) and the worst
 * region zoomed (errmap.c), as sRGB codes. */
static int write_error_map(const char *path, const char *worst, const aa_image *ref,
                           const aa_image *img, const aa_encode *enc)
{
    aa_image pic;
    int st = aa_error_picture(ref, img, "image - reference (linear)", &pic, NULL);
    if (st)
        return st;
    st = aa_picture_write(path, &pic);
    aa_image_free(&pic);
    if (st || (st = aa_worst_picture(ref, img, enc, &pic, NULL, NULL)))
        return st;
    st = aa_picture_write(worst, &pic);
    aa_image_free(&pic);
    return st;
}

static int write_images(const aa_run_config *cfg, const char *stem, const aa_image *ref,
                        const aa_image *img)
{
    char path[4096];
    int st;
    if ((st = aa_pathf(path, sizeof path, "%s/%s.exr", cfg->images_dir, stem)) ||
        (st = aa_image_write(path, img, NULL)) ||
        (st = aa_pathf(path, sizeof path, "%s/%s.png", cfg->images_dir, stem)) ||
        (st = aa_image_write(path, img, &cfg->enc)))
        return st;
    if (!ref)
        return AA_OK;
    char worst[4096];
    if ((st = aa_pathf(path, sizeof path, "%s/%s-error.png", cfg->images_dir, stem)) ||
        (st = aa_pathf(worst, sizeof worst, "%s/%s-worst.png", cfg->images_dir, stem)))
        return st;
    return write_error_map(path, worst, ref, img, &cfg->enc);
}

/* The machine's name, for the rows it measures (times are only comparable
 * on one machine: a merged run keeps each case's). */
static void host_name(char *buf, size_t len)
{
    struct utsname u;
    if (uname(&u) == 0)
        snprintf(buf, len, "%.63s", u.nodename);
    else
        snprintf(buf, len, "unknown");
}

static void row_names(aa_row *row, const char *pattern, int w, int h, const char *filter,
                      const char *method, const aa_run_config *cfg)
{
    memset(row, 0, sizeof *row);
    host_name(row->host, sizeof row->host);
    snprintf(row->pattern, sizeof row->pattern, "%s", pattern);
    snprintf(row->filter, sizeof row->filter, "%s", filter);
    snprintf(row->method, sizeof row->method, "%s", method);
    row->w = w, row->h = h;
    row->t = cfg->t, row->vx = cfg->vx, row->vy = cfg->vy;
    row->seed = cfg->seed;
    row->threads = cfg->threads;
    row->reps = cfg->reps;
    row->ref_bound = row->ref_scanned = NAN;
}

/* The note of a case the method refused: a result (ok 0, failed 0). */
static void row_refused(aa_row *row)
{
    snprintf(row->note, sizeof row->note, "refused: %s", aa_last_error());
}

/* An image of the method with values outside [0, 1] (wider under a filter
 * with negative lobes: aa_method_value_range) or not finite fails its
 * case: 1 if so (the row says where). */
static int bad_image(aa_row *row, const aa_image *img, const aa_filter *f, const char *what)
{
    int at[3];
    double v = 0, lo, hi;
    aa_method_value_range(f, &lo, &hi);
    size_t bad = aa_image_bad_values(img, lo, hi, at, &v);
    if (bad)
        aa__row_failed(row,
                       "%s%zu value%s outside [%.6g, %.6g] or not finite, the first %.17g at "
                       "pixel (%d, %d) channel %d",
                       what, bad, bad == 1 ? "" : "s", lo, hi, v, at[0], at[1], at[2]);
    return bad != 0;
}

/* A stochastic method's RMSE over seeds seed, seed + 1, ... (the first
 * already measured in row->m): the mean and its 95% interval.  The image
 * is overwritten. */
static int run_seeds(const aa_run_config *cfg, const aa_job *job, const aa_spec *spec,
                     const aa_image *ref, aa_image *img, aa_row *row)
{
    const aa_method_type *type = (const aa_method_type *)spec->info;
    row->seeds = 1;
    row->rmse_mean = row->m.rmse;
    row->rmse_ci_lo = row->rmse_ci_hi = NAN;
    if (cfg->seeds <= 1 || !(type->flags & AA_METHOD_SEEDED))
        return AA_OK;
    double *rmse = malloc((size_t)cfg->seeds * sizeof *rmse);
    if (!rmse)
        return aa_fail(AA_ENOMEM, "out of memory for %d seeds", cfg->seeds);
    rmse[0] = row->m.rmse;
    int st = AA_OK;
    for (int k = 1; k < cfg->seeds && !st; k++) {
        aa_job other = *job; /* the same placed scene, another seed */
        aa_counters c;
        aa_metrics m;
        other.seed = cfg->seed + (uint64_t)k;
        if (!(st = aa_method_run(spec, &other, 1, img, &c, NULL)) &&
            !(st = aa_metrics_compute(ref, img, &cfg->enc, &m)))
            rmse[k] = m.rmse;
    }
    if (!st && !(st = aa_mean_ci(rmse, (size_t)cfg->seeds, 0.95, &row->rmse_mean,
                                 &row->rmse_ci_lo, &row->rmse_ci_hi)))
        row->seeds = cfg->seeds;
    free(rmse);
    return st;
}

/* One method on one view.  A method that shows its image through moving
 * dots (core.h, "Displays") is measured against the reference seen
 * through the same dots (display.c), any other against `ref`. */
static int run_method(const aa_run_config *cfg, const aa_view *view, const aa_job *job,
                      const aa_spec *spec, const aa_image *ref, aa_image *img, aa_row *row)
{
    aa_timing_plan plan = {cfg->reps, cfg->target_ci, cfg->budget};
    aa_counters c;
    aa_image dref = {0};
    int shown = 0;
    int st = aa_method_check(spec, &job->filter);
    if (st == AA_EINVAL) { /* refused (e.g. a filter it cannot honour): a result */
        row_refused(row);
        return AA_OK;
    }
    if (st) {
        aa__row_failed(row, "%s", aa_last_error());
        return AA_OK;
    }
    if ((st = aa_spec_format(spec, row->canonical, sizeof row->canonical)))
        return aa_fail_context(st, "%s", row->method);
    st = aa_method_time(spec, job, &plan, img, &c, &row->timing);
    if (st == AA_EINVAL) {
        /* refused at init: a scene it cannot take (colour, several layers, a
         * field): a result too */
        row_refused(row);
        return AA_OK;
    }
    if (st) {
        aa__row_failed(row, "%s", aa_last_error());
        return AA_OK;
    }
    if (bad_image(row, img, &job->filter, "gave "))
        return AA_OK;
    if (!(st = aa_display_view_reference(view, spec, job, cfg->threads, &dref, &shown)) &&
        !(st = aa_metrics_compute(shown ? &dref : ref, img, &cfg->enc, &row->m)))
        st = aa_metrics_edges(job->placed, aa_filter_support(&job->filter), shown ? &dref : ref,
                              img, &row->m);
    if (st) {
        aa_image_free(&dref);
        return aa_fail_context(st, "%s on %s %dx%d %s", row->method, row->pattern, row->w,
                               row->h, row->filter);
    }
    double pixels = (double)row->w * row->h;
    row->reps = row->timing.n;
    row->seconds = row->timing.stats.median;
    row->seconds_min = row->timing.stats.min;
    row->seconds_max = row->timing.stats.max;
    row->samples = c.samples;
    row->expensive_pixels = c.expensive_pixels;
    row->spp = (double)c.samples / pixels;
    row->ns_per_pixel = row->seconds * 1e9 / pixels;
    row->ns_per_sample = c.samples ? row->seconds * 1e9 / (double)c.samples : 0.0;
    row->expensive_fraction = (double)c.expensive_pixels / pixels;
    row->ok = 1;
    if (((const aa_method_type *)spec->info)->flags & AA_METHOD_EXTERNAL)
        snprintf(row->note, sizeof row->note, "%s",
                 row->timing.n && row->timing.reported == row->timing.n
                     ? "time is the renderer's own drawing, timed in its process by its "
                       "adapter (start-up, reading and writing left out)"
                     : "time is the renderer's whole process, its start-up included");
    st = run_seeds(cfg, job, spec, shown ? &dref : ref, img, row);
    aa_image_free(&dref);
    return st;
}

/* ---- temporal metrics of animated runs ---- */

static int animated(const aa_run_config *cfg)
{
    return cfg->temporal || cfg->vx != 0.0 || cfg->vy != 0.0;
}

static int frame_count(const aa_run_config *cfg)
{
    return cfg->frames > 0 ? cfg->frames : 24;
}

static int window_of(const aa_run_config *cfg)
{
    return cfg->window > 0 ? cfg->window : 6;
}

/* The frames' references: the view at times t, t + 1, ... (from the cache). */
static int temporal_refs(const aa_run_config *cfg, const aa_view *still, aa_image *refs)
{
    int n = frame_count(cfg), st;
    for (int k = 0; k < n; k++) {
        aa_view v = *still;
        v.t = cfg->t + k;
        if ((st = aa_reference(&v, cfg->cache_dir, cfg->threads, &refs[k], NULL, NULL)))
            return st;
    }
    return AA_OK;
}

/* Dots (the `dots` pattern): the centre of each closed path's bounds, in
 * pixel units at time 0.  *n = 0 for other patterns. */
static int dot_centres(const aa_view *view, const aa_scene *scene, double **cx, double **cy,
                       size_t *n)
{
    *cx = *cy = NULL;
    *n = 0;
    if (strcmp(view->pattern.info->name, "dots"))
        return AA_OK;
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(scene, &ne);
    const size_t *start = aa_scene_contours(scene, &nc);
    if (!nc)
        return AA_OK;
    *cx = malloc(nc * sizeof **cx);
    *cy = malloc(nc * sizeof **cy);
    if (!*cx || !*cy)
        return aa_fail(AA_ENOMEM, "out of memory for %zu dots", nc);
    for (size_t c = 0; c < nc; c++) {
        double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
        for (size_t k = start[c]; k < start[c + 1] && k < ne; k++) {
            x0 = fmin(x0, fmin(e[k].x0, e[k].x1)), x1 = fmax(x1, fmax(e[k].x0, e[k].x1));
            y0 = fmin(y0, fmin(e[k].y0, e[k].y1)), y1 = fmax(y1, fmax(e[k].y0, e[k].y1));
        }
        (*cx)[c] = 0.5 * (x0 + x1) * view->w;
        (*cy)[c] = 0.5 * (y0 + y1) * view->h;
    }
    *n = nc;
    return AA_OK;
}

/* The displayed frames of a method at times t, t + 1, ... (temporal methods
 * with frame_only), measured against the references; a frame shown through
 * moving dots against its reference seen through the same dots (display.c),
 * made here for this method. */
static int run_temporal(const aa_run_config *cfg, const aa_view *view, const aa_scene *scene,
                        const aa_spec *spec, const aa_image *refs, aa_image *frames,
                        aa_row *row)
{
    int n = frame_count(cfg), st = AA_OK;
    double *cx = NULL, *cy = NULL, *shift = NULL;
    size_t nd = 0;
    aa_image *own = NULL; /* this method's references, when it moves its dots */
    for (int k = 0; k < n && !st; k++) {
        aa_job job;
        aa_counters c;
        aa_image dref = {0};
        int shown = 0;
        char what[64];
        if ((st = aa_job_init(&job, scene, view->w, view->h, cfg->t + k, cfg->vx, cfg->vy,
                              &view->filter, cfg->seed, cfg->threads)))
            break;
        job.frame_only = 1;
        int mst = aa_method_run(spec, &job, 1, &frames[k], &c, NULL);
        /* the method's failure on a frame fails the case, not the run */
        snprintf(what, sizeof what, "frame %d (time %g): ", k, cfg->t + k);
        if (mst) {
            aa_job_free(&job);
            aa__row_failed(row, "%s%s", what, aa_last_error());
            st = AA_OK;
            goto out;
        }
        if (bad_image(row, &frames[k], &view->filter, what)) {
            aa_job_free(&job);
            goto out;
        }
        st = aa_display_view_reference(view, spec, &job, cfg->threads, &dref, &shown);
        aa_job_free(&job);
        if (!st && shown && !own && !(own = calloc((size_t)n, sizeof *own)))
            st = aa_fail(AA_ENOMEM, "out of memory");
        if (st || !shown)
            aa_image_free(&dref);
        else
            own[k] = dref; /* owned by own[] from here */
    }
    for (int k = 0; own && k < n && !st; k++)
        if (!own[k].v)
            st = aa_fail(AA_EFAIL, "method %s shows some frames through moving dots and "
                                   "others not", row->method);
    if (own)
        refs = own;
    if (!st)
        st = aa_temporal_compute(frames, refs, n, window_of(cfg), &row->tm);
    if (!st)
        st = dot_centres(view, scene, &cx, &cy, &nd);
    if (!st && nd) {
        if (!(shift = malloc(2 * (size_t)n * sizeof *shift))) {
            st = aa_fail(AA_ENOMEM, "out of memory");
        } else {
            for (int k = 0; k < n; k++)
                shift[2 * k] = (cfg->t + k) * cfg->vx, shift[2 * k + 1] = (cfg->t + k) * cfg->vy;
            st = aa_temporal_popping(frames, refs, n, cx, cy, nd, shift, &row->tm.popping);
        }
    }
    free(cx);
    free(cy);
    free(shift);
    if (own) {
        for (int k = 0; k < n; k++)
            aa_image_free(&own[k]);
        free(own);
    }
    if (st)
        return aa_fail_context(st, "temporal metrics of %s on %s", row->method, row->pattern);
    row->temporal = 1;
    return AA_OK;
out: /* the method failed a frame: the case failed (the row says why) */
    if (own) {
        for (int k = 0; k < n; k++)
            aa_image_free(&own[k]);
        free(own);
    }
    return AA_OK;
}

/* Everything a case needs, for run_case in this process or in a child. */
typedef struct case_args {
    const aa_run_config *cfg;
    const aa_view *view;
    const aa_scene *scene;
    const aa_job *job;
    const aa_spec *spec;
    const aa_image *ref, *refs;
    aa_image *img, *frames;
    int nt;
    double timeout;
} case_args;

/* One case: the method on the view, and for animated runs its frames. */
static int run_case(void *arg, aa_row *row)
{
    const case_args *a = arg;
    aa_external_time_limit(a->timeout); /* renderers it runs end with the case */
    int st = run_method(a->cfg, a->view, a->job, a->spec, a->ref, a->img, row);
    if (!st && a->nt && row->ok)
        st = run_temporal(a->cfg, a->view, a->scene, a->spec, a->refs, a->frames, row);
    return st;
}

/* ---- a case in this process, guarded ---- */

/* The method whose case runs in this process now, for the exit handler. */
static char running[sizeof ((aa_row *)0)->method];
static volatile sig_atomic_t in_case;

/* exit() called while a method runs in this process: the rows kept so far
 * are whole (each is written after its case), the case is lost, so the run
 * ends with status 3, nothing more flushed or written. */
static void exit_during_case(void)
{
    if (!in_case)
        return;
    char msg[sizeof running + 96];
    int n = snprintf(msg, sizeof msg, "aabench: method %s called exit() during its render\n",
                     running);
    if (n > 0) {
        ssize_t w = write(STDERR_FILENO, msg, (size_t)n < sizeof msg ? (size_t)n : sizeof msg - 1);
        (void)w;
    }
    _exit(3);
}

/* Guard zones either side of the image a method writes, in doubles (4 KiB
 * each), filled with a pattern no render leaves by chance. */
#define GUARD 512
static const unsigned char guard_byte = 0xa5;

/* run_case in this process: into a copy of the image between guard zones,
 * with exit() caught and the floating-point environment restored after. */
static int run_case_here(case_args *ca, aa_row *row)
{
    static int registered;
    if (!registered) {
        if (atexit(exit_during_case))
            return aa_fail(AA_ENOMEM, "cannot register the exit handler of the run");
        registered = 1;
    }
    aa_image *img = ca->img;
    size_t n = (size_t)img->w * (size_t)img->h * (size_t)img->c; /* allocated, so it fits */
    double *buf = malloc((n + 2 * GUARD) * sizeof *buf);
    if (!buf)
        return aa_fail(AA_ENOMEM, "image %d x %d x %d: out of memory for its guarded copy",
                       img->w, img->h, img->c);
    unsigned char pattern[GUARD * sizeof *buf];
    memset(pattern, guard_byte, sizeof pattern);
    memcpy(buf, pattern, sizeof pattern);
    memcpy(buf + GUARD + n, pattern, sizeof pattern);
    memcpy(buf + GUARD, img->v, n * sizeof *buf);
    aa_image guarded = *img;
    guarded.v = buf + GUARD;
    case_args a = *ca;
    a.img = &guarded;

    fenv_t env;
    int saved = !fegetenv(&env);
    int round = fegetround();
    snprintf(running, sizeof running, "%s", row->method);
    in_case = 1;
    int st = run_case(&a, row);
    in_case = 0;
    int changed = fegetround() != round;
    if (saved)
        fesetenv(&env);

    if (memcmp(buf, pattern, sizeof pattern) || memcmp(buf + GUARD + n, pattern, sizeof pattern)) {
        /* what it wrote may be anywhere: the case failed, whatever it gave */
        aa__row_failed(row, "wrote past its image (%d x %d x %d)", img->w, img->h, img->c);
        st = AA_OK;
    } else {
        memcpy(img->v, guarded.v, n * sizeof *buf);
        if (!st && changed) {
            size_t len = strlen(row->note);
            snprintf(row->note + len, sizeof row->note - len, "%s%s", len ? "; " : "",
                     "changed the rounding mode (restored after it)");
        }
    }
    free(buf);
    return st;
}

/* Whether a method's cases run in a child of their own. */
static int isolated(const aa_run_config *cfg, const aa_spec *spec)
{
    if (cfg->isolate == AA_ISOLATE_ALL)
        return 1;
    if (cfg->isolate != AA_ISOLATE_PLUGINS)
        return 0;
    for (size_t k = 0; aa_method_types[k]; k++)
        if (&aa_method_types[k]->info == spec->info)
            return 0; /* built in */
    return 1;
}

static void free_images(aa_image *im, int n)
{
    for (int k = 0; im && k < n; k++)
        aa_image_free(&im[k]);
}

static int alloc_images(aa_image *im, int n, int w, int h)
{
    int st = AA_OK;
    for (int k = 0; k < n && !st; k++)
        st = aa_image_alloc(&im[k], w, h, 3);
    return st;
}

int aa_run(const aa_run_config *cfg, aa_row **rows_out, size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    int st = aa_run_check(cfg);
    if (st)
        return st;
    const double timeout = cfg->case_timeout > 0 ? cfg->case_timeout : AA_CASE_TIMEOUT;
    const size_t nm = cfg->nmethods;
    size_t all = cfg->npatterns * cfg->nsizes * cfg->nfilters * nm, total = 0, n = 0;
    for (size_t k = 0; k < all; k++)
        total += !cfg->only || cfg->only[k];
    aa_row *rows = calloc(total ? total : 1, sizeof *rows);
    aa_scene *scene = NULL;
    aa_image ref = {0}, img = {0};
    aa_truth_stats rstats = {0};
    aa_job job = {0};
    const int nt = animated(cfg) ? frame_count(cfg) : 0;
    aa_image *refs = nt ? calloc((size_t)nt, sizeof *refs) : NULL;
    aa_image *frames = nt ? calloc((size_t)nt, sizeof *frames) : NULL;
    if (!rows || (nt && (!refs || !frames))) {
        free(rows);
        free(refs);
        free(frames);
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", total);
    }
    if (cfg->images_dir && (st = aa_mkdirs(cfg->images_dir)))
        goto done;
    for (size_t ip = 0; ip < cfg->npatterns && !st; ip++) {
        aa_view view;
        char pbuf[sizeof rows->pattern];
        const char *pattern = shown(cfg->patterns[ip].text, &cfg->patterns[ip].spec, pbuf,
                                    sizeof pbuf);
        memset(&view, 0, sizeof view);
        view.pattern = cfg->patterns[ip].spec;
        /* a pattern drawn at the view's size (svg, text) is built for each size */
        int sized = aa_pattern_sized(&view.pattern);
        if (!sized && (st = aa_pattern_scene(&view.pattern, &scene)))
            break;
        for (size_t is = 0; is < cfg->nsizes && !st; is++) {
            view.w = cfg->sizes[is].w, view.h = cfg->sizes[is].h;
            if (sized) {
                aa_scene_free(scene);
                scene = NULL;
                if ((st = aa_pattern_scene_at(&view.pattern, view.w, view.h, &scene)))
                    break;
            }
            if ((st = aa_image_alloc(&img, view.w, view.h, 3)))
                break;
            const char *images_dir = cfg->images_dir;
            if (cfg->images_max && (long)view.w * view.h > cfg->images_max)
                images_dir = NULL;
            if (nt && ((st = aa_size_check(view.w, view.h, 3, 2 * nt + 4)) ||
                       (st = alloc_images(frames, nt, view.w, view.h))))
                break;
            for (size_t jf = 0; jf < cfg->nfilters && !st; jf++) {
                char stem[1400], ps[512], fs[256], fbuf[sizeof rows->filter];
                /* the view's first case in the cross product */
                const size_t first = ((ip * cfg->nsizes + is) * cfg->nfilters + jf) * nm;
                size_t chosen = 0;
                for (size_t im = 0; im < nm; im++)
                    chosen += !cfg->only || cfg->only[first + im];
                if (!chosen)
                    continue; /* another shard's view, or done before */
                const char *filter = shown(cfg->filters[jf].text, &cfg->filters[jf].filter.spec,
                                           fbuf, sizeof fbuf);
                view.filter = cfg->filters[jf].filter;
                view.t = cfg->t, view.vx = cfg->vx, view.vy = cfg->vy;
                aa_spec_slug(pattern, ps, sizeof ps);
                aa_spec_slug(filter, fs, sizeof fs);
                aa_case_estimate_warn(cfg, &view, scene, first); /* before a case of minutes */
                if (cfg->progress && cfg->progress(cfg->ctx, n, total, "reference")) {
                    st = aa_fail(AA_EFAIL, "interrupted");
                    break;
                }
                if ((st = aa_reference(&view, cfg->cache_dir, cfg->threads, &ref, &rstats, NULL)) ||
                    (st = aa_job_init(&job, scene, view.w, view.h, cfg->t, cfg->vx, cfg->vy,
                                      &view.filter, cfg->seed, cfg->threads)))
                    break;
                if (nt && (st = temporal_refs(cfg, &view, refs)))
                    break;
                snprintf(stem, sizeof stem, "%s-%dx%d-%s-reference", ps, view.w, view.h, fs);
                if (images_dir && (st = write_images(cfg, stem, NULL, &ref)))
                    break;
                for (size_t im = 0; im < cfg->nmethods && !st; im++) {
                    char what[1400], ms[512], mbuf[sizeof rows->method];
                    const aa_spec *spec = &cfg->methods[im].spec;
                    const char *method = shown(cfg->methods[im].text, spec, mbuf, sizeof mbuf);
                    aa_row *row = &rows[n];
                    if (cfg->only && !cfg->only[first + im])
                        continue;
                    snprintf(what, sizeof what, "%s %dx%d %s %s", pattern, view.w, view.h, filter,
                             method);
                    if (cfg->progress && cfg->progress(cfg->ctx, n, total, what)) {
                        st = aa_fail(AA_EFAIL, "interrupted");
                        break;
                    }
                    row_names(row, pattern, view.w, view.h, filter, method, cfg);
                    if ((st = aa_case_inputs(&cfg->patterns[ip].spec, spec, row->inputs,
                                             sizeof row->inputs)))
                        break;
                    row->case_index = (long)(cfg->case_base + first + im);
                    aa_spec_slug(method, ms, sizeof ms);
                    snprintf(stem, sizeof stem, "%s-%dx%d-%s-%s", ps, view.w, view.h, fs, ms);
                    case_args ca = {cfg,  &view, scene,  &job, spec,  &ref,
                                   refs, &img,  frames, nt,   timeout};
                    if (!isolated(cfg, spec)) {
                        st = run_case_here(&ca, row);
                    } else {
                        st = aa__case_isolated(run_case, &ca, row, images_dir ? &img : NULL,
                                               timeout, cfg->threads);
                        if (!st && row->failed && !*row->canonical &&
                            aa_spec_format(spec, row->canonical, sizeof row->canonical))
                            row->canonical[0] = '\0';
                    }
                    if (st)
                        break;
                    if (!row->ok && !row->failed && cfg->skip_refused) {
                        /* a pair the method refuses: no row */
                        if (cfg->skipped)
                            (*cfg->skipped)++;
                        if (cfg->refused)
                            cfg->refused[first + im] = 1;
                        memset(row, 0, sizeof *row);
                        continue;
                    }
                    row->ref_bound = rstats.max_bound;
                    row->ref_scanned = (double)rstats.scanned;
                    /* images are written here, by this process, whichever ran the case */
                    if (row->ok && images_dir && (st = write_images(cfg, stem, &ref, &img)))
                        break;
                    n++;
                    if (cfg->row_done && (st = cfg->row_done(cfg->ctx, rows, n)))
                        break;
                }
                aa_job_free(&job);
                aa_image_free(&ref);
                free_images(refs, nt);
            }
            aa_image_free(&img);
            free_images(frames, nt);
        }
        aa_scene_free(scene);
        scene = NULL;
    }
    if (!st && cfg->progress)
        cfg->progress(cfg->ctx, n, total, "done");
done:
    free_images(refs, nt);
    free_images(frames, nt);
    free(refs);
    free(frames);
    aa_job_free(&job);
    aa_image_free(&ref);
    aa_image_free(&img);
    aa_scene_free(scene);
    *rows_out = rows;
    *n_out = n;
    return st;
}

int aa_run_warm(const aa_run_config *cfg, size_t *computed, size_t *cached)
{
    int st = aa_run_check(cfg);
    if (st)
        return st;
    const int nt = animated(cfg) ? frame_count(cfg) : 1;
    const size_t nm = cfg->nmethods;
    for (size_t ip = 0; ip < cfg->npatterns && !st; ip++)
        for (size_t is = 0; is < cfg->nsizes && !st; is++)
            for (size_t jf = 0; jf < cfg->nfilters && !st; jf++) {
                const size_t first = ((ip * cfg->nsizes + is) * cfg->nfilters + jf) * nm;
                size_t chosen = 0;
                for (size_t im = 0; im < nm; im++)
                    chosen += !cfg->only || cfg->only[first + im];
                if (!chosen)
                    continue;
                /* the references aa_run asks for: the view at t, and for
                 * animated runs at t + 1, ... too */
                for (int k = 0; k < nt && !st; k++) {
                    aa_view view;
                    aa_image ref = {0};
                    int hit = 0;
                    memset(&view, 0, sizeof view);
                    view.pattern = cfg->patterns[ip].spec;
                    view.w = cfg->sizes[is].w, view.h = cfg->sizes[is].h;
                    view.filter = cfg->filters[jf].filter;
                    view.t = cfg->t + k, view.vx = cfg->vx, view.vy = cfg->vy;
                    if (cfg->progress && cfg->progress(cfg->ctx, *computed + *cached, 0,
                                                       "reference"))
                        st = aa_fail(AA_EFAIL, "interrupted");
                    if (!st && !(st = aa_reference(&view, cfg->cache_dir, cfg->threads, &ref,
                                                   NULL, &hit)))
                        ++*(hit ? cached : computed);
                    aa_image_free(&ref);
                }
            }
    return st;
}
