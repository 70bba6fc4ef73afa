/*
 * test_temporal_post.c: Crow's temporal hexagon scheme (algorithms/hexagon.c,
 * Crow 1976 fig. 4.1) and the post-processes of a point-sampled image
 * (algorithms/trio.c, Crow ch. 4, figs. 4.2-4.3), beyond the generic tests
 * of test_methods.c.
 *
 * hexagon (display=fixed, the model of earlier versions; the screen display
 * and the random path are tested in test_crow_methods.c):
 *  - the eye's image is the mean of its frames, each rendered alone with
 *    frame_only at the window's times (T, T-1, ..., moving scene, real and
 *    negative T, several windows and orders);
 *  - each frame samples at the pixel centres moved by the vertex
 *    order[floor(T) mod 6] of a hexagon of the given radius and angle: every
 *    pixel of a test-only scene of many coloured triangles equals the
 *    scene's colour at that point, with the vertices derived here by
 *    turning vertex 0 by 60 degrees with a rotation matrix;
 *  - radius 0 is point sampling; the counters;
 *  - on crow 256x256, still and moving slowly, the eye's image is nearer
 *    the box reference (aa_truth_render) at T than point's frame at T;
 *    moving, also nearer the mean of the references of the six frames (what
 *    an eye integrating six frames should see) than the mean of six point
 *    frames is.
 * trio:
 *  - an edge lying on pixel boundaries (rectangles, a bar one dot thick) is
 *    left as sampled, and by variant=halflines a 45-degree staircase;
 *  - a staircase of runs of two dots gives fig. 4.3's answer, 3/4 and 1/4,
 *    for a mostly-horizontal and a mostly-vertical edge;
 *  - slanted straight edges (colour) move toward the box reference: RMSE
 *    lower than point's;
 *  - sancha: threshold 1 changes nothing; known compromises 1/2 and 1/3;
 *  - recursive: a step gives the values worked out by hand;
 *  - 1, 2 and 3 threads agree bit for bit on a larger image (the recursive
 *    filter's pipeline), and the counters.
 */
#include "bench.h"
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

/* ---- scenes (pattern units) ---- */

/* A colour inside the polygon (x, y pairs), another outside. */
static aa_scene *polygon_scene(const double *xy, int n, aa_rgb inside, aa_rgb outside)
{
    return scenes_polygon(xy, n, inside, outside, AA_FILL_NONZERO);
}

/* ---- rendering ---- */

static int render_at(const char *method, const aa_scene *scene, int w, int h, double t,
                     double vx, double vy, int frame_only, int threads, aa_image *out,
                     aa_counters *c)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .seed = 1,
                            .threads = threads, .frame_only = frame_only};
    support_render_must(method, scene, &v, out, c);
    return AA_OK;
}

static void render(const char *method, const aa_scene *scene, int w, int h, aa_image *out,
                   aa_counters *c)
{
    assert_int_equal(render_at(method, scene, w, h, 0, 0, 0, 0, 2, out, c), AA_OK);
}

static void reference(const aa_scene *scene, int w, int h, double t, double vx, double vy,
                      aa_image *out)
{
    support_reference(scene, &(support_view){.w = w, .h = h, .t = t, .vx = vx, .vy = vy}, out,
                      NULL, NULL);
}

/* ---- hexagon ---- */

