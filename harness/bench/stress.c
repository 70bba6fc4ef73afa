/*
 * stress.c: the numerical stress suite (`aabench stress`).
 *
 * Each case is a scene pushed toward a limit of the geometry: Crow's
 * pattern from straight (kmax = 0, 1e-15) to the validity limit, gaps of
 * 1e-7 pattern units, the documented limit on curves; scenes moved by up to
 * 1e6 pixels; sizes 1x1, 1x8192, 8192x1 and odd primes; slivers down to
 * 1e-9 px tall; degenerate polygons (zero area, repeated vertices, collinear
 * points, edges exactly on pixel boundaries and through pixel centres).
 *
 * Each case's box reference and the `area` method are compared with a
 * higher-precision evaluation of the same definitions: the pattern's scene
 * (pattern units, as built in double) placed and integrated in long double
 * (64-bit mantissa) by a path that shares nothing with truth.c or area.c.
 * Per pixel, the band [j, j+1] is cut at every y where the crossing
 * structure inside the pixel can change: ends of edges, crossings of the
 * pixel's sides x = i and x = i+1, and meetings of two edges that reach the
 * pixel.  Between cuts every edge's x is a polynomial of degree at most 2 in
 * y (lines, and quadratic arcs whose control point lies halfway in y, as
 * Crow's do), so the covered length of [i, i+1] per colour is a quadratic
 * in y and two-point Gauss-Legendre, exact for cubics, integrates it
 * exactly; the nodes are inside the slab, so no node lies on an edge end.
 * Arcs of other shapes are outside this evaluator and their cases would be
 * refused.  Where even that is too slow (the curves limit: 131 072 arcs),
 * the check is the closed-form white area of crow.c's header, which a 1x1
 * image and the sum of an 8x8 image must equal.
 *
 * Bounds (harness/bench/README.md, "Stress"): the reference within 1e-12 of the
 * evaluation (the ground truth's own bar) plus, for a scene moved by s
 * pixels, 1e-15 s (placing a scene rounds its coordinates to double, whose
 * spacing at 1e6 is 1.2e-10; the evaluation places in long double);
 * `area` within 1e-11 plus the same allowance.  Every method of the table
 * must give finite values in [0, 1] (within 1e-12) on every case, or refuse
 * the case with a message; a NaN, an Inf, a value outside or a failure
 * other than a refusal fails the case.
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef long double ld;

/* ------------------------------------------------------------------------
 * The long double evaluator
 * ------------------------------------------------------------------------ */

typedef struct ev_edge {
    ld ya, yb;      /* y extent, ya < yb (horizontal edges are dropped) */
    ld c0, c1, c2;  /* x(y) = c0 + c1 (y - ya) + c2 (y - ya)^2 */
    int dir, layer; /* +1 downward, -1 upward */
} ev_edge;

typedef struct ev_scene {
    ev_edge *e;
    size_t n;
    int nlayers;
    aa_rgb background, colour[64];
    int rule[64];
} ev_scene;

static ld ev_x(const ev_edge *e, ld y)
{
    ld d = y - e->ya;
    return e->c0 + d * (e->c1 + d * e->c2);
}

/* The pattern scene `s` placed at w x h moved by (sx, sy) pixels, in long
 * double.  Returns AA_EINVAL for an arc this evaluator cannot take. */
