/*
 * truth.h: the ground truth (harness/truth): the exact reference image of a
 * placed scene, and the cache of references keyed by their view.
 */
#ifndef AA_TRUTH_H
#define AA_TRUTH_H

#include "core.h"

/* ------------------------------------------------------------------------
 * Ground truth: the pattern convolved with the filter, at pixel centres
 * ------------------------------------------------------------------------ */

#define AA_TRUTH_BOUND 1e-12

typedef struct aa_truth_stats {
    size_t integrated; /* pixels integrated */
    size_t filled;     /* uniform pixels filled without integration */
    size_t crowded;    /* of the integrated, those taken one piece at a time */
    double max_bound;  /* largest per-pixel error bound */
    int worst_i, worst_j;
    /* of the integrated, those whose threshold heights where gradients of
     * different t mix were scanned, not certified: their bound is QAG's
     * estimate, not a proof (truth.c, "several gradients") */
    size_t scanned;
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

/* Progress of the references rendered from now on (aa_truth_render, and so
 * aa_reference when it computes one): fn(ctx, done, total) with the pixels
 * done so far, called by whichever rendering thread finishes a pixel or a
 * run of uniform ones, one call at a time, at most ten times a second (the
 * least time between calls is aa__truth_set_progress_interval's), and
 * once with done == total at the end.  The library prints nothing: the
 * command line shows it (cmd_truth.c).  NULL: no calls.  One setting for
 * the process, changed only between renders. */
typedef void (*aa_truth_progress_fn)(void *ctx, size_t done, size_t total);
void aa_truth_set_progress(aa_truth_progress_fn fn, void *ctx);
/* For tests: the least time between two calls of the progress hook, 0.1 s
 * unless set (0: a call for every pixel or uniform run done). */
void aa__truth_set_progress_interval(double seconds);

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
 * NULL) says which.  From the cache, stats holds only max_bound and
 * scanned (the cache keeps both). */
int aa_reference(const aa_view *view, const char *cache_dir, int threads, aa_image *out,
                 aa_truth_stats *stats, int *from_cache);

/* Internal (tests, benchmarks): mode AA__TRUTH_QAG integrates every
 * non-uniform pixel with QAG, as before the fixed rule existed; *nfast
 * (may be NULL) receives the number of pixels the fixed rule took. */
#define AA__TRUTH_QAG 1
/* mode AA__TRUTH_CROWD takes every non-uniform pixel one piece at a time
 * (truth_crowd.c), as crowded pixels are, to check it against the sum
 * over spans. */
#define AA__TRUTH_CROWD 2
int aa__truth_render_mode(const aa_scene *placed, const aa_filter *f, int threads, int mode,
                          aa_image *out, aa_image *bound, aa_truth_stats *stats, size_t *nfast);

/* Internal (tests): the 21-point Gauss-Kronrod pass in long double that
 * crowded pixels use: the result, QUADPACK's error estimate, the plain
 * |K21 - G10| and the rounding floor. */
void aa__truth_gk21l(long double (*f)(long double, const void *), const void *ctx, long double a,
                     long double b, long double *result, long double *abserr, long double *raw,
                     long double *floor);

/* Internal (tests): fn (NULL: none) is told of every bound the path of
 * several gradients proves on a Bernstein ellipse (truth.c, gen_bounds):
 * the row's height y (pixels), the ellipse's centre m and semi-axes A, B
 * in the piece's variable (B = 0: the real segment [m - A, m + A]; umode
 * 1: the variable is u, x = xr + eps u^2, "a cone beside other
 * gradients"; else x in pixels), fold 1 if the composite was folded
 * layer by layer, and for each of nch channels the bounds emax of the
 * encoded composite |e| and dmax of |e'| there.  One thread only: the
 * probe is called from the thread that integrates. */
typedef struct aa__gen_bound {
    double y, m, A, B;
    int umode, nch, fold;
    double emax[3], dmax[3];
} aa__gen_bound;
typedef void (*aa__gen_probe_fn)(void *ctx, const aa__gen_bound *b);
void aa__truth_set_gen_probe(aa__gen_probe_fn fn, void *ctx);

#endif /* AA_TRUTH_H */
