/*
 * test_run_faults.c: faults during `aabench run` and `aabench check` never
 * give a wrong result, lose a measured row, or fail silently.
 *
 *  - The gate cannot be switched off: a baseline whose errors are nan,
 *    empty, inf or out of range, whose time is nan, whose size has junk
 *    after it, that names a column twice, whose ok=0 rows hold measurements
 *    or give no reason, is refused naming the file, the line and the
 *    column (by the CSV reader `check` calls, in this process; through
 *    `check`, exit 2, for the first bad value and the header's faults); one
 *    with a UTF-8 byte-order mark is read; a row with ok=0 is a recorded
 *    refusal, confirmed when the method still refuses and a
 *    failure when it now runs.
 *  - results.csv and results.json are rewritten after every case: a run
 *    killed with SIGKILL while a method hangs keeps the cases before it
 *    (and its isolated case dies with it).
 *  - A method's NaN, 1.5 or error is a failed case (ok=0, the first bad
 *    pixel and the count in the note), the run goes on and exits 1 naming
 *    the failed cases; in process and isolated alike.
 *  - In process, a method's exit() ends the run with status 3 and a
 *    message (the rows before it kept), a write past its image fails its
 *    case, and a rounding mode it changes is restored: the next row is the
 *    one of a run without it.
 *  - A method's unknown status is named with its number, and impossible
 *    counters (negative, more expensive pixels than pixels) fail the case.
 *  - aa_run and the CSV reader give NULL and 0 when they refuse early, and
 *    `check` with a baseline row that cannot run (65536x65536) says so
 *    instead of freeing an uninitialised pointer.
 *  - Isolation: a method that crashes, aborts, ends the process or never
 *    returns is a failed case ("crashed (signal 11)", "timed out after
 *    2 s") in `run` and in `check`; isolated rows of real methods (point,
 *    jitter, area) equal in-process rows bit for bit, after the process has
 *    used OpenMP (libgomp is not fork-safe unless its threads are released).
 *  - The montage drawn after the cases under a memory limit it cannot fit:
 *    exit status 3 (resources), not 2 (input), the rows kept.
 *  - Checks before work: -s 1x65536 (the montage), -m jitter:spp=15, an
 *    --out of 100 kB or with a 300-character name, a file in place of a
 *    folder: refused, nothing created; long inputs are shortened in
 *    messages, never the reason; control characters are escaped (in the
 *    library's messages too).
 *
 * Known answers come from the faulty plug-ins' sources (tests/plugin_faulty.c
 * puts its fault at pixel (1, 2) channel 1 and at the last pixel's channel
 * 2, so two values, the first in row-major order at (1, 2)), from the
 * signal numbers of <signal.h>, and from the header written here; the CSV
 * written by the run is read here with a reader of this file's own.
 *
 * Runs go through the library's run folder in this process (lib_run: what
 * `aabench run` does but its printing); the command is started for what
 * only a process shows (a run killed by SIGKILL, methods that crash) and
 * for `check`.
 */
#include "bench.h"
#include "support.h"

#include <dirent.h>
#include <errno.h>
#include <fenv.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static char dir[] = "/tmp/aabench-runfaults-XXXXXX";
static char out_text[1 << 16], err_text[1 << 16];

/* ---- running the command ---- */

static void slurp(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, len - 1, f) : 0;
    buf[n] = '\0';
    if (f)
        fclose(f);
}

/* Run the command; its standard output and error in out_text, err_text;
 * the exit status or 128 + the signal. */
static int run(const char *const *args)
{
    char out[600], err[600];
    snprintf(out, sizeof out, "%s/stdout", dir);
    snprintf(err, sizeof err, "%s/stderr", dir);
    int code = support_wait(support_aabench_spawn(args, NULL, out, err));
    slurp(out, out_text, sizeof out_text);
    slurp(err, err_text, sizeof err_text);
    return code;
}

#define RUN(...) run((const char *const[]){__VA_ARGS__, NULL})

/* `run ARGS...` through the library's run folder in this process, as the
 * command does but for its printing (the plug-ins are loaded once, by the
 * set-up): the exit status the command gives (1 when a case failed), the
 * library's message in err_text, the failed cases counted in lib_failed. */
static size_t lib_failed;

static int lib_run(const char *const *args)
{
    err_text[0] = '\0';
    int st = support_lib_run(args, getenv("AABENCH_CACHE"), &lib_failed);
    if (st) {
        snprintf(err_text, sizeof err_text, "%s", aa_last_error());
        return aa_exit_code(st);
    }
    return lib_failed > 0;
}

#define LIB(...) lib_run((const char *const[]){__VA_ARGS__, NULL})

static void expect_in(const char *text, const char *needle, const char *what)
{
    if (!strstr(text, needle))
        fail_msg("%s: \"%s\" not in:\n%s", what, needle, text);
}

static void plugin(const char *name, char *path, size_t len)
{
    const char *exe = getenv("AABENCH");
    const char *slash = strrchr(exe, '/');
    assert_non_null(slash);
    snprintf(path, len, "%.*s/tests/%s.so", (int)(slash - exe), exe, name);
    assert_int_equal(access(path, R_OK), 0);
}

static void path_in(char *buf, size_t len, const char *name)
{
    snprintf(buf, len, "%s/%s", dir, name);
}

static int exists(const char *path)
{
    struct stat sb;
    return lstat(path, &sb) == 0;
}

static void put_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

/* ---- results.csv, read by this file's own reader ---- */

#define MAX_ROWS 16
#define MAX_COLS 80
typedef struct table {
    int nrows, ncols;
    char head[MAX_COLS][64];
    char cell[MAX_ROWS][MAX_COLS][600];
} table;

/* One line of RFC 4180 fields (no line breaks inside: notes have none). */
static int split(const char *line, char out[][600], int max)
{
    int n = 0;
    const char *p = line;
    for (;;) {
        assert_true(n < max);
        size_t k = 0;
        if (*p == '"') {
            for (p++; *p && !(*p == '"' && p[1] != '"'); p++) {
                if (*p == '"')
                    p++;
                if (k + 1 < 600)
                    out[n][k++] = *p;
            }
            if (*p == '"')
                p++;
        } else {
            while (*p && *p != ',' && *p != '\n')
                if (k + 1 < 600)
                    out[n][k++] = *p++;
        }
        out[n++][k] = '\0';
        if (*p != ',')
            return n;
        p++;
    }
}

