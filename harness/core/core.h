/*
 * core.h: the core's internal interface (harness/core, patterns/): specs,
 * sizes, image files, building and placing scenes, fields, the filter and
 * pattern tables, method instances and the method table, plug-in loading,
 * files and the clock.  Includes the plug-in header, aabench.h.
 */
#ifndef AA_CORE_H
#define AA_CORE_H

#include "aabench.h"

#define AA_VERSION "0.1.0"

#ifdef __cplusplus
extern "C" {
#endif

/* The shell exit status for a library status (0, 1, 2 or 3). */
int aa_exit_code(int status);

/* Warnings: something was wrong and was worked around (a corrupt cache file
 * recomputed, say).  The library calls the handler installed here, from any
 * thread (the handler must be thread-safe); with none, warnings are dropped.
 * The command line installs one that prints to stderr. */
typedef void (*aa_warn_fn)(const char *message, void *ctx);
void aa_set_warn(aa_warn_fn fn, void *ctx);
/* The handler installed now (NULL: none), its context into *ctx (may be
 * NULL): to put it back after a change. */
aa_warn_fn aa_get_warn(void **ctx);
void aa_warn(const char *fmt, ...) AA_PRINTF(1, 2);
/* An input as messages quote it: control characters escaped, and past 96
 * characters only the first 64 and "...(N characters)".  The text lives in
 * one of four per-thread buffers: at most four per message. */
const char *aa_echo(const char *text);


/* Parse `text` against `table` (a NULL-terminated array of pointers to types
 * whose first member is an aa_info).  `what` names the kind in messages
 * ("pattern", "filter", "method").  Refuses unknown names and keys, repeated
 * keys, values that are malformed, not finite or out of range, and lists
 * what is accepted. */
int aa_spec_parse(const char *text, const void *const *table, const char *what,
                  aa_spec *out);
/* The spec with every parameter at its default. */
void aa_spec_default(const aa_info *info, aa_spec *out);
/* Canonical text: "name:key=value,..." with every parameter, each number
 * in the shortest form that reads back to the same double (0.6). */
int aa_spec_format(const aa_spec *spec, char *buf, size_t len);
/* The same with every number %.17g: the reference cache's keys, whose
 * names (hashes) must not change. */
int aa_spec_format_key(const aa_spec *spec, char *buf, size_t len);
/* Index of parameter `key`, or -1. */
/* A file-name-safe form of a spec: letters, digits, '.' and '-' kept, every
 * other character '_'. */
void aa_spec_slug(const char *text, char *buf, size_t len);
/* Parse one value for `param` (used by spec parsing and by options). */
int aa_param_parse(const aa_param *param, const char *text, double *value);
size_t aa_param_count(const aa_info *info);
/* Look a name up in a table; NULL if absent (no error recorded). */
const aa_info *aa_table_find(const void *const *table, const char *name);

/* "WxH" with 1 <= W, H <= AA_MAX_SIDE, and an image of `channels` doubles
 * per pixel (`copies` of it) must fit in the memory budget below. */
#define AA_MAX_SIDE 65536
int aa_size_parse(const char *text, int *w, int *h);
int aa_size_check(int w, int h, int channels, int copies);
/* The bytes this process may still take: the smallest of half of the
 * machine's memory, half of its cgroup's limit (memory.max, v2, or
 * memory.limit_in_bytes, v1), and what is left of its address-space and
 * data limits (RLIMIT_AS, RLIMIT_DATA); `why` (may be NULL) says which, for
 * messages.  0 if nothing is known. */
double aa_memory_budget(char *why, size_t len);
/* AA_EINVAL, with a message saying what needs how much and what the limit
 * is, if `bytes` is more than the budget; `what` names the need ("compare
 * of 2048x2048x3"). */
int aa_memory_check(double bytes, const char *what);

/* ---- image files ---- */

/* Display encoding used when an 8-bit file (.png) is written. */
typedef enum aa_encoding {
    AA_ENCODE_SRGB = 0,
    AA_ENCODE_GAMMA, /* v^(1/gamma): gamma 2 is Crow's square law */
    AA_ENCODE_LINEAR
} aa_encoding;

typedef struct aa_encode {
    aa_encoding kind;
    double gamma;
} aa_encode;

/* "srgb", "linear" or "gamma:G" (G in [1, 4]). */
int aa_encode_parse(const char *text, aa_encode *out);
double aa_encode_value(const aa_encode *e, double linear);
/* sRGB's transfer functions (IEC 61966-2-1) as the scene composites with
 * them: the encoding of a linear value and its inverse, each clamped to
 * [0, 1] (a NaN to 0). */
double aa_srgb_encode(double linear);
double aa_srgb_decode(double encoded);
/* Known image file extension (".exr", ".tif", ".tiff", ".png", ".pfm",
 * ".txt")?  1 if yes. */
int aa_image_ext_known(const char *path);
/* Write by extension: .exr/.tif/.pfm as 32-bit float linear, .png as 8-bit
 * display-encoded (enc may be NULL: sRGB; enc matters only for .png), .txt
 * as text with %.17g (finite values only).  1 to 4 channels; .png and .pfm
 * take 1 or 3.  The file is written under a temporary name and renamed, so
 * a failure leaves nothing behind.  (.pfm is written here, not by
 * OpenImageIO, whose 2.4 writer produces 8-bit P6 for it.) */
int aa_image_write(const char *path, const aa_image *im, const aa_encode *enc);
/* The same, row by row, for an image too large to hold whole (a montage):
 * begin makes the temporary file, rows adds the next `rows` rows (top row
 * first, W x rows x C doubles), finish checks that every row was written,
 * closes and renames the file into place.  After a failure of begin or
 * rows nothing is left on disk; a failed writer must still be given to
 * finish (which returns that failure) or abort (which removes the
 * temporary file).  Every write, flush and close is checked: a full disk
 * is AA_EIO and the previous file under `path` stays as it was. */
typedef struct aa_image_out aa_image_out;
int aa_image_out_begin(const char *path, int w, int h, int c, const aa_encode *enc,
                       aa_image_out **out);
int aa_image_out_rows(aa_image_out *out, const double *v, int rows);
int aa_image_out_finish(aa_image_out *out);
void aa_image_out_abort(aa_image_out *out); /* NULL is fine */
/* Read any of the formats above; 8-bit files are decoded with the encoding
 * they declare (sRGB if none).  On failure *im is left empty. */
int aa_image_read(const char *path, aa_image *im);
/* The size an image file declares (its header only: no pixel is read or
 * allocated), checked as aa_image_read checks it but for memory, so a
 * caller can count what it will hold before reading anything. */
int aa_image_file_size(const char *path, int *w, int *h, int *c);
/* AA_EIO if `path` starts as a PNG but does not end with its IEND chunk
 * (cut short: a full disk, for a PNG some other program wrote). */
int aa_png_complete(const char *path);
/* The .txt format: "# aabench W H C", then "i j v0 .. v(C-1)" per pixel. */
int aa_image_write_txt(const char *path, const aa_image *im);
int aa_image_read_txt(const char *path, aa_image *im);

/* ---- building scenes ---- */

/* Building.  Layers are added front to back.  A path starts with move_to
 * and is closed by close (or by the next move_to / finish). */
aa_scene *aa_scene_new(aa_rgb background);
void aa_scene_free(aa_scene *s);
int aa_scene_layer(aa_scene *s, aa_rgb colour, aa_fill_rule rule);
int aa_scene_move_to(aa_scene *s, double x, double y);
int aa_scene_line_to(aa_scene *s, double x, double y);
int aa_scene_quad_to(aa_scene *s, double cx, double cy, double x, double y);
/* A cubic Bezier arc from the pen through (c1x,c1y) and (c2x,c2y) to (x,y). */
int aa_scene_cubic_to(aa_scene *s, double c1x, double c1y, double c2x, double c2y, double x, double y);
/* An elliptical arc from the pen to (x, y): the points
 * (cx + ux cos t + vx sin t, cy + uy cos t + vy sin t), t from t0 to t1
 * (aa_edge).  The pen must be the point for t0 and (x, y) the point for t1,
 * each within 1e-9 of the ellipse's size (|u| + |v|); the edge starts and
 * ends at exactly the pen and (x, y), so paths close exactly.  Refused:
 * non-finite numbers, |t1 - t0| > 2 pi (beyond rounding), u and v parallel
 * (a degenerate ellipse: draw its lines instead).  t0 == t1 adds nothing. */
int aa_scene_arc_to(aa_scene *s, double cx, double cy, double ux, double uy, double vx,
                    double vy, double t0, double t1, double x, double y);
/* An offset curve or evolute of a Bezier arc or an ellipse
 * (aa_offset_curve, in this scene's coordinates through its map) from the
 * pen to (x, y), its parameter from t0 to t1 (in [0, 1] for a cubic; angles
 * at most 2 pi apart for an ellipse); the pen and (x, y) must be its points
 * there within 1e-9 of their size.  Meant for stroke outlines (path.h): the
 * curve must have no fold (an offset: d k != 1) nor extreme of the
 * curvature (an evolute) strictly inside, and B' != 0 on it but at an end
 * (aa__offset_stop).  t0 == t1 adds nothing. */
int aa_scene_offset_to(aa_scene *s, const aa_offset_curve *oc, double t0, double t1, double x,
                       double y);
int aa_scene_close(aa_scene *s);
/* Finish building: split edges into pieces and index them.  Refuses
 * non-finite coordinates.  Queries need a finished scene. */
int aa_scene_finish(aa_scene *s);
/* Add a front layer of the background colour covering everything outside
 * the unit square, when the content reaches outside it (patterns/README.md:
 * outside the unit square every pattern is its background). */
int aa_scene_clip_unit(aa_scene *s);

/* Translucency (patterns/README.md, "Coordinates and pixel values"): a
 * layer has an alpha (1 unless set), and layers may be gathered in groups,
 * each composited as a whole with its opacity, as SVG's `opacity` on a
 * group.  The colour at a point is then the layers covering it composited
 * back to front (painter's order) in sRGB-encoded values, source over,
 * each group first composited on its own over transparent, and the result
 * decoded to linear light.  A layer of alpha 1 outside every group hides
 * what is behind it, as an opaque layer always did. */
/* The alpha (in [0, 1]) of the layer added last. */
int aa_scene_set_alpha(aa_scene *s, double alpha);
/* The paint of the layer added last becomes gradient g (aabench.h,
 * aa_gradient; its stops copied): the kind and spread known, every number
 * finite, m invertible, at least one stop, offsets ascending in [0, 1],
 * colours and opacities in [0, 1]; a linear gradient's two points apart
 * (SVG paints a zero-length one with its last stop: give that as a colour);
 * a radial's r > 0, fr >= 0 and its focal circle not the end circle (SVG
 * 2 paints nothing then).  A focal circle not strictly inside the end
 * circle (|C - F| + fr >= r) is the cone case (aa_gradient_is_cone): the
 * layer paints only the points some circle of radius >= 0 passes
 * through. */
int aa_scene_set_gradient(aa_scene *s, const aa_gradient *g);
/* Where the last layer's gradient was given (e.g. an SVG file's element
 * and line), for messages that refuse it: copied (at most 191 bytes) and
 * kept by aa_scene_place.  aa_scene_layer_gradient_source: that text, or
 * "" for a layer without a gradient or without a source. */
int aa_scene_set_gradient_source(aa_scene *s, const char *source);
const char *aa_scene_layer_gradient_source(const aa_scene *s, int layer);
/* The last layer's gradient interpolates its stops in `interpolation`
 * (aabench.h, aa_interpolation; AA_INTERPOLATE_SRGB unless set): kept by
 * aa_scene_place.  In AA_INTERPOLATE_LINEAR_RGB the colour at t is
 * encode(l(t)), l the stops' linear-light channels interpolated linearly
 * in t, and it composites as every layer's encoded colour does. */
int aa_scene_set_gradient_interpolation(aa_scene *s, int interpolation);
/* The composite at (x, y) of winding numbers `wind` as aa_scene_colour_of_at
 * gives it, before the decoding: its sRGB-encoded channels (the
 * reference integrates their decoding exactly). */
void aa_scene_encoded_of_at(const aa_scene *s, const int *wind, double x, double y, double e[3]);
/* The same composite with layer `layer` painting paint[] (sRGB-encoded
 * channels and opacity, before the layer's alpha) and every other layer
 * its own colour (a gradient layer its first stop's): with one gradient
 * in the scene, the composite as a function of that layer's colour and
 * opacity, which is affine in the opacity and in opacity times channel
 * (the reference of radial gradients reads it so, truth.c). */
void aa_scene_encoded_with(const aa_scene *s, const int *wind, int layer, const double paint[4],
                           double e[3]);
/* The same with n layers, layers[k] painting paints[4 k .. 4 k + 3]: the
 * composite is affine in each layer's opacity and opacity times channel
 * separately (source over and group opacity are), so a product of such
 * terms over the layers; the reference reads its coefficients from
 * composites at three paints per layer (truth.c, "several gradients"). */
void aa_scene_encoded_with_n(const aa_scene *s, const int *wind, int n, const int *layers,
                             const double *paints, double e[3]);
/* The same composite as a program the caller folds: base[] the encoded
 * colour behind (the front-most covering layer of alpha 1 in no group and
 * not among layers[0 .. n - 1], or the background), then, back to front,
 * steps: AA_FOLD_LAYER (layer `layer` of alpha `a` and own encoded colour
 * c[], source over the innermost open group's accumulator), AA_FOLD_OPEN
 * (a group, its accumulator transparent) and AA_FOLD_CLOSE (the innermost
 * group, of opacity `a`, source over its parent's).  The layers[] are
 * folded whatever their paint (painted opaque they give the same
 * composite as aa_scene_encoded_with_n, which then starts from them).
 * Returns the number of steps (at most nlayers + 2 ngroups,
 * aa_scene_fold_cap), or -1 if more than cap. */
enum { AA_FOLD_LAYER, AA_FOLD_OPEN, AA_FOLD_CLOSE };
typedef struct aa_fold_step {
    int op, layer;
    double a, c[3];
} aa_fold_step;
int aa_scene_fold_cap(const aa_scene *s);
int aa_scene_fold(const aa_scene *s, const int *wind, int n, const int *layers, aa_fold_step *steps,
                  int cap, double base[3]);
/* Layers added from now until the matching end belong to a new group of
 * opacity in [0, 1], inside the group open now (at most
 * AA_SCENE_MAX_GROUP_DEPTH deep).  Layers go front to back, so a group is
 * begun at its front layer. */
#define AA_SCENE_MAX_GROUP_DEPTH 64
int aa_scene_group_begin(aa_scene *s, double opacity);
int aa_scene_group_end(aa_scene *s);
/* What export needs: the alpha and innermost group of a layer (-1: none), a
 * group's parent (-1: none) and opacity. */
double aa_scene_layer_alpha(const aa_scene *s, int layer);
int aa_scene_layer_group(const aa_scene *s, int layer);
int aa_scene_group_count(const aa_scene *s);
int aa_scene_group_parent(const aa_scene *s, int group);
double aa_scene_group_opacity(const aa_scene *s, int group);

/* A copy of the finished scene s still open for building (NULL on
 * failure, reported): layers added to it lie behind s's (layers go front
 * to back), and aa__scene_finish_copy finishes it with `hint` as the
 * height of its index's bins (aa_scene_place's: 1, one pixel row).  For a
 * method that adds geometry of its own, read through its own values of
 * the windings (analytic's stop lines). */
aa_scene *aa__scene_copy_open(const aa_scene *s);
int aa__scene_finish_copy(aa_scene *s, double hint);
/* 1 if `layer` paints the points of winding numbers `wind`: no clip's
 * member, its fill rule holds, and inside its clip (the test
 * aa_scene_colour_of makes of each layer, front to back). */
int aa__scene_covers(const aa_scene *s, const int *wind, int layer);

/* Clips (patterns/README.md, SVG's clipPath): geometry that paints
 * nothing but gates other layers.  clip_begin starts the next clip (its
 * number is the count of clips begun before it), itself clipped by the
 * earlier clip `within` (-1: none); clip_layer adds a member layer of it,
 * a path with a fill rule like any layer's; clip_end ends it and gives its
 * number.  The clip is the union of its members, each the region where
 * its fill rule holds (and inside its own clip, if set), intersected with
 * `within`.  set_clip gates the layer added last (a painting layer or a
 * member) by an ended clip: it paints, or counts, only inside the clip.
 * A clip's members are contiguous; no painting layer, group or other clip
 * begins inside a clip's definition.  At most AA_SCENE_MAX_CLIP_DEPTH
 * clips in a chain of references. */
#define AA_SCENE_MAX_CLIP_DEPTH 32
int aa_scene_clip_begin(aa_scene *s, int within);
int aa_scene_clip_layer(aa_scene *s, aa_fill_rule rule);
int aa_scene_clip_end(aa_scene *s, int *clip);
int aa_scene_set_clip(aa_scene *s, int clip);

/* A finished copy mapped by x' = sx x + tx, y' = sy y + ty (sx, sy > 0). */
aa_scene *aa_scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty);
/* The scene placed on a W x H image at time t (frames) moving (vx, vy)
 * pixels per frame: in pixel units, u = W x + t vx, v = H y + t vy. */
