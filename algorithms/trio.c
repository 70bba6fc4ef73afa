/*
 * trio.c: smoothing the completed point-sampled image (Crow 1976, ch. 4,
 * "Processing the completed image", figs. 4.2 and 4.3).  The image is
 * point sampled at pixel centres (aa_point_sample, as `point`), then one of
 * the three post-processes Crow describes is applied (`variant`), or a
 * variant of the first:
 *
 * trio (default): Lance Williams' edge smoothing by trio detection.
 *   Crow: "searching for places where the edge moves from one dot row to the
 *   next.  Wherever this occurs three edge dots taken in order form a right
 *   angled path.  Tracing along the edge, the middle dot of each trio is
 *   noted.  Subsequent trios are formed by starting at the last dot in the
 *   current trio [fig. 4.2].  When two trios have been found, a line is
 *   constructed between their mid dots.  The position of this line as it
 *   passes between two dots is used to determine the shade of the dot which
 *   lies on the intensity discontinuity [fig. 4.3: the dot X receives 3/4
 *   of the outside intensity and 1/4 of the inside]."  Here, step by step:
 *
 *   1. Discontinuities.  Two neighbours (horizontal or vertical) are on a
 *      discontinuity when some channel differs by more than `threshold`
 *      (the largest channel difference, so an edge between two colours of
 *      equal luma is still found; 1/8 by default, near SMAA's 0.1 on luma:
 *      the point-sampled image has only the scene's flat colours, so any
 *      value below their smallest contrast finds every edge).  Each
 *      discontinuity is a unit segment of the boundary between the dots.
 *   2. Runs.  Along each boundary line between two dot rows, the segments
 *      form runs: stretches where the edge stays between the same two rows.
 *   3. Trios.  At an end of a run the edge may move to the next dot row:
 *      one vertical unit step, after which it runs on along the adjacent
 *      boundary line in the same direction.  There the edge dots form
 *      Williams' right-angled path of three (the last dot of the run, the
 *      corner dot, the first dot of the next run) and the corner is its
 *      middle dot; the next trio starts where this one ends, at the far end
 *      of the next run.  A step is accepted only when the boundary is a
 *      simple path there: nothing else meets the two corners of the step
 *      (no junction of three colours, no checkerboard saddle, no second
 *      step), the step is one dot long, and the edge goes on in the same
 *      direction.  Otherwise the end is open: a corner of a shape, the end
 *      of an edge, the image border.
 *   4. Lines.  Two consecutive trios bound a run, and "a line is
 *      constructed between their mid dots": a straight line from one end of
 *      the run to the other, whatever the two steps do.  Each mid dot is
 *      taken at the middle of its step, the corner dot moved half a dot
 *      onto the discontinuity it marks: the line through the corner dots'
 *      own centres lies half a dot off the edge, on the side they were
 *      traced on, and cannot give fig. 4.3's shares (a run of two dots,
 *      slope 1/2: it gives its mid dot 1/2 and the dots beside it 1/16),
 *      where the middles of the steps give exactly 3/4 and 1/4 (step 5).
 *      For a run that takes the edge from one row to the next (a Z: the
 *      steps go opposite ways across the run's line) the line crosses the
 *      boundary at the middle of the run.  For a run whose two steps go the
 *      same way (a U: a bump one row high, at a turning point of a curve)
 *      the line runs half a dot beyond the boundary, along the whole run,
 *      through the middles of the bump's dots.  A run with an open end is
 *      between fewer than two trios and gets no line: it stays as sampled.
 *   5. Shades.  Where the line passes beyond the boundary into a dot, the
 *      dot takes the colour across the boundary in proportion to the part
 *      of the dot's square on the other side of the line (the exact area
 *      under the line inside the column, in the dot's own colour and its
 *      neighbour's).  A run of two dots gives fig. 4.3's answer: each dot
 *      beside the step keeps 3/4 of its own colour and takes 1/4 of the
 *      other side's.  A run one dot long between two trios (the edge at 45
 *      degrees) gives the dots on either side an eighth each, the area of
 *      the 45-degree line through the steps' middles; a U gives each dot of
 *      the bump half of the colour around it.
 *   6. Both directions.  Crow speaks of dot rows; the same is done on the
 *      boundary lines between dot columns, so mostly-vertical edges, whose
 *      steps along rows are longer than one dot and so form no trios, are
 *      smoothed too.  A run along a column one dot long is not drawn: it is
 *      the unit step of row runs one dot long, whose line (the same line)
 *      the rows have drawn, and drawing it twice would count its area
 *      twice.  A dot beside several discontinuities sums their shares
 *      (scaled down if they exceed 1), every share taken from the sampled
 *      image, so the result does not depend on the order of work.
 *   Colour: detection on the largest channel difference; the shares are
 *   applied to all three channels alike.
 *
 * halflines (a variant, the default of earlier versions): steps 1 to 3 and
 *   5 as above, with lines after MLAA (Reshetov 2009) rather than Crow's:
 *   each run is shaded by two half-lines, from the middle of the step at
 *   each end that is a trio to the point of the boundary at the run's
 *   middle, so a Z gets Crow's line, a U two half-lines meeting on the
 *   boundary (a triangle, not a band), a run with one trio the half-line
 *   at that end, and a run one dot long, along rows or columns, nothing (a
 *   45-degree staircase stays as sampled).  It is kept because it is the
 *   better of the two on curved scenes (below): the turning points of
 *   crow's arcs are U runs, where Crow's band halves dots the arc barely
 *   enters.
 *
 * sancha: T. L. Sancha's neighbour compromise.  "Whenever the intensity of
 *   neighboring dots differs by more than a preset amount, one of them is
 *   changed to a compromise intensity ... It must always be the upper-left
 *   dot".  Each dot is compared with its right and lower neighbours (the
 *   pairs in which it is the upper-left dot); if one or both differ by more
 *   than `threshold` (largest channel difference), the dot becomes the mean
 *   of itself and those neighbours.  The comparisons use the sampled image,
 *   as a raster scan would (the right and lower dots are not yet changed).
 *
 * recursive: "The intensity at each dot is computed as a weighted average
 *   of the intensities of the dot itself, the dot to the left and the dot
 *   above": y(i,j) = x(i,j) + w (y(i-1,j) - x(i,j)) + w (y(i,j-1) - x(i,j)),
 *   recursive in that the left and upper values are already filtered
 *   outputs.  `weight` w = 1/4 by default: the dot keeps half, its two
 *   neighbours share the other half (the text gives no weights; on crow
 *   256x256 the RMSE against the box reference is 0.149 at w = 0.1, 0.145
 *   at 0.15, 0.170 at 1/4, 0.281 at 0.4, point sampling 0.180).  A missing
 *   neighbour at the image border counts as the dot itself.  The result is
 *   clamped to the range of the three values, so rounding cannot leave it
 *   and a flat image stays exactly flat.  It works in place on the samples.
 *   Each output depends on the one to its left and the one above, so it
 *   cannot be shared out by rows; instead rows are pipelined across
 *   threads (a wavefront): row j goes through its columns in chunks of
 *   CHUNK, each once row j-1 has finished that chunk, and the rows are
 *   dealt round-robin.  The arithmetic is the same whatever the threads.
 *
 * Counters: samples = pixels (one point sample each).  expensive_pixels:
 * trio and halflines, the pixels beside at least one discontinuity (those whose shares
 * are gathered rather than copied; not all of them change); sancha, the
 * pixels it changed; recursive, every pixel (each one is filtered).
 *
 * Memory (made in init): trio and halflines keep the samples, a mask byte and four
 * shares per dot (57 bytes a pixel); sancha the samples; recursive a
 * progress counter per row.
 *
 * Limits.  These are post-processes of a point-sampled image: what the
 * sampling lost (thin objects between dots, moire from detail finer than a
 * dot) cannot be restored, and small objects may be shrunk or smeared.
 * trio: the edge's position inside a dot is unknown, so the line goes
 * through the middle of each step and can be off by up to half a dot; a
 * straight edge is recovered well only when its runs are long (nearly
 * horizontal or vertical); a 45-degree staircase gets an eighth a dot
 * whatever the edge's true position within the dots; a U run is taken for
 * a band half a dot wide; junctions, saddles, lines one dot thick turning
 * back, and runs ending at corners and at the image border are left as
 * sampled; the shares assume each discontinuity separates two flat
 * colours, so edges on shaded surfaces or textures blend with the wrong
 * colours; the whole image is re-examined each frame, so in animation the
 * smoothing moves with the staircase.  RMSE against the box reference at
 * 256x256 (aabench run, box): crow, trio 0.1228, halflines 0.0916, point
 * 0.1796; star, trio 0.0579, halflines 0.0556, point 0.1046.  Taken one at
 * a time (the three ways the variants differ): drawing U runs as Crow's
 * band rather than two half-lines costs most on crow (0.0961 with
 * half-lines there, all else Crow's); leaving runs with one trio
 * unshaded costs a little (0.1193 on crow, 0.0513 on star with
 * half-lines at such ends); drawing the 45-degree runs along rows helps
 * star (0.0627 without them) and does not change crow.  sancha blurs every
 * high-contrast edge, correct or not, and always on its upper-left side,
 * which moves edges up and left by about a quarter dot: RMSE 0.254, worse
 * than point.  recursive blurs everything and, being one-sided, shifts the
 * image right and down by w/(1 - 2w) dots (half a dot for w = 1/4); Crow
 * found it "unencouraging".  None has a prefilter: all are measured
 * against the box reference and refuse tent and gauss.
 */
