/*
 * test_filter_truth.c: the reference under the B-splines, Mitchell-Netravali,
 * Catmull-Rom, Lanczos, the Gaussian in a circular mask and the truncated
 * cone (patterns/README.md, "Filters"), against answers derived here from
 * the filters' definitions, not from harness/core/filter.c:
 *
 *  - a half-plane bounded by a vertical or a horizontal line: the pixel's
 *    value is the filter's 1-D mass on the white side, from the weights as
 *    published (Mitchell and Netravali 1988, eq. 8; the B-splines' pieces)
 *    integrated term by term here, and for Lanczos by GSL's quadrature of
 *    sinc(t) sinc(t / a) normalised by its own quadrature of the whole;
 *  - for the radial filters a half-plane at any angle: the mass beyond the
 *    line's distance, by nested quadrature of the weight written here
 *    (the outer integral in x = Rc sin theta, smooth at the mask's wall);
 *    and a disk centred on a pixel centre: the mass within its radius a in
 *    closed form, (1 - exp(-a^2 / (2 s^2))) / (1 - exp(-K^2 / 2)) for the
 *    Gaussian in a mask of radius K s, (a^2 / 2 - a^3 / (3 r)) /
 *    (Rc^2 / 2 - Rc^3 / (3 r)) for the cone of radius r cut at Rc;
 *  - a white square made of 16 abutting squares is exactly 1 wherever the
 *    filter's support lies inside it (the inner edges cross those pixels);
 *  - the translates of the B-splines and of every Mitchell-Netravali cubic
 *    by the pixel grid sum to 1, so a white shape inside the image sums to
 *    its area (a triangle by the shoelace formula, a parabolic segment 2/3
 *    of its control triangle, Archimedes);
 *  - the Gaussian in a mask of radius 9 s equals the untruncated Gaussian
 *    (a different path: radial rows against the separable fixed rule) to
 *    their bounds and the mass beyond the mask, exp(-81 / 2);
 *    mitchell:b=1,c=0 equals the cubic B-spline;
 *  - the tip of a looping cubic arc, which turns 0.0044 above a kink's
 *    breakpoint, under box, tent and mitchell:b=0.2,c=0.7: by Green's
 *    theorem the integral along the arc of the cdf in x times the weight
 *    in y, a polynomial between the knots' crossings that Gauss-Legendre
 *    integrates exactly; and the transposed scene, pixel by pixel.
 * Every pixel is within its bound plus the answer's rounding (1e-15, or
 * the quadrature's estimate) and every bound is at most AA_TRUTH_BOUND;
 * the half-planes again through the one-piece-at-a-time path
 * (AA__TRUTH_CROWD).  Filters with negative lobes give values below 0
 * next to an edge, inside the range aa_filter_range states.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"
#include "truth_internal.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* ---- the filters as published, 1-D, for x = |t| ---- */

typedef struct wpiece {
    double a, b, c[4]; /* the weight on [a, b): c0 + c1 x + c2 x^2 + c3 x^3 */
} wpiece;

/* Mitchell and Netravali (1988), eq. 8. */
static int mitchell_pieces(double B, double C, wpiece *p)
{
    p[0] =
        (wpiece){0, 1, {(6 - 2 * B) / 6, 0, (-18 + 12 * B + 6 * C) / 6, (12 - 9 * B - 6 * C) / 6}};
    p[1] = (wpiece){
        1,
        2,
        {(8 * B + 24 * C) / 6, (-12 * B - 48 * C) / 6, (6 * B + 30 * C) / 6, (-B - 6 * C) / 6}};
    return 2;
}

/* The quadratic B-spline: 3/4 - x^2, then (x - 3/2)^2 / 2. */
static int bspline2_pieces(wpiece *p)
{
    p[0] = (wpiece){0, 0.5, {0.75, 0, -1, 0}};
    p[1] = (wpiece){0.5, 1.5, {9.0 / 8, -1.5, 0.5, 0}};
    return 2;
}

/* The integral of the pieces from 0 to x (x >= 0), term by term. */
static double pieces_mass(const wpiece *p, int n, double x)
{
    double m = 0;
    for (int k = 0; k < n; k++) {
        double hi = fmin(p[k].b, x), lo = p[k].a;
        if (hi <= lo)
            continue;
        for (int d = 0; d < 4; d++)
            m += p[k].c[d] * (pow(hi, d + 1) - pow(lo, d + 1)) / (d + 1);
    }
    return m;
}

