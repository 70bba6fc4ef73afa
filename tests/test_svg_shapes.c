/*
 * test_svg_shapes.c: circles, ellipses, rounded rectangles, the arc
 * command and strokes read by the pattern svg (patterns/svgfile.c), through
 * the pattern's scene and its box reference, against closed forms.
 *
 * The box reference of a white shape over black is at each pixel the area
 * of the shape inside it, so the image's sum is the shape's area (the
 * shape within the view): pi r^2 for a disk, pi a b for an ellipse of
 * semi-axes a and b, and so on, each derived in a comment beside it.  The
 * scene itself is checked first at points inside and outside the shapes,
 * by the shapes' equations.
 */
#include "bench.h"
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

#define N 32 /* the view: N x N pixels */

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "svgshapes");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* `body` inside a root <svg> of N x N pixels, white shapes, written to a
 * file of the temporary folder; its pattern spec into spec. */
static void svg_spec(const char *name, const char *body, char *spec, size_t len)
{
    char path[4200], doc[4096];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    snprintf(doc, sizeof doc,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
             "fill=\"white\">%s</svg>",
             N, N, body);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, len, "svg:file=%s", path);
}

/* The pattern's scene of `body` (in pattern units: a pixel (u, v) is
 * (u / N, v / N)). */
static aa_scene *scene_of(const char *name, const char *body)
{
    char spec[4400];
    svg_spec(name, body, spec, sizeof spec);
    aa_spec s;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &s) != AA_OK || aa_pattern_scene_at(&s, N, N, &sc) != AA_OK)
        fail_msg("%s: %s", body, aa_last_error());
    return sc;
}

/* 1 if the scene is white at pixel coordinates (x, y), 0 if black. */
static int white_at(const aa_scene *sc, double x, double y)
{
    aa_rgb c = aa_scene_colour_at(sc, x / N, y / N);
    if (c.c[0] == 1 && c.c[1] == 1 && c.c[2] == 1)
        return 1;
    if (c.c[0] == 0 && c.c[1] == 0 && c.c[2] == 0)
        return 0;
    fail_msg("colour (%g, %g, %g) at (%g, %g)", c.c[0], c.c[1], c.c[2], x, y);
    return -1;
}

/* Points at 64 angles about (cx, cy) on the ellipse of semi-axes a along
 * the angle phi and b across, scaled by `k`: inside for k < 1, outside for
 * k > 1 (the point (k a cos s, k b sin s) in the axes' frame satisfies
 * (x/a)^2 + (y/b)^2 = k^2). */
static void check_ellipse(const aa_scene *sc, double cx, double cy, double a, double b,
                          double phi, const char *what)
{
    static const double ks[2] = {0.98, 1.02};
    for (int q = 0; q < 2; q++)
        for (int j = 0; j < 64; j++) {
            double s = 2 * M_PI * (j + 0.5) / 64, ex = ks[q] * a * cos(s),
                   ey = ks[q] * b * sin(s);
            double x = cx + ex * cos(phi) - ey * sin(phi), y = cy + ex * sin(phi) + ey * cos(phi);
            if (white_at(sc, x, y) != (q == 0))
                fail_msg("%s: (%g, %g) is %s, k %g", what, x, y, q ? "inside" : "outside", ks[q]);
        }
}