#include "methods.h"

#include <math.h>
#include <sched.h>
#include <stdalign.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

enum { P_VARIANT, P_THRESHOLD, P_WEIGHT };
enum { V_TRIO, V_SANCHA, V_RECURSIVE, V_HALFLINES };

static const aa_param trio_params[] = {
    {"variant", AA_PARAM_CHOICE, V_TRIO, 0, 0, 0, "trio|sancha|recursive|halflines",
     "Williams' trio smoothing, Sancha's compromise, the recursive filter, or trios with "
     "MLAA's half-lines"},
    {"threshold", AA_PARAM_REAL, 0.125, 0.0, 1.0, 0, NULL,
     "trio, halflines and sancha: a larger channel difference is a discontinuity (1: none)"},
    {"weight", AA_PARAM_REAL, 0.25, 0.0, 0.5, 0, NULL,
     "recursive: weight of the left and of the upper dot (the dot keeps 1 - 2 weight)"},
    {0}};

#define SEG_H 1u /* discontinuity between (i, j) and (i, j+1) */
#define SEG_V 2u /* discontinuity between (i, j) and (i+1, j) */
#define CHUNK 128 /* recursive: columns per pipeline step */

/* A row's progress in the recursive pipeline, alone on its cache line. */
typedef struct progress {
    alignas(64) atomic_int done; /* chunks finished */
} progress;

