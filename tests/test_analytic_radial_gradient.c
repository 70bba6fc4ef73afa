/*
 * test_analytic_radial_gradient.c: `analytic` on linear gradients in linear
 * light under the radially symmetric polynomial filters radial:k=K,r=R
 * (algorithms/analytic.c, "Linear gradients under the radial filters": the
 * first moments over the part of the filter's disc in a region, by Green's
 * theorem, from the potentials H and v F), against answers that are not
 * the method's own:
 *
 *  - the exact reference of the harness's truth path (aa_truth_render: its
 *    own quadrature of the filter times the gradient's colour along the
 *    rows, cut at the stop lines; harness/truth/truth.c), within 1e-12 per
 *    pixel and channel, at 1 and 2 threads (bit-identical), on: a path of
 *    lines and a cubic arc painted by a padded gradient of three stops with
 *    a sharp step, in front of a rectangle under a repeated gradient
 *    (radial:k=1,r=1); an elliptical arc (a circle) under
 *    a reflected gradient and a turned ellipse under a padded one
 *    (radial:k=2,r=1.5); in the full tier
 *    (tests/test_analytic_radial_gradient_full.c) both under the other
 *    two of radial:k=1,r=1, radial:k=2,r=1.5 and radial:k=3,r=2, the first
 *    at 40x35 px under all three (each on a third of the view), and a
 *    stroked cubic (its outline offset curves, its inner offset folding)
 *    under a reflected gradient, under all three (under the sanitizers a
 *    subset: TIER below);
 *  - a closed form written here: the half-plane x < x0 painted by the ramp
 *    c(x) = (x - a)/(b - a) along x (black to white, pad not reached
 *    within the filter's disc), on black.  At a pixel centre (cx, cy),
 *    with u = x - cx, its value is the integral over u < d = x0 - cx of
 *    c(cx + u) times the weight of the disc's chord at u,
 *
 *        m(u) = integral over |v| < s of c_K (1 - (u^2 + v^2)/R^2)^K dv
 *             = c_K R B (1 - u^2/R^2)^(K + 1/2),   s = sqrt(R^2 - u^2),
 *
 *    (v = s t: the integrand is c_K (s/R)^(2K) (1 - t^2)^K, B = integral
 *    from -1 to 1 of (1 - t^2)^K = sum_j binom(K, j) (-1)^j 2/(2j + 1),
 *    c_K = (K + 1)/(pi R^2): patterns/README.md, "Filters"), the outer
 *    integral taken by GSL's 64-point Gauss-Legendre rule in theta, u = R
 *    sin theta (whose integrand, cos^(2K + 2) theta times an affine
 *    function of sin theta, is smooth: the rule is exact to rounding
 *    there); and the half-plane y < y0 under the same ramp along y, the
 *    same integral in v; within 1e-14.  The ramp's encoding's sliver
 *    (decode(encode(v)) 2.3e-9 below v on a strip 7.3e-9 (b - a) wide)
 *    changes these by less than 1e-16.
 */
#include "bench.h"
#include "core.h"
#include "patterns.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const char *const filters[] = {"radial:k=1,r=1", "radial:k=2,r=1.5", "radial:k=3,r=2",
                                      NULL};

/* The filters each case takes (TIER, tier.h).  The quick tier (this file):
 * each scene under one filter (the reference's quadrature takes 1 to 3 s
 * of CPU a scene and filter here; the closed forms take all three).  The
 * full tier, test_analytic_radial_gradient_full.c (this file with
 * TIER_FULL set): the two scenes under the filters the quick tier leaves
 * out (`make test` runs both tiers), the first at 40x35 px (each filter on
 * a third of its columns) and the stroke under all three.  Under the
 * sanitizers the full tier runs a declared subset: each case under one
 * filter, every filter reached (another filter on the same scene takes
 * the same code paths with other numbers; tests/README.md, "Tiers"), the
 * plain build running everything. */

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "anaradgrad");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* The size in pixels of the view whose scene is being built (scenes_*_px). */
static int W, H;

