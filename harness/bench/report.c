/*
 * report.c: results as CSV and JSON, and reading a CSV back (baselines).
 *
 * CSV follows RFC 4180: fields holding a comma, a quote or a line break are
 * quoted, quotes doubled (method specs contain commas).  Numbers are written
 * with %.9g; an infinite PSNR is "inf".  A refused or failed case has ok = 0,
 * empty measurements and its reason in `note`.  Both files are written
 * atomically.  Numbers are C-locale text ('.' as the decimal point), read
 * and written so whatever LC_NUMERIC the program has set.
 *
 * The CSV's columns are one table, `columns`: each column's name, how its
 * cell is written and read, and when a row holds a value in it; the writer
 * and the reader both walk it, so they cannot disagree on a column.
 * results.json is built with cJSON, a row a line.
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <cJSON.h>

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

/* a number, or an empty cell when it is not finite (no interval, unknown) */
static void opt(text *t, double v)
{
    if (isfinite(v))
        put(t, "%.9g", v);
}

/* ---- the columns: one table for the writer and the reader ---- */

/* How a cell is written and read: text (a pattern and a filter must
 * parse as specs), WxH, a real number within [lo, hi] (hi = INFINITY
 * lets "inf" in), a count or a seed (0 to 2^64-1), an int within [lo, hi],
 * 0 or 1; or by the column's own functions (the timing's columns: read
 * as they are, never refused for being empty or present). */
enum { K_TEXT, K_SPEC_PATTERN, K_SPEC_FILTER, K_SIZE, K_REAL, K_COUNT, K_INT, K_SEED, K_OK, K_OWN };
/* When a column holds a value: always; in rows with ok = 1; in rows with
 * ok = 1 that are animated (temporal metrics), where it may also be empty
 * (popping: only `dots` has it); text that may be empty; in rows with
 * ok = 1 that were timed; in rows with ok = 1, where it may be empty (no
 * value: the edge RMSE of a view without edges, older files). */
enum { G_ALWAYS, G_MEASURE, G_TEMPORAL, G_TEMPORAL_OPTIONAL, G_OPTIONAL, G_TIMED,
       G_MEASURE_OPTIONAL };

typedef struct column column;
struct column {
    const char *name;
    int kind, group, required; /* required: a results file must have it */
    size_t off, size;          /* where in aa_row; the size of a text */
    double lo, hi;
    /* K_OWN: write the cell; read it back (NULL: not read, the row's
     * statistics are recomputed from its times), non-zero if malformed */
    void (*write)(text *t, const aa_row *r, const column *c);
    int (*read)(aa_row *row, const column *c, const char *v);
};

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

static double *real_at(aa_row *row, const column *c)
{
    return (double *)(void *)((char *)row + c->off);
}

static double real_of(const aa_row *r, const column *c)
{
    double v;
    memcpy(&v, (const char *)r + c->off, sizeof v);
    return v;
}

/* "noisy" read as 1: a reason is taken from "noise", else "ci" */
#define NOISY_MARKED (1u << 31)

static void opt_cell(text *t, const aa_row *r, const column *c)
{
    opt(t, real_of(r, c));
}

/* a number of several seeds' statistics (rmse_mean, rmse_ci_*) */
static void seeds_real_cell(text *t, const aa_row *r, const column *c)
{
    if (r->seeds > 1)
        opt(t, real_of(r, c));
}

static int read_real(aa_row *row, const column *c, const char *v)
{
    int bad = 0;
    if (*v)
        *real_at(row, c) = field_num(v, &bad);
    return bad;
}

static void outliers_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    put(t, "%zu", r->timing.stats.outliers);
}

static void noisy_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    put(t, "%d", r->timing.noisy != 0);
}

static int read_noisy(aa_row *row, const column *c, const char *v)
{
    (void)c;
    if (!strcmp(v, "1"))
        row->timing.noisy |= NOISY_MARKED;
    return 0;
}

static void noise_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    char why[128];
    aa_noisy_text(r->timing.noisy, why, sizeof why);
    put(t, "%s", why);
}

static int read_noise(aa_row *row, const column *c, const char *v)
{
    (void)c;
    row->timing.noisy |= aa_noisy_parse(v);
    return 0;
}

static void seeds_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    put(t, "%d", r->seeds > 0 ? r->seeds : 1);
}

static int read_seeds(aa_row *row, const column *c, const char *v)
{
    (void)c;
    if (*v)
        row->seeds = atoi(v);
    return 0;
}

/* every render's wall or CPU time, separated by spaces */
static void times_cell(text *t, const aa_row *r, const column *c)
{
    const double *v = !strcmp(c->name, "times") ? r->timing.wall : r->timing.cpu;
    for (int k = 0; k < r->timing.n; k++)
        put(t, k ? " %.9g" : "%.9g", v[k]);
}

