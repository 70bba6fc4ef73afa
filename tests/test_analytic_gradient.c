/*
 * test_analytic_gradient.c: `analytic` on linear gradients in linear light
 * (algorithms/analytic.c, "Linear gradients": the stop lines made
 * geometry, each strip's colour affine, its first moments by Green's
 * theorem), against answers that are not the method's own:
 *
 *  - the exact reference of the harness's truth path (aa_truth_render: its
 *    own quadrature of the filter times decode(encode(v)) along the rows,
 *    cut at the stop lines and at the encoding's change of piece;
 *    harness/truth/truth.c, "gradients in linear light"), within 1e-12 per
 *    pixel and channel, at 1 and 2 threads (bit-identical), under box,
 *    tent:r=1, bspline:order=2, bspline:order=3, mitchell, catrom and
 *    tent:r=0.65 (cells narrower than a pixel) (the quick tier: the box
 *    only; the closed forms below take the others there; the full tier:
 *    bspline:order=2 and 3, Mitchell and Catmull-Rom each on a quarter of
 *    the view), on: several layers in painter's order (a flat triangle in
 *    front of a path of lines, a quadratic and a cubic arc painted by a
 *    padded gradient of three stops with a sharp step, in front of a
 *    repeated gradient of a period of 4.4 px across the whole image, over
 *    the background), a self-crossing even-odd path of cubic arcs under a
 *    reflected gradient, a gradient gated by a clip, stroked polylines
 *    (their outlines: lines) read from SVG, and a slow ramp across the
 *    encoding's sliver (the linear values 0.003130 to 0.003132 across the
 *    image, so the sliver (0.0031308, 0.0031308073), where decode(encode(v))
 *    lies 2.2e-9 below v, is 0.07 px wide: taking v there would miss by
 *    about 1e-10, a hundred times the tolerance); and elliptical arcs (a
 *    circle, a turned ellipse and a rounded rectangle under pad, repeat
 *    and reflect gradients) and offset curves (a stroked cubic whose inner
 *    offset folds, a stroked turned ellipse) under box and
 *    bspline:order=3 (the full tier: tent:r=1 and Mitchell too, and
 *    circles and an ellipse under a steep repeated gradient against wide
 *    cells, tent:r=6, whose arcs' parts are long);
 *  - closed forms, derived here: under a filter whose integer translates
 *    sum to 1 (box, tent:r=1, the B-splines, Mitchell-Netravali,
 *    Catmull-Rom) an image holding the whole filtered support of the
 *    picture sums to the picture's integral.  A black-to-white linear-light
 *    ramp along x from a to b (colour (x - a)/(b - a), pad) painting a
 *    rectangle [x0, x1] x [y0, y1] inside [a, b] on black integrates to
 *    (y1 - y0) ((x1 - a)^2 - (x0 - a)^2) / (2 (b - a)) in every channel
 *    (the integral of an affine function; the sliver changes it by at most
 *    2.4e-9 x 7.3e-9 (b - a) (y1 - y0) < 1e-14 here); the same ramp
 *    repeated with period P over a rectangle of whole periods integrates to
 *    half its area (each period's mean is 1/2); a region whose colour is
 *    affine, c(x, y), integrates to its area times c at its centroid: a
 *    disk of radius R under a ramp along x (pad never reached) to pi R^2
 *    c(centre), a turned ellipse of semi-axes a, b under an oblique ramp
 *    to pi a b c(centre) (the sliver's change as above, below 1e-14);
 *  - refusals by name: sRGB interpolation, radial gradients, a stop of
 *    partial opacity, a translucent layer, a gradient of more stop lines
 *    than the method takes (gradients under the radial filters:
 *    tests/test_analytic_radial_gradient.c).
 */
#include "bench.h"
#include "core.h"
#include "patterns.h"
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

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "anagrad");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* The size in pixels of the view whose scene is being built (scenes_*_px). */
static int W, H;

