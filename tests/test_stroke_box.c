/*
 * test_stroke_box.c: the SVG reader's stroke bounding box (patterns/
 * svgfile.c, stroke_box; SVG 2, "Bounding boxes": the tightest rectangle
 * that contains the stroke shape, "with the assumption that the element
 * has no dash pattern") for strokes of Bezier and elliptical arcs, whose
 * outlines hold offset curves, read through transform-box: stroke-box.
 *
 * How the box is read back: with transform-origin 0 0 the reference box's
 * corner (x0, y0) is the origin of the element's transform, so
 * translate(100%, 100%) (percentages of the box's size) gives the
 * stroke's map the translation (x0 + W, y0 + H) ... and scale(0.5) gives
 * it x0/2, y0/2: the map's translation, in pattern units (1/64 of a user
 * unit here, a power of two: exact), says x0, y0, W and H.
 *
 * The oracle: the stroke shape is the union of the normal segments of
 * length w across the path (and the caps and joins), so its box is that
 * of the two offset curves B(t) +- h N(t) over the whole parameter range,
 * ends included, and of the caps' half disks: sampled here at n = 2^20 + 1
 * even steps of t.  A coordinate x(t) of an offset is smooth in t (B' does
 * not vanish), so at an interior extreme the nearest sample falls short
 * by at most max|x''| (dt/2)^2 / 2; here |x''| is under 10^4 user units
 * (w = 8 on curves of size 50: the offset's second derivative is that of
 * B, at most about 6 times the control polygon's size 50, plus h times the
 * derivative of N's rate, k |B'|^2, with |k| h at most about 40 on the
 * tight cubic below), so the sampling is within 10^4 (2^-21)^2 / 2, about
 * 1.2e-9 of the box: the box read back must be within 2e-9 of the samples'
 * and never inside them by more than rounding (1e-12).
 */
#include "bench.h"
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

#define N 64

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "stroke_box");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* The stroke source's map of the one stroked element of `body`. */
static void stroke_map(const char *name, const char *body, double m[6])
{
    aa_scene *sc = support_svg_scene(dir, name, body, N, N);
    size_t n;
    const aa_stroke_source *src = aa_scene_stroke_sources(sc, &n);
    assert_int_equal(n, 1);
    memcpy(m, src[0].m, 6 * sizeof *m);
    aa_scene_free(sc);
}

/* The reader's stroke box of the element <`el` `attrs` .../> (x0 y0 x1 y1). */
static void read_box(const char *el, const char *attrs, double box[4])
{
    char body[2048];
    double m[6];
    snprintf(body, sizeof body,
             "<%s %s fill=\"none\" stroke=\"white\" style=\"transform-box: stroke-box; "
             "transform-origin: 0 0; transform: scale(0.5)\"/>",
             el, attrs);
    stroke_map("corner", body, m);
    box[0] = 2 * m[4] * N, box[1] = 2 * m[5] * N;
    snprintf(body, sizeof body,
             "<%s %s fill=\"none\" stroke=\"white\" style=\"transform-box: stroke-box; "
             "transform-origin: 0 0; transform: translate(100%%, 100%%)\"/>",
             el, attrs);
    stroke_map("size", body, m);
    box[2] = m[4] * N, box[3] = m[5] * N;
}

/* A curve for the oracle: B(t) and B'(t). */
typedef struct curve {
    int ellipse;
    double p[8]; /* a cubic's control points, or cx cy rx ry t0 t1 */
} curve;

static void curve_at(const curve *c, double t, double b[2], double d[2])
{
    const double *p = c->p;
    if (c->ellipse) {
        double a = p[4] + t * (p[5] - p[4]);
        b[0] = p[0] + p[2] * cos(a), b[1] = p[1] + p[3] * sin(a);
        d[0] = -p[2] * sin(a) * (p[5] - p[4]), d[1] = p[3] * cos(a) * (p[5] - p[4]);
        return;
    }
    double s = 1 - t;
    for (int k = 0; k < 2; k++) {
        b[k] = s * s * s * p[k] + 3 * s * s * t * p[2 + k] + 3 * s * t * t * p[4 + k] +
               t * t * t * p[6 + k];
        d[k] = 3 * (s * s * (p[2 + k] - p[k]) + 2 * s * t * (p[4 + k] - p[2 + k]) +
                    t * t * (p[6 + k] - p[4 + k]));
    }
}

static void grow(double box[4], double x, double y)
{
    box[0] = fmin(box[0], x), box[1] = fmin(box[1], y);
    box[2] = fmax(box[2], x), box[3] = fmax(box[3], y);
}

/* The sampled box of the stroke of width w of the curve: both offsets at
 * 2^20 + 1 values of t, and, with round caps, the half disks at the ends
 * (4097 angles each, their axis-aligned extremes included exactly by the
 * angles 0, pi/2, pi, 3 pi/2 where they fall in the half). */
