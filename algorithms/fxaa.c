/*
 * fxaa.c: FXAA 3.11, its quality version (Lottes 2009/2011, "FXAA",
 * NVIDIA whitepaper, and the FXAA 3.11 quality preset 12, the default), on
 * the completed point-sampled image (aa_point_sample, as `point` and
 * `trio`).  Per pixel, from its luma and its eight neighbours' only:
 *
 * 1. Local contrast: the range of luma over the pixel and its four
 *    neighbours.  A pixel whose range is below max(`edge_min`, `edge` x the
 *    largest of the five) is left as it is (the early exit; defaults
 *    0.0833 and 0.166, the whitepaper's defaults).
 * 2. Direction: the edge is horizontal when the sum of the absolute second
 *    differences of luma down the three columns (the middle one counted
 *    twice) is at least that across the three rows; else vertical.
 * 3. Side: of the two neighbours across the edge, the one with the larger
 *    luma step from the pixel; the edge is taken half a pixel that way.
 * 4. End search: from there along the edge both ways, luma read
 *    bilinearly on the edge line (the mean of the two pixels across it, and
 *    of two columns where a step ends between pixels) minus the mean of the
 *    pixel's and its chosen neighbour's luma; an end is where that differs
 *    by at least a quarter of the step (the gradient).  The steps of preset
 *    12: 1, 1.5, 2, 4, then 12 taken without a further look (the end guessed
 *    beyond the last one examined).
 * 5. Offset: nearer end at distance dst of a span of length L gives the
 *    offset 1/2 - dst/L toward the chosen side, kept only when the luma at
 *    that end has the sign that says the pixel is on the inside of the
 *    step there (FXAA's "good span"); else 0.
 * 6. Sub-pixel aliasing: the mean of the neighbours (edge neighbours
 *    weighted 2, corners 1, over 12) against the pixel, over the range,
 *    smoothstepped and squared, times `subpix` (0.75, the default); the
 *    offset is the larger of this and step 5's.
 * 7. The pixel's colour read bilinearly at that offset across the edge:
 *    (1 - offset) of its own, offset of its chosen neighbour's.
 *
 * What is the implementer's here.  Luma: FXAA reads a luma the previous pass
 * wrote (its RGBL input, usually Rec. 601 weights on gamma-encoded colour,
 * or the green channel); here Y = 0.299 R + 0.587 G + 0.114 B of the linear
 * values the benchmark renders, so the thresholds apply to linear luma (on
 * black and white scenes the same pixels pass).  The image's border clamps
 * (a texture's clamp-to-edge).  Arithmetic in double precision.
 *
 * Counters: samples = pixels; expensive_pixels = pixels past the early
 * exit.  Limits: FXAA finds edges by luma, so an edge between colours of
 * equal luma is not smoothed; it blurs any high-contrast detail one pixel
 * wide (the sub-pixel term), and what point sampling lost it cannot
 * restore.  Box only, as the other post-processes.
 */
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { P_SUBPIX, P_EDGE, P_EDGE_MIN };

static const aa_param fxaa_params[] = {
    {"subpix", AA_PARAM_REAL, 0.75, 0.0, 1.0, 0, NULL,
     "amount of sub-pixel aliasing removal (FXAA 3.11 default 0.75; 0 off)"},
    {"edge", AA_PARAM_REAL, 0.166, 0.0, 1.0, 0, NULL,
     "local contrast needed, relative to the local maximum luma (default 0.166)"},
    {"edge_min", AA_PARAM_REAL, 0.0833, 0.0, 1.0, 0, NULL,
     "local contrast below which dark areas are left alone (default 0.0833)"},
    {0}};

/* Preset 12's search steps along the edge (pixels); the last is taken
 * without looking. */
static const double steps[] = {1.0, 1.5, 2.0, 4.0, 12.0};
#define NSTEPS ((int)(sizeof steps / sizeof steps[0]))

typedef struct fxaa_state {
    int w, h, ready;
    double *img;  /* point samples */
    double *luma; /* their luma */
} fxaa_state;

static int fxaa_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "fxaa post-processes point samples and has no prefilter; "
                                  "it is measured against the box reference (use -f box)");
    return AA_OK;
}

static void fxaa_release(void *state)
{
    fxaa_state *s = state;
    free(s->img);
    free(s->luma);
    memset(s, 0, sizeof *s);
}

static int prepare(fxaa_state *s, const aa_job *job)
{
    fxaa_release(s);
    const size_t n = (size_t)job->w * (size_t)job->h;
    s->w = job->w, s->h = job->h;
    if (!(s->img = malloc(n * 3 * sizeof *s->img)) || !(s->luma = malloc(n * sizeof *s->luma))) {
        fxaa_release(s);
        return aa_fail(AA_ENOMEM, "out of memory for the %dx%d post-process buffers", job->w,
                       job->h);
    }
    memset(s->img, 0, n * 3 * sizeof *s->img);
    memset(s->luma, 0, n * sizeof *s->luma);
    s->ready = 1;
    return AA_OK;
}

static int fxaa_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    return prepare(state, job);
}

static inline int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Luma at pixel (i, j), clamped to the image. */
static inline double L(const fxaa_state *s, int i, int j)
{
    return s->luma[(size_t)clampi(j, 0, s->h - 1) * (size_t)s->w + (size_t)clampi(i, 0, s->w - 1)];
}

/* Luma read bilinearly at (x, y) in pixel-centre coordinates (pixel (i, j)
 * at (i, j)), clamped to the image. */
