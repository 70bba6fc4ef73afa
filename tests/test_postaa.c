/*
 * test_postaa.c: the post-processes of today's real-time renderers, mlaa
 * (Reshetov 2009), fxaa (FXAA 3.11 quality) and smaa (SMAA 1x), against
 * known answers:
 *  - the reconstructed edge's areas (SMAA's area table, aa_morph_area)
 *    against trapezoids and triangles worked out by hand for Z, U and L
 *    shapes;
 *  - straight edges of slope 1/4, 1/2 (26.6 degrees) and 1 (45 degrees)
 *    placed so that their point-sampled staircases turn with their middles
 *    on the edge (the case where the papers' reconstruction is the edge
 *    itself): mlaa and smaa give the exact box-filtered image away from
 *    the image border, the coverage of each pixel by the half-plane
 *    computed here by hand geometry, in colour, along rows and
 *    (transposed) along columns;
 *  - an edge along pixel boundaries: point sampling is exact there, and
 *    mlaa and smaa leave it as it is; fxaa's sub-pixel term blurs it by
 *    0.75 (smoothstep(1/3))^2 = 0.0504, from the whitepaper's formula,
 *    and with subpix=0 leaves it;
 *  - a square on pixel boundaries: its corner pixels lose MLAA's
 *    half-line trapezoids (7/16, then 5/16), and a quarter of those under
 *    SMAA's sharp-corner rule (7/64, 5/64), worked out by hand;
 *  - fxaa on a flat image is the identity; every image stays within the
 *    range of the scene's colours;
 *  - on star and crow each is below point sampling in RMSE against the
 *    exact box reference (the papers' claim that they improve on the
 *    aliased image);
 *  - they refuse a prefilter.
 */
#include "bench.h"
#include "methods.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

static const char *const posts[] = {"mlaa", "fxaa", "smaa"};

/* ---- the area table ---- */

static void check_area(int el, int er, int dl, int dr, double near, double far)
{
    double sh[2];
    aa_morph_area(el, er, dl, dr, sh);
    if (fabs(sh[0] - near) > 1e-15 || fabs(sh[1] - far) > 1e-15)
        fail_msg("area(%d, %d, %d, %d) = (%.17g, %.17g), by hand (%.17g, %.17g)", el, er, dl,
                 dr, sh[0], sh[1], near, far);
}

static void test_area_table(void **state)
{
    (void)state;
    /* turns: 1 toward the near pixel (+1/2), 2 toward the far one (-1/2).
     * Z of length 4 (far at the left, near at the right): the half-lines go
     * from -1/2 at x = 0 to 0 at x = 2 and on to +1/2 at x = 4.  Pixel
     * [0, 1]: a trapezoid of heights 1/2 and 1/4 on the far side, 3/8;
     * [1, 2]: a triangle of height 1/4, 1/8; [2, 3] the same on the near
     * side; [3, 4] 3/8 near. */
    check_area(2, 1, 0, 3, 0.0, 0.375);
    check_area(2, 1, 1, 2, 0.0, 0.125);
    check_area(2, 1, 2, 1, 0.125, 0.0);
    check_area(2, 1, 3, 0, 0.375, 0.0);
    /* U of length 3 (near at both ends): the middle pixel [1, 2] holds two
     * triangles of base 1/2 under half-lines that fall 1/2 over 3/2: height
     * 1/6 each, 1/24 + 1/24 = 1/12; an end pixel a trapezoid 1/2 to 1/6:
     * 1/3 */
    check_area(1, 1, 1, 1, 1.0 / 12.0, 0.0);
    check_area(1, 1, 0, 2, 1.0 / 3.0, 0.0);
    /* L of length 5 (near turn at the left, open right): the half-line from
     * 1/2 at 0 to 0 at 5/2: pixel [0, 1] 1/2 to 3/10, 2/5; pixel [2, 3] the
     * triangle from 1/10 at 2 to 0 at 5/2, 1/40; the right half nothing */
    check_area(1, 0, 0, 4, 0.4, 0.0);
    check_area(1, 0, 2, 2, 0.025, 0.0);
    check_area(1, 0, 3, 1, 0.0, 0.0);
    /* a run one pixel long between opposite turns: the 45-degree line
     * through the turns' middles, 1/8 each side */
    check_area(1, 2, 0, 0, 0.125, 0.125);
    /* a turn to both sides, or none, draws nothing */
    check_area(3, 0, 0, 5, 0.0, 0.0);
    check_area(0, 0, 2, 2, 0.0, 0.0);
    /* long: Z over 65 pixels, the pixel at the left end: heights 1/2 and
     * 1/2 (1 - 1/32.5) */
    check_area(2, 1, 0, 64, 0.0, 0.5 * (0.5 + 0.5 * (1.0 - 1.0 / 32.5)));
}