typedef struct trio_state {
    int w, h, variant;
    int ready;            /* buffers made for w x h */
    double *img;          /* trio, sancha: the point-sampled image */
    unsigned char *mask;  /* trio: SEG_H | SEG_V per dot */
    double *hw, *vw;      /* trio: two shares per segment (near dot, far dot) */
    progress *rows;       /* recursive */
} trio_state;

static int trio_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "trio post-processes point samples and has no prefilter; "
                                  "it is measured against the box reference (use -f box)");
    return AA_OK;
}

static void trio_release(void *state)
{
    trio_state *s = state;
    free(s->img);
    free(s->mask);
    free(s->hw);
    free(s->vw);
    free(s->rows);
    memset(s, 0, sizeof *s);
}

static int prepare(trio_state *s, const double *p, const aa_job *job)
{
    trio_release(s);
    size_t n = (size_t)job->w * (size_t)job->h;
    s->w = job->w, s->h = job->h, s->variant = (int)p[P_VARIANT];
    int ok = 1;
    if (s->variant != V_RECURSIVE)
        ok = (s->img = malloc(n * 3 * sizeof *s->img)) != NULL;
    if (ok && (s->variant == V_TRIO || s->variant == V_HALFLINES))
        ok = (s->mask = malloc(n)) && (s->hw = malloc(n * 2 * sizeof *s->hw)) &&
             (s->vw = malloc(n * 2 * sizeof *s->vw));
    if (s->variant == V_RECURSIVE)
        ok = (s->rows = aligned_alloc(alignof(progress), (size_t)job->h * sizeof *s->rows)) !=
             NULL;
    if (!ok) {
        trio_release(s);
        return aa_fail(AA_ENOMEM, "out of memory for the %dx%d post-process buffers", job->w,
                       job->h);
    }
    /* touch everything once here, so page faults are not timed */
    if (s->img)
        memset(s->img, 0, n * 3 * sizeof *s->img);
    if (s->variant == V_TRIO || s->variant == V_HALFLINES) {
        memset(s->mask, 0, n);
        memset(s->hw, 0, n * 2 * sizeof *s->hw);
        memset(s->vw, 0, n * 2 * sizeof *s->vw);
    }
    s->ready = 1;
    return AA_OK;
}

