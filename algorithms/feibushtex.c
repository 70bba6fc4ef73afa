/*
 * feibushtex.c: the texture filter of Feibush, Levoy and Cook (1980,
 * "Synthetic texturing using digital filters", sec. 2.4, fig. 2) with their
 * edge filter (sec. 2.5, fig. 3: `conetable`) weighting each pixel's
 * texture colour by the share of the filter's volume over the polygon.
 *
 * What is theirs.
 *  - A polygon carries a texture, "a two-dimensional array of texture
 *    definition points", mapped onto it by a projective transformation
 *    (sec. 2.2, fig. 1).  For each display pixel the bounding rectangle of
 *    its convolution mask is transformed to texture space, where it is a
 *    quadrilateral; a rectangle around that quadrilateral selects texture
 *    points (step 3), clipped to the parent polygon (step 4); each point is
 *    transformed back to image space (step 5) and kept if it lies in the
 *    mask's bounding rectangle (step 6); "the color values of all the
 *    texture definition points are multiplied by their respective values in
 *    the lookup table and summed together in a weighted average", the table
 *    holding the weighting function "computed at a number of locations",
 *    its nearest value used for a point between them (step 7).
 *  - "The intensity of a pixel computed by the texture filter for one
 *    polygon is weighted by the percentage of the total intensity of the
 *    pixel that is contributed by that polygon", which their edge filter
 *    gives with the same weighting function (sec. 2.5): conetable, run on
 *    the polygon alone, is that filter here.  The rest of the pixel is the
 *    background's.
 *  - The weight: a Gaussian over a circular mask of radius cut x s
 *    ("radius equal to twice the standard deviation", fig. 4d: cut=2) under
 *    -f gauss:s=S, or the filter's own mask under -f gauss:s=S,cut=K (the
 *    truncated Gaussian, the reference it is then measured against), or
 *    the cone of radius r (fig. 2f) under -f cone:r=R.
 *
 * What is chosen here.
 *  - The textured polygon and its texture.  A scene here is polygons and
 *    arcs with colours, not textured polygons, so the method makes the
 *    texture from the scene: the polygon is the convex hull of the scene's
 *    vertices when that is a quadrilateral of straight edges (the `feibush`
 *    pattern's square in perspective, the quadrilateral its stripes tile),
 *    else the scene's bounding rectangle; the texture is `texels` x
 *    `texels` definition points at the centres of a grid over the unit
 *    square of texture space, each the colour of the scene at the point the
 *    polygon's projective map (Heckbert 1989, sec. 2.2.3: corner 0 of the
 *    hull, the one of least x + y, to texture (0, 0), the next two in
 *    order to (1, 0) and (1, 1)) takes it to.  texels=0 (the default) takes
 *    two points per pixel along the polygon's longest side (16 to 4096).
 *    With `feibush:stripes=M` and texels a multiple of M every point lies
 *    inside one stripe and the texture is exact.  Made once per job (init,
 *    untimed), as their texture definition files were made beforehand.
 *  - The table: res x res values of the filter's weight at the centres of a
 *    grid over the mask's bounding square, zero outside the circle ("Care
 *    must be taken in computing the lookup table so that areas inside the
 *    bounding rectangle but outside the convolution mask have no volume").
 *  - A pixel whose mask holds no texture point (a texture magnified beyond
 *    its resolution) takes the point nearest its centre's texture
 *    coordinates; Feibush et al. interpolate bilinearly there (sec. 4).
 *  - The weighted average is formed as c0 + sum w (c - c0) / sum w, c0 the
 *    first point's colour, so a uniform texture gives its colour exactly;
 *    a pixel the polygon covers wholly (edge filter exactly 1) is that
 *    colour, any other background + share x (texture - background).
 *
 * Counters: samples, the texture points weighted; expensive pixels, those
 * the polygon reaches (share above 0).
 *
 * Error analysis.  Against the exact reference of the view under the same
 * filter: under the untruncated -f gauss:s=S the mask's truncation of the
 * Gaussian (the Gaussian's mass beyond 2 s, about 14 %, is dropped and the
 * rest renormalised, as in conetable; none under -f gauss:s=S,cut=K, the
 * truncated reference),
 * the table's nearest-value weights (a step of 2 cut s / res), the texture
 * points standing for the areas between them (a point per 1/texels of
 * texture space; their weighted mean is not the integral of the texture
 * under the mask), and the edge filter's own error (conetable.c).  With a
 * uniform texture the last is all.  Limits: one textured polygon per scene;
 * arcs are textured (sampled), not treated as edges, inside the bounding
 * rectangle; Gaussian and cone only.
 */
