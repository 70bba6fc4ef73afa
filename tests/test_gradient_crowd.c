/*
 * test_gradient_crowd.c: the exact reference of gradient paint in crowded
 * windows (more than 48 pieces near a pixel: the sum over spans with the
 * crowd path's sweep for the meetings, harness/truth/truth.c) and on
 * offset curves (strokes of Bezier arcs).
 *
 * Known answers, derived here and not from the code under test:
 *  - two regular polygons of 80 and 70 sides, each smaller than a pixel
 *    and crossing each other, painted by linear gradients whose encoded
 *    values stay below the decoding's threshold 0.04045, where the
 *    decoding is e / 12.92, so that the linear colour is affine in x and
 *    y: under the box filter a pixel is the integral of an affine
 *    function over convex polygons, sum over the front polygon's part in
 *    the pixel (layers are added front to back) plus the back one's
 *    minus the back one's part under the front (each part clipped here
 *    by Sutherland and Hodgman's
 *    algorithm; the integral of a + b x + c y over a polygon from its
 *    area and first moments by the shoelace formulas);
 *  - the same with two equal stops against the flat colour's reference,
 *    which takes the crowd path proper (colour jumps piece by piece,
 *    truth_crowd.c: another derivation) under box, tent:r=1 and the cone;
 *  - every pixel's bound within 1e-12.
 */
#include "core.h"
#include "support.h"
#include "truth.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 4
#define H 4

/* ---- the polygons ---- */

#define NA 80
#define NB 70
#define MAXV 512

typedef struct poly {
    int n;
    double x[MAXV], y[MAXV];
} poly;

static poly regular(int n, double cx, double cy, double r, double phase)
{
    poly p;
    p.n = n;
    for (int k = 0; k < n; k++) {
        double a = phase + 2.0 * M_PI * k / n;
        p.x[k] = cx + r * cos(a), p.y[k] = cy + r * sin(a);
    }
    return p;
}

/* p clipped to the half plane left of the directed edge (ax, ay) -> (bx,
 * by) of a counter-clockwise convex polygon (Sutherland and Hodgman). */
static poly clip_edge(const poly *p, double ax, double ay, double bx, double by)
{
    poly o;
    o.n = 0;
    for (int k = 0; k < p->n; k++) {
        int j = (k + 1) % p->n;
        double sk = (bx - ax) * (p->y[k] - ay) - (by - ay) * (p->x[k] - ax);
        double sj = (bx - ax) * (p->y[j] - ay) - (by - ay) * (p->x[j] - ax);
        if (sk >= 0)
            o.x[o.n] = p->x[k], o.y[o.n++] = p->y[k];
        if ((sk >= 0) != (sj >= 0)) {
            double t = sk / (sk - sj);
            o.x[o.n] = p->x[k] + t * (p->x[j] - p->x[k]);
            o.y[o.n++] = p->y[k] + t * (p->y[j] - p->y[k]);
        }
    }
    return o;
}

static poly clip(const poly *p, const poly *by)
{
    poly o = *p;
    for (int k = 0; k < by->n && o.n; k++) {
        int j = (k + 1) % by->n;
        o = clip_edge(&o, by->x[k], by->y[k], by->x[j], by->y[j]);
    }
    return o;
}

/* The integral of a + b x + c y over p: a A + b Mx + c My, the area and
 * first moments by the shoelace formulas (long double). */
static long double affine_integral(const poly *p, double a, double b, double c)
{
    long double A = 0, Mx = 0, My = 0;
    for (int k = 0; k < p->n; k++) {
        int j = (k + 1) % p->n;
        long double cr = (long double)p->x[k] * p->y[j] - (long double)p->x[j] * p->y[k];
        A += cr;
        Mx += ((long double)p->x[k] + p->x[j]) * cr;
        My += ((long double)p->y[k] + p->y[j]) * cr;
    }
    A /= 2, Mx /= 6, My /= 6;
    return a * A + b * Mx + c * My;
}

