/*
 * crowtable.c: Crow's table-driven prefilter (Crow 1976, ch. 2, "Applying
 * filters to computer-synthesized images", eqs. 5-8, figs. 2.7 and 2.8;
 * ch. 3, "Implementation of a tiler", the filtering tiler of fig. 3.12 and
 * "Left Areas - Right Areas = Area", fig. 3.13).
 *
 * What is Crow's.  The filter is separable, H(i, j) = H_i(i) H_j(j) (eq. 5),
 * with a square non-zero part.  The image under one filter position is
 * approximated by rectangular blocks of constant colour (eq. 7), so each
 * block's weight factors into a sum over x times a sum over y (eq. 8), and
 * both sums come from two finite tables of partial sums of the 1-D weight,
 * "from the lower non-zero bound to some point": the sum between two points
 * is the difference of two entries (fig. 2.7), "four lookups, two subtracts
 * and two multiplies" per rectangle.  Each edge crossing the filter's
 * square is represented by rectangles (fig. 2.8), the area right of a left
 * edge added and that right of a right edge subtracted (fig. 3.13).  Only
 * pixels whose square meets an edge are summed; the others take their
 * colour (ch. 3: "the summations need only be computed in the problem
 * areas").
 *
 * What is chosen here (the thesis gives no table size and no rule for
 * forming the rectangles beyond "a single rectangular area for each of
 * these edges"):
 *
 *  - The table.  With R the filter's half-width (box 1/2, tent r, Gaussian
 *    cut s, see below) and N = ceil(2 R res) intervals of width d = 2R/N
 *    (res= entries per pixel, default 16), entry k is the normalised
 *    partial sum T[k] = (C(-R + k d) - C(-R)) / (C(R) - C(-R)), C the
 *    filter's exact 1-D integral (aa_filter_cdf).  The x and y tables are
 *    the same (the filters are symmetric and square).  A coordinate is
 *    looked up at the nearest entry, as Crow's discrete tables are: an edge
 *    position is known only to the table's resolution.
 *  - The rectangles.  The square is cut into the table's N rows of height
 *    d.  In row k the colour along the row's middle line is a step
 *    function of x (its crossings with the scene's edges); each run of constant colour c between
 *    x0 and x1 becomes the rectangle [x0, x1] x row k, of weight
 *    (T(x1) - T(x0)) (T[k+1] - T[k]) c.  Summing the runs is Crow's left
 *    areas minus right areas with the colour jumps in place of +-1, and
 *    handles any number of edges, layers and fill rules per row.
 *  - Box: R = 1/2 and T is linear, so the method is area sampling by
 *    rectangles of height 1/N; it needs no table in principle and uses the
 *    same code.
 *  - Gaussian: truncated at R = cut s (cut=, default 3, aa_filter_support's
 *    radius) and renormalised by the truncated mass, so a uniform region
 *    stays exact.  The untruncated reference then measures the truncation:
 *    the 2-D mass outside the square is 1 - m^2, m = erf(cut / sqrt 2)
 *    (1.0 % at cut = 3).  cut= is refused with the other filters.
 *
 * Error analysis (per pixel, against the exact reference with the same
 * filter; wx the largest 1-D weight, w2 = wx^2 the largest 2-D weight):
 *
 *  - lookup: an end of a run snapped to the nearest entry moves by at most
 *    d/2, changing T by at most wx d / 2; over the rows (their weights sum
 *    to 1) each edge contributes at most wx d / 2 per unit of colour jump;
 *  - rows: within a row an edge is replaced by the vertical line through
 *    its crossing of the middle line; the area between is at most
 *    (d / 2) times the edge's x extent inside the row, and those extents
 *    add up to the edge's x variation inside the square, at most 4R for a
 *    y-monotone quadratic piece (2R for a line), so each piece contributes
 *    at most w2 (d / 2) 4R = 2 R w2 d;
 *  - truncation (Gaussian only): at most 2 (1 - m^2) per unit of contrast
 *    (the mass moved by renormalising plus the mass lost).
 *
 * So |error| <= K (wx d / 2 + 2 R w2 d) + trunc for K pieces meeting the
 * square and contrast 1: first order in 1/res.  Known answers
 * (tests/test_tables.c): a half-plane right of a vertical edge at u = e
 * gives 1 - C(e - u_c) within wx d / 2 (its rows are exact), e.g. within
 * 3.9e-3 for tent:r=1 at res=128; and every pixel of crow 128x128 is
 * within the bound above, with K and the pieces' x variation counted from
 * the scene.
 *
 * Cost.  Runs of pixels whose squares meet no edge are filled
 * (aa_strip_uniform_run).  The others are summed one table row at a time:
 * the crossings of that row's middle line are found once per image row
 * (aa_scene_crossings) and swept left to right, so a summed pixel costs, per
 * table row, the crossings inside its square (two lookups each) and one
 * colour; N table rows per pixel make the cost linear in res (crow
 * 1024x1024 tent:r=1, res=16: about 140 ns per pixel, one core).  Tables are
 * made in init; each thread's crossings, sums and indices are made with its
 * strip, so nothing is allocated while rendering.  A pixel depends only on
 * its image row: the image is the same for any thread count.  Counters:
 * samples = 0 (the scene is read along lines, not at points),
 * expensive_pixels = pixels that were summed.
 *
 * Limits: separable filters only (box, tent, gauss); the approximation is
 * first order in 1/res in both directions, and rows cost linearly in res.
 * Values are clamped to [0, 1] (the snapped sums of a mixed pixel may round
 * a hair outside).
 */
