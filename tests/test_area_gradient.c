/*
 * test_area_gradient.c: the exact area method (algorithms/area.c,
 * area_gradient.c) on linear-gradient paint.
 *
 * Known answers, derived here and not from the code under test:
 *  - the sRGB decoding (IEC 61966-2-1) dec(s) = s / 12.92 for s <= T =
 *    0.04045, ((s + 0.055) / 1.055)^2.4 above, and its antiderivative
 *    from 0, D(s) = s^2 / (2 x 12.92) below T and D(T) + (1.055 / 3.4)
 *    (u^3.4 - uT^3.4) above (u = (s + 0.055) / 1.055, du/ds = 1/1.055),
 *    written out by hand here;
 *  - a black-to-white linear ramp across a whole-pixel square (the encoded
 *    value the ramp s = x - i itself, padded): the box value of that
 *    pixel is D(1) - D(0), the integral of dec over [0, 1]; the same ramp
 *    stretched over three pixels gives pixel k the value 3 (D((k + 1)/3)
 *    - D(k/3)), the first of them across the threshold T; at 50% stop
 *    opacity over black, the encoded composite is s / 2 and a pixel's
 *    value 2 (D(1/2) - D(0)) (substituting s = 2 s').
 * The exact reference (harness/truth/truth.c, its own closed form along
 * rows; its gradients are checked against GSL quadrature in two
 * dimensions in tests/test_gradient.c and against Chromium and resvg in
 * tests/test_gradient_renderers.c) is the peer on the other scenes: pad,
 * reflect and repeat, several stops, a sharp step, stop-opacity, rotated
 * and skewed gradientTransform, userSpaceOnUse and objectBoundingBox, a
 * gradient over a flat layer and under a translucent one, a group with
 * opacity, a clip, self-intersecting polygons under both fill rules:
 * every pixel within 1e-12 (support_method_against_reference: at 1 and 2
 * threads, the same bits on both).
 *
 * A negative control: the integration with its split at the threshold T
 * switched off (aa__area_gradient_split = 0, wrong on purpose) must leave
 * the reference by far more than the tolerance, on a ramp that crosses T
 * inside pixels; and the refusals: radial paint, curved edges, a gradient
 * whose colour and opacity change between the same stops, two gradients
 * that show at one pixel (named), while two gradients side by side, or
 * one hidden by an opaque layer in front, are drawn.
 */
#include "bench.h"
#include "core.h"
#include "patterns.h"
#include "support.h"
#include "area_internal.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 24
#define H 20

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "area_gradient");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* the antiderivative of the sRGB decoding from 0 (header) */
static double D(double s)
{
    const double T = 0.04045, uT = (T + 0.055) / 1.055;
    if (s <= T)
        return s * s / (2.0 * 12.92);
    double u = (s + 0.055) / 1.055;
    return T * T / (2.0 * 12.92) + 1.055 / 3.4 * (pow(u, 3.4) - pow(uT, 3.4));
}

/* The scene of `body` inside a root <svg> of w x h pixels over black. */
static aa_scene *svg_scene(const char *name, const char *body, int w, int h, int *st)
{
    char path[4200], doc[8192], spec[4400];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    snprintf(doc, sizeof doc,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n%s\n"
             "</svg>\n",
             w, h, body);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec sp;
    aa_scene *sc = NULL;
    *st = aa_pattern_parse(spec, &sp);
    if (!*st)
        *st = aa_pattern_scene_at(&sp, w, h, &sc);
    return *st ? NULL : sc;
}

static aa_scene *svg_must(const char *name, const char *body, int w, int h)
{
    int st;
    aa_scene *sc = svg_scene(name, body, w, h, &st);
    if (!sc)
        fail_msg("%s: %s", name, aa_last_error());
    return sc;
}

/* ---- closed forms ---- */

static void expect_px(const char *what, const aa_image *im, int i, int j, double want)
{
    for (int c = 0; c < 3; c++) {
        double got = aa_pixel(im, i, j)[c];
        if (!(fabs(got - want) <= 1e-14))
            fail_msg("%s: pixel (%d, %d) channel %d is %.17g, the closed form %.17g (%.1e)",
                     what, i, j, c, got, want, got - want);
    }
}