static int ev_make(const aa_scene *s, int w, int h, ld sx, ld sy, ev_scene *out)
{
    size_t n;
    const aa_edge *edges = aa_scene_edges(s, &n);
    memset(out, 0, sizeof *out);
    out->nlayers = aa_scene_layer_count(s);
    if (aa_scene_is_clipped(s))
        return aa_fail(AA_EINVAL, "stress: clip paths (this evaluator takes the front-most "
                                  "layer's colour, unclipped)");
    if (aa_scene_has_gradients(s))
        return aa_fail(AA_EINVAL, "stress: gradient paint (this evaluator takes the front-most "
                                  "layer's constant colour)");
    if (!aa_scene_is_opaque(s))
        return aa_fail(AA_EINVAL, "stress: translucent layers (this evaluator takes the "
                                  "front-most layer's colour)");
    if (out->nlayers > 64)
        return aa_fail(AA_EINVAL, "stress: more than 64 layers");
    out->background = aa_scene_background(s);
    for (int l = 0; l < out->nlayers; l++) {
        out->colour[l] = aa_scene_layer_colour(s, l);
        out->rule[l] = aa_scene_layer_rule(s, l);
    }
    out->e = malloc((n ? n : 1) * sizeof *out->e);
    if (!out->e)
        return aa_fail(AA_ENOMEM, "stress: out of memory");
    for (size_t k = 0; k < n; k++) {
        const aa_edge *g = &edges[k];
        ld x0 = (ld)w * g->x0 + sx, y0 = (ld)h * g->y0 + sy;
        ld x1 = (ld)w * g->x1 + sx, y1 = (ld)h * g->y1 + sy;
        ld cx = (ld)w * g->cx + sx, cy = (ld)h * g->cy + sy;
        if (g->quad >= 2) {
            free(out->e);
            return aa_fail(AA_EINVAL, "stress: %s (only lines and arcs with x quadratic in y)",
                           g->quad == 2   ? "a cubic arc"
                           : g->quad == 3 ? "an elliptical arc"
                                          : "an offset curve");
        }
        if (y0 == y1)
            continue;
        if (g->quad && fabsl(cy - (y0 + y1) / 2) > 1e-12L * (fabsl(y0) + fabsl(y1) + 1)) {
            free(out->e);
            return aa_fail(AA_EINVAL, "stress: an arc whose control point is not halfway in y");
        }
        ev_edge *e = &out->e[out->n++];
        e->layer = g->layer;
        e->dir = y1 > y0 ? 1 : -1;
        if (y1 < y0) { /* store top to bottom */
            ld t = x0;
            x0 = x1, x1 = t, t = y0, y0 = y1, y1 = t;
        }
        e->ya = y0, e->yb = y1;
        /* u = (y - ya)/(yb - ya); x = x0 + 2 u (cx - x0) + u^2 (x0 - 2 cx + x1) */
        ld L = y1 - y0, q = g->quad ? x0 - 2 * cx + x1 : 0, b = g->quad ? 2 * (cx - x0) : x1 - x0;
        e->c0 = x0, e->c1 = b / L, e->c2 = q / (L * L);
    }
    return AA_OK;
}

/* Roots in (lo, hi) of c0 + c1 d + c2 d^2 = 0 (d = y - base), appended. */
static void roots(ld c0, ld c1, ld c2, ld base, ld lo, ld hi, ld *cut, int *n, int cap)
{
    ld r[2];
    int nr = 0;
    if (c2 == 0) {
        if (c1 != 0)
            r[nr++] = -c0 / c1;
    } else {
        ld disc = c1 * c1 - 4 * c2 * c0;
        if (disc >= 0) {
            ld qq = -0.5L * (c1 + (c1 >= 0 ? sqrtl(disc) : -sqrtl(disc)));
            if (qq != 0)
                r[nr++] = c0 / qq;
            r[nr++] = qq / c2;
        }
    }
    for (int k = 0; k < nr; k++) {
        ld y = base + r[k];
        if (y > lo && y < hi && *n < cap)
            cut[(*n)++] = y;
    }
}

static int cmp_ld(const void *a, const void *b)
{
    ld x = *(const ld *)a, y = *(const ld *)b;
    return x < y ? -1 : x > y;
}

/* The x range of edge e over [lo, hi] (within its extent). */
static void ev_xrange(const ev_edge *e, ld lo, ld hi, ld *xmin, ld *xmax)
{
    lo = lo > e->ya ? lo : e->ya, hi = hi < e->yb ? hi : e->yb;
    ld a = ev_x(e, lo), b = ev_x(e, hi);
    *xmin = a < b ? a : b, *xmax = a < b ? b : a;
    if (e->c2 != 0) {
        ld d = -e->c1 / (2 * e->c2), y = e->ya + d;
        if (y > lo && y < hi) {
            ld v = ev_x(e, y);
            *xmin = v < *xmin ? v : *xmin, *xmax = v > *xmax ? v : *xmax;
        }
    }
}

