/*
 * test_cli.c: the `aabench` command's contract (harness/README.md, "Command
 * line"):
 * bad input gets exit status 2 and a message naming the problem and what is
 * accepted, an unwritable output 3, and a refused command writes nothing.
 * The command under test is $AABENCH (set by the Makefile), run by
 * tests/support.c (a fork of its command server, or exec; under ASan a
 * call of cli_main() in this process); one test checks that these give
 * the same statuses, output and files as an exec, one runs the command
 * line in-process (cli_main, in a child of this process).
 */
#include "bench.h"
#include "support.h"

#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "cli.h"

static char dir[200];
static char output[8192];

/* Run aabench with args (NULL-terminated); capture stdout+stderr. */
static int run(const char *const *args)
{
    return support_aabench(args, output, sizeof output);
}

/* The folder is empty: nothing was written, not even a temporary file. */
static void folder_clean(void)
{
    if (support_count_entries(dir, NULL) != 0)
        fail_msg("files were left in %s", dir);
}

static void expect(int code, const char *needle, const char *const *args)
{
    int got = run(args);
    if (got != code || !strstr(output, needle))
        fail_msg("aabench %s %s ...: exit %d (expected %d), output \"%s\" (expected \"%s\")",
                 args[0], args[1] ? args[1] : "", got, code, output, needle);
    folder_clean();
}

static char out_exr[256], out_txt[256];

