/*
 * conetable.c: edge filtering by volumes over right triangles read from a
 * lookup table (Feibush, Levoy and Cook 1980, "Synthetic texturing using
 * digital filters", section "Edge filtering", fig. 3a-f).
 *
 * What is theirs.  A circularly symmetric weight over a circular mask of
 * radius Rc around the pixel ("the convolution mask is a circle whose
 * radius is equal to twice the standard deviation", fig. 4d); a polygon's
 * contribution is the fraction of the filter's volume above it (fig. 3a).
 * Each edge P -> Q of the polygon with the pixel O makes a triangle OPQ
 * (fig. 3c) counted with the sign of its orientation; the perpendicular
 * from O to the line PQ splits it into two right triangles whose volumes
 * add or subtract (figs. 3d, 3e); the volume above a right triangle comes
 * from a table indexed by its two legs (fig. 3f), which "includes only the
 * volume above the shaded portion", i.e. inside the mask, so that "each
 * filter shape needs only one lookup table, regardless of the filter's
 * absolute size".
 *
 * What is chosen here.
 *  - The table's indices: the right triangle's leg from O, h (the distance
 *    from O to the edge's line), scaled by Rc, and its angle at O,
 *    theta = atan(b / h) in [0, pi/2] (b the other leg), res x res
 *    intervals (res=, default 64), read by bilinear interpolation.  An angle
 *    keeps the index range finite where Feibush et al.'s base length is
 *    not.
 *  - No clipping to the mask's bounding rectangle (their step 1).  The
 *    table stores D(h, theta) = V(h, theta) - theta / (2 pi): the volume
 *    over the right triangle minus that of the whole sector of angle theta,
 *    i.e. minus the volume inside the mask beyond the triangle's far side.
 *    For a closed path the sectors add up to the winding number at O, so
 *    the fraction of the volume over a layer is
 *
 *        I = wind(O) + sum over the path's edges of the signed D terms,
 *
 *    and an edge that does not enter the mask adds exactly 0 (D is 0 for
 *    h >= Rc, and constant for the part of a line beyond the circle), so
 *    only the pieces the strip reports near the pixel are visited, each
 *    clipped to the mask's rows.  This is their signed decomposition of
 *    the clipped polygon, rearranged; it needs no polygon clipping.
 *  - Arcs are flattened: a piece's part inside the mask's rows is cut into
 *    n equal parameter steps, n = ceil(sqrt(|a| dt^2 / (4 tol))), so no
 *    chord is farther than tol= pixels (default 1e-3) from its parabola
 *    (|a| dt^2 / (4 n^2) is the largest gap of a parabola's chord); the
 *    area moved is at most 2/3 tol per pixel of chord, so the error of a
 *    pixel is at most (2/3) tol L wmax, L the flattened length inside the
 *    mask and wmax the largest weight (tests measure it).
 *  - Layers: within a pixel each layer's region is taken to have winding
 *    0 or +-1 (Feibush et al.'s polygons: the coverage is |I| clamped to
 *    [0, 1]), and the layers are composited front to back, each over the
 *    ones behind it with its coverage; a layer without edges near the
 *    pixel has coverage 0 or 1 from its fill rule at O.  This is exact
 *    where one layer's edges reach the mask (the usual case, and crow), and
 *    where several do and their regions do not overlap inside it; where
 *    regions of several layers overlap inside the mask it is the
 *    compositing approximation Crow's z-buffer tiler also makes.
 *  - Weights.  weight=auto (the default) takes the weight the filter
 *    names: gauss with -f gauss:s=S, cone with -f cone:r=R; naming the
 *    other one is refused, so the method is always measured against the
 *    reference of the weight it forms.
 *    weight=gauss: exp(-r^2 / (2 s^2)) with s from -f gauss:s=S,
 *    cut off at Rc = cut s (cut=, default 2, Feibush et al.'s radius) and
 *    normalised by the volume inside the mask, so uniform regions are
 *    exact.  It is measured against the untruncated, separable Gaussian
 *    reference (the 2-D Gaussian is both), so the error includes the
 *    truncation: exp(-cut^2 / 2) of the volume lies outside the mask
 *    (13.5 % at cut = 2, 1.1 % at 3, 3.4e-4 at 4).
 *    weight=cone (their fig. 2f, 3a): 1 - r / Rc with the mask radius
 *    Rc = R from -f cone:r=R, normalised by its volume pi Rc^2 / 3, which
 *    is all inside the mask: it is measured against the exact cone
 *    reference (filter.c, truth.c) and has no truncation error.  cut= is
 *    the Gaussian's and is refused with the cone.
 *
 * The table is made in init by Gauss-Legendre quadrature of
 * D(u, theta) = -(1 / (2 pi M)) int_0^min(theta, acos u)
 *               [exp(-u^2 c^2 / (2 cos^2 phi)) - exp(-c^2 / 2)] dphi,
 * u = h / Rc, c = cut, M = 1 - exp(-c^2 / 2) (the sector integral of the
 * radial weight, in closed form in r): five points on each of 8 sub-cells
 * per table cell, cut at acos u where the integrand has a kink, accurate to
 * about 1e-13.  For the cone the same sector integral is a polynomial,
 * (3 / pi) int_a^1 (1 - rho) rho drho = (3 / pi) (1/6 - a^2/2 + a^3/3)
 * with a = u sec phi, and its integral over phi is closed:
 *
 *   D(u, theta) = -(3 / pi) [t / 6 - (u^2 / 2) tan t
 *                            + (u^3 / 6) (sec t tan t + ln(sec t + tan t))],
 *
 * t = min(theta, acos u) (int sec^2 = tan, int sec^3 = (sec tan +
 * ln(sec + tan)) / 2); D(0, theta) = -theta / (2 pi) and D(1, .) = 0.
 *
 * Error analysis (per pixel, against the untruncated Gaussian reference):
 *  - truncation: at most 2 exp(-cut^2 / 2) (the volume outside the mask
 *    plus the volume moved by renormalising);
 *  - interpolation: a bilinear read is off by at most D's variation over
 *    one cell, |dD/dtheta| <= 1 / (2 pi) and, substituting tan phi,
 *    |dD/du| = (c / (2 pi M)) sqrt(pi / 2) exp(-u^2 c^2 / 2)
 *    <= c / (2 M sqrt(2 pi)), so per chord end at most
 *    (1/4 + c / (2 M sqrt(2 pi))) / res, two ends per chord near the mask.
 *    This is first order in 1/res: D is not smooth at u = 0, theta = pi/2
 *    (an edge through the centre) nor along theta = acos u; away from those
 *    cells bilinear reads are second order (the half-plane test converges
 *    about as 1/res^2);
 *  - flattening: at most (2/3) tol L wmax, see above.
 *
 * Error analysis for weight=cone (per pixel, against the exact cone
 * reference): no truncation (the weight is zero outside the mask and its
 * whole volume is inside); interpolation as above with |dD/dtheta| <=
 * (3 / pi) (1/6) = 1 / (2 pi) and, since the sector integrand has a double
 * zero at a = 1 (no boundary term), dD/du = (3 / pi) int_0^sqrt(1 - u^2)
 * (1 - sqrt(u^2 + x^2)) dx (substituting x = u tan phi), the integral of
 * half a row of the unit cone, largest at u = 0: |dD/du| <= 3 / (2 pi).
 * So per chord end at most (1/4 + 3 / (2 pi)) / res = 0.727 / res, and
 * flattening (2/3) tol L wmax with wmax = 3 / (pi R^2).  Measured
 * (tests/test_tables.c): a half-plane under cone:r=2 is off by at most
 * 8.4e-3 at res=8 and 1.0e-5 at res=256 (bound 0.18 and 5.7e-3); crow
 * 64x64, cone:r=1, defaults: RMSE 3.1e-4, max 2.2e-3, every pixel within
 * its bound; crow 256x256: RMSE 2.2e-4, max 2.0e-3 (res=256, tol=1e-6:
 * 1.6e-5 and 4.4e-4, so the table and the flattening share the error).
 *
 * Known answers (tests/test_tables.c): with cut=8 a half-plane at any angle
 * gives Phi(d / s), d the signed distance of the centre, within the
 * interpolation bound of its two chord ends (measured: 1.3e-3 at res=32,
 * 8e-5 to 4e-4 at res=128); every pixel of crow 128x128 is within the
 * bound above with the pieces near it counted from the scene.
 *
 * Cost: per pixel whose mask square meets an edge, the winding at O and,
 * per segment of the nearby pieces, a projection, an atan2 and a bilinear
 * read; other pixels are filled in runs (aa_strip_uniform_run).  Each
 * pixel depends only on its row's strip: the image is the same for any
 * thread count.  Counters: samples = 0 (no point samples), expensive_pixels
 * = pixels summed.  Limits: radial weights only, Gaussian or cone (box and
 * tent are separable squares, not circles: refused); a centre exactly on an edge
 * takes the winding the scene's crossing rule gives; values clamped to
 * [0, 1].
 */
