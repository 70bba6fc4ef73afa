/*
 * test_gates.c: the gates cannot be fooled: `diff` reads the results file
 * it is given (a results.json as JSON, never the results.csv beside it),
 * and `check` and `diff` judge a case by one rule (aa_case_verdict), a case
 * missing from the new run failing both; `merge` checks each shard's rows
 * against their cases and each shard's cases against the run's plan.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

static char dir[] = "/tmp/aabench-gates-XXXXXX";

/* A measured row of crow 16x8 box: rmse, its largest error twice that,
 * ten repetition times of `scale` seconds and a little more. */
static void fill_row(aa_row *r, const char *method, double rmse, double scale)
{
    memset(r, 0, sizeof *r);
    snprintf(r->pattern, sizeof r->pattern, "crow");
    snprintf(r->filter, sizeof r->filter, "box");
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->canonical, sizeof r->canonical, "%s", method);
    r->w = 16, r->h = 8, r->seed = 1, r->threads = 1, r->ok = 1, r->case_index = -1;
    r->m.rmse = rmse, r->m.max_err = 2 * rmse;
    aa_timing *t = &r->timing;
    t->n = 10, t->threads = 1, t->target_ci = 0.02;
    for (int k = 0; k < 10; k++)
        t->wall[k] = t->cpu[k] = scale * (1.0 + 0.01 * k);
    aa_time_stats_compute(t->wall, 10, &t->stats);
    r->seconds = t->stats.median, r->reps = 10, r->seeds = 1;
}

static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static int diff(const char *a, const char *b, char *out, size_t cap)
{
    const char *args[] = {"diff", a, b, NULL};
    return support_aabench(args, out, cap);
}

/* results.json written, read back as JSON: the same cases, errors and
 * times; its own numbers, not those of a results.csv beside it. */
static void test_json_read_back(void **state)
{
    (void)state;
    aa_row r[2], *back;
    size_t n;
    char json[256], csv[256];
    fill_row(&r[0], "point", 0.25, 1e-3);
    fill_row(&r[1], "jitter:spp=4", 0.125, 2e-3);
    r[1].ok = 0, r[1].m.rmse = r[1].m.max_err = 0;
    snprintf(r[1].note, sizeof r[1].note, "refused: the filter");
    snprintf(json, sizeof json, "%s/rt/results.json", dir);
    snprintf(csv, sizeof csv, "%s/rt/results.csv", dir);
    char sub[128];
    snprintf(sub, sizeof sub, "%s/rt", dir);
    assert_int_equal(aa_mkdirs(sub), AA_OK);
    assert_int_equal(aa_results_write_json(json, NULL, r, 2), AA_OK);
    /* a results.csv beside it with other numbers: never read */
    r[0].m.rmse = 0.5;
    assert_int_equal(aa_rows_write_csv(csv, r, 1), AA_OK);
    assert_int_equal(aa_results_load(json, &back, &n), AA_OK);
    assert_int_equal(n, 2);
    assert_string_equal(back[0].method, "point");
    assert_true(back[0].ok && back[0].m.rmse == 0.25 && back[0].m.max_err == 0.5);
    assert_int_equal(back[0].timing.n, 10);
    assert_true(back[0].timing.wall[9] == 1e-3 * 1.09);
    assert_true(back[0].w == 16 && back[0].h == 8 && back[0].seed == 1);
    assert_true(!back[1].ok && !strcmp(back[1].note, "refused: the filter"));
    free(back);
}

/* diff OLD.json NEW.json: a NEW whose errors are tenfold is a regression
 * (exit 1) although the results.csv beside it equals OLD; a NEW that is
 * not a results file is refused (exit 2) naming it. */
