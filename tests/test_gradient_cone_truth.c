/*
 * test_gradient_cone_truth.c: the exact reference of radial gradients of
 * the cone case (the focal circle not strictly inside the end circle;
 * harness/truth/truth.c, "the cone case") under the box filter, and what
 * it refuses by name.
 *
 * Known answers, derived here and not from the code under test:
 *  - the painted region's area: a gradient whose stops are all white, over
 *    black, paints 1 where some circle of radius >= 0 passes (SVG 2,
 *    13.3.5 radialGradient) and leaves the background 0 elsewhere, so the
 *    box reference of a pixel is the area of the painted region inside its
 *    square.  That region, derived from the circles' geometry: with r >
 *    fr, the wedge from the external centre of similitude P = (r F - fr
 *    C) / (r - fr) (where every circle's radius shrinks to 0) opening
 *    towards C, bounded by the two external tangents of the circles,
 *    whose half-angle is asin((r - fr) / |C - F|) (with |C - F| = |r -
 *    fr|, the circles touching inside, both are the line through P
 *    perpendicular to F C, and the region the half-plane beyond it); with
 *    r = fr the strip of half-width r about the line F C; with the end
 *    circle strictly inside the focal circle, the whole plane.  The area is the square
 *    clipped by the bounding half-planes (Sutherland-Hodgman), by the
 *    shoelace formula;
 *  - single pixels by GSL's adaptive quadrature in two dimensions (outer
 *    rows, inner along the row), the picture from SVG 2's definition: t
 *    the largest root, of radius fr + t dr >= 0, of |q - F - t D| = fr + t
 *    dr (squared, in long double), a black-to-white ramp padded, decoded
 *    by sRGB's curve (tests/gradient_oracle.c, go_dec), the background
 *    where no root qualifies.  Inner cuts: the row's crossings of the
 *    tangents (from the construction above), of the circles t = 0,
 *    0.04045 and 1, and P's column; outer cuts: P's row, the tangents'
 *    and circles' crossings of the pixel's sides, the circles' top and
 *    bottom rows, and where each circle touches each tangent.  Pixels
 *    straddling one tangent or both, holding P, a circle's end on a
 *    tangent, the threshold's arc.
 * Each pixel must lie within its own bound of the answer (plus the
 * quadrature's 1e-14), and every bound within 1e-12.
 */
#include "cone_oracle.h"
#include "core.h"
#include "gradient_oracle.h"
#include "support.h"
#include "tier.h"
#include "truth.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#define W 16
#define H 12

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return 0;
}

/* A scene of one layer over [-8, W + 8] x [-8, H + 8] (pixels) painted
 * by the radial gradient p[] (cx cy r fx fy fr, in pixels) with stops st,
 * over background bg. */
