/*
 * test_truth.c: the ground truth against independent derivations.
 *
 *  - `crow` under the box filter against tests/oracle.c's closed form (the
 *    alternating sum of exact "area right of arc k" integrals of clamped
 *    quadratics, derived from patterns/README.md alone), on every pixel of 256x256,
 *    7x3 and 255x129, with default and non-default parameters: 1e-12.
 *  - tent and Gaussian against the oracle's brute-force integration, within
 *    that integration's own error estimate.
 *  - uniform regions and pixels wholly inside a band are exact (0 or 1);
 *    every pixel's bound is at most 1e-12; 1 and 2 threads agree bit for bit.
 *  - polygon scenes (several layers, vertices inside pixels) against areas
 *    from tests/oracle.c's polygon clipper (Sutherland-Hodgman and the
 *    shoelace formula); Catmull's pixel is (0, 0.25, 0.5) (Catmull 1978).
 *  - a parabolic segment's area is 2/3 of its control triangle (Archimedes).
 *  - crowded pixels of 17 to 300 overlapping rectangles under the tent and
 *    the cubic B-spline: each pixel within its colours' range, the image's
 *    sum the picture's integral (partition of unity; visible areas from
 *    the rectangles' geometry).
 *  - the reference cache returns the same image and treats a damaged file
 *    as a miss.
 *  - the Gaussian's fixed rule: tests/test_truth_gauss.c.
 */
#include "bench.h"
#include "oracle.h"
#include "truth_internal.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* Reference of a pattern spec at w x h under filter text. */
static void reference(const char *pattern, int w, int h, const char *filter, int threads,
                      aa_image *img, aa_image *bound, aa_truth_stats *stats)
{
    const support_view v = {.w = w, .h = h, .filter = filter, .threads = threads};
    support_pattern_reference(pattern, &v, img, bound, stats);
}

static oracle_crow oracle_params(const char *pattern)
{
    aa_spec spec;
    assert_int_equal(aa_pattern_parse(pattern, &spec), AA_OK);
    oracle_crow p = {(int)spec.v[0], spec.v[1], spec.v[2], spec.v[3]};
    assert_true(oracle_crow_valid(&p));
    return p;
}

static void check_box(const char *pattern, int w, int h)
{
    aa_image img, bound;
    aa_truth_stats st;
    oracle_crow p = oracle_params(pattern);
    reference(pattern, w, h, "box", 0, &img, &bound, &st);
    double worst = support_check_crow_box(pattern, &p, &img, 1e-12);
    for (int k = 0; k < w * h; k++)
        assert_true(bound.v[k] <= AA_TRUTH_BOUND);
    print_message("%-40s %4dx%-4d box: max |ref - closed form| %.2e, max bound %.2e, %zu "
                  "integrated, %zu filled\n",
                  pattern, w, h, worst, st.max_bound, st.integrated, st.filled);
    aa_image_free(&img);
    aa_image_free(&bound);
}

static void test_crow_box_default(void **state)
{
    (void)state;
    const int sizes[][2] = {{256, 256}, {7, 3}, {255, 129}, {1, 1}};
    for (int k = 0; k < 4; k++)
        check_box("crow", sizes[k][0], sizes[k][1]);
}

static void test_crow_box_other(void **state)
{
    (void)state;
    check_box("crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", 256, 256);
    check_box("crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", 7, 3);
    check_box("crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", 255, 129);
    check_box("crow:curves=2,kmax=0.3,gap0=0.2", 33, 17);
    check_box("crow:curves=40,kmax=-0.4,gap0=0.01,gap1=0.02", 101, 77); /* curving left */
    /* arcs reaching outside the unit square, clipped by the background */
    check_box("crow:curves=10,kmax=0.5,gap0=0.2,gap1=0.05", 64, 48);
}

/* Tent and Gaussian against the oracle's brute force on a sample of pixels
 * (the brute force costs milliseconds a pixel). */
static void check_filtered(const char *pattern, int w, int h, const char *filter, double r,
                           int gauss)
{
    aa_image img, bound;
    aa_truth_stats st;
    oracle_crow p = oracle_params(pattern);
    reference(pattern, w, h, filter, 0, &img, &bound, &st);
    double worst = 0, worst_ratio = 0;
    int checked = 0;
    for (int j = 0; j < h; j += 3)
        for (int i = (j * 7) % 5; i < w; i += 5) {
            double err, want = gauss ? oracle_crow_gauss(&p, w, h, i, j, r, &err)
                                     : oracle_crow_tent(&p, w, h, i, j, r, &err);
            double got = aa_pixel(&img, i, j)[0], d = fabs(got - want);
            double allowed = err + *aa_pixel(&bound, i, j);
            if (!(d <= allowed))
                fail_msg("%s %s pixel (%d, %d): reference %.17g, brute force %.17g +- %.2e", pattern,
                         filter, i, j, got, want, err);
            worst = fmax(worst, d);
            worst_ratio = fmax(worst_ratio, d / allowed);
            checked++;
        }
    print_message("%-40s %4dx%-4d %-12s: %d pixels, max |ref - brute| %.2e (at most %.0f%% of "
                  "the brute force's error estimate), max bound %.2e\n",
                  pattern, w, h, filter, checked, worst, 100 * worst_ratio, st.max_bound);
    assert_true(st.max_bound <= AA_TRUTH_BOUND);
    aa_image_free(&img);
    aa_image_free(&bound);
}

