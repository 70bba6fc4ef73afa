/*
 * test_shard.c: sharded runs, their merge, resumed runs and the shared
 * reference cache.
 *
 *  - The partition (harness/bench/shard.c): for 1 to 7 shards every case is
 *    in exactly one, the same on every call; costs are the documented
 *    products (pixels x samples), worked out here by hand.
 *  - The peer of a merged run is the unsharded run of the same command:
 *    nine cases of the quick suite run whole, and as 2 shards through GNU parallel
 *    (scripts/gnu-parallel-run.sh, 2 jobs) then merged, must give the same
 *    rows (every error, count and note read back equal, bit for bit), the
 *    same images and the same montage.png, byte for byte.
 *  - A missing, duplicated or foreign shard is refused (exit 2) naming it,
 *    and nothing is written.
 *  - --resume keeps the cases in a run's results (marked here by a host
 *    name no machine has) and measures only the rest, to the same errors;
 *    another command or commit is refused saying what differs.
 *  - truth --warm computes a suite's references once; two processes
 *    writing the same reference at once leave one whole file, which reads
 *    back (its checksum verified) as the reference computed afresh.
 *
 * Runs, resumes, merges and warms go through the library's run folder in
 * this process (lib(): what the command does, but its printing); the
 * command ($AABENCH) is started for what only it does (the driver's
 * shards, a resumed command checked against the run's, its messages,
 * two processes at once), from the repository's top folder as the
 * Makefile does.  No test looks at a time.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "bench.h"
#include "support.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[4096];
static char log_text[1 << 16];

/* ---- helpers ---- */

static int aabench(const char *const *args)
{
    return support_aabench(args, log_text, sizeof log_text);
}

/* sh SCRIPT ARGS..., output into log_text; the exit status.  Killed (with
 * its process group) after SUPPORT_TIMEOUT seconds. */
static int run_script(const char *const *args)
{
    char path[4608];
    snprintf(path, sizeof path, "%s/script.log", dir);
    const char *argv[64] = {"sh"};
    size_t n = 1;
    for (; args[n - 1] && n < 63; n++)
        argv[n] = args[n - 1];
    argv[n] = NULL;
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        setpgid(0, 0);
        int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 1);
        dup2(fd, 2);
        execvp("sh", (char *const *)argv);
        _exit(127);
    }
    int status = 0, waited = 0;
    for (int ms = 0; ms < SUPPORT_TIMEOUT * 1000; ms += 20) {
        if (waitpid(pid, &status, WNOHANG) == pid) {
            waited = 1;
            break;
        }
        usleep(20000);
    }
    if (!waited) {
        kill(-pid, SIGKILL);
        waitpid(pid, &status, 0);
    }
    support_read_file(path, log_text, sizeof log_text, NULL);
    if (!waited)
        fail_msg("%s timed out:\n%s", args[0], log_text);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static void rows_of(const char *folder, aa_row **rows, size_t *n)
{
    char path[4608];
    snprintf(path, sizeof path, "%s/results.csv", folder);
    if (aa_rows_read_csv(path, rows, n))
        fail_msg("%s: %s", path, aa_last_error());
}

/* Every measured value and every note, not the times: bit for bit. */
static void same_rows(const aa_row *a, size_t na, const aa_row *b, size_t nb)
{
    assert_int_equal(na, nb);
    for (size_t k = 0; k < na; k++) {
        const aa_row *x = &a[k], *y = &b[k];
        assert_string_equal(x->pattern, y->pattern);
        assert_string_equal(x->filter, y->filter);
        assert_string_equal(x->method, y->method);
        assert_string_equal(x->canonical, y->canonical);
        assert_string_equal(x->note, y->note);
        assert_int_equal(x->w, y->w);
        assert_int_equal(x->h, y->h);
        assert_int_equal(x->ok, y->ok);
        assert_int_equal(x->case_index, (long)k);
        assert_int_equal(y->case_index, (long)k);
        if (memcmp(&x->m, &y->m, sizeof x->m) || x->spp != y->spp ||
            x->samples != y->samples || x->expensive_pixels != y->expensive_pixels ||
            x->seeds != y->seeds)
            fail_msg("%s on %s %dx%d %s: the errors differ (rmse %.17g and %.17g)", x->method,
                     x->pattern, x->w, x->h, x->filter, x->m.rmse, y->m.rmse);
        assert_true(*y->host != '\0');
    }
}