/* times: the count of renders too; cpu_times: as many, after them */
static int read_times(aa_row *row, const column *c, const char *v)
{
    aa_timing *t = &row->timing;
    int wall = !strcmp(c->name, "times"), n = 0;
    double *dst = wall ? t->wall : t->cpu;
    char *end;
    for (const char *p = v; *p;) {
        if (n == AA_TIMING_MAX_REPS)
            return 1;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno || !(x >= 0))
            return 1;
        dst[n++] = x;
        p = end;
        while (*p == ' ')
            p++;
    }
    if (wall)
        t->n = n;
    return 0;
}

static void case_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    if (r->case_index >= 0)
        put(t, "%ld", r->case_index);
}

static int read_case(aa_row *row, const column *c, const char *v)
{
    (void)c;
    if (!*v)
        return 0;
    char *end;
    errno = 0;
    long k = strtol(v, &end, 10);
    if (*end || errno || k < 0 || !(*v >= '0' && *v <= '9'))
        return 1;
    row->case_index = k;
    return 0;
}

static void host_cell(text *t, const aa_row *r, const column *c)
{
    (void)c;
    csv_field(t, r->host);
}

static int read_host(aa_row *row, const column *c, const char *v)
{
    (void)c;
    if (strlen(v) >= sizeof row->host)
        return 1;
    snprintf(row->host, sizeof row->host, "%s", v);
    return 0;
}

#define MEMBER_SIZE(m) sizeof(((aa_row *)0)->m)
#define TEXT(n, g, req) {#n, K_TEXT, g, req, offsetof(aa_row, n), MEMBER_SIZE(n), 0, 0, NULL, NULL}
#define REAL(n, m, g, req, lo, hi) {#n, K_REAL, g, req, offsetof(aa_row, m), 0, lo, hi, NULL, NULL}
#define INT(n, m, g, req, lo, hi) {#n, K_INT, g, req, offsetof(aa_row, m), 0, lo, hi, NULL, NULL}
#define COUNT(n, m) {#n, K_COUNT, G_MEASURE, 0, offsetof(aa_row, m), 0, 0, 0, NULL, NULL}
/* a timed row's number, read back as it is, or recomputed from the times */
#define TIMED(n, m) {#n, K_OWN, G_TIMED, 0, offsetof(aa_row, m), 0, 0, 0, opt_cell, read_real}
#define DERIVED(n, m) {#n, K_OWN, G_TIMED, 0, offsetof(aa_row, m), 0, 0, 0, opt_cell, NULL}
#define OWN(n, g, write, read) {#n, K_OWN, g, 0, 0, 0, 0, 0, write, read}

/* The columns of results.csv, in the order written.  The timing by
 * precision's columns (core.h, "timing and its statistics") come after
 * the older ones: a reader of older files finds them missing. */
static const column columns[] = {
    {"pattern", K_SPEC_PATTERN, G_ALWAYS, 1, offsetof(aa_row, pattern), MEMBER_SIZE(pattern), 0,
     0, NULL, NULL},
    {"size", K_SIZE, G_ALWAYS, 1, 0, 0, 0, 0, NULL, NULL},
    {"filter", K_SPEC_FILTER, G_ALWAYS, 1, offsetof(aa_row, filter), MEMBER_SIZE(filter), 0, 0,
     NULL, NULL},
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
    {"seed", K_SEED, G_ALWAYS, 1, offsetof(aa_row, seed), 0, 0, 0, NULL, NULL},
    REAL(time, t, G_ALWAYS, 1, -1e9, 1e9),
    REAL(vx, vx, G_ALWAYS, 1, -1e6, 1e6),
    REAL(vy, vy, G_ALWAYS, 1, -1e6, 1e6),
    {"ok", K_OK, G_ALWAYS, 1, offsetof(aa_row, ok), 0, 0, 0, NULL, NULL},
    TEXT(note, G_OPTIONAL, 0),
    DERIVED(render_seconds_mean, timing.stats.mean),
    DERIVED(render_seconds_sd, timing.stats.sd),
    DERIVED(render_seconds_mad, timing.stats.mad),
    DERIVED(render_seconds_ci_lo, timing.stats.ci_lo),
    DERIVED(render_seconds_ci_hi, timing.stats.ci_hi),
    DERIVED(ci_level, timing.stats.ci_level),
    TIMED(target_ci, timing.target_ci),
    OWN(outliers, G_TIMED, outliers_cell, NULL),
    TIMED(cpu_seconds, timing.cpu_median),
    TIMED(cpu_share, timing.cpu_share),
    TIMED(load_before, timing.load_before),
    TIMED(load_after, timing.load_after),
    TIMED(others_cores, timing.others_cores),
    TIMED(steal, timing.steal),
    OWN(noisy, G_MEASURE, noisy_cell, read_noisy),
    OWN(noise, G_MEASURE, noise_cell, read_noise),
    OWN(seeds, G_MEASURE, seeds_cell, read_seeds),
    {"rmse_mean", K_OWN, G_MEASURE, 0, offsetof(aa_row, rmse_mean), 0, 0, 0, seeds_real_cell,
     read_real},
    {"rmse_ci_lo", K_OWN, G_MEASURE, 0, offsetof(aa_row, rmse_ci_lo), 0, 0, 0, seeds_real_cell,
     read_real},
    {"rmse_ci_hi", K_OWN, G_MEASURE, 0, offsetof(aa_row, rmse_ci_hi), 0, 0, 0, seeds_real_cell,
     read_real},
    OWN(times, G_TIMED, times_cell, read_times),
    OWN(cpu_times, G_TIMED, times_cell, read_times),
    OWN(case, G_ALWAYS, case_cell, read_case),
    OWN(host, G_ALWAYS, host_cell, read_host),
    TEXT(inputs, G_OPTIONAL, 0),
    /* added after the columns above: older files lack it */
    REAL(lag, tm.lag, G_TEMPORAL_OPTIONAL, 0, -DBL_MAX, DBL_MAX),
    /* the perceptual and edge errors */
    REAL(flip, m.flip, G_MEASURE_OPTIONAL, 0, 0, 1),
    REAL(edge_rmse, m.edge_rmse, G_MEASURE_OPTIONAL, 0, 0, 1),
    /* the method's init, timed once on its own (render_seconds leaves it
     * out) */
    REAL(init_seconds, timing.init_seconds, G_MEASURE_OPTIONAL, 0, 0, DBL_MAX),
    REAL(init_cpu_seconds, timing.init_cpu, G_MEASURE_OPTIONAL, 0, 0, DBL_MAX),
    /* the view's reference: its largest per-pixel bound, and its pixels
     * whose bounds are estimates */
    REAL(ref_bound, ref_bound, G_MEASURE_OPTIONAL, 0, 0, DBL_MAX),
    REAL(ref_scanned, ref_scanned, G_MEASURE_OPTIONAL, 0, 0, 1e12),
};
#undef TEXT
#undef REAL
#undef INT
#undef COUNT
#undef TIMED
#undef DERIVED
#undef OWN
#define NCOLUMNS (sizeof columns / sizeof *columns)