static table *read_table(const char *path)
{
    static table t;
    static char cells[MAX_COLS][600];
    memset(&t, 0, sizeof t);
    FILE *f = fopen(path, "r");
    if (!f)
        return NULL;
    char line[8192];
    for (int r = -1; fgets(line, sizeof line, f); r++) {
        line[strcspn(line, "\n")] = '\0';
        int n = split(line, cells, MAX_COLS);
        if (r < 0) {
            t.ncols = n;
            for (int c = 0; c < n; c++)
                snprintf(t.head[c], sizeof t.head[c], "%.63s", cells[c]);
            continue;
        }
        assert_true(r < MAX_ROWS);
        assert_int_equal(n, t.ncols);
        memcpy(t.cell[r], cells, sizeof cells);
        t.nrows = r + 1;
    }
    fclose(f);
    return &t;
}

static const char *cell(const table *t, int r, const char *col)
{
    for (int c = 0; c < t->ncols; c++)
        if (!strcmp(t->head[c], col))
            return t->cell[r][c];
    fail_msg("no column %s", col);
    return NULL;
}

/* ---- baselines written here ---- */

/* The columns of results.csv, in order (README.md, "The benchmark"). */
static const char *const columns[] = {
    "pattern", "size", "filter", "method", "canonical", "spp", "rmse", "mae", "max_err",
    "max_i", "max_j", "psnr", "rmse_enc", "mae_enc", "max_err_enc", "psnr_enc", "alias_total",
    "alias_low", "alias_high", "ssim", "render_seconds", "render_seconds_min",
    "render_seconds_max", "ns_per_pixel", "ns_per_sample", "samples", "expensive_pixels",
    "expensive_fraction", "frames", "window", "eye_rmse", "flicker_mean", "flicker_max",
    "conservation", "popping", "threads", "reps", "seed", "time", "vx", "vy", "ok", "note",
    NULL};

/* A row that ran, for `method` on crow 16x16 `filter`: errors at their
 * largest possible values, so any rerun is within them. */
static const char *good_value(const char *col)
{
    static const char *const v[][2] = {
        {"pattern", "crow"}, {"size", "16x16"}, {"filter", "box"}, {"method", "point"},
        {"canonical", "point"}, {"spp", "1"}, {"rmse", "0.9"}, {"mae", "0.5"}, {"max_err", "1"},
        {"max_i", "3"}, {"max_j", "4"}, {"psnr", "0.915"}, {"rmse_enc", "0.9"},
        {"mae_enc", "0.5"}, {"max_err_enc", "1"}, {"psnr_enc", "0.915"},
        {"alias_total", "0.1"}, {"alias_low", "0.05"}, {"alias_high", "0.05"}, {"ssim", "0.5"},
        {"render_seconds", "0.001"}, {"render_seconds_min", "0.001"},
        {"render_seconds_max", "0.002"}, {"ns_per_pixel", "3.9"}, {"ns_per_sample", "3.9"},
        {"samples", "256"}, {"expensive_pixels", "0"}, {"expensive_fraction", "0"},
        {"threads", "1"}, {"reps", "1"}, {"seed", "1"}, {"time", "0"}, {"vx", "0"}, {"vy", "0"},
        {"ok", "1"}};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (!strcmp(v[k][0], col))
            return v[k][1];
    return ""; /* temporal metrics, note */
}

static int column_number(const char *col)
{
    for (int k = 0; columns[k]; k++)
        if (!strcmp(columns[k], col))
            return k + 1;
    fail_msg("no column %s", col);
    return 0;
}

/* A row: the good one with `col` (if not NULL) set to `value`; `method`
 * and `filter` replaced when given. */
static void row_text(char *buf, size_t len, const char *method, const char *filter,
                     const char *col, const char *value)
{
    size_t n = 0;
    for (int k = 0; columns[k]; k++) {
        const char *v = good_value(columns[k]);
        if (method && !strcmp(columns[k], "method"))
            v = method;
        if (method && !strcmp(columns[k], "canonical"))
            v = method;
        if (filter && !strcmp(columns[k], "filter"))
            v = filter;
        if (col && !strcmp(columns[k], col))
            v = value;
        n += (size_t)snprintf(buf + n, len - n, "%s%s", k ? "," : "", v);
    }
    snprintf(buf + n, len - n, "\n");
}

static void header_text(char *buf, size_t len)
{
    size_t n = 0;
    for (int k = 0; columns[k]; k++)
        n += (size_t)snprintf(buf + n, len - n, "%s%s", k ? "," : "", columns[k]);
    snprintf(buf + n, len - n, "\n");
}

/* A baseline: the header, a good row (line 2), then `row3` (line 3). */
static void write_baseline(const char *path, const char *row3)
{
    char text[8192], head[2048], good[2048];
    header_text(head, sizeof head);
    row_text(good, sizeof good, NULL, NULL, NULL, NULL);
    snprintf(text, sizeof text, "%s%s%s", head, good, row3 ? row3 : "");
    put_file(path, text, strlen(text));
}

/* `check` refuses the baseline: exit 2, naming the file, line and column,
 * with `why` in the message, and nothing checked. */
/* The baseline at `path` refused at `line`, column `col` (NULL: none), for
 * `why`: by `check` (exit 2, nothing counted) when `command`, else by the
 * reader `check` calls (aa_rows_read_csv, AA_EINVAL) in this process, which
 * spares a start of the command a row (0.2 s of CPU under the sanitizers)
 * for the same message. */
static void expect_refused(const char *path, size_t line, const char *col, const char *why,
                           int command)
{
    char where[900];
    if (col)
        snprintf(where, sizeof where, "%s:%zu: column %d (%s): ", path, line, column_number(col),
                 col);
    else
        snprintf(where, sizeof where, "%s:%zu: ", path, line);
    if (!command) {
        aa_row *rows = (aa_row *)1;
        size_t n = 1;
        if (aa_rows_read_csv(path, &rows, &n) != AA_EINVAL)
            fail_msg("%s (%s): read, not refused", path, why);
        assert_true(rows == NULL && n == 0);
        expect_in(aa_last_error(), where, why);
        expect_in(aa_last_error(), why, why);
        return;
    }
    int code = RUN("check", "--baseline", path, "--threads", "1");
    if (code != 2)
        fail_msg("check --baseline %s (%s): exit %d, not 2\n%s%s", path, why, code, out_text,
                 err_text);
    expect_in(err_text, where, why);
    expect_in(err_text, why, why);
    if (strstr(out_text, "within"))
        fail_msg("%s: some cases were counted within:\n%s", why, out_text);
}

