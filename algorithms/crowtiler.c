/*
 * crowtiler.c: the filtering of Crow's filtering tiler (Crow 1976, ch. 3,
 * "Implementation of a tiler", figs. 3.12-3.13, compared with conventional
 * tilers in figs. 3.14-3.17; the test pattern filtered in figs. 3.18-3.19),
 * with the hidden surfaces of his z-priority and scanning algorithms
 * (ch. 3, "Implementation of a z-priority algorithm", fig. 3.5;
 * "Implementation of a scanning algorithm").
 *
 * What is Crow's.
 *  - The filter.  "The filters used in this work always cover an area two
 *    picture elements square": the bounds of the non-zero part are the
 *    neighbouring sample points, so the square around the pixel centre has
 *    half-width one pixel.  The filter is separable (ch. 2, eq. 5) and
 *    "pyramid-shaped" (appendix; fig. 2.14: "a roughly triangular filter
 *    with a base width of roughly twice the distance between sample
 *    points"): tent:r=1, w(u) w(v) with w(t) = max(0, 1 - |t|).  The method
 *    takes that filter only.  (Being separable, it is bilinear, not planar,
 *    over each quadrant of the square: its four faces are not triangles.)
 *  - The weighted area.  "The approximate area lying to the right of each
 *    left edge in each intersecting filtered area is weighted and then added
 *    to the intensity for the corresponding image dot.  The contributions
 *    of right edges, on the other hand, are subtracted ... since the final
 *    sum is the weighted area covered by the polygon, very small polygons
 *    are properly handled" (fig. 3.13, "Left Areas - Right Areas = Area").
 *    The area right of an edge in the square is found "by the method of
 *    Chapter Two": where the edge enters and leaves the square's rows gives
 *    one rectangle (fig. 2.8), whose weight is read from the partial-sum
 *    tables of the 1-D weight (fig. 2.7: four lookups, two subtracts, two
 *    multiplies).  An edge whose rows end inside the square ("too small or
 *    too close to horizontal") is taken from its end points, and a flat
 *    edge bounds no rows: its polygon's other edges carry its area, as in
 *    the filtering tiler, which does not drop short edge blocks.
 *  - Hidden surfaces, hidden=priority (the default: a tiler serves the
 *    z-priority and z-buffer algorithms).  Polygons are written back to
 *    front, each blended into the frame buffer by its weighted area ("the
 *    blending constant ... stored ... as a transmittance"): buf = cov c +
 *    (1 - cov) buf.  Abutting polygons would let the background show
 *    through their shared edge (fig. 3.5, "accented with a pencil line"), so
 *    Crow's rule: "when a tagged edge is to be written, it can first be
 *    checked to see if the adjacent polygon has been written; if not, all
 *    those picture elements which would otherwise be blended with the
 *    current polygon intensity are simply overwritten", and the adjacent
 *    polygon, written later, blends with it alone.  Here a layer is
 *    adjacent to a layer in front when a piece of edge of one has the same
 *    end and control points as a piece of the other (the adjacency of his
 *    fig. 3.3); the layer written first overwrites the pixels along their
 *    shared edges: it is painted across them, over the region of the
 *    adjacent layer in front, up to that layer's other edges (what a layer
 *    paints is the union of its region and those of the adjacent layers in
 *    front), and the front layer then blends with it alone.  Edges that
 *    meet only in part (catmull's green and blue) are not adjacent in this
 *    sense and show his pencil line, as do edges of unrelated polygons in
 *    one pixel (fig. 3.6: "no one blending rule can handle all possible
 *    situations"), and a pixel where the two abutting polygons also meet a
 *    third surface (feibush's stripes at the edge of their square).
 *  - Hidden surfaces, hidden=scan: his scanning algorithm, where "all
 *    information is available, all situations can be resolved": each
 *    visible part of an edge is blended between the surfaces on its two
 *    sides, and where visibility changes ("implied edges ... The
 *    intersection of the two segments involved can be computed to high
 *    resolution") the parts are passed to the filter as edges of their own
 *    (visible.c).  So a pixel is the colour left of the square plus, per
 *    visible part of an edge, its rectangle times the change of colour
 *    across it.
 *  - Hidden surfaces, hidden=zbuffer: his z-buffer without the extensions
 *    he proposes (ch. 3, "Comparison of three basic hidden-surface
 *    techniques", fig. 3.7; "Implementation of a z-buffer algorithm"): the
 *    polygons "written in any order", here the worst one, front to back,
 *    so that every surface lies behind what is already stored.  A dot
 *    holds one intensity and one depth: the first layer whose weighted area
 *    reaches it is blended with the background there and stores its depth;
 *    a layer written later lies behind that depth and "no new information
 *    is stored", so "the blending information for the first surface has
 *    been lost" along every edge in front of another surface (no
 *    adjacent-polygon rule: a z-buffer knows nothing of other polygons).
 *
 * What is chosen here.
 *  - The polygons are the scene's layers: a layer's paths are written as
 *    one polygon set, its weighted area the sum over its edges, each edge's
 *    change of the layer's coverage (0 or 1 by its fill rule) times the
 *    area right of it.  Crow's tiler takes convex polygons one at a time;
 *    summing edges handles any polygon, holes and either fill rule, and the
 *    polygons of one layer neither overlap (a layer's coverage is its union)
 *    nor blend into each other.  Quadratic arcs are taken as edges as well:
 *    the rectangle of an arc also lies between where it enters and leaves.
 *  - The tables (area=table): the thesis gives no size.  res= entries per
 *    pixel (default 16), N = 2 res intervals over the square's width 2:
 *    T[k] = C(-1 + k / res) - C(-1), C the tent's exact 1-D integral; a
 *    coordinate is read at the nearest entry, as a discrete table is.
 *  - area=exact (a variant: the limit of Crow's "by making the rectangular
 *    blocks arbitrarily small, an arbitrarily good approximation to G can
 *    be obtained", ch. 2): the area right of an edge weighted exactly,
 *    integral over the edge's rows of w(y - cy) (1 - C(x(y) - cx)) dy.  On
 *    a piece x(t), y(t) are quadratics in its parameter t, w is linear and
 *    C quadratic between their kinks, so between the heights where
 *    y = cy or x = cx - 1, cx, cx + 1 the integrand is a polynomial of
 *    degree at most 7 in t (3 for a line), which 4-point Gauss-Legendre
 *    integrates exactly: the method is exact to rounding wherever the
 *    hidden surfaces are (hidden=scan).  A conic piece (an arc of an
 *    ellipse) gives a trigonometric polynomial of degree 4 in its angle,
 *    taken by 8-point Gauss-Legendre on parts of at most 0.5 radian: not
 *    exact, but within 6e-19 of the integrand's largest value per part
 *    (right_conic).  The colour left of the square
 *    takes the exact weight of its rows, C(yb - cy) - C(ya - cy).
 *
 * Error analysis (per pixel and unit of contrast, against the exact tent
 * reference).
 *  - area=table: each lookup is off by at most wmax d / 2 = 1 / (2 res)
 *    (entries d = 1 / res apart, wmax = 1); a rectangle takes three lookups
 *    (its side and its two rows) and each block of rows two.  The rectangle
 *    itself: an edge of slope s (dx/dy) crossing the square's rows is
 *    replaced by its mean position, which for a straight edge across the
 *    whole square is off by about s^2 |C''| var(v) / 2 <= s^2 / 12 (|C''|
 *    <= 1, var(v) = 1/6 under the tent), and for an edge that ends inside
 *    the square (first order: its rows are not symmetric about the centre)
 *    by up to |s| times the shift of its rows' weighted mean: this does not
 *    fall with res, and is Crow's approximation.  Measured, hidden=scan,
 *    res=16 (RMSE, max): crow 256x256 1.0e-2, 8.1e-2; 128x128 feibush
 *    5.1e-3, 5.0e-2; slivers 5.7e-3, 4.2e-2; star 2.6e-2, 2.3e-1 (its
 *    wedges end inside the squares near the centre); catmull 5e-18 (edges
 *    vertical and horizontal, on the table's entries).
 *  - area=exact: rounding, and the heights where the pieces meet (found in
 *    closed form, aa_piece_meet); hidden=scan is exact.
 *  - hidden=priority: exact where a pixel's square holds one layer's
 *    edges, or two abutting polygons sharing an edge; elsewhere the
 *    blending rule's error (fig. 3.6), up to the whole contrast in the
 *    pencil line between polygons that meet without sharing an edge.
 *    Measured, area=exact, 128x128 (RMSE, max): feibush 2.1e-2, 2.5e-1
 *    (7.4e-2 without the adjacent-polygon rule); catmull:tiles=4 1.7e-2,
 *    1.1e-1; slivers 2.8e-3, 7.4e-2 (the front layer that clips them at
 *    the square's edge); star and crow, one layer, exact.
 *  - hidden=zbuffer: as hidden=priority where a dot is reached by one
 *    layer; where a layer in front reaches it, the whole contrast between
 *    the background and the surface behind it, times the share of the
 *    front layer's weight it does not cover.
 *
 * Known answers (tests/test_prefilters.c): area=exact with hidden=scan
 * matches the exact tent:r=1 reference (aa_truth_render) within 1e-12 on
 * catmull, slivers (also overlapping ones), star, feibush and crow (measured
 * at most 8e-15); area=table gives Crow's rectangle, 1 - C(e) for a
 * straight edge across the square, within its lookups, and approaches the
 * reference with res where edges are vertical and horizontal; two polygons
 * of different colours sharing an edge give the exact two-colour blend
 * under hidden=priority, and the pencil line when the edge is cut
 * differently on each side; a hidden polygon adds nothing.
 *
 * Cost: per pixel whose square meets an edge, the visible parts of the
 * edges near it (visible.c: sorting the pieces of each band along x and one
 * meeting test per neighbouring pair) and one rectangle (table) or a few
 * 4-point rules (exact) per part; other pixels are filled in runs.  A pixel
 * depends only on its row's strip: the image is the same for any thread
 * count.  Counters: samples = 0, expensive_pixels = pixels summed.
 * Limits: tent:r=1 only; values clamped to [0, 1].
 */
