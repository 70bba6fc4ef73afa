/*
 * morph.c: morphological antialiasing of the completed point-sampled image,
 * `mlaa` (Reshetov 2009, "Morphological antialiasing", HPG) and `smaa`
 * (Jimenez, Echevarria, Sousa and Gutierrez 2012, "SMAA: Enhanced Subpixel
 * Morphological Antialiasing", Eurographics, SMAA 1x).  Both point sample
 * the scene at pixel centres (aa_point_sample, as `point` and `trio`), find
 * the discontinuities between neighbouring pixels, read the shapes their
 * lines make, and blend each pixel beside a line with the pixel across it
 * by the area the reconstructed edge cuts from it.  The same family as
 * Crow's trio (trio.c), twenty years on.
 *
 * What the papers specify, and what is chosen here.
 *
 * 1. Discontinuities (edges).  Between two pixels sharing a side.
 *    mlaa: Reshetov looks for colour differences between neighbours and
 *    leaves the test to the implementer; here the largest channel
 *    difference above `threshold` (1/8, as trio: the point-sampled image
 *    holds only the scene's flat colours, so any value below their smallest
 *    contrast finds every edge, and edges between colours of equal luma are
 *    found).
 *    smaa: the paper's luma edge detection: luma Y = 0.2126 R + 0.7152 G
 *    + 0.0722 B (Rec. 709 weights), an edge where |dY| >= `threshold`
 *    (0.1, its high preset), then its local contrast adaptation: an edge is
 *    kept only if its contrast is at least 1/`adapt` (adapt = 2, the
 *    paper's factor) of the largest contrast among the edges next to it.
 *    The paper's neighbourhood is the edges of the pixel and of the pixels
 *    before it; here, symmetrically, the six other sides of the two pixels
 *    the edge separates.  The paper works on gamma-encoded colours; here
 *    luma is taken of the linear values the benchmark renders (a choice:
 *    on black and white scenes it finds the same edges).
 * 2. Lines and shapes.  Along each boundary line between two pixel rows
 *    (columns), the edges form runs.  At each end of a run the boundary may
 *    turn across the line, to the near side (row above, column left) or the
 *    far side: Reshetov's "secondary edge", SMAA's "crossing edge".  Two
 *    turns to opposite sides make a Z, to the same side a U, one an L
 *    (Reshetov's pattern detection).  A turn to both sides at once (a
 *    cross of four regions) is taken as no turn here (a choice).
 * 3. The reconstructed edge (Reshetov's blending weights; SMAA's area
 *    texture).  Z and U shapes are split at the run's middle into two L
 *    shapes; each L's edge is the half-line from the middle of its turn
 *    (half a pixel off the boundary line, at the run's end) to the boundary
 *    line at the run's middle.  A lone L (the other end open: the end of an
 *    edge, the image border) gets its half-line only, as the half of a
 *    split shape would (a choice; SMAA's texture does the same for its
 *    one-ended patterns).  A pixel beside the run takes the colour across
 *    the line in proportion to the part of its square beyond the
 *    reconstructed edge: the area of a trapezoid (or triangle) in its
 *    column, computed exactly here (aa_morph_area).  On a straight edge whose
 *    staircase's turns have their middles on the edge, this is the exact
 *    box-filtered image (tests/test_postaa.c).
 * 4. Blending.  Each pixel blends along rows (with the pixels above and
 *    below) or along columns, whichever direction gives it the larger share
 *    (rows on a tie).  This is SMAA's neighbourhood blending pass.
 *    Reshetov blends the horizontal and vertical passes without saying how
 *    they combine; summing them would count twice the corner that a
 *    one-pixel step of a staircase cuts, since the row run beside the step
 *    and the column run of the step itself both draw it (a run one pixel
 *    long with turns to both sides is the 45-degree line through that
 *    corner), so mlaa takes one direction too, a choice.
 *    mlaa: the pixel takes each of the two shares of its direction of the
 *    colour across that side (scaled to sum to at most 1).
 *    smaa: as the paper's two bilinear fetches: the fetch toward each side
 *    at its share, the two weighted by the shares (each side share^2 /
 *    (sum of both)).
 *    Results are clamped to the range of the colours blended.
 * 5. Search length.  mlaa: whole runs (Reshetov's CPU algorithm scans each
 *    line).  smaa: each edge pixel searches at most `search` pixels each way
 *    (the high preset's 16 steps of two pixels reach 32); a run longer than
 *    that is read as ending there with no turn (open), as the paper's
 *    search that stops at its limit does.
 * 6. Area texture (SMAA's pattern classification): the area of step 3
 *    for each pattern (the turn at each end: none, near, far, both) and the
 *    distances to the two ends, precomputed in init for distances 0 ..
 *    `search` from the definition (aa_morph_area), and read per pixel.  The
 *    paper stores it as a texture with square-root-spaced distances because
 *    a GPU fetches it bilinearly; here it is a table of exact values.  The
 *    paper's search texture only decodes which of two edges a bilinear
 *    fetch saw, so the search advances two pixels a step; here the search
 *    reads the edges themselves, which is what the texture encodes.
 * 7. Sharp corners (SMAA's "sharp geometric features"): where the
 *    turn at the end nearer the pixel continues beyond the pixel's row (the
 *    boundary runs on straight across: a corner of a shape, not a step of a
 *    staircase), the pixel's share is scaled by `rounding` (0.25, SMAA's
 *    default corner rounding of 25%; 1 blends as MLAA).  With both ends
 *    equally near, each counts half.
 * 8. Diagonal patterns (smaa, `diag` = 1).  The paper searches lines near
 *    45 degrees along the diagonals, up to `dsearch` steps each way (8 in
 *    its high preset), reads the sides crossing the line at its two ends,
 *    and takes the shares from a second area table; a pixel on a diagonal
 *    line blends by it and not by its orthogonal patterns.  The details
 *    below are those of the authors' implementation (SMAA.hlsl's diagonal
 *    search and weights, Scripts/AreaTex.py's diagonal areas), which the
 *    paper's text leaves to its figures and code.
 *    A pixel with its north side looks along two diagonals.  Rising to the
 *    right: the pixels down-left (searched only if it has its west side
 *    too) and up-right that have both their north and west sides, each a
 *    step of the staircase; down-left, a pixel with its north side only
 *    ends the line as its first step.  Falling to the right: the same with
 *    north and east sides, up-left, and down-right (searched only if it
 *    has its east side; a pixel with its north side only is the last
 *    step).  A line of four steps or more (the distances to its ends summing
 *    to more than 2) is blended; a search that runs out leaves its end
 *    unknown.  At a found end, the crossing sides: vertical (the line turns
 *    down at its lower end, up at its upper), horizontal (turns left,
 *    right), both, or neither (unknown).
 *    The table, in the frame of the rising line with y up: the steps are
 *    the squares [1 + l, 2 + l] x [l, 1 + l] (l = 0 .. d-1, d = the two
 *    distances + 1), the outer corners (1 + l, 1 + l) on y = x, the inner
 *    ones on y = x - 1.  The reconstructed line runs between the ends of
 *    the staircase: at the lower end (1, 0) (the foot of the first step)
 *    when it turns down, (1, 1) when it turns left; at the upper end
 *    (1 + d, 1 + d) when it turns up, (1 + d, d) when it turns right; an
 *    end turning both ways or unknown has two candidates, the outer and the
 *    inner one (unknown: (0, 0) and (1, 0), (d, d) and (1 + d, d)), and the
 *    shares are the mean over the lines joining the candidates (outer with
 *    outer, inner with inner, or each with the other end's only one).  The
 *    step's pixel takes the part of its square above the line, the pixel
 *    above it the part of its square below (aa_morph_diag_area), computed
 *    exactly for every pattern and pair of distances 0 .. `dsearch` in init
 *    (the authors estimate them by 30 x 30 point samples and store them in
 *    8 bits).  The falling line uses the same table upside down: its
 *    steps' pixels are the table's upper pixels.  The pixel's share across
 *    its north side (and the pixel above's) is the sum of the two
 *    diagonals' in place of the orthogonal one, and its west side blends
 *    nothing.  Outside the image there are no sides (the GPU clamps its
 *    reads to the border; a choice).
 *    What it gives: a long 45-degree staircase (no end within reach) is the
 *    mean of the lines through its outer and its inner corners, 1/4 of the
 *    colour across for every pixel beside it, where the box-filtered edge
 *    through the steps' middles cuts 1/8 (the orthogonal patterns' reading,
 *    exact there); over the edge's positions within the same staircase the
 *    box value of such a pixel is (1 - t)^2 / 2, t in (0, 1), mean 1/6.
 *    Near 45 degrees, where the orthogonal patterns see runs of one and
 *    two, the diagonal reading halves the error or better (slope 1/1.2,
 *    tests/test_postaa.c).  On scenes: lower on the star, rules.svg and
 *    logo.svg, higher on mono.svg, curves.svg and text at 24 ppem
 *    (algorithms/README.md, results/README.md).
 *
 * Variant: `smaa:diag=0`, without the diagonal patterns (step 8): the
 * orthogonal filter alone, staircases of one-pixel runs read as MLAA reads
 * them.  Not here: the temporal and multisample modes (T2x, S2x, 4x): this
 * is SMAA 1x's spatial filter.
 *
 * Counters: samples = pixels (one point sample each); expensive_pixels =
 * pixels beside at least one edge.
 *
 * Cost.  Every pixel is visited in each pass (edges, the row lines, the
 * column lines, smaa's diagonals, blending), and the column lines walk the image down its
 * columns; nothing skips empty stretches as trio does, so on scenes with
 * few edges these cost about four times trio (1.2 against 0.3 ms on the
 * SVG scenes at 256x256, one thread).  smaa's diagonal searches run only
 * from pixels with a north side and stop at the first step missing: on
 * the vector suite's SVG scenes its fastest renders took 1.4 to 1.5 ms,
 * smaa:diag=0's 1.3 to 1.5 (one thread, a busy machine:
 * results/README.md).
 *
 * Limits.  What point sampling lost (thin objects between centres, moire)
 * cannot come back; a 45-degree staircase is read as the 45-degree line
 * through its turns' middles by mlaa and smaa:diag=0 (exact for that edge,
 * tests/test_postaa.c) and as 1/4 of the colour across by smaa's diagonal
 * table, wherever the edge lies; the edge's position inside a pixel is unknown,
 * so reconstructed lines go through the middles of the turns and can be
 * half a pixel off; shapes narrower than two pixels are read as U shapes
 * and smeared; corners of shapes are rounded (mlaa fully, smaa by
 * `rounding`); the search is per frame, so in motion the blend moves with
 * the staircase.  Measured against the box
 * reference; box only.
 */
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { M_MLAA, M_SMAA };

