/*
 * test_rings.c: the `rings` pattern (patterns/rings.c): concentric circles
 * of radii r_k = R sqrt(k/N) drawn as elliptical arcs.
 *
 * Known answers, from the definition (patterns/README.md, `rings`), not
 * from the code under test:
 *  - the scene: N closed paths of two elliptical arcs each (quad == 3),
 *    circles about the centre of radius r_k (|u| = |v| = r_k, u . v = 0);
 *  - colours: a point at distance d from the centre, r_j < d < r_{j+1}
 *    (r_0 = 0), has N - j circles around it, so it is white iff N - j is
 *    odd; outside r_N black;
 *  - windings: circles turn alternately, so along any line the winding
 *    number takes the values 0 and one sign only;
 *  - area: the white bands' area is pi R^2 ceil(N/2)/N (every band
 *    between consecutive circles has area pi (r_{j+1}^2 - r_j^2) =
 *    pi R^2/N): the box reference sums to it, and a peer (AGG, an
 *    independent rasterizer, through its own arc generator) to within its
 *    approximation (below).
 */
#include "support.h"
#include "scenes.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

typedef struct rings_case {
    const char *spec;
    int n;
    double r, x, y;
} rings_case;

static const rings_case cases[] = {
    {"rings", 64, 0.48, 0.5, 0.5},
    {"rings:rings=5,radius=0.3,x=0.4,y=0.55", 5, 0.3, 0.4, 0.55},
};
#define NCASES (sizeof cases / sizeof cases[0])

static double radius(const rings_case *c, int k) { return c->r * sqrt((double)k / c->n); }

static void test_rings_edges(void **state)
{
    (void)state;
    for (size_t q = 0; q < NCASES; q++) {
        const rings_case *c = &cases[q];
        aa_scene *s = scenes_pattern(c->spec);
        size_t ne, nc;
        const aa_edge *e = aa_scene_edges(s, &ne);
        aa_scene_contours(s, &nc);
        assert_int_equal(ne, 2 * (size_t)c->n);
        assert_int_equal(nc, (size_t)c->n);
        assert_int_equal(aa_scene_layer_count(s), 1);
        assert_int_equal(aa_scene_layer_rule(s, 0), AA_FILL_EVENODD);
        for (size_t k = 0; k < ne; k++) {
            assert_int_equal(e[k].quad, 3);
            double r = hypot(e[k].ux, e[k].uy);
            assert_true(fabs(hypot(e[k].vx, e[k].vy) - r) <= 1e-15);
            assert_true(fabs(e[k].ux * e[k].vx + e[k].uy * e[k].vy) <= 1e-15);
            assert_true(e[k].cx == c->x && e[k].cy == c->y);
            assert_true(fabs(fabs(e[k].t1 - e[k].t0) - M_PI) <= 1e-15);
            /* the radius of one of the N circles */
            double kk = (r / c->r) * (r / c->r) * c->n;
            assert_true(fabs(kk - round(kk)) <= 1e-9 && round(kk) >= 1 && round(kk) <= c->n);
        }
        aa_scene_free(s);
    }
}

static void test_rings_colours(void **state)
{
    (void)state;
    for (size_t q = 0; q < NCASES; q++) {
        const rings_case *c = &cases[q];
        aa_scene *s = scenes_pattern(c->spec);
        int checked = 0;
        for (int j = 0; j <= c->n; j++) {
            /* the middle of band j (beyond r_N for j = N) */
            double d = j < c->n ? (radius(c, j) + radius(c, j + 1)) / 2 : c->r * 1.01;
            int white = j < c->n && (c->n - j) % 2 == 1;
            for (int a = 0; a < 12; a++) {
                double ang = 2 * M_PI * (a + 0.37) / 12;
                aa_rgb col = aa_scene_colour_at(s, c->x + d * cos(ang), c->y + d * sin(ang));
                if (col.c[0] != (white ? 1.0 : 0.0))
                    fail_msg("%s: band %d at angle %.3f: %g, want %s", c->spec, j, ang,
                             col.c[0], white ? "white" : "black");
                checked++;
            }
        }
        print_message("%s: %d points in %d bands\n", c->spec, checked, c->n + 1);
        aa_scene_free(s);
    }
}

