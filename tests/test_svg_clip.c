/*
 * test_svg_clip.c: clip paths, in the scene model (aa_scene_clip_begin)
 * and read by the pattern svg (clipPath, clip-path), through the scene and
 * its box reference, against closed forms.
 *
 * The box reference of a white shape over black is at each pixel the area
 * of the shape inside it, so the image's sum is the area of what is drawn
 * (within the view): each clipped picture's area is derived by hand in a
 * comment beside it (a half disk, a lens of two disks, the cells of a
 * self-overlapping path under either rule, a strip of an ellipse; the
 * basic shapes of clip-path by pi r^2, the rounded rectangle's closed form
 * and the shoelace formula), never taken from the code under test; the
 * root's transform by the pixels of a rect moved, worked by hand.  Where a
 * clip is translucent paint, the integral is the area times the one colour
 * it has, SVG 2's group opacity over black worked in sRGB-encoded values.  The exact method `area`
 * (algorithms/area.c) is run on every such scene under both its
 * integrators: within 1e-12 of the reference at every pixel, so its sums
 * meet the same closed forms.
 */
#include "bench.h"
#include "core.h"
#include "path.h"
#include "patterns.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_sf_ellint.h>

#define N 64 /* the view: N x N pixels */

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "svgclip");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* The root's attributes but its size (width and height: N unless given
 * here), in svg_spec's documents. */
static const char *root_attrs = "";

/* `body` inside a root <svg> of N x N pixels (or as root_attrs says),
 * white shapes, written to a file of the temporary folder; its pattern
 * spec into spec. */
static void svg_spec(const char *name, const char *body, char *spec, size_t len)
{
    char path[4200], doc[8192], size[64] = "";
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    if (!strstr(root_attrs, "width="))
        snprintf(size, sizeof size, " width=\"%d\" height=\"%d\"", N, N);
    int n = snprintf(doc, sizeof doc,
                     "<svg xmlns=\"http://www.w3.org/2000/svg\"%s%s "
                     "fill=\"white\">\n%s\n</svg>\n",
                     size, root_attrs, body);
    assert_true(n > 0 && (size_t)n < sizeof doc);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, len, "svg:file=%s", path);
}

/* The sum of the box reference of `body` (channel 0) over the view; and
 * `area` (each integrator) on it, within 1e-12 of the reference at every
 * pixel (area is exact under the box; the reference's bound is 1e-12). */
static double reference_sum(const char *name, const char *body)
{
    char spec[4400];
    svg_spec(name, body, spec, sizeof spec);
    aa_image img;
    const support_view v = {.w = N, .h = N};
    support_pattern_reference(spec, &v, &img, NULL, NULL);
    double sum = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            sum += aa_pixel(&img, i, j)[0];
    aa_spec ps;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse(spec, &ps), AA_OK);
    if (aa_pattern_scene_at(&ps, N, N, &sc) != AA_OK)
        fail_msg("%s: %s", name, aa_last_error());
    static const char *const exact[] = {"area", "area:integrator=bands"};
    for (size_t m = 0; m < sizeof exact / sizeof exact[0]; m++) {
        aa_image out;
        int wi, wj;
        support_render_must(exact[m], sc, &v, &out, NULL);
        double d = support_max_diff(&out, &img, &wi, &wj);
        printf("# %s: %s against the reference %.2g\n", name, exact[m], d);
        if (!(d <= 1e-12))
            fail_msg("%s: %s differs from the reference by %.3g at (%d, %d)", name, exact[m], d,
                     wi, wj);
        aa_image_free(&out);
    }
    aa_scene_free(sc);
    aa_image_free(&img);
    return sum;
}

static void check_area(const char *name, const char *body, double area)
{
    double sum = reference_sum(name, body);
    printf("# %s: area %.15g, reference sum %.15g, difference %.2g\n", name, area, sum,
           sum - area);
    if (!(fabs(sum - area) <= 1e-9))
        fail_msg("%s: the reference sums to %.17g, the area is %.17g", name, sum, area);
}

/* The area of the lens where two disks of radius r, centres d apart,
 * overlap: twice the circular segment cut by the chord at d/2 from each
 * centre, 2 (r^2 acos(d / 2r) - (d / 2) sqrt(r^2 - d^2 / 4)). */
static double lens(double r, double d)
{
    return 2 * r * r * acos(d / (2 * r)) - d * sqrt(r * r - d * d / 4);
}