/* The filters each scene takes.  The quick tier (this file): every scene
 * under the box, the arcs' and offsets' scenes under bspline:order=3 too
 * (the closed forms below take the others).  The full tier,
 * test_analytic_gradient_full.c (this file with TIER_FULL set), takes the rest, every scene under every filter (the reference's
 * quadrature of a gradient scene under the smooth filters takes seconds a
 * scene): the six other filters on the first five scenes (four of them
 * each on a quarter of the view: against_quarters), tent:r=1 and
 * mitchell on the arcs' and offsets', tent:r=6 on the small arcs (their
 * middle 6 x 5 pixels).  It
 * leaves out what the quick tier checks (the box, the arcs under
 * bspline:order=3, the closed forms, the refusals): `make test` runs both
 * tiers, and the same cases twice would check nothing more.
 *
 * Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) the full tier runs a declared subset, `san` below:
 * every filter of the plain run's, every scene, the wide cells, each
 * scene under one or two of them.  The sanitizers find memory and
 * undefined behaviour errors along the code paths taken; more filters on
 * the same scene take the same paths (tests/README.md, "Tiers", says how
 * that was checked), and the plain build runs everything.  The quick tier
 * under the sanitizers likewise takes the arcs' and offsets' scenes under
 * bspline:order=3 on their middle 12 x 9 pixels alone (against_arcs; the
 * box on the whole view), which reach the library's lines the whole views
 * reach, and the full tier there Mitchell on the arcs' same 12 x 9 pixels
 * (its cells as wide: the whole view's 562 functions and all but one of
 * its 6,582 lines, tests/README.md, "Tiers"). */
/* The quick tier's filter for the first five scenes, and the full tier's:
 * every filter but the box */
#define BOX FILTERS("box")
#define NOT_BOX                                                                                   \
    FILTERS("tent:r=1", "bspline:order=2", "bspline:order=3", "mitchell", "catrom", "tent:r=0.65")
/* for the arcs' and offsets' scenes: the box and the cubic B-spline, the
 * largest rule (the reference under the smooth filters is most of this
 * test's time); the full tier adds the linear filter and the one with
 * negative lobes */
#define ARC_QUICK FILTERS("box", "bspline:order=3")
#define ARC_FULL FILTERS("tent:r=1", "mitchell")

/* analytic against the reference under each filter of fl */
static void against(const char *what, const aa_scene *s, int w, int h, const char *const *fl)
{
    support_method_against_filters("analytic", what, s, w, h, fl);
}

#if TIER_FULL || SAN_SUBSET
/* analytic against the reference under `filter` on a part of the view
 * (support_method_against_part) */
static double against_part(const char *what, const aa_scene *s, int sw, int sh, int x0, int y0,
                           int w, int h, const char *filter)
{
    return support_method_against_part("analytic", what, s, sw, sh, x0, y0, w, h, filter);
}
#endif

/* The first five scenes' filters (NOT_BOX): in the full tier those of
 * cells 3 and 4 px wide, bspline:order=2 and 3, Mitchell and Catmull-Rom,
 * each on one quarter of the view (top left, top right, bottom left,
 * bottom right, in that order; against_part), so that the four check every
 * pixel once: the reference's quadrature of these scenes under them is
 * most of this test's time (the three layers' whole view under Mitchell
 * 18 s of CPU, a quarter of it 3 to 5 s).  A quarter's cells meet the
 * same layers, stop lines, arcs and clips as the whole view's, and the
 * filter the same code with other numbers: gcov finds the same functions
 * and lines of the library reached (tests/README.md, "Tiers").  The
 * narrow cells, tent:r=1 and tent:r=0.65, take the whole view, as does
 * the sliver's ramp (against: its sliver crosses the left half only). */
static void against_quarters(const char *what, const aa_scene *s, int w, int h,
                             const char *const *fl)
{
#if TIER_FULL
    static const char *const wide[] = {"bspline:order=2", "bspline:order=3", "mitchell",
                                       "catrom"};
    double worst = 0.0;
    for (; *fl; fl++) {
        int q = -1;
        for (int k = 0; k < 4; k++)
            if (!strcmp(*fl, wide[k]))
                q = k;
        worst = fmax(worst, q < 0 ? support_method_against_reference("analytic", what, s, w, h,
                                                                     *fl)
                                  : against_part(what, s, w, h, q % 2 * (w / 2),
                                                 q / 2 * (h / 2), w / 2, h / 2, *fl));
    }
    print_message("%-28s largest difference over the filters %.1e\n", what, worst);
#else
    against(what, s, w, h, fl);
#endif
}

