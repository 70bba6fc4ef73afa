/*
 * test_gradient_linrgb.c: gradients that interpolate their stops in linear
 * light (color-interpolation: linearRGB on the gradient element;
 * aa_scene_set_gradient_interpolation, harness/core/scene.c;
 * patterns/README.md, "Gradients"): the scene's colour, the exact box
 * reference (harness/truth/truth.c, "gradients in linear light"), the SVG
 * reader (patterns/svgfile.c) and the methods that refuse it.
 *
 * Known answers, derived here and not from the code under test:
 *  - in linear light a stop pair interpolates the linear channels, v(t) =
 *    v0 + t (v1 - v0), and the layer's encoded colour is encode(v(t)); an
 *    opaque layer with nothing over it composites to that encoded colour,
 *    whose decoding is v(t) again (encode and decode are inverse: IEC
 *    61966-2-1), so the picture is the linear ramp itself.  A pixel's box
 *    mean of an affine function is its value at the pixel's centre, so a
 *    black-to-white ramp from x = a to x = b gives pixel i (inside [a, b])
 *    (i + 1/2 - a) / (b - a), and its sum over the image is H ((b - a) / 2
 *    + (W - b)).  (The two pieces of the standard do not meet exactly:
 *    encode's power piece at v = 0.0031308 is 0.0404499, below decode's
 *    threshold 0.04045, so decode(encode(v)) differs from v by less than
 *    1e-8 for v in (0.0031308, 0.0031308073) only; over a ramp of slope
 *    1/8 per pixel that changes a pixel by under 1e-8 x 7.3e-9 x 8 < 1e-15.)
 *    Red to blue: R = 1 - (mean t), B = mean t, G = 0;
 *  - a centred radial gradient black to white (pad) over a rectangle that
 *    holds its disc of radius r: t = rho / r, the picture t inside, 1
 *    outside, so the box reference sums to 2 pi r^2 int_0^1 t t dt + (the
 *    rectangle's area - pi r^2) = 2 pi r^2 / 3 + W H - pi r^2;
 *  - repeat and reflect of the black-to-white ramp over whole periods: each
 *    period's mean is 1/2, so the sum is W H / 2;
 *  - stop opacity: Chromium draws black at opacity 0 to red at opacity 1
 *    over white as (221, 126, 126) at t = 0.504 (measured with
 *    scripts/renderers/chromium), the composite of the colour encode(t, 0,
 *    0) at opacity t, not premultiplied (premultiplied, red would keep 255):
 *    the encoded composite is then R = t encode(t) + 1 - t, G = B = 1 - t,
 *    and a pixel's box mean is the mean of their decodings over its span
 *    of t, by GSL's QAGP here from that formula.
 * The sampling methods converge to the reference; a grid's mean of the
 * opaque ramp (affine) is exact on pixels without a kink.
 */
#include "bench.h"
#include "core.h"
#include "patterns.h"
#include "support.h"
#include "truth.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#define W 16
#define H 12

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return support_tmpdir(dir, sizeof dir, "linrgb");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* sRGB's transfer functions (IEC 61966-2-1), written out here. */
static double enc(double v)
{
    if (v <= 0.0)
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static double dec(double e)
{
    if (e <= 0.0)
        return 0.0;
    if (e >= 1.0)
        return 1.0;
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* A rectangle [x0, x1] x [y0, y1] in pixels as a layer of the scene. */
static void rect_px(aa_scene *s, double x0, double y0, double x1, double y1)
{
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0 / W, y1 / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* A gradient whose coordinates are pixels, on the layer added last, in
 * linear light. */
static void grad_px(aa_scene *s, int kind, int spread, const double p[6],
                    const aa_gradient_stop *st, int n)
{
    aa_gradient g = {kind, spread, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0}, n, st};
    memcpy(g.p, p, sizeof g.p);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB), AA_OK);
}

static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};
static const aa_gradient_stop red_blue[2] = {{0.0, {{1, 0, 0}}, 1.0}, {1.0, {{0, 0, 1}}, 1.0}};
static const aa_gradient_stop clear_red[2] = {{0.0, {{0, 0, 0}}, 0.0},
                                              {1.0, {{1, 0, 0}}, 1.0}};