static void test_diff_reads_json(void **state)
{
    (void)state;
    aa_row r[2];
    char a[256], b[256], bcsv[256], bad[256], sub[2][128], out[8192];
    for (int k = 0; k < 2; k++) {
        snprintf(sub[k], sizeof sub[k], "%s/j%d", dir, k);
        assert_int_equal(aa_mkdirs(sub[k]), AA_OK);
    }
    snprintf(a, sizeof a, "%s/results.json", sub[0]);
    snprintf(b, sizeof b, "%s/results.json", sub[1]);
    snprintf(bcsv, sizeof bcsv, "%s/results.csv", sub[1]);
    snprintf(bad, sizeof bad, "%s/bad.json", dir);
    fill_row(&r[0], "point", 0.025, 1e-3);
    fill_row(&r[1], "area", 0.0125, 2e-3);
    assert_int_equal(aa_results_write_json(a, NULL, r, 2), AA_OK);
    assert_int_equal(aa_rows_write_csv(bcsv, r, 2), AA_OK);
    assert_int_equal(diff(a, a, out, sizeof out), 0);
    r[0].m.rmse *= 10, r[0].m.max_err *= 10;
    r[1].m.rmse *= 10, r[1].m.max_err *= 10;
    assert_int_equal(aa_results_write_json(b, NULL, r, 2), AA_OK);
    int st = diff(a, b, out, sizeof out);
    if (st != 1 || !strstr(out, "2 regressions"))
        fail_msg("diff of a tenfold NEW: exit %d: %s", st, out);
    put_file(bad, "{\"context\": null, \"results\": [{\"pattern\": \"crow\"}]}\n");
    st = diff(a, bad, out, sizeof out);
    if (st != 2 || !strstr(out, "bad.json") || !strstr(out, "\"size\""))
        fail_msg("diff of a malformed NEW: exit %d: %s", st, out);
    put_file(bad, "garbage\n");
    st = diff(a, bad, out, sizeof out);
    if (st != 2 || !strstr(out, "not JSON"))
        fail_msg("diff of garbage: exit %d: %s", st, out);
}

/* One rule: a case of OLD missing from NEW fails `diff` as it fails
 * `check` (exit 1, named); a case only in NEW does not. */
static void test_diff_missing_case(void **state)
{
    (void)state;
    aa_row r[2];
    char a[128], b[128], out[8192];
    snprintf(a, sizeof a, "%s/m-old.csv", dir);
    snprintf(b, sizeof b, "%s/m-new.csv", dir);
    fill_row(&r[0], "point", 0.25, 1e-3);
    fill_row(&r[1], "area", 0.125, 2e-3);
    assert_int_equal(aa_rows_write_csv(a, r, 2), AA_OK);
    assert_int_equal(aa_rows_write_csv(b, r, 1), AA_OK);
    int st = diff(a, b, out, sizeof out);
    if (st != 1 || !strstr(out, "REGRESSION area on crow 16x8 box: missing"))
        fail_msg("diff with a case missing from NEW: exit %d: %s", st, out);
    st = diff(b, a, out, sizeof out);
    if (st != 0)
        fail_msg("diff with a case only in NEW: exit %d: %s", st, out);
}

/* The rule itself, against figures derived by hand: tolerance 1e-3 on
 * 0.25 allows up to 0.25025 + 1e-12. */
static void test_verdict_rule(void **state)
{
    (void)state;
    aa_row o, r;
    int confirmed;
    char detail[256];
    fill_row(&o, "point", 0.25, 1e-3);
    r = o;
    assert_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    r.m.rmse = 0.25025;
    assert_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    r.m.rmse = 0.2503;
    assert_non_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    assert_non_null(aa_case_verdict(&o, NULL, 1e-3, detail, sizeof detail, &confirmed));
    r = o, r.ok = 0;
    assert_non_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    o.ok = 0;
    assert_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    assert_int_equal(confirmed, 1);
    r.failed = 1;
    assert_non_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    /* the same errors from other files: not the same case's result */
    fill_row(&o, "point", 0.25, 1e-3);
    r = o;
    snprintf(o.inputs, sizeof o.inputs, "file fnv1a 0000000000000001 bytes 10");
    snprintf(r.inputs, sizeof r.inputs, "file fnv1a 0000000000000002 bytes 10");
    assert_non_null(aa_case_verdict(&o, &r, 1e-3, detail, sizeof detail, &confirmed));
    assert_non_null(strstr(detail, "0000000000000002"));
}


/* ---- merge trusts no shard ---- */

#define SHARD_RUN "run", "-p", "crow", "-s", "24x16", "-s", "16x16", "-f", "box", "-m", "point", \
                  "-m", "area", "--reps", "1", "--no-plots", "--no-images", "--threads", "1", "-q"

static void sh(const char *fmt, const char *a, const char *b)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, fmt, a, b);
    int st = system(cmd);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
}

static int merge(const char *s1, const char *s2, const char *out, char *text, size_t cap)
{
    const char *args[] = {"merge", s1, s2, "--out", out, "-q", NULL};
    return support_aabench(args, text, cap);
}