/* The scene of each shape at points inside and outside it. */
static void test_scene_points(void **state)
{
    (void)state;
    aa_scene *sc = scene_of("circle", "<circle cx=\"15.3\" cy=\"16.7\" r=\"9.6\"/>");
    check_ellipse(sc, 15.3, 16.7, 9.6, 9.6, 0, "circle");
    aa_scene_free(sc);
    sc = scene_of("ellipse", "<ellipse cx=\"16.2\" cy=\"15.1\" rx=\"12.5\" ry=\"6.3\"/>");
    check_ellipse(sc, 16.2, 15.1, 12.5, 6.3, 0, "ellipse");
    aa_scene_free(sc);
    /* rotate(30) scale(1.5 0.75) of the ellipse of radii 8, 5 about the
     * origin, moved to (16, 16): semi-axes 12 along 30 degrees and 3.75
     * across */
    sc = scene_of("turned", "<ellipse transform=\"translate(16 16) rotate(30) scale(1.5 0.75)\" "
                            "rx=\"8\" ry=\"5\"/>");
    check_ellipse(sc, 16, 16, 12, 3.75, M_PI / 6, "turned ellipse");
    aa_scene_free(sc);
    /* the arc command: the upper half of the disk about (16, 16) of radius
     * 12 (sweep 1 from (4, 16): angles increasing, through (16, 4)) */
    sc = scene_of("half", "<path d=\"M 4 16 A 12 12 0 0 1 28 16 Z\"/>");
    for (int j = 0; j < 32; j++) {
        double s = M_PI * (j + 0.5) / 32;
        assert_int_equal(white_at(sc, 16 + 11.8 * cos(s), 16 - 11.8 * sin(s)), 1);
        assert_int_equal(white_at(sc, 16 + 12.2 * cos(s), 16 - 12.2 * sin(s)), 0);
        assert_int_equal(white_at(sc, 16 + 11.8 * cos(s), 16 + 11.8 * sin(s)), 0);
    }
    aa_scene_free(sc);
    /* a rounded rectangle [3.5, 27.5] x [5.25, 23.25], corners of radii 5
     * and 3.5: about its top left corner's centre (8.5, 8.75), the corner
     * is the quarter ellipse; the sides are straight */
    sc = scene_of("rounded", "<rect x=\"3.5\" y=\"5.25\" width=\"24\" height=\"18\" rx=\"5\" "
                             "ry=\"3.5\"/>");
    for (int j = 0; j < 16; j++) {
        double s = M_PI + M_PI / 2 * (j + 0.5) / 16;
        assert_int_equal(white_at(sc, 8.5 + 0.98 * 5 * cos(s), 8.75 + 0.98 * 3.5 * sin(s)), 1);
        assert_int_equal(white_at(sc, 8.5 + 1.02 * 5 * cos(s), 8.75 + 1.02 * 3.5 * sin(s)), 0);
    }
    assert_int_equal(white_at(sc, 3.6, 14), 1);
    assert_int_equal(white_at(sc, 3.4, 14), 0);
    assert_int_equal(white_at(sc, 3.6, 5.35), 0); /* cut off by the corner */
    aa_scene_free(sc);
}

/* Strokes at points, by SVG 2's stroke shape: a line's stroke of width w
 * is the points within w/2 of it (butt caps: between the normals at its
 * ends; round caps add the disks of radius w/2 at the ends); a circle's
 * is the ring between radii r - w/2 and r + w/2; a miter join fills the
 * corner's square, a bevel cuts it along the line between the offset
 * corners; dashes "4 2" along a line cover the lengths [0, 4], [6, 10], ... */