/* The box reference of s (pattern units) at W x H, its bound checked
 * against 1e-12. */
static void reference(const char *what, const aa_scene *s, aa_image *ref)
{
    support_view v = {W, H, 0, 0, 0, NULL, 1, 0, 0};
    aa_truth_stats stats;
    support_reference(s, &v, ref, NULL, &stats);
    print_message("%s: the reference's largest bound %.2g\n", what, stats.max_bound);
    if (!(stats.max_bound <= 1e-12))
        fail_msg("%s: the reference's bound %.3g is above 1e-12", what, stats.max_bound);
}

static double channel_sum(const aa_image *im, int ch)
{
    double s = 0.0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            s += aa_pixel(im, i, j)[ch];
    return s;
}

/* ---- the scene's colour ---- */

static void test_scene_colour(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{1, 1, 1}});
    rect_px(s, 0, 0, W, H);
    /* no gradient on the layer yet */
    assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB),
                     AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "without a gradient layer"));
    aa_gradient g = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {0, 0, 100, 0, 0, 0},
                     {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, red_blue};
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_set_gradient_interpolation(s, 7), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "unknown gradient interpolation 7"));
    assert_int_equal(aa_scene_layer_gradient_interpolation(s, 0), AA_INTERPOLATE_SRGB);
    assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB), AA_OK);
    rect_px(s, 0, 0, W, H); /* behind: its colour, no gradient */
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_layer_gradient_interpolation(s, 0), AA_INTERPOLATE_LINEAR_RGB);
    assert_int_equal(aa_scene_layer_gradient_interpolation(s, 1), AA_INTERPOLATE_SRGB);
    assert_int_equal(aa_scene_layer_gradient_interpolation(s, 9), AA_INTERPOLATE_SRGB);
    aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
    assert_non_null(placed);
    assert_int_equal(aa_scene_layer_gradient_interpolation(placed, 0),
                     AA_INTERPOLATE_LINEAR_RGB);
    int wind[2] = {1, 1};
    /* t = x / 100 along the row: the linear channels (1 - t, 0, t) */
    for (int k = 0; k <= 8; k++) {
        double x = 0.125 * k * W, t = x / 100;
        aa_rgb c = aa_scene_colour_of_at(placed, wind, x, 3.0);
        double e[3];
        aa_scene_encoded_of_at(placed, wind, x, 3.0, e);
        if (!(fabs(c.c[0] - (1 - t)) < 1e-14 && c.c[1] == 0.0 && fabs(c.c[2] - t) < 1e-14 &&
              fabs(e[0] - enc(1 - t)) < 1e-14 && fabs(e[2] - enc(t)) < 1e-14))
            fail_msg("t = %g: (%.17g, %g, %.17g), encoded (%.17g, %.17g), not linear light", t,
                     c.c[0], c.c[1], c.c[2], e[0], e[2]);
    }
    aa_scene_free(placed);
    aa_scene_free(s);

    /* stop opacity: the channels not premultiplied (Chromium's (221, 126,
     * 126) at t = 0.504: the opening comment) */
    s = aa_scene_new((aa_rgb){{1, 1, 1}});
    rect_px(s, 0, 0, W, H);
    grad_px(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){0, 0, 1, 0, 0, 0},
            clear_red, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    placed = aa_scene_place(s, W, H, 0, 0, 0);
    int w1[1] = {1};
    for (int k = 1; k < 8; k++) {
        double t = k / 8.0, e[3];
        aa_scene_encoded_of_at(placed, w1, t, 1.0, e);
        if (!(fabs(e[0] - (t * enc(t) + 1 - t)) < 1e-14 && fabs(e[1] - (1 - t)) < 1e-14))
            fail_msg("stop opacity at t = %g: encoded (%.17g, %.17g), not (%.17g, %.17g)", t,
                     e[0], e[1], t * enc(t) + 1 - t, 1 - t);
    }
    double e[3];
    aa_scene_encoded_of_at(placed, w1, 0.504, 1.0, e);
    print_message("black at 0 to red at 1 over white, t = 0.504: (%.1f, %.1f, %.1f)/255 "
                  "(Chromium (221, 126, 126))\n",
                  255 * e[0], 255 * e[1], 255 * e[2]);
    assert_true(fabs(255 * e[0] - 221) < 1 && fabs(255 * e[1] - 126) < 1);
    aa_scene_free(placed);
    aa_scene_free(s);
}