aa_scene *aa_scene_place(const aa_scene *s, int w, int h, double t, double vx, double vy);

/* The heights (ascending, at most max) in (ya, yb) where two pieces meet
 * (cross or touch) while both are present: in closed form for lines, a
 * line and an arc, and two arcs whose x is quadratic in y; a line and a
 * cubic at the roots of a cubic in t (isolated between the roots of its
 * derivative, then bisected and Newton-polished to full precision); for two
 * general arcs by bisection on their exact x extents (to 1e-12 relative;
 * with a cubic, an interval of 1e-6 relative across which the difference
 * of their x changes sign is polished by Newton's method, safeguarded by
 * bisection, to full precision), which
 * cannot miss a meeting while its budget of 4096 subintervals lasts (two
 * arcs running side by side over a long stretch can use it up, and a
 * meeting is then lost: harness/truth/truth_crowd.c finds theirs from a
 * quartic instead).  With an offset piece, each interval is first decided
 * by the two pieces' slope ranges where both are bounded (scene_piece.c,
 * slopes_say): pieces running side by side are then told apart at once
 * instead of using up the budget, and pieces within rounding of each
 * other over an interval, crossing at a small angle or touching, report
 * no meeting there (or one at its end) where the region between them
 * that a meeting could misplace is under 1e-15 (square pixels in a
 * placed scene).  Flat pieces meet nothing. */
