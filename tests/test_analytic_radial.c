/*
 * test_analytic_radial.c: `analytic` under the radially symmetric
 * polynomial filters radial:k=K,r=R (algorithms/analytic.c, "Radial
 * filters"), against answers that are not the method's own:
 *
 *  - the exact reference of the harness's truth path (aa_truth_render:
 *    QAG along y of the rows' closed-form integrals, itself checked
 *    against GSL's 2-D quadrature of the filter's definition in
 *    tests/test_radial.c), within 1e-12 per pixel and channel, on crow
 *    (quadratic arcs), crow raised to cubics, the cubic scene of scenes.c,
 *    a polygon (a concave pentagon), two overlapping layers of distinct
 *    colours (a self-crossing even-odd cubic path in front of a nonzero
 *    path of two crossing quadratic loops), a shipped SVG of lines and
 *    Bezier arcs (curves.svg) and one of elliptical arcs (arcs.svg), under
 *    k = 1, 2, 3 and radii from 0.6 to 2.3 px, at 1 and 2 threads
 *    (bit-identical);
 *  - closed forms: a half-plane whose edge passes through a pixel centre
 *    gives exactly 1/2 there at any angle (the weight is even about every
 *    line through its centre); a pixel whose disc lies inside a white
 *    square gives 1 (the volume); a disk (elliptical arcs) of radius a
 *    centred on a pixel centre gives 1 - (1 - a^2/R^2)^(K+1).
 * A white region's image does not sum to its area under a radial filter
 * (its integer translates do not sum to 1), so that check of
 * tests/test_analytic.c does not apply.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const char *const filters[] = {"radial:k=1,r=1", "radial", "radial:k=3,r=2.3",
                                      "radial:k=2,r=0.6", NULL};

/* analytic within 1e-12 of the reference on s (pattern units) at w x h
 * under every filter of the list, at 1 and 2 threads. */
static void against(const char *what, const aa_scene *s, int w, int h,
                    const char *const *list)
{
    for (const char *const *f = list; *f; f++)
        support_method_against_reference("analytic", what, s, w, h, *f);
}

static void against_reference(const char *what, const aa_scene *s, int w, int h)
{
    against(what, s, w, h, filters);
}

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) test_crow runs a declared subset: crow under two of the
 * filters and crow raised to cubics under the other two, every filter
 * reached, as every other case here takes every filter.  The sanitizers
 * find memory and undefined-behaviour errors along the paths taken, and
 * another filter on the same scene takes the same paths with other numbers
 * (tests/README.md, "Tiers", says how that was checked); the plain build
 * runs every case. */

static void test_crow(void **state)
{
    (void)state;
    aa_scene *crow = scenes_pattern("crow");
    against("crow", crow, 32, 30,
            SAN_SUBSET ? FILTERS("radial:k=1,r=1", "radial:k=2,r=0.6") : filters);
    aa_scene *up = scenes_elevated(crow);
    against("crow raised to cubics", up, 24, 24,
            SAN_SUBSET ? FILTERS("radial", "radial:k=3,r=2.3") : filters);
    aa_scene_free(up);
    aa_scene_free(crow);
}

static void test_cubics_and_polygon(void **state)
{
    (void)state;
    aa_scene *c = scenes_cubics();
    against_reference("cubic arcs", c, 22, 20);
    aa_scene_free(c);
    const double pent[] = {0.1, 0.12, 0.9, 0.2, 0.45, 0.5, 0.85, 0.9, 0.08, 0.8};
    aa_scene *p = scenes_polygon(pent, 5, (aa_rgb){{1, 0.5, 0.25}}, (aa_rgb){{0, 0.1, 0.2}},
                                 AA_FILL_NONZERO);
    against_reference("pentagon", p, 17, 15);
    aa_scene_free(p);
}

/* As test_analytic.c's overlapping layers: every channel apart. */
static void test_two_layers(void **state)
{
    (void)state;
    aa_scene *s = scenes_overlapping_layers();
    against_reference("two layers", s, 25, 23);
    aa_scene_free(s);
}

static void test_svg(void **state)
{
    (void)state;
    aa_scene *s = scenes_svg_at("curves", 20);
    against_reference("curves.svg", s, 20, 20);
    aa_scene_free(s);
}

/* Closed forms, the scene placed in pixels (support_render takes pattern
 * units: a 16 x 16 view of the unit square scaled by 1/16). */