/* ---- a straight edge through the middles of its staircase's turns ---- */

/* The part of pixel (i, j) below the line y = y0 + x / k (y down): the
 * integral over the pixel's columns of clamp(j + 1 - y(x), 0, 1), which is
 * piecewise linear with kinks where y(x) = j or j + 1. */
static double below_line(int i, int j, double y0, double k)
{
    double xs[4] = {i, i + 1.0, 0, 0};
    int n = 2;
    for (int q = 0; q < 2; q++) {
        double x = (j + q - y0) * k;
        if (x > i && x < i + 1)
            xs[n++] = x;
    }
    for (int a = 0; a < n; a++) /* sort the few points */
        for (int b = a + 1; b < n; b++)
            if (xs[b] < xs[a]) {
                double t = xs[a];
                xs[a] = xs[b], xs[b] = t;
            }
    double area = 0.0;
    for (int a = 0; a + 1 < n; a++) {
        double f0 = j + 1 - (y0 + xs[a] / k), f1 = j + 1 - (y0 + xs[a + 1] / k);
        f0 = f0 < 0 ? 0 : (f0 > 1 ? 1 : f0);
        f1 = f1 < 0 ? 0 : (f1 > 1 ? 1 : f1);
        area += 0.5 * (f0 + f1) * (xs[a + 1] - xs[a]);
    }
    return area;
}

static void test_slope_exact(void **state)
{
    (void)state;
    /* The line y = y0 + x/k crosses the pixel centres' heights j + 1/2 at
     * x = k (j + 1/2 - y0), on pixel boundaries for these y0: the turns of
     * its staircase are centred on it.  Slope 1/4 (runs of 4), 1/2 (26.6
     * degrees, runs of 2) and 1 (45 degrees, runs of 1 between opposite
     * turns, the 45-degree line through their middles).  Inside below it,
     * outside above; transposed (x = y0 + y/k), the same along columns. */
    static const struct {
        double k, y0;
        int w, h;
    } lines[] = {{4, 4, 32, 16}, {2, 4, 32, 24}, {1, 4.5, 32, 40}};
    const aa_rgb in = {{1.0, 0.8, 0.2}}, out = {{0.1, 0.2, 0.6}};
    for (size_t q = 0; q < sizeof lines / sizeof *lines; q++)
        for (int tr = 0; tr < 2; tr++) {
            const double k = lines[q].k, y0 = lines[q].y0;
            const int w = lines[q].w, h = lines[q].h;
            const int W = tr ? h : w, H = tr ? w : h; /* the image */
            double p[4][2] = {{0, y0}, {w, y0 + w / k}, {w, h}, {0, h}};
            double xy[8];
            for (int c = 0; c < 4; c++) {
                double x = tr ? p[c][1] : p[c][0], y = tr ? p[c][0] : p[c][1];
                xy[2 * c] = x / W, xy[2 * c + 1] = y / H;
            }
            aa_scene *s = scenes_polygon(xy, 4, in, out, AA_FILL_NONZERO);
            for (int m = 0; m < 3; m += 2) { /* mlaa, smaa */
                /* smaa's diagonal patterns read the 45-degree staircase
                 * as a diagonal line (test_diag_staircase); its orthogonal
                 * patterns alone are the ones exact here.  At slopes 1/4
                 * and 1/2 no pixel's diagonal holds four steps in a row
                 * (a step every 4 or 2 pixels), so the diagonal search
                 * finds nothing and smaa is itself. */
                const char *spec = m == 2 && k == 1 ? "smaa:diag=0" : posts[m];
                aa_image img;
                support_render(spec, s, NULL, W, H, 2, &img, NULL);
                double worst = 0.0;
                /* columns 4 .. w-5 along the line: away from the runs that
                 * end at the image border (open ends, drawn by half) */
                for (int u = 4; u < w - 4; u++)
                    for (int v = 0; v < h; v++) {
                        double c = below_line(u, v, y0, k);
                        const double *px = tr ? aa_pixel(&img, v, u) : aa_pixel(&img, u, v);
                        for (int ch = 0; ch < 3; ch++) {
                            double want = out.c[ch] + c * (in.c[ch] - out.c[ch]);
                            double e = fabs(px[ch] - want);
                            worst = e > worst ? e : worst;
                            if (e > 1e-12)
                                fail_msg("%s%s, slope 1/%g: pixel (%d, %d) channel %d is "
                                         "%.15g, the half-plane's box value %.15g",
                                         spec, tr ? " (transposed)" : "", k, tr ? v : u,
                                         tr ? u : v, ch, px[ch], want);
                        }
                    }
                print_message("%s%s, slope 1/%g through the turns' middles: largest error "
                              "%.1e\n",
                              spec, tr ? " (along columns)" : "", k, worst);
                aa_image_free(&img);
            }
            aa_scene_free(s);
        }
}

