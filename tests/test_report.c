/*
 * test_report.c: results.csv and results.json (report.c).
 *
 *  - The CSV's columns are one table: the header written is the column
 *    list aa_results_column gives, in order, and a header naming a column
 *    outside it, or lacking a required one, is refused with a message
 *    naming that column.
 *  - Rows read back equal: a file written by the writer before its columns
 *    became one table (a run of dots and crow at 16x16, point and jitter
 *    under box and gauss, animated, three seeds, two reps: refused rows,
 *    a missing popping, quoted specs, timing columns) reads and writes
 *    back byte for byte, and rows built here write, read and compare equal
 *    field by field.
 *  - results.json parses (cJSON) to the rows' values: numbers with nine
 *    significant digits as in the CSV, null where a value is not finite,
 *    whole counts exact beyond 2^53, one row a line; a row's timing
 *    members (aa_row_timing_json) parse inside an object.
 */
#include "bench.h"

#include <cJSON.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

static char dir[] = "/tmp/aabench-report-XXXXXX";

/* written by the previous writer (aabench run -p dots -p crow -s 16x16
 * -m point -m jitter -f box -f gauss --seeds 3 --reps 2 --motion
 * 0.37,0.11 --frames 4 --window 2) */
static const char old_csv[] =
    "pattern,size,filter,method,canonical,spp,rmse,mae,max_err,max_i,max_j,psnr,rmse_enc,mae_"
    "enc,max_err_enc,psnr_enc,alias_total,alias_low,alias_high,ssim,render_seconds,render_sec"
    "onds_min,render_seconds_max,ns_per_pixel,ns_per_sample,samples,expensive_pixels,expensiv"
    "e_fraction,frames,window,eye_rmse,flicker_mean,flicker_max,conservation,popping,threads,"
    "reps,seed,time,vx,vy,ok,note,render_seconds_mean,render_seconds_sd,render_seconds_mad,re"
    "nder_seconds_ci_lo,render_seconds_ci_hi,ci_level,target_ci,outliers,cpu_seconds,cpu_shar"
    "e,load_before,load_after,others_cores,steal,noisy,noise,seeds,rmse_mean,rmse_ci_lo,rmse_"
    "ci_hi,times,cpu_times,case,host,inputs\n"
    "dots,16x16,box,point,point,1,0.1874344,0.0354830933,0.999648437,0,0,14.543014,0.18670165"
    "7,0.0393790649,0.995457812,14.5770365,0.0351316544,0.0283325935,0.00679906091,0.79733604"
    "6,0.034002164,0.030813206,0.037191122,132820.953,132820.953,256,0,0,4,2,0.0540896175,0.0"
    "152308402,0.433012702,4,0.0208333333,2,2,1,0,0.37,0.11,1,,0.034002164,0.00450986765,0.00"
    "472795621,,,,0.02,0,0.0137199325,0.403501745,3.37,3.37,1.66528409,0,1,busy,1,,,,0.037191"
    "122 0.030813206,0.015880931 0.011558934,0,vm,\n"
    "dots,16x16,box,jitter,\"jitter:spp=16,seq=stratified\",16,0.00673683748,0.00107574463,0."
    "0621484375,1,1,43.4308786,0.029870624,0.0076853883,0.272761989,30.4951141,4.53849792e-05"
    ",7.81074546e-06,3.75742338e-05,0.755302473,0.000106002,8.39200002e-05,0.000128084,414.07"
    "0312,25.8793945,4096,256,1,4,2,0.00487188311,0.00119021656,0.03125,1,0.197916667,2,2,1,0"
    ",0.37,0.11,1,,0.000106002,3.12286635e-05,3.27388218e-05,,,,0.02,0,0.0001087965,1.0263627"
    "1,3.37,3.37,1.68684988,0,0,,3,0.00538042624,0.00184692251,0.00891392996,0.000128084 8.39"
    "200002e-05,0.000132201 8.5392e-05,1,vm,\n"
    "dots,16x16,gauss,point,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,2,2,1,0,0.37,0.11,0,refused: metho"
    "d point: point sampling has no prefilter; it is measured against the box reference (use "
    "-f box),,,,,,,,,,,,,,,,,,,,,,,2,vm,\n"
    "dots,16x16,gauss,jitter,\"jitter:spp=16,seq=stratified\",16,0.0251753532,0.00195251915,0"
    ".402723105,1,1,31.9804886,0.0419159835,0.00747022512,0.662822809,27.5524068,0.0006337984"
    "09,0.000120701928,0.000513096481,0.820430398,0.0003106165,0.000262109,0.000359124,1213.3"
    "457,75.8341064,4096,256,1,4,2,0.00805494015,0.000942634115,0.174526266,3.00291096,0.0585"
    "9375,2,2,1,0,0.37,0.11,1,,0.0003106165,6.8599964e-05,7.19173267e-05,,,,0.02,0,0.00031381"
    "85,1.01030853,3.37,3.37,0.688917836,0,0,,3,0.0152931808,-0.0174031012,0.0479894628,0.000"
    "359124 0.000262109,0.000364025 0.000263612,3,vm,\n"
    "crow,16x16,box,point,point,1,0.448106151,0.404995319,0.672132407,2,13,6.9723819,0.503305"
    "971,0.421445768,0.750805946,5.96335834,0.200799122,0.0480725115,0.152726611,0.0334777891"
    ",1.34504999e-05,1.28749998e-05,1.40259999e-05,52.5410151,52.5410151,256,0,0,4,2,0.340609"
    "189,0.30081852,0.555275218,0.128,,2,2,1,0,0.37,0.11,1,,1.34504999e-05,8.1387998e-07,8.53"
    "237655e-07,,,,0.02,0,1.5264e-05,1.13482771,3.37,3.37,0,0,0,,1,,,,1.28749998e-05 1.402599"
    "99e-05,1.4878e-05 1.565e-05,4,vm,\n"
    "crow,16x16,box,jitter,\"jitter:spp=16,seq=stratified\",13.5,0.0995956762,0.0715573174,0."
    "309434097,11,9,20.0351903,0.0714397129,0.0509576922,0.228530909,22.921206,0.00991929872,"
    "0.00170261587,0.00821668286,0.283793401,0.000143358,0.000137783,0.000148933,559.992188,4"
    "1.4809028,3456,216,0.84375,4,2,0.0719679457,0.0744401353,0.20491785,0.0274528155,,2,2,1,"
    "0,0.37,0.11,1,,0.000143358,7.88424084e-06,8.2655076e-06,,,,0.02,0,0.000145162,1.01258388"
    ",3.37,3.37,0,0,0,,3,0.105895753,0.0882670998,0.123524405,0.000148933 0.000137783,0.00015"
    "0918 0.000139406,5,vm,\n"
    "crow,16x16,gauss,point,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,2,2,1,0,0.37,0.11,0,refused: metho"
    "d point: point sampling has no prefilter; it is measured against the box reference (use "
    "-f box),,,,,,,,,,,,,,,,,,,,,,,6,vm,\n"
    "crow,16x16,gauss,jitter,\"jitter:spp=16,seq=stratified\",15.75,0.178892827,0.13443968,0."
    "485928726,9,6,14.9481415,0.158443501,0.115536486,0.603639362,16.0025114,0.0320026436,0.0"
    "070057903,0.0249968533,0.0583197062,0.022010145,0.015474306,0.028545984,85977.1289,5458."
    "86533,4032,252,0.984375,4,2,0.132077327,0.141275702,0.342616703,0.0910802649,,2,2,1,0,0."
    "37,0.11,1,,0.022010145,0.00924307216,0.0096900494,,,,0.02,0,0.010671963,0.484865638,3.66"
    ",3.66,1.53625029,0,1,busy,3,0.191908067,0.159944393,0.223871741,0.028545984 0.015474306,"
    "0.013874518 0.007469408,7,vm,\n";

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    assert_true(n < sizeof buf - 1);
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