#include "methods.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { P_TEXELS, P_RES, P_CUT };
#define FT_DEFAULT_CUT 2.0
#define FT_MAX_TEXELS 4096

static const aa_param feibushtex_params[] = {
    {"texels", AA_PARAM_INT, 0, 0, FT_MAX_TEXELS, 0, NULL,
     "texture definition points along each side of the texture (0: two per pixel along "
     "the polygon's longest side, 16 to 4096)"},
    {"res", AA_PARAM_INT, 32, 2, 1024, 0, NULL,
     "entries along each side of the two-dimensional table of the weight"},
    {"cut", AA_PARAM_REAL, FT_DEFAULT_CUT, 0.5, 8.0, 0, NULL,
     "Gaussian only: mask radius in standard deviations (Feibush et al.: 2)"},
    {0}};

typedef struct ft_state {
    int have;          /* 0: the scene has no polygon; the image is its background */
    int n;             /* texels a side */
    unsigned short *tex; /* n x n indices into the palette */
    double (*pal)[3];  /* the scene's colours: background, then its layers' */
    int npal;
    double h[9];       /* texture (s, t) -> pixel (u, v), projective */
    double hi[9];      /* pixel -> texture */
    int res;
    double rc;         /* mask radius, pixels */
    double *table;     /* res x res weights over [-rc, rc]^2 */
    aa_rgb bg;
    aa_scene *poly;    /* the polygon alone, white on black, pattern units */
    aa_job ejob;
    int ejob_made;
    aa_method edge;    /* conetable on the polygon: the edge filter */
    int edge_made;
    aa_image share;
} ft_state;

static int feibushtex_check(const double *p, const aa_filter *f)
{
    if (f->type == &aa_filter_gauss_mask && p[P_CUT] != FT_DEFAULT_CUT &&
        p[P_CUT] != f->spec.v[1])
        return aa_fail(AA_EINVAL, "feibushtex: cut=%g differs from the filter's mask cut=%g: "
                                  "leave cut out (the filter's mask is taken)",
                       p[P_CUT], f->spec.v[1]);
    if (f->type == &aa_filter_cone && f->spec.v[1] != 1.0)
        return aa_fail(AA_EINVAL, "feibushtex forms the whole cone; the truncated cone (cut=%g) "
                                  "is not one of its weights",
                       f->spec.v[1]);
    if (f->type != &aa_filter_gauss && f->type != &aa_filter_gauss_mask &&
        f->type != &aa_filter_cone)
        return aa_fail(AA_EINVAL, "feibushtex weighs a circular mask with a radial weight and "
                                  "is measured against -f gauss:s=S or -f cone:r=R; it has no "
                                  "table for %s (its weights: the Gaussian and the cone)",
                       f->type->info.name);
    if (f->type == &aa_filter_cone && p[P_CUT] != FT_DEFAULT_CUT)
        return aa_fail(AA_EINVAL, "cut=%g sets the Gaussian's mask; the cone's mask is its "
                                  "radius r of -f cone:r=R (leave cut out)",
                       p[P_CUT]);
    if (p[P_TEXELS] != 0 && p[P_TEXELS] < 16)
        return aa_fail(AA_EINVAL, "feibushtex: texels=%g: give 0 (automatic) or 16 to %d",
                       p[P_TEXELS], FT_MAX_TEXELS);
    return AA_OK;
}

/* Heckbert's square-to-quadrilateral map (1989, sec. 2.2.3) as a 3 x 3
 * matrix m: (x w, y w, w) = m (s, t, 1). */