#include "core.h"
#include "methods.h"
#include "sampling.h"
#include "visible.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TL_MAX_RES 1024
#define TL_DEFAULT_RES 16

enum { P_AREA, P_HIDDEN, P_RES };
enum { AREA_TABLE, AREA_EXACT };
enum { HIDDEN_PRIORITY, HIDDEN_SCAN, HIDDEN_ZBUFFER };

static const aa_param crowtiler_params[] = {
    {"area", AA_PARAM_CHOICE, AREA_TABLE, 0, 0, 0, "table|exact",
     "the weighted area right of an edge: one rectangle from Crow's partial-sum tables, or "
     "exact (a variant)"},
    {"hidden", AA_PARAM_CHOICE, HIDDEN_PRIORITY, 0, 0, 0, "priority|scan|zbuffer",
     "hidden surfaces: layers blended back to front with Crow's adjacent-polygon rule "
     "(z-priority), each visible edge between its two surfaces (scanning), or layers "
     "written front to back into a z-buffer that keeps no blending information"},
    {"res", AA_PARAM_INT, TL_DEFAULT_RES, 1, TL_MAX_RES, 0, NULL,
     "area=table: table entries per pixel"},
    {0}};

typedef struct tl_state {
    aa__sampler sampler; /* workers; own scratch: visible parts, layer sums */
    double *t;           /* t[0 .. n]: the table */
    int n;
    /* adj[l * nl + m]: layer m, in front of l, shares an edge with it */
    unsigned char *adj;
    int nl;
    const aa_scene *adj_of;
} tl_state;