/* The length of the CSV cell at s (quotes respected). */
static size_t cell_len(const char *s)
{
    int quoted = 0;
    size_t n = 0;
    for (; s[n] && (quoted || (s[n] != ',' && s[n] != '\n')); n++)
        if (s[n] == '"')
            quoted = !quoted;
    return n;
}

static void path_of(char *path, size_t len, const char *name)
{
    snprintf(path, len, "%s/%s", dir, name);
}

static void test_header_is_the_table(void **state)
{
    (void)state;
    char path[256], want[4096] = "";
    path_of(path, sizeof path, "empty.csv");
    assert_int_equal(aa_rows_write_csv(path, NULL, 0), AA_OK);
    size_t k = 0;
    for (; aa_results_column(k); k++) {
        if (k)
            strcat(want, ",");
        strcat(want, aa_results_column(k));
    }
    strcat(want, "\n");
    assert_true(k > 40);
    assert_string_equal(slurp(path, NULL), want);
    /* the previous writer's header is the list's start: columns are added
     * after it */
    size_t old_len = (size_t)(strchr(old_csv, '\n') - old_csv);
    assert_int_equal(strncmp(old_csv, want, old_len), 0);
    assert_true(want[old_len] == ',' &&
                strstr(want + old_len, ",lag,flip,edge_rmse,init_seconds,init_cpu_seconds,"
                                       "ref_bound,ref_scanned\n"));
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(path, &rows, &n), AA_OK);
    assert_int_equal(n, 0);
    free(rows);
}