#if !TIER_FULL && SAN_SUBSET
/* The sanitizer build's subset of the arcs' and offsets' scenes: the box
 * on the whole view, bspline:order=3 on the part x0, y0, w x h of it
 * (tests/README.md, "Tiers") */
static void against_arcs(const char *what, const aa_scene *s, int sw, int sh, int x0, int y0,
                         int w, int h)
{
    against(what, s, sw, sh, BOX);
    against_part(what, s, sw, sh, x0, y0, w, h, "bspline:order=3");
}
#endif

static const aa_gradient_stop three[4] = {{0.0, {{0.9, 0.05, 0.2}}, 1.0},
                                          {0.45, {{0.1, 0.8, 0.3}}, 1.0},
                                          {0.45, {{0.2, 0.1, 0.7}}, 1.0},
                                          {1.0, {{1.0, 0.95, 0.6}}, 1.0}};
static const aa_gradient_stop two[2] = {{0.15, {{0.0, 0.3, 0.05}}, 1.0},
                                        {0.8, {{0.6, 1.0, 0.1}}, 1.0}};

/* A flat triangle in front of a path of lines, a quadratic and a cubic arc
 * (padded gradient, a sharp step), in front of a repeated gradient over the
 * whole image, over the background. */
static void test_layers(void **state)
{
    (void)state;
    W = 24, H = 20;
    aa_scene *s = aa_scene_new((aa_rgb){{0.2, 0.3, 0.4}});
    scenes_layer(s, 0.9, 0.1, 0.5, AA_FILL_NONZERO);
    scenes_move_px(s, W, H, 5.5, 5.5);
    scenes_line_px(s, W, H, 14.2, 9.9);
    scenes_line_px(s, W, H, 7.1, 15.3);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_move_px(s, W, H, 3.3, 2.2);
    scenes_line_px(s, W, H, 20.7, 4.1);
    assert_int_equal(aa_scene_quad_to(s, 22.0 / W, 15.0 / H, 12.2 / W, 18.6 / H), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 8.0 / W, 12.0 / H, 1.0 / W, 19.0 / H, 3.3 / W, 2.2 / H),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){2, 3, 19, 15, 0, 0}, three, 4, 0);
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 0, 0, W, H);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                       (const double[6]){3, 1, 7.3, 2.1, 0, 0}, two, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_quarters("three layers", s, W, H,
            TIER(BOX, NOT_BOX, FILTERS("tent:r=1")));
    aa_scene_free(s);
}

/* A self-crossing even-odd path of cubic arcs under a reflected gradient,
 * over a flat rectangle; and a gradient gated by a clip (a triangle). */
static void test_curves_and_clip(void **state)
{
    (void)state;
    W = 22, H = 20;
    aa_scene *s = aa_scene_new((aa_rgb){{0.05, 0.05, 0.1}});
    scenes_layer(s, 0, 0, 0, AA_FILL_EVENODD);
    scenes_move_px(s, W, H, 2.5, 3.1);
    assert_int_equal(aa_scene_cubic_to(s, 30.0 / W, 1.0 / H, -8.0 / W, 21.0 / H, 19.3 / W,
                                       17.2 / H),
                     AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 12.0 / W, 5.0 / H, 6.0 / W, 25.0 / H, 2.5 / W, 3.1 / H),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_REFLECT,
                       (const double[6]){4, 15, 9.1, 11.2, 0, 0}, three, 4, 0);
    scenes_layer(s, 0.7, 0.6, 0.2, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 4.3, 4.6, 17.7, 13.1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_quarters("reflected, cubic arcs", s, W, H,
            TIER(BOX, NOT_BOX, FILTERS("bspline:order=2")));
    aa_scene_free(s);

    s = aa_scene_new((aa_rgb){{0.3, 0.3, 0.3}});
    int clip;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    scenes_move_px(s, W, H, 1.7, 18.2);
    scenes_line_px(s, W, H, 11.3, 0.9);
    scenes_line_px(s, W, H, 20.6, 16.4);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 3.2, 2.4, 19.1, 17.3);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){4, 4, 18, 9, 0, 0}, three, 4, 0);
    assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_quarters("clipped gradient", s, W, H,
            TIER(BOX, NOT_BOX, FILTERS("catrom")));
    aa_scene_free(s);
}