/* ---- the reference: closed forms ---- */

/* Black to white (and red to blue) in linear light from x = a to x = b
 * across the whole image, padded: every pixel inside [a, b] is its
 * centre's value, and the sum H ((b - a) / 2 + W - b). */
static void test_ramp(void **state)
{
    (void)state;
    const double a = 3.25, b = 11.5;
    for (int pair = 0; pair < 2; pair++) {
        aa_scene *s = aa_scene_new((aa_rgb){{0.3, 0.1, 0.7}});
        rect_px(s, 0, 0, W, H);
        grad_px(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){a, 0, b, 0, 0, 0},
                pair ? red_blue : black_white, 2);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref;
        reference(pair ? "red to blue" : "black to white", s, &ref);
        double worst = 0.0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                double t = (i + 0.5 - a) / (b - a);
                if (i + 1 <= a)
                    t = 0.0;
                else if (i >= b)
                    t = 1.0;
                else if (!(i >= a && i + 1 <= b))
                    continue; /* a pixel across a or b: the sum below */
                const double want[3] = {pair ? 1 - t : t, pair ? 0 : t, t};
                for (int c = 0; c < 3; c++) {
                    double d = fabs(aa_pixel(&ref, i, j)[c] - want[c]);
                    worst = fmax(worst, d);
                    if (!(d <= 1e-12))
                        fail_msg("pixel (%d, %d) channel %d: %.17g, not %.17g", i, j, c,
                                 aa_pixel(&ref, i, j)[c], want[c]);
                }
            }
        double want = H * ((b - a) / 2 + W - b), got = channel_sum(&ref, 2);
        print_message("%s: pixels within %.2g of their centres' values; sum %.15g, closed "
                      "form %.15g\n",
                      pair ? "red to blue" : "black to white", worst, got, want);
        if (!(fabs(got - want) <= 1e-12 * want))
            fail_msg("the sum %.17g is not %.17g", got, want);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
}

/* Repeat and reflect over whole periods (the ramp 4 pixels long, the image
 * 16 wide): the sum W H / 2. */
