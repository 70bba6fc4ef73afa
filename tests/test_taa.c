/*
 * test_taa.c: temporal antialiasing with reprojection (algorithms/taa.c,
 * after Karis 2014) and the lag metric (harness/bench/temporal.c).
 *
 *  - Halton(2,3): the radical inverses of 1, 2, 3, ... are 1/2, 1/4, 3/4,
 *    1/8, 5/8, 3/8, 7/8 in base 2 and 1/3, 2/3, 1/9, 4/9, 7/9, 2/9, 5/9,
 *    8/9 in base 3 (digits reversed behind the point, by hand);
 *  - YCoCg: the primaries and white map to the values of the definition
 *    (Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4, worked
 *    by hand: red (1/4, 1/2, -1/4)), and random colours round-trip within
 *    4 ulp;
 *  - lag on hand-made sequences: references changing linearly in time and
 *    frames that show them d frames late give lag d; frames equal to the
 *    references, or a still reference, give 0;
 *  - a still scene of straight edges (a turned square): the clamp never
 *    acts (each side of a line through a pixel holds a whole neighbouring
 *    pixel), so every pixel is the closed-form steady state of the
 *    exponential history, the weighted mean of the Halton offsets with
 *    weight alpha (1 - alpha)^j / (1 - (1 - alpha)^m) for lag j (a
 *    geometric series), computed here from the scene's colour at each
 *    offset; and as alpha falls with 16 offsets it converges toward the
 *    exact box-filtered image (the reference: the mean of point samples
 *    over the pixel), within 0.015 RMSE, where point sampling is 0.04 away;
 *  - moving (0.37, 0.11) px a frame, the turned square and crow: each
 *    frame's error against its exact reference stays below point
 *    sampling's, the plain history's (which smears) and the clamped
 *    history's without reprojection; on the square at most 0.6 times the
 *    plain history's, with a lag under half a frame where the plain
 *    history's is over 1.5.
 */
#include "bench.h"
#include "frames.h"
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

static void test_halton(void **state)
{
    (void)state;
    const double b2[] = {0, 1 / 2.0, 1 / 4.0, 3 / 4.0, 1 / 8.0, 5 / 8.0, 3 / 8.0, 7 / 8.0};
    const double b3[] = {0,         1 / 3.0, 2 / 3.0, 1 / 9.0, 4 / 9.0,
                         7 / 9.0,   2 / 9.0, 5 / 9.0, 8 / 9.0, 1 / 27.0};
    for (unsigned i = 0; i < 8; i++)
        assert_true(aa__radical_inverse(i, 2) == b2[i]);
    for (unsigned i = 0; i < 10; i++)
        assert_true(fabs(aa__radical_inverse(i, 3) - b3[i]) < 1e-15);
}

static void test_ycocg(void **state)
{
    (void)state;
    const double in[5][3] = {{1, 1, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
    const double want[5][3] = {{1, 0, 0},
                               {0.25, 0.5, -0.25},
                               {0.5, 0, 0.5},
                               {0.25, -0.5, -0.25},
                               {0.5, 0, 0}};
    for (int k = 0; k < 5; k++) {
        double y[3], back[3];
        aa__ycocg_from_rgb(in[k], y);
        aa__rgb_from_ycocg(y, back);
        for (int c = 0; c < 3; c++) {
            assert_true(y[c] == want[k][c]);
            assert_true(back[c] == in[k][c]);
        }
    }
    aa_rng rng;
    aa_rng_seed(&rng, 7, 0, 0);
    double worst = 0;
    for (int k = 0; k < 10000; k++) {
        double rgb[3], y[3], back[3];
        for (int c = 0; c < 3; c++)
            rgb[c] = (double)(aa_rng_next(&rng) >> 11) * 0x1.0p-53;
        aa__ycocg_from_rgb(rgb, y);
        aa__rgb_from_ycocg(y, back);
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(back[c] - rgb[c]));
    }
    print_message("YCoCg round trip: largest difference %.3e\n", worst);
    assert_true(worst <= 4 * 0x1.0p-53);
}

/* ---- lag on hand-made sequences ---- */

static void fill(aa_image *im, int w, int h, double v)
{
    assert_int_equal(aa_image_alloc(im, w, h, 3), AA_OK);
    for (size_t k = 0; k < (size_t)w * h * 3; k++)
        im->v[k] = v;
}

static void test_lag_known(void **state)
{
    (void)state;
    enum { N = 10, W = 4, H = 3 };
    aa_image f[N], r[N];
    aa_temporal tm;
    /* reference k at pixel value q: 0.1 + 0.01 q k (each pixel its rate);
     * frames show reference k - 2 */
    for (int k = 0; k < N; k++) {
        assert_int_equal(aa_image_alloc(&r[k], W, H, 3), AA_OK);
        assert_int_equal(aa_image_alloc(&f[k], W, H, 3), AA_OK);
        for (size_t q = 0; q < (size_t)W * H * 3; q++) {
            r[k].v[q] = 0.1 + 0.01 * (double)q * k;
            f[k].v[q] = 0.1 + 0.01 * (double)q * (k - 2);
        }
    }
    assert_int_equal(aa_temporal_compute(f, r, N, 2, &tm), AA_OK);
    print_message("lag of frames two behind: %.15f\n", tm.lag);
    assert_true(fabs(tm.lag - 2.0) < 1e-12);
    assert_int_equal(aa_temporal_compute(r, r, N, 2, &tm), AA_OK);
    assert_true(tm.lag == 0.0);
    for (int k = 0; k < N; k++) {
        aa_image_free(&f[k]);
        aa_image_free(&r[k]);
        fill(&r[k], W, H, 0.5);
        fill(&f[k], W, H, k % 2 ? 0.25 : 0.75);
    }
    assert_int_equal(aa_temporal_compute(f, r, N, 2, &tm), AA_OK);
    assert_true(tm.lag == 0.0); /* a still reference: nothing to lag */
    for (int k = 0; k < N; k++) {
        aa_image_free(&f[k]);
        aa_image_free(&r[k]);
    }
}

/* ---- still: the closed form, and toward the box filter ---- */

/* A square turned by 0.3 rad, white on black, pattern units. */
static aa_scene *turned_square(void)
{
    double xy[8];
    for (int k = 0; k < 4; k++) {
        double a = 0.3 + k * M_PI / 2;
        xy[2 * k] = 0.5 + 0.32 * cos(a);
        xy[2 * k + 1] = 0.5 + 0.32 * sin(a);
    }
    return scenes_polygon(xy, 4, (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO);
}

static void render(const char *m, const aa_scene *s, int w, int h, double t, double vx,
                   double vy, aa_image *out)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .seed = 3,
                            .threads = 1, .frame_only = 1};
    if (support_render_view(m, s, &v, out, NULL))
        fail_msg("%s: %s", m, aa_last_error());
}

