/* tier: full */
/*
 * test_bezstroke_filters.c: the reference under every filter, and the
 * methods, on a Bezier arc's stroke (exact offset pieces, AA_PIECE_OFFSET),
 * against the tube formula (width x arc length, the arc length by GSL's
 * QAG here) as in test_bezstroke.c.  Full tier: the Gaussian's and the
 * cone's references of offset pieces go to QAG column by column (about 15 s
 * here).
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
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

static void must(int st)
{
    if (st)
        fail_msg("status %d: %s", st, aa_last_error());
}

/* A cubic in control points c (x0 y0 x1 y1 x2 y2 x3 y3). */
static void bez(const double *c, double t, double *x, double *y, double *dx, double *dy)
{
    double s = 1 - t;
    for (int k = 0; k < 2; k++) {
        double p0 = c[k], p1 = c[2 + k], p2 = c[4 + k], p3 = c[6 + k];
        double v = s * s * s * p0 + 3 * s * s * t * p1 + 3 * s * t * t * p2 + t * t * t * p3;
        double d = 3 * (s * s * (p1 - p0) + 2 * s * t * (p2 - p1) + t * t * (p3 - p2));
        if (k == 0)
            *x = v, *dx = d;
        else
            *y = v, *dy = d;
    }
}

static double speed(double t, void *c)
{
    double x, y, dx, dy;
    bez(c, t, &x, &y, &dx, &dy);
    return hypot(dx, dy);
}

static double arc_length(const double *c)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function f = {speed, (void *)c};
    double r = NAN, err;
    gsl_set_error_handler_off();
    int st = gsl_integration_qag(&f, 0, 1, 1e-13, 0, 1000, GSL_INTEG_GAUSS61, w, &r, &err);
    if (st || !(err < 1e-13))
        fail_msg("arc length: QAG status %d, estimate %g", st, err);
    gsl_integration_workspace_free(w);
    return r;
}

static aa_scene *outline_scene(const aa_path *in, const aa_stroke_style *st, const double *m)
{
    aa_path out = {0};
    must(aa_stroke_outline(in, st, &out));
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    must(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO));
    must(aa_path_fill(&out, m, s));
    must(aa_scene_finish(s));
    aa_path_free(&out);
    return s;
}

/* The box, tent and Gaussian references of the gentle arc's butt stroke
 * sum to the tube formula's area (their translates sum to 1: exactly for
 * the box and the tent, for the Gaussian of s = 1.2 within 2 exp(-2 pi^2
 * s^2) ~ 1e-12 relative; the shape is 16 pixels, 13 s, inside the view, so
 * that no weight is lost): the reference's other paths (the tent: QAG; the Gaussian: its
 * panels and QAG) on offset pieces.  The cone's translates do not sum to 1:
 * its reference is only required to keep its bounds (the crossings of its
 * circle found by sampling). */
static void test_filters(void **state)
{
    (void)state;
    const double c[8] = {0.25, 0.5, 0.35, 0.35, 0.65, 0.65, 0.75, 0.5};
    double w = 0.04, want = w * arc_length(c);
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    must(aa_path_move_to(&p, c[0], c[1]));
    must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
    aa_scene *s = outline_scene(&p, &st, NULL);
    const char *filters[] = {"box", "tent:r=1", "gauss:s=1.2", "cone:r=1"};
    for (int k = 0; k < 4; k++) {
        support_view v = {.w = 64, .h = 64, .threads = 0, .filter = filters[k]};
        aa_image im, bound;
        support_reference(s, &v, &im, &bound, NULL);
        double got = support_channel_mean(&im, 0), worst = 0;
        for (int j = 0; j < 64; j++)
            for (int i = 0; i < 64; i++)
                worst = fmax(worst, aa_pixel(&bound, i, j)[0]);
        print_message("%-12s area %.15f, want %.15f (%.1e), largest bound %.1e\n", filters[k],
                      got, want, got - want, worst);
        if ((k < 3 && !(fabs(got - want) < 1e-12)) || !(worst <= 1e-12))
            fail_msg("%s: area %.17g, want %.17g, bound %g", filters[k], got, want, worst);
        aa_image_free(&im);
        aa_image_free(&bound);
    }
    /* the methods take the scene or refuse it by name; those that take it
     * come near the reference (sampling error only) */
    const char *methods[] = {"point",     "supersample:n=4", "jitter",    "adaptive",
                             "crowtiler", "conetable",       "crowtable", "feibushtex",
                             "area",      "trio",            "cairo"};
    support_view v = {.w = 32, .h = 32, .threads = 1};
    aa_image ref;
    support_reference(s, &v, &ref, NULL, NULL);
    for (size_t k = 0; k < sizeof methods / sizeof *methods; k++) {
        aa_image im;
        const char *f = strncmp(methods[k], "conetable", 9) == 0   ? "cone:r=1"
                        : strncmp(methods[k], "crowtiler", 9) == 0 ? "tent:r=1"
                        : strncmp(methods[k], "feibushtex", 10) == 0 ? "gauss:s=0.5"
                                                                     : NULL;
        support_view mv = {.w = 32, .h = 32, .threads = 1, .filter = f, .seed = 1};
        int stt = support_render_view(methods[k], s, &mv, &im, NULL);
        if (stt) {
            print_message("%-16s refused: %s\n", methods[k], aa_last_error());
            assert_true(strlen(aa_last_error()) > 0);
            continue;
        }
        aa_image fref;
        if (f)
            support_reference(s, &mv, &fref, NULL, NULL);
        double e = support_rmse(&im, f ? &fref : &ref);
        if (f)
            aa_image_free(&fref);
        print_message("%-16s rmse %.3g\n", methods[k], e);
        assert_true(e < 0.1);
        aa_image_free(&im);
    }
    aa_image_free(&ref);
    aa_scene_free(s);
    aa_path_free(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_filters)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
