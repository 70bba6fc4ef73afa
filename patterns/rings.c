/*
 * rings.c: concentric circles as a conic moire, exactly as
 * patterns/README.md, `rings`, defines it.
 *
 * N circles about (x, y) with radii r_k = R sqrt(k/N), k = 1 .. N (the
 * edges of a hard-edged Fresnel zone plate: every band between two
 * consecutive circles has the same area pi R^2/N, so the bands narrow as
 * 1/r, R^2/(2 N r) wide at radius r, and towards the outside they fall
 * below a pixel as Crow's parabolic arcs do).  Under the even-odd rule a
 * point at distance d from the centre is white when the number of circles
 * around it, #{k : r_k > d}, is odd: the outermost band (r_{N-1}, r_N) is
 * white, then every other band inwards.
 *
 * Construction: circle k is one closed path of two elliptical arcs
 * (aa_scene_arc_to, centre form with u = (r_k, 0), v = (0, r_k)): from
 * (x + r_k, y) through t = 0 .. pi to (x - r_k, y), then t = pi .. 2 pi
 * back; circles turn alternately one way and the other (circle N with t
 * increasing, circle N-1 decreasing, ...), so that the winding number is
 * 1 exactly where the even-odd rule is white and 0 elsewhere: both rules
 * give the same picture, and coverage rasterizers that fill by |winding|
 * (stb) take it.
 *
 * Domain: 1 <= N <= RINGS_MAX (the reference's cost grows with the circles
 * crossing each row); R > 0; the centre anywhere in [-1000, 1000]^2.  Rings
 * reaching outside the unit square are clipped there (aa_scene_clip_unit,
 * as every pattern).
 *
 * Known answer: while the rings stay inside the unit square (|x - 1/2| and
 * |y - 1/2| at most 1/2 - R, as the defaults: R = 0.48 about the centre),
 * the white area is the sum of the white bands, each pi R^2/N, and there
 * are ceil(N/2) of them (the bands (r_{j}, r_{j+1}) with N - j odd,
 * j = 0 .. N-1, r_0 = 0):
 *     white area = pi R^2 ceil(N/2) / N     (pi R^2 / 2 for N even).
 */
#include "patterns.h"

#include <math.h>

#define RINGS_MAX 4096

enum { RINGS, RADIUS, X, Y };

static const aa_param rings_params[] = {
    {"rings", AA_PARAM_INT, 64, 1, RINGS_MAX, 0, NULL, "number of circles N: 1 to 4096"},
    {"radius", AA_PARAM_REAL, 0.48, 0.0, 1e3, 1, NULL,
     "R, the radius of the outermost circle (pattern units)"},
    {"x", AA_PARAM_REAL, 0.5, -1e3, 1e3, 0, NULL, "the centre's x (pattern units)"},
    {"y", AA_PARAM_REAL, 0.5, -1e3, 1e3, 0, NULL, "the centre's y (pattern units)"},
    {0}};

/* Circle of radius r about (x, y): two half arcs, t increasing (up = 1) or
 * decreasing (up = 0). */
static int circle(aa_scene *s, double x, double y, double r, int up)
{
    double mid = up ? M_PI : -M_PI, end = up ? 2 * M_PI : -2 * M_PI;
    int st;
    if ((st = aa_scene_move_to(s, x + r, y)) ||
        (st = aa_scene_arc_to(s, x, y, r, 0.0, 0.0, r, 0.0, mid, x - r, y)) ||
        (st = aa_scene_arc_to(s, x, y, r, 0.0, 0.0, r, mid, end, x + r, y)))
        return st;
    return aa_scene_close(s);
}

static int rings_build(const double *p, aa_scene *s)
{
    int n = (int)p[RINGS];
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_EVENODD);
    /* circle N turns with t increasing, each one inside the other way */
    for (int k = n; k >= 1 && !st; k--)
        st = circle(s, p[X], p[Y], p[RADIUS] * sqrt((double)k / n), (n - k) % 2 == 0);
    return st;
}

const aa_pattern_type aa_pattern_rings = {
    {"rings", "concentric circles, radii R sqrt(k/N): a conic moire, bands narrowing as 1/r",
     rings_params},
    NULL,
    rings_build,
    {{0, 0, 0}}};