const char *aa_results_column(size_t k)
{
    return k < NCOLUMNS ? columns[k].name : NULL;
}

/* Whether a row holds a value in the column (else its cell is empty). */
static int holds(const column *c, const aa_row *r)
{
    switch (c->group) {
    case G_MEASURE:
    case G_MEASURE_OPTIONAL: return r->ok;
    case G_TEMPORAL:
    case G_TEMPORAL_OPTIONAL: return r->ok && r->temporal;
    case G_TIMED: return r->ok && r->timing.n > 0;
    default: return 1;
    }
}

static void write_cell(text *t, const aa_row *r, const column *c)
{
    const char *at = (const char *)r + c->off;
    int i;
    uint64_t u;
    if (!holds(c, r))
        return;
    switch (c->kind) {
    case K_TEXT:
    case K_SPEC_PATTERN:
    case K_SPEC_FILTER: csv_field(t, at); break;
    case K_SIZE: put(t, "%dx%d", r->w, r->h); break;
    case K_REAL:
        /* a value that may be missing is written only when there is one */
        if (c->group == G_TEMPORAL_OPTIONAL || c->group == G_MEASURE_OPTIONAL)
            opt(t, real_of(r, c));
        else
            num(t, real_of(r, c));
        break;
    case K_INT:
    case K_OK:
        memcpy(&i, at, sizeof i);
        put(t, "%d", i);
        break;
    case K_COUNT:
    case K_SEED:
        memcpy(&u, at, sizeof u);
        put(t, "%llu", (unsigned long long)u);
        break;
    case K_OWN: c->write(t, r, c); break;
    }
}

static int write_csv(const char *path, const aa_row *rows, size_t n)
{
    text tb = {0}, *t = &tb;
    for (size_t c = 0; c < NCOLUMNS; c++)
        put(t, "%s%s", c ? "," : "", columns[c].name);
    put(t, "\n");
    for (size_t k = 0; k < n; k++) {
        for (size_t c = 0; c < NCOLUMNS; c++) {
            if (c)
                put(t, ",");
            write_cell(t, &rows[k], &columns[c]);
        }
        put(t, "\n");
    }
    return finish(t, path);
}

/* ---- results.json, through cJSON ---- */

/* Numbers are written as in results.csv, with nine significant digits
 * (cJSON would write up to 17), counts and seeds whole (2^64 - 1 is no
 * double); what is not finite is null. */
static cJSON *json_num(double v)
{
    if (!isfinite(v))
        return cJSON_CreateNull();
    char b[40];
    snprintf(b, sizeof b, "%.9g", v);
    return cJSON_CreateRaw(b);
}

static int add(cJSON *o, const char *key, cJSON *v)
{
    if (!v)
        return 0;
    if (!cJSON_AddItemToObject(o, key, v)) {
        cJSON_Delete(v);
        return 0;
    }
    return 1;
}

