/*
 * test_analytic.c: `analytic`, the analytic rasterization of Manson and
 * Schaefer 2013 under the separable piecewise polynomial filters.
 *
 * Known answers, none from the method itself:
 *  - the exact reference of the harness's separate truth path
 *    (aa_truth_render, its own quadrature of the filter over the scene's
 *    rows), within 1e-12 per pixel, on crow (quadratic arcs), crow with its
 *    arcs raised to cubics, the cubic scene of scenes.c, star, slivers,
 *    catmull, feibush (several layers), the shipped SVG scenes with quadratic
 *    and cubic arcs and abutting or coincident paths, and two overlapping
 *    layers built here (a self-crossing even-odd cubic path in front of a
 *    nonzero path of two crossing loops of quadratic arcs), that layer
 *    with loops sharing their end points (tangent at one) and with a loop
 *    traced twice, under every filter the method takes; elliptical arcs:
 *    arcs.svg (a circle, an ellipse under a rotation and a scale, a
 *    rounded rectangle, paths of `A` and `a`, an even-odd ring), circles,
 *    turned ellipses, a pie slice and a circle 0.3 px in radius in one
 *    layer and in two overlapping, circles of radius 1e4 and 1e6 px;
 *    curves.svg at 48 px under box, tent:r=1 and bspline:order=3 (a
 *    cubic's cuts found from the neighbouring cut's root, test_cubic_cuts);
 *  - no meeting between two arcs leaving a common end point with a common
 *    control point: at equal parameters their heights agree and their x
 *    differ by t^2 times the difference of their other ends;
 *  - closed forms: a white region on black filtered by a filter whose
 *    integer translates sum to 1 (box, tent:r=1, the B-splines,
 *    Mitchell-Netravali for any B and C, Catmull-Rom) sums, over an image
 *    holding its whole filtered support, to its area: a parabolic segment is
 *    2/3 of its control triangle (Archimedes), and the region under
 *    y = x^3 over [0, 1], the cubic Bezier (0,0) (1/3,0) (2/3,0) (1,1),
 *    has area 1/4, scaled; a disk of radius r, pi r^2, and an ellipse of
 *    semi-axes a, b turned, pi a b (placed: times the view's w h);
 *  - refusals by name: filters that are not piecewise polynomial (the
 *    radial polynomials: tests/test_analytic_radial.c).
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

#include <cmocka.h>

static const char *const filters[] = {"box",         "tent:r=1", "tent:r=0.65", "bspline:order=2",
                                      "bspline:order=3", "mitchell", "mitchell:b=0.2,c=0.7",
                                      "catrom",      NULL};

/* The quick tier takes every filter on crow and one filter a scene (in
 * turn) elsewhere, at smaller sizes; test_analytic_full.c, of the full tier,
 * is this file with ANALYTIC_ALL set: every scene under every filter.  The
 * full tier leaves out what the quick tier checks the same way (crow, the
 * loops of test_shared_ends, and the cases that do not depend on the tier:
 * main below): `make test` runs both tiers, and the same case twice would
 * check nothing more. */
#ifndef ANALYTIC_ALL
#define ANALYTIC_ALL 0
#endif
#define NFILTERS 8

/* Fails where analytic's image a is more than 1e-12 from the reference r;
 * prints the largest difference. */
static void within_reference(const char *what, const char *f, const aa_image *a,
                             const aa_image *r)
{
    double worst = support_within_reference(what, f, a, r, 1e-12);
    print_message("%-24s %-22s largest difference %.1e\n", what, f, worst);
}

/* The largest difference between analytic and the reference on a scene
 * (pattern units) at w x h under every filter (all = 1) or under one, in
 * turn from call to call (quick tier); fails over 1e-12.  sized: the scene
 * is drawn at the view's size (svg), w x h is its size in every tier. */