static void test_refusals(void **state)
{
    (void)state;
    const char *o = out_exr;
#define T(code, needle, ...)                                                                   \
    do {                                                                                       \
        const char *a[] = {__VA_ARGS__, NULL};                                                 \
        expect(code, needle, a);                                                               \
    } while (0)
    T(2, "unknown pattern \"nosuch\" (known: crow", "truth", "-p", "nosuch", "-s", "8x8", "-o", o);
    T(2, "no parameter \"bogus\" (accepted: curves, kmax, gap0, gap1)", "truth", "-p",
      "crow:bogus=1", "-s", "8x8", "-o", o);
    T(2, "must be even", "truth", "-p", "crow:curves=3", "-s", "8x8", "-o", o);
    T(2, "touch", "truth", "-p", "crow:kmax=5", "-s", "8x8", "-o", o);
    T(2, "kmax=nan: not a number", "truth", "-p", "crow:kmax=nan", "-s", "8x8", "-o", o);
    T(2, "kmax=inf: not a number", "truth", "-p", "crow:kmax=inf", "-s", "8x8", "-o", o);
    T(2, "out of range (expected an integer from 2 to 65536)", "truth", "-p",
      "crow:curves=1000000", "-s", "8x8", "-o", o);
    T(2, "from 1 to 4096", "truth", "-p", "star:spokes=5000", "-s", "8x8", "-o", o);
    T(2, "gives 500000 bars; at most 65536", "truth", "-p", "fence:period=1e-6", "-s", "8x8",
      "-o", o);
    T(2, "duty=0: out of range", "truth", "-p", "fence:duty=0", "-s", "8x8", "-o", o);
    T(2, "from 1 to 256", "truth", "-p", "dots:n=257", "-s", "8x8", "-o", o);
    T(2, "from 1 to 256", "truth", "-p", "catmull:tiles=0", "-s", "8x8", "-o", o);
    T(2, "hmin=0.01 must not exceed hmax=0.001", "truth", "-p", "slivers:hmin=0.01,hmax=0.001",
      "-s", "8x8", "-o", o);
    T(2, "from 1 to 65536", "truth", "-p", "slivers:count=100000", "-s", "8x8", "-o", o);
    T(2, "from 1 to 65536", "truth", "-p", "feibush:stripes=70000", "-s", "8x8", "-o", o);
    T(2, "is not WxH", "truth", "-p", "crow", "-s", "256", "-o", o);
    T(2, "is not WxH", "truth", "-p", "crow", "-s", "axb", "-o", o);
    T(2, "each side must be from 1 to 65536", "truth", "-p", "crow", "-s", "0x5", "-o", o);
    T(2, "GB", "truth", "-p", "crow", "-s", "65536x65536", "-o", o);
    T(2, "r=-1: out of range", "truth", "-p", "crow", "-s", "8x8", "-f", "tent:r=-1", "-o", o);
    T(2, "unknown filter \"lanczos\" (known: box, tent, gauss, cone)", "truth", "-p",
      "crow", "-s", "8x8", "-f", "lanczos", "-o", o);
    T(2, "r=0: out of range", "truth", "-p", "crow", "-s", "8x8", "-f", "cone:r=0", "-o", o);
    T(2, "r=nan: not a number", "truth", "-p", "crow", "-s", "8x8", "-f", "cone:r=nan", "-o",
      o);
    T(2, "r=8.5: out of range", "truth", "-p", "crow", "-s", "8x8", "-f", "cone:r=8.5", "-o",
      o);
    T(2, "unknown image type", "truth", "-p", "crow", "-s", "8x8", "-o", "x.bmp");
    T(2, "are required", "truth", "-p", "crow", "-s", "8x8");
    T(2, "unknown option", "truth", "--frobnicate", "-p", "crow", "-s", "8x8", "-o", o);
    T(2, "needs a value", "truth", "-p", "crow", "-s", "8x8", "-o");
    T(2, "--threads 0 is out of range", "truth", "-p", "crow", "-s", "8x8", "-o", o,
      "--threads", "0");
    T(2, "--time \"nan\" is not a finite number", "truth", "-p", "crow", "-s", "8x8", "-o", o,
      "--time", "nan");
    T(2, "not two numbers", "truth", "-p", "crow", "-s", "8x8", "-o", o, "--motion", "1");
    T(3, "does not exist", "truth", "-p", "crow", "-s", "8x8", "-o",
      "/nonexistent-aabench/x.exr");
    T(2, "unknown method \"nosuch\" (known: point", "render", "-p", "crow", "-m", "nosuch", "-s",
      "8x8", "-o", o);
    T(2, "no prefilter", "render", "-p", "crow", "-m", "point", "-f", "tent", "-s", "8x8", "-o",
      o);
    T(2, "--reps 0 is out of range", "render", "-p", "crow", "-m", "point", "-s", "8x8", "-o",
      o, "--reps", "0");
    T(2, "--seed \"-1\" is not a whole number", "render", "-p", "crow", "-m", "point", "-s",
      "8x8", "-o", o, "--seed", "-1");
    T(2, "must end in .json", "render", "-p", "crow", "-m", "point", "-s", "8x8", "-o", o,
      "--stats", "x.txt");
    T(2, "are required", "render", "-p", "crow", "-s", "8x8", "-o", o);
    T(3, "plug-in /nonexistent/p.so", "render", "--plugin", "/nonexistent/p.so", "-p", "crow",
      "-m", "point", "-s", "8x8", "-o", o);
    T(2, "area renders scenes of paths only, and pattern zoneplate is a procedural field",
      "render", "-p", "zoneplate", "-m", "area", "-s", "8x8", "-o", o);
    T(2, "k=0: out of range", "truth", "-p", "zoneplate:k=0", "-s", "8x8", "-o", o);
    T(2, "unknown command", "frobnicate");
    T(2, "unknown list", "list", "methods-and-more");
#undef T
}

#define T(code, needle, ...)                                                                   \
    do {                                                                                       \
        const char *a[] = {__VA_ARGS__, NULL};                                                 \
        expect(code, needle, a);                                                               \
    } while (0)

/* Bad input to every other command: exit 2 for bad input, 3 for files that
 * cannot be read or written, a message, and nothing written. */
