/*
 * slivers.c: slender, nearly horizontal triangles (Crow 1976, fig. 3.17;
 * patterns/README.md, `slivers`).  Point sampling breaks them into strings of
 * beads; exact filtering keeps them whole.
 *
 * K = count white triangles on black; triangle k has vertices
 *   A = (0.05, y_k), B = (0.95, y_k + d_k - h_k/2), C = (0.95, y_k + d_k + h_k/2),
 *   y_k = (k + 1/2)/K, d_k = 0.9 tan(theta_k), theta_k = (k - (K-1)/2) tilt degrees,
 *   h_k = hmin + (hmax - hmin) k/(K-1)   (K = 1: h_0 = hmin).
 * One white layer, nonzero rule (overlapping triangles give their union).
 *
 * Domain: 1 <= count <= SLIVERS_MAX_COUNT; 0 <= hmin <= hmax <= 1 (a zero
 * height is a degenerate triangle of no area, allowed for stress tests);
 * the steepest triangle within 80 degrees of horizontal.
 *
 * Known answer: triangle k has area 0.9 h_k / 2 (base h_k on the line
 * x = 0.95, apex 0.9 away); while the triangles neither overlap nor leave
 * the unit square the white area is the sum (tests/test_patterns.c).
 */
#include "patterns.h"

#include <math.h>

#define SLIVERS_MAX_COUNT 65536

enum { COUNT, TILT, HMIN, HMAX };

static const aa_param slivers_params[] = {
    {"count", AA_PARAM_INT, 24, 1, SLIVERS_MAX_COUNT, 0, NULL, "number of triangles, 1 to 65536"},
    {"tilt", AA_PARAM_REAL, 0.1, -80.0, 80.0, 0, NULL,
     "angle step between triangles (degrees)"},
    {"hmin", AA_PARAM_REAL, 0.1 / 256.0, 0.0, 1.0, 0, NULL,
     "height of triangle 0 at its wide end (pattern units)"},
    {"hmax", AA_PARAM_REAL, 1.5 / 256.0, 0.0, 1.0, 0, NULL,
     "height of triangle count-1 at its wide end (pattern units)"},
    {0}};

static int slivers_check(const double *p)
{
    if (p[HMIN] > p[HMAX])
        return aa_fail(AA_EINVAL, "pattern slivers: hmin=%.17g must not exceed hmax=%.17g",
                       p[HMIN], p[HMAX]);
    double steepest = fabs(p[TILT]) * (p[COUNT] - 1.0) / 2.0;
    if (!(steepest <= 80.0))
        return aa_fail(AA_EINVAL,
                       "pattern slivers: tilt=%.17g with count=%.0f tilts the outermost "
                       "triangle %.17g degrees; at most 80 (|tilt| <= 160/(count-1))",
                       p[TILT], p[COUNT], steepest);
    return AA_OK;
}

static int slivers_build(const double *p, aa_scene *s)
{
    const int K = (int)p[COUNT];
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_NONZERO);
    for (int k = 0; k < K && !st; k++) {
        double y = (k + 0.5) / K;
        double theta = (k - (K - 1) / 2.0) * p[TILT] * (M_PI / 180.0);
        double d = 0.9 * tan(theta);
        double h = K == 1 ? p[HMIN] : p[HMIN] + (p[HMAX] - p[HMIN]) * k / (double)(K - 1);
        if ((st = aa_scene_move_to(s, 0.05, y)) ||
            (st = aa_scene_line_to(s, 0.95, y + d - h / 2)) ||
            (st = aa_scene_line_to(s, 0.95, y + d + h / 2)))
            break;
        st = aa_scene_close(s);
    }
    return st;
}

const aa_pattern_type aa_pattern_slivers = {
    {"slivers", "Crow's slender, nearly horizontal white triangles, 0.1 to 1.5 px tall",
     slivers_params},
    slivers_check,
    slivers_build,
    {{0, 0, 0}}};
