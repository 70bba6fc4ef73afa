/*
 * analytic.c: analytic rasterization under piecewise polynomial filters
 * (Manson and Schaefer 2013, "Analytic Rasterization of Curves with
 * Polynomial Filters", Computer Graphics Forum 32(2), Eurographics): the
 * convolution of the filter with the picture, an integral over area, turned
 * by Green's theorem into an integral along the shapes' boundaries, which
 * for a polynomial curve and a polynomial piece of the filter is the
 * integral of a polynomial, found exactly.
 *
 * What is the paper's.
 *  - The boundary integral.  For a separable filter w(u) w(v) with 1-D
 *    integral W(t) = integral of w from -infinity to t, the weight of a
 *    region R around the centre (cx, cy) is, by Green's theorem with the
 *    field (W(x - cx) w(y - cy), 0), whose curl is the filter,
 *
 *        integral over R of w(x - cx) w(y - cy) dx dy
 *            = - integral along the boundary of R of W(x - cx) w(y - cy) dy,
 *
 *    the boundary taken counter-clockwise in x right, y down coordinates
 *    (clockwise on screen).  Here it is written, as in Crow's "left areas
 *    minus right areas", per edge: the weight right of an edge over its
 *    rows [ya, yb] is
 *
 *        R(edge) = integral from ya to yb of w(y - cy) (1 - W(x(y) - cx)) dy
 *                = integral over t of w(y(t) - cy) (1 - W(x(t) - cx)) y'(t) dt,   (1)
 *
 *    the terms of the boundary integral of the paper, the constant 1 being
 *    the part of the field that integrates to the rows' weight.
 *  - The filters are piecewise polynomials; their support is cut into the
 *    cells of the pieces (the knots below, in u and v), and on each cell
 *    w and W are polynomials.  Cutting a curve where it crosses the knots'
 *    lines x = cx + k and y = cy + k leaves parts inside one cell each,
 *    where the integrand of (1) is a polynomial in the curve's parameter t.
 *  - The filters: box, tent (linear), the quadratic and cubic B-splines and
 *    Mitchell and Netravali's cubics (Catmull-Rom among them), all
 *    separable, as the paper lists; the curves: lines, quadratic and cubic
 *    Bezier arcs.
 *
 * The closed forms.  With w of degree n on a cell (box 0, tent 1,
 * bspline:order=2 2, bspline:order=3 and mitchell 3), W of degree n + 1,
 * and a curve of degree d in t (line 1, quadratic 2, cubic 3), the
 * integrand of (1) on one part is a polynomial of degree
 *
 *     n d + (n + 1) d + (d - 1) = 2 d (n + 1) - 1,
 *
 * and the m-point Gauss-Legendre rule integrates every polynomial of degree
 * 2m - 1 exactly, so m = d (n + 1) points give the integral of each part,
 * in closed form, to rounding:
 *
 *     curve \ filter   box  tent  bspline:2  bspline:3, mitchell, catrom
 *     line              1     2       3          4
 *     quadratic         2     4       6          8
 *     cubic             3     6       9         12
 *
 * (The paper gives closed-form expressions, the polynomial integrated term
 * by term; the Gauss rule of the right degree is the same integral,
 * evaluated from the integrand's values: a variant in the means, chosen
 * because an expanded power basis can have coefficients far larger than
 * the integrand's values and lose digits to cancellation, while the Gauss
 * sum's weights are positive.  The nodes and weights are the roots of the
 * Legendre polynomial P_m and 2 / ((1 - x^2) P_m'(x)^2), found by Newton's
 * method in long double at init, for m up to 12.)
 * The filters' pieces are their definitions in patterns/README.md,
 * "Filters", written per cell about the cell's left knot here (the method
 * reads neither the harness's filter functions nor the reference): on
 * |t| in [a, b) a polynomial P(|t|), so on t in [-b, -a) P(-t) and on
 * [a, b) P(t), each shifted to the cell's left end (a Taylor shift); the
 * two cells about 0 are one where P is even (box, the B-splines, Mitchell:
 * no odd terms near 0; the tent's kink at 0 stays a knot).  W on a cell is
 * W at its left knot plus the integral of the cell's w (each coefficient
 * c_i s^i giving c_i s^(i+1)/(i+1)).
 *
 * What is chosen here (a variant in the means, not in the values).  The
 * paper rasterizes a scene of one shape at a time by scanlines, adding each
 * curve's terms to the pixels whose supports it crosses.  Shapes that
 * overlap are not summed but painted, and the weight of an area hidden by a
 * front layer must not count: here each pixel takes the visible parts of
 * the edges in its support (visible.c, as `crowtiler:hidden=scan` does),
 * each with its step of colour, so the pixel is
 *
 *     sum over bands of (colour left of the support) (W(yb - cy) - W(ya - cy))
 *       + sum over visible parts of (step of colour across it) R(part),
 *
 * which is the filtered picture exactly, for any number of opaque layers in
 * painter's order and either fill rule.  The price is the per-pixel work of
 * finding the visible parts (see Cost).
 *
 * Error analysis: rounding, and the heights where pieces meet (found in
 * closed form by visible.c) and where they cross the knots' lines
 * (aa_piece_meet_x): a cut misplaced by e moves the part of width e into
 * the neighbouring cell's polynomial, whose value differs there by at most
 * e times the jump of w's derivative (w and W are continuous; the box's
 * steps are at the support's sides, where the window ends).  Values are
 * clamped to the filter's range (aa_filter_range: a rounding of 1e-16
 * past it).
 *
 * Known answers (tests/test_analytic.c): the exact reference
 * (aa_truth_render) within 1e-12 per pixel on crow, star, slivers,
 * catmull, feibush, SVG scenes of quadratic and cubic arcs and overlapping
 * even-odd layers, under every filter taken; a white region's image sums
 * to its area (Archimedes' parabolic segment, 2/3 of its control triangle;
 * the area under y = x^3, 1/4) under the filters whose integer translates
 * sum to 1 (box, tent:r=1, the B-splines, Mitchell-Netravali, Catmull-Rom).
 *
 * Limits, refused by name: filters that are not piecewise polynomial
 * (gauss, lanczos) and the radial ones (cone, gauss:cut: the paper's radial
 * polynomial filters are not done); elliptical arcs (the paper's rational
 * quadratic closed form is not done) and offset curves (stroked Bezier arcs,
 * not polynomials); field scenes (no edges).  The paper also fills with
 * linear colour gradients, which the scene model does not hold.
 *
 * Cost: per pixel whose support meets an edge, the visible parts (sorting
 * each band's pieces along x and one meeting test per neighbouring pair)
 * and, per part and cell, the rule of the table above; other pixels are
 * filled in runs.  A pixel depends only on its row's strip: the same image
 * for any thread count.  Counters: samples = 0, expensive_pixels = pixels
 * summed.
 */