static void against_reference(const char *what, const aa_scene *s, int w, int h, int all,
                              int sized)
{
    static int turn;
    if (!ANALYTIC_ALL && !all && !sized) { /* smaller (a scene drawn at its size stays) */
        int q = 3 * w / 4;
        h = h * q / w;
        w = q;
    }
    for (int fi = 0; fi < NFILTERS; fi++) {
        const char *const *f = &filters[fi];
        if (!ANALYTIC_ALL && !all && fi != turn % NFILTERS)
            continue;
        aa_image a, r;
        support_render("analytic", s, *f, w, h, 2, &a, NULL);
        support_reference(s, &(support_view){.w = w, .h = h, .filter = *f, .threads = 1}, &r,
                          NULL, NULL);
        within_reference(what, *f, &a, &r);
        aa_image_free(&a);
        aa_image_free(&r);
    }
    turn++;
}

static void test_patterns(void **state)
{
    (void)state;
    const char *const specs[] = {"crow", "star", "slivers", "catmull:tiles=4", "feibush", NULL};
    for (const char *const *p = specs; *p; p++) {
        int crow = !strcmp(*p, "crow");
        if (ANALYTIC_ALL && crow) /* every filter at 32 x 30 in the quick tier */
            continue;
        aa_scene *s = scenes_pattern(*p);
        against_reference(*p, s, crow ? 32 : 24, crow ? 30 : 24, crow, 0);
        aa_scene_free(s);
    }
}

static void test_cubics(void **state)
{
    (void)state;
    aa_scene *crow = scenes_pattern("crow");
    aa_scene *up = scenes_elevated(crow);
    against_reference("crow raised to cubics", up, 32, 32, 0, 0);
    aa_scene *c = scenes_cubics();
    against_reference("cubic arcs", c, 26, 22, 0, 0);
    aa_scene_free(c);
    aa_scene_free(up);
    aa_scene_free(crow);
}

static void test_svg(void **state)
{
    (void)state;
    const char *const files[] = {"curves", "shapes", "logo", "mono", "abut", "coincident", "arcs",
                                 NULL};
    for (const char *const *f = files; *f; f++) {
        /* drawn at the view's size */
        int n = ANALYTIC_ALL ? 28 : 20;
        aa_scene *s = scenes_svg_at(*f, n);
        against_reference(*f, s, n, n, 0, 1);
        aa_scene_free(s);
    }
}

/* A self-crossing even-odd path of cubic arcs in front of a nonzero path of
 * two crossing loops of quadratic arcs (wound twice where they overlap), in
 * colours apart in every channel. */
static void test_overlapping_layers(void **state)
{
    (void)state;
    aa_scene *s = scenes_overlapping_layers();
    against_reference("overlapping layers", s, 27, 25, 0, 0);
    aa_scene_free(s);
}

#if !ANALYTIC_ALL /* the cases the same in both tiers (main) */
/* curves.svg drawn at 48 px under box, tent:r=1 and bspline:order=3: a
 * cubic's cuts at the knots' lines are found by Newton's method from the
 * neighbouring line's root, and on the lens's halves (of a symmetric arc,
 * whose x'' vanishes at the top) the first step starts where f'' = 0: a
 * stopping test that reads f'' at the step's start alone stops after it,
 * short of the root (1e-3 from the reference at this size under the box,
 * 2e-8 under tent:r=1; this file's other cases passed). */
static void test_cubic_cuts(void **state)
{
    (void)state;
    const char *const fs[] = {"box", "tent:r=1", "bspline:order=3", NULL};
    aa_scene *s = scenes_svg_at("curves", 48);
    for (const char *const *f = fs; *f; f++) {
        aa_image a, r;
        support_render("analytic", s, *f, 48, 48, 1, &a, NULL);
        support_reference(s, &(support_view){.w = 48, .h = 48, .filter = *f, .threads = 1}, &r,
                          NULL, NULL);
        within_reference("curves at 48 px", *f, &a, &r);
        aa_image_free(&a);
        aa_image_free(&r);
    }
    aa_scene_free(s);
}