static void test_rings_windings(void **state)
{
    (void)state;
    for (size_t q = 0; q < NCASES; q++) {
        const rings_case *c = &cases[q];
        aa_scene *s = scenes_pattern(c->spec);
        aa_crossing cross[2 * 4096];
        for (int l = 0; l < 7; l++) {
            double y = c->y + c->r * (l - 3 + 0.1) / 4;
            size_t n = aa_scene_crossings(s, y, cross, sizeof cross / sizeof cross[0]);
            int wind = 0, seen = 0;
            for (size_t k = 0; k < n; k++) {
                wind += cross[k].dir;
                if (wind && seen && wind != seen)
                    fail_msg("%s: windings %d and %d on y = %g", c->spec, seen, wind, y);
                if (wind)
                    seen = wind;
                assert_true(wind >= -1 && wind <= 1);
            }
            assert_int_equal(wind, 0);
        }
        aa_scene_free(s);
    }
}

/* The closed form of the white area. */
static double white_area(const rings_case *c)
{
    return M_PI * c->r * c->r * ((c->n + 1) / 2) / c->n;
}

/* AGG at approximation scale 64 draws each circle as chords within
 * 0.125/64 px inside it (algorithms/README.md), positions rounded to
 * 1/256 px, 8-bit coverage: its image's sum is off the white area by at
 * most sum_k 2 pi r_k (0.125/64 + 1/256) (the boundary moves by that much
 * at most) plus 1/255 for each pixel a circle crosses (at most 8 r + 12 for
 * a circle of radius r px: each quarter is monotone in x and y across r
 * columns and rows). */
static void test_rings_peer_area(void **state)
{
    (void)state;
    const int w = 256;
    for (size_t q = 0; q < NCASES; q++) {
        const rings_case *c = &cases[q];
        aa_scene *s = scenes_pattern(c->spec);
        aa_image img;
        support_render("agg:scale=64", s, "box", w, w, 2, &img, NULL);
        double sum = support_channel_mean(&img, 0) * w * w, want = white_area(c) * w * w;
        double bound = 0.0;
        for (int k = 1; k <= c->n; k++) {
            double r = radius(c, k) * w;
            bound += 2 * M_PI * r * (0.125 / 64 + 1.0 / 256) + (8 * r + 12) / 255;
        }
        print_message("%s: agg's sum %.3f px^2, white area %.3f, bound %.3f\n", c->spec, sum,
                      want, bound);
        if (!(fabs(sum - want) <= bound))
            fail_msg("%s: agg's sum %.6f, the white area %.6f (bound %.3f)", c->spec, sum,
                     want, bound);
        /* a band dropped or added would move it by pi R^2/N */
        assert_true(bound < M_PI * c->r * c->r / c->n * w * w);
        aa_image_free(&img);
        aa_scene_free(s);
    }
}

/* The box reference sums to the white area, within its own bounds. */
static void test_rings_reference_area(void **state)
{
    (void)state;
    const int w = 64, h = 48;
    for (size_t q = 0; q < NCASES; q++) {
        const rings_case *c = &cases[q];
        const support_view v = {.w = w, .h = h, .filter = "box", .threads = 0};
        aa_image img, bound;
        support_pattern_reference(c->spec, &v, &img, &bound, NULL);
        double sum = 0.0, berr = 0.0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++)
                sum += aa_pixel(&img, i, j)[0], berr += aa_pixel(&bound, i, j)[0];
        double got = sum / ((double)w * h), want = white_area(c);
        double tol = berr / ((double)w * h) + 1e-13;
        print_message("%s: reference %.17g, closed form %.17g (bound %.2e)\n", c->spec, got,
                      want, tol);
        if (!(fabs(got - want) <= tol))
            fail_msg("%s: the reference sums to %.17g, the closed form %.17g (off %.3e, "
                     "bound %.3e)",
                     c->spec, got, want, got - want, tol);
        aa_image_free(&img);
        aa_image_free(&bound);
    }
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_rings_edges),
             cmocka_unit_test(test_rings_colours), cmocka_unit_test(test_rings_windings),
             cmocka_unit_test(test_rings_peer_area),
             cmocka_unit_test(test_rings_reference_area))
