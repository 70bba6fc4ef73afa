/*
 * area_gradient.c: the `area` method on linear-gradient paint, exactly.
 *
 * The picture (patterns/README.md, "Gradients").  A layer painted with a
 * linear gradient shows at a point the stops' sRGB-encoded channels and
 * opacity interpolated at the spread of t, t = gu x + gv y + g0 an affine
 * function of the position (pixel units; its level lines are the stop
 * lines).  The composite of the layers covering the point is formed in
 * encoded values and decoded to linear light; the box filter integrates
 * the decoded value over the pixel.
 *
 * The composite as a function of one layer's paint.  Source over and group
 * opacity are affine in a layer's opacity o and in o c (c an encoded
 * channel), so the encoded composite of a region whose winding numbers
 * are fixed is, channel by channel,
 *
 *     e = K0 + K1 o + K2 o c,
 *
 * K0 the composite with the layer at opacity 0, K1 = E(o = 1, c = 0) -
 * K0, K2 = E(1, 1) - E(1, 0), read from the scene's own compositor
 * (aa_scene_encoded_with: no second compositor here).  Between two knots
 * of t (a stop offset passed, or the spread's turn: pad's ends, repeat's
 * and reflect's period ends) o and c are affine in t; if only one of
 * them changes there, e is affine in t.  Where both change, o c is
 * quadratic in t and the decoding of a quadratic, ((q + 0.055)/1.055)^2.4,
 * has no elementary integral: such a gradient is refused by name (load),
 * as are two gradient layers that both show at one point (the composite
 * is then a product of two functions of the position: refused at the
 * pixel, naming it and both layers).
 *
 * Green's theorem.  With h(t) = dec(e(t)) (dec the sRGB decoding: s/12.92
 * for s <= T = 0.04045, ((s + 0.055)/1.055)^2.4 above) the pixel's value
 * over a region R on which the covering layers do not change is the
 * integral of h(t(x, y)) over R.  Take coordinates xi = t and eta = n.p,
 * n = (-gv, gu)/k, k = |(gu, gv)| (the unit normal of the gradient, along
 * the stop lines): the map (x, y) -> (xi, eta) has determinant k > 0, so
 * dx dy = dxi deta / k and orientation is kept.  With H a continuous
 * antiderivative of h (H' = h; H is continuous even across a sharp step,
 * where h jumps), Green's theorem gives
 *
 *     int_R h(t) dA = (1/k) oint_dR H(t) deta,
 *
 * the boundary taken counter-clockwise in (x, y).  On a straight edge from
 * P0 to P1, t and eta are both affine in the edge's parameter lambda in
 * [0, 1], so its term is
 *
 *     (n.(P1 - P0) / k) mean over [t0, t1] of H
 *         = ((-gv dx + gu dy) / k^2) (G(t1) - G(t0)) / (t1 - t0),
 *
 * G' = H (G'' = h): for the power branch G holds powers 3.4 and 4.4 of the
 * shifted value (s + 0.055)/1.055, for the linear branch it is a
 * polynomial.  An edge along a stop line (t0 = t1) takes H(t0): the limit,
 * no division.  The constant of H is free (oint c deta = 0): H is 0 at
 * the region's first vertex and carried from vertex to vertex, so every H
 * is of the size of the region, not of t.  Check: h = 1, H = t - t_ref
 * gives (1/k^2) oint t (-gv dx + gu dy) = (gu^2 + gv^2) (area) / k^2, the
 * area (oint x dy = -oint y dx = area, oint x dx = oint y dy = 0).
 *
 * The pieces.  The mean of H over [lo, hi] is cut at every knot of t
 * (between two knots the spread is affine, of slope 1, -1 or 0) and, in
 * each piece where e is affine, where e passes T (the decoding's two
 * branches).  On a piece of length L starting at w = 0 where e(w) = e0 +
 * de w, with H0 the value of H at its start,
 *
 *     int_0^L H = L H0 + I2,  H(L) = H0 + I1,
 *     I1 = int_0^L h,  I2 = int_0^L (L - w) h(w) dw.
 *
 * Linear branch (h = e / 12.92): I1 = L (e0 + de L/2) / 12.92, I2 = L^2
 * (e0/2 + de L/6) / 12.92, exact polynomials.  Power branch: u(w) =
 * (e(w) + 0.055)/1.055 = u0 (1 + r w/L), r = de L / (1.055 u0) > -1 (u
 * stays at least (T + 0.055)/1.055 > 0.09), and
 *
 *     I1 = L u0^2.4 A(r),   A(r) = ((1 + r)^3.4 - 1) / (3.4 r),
 *     I2 = L^2 u0^2.4 B(r), B(r) = int_0^1 (1 - z)(1 + r z)^2.4 dz
 *                                 = ((1 + r)^4.4 - 1 - 4.4 r) / (4.4 x 3.4 r^2)
 *
 * (by parts: the integral of (1 - z) against (1 + r z)^2.4 is
 * -1/(3.4 r) + ((1 + r)^4.4 - 1)/(4.4 x 3.4 r^2)).  These are G(t1) -
 * G(t0) over the slope written without cancellation: A through expm1(3.4
 * log1p r) / (3.4 r), a few ulps for every r (1 at r = 0, the mean-value
 * form: a nearly constant e gives L u0^2.4, no difference of powers).  B
 * subtracts 1 + 4.4 r from (1 + r)^4.4, which cancels for small r: for
 * |r| <= 1/4 it is taken from its series B(r) = sum_k b_k r^k, b_0 = 1/2,
 * b_k = b_(k-1) (3.4 - k) / (k + 2) (the binomial series of (1 + r)^4.4
 * from its r^2 term on, over 4.4 x 3.4).  From k = 4 on |b_k| <= |b_3| <
 * 0.0112 and the ratio |b_k / b_(k-1)| < 1, so the tail after AR_BSERIES
 * = 30 terms is below 0.0112 x 4^-30 / (1 - 1/4) < 1.4e-20, relative to
 * B >= 0.4 on |r| <= 1/4: under rounding.  The sum stops earlier once
 * a term is under 2^-60 (the tail after it is under a third of it).  Above |r| = 1/4 the closed
 * form loses at most a factor 4.4/(14.96 x 0.25 x 0.227) < 6 to the
 * cancellation (the terms over the result; B >= B(-1) = 0.227 on r > -1),
 * a few ulps.  Each
 * piece's mean over its length is a weighted sum with weights in [0, 1]:
 * nothing divides a small difference by a small length.
 *
 * The regions.  Pixels no edge enters are one region, the pixel's square.
 * Pixels that edges enter go to Catmull's recursive pixel integrater,
 * split on every edge (as in scenes that composite, area_composite.c)
 * until a region holds none; its winding numbers (at its centroid) give
 * the covering layers and so e(t) on it.  Regions are convex polygons of
 * straight edges: a gradient scene with curved edges (quadratic, cubic
 * or elliptical arcs, offset curves) is refused, naming a curved piece's
 * layer (along a parabola t is quadratic in its parameter and H(t) eta'
 * has no closed-form integral), as are radial gradients (t is not affine
 * in the position).  A pixel with more than CM_MAX_EDGES edges is refused
 * naming the pixel (the bands, which take such pixels in flat scenes,
 * integrate constant colours only).  A gradient passing more than
 * AR_GKNOTS knots across a pixel is refused at load.
 *
 * Linear light.  A gradient whose stops interpolate in linear light
 * (aa_scene_layer_gradient_interpolation) paints C = encode(v), v its
 * linear channel affine in t between stops.  Where nothing translucent
 * lies over it and it is opaque there, the composite is C itself (K0 + K1 o
 * = 0 and K2 o = 1 with o its opacity: checked exactly, per region and per
 * stop segment where the channel changes, gstate_make) and h =
 * decode(encode(v)), which is v, affine in t, except on v in (0.0031308,
 * 0.0031308073), where the standard's two pieces do not meet and h is
 * encode's power piece over 12.92 (lin_piece: its integrals by a binomial
 * series, the interval being 2.3e-6 of v wide relative).  So the integral
 * is exact there.  Elsewhere (the layer translucent, or under something
 * translucent, on a segment where a channel changes) the composite is
 * decode(K0 + K1 o + K2 o encode(v)), which has no elementary integral:
 * the pixel is refused, naming it and the layer; the test is the region's,
 * over all the gradient's segments, so a region that shows only a padded
 * end of such a gradient is refused too (a refusal, never a wrong image).
 * Where v is constant between two stops C is too and the sRGB path above
 * takes it.
 */