/* ---- the reconstructed edge's areas ---- */

/* Integral over [x0, x1] (clipped to [a, b]) of the linear function that is
 * fa at a and fb at b. */
static double lin_integral(double a, double b, double fa, double fb, double x0, double x1)
{
    x0 = x0 > a ? x0 : a;
    x1 = x1 < b ? x1 : b;
    if (!(x1 > x0))
        return 0.0;
    double g0 = fa + (fb - fa) * ((x0 - a) / (b - a));
    double g1 = fa + (fb - fa) * ((x1 - a) / (b - a));
    return (x1 - x0) * 0.5 * (g0 + g1);
}

void aa_morph_area(int e_left, int e_right, int d_left, int d_right, double share[2])
{
    /* the run is [0, d]; the pixel [d_left, d_left + 1]; offsets +1/2 into
     * the near pixel for a near turn, -1/2 for a far one, 0 otherwise */
    static const double turn[4] = {0.0, 0.5, -0.5, 0.0};
    const double d = (double)d_left + (double)d_right + 1.0, c = 0.5 * d;
    const double x0 = d_left, x1 = x0 + 1.0;
    double l = lin_integral(0.0, c, turn[e_left & 3], 0.0, x0, x1);
    double r = lin_integral(c, d, 0.0, turn[e_right & 3], x0, x1);
    share[0] = (l > 0 ? l : 0.0) + (r > 0 ? r : 0.0);
    share[1] = (l < 0 ? -l : 0.0) + (r < 0 ? -r : 0.0);
}