static void test_closed_forms(void **state)
{
    (void)state;
    const int n = 16;
    const double angles[] = {0.0, 0.37, M_PI / 4, 1.3, 2.9};
    for (const char *const *f = filters; *f; f++) {
        double worst = 0.0;
        for (int q = 0; q < 5; q++) {
            /* through the centre of pixel (7, 8): (7.5, 8.5) px */
            aa_scene *s = scenes_half_plane_of(7.5 / n, 8.5 / n, angles[q], 4.0,
                                               (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}});
            aa_image a;
            support_render("analytic", s, *f, n, n, 1, &a, NULL);
            double d = fabs(aa_pixel(&a, 7, 8)[0] - 0.5);
            /* the scene's corners 4 units out are rounded: the line moves
             * by up to 4 n 2^-52 px, the value by that times the row's
             * largest mass, under 2 / R */
            if (!(d <= 1e-14))
                fail_msg("half-plane through the centre at %g rad under %s: %.17g", angles[q],
                         *f, aa_pixel(&a, 7, 8)[0]);
            worst = fmax(worst, d);
            aa_image_free(&a);
            aa_scene_free(s);
        }
        /* a white square of side 10 px from (3, 3) px: pixel (7, 7)'s disc,
         * radius at most 2.3 about (7.5, 7.5), lies inside */
        const double r[1][4] = {{3.0 / n, 3.0 / n, 13.0 / n, 13.0 / n}};
        aa_scene *s = scenes_rects(r, 1);
        aa_image a;
        support_render("analytic", s, *f, n, n, 1, &a, NULL);
        double v = aa_pixel(&a, 7, 7)[0];
        if (!(fabs(v - 1.0) <= 1e-14))
            fail_msg("inside a square under %s: %.17g", *f, v);
        print_message("%-18s half-planes through the centre: max |v - 1/2| %.1e; inside a "
                      "square %+.1e\n",
                      *f, worst, v - 1.0);
        aa_image_free(&a);
        aa_scene_free(s);
    }
}

/* Elliptical arcs: arcs.svg (a circle, a turned and scaled ellipse, a
 * rounded rectangle, paths of `A` and `a`, an even-odd ring), and disks
 * centred on a pixel centre, whose value is the filter's mass within
 * their radius a: in polar coordinates, with t = r^2/R^2,
 * (K + 1) int_0^(a^2/R^2) (1 - t)^K dt = 1 - (1 - a^2/R^2)^(K + 1). */
static void test_arcs(void **state)
{
    (void)state;
    aa_scene *s = scenes_svg_at("arcs", 20);
    against_reference("arcs.svg", s, 20, 20);
    aa_scene_free(s);
    const int n = 13;
    const double frac[] = {0.2, 0.5, 0.77, 0.999, 1.4};
    for (const char *const *f = filters; *f; f++) {
        aa_filter filt;
        assert_int_equal(aa_filter_parse(*f, &filt), AA_OK);
        double K = filt.spec.v[0], R = filt.spec.v[1], worst = 0.0;
        for (int q = 0; q < 5; q++) {
            double a = frac[q] * R, t = fmin(1.0, a * a / (R * R));
            double want = 1.0 - pow(1.0 - t, K + 1.0), cx = 6.5 / n, cy = 6.5 / n, ra = a / n;
            aa_scene *d = aa_scene_new((aa_rgb){{0, 0, 0}});
            assert_non_null(d);
            assert_int_equal(aa_scene_layer(d, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_scene_move_to(d, cx + ra, cy), AA_OK);
            assert_int_equal(
                aa_scene_arc_to(d, cx, cy, ra, 0, 0, ra, 0, 2 * M_PI, cx + ra, cy), AA_OK);
            assert_int_equal(aa_scene_close(d), AA_OK);
            assert_int_equal(aa_scene_finish(d), AA_OK);
            aa_image img;
            support_render("analytic", d, *f, n, n, 1, &img, NULL);
            double v = aa_pixel(&img, 6, 6)[0];
            if (!(fabs(v - want) <= 1e-14))
                fail_msg("centred disk of radius %g under %s: %.17g, closed form %.17g", a, *f,
                         v, want);
            worst = fmax(worst, fabs(v - want));
            aa_image_free(&img);
            aa_scene_free(d);
        }
        print_message("%-18s centred disks: max |v - (1 - (1 - a^2/R^2)^(K+1))| %.1e\n", *f,
                      worst);
    }
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crow),        cmocka_unit_test(test_cubics_and_polygon),
        cmocka_unit_test(test_two_layers),  cmocka_unit_test(test_svg),
        cmocka_unit_test(test_closed_forms), cmocka_unit_test(test_arcs)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