/* The eye's image against the plain mean of its frames rendered alone. */
static void check_eye(const char *method, int frames, double t, double vx, double vy)
{
    const int w = 37, h = 23;
    aa_scene *s = scenes_pattern("crow");
    aa_image eye, frame, sum;
    aa_counters c;
    assert_int_equal(render_at(method, s, w, h, t, vx, vy, 0, 2, &eye, &c), AA_OK);
    assert_true(c.samples == (uint64_t)frames * w * h);
    assert_int_equal(aa_image_alloc(&sum, w, h, 3), AA_OK);
    memset(sum.v, 0, sizeof(double) * 3 * w * h);
    int differs = 0;
    for (int k = 0; k < frames; k++) {
        assert_int_equal(render_at(method, s, w, h, t - k, vx, vy, 1, 1, &frame, &c), AA_OK);
        assert_true(c.samples == (uint64_t)w * h);
        for (int q = 0; q < 3 * w * h; q++)
            sum.v[q] += frame.v[q];
        differs += !support_same_image(&frame, &eye);
        aa_image_free(&frame);
    }
    double worst = 0;
    for (int q = 0; q < 3 * w * h; q++)
        worst = fmax(worst, fabs(sum.v[q] / frames - eye.v[q]));
    print_message("%-40s T=%6.2f v=(%g, %g): max |eye - mean of %d frames| %.2e\n", method, t,
                  vx, vy, frames, worst);
    /* the running mean and the plain mean differ by rounding only */
    assert_true(worst <= 1e-14);
    if (frames > 1)
        assert_true(differs == frames); /* the eye's image is no single frame */
    aa_image_free(&sum);
    aa_image_free(&eye);
    aa_scene_free(s);
}

static void test_hexagon_eye_is_mean_of_frames(void **state)
{
    (void)state;
    check_eye("hexagon:display=fixed", 6, 0.0, 0.0, 0.0);
    check_eye("hexagon:display=fixed", 6, 7.25, 0.37, -0.21);
    check_eye("hexagon:frames=4,order=012345,display=fixed", 4, -2.5, -0.4, 0.3);
    check_eye("hexagon:frames=13,order=031425,radius=0.7,angle=20,display=fixed", 13, 100.9,
              0.05, 0.02);
    check_eye("hexagon:frames=1,display=fixed", 1, 3.0, 1.0, 0.0);
}

