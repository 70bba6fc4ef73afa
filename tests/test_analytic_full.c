/* tier: full */
/*
 * test_analytic_full.c: test_analytic.c with every scene under every
 * filter, at the larger sizes (its header says what is checked), without
 * the cases the quick tier checks the same way (its main).
 */
#define ANALYTIC_ALL 1
#include "test_analytic.c"
