/*
 * taa.c: temporal antialiasing with reprojection, after Karis 2014 ("High
 * Quality Temporal Supersampling", SIGGRAPH course Advances in Real-Time
 * Rendering in Games), Crow's hexagon (1976 ch. 4, fig. 4.1,
 * algorithms/hexagon.c) being its ancestor; and, as the variant
 * `taa:reproject=none,clamp=none`, the plain exponential history of
 * earlier versions (algorithms/README.md, "Temporal antialiasing").
 *
 * What the talk specifies, and is done here.
 *  - Sub-pixel jitter along Halton(2,3): frame n (an integer; the scene at
 *    time T - k for frame floor(T) - k) is point sampled at the pixel
 *    centres moved by (phi2(i) - 1/2, phi3(i) - 1/2), i = n mod `frames`,
 *    phi_b the radical inverse in base b (8 frames, the talk's count; 16 as
 *    an option).  Index 0 is (0, 0) in the pixel's [0,1]^2 coordinates.
 *  - One history image, resolved colour per pixel (not samples), carried
 *    from frame to frame by reprojection: pixel p's history is the previous
 *    output read where p's content was one frame before.
 *  - Neighbourhood clamping: the history is limited to the box (per
 *    component min and max) of the current frame's 3 x 3 neighbourhood in
 *    YCoCg (Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4;
 *    frames.h), so stale history (content that moved away) is rejected
 *    and the image converges under motion instead of smearing.
 *    `clamp=clip` clips the history toward the box's centre along the
 *    line joining them instead, the talk's refinement (the colour keeps
 *    its hue where a clamp per component would change it).
 *  - The exponential history h <- h + alpha (x - h), alpha 0.1 by default
 *    (`alpha`).
 *
 * What the talk leaves to the implementer (or what a renderer has that this
 * harness has not), decided here.
 *  - Motion vectors: the scene's known motion is exact and uniform (the
 *    whole scene translates by (vx, vy) pixels a frame, aa_job), so every
 *    pixel's vector is (vx, vy): the talk's dilation of the velocity (the
 *    nearest depth in 3 x 3) has nothing to do.  The history of pixel
 *    centre c is read at c - v.
 *  - The history's sampling filter: bilinear (`sample=bilinear`, the
 *    default; it blurs a little at each resampling) or Catmull-Rom
 *    (`sample=catmull`, the 4 x 4 cubic with a = -1/2; sharper, it may
 *    overshoot, which the clamp then bounds).  Taps outside the image are
 *    read at its nearest edge pixel (a GPU's clamp-to-edge).  With no
 *    motion the history is read at the centres as it is.
 *  - Disocclusion: the scene moves as one, so nothing is uncovered inside
 *    the image; content entering at the borders, whose position one frame
 *    before (c - v) lies outside the image, restarts its history from the
 *    current sample (weight 1).
 *  - The first frame: the history starts `history` frames before the
 *    frame shown (as the variant's does), the oldest frame taken as it is;
 *    with alpha 0.1 and 64 frames its weight is 1.3e-3 where no clamp
 *    intervened, so the image is the steady state, not a game's start-up.
 *  - The current frame's sample is taken as the pixel's value at its
 *    jittered position; the talk's reconstruction filter over the jittered
 *    3 x 3 samples (a Blackman-Harris weight) and its weighting of samples
 *    by inverse luminance (against flicker of bright HDR values; every
 *    value here lies in [0, 1]) are not done, nor sharpening.
 *
 * Known answers (tests/test_temporal.c).  On a still scene of straight
 * edges the clamp never acts (a line through a pixel leaves a whole
 * neighbouring pixel on each of its sides, so the box spans both colours),
 * and the image is exactly the variant's closed-form steady state: lag j
 * (0 = the newest) weighs alpha (1 - alpha)^j / (1 - (1 - alpha)^frames)
 * summed over its cycle, which tends to the plain mean of the `frames`
 * offsets, an estimate of the box-filtered value, as alpha falls.  Moving,
 * the error against each frame's exact reference stays bounded, below the
 * unclamped, unreprojected history's.  The image does not depend on the
 * thread count; a uniform scene stays exact.
 *
 * The variant (`reproject=none,clamp=none`): the history is blended in the
 * fixed pixels with no reprojection and no clamp, so a moving scene drags a
 * trail (ghosting: its `lag`, harness/bench/temporal.c, is several frames).
 * Kept for comparison with the method of earlier versions.
 *
 * A displayed frame of taa is its history, so --frame-only changes nothing.
 * Limits.  Each frame is point sampled, so detail thinner than the spacing
 * of the `frames` offsets is missed and small objects still flicker, and
 * the clamp, by a 3 x 3 box that misses a thin feature in some frames,
 * throws history away there (flicker the variant has not); the Halton
 * points' mean is not the pixel centre (for 8 frames (-1/16, -1/9) pixel
 * from it).  No prefilter: measured against the box reference, other
 * filters refused.  Cost: `history` point-sampled frames per image, each
 * resampled and clamped.
 */