static void test_crow_tent(void **state)
{
    (void)state;
    check_filtered("crow", 64, 64, "tent:r=0.5", 0.5, 0);
    check_filtered("crow", 64, 64, "tent:r=1", 1.0, 0);
    check_filtered("crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", 47, 31, "tent:r=1.5", 1.5, 0);
}

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) two cases run a declared subset: test_crow_gauss crow
 * under gauss:s=1 alone (not also under the default width: the same paths
 * with other numbers), and test_crowd_against_spans crow and the fence under
 * the cone at 12x10 px, not 24x20 (the same scenes under the same filter,
 * fewer pixels), every other view as in the plain build.  The sanitizers
 * find memory and undefined-behaviour errors along the paths taken
 * (tests/README.md, "Tiers", says how that was checked); the plain build
 * runs every case. */

static void test_crow_gauss(void **state)
{
    (void)state;
    if (!SAN_SUBSET)
        check_filtered("crow", 64, 64, "gauss", 0.5, 1);
    check_filtered("crow", 48, 40, "gauss:s=1", 1.0, 1);
}

/* Pixels that no arc enters are exactly 0 or 1 and match the pattern. */
static void test_uniform_exact(void **state)
{
    (void)state;
    const int w = 256, h = 256;
    aa_image img;
    aa_truth_stats st;
    oracle_crow p = oracle_params("crow");
    reference("crow", w, h, "box", 1, &img, NULL, &st);
    int inside = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            /* no arc meets the pixel iff the colour at its four corners and
             * the arcs' extents say so: test with a dense grid of points
             * instead, independently of the scene code */
            int first = oracle_crow_point(&p, (i + 0.5) / w, (j + 0.5) / h), same = 1;
            for (int a = 0; a <= 16 && same; a++)
                for (int b = 0; b <= 16 && same; b++)
                    same = oracle_crow_point(&p, (i + a / 16.0) / w, (j + b / 16.0) / h) == first;
            if (!same)
                continue;
            /* a 16x16 grid can miss a sliver: confirm with the closed form */
            if (oracle_crow_box(&p, w, h, i, j) != first)
                continue;
            inside++;
            assert_true(aa_pixel(&img, i, j)[0] == (double)first);
        }
    print_message("%d pixels wholly inside a band or the background, all exactly 0 or 1\n", inside);
    assert_true(inside > 30000);
    aa_image_free(&img);
}

static void test_threads_identical(void **state)
{
    (void)state;
    const char *filters[] = {"box", "tent:r=1", "gauss"};
    for (int k = 0; k < 3; k++) {
        aa_image a, b;
        aa_truth_stats st;
        reference("crow", 97, 61, filters[k], 1, &a, NULL, &st);
        reference("crow", 97, 61, filters[k], 2, &b, NULL, &st);
        assert_memory_equal(a.v, b.v, sizeof(double) * 97 * 61 * 3);
        aa_image_free(&a);
        aa_image_free(&b);
    }
}

/* ---- polygons against an independent clipper ---- */

/* Two convex polygons in two layers, the front one red over a white one
 * behind, on grey: the box value per pixel is grey + (red - grey) A_front
 * + (white - grey) (A_back - A_overlap), with the overlap the back polygon
 * clipped by the front one's edges (both convex). */