typedef struct tl_render {
    const tl_state *S;
    const aa_scene *scene;
    const aa_filter *f;
    int area, hidden;
} tl_render;

static int crowtiler_check(const double *p, const aa_filter *f)
{
    if (f->type != &aa_filter_tent || f->spec.v[0] != 1.0)
        return aa_fail(AA_EINVAL, "crowtiler forms Crow's filter only, a pyramid two pixels "
                                  "square: use -f tent:r=1");
    if ((int)p[P_AREA] == AREA_EXACT && p[P_RES] != TL_DEFAULT_RES)
        return aa_fail(AA_EINVAL, "res=%g sets the tables of area=table; area=exact reads no "
                                  "table (leave res out)",
                       p[P_RES]);
    return AA_OK;
}

/* ---- the table and the exact integral ---- */

static int table_make(tl_state *S, const double *p, const aa_filter *f)
{
    int n = 2 * (int)p[P_RES];
    double *t = malloc((size_t)(n + 1) * sizeof *t);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for a table of %d entries", n + 1);
    double lo = aa_filter_cdf(f, -1.0);
    for (int k = 0; k <= n; k++)
        t[k] = aa_filter_cdf(f, -1.0 + 2.0 * k / n) - lo;
    t[0] = 0.0, t[n] = 1.0;
    free(S->t);
    S->t = t;
    S->n = n;
    return AA_OK;
}