/* ---- SMAA's diagonal patterns ---- */

static void check_diag(int el, int er, int dl, int dr, double px, double above)
{
    double sh[2];
    aa_morph_diag_area(el, er, dl, dr, sh);
    if (fabs(sh[0] - px) > 1e-15 || fabs(sh[1] - above) > 1e-15)
        fail_msg("diagonal area(%d, %d, %d, %d) = (%.17g, %.17g), by hand (%.17g, %.17g)", el,
                 er, dl, dr, sh[0], sh[1], px, above);
}

static void test_diag_area_table(void **state)
{
    (void)state;
    /* The frame of morph.c's step 8, y up: the line's pixels are the
     * squares [1 + l, 2 + l] x [l, 1 + l] (l = 0 .. d - 1, d = dl + dr + 1),
     * each with its west and north sides on the staircase; the outer
     * corners (1 + l, 1 + l) lie on y = x, the inner ones (1 + l, l) on
     * y = x - 1.  The pixel at l = dl takes the part of its square above
     * the line, the one above it ([1 + l, 2 + l] x [1 + l, 2 + l]) the part
     * of its square below.
     * Both ends unknown: the mean of y = x (the pixel wholly below: 0; the
     * one above halved: 1/2) and y = x - 1 (1/2; 0): 1/4 each, whatever
     * the distances. */
    check_diag(0, 0, 0, 5, 0.25, 0.25);
    check_diag(0, 0, 3, 3, 0.25, 0.25);
    check_diag(0, 0, 8, 7, 0.25, 0.25);
    /* turning down at the lower end, right at the upper: from (1, 0) to
     * (1 + d, d), the line y = x - 1 through the inner corners: 1/2, 0 */
    check_diag(1, 2, 2, 3, 0.5, 0.0);
    /* turning left at the lower end, up at the upper: (1, 1) to
     * (1 + d, 1 + d), y = x: 0, 1/2 */
    check_diag(2, 1, 4, 1, 0.0, 0.5);
    /* left at the lower end, right at the upper, d = 4: from (1, 1) to
     * (5, 4), slope 3/4.  The pixel [2, 3] x [1, 2] (dl = 1): the line
     * meets x = 2 at y = 7/4 and y = 2 at x = 7/3, the triangle above it
     * 1/2 (1/4) (1/3) = 1/24; the one above, [2, 3] x [2, 3]: below the
     * line from (7/3, 2) to (3, 5/2), 1/2 (2/3) (1/2) = 1/6 */
    check_diag(2, 2, 1, 2, 1.0 / 24.0, 1.0 / 6.0);
    /* down at the lower end, the upper unknown, d = 4, the pixel at dl = 0
     * ([1, 2] x [0, 1]): the mean of the lines from (1, 0) to (4, 4) (slope
     * 4/3: it leaves the square's top at x = 7/4, the triangle left of it
     * 3/8; above, the triangle (7/4, 1), (2, 1), (2, 4/3), 1/24) and to
     * (5, 4) (y = x - 1: 1/2; 0): 7/16 and 1/48 */
    check_diag(1, 0, 0, 3, 7.0 / 16.0, 1.0 / 48.0);
    /* crossing at both ends, both sides: the mean of y = x and y = x - 1,
     * as unknown ends */
    check_diag(3, 3, 2, 2, 0.25, 0.25);
}