/* sRGB's decoding (IEC 61966-2-1), written out here. */
static double dec(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

/* ---- the scene model ---- */

/* A unit square painted white, gated by a clip of two members: the
 * left half [0, 1/2] x [0, 1] (nonzero) and the disk of radius 1/4 at
 * (3/4, 1/2) itself clipped by the top half y < 1/2; the whole clip within
 * a clip of the square [1/8, 7/8]^2.  Inside means inside the square
 * [1/8, 7/8]^2 and (x < 1/2, or in the disk's upper half): checked at
 * points, then the picture's area: the square's left part [1/8, 1/2] x
 * [1/8, 7/8] is 3/8 x 3/4, and the disk's upper half pi / 32 lies inside
 * [1/8, 7/8]^2 (its extent is [1/2, 1] x [1/4, 1/2], cut at x = 7/8: the
 * part beyond x = 7/8 is a circular segment of the disk at distance 1/8
 * from its centre, r^2 acos(1/2) - (1/8) sqrt(r^2 - 1/64) for r = 1/4,
 * half of it above y = 1/2). */
static void test_scene_model(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    aa_scene *s = aa_scene_new(black);
    int outer, top, clip;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.125, 0.125), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.875, 0.125), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.875, 0.875), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.125, 0.875), AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &outer), AA_OK);
    assert_int_equal(outer, 0);
    /* a painting layer inside a clip's definition is refused */
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "inside the definition of clip 1"));
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1, 0.5), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0, 0.5), AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &top), AA_OK);
    assert_int_equal(top, 1);
    /* a clip within a clip not yet ended is refused */
    assert_int_equal(aa_scene_clip_begin(s, 2), AA_EINVAL);
    assert_int_equal(aa_scene_clip_begin(s, outer), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.5, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.5, 1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0, 1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_EVENODD), AA_OK);
    assert_int_equal(aa_scene_set_clip(s, 2), AA_EINVAL); /* itself, not ended */
    assert_int_equal(aa_scene_set_clip(s, top), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 1, 0.5), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, 0.75, 0.5, 0.25, 0, 0, 0.25, 0, 2 * M_PI, 1, 0.5),
                     AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
    assert_int_equal(clip, 2);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1, 1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0, 1), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_is_clipped(s), 1);
    assert_int_equal(aa_scene_is_opaque(s), 0);
    assert_int_equal(aa_scene_clip_count(s), 3);
    assert_int_equal(aa_scene_layer_count(s), 5);
    assert_int_equal(aa_scene_layer_clip(s, 4), clip);
    assert_int_equal(aa_scene_layer_clip_member(s, 4), -1);
    assert_int_equal(aa_scene_layer_clip_member(s, 3), clip);
    assert_int_equal(aa_scene_clip_within(s, clip), outer);
    int first;
    assert_int_equal(aa_scene_clip_members(s, clip, &first), 2);
    assert_int_equal(first, 2);
    static const struct {
        double x, y;
        int in;
    } at[] = {{0.3, 0.3, 1},  {0.3, 0.8, 1},  {0.1, 0.3, 0},  {0.3, 0.9, 0},
              {0.75, 0.4, 1}, {0.75, 0.6, 0}, {0.6, 0.2, 0},  {0.9, 0.45, 0},
              {0.85, 0.45, 1}, {0.55, 0.45, 1}};
    for (size_t k = 0; k < sizeof at / sizeof at[0]; k++) {
        aa_rgb c = aa_scene_colour_at(s, at[k].x, at[k].y);
        if (c.c[0] != (at[k].in ? 1.0 : 0.0))
            fail_msg("(%g, %g): %g, not %d", at[k].x, at[k].y, c.c[0], at[k].in);
    }
    /* the reference's sum at 64 x 64 over 64^2 is the area */
    const double r = 0.25, seg = r * r * acos(0.5) - 0.125 * sqrt(r * r - 1.0 / 64);
    const double area = 0.375 * 0.75 + (M_PI * r * r - seg) / 2;
    aa_image img;
    support_reference(s, &(support_view){.w = N, .h = N}, &img, NULL, NULL);
    double sum = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            sum += aa_pixel(&img, i, j)[0];
    printf("# scene model: area %.15g, reference sum %.15g\n", area, sum / (N * N));
    if (!(fabs(sum / (N * N) - area) <= 1e-12))
        fail_msg("the reference sums to %.17g, the area is %.17g", sum / (N * N), area);
    /* transform and place keep the clips; the hash sees them */
    aa_scene *t = aa_scene_transform(s, 2, 2, 0, 0);
    assert_non_null(t);
    assert_int_equal(aa_scene_clip_count(t), 3);
    assert_int_equal(aa_scene_colour_at(t, 1.5, 0.8).c[0], 1.0);
    assert_int_equal(aa_scene_colour_at(t, 1.5, 1.2).c[0], 0.0);
    aa_scene_free(t);
    aa_scene *u = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(u, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(u, 0, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(u, 1, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(u, 1, 1), AA_OK);
    assert_int_equal(aa_scene_line_to(u, 0, 1), AA_OK);
    assert_int_equal(aa_scene_finish(u), AA_OK);
    assert_true(aa_scene_hash(u) != aa_scene_hash(s));
    aa_scene_free(u);
    /* the methods that colour points through the scene take it, and so
     * does `area` (the scene's composite of each region), exactly: within
     * 1e-12 of the reference at every pixel */
    aa_image out;
    const support_view v = {.w = N, .h = N};
    support_render_must("supersample:n=4", s, &v, &out, NULL);
    aa_image_free(&out);
    support_render_must("area", s, &v, &out, NULL);
    double d = support_max_diff(&out, &img, NULL, NULL);
    printf("# scene model: area against the reference %.2g\n", d);
    if (!(d <= 1e-12))
        fail_msg("area differs from the reference by %.3g", d);
    aa_image_free(&out);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* Clipping to the unit square puts a front layer before the clips'
 * members: the clips must still gate what they gated.  A white square
 * [1/2, 3/2] x [0, 1] gated by the disk of radius 1/2 at (1, 1/2) (both
 * reaching outside the unit square): white inside the disk left of x = 1,
 * black right of it (outside the square) and outside the disk. */
static void test_clip_unit(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    aa_scene *s = aa_scene_new(black);
    int clip;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 1.5, 0.5), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, 1, 0.5, 0.5, 0, 0, 0.5, 0, 2 * M_PI, 1.5, 0.5), AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.5, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1.5, 0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1.5, 1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.5, 1), AA_OK);
    assert_int_equal(aa_scene_clip_unit(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_layer_count(s), 3);
    assert_int_equal(aa_scene_layer_clip_member(s, 1), clip);
    assert_int_equal(aa_scene_layer_clip(s, 2), clip);
    assert_true(aa_scene_colour_at(s, 0.9, 0.5).c[0] == 1.0);
    assert_true(aa_scene_colour_at(s, 1.2, 0.5).c[0] == 0.0);
    assert_true(aa_scene_colour_at(s, 0.55, 0.1).c[0] == 0.0);
    aa_scene_free(s);
}

/* ---- the reader ---- */

/* A disk of radius 20 at (32, 32) clipped by the rectangle [0, 32] x
 * [0, 64], through the disk's centre: half the disk, 200 pi. */
static void test_half_disk(void **state)
{
    (void)state;
    check_area("half", "<clipPath id=\"c\"><rect width=\"32\" height=\"64\"/></clipPath>"
                       "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url(#c)\"/>",
               200 * M_PI);
    /* in <defs>, the reference quoted, the clipPath after its use */
    check_area("half-defs", "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url('#c')\"/>"
                            "<defs><clipPath id=\"c\"><rect width=\"32\" height=\"64\"/>"
                            "</clipPath></defs>",
               200 * M_PI);
}

/* clip-path on a nested <svg> and on a used <symbol>: in the user space
 * the element establishes (its viewBox's, here 24 units onto 48 px at
 * (8, 8): scale 2), within the viewport's own clip [8, 56]^2.  The clip
 * disk (20, 24) r 8 is (48, 56) r 16 in pixels: the viewport keeps its
 * upper half (y < 56) left of x = 56, a chord 8 from the centre, so the
 * half disk 128 pi less the upper half of the segment beyond the chord,
 * (r^2 acos(d / r) - d sqrt(r^2 - d^2)) / 2 = (256 pi / 3 - 8 sqrt(192))
 * / 2: 256 pi / 3 + 4 sqrt(192).  The symbol's disk (20, 12) r 8 is (48,
 * 32) r 16: the whole disk less that segment, 512 pi / 3 + 8 sqrt(192).
 * Were the clip taken in the parent's user space (librsvg), the first
 * would be the whole disk (20, 24) r 8, 64 pi, and the second the disk
 * (28, 20) r 8, 64 pi; were the viewport's clip dropped (Chromium, with
 * a clip-path on a nested svg), 256 pi - (256 pi / 3 - 8 sqrt(192)) for
 * the first. */
static void test_viewport_element(void **state)
{
    (void)state;
    check_area("nested-svg",
               "<clipPath id=\"v\"><circle cx=\"20\" cy=\"24\" r=\"8\"/></clipPath>"
               "<svg x=\"8\" y=\"8\" width=\"48\" height=\"48\" viewBox=\"0 0 24 24\" "
               "clip-path=\"url(#v)\"><rect x=\"-50\" y=\"-50\" width=\"200\" "
               "height=\"200\"/></svg>",
               256 * M_PI / 3 + 4 * sqrt(192));
    check_area("symbol",
               "<clipPath id=\"v\"><circle cx=\"20\" cy=\"12\" r=\"8\"/></clipPath>"
               "<symbol id=\"y\" viewBox=\"0 0 24 24\" clip-path=\"url(#v)\"><rect "
               "x=\"-50\" y=\"-50\" width=\"200\" height=\"200\"/></symbol>"
               "<use href=\"#y\" x=\"8\" y=\"8\" width=\"48\" height=\"48\"/>",
               512 * M_PI / 3 + 8 * sqrt(192));
}

