/*
 * test_edges.c: the edge pixels (harness/bench/edges.c) and the edge RMSE
 * on half-planes, whose edge pixels have a closed form.
 *
 * A half-plane x > x0 (white on black) in pixel units: under a filter of
 * support radius r, pixel column i is an edge pixel when the line meets
 * the open interval (i + 1/2 - r, i + 1/2 + r), i.e. x0 - 1/2 - r < i <
 * x0 - 1/2 + r: for the box (r = 1/2) the one column floor(x0) (none when
 * x0 is an integer: the line runs along the pixels' borders), for the
 * tent r = 1 the columns floor(x0 - 1/2) and floor(x0 + 1/2).  A slanted
 * line x = x0 + s y meets row j (box) in the columns floor(x0 + s j) to
 * floor(x0 + s (j + 1)).
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

enum { W = 24, H = 12 };

/* The half-plane right of x0 as a scene in pixel units: a rectangle whose
 * other sides are far outside the W x H image. */
static aa_scene *half_plane(double x0)
{
    const double r[1][4] = {{x0, -100, 100, 100}};
    return scenes_rects(r, 1);
}

static void check_columns(double x0, double radius, int first, int last)
{
    aa_scene *s = half_plane(x0);
    unsigned char mask[W * H];
    assert_int_equal(aa_edge_mask(s, radius, W, H, mask), AA_OK);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            assert_int_equal(mask[j * W + i], i >= first && i <= last);
    aa_scene_free(s);
}

static void test_half_plane_columns(void **state)
{
    (void)state;
    check_columns(10.3, 0.5, 10, 10);
    check_columns(10.7, 0.5, 10, 10);
    check_columns(10.0, 0.5, 1, 0);   /* along the borders: none */
    check_columns(10.3, 1.0, 9, 10);  /* tent r = 1 */
    check_columns(10.8, 1.0, 10, 11);
    check_columns(10.3, 1.5, 9, 11);  /* cone r = 1.5: x0 - 2 < i < x0 + 1 */
}

static void test_slanted(void **state)
{
    (void)state;
    const double x0 = 4.3, s = 0.75;
    const double xy[] = {x0, 0, x0 + s * H, H, 100, H, 100, 0};
    aa_scene *sc = scenes_polygon(xy, 4, (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}},
                                  AA_FILL_NONZERO);
    unsigned char mask[W * H];
    assert_int_equal(aa_edge_mask(sc, 0.5, W, H, mask), AA_OK);
    for (int j = 0; j < H; j++) {
        int a = (int)floor(x0 + s * j), b = (int)floor(x0 + s * (j + 1));
        if (x0 + s * (j + 1) == b) /* ends on a border: not in that column */
            b--;
        for (int i = 0; i < W; i++)
            assert_int_equal(mask[j * W + i], i >= a && i <= b);
    }
    aa_scene_free(sc);
}

/* Point sampling a box-filtered half-plane x > 10.3: the reference is 0.7
 * in column 10 and 1 right of it; point samples at x = i + 1/2 give 1 in
 * column 10.  The error is 0.3 in the one edge column: edge RMSE 0.3,
 * where the RMSE over the image is 0.3 / sqrt(W). */
static void test_edge_rmse(void **state)
{
    (void)state;
    aa_image ref, img;
    aa_metrics m;
    assert_int_equal(aa_image_alloc(&ref, W, H, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&img, W, H, 3), AA_OK);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            for (int c = 0; c < 3; c++) {
                aa_pixel(&ref, i, j)[c] = i < 10 ? 0 : i == 10 ? 0.7 : 1;
                aa_pixel(&img, i, j)[c] = i < 10 ? 0 : 1;
            }
    aa_scene *s = half_plane(10.3);
    assert_int_equal(aa_metrics_compute(&ref, &img, NULL, &m), AA_OK);
    assert_int_equal(aa_metrics_edges(s, 0.5, &ref, &img, &m), AA_OK);
    assert_true(fabs(m.edge_rmse - 0.3) < 1e-15 && m.edge_pixels == H);
    assert_true(fabs(m.rmse - 0.3 / sqrt(W)) < 1e-15);
    /* from the images alone: columns 9, 10 and 11 differ from a neighbour:
     * errors 0, 0.3, 0, so 0.3 / sqrt 3 */
    assert_int_equal(aa_metrics_edges(NULL, 0.5, &ref, &img, &m), AA_OK);
    assert_true(fabs(m.edge_rmse - 0.3 / sqrt(3)) < 1e-15 && m.edge_pixels == 3 * H);
    /* no edge pixel: none */
    aa_scene_free(s);
    s = half_plane(50);
    assert_int_equal(aa_metrics_edges(s, 0.5, &ref, &img, &m), AA_OK);
    assert_true(isnan(m.edge_rmse) && m.edge_pixels == 0);
    assert_int_equal(aa_edge_mask(s, 0, W, H, (unsigned char[W * H]){0}), AA_EINVAL);
    aa_scene_free(s);
    aa_image_free(&ref);
    aa_image_free(&img);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_half_plane_columns),
             cmocka_unit_test(test_slanted),
             cmocka_unit_test(test_edge_rmse))
