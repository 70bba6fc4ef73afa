/*
 * report.c: results as CSV and JSON, and reading a CSV back (baselines).
 *
 * CSV follows RFC 4180: fields holding a comma, a quote or a line break are
 * quoted, quotes doubled (method specs contain commas).  Numbers are written
 * with %.9g; an infinite PSNR is "inf".  A refused or failed case has ok = 0,
 * empty measurements and its reason in `note`.  Both files are written
 * atomically.  Numbers are C-locale text ('.' as the decimal point), read
 * and written so whatever LC_NUMERIC the program has set.
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stddef.h>
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- a growing text buffer ---- */

typedef struct text {
    char *s;
    size_t n, cap;
    int failed;
} text;

static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    if (t->failed)
        return;
    for (;;) {
        va_start(ap, fmt);
        int m = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? t->cap - t->n : 0, fmt, ap);
        va_end(ap);
        if (m < 0) {
            t->failed = 1;
            return;
        }
        if (t->s && t->n + (size_t)m < t->cap) {
            t->n += (size_t)m;
            return;
        }
        size_t cap = t->cap ? t->cap : 4096;
        while (cap <= t->n + (size_t)m)
            cap *= 2;
        char *p = realloc(t->s, cap);
        if (!p) {
            t->failed = 1;
            return;
        }
        t->s = p;
        t->cap = cap;
    }
}

static int finish(text *t, const char *path)
{
    int st = t->failed ? aa_fail(AA_ENOMEM, "out of memory writing %s", path)
                       : aa_file_write_atomic(path, t->s, t->n);
    free(t->s);
    return st;
}

static void csv_field(text *t, const char *v)
{
    if (!strpbrk(v, ",\"\r\n")) {
        put(t, "%s", v);
        return;
    }
    put(t, "\"");
    for (const char *c = v; *c; c++)
        put(t, *c == '"' ? "\"\"" : "%c", *c);
    put(t, "\"");
}

static void num(text *t, double v)
{
    if (isinf(v))
        put(t, v > 0 ? "inf" : "-inf");
    else if (isnan(v))
        put(t, "nan");
    else
        put(t, "%.9g", v);
}

/* The columns, in order; each writes one value of a row. */
#define COLUMNS(X)                                                                               \
    X(pattern, csv_field(t, r->pattern))                                                         \
    X(size, put(t, "%dx%d", r->w, r->h))                                                         \
    X(filter, csv_field(t, r->filter))                                                           \
    X(method, csv_field(t, r->method))                                                           \
    X(canonical, csv_field(t, r->canonical))                                                     \
    X(spp, M(num(t, r->spp)))                                                                    \
    X(rmse, M(num(t, r->m.rmse)))                                                                \
    X(mae, M(num(t, r->m.mae)))                                                                  \
    X(max_err, M(num(t, r->m.max_err)))                                                          \
    X(max_i, M(put(t, "%d", r->m.max_at[0])))                                                    \
    X(max_j, M(put(t, "%d", r->m.max_at[1])))                                                    \
    X(psnr, M(num(t, r->m.psnr)))                                                                \
    X(rmse_enc, M(num(t, r->m.rmse_enc)))                                                        \
    X(mae_enc, M(num(t, r->m.mae_enc)))                                                          \
    X(max_err_enc, M(num(t, r->m.max_err_enc)))                                                  \
    X(psnr_enc, M(num(t, r->m.psnr_enc)))                                                        \
    X(alias_total, M(num(t, r->m.alias_total)))                                                  \
    X(alias_low, M(num(t, r->m.alias_low)))                                                      \
    X(alias_high, M(num(t, r->m.alias_high)))                                                    \
    X(ssim, M(num(t, r->m.ssim)))                                                                \
    X(render_seconds, M(num(t, r->seconds)))                                                     \
    X(render_seconds_min, M(num(t, r->seconds_min)))                                             \
    X(render_seconds_max, M(num(t, r->seconds_max)))                                             \
    X(ns_per_pixel, M(num(t, r->ns_per_pixel)))                                                  \
    X(ns_per_sample, M(num(t, r->ns_per_sample)))                                                \
    X(samples, M(put(t, "%llu", (unsigned long long)r->samples)))                                \
    X(expensive_pixels, M(put(t, "%llu", (unsigned long long)r->expensive_pixels)))              \
    X(expensive_fraction, M(num(t, r->expensive_fraction)))                                      \
    X(frames, T(put(t, "%d", r->tm.frames)))                                                    \
    X(window, T(put(t, "%d", r->tm.window)))                                                    \
    X(eye_rmse, T(num(t, r->tm.eye_rmse)))                                                      \
    X(flicker_mean, T(num(t, r->tm.flicker_mean)))                                              \
    X(flicker_max, T(num(t, r->tm.flicker_max)))                                                \
    X(conservation, T(num(t, r->tm.conservation)))                                              \
    X(popping, T(if (isfinite(r->tm.popping)) num(t, r->tm.popping)))                           \
    X(threads, put(t, "%d", r->threads))                                                         \
    X(reps, put(t, "%d", r->reps))                                                               \
    X(seed, put(t, "%llu", (unsigned long long)r->seed))                                         \
    X(time, num(t, r->t))                                                                        \
    X(vx, num(t, r->vx))                                                                         \
    X(vy, num(t, r->vy))                                                                         \
    X(ok, put(t, "%d", r->ok))                                                                   \
    X(note, csv_field(t, r->note))                                                               \
    TIMING_COLUMNS(X)

/* The timing by precision's columns (core.h, "timing and its statistics"),
 * after the older ones: a reader of older files finds them missing. */