/* ---- the diagonal lines' areas ----
 * In the frame of step 8 (y up): the part of the unit square with lower
 * left corner (px, py) on the right of the line through a and b, directed
 * from a to b (the square clipped by the half-plane, then the shoelace
 * formula: exact up to rounding). */
static double square_right_of(const double a[2], const double b[2], double px, double py)
{
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double sq[4][2] = {{px, py}, {px + 1, py}, {px + 1, py + 1}, {px, py + 1}};
    double poly[8][2], f[4];
    int n = 0;
    for (int k = 0; k < 4; k++) /* > 0: left of the line */
        f[k] = dx * (sq[k][1] - a[1]) - dy * (sq[k][0] - a[0]);
    for (int k = 0; k < 4; k++) {
        const int m = (k + 1) & 3;
        if (f[k] <= 0) {
            poly[n][0] = sq[k][0], poly[n][1] = sq[k][1];
            n++;
        }
        if ((f[k] < 0 && f[m] > 0) || (f[k] > 0 && f[m] < 0)) {
            const double t = f[k] / (f[k] - f[m]);
            poly[n][0] = sq[k][0] + t * (sq[m][0] - sq[k][0]);
            poly[n][1] = sq[k][1] + t * (sq[m][1] - sq[k][1]);
            n++;
        }
    }
    double twice = 0.0;
    for (int k = 0; k < n; k++) {
        const int m = k + 1 < n ? k + 1 : 0;
        twice += poly[k][0] * poly[m][1] - poly[m][0] * poly[k][1];
    }
    return 0.5 * fabs(twice);
}