int aa_piece_meet(const aa_piece *p, const aa_piece *q, double ya, double yb, double *ys,
                  int max);
/* aa_piece_meet with offset pieces' parameters at heights ya and yb
 * already known to the caller (tpa for p, tqa for q; NaN where not known,
 * and ignored for other kinds): where the common heights start at ya or
 * end at yb they are taken as they are, not solved for again (area.c
 * passes each band's).  Its meetings are polished from the chord's root
 * and stopped by an error estimate (scene_piece.c, polish_meet): the same
 * heights as aa_piece_meet's to rounding, not bit for bit. */
int aa__piece_meet_at(const aa_piece *p, const aa_piece *q, double ya, double yb,
                      const double tpa[2], const double tqa[2], double *ys, int max);
/* aa__piece_meet_at with offset pieces' x at heights ya and yb known too
 * (xpa, xqa; NaN where not known): each must be aa__piece_end_x at the
 * height and the parameter passed there (area.c keeps a seg's, asked by
 * every pair the seg is in).  The same meetings bit for bit. */
int aa__piece_meet_atx(const aa_piece *p, const aa_piece *q, double ya, double yb,
                       const double tpa[2], const double tqa[2], const double xpa[2],
                       const double xqa[2], double *ys, int max);
/* x of piece p at height y, its parameter there t (an offset piece's;
 * ignored for other kinds): what the meetings take at their ends. */
double aa__piece_end_x(const aa_piece *p, double y, double t);
/* 1 if x_p - x_q is strictly monotone in y over the heights where line or
 * offset pieces p and q have their parameters between tp[0] and tp[1] and
 * between tq[0] and tq[1] (offset pieces; a line's are ignored): the cones
 * of their tangents lie apart (scene_piece.c, cones_apart), by which
 * aa__piece_meet_at parts a pair at once.  0 where nothing is proven. */