/* The table at offset u in [0, 2] from the square's left (or top) side, at
 * the nearest entry. */
static inline double lookup(const tl_state *S, double u)
{
    double k = floor(u * (S->n / 2.0) + 0.5);
    k = k < 0.0 ? 0.0 : (k > S->n ? S->n : k);
    return S->t[(int)k];
}

static const double gl4_x[4] = {-0.86113631159405257522, -0.33998104358485626480,
                                0.33998104358485626480, 0.86113631159405257522};
static const double gl4_w[4] = {0.34785484513745385737, 0.65214515486254614263,
                                0.65214515486254614263, 0.34785484513745385737};
/* Six points for a cubic arc, exact to degree 11: the weight (linear in
 * y, a cubic in t) times the cdf (quadratic in x, a cubic in t) times
 * dy/dt (quadratic) is of degree 11. */
static const double gl6_x[6] = {-0.93246951420315202781, -0.66120938646626451366,
                                -0.23861918608319690863, 0.23861918608319690863,
                                0.66120938646626451366,  0.93246951420315202781};
static const double gl6_w[6] = {0.17132449237917034504, 0.36076157304813860757,
                                0.46791393457269104739, 0.46791393457269104739,
                                0.36076157304813860757, 0.17132449237917034504};
/* Eight points for a conic piece, in its angle s: the weight (linear in
 * y = ey - er cos s) times the cdf (quadratic in x = ex + ea cos s + eb
 * sin s) times dy/ds = er sin s is a trigonometric polynomial of degree 4,
 * not a polynomial, so the rule is not exact; on parts of at most
 * CONIC_STEP radians its error, h^17 (8!)^4 / (17 (16!)^3) max |f^(16)|
 * with |f^(16)| <= 4^16 max |f|, is below 6e-19 max |f| (the scene's
 * rounding is larger). */
static const double gl8_x[4] = {0.18343464249564980494, 0.52553240991632898582,
                                0.79666647741362673959, 0.96028985649753623168};
static const double gl8_w[4] = {0.36268378337836198297, 0.31370664587788728734,
                                0.22238103445337447054, 0.10122853629037625915};
#define CONIC_STEP 0.5

/* The conic piece p's part of right_exact between parameters ta and tb. */
static double right_conic(const aa_filter *f, const aa_piece *p, double ta, double tb,
                          double cx, double cy)
{
    double w = p->s1 - p->s0, sa = p->s0 + ta * w, sb = p->s0 + tb * w;
    int parts = (int)ceil((sb - sa) / CONIC_STEP);
    parts = parts < 1 ? 1 : parts;
    double sum = 0.0;
    for (int k = 0; k < parts; k++) {
        double a = sa + (sb - sa) * k / parts, b = k + 1 == parts ? sb : sa + (sb - sa) * (k + 1) / parts;
        double h = 0.5 * (b - a), m = 0.5 * (a + b), part = 0.0;
        for (int g = 0; g < 8; g++) {
            double s = m + h * (g < 4 ? -gl8_x[3 - g] : gl8_x[g - 4]);
            double c = cos(s), sn = sin(s);
            double x = p->ex + (p->ea * c + p->eb * sn), y = p->ey - p->er * c;
            part += (g < 4 ? gl8_w[3 - g] : gl8_w[g - 4]) * aa_filter_weight(f, y - cy) *
                    (1.0 - aa_filter_cdf(f, x - cx)) * p->er * sn;
        }
        sum += h * part;
    }
    return sum;
}

