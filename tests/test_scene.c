/*
 * test_scene.c: the scene model and its queries.
 *
 * Known answers are worked by hand in the comments.  The strip (windowed
 * queries) is checked against the plain point query on many random points
 * of `crow` and of a polygon scene with vertices inside the bands.  The
 * crossings of a line against each edge's own (test_crossings_sorted).
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

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
static const aa_rgb red = {{1, 0, 0}}, green = {{0, 1, 0}}, blue = {{0, 0, 1}};

static int same(aa_rgb a, aa_rgb b)
{
    return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

static void test_square(void **state)
{
    (void)state;
    const double square[1][4] = {{0.25, 0.25, 0.75, 0.75}};
    aa_scene *s = scenes_rects(square, 1); /* white on black */
    assert_true(same(aa_scene_colour_at(s, 0.5, 0.5), white));
    assert_true(same(aa_scene_colour_at(s, 0.1, 0.5), black));
    assert_true(same(aa_scene_colour_at(s, 0.5, 0.9), black));
    aa_crossing c[4];
    /* the line y = 0.5 meets the two vertical sides; the flat sides never */
    assert_int_equal(aa_scene_crossings(s, 0.5, c, 4), 2);
    assert_true(c[0].x == 0.25 && c[1].x == 0.75 && c[0].dir == -c[1].dir);
    double x0, y0, x1, y1;
    assert_int_equal(aa_scene_bounds(s, &x0, &y0, &x1, &y1), 1);
    assert_true(x0 == 0.25 && y0 == 0.25 && x1 == 0.75 && y1 == 0.75);
    size_t idx[8];
    /* a rectangle inside the square touches nothing; one across its left
     * side touches that side and the two flat sides it reaches */
    assert_int_equal(aa_scene_touching(s, 0.4, 0.4, 0.6, 0.6, idx, 8), 0);
    assert_int_equal(aa_scene_touching(s, 0.2, 0.4, 0.3, 0.6, idx, 8), 1);
    assert_int_equal(aa_scene_touching(s, 0.2, 0.2, 0.3, 0.3, idx, 8), 2);
    assert_true(aa_scene_is_grey(s));
    aa_scene_free(s);
}

/* quad (0,0)-(1,2)-(2,0): y(t) = 4t(1-t), x(t) = 2t; the top y = 1 at t = 1/2 */
static void test_arc_pieces(void **state)
{
    (void)state;
    aa_scene *s = scenes_arc_segment(0, 0, 1, 2, 2, 0);
    size_t n;
    const aa_piece *p = aa_scene_pieces(s, &n);
    /* split at the y extremum into two monotone pieces, plus the flat close */
    assert_int_equal(n, 3);
    int quads = 0, flats = 0;
    for (size_t k = 0; k < n; k++) {
        quads += p[k].kind == AA_PIECE_QUAD;
        flats += p[k].kind == AA_PIECE_FLAT;
        assert_true(p[k].y0 <= p[k].y1);
    }
    assert_int_equal(quads, 2);
    assert_int_equal(flats, 1);
    for (size_t k = 0; k < n; k++) {
        if (p[k].kind != AA_PIECE_QUAD)
            continue;
        /* y = 3/4 at t = 1/4 and 3/4, so x = 1/2 and 3/2 */
        double x = aa_piece_x_at(&p[k], 0.75);
        assert_true(fabs(x - (p[k].x0 < 1 ? 0.5 : 1.5)) < 1e-15);
        assert_true(fabs(p[k].y1 - 1.0) < 1e-15);
        double ys[3];
        /* x = 1/2 on the left piece at y = 3/4 */
        if (p[k].x0 < 1) {
            assert_int_equal(aa_piece_meet_x(&p[k], 0.5, ys), 1);
            assert_true(fabs(ys[0] - 0.75) < 1e-15);
        }
        double lo, hi;
        aa_piece_xrange(&p[k], 0.75, 2.0, &lo, &hi);
        assert_true(fabs(hi - lo - 0.5) < 1e-15); /* from x = 1/2 to 1 (or 1 to 3/2) */
    }
    /* inside the parabolic segment at (1, 0.5); outside at (1, 1.5) */
    assert_true(same(aa_scene_colour_at(s, 1.0, 0.5), white));
    assert_true(same(aa_scene_colour_at(s, 1.0, 1.5), black));
    assert_true(same(aa_scene_colour_at(s, 0.1, 0.5), black));
    aa_scene_free(s);
}

static void test_fill_rules_and_layers(void **state)
{
    (void)state;
    /* two overlapping squares in one layer: the overlap is inside under
     * nonzero (winding 2) and outside under even-odd */
    for (int rule = 0; rule < 2; rule++) {
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, rule), AA_OK);
        scenes_rect(s, 0.1, 0.1, 0.6, 0.6);
        scenes_rect(s, 0.4, 0.4, 0.9, 0.9);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        assert_true(same(aa_scene_colour_at(s, 0.5, 0.5), rule == AA_FILL_NONZERO ? white : black));
        assert_true(same(aa_scene_colour_at(s, 0.2, 0.2), white));
        aa_scene_free(s);
    }
    /* Catmull's pixel (Catmull 1978, fig. 1): green and blue in front hide red */
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, green, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 0, 0, 0.5, 0.5);
    assert_int_equal(aa_scene_layer(s, blue, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 0, 0.5, 1, 1);
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 0.1, 0.1, 0.45, 0.9);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_true(same(aa_scene_colour_at(s, 0.2, 0.2), green));
    assert_true(same(aa_scene_colour_at(s, 0.2, 0.7), blue));
    assert_true(same(aa_scene_colour_at(s, 0.7, 0.2), black));
    assert_false(aa_scene_is_grey(s));
    aa_scene_free(s);
}