/* The half-plane below y = y0 + x/k in a w x h frame, placed in the image
 * by `orient`: bit 0 mirrors (x -> w - x), bit 1 transposes (the image h x
 * w, the frame's x down its columns). */
static const double *frame_pixel(const aa_image *img, int u, int v, int w, int orient)
{
    int x = orient & 1 ? w - 1 - u : u;
    return orient & 2 ? aa_pixel(img, v, x) : aa_pixel(img, x, v);
}

/* RMSE of an image against the box-filtered half-plane, the frame's
 * columns 4 .. w-5, two colours. */
static double line_rmse(const aa_image *img, double y0, double k, int w, int h, int orient,
                        aa_rgb in, aa_rgb out)
{
    double sum = 0.0;
    size_t n = 0;
    for (int u = 4; u < w - 4; u++)
        for (int v = 0; v < h; v++) {
            double c = below_line(u, v, y0, k);
            const double *px = frame_pixel(img, u, v, w, orient);
            for (int ch = 0; ch < 3; ch++) {
                double e = px[ch] - (out.c[ch] + c * (in.c[ch] - out.c[ch]));
                sum += e * e, n++;
            }
        }
    return sqrt(sum / (double)n);
}

static aa_scene *below_line_scene(double y0, double k, int w, int h, int orient, aa_rgb in,
                                  aa_rgb out)
{
    double p[4][2] = {{0, y0}, {w, y0 + w / k}, {w, h}, {0, h}};
    double xy[8];
    for (int c = 0; c < 4; c++) {
        double x = (orient & 1 ? w - p[c][0] : p[c][0]) / w, y = p[c][1] / h;
        xy[2 * c] = orient & 2 ? y : x, xy[2 * c + 1] = orient & 2 ? x : y;
    }
    return scenes_polygon(xy, 4, in, out, AA_FILL_NONZERO);
}