int aa__piece_cones_apart(const aa_piece *p, const aa_piece *q, const double tp[2],
                          const double tq[2]);
/* 1 if offset pieces p and q are a stroke's two sides, the offsets at d and
 * -d of one cubic under one map, over parameter ranges on whose hull the
 * cubic's directions lie in a cone narrower than pi/2: proven never to
 * meet (scene_piece.c, sides_apart), by which aa__piece_meet_at parts such
 * a pair where the cones do not.  0 where nothing is proven. */
int aa__piece_sides_apart(const aa_piece *p, const aa_piece *q);

/* ------------------------------------------------------------------------
 * Fields: a procedural scene, a point function plus its own exact pixel
 * integral (harness/README.md, "The three contracts"), such as the zone plate.
 *
 * A scene carries either layers of paths or one field, never both: a field
 * scene has no layers, no edges and no pieces, covers the whole plane and
 * has no background showing.  The field is defined in its own units (the
 * pattern's); the scene keeps the map to them, so placing or transforming a
 * field scene only composes that map and the field stays exact.  Queries on
 * a field scene: aa_scene_colour_at gives the field's value, crossings and
 * touching give none, aa_scene_bounds gives the whole plane (infinite
 * bounds, returns 1), aa_scene_is_grey the field's own greyness.
 * ------------------------------------------------------------------------ */

#define AA_FIELD_MAX_PARAMS 8

struct aa_filter; /* below, with the filters */

typedef struct aa_field_type {
    const char *name;
    /* bump when its reference values could change (part of the cache key) */
    int version;
    int grey; /* 1 if every value is grey */
    /* The value at (x, y) in the field's own units. */
    aa_rgb (*value)(const double *p, double x, double y);
    /* The exact filtered image of the field placed so that its own point
     * (x, y) is at (map[0] x + map[2], map[1] y + map[3]) in pixel units:
     * pixel (i, j) is the integral of f(u - i - 1/2, v - j - 1/2) times the
     * value there.  bound (may be NULL): 1 channel, per-pixel error bounds;
     * *max_bound and *worst (i, j) receive the largest.  threads <= 0:
     * OpenMP's default. */
    int (*pixels)(const double *p, const double map[4], const struct aa_filter *f, int threads,
                  aa_image *out, aa_image *bound, double *max_bound, int worst[2]);
} aa_field_type;

/* Make an empty, unfinished scene (no layers yet) a field scene with
 * parameters p[0 .. n) (n <= AA_FIELD_MAX_PARAMS); the map is the identity.
 * Layers added afterwards are refused, and so is a field on a scene that
 * has layers. */
int aa_scene_set_field(aa_scene *s, const aa_field_type *type, const double *p, int n);
/* The scene's field, or NULL for a scene of layers; *p and *n (may be
 * NULL) get its parameters and their count, map (may be NULL) the map from
 * its units to the scene's (sx, sy, tx, ty: x' = sx x + tx, y' = sy y + ty). */
const aa_field_type *aa_scene_field(const aa_scene *s, const double **p, int *n,
                                    double map[4]);

/* ---- SVG (svg.c) ---- */

/* What an SVG of a scene paints. */
typedef enum aa_svg_paint {
    AA_SVG_COLOURS = 0, /* the background, then each layer in its colour */
    AA_SVG_MASK = 1     /* black, then every layer white: one layer's coverage */
} aa_svg_paint;

/* A placed scene (pixel units) as an SVG document of w x h pixels: viewBox
 * 0 0 w h, a rectangle of the background colour over the image, then one
 * <path> per layer in painter's order (the back layer first), with the
 * layer's fill-rule, lines as L, quadratic arcs as Q, cubic arcs as C and
 * elliptical arcs as A, in pieces of at most 90 degrees (svg.c), numbers
 * %.17g;
 * colours as rgb() percentages of the sRGB-encoded linear colour at full
 * precision (svg.c says why).  A layer kept as a stroke (aa_scene_stroke)
 * is written as the stroke: its source's path, fill="none", the stroke's
 * properties and the source's map as transform="matrix(...)".  `desc` (may be NULL) goes in a <desc>.
 * *text is malloc'd and NUL-terminated, *len its length.  A field scene is
 * refused (AA_EINVAL): it has no paths. */
int aa_scene_svg(const aa_scene *placed, int w, int h, aa_svg_paint paint, const char *desc,
                 char **text, size_t *len);
/* The same written to `path` (atomically). */
int aa_scene_svg_write(const char *path, const aa_scene *placed, int w, int h,
                       aa_svg_paint paint, const char *desc);

/* ---- the filter table ---- */

extern const aa_filter_type *const aa_filter_types[]; /* NULL-terminated */

int aa_filter_parse(const char *text, aa_filter *out);
void aa_filter_default(aa_filter *out); /* box */

/* ------------------------------------------------------------------------
 * Patterns (patterns/): named, parameterised scenes (patterns/README.md)
 * ------------------------------------------------------------------------ */

typedef struct aa_pattern_type {
    aa_info info;
    /* Refuse parameter values outside the pattern's domain beyond the
     * simple ranges (records the reason). */
    int (*check)(const double *p);
    /* Add layers and paths to an empty scene (the background is set). */
    int (*build)(const double *p, aa_scene *s);
    aa_rgb background;
} aa_pattern_type;

extern const aa_pattern_type *const aa_pattern_types[]; /* NULL-terminated */

int aa_pattern_parse(const char *text, aa_spec *out);
/* Build the finished scene (pattern units) of a parsed pattern spec. */
int aa_pattern_scene(const aa_spec *spec, aa_scene **out);
/* The same for a view of w x h pixels.  A pattern drawn at the view's size
 * (`svg`, `text`: their geometry is in pixels, so the unit square holds a
 * different part of it at each size) needs it and is refused by
 * aa_pattern_scene; the others ignore w and h. */
int aa_pattern_scene_at(const aa_spec *spec, int w, int h, aa_scene **out);
/* 1 if the pattern is drawn at the view's size (above). */
int aa_pattern_sized(const aa_spec *spec);
/* The image size a pattern drawn at the view's size has of its own (svg:
 * the file's width and height times its scale), or AA_EINVAL saying -s is
 * needed. */
int aa_pattern_own_size(const aa_spec *spec, int *w, int *h);
/* 1 if the pattern has a size of its own (aa_pattern_own_size). */
int aa_pattern_has_own_size(const aa_spec *spec);
/* What the cache key of a view adds for the pattern beyond its canonical
 * text: for a pattern read from files (`svg`, `text`), a line per file with
 * the hash and length of its bytes, so that a file changed under the same
 * name is never served an old reference; "" for the others.  Appended to
 * buf (len bytes, NUL included). */
int aa_pattern_key(const aa_spec *spec, char *buf, size_t len);