typedef struct ev_work {
    size_t *row, *near; /* edges meeting the band; those reaching the pixel */
    ld *nx0, *nx1;      /* the near edges' x ranges over the band */
    ld *cut;
    int cap;
    struct {
        ld x;
        int dir, layer;
    } * cross;
} ev_work;

static aa_rgb ev_colour(const ev_scene *S, const int *wind)
{
    for (int l = 0; l < S->nlayers; l++)
        if (S->rule[l] == AA_FILL_EVENODD ? (wind[l] & 1) : wind[l] != 0)
            return S->colour[l];
    return S->background;
}

/* The covered length per channel of [i, i+1] on line y, times weight. */
static void ev_line(const ev_scene *S, ev_work *W, size_t nrow, int i, ld y, ld weight,
                    ld acc[3])
{
    int wind[64] = {0}, nc = 0;
    for (size_t k = 0; k < nrow; k++) {
        const ev_edge *e = &S->e[W->row[k]];
        if (!(e->ya < y && y < e->yb))
            continue;
        ld x = ev_x(e, y);
        if (x <= i)
            wind[e->layer] += e->dir;
        else if (x < i + 1) {
            int m = nc++;
            while (m > 0 && W->cross[m - 1].x > x) {
                W->cross[m] = W->cross[m - 1];
                m--;
            }
            W->cross[m].x = x, W->cross[m].dir = e->dir, W->cross[m].layer = e->layer;
        }
    }
    ld from = i;
    for (int m = 0; m <= nc; m++) {
        ld to = m < nc ? W->cross[m].x : (ld)i + 1;
        aa_rgb c = ev_colour(S, wind);
        for (int ch = 0; ch < 3; ch++)
            acc[ch] += weight * (to - from) * c.c[ch];
        if (m < nc)
            wind[W->cross[m].layer] += W->cross[m].dir, from = to;
    }
}

/* The box value of pixel (i, j) in long double. */
static void ev_pixel(const ev_scene *S, ev_work *W, size_t nrow, int i, int j, ld out[3])
{
    const ld lo = j, hi = (ld)j + 1;
    size_t nnear = 0;
    int n = 0;
    W->cut[n++] = lo, W->cut[n++] = hi;
    for (size_t k = 0; k < nrow; k++) {
        const ev_edge *e = &S->e[W->row[k]];
        ld xmin, xmax;
        ev_xrange(e, lo, hi, &xmin, &xmax);
        if (xmin >= i + 1)
            continue; /* right of the pixel: no effect */
        if (e->ya > lo && n < W->cap)
            W->cut[n++] = e->ya;
        if (e->yb < hi && n < W->cap)
            W->cut[n++] = e->yb;
        if (xmax <= i)
            continue; /* left of the pixel: winding only */
        W->nx0[nnear] = xmin, W->nx1[nnear] = xmax;
        W->near[nnear++] = W->row[k];
        ld ylo = e->ya > lo ? e->ya : lo, yhi = e->yb < hi ? e->yb : hi;
        for (int side = 0; side < 2; side++)
            roots(e->c0 - (i + side), e->c1, e->c2, e->ya, ylo, yhi, W->cut, &n, W->cap);
    }
    for (size_t a = 0; a < nnear; a++)
        for (size_t b = a + 1; b < nnear; b++) {
            if (W->nx1[a] < W->nx0[b] || W->nx1[b] < W->nx0[a])
                continue; /* apart over the whole band */
            const ev_edge *p = &S->e[W->near[a]], *q = &S->e[W->near[b]];
            ld ylo = p->ya > q->ya ? p->ya : q->ya, yhi = p->yb < q->yb ? p->yb : q->yb;
            ylo = ylo > lo ? ylo : lo, yhi = yhi < hi ? yhi : hi;
            if (!(ylo < yhi))
                continue;
            /* p - q as a polynomial in d = y - p->ya */
            ld s = p->ya - q->ya;
            ld q0 = q->c0 + s * (q->c1 + s * q->c2), q1 = q->c1 + 2 * s * q->c2;
            roots(p->c0 - q0, p->c1 - q1, p->c2 - q->c2, p->ya, ylo, yhi, W->cut, &n, W->cap);
        }
    qsort(W->cut, (size_t)n, sizeof *W->cut, cmp_ld);
    out[0] = out[1] = out[2] = 0;
    const ld g = 0.57735026918962576450914878050195746L; /* 1/sqrt(3) */
    for (int k = 0; k + 1 < n; k++) {
        ld a = W->cut[k], b = W->cut[k + 1];
        if (!(b > a))
            continue;
        ld m = (a + b) / 2, r = (b - a) / 2;
        ev_line(S, W, nrow, i, m - g * r, r, out);
        ev_line(S, W, nrow, i, m + g * r, r, out);
    }
}

