/*
 * test_scene_conic.c: elliptical arcs in the scene model (aa_scene_arc_to,
 * AA_PIECE_CONIC): how an arc is split into y-monotone pieces, and each
 * piece's queries (x at a height, x extent, meetings with a vertical line,
 * with a line and with another arc), against the ellipse's own equation
 * written here: a point (x, y) is on the ellipse of centre c and
 * semi-diameters u, v when, with (a, b) solving c + a u + b v = (x, y),
 * a^2 + b^2 = 1 (Cramer's rule below), independently of the pieces'
 * angle form.  Circles give the answers by hand: x = cx +- sqrt(r^2 -
 * (y - cy)^2).
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* A white ellipse on black: centre c, semi-diameters u, v, as two half
 * arcs (t 0 .. pi .. 2 pi), or reversed (t 2 pi .. pi .. 0). */
static aa_scene *ellipse_scene(double cx, double cy, double ux, double uy, double vx, double vy,
                               int reversed, aa_fill_rule rule)
{
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, rule), AA_OK);
    double ax = cx + ux, ay = cy + uy, bx = cx - ux, by = cy - uy;
    assert_int_equal(aa_scene_move_to(s, ax, ay), AA_OK);
    if (!reversed) {
        assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, 0, M_PI, bx, by), AA_OK);
        assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, M_PI, 2 * M_PI, ax, ay),
                         AA_OK);
    } else {
        assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, 2 * M_PI, M_PI, bx, by),
                         AA_OK);
        assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, M_PI, 0, ax, ay), AA_OK);
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* a^2 + b^2 - 1 for the point: 0 on the ellipse, < 0 inside. */
static double ellipse_level(double cx, double cy, double ux, double uy, double vx, double vy,
                            double x, double y)
{
    double det = ux * vy - uy * vx, dx = x - cx, dy = y - cy;
    double a = (dx * vy - dy * vx) / det, b = (ux * dy - uy * dx) / det;
    return a * a + b * b - 1.0;
}

static void test_circle_pieces(void **state)
{
    (void)state;
    /* a circle of radius 0.25 at (0.5, 0.5): two arcs, split at the top
     * (t = 3 pi/2 here, y = 0.25) and the bottom (t = pi/2, y = 0.75) into
     * four quarter... pieces: the arc 0..pi turns at pi/2 (bottom), pi..2pi
     * at 3pi/2 (top): four y-monotone pieces */
    for (int rev = 0; rev < 2; rev++) {
        aa_scene *s = ellipse_scene(0.5, 0.5, 0.25, 0, 0, 0.25, rev, AA_FILL_NONZERO);
        size_t n;
        const aa_piece *p = aa_scene_pieces(s, &n);
        assert_int_equal(n, 4);
        int down = 0, up = 0;
        for (size_t k = 0; k < n; k++) {
            assert_int_equal(p[k].kind, AA_PIECE_CONIC);
            assert_true(p[k].y0 < p[k].y1);
            assert_true(p[k].s0 >= 0 && p[k].s1 <= M_PI && p[k].s0 < p[k].s1);
            down += p[k].dir > 0, up += p[k].dir < 0;
            /* each piece is a quarter: from a side (y = 0.5) to the top or
             * bottom, whose point is the turn's exact (0.5, 0.25 or 0.75) */
            assert_true(fabs(p[k].y1 - p[k].y0 - 0.25) < 1e-15);
            assert_true(p[k].y0 == 0.25 || p[k].y1 == 0.75);
            /* xmin, xmax by hand: a quarter spans 0.25 in x */
            assert_true(fabs(p[k].xmax - p[k].xmin - 0.25) < 1e-15);
        }
        assert_int_equal(down, 2);
        assert_int_equal(up, 2);
        double x0, y0, x1, y1;
        aa_scene_bounds(s, &x0, &y0, &x1, &y1);
        assert_true(fabs(x0 - 0.25) < 1e-15 && fabs(x1 - 0.75) < 1e-15);
        assert_true(y0 == 0.25 && y1 == 0.75);
        /* crossings of y: x = 0.5 -+ sqrt(r^2 - (y - 0.5)^2), one up, one
         * down */
        for (int j = 0; j <= 100; j++) {
            double y = 0.25 + 0.5 * j / 100.0;
            aa_crossing c[4];
            size_t m = aa_scene_crossings(s, y, c, 4);
            if (j == 100) {
                assert_int_equal(m, 0); /* the bottom: y1 excluded */
                continue;
            }
            assert_int_equal(m, 2);
            double h = sqrt(fmax(0.0, 0.0625 - (y - 0.5) * (y - 0.5)));
            assert_true(fabs(c[0].x - (0.5 - h)) < 2e-15 + (j == 0 ? 1e-7 : 0));
            assert_true(fabs(c[1].x - (0.5 + h)) < 2e-15 + (j == 0 ? 1e-7 : 0));
            assert_int_equal(c[0].dir, -c[1].dir);
        }
        aa_scene_free(s);
    }
}

