/*
 * test_gradient_cone_filter.c: the exact reference of radial gradients of
 * the cone case (the focal circle not strictly inside the end circle;
 * harness/truth/truth.c, "the cone case") under the filters other than
 * the box: the separable ones (tent, bspline of orders 2 and 3, mitchell,
 * catrom, lanczos, gauss) and the radial ones (cone, gauss with cut,
 * radial:k); and beside other gradients ("a cone beside other
 * gradients").
 *
 * Known answers, derived here and not from the code under test (the
 * picture from tests/cone_oracle.c: SVG 2's definition and the circles'
 * geometry; the filters written out below from their definitions,
 * patterns/README.md, "Filters"):
 *  - the painted area: a gradient of white stops on a rectangle inside
 *    the canvas, over black, paints 1 on the rectangle's part of the
 *    painted region (wedge, strip, half-plane or plane) and 0 elsewhere.
 *    Under a separable filter whose integer translates sum to 1 (tent:r=1,
 *    the B-splines, Mitchell-Netravali and Catmull-Rom), the pixels'
 *    weights sum to 1 at every point whose every pixel lies on the
 *    canvas, so the image's sum is that area exactly (the rectangle kept
 *    2 px, the widest support's radius, inside);
 *  - under every filter a pixel whose window lies wholly inside the
 *    painted part is 1 (the weights integrate to 1; the Gaussian to 1
 *    less its mass outside the window, in its bound) and one whose window
 *    misses it is 0;
 *  - single pixels by GSL's adaptive quadrature in two dimensions (outer
 *    rows, inner along the row, or its chord of a radial filter's
 *    support) of the weight times a black-to-white ramp over grey, cut
 *    where the picture or the weight is not smooth: inner, at the row's
 *    crossings of the tangents, the circles t = 0, T, 1 and the
 *    rectangle's sides, the apex's column and the filter's knots (radial:
 *    the centre's column); outer, at the knots' rows (radial: the centre's
 *    row and the support's top and bottom), the apex's row, the tangents'
 *    and circles' crossings of the knots' columns and of the window's
 *    sides (radial: of the support's circle, and where each passes
 *    closest to the centre), the circles' top and bottom rows and where
 *    each touches each tangent.  Pixels straddling one tangent or both,
 *    holding P* and the circles' ends on the tangents.
 * A gradient under a map that rotates, scales unequally and shears: its
 * painted region is the map's image of the one above (each half-plane
 * through the inverse map's transpose), so under the box each pixel is
 * its square's painted area, and under the filters whose translates sum
 * to 1 the image sums to the rectangle's.
 * A cone beside other gradients (a linear one and a radial one of nested
 * circles on rectangles 1 and 0.5 px from the cone's and each other):
 * under the box each pixel is the painted area of its square, under the
 * filters whose translates sum to 1 the image sums to the whole painted
 * area, and single pixels whose windows hold the gaps match the same 2-D
 * quadrature (the linear and radial ramps from tests/gradient_oracle.c,
 * cut at their curves t = 0, T, 1 and the rectangles' sides).  A
 * translucent gradient in front of them (linear, or radial of nested
 * circles; "a cone beside other gradients" at one point): source over in
 * encoded values, alpha C + (1 - alpha) below, decoded, by the same 2-D
 * quadrature, cut also at its rectangle's sides, its curves s = 0, 1 and,
 * along each row, where the composite passes sRGB's threshold (found by
 * sampling and bisection).
 * Each pixel must lie within its own bound of the answer (plus the
 * quadrature's 1e-14), and every bound within 1e-12.
 */
/* tier: full */
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

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) a declared subset: test_2d_separable leaves out the
 * wedge's pixels under tent:r=1, bspline:order=3 and catrom, which it
 * checks on its other scenes; test_beside takes the painted area under
 * the box and Catmull-Rom (not tent:r=1 and bspline:order=3 too), the
 * ramps under tent:r=1 and the cone (not bspline:order=3 too), the linear
 * gradient in front under tent:r=1 and the radial one under
 * bspline:order=3 (not each under both): every filter and every scene of
 * the plain run, each scene under fewer of them.  Another filter on the
 * same scene takes the same code paths with other numbers
 * (tests/README.md, "Tiers", says how that was checked); the sanitizers
 * find memory and undefined-behaviour errors along the paths taken, and
 * the plain build runs every case. */
#define MARGIN 2 /* the rectangle's distance from the canvas's sides */

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return 0;
}

/* ---- the filters, from their definitions (patterns/README.md, "Filters") ---- */

enum {
    F_TENT,
    F_BSPLINE2,
    F_BSPLINE3,
    F_MITCHELL,
    F_CATROM,
    F_LANCZOS2,
    F_GAUSS,
    F_CONE,
    F_GAUSSCUT,
    F_RADIAL
};

typedef struct filt {
    int kind, radial, unity; /* unity: integer translates sum to 1 */
    const char *spec;
    double R;           /* support's radius (the Gaussian: where this test integrates to) */
    double knots[8];    /* separable: where its pieces end */
    int nknots;
    double N;           /* Lanczos: 1 / its integral; radial: the normalisation */
} filt;

static double sinc(double x)
{
    return x == 0 ? 1 : sin(M_PI * x) / (M_PI * x);
}

static double lanczos2_raw(double t, void *v)
{
    (void)v;
    return fabs(t) < 2 ? sinc(t) * sinc(t / 2) : 0;
}

/* Mitchell-Netravali's cubic (Mitchell and Netravali 1988) with B, C. */
static double mn(double t, double B, double C)
{
    double a = fabs(t);
    if (a < 1)
        return ((12 - 9 * B - 6 * C) * a * a * a + (-18 + 12 * B + 6 * C) * a * a + (6 - 2 * B)) /
               6;
    if (a < 2)
        return ((-B - 6 * C) * a * a * a + (6 * B + 30 * C) * a * a + (-12 * B - 48 * C) * a +
                (8 * B + 24 * C)) /
               6;
    return 0;
}

/* The separable filter's 1-D weight. */
static double weight1(const filt *f, double t)
{
    double a = fabs(t);
    switch (f->kind) {
    case F_TENT:
        return a < 1 ? 1 - a : 0;
    case F_BSPLINE2:
        return a < 0.5 ? 0.75 - a * a : a < 1.5 ? 0.5 * (1.5 - a) * (1.5 - a) : 0;
    case F_BSPLINE3:
        return a < 1   ? 2.0 / 3 - a * a + 0.5 * a * a * a
               : a < 2 ? (2 - a) * (2 - a) * (2 - a) / 6
                       : 0;
    case F_MITCHELL:
        return mn(t, 1.0 / 3, 1.0 / 3);
    case F_CATROM:
        return mn(t, 0, 0.5);
    case F_LANCZOS2:
        return lanczos2_raw(t, NULL) * f->N;
    default: /* F_GAUSS, s = 0.5 */
        return exp(-2 * t * t) / (0.5 * sqrt(2 * M_PI));
    }
}