static void test_diag_staircase(void **state)
{
    (void)state;
    const aa_rgb in = {{1.0, 0.8, 0.2}}, out = {{0.1, 0.2, 0.6}};
    const int w = 32, h = 40;
    for (int mirror = 0; mirror < 2; mirror++) {
        /* The 45-degree line y = 4.5 + x (falling to the right; mirrored,
         * rising: the other diagonal), point sampled: one step a pixel, no
         * pixel's run longer than one, so every pixel beside the staircase
         * is on a diagonal line of 4 or more steps whose ends are the
         * image's borders (no crossing sides): both ends unknown.  The
         * diagonal area table gives such a pixel 1/4 of the colour across
         * (test_diag_area_table: the mean of the lines through the outer
         * and the inner corners, the first missing the pixel, the second
         * halving it).  The box-filtered image is 1/8 there: the edge
         * itself is the line through the steps' middles (y = x - 1/2 in
         * that frame), which cuts the corner 1/2 x 1/2 / 2 from each pixel
         * (the orthogonal patterns draw exactly that, test_slope_exact). */
        aa_scene *s = below_line_scene(4.5, 1.0, w, h, mirror, in, out);
        aa_image img, orth;
        support_render("smaa", s, NULL, w, h, 2, &img, NULL);
        support_render("smaa:diag=0", s, NULL, w, h, 2, &orth, NULL);
        int beside = 0;
        for (int u = 4; u < w - 4; u++)
            for (int v = 0; v < h; v++) {
                double c = below_line(u, v, 4.5, 1.0);
                double share = c > 0.5 && c < 1 ? 0.75 : (c > 0 && c < 0.5 ? 0.25 : c);
                beside += c > 0 && c < 1;
                const double *px = frame_pixel(&img, u, v, w, mirror);
                for (int ch = 0; ch < 3; ch++) {
                    double want = out.c[ch] + share * (in.c[ch] - out.c[ch]);
                    if (fabs(px[ch] - want) > 1e-12)
                        fail_msg("smaa, 45 degrees%s: pixel (%d, %d) channel %d is %.15g, the "
                                 "diagonal table's %.15g",
                                 mirror ? " (rising)" : "", mirror ? w - 1 - u : u, v, ch,
                                 px[ch], want);
                }
            }
        assert_int_equal(beside, 2 * (w - 8));
        double ed = line_rmse(&img, 4.5, 1.0, w, h, mirror, in, out);
        double eo = line_rmse(&orth, 4.5, 1.0, w, h, mirror, in, out);
        /* every pixel beside the line 1/8 of the contrast off, 2 of the
         * h = 40 in each column: RMSE over the channels (0.9, 0.6, 0.4)
         * sqrt(2/40 (0.81 + 0.36 + 0.16)/3) / 8 */
        const double hand = sqrt(2.0 / 40.0 * (0.81 + 0.36 + 0.16) / 3.0) / 8.0;
        if (fabs(ed - hand) > 1e-12 || !(eo < 1e-12))
            fail_msg("45 degrees: smaa RMSE %.15g (by hand %.15g), smaa:diag=0 %.3g (exact)",
                     ed, hand, eo);
        print_message("45 degrees%s through the steps' middles: RMSE smaa %.4f (1/8 of the "
                      "contrast beside the line), smaa:diag=0 %.1e\n",
                      mirror ? " rising" : " falling", ed, eo);
        aa_image_free(&img);
        aa_image_free(&orth);
        aa_scene_free(s);
    }
    /* Near 45 degrees, slope 1/1.2: runs of one pixel with one of two every
     * six columns; the diagonal search fires on the stretches between
     * them.  Over the line's positions (ten offsets a tenth of a pixel
     * apart), the RMSE of each against the box-filtered half-plane (hand
     * geometry, below_line): the paper's claim that the diagonal patterns
     * reconstruct such lines better than the orthogonal ones, checked.
     * Falling and rising (mirrored), along rows and (transposed, slope 1.2)
     * along columns. */
    static const char *const orients[] = {"falling", "rising", "falling, along columns",
                                          "rising, along columns"};
    for (int o = 0; o < 4; o++) {
        double sd = 0.0, so = 0.0;
        int fired = 0;
        const int W = o & 2 ? h : w, H = o & 2 ? w : h;
        for (int t = 0; t < 10; t++) {
            const double y0 = 4.0 + 0.1 * t + 0.05;
            aa_scene *s = below_line_scene(y0, 1.2, w, h, o, in, out);
            aa_image img, orth;
            support_render("smaa", s, NULL, W, H, 2, &img, NULL);
            support_render("smaa:diag=0", s, NULL, W, H, 2, &orth, NULL);
            fired += !support_same_image(&img, &orth);
            sd += line_rmse(&img, y0, 1.2, w, h, o, in, out);
            so += line_rmse(&orth, y0, 1.2, w, h, o, in, out);
            aa_image_free(&img);
            aa_image_free(&orth);
            aa_scene_free(s);
        }
        assert_int_equal(fired, 10);
        if (!(sd < so))
            fail_msg("slope 1/1.2, %s: smaa's mean RMSE %.4f not below smaa:diag=0's %.4f",
                     orients[o], sd / 10, so / 10);
        print_message("slope 1/1.2, %s, mean RMSE over 10 offsets: smaa %.4f, smaa:diag=0 "
                      "%.4f\n",
                      orients[o], sd / 10, so / 10);
    }
}

/* ---- edges along pixel boundaries ---- */