/* old_csv with its header's column `from` renamed `to` ("" drops it from
 * the header and every row). */
static int parse_edited(const char *from, const char *to)
{
    char text[sizeof old_csv + 64], *o = text;
    const char *line = old_csv;
    int col = -1;
    for (int row = 0; *line; row++) {
        const char *end = strchr(line, '\n');
        int f = 0, quoted = 0;
        const char *cell = line;
        for (const char *c = line; c <= end; c++) {
            if (*c == '"')
                quoted = !quoted;
            if ((*c == ',' && !quoted) || c == end) {
                size_t len = (size_t)(c - cell);
                if (row == 0 && len == strlen(from) && !strncmp(cell, from, len))
                    col = f;
                int drop = f == col && !*to;
                if (row == 0 && f == col && *to) {
                    o += sprintf(o, "%s%s", f ? "," : "", to);
                } else if (!drop) {
                    if (f && !(f == 1 && col == 0 && !*to))
                        *o++ = ',';
                    memcpy(o, cell, len);
                    o += len;
                }
                f++;
                cell = c + 1;
            }
        }
        *o++ = '\n';
        line = end + 1;
    }
    assert_true(col >= 0);
    aa_row *rows;
    size_t n;
    int st = aa_rows_parse_csv("edited.csv", text, (size_t)(o - text), &rows, &n);
    free(rows);
    return st;
}

static void test_header_refused(void **state)
{
    (void)state;
    assert_int_equal(parse_edited("case", "colour"), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "unknown column \"colour\""));
    assert_int_equal(parse_edited("rmse", "mae"), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "\"mae\" given twice"));
    const char *required[] = {"size", "filter", "method", "rmse", "max_err", "seed", "time",
                              "vx", "vy", "ok"};
    for (size_t k = 0; k < sizeof required / sizeof *required; k++) {
        assert_int_equal(parse_edited(required[k], ""), AA_EINVAL);
        char want[64];
        snprintf(want, sizeof want, "no column \"%s\"", required[k]);
        if (!strstr(aa_last_error(), want))
            fail_msg("without %s: %s", required[k], aa_last_error());
    }
    /* an optional column may be missing (older files) */
    assert_int_equal(parse_edited("times", ""), AA_OK);
    assert_int_equal(parse_edited("case", ""), AA_OK);
}

