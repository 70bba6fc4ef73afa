/*
 * gradient_oracle.h: the pictures of the gradient tests' 2-D quadrature
 * oracles (tests/test_gradient_filter.c, tests/test_gradient_radial_filter.c),
 * written out here from SVG's and sRGB's definitions and sharing no code
 * with the harness: a black-to-white gradient, padded, its encoded value t
 * decoded by sRGB's curve, and the curves t = 0, T0, 1 where the picture's
 * derivatives jump (the cuts of the quadrature).  Units are pixels.
 */
#ifndef AABENCH_TESTS_GRADIENT_ORACLE_H
#define AABENCH_TESTS_GRADIENT_ORACLE_H

#include <gsl/gsl_integration.h>

/* sRGB's decoding threshold on the encoded value (IEC 61966-2-1) */
#define GO_T0 0.04045

/* The encoded values where the picture's derivatives jump: the ramp's
 * ends and the decoding's threshold. */
extern const double go_taus[3];

/* sRGB's decoding (IEC 61966-2-1), clamped to [0, 1]. */
double go_dec(double e);

/* qsort's order of doubles, ascending. */
int go_cmp_double(const void *a, const void *b);

/* The picture: linear (the rectangle rc = x0, y0, x1, y1 over a background
 * of linear value bg, t the projection on P1 P2) or radial (centre (cx,
 * cy), radius r, focus (fx, fy) with fr = 0, over the whole plane).  A
 * radial picture finds t by the focal form (focal set: the largest root of
 * (r^2 - |D|^2) t^2 + 2 (q - F).D t - |q - F|^2 = 0, D = C - F) or, with
 * the focus at the centre, by the centred form t = |q - C| / r; both forms
 * are kept because each test's figures were derived with its own. */
typedef struct go_pic {
    int radial, focal;
    double x1, y1, x2, y2; /* linear */
    double rc[4], bg;      /* linear: the rectangle, the background's linear value */
    double cx, cy, r;      /* radial */
    double fx, fy;         /* radial: the focus (the centre when not focal) */
} go_pic;

/* t at (x, y), not clamped. */
double go_pic_t(const go_pic *p, double x, double y);

/* The picture's linear value at (x, y). */
double go_pic_at(const go_pic *p, double x, double y);

/* Where the row y (or, with col, the column x = at) meets the curve t =
 * tau: the line's one point or the circle's two, written to out; returns
 * how many. */
int go_tau_meet(const go_pic *p, double tau, int col, double at, double *out);

/* The integral of F over [lo, hi] by GSL's QAGS (tolerances epsabs,
 * epsrel, at most 1000 subintervals in ws), piece by piece between the n
 * cuts (sorted here in place): the pieces between neighbouring cuts,
 * clamped to [lo, hi], summed in ascending order. */
double go_qags_cuts(const gsl_function *F, double *cut, int n, double lo, double hi,
                    double epsabs, double epsrel, gsl_integration_workspace *ws);

#endif