static double bilinear(const fxaa_state *s, double x, double y)
{
    double fx = floor(x), fy = floor(y);
    int i = (int)fx, j = (int)fy;
    double tx = x - fx, ty = y - fy;
    double a = L(s, i, j) + tx * (L(s, i + 1, j) - L(s, i, j));
    double b = L(s, i, j + 1) + tx * (L(s, i + 1, j + 1) - L(s, i, j + 1));
    return a + ty * (b - a);
}

/* FXAA on pixel (i, j): the offset across the edge and the direction
 * (di, dj) of the neighbour blended; 0 for the early exit. */
static double pixel_offset(const fxaa_state *s, const double *p, int i, int j, int *di, int *dj)
{
    const double m = L(s, i, j), n = L(s, i, j - 1), so = L(s, i, j + 1), we = L(s, i - 1, j),
                 e = L(s, i + 1, j);
    const double hi = fmax(fmax(fmax(n, so), fmax(we, e)), m);
    const double lo = fmin(fmin(fmin(n, so), fmin(we, e)), m);
    const double range = hi - lo;
    if (range < fmax(p[P_EDGE_MIN], hi * p[P_EDGE]))
        return 0.0;
    const double nw = L(s, i - 1, j - 1), ne = L(s, i + 1, j - 1), sw = L(s, i - 1, j + 1),
                 se = L(s, i + 1, j + 1);

    /* 6: sub-pixel term */
    double sub = fabs((2.0 * (n + so + we + e) + (nw + ne + sw + se)) / 12.0 - m) / range;
    sub = sub > 1.0 ? 1.0 : sub;
    sub = (3.0 - 2.0 * sub) * sub * sub;
    sub = sub * sub * p[P_SUBPIX];

    /* 2: direction.  horz: the edge runs along the row (luma changes down
     * the columns), so the search runs along x and the blend across y */
    const double horz = 2.0 * fabs(n + so - 2.0 * m) + fabs(ne + se - 2.0 * e) +
                        fabs(nw + sw - 2.0 * we);
    const double vert = 2.0 * fabs(we + e - 2.0 * m) + fabs(nw + ne - 2.0 * n) +
                        fabs(sw + se - 2.0 * so);
    const int along_x = horz >= vert;
    const double before = along_x ? n : we, after = along_x ? so : e;

    /* 3: side */
    const double gb = fabs(before - m), ga = fabs(after - m);
    const int sign = gb >= ga ? -1 : 1;
    const double other = sign < 0 ? before : after;
    const double gradient = fmax(gb, ga) * 0.25, mean = 0.5 * (m + other);
    const int m_below = m - mean < 0.0;

    /* 4: search along the edge line, half a pixel toward the side */
    double ex = i, ey = j, sx = along_x, sy = !along_x;
    if (along_x)
        ey += 0.5 * sign;
    else
        ex += 0.5 * sign;
    double dist[2], end[2];
    for (int k = 0; k < 2; k++) {
        const double dir = k ? 1.0 : -1.0;
        double t = steps[0];
        double v = bilinear(s, ex + dir * sx * t, ey + dir * sy * t) - mean;
        int done = fabs(v) >= gradient;
        for (int q = 1; q < NSTEPS && !done; q++) {
            t += steps[q];
            if (q < NSTEPS - 1) {
                v = bilinear(s, ex + dir * sx * t, ey + dir * sy * t) - mean;
                done = fabs(v) >= gradient;
            }
        }
        dist[k] = t, end[k] = v;
    }

    /* 5: offset from the nearer end */
    const int nearer = dist[0] < dist[1] ? 0 : 1;
    const double span = dist[0] + dist[1];
    const int good = (end[nearer] < 0.0) != m_below;
    double off = good ? 0.5 - dist[nearer] / span : 0.0;
    off = fmax(off, sub);
    *di = along_x ? 0 : sign;
    *dj = along_x ? sign : 0;
    return off;
}

static int fxaa_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    fxaa_state *s = state;
    int st;
    if ((!s->ready || s->w != job->w || s->h != job->h) && (st = prepare(s, job)))
        return st;
    aa_image img = {job->w, job->h, 3, s->img};
    if ((st = aa_point_sample(job->placed, 0.0, 0.0, job->threads, &img)))
        return st;
    const int w = s->w, h = s->h;
    counters->samples = (uint64_t)w * (uint64_t)h;
    uint64_t expensive = 0;
#pragma omp parallel num_threads(job->threads)
    {
#pragma omp for schedule(static)
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                const double *c = s->img + 3 * ((size_t)j * (size_t)w + (size_t)i);
                s->luma[(size_t)j * (size_t)w + (size_t)i] =
                    0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
            }
#pragma omp for schedule(static) reduction(+ : expensive)
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                const double *c = s->img + 3 * ((size_t)j * (size_t)w + (size_t)i);
                double *y = aa_pixel(out, i, j);
                int di = 0, dj = 0;
                double off = pixel_offset(s, p, i, j, &di, &dj);
                if (di || dj)
                    expensive++;
                if (off <= 0.0) {
                    y[0] = c[0], y[1] = c[1], y[2] = c[2];
                    continue;
                }
                int ni = clampi(i + di, 0, w - 1), nj = clampi(j + dj, 0, h - 1);
                const double *o = s->img + 3 * ((size_t)nj * (size_t)w + (size_t)ni);
                for (int k = 0; k < 3; k++)
                    y[k] = c[k] + off * (o[k] - c[k]);
            }
    }
    counters->expensive_pixels = expensive;
    return AA_OK;
}

const aa_method_type aa_method_fxaa = {
    {"fxaa", "point samples smoothed by FXAA 3.11 quality, preset 12 (Lottes 2011)",
     fxaa_params},
    sizeof(fxaa_state),
    AA_METHOD_FIELDS,
    fxaa_check,
    fxaa_init,
    fxaa_render,
    fxaa_release};
