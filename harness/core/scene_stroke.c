/*
 * scene_stroke.c: a stroke added to a scene (path.h, "strokes in the scene
 * model", aa_scene_stroke): its exact outline (aa_stroke_outline) filled
 * into a layer of its own, and its source kept (scene_source.c).
 *
 * Kept apart from scene_source.c, which scene.c calls, so that no object
 * file depends on itself through others: this file calls path.c and
 * stroke.c, which call scene.c.
 */
#include "scene_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int aa_scene_stroke(aa_scene *s, const aa_path *path, const aa_stroke_style *style,
                    const double m[6], aa_rgb colour)
{
    if (s->finished)
        return aa_fail(AA_EFAIL, "scene is finished: no more strokes can be added");
    if (m)
        for (int k = 0; k < 6; k++)
            if (!isfinite(m[k]))
                return aa_fail(AA_EINVAL, "stroke: the map is not finite");
    aa_path out;
    aa_path_init(&out);
    int st = aa_stroke_outline(path, style, &out); /* checks the style; its message names it */
    if (st)
        return st;
    if ((st = aa__scene_strokes_reserve(s, s->nstrokes + 1))) {
        aa_path_free(&out);
        return st;
    }
    /* what a failure below takes back */
    const int nlayers = s->nlayers, current = s->current, open = s->open;
    const size_t nedges = s->nedges, ncontours = s->ncontours, first = s->contour_first;
    const double pen[4] = {s->startx, s->starty, s->penx, s->peny};
    if (!(st = aa_scene_layer(s, colour, AA_FILL_NONZERO)) &&
        !(st = aa_path_fill(&out, m, s)))
        st = aa__stroke_source_copy(&s->strokes[s->nstrokes], path, style, m, s->nlayers - 1);
    aa_path_free(&out);
    if (st) {
        /* aa_scene_layer closed an open path first: that close stays
         * undone too (the path is reopened as it was) */
        s->nlayers = nlayers, s->current = current, s->open = open;
        s->nedges = nedges, s->ncontours = ncontours, s->contour_first = first;
        s->startx = pen[0], s->starty = pen[1], s->penx = pen[2], s->peny = pen[3];
        return st;
    }
    s->nstrokes++;
    return AA_OK;
}

