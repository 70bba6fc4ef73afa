/*
 * test_claims.c: the verdicts of the claims table (claims.c), so that a
 * changed number changes the verdict.  The known answers are the rules as
 * bench.h states them, worked out by hand at and around each margin:
 *
 *  - aa_claim_band_verdict: a ratio's 95% interval inside the claim's band
 *    is "yes", wholly outside "no", across an end (or not a number)
 *    "inconclusive"; the band's ends belong to it.
 *  - aa_claim_compare: errors a and b with a 10% margin: a better when
 *    a < 0.9 b, worse when b < 0.9 a, a tie between (0.9 exactly a tie).
 *  - aa_claim_tally: all cases holding "yes", none "no", a mix "partly",
 *    undecided cases without a mix "inconclusive".
 *  - The table: every row names specs that parse (the single edge's SVG
 *    file among them) and a claim past the end is refused.
 */
#include "bench.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

static void test_band(void **state)
{
    (void)state;
    /* claim 3's band, "approximately three" as 2 to 4.5 */
    assert_string_equal(aa_claim_band_verdict(2.0, 4.5, 2, 4.5), "yes");
    assert_string_equal(aa_claim_band_verdict(2.1, 2.4, 2, 4.5), "yes");
    assert_string_equal(aa_claim_band_verdict(1.999, 2.4, 2, 4.5), "inconclusive");
    assert_string_equal(aa_claim_band_verdict(4.4, 4.501, 2, 4.5), "inconclusive");
    assert_string_equal(aa_claim_band_verdict(1.0, 5.0, 2, 4.5), "inconclusive");
    assert_string_equal(aa_claim_band_verdict(1.5, 1.999, 2, 4.5), "no");
    assert_string_equal(aa_claim_band_verdict(4.501, 6, 2, 4.5), "no");
    /* claim 9's open band, more than 2 */
    assert_string_equal(aa_claim_band_verdict(2.2, 2.6, 2, INFINITY), "yes");
    assert_string_equal(aa_claim_band_verdict(1.9, 2.1, 2, INFINITY), "inconclusive");
    assert_string_equal(aa_claim_band_verdict(1.8, 1.95, 2, INFINITY), "no");
    /* an interval that could not be formed */
    assert_string_equal(aa_claim_band_verdict(NAN, NAN, 2, 4.5), "inconclusive");
    assert_string_equal(aa_claim_band_verdict(3, 2.5, 2, 4.5), "inconclusive");
}

static void test_compare(void **state)
{
    (void)state;
    assert_int_equal(aa_claim_compare(0.0899, 0.1, 0.1), -1);
    assert_int_equal(aa_claim_compare(0.0901, 0.1, 0.1), 0);
    assert_int_equal(aa_claim_compare(0.1, 0.1, 0.1), 0);
    assert_int_equal(aa_claim_compare(0.111, 0.1, 0.1), 0);  /* 0.1 > 0.0999 */
    assert_int_equal(aa_claim_compare(0.1112, 0.1, 0.1), 1); /* 0.1 < 0.10008 */
    assert_int_equal(aa_claim_compare(0, 0.1, 0.1), -1);
    assert_int_equal(aa_claim_compare(0, 0, 0.1), 0);
    /* without a margin any difference decides */
    assert_int_equal(aa_claim_compare(0.5, 0.50001, 0), -1);
}

static void test_tally(void **state)
{
    (void)state;
    assert_string_equal(aa_claim_tally(3, 0, 0), "yes");
    assert_string_equal(aa_claim_tally(0, 3, 0), "no");
    assert_string_equal(aa_claim_tally(2, 1, 0), "partly");
    assert_string_equal(aa_claim_tally(1, 1, 1), "partly");
    assert_string_equal(aa_claim_tally(2, 0, 1), "inconclusive");
    assert_string_equal(aa_claim_tally(0, 2, 1), "inconclusive");
    assert_string_equal(aa_claim_tally(0, 0, 3), "inconclusive");
    assert_string_equal(aa_claim_tally(0, 0, 0), "inconclusive");
}

static void test_table(void **state)
{
    (void)state;
    for (size_t k = 0; k < aa_claim_count(); k++)
        if (aa_claim_check(k) != AA_OK)
            fail_msg("%s", aa_last_error());
    assert_int_equal(aa_claim_check(aa_claim_count()), AA_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_band),
        cmocka_unit_test(test_compare),
        cmocka_unit_test(test_tally),
        cmocka_unit_test(test_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