#include "area_pixel.h"

#include <stdlib.h>
#include <string.h>

#define AR_BSERIES 30
#define AR_T 0.04045

int aa__area_gradient_split = 1;

/* ------------------------------------------------------------------------
 * Loading
 * ------------------------------------------------------------------------ */

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void area_gradient_free(ar_state *S)
{
    for (int g = 0; g < S->ngrad; g++) {
        free(S->grad[g].offset);
        free(S->grad[g].enc);
        free(S->grad[g].knot);
        free(S->grad[g].lv);
    }
    free(S->grad);
    free(S->gof);
    S->grad = NULL, S->gof = NULL, S->ngrad = 0;
}

static int load_one(ar_grad *G, int layer, const aa_gradient *g, int lin)
{
    const double *m = g->m, *p = g->p;
    double det = m[0] * m[3] - m[1] * m[2];
    double inv[6] = {m[3] / det, -m[1] / det, -m[2] / det, m[0] / det, 0, 0};
    inv[4] = -(inv[0] * m[4] + inv[2] * m[5]);
    inv[5] = -(inv[1] * m[4] + inv[3] * m[5]);
    /* t = ((q - P1).(P2 - P1)) / |P2 - P1|^2, q = inv p */
    double dx = p[2] - p[0], dy = p[3] - p[1], l2 = dx * dx + dy * dy;
    G->layer = layer;
    G->spread = g->spread;
    G->nstops = g->nstops;
    G->gu = (inv[0] * dx + inv[1] * dy) / l2;
    G->gv = (inv[2] * dx + inv[3] * dy) / l2;
    G->g0 = ((inv[4] - p[0]) * dx + (inv[5] - p[1]) * dy) / l2;
    if (!isfinite(G->gu) || !isfinite(G->gv) || !isfinite(G->g0) ||
        !(G->gu != 0.0 || G->gv != 0.0))
        return aa_fail(AA_EINVAL, "area: the linear gradient of layer %d has no finite "
                                  "direction in pixels (its map is degenerate)", layer);
    int n = g->nstops;
    G->offset = malloc((size_t)n * sizeof *G->offset);
    G->enc = malloc((size_t)n * sizeof *G->enc);
    G->knot = malloc(((size_t)2 * n + 4) * sizeof *G->knot);
    if (!G->offset || !G->enc || !G->knot)
        return aa_fail(AA_ENOMEM, "out of memory for a gradient of %d stops", n);
    G->lin = lin;
    if (lin && !(G->lv = malloc((size_t)n * sizeof *G->lv)))
        return aa_fail(AA_ENOMEM, "out of memory for a gradient of %d stops", n);
    for (int k = 0; k < n; k++) {
        G->offset[k] = g->stops[k].offset;
        for (int c = 0; c < 3; c++) {
            G->enc[k][c] = aa_srgb_encode(g->stops[k].colour.c[c]);
            if (lin)
                G->lv[k][c] = g->stops[k].colour.c[c];
        }
        G->enc[k][3] = g->stops[k].opacity;
        if (lin)
            G->lv[k][3] = g->stops[k].opacity;
    }
    for (int k = 0; k + 1 < n; k++) {
        if (!(G->offset[k + 1] > G->offset[k]))
            continue; /* a sharp step: nothing between */
        int colour = 0;
        for (int c = 0; c < 3; c++)
            colour |= G->enc[k + 1][c] != G->enc[k][c];
        if (colour && G->enc[k + 1][3] != G->enc[k][3])
            return aa_fail(AA_EINVAL,
                           "area: layer %d's linear gradient changes both colour and "
                           "opacity between stops %d and %d (offsets %g, %g): the composite "
                           "is then quadratic in the position and the integral of its sRGB "
                           "decoding has no closed form; refused, not approximated (use "
                           "point, supersample or jitter, or keep the opacity constant "
                           "where the colour changes)",
                           layer, k, k + 1, G->offset[k], G->offset[k + 1]);
    }
    /* the knots in one period: 0, the offsets, 1 (and reflect's mirror) */
    int nk = 0;
    G->knot[nk++] = 0.0;
    G->knot[nk++] = 1.0;
    for (int k = 0; k < n; k++) {
        G->knot[nk++] = G->offset[k];
        if (g->spread == AA_SPREAD_REFLECT)
            G->knot[nk++] = 2.0 - G->offset[k];
    }
    if (g->spread == AA_SPREAD_REFLECT)
        G->knot[nk++] = 2.0;
    qsort(G->knot, (size_t)nk, sizeof *G->knot, cmp_dbl);
    int u = 0;
    for (int k = 0; k < nk; k++)
        if (u == 0 || G->knot[k] != G->knot[u - 1])
            G->knot[u++] = G->knot[k];
    G->nknots = u;
    G->period = g->spread == AA_SPREAD_REPEAT ? 1.0 : g->spread == AA_SPREAD_REFLECT ? 2.0 : 0.0;
    if (G->period > 0.0) {
        /* a pixel's t spans at most k sqrt 2; knots per unit of t: (u - 1) / period */
        double across = hypot(G->gu, G->gv) * M_SQRT2 * (u - 1) / G->period;
        if (!(across <= AR_GKNOTS))
            return aa_fail(AA_EINVAL,
                           "area: layer %d's linear gradient repeats %g times across a pixel "
                           "(more than %d stops or period ends in one pixel): refused",
                           layer, hypot(G->gu, G->gv) * M_SQRT2 / G->period, AR_GKNOTS);
    }
    return AA_OK;
}

