/*
 * bench.h: the benchmark (harness/bench): metrics, temporal metrics, runs
 * and suites, results files, convergence, montages, plots, the published
 * figures and the stress suite.
 */
#ifndef AA_BENCH_H
#define AA_BENCH_H

#include "truth.h"

#include <stdio.h>

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
    /* LDR-FLIP's mean (flip.c) at AA_FLIP_PPD, as the encoded images are
     * shown; the RMSE over the edge pixels (edges.c), NaN when not taken
     * (aa_metrics_edges sets it) or when there is no edge pixel */
    double flip, edge_rmse;
    size_t edge_pixels;
    /* pixels where either image holds a NaN or an infinity (only
     * aa_metrics_compare takes such images): left out of everything above.
     * psnr is infinite only for identical images (the same NaN or infinity
     * in both counts as the same); NaN if they differ only where a value is
     * not finite.  Every figure is NaN when every pixel is left out. */
    size_t nonfinite;
} aa_metrics;

/* enc NULL: sRGB.  Images must have the same size and channels, and hold
 * finite values only (else AA_EINVAL naming the pixel). */
int aa_metrics_compute(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                       aa_metrics *m);
/* The same for images that may hold NaN or infinities (image files): their
 * pixels are counted in m->nonfinite, not refused. */
int aa_metrics_compare(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                       aa_metrics *m);
/* The bytes aa_metrics_compute takes beyond the two images, at most. */
double aa_metrics_bytes(int w, int h);
/* m->edge_rmse and m->edge_pixels over the pixels whose support of radius r
 * meets an edge of the placed scene (edges.c); placed NULL: the pixels of
 * ref that differ from a 4-neighbour (image files without their scene). */
int aa_metrics_edges(const aa_scene *placed, double r, const aa_image *ref, const aa_image *img,
                     aa_metrics *m);

/* FLIP (flip.c): Andersson et al. 2020, LDR-FLIP.  Pixels per degree of a
 * display `width` metres wide of `pixels` pixels seen from `distance`
 * metres; AA_FLIP_PPD the paper's default, a 0.7 m wide 3840-pixel monitor
 * at 0.7 m (67.02). */
double aa_flip_ppd(double distance, double width, int pixels);
#define AA_FLIP_PPD (0.7 * (3840 / 0.7) * 3.14159265358979323846 / 180.0)
/* The colour pipeline's cmax: the Hunt-adjusted HyAB distance of pure green
 * and pure blue, raised to qc = 0.7. */
double aa_flip_cmax(void);
/* The mean FLIP of img against ref (same size; grey or RGB, linear light,
 * shown through `enc`, NULL sRGB) at ppd pixels per degree; map (may be
 * NULL) receives the per-pixel values, w x h x 1, in [0, 1].  Fewer
 * than 3 channels: grey (the first); more: RGB (the first three). */
int aa_flip(const aa_image *ref, const aa_image *img, const aa_encode *enc, double ppd,
            double *mean, aa_image *map);
double aa_flip_bytes(int w, int h);
/* Edge pixels (edges.c): mask[j w + i] = 1 when the open square of
 * half-side r about the pixel's centre meets a piece of the placed scene;
 * from an image alone: when the pixel differs from a 4-neighbour. */
int aa_edge_mask(const aa_scene *placed, double r, int w, int h, unsigned char *mask);
int aa_edge_mask_of_image(const aa_image *ref, unsigned char *mask);
/* The RMSE over the mask's pixels (finite in both), every channel; NaN
 * when none; count (may be NULL) the pixels taken. */
int aa_edge_rmse(const aa_image *ref, const aa_image *img, const unsigned char *mask,
                 double *rmse, size_t *count);

/* Temporal metrics of n displayed frames at times t0, t0 + 1, ... against
 * the references at the same times (temporal.c): eye_rmse over every
 * window of `window` frames (eye's image: the frames' mean, against the
 * references' mean), flicker (per channel and pixel, the population
 * standard deviation over time of frame minus reference; its mean and max),
 * conservation ((max - min)/mean of the total intensity over the frames),
 * lag (the delay in frames that best explains the error along the scene's
 * own change: the ghosting of a history). */
