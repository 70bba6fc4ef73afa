/*
 * svgfile.h: reading an SVG document into paths in pixel units (the
 * pattern `svg`, patterns/README.md).
 *
 * The reader walks the document with libxml2 and gives every shape it draws
 * to a sink, in document order (painter's order: the first shape is at the
 * back): `shape` with the shape's fill colour (linear light) and fill rule
 * (then `alpha` when it is translucent),
 * then its subpaths as move/line/quad/cubic/arc/close in absolute pixel
 * units, every transform and the viewBox mapping applied to the points
 * (exact for Bezier arcs under affine maps; an elliptical arc's centre is
 * mapped as a point and its semi-diameters as vectors, which is exact
 * too).  An element with a stroke gives a second shape after its fill:
 * the stroke's outline, of the stroke's colour, nonzero, then its source
 * to `stroke` (if the sink has one).  Every subpath
 * ends with `close` (a fill closes it).  Anything the exact model cannot
 * hold is refused with AA_EINVAL and a message naming the element and its
 * line.
 */
#ifndef AA_SVGFILE_H
#define AA_SVGFILE_H

#include "core.h"
#include "path.h"

#include <stddef.h>

typedef struct aa_svg_sink {
    int (*shape)(void *ctx, aa_rgb colour, aa_fill_rule rule);
    int (*move_to)(void *ctx, double x, double y);
    int (*line_to)(void *ctx, double x, double y);
    int (*quad_to)(void *ctx, double cx, double cy, double x, double y);
    int (*cubic_to)(void *ctx, double c1x, double c1y, double c2x, double c2y, double x,
                    double y);
    int (*close)(void *ctx);
    /* An elliptical arc from the pen to (x, y), in centre form as
     * aa_scene_arc_to takes it: the points (cx + ux cos t + vx sin t,
     * cy + uy cos t + vy sin t), t from t0 to t1. */
    int (*arc_to)(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                  double t0, double t1, double x, double y);
    /* Optional (NULL: not told).  Called right after a stroke's outline
     * was given as a shape (never for a stroke with an empty outline):
     * what that shape strokes, the path in its user units, the style (its
     * dashes valid during the call only) and the map m from user units to
     * pixels (x' = m0 x + m2 y + m4, y' = m1 x + m3 y + m5), so that the
     * sink can keep the stroke as a stroke (aa_scene_stroke). */
    int (*stroke)(void *ctx, const aa_path *path, const aa_stroke_style *style,
                  const double m[6]);
    /* Optional (NULL: a document that needs them is refused).  `alpha` is
     * called right after `shape` when the shape's alpha is below 1 (its
     * paint's alpha times its fill- or stroke-opacity, times the element's
     * opacity when that is its one painted shape); `group_begin` and
     * `group_end` enclose, in document order, shapes composited as a whole
     * with an opacity below 1 (a <g>, or an element with both a fill and a
     * stroke). */
    int (*alpha)(void *ctx, double alpha);
    int (*group_begin)(void *ctx, double opacity);
    int (*group_end)(void *ctx);
    /* Optional (NULL: a document that needs them is refused).  Clip paths
     * as aa_scene_clip_begin takes them: `clip_begin` starts the next clip
     * (numbered from 0 in the order begun), itself inside the earlier clip
     * `within` (-1: none); the shapes given until `clip_end` are its
     * members (their colour means nothing, their rule is the clip-rule)
     * and no other clip begins meanwhile; `clip` is called right after
     * `shape` (and `alpha`) when that shape, a member or one that paints,
     * is drawn only inside an ended clip. */
    int (*clip_begin)(void *ctx, int within);
    int (*clip_end)(void *ctx);
    int (*clip)(void *ctx, int clip);
    /* Optional (NULL: a document that needs it is refused).  Called right
     * after `shape` when the shape's paint is a gradient (aabench.h,
     * aa_gradient: its stops valid during the call only; its map m from
     * the gradient's coordinates to pixels); the shape's colour is then
     * its first stop's and means nothing; `source` names the gradient
     * element and its line ("FILE: line N: <radialGradient>"), for
     * messages that refuse it later (aa_scene_set_gradient_source). */
    int (*gradient)(void *ctx, const aa_gradient *g, const char *source);
    /* Optional (NULL: such a gradient is refused).  Called right after
     * `gradient` when the gradient interpolates its stops in linear light
     * (color-interpolation: linearRGB; aa_scene_set_gradient_interpolation),
     * with AA_INTERPOLATE_LINEAR_RGB. */
    int (*gradient_interpolation)(void *ctx, int interpolation);
} aa_svg_sink;

/* Limits: larger or deeper documents are refused. */
#define AA_SVG_MAX_BYTES (64u << 20) /* the file */
#define AA_SVG_MAX_DEPTH 64          /* nested elements */
#define AA_SVG_MAX_SEGMENTS 4000000  /* path commands in all */
#define AA_SVG_MAX_NUMBER 1e9        /* |a number| in the document */
#define AA_SVG_MAX_COORD 1e7         /* |a coordinate| in pixels, after transforms */
#define AA_SVG_MAX_DASHES 64         /* values in a stroke-dasharray */
#define AA_SVG_MAX_CLIP_NESTING 16   /* clipPaths referenced while one is read */
#define AA_SVG_MAX_ELEMENTS 1000000  /* elements read, <use> instances counted */

/* Read the document data[0 .. len) (`name` names it in messages) drawn on
 * a view of w x h pixels: the viewport is the root's width and height, or
 * the view's where they are absent.  viewport[0..1] (may be NULL) receives
 * its width and height in pixels; everything outside it is clipped by the
 * caller (when the root has a transform, the reader clips to the
 * transformed viewport itself and viewport[] is the view's size).
 * Returns the first failing status of the sink or of the document. */
int aa_svg_read(const char *data, size_t len, const char *name, int w, int h,
                const aa_svg_sink *sink, void *ctx, double viewport[2]);

/* The same for a file (at most AA_SVG_MAX_BYTES). */
int aa_svg_read_file(const char *path, int w, int h, const aa_svg_sink *sink, void *ctx,
                     double viewport[2]);

/* The same drawn at `scale` image pixels per CSS pixel (rsvg-convert's
 * zoom): the document is laid out in a view of (w, h) / scale CSS pixels
 * and everything, the viewport included, scaled by `scale`.  With sink
 * NULL only the viewport is found (w and h unused): the root's own width
 * and height in px times the scale, refused when either is absent or a
 * percentage. */
#define AA_SVG_MIN_SCALE (1.0 / 64)
#define AA_SVG_MAX_SCALE 64.0
int aa_svg_read_at(const char *data, size_t len, const char *name, int w, int h, double scale,
                   const aa_svg_sink *sink, void *ctx, double viewport[2]);
int aa_svg_read_file_at(const char *path, int w, int h, double scale, const aa_svg_sink *sink,
                        void *ctx, double viewport[2]);

/* A 64-bit FNV-1a hash of a file's bytes and its length (the cache key of a
 * pattern read from a file). */
int aa_file_hash(const char *path, unsigned long long *hash, size_t *len);

/* Read a whole file of at most `max` bytes into a malloc'd buffer (NUL
 * added); `what` names it in messages ("SVG file"). */
int aa_file_read_all(const char *path, size_t max, const char *what, char **data, size_t *len);

#endif
