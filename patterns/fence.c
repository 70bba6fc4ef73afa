/*
 * fence.c: a picket fence finer than a pixel (patterns/README.md, `fence`; Catmull
 * 1978, sec. 1: with point sampling "the picture can be all white in one
 * picture and all black in the next" as such a fence moves, while with area
 * sampling its total intensity stays constant).
 *
 * White vertical bars on black inside the square [1/4, 3/4]^2: I = white
 * where frac((x - 1/4)/p) < duty, p = period.  Bar m covers
 * x in [1/4 + m p, 1/4 + (m + duty) p], clipped at x = 3/4, and
 * y in [1/4, 3/4]; each bar is one rectangle of one white layer.
 *
 * Domain: 0 < period, 0 < duty <= 1, and at most FENCE_MAX_BARS bars
 * (ceil(1/(2p)) of them), so absurd periods are refused before any memory
 * is spent: 65536 bars is a bar every 2 pixels of a 131072-pixel image.
 *
 * Known answer: the white area is exactly (1/2) * (the covered length of
 * [1/4, 3/4]) = (1/2) * (q duty p + min(r, duty p)) with q whole periods
 * and a remainder r (tests/test_patterns.c).
 */
#include "patterns.h"

#include <math.h>

#define FENCE_MAX_BARS 65536

enum { PERIOD, DUTY };

static const aa_param fence_params[] = {
    {"period", AA_PARAM_REAL, 0.9 / 256.0, 0.0, 1.0, 1, NULL,
     "bar spacing p (pattern units), at most 65536 bars in the half-unit square"},
    {"duty", AA_PARAM_REAL, 0.5, 0.0, 1.0, 1, NULL, "white fraction of each period, in (0, 1]"},
    {0}};

static int fence_check(const double *p)
{
    double bars = ceil(0.5 / p[PERIOD]);
    if (!(bars <= FENCE_MAX_BARS))
        return aa_fail(AA_EINVAL,
                       "pattern fence: period=%.17g gives %.0f bars; at most %d (period >= %.17g)",
                       p[PERIOD], bars, FENCE_MAX_BARS, 0.5 / FENCE_MAX_BARS);
    return AA_OK;
}

static int fence_build(const double *p, aa_scene *s)
{
    const double per = p[PERIOD], on = p[DUTY] * per;
    aa_rgb white = {{1, 1, 1}};
    int st = aa_scene_layer(s, white, AA_FILL_NONZERO);
    for (int m = 0; !st; m++) {
        double x0 = 0.25 + m * per, x1 = fmin(x0 + on, 0.75);
        if (!(x0 < 0.75))
            break;
        if ((st = aa_scene_move_to(s, x0, 0.25)) || (st = aa_scene_line_to(s, x1, 0.25)) ||
            (st = aa_scene_line_to(s, x1, 0.75)) || (st = aa_scene_line_to(s, x0, 0.75)))
            break;
        st = aa_scene_close(s);
    }
    return st;
}

const aa_pattern_type aa_pattern_fence = {
    {"fence", "a picket fence of white bars finer than a pixel inside [1/4,3/4]^2", fence_params},
    fence_check,
    fence_build,
    {{0, 0, 0}}};