#define AA_TEMPORAL_MAX_FRAMES 256
typedef struct aa_temporal {
    int frames, window;
    double eye_rmse;
    double flicker_mean, flicker_max;
    double conservation;
    double lag;     /* frames behind the scene, least squares (temporal.c) */
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
 * The eye (eye.c): an image shown as uniform pixel squares (black outside)
 * seen through a Gaussian of s pixels, against the scene seen through the
 * same Gaussian (from its exact box values in cells 1/4 pixel wide)
 * ------------------------------------------------------------------------ */

#define AA_EYE_S 2.0   /* the eye of the figures and claims, in pixels */
#define AA_EYE_CELLS 4 /* the scene seen through cells this many times finer */
/* out (allocated here) = the eye's image of `in`. */
int aa_eye_blur(const aa_image *in, double s, aa_image *out);
/* The scene seen by the eye: its exact box values on a grid AA_EYE_CELLS
 * times finer (2 above 512 pixels), each cell a square seen through the
 * Gaussian of s pixels. */
int aa_eye_truth(const aa_spec *pattern, int w, int h, double t, double vx, double vy,
                 double s, const char *cache_dir, int threads, aa_image *out);
/* RMSE of the eye's image of `shown` (displayed intensities) against
 * `truth` (aa_eye_truth with the same s). */
int aa_eye_rmse(const aa_image *shown, const aa_image *truth, double s, double *rmse);
/* The image's own spectral power with |fx| or |fy| above f0 cycles per
 * pixel, per pixel and channel: near the Nyquist limit (f0 = AA_BEAT_F0)
 * it beats with the grid of dots into visible fringes. */
#define AA_BEAT_F0 0.35
int aa_band_energy(const aa_image *im, double f0, double *out);
/* The 2-D DFT in place of w x h complex values (z interleaved re, im, row
 * by row): the rows, then the columns, by GSL's mixed-radix FFT
 * (metrics.c). */
int aa_fft2(double *z, int w, int h);
/* The frequency of DFT index k of n, in cycles per pixel, folded to
 * [0, 1/2]. */
static inline double aa_fft_freq(int k, int n)
{
    return (k <= n / 2 ? k : n - k) / (double)n;
}

/* ------------------------------------------------------------------------
 * Displays (display.c; core.h, "Displays")
 * ------------------------------------------------------------------------ */

/* The reference of an image made of n frames shown through moving dots:
 * each frame's dots showing their exact values (the view's pattern, size,
 * filter and motion; each frame at its own time), seen through the fixed
 * pixel squares and weighted.  Allocates out (W x H x 3). */
int aa_display_reference(const aa_view *view, const aa_display_frame *frames, int n,
                         int threads, aa_image *out);
/* The same for a pattern scene of one's own (pattern units), W x H, the
 * filter and the motion (vx, vy) pixels per frame. */
int aa_display_reference_scene(const aa_scene *pattern, int w, int h, const aa_filter *filter,
                               double vx, double vy, const aa_display_frame *frames, int n,
                               int threads, aa_image *out);
/* The reference of `method`'s image for `job` when the method shows it
 * through moving dots (aa_method_display): into out (allocated) and
 * *shown = 1; else *shown = 0 and out is left alone (the view's ordinary
 * reference applies). */
int aa_display_view_reference(const aa_view *view, const aa_spec *method, const aa_job *job,
                              int threads, aa_image *out, int *shown);

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
    /* the timing by precision (core.h, "timing and its statistics"): every
     * render's wall and CPU time, their statistics and the noise seen;
     * timing.n = 0 when not timed (a results file without times) */
    aa_timing timing;
    /* several seeds (run --seeds N): the seeds the error was measured over
     * (1: the method is deterministic or one was asked) and the mean RMSE
     * with its 95% interval (NaN for one seed) */
    int seeds;
    double rmse_mean, rmse_ci_lo, rmse_ci_hi;
    /* 1: the case failed (ok = 0): the method gave an error or a value
     * outside [0, 1] or not finite, crashed or timed out; the note says
     * which.  0 with ok = 0: refused (a result, not a failure). */
    int failed;
    /* the case's number in the whole run's order (groups, then pattern,
     * size, filter, method), the same in every shard of it; -1 unknown (a
     * results file without the column) */
    long case_index;
    char host[64]; /* the machine that measured it ("" unknown) */
    /* the input files the case was made from, by their hash and length
     * (aa_pattern_inputs): "" when none or unknown (an older file) */
    char inputs[256];
    /* the view's reference: its largest per-pixel error bound, and how many
     * of its pixels' bounds are estimates, not proofs (aa_truth_stats's
     * max_bound and scanned); NaN unknown (an older file) */
    double ref_bound, ref_scanned;
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
    /* images are written for views of at most this many pixels (0: every
     * view) */
    long images_max;
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
    /* timing by precision: reps (above) > 0 is a fixed count; with reps 0
     * each case is timed until the relative half-width of its median's 95%
     * CI is at most target_ci (0: 2%) or `budget` seconds (0: 1 s) have
     * passed, at least AA_TIMING_MIN_REPS renders */
    double target_ci, budget;
    /* stochastic methods (AA_METHOD_SEEDED) are measured over `seeds` seeds,
     * seed, seed + 1, ... (0 or 1: one) */
    int seeds;
    /* isolation (isolate.c): a case run in a child process of its own, so
     * that a method that crashes or never returns is a failed case and the
     * run goes on; a case longer than case_timeout seconds (0: 600) is
     * stopped */
    int isolate; /* AA_ISOLATE_NONE (0), AA_ISOLATE_PLUGINS or AA_ISOLATE_ALL */
    double case_timeout;
    /* the cases to run (shards, resumed runs): only[k] non-zero for the
     * k-th case of the cross product, in pattern, size, filter, method
     * order; NULL: every case.  A view none of whose cases runs is not
     * visited (its reference is not made).  case_base is added to k for
     * the rows' case_index (the group's first case in the whole run). */
    const unsigned char *only;
    size_t case_base;
    /* 1: a method that refuses a view (a filter it cannot honour, a scene it
     * cannot take) gives no row and adds one to *skipped (may be NULL);
     * 0: it gives a row with ok = 0 and the reason */
    int skip_refused;
    size_t *skipped;
    /* with skip_refused, refused[k] (may be NULL) is set for each case of
     * the cross product skipped so (k as for `only`) */
    unsigned char *refused;
} aa_run_config;
#define AA_ISOLATE_NONE 0
#define AA_ISOLATE_PLUGINS 1 /* the methods of plug-ins only */
#define AA_ISOLATE_ALL 2
#define AA_CASE_TIMEOUT 600.0