/* A disk of radius 24 clipped by a concentric disk of radius 10: the
 * small disk, 100 pi.  The clipPath's child's fill, stroke and opacity do
 * not matter (fill="none" and a wide stroke: still the fill geometry). */
static void test_small_disk(void **state)
{
    (void)state;
    check_area("small", "<clipPath id=\"c\"><circle cx=\"32\" cy=\"32\" r=\"10\" fill=\"none\" "
                        "stroke=\"red\" stroke-width=\"8\" opacity=\"0\"/></clipPath>"
                        "<circle cx=\"32\" cy=\"32\" r=\"24\" clip-path=\"url(#c)\"/>",
               100 * M_PI);
}

/* The whole view clipped by one path of two squares drawn the same way
 * round, [8, 40]^2 and [24, 56]^2, overlapping in [24, 40]^2 (256): with
 * clip-rule evenodd the overlap is out, 1024 + 1024 - 2 x 256 = 1536; with
 * nonzero (winding 2 there) in, 1792.  clip-rule inherits into the
 * clipPath from its ancestors; fill-rule does not matter. */
static void test_clip_rule(void **state)
{
    (void)state;
    const char *path = "d=\"M8 8 H40 V40 H8 Z M24 24 H56 V56 H24 Z\"";
    char body[1024];
    snprintf(body, sizeof body,
             "<clipPath id=\"c\"><path clip-rule=\"evenodd\" fill-rule=\"nonzero\" %s/>"
             "</clipPath><rect width=\"64\" height=\"64\" clip-path=\"url(#c)\"/>",
             path);
    check_area("evenodd", body, 1536);
    snprintf(body, sizeof body,
             "<clipPath id=\"c\"><path fill-rule=\"evenodd\" %s/></clipPath>"
             "<rect width=\"64\" height=\"64\" clip-path=\"url(#c)\"/>",
             path);
    check_area("nonzero", body, 1792);
    snprintf(body, sizeof body,
             "<g clip-rule=\"evenodd\"><defs><clipPath id=\"c\"><path %s/></clipPath></defs></g>"
             "<rect width=\"64\" height=\"64\" clip-path=\"url(#c)\"/>",
             path);
    check_area("inherited", body, 1536);
}

/* <use> in a clipPath (CSS Masking 1: it must name a shape directly),
 * its regions apart so that the clip's area is their sum:
 *  - the 10 x 20 rect through translate(1.25 0.5) and x = 2, y = 1:
 *    [5.75, 15.75] x [4.75, 24.75], area 200;
 *  - the square ring [30, 50]^2 less [35, 45]^2 by the use's clip-rule
 *    evenodd, which the path inherits: 400 - 100 = 300;
 *  - the disk of radius 6 through translate(0 10) scale(1 0.5): an
 *    ellipse of semi-axes 6 and 3 about (20, 32.5), area 18 pi;
 *  - the rect [2, 12] x [40, 60] inside the use's own clip-path, the
 *    strip x < 7: [2, 7] x [40, 60], area 100;
 *  - a use of a <g>, a use of a use (indirect references, an error: no
 *    area) and a use of display none: nothing.
 * In all 600 + 18 pi. */
static void test_use_in_clip(void **state)
{
    (void)state;
    check_area("use in a clipPath",
               "<defs><rect id=\"u1\" x=\"2.5\" y=\"3.25\" width=\"10\" height=\"20\"/>"
               "<path id=\"u2\" d=\"M30 30 H50 V50 H30 Z M35 35 H45 V45 H35 Z\"/>"
               "<circle id=\"u3\" cx=\"20\" cy=\"45\" r=\"6\"/>"
               "<rect id=\"u6\" x=\"2\" y=\"40\" width=\"10\" height=\"20\"/>"
               "<g id=\"u4\"><rect x=\"52\" y=\"2\" width=\"10\" height=\"10\"/></g>"
               "<use id=\"u5\" href=\"#u1\" x=\"40\"/></defs>"
               "<clipPath id=\"h\"><rect width=\"7\" height=\"64\"/></clipPath>"
               "<clipPath id=\"c\"><use href=\"#u1\" x=\"2\" y=\"1\" "
               "transform=\"translate(1.25 0.5)\"/><use href=\"#u2\" clip-rule=\"evenodd\"/>"
               "<use href=\"#u3\" transform=\"translate(0 10) scale(1 0.5)\"/>"
               "<use href=\"#u6\" clip-path=\"url(#h)\"/><use href=\"#u4\"/>"
               "<use href=\"#u5\"/><use href=\"#u1\" x=\"30\" display=\"none\"/></clipPath>"
               "<rect width=\"64\" height=\"64\" clip-path=\"url(#c)\"/>",
               600 + 18 * M_PI);
}

/* clipPathUnits="objectBoundingBox" on an ellipse of semi-axes a = 24,
 * b = 12 at (32, 32) moved by translate(2 4) (its box in its user space:
 * [8, 56] x [20, 44]): the box's middle half across, x in [0.25, 0.75] of
 * it, is the strip |x - cx| <= c = 12 of the ellipse, of area
 * int_{-c}^{c} 2 b sqrt(1 - x^2 / a^2) dx = 2 b (c sqrt(1 - c^2 / a^2) +
 * a asin(c / a)) = 24 (6 sqrt 3 + 4 pi).  Then a cubic's box is its
 * curve's, not its control points': M 8 40 C 8 8, 56 8, 56 40 Z reaches
 * up to y(1/2) = 40/8 + 3 x 8 x 3/8 ... = 5 + 3 + 3 + 5 = 16 (its controls
 * to 8), so its box is [8, 56] x [16, 40], and the box's upper half by
 * objectBoundingBox is y < 28 in user units: the same picture as that
 * rectangle by userSpaceOnUse. */
