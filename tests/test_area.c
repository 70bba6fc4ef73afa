/*
 * test_area.c: the exact area method (algorithms/area.c) against answers
 * derived independently of it.
 *
 *  - `crow` under the box filter against aa_truth_render (adaptive
 *    quadrature, its own code path) and against tests/oracle.c's closed
 *    form from patterns/README.md, on every pixel of 256x256, 7x3 and 255x129:
 *    within 1e-9 (the bar set for it); in practice about 1e-15.  Also
 *    non-default parameters, arcs reaching outside the unit square (so the
 *    background frame layer overlaps them), a scene moved by a fraction of a
 *    pixel, and 4096-pixel-wide and -tall images.
 *  - Catmull's own pixel (Catmull 1978, fig. 1): (0, 0.25, 0.5).
 *  - three overlapping convex polygon layers, front to back, against areas
 *    from a polygon clipper written here (Sutherland-Hodgman and the
 *    shoelace formula, as in tests/test_truth.c), with inclusion-exclusion
 *    for what each layer shows; and two overlapping paths in one layer under
 *    each fill rule (nonzero: the union; even-odd: the symmetric
 *    difference).
 *  - a parabolic segment (Archimedes: 2/3 of its control triangle) half
 *    hidden by a front layer: the visible area in closed form.
 *  - random polygon scenes (several layers, both fill rules, vertices
 *    anywhere) against the reference; the two pixel integrators (Catmull's
 *    and the y-bands) against each other on random scenes with arcs.
 *  - known counters, exact uniform pixels, any thread count the same image,
 *    filters other than the box refused with a message.
 *  - crowded clusters (more than AR_CROWD segs, tested for crossings by
 *    neighbours along x): 2048 arcs 1e-5 apart against the closed form, and
 *    120 crossing segs in one cluster against the reference.
 */
#include "bench.h"
#include "oracle.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* Render `method` on a pattern-unit scene at w x h (time t, motion vx, vy). */
static int render_at(const char *method, const aa_scene *scene, int w, int h, double t,
                     double vx, double vy, int threads, aa_image *out, aa_counters *c)
{
    aa_filter f;
    aa_spec spec;
    aa_job job;
    aa_filter_default(&f);
    int st = aa_method_parse(method, &f, &spec);
    if (st)
        return st;
    assert_int_equal(aa_job_init(&job, scene, w, h, t, vx, vy, &f, 1, threads), AA_OK);
    assert_int_equal(aa_image_alloc(out, w, h, 3), AA_OK);
    st = aa_method_run(&spec, &job, 1, out, c, NULL);
    aa_job_free(&job);
    if (st)
        aa_image_free(out);
    return st;
}

static void render(const char *method, const aa_scene *scene, int w, int h, int threads,
                   aa_image *out, aa_counters *c)
{
    if (render_at(method, scene, w, h, 0, 0, 0, threads, out, c))
        fail_msg("%s: %s", method, aa_last_error());
}

/* The box reference of the same view. */
static void reference_at(const aa_scene *scene, int w, int h, double t, double vx, double vy,
                         aa_image *out)
{
    aa_filter f;
    aa_filter_default(&f);
    aa_scene *placed = aa_scene_place(scene, w, h, t, vx, vy);
    assert_non_null(placed);
    assert_int_equal(aa_image_alloc(out, w, h, 3), AA_OK);
    assert_int_equal(aa_truth_render(placed, &f, 0, out, NULL, NULL), AA_OK);
    aa_scene_free(placed);
}

static double max_diff(const aa_image *a, const aa_image *b, int *wi, int *wj)
{
    double worst = 0;
    for (int j = 0; j < a->h; j++)
        for (int i = 0; i < a->w; i++)
            for (int ch = 0; ch < 3; ch++) {
                double d = fabs(aa_pixel(a, i, j)[ch] - aa_pixel(b, i, j)[ch]);
                if (!(d <= worst)) {
                    worst = d;
                    if (wi)
                        *wi = i, *wj = j;
                }
            }
    return worst;
}

static aa_scene *pattern(const char *text)
{
    aa_spec spec;
    aa_scene *s;
    assert_int_equal(aa_pattern_parse(text, &spec), AA_OK);
    assert_int_equal(aa_pattern_scene(&spec, &s), AA_OK);
    return s;
}

/* Both integrators against the reference on a view; returns the worst. */
static double check_reference(const char *what, const aa_scene *scene, int w, int h, double t,
                              double vx, double vy, double tol)
{
    const char *methods[2] = {"area", "area:integrator=bands"};
    aa_image ref, img;
    aa_counters c;
    reference_at(scene, w, h, t, vx, vy, &ref);
    double worst = 0;
    for (int m = 0; m < 2; m++) {
        assert_int_equal(render_at(methods[m], scene, w, h, t, vx, vy, 2, &img, &c), AA_OK);
        int wi = 0, wj = 0;
        double d = max_diff(&img, &ref, &wi, &wj);
        if (!(d <= tol))
            fail_msg("%s %dx%d %s: pixel (%d, %d) is %.17g, the reference %.17g (%.3e off)", what,
                     w, h, methods[m], wi, wj, aa_pixel(&img, wi, wj)[0],
                     aa_pixel(&ref, wi, wj)[0], d);
        worst = fmax(worst, d);
        aa_image_free(&img);
    }
    print_message("%-48s %4dx%-4d max |area - reference| %.2e\n", what, w, h, worst);
    aa_image_free(&ref);
    return worst;
}

