/*
 * test_area_offset.c: `area` (algorithms/area.c, area_offset.c) on strokes
 * of Bezier arcs, whose outlines hold offset curves and evolutes
 * (AA_PIECE_OFFSET), against answers it does not compute itself:
 *
 *  - the box reference (harness/truth, its own integration of the same
 *    pieces: scanline crossings, then QAG over y), to 1e-12 per pixel, on
 *    a gentle arc, tight arcs whose offsets fold, a loop, a hook, three
 *    arcs with round joins and caps at two widths, dashes, a shear, and
 *    cusps (inside, and a control point on the start);
 *    with both integrators, and the same image on one thread and on two;
 *  - the tube formula: a butt-capped arc whose curvature radius exceeds
 *    half the width everywhere covers width x arc length (the normals do
 *    not cross), the arc length by GSL's QAG (61-point Gauss-Kronrod,
 *    1e-13); `area`'s image summed (a white shape's box image sums to its
 *    area), to 1e-12, and the same on dashes laid out here from the arc
 *    length;
 *  - the meetings `area` cuts its bands at (aa_piece_meet, whose pairs
 *    running side by side are decided by their slopes): every sign change
 *    of x_p - x_q seen at 400 heights over two pieces' common height, on
 *    every pair of a stroke's pieces with an offset piece, holds a meeting
 *    aa_piece_meet reports (ends shared by the two pieces aside);
 *  - a crossing's root near a turn of the offset's y: y at the parameter
 *    aa__offset_root returns is the line's, to rounding.
 */
#include "path.h"
#include "oracle.h"
#include "scenes.h"
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

static void must(int st)
{
    if (st)
        fail_msg("status %d: %s", st, aa_last_error());
}

/* The stroke of nc chained cubics cs (2 + 6 nc numbers), filled white on
 * black through map m (NULL: none). */
static aa_scene *stroke_scene(const double *cs, int nc, const aa_stroke_style *st,
                              const double *m)
{
    aa_path in = {0};
    must(aa_path_move_to(&in, cs[0], cs[1]));
    for (int k = 0; k < nc; k++) {
        const double *q = cs + 2 + 6 * k;
        must(aa_path_cubic_to(&in, q[0], q[1], q[2], q[3], q[4], q[5]));
    }
    size_t noff;
    aa_scene *s = scenes_stroke_outline(&in, st, m, &noff);
    assert_true(noff > 0); /* the case is about offset pieces */
    aa_path_free(&in);
    return s;
}

/* `area` (both integrators, one and two threads) against the reference. */
static void against_reference(const char *what, const double *cs, int nc,
                              const aa_stroke_style *st, const double *m, int n)
{
    aa_scene *s = stroke_scene(cs, nc, st, m);
    support_view v = {.w = n, .h = n, .threads = 0};
    aa_image ref, a1, a2, bands;
    support_reference(s, &v, &ref, NULL, NULL);
    support_render("area", s, "box", n, n, 1, &a1, NULL);
    support_render("area", s, "box", n, n, 2, &a2, NULL);
    support_render("area:integrator=bands", s, "box", n, n, 1, &bands, NULL);
    int wi, wj;
    double e = support_max_diff(&a1, &ref, &wi, &wj), eb = support_max_diff(&bands, &ref, NULL, NULL);
    print_message("%-34s max |area - reference| %.1e (at %d,%d), bands %.1e\n", what, e, wi, wj,
                  eb);
    if (!(e < 1e-12) || !(eb < 1e-12))
        fail_msg("%s: area off the reference by %g (bands %g)", what, e, eb);
    assert_true(support_same_image(&a1, &a2));
    aa_image_free(&ref);
    aa_image_free(&a1);
    aa_image_free(&a2);
    aa_image_free(&bands);
    aa_scene_free(s);
}