static void test_baseline_strict(void **state)
{
    (void)state;
    char path[600], row[2048];
    path_in(path, sizeof path, "bad.csv");
    static const struct {
        const char *col, *value, *why;
    } bad[] = {
        {"rmse", "nan", "\"nan\" is not a number"},
        {"rmse", "", "empty, and a row with ok=1 needs it"},
        {"rmse", "inf", "\"inf\" is not a number"},
        {"max_err", "inf", "\"inf\" is not a number"},
        {"max_err", "-inf", "\"-inf\" is not a number"},
        {"rmse", "0x1p-2", "\"0x1p-2\" is not a number"},
        {"rmse", " 0.5", "\" 0.5\" is not a number"},
        {"rmse", "1.5", "1.5 is out of range (0 to 1)"},
        {"rmse", "1e999", "1e999 is not a finite number"},
        {"time", "nan", "\"nan\" is not a number"},
        {"vx", "inf", "\"inf\" is not a number"},
        {"size", "16x16junk", "size \"16x16junk\" is not WxH"},
        {"size", "99999999999999999999x16", "is out of range"},
        {"seed", "-1", "\"-1\" is not a whole number"},
        {"ok", "yes", "\"yes\" is neither 0 nor 1"},
        /* ok=0 with the good row's measurements: the first is spp */
        {"ok", "0", "a row with ok=0 (refused or failed) has no measurements"},
        {"pattern", "crow:curves=3", "must be even"},
        {"filter", "tent:r=nan", "r=nan: not a number"},
        {"max_i", "16", "is outside the 16x16 image"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        row_text(row, sizeof row, NULL, NULL, bad[k].col, bad[k].value);
        write_baseline(path, row);
        const char *col = !strcmp(bad[k].value, "0") ? "spp" : bad[k].col;
        expect_refused(path, 3, col, bad[k].why, k == 0); /* the command once */
    }

    /* a column named twice: the header is refused at line 1, column 44 */
    char text[8192], head[2048], good[2048];
    header_text(head, sizeof head);
    head[strlen(head) - 1] = '\0';
    row_text(good, sizeof good, NULL, NULL, NULL, NULL);
    good[strlen(good) - 1] = '\0';
    snprintf(text, sizeof text, "%s,rmse\n%s,0.0001\n", head, good);
    put_file(path, text, strlen(text));
    int code = RUN("check", "--baseline", path, "--threads", "1");
    assert_int_equal(code, 2);
    snprintf(row, sizeof row, "%s:1: column 44 (rmse): column \"rmse\" given twice", path);
    expect_in(err_text, row, "duplicate column");

    /* an unknown column, a required column missing */
    snprintf(text, sizeof text, "%s,colour\n%s,red\n", head, good);
    put_file(path, text, strlen(text));
    assert_int_equal(RUN("check", "--baseline", path), 2);
    snprintf(row, sizeof row, "%s:1: column 44 (colour): unknown column", path);
    expect_in(err_text, row, "unknown column");
    snprintf(text, sizeof text, "pattern,size,filter,method,rmse,seed,time,vx,vy,ok,note\n"
                                "crow,16x16,box,point,0.9,1,0,0,0,1,\n");
    put_file(path, text, strlen(text));
    assert_int_equal(RUN("check", "--baseline", path), 2);
    expect_in(err_text, "no column \"max_err\"", "missing column");

    /* a refusal without its reason; a row with a field too many */
    row_text(row, sizeof row, NULL, "tent", NULL, NULL);
    static const char *const measures[] = {
        "spp", "rmse", "mae", "max_err", "max_i", "max_j", "psnr", "rmse_enc", "mae_enc",
        "max_err_enc", "psnr_enc", "alias_total", "alias_low", "alias_high", "ssim",
        "render_seconds", "render_seconds_min", "render_seconds_max", "ns_per_pixel",
        "ns_per_sample", "samples", "expensive_pixels", "expensive_fraction"};
    /* empty measurements, ok=0, no note */
    {
        size_t n = 0;
        for (int k = 0; columns[k]; k++) {
            const char *v = good_value(columns[k]);
            for (size_t q = 0; q < sizeof measures / sizeof *measures; q++)
                if (!strcmp(columns[k], measures[q]))
                    v = "";
            if (!strcmp(columns[k], "ok"))
                v = "0";
            n += (size_t)snprintf(row + n, sizeof row - n, "%s%s", k ? "," : "", v);
        }
        snprintf(row + n, sizeof row - n, "\n");
    }
    write_baseline(path, row);
    expect_refused(path, 3, "note", "must give its reason in the note", 0);
    row_text(row, sizeof row, NULL, NULL, NULL, NULL);
    row[strlen(row) - 1] = '\0';
    strcat(row, ",extra\n");
    write_baseline(path, row);
    expect_refused(path, 3, NULL, "44 fields, the header has 43", 0);

    /* a UTF-8 byte-order mark before the header: read, and checked */
    header_text(head, sizeof head);
    snprintf(text, sizeof text, "\xef\xbb\xbf%s%s", head, good);
    strcat(text, "\n");
    put_file(path, text, strlen(text));
    code = RUN("check", "--baseline", path, "--threads", "1");
    if (code != 0)
        fail_msg("baseline with a byte-order mark: exit %d\n%s%s", code, out_text, err_text);
    expect_in(out_text, "check: 1 cases within", "byte-order mark");
}

/* A row with ok=0 is a recorded refusal: confirmed when the method still
 * refuses (point has no prefilter: it refuses tent), a failure when it now
 * runs. */
static void ok0_row(char *buf, size_t len, const char *filter, const char *note)
{
    size_t n = 0;
    for (int k = 0; columns[k]; k++) {
        const char *v = good_value(columns[k]);
        int c = column_number(columns[k]);
        if (c >= column_number("spp") && c <= column_number("popping"))
            v = "";
        if (!strcmp(columns[k], "filter"))
            v = filter;
        if (!strcmp(columns[k], "ok"))
            v = "0";
        if (!strcmp(columns[k], "note"))
            v = note;
        n += (size_t)snprintf(buf + n, len - n, "%s%s", k ? "," : "", v);
    }
    snprintf(buf + n, len - n, "\n");
}

static void test_baseline_refusal_recorded(void **state)
{
    (void)state;
    char path[600], row[2048];
    path_in(path, sizeof path, "refusal.csv");
    ok0_row(row, sizeof row, "tent", "refused: no prefilter");
    write_baseline(path, row);
    int code = RUN("check", "--baseline", path, "--threads", "1");
    if (code != 0)
        fail_msg("a true refusal: exit %d\n%s%s", code, out_text, err_text);
    expect_in(out_text, "check: 1 cases within", "true refusal");
    expect_in(out_text, "1 refusal confirmed", "true refusal");

    ok0_row(row, sizeof row, "box", "refused: made up");
    write_baseline(path, row);
    code = RUN("check", "--baseline", path, "--threads", "1");
    if (code != 1)
        fail_msg("a refusal that is not one: exit %d\n%s%s", code, out_text, err_text);
    expect_in(out_text,
              "FAIL point on crow 16x16 box: now runs a case its baseline records as refused",
              "made-up refusal");
}

/* ---- results kept when the run is killed ---- */

static int count_lines(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int n = 0, c;
    while ((c = fgetc(f)) != EOF)
        n += c == '\n';
    fclose(f);
    return n;
}

static void test_rows_kept_when_killed(void **state)
{
    (void)state;
    char faulty[1200], out[600], csv[700], json[700], so[700], se[700];
    plugin("plugin_faulty", faulty, sizeof faulty);
    path_in(out, sizeof out, "killed");
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    snprintf(json, sizeof json, "%s/results.json", out);
    path_in(so, sizeof so, "killed.out");
    path_in(se, sizeof se, "killed.err");
    /* the hanging method last: the cases before it are all there is */
    const char *args[] = {"run",  "--plugin", faulty, "-p",          "crow",       "-f", "box", "-s",
                          "16x16", "-m",      "point", "-m",         "area",       "-m",
                          "hang", "--reps",   "1",     "--no-images", "--no-plots", "-q",
                          "--out", out,       NULL};
    /* the hanging case's temporary folder, which its run killed with
     * SIGKILL cannot remove, in this test's folder (removed at teardown) */
    char tmp[600];
    path_in(tmp, sizeof tmp, "killed-tmp");
    assert_int_equal(mkdir(tmp, 0755), 0);
    char *saved = getenv("TMPDIR") ? strdup(getenv("TMPDIR")) : NULL;
    setenv("TMPDIR", tmp, 1);
    pid_t pid = support_aabench_spawn(args, NULL, so, se);
    if (saved) {
        setenv("TMPDIR", saved, 1);
        free(saved);
    } else {
        unsetenv("TMPDIR");
    }
    double t0 = aa_now();
    while (count_lines(csv) < 3) {
        int status;
        if (support_waitpid(pid, &status, WNOHANG) == pid)
            fail_msg("the run ended before it was killed");
        if (aa_now() - t0 > 90) {
            kill(pid, SIGKILL);
            support_waitpid(pid, &status, 0);
            fail_msg("after 90 s results.csv holds %d lines, not the 2 cases before the hang",
                     count_lines(csv));
        }
        struct timespec ts = {0, 50 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
    int status;
    assert_int_equal(kill(pid, SIGKILL), 0);
    assert_int_equal(support_waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    table *t = read_table(csv);
    assert_non_null(t);
    assert_int_equal(t->nrows, 2);
    assert_string_equal(cell(t, 0, "method"), "point");
    assert_string_equal(cell(t, 0, "ok"), "1");
    assert_string_equal(cell(t, 1, "method"), "area");
    assert_string_equal(cell(t, 1, "ok"), "1");
    /* area integrates the box exactly: its error is rounding */
    assert_true(strtod(cell(t, 1, "rmse"), NULL) < 1e-12);
    char text[1 << 14];
    slurp(json, text, sizeof text);
    expect_in(text, "\"method\":\"point\"", "results.json");
    expect_in(text, "\"method\":\"area\"", "results.json");
    /* the isolated case (its command line is the run's) died with the run */
    char cmd[900];
    /* "kille[d]": a pattern the shell running pgrep does not match */
    snprintf(cmd, sizeof cmd, "pgrep -f -- '%.*s[d]' >/dev/null", (int)strlen(out) - 1, out);
    for (t0 = aa_now(); system(cmd) == 0; ) {
        if (aa_now() - t0 > 10)
            fail_msg("the hanging case outlived its run");
        struct timespec ts = {0, 100 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
}

/* ---- bad values and errors are failed cases ---- */

static void test_bad_values_fail_case(void **state)
{
    (void)state;
    char out[600], csv[700];
    static const char *const modes[] = {"--no-isolate", "--isolate"};
    for (int m = 0; m < 2; m++) {
        snprintf(out, sizeof out, "%s/values%d", dir, m);
        snprintf(csv, sizeof csv, "%s/results.csv", out);
        int code = LIB("run", modes[m], "-p", "crow", "-s", "8x8", "-m", "nanout", "-m", "point",
                       "-m", "over", "-m", "fails",
                       "-f", "box", "--reps", "1", "--no-plots", "-q", "--out", out);
        if (code != 1)
            fail_msg("%s: exit %d, not 1\n%s%s", modes[m], code, out_text, err_text);
        table *t = read_table(csv);
        assert_non_null(t);
        assert_int_equal(t->nrows, 4);
        static const char *const method[] = {"nanout", "point", "over", "fails"};
        static const char *const note[] = {
            "failed: gave 2 values outside [0, 1] or not finite, the first nan at pixel (1, 2) "
            "channel 1",
            "",
            "failed: gave 2 values outside [0, 1] or not finite, the first 1.5 at pixel (1, 2) "
            "channel 1",
            "failed: method fails: fault test: this render fails on purpose"};
        for (int r = 0; r < 4; r++) {
            assert_string_equal(cell(t, r, "method"), method[r]);
            assert_string_equal(cell(t, r, "ok"), r == 1 ? "1" : "0");
            assert_string_equal(cell(t, r, "note"), note[r]);
            if (r != 1)
                assert_string_equal(cell(t, r, "rmse"), "");
        }
        assert_int_equal(lib_failed, 3);
        /* the case that ran has its images; the montage was made */
        char path[800];
        snprintf(path, sizeof path, "%s/images/crow-8x8-box-point.exr", out);
        assert_true(exists(path));
        snprintf(path, sizeof path, "%s/images/crow-8x8-box-nanout.exr", out);
        assert_false(exists(path));
        snprintf(path, sizeof path, "%s/montage.png", out);
        assert_true(exists(path));
    }
}

/* ---- the method contract ---- */

/* A render that returns a status no aa_status has is named with its number;
 * one that counts a negative number of samples (-5 stored in the unsigned
 * counter) or more expensive pixels than the image has (65 of 8x8) fails
 * its case: tests/plugin_failing.c's methods, in process and isolated. */
static void test_contract_faults(void **state)
{
    (void)state;
    char out[600], csv[700];
    static const char *const modes[] = {"--no-isolate", "--isolate"};
    for (int m = 0; m < 2; m++) {
        snprintf(out, sizeof out, "%s/contract%d", dir, m);
        snprintf(csv, sizeof csv, "%s/results.csv", out);
        int code = LIB("run", modes[m], "-p", "crow", "-s", "8x8", "-m", "oddstatus", "-m",
                       "negcount", "-m", "overcount", "-m", "point", "-f", "box", "--reps", "1",
                       "--no-plots", "--no-images", "-q", "--out", out);
        if (code != 1)
            fail_msg("%s: exit %d, not 1\n%s%s", modes[m], code, out_text, err_text);
        table *t = read_table(csv);
        assert_non_null(t);
        assert_int_equal(t->nrows, 4);
        static const char *const note[] = {
            "failed: method oddstatus: its render returned the unknown status 42 (the statuses "
            "are 0 to 5, aabench.h)",
            "failed: method negcount counted a negative number of samples (-5)",
            "failed: method overcount counted 65 expensive pixels in an image of 64", ""};
        for (int r = 0; r < 4; r++) {
            assert_string_equal(cell(t, r, "ok"), r == 3 ? "1" : "0");
            assert_string_equal(cell(t, r, "note"), note[r]);
        }
    }
}

/* ---- methods that harm the process they run in ---- */

/* A method that calls exit(0) in process: the run ends with status 3 and
 * says so, never 0 with the cases after it lost; the row before it is
 * kept.  Through the command, which exit() ends. */
static void test_exit_in_process(void **state)
{
    (void)state;
    char failing[1200], out[600], csv[700];
    plugin("plugin_failing", failing, sizeof failing);
    path_in(out, sizeof out, "exit-in-process");
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    int code = RUN("run", "--no-isolate", "--plugin", failing, "-p", "crow", "-s", "8x8", "-m",
                   "point", "-m", "callsexit", "-m", "area", "-f", "box", "--reps", "1",
                   "--threads", "1", "--no-plots", "--no-images", "-q", "--out", out);
    if (code != 3)
        fail_msg("exit %d, not 3\n%s%s", code, out_text, err_text);
    expect_in(err_text, "method callsexit called exit() during its render", "message");
    table *t = read_table(csv);
    assert_non_null(t);
    assert_int_equal(t->nrows, 1);
    assert_string_equal(cell(t, 0, "method"), "point");
}

/* The rmse of `method` on crow 8x8 box in process (one thread), after the
 * method `before` (NULL: none), into buf; the run's table in *tp. */
static void rmse_after(const char *before, const char *method, const char *name, char *buf,
                       size_t len, table **tp)
{
    char out[600], csv[700];
    path_in(out, sizeof out, name);
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    if (before)
        LIB("run", "--no-isolate", "-p", "crow", "-s", "8x8", "-m", before, "-m", method, "-f",
            "box", "--reps", "1", "--threads", "1", "--no-plots", "--no-images", "-q", "--out",
            out);
    else
        LIB("run", "--no-isolate", "-p", "crow", "-s", "8x8", "-m", method, "-f", "box",
            "--reps", "1", "--threads", "1", "--no-plots", "--no-images", "-q", "--out", out);
    table *t = read_table(csv);
    assert_non_null(t);
    assert_int_equal(t->nrows, before ? 2 : 1);
    assert_string_equal(cell(t, t->nrows - 1, "method"), method);
    assert_string_equal(cell(t, t->nrows - 1, "ok"), "1");
    snprintf(buf, len, "%s", cell(t, t->nrows - 1, "rmse"));
    *tp = t;
}

/* A method that leaves the rounding mode upward: the next row's error is
 * the one of a run without it, bit for bit, and its own row says so. */
static void test_rounding_restored(void **state)
{
    (void)state;
    char plain[128], after[128];
    table *t;
    rmse_after(NULL, "jitter", "rounding-plain", plain, sizeof plain, &t);
    rmse_after("rounding", "jitter", "rounding-after", after, sizeof after, &t);
    int round = fegetround();
    fesetround(FE_TONEAREST); /* for the tests after, whatever happened */
    assert_string_equal(after, plain);
    assert_int_equal(round, FE_TONEAREST);
    assert_string_equal(cell(t, 0, "ok"), "1");
    expect_in(cell(t, 0, "note"), "changed the rounding mode", "rounding's note");
}

/* A method that writes 16 values past the end of its image: its case
 * failed, saying so, and the next row is the one of a run without it. */
static void test_overrun_fails_case(void **state)
{
    (void)state;
    char plain[128], after[128];
    table *t;
    rmse_after(NULL, "point", "overrun-plain", plain, sizeof plain, &t);
    rmse_after("overrun", "point", "overrun-after", after, sizeof after, &t);
    assert_string_equal(cell(t, 0, "ok"), "0");
    assert_string_equal(cell(t, 0, "note"), "failed: wrote past its image (8 x 8 x 3)");
    assert_string_equal(cell(t, 0, "rmse"), "");
    assert_string_equal(after, plain);
}

/* ---- outputs initialised when refused early ---- */

/* A run of crow at w x h under the box filter with the n (at most 3)
 * methods given, their specs parsed; the rest of cfg zero. */
typedef struct crow_run {
    aa_run_spec p, m[3];
    aa_run_filter f;
    aa_run_size size;
    aa_run_config cfg;
} crow_run;

static void crow_run_init(crow_run *r, int w, int h, const char *const *methods, int n)
{
    memset(r, 0, sizeof *r);
    r->p.text = "crow";
    assert_int_equal(aa_pattern_parse(r->p.text, &r->p.spec), AA_OK);
    for (int k = 0; k < n; k++) {
        r->m[k].text = methods[k];
        assert_int_equal(aa_spec_parse(methods[k], aa_method_table(), "method", &r->m[k].spec),
                         AA_OK);
    }
    r->f.text = "box";
    aa_filter_default(&r->f.filter);
    r->size = (aa_run_size){w, h};
    r->cfg.patterns = &r->p, r->cfg.npatterns = 1;
    r->cfg.sizes = &r->size, r->cfg.nsizes = 1;
    r->cfg.filters = &r->f, r->cfg.nfilters = 1;
    r->cfg.methods = r->m, r->cfg.nmethods = (size_t)n;
}

static void test_outputs_initialised(void **state)
{
    (void)state;
    static const char *const point[] = {"point"};
    crow_run r;
    crow_run_init(&r, 65536, 65536, point, 1);
    aa_run_config cfg = r.cfg;
    cfg.reps = 1, cfg.threads = 1;
    aa_row *rows = (aa_row *)(uintptr_t)0xdeadbeef;
    size_t n = 12345;
    assert_int_equal(aa_run(&cfg, &rows, &n), AA_EINVAL);
    assert_null(rows);
    assert_int_equal(n, 0);
    cfg.nsizes = 0;
    rows = (aa_row *)(uintptr_t)0xdeadbeef, n = 12345;
    assert_int_equal(aa_run(&cfg, &rows, &n), AA_EINVAL);
    assert_null(rows);
    assert_int_equal(n, 0);
    rows = (aa_row *)(uintptr_t)0xdeadbeef, n = 12345;
    assert_int_equal(aa_rows_read_csv("/nonexistent-aabench/x.csv", &rows, &n), AA_EIO);
    assert_null(rows);
    assert_int_equal(n, 0);

    /* `check` with a baseline row that cannot run: refused, whole */
    char path[600], row[2048];
    path_in(path, sizeof path, "huge.csv");
    row_text(row, sizeof row, NULL, NULL, "size", "65536x65536");
    write_baseline(path, row);
    for (int k = 0; k < 6; k++) {
        int code = RUN("check", "--baseline", path, "--threads", "1");
        if (code != 2)
            fail_msg("check with a 65536x65536 row: exit %d\n%s", code, err_text);
        expect_in(err_text, "the case point on crow 65536x65536 box", "huge row");
        expect_in(err_text, "GB", "huge row");
    }
}

/* ---- isolation ---- */

/* A method that calls exit() in its child after the run has written an
 * image (so the image module's libraries, and their exit handlers, are in
 * the parent the child is a copy of): the case fails with its exit status
 * and the run goes on.  Those handlers once ran in the child, waited for
 * threads it does not have, and the run stopped with the case lost. */
static void test_exit_after_images(void **state)
{
    (void)state;
    char out[600], csv[700];
    path_in(out, sizeof out, "exit-after-images");
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    int code = LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "-m", "quits", "-m", "area",
                   "-f", "box", "--case-timeout", "60", "--reps", "1",
                   "--no-plots", "-q", "--no-cache", "--out", out);
    if (code != 1)
        fail_msg("exit %d, not 1\n%s%s", code, out_text, err_text);
    table *t = read_table(csv);
    assert_non_null(t);
    assert_int_equal(t->nrows, 3);
    assert_string_equal(cell(t, 1, "method"), "quits");
    assert_string_equal(cell(t, 1, "ok"), "0");
    assert_string_equal(cell(t, 1, "note"), "failed: ended (exit status 3) without reporting its result");
    assert_string_equal(cell(t, 2, "ok"), "1");
    assert_int_equal(lib_failed, 1);
}

static void test_isolated_faults(void **state)
{
    (void)state;
    char faulty[1200], failing[1200], out[600], csv[700];
    plugin("plugin_faulty", faulty, sizeof faulty);
    plugin("plugin_failing", failing, sizeof failing);
    path_in(out, sizeof out, "isolated");
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    /* plug-in methods are isolated by default */
    /* through the command: a crash in this process's child would meet the
     * test framework's signal handlers, not a process's own.  `crash` and
     * `hang` leave a file in $TMPDIR before they are ended (plugin_faulty.c):
     * each case's temporary folder is removed with what it holds, so the
     * run's TMPDIR ends as empty as it began */
    char tmp[600];
    path_in(tmp, sizeof tmp, "isolated-tmp");
    assert_int_equal(mkdir(tmp, 0755), 0);
    char *saved = getenv("TMPDIR") ? strdup(getenv("TMPDIR")) : NULL;
    setenv("TMPDIR", tmp, 1);
    int code = RUN("run", "--plugin", faulty, "--plugin", failing, "-p", "crow", "-s", "8x8",
                   "-m", "point", "-m", "crash", "-m", "aborts", "-m", "quits", "-m", "hang",
                   "-m", "area", "-f", "box", "--case-timeout", "2", "--reps", "1", "--no-images",
                   "--no-plots", "-q", "--out", out);
    if (saved) {
        setenv("TMPDIR", saved, 1);
        free(saved);
    } else {
        unsetenv("TMPDIR");
    }
    if (code != 1)
        fail_msg("exit %d, not 1\n%s%s", code, out_text, err_text);
    DIR *d = opendir(tmp);
    assert_non_null(d);
    for (struct dirent *e; (e = readdir(d));)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
            fail_msg("the run left %s in its TMPDIR %s", e->d_name, tmp);
    closedir(d);
    table *t = read_table(csv);
    assert_non_null(t);
    assert_int_equal(t->nrows, 6);
    static const char *const method[] = {"point", "crash", "aborts", "quits", "hang", "area"};
    char crashed[64], aborted[64];
    snprintf(crashed, sizeof crashed, "failed: crashed (signal %d)", SIGSEGV);
    snprintf(aborted, sizeof aborted, "failed: crashed (signal %d)", SIGABRT);
    for (int r = 0; r < 6; r++) {
        assert_string_equal(cell(t, r, "method"), method[r]);
        assert_string_equal(cell(t, r, "ok"), r == 0 || r == 5 ? "1" : "0");
    }
    /* under ASan a SIGSEGV is caught and ends as an abort; a method's
     * exit() ends its child with its status, before the leak checker */
    if (SANITIZED)
        expect_in(cell(t, 1, "note"), "failed: crashed (signal ", "crash");
    else
        assert_string_equal(cell(t, 1, "note"), crashed);
    assert_string_equal(cell(t, 2, "note"), aborted);
    expect_in(cell(t, 3, "note"), "failed: ended (exit status 3)", "quits");
    assert_string_equal(cell(t, 4, "note"), "failed: timed out after 2 s");
    expect_in(err_text, "4 of 6 cases failed: crash on crow 8x8 box; aborts on crow 8x8 box; "
                        "quits on crow 8x8 box; hang on crow 8x8 box", "summary");

    /* check: a baseline that says the crashing method ran */
    char path[600], row[4096], r2[2048];
    path_in(path, sizeof path, "crash.csv");
    row_text(row, sizeof row, "crash", NULL, NULL, NULL);
    row_text(r2, sizeof r2, "hang", NULL, NULL, NULL);
    strcat(row, r2);
    write_baseline(path, row);
    code = RUN("check", "--plugin", faulty, "--baseline", path, "--threads", "1",
               "--case-timeout", "2");
    if (code != 1)
        fail_msg("check with a crashing method: exit %d, not 1\n%s%s", code, out_text, err_text);
    expect_in(out_text, "FAIL crash on crow 16x16 box: now fails: failed: crashed (signal",
              "check");
    expect_in(out_text, "FAIL hang on crow 16x16 box: now fails: failed: timed out after 2 s",
              "check");
    expect_in(out_text, "check: 2 of 3 cases failed", "check");
}

/* Rows of the same cases, in process and isolated, equal bit for bit. */
static void same_rows(const aa_row *a, const aa_row *b, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        if (!a[k].ok || !b[k].ok || memcmp(&a[k].m, &b[k].m, sizeof a[k].m) ||
            a[k].spp != b[k].spp || a[k].samples != b[k].samples ||
            a[k].expensive_pixels != b[k].expensive_pixels ||
            strcmp(a[k].canonical, b[k].canonical) || strcmp(a[k].note, b[k].note))
            fail_msg("%s: in process rmse %.17g (ok %d, \"%s\"), isolated %.17g (ok %d, \"%s\")",
                     a[k].method, a[k].m.rmse, a[k].ok, a[k].note, b[k].m.rmse, b[k].ok,
                     b[k].note);
    }
}

static void test_isolated_equal(void **state)
{
    (void)state;
    static const char *const methods[] = {"point", "jitter:spp=16", "area"};
    crow_run r;
    crow_run_init(&r, 24, 20, methods, 3);
    aa_run_config cfg = r.cfg;
    cfg.reps = 1, cfg.threads = 2, cfg.seed = 7;
    cfg.case_timeout = 60;
    /* no cache: this process computes the reference with OpenMP's threads
     * before it forks */
    aa_row *in = NULL, *iso = NULL, *again = NULL;
    size_t nin, niso, nagain;
    cfg.isolate = AA_ISOLATE_NONE;
    assert_int_equal(aa_run(&cfg, &in, &nin), AA_OK);
    cfg.isolate = AA_ISOLATE_ALL;
    assert_int_equal(aa_run(&cfg, &iso, &niso), AA_OK);
    cfg.isolate = AA_ISOLATE_NONE;
    assert_int_equal(aa_run(&cfg, &again, &nagain), AA_OK);
    assert_int_equal(nin, 3);
    assert_int_equal(niso, 3);
    assert_int_equal(nagain, 3);
    same_rows(in, iso, 3);
    same_rows(in, again, 3);
    free(in);
    free(iso);
    free(again);
}

/* ---- checks before work ---- */

/* Nothing in the folder but the files this test wrote. */
static int entries(const char *path)
{
    char cmd[900], buf[64];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", path);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    assert_non_null(fgets(buf, sizeof buf, p));
    pclose(p);
    return atoi(buf);
}

static void test_checked_before_work(void **state)
{
    (void)state;
    char sub[600], out[700], file[700];
    path_in(sub, sizeof sub, "before");
    assert_int_equal(mkdir(sub, 0755), 0);
    snprintf(out, sizeof out, "%s/out", sub);

    /* error maps too tall (the map, its bar and labels): refused before
     * the run, not after it (a montage shows at most 256x256 of a view) */
    assert_int_equal(LIB("run", "-s", "1x65536", "-p", "crow", "-m", "point", "--reps", "1",
                         "-q", "--out", out),
                     2);
    expect_in(err_text, "error map", "-s 1x65536");
    assert_false(exists(out));

    /* a method spec every filter refuses, as render refuses it */
    assert_int_equal(LIB("run", "-m", "jitter:spp=15", "-p", "crow", "-s", "8x8", "--reps", "1",
                         "-q", "--out", out),
                     2);
    expect_in(err_text, "spp must be a square", "jitter:spp=15");
    assert_false(exists(out));

    /* an output folder of 100 kB, and one with a 300-character name */
    char *big = malloc(100 * 1000 + 700);
    assert_non_null(big);
    int n = snprintf(big, 700, "%s/", sub);
    memset(big + n, 'a', 100 * 1000);
    big[n + 100 * 1000] = '\0';
    assert_int_equal(LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "-q", "--out", big), 2);
    expect_in(err_text, "is too long", "100 kB --out");
    assert_true(strlen(err_text) < 1000);
    big[n + 300] = '\0';
    memcpy(big + n + 300, "/x", 3);
    assert_int_equal(LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "-q", "--out", big), 2);
    expect_in(err_text, "is longer than 255 characters", "300-character name");
    free(big);
    assert_int_equal(entries(sub), 0);

    /* a file where a folder is wanted */
    snprintf(file, sizeof file, "%s/file", sub);
    put_file(file, "x", 1);
    snprintf(out, sizeof out, "%s/file/run", sub);
    assert_int_equal(LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "-q", "--out", out), 3);
    expect_in(err_text, "file is not a folder but a file", "--out under a file");
    snprintf(out, sizeof out, "%s/run", sub);
    assert_int_equal(
        LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "-q", "--cache", file, "--out", out),
        3);
    expect_in(err_text, "--cache", "--cache a file");
    expect_in(err_text, "is not a folder but a file", "--cache a file");
    assert_int_equal(entries(sub), 1);

    /* a side too large to hold is out of range, not malformed */
    assert_int_equal(LIB("run", "-p", "crow", "-s", "99999999999999999999x16", "-m", "point",
                         "--out", out),
                     2);
    expect_in(err_text, "is out of range", "huge side");

    /* long inputs: the input is shortened, the reason kept */
    char longname[3001];
    memset(longname, 'a', 3000);
    longname[3000] = '\0';
    assert_int_equal(LIB("run", "-p", "crow", "-s", "8x8", "-m", longname, "--out", out), 2);
    expect_in(err_text, "(known: point", "long method name");
    expect_in(err_text, "(3000 characters)", "long method name");
    memset(longname, '1', 3000);
    assert_int_equal(
        LIB("run", "-p", "crow", "-s", "8x8", "-m", "point", "--reps", longname, "--out", out), 2);
    expect_in(err_text, "is out of range (1 to 1000)", "long --reps");
    memset(longname, 'b', 3000);
    memcpy(longname, "crow:curves=", 12);
    assert_int_equal(LIB("run", "-p", longname, "-s", "8x8", "-m", "point", "--out", out), 2);
    expect_in(err_text, "not a number (expected an integer", "long value");
    /* control characters escaped */
    assert_int_equal(
        LIB("run", "-p", "cr\033[31mow\nx", "-s", "8x8", "-m", "point", "--out", out), 2);
    expect_in(err_text, "unknown pattern \"cr\\x1b[31mow\\nx\"", "control characters");
    assert_null(strchr(err_text, '\033'));
    assert_int_equal(entries(sub), 1);
}