/* analytic against the reference under each filter of fl (TIER above) */
static void against(const char *what, const aa_scene *s, int w, int h, const char *const *fl)
{
    support_method_against_filters("analytic", what, s, w, h, fl);
}

#if TIER_FULL
/* analytic against the reference under `filter` on a part of the view
 * (support_method_against_part) */
static double against_part(const char *what, const aa_scene *s, int sw, int sh, int x0, int y0,
                           int w, int h, const char *filter)
{
    return support_method_against_part("analytic", what, s, sw, sh, x0, y0, w, h, filter);
}
#endif

static const aa_gradient_stop three[4] = {{0.0, {{0.9, 0.05, 0.2}}, 1.0},
                                          {0.45, {{0.1, 0.8, 0.3}}, 1.0},
                                          {0.45, {{0.2, 0.1, 0.7}}, 1.0},
                                          {1.0, {{1.0, 0.95, 0.6}}, 1.0}};
static const aa_gradient_stop two[2] = {{0.15, {{0.0, 0.3, 0.05}}, 1.0},
                                        {0.8, {{0.6, 1.0, 0.1}}, 1.0}};
static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};

/* A path of lines and a cubic arc (padded gradient, a sharp step) in
 * front of a rectangle under a repeated gradient, over the background. */
static aa_scene *lines_and_cubic(int w, int h)
{
    W = w, H = h;
    double sx = w / 16.0, sy = h / 14.0;
    aa_scene *s = aa_scene_new((aa_rgb){{0.2, 0.3, 0.4}});
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_rect_px(s, W, H, 1.3 * sx, 2.1 * sy, 14.6 * sx, 12.2 * sy);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                       (const double[6]){3 * sx, 1 * sy, 8.6 * sx, 3.6 * sy, 0, 0}, two, 2, 0);
    scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
    scenes_move_px(s, W, H, 2.4 * sx, 1.6 * sy);
    scenes_line_px(s, W, H, 13.7 * sx, 3.1 * sy);
    assert_int_equal(aa_scene_cubic_to(s, 17.0 * sx / W, 9.0 * sy / H, 4.0 * sx / W,
                                       6.0 * sy / H, 6.2 * sx / W, 12.9 * sy / H),
                     AA_OK);
    scenes_line_px(s, W, H, 1.9 * sx, 9.4 * sy);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                       (const double[6]){2 * sx, 3 * sy, 12 * sx, 11 * sy, 0, 0}, three, 4, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_lines_and_cubic(void **state)
{
    (void)state;
    aa_scene *s = lines_and_cubic(16, 14);
    against("lines and a cubic", s, 16, 14,
            TIER(FILTERS("radial:k=1,r=1"), FILTERS("radial:k=2,r=1.5", "radial:k=3,r=2"),
                 FILTERS("radial:k=3,r=2")));
    aa_scene_free(s);
#if TIER_FULL
    /* The 40x35 view: each filter on a third of its columns, filters[k] on
     * [x0[k], x0[k + 1]), so that the three check every pixel once (the
     * sanitizer build's subset: radial:k=2,r=1.5 on the middle third): the
     * reference's quadrature of the whole view under each filter was most
     * of this test's time (the plain run 29.5 s of CPU, with thirds 18.7
     * s; tests/README.md).  Each third, 35 rows high, crosses the
     * rectangle's top and bottom and the path's top line; the left one the
     * rectangle's and the path's left sides, the middle and right ones the
     * cubic arc, the right one the rectangle's right side, the top line's
     * corner and the arc's bulge: the same layers, gradients and pieces at
     * the same scale as the whole view, on the same pixel squares, and the
     * filter the same code with other numbers (gcov: tests/README.md,
     * "Tiers"). */
    static const int x0[4] = {0, 13, 26, 40};
    s = lines_and_cubic(40, 35);
    const char *const *fl = TIER(NULL, filters, FILTERS("radial:k=2,r=1.5"));
    double worst = 0.0;
    for (; *fl; fl++) {
        int k = 0;
        while (strcmp(filters[k], *fl))
            k++;
        worst = fmax(worst, against_part("lines and a cubic, 40 px", s, 40, 35, x0[k], 0,
                                         x0[k + 1] - x0[k], 35, *fl));
    }
    print_message("%-28s largest difference over the filters %.1e\n", "lines and a cubic, 40 px",
                  worst);
    aa_scene_free(s);
#endif
}

