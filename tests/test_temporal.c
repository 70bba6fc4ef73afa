/*
 * test_temporal.c: motion and time (harness/bench/temporal.c, algorithms/taa.c's
 * plain variant, algorithms/cycle.c, and --time/--motion in every method).
 *
 *  - the metrics on hand-computed sequences: a constant offset c between
 *    frames and references gives flicker 0 and eye_rmse c; an offset
 *    alternating +e, -e gives flicker e (population deviation) and, with an
 *    even window, eye_rmse 0; totals 1, 2, 3 give conservation (3-1)/2;
 *    popping counts a dot that blinks and not one that stays;
 *  - every method honours time and motion: a non-temporal method's image at
 *    time t moving v is, bit for bit, its image at time t of the scene
 *    translated by t v (64x64, offsets in 1/4 pixel: both placements round
 *    the same), and a temporal method's image changes with the motion;
 *  - Catmull's picket fence (patterns/README.md, `fence`, built here from its
 *    definition) moving 0.37 px a frame over 8 frames at 128x128: the total
 *    intensity of `area` is constant to 1e-9 relative and equals the fence's
 *    area in pixels (bars of width duty * period clipped to [1/4, 3/4],
 *    height 1/2: summed here in closed form), while `point`'s varies by more
 *    than 10%;
 *  - crow moving slowly: the hexagon's eye image (mean of 6 frames) is
 *    nearer the integrated reference than point's;
 *  - taa's plain history (reproject=none,clamp=none) on a still scene of
 *    crow, thin features included: every pixel is the closed-form steady state, the
 *    weighted mean of the `frames` Halton offsets with weight
 *    alpha (1-alpha)^j / (1 - (1-alpha)^frames) for lag j (derived from
 *    h <- h + alpha (x - h) summed as a geometric series), computed here
 *    from the scene's colour at each offset; and as alpha falls it converges
 *    toward the supersampled image (the equal-weight mean of the 8 offsets);
 *  - cycle on a still scene with one full cycle is supersample's msaa image.
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

/* ---- helpers ---- */

static int render(const char *method, const aa_scene *scene, int w, int h, double t, double vx,
                  double vy, int frame_only, aa_image *out)
{
    /* box, or the Gaussian for a method that forms only circular filters
     * (conetable), or the tent of radius 1 for Crow's tiler: the motion
     * checks below do not depend on the filter */
    support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .seed = 3, .threads = 2,
                      .frame_only = frame_only};
    const char *filters[] = {"box", "gauss", "tent:r=1"};
    for (int k = 0; k < 3; k++) {
        aa_filter f;
        aa_spec spec;
        assert_int_equal(aa_filter_parse(filters[k], &f), AA_OK);
        if (aa_method_parse(method, &f, &spec) != AA_EINVAL) {
            v.filter = k ? filters[k] : NULL;
            break;
        }
    }
    return support_render_view(method, scene, &v, out, NULL);
}

static void reference(const aa_scene *scene, int w, int h, double t, double vx, double vy,
                      aa_image *out)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .threads = 1};
    support_reference(scene, &v, out, NULL, NULL);
}

static double total(const aa_image *im)
{
    double s = 0;
    for (size_t k = 0; k < (size_t)im->w * im->h * 3; k++)
        s += im->v[k];
    return s / 3;
}

static void free_all(aa_image *im, int n)
{
    for (int k = 0; k < n; k++)
        aa_image_free(&im[k]);
}

/* ---- the metrics on hand-computed sequences ---- */

static void fill(aa_image *im, int w, int h, double v)
{
    assert_int_equal(aa_image_alloc(im, w, h, 3), AA_OK);
    for (size_t k = 0; k < (size_t)w * h * 3; k++)
        im->v[k] = v;
}

static void test_metrics_known(void **state)
{
    (void)state;
    enum { N = 8, W = 5, H = 3 };
    aa_image f[N], r[N];
    aa_temporal tm;
    /* a constant offset 0.125 on a changing reference */
    for (int k = 0; k < N; k++) {
        fill(&r[k], W, H, 0.25 + 0.0625 * k);
        fill(&f[k], W, H, 0.25 + 0.0625 * k + 0.125);
    }
    assert_int_equal(aa_temporal_compute(f, r, N, 6, &tm), AA_OK);
    assert_true(tm.flicker_mean < 1e-15 && tm.flicker_max < 1e-15);
    assert_true(fabs(tm.eye_rmse - 0.125) < 1e-15);
    assert_int_equal(tm.frames, N);
    assert_int_equal(tm.window, 6);
    free_all(f, N);
    /* alternating +e, -e */
    const double e = 0.03;
    for (int k = 0; k < N; k++)
        fill(&f[k], W, H, 0.25 + 0.0625 * k + (k % 2 ? -e : e));
    assert_int_equal(aa_temporal_compute(f, r, N, 6, &tm), AA_OK);
    assert_true(fabs(tm.flicker_mean - e) < 1e-15);
    assert_true(fabs(tm.flicker_max - e) < 1e-15);
    assert_true(tm.eye_rmse < 1e-15); /* an even window holds as many +e as -e */
    /* window 1: every frame's own error, e */
    assert_int_equal(aa_temporal_compute(f, r, N, 1, &tm), AA_OK);
    assert_true(fabs(tm.eye_rmse - e) < 1e-15);
    free_all(f, N);
    free_all(r, N);
    /* totals 1, 2, 3 (times the pixel count): spread 2, mean 2 */
    for (int k = 0; k < 3; k++) {
        fill(&f[k], W, H, (k + 1) / 16.0);
        fill(&r[k], W, H, 0.0);
    }
    assert_int_equal(aa_temporal_compute(f, r, 3, 2, &tm), AA_OK);
    assert_true(fabs(tm.conservation - 1.0) < 1e-15);
    /* bad windows and frame counts are refused */
    assert_int_equal(aa_temporal_compute(f, r, 3, 4, &tm), AA_EINVAL);
    assert_int_equal(aa_temporal_compute(f, r, 1, 1, &tm), AA_EINVAL);
    free_all(f, 3);
    free_all(r, 3);
}