/* The address space this process has mapped (VmSize), in bytes; 0 unknown. */
static double address_space(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    double kb = 0;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "VmSize:", 7))
            kb = atof(line + 7);
    if (f)
        fclose(f);
    return kb * 1024;
}

/* After every case has run, the montage under a memory limit it cannot
 * fit: a failure of the machine's resources (AA_ENOMEM, exit status 3),
 * not of the input (2); the rows are kept.  The cases run here, the
 * montage in a child (the limit stays there; the montage is refused before
 * it renders anything, so the child never starts OpenMP threads, which
 * are not fork-safe). */
static int montage_memory_body(void *arg)
{
    aa_runfolder *rf = arg;
    /* 64 kB left: the montage's band of 2 tiles of 64x64 needs more */
    double vm = address_space();
    SUPPORT_CHILD_CHECK(vm > 0);
    struct rlimit r = {(rlim_t)vm + 65536, (rlim_t)vm + 65536};
    SUPPORT_CHILD_CHECK(setrlimit(RLIMIT_AS, &r) == 0);
    int st = aa_runfolder_finish(rf);
    SUPPORT_CHILD_CHECK(st == AA_ENOMEM && aa_exit_code(st) == 3);
    SUPPORT_CHILD_CHECK(strstr(aa_last_error(), "montage") != NULL);
    size_t n;
    aa_runfolder_rows(rf, &n);
    SUPPORT_CHILD_CHECK(n == 2);
    return 0;
}