#include "methods.h"
#include "sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CT_MAX_RES 1024
#define CT_DEFAULT_CUT 3.0

enum { P_RES, P_CUT };

static const aa_param crowtable_params[] = {
    {"res", AA_PARAM_INT, 16, 1, CT_MAX_RES, 0, NULL,
     "table entries per pixel: the partial-sum tables' resolution and the rows' height 1/res"},
    {"cut", AA_PARAM_REAL, CT_DEFAULT_CUT, 1.0, 8.0, 0, NULL,
     "Gaussian only: truncation half-width in standard deviations"},
    {0}};

typedef struct ct_table {
    double half;   /* R: the square's half-width */
    double step;   /* d = 2R / n */
    int n;         /* intervals */
    double *t;     /* t[0..n]: normalised partial sums */
} ct_table;

typedef struct ct_state {
    ct_table tab;
    aa__sampler sampler; /* workers; own scratch: ct_scratch */
    size_t ncross;
} ct_state;

typedef struct ct_render {
    const ct_table *tab;
    const aa_scene *scene; /* placed */
    size_t ncross;
} ct_render;

static double ct_half_width(const double *p, const aa_filter *f)
{
    if (f->type == &aa_filter_gauss)
        return p[P_CUT] * f->spec.v[0];
    return f->radius; /* box 1/2, tent r */
}

static int crowtable_check(const double *p, const aa_filter *f)
{
    if (f->type != &aa_filter_box && f->type != &aa_filter_tent && f->type != &aa_filter_gauss)
        return aa_fail(AA_EINVAL, "crowtable needs a separable filter with a square support "
                                  "(box, tent:r=R or gauss:s=S)");
    if (f->type != &aa_filter_gauss && p[P_CUT] != CT_DEFAULT_CUT)
        return aa_fail(AA_EINVAL, "cut=%g truncates the Gaussian only; with -f %s leave cut "
                                  "out",
                       p[P_CUT], f->type->info.name);
    double n = ceil(2.0 * ct_half_width(p, f) * p[P_RES]);
    if (!(n <= 1 << 20))
        return aa_fail(AA_EINVAL, "a table of %.0f entries is too large (2 R res must stay "
                                  "below 2^20: lower res=)",
                       n);
    return AA_OK;
}

static int table_make(ct_table *tab, const double *p, const aa_filter *f)
{
    double r = ct_half_width(p, f);
    int n = (int)ceil(2.0 * r * p[P_RES]);
    if (n < 1)
        n = 1;
    double *t = malloc((size_t)(n + 1) * sizeof *t);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for a table of %d entries", n + 1);
    double lo = aa_filter_cdf(f, -r), mass = aa_filter_cdf(f, r) - lo;
    for (int k = 0; k <= n; k++)
        t[k] = (aa_filter_cdf(f, -r + 2.0 * r * k / n) - lo) / mass;
    t[0] = 0.0, t[n] = 1.0;
    free(tab->t);
    tab->t = t;
    tab->n = n;
    tab->half = r;
    tab->step = 2.0 * r / n;
    return AA_OK;
}

/* The nearest entry to offset u from the square's left (or top) side. */
static inline double lookup(const ct_table *tab, double u)
{
    double k = floor(u / tab->step + 0.5);
    k = k < 0.0 ? 0.0 : (k > tab->n ? tab->n : k);
    return tab->t[(int)k];
}

/* The scratch of one thread for rows of width w: every crossing of one
 * line, the row's sums and the indices of its summed pixels. */
typedef struct ct_scratch {
    aa_crossing *cross;
    double *acc;
    int *idx;
} ct_scratch;

static ct_scratch scratch_of(void *own, size_t ncross, int w)
{
    ct_scratch sc;
    sc.cross = own;
    sc.acc = (double *)(sc.cross + ncross);
    sc.idx = (int *)(sc.acc + 3 * (size_t)w);
    return sc;
}

static size_t scratch_size(size_t ncross, int w)
{
    return ncross * sizeof(aa_crossing) + 3 * (size_t)w * sizeof(double) +
           (size_t)w * sizeof(int);
}

/* One row of pixels (aa__sampler_row_fn).  Pixels whose square meets no
 * piece are filled in runs; the others are summed one table row at a
 * time: the crossings of the row's middle line are found once for the
 * whole image row and swept left to right, each summed pixel taking the
 * runs between the crossings inside its square. */
