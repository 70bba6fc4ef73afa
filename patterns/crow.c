/*
 * crow.c: Crow's parabolic moire pattern (Crow 1976, ch. 2, figs. 2.9-2.14),
 * exactly as patterns/README.md, `crow`, defines it.
 *
 * N nearly parallel parabolic arcs x_k(y) = a_k + c_k (y - 1/2)^2 on
 * 0 <= y <= 1, curvature c_k = C (1 - k/(N-1)) falling linearly to zero from
 * left to right, spacing g_k falling linearly from gap0 to gap1; the bands
 * between arcs 2m and 2m+1 are white, the rest black.  Each arc is one
 * quadratic Bezier arc, exactly: from (a + c/4, 0) through the control point
 * (a - c/4, 1/2) to (a + c/4, 1), whose y is linear in the parameter so x is
 * the same quadratic in y.  Each white band is one closed path (arc 2m down,
 * the bottom y = 1, arc 2m+1 up, the top y = 0).
 *
 * Domain: N even, 2 <= N <= CROW_MAX_CURVES; gaps positive; and the arcs
 * never touch: x_{k+1}(y) - x_k(y) = g_k - (C/(N-1)) (y - 1/2)^2 > 0 on
 * [0, 1], which for C >= 0 is g_k - C/(4(N-1)) > 0 (closest at y = 0 and
 * y = 1) and for C < 0 is g_k > 0 (closest at mid-height).
 *
 * CROW_MAX_CURVES = 65536 bounds the scene (about 10 MB of edges and
 * pieces, and a reference that must handle every arc crossing every row):
 * larger values are refused rather than exhausting memory.
 *
 * Known answer: the total white area is sum over m of the integral over y
 * of (x_{2m+1}(y) - x_{2m}(y)) = sum_m [g_{2m} - (c_{2m} - c_{2m+1})/12],
 * which a 1x1 box reference must equal (tests/test_truth.c).
 */
#include "patterns.h"

#include <math.h>

#define CROW_MAX_CURVES 65536

enum { CURVES, KMAX, GAP0, GAP1 };

static const aa_param crow_params[] = {
    {"curves", AA_PARAM_INT, 96, 2, CROW_MAX_CURVES, 0, NULL,
     "number of arcs N: even, 2 to 65536"},
    {"kmax", AA_PARAM_REAL, 0.6, -1e3, 1e3, 0, NULL,
     "curvature coefficient C of the leftmost arc"},
    {"gap0", AA_PARAM_REAL, 4.0 / 256.0, 0.0, 1e3, 1, NULL,
     "spacing of arcs 0 and 1 at mid-height (pattern units)"},
    {"gap1", AA_PARAM_REAL, 0.5 / 256.0, 0.0, 1e3, 1, NULL,
     "spacing of arcs N-2 and N-1 at mid-height (pattern units)"},
    {0}};

static double gap(const double *p, int k)
{
    int n = (int)p[CURVES];
    if (n == 2)
        return p[GAP0];
    return p[GAP0] + (p[GAP1] - p[GAP0]) * k / (double)(n - 2);
}

static double curvature(const double *p, int k)
{
    return p[KMAX] * (1.0 - k / (p[CURVES] - 1.0));
}

static int crow_check(const double *p)
{
    int n = (int)p[CURVES];
    if (n % 2)
        return aa_fail(AA_EINVAL, "pattern crow: curves=%d must be even (the bands pair up)", n);
    /* The closest approach of arcs k and k+1 over 0 <= y <= 1. */
    double squeeze = p[KMAX] > 0.0 ? p[KMAX] / (4.0 * (n - 1)) : 0.0;
    for (int k = 0; k <= n - 2; k++)
        if (!(gap(p, k) - squeeze > 0.0))
            return aa_fail(AA_EINVAL,
                           "pattern crow: arcs %d and %d touch (gap %.17g, closest approach "
                           "%.17g): need every gap > kmax/(4(curves-1)) = %.17g",
                           k, k + 1, gap(p, k), gap(p, k) - squeeze, squeeze);
    return AA_OK;
}

/* Add arc k from top to bottom (down) or bottom to top. */
static int arc(aa_scene *s, double a, double c, int down)
{
    double end = a + 0.25 * c;
    if (c == 0.0)
        return aa_scene_line_to(s, a, down ? 1.0 : 0.0);
    return aa_scene_quad_to(s, a - 0.25 * c, 0.5, end, down ? 1.0 : 0.0);
}

static int crow_build(const double *p, aa_scene *s)
{
    int n = (int)p[CURVES];
    double total = 0.0, a = 0.0;
    for (int k = 0; k <= n - 2; k++)
        total += gap(p, k);
    a = (1.0 - total) / 2.0;
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_EVENODD);
    for (int m = 0; m < n / 2 && !st; m++) {
        int k = 2 * m;
        double a0 = a, a1 = a + gap(p, k), c0 = curvature(p, k), c1 = curvature(p, k + 1);
        if ((st = aa_scene_move_to(s, a0 + 0.25 * c0, 0.0)) || (st = arc(s, a0, c0, 1)) ||
            (st = aa_scene_line_to(s, a1 + 0.25 * c1, 1.0)) || (st = arc(s, a1, c1, 0)) ||
            (st = aa_scene_close(s)))
            break;
        /* a_{k+2} = a_k + g_k + g_{k+1}, in the definition's order */
        a = a1 + (k + 1 <= n - 2 ? gap(p, k + 1) : 0.0);
    }
    return st;
}

const aa_pattern_type aa_pattern_crow = {
    {"crow", "Crow's parabolic moire: N arcs, curvature and spacing falling left to right",
     crow_params},
    crow_check,
    crow_build,
    {{0, 0, 0}}};