/* The exact weight right of piece p over rows [ya, yb] (inside the square
 * of centre (cx, cy)): integral of w(y - cy) (1 - C(x(y) - cx)) dy, by
 * 4-point Gauss-Legendre in the piece's parameter between the heights where
 * the integrand's polynomial changes (header). */
static double right_exact(const aa_filter *f, const aa_piece *p, double ya, double yb,
                          double cx, double cy)
{
    double ys[32], k[8];
    int n = 0, nk = f->type->kinks(f->spec.v, k);
    ys[n++] = ya;
    ys[n++] = yb;
    if (cy > ya && cy < yb)
        ys[n++] = cy;
    for (int q = 0; q < nk; q++) {
        double m[3];
        int c = aa_piece_meet_x(p, cx + k[q], m);
        for (int r = 0; r < c; r++)
            if (m[r] > ya && m[r] < yb)
                ys[n++] = m[r];
    }
    aa__vis_sort(ys, (size_t)n);
    double sum = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ys[s] < ys[s + 1]))
            continue;
        double ta = ys[s] <= p->y0 ? 0.0 : aa_piece_t_at(p, ys[s]);
        double tb = ys[s + 1] >= p->y1 ? 1.0 : aa_piece_t_at(p, ys[s + 1]);
        if (p->kind == AA_PIECE_CONIC) {
            sum += right_conic(f, p, ta, tb, cx, cy);
            continue;
        }
        double h = 0.5 * (tb - ta), m = 0.5 * (ta + tb), part = 0.0;
        /* offset pieces (not polynomials): the 6-point rule, not exact */
        int cubic = p->kind == AA_PIECE_CUBIC || p->kind == AA_PIECE_OFFSET, ng = cubic ? 6 : 4;
        const double *gx = cubic ? gl6_x : gl4_x, *gw = cubic ? gl6_w : gl4_w;
        for (int g = 0; g < ng; g++) {
            double t = m + h * gx[g];
            double x, y, dy;
            aa__piece_point(p, t, &x, &y, &dy);
            part += gw[g] * aa_filter_weight(f, y - cy) * (1.0 - aa_filter_cdf(f, x - cx)) * dy;
        }
        sum += h * part;
    }
    return sum;
}

/* ---- edges shared with a polygon in front ---- */

typedef struct tl_key {
    double k[8]; /* ends, control point, a cubic's second (else 0) */
    int layer;
} tl_key;

static int cmp_key(const void *a, const void *b)
{
    const tl_key *x = a, *y = b;
    for (int q = 0; q < 8; q++)
        if (x->k[q] != y->k[q])
            return x->k[q] < y->k[q] ? -1 : 1;
    return (x->layer > y->layer) - (x->layer < y->layer);
}

/* adj[l * nl + m] = 1 if a piece of layer l (not flat) has the same end and
 * control points as a piece of layer m in front of it (m < l): the layers'
 * polygons abut along it. */