static void test_montage_memory(void **state)
{
    (void)state;
    char out[600];
    path_in(out, sizeof out, "montage-memory");
    const char *args[] = {"run", "-p", "crow", "-s", "64x64", "-f", "box", "-m", "point",
                          "-m", "area", "--reps", "1", "--no-plots", "-q", "--no-cache",
                          "--out", out, NULL};
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf = NULL;
    int asked;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    assert_int_equal(aa_plan_parse(18, (char *const *)args, &plan, &opt, &asked), AA_OK);
    assert_int_equal(aa_runfolder_create(&plan, &opt, &rf), AA_OK);
    assert_int_equal(aa_runfolder_run(rf), AA_OK);
    support_in_child(montage_memory_body, rf);
    aa_runfolder_free(rf);
}

/* A message quoting an input of any length keeps its start and its end
 * (the reason), on one line; an echoed input is cut at a character, or at
 * a byte when none starts near (the fuzz target found 0xaf bytes read past
 * their end). */
static void test_messages(void **state)
{
    (void)state;
    char *big = malloc(100001);
    assert_non_null(big);
    memset(big, 'x', 100000);
    big[100000] = '\0';
    big[50000] = '\n';
    assert_int_equal(aa_fail(AA_EINVAL, "input %s: the reason", big), AA_EINVAL);
    const char *e = aa_last_error();
    assert_true(strlen(e) < 1024);
    assert_true(!strncmp(e, "input xxx", 9));
    assert_non_null(strstr(e, " ... "));
    assert_true(!strcmp(e + strlen(e) - 12, ": the reason"));
    assert_null(strchr(e, '\n'));
    assert_int_equal(aa_fail_context(AA_EINVAL, "context %s", big), AA_EINVAL);
    e = aa_last_error();
    assert_true(strlen(e) < 1024 && !strncmp(e, "context xxx", 11));
    assert_true(!strcmp(e + strlen(e) - 12, ": the reason"));
    memset(big, 0xaf, 200);
    big[200] = '\0';
    e = aa_echo(big);
    assert_non_null(strstr(e, "...(200 characters)"));
    assert_true(strlen(e) < 200);
    assert_string_equal(aa_echo("a\033b\tc"), "a\\x1bb\\tc");
    free(big);
}