/* Lanczos: GSL's QAG of sinc(t) sinc(t / a) from 0 to x, piece by piece
 * between the integers. */
static double lanczos_w(double t, void *pa)
{
    double a = *(double *)pa, x = M_PI * t, y = x / a;
    return (x == 0 ? 1 : sin(x) / x) * (y == 0 ? 1 : sin(y) / y);
}

static double lanczos_mass0(double a, double x, double *err)
{
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    gsl_function F = {lanczos_w, &a};
    double m = 0;
    *err = 0;
    for (double lo = 0; lo < fmin(x, a); lo += 1) {
        double r, e, hi = fmin(fmin(lo + 1, x), a);
        gsl_integration_qag(&F, lo, hi, 1e-17, 1e-15, 200, GSL_INTEG_GAUSS61, ws, &r, &e);
        m += r;
        *err += e;
    }
    gsl_integration_workspace_free(ws);
    return m;
}

/* The 1-D cdf of a separable filter named by spec, derived above: *err is
 * the derivation's own error. */
static double cdf_of(const char *spec, double t, double *err)
{
    wpiece p[2];
    int n = 0;
    *err = 2e-15; /* the rounding of the monomials, up to 16 c3 on [1, 2] */
    double B = 1.0 / 3, C = 1.0 / 3;
    if (!strcmp(spec, "bspline:order=2")) {
        n = bspline2_pieces(p);
    } else if (!strcmp(spec, "bspline")) {
        n = mitchell_pieces(1, 0, p);
    } else if (!strcmp(spec, "catrom")) {
        n = mitchell_pieces(0, 0.5, p);
    } else if (!strncmp(spec, "mitchell", 8)) {
        if (spec[8] == ':')
            assert_int_equal(sscanf(spec, "mitchell:b=%lf,c=%lf", &B, &C), 2);
        n = mitchell_pieces(B, C, p);
    } else {
        double a = spec[10] == '2' ? 2 : 3, e1, e2;
        assert_true(!strncmp(spec, "lanczos:a=", 10));
        double whole = lanczos_mass0(a, a, &e1), part = lanczos_mass0(a, fabs(t), &e2);
        *err = (e1 + e2) / whole + 1e-15;
        return t < 0 ? 0.5 - 0.5 * part / whole : 0.5 + 0.5 * part / whole;
    }
    double m = pieces_mass(p, n, fabs(t));
    return t < 0 ? 0.5 - m : 0.5 + m;
}

static const char *const separable[] = {"bspline:order=2",       "bspline", "mitchell",
                                        "mitchell:b=0.5,c=0.75", "catrom",  "lanczos:a=2",
                                        "lanczos:a=3",           NULL};

/* ---- the radial filters as defined, by quadrature ---- */

typedef struct radial {
    int cone;
    double s, k; /* Gaussian: s and the mask K s; cone: r = s and the mask K r */
    double x;    /* the row (outer variable) */
} radial;

static double radial_w(const radial *r, double u, double v)
{
    double rc = r->s * r->k, d = hypot(u, v);
    if (d >= rc)
        return 0;
    if (r->cone)
        return (1 - d / r->s) /
               (2 * M_PI * r->s * r->s * (0.5 * r->k * r->k - r->k * r->k * r->k / 3));
    return exp(-0.5 * d * d / (r->s * r->s)) /
           (2 * M_PI * r->s * r->s * (1 - exp(-0.5 * r->k * r->k)));
}

static double radial_row(double y, void *pr)
{
    const radial *r = pr;
    return radial_w(r, r->x, y);
}

/* The mass of the row at x, 2 int_0^c w(x, y) dy. */
static double radial_marginal(radial *r, double x, gsl_integration_workspace *ws)
{
    double rc = r->s * r->k;
    if (fabs(x) >= rc)
        return 0;
    r->x = x;
    gsl_function F = {radial_row, r};
    double res, err;
    gsl_integration_qag(&F, 0, sqrt(rc * rc - x * x), 1e-16, 1e-14, 200, GSL_INTEG_GAUSS61, ws,
                        &res, &err);
    return 2 * res;
}