/* The slow ramp across the encoding's sliver (the opening comment). */
static void test_sliver(void **state)
{
    (void)state;
    W = 20, H = 8;
    const aa_gradient_stop slow[2] = {{0.0, {{0.003130, 0.003131, 0.5}}, 1.0},
                                      {1.0, {{0.003132, 0.003131, 0.5}}, 1.0}};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 1.3, 1.1, 18.6, 6.7);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){1, 0, 19, 0.4, 0, 0}, slow, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against("ramp across the sliver", s, W, H,
            TIER(BOX, NOT_BOX, FILTERS("tent:r=0.65")));
    aa_scene_free(s);
}

/* Stroked polylines with a gradient stroke, read from SVG (miter joins,
 * butt and square caps: outlines of lines). */
static void test_strokes(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"24\" height=\"20\">\n"
        "<linearGradient id=\"g\" x1=\"2\" y1=\"1\" x2=\"9\" y2=\"6\" gradientUnits=\"userSpaceOnUse\"\n"
        " spreadMethod=\"reflect\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.2\" stop-color=\"#ff2000\"/><stop offset=\"0.9\" stop-color=\"#2040ff\"/>\n"
        "</linearGradient>\n"
        "<rect width=\"24\" height=\"20\" fill=\"#203040\"/>\n"
        "<polyline points=\"2.3,3.4 20.1,5.2 6.2,16.7 21.3,17.9\" fill=\"none\" stroke=\"url(#g)\"\n"
        " stroke-width=\"2.6\"/>\n"
        "<polyline points=\"3.1,12.2 9.7,8.3 12.4,13.6\" fill=\"none\" stroke=\"#e0e0a0\"\n"
        " stroke-width=\"1.3\" stroke-linecap=\"square\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "strokes.svg", svg, 24, 20);
    against_quarters("stroked polylines (SVG)", s, 24, 20,
            TIER(BOX, NOT_BOX, FILTERS("bspline:order=3")));
    aa_scene_free(s);
}

/* A circle, an ellipse turned by 30 degrees and a rounded rectangle
 * (elliptical arcs), painted by linear gradients in linear light, pad,
 * repeat and reflect, over a flat layer they overlap; under box and
 * bspline:order=3 (the full tier: every filter). */
static void test_arcs(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"24\" height=\"18\">\n"
        "<linearGradient id=\"p\" x1=\"3.2\" y1=\"2.1\" x2=\"12.6\" y2=\"13.2\"\n"
        " gradientUnits=\"userSpaceOnUse\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.1\" stop-color=\"#f02010\"/>\n"
        " <stop offset=\"0.55\" stop-color=\"#30e060\"/>\n"
        " <stop offset=\"0.55\" stop-color=\"#2040c0\"/>\n"
        " <stop offset=\"0.9\" stop-color=\"#f0f0a0\"/>\n"
        "</linearGradient>\n"
        "<linearGradient id=\"r\" href=\"#p\" x1=\"12.1\" y1=\"6.3\" x2=\"15.8\" y2=\"4.1\"\n"
        " spreadMethod=\"repeat\" color-interpolation=\"linearRGB\"/>\n"
        "<linearGradient id=\"f\" href=\"#p\" x1=\"16.2\" y1=\"1.3\" x2=\"18.9\" y2=\"4.7\"\n"
        " spreadMethod=\"reflect\" color-interpolation=\"linearRGB\"/>\n"
        "<rect x=\"2.3\" y=\"9.4\" width=\"17.2\" height=\"5.9\" fill=\"#806040\"/>\n"
        "<circle cx=\"7.3\" cy=\"8.1\" r=\"4.7\" fill=\"url(#p)\"/>\n"
        "<ellipse cx=\"13.2\" cy=\"11.3\" rx=\"5.1\" ry=\"2.9\"\n"
        " transform=\"rotate(30 13.2 11.3)\" fill=\"url(#r)\"/>\n"
        "<rect x=\"15.4\" y=\"1.6\" width=\"6.3\" height=\"7.7\" rx=\"2.2\" ry=\"1.6\"\n"
        " fill=\"url(#f)\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "arcs.svg", svg, 24, 18);
#if !TIER_FULL && SAN_SUBSET
    against_arcs("circle, ellipse, round rect", s, 24, 18, 6, 4, 12, 9);
#elif SAN_SUBSET
    /* Mitchell on the middle 12 x 9 pixels, as against_arcs takes the
     * cubic B-spline (cells of the same width) */
    against_part("circle, ellipse, round rect", s, 24, 18, 6, 4, 12, 9, "mitchell");
#else
    against("circle, ellipse, round rect", s, 24, 18,
            TIER(ARC_QUICK, ARC_FULL, FILTERS("mitchell")));
#endif
    aa_scene_free(s);
}