static void test_spreads(void **state)
{
    (void)state;
    for (int sp = AA_SPREAD_REFLECT; sp <= AA_SPREAD_REPEAT; sp++) {
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        rect_px(s, 0, 0, W, H);
        grad_px(s, AA_GRADIENT_LINEAR, sp, (const double[6]){0, 0, 4, 0, 0, 0}, black_white, 2);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref;
        reference(sp == AA_SPREAD_REPEAT ? "repeat" : "reflect", s, &ref);
        double got = channel_sum(&ref, 0), want = W * H / 2.0;
        print_message("%s: sum %.15g, closed form %.15g\n",
                      sp == AA_SPREAD_REPEAT ? "repeat" : "reflect", got, want);
        if (!(fabs(got - want) <= 1e-12 * want))
            fail_msg("the sum %.17g is not %.17g", got, want);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
}

/* A centred radial gradient black to white over its disc: the sum 2 pi
 * r^2 / 3 + W H - pi r^2. */
static void test_radial(void **state)
{
    (void)state;
    const double r = 5.0;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_px(s, 0, 0, W, H);
    grad_px(s, AA_GRADIENT_RADIAL, AA_SPREAD_PAD, (const double[6]){8, 6, r, 8, 6, 0},
            black_white, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref;
    reference("radial", s, &ref);
    double got = channel_sum(&ref, 1), want = 2 * M_PI * r * r / 3 + W * H - M_PI * r * r;
    print_message("radial: sum %.15g, closed form %.15g (diff %.2g)\n", got, want, got - want);
    if (!(fabs(got - want) <= 1e-12 * want))
        fail_msg("the sum %.17g is not %.17g", got, want);
    aa_image_free(&ref);
    aa_scene_free(s);
}

/* Black at opacity 0 to red at opacity 1 over white from x = 0 to W:
 * pixel i is the mean over t in [i / W, (i + 1) / W] of the decoded
 * composite (the opening comment), by QAGP with the encoding's change of
 * piece as a breakpoint. */
static double clear_red_channel(double t, void *p)
{
    int ch = *(const int *)p;
    return ch == 0 ? dec(t * enc(t) + 1 - t) : dec(1 - t);
}

static void test_stop_opacity(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{1, 1, 1}});
    rect_px(s, 0, 0, W, H);
    grad_px(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){0, 0, W, 0, 0, 0},
            clear_red, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref;
    reference("stop opacity", s, &ref);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    double worst = 0.0;
    for (int i = 0; i < W; i++)
        for (int ch = 0; ch < 2; ch++) {
            double lo = (double)i / W, hi = (i + 1.0) / W, pts[3] = {lo, 0.0031308, hi}, v, err;
            int np = lo < 0.0031308 && hi > 0.0031308 ? 3 : 2;
            if (np == 2)
                pts[1] = hi;
            gsl_function F = {clear_red_channel, &ch};
            assert_int_equal(gsl_integration_qagp(&F, pts, (size_t)np, 1e-15, 1e-14, 200, ws,
                                                  &v, &err),
                             GSL_SUCCESS);
            v /= hi - lo;
            for (int j = 0; j < H; j++) {
                double d = fabs(aa_pixel(&ref, i, j)[ch] - v);
                worst = fmax(worst, d);
                if (!(d <= 1e-12))
                    fail_msg("pixel (%d, %d) channel %d: %.17g, QAGP %.17g", i, j, ch,
                             aa_pixel(&ref, i, j)[ch], v);
            }
        }
    print_message("stop opacity: every pixel within %.2g of QAGP\n", worst);
    gsl_integration_workspace_free(ws);
    aa_image_free(&ref);
    aa_scene_free(s);
}

/* ---- methods ---- */

/* point and supersample draw it (they sample the scene): on pixels without
 * a kink the grid's mean of the opaque ramp is exact; area draws the opaque
 * ramp with nothing over it exactly (algorithms/area_gradient.c, "linear
 * light": decode(encode(v)) = v) within 1e-12 of the reference on every
 * pixel, the kinks' too, and a black-to-white ramp crossing 0.0031308 inside
 * a pixel (where the standard's two pieces do not meet); it refuses the
 * layer at alpha 1/2 at its first pixel, naming linear light; cairo and agg refuse
 * it naming linear light. */