/* The nonzero layer of test_overlapping_layers with loops that share end
 * points: the second starts 0.013 to the right of the first, its first arc's
 * control 0.013 lower, and both arcs of each loop end at the other loop's
 * ends, (0.72, 0.5) and its own start.  The second arcs leave (0.72, 0.5)
 * through the same control point (0.55, 0.95): at equal parameters t their
 * heights are equal and their x differ by t^2 (0.313 - 0.3), so they meet
 * only at that end, tangent there, and stay within rounding of each other
 * for a while below it.  Then a loop traced twice: every piece twice, the
 * same curve, which no meeting separates (it winds 2 inside). */
static void add_loop(aa_scene *s, double x0, double cy, double x1)
{
    assert_int_equal(aa_scene_move_to(s, x0, 0.55), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.5, cy, 0.72, 0.5), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.55, 0.95, x1, 0.55), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* The meetings aa_piece_meet reports between the two pieces leaving
 * (0.72, 0.5) downward, of which there are exactly two. */
static int meetings_below_shared_end(const aa_scene *s)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n), *p = NULL, *q = NULL;
    for (size_t k = 0; k < n; k++)
        if (pc[k].kind == AA_PIECE_QUAD && pc[k].x0 == 0.72 && pc[k].y0 == 0.5) {
            assert_null(q);
            if (!p)
                p = &pc[k];
            else
                q = &pc[k];
        }
    assert_non_null(q);
    double ys[16];
    return aa_piece_meet(p, q, 0.5, 1.0, ys, 16);
}

static void test_shared_ends(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_loop(s, 0.3, 0.1, 0.3);
    add_loop(s, 0.313, 0.113, 0.313);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    /* first the meetings, so that a search that cannot part the pieces
     * fails here instead of rendering for minutes */
    assert_int_equal(meetings_below_shared_end(s), 0);
    against_reference("loops sharing end points", s, 27, 25, 1, 0);
    aa_scene_free(s);

    s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_loop(s, 0.3, 0.1, 0.3);
    add_loop(s, 0.3, 0.1, 0.3);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(meetings_below_shared_end(s), 0);
    against_reference("a loop traced twice", s, 27, 25, 1, 0);
    aa_scene_free(s);
}

/* analytic against the reference under each filter of `filters` (NULL
 * ended), at w x h, threads 1 and 2 (the image does not depend on them). */
static void against_filters(const char *what, const aa_scene *s, int w, int h,
                            const char *const *flist)
{
    for (const char *const *f = flist; *f; f++) {
        aa_image a, a1, r;
        support_render("analytic", s, *f, w, h, 2, &a, NULL);
        support_render("analytic", s, *f, w, h, 1, &a1, NULL);
        support_reference(s, &(support_view){.w = w, .h = h, .filter = *f, .threads = 1}, &r,
                          NULL, NULL);
        within_reference(what, *f, &a, &r);
        size_t n = (size_t)w * h * 3;
        for (size_t k = 0; k < n; k++)
            if (memcmp(&a.v[k], &a1.v[k], sizeof a.v[k]))
                fail_msg("%s under %s: pixel %zu channel %zu differs between 1 and 2 threads",
                         what, *f, k / 3, k % 3);
        aa_image_free(&a);
        aa_image_free(&a1);
        aa_image_free(&r);
    }
}

/* A closed path of quadratic arcs through the corners of the box [x0, x1] x
 * [y0, y1], bulging out by b, clockwise on screen (ccw = 0) or the other
 * way. */