/* The long double box image of scene s at w x h moved (sx, sy) pixels,
 * compared with img: the largest difference.  Returns a status. */
static int ev_compare(const aa_scene *s, int w, int h, ld sx, ld sy, const aa_image *img,
                      double *maxerr)
{
    ev_scene S;
    int st = ev_make(s, w, h, sx, sy, &S);
    if (st)
        return st;
    ev_work W = {0};
    if (S.n > 4096) {
        free(S.e);
        return aa_fail(AA_EINVAL, "stress: %zu edges is beyond the long double evaluator", S.n);
    }
    /* every end, two side crossings each, two meetings per pair */
    W.cap = (int)(4 * S.n + S.n * (S.n - 1) + 8);
    W.row = malloc((S.n + 1) * sizeof *W.row);
    W.nx0 = malloc((S.n + 1) * sizeof *W.nx0);
    W.nx1 = malloc((S.n + 1) * sizeof *W.nx1);
    W.near = malloc((S.n + 1) * sizeof *W.near);
    W.cut = malloc((size_t)W.cap * sizeof *W.cut);
    W.cross = malloc((S.n + 1) * sizeof *W.cross);
    if (!W.row || !W.near || !W.nx0 || !W.nx1 || !W.cut || !W.cross) {
        st = aa_fail(AA_ENOMEM, "stress: out of memory");
        goto done;
    }
    double worst = 0.0;
    for (int j = 0; j < h; j++) {
        size_t nrow = 0;
        for (size_t k = 0; k < S.n; k++)
            if (S.e[k].ya < j + 1 && S.e[k].yb > j)
                W.row[nrow++] = k;
        for (int i = 0; i < w; i++) {
            ld v[3];
            ev_pixel(&S, &W, nrow, i, j, v);
            const double *px = aa_pixel(img, i, j);
            for (int c = 0; c < 3; c++) {
                double d = fabs((double)((ld)px[c] - v[c]));
                if (!(d <= worst))
                    worst = isnan(d) ? INFINITY : d;
            }
        }
    }
    *maxerr = worst;
done:
    free(W.row);
    free(W.near);
    free(W.nx0);
    free(W.nx1);
    free(W.cut);
    free(W.cross);
    free(S.e);
    return st;
}

/* ------------------------------------------------------------------------
 * The cases
 * ------------------------------------------------------------------------ */

enum { SC_PATTERN, SC_ZERO_AREA, SC_REPEATED, SC_COLLINEAR, SC_ON_BOUNDARIES, SC_THROUGH_CENTRES,
       SC_SPIKE };

typedef struct stress_case {
    const char *name;
    int kind;            /* SC_* */
    const char *pattern; /* SC_PATTERN */
    int w, h;
    double t, vx, vy;
    int closed_form; /* 1: check the total white area of crow.c's header only */
} stress_case;

