/*
 * taa.c: temporal antialiasing as games do it (algorithms/README.md,
 * "Temporal antialiasing": the projection jittered per frame along
 * Halton(2,3) over 8 or 16 frames, history blended with a factor around
 * 0.1; Crow's hexagon, 1976 ch. 4 fig. 4.1, is its ancestor,
 * algorithms/hexagon.c).
 *
 * Frame n (an integer; the scene at time T - k for frame floor(T) - k) is
 * point sampled at the pixel centres moved by the offset
 *
 *     (phi2(i) - 1/2, phi3(i) - 1/2),   i = n mod `frames`,
 *
 * phi_b the radical inverse in base b, so index 0 is (0, 0) in the pixel's
 * [0,1]^2 coordinates and the 8-frame sequence is algorithms/README.md's (0/8,
 * 0/9) (4/8, 3/9) (2/8, 6/9) (6/8, 1/9) ...  The history is
 *
 *     h = x(first frame),  then  h <- h + alpha (x - h)   (= alpha x + (1 - alpha) h)
 *
 * and the image at --time T is the history after frame floor(T).
 *
 * Where the history starts.  Starting it at frame 0 would make the image
 * depend on how far T is from 0 (at T = 0 a single jittered frame), which
 * is the start-up of a game, not its steady state.  So it starts `history`
 * frames back: frames floor(T) - history + 1 .. floor(T) are blended, the
 * oldest taken as it is.  The weight left on that first frame is
 * (1 - alpha)^(history - 1): with the defaults (alpha 0.1, history 64)
 * 1.3e-3, and every frame of the Halton cycle is still in the history
 * with its steady-state weight to that precision.  On a still scene the
 * steady state is a fixed weighted mean of the `frames` offsets: lag j
 * (0 = the newest) weighs alpha (1 - alpha)^j / (1 - (1 - alpha)^frames)
 * summed over its cycle, so the newest offset weighs about 2.1 times the
 * oldest of 8 at alpha 0.1: not the equal weights of supersampling, which
 * it approaches as alpha falls (tests/test_temporal.c checks the closed
 * form).  The image does not depend on the thread count; a uniform scene
 * stays exact (h + alpha (x - h) = h when x = h).
 *
 * A displayed frame of taa is its history, so --frame-only changes nothing:
 * the temporal metrics see the images the screen would show.
 *
 * Limits.  No reprojection and no history clamping: when the scene moves,
 * the history lags behind it and smears a trail (the method's known
 * ghosting), and nothing rejects stale history.  Each frame is point
 * sampled, so detail between the `frames` sample positions is missed and
 * small objects still flicker; the Halton points' mean is not the pixel
 * centre (for 8 frames it is (-1/16, -1/9) pixel from it), which shifts
 * the image slightly.  No prefilter: measured against the box reference,
 * other filters refused.  Cost: `history` point-sampled frames per image.
 */
#include "frames.h"
#include "methods.h"

#include <math.h>
#include <stdlib.h>

#define TAA_MAX_HISTORY 1024

enum { P_FRAMES, P_ALPHA, P_HISTORY };

static const aa_param taa_params[] = {
    {"frames", AA_PARAM_CHOICE, 0, 0, 0, 0, "8|16",
     "length of the Halton(2,3) jitter cycle: frame n uses index n mod frames"},
    {"alpha", AA_PARAM_REAL, 0.1, 0.0, 1.0, 1, NULL,
     "blend factor: h = alpha x + (1 - alpha) h"},
    {"history", AA_PARAM_INT, 64, 1, TAA_MAX_HISTORY, 0, NULL,
     "frames blended: the history starts this many frames before --time"},
    {0}};

typedef struct taa_state {
    aa__frames fs;
    double dx[TAA_MAX_HISTORY], dy[TAA_MAX_HISTORY], wt[TAA_MAX_HISTORY];
} taa_state;

static int taa_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "taa samples points and has no prefilter; it is measured "
                                  "against the box reference (use -f box)");
    return AA_OK;
}

static int taa_init(void *state, const double *p, const aa_job *job)
{
    taa_state *s = state;
    return aa__frames_ready(&s->fs, job, (int)p[P_HISTORY]);
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
    return aa__frames_render(&s->fs, job, n, s->dx, s->dy, s->wt, out, counters);
}

static void taa_release(void *state)
{
    taa_state *s = state;
    aa__frames_free(&s->fs);
}

const aa_method_type aa_method_taa = {
    {"taa", "temporal antialiasing: Halton(2,3) jitter per frame, exponential history "
            "(no reprojection)",
     taa_params},
    sizeof(taa_state),
    AA_METHOD_TEMPORAL,
    taa_check,
    taa_init,
    taa_render,
    taa_release};