static void square_to_quad(const double q[4][2], double m[9])
{
    double dx1 = q[1][0] - q[2][0], dx2 = q[3][0] - q[2][0];
    double dx3 = q[0][0] - q[1][0] + q[2][0] - q[3][0];
    double dy1 = q[1][1] - q[2][1], dy2 = q[3][1] - q[2][1];
    double dy3 = q[0][1] - q[1][1] + q[2][1] - q[3][1];
    double den = dx1 * dy2 - dx2 * dy1;
    double g = (dx3 * dy2 - dx2 * dy3) / den, h = (dx1 * dy3 - dx3 * dy1) / den;
    m[0] = q[1][0] - q[0][0] + g * q[1][0], m[1] = q[3][0] - q[0][0] + h * q[3][0];
    m[2] = q[0][0];
    m[3] = q[1][1] - q[0][1] + g * q[1][1], m[4] = q[3][1] - q[0][1] + h * q[3][1];
    m[5] = q[0][1];
    m[6] = g, m[7] = h, m[8] = 1;
}

/* The inverse of a 3 x 3 matrix up to scale (its adjugate). */
static void adjugate(const double a[9], double b[9])
{
    b[0] = a[4] * a[8] - a[5] * a[7], b[1] = a[2] * a[7] - a[1] * a[8];
    b[2] = a[1] * a[5] - a[2] * a[4], b[3] = a[5] * a[6] - a[3] * a[8];
    b[4] = a[0] * a[8] - a[2] * a[6], b[5] = a[2] * a[3] - a[0] * a[5];
    b[6] = a[3] * a[7] - a[4] * a[6], b[7] = a[1] * a[6] - a[0] * a[7];
    b[8] = a[0] * a[4] - a[1] * a[3];
}

/* m (x, y, 1): 0 where the point lies on or beyond the line at infinity. */
static int apply(const double m[9], double x, double y, double *u, double *v)
{
    double w = m[6] * x + m[7] * y + m[8];
    if (!(w > 0))
        return 0;
    *u = (m[0] * x + m[1] * y + m[2]) / w;
    *v = (m[3] * x + m[4] * y + m[5]) / w;
    return 1;
}

static double cross(const double o[2], const double a[2], const double b[2])
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static int cmp_point(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb;
    return a[0] < b[0] ? -1 : a[0] > b[0] ? 1 : (a[1] < b[1] ? -1 : a[1] > b[1]);
}

/* The polygon, pattern units, corners in order: the hull of the vertices
 * when it is a quadrilateral and every edge a line, else the bounds. */
static int find_polygon(const aa_scene *s, double q[4][2], int *have)
{
    size_t ne;
    const aa_edge *e = aa_scene_edges(s, &ne);
    double x0, y0, x1, y1;
    *have = aa_scene_bounds(s, &x0, &y0, &x1, &y1) && x1 > x0 && y1 > y0;
    if (!*have)
        return AA_OK;
    int lines = 1;
    for (size_t k = 0; k < ne; k++)
        lines &= !e[k].quad;
    int hull_n = 0;
    if (lines && ne >= 4) {
        double(*pt)[2] = malloc(ne * sizeof *pt), (*h)[2] = malloc(2 * ne * sizeof *h);
        if (!pt || !h) {
            free(pt);
            free(h);
            return aa_fail(AA_ENOMEM, "feibushtex: out of memory for %zu vertices", ne);
        }
        for (size_t k = 0; k < ne; k++)
            pt[k][0] = e[k].x0, pt[k][1] = e[k].y0;
        qsort(pt, ne, sizeof *pt, cmp_point);
        /* Andrew's monotone chain; points within rounding of a hull edge
         * (the vertices along the sides of a tiled polygon) dropped */
        double eps = 1e-9 * ((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0));
        int n = 0, count = (int)ne;
        for (int k = 0; k < count; k++) {
            while (n >= 2 && cross(h[n - 2], h[n - 1], pt[k]) <= eps)
                n--;
            memcpy(h[n++], pt[k], sizeof h[0]);
        }
        for (int k = count - 2, lo = n + 1; k >= 0; k--) {
            while (n >= lo && cross(h[n - 2], h[n - 1], pt[k]) <= eps)
                n--;
            memcpy(h[n++], pt[k], sizeof h[0]);
        }
        hull_n = n - 1; /* the last repeats the first */
        if (hull_n == 4) {
            int first = 0;
            for (int k = 1; k < 4; k++)
                if (h[k][0] + h[k][1] < h[first][0] + h[first][1])
                    first = k;
            for (int k = 0; k < 4; k++)
                memcpy(q[k], h[(first + k) % 4], sizeof q[0]);
        }
        free(pt);
        free(h);
    }
    if (hull_n != 4) {
        q[0][0] = x0, q[0][1] = y0, q[1][0] = x1, q[1][1] = y0;
        q[2][0] = x1, q[2][1] = y1, q[3][0] = x0, q[3][1] = y1;
    }
    return AA_OK;
}