/* ---- set-up ---- */

static int setup(void **state)
{
    (void)state;
    if (!getenv("AABENCH") || !mkdtemp(dir))
        return -1;
    char cache[600];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    setenv("AABENCH_CACHE", cache, 1);
    setenv("CI", "1", 1);
    /* the faulty plug-ins' methods, for the runs in this process */
    const char *exe = getenv("AABENCH"), *slash = strrchr(exe, '/');
    static const char *const names[] = {"plugin_faulty", "plugin_failing"};
    for (int k = 0; k < 2 && slash; k++) {
        char path[1200];
        snprintf(path, sizeof path, "%.*s/tests/%s.so", (int)(slash - exe), exe, names[k]);
        if (aa_plugin_load(path))
            return -1;
    }
    return slash ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd);
}

SUPPORT_MAIN(setup, teardown,
             cmocka_unit_test(test_baseline_strict),
             cmocka_unit_test(test_baseline_refusal_recorded),
             cmocka_unit_test(test_rows_kept_when_killed),
             cmocka_unit_test(test_bad_values_fail_case),
             cmocka_unit_test(test_contract_faults),
             cmocka_unit_test(test_exit_in_process),
             cmocka_unit_test(test_rounding_restored),
             cmocka_unit_test(test_overrun_fails_case),
             cmocka_unit_test(test_outputs_initialised),
             cmocka_unit_test(test_isolated_faults),
             cmocka_unit_test(test_exit_after_images),
             cmocka_unit_test(test_isolated_equal),
             cmocka_unit_test(test_checked_before_work),
             cmocka_unit_test(test_montage_memory),
             cmocka_unit_test(test_messages))