/* ------------------------------------------------------------------------
 * Displays: where a method's dots are shown (Crow 1976, ch. 4, "A temporal
 * scheme": "the data in the scene description is shifted to compensate.
 * Therefore, the image always stays in the same place on the screen while
 * the dot positions change").
 *
 * An ordinary method's value of pixel (i, j) is shown on the pixel's own
 * square, and is measured against the reference of that pixel.  A method
 * flagged AA_METHOD_DISPLAY shows each of its frames on a screen whose
 * dots are moved: in frame k the dot of pixel p is a uniform square one
 * pixel wide centred on p's centre plus (dx_k, dy_k), the dots of a frame
 * tiling the plane (a flat field, the dots just touching) and covering the
 * image with a ring of one dot beyond its border.  Its image is the
 * eye's: the frames' screens, weighted, seen through the image's fixed
 * pixel squares (the mean of the screen over each square).  So a frame
 * whose dots have values x(p) gives pixel q
 *
 *     sum over p of x(p) a(q - p - d_k),  a(u, v) = max(0, 1 - |u|) max(0, 1 - |v|),
 *
 * the area of pixel q that dot p covers.  The reference it is measured
 * against is the same screen showing in each dot its exact value, the
 * scene at the frame's time convolved with the filter at the dot's centre
 * (harness/bench/display.c).  With every offset 0 this is the ordinary
 * display and the ordinary reference.
 * ------------------------------------------------------------------------ */

/* A method's image is what a screen shows whose dots move from frame to
 * frame (Crow 1976, ch. 4): its type is the `method` member of an
 * aa_display_method_type, whose `display` says where.  For built-in
 * methods (aa_method_flags, aabench.h). */
#define AA_METHOD_DISPLAY 16

#define AA_DISPLAY_MAX_FRAMES 64

typedef struct aa_display_frame {
    double t;      /* the frame's time */
    double dx, dy; /* its dots' offset from the pixel centres, in pixels, within [-1, 1] */
    double weight; /* its share of the image; the shares of an image sum to 1 */
} aa_display_frame;

typedef struct aa_display_method_type {
    aa_method_type method; /* flags include AA_METHOD_DISPLAY; first, so that a
                            * pointer to this is a pointer to the method */
    /* The frames the image of `job` is made of (at most
     * AA_DISPLAY_MAX_FRAMES) into frames[], their count into *n; *n = 0
     * when this image is shown in the ordinary way.  Never reads the scene. */
    int (*display)(const double *p, const aa_job *job, aa_display_frame *frames, int *n);
} aa_display_method_type;

/* ---- method instances and the method table ---- */

/* Build a job for a pattern scene (placing it at t); aa_job_free frees
 * only what aa_job_init made (the placed scene). */
int aa_job_init(aa_job *job, const aa_scene *pattern, int w, int h, double t, double vx,
                double vy, const aa_filter *f, uint64_t seed, int threads);
void aa_job_free(aa_job *job);

typedef struct aa_method {
    const aa_method_type *type;
    aa_spec spec;
    void *state;
} aa_method;

/* The method table in use: the method types registered, in the order
 * registered (the built-in ones, then the optional ones and those of
 * loaded plug-ins).  NULL-terminated; valid until the next registration.
 * Empty, it warns once: the built-in methods were not linked in. */
const void *const *aa_method_table(void);
/* Add method types (NULL-terminated) to the table in use; `origin` names
 * them in messages (a plug-in's path).  Refuses a type without a name,
 * summary or render, a name already in the table, more than AA_MAX_PARAMS
 * parameters, and a table that would grow past its limit; on refusal
 * nothing is added. */
int aa_method_register(const aa_method_type *const *types, const char *origin);
/* The plug-in file registered types were loaded from (aa_plugin_load
 * records it), and a type's: NULL for a built-in one. */
int aa_method_set_file(const aa_method_type *const *types, const char *path);
const char *aa_method_file(const aa_method_type *type);

/* The built-in method types (algorithms/methods.c), NULL-terminated. */
extern const aa_method_type *const aa_method_types[];
/* Register them: done when the library starts (a constructor in
 * methods.c), so a program need not.  A program that links libaabench.a
 * and refers to nothing of the methods' own does not link methods.c in,
 * and calls this first.  A second call does nothing. */
int aa_method_add_builtin(void);
/* Methods that need an optional program (an external renderer), kept out of
 * the built-in table that the generic tests render every method of.  The
 * command adds them at start; a program of one's own may too.  A second
 * call does nothing.  Defined in algorithms/methods.c. */
extern const aa_method_type *const aa_method_types_optional[];
int aa_method_add_optional(void);
/* The time limit of the programs the external method runs: each one it
 * starts from now on is killed, with what it started, when `seconds` have
 * passed since this call, and its render fails with "timed out after S s".
 * A run calls it as each case starts, `render` once.  Without a call, or
 * after one with 0, each program gets 600 s of its own.  Defined in
 * algorithms/external.c. */
void aa_external_time_limit(double seconds);
/* Parse a method spec and check it against the filter. */
int aa_method_parse(const char *text, const aa_filter *f, aa_spec *out);
/* Check a parsed method spec against a filter (the method's own check). */
int aa_method_check(const aa_spec *spec, const aa_filter *f);
int aa_method_init(aa_method *m, const aa_spec *spec, const aa_job *job);
int aa_method_render(aa_method *m, const aa_job *job, aa_image *out, aa_counters *counters);
void aa_method_free(aa_method *m);

/* Render `reps` times (after one untimed init); the image and counters are
 * those of the last render, `seconds` receives each render's time (may be
 * NULL).  The image must be allocated W x H x 3 and is touched before
 * timing, so page faults are not counted. */
int aa_method_run(const aa_spec *spec, const aa_job *job, int reps, aa_image *out,
                  aa_counters *counters, double *seconds);

/* Where the image of `spec` for `job` is shown ("Displays" above):
 * its frames into frames[AA_DISPLAY_MAX_FRAMES] and their count into *n, 0
 * for a method shown in the ordinary way (every method not flagged
 * AA_METHOD_DISPLAY).  The frames are checked: offsets within [-1, 1],
 * weights that sum to 1. */
int aa_method_display(const aa_spec *spec, const aa_job *job, aa_display_frame *frames,
                      int *n);

/* ---- timing and its statistics (timing.c) ----
 *
 * A case is timed as hyperfine and Google Benchmark do: after the untimed
 * init, one untimed render (warm-up), then timed renders until the 95%
 * confidence interval of the median is within `target_ci` of it (relative
 * half-width) or `budget` seconds of timed renders have passed, with at
 * least AA_TIMING_MIN_REPS and at most AA_TIMING_MAX_REPS; or exactly
 * `reps` renders when reps > 0.  Each render's wall time is taken on the
 * monotonic clock and its CPU time on the calling thread's clock (one
 * thread) or the process's (several), so preemption shows as wall time well
 * above CPU time.  Around the renders the load average and /proc/stat are
 * read, to see whether other processes used the cores meanwhile.  The
 * statistics are taken from the wall times alone; CPU time (the children's
 * too: an external renderer's program) only tells contention. */