/* Polygon p as a layer of s (pattern units). */
static void add_poly(aa_scene *s, const poly *p, aa_rgb col)
{
    assert_int_equal(aa_scene_layer(s, col, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, p->x[0] / W, p->y[0] / H), AA_OK);
    for (int k = 1; k < p->n; k++)
        assert_int_equal(aa_scene_line_to(s, p->x[k] / W, p->y[k] / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* A linear gradient in pixels from (x1, y1) to (x2, y2), stops st. */
static void set_linear(aa_scene *s, double x1, double y1, double x2, double y2,
                       const aa_gradient_stop *st)
{
    aa_gradient g = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {x1, y1, x2, y2, 0, 0},
                     {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, st};
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
}

/* Stop colours in linear light whose encoded values are e[0..2] (each
 * below 0.04045: the encoded value is 12.92 times the linear one). */
static aa_gradient_stop stop_enc(double offset, double r, double g, double b)
{
    aa_gradient_stop s = {offset, {{r / 12.92, g / 12.92, b / 12.92}}, 1.0};
    return s;
}

static const double A1[4] = {0.2, 0.3, 3.9, 3.4}, A2[4] = {3.5, 0.1, 0.6, 3.8};

static void reference(const aa_scene *s, const char *filter, aa_image *ref, aa_image *bound,
                      aa_truth_stats *stats)
{
    support_view v = {W, H, 0, 0, 0, filter, 1, 1, 0};
    support_reference(s, &v, ref, bound, stats);
}

/* The affine coefficients (a + b x + c y) of channel ch of the linear
 * colour of a gradient from P1 to P2 with stops s0 and s1 (t inside [0,
 * 1] over the polygons: no clamping). */
static void affine_of(const double P[4], const aa_gradient_stop *st, int ch, double *a,
                      double *b, double *c)
{
    double dx = P[2] - P[0], dy = P[3] - P[1], l2 = dx * dx + dy * dy;
    double c0 = st[0].colour.c[ch], c1 = st[1].colour.c[ch];
    /* t = ((x - x1) dx + (y - y1) dy) / l2; colour c0 + t (c1 - c0) */
    *b = (c1 - c0) * dx / l2, *c = (c1 - c0) * dy / l2;
    *a = c0 - (c1 - c0) * (P[0] * dx + P[1] * dy) / l2;
}

static void test_crowded_box(void **state)
{
    (void)state;
    poly pa = regular(NA, 1.5, 1.5, 0.42, 0.1), pb = regular(NB, 1.62, 1.58, 0.33, 0.37);
    const aa_gradient_stop s1[2] = {stop_enc(0, 0.0, 0.03, 0.02), stop_enc(1, 0.04, 0.0, 0.02)};
    const aa_gradient_stop s2[2] = {stop_enc(0, 0.035, 0.004, 0.0), stop_enc(1, 0.001, 0.039, 0.03)};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    add_poly(s, &pa, (aa_rgb){{0, 0, 0}});
    set_linear(s, A1[0], A1[1], A1[2], A1[3], s1);
    add_poly(s, &pb, (aa_rgb){{0, 0, 0}});
    set_linear(s, A2[0], A2[1], A2[2], A2[3], s2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, "box", &ref, &bound, &stats);
    print_message("crowded windows, box: %zu pixels integrated, largest bound %.2g\n",
                  stats.integrated, stats.max_bound);
    /* the polygons' edges: 150 pieces near pixel (1, 1) */
    {
        aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
        size_t np;
        aa_scene_pieces(placed, &np);
        assert_true(np >= NA + NB);
        aa_scene_free(placed);
    }
    assert_true(stats.max_bound <= 1e-12);
    double worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            poly sq = {4, {i, i + 1, i + 1, i}, {j, j, j + 1, j + 1}};
            poly qa = clip(&pa, &sq), qb = clip(&pb, &sq), qab = clip(&qb, &pa);
            for (int ch = 0; ch < 3; ch++) {
                double a, b, c, a2, b2, c2;
                affine_of(A1, s1, ch, &a, &b, &c);
                affine_of(A2, s2, ch, &a2, &b2, &c2);
                /* pa in front (added first) */
                long double want = affine_integral(&qa, a, b, c) +
                                   affine_integral(&qb, a2, b2, c2) -
                                   affine_integral(&qab, a2, b2, c2);
                double got = aa_pixel(&ref, i, j)[ch], bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - (double)want));
                if (!(fabs(got - (double)want) <= bd + 1e-16))
                    fail_msg("pixel (%d, %d) channel %d: %.17g, the polygons' closed form "
                             "%.17Lg (bound %.3g)",
                             i, j, ch, got, want, bd);
            }
        }
    print_message("crowded windows, box: largest difference from the closed form %.2g\n", worst);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* Two equal stops against the flat colours, which take the crowd path. */
static void test_crowded_constant(void **state)
{
    (void)state;
    poly pa = regular(NA, 1.5, 1.5, 0.42, 0.1), pb = regular(NB, 1.62, 1.58, 0.33, 0.37);
    const aa_rgb ca = {{0.7, 0.2, 0.05}}, cb = {{0.1, 0.5, 0.9}};
    const aa_gradient_stop sa[2] = {{0, ca, 1.0}, {1, ca, 1.0}}, sb[2] = {{0, cb, 1.0}, {1, cb, 1.0}};
    aa_scene *g = aa_scene_new((aa_rgb){{0.2, 0.2, 0.2}}), *flat = aa_scene_new((aa_rgb){{0.2, 0.2, 0.2}});
    add_poly(g, &pa, ca);
    set_linear(g, A1[0], A1[1], A1[2], A1[3], sa);
    add_poly(g, &pb, cb);
    set_linear(g, A2[0], A2[1], A2[2], A2[3], sb);
    add_poly(flat, &pa, ca);
    add_poly(flat, &pb, cb);
    assert_int_equal(aa_scene_finish(g), AA_OK);
    assert_int_equal(aa_scene_finish(flat), AA_OK);
    static const char *const filters[] = {"box", "tent:r=1", "cone:r=1"};
    for (int k = 0; k < 3; k++) {
        aa_image rg, rf, bg, bf;
        aa_truth_stats sg, sf;
        reference(g, filters[k], &rg, &bg, &sg);
        reference(flat, filters[k], &rf, &bf, &sf);
        double worst = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                for (int ch = 0; ch < 3; ch++)
                    worst = fmax(worst, fabs(aa_pixel(&rg, i, j)[ch] - aa_pixel(&rf, i, j)[ch]));
        print_message("%-9s crowded: constant gradients against the flat colours (%zu pixels "
                      "crowded there): %.2g (bounds %.2g, %.2g)\n",
                      filters[k], sf.crowded, worst, sg.max_bound, sf.max_bound);
        assert_true(sf.crowded > 0); /* the flat colours did take the crowd path */
        assert_true(sg.max_bound <= 1e-12);
        if (!(worst <= sg.max_bound + sf.max_bound + 1e-15))
            fail_msg("%s: constant gradients %.3g off the flat colours in crowded windows",
                     filters[k], worst);
        aa_image_free(&rg);
        aa_image_free(&rf);
        aa_image_free(&bg);
        aa_image_free(&bf);
    }
    aa_scene_free(g);
    aa_scene_free(flat);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crowded_box),
        cmocka_unit_test(test_crowded_constant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