static int trio_init(void *state, const double *p, const aa_job *job)
{
    return prepare(state, p, job);
}

/* Largest channel difference above the threshold? */
static inline int differ(const double *a, const double *b, double threshold)
{
    double d = fabs(a[0] - b[0]), e = fabs(a[1] - b[1]), f = fabs(a[2] - b[2]);
    d = d > e ? d : e;
    return (d > f ? d : f) > threshold;
}

/* ---- trio ---- */

/* Eight mask bytes as one word (memcpy: no alignment or aliasing issue). */
static inline uint64_t load8(const unsigned char *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
    return v;
}

typedef struct grid {
    const unsigned char *mask;
    int w, h;
    int halflines; /* variant=halflines: MLAA's half-lines (see the header) */
} grid;

static inline int seg_h(const grid *g, int i, int j)
{
    return i >= 0 && i < g->w && j >= 0 && j < g->h &&
           (g->mask[(size_t)j * (size_t)g->w + (size_t)i] & SEG_H);
}

static inline int seg_v(const grid *g, int i, int j)
{
    return i >= 0 && i < g->w && j >= 0 && j < g->h &&
           (g->mask[(size_t)j * (size_t)g->w + (size_t)i] & SEG_V);
}

/* Boundary lines in either direction.  A line l lies between dot rows l and
 * l+1 (tr = 0) or dot columns l and l+1 (tr = 1); u is the position along
 * it.  run(u, l): the segment of line l beside position u.  step(u, l): the
 * perpendicular segment between positions u and u+1, beside dot l. */
static inline int run(const grid *g, int tr, int u, int l)
{
    return tr ? seg_v(g, l, u) : seg_h(g, u, l);
}

static inline int step(const grid *g, int tr, int u, int l)
{
    return tr ? seg_h(g, l, u) : seg_v(g, u, l);
}

/* The end of a run of line l: the step lies between positions s and s+1,
 * `beyond` is the position past the run and `last` the run's end position.
 * Returns the middle of the step as an offset across the line: -1/2 (the
 * edge moves to line l-1), +1/2 (to line l+1), or 0 when the end is not a
 * trio (see the header: one unit step, simple corners, same direction). */
static double trio_end(const grid *g, int tr, int l, int s, int beyond, int last)
{
    if (step(g, tr, s, l) && !step(g, tr, s, l + 1) && run(g, tr, beyond, l - 1) &&
        !run(g, tr, last, l - 1) && !step(g, tr, s, l - 1))
        return -0.5;
    if (step(g, tr, s, l + 1) && !step(g, tr, s, l) && run(g, tr, beyond, l + 1) &&
        !run(g, tr, last, l + 1) && !step(g, tr, s, l + 2))
        return 0.5;
    return 0.0;
}

/* Integral over the column [u, u+1] of the half-line that is linear from
 * d0 at x = lo to d1 at x = hi (zero outside [lo, hi]). */
