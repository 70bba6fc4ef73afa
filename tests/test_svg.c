/*
 * test_svg.c: the pattern svg (patterns/svgfile.c): the reader's parsed,
 * transformed absolute coordinates of every path command against values
 * derived by hand from the SVG specification (SVG 1.1, "Paths" and
 * "Coordinate systems"), colours, the viewBox mapping, refusals naming the
 * element and its line, a rectangle whose box reference is known in closed
 * form, the file's hash in the cache key, and the export round trip (of
 * the patterns, and of strokes of ellipses and a cusp, written as strokes).
 */
#include "bench.h"
#include "patterns.h"
#include "support.h"
#include "svgfile.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

/* ---- a sink that writes what it is given as text ---- */

static int s_shape(void *ctx, aa_rgb c, aa_fill_rule rule)
{
    return support_put(ctx, "%sfill %.17g %.17g %.17g %s;", ((support_text *)ctx)->n ? " " : "",
                       c.c[0], c.c[1], c.c[2], rule == AA_FILL_EVENODD ? "evenodd" : "nonzero");
}
static int s_arc(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                 double t0, double t1, double x, double y)
{
    return support_put(ctx, " A %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", cx,
                       cy, ux, uy, vx, vy, t0, t1, x, y);
}

/* the path's commands by support_put_move and the others */
static const aa_svg_sink sink = {.shape = s_shape, .move_to = support_put_move,
                                 .line_to = support_put_line, .quad_to = support_put_quad,
                                 .cubic_to = support_put_cubic, .close = support_put_close,
                                 .arc_to = s_arc};

/* Read `doc` on a w x h view; the sink's text, or fail. */
static const char *read_doc(const char *doc, int w, int h, double vp[2])
{
    static support_text t;
    t.n = 0;
    t.buf[0] = '\0';
    if (aa_svg_read(doc, strlen(doc), "test.svg", w, h, &sink, &t, vp) != AA_OK)
        fail_msg("%s: %s", doc, aa_last_error());
    return t.buf;
}

#define SVG_OPEN "<svg xmlns=\"http://www.w3.org/2000/svg\">"
#define PATH(d) SVG_OPEN "<path d=\"" d "\"/></svg>"

static void expect(const char *doc, const char *want)
{
    const char *got = read_doc(doc, 100, 100, NULL);
    if (strcmp(got, want))
        fail_msg("%s\n  got  %s\n  want %s", doc, got, want);
}

/* The initial fill is black, the rule nonzero (SVG 1.1, "fill" and
 * "fill-rule": initial values). */
#define BLACK "fill 0 0 0 nonzero;"

static void test_commands_absolute(void **state)
{
    (void)state;
    expect(PATH("M1 2 L3 4 H5 V6 Q7 8 9 10 C 11 12 13 14 15 16 Z"),
           BLACK " M 1 2 L 3 4 L 5 4 L 5 6 Q 7 8 9 10 C 11 12 13 14 15 16 Z");
}

static void test_commands_relative(void **state)
{
    (void)state;
    /* from (1, 2): l3 4 -> (4, 6); h5 -> (9, 6); v6 -> (9, 12);
     * q1 1 2 2 -> control (10, 13), end (11, 14); c1 1 2 2 3 3 -> (12, 15),
     * (13, 16), (14, 17); z */
    expect(PATH("m1 2 l3 4 h5 v6 q1 1 2 2 c1 1 2 2 3 3 z"),
           BLACK " M 1 2 L 4 6 L 9 6 L 9 12 Q 10 13 11 14 C 12 15 13 16 14 17 Z");
    /* a second relative m is relative to the start point after z */
    expect(PATH("m10 10 h5 z m1 1 h2 z"), BLACK " M 10 10 L 15 10 Z M 11 11 L 13 11 Z");
}

static void test_implicit_repeats(void **state)
{
    (void)state;
    /* pairs after M are lines, after m relative lines; the subpath closes at
     * the end of the data (a fill closes it) */
    expect(PATH("M0 0 10 0 10 10z"), BLACK " M 0 0 L 10 0 L 10 10 Z");
    expect(PATH("m1 1 2 2 3 3"), BLACK " M 1 1 L 3 3 L 6 6 Z");
    expect(PATH("M0 0 L1 1 2 2 H3 4 V5 6"), BLACK " M 0 0 L 1 1 L 2 2 L 3 2 L 4 2 L 4 5 L 4 6 Z");
    expect(PATH("M0 0 Q1 1 2 0 3 -1 4 0"), BLACK " M 0 0 Q 1 1 2 0 Q 3 -1 4 0 Z");
    /* a drawing command after z starts a new subpath at the start point */
    expect(PATH("M1 1 L2 1 L2 2 Z L 5 5"), BLACK " M 1 1 L 2 1 L 2 2 Z M 1 1 L 5 5 Z");
}

static void test_reflections(void **state)
{
    (void)state;
    /* T reflects the last control point (10, 0) about the current point
     * (10, 10): (10, 20); T after no Q takes the current point */
    expect(PATH("M0 0 Q10 0 10 10 T20 20"), BLACK " M 0 0 Q 10 0 10 10 Q 10 20 20 20 Z");
    expect(PATH("M0 0 T5 5"), BLACK " M 0 0 Q 0 0 5 5 Z");
    expect(PATH("M0 0 Q10 0 10 10 t10 10"), BLACK " M 0 0 Q 10 0 10 10 Q 10 20 20 20 Z");
    /* S reflects the second control point (10, 10) about (10, 0): (10, -10) */
    expect(PATH("M0 0 C0 10 10 10 10 0 S 20 -10 20 0"),
           BLACK " M 0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0 Z");
    expect(PATH("M0 0 C0 10 10 10 10 0 s 10 -10 10 0"),
           BLACK " M 0 0 C 0 10 10 10 10 0 C 10 -10 20 -10 20 0 Z");
    /* S after a line: the first control point is the current point */
    expect(PATH("M0 0 L 1 0 S 2 2 3 0"), BLACK " M 0 0 L 1 0 C 1 0 2 2 3 0 Z");
    /* T after a cubic does not reflect */
    expect(PATH("M0 0 C1 1 2 1 3 0 T 5 5"), BLACK " M 0 0 C 1 1 2 1 3 0 Q 3 0 5 5 Z");
}

static void test_numbers(void **state)
{
    (void)state;
    /* the grammar of SVG path numbers: "1e2-1" is 100 then -1, ".5.5" is
     * 0.5 then 0.5, "-1-2" is -1 then -2, exponents with signs */
    expect(PATH("M1e2-1L.5.5-1-2"), BLACK " M 100 -1 L 0.5 0.5 L -1 -2 Z");
    expect(PATH("M1E+1,-.5e-1 l+2,3"), BLACK " M 10 -0.050000000000000003 L 12 2.9500000000000002 Z");
    expect(PATH("M 0.5 ,1 , L2\t3\n4 5"), BLACK " M 0.5 1 L 2 3 L 4 5 Z");
    expect(PATH("M1.5e1.5 0 1"), BLACK " M 15 0.5 L 0 1 Z"); /* 1.5e1 and .5, then a line */
}

/* A transform per element: the points are mapped by hand. */
static void test_transforms(void **state)
{
    (void)state;
    /* translate(10,20) scale(2): (x, y) -> (2x + 10, 2y + 20) */
    expect(SVG_OPEN "<g transform=\"translate(10,20) scale(2)\"><path d=\"M1 1 L2 1 L1 2z\"/></g></svg>",
           BLACK " M 12 22 L 14 22 L 12 24 Z");
    /* rotate(90): (x, y) -> (-y, x), exactly */
    expect(SVG_OPEN "<path transform=\"rotate(90)\" d=\"M1 2 L3 4\"/></svg>",
           BLACK " M -2 1 L -4 3 Z");
    /* rotate(90, 10, 10): about (10, 10), (20, 10) -> (10, 20) */
    expect(SVG_OPEN "<path transform=\"rotate(90 10 10)\" d=\"M20 10 L10 10\"/></svg>",
           BLACK " M 10 20 L 10 10 Z");
    /* skewX(45): x' = x + y; skewY(45): y' = y + x; rotate(-180): (-x, -y) */
    expect(SVG_OPEN "<path transform=\"skewX(45)\" d=\"M1 2 L3 4\"/></svg>", BLACK " M 3 2 L 7 4 Z");
    expect(SVG_OPEN "<path transform=\"skewY(45)\" d=\"M1 2 L3 4\"/></svg>", BLACK " M 1 3 L 3 7 Z");
    expect(SVG_OPEN "<path transform=\"rotate(-180)\" d=\"M1 2\"/></svg>", BLACK " M -1 -2 Z");
    /* matrix(1 2 3 4 5 6): x' = x + 3y + 5, y' = 2x + 4y + 6; (1, 1) -> (9, 12) */
    expect(SVG_OPEN "<path transform=\"matrix(1 2 3 4 5 6)\" d=\"M1 1 L0 0\"/></svg>",
           BLACK " M 9 12 L 5 6 Z");
    /* nested: the outer applies last; rotate(90) of translate(5 0) of (1, 0)
     * is rotate(90) of (6, 0) = (0, 6) */
    expect(SVG_OPEN "<g transform=\"rotate(90)\"><g transform=\"translate(5 0)\">"
                    "<path d=\"M1 0\"/></g></g></svg>",
           BLACK " M 0 6 Z");
    /* a list on one element applies right to left: translate(5) scale(3) of
     * (1, 1) is (8, 3); control points are mapped too */
    expect(SVG_OPEN "<path transform=\"translate(5) scale(3)\" d=\"M1 1 Q 2 2 3 1 C 0 0 1 1 2 2\"/></svg>",
           BLACK " M 8 3 Q 11 6 14 3 C 5 0 8 3 11 6 Z");
}

static void test_shapes(void **state)
{
    (void)state;
    expect(SVG_OPEN "<rect x=\"1\" y=\"2\" width=\"3\" height=\"4\"/></svg>",
           BLACK " M 1 2 L 4 2 L 4 6 L 1 6 Z");
    expect(SVG_OPEN "<rect width=\"3px\" height=\"0\"/><rect width=\"2\" height=\"1\"/></svg>",
           BLACK " M 0 0 L 2 0 L 2 1 L 0 1 Z");
    expect(SVG_OPEN "<polygon points=\"0,0 1,0 1,1\"/></svg>", BLACK " M 0 0 L 1 0 L 1 1 Z");
    expect(SVG_OPEN "<polyline points=\"0 0 1 0 1 1\"/></svg>", BLACK " M 0 0 L 1 0 L 1 1 Z");
    /* no fill, display none, a line without stroke, and other namespaces'
     * elements draw nothing; title, desc, metadata and defs neither */
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"none\"/>"
                    "<g display=\"none\"><circle r=\"1\"/></g><line x2=\"5\" y2=\"5\"/>"
                    "<x:foo xmlns:x=\"urn:x\"/><title>t</title><desc>d</desc>"
                    "<defs><linearGradient id=\"g\"/></defs></svg>",
           "");
}