#include "methods.h"
#include "sampling.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CN_MAX_RES 1024
#define CN_MAX_STEPS 256 /* chords per piece and pixel */

enum { P_WEIGHT, P_CUT, P_RES, P_TOL };
enum { W_AUTO, W_GAUSS, W_CONE };
#define CN_DEFAULT_CUT 2.0

static const aa_param conetable_params[] = {
    {"weight", AA_PARAM_CHOICE, W_AUTO, 0, 0, 0, "auto|gauss|cone",
     "radial weight: the filter's (auto), Gaussian (-f gauss:s=S) or cone (-f cone:r=R, "
     "Feibush et al. fig. 2f)"},
    {"cut", AA_PARAM_REAL, CN_DEFAULT_CUT, 0.5, 8.0, 0, NULL,
     "Gaussian only: mask radius in standard deviations (Feibush et al.: 2)"},
    {"res", AA_PARAM_INT, 64, 2, CN_MAX_RES, 0, NULL,
     "table intervals along each index (distance to the edge's line, angle)"},
    {"tol", AA_PARAM_REAL, 1e-3, 1e-6, 0.5, 0, NULL,
     "largest distance in pixels between an arc and its chords"},
    {0}};

typedef struct cn_table {
    int n;          /* intervals per index */
    double rc;      /* mask radius in pixels */
    double *d;      /* d[(n + 1) * a + b]: D(u_a, theta_b) */
} cn_table;

