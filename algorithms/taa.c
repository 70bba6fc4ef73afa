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
 *    its hue where a clamp per component would change it);
 *    on a grey scene the two agree, the box being flat in Co and Cg).
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
 *  - The history's sampling filter: Catmull-Rom (`sample=catmull`, the
 *    default: the 4 x 4 cubic with a = -1/2; it may overshoot, which the
 *    clamp then bounds) or bilinear (`sample=bilinear`), which blurs at
 *    every resampling, and the blur adds up over the frames the history
 *    remembers: on crow 128x128 moving (0.37, 0.11) px a frame, frame 30's
 *    RMSE is 0.220 with Catmull-Rom and 0.243 bilinear (point 0.253); on
 *    the star 0.091 and 0.134 (point 0.146).  Taps outside the image are
 *    read at its nearest edge pixel (a GPU's clamp-to-edge).  The blend's
 *    result is kept in [0, 1], a colour's range (with `clamp=none` the
 *    cubic's overshoot would leave it).  With no
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
#ifdef _OPENMP
#include <omp.h>
#endif

#define TAA_MAX_HISTORY 1024

enum { P_FRAMES, P_ALPHA, P_HISTORY, P_REPROJECT, P_CLAMP, P_SAMPLE };
enum { REPROJECT_MOTION, REPROJECT_NONE };
enum { CLAMP_YCOCG, CLAMP_CLIP, CLAMP_NONE };
enum { SAMPLE_CATMULL, SAMPLE_BILINEAR };

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
    {"sample", AA_PARAM_CHOICE, SAMPLE_CATMULL, 0, 0, 0, "catmull|bilinear",
     "filter reading the reprojected history"},
    {0}};