static void refused(const char *doc, const char *want1, const char *want2);
#define L2(x) "<svg xmlns=\"http://www.w3.org/2000/svg\">\n" x "</svg>"

/* ---- shapes, arcs and strokes ---- */

/* A sink that keeps what it is given: ops as letters (s shape, M L Q C A
 * Z) with their numbers (A: cx cy ux uy vx vy t0 t1 x y). */
#define GEO_MAX 512
typedef struct geo_sink {
    int n;
    char op[GEO_MAX];
    double v[GEO_MAX][10];
} geo_sink;

static int g_add(geo_sink *g, char op, int n, const double *v)
{
    assert_true(g->n < GEO_MAX);
    g->op[g->n] = op;
    for (int k = 0; k < n; k++)
        g->v[g->n][k] = v[k];
    g->n++;
    return AA_OK;
}
static int g_shape(void *ctx, aa_rgb c, aa_fill_rule rule)
{
    double v[4] = {c.c[0], c.c[1], c.c[2], rule};
    return g_add(ctx, 's', 4, v);
}
static int g_move(void *ctx, double x, double y) { return g_add(ctx, 'M', 2, (double[]){x, y}); }
static int g_line(void *ctx, double x, double y) { return g_add(ctx, 'L', 2, (double[]){x, y}); }
static int g_quad(void *ctx, double cx, double cy, double x, double y)
{
    return g_add(ctx, 'Q', 4, (double[]){cx, cy, x, y});
}
static int g_cubic(void *ctx, double a, double b, double c, double d, double x, double y)
{
    return g_add(ctx, 'C', 6, (double[]){a, b, c, d, x, y});
}
static int g_close(void *ctx) { return g_add(ctx, 'Z', 0, NULL); }
static int g_arc(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                 double t0, double t1, double x, double y)
{
    return g_add(ctx, 'A', 10, (double[]){cx, cy, ux, uy, vx, vy, t0, t1, x, y});
}
static const aa_svg_sink geo = {g_shape, g_move, g_line, g_quad, g_cubic, g_close, g_arc,
                                NULL,    NULL,   NULL,   NULL,    NULL,    NULL,  NULL, NULL, NULL};

/* The ops' letters of `doc` read on a 100 x 100 view into *g. */
static const char *geo_read(const char *doc, geo_sink *g)
{
    static char ops[GEO_MAX + 1];
    g->n = 0;
    if (aa_svg_read(doc, strlen(doc), "test.svg", 100, 100, &geo, g, NULL) != AA_OK)
        fail_msg("%s: %s", doc, aa_last_error());
    memcpy(ops, g->op, (size_t)g->n);
    ops[g->n] = '\0';
    return ops;
}

static void near(double got, double want, const char *what)
{
    if (!(fabs(got - want) <= 1e-12 * fmax(1, fabs(want))))
        fail_msg("%s: %.17g, want %.17g", what, got, want);
}

/* The arc's point at t: c + u cos t + v sin t. */
static void arc_at(const double *a, double t, double *x, double *y)
{
    *x = a[0] + a[2] * cos(t) + a[4] * sin(t);
    *y = a[1] + a[3] * cos(t) + a[5] * sin(t);
}

/* Op k of g is an arc from (x0, y0) of the ellipse of centre (cx, cy) with
 * the axes (rx along the direction of angle phi, ry across it): its ends
 * are where the previous op ended and its own end, every point of it is
 * on that ellipse, and it passes through (mx, my) (its point at the mean
 * of t0 and t1 is compared when `mid` is set: for a circle the parameter
 * is proportional to the length, so that is the arc's midpoint). */
static void check_arc(const geo_sink *g, int k, double cx, double cy, double rx, double ry,
                      double phi, double mx, double my, int mid)
{
    assert_true(k > 0 && g->op[k] == 'A');
    const double *a = g->v[k], *prev = g->v[k - 1];
    int pn = g->op[k - 1] == 'M' || g->op[k - 1] == 'L' ? 0 : g->op[k - 1] == 'A' ? 8 : -1;
    assert_true(pn >= 0);
    double x, y;
    arc_at(a, a[6], &x, &y);
    near(x, prev[pn], "arc start x");
    near(y, prev[pn + 1], "arc start y");
    arc_at(a, a[7], &x, &y);
    near(x, a[8], "arc end x");
    near(y, a[9], "arc end y");
    near(a[0], cx, "centre x");
    near(a[1], cy, "centre y");
    /* on the ellipse: in its axes' frame (x/rx)^2 + (y/ry)^2 = 1 */
    const double c = cos(phi), s = sin(phi);
    for (int q = 0; q <= 8; q++) {
        arc_at(a, a[6] + (a[7] - a[6]) * q / 8, &x, &y);
        double ex = ((x - cx) * c + (y - cy) * s) / rx, ey = (-(x - cx) * s + (y - cy) * c) / ry;
        near(ex * ex + ey * ey, 1, "on the ellipse");
    }
    if (mid) {
        arc_at(a, (a[6] + a[7]) / 2, &x, &y);
        near(x, mx, "arc's middle x");
        near(y, my, "arc's middle y");
    }
}

/* Circles, ellipses and rounded rectangles: SVG 2's equivalent paths
 * ("Basic shapes": from (cx + rx, cy) four quarter arcs to (cx, cy + ry),
 * (cx - rx, cy), (cx, cy - ry) and back; a rectangle from (x + rx, y)
 * clockwise with quarter arcs at the corners). */