static void test_stroke_points(void **state)
{
    (void)state;
    const double ax = 4, ay = 10.5, len = hypot(23, 9.5), dx = 23 / len, dy = 9.5 / len;
    static const char *const caps[2] = {"butt", "round"};
    for (int c = 0; c < 2; c++) {
        char body[512];
        snprintf(body, sizeof body,
                 "<line x1=\"4\" y1=\"10.5\" x2=\"27\" y2=\"20\" stroke=\"white\" "
                 "stroke-width=\"3\" stroke-linecap=\"%s\"/>",
                 caps[c]);
        aa_scene *sc = scene_of(caps[c], body);
        /* (s, o): s along the line from its start, o across it */
#define AT(s, o) white_at(sc, ax + (s) * dx - (o) * dy, ay + (s) * dy + (o) * dx)
        for (int j = 1; j < 20; j++) {
            double s = len * j / 20;
            assert_int_equal(AT(s, 1.45), 1);
            assert_int_equal(AT(s, -1.45), 1);
            assert_int_equal(AT(s, 1.55), 0);
            assert_int_equal(AT(s, -1.55), 0);
        }
        assert_int_equal(AT(-0.1, 0), c == 1);
        assert_int_equal(AT(len + 0.1, 1), c == 1);
        assert_int_equal(AT(-1.45, 0), c == 1);
        assert_int_equal(AT(-1.55, 0), 0);
        assert_int_equal(AT(len + 1.0, 1.0), c == 1); /* sqrt 2 < 1.5 from the end */
        assert_int_equal(AT(len + 1.1, 1.1), 0);
#undef AT
        aa_scene_free(sc);
    }
    aa_scene *sc = scene_of("ring", "<circle cx=\"15.5\" cy=\"16.25\" r=\"9\" fill=\"none\" "
                                    "stroke=\"white\" stroke-width=\"3\"/>");
    check_ellipse(sc, 15.5, 16.25, 10.5, 10.5, 0, "the ring's outside");
    for (int j = 0; j < 64; j++) {
        double t = 2 * M_PI * (j + 0.5) / 64, c = cos(t), s = sin(t);
        assert_int_equal(white_at(sc, 15.5 + 7.45 * c, 16.25 + 7.45 * s), 0);
        assert_int_equal(white_at(sc, 15.5 + 7.6 * c, 16.25 + 7.6 * s), 1);
    }
    aa_scene_free(sc);
    /* the rectangle [6, 24] x [7, 21] stroked 2 wide: its top left corner
     * (6, 7); mitered, the corner square [5, 6] x [6, 7] is filled; with
     * bevels it is cut along x + y = 12 */
    sc = scene_of("miter", "<rect x=\"6\" y=\"7\" width=\"18\" height=\"14\" fill=\"none\" "
                           "stroke=\"white\" stroke-width=\"2\"/>");
    assert_int_equal(white_at(sc, 5.05, 6.05), 1);
    assert_int_equal(white_at(sc, 4.95, 6.05), 0);
    assert_int_equal(white_at(sc, 7.5, 8.5), 0); /* inside, no fill */
    assert_int_equal(white_at(sc, 6.9, 12), 1);
    aa_scene_free(sc);
    sc = scene_of("bevel", "<rect x=\"6\" y=\"7\" width=\"18\" height=\"14\" fill=\"none\" "
                           "stroke=\"white\" stroke-width=\"2\" stroke-linejoin=\"bevel\"/>");
    assert_int_equal(white_at(sc, 5.05, 6.05), 0);
    assert_int_equal(white_at(sc, 5.6, 6.5), 1);
    aa_scene_free(sc);
    sc = scene_of("dashes", "<line x1=\"6\" y1=\"16\" x2=\"26\" y2=\"16\" stroke=\"white\" "
                            "stroke-width=\"2\" stroke-dasharray=\"4 2\"/>");
    static const double xs[] = {6.1, 9.9, 12.1, 15.9, 18.1, 21.9, 24.1, 25.9};
    static const double gaps[] = {5.9, 10.1, 11.9, 16.1, 17.9, 22.1, 23.9, 26.1};
    for (int j = 0; j < 8; j++) {
        assert_int_equal(white_at(sc, xs[j], 16.5), 1);
        assert_int_equal(white_at(sc, gaps[j], 16.5), 0);
    }
    aa_scene_free(sc);
}

/* ---- areas through the box reference ---- */

/* The sum of the box reference of `body` over the view (the area of the
 * white shapes in it) against `area`. */
static void check_area(const char *name, const char *body, double area)
{
    char spec[4400];
    svg_spec(name, body, spec, sizeof spec);
    aa_image img;
    support_pattern_reference(spec, &(support_view){.w = N, .h = N}, &img, NULL, NULL);
    double sum = 0;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            sum += aa_pixel(&img, i, j)[0];
    aa_image_free(&img);
    printf("# %s: area %.15g, reference sum %.15g, difference %.2g\n", name, area, sum,
           sum - area);
    if (!(fabs(sum - area) <= 1e-9))
        fail_msg("%s: the reference sums to %.17g, the area is %.17g", name, sum, area);
}

/* Strokes of lines (SVG 2, "Stroke shape"): a line of length L stroked w
 * wide with butt caps is a w x L rectangle; a rectangle's stroke with
 * miter joins (right angles, miter length sqrt 2 w below the limit 4 w) is
 * the box grown by w/2 less the box shrunk by w/2; bevels cut from each
 * corner half of its w/2 x w/2 square; dashes "4 2" along a line of 20
 * cover [0, 4], [6, 10], [12, 16], [18, 20]: 14 w. */
