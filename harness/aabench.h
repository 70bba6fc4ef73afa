/*
 * aabench.h: the public interface of the aabench library.
 *
 * aabench renders test patterns with interchangeable antialiasing methods and
 * measures each method's error against an exact reference image.  Everything
 * the `aabench` command does is callable from here, so a program or a plug-in
 * can drive the harness itself.
 *
 * Conventions (as in GSL): functions return an aa_status, 0 on success; on
 * failure the reason is kept per thread and read with aa_last_error().  The
 * library never prints and never exits.  Public names start with `aa_`.
 *
 * Coordinates: a pattern lives in pattern units, the unit square [0,1]^2
 * showing the image, x to the right and y down.  Methods and the reference
 * work on the scene placed in pixel units (u = W x, v = H y): pixel (i, j)
 * covers [i, i+1] x [j, j+1] and its centre is (i + 1/2, j + 1/2).
 */
#ifndef AABENCH_H
#define AABENCH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define AA_VERSION "0.1.0"

/* ------------------------------------------------------------------------
 * Status and errors
 * ------------------------------------------------------------------------ */

typedef enum aa_status {
    AA_OK = 0,
    AA_ECHECK = 1, /* a check failed (regression, stress bound) */
    AA_EINVAL = 2, /* bad input or usage: refused before any work */
    AA_EIO = 3,    /* input/output error */
    AA_ENOMEM = 4, /* out of memory (reported to the shell as 3) */
    AA_EFAIL = 5   /* internal error (reported to the shell as 3) */
} aa_status;

/* Record an error for this thread and return `status`.  Every failure in the
 * library goes through here, so one breakpoint catches them all. */
