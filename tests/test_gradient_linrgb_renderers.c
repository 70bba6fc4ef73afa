/*
 * test_gradient_linrgb_renderers.c: gradients in linear light
 * (color-interpolation: linearRGB on the gradient element; patterns/README.md,
 * "Gradients") drawn by the exact box reference against headless Chromium,
 * which draws the property, and resvg, which ignores it.
 *
 * One document of four bands, each a full-width rectangle of one paint:
 *  0. red to blue, the property on the gradient (at t = 0.504 Chromium
 *     draws (187, 0, 188): encode(0.496), encode(0.504); interpolated in
 *     sRGB-encoded values it would be (126, 0, 129));
 *  1. black at opacity 0 to red at opacity 1 over white, the property
 *     inherited from <defs> (not premultiplied: Chromium's (221, 126, 126)
 *     at t = 0.504 is encode(0.504) at opacity 0.504 over white);
 *  2. a focal radial gradient of three stops, reflected, inherited from a
 *     <g> inside <defs>;
 *  3. black to white in a rectangle of opacity 1/2 over red: the layer's
 *     colour interpolated in linear light, then composited in encoded
 *     values as every layer is.
 * The reference's colours are compared with Chromium's on the pixels where
 * the picture is smooth (the reference's encoded second differences under
 * 6/255 over the pixel's 3 x 3 neighbourhood, as in
 * tests/test_gradient_renderers.c), each band to 3/255 in encoded values
 * (Chromium interpolates in 8 bits and Skia dithers gradients).  Chromium is
 * the oracle for what the picture should be; the hand-worked colours above
 * check the reference at the middle pixel of band 0 (to 2e-3: the pixel's
 * mean against the colour at its centre).  resvg ignores the property: its
 * bands are compared with the reference of the same document without it
 * (sRGB interpolation) to 3/255, which is what it draws, and its difference
 * from the linear-light reference is printed (it is resvg's error).  The
 * linear-light document's reference is drawn once, for both.
 */
/* tier: full */
#include "bench.h"
#include "core.h"
#include "patterns.h"
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

#define W 96
#define BAND 16
#define NB 4
#define H (BAND * NB)

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "linrgbrender");
}

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests), where the renderers are not run, the references are
 * drawn on three parts of the view's columns, the whole height: [0, 8) and
 * [88, 96) (the gradients' ends, the threshold's low t) and [28, 52) (band
 * 0's middle pixel (48, 8), the radial gradient's centre and focus), each a
 * view of its own (support_scene_part): the same paths of the reference with
 * fewer pixels (tests/README.md, "Tiers", says how that was checked); *ref is
 * the middle part, from column X0.  The plain build draws the whole view and
 * compares it with the renderers. */
#if SAN_SUBSET
#define X0 28
#else
#define X0 0
#endif

/* The linear-light document's reference, drawn once for both tests */
static aa_image lin_ref;
static char lin_path[4200];

static int teardown(void **state)
{
    (void)state;
    aa_image_free(&lin_ref);
    return support_rmtree(dir);
}