static void test_refusals_everywhere(void **state)
{
    (void)state;
    char in[256];
    assert_int_equal(support_tmpdir(in, sizeof in, "cli-in"), 0);
    char ok[300], trunc[300], shortf[300], badnum[300], nanf[300], huge[300], empty[300],
        folder[300], pfm[300], csv[300], under[300], sub[300], o[300];
#define PATH(v, name) snprintf(v, sizeof v, "%s/" name, in)
    PATH(ok, "ok.txt"), PATH(trunc, "trunc.exr"), PATH(shortf, "short.txt");
    PATH(badnum, "badnum.txt"), PATH(nanf, "nan.txt"), PATH(huge, "huge.txt");
    PATH(empty, "empty.txt"), PATH(folder, "d.exr"), PATH(pfm, "h.pfm"), PATH(csv, "bad.csv");
    PATH(under, "ok.txt/x.exr"), PATH(sub, "ok.txt/sub");
#undef PATH
    snprintf(o, sizeof o, "%s/x.exr", dir);
    static const char good[] = "# aabench 2 1 3\n0 0 0.5 0.25 1\n1 0 0 0 0.125\n";
    support_write_file(ok, good, sizeof good - 1);
    support_write_file(shortf, "# aabench 2 2 1\n0 0 1\n", 22);
    support_write_file(badnum, "# aabench 2 1 3\n0 0 0.5 x 1\n1 0 0 0 0.125\n", 41);
    support_write_file(nanf, "# aabench 1 1 1\n0 0 nan\n", 24);
    support_write_file(huge, "# aabench 99999999 99999999 3\n", 30);
    support_write_file(empty, "", 0);
    support_write_file(pfm, "Pf\n2 1\n-1.0\n\0\0\0", 15);
    support_write_file(csv, "a,b\n1\n", 6);
    assert_int_equal(mkdir(folder, 0755), 0);
    {
        /* a real .exr cut short */
        char full[300];
        snprintf(full, sizeof full, "%s/full.exr", in);
        const char *a[] = {"truth", "-p", "crow", "-s", "8x8", "-o", full, "--no-cache", NULL};
        assert_int_equal(run(a), 0);
        FILE *f = fopen(full, "rb");
        char head[100];
        assert_int_equal(fread(head, 1, sizeof head, f), sizeof head);
        fclose(f);
        support_write_file(trunc, head, sizeof head);
    }
    /* compare: corrupt and unreadable images */
    T(3, "the file ends before pixel", "compare", ok, shortf);
    T(3, "malformed number", "compare", ok, badnum);
    T(3, "malformed number 'nan'", "compare", ok, nanf);
    T(3, "sides must be in [1, 65536]", "compare", ok, huge);
    T(3, "empty file", "compare", ok, empty);
    T(3, "cannot read", "compare", ok, folder);
    T(3, "cannot read", "compare", ok, trunc);
    T(3, "cannot read", "compare", ok, pfm);
    T(3, "cannot read", "compare", ok, "/nonexistent-aabench.exr");
    T(2, "needs two image files", "compare", ok);
    T(2, "is not a number in [1, 4]", "compare", ok, ok, "--encode", "gamma:nan");
    /* run */
    T(2, "unknown pattern \"nosuch\"", "run", "-p", "nosuch", "-q", "--out", dir);
    T(2, "unknown method \"nosuch\"", "run", "-m", "nosuch", "-q", "--out", dir);
    T(2, "each side must be from 1 to 65536", "run", "-s", "0x0", "-q", "--out", dir);
    T(2, "unknown suite \"nosuch\"", "run", "--suite", "nosuch", "-q", "--out", dir);
    T(2, "--reps 0 is out of range", "run", "--reps", "0", "-q", "--out", dir);
    T(2, "is not a finite number", "run", "-p", "crow", "-m", "point", "-s", "8x8", "--motion",
      "nan,0", "-q", "--out", dir);
    T(2, "r=inf: not a number", "run", "-p", "crow", "-m", "point", "-s", "8x8", "-f",
      "tent:r=inf", "-q", "--out", dir);
    T(2, "kmax given twice", "run", "-p", "crow:kmax=0.1,kmax=0.2", "-q", "--out", dir);
    T(3, "is not a folder", "run", "-p", "crow", "-m", "point", "-s", "8x8", "-q", "--out", sub);
    /* converge */
    T(2, "is not a whole number", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp",
      "1,4,abc", "--out", dir);
    T(2, "out of range", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp", "0",
      "--out", dir);
    T(2, "no spp or n parameter", "converge", "-p", "crow", "-m", "point", "-s", "8x8", "--spp",
      "1,4,16", "--out", dir);
    T(2, "--phases 0 is out of range", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8",
      "--spp", "1,4,16", "--phases", "0", "--out", dir);
    T(2, "each side must be from 1 to 65536", "converge", "-p", "crow", "-m", "jitter", "-s",
      "99999x99999", "--spp", "1,4,16", "--out", dir);
    /* converge measures before it draws into --out: one thread (the
     * default, every core, spends more in OpenMP's waits than in the
     * measuring) */
    T(3, "is not a folder", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp",
      "1,4,16", "--threads", "1", "--out", sub);
    /* check */
    T(3, "cannot open", "check", "--baseline", "/nonexistent-aabench.csv");
    T(3, "no CSV header", "check", "--baseline", empty);
    T(3, "no CSV header", "check", "--baseline", csv);
    T(2, "--tolerance -1 is out of range", "check", "--tolerance", "-1");
    /* stress and list */
    T(2, "--only 0 is out of range", "stress", "--only", "0", "--out", dir);
    T(2, "--only 99 is out of range", "stress", "--only", "99", "--out", dir);
    T(2, "--threads 0 is out of range", "stress", "--threads", "0", "--out", dir);
    T(3, "is not a folder", "stress", "--only", "1", "--out", sub);
    T(2, "unknown list \"nosuch\"", "list", "nosuch");
    /* outputs that cannot be written */
    T(3, "is a folder, not a file", "truth", "-p", "crow", "-s", "8x8", "-o", folder);
    T(3, "is a file, not a folder", "render", "-p", "crow", "-m", "point", "-s", "8x8", "-o", under);
    (void)o;
    assert_int_equal(support_rmtree(in), 0);
}
#undef T