static void test_bounding_box(void **state)
{
    (void)state;
    check_area("obb-ellipse",
               "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\"><rect x=\"0.25\" "
               "width=\"0.5\" height=\"1\"/></clipPath>"
               "<ellipse cx=\"32\" cy=\"32\" rx=\"24\" ry=\"12\" transform=\"translate(2 4)\" "
               "clip-path=\"url(#c)\"/>",
               24 * (6 * sqrt(3) + 4 * M_PI));
    /* the clipPath's transform after the box: x in [0, 1/4] of the box is
     * [8, 20], moved by translate(12 0) in user units to [20, 32], the
     * strip from x = -12 to 0 about the centre: half the strip above (in
     * box units the move would leave nothing) */
    check_area("obb-transform",
               "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\" "
               "transform=\"translate(12 0)\"><rect width=\"0.25\" height=\"1\"/></clipPath>"
               "<ellipse cx=\"32\" cy=\"32\" rx=\"24\" ry=\"12\" clip-path=\"url(#c)\"/>",
               12 * (6 * sqrt(3) + 4 * M_PI));
    const char *shape = "d=\"M 8 40 C 8 8, 56 8, 56 40 Z\"";
    char a[1024], b[1024];
    snprintf(a, sizeof a,
             "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\"><rect width=\"1\" "
             "height=\"0.5\"/></clipPath><path %s clip-path=\"url(#c)\"/>",
             shape);
    snprintf(b, sizeof b,
             "<clipPath id=\"c\"><rect width=\"64\" height=\"28\"/></clipPath>"
             "<path %s clip-path=\"url(#c)\"/>",
             shape);
    double sa = reference_sum("obb-cubic", a), sb = reference_sum("user-cubic", b);
    printf("# cubic's box: objectBoundingBox %.15g, user space %.15g\n", sa, sb);
    assert_true(fabs(sa - sb) <= 1e-9);
    /* a group's box: its children's, each through its transform: two unit
     * squares at (8, 8) and, scaled by 4, at (40, 40) to (44, 44) give
     * [8, 44]^2; the box's left half x < 26 by objectBoundingBox keeps the
     * first square (1) whole and none of the second */
    check_area("obb-group",
               "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" "
               "height=\"1\"/></clipPath><g clip-path=\"url(#c)\"><rect x=\"8\" y=\"8\" "
               "width=\"1\" height=\"1\"/><rect x=\"10\" y=\"10\" width=\"1\" height=\"1\" "
               "transform=\"scale(4)\"/></g>",
               1);
    /* a nested svg's box, for a clip-path on the svg itself: its content's
     * in the user space it establishes (where that clip applies; SVG 2's
     * getBBox of the element).  viewBox 0 0 20 20 onto 40 x 40 px at (10,
     * 10): content unit 2 px.  The content, a rect [2, 12] x [4, 12] and
     * the unit square at (1, 1) moved by translate(15 15) to [16, 17]^2,
     * has the box [2, 17] x [4, 17]; its right half, x >= 9.5, keeps [9.5,
     * 12] x [4, 12] of the first (20 units) and the second whole (1): 21
     * units, 84 px.  Chromium and resvg draw 84 px of white; the same
     * content as a used symbol alike */
    const char *content = "<rect x=\"2\" y=\"4\" width=\"10\" height=\"8\"/><rect x=\"1\" "
                          "y=\"1\" width=\"1\" height=\"1\" transform=\"translate(15 15)\"/>";
    const char *half = "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\"><rect x=\"0.5\" "
                       "width=\"0.5\" height=\"1\"/></clipPath>";
    snprintf(a, sizeof a,
             "%s<svg x=\"10\" y=\"10\" width=\"40\" height=\"40\" viewBox=\"0 0 20 20\" "
             "clip-path=\"url(#c)\">%s</svg>",
             half, content);
    check_area("obb-nested-svg", a, 84);
    snprintf(a, sizeof a,
             "%s<symbol id=\"s\" viewBox=\"0 0 20 20\" clip-path=\"url(#c)\">%s</symbol>"
             "<use href=\"#s\" x=\"10\" y=\"10\" width=\"40\" height=\"40\"/>",
             half, content);
    check_area("obb-symbol", a, 84);
}

/* A clip clipped in turn: the disk of radius 20 at (24, 32), whose
 * clipPath has clip-path to the disk of radius 20 at (40, 32): the lens of
 * two disks 16 apart.  And a member with its own clip-path: a rectangle
 * x < 32 clipped by a disk of radius 20 at (32, 32), in a clipPath with a
 * second member, a disk of radius 4 at (48, 32) (outside the first
 * member): 200 pi + 16 pi. */
static void test_clip_of_clip(void **state)
{
    (void)state;
    check_area("lens",
               "<clipPath id=\"b\"><circle cx=\"40\" cy=\"32\" r=\"20\"/></clipPath>"
               "<clipPath id=\"a\" clip-path=\"url(#b)\"><circle cx=\"24\" cy=\"32\" r=\"20\"/>"
               "</clipPath><rect width=\"64\" height=\"64\" clip-path=\"url(#a)\"/>",
               lens(20, 16));
    check_area("member",
               "<clipPath id=\"d\"><circle cx=\"32\" cy=\"32\" r=\"20\"/></clipPath>"
               "<clipPath id=\"a\"><rect width=\"32\" height=\"64\" clip-path=\"url(#d)\"/>"
               "<circle cx=\"48\" cy=\"32\" r=\"4\"/></clipPath>"
               "<rect width=\"64\" height=\"64\" clip-path=\"url(#a)\"/>",
               216 * M_PI);
    /* the union of two overlapping members: 2 pi r^2 less the lens */
    check_area("union",
               "<clipPath id=\"a\"><circle cx=\"24\" cy=\"32\" r=\"16\"/>"
               "<circle cx=\"40\" cy=\"32\" r=\"16\"/></clipPath>"
               "<rect width=\"64\" height=\"64\" clip-path=\"url(#a)\"/>",
               2 * M_PI * 256 - lens(16, 16));
    /* a group's clip and its child's meet: the child is drawn in both */
    check_area("nested",
               "<clipPath id=\"b\"><circle cx=\"40\" cy=\"32\" r=\"20\"/></clipPath>"
               "<clipPath id=\"a\"><circle cx=\"24\" cy=\"32\" r=\"20\"/></clipPath>"
               "<g clip-path=\"url(#a)\"><rect width=\"64\" height=\"64\" "
               "clip-path=\"url(#b)\"/></g>",
               lens(20, 16));
}

/* clip-path on a group of opacity 0.5: the group's white rectangle over
 * the view, drawn at 0.5 over black inside the disk of radius 20: the
 * encoded value 0.5 (SVG 2 group opacity, source over in encoded values),
 * linear dec(0.5), on 400 pi. */
static void test_group_opacity(void **state)
{
    (void)state;
    check_area("group",
               "<clipPath id=\"c\"><circle cx=\"32\" cy=\"32\" r=\"20\"/></clipPath>"
               "<g opacity=\"0.5\" clip-path=\"url(#c)\"><rect width=\"64\" height=\"64\"/>"
               "<rect width=\"32\" height=\"64\"/></g>",
               400 * M_PI * dec(0.5));
}

/* What browsers do: a reference to no element, or to an element that is
 * not a clipPath, is as if clip-path were not given (SVG 1.1's clip-path,
 * "treated as if it hadn't been specified"; Chromium agrees,
 * test_paint_renderers): the
 * whole disk, 400 pi; clip-path="none" too.  Hidden or undisplayed
 * children add nothing: the clip of only such children is empty. */
