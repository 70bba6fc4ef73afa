/*
 * aabench.h: the method contract, the one header a plug-in includes.
 *
 * A method is a constant aa_method_type (name, parameters, state size,
 * flags, check/init/render/release) that reads the scene through the fast
 * queries below and writes a W x H linear RGB image.  A plug-in is a shared
 * library exporting `aa_plugin_abi` (= AA_PLUGIN_ABI) and a NULL-terminated
 * array `aa_plugin_methods` (tests/plugin_example.c; harness/README.md).
 *
 * Functions return an aa_status, 0 on success; the reason of a failure is
 * kept per thread (aa_fail, aa_last_error).  Methods work in pixel units:
 * pixel (i, j) covers [i, i+1] x [j, j+1], centre (i + 1/2, j + 1/2), x to
 * the right, y down; colours are linear light.
 */
#ifndef AABENCH_H
#define AABENCH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The interface version a plug-in is built for; the command refuses a
 * plug-in built for another.  Raised whenever a type below changes layout. */
#define AA_PLUGIN_ABI 9

/* ------------------------------------------------------------------------
 * Status and errors
 * ------------------------------------------------------------------------ */

#if defined(__GNUC__)
#define AA_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define AA_PRINTF(f, a)
#endif

typedef enum aa_status {
    AA_OK = 0,
    AA_ECHECK = 1, /* a check failed (regression, stress bound) */
    AA_EINVAL = 2, /* bad input or usage: refused before any work */
    AA_EIO = 3,    /* input/output error */
    AA_ENOMEM = 4, /* out of memory (reported to the shell as 3) */
    AA_EFAIL = 5   /* internal error (reported to the shell as 3) */
} aa_status;

/* Record an error for this thread and return `status` (every failure). */
int aa_fail(int status, const char *fmt, ...) AA_PRINTF(2, 3);
/* The message of the last failure on this thread ("" if none). */
const char *aa_last_error(void);
/* Prepend context to the last message: "context: message". Returns status. */
int aa_fail_context(int status, const char *fmt, ...) AA_PRINTF(2, 3);

/* ------------------------------------------------------------------------
 * Parameters and specs: "NAME" or "NAME:key=value,key=value"
 * ------------------------------------------------------------------------ */

#define AA_MAX_PARAMS 12

typedef enum aa_param_kind {
    AA_PARAM_END = 0, /* terminates a parameter list */
    AA_PARAM_INT,     /* an integer in [min, max] */
    AA_PARAM_REAL,    /* a finite real in [min, max], or (min, max] if open_min */
    AA_PARAM_CHOICE,  /* one word of `choices` ("a|b|c"); the value is its index */
    AA_PARAM_WORD,    /* a name found at run time ([A-Za-z0-9._-], at most
                       * AA_PARAM_WORD_MAX); the value numbers it (aa_param_word) */
    AA_PARAM_TEXT     /* any text (a path, a string), at most AA_PARAM_TEXT_MAX bytes; the
                       * value numbers it (aa_param_text); in a spec ',', '%' and control
                       * bytes are written "%XX" (the canonical text too), a bare '%' or
                       * control byte refused.  WORD and TEXT: `choices` is the default */
} aa_param_kind;
#define AA_PARAM_WORD_MAX 63
#define AA_PARAM_TEXT_MAX 1024

typedef struct aa_param {
    const char *key;
    aa_param_kind kind;
    double def;         /* default (index of the default word for CHOICE) */
    double min, max;    /* range, inclusive unless open_min */
    int open_min;       /* 1: the lower bound itself is refused */
    const char *choices;
    const char *help;
} aa_param;

/* What every registered type (pattern, filter, method) starts with. */
typedef struct aa_info {
    const char *name;
    const char *summary; /* one line */
    const aa_param *params; /* terminated by an entry of kind AA_PARAM_END */
} aa_info;