typedef struct taa_state {
    aa__frames fs;
    double dx[TAA_MAX_HISTORY], dy[TAA_MAX_HISTORY], wt[TAA_MAX_HISTORY];
    double *buf; /* two images (history, next history), then each thread's band */
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

/* Limit hv (RGB) to the YCoCg box of the current frame's 3 x 3
 * neighbourhood of (i, j) (the pixels inside the image); ycur holds the
 * frame's rows from c0 on in YCoCg.  hv is changed only when outside. */
static void limit(const double *ycur, int c0, int w, int h, int i, int j, int mode,
                  double hv[3])
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const int a0 = i > 0 ? i - 1 : 0, a1 = i + 1 < w ? i + 1 : w - 1;
    const int b0 = j > 0 ? j - 1 : 0, b1 = j + 1 < h ? j + 1 : h - 1;
    for (int b = b0; b <= b1; b++)
        for (int a = a0; a <= a1; a++) {
            const double *y = ycur + 3 * ((size_t)(b - c0) * (size_t)w + (size_t)a);
            for (int c = 0; c < 3; c++) {
                lo[c] = y[c] < lo[c] ? y[c] : lo[c];
                hi[c] = y[c] > hi[c] ? y[c] : hi[c];
            }
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
            y[c] = y[c] < lo[c] ? lo[c] : y[c] > hi[c] ? hi[c] : y[c];
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

/* What a frame's resolve reads. */
typedef struct taa_frame {
    const double *hist; /* the previous output, w x h */
    double *next;       /* this frame's output */
    int w, h, moving, mode, cubic;
    double vx, vy, alpha;
} taa_frame;

/* Row j of the frame's output from the history and the current frame (its
 * rows from c0 on in cur, and in YCoCg in ycur). */
static void resolve_row(const taa_frame *F, const double *cur, const double *ycur, int c0, int j)
{
    const int w = F->w, h = F->h;
    for (int i = 0; i < w; i++) {
        const size_t q = 3 * ((size_t)j * (size_t)w + (size_t)i);
        const double *x = cur + 3 * ((size_t)(j - c0) * (size_t)w + (size_t)i);
        double hv[3], *o = F->next + q;
        if (!F->moving) {
            hv[0] = F->hist[q], hv[1] = F->hist[q + 1], hv[2] = F->hist[q + 2];
        } else {
            const double px = i + 0.5 - F->vx, py = j + 0.5 - F->vy; /* where it was */
            if (!(px >= 0.0 && px <= w && py >= 0.0 && py <= h)) {
                /* entered the image: no history */
                o[0] = x[0], o[1] = x[1], o[2] = x[2];
                continue;
            }
            read_history(F->hist, w, h, px - 0.5, py - 0.5, F->cubic, hv);
        }
        if (F->mode != CLAMP_NONE)
            limit(ycur, c0, w, h, i, j, F->mode, hv);
        /* a colour's range: Catmull-Rom overshoots where nothing clamps it,
         * and YCoCg's round trip rounds */
        for (int c = 0; c < 3; c++) {
            double v = hv[c] + (x[c] - hv[c]) * F->alpha;
            o[c] = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
        }
    }
}

/* Rows of the current frame a thread keeps (in RGB, then in YCoCg): its
 * block and one row either side. */
static size_t band_rows(int h, int threads)
{
    return (size_t)((h + threads - 1) / threads) + 2;
}

static int buffers(taa_state *s, const aa_job *job)
{
    const int threads = job->threads > 0 ? job->threads : 1;
    size_t row = 3 * (size_t)job->w;
    size_t need =
        2 * row * (size_t)job->h + 2 * (size_t)threads * band_rows(job->h, threads) * row;
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

/* Each thread takes a fixed block of rows through every frame: it samples
 * its rows of the frame and one more either side (the clamp's
 * neighbourhood) into a band of its own, and resolves its rows from the
 * shared previous output into the other of two images; one barrier per
 * frame.  A pixel's value does not depend on the block it falls in. */
static int render_karis(taa_state *s, const double *p, const aa_job *job, int n, aa_image *out,
                        aa_counters *counters)
{
    int st = buffers(s, job);
    if (st)
        return st;
    const int w = job->w, h = job->h, threads = job->threads > 0 ? job->threads : 1;
    const size_t len = 3 * (size_t)w * (size_t)h, brows = band_rows(h, threads);
    double *img[2] = {s->buf, s->buf + len}, *bands = s->buf + 2 * len;
    const taa_frame base = {NULL,
                            NULL,
                            w,
                            h,
                            (int)p[P_REPROJECT] == REPROJECT_MOTION &&
                                (job->vx != 0.0 || job->vy != 0.0),
                            (int)p[P_CLAMP],
                            (int)p[P_SAMPLE] == SAMPLE_CATMULL,
                            job->vx,
                            job->vy,
                            p[P_ALPHA]};
    int status = AA_OK;
#pragma omp parallel num_threads(threads)
    {
        int me = 0, team = 1;
#ifdef _OPENMP
        me = omp_get_thread_num(), team = omp_get_num_threads();
#endif
        const int a = (int)((long long)h * me / team), b = (int)((long long)h * (me + 1) / team);
        const int c0 = a > 0 ? a - 1 : 0, c1 = b < h ? b + 1 : h;
        double *cur = bands + 2 * (size_t)me * brows * 3 * (size_t)w,
               *ycur = cur + brows * 3 * (size_t)w;
        aa_point_ws ws;
        /* every frame's scene has the same pieces: one workspace serves all */
        int bad = aa_point_ws_init(&ws, s->fs.placed[0]);
        for (int step = 0; step < n; step++) { /* oldest first */
            const int k = n - 1 - step;
            if (!bad && step == 0) {
                for (int j = a; j < b; j++)
                    aa_point_row(s->fs.placed[k], &ws, s->dx[k], j + 0.5 + s->dy[k],
                                 img[0] + 3 * (size_t)j * (size_t)w, w);
            } else if (!bad) {
                for (int j = c0; j < c1; j++)
                    aa_point_row(s->fs.placed[k], &ws, s->dx[k], j + 0.5 + s->dy[k],
                                 cur + 3 * (size_t)(j - c0) * (size_t)w, w);
                if (base.mode != CLAMP_NONE)
                    for (size_t q = 0; q < (size_t)(c1 - c0) * (size_t)w; q++)
                        aa__ycocg_from_rgb(cur + 3 * q, ycur + 3 * q);
                taa_frame F = base;
                F.hist = img[(step - 1) & 1], F.next = img[step & 1];
                for (int j = a; j < b; j++)
                    resolve_row(&F, cur, ycur, c0, j);
            }
#pragma omp barrier
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
    const double *last = img[(n - 1) & 1];
    for (int j = 0; j < h; j++)
        memcpy(aa_pixel(out, 0, j), last + 3 * (size_t)j * (size_t)w,
               3 * (size_t)w * sizeof *last);
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