/* The same merge through the library (aa_runfolder_merge, which the command
 * calls) in this process, for the refusals after the first of a kind
 * through the command: the exit status the command would give, the
 * library's message in `text`; a start of the command fewer each. */
static int merge_lib(const char *s1, const char *s2, const char *out, char *text, size_t cap)
{
    const char *dirs[] = {s1, s2};
    aa_run_options opt;
    aa_run_options_default(&opt);
    opt.out = out;
    aa_runfolder *rf = NULL;
    int st = aa_runfolder_merge(dirs, 2, &opt, &rf);
    if (!st) {
        st = aa_runfolder_finish(rf);
        aa_runfolder_free(rf);
    }
    snprintf(text, cap, "%s", st ? aa_last_error() : "");
    return st ? aa_exit_code(st) : 0;
}

/* `run ARGS...` through the library's run folder in this process, as the
 * command does but for its printing: the library's status, its message in
 * `text`.  The shards below are run so, not by starting the command: one
 * OpenImageIO load between those with images (this process's) instead of
 * one a shard (0.9 s of CPU each, 1.8 s under the sanitizers); what merge
 * checks is their folders, made the same way. */
static int lib_run(const char *const *args, char *text, size_t cap)
{
    int st = support_lib_run(args, NULL, NULL);
    snprintf(text, cap, "%s", st ? aa_last_error() : "");
    return st;
}

/* A shard's results.csv rewritten with row `k` changed by `edit`. */
static void edit_rows(const char *shard, void (*edit)(aa_row *r))
{
    char csv[512];
    aa_row *rows;
    size_t n;
    snprintf(csv, sizeof csv, "%s/results.csv", shard);
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_true(n >= 1);
    edit(&rows[0]);
    assert_int_equal(aa_rows_write_csv(csv, rows, n), AA_OK);
    free(rows);
}

/* The shard's manifest made to record its results.csv as it now is (a
 * shard whose own run wrote the row so). */
static void resum(const char *shard)
{
    char path[512], csv[512];
    aa_manifest m;
    snprintf(path, sizeof path, "%s/run.json", shard);
    snprintf(csv, sizeof csv, "%s/results.csv", shard);
    assert_int_equal(aa_manifest_read(path, &m), AA_OK);
    assert_true(m.summed);
    int found = 0;
    for (size_t k = 0; k < m.nsums; k++)
        if (!strcmp(m.sums[k].name, "results.csv")) {
            assert_int_equal(aa_file_checksum(csv, m.sums[k].sum), AA_OK);
            found = 1;
        }
    assert_true(found);
    assert_int_equal(aa_manifest_write(path, &m), AA_OK);
    aa_manifest_free(&m);
}

static void other_method(aa_row *r)
{
    snprintf(r->method, sizeof r->method, "%s", strcmp(r->method, "point") ? "point" : "area");
}

static void other_canonical(aa_row *r)
{
    snprintf(r->canonical, sizeof r->canonical, "%s",
             strcmp(r->method, "point") ? "point" : "area");
}