/* A parsed spec: the type and a value for every parameter, in list order. */
typedef struct aa_spec {
    const aa_info *info;
    double v[AA_MAX_PARAMS];
} aa_spec;

/* Parameter access: a method's functions receive `p`, the values of its
 * parameters in the order of its aa_param list (an index is the position in
 * that list; CHOICE values are word indices).  The index of `key`, or -1. */
int aa_spec_index(const aa_info *info, const char *key);
/* The word or text an AA_PARAM_WORD or AA_PARAM_TEXT value numbers ("" if none). */
const char *aa_param_word(double value);
const char *aa_param_text(double value);

/* ------------------------------------------------------------------------
 * Images: W x H x C doubles, row-major, linear light
 * ------------------------------------------------------------------------ */

typedef struct aa_image {
    int w, h, c;
    double *v; /* v[((size_t)j * w + i) * c + k] */
} aa_image;

#define AA_MAX_CHANNELS 4

/* Leaves *im empty on failure (AA_EINVAL: too large to address). */
int aa_image_alloc(aa_image *im, int w, int h, int c);
void aa_image_free(aa_image *im);
static inline double *aa_pixel(const aa_image *im, int i, int j)
{
    return im->v + ((size_t)j * (size_t)im->w + (size_t)i) * (size_t)im->c;
}

/* ------------------------------------------------------------------------
 * Scenes: layers of closed paths (lines, quadratic and cubic arcs), opaque
 * or translucent (aa_scene_is_opaque, aa_scene_colour_of)
 * ------------------------------------------------------------------------ */

typedef struct aa_rgb { double c[3]; } aa_rgb;

typedef enum aa_fill_rule { AA_FILL_NONZERO = 0, AA_FILL_EVENODD = 1 } aa_fill_rule;

/* One segment of a closed path, as given: a Bezier arc from (x0,y0) through
 * control point (cx,cy) (a cubic's first; its second (c2x,c2y)) to (x1,y1);
 * for a line the control point is the midpoint.  An elliptical arc
 * (quad == 3, aa_scene_arc_to) is the points
 *     (cx + ux cos t + vx sin t,  cy + uy cos t + vy sin t)
 * for t from t0 to t1 (either way, |t1 - t0| <= 2 pi): (cx, cy) is the
 * ellipse's centre, u and v two conjugate semi-diameters (for a circle of
 * radius r, (r, 0) and (0, r)); (x0, y0) and (x1, y1) are its ends exactly
 * as given, and c2x, c2y are 0. */
/* A curve at a signed distance along the unit normal of a cubic Bezier arc
 * or of an ellipse (an offset curve), or at its centres of curvature (its
 * evolute), mapped by an affine map: the exact boundaries of the stroke of
 * a Bezier arc or an elliptical arc (path.h).  The base curve B(t), in the
 * path's own coordinates, is
 *  - base AA_OFFSET_CUBIC (0): the cubic B(t) = (b[0] + t (b[1] + t (b[2]
 *    + t b[3])), b[4] + t (b[5] + t (b[6] + t b[7]))), t in [0, 1];
 *  - base AA_OFFSET_ELLIPSE (1): the ellipse B(t) = c + u cos t + v sin t
 *    with c = (b[0], b[1]), u = (b[2], b[3]), v = (b[4], b[5]) two
 *    conjugate semi-diameters (u x v != 0; b[6] = b[7] = 0), t an angle
 *    (a curve's range of t at most 2 pi long).
 * With N(t) its unit normal (-B'y, B'x)/|B'| and k(t) = (B' x B'')/|B'|^3
 * its signed curvature, the curve is m(B(t) + d N(t)), or m(B(t) +
 * N(t)/k(t)) for the evolute, m(x, y) = (m[0] x + m[2] y + m[4], m[1] x +
 * m[3] y + m[5]).  Its derivative is m(B') (1 - d k), or m(N) (1/k)':
 * offset_eval (core.h). */