static void test_old_file_round_trip(void **state)
{
    (void)state;
    aa_row *rows;
    size_t n, len;
    assert_int_equal(aa_rows_parse_csv("old.csv", old_csv, sizeof old_csv - 1, &rows, &n), AA_OK);
    assert_int_equal(n, 8);
    char path[256];
    path_of(path, sizeof path, "again.csv");
    assert_int_equal(aa_rows_write_csv(path, rows, n), AA_OK);
    const char *back = slurp(path, &len);
    /* cell by cell; the times' statistics are not read but recomputed
     * from the times, written with nine digits: they may differ in the
     * last digit.  The columns added since (flip, edge_rmse, init_seconds,
     * init_cpu_seconds, ref_bound, ref_scanned) are written after the old
     * ones, empty: the old file has no value for them */
    static const char *const recomputed[] = {"render_seconds_mean", "render_seconds_sd",
                                             "render_seconds_mad", "render_seconds_ci_lo",
                                             "render_seconds_ci_hi"};
    const char *a = old_csv, *b = back;
    int cells = 0, header = 1;
    for (size_t col = 0; *a || *b; col++, cells++) {
        size_t na = cell_len(a), nb = cell_len(b);
        const char *name = aa_results_column(col);
        assert_non_null(name);
        int skip = 0;
        for (size_t k = 0; k < sizeof recomputed / sizeof *recomputed; k++)
            skip |= !strcmp(name, recomputed[k]);
        if (!skip && (na != nb || memcmp(a, b, na)))
            fail_msg("column %s: %.*s, read and written back %.*s", name, (int)na, a, (int)nb, b);
        if (a[na] == '\n' && b[nb] == ',') { /* the added columns: named, then empty */
            const char *end = strchr(b, '\n');
            assert_non_null(end);
            if (header)
                assert_int_equal(strncmp(b + nb, ",lag,flip,edge_rmse,init_seconds,init_cpu_"
                                         "seconds,ref_bound,ref_scanned\n", 72), 0);
            else
                for (const char *c = b + nb; c < end; c++)
                    assert_true(*c == ',');
            nb = (size_t)(end - b);
        }
        assert_true(a[na] == b[nb]); /* both end the cell, or the line */
        if (a[na] == '\n')
            col = (size_t)-1, header = 0;
        a += na + (a[na] != '\0');
        b += nb + (b[nb] != '\0');
    }
    assert_int_equal(cells, 9 * 68);
    free(rows);
}

static aa_row row_of(const char *pattern, const char *method, int ok)
{
    aa_row r;
    memset(&r, 0, sizeof r);
    snprintf(r.pattern, sizeof r.pattern, "%s", pattern);
    snprintf(r.filter, sizeof r.filter, "box");
    snprintf(r.method, sizeof r.method, "%s", method);
    snprintf(r.canonical, sizeof r.canonical, "%s", method);
    r.w = 32, r.h = 16;
    r.threads = 2, r.reps = 1, r.seeds = 1;
    r.seed = UINT64_MAX;
    r.t = 0.5, r.vx = 0.25, r.vy = -1.5;
    r.case_index = -1;
    r.tm.popping = NAN;
    r.ok = ok;
    if (!ok) {
        snprintf(r.note, sizeof r.note, "refused: \"quoted\", with a comma");
        return r;
    }
    /* values of at most nine significant digits: written exactly */
    r.spp = 4, r.m.rmse = 0.125, r.m.mae = 0.0625, r.m.max_err = 0.75;
    r.m.max_at[0] = 31, r.m.max_at[1] = 15;
    r.m.psnr = INFINITY, r.m.rmse_enc = 0.25, r.m.mae_enc = 0.5, r.m.max_err_enc = 1;
    r.m.psnr_enc = 18.0625, r.m.alias_total = 3e-5, r.m.alias_low = 1e-5, r.m.alias_high = 2e-5;
    r.m.ssim = -0.5, r.seconds = 0.001953125, r.seconds_min = 0.001, r.seconds_max = 0.003;
    r.ns_per_pixel = 3814.69727, r.ns_per_sample = 953.674316;
    r.samples = (1ull << 60) + 1, r.expensive_pixels = 7, r.expensive_fraction = 0.013671875;
    return r;
}

