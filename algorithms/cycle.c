/*
 * cycle.c: the standard multisample positions visited one per frame, the
 * eye's image the mean of a window of frames: Crow's temporal scheme (1976,
 * ch. 4, fig. 4.1, algorithms/hexagon.c) with the hexagon's six vertices
 * replaced by the Direct3D/Vulkan msaa positions (algorithms/README.md,
 * "Standard multisample positions"; supersample.c's table, aa_msaa_positions,
 * which its pattern=msaaN samples).
 *
 * Frame n (an integer, negative allowed; the scene at time T - k for frame
 * floor(T) - k) samples each pixel at its centre moved by position
 * n mod m of the pattern (m = 2, 4, 8, 16 positions, v/16 pixel, y down).
 * The image at --time T is the mean of `frames` frames ending at T
 * (default: m, one full cycle), accumulated oldest first as a running mean,
 * so a uniform scene stays exact.  --frame-only gives the single frame at
 * T.  On a still scene a window of m frames sees every position once: the
 * image is supersample:pattern=msaaN's with the box (tests/test_temporal.c
 * checks it) for one point sample per frame.
 *
 * Why a method of its own rather than an option of hexagon: the hexagon's
 * parameters (radius, angle, vertex order) describe a hexagon and mean
 * nothing for a fixed table of positions, and the msaa tables already have
 * an order (the one hardware uses).  One method, one set of meaningful
 * parameters.
 *
 * Counters: samples = frames x pixels (pixels for --frame-only);
 * expensive_pixels = 0.
 *
 * Limits: as hexagon.  Each frame is point sampled, so detail between the
 * positions is missed and small objects flicker as the cycle passes them;
 * a window shorter than m does not see every position (the image is then
 * biased toward the positions seen); with motion the eye's image is smeared
 * along the motion.  No prefilter: box only.
 */
#include "frames.h"
#include "methods.h"

#include <math.h>

#define CYCLE_MAX_FRAMES 64

enum { P_POSITIONS, P_FRAMES };

static const aa_param cycle_params[] = {
    {"positions", AA_PARAM_CHOICE, 2, 0, 0, 0, "msaa2|msaa4|msaa8|msaa16",
     "standard multisample positions, one per frame in the table's order"},
    {"frames", AA_PARAM_INT, 0, 0, CYCLE_MAX_FRAMES, 0, NULL,
     "frames the eye integrates, ending at --time (0: one cycle of the positions)"},
    {0}};

typedef struct cycle_state {
    aa__frames fs;
    double dx[CYCLE_MAX_FRAMES], dy[CYCLE_MAX_FRAMES], wt[CYCLE_MAX_FRAMES];
} cycle_state;

/* positions=msaaN, N = 2, 4, 8, 16: the standard multisample positions
 * (supersample.c), in 1/16 pixel from the centre, y down */
static const signed char (*positions(const double *p, int *m))[2]
{
    *m = 2 << (int)p[P_POSITIONS];
    return aa_msaa_positions(*m);
}

static int window(const double *p)
{
    int m;
    positions(p, &m);
    return (int)p[P_FRAMES] > 0 ? (int)p[P_FRAMES] : m;
}

static int cycle_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "cycle samples points and has no prefilter; it is measured "
                                  "against the box reference (use -f box)");
    return AA_OK;
}

static int cycle_init(void *state, const double *p, const aa_job *job)
{
    cycle_state *s = state;
    return aa__frames_ready(&s->fs, job, window(p));
}

static int cycle_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    cycle_state *s = state;
    int m, n = window(p), st = aa__frames_ready(&s->fs, job, n);
    if (st)
        return st;
    const signed char(*v)[2] = positions(p, &m);
    if (job->frame_only)
        n = 1;
    const long long base = (long long)floor(job->t);
    for (int k = 0; k < n; k++) { /* frame k of the window: time t - k */
        int q = aa__mod(base - k, m);
        s->dx[k] = v[q][0] / 16.0;
        s->dy[k] = v[q][1] / 16.0;
        s->wt[k] = 1.0 / (double)(n - k); /* running mean, oldest first */
    }
    return aa__frames_render(&s->fs, job, n, s->dx, s->dy, s->wt, out, counters);
}

static void cycle_release(void *state)
{
    cycle_state *s = state;
    aa__frames_free(&s->fs);
}

const aa_method_type aa_method_cycle = {
    {"cycle", "msaa positions visited one per frame, eye's image the mean of a cycle "
              "(Crow fig. 4.1 with msaa offsets)",
     cycle_params},
    sizeof(cycle_state),
    AA_METHOD_TEMPORAL,
    cycle_check,
    cycle_init,
    cycle_render,
    cycle_release};