enum { AA_OFFSET_CUBIC = 0, AA_OFFSET_ELLIPSE = 1 };
typedef struct aa_offset_curve {
    double b[8], m[6], d;
    int evolute;
    int base; /* AA_OFFSET_CUBIC or AA_OFFSET_ELLIPSE */
} aa_offset_curve;

typedef struct aa_edge {
    double x0, y0, cx, cy, x1, y1;
    /* quad: 0 line, 1 quadratic arc, 2 cubic arc, 3 elliptical arc, 4 offset
     * curve (oc, its parameter from t0 to t1; (x0, y0) and (x1, y1) its ends) */
    int quad, layer;
    double c2x, c2y;
    double ux, uy, vx, vy, t0, t1; /* elliptical arcs and offset curves only */
    aa_offset_curve oc;            /* offset curves only */
} aa_edge;

/* A y-monotone part of an edge, top to bottom (y0 <= y1); it meets line y when
 * y0 <= y < y1 (a vertex counts once, a flat piece never). */
typedef enum aa_piece_kind {
    AA_PIECE_LINE, AA_PIECE_QUAD, AA_PIECE_FLAT, AA_PIECE_CUBIC, AA_PIECE_CONIC,
    AA_PIECE_OFFSET } aa_piece_kind;

typedef struct aa_piece {
    double x0, y0, cx, cy, x1, y1; /* Bezier control points, top to bottom */
    double xmin, xmax;             /* x extent of the whole piece */
    /* y(t) = y0 + t (by + t (ay + t dy)), x(t) likewise; dy = dx = 0 but
     * for cubics, whose second control point is (c2x, c2y) */
    double ay, by, ax, bx;
    int kind;  /* aa_piece_kind */
    int dir;   /* +1 if the edge runs down (y increasing), -1 up, 0 flat */
    int layer, edge; /* edge: index of the edge it came from */
    double c2x, c2y, dy, dx;
    /* AA_PIECE_CONIC, a y-monotone arc of an ellipse, in its angle s:
     *     y(s) = ey - er cos s,   x(s) = ex + ea cos s + eb sin s,
     * s from s0 (the top, y0) to s1 (the bottom, y1), 0 <= s0 < s1 <= pi,
     * so y increases with s; er > 0 is the ellipse's half height and ey its
     * centre's height, so that on the piece
     *     x(y) = ex + ea c + eb sqrt(1 - c^2),   c = (ey - y)/er.
     * (x0, y0) and (x1, y1) are the edge's ends exactly where the piece
     * ends at one; cx, cy, c2x, c2y, ax, bx, ay, by, dx, dy are 0; xmin,
     * xmax its extent.  aa_piece_t_at gives (s - s0)/(s1 - s0). */
    double ex, ey, er, ea, eb, s0, s1;
    /* AA_PIECE_OFFSET, a y-monotone part of an offset curve or evolute (oc,
     * aa_offset_curve) from its parameter ot0 (the top, y0) to ot1 (the
     * bottom, y1; ot1 < ot0 where the curve runs up): no fold, cusp or
     * extreme of y inside.  x(y) is the root of y(t) = y, found by Newton's
     * method safeguarded by bisection; aa_piece_t_at gives
     * (t - ot0)/(ot1 - ot0).  The power-basis fields are 0. */
    aa_offset_curve oc;
    double ot0, ot1;
} aa_piece;

typedef struct aa_scene aa_scene;