static void check_offsets(const char *method, double r, double angle, const char *order)
{
    const int w = 41, h = 29;
    const double vx = 0.3, vy = -0.7;
    aa_scene *s = scenes_triangles(12345);
    for (double t = -7.5; t <= 6.0; t += 1.25) {
        int n = (int)floor(t), v = order[((n % 6) + 6) % 6] - '0';
        double dx[6], dy[6];
        for (int q = 0; q < 6; q++)
            oracle_hexagon_vertex(r, angle, q, &dx[q], &dy[q]);
        /* the vertices are those of a regular hexagon of radius r */
        for (int q = 0; q < 6; q++) {
            assert_true(fabs(hypot(dx[q], dy[q]) - r) < 1e-15);
            double ex = dx[(q + 1) % 6] - dx[q], ey = dy[(q + 1) % 6] - dy[q];
            assert_true(fabs(hypot(ex, ey) - r) < 1e-15);
        }
        aa_image img;
        assert_int_equal(render_at(method, s, w, h, t, vx, vy, 1, 2, &img, NULL), AA_OK);
        aa_scene *placed = aa_scene_place(s, w, h, t, vx, vy);
        int moved = 0, other[6] = {0};
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                const double *px = aa_pixel(&img, i, j);
                aa_rgb want = aa_scene_colour_at(placed, i + 0.5 + dx[v], j + 0.5 + dy[v]);
                for (int ch = 0; ch < 3; ch++)
                    if (px[ch] != want.c[ch])
                        fail_msg("%s T=%g pixel (%d, %d): %g, the scene at vertex %d has %g",
                                 method, t, i, j, px[ch], v, want.c[ch]);
                aa_rgb centre = aa_scene_colour_at(placed, i + 0.5, j + 0.5);
                moved += centre.c[0] != px[0] || centre.c[1] != px[1] || centre.c[2] != px[2];
                for (int q = 0; q < 6; q++) {
                    aa_rgb o = aa_scene_colour_at(placed, i + 0.5 + dx[q], j + 0.5 + dy[q]);
                    other[q] += o.c[0] != px[0] || o.c[1] != px[1] || o.c[2] != px[2];
                }
            }
        /* the test tells the positions apart: the centre and every other
         * vertex would give another image */
        assert_true(moved > w * h / 20);
        for (int q = 0; q < 6; q++)
            if (q != v && !(other[q] > w * h / 50))
                fail_msg("%s: vertex %d is not told apart from vertex %d", method, q, v);
        aa_scene_free(placed);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

static void test_hexagon_offsets(void **state)
{
    (void)state;
    check_offsets("hexagon:order=024153,display=fixed", 0.5, 0.0, "024153");
    check_offsets("hexagon:order=012345,display=fixed", 0.5, 0.0, "012345");
    check_offsets("hexagon:radius=0.3,angle=10,order=031425,display=fixed", 0.3, 10.0, "031425");
    check_offsets("hexagon:radius=0.8,angle=45,order=014523,display=fixed", 0.8, 45.0, "014523");
}

static void test_hexagon_radius_zero_is_point(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    aa_image a, b;
    assert_int_equal(render_at("hexagon:radius=0", s, 64, 40, 2.5, 0, 0, 0, 2, &a, NULL), AA_OK);
    assert_int_equal(render_at("point", s, 64, 40, 2.5, 0, 0, 0, 2, &b, NULL), AA_OK);
    assert_true(support_same_image(&a, &b));
    aa_image_free(&a);
    aa_image_free(&b);
    aa_scene_free(s);
}

/* Mean of point frames or references over the window T, T-1, ..., T-5. */
static void window_mean(const aa_scene *s, int w, int h, double t, double vx, double vy,
                        int truth, aa_image *out)
{
    assert_int_equal(aa_image_alloc(out, w, h, 3), AA_OK);
    memset(out->v, 0, sizeof(double) * 3 * w * h);
    for (int k = 0; k < 6; k++) {
        aa_image f;
        if (truth)
            reference(s, w, h, t - k, vx, vy, &f);
        else
            assert_int_equal(render_at("point", s, w, h, t - k, vx, vy, 0, 2, &f, NULL), AA_OK);
        for (int q = 0; q < 3 * w * h; q++)
            out->v[q] += f.v[q] / 6;
        aa_image_free(&f);
    }
}

static void test_hexagon_beats_point_on_crow(void **state)
{
    (void)state;
    const int n = 256;
    aa_scene *s = scenes_pattern("crow");
    /* T, vx, vy, and whether the hexagon must win.  Crow meant the scheme
     * for still or slowly moving images ("when the dot positions are
     * constant and the edge position slowly varying, the staircases are
     * quite apparent"); the last case, moving 0.4 px a frame, is printed but
     * not asserted: its six frames are smeared over 2 px, and the motion
     * alone already spreads six point frames over distinct positions, so
     * the hexagon's offsets (samples on the box's border) only add error. */
    const double motion[4][4] = {
        {0, 0, 0, 1}, {5.5, 0.1, 0.05, 1}, {3.25, -0.04, 0.09, 1}, {12, -0.35, 0.2, 0}};
    for (int m = 0; m < 4; m++) {
        double t = motion[m][0], vx = motion[m][1], vy = motion[m][2];
        aa_image ref, hex, pt, ref_eye, pt_eye;
        reference(s, n, n, t, vx, vy, &ref);
        assert_int_equal(
            render_at("hexagon:display=fixed,order=024153", s, n, n, t, vx, vy, 0, 2, &hex, NULL),
            AA_OK);
        assert_int_equal(render_at("point", s, n, n, t, vx, vy, 0, 2, &pt, NULL), AA_OK);
        double eh = support_rmse(&hex, &ref), ep = support_rmse(&pt, &ref);
        print_message("crow %dx%d T=%-4g v=(%g, %g) vs the box reference at T: hexagon RMSE "
                      "%.4e, point %.4e\n",
                      n, n, t, vx, vy, eh, ep);
        if (motion[m][3] != 0 && !(eh < ep))
            fail_msg("hexagon %.4e is not below point %.4e", eh, ep);
        if (vx != 0 || vy != 0) {
            /* what an eye integrating six frames should see, and what it
             * sees of point sampling */
            window_mean(s, n, n, t, vx, vy, 1, &ref_eye);
            window_mean(s, n, n, t, vx, vy, 0, &pt_eye);
            double fh = support_rmse(&hex, &ref_eye), fp = support_rmse(&pt_eye, &ref_eye);
            print_message("%38s vs the mean of the six frames' references: hexagon %.4e, six "
                          "point frames %.4e\n",
                          "", fh, fp);
            if (motion[m][3] != 0 && !(fh < fp))
                fail_msg("eye-integrated: hexagon %.4e is not below point %.4e", fh, fp);
            aa_image_free(&ref_eye);
            aa_image_free(&pt_eye);
        }
        aa_image_free(&ref);
        aa_image_free(&hex);
        aa_image_free(&pt);
    }
    aa_scene_free(s);
}

/* ---- trio ---- */

static void check_unchanged(const char *method, const char *what, const aa_scene *s, int w,
                            int h)
{
    aa_image a, b;
    aa_counters c;
    render(method, s, w, h, &a, &c);
    render("point", s, w, h, &b, NULL);
    if (!support_same_image(&a, &b))
        fail_msg("%s changed %s", method, what);
    print_message("%s leaves %s as sampled (%llu pixels examined)\n", method, what,
                  (unsigned long long)c.expensive_pixels);
    aa_image_free(&a);
    aa_image_free(&b);
}

static void test_trio_keeps_aligned_edges(void **state)
{
    (void)state;
    const int w = 41, h = 29;
    const aa_rgb orange = {{0.9, 0.5, 0.1}}, teal = {{0.1, 0.6, 0.5}};
    /* rectangles on pixel boundaries (x = i/w, y = j/h), two colours, one
     * of them a bar one dot thick, another touching the image border */
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, orange, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 5.0 / w, 4.0 / h, 19.0 / w, 17.0 / h);
    scenes_rect(s, 22.0 / w, 3.0 / h, 37.0 / w, 4.0 / h);
    assert_int_equal(aa_scene_layer(s, teal, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 12.0 / w, 10.0 / h, 30.0 / w, 25.0 / h);
    scenes_rect(s, 35.0 / w, 20.0 / h, 1.0, 1.0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_unchanged("trio", "rectangles on pixel boundaries", s, w, h);
    aa_scene_free(s);
    /* a 45-degree staircase on a w x w image: y = x + 0.3 px, so dot (i, j)
     * is inside when j >= i + 1 and every run is one dot long */
    const double tri[] = {0, 0.3 / w, 1.0, 1.0 + 0.3 / w, 0, 1.0};
    s = polygon_scene(tri, 3, white, black);
    /* the variant of earlier versions (tests/test_crow_methods.c: the default's eighths) */
    check_unchanged("trio:variant=halflines", "a 45-degree staircase", s, w, w);
    aa_scene_free(s);
}

/* Fig. 4.3: an edge of slope 1/2 in pixel units sampled into runs of two
 * dots.  Worked out from the construction: the line through the middles of
 * consecutive steps crosses the boundary at the middle of each run; over the
 * run's first column it lies half a dot to zero beyond the boundary on one
 * side (area 1/4), over the second column zero to half a dot on the other.
 * So in each column exactly one of the two dots beside the edge changes,
 * keeping 3/4 of its colour and taking 1/4 of the other side's: Crow's
 * "the image dot at X receives an intensity 3/4 that of the outside and
 * 1/4 that of the intensity inside the polygon".  `vertical` transposes the
 * scene (slope 2, runs of two along columns). */
static void check_fig43(int vertical)
{
    const int n = 40, m = 28; /* along, across */
    const int w = vertical ? m : n, h = vertical ? n : m;
    /* edge: across = 0.3 + along/2 (pixel units), inside (white) beyond it */
    double xy[8] = {0, 0.3, (double)n, 0.3 + n / 2.0, (double)n, (double)m + 5, 0, (double)m + 5};
    for (int k = 0; k < 4; k++) {
        double along = xy[2 * k], across = xy[2 * k + 1];
        xy[2 * k] = (vertical ? across : along) / w;
        xy[2 * k + 1] = (vertical ? along : across) / h;
    }
    aa_scene *s = polygon_scene(xy, 4, white, black);
    aa_image tr, pt;
    render("trio", s, w, h, &tr, NULL);
    render("point", s, w, h, &pt, NULL);
    int quarter = 0, three = 0;
    for (int a = 0; a < n; a++) {
        /* the first dot inside along this column (row if vertical) */
        int first = (int)ceil((a + 0.5) / 2.0 + 0.3 - 0.5);
        for (int c = 0; c < m; c++) {
            int i = vertical ? c : a, j = vertical ? a : c;
            double got = aa_pixel(&tr, i, j)[0], was = aa_pixel(&pt, i, j)[0];
            assert_true(was == (c >= first ? 1.0 : 0.0));
            assert_true(aa_pixel(&tr, i, j)[1] == got && aa_pixel(&tr, i, j)[2] == got);
            if (a < 3 || a > n - 4 || (c != first - 1 && c != first)) {
                /* away from the edge, and near the border where the run's
                 * continuation is unknown, nothing is promised but range */
                if (c != first - 1 && c != first)
                    assert_true(got == was);
                continue;
            }
            /* runs start at even along-positions: column a is the first
             * of its run when a is even */
            int outer = a % 2 == 0; /* the outside dot changes, else the inside */
            double want = c == first - 1 ? (outer ? 0.25 : 0.0) : (outer ? 1.0 : 0.75);
            if (fabs(got - want) > 1e-15)
                fail_msg("%s edge, dot (%d, %d): %.17g, not %g", vertical ? "vertical" : "horizontal",
                         i, j, got, want);
            quarter += want == 0.25, three += want == 0.75;
        }
    }
    print_message("fig. 4.3, %s edge of slope 1/2: %d outside dots at 1/4, %d inside at 3/4\n",
                  vertical ? "vertical" : "horizontal", quarter, three);
    assert_true(quarter >= 16 && three >= 16);
    aa_image_free(&tr);
    aa_image_free(&pt);
    aa_scene_free(s);
}

static void test_trio_fig43(void **state)
{
    (void)state;
    check_fig43(0);
    check_fig43(1);
}

static void check_toward_reference(const char *what, const double *xy, int n, int w, int h,
                                   const char *method)
{
    const aa_rgb orange = {{0.95, 0.55, 0.1}}, blue = {{0.1, 0.2, 0.7}};
    aa_scene *s = polygon_scene(xy, n, orange, blue);
    aa_image ref, tr, pt;
    reference(s, w, h, 0, 0, 0, &ref);
    render(method, s, w, h, &tr, NULL);
    render("point", s, w, h, &pt, NULL);
    double et = support_rmse(&tr, &ref), ep = support_rmse(&pt, &ref);
    print_message("%-26s %-22s RMSE %.4e, point %.4e (ratio %.2f)\n", what, method, et, ep,
                  et / ep);
    if (!(et < ep))
        fail_msg("%s: %s RMSE %.4e is not below point's %.4e", what, method, et, ep);
    aa_image_free(&ref);
    aa_image_free(&tr);
    aa_image_free(&pt);
    aa_scene_free(s);
}

static void test_trio_toward_reference(void **state)
{
    (void)state;
    /* straight edges at slopes 0.23 and 1/0.17 (no simple ratio), the
     * region beyond them a second colour */
    const double shallow[] = {-0.1, 0.3, 1.1, 0.3 + 1.2 * 0.23, 1.1, 1.1, -0.1, 1.1};
    const double steep[] = {0.35, -0.1, 0.35 + 1.2 * 0.17, 1.1, 1.1, 1.1, 1.1, -0.1};
    const double wedge[] = {0.1, 0.15, 0.9, 0.4, 0.3, 0.85};
    check_toward_reference("mostly horizontal edge", shallow, 4, 97, 61, "trio");
    check_toward_reference("mostly vertical edge", steep, 4, 61, 97, "trio");
    check_toward_reference("triangle", wedge, 3, 80, 80, "trio");
}

/* ---- sancha ---- */

static void test_sancha(void **state)
{
    (void)state;
    /* threshold 1: no two values in [0, 1] differ by more than 1, the
     * infinite threshold: the point-sampled image comes back unchanged */
    aa_scene *s = scenes_pattern("crow");
    aa_image a, b;
    aa_counters c;
    render("trio:variant=sancha,threshold=1", s, 64, 48, &a, &c);
    render("point", s, 64, 48, &b, NULL);
    assert_true(support_same_image(&a, &b));
    assert_true(c.expensive_pixels == 0);
    aa_image_free(&a);
    aa_image_free(&b);
    aa_scene_free(s);

    /* a white square on pixel boundaries [4, 9) x [3, 7) on black, 12x10:
     * by hand, a dot left of the square (right neighbour white) or above it
     * (lower neighbour white) becomes (0 + 1)/2; the square's right column
     * and bottom row (black right or lower neighbour) become (1 + 0)/2, and
     * its bottom-right dot, black on both sides, (1 + 0 + 0)/3; the rest,
     * including the dot diagonally above-left of the square, stay. */
    const int w = 12, h = 10;
    s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 4.0 / w, 3.0 / h, 9.0 / w, 7.0 / h);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    render("trio:variant=sancha", s, w, h, &a, &c);
    int changed = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int in = i >= 4 && i < 9 && j >= 3 && j < 7;
            double want = in ? 1.0 : 0.0;
            if (!in && ((i == 3 && j >= 3 && j < 7) || (j == 2 && i >= 4 && i < 9)))
                want = 0.5;
            if (in && (i == 8 || j == 6))
                want = i == 8 && j == 6 ? 1.0 / 3.0 : 0.5;
            changed += want != (in ? 1.0 : 0.0);
            if (aa_pixel(&a, i, j)[0] != want)
                fail_msg("sancha dot (%d, %d): %.17g, not %.17g", i, j, aa_pixel(&a, i, j)[0],
                         want);
        }
    assert_int_equal(changed, 4 + 5 + 4 + 5 - 1);
    assert_true(c.expensive_pixels == (uint64_t)changed);
    aa_image_free(&a);
    aa_scene_free(s);
}