typedef struct outer {
    radial *r;
    gsl_integration_workspace *ws;
} outer;

static double outer_fn(double th, void *po)
{
    outer *o = po;
    double rc = o->r->s * o->r->k;
    return radial_marginal(o->r, rc * sin(th), o->ws) * rc * cos(th);
}

/* The mass of {x > d}: the outer integral in x = Rc sin theta. */
static double radial_beyond(radial r, double d)
{
    double rc = r.s * r.k;
    if (d >= rc)
        return 0;
    if (d <= -rc)
        return 1;
    if (d < 0)
        return 1 - radial_beyond(r, -d);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200),
                              *ws2 = gsl_integration_workspace_alloc(200);
    outer o = {&r, ws2};
    gsl_function F = {outer_fn, &o};
    double res, err;
    gsl_integration_qag(&F, asin(d / rc), M_PI_2, 1e-15, 1e-13, 200, GSL_INTEG_GAUSS61, ws, &res,
                        &err);
    gsl_integration_workspace_free(ws);
    gsl_integration_workspace_free(ws2);
    return res;
}

static radial radial_of(const char *spec)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(spec, &f), AA_OK);
    assert_false(aa_filter_is_separable(&f));
    radial r = {f.type == &aa_filter_cone, f.spec.v[0], f.spec.v[1], 0};
    return r;
}

static const char *const radial_specs[] = {"gauss:s=1,cut=2", "gauss:s=0.6,cut=3.5",
                                           "cone:r=2,cut=0.5", "cone:r=1.2,cut=0.9", NULL};

/* ---- references ---- */


/* Vertical and horizontal half-planes, white right of x0 and above y0. */
static void test_half_planes_separable(void **state)
{
    (void)state;
    gsl_set_error_handler_off(); /* the quadratures are judged by their estimates */
    const int w = 14, h = 10;
    const double x0 = 6.37, y0 = 4.71;
    for (const char *const *f = separable; *f; f++)
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD) {
            double worst = 0, lo = 0, hi = 0, rlo, rhi;
            aa_filter filt;
            assert_int_equal(aa_filter_parse(*f, &filt), AA_OK);
            aa_filter_range(&filt, &rlo, &rhi);
            for (int vertical = 0; vertical < 2; vertical++) {
                aa_scene *s = vertical ? scenes_half_plane_of(x0, 0, 0, 100, white, black)
                                       : scenes_half_plane_of(0, y0, M_PI_2, 100, white, black);
                aa_image img, bound;
                support_reference_mode(s, w, h, *f, mode, &img, &bound);
                for (int j = 0; j < h; j++)
                    for (int i = 0; i < w; i++) {
                        double err, want = vertical ? 1 - cdf_of(*f, x0 - (i + 0.5), &err)
                                                    : cdf_of(*f, y0 - (j + 0.5), &err);
                        double got = aa_pixel(&img, i, j)[0];
                        support_check_value(vertical ? "vertical half-plane"
                                                     : "horizontal half-plane",
                                            *f, i, j, got, *aa_pixel(&bound, i, j), want, err,
                                            &worst);
                        lo = fmin(lo, got);
                        hi = fmax(hi, got);
                    }
                aa_image_free(&img);
                aa_image_free(&bound);
                aa_scene_free(s);
            }
            /* the negative lobes show, inside the range the filter states */
            assert_true(lo >= rlo && hi <= rhi);
            if (rlo < 0)
                assert_true(lo < -1e-3 && hi > 1 + 1e-3);
            else
                assert_true(lo >= -1e-15 && hi <= 1 + 1e-15);
            print_message("half-planes %-22s mode %d: max |ref - closed form| %.2e, values in "
                          "[%.4f, %.4f], range [%.4f, %.4f]\n",
                          *f, mode, worst, lo, hi, rlo, rhi);
        }
}