aa_rgb aa_scene_background(const aa_scene *s);
int aa_scene_layer_count(const aa_scene *s);
aa_rgb aa_scene_layer_colour(const aa_scene *s, int layer);
aa_fill_rule aa_scene_layer_rule(const aa_scene *s, int layer);
const aa_edge *aa_scene_edges(const aa_scene *s, size_t *n);
/* Contours: edges [start[k], start[k+1]) form closed path k. */
const size_t *aa_scene_contours(const aa_scene *s, size_t *ncontours);
const aa_piece *aa_scene_pieces(const aa_scene *s, size_t *n);
/* Bounds of all edges; an empty scene gives 0 0 0 0 and returns 0. */
int aa_scene_bounds(const aa_scene *s, double *x0, double *y0, double *x1, double *y1);
/* 1 if every colour (layers and background) is grey. */
int aa_scene_is_grey(const aa_scene *s);
/* 1 if every layer is opaque (alpha 1, in no group of opacity) and none is
 * clipped (no clips): the colour at a point is then the front-most
 * covering layer's colour.  0 for a scene with translucent layers or
 * clips, whose colour at a point is the covering layers composited
 * (aa_scene_colour_of); a method that draws from the layers' colours
 * itself must refuse such a scene. */
int aa_scene_is_opaque(const aa_scene *s);
/* 1 if some layer is gated by a clip (patterns/README.md, clip paths):
 * some layers are then the members of clips, which paint nothing, and a
 * layer paints only inside its clip; aa_scene_is_opaque is 0, and a
 * method that draws from the layers' colours itself must refuse the scene
 * (or clip as the scene does). */
int aa_scene_is_clipped(const aa_scene *s);
/* The clips: how many; the clip gating a layer (-1: none); the clip a
 * layer is a member of (-1: a layer that paints); the clip a clip is
 * itself inside (-1: none); a clip's members, layers first .. first +
 * count - 1 (the count returned).  A point is inside clip c when it is
 * inside aa_scene_clip_within(c) (if any) and some member's fill rule
 * holds there and the point is inside that member's own clip (if any). */
int aa_scene_clip_count(const aa_scene *s);
int aa_scene_layer_clip(const aa_scene *s, int layer);
int aa_scene_layer_clip_member(const aa_scene *s, int layer);
int aa_scene_clip_within(const aa_scene *s, int clip);
int aa_scene_clip_members(const aa_scene *s, int clip, int *first);
/* The colour at a point whose winding numbers are `wind` (one per layer):
 * in an opaque scene the front-most layer's whose fill rule holds, or the
 * background (a clip's member never paints, and a clipped layer paints
 * only inside its clip); otherwise the covering layers composited back to front in
 * sRGB-encoded values, decoded to linear light (patterns/README.md). */
aa_rgb aa_scene_colour_of(const aa_scene *s, const int *wind);

/* Gradient paint (patterns/README.md, "Gradients"): a layer's paint may be
 * a linear or a radial gradient instead of its colour.  t at a point p
 * of the scene: with q = m^-1(p) in the gradient's own coordinates,
 *  - linear (p[] = x1 y1 x2 y2): t = (q - P1).(P2 - P1) / |P2 - P1|^2;
 *  - radial (p[] = cx cy r fx fy fr): the largest w with |q - F - w (C -
 *    F)| = fr + w (r - fr) (the circles of SVG 2 and canvas, F = (fx, fy),
 *    C = (cx, cy)); with the focal circle strictly inside the end circle
 *    (|C - F| + fr < r) every point has exactly one; otherwise (the cone
 *    case, aa_gradient_is_cone) some points have none and the layer
 *    paints nothing there (transparent), as SVG 2 and canvas leave them;
 * then spread maps t to [0, 1] (pad: clamp; reflect: the distance to the
 * nearest even integer; repeat: t - floor t) and the stops give the colour:
 * sRGB-encoded channels (or linear light: aa_scene_layer_gradient_interpolation)
 * and opacity interpolated linearly, not premultiplied, between the two stops around t (the first stop's below the
 * first offset, the last's above the last).  The layer's alpha multiplies
 * the stop's opacity.  Offsets ascending in [0, 1]; two equal offsets make
 * a sharp step (the later stop's colour from there).  m maps the gradient's
 * coordinates to the scene's: (m[0] x + m[2] y + m[4], m[1] x + m[3] y +
 * m[5]); colours are linear light, as everywhere. */
