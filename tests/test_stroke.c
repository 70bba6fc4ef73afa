/*
 * test_stroke.c: the stroke outline (harness/core/stroke.c,
 * aa_stroke_outline) against answers derived here, independently of it.
 *
 *  - areas of strokes of lines: the outline filled (non-zero) into a scene
 *    and its box reference (aa_truth_render) on 64x64 pixels, whose sum is
 *    the area of the union in pixels, against the area from the geometry:
 *    a butt line w L, a square-capped one w (L + w), a right-angle corner
 *    (miter: w (L1 + L2); bevel: that less the corner triangle h^2/2; a
 *    limit under sqrt 2 turns the miter into the bevel), a 120-degree turn
 *    (the polygon of the offset lines' meeting points, by the shoelace
 *    formula here), a closed square ((s + w)^2 - (s - w)^2 with miters,
 *    less four triangles with bevels), and dashes on a line (their lengths
 *    counted by hand, also with a negative offset and an odd list; on a
 *    closed square, a dash through its start joined there);
 *  - areas of strokes with arcs, the same way: round caps, circles
 *    and half circles wider and narrower than the stroke, a round join,
 *    dashes on a circle (closed forms above test_arc_areas);
 *  - point membership for round joins and round caps: then the stroke is
 *    exactly the points within w/2 of the path (each point's nearest point
 *    on the path is inside a segment, on whose normal it lies, or a vertex
 *    or an end, in whose outward cone it lies: the sector of the join or
 *    the half disk of the cap).  At random points (seeded) the winding
 *    number of the outline, by ray crossings computed here (lines, and arcs
 *    cut where y turns), is non-zero exactly when the distance to the path,
 *    computed here for segments and circular arcs, is at most w/2 (points
 *    within 1e-9 of that boundary skipped): a fixed path with a tight arc
 *    (radius < w/2, the normal crossing the centre), arcs of both turning
 *    senses and of more than half a turn, and random paths of lines and
 *    arcs, open and closed; dashed paths against the distance to their
 *    dashes (laid out here by arc length), and against the shape of those
 *    dashes with every join and cap;
 *  - the outline filled into a scene (aa_path_fill, also through a shear
 *    that makes its circles ellipses): the scene's point query agrees with
 *    the stroke shape at the point's preimage;
 *  - a circle closed by a line of rounding's length: no join of its own;
 *  - orientation: every contour of every outline here has positive signed
 *    area (Simpson's rule on x dy - y dx, 64 steps an arc); every winding
 *    number is >= 0;
 *  - subpaths of no length (a disk, an axis-aligned square, nothing), a
 *    lone move (nothing), and what is refused: a Bezier arc nearly with a cusp, bad styles;
 *    `out` is left as it was (elliptical arcs that are not circles:
 *    test_ellipse_stroke.c).
 */
#include "path.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* ---- reading an outline ---- */

static void arc_at(const double *a, double t, double *x, double *y)
{
    *x = a[0] + a[2] * cos(t) + a[4] * sin(t);
    *y = a[1] + a[3] * cos(t) + a[5] * sin(t);
}

/* Signed area of each contour by (1/2) integral of x dy - y dx: exact for
 * lines, Simpson's rule (64 steps) on arcs, about the contour's start.
 * Fails the test unless every one is positive; returns how many. */
static int check_orientation(const aa_path *out)
{
    int contours = 0;
    double sx = 0, sy = 0, px = 0, py = 0, a = 0;
    for (size_t k = 0; k < out->n; k++) {
        const aa_path_seg *g = &out->seg[k];
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = g->p[0], sy = py = g->p[1], a = 0;
            break;
        case AA_PATH_LINE:
            a += (px - sx) * (g->p[1] - sy) - (py - sy) * (g->p[0] - sx);
            px = g->p[0], py = g->p[1];
            break;
        case AA_PATH_ARC: {
            const double *c = g->p;
            int n = 64;
            double hstep = (c[7] - c[6]) / n, sum = 0;
            for (int i = 0; i <= n; i++) {
                double t = c[6] + i * hstep, x, y;
                arc_at(c, t, &x, &y);
                double dx = -c[2] * sin(t) + c[4] * cos(t), dy = -c[3] * sin(t) + c[5] * cos(t);
                double f = (x - sx) * dy - (y - sy) * dx;
                sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
            }
            a += sum * hstep / 3;
            px = g->p[8], py = g->p[9];
            break;
        }
        case AA_PATH_CLOSE:
            contours++;
            if (!(a > 0))
                fail_msg("contour %d has signed area %g", contours, 0.5 * a);
            break;
        default:
            fail_msg("outline has a segment of kind %d", (int)g->op);
        }
    }
    return contours;
}

/* Signed crossings of the ray from (qx, qy) towards +x with a line: +1 up,
 * -1 down, a vertex counted on the side y0 <= y < y1. */
static int line_cross(double qx, double qy, double x0, double y0, double x1, double y1)
{
    if (y0 <= qy && qy < y1) {
        double x = x0 + (qy - y0) / (y1 - y0) * (x1 - x0);
        return x > qx ? 1 : 0;
    }
    if (y1 <= qy && qy < y0) {
        double x = x0 + (qy - y0) / (y1 - y0) * (x1 - x0);
        return x > qx ? -1 : 0;
    }
    return 0;
}

/* The same for an arc, cut where y(t) = cy + uy cos t + vy sin t turns
 * (t = phi + k pi, phi = atan2(vy, uy)), each y-monotone part's crossing
 * found by bisection. */
static int arc_cross(double qx, double qy, const double *c)
{
    double lo = fmin(c[6], c[7]), hi = fmax(c[6], c[7]);
    double cuts[8];
    int nc = 0;
    cuts[nc++] = lo;
    double phi = atan2(c[5], c[3]);
    double k0 = ceil((lo - phi) / M_PI);
    for (double k = k0; phi + k * M_PI < hi && nc < 7; k++)
        if (phi + k * M_PI > lo)
            cuts[nc++] = phi + k * M_PI;
    cuts[nc++] = hi;
    int w = 0, dir = c[7] > c[6] ? 1 : -1;
    for (int i = 0; i + 1 < nc; i++) {
        double a = cuts[i], b = cuts[i + 1], xa, ya, xb, yb;
        arc_at(c, a, &xa, &ya);
        arc_at(c, b, &xb, &yb);
        /* in travel order: from a to b if dir > 0 */
        double y0 = dir > 0 ? ya : yb, y1 = dir > 0 ? yb : ya;
        int s;
        if (y0 <= qy && qy < y1)
            s = 1;
        else if (y1 <= qy && qy < y0)
            s = -1;
        else
            continue;
        /* y monotone on [a, b]: bisect for y = qy */
        double ta = a, tb = b;
        int up = yb > ya;
        for (int it = 0; it < 200 && ta < tb; it++) {
            double tm = 0.5 * (ta + tb), xm, ym;
            arc_at(c, tm, &xm, &ym);
            if ((ym < qy) == up)
                ta = tm;
            else
                tb = tm;
            if (tm == ta && tm == tb)
                break;
        }
        double x, y;
        arc_at(c, 0.5 * (ta + tb), &x, &y);
        if (x > qx)
            w += s;
    }
    return w;
}

static int winding(const aa_path *out, double qx, double qy)
{
    int w = 0;
    double sx = 0, sy = 0, px = 0, py = 0;
    for (size_t k = 0; k < out->n; k++) {
        const aa_path_seg *g = &out->seg[k];
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = g->p[0], sy = py = g->p[1];
            break;
        case AA_PATH_LINE:
            w += line_cross(qx, qy, px, py, g->p[0], g->p[1]);
            px = g->p[0], py = g->p[1];
            break;
        case AA_PATH_ARC:
            w += arc_cross(qx, qy, g->p);
            px = g->p[8], py = g->p[9];
            break;
        case AA_PATH_CLOSE:
            w += line_cross(qx, qy, px, py, sx, sy);
            px = sx, py = sy;
            break;
        default:
            break;
        }
    }
    return w;
}

/* ---- distances to a path of lines and circular arcs ---- */

static double dist_segment(double qx, double qy, double x0, double y0, double x1, double y1)
{
    double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((qx - x0) * dx + (qy - y0) * dy) / l2 : 0;
    t = fmin(1, fmax(0, t));
    return hypot(qx - x0 - t * dx, qy - y0 - t * dy);
}