void aa_morph_diag_area(int e_left, int e_right, int d_left, int d_right, double share[2])
{
    /* the candidate ends of the line (step 8): [0] on the outer corners'
     * line y = x, [1] on the inner corners' line y = x - 1; the right end's
     * are offset by (d, d) */
    const double d = (double)d_left + (double)d_right + 1.0;
    double l[2][2], r[2][2];
    int nl = 2, nr = 2;
    switch (e_left & 3) {
    case 1: /* the line turns down: from the foot of the first step */
        l[0][0] = 1, l[0][1] = 0, nl = 1;
        break;
    case 2: /* the line turns left: from the top of the first step */
        l[0][0] = 1, l[0][1] = 1, nl = 1;
        break;
    case 3: /* both */
        l[0][0] = 1, l[0][1] = 1, l[1][0] = 1, l[1][1] = 0;
        break;
    default: /* unknown: the staircase going on, or ending at its foot */
        l[0][0] = 0, l[0][1] = 0, l[1][0] = 1, l[1][1] = 0;
    }
    switch (e_right & 3) {
    case 1: /* the line turns up: to the top of the crossing side */
        r[0][0] = 1 + d, r[0][1] = 1 + d, nr = 1;
        break;
    case 2: /* the line turns right: to the top of the last step */
        r[0][0] = 1 + d, r[0][1] = d, nr = 1;
        break;
    case 3:
        r[0][0] = 1 + d, r[0][1] = 1 + d, r[1][0] = 1 + d, r[1][1] = d;
        break;
    default:
        r[0][0] = d, r[0][1] = d, r[1][0] = 1 + d, r[1][1] = d;
    }
    /* two candidates at an end are each paired with the other end's
     * candidate of the same kind (outer with outer, inner with inner), or
     * with its only one; the areas are averaged */
    const int n = nl > nr ? nl : nr;
    const double px = 1.0 + d_left, py = d_left;
    share[0] = share[1] = 0.0;
    for (int k = 0; k < n; k++) {
        const double *a = l[nl > 1 ? k : 0], *b = r[nr > 1 ? k : 0];
        share[0] += 1.0 - square_right_of(a, b, px, py);
        share[1] += square_right_of(a, b, px, py + 1.0);
    }
    share[0] /= n, share[1] /= n;
}

/* ---- parameters ---- */

enum { P_THRESHOLD };
enum { S_THRESHOLD, S_ADAPT, S_SEARCH, S_ROUNDING, S_DIAG, S_DSEARCH };

static const aa_param mlaa_params[] = {
    {"threshold", AA_PARAM_REAL, 0.125, 0.0, 1.0, 0, NULL,
     "a larger difference in any channel between neighbours is an edge (1: none)"},
    {0}};

static const aa_param smaa_params[] = {
    {"threshold", AA_PARAM_REAL, 0.1, 0.0, 1.0, 0, NULL,
     "a luma difference at least this large is an edge (the paper's high preset: 0.1)"},
    {"adapt", AA_PARAM_REAL, 2.0, 1.0, 1e9, 0, NULL,
     "local contrast adaptation: an edge is dropped when a neighbouring edge's contrast "
     "exceeds adapt times its own (1e9: off)"},
    {"search", AA_PARAM_INT, 32, 1, 256, 0, NULL,
     "pixels searched each way along a line for its ends (high preset: 32)"},
    {"rounding", AA_PARAM_REAL, 0.25, 0.0, 1.0, 0, NULL,
     "share kept at sharp corners (0.25: SMAA's default 25%; 1: as MLAA)"},
    {"diag", AA_PARAM_INT, 1, 0, 1, 0, NULL,
     "1: diagonal patterns searched and blended from the diagonal area table; 0: the "
     "orthogonal patterns only"},
    {"dsearch", AA_PARAM_INT, 8, 1, 20, 0, NULL,
     "steps searched each way along a diagonal for its ends (high preset: 8; the "
     "authors allow up to 20)"},
    {0}};

/* ---- state ---- */

typedef struct morph_state {
    int w, h, ready, search, dsearch; /* dsearch 0: no diagonal patterns */
    double *img;          /* the point samples */
    unsigned char *hm;    /* edge between (i, j) and (i, j+1) */
    unsigned char *vm;    /* edge between (i, j) and (i+1, j) */
    double *hn, *hf;      /* row line j below pixel (i, j): near (upper) and far shares */
    double *vn, *vf;      /* column line i right of (i, j): near (left) and far shares */
    double *area;         /* smaa: the area table, 16 x (search+1)^2 x 2 */
    double *darea;        /* smaa: the diagonal area table, 16 x (dsearch+1)^2 x 2 */
} morph_state;

static int morph_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "mlaa and smaa post-process point samples and have no "
                                  "prefilter; they are measured against the box reference "
                                  "(use -f box)");
    return AA_OK;
}

static void morph_release(void *state)
{
    morph_state *s = state;
    free(s->img);
    free(s->hm);
    free(s->vm);
    free(s->hn);
    free(s->hf);
    free(s->vn);
    free(s->vf);
    free(s->area);
    free(s->darea);
    memset(s, 0, sizeof *s);
}

static size_t area_at(int search, int el, int er, int dl, int dr)
{
    const size_t n = (size_t)search + 1;
    return 2 * ((((size_t)(el * 4 + er)) * n + (size_t)dl) * n + (size_t)dr);
}