typedef enum aa_gradient_kind { AA_GRADIENT_LINEAR = 1, AA_GRADIENT_RADIAL = 2 } aa_gradient_kind;
typedef enum aa_spread { AA_SPREAD_PAD = 0, AA_SPREAD_REFLECT = 1, AA_SPREAD_REPEAT = 2 } aa_spread;
typedef struct aa_gradient_stop {
    double offset;
    aa_rgb colour;
    double opacity;
} aa_gradient_stop;
typedef struct aa_gradient {
    int kind;   /* aa_gradient_kind */
    int spread; /* aa_spread */
    double p[6];
    double m[6];
    int nstops;
    const aa_gradient_stop *stops;
} aa_gradient;

/* 1 if g is a radial gradient of the cone case: its focal circle not
 * strictly inside its end circle (|C - F| + fr >= r), so that the points
 * on no circle of radius >= 0, outside the cone the circles sweep, are
 * left unpainted. */
int aa_gradient_is_cone(const aa_gradient *g);
/* 1 if some painting layer's paint is a gradient: the colour at a point
 * then depends on the point, not on the winding numbers alone, and
 * aa_scene_is_opaque is 0.  A method takes such a scene only if it
 * declares AA_METHOD_GRADIENTS (it samples the picture through
 * aa_scene_colour_of_at, aa_scene_colour_at or aa_strip_colour_at, or
 * paints each gradient from aa_scene_layer_gradient with a library's
 * own); aa_method_init refuses it to the others. */
int aa_scene_has_gradients(const aa_scene *s);
/* Layer's gradient into *g (its stops the scene's own, valid while the
 * scene lives): 1, or 0 for a layer painted with its colour. */
int aa_scene_layer_gradient(const aa_scene *s, int layer, aa_gradient *g);
/* The space layer's gradient interpolates its stops in (SVG's
 * color-interpolation on a gradient element; patterns/README.md,
 * "Gradients"): AA_INTERPOLATE_SRGB, the stops' sRGB-encoded channels as
 * above (and for a layer without a gradient), or AA_INTERPOLATE_LINEAR_RGB:
 * each stop's colour (linear light) interpolated as it is, not
 * premultiplied, the opacity as above, and the result encoded to sRGB
 * before it composites.  A method that paints gradients with a library's
 * own must draw the latter so or refuse it, never draw it as sRGB. */
typedef enum aa_interpolation {
    AA_INTERPOLATE_SRGB = 0,
    AA_INTERPOLATE_LINEAR_RGB = 1
} aa_interpolation;
int aa_scene_layer_gradient_interpolation(const aa_scene *s, int layer);
/* The colour at point (x, y) whose winding numbers are `wind`: as
 * aa_scene_colour_of, each gradient layer painting its colour at (x, y).
 * aa_scene_colour_of gives a gradient layer the colour of its first stop:
 * it is the picture only in scenes without gradients. */
aa_rgb aa_scene_colour_of_at(const aa_scene *s, const int *wind, double x, double y);

/* The point of an offset curve at parameter t, and its derivative (either
 * pointer NULL: not wanted) (aa_offset_curve). */
void aa_offset_point(const aa_offset_curve *oc, double t, double *x, double *y, double *dx,
                     double *dy);
double aa_piece_x_at(const aa_piece *p, double y);    /* y in [y0, y1] */
double aa_piece_t_at(const aa_piece *p, double y);    /* parameter at y */
/* x extent of the part of the piece with y in [ya, yb] (ya <= yb). */
void aa_piece_xrange(const aa_piece *p, double ya, double yb, double *xmin, double *xmax);
/* The y values (ascending; at most 2, 3 for a cubic) where the piece meets
 * the vertical line x, strictly inside (y0, y1); returns how many. */
int aa_piece_meet_x(const aa_piece *p, double x, double ys[3]);