static int add_num(cJSON *o, const char *key, double v)
{
    return add(o, key, json_num(v));
}

static int add_count(cJSON *o, const char *key, uint64_t v)
{
    char b[24];
    snprintf(b, sizeof b, "%llu", (unsigned long long)v);
    return add(o, key, cJSON_CreateRaw(b));
}

/* An array of n numbers; an interval [lo, hi] is [null, null] unless lo
 * is finite. */
static cJSON *json_nums(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int k = 0; a && k < n; k++)
        if (!cJSON_AddItemToArray(a, json_num(v[k]))) {
            cJSON_Delete(a);
            return NULL;
        }
    return a;
}

static cJSON *json_interval(double lo, double hi)
{
    double v[2] = {lo, isfinite(lo) ? hi : NAN};
    return json_nums(v, 2);
}

/* A row's timing, its noise and its seeds into o. */
static int timing_members(cJSON *o, const aa_row *r)
{
    const aa_timing *t = &r->timing;
    int ok = 1;
    if (r->ok && t->n > 0) {
        const aa_time_stats *s = &t->stats;
        cJSON *j = cJSON_CreateObject();
        ok = add(o, "timing", j) && add(j, "times", json_nums(t->wall, t->n)) &&
             add(j, "cpu_times", json_nums(t->cpu, t->n)) &&
             add(j, "n", cJSON_CreateNumber(t->n)) && add(j, "fixed", cJSON_CreateBool(t->fixed)) &&
             add_num(j, "median", s->median) && add_num(j, "mean", s->mean) &&
             add_num(j, "sd", s->sd) && add_num(j, "mad", s->mad) && add_num(j, "min", s->min) &&
             add_num(j, "max", s->max) && add(j, "ci", json_interval(s->ci_lo, s->ci_hi)) &&
             add_num(j, "ci_level", s->ci_level) && add_num(j, "ci_relative", t->ci_rel) &&
             add_num(j, "target_ci", t->target_ci) &&
             add(j, "target_met", cJSON_CreateBool(t->target_met)) &&
             add_count(j, "outliers", s->outliers) && add_num(j, "cpu_median", t->cpu_median) &&
             add_num(j, "cpu_share", t->cpu_share) && add_num(j, "load_before", t->load_before) &&
             add_num(j, "load_after", t->load_after) &&
             add_num(j, "others_cores", t->others_cores) && add_num(j, "steal", t->steal) &&
             add_num(j, "elapsed", t->elapsed);
    }
    if (ok && r->ok) {
        char why[128];
        aa_noisy_text(t->noisy, why, sizeof why);
        ok = add(o, "noisy", cJSON_CreateBool(t->noisy != 0)) &&
             add(o, "noise", cJSON_CreateString(why)) &&
             add(o, "seeds", cJSON_CreateNumber(r->seeds > 0 ? r->seeds : 1));
        if (ok && r->seeds > 1)
            ok = add_num(o, "rmse_mean", r->rmse_mean) &&
                 add(o, "rmse_ci", json_interval(r->rmse_ci_lo, r->rmse_ci_hi));
    }
    return ok;
}

char *aa_row_timing_json(const aa_row *r)
{
    cJSON *o = cJSON_CreateObject();
    char *json = o && timing_members(o, r) ? cJSON_PrintUnformatted(o) : NULL;
    cJSON_Delete(o);
    if (!json)
        return NULL;
    /* "{...}" as members after those of the caller: ", ..." */
    size_t len = strlen(json);
    char *out = malloc(len + 2);
    if (out) {
        if (len > 2)
            snprintf(out, len + 2, ", %.*s", (int)(len - 2), json + 1);
        else
            out[0] = '\0';
    }
    cJSON_free(json);
    return out;
}

