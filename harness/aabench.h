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
/* A file-name-safe form of a spec: letters, digits, '.' and '-' kept, every
 * other character '_'. */
void aa_spec_slug(const char *text, char *buf, size_t len);
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

/* The heights (ascending, at most max) in (ya, yb) where two pieces meet
 * (cross or touch) while both are present: in closed form for lines, a
 * line and an arc, and two arcs whose x is quadratic in y; for two general
 * arcs by bisection on their exact x extents (to 1e-12 relative), which
 * cannot miss a meeting.  Flat pieces meet nothing. */
int aa_piece_meet(const aa_piece *p, const aa_piece *q, double ya, double yb, double *ys,
                  int max);

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
 * Fields: a procedural scene, a point function plus its own exact pixel
 * integral (DESIGN.md, "The three contracts"), such as the zone plate.
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
/* 1 if no piece ends inside the band: then every piece meeting it crosses
 * every line of the band, so the winding left of a window is the same on
 * all its lines and a point's colour depends only on which local pieces lie
 * left of it (a shortcut for sampling methods). */
int aa_strip_all_full(const aa_strip *st);
/* The left end of the next piece to enter (INFINITY if none). */
double aa_strip_next_entry(const aa_strip *st);
/* With the window of pixel i ([i + 1/2 - r, i + 1/2 + r]) holding no local
 * piece: the run of pixels i .. end-1 (of a row of w) whose windows are all
 * uniform with the same colour, found without a window call each.  Returns
 * end (> i) and the colour at height y; `wind` is the caller's winding
 * array (one int per layer). */
int aa_strip_uniform_run(const aa_strip *st, int i, int w, double r, double y, int *wind,
                         aa_rgb *colour);

typedef struct aa_span {
    double x0, x1;
    aa_rgb colour;
} aa_span;

/* The spans of constant colour along line y from xl to xr in the current
 * window: writes at most `cap`, returns the count (at most local + 1). */
size_t aa_strip_spans(aa_strip *st, double y, aa_span *out, size_t cap);

/* ------------------------------------------------------------------------
 * Filters: normalised weights in pixel units (PATTERNS.md)
 *
 * box, tent and gauss are separable, w(u) w(v): `weight` and `cdf` are
 * their 1-D weight and its integral.  cone (Feibush et al. fig. 2f, 3a,
 * an extension of PATTERNS.md's table) is radial and not separable: its
 * `weight` and `cdf` are NULL, and it gives instead the 2-D weight and the
 * integral of a row, which is what the exact inner integral along u needs.
 * Code that reads the 1-D weight checks aa_filter_is_separable first (a
 * method's check refuses a filter it cannot form); aa_filter_weight2 and
 * aa_filter_row_cdf serve every filter.
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
    /* Points where the weight is not smooth along either axis (for a
     * filter that is not separable, where the integral of a row is not
     * smooth in v) (at most 8); returns count. */
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

extern const aa_filter_type *const aa_filter_types[]; /* NULL-terminated */
extern const aa_filter_type aa_filter_box, aa_filter_tent, aa_filter_gauss, aa_filter_cone;

int aa_filter_parse(const char *text, aa_filter *out);
void aa_filter_default(aa_filter *out); /* box */
int aa_filter_is_box(const aa_filter *f);
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

/* Whether long double arithmetic is wider than double where this runs (the
 * type may say so while an emulator, valgrind for one, computes it in
 * double).  The reference's Gaussian fixed rule and the extended-precision
 * goals of the tests count on it. */
