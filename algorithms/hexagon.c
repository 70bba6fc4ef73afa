/*
 * hexagon.c: Crow's temporal scheme (Crow 1976, ch. 4, "A temporal scheme",
 * fig. 4.1): "Since the eye integrates over approximately six frames, a
 * cyclic pattern following a random path about the points of a hexagon is
 * appropriate.  The hexagon would have to be about as large as the distance
 * between two dots.  As each node of the hexagon is visited, the data in the
 * scene description is shifted to compensate.  Therefore, the image always
 * stays in the same place on the screen while the dot positions change."
 *
 * Each frame is a point-sampled image (aa_point_sample) whose sample points
 * are the pixel centres moved by one vertex of a hexagon; the image the eye
 * sees is the mean of a window of consecutive frames.  It costs one point
 * sampling per frame and nothing else: Crow's "virtually no additional
 * computation" per frame.
 *
 * Conventions (the choices the text leaves open):
 *
 *  - Frames.  Frame n (an integer, negative allowed) is shown at time n;
 *    a real time T shows frame floor(T).  The eye's image at time T is the
 *    mean of `frames` frames, the scene at times T, T-1, ..., T-frames+1
 *    (each frame the scene at its own time, patterns/README.md, "Animation", so a
 *    moving scene moves between frames), with frame numbers floor(T) - k.
 *    `--frame-only` (job->frame_only) gives the single frame at T.
 *  - Vertex.  Frame n uses vertex order[n mod 6] (mod taken non-negative):
 *    it depends on the frame number only, so a frame looks the same in
 *    every window that holds it, and six consecutive frames use every
 *    vertex once.
 *  - Hexagon.  Vertex v is at (dx, dy) = radius (cos a, sin a) with
 *    a = angle + 60 v degrees, in pixel units with y down (so angles turn
 *    clockwise on the screen).  radius = 0.5, the default, makes the hexagon
 *    one dot across, Crow's "about as large as the distance between two
 *    dots".  angle = 0, the default, puts vertex 0 to the right of the
 *    centre (flat top and bottom).  With angle 0 (or 30) and radius 0.5 two
 *    opposite vertices are a whole pixel apart, so on a still scene their
 *    frames sample the same lattice; other angles give six distinct
 *    lattices, but gain little: RMSE on still crow 256x256 against the box
 *    reference is 0.0660 at angle 0, 0.0641 at 15, 0.0690 at 30 (point
 *    sampling 0.1796).  The radius matters more: 0.0426 at radius 0.4,
 *    0.0983 at 0.6 (angle 15), the hexagon one pixel across being a little
 *    wider than the box.
 *  - Order.  `order` is the cycle of vertices, a word of the six digits.
 *    The twelve words offered are one cycle from each of the twelve classes
 *    of six-vertex cycles up to rotation and reflection of the hexagon, the
 *    starting frame and the direction, for a study of which order the eye
 *    prefers (steps are counted in vertices, 1 = to a neighbour, 3 = to the
 *    opposite vertex):
 *
 *      012345  steps 1 1 1 1 1 1   sequential, around the rim
 *      012354  1 1 1 2 1 2         012453  1 1 2 1 2 3
 *      012543  1 1 3 1 1 3         013254  1 2 1 3 1 2
 *      013542  1 2 2 1 2 2         014352  1 3 1 2 3 2
 *      015342  1 2 2 1 2 2         014523  1 3 1 3 1 3
 *      024135  2 2 3 2 2 1         two triangles, same sense
 *      031425  3 2 3 2 3 1         opposite vertices alternate
 *      024153  2 2 3 2 2 3         two triangles, opposite senses (default)
 *
 *    The default 024153 is the only class whose every step skips at least
 *    one vertex; the mean offset of any 2, 3 or 4 consecutive frames is at
 *    most radius/2, radius/3 and radius/4 from the centre, which no other
 *    class matches (for 2 and 4 frames every other class reaches 0.87 and
 *    0.43 radius; for 3, three classes tie), so an eye that integrates
 *    fewer than six frames sees the least shimmer.  On a still scene a
 *    window of six frames holds each vertex once whatever the order: the
 *    order matters with motion, other window lengths, and for flicker.
 *  - The mean.  The window is accumulated oldest frame first as a running
 *    mean m += (x - m)/k, so a pixel on which all frames agree keeps that
 *    value exactly (a uniform scene renders exactly) and the result never
 *    leaves the range of the frames.  It equals the plain mean up to a few
 *    units in the last place.
 *
 * The frames are sampled and combined by the frame stack the temporal
 * comparators share (frames.h): work goes out in bands of a fixed number
 * of rows, each sampled into the output and a per-thread scratch band, so
 * the image does not depend on the thread count; the placed scenes (one
 * per frame time, or one for a still scene) are made in init and again
 * only for a job of another size, time, motion or thread count.
 *
 * Counters: samples = frames x pixels (pixels for --frame-only);
 * expensive_pixels = 0 (every pixel takes the same path).
 *
 * Limits: no prefilter, so it is measured against the box reference and
 * refuses tent and gauss.  Each frame is still point sampled: detail
 * between the six sample points of a pixel is missed, and a small object
 * flickers as the cycle visits it and leaves it (Crow: "small objects will
 * still disappear between dots and may sometimes flicker noticeably").
 * Its six samples per pixel span a hexagon one pixel across, a little wider
 * than the box filter, so it blurs slightly.  With motion the eye's image
 * is smeared along the motion, as the eye's own integration would.  It
 * helps still and slowly moving images, the case Crow meant ("when the dot
 * positions are constant and the edge position slowly varying, the
 * staircases are quite apparent"); once the motion alone spreads six point
 * frames over distinct positions, the offsets only add error: on crow
 * 256x256 moving (-0.35, 0.2) px a frame, against the mean of the six
 * frames' box references, the eye's image has RMSE 0.097 and six plain
 * point frames 0.051 (still: 0.066 against point's 0.180).
 */