/* A case's estimated cost before it runs (cost.c): W H S + the sum over
 * pixel rows of the square of the number of the placed scene's pieces
 * crossing the row, S the method's samples per pixel (spp, n^2 for n, else
 * 1).  A run warns (aa_warn) before a view whose case is past
 * AA_COST_LIMIT, naming the case. */
#define AA_COST_LIMIT 1e11
double aa_case_estimate(const aa_scene *placed, int w, int h, const aa_spec *method);
/* The warning for each chosen method of the view (cases first .. first +
 * nmethods - 1 of cfg's cross product) past the limit. */
void aa_case_estimate_warn(const aa_run_config *cfg, const aa_view *view, const aa_scene *scene,
                       size_t first);

/* Check the config before any work: lists present, sizes within memory,
 * counts in range, each spec of the kind its list holds. */
int aa_run_check(const aa_run_config *cfg);
/* Run it: *rows (malloc'd, n rows) in pattern, size, filter, method order.
 * A method that refuses a filter or a scene gives a row with ok = 0 and the
 * reason, or no row with skip_refused; a method that fails (an error, a
 * value outside [0, 1] or not finite, and when isolated a crash or a
 * time-out) a row with ok = 0 and failed = 1, and the run goes on.  A
 * status only for the harness's own failures (files, memory, an
 * interruption); *rows and *n hold the rows measured until then, whatever
 * the status (NULL and 0 if none). */
int aa_run(const aa_run_config *cfg, aa_row **rows, size_t *n);
/* The references aa_run would ask the cache for (every view with a case
 * to run; for animated runs each frame's), computed and stored into
 * cfg->cache_dir where missing: *computed and *cached (added to) count
 * them. */