static void same_file(const char *a, const char *b)
{
    static char x[1 << 22], y[1 << 22];
    size_t nx, ny;
    support_read_file(a, x, sizeof x, &nx);
    support_read_file(b, y, sizeof y, &ny);
    if (nx != ny || memcmp(x, y, nx))
        fail_msg("%s and %s differ", a, b);
}

/* Every file of a/images is in b/images, and as many: the PNGs the same
 * bytes, the EXRs the same values (OpenEXR's header may hold a date). */
static void same_images(const char *a, const char *b)
{
    char da[5632], db[5632], fa[6144], fb[6144];
    snprintf(da, sizeof da, "%s/images", a);
    snprintf(db, sizeof db, "%s/images", b);
    DIR *d = opendir(da);
    assert_non_null(d);
    struct dirent *e;
    int files = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        snprintf(fa, sizeof fa, "%s/%s", da, e->d_name);
        snprintf(fb, sizeof fb, "%s/%s", db, e->d_name);
        if (!strstr(e->d_name, ".exr")) {
            same_file(fa, fb);
        } else {
            aa_image x, y;
            if (aa_image_read(fa, &x) || aa_image_read(fb, &y))
                fail_msg("%s", aa_last_error());
            if (!support_same_image(&x, &y))
                fail_msg("%s and %s hold different values", fa, fb);
            aa_image_free(&x);
            aa_image_free(&y);
        }
        files++;
    }
    closedir(d);
    assert_true(files > 0);
    assert_int_equal(support_count_entries(db, NULL), files);
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* ---- the library in this process, as the command does ---- */

/* What the last lib() call's run folder said: the rows it kept from
 * before, the cases skipped as refused, references computed and found. */
static size_t lib_kept, lib_refused, lib_computed, lib_cached;

static int lib_fail(int st)
{
    snprintf(log_text, sizeof log_text, "%s", aa_last_error());
    return aa_exit_code(st);
}

/* `run [--resume DIR] ...`, `merge DIR... --out DIR [-q] [--cache DIR]` or
 * `truth --warm SUITE ...` through the library's run folder in this
 * process (runfolder.h), as the command does but for its printing: the
 * exit status the command gives (1 when a case failed), the library's
 * message in log_text.  What only the command does (its messages, its
 * check of a resumed command) is tested through the command. */
static int lib(const char *const *args)
{
    int argc = 0, asked, st;
    while (args[argc])
        argc++;
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf = NULL;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    opt.cache = "results/cache";
    log_text[0] = '\0';
    lib_kept = lib_refused = lib_computed = lib_cached = 0;
    if (!strcmp(args[0], "merge")) {
        const char *dirs[16];
        size_t n = 0;
        for (int k = 1; k < argc; k++) {
            if (!strcmp(args[k], "--out") && k + 1 < argc)
                opt.out = args[++k];
            else if (!strcmp(args[k], "--cache") && k + 1 < argc)
                opt.cache = args[++k];
            else if (strcmp(args[k], "-q") && n < 16)
                dirs[n++] = args[k];
        }
        assert_non_null(opt.out);
        st = aa_runfolder_merge(dirs, n, &opt, &rf);
    } else {
        const char *words[128] = {"run"};
        int n = 1;
        for (int k = 1; k < argc && n < 127; k++)
            if (!strcmp(args[k], "--warm"))
                words[n++] = "--suite";
            else if (strcmp(args[k], "truth"))
                words[n++] = args[k];
        if ((st = aa_plan_parse(n, (char *const *)words, &plan, &opt, &asked)))
            return lib_fail(st);
        assert_int_equal(asked, 0);
        if (!strcmp(args[0], "truth")) {
            st = aa_runfolder_warm(&plan, &opt, &lib_computed, &lib_cached);
            return st ? lib_fail(st) : 0;
        }
        st = opt.resume ? aa_runfolder_open(opt.resume, &opt, &rf)
                        : aa_runfolder_create(&plan, &opt, &rf);
        if (!st)
            st = aa_runfolder_run(rf);
    }
    if (!st)
        st = aa_runfolder_finish(rf);
    int code = st ? lib_fail(st) : 0;
    if (rf) {
        size_t n;
        const aa_row *rows = aa_runfolder_rows(rf, &n);
        for (size_t k = 0; k < n && !code; k++)
            code = rows[k].failed != 0;
        lib_kept = aa_runfolder_kept(rf);
        lib_refused = aa_runfolder_refused(rf);
    }
    aa_runfolder_free(rf);
    return code;
}