/* Circles and an ellipse against wide cells (tent:r=6, cells 6 px wide,
 * where a part of an arc is up to a quarter of it), under a steep
 * repeated gradient (the full tier: the reference takes tens of seconds
 * here). */
#if TIER_FULL
static void test_small_arcs(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"12\" height=\"10\">\n"
        "<linearGradient id=\"g\" x1=\"1\" y1=\"2\" x2=\"2.3\" y2=\"2.9\"\n"
        " gradientUnits=\"userSpaceOnUse\" spreadMethod=\"repeat\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0\" stop-color=\"#000000\"/><stop offset=\"1\" stop-color=\"#ffffff\"/>\n"
        "</linearGradient>\n"
        "<circle cx=\"3.6\" cy=\"3.9\" r=\"2.9\" fill=\"url(#g)\"/>\n"
        "<circle cx=\"8.6\" cy=\"2.7\" r=\"0.45\" fill=\"url(#g)\"/>\n"
        "<ellipse cx=\"7.4\" cy=\"6.8\" rx=\"2.6\" ry=\"1.2\" transform=\"rotate(35 7.4 6.8)\"\n"
        " fill=\"url(#g)\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "smallarcs.svg", svg, 12, 10);
    /* the middle 6 x 5 pixels of the 12 x 10 (7.5 s of CPU, the whole view
     * 24 s): every cell is 12 px wide, so each holds most of the picture,
     * and their sides cross the three shapes' arcs on every side (the
     * large circle's from column 7 on, the ellipse's up to column 3, the
     * rows' likewise), as the whole view's do */
    against_part("small arcs, wide cells", s, 12, 10, 3, 2, 6, 5, "tent:r=6");
    aa_scene_free(s);
}
#endif

/* A stroked cubic (its outline: offset curves, with a fold of the inner
 * offset at its sharp turn) and a stroked turned ellipse, with gradient
 * paint, over a flat circle. */
static void test_curve_strokes(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"22\" height=\"20\">\n"
        "<linearGradient id=\"g\" x1=\"2\" y1=\"3\" x2=\"8.5\" y2=\"7\"\n"
        " gradientUnits=\"userSpaceOnUse\" spreadMethod=\"reflect\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.15\" stop-color=\"#ff3010\"/><stop offset=\"0.85\" stop-color=\"#1050ff\"/>\n"
        "</linearGradient>\n"
        "<linearGradient id=\"h\" x1=\"4\" y1=\"18\" x2=\"19\" y2=\"9\"\n"
        " gradientUnits=\"userSpaceOnUse\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0\" stop-color=\"#e0e020\"/><stop offset=\"1\" stop-color=\"#20a0a0\"/>\n"
        "</linearGradient>\n"
        "<circle cx=\"11\" cy=\"10\" r=\"6.5\" fill=\"#404060\"/>\n"
        "<path d=\"M2.4,3.3 C19.7,1.2 0.8,17.9 19.1,16.2\" fill=\"none\" stroke=\"url(#g)\"\n"
        " stroke-width=\"2.3\"/>\n"
        "<ellipse cx=\"12.1\" cy=\"11.4\" rx=\"6.2\" ry=\"3.1\" transform=\"rotate(-25 12.1 11.4)\"\n"
        " fill=\"none\" stroke=\"url(#h)\" stroke-width=\"1.7\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "curvestrokes.svg", svg, 22, 20);
#if !TIER_FULL && SAN_SUBSET
    against_arcs("stroked cubic and ellipse", s, 22, 20, 5, 4, 12, 9);
#else
    against("stroked cubic and ellipse", s, 22, 20,
            TIER(ARC_QUICK, ARC_FULL, FILTERS("tent:r=1")));
#endif
    aa_scene_free(s);
}

