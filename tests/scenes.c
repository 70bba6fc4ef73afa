/*
 * scenes.c: test-only scenes shared by several tests (scenes.h).
 */
#include "scenes.h"

#include <math.h>

aa_scene *scenes_half_plane(double px, double py, double angle)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    if (!s)
        return NULL;
    double dx = sin(angle), dy = cos(angle); /* along the edge, downwards */
    double nx = dy, ny = -dx;                /* into the white side */
    const double L = 50.0;
    if (aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) ||
        aa_scene_move_to(s, px - L * dx, py - L * dy) ||
        aa_scene_line_to(s, px + L * dx, py + L * dy) ||
        aa_scene_line_to(s, px + L * dx + L * nx, py + L * dy + L * ny) ||
        aa_scene_line_to(s, px - L * dx + L * nx, py - L * dy + L * ny) || aa_scene_finish(s)) {
        aa_scene_free(s);
        return NULL;
    }
    return s;
}