static void reference(const aa_scene *s, int w, int h, double t, double vx, double vy,
                      aa_image *out)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .threads = 1};
    support_reference(s, &v, out, NULL, NULL);
}

static void test_still_edges(void **state)
{
    (void)state;
    const int w = 64, h = 48;
    aa_scene *s = turned_square(), *placed = aa_scene_place(s, w, h, 0, 0, 0);
    aa_image img, form, ref, pt;
    const char *specs[] = {"taa:history=512", "taa:history=512,clamp=clip",
                           "taa:history=512,sample=bilinear"};
    scenes_history_steady(placed, w, h, 5, 8, 0.1, &form);
    for (int k = 0; k < 3; k++) {
        render(specs[k], s, w, h, 5.5, 0, 0, &img);
        double d = support_max_diff(&img, &form, NULL, NULL);
        print_message("%s still: largest difference from the closed form %.3e\n", specs[k], d);
        assert_true(d < 1e-12);
        aa_image_free(&img);
    }
    aa_image_free(&form);
    /* toward the box filter as alpha falls (16 offsets) */
    reference(s, w, h, 5, 0, 0, &ref);
    render("point", s, w, h, 5, 0, 0, &pt);
    double ept = support_rmse(&pt, &ref), last = INFINITY;
    const char *conv[] = {"taa:frames=16,history=512", "taa:frames=16,alpha=0.03,history=1024",
                          "taa:frames=16,alpha=0.01,history=1024"};
    for (int k = 0; k < 3; k++) {
        render(conv[k], s, w, h, 5, 0, 0, &img);
        double e = support_rmse(&img, &ref);
        print_message("%s: RMSE to the exact box image %.3e (point %.3e)\n", conv[k], e, ept);
        assert_true(e < last);
        last = e;
        aa_image_free(&img);
    }
    assert_true(last < 0.015 && ept > 0.04);
    aa_image_free(&pt);
    aa_image_free(&ref);
    aa_scene_free(placed);
    aa_scene_free(s);
}

/* ---- moving: bounded error, no smear ---- */

enum { NF = 8 };

static void frames_of(const char *m, const aa_scene *s, int w, int h, double vx, double vy,
                      const aa_image *refs, double *worst, aa_temporal *tm)
{
    aa_image f[NF];
    *worst = 0;
    for (int k = 0; k < NF; k++) {
        render(m, s, w, h, 40 + k, vx, vy, &f[k]);
        *worst = fmax(*worst, support_rmse(&f[k], &refs[k]));
    }
    assert_int_equal(aa_temporal_compute(f, refs, NF, 6, tm), AA_OK);
    for (int k = 0; k < NF; k++)
        aa_image_free(&f[k]);
}

static void test_moving(void **state)
{
    (void)state;
    const int w = 64, h = 48;
    const double vx = 0.37, vy = 0.11;
    const char *pats[] = {"turned", "crow"};
    for (int p = 0; p < 2; p++) {
        aa_scene *s = p ? scenes_pattern("crow") : turned_square();
        aa_image refs[NF];
        for (int k = 0; k < NF; k++)
            reference(s, w, h, 40 + k, vx, vy, &refs[k]);
        double e_new, e_plain, e_fixed, e_pt;
        aa_temporal t_new, t_plain, t_fixed, t_pt;
        frames_of("taa", s, w, h, vx, vy, refs, &e_new, &t_new);
        frames_of("taa:reproject=none,clamp=none", s, w, h, vx, vy, refs, &e_plain, &t_plain);
        frames_of("taa:reproject=none", s, w, h, vx, vy, refs, &e_fixed, &t_fixed);
        frames_of("point", s, w, h, vx, vy, refs, &e_pt, &t_pt);
        print_message("%s moving: worst frame RMSE taa %.4f, plain %.4f, clamped without "
                      "reprojection %.4f, point %.4f; lag %.2f, %.2f, %.2f, %.2f\n",
                      pats[p], e_new, e_plain, e_fixed, e_pt, t_new.lag, t_plain.lag,
                      t_fixed.lag, t_pt.lag);
        assert_true(e_new < e_pt);
        assert_true(e_new < e_plain && e_new < e_fixed);
        if (!p) /* straight edges: the plain history's trail is wide */
            assert_true(e_new < 0.6 * e_plain && t_plain.lag > 1.5 && fabs(t_new.lag) < 0.5);
        for (int k = 0; k < NF; k++)
            aa_image_free(&refs[k]);
        aa_scene_free(s);
    }
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_halton),
             cmocka_unit_test(test_ycocg),
             cmocka_unit_test(test_lag_known),
             cmocka_unit_test(test_still_edges),
             cmocka_unit_test(test_moving))