static void add_blob(aa_scene *s, double x0, double y0, double x1, double y1, double b, int ccw)
{
    double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
    const double pts[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const double ctl[4][2] = {{xm, y0 - b}, {x1 + b, ym}, {xm, y1 + b}, {x0 - b, ym}};
    if (!ccw) {
        assert_int_equal(aa_scene_move_to(s, pts[0][0], pts[0][1]), AA_OK);
        for (int k = 0; k < 4; k++)
            assert_int_equal(aa_scene_quad_to(s, ctl[k][0], ctl[k][1], pts[(k + 1) % 4][0],
                                              pts[(k + 1) % 4][1]),
                             AA_OK);
    } else {
        assert_int_equal(aa_scene_move_to(s, pts[0][0], pts[0][1]), AA_OK);
        for (int k = 3; k >= 0; k--)
            assert_int_equal(aa_scene_quad_to(s, ctl[k][0], ctl[k][1], pts[k][0], pts[k][1]),
                             AA_OK);
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* Rows of both paths in one image (analytic.c, "One layer at a time"):
 * the top third holds two layers that overlap (every row whose support
 * reaches the overlap is integrated pixel by pixel from the visible
 * parts), the rest disjoint shapes of both layers, one layer's paths
 * clockwise and the other's counter-clockwise (winding +1 and -1: the
 * per-edge scatter, with a step of colour per layer), one of them cut by
 * the image's left side and one by its bottom.  Then one layer whose two
 * paths run opposite ways (the lower one's rows go the per-pixel way, as
 * for a layer wound twice), and a scene of one colour (one value per
 * piece).  The reference is the harness's own quadrature (support.h). */
static void test_fast_and_layered(void **state)
{
    (void)state;
    const char *const flist[] = {"box", "tent:r=1", "tent:r=0.65", "bspline:order=2",
                                 "bspline:order=3", "mitchell:b=0.2,c=0.7", NULL};
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_blob(s, 0.1, 0.06, 0.45, 0.28, 0.05, 0);
    add_blob(s, -0.2, 0.5, 0.3, 0.7, 0.08, 0);   /* beyond the left side */
    add_blob(s, 0.55, 0.8, 0.8, 1.1, 0.04, 0);   /* beyond the bottom */
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.9, 0.05, 0.6}}, AA_FILL_EVENODD), AA_OK);
    add_blob(s, 0.3, 0.12, 0.7, 0.3, 0.06, 1);   /* over the first */
    add_blob(s, 0.5, 0.45, 0.9, 0.7, 0.03, 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("both paths", s, 30, 36, flist);
    aa_scene_free(s);

    s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_blob(s, 0.15, 0.1, 0.8, 0.4, 0.05, 0);
    add_blob(s, 0.2, 0.6, 0.75, 0.9, 0.05, 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("one layer, both ways", s, 24, 30, flist);
    aa_scene_free(s);

    s = aa_scene_new((aa_rgb){{0.25, 0.25, 0.25}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.75, 0.75, 0.75}}, AA_FILL_NONZERO), AA_OK);
    add_blob(s, 0.15, 0.1, 0.5, 0.4, 0.05, 0);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.75, 0.75, 0.75}}, AA_FILL_EVENODD), AA_OK);
    add_blob(s, 0.55, 0.5, 0.85, 0.9, 0.05, 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("two layers, one colour", s, 24, 30, flist);
    aa_scene_free(s);
}

/* Wide rectangles (flat top and bottom edges) in two colours, then in one:
 * against the reference, and every pixel whose support lies wholly inside
 * a rectangle or wholly outside both, not touching a side, is that face's
 * colour exactly (the supports inside are found from the geometry alone;
 * a side on a support's edge leaves that pixel to the integration, within
 * rounding of the colour). */