static void test_polygon_layers(void **state)
{
    (void)state;
    const int w = 23, h = 17;
    const oracle_poly front = {3, {0.13, 0.81, 0.37}, {0.21, 0.33, 0.92}};
    const oracle_poly back = {5, {0.4, 0.95, 0.9, 0.6, 0.35}, {0.05, 0.2, 0.7, 0.85, 0.5}};
    const aa_rgb red = {{1, 0, 0}}, grey = {{0.25, 0.25, 0.25}};
    aa_scene *s = aa_scene_new(grey);
    const oracle_poly *polys[2] = {&front, &back};
    aa_rgb colours[2] = {red, white};
    for (int l = 0; l < 2; l++) {
        assert_int_equal(aa_scene_layer(s, colours[l], AA_FILL_NONZERO), AA_OK);
        scenes_add_poly(s, polys[l]);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    aa_truth_stats st;
    support_reference(s, &(support_view){.w = w, .h = h}, &img, NULL, &st);
    /* the overlap: back clipped to the inside of front */
    const oracle_poly overlap = oracle_poly_intersect(&back, &front);
    /* pattern units: the pixel is the square of side 1/w by 1/h; scale y so
     * the pixel is square in a stretched copy */
    const oracle_poly fs = oracle_poly_scaled(&front, w, h), bs = oracle_poly_scaled(&back, w, h);
    const oracle_poly os = oracle_poly_scaled(&overlap, w, h);
    double worst = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double af = oracle_poly_area_in_rect(&fs, i, j, i + 1, j + 1);
            double ab = oracle_poly_area_in_rect(&bs, i, j, i + 1, j + 1);
            double ao = oracle_poly_area_in_rect(&os, i, j, i + 1, j + 1);
            for (int c = 0; c < 3; c++) {
                double want = grey.c[c] + (red.c[c] - grey.c[c]) * af +
                              (white.c[c] - grey.c[c]) * (ab - ao);
                double d = fabs(aa_pixel(&img, i, j)[c] - want);
                worst = fmax(worst, d);
                if (d > 1e-12)
                    fail_msg("pixel (%d, %d) channel %d: %.17g, clipper %.17g", i, j, c,
                             aa_pixel(&img, i, j)[c], want);
            }
        }
    print_message("two polygon layers 23x17: max |ref - clipper| %.2e\n", worst);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* Catmull 1978, fig. 1: "The correct integration would be 25% green, 25%
 * black, 50% blue and no red": the pixel is (0, 0.25, 0.5). */
static void test_catmull_pixel(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    double rects[3][4] = {{0, 0, 0.5, 0.5}, {0, 0.5, 1, 1}, {0.1, 0.1, 0.45, 0.9}};
    aa_rgb colours[3] = {{{0, 1, 0}}, {{0, 0, 1}}, {{1, 0, 0}}};
    for (int l = 0; l < 3; l++) {
        const double *r = rects[l];
        assert_int_equal(aa_scene_layer(s, colours[l], AA_FILL_NONZERO), AA_OK);
        scenes_rect(s, r[0], r[1], r[2], r[3]);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    support_reference(s, &(support_view){.w = 1, .h = 1, .threads = 1}, &img, NULL, NULL);
    assert_true(fabs(img.v[0]) < 1e-15 && fabs(img.v[1] - 0.25) < 1e-15 &&
                fabs(img.v[2] - 0.5) < 1e-15);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* The segment between the chord and the quadratic arc (0.1,0.9)-(0.5,-0.3)-
 * (0.9,0.9) has 2/3 of the control triangle's area (Archimedes): the
 * triangle has base 0.8 and height 1.2, area 0.48, so the segment 0.32. */
static void test_parabolic_segment(void **state)
{
    (void)state;
    aa_scene *s = scenes_arc_segment(0.1, 0.9, 0.5, -0.3, 0.9, 0.9);
    aa_image img;
    aa_truth_stats st;
    /* the whole image as one pixel, and summed over 13 x 11 pixels */
    int sizes[2][2] = {{1, 1}, {13, 11}};
    for (int k = 0; k < 2; k++) {
        support_reference(s, &(support_view){.w = sizes[k][0], .h = sizes[k][1]}, &img, NULL, &st);
        assert_true(fabs(support_channel_mean(&img, 0) - 0.32) < 1e-13);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* Two shapes, each a general quadratic arc (y not linear in its
 * parameter) closed by its chord, that cross: a shape's area is 2/3 of its
 * control triangle (Archimedes), and with both shapes in one layer drawn the
 * same way round, nonzero fill covers A1 + A2 - A(both) and even-odd
 * A1 + A2 - 2 A(both), so 2 T(nonzero) - T(even-odd) = A1 + A2 whatever the
 * overlap: a check of the crossings that needs no crossing to be known. */
static double shapes_total(int rule, int w, int h, double *max_bound)
{
    const double s1[6] = {0.2, 0.2, 0.95, 0.3, 0.2, 0.8}, s2[6] = {0.7, 0.15, 0.05, 0.6, 0.75, 0.85};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, rule), AA_OK);
    const double *sh[2] = {s1, s2};
    for (int k = 0; k < 2; k++) {
        /* the second arc bulges left: trace it the other way so both
         * shapes run the same way round */
        const double *a = sh[k];
        if (k == 0) {
            assert_int_equal(aa_scene_move_to(s, a[0], a[1]), AA_OK);
            assert_int_equal(aa_scene_quad_to(s, a[2], a[3], a[4], a[5]), AA_OK);
        } else {
            assert_int_equal(aa_scene_move_to(s, a[4], a[5]), AA_OK);
            assert_int_equal(aa_scene_quad_to(s, a[2], a[3], a[0], a[1]), AA_OK);
        }
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    aa_truth_stats st;
    support_reference(s, &(support_view){.w = w, .h = h}, &img, NULL, &st);
    double mean = support_channel_mean(&img, 0);
    *max_bound = st.max_bound;
    aa_image_free(&img);
    aa_scene_free(s);
    return mean;
}

static double triangle(const double *a)
{
    return 0.5 * fabs((a[2] - a[0]) * (a[5] - a[1]) - (a[4] - a[0]) * (a[3] - a[1]));
}

static void test_crossing_arcs(void **state)
{
    (void)state;
    const double s1[6] = {0.2, 0.2, 0.95, 0.3, 0.2, 0.8}, s2[6] = {0.7, 0.15, 0.05, 0.6, 0.75, 0.85};
    double want = 2.0 / 3.0 * (triangle(s1) + triangle(s2));
    int sizes[3][2] = {{1, 1}, {17, 13}, {64, 48}};
    for (int k = 0; k < 3; k++) {
        double bn, be;
        double nz = shapes_total(AA_FILL_NONZERO, sizes[k][0], sizes[k][1], &bn);
        double eo = shapes_total(AA_FILL_EVENODD, sizes[k][0], sizes[k][1], &be);
        print_message("crossing arcs %dx%d: 2 T(nonzero) - T(even-odd) - (A1 + A2) = %.2e "
                      "(overlap %.6f), max bounds %.1e %.1e\n",
                      sizes[k][0], sizes[k][1], 2 * nz - eo - want, nz - eo, bn, be);
        assert_true(nz - eo > 0.01); /* they do overlap */
        assert_true(fabs(2 * nz - eo - want) < 1e-12);
        assert_true(bn <= AA_TRUTH_BOUND && be <= AA_TRUTH_BOUND);
    }
}

/* Random scenes of three shapes, each two general quadratic arcs (y not
 * linear in their parameter), crossing each other and turning inside
 * pixels: the reference must lie within its own bound (plus 1e-12) of
 * `area` (algorithms/area.c), an exact method derived independently (cell
 * accumulation and clipping, not quadrature).  300 seeded scenes; this
 * caught QAGP's extrapolation returning values 2.6e-7 off with bounds of
 * 1e-14, and missing arc-arc breakpoints (2.6e-5). */
static void random_arcs_against_area(int mode)
{
    aa_filter f;
    aa_filter_default(&f);
    int bad = 0;
    double worst = 0;
    for (int sc = 0; sc < 300; sc++) {
        aa_rng r;
        aa_rng_seed(&r, 99, (uint64_t)sc, 0);
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, sc % 2 ? AA_FILL_EVENODD : AA_FILL_NONZERO), AA_OK);
        for (int k = 0; k < 3; k++) {
            double p[8];
            for (int q = 0; q < 8; q++)
                p[q] = 0.05 + 0.9 * aa_rng_uniform(&r);
            assert_int_equal(aa_scene_move_to(s, p[0], p[1]), AA_OK);
            assert_int_equal(aa_scene_quad_to(s, p[2], p[3], p[4], p[5]), AA_OK);
            assert_int_equal(aa_scene_quad_to(s, p[6], p[7], p[0], p[1]), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref, img, bound;
        aa_counters c;
        aa_scene *placed = aa_scene_place(s, 12, 12, 0, 0, 0);
        assert_non_null(placed);
        assert_int_equal(aa_image_alloc(&ref, 12, 12, 3), AA_OK);
        assert_int_equal(aa_image_alloc(&bound, 12, 12, 1), AA_OK);
        assert_int_equal(aa__truth_render_mode(placed, &f, 1, mode, &ref, &bound, NULL, NULL),
                         AA_OK);
        aa_scene_free(placed);
        support_render("area", s, NULL, 12, 12, 1, &img, &c);
        for (int p = 0; p < 144; p++) {
            double d = fabs(ref.v[3 * p] - img.v[3 * p]);
            worst = fmax(worst, d);
            if (d > bound.v[p] + 1e-12) {
                if (bad++ < 5)
                    print_message("scene %d pixel %d: reference %.15f (bound %.1e), area %.15f\n",
                                  sc, p, ref.v[3 * p], bound.v[p], img.v[3 * p]);
            }
            assert_true(bound.v[p] <= AA_TRUTH_BOUND);
        }
        aa_image_free(&ref);
        aa_image_free(&img);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
    print_message("300 random scenes of crossing arcs%s: max |reference - area| %.2e, %d pixels "
                  "beyond the reference's bound\n", mode == AA__TRUTH_CROWD ? " (one piece at a time)" : "",
                  worst, bad);
    assert_int_equal(bad, 0);
}

static void test_random_arcs_against_area(void **state)
{
    (void)state;
    random_arcs_against_area(0);
}

static void test_cache(void **state)
{
    (void)state;
    char dir[256];
    assert_int_equal(support_tmpdir(dir, sizeof dir, "cache"), 0);
    aa_view v;
    memset(&v, 0, sizeof v);
    assert_int_equal(aa_pattern_parse("crow", &v.pattern), AA_OK);
    assert_int_equal(aa_filter_parse("tent:r=0.5", &v.filter), AA_OK);
    v.w = 40, v.h = 30;
    aa_image a, b;
    int hit;
    assert_int_equal(aa_reference(&v, dir, 0, &a, NULL, &hit), AA_OK);
    assert_int_equal(hit, 0);
    assert_int_equal(aa_reference(&v, dir, 0, &b, NULL, &hit), AA_OK);
    assert_int_equal(hit, 1);
    assert_memory_equal(a.v, b.v, sizeof(double) * 40 * 30 * 3);
    aa_image_free(&b);
    /* damage the file: cut it short; the next call recomputes */
    char cmd[512];
    snprintf(cmd, sizeof cmd, "for f in '%s'/*.bin; do truncate -s 100 \"$f\"; done", dir);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(aa_reference(&v, dir, 0, &b, NULL, &hit), AA_OK);
    assert_int_equal(hit, 0);
    assert_memory_equal(a.v, b.v, sizeof(double) * 40 * 30 * 3);
    aa_image_free(&b);
    /* another time is another image */
    v.t = 1, v.vx = 0.5;
    assert_int_equal(aa_reference(&v, dir, 0, &b, NULL, &hit), AA_OK);
    assert_int_equal(hit, 0);
    aa_image_free(&a);
    aa_image_free(&b);
    assert_int_equal(support_rmtree(dir), 0);
}

/* ---- crowded pixels: one piece at a time (truth_crowd.c) ---- */

/* A moderately pathological crow, thousands of arcs 1e-5 pattern units
 * apart (a pixel crossed by all of them: the sum over spans cost the
 * square of the arcs, 18 s for these 4x4), against tests/oracle.c's closed
 * form: every pixel within 1e-12, every bound within AA_TRUTH_BOUND, every
 * integrated pixel taken one piece at a time, 1 and 2 threads identical.
 * The closed form is of the pattern as defined; the scene's arcs are placed
 * by sums in double, which drift from it by about 1e-16 per arc (the same
 * on the sum over spans: 7e-14 here, 6e-13 at 65536 arcs on one pixel). */
static void check_crowd_box(const char *pattern, int w, int h)
{
    aa_image img, one, bound;
    aa_truth_stats st, st1;
    oracle_crow p = oracle_params(pattern);
    reference(pattern, w, h, "box", 2, &img, &bound, &st);
    reference(pattern, w, h, "box", 1, &one, NULL, &st1);
    assert_memory_equal(img.v, one.v, sizeof(double) * (size_t)w * (size_t)h * 3);
    double worst = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double want = oracle_crow_box(&p, w, h, i, j), *px = aa_pixel(&img, i, j);
            double d = fabs(px[0] - want);
            worst = fmax(worst, d);
            if (d > 1e-12 || px[1] != px[0] || px[2] != px[0])
                fail_msg("%s %dx%d pixel (%d, %d): reference %.17g, closed form %.17g", pattern,
                         w, h, i, j, px[0], want);
            assert_true(*aa_pixel(&bound, i, j) <= AA_TRUTH_BOUND);
        }
    print_message("%-52s %2dx%-2d box: max |ref - closed form| %.2e, max bound %.2e, %zu of %zu "
                  "integrated pixels crowded\n",
                  pattern, w, h, worst, st.max_bound, st.crowded, st.integrated);
    assert_true(st.crowded > 0); /* pixels at the pattern's edges may hold few arcs */
    aa_image_free(&img);
    aa_image_free(&one);
    aa_image_free(&bound);
}

static void test_crowd_crow_oracle(void **state)
{
    (void)state;
    check_crowd_box("crow:curves=2048,gap0=1e-5,gap1=1e-5,kmax=0.05", 4, 4);
    check_crowd_box("crow:curves=2048,gap0=1e-5,gap1=1e-5,kmax=0.05", 16, 16);
    /* wider and more curved: arcs cross the windows' sides at every height */
    check_crowd_box("crow:curves=1024,gap0=2e-4,gap1=5e-5,kmax=0.15", 13, 11);
    check_crowd_box("crow:curves=1024,gap0=2e-4,gap1=5e-5,kmax=-0.3", 9, 12);
}

/* Every non-uniform pixel one piece at a time against the sum over spans
 * (AA__TRUTH_QAG), two derivations that share the crossings only: within
 * the sum of their bounds, on scenes with vertices, horizontal edges,
 * layers and shared edges, crossing paths, and every filter.  (Not slivers
 * under the cone: there the sum over spans is off by up to 3e-13 while its
 * estimate says 5e-15, where a nearly horizontal edge passes the cone's
 * centre; one piece at a time agrees with a brute-force integration to
 * 1e-16.) */
static void test_crowd_against_spans(void **state)
{
    (void)state;
    const char *views[][2] = {
        {"crow", "box"},
        {"crow", "tent:r=1"},
        {"crow", "cone"},
        {"crow", "gauss:s=0.3"},
        {"crow:curves=10,kmax=0.5,gap0=0.2,gap1=0.05", "box"},
        {"feibush", "box"},
        {"feibush", "cone"},
        {"star", "tent:r=1"},
        {"star:spokes=200", "box"},
        {"catmull:tiles=3", "cone"},
        {"fence", "cone"},
        {"dots:n=40,size=0.02", "cone"},
    };
    for (size_t v = 0; v < sizeof views / sizeof *views; v++) {
        /* crow and the fence under the cone at 12x10 px in the subset */
        int w = SAN_SUBSET && (v == 2 || v == 10) ? 12 : 24, h = w * 5 / 6;
        aa_spec spec;
        aa_filter f;
        aa_scene *s, *placed;
        aa_image a, b, ba, bb;
        aa_truth_stats sa, sb;
        assert_int_equal(aa_pattern_parse(views[v][0], &spec), AA_OK);
        assert_int_equal(aa_filter_parse(views[v][1], &f), AA_OK);
        assert_int_equal(aa_pattern_scene(&spec, &s), AA_OK);
        assert_non_null(placed = aa_scene_place(s, w, h, 0, 0, 0));
        assert_int_equal(aa_image_alloc(&a, w, h, 3), AA_OK);
        assert_int_equal(aa_image_alloc(&b, w, h, 3), AA_OK);
        assert_int_equal(aa_image_alloc(&ba, w, h, 1), AA_OK);
        assert_int_equal(aa_image_alloc(&bb, w, h, 1), AA_OK);
        assert_int_equal(aa__truth_render_mode(placed, &f, 0, AA__TRUTH_QAG, &a, &ba, &sa, NULL),
                         AA_OK);
        assert_int_equal(aa__truth_render_mode(placed, &f, 0, AA__TRUTH_CROWD, &b, &bb, &sb, NULL),
                         AA_OK);
        assert_int_equal(sb.crowded, sb.integrated);
        double worst = 0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double lim = *aa_pixel(&ba, i, j) + *aa_pixel(&bb, i, j);
                assert_true(*aa_pixel(&bb, i, j) <= AA_TRUTH_BOUND);
                for (int ch = 0; ch < 3; ch++) {
                    double d = fabs(aa_pixel(&a, i, j)[ch] - aa_pixel(&b, i, j)[ch]);
                    worst = fmax(worst, d);
                    if (!(d <= lim))
                        fail_msg("%s %s pixel (%d, %d) channel %d: spans %.17g, pieces %.17g, "
                                 "bounds %.1e", views[v][0], views[v][1], i, j, ch,
                                 aa_pixel(&a, i, j)[ch], aa_pixel(&b, i, j)[ch], lim);
                }
            }
        print_message("%-44s %-11s max |spans - pieces| %.2e, bounds %.1e %.1e\n", views[v][0],
                      views[v][1], worst, sa.max_bound, sb.max_bound);
        aa_image_free(&a);
        aa_image_free(&b);
        aa_image_free(&ba);
        aa_image_free(&bb);
        aa_scene_free(placed);
        aa_scene_free(s);
    }
}

/* The random scenes of crossing general arcs again, one piece at a time:
 * meetings of arcs (found by the sweep as neighbours), turning points,
 * pieces ending inside pixels. */
static void test_crowd_random_arcs(void **state)
{
    (void)state;
    random_arcs_against_area(AA__TRUTH_CROWD);
}

/* The long double Gauss-Kronrod pass against the integrals of monomials,
 * int_a^b x^k dx = (b^(k+1) - a^(k+1))/(k+1): K21 is exact to degree 31
 * and G10 to degree 19, so |K21 - G10| is rounding up to degree 19 and not
 * at degree 20 (where G10's error on [-1, 1] is 2^21 (10!)^4 / (21 (20!)^3)
 * times the 20th derivative / 20!, about 1.4e-6 here). */
static long double monomial(long double x, const void *ctx)
{
    int k = *(const int *)ctx;
    long double p = 1;
    for (int q = 0; q < k; q++)
        p *= x;
    return p;
}

static void test_crowd_rule(void **state)
{
    (void)state;
    const long double ends[3][2] = {{-1, 1}, {0, 3}, {-0.25L, 0.5L}};
    /* double's epsilon where long double is computed in double (valgrind) */
    const long double eps = aa_long_double_is_extended() ? LDBL_EPSILON : DBL_EPSILON;
    for (int e = 0; e < 3; e++)
        for (int k = 0; k <= 31; k++) {
            long double a = ends[e][0], b = ends[e][1], r, err, raw, fl, pa = a, pb = b;
            for (int q = 0; q < k; q++)
                pa *= a, pb *= b;
            long double want = (pb - pa) / (k + 1);
            aa__truth_gk21l(monomial, &k, a, b, &r, &err, &raw, &fl);
            long double scale = fmaxl(1, fabsl(want));
            if (!(fabsl(r - want) <= 64 * eps * scale * powl(3, k) / (k + 1)))
                fail_msg("x^%d on [%Lg, %Lg]: K21 %.21Lg, exact %.21Lg", k, a, b, r, want);
            if (k <= 19)
                assert_true(raw <= 64 * eps * scale * powl(3, k));
            if (e == 0 && k == 20)
                assert_true(raw > 1e-7); /* G10 is not exact there */
        }
}

/* The progress hook: calls with pixels done, non-decreasing, ending with
 * the total; none once unset. */
typedef struct progress_log {
    size_t calls, last, total, within;
    int backwards;
} progress_log;

static void log_progress(void *ctx, size_t done, size_t total)
{
    progress_log *p = ctx;
    p->backwards |= done < p->last;
    p->calls++;
    p->within += done < total;
    p->last = done;
    p->total = total;
}

static void test_progress(void **state)
{
    (void)state;
    progress_log log = {0, 0, 0, 0, 0};
    aa_image img;
    aa_truth_stats st;
    aa_truth_set_progress(log_progress, &log);
    reference("crow", 64, 48, "box", 2, &img, NULL, &st);
    aa_truth_set_progress(NULL, NULL);
    aa_image_free(&img);
    assert_true(log.calls >= 1);
    assert_int_equal(log.total, 64 * 48);
    assert_int_equal(log.last, 64 * 48);
    assert_false(log.backwards);
    size_t calls = log.calls;
    reference("crow", 16, 16, "box", 2, &img, NULL, &st);
    aa_image_free(&img);
    assert_int_equal(log.calls, calls);
}

/* Progress within a row: a pixel of a crowded window can take seconds and a
 * row of them minutes (a thumbnail of a dense drawing), so the hook hears
 * of pixels as they are done, not of rows at their end.  One row of crow
 * at 64 px, no least time between calls: a call for each pixel integrated
 * or run of uniform ones before the last, each after the one before.  Told
 * of rows only, the hook was called once, with the total. */
static void test_progress_pixels(void **state)
{
    (void)state;
    progress_log log = {0, 0, 0, 0, 0};
    aa_image img;
    aa_truth_stats st;
    aa_truth_set_progress(log_progress, &log);
    aa__truth_set_progress_interval(0.0);
    reference("crow", 64, 1, "box", 1, &img, NULL, &st);
    aa__truth_set_progress_interval(0.1);
    aa_truth_set_progress(NULL, NULL);
    aa_image_free(&img);
    print_message("progress in one row of 64 pixels: %zu calls, %zu before the total (%zu "
                  "pixels integrated)\n",
                  log.calls, log.within, st.integrated);
    assert_true(st.integrated >= 8);
    assert_true(log.within >= st.integrated - 1);
    assert_int_equal(log.total, 64);
    assert_int_equal(log.last, 64);
    assert_false(log.backwards);
}

/* Many overlapping layers (more than CROWD_WL_LAYERS, past which the
 * crowded sweep keeps no winding numbers per piece): n rectangles W x H
 * px, each dx right and dy down of the one before, of distinct colours,
 * on a 40x20 canvas, under the tent and the cubic B-spline, both paths
 * (crowded pixels in the default mode, every pixel in AA__TRUTH_CROWD).
 * Known answers from the geometry alone:
 *  - the filters are non-negative, so each pixel is a convex combination
 *    of the colours present: within [min, max] of them per channel;
 *  - both filters' translates by whole pixels sum to 1 (a partition of
 *    unity) over every point whose support's pixel centres lie in the
 *    canvas, which holds the rectangles ([2, 38] x [4, 18] px, radius at
 *    most 2), so the image's sum less the background's equals the
 *    integral of the picture less the background: sum over layers of
 *    (colour - background) times its visible area.  Layers go front to
 *    back (core.h), and every rectangle before k meets rectangle k inside
 *    rectangle k - 1 (their corners move right and down together), so k's
 *    visible area is W H - (W - dx)(H - dy), and the first one's W H.
 * The sweep once walked only from the first changed piece when the colour
 * left of the window changed, leaving the jumps to its left stale: values
 * down to -1.4. */
static void test_crowd_many_layers(void **state)
{
    (void)state;
    const char *const filters[] = {"tent:r=1", "bspline:order=3"};
    const int counts[] = {17, 40, 300};
    const int w = 40, h = 20;
    const aa_rgb bg = {{0.1, 0.2, 0.3}};
    for (size_t q = 0; q < sizeof counts / sizeof *counts; q++) {
        int n = counts[q];
        aa_scene *s = aa_scene_new(bg), *placed;
        assert_non_null(s);
        double want[3] = {0, 0, 0}, lo[3], hi[3];
        /* in pixels: W = 0.1 w, H = 0.4 h, dx = 0.8 w / n, dy = 0.3 h / n */
        double W = 0.1 * w, H = 0.4 * h, dx = 0.8 * w / n, dy = 0.3 * h / n;
        for (int ch = 0; ch < 3; ch++)
            lo[ch] = hi[ch] = bg.c[ch];
        for (int k = 0; k < n; k++) {
            aa_rgb c = {{(k % 7) / 7.0, (k % 11) / 11.0, k / (double)n}};
            double x0 = 0.05 + 0.8 * k / n, x1 = x0 + 0.1, y0 = 0.2 + 0.3 * k / n,
                   y1 = y0 + 0.4;
            assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x1, y0), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x1, y1), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x0, y1), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
            double area = k > 0 ? W * H - (W - dx) * (H - dy) : W * H;
            for (int ch = 0; ch < 3; ch++) {
                want[ch] += (c.c[ch] - bg.c[ch]) * area;
                lo[ch] = fmin(lo[ch], c.c[ch]);
                hi[ch] = fmax(hi[ch], c.c[ch]);
            }
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        assert_non_null(placed = aa_scene_place(s, w, h, 0, 0, 0));
        for (size_t fi = 0; fi < sizeof filters / sizeof *filters; fi++)
            for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD) {
                aa_filter f;
                aa_image img;
                aa_truth_stats st;
                assert_int_equal(aa_filter_parse(filters[fi], &f), AA_OK);
                assert_int_equal(aa_image_alloc(&img, w, h, 3), AA_OK);
                assert_int_equal(aa__truth_render_mode(placed, &f, 1, mode, &img, NULL, &st, NULL),
                                 AA_OK);
                double worst = 0;
                for (int ch = 0; ch < 3; ch++) {
                    double sum = 0;
                    for (int j = 0; j < h; j++)
                        for (int i = 0; i < w; i++) {
                            double v = aa_pixel(&img, i, j)[ch];
                            if (v < lo[ch] - 1e-12 || v > hi[ch] + 1e-12)
                                fail_msg("%d layers under %s, mode %d: pixel (%d, %d) channel "
                                         "%d is %.17g, outside the colours' [%g, %g]",
                                         n, filters[fi], mode, i, j, ch, v, lo[ch], hi[ch]);
                            sum += v - bg.c[ch];
                        }
                    worst = fmax(worst, fabs(sum - want[ch]));
                }
                print_message("%3d layers %-16s %s: |sum - integral| %.1e, %zu of %zu "
                              "integrated pixels crowded\n",
                              n, filters[fi], mode ? "all crowded" : "default    ", worst,
                              st.crowded, st.integrated);
                /* 800 pixels, each within 1e-12 */
                assert_true(worst <= (double)w * h * AA_TRUTH_BOUND);
                /* the default mode takes some of 300 layers' windows one piece at a time */
                assert_true(mode ? st.crowded == st.integrated : n < 300 || st.crowded > 0);
                aa_image_free(&img);
            }
        aa_scene_free(placed);
        aa_scene_free(s);
    }
}

/* the cases this build runs (SAN_SUBSET, above), said first */
static int say_cases(void **state)
{
    (void)state;
    SAN_CASES_PRINT();
    return 0;
}

SUPPORT_MAIN(say_cases, NULL,
             cmocka_unit_test(test_crow_box_default),
             cmocka_unit_test(test_crow_box_other),
             cmocka_unit_test(test_crow_tent),
             cmocka_unit_test(test_crow_gauss),
             cmocka_unit_test(test_uniform_exact),
             cmocka_unit_test(test_threads_identical),
             cmocka_unit_test(test_polygon_layers),
             cmocka_unit_test(test_catmull_pixel),
             cmocka_unit_test(test_parabolic_segment),
             cmocka_unit_test(test_crossing_arcs),
             cmocka_unit_test(test_random_arcs_against_area),
             cmocka_unit_test(test_cache),
             cmocka_unit_test(test_crowd_crow_oracle),
             cmocka_unit_test(test_crowd_against_spans),
             cmocka_unit_test(test_crowd_many_layers),
             cmocka_unit_test(test_crowd_random_arcs),
             cmocka_unit_test(test_crowd_rule),
             cmocka_unit_test(test_progress),
             cmocka_unit_test(test_progress_pixels))