static void test_merge_checks_rows(void **state)
{
    (void)state;
    char cache[256], s[2][256], t[256], out[256], text[8192];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(t, sizeof t, "%s/tampered", dir);
    snprintf(out, sizeof out, "%s/merged", dir);
    for (int k = 0; k < 2; k++) {
        char shard[16];
        snprintf(s[k], sizeof s[k], "%s/shard%d", dir, k + 1);
        snprintf(shard, sizeof shard, "%d/2", k + 1);
        const char *args[] = {SHARD_RUN, "--cache", cache, "--shard", shard, "--out", s[k], NULL};
        if (lib_run(args, text, sizeof text) != AA_OK)
            fail_msg("shard %s: %s", shard, text);
    }
    if (merge(s[0], s[1], out, text, sizeof text) != 0)
        fail_msg("merge of two true shards: %s", text);
    /* a shard with rows: the first whose results.csv is there */
    char csv[512];
    snprintf(csv, sizeof csv, "%s/results.csv", s[0]);
    const char *src = access(csv, F_OK) == 0 ? s[0] : s[1], *other = src == s[0] ? s[1] : s[0];
    void (*edits[])(aa_row *) = {other_method, other_canonical};
    for (size_t e = 0; e < sizeof edits / sizeof *edits; e++) {
        sh("rm -rf '%s'%s", t, "");
        sh("cp -R '%s' '%s'", src, t);
        edit_rows(t, edits[e]);
        sh("rm -rf '%s'%s", out, "");
        /* edited after its run: its checksum tells (through the command once) */
        int st = (e == 0 ? merge : merge_lib)(t, other, out, text, sizeof text);
        if (st != 2 || !strstr(text, "edited or damaged"))
            fail_msg("merge of a shard whose results.csv was edited: exit %d: %s", st, text);
        /* written so by its run: the row is not its case */
        resum(t);
        st = merge_lib(t, other, out, text, sizeof text);
        if (st != 2 || !strstr(text, "is not its case"))
            fail_msg("merge of a shard whose row %s was edited: exit %d: %s",
                     e ? "canonical name" : "method", st, text);
        snprintf(csv, sizeof csv, "%s/results.csv", out);
        assert_int_equal(access(csv, F_OK), -1);
    }
    /* a manifest whose cases are not its shard's */
    sh("rm -rf '%s'%s", t, "");
    sh("cp -R '%s' '%s'", src, t);
    char path[512];
    aa_manifest m;
    snprintf(path, sizeof path, "%s/run.json", t);
    assert_int_equal(aa_manifest_read(path, &m), AA_OK);
    assert_true(m.nselected >= 1);
    m.nselected--;
    assert_int_equal(aa_manifest_write(path, &m), AA_OK);
    aa_manifest_free(&m);
    sh("rm -rf '%s'%s", out, "");
    int st = merge_lib(t, other, out, text, sizeof text);
    if (st != 2 || !strstr(text, "an edited manifest"))
        fail_msg("merge of a shard whose manifest was edited: exit %d: %s", st, text);
}

/* ---- input files by their hash ---- */

static void write_svg(const char *path, const char *width)
{
    char text[512];
    snprintf(text, sizeof text,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"16\">"
             "<rect x=\"2\" y=\"3\" width=\"%s\" height=\"7.25\" fill=\"white\"/></svg>\n",
             width);
    put_file(path, text);
}

/* A run of an SVG file records the file's hash in each row; once the file
 * changes, `check` against that baseline, `run --resume` of its folder and
 * `merge` of shards made before and after are refused (exit 2), naming the
 * pattern's file. */
static void test_changed_input_file(void **state)
{
    (void)state;
    char svg[256], pattern[300], cache[256], run[256], csv[300], s1[256], s2[256], out[256];
    char text[8192];
    snprintf(svg, sizeof svg, "%s/scene.svg", dir);
    snprintf(pattern, sizeof pattern, "svg:file=%s", svg);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(run, sizeof run, "%s/svgrun", dir);
    snprintf(csv, sizeof csv, "%s/results.csv", run);
    snprintf(s1, sizeof s1, "%s/svg1", dir);
    snprintf(s2, sizeof s2, "%s/svg2", dir);
    snprintf(out, sizeof out, "%s/svgmerged", dir);
    write_svg(svg, "9.5");
#define SVG_RUN "run", "-p", pattern, "-s", "16x16", "-s", "24x24", "-f", "box", "-m", "point", \
                "--reps", "1", "--no-images", "--no-plots", "--threads", "1", "-q", "--cache", cache
    const char *whole[] = {SVG_RUN, "--out", run, NULL};
    const char *first[] = {SVG_RUN, "--shard", "1/2", "--out", s1, NULL};
    const char *second[] = {SVG_RUN, "--shard", "2/2", "--out", s2, NULL};
    const char *check[] = {"check", "--baseline", csv, "--cache", cache, NULL};
    const char *resume[] = {"run", "--resume", run, "--cache", cache, "-q", NULL};
    const char *join[] = {"merge", s1, s2, "--out", out, "-q", NULL};
    if (support_aabench(whole, text, sizeof text) || support_aabench(first, text, sizeof text))
        fail_msg("run of %s: %s", pattern, text);
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_int_equal(n, 2);
    assert_non_null(strstr(rows[0].inputs, "fnv1a"));
    /* run.json records them too, by the pattern that reads the file */
    char manifest[300];
    aa_manifest m;
    snprintf(manifest, sizeof manifest, "%s/run.json", run);
    assert_int_equal(aa_manifest_read(manifest, &m), AA_OK);
    assert_int_equal(m.ninputs, 1);
    assert_true(!strncmp(m.inputs[0].what, "pattern svg:file=", 17));
    assert_string_equal(m.inputs[0].inputs, rows[0].inputs);
    aa_manifest_free(&m);
    free(rows);
    if (support_aabench(check, text, sizeof text) != 0)
        fail_msg("check against its own baseline: %s", text);
    /* the file changes: a different scene under the same name */
    write_svg(svg, "10.5");
    int st = support_aabench(check, text, sizeof text);
    if (st != 2 || !strstr(text, svg) || !strstr(text, "has changed"))
        fail_msg("check after the file changed: exit %d: %s", st, text);
    st = support_aabench(resume, text, sizeof text);
    if (st != 2 || !strstr(text, svg) || !strstr(text, "changed"))
        fail_msg("resume after the file changed: exit %d: %s", st, text);
    if (support_aabench(second, text, sizeof text) != 0)
        fail_msg("shard 2/2: %s", text);
    st = support_aabench(join, text, sizeof text);
    if (st != 2 || !strstr(text, svg) || !strstr(text, "differ"))
        fail_msg("merge of shards of two files: exit %d: %s", st, text);
#undef SVG_RUN
}