static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    const ct_render *R = ctx;
    const ct_table *tab = R->tab;
    const aa_scene *s = R->scene;
    ct_scratch sc = scratch_of(wk->own, R->ncross, out->w);
    double half = tab->half, cy = j + 0.5, top = cy - half;
    (void)samples;
    if (aa_strip_begin(wk->strip, cy - half, cy + half))
        return 1;
    int ne = 0;
    for (int i = 0; i < out->w;) {
        double cx = i + 0.5, *px = aa_pixel(out, i, j);
        if (aa_strip_window(wk->strip, cx - half, cx + half) == 0) {
            aa_rgb c;
            int end = aa_strip_uniform_run(wk->strip, i, out->w, half, cy, wk->wind, &c);
            for (; i < end; i++, px += 3)
                px[0] = c.c[0], px[1] = c.c[1], px[2] = c.c[2];
            continue;
        }
        sc.acc[3 * ne] = sc.acc[3 * ne + 1] = sc.acc[3 * ne + 2] = 0.0;
        sc.idx[ne++] = i++;
    }
    if (!ne)
        return 0;
    *expensive += (uint64_t)ne;
    int nl = aa_scene_layer_count(s);
    size_t nw = (size_t)(nl > 0 ? nl : 1) * sizeof(int);
    for (int k = 0; k < tab->n; k++) {
        double wy = tab->t[k + 1] - tab->t[k];
        if (!(wy > 0.0))
            continue;
        size_t m = aa_scene_crossings(s, top + (k + 0.5) * tab->step, sc.cross, R->ncross);
        if (m > R->ncross)
            m = R->ncross; /* cannot happen: a line meets each piece once */
        memset(wk->wind, 0, nw);
        size_t q = 0;
        aa_rgb cl = aa_scene_colour_of(s, wk->wind); /* the colour left of the square */
        for (int e = 0; e < ne; e++) {
            double left = sc.idx[e] + 0.5 - half, right = left + 2.0 * half;
            int moved = 0;
            while (q < m && sc.cross[q].x < left) {
                wk->wind[sc.cross[q].layer] += sc.cross[q].dir;
                q++, moved = 1;
            }
            if (moved)
                cl = aa_scene_colour_of(s, wk->wind);
            aa_rgb c = cl;
            double r0, r1, r2;
            if (q == m || !(sc.cross[q].x < right)) {
                r0 = c.c[0], r1 = c.c[1], r2 = c.c[2]; /* one run: T(R) - T(-R) = 1 */
            } else {
                /* runs between the crossings inside the square: each is a
                 * rectangle, (T(x1) - T(x0)) times the row's weight */
                memcpy(wk->wind2, wk->wind, nw);
                double t0 = 0.0;
                r0 = r1 = r2 = 0.0;
                for (size_t u = q; u < m && sc.cross[u].x < right; u++) {
                    double t1 = lookup(tab, sc.cross[u].x - left), wx = t1 - t0;
                    r0 += wx * c.c[0], r1 += wx * c.c[1], r2 += wx * c.c[2];
                    wk->wind2[sc.cross[u].layer] += sc.cross[u].dir;
                    c = aa_scene_colour_of(s, wk->wind2);
                    t0 = t1;
                }
                double wx = 1.0 - t0;
                r0 += wx * c.c[0], r1 += wx * c.c[1], r2 += wx * c.c[2];
            }
            double *a = sc.acc + 3 * e;
            a[0] += wy * r0, a[1] += wy * r1, a[2] += wy * r2;
        }
    }
    for (int e = 0; e < ne; e++) {
        double *px = aa_pixel(out, sc.idx[e], j), *a = sc.acc + 3 * e;
        for (int ch = 0; ch < 3; ch++)
            px[ch] = a[ch] < 0.0 ? 0.0 : (a[ch] > 1.0 ? 1.0 : a[ch]);
    }
    return 0;
}

static int prepare(ct_state *S, const aa_job *job)
{
    size_t npieces;
    aa_scene_pieces(job->placed, &npieces);
    S->ncross = npieces + 1;
    return aa__sampler_ready(&S->sampler, job, scratch_size(S->ncross, job->w));
}

static int crowtable_init(void *state, const double *p, const aa_job *job)
{
    ct_state *S = state;
    int st = table_make(&S->tab, p, &job->filter);
    return st ? st : prepare(S, job);
}

static int crowtable_render(void *state, const double *p, const aa_job *job, aa_image *out,
                            aa_counters *counters)
{
    (void)p;
    ct_state *S = state;
    int st = prepare(S, job);
    if (st)
        return st;
    const ct_render R = {&S->tab, job->placed, S->ncross};
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void crowtable_release(void *state)
{
    ct_state *S = state;
    aa__sampler_free(&S->sampler);
    free(S->tab.t);
    S->tab.t = NULL;
}

const aa_method_type aa_method_crowtable = {
    {"crowtable",
     "Crow's partial-sum lookup tables over rectangles per edge and row (figs. 2.7-2.8, 3.12)",
     crowtable_params},
    sizeof(ct_state),
    0,
    crowtable_check,
    crowtable_init,
    crowtable_render,
    crowtable_release};
