/*
 * test_arcpath.c: paths (harness/core/path.c): the builder's checks, the
 * SVG arc command's endpoint-to-centre conversion (aa_arc_endpoints) and
 * filling a path through an affine map.
 *
 *  - aa_arc_endpoints against the rules of the SVG implementation notes
 *    (SVG 1.1 F.6.2, F.6.5, F.6.6), checked from their meaning, not from the
 *    code's formulas: equal ends give nothing (2), a zero radius a line (1);
 *    radii are made positive; on random arcs the ellipse's point for t0 is
 *    the start and for t1 the end (to 1e-14 of the size; about 7e-16 seen), the semi-axes
 *    have the given lengths and rotation (or, when too small, both scaled
 *    by one factor with the centre at the chord's midpoint, |dt| = pi), the
 *    sweep flag is the sign of dt and the large-arc flag |dt| > pi.  The
 *    four arcs of radius 1 from (1, 0) to (0, 1): centres and angles by
 *    hand (the unit circle's quarter and three quarters).
 *  - builder: non-finite numbers, drawing before move_to, an arc whose ends
 *    are not the pen and the given end, parallel semi-diameters and sweeps
 *    beyond 2 pi refused; after close the next segment starts at the
 *    closed subpath's start (SVG's implicit move_to).
 *  - aa_path_fill: a square through a shear and scale: the box reference of
 *    the filled white shape sums to |det| times its area in pixels; a
 *    circle's arcs through the same map become the scene's elliptical arc
 *    edges with the centre mapped and u, v by the linear part (by hand).
 */
#include "path.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

static void ellipse_at(const double c[8], double t, double *x, double *y)
{
    *x = c[0] + c[2] * cos(t) + c[4] * sin(t);
    *y = c[1] + c[3] * cos(t) + c[5] * sin(t);
}

static uint64_t rng = 0x9e3779b97f4a7c15u;
static double uniform(double a, double b)
{
    return support_uniform(&rng, a, b);
}

static void test_endpoints_special(void **state)
{
    (void)state;
    double c[8];
    aa_arc_kind kind = AA_ARC_CURVE;
    /* F.6.2: equal ends draw nothing, a zero radius a line; a non-finite
     * number is an error, told apart from both */
    assert_int_equal(aa_arc_endpoints(1, 2, 3, 4, 0, 0, 0, 1, 2, c, &kind), AA_OK);
    assert_int_equal(kind, AA_ARC_NONE);
    assert_int_equal(aa_arc_endpoints(1, 2, 0, 4, 0, 0, 0, 5, 2, c, &kind), AA_OK);
    assert_int_equal(kind, AA_ARC_LINE);
    kind = AA_ARC_CURVE;
    assert_int_equal(aa_arc_endpoints(1, 2, 3, 0, 0, 1, 1, 5, 2, c, &kind), AA_OK);
    assert_int_equal(kind, AA_ARC_LINE);
    assert_int_equal(aa_arc_endpoints(1, 2, 3, 4, NAN, 0, 0, 5, 2, c, &kind), AA_EINVAL);
    assert_int_equal(aa_arc_endpoints(1, 2, INFINITY, 4, 0, 0, 0, 5, 2, c, &kind), AA_EINVAL);
    assert_int_equal(aa_arc_endpoints(1, NAN, 3, 4, 0, 0, 0, 5, 2, c, &kind), AA_EINVAL);
    assert_int_equal(aa_arc_endpoints(1, 2, 3, 4, 0, 0, 0, 1, NAN, c, &kind), AA_EINVAL);

    /* Radius 1 from (1, 0) to (0, 1): the centre is (0, 0) or (1, 1).  The
     * sweep flag 1 is the direction of increasing angle.  By hand:
     *   large 0 sweep 1: centre (0,0), angle 0 -> pi/2;
     *   large 1 sweep 1: centre (1,1), angle -pi/2 -> pi (3 pi/2 of turn);
     *   large 0 sweep 0: centre (1,1), angle -pi/2 -> -pi;
     *   large 1 sweep 0: centre (0,0), angle 0 -> -3 pi/2. */
    const struct {
        int large, sweep;
        double cx, cy, t0, dt;
    } hand[4] = {{0, 1, 0, 0, 0, M_PI / 2},
                 {1, 1, 1, 1, -M_PI / 2, 1.5 * M_PI},
                 {0, 0, 1, 1, -M_PI / 2, -M_PI / 2},
                 {1, 0, 0, 0, 0, -1.5 * M_PI}};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(
            aa_arc_endpoints(1, 0, 1, -1, 0, hand[k].large, hand[k].sweep, 0, 1, c, &kind), AA_OK);
        assert_int_equal(kind, AA_ARC_CURVE);
        assert_true(fabs(c[0] - hand[k].cx) < 1e-15 && fabs(c[1] - hand[k].cy) < 1e-15);
        assert_true(fabs(c[2] - 1) < 1e-15 && fabs(c[3]) < 1e-15);
        assert_true(fabs(c[4]) < 1e-15 && fabs(c[5] - 1) < 1e-15);
        assert_true(fabs(c[6] - hand[k].t0) < 1e-15);
        assert_true(fabs(c[7] - c[6] - hand[k].dt) < 1e-15);
    }

    /* Radii too small: (0,0) to (4,0) with radius 1 is scaled to radius 2
     * about the midpoint (2, 0), half a circle. */
    assert_int_equal(aa_arc_endpoints(0, 0, 1, 1, 0, 1, 1, 4, 0, c, &kind), AA_OK);
    assert_true(fabs(c[0] - 2) < 1e-15 && fabs(c[1]) < 1e-15);
    assert_true(fabs(hypot(c[2], c[3]) - 2) < 1e-15 && fabs(hypot(c[4], c[5]) - 2) < 1e-15);
    assert_true(fabs(fabs(c[7] - c[6]) - M_PI) < 1e-15);
    assert_true(c[7] > c[6]);
}