/* Half-planes at three angles under the radial filters. */
static void test_half_planes_radial(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const int w = 12, h = 9;
    const double px = 5.83, py = 4.27, angles[] = {0.0, 0.41, 2.3};
    for (const char *const *f = radial_specs; *f; f++) {
        radial r = radial_of(*f);
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD) {
            double worst = 0;
            for (int q = 0; q < 3; q++) {
                double an = angles[q], nx = cos(an), ny = -sin(an);
                aa_scene *s = scenes_half_plane_of(px, py, an, 100, white, black);
                aa_image img, bound;
                support_reference_mode(s, w, h, *f, mode, &img, &bound);
                for (int j = 0; j < h; j++)
                    for (int i = (j * 3) % 2; i < w; i += 2) {
                        /* the centre's signed distance into the white side */
                        double d = (i + 0.5 - px) * nx + (j + 0.5 - py) * ny;
                        double want = radial_beyond(r, -d);
                        support_check_value("half-plane", *f, i, j, aa_pixel(&img, i, j)[0],
                                            *aa_pixel(&bound, i, j), want, 1e-14, &worst);
                    }
                aa_image_free(&img);
                aa_image_free(&bound);
                aa_scene_free(s);
            }
            print_message("half-planes %-22s mode %d: max |ref - quadrature| %.2e\n", *f, mode,
                          worst);
        }
    }
}

/* A disk of radius a centred on pixel (6, 5)'s centre. */
static void test_centred_disks(void **state)
{
    (void)state;
    const double cx = 6.5, cy = 5.5;
    for (const char *const *f = radial_specs; *f; f++) {
        radial r = radial_of(*f);
        double rc = r.s * r.k;
        const double frac[] = {0.3, 0.77, 1.4};
        for (int q = 0; q < 3; q++) {
            double a = frac[q] * rc, want;
            if (a >= rc)
                want = 1;
            else if (r.cone)
                want =
                    (a * a / 2 - a * a * a / (3 * r.s)) / (rc * rc / 2 - rc * rc * rc / (3 * r.s));
            else
                want = -expm1(-0.5 * a * a / (r.s * r.s)) / -expm1(-0.5 * r.k * r.k);
            aa_scene *s = scenes_disk(cx, cy, a);
            aa_image img, bound;
            double worst = 0;
            support_reference_mode(s, 13, 11, *f, 0, &img, &bound);
            support_check_value("centred disk", *f, 6, 5, aa_pixel(&img, 6, 5)[0],
                                *aa_pixel(&bound, 6, 5), want, 1e-15, &worst);
            print_message("disk of radius %.3f under %-20s: %.17f, error %.2e\n", a, *f,
                          aa_pixel(&img, 6, 5)[0], worst);
            aa_image_free(&img);
            aa_image_free(&bound);
            aa_scene_free(s);
        }
    }
}

/* 3 x 3 abutting squares of side 5.5 from (2.3, 1.7): 1 wherever the
 * support is inside, 0 wherever it is outside. */
