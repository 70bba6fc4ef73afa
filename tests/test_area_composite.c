/*
 * test_area_composite.c: the exact area method (algorithms/area.c) on
 * scenes that composite: translucent layers, groups of opacity, clip paths
 * and clips clipped in turn, against answers derived here.
 *
 * The known answers.  The picture is constant on each region of the
 * arrangement, so the box filter's value at a pixel is the sum over the
 * regions of (the region's area inside the pixel) x (its colour), the
 * colour being the composite decoded to linear light (patterns/README.md:
 * compositing in sRGB-encoded values, source over, W3C Compositing and
 * Blending Level 1; a group as SVG 2's `opacity`: its content composited
 * over transparent, then times the opacity, then source over; the
 * reference filters in linear light).  Each composite colour is worked by
 * hand in the comment beside its scene, in encoded values, and decoded by
 * the sRGB formula written out here (IEC 61966-2-1).  The areas:
 *  - a rectangle's inside a pixel, the product of the overlaps of two
 *    intervals; two rectangles' overlap is a rectangle;
 *  - a disk's inside a rectangle, from the area of the disk of radius r
 *    about the origin in the quadrant {x <= X, y <= Y}, in closed form
 *    (quad below, from the integral of the chord length with
 *    G(x) = (x sqrt(r^2 - x^2) + r^2 asin(x/r))/2, the integral of
 *    sqrt(r^2 - x^2)), by inclusion and exclusion of four quadrants;
 *  - the whole disk cut by a line at distance d from its centre, its area
 *    less the circular segment r^2 acos(d/r) - d sqrt(r^2 - d^2).
 * Every pixel must be within 1e-12 of the closed form (measured at most a
 * few 1e-15), under both of area's integrators (catmull, bands), and the
 * image's sum within 1e-9 of the region's area times its colour.
 *
 * Besides: 1200 translucent stripes of their own colours, two covering
 * each point, more winding states in a row than area's colour cache holds
 * (AR_CACHE_ENTRIES): equal to the exact reference within 1e-12 and the
 * same bit for bit on one thread and on three.
 */
#include "bench.h"
#include "core.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define N 48 /* the view: N x N pixels; the scenes are given in pixels / N */

/* sRGB's decoding and encoding (IEC 61966-2-1), written out here. */
static double dec(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static aa_rgb rgb_dec(double r, double g, double b)
{
    return (aa_rgb){{dec(r), dec(g), dec(b)}};
}

/* The overlap of [a0, a1] and [b0, b1]. */
static double overlap(double a0, double a1, double b0, double b1)
{
    double lo = a0 > b0 ? a0 : b0, hi = a1 < b1 ? a1 : b1;
    return hi > lo ? hi - lo : 0.0;
}

/* A rectangle in pixels. */
typedef struct rect {
    double x0, y0, x1, y1;
} rect;

static double rect_in_pixel(const rect *r, int i, int j)
{
    return overlap(r->x0, r->x1, i, i + 1.0) * overlap(r->y0, r->y1, j, j + 1.0);
}

static rect rect_and(const rect *a, const rect *b)
{
    return (rect){fmax(a->x0, b->x0), fmax(a->y0, b->y0), fmin(a->x1, b->x1),
                  fmin(a->y1, b->y1)};
}

/* A rectangle as a path of the current layer, in pattern units. */
static void rect_path(aa_scene *s, const rect *r)
{
    assert_int_equal(aa_scene_move_to(s, r->x0 / N, r->y0 / N), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r->x1 / N, r->y0 / N), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r->x1 / N, r->y1 / N), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r->x0 / N, r->y1 / N), AA_OK);
}

/* A circle as a path of the current layer (centre and radius in pixels). */
static void circle_path(aa_scene *s, double cx, double cy, double r)
{
    assert_int_equal(aa_scene_move_to(s, (cx + r) / N, cy / N), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx / N, cy / N, r / N, 0, 0, r / N, 0, 2 * M_PI,
                                     (cx + r) / N, cy / N),
                     AA_OK);
}

/* The integral of sqrt(r^2 - x^2) from 0 to x, |x| <= r. */
static long double G(long double r, long double x)
{
    return 0.5L * (x * sqrtl(r * r - x * x) + r * r * asinl(x / r));
}

