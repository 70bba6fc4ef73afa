/*
 * test_run.c: the benchmark's runs, reports and regression gate.
 *
 *  - results.csv and results.json parse back (the CSV through the library's
 *    reader, the JSON through a strict validator written here), with the
 *    values of the rows that made them;
 *  - `aabench check` passes on a baseline made from its own run (made
 *    through the library's run folder in this process), fails
 *    (exit 1, naming the offender) when a baseline error is made smaller
 *    than what the method achieves, and when a baseline method is missing;
 *  - a run's references go to the cache given, and only there; one that
 *    cannot be written is said once;
 *  - an `aabench run` interrupted by a signal (SIGINT, SIGHUP) leaves no
 *    half-written or temporary file: everything in its folder is complete
 *    and parses; resuming a killed run removes the temporary files it left;
 *  - options that would be ignored are refused;
 *  - the results table tells apart names that differ late.
 */
#include "bench.h"
#include "support.h"

#include <ctype.h>
#include <fcntl.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

static char dir[256];
static char output[16384];

/* Run $AABENCH with args, interrupted after interrupt_after_ms if > 0. */
static int run_cmd(const char *const *args, int interrupt_after_ms)
{
    return support_aabench_interrupted(args, interrupt_after_ms, output, sizeof output);
}

/* `run ARGS...` through the library's run folder in this process, as the
 * command does but for its printing; the status, the message in output. */
static int lib_run(const char *const *args)
{
    int st = support_lib_run(args, NULL, NULL);
    snprintf(output, sizeof output, "%s", st ? aa_last_error() : "");
    return st;
}

/* The view's reference's largest bound and count scanned in out's
 * results.csv: the same as the reference computed here, without a cache,
 * gives (the bound reaches the results whether the run computed the
 * reference or read it from a cache). */
static void expect_ref_stats(const char *out, const char *pattern, int w, int h)
{
    char csv[400];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_true(n >= 1);
    aa_view v;
    memset(&v, 0, sizeof v);
    assert_int_equal(aa_pattern_parse(pattern, &v.pattern), AA_OK);
    v.w = w, v.h = h;
    aa_filter_default(&v.filter);
    aa_image ref;
    aa_truth_stats ts;
    assert_int_equal(aa_reference(&v, NULL, 1, &ref, &ts, NULL), AA_OK);
    aa_image_free(&ref);
    assert_true(ts.max_bound > 0 && ts.max_bound <= AA_TRUTH_BOUND);
    for (size_t k = 0; k < n; k++) { /* results.csv's nine digits */
        if (!(fabs(rows[k].ref_bound - ts.max_bound) <= 5e-9 * ts.max_bound))
            fail_msg("%s: ref_bound %.17g, the reference's %.17g", csv, rows[k].ref_bound,
                     ts.max_bound);
        assert_true(rows[k].ref_scanned == (double)ts.scanned);
    }
    free(rows);
    /* index.html says the view's bound, proven (nothing scanned here) */
    assert_true(ts.scanned == 0);
    char html[400], want[200];
    snprintf(html, sizeof html, "%s/index.html", out);
    if (access(html, F_OK) == 0) { /* (a run without images writes none) */
        size_t cap = 1 << 20;
        char *text = malloc(cap);
        assert_non_null(text);
        support_read_file(html, text, cap, NULL);
        snprintf(want, sizeof want, "each pixel within %.2e of the filtered scene, proven",
                 ts.max_bound);
        if (!strstr(text, want))
            fail_msg("%s does not say \"%s\"", html, want);
        free(text);
    }
}

/* ---- a strict JSON validator (RFC 8259 grammar) ---- */

static const char *ws(const char *p)
{
    while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')
        p++;
    return p;
}

static const char *value(const char *p);

static const char *string(const char *p)
{
    if (*p++ != '"')
        return NULL;
    while (*p != '"') {
        if (!*p || (unsigned char)*p < 0x20)
            return NULL;
        if (*p == '\\') {
            p++;
            if (*p == 'u') {
                for (int k = 1; k <= 4; k++)
                    if (!isxdigit((unsigned char)p[k]))
                        return NULL;
                p += 4;
            } else if (!strchr("\"\\/bfnrt", *p)) {
                return NULL;
            }
        }
        p++;
    }
    return p + 1;
}