#define TIMING_COLUMNS(X)                                                                        \
    X(render_seconds_mean, S(opt(t, r->timing.stats.mean)))                                      \
    X(render_seconds_sd, S(opt(t, r->timing.stats.sd)))                                          \
    X(render_seconds_mad, S(opt(t, r->timing.stats.mad)))                                        \
    X(render_seconds_ci_lo, S(opt(t, r->timing.stats.ci_lo)))                                    \
    X(render_seconds_ci_hi, S(opt(t, r->timing.stats.ci_hi)))                                    \
    X(ci_level, S(opt(t, r->timing.stats.ci_level)))                                             \
    X(target_ci, S(opt(t, r->timing.target_ci)))                                                 \
    X(outliers, S(put(t, "%zu", r->timing.stats.outliers)))                                      \
    X(cpu_seconds, S(opt(t, r->timing.cpu_median)))                                              \
    X(cpu_share, S(opt(t, r->timing.cpu_share)))                                                 \
    X(load_before, S(opt(t, r->timing.load_before)))                                             \
    X(load_after, S(opt(t, r->timing.load_after)))                                               \
    X(others_cores, S(opt(t, r->timing.others_cores)))                                           \
    X(steal, S(opt(t, r->timing.steal)))                                                         \
    X(noisy, M(put(t, "%d", r->timing.noisy != 0)))                                              \
    X(noise, M(noise_cell(t, r)))                                                                \
    X(seeds, M(put(t, "%d", r->seeds > 0 ? r->seeds : 1)))                                       \
    X(rmse_mean, M(if (r->seeds > 1) opt(t, r->rmse_mean)))                                      \
    X(rmse_ci_lo, M(if (r->seeds > 1) opt(t, r->rmse_ci_lo)))                                    \
    X(rmse_ci_hi, M(if (r->seeds > 1) opt(t, r->rmse_ci_hi)))                                    \
    X(times, S(times_cell(t, r)))                                                                \
    X(cpu_times, S(cpu_times_cell(t, r)))                                                        \
    X(case, if (r->case_index >= 0) put(t, "%ld", r->case_index))                                \
    X(host, csv_field(t, r->host))

/* timing columns only for rows that ran and were timed */
#define S(write)                                                                                 \
    do {                                                                                         \
        if (r->ok && r->timing.n > 0)                                                            \
            write;                                                                               \
    } while (0)

/* a number, or an empty cell when it is not finite (no interval, unknown) */
static void opt(text *t, double v)
{
    if (isfinite(v))
        put(t, "%.9g", v);
}

static void noise_cell(text *t, const aa_row *r)
{
    char why[128];
    aa_noisy_text(r->timing.noisy, why, sizeof why);
    put(t, "%s", why);
}

/* every render's time, separated by spaces */
static void times_cell(text *t, const aa_row *r)
{
    for (int k = 0; k < r->timing.n; k++)
        put(t, k ? " %.9g" : "%.9g", r->timing.wall[k]);
}

/* every render's CPU time, likewise */
static void cpu_times_cell(text *t, const aa_row *r)
{
    for (int k = 0; k < r->timing.n; k++)
        put(t, k ? " %.9g" : "%.9g", r->timing.cpu[k]);
}

/* temporal metrics only for animated rows that ran */
#define T(write)                                                                                 \
    do {                                                                                         \
        if (r->ok && r->temporal)                                                                \
            write;                                                                               \
    } while (0)

/* measurements only for rows that ran */
#define M(write)                                                                                 \
    do {                                                                                         \
        if (r->ok)                                                                               \
            write;                                                                               \
    } while (0)

static int write_csv(const char *path, const aa_row *rows, size_t n)
{
    text tb = {0}, *t = &tb;
    int first = 1;
#define HEAD(name, write) put(t, "%s%s", first ? "" : ",", #name), first = 0;
    COLUMNS(HEAD)
#undef HEAD
    put(t, "\n");
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = &rows[k];
        first = 1;
#define CELL(name, write)                                                                        \
    if (!first)                                                                                  \
        put(t, ",");                                                                             \
    first = 0;                                                                                   \
    write;
        COLUMNS(CELL)
#undef CELL
        put(t, "\n");
    }
    return finish(t, path);
}

/* A row's timing, its noise and its seeds as JSON members, each after
 * ", " (the tail of a results object; `render --stats` uses it too). */