/* The ramp across whole pixels, black to white (header). */
static void test_closed_form(void **state)
{
    (void)state;
    aa_image im;
    /* one pixel: the square [2, 3] x [1, 2], the ramp from x = 2 to 3 */
    aa_scene *sc = svg_must("one", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" "
                                   "x1=\"2\" x2=\"3\"><stop offset=\"0\"/><stop offset=\"1\" "
                                   "stop-color=\"white\"/></linearGradient>"
                                   "<rect x=\"2\" y=\"1\" width=\"1\" height=\"1\" "
                                   "fill=\"url(#g)\"/>",
                            6, 4);
    support_render("area", sc, NULL, 6, 4, 1, &im, NULL);
    expect_px("one pixel", &im, 2, 1, D(1.0) - D(0.0));
    expect_px("one pixel, beside it", &im, 3, 1, 0.0);
    print_message("ramp over one pixel: %.17g (closed form %.17g)\n", aa_pixel(&im, 2, 1)[0],
                  D(1.0) - D(0.0));
    aa_image_free(&im);
    aa_scene_free(sc);
    /* three pixels: [1, 4] x [0, 2], turned: the ramp runs down y instead */
    sc = svg_must("three", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" "
                           "x1=\"0\" y1=\"1\" x2=\"0\" y2=\"4\"><stop offset=\"0\"/>"
                           "<stop offset=\"1\" stop-color=\"white\"/></linearGradient>"
                           "<rect x=\"0\" y=\"1\" width=\"2\" height=\"3\" fill=\"url(#g)\"/>",
                  3, 5);
    support_render("area", sc, NULL, 3, 5, 1, &im, NULL);
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 2; i++)
            expect_px("three pixels", &im, i, 1 + k, 3.0 * (D((k + 1) / 3.0) - D(k / 3.0)));
    aa_image_free(&im);
    aa_scene_free(sc);
    /* at stop-opacity 0.5 over black: encoded s / 2 */
    sc = svg_must("half", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" "
                          "x1=\"2\" x2=\"3\"><stop offset=\"0\" stop-opacity=\"0.5\"/>"
                          "<stop offset=\"1\" stop-color=\"white\" stop-opacity=\"0.5\"/>"
                          "</linearGradient><rect x=\"2\" y=\"1\" width=\"1\" height=\"1\" "
                          "fill=\"url(#g)\"/>",
                  6, 4);
    support_render("area", sc, NULL, 6, 4, 1, &im, NULL);
    expect_px("half opacity", &im, 2, 1, 2.0 * (D(0.5) - D(0.0)));
    aa_image_free(&im);
    aa_scene_free(sc);
}

/* ---- against the exact reference ---- */