int area_gradient_load(ar_state *S, const aa_scene *scene)
{
    if (!aa_scene_has_gradients(scene))
        return AA_OK;
    size_t np;
    const aa_piece *pc = aa_scene_pieces(scene, &np);
    for (size_t k = 0; k < np; k++)
        if (pc[k].kind != AA_PIECE_LINE && pc[k].kind != AA_PIECE_FLAT)
            return aa_fail(AA_EINVAL,
                           "area: the scene has gradient paint and curved edges (layer %d has "
                           "%s): area integrates gradients exactly over regions bounded by "
                           "straight edges only (along an arc the gradient's t is not affine "
                           "and the decoded integral has no closed form); refused, not "
                           "approximated (use point, supersample or jitter)",
                           pc[k].layer,
                           pc[k].kind == AA_PIECE_QUAD    ? "a quadratic arc"
                           : pc[k].kind == AA_PIECE_CUBIC ? "a cubic arc"
                           : pc[k].kind == AA_PIECE_CONIC ? "an elliptical arc"
                                                          : "an offset curve (a stroked arc)");
    int nl = aa_scene_layer_count(scene), ng = 0;
    if (!(S->gof = malloc(((size_t)nl + 1) * sizeof *S->gof)) ||
        !(S->grad = calloc((size_t)nl + 1, sizeof *S->grad)))
        return aa_fail(AA_ENOMEM, "out of memory for %d layers' gradients", nl);
    for (int l = 0; l < nl; l++) {
        aa_gradient g;
        S->gof[l] = -1;
        if (!aa_scene_layer_gradient(scene, l, &g))
            continue;
        if (g.kind != AA_GRADIENT_LINEAR)
            return aa_fail(AA_EINVAL,
                           "area: layer %d is painted with a radial gradient: its t is not "
                           "affine in the position and the integral of the decoded colour over "
                           "a pixel has no closed form; area refuses it rather than approximate "
                           "(linear gradients are exact; use point, supersample or jitter)",
                           l);
        S->gof[l] = ng;
        S->ngrad = ++ng;
        int st = load_one(&S->grad[ng - 1], l, &g,
                          aa_scene_layer_gradient_interpolation(scene, l) != AA_INTERPOLATE_SRGB);
        if (st)
            return st;
    }
    return AA_OK;
}