/* The filter's 2-D weight at (u, v) from the pixel's centre. */
static double weight2(const filt *f, double u, double v)
{
    if (!f->radial)
        return weight1(f, u) * weight1(f, v);
    double d = hypot(u, v);
    if (!(d < f->R))
        return 0;
    if (f->kind == F_CONE) /* cone:r=1 */
        return f->N * (1 - d);
    if (f->kind == F_GAUSSCUT) /* gauss:s=0.5,cut=2 */
        return f->N * exp(-2 * d * d);
    double q = 1 - d * d / (1.5 * 1.5); /* radial:k=2,r=1.5 */
    return f->N * q * q;
}

static filt make_filt(int kind)
{
    filt f = {kind, 0, 0, NULL, 2, {0}, 0, 1};
    switch (kind) {
    case F_TENT:
        f.spec = "tent:r=1", f.R = 1, f.unity = 1;
        break;
    case F_BSPLINE2:
        f.spec = "bspline:order=2", f.R = 1.5, f.unity = 1;
        break;
    case F_BSPLINE3:
        f.spec = "bspline:order=3", f.unity = 1;
        break;
    case F_MITCHELL:
        f.spec = "mitchell", f.unity = 1;
        break;
    case F_CATROM:
        f.spec = "catrom", f.unity = 1;
        break;
    case F_LANCZOS2:
        f.spec = "lanczos:a=2";
        break;
    case F_GAUSS:
        f.spec = "gauss:s=0.5", f.R = 4; /* 8 standard deviations: 1.2e-15 outside */
        break;
    case F_CONE: /* 1 / the cone's volume, pi r^2 / 3 */
        f.spec = "cone:r=1", f.R = 1, f.radial = 1, f.N = 3 / M_PI;
        break;
    case F_GAUSSCUT: /* 1 / (2 pi S^2 (1 - exp(-K^2 / 2))), S = 0.5, K = 2 */
        f.spec = "gauss:s=0.5,cut=2", f.R = 1, f.radial = 1;
        f.N = 1 / (2 * M_PI * 0.25 * (1 - exp(-2.0)));
        break;
    default: /* (k + 1) / (pi r^2), k = 2, r = 1.5 */
        f.spec = "radial:k=2,r=1.5", f.R = 1.5, f.radial = 1, f.N = 3 / (M_PI * 2.25);
    }
    if (kind == F_BSPLINE2) {
        double k[4] = {-1.5, -0.5, 0.5, 1.5};
        memcpy(f.knots, k, sizeof k), f.nknots = 4;
    } else if (!f.radial && kind != F_GAUSS)
        for (double t = -f.R; t <= f.R; t++)
            f.knots[f.nknots++] = t;
    if (kind == F_LANCZOS2) { /* normalised by its integral (QAG here) */
        gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
        gsl_function F = {lanczos2_raw, NULL};
        double sum = 0, res, err;
        for (int k = -2; k < 2; k++) {
            gsl_integration_qag(&F, k, k + 1, 1e-17, 1e-14, 100, GSL_INTEG_GAUSS61, ws, &res,
                                &err);
            sum += res;
        }
        gsl_integration_workspace_free(ws);
        f.N = 1 / sum;
    }
    return f;
}

/* ---- scenes ---- */

/* A rectangle [MARGIN, W - MARGIN] x [MARGIN, H - MARGIN] (pixels) painted
 * by the radial gradient p[] (cx cy r fx fy fr, in pixels) with stops st
 * and spread, over background bg. */
static aa_scene *grad_scene(const double p[6], int spread, const aa_gradient_stop *st, int n,
                            double bg)
{
    aa_scene *s = aa_scene_new((aa_rgb){{bg, bg, bg}});
    assert_non_null(s);
    double x0 = (double)MARGIN / W, y0 = (double)MARGIN / H;
    double x1 = (double)(W - MARGIN) / W, y1 = (double)(H - MARGIN) / H;
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1, y0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1, y1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0, y1), AA_OK);
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

/* The geometries: a wedge opening right (r > fr), one opening left and
 * down (fr > r), a strip (r = fr), the plane (the end circle inside the
 * focal one), a half-plane (the circles touching inside). */
typedef struct geom {
    const char *what;
    double p[6];
} geom;

static const geom geoms[] = {
    {"wedge, r > fr", {11.3, 6.1, 3.1, 5.7, 5.2, 1.2}},
    {"wedge, fr > r", {7.2, 7.9, 1.1, 13.4, 3.3, 3.9}},
    {"strip, r = fr", {13.2, 8.3, 2.35, 6.1, 3.3, 2.35}},
    {"nested, fr > r + |C - F|", {9.2, 6.3, 1.5, 8.6, 5.9, 6.0}},
    {"half-plane, fr < r", {10.0, 6.0, 5.0, 8.0, 6.0, 3.0}},
};
#define NGEOM ((int)(sizeof geoms / sizeof *geoms))

/* The reference of s under f, every bound within 1e-12. */
static void reference(const aa_scene *s, const filt *f, aa_image *ref, aa_image *bound,
                      aa_truth_stats *stats)
{
    support_view v = {W, H, 0, 0, 0, f->spec, 1, 1, 0};
    support_reference(s, &v, ref, bound, stats);
    if (!(stats->max_bound <= 1e-12))
        fail_msg("%s: largest bound %.3g", f->spec, stats->max_bound);
}

/* The reference of pixel (i, j) alone under f, its value and bound
 * (*bd): s mapped so that the pixel is a view of its own
 * (support_reference_part), the same picture on the same pixel square;
 * its bound within 1e-12 as reference's, *max_bound the largest so far.  A check of a few
 * pixels against the 2-D quadrature need not integrate the view's other
 * pixels (check_2d_spread and test_beside: 6 to 12 of its 192). */
