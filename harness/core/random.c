/*
 * random.c: counter-based random streams for methods.
 *
 * Each stream is SplitMix64 (Steele, Lea and Flood 2014) started from a hash
 * of (seed, pixel, frame), so the numbers a pixel draws do not depend on
 * which thread renders it or in which order: images are bit-identical for
 * any thread count.  SplitMix64's output function is a bijective 64-bit
 * mixer that passes BigCrush; it is also used as the hash.  The hash and
 * the step (aa_hash64, aa_rng_next) are inline in aabench.h, since methods
 * call them per sample.
 *
 * Frames: aa_frame_index(t) is floor(t), the harness's convention (a real
 * time T shows frame floor(T), as in hexagon), so a method seeded with it
 * draws the same numbers at every time of one frame and others in the
 * next; the frame number is taken modulo 2^64, so that no time, however
 * far, is refused.
 */
#include "core.h"

#include <math.h>

void aa_rng_seed(aa_rng *r, uint64_t seed, uint64_t pixel, uint64_t frame)
{
    /* chain the hash so that (a, b) and (b, a) give different streams */
    uint64_t h = aa_hash64(seed + 0x9e3779b97f4a7c15ull);
    h = aa_hash64(h ^ (pixel + 0x632be59bd9b4e019ull));
    r->state = aa_hash64(h ^ (frame + 0x85157af5ull));
}

double aa_rng_uniform(aa_rng *r)
{
    return (double)(aa_rng_next(r) >> 11) * 0x1.0p-53;
}

uint64_t aa_frame_index(double t)
{
    const double two63 = 0x1.0p63, two64 = 0x1.0p64;
    if (!isfinite(t))
        return 0;
    double f = floor(t);
    if (!(f >= -two63 && f < two63)) {
        /* reduce modulo 2^64 into [-2^63, 2^63): fmod is exact, and so is
         * each subtraction (Sterbenz: the operands are within a factor 2) */
        f = fmod(f, two64);
        if (f >= two63)
            f -= two64;
        else if (f < -two63)
            f += two64;
    }
    return (uint64_t)(int64_t)f;
}