static void member(FILE *f, const char *key, double v)
{
    fprintf(f, ", \"%s\": ", key);
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

char *aa_row_timing_json(const aa_row *r)
{
    char *json = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&json, &len);
    if (!f)
        return NULL;
    const aa_timing *t = &r->timing;
    if (r->ok && t->n > 0) {
        const aa_time_stats *s = &t->stats;
        fputs(", \"timing\": {\"times\": [", f);
        for (int k = 0; k < t->n; k++)
            fprintf(f, "%s%.9g", k ? ", " : "", t->wall[k]);
        fputs("], \"cpu_times\": [", f);
        for (int k = 0; k < t->n; k++)
            fprintf(f, "%s%.9g", k ? ", " : "", t->cpu[k]);
        fprintf(f, "], \"n\": %d, \"fixed\": %s", t->n, t->fixed ? "true" : "false");
        member(f, "median", s->median);
        member(f, "mean", s->mean);
        member(f, "sd", s->sd);
        member(f, "mad", s->mad);
        member(f, "min", s->min);
        member(f, "max", s->max);
        fputs(", \"ci\": [", f);
        if (isfinite(s->ci_lo))
            fprintf(f, "%.9g, %.9g]", s->ci_lo, s->ci_hi);
        else
            fputs("null, null]", f);
        member(f, "ci_level", s->ci_level);
        member(f, "ci_relative", t->ci_rel);
        member(f, "target_ci", t->target_ci);
        fprintf(f, ", \"target_met\": %s, \"outliers\": %zu", t->target_met ? "true" : "false",
                s->outliers);
        member(f, "cpu_median", t->cpu_median);
        member(f, "cpu_share", t->cpu_share);
        member(f, "load_before", t->load_before);
        member(f, "load_after", t->load_after);
        member(f, "others_cores", t->others_cores);
        member(f, "steal", t->steal);
        member(f, "elapsed", t->elapsed);
        fputs("}", f);
    }
    if (r->ok) {
        char why[128];
        aa_noisy_text(t->noisy, why, sizeof why);
        fprintf(f, ", \"noisy\": %s, \"noise\": \"%s\"", t->noisy ? "true" : "false", why);
        fprintf(f, ", \"seeds\": %d", r->seeds > 0 ? r->seeds : 1);
        if (r->seeds > 1) {
            member(f, "rmse_mean", r->rmse_mean);
            fputs(", \"rmse_ci\": [", f);
            if (isfinite(r->rmse_ci_lo))
                fprintf(f, "%.9g, %.9g]", r->rmse_ci_lo, r->rmse_ci_hi);
            else
                fputs("null, null]", f);
        }
    }
    if (fclose(f) != 0) {
        free(json);
        return NULL;
    }
    return json;
}

static void json_string(text *t, const char *v)
{
    put(t, "\"");
    for (const unsigned char *c = (const unsigned char *)v; *c; c++) {
        if (*c == '"' || *c == '\\')
            put(t, "\\%c", *c);
        else if (*c < 0x20)
            put(t, "\\u%04x", *c);
        else
            put(t, "%c", *c);
    }
    put(t, "\"");
}

static void json_num(text *t, double v)
{
    if (isfinite(v))
        put(t, "%.9g", v);
    else
        put(t, "null");
}

static int write_json(const char *path, const aa_context *ctx, const aa_row *rows, size_t n)
{
    text tb = {0}, *t = &tb;
    char *cj = ctx ? aa_context_json(ctx, 2) : NULL;
    if (ctx && !cj)
        t->failed = 1;
    put(t, "{\n  \"context\": %s,\n  \"results\": [\n", cj ? cj : "null");
    free(cj);
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = &rows[k];
        put(t, "  {\"pattern\": ");
        json_string(t, r->pattern);
        put(t, ", \"size\": \"%dx%d\", \"filter\": ", r->w, r->h);
        json_string(t, r->filter);
        put(t, ", \"method\": ");
        json_string(t, r->method);
        put(t, ", \"canonical\": ");
        json_string(t, r->canonical);
        put(t, ", \"ok\": %s", r->ok ? "true" : "false");
        if (r->ok) {
            const struct {
                const char *key;
                double v;
            } f[] = {{"spp", r->spp},
                     {"rmse", r->m.rmse},
                     {"mae", r->m.mae},
                     {"max_err", r->m.max_err},
                     {"psnr", r->m.psnr},
                     {"rmse_enc", r->m.rmse_enc},
                     {"mae_enc", r->m.mae_enc},
                     {"max_err_enc", r->m.max_err_enc},
                     {"psnr_enc", r->m.psnr_enc},
                     {"alias_total", r->m.alias_total},
                     {"alias_low", r->m.alias_low},
                     {"alias_high", r->m.alias_high},
                     {"ssim", r->m.ssim},
                     {"render_seconds", r->seconds},
                     {"render_seconds_min", r->seconds_min},
                     {"render_seconds_max", r->seconds_max},
                     {"ns_per_pixel", r->ns_per_pixel},
                     {"ns_per_sample", r->ns_per_sample},
                     {"expensive_fraction", r->expensive_fraction}};
            for (size_t q = 0; q < sizeof f / sizeof *f; q++) {
                put(t, ", \"%s\": ", f[q].key);
                json_num(t, f[q].v);
            }
            put(t, ", \"max_at\": [%d, %d, %d], \"samples\": %llu, \"expensive_pixels\": %llu",
                r->m.max_at[0], r->m.max_at[1], r->m.max_at[2], (unsigned long long)r->samples,
                (unsigned long long)r->expensive_pixels);
            if (r->temporal) {
                put(t, ", \"temporal\": {\"frames\": %d, \"window\": %d", r->tm.frames,
                    r->tm.window);
                const struct {
                    const char *key;
                    double v;
                } g[] = {{"eye_rmse", r->tm.eye_rmse},
                         {"flicker_mean", r->tm.flicker_mean},
                         {"flicker_max", r->tm.flicker_max},
                         {"conservation", r->tm.conservation},
                         {"popping", r->tm.popping}};
                for (size_t q = 0; q < sizeof g / sizeof *g; q++) {
                    put(t, ", \"%s\": ", g[q].key);
                    json_num(t, g[q].v);
                }
                put(t, "}");
            }
        }
        put(t, ", \"threads\": %d, \"reps\": %d, \"seed\": %llu, \"time\": ", r->threads, r->reps,
            (unsigned long long)r->seed);
        json_num(t, r->t);
        put(t, ", \"motion\": [");
        json_num(t, r->vx);
        put(t, ", ");
        json_num(t, r->vy);
        put(t, "], \"note\": ");
        json_string(t, r->note);
        char *timing = aa_row_timing_json(r);
        if (!timing)
            t->failed = 1;
        put(t, "%s}%s\n", timing ? timing : "", k + 1 < n ? "," : "");
        free(timing);
    }
    put(t, "]\n}\n");
    return finish(t, path);
}

