/*
 * test_faults.c: results stay right when files and inputs go wrong.
 *
 * The reference cache: a file of the cache that is damaged anywhere (a
 * flipped bit in the pixels, the bound, the key or the checksum), cut short,
 * grown, or holding another view's pixels under this view's header is never
 * served: the reference is recomputed, equal to a fresh computation, and a
 * warning names the file.  A FIFO in the cache's place is not opened (a
 * reader would block forever: the test runs under an alarm).
 *
 * The command ($AABENCH): an absurd OMP_NUM_THREADS does not crash it;
 * `converge --out` writes its table once when stdout is a file (a forked
 * child used to flush the parent's buffer a second time); two runs into
 * one folder at once both succeed and leave no temporary file; a result
 * name near NAME_MAX is written; output to a full standard output is an
 * error (exit status 3); outputs are all written or none; a method's NaN
 * or out-of-range value fails the render; SIGTERM exits 130 cleanly.
 */
#include "bench.h"
#include "support.h"

#include <stdarg.h>
#include <setjmp.h>
#include <stddef.h>
#include <cmocka.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char warned[1024];
static int nwarn;

static void capture(const char *message, void *ctx)
{
    (void)ctx;
    snprintf(warned, sizeof warned, "%s", message);
    nwarn++;
}

static void make_view(aa_view *v, const char *pattern, int w, int h)
{
    memset(v, 0, sizeof *v);
    assert_int_equal(aa_pattern_parse(pattern, &v->pattern), AA_OK);
    v->w = w, v->h = h;
    aa_filter_default(&v->filter);
}

/* The one cache file of `dir` into path. */
static long file_size(const char *path)
{
    struct stat sb;
    assert_int_equal(stat(path, &sb), 0);
    return (long)sb.st_size;
}

static void flip_byte(const char *path, long at)
{
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, at, SEEK_SET), 0);
    int c = fgetc(f);
    assert_true(c != EOF);
    assert_int_equal(fseek(f, at, SEEK_SET), 0);
    fputc(c ^ 0x10, f);
    assert_int_equal(fclose(f), 0);
}

static void copy_file(const char *from, const char *to)
{
    char cmd[2400];
    snprintf(cmd, sizeof cmd, "cp '%s' '%s'", from, to);
    assert_int_equal(system(cmd), 0);
}

static int same_image(const aa_image *a, const aa_image *b)
{
    return a->w == b->w && a->h == b->h && a->c == b->c &&
           !memcmp(a->v, b->v, (size_t)a->w * a->h * a->c * sizeof *a->v);
}

/* Read the view's reference through the cache: expect a recomputation with
 * a warning naming the file, and the fresh image. */
static void expect_recomputed(const aa_view *v, const char *dir, const char *path,
                              const aa_image *fresh, const char *what)
{
    aa_image img;
    int hit = -1;
    nwarn = 0, warned[0] = '\0';
    assert_int_equal(aa_reference(v, dir, 1, &img, NULL, &hit), AA_OK);
    if (hit != 0 || nwarn != 1 || !strstr(warned, path))
        fail_msg("%s: hit %d, %d warnings (\"%s\")", what, hit, nwarn, warned);
    assert_true(same_image(&img, fresh));
    aa_image_free(&img);
    /* and the file was stored again, whole: the next read is a hit */
    nwarn = 0;
    assert_int_equal(aa_reference(v, dir, 1, &img, NULL, &hit), AA_OK);
    assert_int_equal(hit, 1);
    assert_int_equal(nwarn, 0);
    assert_true(same_image(&img, fresh));
    aa_image_free(&img);
}

static void test_cache_damage(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", path[1024], save[1100];
    assert_non_null(mkdtemp(dir));
    aa_set_warn(capture, NULL);
    aa_view v;
    make_view(&v, "crow", 24, 16);
    aa_image fresh;
    int hit = -1;
    assert_int_equal(aa_reference(&v, NULL, 1, &fresh, NULL, NULL), AA_OK);
    aa_image first;
    assert_int_equal(aa_reference(&v, dir, 1, &first, NULL, &hit), AA_OK);
    aa_image_free(&first);
    support_cache_file(dir, path, sizeof path);
    snprintf(save, sizeof save, "%s.good", path);
    copy_file(path, save);
    long size = file_size(path);
    size_t pixels = (size_t)24 * 16 * 3 * sizeof(double);
    /* byte offsets: the first key byte (after the 20-byte magic and the
     * 4-byte length), the count of pixels scanned and the bound (just
     * before the pixels), a pixel, the checksum (the last 8 bytes) */
    long at[] = {24, size - 8 - (long)pixels - 16, size - 8 - (long)pixels - 8,
                 size - 8 - (long)pixels / 2, size - 3};
    const char *name[] = {"key", "count scanned", "bound", "pixels", "checksum"};
    for (int k = 0; k < 5; k++) {
        copy_file(save, path);
        flip_byte(path, at[k]);
        expect_recomputed(&v, dir, path, &fresh, name[k]);
    }
    /* cut short, and grown */
    copy_file(save, path);
    assert_int_equal(truncate(path, size - 100), 0);
    expect_recomputed(&v, dir, path, &fresh, "cut short");
    copy_file(save, path);
    assert_int_equal(truncate(path, size + 8), 0);
    expect_recomputed(&v, dir, path, &fresh, "grown");
    aa_image_free(&fresh);
    aa_set_warn(NULL, NULL);
    assert_int_equal(support_rmtree(dir), 0);
}

