/*
 * bluenoise.h: void-and-cluster dither arrays (Ulichney 1993), used as
 * blue-noise sample offsets by `jitter:seq=bluenoise` (internal to
 * algorithms/; bluenoise.c).
 */
#ifndef AA_BLUENOISE_H
#define AA_BLUENOISE_H

#include <stdint.h>

/* The side of jitter's masks: 64 x 64 ranks. */
#define AA__BLUENOISE_SIDE 64
/* The paper's Gaussian filter. */
#define AA__BLUENOISE_SIGMA 1.5

/* A side x side rank mask: rank[y side + x] is a permutation of 0 ..
 * side^2 - 1, from an initial pattern of side^2/10 minority pixels drawn
 * from the stream of `seed` and relaxed, then ranked by the void-and-
 * cluster phases under the wrapped Gaussian of `sigma` pixels.  The same
 * seed gives the same mask.  AA_EINVAL for a side outside 4 .. 256 or a
 * sigma not positive, AA_ENOMEM. */
int aa__bluenoise_mask(int side, double sigma, uint64_t seed, uint32_t *rank);

#endif