typedef struct cn_state {
    cn_table tab;
    aa__sampler sampler; /* workers; own scratch: per-layer sums and flags */
    double tol;
} cn_state;

typedef struct cn_render {
    const cn_table *tab;
    const aa_scene *scene;
    double tol;
} cn_render;

static int conetable_check(const double *p, const aa_filter *f)
{
    int weight = (int)p[P_WEIGHT];
    if (f->type != &aa_filter_gauss && f->type != &aa_filter_cone)
        return aa_fail(AA_EINVAL, "conetable weighs a circular mask with a radial weight and "
                                  "is measured against -f gauss:s=S or -f cone:r=R; %s is a "
                                  "separable square filter it cannot form",
                       f->type->info.name);
    if (weight == W_CONE && f->type != &aa_filter_cone)
        return aa_fail(AA_EINVAL, "conetable: weight=cone is measured against the cone "
                                  "reference: use -f cone:r=R (or weight=gauss with -f %s)",
                       f->type->info.name);
    if (weight == W_GAUSS && f->type != &aa_filter_gauss)
        return aa_fail(AA_EINVAL, "conetable: weight=gauss is measured against the Gaussian "
                                  "reference: use -f gauss:s=S (or weight=cone with -f %s)",
                       f->type->info.name);
    if (f->type == &aa_filter_cone && p[P_CUT] != CN_DEFAULT_CUT)
        return aa_fail(AA_EINVAL, "cut=%g sets the Gaussian's mask; the cone's mask is its "
                                  "radius r of -f cone:r=R (leave cut out)",
                       p[P_CUT]);
    return AA_OK;
}

/* The cone's D(u, theta) in closed form (header). */
static double cone_d(double u, double theta)
{
    double t = fmin(theta, acos(u));
    if (!(t > 0.0))
        return 0.0;
    double sec = 1.0 / cos(t), tn = tan(t);
    return -(3.0 / M_PI) *
           (t / 6.0 - 0.5 * u * u * tn + (u * u * u / 6.0) * (sec * tn + log(sec + tn)));
}

/* 5-point Gauss-Legendre on [-1, 1]. */
static const double gl_x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                               0.5384693101056831, 0.9061798459386640};
static const double gl_w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                               0.4786286704993665, 0.2369268850561891};

/* int over [lo, hi] of exp(-k / cos^2 phi) - e0. */
static double cell_integral(double lo, double hi, double k, double e0)
{
    double sum = 0.0;
    const int sub = 8;
    for (int q = 0; q < sub; q++) {
        double a = lo + (hi - lo) * q / sub, b = lo + (hi - lo) * (q + 1) / sub;
        double m = 0.5 * (a + b), r = 0.5 * (b - a);
        for (int g = 0; g < 5; g++) {
            double c = cos(m + r * gl_x[g]);
            sum += r * gl_w[g] * (exp(-k / (c * c)) - e0);
        }
    }
    return sum;
}

