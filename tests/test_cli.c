/*
 * test_cli.c: the `aabench` command's contract (harness/cli/README.md, "Bad
 * input and exit status"):
 * bad input gets exit status 2 and a message naming the problem and what is
 * accepted, an unwritable output 3, and a refused command writes nothing.
 * The command under test is $AABENCH (set by scripts/run-tests.sh), exec'd
 * by tests/support.c.  The refusals whose message is the library's (the
 * pattern, filter, method and size specs, the image readers) are checked
 * on the library here, each kind also once through the command for its
 * exit status; the command's own options through the command.
 */
#include "bench.h"
#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

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

/* The library refuses with `code` and a message holding needle. */
static void lib_refused(int st, int code, const char *needle, const char *what)
{
    if (st != code || !strstr(aa_last_error(), needle))
        fail_msg("%s: status %d (expected %d), \"%s\" (expected \"%s\")", what, st, code,
                 st ? aa_last_error() : "", needle);
}

/* A pattern spec, parsed and made into a scene of 8 x 8 pixels. */
static int pattern_status(const char *text)
{
    aa_spec spec;
    aa_scene *scene = NULL;
    int st = aa_pattern_parse(text, &spec);
    if (st == AA_OK)
        st = aa_pattern_scene_at(&spec, 8, 8, &scene);
    aa_scene_free(scene);
    return st;
}

/* The specs' refusals come from the library: status AA_EINVAL (exit 2)
 * and a message naming the problem and what is accepted. */
static void test_spec_refusals(void **state)
{
    (void)state;
    static const struct {
        const char *spec, *needle;
    } patterns[] = {
        {"nosuch", "unknown pattern \"nosuch\" (known: crow"},
        {"crow:bogus=1", "no parameter \"bogus\" (accepted: curves, kmax, gap0, gap1)"},
        {"crow:curves=3", "must be even"},
        {"crow:kmax=5", "touch"},
        {"crow:kmax=nan", "kmax=nan: not a number"},
        {"crow:kmax=inf", "kmax=inf: not a number"},
        {"crow:curves=1000000", "out of range (expected an integer from 2 to 65536)"},
        {"star:spokes=5000", "from 1 to 4096"},
        {"fence:period=1e-6", "gives 500000 bars; at most 65536"},
        {"fence:duty=0", "duty=0: out of range"},
        {"dots:n=257", "from 1 to 256"},
        {"catmull:tiles=0", "from 1 to 256"},
        {"slivers:hmin=0.01,hmax=0.001", "hmin=0.01 must not exceed hmax=0.001"},
        {"slivers:count=100000", "from 1 to 65536"},
        {"feibush:stripes=70000", "from 1 to 65536"},
        {"zoneplate:k=0", "k=0: out of range"},
        {"crow:kmax=0.1,kmax=0.2", "kmax given twice"},
    };
    for (size_t k = 0; k < sizeof patterns / sizeof *patterns; k++)
        lib_refused(pattern_status(patterns[k].spec), AA_EINVAL, patterns[k].needle,
                    patterns[k].spec);
    static const struct {
        const char *spec, *needle;
    } filters[] = {
        {"tent:r=-1", "r=-1: out of range"},
        {"sinc", "unknown filter \"sinc\" (known: box, tent, gauss, cone, radial, bspline, "
                 "mitchell, catrom, lanczos)"},
        {"cone:r=0", "r=0: out of range"},
        {"cone:r=nan", "r=nan: not a number"},
        {"cone:r=8.5", "r=8.5: out of range"},
        {"tent:r=inf", "r=inf: not a number"},
    };
    aa_filter f;
    for (size_t k = 0; k < sizeof filters / sizeof *filters; k++)
        lib_refused(aa_filter_parse(filters[k].spec, &f), AA_EINVAL, filters[k].needle,
                    filters[k].spec);
    static const char *const sizes[][2] = {
        {"256", "is not WxH"}, {"axb", "is not WxH"}, {"0x5", "each side must be from 1 to 65536"},
        {"0x0", "each side must be from 1 to 65536"},
        {"99999x99999", "each side must be from 1 to 65536"}};
    int w, h;
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++)
        lib_refused(aa_size_parse(sizes[k][0], &w, &h), AA_EINVAL, sizes[k][1], sizes[k][0]);
    lib_refused(support_parse_method("nosuch", NULL, NULL), AA_EINVAL,
                "unknown method \"nosuch\" (known: point", "method nosuch");
    lib_refused(support_parse_method("point", "tent", NULL), AA_EINVAL, "no prefilter",
                "point under tent");
}