static double reference_pixel(const aa_scene *s, const filt *f, int i, int j, double *bd,
                              double *max_bound)
{
    aa_image ref, bound;
    aa_truth_stats stats;
    support_reference_part(s, W, H, i, j, 1, 1, f->spec, &ref, &bound, &stats);
    if (!(stats.max_bound <= 1e-12))
        fail_msg("%s: pixel (%d, %d)'s bound %.3g", f->spec, i, j, stats.max_bound);
    double got = aa_pixel(&ref, 0, 0)[0];
    *bd = *aa_pixel(&bound, 0, 0), *max_bound = fmax(*max_bound, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    return got;
}

/* ---- the painted area, and pixels wholly in or out ---- */

static void check_area(const filt *f, const geom *gm)
{
    aa_scene *s = grad_scene(gm->p, AA_SPREAD_PAD, white, 2, 0.0);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, f, &ref, &bound, &stats);
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(gm->p, hp, &wedge, apex);
    long double sum = 0, bsum = 0;
    int inside = 0, outside = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
            sum += got, bsum += bd;
            /* the window [uc - R, uc + R]^2 (radial: the square holding
             * the support) against the painted part of the rectangle */
            double x0 = i + 0.5 - f->R, x1 = i + 0.5 + f->R, y0 = j + 0.5 - f->R,
                   y1 = j + 0.5 + f->R;
            double win = (x1 - x0) * (y1 - y0);
            double cx0 = fmax(x0, MARGIN), cx1 = fmin(x1, W - MARGIN);
            double cy0 = fmax(y0, MARGIN), cy1 = fmin(y1, H - MARGIN);
            double in = cx1 > cx0 && cy1 > cy0 ? co_clipped_area(cx0, cy0, cx1, cy1, hp, nh) : 0;
            double want = NAN;
            if (in == 0)
                want = 0, outside++;
            else if (fabs(in - win) <= 1e-12 * win)
                want = 1, inside++;
            if (!isnan(want) && !(fabs(got - want) <= bd + 1e-15))
                fail_msg("%s, %s: pixel (%d, %d) is %.17g, not %g (bound %.3g)", f->spec,
                         gm->what, i, j, got, want, bd);
        }
    double area = co_clipped_area(MARGIN, MARGIN, W - MARGIN, H - MARGIN, hp, nh);
    if (f->unity) {
        double diff = fabs((double)sum - area);
        if (!(diff <= (double)bsum + W * H * 1e-16))
            fail_msg("%s, %s: the image sums to %.17g, the painted area %.17g (bounds sum to "
                     "%.3g)",
                     f->spec, gm->what, (double)sum, area, (double)bsum);
        print_message("%-18s %-26s sum - area %8.2g (bounds' sum %.2g), %d in, %d out\n",
                      f->spec, gm->what, (double)sum - area, (double)bsum, inside, outside);
    } else
        print_message("%-18s %-26s %d pixels in, %d out, largest bound %.2g\n", f->spec,
                      gm->what, inside, outside, stats.max_bound);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

static void test_area(void **state)
{
    (void)state;
    static const int kinds[] = {F_TENT, F_BSPLINE2, F_BSPLINE3, F_MITCHELL, F_CATROM};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        for (int g = 0; g < NGEOM; g++)
            check_area(&f, &geoms[g]);
    }
}

/* Lanczos, the Gaussian and the radial filters: pixels wholly in or out
 * (their translates do not sum to 1). */
static void test_inside(void **state)
{
    (void)state;
    static const int kinds[] = {F_LANCZOS2, F_GAUSS, F_CONE, F_GAUSSCUT, F_RADIAL};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        check_area(&f, &geoms[0]);
        check_area(&f, &geoms[2]);
    }
}

/* ---- single pixels against 2-D quadrature ---- */

#define MAX_TAUS 120
#define MAX_CUTS (4 * MAX_TAUS + 64)
typedef struct pic {
    double p[6], bg;
    int spread, ntaus;
    double taus[MAX_TAUS]; /* where the spread ramp's derivatives jump */
    co_half hp[2];
    int nh, wedge;
    double apex[2];
    const filt *f;
    double uc, vc, y;
    gsl_integration_workspace *wi;
    /* beside: the cone on BA only, a linear ramp on BB and a focal
     * radial one on BC beside it (beside_scene) */
    int beside;
    go_pic lin, rad;
    /* over: a translucent gradient ov on OV in front of them all
     * (beside_scene), over black */
    int over;
    go_pic ov;
} pic;

/* The rectangles of beside_scene (pixels): the cone's, the linear
 * gradient's and the radial one's, 1 and 0.5 px apart. */
static const double BA[4] = {2, 2, 9, 10}, BB[4] = {10, 2, 14, 6}, BC[4] = {10, 6.5, 14, 10};

static int in_rect(const double r[4], double x, double y)
{
    return x > r[0] && x < r[2] && y > r[1] && y < r[3];
}

/* The front gradient's rectangle (beside_scene with over). */
static const double OV[4] = {6, 2, 12, 10};