/* Images: each checked against the checksum its shard recorded; one
 * changed, added or removed is refused, naming it, and nothing written. */
static void test_merge_checks_images(void **state)
{
    (void)state;
    char cache[256], s[2][256], t[256], out[256], text[8192], img[512], csv[512];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(t, sizeof t, "%s/itampered", dir);
    snprintf(out, sizeof out, "%s/imerged", dir);
    for (int k = 0; k < 2; k++) {
        char shard[16];
        snprintf(s[k], sizeof s[k], "%s/ishard%d", dir, k + 1);
        snprintf(shard, sizeof shard, "%d/2", k + 1);
        const char *args[] = {"run", "-p", "crow", "-s", "16x16", "-s", "8x8", "-f", "box",
                              "-m", "point", "--reps", "1", "--no-plots", "--threads", "1",
                              "-q", "--cache", cache, "--shard", shard, "--out", s[k], NULL};
        if (lib_run(args, text, sizeof text) != AA_OK)
            fail_msg("shard %s: %s", shard, text);
    }
    if (merge(s[0], s[1], out, text, sizeof text) != 0)
        fail_msg("merge of two true shards: %s", text);
    snprintf(csv, sizeof csv, "%s/results.csv", s[0]);
    const char *src = access(csv, F_OK) == 0 ? s[0] : s[1], *other = src == s[0] ? s[1] : s[0];
    const char *steps[] = {
        /* one byte of an image changed (the last: a PNG's end, a PFM's data) */
        "f=$(ls '%s'/images/* | head -1) && printf 'x' | dd of=\"$f\" bs=1 seek=$(($(wc -c < \"$f\") - 1)) conv=notrunc 2>/dev/null%s",
        /* an image added */
        "cp \"$(ls '%s'/images/* | head -1)\" '%s'/images/extra.png",
        /* an image removed */
        "rm \"$(ls '%s'/images/* | head -1)\"%s"};
    const char *expect[] = {"is not the image its run wrote", "its run wrote no such image",
                            "images its run wrote are missing"};
    for (size_t k = 0; k < 3; k++) {
        sh("rm -rf '%s' '%s'", t, out);
        sh("cp -R '%s' '%s'", src, t);
        if (k == 1)
            sh(steps[k], t, t);
        else
            sh(steps[k], t, "");
        int st = (k == 0 ? merge : merge_lib)(t, other, out, text, sizeof text);
        if (st != 2 || !strstr(text, expect[k]))
            fail_msg("merge, step %zu: exit %d: %s", k, st, text);
        snprintf(img, sizeof img, "%s/images", out);
        assert_int_equal(access(img, F_OK), -1);
    }
}

/* A plug-in is recorded by its file's hash too: a baseline of its method
 * is refused by `check` (exit 2, naming the plug-in) once the file loaded
 * under the same name is another. */