static int table_make(cn_table *tab, const double *p, const aa_filter *f)
{
    int n = (int)p[P_RES];
    double cut = p[P_CUT];
    double *d = malloc((size_t)(n + 1) * (size_t)(n + 1) * sizeof *d);
    if (!d)
        return aa_fail(AA_ENOMEM, "out of memory for a %d x %d table", n + 1, n + 1);
    int cone = f->type == &aa_filter_cone;
    double e0 = exp(-0.5 * cut * cut), M = -expm1(-0.5 * cut * cut);
    double scale = -1.0 / (2.0 * M_PI * M);
    for (int a = 0; a <= n && cone; a++)
        for (int b = 0; b <= n; b++)
            d[(size_t)(n + 1) * a + b] = cone_d((double)a / n, M_PI_2 * b / n);
    for (int a = 0; a <= n && !cone; a++) {
        double u = (double)a / n, k = 0.5 * u * u * cut * cut;
        double kink = acos(u); /* beyond it the triangle's far side is outside the mask */
        double acc = 0.0;
        d[(size_t)(n + 1) * a] = 0.0;
        for (int b = 1; b <= n; b++) {
            double lo = M_PI_2 * (b - 1) / n, hi = M_PI_2 * b / n;
            if (u == 0.0)
                acc += M * (hi - lo); /* exp(-0) - e0 */
            else if (lo < kink)
                acc += cell_integral(lo, fmin(hi, kink), k, e0);
            d[(size_t)(n + 1) * a + b] = scale * acc;
        }
    }
    free(tab->d);
    tab->d = d;
    tab->n = n;
    tab->rc = cone ? f->spec.v[0] : cut * f->spec.v[0];
    return AA_OK;
}

/* G(h, t) = sign(t) D(h / Rc, atan(|t| / h)), bilinear in the table. */
static inline double table_g(const cn_table *tab, double h, double t)
{
    double u = h / tab->rc;
    if (!(u < 1.0))
        return 0.0;
    double th = atan2(fabs(t), h) * (tab->n / M_PI_2), x = u * tab->n;
    int a = (int)x, b = (int)th;
    if (a >= tab->n)
        a = tab->n - 1;
    if (b >= tab->n)
        b = tab->n - 1;
    double fa = x - a, fb = th - b;
    const double *r0 = tab->d + (size_t)(tab->n + 1) * a, *r1 = r0 + tab->n + 1;
    double v = (1 - fa) * ((1 - fb) * r0[b] + fb * r0[b + 1]) +
               fa * ((1 - fb) * r1[b] + fb * r1[b + 1]);
    return t < 0.0 ? -v : v;
}

/* The signed D term of the segment P -> Q seen from O = (ox, oy). */
static inline double segment_term(const cn_table *tab, double ox, double oy, double px,
                                  double py, double qx, double qy)
{
    double dx = qx - px, dy = qy - py, len = hypot(dx, dy);
    if (!(len > 0.0))
        return 0.0;
    dx /= len, dy /= len;
    double rx = px - ox, ry = py - oy;
    double hn = dx * ry - dy * rx; /* signed distance of the line from O */
    double tp = rx * dx + ry * dy, tq = tp + len;
    double h = fabs(hn);
    if (!(h < tab->rc))
        return 0.0;
    /* a path whose shoelace area is positive has winding -1 in the scene's
     * convention (y down, crossings of up edges count -1) */
    double g = table_g(tab, h, tq) - table_g(tab, h, tp);
    return hn > 0.0 ? g : (hn < 0.0 ? -g : 0.0);
}

/* The sum of the D terms of the part of piece p inside rows [ya, yb],
 * flattened to chords within tol, in the direction of its edge. */
static double piece_term(const cn_table *tab, const aa_piece *p, double ox, double oy,
                         double ya, double yb, double tol, int *cross)
{
    double ta = 0.0, tb = 1.0;
    if (p->kind != AA_PIECE_FLAT) {
        double lo = fmax(ya, p->y0), hi = fmin(yb, p->y1);
        if (!(lo < hi))
            return 0.0;
        ta = lo <= p->y0 ? 0.0 : aa_piece_t_at(p, lo);
        tb = hi >= p->y1 ? 1.0 : aa_piece_t_at(p, hi);
    }
    int n = 1;
    if (p->kind == AA_PIECE_QUAD) {
        double dt = tb - ta, ca = hypot(p->ax, p->ay);
        double steps = ceil(sqrt(ca * dt * dt / (4.0 * tol)));
        n = steps < 1.0 ? 1 : (steps > CN_MAX_STEPS ? CN_MAX_STEPS : (int)steps);
    }
    double sum = 0.0, t = ta;
    double x0 = p->x0 + t * (p->bx + t * p->ax), y0 = p->y0 + t * (p->by + t * p->ay);
    for (int k = 1; k <= n; k++) {
        t = k == n ? tb : ta + (tb - ta) * k / n;
        double x1 = p->x0 + t * (p->bx + t * p->ax), y1 = p->y0 + t * (p->by + t * p->ay);
        sum += segment_term(tab, ox, oy, x0, y0, x1, y1);
        /* the chord's crossing of the line through O, by the scene's rule
         * (y0 <= y < y1 along the piece), so the winding at O is that of
         * the flattened path the D terms describe */
        if (p->dir && y0 <= oy && oy < y1 && x0 + (x1 - x0) * ((oy - y0) / (y1 - y0)) < ox)
            *cross += p->dir;
        x0 = x1, y0 = y1;
    }
    /* pieces are stored top to bottom: an edge running up is reversed */
    return p->dir < 0 ? -sum : sum;
}

