/*
 * test_analytic_visible.c: `analytic` in the rows where layers overlap,
 * whose visible parts are found once per block of rows and scattered
 * (algorithms/analytic.c, "The visible parts' scatter").
 *
 * Known answers, none from the method itself:
 *  - the exact reference of the harness's separate truth path
 *    (aa_truth_render, its own quadrature of the filter over the scene's
 *    rows), within 1e-12 per pixel, at 1 and 2 threads bit-identical, on
 *    wide rectangles in two colours, in one, and overlapping, and on 200
 *    and 300 overlapping layers of distinct colours (within and past the
 *    scatter's table of faces' colours);
 *  - a pixel whose support lies, for each rectangle, wholly inside it or
 *    wholly outside it is the colour of the scene's own point query at its
 *    centre (aa_scene_colour_at), exactly: the face's colour, not a sum;
 *  - the visible parts of windows 8 px wide (the scatter's tiles) are the
 *    same, run for run and bit for bit, whether or not the meetings of two
 *    pieces both outside the window are sought (visible.h, inside_meets:
 *    such a meeting changes no part's jump, only where bands are cut),
 *    and the reference as above on that scene: two layers of long cubic
 *    arcs crossing each other in a few tiles, outside the others.
 * (test_analytic.c holds the rest: the shipped scenes with overlapping
 * layers, rows of both paths in one image, abutting paths.)
 */
#include "bench.h"
#include "support.h"
#include "tier.h"
#include "visible.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) test_many_colours runs a declared subset: each of its
 * two scenes under two of its four filters, every filter reached.  The
 * sanitizers find memory and undefined-behaviour errors along the paths
 * taken, and another filter on the same scene takes the same paths with
 * other numbers (tests/README.md, "Tiers", says how that was checked); the
 * plain build runs every case. */

/* analytic against the reference under each filter of `filters` (NULL
 * ended), at w x h, threads 1 and 2 (the image does not depend on them);
 * fails over 1e-12 per pixel and prints the largest difference. */
static void against_filters(const char *what, const aa_scene *s, int w, int h,
                            const char *const *flist)
{
    for (const char *const *f = flist; *f; f++) {
        aa_image a, a1, r;
        support_render("analytic", s, *f, w, h, 2, &a, NULL);
        support_render("analytic", s, *f, w, h, 1, &a1, NULL);
        support_reference(s, &(support_view){.w = w, .h = h, .filter = *f, .threads = 1}, &r,
                          NULL, NULL);
        double worst = support_within_reference(what, *f, &a, &r, 1e-12);
        print_message("%-24s %-22s largest difference %.1e\n", what, *f, worst);
        size_t n = (size_t)w * h * 3;
        for (size_t k = 0; k < n; k++)
            if (memcmp(&a.v[k], &a1.v[k], sizeof a.v[k]))
                fail_msg("%s under %s: pixel %zu channel %zu differs between 1 and 2 threads",
                         what, *f, k / 3, k % 3);
        aa_image_free(&a);
        aa_image_free(&a1);
        aa_image_free(&r);
    }
}

/* Wide rectangles (flat top and bottom edges) in two colours, then in one,
 * then in two colours overlapping (their rows take the visible parts'
 * scatter, whose faces are named by a code): against the reference, and
 * every pixel whose support lies, for each rectangle, wholly inside it or
 * wholly outside it, not touching a side, is the colour of the scene's
 * own point query at its centre (aa_scene_colour_at: the front
 * rectangle's where they overlap) exactly (the supports are found from
 * the geometry alone; a side on a support's edge leaves that pixel to the
 * integration, within rounding of the colour). */