/* sRGB's encoding (IEC 61966-2-1), written out here. */
static double enc(double v)
{
    if (v <= 0)
        return 0;
    if (v >= 1)
        return 1;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

/* The document, in linear light (lin) or with every color-interpolation
 * left out; its path into path and its box reference into ref. */
static void draw_document(int lin, char *path, size_t len, aa_image *ref)
{
    const char *ci = lin ? " color-interpolation=\"linearRGB\"" : "";
    const char *cs = lin ? " style=\"color-interpolation: linearRGB\"" : "";
    char doc[4096];
    int m = snprintf(
        doc, sizeof doc,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n"
        "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n"
        "<linearGradient id=\"rb\"%s gradientUnits=\"userSpaceOnUse\" x2=\"%d\">"
        "<stop stop-color=\"red\"/><stop offset=\"1\" stop-color=\"blue\"/></linearGradient>\n"
        "<defs%s><linearGradient id=\"cr\" gradientUnits=\"userSpaceOnUse\" x2=\"%d\">"
        "<stop stop-color=\"black\" stop-opacity=\"0\"/><stop offset=\"1\" stop-color=\"red\"/>"
        "</linearGradient>\n"
        "<g%s><radialGradient id=\"rad\" gradientUnits=\"userSpaceOnUse\" cx=\"48\" cy=\"40\" "
        "r=\"30\" fx=\"30\" fy=\"37\" spreadMethod=\"reflect\"><stop stop-color=\"#20ff40\"/>"
        "<stop offset=\"0.4\" stop-color=\"#000010\"/><stop offset=\"1\" stop-color=\"#ff8000\"/>"
        "</radialGradient>\n"
        "<linearGradient id=\"kw\" gradientUnits=\"userSpaceOnUse\" x2=\"%d\"><stop/>"
        "<stop offset=\"1\" stop-color=\"white\"/></linearGradient></g></defs>\n"
        "<rect width=\"%d\" height=\"%d\" fill=\"url(#rb)\"/>\n"
        "<rect y=\"%d\" width=\"%d\" height=\"%d\" fill=\"url(#cr)\"/>\n"
        "<rect y=\"%d\" width=\"%d\" height=\"%d\" fill=\"url(#rad)\"/>\n"
        "<rect y=\"%d\" width=\"%d\" height=\"%d\" fill=\"red\"/>\n"
        "<rect y=\"%d\" width=\"%d\" height=\"%d\" fill=\"url(#kw)\" opacity=\"0.5\"/>\n"
        "</svg>\n",
        W, H, W, H, ci, W, ci, W, cs, W, W, BAND, BAND, W, BAND, 2 * BAND, W, BAND, 3 * BAND, W,
        BAND, 3 * BAND, W, BAND);
    assert_true(m > 0 && m < (int)sizeof doc);
    snprintf(path, len, "%s/%s.svg", dir, lin ? "linear" : "srgb");
    support_write_file(path, doc, (size_t)m);
    char spec[4200];
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    support_view v = {W, H, 0, 0, 0, NULL, 1, 0, 0};
    aa_truth_stats stats;
    if (!SAN_SUBSET) {
        support_pattern_reference(spec, &v, ref, NULL, &stats);
    } else { /* columns [x0, x0 + w) of the view, for each part below */
        static const int parts[3][2] = {{0, 8}, {88, 8}, {X0, 24}};
        aa_spec sp;
        aa_scene *s = NULL;
        if (aa_pattern_parse(spec, &sp) || aa_pattern_scene_at(&sp, W, H, &s))
            fail_msg("pattern %s: %s", spec, aa_last_error());
        double most = 0;
        for (int k = 0; k < 3; k++) {
            aa_scene *part = support_scene_part(s, W, H, parts[k][0], 0, parts[k][1], H);
            aa_image other;
            v.w = parts[k][1];
            support_reference(part, &v, k == 2 ? ref : &other, NULL, &stats);
            if (k < 2)
                aa_image_free(&other);
            most = fmax(most, stats.max_bound);
            aa_scene_free(part);
        }
        stats.max_bound = most;
        aa_scene_free(s);
    }
    print_message("%s: the reference's largest bound %.2g\n", lin ? "linear light" : "sRGB",
                  stats.max_bound);
    assert_true(stats.max_bound <= 1e-12);
}

/* The same, the linear-light one's reference drawn once (lin_ref) and
 * shared by the tests: *ref points to it, or to out for the other. */
static void document(int lin, char *path, size_t len, const aa_image **ref, aa_image *out)
{
    if (!lin) {
        draw_document(0, path, len, out);
        *ref = out;
        return;
    }
    if (!lin_ref.v)
        draw_document(1, lin_path, sizeof lin_path, &lin_ref);
    snprintf(path, len, "%s", lin_path);
    *ref = &lin_ref;
}

/* 1 if the picture is smooth about pixel (i, j) within its band: every
 * channel's encoded second differences along x and y under 6/255 over its
 * 3 x 3 neighbourhood, none of it on the band's edge rows. */
static int smooth(const aa_image *ref, int i, int j)
{
    if (i < 2 || i > W - 3 || j % BAND < 2 || j % BAND > BAND - 3)
        return 0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++)
            for (int c = 0; c < 3; c++) {
                int x = i + di, y = j + dj;
                double e = enc(aa_pixel(ref, x, y)[c]);
                double dx = enc(aa_pixel(ref, x - 1, y)[c]) + enc(aa_pixel(ref, x + 1, y)[c]) - 2 * e;
                double dy = enc(aa_pixel(ref, x, y - 1)[c]) + enc(aa_pixel(ref, x, y + 1)[c]) - 2 * e;
                if (!(fabs(dx) < 6.0 / 255 && fabs(dy) < 6.0 / 255))
                    return 0;
            }
    return 1;
}

/* Each band's largest encoded difference between img and ref on the
 * smooth pixels into worst[] (codes); the counts into count[]. */
static void compare(const aa_image *img, const aa_image *ref, double worst[NB], int count[NB])
{
    for (int b = 0; b < NB; b++)
        worst[b] = 0, count[b] = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            if (!smooth(ref, i, j))
                continue;
            count[j / BAND]++;
            for (int c = 0; c < 3; c++) {
                double d = fabs(enc(aa_pixel(ref, i, j)[c]) - enc(aa_pixel(img, i, j)[c]));
                worst[j / BAND] = fmax(worst[j / BAND], 255 * d);
            }
        }
}

/* Runs renderer `name` on the document at path into img; 0 if it is not
 * installed. */
