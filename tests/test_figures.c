/*
 * test_figures.c: the published figures (figures.c, `aabench figures`).
 * Two cheap figures are made into a temporary folder; their PNG, caption
 * and index.html must exist, and a caption's RMSE must equal one recomputed
 * here from scratch: the same method run on its own (aa_method_run), the
 * reference rendered directly (aa_truth_render, not through the cache) and
 * the RMSE summed by the tests' own code (tests/support.c).  An unwritable
 * --out must give exit status 3 and write nothing.  Manson and Schaefer's
 * filters figure: every panel exact under its own filter, and the cubic
 * B-spline smoother than the box (test_manson_filters).  The command under test
 * is $AABENCH.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"

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

static char dir[256];

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
    static char buf[65536];
    return support_read_file(path, buf, sizeof buf, NULL);
}

/* The "rmse:" value of panel `panel` (1-based) in a caption. */
static double caption_rmse(const char *text, int panel)
{
    return strtod(support_caption_field(text, panel, "rmse: "), NULL);
}

/* RMSE of `method` on pattern at w x h (box filter) against the reference,
 * every step done here. */
static double recompute_rmse(const char *pattern, int w, int h, const char *method)
{
    aa_scene *scene = scenes_pattern(pattern);
    aa_image img, ref;
    aa_counters counters;
    support_render(method, scene, "box", w, h, 1, &img, &counters);
    support_reference(scene, &(support_view){.w = w, .h = h, .filter = "box"}, &ref, NULL, NULL);
    double e = support_rmse(&img, &ref);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(scene);
    return e;
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

    /* Catmull's pixel as he draws it, (0, 1/4, 1/2): the 2 x 2 grid's
     * samples, at 1/4 and 3/4 on each axis, miss every edge and see green,
     * black, blue, blue, his split exactly; so does area (panel 4); 16
     * independent random samples cannot hit 1/4 and 1/2 both unless their
     * counts fall so (and with this seed they do not). */
    const char *cap = slurp("fig-catmull-1.txt");
    assert_true(caption_rmse(cap, 1) < 1e-12);
    assert_true(caption_rmse(cap, 4) < 1e-12);
    assert_true(caption_rmse(cap, 3) > 1e-3);
    assert_non_null(strstr(cap, "remake: aabench figures --only fig-catmull-1"));
}

/* Manson and Schaefer's filters figure: `analytic` under the box, the tent,
 * the cubic B-spline and Mitchell-Netravali, each panel's RMSE against
 * the exact reference under its own filter (the harness's truth path, an
 * independent quadrature) at rounding, and the smoothing the filters'
 * responses predict: the B-spline, whose response falls as sinc^4, leaves
 * less power near the Nyquist limit (beat_energy) than the box (sinc). */
static void test_manson_filters(void **state)
{
    (void)state;
    int i = aa_figure_find("fig-manson-filters");
    assert_true(i >= 0);
    aa_figure_result r;
    assert_int_equal(aa_figure_make((size_t)i, dir, NULL, 2, &r), 0);
    const char *cap = slurp("fig-manson-filters.txt");
    static const char *const filter[] = {"box", "tent:r=1", "bspline:order=3", "mitchell"};
    for (int p = 1; p <= 4; p++) {
        assert_non_null(strstr(support_caption_field(cap, p, "filter: "), filter[p - 1]));
        assert_true(caption_rmse(cap, p) < 1e-12);
    }
    double box = strtod(support_caption_field(cap, 1, "beat_energy: "), NULL);
    double bspline = strtod(support_caption_field(cap, 3, "beat_energy: "), NULL);
    print_message("beat energy: box %.3g, bspline:order=3 %.3g\n", box, bspline);
    assert_true(bspline > 0.0 && bspline < 0.5 * box);
}

/* Run $AABENCH with args; returns the exit status. */
static int run(const char *const *args)
{
    return support_aabench(args, NULL, 0);
}

static void test_unwritable_out(void **state)
{
    (void)state;
    char base[256], file[1024], out[2048];
    assert_int_equal(support_tmpdir(base, sizeof base, "figw"), 0);
    snprintf(file, sizeof file, "%s/plain", base);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fclose(f);
    /* a folder below a plain file cannot be made */
    snprintf(out, sizeof out, "%s/figs", file);
    const char *args[] = {"figures", "-q", "--only", "fig-catmull-1", "--out", out, NULL};
    assert_int_equal(run(args), 3);
    /* nothing was written: the folder holds only the plain file */
    assert_int_equal(support_count_entries(base, NULL), 1);
    assert_int_equal(support_count_entries(base, "plain"), 0);
    /* an unknown figure is bad input, refused before any work */
    snprintf(out, sizeof out, "%s/new", base);
    const char *bad[] = {"figures", "--only", "fig-nothing", "--out", out, NULL};
    assert_int_equal(run(bad), 2);
    assert_int_equal(support_count_entries(base, NULL), 1);
    assert_int_equal(support_count_entries(base, "plain"), 0);
    assert_int_equal(support_rmtree(base), 0);
}

static int setup(void **state)
{
    if (support_tmpdir(dir, sizeof dir, "fig") != 0)
        return -1;
    *state = dir; /* removed by support_teardown_dir */
    return 0;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test(test_two_figures),
             cmocka_unit_test(test_manson_filters),
             cmocka_unit_test(test_unwritable_out))