static void test_basic_arcs(void **state)
{
    (void)state;
    static geo_sink store; /* large: not on the stack */
    geo_sink *g = &store;
    const double h = sqrt(0.5);
    assert_string_equal(geo_read(SVG_OPEN "<circle cx=\"5\" cy=\"6\" r=\"2\"/></svg>", g),
                        "sMAAAAZ");
    near(g->v[1][0], 7, "start x");
    near(g->v[1][1], 6, "start y");
    /* quarter q from angle q pi/2: its middle at angle (q + 1/2) pi/2 */
    static const double ends[4][2] = {{5, 8}, {3, 6}, {5, 4}, {7, 6}};
    static const double mids[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    for (int q = 0; q < 4; q++) {
        check_arc(g, 2 + q, 5, 6, 2, 2, 0, 5 + 2 * h * mids[q][0], 6 + 2 * h * mids[q][1], 1);
        near(g->v[2 + q][8], ends[q][0], "end x");
        near(g->v[2 + q][9], ends[q][1], "end y");
    }
    /* an ellipse; rx auto is ry; a zero radius or none draws nothing */
    assert_string_equal(geo_read(SVG_OPEN "<ellipse cx=\"10\" rx=\"4\" ry=\"1\"/></svg>", g),
                        "sMAAAAZ");
    for (int q = 0; q < 4; q++)
        check_arc(g, 2 + q, 10, 0, 4, 1, 0, 0, 0, 0);
    near(g->v[3][8], 6, "ellipse's left end");
    assert_string_equal(geo_read(SVG_OPEN "<ellipse rx=\"auto\" ry=\"3\"/></svg>", g), "sMAAAAZ");
    check_arc(g, 2, 0, 0, 3, 3, 0, 3 * h, 3 * h, 1);
    assert_string_equal(geo_read(SVG_OPEN "<circle r=\"0\"/><ellipse ry=\"0\" "
                                          "rx=\"3\"/><ellipse/></svg>",
                                 g),
                        "");
    /* a rounded rectangle [1, 11] x [2, 8], rx 3 and ry 2: top side from
     * (4, 2) to (8, 2), the top right corner about (8, 4), ... */
    assert_string_equal(
        geo_read(SVG_OPEN "<rect x=\"1\" y=\"2\" width=\"10\" height=\"6\" rx=\"3\" ry=\"2\"/></svg>",
                 g),
        "sMLALALALAZ");
    near(g->v[1][0], 4, "rect start");
    near(g->v[2][0], 8, "top side");
    check_arc(g, 3, 8, 4, 3, 2, 0, 0, 0, 0);
    check_arc(g, 5, 8, 6, 3, 2, 0, 0, 0, 0);
    check_arc(g, 7, 4, 6, 3, 2, 0, 0, 0, 0);
    check_arc(g, 9, 4, 4, 3, 2, 0, 0, 0, 0);
    near(g->v[4][1], 6, "right side");
    near(g->v[9][8], 4, "back to the start x");
    near(g->v[9][9], 2, "back to the start y");
    /* one radius given: the other equals it; each clamped to half the side
     * (SVG 2: rx 30 -> ry 30, then rx 5 and ry 3): the sides vanish */
    assert_string_equal(
        geo_read(SVG_OPEN "<rect width=\"10\" height=\"6\" rx=\"30\"/></svg>", g), "sMAAAAZ");
    check_arc(g, 2, 5, 3, 5, 3, 0, 0, 0, 0);
    assert_string_equal(
        geo_read(SVG_OPEN "<rect width=\"10\" height=\"6\" ry=\"1\"/></svg>", g), "sMLALALALAZ");
    check_arc(g, 3, 9, 1, 1, 1, 0, 9 + h, 1 - h, 1);
    /* rx 0 (or ry 0) gives square corners */
    assert_string_equal(
        geo_read(SVG_OPEN "<rect width=\"10\" height=\"6\" rx=\"0\" ry=\"2\"/></svg>", g),
        "sMLLLZ");
    /* under a transform: the centre maps as a point, the semi-diameters as
     * vectors; scale(2, 3) of the circle of radius 1 at (1, 1) is the
     * ellipse of radii 2, 3 at (2, 3) */
    assert_string_equal(
        geo_read(SVG_OPEN "<circle transform=\"scale(2 3)\" cx=\"1\" cy=\"1\" r=\"1\"/></svg>", g),
        "sMAAAAZ");
    for (int q = 0; q < 4; q++)
        check_arc(g, 2 + q, 2, 3, 2, 3, 0, 0, 0, 0);
    /* a singular map flattens the circle onto the x axis: the quarters are
     * the lines between their ends (which bound the same, empty, region);
     * a map that nearly flattens it is refused */
    expect(SVG_OPEN "<circle transform=\"scale(1 0)\" r=\"5\"/></svg>",
           BLACK " M 5 0 L 0 0 L -5 0 L 0 0 L 5 0 Z");
    refused(L2("<circle transform=\"scale(1 1e-14)\" r=\"5\"/>"), "line 2: <circle>",
            "flattens");
}

/* The arc command (SVG 2, "The elliptical arc curve commands" and the
 * implementation notes): centres and midpoints worked out by hand. */
static void test_arc_command(void **state)
{
    (void)state;
    static geo_sink store; /* large: not on the stack */
    geo_sink *g = &store;
    const double h = sqrt(0.5);
    /* (0, 0) to (10, 0), radius 5, sweep 1 (angles increasing: from the
     * angle pi through 3 pi / 2, the point (5, -5)): the upper half */
    assert_string_equal(geo_read(PATH("M0 0 A 5 5 0 0 1 10 0"), g), "sMAZ");
    check_arc(g, 2, 5, 0, 5, 5, 0, 5, -5, 1);
    /* sweep 0: the lower half, through (5, 5) */
    geo_read(PATH("M0 0 A 5 5 0 1 0 10 0"), g);
    check_arc(g, 2, 5, 0, 5, 5, 0, 5, 5, 1);
    /* radii too small: scaled up until they reach (implementation notes,
     * F.6.6): 1 -> 5, the same half circle */
    geo_read(PATH("M0 0 A 1 1 0 0 1 10 0"), g);
    check_arc(g, 2, 5, 0, 5, 5, 0, 5, -5, 1);
    /* an ellipse 2 x 1 scaled by 5/2 to 5 x 2.5: the half through (5, -2.5) */
    geo_read(PATH("M0 0 A 2 1 0 0 1 10 0"), g);
    check_arc(g, 2, 5, 0, 5, 2.5, 0, 0, 0, 0);
    /* flags without separators: "a1 1 0 00 1 1" is rx 1, ry 1, rotation 0,
     * large 0, sweep 0, to (1, 1) relative: of the two unit circles through
     * (0, 0) and (1, 1) (centres (1, 0) and (0, 1)), the one whose short arc
     * goes from (0, 0) to (1, 1) with decreasing angle is centred at
     * (1, 0) (from pi to pi / 2), through (1 - h, h) */
    assert_string_equal(geo_read(PATH("M0 0 a1 1 0 00 1 1"), g), "sMAZ");
    check_arc(g, 2, 1, 0, 1, 1, 0, 1 - h, h, 1);
    geo_read(PATH("M0 0a1,1,0,0,0,1,1"), g);
    check_arc(g, 2, 1, 0, 1, 1, 0, 1 - h, h, 1);
    /* the large arc of the same: centre (0, 1), through (-h, 1 + h)... with
     * sweep 0 the large arc from (0, 0) to (1, 1) turns with decreasing
     * angle about (0, 1): from -pi / 2 down to -2 pi, through its middle
     * at -5 pi / 4, (-h, 1 + h) */
    geo_read(PATH("M0 0 a1 1 0 10 1 1"), g);
    check_arc(g, 2, 0, 1, 1, 1, 0, -h, 1 + h, 1);
    /* relative, and implicit repeats: two half circles */
    assert_string_equal(geo_read(PATH("m0 0 a5 5 0 0 1 10 0 5 5 0 0 1 10 0"), g), "sMAAZ");
    check_arc(g, 2, 5, 0, 5, 5, 0, 5, -5, 1);
    check_arc(g, 3, 15, 0, 5, 5, 0, 15, -5, 1);
    /* the rotation: rx 4 along the angle 90 degrees (the y axis), ry 2 across:
     * from (0, 0) to (0, 8) the half ellipse about (0, 4), through (2, 4)
     * with sweep 1 (from the top, angles increasing turn to the right) */
    geo_read(PATH("M 0 0 A 4 2 90 0 1 0 8"), g);
    check_arc(g, 2, 0, 4, 4, 2, M_PI / 2, 0, 0, 0);
    double x, y;
    const double *a = g->v[2];
    arc_at(a, (a[6] + a[7]) / 2, &x, &y);
    assert_true(x > 1); /* the right half */
    /* negative radii are made positive; a zero radius is a line; equal ends
     * draw nothing */
    geo_read(PATH("M0 0 A -5 -5 0 0 1 10 0"), g);
    check_arc(g, 2, 5, 0, 5, 5, 0, 5, -5, 1);
    expect(PATH("M0 0 A 0 5 0 0 1 10 0"), BLACK " M 0 0 L 10 0 Z");
    expect(PATH("M1 1 A 5 5 0 0 1 1 1 L 2 2"), BLACK " M 1 1 L 2 2 Z");
    /* after an arc, S and T do not reflect */
    expect(PATH("M0 0 A 0 5 0 0 1 10 0 T 20 0"), BLACK " M 0 0 L 10 0 Q 10 0 20 0 Z");
}

/* Strokes: the outline is a second shape after the fill, of the stroke's
 * colour, nonzero; every stroke property parsed. */
static void test_stroke_props(void **state)
{
    (void)state;
    static geo_sink store; /* large: not on the stack */
    geo_sink *g = &store;
    /* a white fill and a red stroke: two shapes, the fill first */
    const char *ops = geo_read(SVG_OPEN "<rect x=\"2\" y=\"2\" width=\"4\" height=\"4\" "
                                        "fill=\"white\" stroke=\"red\"/></svg>",
                               g);
    assert_true(ops[0] == 's' && strchr(ops + 1, 's'));
    int second = (int)(strchr(ops + 1, 's') - ops);
    assert_true(g->v[0][0] == 1 && g->v[0][1] == 1 && g->v[0][2] == 1);
    assert_true(g->v[second][0] == 1 && g->v[second][1] == 0 && g->v[second][2] == 0);
    assert_true(g->v[second][3] == AA_FILL_NONZERO);
    /* a line: a stroke only; fill none: a stroke only; stroke none, or a
     * width of 0: none */
    ops = geo_read(SVG_OPEN "<line x2=\"5\" stroke=\"white\"/></svg>", g);
    assert_true(ops[0] == 's' && !strchr(ops + 1, 's'));
    ops = geo_read(SVG_OPEN "<circle r=\"3\" fill=\"none\" stroke=\"white\"/></svg>", g);
    assert_true(ops[0] == 's' && !strchr(ops + 1, 's'));
    assert_string_equal(geo_read(SVG_OPEN "<line x2=\"5\" stroke=\"none\"/>"
                                          "<line x2=\"5\" stroke=\"red\" stroke-width=\"0\"/>"
                                          "<g stroke=\"red\"><line x2=\"5\" stroke=\"NONE\"/></g>"
                                          "</svg>",
                                 g),
                        "");
    /* every property, as attributes and in styles, in any case, inherited */
    ops = geo_read(SVG_OPEN "<g stroke=\"white\" style=\"stroke-linejoin: ROUND; "
                            "stroke-linecap: Square\" stroke-miterlimit=\"10\">"
                            "<polyline points=\"0 0 10 0 10 10\" fill=\"none\" "
                            "stroke-width=\"2px\" style=\"stroke-dasharray: 3, 1 2; "
                            "stroke-dashoffset: 1.5px\" stroke-opacity=\"1\"/></g></svg>",
                   g);
    assert_true(ops[0] == 's');
}

static double dec(double v) { return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); }

static void test_colours(void **state)
{
    (void)state;
    char want[512];
    /* named, #rgb, #rrggbb, rgb() of integers and of percentages: sRGB
     * values decoded to linear light (IEC 61966-2-1) */
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"red\"/></svg>",
           "fill 1 0 0 nonzero; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"#fFf\" fill-rule=\"evenodd\"/></svg>",
           "fill 1 1 1 evenodd; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    snprintf(want, sizeof want, "fill 0 0 %.17g nonzero; M 0 0 L 1 0 L 1 1 L 0 1 Z",
             dec(128 / 255.0)); /* navy is #000080 (CSS Color 3) */
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"navy\"/></svg>", want);
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"#000080\"/></svg>", want);
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"rgb(0, 0, 128)\"/></svg>", want);
    snprintf(want, sizeof want, "fill 1 0 %.17g nonzero; M 0 0 L 1 0 L 1 1 L 0 1 Z", dec(0.5));
    expect(SVG_OPEN "<rect width=\"1\" height=\"1\" fill=\"rgb(100%,0%, 50%)\"/></svg>", want);
    /* inherited from a group; the style attribute wins over the attribute */
    expect(SVG_OPEN "<g fill=\"lime\" fill-rule=\"evenodd\"><rect width=\"1\" height=\"1\"/>"
                    "<rect width=\"1\" height=\"1\" fill=\"red\" style=\"fill: blue ;\"/></g></svg>",
           "fill 0 1 0 evenodd; M 0 0 L 1 0 L 1 1 L 0 1 Z fill 0 0 1 evenodd; M 0 0 L 1 0 L 1 1 L "
           "0 1 Z");
}

static void test_viewbox(void **state)
{
    (void)state;
    double vp[2];
    /* 200 x 100 viewport, viewBox 10 x 10, meet: scale min(20, 10) = 10,
     * centred in x: offset (200 - 100) / 2 = 50; (1, 1) -> (60, 10) */
    const char *got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" "
                               "height=\"100\" viewBox=\"0 0 10 10\"><path d=\"M1 1\"/></svg>",
                               64, 64, vp);
    assert_string_equal(got, BLACK " M 60 10 Z");
    assert_true(vp[0] == 200 && vp[1] == 100);
    /* slice, aligned at the minimum: scale 20; (1, 1) -> (20, 20) */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"100\" "
                   "viewBox=\"0 0 10 10\" preserveAspectRatio=\"xMinYMin slice\"><path d=\"M1 1\"/></svg>",
                   64, 64, vp);
    assert_string_equal(got, BLACK " M 20 20 Z");
    /* slice at xMaxYMax: scale 20, y offset 100 - 200 = -100: (1, 1) -> (20, -80) */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"100\" "
                   "viewBox=\"0 0 10 10\" preserveAspectRatio=\"xMaxYMax slice\"><path d=\"M1 1\"/></svg>",
                   64, 64, vp);
    assert_string_equal(got, BLACK " M 20 -80 Z");
    /* none: 20 and 10; the viewBox's origin (-1, 2) goes to (0, 0) */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"100\" "
                   "viewBox=\"-1 2 10 10\" preserveAspectRatio=\"none\"><path d=\"M1 3\"/></svg>",
                   64, 64, vp);
    assert_string_equal(got, BLACK " M 40 10 Z");
    /* no width or height: the view's 64 x 32; viewBox 8 x 8 meets at 4,
     * centred in x: (64 - 32) / 2 = 16; (1, 1) -> (20, 4) */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0,0,8,8\"><path d=\"M1 1\"/></svg>",
                   64, 32, vp);
    assert_string_equal(got, BLACK " M 20 4 Z");
    assert_true(vp[0] == 64 && vp[1] == 32);
    /* no viewBox: user units are pixels */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10px\" height=\"100%\">"
                   "<path d=\"M1 1\"/></svg>",
                   64, 32, vp);
    assert_string_equal(got, BLACK " M 1 1 Z");
    assert_true(vp[0] == 10 && vp[1] == 32);
    /* a transform on the root, in CSS px outside the viewBox map, about
     * the centre of the viewport (CSS Transforms 1 on a layout box):
     * rotate(90) about (50, 50) takes (x, y) to (100 - y, x), after the
     * viewBox's scale 10; the viewport is then the view (the caller's
     * clip; the reader clips to the turned viewport) */
    got = read_doc("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"100\" "
                   "viewBox=\"0 0 10 10\" transform=\"rotate(90)\"><path d=\"M1 2\"/></svg>",
                   120, 110, vp);
    assert_string_equal(got, BLACK " M 80 10 Z");
    assert_true(vp[0] == 120 && vp[1] == 110);
}

/* ---- refusals ---- */

