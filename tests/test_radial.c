/*
 * test_radial.c: the radially symmetric polynomial filters radial:k=K,r=R
 * (patterns/README.md, "Filters"; harness/core/filter.c) and the reference
 * under them, against answers derived here from the definition
 *     w(u, v) = (K + 1) / (pi R^2) (1 - (u^2 + v^2) / R^2)^K,  u^2 + v^2 < R^2,
 * not from filter.c's closed forms:
 *
 *  - the filter: its 2-D weight against the definition; its rows' integrals
 *    against GSL's quadrature (QAG) of the definition along the row; its
 *    volume 1 both as GSL's nested quadrature of the definition and as the
 *    quadrature over v of the rows' whole integrals (the normalisation in
 *    polar coordinates: int_0^R (1 - r^2/R^2)^K 2 pi r dr = pi R^2 /
 *    (K + 1));
 *  - a half-plane whose edge passes through a pixel centre gives exactly
 *    1/2 there, at any angle (the weight is even about every line through
 *    its centre);
 *  - a disk of radius a centred on a pixel centre gives the mass within
 *    radius a, in polar coordinates 1 - (1 - a^2/R^2)^(K+1) (t = r^2/R^2:
 *    (K + 1) int_0^(a^2/R^2) (1 - t)^K dt);
 *  - half-planes at any angle and distance, and every pixel of a concave
 *    pentagon over two layers, against GSL's nested 2-D quadrature of the
 *    definition over the region (the outer integral in v split at the
 *    polygon's vertices, at the heights where its edges cross the circle
 *    of radius R, and at +-R; the inner one over each covered span of the
 *    row clipped to the disc's chord, the spans from the test's own
 *    crossing of the polygon's edges), within the pixel's bound plus the
 *    quadrature's estimate;
 * and the half-planes again through the one-piece-at-a-time path
 * (AA__TRUTH_CROWD).  Every bound is at most AA_TRUTH_BOUND.
 *
 * A white shape's image does not sum to its area under these filters: the
 * integer translates of a radial filter do not sum to 1 (their sum is
 * periodic with mean 1 and ripples), so that test of the separable
 * filters (tests/test_filter_truth.c) does not apply here.
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

static const char *const specs[] = {"radial:k=1,r=1", "radial", "radial:k=3,r=2.3",
                                    "radial:k=2,r=0.6", NULL};

/* ---- the filter as defined ---- */

typedef struct def {
    int k;
    double r;
    double v; /* the row (outer variable) */
    /* the region of the 2-D quadrature: a polygon of n points, nonzero */
    const double *xy;
    int n;
    double cx, cy; /* the pixel centre */
    gsl_integration_workspace *ws;
} def;

static def def_of(const char *spec)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(spec, &f), AA_OK);
    assert_false(aa_filter_is_separable(&f));
    assert_true(f.type == &aa_filter_radial);
    def d = {(int)f.spec.v[0], f.spec.v[1], 0, NULL, 0, 0, 0, NULL};
    assert_true(f.radius == d.r && f.lost == 0);
    return d;
}

static double def_w(const def *d, double u, double v)
{
    double q = 1 - (u * u + v * v) / (d->r * d->r);
    return q <= 0 ? 0 : (d->k + 1) / (M_PI * d->r * d->r) * pow(q, d->k);
}

static double row_fn(double u, void *pd)
{
    const def *d = pd;
    return def_w(d, u, d->v);
}

/* int over [u0, u1] of the row at v, by QAG (a polynomial on the chord:
 * the 21-point rule is exact, the estimate tiny). */
static double row_quad(def *d, double v, double u0, double u1, gsl_integration_workspace *ws,
                       double *err)
{
    double c2 = d->r * d->r - v * v;
    *err = 0;
    if (c2 <= 0)
        return 0;
    double c = sqrt(c2);
    u0 = fmax(u0, -c), u1 = fmin(u1, c);
    if (u1 <= u0)
        return 0;
    d->v = v;
    gsl_function F = {row_fn, d};
    double res, e;
    gsl_integration_qag(&F, u0, u1, 1e-17, 1e-15, 100, GSL_INTEG_GAUSS21, ws, &res, &e);
    *err = e;
    return res;
}

/* The spans of row y (absolute) inside the polygon (nonzero rule): the
 * crossings of its edges with their directions, sorted; returns the count
 * of spans written to sp (pairs). */