static double clamp01(double t)
{
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* With over, the encoded composite at (x, y): below, the ramps' encoded
 * values (the cone's clamped t where it paints BA, the others' on BB and
 * BC, 0 on the black background); on OV the front gradient of encoded
 * colour C = 0.9 - 0.88 s and opacity alpha = 0.35 + 0.45 s (s its t
 * clamped) laid source over in encoded values: alpha C + (1 - alpha)
 * below (SVG's compositing of sRGB-encoded colours). */
static double over_enc(const pic *pc, double x, double y)
{
    double e = 0;
    if (in_rect(BB, x, y))
        e = clamp01(go_pic_t(&pc->lin, x, y));
    else if (in_rect(BC, x, y))
        e = clamp01(go_pic_t(&pc->rad, x, y));
    else if (in_rect(BA, x, y)) {
        double t = co_t(pc->p, x, y);
        e = isnan(t) ? 0 : clamp01(t);
    }
    if (in_rect(OV, x, y)) {
        double sv = clamp01(go_pic_t(&pc->ov, x, y)), al = 0.35 + 0.45 * sv;
        e = al * (0.9 - 0.88 * sv) + (1 - al) * e;
    }
    return e;
}

/* The picture: the ramp black to white, padded, decoded, on the
 * rectangle where painted; bg elsewhere. */
static double pic_at(const pic *pc, double x, double y)
{
    if (pc->over)
        return go_dec(over_enc(pc, x, y));
    if (pc->beside) {
        if (in_rect(BB, x, y))
            return go_pic_at(&pc->lin, x, y);
        if (in_rect(BC, x, y))
            return go_pic_at(&pc->rad, x, y);
        if (!in_rect(BA, x, y))
            return pc->bg;
    }
    if (x < MARGIN || x > W - MARGIN || y < MARGIN || y > H - MARGIN)
        return pc->bg;
    double t = co_t(pc->p, x, y);
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
    return weight2(pc->f, x - pc->uc, pc->y - pc->vc) * pic_at(pc, x, pc->y);
}

/* Where the circle of centre (ax, ay), radius ar, meets the circle (bx,
 * by) rb: their heights into out; how many. */
static int circles_meet(double ax, double ay, double ar, double bx, double by, double rb,
                        double *out)
{
    double dx = bx - ax, dy = by - ay, d = hypot(dx, dy);
    if (!(d > 0) || d > ar + rb || d < fabs(ar - rb))
        return 0;
    double l = (d * d + ar * ar - rb * rb) / (2 * d), h = sqrt(fmax(0, ar * ar - l * l));
    double mx = ax + l * dx / d, my = ay + l * dy / d;
    (void)mx;
    out[0] = my + h * dx / d, out[1] = my - h * dx / d;
    return 2;
}

static double pic_y(double y, void *v)
{
    pic *pc = v;
    const filt *f = pc->f;
    pc->y = y;
    double cut[MAX_CUTS], lo = pc->uc - f->R, hi = pc->uc + f->R;
    int n = 0;
    if (f->radial) {
        double dv = y - pc->vc, c = sqrt(fmax(0, f->R * f->R - dv * dv));
        lo = pc->uc - c, hi = pc->uc + c;
        cut[n++] = pc->uc;
    } else
        for (int k = 0; k < f->nknots; k++)
            cut[n++] = pc->uc + f->knots[k];
    for (int k = 0; k < pc->nh; k++)
        n += co_line_meet(&pc->hp[k], 0, y, cut + n);
    for (int q = 0; q < pc->ntaus; q++)
        n += co_circle_meet(pc->p, pc->taus[q], 0, y, cut + n);
    if (pc->wedge)
        cut[n++] = pc->apex[0];
    cut[n++] = MARGIN, cut[n++] = W - MARGIN;
    cut[n++] = lo, cut[n++] = hi;
    if (pc->beside) {
        cut[n++] = BA[2], cut[n++] = BB[0];
        for (int q = 0; q < 3; q++) {
            n += go_tau_meet(&pc->lin, go_taus[q], 0, y, cut + n);
            n += go_tau_meet(&pc->rad, go_taus[q], 0, y, cut + n);
        }
    }
    if (pc->over && hi > lo) {
        /* OV's sides, the front gradient's curves s = 0, 1, and where the
         * composite passes sRGB's threshold (sign changes among 400
         * samples, bisected) */
        cut[n++] = OV[0], cut[n++] = OV[2];
        for (int q = 0; q < 3; q += 2)
            n += go_tau_meet(&pc->ov, go_taus[q], 0, y, cut + n);
        double h = (hi - lo) / 400, xp = lo, gp = over_enc(pc, xp, y) - GO_T0;
        for (int k = 1; k <= 400 && n < MAX_CUTS - 2; k++) {
            double xq = lo + k * h, gq = over_enc(pc, xq, y) - GO_T0;
            if ((gp < 0) != (gq < 0)) {
                double a = xp, b = xq;
                for (int it = 0; it < 100; it++) {
                    double m = 0.5 * (a + b);
                    if ((over_enc(pc, m, y) - GO_T0 < 0) == (gp < 0))
                        a = m;
                    else
                        b = m;
                }
                cut[n++] = 0.5 * (a + b);
            }
            xp = xq, gp = gq;
        }
    }
    if (!(hi > lo))
        return 0;
    gsl_function F = {pic_x, pc};
    return go_qags_cuts(&F, cut, n, lo, hi, 1e-16, 1e-14, pc->wi);
}

/* The reference of pixel (i, j) under pc->f by 2-D quadrature. */
static double pic_pixel(pic *pc, int i, int j)
{
    const double *p = pc->p;
    const filt *f = pc->f;
    static double cut[32 * MAX_TAUS + 64];
    double R = f->R;
    int n = 0;
    pc->uc = i + 0.5, pc->vc = j + 0.5;
    double cols[16];
    int ncol = 0;
    cut[n++] = pc->vc - R, cut[n++] = pc->vc + R, cut[n++] = MARGIN, cut[n++] = H - MARGIN;
    if (pc->wedge)
        cut[n++] = pc->apex[1];
    if (f->radial)
        cut[n++] = pc->vc;
    else {
        for (int k = 0; k < f->nknots; k++)
            cut[n++] = pc->vc + f->knots[k], cols[ncol++] = pc->uc + f->knots[k];
        cols[ncol++] = pc->uc - R, cols[ncol++] = pc->uc + R;
    }
    cols[ncol++] = MARGIN, cols[ncol++] = W - MARGIN;
    if (pc->beside) {
        cut[n++] = BB[3], cut[n++] = BC[1];
        cols[ncol++] = BA[2], cols[ncol++] = BB[0];
        for (int q = 0; q < 3; q++) {
            /* the radial ramp's circles t = tau (centre F + tau D, radius
             * tau r): top and bottom rows, crossings of the columns */
            const go_pic *g = &pc->rad;
            double cy = g->fy + go_taus[q] * (g->cy - g->fy), rr = go_taus[q] * g->r;
            cut[n++] = cy - rr, cut[n++] = cy + rr;
            for (int c = 0; c < ncol; c++)
                n += go_tau_meet(g, go_taus[q], 1, cols[c], cut + n);
        }
    }
    if (pc->over) {
        /* OV's top and bottom and sides; the front gradient's curves s =
         * 0, 1 across the columns (the radial one's top and bottom rows) */
        cut[n++] = OV[1], cut[n++] = OV[3];
        cols[ncol++] = OV[0], cols[ncol++] = OV[2];
        for (int q = 0; q < 3; q += 2) {
            const go_pic *g = &pc->ov;
            if (g->radial) {
                double cy = g->fy + go_taus[q] * (g->cy - g->fy), rr = go_taus[q] * g->r;
                cut[n++] = cy - rr, cut[n++] = cy + rr;
            }
            for (int c = 0; c < ncol; c++)
                n += go_tau_meet(g, go_taus[q], 1, cols[c], cut + n);
        }
    }
    for (int c = 0; c < ncol; c++) {
        for (int k = 0; k < pc->nh; k++)
            n += co_line_meet(&pc->hp[k], 1, cols[c], cut + n);
        for (int q = 0; q < pc->ntaus; q++)
            n += co_circle_meet(p, pc->taus[q], 1, cols[c], cut + n);
    }
    for (int q = 0; q < pc->ntaus; q++) {
        double tau = pc->taus[q], rr = p[5] + tau * (p[2] - p[5]);
        double ccx = p[3] + tau * (p[0] - p[3]), ccy = p[4] + tau * (p[1] - p[4]);
        if (rr < 0)
            continue;
        cut[n++] = ccy - rr, cut[n++] = ccy + rr;
        for (int k = 0; k < pc->nh; k++)
            cut[n++] = co_touch_y(p, tau, &pc->hp[k]);
        if (f->radial) {
            /* its crossings of the support's circle, and its point
             * nearest the centre (on the line through the two centres) */
            n += circles_meet(ccx, ccy, rr, pc->uc, pc->vc, R, cut + n);
            double d = hypot(pc->uc - ccx, pc->vc - ccy);
            if (d > 0)
                cut[n++] = ccy + rr * (pc->vc - ccy) / d;
        }
    }
    if (f->radial)
        for (int k = 0; k < pc->nh; k++) {
            /* the tangent's crossings of the support's circle, and its
             * foot from the centre */
            const co_half *h = &pc->hp[k];
            long double nn = sqrtl(h->nx * h->nx + h->ny * h->ny);
            double d = (double)((h->nx * pc->uc + h->ny * pc->vc + h->k) / nn);
            double ny = (double)(h->ny / nn), nx = (double)(h->nx / nn);
            double fy = pc->vc - d * ny;
            cut[n++] = fy;
            if (fabs(d) < R) {
                double hc = sqrt(R * R - d * d);
                cut[n++] = fy + hc * nx, cut[n++] = fy - hc * nx;
            }
        }
    pc->wi = gsl_integration_workspace_alloc(1000);
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    gsl_function F = {pic_y, pc};
    double sum = go_qags_cuts(&F, cut, n, pc->vc - R, pc->vc + R, 1e-16, 1e-14, wo);
    gsl_integration_workspace_free(pc->wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The reference of the black-to-white ramp of gm with spread over bg
 * under f against 2-D quadrature at the pixels px; repeat and reflect cut
 * at every integer t and where the spread t is T, for t in [-20, 20]
 * (wider than the cases' ranges). */
static void check_2d_spread(const filt *f, const geom *gm, int spread, double bg,
                            const int (*px)[2], int npx)
{
    pic pc;
    memset(&pc, 0, sizeof pc);
    memcpy(pc.p, gm->p, sizeof pc.p);
    pc.bg = bg, pc.f = f, pc.spread = spread;
    if (spread == AA_SPREAD_PAD)
        for (int q = 0; q < 3; q++)
            pc.taus[pc.ntaus++] = go_taus[q];
    else
        for (int k = -20; k <= 20 && pc.ntaus + 2 <= MAX_TAUS; k++) {
            pc.taus[pc.ntaus++] = k;
            pc.taus[pc.ntaus++] = spread == AA_SPREAD_REPEAT || !(k & 1) ? k + GO_T0 : k - GO_T0;
        }
    pc.nh = co_region(gm->p, pc.hp, &pc.wedge, pc.apex);
    aa_scene *s = grad_scene(gm->p, spread, black_white, 2, bg);
    double worst = 0, max_bound = 0;
    for (int k = 0; k < npx; k++) {
        int i = px[k][0], j = px[k][1];
        double bd, got = reference_pixel(s, f, i, j, &bd, &max_bound);
        double want = pic_pixel(&pc, i, j);
        worst = fmax(worst, fabs(got - want));
        if (!(fabs(got - want) <= bd + 1e-14))
            fail_msg("%s, %s: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)",
                     f->spec, gm->what, i, j, got, want, bd);
    }
    print_message("%-18s %-26s %s%d pixels, largest difference from 2-D quadrature %.2g, "
                  "largest bound %.2g\n",
                  f->spec, gm->what,
                  spread == AA_SPREAD_REPEAT    ? "repeat, "
                  : spread == AA_SPREAD_REFLECT ? "reflect, "
                                                : "",
                  npx, worst, max_bound);
    aa_scene_free(s);
}

static void check_2d(const filt *f, const geom *gm, double bg, const int (*px)[2], int npx)
{
    check_2d_spread(f, gm, AA_SPREAD_PAD, bg, px, npx);
}

/* ---- a gradient under a transform ---- */

/* The cone p[] in its own coordinates (u, v), drawn through the map x =
 * a u + c v + e, y = b u + d v + f (M = a b c d e f, pixels): white stops
 * on the rectangle over black.  The painted region is the map's image of
 * the one co_region gives: a half-plane n.q + k >= 0 in (u, v), q = M^-1
 * (x - (e, f)), is N.x + k - N.(e, f) >= 0 with N = M^-T n (the linear
 * part's inverse transposed).  Under the box each pixel is its square's
 * painted area; under the filters whose translates sum to 1 the image
 * sums to the rectangle's painted area. */
static void check_transformed(const filt *f, const double p[6], const double M[6])
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    aa_gradient g = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {0}, 2, white};
    memcpy(g.p, p, sizeof g.p);
    g.m[0] = M[0] / W, g.m[1] = M[1] / H, g.m[2] = M[2] / W, g.m[3] = M[3] / H;
    g.m[4] = M[4] / W, g.m[5] = M[5] / H;
    double x0 = (double)MARGIN / W, y0 = (double)MARGIN / H;
    double x1 = (double)(W - MARGIN) / W, y1 = (double)(H - MARGIN) / H;
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1, y0), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1, y1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0, y1), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, f, &ref, &bound, &stats);
    co_half hg[2], hp[2];
    double apex[2];
    int wedge, nh = co_region(p, hg, &wedge, apex);
    long double det = (long double)M[0] * M[3] - (long double)M[2] * M[1];
    /* M^-1 = (d -c; -b a) / det; N = M^-T n */
    for (int k = 0; k < nh; k++) {
        long double nx = (M[3] * hg[k].nx - M[1] * hg[k].ny) / det;
        long double ny = (-M[2] * hg[k].nx + M[0] * hg[k].ny) / det;
        hp[k] = (co_half){nx, ny, hg[k].k - nx * M[4] - ny * M[5]};
    }
    long double sum = 0, bsum = 0;
    double worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
            sum += got, bsum += bd;
            if (f->kind >= 0)
                continue;
            double cx0 = fmax(i, MARGIN), cx1 = fmin(i + 1, W - MARGIN);
            double cy0 = fmax(j, MARGIN), cy1 = fmin(j + 1, H - MARGIN);
            double want = cx1 > cx0 && cy1 > cy0 ? co_clipped_area(cx0, cy0, cx1, cy1, hp, nh) : 0;
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-15))
                fail_msg("box, transformed: pixel (%d, %d) is %.17g, the painted area %.17g "
                         "(bound %.3g)",
                         i, j, got, want, bd);
        }
    double area = co_clipped_area(MARGIN, MARGIN, W - MARGIN, H - MARGIN, hp, nh);
    if (!(fabs((double)sum - area) <= (double)bsum + W * H * 1e-16))
        fail_msg("%s, transformed: the image sums to %.17g, the painted area %.17g (bounds sum "
                 "to %.3g)",
                 f->spec, (double)sum, area, (double)bsum);
    print_message("%-18s transformed: sum - area %8.2g (bounds' sum %.2g)", f->spec,
                  (double)sum - area, (double)bsum);
    if (f->kind < 0)
        print_message(", largest pixel difference %.2g", worst);
    print_message("\n");
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* A wedge (C = (6, 1), r = 2, F = (1, 0.5), fr = 0.6; P* = (-8/7, 2/7))
 * and a strip (r = fr), through a map rotating, scaling unequally and
 * shearing: P* lands near (2.1, 4.3) px. */
