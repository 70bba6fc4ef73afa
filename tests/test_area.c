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
 *    from tests/oracle.c's polygon clipper (Sutherland-Hodgman and the
 *    shoelace formula), with inclusion-exclusion
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
 *    120 crossing segs in one cluster against the reference; bands with
 *    thousands of crossings (strips against the clipper, 60 crossing strokes
 *    against the reference at 16x16 summed over blocks), their heights in
 *    one pass (the room grown) and in passes of CM_MAX_EVENTS.
 *  - a seg's parts in the sub-bands of a band joined while its colour jump
 *    stays the same (sweep_part), three layers in one pixel against the
 *    clipper.
 *  - the sort of a row's new pieces' keys (area_sort_new_keys) against
 *    qsort with the rows' comparison, written here.
 *  - sub-bands of a band holding one seg or none (ordered without their
 *    ends' roots) and sub-bands whose first two segs have the same ends
 *    (ordered at the middle) against the reference.
 *  - pieces entering rows out of the order by x, and a scene whose pieces
 *    begin far below (the order by (y0, id)), against the reference
 *    (sort_pieces' order by rows, merge_keys' insertion).
 */
#include "area_internal.h"
#include "bench.h"
#include "oracle.h"
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

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* The two pixel integrators: Catmull's (for clusters of lines) with the
 * bands for the rest, and the bands alone. */
static const char *const methods[2] = {"area", "area:integrator=bands"};

/* `method` or the box reference on a pattern-unit scene at w x h (time t,
 * motion vx, vy). */
static support_view view_at(int w, int h, double t, double vx, double vy, int threads)
{
    return (support_view){.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .seed = 1,
                          .threads = threads};
}

static void render(const char *method, const aa_scene *scene, int w, int h, int threads,
                   aa_image *out, aa_counters *c)
{
    support_render(method, scene, NULL, w, h, threads, out, c);
}

/* Both integrators against the reference on a view; returns the worst. */
static double check_reference(const char *what, const aa_scene *scene, int w, int h, double t,
                              double vx, double vy, double tol)
{
    aa_image ref, img;
    aa_counters c;
    const support_view mv = view_at(w, h, t, vx, vy, 2), rv = view_at(w, h, t, vx, vy, 0);
    support_reference(scene, &rv, &ref, NULL, NULL);
    double worst = 0;
    for (int m = 0; m < 2; m++) {
        support_render_must(methods[m], scene, &mv, &img, &c);
        int wi = 0, wj = 0;
        double d = support_max_diff(&img, &ref, &wi, &wj);
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

/* ---- the rows' sorts ---- */

static uint64_t order_rng(uint64_t *s)
{
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return *s;
}

/* The order the rows sort their keys in (area.c, key_after): key rising,
 * ties by id. */
static int cmp_row_key(const void *a, const void *b)
{
    const ar_key *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->id < q->id ? -1 : (p->id > q->id);
}

/* area_sort_new_keys (the runs of insertion sort merged in pairs) against
 * qsort with that comparison: every size from 0 to 300 and 5000, keys few
 * (many ties, broken by id) or many, sorted, reversed or shuffled. */
static void test_sort_new_keys(void **state)
{
    (void)state;
    enum { N = 5000 };
    ar_key *k = malloc(N * sizeof *k), *want = malloc(N * sizeof *want);
    ar_key *tmp = malloc(N * sizeof *tmp);
    uint64_t rs = 0x9e3779b97f4a7c15ull;
    assert_non_null(k), assert_non_null(want), assert_non_null(tmp);
    for (size_t n = 0; n <= N; n = n < 300 ? n + 1 : N) {
        for (int kind = 0; kind < 4; kind++) {
            for (size_t a = 0; a < n; a++) {
                uint64_t r = order_rng(&rs);
                double key = kind == 0 ? (double)(r % 7) - 1.0 : (double)(r >> 11) * 0x1p-40;
                if (kind == 2)
                    key = (double)a; /* sorted */
                if (kind == 3)
                    key = (double)(n - a); /* reversed */
                /* ids distinct (an odd factor), in no order */
                k[a] = (ar_key){key, (uint32_t)a * 2654435761u, (uint32_t)a};
            }
            memcpy(want, k, n * sizeof *k);
            if (n)
                qsort(want, n, sizeof *want, cmp_row_key);
            area_sort_new_keys(k, n, tmp);
            for (size_t a = 0; a < n; a++)
                if (k[a].key != want[a].key || k[a].id != want[a].id || k[a].idx != want[a].idx)
                    fail_msg("%zu keys of kind %d: place %zu holds (%g, %u), qsort's (%g, %u)",
                             n, kind, a, k[a].key, k[a].id, want[a].key, want[a].id);
        }
        if (n == N)
            break;
    }
    free(k), free(want), free(tmp);
}

/* ---- crow ---- */

/* The acceptance bar: the box reference within 1e-9 on crow 256x256,
 * 7x3 and 255x129.  The reference is aa_truth_render (QAGP with
 * breakpoints, harness/truth/truth.c), which shares nothing with the method but
 * the scene. */
static void test_crow_reference(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
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
    aa_scene *s = scenes_pattern("crow");
    oracle_crow p = oracle_crow_defaults();
    int sizes[3][2] = {{256, 256}, {7, 3}, {255, 129}};
    for (int k = 0; k < 3; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        aa_image img;
        render("area", s, w, h, 1, &img, NULL);
        double worst = support_check_crow_box("crow: area", &p, &img, 1e-9);
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
        aa_scene *s = scenes_pattern(views[k].spec);
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
    aa_scene *s = scenes_pattern("crow");
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

/* p scaled to pixel units and clipped to pixel (i, j) (tests/oracle.c). */
static double area_in_pixel(const oracle_poly *p, int w, int h, int i, int j)
{
    oracle_poly q = oracle_poly_scaled(p, w, h);
    return oracle_poly_area_in_rect(&q, i, j, i + 1, j + 1);
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
    for (int tiles = 1; tiles <= 4; tiles += 3) {
        aa_scene *s = aa_scene_new(black);
        for (int l = 0; l < 3; l++) {
            assert_int_equal(aa_scene_layer(s, colours[l], AA_FILL_NONZERO), AA_OK);
            for (int p = 0; p < tiles; p++)
                for (int q = 0; q < tiles; q++) {
                    const double *r = rects[l];
                    double d = 1.0 / tiles;
                    oracle_poly pr = {4,
                               {(p + r[0]) * d, (p + r[2]) * d, (p + r[2]) * d, (p + r[0]) * d},
                               {(q + r[1]) * d, (q + r[1]) * d, (q + r[3]) * d, (q + r[3]) * d}};
                    scenes_add_poly(s, &pr);
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

/* What a pixel should be: the three channels of pixel (i, j) of a w x h
 * image, from the clipper. */
typedef void clipper_fn(const void *ctx, int w, int h, int i, int j, double want[3]);

/* Both integrators at w x h against the clipper, every pixel and channel:
 * each off by less than tol[ch], or exactly right where tol[ch] is 0.
 * Prints and returns the largest difference. */
static double against_clipper(const char *what, const aa_scene *s, int w, int h, int threads,
                              clipper_fn *want, const void *ctx, const double tol[3])
{
    double worst = 0;
    for (int m = 0; m < 2; m++) {
        aa_image img;
        render(methods[m], s, w, h, threads, &img, NULL);
        double worst_m = 0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double v[3];
                want(ctx, w, h, i, j, v);
                for (int ch = 0; ch < 3; ch++) {
                    double got = aa_pixel(&img, i, j)[ch], d = fabs(got - v[ch]);
                    worst_m = fmax(worst_m, d);
                    if (!(d < tol[ch] || d == 0.0))
                        fail_msg("%s %dx%d %s pixel (%d, %d) channel %d: %.17g, clipper %.17g",
                                 what, w, h, methods[m], i, j, ch, got, v[ch]);
                }
            }
        print_message("%-46s %2dx%-2d %-22s max |area - clipper| %.2e\n", what, w, h,
                      methods[m], worst_m);
        aa_image_free(&img);
        worst = fmax(worst, worst_m);
    }
    return worst;
}

/* Three convex polygons in three layers, front to back (red, green, blue:
 * one channel each, so each channel measures one layer's visible area), on
 * grey.  By inclusion-exclusion over the pixel:
 *
 *     visible(A) = |A|,  visible(B) = |B| - |A B|,
 *     visible(C) = |C| - |A C| - |B C| + |A B C|,
 *
 * each intersection of convex polygons found with tests/oracle.c's clipper;
 * the pixel is grey + sum (colour - grey) visible.  Vertices fall inside
 * pixels and edges of all three layers cross inside pixels. */
typedef struct layers {
    oracle_poly A, B, C, AB, AC, BC, ABC;
    aa_rgb colours[3], grey;
} layers;

static void layers_want(const void *ctx, int w, int h, int i, int j, double want[3])
{
    const layers *L = ctx;
    double vis[3];
    vis[0] = area_in_pixel(&L->A, w, h, i, j);
    vis[1] = area_in_pixel(&L->B, w, h, i, j) - area_in_pixel(&L->AB, w, h, i, j);
    vis[2] = area_in_pixel(&L->C, w, h, i, j) - area_in_pixel(&L->AC, w, h, i, j) -
             area_in_pixel(&L->BC, w, h, i, j) + area_in_pixel(&L->ABC, w, h, i, j);
    for (int ch = 0; ch < 3; ch++) {
        want[ch] = L->grey.c[ch];
        for (int l = 0; l < 3; l++)
            want[ch] += (L->colours[l].c[ch] - L->grey.c[ch]) * vis[l];
    }
}

/* The scene of layers A (nonzero), B (even-odd) and C (nonzero) over the
 * grey, with their intersections for the oracle (layers_want). */
static aa_scene *layers_scene(layers *L)
{
    L->AB = oracle_poly_intersect(&L->A, &L->B), L->AC = oracle_poly_intersect(&L->A, &L->C);
    L->BC = oracle_poly_intersect(&L->B, &L->C), L->ABC = oracle_poly_intersect(&L->AB, &L->C);
    const oracle_poly *polys[3] = {&L->A, &L->B, &L->C};
    aa_scene *s = aa_scene_new(L->grey);
    for (int l = 0; l < 3; l++) {
        assert_int_equal(aa_scene_layer(s, L->colours[l],
                                        l == 1 ? AA_FILL_EVENODD : AA_FILL_NONZERO),
                         AA_OK);
        scenes_add_poly(s, polys[l]);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_polygon_layers(void **state)
{
    (void)state;
    layers L = {.A = {3, {0.13, 0.81, 0.37}, {0.21, 0.33, 0.92}},
                .B = {5, {0.4, 0.95, 0.9, 0.6, 0.35}, {0.05, 0.2, 0.7, 0.85, 0.5}},
                .C = {4, {0.05, 0.62, 0.71, 0.12}, {0.55, 0.08, 0.74, 0.97}},
                .colours = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}},
                .grey = {{0.25, 0.25, 0.25}}};
    aa_scene *s = layers_scene(&L);
    const double tol[3] = {1e-13, 1e-13, 1e-13};
    int sizes[3][2] = {{23, 17}, {5, 4}, {1, 1}};
    for (int z = 0; z < 3; z++)
        against_clipper("three polygon layers", s, sizes[z][0], sizes[z][1], 2, layers_want, &L,
                        tol);
    aa_scene_free(s);
}

/* The sub-bands' sweep keeps a seg's part while its colour jump stays the
 * same from one sub-band to the next, and adds it once (area.c,
 * sweep_part): three layers as above in one pixel, so the band is cut at
 * every vertex and crossing.  Back, C's long left edge crosses the whole
 * band, its jump the same above and below B's vertices and crossings (its
 * parts joined across them), hidden in the middle heights by the front
 * triangle A, whose vertex pokes over it (a jump of 0 there: its parts
 * above and below apart); B (even-odd) crosses both.  Against the
 * clipper, at 1x1 and 4x3. */
static void test_sweep_parts(void **state)
{
    (void)state;
    layers L = {.A = {3, {0.05, 0.55, 0.05}, {0.35, 0.5, 0.65}},
                .B = {3, {0.2, 0.7, 0.25}, {0.1, 0.25, 0.85}},
                .C = {4, {0.3, 0.95, 0.9, 0.45}, {0.02, 0.05, 0.95, 0.98}},
                .colours = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}},
                .grey = {{0.25, 0.25, 0.25}}};
    aa_scene *s = layers_scene(&L);
    const double tol[3] = {1e-13, 1e-13, 1e-13};
    against_clipper("sub-bands' parts joined", s, 1, 1, 1, layers_want, &L, tol);
    against_clipper("sub-bands' parts joined", s, 4, 3, 2, layers_want, &L, tol);
    aa_scene_free(s);
}

/* Two overlapping convex paths in one layer, white on black.  Drawn the
 * same way round, the overlap has winding number 2: nonzero shows the
 * union |A| + |B| - |A B|, even-odd the symmetric difference
 * |A| + |B| - 2 |A B|.  Drawn opposite ways, the overlap has winding 0 and
 * both rules show the symmetric difference. */
typedef struct two_paths {
    oracle_poly A, B, AB;
    int difference; /* 1: the symmetric difference, 0: the union */
} two_paths;

static void two_paths_want(const void *ctx, int w, int h, int i, int j, double want[3])
{
    const two_paths *T = ctx;
    double a = area_in_pixel(&T->A, w, h, i, j), b = area_in_pixel(&T->B, w, h, i, j);
    double ab = area_in_pixel(&T->AB, w, h, i, j);
    want[0] = want[1] = want[2] = T->difference ? a + b - 2 * ab : a + b - ab;
}

static void test_fill_rules(void **state)
{
    (void)state;
    two_paths T = {.A = {4, {0.1, 0.7, 0.8, 0.2}, {0.15, 0.1, 0.6, 0.75}},
                   .B = {3, {0.45, 0.95, 0.3}, {0.3, 0.55, 0.9}}};
    oracle_poly Brev = T.B;
    for (int k = 0; k < T.B.n; k++)
        Brev.x[k] = T.B.x[T.B.n - 1 - k], Brev.y[k] = T.B.y[T.B.n - 1 - k];
    T.AB = oracle_poly_intersect(&T.A, &T.B);
    const double tol[3] = {1e-13, 1e-13, 1e-13};
    for (int rule = 0; rule < 2; rule++)
        for (int rev = 0; rev < 2; rev++) {
            aa_scene *s = aa_scene_new(black);
            assert_int_equal(aa_scene_layer(s, white, rule ? AA_FILL_EVENODD : AA_FILL_NONZERO),
                             AA_OK);
            scenes_add_poly(s, &T.A);
            scenes_add_poly(s, rev ? &Brev : &T.B);
            assert_int_equal(aa_scene_finish(s), AA_OK);
            T.difference = rule || rev;
            char what[64];
            snprintf(what, sizeof what, "%s, %s", rule ? "even-odd" : "nonzero",
                     rev ? "opposite orientations" : "same orientation");
            assert_true(against_clipper(what, s, 19, 13, 1, two_paths_want, &T, tol) <= 1e-13);
            aa_scene_free(s);
        }
}

/* Many crossings in one pixel: N thin disjoint strips, nearly horizontal,
 * in a back layer, and N nearly vertical ones in a front layer, crossing in
 * N^2 small parallelograms.  The back layer shows |A_k| minus its overlaps
 * with the front strips: visible = sum_k |A_k| - sum_km |A_k B_m|, the
 * strips of a layer being disjoint.  With N = 40 the 1x1 image has 160
 * edges in its pixel (more than Catmull's integrater takes: the bands do
 * it) and 6400 crossings (more than one pass of events holds).  Red is the
 * back layer, blue the front; green is exactly 0. */
enum { STRIPS = 40 };

typedef struct strips {
    oracle_poly A[STRIPS], B[STRIPS];
} strips;

static void strips_want(const void *ctx, int w, int h, int i, int j, double want[3])
{
    const strips *S = ctx;
    double red_area = 0, blue_area = 0;
    for (int k = 0; k < STRIPS; k++) {
        red_area += area_in_pixel(&S->A[k], w, h, i, j);
        blue_area += area_in_pixel(&S->B[k], w, h, i, j);
        for (int q = 0; q < STRIPS; q++) {
            oracle_poly AB = oracle_poly_intersect(&S->A[k], &S->B[q]);
            red_area -= area_in_pixel(&AB, w, h, i, j);
        }
    }
    want[0] = red_area, want[1] = 0.0, want[2] = blue_area;
}

/* The strips' scene, S filled in: blue's strips B (non-zero) behind red's
 * strips A (even-odd), on black. */
static aa_scene *strips_scene(strips *S)
{
    for (int k = 0; k < STRIPS; k++) {
        double a = 0.05 + 0.9 * k / STRIPS, t = 0.011;
        S->A[k] = (oracle_poly){4, {0.02, 0.98, 0.98, 0.02}, {a, a + 0.03, a + 0.03 + t, a + t}};
        S->B[k] = (oracle_poly){4, {a + 0.02, a + 0.02 + t, a + t, a}, {0.01, 0.01, 0.99, 0.99}};
    }
    const aa_rgb red = {{1, 0, 0}}, blue = {{0, 0, 1}};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, blue, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < STRIPS; k++)
        scenes_add_poly(s, &S->B[k]);
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_EVENODD), AA_OK);
    for (int k = 0; k < STRIPS; k++)
        scenes_add_poly(s, &S->A[k]);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_many_crossings(void **state)
{
    (void)state;
    static strips S;
    aa_scene *s = strips_scene(&S);
    const double tol[3] = {1e-13, 0.0, 1e-13};
    int sizes[2][2] = {{1, 1}, {3, 2}};
    for (int z = 0; z < 2; z++)
        against_clipper("strips crossing", s, sizes[z][0], sizes[z][1], 1, strips_want, &S, tol);
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
    oracle_poly rect = {4, {0.3, 0.6, 0.6, 0.3}, {-0.5, -0.5, 1.5, 1.5}};
    scenes_add_poly(s, &rect);
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
        double mean = support_channel_mean(&img, 0);
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
        const support_view v = view_at(w, h, t, 0.31, -0.17, 1);
        aa_image ref, bound, img;
        support_reference(s, &v, &ref, &bound, NULL);
            for (int m = 0; m < 2; m++) {
            aa_counters c;
            support_render_must(methods[m], s, &v, &img, &c);
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
        double d = support_max_diff(&a, &b, NULL, NULL);
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
    oracle_poly sq = {4, {0.31, 0.69, 0.69, 0.31}, {0.31, 0.31, 0.69, 0.69}};
    scenes_add_poly(s, &sq);
    assert_int_equal(aa_scene_finish(s), AA_OK);
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
    aa_scene *scenes[3] = {scenes_pattern("crow"), random_scene(7, 0.3), random_scene(8, 0.0)};
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
    aa_scene *s = scenes_pattern(spec);
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
        oracle_poly q = {4, {a, a + t, b + t, b}, {0.02, 0.02, 0.98, 0.98}};
        scenes_add_poly(s, &q);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_reference("60 crossing thin quadrilaterals", s, 64, 64, 0, 0, 0, 1e-11);
    check_reference("60 crossing thin quadrilaterals", s, 37, 101, 0, 0, 0, 1e-11);
    aa_scene_free(s);
}

/* 60 thin crossing hexagons in three layers (two nonzero, one even-odd)
 * against the reference within 1e-11: a crowded band's sub-bands are
 * ordered from the one above (area.c, order_next) and the sweep walks
 * only from their first change to their last, the windings at the first
 * summed over every layer from the cluster's left.  Each hexagon has a
 * vertex halfway down its sides at a height it shares with its neighbour
 * in x, in another layer, so that a sub-band's top changes segs of two
 * layers at once. */
static void test_crowded_layers(void **state)
{
    (void)state;
    enum { N = 60 };
    const aa_rgb col[3] = {{{1, 0, 0}}, {{0, 0.5, 1}}, {{0.25, 1, 0.5}}};
    const aa_fill_rule rule[3] = {AA_FILL_NONZERO, AA_FILL_EVENODD, AA_FILL_NONZERO};
    aa_scene *s = aa_scene_new(black);
    for (int l = 0; l < 3; l++) {
        assert_int_equal(aa_scene_layer(s, col[l], rule[l]), AA_OK);
        for (int k = l; k < N; k += 3) {
            double a = 0.3 + 0.4 * k / N, b = 0.68 - 0.37 * k / N + 0.01 * sin(k), t = 0.002;
            double ym = 0.25 + 0.5 * (k / 2) / (N / 2.0), xm = a + (b - a) * (ym - 0.02) / 0.96;
            xm += 0.004 * cos(k);
            oracle_poly q = {6,
                             {a, a + t, xm + t, b + t, b, xm},
                             {0.02, 0.02, ym, 0.98, 0.98, ym}};
            scenes_add_poly(s, &q);
        }
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_reference("60 crossing thin hexagons, 3 layers", s, 64, 64, 0, 0, 0, 1e-11);
    check_reference("60 crossing thin hexagons, 3 layers", s, 37, 101, 0, 0, 0, 1e-11);
    aa_scene_free(s);
}

/* The largest |img - the mean of fine's F/n x F/n block| over img's n x n
 * pixels (n dividing F: the box's pixel is the mean of the finer pixels
 * it covers), channel 0; a pixel off by more than 1e-13 fails, named by
 * `what`. */
static double off_blocks(const char *what, const aa_image *img, const aa_image *fine, int F)
{
    int n = img->w, b = F / n;
    double worst = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double want = 0;
            for (int fj = j * b; fj < (j + 1) * b; fj++)
                for (int fi = i * b; fi < (i + 1) * b; fi++)
                    want += aa_pixel(fine, fi, fj)[0];
            want /= (double)b * b;
            double d = fabs(aa_pixel(img, i, j)[0] - want);
            worst = fmax(worst, d);
            if (!(d <= 1e-13))
                fail_msg("60 crossing strokes %dx%d %s pixel (%d, %d): %.17g, the reference "
                         "at %dx%d summed %.17g (%.3e off)",
                         n, n, what, i, j, aa_pixel(img, i, j)[0], F, F, want, d);
        }
    return worst;
}

/* Crowded bands with more crossings than band_events' first room
 * (CM_MAX_EVENTS, 2048): the room grows to hold them (as built), or, with
 * aa__area_events_grown at CM_MAX_EVENTS, they are taken a pass per 1024
 * beyond the first.  A crossing missed moves a sub-band's order, by up to
 * a whole seg's width.  The strips of test_many_crossings at 1x1 (40 by
 * 40, four crossings a pair: 6,400 in one band) against the clipper, and
 * 30 stroked cubics across the square by 30 down it, 0.02 wide (each pair
 * of strokes crossing in four points of their outlines or more, 3,600 and
 * more in a band, offset pieces) at 1x1 and 2x2 against the reference. */
static void test_crowded_passes(void **state)
{
    (void)state;
    enum { N = 30 };
    static strips S;
    aa_scene *s = strips_scene(&S);
    const double tol[3] = {1e-13, 0.0, 1e-13};
    aa_path p = {0};
    for (int k = 0; k < N; k++) {
        double c = 0.04 + 0.92 * (k + 0.5) / N, a = 0.03 * sin(1.3 * k);
        assert_int_equal(aa_path_move_to(&p, 0.01, c), AA_OK);
        assert_int_equal(aa_path_cubic_to(&p, 0.34, c + a, 0.67, c - a, 0.99, c + 0.5 * a), AA_OK);
        assert_int_equal(aa_path_move_to(&p, c, 0.01), AA_OK);
        assert_int_equal(aa_path_cubic_to(&p, c - a, 0.34, c + a, 0.67, c - 0.5 * a, 0.99), AA_OK);
    }
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.02;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    size_t noff = 0;
    aa_scene *c = scenes_stroke_outline(&p, &st, NULL, &noff);
    aa_path_free(&p);
    assert_true(noff > 0);
    /* the reference at 16x16 summed over blocks: the box's pixel at 1x1,
     * 2x2 and 4x4 is the mean of its 16x16 pixels.  The reference itself at
     * those sizes, its windows crowded, must agree: it was off by up to
     * 2.5e-2 (truth_crowd.c, cmp_after: a pair just swapped at a meeting
     * swapped back by x at the meeting's height, on a nearly horizontal
     * piece) */
    enum { F = 16 };
    aa_image fine;
    const support_view fv = view_at(F, F, 0, 0, 0, 0);
    support_reference(c, &fv, &fine, NULL, NULL);
    for (int n = 1; n <= 4; n *= 2) {
        aa_image ref;
        const support_view rv = view_at(n, n, 0, 0, 0, 0);
        support_reference(c, &rv, &ref, NULL, NULL);
        double worst = off_blocks("the reference", &ref, &fine, F);
        print_message("%-32s %dx%d max |reference - reference %dx%d summed| %.2e\n",
                      "60 crossing strokes", n, n, F, F, worst);
        aa_image_free(&ref);
    }
    size_t rooms[2] = {CM_MAX_EVENTS_GROWN, CM_MAX_EVENTS};
    for (int z = 0; z < 2; z++) {
        aa__area_events_grown = rooms[z];
        print_message("room for %zu heights a pass:\n", rooms[z]);
        against_clipper("strips crossing", s, 1, 1, 1, strips_want, &S, tol);
        for (int n = 1; n <= 4; n *= 2)
            for (int m = 0; m < 2; m++) {
                aa_image img;
                aa_counters cnt;
                const support_view mv = view_at(n, n, 0, 0, 0, 1);
                support_render_must(methods[m], c, &mv, &img, &cnt);
                double worst = off_blocks(methods[m], &img, &fine, F);
                print_message("%-32s %dx%d %-22s max |area - reference %dx%d summed| %.2e\n",
                              "60 crossing strokes", n, n, methods[m], F, F, worst);
                aa_image_free(&img);
            }
    }
    aa_image_free(&fine);
    aa__area_events_grown = CM_MAX_EVENTS_GROWN;
    aa_scene_free(s);
    aa_scene_free(c);
}

/* Only the box is integrated; other filters are refused, saying so. */
static void test_filters_refused(void **state)
{
    (void)state;
    const char *filters[] = {"tent", "tent:r=0.5", "gauss", "gauss:s=1", "cone"};
    for (int k = 0; k < 5; k++) {
        assert_int_equal(support_parse_method("area", filters[k], NULL), AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "box"));
    }
    assert_int_equal(support_parse_method("area:integrator=bands", NULL, NULL), AA_OK);
    assert_int_equal(support_parse_method("area:integrator=exact", NULL, NULL), AA_EINVAL);
}

/* A crowded band's sub-bands that the ends do not order (area.c,
 * cluster_bands, order_ends): at 64 x 64, twelve lenses (two quadratics
 * from one point to another, bulging either way) each from 0.3 to 0.8 of
 * a row's height down to its bottom, with a thin rectangle right of it in
 * the same pixel over three rows, so that the sub-band between holds four
 * segs, the first two of which, in order, have the same ends (the order
 * then taken at the middle, every seg's index mapped back from order_ends'
 * places), and those above and below the rectangle's two alone; and a
 * zigzag whose vertices lie inside the rows, at 0.2 and 0.7 of them, each
 * band's sub-bands holding one seg (ordered without order_ends' roots).
 * Against the reference (both integrators: the bands' takes cluster_bands
 * for the lines too), within 1e-12. */
static void test_sub_band_orders(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < 12; k++) {
        double x = (4.15 + 5 * k + 0.05 * sin(k)) / 64, y0 = (2 + 5 * k + 0.3) / 64,
               y1 = (2 + 5 * k + 0.8) / 64, b = (0.5 + 0.02 * k) / 64;
        assert_int_equal(aa_scene_move_to(s, x, y0), AA_OK);
        assert_int_equal(aa_scene_quad_to(s, x + b, 0.5 * (y0 + y1), x, y1), AA_OK);
        assert_int_equal(aa_scene_quad_to(s, x - 0.7 * b, 0.5 * (y0 + y1), x, y0), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        oracle_poly q = {4,
                         {x + 0.45 / 64, x + 0.55 / 64, x + 0.56 / 64, x + 0.46 / 64},
                         {y0 - 1.0 / 64, y0 - 1.0 / 64, y1 + 1.0 / 64, y1 + 1.0 / 64}};
        scenes_add_poly(s, &q);
    }
    /* the zigzag: its left side's vertices at 0.2 and 0.7 of rows 2 to
     * 61, its right side straight, 9 px to the right */
    assert_int_equal(aa_scene_move_to(s, 40.0 / 64, 2.2 / 64), AA_OK);
    for (int r = 2; r < 62; r++) {
        double x = (40 + 0.8 * sin(0.9 * r)) / 64;
        assert_int_equal(aa_scene_line_to(s, x, (r + 0.2) / 64), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x + 0.45 / 64, (r + 0.7) / 64), AA_OK);
    }
    assert_int_equal(aa_scene_line_to(s, 49.0 / 64, 61.7 / 64), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 49.0 / 64, 2.2 / 64), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_reference("lenses and a zigzag inside rows", s, 64, 64, 0, 0, 0, 1e-12);
    aa_scene_free(s);
}

/* The pieces' order by the row they enter in, then by x (area.c,
 * sort_pieces), against the reference on 64 x 64 px (both integrators,
 * two threads: rows taken out of turn start the active list again).  Six
 * parallelograms 1 px wide enter row 5 left to right, each running down
 * and left at 45 degrees, the longer the further right, so that their
 * least x (the order they are put in) is the reverse of their cells' in
 * the row they enter (merge_keys' insertion runs past its budget); twelve
 * triangles, added right to left, enter rows 0 (from above the image) and
 * 1, 29 and 30 (exactly on its line), each left of one entering the row
 * before, and 33; a disc of cubics makes the scene's rows take the curved
 * pieces' path.  With `far`, a rectangle reaching 300 px down (its bottom
 * edge begins in a row more than twice the pieces) sends the order to the
 * one by (y0, id). */
static void test_piece_rows(void **state)
{
    (void)state;
    for (int far = 0; far < 2; far++) {
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        for (int k = 0; k < 6; k++) {
            double x = 10.0 + 3 * k, h = 4.0 * k + 2, y = 5.3;
            assert_int_equal(aa_scene_move_to(s, x / 64, y / 64), AA_OK);
            assert_int_equal(aa_scene_line_to(s, (x + 1) / 64, y / 64), AA_OK);
            assert_int_equal(aa_scene_line_to(s, (x + 1 - h) / 64, (y + h) / 64), AA_OK);
            assert_int_equal(aa_scene_line_to(s, (x - h) / 64, (y + h) / 64), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        for (int k = 11; k >= 0; k--) {
            double x = 2.0 + 4 * k, y = k < 4 ? (k % 2 ? -2.5 : 1.4)
                                               : k < 8 ? (k % 2 ? 29.6 : 30.0) : 33.25;
            assert_int_equal(aa_scene_move_to(s, (x + 1.5) / 64, y / 64), AA_OK);
            assert_int_equal(aa_scene_line_to(s, (x + 3.2) / 64, (y + 6.4) / 64), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x / 64, (y + 5.1) / 64), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        const double cx = 54.0 / 64, cy = 48.0 / 64, r = 6.5 / 64, c = 0.5523 * r;
        assert_int_equal(aa_scene_move_to(s, cx + r, cy), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, cx + r, cy + c, cx + c, cy + r, cx, cy + r), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, cx - c, cy + r, cx - r, cy + c, cx - r, cy), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, cx - r, cy - c, cx - c, cy - r, cx, cy - r), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, cx + c, cy - r, cx + r, cy - c, cx + r, cy), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        if (far) {
            oracle_poly q = {4, {40.2 / 64, 44.7 / 64, 44.7 / 64, 40.2 / 64},
                             {56.4 / 64, 56.4 / 64, 300.0 / 64, 300.0 / 64}};
            scenes_add_poly(s, &q);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        check_reference(far ? "pieces by rows and x, one far below" : "pieces by rows and x", s,
                        64, 64, 0, 0, 0, 1e-12);
        aa_scene_free(s);
    }
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_crow_reference),
             cmocka_unit_test(test_crow_oracle),
             cmocka_unit_test(test_crow_other),
             cmocka_unit_test(test_crow_large),
             cmocka_unit_test(test_catmull_pixel),
             cmocka_unit_test(test_polygon_layers),
             cmocka_unit_test(test_fill_rules),
             cmocka_unit_test(test_many_crossings),
             cmocka_unit_test(test_arc_under_layer),
             cmocka_unit_test(test_random_polygons),
             cmocka_unit_test(test_integrators_agree),
             cmocka_unit_test(test_counters_and_uniform),
             cmocka_unit_test(test_threads_identical),
             cmocka_unit_test(test_filters_refused),
             cmocka_unit_test(test_crowded_cluster),
             cmocka_unit_test(test_crowded_crossings),
             cmocka_unit_test(test_crowded_layers),
             cmocka_unit_test(test_crowded_passes),
             cmocka_unit_test(test_sweep_parts),
             cmocka_unit_test(test_sort_new_keys),
             cmocka_unit_test(test_sub_band_orders),
             cmocka_unit_test(test_piece_rows))