static void test_invalid_references(void **state)
{
    (void)state;
    check_area("missing", "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url(#nowhere)\"/>",
               400 * M_PI);
    check_area("not-a-clip",
               "<rect id=\"r\" width=\"1\" height=\"1\"/>"
               "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url(#r)\"/>",
               1 + 400 * M_PI);
    check_area("none", "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"none\"/>", 400 * M_PI);
    check_area("hidden",
               "<clipPath id=\"c\"><rect width=\"64\" height=\"64\" visibility=\"hidden\"/>"
               "<rect width=\"64\" height=\"64\" display=\"none\"/></clipPath>"
               "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url(#c)\"/>",
               0);
    check_area("visible-again",
               "<clipPath id=\"c\" visibility=\"hidden\"><rect width=\"32\" height=\"64\" "
               "visibility=\"visible\"/></clipPath>"
               "<circle cx=\"32\" cy=\"32\" r=\"20\" clip-path=\"url(#c)\"/>",
               200 * M_PI);
}

/* ---- basic shapes and geometry boxes ---- */

/* The signed area of the polygon (x[k], y[k]) by the shoelace formula,
 * sum (x_k y_k+1 - x_k+1 y_k) / 2. */
static double shoelace(const double *x, const double *y, int n)
{
    double s = 0;
    for (int k = 0; k < n; k++)
        s += x[k] * y[(k + 1) % n] - x[(k + 1) % n] * y[k];
    return s / 2;
}

/* The area of a rectangle w x h whose corners are quarters of ellipses of
 * radii rx[k], ry[k]: each corner cuts rx ry - pi rx ry / 4 off. */
static double rounded_rect(double w, double h, const double *rx, const double *ry)
{
    double a = w * h;
    for (int k = 0; k < 4; k++)
        a -= (1 - M_PI / 4) * rx[k] * ry[k];
    return a;
}

/* CSS Shapes 1's basic shapes as clip-path, in the reference box (a
 * shape's stroke-box by default, its fill box when it has no stroke):
 * each picture's area worked by hand beside it. */
static void test_basic_shapes(void **state)
{
    (void)state;
    /* circle(30% at 40% 50%) of the box 40 x 30 at (8, 8): the radius
     * 30% of the normalised diagonal sqrt((40^2 + 30^2) / 2) = sqrt(1250),
     * about (24, 23), inside the rect: pi 0.09 x 1250 */
    check_area("circle", "<rect x=\"8\" y=\"8\" width=\"40\" height=\"30\" "
                         "style=\"clip-path: circle(30% at 40% 50%)\"/>",
               M_PI * 0.09 * 1250);
    /* closest-side about (20, 24) of the box [0, 64]^2: radius 20 */
    check_area("circle-closest", "<rect width=\"64\" height=\"64\" "
                                 "clip-path=\"circle(closest-side at 20px 24px)\"/>",
               400 * M_PI);
    /* ellipse(30% 10px at right 30px top 50%) of the box 50 x 40 at (4,
     * 4): rx 15, ry 10 about (4 + 50 - 30, 4 + 20) = (24, 24): 150 pi */
    check_area("ellipse", "<rect x=\"4\" y=\"4\" width=\"50\" height=\"40\" "
                          "style=\"clip-path: ellipse(30% 10px at right 30px top 50%)\"/>",
               150 * M_PI);
    /* inset(4px 6px round 8px 4px / 6px) of the box 50 x 40 at (4, 4):
     * [10, 48] x [8, 40], 38 x 32, the corners' horizontal radii 8, 4, 8,
     * 4 (top left, top right, bottom right, bottom left), vertical 6 */
    const double rx1[4] = {8, 4, 8, 4}, ry1[4] = {6, 6, 6, 6};
    check_area("inset", "<rect x=\"4\" y=\"4\" width=\"50\" height=\"40\" "
                        "style=\"clip-path: inset(4px 6px round 8px 4px / 6px)\"/>",
               rounded_rect(38, 32, rx1, ry1));
    /* inset(0 round 30px) of 40 x 20: the radii scaled by the least of
     * 40 / 60 and 20 / 60, to 10: a stadium, 20 x 20 + pi 10^2 */
    check_area("inset-scaled", "<rect x=\"8\" y=\"8\" width=\"40\" height=\"20\" "
                               "style=\"clip-path: inset(0 round 30px)\"/>",
               400 + 100 * M_PI);
    /* inset(0 round 50%) of 40 x 20: radii 20 and 10, just fitting: the
     * ellipse, pi 20 x 10 */
    check_area("inset-ellipse", "<rect x=\"4\" y=\"4\" width=\"40\" height=\"20\" "
                                "style=\"clip-path: inset(0 round 50%)\"/>",
               200 * M_PI);
    /* polygon() of two squares joined at a corner, [8, 40]^2 and [24,
     * 56]^2 (12.5% to 62.5% and 37.5% to 87.5% of the view): evenodd
     * leaves their overlap [24, 40]^2 out, nonzero keeps it */
    const double ax[4] = {8, 40, 40, 8}, ay[4] = {8, 8, 40, 40};
    const double bx[4] = {24, 56, 56, 24}, by[4] = {24, 24, 56, 56};
    const double ox[4] = {24, 40, 40, 24}, oy[4] = {24, 24, 40, 40};
    const double a = shoelace(ax, ay, 4), b = shoelace(bx, by, 4), o = shoelace(ox, oy, 4);
    check_area("polygon-evenodd",
               "<rect width=\"64\" height=\"64\" style=\"clip-path: polygon(evenodd, 12.5% "
               "12.5%, 62.5% 12.5%, 62.5% 62.5%, 12.5% 62.5%, 12.5% 12.5%, 37.5% 37.5%, "
               "87.5% 37.5%, 87.5% 87.5%, 37.5% 87.5%, 37.5% 37.5%)\"/>",
               a + b - 2 * o);
    check_area("polygon-nonzero",
               "<rect width=\"64\" height=\"64\" style=\"clip-path: polygon(8px 8px, 40px "
               "8px, 40px 40px, 8px 40px, 8px 8px, 24px 24px, 56px 24px, 56px 56px, 24px "
               "56px, 24px 24px)\"/>",
               a + b - o);
    /* path() from the fill box's corner (10, 10): the square [10, 42]^2
     * with a hole [18, 34]^2 under evenodd (1024 - 256), none under
     * nonzero (both drawn the same way round) */
    check_area("path-evenodd", "<rect x=\"10\" y=\"10\" width=\"32\" height=\"32\" "
                               "style=\"clip-path: path(evenodd, 'M0 0 H32 V32 H0 Z M8 8 "
                               "H24 V24 H8 Z') fill-box\"/>",
               768);
    check_area("path-nonzero", "<rect width=\"64\" height=\"64\" "
                               "style=\"clip-path: fill-box path('M10 10 H42 V42 H10 Z M18 "
                               "18 H34 V34 H18 Z')\"/>",
               1024);
    /* xywh(2px 3px 50% 10px) of 40 x 40: 20 x 10; rect(2px auto 12px
     * 25%): the edges 2 from the top, the box's right, 12 from the top,
     * 10 from the left: 30 x 10 */
    check_area("xywh", "<rect x=\"4\" y=\"4\" width=\"40\" height=\"40\" "
                       "style=\"clip-path: xywh(2px 3px 50% 10px)\"/>",
               200);
    check_area("rect", "<rect x=\"4\" y=\"4\" width=\"40\" height=\"40\" "
                       "style=\"clip-path: rect(2px auto 12px 25%)\"/>",
               300);
    /* a shape with a transform: the box in its user space, 20 x 20, the
     * disk of radius 10 inscribed, scaled by 2: 400 pi */
    check_area("transformed", "<rect width=\"20\" height=\"20\" transform=\"translate(10 10) "
                              "scale(2)\" style=\"clip-path: circle(50%)\"/>",
               400 * M_PI);
    /* inside a group's clip: the disk of radius 20 about (32, 32) within
     * the left half, 200 pi */
    check_area("within", "<clipPath id=\"c\"><rect width=\"32\" height=\"64\"/></clipPath>"
                         "<g clip-path=\"url(#c)\"><rect width=\"64\" height=\"64\" "
                         "style=\"clip-path: circle(20px at 32px 32px)\"/></g>",
               200 * M_PI);
    /* a group in its fill-box, its object bounding box [8, 32]^2: the
     * quarter of the disk of radius 12 about (8, 8), 36 pi */
    check_area("group", "<g style=\"clip-path: circle(50% at 0 0) fill-box\"><rect x=\"8\" "
                        "y=\"8\" width=\"24\" height=\"24\"/></g>",
               36 * M_PI);
}