/* `doc` is refused with a message containing each of want[] (NULL-ended). */
static void refused(const char *doc, const char *want1, const char *want2)
{
    support_text t = {.n = 0};
    if (aa_svg_read(doc, strlen(doc), "test.svg", 64, 64, &sink, &t, NULL) != AA_EINVAL)
        fail_msg("accepted: %s", doc);
    const char *msg = aa_last_error();
    if ((want1 && !strstr(msg, want1)) || (want2 && !strstr(msg, want2)))
        fail_msg("%s\n  message: %s\n  wanted: %s / %s", doc, msg, want1, want2 ? want2 : "");
}

static void test_refusals(void **state)
{
    (void)state;
    /* shapes, arcs and strokes: invalid values, and what cannot be
     * stroked exactly yet (Bezier arcs, arcs of ellipses that are not
     * circles), or painted (stroke opacity) */
    refused(L2("<circle r=\"10ch\"/>"), "<circle>", "not a length");
    /* an invalid declaration is ignored (CSS 2.1, 4.2) and an invalid
     * attribute is its initial value (SVG 2): the line's stroke is drawn
     * opaque (this sink takes no translucent shape), of width 1 (the
     * outline of [0, 5] x [-1/2, 1/2]), solid, with butt caps, or not at
     * all (stroke none) */
    static const char *const opaque_line[] = {
        "<line x2=\"5\" stroke=\"red\" style=\"stroke-opacity: half\"/>",
        "<g style=\"stroke-opacity: 50% 1\"><line x2=\"5\" stroke=\"red\"/></g>",
        "<line x2=\"5\" stroke=\"red\" stroke-width=\"-1\"/>",
        "<line x2=\"5\" stroke=\"red\" style=\"stroke-linecap: flat\"/>",
        "<line x2=\"5\" stroke=\"red\" stroke-miterlimit=\"0.5\"/>",
        "<line x2=\"5\" stroke=\"red\" stroke-dasharray=\"1 -2\"/>",
    };
    for (size_t k = 0; k < sizeof opaque_line / sizeof opaque_line[0]; k++) {
        char doc[512];
        snprintf(doc, sizeof doc, L2("%s"), opaque_line[k]);
        const char *got = read_doc(doc, 64, 64, NULL);
        if (!strstr(got, "fill 1 0 0 nonzero;") || !strstr(got, " 5 -0.5") ||
            !strstr(got, " 0 0.5") || strstr(got, " 1 -0.5"))
            fail_msg("%s: %s", doc, got);
    }
    assert_string_equal(read_doc(L2("<line x2=\"5\" stroke=\"#f00z\"/>"), 64, 64, NULL), "");
    /* a sink without `alpha` takes no translucent shape (test_opacity.c
     * reads them through the pattern's) */
    refused(L2("<line x2=\"5\" stroke=\"red\" stroke-opacity=\"0.5\"/>"), "line 2: <line>",
            "translucent");
    /* nor gradient paint (test_gradient.c reads it through the pattern's) */
    refused(L2("<linearGradient id=\"g\"><stop/><stop offset=\"1\"/></linearGradient>"
               "<rect width=\"1\" height=\"1\" stroke=\"url(#g)\"/>"),
            "<rect>", "gradient paint is not taken here");
    refused(L2("<line x2=\"5\" stroke=\"red\" stroke-width=\"10ch\"/>"), "<line>", "length");
    refused(L2("<line x2=\"5\" stroke-dasharray=\"1 2lh\"/>"), "<line>", "stroke-dasharray");
    /* pathLength 0 scales an offset to infinity: no one picture */
    refused(L2("<line x2=\"5\" stroke=\"red\" stroke-dasharray=\"1\" stroke-dashoffset=\"1\" "
               "pathLength=\"0\"/>"),
            "<line>", "pathLength");
    refused(L2("<line x2=\"5\" stroke-dashoffset=\"1cap\"/>"), "<line>", "stroke-dashoffset");
    /* a stroked Bezier arc nearly with a cusp (its speed 1e-10 of its size
     * near t = 1/2, neither 0 to rounding nor clear of it) */
    refused(L2("\n\n<path stroke=\"red\" d=\"M0 0 C 10 10 0.000000001 10 10 0\"/>"),
            "line 4: <path>", "cusp");
    /* a dash pattern finer than the limits allow */
    refused(L2("<line x2=\"100000\" stroke=\"red\" stroke-dasharray=\"0.001\"/>"), "<line>",
            "dashes");
    /* fill-opacity: . is ignored and fill="bogus" is black, the initial
     * fill: an opaque black square (this sink takes no translucent shape) */
    assert_string_equal(read_doc(L2("<rect width=\"1\" height=\"1\" style=\"fill-opacity: .\" "
                                    "fill=\"bogus\"/>"),
                                 64, 64, NULL),
                        BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    refused(L2("<rect width=\"1\" height=\"1\" color-interpolation=\"linearRGB\"/>"), "<rect>",
            "linear light");
    /* nor a group of an opacity */
    refused(L2("<g opacity=\"0.99\"/>"), "<g>", "opacity");
    refused(L2("<rect width=\"1\" height=\"1\" fill=\"#f008\"/>"), "<rect>", "alpha");
    refused(L2("<defs><pattern id=\"a\"/></defs><rect width=\"1\" height=\"1\" fill=\"url(#a)\"/>"),
            "<rect>", "patterns are not supported");
    refused(L2("<rect width=\"1\" height=\"1\" fill=\"url(o.svg#a)\"/>"), "<rect>",
            "this document");
    refused(L2("<text>hi</text>"), "line 2: <text>", "text");
    refused(L2("<image href=\"x.png\"/>"), "<image>", "images");
    /* this sink takes no clips: a clip path it would need is refused */
    refused(L2("<clipPath id=\"c\"/><rect width=\"1\" height=\"1\" clip-path=\"url(#c)\"/>"),
            "<rect>", "clip paths are not taken here");
    refused(L2("<rect width=\"1\" height=\"1\" clip-path=\"circle(1px)\"/>"), "<rect>",
            "clip paths are not taken here");
    refused(L2("<use href=\"other.svg#a\"/>"), "<use>", "another document");
    refused(L2("<style>rect:first-child{fill:red}</style>"), "line 2: <style>", "pseudo-class");
    /* nor content beyond a viewport that clips, which needs a clip */
    refused(L2("<svg width=\"4\" height=\"4\"><rect width=\"5\" height=\"1\"/></svg>"),
            "line 2: <rect>", "viewport of the <svg> at line 2");
    refused(L2("<blink/>"), "<blink>", "not supported");
    refused(L2("<rect width=\"10pz\" height=\"1\"/>"), "<rect>", "not a length");
    refused(L2("<polygon points=\"0 0 1\"/>"), "<polygon>", "odd");
    refused(L2("<path style=\"transform: spin(3)\" d=\"M0 0\"/>"), "<path>", "transform");
    refused(L2("<path transform=\"skewX(90)\" d=\"M0 0\"/>"), "<path>", "infinite");
    /* absurd numbers: beyond AA_SVG_MAX_NUMBER, overflowing a double, and
     * coordinates that transforms carry beyond AA_SVG_MAX_COORD */
    refused(L2("<path d=\"M 1e10 0\"/>"), "<path>", "out of range");
    refused(L2("<path d=\"M 1e400 0\"/>"), "<path>", "out of range");
    refused(L2("<path transform=\"scale(1e5)\" d=\"M 1e3 0\"/>"), "<path>", "beyond");
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1e300\"/>", "width", NULL);
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 0 1\"/>", "viewBox", "positive");
    /* a root transform moving the viewport: content beyond it needs a
     * clip, which this sink does not take */
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\" "
            "transform=\"translate(1 0)\"><rect width=\"20\" height=\"1\"/></svg>",
            "<rect>", "beyond the viewport of the <svg> at line 1");
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 1 1\" "
            "preserveAspectRatio=\"xMidYMed\"/>",
            "preserveAspectRatio", NULL);
    /* not SVG, malformed XML */
    refused("<svg/>", "not <svg> in the SVG namespace", NULL);
    refused("<html xmlns=\"http://www.w3.org/2000/svg\"/>", "not <svg>", NULL);
    refused(L2("<rect>"), "malformed XML", "line");
    refused("", "malformed XML", NULL);
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\"><rect width=\"1\" width=\"2\"/></svg>",
            "malformed XML", NULL);
}

/* External and internal entities are never loaded nor expanded: a document
 * declaring any is refused, whatever it names (a file, the network, a
 * billion laughs). */
static void test_entities(void **state)
{
    (void)state;
    refused("<?xml version=\"1.0\"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM \"file:///etc/passwd\">]>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"&x;\"/></svg>",
            "entity", NULL);
    refused("<?xml version=\"1.0\"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM \"http://127.0.0.1:9/x\">]>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\">&x;</svg>",
            "entity", NULL);
    refused("<!DOCTYPE svg [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;\">]>"
            "<svg xmlns=\"http://www.w3.org/2000/svg\"><desc>&b;</desc></svg>",
            "entity", NULL);
    /* an external DTD is not fetched: the document is read without it */
    expect("<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" "
           "\"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">" PATH("M1 1"),
           BLACK " M 1 1 Z");
}

static void test_deep_and_huge(void **state)
{
    (void)state;
    /* nesting deeper than AA_SVG_MAX_DEPTH */
    size_t cap = 100000, n = 0;
    char *doc = malloc(cap);
    assert_non_null(doc);
    n += (size_t)sprintf(doc + n, "%s", SVG_OPEN);
    for (int k = 0; k < AA_SVG_MAX_DEPTH + 5; k++)
        n += (size_t)sprintf(doc + n, "<g>");
    for (int k = 0; k < AA_SVG_MAX_DEPTH + 5; k++)
        n += (size_t)sprintf(doc + n, "</g>");
    sprintf(doc + n, "</svg>");
    refused(doc, "nested deeper", NULL);
    /* nesting far past libxml2's own limit is malformed to it */
    free(doc);
    cap = 20000 * 7 + 100;
    doc = malloc(cap);
    assert_non_null(doc);
    n = (size_t)sprintf(doc, "%s", SVG_OPEN);
    for (int k = 0; k < 20000; k++)
        n += (size_t)sprintf(doc + n, "<g>");
    refused(doc, "malformed XML", NULL);
    free(doc);
    /* a document larger than AA_SVG_MAX_BYTES is refused before parsing */
    support_text t = {.n = 0};
    assert_int_equal(aa_svg_read(SVG_OPEN, (size_t)AA_SVG_MAX_BYTES + 1, "big.svg", 8, 8, &sink,
                                 &t, NULL),
                     AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "larger than"));
}

/* ---- files, scenes and references ---- */

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "svg");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

static void write_svg(const char *path, const char *doc)
{
    support_write_file(path, doc, strlen(doc));
}

/* The exact box coverage of [a, b] x [c, d] in pixel (i, j): the product
 * of the overlaps of the intervals (closed form). */
static double overlap(double a, double b, double lo, double hi)
{
    double x0 = fmax(a, lo), x1 = fmin(b, hi);
    return x1 > x0 ? x1 - x0 : 0;
}