/* ---- recursive ---- */

/* A step from black to white at column 3 (or row 3) of an 8x4 (4x8) image,
 * filtered with weight 1/4: y = x + (yl - x)/4 + (yu - x)/4, a missing
 * neighbour counting as the dot itself.  By hand, with e = 1 - y on the
 * white side (e = 1 on the black side, which stays black):
 *   row 0 (nothing above): e(3+m, 0) = e(2+m, 0)/4, so 1/4, 1/16, 1/64, ...
 *     and y = 3/4, 15/16, 63/64, 255/256, 1023/1024;
 *   row 1: e(i, 1) = e(i-1, 1)/4 + e(i, 0)/4:
 *     e(3,1) = 1/4 + 1/16 = 5/16            y = 11/16
 *     e(4,1) = 5/64 + 1/64 = 6/64           y = 29/32
 *     e(5,1) = 6/256 + 1/256 = 7/256        y = 249/256
 *   row 2: e(3,2) = 1/4 + 5/64 = 21/64     y = 43/64
 *          e(4,2) = 21/256 + 6/256 = 27/256 y = 229/256
 * All are short binary fractions, so the floating-point result is exact. */
static void check_recursive_step(int vertical)
{
    const int n = 8, m = 4;
    const int w = vertical ? m : n, h = vertical ? n : m;
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    if (vertical)
        scenes_rect(s, -1, 3.0 / h, 2, 2);
    else
        scenes_rect(s, 3.0 / w, -1, 2, 2);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    render("trio:variant=recursive", s, w, h, &img, NULL);
    const double want[3][8] = {{0, 0, 0, 3 / 4., 15 / 16., 63 / 64., 255 / 256., 1023 / 1024.},
                               {0, 0, 0, 11 / 16., 29 / 32., 249 / 256., -1, -1},
                               {0, 0, 0, 43 / 64., 229 / 256., -1, -1, -1}};
    for (int r = 0; r < 3; r++)
        for (int a = 0; a < n; a++) {
            if (want[r][a] < 0)
                continue;
            int i = vertical ? r : a, j = vertical ? a : r;
            double got = aa_pixel(&img, i, j)[0];
            if (got != want[r][a])
                fail_msg("recursive, %s step, dot (%d, %d): %.17g, not %.17g",
                         vertical ? "horizontal" : "vertical", i, j, got, want[r][a]);
        }
    aa_image_free(&img);
    aa_scene_free(s);
}