static double under(double u, double lo, double hi, double d0, double d1)
{
    double x0 = u > lo ? u : lo, x1 = u + 1 < hi ? u + 1 : hi;
    if (!(x1 > x0))
        return 0.0;
    double f0 = d0 + (d1 - d0) * ((x0 - lo) / (hi - lo));
    double f1 = d0 + (d1 - d0) * ((x1 - lo) / (hi - lo));
    return (x1 - x0) * 0.5 * (f0 + f1);
}

/* Shares of the dots beside run [a, b] of line l, given the offsets of the
 * steps at its ends (0: open).  Positive offsets lie on the far side: the
 * far dot takes that much of the near dot's colour, and the other way. */
static void shade_run(const grid *g, int tr, int l, int a, int b, double dl, double dr,
                      double *hw, double *vw)
{
    const double c = 0.5 * ((double)a + (double)b + 1.0);
    for (int u = a; u <= b; u++) {
        double *share = tr ? vw + 2 * ((size_t)u * (size_t)g->w + (size_t)l)
                           : hw + 2 * ((size_t)l * (size_t)g->w + (size_t)u);
        double near = 0.0, far = 0.0;
        double left = dl != 0.0 ? under(u, a, c, dl, 0.0) : 0.0;
        double right = dr != 0.0 ? under(u, c, b + 1.0, 0.0, dr) : 0.0;
        if (left > 0)
            far += left;
        else
            near -= left;
        if (right > 0)
            far += right;
        else
            near -= right;
        share[0] = near, share[1] = far;
    }
}

/* The integrals over a unit column of the positive and the negative parts
 * of the linear function from f0 to f1. */
static void parts(double f0, double f1, double *pos, double *neg)
{
    if (f0 >= 0 && f1 >= 0)
        *pos = 0.5 * (f0 + f1), *neg = 0.0;
    else if (f0 <= 0 && f1 <= 0)
        *pos = 0.0, *neg = -0.5 * (f0 + f1);
    else {
        double t = f0 / (f0 - f1); /* where it crosses zero */
        double a = 0.5 * f0 * t, b = 0.5 * f1 * (1.0 - t);
        *pos = f0 > 0 ? a : b, *neg = f0 > 0 ? -b : -a;
    }
}

/* Crow's line between the mid dots of the trios at the two ends of run
 * [a, b] of line l: the straight line from offset dl at the run's left end
 * (position a) to dr at its right end (b + 1).  In each column the part of
 * the line beyond the boundary on the far side is the far dot's share of
 * the near dot's colour, the part on the near side the near dot's share of
 * the far dot's. */
static void shade_line(const grid *g, int tr, int l, int a, int b, double dl, double dr,
                       double *hw, double *vw)
{
    const double len = (double)b + 1.0 - (double)a;
    for (int u = a; u <= b; u++) {
        double *share = tr ? vw + 2 * ((size_t)u * (size_t)g->w + (size_t)l)
                           : hw + 2 * ((size_t)l * (size_t)g->w + (size_t)u);
        double f0 = dl + (dr - dl) * ((double)(u - a) / len);
        double f1 = dl + (dr - dl) * ((double)(u + 1 - a) / len);
        double pos, neg;
        parts(f0, f1, &pos, &neg);
        share[0] = neg, share[1] = pos;
    }
}

/* Run [a, b] of line l, found: its ends examined and its dots shaded. */
static void found_run(const grid *g, int tr, int l, int a, int b, double *hw, double *vw)
{
    if (g->halflines) {
        /* a run one dot long is left alone (see the header, halflines) */
        double dl = b > a ? trio_end(g, tr, l, a - 1, a - 1, a) : 0.0;
        double dr = b > a ? trio_end(g, tr, l, b, b + 1, b) : 0.0;
        shade_run(g, tr, l, a, b, dl, dr, hw, vw);
        return;
    }
    /* along columns a run one dot long is the step of the row runs beside
     * it, which have drawn its line already (see the header, step 6) */
    double dl = 0.0, dr = 0.0;
    if (!tr || b > a) {
        dl = trio_end(g, tr, l, a - 1, a - 1, a);
        dr = trio_end(g, tr, l, b, b + 1, b);
    }
    if (dl != 0.0 && dr != 0.0)
        shade_line(g, tr, l, a, b, dl, dr, hw, vw);
    else
        shade_run(g, tr, l, a, b, 0.0, 0.0, hw, vw); /* no line: the shares are zero */
}

