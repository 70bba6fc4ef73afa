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
 * layers, its translucency or its clips (aa_peer_paintable) is painted
 * layer by layer by every peer (aa_peer_paint_band): each layer's own
 * outline (the contours whose edges carry it, under its rule; a layer
 * kept as a stroke by the peer's own stroker where it has one, else its
 * exact outline) rasterized by the library into an 8-bit coverage row,
 * composited back to front over the background in linear light by
 * aa_peer_composite_row.  Coverage is used as alpha, so layers sharing an
 * edge let what is behind show through their seam (conflation), which the
 * exact reference does not have.  A filled layer of offset curves is
 * refused (aa_peer_painted_check).
 *
 * Clips, by masks: the library rasterizes each member of a clip under its
 * rule, as any layer; the clip's mask is the members' coverages painted
 * OVER each other (their union as the peers paint strokes of one grey:
 * u = m + (1 - m) u), each member's first multiplied by its own clip's
 * mask, and the whole by the mask of the clip it is defined within; a
 * gated layer's coverage is its own times its clip's mask.  A mask of 0
 * or 1 is exact (so are whole pixels inside or outside every edge), but
 * in a pixel both shapes cross, the product of two coverages is not the
 * coverage of their intersection (two half-covering shapes give 1/4
 * whether they overlap in all, half or none of the pixel): that is the
 * error of masking, measured against the exact reference.  A peer whose
 * library clips by itself marks the layers it clips so
 * (aa_peer_painter_new's `own`; cairo.c, cairo_clip for a clip that is an
 * intersection of paths), and those take no mask.
 *
 * Groups of opacity, by offscreen buffers: a group's layers are painted
 * into a buffer of the band, transparent at first, that holds per pixel
 * the group's coverage k and its encoded premultiplied colour Q and alpha
 * B, each times k; a layer of coverage a, alpha alpha and linear colour c
 * goes on as the libraries composite coverage, source over with a alpha
 * as alpha in the group's (sRGB-encoded) values:
 *     Q = a alpha encode(c) + (1 - a alpha) Q,  B = a alpha + (1 - a alpha) B,
 *     k = a + (1 - a) k
 * (the area averages of the group's colour where it covers, the layer's
 * coverage taken as independent of what is below it, as OVER does).  The
 * group, closed, goes over what is below with its opacity o: over the
 * canvas, as a layer goes, its covered part mixed in by coverage in
 * linear light,
 *     v = k decode(o Q/k + (1 - o B/k) encode(v)) + (1 - k) v,
 * and into the buffer of the group holding it as a layer of colour o Q
 * and alpha o B: Q' = o Q + (1 - o B) Q', B' = o B + (1 - o B) B',
 * k' = k + (1 - k) k'.  Where every coverage is 0 or 1 this is the
 * scene's own compositing (patterns/README.md); a group of one layer
 * paints as the layer with its alpha times o would; a seam between two
 * layers of a group shows the buffer's transparency through, conflation
 * as above, once per group.
 *
 * Gradient paint (aa_scene_layer_gradient), by the library's own gradient
 * code, where it has one (cairo.c: pixman's gradients; agg.cpp:
 * span_gradient and its colour LUT): the library paints the layer's
 * gradient on the band (over the layer's covered span of it), per pixel its colour at the pixel's centre as
 * the library samples and interpolates it, premultiplied by the stops'
 * opacity, in the scene's encoded values (aa_peer_shade_fn); the layer
 * then goes on as a layer of that pixel's colour would, its coverage
 * mixing in linear light and its alpha (the layer's times the paint's)
 * in encoded values:
 *     v = a decode(alpha P + (1 - alpha A) encode(v)) + (1 - a) v,
 * P, A the paint's premultiplied colour and alpha, and into a group's
 * buffer alike.  The paint is the library's, quantised as it keeps it
 * (8 bits a channel in both); a coverage of 0 or 1 gives that colour
 * exactly.  FreeType and stb have no gradients: aa_method_init refuses
 * them such a scene (they do not declare AA_METHOD_GRADIENTS).  A
 * gradient that interpolates its stops in linear light
 * (aa_scene_layer_gradient_interpolation) is refused by name
 * (aa_peer_painted_check): pixman and AGG interpolate in the values they
 * are given, and an sRGB drawing of it would be a different picture.
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
/* Refuse a scene with a stroke whose join is SVG 2's arcs, or
 * miter-clip unless `miter_clip`, naming the join, for the peers whose
 * strokers do not draw it (`what` says what the peer's stroker has
 * instead, for the message). */
int aa_peer_refuse_joins(const char *name, const aa_scene *s, int miter_clip, const char *what);
/* The grey value of coverage a. */
static inline double aa_peer_mix(const aa_peer_scene *ps, double a)
{
    return (1.0 - a) * ps->bg + a * ps->fg;
}
/* Fill pixels [i0, i1) of row j of a W x H x 3 image with grey v. */
void aa_peer_fill(aa_image *out, int j, int i0, int i1, double v);

/* Whether the placed scene, refused by the grey path, is painted layer by
 * layer: of colour, of several layers, translucent or clipped. */
int aa_peer_paintable(const aa_scene *s);
/* Painted mode's refusals: (for every layer if `strokes_filled`, else
 * only for layers filled as fills) a layer whose outline has offset
 * curves (edge quad 4); a gradient in linear light, which neither
 * library's gradients draw. */
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

/* The library's coverage of layer `layer` (a painting layer or a clip's
 * member, under its rule, or its stroke) on rows [y0, y0 + rows) of the
 * image: *cov set to its first row's w bytes, row j at *cov + j *stride,
 * valid until the next call (or *cov NULL: no coverage anywhere).  Returns
 * a status. */
typedef int (*aa_peer_cover_fn)(void *ctx, int layer, int y0, int rows,
                                const unsigned char **cov, size_t *stride);
/* The library's paint of gradient layer `layer` on rows [y0, y0 + rows)
 * of the image, columns [x0, x1) (the layer's covered span on the band:
 * the pixels outside it are not read, and need not be painted): *rgba set
 * to its first row's w pixels of four floats, the sRGB-encoded channels
 * premultiplied by the opacity, then the opacity (the stops', not yet the
 * layer's alpha), pixel i of row j at *rgba + j * stride + 4 i (floats),
 * valid until the next call.  Each pixel's paint must be what painting
 * the whole row would give it, to the bit.  Returns a status. */
typedef int (*aa_peer_shade_fn)(void *ctx, int layer, int y0, int rows, int x0, int x1,
                                const float **rgba, size_t *stride);
/* Tests only: 1 makes aa_peer_paint_band ask every gradient layer's paint
 * over the band's whole width, as it did before spans, so that a test can
 * hold the span's paint to the whole row's, bit for bit. */
extern int aa__peer_shade_whole;
/* One thread's workspace for painting bands of at most `band` rows of w
 * pixels of the scene: the clips' masks and the groups' buffers, 8 x
 * (masks alive at once + 5 x depth of groups) bytes a pixel (a mask is
 * made once per band, before the first layer that needs it, and its
 * memory reused once its last use is past).  own (NULL: none) marks
 * the layers whose coverage from the peer already holds their clip (the
 * library's own clipping, cairo.c), which take no mask. */
typedef struct aa_peer_painter aa_peer_painter;
int aa_peer_painter_new(const char *name, const aa_scene *s, int w, int band,
                        const unsigned char *own, aa_peer_painter **out);
void aa_peer_painter_free(aa_peer_painter *pp);
/* Rows [y0, y0 + rows) of out painted (above): the background, then each
 * layer back to front, through its clip's mask and its groups' buffers,
 * a gradient layer in the paint `shade` gives (NULL: the peer draws no
 * gradients, and a gradient layer is an error).  A scene of no clip, no
 * group and no gradient composites each layer's coverage by
 * aa_peer_composite_row alone. */
int aa_peer_paint_band(aa_peer_painter *pp, const aa_scene *s, aa_peer_cover_fn cover,
                       aa_peer_shade_fn shade, void *ctx, aa_image *out, int y0, int rows);

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