static int run(const char *name, const char *path, aa_image *img)
{
    const char *tree = aa_source_tree();
    if (!tree) {
        print_message("%s skipped: no source tree (its adapters)\n", name);
        return 0;
    }
    char adapter[4200], cmd[13000], png[4300];
    snprintf(adapter, sizeof adapter, "%s/scripts/renderers/%s", tree, name);
    assert_null(strchr(adapter, '\''));
    assert_null(strchr(dir, '\''));
    snprintf(cmd, sizeof cmd, "'%s' --check >/dev/null 2>&1", adapter);
    if (system(cmd) != 0) {
        print_message("%s skipped: not installed (sh scripts/install-deps.sh "
                      "--with-renderers)\n",
                      name);
        return 0;
    }
    snprintf(png, sizeof png, "%s/%s.png", dir, name);
    snprintf(cmd, sizeof cmd, "'%s' '%s' %d %d '%s' >/dev/null", adapter, path, W, H, png);
    if (system(cmd) != 0 || aa_image_read(png, img))
        fail_msg("%s failed on %s: %s", name, path, aa_last_error());
    assert_int_equal(img->w, W);
    assert_int_equal(img->h, H);
    return 1;
}

static const char *const what[NB] = {"red to blue", "opacity 0 to 1 (from <defs>)",
                                     "focal radial, reflect", "in a layer of opacity 1/2"};

static void test_chromium(void **state)
{
    (void)state;
    char path[4200];
    const aa_image *ref;
    aa_image img;
    document(1, path, sizeof path, &ref, NULL);
    /* band 0's middle pixel (48, 8), t = 48.5 / 96: (encode(1 - t), 0,
     * encode(t)) */
    const double t = 48.5 / W, want[3] = {enc(1 - t), 0, enc(t)};
    for (int c = 0; c < 3; c++)
        if (!(fabs(enc(aa_pixel(ref, 48 - X0, 8)[c]) - want[c]) < 2e-3))
            fail_msg("the reference at (48, 8), channel %d: %.4f, not %.4f", c,
                     enc(aa_pixel(ref, 48 - X0, 8)[c]), want[c]);
#if defined(__SANITIZE_ADDRESS__)
    print_message("chromium: compared in the plain build (the references above run here)\n");
    skip();
#endif
    if (!run("chromium", path, &img))
        skip();
    double worst[NB];
    int count[NB];
    compare(&img, ref, worst, count);
    /* the control: Chromium is far from the sRGB interpolation there */
    const double srgb_mid = 0.5 * (enc(1.0) + enc(0.0));
    double far = fabs(enc(aa_pixel(&img, 48, 8)[0]) - srgb_mid);
    print_message("chromium at (48, 8): (%.0f, %.0f, %.0f); interpolated in sRGB it would be "
                  "about (%.0f, 0, %.0f)\n",
                  255 * enc(aa_pixel(&img, 48, 8)[0]), 255 * enc(aa_pixel(&img, 48, 8)[1]),
                  255 * enc(aa_pixel(&img, 48, 8)[2]), 255 * (1 - t), 255 * t);
    assert_true(far > 40.0 / 255);
    int bad = 0;
    for (int b = 0; b < NB; b++) {
        print_message("chromium, %s: %d smooth pixels, largest difference %.1f/255\n", what[b],
                      count[b], worst[b]);
        if (count[b] < 200 || !(worst[b] <= 3.0 + 1e-9))
            bad++;
    }
    if (bad)
        fail_msg("chromium: %d bands differ from the reference beyond 3/255 (or too few "
                 "smooth pixels)",
                 bad);
    aa_image_free(&img);
}

static void test_resvg(void **state)
{
    (void)state;
    char path[4200], path0[4200];
    const aa_image *ref, *ref0;
    aa_image img, own0;
    document(1, path, sizeof path, &ref, NULL);
    document(0, path0, sizeof path0, &ref0, &own0);
#if defined(__SANITIZE_ADDRESS__)
    print_message("resvg: compared in the plain build (the references above run here)\n");
    aa_image_free(&own0);
    skip();
#endif
    if (!run("resvg", path, &img)) {
        aa_image_free(&own0);
        skip();
    }
    double worst[NB], worst0[NB];
    int count[NB], count0[NB];
    compare(&img, ref, worst, count);
    compare(&img, ref0, worst0, count0);
    int bad = 0;
    for (int b = 0; b < NB; b++) {
        print_message("resvg, %s: against the linear-light reference %.1f/255 (resvg ignores "
                      "color-interpolation: its error); against the sRGB one %.1f/255 over %d "
                      "smooth pixels\n",
                      what[b], worst[b], worst0[b], count0[b]);
        if (count0[b] < 200 || !(worst0[b] <= 3.0 + 1e-9))
            bad++;
    }
    assert_true(worst[0] > 40.0); /* it does ignore the property */
    if (bad)
        fail_msg("resvg: %d bands differ from the sRGB interpolation's reference beyond 3/255",
                 bad);
    aa_image_free(&img);
    aa_image_free(&own0);
}

/* the cases this build runs (SAN_SUBSET, above), said first */
static int start(void **state)
{
    SAN_CASES_PRINT();
    return setup(state);
}

SUPPORT_MAIN(start, teardown, cmocka_unit_test(test_chromium), cmocka_unit_test(test_resvg))