int aa_rows_write_csv(const char *path, const aa_row *rows, size_t n)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, path);
    if (st)
        return st;
    st = write_csv(path, rows, n);
    aa__c_numbers_end(&numbers);
    return st;
}

int aa_rows_write_json(const char *path, const aa_row *rows, size_t n)
{
    return aa_results_write_json(path, NULL, rows, n);
}

int aa_results_write_json(const char *path, const aa_context *ctx, const aa_row *rows, size_t n)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, path);
    if (st)
        return st;
    st = write_json(path, ctx, rows, n);
    aa__c_numbers_end(&numbers);
    return st;
}

/* A results CSV read back (a baseline above all) is checked as strictly as
 * a spec: the regression gate must never pass on a row it cannot trust.
 * The header names known columns, each once, the required ones present; a
 * UTF-8 byte-order mark before it is skipped.  Every row has as many fields
 * as the header; numbers are plain C-locale decimals, finite and within
 * what the column can hold ("inf" only for a PSNR); sizes are WxH with
 * nothing after; patterns and filters parse as specs; a row with ok = 1
 * has every measurement and a row with ok = 0 none, but its reason in the
 * note.  Anything else is refused (AA_EINVAL) naming the file, the line
 * and the column; a file that has no header at all is not a results file
 * (AA_EIO). */

#define CSV_MAX_BYTES ((size_t)256 << 20)
#define CSV_MAX_FIELDS 256

/* the columns the writer writes: a header may name only these */
#define NAME(name, write) #name,
static const char *const csv_known[] = {COLUMNS(NAME) NULL};
#undef NAME

enum { K_TEXT, K_SPEC_PATTERN, K_SPEC_FILTER, K_SIZE, K_REAL, K_COUNT, K_INT, K_SEED, K_OK };
/* when a column holds a value: always; in rows with ok = 1; in rows with
 * ok = 1 that are animated (temporal metrics), where it may also be empty
 * (popping: only `dots` has it); text that may be empty */
enum { G_ALWAYS, G_MEASURE, G_TEMPORAL, G_TEMPORAL_OPTIONAL, G_OPTIONAL };

#define MEMBER_SIZE(m) sizeof(((aa_row *)0)->m)
typedef struct csv_column {
    const char *name;
    int kind, group, required;
    size_t off, size;
    double lo, hi; /* K_REAL, K_INT: the range; hi = INFINITY lets "inf" in */
} csv_column;

#define TEXT(n, g, req) {#n, K_TEXT, g, req, offsetof(aa_row, n), MEMBER_SIZE(n), 0, 0}
#define REAL(n, m, g, req, lo, hi) {#n, K_REAL, g, req, offsetof(aa_row, m), 0, lo, hi}
#define INT(n, m, g, req, lo, hi) {#n, K_INT, g, req, offsetof(aa_row, m), 0, lo, hi}
#define COUNT(n, m) {#n, K_COUNT, G_MEASURE, 0, offsetof(aa_row, m), 0, 0, 0}

static const csv_column csv_columns[] = {
    {"pattern", K_SPEC_PATTERN, G_ALWAYS, 1, offsetof(aa_row, pattern), MEMBER_SIZE(pattern), 0,
     0},
    {"size", K_SIZE, G_ALWAYS, 1, 0, 0, 0, 0},
    {"filter", K_SPEC_FILTER, G_ALWAYS, 1, offsetof(aa_row, filter), MEMBER_SIZE(filter), 0, 0},
    TEXT(method, G_ALWAYS, 1),
    TEXT(canonical, G_OPTIONAL, 0),
    REAL(spp, spp, G_MEASURE, 0, 0, DBL_MAX),
    REAL(rmse, m.rmse, G_MEASURE, 1, 0, 1),
    REAL(mae, m.mae, G_MEASURE, 0, 0, 1),
    REAL(max_err, m.max_err, G_MEASURE, 1, 0, 1),
    INT(max_i, m.max_at[0], G_MEASURE, 0, 0, AA_MAX_SIDE - 1),
    INT(max_j, m.max_at[1], G_MEASURE, 0, 0, AA_MAX_SIDE - 1),
    REAL(psnr, m.psnr, G_MEASURE, 0, 0, INFINITY),
    REAL(rmse_enc, m.rmse_enc, G_MEASURE, 0, 0, 1),
    REAL(mae_enc, m.mae_enc, G_MEASURE, 0, 0, 1),
    REAL(max_err_enc, m.max_err_enc, G_MEASURE, 0, 0, 1),
    REAL(psnr_enc, m.psnr_enc, G_MEASURE, 0, 0, INFINITY),
    REAL(alias_total, m.alias_total, G_MEASURE, 0, 0, DBL_MAX),
    REAL(alias_low, m.alias_low, G_MEASURE, 0, 0, DBL_MAX),
    REAL(alias_high, m.alias_high, G_MEASURE, 0, 0, DBL_MAX),
    REAL(ssim, m.ssim, G_MEASURE, 0, -1, 1),
    REAL(render_seconds, seconds, G_MEASURE, 0, 0, DBL_MAX),
    REAL(render_seconds_min, seconds_min, G_MEASURE, 0, 0, DBL_MAX),
    REAL(render_seconds_max, seconds_max, G_MEASURE, 0, 0, DBL_MAX),
    REAL(ns_per_pixel, ns_per_pixel, G_MEASURE, 0, 0, DBL_MAX),
    REAL(ns_per_sample, ns_per_sample, G_MEASURE, 0, 0, DBL_MAX),
    COUNT(samples, samples),
    COUNT(expensive_pixels, expensive_pixels),
    REAL(expensive_fraction, expensive_fraction, G_MEASURE, 0, 0, 1),
    INT(frames, tm.frames, G_TEMPORAL, 0, 2, AA_TEMPORAL_MAX_FRAMES),
    INT(window, tm.window, G_TEMPORAL, 0, 1, AA_TEMPORAL_MAX_FRAMES),
    REAL(eye_rmse, tm.eye_rmse, G_TEMPORAL, 0, 0, 1),
    REAL(flicker_mean, tm.flicker_mean, G_TEMPORAL, 0, 0, 1),
    REAL(flicker_max, tm.flicker_max, G_TEMPORAL, 0, 0, 1),
    REAL(conservation, tm.conservation, G_TEMPORAL, 0, 0, DBL_MAX),
    REAL(popping, tm.popping, G_TEMPORAL_OPTIONAL, 0, 0, 1),
    INT(threads, threads, G_ALWAYS, 0, 1, AA_MAX_THREADS),
    INT(reps, reps, G_ALWAYS, 0, 1, 1000),
    {"seed", K_SEED, G_ALWAYS, 1, offsetof(aa_row, seed), 0, 0, 0},
    REAL(time, t, G_ALWAYS, 1, -1e9, 1e9),
    REAL(vx, vx, G_ALWAYS, 1, -1e6, 1e6),
    REAL(vy, vy, G_ALWAYS, 1, -1e6, 1e6),
    {"ok", K_OK, G_ALWAYS, 1, offsetof(aa_row, ok), 0, 0, 0},
    TEXT(note, G_OPTIONAL, 0),
};
#undef TEXT
#undef REAL
#undef INT
#undef COUNT
#define NCOLUMNS (sizeof csv_columns / sizeof *csv_columns)

