/*
 * truth_internal.h: the reference renderer's modes, for the tests and the
 * benchmarks (not part of the public interface).
 */
#ifndef AA_TRUTH_INTERNAL_H
#define AA_TRUTH_INTERNAL_H

#include "aabench.h"

/* Mode 0 is aa_truth_render's.  Mode AA__TRUTH_QAG integrates every
 * non-uniform pixel with QAG, as before the Gaussian's fixed rule existed.
 * *nfast (may be NULL) receives the number of pixels the fixed rule took. */
#define AA__TRUTH_QAG 1
int aa__truth_render_mode(const aa_scene *placed, const aa_filter *f, int threads, int mode,
                          aa_image *out, aa_image *bound, aa_truth_stats *stats, size_t *nfast);

#endif
