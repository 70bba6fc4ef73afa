/*
 * test_runfolder.c: a C program does what `aabench run`, `run --resume`
 * and `merge` do, through the library's run folder (runfolder.h), in this
 * process, and the outcomes are checked against facts that do not come
 * from the code under test:
 *
 *  - a run stopped by its interrupt hook after two cases and then opened
 *    and run to the end holds the rows of a run never stopped, case for
 *    case (the errors are deterministic: every case is computed the same
 *    way whichever run measures it), and its results.csv says so too;
 *  - three shards merged hold the rows of the unsharded run, and a merge
 *    with a shard missing is refused naming it, with nothing written;
 *  - the exact method's image of a white triangle (an SVG) box-filtered
 *    sums to the triangle's area by the shoelace formula, and its error
 *    against the reference is zero to rounding;
 *  - the words made for a plan given without them read back as that plan;
 *  - images: by default those of the views of at most 512x512 pixels and
 *    of the run's smallest size, all of them with --images all, and the
 *    choice kept in the run's words.
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
#include <unistd.h>

#include <cmocka.h>

static char dir[256];

/* The plan of the tests: one cross product of 2 sizes x 3 methods. */
static void small_plan(aa_plan *plan)
{
    aa_plan_default(plan);
    plan->patterns[plan->npatterns++] = "crow";
    plan->sizes[plan->nsizes++] = "16x16";
    plan->sizes[plan->nsizes++] = "24x16";
    plan->filters[plan->nfilters++] = "box";
    plan->methods[plan->nmethods++] = "point";
    plan->methods[plan->nmethods++] = "area";
    plan->methods[plan->nmethods++] = "supersample:n=2";
    plan->reps = 1;
}
#define SMALL_CASES 6

static void small_options(aa_run_options *opt, const char *out, char *buf, size_t len)
{
    static char cache[300];
    aa_run_options_default(opt);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(buf, len, "%s/%s", dir, out);
    opt->out = buf;
    opt->cache = cache;
    opt->threads = 1;
    opt->plots = 0; /* the convergence is not what these tests are about */
}

/* The rows of the run never stopped, made once. */
static aa_row *whole;
static size_t nwhole;

static void rows_equal(const char *what, const aa_row *a, size_t na, const aa_row *b, size_t nb)
{
    if (na != nb)
        fail_msg("%s: %zu rows, not %zu", what, na, nb);
    for (size_t k = 0; k < na; k++) {
        if (a[k].case_index != b[k].case_index || strcmp(a[k].method, b[k].method) ||
            strcmp(a[k].pattern, b[k].pattern) || strcmp(a[k].filter, b[k].filter) ||
            a[k].w != b[k].w || a[k].h != b[k].h || a[k].ok != b[k].ok)
            fail_msg("%s: row %zu is %s on %s %dx%d (case %ld), not %s on %s %dx%d (case %ld)",
                     what, k, a[k].method, a[k].pattern, a[k].w, a[k].h, a[k].case_index,
                     b[k].method, b[k].pattern, b[k].w, b[k].h, b[k].case_index);
        /* results.csv keeps nine significant digits */
        if (fabs(a[k].m.rmse - b[k].m.rmse) > 1e-8 * fabs(b[k].m.rmse) ||
            fabs(a[k].m.max_err - b[k].m.max_err) > 1e-8 * fabs(b[k].m.max_err))
            fail_msg("%s: %s on %dx%d: rmse %.17g, not %.17g", what, a[k].method, a[k].w,
                     a[k].h, a[k].m.rmse, b[k].m.rmse);
    }
}

static void csv_equal(const char *what, const char *folder)
{
    char path[400];
    aa_row *rows;
    size_t n;
    snprintf(path, sizeof path, "%s/results.csv", folder);
    assert_int_equal(aa_rows_read_csv(path, &rows, &n), AA_OK);
    rows_equal(what, rows, n, whole, nwhole);
    free(rows);
}

