/*
 * test_adaptive.c: Ramos and Borges' adaptive scanline method.
 *
 *  - On crow 256x256 box, with tag=1, it reaches the RMSE of supersample:n=4
 *    with fewer samples in total (both measured against the exact reference).
 *  - On a single straight edge the value converges to the exact coverage as
 *    the search deepens: the coverage is found independently by clipping
 *    the pixel square with the half-plane (Sutherland-Hodgman) and the
 *    shoelace formula; the paper's argument (the centroid of the two found
 *    points lies on the edge) bounds the error by the search resolution,
 *    2^-depth of a border.
 *  - A band thinner than a pixel that misses the corners is lost without
 *    tagging (the paper's case 6d) and found with it.
 */
#include "bench.h"

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
    aa_filter f;
    aa_spec m;
    aa_job job;
    aa_filter_default(&f);
    assert_int_equal(aa_method_parse(method, &f, &m), AA_OK);
    assert_int_equal(aa_job_init(&job, scene, w, h, 0, 0, 0, &f, 1, threads), AA_OK);
    assert_int_equal(aa_image_alloc(out, w, h, 3), AA_OK);
    assert_int_equal(aa_method_run(&m, &job, 1, out, c, NULL), AA_OK);
    aa_job_free(&job);
}

static double rmse(const aa_image *a, const aa_image *b)
{
    double s = 0.0;
    size_t n = (size_t)3 * a->w * a->h;
    for (size_t k = 0; k < n; k++)
        s += (a->v[k] - b->v[k]) * (a->v[k] - b->v[k]);
    return sqrt(s / n);
}

static void test_crow_against_supersample(void **state)
{
    (void)state;
    aa_spec spec;
    aa_scene *s, *placed;
    aa_filter f;
    aa_image ref, ad, ss;
    aa_counters cad, css;
    aa_filter_default(&f);
    assert_int_equal(aa_pattern_parse("crow", &spec), AA_OK);
    assert_int_equal(aa_pattern_scene(&spec, &s), AA_OK);
    assert_non_null(placed = aa_scene_place(s, 256, 256, 0, 0, 0));
    assert_int_equal(aa_image_alloc(&ref, 256, 256, 3), AA_OK);
    assert_int_equal(aa_truth_render(placed, &f, 0, &ref, NULL, NULL), AA_OK);
    render("adaptive:tag=1", s, 256, 256, 2, &ad, &cad); /* the extension, not the default */
    render("supersample:n=4", s, 256, 256, 2, &ss, &css);
    double ea = rmse(&ad, &ref), es = rmse(&ss, &ref);
    if (!(ea <= es && cad.samples < css.samples))
        fail_msg("adaptive rmse %.6g with %llu samples; supersample:n=4 %.6g with %llu", ea,
                 (unsigned long long)cad.samples, es, (unsigned long long)css.samples);
    /* the corners alone are (W+1)(H+1) samples */
    assert_true(cad.samples > 257u * 257u);
    aa_image_free(&ref);
    aa_image_free(&ad);
    aa_image_free(&ss);
    aa_scene_free(placed);
    aa_scene_free(s);
}

/* The half-plane y < a + b x (pattern units) as a large white quad. */
static aa_scene *half_plane(double a, double b)
{
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, -1, -2), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2, -2), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2, a + 2 * b), AA_OK);
    assert_int_equal(aa_scene_line_to(s, -1, a - b), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The area of the unit pixel [i, i+1] x [j, j+1] (pixel units) where
 * v < A + B u: the square clipped by the half-plane, then the shoelace. */
static double pixel_coverage(int i, int j, double A, double B)
{
    double in[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}, out[8][2];
    int n = 0;
    for (int k = 0; k < 4; k++) {
        const double *p = in[k], *q = in[(k + 1) % 4];
        double dp = A + B * p[0] - p[1], dq = A + B * q[0] - q[1];
        if (dp >= 0)
            out[n][0] = p[0], out[n][1] = p[1], n++;
        if ((dp >= 0) != (dq >= 0)) {
            double t = dp / (dp - dq);
            out[n][0] = p[0] + t * (q[0] - p[0]), out[n][1] = p[1] + t * (q[1] - p[1]), n++;
        }
    }
    double sum = 0.0;
    for (int k = 0; k < n; k++)
        sum += out[k][0] * out[(k + 1) % n][1] - out[(k + 1) % n][0] * out[k][1];
    return fabs(sum) / 2.0;
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
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, -1, 3.4 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2, 3.4 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 2, 3.6 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, -1, 3.6 / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crow_against_supersample),
        cmocka_unit_test(test_straight_edge_converges),
        cmocka_unit_test(test_thin_band_needs_tagging),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