static void sampled_box(const curve *c, double w, int round, double box[4])
{
    const int n = 1 << 20;
    double h = w / 2;
    box[0] = box[1] = INFINITY, box[2] = box[3] = -INFINITY;
    for (int i = 0; i <= n; i++) {
        double b[2], d[2];
        curve_at(c, (double)i / n, b, d);
        double l = hypot(d[0], d[1]), nx = -d[1] / l, ny = d[0] / l;
        grow(box, b[0] + h * nx, b[1] + h * ny);
        grow(box, b[0] - h * nx, b[1] - h * ny);
    }
    if (!round)
        return;
    for (int e = 0; e < 2; e++) {
        double b[2], d[2];
        curve_at(c, e, b, d);
        double l = hypot(d[0], d[1]), ox = (e ? 1 : -1) * d[0] / l, oy = (e ? 1 : -1) * d[1] / l;
        for (int q = 0; q < 4; q++) {
            double ax = q == 0 ? 1 : q == 2 ? -1 : 0, ay = q == 1 ? 1 : q == 3 ? -1 : 0;
            if (ax * ox + ay * oy >= 0)
                grow(box, b[0] + h * ax, b[1] + h * ay);
        }
    }
}

static void compare(const char *what, const double got[4], const double want[4])
{
    /* got: x0 y0 W H; as corners */
    const double g[4] = {got[0], got[1], got[0] + got[2], got[1] + got[3]};
    print_message("%-24s box     %.12f %.12f %.12f %.12f\n", what, g[0], g[1], g[2], g[3]);
    print_message("%-24s samples %.12f %.12f %.12f %.12f\n", "", want[0], want[1], want[2],
                  want[3]);
    for (int k = 0; k < 4; k++) {
        /* the box holds the samples (to rounding), and passes them by at
         * most the sampling's shortfall */
        double out = k < 2 ? want[k] - g[k] : g[k] - want[k];
        if (!(out >= -1e-12 && out <= 2e-9))
            fail_msg("%s: corner value %d of the box is %.17g, the samples' %.17g", what, k,
                     g[k], want[k]);
    }
}

static void check(const char *what, const char *el, const char *attrs, const curve *c,
                  double w, int round)
{
    double got[4], want[4];
    read_box(el, attrs, got);
    sampled_box(c, w, round, want);
    compare(what, got, want);
}

/* A tight cubic whose inner offset folds (cusps: |k| h > 1 near its
 * turn), butt and round caps; a gentle one; a quarter of an ellipse
 * (rx 20, ry 8: an offset curve, the ellipse not a circle). */
static void test_offset_boxes(void **state)
{
    (void)state;
    const curve tight = {0, {6, 40, 60, 2, -10, 10, 50, 44}};
    check("tight cubic, butt", "path", "d=\"M 6 40 C 60 2 -10 10 50 44\" stroke-width=\"8\"",
          &tight, 8, 0);
    check("tight cubic, round", "path",
          "d=\"M 6 40 C 60 2 -10 10 50 44\" stroke-width=\"8\" stroke-linecap=\"round\"",
          &tight, 8, 1);
    const curve gentle = {0, {4, 30, 20, 10, 40, 50, 58, 30}};
    check("gentle cubic", "path", "d=\"M 4 30 C 20 10 40 50 58 30\" stroke-width=\"3\"",
          &gentle, 3, 0);
    /* the ellipse (32, 30), radii 20 and 8, from angle 0 to pi/2 (SVG's y
     * down: from (52, 30) to (32, 38), the sweep flag 1) */
    const curve quarter = {1, {32, 30, 20, 8, 0, M_PI / 2}};
    check("elliptical arc", "path", "d=\"M 52 30 A 20 8 0 0 1 32 38\" stroke-width=\"6\"",
          &quarter, 6, 0);
}

/* Dashes play no part (SVG 2: "with the assumption that the element has
 * no dash pattern"): a dashed cubic, with pathLength too, whose dashes
 * miss both ends and its turn, has the undashed stroke's box. */
static void test_dashes_ignored(void **state)
{
    (void)state;
    const curve tight = {0, {6, 40, 60, 2, -10, 10, 50, 44}};
    check("dashed cubic", "path",
          "d=\"M 6 40 C 60 2 -10 10 50 44\" stroke-width=\"8\" stroke-dasharray=\"3 7\" "
          "stroke-dashoffset=\"5\"",
          &tight, 8, 0);
    check("dashed, pathLength", "path",
          "d=\"M 6 40 C 60 2 -10 10 50 44\" stroke-width=\"8\" stroke-dasharray=\"1 2\" "
          "pathLength=\"10\"",
          &tight, 8, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offset_boxes),
        cmocka_unit_test(test_dashes_ignored),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