static void test_refusals(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_EFAIL); /* no layer yet */
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{2, 0, 0}}, AA_FILL_NONZERO), AA_EINVAL);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, NAN, 0), AA_EINVAL);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, INFINITY, 0), AA_EINVAL);
    assert_int_equal(aa_scene_quad_to(s, 0, NAN, 1, 1), AA_EINVAL);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_EFAIL); /* finished */
    aa_scene_free(s);
}

static void test_transform_and_clip(void **state)
{
    (void)state;
    aa_scene *crow = scenes_pattern("crow"), *placed;
    assert_non_null(placed = aa_scene_place(crow, 300, 200, 2.0, 0.25, -0.5));
    /* u = 300 x + 2 * 0.25, v = 200 y - 2 * 0.5 */
    srand(7);
    for (int k = 0; k < 2000; k++) {
        double x = rand() / (double)RAND_MAX, y = rand() / (double)RAND_MAX;
        assert_true(same(aa_scene_colour_at(crow, x, y),
                         aa_scene_colour_at(placed, 300 * x + 0.5, 200 * y - 1.0)));
    }
    aa_scene_free(placed);
    aa_scene_free(crow);
    /* content outside the unit square is covered by the background */
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, -0.5, -0.5, 0.5, 0.5);
    assert_int_equal(aa_scene_clip_unit(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_layer_count(s), 2);
    assert_true(same(aa_scene_colour_at(s, 0.25, 0.25), white));
    assert_true(same(aa_scene_colour_at(s, -0.25, 0.25), black));
    assert_true(same(aa_scene_colour_at(s, 0.25, -0.25), black));
    aa_scene_free(s);
}

/* A polygon scene with vertices inside bands: a star of thin triangles
 * and an overlapping second layer, placed on a 37x23 image. */
static aa_scene *polygon_scene(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.1, 0.1}});
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_EVENODD), AA_OK);
    for (int k = 0; k < 12; k++) {
        double a = 2 * M_PI * k / 12 + 0.01, b = a + M_PI / 12;
        assert_int_equal(aa_scene_move_to(s, 0.5, 0.5), AA_OK);
        assert_int_equal(aa_scene_line_to(s, 0.5 + 0.4 * cos(a), 0.5 + 0.4 * sin(a)), AA_OK);
        assert_int_equal(aa_scene_line_to(s, 0.5 + 0.4 * cos(b), 0.5 + 0.4 * sin(b)), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    assert_int_equal(aa_scene_layer(s, blue, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.2, 0.3), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.9, 0.1, 0.7, 0.8), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.3, 0.75), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_scene *p = aa_scene_place(s, 37, 23, 0, 0, 0);
    aa_scene_free(s);
    return p;
}

/* The strip's windowed answers equal the plain point query everywhere. */
static void check_strip(aa_scene *s, int w, int h, double radius)
{
    aa_strip *st = aa_strip_new(s);
    aa_span spans[256];
    assert_non_null(st);
    srand(11);
    for (int j = 0; j < h; j++) {
        double vc = j + 0.5;
        assert_int_equal(aa_strip_begin(st, vc - radius, vc + radius), AA_OK);
        for (int i = 0; i < w; i++) {
            double uc = i + 0.5, xl = uc - radius, xr = uc + radius;
            size_t n = aa_strip_window(st, xl, xr);
            for (int k = 0; k < 8; k++) {
                double x = xl + (xr - xl) * rand() / (double)RAND_MAX;
                double y = vc - radius + 2 * radius * rand() / (double)RAND_MAX;
                aa_rgb a = aa_strip_colour_at(st, x, y), b = aa_scene_colour_at(s, x, y);
                if (!same(a, b))
                    fail_msg("strip colour at (%.17g, %.17g) differs", x, y);
                if (n == 0) /* uniform window: every point has the centre's colour */
                    assert_true(same(b, aa_scene_colour_at(s, uc, vc)));
                /* spans cover the window and carry the point colours */
                size_t m = aa_strip_spans(st, y, spans, 256);
                assert_true(m >= 1 && m <= n + 1);
                assert_true(spans[0].x0 == xl && spans[m - 1].x1 == xr);
                for (size_t q = 0; q < m; q++) {
                    if (q)
                        assert_true(spans[q].x0 == spans[q - 1].x1);
                    double mid = 0.5 * (spans[q].x0 + spans[q].x1);
                    if (spans[q].x1 - spans[q].x0 > 1e-9)
                        assert_true(same(spans[q].colour, aa_scene_colour_at(s, mid, y)));
                }
            }
        }
    }
    aa_strip_free(st);
}