int aa_run_warm(const aa_run_config *cfg, size_t *computed, size_t *cached);

/* ---- sharded runs (shard.c) ----
 *
 * A run's cases are numbered in the order the whole run takes them
 * (groups in turn, each in pattern, size, filter, method order).  A shard
 * K of N (1 <= K <= N) takes the cases a deterministic partition gives it:
 * each case costs pixels x samples (spp, or n x n, else 1; times the frames
 * of an animated run and the seeds of a stochastic method), and each view
 * a shard visits costs its reference (pixels x AA_SHARD_REFERENCE_WEIGHT
 * per frame) once in that shard; a case whose method refuses its filter
 * costs nothing; cases are taken from the most costly down
 * (ties by number), each to the shard whose load then is least (ties: the
 * lowest K).  The union of the N shards is the whole run, each case once. */
#define AA_SHARD_REFERENCE_WEIGHT 16
#define AA_SHARD_MAX 4096
/* The estimated cost of case k of a group's cross product, and of the
 * references of its view. */
uint64_t aa_case_cost(const aa_run_config *cfg, size_t k);
uint64_t aa_case_reference_cost(const aa_run_config *cfg, size_t k);
/* The cases of a group's cross product. */
size_t aa_run_case_count(const aa_run_config *cfg);
/* Shard `shard` of `nshards` of the ng groups: masks[g] (malloc'd, one byte
 * per case of group g) marks its cases; *selected counts them, *cost (may
 * be NULL) is their estimated cost, references included. */
int aa_shard_plan(const aa_run_config *cfgs, size_t ng, int shard, int nshards,
                  unsigned char **masks, size_t *selected, uint64_t *cost);

/* A run folder's manifest, run.json: the command (its arguments after
 * `run`, without those that do not change the results: --out, --resume,
 * --shard, --cache, --no-cache, -q, --threads: images are the same for any
 * thread count), the suite, the commit and whether the
 * tree was dirty, the shard (1 of 1 unsharded), the cases of the whole
 * run and those of this folder, and the context of the machine (text of a
 * JSON object).  Written before any case, so an interrupted run can be
 * resumed and shards merged (runfolder.c). */
typedef struct aa_manifest {
    int argc;
    char **argv;
    char suite[64], commit[64], host[64];
    int dirty; /* 1, 0, -1 unknown */
    int shard, shards;
    size_t cases;
    size_t *selected;
    size_t nselected;
    /* the cases the run skipped because their method refuses the view (a
     * filter, a scene): no rows, but done; added when the run ends */
    size_t *refused;
    size_t nrefused;
    char *context; /* JSON text, may be NULL */
    /* the folder's files when its run ended (results.csv and images/...,
     * by path within the folder) with their checksums, "fnv1a HASH bytes
     * N" (aa_file_checksum): what a merge checks each shard's files
     * against; summed = 0 while the run has not ended */
    int summed;
    size_t nsums;
    struct aa_manifest_sum {
        char *name;
        char sum[64];
    } *sums;
    /* the run's input files (aa_case_inputs), by what reads them:
     * "pattern SPEC" or "method SPEC", and their record; those that read
     * none are left out */
    size_t ninputs;
    struct aa_manifest_input {
        char *what, *inputs;
    } *inputs;
} aa_manifest;
/* A file's checksum as a manifest records it: "fnv1a %016llx bytes %zu"
 * (64-bit FNV-1a of its bytes, and their count) into sum (64 bytes); of
 * bytes in memory with aa_bytes_checksum. */
int aa_file_checksum(const char *path, char sum[64]);
void aa_bytes_checksum(const void *data, size_t n, char sum[64]);
int aa_manifest_write(const char *path, const aa_manifest *m);
/* Read strictly: a member missing or of the wrong type, or a case outside
 * the run, is AA_EINVAL naming the file and the member; a file that is not
 * there, AA_EIO. */
int aa_manifest_read(const char *path, aa_manifest *m);
void aa_manifest_free(aa_manifest *m);
/* Whether an argument of `run` is left out of a manifest's command, and
 * whether it takes a value (*takes_value). */
int aa_manifest_skips(const char *arg, int *takes_value);