/* A circle under a reflected gradient and a turned ellipse under a padded
 * one (elliptical arcs), over a flat rectangle they overlap. */
static void test_arcs(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"14\">\n"
        "<linearGradient id=\"f\" x1=\"3.1\" y1=\"2.2\" x2=\"5.3\" y2=\"4.9\"\n"
        " gradientUnits=\"userSpaceOnUse\" spreadMethod=\"reflect\"\n"
        " color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.1\" stop-color=\"#f02010\"/>\n"
        " <stop offset=\"0.9\" stop-color=\"#30e0c0\"/>\n"
        "</linearGradient>\n"
        "<linearGradient id=\"p\" x1=\"8.2\" y1=\"12.1\" x2=\"14.6\" y2=\"7.3\"\n"
        " gradientUnits=\"userSpaceOnUse\" color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.2\" stop-color=\"#2040c0\"/>\n"
        " <stop offset=\"0.8\" stop-color=\"#f0f0a0\"/>\n"
        "</linearGradient>\n"
        "<rect x=\"1.3\" y=\"7.4\" width=\"12.2\" height=\"4.9\" fill=\"#806040\"/>\n"
        "<circle cx=\"5.3\" cy=\"5.9\" r=\"3.7\" fill=\"url(#f)\"/>\n"
        "<ellipse cx=\"10.6\" cy=\"9.3\" rx=\"4.1\" ry=\"2.3\"\n"
        " transform=\"rotate(30 10.6 9.3)\" fill=\"url(#p)\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "arcs.svg", svg, 16, 14);
    against("circle and turned ellipse", s, 16, 14,
            TIER(FILTERS("radial:k=2,r=1.5"), FILTERS("radial:k=1,r=1", "radial:k=3,r=2"),
                 FILTERS("radial:k=1,r=1")));
    aa_scene_free(s);
}

#if TIER_FULL
/* A stroked cubic (its outline: offset curves, its inner offset folding
 * at the sharp turn) under a reflected gradient, over a flat circle. */
static void test_stroke(void **state)
{
    (void)state;
    static const char svg[] =
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"14\">\n"
        "<linearGradient id=\"g\" x1=\"2\" y1=\"3\" x2=\"6.5\" y2=\"5\"\n"
        " gradientUnits=\"userSpaceOnUse\" spreadMethod=\"reflect\"\n"
        " color-interpolation=\"linearRGB\">\n"
        " <stop offset=\"0.15\" stop-color=\"#ff3010\"/>\n"
        " <stop offset=\"0.85\" stop-color=\"#1050ff\"/>\n"
        "</linearGradient>\n"
        "<circle cx=\"8\" cy=\"7\" r=\"4.5\" fill=\"#404060\"/>\n"
        "<path d=\"M2.1,2.3 C14.7,1.2 0.8,12.9 13.9,11.6\" fill=\"none\" stroke=\"url(#g)\"\n"
        " stroke-width=\"2.1\"/>\n"
        "</svg>\n";
    aa_scene *s = scenes_svg_text(dir, "stroke.svg", svg, 16, 14);
    against("stroked cubic", s, 16, 14, TIER(NULL, filters, FILTERS("radial:k=3,r=2")));
    aa_scene_free(s);
}
#endif

/* The closed form of the opening comment: the value at a pixel centre of
 * the half-plane u < d under the ramp c0 + g u (u measured from the
 * centre), under radial:k=K,r=R. */
