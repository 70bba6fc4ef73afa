/*
 * test_errmap.c: the pictures of the error (harness/bench/errmap.c) and the
 * run folder's report (harness/bench/runreport.c).
 *
 * Known answers, independent of the code under test:
 *  - Moreland's cool to warm map (Moreland 2009, "Diverging Color Maps for
 *    Scientific Visualization", its table of the map): the ends are sRGB
 *    (59, 76, 192) and (180, 4, 38), the middle (221, 221, 221); its
 *    lightness falls from the middle to either end;
 *  - magma: matplotlib's published table (_cm_listed.py), entries 0, 127,
 *    128 and 255; its CIELAB lightness rises with t (the map's design);
 *  - the error picture: one pixel of error +0.1 on an otherwise exact
 *    image is drawn in the warm end's colour, every other in the middle's,
 *    at the scale 0.1; the worst window holds the bad block;
 *  - the report names every view, method and note (escaped), and shows
 *    only the images present.
 */
#include "bench.h"
#include "support.h"

#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

static double lightness(const double code[3])
{
    double lin[3];
    for (int k = 0; k < 3; k++)
        lin[k] = code[k] <= 0.04045 ? code[k] / 12.92 : pow((code[k] + 0.055) / 1.055, 2.4);
    double y = 0.2126729 * lin[0] + 0.7151522 * lin[1] + 0.0721750 * lin[2];
    return y > 216.0 / 24389 ? 116 * cbrt(y) - 16 : y * 24389.0 / 27;
}

static void near_rgb(const double got[3], double r, double g, double b, double tol)
{
    assert_true(fabs(got[0] - r) <= tol && fabs(got[1] - g) <= tol && fabs(got[2] - b) <= tol);
}

static void test_diverging(void **state)
{
    (void)state;
    double c[3];
    aa_colormap_diverging(-1, c);
    near_rgb(c, 59 / 255.0, 76 / 255.0, 192 / 255.0, 0.6 / 255);
    aa_colormap_diverging(1, c);
    near_rgb(c, 180 / 255.0, 4 / 255.0, 38 / 255.0, 0.6 / 255);
    aa_colormap_diverging(0, c);
    near_rgb(c, 221 / 255.0, 221 / 255.0, 221 / 255.0, 1.5 / 255);
    aa_colormap_diverging(-7, c); /* clamped */
    near_rgb(c, 59 / 255.0, 76 / 255.0, 192 / 255.0, 0.6 / 255);
    double last = 1e9;
    for (int k = 0; k <= 32; k++) { /* lighter towards the middle, both sides */
        double a[3], b[3];
        aa_colormap_diverging(k / 32.0, a);
        aa_colormap_diverging(-k / 32.0, b);
        assert_true(lightness(a) < last + 1e-9 && lightness(b) < last + 1e-9);
        last = fmax(lightness(a), lightness(b));
    }
}

static void test_magma(void **state)
{
    (void)state;
    double c[3];
    aa_colormap_magma(0, c);
    near_rgb(c, 0.001462, 0.000466, 0.013866, 1e-12);
    aa_colormap_magma(1, c);
    near_rgb(c, 0.987053, 0.991438, 0.749504, 1e-12);
    aa_colormap_magma(127.5 / 255, c); /* between entries 127 and 128 */
    near_rgb(c, (0.709962 + 0.716387) / 2, (0.212797 + 0.214982) / 2, (0.477201 + 0.475290) / 2,
             0.002);
    double last = -1;
    for (int k = 0; k <= 255; k++) {
        aa_colormap_magma(k / 255.0, c);
        assert_true(lightness(c) > last);
        last = lightness(c);
    }
}

static void test_nice_scale(void **state)
{
    (void)state;
    assert_true(fabs(aa_nice_scale(0.03) - 0.05) < 1e-15);
    assert_true(fabs(aa_nice_scale(0.2) - 0.2) < 1e-15);
    assert_true(fabs(aa_nice_scale(0.21) - 0.5) < 1e-15);
    assert_true(fabs(aa_nice_scale(7) - 10) < 1e-12);
    assert_true(aa_nice_scale(0) == 1);
}