static void run_whole(void)
{
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf;
    char out[300];
    small_plan(&plan);
    small_options(&opt, "whole", out, sizeof out);
    if (aa_runfolder_create(&plan, &opt, &rf) || aa_runfolder_run(rf) ||
        aa_runfolder_finish(rf))
        fail_msg("the whole run: %s", aa_last_error());
    const aa_row *rows = aa_runfolder_rows(rf, &nwhole);
    assert_int_equal(nwhole, SMALL_CASES);
    assert_non_null(whole = malloc(nwhole * sizeof *whole));
    memcpy(whole, rows, nwhole * sizeof *whole);
    for (size_t k = 0; k < nwhole; k++)
        assert_int_equal(whole[k].case_index, (long)k);
    assert_string_equal(aa_runfolder_dir(rf), out);
    aa_runfolder_free(rf);
    char path[400];
    snprintf(path, sizeof path, "%s/montage.png", out);
    assert_int_equal(access(path, F_OK), 0);
}

/* The hooks: cases announced (a reference is not a case); a stop asked
 * before the third. */
typedef struct hooks {
    size_t cases;
} hooks;

static void count_cases(void *vh, size_t done, size_t total, const char *what)
{
    (void)done, (void)total;
    if (strcmp(what, "reference") && strcmp(what, "done"))
        ((hooks *)vh)->cases++;
}

static int stop_at_third(void *vh)
{
    return ((hooks *)vh)->cases >= 3;
}

static void test_interrupt_and_resume(void **state)
{
    (void)state;
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf;
    char out[300];
    hooks h = {0};
    small_plan(&plan);
    small_options(&opt, "resumed", out, sizeof out);
    opt.progress = count_cases, opt.interrupted = stop_at_third, opt.hook = &h;
    assert_int_equal(aa_runfolder_create(&plan, &opt, &rf), AA_OK);
    assert_int_equal(aa_runfolder_run(rf), AA_EFAIL);
    assert_true(aa_runfolder_interrupted(rf));
    size_t n;
    aa_runfolder_rows(rf, &n);
    assert_int_equal(n, 2);
    aa_runfolder_free(rf);
    /* what is on disk: the two cases */
    aa_row *rows;
    char path[400];
    snprintf(path, sizeof path, "%s/results.csv", out);
    assert_int_equal(aa_rows_read_csv(path, &rows, &n), AA_OK);
    rows_equal("the stopped run", rows, n, whole, 2);
    free(rows);

    /* open it as `run --resume` does: the two kept, the four left run */
    aa_run_options again;
    aa_run_options_default(&again);
    again.cache = opt.cache, again.threads = 1;
    h.cases = 0;
    again.progress = count_cases, again.hook = &h;
    assert_int_equal(aa_runfolder_open(out, &again, &rf), AA_OK);
    assert_int_equal(aa_runfolder_kept(rf), 2);
    assert_int_equal(aa_runfolder_run(rf), AA_OK);
    assert_int_equal(h.cases, SMALL_CASES - 2);
    const aa_row *all = aa_runfolder_rows(rf, &n);
    rows_equal("the resumed run", all, n, whole, nwhole);
    assert_int_equal(aa_runfolder_finish(rf), AA_OK);
    aa_runfolder_free(rf);
    csv_equal("the resumed run's results.csv", out);
    /* the options recorded with the run are its own: no plots */
    snprintf(path, sizeof path, "%s/plots", out);
    assert_int_not_equal(access(path, F_OK), 0);

    /* nothing left to measure: opened again, it measures nothing */
    h.cases = 0;
    assert_int_equal(aa_runfolder_open(out, &again, &rf), AA_OK);
    assert_int_equal(aa_runfolder_kept(rf), SMALL_CASES);
    assert_int_equal(aa_runfolder_run(rf), AA_OK);
    assert_int_equal(h.cases, 0);
    aa_runfolder_free(rf);

    /* a folder that is not a run's */
    snprintf(path, sizeof path, "%s/cache", dir);
    assert_int_equal(aa_runfolder_open(path, &again, &rf), AA_EIO);
    assert_null(rf);
}