static double field_num(const char *s, int *bad)
{
    char *end;
    if (!*s)
        return NAN;
    errno = 0;
    double v = strtod(s, &end);
    if (*end)
        *bad = 1;
    return v;
}

/* "noisy" read as 1: a reason is taken from "noise", else "ci" */
#define NOISY_MARKED (1u << 31)

/* The timing columns (absent from older files: a row then has no times,
 * timing.n = 0, and one seed).  Returns non-zero if a cell is malformed. */
static int read_timing_cell(aa_row *row, const char *h, const char *v)
{
    int bad = 0;
    aa_timing *t = &row->timing;
    if (!strcmp(h, "cpu_times")) {
        char *end;
        int n = 0;
        for (const char *p = v; *p;) {
            if (n == AA_TIMING_MAX_REPS)
                return 1;
            errno = 0;
            double x = strtod(p, &end);
            if (end == p || errno || !(x >= 0))
                return 1;
            t->cpu[n++] = x;
            p = end;
            while (*p == ' ')
                p++;
        }
    }
    if (!strcmp(h, "case") && *v) {
        char *end;
        errno = 0;
        long k = strtol(v, &end, 10);
        if (*end || errno || k < 0 || !(*v >= '0' && *v <= '9'))
            return 1;
        row->case_index = k;
    }
    if (!strcmp(h, "host")) {
        if (strlen(v) >= sizeof row->host)
            return 1;
        snprintf(row->host, sizeof row->host, "%s", v);
    }
    if (!strcmp(h, "times")) {
        char *end;
        t->n = 0;
        for (const char *p = v; *p;) {
            if (t->n == AA_TIMING_MAX_REPS)
                return 1;
            errno = 0;
            double x = strtod(p, &end);
            if (end == p || errno || !(x >= 0))
                return 1;
            t->wall[t->n++] = x;
            p = end;
            while (*p == ' ')
                p++;
        }
    }
    if (!strcmp(h, "noise"))
        t->noisy |= aa_noisy_parse(v);
    if (!strcmp(h, "noisy") && !strcmp(v, "1"))
        t->noisy |= NOISY_MARKED;
    if (!strcmp(h, "seeds") && *v)
        row->seeds = atoi(v);
#define TNUM(name, dst) if (!strcmp(h, name) && *v) dst = field_num(v, &bad);
    TNUM("target_ci", t->target_ci) TNUM("cpu_seconds", t->cpu_median)
    TNUM("cpu_share", t->cpu_share) TNUM("load_before", t->load_before)
    TNUM("load_after", t->load_after) TNUM("others_cores", t->others_cores)
    TNUM("steal", t->steal) TNUM("rmse_mean", row->rmse_mean)
    TNUM("rmse_ci_lo", row->rmse_ci_lo) TNUM("rmse_ci_hi", row->rmse_ci_hi)
#undef TNUM
    return bad;
}

/* A row read back: its statistics from its times (when the file has them). */
static void settle_timing(aa_row *row)
{
    aa_timing *t = &row->timing;
    if (t->noisy & NOISY_MARKED) {
        t->noisy &= ~NOISY_MARKED;
        if (!t->noisy)
            t->noisy = AA_NOISY_CI; /* marked, reason not given */
    }
    if (row->seeds < 1)
        row->seeds = 1;
    if (t->n == 0)
        return;
    aa_time_stats_compute(t->wall, (size_t)t->n, &t->stats);
    t->ci_rel = isfinite(t->stats.ci_lo) && t->stats.median > 0
                    ? (t->stats.ci_hi - t->stats.ci_lo) / 2 / t->stats.median
                    : NAN;
    t->target_met = t->ci_rel <= t->target_ci;
    t->threads = row->threads;
}

/* The parser: records of fields over the whole text, each field with the
 * line it starts on. */