static void feibushtex_release(void *state)
{
    ft_state *s = state;
    if (s->edge_made)
        aa_method_free(&s->edge);
    if (s->ejob_made)
        aa_job_free(&s->ejob);
    aa_scene_free(s->poly);
    aa_image_free(&s->share);
    free(s->tex);
    free(s->pal);
    free(s->table);
    memset(s, 0, sizeof *s);
}

static int feibushtex_init(void *state, const double *p, const aa_job *job)
{
    ft_state *s = state;
    double q[4][2];
    int st = find_polygon(job->pattern, q, &s->have);
    s->bg = aa_scene_background(job->placed);
    if (st || !s->have)
        return st;
    /* corners in pixels, as the job places the scene */
    double qp[4][2], side = 0;
    for (int k = 0; k < 4; k++) {
        qp[k][0] = job->w * q[k][0] + job->t * job->vx;
        qp[k][1] = job->h * q[k][1] + job->t * job->vy;
    }
    for (int k = 0; k < 4; k++)
        side = fmax(side, hypot(qp[(k + 1) % 4][0] - qp[k][0], qp[(k + 1) % 4][1] - qp[k][1]));
    square_to_quad(qp, s->h);
    adjugate(s->h, s->hi);
    /* the adjugate is the inverse times the determinant: make its w
     * positive inside the polygon */
    double cu, cv;
    apply(s->h, 0.5, 0.5, &cu, &cv);
    if (s->hi[6] * cu + s->hi[7] * cv + s->hi[8] < 0)
        for (int k = 0; k < 9; k++)
            s->hi[k] = -s->hi[k];
    int n = (int)p[P_TEXELS];
    if (n == 0)
        n = (int)fmin(FT_MAX_TEXELS, fmax(16, ceil(2 * side)));
    s->n = n;
    /* the texture: the scene's colour at each definition point, as an
     * index into its colours (the background and each layer's) */
    int nl = aa_scene_layer_count(job->placed);
    if (aa_scene_is_clipped(job->placed))
        return aa_fail(AA_EINVAL, "feibushtex takes unclipped layers only: its texture "
                                  "indexes one layer's colour per point by the front-most "
                                  "covering layer, and this scene has clip paths");
    if (!aa_scene_is_opaque(job->placed))
        return aa_fail(AA_EINVAL, "feibushtex takes opaque layers only: its texture indexes "
                                  "one layer's colour per point, and this scene has "
                                  "translucent layers (opacity below 1)");
    if (nl + 1 > 65535)
        return aa_fail(AA_EINVAL, "feibushtex: %d layers; at most 65534 are taken", nl);
    s->npal = nl + 1;
    s->tex = malloc((size_t)n * n * sizeof *s->tex);
    s->pal = malloc((size_t)s->npal * sizeof *s->pal);
    if (!s->tex || !s->pal)
        return aa_fail(AA_ENOMEM, "feibushtex: out of memory for %d x %d texels", n, n);
    for (int k = 0; k < 3; k++)
        s->pal[0][k] = s->bg.c[k];
    for (int l = 0; l < nl; l++) {
        aa_rgb c = aa_scene_layer_colour(job->placed, l);
        for (int k = 0; k < 3; k++)
            s->pal[l + 1][k] = c.c[k];
    }
    const aa_scene *placed = job->placed;
    unsigned short *tex = s->tex;
    const double *hm = s->h;
    const double(*pal)[3] = (const double(*)[3])s->pal;
    const int npal = s->npal;
#pragma omp parallel for num_threads(job->threads) schedule(static)
    for (int b = 0; b < n; b++)
        for (int a = 0; a < n; a++) {
            double u, v;
            int best = 0;
            if (apply(hm, (a + 0.5) / n, (b + 0.5) / n, &u, &v)) {
                aa_rgb c = aa_scene_colour_at(placed, u, v);
                double d = INFINITY;
                for (int k = 0; k < npal && d > 0; k++) {
                    double e = fabs(c.c[0] - pal[k][0]) + fabs(c.c[1] - pal[k][1]) +
                               fabs(c.c[2] - pal[k][2]);
                    if (e < d)
                        d = e, best = k;
                }
            }
            tex[(size_t)b * n + a] = (unsigned short)best;
        }
    /* the two-dimensional table of the weight over the mask's square */
    const aa_filter *f = &job->filter;
    double cut = f->type == &aa_filter_gauss_mask ? f->spec.v[1] : p[P_CUT];
    s->rc = f->type == &aa_filter_cone ? f->spec.v[0] : cut * f->spec.v[0];
    s->res = (int)p[P_RES];
    if (!(s->table = malloc((size_t)s->res * s->res * sizeof *s->table)))
        return aa_fail(AA_ENOMEM, "feibushtex: out of memory for the table");
    for (int j = 0; j < s->res; j++)
        for (int i = 0; i < s->res; i++) {
            double x = -s->rc + (i + 0.5) * 2 * s->rc / s->res;
            double y = -s->rc + (j + 0.5) * 2 * s->rc / s->res;
            s->table[(size_t)j * s->res + i] =
                hypot(x, y) <= s->rc ? aa_filter_weight2(f, x, y) : 0.0;
        }
    /* the edge filter: conetable on the polygon alone */
    s->poly = aa_scene_new((aa_rgb){{0, 0, 0}});
    if (!s->poly)
        return aa_fail(AA_ENOMEM, "feibushtex: out of memory");
    if ((st = aa_scene_layer(s->poly, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO)) ||
        (st = aa_scene_move_to(s->poly, q[0][0], q[0][1])))
        return st;
    for (int k = 1; k < 4 && !st; k++)
        st = aa_scene_line_to(s->poly, q[k][0], q[k][1]);
    if (st || (st = aa_scene_finish(s->poly)))
        return st;
    char text[128];
    aa_spec spec;
    if (f->type == &aa_filter_cone)
        snprintf(text, sizeof text, "conetable");
    else
        snprintf(text, sizeof text, "conetable:cut=%.17g", cut);
    if ((st = aa_method_parse(text, f, &spec)) ||
        (st = aa_job_init(&s->ejob, s->poly, job->w, job->h, job->t, job->vx, job->vy, f,
                          job->seed, job->threads)))
        return st;
    s->ejob_made = 1;
    if ((st = aa_method_init(&s->edge, &spec, &s->ejob)))
        return st;
    s->edge_made = 1;
    return aa_image_alloc(&s->share, job->w, job->h, 3);
}

