/*
 * test_cost.c: a case's cost estimated before it runs (harness/bench/cost.c).
 *
 * Known answers from the stated formula, E = W H S + the sum over pixel rows
 * of the square of the number of pieces crossing the row (S: spp, n^2 for
 * n, else 1), worked out here by hand:
 *  - a square with corners (0.2, 0.2) and (0.8, 0.8) at 10x10 has two
 *    pieces that are not flat (its vertical sides), each crossing rows 2 to
 *    7: 6 rows of 2, 24; with point (S = 1) E = 100 + 24 = 124, with
 *    jitter:spp=16 1600 + 24 = 1624, with supersample:n=3 900 + 24 = 924;
 *  - feibush:stripes=65536 at 48x48 (patterns/README.md: 65536 vertical
 *    stripes across the square, each with two vertical sides crossing every
 *    row) has at least 65536 pieces crossing each of the 48 rows: E >=
 *    48 x 65536^2 = 2.1e11, past the limit 1e11; crow at 1024x1024, of n
 *    pieces each crossing at most every row, has E at most 1024^2 + 1024
 *    n^2 under area, and under the limit;
 *  - a run that reaches such a view warns before the view's reference,
 *    naming the case (the run is stopped there by its progress callback).
 */
#include "bench.h"
#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static aa_scene *square(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.2, 0.2), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.8, 0.2), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.8, 0.8), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.2, 0.8), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static double estimate(const aa_scene *scene, int w, int h, const char *method)
{
    aa_spec m;
    aa_filter box;
    aa_filter_default(&box);
    assert_int_equal(aa_spec_parse(method, aa_method_table(), "method", &m), AA_OK);
    aa_scene *placed = aa_scene_place(scene, w, h, 0, 0, 0);
    assert_non_null(placed);
    double e = aa_case_estimate(placed, w, h, &m);
    aa_scene_free(placed);
    return e;
}

static void test_formula(void **state)
{
    (void)state;
    aa_scene *s = square();
    assert_true(estimate(s, 10, 10, "point") == 124);
    assert_true(estimate(s, 10, 10, "jitter:spp=16") == 1624);
    assert_true(estimate(s, 10, 10, "supersample:n=3") == 924);
    aa_scene_free(s);
}

static aa_scene *pattern(const char *text)
{
    aa_spec p;
    aa_scene *s;
    assert_int_equal(aa_pattern_parse(text, &p), AA_OK);
    assert_int_equal(aa_pattern_scene(&p, &s), AA_OK);
    return s;
}

static void test_limit(void **state)
{
    (void)state;
    aa_scene *f = pattern("feibush:stripes=65536"), *c = pattern("crow");
    double ef = estimate(f, 48, 48, "area"), ec = estimate(c, 1024, 1024, "area");
    print_message("feibush:stripes=65536 48x48 area: %.3g; crow 1024x1024 area: %.3g\n", ef, ec);
    assert_true(ef >= 48.0 * 65536 * 65536 && ef > AA_COST_LIMIT);
    size_t n;
    aa_scene *placed = aa_scene_place(c, 1024, 1024, 0, 0, 0);
    aa_scene_pieces(placed, &n);
    aa_scene_free(placed);
    assert_true(ec <= 1024.0 * 1024 + 1024.0 * (double)n * (double)n && ec < AA_COST_LIMIT);
    aa_scene_free(f);
    aa_scene_free(c);
}

static char warned[4096];
static void capture(const char *message, void *ctx)
{
    (void)ctx;
    snprintf(warned, sizeof warned, "%s", message);
}
static int stop(void *ctx, size_t done, size_t total, const char *what)
{
    (void)ctx, (void)done, (void)total, (void)what;
    return 1;
}

static void test_run_warns(void **state)
{
    (void)state;
    aa_run_spec p = {.text = "feibush:stripes=65536"}, m = {.text = "area"};
    assert_int_equal(aa_pattern_parse(p.text, &p.spec), AA_OK);
    assert_int_equal(aa_spec_parse(m.text, aa_method_table(), "method", &m.spec), AA_OK);
    aa_run_filter f = {.text = "box"};
    aa_filter_default(&f.filter);
    aa_run_size size = {48, 48};
    aa_run_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.patterns = &p, cfg.npatterns = 1;
    cfg.sizes = &size, cfg.nsizes = 1;
    cfg.filters = &f, cfg.nfilters = 1;
    cfg.methods = &m, cfg.nmethods = 1;
    cfg.reps = 1, cfg.threads = 1;
    cfg.progress = stop;
    void *old_ctx;
    aa_warn_fn old = aa_get_warn(&old_ctx);
    aa_set_warn(capture, NULL);
    aa_row *rows;
    size_t n;
    int st = aa_run(&cfg, &rows, &n);
    aa_set_warn(old, old_ctx);
    free(rows);
    assert_int_equal(st, AA_EFAIL); /* stopped by the callback, before the reference */
    if (!strstr(warned, "area on feibush:stripes=65536 48x48: estimated cost") ||
        !strstr(warned, "may run for minutes"))
        fail_msg("no warning: \"%s\"", warned);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_formula), cmocka_unit_test(test_limit),
             cmocka_unit_test(test_run_warns))