static void test_changed_plugin(void **state)
{
    (void)state;
    const char *exe = getenv("AABENCH");
    assert_non_null(exe);
    const char *slash = strrchr(exe, '/');
    assert_non_null(slash);
    char so[512], lib[256], cache[256], run[256], csv[300], text[8192];
    snprintf(so, sizeof so, "%.*s/tests/plugin_example.so", (int)(slash - exe), exe);
    snprintf(lib, sizeof lib, "%s/centre4.so", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(run, sizeof run, "%s/pluginrun", dir);
    snprintf(csv, sizeof csv, "%s/results.csv", run);
    sh("cp '%s' '%s'", so, lib);
    const char *args[] = {"run", "--plugin", lib, "-p", "crow", "-s", "16x16", "-f", "box",
                          "-m", "centre4", "-m", "point", "--reps", "1", "--no-images",
                          "--no-plots", "--threads", "1", "-q", "--cache", cache, "--out", run,
                          NULL};
    const char *check[] = {"check", "--plugin", lib, "--baseline", csv, "--cache", cache, NULL};
    if (support_aabench(args, text, sizeof text) != 0)
        fail_msg("run of a plug-in's method: %s", text);
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_int_equal(n, 2);
    for (size_t k = 0; k < n; k++)
        assert_int_equal(strstr(rows[k].inputs, "plugin fnv1a") != NULL,
                         !strcmp(rows[k].method, "centre4"));
    free(rows);
    if (support_aabench(check, text, sizeof text) != 0)
        fail_msg("check against its own baseline: %s", text);
    /* another file under the same name: one byte more (still loadable) */
    sh("printf x >> '%s'%s", lib, "");
    int st = support_aabench(check, text, sizeof text);
    if (st != 2 || !strstr(text, "the plug-in") || !strstr(text, "centre4.so"))
        fail_msg("check after the plug-in changed: exit %d: %s", st, text);
}

/* An external method's adapter is recorded by its file's hash: once the
 * adapter changes, `check` of its baseline is refused (exit 2), naming it. */
static void test_changed_adapter(void **state)
{
    (void)state;
    char ren[256], adapter[300], png[256], cache[256], run[256], csv[300], text[8192];
    snprintf(ren, sizeof ren, "%s/renderers", dir);
    snprintf(adapter, sizeof adapter, "%s/mine", ren);
    snprintf(png, sizeof png, "%s/crow16.png", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(run, sizeof run, "%s/adapterrun", dir);
    snprintf(csv, sizeof csv, "%s/results.csv", run);
    assert_int_equal(aa_mkdirs(ren), AA_OK);
    const char *image[] = {"render", "-p", "crow", "-s", "16x16", "-f", "box", "-m", "point",
                           "-o", png, NULL};
    if (support_aabench(image, text, sizeof text) != 0)
        fail_msg("render: %s", text);
    /* an adapter that "draws" the PNG made above */
    char script[600];
    snprintf(script, sizeof script, "#!/bin/sh\n[ \"$1\" = --check ] && exit 0\ncp '%s' \"$4\"\n",
             png);
    put_file(adapter, script);
    sh("chmod +x '%s'%s", adapter, "");
    assert_int_equal(setenv("AABENCH_RENDERERS", ren, 1), 0);
    const char *args[] = {"run", "-p", "crow", "-s", "16x16", "-f", "box", "-m",
                          "external:renderer=mine", "--reps", "1", "--no-images", "--no-plots",
                          "-q", "--cache", cache, "--out", run, NULL};
    const char *check[] = {"check", "--baseline", csv, "--cache", cache, NULL};
    if (support_aabench(args, text, sizeof text) != 0)
        fail_msg("run of an external method: %s", text);
    if (support_aabench(check, text, sizeof text) != 0)
        fail_msg("check against its own baseline: %s", text);
    sh("echo '# changed' >> '%s'%s", adapter, "");
    int st = support_aabench(check, text, sizeof text);
    unsetenv("AABENCH_RENDERERS");
    if (st != 2 || !strstr(text, "the adapter") || !strstr(text, adapter))
        fail_msg("check after the adapter changed: exit %d: %s", st, text);
}

static int setup(void **state)
{
    *state = dir;
    return mkdtemp(dir) ? 0 : -1;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test(test_json_read_back),
             cmocka_unit_test(test_diff_reads_json),
             cmocka_unit_test(test_diff_missing_case),
             cmocka_unit_test(test_verdict_rule),
             cmocka_unit_test(test_merge_checks_rows),
             cmocka_unit_test(test_merge_checks_images),
             cmocka_unit_test(test_changed_input_file),
             cmocka_unit_test(test_changed_plugin),
             cmocka_unit_test(test_changed_adapter))