/* Geometry boxes alone and as a shape's reference box: the rect [10, 40] x
 * [10, 30] stroked 6 wide (its stroke bounding box [7, 43] x [7, 33], 36 x
 * 26 = 936; its fill box 30 x 20 = 600), white on white; view-box the
 * root's viewport, 64 x 64, the radius 50% of its normalised diagonal 32. */
static void test_geometry_boxes(void **state)
{
    (void)state;
    static const struct {
        const char *clip;
        double area;
    } boxes[] = {{"none", 936},        {"fill-box", 600},    {"content-box", 600},
                 {"padding-box", 600}, {"stroke-box", 936},  {"border-box", 936},
                 {"margin-box", 936},  {"inset(0)", 936},    {"inset(0) fill-box", 600}};
    for (size_t k = 0; k < sizeof boxes / sizeof boxes[0]; k++) {
        char body[512];
        snprintf(body, sizeof body,
                 "<rect x=\"10\" y=\"10\" width=\"30\" height=\"20\" stroke=\"white\" "
                 "stroke-width=\"6\" clip-path=\"%s\"/>",
                 boxes[k].clip);
        check_area(boxes[k].clip, body, boxes[k].area);
    }
    /* a group's: the union of its children's, each through its
     * transform, a stroke inherited; a child group's stroke none: the
     * rect [10, 40] x [10, 30] stroked ([7, 43] x [7, 33]) and [30, 50]^2,
     * overlapping in [30, 43] x [30, 33]; all of it inside the stroke-box
     * [7, 50]^2, 936 + 400 - 39; the fill-box [10, 50]^2 cuts the stroke
     * to [10, 43] x [10, 33], 759 + 400 - 39 */
    check_area("group-stroke-box",
               "<g style=\"clip-path: inset(0)\" stroke=\"white\" stroke-width=\"6\"><rect "
               "x=\"5\" width=\"30\" height=\"20\" transform=\"translate(5 10)\"/><g "
               "stroke=\"none\"><rect x=\"30\" y=\"30\" width=\"20\" height=\"20\"/></g></g>",
               936 + 400 - 39);
    check_area("group-fill-box",
               "<g style=\"clip-path: inset(0) fill-box\" stroke=\"white\" stroke-width=\"6\">"
               "<rect x=\"5\" width=\"30\" height=\"20\" transform=\"translate(5 10)\"/><g "
               "stroke=\"none\"><rect x=\"30\" y=\"30\" width=\"20\" height=\"20\"/></g></g>",
               759 + 400 - 39);
    /* a stroked circle's stroke-box, [20, 44]^2 (the outline's arcs bounded
     * exactly): inset(0 50% 0 0) keeps x < 32, half the disk of radius
     * 12, 72 pi */
    check_area("circle-stroke-box", "<circle cx=\"32\" cy=\"32\" r=\"10\" stroke=\"white\" "
                                    "stroke-width=\"4\" style=\"clip-path: inset(0 50% 0 0)\"/>",
               72 * M_PI);
    /* a stroked ellipse's (its outline's offset curves bounded exactly):
     * rx 20, ry 10 at (32, 32), the stroke 4 wide, so the box [10, 54] x
     * [20, 44]; an inset of 22 px from its left, of 22 px from its right,
     * of 12 px from its top keeps x > 32, x < 32, y > 32: each half the
     * ellipse's parallel body at distance d = 2 (its curvature radius, at
     * least ry^2 / rx = 5, exceeds d, so fill and stroke make the convex
     * body), by Steiner's formula pi rx ry + d P + pi d^2, P the ellipse's
     * perimeter 4 rx E(e), e^2 = 1 - ry^2 / rx^2 (GSL's complete elliptic
     * integral); a box of the fill alone, [12, 52] x [22, 42], or of the
     * control points, would cut elsewhere */
    double perim = 4 * 20 * gsl_sf_ellint_Ecomp(sqrt(0.75), GSL_PREC_DOUBLE);
    static const char *const insets[] = {"0 0 0 22px", "0 22px 0 0", "12px 0 0 0"};
    for (int k = 0; k < 3; k++) {
        char body[400];
        snprintf(body, sizeof body,
                 "<ellipse cx=\"32\" cy=\"32\" rx=\"20\" ry=\"10\" stroke=\"white\" "
                 "stroke-width=\"4\" style=\"clip-path: inset(%s)\"/>",
                 insets[k]);
        check_area("ellipse-stroke-box", body, 0.5 * (M_PI * 200 + 2 * perim + 4 * M_PI));
    }
    /* a use's, in its space after translate(x, y): its target's stroke
     * box [7, 43] x [7, 33], the left half [7, 25] kept, drawn at [12, 30]
     * x [12, 38]: 18 x 26; a group's holding a use whose target inherits
     * the group's stroke: [12, 48] x [12, 38], the top half kept, 36 x 13 */
    check_area("use-stroke-box",
               "<defs><rect id=\"r\" x=\"10\" y=\"10\" width=\"30\" height=\"20\" "
               "stroke=\"white\" stroke-width=\"6\"/></defs><use href=\"#r\" x=\"5\" y=\"5\" "
               "style=\"clip-path: inset(0 50% 0 0)\"/>",
               18 * 26);
    check_area("group-use-stroke-box",
               "<defs><rect id=\"q\" x=\"10\" y=\"10\" width=\"30\" height=\"20\"/></defs>"
               "<g style=\"clip-path: inset(0 0 50% 0)\" stroke=\"white\" stroke-width=\"6\">"
               "<use href=\"#q\" x=\"5\" y=\"5\"/></g>",
               36 * 13);
    check_area("view-box", "<rect x=\"-10\" y=\"-10\" width=\"100\" height=\"100\" "
                           "clip-path=\"view-box\"/>",
               4096);
    check_area("view-box-circle", "<rect width=\"64\" height=\"64\" "
                                  "style=\"clip-path: view-box circle(50%)\"/>",
               1024 * M_PI);
}