static void test_success(void **state)
{
    (void)state;
    const char *list[] = {"list", NULL};
    assert_int_equal(run(list), 0);
    assert_non_null(strstr(output, "crow\t"));
    assert_non_null(strstr(output, "tent\t"));
    const char *patterns[] = {"list", "patterns", NULL};
    assert_int_equal(run(patterns), 0);
    static const char *names[] = {"crow\t", "catmull\t", "slivers\t", "star\t",
                                  "feibush\t", "fence\t", "dots\t"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strstr(output, names[k]))
            fail_msg("aabench list patterns: no %s in \"%s\"", names[k], output);
    const char *help[] = {"truth", "--help", NULL};
    assert_int_equal(run(help), 0);
    assert_non_null(strstr(output, "usage: aabench truth"));
    const char *truth[] = {"truth", "-p", "crow", "-s", "8x4", "-o", out_txt, "--no-cache", NULL};
    assert_int_equal(run(truth), 0);
    aa_image im;
    assert_int_equal(aa_image_read_txt(out_txt, &im), AA_OK);
    assert_true(im.w == 8 && im.h == 4 && im.c == 3);
    aa_image_free(&im);
    unlink(out_txt);
}

/* The command line without exec: cli_main() in a forked child of this
 * process, its standard output into a file.  The child must not count on
 * OpenMP state from here (fork copies no threads of libgomp's pool); this
 * process runs no parallel region; the other tests start the command as
 * every test does (tests/support.h). */
static void test_cli_main(void **state)
{
    (void)state;
    char log[4096];
    snprintf(log, sizeof log, "%s/log", dir);
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0 || dup2(fd, 1) < 0)
            _exit(126);
        close(fd);
        char a0[] = "aabench", a1[] = "list", a2[] = "patterns";
        char *argv[] = {a0, a1, a2, NULL};
        int code = cli_main(3, argv);
        fflush(NULL);
        _exit(code);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    FILE *f = fopen(log, "r");
    assert_non_null(f);
    size_t n = fread(output, 1, sizeof output - 1, f);
    output[n] = '\0';
    fclose(f);
    if (!strstr(output, "crow\t") || !strstr(output, "zoneplate\t"))
        fail_msg("cli_main list patterns: \"%s\"", output);
    assert_int_equal(unlink(log), 0);
    folder_clean();
}