/* Random arcs: the meaning of every output (header comment). */
static void test_endpoints_random(void **state)
{
    (void)state;
    int scaled = 0, kept = 0;
    double worst = 0;
    for (int i = 0; i < 20000; i++) {
        double scale = pow(10.0, uniform(-3, 3));
        double x0 = scale * uniform(-1, 1), y0 = scale * uniform(-1, 1);
        double x1 = scale * uniform(-1, 1), y1 = scale * uniform(-1, 1);
        double rx = scale * uniform(-1.5, 1.5), ry = scale * uniform(-1.5, 1.5);
        double phi = uniform(-720, 720);
        int large = i & 1, sweep = (i >> 1) & 1;
        double c[8];
        aa_arc_kind kind;
        assert_int_equal(aa_arc_endpoints(x0, y0, rx, ry, phi, large, sweep, x1, y1, c, &kind), AA_OK);
        assert_int_equal(kind, AA_ARC_CURVE);
        double size = hypot(c[2], c[3]) + hypot(c[4], c[5]);
        double ax, ay, bx, by;
        ellipse_at(c, c[6], &ax, &ay);
        ellipse_at(c, c[7], &bx, &by);
        double tol = 1e-14 * (size + fabs(x0) + fabs(y0) + fabs(x1) + fabs(y1));
        if (hypot(ax - x0, ay - y0) > tol || hypot(bx - x1, by - y1) > tol)
            fail_msg("arc %d: ends off by %g, %g (tol %g)", i, hypot(ax - x0, ay - y0),
                     hypot(bx - x1, by - y1), tol);
        double rel = fmax(hypot(ax - x0, ay - y0), hypot(bx - x1, by - y1)) / tol * 1e-14;
        worst = fmax(worst, rel);
        double dt = c[7] - c[6];
        assert_true(sweep ? dt > 0 : dt < 0);
        assert_true(fabs(dt) <= 2 * M_PI);
        /* the axes' directions: u along phi, v a quarter turn on */
        double pr = phi * M_PI / 180;
        double lu = hypot(c[2], c[3]), lv = hypot(c[4], c[5]);
        assert_true(fabs(c[2] / lu - cos(pr)) < 1e-12 && fabs(c[3] / lu - sin(pr)) < 1e-12);
        assert_true(fabs(c[4] / lv + sin(pr)) < 1e-12 && fabs(c[5] / lv - cos(pr)) < 1e-12);
        double kx = lu / fabs(rx), ky = lv / fabs(ry);
        assert_true(fabs(kx - ky) < 1e-12 * kx);
        if (kx > 1 + 1e-12) {
            /* scaled up: the smallest ellipse, centred on the chord */
            scaled++;
            assert_true(hypot(c[0] - 0.5 * (x0 + x1), c[1] - 0.5 * (y0 + y1)) < tol);
            assert_true(fabs(fabs(dt) - M_PI) < 1e-9);
        } else {
            kept++;
            assert_true(fabs(kx - 1) < 1e-12);
            /* clear of the half-turn case, the flag decides */
            if (fabs(fabs(dt) - M_PI) > 1e-6)
                assert_int_equal(fabs(dt) > M_PI, large);
        }
    }
    print_message("random arcs: %d with radii kept, %d scaled up; ends within %.2g of the "
                  "size\n",
                  kept, scaled, worst);
    assert_true(kept > 1000 && scaled > 1000);
}