static void test_reference(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double tight[8] = {0.2, 0.2, 0.9, 0.3, 0.9, 0.7, 0.25, 0.75};
    const double loop[8] = {0.2, 0.8, 0.9, 0.1, 0.1, 0.1, 0.8, 0.8};
    const double hook[8] = {0.1, 0.9, 0.1, 0.1, 0.9, 0.1, 0.55, 0.5};
    const double three[20] = {0.1, 0.5, 0.3, 0.1,  0.5, 0.1,  0.6, 0.4, 0.7, 0.9,
                              0.2, 0.6, 0.5, 0.5, 0.95, 0.2, 0.9, 0.8, 0.6, 0.85};
    const double shear[6] = {1.3, 0.2, 0.5, 0.8, -0.1, -0.05};
    const double dash[2] = {0.07, 0.03};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    against_reference("gentle, w 0.05", gentle, 1, &st, NULL, 64);
    st.width = 0.3;
    against_reference("tight, w 0.3 (folds)", tight, 1, &st, NULL, 64);
    against_reference("tight, w 0.3, sheared", tight, 1, &st, shear, 64);
    st.width = 1.0;
    against_reference("tight, w 1.0 (folds)", tight, 1, &st, NULL, 48);
    st.width = 0.5;
    against_reference("loop, w 0.5 (folds)", loop, 1, &st, NULL, 64);
    st.width = 0.4;
    against_reference("hook, w 0.4 (folds)", hook, 1, &st, NULL, 64);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 0.08;
    against_reference("3 arcs, round, w 0.08", three, 3, &st, NULL, 64);
    st.width = 0.4;
    against_reference("3 arcs, round, w 0.4", three, 3, &st, NULL, 48);
    st.join = AA_JOIN_MITER, st.cap = AA_CAP_SQUARE;
    st.width = 0.03;
    st.dash = dash, st.ndash = 2;
    against_reference("3 arcs, miter, square dashes", three, 3, &st, NULL, 64);
    /* cusps: B'(1/2) = 0 inside; a first control point on the start */
    const double cusp[8] = {0.2, 0.25, 0.8, 0.85, 0.2, 0.85, 0.8, 0.25};
    const double stop[8] = {0.2, 0.8, 0.2, 0.8, 0.9, 0.7, 0.6, 0.2};
    aa_stroke_style_default(&st);
    st.width = 0.1;
    against_reference("cusp, w 0.1", cusp, 1, &st, NULL, 64);
    st.width = 0.3;
    against_reference("cusp, w 0.3, sheared", cusp, 1, &st, shear, 48);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.dash = dash, st.ndash = 2;
    against_reference("cusp, round dashes, w 0.05", cusp, 1, &st, NULL, 64);
    st.dash = NULL, st.ndash = 0, st.width = 0.4;
    against_reference("P1 = P0, round, w 0.4", stop, 1, &st, NULL, 48);
}

/* ---- the tube formula ---- */

static void tube(const char *what, const double *c, double w, const double *dash, double off,
                 int n)
{
    for (int k = 0; k <= 1000; k++) /* the curvature radius above w/2 */
        assert_true(fabs(oracle_cubic_curvature(c, k / 1000.0)) * 0.5 * w < 0.99);
    double L = oracle_cubic_length(c, 0, 1), len = L;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (dash) {
        /* dash j covers [j P - off, j P - off + on] of [0, L] */
        double P = dash[0] + dash[1];
        len = 0;
        for (int j = 0; j * P - off < L; j++) {
            double a = fmax(j * P - off, 0), b = fmin(j * P - off + dash[0], L);
            if (b > a)
                len += b - a;
        }
        st.dash = dash, st.ndash = 2, st.dashoffset = off;
    }
    aa_scene *s = stroke_scene(c, 1, &st, NULL);
    aa_image im;
    support_render("area", s, "box", n, n, 1, &im, NULL);
    double got = support_channel_mean(&im, 0), want = w * len;
    print_message("%-34s area %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) < 1e-12))
        fail_msg("%s: area %.17g, want %.17g", what, got, want);
    aa_image_free(&im);
    aa_scene_free(s);
}

static void test_tube(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double s_curve[8] = {0.15, 0.2, 0.9, 0.25, 0.1, 0.75, 0.85, 0.8};
    const double dash[2] = {0.11, 0.05};
    tube("gentle S, w 0.05, 64 px", gentle, 0.05, NULL, 0, 64);
    tube("gentle S, w 0.05, 256 px", gentle, 0.05, NULL, 0, 256);
    tube("S across, w 0.02, 200 px", s_curve, 0.02, NULL, 0, 200);
    tube("S across, w 0.02, dashes", s_curve, 0.02, dash, 0.04, 128);
}

/* ---- meetings against sampled sign changes ---- */

static int meetings(const char *what, const double *cs, int nc, const aa_stroke_style *st)
{
    aa_scene *s = stroke_scene(cs, nc, st, NULL);
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int pairs = 0, changes = 0, missed = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            if (!p->dir || !q->dir ||
                (p->kind != AA_PIECE_OFFSET && q->kind != AA_PIECE_OFFSET))
                continue;
            double lo = fmax(p->y0, q->y0), hi = fmin(p->y1, q->y1), ys[16];
            if (!(lo < hi) || p->xmax < q->xmin || q->xmax < p->xmin)
                continue;
            pairs++;
            int m = aa_piece_meet(p, q, lo, hi, ys, 16);
            double prev = NAN, yprev = lo;
            for (int j = 1; j < 400; j++) { /* inner heights: shared ends aside */
                double y = lo + (hi - lo) * j / 400.0;
                double d = aa_piece_x_at(p, y) - aa_piece_x_at(q, y);
                if (fabs(d) < 1e-9) {
                    prev = NAN; /* too near a meeting to tell its side */
                    continue;
                }
                if (prev == prev && (prev < 0) != (d < 0)) {
                    changes++;
                    int found = 0;
                    for (int r = 0; r < m; r++)
                        found |= ys[r] >= yprev - 1e-9 && ys[r] <= y + 1e-9;
                    if (!found && missed++ < 5)
                        print_message("%s: pieces %zu, %zu change sides in [%.17g, %.17g], "
                                      "not met\n",
                                      what, i, k, yprev, y);
                }
                prev = d, yprev = y;
            }
        }
    print_message("%-34s %d pairs, %d sign changes sampled, %d not met\n", what, pairs,
                  changes, missed);
    assert_int_equal(missed, 0);
    aa_scene_free(s);
    return changes;
}

