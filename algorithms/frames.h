/*
 * frames.h: what the temporal methods `hexagon`, `taa` and `cycle` share
 * (internal to algorithms/): a stack of point-sampled frames at times t,
 * t - 1, ..., each sampled at the pixel centres moved by its own offset,
 * combined oldest first by out += (frame - out) * weight.  A weight of 1/m
 * for the m-th frame gives the running mean (hexagon, cycle), a constant
 * alpha the exponential history of temporal antialiasing (taa).
 *
 * Work is shared in bands of AA__FRAMES_BAND rows whatever the thread
 * count, so the image does not depend on it.  The placed scenes (one per
 * frame time, one for a still scene) and the scratch bands are made by
 * aa__frames_ready in init, and again only for a job of another size, time,
 * motion, thread count or frame count.
 */
#ifndef AA_FRAMES_H
#define AA_FRAMES_H

#include "aabench.h"

#define AA__FRAMES_BAND 8

typedef struct aa__frames {
    const aa_scene *pattern;
    int w, h, threads, n;
    double t, vx, vy;
    aa_scene **placed; /* placed[k]: the scene at time t - k */
    int shared;        /* still scene: every placed[k] is placed[0] */
    double *scratch;   /* threads x band x w x 3 */
    double *dots;      /* screen display: per thread, band + 1 + n rows of w + 1 dots */
} aa__frames;

/* Scenes for n frames of the job (t, t - 1, ..., t - n + 1). */
int aa__frames_ready(aa__frames *fs, const aa_job *job, int n);
void aa__frames_free(aa__frames *fs);
/* Combine frames n-1 (oldest) .. 0: frame k sampled at centres + (dx[k],
 * dy[k]); out = frame n-1, then out += (frame k - out) * weight[k].  n must
 * not exceed the n given to aa__frames_ready.  Sets samples = n W H. */
int aa__frames_render(aa__frames *fs, const aa_job *job, int n, const double *dx,
                      const double *dy, const double *weight, aa_image *out,
                      aa_counters *counters);

/* The screen display (core.h, "Displays"): frame k's dots are sampled
 * at the pixel centres + (dx[k], dy[k]), |dx|, |dy| <= 1, and shown there
 * as squares one pixel wide, which cover pixel q by the areas
 * a(q - p - d) = (1 - |u|)(1 - |v|), the bilinear weights of the two
 * nearest dots in each direction; the dots in the ring just beyond the
 * image are sampled too.  The frames are combined as by aa__frames_render.
 * aa__frames_screen makes the per-thread dot bands (after
 * aa__frames_ready).  Each thread takes a block of rows in bands, and a
 * band of a frame starts from the last row of dots of the band before;
 * samples = n (W + 1) (H + 1), the dots of the frames (one more row and
 * column than there are pixels); a thread that starts inside the image
 * samples its first row of dots again, which is not counted. */
int aa__frames_screen(aa__frames *fs);
int aa__frames_render_screen(aa__frames *fs, const aa_job *job, int n, const double *dx,
                             const double *dy, const double *weight, aa_image *out,
                             aa_counters *counters);

/* The radical inverse of i in base b (Halton's sequence): 0, 1/2, 1/4, ...
 * for b = 2. */
double aa__radical_inverse(uint64_t i, unsigned b);
/* YCoCg (Malvar and Sullivan's transform, used by taa's neighbourhood
 * clamp): Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4, and
 * back R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg.  Grey (v, v, v) is
 * (v, 0, 0). */
static inline void aa__ycocg_from_rgb(const double rgb[3], double y[3])
{
    y[0] = 0.25 * rgb[0] + 0.5 * rgb[1] + 0.25 * rgb[2];
    y[1] = 0.5 * rgb[0] - 0.5 * rgb[2];
    y[2] = -0.25 * rgb[0] + 0.5 * rgb[1] - 0.25 * rgb[2];
}
static inline void aa__rgb_from_ycocg(const double y[3], double rgb[3])
{
    const double t = y[0] - y[2];
    rgb[0] = t + y[1];
    rgb[1] = y[0] + y[2];
    rgb[2] = t - y[1];
}
/* n mod m in 0 .. m-1 for any n. */
static inline int aa__mod(long long n, int m)
{
    int r = (int)(n % m);
    return r < 0 ? r + m : r;
}

#endif
