/*
 * dots.c: objects smaller than a pixel (patterns/README.md, `dots`; Crow 1976,
 * ch. 1: small objects that point sampling loses or makes blink as they
 * move).
 *
 * An n x n grid of white squares of side `size` on black.  Dot (p, q),
 * p, q = 0 .. n-1, is centred at ((p + 1/2)/n + (q/n)/256,
 * (q + 1/2)/n + (p/n)/256), so the dots sit at n^2 different sub-pixel
 * phases of a 256-pixel image.  One white layer, nonzero rule: where dots
 * overlap (size larger than the spacing) the union is white.
 *
 * Domain: 1 <= n <= DOTS_MAX_N (65536 dots), 0 < size <= 1.
 *
 * Known answer: while the dots neither overlap nor leave the unit square,
 * the white area is n^2 size^2 (tests/test_patterns.c).
 */
#include "patterns.h"

#define DOTS_MAX_N 256

enum { N, SIZE };

static const aa_param dots_params[] = {
    {"n", AA_PARAM_INT, 16, 1, DOTS_MAX_N, 0, NULL, "dots per row and column, 1 to 256"},
    {"size", AA_PARAM_REAL, 0.3 / 256.0, 0.0, 1.0, 1, NULL, "side of each dot (pattern units)"},
    {0}};

static int dots_build(const double *p, aa_scene *s)
{
    const int n = (int)p[N];
    const double half = 0.5 * p[SIZE];
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_NONZERO);
    for (int q = 0; q < n && !st; q++)
        for (int k = 0; k < n && !st; k++) {
            double cx = (k + 0.5) / n + (q / (double)n) / 256.0;
            double cy = (q + 0.5) / n + (k / (double)n) / 256.0;
            if ((st = aa_scene_move_to(s, cx - half, cy - half)) ||
                (st = aa_scene_line_to(s, cx + half, cy - half)) ||
                (st = aa_scene_line_to(s, cx + half, cy + half)) ||
                (st = aa_scene_line_to(s, cx - half, cy + half)))
                break;
            st = aa_scene_close(s);
        }
    return st;
}

const aa_pattern_type aa_pattern_dots = {
    {"dots", "an n x n grid of white squares smaller than a pixel at n^2 sub-pixel phases",
     dots_params},
    NULL,
    dots_build,
    {{0, 0, 0}}};