static const struct {
    const char *name, *body;
} scenes[] = {
    {"pad", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"4.3\" y1=\"2\" "
            "x2=\"17.7\" y2=\"9\"><stop offset=\"0\" stop-color=\"#102030\"/>"
            "<stop offset=\"1\" stop-color=\"#f0c080\"/></linearGradient>"
            "<rect x=\"1.5\" y=\"2.25\" width=\"20\" height=\"15.3\" fill=\"url(#g)\"/>"},
    {"reflect", "<linearGradient id=\"g\" x1=\"0.1\" y1=\"0.2\" x2=\"0.35\" y2=\"0.5\" "
                "spreadMethod=\"reflect\"><stop offset=\"0\" stop-color=\"black\"/>"
                "<stop offset=\"0.25\" stop-color=\"#f80\"/><stop offset=\"0.7\" "
                "stop-color=\"#08f\"/><stop offset=\"1\" stop-color=\"white\"/>"
                "</linearGradient><polygon points=\"2.2,1.3 22.7,4.1 17.2,18.6 4.4,15.1\" "
                "fill=\"url(#g)\"/>"},
    {"repeat-step", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"3\" "
                    "y1=\"3\" x2=\"8.5\" y2=\"5\" spreadMethod=\"repeat\">"
                    "<stop offset=\"0.1\" stop-color=\"#000\"/><stop offset=\"0.5\" "
                    "stop-color=\"#ff0\"/><stop offset=\"0.5\" stop-color=\"#00f\"/>"
                    "<stop offset=\"0.9\" stop-color=\"#0f0\"/></linearGradient>"
                    "<rect width=\"24\" height=\"20\" fill=\"url(#g)\"/>"},
    {"stop-opacity", "<rect x=\"3\" y=\"3\" width=\"12\" height=\"12\" fill=\"#c04020\"/>"
                     "<linearGradient id=\"g\" x1=\"0\" x2=\"1\" y2=\"1\">"
                     "<stop offset=\"0\" stop-color=\"#4080ff\" stop-opacity=\"0.1\"/>"
                     "<stop offset=\"0.6\" stop-color=\"#4080ff\" stop-opacity=\"0.9\"/>"
                     "<stop offset=\"0.6\" stop-color=\"#4080ff\" stop-opacity=\"0.3\"/>"
                     "<stop offset=\"1\" stop-color=\"#ffffff\" stop-opacity=\"0.3\"/>"
                     "</linearGradient><polygon points=\"7.3,1.2 22.8,8.9 9.6,18.7\" "
                     "fill=\"url(#g)\"/>"},
    {"transform", "<linearGradient id=\"g\" x1=\"0\" x2=\"0.4\" spreadMethod=\"reflect\" "
                  "gradientTransform=\"rotate(30 0.5 0.5) skewX(20)\">"
                  "<stop offset=\"0\" stop-color=\"#203040\"/><stop offset=\"1\" "
                  "stop-color=\"#e0f0a0\"/></linearGradient>"
                  "<polygon points=\"1.5,2.5 21.5,1.25 19,18.5 3,17\" fill=\"url(#g)\"/>"},
    {"user-transform", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"2\" "
                       "y1=\"2\" x2=\"9\" y2=\"4\" spreadMethod=\"repeat\" "
                       "gradientTransform=\"matrix(0.8 0.3 -0.4 1.1 2 1)\">"
                       "<stop offset=\"0\" stop-color=\"black\"/><stop offset=\"1\" "
                       "stop-color=\"white\"/></linearGradient>"
                       "<g transform=\"translate(1.3 0.7) rotate(7)\">"
                       "<rect x=\"1\" y=\"1\" width=\"18\" height=\"14\" fill=\"url(#g)\"/>"
                       "</g>"},
    {"over-flat", "<rect width=\"24\" height=\"20\" fill=\"#305070\"/>"
                  "<linearGradient id=\"g\" x2=\"0\" y2=\"1\"><stop offset=\"0\" "
                  "stop-color=\"#fff\"/><stop offset=\"1\" stop-color=\"#000\"/>"
                  "</linearGradient><rect x=\"4.5\" y=\"3.5\" width=\"15\" height=\"13\" "
                  "fill=\"url(#g)\" fill-opacity=\"0.6\"/>"
                  "<polygon points=\"0,10 24,4 24,12\" fill=\"#ff8000\" fill-opacity=\"0.4\"/>"},
    {"group", "<rect x=\"2\" y=\"2\" width=\"14\" height=\"10\" fill=\"#0c6\"/>"
              "<linearGradient id=\"g\" x1=\"0\" x2=\"1\"><stop offset=\"0\" "
              "stop-color=\"#f00\"/><stop offset=\"1\" stop-color=\"#00f\"/>"
              "</linearGradient><g opacity=\"0.55\"><rect x=\"6.2\" y=\"5.1\" width=\"15\" "
              "height=\"12\" fill=\"url(#g)\"/><polygon points=\"8,1 20,10 5,19\" "
              "fill=\"#ff0\" fill-opacity=\"0.5\"/></g>"},
    {"clip", "<clipPath id=\"c\"><polygon points=\"3,3 21,5 12,19\"/></clipPath>"
             "<linearGradient id=\"g\" x1=\"0\" x2=\"1\" y2=\"0.5\"><stop offset=\"0\" "
             "stop-color=\"#fe8\"/><stop offset=\"1\" stop-color=\"#148\"/></linearGradient>"
             "<rect width=\"24\" height=\"20\" fill=\"url(#g)\" clip-path=\"url(#c)\"/>"},
    {"crow-polygons", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"2\" "
                      "y1=\"18\" x2=\"20\" y2=\"3\"><stop offset=\"0\" stop-color=\"#000\"/>"
                      "<stop offset=\"0.3\" stop-color=\"#a33\"/><stop offset=\"0.55\" "
                      "stop-color=\"#3a3\"/><stop offset=\"1\" stop-color=\"#fff\"/>"
                      "</linearGradient><rect width=\"24\" height=\"20\" fill=\"url(#g)\"/>"
                      "<polygon points=\"12,1 14.6,7.7 21.9,8 16.2,12.4 18.1,19.3 12,15.4 "
                      "5.9,19.3 7.8,12.4 2.1,8 9.4,7.7\" fill=\"#224\" "
                      "fill-rule=\"evenodd\"/><polygon points=\"3,3 21,17 21,3 3,17\" "
                      "fill=\"url(#g)\" fill-rule=\"nonzero\"/><polygon points=\"11.5,9.5 "
                      "12.5,9.5 12.5,10.5 11.5,10.5\" fill=\"#fff\"/>"},
};