/* ---- the partition ---- */

static void test_partition(void **state)
{
    (void)state;
    static const char *const pnames[] = {"crow", "star"};
    static const char *const mnames[] = {"point", "supersample:n=4", "jitter:spp=16", "area",
                                         "taa"};
    static const aa_run_size sizes[] = {{32, 32}, {256, 128}, {64, 64}};
    aa_run_spec p[2], m[5];
    aa_run_filter f[2] = {{.text = "box"}, {.text = "tent:r=1"}};
    for (int k = 0; k < 2; k++) {
        p[k].text = pnames[k];
        assert_int_equal(aa_pattern_parse(pnames[k], &p[k].spec), AA_OK);
        assert_int_equal(aa_filter_parse(f[k].text, &f[k].filter), AA_OK);
    }
    for (int k = 0; k < 5; k++) {
        m[k].text = mnames[k];
        assert_int_equal(aa_spec_parse(mnames[k], aa_method_table(), "method", &m[k].spec),
                         AA_OK);
    }
    aa_run_config cfgs[2];
    memset(cfgs, 0, sizeof cfgs);
    cfgs[0].patterns = p, cfgs[0].npatterns = 2;
    cfgs[0].sizes = sizes, cfgs[0].nsizes = 3;
    cfgs[0].filters = f, cfgs[0].nfilters = 2;
    cfgs[0].methods = m, cfgs[0].nmethods = 5;
    cfgs[1] = cfgs[0];
    cfgs[1].npatterns = 1, cfgs[1].nsizes = 1, cfgs[1].nmethods = 3;
    cfgs[1].case_base = aa_run_case_count(&cfgs[0]);
    const size_t n0 = aa_run_case_count(&cfgs[0]), n1 = aa_run_case_count(&cfgs[1]);
    assert_int_equal(n0, 2 * 3 * 2 * 5);
    assert_int_equal(n1, 1 * 1 * 2 * 3);
    /* costs by hand: case 1 is crow 32x32 box supersample:n=4, 16 samples a
     * pixel; case 5 + 2 = 7 crow 32x32 tent jitter:spp=16; case 10 + 1 is
     * crow 256x128 box supersample:n=4; taa renders its `history` (64)
     * frames of one sample; every view's reference costs 16 a pixel */
    assert_true(aa_case_cost(&cfgs[0], 1) == 32 * 32 * 16);
    assert_true(aa_case_cost(&cfgs[0], 7) == 32 * 32 * 16);
    assert_true(aa_case_cost(&cfgs[0], 11) == 256 * 128 * 16);
    assert_true(aa_case_cost(&cfgs[0], 0) == 32 * 32);
    assert_true(aa_case_cost(&cfgs[0], 4) == 32 * 32 * 64);
    assert_true(aa_case_reference_cost(&cfgs[0], 11) == 256 * 128 * AA_SHARD_REFERENCE_WEIGHT);
    /* point and area refuse the tent (cases 5 and 8): nothing to render */
    assert_true(aa_case_cost(&cfgs[0], 5) == 0 && aa_case_reference_cost(&cfgs[0], 5) == 0);
    assert_true(aa_case_cost(&cfgs[0], 8) == 0);
    for (int ns = 1; ns <= 7; ns++) {
        int seen[80] = {0};
        size_t total = 0;
        uint64_t most = 0, least = UINT64_MAX;
        for (int k = 1; k <= ns; k++) {
            unsigned char *masks[2], *again[2];
            size_t sel, sel2;
            uint64_t cost, cost2;
            assert_int_equal(aa_shard_plan(cfgs, 2, k, ns, masks, &sel, &cost), AA_OK);
            assert_int_equal(aa_shard_plan(cfgs, 2, k, ns, again, &sel2, &cost2), AA_OK);
            assert_int_equal(sel, sel2);
            assert_true(cost == cost2);
            assert_memory_equal(masks[0], again[0], n0);
            assert_memory_equal(masks[1], again[1], n1);
            for (size_t c = 0; c < n0; c++)
                seen[c] += masks[0][c];
            for (size_t c = 0; c < n1; c++)
                seen[n0 + c] += masks[1][c];
            total += sel;
            most = cost > most ? cost : most;
            least = cost < least ? cost : least;
            for (int g = 0; g < 2; g++)
                free(masks[g]), free(again[g]);
        }
        assert_int_equal(total, n0 + n1);
        for (size_t c = 0; c < n0 + n1; c++)
            if (seen[c] != 1)
                fail_msg("%d shards: case %zu is in %d of them", ns, c, seen[c]);
        /* balanced: no shard above the least loaded by more than the most
         * costly case and its reference (taa at 256x128: 64 frames, and 16) */
        assert_true(most - least <= (64u + 16u) * 256 * 128);
    }
    unsigned char *masks[2];
    size_t sel;
    assert_int_equal(aa_shard_plan(cfgs, 2, 4, 3, masks, &sel, NULL), AA_EINVAL);
    assert_int_equal(aa_shard_plan(cfgs, 2, 0, 3, masks, &sel, NULL), AA_EINVAL);
}

