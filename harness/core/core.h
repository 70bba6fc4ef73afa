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

/* ---- building scenes ---- */

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
 * the unit square, when the content reaches outside it (patterns/README.md:
 * outside the unit square every pattern is its background). */
int aa_scene_clip_unit(aa_scene *s);

/* A finished copy mapped by x' = sx x + tx, y' = sy y + ty (sx, sy > 0). */
aa_scene *aa_scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty);
/* The scene placed on a W x H image at time t (frames) moving (vx, vy)
 * pixels per frame: in pixel units, u = W x + t vx, v = H y + t vy. */
aa_scene *aa_scene_place(const aa_scene *s, int w, int h, double t, double vx, double vy);

/* The heights (ascending, at most max) in (ya, yb) where two pieces meet
 * (cross or touch) while both are present: in closed form for lines, a
 * line and an arc, and two arcs whose x is quadratic in y; for two general
 * arcs by bisection on their exact x extents (to 1e-12 relative), which
 * cannot miss a meeting while its budget of 4096 subintervals lasts (two
 * arcs running side by side over a long stretch can use it up, and a
 * meeting is then lost: harness/truth/truth_crowd.c finds theirs from a
 * quartic instead).  Flat pieces meet nothing. */
int aa_piece_meet(const aa_piece *p, const aa_piece *q, double ya, double yb, double *ys,
                  int max);

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

extern const aa_method_type *const aa_method_types[]; /* built-in, NULL-terminated */

/* The method table in use: the built-in methods, then those of loaded
 * plug-ins.  NULL-terminated; valid until the next aa_plugin_load. */
const void *const *aa_method_table(void);
/* Parse a method spec and check it against the filter. */
int aa_method_parse(const char *text, const aa_filter *f, aa_spec *out);
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
int aa_plugin_load(const char *path);

/* Add a plug-in's methods to the table; `origin` names it in messages.  A
 * name already in the table is refused. */
int aa__method_register(const aa_method_type *const *types, const char *origin);

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

/* Monotonic clock in seconds. */
double aa_now(void);

#ifdef __cplusplus
}
#endif

#endif /* AA_CORE_H */