static const char *number(const char *p)
{
    const char *s = p;
    if (*p == '-')
        p++;
    if (!isdigit((unsigned char)*p))
        return NULL;
    while (isdigit((unsigned char)*p) || *p == '.' || *p == 'e' || *p == 'E' || *p == '+' ||
           *p == '-')
        p++;
    char *end;
    strtod(s, &end);
    return end == p ? p : NULL;
}

static const char *value(const char *p)
{
    p = ws(p);
    if (*p == '{' || *p == '[') {
        char close = *p == '{' ? '}' : ']';
        int object = *p == '{';
        p = ws(p + 1);
        if (*p == close)
            return p + 1;
        for (;;) {
            if (object) {
                if (!(p = string(ws(p))) || *(p = ws(p)) != ':')
                    return NULL;
                p++;
            }
            if (!(p = value(p)))
                return NULL;
            p = ws(p);
            if (*p == close)
                return p + 1;
            if (*p++ != ',')
                return NULL;
        }
    }
    if (*p == '"')
        return string(p);
    if (!strncmp(p, "true", 4) || !strncmp(p, "null", 4))
        return p + 4;
    if (!strncmp(p, "false", 5))
        return p + 5;
    return number(p);
}

static void json_valid(const char *path)
{
    static char buf[1 << 20];
    const char *end = value(support_read_file(path, buf, sizeof buf, NULL));
    if (!end || *ws(end))
        fail_msg("%s is not valid JSON", path);
}

/* A small run through the library: rows, then CSV and JSON. */
static void test_reports_parse_back(void **state)
{
    (void)state;
    aa_run_spec patterns[1] = {{.text = "crow"}}, methods[4];
    aa_run_size sizes[1] = {{24, 16}};
    aa_run_filter filters[1] = {{.text = "box"}};
    const char *names[] = {"point", "centre4", "point", "jitter:seq=random,spp=4"};
    assert_int_equal(aa_pattern_parse(patterns[0].text, &patterns[0].spec), AA_OK);
    assert_int_equal(aa_filter_parse(filters[0].text, &filters[0].filter), AA_OK);
    for (size_t k = 0; k < 4; k++) {
        methods[k].text = names[k];
        assert_int_equal(aa_spec_parse(names[k], aa_method_table(), "method", &methods[k].spec),
                         AA_OK);
    }
    /* the last given by its value alone: the run shows its canonical text */
    methods[3].text = NULL;
    aa_run_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.patterns = patterns, cfg.npatterns = 1;
    cfg.sizes = sizes, cfg.nsizes = 1;
    cfg.filters = filters, cfg.nfilters = 1;
    cfg.methods = methods, cfg.nmethods = 4;
    cfg.reps = 2, cfg.threads = 2, cfg.seed = 3;
    aa_row *rows, *back;
    size_t n, nb;
    assert_int_equal(aa_run(&cfg, &rows, &n), AA_OK);
    assert_int_equal(n, 4);
    /* the spec as given, or, given none, every parameter in table order */
    assert_string_equal(rows[1].method, "centre4");
    assert_string_equal(rows[3].method, "jitter:spp=4,seq=random");
    assert_string_equal(rows[3].pattern, "crow");
    /* a note with a comma and a quote must survive the CSV */
    snprintf(rows[1].note, sizeof rows[1].note, "a \"quoted\", note");
    char csv[512], json[512];
    snprintf(csv, sizeof csv, "%s/r.csv", dir);
    snprintf(json, sizeof json, "%s/r.json", dir);
    assert_int_equal(aa_rows_write_csv(csv, rows, n), AA_OK);
    assert_int_equal(aa_rows_write_json(json, rows, n), AA_OK);
    assert_int_equal(aa_rows_read_csv(csv, &back, &nb), AA_OK);
    assert_int_equal(nb, n);
    for (size_t k = 0; k < n; k++) {
        assert_string_equal(back[k].method, rows[k].method);
        assert_string_equal(back[k].pattern, rows[k].pattern);
        assert_string_equal(back[k].note, rows[k].note);
        assert_true(back[k].w == 24 && back[k].h == 16 && back[k].ok == 1);
        /* the gate reruns a row with its own seed */
        assert_true(back[k].seed == 3 && rows[k].seed == 3);
        /* %.9g keeps nine significant digits */
        assert_true(fabs(back[k].m.rmse - rows[k].m.rmse) <= 1e-8 * rows[k].m.rmse);
        assert_true(fabs(back[k].seconds - rows[k].seconds) <= 1e-8 * rows[k].seconds);
    }
    /* the same method twice gives the same error (deterministic) */
    assert_true(rows[0].m.rmse == rows[2].m.rmse);
    json_valid(json);
    free(rows);
    free(back);
}

