/*
 * test_prefilters.c: the prefilters of the seed papers on scenes of several
 * layers: conetable (Feibush, Levoy and Cook 1980), crowtable (Crow 1976,
 * ch. 2) and crowtiler (Crow 1976, ch. 3).
 *
 * Known answers, none from the methods themselves:
 *  - the exact reference of the harness's separate truth path
 *    (aa_truth_render), on the patterns and on scenes built here: abutting
 *    polygons of different colours, a polygon hidden behind another;
 *  - closed forms: behind a front polygon nothing of a hidden one can show
 *    (its colour's channel is exactly zero where the visible colours have
 *    none); a straight edge crossing the whole square of a separable filter,
 *    represented by one rectangle as Crow describes (fig. 2.8: entry at the
 *    top, exit at the bottom), gives 1 - C(d), C the filter's 1-D integral
 *    and d the edge's horizontal offset at the centre row, which differs
 *    from the exact value by about s^2 / 12 for an edge of slope s under
 *    tent:r=1 (s^2 C''(d) var(v) / 2, var(v) = 1/6);
 *  - each method's header bound on its tables, computed here from the
 *    scene's own piece geometry.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* ---- helpers ---- */

static int render(const char *method, const aa_scene *scene, const char *filter, int w, int h,
                  int threads, double t, double vx, double vy, aa_image *out)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .filter = filter,
                            .seed = 1, .threads = threads};
    return support_render_view(method, scene, &v, out, NULL);
}

static void must_render(const char *method, const aa_scene *scene, const char *filter, int w,
                        int h, aa_image *out)
{
    support_render(method, scene, filter, w, h, 2, out, NULL);
}

/* On one thread: the reference does not depend on the threads
 * (test_truth.c checks that), and on two one thread spun, using CPU for
 * nothing, while the other finished the last rows of costly pixels. */
static void reference(const aa_scene *scene, const char *filter, int w, int h, aa_image *out)
{
    support_reference(scene, &(support_view){.w = w, .h = h, .filter = filter, .threads = 1},
                      out, NULL, NULL);
}

/* RMSE and largest error of img against ref over every channel. */
static double compare(const aa_image *img, const aa_image *ref, double *worst)
{
    double sum = 0.0;
    size_t n = (size_t)img->w * img->h * 3;
    *worst = 0.0;
    for (size_t k = 0; k < n; k++) {
        if (!(img->v[k] >= 0.0 && img->v[k] <= 1.0))
            fail_msg("value %.17g outside [0, 1] at %zu", img->v[k], k);
        double e = fabs(img->v[k] - ref->v[k]);
        sum += e * e;
        *worst = fmax(*worst, e);
    }
    return sqrt(sum / (double)n);
}

static const aa_rgb RED = {{1, 0, 0}}, GREEN = {{0, 1, 0}}, BLUE = {{0, 0, 1}},
                    GREY = {{0.5, 0.5, 0.5}}, BLACK = {{0, 0, 0}};

/* A polygon of n points (x, y pairs) in one colour. */
typedef struct piece {
    aa_rgb colour;
    int n;
    double xy[10];
} piece;

/* The pieces over bg, each a layer of its own (nonzero), the first in
 * front; finished. */
