/*
 * path.h: paths as drawn (before filling or stroking), the SVG arc's
 * endpoint parametrisation, and the stroke outline (SVG 2, "Stroke shape").
 *
 * A path is subpaths of lines, quadratic and cubic Bezier arcs and
 * elliptical arcs (in centre form, aa_edge), open or closed, in its own
 * (user) coordinates.  A fill gives it to a scene through an affine map; a
 * stroke first becomes its outline, in the same user coordinates, and the
 * outline goes through the map: a non-uniform map transforms the outline,
 * not the width, as SVG says.
 */
#ifndef AA_PATH_H
#define AA_PATH_H

#include "core.h"

#include <stddef.h>

typedef enum aa_path_op {
    AA_PATH_MOVE,  /* p[0..1]: the new subpath's start */
    AA_PATH_LINE,  /* p[0..1]: end */
    AA_PATH_QUAD,  /* p[0..3]: control, end */
    AA_PATH_CUBIC, /* p[0..5]: control 1, control 2, end */
    AA_PATH_ARC,   /* p[0..7]: cx cy ux uy vx vy t0 t1 (aa_edge); p[8..9]: end */
    AA_PATH_CLOSE, /* back to the subpath's start (a line if it is elsewhere) */
    /* p[0..7]: b, p[8]: d, p[9]: 1 for the evolute (aa_offset_curve, its map
     * the identity); p[10..11]: t0 t1; p[12..13]: end; p[14]: its base
     * (AA_OFFSET_CUBIC or AA_OFFSET_ELLIPSE).  Stroke outlines only
     * (aa_stroke_outline): aa_path_fill takes them, nothing else */
    AA_PATH_OFFSET
} aa_path_op;

typedef struct aa_path_seg {
    aa_path_op op;
    double p[15];
} aa_path_seg;

typedef struct aa_path {
    aa_path_seg *seg;
    size_t n, cap;
    double penx, peny, startx, starty; /* while building */
    int open;                          /* a subpath has begun */
} aa_path;

/* An empty path ({0} is one too). */
void aa_path_init(aa_path *p);
void aa_path_free(aa_path *p);
int aa_path_move_to(aa_path *p, double x, double y);
int aa_path_line_to(aa_path *p, double x, double y);
int aa_path_quad_to(aa_path *p, double cx, double cy, double x, double y);
int aa_path_cubic_to(aa_path *p, double c1x, double c1y, double c2x, double c2y, double x,
                     double y);
/* As aa_scene_arc_to, same checks. */
int aa_path_arc_to(aa_path *p, double cx, double cy, double ux, double uy, double vx, double vy,
                   double t0, double t1, double x, double y);
/* An offset curve or evolute of a Bezier arc or an ellipse (aa_offset_curve; its map is
 * ignored: the path's own coordinates) from the pen to (x, y), its
 * parameter from t0 to t1, as aa_scene_offset_to checks it. */
int aa_path_offset_to(aa_path *p, const aa_offset_curve *oc, double t0, double t1, double x,
                      double y);
/* A segment drawn after a close starts at the closed subpath's start (SVG's
 * implicit move_to); drawing before any move_to is refused. */
int aa_path_close(aa_path *p);

/* The SVG arc command from (x0, y0) to (x1, y1) with radii rx, ry, x-axis
 * rotation phi (degrees) and the two flags, by the SVG implementation notes
 * (SVG 1.1 F.6.5, F.6.6; SVG 2 "Elliptical arc implementation notes"):
 * radii made positive, scaled up when too small for the ends.  *kind is
 * AA_ARC_CURVE (c[0..7] = cx cy ux uy vx vy t0 t1 as aa_edge, from (x0, y0)
 * to (x1, y1)), AA_ARC_LINE (a radius is zero: a straight line) or
 * AA_ARC_NONE (the ends are equal: nothing is drawn).  Returns AA_OK, or
 * AA_EINVAL for non-finite input (*kind then AA_ARC_NONE). */
typedef enum aa_arc_kind { AA_ARC_CURVE = 0, AA_ARC_LINE, AA_ARC_NONE } aa_arc_kind;
int aa_arc_endpoints(double x0, double y0, double rx, double ry, double phi, int large,
                     int sweep, double x1, double y1, double c[8], aa_arc_kind *kind);

/* Give every segment of `path` to a scene, each point mapped by the affine
 * map m (x' = m0 x + m2 y + m4, y' = m1 x + m3 y + m5; NULL: identity):
 * every subpath is closed (a fill closes it).  An elliptical arc maps to
 * an elliptical arc (centre and semi-diameters mapped). */
int aa_path_fill(const aa_path *path, const double m[6], aa_scene *s);

/* SVG 2's joins (stroke.c says how each is drawn): miter-clip and arcs
 * are SVG 2's, after the three of SVG 1.1. */
