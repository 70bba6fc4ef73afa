/*
 * test_truth_gauss.c: the Gaussian's fixed rule in the ground truth
 * (truth.c), against a closed form and against QAG (the rest of the ground
 * truth's tests: tests/test_truth.c).
 *
 *  - a straight edge through the image against the closed form (the 2-D
 *    Gaussian is radial, so a half-plane gives Phi(d / s), d the signed
 *    distance of the centre from the edge), every pixel within its own
 *    bound, for edges that take the fixed rule (slopes up to 0.84) and edges
 *    that must leave it to QAG (nearly horizontal), on each kind of panel
 *    grid (s = 0.07, 0.3, 0.5, 1.3);
 *  - scenes with vertices, crossing edges, layers and general arcs (the
 *    fall-back path) and crow against the QAG-only computation, within the
 *    two bounds; thread counts 1, 2, 3 bit-identical.
 *
 * Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets it
 * for the tests) a declared subset: the fixed rule at 1 and 2 threads (not 3
 * too), and crow's first pattern still only (not moving too; its other two
 * patterns both ways).  A third thread splits the rows otherwise and a
 * moving view of that crow takes the same code paths with other numbers
 * (tests/README.md, "Tiers", says how that was checked); the sanitizers find
 * memory and undefined-behaviour errors along the paths taken, and the plain
 * build runs every case.
 */
/* tier: full */
#include "bench.h"
#include "truth_internal.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* A half-plane of colour fg on bg, its edge through (px, py) at angle theta
 * (degrees) from the vertical, in pixel units: a quadrilateral whose other
 * edges are 5000 pixels away.  The interior is on the side of n = (cos t,
 * -sin t), so d = n . (c - p). */
static aa_scene *half_plane(double px, double py, double theta, aa_rgb fg, aa_rgb bg)
{
    return scenes_half_plane_of(px, py, theta * M_PI / 180.0, 5000.0, fg, bg);
}

/* The half-planes' edges pass through (hp_px, hp_py), hp_fg on hp_bg. */
static const double hp_px = 15.37, hp_py = 12.61;
static const aa_rgb hp_fg = {{0.9, 0.3, 0.05}}, hp_bg = {{0.1, 0.2, 0.7}};

/* Every pixel of s = half_plane(hp_px, hp_py, theta, hp_fg, hp_bg) against
 * Phi(d / sd) (long double: its own error is below 1e-18), within the
 * pixel's bound; returns the largest error / bound over the pixels the
 * fixed rule took, and checks which path the pixels took.  The caller
 * builds s once for every s.d. (the scene does not depend on it). */
static double check_half_plane(const aa_scene *s, double sd, double theta, int want_fast)
{
    const int w = 31, h = 27;
    const double t = theta * M_PI / 180.0;
    const aa_rgb fg = hp_fg, bg = hp_bg;
    char spec[64];
    snprintf(spec, sizeof spec, "gauss:s=%g", sd);
    aa_filter f;
    assert_int_equal(aa_filter_parse(spec, &f), AA_OK);
    aa_image img, bound;
    aa_truth_stats st;
    size_t fast = 0;
    assert_int_equal(aa_image_alloc(&img, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&bound, w, h, 1), AA_OK);
    assert_int_equal(aa__truth_render_mode(s, &f, 2, 0, &img, &bound, &st, &fast), AA_OK);
    /* the edge as stored: its ends are rounded 5000 pixels out, which moves
     * it by up to 1e-12 pixels, so d is measured from the stored edge */
    size_t ne;
    const aa_edge *e = aa_scene_edges(s, &ne);
    long double ex = (long double)e[0].x1 - e[0].x0, ey = (long double)e[0].y1 - e[0].y0;
    long double len = sqrtl(ex * ex + ey * ey);
    double worst = 0, ratio = 0;
    /* without extended precision the per-pixel bound is not claimed; the
     * error must still be within the reference's promise */
    const int extended = aa_long_double_is_extended();
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            /* n = (ey, -ex) / len points into the interior */
            long double d = (ey * (i + 0.5L - e[0].x0) - ex * (j + 0.5L - e[0].y0)) / len;
            long double phi = 0.5L * erfcl(-d / (sd * sqrtl(2.0L)));
            double b = *aa_pixel(&bound, i, j);
            assert_true(b <= AA_TRUTH_BOUND);
            for (int c = 0; c < 3; c++) {
                double want = (double)(bg.c[c] + (fg.c[c] - bg.c[c]) * phi);
                double err = fabs(aa_pixel(&img, i, j)[c] - want);
                if (!(err <= (extended ? b : AA_TRUTH_BOUND) + 2e-16))
                    fail_msg("half-plane s=%g theta=%g pixel (%d, %d) channel %d: %.17g, "
                             "closed form %.17g, error %.2e > bound %.2e",
                             sd, theta, i, j, c, aa_pixel(&img, i, j)[c], want, err, b);
                worst = fmax(worst, err);
                if (b > f.lost * 1.01)
                    ratio = fmax(ratio, err / b);
            }
        }
    print_message("half-plane gauss:s=%-4g theta %4.1f (dx/dy %6.2f): %zu integrated, %zu by the "
                  "fixed rule; max error %.2e, max error/bound %.3f, max bound %.2e\n",
                  sd, theta, tan(t), st.integrated, fast, worst, ratio, st.max_bound);
    assert_true(st.integrated > 0);
    if (want_fast && extended) /* without it the reference takes QAG only */
        assert_int_equal(fast, st.integrated);
    else
        assert_int_equal(fast, 0);
    aa_image_free(&img);
    aa_image_free(&bound);
    return ratio;
}

