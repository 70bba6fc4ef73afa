/*
 * jitter.c: stochastic supersampling, `spp` point samples per pixel at
 * random or randomised quasi-random positions, weighted by the filter.
 * The Pfenning slides (slide 26, "Supersampling example", other
 * improvements) name the two ideas followed here: stochastic sampling,
 * "avoiding repetition", the regular grid of Crow 1976 (ch. 2, figs.
 * 2.11-2.12: 9 and 25 samples per dot; `supersample`) whose repetition
 * aliases, and jittering, "perturb a regular grid".
 *
 * Positions.  A point (u, v) of [0,1)^2 maps to the filter's support:
 * x = centre - R + 2R u, with R = aa_filter_support (box 1/2, tent r,
 * Gaussian 3s).  `seq` chooses the points:
 *
 *  - stratified (default): one uniform point in each cell of a k x k grid,
 *    spp = k^2 (other spp are refused);
 *  - random: spp independent uniform points;
 *  - sobol, niederreiter, halton: the first spp points of GSL's 2-D
 *    sequence (gsl_qrng), made once in init, then randomised per pixel by
 *    Owen's nested uniform scrambling.  GSL's Sobol sequence skips the
 *    origin, so its first 2^m points are not a (0,m,2)-net; the origin is
 *    put back in front, making the set the first spp points of the Sobol
 *    sequence proper.  In two dimensions that is exactly GSL's
 *    niederreiter_2 (generator matrices identity and Pascal mod 2, same
 *    Gray-code order; the tests check it), so seq=sobol and
 *    seq=niederreiter give the same images.  Both are (0,2)-sequences: for
 *    spp = 2^m every scrambled pixel set is a (0,m,2)-net.  GSL's Halton
 *    starts at index 1 (1/2, 1/3); for spp = 2^a 3^b its points fall one
 *    in each 2^-a x 3^-b box.
 *  - bluenoise: the first spp points of the Sobol sequence (as above,
 *    unscrambled) moved, modulo 1, by a shift per pixel: in x and in y the
 *    ranks of two 64 x 64 void-and-cluster masks (Ulichney 1993,
 *    algorithms/bluenoise.c; made in init from the seed) at the pixel,
 *    (rank + 1/2)/4096, the masks tiled over the image from an origin
 *    moved per frame by a hash of the seed and the frame (none at frame
 *    0).  A shift modulo 1 (Cranley-Patterson) keeps each pixel's set
 *    evenly spread but not a net; what it buys is that neighbouring
 *    pixels' offsets differ as blue noise, so their errors anticorrelate
 *    and the error image's power leaves the low frequencies
 *    (tests/test_bluenoise.c; algorithms/README.md, "Blue noise").
 *
 * Weights and value.  Sample s at offset (dx, dy) from the centre weighs
 * w(dx) w(dy) (1 for the box; for the cone, which is not separable, its
 * 2-D weight w(dx, dy), with samples over the square of its radius, so a
 * fifth of them (1 - pi/4) fall outside the disc and weigh 0; should all of
 * a pixel's do, it takes their plain mean), and the pixel is the weighted mean
 * sum w_s I_s / sum w_s: a ratio estimator of the filtered value, unbiased
 * only as spp grows (exactly unbiased for the box, whose weights are
 * equal), and the Gaussian is truncated at 3s (its 2-D mass outside, about
 * 0.5%, is never sampled).  A pixel whose samples all see one colour takes
 * that colour exactly.
 *
 * Scrambling (Owen 1995; hash-based after Burley 2020, "Practical
 * hash-based Owen scrambling", sec. 3).  Each coordinate's base-b digits
 * form a tree; every node at depth l carries a random permutation of the
 * digits 0..b-1, applied to digit l+1 of the points below it.  The
 * permutations are not stored: a node's is read from a counter-based hash
 * of (the pixel's key, the node), so each pixel gets an independent
 * scramble.  In base 2 a node's permutation is one flip bit, 64 nodes per
 * hash.  Only the top D levels are walked, D being the fewest digits that
 * tell the spp points apart; below that every point has a node of its
 * own, and Owen's scramble makes its remaining digits independent uniform,
 * so they are drawn as such.  Burley applies a Laine-Karras style integer
 * permutation to the bit-reversed value instead; the variants of it tried
 * here left sibling nodes' flips visibly correlated (a pair-of-points
 * digit test off by 0.13 from 1/2), while drawing each node from a hash
 * is exact Owen scrambling, at a cost of one hash per point (its lower
 * digits, both axes) plus 2^D/64 per axis for the nodes (Halton's base 3:
 * one per digit walked).  A random shift (Cranley-Patterson) is not used:
 * it spoils the net structure.
 *
 * Seeding.  Every random number of pixel (i, j) comes from the stream
 * aa_rng_seed(seed, j W + i, frame), frame being 0 at t = 0 and otherwise
 * the bits of t, so images are bit-identical for any thread count and
 * --seed changes them.  Positions have 32 random bits per coordinate
 * (u = (k + 1/2) 2^-32 within its cell or elementary interval).
 *
 * Cost.  Pixels whose support no edge touches are filled, not sampled
 * (aa_strip_window returns no local piece).  In a row where no piece ends
 * (all but the top and bottom rows on crow) a sample costs one root per
 * local piece of its window (one or two on crow) and a comparison: its
 * colour is that of the subset of local pieces left of it, found once per
 * pixel.  With the default stratified points and the box filter, all a
 * pixel needs is the count of samples per subset, so each sample is made
 * from its random number with one multiply-add per coordinate (a table of
 * cell corners made in init), tested and counted in the same pass, never
 * stored (callgrind: the positions were a third of the instructions of
 * jitter spp=16 on crow, stores and conversions more than the hash).
 * Elsewhere a sample also asks the strip for the winding left of the
 * window on its line.  On a field scene (the zone plate) every pixel is
 * sampled through the point function, and so is every pixel of a scene with
 * gradient paint.  Counters: samples = point evaluations,
 * expensive_pixels = pixels sampled.
 *
 * Limits.  Noise instead of aliasing: the RMSE of a pixel crossed by an
 * edge falls as spp^-3/4 for stratified points (Mitchell 1996;
 * algorithms/README.md, "Convergence rates"; the tests measure -0.75, and
 * the same for the scrambled
 * Sobol nets) and as spp^-1/2 for random points; other spp than 2^m lose
 * the net property.  With a filter other than the box the ratio estimator
 * adds a bias of order 1/spp, and the Gaussian is truncated at 3s.  Each
 * pixel is scrambled independently, so neighbouring pixels' samples are
 * not stratified against each other (no blue noise) but with
 * seq=bluenoise, whose two masks take about 0.09 s to make in init.
 */