static double frand(unsigned *st)
{
    *st = *st * 1103515245u + 12345u;
    return (double)((*st >> 8) & 0xffffff) / 16777216.0;
}

static void test_rotated_ellipse_points(void **state)
{
    (void)state;
    /* an ellipse of semi-axes 0.3 and 0.1 turned by 30 degrees, and one
     * given by oblique conjugate semi-diameters; both directions; points
     * inside iff the level is < 0 */
    const double E[2][6] = {
        {0.5, 0.5, 0.3 * cos(M_PI / 6), 0.3 * sin(M_PI / 6), -0.1 * sin(M_PI / 6),
         0.1 * cos(M_PI / 6)},
        {0.45, 0.55, 0.2, 0.15, -0.05, 0.25}};
    unsigned st = 7;
    for (int e = 0; e < 2; e++)
        for (int rev = 0; rev < 2; rev++) {
            const double *q = E[e];
            aa_scene *s =
                ellipse_scene(q[0], q[1], q[2], q[3], q[4], q[5], rev, AA_FILL_NONZERO);
            int checked = 0;
            for (int k = 0; k < 20000; k++) {
                double x = frand(&st), y = frand(&st);
                double lev = ellipse_level(q[0], q[1], q[2], q[3], q[4], q[5], x, y);
                if (fabs(lev) < 1e-9)
                    continue;
                aa_rgb c = aa_scene_colour_at(s, x, y);
                assert_true(c.c[0] == (lev < 0 ? 1.0 : 0.0));
                checked++;
            }
            assert_true(checked > 19000);
            /* every piece's crossing lies on the ellipse */
            size_t n;
            const aa_piece *p = aa_scene_pieces(s, &n);
            for (size_t k = 0; k < n; k++)
                for (int j = 0; j <= 50; j++) {
                    double y = p[k].y0 + (p[k].y1 - p[k].y0) * j / 50.0;
                    double x = aa_piece_x_at(&p[k], y);
                    double lev = ellipse_level(q[0], q[1], q[2], q[3], q[4], q[5], x, y);
                    /* near the turns x moves like sqrt of the height: the
                     * level's error grows there, so a looser bound */
                    assert_true(fabs(lev) < 1e-13);
                    double lo, hi;
                    aa_piece_xrange(&p[k], y, fmin(p[k].y1, y + 0.01), &lo, &hi);
                    assert_true(lo <= x + 1e-15 && x <= hi + 1e-15);
                }
            aa_scene_free(s);
        }
}