/* Two dots on a 16x8 image: dot 0 blinks (1, 0, 1, 0), dot 1 stays at its
 * reference value; references 0.25 each.  Pairs: 3 per dot, 3 pops. */
static void test_popping_known(void **state)
{
    (void)state;
    enum { N = 4 };
    aa_image f[N], r[N];
    const double cx[2] = {3.5, 11.5}, cy[2] = {3.5, 4.0}, shift[2 * N] = {0};
    for (int k = 0; k < N; k++) {
        fill(&f[k], 16, 8, 0.0);
        fill(&r[k], 16, 8, 0.0);
        aa_pixel(&r[k], 3, 3)[0] = aa_pixel(&r[k], 3, 3)[1] = aa_pixel(&r[k], 3, 3)[2] = 0.25;
        aa_pixel(&r[k], 11, 3)[0] = aa_pixel(&r[k], 11, 3)[1] = aa_pixel(&r[k], 11, 3)[2] = 0.25;
        double v = k % 2 ? 0.0 : 1.0;
        aa_pixel(&f[k], 3, 3)[0] = aa_pixel(&f[k], 3, 3)[1] = aa_pixel(&f[k], 3, 3)[2] = v;
        aa_pixel(&f[k], 11, 4)[0] = aa_pixel(&f[k], 11, 4)[1] = aa_pixel(&f[k], 11, 4)[2] = 0.25;
    }
    double pop;
    assert_int_equal(aa_temporal_popping(f, r, N, cx, cy, 2, shift, &pop), AA_OK);
    assert_true(fabs(pop - 0.5) < 1e-15);
    free_all(f, N);
    free_all(r, N);
}

/* ---- every method honours time and motion ---- */

static void test_methods_honour_motion(void **state)
{
    (void)state;
    const int w = 64, h = 64;
    const double t = 2.0, vx = 0.375, vy = -0.25; /* displacement (0.75, -0.5) px */
    aa_scene *s = scenes_pattern("crow");
    aa_scene *moved = aa_scene_transform(s, 1.0, 1.0, t * vx / w, t * vy / h);
    assert_non_null(moved);
    const void *const *table = aa_method_table();
    for (size_t k = 0; table[k]; k++) {
        const aa_method_type *type = table[k];
        const char *name = type->info.name;
        aa_image a, b, still;
        if (render(name, s, w, h, t, vx, vy, 0, &a))
            fail_msg("%s: %s", name, aa_last_error());
        assert_int_equal(render(name, moved, w, h, t, 0, 0, 0, &b), AA_OK);
        assert_int_equal(render(name, s, w, h, t, 0, 0, 0, &still), AA_OK);
        size_t bytes = sizeof(double) * (size_t)w * h * 3;
        if (!(type->flags & AA_METHOD_TEMPORAL)) {
            if (memcmp(a.v, b.v, bytes))
                fail_msg("%s: image at t=%g moving (%g, %g) is not that of the scene moved "
                         "by t v", name, t, vx, vy);
        } else if (!memcmp(a.v, still.v, bytes)) {
            fail_msg("%s: the motion does not change the image", name);
        }
        aa_image_free(&a);
        aa_image_free(&b);
        aa_image_free(&still);
    }
    aa_scene_free(moved);
    aa_scene_free(s);
}

/* ---- Catmull's picket fence ---- */

#define FENCE_P (0.9 / 256)
/* patterns/README.md, `fence`: white where 1/4 <= x <= 3/4, 1/4 <= y <= 3/4 and
 * frac((x - 1/4)/p) < 1/2. */
