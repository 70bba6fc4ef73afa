/*
 * scenes.h: test-only scenes shared by several tests.
 */
#ifndef AA_TEST_SCENES_H
#define AA_TEST_SCENES_H

#include "bench.h"

/* White right of the line through (px, py) (pattern units) with direction
 * angle `angle` from the vertical (0: the region right of a vertical line),
 * on black: a square of side 50 with one side on the line.  NULL if the
 * scene cannot be built. */
aa_scene *scenes_half_plane(double px, double py, double angle);

#endif