/* results.csv and results.json: one row per case. */
int aa_rows_write_csv(const char *path, const aa_row *rows, size_t n);
int aa_rows_write_json(const char *path, const aa_row *rows, size_t n);
/* Read a results or baseline CSV back (the columns written above),
 * checked as strictly as a spec (report.c): a row the gate cannot trust is
 * refused (AA_EINVAL) naming the file, line and column.  *rows is NULL and
 * *n 0 on failure. */
int aa_rows_read_csv(const char *path, aa_row **rows, size_t *n);
/* The same from `len` bytes in memory; `name` names them in messages. */
int aa_rows_parse_csv(const char *name, const char *data, size_t len, aa_row **rows,
                      size_t *n);
/* A results.json read back as strictly (report.c): the case, ok, the note,
 * a row's errors and its repetition times; anything malformed is refused
 * (AA_EINVAL) naming the file, the row and the member. */
int aa_rows_read_json(const char *path, aa_row **rows, size_t *n);
int aa_rows_parse_json(const char *name, const char *data, size_t len, aa_row **rows,
                       size_t *n);

/* Fair comparisons: methods in one table should have run with the same
 * effective parallelism, a render's CPU time over its wall time (the
 * timing's cpu_share).  The rows measured ok with a share (threads > 0,
 * renders timed) of least and most, into *least and *most, and the ratio
 * of the most to the least; 1 with fewer than two such rows.  A ratio above
 * AA_PARALLELISM_FACTOR is worth a warning. */
#define AA_PARALLELISM_FACTOR 1.5
double aa_rows_parallelism(const aa_row *rows, size_t n, size_t *least, size_t *most);

/* 1 if rows a and b are of the same view (pattern, size, filter). */
int aa_rows_same_view(const aa_row *a, const aa_row *b);

/* 1 if rows[k] is the first measured row (ok) of its view (pattern, size,
 * filter) and its reference is not proven everywhere: pixels whose bounds
 * are estimates (ref_scanned > 0) or a bound above AA_TRUTH_BOUND. */
int aa_row_reference_unproven(const aa_row *rows, size_t k);

/* The commit the program was built from ("unknown" outside a git checkout)
 * and, into *dirty, whether the tree was dirty then (1, 0, -1 unknown). */
const char *aa_build_commit(int *dirty);

/* What a results file says of the run that made it (context.c): the
 * commit the program was built from (and the commit and state of the
 * checkout it lives in at run time, which may have moved on), the
 * compiler and its flags, the CPU, cores, threads, OS and kernel, the
 * libraries' versions, the date, the load and the command line. */
typedef struct aa_context {
    char commit[64];
    int dirty;             /* 1 dirty, 0 clean, -1 unknown */
    char commit_from[16];  /* "build": the commit is the build's */
    char checkout[64];     /* the checkout's commit at run time, "" outside one */
    int checkout_dirty;    /* its state then: 1 dirty, 0 clean, -1 unknown */
    char compiler[128], cflags[512];
    char cpu[256];
    int cores, cores_allowed, threads;
    char os[256], kernel[128], machine[64], governor[64];
    char host[64];         /* the node's name (uname) */
    char gsl[32], oiio[32], freetype[32], cairo[32], stb[64];
    char date[32];         /* UTC, ISO 8601 */
    double load[3];        /* load averages at the start */
    int argc;
    const char *const *argv; /* the command line, kept by the caller */
} aa_context;
int aa_context_collect(aa_context *c, int argc, const char *const *argv, int threads);
/* The context as a JSON object, its inner lines indented by `indent`
 * spaces (malloc'd; NULL when out of memory). */
char *aa_context_json(const aa_context *c, int indent);
/* results.json as {"context": ..., "results": [rows]} (ctx NULL: null). */
int aa_results_write_json(const char *path, const aa_context *ctx, const aa_row *rows, size_t n);
/* A row's timing, noise and seeds as JSON members to follow an object's
 * others: ", " and the members as cJSON prints them compactly, or "" for
 * a row without (malloc'd; NULL: out of memory). */
char *aa_row_timing_json(const aa_row *r);
/* The columns of results.csv in the order written, the one table the
 * writer and the reader share: column k's name, NULL past the end. */