/* The texture filter at the pixel centre (cx, cy): the weighted average of
 * the texture points in the mask's square (steps 3-7); *used the points
 * weighted. */
static void texture_filter(const ft_state *s, double cx, double cy, double out[3],
                           uint64_t *used)
{
    const int n = s->n, res = s->res;
    const double rc = s->rc;
    /* step 3: the mask's square to texture space, a rectangle around it */
    double smin = INFINITY, smax = -INFINITY, tmin = INFINITY, tmax = -INFINITY;
    int finite = 1;
    for (int k = 0; k < 4 && finite; k++) {
        double u, v;
        finite = apply(s->hi, cx + (k & 1 ? rc : -rc), cy + (k & 2 ? rc : -rc), &u, &v);
        smin = fmin(smin, u), smax = fmax(smax, u), tmin = fmin(tmin, v), tmax = fmax(tmax, v);
    }
    /* step 4: clipped to the parent polygon, the texture's unit square */
    int a0 = 0, a1 = n - 1, b0 = 0, b1 = n - 1;
    if (finite) {
        a0 = (int)fmax(0, floor(smin * n - 0.5)), a1 = (int)fmin(n - 1, ceil(smax * n - 0.5));
        b0 = (int)fmax(0, floor(tmin * n - 0.5)), b1 = (int)fmin(n - 1, ceil(tmax * n - 0.5));
    }
    double sw = 0, acc[3] = {0, 0, 0}, c0[3] = {0, 0, 0};
    int first = 1;
    uint64_t m = 0;
    for (int b = b0; b <= b1; b++)
        for (int a = a0; a <= a1; a++) {
            /* step 5: the point to image space; step 6: inside the square */
            double u, v;
            if (!apply(s->h, (a + 0.5) / n, (b + 0.5) / n, &u, &v))
                continue;
            double dx = u - cx, dy = v - cy;
            if (fabs(dx) > rc || fabs(dy) > rc)
                continue;
            /* step 7: the nearest table entry */
            int i = (int)((dx + rc) / (2 * rc) * res), j = (int)((dy + rc) / (2 * rc) * res);
            i = i < 0 ? 0 : i >= res ? res - 1 : i;
            j = j < 0 ? 0 : j >= res ? res - 1 : j;
            double w = s->table[(size_t)j * res + i];
            if (!(w > 0))
                continue;
            const double *c = s->pal[s->tex[(size_t)b * n + a]];
            if (first) {
                for (int k = 0; k < 3; k++)
                    c0[k] = c[k];
                first = 0;
            }
            for (int k = 0; k < 3; k++)
                acc[k] += w * (c[k] - c0[k]);
            sw += w;
            m++;
        }
    *used += m;
    if (sw > 0) {
        for (int k = 0; k < 3; k++)
            out[k] = c0[k] + acc[k] / sw;
        return;
    }
    /* no point in the mask: the one nearest the centre's texture coordinates */
    double u = 0.5, v = 0.5;
    apply(s->hi, cx, cy, &u, &v);
    int a = (int)floor(u * n), b = (int)floor(v * n);
    a = a < 0 ? 0 : a >= n ? n - 1 : a;
    b = b < 0 ? 0 : b >= n ? n - 1 : b;
    for (int k = 0; k < 3; k++)
        out[k] = s->pal[s->tex[(size_t)b * n + a]][k];
}