/* A start that is not an exec (a fork of the command server, or under ASan
 * a call of cli_main() in this process) and an exec of the binary give the
 * same exit status, output and files: the success of a listing and of
 * writing images (PNG and EXR, through the image module, which the server
 * loads before its first image start), a warning beside the output, and
 * refusals. */
static void test_start_same_as_exec(void **state)
{
    (void)state;
    const char *kind = support_start_kind();
    if (kind == NULL) {
        print_message("skipped: every start is an exec ($AABENCH is not the command built "
                      "beside this test, or AABENCH_TEST_EXEC=1)\n");
        skip();
    }
    print_message("%s against an exec\n", kind);
    char png[2][300], exr[2][300], cache[300], entry[600];
    static char said[2][8192];
    for (int how = 0; how < 2; how++) {
        snprintf(png[how], sizeof png[how], "%s/same-%d.png", dir, how);
        snprintf(exr[how], sizeof exr[how], "%s/same-%d.exr", dir, how);
    }
    /* a reference cache whose entry for crow 12x8 is a folder: each truth
     * of it warns (and recomputes) */
    snprintf(cache, sizeof cache, "%s/cache", dir);
    const char *fill[] = {"truth", "-p", "crow", "-s", "12x8", "-q", "--cache", cache,
                          "-o", png[0], NULL};
    assert_int_equal(run(fill), 0);
    support_cache_file(cache, entry, sizeof entry);
    assert_int_equal(unlink(entry), 0);
    assert_int_equal(mkdir(entry, 0755), 0);
    for (int c = 0; c < 6; c++) {
        int status[2];
        for (int how = 0; how < 2; how++) {
            /* a start-up variable changed: support.c execs */
            if (how == 1)
                assert_int_equal(setenv("AABENCH_TEST_EXEC", "1", 1), 0);
            const char *list[] = {"list", "patterns", NULL};
            const char *truth_png[] = {"truth", "-p", "crow", "-s", "12x8", "--no-cache", "-q",
                                       "-o", png[how], NULL};
            const char *truth_exr[] = {"truth", "-p", "feibush", "-s", "12x8", "-f", "gauss",
                                       "--no-cache", "-q", "-o", exr[how], NULL};
            const char *bad_size[] = {"render", "-p", "crow", "-m", "point", "-s", "12xx8",
                                      "-o", png[how], NULL};
            const char *missing[] = {"compare", "/nonexistent/a.png", "/nonexistent/b.png", NULL};
            const char *warned[] = {"truth", "-p", "crow", "-s", "12x8", "-q", "--cache", cache,
                                    "-o", png[how], NULL};
            const char *const *args[] = {list, truth_png, truth_exr, bad_size, missing, warned};
            status[how] = support_aabench(args[c], said[how], sizeof said[how]);
            if (how == 1)
                assert_int_equal(unsetenv("AABENCH_TEST_EXEC"), 0);
        }
        if (status[0] != status[1] || strcmp(said[0], said[1]) != 0)
            fail_msg("case %d: %s gave status %d and \"%s\", an exec %d and \"%s\"", c, kind,
                     status[0], said[0], status[1], said[1]);
        if (c == 5 && !strstr(said[0], "is not a regular file"))
            fail_msg("no warning from a cache entry that is a folder: \"%s\"", said[0]);
    }
    assert_int_equal(rmdir(entry), 0);
    assert_int_equal(rmdir(cache), 0);
    /* the PNGs to the byte; the EXRs hold the time they were written
     * (capDate): their pixels */
    size_t n0, n1;
    static char a[1 << 16], b[1 << 16];
    assert_non_null(support_read_file(png[0], a, sizeof a, &n0));
    assert_non_null(support_read_file(png[1], b, sizeof b, &n1));
    assert_true(n0 > 0 && n0 == n1);
    assert_memory_equal(a, b, n0);
    aa_image im[2];
    for (int how = 0; how < 2; how++)
        assert_int_equal(aa_image_read(exr[how], &im[how]), AA_OK);
    assert_true(support_same_image(&im[0], &im[1]));
    for (int how = 0; how < 2; how++) {
        aa_image_free(&im[how]);
        assert_int_equal(unlink(png[how]), 0);
        assert_int_equal(unlink(exr[how]), 0);
    }
    folder_clean();
}

