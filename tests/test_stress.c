/*
 * test_stress.c: the stress suite's cheap cases pass, by name: the thin
 * slivers (a region 1e-9 px wide once lost `area` its whole value in
 * Catmull's integrater: the centroid of a thin region was computed with
 * cancellation and fell outside it), the degenerate polygons and the odd
 * sizes.  The expected values are the suite's long double evaluation of the
 * same scenes (stress.c), a path separate from truth.c and area.c.
 */
#include "bench.h"
#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

static void run_named(const char *name)
{
    for (size_t k = 0; k < aa_stress_count(); k++)
        if (!strcmp(aa_stress_name(k), name)) {
            aa_stress_result r;
            assert_int_equal(aa_stress_run_case(k, 2, &r), AA_OK);
            if (!r.pass)
                fail_msg("%s: reference %.3g (bound %.3g), area %.3g (bound %.3g), %zu non-finite, "
                         "%zu out of range",
                         name, r.ref_err, r.ref_bound, r.area_err, r.area_bound, r.nonfinite,
                         r.out_of_range);
            assert_true(r.methods >= 6);
            return;
        }
    fail_msg("no stress case named %s", name);
}

static void test_slivers(void **state)
{
    (void)state;
    run_named("slivers 1e-9 px tall");
}

static void test_degenerate(void **state)
{
    (void)state;
    static const char *names[] = {"zero-area triangle",        "repeated vertices",
                                  "collinear points",          "edges on pixel boundaries",
                                  "edges through pixel centres", "zero-width spike on a square"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        run_named(names[k]);
}

static void test_sizes_and_moves(void **state)
{
    (void)state;
    run_named("crow 1x1");
    run_named("crow 7x3");
    run_named("crow kmax 1e-15");
    run_named("crow at t=1e6 moved 20,-1 px");
    /* stb_truetype asserted on a scene reaching above the image */
    run_named("star moved 12.3,-7.7 px over 1e6 frames");
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_slivers),
             cmocka_unit_test(test_degenerate),
             cmocka_unit_test(test_sizes_and_moves))
