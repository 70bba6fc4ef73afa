/*
 * test_peer_clips.c: the peer rasterizers (freetype, stb, cairo, agg) on
 * groups of opacity and clipped scenes (peer.h, "Clips" and "Groups of
 * opacity"), against closed forms.
 *
 * Known answers, independent of the peers:
 *  - groups: the scene's compositing (patterns/README.md, "Translucency";
 *    SVG 2 group opacity, W3C Compositing source-over) worked by hand in
 *    sRGB-encoded values, with IEC 61966-2-1's transfer written out here:
 *    a group of opacity o whose opaque layers cover a point shows the
 *    front-most one's colour c over the background b as
 *    decode(o encode(c) + (1 - o) encode(b)), however many of them
 *    overlap there (layer by layer it would be o again for each);
 *  - clips: a white shape on black, wholly covering a pixel or missing
 *    it, gives exactly 1 or 0 there in each peer (full coverage is
 *    255/255), and the image's sum is the area of what is drawn.  The
 *    areas are derived here: a disk of radius r cut by a line at distance
 *    d from its centre keeps
 *        A(r, d) = pi r^2 - (r^2 acos(d/r) - d sqrt(r^2 - d^2))
 *    on the centre's side (the circular segment subtracted); a square
 *    wholly inside the disk takes away its own area.
 * Each peer's polygon of a circle lies between the circle shrunk by s_in
 * and grown by s_out about its centre, the bounds test_peers.c derives
 * for its elliptical arcs (FreeType's and stb's flattening of the cubics
 * of aa_peer_arc_cubics, Cairo's tolerance, AGG's arc chords), and each
 * pixel a shape's edge crosses is off its polygon's exact coverage by at
 * most that peer's q (8-bit rounding; Cairo's best converter samples 15
 * sub-rows): the clips' edges here lie on pixel boundaries, where a mask
 * is exactly 0 or 1, so those bounds hold for the clipped picture too.
 * Where a clip's edge and a shape's cross one pixel the peers that mask
 * multiply coverages, which is not the coverage of the intersection, and
 * Cairo clipping to a path itself intersects the polygons: the last test
 * tells the two apart on a case with a known answer.
 */
#include "bench.h"
#include "core.h"
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

#define N 64 /* images of N x N pixels */

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* IEC 61966-2-1, written out. */
static double dec(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

static const char *const painters[] = {"freetype", "stb", "cairo", "cairo:aa=good", "agg"};
#define NPAINTERS (sizeof painters / sizeof painters[0])

/* A rectangle [x0, x1] x [y0, y1] px as a closed path of the layer open
 * (clockwise on screen, y down), or the other way round if `reversed`. */
static void rect_path(aa_scene *s, double x0, double y0, double x1, double y1, int reversed)
{
    assert_int_equal(aa_scene_move_to(s, x0 / N, y0 / N), AA_OK);
    if (reversed) {
        assert_int_equal(aa_scene_line_to(s, x0 / N, y1 / N), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x1 / N, y1 / N), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x1 / N, y0 / N), AA_OK);
    } else {
        assert_int_equal(aa_scene_line_to(s, x1 / N, y0 / N), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x1 / N, y1 / N), AA_OK);
        assert_int_equal(aa_scene_line_to(s, x0 / N, y1 / N), AA_OK);
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
}

static void rect_layer(aa_scene *s, aa_rgb c, double x0, double y0, double x1, double y1)
{
    assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
    rect_path(s, x0, y0, x1, y1, 0);
}

/* ---- groups of opacity ---- */

/* Pixel (i, j) of img against want within tol, every channel. */
static void expect_px(const char *spec, const aa_image *img, int i, int j, const double want[3],
                      double tol, const char *what)
{
    const double *px = aa_pixel(img, i, j);
    for (int c = 0; c < 3; c++)
        if (!(fabs(px[c] - want[c]) <= tol))
            fail_msg("%s: %s: pixel (%d, %d) channel %d %.17g, not %.17g within %.3g", spec,
                     what, i, j, c, px[c], want[c], tol);
}