/* Fields written, compared between a row and the row read back. */
static void assert_rows_equal(const aa_row *a, const aa_row *b)
{
    assert_string_equal(a->pattern, b->pattern);
    assert_string_equal(a->filter, b->filter);
    assert_string_equal(a->method, b->method);
    assert_string_equal(a->canonical, b->canonical);
    assert_string_equal(a->note, b->note);
    assert_string_equal(a->host, b->host);
    assert_string_equal(a->inputs, b->inputs);
    assert_true(a->w == b->w && a->h == b->h && a->ok == b->ok && a->temporal == b->temporal);
    assert_true(a->threads == b->threads && a->reps == b->reps && a->seed == b->seed);
    assert_true(a->t == b->t && a->vx == b->vx && a->vy == b->vy);
    assert_true(a->case_index == b->case_index && a->seeds == b->seeds);
    if (a->ok) {
        assert_memory_equal(&a->m, &b->m, sizeof a->m);
        assert_true(a->spp == b->spp && a->seconds == b->seconds);
        assert_true(a->seconds_min == b->seconds_min && a->seconds_max == b->seconds_max);
        assert_true(a->ns_per_pixel == b->ns_per_pixel && a->ns_per_sample == b->ns_per_sample);
        assert_true(a->samples == b->samples && a->expensive_pixels == b->expensive_pixels);
        assert_true(a->expensive_fraction == b->expensive_fraction);
        assert_int_equal(a->timing.n, b->timing.n);
        for (int k = 0; k < a->timing.n; k++)
            assert_true(a->timing.wall[k] == b->timing.wall[k] &&
                        a->timing.cpu[k] == b->timing.cpu[k]);
        assert_true(a->timing.n == 0 || (a->timing.cpu_median == b->timing.cpu_median &&
                                         a->timing.steal == b->timing.steal &&
                                         a->timing.target_ci == b->timing.target_ci));
        assert_int_equal(a->timing.noisy, b->timing.noisy);
    }
    if (a->temporal) {
        assert_true(a->tm.frames == b->tm.frames && a->tm.window == b->tm.window);
        assert_true(a->tm.eye_rmse == b->tm.eye_rmse && a->tm.conservation == b->tm.conservation);
        assert_true(a->tm.popping == b->tm.popping || (isnan(a->tm.popping) && isnan(b->tm.popping)));
    }
    if (a->seeds > 1)
        assert_true(a->rmse_mean == b->rmse_mean && a->rmse_ci_lo == b->rmse_ci_lo &&
                    a->rmse_ci_hi == b->rmse_ci_hi);
}

static aa_row rows_made[4];

static void make_rows(void)
{
    rows_made[0] = row_of("crow", "point", 1);
    rows_made[1] = row_of("star", "supersample:n=3,pattern=grid", 0);
    aa_row *t = &rows_made[2];
    *t = row_of("dots", "hexagon", 1);
    t->temporal = 1;
    t->tm.frames = 24, t->tm.window = 6, t->tm.eye_rmse = 0.03125, t->tm.flicker_mean = 0.5;
    t->tm.flicker_max = 0.75, t->tm.conservation = 0.0078125, t->tm.popping = 0.25;
    t->case_index = 12;
    snprintf(t->host, sizeof t->host, "node-1");
    snprintf(t->inputs, sizeof t->inputs, "file fnv1a 0123456789abcdef bytes 128; plugin fnv1a "
             "fedcba9876543210 bytes 24888");
    aa_row *s = &rows_made[3];
    *s = row_of("crow", "jitter", 1);
    s->seeds = 3, s->rmse_mean = 0.1875, s->rmse_ci_lo = 0.125, s->rmse_ci_hi = 0.25;
    s->timing.n = 3;
    const double wall[3] = {0.001, 0.00101, 0.0011}, cpu[3] = {0.002, 0.00202, 0.0022};
    memcpy(s->timing.wall, wall, sizeof wall);
    memcpy(s->timing.cpu, cpu, sizeof cpu);
    /* the statistics as a run computes them (and a reader recomputes) */
    aa_time_stats_compute(s->timing.wall, 3, &s->timing.stats);
    s->timing.cpu_median = 0.00202, s->timing.steal = 0.5, s->timing.target_ci = 0.02;
    s->timing.noisy = AA_NOISY_BUSY | AA_NOISY_OUTLIERS;
}