#define AA_TIMING_MAX_REPS 1000
#define AA_TIMING_MIN_REPS 5
#define AA_TIMING_TARGET 0.02  /* default target_ci: 2% */
#define AA_TIMING_BUDGET 1.0   /* default budget, seconds */
/* The fewest renders that give a 95% interval of the median: 5 cover at
 * most 1 - 2/32 (aa_median_ci_ranks). */
#define AA_TIMING_CI_MIN_REPS 6
/* Other processes "used the cores" above this many cores on average. */
#define AA_TIMING_BUSY_CORES 0.10
/* /proc/stat counts whole ticks (two a core of error over a window): a
 * window whose error is this many cores or more is too short for it, and
 * the load average around it, less the process's own threads, is read
 * instead, with this many cores of allowance. */
#define AA_TIMING_STAT_WINDOW 0.25
#define AA_TIMING_BUSY_LOAD 0.5
/* One thread "was preempted" when its CPU time is below this share of its
 * wall time. */
#define AA_TIMING_CPU_SHARE 0.95

typedef struct aa_timing_plan {
    int reps;         /* > 0: exactly this many timed renders; 0: by precision */
    double target_ci; /* relative half-width of the median's 95% CI; 0: 2% */
    double budget;    /* seconds of timed renders per case; 0: 1 s */
} aa_timing_plan;

/* Statistics of a sample of times.  The confidence interval of the median
 * is distribution-free: the order statistics x(l), x(n+1-l) with l the
 * largest rank such that P(B <= l - 1) <= 2.5% for B ~ Binomial(n, 1/2);
 * its coverage 1 - 2 P(B <= l - 1) is ci_level (>= 0.95).  With fewer than
 * 6 values no such interval exists: ci_lo, ci_hi and ci_level are NaN.
 * mad is the median absolute deviation scaled by 1.4826 (an estimate of
 * the standard deviation for normal data, gsl_stats_mad); an outlier lies
 * more than 3 mad from the median. */
typedef struct aa_time_stats {
    size_t n;
    double median, mean, sd, mad, min, max;
    double ci_lo, ci_hi, ci_level;
    size_t outliers;
} aa_time_stats;
int aa_time_stats_compute(const double *x, size_t n, aa_time_stats *s);
/* How far the outliers move the median: |median of all - median of those
 * within 3 mad| / the latter; 0 without outliers. */
double aa_time_stats_outlier_shift(const double *x, size_t n);
/* The 1-based ranks lo, hi of the order statistics that bound the median
 * with coverage at least `level` (0 < level < 1), and that coverage;
 * AA_EINVAL if n is too small for any. */
int aa_median_ci_ranks(size_t n, double level, size_t *lo, size_t *hi, double *coverage);
/* The mean of n >= 2 values and its `level` confidence interval by
 * Student's t (gsl_cdf_tdist_Pinv). */
int aa_mean_ci(const double *x, size_t n, double level, double *mean, double *lo, double *hi);
/* Mann-Whitney U test of x against y (two-sided), normal approximation
 * with the tie correction and no continuity correction (R's wilcox.test
 * with exact = FALSE, correct = FALSE): u is U of x (the number of pairs
 * with x above y, ties counting one half), z its standard score (positive:
 * x tends to be larger), p the two-sided p-value (gsl_cdf_ugaussian_Q). */
int aa_mann_whitney(const double *x, size_t nx, const double *y, size_t ny, double *u, double *z,
                    double *p);

/* Why a measurement is marked noisy (aa_timing.noisy). */
enum {
    AA_NOISY_CI = 1,        /* the CI target was not met */
    AA_NOISY_OUTLIERS = 2,  /* outliers moved the median by more than the target */
    AA_NOISY_BUSY = 4,      /* other processes used the cores */
    AA_NOISY_STEAL = 8,     /* the hypervisor took more than 1% of the cores' time */
    AA_NOISY_PREEMPTED = 16 /* one thread: CPU time below 95% of wall time */
};
/* "ci+busy": the reasons' names joined by '+', "" if none. */
void aa_noisy_text(unsigned noisy, char *buf, size_t len);
/* The names back to AA_NOISY_* bits; unknown names are ignored. */
unsigned aa_noisy_parse(const char *text);

typedef struct aa_timing {
    int n;          /* timed renders */
    int threads;    /* threads of the job */
    int fixed;      /* 1: a fixed count was asked (plan.reps) */
    double target_ci, budget;
    double wall[AA_TIMING_MAX_REPS], cpu[AA_TIMING_MAX_REPS]; /* seconds, in order */
    aa_time_stats stats;  /* of wall */
    double ci_rel;        /* (ci_hi - ci_lo) / 2 / median; NaN without a CI */
    double cpu_median;    /* median CPU time of a render */
    int target_met;
    /* the machine around the timed renders */
    double load_before, load_after; /* 1-minute load average (NaN: unknown) */
    double others_cores;  /* other processes' mean busy cores, 0 to the cores (NaN: unknown) */
    double steal;         /* share of the cores' time stolen (NaN: unknown) */
    double cpu_share;     /* total CPU time / total wall time of the renders */
    double elapsed;       /* seconds from the warm-up's start to the last render's end */
    unsigned noisy;       /* AA_NOISY_* */
    int reported;         /* renders whose time the method reported (below) */
    /* the method's init, timed once on its own before the renders (its
     * tables for the scene, size and filter): wall and process CPU
     * seconds, NaN where not measured; the renders' times leave it out */
    double init_seconds, init_cpu;
} aa_timing;

/* The median's interval as text: "+-1.2%", "CI needs 6 renders" with
 * fewer renders than an interval needs, "no CI" otherwise. */
void aa_timing_ci_text(const aa_timing *t, char *buf, size_t len);

/* The machine read before and after a measurement. */
typedef struct aa_machine_sample {
    double wall, load, own; /* seconds; 1-minute load; this process's and its children's CPU */
    int have_stat;
    unsigned long long busy, steal, total; /* /proc/stat's ticks over every core */
} aa_machine_sample;
/* Other processes' mean busy cores between two samples (clamped to [0,
 * cores]), the stolen share of the cores' time, and the allowance in cores
 * a busy verdict must clear: from /proc/stat's busy ticks less the
 * process's own CPU when the window holds enough ticks
 * (AA_TIMING_STAT_WINDOW), else from the lower load average less
 * `threads`.  NaN where unknown. */
void aa_machine_use(const aa_machine_sample *a, const aa_machine_sample *b, long hz, long cores,
                    int threads, double *others, double *steal, double *allowance);
/* Set t->noisy from its times, target and machine figures (ci, outliers,
 * others_cores, steal, cpu_share, threads): by effect, the target missed
 * or outliers that move the median beyond it, and by contention. */
void aa_timing_judge(aa_timing *t, double allowance, long cores);

