/*
 * test_figures.c: the published figures (figures.c, `aabench figures`).
 * Two cheap figures are made into a temporary folder; their PNG, caption
 * and index.html must exist, and a caption's RMSE must equal one recomputed
 * here from scratch: the same method run on its own (aa_method_run), the
 * reference rendered directly (aa_truth_render, not through the cache) and
 * the RMSE summed in this file.  An unwritable --out must give exit status
 * 3 and write nothing.  The command under test is $AABENCH.
 */
#include "bench.h"

#include <math.h>
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

static char dir[] = "/tmp/aabench-fig-XXXXXX";

static int exists(const char *name)
{
    char path[4096];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > 0;
}

static char *slurp(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* The "rmse:" value of panel `panel` (1-based) in a caption. */
static double caption_rmse(const char *text, int panel)
{
    char key[32];
    snprintf(key, sizeof key, "panel %d:", panel);
    const char *p = strstr(text, key);
    assert_non_null(p);
    p = strstr(p, "rmse: ");
    assert_non_null(p);
    return strtod(p + 6, NULL);
}

/* RMSE of `method` on pattern at w x h (box filter) against the reference,
 * every step done here. */
static double recompute_rmse(const char *pattern, int w, int h, const char *method)
{
    aa_spec ps, ms;
    aa_filter f;
    aa_scene *scene = NULL;
    aa_job job;
    aa_image img, ref;
    aa_counters counters;
    assert_int_equal(aa_pattern_parse(pattern, &ps), 0);
    assert_int_equal(aa_filter_parse("box", &f), 0);
    assert_int_equal(aa_pattern_scene(&ps, &scene), 0);
    assert_int_equal(aa_method_parse(method, &f, &ms), 0);
    assert_int_equal(aa_job_init(&job, scene, w, h, 0, 0, 0, &f, 1, 1), 0);
    assert_int_equal(aa_image_alloc(&img, w, h, 3), 0);
    assert_int_equal(aa_method_run(&ms, &job, 1, &img, &counters, NULL), 0);
    assert_int_equal(aa_image_alloc(&ref, w, h, 3), 0);
    assert_int_equal(aa_truth_render(job.placed, &f, 0, &ref, NULL, NULL), 0);
    double sum = 0;
    size_t n = (size_t)w * h * 3;
    for (size_t k = 0; k < n; k++)
        sum += (img.v[k] - ref.v[k]) * (img.v[k] - ref.v[k]);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_job_free(&job);
    aa_scene_free(scene);
    return sqrt(sum / (double)n);
}

static void test_two_figures(void **state)
{
    (void)state;
    const char *names[] = {"fig-catmull-1", "fig-crow-2.10"};
    for (int k = 0; k < 2; k++) {
        int i = aa_figure_find(names[k]);
        assert_true(i >= 0);
        aa_figure_result r;
        assert_int_equal(aa_figure_make((size_t)i, dir, NULL, 2, &r), 0);
    }
    assert_int_equal(aa_figure_index(dir), 0);
    assert_true(exists("fig-catmull-1.png"));
    assert_true(exists("fig-catmull-1.txt"));
    assert_true(exists("fig-crow-2.10.png"));
    assert_true(exists("fig-crow-2.10.txt"));
    assert_true(exists("index.html"));
    /* the gallery shows both and no other */
    const char *html = slurp("index.html");
    assert_non_null(strstr(html, "src=\"fig-catmull-1.png\""));
    assert_non_null(strstr(html, "src=\"fig-crow-2.10.png\""));
    assert_null(strstr(html, "fig-feibush-4b.png"));
    assert_null(strstr(html, "<script"));
    /* the PNG decodes: the montage holds the 256 x 256 panel and labels */
    char path[4096];
    aa_image im;
    snprintf(path, sizeof path, "%s/fig-crow-2.10.png", dir);
    assert_int_equal(aa_image_read(path, &im), 0);
    assert_true(im.w > 256 && im.h > 256);
    aa_image_free(&im);

    double crow = caption_rmse(slurp("fig-crow-2.10.txt"), 1);
    double want = recompute_rmse("crow", 256, 256, "point");
    assert_true(want > 0.01); /* point sampling aliases this pattern badly */
    assert_true(fabs(crow - want) <= 1e-8 * want);

    /* Catmull's pixel, moved 1/16 pixel right and down so that no sample
     * lies on an edge: point sampling sees only the green in front at the
     * centre, against (0, 1/4, 105/256); area panel 4 matches the reference. */
    const char *cap = slurp("fig-catmull-1.txt");
    double pt = caption_rmse(cap, 1);
    double want_pt = sqrt((0.75 * 0.75 + (105.0 / 256) * (105.0 / 256)) / 3);
    assert_true(fabs(pt - want_pt) <= 1e-8 * want_pt);
    assert_true(caption_rmse(cap, 4) < 1e-12);
    assert_non_null(strstr(cap, "remake: aabench figures --only fig-catmull-1"));
}

/* Run $AABENCH with args; returns the exit status. */
static int run(const char *const *args)
{
    const char *exe = getenv("AABENCH");
    if (!exe)
        skip();
    pid_t pid = fork();
    if (pid == 0) {
        const char *argv[16] = {exe};
        for (int k = 0; args[k] && k < 14; k++)
            argv[k + 1] = args[k];
        freopen("/dev/null", "w", stdout);
        freopen("/dev/null", "w", stderr);
        execv(exe, (char *const *)argv);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

static void test_unwritable_out(void **state)
{
    (void)state;
    char base[] = "/tmp/aabench-figw-XXXXXX", file[1024], out[2048];
    assert_non_null(mkdtemp(base));
    snprintf(file, sizeof file, "%s/plain", base);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fclose(f);
    /* a folder below a plain file cannot be made */
    snprintf(out, sizeof out, "%s/figs", file);
    const char *args[] = {"figures", "-q", "--only", "fig-catmull-1", "--out", out, NULL};
    assert_int_equal(run(args), 3);
    /* nothing was written: the folder holds only the plain file */
    char cmd[4300];
    snprintf(cmd, sizeof cmd, "test \"$(ls -A %s)\" = plain", base);
    assert_int_equal(system(cmd), 0);
    /* an unknown figure is bad input, refused before any work */
    snprintf(out, sizeof out, "%s/new", base);
    const char *bad[] = {"figures", "--only", "fig-nothing", "--out", out, NULL};
    assert_int_equal(run(bad), 2);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "rm -rf %s", base);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_figures),
        cmocka_unit_test(test_unwritable_out),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        failed++;
    return failed;
}