typedef enum aa_line_join {
    AA_JOIN_MITER = 0, AA_JOIN_ROUND, AA_JOIN_BEVEL, AA_JOIN_MITER_CLIP, AA_JOIN_ARCS
} aa_line_join;
typedef enum aa_line_cap { AA_CAP_BUTT = 0, AA_CAP_ROUND, AA_CAP_SQUARE } aa_line_cap;

typedef struct aa_stroke_style {
    double width;      /* > 0 */
    aa_line_join join; /* SVG's default miter */
    aa_line_cap cap;   /* SVG's default butt */
    double miterlimit; /* >= 1; SVG's default 4 */
    const double *dash; /* NULL or ndash >= 1 lengths >= 0, not all 0 (an odd
                         * count repeats, as SVG says) */
    size_t ndash;
    double dashoffset;
} aa_stroke_style;

/* SVG's defaults: width 1, miter, butt, limit 4, no dashes. */
void aa_stroke_style_default(aa_stroke_style *st);

/* The stroke of `in` as closed contours appended to `out`, in the same
 * coordinates, such that the stroke's shape (SVG 2, "Stroke shape") is
 * exactly the set of points of non-zero winding number of `out`: every
 * contour winds about each point a non-negative number of times (each is
 * the sum of simple contours of lines, arcs, joins and caps turning the
 * positive way: a run's bodies, joins and caps are one contour, the lines
 * they share cancelled, and at a join whose inner side's triangle lies in
 * both bodies one line across it), so their union is what the non-zero
 * rule fills.  Lines and
 * circular arcs stroke exactly to lines and circular arcs; quadratic and
 * cubic Bezier arcs and elliptical arcs that are not circles to their
 * offset curves and evolutes (AA_PATH_OFFSET, exact pieces: stroke.c says
 * how), cusps included.  What cannot be stroked exactly is refused with
 * AA_EINVAL naming it (a Bezier arc nearly with a cusp: its speed within
 * 1e-9 of its size but not 0 to rounding; an arcs join that is not one
 * simple region of lines and arcs, stroke.c's arcs_join), and so is a
 * subpath of more than 10000 dashes.  stroke.c says what it
 * chose where SVG leaves room (zero-length subpaths and segments, dashes on
 * closed subpaths).  On failure `out` is as it was. */
int aa_stroke_outline(const aa_path *in, const aa_stroke_style *style, aa_path *out);

/* The length of `in` (every subpath's, a close's closing line included),
 * as aa_stroke_outline measures it for dashes: lines and circular arcs in
 * closed form, Bezier and elliptical arcs by Gauss-Legendre quadrature to
 * about 1e-15 of their length.  AA_EINVAL for a path it cannot measure. */
int aa_path_length(const aa_path *in, double *len);

/* ---- strokes in the scene model (scene_stroke.c) ----
 *
 * A stroke layer is drawn by its exact outline, and the scene keeps what
 * was stroked, so that a renderer with a stroker of its own (a peer) can
 * stroke the path itself and `export` can write it as an SVG stroke.  The
 * outline in the scene and the source always say the same thing: every
 * operation on the scene (transform, place, clip to the unit square) keeps
 * the source with it, its map composed and its layer renumbered. */
typedef struct aa_stroke_source {
    aa_path path;          /* the path stroked, in its own (user) units */
    aa_stroke_style style; /* style.dash points to the source's own copy */
    double m[6];           /* user units to the scene's: x' = m0 x + m2 y + m4,
                            * y' = m1 x + m3 y + m5 */
    int layer;             /* the layer holding its outline */
} aa_stroke_source;

/* Add a front layer of `colour`, non-zero rule, holding the exact outline
 * of `path` stroked with `st` (aa_stroke_outline, in user units) mapped by
 * m (NULL: the identity), and keep a copy of path, style (its dashes
 * included) and map as the layer's stroke source.  What the outline
 * refuses (Bezier arcs and non-circular arcs until they stroke exactly)
 * is refused here with its message; on any failure the scene is as it
 * was. */
int aa_scene_stroke(aa_scene *s, const aa_path *path, const aa_stroke_style *st,
                    const double m[6], aa_rgb colour);
/* The scene's stroke sources, by ascending layer; *n their count. */
const aa_stroke_source *aa_scene_stroke_sources(const aa_scene *s, size_t *n);
/* The index of the source stroked into `layer`, or -1 for a filled layer. */
int aa_scene_layer_stroked(const aa_scene *s, int layer);
/* A 64-bit hash (FNV-1a) of everything the scene draws and says: the
 * background, the layers' colours and rules, every edge and contour, the
 * stroke sources (path, style, dashes, map, layer) and a field with its
 * parameters and map.  Two scenes that differ in any of them, a stroke's
 * style alone included (a peer strokes from it), hash differently but for
 * a collision. */
unsigned long long aa_scene_hash(const aa_scene *s);

#endif