static int feibushtex_render(void *state, const double *p, const aa_job *job, aa_image *out,
                             aa_counters *counters)
{
    (void)p;
    ft_state *s = state;
    const int w = job->w, h = job->h;
    counters->samples = counters->expensive_pixels = 0;
    if (!s->have) {
        for (size_t q = 0; q < (size_t)w * h; q++)
            for (int k = 0; k < 3; k++)
                out->v[3 * q + k] = s->bg.c[k];
        return AA_OK;
    }
    aa_counters ec;
    int st = aa_method_render(&s->edge, &s->ejob, &s->share, &ec);
    if (st)
        return st;
    uint64_t used = 0, textured = 0;
#pragma omp parallel for num_threads(job->threads) schedule(dynamic, 4) reduction(+ : used, textured)
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double *o = aa_pixel(out, i, j);
            double v = aa_pixel(&s->share, i, j)[0];
            if (!(v > 0)) {
                for (int k = 0; k < 3; k++)
                    o[k] = s->bg.c[k];
                continue;
            }
            double c[3];
            texture_filter(s, i + 0.5, j + 0.5, c, &used);
            textured++;
            for (int k = 0; k < 3; k++) {
                double x = v >= 1 ? c[k] : s->bg.c[k] + v * (c[k] - s->bg.c[k]);
                o[k] = x < 0 ? 0 : x > 1 ? 1 : x;
            }
        }
    counters->samples = used;
    counters->expensive_pixels = textured;
    return AA_OK;
}

const aa_method_type aa_method_feibushtex = {
    .info = {"feibushtex",
             "Feibush et al.'s texture filter: texture points weighted from a 2-D table, times "
             "the edge filter's share (sec. 2.4-2.5)",
             feibushtex_params},
    .size = sizeof(ft_state),
    .flags = 0,
    .check = feibushtex_check,
    .init = feibushtex_init,
    .render = feibushtex_render,
    .release = feibushtex_release,
};