/* The area of the disk of radius r about the origin in {x <= X, y <= Y}:
 * the integral over x of the part of the chord [-s, s] (s = sqrt(r^2 -
 * x^2)) below Y.  For Y >= 0 the part is 2s where s <= Y (|x| >= q =
 * sqrt(r^2 - Y^2)) and s + Y where |x| < q; for Y < 0 it is s + Y where
 * |x| < q and nothing elsewhere. */
static long double quad(long double r, long double X, long double Y)
{
    if (X <= -r || Y <= -r)
        return 0.0L;
    X = X < r ? X : r;
    long double q = Y < r ? sqrtl(r * r - Y * Y) : 0.0L;
    long double c = X < -q ? -q : (X > q ? q : X);
    if (Y < 0.0L)
        return G(r, c) - G(r, -q) + Y * (c + q);
    long double a = (G(r, X) - G(r, -r)) + (G(r, X < -q ? X : -q) - G(r, -r)) + Y * (c + q);
    if (X > q)
        a += G(r, X) - G(r, q);
    return a;
}

/* The area of the disk of radius r about (cx, cy) inside rectangle b. */
static double disk_in_rect(double cx, double cy, double r, const rect *b)
{
    if (!(b->x1 > b->x0 && b->y1 > b->y0))
        return 0.0;
    long double x0 = b->x0 - cx, x1 = b->x1 - cx, y0 = b->y0 - cy, y1 = b->y1 - cy;
    return (double)(quad(r, x1, y1) - quad(r, x0, y1) - quad(r, x1, y0) + quad(r, x0, y0));
}

/* The expected value of pixel (i, j), channel ch. */
typedef double (*expect_fn)(const void *ctx, int i, int j, int ch);

/* area (each integrator) against the closed form at every pixel, and its
 * sum against `sum` per channel (NULL: not checked). */
static void check(const char *what, const aa_scene *s, expect_fn f, const void *ctx,
                  const double *sum)
{
    static const char *const methods[] = {"area", "area:integrator=bands"};
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; m++) {
        aa_image img;
        support_render_must(methods[m], s, &(support_view){.w = N, .h = N}, &img, NULL);
        double worst = 0.0, total[3] = {0, 0, 0};
        int wi = 0, wj = 0, wc = 0;
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++)
                for (int ch = 0; ch < 3; ch++) {
                    double v = aa_pixel(&img, i, j)[ch], d = fabs(v - f(ctx, i, j, ch));
                    total[ch] += v;
                    if (!(d <= worst))
                        worst = d, wi = i, wj = j, wc = ch;
                }
        printf("# %s, %s: largest difference from the closed form %.3g (pixel %d %d "
               "channel %d)",
               what, methods[m], worst, wi, wj, wc);
        if (sum)
            printf("; sums less the areas times the colours %.3g %.3g %.3g", total[0] - sum[0],
                   total[1] - sum[1], total[2] - sum[2]);
        printf("\n");
        if (!(worst <= 1e-12))
            fail_msg("%s, %s: pixel (%d, %d) channel %d is %.17g, the closed form %.17g", what,
                     methods[m], wi, wj, wc, aa_pixel(&img, wi, wj)[wc], f(ctx, wi, wj, wc));
        for (int ch = 0; sum && ch < 3; ch++)
            if (!(fabs(total[ch] - sum[ch]) <= 1e-9))
                fail_msg("%s, %s: channel %d sums to %.17g, the closed form %.17g", what,
                         methods[m], ch, total[ch], sum[ch]);
        aa_image_free(&img);
    }
}

/* ------------------------------------------------------------------------
 * Translucent layers
 * ------------------------------------------------------------------------ */

/* Regions of rectangles: a background and up to two rectangles, each
 * region's colour given (a only, b only, both, neither). */
typedef struct two_rects {
    rect a, b;
    aa_rgb ca, cb, cab, bg;
} two_rects;

static double two_rects_at(const void *ctx, int i, int j, int ch)
{
    const two_rects *t = ctx;
    rect ab = rect_and(&t->a, &t->b);
    double A = rect_in_pixel(&t->a, i, j), B = rect_in_pixel(&t->b, i, j);
    double AB = rect_in_pixel(&ab, i, j);
    return (A - AB) * t->ca.c[ch] + (B - AB) * t->cb.c[ch] + AB * t->cab.c[ch] +
           (1.0 - A - B + AB) * t->bg.c[ch];
}