static const stress_case cases[] = {
    {"crow default", SC_PATTERN, "crow", 128, 128, 0, 0, 0, 0},
    {"crow straight (kmax 0)", SC_PATTERN, "crow:kmax=0", 96, 96, 0, 0, 0, 0},
    {"crow kmax 1e-15", SC_PATTERN, "crow:kmax=1e-15", 96, 96, 0, 0, 0, 0},
    {"crow kmax -1e-15", SC_PATTERN, "crow:kmax=-1e-15", 96, 96, 0, 0, 0, 0},
    {"crow kmax at the validity limit", SC_PATTERN, "crow:kmax=0.74218749", 96, 96, 0, 0, 0, 0},
    {"crow gaps 1e-7", SC_PATTERN, "crow:curves=8,gap0=1e-7,gap1=1e-7,kmax=2e-6", 64, 64, 0, 0, 0,
     0},
    {"crow gaps 1e-7, straight", SC_PATTERN, "crow:curves=8,gap0=1e-7,gap1=1e-7,kmax=0", 61, 67, 0,
     0, 0, 0},
    {"crow 65536 curves, 1x1", SC_PATTERN, "crow:curves=65536,gap0=1e-5,gap1=1e-5,kmax=0.1", 1, 1,
     0, 0, 0, 1},
    {"crow 65536 curves, 1x4 total", SC_PATTERN, "crow:curves=65536,gap0=1e-5,gap1=1e-5,kmax=0.1",
     1, 4, 0, 0, 0, 1},
    {"crow 65536 straight curves, 8x8 total", SC_PATTERN,
     "crow:curves=65536,gap0=1e-5,gap1=1e-5,kmax=0", 8, 8, 0, 0, 0, 1},
    {"crow 1x1", SC_PATTERN, "crow", 1, 1, 0, 0, 0, 0},
    {"crow 1x8192", SC_PATTERN, "crow", 1, 8192, 0, 0, 0, 0},
    {"crow 8192x1", SC_PATTERN, "crow", 8192, 1, 0, 0, 0, 0},
    {"crow 7x3", SC_PATTERN, "crow", 7, 3, 0, 0, 0, 0},
    {"crow 131x257", SC_PATTERN, "crow", 131, 257, 0, 0, 0, 0},
    {"crow moved 0.37,-0.21 px", SC_PATTERN, "crow", 64, 64, 1, 0.37, -0.21, 0},
    {"crow moved 1e6 px (out of view)", SC_PATTERN, "crow", 64, 64, 1e6, 1, 0, 0},
    {"crow at t=1e6 moved 20,-1 px", SC_PATTERN, "crow", 64, 64, 1e6, 2e-5, -1e-6,
     0},
    {"star moved 12.3,-7.7 px over 1e6 frames", SC_PATTERN, "star:spokes=12", 64, 64, 1e6, 1.23e-5,
     -7.7e-6, 0},
    {"slivers default", SC_PATTERN, "slivers", 256, 256, 0, 0, 0, 0},
    {"slivers 1e-9 px tall", SC_PATTERN, "slivers:hmin=3.90625e-12,hmax=3.90625e-12", 256, 256, 0,
     0, 0, 0},
    {"slivers 0 to 1e-6 px tall", SC_PATTERN, "slivers:hmin=0,hmax=3.90625e-9", 256, 256, 0, 0, 0,
     0},
    {"catmull tiles 5, 37x37", SC_PATTERN, "catmull:tiles=5", 37, 37, 0, 0, 0, 0},
    {"feibush 97x89", SC_PATTERN, "feibush", 97, 89, 0, 0, 0, 0},
    {"fence period 0.3 px", SC_PATTERN, "fence:period=0.001171875", 64, 64, 0, 0, 0, 0},
    {"dots", SC_PATTERN, "dots", 128, 128, 0, 0, 0, 0},
    {"zero-area triangle", SC_ZERO_AREA, NULL, 16, 16, 0, 0, 0, 0},
    {"repeated vertices", SC_REPEATED, NULL, 16, 16, 0, 0, 0, 0},
    {"collinear points", SC_COLLINEAR, NULL, 16, 16, 0, 0, 0, 0},
    {"edges on pixel boundaries", SC_ON_BOUNDARIES, NULL, 16, 16, 0, 0, 0, 0},
    {"edges through pixel centres", SC_THROUGH_CENTRES, NULL, 16, 16, 0, 0, 0, 0},
    {"zero-width spike on a square", SC_SPIKE, NULL, 16, 16, 0, 0, 0, 0},
};

size_t aa_stress_count(void)
{
    return sizeof cases / sizeof cases[0];
}

const char *aa_stress_name(size_t k)
{
    return k < aa_stress_count() ? cases[k].name : NULL;
}