#include "bluenoise.h"
#include "methods.h"
#include "sampling.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_qrng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define JT_MAX_SPP 4096
#define GOLDEN 0x9e3779b97f4a7c15ull

enum { P_SPP, P_SEQ };
enum { SEQ_STRATIFIED, SEQ_RANDOM, SEQ_SOBOL, SEQ_HALTON, SEQ_NIEDERREITER, SEQ_BLUENOISE };

static const aa_param jitter_params[] = {
    {"spp", AA_PARAM_INT, 16, 1, JT_MAX_SPP, 0, NULL,
     "samples per pixel (a square k^2 for seq=stratified)"},
    {"seq", AA_PARAM_CHOICE, SEQ_STRATIFIED, 0, 0, 0,
     "stratified|random|sobol|halton|niederreiter|bluenoise",
     "positions: one per cell of a k x k grid, independent uniform, an Owen-scrambled "
     "quasi-random sequence (gsl_qrng), or Sobol points shifted per pixel by "
     "void-and-cluster masks"},
    {0}};

static int square_side(int n)
{
    int k = (int)floor(sqrt((double)n) + 0.5);
    return k * k == n ? k : 0;
}

static int jitter_check(const double *p, const aa_filter *f)
{
    /* every filter is sampled over aa_filter_support, by its 2-D weight,
     * and the weighted sum divided by the sum of the weights: with
     * negative lobes (mitchell, catrom, lanczos) that sum of random
     * weights can come near 0 (values of -40 were seen), so those are
     * refused; supersample's regular grid takes them */
    double lo, hi;
    aa_filter_range(f, &lo, &hi);
    if (lo < 0.0)
        return aa_fail(AA_EINVAL, "jitter divides by the sum of its samples' weights, which "
                                  "under %s (negative lobes) can come near 0: use a filter "
                                  "without negative lobes, or supersample",
                       f->type->info.name);
    int spp = (int)p[P_SPP];
    if ((int)p[P_SEQ] == SEQ_STRATIFIED && !square_side(spp)) {
        int k = (int)floor(sqrt((double)spp));
        return aa_fail(AA_EINVAL,
                       "spp=%d: seq=stratified puts one sample in each cell of a k x k grid, "
                       "so spp must be a square (nearest: %d or %d), or use seq=random",
                       spp, k * k, (k + 1) * (k + 1));
    }
    return AA_OK;
}

/* ---- the quasi-random point set, made once ---- */

