/*
 * test_bezstroke.c: strokes of Bezier arcs (harness/core/stroke.c, offset
 * curves and evolutes as exact pieces: harness/core/offset.c, AA_PIECE_OFFSET)
 * against answers derived here, independently of the code under test.
 *
 *  - the tube formula: a butt-capped arc whose curvature radius exceeds
 *    half the width everywhere sweeps an area of width x arc length (the
 *    normals do not cross); the arc length here by GSL's QAG (61-point
 *    Gauss-Kronrod, 1e-15 relative), the area by the box reference
 *    (aa_truth_render) of the outline filled into a scene, summed (a white
 *    shape's box reference sums to its area); to 1e-12; and butt dashes on
 *    such an arc: width x the dashes' total length, laid out here from the
 *    arc length;
 *  - a point-in-stroke oracle at random points (seeded), against the
 *    scene's own point query (aa_scene_colour_at: the non-zero winding of
 *    the outline's pieces): for butt caps and one arc, p is in the stroke
 *    iff some t in [0, 1] has p - B(t) perpendicular to B'(t) with
 *    |p - B(t)| <= h (SVG 2's union of the normal segments), the t's found
 *    here as the sign changes of (p - B) . B' at 4000 samples, bisected;
 *    with round joins and caps on a path of several arcs, p is in the
 *    stroke iff its distance to the path is at most h (the nearest point
 *    is inside a segment, on whose normal it lies, or a vertex or an end,
 *    in whose join or cap it lies), the distance found the same way.
 *    Tight arcs whose offsets fold (curvature radius under h), loops,
 *    quadratics, and a map that shears the outline; points within 1e-7 of
 *    the boundary skipped;
 *  - cusps (B' = 0 inside, or at an end whose control point is on it)
 *    against the same oracle with the feet taken on B'/(t - tc) (test_cusp
 *    says how), and the points ahead of a cusp's tip outside; a speed near
 *    0 but not within rounding of it refused, naming it.
 *
 * Under the sanitizers (AA_SANITIZED) a declared subset: a quarter of the
 * random points in each oracle's check (SAN_POINTS); tests/README.md,
 * "Tiers", says how that was checked.
 */
#include "path.h"
#include "oracle.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

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

/* ---- the tube formula ---- */