static int polygon_spans(const double *xy, int n, double y, double *sp)
{
    double xs[32];
    int dir[32], m = 0;
    for (int e = 0; e < n; e++) {
        double x0 = xy[2 * e], y0 = xy[2 * e + 1];
        double x1 = xy[2 * ((e + 1) % n)], y1 = xy[2 * ((e + 1) % n) + 1];
        if ((y0 <= y) == (y1 <= y))
            continue;
        xs[m] = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
        dir[m++] = y1 > y0 ? 1 : -1;
    }
    for (int a = 1; a < m; a++) /* insertion sort along x */
        for (int b = a; b > 0 && xs[b] < xs[b - 1]; b--) {
            double t = xs[b];
            xs[b] = xs[b - 1], xs[b - 1] = t;
            int q = dir[b];
            dir[b] = dir[b - 1], dir[b - 1] = q;
        }
    int wind = 0, ns = 0;
    for (int a = 0; a < m; a++) {
        int was = wind != 0;
        wind += dir[a];
        if (!was && wind)
            sp[2 * ns] = xs[a];
        else if (was && !wind)
            sp[2 * ns++ + 1] = xs[a];
    }
    return ns;
}

typedef struct outer {
    def *d;
    double err; /* the inner quadratures' estimates, summed (times the step) */
} outer;

/* In theta, v = R sin theta: the rows' masses close like (R - |v|)^(K +
 * 1/2) at +-R, which QAG in v meets only slowly (1.9e-7 estimated for a
 * pixel inside a shape under r=0.6); in theta they are smooth there. */