typedef struct csv {
    const char *name, *s;
    size_t n, at, line;
    char *buf; /* the record's fields, each NUL-terminated */
    size_t blen, bcap;
    size_t off[CSV_MAX_FIELDS], fline[CSV_MAX_FIELDS];
    int nf;
    const char *const *head; /* the header's names, once read (for messages) */
} csv;

static int csv_put(csv *p, char c)
{
    if (p->blen == p->bcap) {
        size_t cap = p->bcap ? 2 * p->bcap : 4096;
        char *b = realloc(p->buf, cap);
        if (!b)
            return aa_fail(AA_ENOMEM, "out of memory reading %s", p->name);
        p->buf = b, p->bcap = cap;
    }
    p->buf[p->blen++] = c;
    return AA_OK;
}

/* "FILE:LINE: column C (NAME): " before a message about field f. */
static int csv_fail(const csv *p, int f, const char *fmt, ...) AA_PRINTF(3, 4);
static int csv_fail(const csv *p, int f, const char *fmt, ...)
{
    char why[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    if (f < 0)
        return aa_fail(AA_EINVAL, "%s:%zu: %s", aa_echo(p->name), p->line, why);
    if (p->head && p->head[f])
        return aa_fail(AA_EINVAL, "%s:%zu: column %d (%s): %s", aa_echo(p->name), p->fline[f],
                       f + 1, aa_echo(p->head[f]), why);
    return aa_fail(AA_EINVAL, "%s:%zu: column %d: %s", aa_echo(p->name), p->fline[f], f + 1, why);
}

/* The next record into p->buf; *got = 0 at the end.  Blank lines are
 * skipped. */
static int csv_record(csv *p, int *got)
{
    int st;
    *got = 0;
    p->nf = 0;
    p->blen = 0;
    while (p->at < p->n && (p->s[p->at] == '\n' ||
                            (p->s[p->at] == '\r' && p->at + 1 < p->n && p->s[p->at + 1] == '\n'))) {
        p->at += p->s[p->at] == '\r' ? 2 : 1;
        p->line++;
    }
    if (p->at >= p->n)
        return AA_OK;
    for (;;) {
        if (p->nf == CSV_MAX_FIELDS)
            return csv_fail(p, -1, "more than %d fields", CSV_MAX_FIELDS);
        int f = p->nf++;
        p->off[f] = p->blen;
        p->fline[f] = p->line;
        if (p->at < p->n && p->s[p->at] == '"') {
            p->at++;
            for (;;) {
                if (p->at >= p->n)
                    return csv_fail(p, f, "the quote opened here is never closed");
                char c = p->s[p->at++];
                if (c == '"') {
                    if (p->at < p->n && p->s[p->at] == '"') {
                        p->at++;
                    } else {
                        break;
                    }
                } else if (c == '\0') {
                    return csv_fail(p, f, "a NUL byte");
                } else if (c == '\n') {
                    p->line++;
                }
                if ((st = csv_put(p, c)))
                    return st;
            }
            if (p->at < p->n && p->s[p->at] != ',' && p->s[p->at] != '\n' &&
                !(p->s[p->at] == '\r' && p->at + 1 < p->n && p->s[p->at + 1] == '\n'))
                return csv_fail(p, f, "text after the closing quote");
        } else {
            while (p->at < p->n && p->s[p->at] != ',' && p->s[p->at] != '\n') {
                char c = p->s[p->at];
                if (c == '"')
                    return csv_fail(p, f, "a quote inside a field that does not start with one");
                if (c == '\0')
                    return csv_fail(p, f, "a NUL byte");
                if (c == '\r') {
                    if (p->at + 1 < p->n && p->s[p->at + 1] == '\n')
                        break;
                    return csv_fail(p, f, "a carriage return inside a field");
                }
                if ((st = csv_put(p, c)))
                    return st;
                p->at++;
            }
        }
        if ((st = csv_put(p, '\0')))
            return st;
        if (p->at < p->n && p->s[p->at] == ',') {
            p->at++;
            continue;
        }
        /* the end of the record: a line break or the end of the text */
        if (p->at < p->n) {
            p->at += p->s[p->at] == '\r' ? 2 : 1;
            p->line++;
        }
        *got = 1;
        return AA_OK;
    }
}

static const char *field_text(const csv *p, int f)
{
    return p->buf + p->off[f];
}

/* A plain decimal: [-]digits[.digits][e[+-]digits] (or .digits). */
static int plain_decimal(const char *v)
{
    const char *c = v;
    int digits = 0;
    if (*c == '-')
        c++;
    while (*c >= '0' && *c <= '9')
        c++, digits++;
    if (*c == '.')
        for (c++; *c >= '0' && *c <= '9'; c++)
            digits++;
    if (!digits)
        return 0;
    if (*c == 'e' || *c == 'E') {
        c++;
        if (*c == '+' || *c == '-')
            c++;
        if (!(*c >= '0' && *c <= '9'))
            return 0;
        while (*c >= '0' && *c <= '9')
            c++;
    }
    return *c == '\0';
}

/* Digits only, at most UINT64_MAX. */
static int plain_count(const char *v, uint64_t *out)
{
    uint64_t x = 0;
    if (!*v)
        return 0;
    for (const char *c = v; *c; c++) {
        if (*c < '0' || *c > '9')
            return 0;
        unsigned d = (unsigned)(*c - '0');
        if (x > (UINT64_MAX - d) / 10)
            return 0;
        x = 10 * x + d;
    }
    *out = x;
    return 1;
}

/* One field into the row. */
static int csv_value(const csv *p, int f, const csv_column *col, const char *v, aa_row *row)
{
    char *dst = (char *)row + col->off;
    switch (col->kind) {
    case K_TEXT:
    case K_SPEC_PATTERN:
    case K_SPEC_FILTER: {
        size_t len = strlen(v);
        if (len >= col->size)
            return csv_fail(p, f, "%zu characters, more than the %zu a %s can have", len,
                            col->size - 1, col->name);
        memcpy(dst, v, len + 1);
        if (col->kind == K_SPEC_PATTERN || col->kind == K_SPEC_FILTER) {
            aa_spec spec;
            aa_filter filter;
            int st = col->kind == K_SPEC_PATTERN ? aa_pattern_parse(v, &spec)
                                                 : aa_filter_parse(v, &filter);
            if (st) {
                char why[1024];
                snprintf(why, sizeof why, "%s", aa_last_error());
                return csv_fail(p, f, "%s", why);
            }
        }
        return AA_OK;
    }
    case K_SIZE:
        if (aa_size_parse(v, &row->w, &row->h)) {
            char why[1024];
            snprintf(why, sizeof why, "%s", aa_last_error());
            return csv_fail(p, f, "%s", why);
        }
        return AA_OK;
    case K_REAL: {
        double x;
        if (col->hi == INFINITY && !strcmp(v, "inf")) {
            x = INFINITY;
        } else {
            char *end;
            if (!plain_decimal(v))
                return csv_fail(p, f, "\"%s\" is not a number", aa_echo(v));
            x = strtod(v, &end);
            if (!isfinite(x))
                return csv_fail(p, f, "%s is not a finite number", aa_echo(v));
        }
        if (!(x >= col->lo && x <= col->hi))
            return csv_fail(p, f, "%s is out of range (%g to %g)", aa_echo(v), col->lo, col->hi);
        memcpy(dst, &x, sizeof x);
        return AA_OK;
    }
    case K_INT: {
        uint64_t x;
        if (!plain_count(v, &x))
            return csv_fail(p, f, "\"%s\" is not a whole number", aa_echo(v));
        if ((double)x < col->lo || (double)x > col->hi)
            return csv_fail(p, f, "%s is out of range (%g to %g)", aa_echo(v), col->lo, col->hi);
        int i = (int)x;
        memcpy(dst, &i, sizeof i);
        return AA_OK;
    }
    case K_COUNT:
    case K_SEED: {
        uint64_t x;
        if (!plain_count(v, &x))
            return csv_fail(p, f, "\"%s\" is not a whole number from 0 to 2^64-1", aa_echo(v));
        memcpy(dst, &x, sizeof x);
        return AA_OK;
    }
    case K_OK:
        if (strcmp(v, "0") && strcmp(v, "1"))
            return csv_fail(p, f, "\"%s\" is neither 0 nor 1", aa_echo(v));
        row->ok = v[0] == '1';
        return AA_OK;
    }
    return aa_fail(AA_EFAIL, "csv_value: unknown kind");
}

static const csv_column *column_named(const char *name)
{
    for (size_t k = 0; k < NCOLUMNS; k++)
        if (!strcmp(csv_columns[k].name, name))
            return &csv_columns[k];
    return NULL;
}

/* What a single field cannot show: a reason for a row that did not run,
 * a pixel inside the image, a window within the frames.  (Errors are not
 * held to each other: a baseline tightened by hand, an rmse lowered below
 * the mae, is still a baseline.) */
static int csv_row_check(const csv *p, const int *at, aa_row *row)
{
#define AT(name) (column_named(name) ? at[column_named(name) - csv_columns] : -1)
    if (!row->ok) {
        int f = AT("note");
        if (f < 0 || !*row->note)
            return csv_fail(p, f >= 0 ? f : AT("ok"),
                            "a row with ok=0 (refused or failed) must give its reason in the "
                            "note");
        return AA_OK;
    }
    if (row->m.max_at[0] >= row->w || row->m.max_at[1] >= row->h)
        return csv_fail(p, AT(row->m.max_at[0] >= row->w ? "max_i" : "max_j"),
                        "pixel (%d, %d) of the largest error is outside the %dx%d image",
                        row->m.max_at[0], row->m.max_at[1], row->w, row->h);
    if (row->temporal && row->tm.window > row->tm.frames)
        return csv_fail(p, AT("window"), "a window of %d frames in %d frames", row->tm.window,
                        row->tm.frames);
    return AA_OK;
#undef AT
}

static int parse_csv(const char *name, const char *data, size_t len, aa_row **rows_out,
                     size_t *n_out)
{
    csv p = {.name = name, .s = data, .n = len, .line = 1};
    const char *head[CSV_MAX_FIELDS + 1] = {0};
    int at[NCOLUMNS], nh, got, st;
    aa_row *rows = NULL;
    size_t n = 0, cap = 0;
    char *names = NULL;
    for (size_t k = 0; k < NCOLUMNS; k++)
        at[k] = -1;
    if (len >= 3 && !memcmp(data, "\xef\xbb\xbf", 3))
        p.at = 3; /* a UTF-8 byte-order mark */
    if ((st = csv_record(&p, &got)))
        goto done;
    if (!got) {
        st = aa_fail(AA_EIO, "%s: no CSV header: the file is empty", aa_echo(name));
        goto done;
    }
    nh = p.nf;
    if (!(names = malloc(p.blen))) {
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(name));
        goto done;
    }
    memcpy(names, p.buf, p.blen);
    for (int f = 0; f < nh; f++)
        head[f] = names + p.off[f];
    {
        int any = 0;
        for (int f = 0; f < nh; f++)
            any |= !strcmp(head[f], "pattern");
        if (!any) {
            st = aa_fail(AA_EIO,
                         "%s: no CSV header: its first line does not name the columns of a "
                         "results file (pattern,size,filter,method,...)",
                         aa_echo(name));
            goto done;
        }
    }
    p.head = head;
    for (int f = 0; f < nh; f++) {
        int known = 0;
        for (size_t k = 0; csv_known[k]; k++)
            known |= !strcmp(csv_known[k], head[f]);
        if (!known) {
            st = csv_fail(&p, f, "unknown column \"%s\"", aa_echo(head[f]));
            goto done;
        }
        for (int g = 0; g < f; g++)
            if (!strcmp(head[g], head[f])) {
                st = csv_fail(&p, f, "column \"%s\" given twice (columns %d and %d)", head[f],
                              g + 1, f + 1);
                goto done;
            }
        const csv_column *col = column_named(head[f]);
        if (col)
            at[col - csv_columns] = f;
    }
    for (size_t k = 0; k < NCOLUMNS; k++)
        if (csv_columns[k].required && at[k] < 0) {
            st = aa_fail(AA_EINVAL, "%s:%zu: no column \"%s\", which a results file must have",
                         aa_echo(name), p.fline[0], csv_columns[k].name);
            goto done;
        }
    for (;;) {
        if ((st = csv_record(&p, &got)) || !got)
            break;
        if (p.nf != nh) {
            st = aa_fail(AA_EINVAL, "%s:%zu: %d field%s, the header has %d", aa_echo(name),
                         p.fline[0], p.nf, p.nf == 1 ? "" : "s", nh);
            break;
        }
        if (n == cap) {
            size_t c2 = cap ? 2 * cap : 64;
            aa_row *r2 = realloc(rows, c2 * sizeof *r2);
            if (!r2) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(name));
                break;
            }
            rows = r2, cap = c2;
        }
        aa_row *row = &rows[n];
        memset(row, 0, sizeof *row);
        row->tm.popping = NAN;
        row->case_index = -1;
        /* ok first: which columns must hold a value depends on it; then
         * whether the row is animated */
        const int f_ok = at[column_named("ok") - csv_columns];
        if ((st = csv_value(&p, f_ok, column_named("ok"), field_text(&p, f_ok), row)))
            break;
        const csv_column *eye = column_named("eye_rmse");
        row->temporal = row->ok && at[eye - csv_columns] >= 0 &&
                        *field_text(&p, at[eye - csv_columns]);
        for (size_t k = 0; k < NCOLUMNS && !st; k++) {
            const csv_column *col = &csv_columns[k];
            int f = at[k];
            if (f < 0 || col->kind == K_OK)
                continue;
            const char *v = field_text(&p, f);
            /* 1: must hold a value, 0: must be empty, -1: either */
            int want = col->group == G_ALWAYS              ? 1
                       : col->group == G_MEASURE           ? row->ok
                       : col->group == G_TEMPORAL          ? row->temporal
                       : col->group == G_TEMPORAL_OPTIONAL ? (row->temporal ? -1 : 0)
                                                           : -1;
            if (want == 1 && !*v)
                st = csv_fail(&p, f, "empty, and %s", col->group == G_ALWAYS
                                                          ? "every row needs it"
                                                      : col->group == G_MEASURE
                                                          ? "a row with ok=1 needs it"
                                                          : "an animated row needs it");
            else if (want == 0 && *v)
                st = csv_fail(&p, f, "\"%s\" where %s", aa_echo(v),
                              !row->ok
                                  ? "a row with ok=0 (refused or failed) has no measurements"
                                  : "a row without eye_rmse has no temporal metrics");
            else if (*v || col->kind == K_TEXT)
                st = csv_value(&p, f, col, v, row);
        }
        /* the timing columns (older files have none): read as they are */
        for (int f = 0; f < nh && !st; f++)
            if (!column_named(head[f]) && read_timing_cell(row, head[f], field_text(&p, f)))
                st = csv_fail(&p, f, "malformed timing value \"%s\"", aa_echo(field_text(&p, f)));
        if (!st)
            settle_timing(row);
        if (st || (st = csv_row_check(&p, at, row)))
            break;
        n++;
    }
