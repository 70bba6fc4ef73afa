/*
 * run.c: running a suite: every method on every view, timed and measured.
 *
 * For each pattern x size x filter the reference comes from the cache (or
 * is computed once and stored); then each method is initialised once,
 * rendered `reps` times into an image touched beforehand (only the render is
 * timed, not set-up or file output), and measured against the reference.
 * Everything is checked before any work, so a typo in the last method of a
 * long suite is refused at once.
 */
#include "aabench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check_list(const char *const *specs, size_t n, const char *what)
{
    if (n == 0 || !specs)
        return aa_fail(AA_EINVAL, "no %s given", what);
    return AA_OK;
}

int aa_run_check(const aa_run_config *cfg)
{
    int st, w, h;
    aa_spec spec;
    aa_filter f;
    if ((st = check_list(cfg->patterns, cfg->npatterns, "pattern")) ||
        (st = check_list(cfg->sizes, cfg->nsizes, "size")) ||
        (st = check_list(cfg->filters, cfg->nfilters, "filter")) ||
        (st = check_list(cfg->methods, cfg->nmethods, "method")))
        return st;
    if (cfg->reps < 1 || cfg->reps > 1000)
        return aa_fail(AA_EINVAL, "reps %d out of range (1 to 1000)", cfg->reps);
    for (size_t k = 0; k < cfg->npatterns; k++)
        if ((st = aa_pattern_parse(cfg->patterns[k], &spec)))
            return st;
    for (size_t k = 0; k < cfg->nsizes; k++)
        if ((st = aa_size_parse(cfg->sizes[k], &w, &h)) || (st = aa_size_check(w, h, 3, 4)))
            return st;
    /* a method must parse; whether it accepts each filter is a result */
    aa_filter_default(&f);
    for (size_t k = 0; k < cfg->nfilters; k++)
        if ((st = aa_filter_parse(cfg->filters[k], &f)))
            return st;
    for (size_t k = 0; k < cfg->nmethods; k++)
        if ((st = aa_spec_parse(cfg->methods[k], aa_method_table(), "method", &spec)))
            return st;
    return AA_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
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

/* |error| per pixel (largest channel) on a fixed scale: 0 black, 0.5 and
 * above white, through red and yellow, so maps compare across methods. */
static int write_error_map(const char *path, const aa_image *ref, const aa_image *img)
{
    aa_image map;
    int st = aa_image_alloc(&map, ref->w, ref->h, 3);
    if (st)
        return st;
    size_t n = (size_t)ref->w * ref->h;
    for (size_t p = 0; p < n; p++) {
        double e = 0;
        for (int c = 0; c < ref->c; c++)
            e = fmax(e, fabs(img->v[3 * p + c] - ref->v[3 * p + c]));
        double v = fmin(1.0, e / 0.5);
        map.v[3 * p] = fmin(1.0, 3 * v);
        map.v[3 * p + 1] = fmin(1.0, fmax(0.0, 3 * v - 1));
        map.v[3 * p + 2] = fmin(1.0, fmax(0.0, 3 * v - 2));
    }
    aa_encode linear = {AA_ENCODE_LINEAR, 0};
    st = aa_image_write(path, &map, &linear);
    aa_image_free(&map);
    return st;
}

static int write_images(const aa_run_config *cfg, const char *stem, const aa_image *ref,
                        const aa_image *img)
{
    char path[4096];
    int st;
    snprintf(path, sizeof path, "%s/%s.exr", cfg->images_dir, stem);
    if ((st = aa_image_write(path, img, NULL)))
        return st;
    snprintf(path, sizeof path, "%s/%s.png", cfg->images_dir, stem);
    if ((st = aa_image_write(path, img, &cfg->enc)))
        return st;
    if (!ref)
        return AA_OK;
    snprintf(path, sizeof path, "%s/%s-error.png", cfg->images_dir, stem);
    return write_error_map(path, ref, img);
}

static void row_names(aa_row *row, const char *pattern, int w, int h, const char *filter,
                      const char *method, const aa_run_config *cfg)
{
    memset(row, 0, sizeof *row);
    snprintf(row->pattern, sizeof row->pattern, "%s", pattern);
    snprintf(row->filter, sizeof row->filter, "%s", filter);
    snprintf(row->method, sizeof row->method, "%s", method);
    row->w = w, row->h = h;
    row->t = cfg->t, row->vx = cfg->vx, row->vy = cfg->vy;
    row->seed = cfg->seed;
    row->threads = cfg->threads;
    row->reps = cfg->reps;
}

/* One method on one view. */
static int run_method(const aa_run_config *cfg, const aa_job *job, const aa_image *ref,
                      aa_image *img, const char *stem, aa_row *row, double *seconds)
{
    aa_spec spec;
    aa_counters c;
    int st = aa_method_parse(row->method, &job->filter, &spec);
    if (st == AA_EINVAL) { /* refused (e.g. a filter it cannot honour): a result */
        snprintf(row->note, sizeof row->note, "refused: %s", aa_last_error());
        return AA_OK;
    }
    if (st || (st = aa_spec_format(&spec, row->canonical, sizeof row->canonical)) ||
        (st = aa_method_run(&spec, job, cfg->reps, img, &c, seconds)) ||
        (st = aa_metrics_compute(ref, img, &cfg->enc, &row->m)))
        return aa_fail_context(st, "%s on %s %dx%d %s", row->method, row->pattern, row->w,
                               row->h, row->filter);
    qsort(seconds, (size_t)cfg->reps, sizeof *seconds, cmp_double);
    double pixels = (double)row->w * row->h;
    row->seconds = seconds[cfg->reps / 2];
    row->seconds_min = seconds[0];
    row->seconds_max = seconds[cfg->reps - 1];
    row->samples = c.samples;
    row->expensive_pixels = c.expensive_pixels;
    row->spp = (double)c.samples / pixels;
    row->ns_per_pixel = row->seconds * 1e9 / pixels;
    row->ns_per_sample = c.samples ? row->seconds * 1e9 / (double)c.samples : 0.0;
    row->expensive_fraction = (double)c.expensive_pixels / pixels;
    row->ok = 1;
    if (cfg->images_dir && (st = write_images(cfg, stem, ref, img)))
        return st;
    return AA_OK;
}

int aa_run(const aa_run_config *cfg, aa_row **rows_out, size_t *n_out)
{
    int st = aa_run_check(cfg);
    if (st)
        return st;
    size_t total = cfg->npatterns * cfg->nsizes * cfg->nfilters * cfg->nmethods, n = 0;
    aa_row *rows = calloc(total, sizeof *rows);
    double *seconds = malloc((size_t)cfg->reps * sizeof *seconds);
    aa_scene *scene = NULL;
    aa_image ref = {0}, img = {0};
    aa_job job = {0};
    if (!rows || !seconds) {
        free(rows);
        free(seconds);
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", total);
    }
    if (cfg->images_dir && (st = aa_mkdirs(cfg->images_dir)))
        goto done;
    for (size_t ip = 0; ip < cfg->npatterns && !st; ip++) {
        aa_view view;
        memset(&view, 0, sizeof view);
        if ((st = aa_pattern_parse(cfg->patterns[ip], &view.pattern)) ||
            (st = aa_pattern_scene(&view.pattern, &scene)))
            break;
        for (size_t is = 0; is < cfg->nsizes && !st; is++) {
            aa_size_parse(cfg->sizes[is], &view.w, &view.h);
            if ((st = aa_image_alloc(&img, view.w, view.h, 3)))
                break;
            for (size_t jf = 0; jf < cfg->nfilters && !st; jf++) {
                char stem[1400], ps[512], fs[256];
                aa_filter_parse(cfg->filters[jf], &view.filter);
                view.t = cfg->t, view.vx = cfg->vx, view.vy = cfg->vy;
                aa_spec_slug(cfg->patterns[ip], ps, sizeof ps);
                aa_spec_slug(cfg->filters[jf], fs, sizeof fs);
                if (cfg->progress && cfg->progress(cfg->ctx, n, total, "reference")) {
                    st = aa_fail(AA_EFAIL, "interrupted");
                    break;
                }
                if ((st = aa_reference(&view, cfg->cache_dir, cfg->threads, &ref, NULL, NULL)) ||
                    (st = aa_job_init(&job, scene, view.w, view.h, cfg->t, cfg->vx, cfg->vy,
                                      &view.filter, cfg->seed, cfg->threads)))
                    break;
                snprintf(stem, sizeof stem, "%s-%dx%d-%s-reference", ps, view.w, view.h, fs);
                if (cfg->images_dir && (st = write_images(cfg, stem, NULL, &ref)))
                    break;
                for (size_t im = 0; im < cfg->nmethods && !st; im++) {
                    char what[1400], ms[512];
                    aa_row *row = &rows[n];
                    snprintf(what, sizeof what, "%s %dx%d %s %s", cfg->patterns[ip], view.w,
                             view.h, cfg->filters[jf], cfg->methods[im]);
                    if (cfg->progress && cfg->progress(cfg->ctx, n, total, what)) {
                        st = aa_fail(AA_EFAIL, "interrupted");
                        break;
                    }
                    row_names(row, cfg->patterns[ip], view.w, view.h, cfg->filters[jf],
                              cfg->methods[im], cfg);
                    aa_spec_slug(cfg->methods[im], ms, sizeof ms);
                    snprintf(stem, sizeof stem, "%s-%dx%d-%s-%s", ps, view.w, view.h, fs, ms);
                    if ((st = run_method(cfg, &job, &ref, &img, stem, row, seconds)))
                        break;
                    n++;
                    if (cfg->row_done && (st = cfg->row_done(cfg->ctx, rows, n)))
                        break;
                }
                aa_job_free(&job);
                aa_image_free(&ref);
            }
            aa_image_free(&img);
        }
        aa_scene_free(scene);
        scene = NULL;
    }
    if (!st && cfg->progress)
        cfg->progress(cfg->ctx, n, total, "done");
done:
    aa_job_free(&job);
    aa_image_free(&ref);
    aa_image_free(&img);
    aa_scene_free(scene);
    free(seconds);
    *rows_out = rows;
    *n_out = n;
    return st;
}
