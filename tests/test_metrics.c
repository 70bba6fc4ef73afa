/*
 * test_metrics.c: the error metrics on cases worked by hand.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

static void fill_ramp(aa_image *im)
{
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            for (int c = 0; c < im->c; c++)
                aa_pixel(im, i, j)[c] = 0.1 + 0.5 * (i + 2.0 * j + c) / (im->w + 2.0 * im->h + 3);
}

/* img = ref + d everywhere: rmse = mae = max = d, psnr = -20 log10 d; the
 * error is constant, so all its power is at zero frequency: d^2, all low. */
static void test_constant_offset(void **state)
{
    (void)state;
    aa_image ref, img;
    aa_metrics m;
    const double d = 0.01;
    assert_int_equal(aa_image_alloc(&ref, 24, 16, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&img, 24, 16, 3), AA_OK);
    fill_ramp(&ref);
    for (size_t k = 0; k < 24 * 16 * 3; k++)
        img.v[k] = ref.v[k] + d;
    assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_OK);
    assert_true(fabs(m.rmse - d) < 1e-15 && fabs(m.mae - d) < 1e-15);
    assert_true(fabs(m.max_err - d) < 1e-15);
    assert_true(fabs(m.psnr - 40.0) < 1e-9);
    assert_true(fabs(m.alias_total - d * d) < 1e-17 && fabs(m.alias_low - d * d) < 1e-17);
    assert_true(m.alias_high < 1e-25);
    assert_true(m.ssim < 1.0 && m.ssim > 0.9);
    aa_image_free(&ref);
    aa_image_free(&img);
}

/* One channel of one pixel wrong by d in an N-pixel, C-channel image:
 * rmse = d / sqrt(N C), mae = d / (N C), max = d there; the channel mean
 * error is an impulse of d / C, whose spectrum is flat: total (d/C)^2 / N,
 * split in proportion to the number of frequencies in each band. */
static void test_one_pixel(void **state)
{
    (void)state;
    const int w = 20, h = 12, c = 3;
    const double d = 0.5;
    aa_image ref, img;
    aa_metrics m;
    assert_int_equal(aa_image_alloc(&ref, w, h, c), AA_OK);
    assert_int_equal(aa_image_alloc(&img, w, h, c), AA_OK);
    fill_ramp(&ref);
    memcpy(img.v, ref.v, sizeof(double) * w * h * c);
    aa_pixel(&img, 13, 7)[2] -= d;
    assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_OK);
    double n = (double)w * h;
    assert_true(fabs(m.rmse - d / sqrt(n * c)) < 1e-15);
    assert_true(fabs(m.mae - d / (n * c)) < 1e-15);
    assert_true(m.max_err == d || fabs(m.max_err - d) < 1e-15);
    assert_true(m.max_at[0] == 13 && m.max_at[1] == 7 && m.max_at[2] == 2);
    assert_true(fabs(m.alias_total - (d / c) * (d / c) / n) < 1e-15);
    /* frequencies with |f| < 1/4: x indices 0..4 and 16..19 of 20 (|i/20| < 1/4
     * means i in {0,1,2,3,4} and -i in {1..4}): 9; y of 12: {0,1,2} and
     * {-1,-2}: 5; so 45 of 240 */
    assert_true(fabs(m.alias_low / m.alias_total - 45.0 / 240.0) < 1e-12);
    aa_image_free(&ref);
    aa_image_free(&img);
}

/* A pure cosine error of amplitude A along x with f cycles across the
 * image: mean power A^2 / 2, all at frequency f / W: in the low band if
 * f / W < 1/4, else in the high band. */
static void test_sinusoid(void **state)
{
    (void)state;
    const int w = 64, h = 8;
    const double A = 0.02;
    int freqs[2] = {5, 24};
    for (int t = 0; t < 2; t++) {
        aa_image ref, img;
        aa_metrics m;
        assert_int_equal(aa_image_alloc(&ref, w, h, 1), AA_OK);
        assert_int_equal(aa_image_alloc(&img, w, h, 1), AA_OK);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                aa_pixel(&ref, i, j)[0] = 0.5;
                aa_pixel(&img, i, j)[0] = 0.5 + A * cos(2 * M_PI * freqs[t] * i / w);
            }
        assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_OK);
        assert_true(fabs(m.alias_total - A * A / 2) < 1e-15);
        double in_band = t == 0 ? m.alias_low : m.alias_high;
        double out_band = t == 0 ? m.alias_high : m.alias_low;
        assert_true(fabs(in_band - A * A / 2) < 1e-15 && out_band < 1e-20);
        /* rmse = A / sqrt 2 too */
        assert_true(fabs(m.rmse - A / sqrt(2.0)) < 1e-15);
        aa_image_free(&ref);
        aa_image_free(&img);
    }
}

static void test_identical_and_encoded(void **state)
{
    (void)state;
    aa_image ref, img;
    aa_metrics m;
    assert_int_equal(aa_image_alloc(&ref, 30, 20, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&img, 30, 20, 3), AA_OK);
    fill_ramp(&ref);
    memcpy(img.v, ref.v, sizeof(double) * 30 * 20 * 3);
    assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_OK);
    assert_true(m.rmse == 0 && m.max_err == 0 && isinf(m.psnr) && m.ssim == 1.0);
    /* after Crow's square law, an error of d at value v becomes
     * sqrt(v + d) - sqrt(v): ref 0.25 everywhere, img 0.36 gives 0.1 */
    for (size_t k = 0; k < 30 * 20 * 3; k++)
        ref.v[k] = 0.25, img.v[k] = 0.36;
    aa_encode square;
    assert_int_equal(aa_encode_parse("gamma:2", &square), AA_OK);
    assert_int_equal(aa_metrics_compute(&ref, &img, &square, &m), AA_OK);
    assert_true(fabs(m.rmse - 0.11) < 1e-15 && fabs(m.rmse_enc - 0.1) < 1e-15);
    aa_image_free(&img);
    assert_int_equal(aa_image_alloc(&img, 30, 21, 3), AA_OK);
    assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_EINVAL);
    aa_image_free(&ref);
    aa_image_free(&img);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_constant_offset),
             cmocka_unit_test(test_one_pixel),
             cmocka_unit_test(test_sinusoid),
             cmocka_unit_test(test_identical_and_encoded))