static void test_methods(void **state)
{
    (void)state;
    const double a = 3.25, b = 11.5;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_px(s, 0, 0, W, H);
    grad_px(s, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){a, 0, b, 0, 0, 0},
            red_blue, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref;
    reference("methods", s, &ref);
    static const char *const sampling[] = {"point", "supersample:n=4"};
    for (int k = 0; k < 2; k++) {
        aa_image img;
        support_render(sampling[k], s, NULL, W, H, 1, &img, NULL);
        double worst = 0.0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                if (!(i + 1 <= a || i >= b || (i >= a && i + 1 <= b)))
                    continue;
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fabs(aa_pixel(&img, i, j)[c] - aa_pixel(&ref, i, j)[c]));
            }
        print_message("%s: within %.2g of the reference off the kinks\n", sampling[k], worst);
        if (!(worst <= 1e-12))
            fail_msg("%s: %.3g from the reference", sampling[k], worst);
        aa_image_free(&img);
    }
    for (int pair = 0; pair < 2; pair++) {
        aa_scene *s2 = s;
        if (pair) { /* black to white over 400 px, v = 0.0031308 at x = 0.5 */
            s2 = aa_scene_new((aa_rgb){{0, 0, 0}});
            rect_px(s2, 0, 0, W, H);
            grad_px(s2, AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                    (const double[6]){0.5 - 0.0031308 * 400, 0, 400.5 - 0.0031308 * 400, 0, 0,
                                      0},
                    black_white, 2);
            assert_int_equal(aa_scene_finish(s2), AA_OK);
        }
        print_message("area, %s:\n", pair ? "black to white across 0.0031308" : "red to blue");
        support_method_against_reference("area", pair ? "across" : "red to blue", s2, W, H,
                                         NULL);
        if (pair)
            aa_scene_free(s2);
    }
    {
        aa_scene *s3 = aa_scene_new((aa_rgb){{0, 0, 0}});
        rect_px(s3, 0, 0, W, H);
        grad_px(s3, AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){a, 0, b, 0, 0, 0},
                red_blue, 2);
        assert_int_equal(aa_scene_set_alpha(s3, 0.5), AA_OK);
        assert_int_equal(aa_scene_finish(s3), AA_OK);
        const support_view v = {.w = W, .h = H, .filter = "box", .seed = 1, .threads = 1};
        aa_image img;
        int st = support_render_view("area", s3, &v, &img, NULL);
        print_message("area at alpha 1/2: %s\n", aa_last_error());
        assert_int_equal(st, AA_EINVAL);
        /* the first pixel: its region's composite is checked for every
         * stop segment, not only where t lies */
        assert_non_null(strstr(aa_last_error(), "pixel (0, 0)"));
        assert_non_null(strstr(aa_last_error(), "linear light"));
        aa_scene_free(s3);
    }
    static const char *const refusing[] = {"cairo", "agg"};
    for (int k = 0; k < 2; k++) {
        const support_view v = {.w = W, .h = H, .filter = "box", .seed = 1, .threads = 1};
        aa_image img;
        int st = support_render_view(refusing[k], s, &v, &img, NULL);
        print_message("%s: %s\n", refusing[k], aa_last_error());
        assert_int_equal(st, AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), refusing[k]));
        assert_non_null(strstr(aa_last_error(), "linear light"));
    }
    aa_image_free(&ref);
    aa_scene_free(s);
}

/* ---- the SVG reader ---- */

/* The scene of `body` inside a root <svg> of W x H pixels, or NULL. */
static aa_scene *svg_scene(const char *name, const char *body)
{
    char path[4200], doc[8192], spec[4400];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    snprintf(doc, sizeof doc,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" "
             "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" height=\"%d\">\n%s\n"
             "</svg>\n",
             W, H, body);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec sp;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &sp) || aa_pattern_scene_at(&sp, W, H, &sc))
        return NULL;
    return sc;
}

#define RB "<stop stop-color=\"red\"/><stop offset=\"1\" stop-color=\"blue\"/>"
#define RECT(id) "<rect width=\"16\" height=\"12\" fill=\"url(#" id ")\"/>"

/* color-interpolation is the gradient element's property, inherited
 * through its own ancestors (SVG 1.1, "color-interpolation": inherited),
 * not from the shape it paints and not through href (which passes
 * attributes and stops): each document's gradient is in linear light
 * (1) or not (0); for those in linear light the colour at the middle of
 * the 16-pixel ramp is (1/2, 0, 1/2) in linear light, not the sRGB
 * interpolation's decode(1/2). */
