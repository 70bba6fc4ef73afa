/*
 * test_adaptive.c: Ramos and Borges' adaptive scanline method.
 *
 *  - On crow 256x256 box, with tag=1, it reaches the RMSE of supersample:n=4
 *    with fewer samples in total (both measured against the exact reference).
 *  - On a single straight edge the value converges to the exact coverage as
 *    the search deepens: the coverage is found independently by clipping
 *    the pixel square with the half-plane (Sutherland-Hodgman) and the
 *    shoelace formula (tests/oracle.c); the paper's argument (the centroid of the two found
 *    points lies on the edge) bounds the error by the search resolution,
 *    2^-depth of a border.
 *  - A band thinner than a pixel that misses the corners is lost without
 *    tagging (the paper's case 6d) and found with it.
 */
#include "bench.h"
#include "oracle.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* Render `method` (box filter) of a pattern-unit scene at w x h. */
static void render(const char *method, const aa_scene *scene, int w, int h, int threads,
                   aa_image *out, aa_counters *c)
{
    support_render(method, scene, NULL, w, h, threads, out, c);
}

static void test_crow_against_supersample(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    aa_image ref, ad, ss;
    aa_counters cad, css;
    support_reference(s, &(support_view){.w = 256, .h = 256}, &ref, NULL, NULL);
    render("adaptive:tag=1", s, 256, 256, 2, &ad, &cad); /* the extension, not the default */
    render("supersample:n=4", s, 256, 256, 2, &ss, &css);
    double ea = support_rmse(&ad, &ref), es = support_rmse(&ss, &ref);
    if (!(ea <= es && cad.samples < css.samples))
        fail_msg("adaptive rmse %.6g with %llu samples; supersample:n=4 %.6g with %llu", ea,
                 (unsigned long long)cad.samples, es, (unsigned long long)css.samples);
    /* the corners alone are (W+1)(H+1) samples */
    assert_true(cad.samples > 257u * 257u);
    aa_image_free(&ref);
    aa_image_free(&ad);
    aa_image_free(&ss);
    aa_scene_free(s);
}

/* The half-plane y < a + b x (pattern units) as a large white quad. */
static aa_scene *half_plane(double a, double b)
{
    const double xy[] = {-1, -2, 2, -2, 2, a + 2 * b, -1, a - b};
    return scenes_polygon(xy, 4, white, black, AA_FILL_NONZERO);
}

/* The area of the unit pixel [i, i+1] x [j, j+1] (pixel units) where
 * v < A + B u, i.e. -B u + v <= A: the square clipped by the half-plane,
 * then the shoelace. */
static double pixel_coverage(int i, int j, double A, double B)
{
    const oracle_poly square = {4, {i, i + 1, i + 1, i}, {j, j, j + 1, j + 1}};
    oracle_poly in = oracle_poly_clip(&square, -B, 1, A);
    return oracle_poly_area(&in);
}

static void test_straight_edge_converges(void **state)
{
    (void)state;
    const int W = 32, H = 32;
    const double a = 0.31, b = 0.37; /* y < a + b x, pattern units */
    aa_scene *s = half_plane(a, b);
    /* in pixel units v = H y, u = W x: v < H a + (H/W) b u */
    const double A = H * a, B = (double)H / W * b;
    double prev = INFINITY;
    static const int depths[] = {3, 6, 10, 16, 24};
    for (size_t k = 0; k < sizeof depths / sizeof depths[0]; k++) {
        char spec[64];
        snprintf(spec, sizeof spec, "adaptive:depth=%d", depths[k]);
        aa_image img;
        aa_counters c;
        render(spec, s, W, H, 1, &img, &c);
        double worst = 0.0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                worst = fmax(worst, fabs(aa_pixel(&img, i, j)[0] - pixel_coverage(i, j, A, B)));
        if (!(worst <= ldexp(1.0, -depths[k])))
            fail_msg("depth %d: error %.3g above 2^-%d", depths[k], worst, depths[k]);
        assert_true(worst <= prev);
        prev = worst;
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

static void test_thin_band_needs_tagging(void **state)
{
    (void)state;
    /* 8x8 image; a white band 0.2 px tall across row 3, from 3.4 to 3.6
     * pixels: no pixel corner (integer lines) lies in it */
    const int W = 8, H = 8;
    const double band[1][4] = {{-1, 3.4 / H, 2, 3.6 / H}};
    aa_scene *s = scenes_rects(band, 1);
    aa_image off, on;
    aa_counters c;
    render("adaptive:tag=0", s, W, H, 1, &off, &c);
    render("adaptive:tag=1,depth=10", s, W, H, 1, &on, &c);
    for (int i = 0; i < W; i++) {
        /* lost: the corners all see black */
        assert_true(aa_pixel(&off, i, 3)[0] == 0.0);
        /* found: the cells' corners at v = 3.5 see white; the search finds
         * the band's edges to 2^-10 of a half-pixel border */
        assert_true(fabs(aa_pixel(&on, i, 3)[0] - 0.2) <= 2e-3);
    }
    assert_true(c.expensive_pixels == (uint64_t)W);
    aa_image_free(&off);
    aa_image_free(&on);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_crow_against_supersample),
             cmocka_unit_test(test_straight_edge_converges),
             cmocka_unit_test(test_thin_band_needs_tagging))