static void test_meetings(void **state)
{
    (void)state;
    const double three[20] = {0.1, 0.5, 0.3, 0.1,  0.5, 0.1,  0.6, 0.4, 0.7, 0.9,
                              0.2, 0.6, 0.5, 0.5, 0.95, 0.2, 0.9, 0.8, 0.6, 0.85};
    const double tight[8] = {0.2, 0.2, 0.9, 0.3, 0.9, 0.7, 0.25, 0.75};
    /* smooth joins: the offsets of consecutive arcs run side by side */
    const double wave[20] = {0.05, 0.5, 0.15, 0.45, 0.25, 0.45, 0.35, 0.5, 0.45, 0.55,
                             0.55, 0.55, 0.65, 0.5, 0.75, 0.45, 0.85, 0.45, 0.95, 0.5};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    int changes = 0;
    st.width = 0.08;
    changes += meetings("3 arcs, round, w 0.08", three, 3, &st);
    st.width = 0.01;
    changes += meetings("wave, round, w 0.01", wave, 3, &st);
    st.width = 0.06;
    changes += meetings("wave, round, w 0.06", wave, 3, &st);
    st.join = AA_JOIN_MITER, st.cap = AA_CAP_BUTT;
    st.width = 0.3;
    changes += meetings("tight, w 0.3 (folds)", tight, 1, &st);
    assert_true(changes > 0); /* the oracle saw crossings */
}

/* A crossing of an offset curve is the root of y(t) = v: whatever path the
 * solver takes, the offset's y at the parameter it returns must be v to
 * long double's rounding of the coordinates (the equation itself is the
 * oracle, through the same evaluation of the curve, not the solver).  The
 * case: the left offset (d = 0.05) of the `tight` cubic below at 64 px,
 * crossed by the line y = 44.89 over a bracket near a turn of its y, where
 * Newton's steps in long double left the bracket or landed on its ends and
 * a solver that stopped after 8 of them returned y 1.4e-5 px off (up to
 * 3.5e-4 px in other calls the stroke tests make). */
static void test_root(void **state)
{
    (void)state;
    aa_offset_curve oc = {{0x1.999999999999ap-3, 0x1.cccccccccccc9p-1, -0x1.cccccccccccc5p-1,
                           0x1.333333333332bp-2, 0x1p-2, 0x1.cccccccccccc8p-1,
                           -0x1.cccccccccccc3p-2, 0},
                          {64, 0, 0, 64, 0, 0},
                          0.05,
                          0,
                          AA_OFFSET_CUBIC};
    const long double ta = 0x1.8a8d304019cdp-1, tb = 0x1.e3af7fdeab36ap-1;
    const long double target = 0xb.38df1a0932d3p+2L;
    long double X, Y, DX, DY, other;
    aa__offset_eval(&oc, ta, &X, &Y, &DX, &DY);
    const long double fa = Y - target;
    aa__offset_eval(&oc, tb, &X, &Y, &DX, &DY);
    assert_true((fa < 0) != (Y - target < 0)); /* a bracket */
    double slope;
    long double t = aa__offset_root(&oc, 1, ta, tb, fa, target, NAN, &other, &slope);
    aa__offset_eval(&oc, t, &X, &Y, &DX, &DY);
    print_message("root t %.21Lg: y - v = %.3Lg px, x %.17Lg (other %.17Lg)\n", t, Y - target,
                  X, other);
    assert_true(t >= ta && t <= tb);
    assert_true(fabsl(Y - target) <= 1e-15L);
    assert_true(fabsl(X - other) <= 1e-12L);
}