#include "core.h"
#include "methods.h"
#include "sampling.h"
#include "visible.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define AN_MAX_CELLS 6
#define AN_MAX_GAUSS 12

static const aa_param analytic_params[] = {{0}};

/* A piecewise polynomial 1-D filter: cells [k[c], k[c+1]), on each
 * w(t) = sum w[c][i] s^i and W(t) = sum cdf[c][i] s^i, s = t - k[c]. */
typedef struct an_pp {
    int ncell, deg; /* deg: of w (n above) */
    double k[AN_MAX_CELLS + 1];
    double w[AN_MAX_CELLS][4];
    double cdf[AN_MAX_CELLS][5];
} an_pp;

typedef struct an_state {
    aa__sampler sampler;
    an_pp pp;
    /* Gauss-Legendre on [-1, 1]: gx[m][q], gw[m][q] for m points */
    double gx[AN_MAX_GAUSS + 1][AN_MAX_GAUSS], gw[AN_MAX_GAUSS + 1][AN_MAX_GAUSS];
} an_state;

typedef struct an_render {
    const an_state *S;
    const aa_scene *scene;
    double lo, hi; /* the filter's range */
} an_render;

/* ---- the filters' pieces (patterns/README.md, "Filters") ---- */

/* A symmetric filter by its pieces in x = |t|: on [xb[q], xb[q+1]) the
 * polynomial sum c[q][i] x^i. */
typedef struct an_def {
    int npiece;
    double xb[4];
    double c[3][4];
} an_def;