/* Another view's pixels pasted under this view's header (same size, so
 * every length matches): only the checksum can tell. */
static void test_cache_pasted(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", path_a[1024], path_b[1024];
    assert_non_null(mkdtemp(dir));
    aa_set_warn(capture, NULL);
    aa_view a, b;
    make_view(&a, "crow", 20, 20);
    make_view(&b, "star", 20, 20);
    aa_image fresh, img;
    assert_int_equal(aa_reference(&a, NULL, 1, &fresh, NULL, NULL), AA_OK);
    char sub_a[1100], sub_b[1100];
    snprintf(sub_a, sizeof sub_a, "%s/a", dir);
    snprintf(sub_b, sizeof sub_b, "%s/b", dir);
    assert_int_equal(aa_reference(&a, sub_a, 1, &img, NULL, NULL), AA_OK);
    aa_image_free(&img);
    assert_int_equal(aa_reference(&b, sub_b, 1, &img, NULL, NULL), AA_OK);
    aa_image_free(&img);
    support_cache_file(sub_a, path_a, sizeof path_a);
    support_cache_file(sub_b, path_b, sizeof path_b);
    size_t pixels = (size_t)20 * 20 * 3 * sizeof(double);
    long size_a = file_size(path_a), size_b = file_size(path_b);
    FILE *fb = fopen(path_b, "rb"), *fa = fopen(path_a, "r+b");
    assert_non_null(fb);
    assert_non_null(fa);
    char *buf = malloc(pixels);
    assert_int_equal(fseek(fb, size_b - 8 - (long)pixels, SEEK_SET), 0);
    assert_int_equal(fread(buf, 1, pixels, fb), pixels);
    assert_int_equal(fseek(fa, size_a - 8 - (long)pixels, SEEK_SET), 0);
    assert_int_equal(fwrite(buf, 1, pixels, fa), pixels);
    fclose(fb);
    assert_int_equal(fclose(fa), 0);
    free(buf);
    expect_recomputed(&a, sub_a, path_a, &fresh, "pasted pixels");
    aa_image_free(&fresh);
    aa_set_warn(NULL, NULL);
    assert_int_equal(support_rmtree(dir), 0);
}

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "test_faults: the cache reader blocked on a FIFO\n";
    if (write(2, msg, sizeof msg - 1) < 0) {
    }
    _exit(1);
}

static void test_cache_fifo(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", path[1024];
    assert_non_null(mkdtemp(dir));
    aa_set_warn(capture, NULL);
    aa_view v;
    make_view(&v, "crow", 8, 8);
    aa_image img, fresh;
    assert_int_equal(aa_reference(&v, NULL, 1, &fresh, NULL, NULL), AA_OK);
    assert_int_equal(aa_reference(&v, dir, 1, &img, NULL, NULL), AA_OK);
    aa_image_free(&img);
    support_cache_file(dir, path, sizeof path);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(mkfifo(path, 0644), 0);
    signal(SIGALRM, on_alarm);
    alarm(30);
    expect_recomputed(&v, dir, path, &fresh, "FIFO");
    alarm(0);
    aa_image_free(&fresh);
    aa_set_warn(NULL, NULL);
    assert_int_equal(support_rmtree(dir), 0);
}

/* Run $AABENCH with argv (NULL-terminated, without the program), `env`
 * ("NAME=value" or NULL) added, stdout to `out` (or /dev/null), stderr to
 * /dev/null.  The exit status, or 128 + the signal that ended it. */
static int run_cli(const char *const *argv, const char *env, const char *out)
{
    return support_wait(support_aabench_spawn(argv, env, out, NULL));
}