static double outer_fn(double th, void *po)
{
    outer *o = po;
    def *d = o->d;
    double v = d->r * sin(th), dv = d->r * cos(th);
    double sp[32], sum = 0;
    int ns = polygon_spans(d->xy, d->n, d->cy + v, sp);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
    for (int q = 0; q < ns; q++) {
        double e;
        sum += row_quad(d, v, sp[2 * q] - d->cx, sp[2 * q + 1] - d->cx, ws, &e);
        o->err = fmax(o->err, e);
    }
    gsl_integration_workspace_free(ws);
    return sum * dv;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The integral of the definition over the polygon, the filter centred on
 * (cx, cy): outer QAGP in theta between the breakpoints named in the
 * header.  An estimate above 1e-13 fails the test: the answer must be
 * sharper than the reference's promise to judge it. */
static double polygon_mass(def *d, const double *xy, int n, double cx, double cy, double *err)
{
    double pts[64];
    int np = 0;
    double R = d->r;
    pts[np++] = -R, pts[np++] = R, pts[np++] = 0;
    for (int e = 0; e < n; e++) {
        double x0 = xy[2 * e] - cx, y0 = xy[2 * e + 1] - cy;
        double x1 = xy[2 * ((e + 1) % n)] - cx, y1 = xy[2 * ((e + 1) % n) + 1] - cy;
        if (fabs(y0) < R)
            pts[np++] = y0;
        /* the edge's crossings of the circle: |P0 + t (P1 - P0)|^2 = R^2 */
        double dx = x1 - x0, dy = y1 - y0, A = dx * dx + dy * dy, B = x0 * dx + y0 * dy,
               C = x0 * x0 + y0 * y0 - R * R, disc = B * B - A * C;
        if (disc > 0)
            for (int sg = -1; sg <= 1; sg += 2) {
                double t = (-B + sg * sqrt(disc)) / A;
                if (t > 0 && t < 1)
                    pts[np++] = y0 + t * dy;
            }
    }
    qsort(pts, np, sizeof *pts, cmp_double);
    int m = 1;
    for (int q = 1; q < np; q++)
        if (pts[q] > pts[m - 1])
            pts[m++] = pts[q];
    for (int q = 0; q < m; q++) /* the heights as angles */
        pts[q] = asin(fmax(-1, fmin(1, pts[q] / R)));
    d->xy = xy, d->n = n, d->cx = cx, d->cy = cy;
    outer o = {d, 0};
    gsl_function F = {outer_fn, &o};
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(400);
    double res, e;
    gsl_integration_qagp(&F, pts, m, 1e-15, 1e-14, 400, ws, &res, &e);
    gsl_integration_workspace_free(ws);
    *err = e + 2 * R * o.err + 1e-15;
    if (!(*err <= 1e-13))
        fail_msg("2-D quadrature at (%g, %g): estimate %.2e", cx, cy, *err);
    return res;
}

/* ---- the filter ---- */

/* The whole row at v from filter.c. */
static double rowtot(double v, void *p)
{
    const aa_filter *f = p;
    return aa_filter_row_cdf(f, v, 2 * f->radius);
}

static void test_weight_rows_volume(void **state)
{
    (void)state;
    gsl_set_error_handler_off(); /* judged by the estimates */
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    for (const char *const *sp = specs; *sp; sp++) {
        def d = def_of(*sp);
        aa_filter f;
        assert_int_equal(aa_filter_parse(*sp, &f), AA_OK);
        double R = d.r, worst_w = 0, worst_row = 0;
        for (double v = -1.1 * R; v <= 1.1 * R; v += R / 7.3)
            for (double u = -1.1 * R; u <= 1.1 * R; u += R / 5.9) {
                double want = def_w(&d, u, v), got = aa_filter_weight2(&f, u, v);
                worst_w = fmax(worst_w, fabs(got - want));
                if (!(fabs(got - want) <= 1e-15 * (1 + want)))
                    fail_msg("%s w(%g, %g) = %.17g, definition %.17g", *sp, u, v, got, want);
                double e, q = row_quad(&d, v, -2 * R, u, ws, &e);
                double row = aa_filter_row_cdf(&f, v, u);
                worst_row = fmax(worst_row, fabs(row - q));
                if (!(fabs(row - q) <= e + 1e-15))
                    fail_msg("%s row v=%g up to u=%g: %.17g, quadrature %.17g +- %.1e", *sp, v,
                             u, row, q, e);
            }
        /* the volume, by the test's own 2-D quadrature of the definition
         * (a square containing the disc) */
        const double sq[] = {-2 * R, -2 * R, 2 * R, -2 * R, 2 * R, 2 * R, -2 * R, 2 * R};
        double e2, vol2 = polygon_mass(&d, sq, 4, 0, 0, &e2);
        /* and over v of the rows' whole integrals from filter.c (like
         * (R - |v|)^(K + 1/2) at the ends: QAG on 64 panels) */
        double vol = 0, e1 = 0;
        const int panels = 64;
        gsl_function F = {rowtot, &f};
        for (int q = 0; q < panels; q++) {
            double a = -R + 2 * R * q / panels, b = -R + 2 * R * (q + 1) / panels, res, e;
            gsl_integration_qag(&F, a, b, 1e-17, 1e-15, 200, GSL_INTEG_GAUSS61, ws, &res, &e);
            vol += res, e1 += e;
        }
        if (!(fabs(vol - 1) <= e1 + 1e-14) || !(fabs(vol2 - 1) <= e2 + 1e-14))
            fail_msg("%s: volume %.17g (+- %.1e) from the rows, %.17g (+- %.1e) by 2-D "
                     "quadrature of the definition",
                     *sp, vol, e1, vol2, e2);
        print_message("%-18s |w - def| %.1e, |row - QAG| %.1e, volume 1 %+.1e (rows), %+.1e "
                      "(2-D)\n",
                      *sp, worst_w, worst_row, vol - 1, vol2 - 1);
    }
    gsl_integration_workspace_free(ws);
}

/* ---- the reference ---- */


/* Half-planes whose edge passes through the centre of pixel (5, 4): 1/2. */
static void test_half_plane_centre(void **state)
{
    (void)state;
    const double angles[] = {0.0, 0.3, M_PI / 4, 1.1, M_PI_2, 2.7};
    for (const char *const *sp = specs; *sp; sp++)
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD) {
            double worst = 0;
            for (int q = 0; q < 6; q++) {
                aa_scene *s = scenes_half_plane_of(5.5, 4.5, angles[q], 40, white, black);
                aa_image img, bound;
                support_reference_mode(s, 11, 9, *sp, mode, &img, &bound);
                /* the stored edge's ends are rounded 40 px out: the line
                 * moves by up to 40 * 2^-52 px, times the row's largest
                 * mass (K + 1) B_K / (pi R) < 1.4 / R */
                support_check_value("half-plane through the centre", *sp, 5, 4,
                                    aa_pixel(&img, 5, 4)[0], *aa_pixel(&bound, 5, 4), 0.5,
                                    1e-14, &worst);
                aa_image_free(&img);
                aa_image_free(&bound);
                aa_scene_free(s);
            }
            print_message("half-planes through the centre %-18s mode %d: max |ref - 1/2| %.1e\n",
                          *sp, mode, worst);
        }
}