static int an_def_of(const aa_filter *f, an_def *d)
{
    const double *p = f->spec.v;
    memset(d, 0, sizeof *d);
    if (f->type == &aa_filter_box) {
        *d = (an_def){1, {0.0, 0.5}, {{1.0}}};
        return 0;
    }
    if (f->type == &aa_filter_tent) {
        double r = p[0];
        *d = (an_def){1, {0.0, r}, {{1.0 / r, -1.0 / (r * r)}}};
        return 0;
    }
    if (f->type == &aa_filter_bspline && p[0] == 2.0) {
        /* 3/4 - x^2; (3/2 - x)^2 / 2 = 9/8 - 3/2 x + x^2/2 */
        *d = (an_def){2, {0.0, 0.5, 1.5}, {{0.75, 0.0, -1.0}, {1.125, -1.5, 0.5}}};
        return 0;
    }
    double b, c;
    if (f->type == &aa_filter_bspline && p[0] == 3.0)
        b = 1.0, c = 0.0; /* (4 - 6x^2 + 3x^3)/6, (2 - x)^3/6: mitchell:b=1,c=0 */
    else if (f->type == &aa_filter_mitchell)
        b = p[0], c = p[1];
    else if (f->type == &aa_filter_catrom)
        b = 0.0, c = 0.5;
    else
        return -1;
    /* Mitchell and Netravali (1988, eq. 8) */
    *d = (an_def){2,
                  {0.0, 1.0, 2.0},
                  {{(6.0 - 2.0 * b) / 6.0, 0.0, (-18.0 + 12.0 * b + 6.0 * c) / 6.0,
                    (12.0 - 9.0 * b - 6.0 * c) / 6.0},
                   {(8.0 * b + 24.0 * c) / 6.0, (-12.0 * b - 48.0 * c) / 6.0,
                    (6.0 * b + 30.0 * c) / 6.0, (-b - 6.0 * c) / 6.0}}};
    return 0;
}

/* q(s) = P(x0 + sg s), P of degree 3 (a Taylor shift, then the sign). */
static void shift(const double *P, double x0, double sg, double *q)
{
    double a[4] = {P[0], P[1], P[2], P[3]};
    /* synthetic division by (x - x0), repeated: a becomes the Taylor
     * coefficients about x0 */
    for (int i = 0; i < 4; i++)
        for (int j = 2; j >= i; j--)
            a[j] += x0 * a[j + 1];
    double s = 1.0;
    for (int i = 0; i < 4; i++, s *= sg)
        q[i] = a[i] * s;
}

static void an_pp_make(const an_def *d, an_pp *pp)
{
    memset(pp, 0, sizeof *pp);
    int n = 0;
    /* the left half, outermost first: t in [-xb[q+1], -xb[q]), x = -t */
    for (int q = d->npiece - 1; q >= 0; q--) {
        pp->k[n] = -d->xb[q + 1];
        shift(d->c[q], d->xb[q + 1], -1.0, pp->w[n]);
        n++;
    }
    /* the right half: t in [xb[q], xb[q+1]), x = t */
    for (int q = 0; q < d->npiece; q++) {
        pp->k[n] = d->xb[q];
        shift(d->c[q], d->xb[q], 1.0, pp->w[n]);
        n++;
    }
    pp->k[n] = d->xb[d->npiece];
    /* the innermost piece even (no odd terms): its two cells are one */
    const double *c0 = d->c[0];
    if (c0[1] == 0.0 && c0[3] == 0.0) {
        int m = d->npiece - 1; /* the left innermost cell, [-xb[1], 0) */
        for (int i = m + 1; i < n; i++) {
            pp->k[i] = pp->k[i + 1];
            if (i + 1 < n)
                memcpy(pp->w[i], pp->w[i + 1], sizeof pp->w[i]);
        }
        n--;
    }
    pp->ncell = n;
    pp->deg = 0;
    for (int c = 0; c < n; c++)
        for (int i = 0; i < 4; i++)
            if (pp->w[c][i] != 0.0 && i > pp->deg)
                pp->deg = i;
    double acc = 0.0;
    for (int c = 0; c < n; c++) {
        double h = pp->k[c + 1] - pp->k[c], v = 0.0;
        pp->cdf[c][0] = acc;
        for (int i = 0; i < 4; i++)
            pp->cdf[c][i + 1] = pp->w[c][i] / (i + 1);
        for (int i = 4; i >= 1; i--)
            v = (v + pp->cdf[c][i]) * h;
        acc += v;
    }
}

