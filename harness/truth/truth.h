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

/* Internal (tests, benchmarks): mode AA__TRUTH_QAG integrates every
 * non-uniform pixel with QAG, as before the fixed rule existed; *nfast
 * (may be NULL) receives the number of pixels the fixed rule took. */
#define AA__TRUTH_QAG 1
int aa__truth_render_mode(const aa_scene *placed, const aa_filter *f, int threads, int mode,
                          aa_image *out, aa_image *bound, aa_truth_stats *stats, size_t *nfast);

#endif /* AA_TRUTH_H */