int aa_long_double_is_extended(void);

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
 * Methods (algorithms/): named, parameterised renderers
 *
 * A method is a constant type struct, as GSL describes each generator with
 * one gsl_rng_type: metadata, the size of its instance state, and functions.
 * The harness allocates `size` zeroed bytes of state, calls init once
 * (outside any timing), render one or more times with the same job (an
 * instance serves the job it was initialised with: tables made in init for
 * that job's scene, size and filter stay valid), and release.  A method
 * writes a W x H linear RGB image and counters; it never allocates inside
 * its per-pixel loops, and its image must not depend on the thread count:
 * random streams come from (seed, pixel, frame), see aa_rng_seed, the frame
 * being aa_frame_index(t).
 * ------------------------------------------------------------------------ */

typedef struct aa_counters {
    uint64_t samples;          /* point evaluations of the scene */
    uint64_t expensive_pixels; /* pixels that took more than the cheap path */
} aa_counters;

/* What a render is asked for. */
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

/* Build a job for a pattern scene (placing it at t); aa_job_free frees
 * only what aa_job_init made (the placed scene). */
int aa_job_init(aa_job *job, const aa_scene *pattern, int w, int h, double t, double vx,
                double vy, const aa_filter *f, uint64_t seed, int threads);
void aa_job_free(aa_job *job);

enum aa_method_flags {
    AA_METHOD_SEEDED = 1,  /* the image depends on the seed */
    AA_METHOD_TEMPORAL = 2, /* the image depends on several frames */
    /* init refuses some scenes (colour, several layers) with AA_EINVAL and
     * a message: the peer rasterizers */
    AA_METHOD_SOME_SCENES = 4,
    /* the method renders a field scene (aa_scene_field) through its point
     * function; a method without this flag is refused a field scene by
     * aa_method_init, rather than rendering the background */
    AA_METHOD_FIELDS = 8
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

typedef struct aa_method {
    const aa_method_type *type;
    aa_spec spec;
    void *state;
} aa_method;

extern const aa_method_type *const aa_method_types[]; /* built-in, NULL-terminated */

/* The method table in use: the built-in methods, then those of loaded
 * plug-ins.  NULL-terminated; valid until the next aa_plugin_load. */
const void *const *aa_method_table(void);
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

/* Plug-ins: a shared library exporting `aa_plugin_abi` (an int equal to
 * AA_PLUGIN_ABI) and `aa_plugin_methods` (a NULL-terminated array of
 * pointers to aa_method_type).  Its methods join the table; a name that is
 * already there is refused. */
#define AA_PLUGIN_ABI 1
int aa_plugin_load(const char *path);

/* ---- helpers for methods ---- */

/* Support radius a sampling method uses for the filter: box 1/2, tent r, cone r,
 * Gaussian 3 s (pbrt's default radius 1.5 for s = 0.5).  Sampling methods
 * truncate the Gaussian there; their error against the untruncated
 * reference includes that. */
double aa_filter_support(const aa_filter *f);

/* Counter-based random streams: one per (seed, pixel, frame), so an image
 * does not depend on how pixels are shared among threads (random.c).  The
 * hash and the next number are inline: methods call them per sample. */
typedef struct aa_rng {
    uint64_t state;
} aa_rng;
/* SplitMix64's output function: a bijective 64-bit mixer. */
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
/* The frame of time t (frames) for aa_rng_seed: floor(t) as a
 * two's-complement 64-bit integer (modulo 2^64 beyond its range), so every
 * t of [n, n + 1) is frame n (0.3 and 0.7 are frame 0, 1 is frame 1, -0.5
 * is frame -1); 0 for a t that is not finite. */
uint64_t aa_frame_index(double t);

/* ------------------------------------------------------------------------
 * Metrics: an image against its reference
 * ------------------------------------------------------------------------ */

typedef struct aa_metrics {
    /* linear light, over every channel of every pixel */
    double rmse, mae, max_err, psnr; /* psnr = 10 log10(1/mse), infinite if equal */
    int max_at[3];                   /* pixel i, j and channel of max_err */
    /* the same after display encoding */
    double rmse_enc, mae_enc, max_err_enc, psnr_enc;
    /* power of the error image's spectrum per pixel: total (= the mean
     * squared error of the channel mean), below 1/4 cycle per pixel in x
     * and y (moire), and the rest up to the Nyquist frequency */
    double alias_total, alias_low, alias_high;
    double ssim; /* on the display-encoded luma */
} aa_metrics;

/* enc NULL: sRGB.  Images must have the same size and channels. */
int aa_metrics_compute(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                       aa_metrics *m);

/* Temporal metrics of n displayed frames at times t0, t0 + 1, ... against
 * the references at the same times (temporal.c): eye_rmse over every
 * window of `window` frames (eye's image: the frames' mean, against the
 * references' mean), flicker (per channel and pixel, the population
 * standard deviation over time of frame minus reference; its mean and max),
 * conservation ((max - min)/mean of the total intensity over the frames). */
#define AA_TEMPORAL_MAX_FRAMES 256
typedef struct aa_temporal {
    int frames, window;
    double eye_rmse;
    double flicker_mean, flicker_max;
    double conservation;
    double popping; /* NAN unless measured (aa_temporal_popping) */
} aa_temporal;
int aa_temporal_compute(const aa_image *frames, const aa_image *refs, int n, int window,
                        aa_temporal *out);
/* Popping: ndots dots centred at (cx, cy) (pixel units) plus shift[2k],
 * shift[2k+1] at frame k; the fraction of (dot, consecutive frames) whose
 * value (channel mean summed over the pixels with centres within 1.5 px of
 * the dot) changes by more than half its reference value. */
int aa_temporal_popping(const aa_image *frames, const aa_image *refs, int n, const double *cx,
                        const double *cy, size_t ndots, const double *shift, double *out);

/* ------------------------------------------------------------------------
 * Runs: every method on every view of a suite, measured
 * ------------------------------------------------------------------------ */

/* One result: a pattern x size x filter x method. */
typedef struct aa_row {
    char pattern[512];  /* the pattern spec as given */
    char filter[128];   /* the filter spec as given */
    char method[512];   /* the method spec as given */
    char canonical[1024]; /* the method spec with every parameter */
    int w, h;
    double t, vx, vy;
    uint64_t seed;
    int threads, reps;
    double spp;         /* samples per pixel */
    aa_metrics m;
    double seconds, seconds_min, seconds_max; /* median, min, max of the renders */
    double ns_per_pixel, ns_per_sample;
    uint64_t samples, expensive_pixels;
    double expensive_fraction;
    int ok;             /* 0: refused or failed, see note */
    char note[512];
    int temporal;       /* 1: an animated run: the temporal metrics below were taken */
    aa_temporal tm;
} aa_row;

/* A suite is a list of groups; each group is a cross product of patterns,
 * sizes, filters and methods (NULL-terminated lists of specs). */
typedef struct aa_suite_group {
    const char *const *patterns, *const *sizes, *const *filters, *const *methods;
} aa_suite_group;

typedef struct aa_suite {
    const char *name, *summary;
    const aa_suite_group *groups; /* ends with a group whose patterns is NULL */
} aa_suite;

extern const aa_suite aa_suites[]; /* ends with a NULL name */
const aa_suite *aa_suite_find(const char *name);

/* The animated suites (suite_temporal.c): their motion (pixels per frame),
 * the frames the temporal metrics are taken over and the eye's window; the
 * command line's --motion, --frames and --window override them. */
typedef struct aa_suite_motion {
    const char *suite;
    double vx, vy;
    int frames, window;
} aa_suite_motion;
extern const aa_suite_group aa_suite_temporal_groups[];
/* NULL for a still suite. */
const aa_suite_motion *aa_suite_motion_find(const char *suite);

/* A run's patterns, filters and methods are parsed once, where their text
 * comes in (the command line, a suite, a baseline), and reach the run as
 * values.  `text` (may be NULL) is the spec as it was given: the results'
 * pattern, filter and method columns, the image names and the progress
 * show it; NULL shows the canonical text of the value (aa_spec_format).
 * Nothing parses it again. */
typedef struct aa_run_spec {
    aa_spec spec;
    const char *text;
} aa_run_spec;
typedef struct aa_run_filter {
    aa_filter filter;
    const char *text;
} aa_run_filter;
typedef struct aa_run_size {
    int w, h;
} aa_run_size;

typedef struct aa_run_config {
    const aa_run_spec *patterns;  /* pattern specs */
    const aa_run_size *sizes;
    const aa_run_filter *filters;
    const aa_run_spec *methods;   /* method specs, checked against each filter by the run */
    size_t npatterns, nsizes, nfilters, nmethods;
    int reps, threads;
    uint64_t seed;
    double t, vx, vy;
    const char *cache_dir;  /* NULL: no cache */
    const char *images_dir; /* NULL: no images written */
    aa_encode enc;
    /* called before each case (may be NULL); returning non-zero stops */
    int (*progress)(void *ctx, size_t done, size_t total, const char *what);
    void *ctx;
    /* called after each row (may be NULL), e.g. to save results so far */
    int (*row_done)(void *ctx, const aa_row *rows, size_t n);
    /* temporal metrics: taken when the motion is not zero or `temporal` is
     * set, over `frames` frames (times t, t + 1, ...; 0: 24) and an eye
     * window of `window` frames (0: 6) */
    int temporal, frames, window;
} aa_run_config;

/* Check the config before any work: lists present, sizes within memory,
 * counts in range, each spec of the kind its list holds. */
int aa_run_check(const aa_run_config *cfg);
/* Run it: *rows (malloc'd, n rows) in pattern, size, filter, method order.
 * A method that refuses a filter gives a row with ok = 0 and the reason. */
int aa_run(const aa_run_config *cfg, aa_row **rows, size_t *n);

/* results.csv and results.json: one row per case. */
int aa_rows_write_csv(const char *path, const aa_row *rows, size_t n);
int aa_rows_write_json(const char *path, const aa_row *rows, size_t n);
/* Read a results or baseline CSV back (the columns written above). */
int aa_rows_read_csv(const char *path, aa_row **rows, size_t *n);

/* Convergence: RMSE against samples per pixel over `phases` random sub-pixel
 * shifts of the scene; the log-log slope by least squares (gsl_fit_linear).
 * The method spec's spp (or n, an n x n grid) takes each count in turn. */
typedef struct aa_convergence {
    size_t n;
    double spp[64], rmse[64], rmse_sd[64], seconds[64];
    double slope, slope_err, intercept;
} aa_convergence;
int aa_converge(const aa_spec *pattern, const aa_spec *method, const aa_filter *f, int w, int h,
                const int *spp, size_t nspp, int phases, uint64_t seed, int threads,
                const char *cache_dir, aa_convergence *out);
/* The same for a scene at time t moving (vx, vy) pixels per frame: each
 * phase's random sub-pixel shift is added to the motion's displacement
 * (aa_converge is this with 0, 0, 0). */
int aa_converge_moving(const aa_spec *pattern, const aa_spec *method, const aa_filter *f, int w,
                       int h, double t, double vx, double vy, const int *spp, size_t nspp,
                       int phases, uint64_t seed, int threads, const char *cache_dir,
                       aa_convergence *out);

/* A montage: images side by side in `columns`, each copied pixel for
 * pixel (never resampled) under up to AA_TILE_LINES lines of label; written
 * as any image file (PNG display-encoded with enc). */
#define AA_TILE_LINES 3
typedef struct aa_tile {
    const aa_image *image; /* W x H x 3 */
    const char *label[AA_TILE_LINES]; /* NULL-terminated if fewer */
} aa_tile;
int aa_montage_write(const char *path, const aa_tile *tiles, size_t n, int columns,
                     const aa_encode *enc);

/* Plots with gnuplot into `dir`: error_vs_time.{dat,gp,png} (log-log, each
 * view's Pareto front marked) and convergence.{dat,gp,png}. */
int aa_plot_error_vs_time(const char *dir, const aa_row *rows, size_t n);
int aa_plot_convergence(const char *dir, const aa_convergence *c, const char *const *names,
                        size_t n, const char *title);

/* Published figures (figures.c): the seed papers' comparison figures remade
 * into a folder as NAME.png (labelled panels, aa_montage_write) and NAME.txt
 * (settings, the command that remakes it, and each panel's RMSE and largest
 * error against the exact reference, linear light); aa_figure_index writes
 * index.html showing every figure present in the folder. */
#define AA_FIGURE_PANELS 6
typedef struct aa_figure_panel {
    char label[128];
    int reference;                   /* 1: the panel is the exact reference */
    double rmse, max_err;            /* linear light */
    double rmse_enc, max_err_enc;    /* after the panel's display encoding */
    double rgb[3];                   /* the first pixel (1 x 1 figures: its colour) */
} aa_figure_panel;
typedef struct aa_figure_result {
    const char *name;
    int npanels;
    aa_figure_panel panel[AA_FIGURE_PANELS];
    double seconds;
} aa_figure_result;
size_t aa_figure_count(void);
const char *aa_figure_name(size_t k);  /* NULL past the end */
int aa_figure_find(const char *name);  /* index, or -1 */
/* Make figure k in `dir` (which must exist); references come from and go
 * to `cache_dir` (NULL: no cache).  Nothing is left half-written. */
int aa_figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                   aa_figure_result *r);
int aa_figure_index(const char *dir);

/* ------------------------------------------------------------------------
 * Files
 * ------------------------------------------------------------------------ */

/* ------------------------------------------------------------------------
 * The stress suite (stress.c): scenes at the limits of the geometry, the
 * reference and `area` against a long double evaluation, every method
 * finite and within [0, 1]
 * ------------------------------------------------------------------------ */

typedef struct aa_stress_result {
    const char *name;
    int w, h;
    double ref_err, ref_bound;   /* reference against the evaluation */
    double area_err, area_bound; /* `area` against the evaluation */
    size_t nonfinite;            /* NaN or Inf values, reference and methods */
    size_t out_of_range;         /* method values outside [0, 1] */
    int methods, refused;        /* methods run, methods that refused */
    int pass;
} aa_stress_result;

size_t aa_stress_count(void);
const char *aa_stress_name(size_t k);
/* Run case k; a status for failures to run (memory), not for failed checks. */
int aa_stress_run_case(size_t k, int threads, aa_stress_result *r);

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

/* Monotonic clock in seconds. */
double aa_now(void);

#ifdef __cplusplus
}
#endif

#endif /* AABENCH_H */