static void test_faces_exact(void **state)
{
    (void)state;
    const char *const flist[] = {"box", "tent:r=1", "bspline:order=3", NULL};
    const int w = 40, h = 30;
    const aa_rgb bg = {{0.1, 0.2, 0.3}}, c[2][2] = {{{{0.3, 0.8, 0.15}}, {{0.9, 0.05, 0.6}}},
                                                   {{{0.7, 0.7, 0.7}}, {{0.7, 0.7, 0.7}}}};
    /* pixel boxes [x0, x1) x [y0, y1) */
    const int r[2][4] = {{4, 3, 36, 12}, {6, 17, 30, 27}};
    for (int colours = 0; colours < 2; colours++) {
        aa_scene *s = aa_scene_new(bg);
        assert_non_null(s);
        for (int k = 0; k < 2; k++) {
            assert_int_equal(aa_scene_layer(s, c[colours][k], AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(s, r[k][0] / (double)w, r[k][1] / (double)h),
                             AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[k][2] / (double)w, r[k][1] / (double)h),
                             AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[k][2] / (double)w, r[k][3] / (double)h),
                             AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[k][0] / (double)w, r[k][3] / (double)h),
                             AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        against_filters(colours ? "rectangles, one colour" : "rectangles", s, w, h, flist);
        for (const char *const *f = flist; *f; f++) {
            aa_filter fl;
            assert_int_equal(aa_filter_parse(*f, &fl), AA_OK);
            double rad = fl.radius; /* the support: [c - rad, c + rad] */
            aa_image a;
            support_render("analytic", s, *f, w, h, 1, &a, NULL);
            int inside = 0, outside = 0;
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    double x0 = i + 0.5 - rad, x1 = i + 0.5 + rad, y0 = j + 0.5 - rad,
                           y1 = j + 0.5 + rad;
                    const double *want = NULL;
                    int apart = 1;
                    for (int k = 0; k < 2; k++) {
                        if (x0 > r[k][0] && x1 < r[k][2] && y0 > r[k][1] && y1 < r[k][3])
                            want = c[colours][k].c, inside++;
                        apart &= x1 < r[k][0] || x0 > r[k][2] || y1 < r[k][1] || y0 > r[k][3];
                    }
                    if (!want && apart)
                        want = bg.c, outside++;
                    for (int ch = 0; want && ch < 3; ch++)
                        if (aa_pixel(&a, i, j)[ch] != want[ch])
                            fail_msg("%s under %s: pixel (%d, %d) channel %d is %.17g, not the "
                                     "face's %.17g",
                                     colours ? "one colour" : "two colours", *f, i, j, ch,
                                     aa_pixel(&a, i, j)[ch], want[ch]);
                }
            assert_true(inside > 0 && outside > 0);
            aa_image_free(&a);
        }
        aa_scene_free(s);
    }
}

/* Supports many pixels wide: tent:r=6 (12 px) and tent:r=3.7 (cells of
 * width 3.7, so the knots' lines of neighbouring pixels interleave) on an
 * edge that crosses most of the image within one row (a thin wedge), a
 * cubic and crow's arcs; and a line far left of the image, whose terms are
 * the constant part alone. */
static void test_wide_supports(void **state)
{
    (void)state;
    const char *const flist[] = {"tent:r=6", "tent:r=3.7", "bspline:order=3", NULL};
    aa_scene *s = aa_scene_new((aa_rgb){{0.0, 0.0, 0.0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.03, 0.31), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.97, 0.27), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.95, 0.33), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.1, 0.5), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.9, 0.45, 0.2, 0.95, 0.85, 0.9), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.9, 0.55), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_move_to(s, -30.0, 0.4), AA_OK);
    assert_int_equal(aa_scene_line_to(s, -29.0, 0.42), AA_OK);
    assert_int_equal(aa_scene_line_to(s, -29.5, 0.9), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("wide supports", s, 40, 32, flist);
    aa_scene_free(s);
    aa_scene *crow = scenes_pattern("crow");
    against_filters("crow", crow, 32, 24, flist);
    aa_scene_free(crow);
}

/* An ellipse of centre (cx, cy) and semi-axes a, b turned by th, as one arc
 * from angle 0 to 2 pi (or back: reversed), in pattern units. */