static void test_recursive_step(void **state)
{
    (void)state;
    check_recursive_step(0);
    check_recursive_step(1);
}

/* ---- threads and counters ---- */

static void test_threads_agree(void **state)
{
    (void)state;
    const char *methods[] = {"trio", "trio:variant=sancha", "trio:variant=recursive",
                             "trio:variant=recursive,weight=0.5", "hexagon"};
    aa_scene *s = scenes_pattern("crow");
    for (int k = 0; k < 5; k++) {
        aa_image a, b;
        aa_counters ca, cb;
        /* 300 columns: three pipeline chunks per row for the recursive filter */
        assert_int_equal(render_at(methods[k], s, 300, 203, 1.5, 0.2, 0.1, 0, 1, &a, &ca), AA_OK);
        for (int t = 2; t <= 3; t++) {
            assert_int_equal(render_at(methods[k], s, 300, 203, 1.5, 0.2, 0.1, 0, t, &b, &cb),
                             AA_OK);
            if (!support_same_image(&a, &b) || ca.samples != cb.samples ||
                ca.expensive_pixels != cb.expensive_pixels)
                fail_msg("%s: 1 and %d threads differ", methods[k], t);
            aa_image_free(&b);
        }
        print_message("%-36s 1, 2, 3 threads agree: %llu samples, %llu expensive pixels\n",
                      methods[k], (unsigned long long)ca.samples,
                      (unsigned long long)ca.expensive_pixels);
        aa_image_free(&a);
    }
    aa_scene_free(s);
}