static void test_rect_reference(void **state)
{
    (void)state;
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/rect.svg", dir);
    /* viewport 6 x 8 in a view of 8 x 8: the rectangle's part beyond x = 6
     * is clipped; a white rectangle [1.25, 7.5] x [2.5, 4.25], of which
     * [1.25, 6] x [2.5, 4.25] shows */
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"6\" height=\"8\">"
                    "<rect x=\"1.25\" y=\"2.5\" width=\"6.25\" height=\"1.75\" fill=\"white\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_image img;
    support_pattern_reference(spec, &(support_view){.w = 8, .h = 8}, &img, NULL, NULL);
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) {
            double want = overlap(1.25, 6, i, i + 1) * overlap(2.5, 4.25, j, j + 1);
            for (int c = 0; c < 3; c++)
                if (fabs(aa_pixel(&img, i, j)[c] - want) > 1e-14)
                    fail_msg("pixel (%d, %d): %.17g, want %.17g", i, j, aa_pixel(&img, i, j)[c],
                             want);
        }
    aa_image_free(&img);
}

/* The box reference's sum of the white document `doc` on a w x h view. */
static double doc_sum(const char *name, const char *doc, int w, int h, aa_image *keep)
{
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    write_svg(path, doc);
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_image img;
    support_pattern_reference(spec, &(support_view){.w = w, .h = h}, &img, NULL, NULL);
    double sum = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            sum += aa_pixel(&img, i, j)[0];
    if (keep)
        *keep = img;
    else
        aa_image_free(&img);
    return sum;
}

/* The speed of the cubic (2, 16) (10, 2) (22, 30) (30, 16) at t. */
static double cubic_speed(double t)
{
    const double x[4] = {2, 10, 22, 30}, y[4] = {16, 2, 30, 16}, u = 1 - t;
    double dx = 3 * (u * u * (x[1] - x[0]) + 2 * u * t * (x[2] - x[1]) + t * t * (x[3] - x[2]));
    double dy = 3 * (u * u * (y[1] - y[0]) + 2 * u * t * (y[2] - y[1]) + t * t * (y[3] - y[2]));
    return hypot(dx, dy);
}

#define LINE_DOC(attrs)                                                                    \
    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"8\"><path d=\"M0 4 H30\" " \
    "stroke=\"white\" stroke-width=\"2\" " attrs "/></svg>"

/* pathLength (SVG 2, "The pathLength attribute"): the dashes and the offset
 * scaled by the computed length over the author's.  The sums are the
 * dashes' areas worked by hand (stroke width 2, butt caps). */
static void test_path_length(void **state)
{
    (void)state;
    static const struct {
        const char *name, *doc, *what;
        double area;
    } cases[] = {
        /* a line of 30 given as 15: "3 1" becomes 6 on, 2 off: [0, 6],
         * [8, 14], [16, 22], [24, 30], 24 long (unscaled it would be 7
         * dashes of 3 and [28, 30], 23) */
        {"line", LINE_DOC("pathLength=\"15\" stroke-dasharray=\"3 1\""), "2 x 24", 48},
        /* the offset 1 scaled to 2: [-2, 4], [6, 12], [14, 20], [22, 28] */
        {"offset", LINE_DOC("pathLength=\"15\" stroke-dasharray=\"3 1\" "
                            "stroke-dashoffset=\"1\""), "2 x 22", 44},
        /* a negative value is an error: ignored (the unscaled 23) */
        {"negative", LINE_DOC("pathLength=\"-15\" stroke-dasharray=\"3 1\""), "2 x 23", 46},
        /* 0: an infinite scale, the first dash covering the line */
        {"zero", LINE_DOC("pathLength=\"0\" stroke-dasharray=\"3 1\""), "2 x 30", 60},
        /* a circle of radius 5 given as 4: dashes of a quarter turn, on
         * and off, half the ring between radii 4 and 6 (unscaled, dashes
         * of 1 on 10 pi would cover 16 of it) */
        {"circle", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"16\" height=\"16\">"
                   "<circle cx=\"8\" cy=\"8\" r=\"5\" fill=\"none\" stroke=\"white\" "
                   "stroke-width=\"2\" pathLength=\"4\" stroke-dasharray=\"1\"/></svg>",
         "10 pi", 10 * M_PI},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double sum = doc_sum(cases[k].name, cases[k].doc, 32, 16, NULL);
        printf("# pathLength %s: sum %.17g, %s %.17g, error %.3g\n", cases[k].name, sum,
               cases[k].what, cases[k].area, sum - cases[k].area);
        if (!(fabs(sum - cases[k].area) < 1e-11))
            fail_msg("pathLength %s: sum %.17g, want %.17g", cases[k].name, sum, cases[k].area);
    }
    /* along a cubic: pathLength 2 and dashes of 1 dash the first half of
     * its length L, as dashes of L / 2 without pathLength do; L by
     * composite Simpson's rule on its speed (4096 intervals: the error,
     * of order h^4, is below 1e-13 here), not by the code under test */
    double L = 0;
    const int n = 4096;
    for (int i = 0; i <= n; i++)
        L += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * cubic_speed((double)i / n);
    L /= 3.0 * n;
    char doc[2][512];
    for (int k = 0; k < 2; k++) {
        char dash[64];
        if (k)
            snprintf(dash, sizeof dash, "stroke-dasharray=\"%.17g\"", L / 2);
        else
            snprintf(dash, sizeof dash, "pathLength=\"2\" stroke-dasharray=\"1\"");
        snprintf(doc[k], sizeof doc[k],
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"32\">"
                 "<path d=\"M2 16 C10 2 22 30 30 16\" fill=\"none\" stroke=\"white\" "
                 "stroke-width=\"3\" %s/></svg>",
                 dash);
    }
    aa_image a, b;
    doc_sum("cubic-pl", doc[0], 32, 32, &a);
    doc_sum("cubic-l", doc[1], 32, 32, &b);
    int wi, wj;
    double d = support_max_diff(&a, &b, &wi, &wj);
    printf("# pathLength on a cubic of length %.15g: max difference %.3g\n", L, d);
    if (!(d <= 1e-10))
        fail_msg("pathLength on a cubic: max difference %.3g at (%d, %d)", d, wi, wj);
    aa_image_free(&a);
    aa_image_free(&b);
}

/* Painter's order: the later shape is in front. */
static void test_painters_order(void **state)
{
    (void)state;
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/order.svg", dir);
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\">"
                    "<rect width=\"4\" height=\"4\" fill=\"red\"/>"
                    "<rect x=\"2\" width=\"2\" height=\"4\" fill=\"blue\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_image img;
    support_pattern_reference(spec, &(support_view){.w = 4, .h = 4}, &img, NULL, NULL);
    const double *a = aa_pixel(&img, 1, 1), *b = aa_pixel(&img, 3, 1);
    assert_true(a[0] == 1 && a[1] == 0 && a[2] == 0);
    assert_true(b[0] == 0 && b[1] == 0 && b[2] == 1);
    aa_image_free(&img);
}

/* Layers: consecutive shapes of one colour and rule whose boxes are
 * disjoint share a layer; overlapping ones do not, so that even-odd shapes
 * painted over each other stay filled where they overlap (two opaque
 * squares: the overlap is white, where one even-odd layer of both would
 * leave it black). */
static void test_layers(void **state)
{
    (void)state;
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/layers.svg", dir);
    aa_spec s;
    aa_scene *sc;
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" fill=\"white\">"
                    "<rect width=\"1\" height=\"1\"/><rect x=\"2\" width=\"1\" height=\"1\"/>"
                    "<rect x=\"4\" width=\"1\" height=\"1\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    assert_int_equal(aa_pattern_parse(spec, &s), AA_OK);
    assert_int_equal(aa_pattern_scene_at(&s, 8, 8, &sc), AA_OK);
    assert_int_equal(aa_scene_layer_count(sc), 1);
    aa_scene_free(sc);
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" fill=\"white\" fill-rule=\"evenodd\">"
                    "<rect width=\"2\" height=\"2\"/><rect x=\"1\" y=\"1\" width=\"2\" height=\"2\"/></svg>");
    assert_int_equal(aa_pattern_scene_at(&s, 4, 4, &sc), AA_OK);
    assert_int_equal(aa_scene_layer_count(sc), 2);
    aa_scene_free(sc);
    aa_image img;
    support_pattern_reference(spec, &(support_view){.w = 4, .h = 4}, &img, NULL, NULL);
    assert_true(aa_pixel(&img, 1, 1)[0] == 1 && aa_pixel(&img, 3, 3)[0] == 0);
    aa_image_free(&img);
}

/* The key of a view changes with the file's bytes, not its name. */
static void test_cache_key(void **state)
{
    (void)state;
    char path[4200], spec[4400], k1[8192], k2[8192], k3[8192];
    snprintf(path, sizeof path, "%s/key.svg", dir);
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_view v = {0};
    v.w = v.h = 8;
    aa_filter_default(&v.filter);
    assert_int_equal(aa_pattern_parse(spec, &v.pattern), AA_OK);
    write_svg(path, PATH("M0 0 L1 0 L1 1"));
    assert_int_equal(aa_view_key(&v, k1, sizeof k1), AA_OK);
    assert_int_equal(aa_view_key(&v, k2, sizeof k2), AA_OK);
    assert_string_equal(k1, k2);
    write_svg(path, PATH("M0 0 L1 0 L1 2"));
    assert_int_equal(aa_view_key(&v, k3, sizeof k3), AA_OK);
    assert_string_not_equal(k1, k3);
    assert_non_null(strstr(k1, "file fnv1a"));
}

/* TEXT values: %XX escapes, the canonical text, refusals. */
static void test_text_values(void **state)
{
    (void)state;
    aa_spec s;
    char buf[4096];
    assert_int_equal(aa_pattern_parse("svg:file=a%2Cb%25c d=e", &s), AA_OK);
    assert_string_equal(aa_param_text(s.v[0]), "a,b%c d=e");
    assert_int_equal(aa_spec_format(&s, buf, sizeof buf), AA_OK);
    assert_string_equal(buf, "svg:file=a%2Cb%25c d=e,scale=1");
    aa_spec back;
    assert_int_equal(aa_pattern_parse(buf, &back), AA_OK);
    assert_true(back.v[0] == s.v[0]);
    /* control characters written %XX, and so in the canonical text */
    assert_int_equal(aa_pattern_parse("svg:file=a%0ab", &s), AA_OK);
    assert_string_equal(aa_param_text(s.v[0]), "a\nb");
    assert_int_equal(aa_spec_format(&s, buf, sizeof buf), AA_OK);
    assert_string_equal(buf, "svg:file=a%0Ab,scale=1");
    static const char *bad[] = {"svg:file=a%2", "svg:file=a%zz", "svg:file=%00", "svg:file=a,b",
                                "svg:file=", "svg:file=a\nb", "svg:file=a\tb"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        if (aa_pattern_parse(bad[k], &s) == AA_OK)
            fail_msg("%s was accepted", bad[k]);
    /* unsized building is refused with a reason */
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse("svg", &s), AA_OK);
    assert_int_equal(aa_pattern_scene(&s, &sc), AA_EINVAL);
    assert_null(sc);
}

/* The svg pattern's status for spec, made into a scene of 16 x 16 pixels;
 * the message must hold needle. */