static aa_scene *pieces_scene(aa_rgb bg, const piece *p, int n)
{
    aa_scene *s = aa_scene_new(bg);
    assert_non_null(s);
    for (int k = 0; k < n; k++) {
        assert_int_equal(aa_scene_layer(s, p[k].colour, AA_FILL_NONZERO), AA_OK);
        scenes_path(s, p[k].xy, p[k].n);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* Abutting polygons of different colours over blue: red (front) and green
 * (behind it in the layer order, but they do not overlap) share a slanted
 * edge from (0.31, 0.12) to (0.62, 0.83), each with edges of its own in the
 * picture, and a grey triangle lies wholly behind red (with `hidden`), where
 * nothing of it may show. */
static aa_scene *abutting(int hidden)
{
    const piece p[] = {{RED, 4, {0.31, 0.12, 0.62, 0.83, 0.18, 0.77, 0.12, 0.21}},
                       {GREEN, 4, {0.62, 0.83, 0.31, 0.12, 0.86, 0.23, 0.91, 0.71}},
                       {GREY, 3, {0.22, 0.3, 0.4, 0.4, 0.25, 0.6}}};
    return pieces_scene(BLUE, p, hidden ? 3 : 2);
}

/* A green square over black with a red square wholly behind it, 0.1 (several
 * pixels at the sizes used) inside its edges: no red may show anywhere. */
static aa_scene *occluded(void)
{
    const piece p[] = {{GREEN, 4, {0.15, 0.1, 0.85, 0.17, 0.8, 0.9, 0.1, 0.82}},  /* front */
                       {RED, 4, {0.3, 0.3, 0.65, 0.33, 0.6, 0.7, 0.28, 0.66}}}; /* back */
    return pieces_scene(BLACK, p, 2);
}

static void red_is_zero(const char *method, const char *filter, double tol)
{
    aa_scene *s = occluded();
    aa_image img;
    must_render(method, s, filter, 48, 48, &img);
    double worst = 0.0;
    for (int p = 0; p < 48 * 48; p++)
        worst = fmax(worst, fabs(img.v[3 * p]));
    print_message("%s -f %s: hidden red square, largest red %.3g\n", method, filter, worst);
    if (!(worst <= tol))
        fail_msg("%s -f %s: a hidden polygon shows: red %.3g", method, filter, worst);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* ---- conetable: the visible parts of the polygons ---- */

/* conetable's bound per chord end on the table's interpolation (its
 * header): (1/4 + c / (2 M sqrt(2 pi))) / res for the Gaussian cut at c
 * standard deviations, (1/4 + 3 / (2 pi)) / res for the cone. */
static double cone_end(int gauss, double cut, int res)
{
    if (!gauss)
        return (0.25 + 3.0 / (2.0 * M_PI)) / res;
    double M = -expm1(-0.5 * cut * cut);
    return (0.25 + cut / (2.0 * M * sqrt(2.0 * M_PI))) / res;
}

/* Pieces of the placed scene whose extent meets the square of half-width R
 * around (cx, cy) (from the scene's own piece extents). */
static int pieces_near(const aa_scene *placed, double cx, double cy, double R)
{
    size_t n;
    const aa_piece *p = aa_scene_pieces(placed, &n);
    int count = 0;
    for (size_t q = 0; q < n; q++)
        count += p[q].xmax >= cx - R && p[q].xmin <= cx + R && p[q].y1 >= cy - R &&
                 p[q].y0 <= cy + R;
    return count;
}

/* Every pixel of the abutting scene within its bound: each piece near the
 * pixel is cut into at most three visible parts here (the shared edge
 * where the other polygon's edges end on it), two chord ends each, a colour
 * step of at most 1 per channel; plus the truncation. */
static void cone_abutting(const char *method, const char *filter, int gauss, double cut,
                          int res, double trunc, double rmse_max)
{
    const int n = 48;
    aa_scene *s = abutting(1);
    aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    double R = gauss ? cut * f.spec.v[0] : f.spec.v[0];
    aa_image img, ref;
    must_render(method, s, filter, n, n, &img);
    reference(s, filter, n, n, &ref);
    double worst, rmse = compare(&img, &ref, &worst), end = cone_end(gauss, cut, res);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double b = pieces_near(placed, i + 0.5, j + 0.5, R) * 3 * 2 * end + trunc + 1e-12;
            for (int ch = 0; ch < 3; ch++) {
                double e = fabs(aa_pixel(&img, i, j)[ch] - aa_pixel(&ref, i, j)[ch]);
                if (!(e <= b))
                    fail_msg("%s -f %s: pixel (%d, %d) error %.3e above its bound %.3e", method,
                             filter, i, j, e, b);
            }
        }
    print_message("%s -f %s: abutting layers RMSE %.3e, max %.3e\n", method, filter, rmse,
                  worst);
    if (!(rmse <= rmse_max))
        fail_msg("%s -f %s: RMSE %.3e above %.3e", method, filter, rmse, rmse_max);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(placed);
    aa_scene_free(s);
}

static void test_cone_abutting_layers(void **state)
{
    (void)state;
    /* cut=8: 1.3e-14 of the Gaussian outside the mask; the cone has none.
     * Compositing the layers' coverages front to back (the code before the
     * visible parts) was off by up to 0.25 along the shared edge. */
    cone_abutting("conetable:cut=8,res=256", "gauss:s=1", 1, 8.0, 256, 3e-14, 1e-3);
    cone_abutting("conetable:res=1024", "cone:r=1.5", 0, 1.0, 1024, 0.0, 1e-4);
}

/* A hidden polygon adds nothing: the same image with and without it. */
static void test_cone_hidden_adds_nothing(void **state)
{
    (void)state;
    const char *filters[] = {"gauss:s=1", "cone:r=1.5"};
    for (int k = 0; k < 2; k++) {
        aa_scene *a = abutting(1), *b = abutting(0);
        aa_image ia, ib;
        must_render("conetable:res=256", a, filters[k], 48, 48, &ia);
        must_render("conetable:res=256", b, filters[k], 48, 48, &ib);
        double worst;
        compare(&ia, &ib, &worst);
        print_message("conetable -f %s: with and without the hidden polygon differ by %.3g\n",
                      filters[k], worst);
        assert_true(worst <= 1e-15);
        aa_image_free(&ia);
        aa_image_free(&ib);
        aa_scene_free(a);
        aa_scene_free(b);
    }
    red_is_zero("conetable:res=256", "gauss:s=1", 0.0);
    red_is_zero("conetable", "cone", 0.0);
}

/* The patterns of several layers (feibush: red and white stripes sharing
 * edges; catmull: a hidden red rectangle, green and blue abutting; slivers:
 * a front layer of black clipping triangles at the square's edge) within
 * the target of 5e-3 RMSE (measured 64x64, gauss:s=1, cut=4, res=256:
 * about 1e-4, and 6e-5 to 1.1e-4 at 24x24; compositing layers gave 0.12,
 * 0.034 and 0.018 at 128x128).  The Gaussian's view is 24x24: its
 * reference takes QAG on most pixels of these patterns (edges meeting,
 * steeper than 1) and cost some 20 s at 64x64.  The size is not what is
 * checked: every layer and shared edge of the patterns is still in view,
 * each mask (4 pixels in radius at cut=4) holds more edges and layers
 * than at 64x64, not fewer, and a wrong compositing, a share of the
 * contrast off on each pixel along a shared edge, weighs more in the RMSE
 * of fewer pixels, not less.  The cone's reference is cheap: 64x64. */
static void test_cone_patterns(void **state)
{
    (void)state;
    const char *names[] = {"feibush", "catmull:tiles=4", "slivers", "star"};
    const char *filters[] = {"gauss:s=1", "cone"};
    const char *methods[] = {"conetable:cut=4,res=256", "conetable:res=256"};
    const int sizes[] = {24, 64};
    SAN_CASES_PRINT();
    for (int k = 0; k < 4; k++)
        for (int f = 0; f < 2; f++) {
            /* the sanitizer build's subset (SAN_SUBSET): feibush not
             * under the Gaussian (its stripes' shared edges under the
             * cone; catmull's abutting layers under both) */
            if (SAN_SUBSET && f == 0 && k == 0)
                continue;
            aa_scene *s = scenes_pattern(names[k]);
            aa_image img, ref;
            const int n = sizes[f];
            must_render(methods[f], s, filters[f], n, n, &img);
            reference(s, filters[f], n, n, &ref);
            double worst, rmse = compare(&img, &ref, &worst);
            print_message("%s -f %s on %s %dx%d: RMSE %.3e, max %.3e\n", methods[f], filters[f],
                          names[k], n, n, rmse, worst);
            if (!(rmse <= 5e-3 && worst <= 2e-2))
                fail_msg("%s on %s: RMSE %.3e, max %.3e", methods[f], names[k], rmse, worst);
            aa_image_free(&img);
            aa_image_free(&ref);
            aa_scene_free(s);
        }
}

/* ---- Crow's rectangle per edge ---- */

#define HP 24

/* White right of the straight edge through (px, py) pixels of an HP x HP
 * image at `angle` from the vertical, on black (the slope dx/dy is
 * tan(angle)). */
static aa_scene *half_plane(double px, double py, double angle)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    double dx = sin(angle), dy = cos(angle), nx = dy, ny = -dx, L = 50.0;
    px /= HP, py /= HP;
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    const double xy[] = {px - L * dx,          py - L * dy,          px + L * dx,
                         py + L * dy,          px + L * dx + L * nx, py + L * dy + L * ny,
                         px - L * dx + L * nx, py - L * dy + L * ny};
    scenes_path(s, xy, 4);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* On the pixels whose square (half-width 1, tent:r=1) the edge crosses from
 * its top to its bottom, the one rectangle at the edge's mean position gives
 * 1 - C(d), d its horizontal offset at the centre row, within the table's
 * lookup (1 / (2 res): a side read at the nearest of entries 1 / res
 * apart, the weight at most 1); and the exact tent value differs from that
 * by about s^2 / 12, so the method is not the exact prefilter. */
static void one_rectangle(const char *method, int res)
{
    const double angle = 0.5, s = tan(angle), px = 11.3, py = 12.1;
    aa_scene *sc = half_plane(px, py, angle);
    aa_image img, ref;
    aa_filter f;
    assert_int_equal(aa_filter_parse("tent:r=1", &f), AA_OK);
    must_render(method, sc, "tent:r=1", HP, HP, &img);
    reference(sc, "tent:r=1", HP, HP, &ref);
    double worst = 0.0, apart = 0.0;
    int used = 0;
    for (int j = 0; j < HP; j++)
        for (int i = 0; i < HP; i++) {
            double cx = i + 0.5, cy = j + 0.5;
            double d = px + s * (cy - py) - cx; /* the edge's x at the centre row, from cx */
            if (!(fabs(d) + fabs(s) <= 0.98))
                continue;
            used++;
            double crow = 1.0 - aa_filter_cdf(&f, d), v = aa_pixel(&img, i, j)[0];
            worst = fmax(worst, fabs(v - crow));
            apart = fmax(apart, fabs(aa_pixel(&ref, i, j)[0] - crow));
        }
    print_message("%s: %d pixels, one rectangle per edge within %.3e of 1 - C(d) (bound %.3e); "
                  "the exact value up to %.3e away\n",
                  method, used, worst, 0.5 / res, apart);
    assert_true(used >= 10);
    if (!(worst <= 0.5 / res + 1e-12))
        fail_msg("%s: %.3e from Crow's one rectangle per edge", method, worst);
    /* s^2 / 12 = 0.025 at the largest |C''| = 1 */
    assert_true(apart > 0.01);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(sc);
}

static void test_crowtable_one_rectangle(void **state)
{
    (void)state;
    one_rectangle("crowtable:res=1024", 1024);
    one_rectangle("crowtable:form=crow,res=64", 64);
}

/* Vertical and horizontal edges make Crow's rectangles exact up to the
 * lookups: abutting rectangles of different colours, and one hidden behind
 * them.  Per pixel at most 3 lookups per piece near it and 2 per block of
 * rows (one per end of a piece, plus the square's), each within
 * 1 / (2 res), contrast at most 1 per channel. */
static aa_scene *boxes(void)
{
    const piece p[] = {
        {RED, 4, {0.2137, 0.1581, 0.5119, 0.1581, 0.5119, 0.8363, 0.2137, 0.8363}},
        {GREEN, 4, {0.5119, 0.3029, 0.8347, 0.3029, 0.8347, 0.7043, 0.5119, 0.7043}},
        {GREY, 4, {0.3011, 0.3107, 0.4493, 0.3107, 0.4493, 0.6021, 0.3011, 0.6021}}};
    return pieces_scene(BLUE, p, 3);
}

static void rect_scene_within(const char *method, const char *filter, double R, int res)
{
    const int n = 40;
    aa_scene *s = boxes();
    aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
    aa_image img, ref;
    must_render(method, s, filter, n, n, &img);
    reference(s, filter, n, n, &ref);
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    double wx = aa_filter_weight(&f, 0.0), d = 2.0 * R / ceil(2.0 * R * res);
    double worst, rmse = compare(&img, &ref, &worst);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int k = pieces_near(placed, i + 0.5, j + 0.5, R);
            double b = (3.0 * k + 2.0 * (2 * k + 1)) * wx * d / 2.0 + 1e-12;
            for (int ch = 0; ch < 3; ch++) {
                double e = fabs(aa_pixel(&img, i, j)[ch] - aa_pixel(&ref, i, j)[ch]);
                if (!(e <= b))
                    fail_msg("%s -f %s: pixel (%d, %d) error %.3e above its bound %.3e", method,
                             filter, i, j, e, b);
            }
        }
    print_message("%s -f %s: abutting and hidden rectangles RMSE %.3e, max %.3e\n", method,
                  filter, rmse, worst);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(placed);
    aa_scene_free(s);
}

static void test_crowtable_layers(void **state)
{
    (void)state;
    rect_scene_within("crowtable:res=64", "tent:r=1", 1.0, 64);
    rect_scene_within("crowtable:res=256", "tent:r=0.5", 0.5, 256);
    red_is_zero("crowtable", "tent:r=1", 0.0);
    red_is_zero("crowtable:form=rows", "tent:r=1", 0.0);
}

/* ---- crowtiler ---- */

/* area=exact with hidden=scan is the exact prefilter: within rounding of the
 * reference on polygon scenes of several layers, and on crow's arcs. */
static void test_tiler_exact(void **state)
{
    (void)state;
    const char *names[] = {"catmull:tiles=4", "slivers", "star", "feibush", "crow",
                           "slivers:tilt=3,count=12"};
    for (int k = 0; k < 6; k++) {
        aa_scene *s = scenes_pattern(names[k]);
        aa_image img, ref;
        must_render("crowtiler:area=exact,hidden=scan", s, "tent:r=1", 64, 64, &img);
        reference(s, "tent:r=1", 64, 64, &ref);
        double worst, rmse = compare(&img, &ref, &worst);
        print_message("crowtiler:area=exact,hidden=scan on %s 64x64: RMSE %.3e, max %.3e\n",
                      names[k], rmse, worst);
        if (!(worst <= 1e-12))
            fail_msg("%s: max error %.3e", names[k], worst);
        aa_image_free(&img);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
    aa_scene *s = abutting(1);
    aa_image img, ref;
    must_render("crowtiler:area=exact,hidden=scan", s, "tent:r=1", 48, 48, &img);
    reference(s, "tent:r=1", 48, 48, &ref);
    double worst;
    compare(&img, &ref, &worst);
    print_message("crowtiler:area=exact,hidden=scan on abutting layers: max %.3e\n", worst);
    assert_true(worst <= 1e-12);
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(s);
}

/* Two polygons of different colours sharing a slanted edge, covering the
 * whole image (so that edge is the only one in view), over black.  In the
 * z-priority order green (behind) is written first; its edge shared with
 * red, not yet written, is overwritten (Crow's adjacent-polygon rule), and
 * red then blends with green alone: exact with area=exact.  With the shared
 * edge cut at another point on one side, the pieces are not the same, the
 * polygons are not adjacent, and black shows along the edge (fig. 3.5's
 * pencil line). */
static aa_scene *two_halves(int adjacent)
{
    /* not adjacent: green is the same region, its edge cut at (0.5, 0.5) */
    const piece p[] = {
        {RED, 4, {-1.0, -1.0, 0.3, -1.0, 0.7, 2.0, -1.0, 2.0}},
        {GREEN, adjacent ? 4 : 5, {0.3, -1.0, 2.0, -1.0, 2.0, 2.0, 0.7, 2.0, 0.5, 0.5}}};
    return pieces_scene(BLACK, p, 2);
}

static void test_tiler_priority(void **state)
{
    (void)state;
    for (int adjacent = 1; adjacent >= 0; adjacent--) {
        aa_scene *s = two_halves(adjacent);
        aa_image img, ref;
        reference(s, "tent:r=1", 32, 32, &ref);
        must_render("crowtiler:area=exact", s, "tent:r=1", 32, 32, &img);
        double worst, rmse = compare(&img, &ref, &worst);
        print_message("crowtiler:area=exact (priority), %s halves: RMSE %.3e, max %.3e\n",
                      adjacent ? "adjacent" : "unrelated", rmse, worst);
        if (adjacent)
            assert_true(worst <= 1e-12);
        else
            assert_true(worst > 0.05); /* the pencil line */
        aa_image_free(&img);
        /* the scanning algorithm resolves both */
        must_render("crowtiler:area=exact,hidden=scan", s, "tent:r=1", 32, 32, &img);
        compare(&img, &ref, &worst);
        assert_true(worst <= 1e-12);
        aa_image_free(&img);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
    red_is_zero("crowtiler", "tent:r=1", 1e-15);
    red_is_zero("crowtiler:area=exact", "tent:r=1", 1e-15);
    red_is_zero("crowtiler:hidden=scan", "tent:r=1", 0.0);
    red_is_zero("crowtiler:area=exact,hidden=scan", "tent:r=1", 0.0);
}

/* The z-buffer written front to back: red, in front, is blended with the
 * black background wherever its weighted area a reaches a dot, and green,
 * behind, is then not written there (its blending information lost): red
 * a, green 0, where the exact picture has green 1 - a; where red does not
 * reach, green alone, exactly.  A scene of one layer is the z-priority
 * image bit for bit. */
static void test_tiler_zbuffer(void **state)
{
    (void)state;
    aa_scene *s = two_halves(1);
    aa_image img, ref;
    reference(s, "tent:r=1", 32, 32, &ref);
    must_render("crowtiler:area=exact,hidden=zbuffer", s, "tent:r=1", 32, 32, &img);
    int lost = 0;
    for (int j = 0; j < 32; j++)
        for (int i = 0; i < 32; i++) {
            const double *v = aa_pixel(&img, i, j), *r = aa_pixel(&ref, i, j);
            double a = r[0], green = a > 1e-12 ? 0.0 : r[1];
            lost += a > 1e-12 && r[1] > 1e-12;
            if (!(fabs(v[0] - a) <= 1e-12 && fabs(v[1] - green) <= 1e-12 && v[2] == 0.0))
                fail_msg("zbuffer pixel (%d, %d): %.6f %.6f %.6f, expected %.6f %.6f 0", i, j,
                         v[0], v[1], v[2], a, green);
        }
    print_message("crowtiler:area=exact,hidden=zbuffer on two halves: %d dots lose green\n",
                  lost);
    assert_true(lost >= 32); /* the shared edge crosses every row */
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(s);
    aa_scene *crow = scenes_pattern("crow");
    aa_image z, p;
    must_render("crowtiler:hidden=zbuffer", crow, "tent:r=1", 48, 48, &z);
    must_render("crowtiler", crow, "tent:r=1", 48, 48, &p);
    assert_memory_equal(z.v, p.v, sizeof(double) * 48 * 48 * 3);
    aa_image_free(&z);
    aa_image_free(&p);
    aa_scene_free(crow);
}

static void test_tiler_tables(void **state)
{
    (void)state;
    /* Crow's tables: one rectangle per edge, as crowtable's */
    one_rectangle("crowtiler:res=1024,hidden=scan", 1024);
    one_rectangle("crowtiler:res=64", 64);
    rect_scene_within("crowtiler:res=64,hidden=scan", "tent:r=1", 1.0, 64);
    /* converging with res where the rectangles are exact */
    double first = 0.0, last = 0.0;
    const int res[] = {4, 16, 64, 256};
    for (int k = 0; k < 4; k++) {
        char spec[64];
        snprintf(spec, sizeof spec, "crowtiler:hidden=scan,res=%d", res[k]);
        aa_scene *s = boxes();
        aa_image img, ref;
        must_render(spec, s, "tent:r=1", 40, 40, &img);
        reference(s, "tent:r=1", 40, 40, &ref);
        double worst, rmse = compare(&img, &ref, &worst);
        print_message("%s on rectangles: RMSE %.3e\n", spec, rmse);
        if (k == 0)
            first = rmse;
        last = rmse;
        aa_image_free(&img);
        aa_image_free(&ref);
        aa_scene_free(s);
    }
    assert_true(last < first / 16.0);
}

/* What test_methods.c and test_temporal.c check of every method with the
 * box or the Gaussian, with crowtiler's own filter: a uniform scene exactly,
 * values in [0, 1], the same image on 1 and 2 threads, and the motion of
 * the scene honoured. */
static void test_tiler_generic(void **state)
{
    (void)state;
    const char *specs[] = {"crowtiler", "crowtiler:hidden=scan", "crowtiler:area=exact",
                           "crowtiler:area=exact,hidden=scan", "crowtiler:hidden=zbuffer"};
    aa_rgb colour = {{0.3, 0.5, 0.7}};
    aa_scene *u = aa_scene_new(colour);
    assert_int_equal(aa_scene_finish(u), AA_OK);
    aa_scene *crow = scenes_pattern("crow");
    /* 64 pixels: the displacement t v / 64 and its placing are exact in
     * binary, so the two placed scenes are the same bit for bit */
    aa_scene *moved = aa_scene_transform(crow, 1.0, 1.0, 2.0 * 0.375 / 64, 2.0 * -0.25 / 64);
    assert_non_null(moved);
    for (int k = 0; k < 5; k++) {
        aa_image a, b, c;
        assert_int_equal(render(specs[k], u, "tent:r=1", 41, 29, 1, 0, 0, 0, &a), AA_OK);
        for (int p = 0; p < 41 * 29 * 3; p++)
            if (a.v[p] != colour.c[p % 3])
                fail_msg("%s: uniform scene value %.17g", specs[k], a.v[p]);
        aa_image_free(&a);
        assert_int_equal(render(specs[k], crow, "tent:r=1", 41, 29, 1, 0, 0, 0, &a), AA_OK);
        assert_int_equal(render(specs[k], crow, "tent:r=1", 41, 29, 2, 0, 0, 0, &b), AA_OK);
        for (int p = 0; p < 41 * 29 * 3; p++)
            assert_true(a.v[p] >= 0.0 && a.v[p] <= 1.0);
        if (memcmp(a.v, b.v, sizeof(double) * 41 * 29 * 3))
            fail_msg("%s: 1 and 2 threads give different images", specs[k]);
        aa_image_free(&a);
        aa_image_free(&b);
        assert_int_equal(render(specs[k], crow, "tent:r=1", 64, 64, 2, 2.0, 0.375, -0.25, &a),
                         AA_OK);
        assert_int_equal(render(specs[k], moved, "tent:r=1", 64, 64, 2, 2.0, 0, 0, &c), AA_OK);
        if (memcmp(a.v, c.v, sizeof(double) * 64 * 64 * 3))
            fail_msg("%s: the moving scene's image is not the moved scene's", specs[k]);
        aa_image_free(&a);
        aa_image_free(&c);
    }
    aa_scene_free(moved);
    aa_scene_free(crow);
    aa_scene_free(u);
}

static void refused(const char *method, const char *filter, const char *words)
{
    aa_filter f;
    aa_spec spec;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    int st = aa_method_parse(method, &f, &spec);
    if (st != AA_EINVAL || !strstr(aa_last_error(), words))
        fail_msg("%s -f %s: status %d, \"%s\" (expected %d and \"%s\")", method, filter, st,
                 aa_last_error(), AA_EINVAL, words);
}

static void test_tiler_refusals(void **state)
{
    (void)state;
    refused("crowtiler", "box", "tent:r=1");
    refused("crowtiler", "gauss", "tent:r=1");
    refused("crowtiler", "tent:r=0.5", "tent:r=1");
    refused("crowtiler", "tent:r=2", "tent:r=1");
    refused("crowtiler", "cone", "tent:r=1");
    refused("crowtiler:area=exact,res=8", "tent:r=1", "leave res out");
    refused("crowtiler:hidden=depth", "tent:r=1", "hidden");
    refused("crowtable:form=exact", "tent:r=1", "form");
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_cone_abutting_layers),
             cmocka_unit_test(test_cone_hidden_adds_nothing),
             cmocka_unit_test(test_cone_patterns),
             cmocka_unit_test(test_crowtable_one_rectangle),
             cmocka_unit_test(test_crowtable_layers),
             cmocka_unit_test(test_tiler_exact),
             cmocka_unit_test(test_tiler_priority),
             cmocka_unit_test(test_tiler_zbuffer),
             cmocka_unit_test(test_tiler_tables),
             cmocka_unit_test(test_tiler_generic),
             cmocka_unit_test(test_tiler_refusals))