static void test_against_reference(void **state)
{
    (void)state;
    double worst = 0.0;
    for (size_t k = 0; k < sizeof scenes / sizeof *scenes; k++) {
        aa_scene *sc = svg_must(scenes[k].name, scenes[k].body, W, H);
        double d = support_method_against_reference("area", scenes[k].name, sc, W, H, NULL);
        worst = d > worst ? d : worst;
        aa_scene_free(sc);
    }
    print_message("largest difference from the reference over %zu scenes: %.1e\n",
                  sizeof scenes / sizeof *scenes, worst);
}

/* Crowded pixels: 24 random triangles (a fixed stream, drawn here), flat,
 * some translucent, four of them painted with one reflected gradient,
 * over a repeated gradient behind everything, at 48 x 40; the gradient
 * triangles are kept apart from each other (each in its own quarter of
 * the view), so no two gradients show over one point except the one
 * behind, which every gradient triangle hides (opaque stops).  (The
 * reference takes nearly all the time here, more with every gradient
 * layer.) */
static void test_crowded(void **state)
{
    (void)state;
    enum { CW = 48, CH = 40 };
    static char body[32768];
    size_t at = 0;
    at += (size_t)snprintf(body + at, sizeof body - at,
                           "<linearGradient id=\"b\" gradientUnits=\"userSpaceOnUse\" x1=\"0\" "
                           "y1=\"0\" x2=\"13\" y2=\"5\" spreadMethod=\"repeat\"><stop "
                           "offset=\"0\" stop-color=\"#102040\"/><stop offset=\"1\" "
                           "stop-color=\"#e0d0a0\"/></linearGradient>"
                           "<linearGradient id=\"g\" x1=\"0.2\" x2=\"0.6\" y2=\"0.3\" "
                           "spreadMethod=\"reflect\"><stop offset=\"0\" stop-color=\"#f0f\"/>"
                           "<stop offset=\"0.4\" stop-color=\"#0ff\"/><stop offset=\"1\" "
                           "stop-color=\"#000\"/></linearGradient>"
                           "<rect width=\"%d\" height=\"%d\" fill=\"url(#b)\"/>",
                           CW, CH);
    uint64_t x = 0x9e3779b97f4a7c15u;
    for (int k = 0; k < 24; k++) {
        double v[6];
        int cell = k / 6, gradient = k % 6 == 0;
        for (int q = 0; q < 6; q++) {
            double u = support_xorshift(&x);
            /* gradient triangles inside their grid cell, the others anywhere */
            v[q] = gradient ? (q % 2 ? (cell / 2) * 20.0 + 0.25 + 19.5 * u
                                     : (cell % 2) * 24.0 + 0.25 + 23.5 * u)
                            : (q % 2 ? CH : CW) * u;
        }
        at += (size_t)snprintf(
            body + at, sizeof body - at,
            "<polygon points=\"%.6f,%.6f %.6f,%.6f %.6f,%.6f\" fill=\"%s\" fill-opacity=\"%s\"/>",
            v[0], v[1], v[2], v[3], v[4], v[5],
            gradient ? "url(#g)" : (k % 3 == 1 ? "#c84" : "#4c8"),
            gradient ? "1" : (k % 2 ? "0.5" : "1"));
    }
    aa_scene *sc = svg_must("crowded", body, CW, CH);
    support_method_against_reference("area", "crowded", sc, CW, CH, NULL);
    aa_scene_free(sc);
}

/* ---- the negative control ---- */

static void test_threshold_split_matters(void **state)
{
    (void)state;
    /* black to white over 1.6 px: T is crossed inside pixels */
    aa_scene *sc = svg_must("control", "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" "
                                       "x1=\"3.3\" y1=\"0\" x2=\"4.9\" y2=\"0.7\"><stop "
                                       "offset=\"0\"/><stop offset=\"1\" stop-color=\"white\"/>"
                                       "</linearGradient><rect width=\"24\" height=\"20\" "
                                       "fill=\"url(#g)\"/>",
                            W, H);
    aa_image a, r;
    support_reference(sc, &(support_view){.w = W, .h = H, .threads = 1}, &r, NULL, NULL);
    aa__area_gradient_split = 0;
    support_render("area", sc, NULL, W, H, 1, &a, NULL);
    aa__area_gradient_split = 1;
    int wi, wj;
    double off = support_max_diff(&a, &r, &wi, &wj);
    print_message("without the split at T: %.1e from the reference at pixel (%d, %d)\n", off,
                  wi, wj);
    if (!(off > 1e-9))
        fail_msg("the threshold's split removed left the image within %.1e of the reference: "
                 "the comparison cannot see it",
                 off);
    aa_image_free(&a);
    support_render("area", sc, NULL, W, H, 1, &a, NULL);
    support_within_reference("control, split on", NULL, &a, &r, 1e-12);
    aa_image_free(&a);
    aa_image_free(&r);
    aa_scene_free(sc);
}