static void two_rects_sum(const two_rects *t, double *sum)
{
    rect ab = rect_and(&t->a, &t->b);
    double A = (t->a.x1 - t->a.x0) * (t->a.y1 - t->a.y0);
    double B = (t->b.x1 - t->b.x0) * (t->b.y1 - t->b.y0);
    double AB = ab.x1 > ab.x0 && ab.y1 > ab.y0 ? (ab.x1 - ab.x0) * (ab.y1 - ab.y0) : 0.0;
    for (int ch = 0; ch < 3; ch++)
        sum[ch] = (A - AB) * t->ca.c[ch] + (B - AB) * t->cb.c[ch] + AB * t->cab.c[ch] +
                  ((double)N * N - A - B + AB) * t->bg.c[ch];
}

static const rect RA = {5.3, 7.1, 30.7, 33.9}, RB = {17.2, 3.4, 41.6, 26.55};

/* A white rectangle of alpha 1/2 over black: encoded 1/2 over 0 is 1/2,
 * so the rectangle is dec(1/2) (0.214041...) and its box integral its
 * area times that.  A grey scene (area computes one channel). */
static void test_half_opacity(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    rect_path(s, &RA);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_false(aa_scene_is_opaque(s));
    const rect none = {0, 0, 0, 0};
    const double h = dec(0.5);
    two_rects t = {RA, none, {{h, h, h}}, black, {{h, h, h}}, black};
    double sum[3];
    two_rects_sum(&t, sum);
    check("white at 1/2 over black", s, two_rects_at, &t, sum);
    aa_scene_free(s);
}

/* Red (1, 0, 0) at alpha 1/2 in front of blue (0, 0, 1) at alpha 1/2, over
 * the background whose encoded value is 0.4 in every channel.  Encoded:
 *   blue alone: 0.5 (0, 0, 1) + 0.5 (0.4, 0.4, 0.4) = (0.2, 0.2, 0.7);
 *   red alone:  0.5 (1, 0, 0) + 0.5 (0.4, 0.4, 0.4) = (0.7, 0.2, 0.2);
 *   both: red over blue alone, 0.5 (1, 0, 0) + 0.5 (0.2, 0.2, 0.7)
 *         = (0.6, 0.1, 0.35);
 * each decoded. */