static void test_faces_exact(void **state)
{
    (void)state;
    const char *const flist[] = {"box", "tent:r=1", "bspline:order=3", NULL};
    const int w = 40, h = 30;
    const aa_rgb bg = {{0.1, 0.2, 0.3}}, c[3][2] = {{{{0.3, 0.8, 0.15}}, {{0.9, 0.05, 0.6}}},
                                                   {{{0.7, 0.7, 0.7}}, {{0.7, 0.7, 0.7}}},
                                                   {{{0.3, 0.8, 0.15}}, {{0.9, 0.05, 0.6}}}};
    static const char *const names[3] = {"rectangles", "rectangles, one colour",
                                         "rectangles overlapping"};
    /* pixel boxes [x0, x1) x [y0, y1) */
    const int r[3][2][4] = {{{4, 3, 36, 12}, {6, 17, 30, 27}},
                            {{4, 3, 36, 12}, {6, 17, 30, 27}},
                            {{4, 3, 30, 19}, {12, 9, 37, 27}}};
    for (int k0 = 0; k0 < 3; k0++) {
        aa_scene *s = aa_scene_new(bg);
        assert_non_null(s);
        for (int k = 0; k < 2; k++) {
            const int *b = r[k0][k];
            assert_int_equal(aa_scene_layer(s, c[k0][k], AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(s, b[0] / (double)w, b[1] / (double)h), AA_OK);
            assert_int_equal(aa_scene_line_to(s, b[2] / (double)w, b[1] / (double)h), AA_OK);
            assert_int_equal(aa_scene_line_to(s, b[2] / (double)w, b[3] / (double)h), AA_OK);
            assert_int_equal(aa_scene_line_to(s, b[0] / (double)w, b[3] / (double)h), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        against_filters(names[k0], s, w, h, flist);
        for (const char *const *f = flist; *f; f++) {
            aa_filter fl;
            assert_int_equal(aa_filter_parse(*f, &fl), AA_OK);
            double rad = fl.radius; /* the support: [c - rad, c + rad] */
            aa_image a;
            support_render("analytic", s, *f, w, h, 1, &a, NULL);
            int inside = 0, outside = 0, both = 0;
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    double x0 = i + 0.5 - rad, x1 = i + 0.5 + rad, y0 = j + 0.5 - rad,
                           y1 = j + 0.5 + rad;
                    int in = 0, clear = 1;
                    for (int k = 0; k < 2; k++) {
                        const int *b = r[k0][k];
                        int kin = x0 > b[0] && x1 < b[2] && y0 > b[1] && y1 < b[3];
                        in += kin;
                        clear &= kin || x1 < b[0] || x0 > b[2] || y1 < b[1] || y0 > b[3];
                    }
                    if (!clear)
                        continue;
                    inside += in > 0, outside += in == 0, both += in == 2;
                    /* the scene in pattern units: the centre over the size */
                    aa_rgb want = aa_scene_colour_at(s, (i + 0.5) / w, (j + 0.5) / h);
                    for (int ch = 0; ch < 3; ch++)
                        if (aa_pixel(&a, i, j)[ch] != want.c[ch])
                            fail_msg("%s under %s: pixel (%d, %d) channel %d is %.17g, not the "
                                     "face's %.17g",
                                     names[k0], *f, i, j, ch, aa_pixel(&a, i, j)[ch],
                                     want.c[ch]);
                }
            assert_true(inside > 0 && outside > 0);
            assert_true(k0 < 2 || both > 0);
            aa_image_free(&a);
        }
        aa_scene_free(s);
    }
}

/* Many overlapping layers of distinct colours: n rectangles, each 0.1 of
 * the width, their left sides 0.8/n apart, every one seen in a sliver.
 * The visible parts' scatter names each colour its faces meet in a block
 * by a code, up to 256 of them (analytic.c, AN_FACES); 200 colours stay
 * within, 300 do not, and those rows take the per-pixel path.  Either way
 * the reference (support.h) within 1e-12, at 1 and 2 threads alike. */
static void test_many_colours(void **state)
{
    (void)state;
    const char *const flist[] = {"box", "tent:r=1", "tent:r=0.65", "bspline:order=3", NULL};
    /* the sanitizer build's subset: 200 colours under the box and
     * bspline:order=3, 300 under tent:r=1 and tent:r=0.65 (SAN_SUBSET) */
    const char *const half[2][3] = {{"box", "bspline:order=3", NULL},
                                    {"tent:r=1", "tent:r=0.65", NULL}};
    SAN_CASES_PRINT();
    const int counts[2] = {200, 300};
    for (int q = 0; q < 2; q++) {
        int n = counts[q];
        aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
        assert_non_null(s);
        for (int k = 0; k < n; k++) {
            aa_rgb c = {{(k % 7) / 7.0, (k % 11) / 11.0, k / (double)n}};
            double x0 = 0.05 + 0.8 * k / n, x1 = x0 + 0.1, y0 = 0.2 + 0.3 * k / n,
                   y1 = y0 + 0.4;
            assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x1, y0), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x1, y1), AA_OK);
            assert_int_equal(aa_scene_line_to(s, x0, y1), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        against_filters(q ? "300 colours" : "200 colours", s, 40, 20, SAN_SUBSET ? half[q] : flist);
        aa_scene_free(s);
    }
}

/* Two lenses of cubic arcs, each 0.9 of the width wide, in two colours,
 * the second shifted down and sheared so that their arcs cross each other
 * near x = 0.3 and x = 0.7 (pattern units). */
static aa_scene *lenses(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    const aa_rgb c[2] = {{{0.9, 0.6, 0.1}}, {{0.2, 0.7, 0.9}}};
    for (int k = 0; k < 2; k++) {
        double d = 0.12 * k, e = 0.1 * k;
        assert_int_equal(aa_scene_layer(s, c[k], AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, 0.05, 0.5 + d - e), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, 0.3, 0.05 + d, 0.7, 0.05 + d, 0.95, 0.5 + d + e),
                         AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, 0.7, 0.95 + d - e, 0.3, 0.95 - d, 0.05,
                                           0.5 + d - e),
                         AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

typedef struct vis_log {
    const aa_piece *base;
    size_t nrun, nband;
    double run[4096][7]; /* piece index, ya, yb, jump (3), inside */
    double band[4096][2]; /* ya, yb */
} vis_log;

static void log_band(void *ctx, double ya, double yb, const int *wind)
{
    vis_log *L = ctx;
    (void)wind;
    assert_true(L->nband < 4096);
    double *b = L->band[L->nband++];
    b[0] = ya, b[1] = yb;
}

static void log_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                    int inside)
{
    vis_log *L = ctx;
    assert_true(L->nrun < 4096);
    double *r = L->run[L->nrun++];
    r[0] = (double)(p - L->base), r[1] = ya, r[2] = yb;
    r[3] = jump[0], r[4] = jump[1], r[5] = jump[2], r[6] = inside;
}

/* The visible parts of the lenses placed at 96 x 32 px, in windows 8 px
 * wide across the rows [0, 32], with inside_meets off (every neighbouring
 * pair's meetings sought) and on: the same runs in the same order, bit for
 * bit; every band cut with it on is one cut with it off (only cuts go);
 * and fewer bands with it on (the scene has meetings outside windows). */
static void test_outside_meetings(void **state)
{
    (void)state;
    aa_scene *s = lenses();
    aa_scene *P = aa_scene_place(s, 96, 32, 0.0, 0.0, 0.0);
    assert_non_null(P);
    size_t n;
    const aa_piece *base = aa_scene_pieces(P, &n);
    void *block = malloc(aa__vis_size(P, 3));
    vis_log *L[2] = {calloc(1, sizeof(vis_log)), calloc(1, sizeof(vis_log))};
    aa_strip *st = aa_strip_new(P);
    assert_true(block && L[0] && L[1] && st);
    size_t total[2] = {0, 0};
    for (double xa = -1.0; xa < 97.0; xa += 8.0) {
        for (int f = 0; f < 2; f++) {
            aa__vis v;
            aa__vis_bind(&v, P, 3, block);
            L[f]->base = base, L[f]->nrun = L[f]->nband = 0;
            const aa__vis_sink sk = {log_band, log_run, NULL, NULL, L[f], 3, 0, 0, f};
            assert_int_equal(aa_strip_begin(st, 0.0, 32.0), AA_OK);
            aa_strip_window(st, xa, xa + 8.0);
            aa__vis_window(&v, st, xa, xa + 8.0, 0.0, 32.0, &sk);
            total[f] += L[f]->nband;
        }
        if (L[0]->nrun != L[1]->nrun ||
            memcmp(L[0]->run, L[1]->run, L[0]->nrun * sizeof L[0]->run[0]))
            fail_msg("window [%g, %g]: the runs differ with inside_meets (%zu and %zu runs)", xa,
                     xa + 8.0, L[0]->nrun, L[1]->nrun);
        /* each cut of the bands with it on is a cut with it off */
        size_t k = 0;
        for (size_t b = 0; b < L[1]->nband; b++) {
            while (k < L[0]->nband && L[0]->band[k][1] < L[1]->band[b][1])
                k++;
            if (k == L[0]->nband || L[0]->band[k][1] != L[1]->band[b][1])
                fail_msg("window [%g, %g]: a band ends at %.17g with inside_meets only", xa,
                         xa + 8.0, L[1]->band[b][1]);
        }
    }
    print_message("bands over the windows: %zu seeking every meeting, %zu with inside_meets\n",
                  total[0], total[1]);
    assert_true(total[1] < total[0]);
    aa_strip_free(st);
    free(L[0]);
    free(L[1]);
    free(block);
    aa_scene_free(P);
    const char *const flist[] = {"box", "tent:r=1", "bspline:order=3", NULL};
    against_filters("lenses crossing", s, 96, 32, flist);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_faces_exact),
             cmocka_unit_test(test_many_colours), cmocka_unit_test(test_outside_meetings))