static void test_transformed(void **state)
{
    (void)state;
    static const double M[6] = {1.1, 0.4, -0.5, 0.9, 3.5, 4.5};
    static const double wedge[6] = {6, 1, 2, 1, 0.5, 0.6}, strip[6] = {7, 0.5, 1.5, 2, 0, 1.5};
    filt box = {-1, 0, 1, "box", 0.5, {0}, 0, 1};
    check_transformed(&box, wedge, M);
    check_transformed(&box, strip, M);
    static const int kinds[] = {F_TENT, F_BSPLINE3, F_CATROM};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        check_transformed(&f, wedge, M);
        check_transformed(&f, strip, M);
    }
}

/* ---- a cone beside other gradients ---- */

/* The layer of the rectangle r (pixels) painted by g (its p[] in pixels). */
static void rect_layer(aa_scene *s, const double r[4], aa_gradient g)
{
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, r[0] / W, r[1] / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r[2] / W, r[1] / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r[2] / W, r[3] / H), AA_OK);
    assert_int_equal(aa_scene_line_to(s, r[0] / W, r[3] / H), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    const double m[6] = {1.0 / W, 0, 0, 1.0 / H, 0, 0};
    memcpy(g.m, m, sizeof g.m);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
}

/* The front gradients' stops (over_enc): encoded colour 0.9 to 0.02
 * (given in linear light, interpolated encoded), opacity 0.35 to 0.8. */