static inline int an_cell(const an_pp *pp, double t)
{
    int c = 0;
    while (c + 1 < pp->ncell && t >= pp->k[c + 1])
        c++;
    return c;
}

static inline double an_weight(const an_pp *pp, double t)
{
    if (!(t >= pp->k[0] && t < pp->k[pp->ncell]))
        return 0.0;
    int c = an_cell(pp, t);
    const double *a = pp->w[c];
    double s = t - pp->k[c];
    return a[0] + s * (a[1] + s * (a[2] + s * a[3]));
}

static inline double an_cdf(const an_pp *pp, double t)
{
    if (t < pp->k[0])
        return 0.0;
    if (t >= pp->k[pp->ncell])
        return 1.0;
    int c = an_cell(pp, t);
    const double *a = pp->cdf[c];
    double s = t - pp->k[c];
    return a[0] + s * (a[1] + s * (a[2] + s * (a[3] + s * a[4])));
}

/* ---- Gauss-Legendre nodes and weights ---- */

static void gauss_make(an_state *S)
{
    for (int m = 1; m <= AN_MAX_GAUSS; m++)
        for (int i = 0; i < m; i++) {
            long double x = cosl(3.14159265358979323846264338327950288L * (i + 0.75L) /
                                 (m + 0.5L)),
                        dp = 1.0L;
            for (int it = 0; it < 100; it++) {
                long double p0 = 1.0L, p1 = x;
                for (int k = 2; k <= m; k++) {
                    long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1, p1 = p2;
                }
                dp = m * (x * p1 - p0) / (x * x - 1.0L);
                long double dx = p1 / dp;
                x -= dx;
                if (fabsl(dx) < 1e-19L)
                    break;
            }
            {
                long double p0 = 1.0L, p1 = x;
                for (int k = 2; k <= m; k++) {
                    long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                    p0 = p1, p1 = p2;
                }
                dp = m * (x * p1 - p0) / (x * x - 1.0L);
            }
            S->gx[m][i] = (double)x;
            S->gw[m][i] = (double)(2.0L / ((1.0L - x * x) * dp * dp));
        }
}

/* ---- one pixel ---- */

typedef struct an_pixel {
    const an_render *R;
    double cx, cy;
    double acc[3];
} an_pixel;

static inline int curve_degree(const aa_piece *p)
{
    return p->kind == AA_PIECE_CUBIC ? 3 : (p->kind == AA_PIECE_QUAD ? 2 : 1);
}

/* R(part) of (1): the weight right of piece p over rows [ya, yb] */
static double right_of(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                       double cy)
{
    const an_pp *pp = &S->pp;
    double ys[2 + 2 * (AN_MAX_CELLS + 1) * 3];
    int n = 0;
    ys[n++] = ya;
    ys[n++] = yb;
    for (int q = 1; q < pp->ncell; q++) {
        double yk = cy + pp->k[q], m[3];
        if (yk > ya && yk < yb)
            ys[n++] = yk;
        double xk = cx + pp->k[q];
        if (!(xk > p->xmin && xk < p->xmax)) /* the piece's extent misses the line */
            continue;
        int c = aa_piece_meet_x(p, xk, m);
        for (int r = 0; r < c; r++)
            if (m[r] > ya && m[r] < yb)
                ys[n++] = m[r];
    }
    aa__vis_sort(ys, (size_t)n);
    int m = curve_degree(p) * (pp->deg + 1);
    const double *gx = S->gx[m], *gw = S->gw[m];
    double sum = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ys[s] < ys[s + 1]))
            continue;
        double ta = ys[s] <= p->y0 ? 0.0 : aa_piece_t_at(p, ys[s]);
        double tb = ys[s + 1] >= p->y1 ? 1.0 : aa_piece_t_at(p, ys[s + 1]);
        double h = 0.5 * (tb - ta), mid = 0.5 * (ta + tb), part = 0.0;
        for (int g = 0; g < m; g++) {
            double t = mid + h * gx[g], x, y, dy;
            aa__piece_point(p, t, &x, &y, &dy);
            part += gw[g] * an_weight(pp, y - cy) * (1.0 - an_cdf(pp, x - cx)) * dy;
        }
        sum += h * part;
    }
    return sum;
}

