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
 * and two multiplies" per rectangle.  The blocks: "at most only a few edges
 * in the image pass through [the square].  So far it has been sufficient to
 * approximate the image function by forming a single rectangular area for
 * each of these edges [Fig. 2.8]"; the area right of a left edge is added
 * and that right of a right edge subtracted (fig. 3.13), and in the tiler
 * the rectangle comes from where "a tagged edge enters the top of the
 * square area ... [and] exits at the bottom", an edge "too small or too
 * close to horizontal" from its end points (ch. 3).  Only pixels whose
 * square meets an edge are summed; the others take their colour (ch. 3:
 * "the summations need only be computed in the problem areas").
 *
 * So form=crow, the default, is Crow's: one rectangle per edge.  form=rows
 * is a finer variant, not his, kept for comparison: the square cut into the
 * table's rows, a rectangle per run of colour in each row, first order in
 * 1/res where Crow's rectangle is not (below).
 *
 * What is chosen here (the thesis gives no table size, and no rule for an
 * edge's rectangle beyond its entry and exit):
 *
 *  - The table.  With R the filter's half-width (box 1/2, tent r, Gaussian
 *    cut s, see below) and N = ceil(2 R res) intervals of width d = 2R/N
 *    (res= entries per pixel, default 16), entry k is the normalised
 *    partial sum T[k] = (C(-R + k d) - C(-R)) / (C(R) - C(-R)), C the
 *    filter's exact 1-D integral (aa_filter_cdf).  The x and y tables are
 *    the same (the filters are symmetric and square).  A coordinate is
 *    looked up at the nearest entry, as Crow's discrete tables are: an edge
 *    position is known only to the table's resolution.
 *  - form=crow.  Each piece of edge (the scene's y-monotone pieces of lines
 *    and arcs) is clipped to the square's rows and cut where it crosses the
 *    square's left and right sides.  Each part inside the square gives one
 *    rectangle, from the mean x of its two ends (its entry and exit) to the
 *    square's right side, over its rows: weight (1 - T(x)) (T(y1) - T(y0)).
 *    Its colour is the step of colour across the edge (right minus left)
 *    at the middle of its rows, found from the winding numbers just left of
 *    it there (pieces at the same x, such as the shared edge of two
 *    abutting polygons, taken in the order of their index, so that the two
 *    steps add up to the whole): an edge hidden behind a front layer steps
 *    by nothing, so hidden surfaces are resolved edge by edge as in Crow's
 *    scanning algorithm (ch. 3), one colour step per edge.  The parts of
 *    edges left of the square are in the colour just inside its left side,
 *    which is summed in blocks of full rows between the heights where it
 *    can change (the local pieces' ends, flat pieces' heights and crossings
 *    of the left side); parts right of it add nothing; a flat edge bounds no
 *    rows (its polygon's other edges carry its area).
 *  - form=rows.  The square is cut into the table's N rows of height d.  In
 *    row k the colour along the row's middle line is a step function of x
 *    (its crossings with the scene's edges); each run of constant colour c
 *    between x0 and x1 becomes the rectangle [x0, x1] x row k, of weight
 *    (T(x1) - T(x0)) (T[k+1] - T[k]) c.  Summing the runs is Crow's left
 *    areas minus right areas with the colour jumps in place of +-1, and
 *    handles any number of edges, layers and fill rules per row.
 *  - Box: R = 1/2 and T is linear; the same code.
 *  - Gaussian: truncated at R = cut s (cut=, default 3, aa_filter_support's
 *    radius) and renormalised by the truncated mass, so a uniform region
 *    stays exact.  The untruncated reference then measures the truncation:
 *    the 2-D mass outside the square is 1 - m^2, m = erf(cut / sqrt 2)
 *    (1.0 % at cut = 3).  cut= is refused with the other filters.
 *
 * Error analysis (per pixel, against the exact reference with the same
 * filter; wx the largest 1-D weight, w2 = wx^2 the largest 2-D weight):
 *
 *  - lookup: an end snapped to the nearest entry moves by at most d/2,
 *    changing T by at most wx d / 2.  form=crow reads three entries per
 *    rectangle and two per block of rows; form=rows, over its rows (whose
 *    weights sum to 1), at most wx d / 2 per edge and unit of colour jump;
 *  - form=crow, the rectangle: an edge x(y) replaced by its mean position
 *    over its rows.  For a straight edge of slope s (dx/dy) crossing the
 *    whole square at horizontal offset e from the centre, the rectangle
 *    gives 1 - C(e) where the exact value is the mean of 1 - C(e + s v)
 *    under the weight of v: off by about s^2 C''(e) var(v) / 2 (s^2 / 12 at
 *    most for tent:r=1, var(v) = 1/6), which does not fall with res; for an
 *    edge that ends inside the square the rows are not symmetric about the
 *    centre and the error is first order in s.  One colour step per edge:
 *    where the colours beside an edge change inside the square (another
 *    edge crosses or ends on it) the step at its middle is taken for all of
 *    it;
 *  - form=rows: within a row an edge is replaced by the vertical line
 *    through its crossing of the middle line; the area between is at most
 *    (d / 2) times the edge's x extent inside the row, and those extents
 *    add up to the edge's x variation inside the square, at most 4R for a
 *    y-monotone quadratic piece (2R for a line), so each piece contributes
 *    at most w2 (d / 2) 4R = 2 R w2 d;
 *  - truncation (Gaussian only): at most 2 (1 - m^2) per unit of contrast
 *    (the mass moved by renormalising plus the mass lost).
 *
 * So form=rows is within K (wx d / 2 + 2 R w2 d) + trunc for K pieces
 * meeting the square and contrast 1, first order in 1/res; form=crow is
 * exact up to the lookups for vertical edges only.  Measured on crow
 * 256x256 against the exact references (RMSE, max): tent:r=1, res=16:
 * crow 1.0e-2, 8.1e-2; rows 3.1e-3, 4.3e-2; res=256: crow 4.4e-3, 7.6e-2;
 * rows 4.7e-5, 1.7e-3; gauss (s = 0.5), res=16: crow 1.1e-2, 1.4e-1; rows
 * 2.9e-3, 4.3e-2.  Crow's largest errors are in the top and bottom rows,
 * where crow's arcs end slanted (slope up to 0.6) inside the square.
 * Known answers (tests/test_tables.c, form=rows: a half-plane right of a
 * vertical edge at u = e gives 1 - C(e - u_c) within wx d / 2; every pixel
 * of crow 128x128 within the bound above.  tests/test_prefilters.c,
 * form=crow: a slanted straight edge across the square gives 1 - C(e)
 * within the lookup, which the exact value differs from by about s^2 / 12;
 * abutting rectangles of different colours and one hidden behind them
 * within the lookups of the exact reference; nothing of a hidden polygon
 * shows).
 *
 * Cost.  Runs of pixels whose squares meet no edge are filled
 * (aa_strip_uniform_run).  form=crow: per summed pixel and part of an edge
 * in its square, three lookups and the winding just left of it (a pass
 * over the local pieces), so quadratic in the (few) local pieces.
 * form=rows: summed one table row at a time: the crossings of that row's
 * middle line are found once per image row (aa_scene_crossings) and swept
 * left to right, so a summed pixel costs, per table row, the crossings
 * inside its square (two lookups each) and one colour; N table rows per
 * pixel make the cost linear in res (crow 1024x1024 tent:r=1, res=16:
 * about 140 ns per pixel, one core).  Tables are made in init; each
 * thread's scratch is made with its strip, so nothing is allocated while
 * rendering.  A pixel depends only on its image row: the image is the same
 * for any thread count.  Counters: samples = 0 (the scene is read along
 * lines, not at points), expensive_pixels = pixels that were summed.
 *
 * Limits: separable filters only (box, tent, gauss); values are clamped to
 * [0, 1] (the snapped sums of a mixed pixel may round a hair outside).
 */
#include "methods.h"
#include "sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CT_MAX_RES 1024
#define CT_DEFAULT_CUT 3.0

enum { P_RES, P_CUT, P_FORM };
enum { FORM_CROW, FORM_ROWS };

static const aa_param crowtable_params[] = {
    {"res", AA_PARAM_INT, 16, 1, CT_MAX_RES, 0, NULL,
     "table entries per pixel: the partial-sum tables' resolution (and, form=rows, the rows' "
     "height 1/res)"},
    {"cut", AA_PARAM_REAL, CT_DEFAULT_CUT, 1.0, 8.0, 0, NULL,
     "Gaussian only: truncation half-width in standard deviations"},
    {"form", AA_PARAM_CHOICE, FORM_CROW, 0, 0, 0, "crow|rows",
     "rectangles: one per edge in the square (crow, Crow's fig. 2.8) or one per run of colour "
     "in each of the table's rows (rows, a finer variant)"},
    {0}};

typedef struct ct_table {
    double half;   /* R: the square's half-width */
    double step;   /* d = 2R / n */
    int n;         /* intervals */
    double *t;     /* t[0..n]: normalised partial sums */
} ct_table;

typedef struct ct_state {
    ct_table tab;
    aa__sampler sampler; /* workers; own scratch: ct_scratch or ct_edges */
    size_t ncross;
} ct_state;

typedef struct ct_render {
    const ct_table *tab;
    const aa_scene *scene; /* placed */
    size_t ncross;
    const aa_piece *pieces; /* the scene's, for a piece's index */
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

/* ---- form=crow: one rectangle per edge (Crow's fig. 2.8) ---- */

/* An edge's part inside the square: its rows [lo, hi], the middle row ym
 * and its x there (the order along x), the rectangle's left side xr (the
 * mean of where the part enters and leaves: Crow's "where a tagged edge
 * enters the top of the square area ... where the edge exits at the
 * bottom", or its end points for an edge "too small or too close to
 * horizontal"), its index for ties. */
typedef struct ct_edge {
    const aa_piece *p;
    double lo, hi, ym, xm, xr;
    int id;
} ct_edge;

/* Parts: at most two per piece (a y-monotone arc leaves and re-enters the
 * square once); heights: the rows' ends, two ends and two crossings of the
 * square's left side per piece. */
static size_t edges_size(size_t npieces)
{
    return 7 * npieces * sizeof(ct_edge) + (6 * npieces + 2) * sizeof(double);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void sort_small(double *v, int n)
{
    for (int a = 1; a < n; a++) {
        double t = v[a];
        int b = a;
        while (b > 0 && v[b - 1] > t)
            v[b] = v[b - 1], b--;
        v[b] = t;
    }
}

/* Pixel (i, j) whose square holds local pieces (aa__sampler_shade_fn).  The
 * colour just inside the square's left side, in blocks of rows between the
 * heights where it can change (the ends of local pieces, the heights of
 * flat ones, where a piece crosses the left side), plus one rectangle per
 * edge inside the square, from the edge to the square's right side over the
 * edge's rows, weighted by the step of colour across the edge at its middle
 * row.  (An edge left of the square is in the colour at its left side; one
 * right of it adds nothing.) */
static void shade_crow(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const ct_render *R = ctx;
    const ct_table *tab = R->tab;
    const aa_scene *s = R->scene;
    double half = tab->half, left = i + 0.5 - half, right = left + 2.0 * half;
    double top = j + 0.5 - half, bottom = top + 2.0 * half;
    size_t nloc, k = 0, nb = 0;
    const aa_piece *const *loc = aa_strip_local(wk->strip, &nloc);
    ct_edge *e = wk->own;
    double *ys = (double *)(e + 7 * nloc); /* a cubic: up to 7 parts */
    ys[nb++] = top;
    ys[nb++] = bottom;
    for (size_t q = 0; q < nloc; q++) {
        const aa_piece *p = loc[q];
        if (!p->dir) {
            /* a flat edge bounds no rows (its area right is nil), but the
             * colour left of the square may change at its height */
            if (p->y0 > top && p->y0 < bottom)
                ys[nb++] = p->y0;
            continue;
        }
        double lo = fmax(p->y0, top), hi = fmin(p->y1, bottom);
        if (!(lo < hi))
            continue;
        if (lo > top)
            ys[nb++] = lo;
        if (hi < bottom)
            ys[nb++] = hi;
        /* the piece's rows cut where it crosses the square's sides */
        double cut[8], m[3];
        int nc = 0;
        cut[nc++] = lo;
        cut[nc++] = hi;
        int c = aa_piece_meet_x(p, left, m);
        for (int r = 0; r < c; r++)
            if (m[r] > lo && m[r] < hi)
                cut[nc++] = m[r], ys[nb++] = m[r];
        c = aa_piece_meet_x(p, right, m);
        for (int r = 0; r < c; r++)
            if (m[r] > lo && m[r] < hi)
                cut[nc++] = m[r];
        sort_small(cut, nc);
        for (int r = 0; r + 1 < nc; r++) {
            if (!(cut[r] < cut[r + 1]))
                continue;
            double ym = 0.5 * (cut[r] + cut[r + 1]), xm = aa_piece_x_at(p, ym);
            if (!(xm >= left && xm <= right))
                continue;
            e[k++] = (ct_edge){p, cut[r], cut[r + 1], ym, xm,
                               0.5 * (aa_piece_x_at(p, cut[r]) + aa_piece_x_at(p, cut[r + 1])),
                               (int)(p - R->pieces)};
        }
    }
    qsort(ys, nb, sizeof *ys, cmp_double);
    double acc[3] = {0.0, 0.0, 0.0};
    for (size_t b = 0; b + 1 < nb; b++) {
        if (!(ys[b] < ys[b + 1]))
            continue;
        double wy = lookup(tab, ys[b + 1] - top) - lookup(tab, ys[b] - top);
        if (!(wy != 0.0))
            continue;
        double y = 0.5 * (ys[b] + ys[b + 1]);
        aa_strip_winding_left(wk->strip, y, wk->wind);
        for (size_t q = 0; q < nloc; q++) {
            const aa_piece *g = loc[q];
            if (g->dir && g->y0 <= y && y < g->y1 && aa_piece_x_at(g, y) < left)
                wk->wind[g->layer] += g->dir;
        }
        aa_rgb c = aa_scene_colour_of(s, wk->wind);
        for (int ch = 0; ch < 3; ch++)
            acc[ch] += wy * c.c[ch];
    }
    for (size_t q = 0; q < k; q++) {
        const ct_edge *E = &e[q];
        double w = (1.0 - lookup(tab, E->xr - left)) *
                   (lookup(tab, E->hi - top) - lookup(tab, E->lo - top));
        if (!(w != 0.0))
            continue;
        /* the winding just left of the edge at its middle row: the pieces
         * left of the square, and the local ones before it along x (ties,
         * such as two abutting polygons' shared edge, by index) */
        aa_strip_winding_left(wk->strip, E->ym, wk->wind);
        for (size_t r = 0; r < nloc; r++) {
            const aa_piece *g = loc[r];
            if (!g->dir || g == E->p || !(g->y0 <= E->ym && E->ym < g->y1))
                continue;
            double x = aa_piece_x_at(g, E->ym);
            if (x < E->xm || (x == E->xm && (int)(g - R->pieces) < E->id))
                wk->wind[g->layer] += g->dir;
        }
        aa_rgb c0 = aa_scene_colour_of(s, wk->wind);
        wk->wind[E->p->layer] += E->p->dir;
        aa_rgb c1 = aa_scene_colour_of(s, wk->wind);
        for (int ch = 0; ch < 3; ch++)
            acc[ch] += w * (c1.c[ch] - c0.c[ch]);
    }
    for (int ch = 0; ch < 3; ch++)
        px[ch] = acc[ch] < 0.0 ? 0.0 : (acc[ch] > 1.0 ? 1.0 : acc[ch]);
}

static int render_row_crow(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                           uint64_t *samples, uint64_t *expensive)
{
    const ct_render *R = ctx;
    return aa__sampler_row(wk, j, R->tab->half, 0, shade_crow, ctx, out, samples, expensive);
}

static int prepare(ct_state *S, const double *p, const aa_job *job)
{
    size_t npieces;
    aa_scene_pieces(job->placed, &npieces);
    S->ncross = npieces + 1;
    size_t own = (int)p[P_FORM] == FORM_CROW ? edges_size(npieces)
                                              : scratch_size(S->ncross, job->w);
    return aa__sampler_ready(&S->sampler, job, own);
}

static int crowtable_init(void *state, const double *p, const aa_job *job)
{
    ct_state *S = state;
    int st = table_make(&S->tab, p, &job->filter);
    return st ? st : prepare(S, p, job);
}

static int crowtable_render(void *state, const double *p, const aa_job *job, aa_image *out,
                            aa_counters *counters)
{
    ct_state *S = state;
    int st = prepare(S, p, job);
    if (st)
        return st;
    size_t npieces;
    const aa_piece *pieces = aa_scene_pieces(job->placed, &npieces);
    const ct_render R = {&S->tab, job->placed, S->ncross, pieces};
    return aa__sampler_render(&S->sampler, job, out,
                              (int)p[P_FORM] == FORM_CROW ? render_row_crow : render_row, &R,
                              counters);
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
     "Crow's partial-sum lookup tables, one rectangle per edge (figs. 2.7-2.8; form=rows: per "
     "run of colour in each row)",
     crowtable_params},
    sizeof(ct_state),
    0,
    crowtable_check,
    crowtable_init,
    crowtable_render,
    crowtable_release};