#include "frames.h"
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TAA_MAX_HISTORY 1024

enum { P_FRAMES, P_ALPHA, P_HISTORY, P_REPROJECT, P_CLAMP, P_SAMPLE };
enum { REPROJECT_MOTION, REPROJECT_NONE };
enum { CLAMP_YCOCG, CLAMP_CLIP, CLAMP_NONE };
enum { SAMPLE_BILINEAR, SAMPLE_CATMULL };

static const aa_param taa_params[] = {
    {"frames", AA_PARAM_CHOICE, 0, 0, 0, 0, "8|16",
     "length of the Halton(2,3) jitter cycle: frame n uses index n mod frames"},
    {"alpha", AA_PARAM_REAL, 0.1, 0.0, 1.0, 1, NULL,
     "blend factor: h = alpha x + (1 - alpha) h"},
    {"history", AA_PARAM_INT, 64, 1, TAA_MAX_HISTORY, 0, NULL,
     "frames blended: the history starts this many frames before --time"},
    {"reproject", AA_PARAM_CHOICE, REPROJECT_MOTION, 0, 0, 0, "motion|none",
     "read the history where the content was a frame before (the scene's motion), or in "
     "the fixed pixels"},
    {"clamp", AA_PARAM_CHOICE, CLAMP_YCOCG, 0, 0, 0, "ycocg|clip|none",
     "limit the history to the YCoCg box of the current 3x3 neighbourhood: per component, "
     "toward its centre, or not at all"},
    {"sample", AA_PARAM_CHOICE, SAMPLE_BILINEAR, 0, 0, 0, "bilinear|catmull",
     "filter reading the reprojected history"},
    {0}};

typedef struct taa_state {
    aa__frames fs;
    double dx[TAA_MAX_HISTORY], dy[TAA_MAX_HISTORY], wt[TAA_MAX_HISTORY];
    double *buf; /* three images: current frame, history, next history */
    size_t cap;  /* doubles in buf */
} taa_state;

static int plain(const double *p)
{
    return (int)p[P_REPROJECT] == REPROJECT_NONE && (int)p[P_CLAMP] == CLAMP_NONE;
}

static int taa_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "taa samples points and has no prefilter; it is measured "
                                  "against the box reference (use -f box)");
    return AA_OK;
}

static int buffers(taa_state *s, const aa_job *job)
{
    size_t need = 3 * 3 * (size_t)job->w * (size_t)job->h;
    if (need <= s->cap)
        return AA_OK;
    free(s->buf);
    s->cap = 0;
    if (!(s->buf = malloc(need * sizeof *s->buf)))
        return aa_fail(AA_ENOMEM, "out of memory for taa's history (%dx%d)", job->w, job->h);
    memset(s->buf, 0, need * sizeof *s->buf); /* touched here, not in the timed render */
    s->cap = need;
    return AA_OK;
}

static int taa_init(void *state, const double *p, const aa_job *job)
{
    taa_state *s = state;
    int st = aa__frames_ready(&s->fs, job, (int)p[P_HISTORY]);
    return st ? st : plain(p) ? AA_OK : buffers(s, job);
}

static inline int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* Catmull-Rom weights of the taps at -1, 0, 1, 2 for a point t in [0, 1)
 * past tap 0. */
static inline void catmull(double t, double w[4])
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = -0.5 * t3 + t2 - 0.5 * t;
    w[1] = 1.5 * t3 - 2.5 * t2 + 1.0;
    w[2] = -1.5 * t3 + 2.0 * t2 + 0.5 * t;
    w[3] = 0.5 * t3 - 0.5 * t2;
}