static void add_ellipse(aa_scene *s, double cx, double cy, double a, double b, double th,
                        int reversed)
{
    double ux = a * cos(th), uy = a * sin(th), vx = -b * sin(th), vy = b * cos(th);
    assert_int_equal(aa_scene_move_to(s, cx + ux, cy + uy), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, 0.0,
                                     reversed ? -2.0 * M_PI : 2.0 * M_PI, cx + ux, cy + uy),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* Elliptical arcs (analytic.c, "Elliptical arcs") against the reference
 * under every filter taken, at 1 and 2 threads: one layer of disjoint
 * shapes (the per-edge scatter) holding a circle, an ellipse turned by 0.4
 * rad, a circle of radius 0.3 px (arcs far shorter than a cell), a pie
 * slice (an arc between two lines, starting and ending away from the
 * extremes) and a circle cut by the image's left side; then two layers
 * that overlap (the visible parts, pixel by pixel): an ellipse turned by
 * -1.1 rad, wound the other way, in front of a circle. */
static void test_arcs(void **state)
{
    (void)state;
    const char *const flist[] = {"box",      "tent:r=1", "tent:r=0.65", "bspline:order=2",
                                 "bspline:order=3", "mitchell", "mitchell:b=0.2,c=0.7",
                                 "catrom", NULL};
    const int w = 30, h = 26;
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_ellipse(s, 0.27, 0.3, 0.17, 0.17, 0.0, 0);
    add_ellipse(s, 0.7, 0.28, 0.22, 0.1, 0.4, 0);
    add_ellipse(s, 0.515, 0.62, 0.3 / w, 0.3 / w, 0.0, 0);
    add_ellipse(s, 0.02, 0.8, 0.12, 0.15, 0.0, 0);
    const double px = 0.55, py = 0.78, r = 0.17, t0 = 0.37, t1 = 2.3;
    assert_int_equal(aa_scene_move_to(s, px, py), AA_OK);
    assert_int_equal(aa_scene_line_to(s, px + r * cos(t0), py + r * sin(t0) * w / h), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, px, py, r, 0, 0, r * w / h, t0, t1, px + r * cos(t1),
                                     py + r * sin(t1) * w / h),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("arcs, one layer", s, w, h, flist);
    aa_scene_free(s);

    s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    add_ellipse(s, 0.45, 0.5, 0.3, 0.3, 0.0, 0);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.9, 0.05, 0.6}}, AA_FILL_EVENODD), AA_OK);
    add_ellipse(s, 0.6, 0.45, 0.33, 0.12, -1.1, 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_filters("arcs, overlapping", s, 24, 22, flist);
    aa_scene_free(s);
}

/* Circles of radius 1e4 and 1e6 (pattern units; placed, ellipses of
 * 1e4 px by 8.3e3 px and 100 times that) whose rightmost point lies
 * inside the image (a cap of the image's height, the rest of the image
 * left of it inside): the arcs in a cell are 1e-4 to 1e-6 rad long, and
 * two pieces meet at the rightmost point, where the pieces' double angles
 * would leave a gap of er 2e-16 in y (analytic.c, arc_angle).  Within
 * 1e-12 of the reference (its stated bound at 1e6 is larger, about 1e-11,
 * but it came out 1.6e-14 from the exact disk there: tests/test_conic.c,
 * test_huge; here the box pixel (14, 2) at 1e6 is 0.63996566093038406 by
 * a 50-digit quadrature of the placed ellipse's x(y), analytic 7.6e-14
 * above it, the reference 1.6e-14 below). */
static void test_huge_radii(void **state)
{
    (void)state;
    const char *const flist[] = {"box", "tent:r=1", "bspline:order=3", "catrom", NULL};
    const int w = 24, h = 20;
    const double radii[] = {1e4, 1e6};
    for (int k = 0; k < 2; k++) {
        double R = radii[k] / w;
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_non_null(s);
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
        add_ellipse(s, 0.61 - R, 0.47, R, R, 0.0, 0);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        for (const char *const *f = flist; *f; f++) {
            aa_image a, r;
            support_render("analytic", s, *f, w, h, 1, &a, NULL);
            support_reference(s, &(support_view){.w = w, .h = h, .filter = *f, .threads = 1},
                              &r, NULL, NULL);
            double d = support_max_diff(&a, &r, NULL, NULL);
            if (!(d <= 1e-12))
                fail_msg("circle of radius %g px under %s: largest difference %.3g", radii[k],
                         *f, d);
            print_message("circle of radius %-6g  %-22s largest difference %.1e\n", radii[k],
                          *f, d);
            aa_image_free(&a);
            aa_image_free(&r);
        }
        aa_scene_free(s);
    }
}