static void test_stroke_areas(void **state)
{
    (void)state;
    check_area("line", "<line x1=\"4\" y1=\"10.5\" x2=\"27\" y2=\"20\" stroke=\"white\" "
                       "stroke-width=\"3\"/>",
               3 * hypot(23, 9.5));
    check_area("stroked rect", "<rect x=\"6\" y=\"7\" width=\"18\" height=\"14\" fill=\"none\" "
                               "stroke=\"white\" stroke-width=\"2\"/>",
               20 * 16 - 16 * 12);
    check_area("bevelled rect", "<rect x=\"6\" y=\"7\" width=\"18\" height=\"14\" "
                                "fill=\"none\" stroke=\"white\" stroke-width=\"2\" "
                                "stroke-linejoin=\"bevel\"/>",
               20 * 16 - 16 * 12 - 4 * 0.5);
    check_area("dashes", "<line x1=\"6\" y1=\"16\" x2=\"26\" y2=\"16\" stroke=\"white\" "
                         "stroke-width=\"2\" stroke-dasharray=\"4 2\"/>",
               14 * 2);
}

/* The areas of shapes with elliptical arcs, through the reference of conic
 * pieces (harness/truth). */

/* Fills with elliptical arcs: pi r^2; pi a b; a rounded rectangle is its
 * box less four corners, each a square rx ry less a quarter ellipse
 * pi rx ry / 4: w h - (4 - pi) rx ry; a half disk pi r^2 / 2; an affine
 * map multiplies areas by its determinant (rotate: 1, scale(1.5 0.75):
 * 1.125); radii too small for the arc's ends are scaled up until they
 * reach (SVG's implementation notes, F.6.6): radii 2, 1 over a chord of
 * 20 along the x axis become 10, 5 (Lambda = (10/2)^2 = 25, scale 5), and
 * the arc is half the ellipse, pi 10 5 / 2. */
static void test_fill_areas(void **state)
{
    (void)state;
    check_area("circle", "<circle cx=\"15.3\" cy=\"16.7\" r=\"9.6\"/>", M_PI * 9.6 * 9.6);
    check_area("ellipse", "<ellipse cx=\"16.2\" cy=\"15.1\" rx=\"12.5\" ry=\"6.3\"/>",
               M_PI * 12.5 * 6.3);
    check_area("rounded",
               "<rect x=\"3.5\" y=\"5.25\" width=\"24\" height=\"18\" rx=\"5\" ry=\"3.5\"/>",
               24 * 18 - (4 - M_PI) * 5 * 3.5);
    check_area("half", "<path d=\"M 4 16 A 12 12 0 0 1 28 16 Z\"/>", M_PI * 144 / 2);
    check_area("turned",
               "<ellipse transform=\"translate(16 16) rotate(30) scale(1.5 0.75)\" rx=\"8\" "
               "ry=\"5\"/>",
               M_PI * 8 * 5 * 1.5 * 0.75);
    check_area("small radii", "<path d=\"M 6 16 A 2 1 0 0 1 26 16 Z\"/>", M_PI * 10 * 5 / 2);
}

/* Strokes with circular arcs: round caps add to a butt line's w L a disk
 * of diameter w (two half disks); a circle's stroke is the ring between
 * radii r +- w/2, pi ((r + w/2)^2 - (r - w/2)^2) = 2 pi r w; a rounded
 * rectangle's stroke (round corners of radius r, the stroke w) is the
 * grown rounded box less the shrunk one: (W + w)(H + w) - (4 - pi)
 * (r + w/2)^2 - ((W - w)(H - w) - (4 - pi)(r - w/2)^2). */