static void test_gate(void **state)
{
    (void)state;
    char out[512], csv[512], bad[512], missing[512];
    snprintf(out, sizeof out, "%s/gate", dir);
    snprintf(csv, sizeof csv, "%s/gate/results.csv", dir);
    const char *plugin = getenv("AABENCH_PLUGIN");
    /* in this process, which has loaded the plug-in (setup) */
    const char *run[] = {"run", "-p", "crow", "-s", "32x24", "-f", "box", "-m", "point", "-m",
                         "centre4", "--reps", "1", "--no-images", "--no-plots", "--out", out,
                         "-q", NULL};
    if (lib_run(run) != AA_OK)
        fail_msg("the run: %s", output);
    const char *check[] = {"check", "--baseline", csv, "--plugin", plugin, NULL};
    if (run_cmd(check, 0) != 0)
        fail_msg("check fails on its own baseline: %s", output);
    /* a baseline claiming half the error of point: point is an offender */
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    for (size_t k = 0; k < n; k++)
        if (!strcmp(rows[k].method, "point"))
            rows[k].m.rmse *= 0.5;
    snprintf(bad, sizeof bad, "%s/worse.csv", dir);
    assert_int_equal(aa_rows_write_csv(bad, rows, n), AA_OK);
    const char *check_bad[] = {"check", "--baseline", bad, "--plugin", plugin, NULL};
    assert_int_equal(run_cmd(check_bad, 0), 1);
    assert_non_null(strstr(output, "FAIL point on crow 32x24 box: error above its baseline"));
    assert_null(strstr(output, "FAIL centre4"));
    /* a method the table no longer has: an offender too */
    free(rows);
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    snprintf(rows[0].method, sizeof rows[0].method, "vanished");
    snprintf(missing, sizeof missing, "%s/missing.csv", dir);
    assert_int_equal(aa_rows_write_csv(missing, rows, n), AA_OK);
    const char *check_missing[] = {"check", "--baseline", missing, "--plugin", plugin, NULL};
    assert_int_equal(run_cmd(check_missing, 0), 1);
    assert_non_null(strstr(output, "FAIL vanished"));
    /* without the plug-in, its method is missing */
    const char *check_noplugin[] = {"check", "--baseline", csv, NULL};
    assert_int_equal(run_cmd(check_noplugin, 0), 1);
    assert_non_null(strstr(output, "FAIL centre4"));
    free(rows);
}

/* The montage's reference (and the convergence plots') go where the run's
 * other references go: nowhere without a cache, into the cache given
 * when one is, nowhere else. */