static void svg_refused(const char *spec, const char *needle)
{
    aa_spec s;
    aa_scene *sc = NULL;
    int st = aa_pattern_parse(spec, &s);
    if (st == AA_OK)
        st = aa_pattern_scene_at(&s, 16, 16, &sc);
    aa_scene_free(sc);
    if (st != AA_EINVAL || !strstr(aa_last_error(), needle))
        fail_msg("%s: status %d, \"%s\" (expected \"%s\")", spec, st, aa_last_error(), needle);
}

/* Files refused by the library: missing, over 64 MB (refused before it is
 * read: a sparse file), a folder.  Then the command: a refusal is exit 2
 * naming the element and the line; the default file draws. */
static void test_command(void **state)
{
    (void)state;
    char path[4200], spec[4400], out[8192], txt[4200];
    snprintf(spec, sizeof spec, "svg:file=%s/none.svg", dir);
    svg_refused(spec, "none.svg");
    char big[4300];
    snprintf(big, sizeof big, "%s/big.svg", dir);
    FILE *f = fopen(big, "wb");
    assert_non_null(f);
    assert_int_equal(ftruncate(fileno(f), (off_t)AA_SVG_MAX_BYTES + 1), 0);
    fclose(f);
    snprintf(spec, sizeof spec, "svg:file=%s", big);
    svg_refused(spec, "larger than");
    assert_int_equal(unlink(big), 0);
    snprintf(spec, sizeof spec, "svg:file=%s", dir);
    svg_refused(spec, "not a regular file");

    snprintf(path, sizeof path, "%s/circle.svg", dir);
    snprintf(txt, sizeof txt, "%s/out.txt", dir);
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\">\n\n<use href=\"b.svg#a\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    const char *args[] = {"truth", "-p", spec, "-s", "16x16", "-o", txt, NULL};
    assert_int_equal(support_aabench(args, out, sizeof out), 2);
    if (!strstr(out, "line 3") || !strstr(out, "<use>"))
        fail_msg("message: %s", out);
    const char *def[] = {"truth", "-p", "svg", "-s", "32x32", "-o", txt, NULL};
    assert_int_equal(support_aabench(def, out, sizeof out), 0);
}

/* svg:file=PATH,scale=S draws the document at S pixels a CSS pixel, as
 * rsvg-convert -z does, and without -s the image is the file's own size
 * times S (rounded up to whole pixels).  Known answers: a white
 * rectangle's box reference sums to its area times S^2 (clipped to the
 * viewport, itself scaled); a viewBox scales the same way. */
static void test_scale(void **state)
{
    (void)state;
    char path[4200], spec[4400], out[8192], txt[4200];
    snprintf(path, sizeof path, "%s/scaled.svg", dir);
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"10.5\">"
                    "<rect x=\"2.25\" y=\"1.5\" width=\"10\" height=\"5\" fill=\"white\"/>"
                    "<rect x=\"15\" y=\"8\" width=\"10\" height=\"10\" fill=\"white\"/></svg>");
    static const struct {
        double scale;
        int w, h;
    } cases[] = {{1, 20, 11}, {2, 40, 21}, {1.5, 30, 16}, {0.25, 5, 3}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double S = cases[k].scale;
        snprintf(spec, sizeof spec, "svg:file=%s,scale=%g", path, S);
        aa_spec ps;
        int w, h;
        assert_int_equal(aa_pattern_parse(spec, &ps), AA_OK);
        if (aa_pattern_own_size(&ps, &w, &h))
            fail_msg("%s: %s", spec, aa_last_error());
        assert_int_equal(w, cases[k].w);
        assert_int_equal(h, cases[k].h);
        /* the first rectangle, and the second cut by the viewport at
         * (20, 10.5): 5 x 2.5 */
        support_view v = {w, h, 0, 0, 0, NULL, 1, 1, 0};
        aa_image ref;
        support_pattern_reference(spec, &v, &ref, NULL, NULL);
        const double want = (50 + 12.5) * S * S;
        const double got = support_channel_mean(&ref, 0) * w * h;
        if (!(fabs(got - want) <= 1e-12 * want))
            fail_msg("%s: the box reference sums to %.17g, not %.17g", spec, got, want);
        aa_image_free(&ref);
    }
    /* a viewBox: 100 user units in 10 CSS px, at 3 pixels a CSS pixel */
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\" "
                    "viewBox=\"0 0 100 100\"><rect width=\"50\" height=\"30\" fill=\"white\"/>"
                    "</svg>");
    snprintf(spec, sizeof spec, "svg:file=%s,scale=3", path);
    snprintf(txt, sizeof txt, "%s/scaled.txt", dir);
    const char *args[] = {"truth", "-p", spec, "-o", txt, NULL};
    assert_int_equal(support_aabench(args, out, sizeof out), 0);
    if (!strstr(out, " 30x30 box"))
        fail_msg("without -s: %s", out);
    aa_image img;
    assert_int_equal(aa_image_read_txt(txt, &img), AA_OK);
    assert_int_equal(img.w, 30);
    const double got = support_channel_mean(&img, 0) * 30 * 30;
    if (!(fabs(got - 15 * 9) <= 1e-12 * 135))
        fail_msg("viewBox at scale 3: sum %.17g, not 135", got);
    aa_image_free(&img);
    /* -s still wins: the document in the view's top left corner */
    const char *sized[] = {"truth", "-p", spec, "-s", "64x48", "-o", txt, NULL};
    assert_int_equal(support_aabench(sized, out, sizeof out), 0);
    assert_non_null(strstr(out, " 64x48 box"));
    /* no size of its own: -s is needed, and said so */
    write_svg(path, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100%\" height=\"8\">"
                    "<rect width=\"3\" height=\"3\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    assert_int_equal(support_aabench(args, out, sizeof out), 2);
    if (!strstr(out, "no size of its own"))
        fail_msg("message: %s", out);
    const char *crow[] = {"render", "-p", "crow", "-m", "point", "-o", txt, NULL};
    assert_int_equal(support_aabench(crow, out, sizeof out), 2);
    if (!strstr(out, "-s WxH"))
        fail_msg("message: %s", out);
    /* the scale's range */
    aa_spec ps;
    snprintf(spec, sizeof spec, "svg:file=%s,scale=0", path);
    assert_int_equal(aa_pattern_parse(spec, &ps), AA_EINVAL);
    snprintf(spec, sizeof spec, "svg:file=%s,scale=65", path);
    assert_int_equal(aa_pattern_parse(spec, &ps), AA_EINVAL);
}

/* Export, read back: the same reference to 1e-15, for every pattern of
 * paths (the exported document is in pixels, viewBox 0 0 W H), text and
 * the default SVG scene among them: the library's writer
 * (aa_scene_svg_write) for each, `aabench export` for the first. */
static void test_export_round_trip(void **state)
{
    (void)state;
    static const char *patterns[] = {"crow",  "catmull", "slivers",      "star", "feibush",
                                     "fence", "dots",    "text:ppem=12", "svg"};
    for (size_t k = 0; k < sizeof patterns / sizeof patterns[0]; k++) {
        char path[4200], spec[4400], out[4096];
        snprintf(path, sizeof path, "%s/%.12s.svg", dir, patterns[k]);
        if (k == 0) {
            const char *args[] = {"export", "-p", patterns[k], "-s", "64x48", "-o", path, "-q",
                                  NULL};
            if (support_aabench(args, out, sizeof out) != 0)
                fail_msg("export %s: %s", patterns[k], out);
        } else {
            aa_spec ps;
            aa_scene *scene = NULL, *placed = NULL;
            int st = aa_pattern_parse(patterns[k], &ps);
            if (st == AA_OK)
                st = aa_pattern_scene_at(&ps, 64, 48, &scene);
            if (st == AA_OK && (placed = aa_scene_place(scene, 64, 48, 0, 0, 0)) == NULL)
                st = AA_ENOMEM;
            if (st == AA_OK)
                st = aa_scene_svg_write(path, placed, 64, 48, AA_SVG_COLOURS, NULL);
            if (st != AA_OK)
                fail_msg("export %s: %s", patterns[k], aa_last_error());
            aa_scene_free(placed);
            aa_scene_free(scene);
        }
        snprintf(spec, sizeof spec, "svg:file=%s", path);
        aa_image a, b;
        support_view v = {.w = 64, .h = 48};
        support_pattern_reference(patterns[k], &v, &a, NULL, NULL);
        support_pattern_reference(spec, &v, &b, NULL, NULL);
        int wi, wj;
        double d = support_max_diff(&a, &b, &wi, &wj);
        printf("# export round trip %s: max difference %.3g\n", patterns[k], d);
        if (!(d <= 1e-15))
            fail_msg("%s: max difference %.3g at (%d, %d)", patterns[k], d, wi, wj);
        aa_image_free(&a);
        aa_image_free(&b);
    }
}

/* Strokes of ellipses and of a cusp written by `export` (as strokes: the
 * source path with its A commands, not the offset curves) and read back:
 * the same box reference, to 1e-13.  Not to 1e-15 as the patterns above:
 * an elliptical arc is written as its radii and angle, cut at quarter
 * turns, and read back through SVG's endpoint parametrization, so the
 * ellipse comes back to rounding, not bit for bit, and its stroke moves
 * with it (3.6e-15 here without the dashes, where the thin ellipse's
 * offset folds; 1.7e-14 with them, the dash ends moving with the arc
 * lengths summed over the parts). */
static void test_export_strokes(void **state)
{
    (void)state;
    char src[4200], dst[4200], spec[4400];
    snprintf(src, sizeof src, "%s/strokes.svg", dir);
    snprintf(dst, sizeof dst, "%s/strokes-export.svg", dir);
    write_svg(src, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"64\" height=\"48\">"
                   "<ellipse cx=\"20\" cy=\"16\" rx=\"14\" ry=\"3\" fill=\"none\" "
                   "stroke=\"white\" stroke-width=\"7\" stroke-dasharray=\"9 2\"/>"
                   "<rect x=\"36\" y=\"6\" width=\"22\" height=\"14\" rx=\"9\" ry=\"4\" "
                   "fill=\"none\" stroke=\"red\" stroke-width=\"3\" "
                   "transform=\"rotate(10 47 13) scale(1 1.2)\"/>"
                   "<path d=\"M 8 28 C 30 46 8 46 30 28 A 12 5 20 0 1 56 40\" fill=\"none\" "
                   "stroke=\"lime\" stroke-width=\"5\" stroke-linejoin=\"round\"/></svg>");
    snprintf(spec, sizeof spec, "svg:file=%s", src);
    aa_spec ps;
    aa_scene *scene = NULL, *placed = NULL;
    int st = aa_pattern_parse(spec, &ps);
    if (st == AA_OK)
        st = aa_pattern_scene_at(&ps, 64, 48, &scene);
    if (st == AA_OK && (placed = aa_scene_place(scene, 64, 48, 0, 0, 0)) == NULL)
        st = AA_ENOMEM;
    if (st == AA_OK)
        st = aa_scene_svg_write(dst, placed, 64, 48, AA_SVG_COLOURS, NULL);
    if (st != AA_OK)
        fail_msg("export: %s", aa_last_error());
    aa_scene_free(placed);
    aa_scene_free(scene);
    aa_image a, b;
    support_view v = {.w = 64, .h = 48};
    char back[4400];
    snprintf(back, sizeof back, "svg:file=%s", dst);
    support_pattern_reference(spec, &v, &a, NULL, NULL);
    support_pattern_reference(back, &v, &b, NULL, NULL);
    int wi, wj;
    double d = support_max_diff(&a, &b, &wi, &wj);
    printf("# export round trip, stroked ellipses and a cusp: max difference %.3g at (%d, %d)\n",
           d, wi, wj);
    if (!(d <= 1e-13))
        fail_msg("max difference %.3g at (%d, %d)", d, wi, wj);
    aa_image_free(&a);
    aa_image_free(&b);
}