/* ---- crow ---- */

/* The acceptance bar: the box reference within 1e-9 on crow 256x256,
 * 7x3 and 255x129.  The reference is aa_truth_render (QAGP with
 * breakpoints, harness/truth/truth.c), which shares nothing with the method but
 * the scene. */
static void test_crow_reference(void **state)
{
    (void)state;
    aa_scene *s = pattern("crow");
    int sizes[3][2] = {{256, 256}, {7, 3}, {255, 129}};
    for (int k = 0; k < 3; k++)
        check_reference("crow", s, sizes[k][0], sizes[k][1], 0, 0, 0, 1e-9);
    aa_scene_free(s);
}

/* The same pixels against tests/oracle.c, a closed form derived from
 * patterns/README.md alone (long double; it agrees with the reference to 1e-12). */
static void test_crow_oracle(void **state)
{
    (void)state;
    aa_scene *s = pattern("crow");
    oracle_crow p = oracle_crow_defaults();
    int sizes[3][2] = {{256, 256}, {7, 3}, {255, 129}};
    for (int k = 0; k < 3; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        aa_image img;
        aa_counters c;
        render("area", s, w, h, 1, &img, &c);
        double worst = 0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double want = oracle_crow_box(&p, w, h, i, j), *px = aa_pixel(&img, i, j);
                double d = fabs(px[0] - want);
                worst = fmax(worst, d);
                if (d > 1e-9 || px[1] != px[0] || px[2] != px[0])
                    fail_msg("crow %dx%d pixel (%d, %d): area %.17g, closed form %.17g", w, h, i,
                             j, px[0], want);
            }
        print_message("crow %4dx%-4d max |area - closed form| %.2e\n", w, h, worst);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* Other parameters: fewer, straighter arcs; arcs curving left; arcs that
 * reach outside the unit square, clipped by the background's frame layer
 * (a second, front layer whose edges cross the arcs); and the scene moved
 * by a fraction of a pixel (arcs whose y is no longer exactly linear in the
 * parameter after rounding). */
static void test_crow_other(void **state)
{
    (void)state;
    struct {
        const char *spec;
        int w, h;
        double t, vx, vy;
    } views[] = {
        {"crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", 256, 256, 0, 0, 0},
        {"crow:curves=40,kmax=-0.4,gap0=0.01,gap1=0.02", 101, 77, 0, 0, 0},
        {"crow:curves=10,kmax=0.5,gap0=0.2,gap1=0.05", 64, 48, 0, 0, 0},
        {"crow", 97, 61, 0.37, 0.31, -0.173},
        {"crow:curves=2,kmax=0.3,gap0=0.2", 33, 17, 1.5, -2.25, 0.7},
    };
    for (size_t k = 0; k < sizeof views / sizeof *views; k++) {
        aa_scene *s = pattern(views[k].spec);
        check_reference(views[k].spec, s, views[k].w, views[k].h, views[k].t, views[k].vx,
                        views[k].vy, 1e-9);
        aa_scene_free(s);
    }
}

/* Large coordinates: 4096 px wide (an x coordinate's last bit is 5e-13 px)
 * and 4096 px tall (each arc one piece 4096 rows long).  The design goal is
 * an error near 1e-13 there; the reference's own bound is 1e-12. */
static void test_crow_large(void **state)
{
    (void)state;
    aa_scene *s = pattern("crow");
    double a = check_reference("crow, wide", s, 4096, 96, 0, 0, 0, 1e-12);
    double b = check_reference("crow, tall", s, 96, 4096, 0, 0, 0, 1e-12);
    /* the 1e-13 goal counts on long double's 64-bit mantissa where area.c
     * and truth.c use it; where long double is no wider than double (as
     * under valgrind, which emulates the x87 unit in double) only the
     * reference's own bound holds */
    double goal = aa_long_double_is_extended() ? 1e-13 : 1e-12;
    assert_true(a <= goal && b <= goal);
    aa_scene_free(s);
}

/* ---- polygons ---- */

typedef struct poly {
    int n;
    double x[64], y[64];
} poly;

/* Clip against the half-plane a x + b y <= c (Sutherland-Hodgman). */
static poly clip(const poly *in, double a, double b, double c)
{
    poly out = {0};
    for (int k = 0; k < in->n; k++) {
        int m = (k + 1) % in->n;
        double dk = a * in->x[k] + b * in->y[k] - c, dm = a * in->x[m] + b * in->y[m] - c;
        if (dk <= 0)
            out.x[out.n] = in->x[k], out.y[out.n++] = in->y[k];
        if ((dk < 0 && dm > 0) || (dk > 0 && dm < 0)) {
            double t = dk / (dk - dm);
            out.x[out.n] = in->x[k] + t * (in->x[m] - in->x[k]);
            out.y[out.n++] = in->y[k] + t * (in->y[m] - in->y[k]);
        }
    }
    return out;
}

/* The intersection of p with convex polygon q. */
static poly clip_by(const poly *p, const poly *q)
{
    poly out = *p;
    for (int k = 0; k < q->n; k++) {
        int m = (k + 1) % q->n, o = (k + 2) % q->n;
        double a = q->y[m] - q->y[k], b = q->x[k] - q->x[m];
        double c = a * q->x[k] + b * q->y[k];
        if (a * q->x[o] + b * q->y[o] > c) /* keep the side holding vertex o */
            a = -a, b = -b, c = -c;
        out = clip(&out, a, b, c);
    }
    return out;
}

static double area(const poly *p)
{
    double s = 0;
    for (int k = 0; k < p->n; k++) {
        int m = (k + 1) % p->n;
        s += p->x[k] * p->y[m] - p->x[m] * p->y[k];
    }
    return 0.5 * fabs(s);
}

/* p scaled to pixel units and clipped to pixel (i, j). */
static double area_in_pixel(const poly *p, int w, int h, int i, int j)
{
    poly q = *p;
    for (int k = 0; k < q.n; k++)
        q.x[k] *= w, q.y[k] *= h;
    poly r = clip(&q, -1, 0, -i);
    r = clip(&r, 1, 0, i + 1);
    r = clip(&r, 0, -1, -j);
    r = clip(&r, 0, 1, j + 1);
    return area(&r);
}

static void add_poly(aa_scene *s, const poly *p)
{
    assert_int_equal(aa_scene_move_to(s, p->x[0], p->y[0]), AA_OK);
    for (int k = 1; k < p->n; k++)
        assert_int_equal(aa_scene_line_to(s, p->x[k], p->y[k]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* Catmull 1978, fig. 1: "The correct integration would be 25% green, 25%
 * black, 50% blue and no red": the pixel is (0, 0.25, 0.5).  The red
 * rectangle behind is wholly hidden; its edges and the front layers' meet
 * inside the pixel, so this is the hidden-surface integrater's case.  Also
 * tiled 4 x 4 on 4 x 4 pixels and on 3 x 3 (tiles cut by pixels), where
 * the mean over the image is the same. */
static void test_catmull_pixel(void **state)
{
    (void)state;
    const double rects[3][4] = {{0, 0, 0.5, 0.5}, {0, 0.5, 1, 1}, {0.1, 0.1, 0.45, 0.9}};
    const aa_rgb colours[3] = {{{0, 1, 0}}, {{0, 0, 1}}, {{1, 0, 0}}};
    const char *methods[2] = {"area", "area:integrator=bands"};
    for (int tiles = 1; tiles <= 4; tiles += 3) {
        aa_scene *s = aa_scene_new(black);
        for (int l = 0; l < 3; l++) {
            assert_int_equal(aa_scene_layer(s, colours[l], AA_FILL_NONZERO), AA_OK);
            for (int p = 0; p < tiles; p++)
                for (int q = 0; q < tiles; q++) {
                    const double *r = rects[l];
                    double d = 1.0 / tiles;
                    poly pr = {4,
                               {(p + r[0]) * d, (p + r[2]) * d, (p + r[2]) * d, (p + r[0]) * d},
                               {(q + r[1]) * d, (q + r[1]) * d, (q + r[3]) * d, (q + r[3]) * d}};
                    add_poly(s, &pr);
                }
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        int sizes[2] = {tiles, 3};
        for (int z = 0; z < 2; z++)
            for (int m = 0; m < 2; m++) {
                int n = sizes[z];
                aa_image img;
                aa_counters c;
                render(methods[m], s, n, n, 1, &img, &c);
                /* one tile per pixel: every pixel is Catmull's; otherwise
                 * the image's mean is his pixel's value */
                double mean[3] = {0, 0, 0};
                for (int k = 0; k < n * n; k++) {
                    const double *v = img.v + 3 * k;
                    if (n == tiles && !(fabs(v[0]) < 1e-15 && fabs(v[1] - 0.25) < 1e-15 &&
                                        fabs(v[2] - 0.5) < 1e-15))
                        fail_msg("%s, %d tiles on %dx%d, pixel %d: (%.17g, %.17g, %.17g), not "
                                 "(0, 0.25, 0.5)",
                                 methods[m], tiles, n, n, k, v[0], v[1], v[2]);
                    for (int ch = 0; ch < 3; ch++)
                        mean[ch] += v[ch] / (n * n);
                }
                if (!(fabs(mean[0]) < 1e-15 && fabs(mean[1] - 0.25) < 1e-15 &&
                      fabs(mean[2] - 0.5) < 1e-15))
                    fail_msg("%s, %d tiles on %dx%d: mean (%.17g, %.17g, %.17g), not "
                             "(0, 0.25, 0.5)",
                             methods[m], tiles, n, n, mean[0], mean[1], mean[2]);
                aa_image_free(&img);
            }
        aa_scene_free(s);
    }
}

/* Three convex polygons in three layers, front to back (red, green, blue:
 * one channel each, so each channel measures one layer's visible area), on
 * grey.  By inclusion-exclusion over the pixel:
 *
 *     visible(A) = |A|,  visible(B) = |B| - |A B|,
 *     visible(C) = |C| - |A C| - |B C| + |A B C|,
 *
 * each intersection of convex polygons found with the clipper above; the
 * pixel is grey + sum (colour - grey) visible.  Vertices fall inside pixels
 * and edges of all three layers cross inside pixels. */
static void test_polygon_layers(void **state)
{
    (void)state;
    const poly A = {3, {0.13, 0.81, 0.37}, {0.21, 0.33, 0.92}};
    const poly B = {5, {0.4, 0.95, 0.9, 0.6, 0.35}, {0.05, 0.2, 0.7, 0.85, 0.5}};
    const poly C = {4, {0.05, 0.62, 0.71, 0.12}, {0.55, 0.08, 0.74, 0.97}};
    const poly *polys[3] = {&A, &B, &C};
    const aa_rgb colours[3] = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}};
    const aa_rgb grey = {{0.25, 0.25, 0.25}};
    aa_scene *s = aa_scene_new(grey);
    for (int l = 0; l < 3; l++) {
        assert_int_equal(aa_scene_layer(s, colours[l], l == 1 ? AA_FILL_EVENODD : AA_FILL_NONZERO),
                         AA_OK);
        add_poly(s, polys[l]);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    poly AB = clip_by(&A, &B), AC = clip_by(&A, &C), BC = clip_by(&B, &C), ABC = clip_by(&AB, &C);
    const char *methods[2] = {"area", "area:integrator=bands"};
    int sizes[3][2] = {{23, 17}, {5, 4}, {1, 1}};
    for (int z = 0; z < 3; z++) {
        int w = sizes[z][0], h = sizes[z][1];
        for (int m = 0; m < 2; m++) {
            aa_image img;
            aa_counters c;
            render(methods[m], s, w, h, 2, &img, &c);
            double worst = 0;
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    double vis[3];
                    vis[0] = area_in_pixel(&A, w, h, i, j);
                    vis[1] = area_in_pixel(&B, w, h, i, j) - area_in_pixel(&AB, w, h, i, j);
                    vis[2] = area_in_pixel(&C, w, h, i, j) - area_in_pixel(&AC, w, h, i, j) -
                             area_in_pixel(&BC, w, h, i, j) + area_in_pixel(&ABC, w, h, i, j);
                    for (int ch = 0; ch < 3; ch++) {
                        double want = grey.c[ch];
                        for (int l = 0; l < 3; l++)
                            want += (colours[l].c[ch] - grey.c[ch]) * vis[l];
                        double d = fabs(aa_pixel(&img, i, j)[ch] - want);
                        worst = fmax(worst, d);
                        if (d > 1e-13)
                            fail_msg("%s %dx%d pixel (%d, %d) channel %d: %.17g, clipper %.17g",
                                     methods[m], w, h, i, j, ch, aa_pixel(&img, i, j)[ch], want);
                    }
                }
            print_message("three polygon layers %2dx%-2d %-22s max |area - clipper| %.2e\n", w,
                          h, methods[m], worst);
            aa_image_free(&img);
        }
    }
    aa_scene_free(s);
}

/* Two overlapping convex paths in one layer, white on black.  Drawn the
 * same way round, the overlap has winding number 2: nonzero shows the
 * union |A| + |B| - |A B|, even-odd the symmetric difference
 * |A| + |B| - 2 |A B|.  Drawn opposite ways, the overlap has winding 0 and
 * both rules show the symmetric difference. */
static void test_fill_rules(void **state)
{
    (void)state;
    const poly A = {4, {0.1, 0.7, 0.8, 0.2}, {0.15, 0.1, 0.6, 0.75}};
    const poly B = {3, {0.45, 0.95, 0.3}, {0.3, 0.55, 0.9}};
    poly Brev = B;
    for (int k = 0; k < B.n; k++)
        Brev.x[k] = B.x[B.n - 1 - k], Brev.y[k] = B.y[B.n - 1 - k];
    poly AB = clip_by(&A, &B);
    const int w = 19, h = 13;
    for (int rule = 0; rule < 2; rule++)
        for (int rev = 0; rev < 2; rev++) {
            aa_scene *s = aa_scene_new(black);
            assert_int_equal(aa_scene_layer(s, white, rule ? AA_FILL_EVENODD : AA_FILL_NONZERO),
                             AA_OK);
            add_poly(s, &A);
            add_poly(s, rev ? &Brev : &B);
            assert_int_equal(aa_scene_finish(s), AA_OK);
            const char *methods[2] = {"area", "area:integrator=bands"};
            for (int m = 0; m < 2; m++) {
                aa_image img;
                aa_counters c;
                render(methods[m], s, w, h, 1, &img, &c);
                double worst = 0;
                for (int j = 0; j < h; j++)
                    for (int i = 0; i < w; i++) {
                        double a = area_in_pixel(&A, w, h, i, j), b = area_in_pixel(&B, w, h, i, j);
                        double ab = area_in_pixel(&AB, w, h, i, j);
                        double want = rule || rev ? a + b - 2 * ab : a + b - ab;
                        double d = fabs(aa_pixel(&img, i, j)[0] - want);
                        worst = fmax(worst, d);
                        if (d > 1e-13)
                            fail_msg("%s, %s, %s: pixel (%d, %d) %.17g, clipper %.17g", methods[m],
                                     rule ? "even-odd" : "nonzero",
                                     rev ? "opposite orientations" : "same orientation", i, j,
                                     aa_pixel(&img, i, j)[0], want);
                    }
                aa_image_free(&img);
                assert_true(worst <= 1e-13);
            }
            aa_scene_free(s);
        }
}

/* Many crossings in one pixel: N thin disjoint strips, nearly horizontal,
 * in a back layer, and N nearly vertical ones in a front layer, crossing in
 * N^2 small parallelograms.  The back layer shows |A_k| minus its overlaps
 * with the front strips: visible = sum_k |A_k| - sum_km |A_k B_m|, the
 * strips of a layer being disjoint.  With N = 40 the 1x1 image has 160
 * edges in its pixel (more than Catmull's integrater takes: the bands do
 * it) and 6400 crossings (more than one pass of events holds). */
static void test_many_crossings(void **state)
{
    (void)state;
    enum { N = 40 };
    static poly A[N], B[N];
    for (int k = 0; k < N; k++) {
        double a = 0.05 + 0.9 * k / N, t = 0.011;
        A[k] = (poly){4, {0.02, 0.98, 0.98, 0.02}, {a, a + 0.03, a + 0.03 + t, a + t}};
        B[k] = (poly){4, {a + 0.02, a + 0.02 + t, a + t, a}, {0.01, 0.01, 0.99, 0.99}};
    }
    const aa_rgb red = {{1, 0, 0}}, blue = {{0, 0, 1}};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, blue, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < N; k++)
        add_poly(s, &B[k]);
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_EVENODD), AA_OK);
    for (int k = 0; k < N; k++)
        add_poly(s, &A[k]);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    int sizes[2][2] = {{1, 1}, {3, 2}};
    for (int z = 0; z < 2; z++) {
        int w = sizes[z][0], h = sizes[z][1];
        const char *methods[2] = {"area", "area:integrator=bands"};
        for (int m = 0; m < 2; m++) {
            aa_image img;
            aa_counters c;
            render(methods[m], s, w, h, 1, &img, &c);
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    double red_area = 0, blue_area = 0;
                    for (int k = 0; k < N; k++) {
                        red_area += area_in_pixel(&A[k], w, h, i, j);
                        blue_area += area_in_pixel(&B[k], w, h, i, j);
                        for (int q = 0; q < N; q++) {
                            poly AB = clip_by(&A[k], &B[q]);
                            red_area -= area_in_pixel(&AB, w, h, i, j);
                        }
                    }
                    const double *px = aa_pixel(&img, i, j);
                    if (!(fabs(px[0] - red_area) < 1e-13 && fabs(px[2] - blue_area) < 1e-13 &&
                          px[1] == 0.0))
                        fail_msg("%s %dx%d pixel (%d, %d): (%.17g, %.17g, %.17g), clipper (%.17g, "
                                 "0, %.17g)",
                                 methods[m], w, h, i, j, px[0], px[1], px[2], red_area, blue_area);
                }
            aa_image_free(&img);
        }
    }
    aa_scene_free(s);
}