/* ------------------------------------------------------------------------
 * The composite of a region
 * ------------------------------------------------------------------------ */

typedef ar_gstate gstate;

/* Record the refusal of pixel i of row r (the first in row order). */
static void gfail(const ar_row *r, int i, int kind, int a, int b)
{
    ar_worker *wk = r->wk;
    if (wk->gerr && (wk->gj < r->j || (wk->gj == r->j && wk->gi <= i)))
        return;
    wk->gerr = kind, wk->gi = i, wk->gj = r->j, wk->ga = a, wk->gb = b;
}

static const double corner[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};

/* Does layer lay[0]'s paint change the composite where the n layers lay[]
 * all cover the point?  Each layer's paint (encoded channels and opacity
 * o) between two of its stops moves on the segment between the stops'
 * points (o, o c) (one of o and c is constant there, load_one), so over
 * the gradient it stays in their convex hull; the composite is affine in
 * each layer's (o, o c), so it depends on lay[0]'s paint anywhere if and
 * only if it differs between two of lay[0]'s stops with each other layer
 * at one of its stops.  At most AR_GCOMBOS combinations are tried; past
 * that the answer is yes (a refusal, never a wrong image). */
#define AR_GCOMBOS 65536
static int influences(const ar_state *S, const int *w, int n, const int *lay)
{
    const ar_grad *G[5];
    double paints[4 * 5], e0[3], e[3];
    int idx[5] = {0};
    long combos = 1;
    for (int m = 0; m < n; m++) {
        G[m] = &S->grad[S->gof[lay[m]]];
        combos *= G[m]->nstops;
        if (combos > AR_GCOMBOS)
            return 1;
    }
    for (;;) {
        for (int m = 1; m < n; m++)
            memcpy(paints + 4 * m, G[m]->enc[idx[m]], sizeof corner[0]);
        for (int q = 0; q < G[0]->nstops; q++) {
            memcpy(paints, G[0]->enc[q], sizeof corner[0]);
            aa_scene_encoded_with_n(S->scene, w, n, lay, paints, q ? e : e0);
            if (q && (e[0] != e0[0] || e[1] != e0[1] || e[2] != e0[2]))
                return 1;
        }
        int m = 1;
        while (m < n && ++idx[m] == G[m]->nstops)
            idx[m++] = 0;
        if (m == n)
            return 0;
    }
}

