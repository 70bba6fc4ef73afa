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
 *  - Arcs are flattened: each visible part of a piece inside the mask's
 *    rows (see Layers) is cut into n equal parameter steps, n = ceil(sqrt(|a| dt^2 / (4 tol))), so no
 *    chord is farther than tol= pixels (default 1e-3) from its parabola
 *    (|a| dt^2 / (4 n^2) is the largest gap of a parabola's chord); the
 *    area moved is at most 2/3 tol per pixel of chord, so the error of a
 *    pixel is at most (2/3) tol L wmax, L the flattened length inside the
 *    mask and wmax the largest weight (tests measure it).  A conic piece
 *    (an arc of an ellipse) the same in its parameter t (its angle scaled
 *    to [0, 1]), with |a| replaced by a bound on |P''|/2 (visible.h,
 *    aa__piece_bend); the segment between a chord and an elliptic arc
 *    within tol of it is at most pi/4 tol per pixel of chord (a half
 *    disc's share), so there the bound is (pi/4) tol L wmax.
 *  - Layers: Feibush et al. remove the hidden surfaces first (sec. 2.3, a
 *    polygon subdivision algorithm after Weiler: "the visible portions of
 *    all the polygons", the display polygons) and add each display
 *    polygon's filtered share, "the percentage of the total intensity of
 *    the pixel that is contributed by that polygon" (sec. 2.5).  Here the
 *    visible parts are found per pixel instead of for the whole picture
 *    (visible.c; a variant in the means, not the result: a polygon
 *    subdivision of the whole picture would have to clip arcs against
 *    arcs, while per pixel only the meeting heights of the few pieces near
 *    it are needed): the rows of the mask are cut into bands wherever a
 *    piece ends or two pieces meet, and in each band the pieces are swept
 *    along x, so each part of an edge knows the colours of the two visible
 *    surfaces beside it.  A display polygon's share is its colour times its
 *    volume, the winding at O plus the D terms of its boundary (above);
 *    each part of an edge bounds two display polygons with opposite
 *    orientations, so the sum of the shares regroups as
 *
 *        colour at O + sum over the visible parts of edges of
 *                      (colour right - colour left) x (D terms, top to bottom),
 *
 *    the flat (horizontal) parts with the colour above minus below and
 *    their D term from left to right.  These are the same table reads as
 *    clipping the display polygons and summing their shares; a hidden edge
 *    changes no colour and is not read, abutting polygons meet along one
 *    edge whose step is the difference of their colours (two coincident
 *    pieces, one per polygon, are taken in a fixed order so that their
 *    steps add up to it), and the background's share is the colour at O
 *    where no polygon is.  Parts of pieces outside the mask's square add
 *    nothing (their D terms are zero beyond the circle) and are joined to
 *    the part beside them, so no chord is cut there.
 *  - Weights.  weight=auto (the default) takes the weight the filter
 *    names: gauss with -f gauss:s=S, cone with -f cone:r=R; naming the
 *    other one is refused, so the method is always measured against the
 *    reference of the weight it forms.
 *    weight=gauss: exp(-r^2 / (2 s^2)) with s from -f gauss:s=S,
 *    cut off at Rc = cut s (cut=, default 2, Feibush et al.'s radius) and
 *    normalised by the volume inside the mask, so uniform regions are
 *    exact.  Under -f gauss:s=S,cut=K the mask is the filter's (K; cut=
 *    left out or equal) and the reference is that truncated Gaussian:
 *    no truncation error.  Under the untruncated -f gauss:s=S the error
 *    includes the truncation: exp(-cut^2 / 2) of the volume lies outside
 *    the mask (13.5 % at cut = 2, 1.1 % at 3, 3.4e-4 at 4).  The
 *    truncated cone (-f cone:cut=K, K < 1) is refused.
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
 * tests/test_prefilters.c: abutting polygons of different colours, with a
 * third hidden behind one, within the bound (two chord ends per visible
 * part) of the exact reference; the hidden polygon changes nothing, and no
 * red shows from a red square hidden behind a green one; feibush,
 * catmull:tiles=4, slivers and star within 5e-3 RMSE.
 *
 * Measured (against the exact references, 128x128, cut=4, res=256,
 * -f gauss:s=1; RMSE, max): feibush 8.2e-5, 4.2e-4; catmull:tiles=4 4.7e-5,
 * 1.8e-4; slivers 1.8e-5, 4.1e-4; crow 1.09e-4, 1.0e-3 and star 1.13e-4,
 * 8.0e-4 (both as before the visible parts).  Compositing the layers'
 * coverages front to back, as the code did before, was off by 0.12, 0.034
 * and 0.018 RMSE on the first three (abutting stripes darkened along their
 * shared edges, up to 0.25).  With -f cone, res=256: feibush 7.4e-6,
 * catmull 6.6e-17, slivers 1.2e-6 (before: 0.073, 0.015, 0.023).
 *
 * Cost: per pixel whose mask square meets an edge, the winding at O, the
 * visible parts of the edges near it (visible.c: a sort of the pieces
 * along x per band and a meeting test per neighbouring pair) and, per part
 * with a colour step, a projection, an atan2 and a bilinear read per chord;
 * other pixels are filled in runs (aa_strip_uniform_run).  Each pixel
 * depends only on its row's strip: the image is the same for any thread
 * count.  Counters: samples = 0 (no point samples), expensive_pixels =
 * pixels summed.  Limits: radial weights only, Gaussian or cone (box and
 * tent are separable squares, not circles: refused); a centre exactly on an
 * edge takes the winding the scene's crossing rule gives; values clamped to
 * [0, 1].
 */
#include "methods.h"
#include "sampling.h"
#include "visible.h"

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
    aa__sampler sampler; /* workers; own scratch: the visible parts' workspace */
    double tol;
} cn_state;

typedef struct cn_render {
    const cn_table *tab;
    const aa_scene *scene;
    double tol;
} cn_render;

/* The mask's radius in units of s: the filter's own under -f
 * gauss:s=S,cut=K (the reference is then the same truncated Gaussian),
 * else cut=. */
static double mask_cut(const double *p, const aa_filter *f)
{
    return f->type == &aa_filter_gauss_mask ? f->spec.v[1] : p[P_CUT];
}

static int conetable_check(const double *p, const aa_filter *f)
{
    int weight = (int)p[P_WEIGHT];
    int gauss = f->type == &aa_filter_gauss || f->type == &aa_filter_gauss_mask;
    if (f->type == &aa_filter_gauss_mask && p[P_CUT] != CN_DEFAULT_CUT &&
        p[P_CUT] != f->spec.v[1])
        return aa_fail(AA_EINVAL, "conetable: cut=%g differs from the filter's mask cut=%g: "
                                  "leave cut out (the filter's mask is taken)",
                       p[P_CUT], f->spec.v[1]);
    if (f->type == &aa_filter_cone && f->spec.v[1] != 1.0)
        return aa_fail(AA_EINVAL, "conetable forms the whole cone; the truncated cone (cut=%g) "
                                  "has no table here",
                       f->spec.v[1]);
    if (!gauss && f->type != &aa_filter_cone)
        return aa_fail(AA_EINVAL, "conetable weighs a circular mask with a radial weight and "
                                  "is measured against -f gauss:s=S or -f cone:r=R; it has no "
                                  "table for %s (its weights: the Gaussian and the cone)",
                       f->type->info.name);
    if (weight == W_CONE && f->type != &aa_filter_cone)
        return aa_fail(AA_EINVAL, "conetable: weight=cone is measured against the cone "
                                  "reference: use -f cone:r=R (or weight=gauss with -f %s)",
                       f->type->info.name);
    if (weight == W_GAUSS && !gauss)
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
    double cut = mask_cut(p, f);
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

/* One pixel's sums (the sink's context): the centre O, the colour steps
 * times their D terms, and the winding at O of the flattened picture. */
typedef struct cn_pixel {
    const cn_table *tab;
    double ox, oy, tol;
    double sum[3];
    int *wind; /* at O */
} cn_pixel;

/* A run of piece p over rows [ya, yb] with one colour step `jump` (right
 * minus left): flattened to chords within tol, its D terms (top to bottom)
 * times the step; and, if the run holds O's row, the crossing of its chord
 * there by the scene's rule (y0 <= y < y1), so that the winding at O is
 * that of the flattened picture the D terms describe. */
static void cn_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                   int inside)
{
    cn_pixel *P = ctx;
    int use = inside && (jump[0] != 0.0 || jump[1] != 0.0 || jump[2] != 0.0);
    int holds = ya <= P->oy && P->oy < yb;
    if (!use && !holds)
        return;
    double ta = ya <= p->y0 ? 0.0 : aa_piece_t_at(p, ya);
    double tb = yb >= p->y1 ? 1.0 : aa_piece_t_at(p, yb);
    int n = 1;
    if (p->kind == AA_PIECE_QUAD || p->kind == AA_PIECE_CUBIC || p->kind == AA_PIECE_CONIC) {
        /* |P''|/2 over [0, 1] is at most aa__piece_bend (visible.h) */
        double dt = tb - ta;
        double ca = aa__piece_bend(p);
        double steps = ceil(sqrt(ca * dt * dt / (4.0 * P->tol)));
        n = steps < 1.0 ? 1 : (steps > CN_MAX_STEPS ? CN_MAX_STEPS : (int)steps);
    }
    double sum = 0.0, t = ta, x0, y0, x1, y1, dydt;
    aa__piece_point(p, t, &x0, &y0, &dydt);
    for (int k = 1; k <= n; k++) {
        t = k == n ? tb : ta + (tb - ta) * k / n;
        aa__piece_point(p, t, &x1, &y1, &dydt);
        if (use)
            sum += segment_term(P->tab, P->ox, P->oy, x0, y0, x1, y1);
        if (holds && y0 <= P->oy && P->oy < y1 &&
            x0 + (x1 - x0) * ((P->oy - y0) / (y1 - y0)) < P->ox)
            P->wind[p->layer] += p->dir;
        x0 = x1, y0 = y1;
    }
    if (use)
        for (int ch = 0; ch < 3; ch++)
            P->sum[ch] += jump[ch] * sum;
}

/* A part of a flat piece from xa to xb at height y, with the colour above
 * minus below: its D term from left to right (a rightward edge has its
 * higher winding above it). */
static void cn_flat(void *ctx, const aa_piece *p, double xa, double xb, double y,
                    const double *jump)
{
    (void)p;
    cn_pixel *P = ctx;
    double g = segment_term(P->tab, P->ox, P->oy, xa, y, xb, y);
    for (int ch = 0; ch < 3; ch++)
        P->sum[ch] += jump[ch] * g;
}

/* Pixel (i, j), whose mask square holds local pieces (aa__sampler_shade_fn):
 * the colour at O plus, over the visible parts of the edges near it, the
 * step of colour across each times its D terms (header, "Layers"). */
static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const cn_render *R = ctx;
    const cn_table *tab = R->tab;
    const aa_scene *s = R->scene;
    cn_pixel P = {tab, i + 0.5, j + 0.5, R->tol, {0.0, 0.0, 0.0}, wk->wind};
    aa__vis v;
    aa__vis_bind(&v, s, 3, wk->own);
    aa_strip_winding_left(wk->strip, P.oy, P.wind);
    const aa__vis_sink sink = {NULL, cn_run, cn_flat, NULL, &P, 3, 1, 1, 0};
    aa__vis_window(&v, wk->strip, P.ox - tab->rc, P.ox + tab->rc, P.oy - tab->rc,
                   P.oy + tab->rc, &sink);
    aa_rgb c = aa_scene_colour_of(s, P.wind);
    for (int ch = 0; ch < 3; ch++) {
        double a = c.c[ch] + P.sum[ch];
        px[ch] = a < 0.0 ? 0.0 : (a > 1.0 ? 1.0 : a);
    }
}

static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    const cn_render *R = ctx;
    return aa__sampler_row(wk, j, R->tab->rc, 0, shade, ctx, out, samples, expensive);
}

static int prepare(cn_state *S, const aa_job *job)
{
    return aa__sampler_ready(&S->sampler, job, aa__vis_size(job->placed, 3));
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
