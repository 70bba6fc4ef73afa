/*
 * hexagon.c: Crow's temporal scheme (Crow 1976, ch. 4, "A temporal scheme",
 * pp. 76-79, fig. 4.1): "It seems clear that a better looking animated image
 * could be obtained by varying the position of the dots from frame to
 * frame.  Since the eye integrates over approximately six frames, a cyclic
 * pattern following a random path about the points of a hexagon is
 * appropriate.  The hexagon would have to be about as large as the
 * distance between two dots [Fig. 4.1].  As each node of the hexagon is
 * visited, the data in the scene description is shifted to compensate.
 * Therefore, the image always stays in the same place on the screen while
 * the dot positions change."  And how: "it is sufficient to set the least
 * significant bits sent to the DACs for each frame" (the CRT's beam moves
 * the dot), or, on a display that cannot, "by moving the entire display".
 *
 * So in Crow's scheme two things move by the same vertex each frame: the
 * point each dot samples, and the dot itself on the screen.  Each frame is
 * a point-sampled image (aa_point_row) whose sample points are the pixel
 * centres moved by one vertex of a hexagon; it costs one point sampling per
 * frame and nothing else: Crow's "virtually no additional computation".
 *
 * The display (`display`).
 *
 *  - screen (the default; Crow's): frame k's dot of pixel p is shown at
 *    the point it sampled, p's centre c_p plus the vertex d_k, as a
 *    uniform square one pixel wide (the dots of a frame tile the screen:
 *    Crow's CRT spot, "adjusted to present a flat field", ch. 2, made the
 *    flattest it can be; the ring of dots just outside the image is sampled
 *    and shown too, so the field is flat up to the image's border).  The
 *    eye's image is the mean of the screens of the window's frames, seen
 *    through the image's fixed pixel squares: pixel q is
 *
 *        E(q) = (1/n) sum_k sum_p x_k(p) a(q - p - d_k),
 *        a(u, v) = max(0, 1 - |u|) max(0, 1 - |v|),
 *
 *    x_k(p) the scene at frame k's time sampled at c_p + d_k, and a the
 *    area of pixel q that the dot covers: each frame is the bilinear mix of
 *    the four dots nearest to q.  Its reference (harness/bench/display.c,
 *    the same for every method shown this way) is the same screen with
 *    each dot showing its exact value, the scene at frame k's time
 *    convolved with the box at c_p + d_k:
 *
 *        R(q) = (1/n) sum_k sum_p r_k(p) a(q - p - d_k).
 *
 *    The method and its reference are seen through the same dots, so the
 *    blur of the moving dots, which any image shown on this screen would
 *    suffer, is not counted as the method's error; with radius 0 both are
 *    the ordinary image and reference.  `--frame-only` gives one frame's
 *    screen seen through the pixel squares (its reference that frame's
 *    R), so the temporal metrics (eye_rmse over windows of frames) compare
 *    the eye's images with the eye's references.
 *  - fixed (a variant, the model of earlier versions): the dot that sampled
 *    c_p + d_k is shown at pixel p's own place, the display never moves,
 *    and the image is measured against the ordinary box reference at the
 *    pixel centres.  This is temporal supersampling on a fixed grid, not
 *    Crow's display: a dot shows the scene up to half a pixel from where it
 *    is shown, which moving scenes expose (below).
 *
 * The order of the vertices (`order`).
 *
 *  - random (the default; Crow's "a cyclic pattern following a random path
 *    about the points of a hexagon"): the frames go in cycles of six, and
 *    each cycle visits the six vertices once, in an order drawn at random
 *    for that cycle (a uniform permutation, Fisher-Yates).  The cycles are
 *    frames 6m - 5 .. 6m, so the window of six frames ending at frame 0
 *    (the still image at --time 0) is one whole cycle; a window that
 *    straddles two cycles may see a vertex twice and miss another.  The
 *    permutations come from a counter-based stream of their own (a fixed
 *    key and the cycle's number), not from the job's seed: the path is a
 *    property of the display, as Crow's bits sent to the DACs would be,
 *    so the image does not depend on --seed and every run shows the same
 *    path.
 *  - the twelve words (variants): one fixed cycle repeated every six
 *    frames, frame n showing vertex order[n mod 6] (mod taken
 *    non-negative), so every window of six frames sees each vertex once.
 *    One cycle from each of the twelve classes of six-vertex cycles up to
 *    rotation and reflection of the hexagon, the starting frame and the
 *    direction (steps counted in vertices, 1 = to a neighbour, 3 = to the
 *    opposite vertex):
 *
 *      012345  steps 1 1 1 1 1 1   sequential, around the rim
 *      012354  1 1 1 2 1 2         012453  1 1 2 1 2 3
 *      012543  1 1 3 1 1 3         013254  1 2 1 3 1 2
 *      013542  1 2 2 1 2 2         014352  1 3 1 2 3 2
 *      015342  1 2 2 1 2 2         014523  1 3 1 3 1 3
 *      024135  2 2 3 2 2 1         two triangles, same sense
 *      031425  3 2 3 2 3 1         opposite vertices alternate
 *      024153  2 2 3 2 2 3         two triangles, opposite senses
 *
 *    024153 (the default of earlier versions) is the only class whose every
 *    step skips at least one vertex; the mean offset of any 2, 3 or 4
 *    consecutive frames is at most radius/2, radius/3 and radius/4 from the
 *    centre, which no other class matches (for 2 and 4 frames every other
 *    class reaches 0.87 and 0.43 radius; for 3, three classes tie), so an
 *    eye that integrates fewer than six frames sees the least shimmer.  It
 *    is a chosen path, not a random one, hence not the default.
 *
 * Other conventions (the choices the text leaves open):
 *
 *  - Frames.  Frame n (an integer, negative allowed) is shown at time n;
 *    a real time T shows frame floor(T).  The eye's image at time T is the
 *    mean of `frames` frames, the scene at times T, T-1, ..., T-frames+1
 *    (each frame the scene at its own time, patterns/README.md,
 *    "Animation", so a moving scene moves between frames), with frame
 *    numbers floor(T) - k.  A frame looks the same in every window that
 *    holds it.
 *  - Hexagon.  Vertex v is at (dx, dy) = radius (cos a, sin a) with
 *    a = angle + 60 v degrees, in pixel units with y down (so angles turn
 *    clockwise on the screen).  radius = 0.5, the default, makes the
 *    hexagon one dot across, Crow's "about as large as the distance between
 *    two dots".  angle = 0, the default, puts vertex 0 to the right of the
 *    centre (flat top and bottom).
 *  - The mean.  The window is accumulated oldest frame first as a running
 *    mean m += (x - m)/k, and a screen frame mixes its dots as
 *    x1 + phi (x0 - x1), so a pixel on which everything agrees keeps that
 *    value exactly (a uniform scene renders exactly) and the result never
 *    leaves the range of the dots.  It equals the plain mean up to a few
 *    units in the last place.
 *
 * Measured (aabench run -p crow -s 128x128, box; still, the RMSE of the
 * eye's image at --time 0; moving (0.37, 0.11) px a frame, eye_rmse and
 * mean flicker over 24 frames with a window of 6, each method against its
 * own references: the screen's for display=screen, the ordinary ones
 * otherwise):
 *
 *                                        still RMSE   eye_rmse   flicker
 *     point                                 0.2574      0.0692    0.226
 *     hexagon (screen, random path)         0.0805      0.0675    0.145
 *     hexagon:order=024153                  0.0805      0.0566    0.147
 *     hexagon:display=fixed                 0.0957      0.1541    0.322
 *     hexagon:display=fixed,order=024153    0.0957      0.1326    0.325
 *
 * Still, any order gives the same image (a window of one cycle) and the
 * screen is nearer its reference than the fixed display is to its own.
 * Moving, the fixed display is twice as far from the eye's reference as
 * point sampling, since each dot shows the scene up to half a pixel from
 * where it sampled it; on the screen the dot is where it sampled, and the
 * eye's image is about as near its reference as point's (the random path)
 * or nearer (024153), with a third less flicker.  The twelve fixed cycles
 * range from eye_rmse 0.056 (024153, 012354, 014352) to 0.078 (013254);
 * a random path averages over them.  At 12 frames (two windows' worth) the
 * random path's eye_rmse is 0.075 against point's 0.069: which windows
 * straddle two cycles matters over short runs.  In the `temporal` suite
 * (128x128, the same motion) the default's eye_rmse is below point's on
 * dots (0.0042 against 0.0080) and star (0.038 against 0.061) but above
 * it on fence (0.066 against 0.040: bars 0.45 px apart, beyond what any
 * offset of the samples can resolve).
 *
 * The frames are sampled and combined by the frame stack the temporal
 * comparators share (frames.h): for display=fixed in bands of a fixed
 * number of rows, each sampled into the output and a per-thread scratch
 * band; for display=screen in a block of rows per thread, band by band and
 * within a band frame by frame, the band's rows of dots (one more than its
 * rows of pixels, the first carried over from the band above) sampled,
 * mixed along x, then along y into the output.  Either way the image does
 * not depend on the thread count; the placed scenes (one
 * per frame time, or one for a still scene) are made in init and again
 * only for a job of another size, time, motion or thread count.
 *
 * Counters: samples = frames x pixels for display=fixed, frames x
 * (W + 1)(H + 1) dots for display=screen (pixels, or (W + 1)(H + 1), for
 * --frame-only; a thread that starts inside the image samples its first
 * row of dots again, which is not counted); expensive_pixels = 0 (every
 * pixel takes the same path).
 *
 * Limits: no prefilter, so it is measured against the box reference (seen
 * through its dots) and refuses tent and gauss.  Each frame is still point
 * sampled: detail between the six sample points of a pixel is missed, and
 * a small object flickers as the cycle visits it and leaves it (Crow:
 * "small objects will still disappear between dots and may sometimes
 * flicker noticeably").  The screen's square dots are a model: Crow's CRT
 * spot is Gaussian (ch. 2), and a wider spot would blur method and
 * reference alike.  With motion the eye's image is smeared along the
 * motion, as the eye's own integration would.
 */