static void an_band(void *ctx, double ya, double yb, const int *wind)
{
    an_pixel *P = ctx;
    const an_pp *pp = &P->R->S->pp;
    double wy = an_cdf(pp, yb - P->cy) - an_cdf(pp, ya - P->cy);
    if (!(wy != 0.0))
        return;
    aa_rgb c = aa_scene_colour_of(P->R->scene, wind);
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += wy * c.c[ch];
}

static void an_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                   int inside)
{
    an_pixel *P = ctx;
    (void)inside;
    double r = right_of(P->R->S, p, ya, yb, P->cx, P->cy);
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += jump[ch] * r;
}

static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const an_render *R = ctx;
    const an_pp *pp = &R->S->pp;
    aa__vis v;
    aa__vis_bind(&v, R->scene, 3, wk->own);
    an_pixel P = {R, i + 0.5, j + 0.5, {0.0, 0.0, 0.0}};
    const aa__vis_sink sink = {an_band, an_run, NULL, NULL, &P, 3, 0, 0};
    double lo = pp->k[0], hi = pp->k[pp->ncell];
    aa__vis_window(&v, wk->strip, P.cx + lo, P.cx + hi, P.cy + lo, P.cy + hi, &sink);
    for (int ch = 0; ch < 3; ch++) {
        double c = P.acc[ch];
        px[ch] = c < R->lo ? R->lo : (c > R->hi ? R->hi : c);
    }
}

static int render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                      uint64_t *samples, uint64_t *expensive)
{
    const an_render *R = ctx;
    return aa__sampler_row(wk, j, R->S->pp.k[R->S->pp.ncell], 0, shade, ctx, out, samples,
                           expensive);
}

/* ---- the method ---- */

static int analytic_check(const double *p, const aa_filter *f)
{
    an_def d;
    (void)p;
    if (an_def_of(f, &d))
        return aa_fail(AA_EINVAL,
                       "analytic integrates separable piecewise polynomial filters only (box, "
                       "tent, bspline, mitchell, catrom); %s is not one (the Gaussian and "
                       "Lanczos are not polynomials; radial polynomial filters are not done)",
                       f->type->info.name);
    return AA_OK;
}

/* The scene's pieces: lines, quadratic and cubic arcs only. */
static int scene_check(const aa_scene *s)
{
    size_t n;
    const aa_piece *p = aa_scene_pieces(s, &n);
    for (size_t i = 0; i < n; i++) {
        if (p[i].kind == AA_PIECE_CONIC)
            return aa_fail(AA_EINVAL, "elliptical arcs are not done (the closed form "
                                      "for rational quadratic curves is not implemented)");
        if (p[i].kind == AA_PIECE_OFFSET)
            return aa_fail(AA_EINVAL, "offset curves (the outlines of stroked Bezier "
                                      "arcs) are not polynomial curves: refused");
    }
    return AA_OK;
}

static int prepare(an_state *S, const aa_job *job)
{
    int st = scene_check(job->placed);
    return st ? st : aa__sampler_ready(&S->sampler, job, aa__vis_size(job->placed, 3));
}

static int analytic_init(void *state, const double *p, const aa_job *job)
{
    an_state *S = state;
    an_def d;
    int st = analytic_check(p, &job->filter);
    if (st)
        return st;
    an_def_of(&job->filter, &d);
    an_pp_make(&d, &S->pp);
    gauss_make(S);
    return prepare(S, job);
}

static int analytic_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    an_state *S = state;
    (void)p;
    int st = prepare(S, job);
    if (st)
        return st;
    an_render R = {S, job->placed, 0.0, 1.0};
    aa_filter_range(&job->filter, &R.lo, &R.hi);
    return aa__sampler_render(&S->sampler, job, out, render_row, &R, counters);
}

static void analytic_release(void *state)
{
    an_state *S = state;
    aa__sampler_free(&S->sampler);
}

const aa_method_type aa_method_analytic = {
    {"analytic",
     "exact under piecewise polynomial filters: Green's theorem per filter cell and curve "
     "degree (Manson and Schaefer 2013)",
     analytic_params},
    sizeof(an_state),
    AA_METHOD_SOME_SCENES, /* elliptical arcs and offset curves: refused at init */
    analytic_check,
    analytic_init,
    analytic_render,
    analytic_release};