static void test_refusals(void **state)
{
    (void)state;
    const char *o = out_exr;
#define T(code, needle, ...)                                                                   \
    do {                                                                                       \
        const char *a[] = {__VA_ARGS__, NULL};                                                 \
        expect(code, needle, a);                                                               \
    } while (0)
    /* a refusal of each spec's parser, as the command reports it */
    T(2, "unknown pattern \"nosuch\" (known: crow", "truth", "-p", "nosuch", "-s", "8x8", "-o", o);
    T(2, "must be even", "truth", "-p", "crow:curves=3", "-s", "8x8", "-o", o);
    T(2, "is not WxH", "truth", "-p", "crow", "-s", "256", "-o", o);
    T(2, "unknown filter \"sinc\" (known: box, tent, gauss, cone, radial, bspline, mitchell, "
         "catrom, lanczos)",
      "truth", "-p", "crow", "-s", "8x8", "-f", "sinc", "-o", o);
    T(2, "unknown method \"nosuch\" (known: point", "render", "-p", "crow", "-m", "nosuch", "-s",
      "8x8", "-o", o);
    T(2, "no prefilter", "render", "-p", "crow", "-m", "point", "-f", "tent", "-s", "8x8", "-o",
      o);
    /* the command's own */
    T(2, "GB", "truth", "-p", "crow", "-s", "65536x65536", "-o", o);
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
    /* an option of one value given two: the first would be ignored */
    T(2, "-s is given twice (-s 8x8, then -s 16x16): the first would be ignored", "render",
      "-p", "crow", "-m", "point", "-s", "8x8", "-o", o, "-s", "16x16");
    T(2, "-p is given twice (-p crow, then -p star)", "truth", "-p", "crow", "-s", "8x8", "-o",
      o, "--pattern=star");
    T(2, "--threads is given twice (--threads 1, then --threads 2)", "truth", "-p", "crow",
      "-s", "8x8", "-o", o, "--threads", "1", "--threads", "2");
    T(2, "-o is given twice", "export", "-p", "crow", "-s", "8x8", "-o", "a.svg", "-o", "b.svg");
    T(2, "--keep is given twice (--keep 1, then --keep 2)", "prune", "--keep", "1", "--keep",
      "2");
    T(2, "--tolerance is given twice", "diff", "a", "b", "--tolerance", "0.1", "--tolerance",
      "0.2");
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
        aa_image im;
        assert_int_equal(aa_image_alloc(&im, 8, 8, 3), AA_OK);
        assert_int_equal(aa_image_write(full, &im, NULL), AA_OK);
        aa_image_free(&im);
        FILE *f = fopen(full, "rb");
        char head[100];
        assert_int_equal(fread(head, 1, sizeof head, f), sizeof head);
        fclose(f);
        support_write_file(trunc, head, sizeof head);
    }
    /* corrupt and unreadable images: the readers' refusals (AA_EIO, exit
     * 3), one of them through compare */
    const char *const unread[][2] = {
        {shortf, "the file ends before pixel"}, {badnum, "malformed number"},
        {nanf, "malformed number 'nan'"},      {huge, "sides must be in [1, 65536]"},
        {empty, "empty file"},                 {folder, "cannot read"},
        {trunc, "cannot read"},                {pfm, "cannot read"},
        {"/nonexistent-aabench.exr", "cannot read"}};
    for (size_t k = 0; k < sizeof unread / sizeof *unread; k++) {
        aa_image im;
        lib_refused(aa_image_read(unread[k][0], &im), AA_EIO, unread[k][1], unread[k][0]);
    }
    T(3, "the file ends before pixel", "compare", ok, shortf);
    T(3, "cannot open", "compare", ok, "/nonexistent-aabench.txt");
    T(2, "needs two image files", "compare", ok);
    T(2, "is not a number in [1, 4]", "compare", ok, ok, "--encode", "gamma:nan");
    /* run */
    T(2, "unknown pattern \"nosuch\"", "run", "-p", "nosuch", "-q", "--out", dir);
    T(2, "unknown method \"nosuch\"", "run", "-m", "nosuch", "-q", "--out", dir);
    T(2, "unknown suite \"nosuch\"", "run", "--suite", "nosuch", "-q", "--out", dir);
    T(2, "--reps 0 is out of range", "run", "--reps", "0", "-q", "--out", dir);
    T(2, "is not a finite number", "run", "-p", "crow", "-m", "point", "-s", "8x8", "--motion",
      "nan,0", "-q", "--out", dir);
    /* --no-images: the refusal is the same, without loading OpenImageIO first */
    T(3, "is not a folder", "run", "-p", "crow", "-m", "point", "-s", "8x8", "-q", "--no-images",
      "--out", sub);
    /* converge */
    T(2, "is not a whole number", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp",
      "1,4,abc", "--out", dir);
    T(2, "out of range", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp", "0",
      "--out", dir);
    T(2, "no spp or n parameter", "converge", "-p", "crow", "-m", "point", "-s", "8x8", "--spp",
      "1,4,16", "--out", dir);
    T(2, "--phases 0 is out of range", "converge", "-p", "crow", "-m", "jitter", "-s", "8x8",
      "--spp", "1,4,16", "--phases", "0", "--out", dir);
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
    /* a value given again is the same value: nothing ignored, taken */
    const char *truth[] = {"truth", "-p",         "crow",       "-s", "8x4", "-o",
                           out_txt, "--no-cache", "--size=8x4", NULL};
    assert_int_equal(run(truth), 0);
    aa_image im;
    assert_int_equal(aa_image_read_txt(out_txt, &im), AA_OK);
    assert_true(im.w == 8 && im.h == 4 && im.c == 3);
    aa_image_free(&im);
    unlink(out_txt);
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
    /* with no timing option: rendered once, and said so; no timing, no
     * warning about it */
    const char *once[] = {"render", "-p", "crow", "-m", "point", "-s", "16x8", "-o", out_txt,
                          NULL};
    assert_int_equal(run(once), 0);
    if (!strstr(output, "rendered once in ") || strstr(output, "median") ||
        strstr(output, "warning"))
        fail_msg("render without a timing option: %s", output);
    assert_int_equal(access(out_txt, F_OK), 0);
    unlink(out_txt);
    /* --budget asks for the timing: a median over renders */
    const char *budget[] = {"render", "-p", "crow", "-m", "point", "-s", "16x8", "-o", out_txt,
                            "--budget", "0.05", NULL};
    assert_int_equal(run(budget), 0);
    if (!strstr(output, "median ") || !strstr(output, " renders"))
        fail_msg("render --budget: %s", output);
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