/* Cubic arcs in a scene: a cubic that is a quadratic raised to degree three
 * (control points P0 + 2/3 (Q - P0) and P2 + 2/3 (Q - P2): the same curve)
 * has the quadratic's reference.  Live once the scene holds cubics. */
static void test_cubic_scene(void **state)
{
    (void)state;
    int can = support_scene_holds_cubics();
    if (!can) {
        printf("# skipped: aa_scene_cubic_to refuses (%s)\n", aa_last_error());
        skip();
    }
    char pq[4200], pc[4200], sq[4400], sc[4400];
    snprintf(pq, sizeof pq, "%s/quad.svg", dir);
    snprintf(pc, sizeof pc, "%s/cubic.svg", dir);
    /* P0 (3, 12), Q (9, 0), P2 (15, 12): C1 = (7, 4), C2 = (11, 4) */
    write_svg(pq, PATH("M3 12 Q 9 0 15 12 Z"));
    write_svg(pc, PATH("M3 12 C 7 4 11 4 15 12 Z"));
    snprintf(sq, sizeof sq, "svg:file=%s", pq);
    snprintf(sc, sizeof sc, "svg:file=%s", pc);
    aa_image a, b;
    support_view v = {.w = 16, .h = 16};
    support_pattern_reference(sq, &v, &a, NULL, NULL);
    support_pattern_reference(sc, &v, &b, NULL, NULL);
    assert_true(support_max_diff(&a, &b, NULL, NULL) <= 1e-13);
    aa_image_free(&a);
    aa_image_free(&b);
}

/* Every presentation attribute or style property the reader does not
 * implement is refused, named with its line: skipped, each would change
 * the picture (SVG 2 and CSS: transform in a style, transform-origin,
 * transform-box, mix-blend-mode, markers, conditional processing).  CSS
 * property names and keywords match in any case; attribute names are XML
 * names and match exactly, so an upper-case attribute is refused too. */
#define R1 "<rect width=\"4\" height=\"4\" "
static void test_unknown_properties(void **state)
{
    (void)state;
    refused(L2(R1 "style=\"transform: scale(2) perspective(3px)\"/>"), "line 2: <rect>",
            "transform");
    refused(L2(R1 "transform=\"scale(2)\" transform-origin=\"2 2 1px\"/>"), "line 2: <rect>",
            "transform-origin");
    refused(L2("<g mix-blend-mode=\"multiply\">" R1 "/></g>"), "line 2: <g>", "mix-blend-mode");
    refused(L2("<path d=\"M0 0 L4 0 L4 4z\" marker-start=\"url(#m)\"/>"), "line 2: <path>",
            "marker-start");
    refused(L2("<path d=\"M0 0 L4 0 L4 4z\" style=\"marker: url(#m)\"/>"), "line 2: <path>",
            "marker");
    refused(L2("<path d=\"M0 0 L4 0 L4 4z\" marker-mid=\"url(#m)\"/>"), "<path>", "marker-mid");
    refused(L2("<path d=\"M0 0 L4 0 L4 4z\" marker-end=\"url(#m)\"/>"), "<path>", "marker-end");
    refused(L2(R1 "style=\"display: none !importan\"/>"), "line 2: <rect>", "not a declaration");
    refused(L2(R1 "style=\"fill: red!\"/>"), "<rect>", "not a declaration");
    refused(L2(R1 "FILL=\"white\"/>"), "line 2: <rect>", "FILL");
    refused(L2("\n" R1 "baseFrequency=\"1\"/>"), "line 3: <rect>", "baseFrequency");
    refused(L2("<g requiredFoo=\"\">" R1 "/></g>"), "<g>", "requiredFoo");
    refused(L2(R1 "shape-rendering=\"crispEdges\"/>"), "<rect>", "shape-rendering");
    refused(L2(R1 "style=\"fill: red; bogus\"/>"), "<rect>", "bogus");
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" zoomAndPan=\"x\"/>", "<svg>",
            "zoomAndPan");
    refused(L2("<path d=\"M0 0 L4 0 L4 4z\" points=\"0 0\"/>"), "<path>", "points");
    /* Case: CSS names and keywords in any case; the results equal the
     * lower-case forms' (white is #ffffff: 1 1 1 in linear light). */
    expect(SVG_OPEN "<path style=\"FILL: WHITE; Fill-Rule: EvenOdd\" d=\"M0 0 L1 0 L0 1z\"/>"
                    "</svg>",
           "fill 1 1 1 evenodd; M 0 0 L 1 0 L 0 1 Z");
    expect(SVG_OPEN "<path fill=\"NONE\" d=\"M0 0 L1 0 L0 1z\"/>"
                    "<path display=\"None\" d=\"M0 0 L1 0 L0 1z\"/>"
                    "<path style=\"DISPLAY:NONE\" d=\"M0 0 L1 0 L0 1z\"/></svg>",
           "");
    expect(SVG_OPEN "<path fill=\"RGB(100%, 100%, 100%)\" stroke=\"None\" d=\"M0 0 L1 0 L0 1z\"/>"
                    "</svg>",
           "fill 1 1 1 nonzero; M 0 0 L 1 0 L 0 1 Z");
    /* What is accepted without effect on a filled shape: ids, classes (no
     * style sheet is read), stroke properties without a stroke, attributes
     * of other namespaces. */
    expect(SVG_OPEN "<g id=\"a\" class=\"b\" xmlns:x=\"urn:x\" x:y=\"1\" xml:space=\"preserve\">"
                    "<path stroke-width=\"3\" style=\"stroke-linejoin: round;\""
                    " d=\"M0 0 L1 0 L0 1z\"/>"
                    "</g></svg>",
           BLACK " M 0 0 L 1 0 L 0 1 Z");
    /* Through the pattern: parse and build refuse, naming the property. */
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/blend.svg", dir);
    write_svg(path, L2(R1 "mix-blend-mode=\"screen\"/>"));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    svg_refused(spec, "mix-blend-mode");
    svg_refused(spec, "line 2");
    assert_int_equal(unlink(path), 0);
}

/* What editors and icon sets write beside the geometry and a browser draws
 * nothing of (measured on public icon sets: patterns/README.md, "Public
 * files"): accessibility and data attributes (role="img" on the root of
 * every simple-icons file, aria-*, data-*, tabindex, focusable, lang), the
 * properties of text, of filter primitives, of interaction, and markers,
 * blending, isolation, vector effects and rendering hints at values that
 * draw nothing (Inkscape's style attribute), names no CSS knows
 * (block-progression, filter-blend-mode: CSS 2.1, 4.2, ignores them), and
 * width and height on a path.  The known answer is the
 * document's geometry without them, written by hand: white is 1 1 1 in
 * linear light, the triangle's points as given.  Any value that would draw
 * something (a marker, a blend, a non-scaling stroke, crisp edges) is
 * refused naming the element and its line, and so is a name the reader
 * does not know. */
#define TRI "d=\"M0 0 L1 0 L0 1z\" fill=\"white\""
#define WHITE_TRI "fill 1 1 1 nonzero; M 0 0 L 1 0 L 0 1 Z"
static void test_noop_properties(void **state)
{
    (void)state;
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" role=\"img\" aria-label=\"x\" "
           "focusable=\"false\" tabindex=\"-1\" lang=\"en\" data-name=\"Layer 1\">"
           "<path " TRI " aria-hidden=\"true\" data-x=\"1\"/></svg>",
           WHITE_TRI);
    expect(SVG_OPEN "<path " TRI " style=\"marker:none;marker-start:none;isolation:auto;"
                    "mix-blend-mode:normal;vector-effect:none;shape-rendering:auto;"
                    "color-rendering:auto;image-rendering:auto;"
                    "color-interpolation-filters:linearRGB;flood-color:red;"
                    "flood-opacity:1;lighting-color:blue;solid-color:#000000;"
                    "solid-opacity:1;pointer-events:none;cursor:pointer;line-height:1.25;"
                    "letter-spacing:0px;word-spacing:0px;text-anchor:middle;"
                    "text-align:center;writing-mode:lr-tb;direction:ltr;"
                    "baseline-shift:baseline;white-space:normal;"
                    "font-variant-ligatures:normal;font-feature-settings:normal;"
                    "-inkscape-font-specification:Sans;text-decoration-line:none;"
                    "block-progression:tb;filter-blend-mode:normal;"
                    "filter-gaussianBlur-deviation:0\"/></svg>",
           WHITE_TRI);
    /* width and height on a path, where they are no geometry (SVG 2 gives
     * them to rect, svg, image, foreignObject and use): breeze's
     * application-x-root.svg writes 100% there */
    expect(SVG_OPEN "<path " TRI " width=\"100%\" height=\"100%\"/></svg>", WHITE_TRI);
    refused(L2("<g width=\"10\"><path " TRI "/></g>"), "line 2: <g>", "width");
    /* r on an ellipse (SVG 2 gives r to circle only): rx and ry auto, so
     * radius 0, nothing drawn; and SVG 1.2 drafts' flowRoot, no SVG
     * element.  Chromium and resvg draw neither (a white ellipse of r = 8
     * and white flowed text over black, 20 x 20: every pixel black) */
    expect(SVG_OPEN "<path " TRI "/><ellipse cx=\"5\" cy=\"5\" r=\"3\" fill=\"white\"/>"
                    "<flowRoot><flowRegion><rect width=\"9\" height=\"9\"/></flowRegion>"
                    "<flowPara fill=\"white\">M</flowPara></flowRoot></svg>",
           WHITE_TRI);
    refused(L2("<circle cx=\"5\" cy=\"5\" r=\"3\" rx=\"2\"/>"), "line 2: <circle>", "rx");
    /* as presentation attributes, and isolate: an isolated group of
     * normal blending and opacity 1 is its content laid one by one */
    expect(SVG_OPEN "<g isolation=\"isolate\" marker-end=\"none\" "
                    "shape-rendering=\"geometricPrecision\" color-rendering=\"optimizeQuality\">"
                    "<path " TRI " marker-mid=\"inherit\" text-anchor=\"end\"/></g></svg>",
           WHITE_TRI);
    /* in a sheet, and on a clipPath's child */
    expect(SVG_OPEN "<style>path { marker: none; line-height: 2 }</style>"
                    "<path " TRI "/></svg>",
           WHITE_TRI);
    refused(L2("<path " TRI " style=\"marker: url(#m)\"/>"), "line 2: <path>",
            "markers are not drawn");
    refused(L2("<g style=\"marker-start: url(#m)\"><path " TRI "/></g>"), "line 2: <g>",
            "marker-start");
    refused(L2("<path " TRI " vector-effect=\"non-scaling-stroke\"/>"), "line 2: <path>",
            "vector-effect");
    refused(L2("<path " TRI " style=\"mix-blend-mode: multiply\"/>"), "line 2: <path>",
            "blending is not drawn");
    refused(L2("<path " TRI " style=\"shape-rendering: crispEdges\"/>"), "line 2: <path>",
            "shape-rendering");
    refused(L2("<path " TRI " shape-rendering=\"optimizeSpeed\"/>"), "line 2: <path>",
            "shape-rendering");
    refused(L2("<path " TRI " isolation=\"bogus\"/>"), "line 2: <path>", "isolation");
    refused(L2("<style>\n.a { marker-end: url(#m) }</style><path class=\"a\" " TRI "/>"),
            "<path>", "marker-end=\"url(#m)\" is not supported (markers are not drawn) "
                      "(style sheet line 3)");
    /* not every name: `font` sets font-size (em lengths), data- and aria-
     * need a name after them, and names stay case-sensitive */
    refused(L2("<path " TRI " style=\"font: 12px serif\"/>"), "line 2: <path>", "font");
    refused(L2("<path " TRI " data-=\"1\"/>"), "line 2: <path>", "data-");
    refused(L2("<path " TRI " aria-=\"1\"/>"), "line 2: <path>", "aria-");
    refused(L2("<path " TRI " ROLE=\"img\"/>"), "line 2: <path>", "ROLE");
}