/* A polygon (pattern units) as one path of the current layer. */
static int poly(aa_scene *s, const double (*p)[2], int n)
{
    int st = aa_scene_move_to(s, p[0][0], p[0][1]);
    for (int k = 1; k < n && !st; k++)
        st = aa_scene_line_to(s, p[k][0], p[k][1]);
    return st ? st : aa_scene_close(s);
}

/* The degenerate scenes, on a 16x16 image (pattern unit = 16 px). */
static int degenerate(int kind, aa_scene **out)
{
    static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}}, grey = {{0.25, 0.5, 0.75}};
    aa_scene *s = aa_scene_new(black);
    if (!s)
        return AA_ENOMEM;
    int st = aa_scene_layer(s, white, AA_FILL_NONZERO);
    const double u = 1.0 / 16;
    if (!st)
        switch (kind) {
        case SC_ZERO_AREA: {
            const double a[3][2] = {{0.1, 0.2}, {0.9, 0.6}, {0.5, 0.4}}; /* collinear */
            const double b[4][2] = {{0.2, 0.7}, {0.8, 0.7}, {0.8, 0.7}, {0.2, 0.7}};
            st = poly(s, a, 3);
            if (!st)
                st = poly(s, b, 4);
            break;
        }
        case SC_REPEATED: {
            const double a[7][2] = {{0.1, 0.1}, {0.1, 0.1}, {0.7, 0.15}, {0.7, 0.15},
                                    {0.7, 0.15}, {0.4, 0.83}, {0.1, 0.1}};
            st = poly(s, a, 7);
            break;
        }
        case SC_COLLINEAR: {
            const double a[8][2] = {{0.2, 0.2}, {0.35, 0.2}, {0.5, 0.2}, {0.8, 0.2},
                                    {0.8, 0.5}, {0.8, 0.8}, {0.2, 0.8}, {0.2, 0.41}};
            st = poly(s, a, 8);
            break;
        }
        case SC_ON_BOUNDARIES: {
            const double a[4][2] = {{3 * u, 2 * u}, {11 * u, 2 * u}, {11 * u, 9 * u}, {3 * u, 9 * u}};
            const double b[3][2] = {{5 * u, 10 * u}, {13 * u, 10 * u}, {5 * u, 15 * u}};
            st = poly(s, a, 4);
            if (!st && !(st = aa_scene_layer(s, grey, AA_FILL_EVENODD)))
                st = poly(s, b, 3);
            break;
        }
        case SC_THROUGH_CENTRES: {
            const double a[4][2] = {
                {2.5 * u, 1.5 * u}, {12.5 * u, 1.5 * u}, {12.5 * u, 8.5 * u}, {2.5 * u, 8.5 * u}};
            const double b[3][2] = {{0.5 * u, 9.5 * u}, {15.5 * u, 15.5 * u}, {0.5 * u, 15.5 * u}};
            st = poly(s, a, 4);
            if (!st)
                st = poly(s, b, 3);
            break;
        }
        case SC_SPIKE: {
            /* a square with a spike out and back along one line */
            const double a[7][2] = {{0.3, 0.3}, {0.6, 0.3}, {0.6, 0.45}, {0.95, 0.45},
                                    {0.6, 0.45}, {0.6, 0.7}, {0.3, 0.7}};
            st = poly(s, a, 7);
            break;
        }
        }
    if (!st)
        st = aa_scene_finish(s);
    if (st) {
        aa_scene_free(s);
        return st;
    }
    *out = s;
    return AA_OK;
}

/* crow.c's closed-form white area (its header): sum over m of
 * g_{2m} - (c_{2m} - c_{2m+1})/12, in long double. */
static ld crow_white_area(const aa_spec *spec)
{
    const int n = (int)spec->v[0];
    const ld C = spec->v[1], g0 = spec->v[2], g1 = spec->v[3];
    ld sum = 0;
    for (int m = 0; m < n / 2; m++) {
        int k = 2 * m;
        ld g = n == 2 ? g0 : g0 + (g1 - g0) * k / (ld)(n - 2);
        ld c0 = C * (1 - k / (ld)(n - 1)), c1 = C * (1 - (k + 1) / (ld)(n - 1));
        sum += g - (c0 - c1) / 12;
    }
    return sum;
}