static void test_meet_x_and_lines(void **state)
{
    (void)state;
    aa_scene *s = ellipse_scene(0.5, 0.5, 0.25, 0, 0, 0.25, 0, AA_FILL_NONZERO);
    size_t n;
    const aa_piece *p = aa_scene_pieces(s, &n);
    /* the vertical line x = 0.6 meets the circle at y = 0.5 -+ sqrt(r^2 -
     * 0.01): one height on each of the two right-hand pieces */
    double want = sqrt(0.0625 - 0.01);
    int found = 0;
    for (size_t k = 0; k < n; k++) {
        double ys[3];
        int m = aa_piece_meet_x(&p[k], 0.6, ys);
        for (int j = 0; j < m; j++) {
            assert_true(fabs(fabs(ys[j] - 0.5) - want) < 1e-15);
            found++;
        }
    }
    assert_int_equal(found, 2);
    /* a line piece x = 0.3 + (y - 0.2) (45 degrees) meets the circle where
     * (x - 0.5)^2 + (y - 0.5)^2 = r^2, solved by hand below */
    aa_scene *l = aa_scene_new(black);
    aa_scene_layer(l, white, AA_FILL_NONZERO);
    aa_scene_move_to(l, 0.3, 0.2);
    aa_scene_line_to(l, 0.9, 0.8);
    aa_scene_line_to(l, 0.0, 0.8);
    aa_scene_close(l);
    aa_scene_finish(l);
    size_t nl;
    const aa_piece *lp = aa_scene_pieces(l, &nl);
    const aa_piece *diag = NULL;
    for (size_t k = 0; k < nl; k++)
        if (lp[k].kind == AA_PIECE_LINE && lp[k].x1 > lp[k].x0)
            diag = &lp[k];
    assert_non_null(diag);
    /* with w = y - 0.5: x - 0.5 = w + 0.1, so (w + 0.1)^2 + w^2 = 0.0625:
     * 2 w^2 + 0.2 w - 0.0525 = 0, w = (-0.2 +- sqrt(0.04 + 0.42))/4 */
    double w1 = (-0.2 - sqrt(0.04 + 0.42)) / 4, w2 = (-0.2 + sqrt(0.04 + 0.42)) / 4;
    double got[4];
    int ng = 0;
    for (size_t k = 0; k < n; k++) {
        double ys[4];
        int m = aa_piece_meet(diag, &p[k], 0.0, 1.0, ys, 4);
        int m2 = aa_piece_meet(&p[k], diag, 0.0, 1.0, ys + 2, 2);
        assert_int_equal(m, m2);
        for (int j = 0; j < m; j++) {
            assert_true(fabs(ys[j] - ys[2 + j]) < 1e-15);
            got[ng++] = ys[j];
        }
    }
    assert_int_equal(ng, 2);
    double a = fmin(got[0], got[1]), b = fmax(got[0], got[1]);
    assert_true(fabs(a - (0.5 + w1)) < 1e-15);
    assert_true(fabs(b - (0.5 + w2)) < 1e-15);
    /* two circles of radius 0.25 at x = 0.5 and 0.7 meet at x = 0.6,
     * y = 0.5 -+ sqrt(0.0625 - 0.01) (found by the general bisection and
     * polished) */
    aa_scene *t = ellipse_scene(0.7, 0.5, 0.25, 0, 0, 0.25, 0, AA_FILL_NONZERO);
    size_t nt;
    const aa_piece *tp = aa_scene_pieces(t, &nt);
    int nm = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < nt; j++) {
            double ys[4];
            int m = aa_piece_meet(&p[i], &tp[j], 0.0, 1.0, ys, 4);
            for (int k = 0; k < m; k++) {
                assert_true(fabs(fabs(ys[k] - 0.5) - want) < 1e-14);
                nm++;
            }
        }
    assert_int_equal(nm, 2);
    aa_scene_free(t);
    aa_scene_free(l);
    aa_scene_free(s);
}

static void test_arc_refusals_and_transform(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    aa_scene_layer(s, white, AA_FILL_NONZERO);
    assert_int_equal(aa_scene_arc_to(s, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0), AA_EFAIL); /* no pen */
    aa_scene_move_to(s, 1.0, 0.0);
    /* the pen is not the arc's start; parallel semi-diameters; a sweep
     * over 2 pi; NaN */
    assert_int_equal(aa_scene_arc_to(s, 0.5, 0, 1, 0, 0, 1, 0, M_PI, -0.5, 0), AA_EINVAL);
    assert_int_equal(aa_scene_arc_to(s, 0, 0, 1, 0, 2, 0, 0, M_PI, -1, 0), AA_EINVAL);
    assert_int_equal(aa_scene_arc_to(s, 0, 0, 1, 0, 0, 1, 0, 7, cos(7), sin(7)), AA_EINVAL);
    assert_int_equal(aa_scene_arc_to(s, 0, 0, 1, 0, 0, NAN, 0, 1, cos(1), sin(1)), AA_EINVAL);
    /* an empty sweep adds nothing */
    assert_int_equal(aa_scene_arc_to(s, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0), AA_OK);
    size_t ne;
    aa_scene_edges(s, &ne);
    assert_int_equal(ne, 0);
    aa_scene_free(s);

    /* placed on 64 x 32 pixels the circle becomes an ellipse of semi-axes
     * 16 and 8 around (32, 16): crossings by hand */
    aa_scene *c = ellipse_scene(0.5, 0.5, 0.25, 0, 0, 0.25, 0, AA_FILL_NONZERO);
    aa_scene *pl = aa_scene_place(c, 64, 32, 0, 0, 0);
    assert_non_null(pl);
    aa_crossing x[4];
    assert_int_equal(aa_scene_crossings(pl, 20.0, x, 4), 2);
    double h = 16.0 * sqrt(1.0 - (4.0 / 8.0) * (4.0 / 8.0));
    assert_true(fabs(x[0].x - (32 - h)) < 1e-13 && fabs(x[1].x - (32 + h)) < 1e-13);
    aa_scene_free(pl);
    /* outside the unit square: clip_unit sees the arc's own extent (the
     * circle reaches x = 1.1 though its ends are inside) */
    aa_scene *o = aa_scene_new(black);
    aa_scene_layer(o, white, AA_FILL_NONZERO);
    aa_scene_move_to(o, 0.8, 0.2);
    aa_scene_arc_to(o, 0.8, 0.5, 0, -0.3, 0.3, 0, 0, M_PI, 0.8, 0.8);
    aa_scene_close(o);
    assert_int_equal(aa_scene_clip_unit(o), AA_OK);
    assert_int_equal(aa_scene_layer_count(o), 2); /* the frame was added */
    aa_scene_free(o);
    aa_scene_free(c);
}