/* Every run of the line between dot rows l and l+1, skipping eight
 * positions at a time where there is none. */
static void shade_row_line(const grid *g, int l, double *hw, double *vw)
{
    const unsigned char *m = g->mask + (size_t)l * (size_t)g->w;
    const int n = g->w;
    for (int u = 0; u < n;) {
        if (u + 8 <= n && !(load8(m + u) & (0x0101010101010101ull * SEG_H))) {
            u += 8;
            continue;
        }
        if (!(m[u] & SEG_H)) {
            u++;
            continue;
        }
        int a = u;
        while (u < n && (m[u] & SEG_H))
            u++;
        found_run(g, 0, l, a, u - 1, hw, vw);
    }
}

/* Every run of the lines between dot columns c0 .. c0+63 (and the next),
 * found in one sweep down the rows, so the mask is read row by row; open
 * runs are kept as bits, and eight columns with no V bit and no open run
 * are passed over at once. */
static void shade_column_lines(const grid *g, int c0, double *hw, double *vw)
{
    const int n = g->w - 1 - c0 < 64 ? g->w - 1 - c0 : 64;
    int start[64];
    uint64_t open = 0;
    for (int u = 0; u <= g->h; u++) { /* u = h closes the runs still open */
        const unsigned char *m =
            u < g->h ? g->mask + (size_t)u * (size_t)g->w + (size_t)c0 : NULL;
        for (int k = 0; k < n; k++) {
            if (m && (k & 7) == 0 && k + 8 <= n && !((open >> k) & 0xff) &&
                !(load8(m + k) & (0x0101010101010101ull * SEG_V))) {
                k += 7;
                continue;
            }
            int bit = m && (m[k] & SEG_V);
            if (bit && !((open >> k) & 1)) {
                start[k] = u;
                open |= 1ull << k;
            } else if (!bit && ((open >> k) & 1)) {
                found_run(g, 1, c0 + k, start[k], u - 1, hw, vw);
                open &= ~(1ull << k);
            }
        }
    }
}

/* The new value y of dot (i, j), beside at least one discontinuity, from
 * the sampled image img and the shares of its four sides. */
static void gather(const trio_state *s, const double *img, int i, int j, double *y)
{
    const size_t w = (size_t)s->w, at = (size_t)j * w + (size_t)i;
    const unsigned char *m = s->mask + at;
    const double *x = img + 3 * at;
    double share[4] = {0, 0, 0, 0};
    const double *nb[4] = {x, x, x, x};
    if (m[0] & SEG_H)
        share[0] = s->hw[2 * at], nb[0] = x + 3 * w;
    if (j > 0 && (m[-(ptrdiff_t)w] & SEG_H))
        share[1] = s->hw[2 * (at - w) + 1], nb[1] = x - 3 * w;
    if (m[0] & SEG_V)
        share[2] = s->vw[2 * at], nb[2] = x + 3;
    if (i > 0 && (m[-1] & SEG_V))
        share[3] = s->vw[2 * (at - 1) + 1], nb[3] = x - 3;
    double sum = share[0] + share[1] + share[2] + share[3];
    if (sum == 0.0) {
        y[0] = x[0], y[1] = x[1], y[2] = x[2];
        return;
    }
    double scale = sum > 1.0 ? 1.0 / sum : 1.0;
    for (int ch = 0; ch < 3; ch++) {
        double v = x[ch], lo = v, hi = v;
        for (int k = 0; k < 4; k++) {
            if (share[k] == 0.0)
                continue;
            double n = nb[k][ch];
            v += share[k] * scale * (n - x[ch]);
            lo = n < lo ? n : lo;
            hi = n > hi ? n : hi;
        }
        y[ch] = v < lo ? lo : (v > hi ? hi : v);
    }
}