static void test_gauss_half_plane(void **state)
{
    (void)state;
    const double sds[] = {0.07, 0.3, 0.5, 1.3};
    /* smooth: the fixed rule (4 angles); steep and nearly horizontal: QAG.
     * Each angle's scene is built once and rendered at every s.d.: its
     * index spans the 10000 pixels of the edge and building it costs more
     * than the renders. */
    const double thetas[] = {0.0, 3.0, -20.0, 40.0, 60.0, -80.0, 89.5};
    double r[4] = {0, 0, 0, 0};
    for (int a = 0; a < 7; a++) {
        aa_scene *s = half_plane(hp_px, hp_py, thetas[a], hp_fg, hp_bg);
        for (int k = 0; k < 4; k++) {
            double ratio = check_half_plane(s, sds[k], thetas[a], a < 4);
            if (a < 4)
                r[k] = fmax(r[k], ratio);
        }
        aa_scene_free(s);
    }
    /* smooth: the fixed rule's estimate bounds its actual error */
    for (int k = 0; k < 4; k++)
        if (aa_long_double_is_extended())
            assert_true(r[k] <= 1.0);
}

/* The reference of `placed` with the fixed rule against QAG only: within
 * the sum of the two bounds per pixel and channel, and the same for 1, 2 and
 * 3 threads.  Returns the fraction of non-uniform pixels the rule took. */
static double check_against_qagp(const char *what, const aa_scene *placed, int w, int h,
                                 const char *filter)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    aa_image a, b, a2, a3, ba, bb;
    aa_truth_stats sa, sb;
    size_t fast, fast2;
    assert_int_equal(aa_image_alloc(&a, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&a2, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&a3, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&b, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&ba, w, h, 1), AA_OK);
    assert_int_equal(aa_image_alloc(&bb, w, h, 1), AA_OK);
    assert_int_equal(aa__truth_render_mode(placed, &f, 1, 0, &a, &ba, &sa, &fast), AA_OK);
    assert_int_equal(aa__truth_render_mode(placed, &f, 2, 0, &a2, NULL, NULL, &fast2), AA_OK);
    if (!SAN_SUBSET)
        assert_int_equal(aa__truth_render_mode(placed, &f, 3, 0, &a3, NULL, NULL, NULL), AA_OK);
    assert_int_equal(aa__truth_render_mode(placed, &f, 2, AA__TRUTH_QAG, &b, &bb, &sb, NULL),
                     AA_OK);
    size_t bytes = sizeof(double) * (size_t)w * (size_t)h * 3;
    assert_memory_equal(a.v, a2.v, bytes);
    if (!SAN_SUBSET)
        assert_memory_equal(a.v, a3.v, bytes);
    assert_int_equal(fast, fast2);
    double worst = 0, ratio = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double allowed = *aa_pixel(&ba, i, j) + *aa_pixel(&bb, i, j);
            for (int c = 0; c < 3; c++) {
                double d = fabs(aa_pixel(&a, i, j)[c] - aa_pixel(&b, i, j)[c]);
                if (!(d <= allowed))
                    fail_msg("%s %s pixel (%d, %d) channel %d: fixed rule %.17g, QAG %.17g", what,
                             filter, i, j, c, aa_pixel(&a, i, j)[c], aa_pixel(&b, i, j)[c]);
                worst = fmax(worst, d);
                ratio = fmax(ratio, d / allowed);
            }
        }
    if (!(sa.max_bound <= AA_TRUTH_BOUND && sb.max_bound <= AA_TRUTH_BOUND))
        fail_msg("%s %s: largest bound %.2e with the fixed rule, %.2e with QAG only", what,
                 filter, sa.max_bound, sb.max_bound);
    assert_int_equal(sa.integrated, sb.integrated);
    double share = sa.integrated ? (double)fast / (double)sa.integrated : 0.0;
    print_message("%-28s %4dx%-4d %-11s: %zu integrated, %.1f%% by the fixed rule; max |rule - "
                  "QAG| %.2e (%.0f%% of the bounds), max bound %.2e\n",
                  what, w, h, filter, sa.integrated, 100 * share, worst, 100 * ratio, sa.max_bound);
    aa_image_free(&a);
    aa_image_free(&a2);
    aa_image_free(&a3);
    aa_image_free(&b);
    aa_image_free(&ba);
    aa_image_free(&bb);
    return share;
}