static void test_absurd_threads(void **state)
{
    (void)state;
    const char *truth[] = {"truth", "-p", "crow", "-s", "8x8", "--no-cache", "-o",
                           "/tmp/aabench-faults-threads.txt", NULL};
    assert_int_equal(run_cli(truth, "OMP_NUM_THREADS=100000", NULL), 0);
    const char *zone[] = {"truth", "-p", "zoneplate", "-s", "8x8", "--no-cache", "-o",
                          "/tmp/aabench-faults-threads.txt", NULL};
    assert_int_equal(run_cli(zone, "OMP_NUM_THREADS=100000", NULL), 0);
    unlink("/tmp/aabench-faults-threads.txt");
}

static void test_converge_once(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", out[1100], plots[1100];
    assert_non_null(mkdtemp(dir));
    snprintf(out, sizeof out, "%s/table.txt", dir);
    snprintf(plots, sizeof plots, "%s/plots", dir);
    const char *argv[] = {"converge", "-p",      "crow",    "-m",     "jitter",
                          "-s",       "16x16",   "--spp",   "4,16,64", "--phases",
                          "2",        "--out",   plots,     "--no-cache", NULL};
    assert_int_equal(run_cli(argv, NULL, out), 0);
    FILE *f = fopen(out, "r");
    assert_non_null(f);
    char line[512];
    int rows = 0, slopes = 0;
    while (fgets(line, sizeof line, f)) {
        rows += line[0] >= '0' && line[0] <= '9';
        slopes += !strncmp(line, "slope", 5);
    }
    fclose(f);
    assert_int_equal(rows, 3);
    assert_int_equal(slopes, 1);
    assert_int_equal(support_rmtree(dir), 0);
}

/* Two runs into one folder at once: each renames only its own temporary
 * files (plots included), so both succeed and nothing temporary is left. */
static void test_two_runs_one_folder(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", cache[1100];
    assert_non_null(mkdtemp(dir));
    snprintf(cache, sizeof cache, "AABENCH_CACHE=%s/cache", dir);
    for (int round = 0; round < 3; round++) {
        const char *argv[] = {"run", "-p", "crow", "-f", "box", "-s", "16x16", "-m", "point",
                              "-m", "area", "--reps", "1", "--no-images", "-q", "--out", dir,
                              NULL};
        pid_t a = support_aabench_spawn(argv, cache, NULL, NULL);
        pid_t b = support_aabench_spawn(argv, cache, NULL, NULL);
        int sa, sb;
        assert_int_equal(support_waitpid(a, &sa, 0), a);
        assert_int_equal(support_waitpid(b, &sb, 0), b);
        assert_true(WIFEXITED(sa) && WEXITSTATUS(sa) == 0);
        assert_true(WIFEXITED(sb) && WEXITSTATUS(sb) == 0);
    }
    char cmd[1400];
    /* temporary names start with a dot */
    snprintf(cmd, sizeof cmd, "test -z \"$(find '%s' -name '.*' ! -name . -print)\"", dir);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "test -s '%s/plots/error_vs_time.png'", dir);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(support_rmtree(dir), 0);
}

/* A result name of 250 characters (NAME_MAX is 255): its temporary name
 * must still fit, for the writers through OpenImageIO and the .txt one. */
static void test_long_name(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", path[3][1100];
    assert_non_null(mkdtemp(dir));
    const char *ext[] = {".png", ".txt", ".exr"};
    for (int k = 0; k < 3; k++) {
        int n = snprintf(path[k], sizeof path[k], "%s/", dir);
        memset(path[k] + n, 'x', 246);
        snprintf(path[k] + n + 246, sizeof path[k] - (size_t)n - 246, "%s", ext[k]);
    }
    aa_image img;
    assert_int_equal(aa_image_alloc(&img, 8, 8, 3), AA_OK);
    for (int k = 0; k < 3; k++)
        if (aa_image_write(path[k], &img, NULL) != AA_OK)
            fail_msg("%s: %s", ext[k], aa_last_error());
    aa_image_free(&img);
    for (int k = 0; k < 3; k++) {
        struct stat sb;
        assert_int_equal(stat(path[k], &sb), 0);
    }
    assert_int_equal(support_rmtree(dir), 0);
}

/* Standard output that cannot be written (/dev/full: ENOSPC) is an error
 * (exit status 3), never a silent success. */