/* Pixel (i, j), whose mask square holds local pieces (aa__sampler_shade_fn). */
static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const cn_render *R = ctx;
    const cn_table *tab = R->tab;
    const aa_scene *s = R->scene;
    double cx = i + 0.5, cy = j + 0.5;
    int nl = aa_scene_layer_count(s);
    double *sum = wk->own;
    unsigned char *has = (unsigned char *)(sum + (nl > 0 ? nl : 1));
    memset(has, 0, (size_t)(nl > 0 ? nl : 1));
    /* the winding at O: the pieces left of the window, then the local
     * pieces' chords */
    int *cross = wk->wind;
    aa_strip_winding_left(wk->strip, cy, cross);
    size_t nloc;
    const aa_piece *const *loc = aa_strip_local(wk->strip, &nloc);
    for (size_t k = 0; k < nloc; k++) {
        const aa_piece *p = loc[k];
        double v =
            piece_term(tab, p, cx, cy, cy - tab->rc, cy + tab->rc, R->tol, &cross[p->layer]);
        if (!has[p->layer])
            has[p->layer] = 1, sum[p->layer] = 0.0;
        sum[p->layer] += v;
    }
    double a0 = 0, a1 = 0, a2 = 0, through = 1.0;
    for (int l = 0; l < nl && through > 0.0; l++) {
        double cov;
        if (has[l]) {
            cov = fabs(wk->wind[l] + sum[l]);
            cov = cov > 1.0 ? 1.0 : cov;
        } else {
            int w = wk->wind[l];
            cov = aa_scene_layer_rule(s, l) == AA_FILL_EVENODD ? (double)(w & 1) : (w != 0);
        }
        aa_rgb c = aa_scene_layer_colour(s, l);
        double k = through * cov;
        a0 += k * c.c[0], a1 += k * c.c[1], a2 += k * c.c[2];
        through -= k;
    }
    aa_rgb bg = aa_scene_background(s);
    const double acc[3] = {a0 + through * bg.c[0], a1 + through * bg.c[1],
                           a2 + through * bg.c[2]};
    for (int ch = 0; ch < 3; ch++)
        px[ch] = acc[ch] < 0.0 ? 0.0 : (acc[ch] > 1.0 ? 1.0 : acc[ch]);
}

static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    const cn_render *R = ctx;
    return aa__sampler_row(wk, j, R->tab->rc, 0, shade, ctx, out, samples, expensive);
}

static int prepare(cn_state *S, const aa_job *job)
{
    int nl = aa_scene_layer_count(job->placed);
    size_t n = (size_t)(nl > 0 ? nl : 1);
    return aa__sampler_ready(&S->sampler, job, n * (sizeof(double) + 1));
}

static int conetable_init(void *state, const double *p, const aa_job *job)
{
    cn_state *S = state;
    int st = table_make(&S->tab, p, &job->filter);
    S->tol = p[P_TOL];
    return st ? st : prepare(S, job);
}

static int conetable_render(void *state, const double *p, const aa_job *job, aa_image *out,
                            aa_counters *counters)
{
    (void)p;
    cn_state *S = state;
    int st = prepare(S, job);
    if (st)
        return st;
    const cn_render R = {&S->tab, job->placed, S->tol};
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void conetable_release(void *state)
{
    cn_state *S = state;
    aa__sampler_free(&S->sampler);
    free(S->tab.d);
    S->tab.d = NULL;
}

const aa_method_type aa_method_conetable = {
    {"conetable",
     "radial filter volumes over right triangles from a lookup table (Feibush et al. fig. 3)",
     conetable_params},
    sizeof(cn_state),
    0,
    conetable_check,
    conetable_init,
    conetable_render,
    conetable_release};
