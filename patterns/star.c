/*
 * star.c: the Siemens star (patterns/README.md, `star`), a classic resolution
 * target: S white wedges on black whose frequency grows without bound
 * toward the centre, so every finite sampling rate aliases near it.
 *
 * Wedge k = 0 .. S-1 is the triangle (1/2, 1/2), (1/2 + R cos a,
 * 1/2 + R sin a), (1/2 + R cos b, 1/2 + R sin b), a = 2 pi k/S + rot pi/180,
 * b = a + pi/S, R = 0.48.  One white layer, nonzero rule.
 *
 * Domain: 1 <= spokes <= STAR_MAX_SPOKES; |rot| <= 360.  All wedges meet at
 * the centre, so the reference's cost near it grows with S: 65536 spokes
 * would put 131072 edges through one pixel, which is refused.
 *
 * Known answer: each wedge has area R^2 sin(pi/S)/2, the star
 * S R^2 sin(pi/S)/2 (tests/test_patterns.c).
 */
#include "patterns.h"

#include <math.h>

#define STAR_MAX_SPOKES 4096
#define STAR_RADIUS 0.48

enum { SPOKES, ROT };

static const aa_param star_params[] = {
    {"spokes", AA_PARAM_INT, 36, 1, STAR_MAX_SPOKES, 0, NULL, "number of white wedges, 1 to 4096"},
    {"rot", AA_PARAM_REAL, 0.5, -360.0, 360.0, 0, NULL, "rotation of the star in degrees"},
    {0}};

static int star_build(const double *p, aa_scene *s)
{
    const int n = (int)p[SPOKES];
    const double R = STAR_RADIUS, rot = p[ROT] * (M_PI / 180.0);
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_NONZERO);
    for (int k = 0; k < n && !st; k++) {
        double a = 2.0 * M_PI * k / n + rot, b = a + M_PI / n;
        if ((st = aa_scene_move_to(s, 0.5, 0.5)) ||
            (st = aa_scene_line_to(s, 0.5 + R * cos(a), 0.5 + R * sin(a))) ||
            (st = aa_scene_line_to(s, 0.5 + R * cos(b), 0.5 + R * sin(b))))
            break;
        st = aa_scene_close(s);
    }
    return st;
}

const aa_pattern_type aa_pattern_star = {
    {"star", "Siemens star: white wedges around the centre, frequency unbounded toward it",
     star_params},
    NULL,
    star_build,
    {{0, 0, 0}}};