/* A circle's arc c[0..7] (|u| = |v| = r, u . v = 0): the radial distance
 * where the point's angle is within the arc's, else the nearer end. */
static double dist_arc(double qx, double qy, const double *c)
{
    double r2 = c[2] * c[2] + c[3] * c[3], r = sqrt(r2);
    double rx = qx - c[0], ry = qy - c[1];
    double a = (rx * c[2] + ry * c[3]) / r2, b = (rx * c[4] + ry * c[5]) / r2;
    double t = atan2(b, a), lo = fmin(c[6], c[7]), hi = fmax(c[6], c[7]);
    double k = ceil((lo - t) / (2 * M_PI));
    if (t + k * 2 * M_PI <= hi)
        return fabs(hypot(rx, ry) - r);
    double x0, y0, x1, y1;
    arc_at(c, c[6], &x0, &y0);
    arc_at(c, c[7], &x1, &y1);
    return fmin(hypot(qx - x0, qy - y0), hypot(qx - x1, qy - y1));
}

/* Distance to every drawn segment of a path (the closing lines too). */
static double dist_path(const aa_path *p, double qx, double qy)
{
    double d = INFINITY, sx = 0, sy = 0, px = 0, py = 0;
    for (size_t k = 0; k < p->n; k++) {
        const aa_path_seg *g = &p->seg[k];
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = g->p[0], sy = py = g->p[1];
            break;
        case AA_PATH_LINE:
            d = fmin(d, dist_segment(qx, qy, px, py, g->p[0], g->p[1]));
            px = g->p[0], py = g->p[1];
            break;
        case AA_PATH_ARC:
            d = fmin(d, dist_arc(qx, qy, g->p));
            px = g->p[8], py = g->p[9];
            break;
        case AA_PATH_CLOSE:
            d = fmin(d, dist_segment(qx, qy, px, py, sx, sy));
            px = sx, py = sy;
            break;
        default:
            break;
        }
    }
    return d;
}

/* ---- random numbers ---- */

static uint64_t rng = 0x2545f4914f6cdd1du;
static double uniform(double a, double b)
{
    return support_uniform(&rng, a, b);
}

/* ---- building ---- */

static void must(int st)
{
    if (st)
        fail_msg("%s", aa_last_error());
}

/* A circular arc from the pen: centre (cx, cy), radius r, angles t0 to t1,
 * counter-clockwise parametrisation (v = u turned a quarter) or clockwise. */
static void circle_to(aa_path *p, double cx, double cy, double r, double t0, double t1, int ccw)
{
    double s = ccw ? 1 : -1;
    double x = cx + r * cos(t1), y = cy + s * r * sin(t1);
    must(aa_path_arc_to(p, cx, cy, r, 0, 0, s * r, t0, t1, x, y));
}

static void circle_start(aa_path *p, double cx, double cy, double r, double t0, int ccw)
{
    double s = ccw ? 1 : -1;
    must(aa_path_move_to(p, cx + r * cos(t0), cy + s * r * sin(t0)));
}

/* The stroke's outline, checked for its orientation, filled into a scene
 * (pattern units, inside the unit square): its area in pattern units
 * (support_fill_area). */
static double stroke_area(const aa_path *in, const aa_stroke_style *st)
{
    aa_path out = {0};
    must(aa_stroke_outline(in, st, &out));
    check_orientation(&out);
    double area = support_fill_area(&out);
    aa_path_free(&out);
    return area;
}

static void expect_area(const char *what, const aa_path *in, const aa_stroke_style *st,
                        double want)
{
    double got = stroke_area(in, st);
    print_message("%-28s area %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) < 1e-12))
        fail_msg("%s: area %.17g, want %.17g", what, got, want);
}

/* The polygon's area, unsigned. */
static double shoelace(const double *xy, int n)
{
    return fabs(support_shoelace(xy, n));
}

/* ---- areas of strokes of lines ---- */

/* A run's bodies, joins and caps are one contour (stroke.c, "runs"), a
 * closed subpath's last join a contour of its own: the count of contours
 * is that, and the area the union's.  Known answers: three collinear lines
 * 0.6 long stroked 0.1 wide (h = 0.05), the rectangle 0.6 x 0.1 with butt
 * caps, 0.7 x 0.1 with square caps, and with round caps the rectangle and
 * a disk of radius h; a right-angle corner of legs 0.4 and 0.3 with a miter
 * join, the outer rectangle's area less the inner one's:
 * (0.4 + h)(0.3 + h) - (0.4 - h)(0.3 - h) = 1.4 h. */
static int stroke_contours(const aa_path *in, const aa_stroke_style *st)
{
    aa_path out = {0};
    must(aa_stroke_outline(in, st, &out));
    int n = check_orientation(&out);
    aa_path_free(&out);
    return n;
}

static void test_runs_one_contour(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.1;
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.1, 0.5));
    must(aa_path_line_to(&p, 0.3, 0.5));
    must(aa_path_line_to(&p, 0.45, 0.5));
    must(aa_path_line_to(&p, 0.7, 0.5));
    assert_int_equal(stroke_contours(&p, &st), 1);
    expect_area("collinear run", &p, &st, 0.06);
    st.cap = AA_CAP_SQUARE;
    assert_int_equal(stroke_contours(&p, &st), 1);
    expect_area("collinear run, square caps", &p, &st, 0.07);
    st.cap = AA_CAP_ROUND;
    assert_int_equal(stroke_contours(&p, &st), 1);
    expect_area("collinear run, round caps", &p, &st, 0.06 + M_PI * 0.05 * 0.05);
    st.cap = AA_CAP_BUTT;
    aa_path_free(&p);
    aa_path_init(&p);
    must(aa_path_move_to(&p, 0.2, 0.2));
    must(aa_path_line_to(&p, 0.6, 0.2));
    must(aa_path_line_to(&p, 0.6, 0.5));
    assert_int_equal(stroke_contours(&p, &st), 1);
    expect_area("miter corner run", &p, &st, 1.4 * 0.05);
    aa_path_free(&p);
    /* a zigzag of lines and a circular arc: one contour for each join,
     * turning either way, and each cap */
    const aa_line_join joins[4] = {AA_JOIN_MITER, AA_JOIN_ROUND, AA_JOIN_BEVEL, AA_JOIN_ARCS};
    for (int j = 0; j < 4; j++) {
        aa_path_init(&p);
        must(aa_path_move_to(&p, 0.1, 0.3));
        must(aa_path_line_to(&p, 0.25, 0.6));
        must(aa_path_line_to(&p, 0.4, 0.3));
        circle_to(&p, 0.5, 0.3, 0.1, M_PI, 2 * M_PI, 0);
        must(aa_path_line_to(&p, 0.75, 0.6));
        must(aa_path_line_to(&p, 0.9, 0.35));
        st.join = joins[j];
        st.cap = AA_CAP_BUTT;
        assert_int_equal(stroke_contours(&p, &st), 1);
        st.cap = AA_CAP_ROUND;
        assert_int_equal(stroke_contours(&p, &st), 1);
        st.cap = AA_CAP_SQUARE;
        assert_int_equal(stroke_contours(&p, &st), 1);
        aa_path_free(&p);
    }
    /* closed: the run and its closing join */
    aa_path_init(&p);
    must(aa_path_move_to(&p, 0.25, 0.25));
    must(aa_path_line_to(&p, 0.75, 0.25));
    must(aa_path_line_to(&p, 0.75, 0.75));
    must(aa_path_line_to(&p, 0.25, 0.75));
    must(aa_path_close(&p));
    st.join = AA_JOIN_MITER;
    assert_int_equal(stroke_contours(&p, &st), 2);
    aa_path_free(&p);
}


static void test_line_caps(void **state)
{
    (void)state;
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.2, 0.3));
    must(aa_path_line_to(&p, 0.7, 0.6));
    double L = hypot(0.5, 0.3), w = 0.08;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    expect_area("butt line", &p, &st, w * L);
    st.cap = AA_CAP_SQUARE;
    expect_area("square-capped line", &p, &st, w * (L + w));
    aa_path_free(&p);
}