/* ---- arcs under other layers ---- */

/* The parabolic segment between the chord y = 0.9 and the arc
 * (0.1, 0.9)-(0.5, -0.3)-(0.9, 0.9) (white, behind) has 2/3 of its control
 * triangle's area, 0.32 (Archimedes).  A grey front rectangle covers
 * 0.3 <= x <= 0.6 over the whole height.  With t = (x - 0.1)/0.8 the
 * segment's height is 2.4 t (1 - t), so the part hidden is
 *
 *     0.8 * 2.4 * [t^2/2 - t^3/3] from t = 0.25 to 0.625
 *       = 1.92 * (0.11393229... - 0.02604166...) = 1.92 * 45/512 = 0.16875,
 *
 * and the mean of the image (black background) is, per channel,
 * 1 * (0.32 - 0.16875) + 0.4 * 0.3 (the rectangle's area in the square)
 * = 0.27125.
 * The arc meets the rectangle's sides inside pixels, so this is the band
 * integrator's case (arcs and another layer's edges); every pixel is also
 * checked against the reference. */
static void test_arc_under_layer(void **state)
{
    (void)state;
    const aa_rgb grey = {{0.4, 0.4, 0.4}};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, grey, AA_FILL_NONZERO), AA_OK);
    poly rect = {4, {0.3, 0.6, 0.6, 0.3}, {-0.5, -0.5, 1.5, 1.5}};
    add_poly(s, &rect);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.1, 0.9), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.5, -0.3, 0.9, 0.9), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const double want = (0.32 - 0.16875) + 0.4 * 0.3;
    int sizes[4][2] = {{1, 1}, {3, 2}, {13, 11}, {64, 48}};
    for (int z = 0; z < 4; z++) {
        int w = sizes[z][0], h = sizes[z][1];
        aa_image img;
        aa_counters c;
        render("area", s, w, h, 2, &img, &c);
        double mean = 0;
        for (int k = 0; k < w * h; k++)
            mean += img.v[3 * k];
        mean /= w * h;
        if (!(fabs(mean - want) < 1e-14))
            fail_msg("%dx%d: mean %.17g, closed form %.17g", w, h, mean, want);
        aa_image_free(&img);
        check_reference("parabolic segment under a front layer", s, w, h, 0, 0, 0, 1e-9);
    }
    aa_scene_free(s);
}