static int prepare(morph_state *s, int smaa, int search, int dsearch, const aa_job *job)
{
    morph_release(s);
    const size_t n = (size_t)job->w * (size_t)job->h;
    s->w = job->w, s->h = job->h, s->search = search, s->dsearch = dsearch;
    int ok = (s->img = calloc(n * 3, sizeof *s->img)) && (s->hm = calloc(n, 1)) &&
             (s->vm = calloc(n, 1)) && (s->hn = calloc(n, sizeof(double))) &&
             (s->hf = calloc(n, sizeof(double))) && (s->vn = calloc(n, sizeof(double))) &&
             (s->vf = calloc(n, sizeof(double)));
    if (ok && smaa) {
        const size_t k = (size_t)search + 1;
        ok = (s->area = malloc(16 * k * k * 2 * sizeof *s->area)) != NULL;
        if (ok)
            for (int el = 0; el < 4; el++)
                for (int er = 0; er < 4; er++)
                    for (int dl = 0; dl <= search; dl++)
                        for (int dr = 0; dr <= search; dr++)
                            aa_morph_area(el, er, dl, dr,
                                          s->area + area_at(search, el, er, dl, dr));
    }
    if (ok && smaa && dsearch > 0) {
        const size_t k = (size_t)dsearch + 1;
        ok = (s->darea = malloc(16 * k * k * 2 * sizeof *s->darea)) != NULL;
        if (ok)
            for (int el = 0; el < 4; el++)
                for (int er = 0; er < 4; er++)
                    for (int dl = 0; dl <= dsearch; dl++)
                        for (int dr = 0; dr <= dsearch; dr++)
                            aa_morph_diag_area(el, er, dl, dr,
                                               s->darea + area_at(dsearch, el, er, dl, dr));
    }
    if (!ok) {
        morph_release(s);
        return aa_fail(AA_ENOMEM, "out of memory for the %dx%d post-process buffers", job->w,
                       job->h);
    }
    /* calloc'd pages are touched by the first render; touch them now so
     * page faults are not timed */
    memset(s->img, 0, n * 3 * sizeof *s->img);
    memset(s->hm, 0, n);
    memset(s->vm, 0, n);
    memset(s->hn, 0, n * sizeof(double));
    memset(s->hf, 0, n * sizeof(double));
    memset(s->vn, 0, n * sizeof(double));
    memset(s->vf, 0, n * sizeof(double));
    s->ready = 1;
    return AA_OK;
}

/* ---- edges ---- */

static inline double max_channel_diff(const double *a, const double *b)
{
    double d = fabs(a[0] - b[0]), e = fabs(a[1] - b[1]), f = fabs(a[2] - b[2]);
    d = d > e ? d : e;
    return d > f ? d : f;
}

static void mlaa_edges(morph_state *s, double threshold, int threads)
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const double *a = s->img + 3 * ((size_t)j * (size_t)w + (size_t)i);
            size_t at = (size_t)j * (size_t)w + (size_t)i;
            s->hm[at] = j + 1 < h && max_channel_diff(a, a + 3 * (size_t)w) > threshold;
            s->vm[at] = i + 1 < w && max_channel_diff(a, a + 3) > threshold;
        }
}

static inline double luma709(const double *c)
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

/* SMAA's luma edges with local contrast adaptation.  The contrasts go to
 * hn and vn first (free until the shares are made). */
static void smaa_edges(morph_state *s, double threshold, double adapt, int threads)
{
    const int w = s->w, h = s->h;
    double *ch = s->hn, *cv = s->vn; /* contrast across each side, 0 past the border */
#pragma omp parallel num_threads(threads)
    {
#pragma omp for schedule(static)
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                size_t at = (size_t)j * (size_t)w + (size_t)i;
                const double *a = s->img + 3 * at;
                double y = luma709(a);
                ch[at] = j + 1 < h ? fabs(y - luma709(a + 3 * (size_t)w)) : 0.0;
                cv[at] = i + 1 < w ? fabs(y - luma709(a + 3)) : 0.0;
            }
#pragma omp for schedule(static)
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                size_t at = (size_t)j * (size_t)w + (size_t)i;
                /* the edge below (i, j): the other sides of (i, j) and (i, j+1) */
                if (j + 1 < h && ch[at] >= threshold) {
                    double m = 0.0;
                    if (j > 0)
                        m = fmax(m, ch[at - (size_t)w]);
                    if (j + 2 < h)
                        m = fmax(m, ch[at + (size_t)w]);
                    if (i > 0)
                        m = fmax(m, fmax(cv[at - 1], cv[at + (size_t)w - 1]));
                    m = fmax(m, fmax(cv[at], cv[at + (size_t)w]));
                    s->hm[at] = adapt * ch[at] >= m;
                } else
                    s->hm[at] = 0;
                /* the edge right of (i, j): the other sides of (i, j) and (i+1, j) */
                if (i + 1 < w && cv[at] >= threshold) {
                    double m = 0.0;
                    if (i > 0)
                        m = fmax(m, cv[at - 1]);
                    if (i + 2 < w)
                        m = fmax(m, cv[at + 1]);
                    if (j > 0)
                        m = fmax(m, fmax(ch[at - (size_t)w], ch[at - (size_t)w + 1]));
                    m = fmax(m, fmax(ch[at], ch[at + 1]));
                    s->vm[at] = adapt * cv[at] >= m;
                } else
                    s->vm[at] = 0;
            }
    }
}

/* ---- lines, in either direction ----
 * Line l lies between rows l and l+1 (tr = 0) or columns l and l+1 (tr =
 * 1); u is the position along it, 0 .. len-1. */