/* The first D digits of each coordinate, the part the scramble walks. */
typedef struct jt_points {
    int n;          /* points */
    int d2;         /* binary digits walked in x, and in y unless base 3 */
    int d3;         /* ternary digits walked in y (Halton), else 0 */
    uint32_t *px;   /* x prefix: floor(x 2^d2) */
    uint32_t *py;   /* y prefix: floor(y 2^d2), or the Halton index's digits */
    uint8_t *dig3;  /* Halton: y's ternary digits, most significant first */
} jt_points;

static void points_free(jt_points *q)
{
    free(q->px);
    free(q->py);
    free(q->dig3);
    memset(q, 0, sizeof *q);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* Do the top `d` binary digits of v[0..n) tell the points apart? */
static int distinct(const uint32_t *v, int n, uint32_t *work)
{
    memcpy(work, v, (size_t)n * sizeof *work);
    qsort(work, (size_t)n, sizeof *work, cmp_u32);
    for (int k = 1; k < n; k++)
        if (work[k] == work[k - 1])
            return 0;
    return 1;
}

/* Binary prefixes of d digits of the values in x (dyadic, at most 30
 * bits: exact). */
static void prefixes(const double *x, int n, int d, uint32_t *out)
{
    for (int k = 0; k < n; k++)
        out[k] = (uint32_t)floor(ldexp(x[k], d));
}

/* The first n points of GSL's 2-D sequence into x[], y[]; Sobol's with the
 * origin put back in front.  Dimension 2 is within every GSL limit
 * (sobol 40, niederreiter_2 12, halton 1229; gsl_qrng_alloc would not
 * refuse more: algorithms/README.md, "Quasi-random sequences in GSL"), and
 * every point is checked to lie in
 * [0,1)^2. */
static int points_fetch(int seq, int n, double *x, double *y)
{
    const gsl_qrng_type *type = seq == SEQ_SOBOL    ? gsl_qrng_sobol
                                : seq == SEQ_HALTON ? gsl_qrng_halton
                                                    : gsl_qrng_niederreiter_2;
    gsl_set_error_handler_off(); /* statuses are checked here */
    gsl_qrng *g = gsl_qrng_alloc(type, 2);
    if (!g)
        return aa_fail(AA_ENOMEM, "out of memory for a quasi-random generator");
    int k = 0, st = AA_OK;
    if (seq == SEQ_SOBOL) /* GSL skips the origin: its first 2^m are no net */
        x[0] = y[0] = 0.0, k = 1;
    for (; k < n && !st; k++) {
        double v[2];
        if (gsl_qrng_get(g, v) || !(v[0] >= 0.0 && v[0] < 1.0 && v[1] >= 0.0 && v[1] < 1.0))
            st = aa_fail(AA_EFAIL, "gsl_qrng %s failed at point %d", gsl_qrng_name(g), k);
        x[k] = v[0], y[k] = v[1];
    }
    gsl_qrng_free(g);
    return st;
}

/* Halton's y is the base-3 radical inverse of the index k+1 < 3^d3, so
 * y 3^d3 is an integer: read back from GSL's value by rounding, then cut
 * into d3 ternary digits. */
static int halton_digits(jt_points *q, const double *y)
{
    int n = q->n, d3 = 0;
    long p3 = 1;
    while (p3 <= n)
        p3 *= 3, d3++;
    q->d3 = d3;
    if (!(q->dig3 = malloc((size_t)n * (size_t)d3)))
        return aa_fail(AA_ENOMEM, "out of memory for %d quasi-random points", n);
    for (int k = 0; k < n; k++) {
        double Y = y[k] * (double)p3, r = floor(Y + 0.5);
        if (!(fabs(Y - r) < 1e-6) || r < 0 || r >= (double)p3)
            return aa_fail(AA_EFAIL, "gsl_qrng halton point %d is not a ternary fraction", k);
        long v = (long)r;
        q->py[k] = (uint32_t)v;
        for (int l = d3 - 1; l >= 0; l--, v /= 3)
            q->dig3[(size_t)k * d3 + l] = (uint8_t)(v % 3);
    }
    return AA_OK;
}

static int points_make(jt_points *q, int seq, int n)
{
    double *x = malloc(2 * (size_t)n * sizeof *x), *y = x ? x + n : NULL;
    uint32_t *work = malloc((size_t)n * sizeof *work);
    q->n = n;
    q->px = malloc((size_t)n * sizeof *q->px);
    q->py = malloc((size_t)n * sizeof *q->py);
    int st = !x || !work || !q->px || !q->py
                 ? aa_fail(AA_ENOMEM, "out of memory for %d quasi-random points", n)
                 : points_fetch(seq, n, x, y);
    /* the fewest binary digits that tell the x's (and the y's) apart */
    int d = 0;
    while ((1L << d) < n)
        d++;
    for (; !st; d++) {
        if (d > 30) {
            st = aa_fail(AA_EFAIL, "quasi-random sequence repeats a coordinate");
            break;
        }
        prefixes(x, n, d, q->px);
        if (!distinct(q->px, n, work))
            continue;
        if (seq != SEQ_HALTON)
            prefixes(y, n, d, q->py);
        if (seq == SEQ_HALTON || distinct(q->py, n, work))
            break;
    }
    q->d2 = d;
    if (!st && seq == SEQ_HALTON)
        st = halton_digits(q, y);
    free(x);
    free(work);
    if (st)
        points_free(q);
    return st;
}

/* ---- the state and each worker's scratch ---- */

typedef struct jt_state {
    int seq, spp, k;     /* k: side of the stratified grid */
    jt_points pts;       /* quasi-random sequences only */
    double *cell;        /* stratified: cell n's corner plus 2^-33 of a cell, in
                            pixels from the window's corner (x, y pairs) */
    double cell_r;       /* the support radius the table is for */
    double cell_scale;   /* pixels per unit of 32 random bits: span / k 2^-32 */
    size_t nflips;       /* 64-bit words of node bits: 2^d2 bits */
    double *bx, *by;     /* bluenoise: the first spp Sobol points */
    uint32_t *mask;      /* bluenoise: two rank masks, x's then y's */
    uint64_t mask_seed;  /* the seed they were made from */
    aa__sampler sampler; /* workers; own scratch: a jt_scratch */
} jt_state;

/* A worker's own scratch (aa__sampler_worker.own), cut into arrays. */
typedef struct jt_scratch {
    double *u, *v;      /* the pixel's points, in pixels from the window's
                           corner: [0, 2r)^2 */
    uint64_t *flips;    /* one bit per node of the x and the y digit trees */
    unsigned char *sub; /* each point's subset of local pieces left of it */
} jt_scratch;

/* The bytes of a jt_scratch, and where each array starts in them. */
static size_t scratch_layout(const jt_state *S, size_t *o_flips, size_t *o_sub)
{
    size_t spp = (size_t)S->spp, nf = S->nflips ? S->nflips : 1;
    *o_flips = 2 * spp * sizeof(double);
    *o_sub = *o_flips + 2 * nf * sizeof(uint64_t);
    return *o_sub + spp;
}

static jt_scratch scratch_of(const jt_state *S, const aa__sampler_worker *wk)
{
    size_t o_flips, o_sub;
    scratch_layout(S, &o_flips, &o_sub);
    char *b = wk->own;
    jt_scratch sc = {(double *)b, (double *)b + S->spp, (uint64_t *)(b + o_flips),
                     (unsigned char *)(b + o_sub)};
    return sc;
}

/* ---- scrambling ---- */

/* (k + 1/2) 2^-32: a uniform number in (0, 1) from 32 random bits. */
static inline double unit32(uint32_t k)
{
    return ((double)k + 0.5) * 0x1.0p-32;
}

/* Node bits of a binary digit tree for one pixel and coordinate: node 1 is
 * the root, node m has children 2m and 2m+1 (m's digits, then 0 or 1). */
static void fill_flips(uint64_t *flips, size_t words, uint64_t key)
{
    for (size_t w = 0; w < words; w++)
        flips[w] = aa_hash64(key + (uint64_t)(w + 1) * GOLDEN);
}

/* Owen-scramble the d-digit binary prefix p: digit l+1 is flipped by the
 * bit of the node of digits 1..l. */
static inline uint32_t scramble2(uint32_t p, int d, const uint64_t *flips)
{
    uint32_t node = 1, out = 0;
    for (int l = d - 1; l >= 0; l--) {
        uint32_t digit = (p >> l) & 1u;
        out = (out << 1) | (digit ^ (uint32_t)((flips[node >> 6] >> (node & 63)) & 1u));
        node = (node << 1) | digit;
    }
    return out;
}

/* Owen-scramble d ternary digits: each node's permutation of {0, 1, 2} is
 * one of the six, picked by a hash of the node. */
static inline uint32_t scramble3(const uint8_t *digits, int d, uint64_t key)
{
    static const uint8_t perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                       {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    uint64_t node = 1;
    uint32_t out = 0;
    for (int l = 0; l < d; l++) {
        const uint8_t *pi = perm[aa_hash64(key + node * GOLDEN) % 6];
        out = out * 3 + pi[digits[l]];
        node = node * 3 + digits[l];
    }
    return out;
}

/* The pixel's scrambled copy of the point set into sc->u, sc->v, in [0,1)^2
 * (positions() scales them to the window). */
static void scramble_points(const jt_state *S, const jt_scratch *sc, aa_rng *rng)
{
    const jt_points *q = &S->pts;
    uint64_t kx = aa_rng_next(rng), ky = aa_rng_next(rng), kt = aa_rng_next(rng);
    uint64_t *fx = sc->flips, *fy = sc->flips + S->nflips;
    double sx = ldexp(1.0, -q->d2), sy = q->d3 ? 1.0 / pow(3.0, q->d3) : sx;
    fill_flips(fx, S->nflips, kx);
    if (!q->d3)
        fill_flips(fy, S->nflips, ky);
    for (int s = 0; s < q->n; s++) {
        /* below the walked digits every point has a node of its own: its
         * remaining digits are independent uniform, 32 bits per axis */
        uint64_t tail = aa_hash64(kt + (uint64_t)(s + 1) * GOLDEN);
        uint32_t y = q->d3 ? scramble3(q->dig3 + (size_t)s * q->d3, q->d3, ky)
                           : scramble2(q->py[s], q->d2, fy);
        sc->u[s] = (scramble2(q->px[s], q->d2, fx) + unit32((uint32_t)(tail >> 32))) * sx;
        sc->v[s] = (y + unit32((uint32_t)tail)) * sy;
    }
}

/* The stratified grid's cells for support radius r: cell (a, b) of side
 * span/k starts at (a, b) span/k; a sample is its corner plus 2^-33 of a
 * cell plus 32 random bits times cell_scale (span/k 2^-32), the point
 * (a + (m + 1/2) 2^-32)/k of the unit square scaled to the window with one
 * multiply-add per coordinate.  It stays inside its cell: the largest
 * offset, (2^32 - 1/2) 2^-32 of a cell, is below a cell by 2^-33 of one,
 * far above the rounding of the sum. */
static void cells_make(jt_state *S, double r)
{
    double span = 2.0 * r, side = span / S->k;
    for (int b = 0, n = 0; b < S->k; b++)
        for (int a = 0; a < S->k; a++, n++) {
            S->cell[2 * n] = (a + 0x1.0p-33) * side;
            S->cell[2 * n + 1] = (b + 0x1.0p-33) * side;
        }
    S->cell_scale = side * 0x1.0p-32;
    S->cell_r = r;
}

/* Sample n of a stratified pixel from its random number: offsets in pixels
 * from the window's corner. */
static inline void cell_point(const jt_state *S, int n, uint64_t r, double *dx, double *dy)
{
    *dx = S->cell[2 * n] + (double)(uint32_t)(r >> 32) * S->cell_scale;
    *dy = S->cell[2 * n + 1] + (double)(uint32_t)r * S->cell_scale;
}

/* Blue noise: the Sobol points moved by the pixel's shift modulo 1 (a
 * Cranley-Patterson rotation), the shift in x and in y the ranks of two
 * void-and-cluster masks at the pixel, (rank + 1/2)/side^2, the masks
 * tiled over the image from an origin moved per frame (by a hash of the
 * seed and the frame; none at frame 0). */
static void bluenoise_points(const jt_state *S, const jt_scratch *sc, uint64_t seed,
                             uint64_t frame, int i, int j)
{
    const int side = AA__BLUENOISE_SIDE;
    const double n = (double)side * side;
    uint64_t o = frame ? aa_hash64(seed ^ aa_hash64(frame)) : 0;
    const size_t x = (size_t)(((uint64_t)i + (o & 0xffff)) % side),
                 y = (size_t)(((uint64_t)j + ((o >> 16) & 0xffff)) % side);
    const size_t q = y * side + x;
    const double sx = (S->mask[q] + 0.5) / n, sy = (S->mask[q + (size_t)side * side] + 0.5) / n;
    for (int k = 0; k < S->spp; k++) {
        double u = S->bx[k] + sx, v = S->by[k] + sy;
        sc->u[k] = u >= 1.0 ? u - 1.0 : u;
        sc->v[k] = v >= 1.0 ? v - 1.0 : v;
    }
}

/* The pixel's points into sc->u, sc->v, in pixels from the window's corner
 * (span = 2r); pixel (i, j) of frame `frame`. */
static void positions(const jt_state *S, const jt_scratch *sc, aa_rng *rng, double span,
                      uint64_t seed, uint64_t frame, int i, int j)
{
    if (S->seq == SEQ_STRATIFIED) {
        for (int n = 0; n < S->spp; n++)
            cell_point(S, n, aa_rng_next(rng), &sc->u[n], &sc->v[n]);
        return;
    }
    if (S->seq == SEQ_BLUENOISE) {
        bluenoise_points(S, sc, seed, frame, i, j);
    } else if (S->seq >= SEQ_SOBOL) {
        scramble_points(S, sc, rng);
    } else {
        for (int n = 0; n < S->spp; n++) {
            uint64_t r = aa_rng_next(rng);
            sc->u[n] = unit32((uint32_t)(r >> 32));
            sc->v[n] = unit32((uint32_t)r);
        }
    }
    for (int n = 0; n < S->spp; n++)
        sc->u[n] *= span, sc->v[n] *= span;
}

/* ---- sampling a pixel ---- */

/* What the pixels of a row read. */
typedef struct jt_row {
    const jt_state *S;
    const aa_job *job;
    uint64_t frame; /* of the random streams: aa_frame_index(t) */
    double r;       /* support radius */
    jt_scratch sc;  /* the worker's, set per row */
} jt_row;

typedef struct jt_pixel {
    double cx, cy, r; /* centre and support radius */
    uint64_t index;   /* j W + i */
} jt_pixel;

static inline double weight(const aa_filter *f, int box, const jt_pixel *pix, double dx,
                            double dy)
{
    return box ? 1.0 : aa_filter_weight2(f, dx - pix->r, dy - pix->r);
}

/* A pixel in a band no piece ends in (aa_strip_all_full) with few local
 * pieces: the colour
 * of a sample is that of the subset of local pieces left of it (bit q for
 * pcs[q]), so samples are only sorted into subsets, their weights summed
 * per subset, and the subsets' colours found once.  The roots come first,
 * in a loop of their own, so that the sums after them run without calls
 * and without branches (which side of an edge a sample falls is a coin
 * toss to the branch predictor). */
static void shade_simple(const jt_row *R, aa__sampler_worker *wk, const jt_pixel *pix,
                         const aa_piece *const *pcs, int np, double *px)
{
    const aa_filter *f = &R->job->filter;
    const int spp = R->S->spp;
    const double *u = R->sc.u, *v = R->sc.v;
    double x0 = pix->cx - pix->r, y0 = pix->cy - pix->r;
    unsigned char *sub = R->sc.sub;
    memset(sub, 0, (size_t)spp);
    for (int q = 0; q < np; q++) {
        const aa_piece *p = pcs[q];
        if (p->ay == 0.0 && p->by > 0.0 &&
            (p->kind == AA_PIECE_LINE || p->kind == AA_PIECE_QUAD)) {
            /* a line, or an arc whose y is linear in t (crow's): with
             * t = d/by (d = y - y0) the power basis of aabench.h is
             * x = x0 + d (bx/by + d ax/by^2), no division per sample.  It
             * may differ from aa_piece_x_at in the last bits, which only
             * decides samples within rounding of the edge
             * (patterns/README.md, "Boundaries": on the edge, either side).
             * Measured: a fifth of the time of jitter spp=16 on crow. */
            double b = p->bx / p->by, c = p->ax / (p->by * p->by);
            for (int n = 0; n < spp; n++) {
                double x = x0 + u[n], d = y0 + v[n] - p->y0;
                sub[n] |= (unsigned char)((p->x0 + d * (b + d * c) < x) << q);
            }
        } else {
            for (int n = 0; n < spp; n++) {
                double x = x0 + u[n], y = y0 + v[n];
                sub[n] |= (unsigned char)((aa_piece_x_at(p, y) < x) << q);
            }
        }
    }
    double wsum[1 << AA__SAMPLER_SUBSET_MAX] = {0};
    if (aa_filter_is_box(f) && np <= 1) {
        int right = 0; /* equal weights: count */
        for (int n = 0; n < spp; n++)
            right += sub[n];
        wsum[0] = spp - right, wsum[1] = right;
    } else {
        double total = 0.0;
        for (int n = 0; n < spp; n++) {
            double w = weight(f, aa_filter_is_box(f), pix, u[n], v[n]);
            wsum[sub[n]] += w;
            total += w;
        }
        /* every sample outside the cone's disc: the samples' plain mean */
        if (!(total > 0.0))
            for (int n = 0; n < spp; n++)
                wsum[sub[n]] += 1.0;
    }
    aa__sampler_by_subsets(wk, R->job->placed, pix->cy, pcs, np, wsum, px);
}

/* Any pixel: every sample's colour from the strip. */
static void shade_general(const jt_row *R, aa__sampler_worker *wk, const jt_pixel *pix,
                          const aa_piece *const *loc, size_t nloc, double *px)
{
    const aa_filter *f = &R->job->filter;
    int box = aa_filter_is_box(f);
    double x0 = pix->cx - pix->r, y0 = pix->cy - pix->r;
    double a0 = 0, a1 = 0, a2 = 0, total = 0, m0 = 0, m1 = 0, m2 = 0;
    aa_rgb first = {{0, 0, 0}};
    int uniform = 1;
    for (int n = 0; n < R->S->spp; n++) {
        double dx = R->sc.u[n], dy = R->sc.v[n];
        aa_rgb c = aa__sampler_colour_at(wk, R->job->placed, loc, nloc, x0 + dx, y0 + dy);
        double w = weight(f, box, pix, dx, dy);
        if (n == 0)
            first = c;
        uniform = uniform && aa__sampler_same_rgb(c, first);
        a0 += w * c.c[0], a1 += w * c.c[1], a2 += w * c.c[2];
        m0 += c.c[0], m1 += c.c[1], m2 += c.c[2];
        total += w;
    }
    if (!(total > 0.0)) /* every sample outside the cone's disc: their plain mean */
        a0 = m0, a1 = m1, a2 = m2, total = R->S->spp;
    const double acc[3] = {a0, a1, a2};
    for (int ch = 0; ch < 3; ch++)
        px[ch] = uniform ? first.c[ch] : acc[ch] / total;
}

/* The by-subset path of the default, stratified samples under the box
 * filter, where all a pixel needs is how many samples fall in each subset
 * of local pieces: each sample is made and placed in one pass, without
 * storing it (the same points as positions() makes), and counted.  Pieces
 * whose y is linear in t (lines, crow's arcs) are tested in the power
 * basis as in shade_simple; others through aa_piece_x_at. */
static void shade_stratified_box(const jt_row *R, aa__sampler_worker *wk,
                                 const jt_pixel *pix, const aa_piece *const *pcs, int np,
                                 aa_rng *rng, double *px)
{
    const jt_state *S = R->S;
    const int spp = S->spp;
    double x0 = pix->cx - pix->r, y0 = pix->cy - pix->r;
    double ex[AA__SAMPLER_SUBSET_MAX], ey[AA__SAMPLER_SUBSET_MAX], eb[AA__SAMPLER_SUBSET_MAX],
        ec[AA__SAMPLER_SUBSET_MAX];
    int general = 0;
    for (int q = 0; q < np; q++) {
        const aa_piece *p = pcs[q];
        if (p->ay == 0.0 && p->by > 0.0 &&
            (p->kind == AA_PIECE_LINE || p->kind == AA_PIECE_QUAD)) {
            /* x = x0 + d (b + d c) with d measured from the window's corner */
            ex[q] = p->x0 - x0, ey[q] = p->y0 - y0;
            eb[q] = p->bx / p->by, ec[q] = p->ax / (p->by * p->by);
        } else {
            general = 1;
        }
    }
    int cnt[1 << AA__SAMPLER_SUBSET_MAX] = {0};
    if (general) {
        for (int n = 0; n < spp; n++) {
            double dx, dy;
            cell_point(S, n, aa_rng_next(rng), &dx, &dy);
            unsigned m = 0;
            for (int q = 0; q < np; q++)
                m |= (unsigned)(aa_piece_x_at(pcs[q], y0 + dy) < x0 + dx) << q;
            cnt[m]++;
        }
    } else if (np == 1) {
        for (int n = 0; n < spp; n++) {
            double dx, dy;
            cell_point(S, n, aa_rng_next(rng), &dx, &dy);
            double d = dy - ey[0];
            cnt[1] += ex[0] + d * (eb[0] + d * ec[0]) < dx;
        }
        cnt[0] = spp - cnt[1];
    } else {
        for (int n = 0; n < spp; n++) {
            double dx, dy;
            cell_point(S, n, aa_rng_next(rng), &dx, &dy);
            unsigned m = 0;
            for (int q = 0; q < np; q++) {
                double d = dy - ey[q];
                m |= (unsigned)(ex[q] + d * (eb[q] + d * ec[q]) < dx) << q;
            }
            cnt[m]++;
        }
    }
    double wsum[1 << AA__SAMPLER_SUBSET_MAX];
    for (int m = 0; m < 1 << np; m++)
        wsum[m] = cnt[m];
    aa__sampler_by_subsets(wk, R->job->placed, pix->cy, pcs, np, wsum, px);
}

/* Pixel (i, j), whose support holds local pieces (aa__sampler_shade_fn). */
static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const jt_row *R = ctx;
    const jt_pixel pix = {i + 0.5, j + 0.5, R->r,
                          (uint64_t)j * (uint64_t)R->job->w + (uint64_t)i};
    aa_rng rng;
    aa_rng_seed(&rng, R->job->seed, pix.index, R->frame);
    const aa_piece *const *loc, *pcs[AA__SAMPLER_SUBSET_MAX];
    size_t nloc;
    int np = aa__sampler_subsets(wk, &loc, &nloc, pcs);
    if (np >= 0 && R->S->seq == SEQ_STRATIFIED && aa_filter_is_box(&R->job->filter)) {
        shade_stratified_box(R, wk, &pix, pcs, np, &rng, px);
        return;
    }
    positions(R->S, &R->sc, &rng, 2.0 * pix.r, R->job->seed, R->frame, i, j);
    if (np >= 0)
        shade_simple(R, wk, &pix, pcs, np, px);
    else
        shade_general(R, wk, &pix, loc, nloc, px);
}

/* One row of pixels (aa__sampler_row_fn), with the worker's scratch. */
static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    jt_row R = *(const jt_row *)ctx;
    R.sc = scratch_of(R.S, wk);
    return aa__sampler_row(wk, j, R.r, (uint64_t)R.S->spp, shade, &R, out, samples, expensive);
}