/* A right angle: (0.2, 0.2) -> (0.7, 0.2) -> (0.7, 0.7), w = 0.1, butt.
 * The two rectangles overlap in the inner (w/2)^2 square at the corner and
 * miss the outer one, which the miter (ratio sqrt 2) fills: w (L1 + L2).
 * The bevel fills half of it: less h^2/2. */
static void test_corner(void **state)
{
    (void)state;
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.2, 0.2));
    must(aa_path_line_to(&p, 0.7, 0.2));
    must(aa_path_line_to(&p, 0.7, 0.7));
    double w = 0.1, h = 0.05;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    expect_area("miter corner", &p, &st, w * 1.0);
    st.join = AA_JOIN_BEVEL;
    expect_area("bevel corner", &p, &st, w * 1.0 - 0.5 * h * h);
    st.join = AA_JOIN_MITER;
    st.miterlimit = 1.41; /* under sqrt 2 */
    expect_area("miter over its limit", &p, &st, w * 1.0 - 0.5 * h * h);
    st.miterlimit = 1.4143; /* over sqrt 2 */
    expect_area("miter under its limit", &p, &st, w * 1.0);
    aa_path_free(&p);
}

/* A turn of 120 degrees (segments meeting at 60): the stroke is the
 * hexagon of the start's two offset points, the outer offset lines' meeting
 * point, the end's two offset points and the inner lines' meeting point
 * (the segments are long enough for the inner corner).  Miter ratio
 * 1/sin(30 degrees) = 2: a limit of 2.01 keeps it, 1.99 bevels it (less
 * the triangle of the outer meeting point and the two offset points at the
 * vertex). */
static void test_sharp_turn(void **state)
{
    (void)state;
    const double a[2] = {0.15, 0.3}, b[2] = {0.75, 0.3};
    const double c[2] = {0.75 - 0.5 * cos(M_PI / 3), 0.3 + 0.5 * sin(M_PI / 3)};
    double w = 0.06, h = 0.03;
    double d1[2] = {1, 0}, d2[2] = {c[0] - b[0], c[1] - b[1]};
    double l2 = hypot(d2[0], d2[1]);
    d2[0] /= l2, d2[1] /= l2;
    /* left normals (-dy, dx); the turn is to the left, the outer side right */
    double n1[2] = {-d1[1], d1[0]}, n2[2] = {-d2[1], d2[0]};
    /* o: outer (right) offset points, i: inner (left) */
    double oa[2] = {a[0] - h * n1[0], a[1] - h * n1[1]};
    double ob1[2] = {b[0] - h * n1[0], b[1] - h * n1[1]};
    double ob2[2] = {b[0] - h * n2[0], b[1] - h * n2[1]};
    double oc[2] = {c[0] - h * n2[0], c[1] - h * n2[1]};
    double ia[2] = {a[0] + h * n1[0], a[1] + h * n1[1]};
    double ic[2] = {c[0] + h * n2[0], c[1] + h * n2[1]};
    double m[2], in[2];
    support_line_meet(oa, d1, oc, d2, m);
    support_line_meet(ia, d1, ic, d2, in);
    const double hex[12] = {oa[0], oa[1], m[0], m[1], oc[0], oc[1],
                            ic[0], ic[1], in[0], in[1], ia[0], ia[1]};
    double miter = shoelace(hex, 6);
    const double tri[6] = {ob1[0], ob1[1], m[0], m[1], ob2[0], ob2[1]};
    double bevel = miter - shoelace(tri, 3);
    aa_path p = {0};
    must(aa_path_move_to(&p, a[0], a[1]));
    must(aa_path_line_to(&p, b[0], b[1]));
    must(aa_path_line_to(&p, c[0], c[1]));
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    st.miterlimit = 2.01;
    expect_area("120-degree miter", &p, &st, miter);
    st.miterlimit = 1.99;
    expect_area("120-degree miter to bevel", &p, &st, bevel);
    st.join = AA_JOIN_BEVEL;
    expect_area("120-degree bevel", &p, &st, bevel);
    aa_path_free(&p);
}

/* A closed square of side 0.5 at (0.25, 0.25), w = 0.1: with miters the
 * ring between squares of sides 0.6 and 0.4; with bevels less a triangle
 * (h^2/2) at each corner; the same starting mid-side (the closing join). */
static void test_closed_square(void **state)
{
    (void)state;
    double w = 0.1, h = 0.05;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    for (int mid = 0; mid < 2; mid++) {
        aa_path p = {0};
        if (mid) {
            must(aa_path_move_to(&p, 0.5, 0.25));
            must(aa_path_line_to(&p, 0.75, 0.25));
        } else {
            must(aa_path_move_to(&p, 0.25, 0.25));
            must(aa_path_line_to(&p, 0.75, 0.25));
        }
        must(aa_path_line_to(&p, 0.75, 0.75));
        must(aa_path_line_to(&p, 0.25, 0.75));
        if (mid)
            must(aa_path_line_to(&p, 0.25, 0.25));
        must(aa_path_close(&p));
        st.join = AA_JOIN_MITER;
        expect_area("closed square, miter", &p, &st, 0.36 - 0.16);
        st.join = AA_JOIN_BEVEL;
        expect_area("closed square, bevel", &p, &st, 0.36 - 0.16 - 4 * 0.5 * h * h);
        aa_path_free(&p);
    }
}

/* Dashes on a line of length 0.6 (from (0.2, 0.5) along x), w = 0.02:
 *  - [0.1, 0.05] offset 0.02: dashes [0, 0.08], [0.13, 0.23], [0.28, 0.38],
 *    [0.43, 0.53], [0.58, 0.6]: 0.4 long, 5 dashes;
 *  - offset -0.03, the pattern 0.12 in, in the gap with 0.03 left:
 *    [0.03, 0.13], [0.18, 0.28], [0.33, 0.43], [0.48, 0.58]: 0.4, 4 dashes;
 *  - [0.1] (repeated: [0.1, 0.1]): [0, 0.1], [0.2, 0.3], [0.4, 0.5]: 0.3, 3.
 * Butt: w times the length; square caps add w h at each end (the gaps are
 * wider than w, so the caps overlap nothing). */
static void test_dashes_line(void **state)
{
    (void)state;
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.2, 0.5));
    must(aa_path_line_to(&p, 0.8, 0.5));
    double w = 0.02, h = 0.01;
    const double d2[2] = {0.1, 0.05}, d1[1] = {0.1};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    st.dash = d2;
    st.ndash = 2;
    st.dashoffset = 0.02;
    expect_area("dashes, butt", &p, &st, w * 0.4);
    st.cap = AA_CAP_SQUARE;
    expect_area("dashes, square", &p, &st, w * 0.4 + 5 * 2 * w * h);
    st.dashoffset = -0.03;
    expect_area("dashes, negative offset", &p, &st, w * 0.4 + 4 * 2 * w * h);
    st.cap = AA_CAP_BUTT;
    st.dash = d1;
    st.ndash = 1;
    st.dashoffset = 0;
    expect_area("dashes, odd list", &p, &st, w * 0.3);
    aa_path_free(&p);
}

/* Dashes on the closed square of test_closed_square (from its corner
 * (0.25, 0.25), perimeter 2), w = 0.1, miter joins, butt caps:
 *  - [1.5, 0.5] offset 0.25: the pattern is on from 0 to 1.25 and from
 *    1.75 to 2, which meet at the start: one dash from (0.25, 0.5) round
 *    three corners to (0.5, 0.75), 1.5 long with three right-angle miters:
 *    w 1.5 (as in test_corner: each miter fills the square the rectangles
 *    miss outside and they overlap in one inside);
 *  - [3, 1]: on over the whole square: the closed square, 0.36 - 0.16. */
static void test_dashes_closed(void **state)
{
    (void)state;
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.25, 0.25));
    must(aa_path_line_to(&p, 0.75, 0.25));
    must(aa_path_line_to(&p, 0.75, 0.75));
    must(aa_path_line_to(&p, 0.25, 0.75));
    must(aa_path_close(&p));
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.1;
    const double d1[2] = {1.5, 0.5}, d2[2] = {3, 1};
    st.dash = d1;
    st.ndash = 2;
    st.dashoffset = 0.25;
    expect_area("dash through a closed start", &p, &st, 0.1 * 1.5);
    st.dash = d2;
    st.dashoffset = 0;
    expect_area("dash over a closed square", &p, &st, 0.36 - 0.16);
    aa_path_free(&p);
}