static aa_scene *fence_scene(double *area)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    *area = 0;
    for (int m = 0;; m++) {
        double x0 = 0.25 + m * FENCE_P, x1 = fmin(0.75, x0 + 0.5 * FENCE_P);
        if (x0 >= 0.75)
            break;
        scenes_rect(s, x0, 0.25, x1, 0.75);
        *area += (x1 - x0) * 0.5;
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void spread(const char *method, const aa_scene *s, double *lo, double *hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    for (int k = 0; k < 8; k++) {
        aa_image im;
        assert_int_equal(render(method, s, 128, 128, k, 0.37, 0.0, 1, &im), AA_OK);
        double v = total(&im);
        *lo = fmin(*lo, v), *hi = fmax(*hi, v);
        aa_image_free(&im);
    }
}

static void test_fence_conservation(void **state)
{
    (void)state;
    double area, lo, hi;
    aa_scene *s = fence_scene(&area);
    area *= 128.0 * 128.0; /* in pixels */
    spread("area", s, &lo, &hi);
    print_message("fence: area totals %.12g .. %.12g, exact %.12g\n", lo, hi, area);
    assert_true((hi - lo) / area < 1e-9);
    assert_true(fabs(lo - area) / area < 1e-9);
    spread("point", s, &lo, &hi);
    print_message("fence: point totals %.6g .. %.6g\n", lo, hi);
    assert_true((hi - lo) / area > 0.10);
    aa_scene_free(s);
}

/* ---- the hexagon's eye on crow ---- */

static double eye_rmse(const char *method, const aa_scene *s, const aa_image *refs, int n)
{
    aa_image f[12];
    aa_temporal tm;
    for (int k = 0; k < n; k++)
        assert_int_equal(render(method, s, 128, 128, k, 0.05, 0.02, 1, &f[k]), AA_OK);
    assert_int_equal(aa_temporal_compute(f, refs, n, 6, &tm), AA_OK);
    free_all(f, n);
    return tm.eye_rmse;
}

static void test_hexagon_eye_beats_point(void **state)
{
    (void)state;
    enum { N = 12 };
    aa_scene *s = scenes_pattern("crow");
    aa_image refs[N];
    for (int k = 0; k < N; k++)
        reference(s, 128, 128, k, 0.05, 0.02, &refs[k]);
    double hex = eye_rmse("hexagon:display=fixed,order=024153", s, refs, N),
           pt = eye_rmse("point", s, refs, N);
    print_message("crow 128x128 moving (0.05, 0.02): eye RMSE hexagon %.4f, point %.4f\n", hex,
                  pt);
    assert_true(hex < pt);
    free_all(refs, N);
    aa_scene_free(s);
}

/* ---- taa and cycle on a still scene ---- */

static void test_taa_still(void **state)
{
    (void)state;
    const int w = 96, h = 64;
    aa_scene *s = scenes_pattern("crow"), *placed = aa_scene_place(s, w, h, 0, 0, 0);
    aa_image img, form, mean;
    /* 0.9^511 ~ 4e-24: the start of the history is gone */
    assert_int_equal(render("taa:reproject=none,clamp=none,history=512", s, w, h, 5.5, 0, 0, 0,
                            &img), AA_OK);
    scenes_history_steady(placed, w, h, 5, 8, 0.1, &form);
    double d = support_max_diff(&img, &form, NULL, NULL);
    print_message("taa still: largest difference from the closed form %.3e\n", d);
    assert_true(d < 1e-12);
    aa_image_free(&img);
    aa_image_free(&form);
    /* toward the equal-weight mean of the 8 offsets as alpha falls (the
     * same formula at alpha -> 0 is the plain mean) */
    scenes_history_steady(placed, w, h, 5, 8, 1e-9, &mean);
    double last = INFINITY;
    const char *specs[] = {"taa:reproject=none,clamp=none,alpha=0.3,history=512",
                           "taa:reproject=none,clamp=none,alpha=0.1,history=512",
                           "taa:reproject=none,clamp=none,alpha=0.02,history=1024"};
    for (int k = 0; k < 3; k++) {
        assert_int_equal(render(specs[k], s, w, h, 5, 0, 0, 0, &img), AA_OK);
        double e = support_rmse(&img, &mean);
        print_message("%s: RMSE to the 8-offset supersampled image %.3e\n", specs[k], e);
        assert_true(e < last);
        last = e;
        aa_image_free(&img);
    }
    assert_true(last < 0.02);
    aa_image_free(&mean);
    aa_scene_free(placed);
    aa_scene_free(s);
}

static void test_cycle_is_msaa(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    const char *pairs[][2] = {{"cycle:positions=msaa8", "supersample:pattern=msaa8"},
                              {"cycle:positions=msaa16", "supersample:pattern=msaa16"},
                              {"cycle:positions=msaa4", "supersample:pattern=msaa4"}};
    for (int k = 0; k < 3; k++) {
        aa_image a, b;
        assert_int_equal(render(pairs[k][0], s, 80, 48, 3.7, 0, 0, 0, &a), AA_OK);
        assert_int_equal(render(pairs[k][1], s, 80, 48, 3.7, 0, 0, 0, &b), AA_OK);
        double d = support_max_diff(&a, &b, NULL, NULL);
        if (!(d < 1e-12))
            fail_msg("%s differs from %s by %.3e", pairs[k][0], pairs[k][1], d);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_metrics_known),
             cmocka_unit_test(test_popping_known),
             cmocka_unit_test(test_methods_honour_motion),
             cmocka_unit_test(test_fence_conservation),
             cmocka_unit_test(test_hexagon_eye_beats_point),
             cmocka_unit_test(test_taa_still),
             cmocka_unit_test(test_cycle_is_msaa))