/* For a built-in method that runs another program (AA_METHOD_EXTERNAL) and
 * is told that program's own render time: called from its render, it makes
 * that the render's wall and CPU time in aa_timing_measure (this thread's
 * next timed render only).  Seconds, finite and >= 0. */
void aa_method_report_seconds(double seconds);

/* Time `k` functions taking turns (fn[i](ctx[i]) renders once; threads[i]
 * is its thread count), each warmed up once, until each meets the plan's
 * target or k times the budget has passed; out[i] gets each one's timing
 * and the noise seen around them all.  A function's non-zero status stops
 * everything and is returned. */
typedef int (*aa_timed_fn)(void *ctx);
int aa_timing_measure(const aa_timing_plan *plan, size_t k, aa_timed_fn const *fn,
                      void *const *ctx, const int *threads, aa_timing *out);
/* A method timed by the plan: init (untimed), a warm-up render, the timed
 * renders; the image and counters are those of the last render.  The image
 * is touched before timing. */
int aa_method_time(const aa_spec *spec, const aa_job *job, const aa_timing_plan *plan,
                   aa_image *out, aa_counters *counters, aa_timing *timing);

/* Plug-ins: a shared library exporting `aa_plugin_abi` (an int equal to
 * AA_PLUGIN_ABI) and `aa_plugin_methods` (a NULL-terminated array of
 * pointers to aa_method_type).  Its methods join the table; a name that is
 * already there is refused. */
int aa_plugin_load(const char *path);

/* The values a method's image under filter f may hold: [0, 1] for filters
 * without negative lobes; for the others aa_filter_range's [-N, 1 + N]
 * widened to [-2N, 1 + 2N], as a method that samples or tabulates the
 * weight may reach a little past the exact extremes. */
void aa_method_value_range(const aa_filter *f, double *lo, double *hi);
/* Values of a method's image outside [lo, hi] or not finite: their count
 * (0 if none), and the first one's pixel and channel in at[0..2] (i, j,
 * channel) and value in *value.  A method's image with any is a failed
 * render, never a result. */
size_t aa_image_bad_values(const aa_image *im, double lo, double hi, int at[3], double *value);

/* The threads to use for a `threads` argument: itself if positive, else
 * OpenMP's default (OMP_NUM_THREADS, or the cores) clamped to at most four
 * per core and AA_MAX_THREADS, so an absurd environment cannot crash the
 * thread library. */
#define AA_MAX_THREADS 1024
int aa_thread_count(int threads);

/* ---- files and the clock ---- */

/* Write `len` bytes to `path` through a temporary file in the same folder
 * and rename; nothing is left behind on failure. */