/* ---- areas of strokes with arcs ---- */

/* Closed forms, h = w/2:
 *  - a line with round caps: w L + pi h^2;
 *  - a circle of radius r > h: the annulus pi ((r + h)^2 - (r - h)^2) =
 *    4 pi r h; r < h: the disk of radius r + h;
 *  - half a circle, butt caps: r > h half the annulus, 2 pi r h; r < h
 *    the half disk of radius r + h and, beyond the centre, the half disk
 *    of radius h - r: pi ((r + h)^2 + (h - r)^2) / 2;
 *  - a right angle of two lines with a round join: the rectangles,
 *    w (L1 + L2), overlap in the inner h x h square; the join adds the
 *    quarter disk outside: w (L1 + L2) - h^2 + pi h^2 / 4;
 *  - dashes on a circle, butt: an annular sector of arc length l has area
 *    l w (its angle times ((r + h)^2 - (r - h)^2) / 2): the dashes' total
 *    length, counted by hand, times w. */
static void test_arc_areas(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    aa_path p = {0};
    must(aa_path_move_to(&p, 0.2, 0.3));
    must(aa_path_line_to(&p, 0.7, 0.6));
    st.width = 0.08;
    st.cap = AA_CAP_ROUND;
    expect_area("round-capped line", &p, &st, 0.08 * hypot(0.5, 0.3) + M_PI * 0.04 * 0.04);
    aa_path_free(&p);

    for (int tight = 0; tight < 2; tight++) {
        double r = tight ? 0.1 : 0.3, h = tight ? 0.15 : 0.05;
        st.width = 2 * h;
        st.cap = AA_CAP_BUTT;
        circle_start(&p, 0.5, 0.5, r, 0, 1);
        circle_to(&p, 0.5, 0.5, r, 0, 2 * M_PI, 1);
        must(aa_path_close(&p));
        expect_area(tight ? "tight circle" : "circle", &p, &st,
                    tight ? M_PI * (r + h) * (r + h) : 4 * M_PI * r * h);
        aa_path_free(&p);
        circle_start(&p, 0.5, 0.5, r, 0.3, 0);
        circle_to(&p, 0.5, 0.5, r, 0.3, 0.3 + M_PI, 0);
        expect_area(tight ? "tight half circle" : "half circle", &p, &st,
                    tight ? 0.5 * M_PI * ((r + h) * (r + h) + (h - r) * (h - r))
                          : 2 * M_PI * r * h);
        aa_path_free(&p);
    }

    must(aa_path_move_to(&p, 0.2, 0.2));
    must(aa_path_line_to(&p, 0.7, 0.2));
    must(aa_path_line_to(&p, 0.7, 0.7));
    st.width = 0.1;
    st.join = AA_JOIN_ROUND;
    expect_area("round join", &p, &st, 0.1 - 0.0025 + M_PI * 0.0025 / 4);
    aa_path_free(&p);

    /* radius 0.3: length 0.6 pi = 1.88496; dashes [0.2, 0.1] from 0: 6
     * whole ones (to 1.8) and [1.8, 1.88496]: 1.2 + 0.6 pi - 1.8 */
    const double dash[2] = {0.2, 0.1};
    st.join = AA_JOIN_MITER;
    st.width = 0.04;
    st.dash = dash;
    st.ndash = 2;
    circle_start(&p, 0.5, 0.5, 0.3, 0, 1);
    circle_to(&p, 0.5, 0.5, 0.3, 0, 2 * M_PI, 1);
    expect_area("dashed circle", &p, &st, 0.04 * (1.2 + 0.6 * M_PI - 1.8));
    aa_path_free(&p);
}

/* ---- point membership, round joins and caps ---- */

/* Points found inside and outside since the last check_seen: a test sees
 * both, so it can fail either way. */
static long seen_in, seen_out;

static void check_seen(const char *what)
{
    print_message("%s: %ld points inside, %ld outside\n", what, seen_in, seen_out);
    if (!(seen_in > 100 && seen_out > 100))
        fail_msg("%s: too few points inside (%ld) or outside (%ld)", what, seen_in, seen_out);
    seen_in = seen_out = 0;
}

typedef int (*inside_fn)(const void *ctx, double x, double y, double *margin);

/* The outline's winding at random points of the box against `inside`;
 * returns how many points were compared. */
/* A point near the path: on a random segment (the closing lines too), then
 * moved by up to 1.5 h each way. */
static void near_point(const aa_path *p, double h, double *x, double *y)
{
    size_t k = (size_t)uniform(0, (double)p->n);
    if (k >= p->n)
        k = p->n - 1;
    double sx = 0, sy = 0, px = 0, py = 0;
    for (size_t i = 0; i <= k; i++) {
        const aa_path_seg *g = &p->seg[i];
        double ex = px, ey = py;
        if (g->op == AA_PATH_MOVE)
            sx = ex = g->p[0], sy = ey = g->p[1];
        else if (g->op == AA_PATH_LINE)
            ex = g->p[0], ey = g->p[1];
        else if (g->op == AA_PATH_ARC)
            ex = g->p[8], ey = g->p[9];
        else if (g->op == AA_PATH_CLOSE)
            ex = sx, ey = sy;
        if (i == k) {
            double f = uniform(0, 1);
            if (g->op == AA_PATH_ARC)
                arc_at(g->p, g->p[6] + f * (g->p[7] - g->p[6]), x, y);
            else
                *x = px + f * (ex - px), *y = py + f * (ey - py);
        }
        px = ex, py = ey;
    }
    *x += uniform(-1.5, 1.5) * h;
    *y += uniform(-1.5, 1.5) * h;
}

/* The outline's winding at n points, half of them random in the box and
 * half near `path` (within 1.5 h), against `inside`; returns how many
 * were compared (not within 1e-9 of a boundary). */
static int compare_points_near(const aa_path *out, double x0, double y0, double x1, double y1,
                               int n, inside_fn inside, const void *ctx, const char *what,
                               const aa_path *path, double h)
{
    int compared = 0, in = 0;
    for (int i = 0; i < n; i++) {
        double x = uniform(x0, x1), y = uniform(y0, y1), margin;
        if (path && path->n > 0 && i % 2)
            near_point(path, h, &x, &y);
        int want = inside(ctx, x, y, &margin);
        int w = winding(out, x, y);
        if (w < 0)
            fail_msg("%s: winding %d at (%.17g, %.17g)", what, w, x, y);
        if (margin < 1e-9)
            continue;
        compared++;
        in += want;
        if ((w != 0) != want)
            fail_msg("%s: at (%.17g, %.17g) winding %d, but the point is %s the stroke "
                     "(margin %g)",
                     what, x, y, w, want ? "inside" : "outside", margin);
    }
    seen_in += in;
    seen_out += compared - in;
    return compared;
}

static int compare_points(const aa_path *out, double x0, double y0, double x1, double y1, int n,
                          inside_fn inside, const void *ctx, const char *what)
{
    return compare_points_near(out, x0, y0, x1, y1, n, inside, ctx, what, NULL, 0);
}

typedef struct within {
    const aa_path *path;
    double h;
} within;

static int within_h(const void *ctx, double x, double y, double *margin)
{
    const within *c = ctx;
    double d = dist_path(c->path, x, y);
    *margin = fabs(d - c->h);
    return d <= c->h;
}

static void round_style(aa_stroke_style *st, double w)
{
    aa_stroke_style_default(st);
    st->width = w;
    st->join = AA_JOIN_ROUND;
    st->cap = AA_CAP_ROUND;
}

/* Lines and arcs: a quarter turn, a tight arc of radius 0.1 under
 * h = 0.15 (the normal crosses the centre), a clockwise one, and 1.6 pi of
 * a circle; then the same closed. */