typedef struct lines {
    const morph_state *s;
    int tr, len, across; /* positions along a line; rows (columns) across */
} lines;

static inline int edge_at(const lines *g, int l, int u)
{
    const size_t w = (size_t)g->s->w;
    return g->tr ? g->s->vm[(size_t)u * w + (size_t)l] : g->s->hm[(size_t)l * w + (size_t)u];
}

/* Does the boundary cross row (column) k at boundary position p (between
 * positions p-1 and p along the line)? */
static inline int cross_at(const lines *g, int k, int p)
{
    if (p <= 0 || p >= g->len || k < 0 || k >= g->across)
        return 0;
    const size_t w = (size_t)g->s->w;
    return g->tr ? g->s->hm[(size_t)(p - 1) * w + (size_t)k]
                 : g->s->vm[(size_t)k * w + (size_t)(p - 1)];
}

/* The turn at boundary position p of line l: 0 none, 1 near, 2 far, 3 both. */
static inline int turn_at(const lines *g, int l, int p)
{
    return cross_at(g, l, p) | (cross_at(g, l + 1, p) << 1);
}

static inline double *near_share(const lines *g, int l, int u)
{
    const size_t w = (size_t)g->s->w;
    return g->tr ? g->s->vn + (size_t)u * w + (size_t)l : g->s->hn + (size_t)l * w + (size_t)u;
}

static inline double *far_share(const lines *g, int l, int u)
{
    const size_t w = (size_t)g->s->w;
    return g->tr ? g->s->vf + (size_t)u * w + (size_t)l : g->s->hf + (size_t)l * w + (size_t)u;
}

/* mlaa: every run of line l, whole. */
static void mlaa_line(const lines *g, int l)
{
    for (int u = 0; u < g->len;) {
        if (!edge_at(g, l, u)) {
            *near_share(g, l, u) = *far_share(g, l, u) = 0.0;
            u++;
            continue;
        }
        int a = u;
        while (u < g->len && edge_at(g, l, u))
            u++;
        int b = u - 1, el = turn_at(g, l, a), er = turn_at(g, l, b + 1);
        for (int k = a; k <= b; k++) {
            double sh[2];
            aa_morph_area(el, er, k - a, b - k, sh);
            *near_share(g, l, k) = sh[0];
            *far_share(g, l, k) = sh[1];
        }
    }
}

/* smaa: each edge pixel of line l searches for its ends, reads the table,
 * and rounds sharp corners. */
static void smaa_line(const lines *g, int l, double rounding)
{
    const morph_state *s = g->s;
    const int S = s->search;
    for (int u = 0; u < g->len; u++) {
        double *ns = near_share(g, l, u), *fs = far_share(g, l, u);
        if (!edge_at(g, l, u)) {
            *ns = *fs = 0.0;
            continue;
        }
        int dl = 0, dr = 0;
        while (dl < S && u - dl - 1 >= 0 && edge_at(g, l, u - dl - 1))
            dl++;
        while (dr < S && u + dr + 1 < g->len && edge_at(g, l, u + dr + 1))
            dr++;
        const int pl = u - dl, pr = u + dr + 1; /* boundary positions of the ends */
        /* an end the search did not reach is open */
        int el = dl == S && u - dl - 1 >= 0 && edge_at(g, l, u - dl - 1) ? 0 : turn_at(g, l, pl);
        int er = dr == S && u + dr + 1 < g->len && edge_at(g, l, u + dr + 1)
                     ? 0
                     : turn_at(g, l, pr);
        const double *a = s->area + area_at(S, el, er, dl, dr);
        double sn = a[0], sf = a[1];
        if (rounding < 1.0 && (sn > 0 || sf > 0)) {
            /* the nearer end (both if equally near) */
            double wl = dl <= dr ? 1.0 : 0.0, wr = dr <= dl ? 1.0 : 0.0;
            double k = (1.0 - rounding) / (wl + wr);
            double cn = wl * cross_at(g, l - 1, pl) + wr * cross_at(g, l - 1, pr);
            double cf = wl * cross_at(g, l + 2, pl) + wr * cross_at(g, l + 2, pr);
            sn *= fmax(0.0, 1.0 - k * cn);
            sf *= fmax(0.0, 1.0 - k * cf);
        }
        *ns = sn, *fs = sf;
    }
}