/* The box reference of `body` (under root_attrs) is 1 on the pixels of
 * [x0, x1) x [y0, y1) and 0 elsewhere (rectangles on whole pixels, worked
 * by hand). */
static void check_pixels(const char *name, const char *body, int x0, int y0, int x1, int y1)
{
    char spec[4400];
    svg_spec(name, body, spec, sizeof spec);
    aa_image img;
    const support_view v = {.w = N, .h = N};
    support_pattern_reference(spec, &v, &img, NULL, NULL);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            const double want = i >= x0 && i < x1 && j >= y0 && j < y1;
            if (!(fabs(aa_pixel(&img, i, j)[0] - want) <= 1e-12))
                fail_msg("%s: pixel (%d, %d) is %.17g, not %g", name, i, j,
                         aa_pixel(&img, i, j)[0], want);
        }
    aa_image_free(&img);
}

/* transform and clip-path on the root <svg>: those of its layout box (CSS
 * px, outside its viewBox map; transform-origin initially its centre),
 * its viewport clipping the content as transformed. */
static void test_root(void **state)
{
    (void)state;
    /* translate(10 5) moves the rect [0, 20] x [0, 10] to [10, 30] x [5,
     * 15] */
    root_attrs = " transform=\"translate(10 5)\"";
    check_pixels("root-translate", "<rect width=\"20\" height=\"10\"/>", 10, 5, 30, 15);
    /* rotate(90) about the centre (32, 32): (x, y) to (64 - y, x), so the
     * rect [0, 20] x [0, 10] to [54, 64] x [0, 20] */
    root_attrs = " transform=\"rotate(90)\"";
    check_pixels("root-rotate", "<rect width=\"20\" height=\"10\"/>", 54, 0, 64, 20);
    /* a viewport of 32 x 32 moved by (16, 16): the content clipped to it
     * there, [16, 48]^2 */
    root_attrs = " width=\"32\" height=\"32\" transform=\"translate(16 16)\"";
    check_pixels("root-viewport", "<rect x=\"-50\" y=\"-50\" width=\"200\" height=\"200\"/>",
                 16, 16, 48, 48);
    /* scale(1.5) about the origin (transform-origin: 0 0): [0, 48]^2 */
    root_attrs = " width=\"32\" height=\"32\" style=\"transform: scale(1.5); "
                 "transform-origin: 0 0\"";
    check_pixels("root-origin", "<rect x=\"-50\" y=\"-50\" width=\"200\" height=\"200\"/>", 0,
                 0, 48, 48);
    /* clip-path in CSS px, not in the viewBox's units (which are 2 px
     * here): a clipPath rect 10 wide keeps [0, 10] x [0, 64]; one of
     * objectBoundingBox 0.25 wide, a quarter of the viewport: [0, 16] */
    root_attrs = " viewBox=\"0 0 32 32\" clip-path=\"url(#c)\"";
    check_pixels("root-clip", "<clipPath id=\"c\"><rect width=\"10\" height=\"64\"/></clipPath>"
                              "<rect width=\"32\" height=\"32\"/>",
                 0, 0, 10, 64);
    check_pixels("root-clip-box", "<clipPath id=\"c\" clipPathUnits=\"objectBoundingBox\">"
                                  "<rect width=\"0.25\" height=\"1\"/></clipPath>"
                                  "<rect width=\"32\" height=\"32\"/>",
                 0, 0, 16, 64);
    /* a basic shape in the viewport's box: circle(16px at 32px 32px), 256
     * pi (1024 pi in the viewBox's units) */
    root_attrs = " viewBox=\"0 0 32 32\" style=\"clip-path: circle(16px at 32px 32px)\"";
    check_area("root-circle", "<rect width=\"32\" height=\"32\"/>", 256 * M_PI);
    /* and moved with the transform: inset(0 32px 0 0) keeps [0, 32] of
     * the box, at [8, 40] */
    root_attrs = " transform=\"translate(8 0)\" style=\"clip-path: inset(0 32px 0 0)\"";
    check_pixels("root-both", "<rect width=\"64\" height=\"64\"/>", 8, 0, 40, 64);
    root_attrs = "";
}

/* The refusal for `body`, naming the element and containing `want`. */
static void refused(const char *body, const char *where, const char *want)
{
    char spec[4400];
    svg_spec("refused", body, spec, sizeof spec);
    aa_spec s;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse(spec, &s), AA_OK);
    int st = aa_pattern_scene_at(&s, N, N, &sc);
    if (st == AA_OK) {
        aa_scene_free(sc);
        fail_msg("%s: read, not refused", body);
    }
    const char *e = aa_last_error();
    printf("# %s\n", e);
    if (!strstr(e, where) || !strstr(e, want))
        fail_msg("%s: the message \"%s\" does not name %s and %s", body, e, where, want);
}