aa_rgb aa_scene_colour_at(const aa_scene *s, double x, double y);

typedef struct aa_crossing {
    double x;
    int dir;   /* +1 down, -1 up */
    int layer;
} aa_crossing;

/* The crossings of line y, sorted by x: at most `cap` written, the total returned. */
size_t aa_scene_crossings(const aa_scene *s, double y, aa_crossing *out, size_t cap);
/* Indices of the pieces that touch [x0,x1] x [y0,y1] (conservatively, by their
 * extent in its rows), counted as aa_scene_crossings counts. */
size_t aa_scene_touching(const aa_scene *s, double x0, double y0, double x1, double y1,
                         size_t *out, size_t cap);

/* ------------------------------------------------------------------------
 * Strips: fast windowed queries along a horizontal band of a scene.
 *
 * A strip holds the pieces meeting the band [ya, yb].  Windows [xl, xr] are
 * visited left to right (neither end decreases until the next begin); each
 * knows its local pieces and the winding to its left, so a query inside it
 * costs work in the local pieces only; a window with none is uniform.  One
 * strip per thread; the scene is shared read-only.
 * ------------------------------------------------------------------------ */

typedef struct aa_strip aa_strip;

aa_strip *aa_strip_new(const aa_scene *s);
void aa_strip_free(aa_strip *st);
int aa_strip_begin(aa_strip *st, double ya, double yb);
/* Move to window [xl, xr]; returns the number of local pieces. */
size_t aa_strip_window(aa_strip *st, double xl, double xr);
const aa_piece *const *aa_strip_local(const aa_strip *st, size_t *n);
/* Winding numbers (one per layer) at (x, y) inside the window and band. */
void aa_strip_winding(const aa_strip *st, double x, double y, int *wind);
aa_rgb aa_strip_colour_at(const aa_strip *st, double x, double y);
/* The winding at line y from the pieces left of the window (add the local
 * pieces' crossings to get any point of the window). */
void aa_strip_winding_left(const aa_strip *st, double y, int *wind);
/* The same at line yc + s, that sum taken exactly (not rounded to double):
 * a piece whose end lies within half an ulp of it is on its own side of
 * the line, as a piece given relative to yc is (the reference's local
 * pieces; harness/truth). */
void aa_strip_winding_left_at(const aa_strip *st, double yc, double s, int *wind);
/* 1 if no piece ends inside the band: the winding left of a window is then
 * the same on all its lines (a shortcut for sampling methods). */
int aa_strip_all_full(const aa_strip *st);
/* The left end of the next piece to enter (INFINITY if none). */
double aa_strip_next_entry(const aa_strip *st);
/* With pixel i's window [i + 1/2 - r, i + 1/2 + r] uniform: the run of pixels
 * i .. end-1 (of w) with uniform windows of one colour, without a window call
 * each.  Returns end (> i), the colour at y; `wind`: one int per layer. */
int aa_strip_uniform_run(const aa_strip *st, int i, int w, double r, double y, int *wind,
                         aa_rgb *colour);

typedef struct aa_span { double x0, x1; aa_rgb colour; } aa_span;

/* The spans of one colour along line y in the window (at most local + 1). */
size_t aa_strip_spans(aa_strip *st, double y, aa_span *out, size_t cap);

/* ------------------------------------------------------------------------
 * Filters: normalised weights in pixel units (patterns/README.md, "Filters")
 *
 * box, tent, gauss, bspline, mitchell, catrom and lanczos are separable,
 * w(u) w(v): `weight` and `cdf` are the 1-D weight and its integral.  cone,
 * the polynomials in r^2 on a disc (radial:k=K,r=R) and the Gaussian in a
 * circular mask (gauss with cut > 0, whose type is aa_filter_gauss_mask,
 * not aa_filter_gauss) are radial: their `weight`
 * and `cdf` are NULL and they give the 2-D weight and the integral of a
 * row instead.  A
 * method's check refuses a filter it cannot form (aa_filter_is_separable);
 * aa_filter_weight2 and aa_filter_row_cdf serve every filter.
 * ------------------------------------------------------------------------ */