static void test_rows_round_trip(void **state)
{
    (void)state;
    make_rows();
    char path[256], path2[256];
    path_of(path, sizeof path, "made.csv");
    path_of(path2, sizeof path2, "made2.csv");
    assert_int_equal(aa_rows_write_csv(path, rows_made, 4), AA_OK);
    aa_row *back;
    size_t n, len, len2;
    assert_int_equal(aa_rows_read_csv(path, &back, &n), AA_OK);
    assert_int_equal(n, 4);
    for (size_t k = 0; k < n; k++)
        assert_rows_equal(&rows_made[k], &back[k]);
    assert_int_equal(aa_rows_write_csv(path2, back, n), AA_OK);
    char *first = strdup(slurp(path, &len));
    assert_non_null(first);
    assert_string_equal(slurp(path2, &len2), first);
    assert_non_null(strstr(first, ",1152921504606846977,")); /* 2^60 + 1 */
    assert_non_null(strstr(first, ",18446744073709551615,")); /* the seed */
    assert_non_null(strstr(first, ",inf,"));                   /* the PSNR */
    free(first);
    free(back);
}

static double num_of(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(v))
        fail_msg("%s is not a number", key);
    return v->valuedouble;
}

static void test_json(void **state)
{
    (void)state;
    make_rows();
    char path[256];
    path_of(path, sizeof path, "results.json");
    assert_int_equal(aa_rows_write_json(path, rows_made, 4), AA_OK);
    const char *text = slurp(path, NULL);
    /* the frame, then one row a line */
    const char *frame = "{\n  \"context\": null,\n  \"results\": [\n  {\"pattern\":";
    assert_int_equal(strncmp(text, frame, strlen(frame)), 0);
    int lines = 0;
    for (const char *c = text; *c; c++)
        lines += *c == '\n';
    assert_int_equal(lines, 3 + 4 + 2);
    cJSON *doc = cJSON_Parse(text);
    assert_non_null(doc);
    const cJSON *res = cJSON_GetObjectItemCaseSensitive(doc, "results");
    assert_int_equal(cJSON_GetArraySize(res), 4);
    const cJSON *r0 = cJSON_GetArrayItem(res, 0), *r1 = cJSON_GetArrayItem(res, 1),
                *r2 = cJSON_GetArrayItem(res, 2), *r3 = cJSON_GetArrayItem(res, 3);
    assert_true(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(r0, "ok")));
    assert_string_equal(cJSON_GetObjectItemCaseSensitive(r0, "size")->valuestring, "32x16");
    assert_true(num_of(r0, "rmse") == 0.125 && num_of(r0, "psnr_enc") == 18.0625);
    assert_true(num_of(r0, "ns_per_pixel") == 3814.69727);
    assert_true(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(r0, "psnr"))); /* infinite */
    assert_non_null(strstr(text, "\"samples\":1152921504606846977"));
    assert_non_null(strstr(text, "\"seed\":18446744073709551615"));
    const cJSON *at = cJSON_GetObjectItemCaseSensitive(r0, "max_at");
    assert_int_equal(cJSON_GetArraySize(at), 3);
    assert_int_equal(cJSON_GetArrayItem(at, 0)->valueint, 31);
    const cJSON *motion = cJSON_GetObjectItemCaseSensitive(r0, "motion");
    assert_true(cJSON_GetArrayItem(motion, 1)->valuedouble == -1.5);
    assert_null(cJSON_GetObjectItemCaseSensitive(r0, "timing"));
    assert_true(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(r0, "noisy")));
    /* a refused row: no measurements, its note escaped */
    assert_true(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(r1, "ok")));
    assert_null(cJSON_GetObjectItemCaseSensitive(r1, "rmse"));
    assert_null(cJSON_GetObjectItemCaseSensitive(r1, "seeds"));
    assert_string_equal(cJSON_GetObjectItemCaseSensitive(r1, "note")->valuestring,
                        rows_made[1].note);
    const cJSON *tm = cJSON_GetObjectItemCaseSensitive(r2, "temporal");
    assert_true(num_of(tm, "frames") == 24 && num_of(tm, "popping") == 0.25);
    assert_true(num_of(tm, "conservation") == 0.0078125);
    const cJSON *timing = cJSON_GetObjectItemCaseSensitive(r3, "timing");
    const cJSON *times = cJSON_GetObjectItemCaseSensitive(timing, "times");
    assert_int_equal(cJSON_GetArraySize(times), 3);
    assert_true(cJSON_GetArrayItem(times, 1)->valuedouble == 0.00101);
    assert_true(num_of(timing, "cpu_median") == 0.00202 && num_of(timing, "n") == 3);
    assert_true(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(r3, "noisy")));
    assert_string_equal(cJSON_GetObjectItemCaseSensitive(r3, "noise")->valuestring,
                        "outliers+busy");
    assert_true(num_of(r3, "seeds") == 3 && num_of(r3, "rmse_mean") == 0.1875);
    const cJSON *ci = cJSON_GetObjectItemCaseSensitive(r3, "rmse_ci");
    assert_true(cJSON_GetArrayItem(ci, 0)->valuedouble == 0.125);
    cJSON_Delete(doc);
    /* the timing members alone, inside an object */
    char *members = aa_row_timing_json(&rows_made[3]);
    assert_non_null(members);
    char obj[8192];
    snprintf(obj, sizeof obj, "{\"a\": 1%s}", members);
    free(members);
    cJSON *o = cJSON_Parse(obj);
    assert_non_null(o);
    assert_true(num_of(o, "seeds") == 3);
    assert_non_null(cJSON_GetObjectItemCaseSensitive(o, "timing"));
    cJSON_Delete(o);
    members = aa_row_timing_json(&rows_made[1]); /* refused: none */
    assert_string_equal(members, "");
    free(members);
}