/* The history image h (w x h pixels, values at the centres) read at grid
 * point (gx, gy) (pixel units minus 1/2: pixel (i, j)'s centre is (i, j)),
 * clamp-to-edge, into v. */
static void read_history(const double *hist, int w, int h, double gx, double gy, int cubic,
                         double v[3])
{
    const double fx = floor(gx), fy = floor(gy);
    const int i0 = (int)fx, j0 = (int)fy;
    const double tx = gx - fx, ty = gy - fy;
    v[0] = v[1] = v[2] = 0.0;
    if (!cubic) {
        const double wx[2] = {1.0 - tx, tx}, wy[2] = {1.0 - ty, ty};
        for (int b = 0; b < 2; b++)
            for (int a = 0; a < 2; a++) {
                const double *q = hist + 3 * ((size_t)clampi(j0 + b, 0, h - 1) * (size_t)w +
                                              (size_t)clampi(i0 + a, 0, w - 1));
                double wt = wx[a] * wy[b];
                v[0] += wt * q[0], v[1] += wt * q[1], v[2] += wt * q[2];
            }
        return;
    }
    double wx[4], wy[4];
    catmull(tx, wx);
    catmull(ty, wy);
    for (int b = 0; b < 4; b++)
        for (int a = 0; a < 4; a++) {
            const double *q = hist + 3 * ((size_t)clampi(j0 - 1 + b, 0, h - 1) * (size_t)w +
                                          (size_t)clampi(i0 - 1 + a, 0, w - 1));
            double wt = wx[a] * wy[b];
            v[0] += wt * q[0], v[1] += wt * q[1], v[2] += wt * q[2];
        }
}

/* Limit hv (RGB) to the YCoCg box of cur's 3 x 3 neighbourhood of (i, j)
 * (the pixels inside the image).  It is changed only when outside. */
static void limit(const double *cur, int w, int h, int i, int j, int mode, double hv[3])
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int b = j - 1; b <= j + 1; b++)
        for (int a = i - 1; a <= i + 1; a++) {
            if (a < 0 || b < 0 || a >= w || b >= h)
                continue;
            double y[3];
            aa__ycocg_from_rgb(cur + 3 * ((size_t)b * (size_t)w + (size_t)a), y);
            for (int c = 0; c < 3; c++)
                lo[c] = fmin(lo[c], y[c]), hi[c] = fmax(hi[c], y[c]);
        }
    double y[3];
    aa__ycocg_from_rgb(hv, y);
    int out = 0;
    for (int c = 0; c < 3; c++)
        out |= y[c] < lo[c] || y[c] > hi[c];
    if (!out)
        return;
    if (mode == CLAMP_YCOCG) {
        for (int c = 0; c < 3; c++)
            y[c] = fmin(fmax(y[c], lo[c]), hi[c]);
    } else { /* clip: the point of the segment centre -> y nearest y inside the box */
        double m[3], e[3], d[3], t = 1.0;
        for (int c = 0; c < 3; c++) {
            m[c] = 0.5 * (lo[c] + hi[c]), e[c] = 0.5 * (hi[c] - lo[c]), d[c] = y[c] - m[c];
            if (fabs(d[c]) > e[c])
                t = fmin(t, e[c] / fabs(d[c]));
        }
        for (int c = 0; c < 3; c++)
            y[c] = m[c] + t * d[c];
    }
    aa__rgb_from_ycocg(y, hv);
}

/* The reprojected history's pixel rows [j] into next, from hist and cur. */
static void resolve_row(const double *hist, const double *cur, double *next, int w, int h,
                        int j, double vx, double vy, int moving, int mode, int cubic,
                        double alpha)
{
    for (int i = 0; i < w; i++) {
        const size_t q = 3 * ((size_t)j * (size_t)w + (size_t)i);
        double hv[3];
        const double *x = cur + q;
        if (!moving) {
            hv[0] = hist[q], hv[1] = hist[q + 1], hv[2] = hist[q + 2];
        } else {
            const double px = i + 0.5 - vx, py = j + 0.5 - vy; /* where it was */
            if (!(px >= 0.0 && px <= w && py >= 0.0 && py <= h)) {
                /* entered the image: no history */
                next[q] = x[0], next[q + 1] = x[1], next[q + 2] = x[2];
                continue;
            }
            read_history(hist, w, h, px - 0.5, py - 0.5, cubic, hv);
        }
        if (mode != CLAMP_NONE)
            limit(cur, w, h, i, j, mode, hv);
        for (int c = 0; c < 3; c++)
            next[q + (size_t)c] = hv[c] + (x[c] - hv[c]) * alpha;
    }
}