static aa_gradient_stop over_st[2];

/* The cone gm on BA, a linear gradient along x from x = 10 to 14 on BB
 * and a focal radial one (centre (12, 8.25), r 3, focus (12.5, 8), fr 0:
 * nested circles) on BC, each with stops st, over bg; with over, in front
 * of them on OV (layers are front to back) a gradient with stops over_st,
 * linear along x from x = 6 to 12 (over 1) or radial of nested circles
 * (over 2: centre (9, 6), r 5, focus (8, 5.5), fr 0). */
static aa_scene *beside_scene(const geom *gm, const aa_gradient_stop *st, double bg, int over)
{
    aa_scene *s = aa_scene_new((aa_rgb){{bg, bg, bg}});
    assert_non_null(s);
    if (over) {
        double c0 = go_dec(0.9), c1 = go_dec(0.02);
        over_st[0] = (aa_gradient_stop){0.0, {{c0, c0, c0}}, 0.35};
        over_st[1] = (aa_gradient_stop){1.0, {{c1, c1, c1}}, 0.8};
        if (over == 1)
            rect_layer(s, OV, (aa_gradient){AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {6, 0, 12, 0}, {0},
                                            2, over_st});
        else
            rect_layer(s, OV, (aa_gradient){AA_GRADIENT_RADIAL, AA_SPREAD_PAD,
                                            {9, 6, 5, 8, 5.5, 0}, {0}, 2, over_st});
    }
    aa_gradient cone = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {0}, 2, st};
    memcpy(cone.p, gm->p, sizeof cone.p);
    rect_layer(s, BA, cone);
    rect_layer(s, BB, (aa_gradient){AA_GRADIENT_LINEAR, AA_SPREAD_PAD, {10, 0, 14, 0}, {0}, 2, st});
    rect_layer(s, BC, (aa_gradient){AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {12, 8.25, 3, 12.5, 8, 0},
                                    {0}, 2, st});
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* White stops over black: under the box each pixel is the painted area
 * of its square (the wedge's part of BA, and BB and BC whole); under the
 * filters whose translates sum to 1 the image sums to the whole painted
 * area. */
static void check_beside_area(const filt *f, const geom *gm)
{
    aa_scene *s = beside_scene(gm, white, 0.0, 0);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, f, &ref, &bound, &stats);
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(gm->p, hp, &wedge, apex);
    long double sum = 0, bsum = 0;
    double worst = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double got = aa_pixel(&ref, i, j)[0], bd = *aa_pixel(&bound, i, j);
            sum += got, bsum += bd;
            if (f->kind >= 0)
                continue;
            /* the box: the pixel's square against the three */
            double want = 0;
            const double *rs[3] = {BA, BB, BC};
            for (int r = 0; r < 3; r++) {
                double x0 = fmax(i, rs[r][0]), x1 = fmin(i + 1, rs[r][2]);
                double y0 = fmax(j, rs[r][1]), y1 = fmin(j + 1, rs[r][3]);
                if (x1 > x0 && y1 > y0)
                    want += r ? (x1 - x0) * (y1 - y0) : co_clipped_area(x0, y0, x1, y1, hp, nh);
            }
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-15))
                fail_msg("box, beside: pixel (%d, %d) is %.17g, the painted area %.17g (bound "
                         "%.3g)",
                         i, j, got, want, bd);
        }
    double area = co_clipped_area(BA[0], BA[1], BA[2], BA[3], hp, nh) +
                  (BB[2] - BB[0]) * (BB[3] - BB[1]) + (BC[2] - BC[0]) * (BC[3] - BC[1]);
    double diff = fabs((double)sum - area);
    if (!(diff <= (double)bsum + W * H * 1e-16))
        fail_msg("%s, beside: the image sums to %.17g, the painted area %.17g (bounds sum to "
                 "%.3g)",
                 f->spec, (double)sum, area, (double)bsum);
    if (f->kind < 0)
        print_message("%-18s beside %-19s sum - area %8.2g (bounds' sum %.2g), largest pixel "
                      "difference %.2g\n",
                      f->spec, gm->what, (double)sum - area, (double)bsum, worst);
    else
        print_message("%-18s beside %-19s sum - area %8.2g (bounds' sum %.2g)\n", f->spec,
                      gm->what, (double)sum - area, (double)bsum);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