static void test_centred_disks(void **state)
{
    (void)state;
    const double cx = 6.5, cy = 5.5, frac[] = {0.25, 0.5, 0.77, 0.999, 1.3};
    for (const char *const *sp = specs; *sp; sp++) {
        def d = def_of(*sp);
        double worst = 0;
        for (int q = 0; q < 5; q++) {
            double a = frac[q] * d.r, t = fmin(a * a / (d.r * d.r), 1);
            double want = 1 - pow(1 - t, d.k + 1);
            aa_scene *s = scenes_disk(cx, cy, a);
            aa_image img, bound;
            support_reference_mode(s, 13, 11, *sp, 0, &img, &bound);
            support_check_value("centred disk", *sp, 6, 5, aa_pixel(&img, 6, 5)[0],
                                *aa_pixel(&bound, 6, 5), want, 1e-15, &worst);
            aa_image_free(&img);
            aa_image_free(&bound);
            aa_scene_free(s);
        }
        print_message("centred disks %-18s: max |ref - (1 - (1 - a^2/R^2)^(K+1))| %.1e\n", *sp,
                      worst);
    }
}

/* Half-planes at any distance, against the 2-D quadrature. */
static void test_half_planes(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const int w = 10, h = 8;
    const double px = 4.83, py = 3.27, angles[] = {0.0, 0.41, 2.3};
    for (const char *const *sp = specs; *sp; sp++)
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode += AA__TRUTH_CROWD) {
            def d = def_of(*sp);
            double worst = 0;
            for (int q = 0; q < 3; q++) {
                double an = angles[q], L = 40, dx = sin(an), dy = cos(an), nx = dy, ny = -dx;
                const double xy[] = {px - L * dx,          py - L * dy,
                                     px + L * dx,          py + L * dy,
                                     px + L * dx + L * nx, py + L * dy + L * ny,
                                     px - L * dx + L * nx, py - L * dy + L * ny};
                aa_scene *s = scenes_polygon(xy, 4, white, black, AA_FILL_NONZERO);
                aa_image img, bound;
                support_reference_mode(s, w, h, *sp, mode, &img, &bound);
                for (int j = 0; j < h; j++)
                    for (int i = (j * 3) % 2; i < w; i += 2) {
                        double e, want = polygon_mass(&d, xy, 4, i + 0.5, j + 0.5, &e);
                        support_check_value("half-plane", *sp, i, j, aa_pixel(&img, i, j)[0],
                                            *aa_pixel(&bound, i, j), want, e, &worst);
                    }
                aa_image_free(&img);
                aa_image_free(&bound);
                aa_scene_free(s);
            }
            print_message("half-planes %-18s mode %d: max |ref - 2-D quadrature| %.1e\n", *sp,
                          mode, worst);
        }
}

/* A concave pentagon (white) and a triangle apart from it (another
 * colour, a layer of its own) on black: every pixel and channel against the
 * quadrature of the two regions, weighed by their colours. */
static void test_polygons(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    const int w = 12, h = 10;
    const double pent[] = {2.3, 1.7, 9.1, 2.45, 5.2, 4.9, 8.7, 8.3, 1.9, 7.6};
    const double tri[] = {9.6, 4.4, 11.4, 9.2, 8.9, 9.6};
    const aa_rgb grey = {{0.25, 0.5, 0.75}};
    for (const char *const *sp = specs; *sp; sp++) {
        def d = def_of(*sp);
        aa_scene *s = aa_scene_new(black);
        assert_non_null(s);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        scenes_path(s, pent, 5);
        assert_int_equal(aa_scene_layer(s, grey, AA_FILL_NONZERO), AA_OK);
        scenes_path(s, tri, 3);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image img, bound;
        support_reference_mode(s, w, h, *sp, 0, &img, &bound);
        double worst = 0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double e1, e2;
                double m1 = polygon_mass(&d, pent, 5, i + 0.5, j + 0.5, &e1);
                double m2 = polygon_mass(&d, tri, 3, i + 0.5, j + 0.5, &e2);
                for (int c = 0; c < 3; c++)
                    support_check_value("pentagon and triangle", *sp, i, j, aa_pixel(&img, i, j)[c],
                                *aa_pixel(&bound, i, j), m1 + grey.c[c] * m2, e1 + e2, &worst);
            }
        print_message("pentagon and triangle %-18s: max |ref - 2-D quadrature| %.1e\n", *sp,
                      worst);
        aa_image_free(&img);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_weight_rows_volume),
                                       cmocka_unit_test(test_half_plane_centre),
                                       cmocka_unit_test(test_centred_disks),
                                       cmocka_unit_test(test_half_planes),
                                       cmocka_unit_test(test_polygons)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