static aa_scene *grad_scene(const double p[6], int spread, const aa_gradient_stop *st, int n,
                            double bg)
{
    aa_scene *s = aa_scene_new((aa_rgb){{bg, bg, bg}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, -8.0 / W, -8.0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, (W + 8.0) / W, -8.0 / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, (W + 8.0) / W, (H + 8.0) / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, -8.0 / W, (H + 8.0) / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    aa_gradient g = {AA_GRADIENT_RADIAL, spread, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0}, n, st};
    memcpy(g.p, p, sizeof g.p);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static const aa_gradient_stop white[2] = {{0.0, {{1, 1, 1}}, 1.0}, {1.0, {{1, 1, 1}}, 1.0}};
static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};

/* ---- the painted region from the circles' geometry (tests/cone_oracle.c) ---- */

/* The area of the square [i, i + 1] x [j, j + 1] inside the half-planes. */
static double clipped_area(int i, int j, const co_half *hp, int nh)
{
    return co_clipped_area(i, j, i + 1, j + 1, hp, nh);
}

static void check_area(const char *what, const double p[6])
{
    aa_scene *s = grad_scene(p, AA_SPREAD_PAD, white, 2, 0.0);
    aa_image ref, bound;
    aa_truth_stats stats;
    support_view v = {W, H, 0, 0, 0, "box", 1, 1, 0};
    support_reference(s, &v, &ref, &bound, &stats);
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(p, hp, &wedge, apex);
    double worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double want = clipped_area(i, j, hp, nh), got = aa_pixel(&ref, i, j)[0];
            double bd = *aa_pixel(&bound, i, j);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-16 && bd <= 1e-12))
                fail_msg("%s: pixel (%d, %d) is %.17g, the painted area %.17g (bound %.3g)", what,
                         i, j, got, want, bd);
        }
    print_message("%-34s %d pixels, largest difference from the area %.2g, largest bound "
                  "%.2g\n",
                  what, W * H, worst, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* White stops over black: the reference is the painted area. */
static void test_area(void **state)
{
    (void)state;
    /* the wedge opening right (r > fr), from P = (0.16, 4.63) */
    check_area("wedge, r > fr", (const double[6]){9.3, 6.1, 3.1, 3.7, 5.2, 1.2});
    /* opening left and down, P right of the picture (fr > r, the focal
     * circle the larger) */
    check_area("wedge, fr > r", (const double[6]){5.2, 7.9, 1.1, 12.4, 3.3, 3.9});
    /* fr = 0 with the focus outside the end circle: P is the focus */
    check_area("wedge, fr = 0", (const double[6]){10.6, 5.3, 2.7, 3.45, 6.55, 0.0});
    /* equal radii: the strip, oblique */
    check_area("strip, r = fr", (const double[6]){11.2, 8.3, 2.35, 4.1, 3.3, 2.35});
    /* the end circle inside the focal one: everything painted */
    check_area("nested, fr > r + |C - F|", (const double[6]){8.2, 6.3, 1.5, 7.6, 5.9, 6.0});
    /* the circles touching inside (|C - F| = |r - fr|): both tangents are
     * the line through P perpendicular to F C, the half-plane beyond it
     * painted; the focus on the end circle (D = (3, 4), r = 5), the focal
     * circle inside touching (P = (3, 6)), and the end circle inside the
     * focal one touching it (P = (3, 6), painted x > 3) */
    check_area("half-plane, fr = 0", (const double[6]){10.5, 8.25, 5.0, 7.5, 4.25, 0.0});
    check_area("half-plane, fr < r", (const double[6]){8.0, 6.0, 5.0, 6.0, 6.0, 3.0});
    check_area("half-plane, fr > r", (const double[6]){6.0, 6.0, 3.0, 8.0, 6.0, 5.0});
}

/* ---- single pixels against 2-D quadrature ---- */

#define MAX_TAUS 200
typedef struct pic {
    double p[6], bg;
    int spread, ntaus;
    double taus[MAX_TAUS]; /* where the spread ramp's derivatives jump */
    co_half hp[2];
    int nh, wedge;
    double apex[2];
    double y, xlo, xhi;
    gsl_integration_workspace *wi;
} pic;

/* t from SVG 2's definition (the opening comment), NAN where none. */
static double pic_t(const pic *pc, double x, double y)
{
    return co_t(pc->p, x, y);
}

static double pic_at(const pic *pc, double x, double y)
{
    double t = pic_t(pc, x, y);
    if (isnan(t))
        return pc->bg;
    if (pc->spread == AA_SPREAD_REPEAT)
        return go_dec(t - floor(t));
    if (pc->spread == AA_SPREAD_REFLECT) {
        double f = t - 2 * floor(t / 2);
        return go_dec(f <= 1 ? f : 2 - f);
    }
    return go_dec(t < 0 ? 0 : t > 1 ? 1 : t);
}

static double pic_x(double x, void *v)
{
    const pic *pc = v;
    return pic_at(pc, x, pc->y);
}

/* Where the circle t = tau meets the line x = at (col) or y = at. */
static int circle_meet(const pic *pc, double tau, int col, double at, double *out)
{
    return co_circle_meet(pc->p, tau, col, at, out);
}

/* Where the half-plane k's line meets the line x = at (col) or y = at. */
static int line_meet(const pic *pc, int k, int col, double at, double *out)
{
    return co_line_meet(&pc->hp[k], col, at, out);
}

static double pic_y(double y, void *v)
{
    pic *pc = v;
    pc->y = y;
    double cut[2 * MAX_TAUS + 8];
    int n = 0;
    for (int k = 0; k < pc->nh; k++)
        n += line_meet(pc, k, 0, y, cut + n);
    for (int q = 0; q < pc->ntaus; q++)
        n += circle_meet(pc, pc->taus[q], 0, y, cut + n);
    if (pc->wedge)
        cut[n++] = pc->apex[0];
    cut[n++] = pc->xlo, cut[n++] = pc->xhi;
    gsl_function F = {pic_x, pc};
    return go_qags_cuts(&F, cut, n, pc->xlo, pc->xhi, 1e-16, 1e-14, pc->wi);
}

/* The box reference of pixel (i, j) by 2-D quadrature. */
static double pic_pixel(pic *pc, int i, int j)
{
    const double *p = pc->p;
    double cut[7 * MAX_TAUS + 16];
    int n = 0;
    pc->xlo = i, pc->xhi = i + 1;
    cut[n++] = j, cut[n++] = j + 1;
    if (pc->wedge)
        cut[n++] = pc->apex[1];
    for (int k = 0; k < pc->nh; k++)
        for (int e = 0; e < 2; e++)
            n += line_meet(pc, k, 1, i + e, cut + n);
    for (int q = 0; q < pc->ntaus; q++) {
        double tau = pc->taus[q], rr = p[5] + tau * (p[2] - p[5]);
        double ccy = p[4] + tau * (p[1] - p[4]);
        if (rr < 0)
            continue;
        cut[n++] = ccy - rr, cut[n++] = ccy + rr;
        for (int e = 0; e < 2; e++)
            n += circle_meet(pc, tau, 1, i + e, cut + n);
        /* where it touches each bounding line: the foot of the
         * perpendicular from its centre */
        for (int k = 0; k < pc->nh; k++)
            cut[n++] = co_touch_y(p, tau, &pc->hp[k]);
    }
    pc->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {pic_y, pc};
    double sum = go_qags_cuts(&F, cut, n, j, j + 1, 1e-16, 1e-14, wo);
    gsl_integration_workspace_free(pc->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The reference of the black-to-white ramp p[] with spread over bg
 * against 2-D quadrature at the pixels px; repeat and reflect cut at
 * every integer t and where the spread t is 0.04045, for t in [-40,
 * 40] (wider than the cases' ranges). */
static void check_2d_spread(const char *what, const double p[6], int spread, double bg,
                            const int (*px)[2], int npx)
{
    pic pc;
    memset(&pc, 0, sizeof pc);
    memcpy(pc.p, p, sizeof pc.p);
    pc.bg = bg;
    pc.spread = spread;
    if (spread == AA_SPREAD_PAD)
        for (int q = 0; q < 3; q++)
            pc.taus[pc.ntaus++] = go_taus[q];
    else
        for (int k = -40; k <= 40 && pc.ntaus + 2 <= MAX_TAUS; k++) {
            pc.taus[pc.ntaus++] = k;
            pc.taus[pc.ntaus++] = spread == AA_SPREAD_REPEAT || !(k & 1) ? k + GO_T0 : k - GO_T0;
        }
    pc.nh = co_region(p, pc.hp, &pc.wedge, pc.apex);
    aa_scene *s = grad_scene(p, spread, black_white, 2, bg);
    aa_image ref, bound;
    aa_truth_stats stats;
    support_view v = {W, H, 0, 0, 0, "box", 1, 1, 0};
    support_reference(s, &v, &ref, &bound, &stats);
    assert_true(stats.max_bound <= 1e-12);
    double worst = 0;
    for (int k = 0; k < npx; k++) {
        int i = px[k][0], j = px[k][1];
        double want = pic_pixel(&pc, i, j), got = aa_pixel(&ref, i, j)[0];
        double bd = *aa_pixel(&bound, i, j);
        worst = fmax(worst, fabs(got - want));
        if (!(fabs(got - want) <= bd + 1e-14))
            fail_msg("%s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)", what, i, j,
                     got, want, bd);
    }
    print_message("%-34s %d pixels, largest difference from 2-D quadrature %.2g, largest "
                  "bound %.2g\n",
                  what, npx, worst, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

static void check_2d(const char *what, const double p[6], double bg, const int (*px)[2], int npx)
{
    check_2d_spread(what, p, AA_SPREAD_PAD, bg, px, npx);
}

static void test_2d(void **state)
{
    (void)state;
    /* the wedge from P = (0.16, 4.63) towards C = (9.3, 6.1), r = 3.1,
     * fr = 1.2: P's pixel; the circles t = 0 and 0.04045 touching the
     * tangents (3, 3), (3, 6); the ramp along the tangents (4, 3) .. (8,
     * 3) and (4, 7) .. (7, 8), t = 1 touching them at (8, 3) and (7, 8);
     * inside and outside */
    static const int a[][2] = {{0, 4}, {3, 3}, {3, 6}, {4, 3}, {5, 3}, {6, 3}, {8, 3}, {4, 7},
                               {5, 7}, {6, 8}, {7, 8}, {5, 6}, {11, 6}, {13, 1}, {12, 10}};
    check_2d("wedge, r > fr", (const double[6]){9.3, 6.1, 3.1, 3.7, 5.2, 1.2}, 0.3, a,
             (int)(sizeof a / sizeof *a));
    /* fr = 0, the focus outside the end circle: P the focus (3, 6), the
     * ramp along the tangents from it, t = 1 touching them at (9, 3) and
     * (10, 7) */
    static const int b[][2] = {{3, 6}, {4, 6}, {4, 5}, {5, 5}, {6, 4}, {6, 7},
                               {8, 3}, {8, 7}, {9, 3}, {10, 7}, {12, 3}};
    check_2d("wedge, fr = 0", (const double[6]){10.6, 5.3, 2.7, 3.45, 6.55, 0.0}, 0.5, b,
             (int)(sizeof b / sizeof *b));
    /* the focal circle the larger: the wedge opening left and down from P
     * = (2.37, 9.71); t = 0 and 0.04045 touching the tangents at (9, 0),
     * (9, 1), (13, 7), (12, 7), the ramp along them, t = 1 at (4, 7), (5,
     * 8) */
    static const int c[][2] = {{9, 0}, {9, 1}, {8, 2}, {7, 2}, {6, 4}, {4, 7}, {13, 7},
                               {12, 7}, {10, 7}, {8, 8}, {5, 8}, {9, 5}, {2, 9}};
    check_2d("wedge, fr > r", (const double[6]){5.2, 7.9, 1.1, 12.4, 3.3, 3.9}, 0.1, c,
             (int)(sizeof c / sizeof *c));
    /* the strip, oblique, the ramp across its edges */
    static const int d[][2] = {{4, 1}, {4, 5}, {6, 2}, {8, 3}, {8, 8}, {11, 6}, {11, 10}, {13, 8}};
    check_2d("strip, r = fr", (const double[6]){11.2, 8.3, 2.35, 4.1, 3.3, 2.35}, 0.2, d,
             (int)(sizeof d / sizeof *d));
    /* the end circle inside the focal one: t greatest at P = (8.4,
     * 6.43) */
    static const int e[][2] = {{8, 6}, {7, 5}, {8, 5}, {7, 6}, {6, 3}, {10, 9}, {2, 2}};
    check_2d("nested, fr > r + |C - F|", (const double[6]){8.2, 6.3, 1.5, 7.6, 5.9, 6.0}, 0.4,
             e, (int)(sizeof e / sizeof *e));
    /* the circles touching inside: t = c / (2 b) runs to infinity at the
     * half-plane's edge (padded to the last stop there), every circle
     * through P; P's pixel and the edge's */
    static const int f[][2] = {{7, 4}, {11, 1}, {9, 2}, {5, 5}, {3, 7}, {1, 8}, {9, 7}, {12, 9}};
    check_2d("half-plane, fr = 0", (const double[6]){10.5, 8.25, 5.0, 7.5, 4.25, 0.0}, 0.3, f,
             (int)(sizeof f / sizeof *f));
    static const int g[][2] = {{3, 6}, {3, 2}, {3, 9}, {2, 6}, {4, 6}, {5, 3}, {4, 5}};
    check_2d("half-plane, fr < r", (const double[6]){8.0, 6.0, 5.0, 6.0, 6.0, 3.0}, 0.3, g,
             (int)(sizeof g / sizeof *g));
    check_2d("half-plane, fr > r", (const double[6]){6.0, 6.0, 3.0, 8.0, 6.0, 5.0}, 0.3, g,
             (int)(sizeof g / sizeof *g));
}

/* Repeat and reflect: many stop circles, their front arcs ending on the
 * tangents, the range of t of each row and window taken from t's
 * quasiconcavity. */
static void test_2d_spread(void **state)
{
    (void)state;
    /* a narrow wedge from P = (3.64, 4.69) towards C = (9.3, 6.1), r =
     * 1.1, fr = 0.4, repeated: about 1.3 periods a pixel along the axis */
    static const int a[][2] = {{3, 4}, {4, 4}, {5, 3}, {5, 5}, {7, 2}, {7, 6},
                               {9, 1}, {10, 8}, {12, 5}, {14, 10}};
    check_2d_spread("wedge, repeat", (const double[6]){9.3, 6.1, 1.1, 5.7, 5.2, 0.4},
                    AA_SPREAD_REPEAT, 0.3, a, (int)(sizeof a / sizeof *a));
    /* the focal circle the larger, reflected: P = (1.88, 10.02) */
    static const int b[][2] = {{1, 10}, {2, 9}, {3, 9}, {5, 7}, {7, 6}, {8, 5},
                               {10, 4}, {12, 3}, {13, 2}, {6, 3}};
    check_2d_spread("wedge, reflect", (const double[6]){5.2, 7.9, 0.6, 12.4, 3.3, 1.9},
                    AA_SPREAD_REFLECT, 0.2, b, (int)(sizeof b / sizeof *b));
    /* the strip, repeated */
    static const int c[][2] = {{4, 1}, {4, 5}, {6, 2}, {8, 3}, {8, 8}, {11, 6}, {13, 8}};
    check_2d_spread("strip, repeat", (const double[6]){11.2, 8.3, 1.35, 7.1, 5.3, 1.35},
                    AA_SPREAD_REPEAT, 0.2, c, (int)(sizeof c / sizeof *c));
}

/* ---- several layers of one cone ----
 *
 * Two rectangles filled with the same cone-case gradient (the same
 * circles, map and stops: two overlapping shapes of an SVG filled with
 * it), over black.  Known answers:
 *  - stops all white of opacity 1/2: source over in encoded values
 *    (SVG's compositing of sRGB-encoded colours) gives 1/2 where one
 *    rectangle paints the wedge, 1/2 + 1/2 x 1/2 = 3/4 where both do, so
 *    the box reference of a pixel is dec(1/2) (|A| + |B| - 2 |A B|) +
 *    dec(3/4) |A B|, each area the pixel's square clipped by the
 *    rectangle(s) and the wedge's half-planes (cone_oracle.c), dec sRGB's
 *    curve (gradient_oracle.c, go_dec);
 *  - a ramp of encoded colour and opacity (C = 0.2 + 0.8 t, alpha = 0.9 -
 *    0.5 t, padded; stops' colours are given in linear light and
 *    interpolated encoded), and C = t, whose composite crosses sRGB's
 *    threshold 0.04045 on circles of t found here by bisection (cut there
 *    too), against 2-D quadrature of the composite from that
 *    definition: alpha C where one rectangle paints, alpha C (2 - alpha)
 *    where both do, decoded; cut at the tangents, the circles t = 0 and
 *    1 (where the padding's derivatives jump), the rectangles' sides. */
static const double LA[4] = {2.5, 2.25, 11.5, 9.5}, LB[4] = {2.75, 4.25, 14.75, 11.25};
static double layers_c0; /* the ramp's first encoded colour */

/* Two layers, rectangles LA then LB, each painted by the cone p[] with
 * stops st, over black. */
static aa_scene *layers_scene(const double p[6], const aa_gradient_stop *st)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    const double *rs[2] = {LA, LB};
    for (int k = 0; k < 2; k++) {
        const double *r = rs[k];
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, r[0] / W, r[1] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[2] / W, r[1] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[2] / W, r[3] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[0] / W, r[3] / H), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        aa_gradient g = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0},
                         2, st};
        memcpy(g.p, p, sizeof g.p);
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static int in_rect(const double *r, double x, double y)
{
    return x >= r[0] && x <= r[2] && y >= r[1] && y <= r[3];
}

/* The two layers' composite at (x, y) from the definition (the comment
 * above), decoded. */
static double layers_at(const pic *pc, double x, double y)
{
    double t = pic_t(pc, x, y);
    int n = in_rect(LA, x, y) + in_rect(LB, x, y);
    if (isnan(t) || n == 0)
        return 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double c = layers_c0 + (1 - layers_c0) * t, al = 0.9 - 0.5 * t;
    return go_dec(n == 1 ? al * c : al * c * (2 - al));
}

static double layers_x(double x, void *v)
{
    const pic *pc = v;
    return layers_at(pc, x, pc->y);
}

static double layers_y(double y, void *v)
{
    pic *pc = v;
    pc->y = y;
    double cut[2 * MAX_TAUS + 16];
    int n = 0;
    for (int k = 0; k < pc->nh; k++)
        n += line_meet(pc, k, 0, y, cut + n);
    for (int q = 0; q < pc->ntaus; q++)
        n += circle_meet(pc, pc->taus[q], 0, y, cut + n);
    cut[n++] = LA[0], cut[n++] = LA[2], cut[n++] = LB[0], cut[n++] = LB[2];
    cut[n++] = pc->apex[0], cut[n++] = pc->xlo, cut[n++] = pc->xhi;
    gsl_function F = {layers_x, pc};
    return go_qags_cuts(&F, cut, n, pc->xlo, pc->xhi, 1e-16, 1e-14, pc->wi);
}

/* Pixel (i, j) of the two layers by 2-D quadrature. */
static double layers_pixel(pic *pc, int i, int j)
{
    const double *p = pc->p;
    double cut[7 * MAX_TAUS + 24];
    int n = 0;
    pc->xlo = i, pc->xhi = i + 1;
    cut[n++] = j, cut[n++] = j + 1, cut[n++] = pc->apex[1];
    cut[n++] = LA[1], cut[n++] = LA[3], cut[n++] = LB[1], cut[n++] = LB[3];
    for (int k = 0; k < pc->nh; k++)
        for (int e = 0; e < 2; e++)
            n += line_meet(pc, k, 1, i + e, cut + n);
    for (int q = 0; q < pc->ntaus; q++) {
        double tau = pc->taus[q], rr = p[5] + tau * (p[2] - p[5]);
        double ccy = p[4] + tau * (p[1] - p[4]);
        cut[n++] = ccy - rr, cut[n++] = ccy + rr;
        for (int e = 0; e < 2; e++)
            n += circle_meet(pc, tau, 1, i + e, cut + n);
        for (int k = 0; k < pc->nh; k++)
            cut[n++] = co_touch_y(p, tau, &pc->hp[k]);
    }
    pc->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {layers_y, pc};
    double sum = go_qags_cuts(&F, cut, n, j, j + 1, 1e-16, 1e-14, wo);
    gsl_integration_workspace_free(pc->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The area of [x0, x1] x [y0, y1] meeting rectangle r (and r2 if not
 * NULL) inside the half-planes. */
static double rect_area(double x0, double y0, double x1, double y1, const double *r,
                        const double *r2, const co_half *hp, int nh)
{
    x0 = fmax(x0, r[0]), y0 = fmax(y0, r[1]), x1 = fmin(x1, r[2]), y1 = fmin(y1, r[3]);
    if (r2)
        x0 = fmax(x0, r2[0]), y0 = fmax(y0, r2[1]), x1 = fmin(x1, r2[2]), y1 = fmin(y1, r2[3]);
    return x1 > x0 && y1 > y0 ? co_clipped_area(x0, y0, x1, y1, hp, nh) : 0.0;
}

static void test_layers(void **state)
{
    (void)state;
    /* the wedge from P = (0.16, 4.63) towards C = (9.3, 6.1): its upper
     * tangent crosses the overlap [2.75, 11.5] x [4.25, 9.5] near (4, 6) ..
     * (9, 9), the lower one LA alone near (3, 4) .. (10, 2); the circles
     * t = 0 and where the composite crosses 0.04045 lie in the overlap
     * near (2, 4) .. (4, 6) */
    const double p[6] = {9.3, 6.1, 3.1, 3.7, 5.2, 1.2};
    static const aa_gradient_stop half[2] = {{0.0, {{1, 1, 1}}, 0.5}, {1.0, {{1, 1, 1}}, 0.5}};
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(p, hp, &wedge, apex);
    aa_scene *s = layers_scene(p, half);
    aa_image ref, bound;
    aa_truth_stats stats;
    support_view v = {W, H, 0, 0, 0, "box", 1, 1, 0};
    support_reference(s, &v, &ref, &bound, &stats);
    double d1 = go_dec(0.5), d2 = go_dec(0.75), worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double a = rect_area(i, j, i + 1, j + 1, LA, NULL, hp, nh);
            double b = rect_area(i, j, i + 1, j + 1, LB, NULL, hp, nh);
            double ab = rect_area(i, j, i + 1, j + 1, LA, LB, hp, nh);
            double want = d1 * (a + b - 2 * ab) + d2 * ab, got = aa_pixel(&ref, i, j)[0];
            double bd = *aa_pixel(&bound, i, j);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-15 && bd <= 1e-12))
                fail_msg("two layers, opacity 1/2: pixel (%d, %d) is %.17g, from the areas "
                         "%.17g (bound %.3g)",
                         i, j, got, want, bd);
        }
    print_message("%-34s %d pixels, largest difference from the areas %.2g, largest bound "
                  "%.2g\n",
                  "two layers of one cone, 1/2 each", W * H, worst, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);

    /* the ramps of colour and opacity: the composite a quartic in t */
    static const int px[][2] = {{6, 8}, {7, 8}, {8, 8}, {9, 9}, {6, 4}, {6, 6}, {11, 4},
                                {11, 9}, {10, 6}, {8, 5}, {3, 4}, {5, 3}, {2, 4}, {14, 7},
                                {12, 10}, {9, 2}, {1, 4}, {3, 5}, {4, 5}, {3, 3}, {4, 6},
                                {3, 6}, {4, 4}, {5, 5}, {2, 5}, {2, 6}};
    for (int r = 0; r < 2; r++) {
        layers_c0 = r ? 0.0 : 0.2;
        /* stop colours are given in linear light and interpolated
         * encoded: the first stop's colour the decoding of c0 (encoded c0
         * again to within rounding) */
        double d0 = go_dec(layers_c0);
        const aa_gradient_stop ramp[2] = {{0.0, {{d0, d0, d0}}, 0.9}, {1.0, {{1, 1, 1}}, 0.4}};
        pic pc;
        memset(&pc, 0, sizeof pc);
        memcpy(pc.p, p, sizeof pc.p);
        pc.taus[pc.ntaus++] = 0.0, pc.taus[pc.ntaus++] = 1.0;
        /* where alpha C and alpha C (2 - alpha) reach 0.04045 (both
         * increasing on [0, 1/2] for C = t), by bisection */
        for (int n = 1; r && n <= 2; n++) {
            double lo = 0, hi = 0.5;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (lo + hi), al = 0.9 - 0.5 * m;
                double e = n == 1 ? al * m : al * m * (2 - al);
                *(e < GO_T0 ? &lo : &hi) = m;
            }
            pc.taus[pc.ntaus++] = 0.5 * (lo + hi);
        }
        pc.nh = co_region(p, pc.hp, &pc.wedge, pc.apex);
        s = layers_scene(p, ramp);
        support_reference(s, &v, &ref, &bound, &stats);
        assert_true(stats.max_bound <= 1e-12);
        worst = 0;
        for (size_t k = 0; k < sizeof px / sizeof *px; k++) {
            int i = px[k][0], j = px[k][1];
            double want = layers_pixel(&pc, i, j), got = aa_pixel(&ref, i, j)[0];
            double bd = *aa_pixel(&bound, i, j);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-14))
                fail_msg("two layers, ramp from %g: pixel (%d, %d) is %.17g, 2-D quadrature "
                         "%.17g (bound %.3g)",
                         layers_c0, i, j, got, want, bd);
        }
        print_message("two layers of one cone, ramp from %.1f %d pixels, largest difference "
                      "from 2-D quadrature %.2g, largest bound %.2g\n",
                      layers_c0, (int)(sizeof px / sizeof *px), worst, stats.max_bound);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

/* ---- a cone beside other gradients at one point ----
 *
 * The cone's black-to-white ramp (padded, opaque) over the whole canvas,
 * over black, and over it on the rectangle OR a second gradient of
 * encoded colour C = 0.9 - 0.88 s and opacity alpha = 0.35 + 0.45 s, s
 * its own t padded: a linear one (P1 (4, 2) to P2 (12, 9)), a radial
 * one of nested circles (centre (8, 6), r 6, focus (6.5, 5), fr 0) or a
 * second cone-case one (C (6, 4), r 2.4, F (11.5, 6.5), fr 0.8: a wedge
 * opening the other way, its s unpainted outside it, where the layer
 * leaves the cone below as it is; its tangents, circles s = 0 and 1 and
 * apex cut as the first cone's).
 * Known answer: source over in encoded values (SVG's compositing of
 * sRGB-encoded colours) gives e = alpha C + (1 - alpha) e_cone on OR,
 * e_cone elsewhere (e_cone the cone's clamped t where painted, 0 where
 * not), decoded by sRGB's curve; each pixel by 2-D quadrature of that
 * definition (t of the cone from cone_oracle.c, of the other from
 * gradient_oracle.c), cut inside each row at the tangents, the cone's
 * circles t = 0, 0.04045, 1, the apex's column, OR's sides, the other
 * gradient's curves s = 0 and 1, and where e passes 0.04045 (which the
 * second gradient moves off the circles: found along the row by 400
 * samples and bisection); outside, at the apex's row, OR's top and
 * bottom, the tangents' and circles' crossings of the pixel's sides and
 * of OR's, the circles' top and bottom rows and where each touches each
 * tangent, and the other's curves' crossings of the sides (the radial
 * one's top and bottom rows too).  Pixels straddling the tangents inside
 * OR, the threshold's curve next to them, OR's corners over the wedge.
 * And the linear gradient in front of test_layers' two rectangles of one
 * cone (the ramp from 0.2: alpha C where one paints, alpha C (2 - alpha)
 * where both do, below it), cut also at LA's and LB's sides: two layers
 * of one cone and another gradient at one point. */
static const double OR[4] = {4.5, 1.5, 12.25, 9.75};
typedef struct over_pic {
    pic pc;
    go_pic g;
    int front; /* the gradient on OR (else the cone alone) */
    int lin;   /* the cone in linear light (test_linear) */
    int two;   /* the cone on LA and LB with test_layers' ramp from 0.2 */
    int cone;  /* the gradient on OR is a second cone, fc (else g) */
    pic fc;
} over_pic;

/* sRGB's encoding (IEC 61966-2-1) of the linear value v. */
static double enc(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static double over_enc(const over_pic *o, double x, double y)
{
    double t = pic_t(&o->pc, x, y), e = isnan(t) ? 0.0 : t < 0 ? 0 : t > 1 ? 1 : t;
    if (o->lin && !isnan(t)) /* linear light: LIN_STOPS over black */
        e = (0.9 - 0.4 * e) * enc(0.002 + 0.598 * e);
    if (o->two) { /* two layers of one cone (test_layers' composite) */
        int n = in_rect(LA, x, y) + in_rect(LB, x, y);
        double c = 0.2 + 0.8 * e, al = 0.9 - 0.5 * e;
        e = isnan(t) || n == 0 ? 0.0 : n == 1 ? al * c : al * c * (2 - al);
    }
    if (o->front && x > OR[0] && x < OR[2] && y > OR[1] && y < OR[3]) {
        double s = o->cone ? pic_t(&o->fc, x, y) : go_pic_t(&o->g, x, y);
        if (isnan(s)) /* the second cone does not paint here */
            return e;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
        double C = 0.9 - 0.88 * s, al = 0.35 + 0.45 * s;
        e = al * C + (1 - al) * e;
    }
    return e;
}

static double over_x(double x, void *v)
{
    const over_pic *o = v;
    return go_dec(over_enc(o, x, o->pc.y));
}

static double over_y(double y, void *v)
{
    over_pic *o = v;
    pic *pc = &o->pc;
    pc->y = y;
    double cut[2 * MAX_TAUS + 64];
    int n = 0;
    for (int k = 0; k < pc->nh; k++)
        n += line_meet(pc, k, 0, y, cut + n);
    for (int q = 0; q < pc->ntaus; q++)
        n += circle_meet(pc, pc->taus[q], 0, y, cut + n);
    if (o->cone) { /* the second cone's tangents, circles t = 0 and 1, apex */
        for (int k = 0; k < o->fc.nh; k++)
            n += line_meet(&o->fc, k, 0, y, cut + n);
        for (int q = 0; q < 3; q += 2)
            n += circle_meet(&o->fc, go_taus[q], 0, y, cut + n);
        cut[n++] = o->fc.apex[0];
    } else
        for (int q = 0; q < 3; q += 2)
            n += go_tau_meet(&o->g, go_taus[q], 0, y, cut + n);
    cut[n++] = OR[0], cut[n++] = OR[2], cut[n++] = pc->apex[0];
    cut[n++] = pc->xlo, cut[n++] = pc->xhi;
    if (o->two)
        cut[n++] = LA[0], cut[n++] = LA[2], cut[n++] = LB[0], cut[n++] = LB[2];
    /* where e passes the threshold: sign changes among 400 samples */
    double h = (pc->xhi - pc->xlo) / 400, xp = pc->xlo, gp = over_enc(o, xp, y) - GO_T0;
    for (int k = 1; k <= 400 && n < 2 * MAX_TAUS + 60; k++) {
        double xq = pc->xlo + k * h, gq = over_enc(o, xq, y) - GO_T0;
        if ((gp < 0) != (gq < 0)) {
            double lo = xp, hi = xq;
            for (int it = 0; it < 100; it++) {
                double m = 0.5 * (lo + hi);
                if ((over_enc(o, m, y) - GO_T0 < 0) == (gp < 0))
                    lo = m;
                else
                    hi = m;
            }
            cut[n++] = 0.5 * (lo + hi);
        }
        xp = xq, gp = gq;
    }
    gsl_function F = {over_x, o};
    return go_qags_cuts(&F, cut, n, pc->xlo, pc->xhi, 1e-16, 1e-14, pc->wi);
}

static double over_pixel(over_pic *o, int i, int j)
{
    pic *pc = &o->pc;
    const double *p = pc->p;
    double cut[16 * MAX_TAUS + 64], cols[8] = {i, i + 1, OR[0], OR[2], LA[0], LA[2], LB[0], LB[2]};
    int n = 0, ncol = o->two ? 8 : 4;
    pc->xlo = i, pc->xhi = i + 1;
    cut[n++] = j, cut[n++] = j + 1, cut[n++] = pc->apex[1], cut[n++] = OR[1], cut[n++] = OR[3];
    if (o->two)
        cut[n++] = LA[1], cut[n++] = LA[3], cut[n++] = LB[1], cut[n++] = LB[3];
    for (int c = 0; c < ncol; c++) {
        for (int k = 0; k < pc->nh; k++)
            n += line_meet(pc, k, 1, cols[c], cut + n);
        for (int q = 0; q < pc->ntaus; q++)
            n += circle_meet(pc, pc->taus[q], 1, cols[c], cut + n);
        if (o->cone) {
            for (int k = 0; k < o->fc.nh; k++)
                n += line_meet(&o->fc, k, 1, cols[c], cut + n);
            for (int q = 0; q < 3; q += 2)
                n += circle_meet(&o->fc, go_taus[q], 1, cols[c], cut + n);
        } else
            for (int q = 0; q < 3; q += 2)
                n += go_tau_meet(&o->g, go_taus[q], 1, cols[c], cut + n);
    }
    if (o->cone) { /* the second cone's apex row, circles' top and bottom rows, touches */
        const double *f = o->fc.p;
        cut[n++] = o->fc.apex[1];
        for (int q = 0; q < 3; q += 2) {
            double tau = go_taus[q], rr = f[5] + tau * (f[2] - f[5]);
            double ccy = f[4] + tau * (f[1] - f[4]);
            cut[n++] = ccy - rr, cut[n++] = ccy + rr;
            for (int k = 0; k < o->fc.nh; k++)
                cut[n++] = co_touch_y(f, tau, &o->fc.hp[k]);
        }
    }
    if (o->g.radial)
        for (int q = 0; q < 3; q += 2) {
            double cy = o->g.fy + go_taus[q] * (o->g.cy - o->g.fy), rr = go_taus[q] * o->g.r;
            cut[n++] = cy - rr, cut[n++] = cy + rr;
        }
    for (int q = 0; q < pc->ntaus; q++) {
        double tau = pc->taus[q], rr = p[5] + tau * (p[2] - p[5]);
        double ccy = p[4] + tau * (p[1] - p[4]);
        cut[n++] = ccy - rr, cut[n++] = ccy + rr;
        for (int k = 0; k < pc->nh; k++)
            cut[n++] = co_touch_y(p, tau, &pc->hp[k]);
    }
    pc->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {over_y, o};
    double sum = go_qags_cuts(&F, cut, n, j, j + 1, 1e-16, 1e-14, wo);
    gsl_integration_workspace_free(pc->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The cone in linear light (test_linear): linear values 0.002 to 0.6
 * (across the encoding's change of piece at 0.0031308), opacity 0.9 to
 * 0.5. */
static const aa_gradient_stop LIN_STOPS[2] = {{0.0, {{0.002, 0.002, 0.002}}, 0.9},
                                              {1.0, {{0.6, 0.6, 0.6}}, 0.5}};

/* Gradient g (stops above; none if NULL) on OR in front of the cone p[]
 * over [-8, W + 8] x [-8, H + 8] (black to white, or with lin LIN_STOPS
 * in linear light), over black. */
static aa_scene *over_scene(const double p[6], const aa_gradient *g, int lin)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    if (lin == 2) { /* g on OR in front of test_layers' two layers, the ramp from 0.2 */
        double d0 = go_dec(0.2);
        static aa_gradient_stop ramp[2];
        ramp[0] = (aa_gradient_stop){0.0, {{d0, d0, d0}}, 0.9};
        ramp[1] = (aa_gradient_stop){1.0, {{1, 1, 1}}, 0.4};
        const double *rs[3] = {OR, LA, LB};
        for (int k = 0; k < 3; k++) {
            const double *r = rs[k];
            assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(s, r[0] / W, r[1] / H), AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[2] / W, r[1] / H), AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[2] / W, r[3] / H), AA_OK);
            assert_int_equal(aa_scene_line_to(s, r[0] / W, r[3] / H), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
            aa_gradient c = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0},
                             {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, ramp};
            memcpy(c.p, p, sizeof c.p);
            assert_int_equal(aa_scene_set_gradient(s, k ? &c : g), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        return s;
    }
    const double big[4] = {-8, -8, W + 8, H + 8};
    for (int k = !g; k < 2; k++) {
        const double *r = k ? big : OR; /* front to back: OR's layer first */
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, r[0] / W, r[1] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[2] / W, r[1] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[2] / W, r[3] / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, r[0] / W, r[3] / H), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        if (!k) {
            assert_int_equal(aa_scene_set_gradient(s, g), AA_OK);
            continue;
        }
        aa_gradient c = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0},
                         2, lin ? LIN_STOPS : black_white};
        memcpy(c.p, p, sizeof c.p);
        assert_int_equal(aa_scene_set_gradient(s, &c), AA_OK);
        if (lin)
            assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB),
                             AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The box reference of scene s (freed here) at the pixels px against
 * over_pixel's 2-D quadrature of o: each within its bound (plus 1e-14 for
 * the quadrature's own rounding); label names the case in messages. */
static void over_check(over_pic *o, aa_scene *s, const int (*px)[2], size_t npx,
                       const char *label)
{
    aa_image ref, bound;
    aa_truth_stats stats;
    support_view v = {W, H, 0, 0, 0, "box", 1, 1, 0};
    support_reference(s, &v, &ref, &bound, &stats);
    assert_true(stats.max_bound <= 1e-12);
    double worst = 0;
    for (size_t k = 0; k < npx; k++) {
        int i = px[k][0], j = px[k][1];
        double want = over_pixel(o, i, j), got = aa_pixel(&ref, i, j)[0];
        double bd = *aa_pixel(&bound, i, j);
        worst = fmax(worst, fabs(got - want));
        if (!(fabs(got - want) <= bd + 1e-14))
            fail_msg("%s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)", label, i,
                     j, got, want, bd);
    }
    print_message("%s %d pixels, largest difference from 2-D quadrature %.2g, largest bound "
                  "%.2g\n",
                  label, (int)npx, worst, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

static void test_over(void **state)
{
    (void)state;
    /* the wedge from P = (0.16, 4.63) towards C = (9.3, 6.1) (test_2d):
     * its tangents cross OR near (4, 3) .. (8, 3) and (4, 7) .. (7, 8) */
    const double p[6] = {9.3, 6.1, 3.1, 3.7, 5.2, 1.2};
    /* colours given in linear light, interpolated encoded: the stops'
     * encoded 0.9 and 0.02 */
    double c0 = go_dec(0.9), c1 = go_dec(0.02);
    static aa_gradient_stop st[2];
    st[0] = (aa_gradient_stop){0.0, {{c0, c0, c0}}, 0.35};
    st[1] = (aa_gradient_stop){1.0, {{c1, c1, c1}}, 0.8};
    static const int px[][2] = {{4, 3}, {5, 3}, {6, 3}, {7, 3}, {8, 3}, {4, 6}, {4, 7},
                                {5, 7}, {6, 7}, {6, 8}, {7, 8}, {8, 9}, {4, 4}, {5, 5},
                                {9, 5}, {11, 2}, {12, 9}, {4, 1}, {10, 8}, {4, 5}};
    static const char *const what[4] = {"a linear gradient", "a radial gradient",
                                        "a linear gradient, on two layers",
                                        "a second cone-case gradient"};
    /* the second cone: from P2 = (14.25, 7.75) opening towards C = (6, 4),
     * half-angle 15.4 degrees; its tangents cross OR and the first
     * wedge's (pixels (8, 3), (9, 3), (4, 6) hold an edge of each) */
    static const double q2[6] = {6.0, 4.0, 2.4, 11.5, 6.5, 0.8};
    static const int px2[][2] = {{8, 3}, {9, 3}, {4, 6}, {6, 1}, {7, 2}, {8, 2}, {9, 4},
                                 {10, 5}, {12, 5}, {5, 6}, {7, 6}, {9, 6}, {12, 6}, {10, 7},
                                 {12, 7}, {6, 4}, {7, 4}, {6, 5}, {4, 1}, {12, 9}};
    for (int kind = 0; kind < 4; kind++) {
        int radial = kind == 1 || kind == 3;
        aa_gradient g = {radial ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {0},
                         {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, st};
        over_pic o;
        memset(&o, 0, sizeof o);
        o.front = 1, o.two = kind == 2;
        if (kind == 3) {
            memcpy(g.p, q2, sizeof q2);
            o.cone = 1;
            memcpy(o.fc.p, q2, sizeof q2);
            o.fc.nh = co_region(q2, o.fc.hp, &o.fc.wedge, o.fc.apex);
            assert_int_equal(o.fc.wedge, 1);
        } else if (kind == 1) {
            const double q[6] = {8, 6, 6, 6.5, 5, 0};
            memcpy(g.p, q, sizeof q);
            o.g.radial = o.g.focal = 1;
            o.g.cx = 8, o.g.cy = 6, o.g.r = 6, o.g.fx = 6.5, o.g.fy = 5;
        } else {
            const double q[4] = {4, 2, 12, 9};
            memcpy(g.p, q, sizeof q);
            o.g.x1 = 4, o.g.y1 = 2, o.g.x2 = 12, o.g.y2 = 9;
        }
        memcpy(o.pc.p, p, sizeof o.pc.p);
        for (int q = 0; q < 3; q++)
            o.pc.taus[o.pc.ntaus++] = go_taus[q];
        o.pc.nh = co_region(p, o.pc.hp, &o.pc.wedge, o.pc.apex);
        char label[64];
        snprintf(label, sizeof label, "cone under %s", what[kind]);
        if (kind == 3)
            over_check(&o, over_scene(p, &g, 0), px2, sizeof px2 / sizeof *px2, label);
        else
            over_check(&o, over_scene(p, &g, kind == 2 ? 2 : 0), px, sizeof px / sizeof *px,
                       label);
    }
}

/* ---- the cone in linear light ----
 *
 * The cone (test_over's wedge) interpolating in linear light (SVG's
 * color-interpolation linearRGB): its stops' linear values 0.002 to 0.6
 * interpolated as they are and encoded, then laid over black with the
 * opacity 0.9 to 0.5 (SVG 1.1, 'color-interpolation'; sRGB's encoding
 * from IEC 61966-2-1), alone and under test_over's linear gradient on
 * OR.  Known answer: e = alpha enc(v) (+ the front layer's source over),
 * decoded, by the same 2-D quadrature, cut also at the circles where v
 * passes 0.0031308 (the encoding's change of piece) and where the cone's
 * composite alone passes sRGB's threshold. */
static void test_linear(void **state)
{
    (void)state;
    const double p[6] = {9.3, 6.1, 3.1, 3.7, 5.2, 1.2};
    double c0 = go_dec(0.9), c1 = go_dec(0.02);
    static aa_gradient_stop st[2];
    st[0] = (aa_gradient_stop){0.0, {{c0, c0, c0}}, 0.35};
    st[1] = (aa_gradient_stop){1.0, {{c1, c1, c1}}, 0.8};
    aa_gradient g = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {4, 2, 12, 9},
                     {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, st};
    static const int px[][2] = {{0, 4}, {1, 4}, {2, 4}, {3, 3}, {3, 6}, {4, 3}, {6, 3},
                                {4, 7}, {6, 8}, {5, 5}, {8, 3}, {7, 8}, {11, 6}, {13, 1}};
    for (int front = 0; front < 2; front++) {
        over_pic o;
        memset(&o, 0, sizeof o);
        o.front = front, o.lin = 1;
        o.g.x1 = 4, o.g.y1 = 2, o.g.x2 = 12, o.g.y2 = 9;
        memcpy(o.pc.p, p, sizeof o.pc.p);
        for (int q = 0; q < 3; q++)
            o.pc.taus[o.pc.ntaus++] = go_taus[q];
        o.pc.taus[o.pc.ntaus++] = (0.0031308 - 0.002) / 0.598;
        { /* where the cone's composite alone passes sRGB's threshold (bisection) */
            double lo = 0, hi = 0.1;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (lo + hi);
                *((0.9 - 0.4 * m) * enc(0.002 + 0.598 * m) < GO_T0 ? &lo : &hi) = m;
            }
            o.pc.taus[o.pc.ntaus++] = 0.5 * (lo + hi);
        }
        o.pc.nh = co_region(p, o.pc.hp, &o.pc.wedge, o.pc.apex);
        over_check(&o, over_scene(p, front ? &g : NULL, 1), px, sizeof px / sizeof *px,
                   front ? "cone in linear light under a linear gradient" : "cone in linear light");
    }
}

/* ---- more than five layers at a point: the fold ----
 *
 * Past five gradient layers at a point the reference folds the composite
 * layer by layer (harness/truth/truth.c, "the fold"), a cone-case layer
 * among them taking the cone's cuts and its pieces in u.  Known answers,
 * derived here: layers of constant white at opacity a_k over black
 * composite, by source over in any order, to 1 - prod (1 - a_k) where
 * they paint, and an opaque white layer among them to 1; so
 *  - test_area's wedge, opaque white, with five linear gradients on the
 *    whole picture in front of it, each of constant white at opacity a_k
 *    = 0.1 k: a pixel is A + (1 - A) dec(1 - prod (1 - a_k)), A its
 *    painted area (the clipped square above), dec sRGB's decoding;
 *  - six layers of that wedge, each white at opacity 0.3 (one cone on
 *    six layers, past the five its own path takes): A dec(1 - 0.7^6).
 */
static aa_scene *fold_scene(const double p[6], int cones)
{
    static const aa_gradient_stop w3[2] = {{0.0, {{1, 1, 1}}, 0.3}, {1.0, {{1, 1, 1}}, 0.3}};
    static aa_gradient_stop wk[5][2];
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    for (int k = 0; k < 6; k++) {
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, -8.0 / W, -8.0 / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, (W + 8.0) / W, -8.0 / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, (W + 8.0) / W, (H + 8.0) / H), AA_OK);
        assert_int_equal(aa_scene_line_to(s, -8.0 / W, (H + 8.0) / H), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        aa_gradient g = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {1.0 / W, 0, 0, 1.0 / H, 0, 0},
                         2, cones ? w3 : white};
        memcpy(g.p, p, sizeof g.p);
        if (!cones && k > 0) { /* a linear gradient along x, constant white at 0.1 k */
            for (int q = 0; q < 2; q++)
                wk[k - 1][q] = (aa_gradient_stop){q, {{1, 1, 1}}, 0.1 * k};
            aa_gradient lg = {AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {3, 2, 13, 9},
                              {1.0 / W, 0, 0, 1.0 / H, 0, 0}, 2, wk[k - 1]};
            g = lg;
        }
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) the six layers of one cone, 5 of the 10 s of CPU this
 * test takes plain, are drawn on the left half of the view only: the apex,
 * both tangents and pixels wholly inside and outside the wedge, the same
 * paths of the fold as on the whole view with other numbers (tests/README.md,
 * "Tiers", says how that was checked); the plain build draws every pixel. */

static void test_fold(void **state)
{
    (void)state;
    const double p[6] = {9.3, 6.1, 3.1, 3.7, 5.2, 1.2}; /* test_area's first wedge */
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(p, hp, &wedge, apex);
    for (int cones = 0; cones < 2; cones++) {
        double keep = 1.0;
        for (int k = 1; k <= 5; k++)
            keep *= 1.0 - 0.1 * k;
        double out = cones ? 0.0 : go_dec(1.0 - keep), in = cones ? go_dec(1.0 - pow(0.7, 6)) : 1.0;
        aa_scene *s = fold_scene(p, cones);
        aa_image ref, bound;
        aa_truth_stats stats;
        /* pixels [0, w) x [0, H) of the W x H view */
        int w = SAN_SUBSET && cones ? W / 2 : W;
        support_view v = {W, H, 0, 0, 0, "box", 1, 1, 0};
        if (w == W)
            support_reference(s, &v, &ref, &bound, &stats);
        else
            support_reference_part(s, W, H, 0, 0, w, H, "box", &ref, &bound, &stats);
        double worst = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < w; i++) {
                double A = clipped_area(i, j, hp, nh), want = A * in + (1.0 - A) * out;
                double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
                worst = fmax(worst, fabs(got - want));
                if (!(fabs(got - want) <= bd + 1e-15 && bd <= 1e-12))
                    fail_msg("%s: pixel (%d, %d) is %.17g, the closed form %.17g (bound %.3g)",
                             cones ? "six layers of one cone" : "a cone under five gradients", i,
                             j, got, want, bd);
            }
        print_message("%-34s %d pixels, largest difference from the closed form %.2g, largest "
                      "bound %.2g\n",
                      cones ? "six layers of one cone" : "a cone under five gradients", w * H,
                      worst, stats.max_bound);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_area),
        cmocka_unit_test(test_2d),
        cmocka_unit_test(test_2d_spread),
        cmocka_unit_test(test_layers),
        cmocka_unit_test(test_over),
        cmocka_unit_test(test_linear),
        cmocka_unit_test(test_fold),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