/* Vertices inside pixels, nearly horizontal edges, edges of two layers
 * crossing, a self-intersecting even-odd star and arcs whose y is not
 * linear in the parameter: the fall-back path next to the fixed rule. */
static aa_scene *mixed_scene(int w, int h)
{
    const aa_rgb red = {{0.95, 0.1, 0.2}}, teal = {{0.05, 0.6, 0.55}}, cream = {{1, 0.9, 0.7}};
    aa_scene *s = aa_scene_new((aa_rgb){{0.05, 0.05, 0.1}});
    /* front: a tall triangle with a nearly horizontal base */
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.12 * w, 0.83 * h), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.31 * w, 0.06 * h), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.58 * w, 0.86 * h), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    /* middle: a tall five-pointed star, even-odd (its edges cross) */
    assert_int_equal(aa_scene_layer(s, teal, AA_FILL_EVENODD), AA_OK);
    for (int k = 0; k < 5; k++) {
        double a = 2 * M_PI * (2 * k) / 5 + 0.3;
        double x = (0.62 + 0.2 * cos(a)) * w, y = (0.5 + 0.45 * sin(a)) * h;
        assert_int_equal(k ? aa_scene_line_to(s, x, y) : aa_scene_move_to(s, x, y), AA_OK);
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
    /* back: a tall lens of two arcs, each through an x extremum, and a
     * wide one through y extrema (split into monotone pieces whose y is
     * not linear in the parameter) */
    assert_int_equal(aa_scene_layer(s, cream, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.45 * w, 0.04 * h), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.95 * w, 0.45 * h, 0.52 * w, 0.97 * h), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.7 * w, 0.4 * h, 0.45 * w, 0.04 * h), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.05 * w, 0.62 * h), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.4 * w, 0.35 * h, 0.93 * w, 0.71 * h), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.5 * w, 0.9 * h, 0.05 * w, 0.62 * h), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_gauss_fallback(void **state)
{
    (void)state;
    if (!aa_long_double_is_extended()) { /* the reference takes QAG only: no rule to test */
        print_message("long double is not extended here: skipped\n");
        skip();
    }
    const int w = 47, h = 43;
    aa_scene *s = mixed_scene(w, h);
    const char *filters[] = {"gauss", "gauss:s=0.3", "gauss:s=0.8"};
    for (int k = 0; k < 3; k++) {
        double share = check_against_qagp("layers, star, arcs", s, w, h, filters[k]);
        /* both paths are exercised */
        assert_true(share > 0.05 && share < 0.95);
    }
    aa_scene_free(s);
}

static void test_gauss_crow_against_qagp(void **state)
{
    (void)state;
    if (!aa_long_double_is_extended()) { /* the reference takes QAG only: no rule to test */
        print_message("long double is not extended here: skipped\n");
        skip();
    }
    const char *patterns[] = {"crow", "crow:curves=10,kmax=0.5,gap0=0.2,gap1=0.05",
                              "crow:curves=40,kmax=-0.4,gap0=0.01,gap1=0.02"};
    int sizes[3][2] = {{72, 56}, {48, 40}, {57, 45}};
    for (int k = 0; k < 3; k++) {
        aa_scene *s = scenes_pattern(patterns[k]);
        aa_scene *placed = aa_scene_place(s, sizes[k][0], sizes[k][1], 0, 0, 0);
        assert_non_null(placed);
        double share = check_against_qagp(patterns[k], placed, sizes[k][0], sizes[k][1],
                                          k == 1 ? "gauss:s=0.8" : "gauss");
        assert_true(share > 0.9);
        aa_scene_free(placed);
        /* moving: the arcs' ends leave the panel grid */
        if (!SAN_SUBSET || k > 0) {
            assert_non_null(placed = aa_scene_place(s, sizes[k][0], sizes[k][1], 0.37, 0.2,
                                                    0.45));
            check_against_qagp(patterns[k], placed, sizes[k][0], sizes[k][1], "gauss");
            aa_scene_free(placed);
        }
        aa_scene_free(s);
    }
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_gauss_half_plane),
                                       cmocka_unit_test(test_gauss_fallback),
                                       cmocka_unit_test(test_gauss_crow_against_qagp)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