static void test_stdout_full(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", a[1100], b[1100], out[1100], csv[1100];
    assert_non_null(mkdtemp(dir));
    snprintf(a, sizeof a, "%s/a.txt", dir);
    snprintf(b, sizeof b, "%s/b.txt", dir);
    snprintf(out, sizeof out, "%s/run", dir);
    snprintf(csv, sizeof csv, "%s/run/results.csv", dir);
    const char *run[] = {"run", "-p", "crow", "-f", "box", "-s", "8x8", "-m", "point", "--reps",
                         "1", "--no-images", "--no-plots", "-q", "--out", out, NULL};
    /* the two images to compare: the references `truth` writes, written
     * here by the same library (what compare prints is what is tested) */
    const char *pattern[] = {"crow", "star"}, *file[] = {a, b};
    for (int k = 0; k < 2; k++) {
        aa_view v;
        aa_image img;
        make_view(&v, pattern[k], 8, 8);
        assert_int_equal(aa_reference(&v, NULL, 1, &img, NULL, NULL), AA_OK);
        assert_int_equal(aa_image_write(file[k], &img, NULL), AA_OK);
        aa_image_free(&img);
    }
    assert_int_equal(run_cli(run, "AABENCH_CACHE=/tmp/aabench-faults-cache", NULL), 0);
    const char *list[] = {"list", "methods", NULL};
    const char *help[] = {"--help", NULL};
    const char *compare[] = {"compare", a, b, NULL};
    const char *check[] = {"check", "--baseline", csv, NULL};
    const char *const *cmds[] = {list, help, compare, check};
    for (int k = 0; k < 4; k++) {
        /* the same commands succeed with somewhere to write */
        assert_int_equal(run_cli(cmds[k], "AABENCH_CACHE=/tmp/aabench-faults-cache", NULL), 0);
        int st = run_cli(cmds[k], "AABENCH_CACHE=/tmp/aabench-faults-cache", "/dev/full");
        if (st != 3)
            fail_msg("aabench %s > /dev/full exited %d, not 3", cmds[k][0], st);
    }
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s' /tmp/aabench-faults-cache", dir);
    assert_int_equal(system(cmd), 0);
}

static void read_text(const char *path, char *buf, size_t len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
    fclose(f);
}

/* A command that fails after its work leaves every output as it was: the
 * main output is written only once the others have been (truth -o with a
 * --bound that cannot be written: here its format's module is missing). */
static void test_all_or_nothing(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", out[1100], bound[1100], cmd[1400];
    assert_non_null(mkdtemp(dir));
    snprintf(out, sizeof out, "%s/o.txt", dir);
    snprintf(bound, sizeof bound, "%s/b.exr", dir);
    FILE *f = fopen(out, "w");
    assert_non_null(f);
    fputs("previous\n", f);
    assert_int_equal(fclose(f), 0);
    const char *argv[] = {"truth", "-p", "crow", "-s", "8x8", "--no-cache",
                          "-o",    out,  "--bound", bound, NULL};
    assert_int_equal(run_cli(argv, "AABENCH_OIIO=/nonexistent/aabench-oiio.so", NULL), 3);
    char text[64];
    read_text(out, text, sizeof text);
    assert_string_equal(text, "previous\n");
    snprintf(cmd, sizeof cmd, "test -z \"$(find '%s' -name '.*' ! -name . -print)\"", dir);
    assert_int_equal(system(cmd), 0);
    /* a folder that is a file: refused before any work, exit 3 */
    snprintf(bound, sizeof bound, "%s/o.txt/b.txt", dir);
    assert_int_equal(run_cli(argv, NULL, NULL), 3);
    read_text(out, text, sizeof text);
    assert_string_equal(text, "previous\n");
    assert_int_equal(support_rmtree(dir), 0);
}

/* The example plug-in's faulty methods (plugin_faulty.so beside the tests'
 * command): NaN or 1.5 in the image is a failed render (exit 1), with the
 * first bad pixel named, and nothing written. */
static void faulty_plugin(char *path, size_t len)
{
    const char *exe = getenv("AABENCH");
    assert_non_null(exe);
    const char *slash = strrchr(exe, '/');
    assert_non_null(slash);
    snprintf(path, len, "%.*s/tests/plugin_faulty.so", (int)(slash - exe), exe);
}

static void test_bad_values(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", out[1100], plugin[1100], err[1100], cmd[5000];
    assert_non_null(mkdtemp(dir));
    faulty_plugin(plugin, sizeof plugin);
    snprintf(out, sizeof out, "%s/o.png", dir);
    snprintf(err, sizeof err, "%s/err.txt", dir);
    const char *methods[] = {"nanout", "over"};
    for (int k = 0; k < 2; k++) {
        snprintf(cmd, sizeof cmd,
                 "'%s' render --plugin '%s' -m %s -p crow -s 8x8 -o '%s' 2>'%s'; test $? = 1",
                 getenv("AABENCH"), plugin, methods[k], out, err);
        assert_int_equal(system(cmd), 0);
        char text[1024];
        read_text(err, text, sizeof text);
        if (!strstr(text, "pixel (1, 2) channel 1") || !strstr(text, "2 values"))
            fail_msg("%s: %s", methods[k], text);
        assert_int_equal(access(out, F_OK), -1);
    }
    assert_int_equal(support_rmtree(dir), 0);
}