/* The image of a white region sums to its area (header), w x h pixels. */
static void check_sum(const char *what, const aa_scene *s, int w, int h, double area)
{
    const char *const pu[] = {"box",      "tent:r=1", "bspline:order=2",      "bspline:order=3",
                              "mitchell", "catrom",   "mitchell:b=0.5,c=0.75", NULL};
    for (const char *const *f = pu; *f; f++) {
        aa_image img;
        support_render("analytic", s, *f, w, h, 1, &img, NULL);
        double sum = 0.0;
        for (int k = 0; k < w * h; k++)
            sum += img.v[3 * k];
        if (!(fabs(sum - area) <= 1e-12 * area))
            fail_msg("%s under %s: sum %.17g, area %.17g", what, *f, sum, area);
        print_message("%s under %-22s: sum - area %.1e\n", what, *f, sum - area);
        aa_image_free(&img);
    }
}

static void test_sums(void **state)
{
    (void)state;
    int w = 23, h = 19;
    /* a parabolic segment, pattern units inside [0.2, 0.8]^2 */
    const double p0[2] = {0.21, 0.74}, c[2] = {0.47, 0.22}, p1[2] = {0.78, 0.69};
    aa_scene *s = scenes_arc_segment(p0[0], p0[1], c[0], c[1], p1[0], p1[1]);
    double tri = 0.5 * fabs((c[0] - p0[0]) * (p1[1] - p0[1]) - (p1[0] - p0[0]) * (c[1] - p0[1]));
    check_sum("parabolic segment", s, w, h, 2.0 / 3.0 * tri * w * h);
    aa_scene_free(s);
    /* under y = x^3 on [0, 1], placed at (0.25, 0.75) scaled by (0.5, -0.5):
     * the cubic (0,0) (1/3,0) (2/3,0) (1,1), then down and back */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.25, 0.75), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.25 + 0.5 / 3, 0.75, 0.25 + 1.0 / 3, 0.75, 0.75, 0.25),
                     AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.75, 0.75), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_sum("under y = x^3", s, w, h, 0.25 * 0.5 * 0.5 * w * h);
    aa_scene_free(s);
    /* a disk of radius 0.3 (placed, an ellipse of semi-axes 0.3 w and 0.3
     * h: area pi 0.09 w h), and an ellipse of semi-axes 0.33 and 0.12 turned
     * by 0.7 rad (placed, the linear map diag(w, h) of it: area pi 0.33 0.12
     * w h), wound the other way, beside it */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    add_ellipse(s, 0.48, 0.51, 0.3, 0.3, 0.0, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_sum("disk", s, w, h, M_PI * 0.09 * w * h);
    aa_scene_free(s);
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    add_ellipse(s, 0.52, 0.47, 0.33, 0.12, 0.7, 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_sum("turned ellipse", s, w, h, M_PI * 0.33 * 0.12 * w * h);
    aa_scene_free(s);
}

static void refused_filter(const char *filter, const char *words)
{
    aa_filter f;
    aa_spec spec;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    int st = aa_method_parse("analytic", &f, &spec);
    if (st != AA_EINVAL || !strstr(aa_last_error(), words))
        fail_msg("analytic -f %s: status %d, \"%s\" (expected %d and \"%s\")", filter, st,
                 aa_last_error(), AA_EINVAL, words);
}

static void test_refusals(void **state)
{
    (void)state;
    refused_filter("gauss", "gauss is not one");
    refused_filter("lanczos", "lanczos is not one");
    refused_filter("cone", "cone is not one");
    refused_filter("gauss:s=1,cut=2", "is not one");
}

#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_patterns),
        cmocka_unit_test(test_cubics),
        cmocka_unit_test(test_svg),
        cmocka_unit_test(test_overlapping_layers),
#if !ANALYTIC_ALL /* the same in both tiers: the quick tier's alone */
        cmocka_unit_test(test_cubic_cuts),
        cmocka_unit_test(test_shared_ends),
        cmocka_unit_test(test_fast_and_layered),
        cmocka_unit_test(test_wide_supports),
        cmocka_unit_test(test_faces_exact),
        cmocka_unit_test(test_arcs),
        cmocka_unit_test(test_huge_radii),
        cmocka_unit_test(test_sums),
        cmocka_unit_test(test_refusals),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