static void test_cache_options(void **state)
{
    (void)state;
    char mine[300], out[300], cmd[900];
    snprintf(mine, sizeof mine, "%s/my-cache", dir);
    snprintf(out, sizeof out, "%s/cache-run", dir);
    const char *none[] = {"run", "-p", "crow", "-f", "box", "-s", "24x24", "-m", "point",
                          "--reps", "1", "--no-plots", "-q", "--no-cache", "--out", out, NULL};
    assert_int_equal(lib_run(none), AA_OK);
    snprintf(cmd, sizeof cmd, "%s/montage.png", out);
    assert_int_equal(access(cmd, F_OK), 0); /* the montage was made */
    expect_ref_stats(out, "crow", 24, 24);
    snprintf(cmd, sizeof cmd, "test -z \"$(find %s -name 'ref-*.bin' | head -1)\"", dir);
    if (system(cmd) != 0)
        fail_msg("run --no-cache wrote a reference under %s", dir);
    const char *given[] = {"run", "-p", "crow", "-f", "box", "-s", "24x24", "-m", "point",
                           "--reps", "1", "--no-plots", "-q", "--cache", mine, "--out", out, NULL};
    assert_int_equal(lib_run(given), AA_OK);
    snprintf(cmd, sizeof cmd, "test -n \"$(find %s -name 'ref-*.bin' | head -1)\"", mine);
    if (system(cmd) != 0)
        fail_msg("run --cache %s left no reference there", mine);
    snprintf(cmd, sizeof cmd,
             "test -z \"$(find %s -name 'ref-*.bin' -not -path '%s/*' | head -1)\"", dir, mine);
    if (system(cmd) != 0)
        fail_msg("run --cache %s wrote a reference elsewhere", mine);
    expect_ref_stats(out, "crow", 24, 24);
    assert_int_equal(lib_run(given), AA_OK); /* the reference from the cache */
    expect_ref_stats(out, "crow", 24, 24);
    /* the command's default cache is $AABENCH_CACHE: --cache replaces it */
    char env[400], def[300], log[300];
    snprintf(def, sizeof def, "%s/default-cache", dir);
    snprintf(env, sizeof env, "AABENCH_CACHE=%s", def);
    snprintf(log, sizeof log, "%s/cache-run.log", dir);
    assert_int_equal(support_wait(support_aabench_spawn(given, env, log, log)), 0);
    if (access(def, F_OK) == 0)
        fail_msg("run --cache %s wrote the default cache %s", mine, def);
}

/* A reference cache that cannot be written is said once, whatever the
 * number of references (here the three views', through aa_reference as the
 * montage's is: --no-images spares the command OpenImageIO's load), and the
 * run goes on without it. */
static void test_cache_unusable(void **state)
{
    (void)state;
    char out[300];
    snprintf(out, sizeof out, "%s/no-cache-run", dir);
    /* /proc takes no new folder, even from root */
    const char *run[] = {"run", "-p", "crow", "-f", "box", "-s", "24x24", "-s", "32x32",
                         "-s", "40x40", "-m", "point", "--reps", "1", "--no-plots", "-q",
                         "--no-images", "--cache", "/proc/aabench-none/cache", "--out", out,
                         NULL};
    assert_int_equal(run_cmd(run, 0), 0);
    /* (a warning of noisy timings may follow on a busy machine) */
    const char *first = strstr(output, "warning: the reference cache /proc/aabench-none/cache");
    if (!first || strstr(first + 20, "reference cache"))
        fail_msg("expected one warning about the cache, got: %s", output);
}

/* The results table never cuts two names to the same text: the pattern
 * column (10 wide) widens to tell crow:kmax=0.3 from crow:kmax=0.35. */