/* A crescent: the upper half of the circle of centre (4.4, 16) and radius
 * 2.4 from (2, 16) to (6.8, 16), back along the upper half of the ellipse
 * of the same centre and semi-axes 2.4 and 1.6 (arcs.svg's first `A` and
 * `a` path placed on 20 x 20 pixels).  The two meet only at their common
 * end points: with X = x - 4.4, Y = y - 16, X^2 + Y^2 = 2.4^2 and
 * X^2/2.4^2 + Y^2/1.6^2 = 1 give Y^2 (1 - 2.4^2/1.6^2) = 0, Y = 0.  Near
 * the ends they are tangent (both vertical), their x apart by about 0.26
 * Y^2, within rounding of each other for |Y| below about 1e-7.  So no
 * band strictly above y = 16, wherever it stops short of it, holds a
 * meeting of the circle's and the ellipse's pieces on one side. */
static void test_crescent_meetings(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 2.0, 16.0), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, 4.4, 16.0, -2.4, 0, 0, -2.4, 0, M_PI, 6.8, 16.0), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, 4.4, 16.0, 2.4, 0, 0, -1.6, 0, M_PI, 2.0, 16.0), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    size_t n;
    const aa_piece *p = aa_scene_pieces(s, &n);
    int pairs = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            const aa_piece *a = &p[i], *b = &p[j];
            /* the circle's and the ellipse's pieces on one side: both end
             * at y = 16 at one point */
            if (a->kind != AA_PIECE_CONIC || b->kind != AA_PIECE_CONIC || a->y1 != 16.0 ||
                b->y1 != 16.0 || fabs(a->x1 - b->x1) > 1e-12 || a->er == b->er)
                continue;
            pairs++;
            double lo = fmax(a->y0, b->y0);
            for (int k = 0; k <= 40; k++) {
                /* cut at 16 - 2^-k, 1 down to about 1e-12 below the end */
                double cut = 16.0 - ldexp(1.0, -k), ys[4];
                int m1 = aa_piece_meet(a, b, lo, cut, ys, 4);
                if (m1 != 0)
                    fail_msg("pieces %zu, %zu over [%.17g, %.17g]: %d meetings, the first "
                             "at %.17g; none exists",
                             i, j, lo, cut, m1, ys[0]);
                int m2 = aa_piece_meet(b, a, cut, 16.0, ys, 4);
                if (m2 != 0)
                    fail_msg("pieces %zu, %zu over [%.17g, 16]: %d meetings, the first at "
                             "%.17g; none exists",
                             j, i, cut, m2, ys[0]);
            }
        }
    assert_int_equal(pairs, 2);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_circle_pieces),
             cmocka_unit_test(test_rotated_ellipse_points), cmocka_unit_test(test_meet_x_and_lines),
             cmocka_unit_test(test_arc_refusals_and_transform),
             cmocka_unit_test(test_crescent_meetings))