/* ---- refusals, and what is not refused ---- */

static void expect_refused(const char *name, const char *body, const char *what)
{
    aa_scene *sc = svg_must(name, body, W, H);
    aa_image im;
    int st = support_render_view("area", sc, &(support_view){.w = W, .h = H, .threads = 1},
                                 &im, NULL);
    if (st == AA_OK)
        fail_msg("%s: drawn, not refused", name);
    print_message("%s refused: %s\n", name, aa_last_error());
    if (!strstr(aa_last_error(), what))
        fail_msg("%s: the message \"%s\" does not name \"%s\"", name, aa_last_error(), what);
    aa_scene_free(sc);
}

static void test_refusals(void **state)
{
    (void)state;
    const char *ramp = "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"2\" "
                       "x2=\"20\"><stop offset=\"0\"/><stop offset=\"1\" stop-color=\"white\"/>"
                       "</linearGradient><linearGradient id=\"h\" x2=\"0\" y2=\"1\"><stop "
                       "offset=\"0\" stop-color=\"red\"/><stop offset=\"1\" stop-color=\"blue\"/>"
                       "</linearGradient>";
    char body[4096];
    expect_refused("radial",
                   "<radialGradient id=\"g\"><stop offset=\"0\"/><stop offset=\"1\" "
                   "stop-color=\"white\"/></radialGradient><rect width=\"20\" height=\"10\" "
                   "fill=\"url(#g)\"/>",
                   "radial gradient");
    snprintf(body, sizeof body, "%s<circle cx=\"12\" cy=\"10\" r=\"6\" fill=\"url(#g)\"/>", ramp);
    expect_refused("curved", body, "elliptical arc");
    expect_refused("both-change",
                   "<linearGradient id=\"g\"><stop offset=\"0\" stop-opacity=\"0.2\"/>"
                   "<stop offset=\"1\" stop-color=\"white\"/></linearGradient>"
                   "<rect width=\"20\" height=\"10\" fill=\"url(#g)\"/>",
                   "both colour and opacity");
    snprintf(body, sizeof body,
             "%s<rect x=\"2\" y=\"2\" width=\"10\" height=\"10\" fill=\"url(#g)\"/>"
             "<rect x=\"8\" y=\"6\" width=\"10\" height=\"10\" fill=\"url(#h)\" "
             "fill-opacity=\"0.5\"/>",
             ramp);
    expect_refused("two-gradients", body, "pixel (8, 6)");
    /* drawn: side by side; one hidden where they overlap by an opaque
     * front layer; the one behind an opaque gradient */
    const char *drawn[] = {
        "<rect x=\"2\" y=\"2\" width=\"6\" height=\"10\" fill=\"url(#g)\"/>"
        "<rect x=\"8\" y=\"6\" width=\"10\" height=\"10\" fill=\"url(#h)\"/>",
        "<rect x=\"2\" y=\"2\" width=\"10\" height=\"10\" fill=\"url(#g)\" "
        "fill-opacity=\"0.5\"/><rect x=\"8.5\" y=\"6.5\" width=\"3\" height=\"4\" "
        "fill=\"url(#h)\"/><rect x=\"7\" y=\"5\" width=\"6\" height=\"12\" "
        "fill=\"#123\"/>",
        "<rect x=\"2.5\" y=\"2\" width=\"10\" height=\"10.3\" fill=\"url(#h)\"/>"
        "<rect x=\"8\" y=\"6\" width=\"10\" height=\"10\" fill=\"url(#g)\"/>",
    };
    for (size_t k = 0; k < sizeof drawn / sizeof *drawn; k++) {
        snprintf(body, sizeof body, "%s%s", ramp, drawn[k]);
        aa_scene *sc = svg_must("drawn", body, W, H);
        support_method_against_reference("area", "two, not together", sc, W, H, NULL);
        aa_scene_free(sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form),
        cmocka_unit_test(test_against_reference),
        cmocka_unit_test(test_crowded),
        cmocka_unit_test(test_threshold_split_matters),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