int aa_fail(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The message of the last failure on this thread ("" if none). */
const char *aa_last_error(void);
/* Prepend context to the last message: "context: message". Returns status. */
int aa_fail_context(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The shell exit status for a library status (0, 1, 2 or 3). */
int aa_exit_code(int status);

/* ------------------------------------------------------------------------
 * Parameters and specs: "NAME" or "NAME:key=value,key=value"
 * ------------------------------------------------------------------------ */

#define AA_MAX_PARAMS 12

typedef enum aa_param_kind {
    AA_PARAM_END = 0, /* terminates a parameter list */
    AA_PARAM_INT,     /* an integer in [min, max] */
    AA_PARAM_REAL,    /* a finite real in [min, max], or (min, max] if open_min */
    AA_PARAM_CHOICE   /* one word of `choices` ("a|b|c"); the value is its index */
} aa_param_kind;

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

/* Parse `text` against `table` (a NULL-terminated array of pointers to types
 * whose first member is an aa_info).  `what` names the kind in messages
 * ("pattern", "filter", "method").  Refuses unknown names and keys, repeated
 * keys, values that are malformed, not finite or out of range, and lists
 * what is accepted. */
int aa_spec_parse(const char *text, const void *const *table, const char *what,
                  aa_spec *out);
/* The spec with every parameter at its default. */
void aa_spec_default(const aa_info *info, aa_spec *out);
/* Canonical text: "name:key=value,..." with every parameter, %.17g. */
int aa_spec_format(const aa_spec *spec, char *buf, size_t len);
/* Index of parameter `key`, or -1. */
int aa_spec_index(const aa_info *info, const char *key);
/* Parse one value for `param` (used by spec parsing and by options). */
int aa_param_parse(const aa_param *param, const char *text, double *value);
size_t aa_param_count(const aa_info *info);
/* Look a name up in a table; NULL if absent (no error recorded). */
const aa_info *aa_table_find(const void *const *table, const char *name);

/* "WxH" with 1 <= W, H <= AA_MAX_SIDE, and an image of `channels` doubles
 * per pixel (`copies` of it) must fit in this machine's memory. */
#define AA_MAX_SIDE 65536
int aa_size_parse(const char *text, int *w, int *h);
int aa_size_check(int w, int h, int channels, int copies);

/* ------------------------------------------------------------------------
 * Images: W x H x C doubles, row-major, linear light
 * ------------------------------------------------------------------------ */

typedef struct aa_image {
    int w, h, c;
    double *v; /* v[((size_t)j * w + i) * c + k] */
} aa_image;

#define AA_MAX_CHANNELS 4

/* Leaves *im empty on failure; sizes too large to address are AA_EINVAL. */
int aa_image_alloc(aa_image *im, int w, int h, int c);
void aa_image_free(aa_image *im);
static inline double *aa_pixel(const aa_image *im, int i, int j)
{
    return im->v + ((size_t)j * (size_t)im->w + (size_t)i) * (size_t)im->c;
}

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
/* Read any of the formats above; 8-bit files are decoded with the encoding
 * they declare (sRGB if none).  On failure *im is left empty. */
int aa_image_read(const char *path, aa_image *im);
/* The .txt format: "# aabench W H C", then "i j v0 .. v(C-1)" per pixel. */
int aa_image_write_txt(const char *path, const aa_image *im);
int aa_image_read_txt(const char *path, aa_image *im);

/* ------------------------------------------------------------------------
 * Scenes: opaque layers of closed paths (line segments, quadratic arcs)
 * ------------------------------------------------------------------------ */

typedef struct aa_rgb {
    double c[3];
} aa_rgb;

typedef enum aa_fill_rule { AA_FILL_NONZERO = 0, AA_FILL_EVENODD = 1 } aa_fill_rule;

/* One segment of a closed path, as given: a quadratic Bezier arc from
 * (x0,y0) through control point (cx,cy) to (x1,y1); for a line the control
 * point is the midpoint. */
typedef struct aa_edge {
    double x0, y0, cx, cy, x1, y1;
    int quad;  /* 0 line, 1 quadratic arc */
    int layer;
} aa_edge;

/* A y-monotone part of an edge, stored top to bottom (y0 <= y1).  Pieces are
 * what the queries work on.  Crossing rule: a piece meets the horizontal line
 * y when y0 <= y < y1 (top included, bottom excluded), so a path through a
 * vertex is counted once and a horizontal piece never. */
typedef enum aa_piece_kind { AA_PIECE_LINE, AA_PIECE_QUAD, AA_PIECE_FLAT } aa_piece_kind;

typedef struct aa_piece {
    double x0, y0, cx, cy, x1, y1; /* Bezier control points, top to bottom */
    double xmin, xmax;             /* x extent of the whole piece */
    /* y(t) = y0 + t (by + t ay); x(t) = x0 + t (bx + t ax) */
    double ay, by, ax, bx;
    int kind;  /* aa_piece_kind */
    int dir;   /* +1 if the edge runs down (y increasing), -1 up, 0 flat */
    int layer;
    int edge;  /* index of the edge it came from */
} aa_piece;

typedef struct aa_scene aa_scene;

/* Building.  Layers are added front to back.  A path starts with move_to
 * and is closed by close (or by the next move_to / finish). */
aa_scene *aa_scene_new(aa_rgb background);
void aa_scene_free(aa_scene *s);
int aa_scene_layer(aa_scene *s, aa_rgb colour, aa_fill_rule rule);
int aa_scene_move_to(aa_scene *s, double x, double y);
int aa_scene_line_to(aa_scene *s, double x, double y);
int aa_scene_quad_to(aa_scene *s, double cx, double cy, double x, double y);
int aa_scene_close(aa_scene *s);
/* Finish building: split edges into pieces and index them.  Refuses
 * non-finite coordinates.  Queries need a finished scene. */
int aa_scene_finish(aa_scene *s);
/* Add a front layer of the background colour covering everything outside
 * the unit square, when the content reaches outside it (PATTERNS.md:
 * outside the unit square every pattern is its background). */
int aa_scene_clip_unit(aa_scene *s);

/* A finished copy mapped by x' = sx x + tx, y' = sy y + ty (sx, sy > 0). */
aa_scene *aa_scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty);
/* The scene placed on a W x H image at time t (frames) moving (vx, vy)
 * pixels per frame: in pixel units, u = W x + t vx, v = H y + t vy. */
aa_scene *aa_scene_place(const aa_scene *s, int w, int h, double t, double vx, double vy);

/* Reading a scene. */
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
/* The colour of the front-most layer whose fill rule holds for the winding
 * numbers `wind` (one per layer), or the background. */
aa_rgb aa_scene_colour_of(const aa_scene *s, const int *wind);

/* Piece geometry. */
double aa_piece_x_at(const aa_piece *p, double y);    /* y in [y0, y1] */
double aa_piece_t_at(const aa_piece *p, double y);    /* parameter at y */
/* x extent of the part of the piece with y in [ya, yb] (ya <= yb). */
void aa_piece_xrange(const aa_piece *p, double ya, double yb, double *xmin, double *xmax);
/* The y values (at most 2, ascending) where the piece meets the vertical
 * line x, strictly inside (y0, y1); returns how many. */
int aa_piece_meet_x(const aa_piece *p, double x, double ys[2]);

/* Point and line queries (work on any finished scene). */
aa_rgb aa_scene_colour_at(const aa_scene *s, double x, double y);

typedef struct aa_crossing {
    double x;
    int dir;   /* +1 down, -1 up */
    int layer;
} aa_crossing;

/* The crossings of the horizontal line y, sorted by x; writes at most
 * `cap` and returns the total count (call again with more room if larger). */
size_t aa_scene_crossings(const aa_scene *s, double y, aa_crossing *out, size_t cap);
/* Indices of the pieces that touch the closed rectangle [x0,x1] x [y0,y1]
 * (conservatively: a piece whose extent inside the rectangle's rows
 * overlaps it); same counting convention as aa_scene_crossings. */
size_t aa_scene_touching(const aa_scene *s, double x0, double y0, double x1, double y1,
                         size_t *out, size_t cap);

/* ------------------------------------------------------------------------
 * Strips: fast windowed queries along a horizontal band of a scene.
 *
 * A strip holds the pieces meeting the band [ya, yb].  Windows [xl, xr]
 * are visited left to right (xl and xr never decrease until the next
 * begin); for each window the strip knows the pieces that meet it (the
 * local pieces) and the winding numbers to its left, so the colour at a
 * point or the spans along a line inside the window cost work in the local
 * pieces only.  A window with no local piece is uniform.  One strip per
 * thread; the scene is shared read-only.
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
/* The winding numbers at line y from the pieces left of the window only
 * (base + pieces that ended inside the band): add the local pieces' own
 * crossings to get any point of the window. */
void aa_strip_winding_left(const aa_strip *st, double y, int *wind);
/* Pieces entered or left so far in this band: unchanged between two
 * windows with no local piece means the same uniform colour. */
size_t aa_strip_events(const aa_strip *st);

typedef struct aa_span {
    double x0, x1;
    aa_rgb colour;
} aa_span;

/* The spans of constant colour along line y from xl to xr in the current
 * window: writes at most `cap`, returns the count (at most local + 1). */
size_t aa_strip_spans(aa_strip *st, double y, aa_span *out, size_t cap);

/* ------------------------------------------------------------------------
 * Filters: separable, normalised weights in pixel units (PATTERNS.md)
 * ------------------------------------------------------------------------ */

typedef struct aa_filter_type {
    aa_info info;
    /* 1-D weight w(t) and its integral from -infinity to t */
    double (*weight)(const double *p, double t);
    double (*cdf)(const double *p, double t);
    /* Radius of the support; for an unbounded weight, the radius outside
     * which the 2-D mass is below `tail` (and *lost gets that mass). */
    double (*radius)(const double *p, double tail, double *lost);
    /* Points where the 1-D weight is not smooth (at most 8); returns count. */
    int (*kinks)(const double *p, double *t);
} aa_filter_type;

typedef struct aa_filter {
    const aa_filter_type *type;
    aa_spec spec;
    double radius; /* support radius used (truncation for unbounded weights) */
    double lost;   /* 2-D weight outside the square of that radius */
} aa_filter;

extern const aa_filter_type *const aa_filter_types[]; /* NULL-terminated */
extern const aa_filter_type aa_filter_box, aa_filter_tent, aa_filter_gauss;

int aa_filter_parse(const char *text, aa_filter *out);
void aa_filter_default(aa_filter *out); /* box */
int aa_filter_is_box(const aa_filter *f);
static inline double aa_filter_weight(const aa_filter *f, double t)
{
    return f->type->weight(f->spec.v, t);
}
static inline double aa_filter_cdf(const aa_filter *f, double t)
{
    return f->type->cdf(f->spec.v, t);
}

/* ------------------------------------------------------------------------
 * Patterns (patterns/): named, parameterised scenes (PATTERNS.md)
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

/* ------------------------------------------------------------------------
 * Ground truth: the pattern convolved with the filter, at pixel centres
 * ------------------------------------------------------------------------ */

#define AA_TRUTH_BOUND 1e-12

typedef struct aa_truth_stats {
    size_t integrated; /* pixels integrated */
    size_t filled;     /* uniform pixels filled without integration */
    double max_bound;  /* largest per-pixel error bound */
    int worst_i, worst_j;
} aa_truth_stats;

/* The reference image of a placed scene (pixel units).  `bound`, if not
 * NULL, receives a 1-channel image of per-pixel error bounds (the largest
 * over channels).  threads <= 0: OpenMP's default.  Fails only on bad
 * arguments or memory; a bound above AA_TRUTH_BOUND is reported in stats. */
int aa_truth_render(const aa_scene *placed, const aa_filter *f, int threads,
                    aa_image *out, aa_image *bound, aa_truth_stats *stats);

/* What defines a reference image. */
typedef struct aa_view {
    aa_spec pattern;
    int w, h;
    aa_filter filter;
    double t, vx, vy; /* time (frames) and motion (pixels per frame) */
} aa_view;

/* The canonical key text of a view (used by the cache). */
int aa_view_key(const aa_view *view, char *buf, size_t len);

/* The reference of a view, from the cache under `cache_dir` when present
 * (NULL: no cache), else computed and stored there. `from_cache` (may be
 * NULL) says which. */
int aa_reference(const aa_view *view, const char *cache_dir, int threads, aa_image *out,
                 aa_truth_stats *stats, int *from_cache);

/* ------------------------------------------------------------------------
 * Files
 * ------------------------------------------------------------------------ */

/* Write `len` bytes to `path` through a temporary file in the same folder
 * and rename; nothing is left behind on failure. */
int aa_file_write_atomic(const char *path, const void *data, size_t len);
/* mkdir -p */
int aa_mkdirs(const char *path);
/* A temporary name beside `path` keeping its extension. */
int aa_temp_name(const char *path, char *buf, size_t len);

/* Monotonic clock in seconds. */
double aa_now(void);

#ifdef __cplusplus
}
#endif

#endif /* AABENCH_H */