static int adjacency_make(tl_state *S, const aa_scene *s)
{
    size_t n;
    const aa_piece *p = aa_scene_pieces(s, &n);
    int nl = aa_scene_layer_count(s);
    size_t nn = (size_t)(nl > 0 ? nl : 1);
    unsigned char *adj = calloc(nn * nn, 1);
    tl_key *key = malloc((n ? n : 1) * sizeof *key);
    if (!adj || !key) {
        free(adj);
        free(key);
        return aa_fail(AA_ENOMEM, "out of memory for the adjacency of %zu pieces", n);
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (p[i].dir)
            key[m++] = (tl_key){{p[i].y0, p[i].y1, p[i].x0, p[i].x1, p[i].cx, p[i].cy,
                                 p[i].c2x, p[i].c2y},
                                p[i].layer};
    qsort(key, m, sizeof *key, cmp_key);
    for (size_t a = 0; a < m;) {
        size_t b = a + 1;
        while (b < m && !memcmp(key[b].k, key[a].k, sizeof key[a].k))
            b++;
        for (size_t q = a; q < b; q++)
            for (size_t r = a; r < b; r++)
                if (key[r].layer < key[q].layer)
                    adj[(size_t)key[q].layer * nn + (size_t)key[r].layer] = 1;
        a = b;
    }
    free(key);
    free(S->adj);
    S->adj = adj;
    S->nl = nl;
    S->adj_of = s;
    return AA_OK;
}

/* ---- one pixel ---- */

typedef struct tl_pixel {
    const tl_render *R;
    double cx, cy, xl, top;
    double acc[3]; /* hidden=scan */
    double *cov;   /* hidden=priority, zbuffer: per layer */
    double *val;   /* hidden=priority, zbuffer: per layer */
} tl_pixel;

static double rows_weight(const tl_pixel *P, double ya, double yb)
{
    if (P->R->area == AREA_EXACT)
        return aa_filter_cdf(P->R->f, yb - P->cy) - aa_filter_cdf(P->R->f, ya - P->cy);
    return lookup(P->R->S, yb - P->top) - lookup(P->R->S, ya - P->top);
}

static inline int covered(const aa_scene *s, int layer, const int *wind)
{
    int w = wind[layer];
    return aa_scene_layer_rule(s, layer) == AA_FILL_EVENODD ? (w & 1) : (w != 0);
}

/* hidden=priority, zbuffer: what each layer paints under a winding.  With
 * priority, a layer written before an abutting layer in front (adj)
 * overwrites the pixels it would blend along their shared edge: it is
 * painted across that edge, over the front layer's region too, up to the
 * front layer's other edges, and the front layer then blends with it
 * alone.  The z-buffer has no such rule. */
static void tl_values(void *ctx, const int *wind, double *out)
{
    const tl_pixel *P = ctx;
    const tl_state *S = P->R->S;
    const aa_scene *s = P->R->scene;
    int nl = S->nl;
    const int adjacent = P->R->hidden == HIDDEN_PRIORITY;
    for (int l = 0; l < nl; l++) {
        int c = covered(s, l, wind);
        for (int m = 0; m < l && !c && adjacent; m++)
            c = S->adj[(size_t)l * nl + m] && covered(s, m, wind);
        out[l] = c;
    }
}

/* A band of rows: the colour (scan) or the layers painted (priority) just
 * inside the square's left side. */
static void tl_band(void *ctx, double ya, double yb, const int *wind)
{
    tl_pixel *P = ctx;
    const aa_scene *s = P->R->scene;
    double wy = rows_weight(P, ya, yb);
    if (!(wy != 0.0))
        return;
    if (P->R->hidden == HIDDEN_SCAN) {
        aa_rgb c = aa_scene_colour_of(s, wind);
        for (int ch = 0; ch < 3; ch++)
            P->acc[ch] += wy * c.c[ch];
        return;
    }
    tl_values(P, wind, P->val);
    for (int l = 0; l < P->R->S->nl; l++)
        P->cov[l] += wy * P->val[l];
}

/* A visible part of an edge inside the square with its change of colour
 * (scan) or of what each layer paints (priority): the weighted area right
 * of it. */
static void tl_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                   int inside)
{
    tl_pixel *P = ctx;
    const tl_render *R = P->R;
    (void)inside;
    double area;
    if (R->area == AREA_EXACT) {
        area = right_exact(R->f, p, ya, yb, P->cx, P->cy);
    } else {
        double xr = 0.5 * (aa_piece_x_at(p, ya) + aa_piece_x_at(p, yb));
        area = (1.0 - lookup(R->S, xr - P->xl)) * rows_weight(P, ya, yb);
    }
    if (R->hidden == HIDDEN_SCAN)
        for (int ch = 0; ch < 3; ch++)
            P->acc[ch] += jump[ch] * area;
    else
        for (int l = 0; l < R->S->nl; l++)
            P->cov[l] += jump[l] * area;
}

