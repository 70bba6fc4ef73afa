/*
 * catmull.c: the hidden-surface pixel (Catmull 1978, "A hidden-surface
 * algorithm with anti-aliasing", fig. 1; patterns/README.md, `catmull`).
 *
 * Opaque layers, front to back, over black: in front a green square
 * [0, 1/2] x [0, 1/2] and a blue rectangle [0, 1] x [1/2, 1]; behind them a
 * red rectangle [0.1, 0.45] x [0.1, 0.9], wholly hidden.  `tiles` = T
 * repeats the configuration on a T x T grid, tile (p, q) covering
 * [p/T, (p+1)/T] x [q/T, (q+1)/T].  Green and blue do not overlap, so their
 * order among themselves does not matter; both are in front of red.
 *
 * Rendered as one pixel, the exact box value is (0, 0.25, 0.5): 25% green,
 * 25% black, 50% blue and no red, Catmull's own statement.  Any red in an
 * answer is a hidden-surface error.
 *
 * Domain: 1 <= tiles <= CATMULL_MAX_TILES (3 rectangles per tile).
 */
#include "patterns.h"

#define CATMULL_MAX_TILES 256

enum { TILES };

static const aa_param catmull_params[] = {
    {"tiles", AA_PARAM_INT, 1, 1, CATMULL_MAX_TILES, 0, NULL,
     "repeats of the configuration per side, 1 to 256"},
    {0}};

/* The axis-aligned rectangle [x0, x1] x [y0, y1] of tile (p, q) in the
 * current layer. */
static int rect(aa_scene *s, int T, int p, int q, double x0, double y0, double x1, double y1)
{
    int st;
    double ox = (double)p / T, oy = (double)q / T, k = 1.0 / T;
    if ((st = aa_scene_move_to(s, ox + k * x0, oy + k * y0)) ||
        (st = aa_scene_line_to(s, ox + k * x1, oy + k * y0)) ||
        (st = aa_scene_line_to(s, ox + k * x1, oy + k * y1)) ||
        (st = aa_scene_line_to(s, ox + k * x0, oy + k * y1)))
        return st;
    return aa_scene_close(s);
}

static int catmull_build(const double *p, aa_scene *s)
{
    static const struct {
        aa_rgb colour;
        double x0, y0, x1, y1;
    } shapes[3] = {
        {{{0, 1, 0}}, 0.0, 0.0, 0.5, 0.5}, /* depth 1: green */
        {{{0, 0, 1}}, 0.0, 0.5, 1.0, 1.0}, /* depth 1: blue */
        {{{1, 0, 0}}, 0.1, 0.1, 0.45, 0.9} /* depth 2: red, hidden */
    };
    const int T = (int)p[TILES];
    int st = AA_OK;
    for (int k = 0; k < 3 && !st; k++) {
        if ((st = aa_scene_layer(s, shapes[k].colour, AA_FILL_NONZERO)))
            break;
        for (int q = 0; q < T && !st; q++)
            for (int r = 0; r < T && !st; r++)
                st = rect(s, T, r, q, shapes[k].x0, shapes[k].y0, shapes[k].x1, shapes[k].y1);
    }
    return st;
}

const aa_pattern_type aa_pattern_catmull = {
    {"catmull", "Catmull's hidden-surface pixel: green and blue in front of a hidden red",
     catmull_params},
    NULL,
    catmull_build,
    {{0, 0, 0}}};