/* aa__offset_eval_s given aa__offset_stops (the curve's stops found once)
 * against aa__offset_eval, which asks aa__offset_stop at every evaluation:
 * the same point and derivative, bit for bit, and the same point without
 * the derivative.  The stops expected by construction: a cubic whose
 * first control point lies on its start has B'(0) = 0 (bit 0), one whose
 * last lies on its end B'(1) = 0 (bit 1), as test_root's cubic's (B'(1) =
 * (0.9 - 1.8 + 0.9, 0.9 - 0.9)); a cubic without and an ellipse have
 * none. */
static void test_stops(void **state)
{
    (void)state;
    /* power basis x: b[0..3], y: b[4..7]; P0 = P1 = (0, 0), P2 = (1, 1),
     * P3 = (2, 0); the same reversed; test_root's cubic; P = (0, 0), (1,
     * 2), (2, -1), (3, 0); an ellipse (centre, u, v) */
    static const double bs[5][8] = {{0, 0, 3, -1, 0, 0, 3, -3},
                                    {2, -3, 0, 1, 0, 3, -6, 3},
                                    {0x1.999999999999ap-3, 0x1.cccccccccccc9p-1,
                                     -0x1.cccccccccccc5p-1, 0x1.333333333332bp-2, 0x1p-2,
                                     0x1.cccccccccccc8p-1, -0x1.cccccccccccc3p-2, 0},
                                    {0, 3, 0, 0, 0, 6, -15, 9},
                                    {0.5, 0.5, 0.3, 0.1, -0.05, 0.2, 0, 0}};
    static const int want[5] = {1, 2, 2, 0, 0};
    static const double maps[2][6] = {{64, 0, 0, 64, 0, 0}, {64, 5, -7, 60, 3, 2}};
    for (int c = 0; c < 5; c++)
        for (int e = 0; e < 2; e++)
            for (int k = 0; k < 2; k++) {
                aa_offset_curve oc;
                memset(&oc, 0, sizeof oc);
                memcpy(oc.b, bs[c], sizeof oc.b);
                memcpy(oc.m, maps[k], sizeof oc.m);
                oc.d = 0.1;
                oc.evolute = e;
                oc.base = c == 4 ? AA_OFFSET_ELLIPSE : AA_OFFSET_CUBIC;
                int stops = aa__offset_stops(&oc);
                double te, q[4];
                assert_int_equal(stops, want[c]);
                assert_int_equal(stops & 1, aa__offset_stop(&oc, 0.25, &te, q));
                assert_int_equal(stops >> 1, aa__offset_stop(&oc, 0.75, &te, q));
                for (int i = 0; i <= 66; i++) {
                    long double t = i <= 64 ? i / 64.0L : (i == 65 ? 0.5L - 0x1p-40L : 0x1p-30L);
                    if (c < 4 && e && (t == 0 || t == 1))
                        continue; /* an evolute's point at a stop is 0/0 in the plain form */
                    long double x0, y0, dx0, dy0, x1, y1, dx1, dy1, x2, y2;
                    aa__offset_eval(&oc, t, &x0, &y0, &dx0, &dy0);
                    aa__offset_eval_s(&oc, stops, t, &x1, &y1, &dx1, &dy1);
                    aa__offset_eval_s(&oc, stops, t, &x2, &y2, NULL, NULL);
                    assert_true(x0 == x1 && y0 == y1 && dx0 == dx1 && dy0 == dy1);
                    assert_true(x0 == x2 && y0 == y2);
                }
            }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_reference),
                                       cmocka_unit_test(test_tube),
                                       cmocka_unit_test(test_meetings),
                                       cmocka_unit_test(test_root),
                                       cmocka_unit_test(test_stops)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