static void test_abutting_squares(void **state)
{
    (void)state;
    double rects[9][4];
    for (int k = 0; k < 9; k++) {
        double x = 2.3 + 5.5 * (k % 3), y = 1.7 + 5.5 * (k / 3);
        rects[k][0] = x, rects[k][1] = y, rects[k][2] = x + 5.5, rects[k][3] = y + 5.5;
    }
    aa_scene *s = scenes_rects(rects, 9);
    const char *const all[] = {"bspline:order=2", "bspline",         "mitchell",         "catrom",
                               "lanczos:a=2",     "gauss:s=1,cut=2", "cone:r=2,cut=0.5", NULL};
    for (const char *const *f = all; *f; f++) {
        aa_filter filt;
        assert_int_equal(aa_filter_parse(*f, &filt), AA_OK);
        double R = filt.radius, worst = 0;
        int inside = 0;
        aa_image img, bound;
        support_reference_mode(s, 21, 20, *f, 0, &img, &bound);
        for (int j = 0; j < 20; j++)
            for (int i = 0; i < 21; i++) {
                double u = i + 0.5, v = j + 0.5;
                int in = u - R > 2.3 && u + R < 18.8 && v - R > 1.7 && v + R < 18.2;
                int out = u + R < 2.3 || u - R > 18.8 || v + R < 1.7 || v - R > 18.2;
                if (in || out)
                    support_check_value("abutting squares", *f, i, j, aa_pixel(&img, i, j)[0],
                                        *aa_pixel(&bound, i, j), in ? 1 : 0, 1e-15, &worst);
                inside += in;
            }
        assert_true(inside >= 64);
        print_message("abutting squares under %-18s: %d pixels inside, max |ref - 1| %.2e\n", *f,
                      inside, worst);
        aa_image_free(&img);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* The image sums to the shape's area where the translates sum to 1. */
static void check_sum(const char *what, const aa_scene *s, int w, int h, double area)
{
    const char *const pu[] = {"bspline:order=2",  "bspline", "mitchell", "mitchell:b=0.5,c=0.75",
                              "mitchell:b=0,c=1", "catrom",  NULL};
    for (const char *const *f = pu; *f; f++) {
        aa_image img, bound;
        support_reference_mode(s, w, h, *f, 0, &img, &bound);
        double sum = 0, bsum = 0;
        for (int k = 0; k < w * h; k++) {
            sum += img.v[3 * k];
            bsum += bound.v[k];
        }
        double d = fabs(sum - area);
        if (!(d <= bsum + 1e-13))
            fail_msg("%s under %s: sum %.17g, area %.17g (bounds sum to %.2e)", what, *f, sum, area,
                     bsum);
        print_message("%s under %-22s: sum - area %.2e (bounds %.2e)\n", what, *f, sum - area,
                      bsum);
        aa_image_free(&img);
        aa_image_free(&bound);
    }
}

static void test_sums(void **state)
{
    (void)state;
    const double tri[] = {3.2, 2.7, 17.9, 4.1, 8.3, 15.6};
    aa_scene *s = scenes_polygon(tri, 3, white, black, AA_FILL_NONZERO);
    double area =
        0.5 * fabs((tri[2] - tri[0]) * (tri[5] - tri[1]) - (tri[4] - tri[0]) * (tri[3] - tri[1]));
    check_sum("triangle", s, 22, 20, area);
    aa_scene_free(s);
    /* a parabolic segment: 2/3 of its control triangle */
    const double p0[2] = {3.1, 14.2}, c[2] = {9.4, -1.3}, p1[2] = {16.7, 13.3};
    s = scenes_arc_segment(p0[0], p0[1], c[0], c[1], p1[0], p1[1]);
    area =
        2.0 / 3 * 0.5 * fabs((c[0] - p0[0]) * (p1[1] - p0[1]) - (p1[0] - p0[0]) * (c[1] - p0[1]));
    check_sum("parabolic segment", s, 21, 18, area);
    aa_scene_free(s);
}

/* Two paths to the same values, on a parabolic segment and a triangle. */
static void check_same(const char *fa, const char *fb, double extra)
{
    const double tri[] = {3.2, 2.7, 17.9, 4.1, 8.3, 15.6};
    aa_scene *scenes[2] = {scenes_arc_segment(3.1, 14.2, 9.4, -1.3, 16.7, 13.3),
                           scenes_polygon(tri, 3, white, black, AA_FILL_NONZERO)};
    double worst = 0;
    for (int q = 0; q < 2; q++) {
        aa_image a, b, ba, bb;
        support_reference_mode(scenes[q], 21, 18, fa, 0, &a, &ba);
        support_reference_mode(scenes[q], 21, 18, fb, 0, &b, &bb);
        for (int k = 0; k < 21 * 18; k++) {
            double d = fabs(a.v[3 * k] - b.v[3 * k]);
            if (!(d <= ba.v[k] + bb.v[k] + extra))
                fail_msg("scene %d, pixel %d: %s %.17g, %s %.17g", q, k, fa, a.v[3 * k], fb,
                         b.v[3 * k]);
            worst = fmax(worst, d);
        }
        aa_image_free(&a);
        aa_image_free(&b);
        aa_image_free(&ba);
        aa_image_free(&bb);
        aa_scene_free(scenes[q]);
    }
    print_message("%s against %s: max difference %.2e\n", fa, fb, worst);
}

static void test_same_filters(void **state)
{
    (void)state;
    check_same("gauss:s=0.7,cut=9", "gauss:s=0.7", exp(-40.5) + 1e-15);
    check_same("mitchell:b=1,c=0", "bspline", 1e-15);
    check_same("mitchell:b=0,c=0.5", "catrom", 0);
}

/* ---- the tip of a looping cubic ---- */

/* The 1-D weight of spec at t, derived as above (box, tent:r=1 and the
 * Mitchell-Netravali cubics). */
static double weight_of(const char *spec, double t)
{
    double x = fabs(t), B, C;
    if (!strcmp(spec, "box"))
        return x < 0.5 ? 1 : 0;
    if (!strcmp(spec, "tent:r=1"))
        return x < 1 ? 1 - x : 0;
    assert_int_equal(sscanf(spec, "mitchell:b=%lf,c=%lf", &B, &C), 2);
    wpiece p[2];
    mitchell_pieces(B, C, p);
    for (int k = 0; k < 2; k++)
        if (x >= p[k].a && x < p[k].b)
            return p[k].c[0] + x * (p[k].c[1] + x * (p[k].c[2] + x * p[k].c[3]));
    return 0;
}

/* Its cdf: the box's and the tent's by hand, the cubics' as cdf_of. */
static double tip_cdf(const char *spec, double t)
{
    double err;
    if (!strcmp(spec, "box"))
        return fmin(fmax(t + 0.5, 0), 1);
    if (!strcmp(spec, "tent:r=1"))
        return t <= -1  ? 0
               : t >= 1 ? 1
               : t < 0  ? 0.5 * (1 + t) * (1 + t)
                        : 1 - 0.5 * (1 - t) * (1 - t);
    return cdf_of(spec, t, &err);
}

/* A looping cubic arc, closed by its chord (SVG path "M 2.55 12.6 C 16.15
 * 7.7 0.85 7.7 14.45 13.3 Z"; x and y swapped when `swap`): its loop's
 * tip turns (dy/dt = 0) at y = 9.008, 0.0044 above the height where the
 * arc crosses x = 8.5, a kink of Mitchell's filter 1 from the centre of
 * pixel (7, 7), whose window [5.5, 9.5]^2 holds only the tip. */
static const double loop_cubic[8] = {2.55, 12.6, 16.15, 7.7, 0.85, 7.7, 14.45, 13.3};

static aa_scene *loop_scene(int swap)
{
    const double *c = loop_cubic;
    int a = swap, b = !swap;
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, c[a], c[b]), AA_OK);
    assert_int_equal(
        aa_scene_cubic_to(s, c[2 + a], c[2 + b], c[4 + a], c[4 + b], c[6 + a], c[6 + b]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void loop_at(double t, double *x, double *y, double *dy)
{
    const double *c = loop_cubic;
    double u = 1 - t, b[4] = {u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t};
    *x = b[0] * c[0] + b[1] * c[2] + b[2] * c[4] + b[3] * c[6];
    *y = b[0] * c[1] + b[1] * c[3] + b[2] * c[5] + b[3] * c[7];
    *dy = 3 * (u * u * (c[3] - c[1]) + 2 * u * t * (c[5] - c[3]) + t * t * (c[7] - c[5]));
}

typedef struct tip {
    const char *spec;
    double uc, vc;
} tip;

/* Green's theorem: the filtered tip is minus the integral along the arc
 * of W(x - uc) w(y - vc) dy, W the cdf: the chord lies outside the
 * window's rows, and the arc reaches the tip from the right and leaves it
 * to the left (its loop crosses itself below the window), clockwise round
 * it: winding -1, white under the nonzero rule. */
static double tip_integrand(double t, void *pt)
{
    const tip *p = pt;
    double x, y, dy;
    loop_at(t, &x, &y, &dy);
    return tip_cdf(p->spec, x - p->uc) * weight_of(p->spec, y - p->vc) * dy;
}

/* Where x - uc or y - vc crosses k / 2 (k = -4 .. 4: every filter's knots
 * here), by a scan in steps of 1e-3 (no two are closer on this arc) and
 * bisection; the integrand is a polynomial of degree 23 at most between
 * them, which 12-point Gauss-Legendre integrates exactly. */
static double tip_value(const char *spec, double uc, double vc)
{
    double cut[64] = {0};
    int n = 1;
    for (int axis = 0; axis < 2; axis++)
        for (int k = -4; k <= 4; k++) {
            double level = (axis ? vc : uc) + 0.5 * k;
            for (int s = 0; s < 1000; s++) {
                double a = s / 1000.0, b = (s + 1) / 1000.0, xa, ya, xb, yb, d;
                loop_at(a, &xa, &ya, &d);
                loop_at(b, &xb, &yb, &d);
                double fa = (axis ? ya : xa) - level, fb = (axis ? yb : xb) - level;
                if (!((fa < 0) != (fb < 0)))
                    continue;
                for (int it = 0; it < 200 && b - a > 1e-17; it++) {
                    double m = 0.5 * (a + b), xm, ym;
                    loop_at(m, &xm, &ym, &d);
                    if (((axis ? ym : xm) - level < 0) == (fa < 0))
                        a = m;
                    else
                        b = m;
                }
                assert_true(n < 63);
                cut[n++] = 0.5 * (a + b);
            }
        }
    cut[n++] = 1;
    qsort(cut, (size_t)n, sizeof *cut, truth_cmp_double);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(12);
    assert_non_null(gl);
    tip p = {spec, uc, vc};
    gsl_function F = {tip_integrand, &p};
    double sum = 0;
    for (int k = 0; k + 1 < n; k++)
        sum += gsl_integration_glfixed(&F, cut[k], cut[k + 1], gl);
    gsl_integration_glfixed_table_free(gl);
    return -sum;
}

/* One filter and path: every pixel whose window sees only the loop
 * against the closed form, in the scene and its transpose, and the two
 * images against each other, within their bounds. */
static void check_loop(const aa_scene *s, const aa_scene *st, const char *f, int mode)
{
    aa_image a, ba, b, bb;
    aa_filter filt;
    assert_int_equal(aa_filter_parse(f, &filt), AA_OK);
    support_reference_mode(s, 17, 14, f, mode, &a, &ba);
    support_reference_mode(st, 14, 17, f, mode, &b, &bb);
    double worst = 0, tip77 = 0;
    /* rows whose window ends above the loop's crossing (y = 9.687) */
    for (int j = 0; j + 0.5 + filt.radius <= 9.68; j++)
        for (int i = 0; i < 17; i++) {
            double want = tip_value(f, i + 0.5, j + 0.5);
            if (i == 7 && j == 7)
                tip77 = want;
            support_check_value("loop tip", f, i, j, aa_pixel(&a, i, j)[0], *aa_pixel(&ba, i, j),
                                want, 1e-15, &worst);
            support_check_value("transposed loop tip", f, j, i, aa_pixel(&b, j, i)[0],
                                *aa_pixel(&bb, j, i), want, 1e-15, &worst);
        }
    for (int j = 0; j < 14; j++)
        for (int i = 0; i < 17; i++) {
            double d = fabs(aa_pixel(&a, i, j)[0] - aa_pixel(&b, j, i)[0]);
            if (!(d <= *aa_pixel(&ba, i, j) + *aa_pixel(&bb, j, i) + 1e-15))
                fail_msg("loop under %s, pixel (%d, %d): %.17g, transposed %.17g", f, i, j,
                         aa_pixel(&a, i, j)[0], aa_pixel(&b, j, i)[0]);
            worst = fmax(worst, d);
        }
    print_message("loop tip %-22s mode %d: pixel (7, 7) %.17g, max difference %.2e\n", f, mode,
                  tip77, worst);
    aa_image_free(&a);
    aa_image_free(&ba);
    aa_image_free(&b);
    aa_image_free(&bb);
}

/* The tip against its closed form and the transposed scene (where it
 * turns in x, a different path), also one piece at a time
 * (AA__TRUTH_CROWD): a turning point just outside an interval between
 * breakpoints. */
static void test_loop_tip(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const char *const specs[] = {"mitchell:b=0.2,c=0.7", "box", "tent:r=1", NULL};
    aa_scene *s = loop_scene(0), *st = loop_scene(1);
    for (const char *const *f = specs; *f; f++)
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD)
            check_loop(s, st, *f, mode);
    aa_scene_free(s);
    aa_scene_free(st);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_half_planes_separable),
                                       cmocka_unit_test(test_half_planes_radial),
                                       cmocka_unit_test(test_centred_disks),
                                       cmocka_unit_test(test_abutting_squares),
                                       cmocka_unit_test(test_sums),
                                       cmocka_unit_test(test_same_filters),
                                       cmocka_unit_test(test_loop_tip)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