static void make_shares(morph_state *s, int smaa, double rounding, int threads)
{
    const lines rows = {s, 0, s->w, s->h}, cols = {s, 1, s->h, s->w};
#pragma omp parallel num_threads(threads)
    {
#pragma omp for schedule(static)
        for (int l = 0; l < s->h; l++) {
            if (l + 1 >= s->h) { /* no line below the last row */
                for (int u = 0; u < s->w; u++)
                    s->hn[(size_t)l * (size_t)s->w + (size_t)u] =
                        s->hf[(size_t)l * (size_t)s->w + (size_t)u] = 0.0;
            } else if (smaa)
                smaa_line(&rows, l, rounding);
            else
                mlaa_line(&rows, l);
        }
#pragma omp for schedule(static)
        for (int l = 0; l < s->w; l++) {
            if (l + 1 >= s->w) {
                for (int u = 0; u < s->h; u++)
                    s->vn[(size_t)u * (size_t)s->w + (size_t)l] =
                        s->vf[(size_t)u * (size_t)s->w + (size_t)l] = 0.0;
            } else if (smaa)
                smaa_line(&cols, l, rounding);
            else
                mlaa_line(&cols, l);
        }
    }
}

/* ---- diagonal patterns (SMAA, step 8) ----
 * Edges by pixel: the north side of (i, j) (the row line above it) and the
 * west side (the column line left of it); none outside the image. */

static inline int north_at(const morph_state *s, int i, int j)
{
    return i >= 0 && i < s->w && j >= 1 && j < s->h &&
           s->hm[(size_t)(j - 1) * (size_t)s->w + (size_t)i];
}

static inline int west_at(const morph_state *s, int i, int j)
{
    return i >= 1 && i < s->w && j >= 0 && j < s->h &&
           s->vm[(size_t)j * (size_t)s->w + (size_t)(i - 1)];
}

/* From (i, j), steps (di, dj) while the pixel has its north side and its
 * west side (east = 0) or east side (east = 1), at most dsearch of them.
 * Returns the steps before the first pixel without both (the last
 * searched when the search ran out: *found 0); *north: that pixel's north
 * side. */
static int diag_search(const morph_state *s, int i, int j, int di, int dj, int east, int *found,
                       int *north)
{
    for (int k = 0;; k++) {
        const int x = i + (k + 1) * di, y = j + (k + 1) * dj;
        const int n = north_at(s, x, y), side = west_at(s, x + east, y);
        if (!(n && side) || k + 1 == s->dsearch) {
            *found = !(n && side);
            *north = n;
            return k;
        }
    }
}

/* The diagonal shares of pixel (i, j), which has its north side: sh[0] its
 * own toward the pixel above, sh[1] the pixel above's toward it. */
static void diag_shares(const morph_state *s, int i, int j, double sh[2])
{
    const int S = s->dsearch;
    int fl = 1, fr = 1, n, dl = 0, dr;
    sh[0] = sh[1] = 0.0;
    /* the line rising to the right (north and west sides): down-left only
     * if (i, j) has its west side too; the pixel with only its north side
     * that ends the search there is the line's first */
    if (west_at(s, i, j))
        dl = diag_search(s, i, j, -1, 1, 0, &fl, &n) + n;
    dr = diag_search(s, i, j, 1, -1, 0, &fr, &n);
    if (dl + dr > 2) {
        const int xl = i - dl, yl = j + dl, xr = i + dr, yr = j - dr;
        int el = fl ? 2 * north_at(s, xl - 1, yl) + west_at(s, xl, yl) : 0;
        int er = fr ? 2 * north_at(s, xr + 1, yr) + west_at(s, xr + 1, yr - 1) : 0;
        const double *a = s->darea + area_at(S, el, er, dl, dr);
        sh[0] += a[0], sh[1] += a[1];
    }
    /* the line falling to the right (north and east sides), the same
     * upside down: the table's lower pixel is the one above (i, j) */
    dl = diag_search(s, i, j, -1, -1, 1, &fl, &n);
    dr = 0, fr = 1;
    if (west_at(s, i + 1, j))
        dr = diag_search(s, i, j, 1, 1, 1, &fr, &n) + n;
    if (dl + dr > 2) {
        const int xl = i - dl, yl = j - dl, xr = i + dr, yr = j + dr;
        int el = fl ? 2 * north_at(s, xl - 1, yl) + west_at(s, xl, yl - 1) : 0;
        int er = fr ? 2 * north_at(s, xr + 1, yr) + west_at(s, xr + 1, yr) : 0;
        const double *a = s->darea + area_at(S, el, er, dl, dr);
        sh[0] += a[1], sh[1] += a[0];
    }
}

/* Every pixel with its north side on a diagonal line takes the diagonal
 * shares across that side in place of the orthogonal ones, and its west
 * side blends nothing (SMAA gives diagonals priority). */
static void smaa_diagonals(morph_state *s, int threads)
{
    const int w = s->w, h = s->h;
    const size_t W = (size_t)w;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int j = 1; j < h; j++)
        for (int i = 0; i < w; i++) {
            const size_t up = (size_t)(j - 1) * W + (size_t)i;
            if (!s->hm[up])
                continue;
            double sh[2];
            diag_shares(s, i, j, sh);
            if (sh[0] == 0.0 && sh[1] == 0.0)
                continue;
            s->hf[up] = sh[0], s->hn[up] = sh[1];
            if (i > 0)
                s->vn[(size_t)j * W + (size_t)i - 1] = s->vf[(size_t)j * W + (size_t)i - 1] = 0.0;
        }
}