static void test_beside(void **state)
{
    (void)state;
    filt box = {-1, 0, 1, "box", 0.5, {0}, 0, 1};
    check_beside_area(&box, &geoms[0]);
    static const int kinds[] = {F_TENT, F_BSPLINE3, F_CATROM};
    for (size_t k = SAN_SUBSET ? 2 : 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        check_beside_area(&f, &geoms[0]);
    }
    /* ramps: pixels whose windows hold the cone's tangents and the other
     * gradients, the gaps between the rectangles */
    static const int px[][2] = {{5, 3}, {7, 7}, {8, 4}, {9, 4}, {9, 7}, {10, 3},
                                {11, 5}, {12, 6}, {12, 8}};
    static const int kr[] = {F_TENT, F_BSPLINE3, F_CONE};
    for (size_t k = 0; k < sizeof kr / sizeof *kr; k++) {
        if (SAN_SUBSET && kr[k] == F_BSPLINE3)
            continue;
        filt f = make_filt(kr[k]);
        pic pc;
        memset(&pc, 0, sizeof pc);
        memcpy(pc.p, geoms[0].p, sizeof pc.p);
        pc.bg = 0.3, pc.f = &f, pc.spread = AA_SPREAD_PAD, pc.beside = 1;
        for (int q = 0; q < 3; q++)
            pc.taus[pc.ntaus++] = go_taus[q];
        pc.nh = co_region(pc.p, pc.hp, &pc.wedge, pc.apex);
        pc.lin = (go_pic){0, 0, 10, 0, 14, 0, {BB[0], BB[1], BB[2], BB[3]}, 0.3, 0, 0, 0, 0, 0};
        pc.rad = (go_pic){1, 1, 0, 0, 0, 0, {0, 0, 0, 0}, 0.3, 12, 8.25, 3, 12.5, 8};
        aa_scene *s = beside_scene(&geoms[0], black_white, 0.3, 0);
        double worst = 0, max_bound = 0;
        for (size_t q = 0; q < sizeof px / sizeof *px; q++) {
            int i = px[q][0], j = px[q][1];
            double bd, got = reference_pixel(s, &f, i, j, &bd, &max_bound);
            double want = pic_pixel(&pc, i, j);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= bd + 1e-14))
                fail_msg("%s, beside: pixel (%d, %d) is %.17g, 2-D quadrature %.17g (bound %.3g)",
                         f.spec, i, j, got, want, bd);
        }
        print_message("%-18s beside, ramps: %d pixels, largest difference from 2-D quadrature "
                      "%.2g, largest bound %.2g\n",
                      f.spec, (int)(sizeof px / sizeof *px), worst, max_bound);
        aa_scene_free(s);
    }
    /* a translucent linear or radial gradient in front of the cone and
     * the others (over_enc): pixels whose windows hold the cone's
     * tangents under it, the composite's threshold near them, OV's sides
     * across the wedge and the rectangles' gaps */
    static const int po[][2] = {{6, 3}, {7, 3}, {8, 3}, {6, 6}, {7, 7}, {8, 7},
                                {8, 8}, {7, 5}, {8, 4}, {9, 4}, {10, 5}, {11, 7}};
    static const int ko[] = {F_TENT, F_BSPLINE3};
    for (int over = 1; over <= 2; over++)
        for (size_t k = 0; k < sizeof ko / sizeof *ko; k++) {
            if (SAN_SUBSET && (int)k != over - 1)
                continue;
            filt f = make_filt(ko[k]);
            pic pc;
            memset(&pc, 0, sizeof pc);
            memcpy(pc.p, geoms[0].p, sizeof pc.p);
            pc.bg = 0.0, pc.f = &f, pc.spread = AA_SPREAD_PAD, pc.beside = 1, pc.over = over;
            for (int q = 0; q < 3; q++)
                pc.taus[pc.ntaus++] = go_taus[q];
            pc.nh = co_region(pc.p, pc.hp, &pc.wedge, pc.apex);
            pc.lin = (go_pic){0, 0, 10, 0, 14, 0, {BB[0], BB[1], BB[2], BB[3]}, 0, 0, 0, 0, 0, 0};
            pc.rad = (go_pic){1, 1, 0, 0, 0, 0, {0, 0, 0, 0}, 0, 12, 8.25, 3, 12.5, 8};
            pc.ov = over == 1
                        ? (go_pic){0, 0, 6, 0, 12, 0, {OV[0], OV[1], OV[2], OV[3]}, 0, 0, 0, 0, 0, 0}
                        : (go_pic){1, 1, 0, 0, 0, 0, {0, 0, 0, 0}, 0, 9, 6, 5, 8, 5.5};
            aa_scene *s = beside_scene(&geoms[0], black_white, 0.0, over);
            double worst = 0, max_bound = 0;
            for (size_t q = 0; q < sizeof po / sizeof *po; q++) {
                int i = po[q][0], j = po[q][1];
                double bd, got = reference_pixel(s, &f, i, j, &bd, &max_bound);
                double want = pic_pixel(&pc, i, j);
                worst = fmax(worst, fabs(got - want));
                if (!(fabs(got - want) <= bd + 1e-14))
                    fail_msg("%s, %s gradient over the cone: pixel (%d, %d) is %.17g, 2-D "
                             "quadrature %.17g (bound %.3g)",
                             f.spec, over == 1 ? "linear" : "radial", i, j, got, want, bd);
            }
            print_message("%-18s %s over the cone: %d pixels, largest difference from 2-D "
                          "quadrature %.2g, largest bound %.2g\n",
                          f.spec, over == 1 ? "linear" : "radial", (int)(sizeof po / sizeof *po),
                          worst, max_bound);
            aa_scene_free(s);
        }
}

/* Two rectangles filled with one cone (geoms[0]; the same circles, map
 * and stops), white stops of opacity 1/2 over black: source over in
 * encoded values gives 1/2 where one paints the wedge and 3/4 where both
 * do, so under the filters whose translates sum to 1 the image sums to
 * dec(1/2) (|A| + |B| - 2 |A B|) + dec(3/4) |A B|, the areas of the
 * rectangles and their overlap clipped by the wedge (cone_oracle.c), dec
 * sRGB's curve (gradient_oracle.c, go_dec). */