/* Is dot i of a row beside a discontinuity (its own bits, an H bit in the
 * row above `up`, NULL for the first row, or a V bit on its left)? */
static inline unsigned beside(const unsigned char *m, const unsigned char *up, int i)
{
    return m[i] | (up ? up[i] & SEG_H : 0u) | (i > 0 ? m[i - 1] & SEG_V : 0u);
}

/* Are none of dots i .. i+7 beside a discontinuity? */
static inline int none8(const unsigned char *m, const unsigned char *up, int i)
{
    return !load8(m + i) && !(up && (load8(up + i) & (0x0101010101010101ull * SEG_H))) &&
           !(i > 0 && (m[i - 1] & SEG_V));
}

/* Williams' trios, from the sampled image s->img into out.  (Working in
 * place in out, writing back only the dots beside a discontinuity, was
 * slower on crow: its edges are so dense that the scattered write-back cost
 * more than one streaming copy.) */
static uint64_t trio_smooth(trio_state *s, double threshold, int threads, aa_image *out)
{
    const int w = s->w, h = s->h;
    const grid g = {s->mask, w, h, s->variant == V_HALFLINES};
    const double *img = s->img;
    uint64_t expensive = 0;
#pragma omp parallel num_threads(threads)
    {
#pragma omp for schedule(static)
        for (int j = 0; j < h; j++) {
            const double *a = img + (size_t)j * (size_t)w * 3;
            unsigned char *m = s->mask + (size_t)j * (size_t)w;
            for (int i = 0; i < w; i++, a += 3) {
                unsigned bits = 0;
                if (j + 1 < h && differ(a, a + (size_t)w * 3, threshold))
                    bits |= SEG_H;
                if (i + 1 < w && differ(a, a + 3, threshold))
                    bits |= SEG_V;
                m[i] = (unsigned char)bits;
            }
        }
        /* lines between rows, then between columns; each writes the shares
         * of its own segments only */
#pragma omp for schedule(static)
        for (int l = 0; l < h - 1; l++)
            shade_row_line(&g, l, s->hw, s->vw);
#pragma omp for schedule(static)
        for (int c = 0; c < (w - 1 + 63) / 64; c++)
            shade_column_lines(&g, 64 * c, s->hw, s->vw);
        /* copy each row, then visit the dots beside a discontinuity,
         * passing over eight at a time where none is */
#pragma omp for schedule(static) reduction(+ : expensive)
        for (int j = 0; j < h; j++) {
            const unsigned char *m = s->mask + (size_t)j * (size_t)w;
            const unsigned char *up = j > 0 ? m - w : NULL;
            memcpy(aa_pixel(out, 0, j), img + (size_t)j * (size_t)w * 3,
                   (size_t)w * 3 * sizeof *img);
            for (int i = 0; i < w; i++) {
                if ((i & 7) == 0 && i + 8 <= w && none8(m, up, i)) {
                    i += 7;
                    continue;
                }
                if (beside(m, up, i)) {
                    expensive++;
                    gather(s, img, i, j, aa_pixel(out, i, j));
                }
            }
        }
    }
    return expensive;
}

/* ---- sancha ---- */

static uint64_t sancha(const trio_state *s, double threshold, int threads, aa_image *out)
{
    const int w = s->w, h = s->h;
    uint64_t changed = 0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : changed)
    for (int j = 0; j < h; j++) {
        const double *x = s->img + (size_t)j * (size_t)w * 3;
        double *y = aa_pixel(out, 0, j);
        for (int i = 0; i < w; i++, x += 3, y += 3) {
            const double *r = i + 1 < w && differ(x, x + 3, threshold) ? x + 3 : NULL;
            const double *d = j + 1 < h && differ(x, x + (size_t)w * 3, threshold)
                                  ? x + (size_t)w * 3
                                  : NULL;
            if (!r && !d) {
                y[0] = x[0], y[1] = x[1], y[2] = x[2];
                continue;
            }
            changed++;
            for (int ch = 0; ch < 3; ch++)
                y[ch] = r && d ? (x[ch] + r[ch] + d[ch]) / 3.0
                               : 0.5 * (x[ch] + (r ? r[ch] : d[ch]));
        }
    }
    return changed;
}

