/*
 * scene_internal.h: the scene's private layout, shared by scene.c and
 * strip.c only.
 */
#ifndef AA_SCENE_INTERNAL_H
#define AA_SCENE_INTERNAL_H

#include "core.h"

struct aa_scene {
    aa_rgb background;
    int nlayers, current;
    size_t caplayers;
    aa_rgb *colour;
    aa_fill_rule *rule;

    aa_edge *edges;
    size_t nedges, capedges;
    size_t *contour; /* first edge of each contour, then a sentinel */
    size_t ncontours, capcontours;

    /* path being built */
    int open;
    double startx, starty, penx, peny;
    size_t contour_first;

    int finished, grey, has_bounds;
    aa_piece *pieces;
    size_t npieces;
    double bx0, by0, bx1, by1;

    /* y index: bin b covers [iy0 + b ihb, iy0 + (b+1) ihb] */
    double iy0, ihb;
    size_t nbins;
    size_t *bin_start;   /* nbins + 1 */
    uint32_t *bin_items; /* piece indices */

    /* a field scene (aa_scene_set_field): no layers, the field everywhere */
    const aa_field_type *field;
    double fparam[AA_FIELD_MAX_PARAMS];
    int fnparam;
    double fmap[4]; /* sx, sy, tx, ty: the field's (x, y) is at (sx x + tx, sy y + ty) */
};

/* Call visit(ctx, piece) once for every piece whose closed y range meets
 * [ya, yb]; returns the number of visits that returned non-zero. */
typedef int (*aa__visit)(void *ctx, const aa_piece *p);
size_t aa__scene_gather(const aa_scene *s, double ya, double yb, aa__visit visit, void *ctx);

aa_scene *aa__scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty,
                              double hint);

#endif