static void test_refused(void **state)
{
    (void)state;
    /* a cycle: a's clip-path is b, b's is a */
    refused("<clipPath id=\"a\" clip-path=\"url(#b)\"><rect width=\"9\" height=\"9\"/>"
            "</clipPath>\n<clipPath id=\"b\" clip-path=\"url(#a)\"><rect width=\"9\" "
            "height=\"9\"/></clipPath>\n<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "line 3: <clipPath>", "cycle");
    /* a member referring to its own clipPath */
    refused("<clipPath id=\"a\">\n<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>"
            "</clipPath><rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "line 3: <rect>", "cycle");
    /* a malformed clip-path (two radii for a circle, a negative radius,
     * two boxes) is invalid: ignored, as SVG 2 takes an invalid
     * presentation attribute (its initial value, none: the whole 9 x 9
     * rect, 81) and CSS an invalid declaration (the cascade goes on, here
     * to the attribute's inset(), which keeps x > 4.5 of the rect: 40.5);
     * a unit the reader does not read may be valid: refused */
    static const char *const malformed[] = {"circle(4px 5px)", "circle(-4px)",
                                            "fill-box view-box"};
    for (int k = 0; k < 3; k++) {
        char body[200];
        snprintf(body, sizeof body, "<rect width=\"9\" height=\"9\" clip-path=\"%s\"/>",
                 malformed[k]);
        check_area("clip-path-invalid", body, 81);
    }
    check_area("clip-path-invalid-cascade",
               "<rect width=\"9\" height=\"9\" clip-path=\"inset(0 0 0 50%)\" "
               "style=\"clip-path: circle(-4px)\"/>",
               40.5);
    refused("<rect width=\"9\" height=\"9\" clip-path=\"circle(2ch)\"/>", "<rect>",
            "basic shape");
    /* the stroke-box of a group, and of a shape in a clipPath, whose
     * stroke is not known there */
    refused("<symbol id=\"s\"><rect width=\"9\" height=\"9\"/></symbol><g "
            "clip-path=\"circle(4px)\"><use href=\"#s\"/></g>",
            "<use>", "use of a <symbol>");
    refused("<g clip-path=\"circle(4px)\"><svg width=\"9\" height=\"9\"/></g>", "<svg>",
            "stroke-box");
    refused("<clipPath id=\"a\"><rect width=\"9\" height=\"9\" clip-path=\"inset(1px)\"/>"
            "</clipPath><rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "<rect>", "stroke-box");
    refused("<svg width=\"9\" height=\"9\" clip-path=\"circle(4px)\"/>", "<svg>",
            "nested <svg>");
    root_attrs = " transform=\"scale(0)\"";
    refused("<rect width=\"9\" height=\"9\"/>", "<svg>", "singular");
    root_attrs = "";
    refused("<rect width=\"9\" height=\"9\" clip-path=\"url(other.svg#a)\"/>", "<rect>",
            "url(#id)");
    refused("<clipPath id=\"a\"><text>x</text></clipPath>"
            "<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "<text>", "not supported");
    refused("<clipPath id=\"a\"><g/></clipPath>"
            "<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "<g>", "not allowed");
    refused("<clipPath id=\"a\" clipPathUnits=\"pixels\"/>"
            "<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
            "<clipPath>", "clipPathUnits");
    /* an invalid clip-rule is its initial value, nonzero (SVG 2,
     * "Attribute syntax"), with a warning: the square of two windings
     * [0, 9]^2 (evenodd would leave its inner [3, 6]^2 out: 72) keeps the
     * rect whole, 81 */
    check_area("invalid clip-rule",
               "<clipPath id=\"a\"><path d=\"M0 0 H9 V9 H0 Z M3 3 H6 V6 H3 Z\" "
               "clip-rule=\"odd\"/></clipPath>"
               "<rect width=\"9\" height=\"9\" clip-path=\"url(#a)\"/>",
               81);
    refused("<clipPath id=\"a\" clipPathUnits=\"objectBoundingBox\"/>"
            "<line x2=\"9\" stroke=\"red\" clip-path=\"url(#a)\"/>",
            "<clipPath>", "no width or no height");
    /* a nested svg whose content has no area */
    refused("<clipPath id=\"a\" clipPathUnits=\"objectBoundingBox\"/>"
            "<svg width=\"9\" height=\"9\" clip-path=\"url(#a)\"><line x2=\"9\" "
            "stroke=\"red\"/></svg>",
            "<clipPath>", "content's bounding box has no width");
}

/* The shipped clips.svg builds, clipped. */
static void test_shipped(void **state)
{
    (void)state;
    char spec[4400];
    snprintf(spec, sizeof spec, "svg:file=%s/clips.svg", aa_svg_dir());
    aa_spec s;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse(spec, &s), AA_OK);
    if (aa_pattern_scene_at(&s, 128, 128, &sc) != AA_OK)
        fail_msg("%s", aa_last_error());
    assert_int_equal(aa_scene_is_clipped(sc), 1);
    /* inside the half disk, and left of its centre but right of the clip */
    assert_true(aa_scene_colour_at(sc, 20.0 / 128, 32.0 / 128).c[0] == 1.0);
    assert_true(aa_scene_colour_at(sc, 40.0 / 128, 32.0 / 128).c[0] == 0.0);
    /* `area` within 1e-12 of the reference at every pixel, at 128 x 96
     * (the picture placed unevenly: its edges off the pixel grid) */
    const support_view v = {.w = 128, .h = 96};
    aa_image ref, out;
    aa_scene_free(sc);
    if (aa_pattern_scene_at(&s, v.w, v.h, &sc) != AA_OK)
        fail_msg("%s", aa_last_error());
    support_pattern_reference(spec, &v, &ref, NULL, NULL);
    support_render_must("area", sc, &v, &out, NULL);
    double d = support_max_diff(&out, &ref, NULL, NULL);
    printf("# clips.svg at 128 x 96: area against the reference %.2g\n", d);
    if (!(d <= 1e-12))
        fail_msg("clips.svg: area differs from the reference by %.3g", d);
    aa_image_free(&ref);
    aa_image_free(&out);
    aa_scene_free(sc);
}

/* `export` writes a clipped scene as SVG with its clipPaths; read back,
 * the same picture (the scene's own numbers, to rounding). */
static void test_export_round_trip(void **state)
{
    (void)state;
    const char *body =
        "<clipPath id=\"b\"><circle cx=\"40\" cy=\"32\" r=\"20\"/></clipPath>"
        "<clipPath id=\"a\" clip-path=\"url(#b)\"><circle cx=\"24\" cy=\"32\" r=\"20\"/>"
        "<rect x=\"30\" width=\"4\" height=\"64\" clip-rule=\"evenodd\" clip-path=\"url(#b)\"/>"
        "</clipPath><g opacity=\"0.5\"><rect width=\"64\" height=\"64\" fill=\"red\" "
        "clip-path=\"url(#a)\"/><line x1=\"0\" y1=\"8\" x2=\"64\" y2=\"60\" stroke=\"white\" "
        "stroke-width=\"3\" clip-path=\"url(#b)\"/></g>";
    char spec[4400], spec2[4400], path[4200];
    svg_spec("export", body, spec, sizeof spec);
    aa_spec s;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse(spec, &s), AA_OK);
    if (aa_pattern_scene_at(&s, N, N, &sc) != AA_OK)
        fail_msg("%s", aa_last_error());
    aa_scene *placed = aa_scene_place(sc, N, N, 0, 0, 0);
    assert_non_null(placed);
    snprintf(path, sizeof path, "%s/exported.svg", dir);
    if (aa_scene_svg_write(path, placed, N, N, AA_SVG_COLOURS, NULL) != AA_OK)
        fail_msg("%s", aa_last_error());
    snprintf(spec2, sizeof spec2, "svg:file=%s", path);
    aa_image a, b;
    support_pattern_reference(spec, &(support_view){.w = N, .h = N}, &a, NULL, NULL);
    support_pattern_reference(spec2, &(support_view){.w = N, .h = N}, &b, NULL, NULL);
    double worst = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(aa_pixel(&a, i, j)[c] - aa_pixel(&b, i, j)[c]));
    printf("# export and read back: largest difference %.3g\n", worst);
    assert_true(worst <= 1e-12);
    aa_image_free(&a);
    aa_image_free(&b);
    aa_scene_free(placed);
    aa_scene_free(sc);
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_scene_model),
             cmocka_unit_test(test_clip_unit), cmocka_unit_test(test_half_disk),
             cmocka_unit_test(test_small_disk), cmocka_unit_test(test_viewport_element),
             cmocka_unit_test(test_clip_rule), cmocka_unit_test(test_use_in_clip),
             cmocka_unit_test(test_bounding_box), cmocka_unit_test(test_clip_of_clip),
             cmocka_unit_test(test_group_opacity), cmocka_unit_test(test_invalid_references),
             cmocka_unit_test(test_basic_shapes), cmocka_unit_test(test_geometry_boxes),
             cmocka_unit_test(test_root), cmocka_unit_test(test_refused),
             cmocka_unit_test(test_shipped),
             cmocka_unit_test(test_export_round_trip))