const char *aa_results_column(size_t k);

/* Comparing two runs (diff.c), case by case. */
#define AA_ERROR_ABS_TOLERANCE 1e-12
#define AA_TIME_ALPHA 0.05 /* a time change is significant at p below this */
typedef struct aa_case_change {
    const aa_row *old, *now;
    int error_worse;    /* rmse or max_err above old (1 + tol) + 1e-12 */
    int refused;        /* ran before, refused now */
    double rmse_change; /* now / old - 1 */
    double time_ratio;  /* median now / median before; NaN if either is missing */
    int tested;         /* both had repetition times: Mann-Whitney U was taken */
    double u, z, p;     /* of now against before (z > 0: slower) */
    int significant;    /* tested and p < AA_TIME_ALPHA */
    int noisy;          /* either measurement was marked noisy */
    const char *regression; /* aa_case_verdict's: NULL when the case passes */
} aa_case_change;
/* The gates' one rule (`check` and `diff`), a case of OLD (the baseline)
 * against NOW, the same case run again (NULL: missing from the new run):
 * NULL when it passes, else why not, with the figures in detail (may be
 * NULL).  It fails when it is missing, was made from other input files
 * (both record them, aa_case_inputs, and they differ), now fails, now
 * refuses a case that
 * ran, now runs a case recorded as refused, or its RMSE or largest error
 * exceeds the old one by more than tol relative plus 1e-12.
 * *confirmed is 1 when both refused the case (it passes). */
const char *aa_case_verdict(const aa_row *old, const aa_row *now, double tol, char *detail,
                            size_t len, int *confirmed);
/* The input files of a pattern (`svg`'s file, `text`'s font) by their
 * hash and length, as the reference cache keys them (aa_pattern_key), on
 * one line: "" for a pattern that reads none.  Rows record it with the
 * method's plug-in (aa_case_inputs: the `inputs` column), and `check`, `merge` and `run --resume` refuse rows
 * whose files have changed (aa_inputs_check). */
int aa_pattern_inputs(const aa_spec *pattern, char *buf, size_t len);
/* A case's inputs: its pattern's (pattern may be NULL), then, for a
 * method of a plug-in, the plug-in file's checksum ("plugin fnv1a HASH
 * bytes N", aa_method_file), or for `external` its adapter's ("adapter
 * ..."); method may be NULL. */
int aa_case_inputs(const aa_spec *pattern, const aa_spec *method, char *buf, size_t len);
/* A row's recorded inputs against its files now: AA_OK when they agree or
 * the row records none; else AA_EINVAL naming the file that changed (the
 * pattern's or the plug-in), `what` (the file the row was read from) and
 * both records. */
int aa_inputs_check(const char *what, const aa_row *r);
/* The same case: pattern, size, filter, method, time, motion, seed. */
int aa_case_same(const aa_row *a, const aa_row *b);
int aa_case_compare(const aa_row *old, const aa_row *now, double tol, aa_case_change *c);
/* A run folder (its results.csv) or a results file (a .json read as JSON,
 * aa_rows_read_json; any other as CSV) read as rows. */
int aa_results_load(const char *path, aa_row **rows, size_t *n);

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
/* The same with tiles given one at a time, for montages too large to hold:
 * the montage is drawn and written a row of tiles at a time, and asks
 * `get` for each tile once, in order; `put` (may be NULL) is called when
 * tile k has been copied, so its image can be freed.  Tiles are at most
 * tw x th, with at most `lines` lines of label. */
typedef struct aa_tile_source {
    size_t n;
    int tw, th, lines;
    int (*get)(void *ctx, size_t k, aa_tile *tile);
    void (*put)(void *ctx, size_t k);
    void *ctx;
} aa_tile_source;
int aa_montage_stream(const char *path, const aa_tile_source *src, int columns,
                      const aa_encode *enc);
/* What such a montage holds at once (its row of tiles being drawn, and one
 * tile), and the check of that and of the montage's sides against the
 * limits, before any work (AA_EINVAL with a message). */
double aa_montage_bytes(size_t n, int columns, int tw, int th, int lines);
int aa_montage_check(size_t n, int columns, int tw, int th, int lines);