static void test_round_fixed(void **state)
{
    (void)state;
    for (int closed = 0; closed < 2; closed++) {
        aa_path p = {0};
        must(aa_path_move_to(&p, 0, 0));
        must(aa_path_line_to(&p, 1, 0));
        circle_to(&p, 1, 1, 1, -M_PI / 2, 0, 1);        /* to (2, 1) */
        must(aa_path_line_to(&p, 2, 2));
        circle_to(&p, 2.1, 2, 0.1, M_PI, 0.1, 1);       /* tight, clockwise in angle */
        double x = p.penx, y = p.peny;
        must(aa_path_line_to(&p, x + 0.5, y + 0.7));
        circle_start(&p, 3, 3, 0.4, 0, 0); /* a new subpath: 1.6 pi, clockwise */
        circle_to(&p, 3, 3, 0.4, 0, 1.6 * M_PI, 0);
        must(aa_path_line_to(&p, 2.2, 3.2));
        if (closed)
            must(aa_path_close(&p));
        aa_stroke_style st;
        round_style(&st, 0.3);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        int nc = check_orientation(&out);
        within c = {&p, 0.15};
        int n = compare_points_near(&out, -0.4, -0.4, 3.6, 3.6, 8000, within_h, &c, "fixed path",
                                    &p, 0.15);
        check_seen("fixed path");
        print_message("fixed path (%s): %d contours, %d points agree\n",
                      closed ? "closed" : "open", nc, n);
        aa_path_free(&out);
        aa_path_free(&p);
    }
}

/* A random path of lines and circular arcs (some tight), open or closed. */
static void random_path(aa_path *p, int closed)
{
    int n = 2 + (int)uniform(0, 6);
    must(aa_path_move_to(p, uniform(0, 1), uniform(0, 1)));
    for (int k = 0; k < n; k++) {
        if (uniform(0, 1) < 0.5) {
            must(aa_path_line_to(p, uniform(0, 1), uniform(0, 1)));
        } else {
            /* a circle through the pen: centre at a random offset */
            double r = uniform(0, 1) < 0.3 ? uniform(0.01, 0.08) : uniform(0.1, 0.5);
            double a = uniform(-M_PI, M_PI), ccw = uniform(0, 1) < 0.5;
            double s = ccw ? 1 : -1;
            double cx = p->penx - r * cos(a), cy = p->peny - s * r * sin(a);
            double t1 = a + uniform(-2 * M_PI, 2 * M_PI);
            circle_to(p, cx, cy, r, a, t1, ccw);
        }
    }
    if (closed)
        must(aa_path_close(p));
}