/* A view whose reference is not proven everywhere is named once, at its
 * first measured row: pixels bounded by an estimate, or a bound above the
 * promise; a proven one, a refused row and a file without the columns
 * (NaN) are not. */
static void test_reference_unproven(void **state)
{
    (void)state;
    static const struct {
        const char *pattern;
        int w, ok;
        double bound, scanned;
        int named;
    } c[] = {
        {"crow", 16, 0, 1e-13, 3, 0},        /* refused: its reference not used */
        {"crow", 16, 1, 1e-13, 3, 1},        /* 3 pixels estimated */
        {"crow", 16, 1, 1e-13, 3, 0},        /* the same view again */
        {"crow", 32, 1, 2e-13, 0, 0},        /* proven */
        {"star", 16, 1, 2e-12, 0, 1},        /* above the promise */
        {"star", 32, 1, NAN, NAN, 0},        /* not known */
        {"star", 48, 1, AA_TRUTH_BOUND, 0, 0}, /* at the promise */
    };
    enum { N = sizeof c / sizeof *c };
    aa_row rows[N];
    for (size_t k = 0; k < N; k++) {
        memset(&rows[k], 0, sizeof rows[k]);
        snprintf(rows[k].pattern, sizeof rows[k].pattern, "%s", c[k].pattern);
        snprintf(rows[k].filter, sizeof rows[k].filter, "box");
        rows[k].w = rows[k].h = c[k].w;
        rows[k].ok = c[k].ok;
        rows[k].ref_bound = c[k].bound, rows[k].ref_scanned = c[k].scanned;
    }
    for (size_t k = 0; k < N; k++)
        if (aa_row_reference_unproven(rows, k) != c[k].named)
            fail_msg("row %zu (%s %d): named %d, expected %d", k, c[k].pattern, c[k].w,
                     aa_row_reference_unproven(rows, k), c[k].named);
}

int main(void)
{
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_header_is_the_table), cmocka_unit_test(test_header_refused),
        cmocka_unit_test(test_old_file_round_trip), cmocka_unit_test(test_rows_round_trip),
        cmocka_unit_test(test_json), cmocka_unit_test(test_reference_unproven),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        failed++;
    return failed;
}