static size_t count_nonfinite(const aa_image *im)
{
    size_t n = 0;
    for (size_t q = 0; q < (size_t)im->c * im->w * im->h; q++)
        n += !isfinite(im->v[q]);
    return n;
}

static int case_scene(const stress_case *c, aa_scene **out, aa_spec *spec)
{
    if (c->kind != SC_PATTERN)
        return degenerate(c->kind, out);
    int st = aa_pattern_parse(c->pattern, spec);
    return st ? st : aa_pattern_scene(spec, out);
}

int aa_stress_run_case(size_t k, int threads, aa_stress_result *r)
{
    const stress_case *c = &cases[k];
    memset(r, 0, sizeof *r);
    r->name = c->name;
    r->w = c->w, r->h = c->h;
    const ld sx = (ld)c->t * c->vx, sy = (ld)c->t * c->vy;
    const double shift = (double)(fabsl(sx) + fabsl(sy));
    r->ref_bound = AA_TRUTH_BOUND + 1e-15 * shift;
    r->area_bound = 1e-11 + 1e-15 * shift;
    aa_spec spec;
    aa_scene *s = NULL;
    aa_job job;
    aa_filter box;
    aa_image ref = {0}, img = {0};
    aa_filter_default(&box);
    int st = case_scene(c, &s, &spec);
    if (st)
        return st;
    if ((st = aa_job_init(&job, s, c->w, c->h, c->t, c->vx, c->vy, &box, 1, threads))) {
        aa_scene_free(s);
        return st;
    }
    if ((st = aa_image_alloc(&ref, c->w, c->h, 3)) || (st = aa_image_alloc(&img, c->w, c->h, 3)))
        goto done;
    if ((st = aa_truth_render(job.placed, &box, threads, &ref, NULL, NULL)))
        goto done;
    r->nonfinite += count_nonfinite(&ref);
    if (c->closed_form) {
        ld want = crow_white_area(&spec), sum = 0;
        for (size_t q = 0; q < (size_t)c->w * c->h; q++)
            sum += ref.v[3 * q];
        r->ref_err = (double)fabsl(sum / ((ld)c->w * c->h) - want);
    } else if ((st = ev_compare(s, c->w, c->h, sx, sy, &ref, &r->ref_err))) {
        goto done;
    }
    /* every method: finite, within [0, 1], or a refusal */
    for (const aa_method_type *const *t = (const aa_method_type *const *)aa_method_table(); *t;
         t++) {
        aa_spec m;
        aa_counters cnt;
        if (aa_method_parse((*t)->info.name, &box, &m)) {
            r->refused++;
            continue;
        }
        int ms = aa_method_run(&m, &job, 1, &img, &cnt, NULL);
        if (ms == AA_EINVAL) {
            r->refused++;
            continue;
        }
        if (ms) {
            st = ms;
            goto done;
        }
        r->methods++;
        size_t bad = count_nonfinite(&img);
        r->nonfinite += bad;
        for (size_t q = 0; q < (size_t)3 * c->w * c->h; q++)
            if (img.v[q] < -1e-12 || img.v[q] > 1 + 1e-12)
                r->out_of_range++;
        if (!strcmp((*t)->info.name, "area")) {
            if (c->closed_form) {
                ld want = crow_white_area(&spec), sum = 0;
                for (size_t q = 0; q < (size_t)c->w * c->h; q++)
                    sum += img.v[3 * q];
                r->area_err = (double)fabsl(sum / ((ld)c->w * c->h) - want);
            } else if ((st = ev_compare(s, c->w, c->h, sx, sy, &img, &r->area_err))) {
                goto done;
            }
        }
    }
    r->pass = r->ref_err <= r->ref_bound && r->area_err <= r->area_bound && r->nonfinite == 0 &&
              r->out_of_range == 0;
done:
    aa_image_free(&ref);
    aa_image_free(&img);
    aa_job_free(&job);
    aa_scene_free(s);
    return st;
}