static void test_render(void **state)
{
    (void)state;
    char stats[256];
    snprintf(stats, sizeof stats, "%s/stats.json", dir);
    const char *render[] = {"render", "-p", "crow", "-m", "point", "-s", "16x8", "-o", out_txt,
                            "--stats", stats, "--reps", "3", "--threads", "1", NULL};
    assert_int_equal(run(render), 0);
    FILE *f = fopen(stats, "r");
    assert_non_null(f);
    char json[4096];
    size_t n = fread(json, 1, sizeof json - 1, f);
    json[n] = '\0';
    fclose(f);
    const char *keys[] = {"\"render_seconds\": ", "\"samples\": 128", "\"pixels\": 128",
                          "\"expensive_pixels\": 0", "\"reps\": 3", "\"method\": \"point\""};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
        if (!strstr(json, keys[k]))
            fail_msg("stats lack %s: %s", keys[k], json);
    unlink(stats);
    unlink(out_txt);
    /* a plug-in's method through the command line */
    const char *plugin = getenv("AABENCH_PLUGIN");
    const char *list[] = {"list", "methods", "--plugin", plugin, NULL};
    assert_int_equal(run(list), 0);
    assert_non_null(strstr(output, "centre4\t"));
    const char *prender[] = {"render", "--plugin", plugin, "-p", "crow", "-m", "centre4", "-s",
                             "16x8", "-o", out_txt, NULL};
    assert_int_equal(run(prender), 0);
    assert_int_equal(access(out_txt, F_OK), 0);
    unlink(out_txt);
}

static void test_cache(void **state)
{
    (void)state;
    char cache[256];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    const char *truth[] = {"truth", "-p", "crow", "-s", "16x8", "-f", "tent:r=0.5",
                           "-o", out_txt, "--cache", cache, NULL};
    assert_int_equal(run(truth), 0);
    assert_null(strstr(output, "from the cache"));
    aa_image a, b;
    assert_int_equal(aa_image_read_txt(out_txt, &a), AA_OK);
    assert_int_equal(run(truth), 0);
    assert_non_null(strstr(output, "from the cache"));
    assert_int_equal(aa_image_read_txt(out_txt, &b), AA_OK);
    assert_memory_equal(a.v, b.v, sizeof(double) * 16 * 8 * 3);
    /* a different filter parameter is a different image: not from the cache */
    const char *other[] = {"truth", "-p", "crow", "-s", "16x8", "-f", "tent:r=0.75",
                           "-o", out_txt, "--cache", cache, NULL};
    assert_int_equal(run(other), 0);
    assert_null(strstr(output, "from the cache"));
    aa_image_free(&a);
    aa_image_free(&b);
    assert_int_equal(support_rmtree(cache), 0);
    assert_int_equal(unlink(out_txt), 0);
}

static int setup(void **state)
{
    if (!getenv("AABENCH") || !getenv("AABENCH_PLUGIN") ||
        support_tmpdir(dir, sizeof dir, "cli") != 0)
        return -1;
    snprintf(out_exr, sizeof out_exr, "%s/out.exr", dir);
    snprintf(out_txt, sizeof out_txt, "%s/out.txt", dir);
    *state = dir; /* removed by support_teardown_dir */
    return 0;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test(test_refusals),
             cmocka_unit_test(test_refusals_everywhere),
             cmocka_unit_test(test_success),
             cmocka_unit_test(test_cli_main),
             cmocka_unit_test(test_start_same_as_exec),
             cmocka_unit_test(test_render),
             cmocka_unit_test(test_cache))