static void test_stroke_arc_areas(void **state)
{
    (void)state;
    check_area("round caps", "<line x1=\"6\" y1=\"10.5\" x2=\"25\" y2=\"20\" stroke=\"white\" "
                             "stroke-width=\"3\" stroke-linecap=\"round\"/>",
               3 * hypot(19, 9.5) + M_PI * 1.5 * 1.5);
    check_area("ring", "<circle cx=\"15.5\" cy=\"16.25\" r=\"9\" fill=\"none\" stroke=\"white\" "
                       "stroke-width=\"3\"/>",
               2 * M_PI * 9 * 3);
    check_area("stroked rounded rect",
               "<rect x=\"5\" y=\"6\" width=\"22\" height=\"18\" rx=\"4\" fill=\"none\" "
               "stroke=\"white\" stroke-width=\"2\"/>",
               24 * 20 - (4 - M_PI) * 25 - (20 * 16 - (4 - M_PI) * 9));
}

/* Strokes of Bezier arcs, read from SVG: the quadratic from (0, 0) through
 * (X/2, 0) to (X, a X^2) is the parabola y = a x^2 (x = X t, y = a X^2
 * t^2), whose curvature radius (1 + 4 a^2 x^2)^(3/2) / (2 a) is at least
 * 1/(2a) = 20 > w/2 = 1.5, so that its butt-capped stroke is a tube of
 * area w L (the tube formula), with the arc length in closed form
 * L = [x/2 sqrt(1 + 4 a^2 x^2) + asinh(2 a x)/(4 a)] from 0 to X; the
 * cubic with the same curve (degree elevated: controls at 1/3 and 2/3 of
 * the way to the quadratic's control) has the same stroke. */
static void test_stroke_bezier_areas(void **state)
{
    (void)state;
    const double a = 1.0 / 40, X = 20, w = 3;
    const double L = X / 2 * sqrt(1 + 4 * a * a * X * X) + asinh(2 * a * X) / (4 * a);
    check_area("stroked parabola",
               "<path transform=\"translate(5 4)\" d=\"M 0 0 Q 10 0 20 10\" fill=\"none\" "
               "stroke=\"white\" stroke-width=\"3\"/>",
               w * L);
    /* a line written as a cubic whose controls are its ends (C a a b b,
     * as editors write it): the points a + (3t^2 - 2t^3)(b - a), the
     * segment traced once, so its stroke is the line's, w L with butt
     * caps and w (L + w) with square ones; the ends off the grid and the
     * chord at no simple angle, in the user units of a Papirus icon
     * (CubicSDR.svg), where it was refused: its speed vanishes at both
     * ends, where rounding gave the straight arc a curvature) */
    const double cl = hypot(15.110139 - 14.169408, 27.722371 - 36.963583);
    check_area("line as a cubic",
               "<path transform=\"translate(0 -20)\" d=\"M 14.169408 36.963583 C 14.169408 "
               "36.963583 15.110139 27.722371 15.110139 27.722371\" fill=\"none\" stroke=\"white\" stroke-width=\"0.7\"/>",
               0.7 * cl);
    check_area("line as a cubic with square caps",
               "<path transform=\"translate(0 -20)\" d=\"M 14.169408 36.963583 C 14.169408 "
               "36.963583 15.110139 27.722371 15.110139 27.722371\" fill=\"none\" stroke=\"white\" stroke-width=\"0.7\" "
               "stroke-linecap=\"square\"/>",
               0.7 * (cl + 0.7));
    check_area("line as a cubic 0 1 0 1 dashed",
               "<path d=\"M 4 5 C 26 20 4 5 26 20\" fill=\"none\" stroke=\"white\" "
               "stroke-width=\"2\" stroke-dasharray=\"4 2\"/>",
               2 * (4 + 4 + 4 + 4 + (hypot(22, 15) - 24)));
    check_area("stroked parabola as a cubic",
               "<path transform=\"translate(5 4)\" d=\"M 0 0 C 6.6666666666666667 0 "
               "13.333333333333333 3.3333333333333333 20 10\" fill=\"none\" stroke=\"white\" "
               "stroke-width=\"3\"/>",
               w * L);
}

#define CONIC_AREA_TESTS                                                                       \
    , cmocka_unit_test(test_fill_areas), cmocka_unit_test(test_stroke_arc_areas),             \
        cmocka_unit_test(test_stroke_bezier_areas)

SUPPORT_MAIN(setup, teardown,
             cmocka_unit_test(test_scene_points),
             cmocka_unit_test(test_stroke_points),
             cmocka_unit_test(test_stroke_areas) CONIC_AREA_TESTS)
