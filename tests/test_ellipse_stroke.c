/*
 * test_ellipse_stroke.c: strokes of elliptical arcs that are not circles
 * (harness/core/stroke.c; their offset curves and evolutes as exact pieces
 * on the base curve c + u cos t + v sin t: harness/core/offset.c,
 * AA_OFFSET_ELLIPSE) against answers derived here, independently of the
 * code under test:
 *
 *  - the tube formula: a stroke whose half width h is under the least
 *    curvature radius b^2/a of an ellipse of semi-axes a > b sweeps width
 *    x length (the normals do not cross; a closed convex curve's outer and
 *    inner parallel curves enclose A + P h + pi h^2 and A - P h + pi h^2);
 *    the full ellipse's perimeter by the Gauss-Kummer series
 *    P = pi (a + b) sum_n binom(1/2, n)^2 q^n, q = ((a - b)/(a + b))^2,
 *    a part's length by GSL's QAG (61-point Gauss-Kronrod, 1e-13) of
 *    |B'(t)| = sqrt(|u|^2 sin^2 t + |v|^2 cos^2 t - 2 (u.v) sin t cos t);
 *    the area by the box reference (aa_truth_render) of the outline filled
 *    into a scene, summed (a white shape's box reference sums to its area),
 *    to 1e-12; through a map m, |det m| times that; and butt dashes: width
 *    x the dashes' total length, laid out here from the perimeter;
 *  - a point-in-stroke oracle at random points (seeded) against the scene's
 *    own point query (aa_scene_colour_at, the non-zero winding of the
 *    outline's pieces), on thick strokes of thin ellipses whose offsets
 *    fold (h above the least curvature radius, and above b): a closed
 *    ellipse's stroke is the points within h of it (every such point lies
 *    on the normal at its nearest point); an open arc's with round caps
 *    the points within h of the arc (SVG 2: the normals, and the caps'
 *    half disks); with butt caps the points on a normal segment, the feet
 *    t where p - B(t) is perpendicular to B'(t) found here as the sign
 *    changes of (p - B) . B' at 4000 samples, bisected; points within 1e-7
 *    of the boundary skipped;
 *  - `area` (algorithms/area.c, area_offset.c) against the box reference,
 *    to 1e-12 per pixel, on folding, dashed and sheared ellipse strokes.
 *
 * Under the sanitizers (AA_SANITIZED) a declared subset: a quarter of the
 * oracle's random points in each check (test_oracle); tests/README.md,
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
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

static void must(int st)
{
    if (st)
        fail_msg("status %d: %s", st, aa_last_error());
}

/* An ellipse: centre c, conjugate semi-diameters u, v (e[0..5]). */
typedef struct ell {
    double cx, cy, ux, uy, vx, vy;
} ell;

/* The ellipse of semi-axes a, b turned by phi, its parameter shifted by
 * alpha (so that u and v are conjugate, not the axes, unless alpha = 0). */
static ell ellipse(double cx, double cy, double a, double b, double phi, double alpha)
{
    double ax = a * cos(phi), ay = a * sin(phi), bx = -b * sin(phi), by = b * cos(phi);
    ell e = {cx, cy, ax * cos(alpha) + bx * sin(alpha), ay * cos(alpha) + by * sin(alpha),
             -ax * sin(alpha) + bx * cos(alpha), -ay * sin(alpha) + by * cos(alpha)};
    return e;
}

static void at(const ell *e, double t, double *x, double *y, double *dx, double *dy)
{
    double c = cos(t), s = sin(t);
    *x = e->cx + e->ux * c + e->vx * s;
    *y = e->cy + e->uy * c + e->vy * s;
    if (dx)
        *dx = -e->ux * s + e->vx * c, *dy = -e->uy * s + e->vy * c;
}

/* The arc from t0 to t1 (after a move to its start); closed: and a close. */
static void add_arc(aa_path *p, const ell *e, double t0, double t1, int closed)
{
    double x, y;
    at(e, t0, &x, &y, NULL, NULL);
    must(aa_path_move_to(p, x, y));
    at(e, t1, &x, &y, NULL, NULL);
    must(aa_path_arc_to(p, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, t0, t1, x, y));
    if (closed)
        must(aa_path_close(p));
}

/* The stroke's outline filled (scenes_stroke_outline), the case being
 * about offset pieces. */
static aa_scene *outline_scene(const aa_path *in, const aa_stroke_style *st, const double *m)
{
    size_t noff;
    aa_scene *s = scenes_stroke_outline(in, st, m, &noff);
    assert_true(noff > 0);
    return s;
}

/* ---- lengths, independently ---- */

static double speed(double t, void *arg)
{
    double x, y, dx, dy;
    at(arg, t, &x, &y, &dx, &dy);
    return hypot(dx, dy);
}

static double arc_length(const ell *e, double t0, double t1)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    assert_non_null(w);
    gsl_function f = {speed, (void *)e};
    double r = NAN, err = INFINITY;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int st = gsl_integration_qag(&f, fmin(t0, t1), fmax(t0, t1), 1e-13, 0, 1000,
                                 GSL_INTEG_GAUSS61, w, &r, &err);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    assert_int_equal(st, 0);
    return r;
}

