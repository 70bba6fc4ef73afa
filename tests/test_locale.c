/*
 * test_locale.c: numbers stay C-locale text under a locale whose decimal
 * point is a comma.
 *
 * A program that links the library (or hosts its plug-ins) may set
 * LC_NUMERIC, and strtod and printf follow it.  Every test here runs under
 * de_DE.UTF-8 (scripts/install-deps.sh generates it; without it the tests
 * fail, they do not skip) and checks that specs parse and print, CSV and
 * JSON numbers, the reference cache's key, plot data and error messages
 * all use '.', written out by hand here.
 */
#include "bench.h"
#include "support.h"

#include <locale.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

static char dir[] = "/tmp/aabench-locale-XXXXXX";

static const void *const *pattern_table(void) { return (const void *const *)aa_pattern_types; }
static const void *const *filter_table(void) { return (const void *const *)aa_filter_types; }

/* Per test: the comma locale, and proof that printf obeys it here. */
static int comma_locale(void **state)
{
    (void)state;
    if (!setlocale(LC_ALL, "de_DE.UTF-8")) {
        print_error("locale de_DE.UTF-8 is missing: scripts/install-deps.sh generates it\n");
        return -1;
    }
    char probe[16];
    snprintf(probe, sizeof probe, "%g", 0.5);
    if (strcmp(probe, "0,5") != 0) {
        setlocale(LC_ALL, "C");
        print_error("de_DE.UTF-8 prints 0.5 as \"%s\", not with a decimal comma\n", probe);
        return -1;
    }
    return 0;
}

static int c_locale(void **state)
{
    (void)state;
    setlocale(LC_ALL, "C");
    return 0;
}

static char *slurp(const char *path)
{
    static char buf[1 << 16];
    return support_read_file(path, buf, sizeof buf, NULL);
}