/* A row of results.json. */
static cJSON *row_json(const aa_row *r)
{
    cJSON *o = cJSON_CreateObject();
    char size[32];
    snprintf(size, sizeof size, "%dx%d", r->w, r->h);
    int ok = o && add(o, "pattern", cJSON_CreateString(r->pattern)) &&
             add(o, "size", cJSON_CreateString(size)) &&
             add(o, "filter", cJSON_CreateString(r->filter)) &&
             add(o, "method", cJSON_CreateString(r->method)) &&
             add(o, "canonical", cJSON_CreateString(r->canonical)) &&
             add(o, "inputs", cJSON_CreateString(r->inputs)) &&
             add(o, "ok", cJSON_CreateBool(r->ok));
    if (ok && r->ok) {
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
                 {"flip", r->m.flip},
                 {"edge_rmse", r->m.edge_rmse},
                 {"render_seconds", r->seconds},
                 {"render_seconds_min", r->seconds_min},
                 {"render_seconds_max", r->seconds_max},
                 {"init_seconds", r->timing.init_seconds},
                 {"init_cpu_seconds", r->timing.init_cpu},
                 {"ref_bound", r->ref_bound},
                 {"ref_scanned", r->ref_scanned},
                 {"ns_per_pixel", r->ns_per_pixel},
                 {"ns_per_sample", r->ns_per_sample},
                 {"expensive_fraction", r->expensive_fraction}};
        for (size_t q = 0; ok && q < sizeof f / sizeof *f; q++)
            ok = add_num(o, f[q].key, f[q].v);
        ok = ok && add(o, "max_at", cJSON_CreateIntArray(r->m.max_at, 3)) &&
             add_count(o, "samples", r->samples) &&
             add_count(o, "expensive_pixels", r->expensive_pixels);
        if (ok && r->temporal) {
            cJSON *tm = cJSON_CreateObject();
            ok = add(o, "temporal", tm) && add(tm, "frames", cJSON_CreateNumber(r->tm.frames)) &&
                 add(tm, "window", cJSON_CreateNumber(r->tm.window)) &&
                 add_num(tm, "eye_rmse", r->tm.eye_rmse) &&
                 add_num(tm, "flicker_mean", r->tm.flicker_mean) &&
                 add_num(tm, "flicker_max", r->tm.flicker_max) &&
                 add_num(tm, "conservation", r->tm.conservation) &&
                 add_num(tm, "lag", r->tm.lag) &&
                 add_num(tm, "popping", r->tm.popping);
        }
    }
    double motion[2] = {r->vx, r->vy};
    ok = ok && add(o, "threads", cJSON_CreateNumber(r->threads)) &&
         add(o, "reps", cJSON_CreateNumber(r->reps)) && add_count(o, "seed", r->seed) &&
         add_num(o, "time", r->t) && add(o, "motion", json_nums(motion, 2)) &&
         add(o, "note", cJSON_CreateString(r->note)) && timing_members(o, r);
    if (!ok) {
        cJSON_Delete(o);
        return NULL;
    }
    return o;
}

/* {"context": ..., "results": [...]}: the context as aa_context_json
 * gives it, then one row a line (cJSON's compact print), so that a run's
 * rows can be read and compared line by line. */