static int gstate_make(const ar_row *r, int i, const int *w, gstate *gs);

/* The state of winding numbers w: 0, or 1 if refused (recorded).  It
 * depends on w only through the set of layers whose fill rule holds (as
 * the composite does, area_composite.c): the last AR_GMEMO sets met are
 * kept with their states. */
static int gstate_of(const ar_row *r, int i, const int *w, gstate *gs)
{
    const ar_state *S = r->S;
    ar_worker *wk = r->wk;
    const size_t nw = (size_t)S->nwords;
    uint64_t *key = wk->gkey + AR_GMEMO * nw;
    memset(key, 0, nw * sizeof *key);
    for (int l = 0; l < S->nl; l++)
        if (w[l] & S->inside[l])
            key[l >> 6] |= (uint64_t)1 << (l & 63);
    for (unsigned k = 0; k < wk->gn; k++)
        if (!memcmp(wk->gkey + k * nw, key, nw * sizeof *key)) {
            *gs = wk->gmemo[k];
            return 0;
        }
    if (gstate_make(r, i, w, gs))
        return 1;
    memcpy(wk->gkey + wk->gnext * nw, key, nw * sizeof *key);
    wk->gmemo[wk->gnext] = *gs;
    wk->gnext = (wk->gnext + 1) % AR_GMEMO;
    wk->gn += wk->gn < AR_GMEMO;
    return 0;
}

static int gstate_make(const ar_row *r, int i, const int *w, gstate *gs)
{
    const ar_state *S = r->S;
    int lay[5], n = 0, shown = -1;
    for (int g = 0; g < S->ngrad; g++) {
        int l = S->grad[g].layer;
        if (!(w[l] & S->inside[l]))
            continue;
        if (n == 5) {
            gfail(r, i, AR_GERR_TWO_GRADIENTS, lay[0], l);
            return 1;
        }
        lay[n++] = l;
    }
    if (n == 1) {
        shown = lay[0];
    } else if (n > 1) {
        for (int k = 0; k < n; k++) {
            int o[5], m = 0;
            o[m++] = lay[k];
            for (int q = 0; q < n; q++)
                if (q != k)
                    o[m++] = lay[q];
            if (!influences(S, w, n, o))
                continue;
            if (shown >= 0) {
                gfail(r, i, AR_GERR_TWO_GRADIENTS, shown, lay[k]);
                return 1;
            }
            shown = lay[k];
        }
    }
    gs->g = -1;
    if (shown >= 0) {
        double e[3][3];
        for (int q = 0; q < 3; q++)
            aa_scene_encoded_with(S->scene, w, shown, corner[q], e[q]);
        int any = 0;
        for (int c = 0; c < 3; c++) {
            gs->K0[c] = e[0][c];
            gs->K1[c] = e[1][c] - e[0][c];
            gs->K2[c] = e[2][c] - e[1][c];
            any |= gs->K1[c] != 0.0 || gs->K2[c] != 0.0;
        }
        if (any) {
            gs->g = S->gof[shown];
            const ar_grad *G = &S->grad[gs->g];
            /* linear light: wherever a channel changes between two stops
             * (the opacity o constant there, load_one) the composite must
             * be that channel, e = C: K0 + K1 o = 0 and K2 o = 1 */
            for (int k = 0; G->lin && k + 1 < G->nstops; k++) {
                if (!(G->offset[k + 1] > G->offset[k]))
                    continue;
                double o = G->lv[k][3];
                for (int c = 0; c < S->nch; c++)
                    if (G->lv[k + 1][c] != G->lv[k][c] &&
                        !(gs->K0[c] + gs->K1[c] * o == 0.0 && gs->K2[c] * o == 1.0)) {
                        gfail(r, i, AR_GERR_LINEAR_LIGHT, shown, 0);
                        return 1;
                    }
            }
            return 0;
        }
    }
    const double *c = colour_of(S, r->wk, w);
    memcpy(gs->c, c, sizeof gs->c);
    return 0;
}