static void test_spec(void **state)
{
    (void)state;
    aa_spec s;
    char text[512];
    assert_int_equal(aa_spec_parse("tent:r=0.5", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 0.5);
    assert_int_equal(aa_spec_parse("gauss:s=1.25", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 1.25);
    /* a comma-locale number is not a number: "0,5" would end the pair */
    assert_int_equal(aa_spec_parse("tent:r=0,5", filter_table(), "filter", &s), AA_EINVAL);
    assert_int_equal(aa_spec_parse("crow:kmax=0.5,gap0=3/256", pattern_table(), "pattern", &s),
                     AA_OK);
    assert_true(s.v[1] == 0.5 && s.v[2] == 0.01171875);
    /* every parameter, in table order: curves 96, kmax, gap0, gap1 = 0.5/256 */
    assert_int_equal(aa_spec_format(&s, text, sizeof text), AA_OK);
    assert_string_equal(text, "crow:curves=96,kmax=0.5,gap0=0.01171875,gap1=0.001953125");
    const aa_param *r = &aa_filter_tent.info.params[0];
    double v;
    assert_int_equal(aa_param_parse(r, "0.75", &v), AA_OK);
    assert_true(v == 0.75);
}

static void test_csv_json(void **state)
{
    (void)state;
    aa_row row, *back;
    size_t n;
    char csv[512], json[512];
    memset(&row, 0, sizeof row);
    snprintf(row.pattern, sizeof row.pattern, "crow");
    snprintf(row.filter, sizeof row.filter, "tent:r=0.5");
    snprintf(row.method, sizeof row.method, "jitter:spp=4");
    snprintf(row.canonical, sizeof row.canonical, "jitter:spp=4,seq=stratified");
    row.w = 8, row.h = 4;
    row.t = 0.5, row.vx = 0.25, row.vy = -1.5;
    row.seed = 1, row.threads = 1, row.reps = 1;
    row.spp = 4;
    row.m.rmse = 0.125;
    row.m.max_err = 0.75;
    row.m.psnr = 18.0625;
    row.seconds = row.seconds_min = row.seconds_max = 0.001953125;
    row.ok = 1;
    snprintf(csv, sizeof csv, "%s/r.csv", dir);
    snprintf(json, sizeof json, "%s/r.json", dir);
    assert_int_equal(aa_rows_write_csv(csv, &row, 1), AA_OK);
    const char *t = slurp(csv);
    /* the header's columns: pattern,size,filter,method,canonical,spp,rmse,
     * mae,max_err,...; the row's first seven cells */
    assert_non_null(strstr(t, "\ncrow,8x4,tent:r=0.5,jitter:spp=4,\"jitter:spp=4,seq=stratified\","
                              "4,0.125,0,0.75,"));
    assert_non_null(strstr(t, ",0.5,0.25,-1.5,1,,")); /* time, vx, vy, ok, note, timing */
    assert_null(strstr(t, "0,125"));
    assert_int_equal(aa_rows_read_csv(csv, &back, &n), AA_OK);
    assert_int_equal(n, 1);
    assert_true(back[0].m.rmse == 0.125 && back[0].m.max_err == 0.75 && back[0].t == 0.5 &&
                back[0].vx == 0.25 && back[0].vy == -1.5 && back[0].m.psnr == 18.0625);
    free(back);
    assert_int_equal(aa_rows_write_json(json, &row, 1), AA_OK);
    t = slurp(json);
    assert_non_null(strstr(t, "\"rmse\":0.125,"));
    assert_non_null(strstr(t, "\"psnr\":18.0625,"));
    assert_non_null(strstr(t, "\"render_seconds\":0.001953125,"));
    assert_non_null(strstr(t, "\"time\":0.5,\"motion\":[0.25,-1.5]"));
}

static void test_view_key(void **state)
{
    (void)state;
    aa_view v;
    char key[4096];
    memset(&v, 0, sizeof v);
    assert_int_equal(aa_spec_parse("fence:period=0.125", pattern_table(), "pattern", &v.pattern),
                     AA_OK);
    assert_int_equal(aa_filter_parse("gauss:s=0.75", &v.filter), AA_OK);
    v.w = 16, v.h = 8;
    v.t = 2.5, v.vx = 0.25, v.vy = -0.5;
    assert_int_equal(aa_view_key(&v, key, sizeof key), AA_OK);
    assert_non_null(strstr(key, "\nsize 16x8\nfilter gauss:s=0.75,cut=0\ntime 2.5\n"
                                "motion 0.25,-0.5\n"));
    assert_non_null(strstr(key, "period=0.125"));
}

static void test_plot_data(void **state)
{
    (void)state;
    aa_convergence c;
    const char *names[] = {"jitter"};
    char path[512];
    memset(&c, 0, sizeof c);
    c.n = 3;
    for (size_t q = 0; q < 3; q++) {
        c.spp[q] = 1 << (2 * q);            /* 1, 4, 16 */
        c.rmse[q] = 0.5 / (double)(1 << q); /* 0.5 spp^-1/2 */
        c.rmse_sd[q] = c.rmse[q] / 8;
    }
    c.slope = -0.5, c.slope_err = 0.015625, c.intercept = 0.0;
    assert_int_equal(aa_plot_convergence(dir, &c, names, 1, "convergence 0.5"), AA_OK);
    snprintf(path, sizeof path, "%s/convergence.dat", dir);
    /* spp, rmse, its spread, the fitted line exp(0) spp^-1/2 */
    assert_string_equal(slurp(path), "\"jitter: slope -0.500 +- 0.016\"\n"
                                     "1 0.5 0.0625 1\n"
                                     "4 0.25 0.03125 0.5\n"
                                     "16 0.125 0.015625 0.25\n\n\n");
}

static void test_message(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_null(aa_scene_transform(s, -0.5, 1.0, 0.25, 0.0));
    assert_string_equal(aa_last_error(),
                        "scene transform (-0.5, 1, 0.25, 0) is not a positive scaling");
    aa_scene_free(s);
}

static int setup(void **state)
{
    *state = dir;
    return mkdtemp(dir) ? 0 : -1;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test_setup_teardown(test_spec, comma_locale, c_locale),
             cmocka_unit_test_setup_teardown(test_csv_json, comma_locale, c_locale),
             cmocka_unit_test_setup_teardown(test_view_key, comma_locale, c_locale),
             cmocka_unit_test_setup_teardown(test_plot_data, comma_locale, c_locale),
             cmocka_unit_test_setup_teardown(test_message, comma_locale, c_locale))
