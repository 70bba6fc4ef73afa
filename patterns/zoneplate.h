/*
 * zoneplate.h: the zone plate's one-dimensional integrals (internal to the
 * library; the tests check them against quadrature).
 */
#ifndef AA_ZONEPLATE_H
#define AA_ZONEPLATE_H

#include "core.h"

#include <complex.h>

/* The largest k the pattern accepts. */
#define AA__ZONEPLATE_KMAX 1e6

/* G = integral of w(s) exp(i a (c + s)^2) ds over the line, w the 1-D
 * weight of filter f (box, tent, untruncated Gaussian), with a and c given
 * as unevaluated sums a_hi + a_lo, c_hi + c_lo (so that the phase a (c+s)^2
 * is exact to rounding even where it is large).  a > 0.  *bound (may be
 * NULL) gets a bound on the absolute error of G.  Returns AA_EINVAL for a
 * filter it does not know. */
int aa__zoneplate_1d(const aa_filter *f, double a_hi, double a_lo, double c_hi, double c_lo,
                     double complex *g, double *bound);

#endif