static void test_builder(void **state)
{
    (void)state;
    aa_path p;
    aa_path_init(&p);
    assert_int_equal(aa_path_line_to(&p, 1, 1), AA_EINVAL);
    assert_int_equal(aa_path_close(&p), AA_EINVAL);
    assert_int_equal(aa_path_move_to(&p, NAN, 0), AA_EINVAL);
    assert_int_equal(aa_path_move_to(&p, 0, 0), AA_OK);
    assert_int_equal(aa_path_line_to(&p, INFINITY, 0), AA_EINVAL);
    assert_int_equal(aa_path_quad_to(&p, 0, NAN, 1, 1), AA_EINVAL);
    assert_int_equal(aa_path_cubic_to(&p, 0, 0, 1, 1, NAN, 1), AA_EINVAL);
    assert_int_equal(aa_path_move_to(&p, 1, 0), AA_OK);
    /* unit circle from angle 0 to pi/2: the pen (1, 0), the end (0, 1) */
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 1, 0, 0, 1, 0, M_PI / 2, 0.5, 1), AA_EINVAL);
    assert_int_equal(aa_path_arc_to(&p, 0.1, 0, 1, 0, 0, 1, 0, M_PI / 2, 0, 1), AA_EINVAL);
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 1, 0, 2, 0, 0, M_PI / 2, 0, 1), AA_EINVAL);
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 1, 0, 0, 1, 0, 2 * M_PI + 0.1,
                                    cos(2 * M_PI + 0.1), sin(2 * M_PI + 0.1)),
                     AA_EINVAL);
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 1, 0, 0, 1, 0, M_PI / 2, 0, 1), AA_OK);
    assert_int_equal(p.seg[p.n - 1].op, AA_PATH_ARC);
    assert_true(p.penx == 0 && p.peny == 1);
    size_t n = p.n;
    /* t0 == t1 adds nothing */
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 0, -1, 1, 0, 0, 0, 0, 0), AA_EINVAL);
    assert_int_equal(aa_path_arc_to(&p, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1), AA_OK);
    assert_int_equal(p.n, n);
    assert_int_equal(aa_path_close(&p), AA_OK);
    assert_true(p.penx == 1 && p.peny == 0);
    /* SVG: after Z the next command starts at the subpath's start */
    assert_int_equal(aa_path_line_to(&p, 3, 3), AA_OK);
    assert_int_equal(p.seg[p.n - 2].op, AA_PATH_MOVE);
    assert_true(p.seg[p.n - 2].p[0] == 1 && p.seg[p.n - 2].p[1] == 0);
    aa_path_free(&p);
    assert_int_equal(p.n, 0);
}