static void test_shards_merged(void **state)
{
    (void)state;
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf;
    char out[3][300], merged[300];
    const char *dirs[3];
    size_t total = 0, n;
    for (int k = 1; k <= 3; k++) {
        char name[32];
        snprintf(name, sizeof name, "shard%d", k);
        small_plan(&plan);
        plan.shard = k, plan.shards = 3;
        small_options(&opt, name, out[k - 1], sizeof out[k - 1]);
        dirs[k - 1] = out[k - 1];
        assert_int_equal(aa_runfolder_create(&plan, &opt, &rf), AA_OK);
        assert_int_equal(aa_runfolder_run(rf), AA_OK);
        assert_int_equal(aa_runfolder_finish(rf), AA_OK);
        int sk, sn;
        aa_runfolder_shard(rf, &sk, &sn);
        assert_true(sk == k && sn == 3);
        aa_runfolder_rows(rf, &n);
        total += n;
        aa_runfolder_free(rf);
        /* a shard makes no montage: the merge does */
        char path[1000];
        snprintf(path, sizeof path, "%s/montage.png", out[k - 1]);
        assert_int_not_equal(access(path, F_OK), 0);
    }
    assert_int_equal(total, SMALL_CASES);

    /* one missing: refused, naming it, nothing written */
    small_options(&opt, "merged-two", merged, sizeof merged);
    assert_int_equal(aa_runfolder_merge(dirs, 2, &opt, &rf), AA_EINVAL);
    assert_null(rf);
    if (!strstr(aa_last_error(), "3/3 missing"))
        fail_msg("the merge of two of three shards says: %s", aa_last_error());
    assert_int_not_equal(access(merged, F_OK), 0);
    /* one given twice */
    const char *twice[] = {dirs[0], dirs[1], dirs[2], dirs[1]};
    assert_int_equal(aa_runfolder_merge(twice, 4, &opt, &rf), AA_EINVAL);
    assert_int_not_equal(access(merged, F_OK), 0);

    small_options(&opt, "merged", merged, sizeof merged);
    assert_int_equal(aa_runfolder_merge(dirs, 3, &opt, &rf), AA_OK);
    const aa_row *rows = aa_runfolder_rows(rf, &n);
    rows_equal("the merged shards", rows, n, whole, nwhole);
    /* a merged run has run: it measures nothing again */
    assert_int_equal(aa_runfolder_run(rf), AA_EINVAL);
    assert_int_equal(aa_runfolder_finish(rf), AA_OK);
    aa_runfolder_free(rf);
    csv_equal("the merged results.csv", merged);
    char path[400];
    snprintf(path, sizeof path, "%s/montage.png", merged);
    assert_int_equal(access(path, F_OK), 0);
    /* the merged folder is a whole run's: opened, it has nothing left */
    aa_run_options again;
    aa_run_options_default(&again);
    again.cache = opt.cache;
    assert_int_equal(aa_runfolder_open(merged, &again, &rf), AA_OK);
    assert_int_equal(aa_runfolder_kept(rf), SMALL_CASES);
    aa_runfolder_free(rf);
}

/* A white triangle on black, an SVG at one pixel per unit: the exact
 * method's box-filtered image sums to its area. */