static void test_trio_counters(void **state)
{
    (void)state;
    /* a 5x4 square on pixel boundaries: the dots beside its boundary are
     * its 14 rim dots and the 18 outside dots that share a side with it */
    const int w = 12, h = 10;
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, 4.0 / w, 3.0 / h, 9.0 / w, 7.0 / h);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    aa_counters c;
    render("trio", s, w, h, &img, &c);
    assert_true(c.samples == (uint64_t)w * h);
    assert_true(c.expensive_pixels == 14 + 18);
    aa_image_free(&img);
    aa_scene_free(s);
}

static void test_refusals(void **state)
{
    (void)state;
    const char *methods[] = {"hexagon", "trio", "trio:variant=sancha", "trio:variant=recursive"};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(support_parse_method(methods[k], "tent", NULL), AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "box reference"));
        assert_int_equal(support_parse_method(methods[k], "gauss", NULL), AA_EINVAL);
    }
    /* and under the box, values these methods do not take */
    const char *bad[] = {"hexagon:order=001122", "hexagon:frames=0", "trio:variant=mlaa"};
    for (int k = 0; k < 3; k++)
        assert_int_equal(support_parse_method(bad[k], NULL, NULL), AA_EINVAL);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_hexagon_eye_is_mean_of_frames),
             cmocka_unit_test(test_hexagon_offsets),
             cmocka_unit_test(test_hexagon_radius_zero_is_point),
             cmocka_unit_test(test_hexagon_beats_point_on_crow),
             cmocka_unit_test(test_trio_keeps_aligned_edges),
             cmocka_unit_test(test_trio_fig43),
             cmocka_unit_test(test_trio_toward_reference),
             cmocka_unit_test(test_sancha),
             cmocka_unit_test(test_recursive_step),
             cmocka_unit_test(test_threads_agree),
             cmocka_unit_test(test_trio_counters),
             cmocka_unit_test(test_refusals))
