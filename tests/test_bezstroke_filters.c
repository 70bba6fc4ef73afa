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
    double w = 0.04, want = w * oracle_cubic_length(c, 0, 1);
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    must(aa_path_move_to(&p, c[0], c[1]));
    must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, NULL);
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
