/*
 * test_bluenoise.c: void-and-cluster masks (algorithms/bluenoise.c, after
 * Ulichney 1993) and `jitter:seq=bluenoise`, by their power spectra.
 *
 * The spectrum (computed here by a direct discrete Fourier transform, rows
 * then columns): the power |F(k)|^2 of the image less its mean, averaged
 * over the frequencies of each band of radius |k|/N cycles per pixel (the
 * radially averaged power spectrum).  White noise has the same expected
 * power at every frequency, so the ratio of its low band (0 < f <= 1/8) to
 * its high band (3/8 < f <= 1/2) is 1 up to sampling noise; blue noise has
 * little power at low frequencies (Ulichney's "blue noise": the principal
 * frequency high, the low band empty).
 *
 *  - a mask is a permutation of 0 .. side^2 - 1, the same for the same seed
 *    and another for another; bad sides and sigmas are refused;
 *  - the 64 x 64 mask's spectrum has a low/high ratio below 0.1, and so has
 *    its threshold pattern at 10%; a random permutation's is above 0.5
 *    (the measure tells them apart);
 *  - jitter with one sample per pixel at 128x128, the error image's
 *    low/high ratio: on stripes finer than a pixel, the same in every pixel
 *    (a grey made of sub-pixel detail), seq=bluenoise's is below a tenth of
 *    seq=random's (independent positions: white error, ratio above 0.5)
 *    and of seq=sobol's (Owen-scrambled per pixel, independent across
 *    pixels); on crow, whose error lies along its curves, below both;
 *    and with 16 samples its RMSE stays within 1.5 times seq=sobol's.
 */
#include "bluenoise.h"
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

/* Power spectrum of v (n x n, mean removed) by a direct DFT; the mean
 * power of the low band and of the high band. */
static void bands(const double *v, int n, double *low, double *high)
{
    double *re = calloc((size_t)n * n, sizeof *re), *im = calloc((size_t)n * n, sizeof *im);
    double *c = malloc((size_t)n * sizeof *c), *s = malloc((size_t)n * sizeof *s);
    double *r2 = calloc((size_t)n * n, sizeof *r2), *i2 = calloc((size_t)n * n, sizeof *i2);
    assert_true(re && im && c && s && r2 && i2);
    double mean = 0;
    for (int q = 0; q < n * n; q++)
        mean += v[q] / (n * n);
    for (int k = 0; k < n; k++)
        c[k] = cos(2 * M_PI * k / n), s[k] = -sin(2 * M_PI * k / n);
    for (int y = 0; y < n; y++) /* rows */
        for (int kx = 0; kx < n; kx++)
            for (int x = 0; x < n; x++) {
                int t = (kx * x) % n;
                double a = v[y * n + x] - mean;
                re[y * n + kx] += a * c[t], im[y * n + kx] += a * s[t];
            }
    for (int kx = 0; kx < n; kx++) /* columns */
        for (int ky = 0; ky < n; ky++)
            for (int y = 0; y < n; y++) {
                int t = (ky * y) % n;
                double a = re[y * n + kx], b = im[y * n + kx];
                r2[ky * n + kx] += a * c[t] - b * s[t], i2[ky * n + kx] += a * s[t] + b * c[t];
            }
    double sl = 0, sh = 0;
    int nl = 0, nh = 0;
    for (int ky = 0; ky < n; ky++)
        for (int kx = 0; kx < n; kx++) {
            int wx = kx < n / 2 ? kx : kx - n, wy = ky < n / 2 ? ky : ky - n;
            double f = sqrt((double)(wx * wx + wy * wy)) / n;
            double p = r2[ky * n + kx] * r2[ky * n + kx] + i2[ky * n + kx] * i2[ky * n + kx];
            if (f > 0 && f <= 0.125)
                sl += p, nl++;
            else if (f > 0.375 && f <= 0.5)
                sh += p, nh++;
        }
    *low = sl / nl, *high = sh / nh;
    free(re), free(im), free(c), free(s), free(r2), free(i2);
}

static double ratio(const double *v, int n)
{
    double l, h;
    bands(v, n, &l, &h);
    return l / h;
}

enum { S = AA__BLUENOISE_SIDE, N = S * S };