static void test_two_translucent(void **state)
{
    (void)state;
    const aa_rgb red = {{1, 0, 0}}, blue = {{0, 0, 1}};
    const aa_rgb bg = rgb_dec(0.4, 0.4, 0.4);
    aa_scene *s = aa_scene_new(bg);
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    rect_path(s, &RA);
    assert_int_equal(aa_scene_layer(s, blue, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    rect_path(s, &RB);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    two_rects t = {RA, RB, rgb_dec(0.7, 0.2, 0.2), rgb_dec(0.2, 0.2, 0.7),
                   rgb_dec(0.6, 0.1, 0.35), bg};
    double sum[3];
    two_rects_sum(&t, sum);
    check("red and blue at 1/2", s, two_rects_at, &t, sum);
    aa_scene_free(s);
}

/* ------------------------------------------------------------------------
 * Groups of opacity
 * ------------------------------------------------------------------------ */

/* A group of opacity 1/2 holding opaque red in front of opaque green, over
 * white.  The group's content is red where red is, green where green alone
 * is, so encoded:
 *   red (also where both are): 0.5 (1, 0, 0) + 0.5 (1, 1, 1) = (1, 0.5, 0.5);
 *   green alone: 0.5 (0, 1, 0) + 0.5 (1, 1, 1) = (0.5, 1, 0.5).
 * The same layers each at alpha 1/2 would show red over green in the
 * overlap, 0.5 (1, 0, 0) + 0.5 (0.5, 1, 0.5) = (0.75, 0.5, 0.25): a group
 * is not its children's opacity.
 * Then the same group with red at alpha 1/2: its content where both are is
 * 0.5 (1, 0, 0) + 0.5 (0, 1, 0) = (0.5, 0.5, 0), opaque, so
 * 0.5 (0.5, 0.5, 0) + 0.5 (1, 1, 1) = (0.75, 0.75, 0.5); where red alone
 * is, the content is red premultiplied by 1/2 of alpha 1/2, and the group
 * times 1/2 is (0.25, 0, 0) of alpha 1/4 over white:
 * (0.25 + 0.75, 0.75, 0.75) = (1, 0.75, 0.75). */
static void test_group(void **state)
{
    (void)state;
    const aa_rgb white = {{1, 1, 1}}, red = {{1, 0, 0}}, green = {{0, 1, 0}};
    for (int half = 0; half < 2; half++) {
        aa_scene *s = aa_scene_new(white);
        assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
        assert_int_equal(aa_scene_layer(s, red, AA_FILL_NONZERO), AA_OK);
        if (half)
            assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
        rect_path(s, &RA);
        assert_int_equal(aa_scene_layer(s, green, AA_FILL_NONZERO), AA_OK);
        rect_path(s, &RB);
        assert_int_equal(aa_scene_group_end(s), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        two_rects t = {RA, RB, rgb_dec(1, 0.5, 0.5), rgb_dec(0.5, 1, 0.5),
                       rgb_dec(1, 0.5, 0.5), white};
        if (half)
            t.ca = rgb_dec(1, 0.75, 0.75), t.cab = rgb_dec(0.75, 0.75, 0.5);
        double sum[3];
        two_rects_sum(&t, sum);
        check(half ? "a group of 1/2, red at 1/2 over green" : "a group of 1/2, red over green",
              s, two_rects_at, &t, sum);
        aa_scene_free(s);
    }
}

/* Groups of 1/2 nested, holding white over black: the inner group gives
 * white at 1/2 over transparent, (1/2 premultiplied, alpha 1/2), the outer
 * halves it again: 1/4 over black, encoded 0.25 in the rectangle; beside
 * it, a white rectangle of alpha 1/2 outside the groups, behind them, so
 * where both are: 0.5 over black is 0.5, then 0.25 + 0.75 x 0.5 = 0.625. */
static void test_nested_groups(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
    assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    rect_path(s, &RA);
    assert_int_equal(aa_scene_group_end(s), AA_OK);
    assert_int_equal(aa_scene_group_end(s), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    rect_path(s, &RB);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    two_rects t = {RA, RB, rgb_dec(0.25, 0.25, 0.25), rgb_dec(0.5, 0.5, 0.5),
                   rgb_dec(0.625, 0.625, 0.625), black};
    double sum[3];
    two_rects_sum(&t, sum);
    check("nested groups of 1/2", s, two_rects_at, &t, sum);
    aa_scene_free(s);
}

/* ------------------------------------------------------------------------
 * Clips
 * ------------------------------------------------------------------------ */

/* A disk (centre, radius, in pixels) of colour c over black, seen through
 * the rectangle k (the clip), elsewhere black. */
typedef struct clipped_disk {
    double cx, cy, r;
    rect k;
    aa_rgb c;
} clipped_disk;

static double clipped_disk_at(const void *ctx, int i, int j, int ch)
{
    const clipped_disk *d = ctx;
    rect px = {i, j, i + 1.0, j + 1.0}, b = rect_and(&px, &d->k);
    return disk_in_rect(d->cx, d->cy, d->r, &b) * d->c.c[ch];
}

/* A white disk of radius 15 px at (24, 24) gated by a clip of one member,
 * the rectangle x <= 31 (all of the view's height): the disk less the
 * circular segment beyond the line at d = 7 from its centre,
 * pi r^2 - (r^2 acos(d/r) - d sqrt(r^2 - d^2)). */
static void test_clipped_disk(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    const clipped_disk d = {24, 24, 15, {0, 0, 31, N}, white};
    aa_scene *s = aa_scene_new(black);
    int clip;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, &d.k);
    assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
    circle_path(s, d.cx, d.cy, d.r);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const double r = d.r, dd = 7.0;
    const double area = M_PI * r * r - (r * r * acos(dd / r) - dd * sqrt(r * r - dd * dd));
    const double sum[3] = {area, area, area};
    check("a disk clipped by a rectangle", s, clipped_disk_at, &d, sum);
    aa_scene_free(s);
}

/* A clip clipped in turn: the disk of radius 15 px at (24, 24), white at
 * alpha 1/2 over black (encoded 1/2, dec(1/2)), gated by clip A, the
 * rectangle x <= 29.25, itself within clip B, the rectangle y <= 27.5: the
 * disk in the quadrant {x <= 29.25, y <= 27.5}.  The same picture with
 * A's member gated by B instead of A defined within B (a member's own
 * clip), and with B an even-odd member (a rectangle drawn twice over a
 * larger one: wound twice, outside B, where once, inside). */
static void test_nested_clips(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    const double h = dec(0.5);
    const clipped_disk d = {24, 24, 15, {0, 0, 29.25, 27.5}, {{h, h, h}}};
    const rect ka = {0, 0, 29.25, N}, kb = {0, 0, N, 27.5}, below = {0, 27.5, N, N};
    const rect all = {0, 0, N, N};
    for (int way = 0; way < 3; way++) {
        aa_scene *s = aa_scene_new(black);
        int a, b;
        assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
        assert_int_equal(aa_scene_clip_layer(s, way == 2 ? AA_FILL_EVENODD : AA_FILL_NONZERO),
                         AA_OK);
        if (way == 2) {
            /* the view once and the part below B three times: wound 4
             * times below (even: outside), once above (inside) */
            rect_path(s, &all);
            for (int k = 0; k < 3; k++)
                rect_path(s, &below);
        } else {
            rect_path(s, &kb);
        }
        assert_int_equal(aa_scene_clip_end(s, &b), AA_OK);
        assert_int_equal(aa_scene_clip_begin(s, way == 0 ? b : -1), AA_OK);
        assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
        if (way)
            assert_int_equal(aa_scene_set_clip(s, b), AA_OK);
        rect_path(s, &ka);
        assert_int_equal(aa_scene_clip_end(s, &a), AA_OK);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
        assert_int_equal(aa_scene_set_clip(s, a), AA_OK);
        circle_path(s, d.cx, d.cy, d.r);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        /* the whole picture's integral: the disk in the quadrant, from the
         * same closed form over the view */
        const double area = disk_in_rect(d.cx, d.cy, d.r, &d.k);
        const double sum[3] = {area * h, area * h, area * h};
        static const char *const what[] = {"a clip within a clip", "a clip whose member is clipped",
                                           "a clip whose member is clipped by an even-odd clip"};
        check(what[way], s, clipped_disk_at, &d, sum);
        aa_scene_free(s);
    }
}

/* ------------------------------------------------------------------------
 * Many winding states
 * ------------------------------------------------------------------------ */

/* 1200 stripes, each its own colour at alpha 0.6, stripe k covering
 * [k w, (k + 2) w] x [0, 1] (two cover each point, every pair a state of
 * its own: more than the cache's 1024 entries in one row), against the
 * exact reference within 1e-12, and bit for bit on one and three threads. */
static void test_many_states(void **state)
{
    (void)state;
    const int n = 1200, w = 64, h = 3;
    const aa_rgb bg = {{0.1, 0.2, 0.3}};
    aa_scene *s = aa_scene_new(bg);
    for (int k = 0; k < n; k++) {
        aa_rgb c = {{(k % 7) / 6.0, (k % 11) / 10.0, (k % 13) / 12.0}};
        assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_set_alpha(s, 0.6), AA_OK);
        double x0 = (double)k / (n + 1), x1 = (double)(k + 2) / (n + 1);
        assert_int_equal(aa_scene_move_to(s, x0, 0.1), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x1, 0.15), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x1, 0.9), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x0, 0.85), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref, one, three;
    const support_view v1 = {.w = w, .h = h, .threads = 1}, v3 = {.w = w, .h = h, .threads = 3};
    support_reference(s, &v1, &ref, NULL, NULL);
    support_render_must("area", s, &v1, &one, NULL);
    support_render_must("area", s, &v3, &three, NULL);
    int wi, wj;
    double d = support_max_diff(&one, &ref, &wi, &wj);
    printf("# %d translucent stripes: area against the reference %.3g (pixel %d %d)\n", n, d, wi,
           wj);
    if (!(d <= 1e-12))
        fail_msg("stripes: area differs from the reference by %.3g at (%d, %d)", d, wi, wj);
    assert_true(support_same_image(&one, &three));
    aa_image_free(&ref);
    aa_image_free(&one);
    aa_image_free(&three);
    aa_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_opacity), cmocka_unit_test(test_two_translucent),
        cmocka_unit_test(test_group),        cmocka_unit_test(test_nested_groups),
        cmocka_unit_test(test_clipped_disk), cmocka_unit_test(test_nested_clips),
        cmocka_unit_test(test_many_states),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