static void test_table_names(void **state)
{
    (void)state;
    char out[300];
    snprintf(out, sizeof out, "%s/names-run", dir);
    const char *run[] = {"run", "-p", "crow:kmax=0.3", "-p", "crow:kmax=0.35", "-f", "box",
                         "-s", "8x8", "-m", "point", "--reps", "1", "--no-plots",
                         "--no-images", "--no-cache", "--out", out, NULL};
    assert_int_equal(run_cmd(run, 0), 0);
    int seen[2] = {0, 0};
    /* each row shows its reference's bound, as results.csv holds it */
    char csv[400];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_int_equal(n, 2);
    if (!strstr(output, " max_err ref_bound "))
        fail_msg("the table's header has no ref_bound:\n%s", output);
    for (size_t k = 0; k < n; k++) {
        char want[sizeof rows[k].pattern + 8];
        assert_true(rows[k].ref_bound > 0 && rows[k].ref_bound <= AA_TRUTH_BOUND);
        snprintf(want, sizeof want, " %s ", rows[k].pattern);
        const char *row = strstr(output, want);
        assert_non_null(row);
        snprintf(want, sizeof want, " %.2e ", rows[k].ref_bound);
        const char *end = strchr(row, '\n');
        const char *at = strstr(row, want);
        if (!at || (end && at > end))
            fail_msg("the row of %s does not show ref_bound%s:\n%s", rows[k].pattern, want,
                     output);
    }
    free(rows);
    for (const char *line = output; *line;) {
        size_t len = strcspn(line, "\n");
        const char *next = line[len] ? line + len + 1 : line + len;
        if (strncmp(line, "point ", 6)) { /* the table's rows start with the method */
            line = next;
            continue;
        }
        char row[1024];
        snprintf(row, sizeof row, "%.*s", (int)len, line);
        seen[0] |= strstr(row, " crow:kmax=0.3 ") != NULL;
        seen[1] |= strstr(row, " crow:kmax=0.35 ") != NULL;
        line = next;
    }
    if (!seen[0] || !seen[1])
        fail_msg("the table does not tell the patterns apart:\n%s", output);
}

/* Interrupt a run part-way: exit 130, and nothing half-written. */
static void test_interrupted(void **state)
{
    (void)state;
    char out[512], cmd[1200];
    snprintf(out, sizeof out, "%s/interrupted", dir);
    const char *plugin = getenv("AABENCH_PLUGIN");
    const char *run[] = {"run", "-p", "crow", "-f", "box", "-s", "48x48", "-s", "64x64",
                         "-s", "96x96", "-m", "centre4", "-m", "point", "--plugin", plugin, "--reps", "20",
                         "--out", out, "--no-cache", "-q", NULL};
    int code = run_cmd(run, 400);
    if (code != 130 && code != 0)
        fail_msg("interrupted run exited %d: %s", code, output);
    /* no temporary files (hidden, named .NAME.PID.N.ext) anywhere */
    snprintf(cmd, sizeof cmd, "test -z \"$(find %s -name '.*' ! -name '.' | head -1)\"", out);
    if (system(cmd) != 0)
        fail_msg("temporary files left in %s", out);
    char csv[600];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    if (access(csv, F_OK) == 0) {
        aa_row *rows;
        size_t n;
        assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
        free(rows);
        snprintf(csv, sizeof csv, "%s/results.json", out);
        json_valid(csv);
    }
    /* every image file present reads back whole */
    snprintf(cmd, sizeof cmd,
             "for f in $(find %s -name '*.exr' -o -name '*.png'); do echo $f; done > %s/list", out,
             dir);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "%s/list", dir);
    FILE *f = fopen(cmd, "r");
    char line[1024];
    int files = 0;
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        aa_image im;
        if (aa_image_read(line, &im))
            fail_msg("%s does not read back: %s", line, aa_last_error());
        aa_image_free(&im);
        files++;
    }
    if (f)
        fclose(f);
    print_message("interrupted run: exit %d, %d image files, all complete\n", code, files);
}

/* Options that would be ignored are refused, naming what is ignored:
 * --out and --shard beside --resume, a value given twice in a list (sizes
 * compared as sizes). */
