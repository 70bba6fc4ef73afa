/*
 * peer.h: what the peer rasterizers (freetype.c, stb.c, cairo.c, agg.cpp)
 * share.
 *
 * The peers are other libraries' coverage rasterizers given the same placed
 * scene as our methods.  Each produces a coverage a in [0, 1] per pixel for
 * one filled layer; the pixel is then (1 - a) background + a colour, so a
 * coverage of exactly 0 or 1 gives the colour exactly.  Their grey path
 * takes grey scenes of at most one layer (or of strokes of one grey,
 * below); every peer takes the box filter only: anything else is refused
 * with a message (status AA_EINVAL, exit status 2 from the command).
 *
 * Strokes (aa_scene_stroke): a scene of several layers is taken when every
 * layer is a stroke of the same grey and every stroke's map turns the same
 * way (the sign of its determinant).  Layers of one colour painted over
 * each other show their union, so the coverage is the union's: the peers
 * with a stroker of their own (cairo.c, agg.cpp) stroke each source and
 * composite the coverages (OVER: a + b - a b, what painting them in turn
 * gives); the others (freetype.c, stb.c) fill the scene's exact outlines
 * of all the layers as one non-zero outline, which is the union because
 * every outline's contours turn the same way (aa_stroke_outline), and a
 * map turns them all alike, so no winding cancels.
 *
 * Painted: a scene the grey path refuses for its colour, its several
 * layers or its translucency (aa_peer_paintable) is painted layer by layer
 * by every peer: each layer's own outline (the contours whose edges carry
 * it, under its rule; a layer kept as a stroke by the peer's own stroker
 * where it has one, else its exact outline) rasterized by the library into
 * an 8-bit coverage row, composited back to front over the background in
 * linear light by aa_peer_composite_row.  Coverage is used as alpha, so
 * layers sharing an edge let what is behind show through their seam
 * (conflation), which the exact reference does not have.  Clipped scenes
 * and groups of opacity are refused (a group's coverage is no one
 * layer's), and so is a filled layer of offset curves (aa_peer_painted_check).
 */
#ifndef AA_PEER_H
#define AA_PEER_H

#include "aabench.h"

/* The one layer of a peer's scene. */
typedef struct aa_peer_scene {
    double bg, fg;     /* grey levels of the background and of the layer */
    int layers;        /* 0 (background only), 1, or more (all strokes, above) */
    aa_fill_rule rule; /* the layer's rule (nonzero if no layer; strokes: nonzero) */
    int strokes;       /* 1 if the layers are strokes (aa_scene_stroke) */
} aa_peer_scene;

/* Refuse a filter other than box (`name` is the method, for the message). */
int aa_peer_check_filter(const char *name, const aa_filter *f);
/* Read the placed scene of the job, refusing colour scenes and several
 * layers. */
int aa_peer_scene_read(const char *name, const aa_job *job, aa_peer_scene *ps);
/* Refuse a scene whose outline has the exact offset curves of a Bezier
 * arc's stroke (edge quad 4), for the peers that fill the outline. */
int aa_peer_refuse_offsets(const char *name, const aa_scene *s);
/* The grey value of coverage a. */
static inline double aa_peer_mix(const aa_peer_scene *ps, double a)
{
    return (1.0 - a) * ps->bg + a * ps->fg;
}
/* Fill pixels [i0, i1) of row j of a W x H x 3 image with grey v. */
void aa_peer_fill(aa_image *out, int j, int i0, int i1, double v);

/* Whether the placed scene, refused by the grey path, is painted layer by
 * layer: unclipped, and of colour, of several layers or translucent. */
int aa_peer_paintable(const aa_scene *s);
/* Painted mode's refusals: groups of opacity, and (for every layer if
 * `strokes_filled`, else only for layers filled as fills) a layer whose
 * outline has offset curves (edge quad 4). */
int aa_peer_painted_check(const char *name, const aa_scene *s, int strokes_filled);
/* Row j of out, pixels [0, n), set to the scene's background colour. */
void aa_peer_background_row(const aa_scene *s, aa_image *out, int j, int n);
/* Layer `layer` of the scene composited over pixels px[0 .. n) (three
 * linear channels each) from its 8-bit coverages cov[0 .. n):
 *     v = a inside + (1 - a) v,   a = cov / 255,
 * inside the layer's colour c (alpha 1) or c over v in sRGB-encoded
 * values, decode(alpha encode(c) + (1 - alpha) encode(v)) (the scene's
 * compositing rule, patterns/README.md).  A coverage of 0 leaves v. */
void aa_peer_composite_row(const aa_scene *s, int layer, const unsigned char *cov, int n,
                           double *px);

/* An elliptical arc edge (quad == 3) as cubic Bezier arcs, for the peers
 * whose outlines have no arcs (freetype.c, stb.c): the arc split into n
 * equal pieces of at most 90 degrees of its angle t (n = 1 .. 4), each the
 * standard cubic along the tangents (peer.c derives it).  Piece k is
 * c[k] = c1x c1y c2x c2y x y, from the previous piece's end (the first
 * from the edge's (x0, y0)); the last ends at exactly (x1, y1).  Every
 * cubic lies between the ellipse and the ellipse scaled by 1 + e about its
 * centre, e = sqrt(1 + (4/27) sin^6(h/4) / cos^2(h/4)) - 1 for a piece of
 * angle h: at most 2.7253e-4 (h = 90 degrees), so within 2.7253e-4 times
 * the longer semi-axis outside the ellipse.  Returns n. */
#define AA_PEER_ARC_CUBICS 4
int aa_peer_arc_cubics(const aa_edge *e, double c[AA_PEER_ARC_CUBICS][6]);
/* The half extents of edge e's whole ellipse about its centre, in x and in
 * y: sqrt(ux^2 + vx^2) and sqrt(uy^2 + vy^2) (the maxima of ux cos t +
 * vx sin t and of uy cos t + vy sin t). */
void aa_peer_arc_extent(const aa_edge *e, double *hx, double *hy);

#endif