static void test_svg(void **state)
{
    (void)state;
    static const struct {
        const char *body;
        int lin;
    } docs[] = {
        {"<linearGradient id=\"g\" color-interpolation=\"linearRGB\">" RB "</linearGradient>"
         RECT("g"), 1},
        {"<linearGradient id=\"g\" style=\"color-interpolation: linearRGB\">" RB
         "</linearGradient>" RECT("g"), 1},
        {"<style>linearGradient { color-interpolation: linearRGB }</style>"
         "<linearGradient id=\"g\">" RB "</linearGradient>" RECT("g"), 1},
        {"<defs color-interpolation=\"linearRGB\"><linearGradient id=\"g\">" RB
         "</linearGradient></defs>" RECT("g"), 1},
        {"<defs style=\"color-interpolation: linearRGB\"><g><radialGradient id=\"g\" r=\"2\">"
         RB "</radialGradient></g></defs>" RECT("g"), 1},
        {"<defs color-interpolation=\"linearRGB\"><linearGradient id=\"g\" "
         "color-interpolation=\"inherit\">" RB "</linearGradient></defs>" RECT("g"), 1},
        /* the nearest value decides */
        {"<defs color-interpolation=\"linearRGB\"><linearGradient id=\"g\" "
         "color-interpolation=\"sRGB\">" RB "</linearGradient></defs>" RECT("g"), 0},
        {"<defs color-interpolation=\"linearRGB\"><linearGradient id=\"g\" "
         "color-interpolation=\"auto\">" RB "</linearGradient></defs>" RECT("g"), 0},
        /* not through href: g takes a's stops, not its property */
        {"<linearGradient id=\"a\" color-interpolation=\"linearRGB\">" RB "</linearGradient>"
         "<linearGradient id=\"g\" href=\"#a\"/>" RECT("g"), 0},
        {"<linearGradient id=\"a\">" RB "</linearGradient>"
         "<linearGradient id=\"g\" xlink:href=\"#a\" color-interpolation=\"linearRGB\"/>"
         RECT("g"), 1},
        /* not from the shape's ancestors (linearRGB on what is drawn is
         * refused: below) */
        {"<defs color-interpolation=\"linearRGB\"><linearGradient id=\"g\">" RB
         "</linearGradient></defs><g color-interpolation=\"sRGB\">" RECT("g") "</g>", 1},
    };
    for (size_t k = 0; k < sizeof docs / sizeof *docs; k++) {
        char name[32];
        snprintf(name, sizeof name, "doc%zu", k);
        aa_scene *sc = svg_scene(name, docs[k].body);
        if (!sc)
            fail_msg("%s: %s", docs[k].body, aa_last_error());
        int n = aa_scene_layer_count(sc), layer = -1;
        for (int l = 0; l < n; l++)
            if (aa_scene_layer_gradient(sc, l, NULL))
                layer = l;
        assert_true(layer >= 0);
        int got = aa_scene_layer_gradient_interpolation(sc, layer) == AA_INTERPOLATE_LINEAR_RGB;
        if (got != docs[k].lin)
            fail_msg("%s: %s, not %s", docs[k].body, got ? "linear light" : "sRGB",
                     docs[k].lin ? "linear light" : "sRGB");
        aa_gradient g;
        aa_scene_layer_gradient(sc, layer, &g);
        if (docs[k].lin && g.kind == AA_GRADIENT_LINEAR) {
            aa_scene *placed = aa_scene_place(sc, W, H, 0, 0, 0);
            int *wind = calloc((size_t)n, sizeof *wind);
            assert_non_null(wind);
            wind[layer] = 1;
            aa_rgb c = aa_scene_colour_of_at(placed, wind, 8.0, 6.0);
            if (!(fabs(c.c[0] - 0.5) < 1e-14 && fabs(c.c[2] - 0.5) < 1e-14))
                fail_msg("%s: (%.17g, %g, %.17g) at the middle, not (1/2, 0, 1/2)",
                         docs[k].body, c.c[0], c.c[1], c.c[2]);
            free(wind);
            aa_scene_free(placed);
        }
        aa_scene_free(sc);
    }
    /* compositing in linear light (the property on what is drawn) is
     * still refused, naming the element */
    aa_scene *sc = svg_scene("drawn", "<g color-interpolation=\"linearRGB\" opacity=\"0.5\">"
                                      "<rect width=\"4\" height=\"4\"/></g>");
    assert_null(sc);
    print_message("refused: %s\n", aa_last_error());
    assert_non_null(strstr(aa_last_error(), "<g>"));
    assert_non_null(strstr(aa_last_error(), "linearRGB"));
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_scene_colour), cmocka_unit_test(test_ramp),
             cmocka_unit_test(test_spreads), cmocka_unit_test(test_radial),
             cmocka_unit_test(test_stop_opacity), cmocka_unit_test(test_methods),
             cmocka_unit_test(test_svg))