static void test_strip_crow(void **state)
{
    (void)state;
    aa_scene *crow = scenes_pattern("crow:curves=24,kmax=0.1"), *placed;
    assert_non_null(placed = aa_scene_place(crow, 61, 47, 0.3, 0.7, 0.2));
    check_strip(placed, 61, 47, 0.5);
    check_strip(placed, 61, 47, 1.5);
    aa_scene_free(placed);
    aa_scene_free(crow);
}

static void test_strip_polygons(void **state)
{
    (void)state;
    aa_scene *s = polygon_scene();
    check_strip(s, 37, 23, 0.5);
    check_strip(s, 37, 23, 2.0);
    aa_scene_free(s);
}

/* The crossings of a line come sorted by x (then layer, then direction)
 * whatever order the pieces give them: a comb whose contour runs right
 * along its teeth and back along its spine (the crossings in two runs,
 * one rising and one falling, as a stroke's outline gives them), and a
 * star whose edges cross the line in no order.  The known answer: each
 * edge (x0, y0)-(x1, y1) with y strictly between its ends crosses at
 * x0 + (y - y0) (x1 - x0) / (y1 - y0), going down (dir +1) where y1 > y0;
 * those sorted by qsort; the lines' y are off every vertex. */
static int cmp_cross(const void *a, const void *b)
{
    const aa_crossing *p = a, *q = b;
    return p->x < q->x ? -1 : p->x > q->x ? 1 : p->dir - q->dir;
}

static void check_crossings(const double *xy, int n, double y)
{
    aa_scene *s = scenes_polygon(xy, n, white, black, AA_FILL_NONZERO);
    static aa_crossing got[1024], want[1024];
    size_t m = 0;
    for (int k = 0; k < n; k++) {
        double x0 = xy[2 * k], y0 = xy[2 * k + 1];
        double x1 = xy[2 * ((k + 1) % n)], y1 = xy[2 * ((k + 1) % n) + 1];
        if ((y0 < y && y < y1) || (y1 < y && y < y0)) {
            want[m].x = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
            want[m].dir = y1 > y0 ? 1 : -1;
            want[m++].layer = 0;
        }
    }
    qsort(want, m, sizeof *want, cmp_cross);
    size_t got_n = aa_scene_crossings(s, y, got, 1024);
    assert_int_equal(got_n, m);
    for (size_t k = 0; k < m; k++) {
        assert_true(fabs(got[k].x - want[k].x) < 1e-12);
        assert_int_equal(got[k].dir, want[k].dir);
        if (k > 0)
            assert_true(got[k - 1].x <= got[k].x);
    }
    aa_scene_free(s);
}

static void test_crossings_sorted(void **state)
{
    (void)state;
    /* the comb: T teeth from x = 0.05 to 0.95, tips at y = 0.2 and roots
     * at y = 0.6 along the way out, then back along a spine with notches
     * from y = 0.9 down to 0.35 (across the teeth: the lines at y 0.4137
     * and 0.5137 meet both, in a rising run and a falling one); 40 teeth,
     * then 150 (600 crossings, more than sort_crossings holds on the
     * stack) */
    static double xy[2 * 600];
    int n = 0;
    const int teeth[2] = {40, 150};
    for (int c = 0; c < 2; c++) {
        int T = teeth[c];
        double d = 0.45 / T; /* a tooth's half width */
        n = 0;
        for (int k = 0; k < T; k++) {
            double x = 0.05 + 0.9 * k / T;
            xy[2 * n] = x, xy[2 * n + 1] = 0.6, n++;
            xy[2 * n] = x + d, xy[2 * n + 1] = 0.2, n++;
        }
        for (int k = T; k-- > 0;) {
            double x = 0.05 + 0.9 * (k + 1) / T;
            xy[2 * n] = x, xy[2 * n + 1] = 0.9, n++;
            xy[2 * n] = x - d, xy[2 * n + 1] = 0.35, n++;
        }
        for (int j = 0; j < 7; j++)
            check_crossings(xy, n, 0.2137 + 0.1 * j);
    }
    /* a star of 61 points (each edge jumps 30 vertices of a circle): a
     * line meets its edges in no order along the contour */
    n = 0;
    for (int k = 0; k < 61; k++) {
        double a = 2 * M_PI * (30.0 * k) / 61.0 + 0.01;
        xy[2 * n] = 0.5 + 0.45 * cos(a), xy[2 * n + 1] = 0.5 + 0.45 * sin(a), n++;
    }
    for (int j = 0; j < 7; j++)
        check_crossings(xy, n, 0.2137 + 0.1 * j);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_square),
             cmocka_unit_test(test_arc_pieces),
             cmocka_unit_test(test_fill_rules_and_layers),
             cmocka_unit_test(test_refusals),
             cmocka_unit_test(test_transform_and_clip),
             cmocka_unit_test(test_strip_crow),
             cmocka_unit_test(test_strip_polygons),
             cmocka_unit_test(test_crossings_sorted))