static void tube(const char *what, const double *c, double w, int n)
{
    /* the formula needs the curvature radius above w/2 everywhere */
    for (int k = 0; k <= 1000; k++)
        assert_true(fabs(oracle_cubic_curvature(c, k / 1000.0)) * 0.5 * w < 0.99);
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    must(aa_path_move_to(&p, c[0], c[1]));
    must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, NULL);
    support_view v = {.w = n, .h = n, .threads = 1};
    aa_image im;
    support_reference(s, &v, &im, NULL, NULL);
    double got = support_channel_mean(&im, 0), want = w * oracle_cubic_length(c, 0, 1);
    print_message("%-24s area %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) < 1e-12))
        fail_msg("%s: area %.17g, want %.17g", what, got, want);
    aa_image_free(&im);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_tube(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double s_curve[8] = {0.15, 0.2, 0.9, 0.25, 0.1, 0.75, 0.85, 0.8};
    tube("gentle S, w 0.05", gentle, 0.05, 64);
    tube("S across, w 0.02", s_curve, 0.02, 64);
}

/* Dashes by arc length: butt dashes on a gentle arc (curvature radius over
 * h) are tubes, so the stroke's area is w times the dashes' total length,
 * counted here from the arc length L (QAG): a pattern (on, off) with
 * offset o covers, of [0, L], the parts of [j P - o, j P - o + on]. */
static void test_dashes(void **state)
{
    (void)state;
    const double c[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double dash[2][3] = {{0.07, 0.03, 0.0}, {0.11, 0.05, 0.04}};
    double L = oracle_cubic_length(c, 0, 1), w = 0.02;
    for (int k = 0; k < 2; k++) {
        double on = dash[k][0], off = dash[k][1], o = dash[k][2], P = on + off, total = 0;
        for (int j = 0; j * P - o < L; j++) {
            double a = fmax(j * P - o, 0), b = fmin(j * P - o + on, L);
            if (b > a)
                total += b - a;
        }
        aa_path p = {0};
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = w;
        st.dash = dash[k];
        st.ndash = 2;
        st.dashoffset = o;
        must(aa_path_move_to(&p, c[0], c[1]));
        must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
        aa_scene *s = scenes_stroke_outline(&p, &st, NULL, NULL);
        support_view v = {.w = 64, .h = 64, .threads = 1};
        aa_image im;
        support_reference(s, &v, &im, NULL, NULL);
        double got = support_channel_mean(&im, 0), want = w * total;
        print_message("dashes %g %g offset %g: area %.15f, want %.15f (%.1e)\n", on, off, o,
                      got, want, got - want);
        if (!(fabs(got - want) < 1e-12))
            fail_msg("dashes: area %.17g, want %.17g", got, want);
        aa_image_free(&im);
        aa_scene_free(s);
        aa_path_free(&p);
    }
}

/* ---- the point-in-stroke oracle ---- */

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static void cubic_at(const void *c, double t, double *x, double *y, double *dx, double *dy)
{
    oracle_cubic_at(c, t, x, y, dx, dy);
}

/* The distances from p to c at the t where p - B(t) is perpendicular to
 * B'(t) (sign changes of g(t) = (p - B) . B' at 4000 samples, bisected),
 * and the ends' too when `ends`; the least of them (butt: only the
 * perpendicular feet, *edge set if p is within tol of an end's normal
 * line's end region, where the oracle is unsure). */
static double feet(const double *c, double px, double py, int ends, double h, int *unsure)
{
    return oracle_curve_feet(cubic_at, c, 0, 1, 4000, px, py, ends, h, unsure);
}

/* The random points a check takes: npts, a quarter of them in the
 * sanitizer build's subset (SAN_SUBSET), where the time is the oracle's
 * own (feet) and the stroke's point query is the code under test */
#define SAN_POINTS(npts) (SAN_SUBSET ? (npts) / 4 : (npts))

/* The oracle's distance to a path of nc chained cubics: the least over
 * its cubics (feet). */
typedef struct path_ctx {
    const double *cs;
    int nc, round;
    double h;
} path_ctx;

static double path_distance(const void *vctx, double px, double py, int *unsure)
{
    const path_ctx *c = vctx;
    double d = INFINITY;
    for (int k = 0; k < c->nc; k++) {
        double q[8] = {c->cs[6 * k], c->cs[6 * k + 1]};
        memcpy(q + 2, c->cs + 2 + 6 * k, 6 * sizeof *q);
        d = fmin(d, feet(q, px, py, c->round, c->h, unsure));
    }
    return d;
}

/* Path of nc cubics (control points chained: 2 + 6 nc numbers), stroked at
 * width w (butt and one cubic, or round joins and caps), the outline
 * filled through map m (NULL: none; the oracle at the preimage). */
static void oracle(const char *what, const double *cs, int nc, double w, int round, const double *m,
                   int npts)
{
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (round)
        st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    must(aa_path_move_to(&p, cs[0], cs[1]));
    for (int k = 0; k < nc; k++) {
        const double *q = cs + 2 + 6 * k;
        must(aa_path_cubic_to(&p, q[0], q[1], q[2], q[3], q[4], q[5]));
    }
    aa_scene *s = scenes_stroke_outline(&p, &st, m, NULL);
    double h = 0.5 * w, x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 2 + 6 * nc; k += 2) {
        x0 = fmin(x0, cs[k]), x1 = fmax(x1, cs[k]);
        y0 = fmin(y0, cs[k + 1]), y1 = fmax(y1, cs[k + 1]);
    }
    const double box[4] = {x0 - 2 * h, y0 - 2 * h, x1 + 2 * h, y1 + 2 * h};
    const path_ctx ctx = {cs, nc, round, h};
    support_stroke_check(what, s, box, h, m, SAN_POINTS(npts), &rng, path_distance, &ctx);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_oracle_butt(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double tight[8] = {0.2, 0.2, 0.9, 0.3, 0.9, 0.7, 0.25, 0.75};
    const double loop[8] = {0.2, 0.8, 0.9, 0.1, 0.1, 0.1, 0.8, 0.8};
    const double hook[8] = {0.1, 0.9, 0.1, 0.1, 0.9, 0.1, 0.55, 0.5};
    oracle("gentle, w 0.05", gentle, 1, 0.05, 0, NULL, 3000);
    oracle("gentle, w 0.6 (folds)", gentle, 1, 0.6, 0, NULL, 3000);
    oracle("tight, w 0.3 (folds)", tight, 1, 0.3, 0, NULL, 3000);
    oracle("tight, w 1.0 (folds)", tight, 1, 1.0, 0, NULL, 3000);
    oracle("loop, w 0.12", loop, 1, 0.12, 0, NULL, 3000);
    oracle("loop, w 0.5 (folds)", loop, 1, 0.5, 0, NULL, 3000);
    oracle("hook, w 0.4 (folds)", hook, 1, 0.4, 0, NULL, 3000);
    const double shear[6] = {1.5, 0.2, 0.7, 0.9, 0.1, -0.05};
    oracle("tight, w 0.3, sheared", tight, 1, 0.3, 0, shear, 3000);
}

static void test_oracle_round(void **state)
{
    (void)state;
    const double path[20] = {0.1, 0.5, 0.3, 0.1,  0.5, 0.1,  0.6, 0.4, 0.7, 0.9,
                             0.2, 0.6, 0.5, 0.5, 0.95, 0.2, 0.9, 0.8, 0.6, 0.85};
    oracle("3 cubics, round, w 0.08", path, 3, 0.08, 1, NULL, 3000);
    oracle("3 cubics, round, w 0.4", path, 3, 0.4, 1, NULL, 3000);
    for (int r = 0; r < 6; r++) {
        double cs[14];
        for (int k = 0; k < 14; k++)
            cs[k] = 0.1 + 0.8 * support_xorshift(&rng);
        char name[64];
        double w = 0.02 + 0.4 * support_xorshift(&rng);
        snprintf(name, sizeof name, "random pair %d, w %.3f", r, w);
        oracle(name, cs, 2, w, 1, NULL, 2000);
    }
}

static void test_quadratic(void **state)
{
    (void)state;
    /* a quadratic is its cubic with controls at 2/3 of the way to its control point */
    aa_path p = {0}, q = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.3;
    must(aa_path_move_to(&p, 0.1, 0.8));
    must(aa_path_quad_to(&p, 0.5, 0.0, 0.9, 0.8));
    must(aa_path_move_to(&q, 0.1, 0.8));
    must(aa_path_cubic_to(&q, 0.1 + 2.0 / 3 * 0.4, 0.8 - 2.0 / 3 * 0.8, 0.9 - 2.0 / 3 * 0.4,
                          0.8 - 2.0 / 3 * 0.8, 0.9, 0.8));
    aa_scene *a = scenes_stroke_outline(&p, &st, NULL, NULL);
    aa_scene *b = scenes_stroke_outline(&q, &st, NULL, NULL);
    int differ = 0;
    for (int i = 0; i < 4000; i++) {
        double x = support_xorshift(&rng), y = support_xorshift(&rng);
        differ += aa_scene_colour_at(a, x, y).c[0] != aa_scene_colour_at(b, x, y).c[0];
    }
    /* points within rounding of the boundary may differ: none at random */
    assert_int_equal(differ, 0);
    aa_scene_free(a);
    aa_scene_free(b);
    aa_path_free(&p);
    aa_path_free(&q);
}

/* ---- cusps ----
 *
 * Where B' vanishes SVG 2's stroke is still the union of the normal
 * segments, the normal at the cusp the limit of those beside it (the same
 * line from both sides), with no join there (joins are at segment
 * boundaries only) and, at an end whose control point is on it, a cap in
 * the direction of the next distinct control point.  The oracle: a cubic
 * whose B'(t) = (t - tc) Q(t) with Q known here in closed form has its
 * feet where G(t) = (p - B(t)) . Q(t) changes sign (G has no root at tc
 * for points off the limit normal, unlike (p - B) . B'), p in the stroke
 * iff some foot is within h (with round caps: or an end is).  The cubics:
 *  - (0,0) (1,1) (0,1) (1,0) scaled by S about o: B'x = 3 S (1 - 2t)^2,
 *    B'y = 3 S (1 - 2t), so Q = S (3 (1 - 2t), 3) (times -1/2, whose sign
 *    does not matter), a cusp at t = 1/2 pointing up, tangent (0, -1)
 *    on both sides there;
 *  - P1 = P0: B' = 3 t (2 (1 - t) (P2 - P1) + t (P3 - P2)) = t Q. */
typedef struct cusp_cubic {
    double c[8];
    int kind; /* 0: the cusp family, 1: P1 = P0 */
    double S;
} cusp_cubic;

static void cusp_q(const cusp_cubic *k, double t, double *qx, double *qy)
{
    const double *c = k->c;
    if (k->kind == 0) {
        *qx = k->S * 3 * (1 - 2 * t), *qy = k->S * 3;
    } else {
        *qx = 3 * (2 * (1 - t) * (c[4] - c[2]) + t * (c[6] - c[4]));
        *qy = 3 * (2 * (1 - t) * (c[5] - c[3]) + t * (c[7] - c[5]));
    }
}

/* The cusp cubic's point, and B'/(t - tc) as its direction (cusp_q). */
static void cusp_at(const void *vk, double t, double *x, double *y, double *dx, double *dy)
{
    const cusp_cubic *k = vk;
    double ux, uy;
    oracle_cubic_at(k->c, t, x, y, &ux, &uy);
    cusp_q(k, t, dx, dy);
}

static double cusp_feet(const cusp_cubic *k, double px, double py, int round, double h,
                        int *unsure)
{
    return oracle_curve_feet(cusp_at, k, 0, 1, 4000, px, py, round, h, unsure);
}

typedef struct cusp_ctx {
    const cusp_cubic *k;
    int round;
    double h;
} cusp_ctx;

static double cusp_distance(const void *vctx, double px, double py, int *unsure)
{
    const cusp_ctx *c = vctx;
    return cusp_feet(c->k, px, py, c->round, c->h, unsure);
}

static void cusp_oracle(const char *what, const cusp_cubic *k, double w, int round, const double *m,
                        int npts)
{
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (round)
        st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    const double *c = k->c;
    must(aa_path_move_to(&p, c[0], c[1]));
    must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
    aa_scene *s = scenes_stroke_outline(&p, &st, m, NULL);
    double h = 0.5 * w, x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int j = 0; j < 8; j += 2) {
        x0 = fmin(x0, c[j]), x1 = fmax(x1, c[j]);
        y0 = fmin(y0, c[j + 1]), y1 = fmax(y1, c[j + 1]);
    }
    const double box[4] = {x0 - 2 * h, y0 - 2 * h, x1 + 2 * h, y1 + 2 * h};
    const cusp_ctx ctx = {k, round, h};
    support_stroke_check(what, s, box, h, m, SAN_POINTS(npts), &rng, cusp_distance, &ctx);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_cusp(void **state)
{
    (void)state;
    const double S = 0.6, o[2] = {0.2, 0.25};
    cusp_cubic k = {{o[0], o[1], o[0] + S, o[1] + S, o[0], o[1] + S, o[0] + S, o[1]}, 0, S};
    const double shear[6] = {1.5, 0.2, 0.7, 0.9, 0.1, -0.05};
    cusp_oracle("cusp, butt, w 0.05", &k, 0.05, 0, NULL, 4000);
    cusp_oracle("cusp, butt, w 0.3 (folds)", &k, 0.3, 0, NULL, 4000);
    cusp_oracle("cusp, round, w 0.2", &k, 0.2, 1, NULL, 4000);
    cusp_oracle("cusp, butt, w 0.2, sheared", &k, 0.2, 0, shear, 4000);
    cusp_cubic e = {{0.2, 0.8, 0.2, 0.8, 0.9, 0.7, 0.6, 0.2}, 1, 0};
    cusp_oracle("P1 = P0, butt, w 0.1", &e, 0.1, 0, NULL, 4000);
    cusp_oracle("P1 = P0, round, w 0.4 (folds)", &e, 0.4, 1, NULL, 4000);
}

/* A cusp's tip: the points just ahead of it, within h of the cusp but on
 * no normal, are outside (no join, no cap there); those on the limit
 * normal's line through it, inside. */
static void test_cusp_tip(void **state)
{
    (void)state;
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.1;
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    must(aa_path_move_to(&p, 0.2, 0.25));
    must(aa_path_cubic_to(&p, 0.8, 0.85, 0.2, 0.85, 0.8, 0.25));
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, NULL);
    /* the cusp B(1/2) = (0.5, 0.7), its tangent (0, 1) arriving: ahead is y > 0.7 */
    assert_true(aa_scene_colour_at(s, 0.5, 0.72).c[0] < 0.5);
    assert_true(aa_scene_colour_at(s, 0.5, 0.74).c[0] < 0.5);
    assert_true(aa_scene_colour_at(s, 0.47, 0.7 - 1e-9).c[0] > 0.5);
    assert_true(aa_scene_colour_at(s, 0.53, 0.7 - 1e-9).c[0] > 0.5);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_near_cusp_refused(void **state)
{
    (void)state;
    aa_path p = {0}, out = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    /* the cusp family with its middle control points 1e-10 apart in x: the
     * least speed is about 1e-10 of the size, neither a zero nor clear of one */
    must(aa_path_move_to(&p, 0, 0));
    must(aa_path_cubic_to(&p, 1, 1, 1e-10, 1, 1, 0));
    assert_int_equal(aa_stroke_outline(&p, &st, &out), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "near a cusp"));
    assert_int_equal(out.n, 0);
    aa_path_free(&p);
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_tube),
                                       cmocka_unit_test(test_dashes),
                                       cmocka_unit_test(test_oracle_butt),
                                       cmocka_unit_test(test_oracle_round),
                                       cmocka_unit_test(test_quadratic),
                                       cmocka_unit_test(test_cusp),
                                       cmocka_unit_test(test_cusp_tip),
                                       cmocka_unit_test(test_near_cusp_refused)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