static void test_pictures(void **state)
{
    (void)state;
    const int w = 40, h = 30;
    aa_image ref, img, pic;
    double s;
    assert_int_equal(aa_image_alloc(&ref, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&img, w, h, 3), AA_OK);
    for (size_t k = 0; k < (size_t)w * h * 3; k++)
        ref.v[k] = img.v[k] = 0.5;
    aa_pixel(&img, 7, 5)[1] += 0.1;
    assert_int_equal(aa_error_picture(&ref, &img, NULL, &pic, &s), AA_OK);
    assert_true(fabs(s - 0.1) < 1e-12);
    /* 40x30 is shown 4 times larger (256 / 40 = 6, at most 4), 160x120, in a
     * picture of 220 for the bar's labels */
    assert_int_equal(aa_error_picture_zoom(w, h), 4);
    assert_int_equal(pic.w, 220);
    int x0 = (220 - 4 * w) / 2;
    double warm[3], mid[3];
    aa_colormap_diverging(1, warm);
    aa_colormap_diverging(0, mid);
    near_rgb(aa_pixel(&pic, x0 + 4 * 7, 4 * 5), warm[0], warm[1], warm[2], 1e-12);
    near_rgb(aa_pixel(&pic, x0 + 4 * 7 + 3, 4 * 5 + 3), warm[0], warm[1], warm[2], 1e-12);
    near_rgb(aa_pixel(&pic, x0 + 4 * 8, 4 * 5), mid[0], mid[1], mid[2], 1e-12);
    near_rgb(aa_pixel(&pic, x0, 0), mid[0], mid[1], mid[2], 1e-12);
    aa_image_free(&pic);
    /* identical: scale 0, every pixel the middle */
    assert_int_equal(aa_error_picture(&ref, &ref, NULL, &pic, &s), AA_OK);
    assert_true(s == 0);
    near_rgb(aa_pixel(&pic, x0 + 4 * 7, 4 * 5), mid[0], mid[1], mid[2], 1e-12);
    assert_int_equal(aa_error_picture_zoom(1024, 1024), 1);
    assert_int_equal(aa_error_picture_zoom(288, 32), 1);
    assert_int_equal(aa_error_picture_zoom(128, 128), 2);
    aa_image_free(&pic);
    /* the worst 4x4 window is the bad block */
    for (int j = 9; j < 13; j++)
        for (int i = 20; i < 24; i++)
            aa_pixel(&img, i, j)[0] = 0;
    int wx, wy;
    assert_int_equal(aa_worst_window(&ref, &img, 4, &wx, &wy), AA_OK);
    assert_true(wx == 20 && wy == 9);
    assert_int_equal(aa_worst_picture(&ref, &img, NULL, &pic, &wx, &wy), AA_OK);
    assert_true(wx <= 20 && wx + 30 >= 23 && wy == 0); /* 30 rows: the window is the image's */
    aa_image_free(&pic);
    aa_image_free(&ref);
    aa_image_free(&img);
}

static void touch(const char *dir, const char *rel)
{
    char path[PATH_MAX + 256];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    support_write_file(path, "x", 1);
}

static void test_report(void **state)
{
    (void)state;
    char dir[PATH_MAX], path[PATH_MAX + 64];
    assert_int_equal(support_tmpdir(dir, sizeof dir, "report"), 0);
    snprintf(path, sizeof path, "%s/images", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    aa_row rows[3];
    memset(rows, 0, sizeof rows);
    for (int k = 0; k < 3; k++) {
        snprintf(rows[k].pattern, sizeof rows[k].pattern, "%s", k < 2 ? "crow" : "star");
        snprintf(rows[k].filter, sizeof rows[k].filter, "box");
        rows[k].w = rows[k].h = 64;
        rows[k].ok = 1;
        rows[k].m.rmse = 0.1 * (k + 1), rows[k].m.flip = 0.05, rows[k].m.edge_rmse = NAN;
        rows[k].seconds = 0.002;
    }
    snprintf(rows[0].method, sizeof rows[0].method, "point");
    snprintf(rows[1].method, sizeof rows[1].method, "area");
    snprintf(rows[2].method, sizeof rows[2].method, "trio");
    rows[2].ok = 0;
    snprintf(rows[2].note, sizeof rows[2].note, "refused: a < b");
    touch(dir, "montage.png");
    touch(dir, "images/crow-64x64-box-point-error.png");
    assert_int_equal(aa_run_report(dir, rows, 3), AA_OK);
    static char html[1 << 16];
    snprintf(path, sizeof path, "%s/index.html", dir);
    support_read_file(path, html, sizeof html, NULL);
    assert_non_null(strstr(html, "crow 64x64, box"));
    assert_non_null(strstr(html, "star 64x64, box"));
    assert_non_null(strstr(html, "refused: a &lt; b"));
    assert_non_null(strstr(html, "src=\"montage.png\""));
    assert_non_null(strstr(html, "src=\"images/crow-64x64-box-point-error.png\""));
    assert_null(strstr(html, "area-error.png"));   /* not present: not shown */
    assert_null(strstr(html, "montage-star"));     /* not present: not shown */
    assert_null(strstr(html, "error_vs_time.png")); /* no plots */
    /* point (0.1) before area (0.2) in crow's table */
    assert_true(strstr(html, ">point<") < strstr(html, ">area<"));
    assert_int_equal(support_rmtree(dir), 0);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_diverging),
             cmocka_unit_test(test_magma),
             cmocka_unit_test(test_nice_scale),
             cmocka_unit_test(test_pictures),
             cmocka_unit_test(test_report))