static const double LA[4] = {2.5, 2.25, 9.5, 9.5}, LB[4] = {5.5, 4.5, 13.75, 9.75};

static double layers_area(const double *r, const double *r2, const co_half *hp, int nh)
{
    double x0 = r[0], y0 = r[1], x1 = r[2], y1 = r[3];
    if (r2)
        x0 = fmax(x0, r2[0]), y0 = fmax(y0, r2[1]), x1 = fmin(x1, r2[2]), y1 = fmin(y1, r2[3]);
    return x1 > x0 && y1 > y0 ? co_clipped_area(x0, y0, x1, y1, hp, nh) : 0.0;
}

static void test_layers(void **state)
{
    (void)state;
    static const aa_gradient_stop half[2] = {{0.0, {{1, 1, 1}}, 0.5}, {1.0, {{1, 1, 1}}, 0.5}};
    const geom *gm = &geoms[0];
    co_half hp[2];
    double apex[2];
    int wedge, nh = co_region(gm->p, hp, &wedge, apex);
    double a = layers_area(LA, NULL, hp, nh), b = layers_area(LB, NULL, hp, nh);
    double ab = layers_area(LA, LB, hp, nh);
    double want = go_dec(0.5) * (a + b - 2 * ab) + go_dec(0.75) * ab;
    static const int kinds[] = {F_TENT, F_BSPLINE3, F_CATROM};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_non_null(s);
        aa_gradient g = {AA_GRADIENT_RADIAL, AA_SPREAD_PAD, {0}, {0}, 2, half};
        memcpy(g.p, gm->p, sizeof g.p);
        rect_layer(s, LA, g);
        rect_layer(s, LB, g);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, &f, &ref, &bound, &stats);
        long double sum = 0, bsum = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                sum += aa_pixel(&ref, i, j)[0], bsum += *aa_pixel(&bound, i, j);
        double diff = fabs((double)sum - want);
        if (!(diff <= (double)bsum + W * H * 1e-16))
            fail_msg("%s, two layers of one cone: the image sums to %.17g, from the areas %.17g "
                     "(bounds sum to %.3g)",
                     f.spec, (double)sum, want, (double)bsum);
        print_message("%-18s two layers of one cone, sum - areas %8.2g (bounds' sum %.2g)\n",
                      f.spec, (double)sum - want, (double)bsum);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

/* The wedge from P* = (2.16, 4.63) towards C = (11.3, 6.1): P*'s pixel,
 * the circles t = 0 and T touching the tangents near (5, 3) and (5, 6),
 * the ramp along the tangents, t = 1 touching them near (10, 3) and (9,
 * 8), inside; the strip's edges and the ramp across them. */
static const int wedge_px[][2] = {{2, 4}, {3, 4}, {5, 3}, {5, 6}, {7, 3}, {7, 7}, {10, 3}, {9, 8},
                                  {11, 6}};
static const int strip_px[][2] = {{6, 1}, {6, 5}, {8, 2}, {10, 3}, {10, 8}, {13, 6}};
/* The wedge from P* = (4.76, 9.71) opening right and up (fr > r): P*'s
 * pixel, both tangents, inside. */
static const int fr_px[][2] = {{4, 9}, {5, 8}, {6, 7}, {7, 5}, {8, 3}, {9, 1}, {10, 7}, {13, 6},
                               {12, 3}};
/* The half-plane x > 5 (the circles touching inside at P* = (5, 6)),
 * where t runs to infinity at the edge (padded: the last stop's colour
 * there): P*'s pixel and the edge's. */
static const int half_px[][2] = {{4, 5}, {5, 5}, {5, 6}, {4, 6}, {6, 3}, {7, 8}, {9, 6}};

static void test_2d_separable(void **state)
{
    (void)state;
    static const int kinds[] = {F_TENT, F_BSPLINE2, F_BSPLINE3, F_MITCHELL, F_CATROM,
                                F_LANCZOS2, F_GAUSS};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        /* the sanitizers' subset: these three on the other scenes below */
        if (SAN_SUBSET && (kinds[k] == F_TENT || kinds[k] == F_BSPLINE3 || kinds[k] == F_CATROM))
            continue;
        filt f = make_filt(kinds[k]);
        check_2d(&f, &geoms[0], 0.3, wedge_px, (int)(sizeof wedge_px / sizeof *wedge_px));
    }
    filt t = make_filt(F_TENT), b = make_filt(F_BSPLINE3);
    check_2d(&t, &geoms[2], 0.2, strip_px, (int)(sizeof strip_px / sizeof *strip_px));
    check_2d(&b, &geoms[2], 0.2, strip_px, (int)(sizeof strip_px / sizeof *strip_px));
    filt c = make_filt(F_CATROM);
    check_2d(&c, &geoms[4], 0.3, half_px, (int)(sizeof half_px / sizeof *half_px));
    check_2d(&t, &geoms[1], 0.1, fr_px, (int)(sizeof fr_px / sizeof *fr_px));
    check_2d(&b, &geoms[3], 0.4, wedge_px, (int)(sizeof wedge_px / sizeof *wedge_px));
    /* repeated and reflected: many stop circles, their front arcs ending
     * on the tangents */
    check_2d_spread(&t, &geoms[0], AA_SPREAD_REPEAT, 0.3, wedge_px,
                    (int)(sizeof wedge_px / sizeof *wedge_px));
    check_2d_spread(&c, &geoms[1], AA_SPREAD_REFLECT, 0.2, fr_px,
                    (int)(sizeof fr_px / sizeof *fr_px));
}

static void test_2d_radial(void **state)
{
    (void)state;
    static const int kinds[] = {F_CONE, F_GAUSSCUT, F_RADIAL};
    for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
        filt f = make_filt(kinds[k]);
        check_2d(&f, &geoms[0], 0.3, wedge_px, (int)(sizeof wedge_px / sizeof *wedge_px));
    }
    filt c = make_filt(F_CONE);
    check_2d_spread(&c, &geoms[0], AA_SPREAD_REPEAT, 0.3, wedge_px,
                    (int)(sizeof wedge_px / sizeof *wedge_px));
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_area),
        cmocka_unit_test(test_inside),
        cmocka_unit_test(test_2d_separable),
        cmocka_unit_test(test_2d_radial),
        cmocka_unit_test(test_transformed),
        cmocka_unit_test(test_beside),
        cmocka_unit_test(test_layers),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