/* ---- the tube formula ---- */

static double box_area(aa_scene *s, int n)
{
    support_view v = {.w = n, .h = n, .threads = 0};
    aa_image im;
    support_reference(s, &v, &im, NULL, NULL);
    double a = support_channel_mean(&im, 0);
    aa_image_free(&im);
    return a;
}

static void check_area(const char *what, double got, double want)
{
    print_message("%-40s area %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) < 1e-12))
        fail_msg("%s: area %.17g, want %.17g", what, got, want);
}

static void test_tube(void **state)
{
    (void)state;
    const double a = 0.35, b = 0.2, w = 0.05; /* b^2/a = 0.114 > w/2 */
    const double shear[6] = {0.8, 0.15, -0.3, 0.6, 0.3, 0.1};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    for (int k = 0; k < 3; k++) {
        /* axes, conjugate diameters, and a turn the other way (t falling) */
        ell e = ellipse(0.5, 0.5, a, b, 0.5, k == 1 ? 0.7 : 0);
        aa_path p = {0};
        add_arc(&p, &e, k == 2 ? 2 * M_PI : 0, k == 2 ? 0 : 2 * M_PI, 1);
        aa_scene *s = outline_scene(&p, &st, NULL);
        char name[64];
        snprintf(name, sizeof name, "closed ellipse %d, w %g", k, w);
        check_area(name, box_area(s, 64), w * oracle_ellipse_perimeter(a, b));
        aa_scene_free(s);
        /* the stroke in user space, its outline mapped (SVG) */
        s = outline_scene(&p, &st, shear);
        snprintf(name, sizeof name, "closed ellipse %d, sheared", k);
        check_area(name, box_area(s, 64), fabs(shear[0] * shear[3] - shear[1] * shear[2]) * w *
                                             oracle_ellipse_perimeter(a, b));
        aa_scene_free(s);
        aa_path_free(&p);
    }
    /* open arcs, butt caps: width x the arc's length */
    const double arcs[3][2] = {{0.3, 2.9}, {-1.0, 4.2}, {5.5, 1.0}};
    for (int k = 0; k < 3; k++) {
        ell e = ellipse(0.5, 0.5, a, b, -0.4, 0.3);
        aa_path p = {0};
        add_arc(&p, &e, arcs[k][0], arcs[k][1], 0);
        aa_scene *s = outline_scene(&p, &st, NULL);
        char name[64];
        snprintf(name, sizeof name, "arc %g .. %g, butt", arcs[k][0], arcs[k][1]);
        check_area(name, box_area(s, 64), w * arc_length(&e, arcs[k][0], arcs[k][1]));
        aa_scene_free(s);
        aa_path_free(&p);
    }
}

/* Butt dashes on a closed ellipse under the tube condition: w x the dashes'
 * total length, a pattern (on, off) with offset o covering, of [0, P], the
 * parts of [j (on + off) - o, j (on + off) - o + on]. */
static void test_dashes(void **state)
{
    (void)state;
    const double a = 0.35, b = 0.2, w = 0.03, P = oracle_ellipse_perimeter(a, b);
    const double dash[3][3] = {{0.07, 0.03, 0.0}, {0.11, 0.05, 0.04}, {0.2, 0.013, -0.31}};
    for (int k = 0; k < 3; k++) {
        double on = dash[k][0], off = dash[k][1], o = dash[k][2], per = on + off, total = 0;
        double o0 = fmod(o, per);
        if (o0 < 0)
            o0 += per;
        for (int j = 0; j * per - o0 < P; j++) {
            double lo = fmax(j * per - o0, 0), hi = fmin(j * per - o0 + on, P);
            if (hi > lo)
                total += hi - lo;
        }
        aa_path p = {0};
        ell e = ellipse(0.5, 0.5, a, b, 0.25, 0.4);
        add_arc(&p, &e, 0, 2 * M_PI, 1);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = w;
        st.dash = dash[k];
        st.ndash = 2;
        st.dashoffset = o;
        aa_scene *s = outline_scene(&p, &st, NULL);
        char name[64];
        snprintf(name, sizeof name, "dashes %g %g offset %g", on, off, o);
        check_area(name, box_area(s, 64), w * total);
        aa_scene_free(s);
        aa_path_free(&p);
    }
}

/* ---- the point-in-stroke oracle ---- */

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static void ell_at(const void *e, double t, double *x, double *y, double *dx, double *dy)
{
    at(e, t, x, y, dx, dy);
}

/* The least distance from p to the arc t0 .. t1 of e at the t where p - B
 * is perpendicular to B' (sign changes of (p - B) . B' at 4000 samples,
 * bisected), and at its ends when `ends` (oracle_curve_feet). */
static double feet(const ell *e, double t0, double t1, double px, double py, int ends, double h,
                   int *unsure)
{
    return oracle_curve_feet(ell_at, e, t0, t1, 4000, px, py, ends, h, unsure);
}

typedef struct arc_ctx {
    const ell *e;
    double t0, t1;
    int ends;
    double h;
} arc_ctx;

static double arc_distance(const void *vctx, double px, double py, int *unsure)
{
    const arc_ctx *c = vctx;
    return feet(c->e, c->t0, c->t1, px, py, c->ends, c->h, unsure);
}

/* The stroke of the arc t0 .. t1 of e (closed: the closed subpath), width
 * w, round or butt caps, through map m (NULL: none), at npts points. */
static void oracle(const char *what, const ell *e, double t0, double t1, int closed, double w,
                   int round, const double *m, int npts)
{
    aa_path p = {0};
    add_arc(&p, e, t0, t1, closed);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (round)
        st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    aa_scene *s = outline_scene(&p, &st, m);
    double h = 0.5 * w, r = hypot(e->ux, e->uy) + hypot(e->vx, e->vy) + h;
    const double box[4] = {e->cx - r, e->cy - r, e->cx + r, e->cy + r};
    const arc_ctx ctx = {e, t0, t1, closed || round, h};
    /* the sanitizer build's subset (SAN_SUBSET): a quarter of the points,
     * whose time is the oracle's own (feet), not the point query's */
    support_stroke_check(what, s, box, h, m, SAN_SUBSET ? npts / 4 : npts, &rng, arc_distance,
                         &ctx);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_oracle(void **state)
{
    (void)state;
    /* b^2/a = 0.0103 and b = 0.06: every w here folds the inner offset */
    ell thin = ellipse(0.5, 0.5, 0.35, 0.06, 0.3, 0.0);
    ell conj = ellipse(0.5, 0.5, 0.3, 0.1, -0.6, 1.1);
    const double shear[6] = {1.2, 0.3, -0.4, 0.7, 0.1, -0.2};
    oracle("thin, closed, w 0.05", &thin, 0, 2 * M_PI, 1, 0.05, 0, NULL, 3000);
    oracle("thin, closed, w 0.3", &thin, 0, 2 * M_PI, 1, 0.3, 0, NULL, 3000);
    oracle("thin, closed, w 0.3, sheared", &thin, 0, 2 * M_PI, 1, 0.3, 0, shear, 3000);
    oracle("conjugate, closed, w 0.4", &conj, 1.0, 1.0 - 2 * M_PI, 1, 0.4, 0, NULL, 3000);
    oracle("thin arc, round caps, w 0.2", &thin, -0.5, 3.5, 0, 0.2, 1, NULL, 3000);
    oracle("thin arc, butt caps, w 0.2", &thin, -0.5, 3.5, 0, 0.2, 0, NULL, 3000);
    oracle("conjugate arc back, butt, w 0.25", &conj, 2.0, -2.5, 0, 0.25, 0, NULL, 3000);
    oracle("conjugate arc, round, w 0.12", &conj, 0.1, 1.7, 0, 0.12, 1, shear, 3000);
}

/* ---- area against the reference ---- */

static void against_reference(const char *what, const ell *e, double t0, double t1, int closed,
                              const aa_stroke_style *st, const double *m, int n)
{
    aa_path p = {0};
    add_arc(&p, e, t0, t1, closed);
    aa_scene *s = outline_scene(&p, st, m);
    support_view v = {.w = n, .h = n, .threads = 0};
    aa_image ref, a1, bands;
    support_reference(s, &v, &ref, NULL, NULL);
    support_render("area", s, "box", n, n, 1, &a1, NULL);
    support_render("area:integrator=bands", s, "box", n, n, 1, &bands, NULL);
    int wi, wj;
    double d = support_max_diff(&a1, &ref, &wi, &wj), db = support_max_diff(&bands, &ref, NULL, NULL);
    print_message("%-40s max |area - reference| %.1e (at %d,%d), bands %.1e\n", what, d, wi, wj,
                  db);
    if (!(d <= 1e-12) || !(db <= 1e-12))
        fail_msg("%s: area off the reference by %g (bands %g)", what, d, db);
    aa_image_free(&ref);
    aa_image_free(&a1);
    aa_image_free(&bands);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_area(void **state)
{
    (void)state;
    ell thin = ellipse(0.5, 0.5, 0.35, 0.06, 0.3, 0.0);
    ell conj = ellipse(0.5, 0.5, 0.3, 0.15, -0.6, 1.1);
    const double shear[6] = {1.2, 0.3, -0.4, 0.7, 0.1, -0.2};
    const double dash[2] = {0.13, 0.05};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.04;
    against_reference("conjugate, closed, w 0.04", &conj, 0, 2 * M_PI, 1, &st, NULL, 48);
    st.width = 0.3;
    against_reference("thin, closed, w 0.3 (folds)", &thin, 0, 2 * M_PI, 1, &st, NULL, 48);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND, st.width = 0.15;
    against_reference("thin arc, round, w 0.15, sheared", &thin, -0.5, 3.5, 0, &st, shear, 48);
    st.dash = dash, st.ndash = 2, st.width = 0.05;
    against_reference("conjugate, dashed, round, w 0.05", &conj, 1, 1 - 2 * M_PI, 1, &st, NULL,
                      48);
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_tube), cmocka_unit_test(test_dashes),
                                       cmocka_unit_test(test_oracle),
                                       cmocka_unit_test(test_area)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