#include "frames.h"
#include "methods.h"

#include <math.h>
#include <string.h>

#define MAX_FRAMES 60

enum { P_RADIUS, P_FRAMES, P_ORDER, P_ANGLE, P_DISPLAY };
enum { D_SCREEN, D_FIXED };

#define ORDERS                                                                             \
    "012345|012354|012453|012543|013254|013542|014352|015342|014523|024135|031425|024153|" \
    "random"
#define ORDER_RANDOM 12

/* The key of the random path's stream (aa_rng_seed's seed): any fixed
 * value; the digits of "Crow fig. 4.1". */
#define PATH_KEY 0x43726f77f41ull

static const aa_param hexagon_params[] = {
    {"radius", AA_PARAM_REAL, 0.5, 0.0, 1.0, 0, NULL,
     "distance of the hexagon's vertices from the pixel centre, in pixels"},
    {"frames", AA_PARAM_INT, 6, 1, MAX_FRAMES, 0, NULL,
     "frames the eye integrates (the window ends at --time)"},
    {"order", AA_PARAM_CHOICE, ORDER_RANDOM, 0, 0, 0, ORDERS,
     "random: each cycle of six frames visits the vertices in a random order (Crow); a "
     "word: frame n uses vertex word[n mod 6]"},
    {"angle", AA_PARAM_REAL, 0.0, 0.0, 60.0, 0, NULL,
     "direction of vertex 0 in degrees from +x (y down: clockwise)"},
    {"display", AA_PARAM_CHOICE, D_SCREEN, 0, 0, 0, "screen|fixed",
     "screen: each dot shown where it sampled (Crow); fixed: at its pixel"},
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

/* The vertex frame n shows. */
static int vertex_of(const double *p, long long n)
{
    if ((int)p[P_ORDER] == ORDER_RANDOM) {
        /* cycle c holds frames 6c - 5 .. 6c; frame n is its (n + 5) mod 6-th */
        long long c = n + 5 >= 0 ? (n + 5) / 6 : -((-(n + 5) + 5) / 6);
        int perm[6] = {0, 1, 2, 3, 4, 5};
        aa_rng r;
        aa_rng_seed(&r, PATH_KEY, 0, (uint64_t)c);
        for (int k = 5; k > 0; k--) { /* Fisher-Yates */
            int m = (int)(aa_rng_uniform(&r) * (k + 1));
            int t = perm[k];
            perm[k] = perm[m], perm[m] = t;
        }
        return perm[aa__mod(n + 5, 6)];
    }
    const char *word = hexagon_params[P_ORDER].choices;
    for (int k = 0; k < (int)p[P_ORDER]; k++)
        word = strchr(word, '|') + 1;
    return word[aa__mod(n, 6)] - '0';
}

/* The offsets of the n frames of the window ending at job->t (frame k of
 * the window at time t - k). */
static void offsets(const double *p, const aa_job *job, int n, double *dx, double *dy)
{
    const long long base = (long long)floor(job->t);
    const double r = p[P_RADIUS], deg = M_PI / 180.0;
    for (int k = 0; k < n; k++) {
        double a = (p[P_ANGLE] + 60.0 * vertex_of(p, base - k)) * deg;
        dx[k] = r * cos(a);
        dy[k] = r * sin(a);
    }
}

static int window(const double *p, const aa_job *job)
{
    return job->frame_only ? 1 : (int)p[P_FRAMES];
}

static int hexagon_init(void *state, const double *p, const aa_job *job)
{
    hexagon_state *s = state;
    int st = aa__frames_ready(&s->fs, job, (int)p[P_FRAMES]);
    if (!st && (int)p[P_DISPLAY] == D_SCREEN)
        st = aa__frames_screen(&s->fs);
    return st;
}

static int hexagon_render(void *state, const double *p, const aa_job *job, aa_image *out,
                          aa_counters *counters)
{
    hexagon_state *s = state;
    int st;
    if ((st = hexagon_init(s, p, job)))
        return st;
    const int n = window(p, job);
    double dx[MAX_FRAMES], dy[MAX_FRAMES], wt[MAX_FRAMES];
    offsets(p, job, n, dx, dy);
    for (int k = 0; k < n; k++)
        wt[k] = 1.0 / (double)(n - k); /* the running mean, oldest frame first */
    if ((int)p[P_DISPLAY] == D_SCREEN)
        return aa__frames_render_screen(&s->fs, job, n, dx, dy, wt, out, counters);
    return aa__frames_render(&s->fs, job, n, dx, dy, wt, out, counters);
}

/* Where the frames are shown (core.h, "Displays"): on the screen, each
 * frame's dots moved by its vertex, the frames weighted alike. */
static int hexagon_display(const double *p, const aa_job *job, aa_display_frame *frames,
                           int *count)
{
    *count = 0;
    if ((int)p[P_DISPLAY] != D_SCREEN)
        return AA_OK;
    const int n = window(p, job);
    double dx[MAX_FRAMES], dy[MAX_FRAMES];
    offsets(p, job, n, dx, dy);
    for (int k = 0; k < n; k++)
        frames[k] = (aa_display_frame){job->t - k, dx[k], dy[k], 1.0 / n};
    *count = n;
    return AA_OK;
}

const aa_display_method_type aa_method_hexagon_display = {
    {{"hexagon", "Crow's temporal scheme: frames sampled and shown at hexagon offsets along a "
                 "random path, the eye's mean of six (Crow fig. 4.1)",
      hexagon_params},
     sizeof(hexagon_state),
     AA_METHOD_TEMPORAL | AA_METHOD_FIELDS | AA_METHOD_DISPLAY,
     hexagon_check,
     hexagon_init,
     hexagon_render,
     hexagon_release},
    hexagon_display};
