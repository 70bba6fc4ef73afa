/*
 * suite_temporal.c: the animated suite `temporal` (motion and time).
 *
 * Small objects and fine detail moving at sub-pixel speeds, where single
 * frames alias and what the eye integrates over a few frames matters
 * (Crow 1976, ch. 4; Catmull 1978 on the picket fence): `fence`, `dots`,
 * `crow` and `star` at 128x128 under the box, moving (0.37, 0.11) pixels a
 * frame over 24 frames, with the eye's window of 6 frames.
 *
 * Methods: the still ones as a yardstick (point, area, the 8 msaa
 * positions in every frame, 9 jittered samples), and the temporal ones:
 * Crow's hexagon at its defaults (the screen display, the random path) and
 * swept in radius and in the order of its vertices (024153 the default of
 * earlier versions), and its fixed display (the model of earlier
 * versions), taa (after Karis 2014: Halton(2,3) jitter, reprojection by
 * the scene's motion, YCoCg neighbourhood clamp, exponential history; 8
 * and 16 frames, the bilinear history, the clip toward the box's centre,
 * and the plain history of earlier versions, reproject=none,clamp=none),
 * and cycle (the msaa8 and msaa16 positions one per frame).
 * Which offsets the eye prefers is read off eye_rmse and flicker, a
 * history's trail off lag; `aabench
 * run` prints the best per pattern after the table.
 */
#include "bench.h"

#include <string.h>

#define LIST(...) ((const char *const[]){__VA_ARGS__, NULL})

const aa_suite_group aa_suite_temporal_groups[] = {
    {LIST("fence", "dots", "crow", "star"), LIST("128x128"), LIST("box"),
     LIST("point", "area", "supersample:pattern=msaa8", "jitter:spp=9", "hexagon",
          "hexagon:radius=0.25", "hexagon:radius=0.35", "hexagon:radius=0.7",
          "hexagon:order=012345", "hexagon:order=031425", "hexagon:order=024135",
          "hexagon:order=024153", "hexagon:display=fixed,order=024153", "taa",
          "taa:frames=16", "taa:sample=bilinear", "taa:clamp=clip",
          "taa:reproject=none,clamp=none", "cycle:positions=msaa8", "cycle:positions=msaa16")},
    {NULL, NULL, NULL, NULL}};

static const aa_suite_motion motions[] = {{"temporal", 0.37, 0.11, 24, 6}, {NULL, 0, 0, 0, 0}};

const aa_suite_motion *aa_suite_motion_find(const char *suite)
{
    for (const aa_suite_motion *m = motions; suite && m->suite; m++)
        if (!strcmp(m->suite, suite))
            return m;
    return NULL;
}