/* ------------------------------------------------------------------------
 * The integral along t
 * ------------------------------------------------------------------------ */

/* B(r) = ((1 + r)^4.4 - 1 - 4.4 r) / (4.4 x 3.4 r^2) (header) */
static double bfun(double r)
{
    if (fabs(r) <= 0.25) {
        /* past k = 1 the terms shrink by at least |r| each, so the tail
         * after a term t is below |t| |r| / (1 - |r|) <= |t| / 3: stop
         * once that is under 2^-60 (B >= 0.4), or at AR_BSERIES terms */
        double b = 0.5, s = 0.5, rk = 1.0;
        for (int k = 1; k < AR_BSERIES; k++) {
            b *= (3.4 - k) / (k + 2);
            rk *= r;
            double t = b * rk;
            s += t;
            if (k > 1 && fabs(t) < 0x1p-60)
                break;
        }
        return s;
    }
    return (expm1(4.4 * log1p(r)) - 4.4 * r) / (4.4 * 3.4 * r * r);
}

/* One piece on one branch: e from e0 with slope de over length L; adds
 * L H + I2 to *M and I1 to *H. */
static void branch(double e0, double de, double L, double *H, double *M)
{
    double i1, i2;
    if (e0 + 0.5 * de * L <= AR_T) {
        i1 = L * (e0 + 0.5 * de * L) / 12.92;
        i2 = L * L * (0.5 * e0 + de * L / 6.0) / 12.92;
    } else {
        double u0 = (e0 + 0.055) / 1.055, r = de * L / 1.055 / u0, base = pow(u0, 2.4);
        double a = r == 0.0 ? 1.0 : expm1(3.4 * log1p(r)) / (3.4 * r);
        i1 = L * base * a;
        i2 = L * L * base * bfun(r);
    }
    *M += L * *H + i2;
    *H += i1;
}

/* A piece where e is affine: split where it passes T. */
static void piece(double e0, double de, double L, double *H, double *M)
{
    double e1 = e0 + de * L;
    if (aa__area_gradient_split && ((e0 < AR_T && e1 > AR_T) || (e0 > AR_T && e1 < AR_T))) {
        double tau = (AR_T - e0) / de;
        tau = tau < 0.0 ? 0.0 : (tau > L ? L : tau);
        branch(e0, de, tau, H, M);
        branch(AR_T, de, L - tau, H, M);
        return;
    }
    branch(e0, de, L, H, M);
}

/* Linear light, where the composite is the channel C = encode(v) of an
 * opaque layer ("linear light" in the header): h = decode(encode(v)),
 * which is v but for v in (LIN_T, LIN_S), where encode's power piece is
 * still below decode's threshold T (the two pieces of IEC 61966-2-1 do
 * not meet: 1.055 LIN_T^(1/2.4) - 0.055 = 0.0404499 < T) and h =
 * (1.055 v^p - 0.055) / 12.92, p = 1/2.4.  A piece where v = v0 + dv w
 * is split at LIN_T and LIN_S; v's parts take I1 = L (v0 + dv L/2), I2 =
 * L^2 (v0/2 + dv L/6), exactly; the part between, where |r| = |dv L /
 * v0| < (LIN_S - LIN_T) / LIN_T < 2.4e-6, takes int_0^L v^p = L v0^p A(r)
 * and int_0^L (L - w) v^p = L^2 v0^p B(r) by their binomial series, A(r)
 * = 1 + p r/2 + p (p - 1) r^2/6, B(r) = 1/2 + p r/6 + p (p - 1) r^2/24,
 * the next terms below |r|^3 < 1.4e-17 of them. */