/* Pictures of the error (errmap.c).  Colour maps, t to sRGB codes in
 * [0, 1]: magma (t in [0, 1]) and Moreland's diverging cool to warm (t in
 * [-1, 1], 0 a light grey). */
void aa_colormap_magma(double t, double rgb[3]);
void aa_colormap_diverging(double t, double rgb[3]);
/* x rounded up to 1, 2 or 5 times a power of ten (1 for x <= 0). */
double aa_nice_scale(double x);
/* The scale of the signed error map (errmap.c): the nice scale of the
 * 99.5th percentile of the non-zero |errors| (0 for identical images);
 * *largest (may be NULL) the largest. */
double aa_error_scale(const aa_image *ref, const aa_image *img, double *largest);
/* The signed error map of img against ref (largest channel error, its
 * sign kept) on the diverging map, auto-scaled (aa_error_scale, into
 * *scale, may be NULL), with a colour bar
 * and the caption (may be NULL) above: an image of sRGB codes (write it
 * with aa_picture_write). */
int aa_error_picture(const aa_image *ref, const aa_image *img, const char *caption,
                     aa_image *out, double *scale);
/* Whether the error map of a w x h image can be made (its sides, its
 * memory): AA_EINVAL with a message if not; its zoom (1 to 4: small
 * images are shown larger). */
int aa_error_picture_check(int w, int h);
int aa_error_picture_zoom(int w, int h);
/* Write a picture of sRGB codes (the above) as an sRGB PNG; the picture's
 * values are made linear on the way. */
int aa_picture_write(const char *path, aa_image *pic);
/* FLIP's map (w x h x 1, aa_flip) on magma, 0 to 1, with its colour bar. */
int aa_flip_picture(const aa_image *map, const char *caption, aa_image *out);
/* The k x k window (k at most the sides) of largest squared error: its
 * top left corner. */
int aa_worst_window(const aa_image *ref, const aa_image *img, int k, int *x0, int *y0);
/* The worst 32 x 32 window zoomed: reference, image, signed error and
 * FLIP side by side, labelled; sRGB codes; its corner in *wx, *wy. */
int aa_worst_picture(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                     aa_image *out, int *wx, int *wy);

/* The run folder's report, DIR/index.html (runreport.c): each view's
 * table, montage, error maps and worst regions, and the plots, those
 * present in DIR. */
int aa_run_report(const char *dir, const aa_row *rows, size_t n);

/* Plots with gnuplot into `dir`: error_vs_time.{dat,gp,png} (log-log, each
 * view's Pareto front marked) and convergence.{dat,gp,png}. */
int aa_plot_error_vs_time(const char *dir, const aa_row *rows, size_t n);
int aa_plot_convergence(const char *dir, const aa_convergence *c, const char *const *names,
                        size_t n, const char *title);
/* A plot of one's own: `data` saved as DIR/NAME.dat and `script`, which reads
 * the gnuplot variables `dat` and `out` (setting them to NAME.dat and
 * NAME.png when unset), saved as NAME.gp and drawn into NAME.png. */
int aa_plot_script(const char *dir, const char *name, const char *data, const char *script);

/* s written as HTML text (<, >, & and " escaped): the gallery, the claims
 * page and the run report share it. */
void aa_html_escape(FILE *out, const char *s);

/* Published figures (figures.c): the seed papers' comparison figures remade
 * into a folder as NAME.png (labelled panels, aa_montage_write) and NAME.txt
 * (the paper's figure and claim, what stands in for it, the settings, the
 * command that remakes it, and each panel's RMSE and largest error against
 * the exact reference under its filter, and its eye error, linear light);
 * aa_figure_index writes index.html showing every figure present in the
 * folder, and the claims table (claims.html) when present. */