typedef struct chord_ramp {
    double R, K, c0, g;
} chord_ramp;

static double chord_integrand(double th, void *arg)
{
    const chord_ramp *q = arg;
    double u = q->R * sin(th), c = cos(th), B = 0.0, bin = 1.0;
    for (int j = 0; j <= (int)q->K; j++) {
        B += bin * (j % 2 ? -2.0 : 2.0) / (2 * j + 1);
        bin = bin * (q->K - j) / (j + 1);
    }
    double cK = (q->K + 1.0) / (M_PI * q->R * q->R);
    /* m(u) du = c_K R B cos^(2K+1) th  R cos th d th */
    return (q->c0 + q->g * u) * cK * q->R * B * pow(c, 2.0 * q->K + 1.0) * q->R * c;
}

static double half_plane_value(double R, double K, double d, double c0, double g)
{
    chord_ramp q = {R, K, c0, g};
    gsl_function F = {chord_integrand, &q};
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(64);
    assert_non_null(t);
    double hi = d >= R ? M_PI / 2 : (d <= -R ? -M_PI / 2 : asin(d / R));
    double v = gsl_integration_glfixed(&F, -M_PI / 2, hi, t);
    gsl_integration_glfixed_table_free(t);
    return v;
}

static void test_half_planes(void **state)
{
    (void)state;
    W = 14, H = 12;
    /* the ramp from a to b, the half-plane's edge at e (x, or y) */
    const double a = -3.25, b = 17.5, e = 7.3;
    for (int axis = 0; axis < 2; axis++)
        for (const char *const *f = filters; *f; f++) {
            aa_filter filt;
            assert_int_equal(aa_filter_parse(*f, &filt), AA_OK);
            double K = filt.spec.v[0], R = filt.spec.v[1], worst = 0.0;
            aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
            scenes_layer(s, 0, 0, 0, AA_FILL_NONZERO);
            if (axis == 0)
                scenes_rect_px(s, W, H, -30, -30, e, H + 30);
            else
                scenes_rect_px(s, W, H, -30, -30, W + 30, e);
            scenes_gradient_px(s, W, H, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                               axis == 0 ? (const double[6]){a, 0, b, 0, 0, 0}
                                         : (const double[6]){0, a, 0, b, 0, 0},
                               black_white, 2, 0);
            assert_int_equal(aa_scene_finish(s), AA_OK);
            aa_image img;
            support_render("analytic", s, *f, W, H, 1, &img, NULL);
            /* pixels along the ramp's axis, the edge's distance from the
             * centre from -R - 1.2 (none) to R + 1.3 (the whole disc) */
            for (int k = 2; k <= 11; k++) {
                int i = axis == 0 ? k : 4, j = axis == 0 ? 5 : k;
                double c = (axis == 0 ? i : j) + 0.5, d = e - c;
                double want = half_plane_value(R, K, d, (c - a) / (b - a), 1.0 / (b - a));
                for (int ch = 0; ch < 3; ch++) {
                    double v = aa_pixel(&img, i, j)[ch];
                    if (!(fabs(v - want) <= 1e-14))
                        fail_msg("half-plane %s < %g under %s at pixel (%d, %d): %.17g, "
                                 "closed form %.17g",
                                 axis == 0 ? "x" : "y", e, *f, i, j, v, want);
                    worst = fmax(worst, fabs(v - want));
                }
            }
            print_message("half-plane %s < %g, ramp along it, %-18s max |v - closed form| "
                          "%.1e\n",
                          axis == 0 ? "x" : "y", e, *f, worst);
            aa_image_free(&img);
            aa_scene_free(s);
        }
}

int main(void)
{
    print_message("tier: %s\n", TIER_NAME);
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_half_planes),
                                       cmocka_unit_test(test_lines_and_cubic),
                                       cmocka_unit_test(test_arcs),
#if TIER_FULL
                                       cmocka_unit_test(test_stroke),
#endif
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