/* Filters, masks, markers and patterns are never drawn where they stand
 * (SVG 2, Filter Effects 1: "never rendered directly"): one defined and not
 * referenced, in <defs> or not, leaves the picture as it is (the answer
 * written by hand, as above).  A reference to one is refused where it is
 * made, and so are text and images, each naming the element and its line:
 * the reader never draws them approximately. */
static void test_never_rendered(void **state)
{
    (void)state;
    expect(SVG_OPEN "<filter id=\"f\"><feGaussianBlur stdDeviation=\"2\"/></filter>"
                    "<mask id=\"m\"><rect width=\"9\" height=\"9\" fill=\"white\"/></mask>"
                    "<marker id=\"k\"><circle r=\"3\"/></marker>"
                    "<pattern id=\"p\" width=\"2\" height=\"2\"><rect width=\"1\" "
                    "height=\"1\"/></pattern>"
                    "<defs><filter id=\"g\"><feOffset dx=\"1\"/></filter></defs>"
                    "<path " TRI "/></svg>",
           WHITE_TRI);
    refused(L2("<filter id=\"f\"><feOffset dx=\"1\"/></filter>\n<path " TRI
               " filter=\"url(#f)\"/>"),
            "line 3: <path>", "filters are not supported");
    refused(L2("<mask id=\"m\"/>\n<g style=\"mask: url(#m)\"><path " TRI "/></g>"),
            "line 3: <g>", "masks are not supported");
    refused(L2("<marker id=\"k\"/>\n<path " TRI " marker-end=\"url(#k)\"/>"),
            "line 3: <path>", "marker-end");
    refused(L2("<pattern id=\"p\"/>\n<path d=\"M0 0 L1 0 L0 1z\" fill=\"url(#p)\"/>"),
            "line 3: <path>",
            "patterns are not supported");
    refused(L2("\n<text x=\"1\" y=\"9\">A</text>"), "line 3: <text>", "text is not supported");
    refused(L2("\n<image href=\"a.png\" width=\"9\" height=\"9\"/>"), "line 3: <image>",
            "images are not supported");
}

/* scripts/svg-corpus.sh over a folder made for it: its table's counts are
 * known by construction.  Six files: two taken (one with a comma in its
 * name, which the spec must escape), two refused for the same reason
 * (<text>, on lines 2 and 3: one reason, counted twice), one for an
 * attribute and one for an element the reader does not know (the element
 * kept in the reason); a symbolic link to a taken file is not followed; the
 * list --list writes gives the same table again (--from).  Then the
 * failures, with a stand-in for the command: one that ends by SIGSEGV
 * (failed, exit 139) and one that sleeps past --timeout (hung), the script
 * exiting 1. */
static void corpus_run(const char *args, char *out, size_t cap, int *status)
{
    char cmd[9200];
    snprintf(cmd, sizeof cmd, "sh scripts/svg-corpus.sh %s 2>&1", args);
    FILE *f = popen(cmd, "r");
    assert_non_null(f);
    size_t n = fread(out, 1, cap - 1, f);
    out[n] = '\0';
    int st = pclose(f);
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void test_corpus_script(void **state)
{
    (void)state;
    const char *aabench = getenv("AABENCH");
    if (!aabench)
        fail_msg("AABENCH is not set (scripts/run-tests.sh sets it)");
    char cdir[4200], path[4400], args[9000], out[8192];
    snprintf(cdir, sizeof cdir, "%s/corpus", dir);
    assert_int_equal(mkdir(cdir, 0755), 0);
    static const struct {
        const char *name, *doc;
    } files[] = {{"a.svg", L2("<rect width=\"4\" height=\"4\" fill=\"white\"/>")},
                 {"b,c.svg", L2("<circle cx=\"8\" cy=\"8\" r=\"3\"/>")},
                 {"t1.svg", L2("<text>A</text>")},
                 {"t2.svg", L2("\n<text>B</text>")},
                 {"u.svg", L2("<rect width=\"4\" height=\"4\" FILL=\"red\"/>")},
                 {"v.svg", L2("<a><rect width=\"4\" height=\"4\"/></a>")}};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", cdir, files[k].name);
        write_svg(path, files[k].doc);
    }
    snprintf(path, sizeof path, "%s/link.svg", cdir);
    assert_int_equal(symlink("a.svg", path), 0);
    int status;
    char list[4400], again[8192];
    snprintf(list, sizeof list, "%s/list.tsv", dir);
    snprintf(args, sizeof args, "--aabench %s --jobs 2 --list %s %s", aabench, list, cdir);
    corpus_run(args, out, sizeof out, &status);
    printf("%s", out);
    assert_int_equal(status, 0);
    assert_non_null(strstr(out, "6 files: 2 taken (33.3%), 4 refused, 0 failed, 0 hung\n"));
    assert_non_null(strstr(out, "      2  text is not supported"));
    assert_non_null(strstr(out, "t1.svg (line 2: <text>)"));
    assert_non_null(strstr(out, "      1  the attribute FILL is not supported"));
    assert_non_null(strstr(out, "u.svg (line 2: <rect>)"));
    assert_non_null(strstr(out, "      1  <a>: this element is not supported"));
    /* the most first */
    assert_true(strstr(out, "text is not") < strstr(out, "FILL"));
    snprintf(args, sizeof args, "--from %s", list);
    corpus_run(args, again, sizeof again, &status);
    assert_int_equal(status, 0);
    assert_string_equal(again, out);
    /* every K-th */
    snprintf(args, sizeof args, "--aabench %s --every 2 %s", aabench, cdir);
    corpus_run(args, out, sizeof out, &status);
    assert_int_equal(status, 0);
    assert_non_null(strstr(out, "3 files: "));
    assert_int_equal(unlink(list), 0);
    /* a crash and a hang, through stand-ins */
    char crash[4400], hang[4400];
    snprintf(crash, sizeof crash, "%s/crash.sh", dir);
    snprintf(hang, sizeof hang, "%s/hang.sh", dir);
    write_svg(crash, "#!/bin/sh\nkill -SEGV $$\n");
    write_svg(hang, "#!/bin/sh\nexec sleep 30\n");
    assert_int_equal(chmod(crash, 0755), 0);
    assert_int_equal(chmod(hang, 0755), 0);
    snprintf(path, sizeof path, "%s/a.svg", cdir);
    snprintf(args, sizeof args, "--aabench %s %s", crash, path);
    corpus_run(args, out, sizeof out, &status);
    printf("%s", out);
    assert_int_equal(status, 1);
    assert_non_null(strstr(out, "1 files: 0 taken (0.0%), 0 refused, 1 failed, 0 hung\n"));
    assert_non_null(strstr(out, "failed (exit 139): "));
    snprintf(args, sizeof args, "--aabench %s --timeout 1 %s", hang, path);
    corpus_run(args, out, sizeof out, &status);
    printf("%s", out);
    assert_int_equal(status, 1);
    assert_non_null(strstr(out, "1 files: 0 taken (0.0%), 0 refused, 0 failed, 1 hung\n"));
    /* bad usage */
    corpus_run("--every 0 .", out, sizeof out, &status);
    assert_int_equal(status, 2);
    corpus_run("/nonexistent-dir", out, sizeof out, &status);
    assert_int_equal(status, 2);
}

/* The shipped scenes read (those with cubics once the scene holds them). */
static void test_shipped(void **state)
{
    (void)state;
    static const char *files[] = {"shapes.svg", "rules.svg", "curves.svg", "logo.svg",
                                  "mono.svg",   "arcs.svg",  "strokes.svg"};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", aa_svg_dir(), files[k]);
        support_text t = {.n = 0};
        if (aa_svg_read_file(path, 64, 64, &sink, &t, NULL) != AA_OK)
            fail_msg("%s: %s", path, aa_last_error());
        assert_true(t.n > 0);
    }
}

SUPPORT_MAIN(setup, teardown,
             cmocka_unit_test(test_commands_absolute),
             cmocka_unit_test(test_commands_relative),
             cmocka_unit_test(test_implicit_repeats),
             cmocka_unit_test(test_reflections),
             cmocka_unit_test(test_numbers),
             cmocka_unit_test(test_transforms),
             cmocka_unit_test(test_shapes),
             cmocka_unit_test(test_basic_arcs),
             cmocka_unit_test(test_arc_command),
             cmocka_unit_test(test_stroke_props),
             cmocka_unit_test(test_colours),
             cmocka_unit_test(test_viewbox),
             cmocka_unit_test(test_refusals),
             cmocka_unit_test(test_entities),
             cmocka_unit_test(test_deep_and_huge),
             cmocka_unit_test(test_rect_reference),
             cmocka_unit_test(test_path_length),
             cmocka_unit_test(test_painters_order),
             cmocka_unit_test(test_layers),
             cmocka_unit_test(test_cache_key),
             cmocka_unit_test(test_text_values),
             cmocka_unit_test(test_command), cmocka_unit_test(test_scale),
             cmocka_unit_test(test_export_round_trip),
             cmocka_unit_test(test_export_strokes),
             cmocka_unit_test(test_cubic_scene),
             cmocka_unit_test(test_unknown_properties),
             cmocka_unit_test(test_noop_properties),
             cmocka_unit_test(test_never_rendered),
             cmocka_unit_test(test_corpus_script),
             cmocka_unit_test(test_shipped))
