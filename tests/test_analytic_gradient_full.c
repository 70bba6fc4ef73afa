/* tier: full */
/*
 * test_analytic_gradient_full.c: test_analytic_gradient.c's scenes under
 * the filters the quick tier leaves out, so that the two take every scene
 * under every filter (its header says what is checked); under the
 * sanitizers a declared subset (its "The filters each scene takes").
 */
#define TIER_FULL 1
#include "test_analytic_gradient.c"
