/* tier: full */
/*
 * test_analytic_gradient_full.c: test_analytic_gradient.c with every scene
 * under every filter (its header says what is checked).
 */
#define ANALYTIC_GRADIENT_ALL 1
#include "test_analytic_gradient.c"