static int write_json(const char *path, const aa_context *ctx, const aa_row *rows, size_t n)
{
    text tb = {0}, *t = &tb;
    char *cj = ctx ? aa_context_json(ctx, 2) : NULL;
    if (ctx && !cj)
        t->failed = 1;
    put(t, "{\n  \"context\": %s,\n  \"results\": [\n", cj ? cj : "null");
    free(cj);
    for (size_t k = 0; k < n && !t->failed; k++) {
        cJSON *o = row_json(&rows[k]);
        char *row = o ? cJSON_PrintUnformatted(o) : NULL;
        cJSON_Delete(o);
        if (!row)
            t->failed = 1;
        else
            put(t, "  %s%s\n", row, k + 1 < n ? "," : "");
        cJSON_free(row);
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
 * The header names columns of the writer's table, each once, the required
 * ones present (the timing's columns, which older files lack, are read as
 * they are); a UTF-8 byte-order mark before it is skipped.  Every row has as many fields
 * as the header; numbers are plain C-locale decimals, finite and within
 * what the column can hold ("inf" only for a PSNR); sizes are WxH with
 * nothing after; patterns and filters parse as specs; a row with ok = 1
 * has every measurement and a row with ok = 0 none, but its reason in the
 * note.  Anything else is refused (AA_EINVAL) naming the file, the line
 * and the column; a file that has no header at all is not a results file
 * (AA_EIO). */

#define CSV_MAX_BYTES ((size_t)256 << 20)
#define CSV_MAX_FIELDS 256

int aa_rows_same_view(const aa_row *a, const aa_row *b)
{
    return !strcmp(a->pattern, b->pattern) && !strcmp(a->filter, b->filter) && a->w == b->w &&
           a->h == b->h;
}

int aa_row_reference_unproven(const aa_row *rows, size_t k)
{
    const aa_row *r = &rows[k];
    if (!r->ok || !(r->ref_scanned > 0 || r->ref_bound > AA_TRUTH_BOUND))
        return 0;
    for (size_t e = 0; e < k; e++)
        if (rows[e].ok && aa_rows_same_view(&rows[e], r))
            return 0;
    return 1;
}

double aa_rows_parallelism(const aa_row *rows, size_t n, size_t *least, size_t *most)
{
    size_t lo = n, hi = n;
    for (size_t k = 0; k < n; k++) {
        const aa_timing *t = &rows[k].timing;
        if (!rows[k].ok || t->n <= 0 || !(t->cpu_share > 0) || !isfinite(t->cpu_share))
            continue;
        if (lo == n || t->cpu_share < rows[lo].timing.cpu_share)
            lo = k;
        if (hi == n || t->cpu_share > rows[hi].timing.cpu_share)
            hi = k;
    }
    *least = lo, *most = hi;
    return lo == n || lo == hi ? 1.0 : rows[hi].timing.cpu_share / rows[lo].timing.cpu_share;
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
static int csv_value(const csv *p, int f, const column *col, const char *v, aa_row *row)
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

static const column *column_named(const char *name)
{
    for (size_t k = 0; k < NCOLUMNS; k++)
        if (!strcmp(columns[k].name, name))
            return &columns[k];
    return NULL;
}

/* What a single field cannot show: a reason for a row that did not run,
 * a pixel inside the image, a window within the frames.  (Errors are not
 * held to each other: a baseline tightened by hand, an rmse lowered below
 * the mae, is still a baseline.) */
static int csv_row_check(const csv *p, const int *at, aa_row *row)
{
#define AT(name) (column_named(name) ? at[column_named(name) - columns] : -1)
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
        if (!column_named(head[f])) {
            st = csv_fail(&p, f, "unknown column \"%s\"", aa_echo(head[f]));
            goto done;
        }
        for (int g = 0; g < f; g++)
            if (!strcmp(head[g], head[f])) {
                st = csv_fail(&p, f, "column \"%s\" given twice (columns %d and %d)", head[f],
                              g + 1, f + 1);
                goto done;
            }
        const column *col = column_named(head[f]);
        if (col)
            at[col - columns] = f;
    }
    for (size_t k = 0; k < NCOLUMNS; k++)
        if (columns[k].required && at[k] < 0) {
            st = aa_fail(AA_EINVAL, "%s:%zu: no column \"%s\", which a results file must have",
                         aa_echo(name), p.fline[0], columns[k].name);
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
        row->tm.popping = row->tm.lag = NAN;
        row->m.flip = row->m.edge_rmse = NAN;
        row->timing.init_seconds = row->timing.init_cpu = NAN;
        row->ref_bound = row->ref_scanned = NAN;
        row->case_index = -1;
        /* ok first: which columns must hold a value depends on it; then
         * whether the row is animated */
        const int f_ok = at[column_named("ok") - columns];
        if ((st = csv_value(&p, f_ok, column_named("ok"), field_text(&p, f_ok), row)))
            break;
        const column *eye = column_named("eye_rmse");
        row->temporal = row->ok && at[eye - columns] >= 0 &&
                        *field_text(&p, at[eye - columns]);
        for (size_t k = 0; k < NCOLUMNS && !st; k++) {
            const column *col = &columns[k];
            int f = at[k];
            if (f < 0 || col->kind == K_OK)
                continue;
            const char *v = field_text(&p, f);
            /* the timing's columns (older files have none): read as they are */
            if (col->kind == K_OWN) {
                if (col->read && col->read(row, col, v))
                    st = csv_fail(&p, f, "malformed timing value \"%s\"", aa_echo(v));
                continue;
            }
            /* 1: must hold a value, 0: must be empty, -1: either */
            int want = col->group == G_ALWAYS              ? 1
                       : col->group == G_MEASURE           ? row->ok
                       : col->group == G_TEMPORAL          ? row->temporal
                       : col->group == G_TEMPORAL_OPTIONAL ? (row->temporal ? -1 : 0)
                       : col->group == G_MEASURE_OPTIONAL  ? (row->ok ? -1 : 0)
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

/* The whole of a results file, at most CSV_MAX_BYTES (malloc'd, *n bytes). */
static int read_whole(const char *path, char **out, size_t *n_out)
{
    *out = NULL;
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
    if (st) {
        free(data);
        return st;
    }
    *out = data;
    *n_out = n;
    return AA_OK;
}

int aa_rows_read_csv(const char *path, aa_row **rows_out, size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    char *data;
    size_t n;
    int st = read_whole(path, &data, &n);
    if (!st)
        st = aa_rows_parse_csv(path, data ? data : "", n, rows_out, n_out);
    free(data);
    return st;
}

/* ---- results.json read back ----
 *
 * As strictly as the CSV: {"context": ..., "results": [rows]}, each row
 * with the members row_json writes that a comparison needs (the case, ok,
 * the note, and for a row with ok = true its errors), of the types it
 * writes them; the timing's members are read when present.  Anything else
 * is refused (AA_EINVAL) naming the file, the row and the member. */

static int json_fail(const char *name, size_t k, const char *key, const char *fmt, ...)
    AA_PRINTF(4, 5);
static int json_fail(const char *name, size_t k, const char *key, const char *fmt, ...)
{
    char why[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    return aa_fail(AA_EINVAL, "%s: result %zu, \"%s\": %s", aa_echo(name), k + 1, key, why);
}

/* A member that must be there, of the given type (cJSON_String, ...). */
static const cJSON *json_member(const char *name, size_t k, const cJSON *o, const char *key,
                                int type, int *st)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (*st)
        return NULL;
    if (!v || !(v->type & type)) {
        *st = json_fail(name, k, key, "%s",
                        !v ? "missing" : "of the wrong type");
        return NULL;
    }
    return v;
}

static int json_text(const char *name, size_t k, const cJSON *o, const char *key, char *dst,
                     size_t size, int optional)
{
    int st = AA_OK;
    if (optional && !cJSON_GetObjectItemCaseSensitive(o, key))
        return AA_OK;
    const cJSON *v = json_member(name, k, o, key, cJSON_String, &st);
    if (st)
        return st;
    if (strlen(v->valuestring) >= size)
        return json_fail(name, k, key, "longer than the %zu characters it can have", size - 1);
    snprintf(dst, size, "%s", v->valuestring);
    return AA_OK;
}

static int json_real(const char *name, size_t k, const cJSON *o, const char *key, double lo,
                     double hi, int optional, double *dst)
{
    int st = AA_OK;
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (optional && (!v || cJSON_IsNull(v)))
        return AA_OK;
    v = json_member(name, k, o, key, cJSON_Number, &st);
    if (st)
        return st;
    if (!(v->valuedouble >= lo && v->valuedouble <= hi))
        return json_fail(name, k, key, "%g is out of range (%g to %g)", v->valuedouble, lo, hi);
    *dst = v->valuedouble;
    return AA_OK;
}

static int json_row(const char *name, size_t k, const cJSON *o, aa_row *row)
{
    int st = AA_OK;
    char size[32] = "";
    memset(row, 0, sizeof *row);
    row->tm.popping = row->tm.lag = NAN;
    row->case_index = -1;
    row->m.rmse = row->m.max_err = row->seconds = NAN;
    row->m.flip = row->m.edge_rmse = NAN;
    row->timing.init_seconds = row->timing.init_cpu = NAN;
    row->ref_bound = row->ref_scanned = NAN;
    if (!cJSON_IsObject(o))
        return json_fail(name, k, "results", "a row is not an object");
    if ((st = json_text(name, k, o, "pattern", row->pattern, sizeof row->pattern, 0)) ||
        (st = json_text(name, k, o, "size", size, sizeof size, 0)) ||
        (st = json_text(name, k, o, "filter", row->filter, sizeof row->filter, 0)) ||
        (st = json_text(name, k, o, "method", row->method, sizeof row->method, 0)) ||
        (st = json_text(name, k, o, "canonical", row->canonical, sizeof row->canonical, 1)) ||
        (st = json_text(name, k, o, "inputs", row->inputs, sizeof row->inputs, 1)) ||
        (st = json_text(name, k, o, "note", row->note, sizeof row->note, 0)))
        return st;
    aa_spec spec;
    aa_filter filter;
    const char *bad = aa_pattern_parse(row->pattern, &spec)  ? "pattern"
                      : aa_filter_parse(row->filter, &filter) ? "filter"
                      : aa_size_parse(size, &row->w, &row->h) ? "size"
                                                              : NULL;
    if (bad) {
        char why[1024];
        snprintf(why, sizeof why, "%s", aa_last_error());
        return json_fail(name, k, bad, "%s", why);
    }
    const cJSON *ok = json_member(name, k, o, "ok", cJSON_True | cJSON_False, &st);
    if (st)
        return st;
    row->ok = cJSON_IsTrue(ok);
    if (!row->ok && !*row->note)
        return json_fail(name, k, "note",
                         "a row with ok=false (refused or failed) must give its reason");
    /* the seed: a whole number that a double holds exactly */
    double seed = 0, threads = 1, reps = 1, seeds = 1;
    if ((st = json_real(name, k, o, "seed", 0, 9007199254740992.0, 0, &seed)))
        return st;
    if (seed != floor(seed))
        return json_fail(name, k, "seed", "not a whole number");
    row->seed = (uint64_t)seed;
    if ((st = json_real(name, k, o, "time", -1e9, 1e9, 0, &row->t)) ||
        (st = json_real(name, k, o, "threads", 1, AA_MAX_THREADS, 1, &threads)) ||
        (st = json_real(name, k, o, "reps", 1, 1000, 1, &reps)))
        return st;
    row->threads = (int)threads, row->reps = (int)reps;
    const cJSON *motion = json_member(name, k, o, "motion", cJSON_Array, &st);
    if (st)
        return st;
    if (cJSON_GetArraySize(motion) != 2 || !cJSON_IsNumber(cJSON_GetArrayItem(motion, 0)) ||
        !cJSON_IsNumber(cJSON_GetArrayItem(motion, 1)))
        return json_fail(name, k, "motion", "not two numbers");
    row->vx = cJSON_GetArrayItem(motion, 0)->valuedouble;
    row->vy = cJSON_GetArrayItem(motion, 1)->valuedouble;
    if (!row->ok)
        return AA_OK;
    if ((st = json_real(name, k, o, "rmse", 0, 1, 0, &row->m.rmse)) ||
        (st = json_real(name, k, o, "max_err", 0, 1, 0, &row->m.max_err)) ||
        (st = json_real(name, k, o, "mae", 0, 1, 1, &row->m.mae)) ||
        (st = json_real(name, k, o, "flip", 0, 1, 1, &row->m.flip)) ||
        (st = json_real(name, k, o, "edge_rmse", 0, 1, 1, &row->m.edge_rmse)) ||
        (st = json_real(name, k, o, "render_seconds", 0, DBL_MAX, 1, &row->seconds)) ||
        (st = json_real(name, k, o, "init_seconds", 0, DBL_MAX, 1, &row->timing.init_seconds)) ||
        (st = json_real(name, k, o, "init_cpu_seconds", 0, DBL_MAX, 1, &row->timing.init_cpu)) ||
        (st = json_real(name, k, o, "ref_bound", 0, DBL_MAX, 1, &row->ref_bound)) ||
        (st = json_real(name, k, o, "ref_scanned", 0, 1e12, 1, &row->ref_scanned)) ||
        (st = json_real(name, k, o, "spp", 0, DBL_MAX, 1, &row->spp)) ||
        (st = json_real(name, k, o, "seeds", 1, 1e9, 1, &seeds)))
        return st;
    row->seeds = (int)seeds;
    const cJSON *noisy = cJSON_GetObjectItemCaseSensitive(o, "noisy");
    const cJSON *noise = cJSON_GetObjectItemCaseSensitive(o, "noise");
    if (noisy && !cJSON_IsBool(noisy))
        return json_fail(name, k, "noisy", "not true or false");
    if (cJSON_IsTrue(noisy)) {
        row->timing.noisy = cJSON_IsString(noise) ? aa_noisy_parse(noise->valuestring) : 0;
        row->timing.noisy |= NOISY_MARKED;
    }
    const cJSON *timing = cJSON_GetObjectItemCaseSensitive(o, "timing");
    if (timing) {
        if (!cJSON_IsObject(timing))
            return json_fail(name, k, "timing", "not an object");
        const char *keys[2] = {"times", "cpu_times"};
        for (int w = 0; w < 2; w++) {
            const cJSON *a = cJSON_GetObjectItemCaseSensitive(timing, keys[w]), *x;
            if (!a && w)
                continue;
            if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) > AA_TIMING_MAX_REPS)
                return json_fail(name, k, keys[w], "not an array of at most %d times",
                                 AA_TIMING_MAX_REPS);
            int n = 0;
            cJSON_ArrayForEach(x, a)
            {
                if (!cJSON_IsNumber(x) || !(x->valuedouble >= 0))
                    return json_fail(name, k, keys[w], "time %d is not a number of seconds",
                                     n + 1);
                (w ? row->timing.cpu : row->timing.wall)[n++] = x->valuedouble;
            }
            if (!w)
                row->timing.n = n;
        }
    }
    return AA_OK;
}

static int parse_json(const char *name, const char *data, size_t len, aa_row **rows_out,
                      size_t *n_out)
{
    cJSON *doc = cJSON_ParseWithLength(data, len);
    if (!doc)
        return aa_fail(AA_EINVAL, "%s: not JSON (malformed near byte %zu)", aa_echo(name),
                       cJSON_GetErrorPtr() && cJSON_GetErrorPtr() >= data
                           ? (size_t)(cJSON_GetErrorPtr() - data)
                           : (size_t)0);
    const cJSON *res = cJSON_GetObjectItemCaseSensitive(doc, "results");
    int st = AA_OK;
    aa_row *rows = NULL;
    size_t n = 0;
    if (!cJSON_IsObject(doc) || !cJSON_IsArray(res)) {
        st = aa_fail(AA_EINVAL,
                     "%s: not a results file: a results.json is an object whose \"results\" is "
                     "an array of rows",
                     aa_echo(name));
    } else {
        size_t count = (size_t)cJSON_GetArraySize(res);
        rows = malloc((count ? count : 1) * sizeof *rows);
        if (!rows)
            st = aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(name));
        const cJSON *o;
        cJSON_ArrayForEach(o, res)
        {
            if (st || (st = json_row(name, n, o, &rows[n])))
                break;
            settle_timing(&rows[n]);
            n++;
        }
    }
    cJSON_Delete(doc);
    if (st) {
        free(rows);
        rows = NULL;
        n = 0;
    }
    *rows_out = rows;
    *n_out = n;
    return st;
}

int aa_rows_parse_json(const char *name, const char *data, size_t len, aa_row **rows_out,
                       size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, name);
    if (st)
        return st;
    st = parse_json(name, data, len, rows_out, n_out);
    aa__c_numbers_end(&numbers);
    return st;
}

int aa_rows_read_json(const char *path, aa_row **rows_out, size_t *n_out)
{
    *rows_out = NULL;
    *n_out = 0;
    char *data;
    size_t n;
    int st = read_whole(path, &data, &n);
    if (!st)
        st = aa_rows_parse_json(path, data ? data : "", n, rows_out, n_out);
    free(data);
    return st;
}