#define LIN_T 0.0031308
#define LIN_S 0.0031308072830676845 /* encode's power piece reaches T there */
static void lin_part(double v0, double dv, double L, double *H, double *M)
{
    double i1, i2;
    const double vm = v0 + 0.5 * dv * L;
    if (vm > LIN_T && vm < LIN_S) {
        const double p = 1.0 / 2.4, r = dv * L / v0, b = pow(v0, p);
        double A = 1.0 + r * (p / 2.0 + r * p * (p - 1.0) / 6.0);
        double B = 0.5 + r * (p / 6.0 + r * p * (p - 1.0) / 24.0);
        i1 = (1.055 * L * b * A - 0.055 * L) / 12.92;
        i2 = (1.055 * L * L * b * B - 0.055 * L * L / 2.0) / 12.92;
    } else {
        i1 = L * (v0 + 0.5 * dv * L);
        i2 = L * L * (0.5 * v0 + dv * L / 6.0);
    }
    *M += L * *H + i2;
    *H += i1;
}

static void lin_piece(double v0, double dv, double L, double *H, double *M)
{
    double cut[2], w = 0.0;
    int n = 0;
    const double lv[2] = {LIN_T, LIN_S};
    for (int k = 0; k < 2; k++) {
        double tau = (lv[dv > 0.0 ? k : 1 - k] - v0) / dv;
        if (tau > 0.0 && tau < L)
            cut[n++] = tau;
    }
    for (int k = 0; k <= n; k++) {
        double e = k < n ? cut[k] : L;
        if (e > w)
            lin_part(v0 + dv * w, dv, e - w, H, M);
        w = e > w ? e : w;
    }
}

/* The first knot of G above t (INFINITY: none). */
static double next_knot(const ar_grad *G, double t)
{
    double base = G->period > 0.0 ? G->period * floor(t / G->period) : 0.0;
    for (int pass = 0; pass < 2; pass++, base += G->period) {
        for (int k = 0; k < G->nknots; k++)
            if (base + G->knot[k] > t)
                return base + G->knot[k];
        if (!(G->period > 0.0))
            return INFINITY;
    }
    return INFINITY; /* not reached: the next period's first knot is above t */
}

/* Over [p, q] (no knot inside): the paint's channel ch (3: opacity) at p
 * and its slope in t. */
static void paint_on(const ar_grad *G, const double (*val)[4], double p, double q, int ch,
                     double *v, double *dv)
{
    double m = 0.5 * (p + q), um, sg;
    if (G->spread == AA_SPREAD_REPEAT) {
        um = m - floor(m), sg = 1.0;
    } else if (G->spread == AA_SPREAD_REFLECT) {
        double f = m - 2.0 * floor(0.5 * m);
        um = f <= 1.0 ? f : 2.0 - f, sg = f <= 1.0 ? 1.0 : -1.0;
    } else {
        um = m < 0.0 ? 0.0 : (m > 1.0 ? 1.0 : m), sg = m < 0.0 || m > 1.0 ? 0.0 : 1.0;
    }
    const double *o = G->offset;
    int n = G->nstops, k = 0;
    if (!(um >= o[0]) || um >= o[n - 1]) {
        *v = val[um >= o[n - 1] ? n - 1 : 0][ch], *dv = 0.0;
        return;
    }
    while (k + 1 < n && o[k + 1] <= um)
        k++;
    double up = um - sg * (m - p), span = o[k + 1] - o[k];
    double a = val[k][ch], b = val[k + 1][ch];
    *v = a + (up - o[k]) / span * (b - a);
    *dv = sg * (b - a) / span;
}

/* The mean of H over the edge's t from t0 to t1 for channel ch, H = *H at
 * t0; *H becomes H(t1).  0, or 1 if the walk passed too many knots. */