/* `run` without -f says which filters it takes: its suite's (the quick
 * suite's are box, tent:r=1 and gauss, harness/bench/README.md) */
static void test_run_filters(void **state)
{
    (void)state;
    char out[300];
    snprintf(out, sizeof out, "%s/run-filters", dir);
    const char *args[] = {"run", "--suite", "quick", "-p", "crow", "-s", "8x8", "-m", "point",
                          "--reps", "1", "-q", "--no-plots", "--no-images", "--no-cache",
                          "--out", out, NULL};
    assert_int_equal(run(args), 0);
    if (!strstr(output, "no -f given: the filters of suite quick, box, tent:r=1, gauss ("))
        fail_msg("run without -f: %s", output);
    /* given, nothing to say */
    const char *given[] = {"run", "--suite", "quick", "-p", "crow", "-s", "8x8", "-m", "point",
                           "-f", "box", "--reps", "1", "-q", "--no-plots", "--no-images",
                           "--no-cache", "--out", out, NULL};
    assert_int_equal(run(given), 0);
    assert_null(strstr(output, "no -f given"));
    assert_int_equal(support_rmtree(out), 0);
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

/* A cache that cannot be written (/proc takes no new folder, even from
 * root) is said once, and the image is made all the same; truth --warm,
 * whose work is to fill it, fails with status 3 and says nothing made. */
static void test_cache_unusable(void **state)
{
    (void)state;
    const char *cache = "/proc/aabench-none/cache";
    const char *warning = "warning: the reference cache /proc/aabench-none/cache cannot be written";
    const char *truth[] = {"truth", "-p", "crow", "-s", "16x8", "-o", out_txt, "--cache", cache,
                           NULL};
    const char *converge[] = {"converge", "-p", "crow", "-m", "jitter", "-s", "8x8", "--spp",
                              "1,4,16", "--threads", "1", "--cache", cache, NULL};
    const char *const *cmds[] = {truth, converge};
    for (size_t k = 0; k < 2; k++) {
        assert_int_equal(run(cmds[k]), 0);
        const char *first = strstr(output, warning);
        if (!first || strstr(first + strlen(warning), "reference cache"))
            fail_msg("aabench %s: expected one warning about the cache, got: %s", cmds[k][0],
                     output);
    }
    aa_image im;
    assert_int_equal(aa_image_read_txt(out_txt, &im), AA_OK);
    aa_image_free(&im);
    assert_int_equal(unlink(out_txt), 0);
    const char *warm[] = {"truth", "--warm", "quick", "-p", "crow", "-s", "8x8", "--cache", cache,
                          NULL};
    expect(3, "--warm: the reference cache /proc/aabench-none/cache cannot be written", warm);
    assert_null(strstr(output, "computed"));
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
             cmocka_unit_test(test_spec_refusals),
             cmocka_unit_test(test_refusals),
             cmocka_unit_test(test_refusals_everywhere),
             cmocka_unit_test(test_success),
             cmocka_unit_test(test_render),
             cmocka_unit_test(test_run_filters),
             cmocka_unit_test(test_cache),
             cmocka_unit_test(test_cache_unusable))