/* ---- the method ---- */

static int prepare(jt_state *S, const aa_job *job)
{
    size_t o_flips, o_sub;
    return aa__sampler_ready(&S->sampler, job, scratch_layout(S, &o_flips, &o_sub));
}

/* Blue noise: the first spp points of the Sobol sequence (as seq=sobol's,
 * unscrambled) and two masks, of seeds made from the job's. */
static int bluenoise_make(jt_state *S, uint64_t seed)
{
    const size_t n = (size_t)AA__BLUENOISE_SIDE * AA__BLUENOISE_SIDE;
    if (!S->bx) {
        S->bx = malloc(2 * (size_t)S->spp * sizeof *S->bx);
        S->mask = malloc(2 * n * sizeof *S->mask);
        if (!S->bx || !S->mask)
            return aa_fail(AA_ENOMEM, "out of memory for blue-noise masks");
        S->by = S->bx + S->spp;
        int st = points_fetch(SEQ_SOBOL, S->spp, S->bx, S->by);
        if (st)
            return st;
    } else if (S->mask_seed == seed) {
        return AA_OK;
    }
    for (int a = 0; a < 2; a++) {
        int st = aa__bluenoise_mask(AA__BLUENOISE_SIDE, AA__BLUENOISE_SIGMA,
                                    aa_hash64(seed * 2 + (uint64_t)a + 1), S->mask + a * n);
        if (st)
            return st;
    }
    S->mask_seed = seed;
    return AA_OK;
}