static int edge_mean(const ar_grad *G, const gstate *gs, int ch, double t0, double t1,
                     double *H, double *mean)
{
    if (t0 == t1) {
        *mean = *H;
        return 0;
    }
    double lo = t0 < t1 ? t0 : t1, hi = t0 < t1 ? t1 : t0, Hr = 0.0, M = 0.0;
    int steps = 0;
    for (double p = lo; p < hi; steps++) {
        if (steps > 4 * AR_GKNOTS)
            return 1;
        double q = next_knot(G, p);
        q = q < hi ? q : hi;
        double o, dop, c, dc;
        paint_on(G, G->enc, p, q, 3, &o, &dop);
        if (G->lin) {
            /* linear light: the channel's linear value v; where it
             * changes the composite is C itself (gstate_make) */
            double v, dv;
            paint_on(G, G->lv, p, q, ch, &v, &dv);
            if (dv != 0.0) {
                lin_piece(v, dv, q - p, &Hr, &M);
                p = q;
                continue;
            }
            c = aa_srgb_encode(v), dc = 0.0;
        } else
            paint_on(G, G->enc, p, q, ch, &c, &dc);
        /* e = K0 + K1 o + K2 o c; at most one of o, c changes here (load) */
        double e0 = gs->K0[ch] + gs->K1[ch] * o + gs->K2[ch] * o * c;
        double de = gs->K1[ch] * dop + gs->K2[ch] * (dop * c + o * dc);
        piece(e0, de, q - p, &Hr, &M);
        p = q;
    }
    double Hlo = t0 < t1 ? *H : *H - Hr;
    *mean = Hlo + M / (hi - lo);
    *H = t0 < t1 ? *H + Hr : Hlo;
    return 0;
}

/* Add the integral over polygon (vx, vy) (pixel-local, pixel i of row r,
 * counter-clockwise in x right, y down) of the decoded composite to sum. */
static int polygon(const ar_row *r, const gstate *gs, int i, const double *vx,
                   const double *vy, int nv, double *sum)
{
    const ar_grad *G = &r->S->grad[gs->g];
    double to = G->gu * i + G->gv * r->j + G->g0, k2 = G->gu * G->gu + G->gv * G->gv;
    int nch = r->S->nch;
    for (int ch = 0; ch < nch; ch++) {
        double H = 0.0, acc = 0.0;
        for (int k = 0; k < nv; k++) {
            int m = k + 1 == nv ? 0 : k + 1;
            double ta = to + G->gu * vx[k] + G->gv * vy[k];
            double tb = to + G->gu * vx[m] + G->gv * vy[m];
            double mean;
            if (edge_mean(G, gs, ch, ta, tb, &H, &mean)) {
                gfail(r, i, AR_GERR_KNOTS, G->layer, 0);
                return 1;
            }
            acc += (-G->gv * (vx[m] - vx[k]) + G->gu * (vy[m] - vy[k])) / k2 * mean;
        }
        sum[ch] += acc;
    }
    for (int ch = nch; ch < 3; ch++)
        sum[ch] = sum[0];
    return 0;
}

static const double unit_x[4] = {0, 1, 1, 0}, unit_y[4] = {0, 0, 1, 1};

void area_gradient_run(const ar_row *r, int i0, int i1, const int *w)
{
    i0 = i0 < 0 ? 0 : i0, i1 = i1 > r->W ? r->W : i1;
    if (i0 >= i1)
        return;
    gstate gs;
    if (gstate_of(r, i0, w, &gs))
        return;
    if (gs.g >= 0) /* integrated, not filled */
        r->wk->expensive += (uint64_t)(i1 - i0);
    for (int i = i0; i < i1; i++) {
        double sum[3] = {0, 0, 0};
        if (gs.g < 0)
            memcpy(sum, gs.c, sizeof sum);
        else if (polygon(r, &gs, i, unit_x, unit_y, 4, sum))
            return;
        store_px(r, r->px + 3 * (size_t)i, sum);
    }
}

/* A region of a gradient scene (cm_split_all, Catmull's integrater split
 * on every edge as area_composite.c's): its integral exact, a flat state's
 * colour times its area, a gradient's over its polygon. */
static void leaf_grad(const ar_row *r, const cm_level *lv, double area, const int *wind, int i,
                      double *sum)
{
    gstate gs;
    if (gstate_of(r, i, wind, &gs))
        return;
    if (gs.g < 0) {
        for (int ch = 0; ch < 3; ch++)
            sum[ch] += gs.c[ch] * area;
        return;
    }
    polygon(r, &gs, i, lv->vx, lv->vy, lv->nv, sum);
}

static void cm_integrate_grad(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                              int d, double *sum)
{
    cm_split_all(r, in, n, w, i, d, sum, leaf_grad);
}

int area_cluster_gradient(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                          const int *w)
{
    if (cm_cluster(r, in, n, lo, hi, w, cm_integrate_grad))
        return 1;
    gfail(r, lo < 0 ? 0 : lo, AR_GERR_EDGES, CM_MAX_EDGES, 0);
    return 0;
}
