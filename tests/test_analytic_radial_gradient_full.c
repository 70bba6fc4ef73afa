/* tier: full */
/*
 * test_analytic_radial_gradient_full.c: test_analytic_radial_gradient.c
 * with every scene under every filter, a stroked cubic and a larger image
 * (its header says what is checked).
 */
#define TIER_FULL 1
#include "test_analytic_radial_gradient.c"