static void test_ignored_options(void **state)
{
    (void)state;
    const struct {
        const char *args[12], *needle;
    } bad[] = {
        {{"run", "--resume", "a", "--out", "b"}, "--out b would be ignored"},
        {{"run", "--resume", "a", "--shard", "1/2"}, "--shard would be ignored"},
        {{"run", "-s", "24x24", "-s", "32x32", "-s", "24x24"}, "-s 24x24 is given twice"},
        {{"run", "-s", "024x24", "-s", "24x024"}, "-s 024x24 is given twice (-s 24x024)"},
        {{"run", "-m", "point", "-m", "point"}, "-m point is given twice"},
        {{"run", "-p", "crow", "-p", "crow"}, "-p crow is given twice"},
        {{"run", "-f", "box", "-f", "tent", "-f", "box"}, "-f box is given twice"},
        /* an option of one value given two: the first would be ignored */
        {{"run", "--out", "a", "--out", "b"}, "--out is given twice (--out a, then --out b)"},
        {{"run", "--budget", "1", "--reps", "3", "--budget=2"},
         "--budget is given twice (--budget 1, then --budget 2)"},
        {{"run", "--suite", "quick", "--suite", "default"}, "--suite is given twice"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        int argc = 0, asked;
        while (bad[k].args[argc])
            argc++;
        aa_plan plan;
        aa_run_options opt;
        aa_plan_default(&plan);
        aa_run_options_default(&opt);
        int st = aa_plan_parse(argc, (char *const *)bad[k].args, &plan, &opt, &asked);
        if (st != AA_EINVAL || !strstr(aa_last_error(), bad[k].needle))
            fail_msg("case %zu: status %d, \"%s\", expected \"%s\"", k, st, aa_last_error(),
                     bad[k].needle);
    }
    /* what is not ignored is taken: --out naming the resumed folder itself,
     * different values in a list, one value given again (truth --warm S
     * beside --suite S, as the shard drivers give it), plug-ins */
    const char *good[] = {"run", "--resume", "a", "--out", "a", "-s", "24x24", "-s", "24x32",
                          "-m", "point", "-m", "point:", "--out", "a", "--suite", "quick",
                          "--suite=quick", NULL};
    aa_plan plan;
    aa_run_options opt;
    int asked;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    assert_int_equal(aa_plan_parse(18, (char *const *)good, &plan, &opt, &asked), AA_OK);
    /* and the command says so, with exit status 2 */
    const char *cmd[] = {"run", "-s", "24x24", "-s", "24x24", "-p", "crow", NULL};
    assert_int_equal(run_cmd(cmd, 0), 2);
    if (!strstr(output, "-s 24x24 is given twice"))
        fail_msg("no reason given: %s", output);
}

/* out's results.csv: its rows' pattern, size, filter and method, one line
 * each, into buf. */
static void cases_of(const char *out, char *buf, size_t len)
{
    char csv[400];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    aa_row *rows;
    size_t n, used = 0;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    buf[0] = '\0';
    for (size_t k = 0; k < n; k++)
        used += (size_t)snprintf(buf + used, len - used, "%s %dx%d %s %s\n", rows[k].pattern,
                                 rows[k].w, rows[k].h, rows[k].filter, rows[k].method);
    free(rows);
}

/* Which cases a run measures from the lists given and the suite's groups:
 * an svg file given without -s at its own size (its width and height, 20
 * and 12, times its scale, written here), a pattern without a size of its
 * own at the suite's sizes (the quick suite's 128x128, suite.c), each case
 * once where the suite's groups become the same cross product (the quick
 * suite's three groups under -p, -f and -m: each case was measured three
 * times), and where groups meet in part (the paper suite's under -p and -s)
 * every case once. */
static void test_group_cases(void **state)
{
    (void)state;
    char svg[300], out[300], text[1024];
    snprintf(svg, sizeof svg, "%s/own.svg", dir);
    static const char doc[] = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" "
                              "height=\"12\"><rect x=\"2\" y=\"3\" width=\"9\" "
                              "height=\"5\" fill=\"#fff\"/></svg>\n";
    support_write_file(svg, doc, sizeof doc - 1);
    char p1[400], p2[400];
    snprintf(p1, sizeof p1, "svg:file=%s", svg);
    snprintf(p2, sizeof p2, "svg:file=%s,scale=2", svg);
    snprintf(out, sizeof out, "%s/own", dir);
    const char *own[] = {"run", "--suite", "quick", "-p", "crow", "-p", p1, "-p", p2, "-f",
                         "box", "-m", "point", "--reps", "1", "--no-images", "--no-plots", "-q",
                         "--no-cache", "--out", out, NULL};
    assert_int_equal(lib_run(own), AA_OK);
    cases_of(out, text, sizeof text);
    char want[1024];
    snprintf(want, sizeof want, "crow 128x128 box point\n%s 20x12 box point\n%s 40x24 box point\n",
             p1, p2);
    assert_string_equal(text, want);
    /* a pattern given at a size: as given */
    const char *sized[] = {"run", "--suite", "quick", "-p", p1, "-s", "16x16", "-f", "box",
                           "-m", "point", "--reps", "1", "--no-images", "--no-plots", "-q",
                           "--no-cache", "--out", out, NULL};
    assert_int_equal(lib_run(sized), AA_OK);
    cases_of(out, text, sizeof text);
    snprintf(want, sizeof want, "%s 16x16 box point\n", p1);
    assert_string_equal(text, want);
    /* The paper suite (suite.c) with -p crow -s 16x16 replacing its lists: its
     * seven groups become box x {point, supersample:n=3, area}; tent:r=1 x
     * {supersample:n=5, crowtable, crowtiler}; tent:r=0.5 x {crowtable,
     * supersample:n=5}; {box, tent:r=1} x {point, crowtiler} and x {point,
     * supersample:n=2, crowtiler}; {box, gauss:s=1} x {point, area, conetable,
     * feibushtex:texels=1000}; cone x conetable:weight=cone.  Their union
     * has 19 cases (the groups meet: crow 16x16 box point is in three), less
     * the 6 pairs the methods refuse (point and area take the box alone,
     * crowtiler, conetable and feibushtex not the box): 13 rows, each case
     * once. */
    const char *paper[] = {"run", "--suite", "paper", "-p", "crow", "-s", "16x16", "--reps",
                           "1", "--no-images", "--no-plots", "-q", "--no-cache", "--out", out,
                           NULL};
    assert_int_equal(lib_run(paper), AA_OK);
    cases_of(out, text, sizeof text);
    static const char *const want_paper[] = {
        "crow 16x16 box area",
        "crow 16x16 box point",
        "crow 16x16 box supersample:n=2",
        "crow 16x16 box supersample:n=3",
        "crow 16x16 cone conetable:weight=cone",
        "crow 16x16 gauss:s=1 conetable",
        "crow 16x16 gauss:s=1 feibushtex:texels=1000",
        "crow 16x16 tent:r=0.5 crowtable",
        "crow 16x16 tent:r=0.5 supersample:n=5",
        "crow 16x16 tent:r=1 crowtable",
        "crow 16x16 tent:r=1 crowtiler",
        "crow 16x16 tent:r=1 supersample:n=2",
        "crow 16x16 tent:r=1 supersample:n=5",
    };
    size_t nwant = sizeof want_paper / sizeof *want_paper, nrows = 0;
    for (const char *line = text; *line; line = strchr(line, '\n') + 1) {
        size_t len = strcspn(line, "\n"), k = 0;
        while (k < nwant && !(strlen(want_paper[k]) == len && !strncmp(line, want_paper[k], len)))
            k++;
        if (k == nwant)
            fail_msg("run --suite paper -p crow -s 16x16 measured %.*s", (int)len, line);
        for (const char *other = text; other < line; other = strchr(other, '\n') + 1)
            if (!strncmp(other, line, len + 1))
                fail_msg("run --suite paper -p crow -s 16x16 measured %.*s twice", (int)len,
                         line);
        nrows++;
    }
    assert_int_equal(nrows, nwant);
}

/* Temporary files (aa_temp_name's .aa-PID-N.ext) left by a run killed
 * outright are removed when it is resumed; those of a process still
 * running, and other hidden files, are kept. */
static void test_resume_removes_stale(void **state)
{
    (void)state;
    char out[300], path[600];
    snprintf(out, sizeof out, "%s/stale", dir);
    const char *run[] = {"run", "-p", "crow", "-f", "box", "-s", "24x24", "-m", "point",
                         "--reps", "1", "--no-plots", "-q", "--no-cache", "--out", out, NULL};
    assert_int_equal(lib_run(run), AA_OK);
    pid_t dead = fork();
    assert_true(dead >= 0);
    if (dead == 0)
        _exit(0);
    int status;
    assert_int_equal(waitpid(dead, &status, 0), dead);
    const char *stale[] = {"%s/.aa-%ld-3.csv", "%s/images/.aa-%ld-17.exr", "%s/.aa-%ld-4"};
    const char *kept[] = {"%s/.aa-%ld-5.csv", "%s/.keep-%ld"};
    for (size_t k = 0; k < 3; k++) {
        snprintf(path, sizeof path, stale[k], out, (long)dead);
        assert_int_equal(aa_file_write_atomic(path, "x", 1), AA_OK);
    }
    for (size_t k = 0; k < 2; k++) {
        snprintf(path, sizeof path, kept[k], out, (long)getpid());
        assert_int_equal(aa_file_write_atomic(path, "x", 1), AA_OK);
    }
    aa_run_options opt;
    aa_run_options_default(&opt);
    opt.cache = "";
    aa_runfolder *rf = NULL;
    assert_int_equal(aa_runfolder_open(out, &opt, &rf), AA_OK);
    aa_runfolder_free(rf);
    for (size_t k = 0; k < 3; k++) {
        snprintf(path, sizeof path, stale[k], out, (long)dead);
        if (access(path, F_OK) == 0)
            fail_msg("%s left after --resume", path);
    }
    for (size_t k = 0; k < 2; k++) {
        snprintf(path, sizeof path, kept[k], out, (long)getpid());
        if (access(path, F_OK) != 0)
            fail_msg("%s removed", path);
        unlink(path);
    }
}

/* SIGHUP (the terminal closed) ends a run as SIGINT and SIGTERM do: after
 * the case under way, the rows kept, no temporary file, a message, 130. */
static void test_hangup(void **state)
{
    (void)state;
    char out[300], log[400], csv[400], cmd[900];
    snprintf(out, sizeof out, "%s/hangup", dir);
    snprintf(log, sizeof log, "%s/hangup.log", dir);
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    const char *run[] = {"run", "-p", "crow", "-f", "box", "-s", "64x64", "-s", "128x128",
                         "-s", "192x192", "-s", "256x256", "-m", "point", "-m",
                         "supersample:n=6", "--reps", "30", "--out", out, "--no-cache", "-q",
                         NULL};
    pid_t pid = support_aabench_spawn(run, NULL, log, log);
    /* once the first case is saved */
    for (int k = 0; k < 6000 && access(csv, F_OK) != 0; k++)
        usleep(5000);
    kill(pid, SIGHUP);
    int code = support_wait(pid);
    FILE *f = fopen(log, "r");
    size_t n = f ? fread(output, 1, sizeof output - 1, f) : 0;
    output[n] = '\0';
    if (f)
        fclose(f);
    if (code != 130 || !strstr(output, "interrupted"))
        fail_msg("run after SIGHUP: exit %d, output: %s", code, output);
    aa_row *rows;
    size_t nrows;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &nrows), AA_OK);
    free(rows);
    assert_true(nrows >= 1 && nrows < 8);
    snprintf(cmd, sizeof cmd, "test -z \"$(find %s -name '.*' ! -name '.' | head -1)\"", out);
    if (system(cmd) != 0)
        fail_msg("temporary files left in %s", out);
}

static int setup(void **state)
{
    const char *plugin = getenv("AABENCH_PLUGIN");
    if (!getenv("AABENCH") || !plugin || support_tmpdir(dir, sizeof dir, "run") != 0)
        return -1;
    *state = dir; /* removed by support_teardown_dir */
    return aa_plugin_load(plugin) ? -1 : 0;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test(test_reports_parse_back),
             cmocka_unit_test(test_gate),
             cmocka_unit_test(test_cache_options),
             cmocka_unit_test(test_cache_unusable),
             cmocka_unit_test(test_table_names),
             cmocka_unit_test(test_interrupted),
             cmocka_unit_test(test_ignored_options),
             cmocka_unit_test(test_resume_removes_stale),
             cmocka_unit_test(test_group_cases),
             cmocka_unit_test(test_hangup))