static void test_round_random(void **state)
{
    (void)state;
    int total = 0;
    for (int i = 0; i < 45; i++) {
        aa_path p = {0};
        random_path(&p, i % 3 == 0);
        aa_stroke_style st;
        round_style(&st, uniform(0.02, 0.3));
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        check_orientation(&out);
        within c = {&p, 0.5 * st.width};
        char what[64];
        snprintf(what, sizeof what, "random path %d", i);
        total += compare_points_near(&out, -0.6, -0.6, 1.6, 1.6, 1000, within_h, &c, what, &p,
                                     c.h);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    check_seen("random round strokes");
    print_message("random round strokes: %d points agree\n", total);
}

/* The dashes of a path laid out here: the parts of it from arc length a to
 * b (a path of lines and circular arcs, as aa_path segments). */
static void dash_part(const aa_path *p, double a, double b, aa_path *part)
{
    double s = 0, px = 0, py = 0;
    int started = 0;
    for (size_t k = 0; k < p->n; k++) {
        const aa_path_seg *g = &p->seg[k];
        if (g->op == AA_PATH_MOVE) {
            px = g->p[0], py = g->p[1];
            continue;
        }
        double len, x1 = g->p[0], y1 = g->p[1];
        if (g->op == AA_PATH_ARC) {
            len = hypot(g->p[2], g->p[3]) * fabs(g->p[7] - g->p[6]);
            x1 = g->p[8], y1 = g->p[9];
        } else {
            len = hypot(x1 - px, y1 - py);
        }
        double lo = fmax(a, s), hi = fmin(b, s + len);
        if (hi > lo || (a == b && lo == hi && len > 0)) {
            double f0 = (lo - s) / len, f1 = (hi - s) / len;
            if (g->op == AA_PATH_ARC) {
                double t0 = g->p[6] + f0 * (g->p[7] - g->p[6]);
                double t1 = g->p[6] + f1 * (g->p[7] - g->p[6]), x, y, ex, ey;
                arc_at(g->p, t0, &x, &y);
                arc_at(g->p, t1, &ex, &ey);
                if (!started)
                    must(aa_path_move_to(part, x, y));
                if (t1 > t0 || t1 < t0)
                    must(aa_path_arc_to(part, g->p[0], g->p[1], g->p[2], g->p[3], g->p[4],
                                        g->p[5], t0, t1, ex, ey));
                else
                    must(aa_path_line_to(part, ex, ey));
            } else {
                if (!started)
                    must(aa_path_move_to(part, px + f0 * (x1 - px), py + f0 * (y1 - py)));
                must(aa_path_line_to(part, px + f1 * (x1 - px), py + f1 * (y1 - py)));
            }
            started = 1;
            if (a == b)
                return;
        }
        s += len;
        px = x1, py = y1;
    }
}

/* The dashes of an open path laid out here by arc length: dash k of the
 * pattern's repetition q runs from q period + its place in the pattern -
 * the offset; each becomes a subpath of `dashes` (dash_part). */
static void lay_dashes(const aa_path *p, const aa_stroke_style *st, aa_path *dashes)
{
    double len = 0, px = 0, py = 0;
    for (size_t k = 0; k < p->n; k++) {
        const aa_path_seg *g = &p->seg[k];
        if (g->op == AA_PATH_MOVE)
            px = g->p[0], py = g->p[1];
        else if (g->op == AA_PATH_LINE)
            len += hypot(g->p[0] - px, g->p[1] - py), px = g->p[0], py = g->p[1];
        else
            len += hypot(g->p[2], g->p[3]) * fabs(g->p[7] - g->p[6]), px = g->p[8],
                py = g->p[9];
    }
    double pat[6];
    int m = st->ndash % 2 ? 2 * (int)st->ndash : (int)st->ndash;
    double period = 0;
    for (int k = 0; k < m; k++)
        period += pat[k] = st->dash[k % st->ndash];
    for (double q = floor((st->dashoffset - period) / period);
         q * period - st->dashoffset <= len; q++) {
        double at = q * period - st->dashoffset;
        for (int k = 0; k < m; k++) {
            double a = at, b = at + pat[k];
            at = b;
            if (k % 2 || b < 0 || a > len || (a == b && (a < 0 || a >= len)))
                continue;
            dash_part(p, fmax(a, 0), fmin(b, len), dashes);
        }
    }
}

/* Dashed random open paths, round joins and caps: the stroke is the points
 * within h of the dashes, each the part of the path between the ends of an
 * "on" entry of the pattern repeated from the offset. */
static void test_round_dashes(void **state)
{
    (void)state;
    int total = 0;
    for (int i = 0; i < 30; i++) {
        aa_path p = {0};
        random_path(&p, 0);
        aa_stroke_style st;
        round_style(&st, uniform(0.02, 0.1));
        double dash[3] = {uniform(0.05, 0.4), uniform(0.02, 0.3), uniform(0, 0.2)};
        st.dash = dash;
        st.ndash = 2 + (i % 2);
        st.dashoffset = uniform(-1, 1);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        check_orientation(&out);
        aa_path dashes = {0};
        lay_dashes(&p, &st, &dashes);
        within c = {&dashes, 0.5 * st.width};
        char what[64];
        snprintf(what, sizeof what, "dashed path %d", i);
        total += compare_points_near(&out, -0.5, -0.5, 1.5, 1.5, 1000, within_h, &c, what,
                                     &dashes, c.h);
        aa_path_free(&dashes);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    check_seen("dashed round strokes");
    print_message("dashed round strokes: %d points agree\n", total);
}

/* ---- point membership, every join and cap ---- */

/* The SVG 2 stroke shape by its definition, point by point: a point is in
 * it when it is on the normal (length w, centred) of a segment, in the join
 * shape at a vertex or in a cap.  Derived here from the definitions, not
 * from the outline: a line's normals sweep its rectangle; a circular arc's
 * normal at t is the radial line through the centre, so a point at polar
 * (rho, theta) about the centre is on it when theta = t and
 * |rho - r| <= h, or theta = t + pi and rho + r <= h; joins on the outer
 * side (away from the turn): bevel the triangle of the vertex and the two
 * offset points, miter the quadrilateral adding the meeting point of the
 * outer offset lines when 1/sin(theta/2) <= limit (theta = pi - the turn),
 * round the points within h ahead of both outer normals; caps beyond the
 * ends: square a rectangle h deep, round a half disk. */
typedef struct seg {
    int arc;
    double x0, y0, x1, y1, c[8], len;
} seg;

typedef struct shape {
    seg s[1024];
    int n, first[256], count[256], closed[256], nsub;
    double h, limit;
    int join, cap;
    const aa_path *out; /* the outline: margins are distances to its edges */
} shape;

static void seg_tangent(const seg *g, int at_end, double d[2])
{
    if (!g->arc) {
        d[0] = (g->x1 - g->x0) / g->len, d[1] = (g->y1 - g->y0) / g->len;
        return;
    }
    const double *c = g->c;
    double t = at_end ? c[7] : c[6], sg = c[7] > c[6] ? 1 : -1;
    double x = sg * (-c[2] * sin(t) + c[4] * cos(t)), y = sg * (-c[3] * sin(t) + c[5] * cos(t));
    d[0] = x / hypot(x, y), d[1] = y / hypot(x, y);
}

static void shape_of(const aa_path *p, shape *sh)
{
    sh->n = sh->nsub = 0;
    double sx = 0, sy = 0, px = 0, py = 0;
    for (size_t k = 0; k < p->n; k++) {
        const aa_path_seg *g = &p->seg[k];
        seg t = {0};
        if (g->op == AA_PATH_MOVE) {
            assert_true(sh->nsub < 256);
            sx = px = g->p[0], sy = py = g->p[1];
            sh->first[sh->nsub] = sh->n, sh->count[sh->nsub] = 0, sh->closed[sh->nsub] = 0;
            sh->nsub++;
            continue;
        }
        if (g->op == AA_PATH_ARC) {
            t.arc = 1;
            memcpy(t.c, g->p, sizeof t.c);
            t.x1 = g->p[8], t.y1 = g->p[9];
            t.len = hypot(g->p[2], g->p[3]) * fabs(g->p[7] - g->p[6]);
        } else {
            t.x1 = g->op == AA_PATH_CLOSE ? sx : g->p[0];
            t.y1 = g->op == AA_PATH_CLOSE ? sy : g->p[1];
            t.len = hypot(t.x1 - px, t.y1 - py);
        }
        t.x0 = px, t.y0 = py;
        px = t.x1, py = t.y1;
        /* a line of rounding's length has no direction (stroke.c drops it) */
        if (!t.arc && t.len <= 1e-14 * (fabs(t.x0) + fabs(t.y0) + fabs(t.x1) + fabs(t.y1)))
            t.len = 0;
        if (t.len > 0) {
            assert_true(sh->n < 1024);
            sh->s[sh->n++] = t;
            sh->count[sh->nsub - 1]++;
        }
        if (g->op == AA_PATH_CLOSE)
            sh->closed[sh->nsub - 1] = 1;
    }
}

static int on_normals(const seg *g, double h, double qx, double qy)
{
    if (!g->arc) {
        double dx = (g->x1 - g->x0) / g->len, dy = (g->y1 - g->y0) / g->len;
        double a = (qx - g->x0) * dx + (qy - g->y0) * dy;
        double b = (qx - g->x0) * dy - (qy - g->y0) * dx;
        return a >= 0 && a <= g->len && fabs(b) <= h;
    }
    const double *c = g->c;
    double r2 = c[2] * c[2] + c[3] * c[3], r = sqrt(r2);
    double rx = qx - c[0], ry = qy - c[1], rho = hypot(rx, ry);
    double th = atan2((rx * c[4] + ry * c[5]) / r2, (rx * c[2] + ry * c[3]) / r2);
    double lo = fmin(c[6], c[7]), hi = fmax(c[6], c[7]);
    for (int side = 0; side < 2; side++) {
        double t = th + side * M_PI;
        double k = ceil((lo - t) / (2 * M_PI));
        if (t + k * 2 * M_PI <= hi && (side ? rho + r <= h : fabs(rho - r) <= h))
            return 1;
    }
    return 0;
}

/* In the convex polygon (either turning sense), edges included. */
static int in_convex(const double *xy, int n, double qx, double qy)
{
    int pos = 0, neg = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        double cr = (xy[2 * j] - xy[2 * i]) * (qy - xy[2 * i + 1]) -
                    (xy[2 * j + 1] - xy[2 * i + 1]) * (qx - xy[2 * i]);
        pos |= cr > 0;
        neg |= cr < 0;
    }
    return !(pos && neg);
}

static int in_join(const shape *sh, double px, double py, const double di[2], const double dd[2],
                   double qx, double qy)
{
    double h = sh->h, cr = di[0] * dd[1] - di[1] * dd[0], dot = di[0] * dd[0] + di[1] * dd[1];
    if (cr == 0 && dot > 0)
        return 0;
    double ex = qx - px, ey = qy - py;
    if (sh->join == AA_JOIN_ROUND)
        return hypot(ex, ey) <= h && ex * di[0] + ey * di[1] >= 0 && ex * dd[0] + ey * dd[1] <= 0;
    /* the outer normals: away from the turn (right of a left turn) */
    double o = cr > 0 ? -1 : 1;
    double ax = px - o * h * di[1], ay = py + o * h * di[0];
    double bx = px - o * h * dd[1], by = py + o * h * dd[0];
    double theta = M_PI - acos(fmax(-1, fmin(1, dot)));
    if (sh->join == AA_JOIN_MITER && sin(theta / 2) > 0 && 1 / sin(theta / 2) <= sh->limit) {
        const double pa[2] = {ax, ay}, pb[2] = {bx, by};
        double m[2];
        support_line_meet(pa, di, pb, dd, m);
        const double quad[8] = {px, py, ax, ay, m[0], m[1], bx, by};
        return in_convex(quad, 4, qx, qy);
    }
    if (cr == 0)
        return 0;
    const double tri[6] = {px, py, ax, ay, bx, by};
    return in_convex(tri, 3, qx, qy);
}

static int in_cap(const shape *sh, double px, double py, const double d[2], double qx, double qy)
{
    double ex = qx - px, ey = qy - py, a = ex * d[0] + ey * d[1], b = ex * d[1] - ey * d[0];
    if (sh->cap == AA_CAP_SQUARE)
        return a >= 0 && a <= sh->h && fabs(b) <= sh->h;
    if (sh->cap == AA_CAP_ROUND)
        return a >= 0 && hypot(ex, ey) <= sh->h;
    return 0;
}

/* Distance to the outline's edges (lines and circular arcs). */
static double dist_outline(const aa_path *out, double qx, double qy)
{
    return dist_path(out, qx, qy);
}

static int in_shape(const void *ctx, double qx, double qy, double *margin)
{
    const shape *sh = ctx;
    *margin = dist_outline(sh->out, qx, qy);
    for (int k = 0; k < sh->n; k++)
        if (on_normals(&sh->s[k], sh->h, qx, qy))
            return 1;
    for (int u = 0; u < sh->nsub; u++) {
        const seg *g = &sh->s[sh->first[u]];
        int n = sh->count[u];
        if (n == 0)
            continue;
        double di[2], dd[2];
        for (int k = 1; k < n; k++) {
            seg_tangent(&g[k - 1], 1, di);
            seg_tangent(&g[k], 0, dd);
            if (in_join(sh, g[k].x0, g[k].y0, di, dd, qx, qy))
                return 1;
        }
        if (sh->closed[u]) {
            seg_tangent(&g[n - 1], 1, di);
            seg_tangent(&g[0], 0, dd);
            if (in_join(sh, g[0].x0, g[0].y0, di, dd, qx, qy))
                return 1;
        } else {
            seg_tangent(&g[0], 0, dd);
            const double back[2] = {-dd[0], -dd[1]};
            seg_tangent(&g[n - 1], 1, di);
            if (in_cap(sh, g[0].x0, g[0].y0, back, qx, qy) ||
                in_cap(sh, g[n - 1].x1, g[n - 1].y1, di, qx, qy))
                return 1;
        }
    }
    return 0;
}

/* Random paths, every join and cap, limits from 1 to 6, widths up to
 * 0.3 (arcs tighter than h among them). */
static void test_shape_random(void **state)
{
    (void)state;
    int total = 0;
    static shape sh;
    for (int i = 0; i < 90; i++) {
        aa_path p = {0};
        random_path(&p, i % 3 == 0);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = uniform(0.02, 0.3);
        st.join = (aa_line_join)(i % 3);
        st.cap = (aa_line_cap)((i / 3) % 3);
        st.miterlimit = uniform(1, 6);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        check_orientation(&out);
        shape_of(&p, &sh);
        sh.h = 0.5 * st.width, sh.limit = st.miterlimit;
        sh.join = st.join, sh.cap = st.cap, sh.out = &out;
        char what[64];
        snprintf(what, sizeof what, "random path %d (join %d cap %d)", i, i % 3, (i / 3) % 3);
        total += compare_points_near(&out, -0.6, -0.6, 1.6, 1.6, 1000, in_shape, &sh, what, &p,
                                     sh.h);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    check_seen("random strokes, every join");
    print_message("random strokes, every join and cap: %d points agree\n", total);
}

/* Dashed random open paths, every join and cap: the shape of the dashes
 * laid out here (lay_dashes), each an open subpath with its own caps and
 * the joins inside it. */
static void test_shape_dashes(void **state)
{
    (void)state;
    int total = 0;
    static shape sh;
    for (int i = 0; i < 36; i++) {
        aa_path p = {0};
        random_path(&p, 0);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = uniform(0.02, 0.1);
        st.join = (aa_line_join)(i % 3);
        st.cap = (aa_line_cap)((i / 3) % 3);
        st.miterlimit = uniform(1, 6);
        double dash[3] = {uniform(0.05, 0.4), uniform(0.15, 0.3), uniform(0.01, 0.2)};
        st.dash = dash;
        st.ndash = 2 + (i % 2);
        st.dashoffset = uniform(-1, 1);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        check_orientation(&out);
        aa_path dashes = {0};
        lay_dashes(&p, &st, &dashes);
        shape_of(&dashes, &sh);
        sh.h = 0.5 * st.width, sh.limit = st.miterlimit;
        sh.join = st.join, sh.cap = st.cap, sh.out = &out;
        char what[64];
        snprintf(what, sizeof what, "dashed path %d (join %d cap %d)", i, i % 3, (i / 3) % 3);
        total += compare_points_near(&out, -0.6, -0.6, 1.6, 1.6, 1000, in_shape, &sh, what,
                                     &dashes, sh.h);
        aa_path_free(&dashes);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    check_seen("dashed strokes, every join");
    print_message("dashed strokes, every join and cap: %d points agree\n", total);
}

/* Single arcs with butt caps: the normals' sweep alone, tight arcs
 * (r < h: the sector beyond the centre) among them. */
static void test_arc_butt(void **state)
{
    (void)state;
    int total = 0;
    static shape sh;
    for (int i = 0; i < 40; i++) {
        aa_path p = {0};
        double r = uniform(0.05, 0.4), a = uniform(-M_PI, M_PI);
        int ccw = i % 2;
        circle_start(&p, 0.5, 0.5, r, a, ccw);
        circle_to(&p, 0.5, 0.5, r, a, a + uniform(-2 * M_PI, 2 * M_PI), ccw);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = r * uniform(0.2, 4);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        check_orientation(&out);
        shape_of(&p, &sh);
        sh.h = 0.5 * st.width, sh.limit = st.miterlimit;
        sh.join = st.join, sh.cap = st.cap, sh.out = &out;
        total += compare_points_near(&out, -0.5, -0.5, 1.5, 1.5, 1000, in_shape, &sh, "butt arc",
                                     &p, sh.h);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    check_seen("butt arcs");
    print_message("butt arcs: %d points agree\n", total);
}

/* A full circle whose end, computed by cos and sin, misses its start by
 * rounding, then closed: the closing line is of rounding's length, and
 * must not join the circle at an angle of its own (with a miter limit of
 * 100 a spurious join would reach far out). */
static void test_closing_rounding(void **state)
{
    (void)state;
    static shape sh;
    aa_path p = {0};
    circle_start(&p, 0.5, 0.5, 0.3, 0.1, 1);
    circle_to(&p, 0.5, 0.5, 0.3, 0.1, 0.1 + 2 * M_PI, 1);
    assert_true(p.penx != 0.5 + 0.3 * cos(0.1) || p.peny != 0.5 + 0.3 * sin(0.1));
    must(aa_path_close(&p));
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.1;
    st.miterlimit = 100;
    aa_path out = {0};
    must(aa_stroke_outline(&p, &st, &out));
    check_orientation(&out);
    shape_of(&p, &sh);
    sh.h = 0.05, sh.limit = 100, sh.join = st.join, sh.cap = st.cap, sh.out = &out;
    compare_points_near(&out, 0, 0, 1, 1, 4000, in_shape, &sh, "closed circle", &p, 0.05);
    /* the annulus: at radius 0.25 .. 0.35 from the centre only */
    for (int k = 0; k < 2000; k++) {
        double a = uniform(0, 2 * M_PI), rho = uniform(0, 0.6);
        if (fabs(rho - 0.25) < 1e-9 || fabs(rho - 0.35) < 1e-9)
            continue;
        int w = winding(&out, 0.5 + rho * cos(a), 0.5 + rho * sin(a));
        assert_int_equal(w != 0, rho >= 0.25 && rho <= 0.35);
    }
    check_seen("closed circle");
    aa_path_free(&out);
    aa_path_free(&p);

    /* the same circle from angle 0, then a line one ulp to the left and
     * the close back: lines at right angles to the circle's tangent
     * (0, 1) there; the turn from (0, 1) to (-1, 0) is to the left, so its
     * miter would fill the outer h x h square [0.8, 0.85] x [0.5, 0.55],
     * and the closing join's [0.8, 0.85] x [0.45, 0.5]; their corners
     * beyond the annulus ((0.849, 0.5 +- 0.049): 0.3524 from the centre)
     * stay outside */
    must(aa_path_move_to(&p, 0.8, 0.5));
    must(aa_path_arc_to(&p, 0.5, 0.5, 0.3, 0, 0, 0.3, 0, 2 * M_PI, 0.8, 0.5));
    must(aa_path_line_to(&p, nextafter(0.8, 0), 0.5));
    must(aa_path_close(&p));
    must(aa_stroke_outline(&p, &st, &out));
    check_orientation(&out);
    assert_int_equal(winding(&out, 0.849, 0.549), 0);
    assert_int_equal(winding(&out, 0.849, 0.451), 0);
    assert_int_equal(winding(&out, 0.849, 0.5 + 1e-3), 1);
    aa_path_free(&out);
    aa_path_free(&p);
}

/* ---- through a scene ---- */

typedef struct mapped {
    const aa_scene *scene;
    double inv[6]; /* the map's inverse */
    shape *sh;
} mapped;

/* The scene's colour at (x, y) against the stroke shape at the point's
 * preimage; the margin is the preimage's distance to the outline, scaled
 * by the map's least stretch (here at least 0.5). */
static int compare_scene(const mapped *m, double x, double y, int *agree)
{
    double px = m->inv[0] * x + m->inv[2] * y + m->inv[4];
    double py = m->inv[1] * x + m->inv[3] * y + m->inv[5];
    double margin;
    int want = in_shape(m->sh, px, py, &margin);
    if (margin * 0.5 < 1e-9)
        return 0;
    aa_rgb c = aa_scene_colour_at(m->scene, x, y);
    int got = c.c[0] == 1;
    if (got != want)
        fail_msg("scene at (%.17g, %.17g) (preimage (%.17g, %.17g)): %s, the shape says %s",
                 x, y, px, py, got ? "inside" : "outside", want ? "inside" : "outside");
    *agree += 1;
    return want;
}

/* The outline filled into a scene through an affine map (a shear: its
 * circles become ellipses): the scene's point query (aa_scene_colour_at)
 * agrees with the stroke shape at the preimage, for random paths, every
 * join and cap. */
static void test_scene_points(void **state)
{
    (void)state;
    static shape sh;
    /* x' = 0.9 x + 0.3 y + 0.05, y' = 0.1 x + 0.8 y + 0.1; det 0.69 */
    const double m[6] = {0.9, 0.1, 0.3, 0.8, 0.05, 0.1};
    double det = m[0] * m[3] - m[1] * m[2];
    mapped q = {.sh = &sh};
    int agree = 0;
    long in = 0;
    for (int i = 0; i < 24; i++) {
        aa_path p = {0};
        random_path(&p, i % 3 == 0);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = uniform(0.02, 0.3);
        st.join = (aa_line_join)(i % 3);
        st.cap = (aa_line_cap)((i / 3) % 3);
        st.miterlimit = uniform(1, 6);
        aa_path out = {0};
        must(aa_stroke_outline(&p, &st, &out));
        shape_of(&p, &sh);
        sh.h = 0.5 * st.width, sh.limit = st.miterlimit;
        sh.join = st.join, sh.cap = st.cap, sh.out = &out;
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_non_null(s);
        must(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO));
        must(aa_path_fill(&out, i % 2 ? m : NULL, s));
        must(aa_scene_finish(s));
        q.scene = s;
        /* every other path through the map, the rest as they are */
        if (!(i % 2)) {
            q.inv[0] = 1, q.inv[1] = 0, q.inv[2] = 0, q.inv[3] = 1, q.inv[4] = 0, q.inv[5] = 0;
        } else {
            q.inv[0] = m[3] / det, q.inv[1] = -m[1] / det, q.inv[2] = -m[2] / det;
            q.inv[3] = m[0] / det;
            q.inv[4] = -(q.inv[0] * m[4] + q.inv[2] * m[5]);
            q.inv[5] = -(q.inv[1] * m[4] + q.inv[3] * m[5]);
        }
        for (int k = 0; k < 600; k++) {
            double x, y;
            if (k % 2) {
                near_point(&p, sh.h, &x, &y);
                if (i % 2) {
                    double tx = m[0] * x + m[2] * y + m[4];
                    y = m[1] * x + m[3] * y + m[5];
                    x = tx;
                }
            } else {
                x = uniform(-0.6, 1.6), y = uniform(-0.6, 1.6);
            }
            in += compare_scene(&q, x, y, &agree);
        }
        aa_scene_free(s);
        aa_path_free(&out);
        aa_path_free(&p);
    }
    print_message("scene point queries: %d points agree, %ld inside\n", agree, in);
    assert_true(in > 100 && agree - in > 100);
}

/* ---- degenerate subpaths, refusals ---- */

typedef struct square {
    double x, y, h;
} square;

static int in_square(const void *ctx, double x, double y, double *margin)
{
    const square *s = ctx;
    double d = fmax(fabs(x - s->x), fabs(y - s->y));
    *margin = fabs(d - s->h);
    return d <= s->h;
}

static void test_zero_length(void **state)
{
    (void)state;
    aa_path p = {0}, out = {0};
    must(aa_path_move_to(&p, 0.5, 0.5));
    must(aa_path_line_to(&p, 0.5, 0.5));
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.4;
    must(aa_stroke_outline(&p, &st, &out));
    assert_int_equal(out.n, 0); /* butt: nothing */
    st.cap = AA_CAP_ROUND;
    must(aa_stroke_outline(&p, &st, &out));
    check_orientation(&out);
    within c = {&p, 0.2};
    compare_points(&out, 0, 0, 1, 1, 2000, within_h, &c, "dot, round");
    check_seen("dot, round");
    aa_path_free(&out);
    st.cap = AA_CAP_SQUARE;
    must(aa_stroke_outline(&p, &st, &out));
    check_orientation(&out);
    square sq = {0.5, 0.5, 0.2};
    compare_points(&out, 0, 0, 1, 1, 2000, in_square, &sq, "dot, square");
    check_seen("dot, square");
    aa_path_free(&out);
    /* dashed: drawn when the pattern starts in a dash, not in a gap */
    const double dash[2] = {0.1, 0.2};
    st.dash = dash;
    st.ndash = 2;
    st.dashoffset = 0.05;
    must(aa_stroke_outline(&p, &st, &out));
    assert_true(out.n > 0);
    aa_path_free(&out);
    st.dashoffset = 0.15;
    must(aa_stroke_outline(&p, &st, &out));
    assert_int_equal(out.n, 0);
    st.dash = NULL;
    st.ndash = 0;
    st.dashoffset = 0;
    aa_path_free(&p);
    /* M p Z is a dot too; a lone move is nothing */
    must(aa_path_move_to(&p, 0.5, 0.5));
    must(aa_path_close(&p));
    must(aa_stroke_outline(&p, &st, &out));
    assert_true(out.n > 0);
    aa_path_free(&out);
    aa_path_free(&p);
    must(aa_path_move_to(&p, 0.5, 0.5));
    must(aa_stroke_outline(&p, &st, &out));
    assert_int_equal(out.n, 0);
    /* zero-length segments inside a path: no join of their own (a straight
     * line through one stays a rectangle, even with round joins) */
    must(aa_path_line_to(&p, 0.5, 0.5));
    must(aa_path_line_to(&p, 0.6, 0.5));
    must(aa_path_line_to(&p, 0.6, 0.5));
    must(aa_path_line_to(&p, 0.7, 0.5));
    st.cap = AA_CAP_BUTT;
    st.join = AA_JOIN_MITER;
    st.width = 0.1;
    expect_area("zero-length segments", &p, &st, 0.1 * 0.2);
    aa_path_free(&p);
}

static void test_refused(void **state)
{
    (void)state;
    aa_path p = {0}, out = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    /* something in out already, kept on failure */
    must(aa_path_move_to(&out, 0, 0));
    must(aa_path_line_to(&out, 1, 0));
    must(aa_path_close(&out));
    size_t keep = out.n;

    /* a cubic nearly with a cusp (|B'(1/2)| 1e-10 of its size; cusps:
     * test_bezstroke.c) */
    must(aa_path_move_to(&p, 0, 0));
    must(aa_path_line_to(&p, 1, 0));
    must(aa_path_cubic_to(&p, 2, 1, 1 + 1e-10, 1, 2, 0));
    assert_int_equal(aa_stroke_outline(&p, &st, &out), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "cusp"));
    assert_int_equal(out.n, keep);
    aa_path_free(&p);

    must(aa_path_move_to(&p, 0, 0));
    must(aa_path_line_to(&p, 1, 0));
    const double neg[2] = {1, -1}, zero[2] = {0, 0};
    aa_stroke_style bad = st;
    bad.width = 0;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.width = NAN;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.miterlimit = 0.5;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.dash = neg, bad.ndash = 2;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.dash = zero, bad.ndash = 2;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.dash = NULL, bad.ndash = 2;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.join = (aa_line_join)7;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.cap = (aa_line_cap)-1;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    bad = st, bad.dash = neg, bad.ndash = 1, bad.dashoffset = INFINITY;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    assert_int_equal(aa_stroke_outline(&p, &st, &p), AA_EINVAL);
    /* a pattern far too fine for the path */
    const double fine[1] = {1e-9};
    bad = st, bad.dash = fine, bad.ndash = 1;
    assert_int_equal(aa_stroke_outline(&p, &bad, &out), AA_EINVAL);
    assert_int_equal(out.n, keep);
    aa_path_free(&p);
    aa_path_free(&out);
}

static void test_default_style(void **state)
{
    (void)state;
    aa_stroke_style st;
    memset(&st, 0x55, sizeof st);
    aa_stroke_style_default(&st);
    /* SVG's initial values: stroke-width 1, miter, butt, miterlimit 4, no
     * dashes */
    assert_true(st.width == 1 && st.join == AA_JOIN_MITER && st.cap == AA_CAP_BUTT);
    assert_true(st.miterlimit == 4 && st.dash == NULL && st.ndash == 0 && st.dashoffset == 0);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_default_style), cmocka_unit_test(test_line_caps),
             cmocka_unit_test(test_corner), cmocka_unit_test(test_sharp_turn),
             cmocka_unit_test(test_closed_square), cmocka_unit_test(test_dashes_line),
             cmocka_unit_test(test_runs_one_contour),
             cmocka_unit_test(test_dashes_closed), cmocka_unit_test(test_arc_areas),
             cmocka_unit_test(test_round_fixed), cmocka_unit_test(test_round_random),
             cmocka_unit_test(test_round_dashes), cmocka_unit_test(test_arc_butt),
             cmocka_unit_test(test_shape_random), cmocka_unit_test(test_shape_dashes),
             cmocka_unit_test(test_closing_rounding),
             cmocka_unit_test(test_scene_points),
             cmocka_unit_test(test_zero_length),
             cmocka_unit_test(test_refused))