done:
    free(p.buf);
    free(names);
    if (st) {
        free(rows);
        rows = NULL;
        n = 0;
    }
    *rows_out = rows;
    *n_out = n;
    return st;
}

int aa_rows_parse_csv(const char *name, const char *data, size_t len, aa_row **rows_out,
                      size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, name);
    if (st)
        return st;
    st = parse_csv(name, data, len, rows_out, n_out);
    aa__c_numbers_end(&numbers);
    return st;
}

int aa_rows_read_csv(const char *path, aa_row **rows_out, size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return aa_fail(AA_EIO, "%s: cannot open: %s", aa_echo(path), strerror(errno));
    char *data = NULL;
    size_t n = 0, cap = 0;
    int st = AA_OK;
    for (;;) {
        if (n == cap) {
            if (cap >= CSV_MAX_BYTES) {
                st = aa_fail(AA_EINVAL, "%s: larger than %zu MB: not a results file",
                             aa_echo(path), CSV_MAX_BYTES >> 20);
                break;
            }
            size_t c2 = cap ? 2 * cap : 65536;
            char *d2 = realloc(data, c2);
            if (!d2) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(path));
                break;
            }
            data = d2, cap = c2;
        }
        size_t got = fread(data + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f))
                st = aa_fail(AA_EIO, "%s: cannot read: %s", aa_echo(path), strerror(errno));
            break;
        }
    }
    fclose(f);
    if (!st)
        st = aa_rows_parse_csv(path, data ? data : "", n, rows_out, n_out);
    free(data);
    return st;
}