static void test_aligned_edges(void **state)
{
    (void)state;
    /* white where x < 10 (a vertical edge), then where y < 7 (a
     * horizontal one), across the whole image */
    const int w = 24, h = 16;
    const double vert[] = {0, 0, 10.0 / w, 0, 10.0 / w, 1, 0, 1};
    const double horz[] = {0, 0, 1, 0, 1, 7.0 / h, 0, 7.0 / h};
    const aa_rgb white = {{1, 1, 1}}, black = {{0, 0, 0}};
    for (int k = 0; k < 2; k++) {
        aa_scene *s = scenes_polygon(k ? horz : vert, 4, white, black, AA_FILL_NONZERO);
        aa_image pt, img;
        support_render("point", s, NULL, w, h, 1, &pt, NULL);
        for (int m = 0; m < 3; m++) {
            const char *spec = m == 1 ? "fxaa:subpix=0" : posts[m];
            support_render(spec, s, NULL, w, h, 1, &img, NULL);
            if (!support_same_image(&pt, &img))
                fail_msg("%s changed a %s edge on pixel boundaries", spec,
                         k ? "horizontal" : "vertical");
            aa_image_free(&img);
        }
        /* fxaa's sub-pixel term: each pixel beside the edge sees the mean
         * of its neighbours (2 (3 + 0) + (2 + 0)) / 12 = 2/3 against its 1 (or
         * 1/3 against 0): |difference| / range 1/3, smoothstep 7/27, squared
         * times subpix 3/4: it takes 0.75 (7/27)^2 of the other side */
        const double sub = 0.75 * (7.0 / 27.0) * (7.0 / 27.0);
        support_render("fxaa", s, NULL, w, h, 1, &img, NULL);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                int pos = k ? j : i, edge = k ? 7 : 10;
                double want = pos == edge - 1 ? 1.0 - sub
                              : pos == edge   ? sub
                                              : (pos < edge ? 1.0 : 0.0);
                double got = aa_pixel(&img, i, j)[0];
                if (fabs(got - want) > 1e-12)
                    fail_msg("fxaa, %s edge: pixel (%d, %d) is %.15g, want %.15g",
                             k ? "horizontal" : "vertical", i, j, got, want);
            }
        aa_image_free(&img);
        aa_image_free(&pt);
        aa_scene_free(s);
    }
    print_message("aligned edges: mlaa, smaa, fxaa:subpix=0 unchanged; fxaa blurs by %.4f\n",
                  0.75 * (7.0 / 27.0) * (7.0 / 27.0));
}

/* ---- corners of a square ---- */

static void test_square_corners(void **state)
{
    (void)state;
    /* A white square [4, 12] x [4, 12] on black, 16 x 16, on pixel
     * boundaries: point sampling is exact, but each side is a run of 8
     * whose ends turn the same way (a U): MLAA's half-lines fall from 1/2
     * at the corner to 0 at the side's middle (x = 8), so the corner pixel
     * [4, 5] loses the trapezoid (1/2 + 3/8) / 2 = 7/16 of its white and
     * the next one [5, 6] (3/8 + 1/4) / 2 = 5/16 (one direction: the row
     * line and the column line give the corner pixel 7/16 each, and it
     * blends with one of them).  SMAA sees that the turn goes on straight
     * past the pixel's row (the square's left side): a sharp corner, the
     * share kept at 1/4: 7/64 and 5/64. */
    const double sq[] = {4 / 16.0, 4 / 16.0, 12 / 16.0, 4 / 16.0,
                         12 / 16.0, 12 / 16.0, 4 / 16.0, 12 / 16.0};
    const aa_rgb white = {{1, 1, 1}}, black = {{0, 0, 0}};
    aa_scene *s = scenes_polygon(sq, 4, white, black, AA_FILL_NONZERO);
    static const struct {
        const char *method;
        double corner, next;
    } want[] = {{"mlaa", 1 - 7.0 / 16, 1 - 5.0 / 16},
                {"smaa", 1 - 7.0 / 64, 1 - 5.0 / 64},
                {"smaa:rounding=1", 1 - 7.0 / 16, 1 - 5.0 / 16}};
    for (int m = 0; m < 3; m++) {
        aa_image img;
        support_render(want[m].method, s, NULL, 16, 16, 1, &img, NULL);
        /* the four corners alike, and the pixel beside each along a side */
        const int corners[4][4] = {{4, 4, 5, 4}, {11, 4, 10, 4}, {4, 11, 4, 10}, {11, 11, 11, 10}};
        for (int k = 0; k < 4; k++) {
            double c = aa_pixel(&img, corners[k][0], corners[k][1])[0];
            double n = aa_pixel(&img, corners[k][2], corners[k][3])[0];
            if (fabs(c - want[m].corner) > 1e-12 || fabs(n - want[m].next) > 1e-12)
                fail_msg("%s, corner %d: %.15g and %.15g beside it, by hand %.15g and %.15g",
                         want[m].method, k, c, n, want[m].corner, want[m].next);
        }
        /* outside the square nothing changes: the black pixels take no
         * share (each turn lies on the square's side of the line) */
        for (int j = 0; j < 16; j++)
            for (int i = 0; i < 16; i++)
                if ((i < 4 || i >= 12 || j < 4 || j >= 12) && aa_pixel(&img, i, j)[0] != 0.0)
                    fail_msg("%s: outside pixel (%d, %d) is %.15g", want[m].method, i, j,
                             aa_pixel(&img, i, j)[0]);
        aa_image_free(&img);
    }
    aa_scene_free(s);
    print_message("square corners: mlaa %.4f, smaa %.4f (rounding 1/4)\n", 1 - 7.0 / 16,
                  1 - 7.0 / 64);
}