#include "frames.h"
#include "methods.h"

#include <math.h>
#include <string.h>

#define MAX_FRAMES 60

enum { P_RADIUS, P_FRAMES, P_ORDER, P_ANGLE };

#define ORDERS                                                                             \
    "012345|012354|012453|012543|013254|013542|014352|015342|014523|024135|031425|024153"
#define ORDER_DEFAULT 11 /* 024153 */

static const aa_param hexagon_params[] = {
    {"radius", AA_PARAM_REAL, 0.5, 0.0, 1.0, 0, NULL,
     "distance of the hexagon's vertices from the pixel centre, in pixels"},
    {"frames", AA_PARAM_INT, 6, 1, MAX_FRAMES, 0, NULL,
     "frames the eye integrates (the window ends at --time)"},
    {"order", AA_PARAM_CHOICE, ORDER_DEFAULT, 0, 0, 0, ORDERS,
     "cycle of vertices: frame n uses vertex order[n mod 6]"},
    {"angle", AA_PARAM_REAL, 0.0, 0.0, 60.0, 0, NULL,
     "direction of vertex 0 in degrees from +x (y down: clockwise)"},
    {0}};

typedef struct hexagon_state {
    aa__frames fs; /* the scenes of the window's frames and the scratch bands */
} hexagon_state;

static int hexagon_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "hexagon samples points and has no prefilter; it is "
                                  "measured against the box reference (use -f box)");
    return AA_OK;
}

static void hexagon_release(void *state)
{
    hexagon_state *s = state;
    aa__frames_free(&s->fs);
}

/* The digits of the order word chosen by p[P_ORDER]. */
static void order_digits(const double *p, int vertex[6])
{
    const char *word = hexagon_params[P_ORDER].choices;
    for (int k = 0; k < (int)p[P_ORDER]; k++)
        word = strchr(word, '|') + 1;
    for (int k = 0; k < 6; k++)
        vertex[k] = word[k] - '0';
}

static int hexagon_init(void *state, const double *p, const aa_job *job)
{
    hexagon_state *s = state;
    return aa__frames_ready(&s->fs, job, (int)p[P_FRAMES]);
}

static int hexagon_render(void *state, const double *p, const aa_job *job, aa_image *out,
                          aa_counters *counters)
{
    hexagon_state *s = state;
    int st, vertex[6];
    if ((st = aa__frames_ready(&s->fs, job, (int)p[P_FRAMES])))
        return st;
    order_digits(p, vertex);
    const int n = job->frame_only ? 1 : (int)p[P_FRAMES];
    const long long base = (long long)floor(job->t);
    const double r = p[P_RADIUS], deg = M_PI / 180.0;
    double dx[MAX_FRAMES], dy[MAX_FRAMES], wt[MAX_FRAMES];
    for (int k = 0; k < n; k++) { /* frame k of the window: time t - k */
        double a = (p[P_ANGLE] + 60.0 * vertex[aa__mod(base - k, 6)]) * deg;
        dx[k] = r * cos(a);
        dy[k] = r * sin(a);
        wt[k] = 1.0 / (double)(n - k); /* the running mean, oldest frame first */
    }
    return aa__frames_render(&s->fs, job, n, dx, dy, wt, out, counters);
}

const aa_method_type aa_method_hexagon = {
    {"hexagon", "Crow's temporal scheme: frames sampled at hexagon offsets, mean of six "
                "(Crow fig. 4.1)",
     hexagon_params},
    sizeof(hexagon_state),
    AA_METHOD_TEMPORAL | AA_METHOD_FIELDS,
    hexagon_check,
    hexagon_init,
    hexagon_render,
    hexagon_release};