static void test_triangle_area(void **state)
{
    (void)state;
    static const double x[3] = {3.3, 20.1, 8.4}, y[3] = {2.7, 5.2, 19.9};
    char svg[300], spec[400], out[300], text[512];
    snprintf(svg, sizeof svg, "%s/triangle.svg", dir);
    snprintf(text, sizeof text,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"24\" height=\"24\">\n"
             "<polygon points=\"%g,%g %g,%g %g,%g\" fill=\"white\"/>\n</svg>\n",
             x[0], y[0], x[1], y[1], x[2], y[2]);
    support_write_file(svg, text, strlen(text));
    /* the shoelace formula */
    double area = 0.5 * fabs((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
    snprintf(spec, sizeof spec, "svg:file=%s", svg);
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf;
    aa_plan_default(&plan);
    plan.patterns[plan.npatterns++] = spec;
    plan.sizes[plan.nsizes++] = "24x24";
    plan.filters[plan.nfilters++] = "box";
    plan.methods[plan.nmethods++] = "area";
    plan.reps = 1;
    small_options(&opt, "triangle", out, sizeof out);
    assert_int_equal(aa_runfolder_create(&plan, &opt, &rf), AA_OK);
    assert_int_equal(aa_runfolder_run(rf), AA_OK);
    size_t n;
    const aa_row *rows = aa_runfolder_rows(rf, &n);
    assert_int_equal(n, 1);
    assert_true(rows[0].ok);
    if (!(rows[0].m.rmse < 1e-12))
        fail_msg("area against the reference: rmse %g", rows[0].m.rmse);
    aa_runfolder_free(rf);
    /* the one EXR the method wrote */
    char cmd[700], path[600];
    snprintf(cmd, sizeof cmd, "ls %s/images/*-area.exr", out);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    assert_non_null(fgets(path, sizeof path, p));
    path[strcspn(path, "\n")] = '\0';
    pclose(p);
    aa_image im;
    assert_int_equal(aa_image_read(path, &im), AA_OK);
    double sum = 0;
    for (int k = 0; k < im.w * im.h; k++)
        sum += im.v[(size_t)k * (size_t)im.c];
    aa_image_free(&im);
    if (fabs(sum - area) > 1e-4)
        fail_msg("the triangle's pixels sum to %.9g, its area is %.9g", sum, area);
}

/* A plan given without words is recorded with words made from it, and
 * they read back as the same plan. */
static void test_words_read_back(void **state)
{
    (void)state;
    aa_plan plan, back;
    aa_run_options opt, oback;
    aa_runfolder *rf;
    char out[300], path[400];
    small_plan(&plan);
    plan.seed = 7;
    plan.target_ci = 0.013;
    plan.motion_given = 1, plan.vx = 0.25, plan.vy = -0.5;
    small_options(&opt, "words", out, sizeof out);
    opt.images = AA_IMAGES_NONE;
    opt.isolate = AA_ISOLATE_NONE;
    assert_int_equal(aa_runfolder_create(&plan, &opt, &rf), AA_OK);
    aa_runfolder_free(rf);
    aa_manifest m;
    snprintf(path, sizeof path, "%s/run.json", out);
    assert_int_equal(aa_manifest_read(path, &m), AA_OK);
    char **args = calloc((size_t)m.argc + 2, sizeof *args);
    assert_non_null(args);
    args[0] = "run";
    for (int k = 0; k < m.argc; k++)
        args[k + 1] = m.argv[k];
    int asked;
    aa_plan_default(&back);
    aa_run_options_default(&oback);
    assert_int_equal(aa_plan_parse(m.argc + 1, args, &back, &oback, &asked), AA_OK);
    assert_int_equal(asked, 0);
    assert_string_equal(back.suite, "default");
    assert_int_equal(back.npatterns, 1);
    assert_string_equal(back.patterns[0], "crow");
    assert_int_equal(back.nsizes, 2);
    assert_string_equal(back.sizes[1], "24x16");
    assert_int_equal(back.nmethods, 3);
    assert_string_equal(back.methods[2], "supersample:n=2");
    assert_int_equal(back.reps, 1);
    assert_true(back.seed == 7);
    /* a percentage in the words: the fraction to the last bit or two */
    assert_true(fabs(back.target_ci - plan.target_ci) <= 1e-15);
    assert_true(back.motion_given && back.vx == 0.25 && back.vy == -0.5);
    assert_int_equal(oback.images, AA_IMAGES_NONE);
    assert_int_equal(oback.plots, 0);
    assert_int_equal(oback.isolate, AA_ISOLATE_NONE);
    free(args);
    aa_manifest_free(&m);
    /* the words of the command line: an unknown option and a stray word */
    char *bad[] = {"run", "--no-such", NULL}, *stray[] = {"run", "stray", NULL};
    aa_plan_default(&back);
    assert_int_equal(aa_plan_parse(2, bad, &back, &oback, &asked), AA_EINVAL);
    assert_int_equal(asked, '?');
    assert_int_equal(aa_plan_parse(2, stray, &back, &oback, &asked), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "unexpected argument"));
}


/* 1 if DIR/images/NAME exists. */
static int has_image(const char *folder, const char *name)
{
    char path[600];
    snprintf(path, sizeof path, "%s/images/%s", folder, name);
    return access(path, F_OK) == 0;
}

/* Which views' images a run writes (AA_IMAGES_*): star at 8x8 and at
 * 520x520 (270,400 pixels, over 512 x 512 = 262,144). */
static void test_images_by_size(void **state)
{
    (void)state;
    static const struct {
        const char *out;
        int images, sizes; /* sizes: 2 both, 1 the large one only */
        int large;         /* the large view's images expected */
    } runs[] = {{"img-small", AA_IMAGES_SMALL, 2, 0},
                {"img-all", AA_IMAGES_ALL, 2, 1},
                {"img-large-only", AA_IMAGES_SMALL, 1, 1}};
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        aa_plan plan;
        aa_run_options opt;
        aa_runfolder *rf;
        char out[300], path[400];
        aa_plan_default(&plan);
        plan.patterns[plan.npatterns++] = "star";
        if (runs[k].sizes == 2)
            plan.sizes[plan.nsizes++] = "8x8";
        plan.sizes[plan.nsizes++] = "520x520";
        plan.filters[plan.nfilters++] = "box";
        plan.methods[plan.nmethods++] = "point";
        plan.reps = 1;
        small_options(&opt, runs[k].out, out, sizeof out);
        opt.images = runs[k].images;
        if (aa_runfolder_create(&plan, &opt, &rf) || aa_runfolder_run(rf) ||
            aa_runfolder_finish(rf))
            fail_msg("%s: %s", runs[k].out, aa_last_error());
        /* what the command prints from: 512 x 512, or the smallest view's
         * pixels where that is larger, or no limit */
        long most = runs[k].images == AA_IMAGES_ALL ? 0 : runs[k].sizes == 2 ? 262144 : 270400;
        assert_int_equal(aa_runfolder_images_max(rf), most);
        aa_runfolder_free(rf);
        if (runs[k].sizes == 2) {
            assert_int_equal(has_image(out, "star-8x8-box-point.exr"), 1);
            assert_int_equal(has_image(out, "star-8x8-box-point-error.png"), 1);
        }
        assert_int_equal(has_image(out, "star-520x520-box-point.exr"), runs[k].large);
        assert_int_equal(has_image(out, "star-520x520-box-point.png"), runs[k].large);
        assert_int_equal(has_image(out, "star-520x520-box-reference.exr"), runs[k].large);
        /* the large view's montage (montage.png is the first view's) */
        snprintf(path, sizeof path, "%s/%s", out,
                 runs[k].sizes == 2 ? "montage-star-520x520-box.png" : "montage.png");
        assert_int_equal(access(path, F_OK) == 0, runs[k].large);
        /* the report says where a view has none */
        snprintf(path, sizeof path, "%s/index.html", out);
        FILE *f = fopen(path, "r");
        assert_non_null(f);
        char page[65536];
        size_t got = fread(page, 1, sizeof page - 1, f);
        fclose(f);
        page[got] = '\0';
        assert_int_equal(strstr(page, "No images of this view") != NULL, !runs[k].large);
    }
    /* the choice in the run's words, and the options that contradict */
    aa_plan back;
    aa_run_options oback;
    int asked;
    char *all[] = {"run", "--images=all", NULL}, *none[] = {"run", "--images", "none", NULL},
         *both[] = {"run", "--no-images", "--images", "all", NULL},
         *bad[] = {"run", "--images", "some", NULL};
    aa_plan_default(&back);
    aa_run_options_default(&oback);
    assert_int_equal(oback.images, AA_IMAGES_SMALL);
    assert_int_equal(aa_plan_parse(2, all, &back, &oback, &asked), AA_OK);
    assert_int_equal(oback.images, AA_IMAGES_ALL);
    aa_plan_default(&back);
    aa_run_options_default(&oback);
    assert_int_equal(aa_plan_parse(3, none, &back, &oback, &asked), AA_OK);
    assert_int_equal(oback.images, AA_IMAGES_NONE);
    aa_plan_default(&back);
    aa_run_options_default(&oback);
    assert_int_equal(aa_plan_parse(4, both, &back, &oback, &asked), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "--no-images"));
    aa_plan_default(&back);
    aa_run_options_default(&oback);
    assert_int_equal(aa_plan_parse(3, bad, &back, &oback, &asked), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "none, small or all"));
    /* the words of a run with --images all read back as it */
    aa_manifest m;
    char path[400];
    snprintf(path, sizeof path, "%s/img-all/run.json", dir);
    assert_int_equal(aa_manifest_read(path, &m), AA_OK);
    int found = 0;
    for (int k = 0; k < m.argc; k++)
        found += !strcmp(m.argv[k], "--images=all");
    assert_int_equal(found, 1);
    aa_manifest_free(&m);
}

static int setup(void **state)
{
    if (support_tmpdir(dir, sizeof dir, "runfolder") != 0)
        return -1;
    *state = dir; /* removed by support_teardown_dir */
    return 0;
}

static int teardown(void **state)
{
    free(whole);
    return support_teardown_dir(state);
}

static void test_whole(void **state)
{
    (void)state;
    run_whole();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whole),
        cmocka_unit_test(test_interrupt_and_resume),
        cmocka_unit_test(test_shards_merged),
        cmocka_unit_test(test_triangle_area),
        cmocka_unit_test(test_words_read_back),
        cmocka_unit_test(test_images_by_size),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