static void test_mask(void **state)
{
    (void)state;
    uint32_t *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b), *c = malloc(N * sizeof *c);
    unsigned char *seen = calloc(N, 1);
    double *v = malloc(N * sizeof *v);
    assert_true(a && b && c && seen && v);
    assert_int_equal(aa__bluenoise_mask(S, AA__BLUENOISE_SIGMA, 5, a), AA_OK);
    assert_int_equal(aa__bluenoise_mask(S, AA__BLUENOISE_SIGMA, 5, b), AA_OK);
    assert_int_equal(aa__bluenoise_mask(S, AA__BLUENOISE_SIGMA, 6, c), AA_OK);
    for (int q = 0; q < N; q++) {
        assert_true(a[q] < N && !seen[a[q]]);
        seen[a[q]] = 1;
    }
    assert_memory_equal(a, b, N * sizeof *a);
    assert_memory_not_equal(a, c, N * sizeof *a);
    assert_int_equal(aa__bluenoise_mask(3, 1.5, 1, a), AA_EINVAL);
    assert_int_equal(aa__bluenoise_mask(S, 0.0, 1, a), AA_EINVAL);
    assert_int_equal(aa__bluenoise_mask(S, 1.5, 5, a), AA_OK);

    for (int q = 0; q < N; q++)
        v[q] = a[q];
    double rm = ratio(v, S);
    for (int q = 0; q < N; q++)
        v[q] = a[q] < N / 10;
    double rt = ratio(v, S);
    /* a random permutation (Fisher-Yates) */
    aa_rng rng;
    aa_rng_seed(&rng, 11, 0, 0);
    for (int q = 0; q < N; q++)
        c[q] = (uint32_t)q;
    for (int q = N - 1; q > 0; q--) {
        int r = (int)(aa_rng_next(&rng) % (uint64_t)(q + 1));
        uint32_t t = c[q];
        c[q] = c[r], c[r] = t;
    }
    for (int q = 0; q < N; q++)
        v[q] = c[q];
    double rw = ratio(v, S);
    print_message("low/high band power: void-and-cluster mask %.4f, its 10%% pattern %.4f, "
                  "random permutation %.4f\n", rm, rt, rw);
    assert_true(rm < 0.1 && rt < 0.1 && rw > 0.5);
    free(a), free(b), free(c), free(seen), free(v);
}

static double error_ratio(const char *m, const aa_scene *s, const aa_image *ref, double *rmse)
{
    const int n = ref->w;
    support_view view = {.w = n, .h = n, .seed = 9, .threads = 1};
    aa_image img;
    if (support_render_view(m, s, &view, &img, NULL))
        fail_msg("%s: %s", m, aa_last_error());
    double *e = malloc((size_t)n * n * sizeof *e);
    assert_non_null(e);
    for (int q = 0; q < n * n; q++)
        e[q] = img.v[3 * q] - ref->v[3 * q];
    double r = ratio(e, n);
    *rmse = support_rmse(&img, ref);
    free(e);
    aa_image_free(&img);
    return r;
}

/* White stripes 0.4 pixel wide, one in each pixel column of an n-pixel
 * image (x in [k, k + 0.4] pixels), on black: every pixel holds the same
 * edges, the case of a uniform grey made of detail finer than the pixels,
 * whose error with one sample is that sample's alone. */
static aa_scene *stripes(int n)
{
    double (*r)[4] = malloc((size_t)n * sizeof *r);
    assert_non_null(r);
    for (int k = 0; k < n; k++) {
        r[k][0] = (k + 0.1) / n, r[k][1] = 0.0, r[k][2] = (k + 0.5) / n, r[k][3] = 1.0;
    }
    aa_scene *s = scenes_rects((const double(*)[4])r, n);
    free(r);
    return s;
}

static void test_error_spectrum(void **state)
{
    (void)state;
    const int n = 128;
    for (int p = 0; p < 2; p++) {
        aa_scene *s = p ? scenes_pattern("crow") : stripes(n);
        aa_image ref;
        const support_view view = {.w = n, .h = n, .threads = 1};
        support_reference(s, &view, &ref, NULL, NULL);
        double e[3], rb, rr, rs;
        rb = error_ratio("jitter:spp=1,seq=bluenoise", s, &ref, &e[0]);
        rr = error_ratio("jitter:spp=1,seq=random", s, &ref, &e[1]);
        rs = error_ratio("jitter:spp=1,seq=sobol", s, &ref, &e[2]);
        print_message("%s %dx%d, 1 spp, error's low/high band power: bluenoise %.4f, random "
                      "%.4f, sobol %.4f (RMSE %.4f, %.4f, %.4f)\n", p ? "crow" : "stripes", n,
                      n, rb, rr, rs, e[0], e[1], e[2]);
        if (!p) /* the same edges in every pixel: the error is the mask's */
            assert_true(rb < 0.1 * rr && rb < 0.1 * rs && rr > 0.5 && rs > 0.5);
        else /* edges along curves: the error lies on them, less blue */
            assert_true(rb < rr && rb < rs);
        double e16b, e16s;
        rb = error_ratio("jitter:spp=16,seq=bluenoise", s, &ref, &e16b);
        rs = error_ratio("jitter:spp=16,seq=sobol", s, &ref, &e16s);
        print_message("  16 spp: low/high bluenoise %.4f, sobol %.4f; RMSE %.4f, %.4f\n", rb,
                      rs, e16b, e16s);
        assert_true(e16b < 1.5 * e16s);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_mask),
             cmocka_unit_test(test_error_spectrum))