static inline double clamp01(double v)
{
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const tl_render *R = ctx;
    const aa_scene *s = R->scene;
    int scan = R->hidden == HIDDEN_SCAN, nl = R->S->nl, dims = scan ? 3 : (nl > 0 ? nl : 1);
    aa__vis v;
    aa__vis_bind(&v, s, dims, wk->own);
    double *cov = (double *)((char *)wk->own + aa__vis_size(s, dims));
    tl_pixel P = {R, i + 0.5, j + 0.5, i - 0.5, j - 0.5, {0.0, 0.0, 0.0}, cov, cov + dims};
    for (int l = 0; l < nl; l++)
        cov[l] = 0.0;
    const aa__vis_sink sink = {tl_band, tl_run, NULL, scan ? NULL : tl_values, &P, dims, 0, 0, 0};
    aa__vis_window(&v, wk->strip, P.xl, P.xl + 2.0, P.top, P.top + 2.0, &sink);
    if (scan) {
        for (int ch = 0; ch < 3; ch++)
            px[ch] = clamp01(P.acc[ch]);
        return;
    }
    aa_rgb buf = aa_scene_background(s);
    if (R->hidden == HIDDEN_ZBUFFER) {
        /* front to back: the first layer to reach the dot is blended with
         * the background and stores its depth there; every later layer
         * lies behind that depth and is not written */
        for (int l = 0; l < nl; l++) {
            double a = clamp01(cov[l]);
            if (!(a > 0.0))
                continue;
            aa_rgb c = aa_scene_layer_colour(s, l);
            for (int ch = 0; ch < 3; ch++)
                buf.c[ch] += a * (c.c[ch] - buf.c[ch]);
            break;
        }
        for (int ch = 0; ch < 3; ch++)
            px[ch] = clamp01(buf.c[ch]);
        return;
    }
    /* back to front, each layer blended into the buffer by its coverage */
    for (int l = nl - 1; l >= 0; l--) {
        double a = clamp01(cov[l]);
        aa_rgb c = aa_scene_layer_colour(s, l);
        for (int ch = 0; ch < 3; ch++)
            buf.c[ch] += a * (c.c[ch] - buf.c[ch]);
    }
    for (int ch = 0; ch < 3; ch++)
        px[ch] = clamp01(buf.c[ch]);
}

static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    return aa__sampler_row(wk, j, 1.0, 0, shade, ctx, out, samples, expensive);
}

static int prepare(tl_state *S, const double *p, const aa_job *job)
{
    int nl = aa_scene_layer_count(job->placed);
    int dims = (int)p[P_HIDDEN] == HIDDEN_SCAN ? 3 : (nl > 0 ? nl : 1);
    size_t own = aa__vis_size(job->placed, dims) + 2 * (size_t)dims * sizeof(double);
    int st = aa__sampler_ready(&S->sampler, job, own);
    if (!st && S->adj_of != job->placed)
        st = adjacency_make(S, job->placed);
    return st;
}

static int crowtiler_init(void *state, const double *p, const aa_job *job)
{
    tl_state *S = state;
    if ((int)p[P_HIDDEN] != HIDDEN_SCAN && aa_scene_is_clipped(job->placed))
        return aa_fail(AA_EINVAL, "crowtiler:hidden=%s blends layers by their areas: this "
                                  "scene has clip paths, which it does not apply; "
                                  "hidden=scan takes them",
                       (int)p[P_HIDDEN] == HIDDEN_PRIORITY ? "priority" : "zbuffer");
    if ((int)p[P_HIDDEN] == HIDDEN_PRIORITY && !aa_scene_is_opaque(job->placed))
        return aa_fail(AA_EINVAL, "crowtiler:hidden=priority blends opaque layers by their "
                                  "areas: this scene has translucent layers (opacity below "
                                  "1); hidden=scan takes them");
    int st = table_make(S, p, &job->filter);
    S->adj_of = NULL; /* the adjacency is made again for this job's scene */
    return st ? st : prepare(S, p, job);
}

static int crowtiler_render(void *state, const double *p, const aa_job *job, aa_image *out,
                            aa_counters *counters)
{
    tl_state *S = state;
    int st = prepare(S, p, job);
    if (st)
        return st;
    const tl_render R = {S, job->placed, &job->filter, (int)p[P_AREA], (int)p[P_HIDDEN]};
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void crowtiler_release(void *state)
{
    tl_state *S = state;
    aa__sampler_free(&S->sampler);
    free(S->t);
    free(S->adj);
    S->t = NULL;
    S->adj = NULL;
    S->adj_of = NULL;
}

const aa_method_type aa_method_crowtiler = {
    {"crowtiler",
     "Crow's filtering tiler: left areas minus right areas under the two-pixel pyramid "
     "(figs. 3.12-3.13)",
     crowtiler_params},
    sizeof(tl_state),
    0,
    crowtiler_check,
    crowtiler_init,
    crowtiler_render,
    crowtiler_release};