static int jitter_init(void *state, const double *p, const aa_job *job)
{
    jt_state *S = state;
    S->seq = (int)p[P_SEQ];
    S->spp = (int)p[P_SPP];
    S->k = square_side(S->spp);
    if (S->seq == SEQ_STRATIFIED) {
        if (!(S->cell = malloc(2 * (size_t)S->spp * sizeof *S->cell)))
            return aa_fail(AA_ENOMEM, "out of memory for %d cells", S->spp);
        cells_make(S, aa_filter_support(&job->filter));
    }
    if (S->seq == SEQ_BLUENOISE) {
        int st = bluenoise_make(S, job->seed);
        if (st)
            return st;
    } else if (S->seq >= SEQ_SOBOL) {
        int st = points_make(&S->pts, S->seq, S->spp);
        if (st)
            return st;
        S->nflips = ((size_t)1 << S->pts.d2) / 64 + 1;
    }
    return prepare(S, job);
}

static int jitter_render(void *state, const double *p, const aa_job *job, aa_image *out,
                         aa_counters *counters)
{
    jt_state *S = state;
    (void)p; /* init read spp and seq into S */
    int st = prepare(S, job);
    if (st)
        return st;
    if (S->cell && S->cell_r != aa_filter_support(&job->filter))
        cells_make(S, aa_filter_support(&job->filter));
    if (S->seq == SEQ_BLUENOISE && (st = bluenoise_make(S, job->seed)))
        return st;
    const jt_row R = {S, job, aa_frame_index(job->t), aa_filter_support(&job->filter), {0}};
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void jitter_release(void *state)
{
    jt_state *S = state;
    aa__sampler_free(&S->sampler);
    points_free(&S->pts);
    free(S->cell);
    S->cell = NULL;
    free(S->bx);
    free(S->mask);
    S->bx = S->by = NULL;
    S->mask = NULL;
}

const aa_method_type aa_method_jitter = {
    {"jitter", "spp stratified, random or Owen-scrambled quasi-random samples per pixel",
     jitter_params},
    sizeof(jt_state),
    AA_METHOD_SEEDED | AA_METHOD_FIELDS | AA_METHOD_GRADIENTS,
    jitter_check,
    jitter_init,
    jitter_render,
    jitter_release};