/* Over white, a group of opacity 1/2 of a green rectangle [6, 12.5] x
 * [2, 14] in front of a blue one [0, 10] x [0, N] (px): where both
 * cover, the front one's green at 1/2, decode(1/2 encode(green) + 1/2
 * encode(white)) = (d, 1, d), d = decode(1/2), exactly as where green
 * covers alone; blue alone (d, d, 1); white elsewhere.  Painted layer by
 * layer the overlap would be green at 1/2 over blue at 1/2, red
 * decode(1/4) there: the test tells the two apart by 0.16.  Column 12 is
 * covered 1/2 by green alone: (d + 1)/2 red, each peer's 8-bit coverage
 * of 1/2 within 1/255 of it (test_peers.c). */
static void test_group_overlap(void **state)
{
    (void)state;
    const aa_rgb green = {{0, 1, 0}}, blue = {{0, 0, 1}};
    aa_scene *s = aa_scene_new(white);
    assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
    rect_layer(s, green, 6, 2, 12.5, 14);
    rect_layer(s, blue, 0, 0, 10, N);
    assert_int_equal(aa_scene_group_end(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const double d = dec(0.5);
    const double g[3] = {d, 1, d}, b[3] = {d, d, 1}, w[3] = {1, 1, 1};
    const double edge[3] = {(d + 1) / 2, 1, (d + 1) / 2};
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        support_render(painters[k], s, "box", N, N, 2, &img, NULL);
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                const int in_g = i >= 6 && i < 12 && j >= 2 && j < 14, in_b = i < 10;
                if (i == 12 && j >= 2 && j < 14)
                    expect_px(painters[k], &img, i, j, edge, 1.0 / 255 + 1e-12, "half green");
                else
                    expect_px(painters[k], &img, i, j, in_g ? g : in_b ? b : w, 1e-15,
                              in_g ? "green at 1/2" : in_b ? "blue at 1/2" : "white");
            }
        print_message("%-14s overlap (7, 5) red %.6f = green's alone (11, 5) %.6f; layer by "
                      "layer %.6f\n",
                      painters[k], aa_pixel(&img, 7, 5)[0], aa_pixel(&img, 11, 5)[0],
                      dec(0.25));
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* Nested groups over white: a group of opacity 1/2 holding a green
 * rectangle [0, 8] x [0, N] in front of a group of opacity 1/2 that
 * holds a blue one [4, N] x [0, N] (px).  Blue alone: the inner group goes
 * into the outer one (colour 1/2 encode(blue), alpha 1/2), the outer over
 * white at 1/2: decode(1/4 encode(blue) + 3/4), so (decode(3/4),
 * decode(3/4), 1); where green covers, it hides the inner group inside
 * the outer one: (d, 1, d), d = decode(1/2). */
static void test_group_nested(void **state)
{
    (void)state;
    const aa_rgb green = {{0, 1, 0}}, blue = {{0, 0, 1}};
    aa_scene *s = aa_scene_new(white);
    assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
    rect_layer(s, green, 0, 0, 8, N);
    assert_int_equal(aa_scene_group_begin(s, 0.5), AA_OK);
    rect_layer(s, blue, 4, 0, N, N);
    assert_int_equal(aa_scene_group_end(s), AA_OK);
    assert_int_equal(aa_scene_group_end(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const double d = dec(0.5), q = dec(0.75);
    const double g[3] = {d, 1, d}, b[3] = {q, q, 1};
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        support_render(painters[k], s, "box", N, N, 1, &img, NULL);
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++)
                expect_px(painters[k], &img, i, j, i < 8 ? g : b, 1e-15,
                          i < 8 ? "green in the outer group" : "blue in both groups");
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* ---- clips ---- */

typedef struct arc_case {
    const char *spec;
    double d_in, d_out, e, q; /* px, px, relative, per edge pixel (test_peers.c) */
} arc_case;

static const arc_case arc_cases[] = {
    {"freetype", 0.19, 0.02, 2.7253e-4, 2.0 / 255},
    {"stb", 0.35 / 2 + 1e-4, 1e-4, 2.7253e-4, 1.0 / 255},
    {"cairo", 0.1 + 1.0 / 256, 0.1 + 1.0 / 256, 0.0, 1.0 / 255 + 1.0 / 15},
    {"cairo:aa=good", 0.1 + 1.0 / 256, 0.1 + 1.0 / 256, 0.0, 1.0 / 255 + 1.0 / 4},
    {"agg", 0.125 + 1.0 / 256, 1.0 / 256, 0.0, 1.0 / 255},
};
#define NARC (sizeof arc_cases / sizeof arc_cases[0])

#define CX 32.0 /* the disk: centre (CX, CX), radius R, px */
#define R 20.0

/* The disk as two half arcs, a closed path of the layer open. */
static void disk_path(aa_scene *s)
{
    const double c = CX / N, r = R / N;
    assert_int_equal(aa_scene_move_to(s, c + r, c), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, c, c, r, 0, 0, r, 0, M_PI, c - r, c), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, c, c, r, 0, 0, r, M_PI, 2 * M_PI, c + r, c), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* The disk of radius rho about the centre below the line y = CX + dcut
 * (A(rho, d) above; all of it if the line misses it). */
static double disk_cut(double rho, double dcut)
{
    if (dcut >= rho)
        return M_PI * rho * rho;
    return M_PI * rho * rho - (rho * rho * acos(dcut / rho) - dcut * sqrt(rho * rho - dcut * dcut));
}

/* Pixel (i, j) against the disk scaled by `scale`: +1 wholly inside, -1
 * wholly outside, 0 neither. */
static int disk_side(int i, int j, double scale)
{
    double far = 0.0, nx = fmax(i, fmin(CX, i + 1.0)), ny = fmax(j, fmin(CX, j + 1.0));
    for (int k = 0; k < 4; k++)
        far = fmax(far, hypot(i + (k & 1) - CX, j + (k >> 1) - CX));
    if (far < R * scale)
        return 1;
    return hypot(nx - CX, ny - CX) > R * scale ? -1 : 0;
}

/* What a clipped disk scene draws: `kept(i, j)` 1 where the clip holds
 * the whole pixel, 0 where it holds none of it (the clips' edges lie on
 * pixel boundaries); its area when the disk is scaled by rho/R. */
typedef struct clip_case {
    const char *name;
    int (*kept)(int i, int j);
    double (*area)(double rho);
} clip_case;

/* Every pixel wholly inside the drawn region (the scaled-in disk, kept)
 * exactly 1, every one wholly outside (outside the scaled-out disk, or
 * not kept) exactly 0, and the others' sum the area of the peer's
 * polygon, between area(R (1 - s_in)) and area(R (1 + s_out)), less the
 * inside pixels' count, within q per pixel. */
static void check_clipped_disk(const aa_scene *s, const clip_case *cc)
{
    const support_view v = {.w = N, .h = N, .filter = "box", .threads = 1};
    aa_image ref;
    support_reference(s, &v, &ref, NULL, NULL);
    for (size_t k = 0; k < NARC; k++) {
        const arc_case *c = &arc_cases[k];
        const double s_in = c->d_in / R, s_out = c->e + c->d_out / R;
        aa_image img;
        support_render(c->spec, s, "box", N, N, 2, &img, NULL);
        int nin = 0, nband = 0, bad = 0;
        double band_sum = 0.0, sum = 0.0, ref_sum = 0.0, ref_err = 0.0;
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                const double *px = aa_pixel(&img, i, j), val = px[0];
                if (!(px[1] == val && px[2] == val))
                    fail_msg("%s %s: pixel (%d, %d) not grey", cc->name, c->spec, i, j);
                sum += val;
                ref_sum += aa_pixel(&ref, i, j)[0];
                ref_err = fmax(ref_err, fabs(val - aa_pixel(&ref, i, j)[0]));
                if (!cc->kept(i, j) || disk_side(i, j, 1.0 + s_out) < 0) {
                    bad += val != 0.0;
                } else if (disk_side(i, j, 1.0 - s_in) > 0) {
                    nin++;
                    bad += val != 1.0;
                } else {
                    nband++;
                    band_sum += val;
                }
            }
        const double lo = cc->area(R * (1 - s_in)) - nin - nband * c->q;
        const double hi = cc->area(R * (1 + s_out)) - nin + nband * c->q;
        print_message("%-22s %-14s sum %.4f px^2, closed form %.4f (off %.4f), reference "
                      "%.4f; worst pixel vs reference %.4f; %d edge pixels sum %.4f in "
                      "[%.4f, %.4f]\n",
                      cc->name, c->spec, sum, cc->area(R), sum - cc->area(R), ref_sum, ref_err,
                      nband, band_sum, lo, hi);
        if (bad)
            fail_msg("%s %s: %d pixels wholly inside or outside are not 1 or 0", cc->name,
                     c->spec, bad);
        if (!(band_sum >= lo && band_sum <= hi))
            fail_msg("%s %s: the edge pixels sum to %.6f, outside [%.6f, %.6f]", cc->name,
                     c->spec, band_sum, lo, hi);
        aa_image_free(&img);
    }
    aa_image_free(&ref);
}

/* The clip rectangle [0, N] x [0, CX + 10]: rows j < 42 kept. */
static int kept_rows(int i, int j)
{
    (void)i;
    return j < (int)CX + 10;
}

static double area_cut(double rho) { return disk_cut(rho, 10.0); }

/* A white disk gated by a clip of one rectangle [0, N] x [0, 42]. */
static void test_clip_disk_by_rect(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new(black);
    int clip;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 0, 0, N, CX + 10, 0);
    assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    disk_path(s);
    assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const clip_case cc = {"disk by rect", kept_rows, area_cut};
    check_clipped_disk(s, &cc);
    aa_scene_free(s);
}

/* Nested clips, both ways the scene nests them, drawing the same: a white
 * rectangle over all the image gated by a clip whose member is the disk,
 * that clip defined within the clip of the rectangle [0, N] x [0, 42];
 * and the same with the disk member itself gated by the rectangle's clip
 * (a member's own clip).  Either way the disk below y = 42: A(R, 10). */
static void test_clip_nested(void **state)
{
    (void)state;
    for (int way = 0; way < 2; way++) {
        aa_scene *s = aa_scene_new(black);
        int rect, disk;
        assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
        assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
        rect_path(s, 0, 0, N, CX + 10, 0);
        assert_int_equal(aa_scene_clip_end(s, &rect), AA_OK);
        assert_int_equal(aa_scene_clip_begin(s, way ? -1 : rect), AA_OK);
        assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
        disk_path(s);
        if (way)
            assert_int_equal(aa_scene_set_clip(s, rect), AA_OK);
        assert_int_equal(aa_scene_clip_end(s, &disk), AA_OK);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        rect_path(s, 0, 0, N, N, 0);
        assert_int_equal(aa_scene_set_clip(s, disk), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        const clip_case cc = {way ? "disk member clipped" : "disk clip within rect",
                              kept_rows, area_cut};
        check_clipped_disk(s, &cc);
        aa_scene_free(s);
    }
}

/* The even-odd frame: [8, 56]^2 holding the hole [24, 40]^2 (inside the
 * disk: its corners are 8 sqrt 2 < 20 from the centre). */
static int kept_frame(int i, int j)
{
    return !(i >= 24 && i < 40 && j >= 24 && j < 40);
}

static double area_frame(double rho) { return M_PI * rho * rho - 256.0; }

/* A white disk gated by an even-odd clip of two squares, [8, 56]^2 and
 * [24, 40]^2: the disk (inside the outer square) less the inner square,
 * pi R^2 - 256.  Wound alike, the inner square has winding 2, a hole by
 * the even-odd rule only: nonzero would keep the whole disk.  stb takes
 * even-odd layers wound once only and refuses that one (test_peers.c);
 * wound the other way round (winding 0) every peer draws it. */
static void test_clip_evenodd(void **state)
{
    (void)state;
    for (int reversed = 0; reversed < 2; reversed++) {
        aa_scene *s = aa_scene_new(black);
        int clip;
        assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
        assert_int_equal(aa_scene_clip_layer(s, AA_FILL_EVENODD), AA_OK);
        rect_path(s, 8, 8, 56, 56, 0);
        rect_path(s, 24, 24, 40, 40, reversed);
        assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        disk_path(s);
        assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        if (!reversed) {
            aa_image img;
            assert_int_equal(support_render_view("stb", s,
                                                 &(support_view){.w = N, .h = N, .threads = 1},
                                                 &img, NULL),
                             AA_EINVAL);
            assert_non_null(strstr(aa_last_error(), "even-odd layer"));
        }
        const clip_case cc = {reversed ? "even-odd frame, once" : "even-odd frame, twice",
                              kept_frame, area_frame};
        if (reversed) {
            check_clipped_disk(s, &cc);
        } else {
            for (size_t k = 0; k < NARC; k++) {
                if (!strcmp(arc_cases[k].spec, "stb"))
                    continue;
                aa_image img;
                support_render(arc_cases[k].spec, s, "box", N, N, 1, &img, NULL);
                for (int j = 24; j < 40; j++)
                    for (int i = 24; i < 40; i++)
                        if (aa_pixel(&img, i, j)[0] != 0.0)
                            fail_msg("%s: the even-odd hole's pixel (%d, %d) is %g, not 0",
                                     arc_cases[k].spec, i, j, aa_pixel(&img, i, j)[0]);
                aa_image_free(&img);
            }
        }
        aa_scene_free(s);
    }
}

/* Several clips, made from each other, over one another (the masks' plan,
 * peer.c), on a 64 x 64 image in cells of 4 px (every edge on pixel
 * boundaries: masks and coverages 0 or 1, so every pixel is exact).
 * Clips, in cells: C0 = [0, 8] x [0, 16]; C1 = [4, 16] x [0, 16] within C0,
 * so [4, 8] x [0, 16]; C2 = [0, 16] x [0, 8] whose member is clipped by
 * C1, so [4, 8] x [0, 8]; C3 = [12, 16] x [0, 8] and [12, 16] x [8, 16],
 * two members (a union Cairo cannot clip to: its mask).  Layers over all
 * the image, front to back: red gated by C3, green by C2, blue by C0,
 * white by C1.  So by hand: columns 0-3 blue; 4-7 green in rows 0-7, blue
 * below (white is behind blue there); 8-11 black; 12-15 red. */
static void test_clip_many(void **state)
{
    (void)state;
    const aa_rgb red = {{1, 0, 0}}, green = {{0, 1, 0}}, blue = {{0, 0, 1}};
    const double u = N / 16.0;
    aa_scene *s = aa_scene_new(black);
    int c0, c1, c2, c3;
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 0, 0, 8 * u, N, 0);
    assert_int_equal(aa_scene_clip_end(s, &c0), AA_OK);
    assert_int_equal(aa_scene_clip_begin(s, c0), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 4 * u, 0, N, N, 0);
    assert_int_equal(aa_scene_clip_end(s, &c1), AA_OK);
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 0, 0, N, 8 * u, 0);
    assert_int_equal(aa_scene_set_clip(s, c1), AA_OK);
    assert_int_equal(aa_scene_clip_end(s, &c2), AA_OK);
    assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 12 * u, 0, N, 8 * u, 0);
    assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
    rect_path(s, 12 * u, 8 * u, N, N, 0);
    assert_int_equal(aa_scene_clip_end(s, &c3), AA_OK);
    const aa_rgb colour[4] = {red, green, blue, white};
    const int gate[4] = {c3, c2, c0, c1};
    for (int k = 0; k < 4; k++) {
        rect_layer(s, colour[k], 0, 0, N, N);
        assert_int_equal(aa_scene_set_clip(s, gate[k]), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        support_render(painters[k], s, "box", N, N, 2, &img, NULL);
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                const int ci = (int)(i / u), cj = (int)(j / u);
                const aa_rgb want = ci < 4                ? blue
                                    : ci < 8 && cj < 8   ? green
                                    : ci < 8             ? blue
                                    : ci < 12            ? black
                                                         : red;
                expect_px(painters[k], &img, i, j, want.c, 0.0, "the clips by hand");
            }
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* The shipped patterns/svg/clips.svg (a half disk, a lens of a clip of a
 * clip, an even-odd clip, an objectBoundingBox clip, a group of opacity
 * clipped by a disk, a stroked line clipped by a rectangle) at 128 x 128:
 * wherever the reference is one colour over a pixel's 3 x 3 neighbourhood
 * (no edge of the picture within a pixel of it), every peer gives that
 * colour (within 1e-9: the reference's quadrature and the peers'
 * encode/decode round trips), so what they draw is the picture the
 * reference integrates, which test_paint_renderers.c holds to Chromium and
 * resvg.  stb refuses the even-odd clip (its two squares wound alike,
 * winding 2). */
static void test_shipped_clips(void **state)
{
    (void)state;
    char spec[4400];
    snprintf(spec, sizeof spec, "svg:file=%s/clips.svg", aa_svg_dir());
    aa_spec ps;
    aa_scene *s = NULL;
    assert_int_equal(aa_pattern_parse(spec, &ps), AA_OK);
    if (aa_pattern_scene_at(&ps, 128, 128, &s) != AA_OK)
        fail_msg("%s", aa_last_error());
    const support_view v = {.w = 128, .h = 128, .filter = "box", .threads = 2};
    aa_image ref;
    support_reference(s, &v, &ref, NULL, NULL);
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        if (!strcmp(painters[k], "stb")) {
            assert_int_equal(support_render_view("stb", s, &v, &img, NULL), AA_EINVAL);
            assert_non_null(strstr(aa_last_error(), "even-odd layer"));
            continue;
        }
        support_render(painters[k], s, "box", 128, 128, 2, &img, NULL);
        int flat = 0;
        double edge2 = 0.0;
        for (int j = 0; j < 128; j++)
            for (int i = 0; i < 128; i++) {
                const double *r = aa_pixel(&ref, i, j), *px = aa_pixel(&img, i, j);
                int uniform = 1;
                for (int dj = -1; dj <= 1; dj++)
                    for (int di = -1; di <= 1; di++) {
                        const int x = i + di, y = j + dj;
                        if (x < 0 || y < 0 || x >= 128 || y >= 128)
                            continue;
                        for (int c = 0; c < 3; c++)
                            uniform &= fabs(aa_pixel(&ref, x, y)[c] - r[c]) <= 1e-12;
                    }
                for (int c = 0; c < 3; c++) {
                    if (uniform && !(fabs(px[c] - r[c]) <= 1e-9))
                        fail_msg("%s: clips.svg pixel (%d, %d) channel %d %.12f, the "
                                 "reference %.12f there and around",
                                 painters[k], i, j, c, px[c], r[c]);
                    edge2 += uniform ? 0.0 : (px[c] - r[c]) * (px[c] - r[c]);
                }
                flat += uniform;
            }
        print_message("%-14s clips.svg: %d flat pixels as the reference; the others' RMSE "
                      "%.3e\n",
                      painters[k], flat, sqrt(edge2 / (3.0 * (128 * 128 - flat))));
        aa_image_free(&img);
    }
    aa_image_free(&ref);
    aa_scene_free(s);
}

/* Masks multiply coverages: a white rectangle [0, 10.5] x [0, 16] gated
 * by a clip of [10.5, 16] x [0, 16] draws nothing in the exact picture
 * (the reference is 0 in every pixel), but column 10 is covered 1/2 by
 * each, so a peer that multiplies masks draws 1/2 x 1/2 = 1/4 there (two
 * 8-bit coverages each within 1/255 of 1/2, test_peers.c: within 1/255 in
 * all), and exactly 0 elsewhere.  Cairo clips to the one member's path
 * itself (cairo.c) and intersects the polygons: exactly 0 everywhere.
 * With the clip made of two members, [10.5, 16] x [0, 8] and
 * [10.5, 16] x [8, 16] (the same region, a union Cairo cannot clip to),
 * Cairo takes the masks too: 1/4 in column 10 for every peer (each
 * member covers its pixels of column 10 by 1/2, the other none). */
static void test_clip_mask_product(void **state)
{
    (void)state;
    for (int members = 1; members <= 2; members++) {
        aa_scene *s = aa_scene_new(black);
        int clip;
        assert_int_equal(aa_scene_clip_begin(s, -1), AA_OK);
        /* rect_path takes px of an N-pixel image: 10.5 px of 16 is 10.5 N / 16 */
        for (int m = 0; m < members; m++) {
            assert_int_equal(aa_scene_clip_layer(s, AA_FILL_NONZERO), AA_OK);
            rect_path(s, 10.5 * N / 16, members == 1 ? 0 : m * N / 2.0, N,
                      members == 1 ? N : (m + 1) * N / 2.0, 0);
        }
        assert_int_equal(aa_scene_clip_end(s, &clip), AA_OK);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        rect_path(s, 0, 0, 10.5 * N / 16, N, 0);
        assert_int_equal(aa_scene_set_clip(s, clip), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        const support_view v = {.w = 16, .h = 16, .filter = "box", .threads = 1};
        aa_image ref;
        support_reference(s, &v, &ref, NULL, NULL);
        for (int j = 0; j < 16; j++)
            for (int i = 0; i < 16; i++)
                assert_true(fabs(aa_pixel(&ref, i, j)[0]) <= 1e-12);
        aa_image_free(&ref);
        for (size_t k = 0; k < NPAINTERS; k++) {
            const int cairo_clips = members == 1 && !strncmp(painters[k], "cairo", 5);
            aa_image img;
            support_render(painters[k], s, "box", 16, 16, 1, &img, NULL);
            for (int j = 0; j < 16; j++)
                for (int i = 0; i < 16; i++) {
                    const double val = aa_pixel(&img, i, j)[0];
                    if (i == 10 && !cairo_clips ? !(fabs(val - 0.25) <= 1.0 / 255 + 1e-12)
                                                : val != 0.0)
                        fail_msg("%s, %d member(s): pixel (%d, %d) %.6f, not %s", painters[k],
                                 members, i, j, val,
                                 i == 10 && !cairo_clips ? "1/4 within 1/255" : "0");
                }
            print_message("%-14s %d member(s): column 10 reads %.6f (%s), the exact reference "
                          "0\n",
                          painters[k], members, aa_pixel(&img, 10, 0)[0],
                          cairo_clips ? "Cairo's own clip" : "the product of two halves");
            aa_image_free(&img);
        }
        aa_scene_free(s);
    }
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_group_overlap),
             cmocka_unit_test(test_group_nested),
             cmocka_unit_test(test_clip_disk_by_rect),
             cmocka_unit_test(test_clip_nested),
             cmocka_unit_test(test_clip_evenodd),
             cmocka_unit_test(test_clip_many),
             cmocka_unit_test(test_shipped_clips),
             cmocka_unit_test(test_clip_mask_product))