/* SIGTERM during a long reference: exit status 130 and no temporary file. */
static void test_interrupted(void **state)
{
    (void)state;
    char dir[] = "/tmp/aabench-faults-XXXXXX", out[1100], cmd[1400];
    assert_non_null(mkdtemp(dir));
    snprintf(out, sizeof out, "%s/o.txt", dir);
    const char *argv[] = {"truth", "-p", "crow", "-s", "2048x2048", "-f", "gauss", "--no-cache",
                          "--threads", "1", "-o", out, NULL};
    pid_t pid = support_aabench_spawn(argv, NULL, NULL, NULL);
    /* the signal once the command catches it (its SigCgt mask in
     * /proc/PID/status, proc(5)): a busy machine may take longer than any
     * fixed delay to get there; then a little into the reference */
    int caught = 0;
    for (int tries = 0; tries < 600 && !caught; tries++) {
        char path[64], line[256];
        snprintf(path, sizeof path, "/proc/%d/status", (int)pid);
        FILE *f = fopen(path, "r");
        while (f && fgets(line, sizeof line, f))
            if (!strncmp(line, "SigCgt:", 7))
                caught = (strtoull(line + 7, NULL, 16) >> (SIGTERM - 1)) & 1;
        if (f)
            fclose(f);
        if (!caught)
            usleep(50 * 1000);
    }
    assert_true(caught);
    usleep(200 * 1000);
    assert_int_equal(kill(pid, SIGTERM), 0);
    int status;
    assert_int_equal(support_waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 130);
    assert_int_equal(access(out, F_OK), -1);
    snprintf(cmd, sizeof cmd, "test -z \"$(find '%s' -name '.*' ! -name . -print)\"", dir);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(support_rmtree(dir), 0);
}

/* The plug-in kit: `--plugin NAME.so` without a slash is the file in the
 * current folder (not a library for the system's search path), and a
 * baseline naming a plug-in's method without --plugin says to load it. */
static void test_plugin_by_name(void **state)
{
    (void)state;
    const char *plugin = getenv("AABENCH_PLUGIN");
    assert_non_null(plugin);
    char dir[] = "/tmp/aabench-faults-XXXXXX", cmd[5000], csv[1100], out[1100];
    assert_non_null(mkdtemp(dir));
    snprintf(cmd, sizeof cmd,
             "cp '%s' '%s/mine.so' && cd '%s' && '%s' list methods --plugin mine.so | "
             "grep -q '^centre4'",
             plugin, dir, dir, getenv("AABENCH"));
    assert_int_equal(system(cmd), 0);
    /* a baseline with the plug-in's method, checked without --plugin */
    snprintf(out, sizeof out, "%s/run", dir);
    snprintf(csv, sizeof csv, "%s/run/results.csv", dir);
    const char *run[] = {"run", "--plugin", plugin, "-p", "crow", "-f", "box", "-s", "8x8",
                         "-m", "centre4", "--reps", "1", "--no-images", "--no-plots", "-q",
                         "--out", out, NULL};
    assert_int_equal(run_cli(run, "AABENCH_CACHE=/tmp/aabench-faults-cache", NULL), 0);
    snprintf(cmd, sizeof cmd,
             "AABENCH_CACHE=/tmp/aabench-faults-cache '%s' check --baseline '%s' > '%s/check.txt';"
             " test $? = 1 && grep -q 'no method \"centre4\" is built in or loaded.*--plugin' "
             "'%s/check.txt'",
             getenv("AABENCH"), csv, dir, dir);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "rm -rf '%s' /tmp/aabench-faults-cache", dir);
    assert_int_equal(system(cmd), 0);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_cache_damage),
             cmocka_unit_test(test_cache_pasted),
             cmocka_unit_test(test_cache_fifo),
             cmocka_unit_test(test_absurd_threads),
             cmocka_unit_test(test_converge_once),
             cmocka_unit_test(test_two_runs_one_folder),
             cmocka_unit_test(test_long_name),
             cmocka_unit_test(test_stdout_full),
             cmocka_unit_test(test_all_or_nothing),
             cmocka_unit_test(test_bad_values),
             cmocka_unit_test(test_interrupted),
             cmocka_unit_test(test_plugin_by_name))