/* ---- recursive ---- */

static inline double clamp3(double v, double a, double b, double c)
{
    double lo = a < b ? a : b, hi = a > b ? a : b;
    lo = c < lo ? c : lo;
    hi = c > hi ? c : hi;
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Columns [i0, i1) of row j, in place: each sample is read just before
 * its output replaces it, and the left and upper values read are outputs. */
static void recursive_chunk(double wt, int j, int i0, int i1, aa_image *out)
{
    const ptrdiff_t row = 3 * (ptrdiff_t)out->w;
    double *y = aa_pixel(out, i0, j);
    for (int i = i0; i < i1; i++, y += 3)
        for (int ch = 0; ch < 3; ch++) {
            /* x + w (l - x) + w (u - x), arranged so that only w l and one
             * addition wait for the left output */
            double x = y[ch];
            double u = j > 0 ? y[ch - row] : x;
            double l = i > 0 ? y[ch - 3] : x;
            double base = x - wt * x + wt * (u - x);
            y[ch] = clamp3(base + wt * l, x, u, l);
        }
}

static void wait_for(progress *row, int chunks)
{
    for (unsigned spins = 0;
         atomic_load_explicit(&row->done, memory_order_acquire) < chunks; spins++)
        if ((spins & 1023u) == 1023u)
            sched_yield();
}

static void recursive(trio_state *s, double wt, int threads, aa_image *out)
{
    const int h = s->h, chunks = (s->w + CHUNK - 1) / CHUNK;
    for (int j = 0; j < h; j++)
        atomic_init(&s->rows[j].done, 0);
#pragma omp parallel num_threads(threads)
    {
        int me = 0, team = 1;
#ifdef _OPENMP
        me = omp_get_thread_num(), team = omp_get_num_threads();
#endif
        /* rows dealt round-robin, each thread in increasing order: row j
         * waits only for row j-1, which never waits for a later row */
        for (int j = me; j < h; j += team)
            for (int c = 0; c < chunks; c++) {
                if (j > 0)
                    wait_for(&s->rows[j - 1], c + 1);
                int i1 = (c + 1) * CHUNK < s->w ? (c + 1) * CHUNK : s->w;
                recursive_chunk(wt, j, c * CHUNK, i1, out);
                atomic_store_explicit(&s->rows[j].done, c + 1, memory_order_release);
            }
    }
}

static int trio_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    trio_state *s = state;
    int st;
    if ((!s->ready || s->w != job->w || s->h != job->h) && (st = prepare(s, p, job)))
        return st;
    /* the recursive filter works in place; the others read the samples
     * around each dot they write, so keep them apart */
    aa_image img = {job->w, job->h, 3, s->variant == V_RECURSIVE ? out->v : s->img};
    if ((st = aa_point_sample(job->placed, 0.0, 0.0, job->threads, &img)))
        return st;
    counters->samples = (uint64_t)job->w * (uint64_t)job->h;
    switch (s->variant) {
    case V_SANCHA:
        counters->expensive_pixels = sancha(s, p[P_THRESHOLD], job->threads, out);
        break;
    case V_RECURSIVE:
        recursive(s, p[P_WEIGHT], job->threads, out);
        counters->expensive_pixels = counters->samples;
        break;
    default:
        counters->expensive_pixels = trio_smooth(s, p[P_THRESHOLD], job->threads, out);
        break;
    }
    return AA_OK;
}

const aa_method_type aa_method_trio = {
    {"trio", "point samples smoothed after the fact: Williams' trios, Sancha's compromise "
             "or a recursive filter (Crow figs. 4.2-4.3)",
     trio_params},
    sizeof(trio_state),
    AA_METHOD_FIELDS,
    trio_check,
    trio_init,
    trio_render,
    trio_release};