typedef struct aa_filter_type {
    aa_info info;
    /* Separable filters: the 1-D weight w(t) and its integral from
     * -infinity to t.  NULL for a filter that is not separable. */
    double (*weight)(const double *p, double t);
    double (*cdf)(const double *p, double t);
    /* Radius of the support; for an unbounded weight, the radius outside
     * which the 2-D mass is below `tail` (and *lost gets that mass). */
    double (*radius)(const double *p, double tail, double *lost);
    /* Where the weight (not separable: a row's integral, in v) is not
     * smooth (at most 8); returns the count. */
    int (*kinks)(const double *p, double *t);
    /* Filters that are not separable (NULL otherwise): the 2-D weight
     * w(u, v), and the integral over u' in (-infinity, u] of w(u', v). */
    double (*weight2)(const double *p, double u, double v);
    double (*row_cdf)(const double *p, double v, double u);
} aa_filter_type;

typedef struct aa_filter {
    const aa_filter_type *type;
    aa_spec spec;
    double radius; /* support radius used (truncation for unbounded weights) */
    double lost;   /* 2-D weight outside the square of that radius */
} aa_filter;

extern const aa_filter_type aa_filter_box, aa_filter_tent, aa_filter_gauss, aa_filter_cone;
extern const aa_filter_type aa_filter_gauss_mask, aa_filter_radial, aa_filter_bspline,
    aa_filter_mitchell, aa_filter_catrom, aa_filter_lanczos;
int aa_filter_is_box(const aa_filter *f);
/* The values a filtered image of values in [0, 1] can take: [0, 1], or
 * wider by the filter's negative mass for filters with negative lobes
 * (mitchell with c > 0, catrom, lanczos), rounded outwards. */
void aa_filter_range(const aa_filter *f, double *lo, double *hi);
/* A radial filter's weight W(d), d the distance from the centre: not
 * increasing, |W'| <= *slope inside its mask, and it drops by *jump at
 * the mask's edge (0 where it is continuous there).  Returns 0 (nothing
 * set) for a separable filter. */
int aa_filter_radial_slope(const aa_filter *f, double *slope, double *jump);
static inline int aa_filter_is_separable(const aa_filter *f)
{
    return f->type->weight != NULL;
}
/* The 1-D weight and cdf: separable filters only. */
static inline double aa_filter_weight(const aa_filter *f, double t)
{
    return f->type->weight(f->spec.v, t);
}
static inline double aa_filter_cdf(const aa_filter *f, double t)
{
    return f->type->cdf(f->spec.v, t);
}
/* The 2-D weight at offset (u, v) from the centre, any filter (for a
 * separable one, w(u) w(v) computed as such). */
static inline double aa_filter_weight2(const aa_filter *f, double u, double v)
{
    if (f->type->weight2)
        return f->type->weight2(f->spec.v, u, v);
    return f->type->weight(f->spec.v, u) * f->type->weight(f->spec.v, v);
}
/* The integral over u' in (-infinity, u] of w(u', v), any filter. */
static inline double aa_filter_row_cdf(const aa_filter *f, double v, double u)
{
    if (f->type->row_cdf)
        return f->type->row_cdf(f->spec.v, v, u);
    return f->type->weight(f->spec.v, v) * f->type->cdf(f->spec.v, u);
}

/* ------------------------------------------------------------------------
 * Methods: named, parameterised renderers
 *
 * The harness allocates `size` zeroed bytes of state, calls check when a
 * spec is parsed, init once per job (untimed: tables for its scene, size and
 * filter), render one or more times, and release.  A method never allocates
 * in its per-pixel loops, and its image must not depend on the thread count
 * (random streams from (seed, pixel, aa_frame_index(t))).  For example:
 *
 *     static const aa_method_type mine = {
 *         .info = {"mine", "one line", mine_params},
 *         .size = sizeof(struct mine_state),
 *         .check = mine_check, .init = mine_init,
 *         .render = mine_render, .release = mine_release,
 *     };
 * ------------------------------------------------------------------------ */