/* ---- random scenes ---- */

static double unit(aa_rng *r, double a, double b) { return a + (b - a) * aa_rng_uniform(r); }

/* A random scene: 1-4 layers, each 1-3 closed paths of 2-6 edges (arcs with
 * probability `arcs`), vertices in [-0.2, 1.2]^2, random colours and fill
 * rules, so paths overlap themselves, each other and the image's edges. */
static aa_scene *random_scene(uint64_t seed, double arcs)
{
    aa_rng r;
    aa_rng_seed(&r, 2024, seed, 0);
    aa_scene *s = aa_scene_new((aa_rgb){{unit(&r, 0, 1), unit(&r, 0, 1), unit(&r, 0, 1)}});
    int nl = 1 + (int)(aa_rng_uniform(&r) * 4);
    for (int l = 0; l < nl; l++) {
        aa_rgb c = {{unit(&r, 0, 1), unit(&r, 0, 1), unit(&r, 0, 1)}};
        assert_int_equal(aa_scene_layer(s, c, aa_rng_uniform(&r) < 0.5 ? AA_FILL_NONZERO
                                                                       : AA_FILL_EVENODD),
                         AA_OK);
        int np = 1 + (int)(aa_rng_uniform(&r) * 3);
        for (int q = 0; q < np; q++) {
            assert_int_equal(aa_scene_move_to(s, unit(&r, -0.2, 1.2), unit(&r, -0.2, 1.2)), AA_OK);
            int ne = 2 + (int)(aa_rng_uniform(&r) * 5);
            for (int e = 0; e < ne; e++) {
                double x = unit(&r, -0.2, 1.2), y = unit(&r, -0.2, 1.2);
                if (aa_rng_uniform(&r) < arcs)
                    assert_int_equal(
                        aa_scene_quad_to(s, unit(&r, -0.2, 1.2), unit(&r, -0.2, 1.2), x, y), AA_OK);
                else
                    assert_int_equal(aa_scene_line_to(s, x, y), AA_OK);
            }
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* Polygon scenes against the reference, which is exact for polygons (its
 * breakpoints include every crossing of two lines).  Where the reference's
 * own bound is loose (many pieces in one pixel) the comparison allows it. */
static void test_random_polygons(void **state)
{
    (void)state;
    const int sizes[4][2] = {{1, 1}, {7, 5}, {13, 11}, {31, 23}};
    double worst = 0;
    for (int k = 0; k < 60; k++) {
        aa_scene *s = random_scene((uint64_t)k, 0.0);
        int w = sizes[k % 4][0], h = sizes[k % 4][1];
        double t = (k % 3) * 0.37;
        aa_scene *placed = aa_scene_place(s, w, h, t, 0.31, -0.17);
        aa_filter f;
        aa_filter_default(&f);
        aa_image ref, bound, img;
        assert_int_equal(aa_image_alloc(&ref, w, h, 3), AA_OK);
        assert_int_equal(aa_image_alloc(&bound, w, h, 1), AA_OK);
        assert_int_equal(aa_truth_render(placed, &f, 1, &ref, &bound, NULL), AA_OK);
        const char *methods[2] = {"area", "area:integrator=bands"};
        for (int m = 0; m < 2; m++) {
            aa_counters c;
            assert_int_equal(render_at(methods[m], s, w, h, t, 0.31, -0.17, 1, &img, &c), AA_OK);
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++)
                    for (int ch = 0; ch < 3; ch++) {
                        double d = fabs(aa_pixel(&img, i, j)[ch] - aa_pixel(&ref, i, j)[ch]);
                        double allowed = 1e-12 + *aa_pixel(&bound, i, j);
                        if (!(d <= allowed))
                            fail_msg("scene %d %dx%d %s pixel (%d, %d) channel %d: %.17g, "
                                     "reference %.17g +- %.2e",
                                     k, w, h, methods[m], i, j, ch, aa_pixel(&img, i, j)[ch],
                                     aa_pixel(&ref, i, j)[ch], *aa_pixel(&bound, i, j));
                        if (*aa_pixel(&bound, i, j) <= 1e-12)
                            worst = fmax(worst, d);
                    }
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(placed);
        aa_scene_free(s);
    }
    print_message("60 random polygon scenes: max |area - reference| %.2e where its bound is "
                  "tight\n",
                  worst);
}

/* With arcs, the two pixel integrators against each other: Catmull's takes
 * the clusters of lines, the bands the rest, so each scene mixes both; on
 * polygon-only clusters they are independent derivations. */
static void test_integrators_agree(void **state)
{
    (void)state;
    double worst = 0;
    for (int k = 0; k < 60; k++) {
        aa_scene *s = random_scene((uint64_t)(1000 + k), k % 2 ? 0.3 : 0.0);
        int w = 5 + k % 17, h = 3 + k % 13;
        aa_image a, b;
        aa_counters c;
        render("area:integrator=catmull", s, w, h, 1, &a, &c);
        render("area:integrator=bands", s, w, h, 2, &b, &c);
        double d = max_diff(&a, &b, NULL, NULL);
        if (!(d <= 1e-13))
            fail_msg("scene %d %dx%d: Catmull's integrater and the bands differ by %.3e", k, w,
                     h, d);
        worst = fmax(worst, d);
        aa_image_free(&a);
        aa_image_free(&b);
        aa_scene_free(s);
    }
    print_message("60 random scenes: max |catmull - bands| %.2e\n", worst);
}

/* ---- generic properties with known answers ---- */

/* A grey square [0.31, 0.69]^2 on a 10x10 image: its edges at 3.1 and 6.9
 * px, so the pixels touched are rows 3 and 6, columns 3 to 6 (8) and rows 4
 * and 5, columns 3 and 6 (4): 12 expensive pixels, no samples.  Pixel
 * (3, 3) is 0.9^2 covered; (4, 3) 0.9; the inner 2x2 exactly the colour,
 * every other pixel exactly the background. */
static void test_counters_and_uniform(void **state)
{
    (void)state;
    const aa_rgb fg = {{0.2, 0.6, 0.9}}, bg = {{0.05, 0.1, 0.15}};
    aa_scene *s = aa_scene_new(bg);
    assert_int_equal(aa_scene_layer(s, fg, AA_FILL_NONZERO), AA_OK);
    poly sq = {4, {0.31, 0.69, 0.69, 0.31}, {0.31, 0.31, 0.69, 0.69}};
    add_poly(s, &sq);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const char *methods[2] = {"area", "area:integrator=bands"};
    for (int m = 0; m < 2; m++) {
        aa_image img;
        aa_counters c;
        render(methods[m], s, 10, 10, 2, &img, &c);
        assert_int_equal(c.samples, 0);
        assert_int_equal(c.expensive_pixels, 12);
        for (int j = 0; j < 10; j++)
            for (int i = 0; i < 10; i++) {
                const double *px = aa_pixel(&img, i, j);
                int in = i >= 4 && i <= 5 && j >= 4 && j <= 5;
                int out = i < 3 || i > 6 || j < 3 || j > 6;
                for (int ch = 0; ch < 3; ch++) {
                    if (in)
                        assert_true(px[ch] == fg.c[ch]);
                    if (out)
                        assert_true(px[ch] == bg.c[ch]);
                }
            }
        for (int ch = 0; ch < 3; ch++) {
            assert_true(fabs(aa_pixel(&img, 3, 3)[ch] - (bg.c[ch] + 0.81 * (fg.c[ch] - bg.c[ch]))) <
                        1e-15);
            assert_true(fabs(aa_pixel(&img, 4, 3)[ch] - (bg.c[ch] + 0.9 * (fg.c[ch] - bg.c[ch]))) <
                        1e-15);
        }
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* Any number of threads, the same image and counters, bit for bit (rows
 * are shared out in blocks, so threads start at different rows). */
static void test_threads_identical(void **state)
{
    (void)state;
    aa_scene *scenes[3] = {pattern("crow"), random_scene(7, 0.3), random_scene(8, 0.0)};
    for (int k = 0; k < 3; k++) {
        aa_image a, b;
        aa_counters ca, cb;
        render("area", scenes[k], 255, 129, 1, &a, &ca);
        for (int t = 2; t <= 5; t++) {
            render("area", scenes[k], 255, 129, t, &b, &cb);
            assert_memory_equal(a.v, b.v, sizeof(double) * 255 * 129 * 3);
            assert_true(ca.expensive_pixels == cb.expensive_pixels);
            aa_image_free(&b);
        }
        aa_image_free(&a);
        aa_scene_free(scenes[k]);
    }
}

/* ---- crowded clusters (more than AR_CROWD segs in a row's cluster) ---- */

/* Thousands of arcs 1e-5 apart: each row is one cluster of 2048 segs, none
 * crossing, tested by neighbours at mid-band (all pairs whose extents
 * overlap were 4e9 tests a row at 65536 arcs).  Against the reference
 * (1e-12) and tests/oracle.c's closed form (1e-10: the scene's arcs are
 * placed by sums in double, 1e-16 an arc from the definition, which moves
 * the pattern by up to 1e-11 px at 64 px), 1 and 2 threads identical. */
static void test_crowded_cluster(void **state)
{
    (void)state;
    const char *spec = "crow:curves=2048,gap0=1e-5,gap1=1e-5,kmax=0.05";
    aa_scene *s = pattern(spec);
    oracle_crow p = {2048, 0.05, 1e-5, 1e-5};
    assert_true(oracle_crow_valid(&p));
    int sizes[2][2] = {{64, 64}, {301, 7}};
    for (int z = 0; z < 2; z++) {
        int w = sizes[z][0], h = sizes[z][1];
        aa_image img, one;
        aa_counters c;
        render("area", s, w, h, 2, &img, &c);
        render("area", s, w, h, 1, &one, &c);
        assert_memory_equal(img.v, one.v, sizeof(double) * (size_t)w * (size_t)h * 3);
        check_reference(spec, s, w, h, 0, 0, 0, 1e-12);
        double worst = 0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double want = oracle_crow_box(&p, w, h, i, j), d = fabs(aa_pixel(&img, i, j)[0] - want);
                worst = fmax(worst, d);
                if (!(d <= 1e-10))
                    fail_msg("%s %dx%d pixel (%d, %d): area %.17g, closed form %.17g", spec, w, h, i,
                             j, aa_pixel(&img, i, j)[0], want);
            }
        print_message("%s %4dx%-4d max |area - closed form| %.2e\n", spec, w, h, worst);
        aa_image_free(&img);
        aa_image_free(&one);
    }
    aa_scene_free(s);
}

/* A crowd that does cross: 60 thin nearly vertical quadrilaterals from the
 * top to the bottom of the image, their feet in the reverse order of their
 * heads, so that in the middle rows clusters of 120 segs cross without any
 * vertex in the band (the neighbours' test must say so, or the one-order
 * sweep would be wrong by whole pixels); against the reference.  (It also
 * holds the reference to account: its sum over spans, with no breakpoints
 * where more than 48 pieces cross, was 1.7e-8 off here with a bound of
 * 1e-14; such windows now go one piece at a time,
 * harness/truth/truth_internal.h, TRUTH_CROWD.) */
static void test_crowded_crossings(void **state)
{
    (void)state;
    enum { N = 60 };
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < N; k++) {
        double a = 0.3 + 0.4 * k / N, b = 0.68 - 0.37 * k / N + 0.01 * sin(k), t = 0.002;
        poly q = {4, {a, a + t, b + t, b}, {0.02, 0.02, 0.98, 0.98}};
        add_poly(s, &q);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_reference("60 crossing thin quadrilaterals", s, 64, 64, 0, 0, 0, 1e-11);
    check_reference("60 crossing thin quadrilaterals", s, 37, 101, 0, 0, 0, 1e-11);
    aa_scene_free(s);
}

/* Only the box is integrated; other filters are refused, saying so. */
static void test_filters_refused(void **state)
{
    (void)state;
    const char *filters[] = {"tent", "tent:r=0.5", "gauss", "gauss:s=1", "cone"};
    for (int k = 0; k < 5; k++) {
        aa_filter f;
        aa_spec spec;
        assert_int_equal(aa_filter_parse(filters[k], &f), AA_OK);
        assert_int_equal(aa_method_parse("area", &f, &spec), AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "box"));
    }
    aa_filter box;
    aa_spec spec;
    aa_filter_default(&box);
    assert_int_equal(aa_method_parse("area:integrator=bands", &box, &spec), AA_OK);
    assert_int_equal(aa_method_parse("area:integrator=exact", &box, &spec), AA_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crow_reference),     cmocka_unit_test(test_crow_oracle),
        cmocka_unit_test(test_crow_other),         cmocka_unit_test(test_crow_large),
        cmocka_unit_test(test_catmull_pixel),      cmocka_unit_test(test_polygon_layers),
        cmocka_unit_test(test_fill_rules),         cmocka_unit_test(test_many_crossings),
        cmocka_unit_test(test_arc_under_layer),
        cmocka_unit_test(test_random_polygons),    cmocka_unit_test(test_integrators_agree),
        cmocka_unit_test(test_counters_and_uniform), cmocka_unit_test(test_threads_identical),
        cmocka_unit_test(test_filters_refused),
        cmocka_unit_test(test_crowded_cluster),    cmocka_unit_test(test_crowded_crossings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
