/*
 * bluenoise.c: the void-and-cluster method (Ulichney 1993, "The
 * void-and-cluster method for dither array generation", Proc. SPIE 1913),
 * a dither array whose every threshold pattern is blue noise: its
 * minority pixels spread evenly, with little energy at low frequencies.
 *
 * The paper's definitions, as done here.  A binary pattern's "energy" at a
 * pixel is the sum over its minority pixels (the 1s) of the Gaussian
 * filter exp(-r^2 / (2 sigma^2)), r the distance on the torus (the filter
 * wraps around, a circular convolution, so the array tiles without seams);
 * sigma = 1.5 as in the paper.  The tightest cluster is the 1 of largest
 * energy, the largest void the 0 of least.
 *  - Initial binary pattern: side^2/10 minority pixels (the paper asks for
 *    no more than half; a tenth is chosen here), placed at random from the
 *    stream of the seed, then relaxed: the tightest cluster is removed and
 *    a 1 put in the largest void, until the largest void is where the
 *    cluster was taken from.
 *  - Phase 1: from the initial pattern, the tightest cluster is removed
 *    repeatedly; each removed pixel's rank is the count of 1s left.
 *  - Phase 2: from the initial pattern, a 1 is put in the largest void
 *    repeatedly, up to half the pixels; each gets the count of 1s before
 *    it as its rank.
 *  - Phase 3: past half the 0s are the minority, and the paper turns the
 *    tightest cluster of 0s into a 1.  The 0s' energy is the sum of the
 *    filter over the whole torus (the same at every pixel) minus the 1s',
 *    so the tightest cluster of 0s is the largest void of 1s: phase 3 is
 *    phase 2 carried on to the last pixel, as done here.
 * Ties (equal energies) go to the lowest index y side + x, which the paper
 * leaves open.  Energies are kept as a table updated by one filter's
 * worth of terms per change: O(side^4) in all (64 x 64: about 3e7 terms).
 */
#include "bluenoise.h"

#include "aabench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vac {
    int side;
    size_t n;
    double *g;      /* the filter: g[dy side + dx], wrapped distances */
    double *e;      /* energy of the current pattern at each pixel */
    unsigned char *on;
} vac;

static void toggle(vac *v, size_t p, int add)
{
    const int s = v->side, px = (int)(p % (size_t)s), py = (int)(p / (size_t)s);
    const double sign = add ? 1.0 : -1.0;
    v->on[p] = (unsigned char)add;
    for (int y = 0; y < s; y++) {
        const int dy = (y - py + s) % s;
        const double *gr = v->g + (size_t)dy * (size_t)s;
        double *er = v->e + (size_t)y * (size_t)s;
        for (int x = 0; x < s; x++)
            er[x] += sign * gr[(x - px + s) % s];
    }
}

/* The tightest cluster (want 1: the 1 of largest energy) or the largest
 * void (want 0: the 0 of least); the lowest index on ties. */
static size_t find(const vac *v, int want)
{
    size_t best = (size_t)-1;
    for (size_t p = 0; p < v->n; p++) {
        if (v->on[p] != want)
            continue;
        if (best == (size_t)-1 || (want ? v->e[p] > v->e[best] : v->e[p] < v->e[best]))
            best = p;
    }
    return best;
}

int aa__bluenoise_mask(int side, double sigma, uint64_t seed, uint32_t *rank)
{
    if (side < 4 || side > 256)
        return aa_fail(AA_EINVAL, "blue-noise mask side %d out of range (4 to 256)", side);
    if (!(sigma > 0.0) || !isfinite(sigma))
        return aa_fail(AA_EINVAL, "blue-noise filter sigma %g is not positive", sigma);
    vac v = {side, (size_t)side * (size_t)side, NULL, NULL, NULL};
    v.g = malloc(v.n * sizeof *v.g);
    v.e = calloc(v.n, sizeof *v.e);
    v.on = calloc(v.n, 1);
    unsigned char *initial = malloc(v.n);
    double *e0 = malloc(v.n * sizeof *e0);
    if (!v.g || !v.e || !v.on || !initial || !e0) {
        free(v.g), free(v.e), free(v.on), free(initial), free(e0);
        return aa_fail(AA_ENOMEM, "out of memory for a %dx%d blue-noise mask", side, side);
    }
    for (int dy = 0; dy < side; dy++)
        for (int dx = 0; dx < side; dx++) {
            int wx = dx <= side / 2 ? dx : side - dx, wy = dy <= side / 2 ? dy : side - dy;
            v.g[(size_t)dy * (size_t)side + (size_t)dx] =
                exp(-(double)(wx * wx + wy * wy) / (2.0 * sigma * sigma));
        }
    /* the initial binary pattern: random, then relaxed */
    const size_t ones = v.n / 10 ? v.n / 10 : 1;
    aa_rng rng;
    aa_rng_seed(&rng, seed, 0, 0);
    for (size_t k = 0; k < ones;) {
        size_t p = (size_t)(aa_rng_next(&rng) % v.n);
        if (!v.on[p])
            toggle(&v, p, 1), k++;
    }
    for (size_t guard = 0; guard < 16 * v.n; guard++) {
        size_t c = find(&v, 1);
        toggle(&v, c, 0);
        size_t h = find(&v, 0);
        toggle(&v, h, 1);
        if (h == c)
            break;
    }
    memcpy(initial, v.on, v.n);
    memcpy(e0, v.e, v.n * sizeof *e0);
    /* phase 1: clusters out, ranks ones-1 .. 0 */
    for (size_t r = ones; r-- > 0;) {
        size_t c = find(&v, 1);
        toggle(&v, c, 0);
        rank[c] = (uint32_t)r;
    }
    /* phases 2 and 3: voids filled, ranks ones .. n-1 */
    memcpy(v.on, initial, v.n);
    memcpy(v.e, e0, v.n * sizeof *e0);
    for (size_t r = ones; r < v.n; r++) {
        size_t h = find(&v, 0);
        toggle(&v, h, 1);
        rank[h] = (uint32_t)r;
    }
    free(v.g), free(v.e), free(v.on), free(initial), free(e0);
    return AA_OK;
}
