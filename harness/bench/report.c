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
    X(times, S(times_cell(t, r)))

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

/* ---- reading CSV ---- */

#define CSV_MAX_FIELDS 128
#define CSV_MAX_LINE 65536

/* Split one record (which may span lines inside quotes) into fields, in
 * place; returns the number of fields or -1 if malformed. */
static int csv_split(char *line, char **fields, int max)
{
    int n = 0;
    char *r = line, *w = line;
    for (;;) {
        if (n == max)
            return -1;
        fields[n++] = w;
        if (*r == '"') {
            r++;
            for (;;) {
                if (!*r)
                    return -1;
                if (*r == '"') {
                    if (r[1] == '"') {
                        *w++ = '"';
                        r += 2;
                        continue;
                    }
                    r++;
                    break;
                }
                *w++ = *r++;
            }
            if (*r && *r != ',')
                return -1;
        } else {
            while (*r && *r != ',') {
                if (*r == '"')
                    return -1;
                *w++ = *r++;
            }
        }
        if (!*r) {
            *w = '\0';
            return n;
        }
        *w++ = '\0';
        r++;
    }
}

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

/* Read one logical CSV record: lines joined while quotes are open. */
static int read_record(FILE *f, char *buf, size_t len)
{
    size_t n = 0;
    int quotes = 0;
    for (;;) {
        if (!fgets(buf + n, (int)(len - n), f))
            return n ? 1 : 0;
        size_t m = strlen(buf + n);
        for (size_t k = n; k < n + m; k++)
            quotes ^= buf[k] == '"';
        n += m;
        if (n + 1 >= len)
            return -1;
        if (!quotes) {
            while (n && (buf[n - 1] == '\n' || buf[n - 1] == '\r'))
                buf[--n] = '\0';
            return 1;
        }
    }
}

/* "noisy" read as 1: a reason is taken from "noise", else "ci" */
#define NOISY_MARKED (1u << 31)

/* The timing columns (absent from older files: a row then has no times,
 * timing.n = 0, and one seed).  Returns non-zero if a cell is malformed. */
static int read_timing_cell(aa_row *row, const char *h, const char *v)
{
    int bad = 0;
    aa_timing *t = &row->timing;
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

static int read_csv(const char *path, aa_row **rows_out, size_t *n_out)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return aa_fail(AA_EIO, "%s: cannot open: %s", path, strerror(errno));
    char *line = malloc(CSV_MAX_LINE), *head[CSV_MAX_FIELDS], *cell[CSV_MAX_FIELDS];
    char *header = malloc(CSV_MAX_LINE);
    aa_row *rows = NULL;
    size_t n = 0, cap = 0, lineno = 1;
    int nh = 0, st = AA_OK;
    if (!line || !header) {
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    if (read_record(f, header, CSV_MAX_LINE) != 1 ||
        (nh = csv_split(header, head, CSV_MAX_FIELDS)) < 4) {
        st = aa_fail(AA_EIO, "%s: no CSV header", path);
        goto done;
    }
    for (int r; (r = read_record(f, line, CSV_MAX_LINE)) != 0;) {
        lineno++;
        if (r < 0) {
            st = aa_fail(AA_EIO, "%s:%zu: record too long", path, lineno);
            goto done;
        }
        if (!*line)
            continue;
        int nc = csv_split(line, cell, CSV_MAX_FIELDS), bad = 0;
        if (nc != nh) {
            st = aa_fail(AA_EIO, "%s:%zu: %d fields, the header has %d", path, lineno, nc, nh);
            goto done;
        }
        if (n == cap) {
            size_t c2 = cap ? 2 * cap : 64;
            aa_row *p = realloc(rows, c2 * sizeof *p);
            if (!p) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
                goto done;
            }
            rows = p;
            cap = c2;
        }
        aa_row *row = &rows[n];
        memset(row, 0, sizeof *row);
        row->ok = 1;
        row->tm.popping = NAN;
        for (int k = 0; k < nh; k++) {
            const char *h = head[k], *v = cell[k];
#define STR(name) if (!strcmp(h, #name)) snprintf(row->name, sizeof row->name, "%s", v);
#define NUM(name, dst) if (!strcmp(h, name)) dst = field_num(v, &bad);
            STR(pattern) STR(filter) STR(method) STR(canonical) STR(note)
            NUM("spp", row->spp) NUM("rmse", row->m.rmse) NUM("mae", row->m.mae)
            NUM("max_err", row->m.max_err) NUM("psnr", row->m.psnr)
            NUM("rmse_enc", row->m.rmse_enc) NUM("psnr_enc", row->m.psnr_enc)
            NUM("alias_total", row->m.alias_total) NUM("alias_low", row->m.alias_low)
            NUM("alias_high", row->m.alias_high) NUM("ssim", row->m.ssim)
            NUM("render_seconds", row->seconds) NUM("ns_per_pixel", row->ns_per_pixel)
            NUM("ns_per_sample", row->ns_per_sample) NUM("time", row->t) NUM("vx", row->vx)
            NUM("vy", row->vy) NUM("expensive_fraction", row->expensive_fraction)
            NUM("eye_rmse", row->tm.eye_rmse) NUM("flicker_mean", row->tm.flicker_mean)
            NUM("flicker_max", row->tm.flicker_max) NUM("conservation", row->tm.conservation)
            NUM("popping", row->tm.popping)
#undef STR
#undef NUM
            if (!strcmp(h, "size") && sscanf(v, "%dx%d", &row->w, &row->h) != 2)
                bad = 1;
            if (!strcmp(h, "seed")) {
                char *end;
                errno = 0;
                row->seed = strtoull(v, &end, 10);
                if (errno || end == v || *end || *v == '-')
                    bad = 1;
            }
            if (!strcmp(h, "ok"))
                row->ok = !strcmp(v, "1");
            if (!strcmp(h, "eye_rmse") && *v)
                row->temporal = 1;
            if (!strcmp(h, "frames") && *v)
                row->tm.frames = atoi(v);
            if (!strcmp(h, "window") && *v)
                row->tm.window = atoi(v);
            if (read_timing_cell(row, h, v))
                bad = 1;
        }
        settle_timing(row);
        if (bad || !*row->pattern || !*row->method || row->w < 1 || row->h < 1) {
            st = aa_fail(AA_EIO, "%s:%zu: malformed row", path, lineno);
            goto done;
        }
        n++;
    }
    if (ferror(f))
        st = aa_fail(AA_EIO, "%s: read error", path);
done:
    fclose(f);
    free(line);
    free(header);
    if (st) {
        free(rows);
        rows = NULL;
        n = 0;
    }
    *rows_out = rows;
    *n_out = n;
    return st;
}

int aa_rows_read_csv(const char *path, aa_row **rows_out, size_t *n_out)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, path);
    if (st) {
        *rows_out = NULL;
        *n_out = 0;
        return st;
    }
    st = read_csv(path, rows_out, n_out);
    aa__c_numbers_end(&numbers);
    return st;
}