/* ---- flat images, range ---- */

static void test_flat_and_range(void **state)
{
    (void)state;
    /* a rectangle covering the whole image: flat */
    const double all[] = {-1, -1, 2, -1, 2, 2, -1, 2};
    const aa_rgb c = {{0.3, 0.6, 0.9}}, bg = {{0, 0, 0}};
    aa_scene *flat = scenes_polygon(all, 4, c, bg, AA_FILL_NONZERO);
    for (int m = 0; m < 3; m++) {
        aa_image img;
        support_render(posts[m], flat, NULL, 17, 13, 1, &img, NULL);
        for (int j = 0; j < 13; j++)
            for (int i = 0; i < 17; i++)
                for (int ch = 0; ch < 3; ch++)
                    assert_true(aa_pixel(&img, i, j)[ch] == c.c[ch]);
        aa_image_free(&img);
    }
    aa_scene_free(flat);
    /* star and crow: every value within [0, 1], the scenes' colours */
    const char *const scenes[] = {"star", "crow"};
    for (int k = 0; k < 2; k++) {
        aa_scene *s = scenes_pattern(scenes[k]);
        for (int m = 0; m < 3; m++) {
            aa_image img;
            support_render(posts[m], s, NULL, 96, 96, 2, &img, NULL);
            for (size_t q = 0; q < (size_t)96 * 96 * 3; q++)
                if (!(img.v[q] >= 0.0 && img.v[q] <= 1.0))
                    fail_msg("%s on %s: value %.17g outside [0, 1]", posts[m], scenes[k],
                             img.v[q]);
            aa_image_free(&img);
        }
        aa_scene_free(s);
    }
}

/* ---- below point sampling ---- */

static void test_below_point(void **state)
{
    (void)state;
    const char *const scenes[] = {"star", "crow"};
    const support_view v = {128, 128, 0, 0, 0, NULL, 1, 2, 0};
    for (int k = 0; k < 2; k++) {
        aa_scene *s = scenes_pattern(scenes[k]);
        for (int m = 0; m < 3; m++) {
            const char *const order[] = {"point", posts[m]};
            char what[64];
            snprintf(what, sizeof what, "%s on %s", posts[m], scenes[k]);
            support_check_rmse_order(what, s, &v, order, 2);
        }
        aa_scene_free(s);
    }
}

static void test_refuse_prefilter(void **state)
{
    (void)state;
    for (int m = 0; m < 3; m++) {
        assert_int_equal(support_parse_method(posts[m], "tent:r=1", NULL), AA_EINVAL);
        assert_int_equal(support_parse_method(posts[m], NULL, NULL), AA_OK);
    }
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_area_table), cmocka_unit_test(test_slope_exact),
             cmocka_unit_test(test_diag_area_table), cmocka_unit_test(test_diag_staircase),
             cmocka_unit_test(test_aligned_edges), cmocka_unit_test(test_square_corners),
             cmocka_unit_test(test_flat_and_range),
             cmocka_unit_test(test_below_point), cmocka_unit_test(test_refuse_prefilter))