/* A square of side 0.25 at (0.3, 0.3) mapped by x' = 1.5 x + 0.5 y - 0.2,
 * y' = 0.2 x + 1.2 y - 0.1: a parallelogram of area |det| 0.0625 =
 * (1.5 * 1.2 - 0.5 * 0.2) * 0.0625, inside the unit square; its box
 * reference on 32x32 pixels sums to that times 1024. */
static void test_fill_map(void **state)
{
    (void)state;
    aa_path p = {0};
    assert_int_equal(aa_path_move_to(&p, 0.3, 0.3), AA_OK);
    assert_int_equal(aa_path_line_to(&p, 0.55, 0.3), AA_OK);
    assert_int_equal(aa_path_line_to(&p, 0.55, 0.55), AA_OK);
    assert_int_equal(aa_path_line_to(&p, 0.3, 0.55), AA_OK); /* closed by the fill */
    const double m[6] = {1.5, 0.2, 0.5, 1.2, -0.2, -0.1};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_path_fill(&p, m, s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    support_view v = {.w = 32, .h = 32, .threads = 1};
    aa_image im;
    support_reference(s, &v, &im, NULL, NULL);
    double sum = support_channel_mean(&im, 0) * 32 * 32;
    double want = (1.5 * 1.2 - 0.5 * 0.2) * 0.0625 * 1024;
    print_message("filled parallelogram: %.15g pixels, want %.15g\n", sum, want);
    assert_true(fabs(sum - want) < 1e-9);
    aa_image_free(&im);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* Half the unit circle about (0.5, 0.5), radius 0.25, closed by its
 * diameter, through the map of test_fill_map: the arc edge has centre
 * (1.5 0.5 + 0.5 0.5 - 0.2, 0.2 0.5 + 1.2 0.5 - 0.1) = (0.8, 0.6),
 * u = L (0.25, 0) = (0.375, 0.05), v = L (0, 0.25) = (0.125, 0.3), the same
 * angles, and ends at the mapped end. */
static void test_fill_arc(void **state)
{
    (void)state;
    aa_path p = {0};
    assert_int_equal(aa_path_move_to(&p, 0.75, 0.5), AA_OK);
    assert_int_equal(aa_path_arc_to(&p, 0.5, 0.5, 0.25, 0, 0, 0.25, 0, M_PI, 0.25, 0.5), AA_OK);
    assert_int_equal(aa_path_close(&p), AA_OK);
    const double m[6] = {1.5, 0.2, 0.5, 1.2, -0.2, -0.1};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_path_fill(&p, m, s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    size_t n;
    const aa_edge *e = aa_scene_edges(s, &n);
    int arcs = 0;
    for (size_t k = 0; k < n; k++) {
        if (e[k].quad != 3)
            continue;
        arcs++;
        assert_true(fabs(e[k].cx - 0.8) < 1e-15 && fabs(e[k].cy - 0.6) < 1e-15);
        assert_true(fabs(e[k].ux - 0.375) < 1e-15 && fabs(e[k].uy - 0.05) < 1e-15);
        assert_true(fabs(e[k].vx - 0.125) < 1e-15 && fabs(e[k].vy - 0.3) < 1e-15);
        assert_true(e[k].t0 == 0 && e[k].t1 == M_PI);
        assert_true(fabs(e[k].x1 - (1.5 * 0.25 + 0.5 * 0.5 - 0.2)) < 1e-15);
        assert_true(fabs(e[k].y1 - (0.2 * 0.25 + 1.2 * 0.5 - 0.1)) < 1e-15);
    }
    assert_int_equal(arcs, 1);
    aa_scene_free(s);
    aa_path_free(&p);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_endpoints_special),
             cmocka_unit_test(test_endpoints_random), cmocka_unit_test(test_builder),
             cmocka_unit_test(test_fill_map), cmocka_unit_test(test_fill_arc))
