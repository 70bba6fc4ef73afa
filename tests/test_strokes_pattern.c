/*
 * test_strokes_pattern.c: the `strokes` pattern (patterns/strokes.c) against
 * the closed forms of patterns/README.md, `strokes`, derived there from the
 * geometry of the stroke (SVG 2, "Stroke shape"), independently of the
 * stroker and of the reference:
 *
 *   a bent line of two segments of length L and width w = 2h turning by q
 *   is two w x L rectangles (2 w L) overlapping on the inside of the turn
 *   in a kite of two right triangles of legs h and h tan(q/2)
 *   (- h^2 tan(q/2)), the outside's wedge filled by the join: the miter's
 *   kite (h^2 tan(q/2)), the round join's sector of angle q (h^2 q / 2) or
 *   the bevel's triangle of two sides h at angle q (h^2 sin(q) / 2);
 *   an arc of radius R sweeping A is an annular sector, w R A;
 *   each end adds nothing (butt), a half disk (pi h^2 / 2) or a w x h
 *   rectangle (square).
 *
 * The box reference of the pattern, summed over the pixels of each cell
 * (pixel centres turned back by the grid's rotation, so that each falls in
 * its cell; the strokes keep well inside their cells), is each cell's
 * area; it must match to 1e-10 relative (the reference is exact to 1e-12
 * per pixel).
 */
#include "bench.h"
#include "path.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* The closed form of cell (c, r): column c the cap, row r the join (3: the
 * arc). */
static double cell_area(int c, int r, double w, double turn_deg)
{
    const double h = w / 2, q = turn_deg * M_PI / 180, L = 0.07, R = 0.08;
    const double A = 150 * M_PI / 180;
    double a;
    if (r == 3) {
        a = w * R * A;
    } else {
        const double J = r == 0 ? h * h * tan(q / 2) : r == 1 ? h * h * q / 2 : h * h * sin(q) / 2;
        a = 2 * w * L - h * h * tan(q / 2) + J;
    }
    const double cap = c == 0 ? 0 : c == 1 ? M_PI * h * h / 2 : w * h;
    return a + 2 * cap;
}

static void check(double w, double turn, double rot)
{
    char spec[256];
    snprintf(spec, sizeof spec, "strokes:width=%.17g,turn=%.17g,rot=%.17g", w, turn, rot);
    aa_spec ps;
    if (aa_pattern_parse(spec, &ps))
        fail_msg("%s: %s", spec, aa_last_error());
    aa_scene *s;
    if (aa_pattern_scene(&ps, &s))
        fail_msg("%s: %s", spec, aa_last_error());
    /* twelve stroke layers and no clip frame: nothing reaches outside */
    assert_int_equal(aa_scene_layer_count(s), 12);
    size_t n;
    aa_scene_stroke_sources(s, &n);
    assert_int_equal(n, 12);
    aa_scene_free(s);

    const int W = 96, H = 96;
    aa_image im;
    support_pattern_reference(spec, &(support_view){.w = W, .h = H}, &im, NULL, NULL);
    double sum[4][3] = {{0}};
    const double t = -rot * M_PI / 180, ct = cos(t), st = sin(t);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double x = (i + 0.5) / W - 0.5, y = (j + 0.5) / H - 0.5;
            double u = ct * x - st * y + 0.5, v = st * x + ct * y + 0.5;
            int c = (int)floor(u * 3), r = (int)floor(v * 4);
            double val = aa_pixel(&im, i, j)[0];
            if (c < 0 || c > 2 || r < 0 || r > 3) {
                if (val != 0)
                    fail_msg("%s: pixel (%d, %d) outside the grid is %g", spec, i, j, val);
                continue;
            }
            sum[r][c] += val / (W * H);
        }
    aa_image_free(&im);
    double worst = 0;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 3; c++) {
            double want = cell_area(c, r, w, turn), rel = fabs(sum[r][c] - want) / want;
            worst = fmax(worst, rel);
            if (!(rel < 1e-10))
                fail_msg("%s: cell (%d, %d) area %.17g, want %.17g (%.2e relative)", spec, c,
                         r, sum[r][c], want, rel);
        }
    print_message("%-48s worst cell %.2e relative\n", spec, worst);
}

static void test_defaults(void **state)
{
    (void)state;
    check(0.02, 50, 7);
}

static void test_extremes(void **state)
{
    (void)state;
    check(0.05, 120, 0);   /* the widest strokes, the sharpest turn */
    check(0.05, 0, -4);    /* straight: every join adds nothing */
    check(0.001, 90, 12);  /* hairlines */
    check(0.03, 17.5, 5);
}

static void test_domain(void **state)
{
    (void)state;
    aa_spec ps;
    assert_int_equal(aa_pattern_parse("strokes:width=0", &ps), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("strokes:width=0.06", &ps), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("strokes:turn=121", &ps), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("strokes:turn=-1", &ps), AA_EINVAL);
    assert_int_equal(aa_pattern_parse("strokes:width=0.05,turn=120,rot=180", &ps), AA_OK);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_defaults),
             cmocka_unit_test(test_extremes),
             cmocka_unit_test(test_domain))