int aa_file_write_atomic(const char *path, const void *data, size_t len);
/* mkdir -p */
int aa_mkdirs(const char *path);
/* snprintf for paths: AA_EINVAL if the result does not fit. */
int aa_pathf(char *buf, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* A temporary name beside `path` keeping its extension. */
int aa_temp_name(const char *path, char *buf, size_t len);
/* Remove the temporary files of the last names aa_temp_name gave that are
 * still on disk: for a signal handler (async-signal-safe). */
void aa_temp_cleanup(void);

/* Monotonic clock in seconds. */
double aa_now(void);

/* ---- where the data is (paths.c) ---- */

/* The root of the source tree the running program was built in (the
 * folder holding harness/aabench.h and patterns/svg), found at run time
 * from the program's file or the library's, up to three folders above it;
 * NULL when it runs from elsewhere (installed). */
const char *aa_source_tree(void);
/* The folder of the shipped SVG scenes: $AABENCH_SVG_DIR if set; else the
 * source tree's patterns/svg; else share/aabench/svg beside the program's
 * bin/ folder; else the install prefix's (PREFIX/share/aabench/svg). */
const char *aa_svg_dir(void);
/* The reference cache's default folder: $AABENCH_CACHE if set; else, run
 * from a source tree with the current folder inside it, results/cache
 * (relative at the tree's root, the root's below it); else
 * $XDG_CACHE_HOME/aabench, or ~/.cache/aabench ($HOME); results/cache when
 * neither is set.  The text is valid until the thread's next call. */
const char *aa_cache_dir_default(void);

/* ---- offset curves of Bezier arcs and ellipses (offset.c; aabench.h, aa_offset_curve) ---- */

/* The point (x, y) of oc at t and its derivative (dx, dy; either NULL: not
 * wanted), in long double. */
void aa__offset_eval(const aa_offset_curve *oc, long double t, long double *x, long double *y,
                     long double *dx, long double *dy);
/* Which ends of oc are stops (aa__offset_stop's test there, once: bit 0
 * at t = 0, bit 1 at t = 1; 0 for an ellipse), and aa__offset_eval given
 * them (a caller that evaluates one curve many times): the same values,
 * bit for bit. */
int aa__offset_stops(const aa_offset_curve *oc);
void aa__offset_eval_s(const aa_offset_curve *oc, int stops, long double t, long double *x,
                       long double *y, long double *dx, long double *dy);
/* The parameters in (lo, hi) (ascending, at most 2) where coordinate coord
 * (0 x, 1 y) of oc turns, on a part without folds (an offset) or extremes
 * of the curvature (an evolute): in closed form. */
int aa__offset_turns(const aa_offset_curve *oc, int coord, double lo, double hi, double t[2]);
/* 1 if t is on the half of [0, 1] next to an end te of a cubic where B'
 * vanishes (within 1e-12 of the sum of its coefficients' magnitudes), there
 * evaluated in the factored form B' = (t - te) Q, Q(t) = (q[0] + q[1] t,
 * q[2] + q[3] t) (offset.c, header). */
int aa__offset_stop(const aa_offset_curve *oc, double t, double *te, double q[4]);
/* The parameter between ta and tb (either order) where coordinate coord of
 * oc equals target, given that it is monotone there and fa (its value at
 * ta less target) has the other sign than at tb: Newton's method kept in
 * the bracket, bisection where a step leaves it; to full long double
 * precision. */
long double aa__offset_solve(const aa_offset_curve *oc, int coord, long double ta, long double tb,
                             long double fa, long double target);
/* The same in double only, to about 1e-15 (the scene's double queries). */
double aa__offset_solve_d(const aa_offset_curve *oc, int coord, double ta, double tb, double fa,
                          double target);
/* aa__offset_solve_d started from guess (inside the bracket, tb's sign
 * taken on trust and tb not evaluated; NaN or outside: none, the same as
 * aa__offset_solve_d): for a caller that knows the root nearly, Newton's
 * step from a nearby root (one evaluation where the guess is within the
 * step tolerance's square root of the root, against three or four from
 * the bracket's ends). */
double aa__offset_solve_dg(const aa_offset_curve *oc, int coord, double ta, double tb, double fa,
                           double target, double guess);
/* The same started from guess (inside the bracket; NaN: none). */
long double aa__offset_solve_from(const aa_offset_curve *oc, int coord, long double ta,
                                  long double tb, long double fa, long double target, double guess);
/* aa__offset_solve_from that also gives the other coordinate at the root
 * (*other, to long double precision) and coordinate coord's derivative
 * there (*slope: a guess's step to a nearby target); either NULL: not
 * wanted. */
long double aa__offset_root(const aa_offset_curve *oc, int coord, long double ta, long double tb,
                            long double fa, long double target, double guess, long double *other,
                            double *slope);
/* What the solvers take from the curve alone, found once a curve
 * (aa__offset_fix_init) by a caller that solves on it many times: its
 * stops (aa__offset_stops) and the sums of the magnitudes of its x and y
 * terms (the scale of the double phase's test for a value within rounding
 * of the target).  The same numbers the solvers find themselves, so the
 * same roots, bit for bit. */
typedef struct aa__offset_fix {
    int stops;
    double sx, sy;
    /* aa__offset_fix_dd: 1 (Dekker's products) or 2 (fma) where the roots
     * and points take the double-double form, else 0; its mapped base
     * cubic, coordinate c's coefficient of t^k in dc[k][0][c] (hi) and
     * dc[k][1][c] (lo: the two coordinates side by side, for packed
     * arithmetic) */
    int dd;
    double dc[4][2][2];
    /* and its base cubic's derivative B' (unmapped), coordinate c's
     * coefficient of t^k in du[k][0][c] (hi) and du[k][1][c] (lo) */
    double du[3][2][2];
    /* and the terms' size the double phase's rounding test takes for
     * coordinate c, less the target's (its first three terms, summed as
     * there) */
    double dsize[2];
} aa__offset_fix;
void aa__offset_fix_init(const aa_offset_curve *oc, aa__offset_fix *fx);
/* aa__offset_fix_init, and on a cubic's offset (not an evolute) without
 * stops the double-double form of its roots and points (offset.c, before
 * dd_two_sum): aa__offset_root_fixd and aa__offset_root_xyd then solve
 * by Newton's method in double on the mapped base cubic and the normal
 * term each evaluated as hi + lo (TwoSum, TwoProduct), their points
 * evaluated so at the root rounded to double (within about 1.1e-16 px of
 * __float128's: tests/test_area_offset.c, test_dd), and
 * aa__offset_point_fix evaluates the point so; fma: 1 its products by
 * fma where the processor has it, 0 by Dekker's split (the same values,
 * bit for bit). */
void aa__offset_fix_dd(const aa_offset_curve *oc, aa__offset_fix *fx, int fma);
/* The point of oc at t: the double-double form's where fx has it, else
 * aa__offset_eval_s's (given fx's stops). */
void aa__offset_point_fix(const aa_offset_curve *oc, const aa__offset_fix *fx, double t,
                          long double *x, long double *y);
/* aa__offset_root given oc's aa__offset_fix and, where endb is not NULL,
 * aa__offset_end's e at tb (then without a guess: as
 * aa__offset_solve_end). */
long double aa__offset_root_fix(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                                long double ta, long double tb, long double fa,
                                long double target, double guess, const double *endb,
                                long double *other, double *slope);
/* aa__offset_root_fix, its root rounded to double, and the point there
 * (xy: x and y, as aa__offset_eval gives them to within about 1e-22 of
 * the second derivative) from the root's last evaluation moved by its
 * derivative: for a caller that would evaluate the point at the root
 * again (`area`'s band lines).  A guess strictly inside (ta, tb) is the
 * start (endb then unused); else (NaN) endb's as aa__offset_root_fix's. */
double aa__offset_root_xy(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                          long double ta, long double tb, long double fa, long double target,
                          double guess, const double *endb, long double xy[2]);
/* aa__offset_root_fix (its root rounded to double; no endb, no slope) and
 * aa__offset_root_xy with their bracket and target in double: the same
 * roots bit for bit, without long double arguments (`area`'s roots). */
double aa__offset_root_fixd(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                            double ta, double tb, double fa, double target, double guess,
                            long double *other);
double aa__offset_root_xyd(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                           double ta, double tb, double fa, double target, double guess,
                           const double *endb, long double xy[2]);
/* On the double-double form by fma (fx->dd 2): aa__offset_root_xyd's
 * (xy not NULL) or aa__offset_root_fixd's root (other) by the solver's
 * build for FMA alone, which those take where the processor has no
 * AVX-512F (else its build for AVX-512F: the same bits; for a test). */
double aa__offset_root_dd_fma(const aa_offset_curve *oc, const aa__offset_fix *fx, int coord,
                              double ta, double tb, double fa, double target, double guess,
                              const double *endb, long double xy[2], long double *other);
/* A root asked of aa__offset_roots: aa__offset_root_xyd's arguments (xy
 * not NULL: its point there; other then not written) or
 * aa__offset_root_fixd's (other), the root in t.  The requests' outputs
 * (t, xy, other) are distinct objects: they are written in another order
 * than one by one. */
typedef struct aa__offset_rootq {
    const aa_offset_curve *oc;
    const aa__offset_fix *fx;
    int coord;
    double ta, tb, fa, target, guess;
    const double *endb;
    long double *xy, *other;
    double t;
} aa__offset_rootq;
/* n roots: each q[k].t (and its xy or other) as aa__offset_root_xyd or
 * aa__offset_root_fixd give it, bit for bit; where the processor has AVX2
 * (and FMA: the double-double form by fma, fx->dd 2, says so), those
 * starting inside their brackets in that form are solved four at a time,
 * one a lane (offset.c, roots4_avx2), and where it has AVX-512F too
 * eight at a time (roots8_512: a batch of more than four), the rest one
 * by one. */
void aa__offset_roots(aa__offset_rootq *q, size_t n);
/* aa__offset_roots with at most `lanes` (8, 4 or 1) requests a batch, as
 * the processor allows: the same roots and points (for a test of each
 * width). */
void aa__offset_roots_lanes(aa__offset_rootq *q, size_t n, int lanes);
/* Coordinate coord of oc at t as the double phase of the solvers first
 * evaluates it at a bracket's far end (e[4], opaque): for a caller that
 * solves for many targets in one bracket [ta, tb] (a piece's band lines),
 * so that tb is evaluated once. */
void aa__offset_end(const aa_offset_curve *oc, int coord, double t, double e[4]);
/* On a curve of the double-double form (aa__offset_fix_dd's fx.dd set):
 * aa__offset_end's e[0] + e[1] (the coordinate) in *at and e[2] (its
 * derivative) in *slope, bit for bit, without its tests of the stops. */
void aa__offset_end_dd(const aa_offset_curve *oc, int coord, double t, double *at,
                       double *slope);
/* aa__offset_solve_from without a guess, given aa__offset_end's e at tb:
 * the same root, bit for bit, one evaluation fewer. */
long double aa__offset_solve_end(const aa_offset_curve *oc, int coord, double ta, double tb,
                                 long double fa, long double target, const double endb[4]);

#ifdef __cplusplus
}
#endif

#endif /* AA_CORE_H */