/* The closed forms and the refusals: the quick tier's alone (above) */
#if !TIER_FULL
static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};
/* the filters whose integer translates sum to 1 */
static const char *const unity[] = {"box",      "tent:r=1", "bspline:order=2", "bspline:order=3",
                                    "mitchell", "catrom",   NULL};

/* The image's sum against the picture's integral (the opening comment). */
static void sums_to(const char *what, const aa_scene *s, int w, int h, double want)
{
    double worst = 0.0;
    for (const char *const *f = unity; *f; f++) {
        aa_image img;
        support_render("analytic", s, *f, w, h, 1, &img, NULL);
        for (int ch = 0; ch < 3; ch++) {
            double sum = 0.0;
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++)
                    sum += aa_pixel(&img, i, j)[ch];
            if (!(fabs(sum - want) <= 1e-12))
                fail_msg("%s under %s: channel %d sums to %.17g, the integral is %.17g", what,
                         *f, ch, sum, want);
            worst = fmax(worst, fabs(sum - want));
        }
        aa_image_free(&img);
    }
    print_message("%-28s max |sum - integral| %.1e (integral %.6f)\n", what, worst, want);
}

static void test_closed_forms(void **state)
{
    (void)state;
    W = 28, H = 16;
    /* the ramp from a to b across the rectangle [x0, x1] x [y0, y1] */
    double a = 2.25, b = 25.5, x0 = 4.3, x1 = 23.6, y0 = 4.2, y1 = 11.9;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, x0, y0, x1, y1);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){a, 7, b, 7, 0, 0}, black_white, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    sums_to("ramp across a rectangle", s, W, H,
            (y1 - y0) * ((x1 - a) * (x1 - a) - (x0 - a) * (x0 - a)) / (2.0 * (b - a)));
    aa_scene_free(s);

    /* repeated with period P = 3.7 over 5 whole periods from x0 */
    double P = 3.7;
    x0 = 4.15, x1 = x0 + 5 * P;
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, x0, y0, x1, y1);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                       (const double[6]){x0, 3, x0 + P, 3, 0, 0}, black_white, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    sums_to("repeated ramp, whole periods", s, W, H, 0.5 * (x1 - x0) * (y1 - y0));
    aa_scene_free(s);

    /* A disk of radius R about (xc, yc) painted by a ramp along x from a to
     * b beyond it (pad never reached): its colour affine, its integral the
     * area times the colour at the centre, pi R^2 (xc - a)/(b - a); and a
     * turned ellipse of semi-axes ea, eb under an oblique ramp, pi ea eb
     * times the colour at its centre (the centroid). */
    W = 26, H = 24;
    double R = 7.35, xc = 12.6, yc = 11.8;
    a = xc - R - 1.5, b = xc + R + 2.25;
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_move_px(s, W, H, xc + R, yc);
    assert_int_equal(aa_scene_arc_to(s, xc / W, yc / H, R / W, 0, 0, R / H, 0, 2.0 * M_PI,
                                     (xc + R) / W, yc / H),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){a, 3, b, 3, 0, 0}, black_white, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    sums_to("disk under a ramp", s, W, H, M_PI * R * R * (xc - a) / (b - a));
    aa_scene_free(s);

    /* the ellipse's axes (cos th, sin th) ea and (-sin th, cos th) eb; the
     * ramp from (a, ya) to (b, yb), t = ((p - P1).d)/|d|^2 at the centre */
    double ea = 8.1, eb = 4.3, th = 0.6, ya = 1.5, yb = 22.0;
    a = 2.0, b = 24.5;
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_move_px(s, W, H, xc + ea * cos(th), yc + ea * sin(th));
    assert_int_equal(aa_scene_arc_to(s, xc / W, yc / H, ea * cos(th) / W, ea * sin(th) / H,
                                     -eb * sin(th) / W, eb * cos(th) / H, 0, 2.0 * M_PI,
                                     (xc + ea * cos(th)) / W, (yc + ea * sin(th)) / H),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){a, ya, b, yb, 0, 0}, black_white, 2, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    double dx = b - a, dy = yb - ya, t = ((xc - a) * dx + (yc - ya) * dy) / (dx * dx + dy * dy);
    sums_to("turned ellipse, oblique ramp", s, W, H, M_PI * ea * eb * t);
    aa_scene_free(s);
}