static int render_karis(taa_state *s, const double *p, const aa_job *job, int n, aa_image *out,
                        aa_counters *counters)
{
    int st = buffers(s, job);
    if (st)
        return st;
    const int w = job->w, h = job->h;
    const size_t len = 3 * (size_t)w * (size_t)h;
    const int moving = (int)p[P_REPROJECT] == REPROJECT_MOTION &&
                       (job->vx != 0.0 || job->vy != 0.0);
    const int mode = (int)p[P_CLAMP], cubic = (int)p[P_SAMPLE] == SAMPLE_CATMULL;
    const double alpha = p[P_ALPHA];
    double *cur = s->buf, *hist = s->buf + len, *next = s->buf + 2 * len;
    int status = AA_OK;
#pragma omp parallel num_threads(job->threads)
    {
        aa_point_ws ws;
        /* every frame's scene has the same pieces: one workspace serves all */
        int bad = aa_point_ws_init(&ws, s->fs.placed[0]);
        for (int k = n - 1; k >= 0; k--) { /* oldest first */
            double *into = k == n - 1 ? hist : cur;
#pragma omp for schedule(static)
            for (int j = 0; j < h; j++)
                if (!bad)
                    aa_point_row(s->fs.placed[k], &ws, s->dx[k], j + 0.5 + s->dy[k],
                                 into + 3 * (size_t)j * (size_t)w, w);
            if (k == n - 1)
                continue;
#pragma omp for schedule(static)
            for (int j = 0; j < h; j++)
                resolve_row(hist, cur, next, w, h, j, job->vx, job->vy, moving, mode, cubic,
                            alpha);
#pragma omp single
            {
                double *t = hist;
                hist = next, next = t;
            }
        }
        if (!bad)
            aa_point_ws_free(&ws);
        else {
#pragma omp atomic write
            status = bad;
        }
    }
    if (status)
        return aa_fail(status, "out of memory while sampling the frames");
    for (int j = 0; j < h; j++)
        memcpy(aa_pixel(out, 0, j), hist + 3 * (size_t)j * (size_t)w,
               3 * (size_t)w * sizeof *hist);
    counters->samples = (uint64_t)n * (uint64_t)w * (uint64_t)h;
    counters->expensive_pixels = 0;
    return AA_OK;
}

static int taa_render(void *state, const double *p, const aa_job *job, aa_image *out,
                      aa_counters *counters)
{
    taa_state *s = state;
    const int n = (int)p[P_HISTORY], cycle = (int)p[P_FRAMES] == 0 ? 8 : 16;
    int st = aa__frames_ready(&s->fs, job, n);
    if (st)
        return st;
    const long long base = (long long)floor(job->t);
    for (int k = 0; k < n; k++) { /* frame k of the history: time t - k */
        uint64_t i = (uint64_t)aa__mod(base - k, cycle);
        s->dx[k] = aa__radical_inverse(i, 2) - 0.5;
        s->dy[k] = aa__radical_inverse(i, 3) - 0.5;
        s->wt[k] = p[P_ALPHA];
    }
    if (plain(p))
        return aa__frames_render(&s->fs, job, n, s->dx, s->dy, s->wt, out, counters);
    return render_karis(s, p, job, n, out, counters);
}

static void taa_release(void *state)
{
    taa_state *s = state;
    aa__frames_free(&s->fs);
    free(s->buf);
    s->buf = NULL;
    s->cap = 0;
}

const aa_method_type aa_method_taa = {
    {"taa", "temporal antialiasing after Karis 2014: Halton(2,3) jitter, reprojection by the "
            "scene's motion, YCoCg neighbourhood clamp, exponential history",
     taa_params},
    sizeof(taa_state),
    AA_METHOD_TEMPORAL,
    taa_check,
    taa_init,
    taa_render,
    taa_release};