/* ---- sharded through GNU parallel, merged, against the whole run ---- */

/* the quick suite's three views (box, tent, Gaussian) at a smaller size,
 * with three methods each takes: nine cases over three references (the
 * split and the merge depend on neither the size nor which methods; each
 * case costs its images and metrics, several times more under the
 * sanitizers) */
#define QUICK                                                                                  \
    "--suite", "quick", "-s", "48x48", "-m", "supersample:n=2", "-m", "crowtable", "-m",       \
        "jitter:spp=4", "--reps", "1", "--no-plots", "-q", "--threads", "1"

static void test_parallel_merge(void **state)
{
    (void)state;
    char whole[4608], merged[4608], cache[4608], path[5120], path2[5120];
    snprintf(whole, sizeof whole, "%s/whole", dir);
    snprintf(merged, sizeof merged, "%s/merged", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    const char *run[] = {"run", QUICK, "--cache", cache, "--out", whole, NULL};
    if (lib(run) != 0)
        fail_msg("the whole run failed:\n%s", log_text);
    /* two shards, not more: each is a start of the command that loads the
     * image module (tests/README.md: 1.6 s of CPU sanitized), and the merge's
     * checks below need no third */
    const char *drive[] = {"scripts/gnu-parallel-run.sh", "--jobs", "2", "--shards", "2",
                           QUICK, "--cache", cache, "--out", merged, NULL};
    if (run_script(drive) != 0)
        fail_msg("gnu-parallel-run.sh failed:\n%s", log_text);
    aa_row *a, *b;
    size_t na, nb;
    rows_of(whole, &a, &na);
    rows_of(merged, &b, &nb);
    same_rows(a, na, b, nb);
    free(a);
    free(b);
    /* two shards, each with some of the cases */
    for (int k = 1; k <= 2; k++) {
        snprintf(path, sizeof path, "%s/shards/%d", merged, k);
        rows_of(path, &a, &na);
        assert_true(na > 0 && na < nb);
        free(a);
    }
    snprintf(path, sizeof path, "%s/montage.png", whole);
    snprintf(path2, sizeof path2, "%s/montage.png", merged);
    same_file(path, path2);
    same_images(whole, merged);

    /* refusals, nothing written: a shard missing, given twice, of another
     * command (another seed), of another commit */
    char s1[5120], s2[5120], other[4608], out[4608];
    snprintf(s1, sizeof s1, "%s/shards/1", merged);
    snprintf(s2, sizeof s2, "%s/shards/2", merged);
    snprintf(other, sizeof other, "%s/other", dir);
    snprintf(out, sizeof out, "%s/refused", dir);
    const char *foreign[] = {"run", QUICK, "--seed", "2", "--cache", cache, "--shard", "2/3",
                             "--out", other, NULL};
    assert_int_equal(lib(foreign), 0);
    const char *missing[] = {"merge", s1, "--out", out, NULL};
    assert_int_equal(lib(missing), 2);
    assert_non_null(strstr(log_text, "shard 2/2 missing"));
    const char *into[] = {"merge", s1, s2, "--out", s2, NULL};
    assert_int_equal(lib(into), 2);
    assert_non_null(strstr(log_text, "is one of the shards' folders"));
    const char *twice[] = {"merge", s1, s2, s2, "--out", out, NULL};
    assert_int_equal(lib(twice), 2);
    assert_non_null(strstr(log_text, s2));
    assert_non_null(strstr(log_text, "given twice"));
    const char *mixed[] = {"merge", s1, other, "--out", out, NULL};
    assert_int_equal(lib(mixed), 2);
    assert_non_null(strstr(log_text, other));
    assert_non_null(strstr(log_text, "--seed 2"));
    assert_false(exists(out));
    /* a shard that stopped part-way (its last case lost): named, then
     * resumed, measuring only that case, and merged equal to the whole */
    aa_row *rows;
    size_t nr;
    char csv2[5632], again[4608];
    rows_of(s2, &rows, &nr);
    assert_true(nr >= 2);
    snprintf(csv2, sizeof csv2, "%s/results.csv", s2);
    assert_int_equal(aa_rows_write_csv(csv2, rows, nr - 1), AA_OK);
    const char *stopped[] = {"merge", s1, s2, "--out", out, NULL};
    assert_int_equal(lib(stopped), 2);
    assert_non_null(strstr(log_text, "has not measured all its cases (1 missing)"));
    assert_non_null(strstr(log_text, "aabench run --resume"));
    assert_false(exists(out));
    /* --threads is no part of the command (the manifest leaves it out):
     * one thread, as the shards ran */
    const char *resume[] = {"run", "--resume", s2, "--cache", cache, "-q", "--threads", "1",
                            NULL};
    if (lib(resume) != 0)
        fail_msg("resuming shard 2 failed:\n%s", log_text);
    assert_int_equal(lib_kept, nr - 1);
    aa_row *back;
    size_t nback;
    rows_of(s2, &back, &nback);
    assert_int_equal(nback, nr);
    for (size_t k = 0; k + 1 < nr; k++) /* the kept ones as they were */
        assert_memory_equal(back[k].timing.wall, rows[k].timing.wall,
                            (size_t)rows[k].timing.n * sizeof *rows[k].timing.wall);
    free(rows);
    free(back);
    snprintf(again, sizeof again, "%s/again", dir);
    const char *remerge[] = {"merge", s2, s1, "--out", again, "-q", NULL};
    if (lib(remerge) != 0)
        fail_msg("merge after resume failed:\n%s", log_text);
    rows_of(whole, &a, &na);
    rows_of(again, &b, &nb);
    same_rows(a, na, b, nb);
    free(a);
    free(b);

    /* a shard of the run whose manifest says another commit */
    char manifest[5632], text[1 << 16];
    size_t len;
    snprintf(manifest, sizeof manifest, "%s/run.json", s2);
    support_read_file(manifest, text, sizeof text, &len);
    char *c = strstr(text, "\"commit\":");
    assert_non_null(c);
    c = strchr(c + 9, '"');
    assert_non_null(c);
    c[1] = c[1] == 'f' ? '0' : 'f';
    support_write_file(manifest, text, len);
    const char *committed[] = {"merge", s1, s2, "--out", out, NULL};
    assert_int_equal(lib(committed), 2);
    assert_non_null(strstr(log_text, s2));
    assert_non_null(strstr(log_text, "commit"));
    assert_false(exists(out));
}

/* A shard whose process dies (here a wrapper of the command that exits 3
 * for shard 2/2) is named by the driver, which merges nothing; resumed, it
 * finishes and the merge goes through.  The run writes no images and uses
 * one thread: what is checked is the driver's report and the merged rows
 * (test_parallel_merge checks merged images and montage). */
static void test_driver_stopped_shard(void **state)
{
    (void)state;
    char wrapper[4608], out[4608], cache[4608], s2[5120], text[6000];
    snprintf(wrapper, sizeof wrapper, "%s/dies.sh", dir);
    snprintf(out, sizeof out, "%s/stopped", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(s2, sizeof s2, "%s/shards/2", out);
    int n = snprintf(text, sizeof text,
                     "#!/bin/sh\ncase \"$*\" in *\"--shard 2/2 \"*) exit 3 ;; esac\n"
                     "exec '%s' \"$@\"\n",
                     getenv("AABENCH"));
    support_write_file(wrapper, text, (size_t)n);
    assert_int_equal(chmod(wrapper, 0755), 0);
    const char *drive[] = {"scripts/gnu-parallel-run.sh", "--jobs", "2", "--shards", "2",
                           "--aabench", wrapper, "-p", "crow", "-s", "24x24", "-f", "box", "-m",
                           "point", "-m", "area", "-m", "supersample", "--reps", "1", "--no-plots",
                           "--no-images", "--threads", "1", "-q", "--cache", cache, "--out", out,
                           NULL};
    assert_int_equal(run_script(drive), 3);
    assert_non_null(strstr(log_text, "shard(s) 2/2 did not finish"));
    assert_non_null(strstr(log_text, "aabench run --resume"));
    char csv[5120];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    assert_false(exists(csv));
    /* the shard died before its manifest: it is run again, not resumed */
    const char *again[] = {"run", "-p", "crow", "-s", "24x24", "-f", "box", "-m", "point",
                           "-m", "area", "-m", "supersample", "--reps", "1", "--no-plots",
                           "--no-images", "--threads", "1", "-q", "--cache", cache, "--shard",
                           "2/2", "--out", s2, NULL};
    assert_int_equal(lib(again), 0);
    char s1[5120];
    snprintf(s1, sizeof s1, "%s/shards/1", out);
    const char *merge[] = {"merge", s1, s2, "--out", out, "-q", NULL};
    if (lib(merge) != 0)
        fail_msg("merge failed:\n%s", log_text);
    aa_row *rows;
    size_t nr;
    rows_of(out, &rows, &nr);
    assert_int_equal(nr, 3);
    free(rows);
}

/* ---- resumed runs ---- */

/* no images and one thread: the case checks the rows kept and measured and
 * the commands refused (--threads is no part of a run's command) */
#define SMALL "-p", "crow", "-s", "24x16", "-s", "40x40", "-f", "box", "-m", "point", "-m", \
              "supersample", "-m", "jitter:spp=4", "--reps", "1", "--no-plots", "--no-images", \
              "--threads", "1", "-q"

static void test_resume(void **state)
{
    (void)state;
    char whole[4608], part[4608], cache[4608], path[5120];
    snprintf(whole, sizeof whole, "%s/rwhole", dir);
    snprintf(part, sizeof part, "%s/rpart", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    const char *run[] = {"run", SMALL, "--cache", cache, "--out", whole, NULL};
    assert_int_equal(lib(run), 0);
    const char *run2[] = {"run", SMALL, "--cache", cache, "--out", part, NULL};
    assert_int_equal(lib(run2), 0);
    /* an interrupted run: its first 2 cases only, marked */
    aa_row *rows, *full;
    size_t n, nf;
    rows_of(part, &rows, &n);
    assert_int_equal(n, 6);
    for (size_t k = 0; k < 2; k++)
        snprintf(rows[k].host, sizeof rows[k].host, "kept-by-test");
    snprintf(path, sizeof path, "%s/results.csv", part);
    assert_int_equal(aa_rows_write_csv(path, rows, 2), AA_OK);
    free(rows);
    const char *resume[] = {"run", "--resume", part, "--cache", cache, "-q", "--threads", "1",
                            NULL};
    if (lib(resume) != 0)
        fail_msg("resume failed:\n%s", log_text);
    assert_int_equal(lib_kept, 2);
    rows_of(part, &rows, &n);
    rows_of(whole, &full, &nf);
    same_rows(full, nf, rows, n);
    for (size_t k = 0; k < n; k++)
        assert_int_equal(strcmp(rows[k].host, "kept-by-test") == 0, k < 2);
    free(rows);
    free(full);
    /* the same command given again is taken; another is refused */
    const char *same[] = {"run", "--resume", part, SMALL, "--cache", cache, NULL};
    assert_int_equal(aabench(same), 0);
    /* and so are options that do not change the results (threads) */
    const char *threads[] = {"run", "--resume", part, "--threads", "1", "--cache", cache, NULL};
    assert_int_equal(lib(threads), 0);
    const char *changed[] = {"run", "--resume", part, "-p", "crow", "-s", "24x16", NULL};
    assert_int_equal(aabench(changed), 2);
    assert_non_null(strstr(log_text, "command differs"));
    assert_non_null(strstr(log_text, "-s 40x40"));
    /* another commit */
    char text[1 << 16];
    size_t len;
    snprintf(path, sizeof path, "%s/run.json", part);
    support_read_file(path, text, sizeof text, &len);
    char *c = strstr(text, "\"commit\":");
    assert_non_null(c);
    c = strchr(c + 9, '"');
    c[1] = c[1] == 'f' ? '0' : 'f';
    support_write_file(path, text, len);
    assert_int_equal(lib(resume), 2);
    assert_non_null(strstr(log_text, "commit"));
    /* the command says which option it was given */
    assert_int_equal(aabench(resume), 2);
    assert_non_null(strstr(log_text, "--resume"));
    /* bad shards and folders: refused, naming them */
    static const char *const bad[] = {"0/2", "3/2", "1/0", "a/b", "1/2x", "2", "1/5000"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        const char *sharded[] = {"run", SMALL, "--shard", bad[k], "--out", part, NULL};
        assert_int_equal(lib(sharded), 2);
        assert_non_null(strstr(log_text, "--shard"));
    }
    const char *no_out[] = {"merge", whole, NULL};
    assert_int_equal(aabench(no_out), 2);
    const char *not_run[] = {"merge", cache, "--out", part, NULL};
    assert_int_equal(lib(not_run), 2);
    assert_non_null(strstr(log_text, "is not a run's folder"));
    /* not a run folder */
    const char *nothing[] = {"run", "--resume", cache, NULL};
    assert_int_equal(aabench(nothing), 2);
    assert_non_null(strstr(log_text, "not a run folder"));
}

/* ---- pairs a suite leaves out ---- */

/* A suite's groups with the methods given and not the filters: the pairs a
 * method refuses are skipped, without rows; sharded, they are done too,
 * and the merge says it skipped as many as the whole run.  No images, one
 * thread and a small view: the rows and the count of pairs skipped are
 * what is checked, the same at any size. */
static void test_refused_pairs(void **state)
{
    (void)state;
    char whole[4608], merged[4608], cache[4608], shard[3][4608];
    snprintf(whole, sizeof whole, "%s/pwhole", dir);
    snprintf(merged, sizeof merged, "%s/pmerged", dir);
    snprintf(cache, sizeof cache, "%s/cache", dir);
#define PAIRS "--suite", "default", "-p", "crow", "-s", "12x12", "-m", "point", "-m", "area", \
              "-m", "supersample:n=3", "--reps", "1", "--no-plots", "--no-images", "--threads", \
              "1", "-q", "--cache", cache
    const char *run[] = {"run", PAIRS, "--out", whole, NULL};
    if (lib(run) != 0)
        fail_msg("the whole run failed:\n%s", log_text);
    size_t skipped = lib_refused;
    assert_true(skipped > 0);
    for (int k = 0; k < 3; k++) {
        char part[32];
        snprintf(part, sizeof part, "%d/3", k + 1);
        snprintf(shard[k], sizeof shard[k], "%s/pshard%d", dir, k + 1);
        const char *sharded[] = {"run", PAIRS, "--shard", part, "--out", shard[k], NULL};
        if (lib(sharded) != 0)
            fail_msg("shard %s failed:\n%s", part, log_text);
    }
    const char *merge[] = {"merge", shard[2], shard[0], shard[1], "--out", merged, "-q",
                           "--cache", cache, NULL};
    if (lib(merge) != 0)
        fail_msg("merge failed:\n%s", log_text);
    assert_int_equal(lib_refused, skipped);
    aa_row *a, *b;
    size_t na, nb;
    rows_of(whole, &a, &na);
    rows_of(merged, &b, &nb);
    /* rows are numbered in the whole run, refused pairs leaving gaps */
    assert_int_equal(na, nb);
    for (size_t k = 0; k < na; k++) {
        assert_int_equal(a[k].case_index, b[k].case_index);
        assert_string_equal(a[k].method, b[k].method);
        assert_string_equal(a[k].filter, b[k].filter);
        assert_true(a[k].ok && b[k].ok);
        assert_memory_equal(&a[k].m, &b[k].m, sizeof a[k].m);
    }
    free(a);
    free(b);
#undef PAIRS
}

/* ---- the shared cache ---- */

static void test_warm_and_concurrent_cache(void **state)
{
    (void)state;
    char cache[4608];
    snprintf(cache, sizeof cache, "%s/warm", dir);
    /* patterns, sizes, filters and methods given: one cross product, whose
     * views are crow at 12x12 and 16x8 under box, tent:r=1 and cone (small:
     * what is checked is which references are computed and which found) */
    const char *warm[] = {"truth", "--warm", "paper", "-p", "crow", "-s", "12x12", "-s", "16x8",
                          "-f", "box", "-f", "tent:r=1", "-f", "cone", "-m", "point",
                          "--cache", cache, "--threads", "1", NULL};
    if (lib(warm) != 0)
        fail_msg("truth --warm failed:\n%s", log_text);
    assert_true(lib_computed == 6 && lib_cached == 0);
    assert_int_equal(support_count_entries(cache, NULL), 6);
    assert_int_equal(lib(warm), 0);
    assert_true(lib_computed == 0 && lib_cached == 6);
    /* the command says so */
    assert_int_equal(aabench(warm), 0);
    assert_non_null(strstr(log_text, "6 references of suite paper"));
    assert_non_null(strstr(log_text, "0 computed, 6 already there"));

    /* two processes computing the same reference into one cache at once */
    char shared[4608], out[2][5120];
    snprintf(shared, sizeof shared, "%s/shared", dir);
    pid_t pid[2];
    for (int k = 0; k < 2; k++) {
        snprintf(out[k], sizeof out[k], "%s/t%d.txt", dir, k);
        const char *args[] = {"truth", "-p", "crow", "-s", "96x64", "-f", "tent:r=1", "--cache",
                              shared, "-q", "-o", out[k], NULL};
        pid[k] = support_aabench_spawn(args, NULL, NULL, NULL);
    }
    for (int k = 0; k < 2; k++)
        assert_int_equal(support_wait(pid[k]), 0);
    /* one file, no temporary left, read back verified and equal to the
     * reference computed without the cache */
    assert_int_equal(support_count_entries(shared, NULL), 1);
    aa_view view;
    memset(&view, 0, sizeof view);
    assert_int_equal(aa_pattern_parse("crow", &view.pattern), AA_OK);
    assert_int_equal(aa_filter_parse("tent:r=1", &view.filter), AA_OK);
    view.w = 96, view.h = 64;
    aa_image cached, fresh;
    int hit = 0;
    assert_int_equal(aa_reference(&view, shared, 1, &cached, NULL, &hit), AA_OK);
    assert_int_equal(hit, 1);
    assert_int_equal(aa_reference(&view, NULL, 1, &fresh, NULL, NULL), AA_OK);
    assert_true(support_same_image(&cached, &fresh));
    aa_image_free(&cached);
    aa_image_free(&fresh);
}

/* ---- two run folders given (scripts/check-slurm.sh) ---- */

/* $AABENCH_COMPARE_RUNS="WHOLE MERGED": the merged run against the whole
 * one, as test_parallel_merge checks its own. */
static void test_compare_runs(void **state)
{
    (void)state;
    char whole[4608], merged[4608], a_png[5120], b_png[5120];
    if (sscanf(getenv("AABENCH_COMPARE_RUNS"), "%4600s %4600s", whole, merged) != 2)
        fail_msg("AABENCH_COMPARE_RUNS: expected two folders");
    aa_row *a, *b;
    size_t na, nb;
    rows_of(whole, &a, &na);
    rows_of(merged, &b, &nb);
    same_rows(a, na, b, nb);
    free(a);
    free(b);
    snprintf(a_png, sizeof a_png, "%s/montage.png", whole);
    snprintf(b_png, sizeof b_png, "%s/montage.png", merged);
    same_file(a_png, b_png);
    same_images(whole, merged);
}

static int setup(void **state)
{
    if (!getenv("AABENCH") || support_tmpdir(dir, sizeof dir, "shard") != 0)
        return -1;
    *state = dir;
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_partition), cmocka_unit_test(test_parallel_merge),
        cmocka_unit_test(test_driver_stopped_shard),
        cmocka_unit_test(test_resume), cmocka_unit_test(test_refused_pairs),
        cmocka_unit_test(test_warm_and_concurrent_cache)};
    const struct CMUnitTest given[] = {cmocka_unit_test(test_compare_runs)};
    if (getenv("AABENCH_COMPARE_RUNS"))
        return cmocka_run_group_tests(given, setup, support_teardown_dir);
    return cmocka_run_group_tests(tests, setup, support_teardown_dir);
}