/* A render's counters.  Counts below 2^63 (a negative count stored here is
 * not) and at most W x H expensive pixels, else the render fails. */
typedef struct aa_counters {
    uint64_t samples;          /* point evaluations of the scene */
    uint64_t expensive_pixels; /* pixels that took more than the cheap path */
} aa_counters;

typedef struct aa_job {
    const aa_scene *pattern; /* the pattern's scene, pattern units */
    const aa_scene *placed;  /* the same placed at time t, pixel units */
    int w, h;
    double t, vx, vy; /* time (frames) and motion (pixels per frame) */
    aa_filter filter;
    uint64_t seed;
    int threads;    /* OpenMP threads to use (>= 1) */
    int frame_only; /* temporal methods: the single frame at t, not the eye's image */
} aa_job;

enum aa_method_flags {
    AA_METHOD_SEEDED = 1,  /* the image depends on the seed */
    AA_METHOD_TEMPORAL = 2, /* the image depends on several frames */
    /* init refuses some scenes (colour, several layers; curves it does not
     * integrate) with AA_EINVAL and a message: the peer rasterizers */
    AA_METHOD_SOME_SCENES = 4,
    /* renders a field scene (aa_scene_field) through its point function;
     * without it a field scene is refused by aa_method_init */
    AA_METHOD_FIELDS = 8, /* 16: AA_METHOD_DISPLAY, built-in only (core.h, "Displays") */
    /* render runs another program: its time includes that start-up */
    AA_METHOD_EXTERNAL = 32,
    /* takes scenes with gradient paint (aa_scene_has_gradients): it samples
     * the picture at points (aa_scene_colour_of_at and the like), or paints
     * the gradients with a library's own (the peers cairo and agg); without
     * it such a scene is refused by aa_method_init */
    AA_METHOD_GRADIENTS = 64
};

typedef struct aa_method_type {
    aa_info info;
    size_t size;    /* bytes of instance state */
    unsigned flags; /* aa_method_flags */
    /* Refuse parameter values or a filter the method cannot honour, with a
     * message that says what is accepted (NULL: everything is accepted). */
    int (*check)(const double *p, const aa_filter *f);
    /* Prepare for renders of jobs like this one (tables, workspaces). */
    int (*init)(void *state, const double *p, const aa_job *job);
    int (*render)(void *state, const double *p, const aa_job *job, aa_image *out,
                  aa_counters *counters);
    void (*release)(void *state);
} aa_method_type;

/* Support radius a sampling method uses: box 1/2, tent r, cone r, Gaussian 3 s
 * (truncated there; the error against the exact reference includes that). */
double aa_filter_support(const aa_filter *f);

/* Counter-based random streams, one per (seed, pixel, frame), so an image
 * does not depend on how pixels are shared among threads. */
typedef struct aa_rng { uint64_t state; } aa_rng;
static inline uint64_t aa_hash64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}
void aa_rng_seed(aa_rng *r, uint64_t seed, uint64_t pixel, uint64_t frame);
static inline uint64_t aa_rng_next(aa_rng *r)
{
    r->state += 0x9e3779b97f4a7c15ull;
    return aa_hash64(r->state);
}
double aa_rng_uniform(aa_rng *r); /* in [0, 1), 53 random bits */
/* The frame of time t for aa_rng_seed: floor(t) as a two's-complement 64-bit
 * integer (t in [n, n + 1) is frame n; -0.5 is frame -1; not finite: 0). */
uint64_t aa_frame_index(double t);

#ifdef __cplusplus
}
#endif

#endif /* AABENCH_H */