/* analytic refuses the scene (or filter) with a message holding `want`. */
static void refused(const char *what, const aa_scene *s, const char *filter, const char *want)
{
    aa_image img;
    support_view v = {W, H, 0, 0, 0, filter, 1, 1, 0};
    int st = support_render_view("analytic", s, &v, &img, NULL);
    if (st == AA_OK) {
        aa_image_free(&img);
        fail_msg("%s: rendered, not refused", what);
    }
    if (!strstr(aa_last_error(), want))
        fail_msg("%s: refused as \"%s\", not naming \"%s\"", what, aa_last_error(), want);
    print_message("%-28s refused: %s\n", what, aa_last_error());
}

/* A rectangle painted by a gradient (kind, spread, p, stops; sRGB if
 * srgb), behind a flat layer of alpha `alpha`. */
static aa_scene *one(int kind, int spread, const double p[6], const aa_gradient_stop *st, int n,
                     int srgb, double alpha)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    scenes_layer(s, 1, 1, 1, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 1, 1, 4, 4);
    assert_int_equal(aa_scene_set_alpha(s, alpha), AA_OK);
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 2, 2, 10, 7);
    scenes_gradient_px(s, W, H, kind, spread, p, st, n, srgb);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_refusals(void **state)
{
    (void)state;
    W = 12, H = 8;
    const double lin[6] = {2, 0, 9, 0, 0, 0}, rad[6] = {6, 4, 3, 6, 4, 0};
    const aa_gradient_stop half[2] = {{0.0, {{1, 0, 0}}, 1.0}, {1.0, {{0, 0, 1}}, 0.5}};
    aa_scene *s = one(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, lin, black_white, 2, 0, 1.0);
    support_method_against_reference("analytic", "refusals' base scene", s, W, H, "box");
    aa_scene_free(s);
    s = one(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, lin, black_white, 2, 1, 1.0);
    refused("sRGB interpolation", s, "box", "layer 1's linear gradient interpolates its stops in "
                                            "sRGB-encoded values");
    aa_scene_free(s);
    s = one(AA_GRADIENT_RADIAL, AA_SPREAD_PAD, rad, black_white, 2, 0, 1.0);
    refused("radial gradient", s, "box", "layer 1's radial gradient is refused");
    aa_scene_free(s);
    s = one(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, lin, half, 2, 0, 1.0);
    refused("stop opacity", s, "box", "has stop 1 of opacity 0.5");
    aa_scene_free(s);
    s = one(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, lin, black_white, 2, 0, 0.5);
    refused("translucent layer", s, "box", "layer 0 is translucent");
    aa_scene_free(s);
    /* a period of 1e-4 px: 1.7e5 periods across the frame */
    s = one(AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT, (const double[6]){2, 0, 2.0001, 0, 0, 0},
            black_white, 2, 0, 1.0);
    refused("too many stop lines", s, "box", "more than 65536 stop lines");
    aa_scene_free(s);
}

#endif

int main(void)
{
    print_message("tier: %s\n", TIER_NAME);
#if !TIER_FULL
    SAN_CASES_PRINT();
#endif
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_layers),       cmocka_unit_test(test_curves_and_clip),
        cmocka_unit_test(test_sliver),       cmocka_unit_test(test_strokes),
        cmocka_unit_test(test_arcs),         cmocka_unit_test(test_curve_strokes),
#if TIER_FULL
        cmocka_unit_test(test_small_arcs),
#else
        cmocka_unit_test(test_closed_forms), cmocka_unit_test(test_refusals),
#endif
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