#define AA_FIGURE_PANELS 6
typedef struct aa_figure_panel {
    char label[128];
    char filter[128];                /* the filter it is measured under */
    int reference;                   /* 1: the panel is the exact reference */
    double rmse, max_err;            /* linear light, against the reference under its filter */
    double rmse_enc, max_err_enc;    /* after the panel's display encoding */
    double eye_rmse;                 /* what the eye sees (eye.c); NAN for tiny images */
    double beat;                     /* near-Nyquist energy of what it shows (eye.c); NAN */
    double rgb[3];                   /* the first pixel (1 x 1 figures: its colour) */
} aa_figure_panel;
typedef struct aa_figure_result {
    const char *name;
    int npanels;                     /* 0: a measurement, said in summary */
    aa_figure_panel panel[AA_FIGURE_PANELS];
    char summary[256];
    double seconds;
} aa_figure_result;
size_t aa_figure_count(void);
const char *aa_figure_name(size_t k);  /* NULL past the end */
int aa_figure_find(const char *name);  /* index, or -1 */
const char *aa_figure_title(size_t k); /* NULL past the end */
/* Figure k's row checked: its texts, size and panels present, its
 * pattern, filters, methods and encodings parsing (AA_EINVAL naming the
 * figure, the panel and the spec). */
int aa_figure_check(size_t k);
/* What figure k is made of, as text: its view and, per panel, the kind,
 * method, filter, encoding and display exponent (two figures with the same
 * key would be the same picture). */
int aa_figure_key(size_t k, char *buf, size_t len);
/* Make figure k in `dir` (which must exist); references come from and go
 * to `cache_dir` (NULL: no cache).  Nothing is left half-written. */
int aa_figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                   aa_figure_result *r);
int aa_figure_index(const char *dir);

/* Crow's colour-map calibration measured (calibration.c; Crow 1976,
 * appendix, figs. A.1-A.4): the test pattern under the two-dot pyramid,
 * stored as v by crowtable ([0]) and by the exact reference ([1]), shown
 * with intensity v^g and seen by the eye (AA_EYE_S): the fringes (standard
 * deviation of the eye's error over the image's right half) and the eye's
 * RMSE, for g = 0.5, 0.55, ... 4; the least of each to 0.001; and the
 * three colour maps of figs. A.1-A.3 (g = 2, 1, 4). */
#define AA_CALIBRATION_MAX 80
typedef struct aa_calibration {
    int n;
    double g[AA_CALIBRATION_MAX];
    double fringe[2][AA_CALIBRATION_MAX], eye[2][AA_CALIBRATION_MAX];
    double gmin_fringe[2], gmin_eye[2];
    double map_g[3], map_fringe[2][3], map_eye[2][3];
} aa_calibration;
int aa_crow_calibration(const char *cache_dir, int threads, aa_calibration *out);

/* The seed papers' quantitative claims measured (claims.c): DIR/claims.md
 * (a Markdown table: paper, where, claim, setting, measured, verdict and
 * its reason) and DIR/claims.html (the same, a page of its own whose body
 * index.html shows).  Each time ratio is the median over `reps` pairs of
 * interleaved single renders on one thread, with its 95% interval. */
int aa_claims_make(const char *dir, const char *cache_dir, int threads, int reps,
                   int (*progress)(void *ctx, const char *what), void *ctx);
/* The claims table (claims.c): how many claims, and claim k's row checked
 * (its texts present, every pattern, filter and method spec it names
 * parsing, its lists of one length); AA_EINVAL names the claim and spec. */
size_t aa_claim_count(void);
int aa_claim_check(size_t k);
/* The claims' verdicts (claims.c), each from numbers and a margin fixed
 * before measuring.  A ratio measured with its confidence interval
 * [ci_lo, ci_hi] against the band [lo, hi] a claim allows: "yes" when the
 * interval lies inside the band, "no" when it lies wholly outside,
 * "inconclusive" when it holds an end of the band (or is not a number). */
const char *aa_claim_band_verdict(double ci_lo, double ci_hi, double lo, double hi);
/* Two errors (smaller is better) compared with a relative margin: -1 when
 * a < b (1 - margin), 1 when b < a (1 - margin), 0 (a tie) otherwise. */
int aa_claim_compare(double a, double b, double margin);
/* A claim made of several cases, from the cases' verdicts: "yes" when all
 * hold, "no" when none does, "partly" when some hold and some do not,
 * "inconclusive" otherwise (some undecided and no such mix). */
const char *aa_claim_tally(int yes, int no, int undecided);

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

/* The run folder as a library object: runfolder.h. */
#include "runfolder.h"

#endif /* AA_BENCH_H */