/* ---- blending ---- */

static uint64_t blend(const morph_state *s, int smaa, int threads, aa_image *out)
{
    const int w = s->w, h = s->h;
    const size_t W = (size_t)w;
    uint64_t expensive = 0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : expensive)
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const size_t at = (size_t)j * W + (size_t)i;
            const double *x = s->img + 3 * at;
            double *y = aa_pixel(out, i, j);
            /* shares toward the pixel below, above, right, left */
            double sh[4] = {s->hn[at], j > 0 ? s->hf[at - W] : 0.0, s->vn[at],
                            i > 0 ? s->vf[at - 1] : 0.0};
            const double *nb[4] = {j + 1 < h ? x + 3 * W : x, j > 0 ? x - 3 * W : x,
                                   i + 1 < w ? x + 3 : x, i > 0 ? x - 3 : x};
            int beside = s->hm[at] || (j > 0 && s->hm[at - W]) || s->vm[at] ||
                         (i > 0 && s->vm[at - 1]);
            expensive += (uint64_t)beside;
            if (sh[0] == 0 && sh[1] == 0 && sh[2] == 0 && sh[3] == 0) {
                y[0] = x[0], y[1] = x[1], y[2] = x[2];
                continue;
            }
            /* one direction: rows (the lines above and below) unless a
             * column line's share is larger */
            double wt[4] = {0, 0, 0, 0};
            const int a = fmax(sh[0], sh[1]) >= fmax(sh[2], sh[3]) ? 0 : 2;
            const double sum = sh[a] + sh[a + 1];
            if (smaa) {
                /* the two fetches at their shares, weighted by the shares:
                 * share^2 / (sum of the two) of each side */
                wt[a] = sh[a] * sh[a] / sum;
                wt[a + 1] = sh[a + 1] * sh[a + 1] / sum;
            } else {
                const double k = sum > 1.0 ? 1.0 / sum : 1.0;
                wt[a] = sh[a] * k;
                wt[a + 1] = sh[a + 1] * k;
            }
            for (int c = 0; c < 3; c++) {
                double v = x[c], lo = v, hi = v;
                for (int q = 0; q < 4; q++) {
                    if (wt[q] == 0.0)
                        continue;
                    double n = nb[q][c];
                    v += wt[q] * (n - x[c]);
                    lo = n < lo ? n : lo;
                    hi = n > hi ? n : hi;
                }
                y[c] = v < lo ? lo : (v > hi ? hi : v);
            }
        }
    return expensive;
}

/* ---- the methods ---- */

static int mlaa_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    return prepare(state, 0, 0, 0, job);
}

static int smaa_init(void *state, const double *p, const aa_job *job)
{
    return prepare(state, 1, (int)p[S_SEARCH], p[S_DIAG] != 0 ? (int)p[S_DSEARCH] : 0, job);
}

static int morph_render(morph_state *s, int smaa, const double *p, const aa_job *job,
                        aa_image *out, aa_counters *counters)
{
    int st;
    int search = smaa ? (int)p[S_SEARCH] : 0;
    int dsearch = smaa && p[S_DIAG] != 0 ? (int)p[S_DSEARCH] : 0;
    if ((!s->ready || s->w != job->w || s->h != job->h || s->search != search ||
         s->dsearch != dsearch) &&
        (st = prepare(s, smaa, search, dsearch, job)))
        return st;
    aa_image img = {job->w, job->h, 3, s->img};
    if ((st = aa_point_sample(job->placed, 0.0, 0.0, job->threads, &img)))
        return st;
    counters->samples = (uint64_t)job->w * (uint64_t)job->h;
    if (smaa)
        smaa_edges(s, p[S_THRESHOLD], p[S_ADAPT], job->threads);
    else
        mlaa_edges(s, p[P_THRESHOLD], job->threads);
    make_shares(s, smaa, smaa ? p[S_ROUNDING] : 1.0, job->threads);
    if (s->dsearch > 0)
        smaa_diagonals(s, job->threads);
    counters->expensive_pixels = blend(s, smaa, job->threads, out);
    return AA_OK;
}

static int mlaa_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    return morph_render(state, 0, p, job, out, counters);
}

static int smaa_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    return morph_render(state, 1, p, job, out, counters);
}

const aa_method_type aa_method_mlaa = {
    {"mlaa", "point samples smoothed by morphological antialiasing: L, Z and U shapes "
             "blended by trapezoid areas (Reshetov 2009)",
     mlaa_params},
    sizeof(morph_state),
    AA_METHOD_FIELDS,
    morph_check,
    mlaa_init,
    mlaa_render,
    morph_release};

const aa_method_type aa_method_smaa = {
    {"smaa", "point samples smoothed by SMAA 1x: luma edges with local contrast adaptation, "
             "orthogonal and diagonal area tables, sharp corners (Jimenez et al. 2012)",
     smaa_params},
    sizeof(morph_state),
    AA_METHOD_FIELDS,
    morph_check,
    smaa_init,
    smaa_render,
    morph_release};
