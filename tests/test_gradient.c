/*
 * test_gradient.c: gradient paint (harness/core/scene.c,
 * aa_scene_set_gradient; patterns/README.md, "Gradients") through the
 * exact box reference (harness/truth/truth.c), the sampling methods, the
 * methods that refuse it, and the SVG reader (patterns/svgfile.c).
 *
 * Known answers, derived here and not from the code under test:
 *  - the sRGB decoding (IEC 61966-2-1) dec(v) = v / 12.92 for v <= T =
 *    0.04045, ((v + 0.055) / 1.055)^2.4 above.  Its integral over [0, 1]:
 *        Ibar = T^2 / (2 x 12.92) + (1.055 / 3.4) (1 - uT^3.4),
 *    uT = (T + 0.055) / 1.055, since d/dv (1.055/3.4) u^3.4 = u^2.4 with
 *    du/dv = 1/1.055.  A black-to-white linear gradient (encoded value
 *    the ramp t itself) from x = a to x = b across a W x H rectangle,
 *    padded, has the box reference sum H (a dec(0) + (b - a) Ibar +
 *    (W - b) dec(1)) = H ((b - a) Ibar + W - b): the box reference of a
 *    picture sums to its integral;
 *  - repeat and reflect of that ramp over whole periods: every period's
 *    integral is (its length) Ibar (reflect's second half is the first
 *    mirrored), so the sum is W H Ibar;
 *  - a gradient over a disc and an oblique gradient with three stops over
 *    a rectangle: their integrals by GSL's adaptive quadrature in two
 *    dimensions (outer rows, inner along the chord, with the gradient's
 *    colour written out here from SVG's definition), a different route
 *    from the reference's closed form along rows;
 *  - per pixel, the same two-dimensional quadrature over single pixels
 *    (1e-11);
 *  - a centred radial gradient black to white over its disc of radius r:
 *    in polar coordinates t = rho / r, so the integral is
 *    2 pi r^2 int_0^1 dec(t) t dt, the last integral by GSL's QAG here;
 *    the sampling methods (point, supersample) must converge to it, and
 *    the box reference matches it to 1e-12 relative;
 *  - a focal radial gradient (fr = 0): its circles are homothetic about
 *    the focus, so its disc's integral is the centred one's; centred ones
 *    with fr > 0 under reflect and repeat: a 1-D polar integral by GSL;
 *    single pixels by GSL in two dimensions (test_radial_reference).
 *
 * The sampling methods' images converge to the reference as their sample
 * counts grow; the methods that draw from the layers' constant colours
 * refuse the scene naming gradient paint, and `area` and `analytic`,
 * which take linear gradients, refuse this radial one naming it.
 */
#include "bench.h"
#include "core.h"
#include "path.h"
#include "patterns.h"
#include "support.h"
#include "tier.h"
#include "truth.h"

#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#define W 16
#define H 12

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) a declared subset: the stack of identical radial
 * layers with 6 layers alone (not 8 and 12), and the mixed stack with 7
 * layers alone (not 12).  Past five layers the reference folds the layers
 * one by one, whatever their number, so more layers take the same code
 * paths with other numbers (tests/README.md, "Tiers", says how that was
 * checked); the sanitizers find memory and undefined-behaviour errors
 * along the paths taken, and the plain build runs every case. */

static char dir[4096];
/* the image's size for the helpers below (pattern units to pixels) */
static int gw = W, gh = H;

static int setup(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    return support_tmpdir(dir, sizeof dir, "gradient");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* sRGB's decoding (IEC 61966-2-1), written out here. */
static double dec(double e)
{
    if (e <= 0.0)
        return 0.0;
    if (e >= 1.0)
        return 1.0;
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* sRGB's encoding (IEC 61966-2-1), written out here. */
static double enc(double l)
{
    return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1 / 2.4) - 0.055;
}

/* enc of a stop's channel, kept for the values asked last: the pictures
 * below encode the same few stops at every point their quadratures take
 * (two pow a layer and channel), and a value kept is the one enc gives
 * again, bit for bit. */
static double stop_enc(double l)
{
    enum { SLOTS = 64 };
    static uint64_t key[SLOTS];
    static double val[SLOTS];
    static unsigned char kept[SLOTS];
    union {
        double d;
        uint64_t u;
    } bits = {l};
    const unsigned k = (unsigned)((bits.u * 0x9E3779B97F4A7C15u) >> 58);
    if (!kept[k] || key[k] != bits.u)
        key[k] = bits.u, val[k] = enc(l), kept[k] = 1;
    return val[k];
}

/* Ibar = int_0^1 dec(v) dv in closed form (the opening comment). */
static double ibar(void)
{
    const double T = 0.04045, uT = (T + 0.055) / 1.055;
    return T * T / (2.0 * 12.92) + (1.055 / 3.4) * (1.0 - pow(uT, 3.4));
}

static double channel_sum(const aa_image *im, int ch)
{
    double s = 0.0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            s += aa_pixel(im, i, j)[ch];
    return s;
}

static void expect_sum(const char *what, const aa_image *im, int ch, double want, double tol)
{
    double got = channel_sum(im, ch);
    print_message("%s, channel %d: sum %.15g, independent %.15g (diff %.2g)\n", what, ch, got,
                  want, got - want);
    if (!(fabs(got - want) <= tol * fmax(1, fabs(want))))
        fail_msg("%s, channel %d: the box reference sums to %.17g, not %.17g", what, ch, got,
                 want);
}

/* ---- scenes in pattern units (the unit square is W x H pixels) ---- */

/* A rectangle [x0, x1] x [y0, y1] in pixels as a layer of the scene. */
static void rect_px(aa_scene *s, aa_rgb c, double x0, double y0, double x1, double y1)
{
    assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0 / gw, y0 / gh), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / gw, y0 / gh), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x1 / gw, y1 / gh), AA_OK);
    assert_int_equal(aa_scene_line_to(s, x0 / gw, y1 / gh), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* A disc of centre (cx, cy) and radius r in pixels. */
static void disc_px(aa_scene *s, double cx, double cy, double r)
{
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, (cx + r) / gw, cy / gh), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx / gw, cy / gh, r / gw, 0, 0, r / gh, 0, 2 * M_PI,
                                     (cx + r) / gw, cy / gh),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* A gradient whose coordinates are pixels (m: pixels to pattern units). */
static aa_gradient grad_px(int kind, int spread, const double p[6], const aa_gradient_stop *st,
                           int n)
{
    aa_gradient g = {kind, spread, {0}, {1.0 / gw, 0, 0, 1.0 / gh, 0, 0}, n, st};
    memcpy(g.p, p, sizeof g.p);
    return g;
}

static const aa_gradient_stop black_white[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                                {1.0, {{1, 1, 1}}, 1.0}};

static void reference(const aa_scene *s, int w, int h, aa_image *ref, aa_image *bound,
                      aa_truth_stats *stats)
{
    support_view v = {w, h, 0, 0, 0, NULL, 1, 1, 0};
    support_reference(s, &v, ref, bound, stats);
}

/* The largest per-pixel bound of a reference, checked against 1e-12. */
static void expect_bound(const char *what, const aa_truth_stats *stats)
{
    print_message("%s: largest bound %.2g\n", what, stats->max_bound);
    if (!(stats->max_bound <= 1e-12))
        fail_msg("%s: the reference's bound %.3g is above 1e-12", what, stats->max_bound);
}

/* Pixel (i, j) of scene s (a W x W view) alone, its reference under
 * `filter` certified: no window left to the scan, its bound within 1e-12. */
static void expect_certified(const char *what, const aa_scene *s, int i, int j,
                             const char *filter)
{
    aa_image ref, bound;
    aa_truth_stats stats;
    char name[200];
    support_reference_part(s, W, W, i, j, 1, 1, filter, &ref, &bound, &stats);
    snprintf(name, sizeof name, "%s, %s: pixel (%d, %d)", what, filter, i, j);
    print_message("%s %s\n", name, stats.scanned ? "scanned" : "certified");
    assert_int_equal(stats.scanned, 0);
    expect_bound(name, &stats);
    aa_image_free(&ref);
    aa_image_free(&bound);
}

/* ---- closed forms ---- */

/* Black to white from x = 3.25 to x = 11.5 across the whole 16 x 12
 * image, padded on both sides; horizontal and, through the gradient's
 * map, the same ramp given along y and rotated by 90 degrees. */
static void test_linear_pad(void **state)
{
    (void)state;
    const double a = 3.25, b = 11.5, want = H * ((b - a) * ibar() + (W - b));
    for (int rot = 0; rot < 2; rot++) {
        aa_scene *s = aa_scene_new((aa_rgb){{0.3, 0.1, 0.7}});
        rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
        aa_gradient g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                                (const double[6]){a, 0, b, 0, 0, 0}, black_white, 2);
        if (rot) { /* gradient (x, y) -> pixels (-y + 0, x): ramp along y in its own units */
            double p[6] = {0, -a, 0, -b, 0, 0}; /* q = (0, -X) maps to pixel X */
            g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, p, black_white, 2);
            double m[6] = {0, 1.0 / H, -1.0 / W, 0, 0, 0};
            memcpy(g.m, m, sizeof m);
        }
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        assert_true(aa_scene_has_gradients(s));
        assert_false(aa_scene_is_opaque(s));
        assert_true(aa_scene_is_grey(s) == 0); /* the background is not grey */
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, H, &ref, &bound, &stats);
        for (int ch = 0; ch < 3; ch++)
            expect_sum(rot ? "linear pad, rotated map" : "linear pad", &ref, ch, want, 1e-13);
        expect_bound("linear pad", &stats);
        /* the first column is black, the last white, exactly */
        assert_true(aa_pixel(&ref, 0, 5)[0] == 0.0 || fabs(aa_pixel(&ref, 0, 5)[0]) < 1e-15);
        assert_true(fabs(aa_pixel(&ref, W - 1, 5)[1] - 1.0) < 1e-15);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

/* Repeat and reflect over whole periods: 16 px holds 4 periods of 4 px
 * (the gradient from x = 1 to 5, so the periods start at 1, 5, 9, 13 and
 * the first and last pixels hold one period's two ends between them). */
static void test_repeat_reflect(void **state)
{
    (void)state;
    for (int spread = AA_SPREAD_REFLECT; spread <= AA_SPREAD_REPEAT; spread++) {
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
        /* slightly oblique: x from 1 to 5 and y 0.5 px down over the period */
        aa_gradient g = grad_px(AA_GRADIENT_LINEAR, spread,
                                (const double[6]){1, 0, 5, 0, 0, 0}, black_white, 2);
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, H, &ref, &bound, &stats);
        const char *what = spread == AA_SPREAD_REPEAT ? "repeat" : "reflect";
        expect_sum(what, &ref, 0, W * H * ibar(), 1e-13);
        expect_bound(what, &stats);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---- an independent 2-D integration of the picture ---- */

/* One gradient layer painting a region over an opaque background: the
 * colour at (x, y) in pixels, written out from SVG's definition (linear:
 * t the projection on P1 P2; pad, reflect, repeat; stops interpolated in
 * encoded values). */
typedef struct picture {
    double x1, y1, x2, y2;
    int spread;
    const aa_gradient_stop *stops;
    int n;
    double alpha;  /* the layer's alpha */
    double bg[3];  /* encoded background */
    int disc;      /* region: disc (cx, cy, r) or rectangle (rx0, ry0, rx1, ry1) */
    double r[4];
    int ch;
    double tau[256]; /* the t where channel ch is not smooth (picture_taus) */
    int ntau;
} picture;

/* t under SVG's spread: repeat's fraction, reflect's fold of period 2;
 * pad's t as it is (its callers clamp it or take the end stops). */
static double spread_fold(int spread, double t)
{
    if (spread == AA_SPREAD_REPEAT)
        return t - floor(t);
    if (spread == AA_SPREAD_REFLECT) {
        t = fmod(fabs(t), 2.0);
        return t > 1.0 ? 2.0 - t : t;
    }
    return t;
}

/* Where t falls among p's stops: the stop k whose colour it takes (*f < 0:
 * before the first or past the last) or, *f >= 0, the fraction f of the
 * way from stop k to k + 1; the opacity there into *opacity. */
static int stop_at(const picture *p, double t, double *f, double *opacity)
{
    t = spread_fold(p->spread, t);
    if (p->spread == AA_SPREAD_PAD)
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
    const aa_gradient_stop *s = p->stops;
    *f = -1.0;
    if (t <= s[0].offset) {
        *opacity = s[0].opacity;
        return 0;
    }
    int k = p->n - 1;
    for (int q = 0; q + 1 < p->n; q++)
        if (t < s[q + 1].offset) {
            k = q;
            break;
        }
    if (k == p->n - 1) {
        *opacity = s[k].opacity;
        return k;
    }
    *f = (t - s[k].offset) / (s[k + 1].offset - s[k].offset);
    *opacity = s[k].opacity + *f * (s[k + 1].opacity - s[k].opacity);
    return k;
}

/* Channel ch's encoded value at stop_at's k and f (0 for ch 3). */
static double stop_colour(const picture *p, int k, double f, int ch)
{
    const aa_gradient_stop *s = p->stops;
    if (ch >= 3)
        return 0;
    double c0 = stop_enc(s[k].colour.c[ch]);
    return f < 0 ? c0 : c0 + f * (stop_enc(s[k + 1].colour.c[ch]) - c0);
}

static double stop_value(const picture *p, double t, int ch, double *opacity)
{
    double f;
    int k = stop_at(p, t, &f, opacity);
    return stop_colour(p, k, f, ch);
}

static double picture_at(const picture *p, double x, double y)
{
    int in = p->disc ? hypot(x - p->r[0], y - p->r[1]) < p->r[2]
                     : (x > p->r[0] && x < p->r[2] && y > p->r[1] && y < p->r[3]);
    if (!in)
        return dec(p->bg[p->ch]);
    double dx = p->x2 - p->x1, dy = p->y2 - p->y1;
    double t = ((x - p->x1) * dx + (y - p->y1) * dy) / (dx * dx + dy * dy), op;
    double c = stop_value(p, t, p->ch, &op);
    double a = p->alpha * op;
    return dec(a * c + (1 - a) * p->bg[p->ch]);
}

typedef struct row_ctx {
    const picture *p;
    double y, xa, xb;
    gsl_integration_workspace *wi;
} row_ctx;

static double along_x(double x, void *v)
{
    const row_ctx *c = v;
    return picture_at(c->p, x, c->y);
}

/* The integral of a row y over [xa, xb], split where the region's side
 * is (the disc's chord ends, the rectangle's sides). */
static double along_y(double y, void *v)
{
    row_ctx *c = v;
    c->y = y;
    double cut[4], res, err, sum = 0;
    int n = 0;
    cut[n++] = c->xa;
    (void)cut;
    double lo, hi;
    if (c->p->disc) {
        double h = c->p->r[2] * c->p->r[2] - (y - c->p->r[1]) * (y - c->p->r[1]);
        lo = h > 0 ? c->p->r[0] - sqrt(h) : c->xa, hi = h > 0 ? c->p->r[0] + sqrt(h) : c->xa;
    } else
        lo = c->p->r[0], hi = c->p->r[2];
    if (lo > c->xa && lo < c->xb)
        cut[n++] = lo;
    if (hi > cut[n - 1] && hi < c->xb)
        cut[n++] = hi;
    cut[n++] = c->xb;
    /* and where t passes a value of p->tau along the row */
    const picture *p = c->p;
    double dx = p->x2 - p->x1, dy = p->y2 - p->y1, l2 = dx * dx + dy * dy;
    double all[300];
    int na = 0;
    for (int q = 0; q < p->ntau && dx != 0; q++) {
        double x = p->x1 + (p->tau[q] * l2 - (y - p->y1) * dy) / dx;
        if (x > c->xa && x < c->xb)
            all[na++] = x;
    }
    for (int k = 0; k < n - 1; k++)
        all[na++] = cut[k + 1];
    qsort(all, (size_t)na, sizeof *all, cmp_double);
    double xs[300];
    int m = 0;
    xs[m++] = c->xa;
    for (int k = 0; k < na; k++)
        if (all[k] > xs[m - 1] && all[k] <= c->xb)
            xs[m++] = all[k];
    gsl_function F = {along_x, c};
    for (int k = 0; k + 1 < m; k++) {
        gsl_integration_qag(&F, xs[k], xs[k + 1], 1e-15, 1e-14, 1000, GSL_INTEG_GAUSS21, c->wi,
                            &res, &err);
        sum += res;
    }
    return sum;
}

/* The values of t in periods -4 .. 4 where channel p->ch of the picture
 * is not smooth: each stop's offset, mirrored for reflect, and where the
 * composite crosses the decoding's threshold 0.04045 inside a stop's
 * segment. */
static void picture_taus(picture *p)
{
    double o[64];
    int no = 0;
    for (int q = 0; q < p->n; q++)
        o[no++] = p->stops[q].offset;
    for (int q = 0; q + 1 < p->n; q++) {
        double op, c0 = stop_value(p, p->stops[q].offset, p->ch, &op);
        double a = p->alpha * op;
        double mid = stop_value(p, 0.5 * (p->stops[q].offset + p->stops[q + 1].offset), p->ch,
                                &op);
        double c1 = 2 * mid - c0; /* the segment's far end, linear */
        if (c1 == c0)
            continue;
        double f = ((0.04045 - (1 - a) * p->bg[p->ch]) / a - c0) / (c1 - c0);
        if (f > 0 && f < 1)
            o[no++] = p->stops[q].offset + f * (p->stops[q + 1].offset - p->stops[q].offset);
    }
    p->ntau = 0;
    for (int per = -4; per <= 4; per++)
        for (int q = 0; q < no; q++) {
            p->tau[p->ntau++] = per + o[q];
            if (p->spread == AA_SPREAD_REFLECT)
                p->tau[p->ntau++] = per + 1 - o[q];
        }
}

/* The integral of the picture over [xa, xb] x [ya, yb], rows split at the
 * given heights. */
static double integrate2d(const picture *p, double xa, double xb, double ya, double yb,
                          const double *ycut, int ncut)
{
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    row_ctx c = {p, 0, xa, xb, gsl_integration_workspace_alloc(1000)};
    gsl_function F = {along_y, &c};
    /* rows also split where a line t = tau (a stop's offset in some
     * period, or where the composite crosses the decoding's threshold)
     * crosses a side of the region or of [xa, xb]: the row integral has a
     * kink there */
    double cut[1200], res, err, sum = 0, all[1200];
    int n = 0, na = 0;
    for (int k = 0; k < ncut; k++)
        all[na++] = ycut[k];
    double dx = p->x2 - p->x1, dy = p->y2 - p->y1, l2 = dx * dx + dy * dy;
    double X[4] = {xa, xb, p->disc ? xa : p->r[0], p->disc ? xb : p->r[2]};
    for (int q = 0; q < p->ntau && dy != 0; q++)
        for (int k = 0; k < 4 && na < 1190; k++)
            all[na++] = p->y1 + (p->tau[q] * l2 - (X[k] - p->x1) * dx) / dy;
    qsort(all, (size_t)na, sizeof *all, cmp_double);
    cut[n++] = ya;
    for (int k = 0; k < na; k++)
        if (all[k] > cut[n - 1] && all[k] < yb)
            cut[n++] = all[k];
    cut[n++] = yb;
    for (int k = 0; k + 1 < n; k++) {
        gsl_integration_qag(&F, cut[k], cut[k + 1], 1e-14, 1e-13, 1000, GSL_INTEG_GAUSS21, wo,
                            &res, &err);
        sum += res;
    }
    gsl_integration_workspace_free(c.wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

static const aa_gradient_stop three[3] = {{0.0, {{1, 0, 0}}, 1.0},
                                          {0.4, {{0.2, 0.9, 0.1}}, 1.0},
                                          {1.0, {{0, 0.05, 1}}, 1.0}};

/* A gradient on a disc over a grey background, and an oblique one with
 * three stops (one of them sharp) and alpha 0.6 on a rectangle: the box
 * reference sums to the 2-D integral, and a few pixels (a disc's edge, a
 * stop's line) match the 2-D integral over the pixel. */
static void test_against_2d(void **state)
{
    (void)state;
    const double bgl = 0.2, bge = 1.055 * pow(bgl, 1 / 2.4) - 0.055;
    for (int which = 0; which < 2; which++) {
        aa_scene *s = aa_scene_new((aa_rgb){{bgl, bgl, bgl}});
        picture p = {0};
        p.bg[0] = p.bg[1] = p.bg[2] = bge;
        p.alpha = 1;
        if (!which) {
            disc_px(s, 8.3, 6.1, 5.2);
            p.disc = 1, p.r[0] = 8.3, p.r[1] = 6.1, p.r[2] = 5.2;
            p.x1 = 3.1, p.y1 = 2.0, p.x2 = 13.4, p.y2 = 9.7;
            p.spread = AA_SPREAD_PAD, p.stops = black_white, p.n = 2;
        } else {
            rect_px(s, (aa_rgb){{0, 0, 0}}, 1.5, 2.25, 14.75, 10.5);
            assert_int_equal(aa_scene_set_alpha(s, 0.6), AA_OK);
            p.r[0] = 1.5, p.r[1] = 2.25, p.r[2] = 14.75, p.r[3] = 10.5;
            p.x1 = 2.0, p.y1 = 9.0, p.x2 = 9.0, p.y2 = 4.5;
            p.spread = AA_SPREAD_REFLECT, p.stops = three, p.n = 3, p.alpha = 0.6;
        }
        aa_gradient g = grad_px(AA_GRADIENT_LINEAR, p.spread,
                                (const double[6]){p.x1, p.y1, p.x2, p.y2, 0, 0}, p.stops, p.n);
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, H, &ref, &bound, &stats);
        expect_bound(which ? "three stops, reflect" : "disc", &stats);
        double ycut[2] = {which ? 2.25 : 6.1 - 5.2, which ? 10.5 : 6.1 + 5.2};
        for (int ch = 0; ch < 3; ch++) {
            p.ch = ch;
            picture_taus(&p);
            double want = integrate2d(&p, 0, W, 0, H, ycut, 2);
            expect_sum(which ? "three stops, reflect" : "disc", &ref, ch, want, 1e-11);
        }
        static const int pix[4][2] = {{3, 6}, {8, 1}, {6, 7}, {12, 3}};
        for (int k = 0; k < 4; k++) {
            int i = pix[k][0], j = pix[k][1];
            for (int ch = 0; ch < 3; ch++) {
                p.ch = ch;
            picture_taus(&p);
                /* rows split also where the disc's rim crosses the pixel's
                 * sides (the row integral has a kink there) */
                double cuts[6] = {ycut[0], ycut[1]};
                int nc = 2;
                for (int side = 0; p.disc && side < 2; side++) {
                    double dx = i + side - p.r[0], h = p.r[2] * p.r[2] - dx * dx;
                    if (h > 0)
                        cuts[nc++] = p.r[1] - sqrt(h), cuts[nc++] = p.r[1] + sqrt(h);
                }
                qsort(cuts, (size_t)nc, sizeof *cuts, cmp_double);
                double want = integrate2d(&p, i, i + 1, j, j + 1, cuts, nc);
                double got = aa_pixel(&ref, i, j)[ch];
                if (!(fabs(got - want) <= 1e-11))
                    fail_msg("pixel (%d, %d) channel %d: %.17g, 2-D quadrature %.17g", i, j, ch,
                             got, want);
            }
        }
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

/* ---- methods ---- */

/* The sampling methods converge to the reference: supersample n = 2, 4,
 * 8, 16 on the disc's gradient; each error below the last, the last
 * below 3e-3; point sampling and jitter run; the methods drawing from the
 * layers' colours refuse, naming gradient paint. */
static void test_methods(void **state)
{
    (void)state;
    gw = gh = W;
    aa_scene *s = aa_scene_new((aa_rgb){{0.2, 0.2, 0.2}});
    disc_px(s, 8.3, 6.1, 5.2);
    aa_gradient g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_REPEAT,
                            (const double[6]){3.1, 2.0, 7.4, 5.7, 0, 0}, three, 3);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image ref;
    aa_truth_stats stats;
    reference(s, W, W, &ref, NULL, &stats);
    double last = INFINITY;
    for (int n = 2; n <= 16; n *= 2) {
        char spec[64];
        snprintf(spec, sizeof spec, "supersample:n=%d", n);
        aa_image im;
        support_render(spec, s, NULL, W, W, 1, &im, NULL);
        double e = support_rmse(&im, &ref);
        print_message("%s: rmse %.3g\n", spec, e);
        assert_true(e < last);
        last = e;
        aa_image_free(&im);
    }
    assert_true(last < 3e-3);
    aa_image im;
    support_render("point", s, NULL, W, W, 1, &im, NULL);
    /* a point sample at a centre inside the disc is the picture there */
    int wind[1] = {1};
    aa_scene *placed = aa_scene_place(s, W, W, 0, 0, 0);
    aa_rgb c = aa_scene_colour_of_at(placed, wind, 8.5, 6.5);
    for (int ch = 0; ch < 3; ch++)
        assert_true(fabs(aa_pixel(&im, 8, 6)[ch] - c.c[ch]) < 1e-15);
    aa_scene_free(placed);
    aa_image_free(&im);
    support_render("jitter:spp=64", s, NULL, W, W, 1, &im, NULL);
    assert_true(support_rmse(&im, &ref) < 2e-2);
    aa_image_free(&im);
    static const char *const refusing[] = {"area", "analytic", "crowtiler", "trio", "fxaa"};
    for (size_t k = 0; k < sizeof refusing / sizeof *refusing; k++) {
        support_view v = {W, W, 0, 0, 0, k == 2 ? "tent:r=1" : NULL, 1, 1, 0};
        int st = support_render_view(refusing[k], s, &v, &im, NULL);
        print_message("%s: %s\n", refusing[k], aa_last_error());
        assert_int_equal(st, AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "gradient"));
    }
    aa_image_free(&ref);
    aa_scene_free(s);
    gw = W, gh = H;
}

/* What the reference and the model refuse, each naming why. */
static void test_refusals(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
    aa_gradient g = grad_px(AA_GRADIENT_RADIAL, AA_SPREAD_PAD,
                            (const double[6]){8, 6, 5, 14, 6, 0}, black_white, 2);
    /* the focal circle the end circle: SVG 2 paints nothing */
    g.p[3] = 8, g.p[5] = 5;
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "end circle"));
    g.p[3] = 9, g.p[5] = 0;
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    aa_scene_free(s);
    /* more than 32 gradient layers painting one point (the reference folds
     * at most that many a span), of varying opacity (linear ones of
     * constant opacity take the closed form, however many) */
    static const aa_gradient_stop fade[2] = {{0.0, {{0, 0, 0}}, 1.0}, {1.0, {{1, 1, 1}}, 0.5}};
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    for (int k = 0; k < 33; k++) {
        rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
        aa_gradient lin = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                                  (const double[6]){0.25 * k, 0, 0.25 * k + 5, 1, 0, 0}, fade, 2);
        assert_int_equal(aa_scene_set_gradient(s, &lin), AA_OK);
        assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
    aa_image out;
    assert_int_equal(aa_image_alloc(&out, W, H, 3), AA_OK);
    aa_filter f;
    aa_filter_default(&f);
    assert_int_equal(aa_truth_render(placed, &f, 1, &out, NULL, NULL), AA_EINVAL);
    print_message("33 gradients: %s\n", aa_last_error());
    assert_non_null(strstr(aa_last_error(), "more than 32 gradient layers"));
    aa_scene_free(placed);
    aa_scene_free(s);
    /* more than 4096 pieces near a pixel of gradient paint (the sum over
     * spans costs every piece at each height): a polygon of 4100 sides
     * inside pixel (3, 3); the radial filters and crowded windows of
     * fewer pieces: tests/test_gradient_radial_filter.c,
     * test_gradient_crowd.c */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < 4100; k++) {
        double a = 2.0 * M_PI * k / 4100, x = (3.5 + 0.4 * cos(a)) / W, y = (3.5 + 0.4 * sin(a)) / H;
        assert_int_equal(k ? aa_scene_line_to(s, x, y) : aa_scene_move_to(s, x, y), AA_OK);
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
    g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){0, 0, 5, 0, 0, 0},
                black_white, 2);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    placed = aa_scene_place(s, W, H, 0, 0, 0);
    aa_filter_default(&f);
    assert_int_equal(aa_truth_render(placed, &f, 1, &out, NULL, NULL), AA_EINVAL);
    print_message("4100 pieces: %s\n", aa_last_error());
    assert_non_null(strstr(aa_last_error(), "more than 4096"));
    aa_scene_free(placed);
    aa_scene_free(s);
    aa_image_free(&out);
    /* bad gradients: stops out of order, none, a zero-length vector */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
    aa_gradient_stop bad[2] = {{0.6, {{0, 0, 0}}, 1}, {0.2, {{1, 1, 1}}, 1}};
    g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){0, 0, 5, 0, 0, 0}, bad, 2);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_EINVAL);
    g.nstops = 0;
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_EINVAL);
    g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD, (const double[6]){2, 2, 2, 2, 0, 0},
                black_white, 2);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_EINVAL);
    aa_scene_free(s);
}

/* A centred radial gradient over its disc, sampled: in polar coordinates
 * the integral is 2 pi r^2 int_0^1 dec(t) t dt (GSL here), plus the
 * background outside.  supersample:n=16's image sums to it within the
 * edge's sampling error. */
static double dec_t(double t, void *v)
{
    (void)v;
    return dec(t) * t;
}

static void test_radial_sampled(void **state)
{
    (void)state;
    gw = gh = W;
    const double r = 6.0;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    disc_px(s, 8, 8, r);
    aa_gradient g = grad_px(AA_GRADIENT_RADIAL, AA_SPREAD_PAD,
                            (const double[6]){8, 8, r, 8, 8, 0}, black_white, 2);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
    gsl_function F = {dec_t, NULL};
    double I, err;
    gsl_integration_qag(&F, 0, 1, 1e-15, 1e-14, 100, GSL_INTEG_GAUSS21, ws, &I, &err);
    gsl_integration_workspace_free(ws);
    const double want = 2 * M_PI * r * r * I;
    aa_image im;
    support_render("supersample:n=64", s, NULL, W, W, 1, &im, NULL);
    double got = channel_sum(&im, 1);
    print_message("radial: supersample n=64 sums to %.6f, polar integral %.6f\n", got, want);
    assert_true(fabs(got - want) < 0.02);
    /* the focal point moved: t = 0 there, 1 on the circle of radius r */
    aa_image_free(&im);
    aa_scene_free(s);
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    disc_px(s, 8, 8, r);
    g.p[3] = 10, g.p[4] = 7;
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_scene *placed = aa_scene_place(s, W, W, 0, 0, 0);
    int wind[1] = {1};
    aa_rgb at_focus = aa_scene_colour_of_at(placed, wind, 10, 7);
    assert_true(at_focus.c[0] < 1e-15);
    /* on the end circle, toward the focal point's side and away from it */
    aa_rgb rim = aa_scene_colour_of_at(placed, wind, 8 + r * 0.999999, 8);
    assert_true(rim.c[0] > 0.9999);
    /* halfway along the ray from F to the rim point (8 - r, 8): t = 1/2 */
    aa_rgb half = aa_scene_colour_of_at(placed, wind, 0.5 * (10 + 8 - r), 0.5 * (7 + 8));
    assert_true(fabs(half.c[0] - dec(0.5)) < 1e-14);
    aa_scene_free(placed);
    aa_scene_free(s);
    gw = W, gh = H;
}

/* ---- the SVG reader ---- */

/* `body` inside a root <svg> of W x H pixels over black, written to a file
 * of the temporary folder; its pattern spec into spec. */
static void svg_spec(const char *name, const char *body, char *spec, size_t len)
{
    char path[4200], doc[8192];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    snprintf(doc, sizeof doc,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" "
             "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" height=\"%d\">\n%s\n"
             "</svg>\n",
             W, H, body);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, len, "svg:file=%s", path);
}

/* The pattern's scene of body, or NULL with the status in *st. */
static aa_scene *svg_scene(const char *name, const char *body, int *st)
{
    char spec[4400];
    svg_spec(name, body, spec, sizeof spec);
    aa_spec sp;
    aa_scene *sc = NULL;
    *st = aa_pattern_parse(spec, &sp);
    if (!*st)
        *st = aa_pattern_scene_at(&sp, W, H, &sc);
    return *st ? NULL : sc;
}

static void svg_box(const char *name, const char *body, aa_image *ref)
{
    int st;
    aa_scene *sc = svg_scene(name, body, &st);
    if (!sc)
        fail_msg("%s: %s", body, aa_last_error());
    aa_truth_stats stats;
    reference(sc, W, H, ref, NULL, &stats);
    expect_bound(name, &stats);
    aa_scene_free(sc);
}

static void svg_refused(const char *body, const char *where, const char *why)
{
    int st;
    aa_scene *sc = svg_scene("refused", body, &st);
    if (sc)
        fail_msg("%s: read, not refused", body);
    print_message("refused: %s\n", aa_last_error());
    assert_int_equal(st, AA_EINVAL);
    if (!strstr(aa_last_error(), where) || !strstr(aa_last_error(), why))
        fail_msg("%s: the message \"%s\" does not name %s and %s", body, aa_last_error(),
                 where, why);
}

/* A whole-view rectangle painted from x = 3.25 to 11.5 (userSpaceOnUse,
 * or objectBoundingBox fractions of it) black to white: the box sum of
 * test_linear_pad, whichever way the document says it: stop colours by
 * attribute, style and sheet; offsets as percentages, clamped; href and
 * xlink:href inheriting stops and attributes; a gradientTransform. */
static void test_svg_linear(void **state)
{
    (void)state;
    const double a = 3.25, b = 11.5, want = H * ((b - a) * ibar() + (W - b));
    static const char *const docs[] = {
        "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"3.25\" x2=\"11.5\">"
        "<stop offset=\"0\" stop-color=\"black\"/><stop offset=\"1\" stop-color=\"white\"/>"
        "</linearGradient><rect width=\"16\" height=\"12\" fill=\"url(#g)\"/>",
        /* fractions of the box, percent offsets clamped, style and sheet */
        "<style>.w { stop-color: #fff }</style>"
        "<linearGradient id=\"g\" x1=\"0.203125\" x2=\"71.875%\">"
        "<stop offset=\"-20%\" style=\"stop-color: black\"/><stop class=\"w\" offset=\"3\"/>"
        "</linearGradient><rect width=\"16\" height=\"12\" fill=\"url('#g')\"/>",
        /* stops from the gradient named by href, its vector from xlink:href's */
        "<linearGradient id=\"s\"><stop offset=\"0\"/><stop offset=\"1\" stop-color=\"white\"/>"
        "</linearGradient><linearGradient id=\"v\" xlink:href=\"#s\" "
        "gradientUnits=\"userSpaceOnUse\" x1=\"3.25\" x2=\"11.5\"/>"
        "<linearGradient id=\"g\" href=\"#v\"/><rect width=\"16\" height=\"12\" "
        "fill=\"url(#g) red\"/>",
        /* the vector (0, 0) to (8.25, 0) moved by the gradient's transform */
        "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x2=\"8.25\" "
        "gradientTransform=\"translate(3.25 7)\"><stop offset=\"0\"/>"
        "<stop offset=\"1\" stop-color=\"white\"/></linearGradient>"
        "<rect width=\"16\" height=\"12\" fill=\"url(#g)\"/>",
    };
    for (size_t k = 0; k < sizeof docs / sizeof *docs; k++) {
        aa_image ref;
        svg_box("linear", docs[k], &ref);
        expect_sum(docs[k], &ref, 1, want, 1e-13);
        aa_image_free(&ref);
    }
}

/* Offsets raised to the largest before them: stops black at 0, white at
 * 0.8, red at 0.3 (read as 0.8): black to white over t in [0, 0.8], then
 * red (a sharp step, then pad).  With t = (x - a) / (b - a) the ramp
 * covers x in [a, a + 0.8 (b - a)]: red's channel sums to H (0.8 (b - a)
 * Ibar + W - a - 0.8 (b - a)), green's to H 0.8 (b - a) Ibar. */
static void test_svg_monotone(void **state)
{
    (void)state;
    const double a = 3.25, b = 11.5, r = 0.8 * (b - a);
    aa_image ref;
    svg_box("monotone",
            "<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\" x1=\"3.25\" x2=\"11.5\">"
            "<stop offset=\"0\" stop-color=\"black\"/><stop offset=\"0.8\" stop-color=\"white\"/>"
            "<stop offset=\"0.3\" stop-color=\"red\"/></linearGradient>"
            "<rect width=\"16\" height=\"12\" fill=\"url(#g)\"/>",
            &ref);
    expect_sum("monotone offsets", &ref, 0, H * (r * ibar() + W - a - r), 1e-13);
    expect_sum("monotone offsets", &ref, 1, H * r * ibar(), 1e-13);
    aa_image_free(&ref);
}

/* What paints a colour or nothing: a fallback colour for a missing id,
 * one stop (its colour and opacity), no stops (none), objectBoundingBox
 * on a horizontal line's stroke (a box of no height: none), the same in
 * userSpaceOnUse (drawn: a 12 x 2 stroke, white throughout). */
static void test_svg_degenerate(void **state)
{
    (void)state;
    static const struct {
        const char *body;
        double sum; /* of channel 1 */
    } cases[] = {
        {"<rect x=\"2\" y=\"2\" width=\"8\" height=\"4\" fill=\"url(#none) white\"/>", 32},
        {"<linearGradient id=\"g\"><stop stop-color=\"white\" stop-opacity=\"0.5\"/>"
         "</linearGradient><rect x=\"2\" y=\"2\" width=\"8\" height=\"4\" fill=\"url(#g)\"/>",
         -32},
        {"<linearGradient id=\"g\"/><rect x=\"2\" y=\"2\" width=\"8\" height=\"4\" "
         "fill=\"url(#g) white\"/>",
         0},
        {"<linearGradient id=\"g\"><stop stop-color=\"white\"/><stop offset=\"1\" "
         "stop-color=\"white\"/></linearGradient><line x1=\"2\" y1=\"6\" x2=\"14\" y2=\"6\" "
         "stroke=\"url(#g)\" stroke-width=\"2\"/>",
         0},
        {"<linearGradient id=\"g\" gradientUnits=\"userSpaceOnUse\"><stop "
         "stop-color=\"white\"/><stop offset=\"1\" stop-color=\"white\"/></linearGradient>"
         "<line x1=\"2\" y1=\"6\" x2=\"14\" y2=\"6\" stroke=\"url(#g)\" stroke-width=\"2\"/>",
         24},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        aa_image ref;
        svg_box("degenerate", cases[k].body, &ref);
        /* -32: 32 pixels of white at 0.5 over black, decoded */
        double want = cases[k].sum >= 0 ? cases[k].sum : 32 * dec(0.5);
        expect_sum(cases[k].body, &ref, 1, want, 1e-13);
        aa_image_free(&ref);
    }
}

/* What the reader refuses, naming the element and its line. */
static void test_svg_refusals(void **state)
{
    (void)state;
    svg_refused("<linearGradient id=\"a\" href=\"#b\"/><linearGradient id=\"b\" href=\"#a\"/>"
                "<rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "line 2: <linearGradient>", "cycle");
    /* the focal circle the end circle (fr = r = 50%): SVG 2 paints nothing
     * (the cone case, fx outside, is read: test_gradient_cone) */
    svg_refused("<radialGradient id=\"a\" fr=\"0.5\"><stop/><stop offset=\"1\"/>"
                "</radialGradient><rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "<radialGradient>", "is the end circle");
    svg_refused("<linearGradient id=\"a\" spreadMethod=\"mirror\"><stop/></linearGradient>"
                "<rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "<linearGradient>", "spreadMethod");
    svg_refused("<linearGradient id=\"a\" x1=\"2px\"><stop/><stop offset=\"1\"/>"
                "</linearGradient><rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "<linearGradient>", "objectBoundingBox");
    svg_refused("<linearGradient id=\"a\"><stop/><rect/></linearGradient>"
                "<rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "<rect>", "only <stop>");
    svg_refused("<linearGradient id=\"a\"><stop offset=\"0\" stop-colour=\"red\"/>"
                "</linearGradient><rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                "<stop>", "stop-colour");
    /* color-interpolation on the gradient: the nearest value given
     * decides, and sRGB under a linearRGB <defs> reads (linearRGB itself:
     * test_gradient_linrgb.c) */
    {
        int st0;
        aa_scene *s0 = svg_scene("interp-srgb",
                                 "<defs color-interpolation=\"linearRGB\"><linearGradient "
                                 "id=\"a\" color-interpolation=\"sRGB\"><stop/><stop "
                                 "offset=\"1\" stop-color=\"white\"/></linearGradient></defs>"
                                 "<rect width=\"4\" height=\"4\" fill=\"url(#a)\"/>",
                                 &st0);
        if (!s0)
            fail_msg("sRGB under a linearRGB <defs>: %s", aa_last_error());
        aa_scene_free(s0);
    }
    /* a radial gradient is read, and the reference integrates it: the
     * bounding box's circle (centre (4, 4), radius 4) black to white, then
     * white (pad) over the rest of the 8 x 8 square: 2 pi 16 int_0^1 dec(t)
     * t dt + 64 - 16 pi (dec_t, GSL) */
    int st;
    aa_scene *sc = svg_scene("radial", "<radialGradient id=\"a\"><stop/><stop offset=\"1\" "
                                       "stop-color=\"white\"/></radialGradient>"
                                       "<rect width=\"8\" height=\"8\" fill=\"url(#a)\"/>",
                             &st);
    assert_non_null(sc);
    aa_scene *placed = aa_scene_place(sc, W, H, 0, 0, 0);
    aa_image out;
    assert_int_equal(aa_image_alloc(&out, W, H, 3), AA_OK);
    aa_filter f;
    aa_filter_default(&f);
    assert_int_equal(aa_truth_render(placed, &f, 1, &out, NULL, NULL), AA_OK);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
    gsl_function F = {dec_t, NULL};
    double I, err, sum = 0;
    gsl_integration_qag(&F, 0, 1, 1e-15, 1e-14, 100, GSL_INTEG_GAUSS21, ws, &I, &err);
    gsl_integration_workspace_free(ws);
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++)
            sum += aa_pixel(&out, i, j)[1];
    double want = 32 * M_PI * I + 64 - 16 * M_PI;
    print_message("svg radial: the square sums to %.15g, independent %.15g\n", sum, want);
    assert_true(fabs(sum - want) < 1e-12 * want);
    aa_image_free(&out);
    aa_scene_free(placed);
    aa_scene_free(sc);
}

/* ---- radial gradients through the box reference ---- */

/* A radial gradient over a disc of the scene, written out from SVG 2's
 * definition: t is the largest w with |q - F - w D| = fr + w dr (D = C -
 * F, dr = r - fr); squared, A w^2 - 2 B w - E = 0 with A = dr^2 - D.D > 0
 * (the focal circle inside the end circle), B = -(q - F).D - fr dr, E =
 * |q - F|^2 - fr^2, whose larger root is (B + S) / A = E / (S - B), S =
 * sqrt(B^2 + A E), taken in the form that does not cancel; spread and
 * stops as SVG says. */
typedef struct rpic {
    double disc[3];      /* the disc painted: centre, radius */
    double c[2], r, f[2], fr;
    int spread, n, ch;
    const aa_gradient_stop *stops;
} rpic;

static double rpic_t(const rpic *p, double x, double y)
{
    double qx = x - p->f[0], qy = y - p->f[1], Dx = p->c[0] - p->f[0], Dy = p->c[1] - p->f[1];
    double dr = p->r - p->fr, A = dr * dr - (Dx * Dx + Dy * Dy);
    double B = -(qx * Dx + qy * Dy) - p->fr * dr, E = qx * qx + qy * qy - p->fr * p->fr;
    double sq = sqrt(fmax(B * B + A * E, 0));
    return B < 0 ? E / (sq - B) : (B + sq) / A;
}

static double rpic_colour(const rpic *p, double t)
{
    if (p->spread == AA_SPREAD_REPEAT)
        t -= floor(t);
    else if (p->spread == AA_SPREAD_REFLECT)
        t = fabs(t - 2 * floor(t / 2 + 0.5));
    else
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
    const aa_gradient_stop *s = p->stops;
    if (t < s[0].offset)
        return dec(stop_enc(s[0].colour.c[p->ch]));
    for (int k = p->n - 1; k > 0; k--)
        if (t >= s[k - 1].offset && t < s[k].offset) {
            double f = (t - s[k - 1].offset) / (s[k].offset - s[k - 1].offset);
            double a = stop_enc(s[k - 1].colour.c[p->ch]), b = stop_enc(s[k].colour.c[p->ch]);
            return dec(a + f * (b - a));
        }
    return dec(stop_enc(s[p->n - 1].colour.c[p->ch]));
}

static double rpic_at(const rpic *p, double x, double y)
{
    if (hypot(x - p->disc[0], y - p->disc[1]) >= p->disc[2])
        return 0; /* the black background */
    return rpic_colour(p, rpic_t(p, x, y));
}

/* The values of t where the picture's channel is not smooth, in periods
 * -1 .. 8: stops, periods' ends, and where the encoded value passes the
 * decoding's threshold 0.04045 on a stop's segment. */
static int rpic_taus(const rpic *p, double *tau)
{
    double o[32];
    int no = 0, n = 0;
    for (int k = 0; k < p->n; k++) {
        o[no++] = p->stops[k].offset;
        if (k + 1 < p->n) {
            double a = enc(p->stops[k].colour.c[p->ch]), b = enc(p->stops[k + 1].colour.c[p->ch]);
            double f = (0.04045 - a) / (b - a);
            if (a != b && f > 0 && f < 1)
                o[no++] = p->stops[k].offset + f * (p->stops[k + 1].offset - p->stops[k].offset);
        }
    }
    o[no++] = 1.0;
    for (int per = -1; per <= 8; per++)
        for (int k = 0; k < no; k++) {
            if (p->spread == AA_SPREAD_PAD && per != 0)
                continue;
            tau[n++] = per + o[k];
            if (p->spread == AA_SPREAD_REFLECT)
                tau[n++] = per + 1 - o[k];
        }
    return n;
}

typedef struct rrow {
    const rpic *p;
    double y, xa, xb;
    gsl_integration_workspace *wi;
} rrow;

static double rrow_x(double x, void *v)
{
    const rrow *c = v;
    return rpic_at(c->p, x, c->y);
}

/* Where t = tau on [a, b] of row y, t monotone there: bisection. */
static double rrow_bisect(const rpic *p, double y, double a, double b, double tau)
{
    double ta = rpic_t(p, a, y) - tau;
    for (int it = 0; it < 200; it++) {
        double m = 0.5 * (a + b);
        if (m <= a || m >= b)
            break;
        double tm = rpic_t(p, m, y) - tau;
        if ((tm < 0) == (ta < 0))
            a = m, ta = tm;
        else
            b = m;
    }
    return 0.5 * (a + b);
}

static double rrow_y(double y, void *v)
{
    rrow *c = v;
    c->y = y;
    const rpic *p = c->p;
    double xs[200];
    int n = 0;
    xs[n++] = c->xa;
    double h = p->disc[2] * p->disc[2] - (y - p->disc[1]) * (y - p->disc[1]);
    if (h > 0) {
        xs[n++] = p->disc[0] - sqrt(h);
        xs[n++] = p->disc[0] + sqrt(h);
    }
    /* t's least point on the row (golden section: t is quasiconvex), and
     * on each side of it where t passes each tau */
    double a = c->xa - 1, b = c->xb + 1, g = (3 - sqrt(5)) / 2;
    for (int it = 0; it < 200 && b - a > 1e-15; it++) {
        double u = a + g * (b - a), w = b - g * (b - a);
        if (rpic_t(p, u, y) <= rpic_t(p, w, y))
            b = w;
        else
            a = u;
    }
    double xm = 0.5 * (a + b), tau[400];
    xs[n++] = xm;
    int nt = rpic_taus(p, tau);
    for (int k = 0; k < nt && n < 196; k++) {
        if ((rpic_t(p, c->xa, y) - tau[k]) * (rpic_t(p, xm, y) - tau[k]) < 0)
            xs[n++] = rrow_bisect(p, y, c->xa, xm, tau[k]);
        if ((rpic_t(p, c->xb, y) - tau[k]) * (rpic_t(p, xm, y) - tau[k]) < 0)
            xs[n++] = rrow_bisect(p, y, xm, c->xb, tau[k]);
    }
    xs[n++] = c->xb;
    qsort(xs, (size_t)n, sizeof *xs, cmp_double);
    gsl_function F = {rrow_x, c};
    double sum = 0, res, err;
    for (int k = 0; k + 1 < n; k++) {
        double lo = fmax(xs[k], c->xa), hi = fmin(xs[k + 1], c->xb);
        if (!(hi > lo))
            continue;
        gsl_integration_qag(&F, lo, hi, 1e-16, 1e-14, 1000, GSL_INTEG_GAUSS21, c->wi, &res,
                            &err);
        sum += res;
    }
    return sum;
}

/* The integral of the picture's channel over the pixel (i, j) by GSL in
 * two dimensions: rows split at the row of the circles' common point, and
 * at the disc's and each circle t = tau's (centre F + tau D, radius fr +
 * tau dr) top and bottom and crossings of the pixel's sides. */
static double rpic_pixel(const rpic *p, int i, int j)
{
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    rrow c = {p, 0, i, i + 1, gsl_integration_workspace_alloc(1000)};
    gsl_function F = {rrow_y, &c};
    double ys[2500], tau[400], dr = p->r - p->fr;
    int n = 0, nt = rpic_taus(p, tau);
    ys[n++] = j;
    ys[n++] = j + 1;
    ys[n++] = p->disc[1] - p->disc[2];
    ys[n++] = p->disc[1] + p->disc[2];
    ys[n++] = p->f[1] - p->fr / dr * (p->c[1] - p->f[1]);
    for (int k = 0; k <= nt; k++) {
        /* each circle (the disc's last): its top and bottom, and where it
         * crosses the pixel's sides x = i, i + 1 */
        double rad = k < nt ? p->fr + tau[k] * dr : p->disc[2];
        double cy = k < nt ? p->f[1] + tau[k] * (p->c[1] - p->f[1]) : p->disc[1];
        double cx = k < nt ? p->f[0] + tau[k] * (p->c[0] - p->f[0]) : p->disc[0];
        if (rad < 0)
            continue;
        ys[n++] = cy - rad;
        ys[n++] = cy + rad;
        for (int e = 0; e < 2; e++) {
            double h = rad * rad - (i + e - cx) * (i + e - cx);
            if (h > 0) {
                ys[n++] = cy - sqrt(h);
                ys[n++] = cy + sqrt(h);
            }
        }
    }
    qsort(ys, (size_t)n, sizeof *ys, cmp_double);
    double sum = 0, res, err, prev = j;
    for (int k = 0; k < n; k++) {
        if (!(ys[k] > prev) || ys[k] > j + 1)
            continue;
        gsl_integration_qag(&F, prev, ys[k], 1e-15, 1e-13, 1000, GSL_INTEG_GAUSS21, wo, &res,
                            &err);
        sum += res;
        prev = ys[k];
    }
    gsl_integration_workspace_free(c.wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The scene of p on a 16 x 16 image (black background, the disc a black
 * layer painted with the gradient). */
static aa_scene *rpic_scene(const rpic *p)
{
    gw = gh = W;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    disc_px(s, p->disc[0], p->disc[1], p->disc[2]);
    aa_gradient g = grad_px(AA_GRADIENT_RADIAL, p->spread,
                            (const double[6]){p->c[0], p->c[1], p->r, p->f[0], p->f[1], p->fr},
                            p->stops, p->n);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

typedef struct polar_ctx {
    const rpic *p;
} polar_ctx;

/* Centred (F = C): t = (rho - fr) / dr on the circle of radius rho about
 * C, so the disc's integral is int_0^R colour(t(rho)) 2 pi rho drho. */
static double polar_f(double rho, void *v)
{
    const rpic *p = v;
    return rpic_colour(p, (rho - p->fr) / (p->r - p->fr)) * 2 * M_PI * rho;
}

static double polar_integral(const rpic *p)
{
    double tau[400], cut[400], res, err, sum = 0;
    int nt = rpic_taus(p, tau), n = 0;
    cut[n++] = 0;
    for (int k = 0; k < nt; k++) {
        double rho = p->fr + tau[k] * (p->r - p->fr);
        if (rho > 0 && rho < p->disc[2])
            cut[n++] = rho;
    }
    cut[n++] = p->disc[2];
    qsort(cut, (size_t)n, sizeof *cut, cmp_double);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    gsl_function F = {polar_f, (void *)p};
    for (int k = 0; k + 1 < n; k++) {
        if (!(cut[k + 1] > cut[k]))
            continue;
        gsl_integration_qag(&F, cut[k], cut[k + 1], 1e-15, 1e-15, 1000, GSL_INTEG_GAUSS61, ws,
                            &res, &err);
        sum += res;
    }
    gsl_integration_workspace_free(ws);
    return sum;
}

/* The box reference of radial gradients against answers derived here:
 *  - centred, fr = 0, black to white over the end circle: the polar
 *    integral 2 pi r^2 int_0^1 dec(t) t dt (test_radial_sampled's);
 *  - the focus moved inside the end circle, fr = 0: the circles are then
 *    homothetic about F, t = rho / rho_e(theta) along the ray from F (rho_e
 *    the distance to the end circle), and the disc's integral is int dtheta
 *    rho_e^2 int_0^1 dec(t) t dt, with int rho_e^2 dtheta = 2 x the disc's
 *    area: the centred case's sum again;
 *  - centred with fr > 0, reflect and repeat over a disc larger than the
 *    end circle, three coloured stops: the 1-D polar integral above (GSL);
 *  - two discs each with its own centred gradient: the sum of the two
 *    polar integrals (and, overlapping under a translucent one, refused);
 *  - single pixels of a focal case with fr > 0 and reflect: GSL in two
 *    dimensions over the pixel (rpic_pixel), the pixels of the focal
 *    circle's centre, the disc's edge, and a stop's circle; and every
 *    pixel of the repeating one above. */
static void test_radial_reference(void **state)
{
    (void)state;
    const double r = 6.0;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(100);
    gsl_function F = {dec_t, NULL};
    double I, err;
    gsl_integration_qag(&F, 0, 1, 1e-15, 1e-14, 100, GSL_INTEG_GAUSS21, ws, &I, &err);
    gsl_integration_workspace_free(ws);
    const double want = 2 * M_PI * r * r * I;
    const double focal[2][2] = {{8, 8}, {10, 7}};
    for (int k = 0; k < 2; k++) {
        rpic p = {{8, 8, r}, {8, 8}, r, {focal[k][0], focal[k][1]}, 0, AA_SPREAD_PAD, 2, 0,
                  black_white};
        aa_scene *s = rpic_scene(&p);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, W, &ref, &bound, &stats);
        expect_sum(k ? "radial, focus (10, 7)" : "radial, centred", &ref, 1, want, 1e-12);
        expect_bound(k ? "radial, focus (10, 7)" : "radial, centred", &stats);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
    const int spreads[2] = {AA_SPREAD_REFLECT, AA_SPREAD_REPEAT};
    for (int k = 0; k < 2; k++) {
        rpic p = {{8, 8, 7.5}, {8, 8}, 3.2, {8, 8}, 1.1, spreads[k], 3, 0, three};
        aa_scene *s = rpic_scene(&p);
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, W, &ref, &bound, &stats);
        for (int ch = 0; ch < 3; ch++) {
            p.ch = ch;
            expect_sum(k ? "radial, fr > 0, repeat" : "radial, fr > 0, reflect", &ref, ch,
                       polar_integral(&p), 1e-12);
        }
        expect_bound(k ? "radial, fr > 0, repeat" : "radial, fr > 0, reflect", &stats);
        /* every pixel of the repeating one, each channel, within its bound
         * plus GSL's own tolerance */
        double worst = 0;
        for (int j = 0; k && j < W; j++)
            for (int i = 0; i < W * 3; i++) {
                p.ch = i / W;
                double g1 = rpic_pixel(&p, i % W, j), r1 = aa_pixel(&ref, i % W, j)[p.ch];
                double b1 = *aa_pixel(&bound, i % W, j);
                worst = fmax(worst, fabs(r1 - g1));
                if (!(fabs(r1 - g1) <= b1 + 1e-14))
                    fail_msg("repeat, pixel (%d, %d) channel %d: %.17g, GSL 2-D %.17g, bound "
                             "%.2g",
                             i % W, j, p.ch, r1, g1, b1);
            }
        if (k)
            print_message("radial, fr > 0, repeat: every pixel and channel within %.2g of GSL "
                          "2-D\n",
                          worst);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
    /* two discs, each with its own centred gradient: the sum of their polar
     * integrals; overlapping with the front one translucent, within the
     * bound (its pixels against GSL in two dimensions:
     * test_several_gradients) */
    for (int k = 0; k < 2; k++) {
        gw = gh = W;
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        const double cx[2] = {k ? 6.5 : 4.0, k ? 9.5 : 12.0}, rr = 3.5;
        for (int d = 0; d < 2; d++) {
            disc_px(s, cx[d], 8, rr);
            aa_gradient g = grad_px(AA_GRADIENT_RADIAL, AA_SPREAD_PAD,
                                    (const double[6]){cx[d], 8, rr, cx[d], 8, 0}, black_white, 2);
            assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
            if (k && !d) /* the front one translucent: both paint the overlap */
                assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image ref, bound;
        aa_truth_stats stats;
        if (!k) {
            reference(s, W, W, &ref, &bound, &stats);
            expect_sum("radial, two discs", &ref, 1, 2 * 2 * M_PI * rr * rr * I, 1e-12);
            expect_bound("radial, two discs", &stats);
            aa_image_free(&ref);
            aa_image_free(&bound);
        } else {
            aa_scene *placed = aa_scene_place(s, W, W, 0, 0, 0);
            aa_filter f;
            aa_filter_default(&f);
            assert_int_equal(aa_image_alloc(&ref, W, W, 3), AA_OK);
            assert_int_equal(aa_image_alloc(&bound, W, W, 1), AA_OK);
            assert_int_equal(aa_truth_render(placed, &f, 1, &ref, &bound, &stats), AA_OK);
            expect_bound("radial, overlapping", &stats);
            aa_image_free(&ref);
            aa_image_free(&bound);
            aa_scene_free(placed);
        }
        aa_scene_free(s);
    }
    /* a focal case with fr > 0, reflect: single pixels */
    rpic p = {{8, 8, 7.5}, {8.5, 8}, 4.0, {7, 7.5}, 0.7, AA_SPREAD_REFLECT, 3, 0, three};
    aa_scene *s = rpic_scene(&p);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, W, W, &ref, &bound, &stats);
    expect_bound("radial, focal, fr > 0, reflect", &stats);
    const int px[5][2] = {{6, 7}, {7, 7}, {1, 8}, {12, 3}, {9, 12}};
    for (int k = 0; k < 5; k++)
        for (int ch = 0; ch < 3; ch++) {
            p.ch = ch;
            double want1 = rpic_pixel(&p, px[k][0], px[k][1]);
            double got = aa_pixel(&ref, px[k][0], px[k][1])[ch];
            double b = *aa_pixel(&bound, px[k][0], px[k][1]);
            print_message("radial focal pixel (%d, %d) ch %d: %.15f, GSL 2-D %.15f (diff %.2g, "
                          "bound %.2g)\n",
                          px[k][0], px[k][1], ch, got, want1, got - want1, b);
            if (!(fabs(got - want1) <= b + 1e-12))
                fail_msg("pixel (%d, %d) channel %d: %.17g, not %.17g", px[k][0], px[k][1], ch,
                         got, want1);
        }
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
    gw = W, gh = H;
}

/* ---- several gradients at a point ----
 *
 * A picture of up to twelve layers, each a disc or a rectangle painted by
 * a linear or radial gradient (SVG's definitions, written out here:
 * stop_value for the stops and spread, rpic_t's quadratic for radial t,
 * the projection for linear t) with its alpha, composited back to front
 * source over in encoded values over an opaque background and decoded.
 * A pixel's integral is taken by GSL in two dimensions: along each row,
 * the places where the picture is not smooth are found by sampling a
 * signature (inside each region, each gradient's period and stop
 * segment, each channel's side of the decoding's threshold) at 256
 * points a pixel and bisecting each change to rounding; QAG between them;
 * QAG over the rows.  Nothing of the reference's is shared: not its
 * cuts, not its composite, not its quadrature. */
typedef struct mlayer {
    int disc;     /* region: disc (r[0], r[1]) radius r[2], or rectangle r[0..3] */
    double r[4];
    int kind;     /* AA_GRADIENT_LINEAR: p = x1, y1, x2, y2; radial: cx, cy, r, fx, fy, fr */
    double p[6];
    int spread, n;
    const aa_gradient_stop *st;
    double alpha;
} mlayer;

typedef struct mpic {
    int nl;       /* layers, back first */
    mlayer l[12];
    double bg[3]; /* encoded background */
    int ch;
} mpic;

/* Bit k set: layer k of the picture interpolates its stops in linear light
 * (AA_INTERPOLATE_LINEAR_RGB), for mpic_enc, mpic_sig and mpic_scene. */
static unsigned mpic_lin;

/* Whether a radial layer is of the cone case: its focal circle not
 * strictly inside its end circle (|F - C| + fr >= r). */
static int mlayer_cone(const mlayer *m)
{
    return m->kind != AA_GRADIENT_LINEAR && hypot(m->p[3] - m->p[0], m->p[4] - m->p[1]) + m->p[5] >=
                                                m->p[2];
}

/* A cone-case layer's t at (x, y) from SVG 2's definition (13.3.5: the
 * largest t whose circle, centre F + t (C - F) and radius fr + t (r - fr)
 * >= 0, passes through the point; none: the layer paints nothing there,
 * NAN): |q - t D| = fr + t dr squared is A t^2 - 2 B t + E = 0, both roots
 * taken (the larger in magnitude by its formula, the other as E / A over
 * it) and the largest of radius >= 0 kept. */
static double mlayer_cone_t(const mlayer *m, double x, double y)
{
    const double *p = m->p;
    double qx = x - p[3], qy = y - p[4], Dx = p[0] - p[3], Dy = p[1] - p[4], dr = p[2] - p[5];
    double A = Dx * Dx + Dy * Dy - dr * dr, B = qx * Dx + qy * Dy + p[5] * dr;
    double E = qx * qx + qy * qy - p[5] * p[5], root[2], best = NAN;
    int n = 0;
    if (A == 0.0 && B != 0.0)
        root[n++] = E / (2 * B);
    else if (A != 0.0 && B * B - A * E >= 0.0) {
        double s = sqrt(B * B - A * E), q = B + (B >= 0 ? s : -s);
        root[n++] = q / A;
        if (q != 0.0)
            root[n++] = E / q;
    }
    for (int k = 0; k < n; k++)
        if (p[5] + root[k] * dr >= 0.0 && !(root[k] <= best))
            best = root[k];
    return best;
}

static double mlayer_t(const mlayer *m, double x, double y)
{
    if (m->kind == AA_GRADIENT_LINEAR) {
        double dx = m->p[2] - m->p[0], dy = m->p[3] - m->p[1];
        return ((x - m->p[0]) * dx + (y - m->p[1]) * dy) / (dx * dx + dy * dy);
    }
    if (mlayer_cone(m)) {
        double t = mlayer_cone_t(m, x, y);
        return t == t ? t : 0.0; /* unpainted: mlayer_in */
    }
    rpic rp = {{0, 0, 0}, {m->p[0], m->p[1]}, m->p[2], {m->p[3], m->p[4]}, m->p[5], 0, 0, 0,
               NULL};
    return rpic_t(&rp, x, y);
}

/* A layer whose region (disc) is 2 is the stroke of the cubic mpic_cubic[0
 * .. 7] (x0, y0, x1, y1, x2, y2, x3, y3, in pixels) of half width
 * mpic_cubic[8], round caps, for mlayer_in and mpic_scene. */
static const double *mpic_cubic;

static void mcubic_at(const double *c, double t, double *b, double *d, double *dd)
{
    double u = 1 - t;
    for (int i = 0; i < 2; i++) {
        double p0 = c[i], p1 = c[2 + i], p2 = c[4 + i], p3 = c[6 + i];
        b[i] = u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
        d[i] = 3 * (u * u * (p1 - p0) + 2 * u * t * (p2 - p1) + t * t * (p3 - p2));
        dd[i] = 6 * (u * (p2 - 2 * p1 + p0) + t * (p3 - 2 * p2 + p1));
    }
}

/* Whether (x, y) lies in the stroke of mpic_cubic: its distance to the
 * cubic at most the half width (SVG 2's stroke shape, round caps), the
 * distance the least of the ends' and the foot's, where (p - B) . B' = 0:
 * the least of |p - B|^2 at 33 parameters, the foot between its two
 * neighbours by Newton's method on (p - B) . B', kept in that bracket by
 * bisection.  For the cubics here (radius of curvature above 3 times the
 * half width, points within a few half widths) |p - B(t)| has one minimum
 * along the curve near p, so the sampled least is next to the foot. */
static int stroke_in(const double *c, double x, double y)
{
    const int N = 32;
    double b[2], d[2], dd[2], best = INFINITY;
    int kb = 0;
    for (int k = 0; k <= N; k++) {
        mcubic_at(c, (double)k / N, b, d, dd);
        double r = (x - b[0]) * (x - b[0]) + (y - b[1]) * (y - b[1]);
        if (r < best)
            best = r, kb = k;
    }
    double lo = kb > 0 ? (kb - 1.0) / N : 0.0, hi = kb < N ? (kb + 1.0) / N : 1.0, g[2];
    for (int e = 0; e < 2; e++) {
        mcubic_at(c, e ? hi : lo, b, d, dd);
        g[e] = (x - b[0]) * d[0] + (y - b[1]) * d[1];
    }
    if (g[0] > 0 && g[1] < 0) { /* a minimum of the distance inside: its foot */
        double t = 0.5 * (lo + hi);
        for (int it = 0; it < 100 && hi - lo > 1e-17; it++) {
            mcubic_at(c, t, b, d, dd);
            double f = (x - b[0]) * d[0] + (y - b[1]) * d[1];
            double df = (x - b[0]) * dd[0] + (y - b[1]) * dd[1] - d[0] * d[0] - d[1] * d[1];
            if (f > 0)
                lo = t;
            else
                hi = t;
            double nt = t - f / df;
            if (!(nt > lo && nt < hi))
                nt = 0.5 * (lo + hi);
            if (fabs(nt - t) < 1e-16)
                break;
            t = nt;
        }
        mcubic_at(c, t, b, d, dd);
        best = fmin(best, (x - b[0]) * (x - b[0]) + (y - b[1]) * (y - b[1]));
    }
    return sqrt(best) <= c[8];
}

static int mlayer_in(const mlayer *m, double x, double y)
{
    if (mlayer_cone(m) && isnan(mlayer_cone_t(m, x, y)))
        return 0; /* the cone case paints nothing there */
    if (m->disc == 2)
        return stroke_in(mpic_cubic, x, y);
    return m->disc ? hypot(x - m->r[0], y - m->r[1]) < m->r[2]
                   : (x > m->r[0] && x < m->r[2] && y > m->r[1] && y < m->r[3]);
}

/* A layer in linear light: channel ch's linear value at t, the stops'
 * linear channels interpolated (SVG's spread as stop_value takes it). */
static double mlayer_linear(const mlayer *m, double t, int ch)
{
    t = spread_fold(m->spread, t);
    const aa_gradient_stop *s = m->st;
    if (t <= s[0].offset)
        return s[0].colour.c[ch];
    for (int q = 0; q + 1 < m->n; q++)
        if (t < s[q + 1].offset) {
            double f = (t - s[q].offset) / (s[q + 1].offset - s[q].offset);
            return s[q].colour.c[ch] + f * (s[q + 1].colour.c[ch] - s[q].colour.c[ch]);
        }
    return s[m->n - 1].colour.c[ch];
}

/* The encoded composites of channels c0 .. c1 - 1 into e[c0 .. c1 - 1], at
 * a point where layer k's region holds it if in[k], its t there t[k]
 * (mlayer_in and mlayer_t, found once for the channels), each layer's
 * place among its stops found once for them. */
static void mpic_enc_at(const mpic *p, int c0, int c1, const int *in, const double *t,
                        double *e)
{
    for (int ch = c0; ch < c1; ch++)
        e[ch] = p->bg[ch];
    for (int k = 0; k < p->nl; k++) {
        const mlayer *m = &p->l[k];
        if (!in[k])
            continue;
        picture pc = {0};
        pc.spread = m->spread, pc.stops = m->st, pc.n = m->n;
        double op, f;
        int q = stop_at(&pc, t[k], &f, &op);
        double a = m->alpha * op;
        for (int ch = c0; ch < c1; ch++) {
            double c = stop_colour(&pc, q, f, ch);
            if ((mpic_lin >> k) & 1u)
                c = enc(mlayer_linear(m, t[k], ch));
            e[ch] = a * c + (1 - a) * e[ch];
        }
    }
}

/* The encoded composite of channel ch at (x, y). */
static double mpic_enc(const mpic *p, int ch, double x, double y)
{
    int in[12];
    double t[12];
    for (int k = 0; k < p->nl; k++) {
        in[k] = mlayer_in(&p->l[k], x, y);
        t[k] = in[k] ? mlayer_t(&p->l[k], x, y) : 0.0;
    }
    double e[3];
    mpic_enc_at(p, ch, ch + 1, in, t, e);
    return e[ch];
}

/* The signature of (x, y): where the picture is smooth it does not change.
 * Ended by SIG_END, which no entry takes (floor(t) is -1 inside a focal
 * circle: ended by -1, the signature stopped at the first layer whose t
 * was negative, and the layers in front of it and the threshold's sides
 * went unseen there; a front layer's focal circle crossing a back one's
 * was no cut, and a pixel holding both came out 1.5e-10 off). */
#define SIG_END INT_MIN
static void mpic_sig(const mpic *p, double x, double y, int *s)
{
    int n = 0, in[12];
    double tk[12];
    for (int k = 0; k < p->nl; k++) {
        const mlayer *m = &p->l[k];
        double t = mlayer_t(m, x, y), u = spread_fold(m->spread, t);
        s[n++] = in[k] = mlayer_in(m, x, y);
        tk[k] = t;
        /* padded, t's whole numbers past -1 and 2 are no events (the half-plane's t
         * runs to infinity at its edge) */
        s[n++] = (int)floor(m->spread == AA_SPREAD_PAD ? fmin(fmax(t, -1.0), 2.0) : t);
        int seg = 0;
        for (int q = 0; q < m->n; q++)
            seg += u >= m->st[q].offset;
        s[n++] = seg;
        for (int c = 0; c < 3 && ((mpic_lin >> k) & 1u); c++) /* the encoding's change of piece */
            s[n++] = mlayer_linear(m, t, c) > 0.0031308;
    }
    double e[3];
    mpic_enc_at(p, 0, 3, in, tk, e);
    for (int c = 0; c < 3; c++)
        s[n++] = e[c] > 0.04045;
    s[n] = SIG_END;
}

static int sig_eq(const int *a, const int *b)
{
    for (int k = 0;; k++) {
        if (a[k] != b[k])
            return 0;
        if (a[k] == SIG_END)
            return 1;
    }
}

typedef struct mrow {
    const mpic *p;
    double y, xa, xb;
    gsl_integration_workspace *wi;
} mrow;

static double mrow_x(double x, void *v)
{
    const mrow *c = v;
    return dec(mpic_enc(c->p, c->p->ch, x, c->y));
}

/* The places along row y of [xa, xb] where the picture is not smooth
 * (the signature changes), into cut (xa and xb included); their count. */
static int mrow_cuts(const mpic *p, double y, double xa, double xb, double *cut)
{
    const int N = 256;
    int nc = 0, sa[64], sb[64], sm[64];
    cut[nc++] = xa;
    mpic_sig(p, xa, y, sa);
    for (int k = 1; k <= N; k++) {
        double a = xa + (xb - xa) * (k - 1) / N, bk = xa + (xb - xa) * k / N;
        mpic_sig(p, bk, y, sb);
        /* each change in (a, bk], the first by bisection, then on from it */
        for (int rep = 0; rep < 64 && !sig_eq(sa, sb); rep++) {
            double b = bk;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (a + b);
                if (m <= a || m >= b)
                    break;
                mpic_sig(p, m, y, sm);
                if (sig_eq(sm, sa))
                    a = m;
                else
                    b = m;
            }
            if (nc < 1000 && b > cut[nc - 1] && b < xb)
                cut[nc++] = b;
            a = b;
            mpic_sig(p, b, y, sa);
        }
        memcpy(sa, sb, sizeof sa);
    }
    cut[nc++] = xb;
    return nc;
}

/* The places along the rows of one pixel of one picture, kept by height:
 * they do not depend on the channel (mpic_sig looks at all three), so the
 * pixel's three channels find each row's once (mrow_events' heights, and
 * the heights the outer QAG asks of each channel, most of them the same),
 * the same values bit for bit.  The picture is known by what mpic_sig
 * reads, written out (memo_key): its layers, their stops, the background,
 * mpic_lin and mpic_cubic's curve. */
enum { MEMO_SLOTS = 1 << 13, MEMO_KEY = 2 + 12 * (15 + 5 * 10) + 13 };
static struct {
    double key[MEMO_KEY];
    int nkey, ne;
    double ev[64];
    struct {
        uint64_t y;
        int nc; /* 0: empty */
        double *cut;
    } slot[MEMO_SLOTS];
} memo;

static int memo_key(const mpic *p, int i, int j, double *k)
{
    int n = 0;
    k[n++] = i, k[n++] = j;
    for (int l = 0; l < p->nl; l++) {
        const mlayer *m = &p->l[l];
        k[n++] = m->disc, k[n++] = m->kind, k[n++] = m->spread, k[n++] = m->n;
        k[n++] = m->alpha;
        for (int q = 0; q < 4; q++)
            k[n++] = m->r[q];
        for (int q = 0; q < 6; q++)
            k[n++] = m->p[q];
        for (int q = 0; q < m->n; q++) {
            k[n++] = m->st[q].offset, k[n++] = m->st[q].opacity;
            for (int c = 0; c < 3; c++)
                k[n++] = m->st[q].colour.c[c];
        }
    }
    for (int c = 0; c < 3; c++)
        k[n++] = p->bg[c];
    k[n++] = mpic_lin;
    for (int q = 0; q < 9; q++)
        k[n++] = mpic_cubic ? mpic_cubic[q] : NAN;
    return n;
}

/* Forgets what memo kept unless it is of the picture p at pixel (i, j);
 * 1 if it is (its events kept). */
static int memo_of(const mpic *p, int i, int j)
{
    double k[MEMO_KEY];
    assert_true(p->nl <= 12);
    for (int l = 0; l < p->nl; l++)
        assert_true(p->l[l].n <= 10);
    int n = memo_key(p, i, j, k);
    if (n == memo.nkey && memcmp(k, memo.key, (size_t)n * sizeof *k) == 0)
        return 1;
    for (int s = 0; s < MEMO_SLOTS; s++)
        if (memo.slot[s].nc)
            free(memo.slot[s].cut), memo.slot[s].nc = 0;
    memcpy(memo.key, k, (size_t)n * sizeof *k);
    memo.nkey = n, memo.ne = 0;
    return 0;
}

/* mrow_cuts of the memo's pixel at height y, kept. */
static int memo_cuts(const mpic *p, double y, double xa, double xb, double *cut)
{
    union {
        double d;
        uint64_t u;
    } bits = {y};
    unsigned h = (unsigned)((bits.u * 0x9E3779B97F4A7C15u) >> 51);
    for (int probe = 0; probe < 64; probe++, h = (h + 1) % MEMO_SLOTS) {
        if (memo.slot[h].nc && memo.slot[h].y == bits.u) {
            memcpy(cut, memo.slot[h].cut, (size_t)memo.slot[h].nc * sizeof *cut);
            return memo.slot[h].nc;
        }
        if (!memo.slot[h].nc)
            break;
    }
    int nc = mrow_cuts(p, y, xa, xb, cut);
    if (!memo.slot[h].nc) {
        memo.slot[h].cut = malloc((size_t)nc * sizeof *cut);
        assert_non_null(memo.slot[h].cut);
        memcpy(memo.slot[h].cut, cut, (size_t)nc * sizeof *cut);
        memo.slot[h].y = bits.u, memo.slot[h].nc = nc;
    }
    return nc;
}

static double mrow_y(double y, void *v)
{
    mrow *c = v;
    c->y = y;
    double cut[1024];
    int nc = memo_cuts(c->p, y, c->xa, c->xb, cut);
    gsl_function F = {mrow_x, c};
    double sum = 0, res, err;
    for (int k = 0; k + 1 < nc; k++) {
        gsl_integration_qag(&F, cut[k], cut[k + 1], 1e-16, 1e-14, 1000, GSL_INTEG_GAUSS21, c->wi,
                            &res, &err);
        sum += res;
    }
    return sum;
}

/* The rows' events in [ya, yb]: heights where the number of places along
 * the row changes (a curve of the picture turns, or crosses the pixel's
 * side), sampled at 64 heights and bisected; the row integral is not
 * smooth there, so the outer QAG is split at them. */
static int mrow_events(const mpic *p, double xa, double xb, double ya, double yb, double *ev)
{
    const int N = 64;
    double cut[1024];
    int ne = 0, na = memo_cuts(p, ya, xa, xb, cut);
    ev[ne++] = ya;
    for (int k = 1; k <= N; k++) {
        double a = ya + (yb - ya) * (k - 1) / N, bk = ya + (yb - ya) * k / N;
        int nb = memo_cuts(p, bk, xa, xb, cut);
        for (int rep = 0; rep < 16 && nb != na; rep++) {
            double b = bk;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (a + b);
                if (m <= a || m >= b)
                    break;
                if (memo_cuts(p, m, xa, xb, cut) == na)
                    a = m;
                else
                    b = m;
            }
            if (ne < 60 && b > ev[ne - 1] && b < yb)
                ev[ne++] = b;
            a = b;
            na = memo_cuts(p, b, xa, xb, cut);
        }
        na = nb;
    }
    ev[ne++] = yb;
    return ne;
}

/* The integral of channel p->ch over pixel (i, j). */
static double mpic_pixel(const mpic *p, int i, int j)
{
    gsl_integration_workspace *wo = gsl_integration_workspace_alloc(1000);
    mrow c = {p, 0, i, i + 1.0, gsl_integration_workspace_alloc(1000)};
    gsl_function F = {mrow_y, &c};
    double ev[64], sum = 0, res, err;
    if (!memo_of(p, i, j)) /* the events: once a pixel */
        memo.ne = mrow_events(p, i, i + 1.0, j, j + 1.0, memo.ev);
    int ne = memo.ne;
    memcpy(ev, memo.ev, sizeof ev);
    for (int k = 0; k + 1 < ne; k++) {
        gsl_integration_qag(&F, ev[k], ev[k + 1], 1e-16, 1e-14, 1000, GSL_INTEG_GAUSS21, wo, &res,
                            &err);
        sum += res;
    }
    gsl_integration_workspace_free(c.wi);
    gsl_integration_workspace_free(wo);
    return sum;
}

/* The scene of p (layers added front first), W x W pixels. */
static aa_scene *mpic_scene(const mpic *p)
{
    aa_rgb bg;
    for (int c = 0; c < 3; c++)
        bg.c[c] = dec(p->bg[c]);
    aa_scene *s = aa_scene_new(bg);
    for (int k = p->nl - 1; k >= 0; k--) {
        const mlayer *m = &p->l[k];
        if (m->disc == 2) { /* the stroke of mpic_cubic, its outline's offset pieces */
            const double *c = mpic_cubic, px[6] = {1.0 / gw, 0, 0, 1.0 / gh, 0, 0};
            aa_path in = {0}, out = {0};
            aa_stroke_style st;
            aa_stroke_style_default(&st);
            st.width = 2 * c[8], st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
            assert_int_equal(aa_path_move_to(&in, c[0], c[1]), AA_OK);
            assert_int_equal(aa_path_cubic_to(&in, c[2], c[3], c[4], c[5], c[6], c[7]), AA_OK);
            assert_int_equal(aa_stroke_outline(&in, &st, &out), AA_OK);
            assert_int_equal(aa_scene_layer(s, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO), AA_OK);
            assert_int_equal(aa_path_fill(&out, px, s), AA_OK);
            aa_path_free(&in);
            aa_path_free(&out);
        } else if (m->disc)
            disc_px(s, m->r[0], m->r[1], m->r[2]);
        else
            rect_px(s, (aa_rgb){{0, 0, 0}}, m->r[0], m->r[1], m->r[2], m->r[3]);
        aa_gradient g = grad_px(m->kind, m->spread, m->p, m->st, m->n);
        assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
        if ((mpic_lin >> k) & 1u)
            assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB),
                             AA_OK);
        if (m->alpha != 1.0)
            assert_int_equal(aa_scene_set_alpha(s, m->alpha), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The reference of p against mpic_pixel at the pixels px (npx of them),
 * every channel: within the reference's bound (the 2-D quadrature's own
 * error, below 1e-15 on these pixels, is not added). */
static void mpic_check(const char *what, mpic *p, const int (*px)[2], int npx)
{
    gw = gh = W;
    aa_scene *s = mpic_scene(p);
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(s, W, W, &ref, &bound, &stats);
    expect_bound(what, &stats);
    double worst = 0;
    for (int k = 0; k < npx; k++)
        for (int ch = 0; ch < 3; ch++) {
            p->ch = ch;
            double want = mpic_pixel(p, px[k][0], px[k][1]);
            double got = aa_pixel(&ref, px[k][0], px[k][1])[ch];
            double b = *aa_pixel(&bound, px[k][0], px[k][1]);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= b))
                fail_msg("%s: pixel (%d, %d) channel %d: %.17g, GSL 2-D %.17g (bound %.2g)", what,
                         px[k][0], px[k][1], ch, got, want, b);
        }
    print_message("%s: %d pixels x 3 channels within %.2g of GSL 2-D\n", what, npx, worst);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
    gw = W, gh = H;
}

static const aa_gradient_stop warm[3] = {{0.0, {{0.9, 0.1, 0.0}}, 1.0},
                                         {0.5, {{1.0, 0.8, 0.2}}, 1.0},
                                         {1.0, {{0.02, 0.0, 0.3}}, 1.0}};
static const aa_gradient_stop fading[2] = {{0.0, {{0.0, 0.3, 1.0}}, 1.0},
                                           {1.0, {{1.0, 1.0, 0.0}}, 0.2}};

/* Linear and radial gradients overlapping at half opacity; two radial
 * gradients overlapping; a gradient whose stops' opacities differ over
 * another gradient; two focal radial gradients whose focal circles cross:
 * each against the 2-D quadrature of its picture, at pixels where the
 * layers overlap, cross stops and the threshold, and at the regions'
 * edges. */
static void test_several_gradients(void **state)
{
    (void)state;
    static const int px[6][2] = {{8, 8}, {5, 9}, {11, 6}, {4, 4}, {12, 12}, {9, 3}};
    /* a radial gradient at half opacity over a linear one */
    mpic a = {2,
              {{0, {1.5, 2.25, 14.5, 13.75}, AA_GRADIENT_LINEAR, {2, 3, 13, 11, 0, 0},
                AA_SPREAD_PAD, 3, three, 1.0},
               {1, {8.5, 8, 5.5, 0}, AA_GRADIENT_RADIAL, {8.5, 8, 5.5, 9.5, 7, 0.5},
                AA_SPREAD_REFLECT, 3, warm, 0.5}},
              {0.2, 0.2, 0.2},
              0};
    mpic_check("linear under radial at half opacity", &a, px, 6);
    /* two radial gradients, the front one at half opacity */
    mpic b = {2,
              {{1, {6, 8, 5, 0}, AA_GRADIENT_RADIAL, {6, 8, 5, 5, 9, 0}, AA_SPREAD_PAD, 2,
                black_white, 1.0},
               {1, {10, 7.5, 5, 0}, AA_GRADIENT_RADIAL, {10, 7.5, 5, 11, 7, 0.8},
                AA_SPREAD_REPEAT, 3, warm, 0.5}},
              {0, 0, 0},
              0};
    mpic_check("two radial gradients", &b, px, 6);
    /* a linear gradient fading to opacity 0.2 over another linear one */
    mpic c = {2,
              {{0, {1, 1, 15, 15}, AA_GRADIENT_LINEAR, {2, 14, 14, 2, 0, 0}, AA_SPREAD_REFLECT, 3,
                warm, 1.0},
               {0, {3.5, 2.5, 13.25, 14}, AA_GRADIENT_LINEAR, {3, 0, 12, 5, 0, 0}, AA_SPREAD_PAD, 2,
                fading, 0.8}},
              {1, 1, 1},
              0};
    mpic_check("fading linear over linear", &c, px, 6);
    /* two focal radial gradients, fr = 0.3, their focal circles (t < 0
     * inside, padded) crossing at y = 7.7 inside pixel (8, 7): the
     * stacks' layers 1 and 3 below (test_many_layers_mixed) */
    static const int fx[3][2] = {{8, 7}, {8, 8}, {7, 7}};
    mpic d = {2,
              {{1, {6.8, 8.3, 6.1, 0}, AA_GRADIENT_RADIAL, {8.2, 7.9, 5.2, 8.5, 7.6, 0.3},
                AA_SPREAD_PAD, 3, warm, 0.39},
               {0, {1.75, 2.6, 14.2, 13.55}, AA_GRADIENT_RADIAL, {8.6, 7.7, 5.6, 8.5, 7.8, 0.3},
                AA_SPREAD_PAD, 2, fading, 0.47}},
              {0.1, 0.05, 0.3},
              0};
    mpic_check("two focal circles crossing", &d, fx, 3);
}

/* ---- more than five gradient layers at a point ----
 *
 * Past five layers the reference folds the composite layer by layer in
 * place of its 3^n coefficients (truth.c, "the fold").  Known answers:
 *  - a closed form: layers of full-image rectangles, each a horizontal
 *    linear gradient of one colour c_l whose opacity runs affinely from
 *    o0 to o1 across a vector wider than the image (no padding inside),
 *    with alpha al_l, over black.  Their encoded composite, source over
 *    back to front, e := a_l c_l + (1 - a_l) e with a_l(x) = al_l op_l(x)
 *    affine in x, is a polynomial in x of degree n, built here by
 *    multiplying out; with every c_l <= 0.04 encoded it stays below the
 *    decoding's threshold 0.04045 (a convex combination of the c_l and
 *    0), where dec(e) = e / 12.92, so a pixel is the polynomial's
 *    integral over [i, i + 1] over 12.92, exact;
 *  - n identical layers of alpha a compose to one layer of alpha 1 - (1 -
 *    a)^n (source over: the background's weight is (1 - a)^n, the
 *    colour's the rest): a stack of radial gradients, crossing the
 *    threshold, against the one radial layer of that alpha, which the
 *    reference takes by its own path ("radial gradient paint", checked
 *    against closed forms above);
 *    held to the two bounds.  The stack's path once took each radial
 *    layer's threshold circles from the composite with the other
 *    gradients at their first stops (threshold_taus) and left the stack's
 *    own to QAG's estimate (truth.c, "several gradients"): its worst
 *    pixel departed from the one layer by 9e-14 (6 layers), 2.9e-13 (8)
 *    and 6.9e-13 (12), above its bound, where GSL's 2-D quadrature of
 *    either picture (mpic_pixel) agrees with the one layer to 4e-17 (with
 *    2 and 3 layers, the product form's path, 1e-14 and 1.5e-14): the
 *    stack's path was the one off.  With the circles where the stack's
 *    composite, (1 - a)^n bg + (1 - (1 - a)^n) C(t) of the shared t,
 *    passes 0.04045 as breakpoints (shared_threshold_taus), 1.1e-16 (2),
 *    2.2e-16 (3), 4.4e-16 (6), 1.2e-14 (8) and 6.7e-16 (12);
 *  - a mixed stack of 7 and 12 translucent linear and radial layers on
 *    discs and rectangles against the 2-D quadrature of its picture
 *    (mpic_pixel, nothing of the reference's shared). */
static void poly_over(double *e, int *deg, double a0, double a1, double c)
{
    /* e := a c + (1 - a) e with a = a0 + a1 x */
    double out[16] = {0};
    for (int k = 0; k <= *deg; k++) {
        out[k] += (1.0 - a0) * e[k];
        out[k + 1] -= a1 * e[k];
    }
    out[0] += a0 * c, out[1] += a1 * c;
    (*deg)++;
    memcpy(e, out, sizeof out);
}

static double poly_int(const double *e, int deg, double a, double b)
{
    double fa = 0.0, fb = 0.0;
    for (int k = deg; k >= 0; k--)
        fa = fa * a + e[k] / (k + 1), fb = fb * b + e[k] / (k + 1);
    return fb * b - fa * a;
}

static void test_many_layers_closed(void **state)
{
    (void)state;
    static const int ns[3] = {6, 8, 12};
    for (int q = 0; q < 3; q++) {
        int n = ns[q];
        double e[3][16] = {{0}}, x1[12], x2[12], o0[12], o1[12], al[12], c[12][3];
        int deg[3] = {0, 0, 0};
        aa_gradient_stop st[12][2];
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        for (int l = 0; l < n; l++) { /* l = 0 the front layer */
            x1[l] = -1.0 - 0.5 * l, x2[l] = W + 1.0 + 0.75 * l;
            o0[l] = 0.15 + 0.05 * l, o1[l] = 0.9 - 0.06 * l, al[l] = 1.0 - 0.03 * l;
            for (int ch = 0; ch < 3; ch++) /* 12.92 v: the encoding's linear piece */
                c[l][ch] = 12.92 * (0.0005 + 0.00025 * ((l + 3 * ch) % 11));
            if (l % 2) /* the vector reversed: the opacity falls along x */
                x1[l] = W + 1.0 + 0.75 * l, x2[l] = -1.0 - 0.5 * l;
            for (int k = 0; k < 2; k++) {
                st[l][k].offset = k;
                st[l][k].opacity = k ? o1[l] : o0[l];
                for (int ch = 0; ch < 3; ch++)
                    st[l][k].colour.c[ch] = c[l][ch] / 12.92;
            }
            rect_px(s, (aa_rgb){{0, 0, 0}}, 0, 0, W, H);
            aa_gradient g = grad_px(AA_GRADIENT_LINEAR, AA_SPREAD_PAD,
                                    (const double[6]){x1[l], 0, x2[l], 0, 0, 0}, st[l], 2);
            assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
            assert_int_equal(aa_scene_set_alpha(s, al[l]), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        for (int l = n - 1; l >= 0; l--) { /* back to front */
            double a1 = al[l] * (o1[l] - o0[l]) / (x2[l] - x1[l]), a0 = al[l] * o0[l] - a1 * x1[l];
            for (int ch = 0; ch < 3; ch++)
                poly_over(e[ch], &deg[ch], a0, a1, c[l][ch]);
        }
        aa_image ref, bound;
        aa_truth_stats stats;
        reference(s, W, H, &ref, &bound, &stats);
        char what[64];
        snprintf(what, sizeof what, "%d layers, closed form", n);
        expect_bound(what, &stats);
        double worst = 0.0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                for (int ch = 0; ch < 3; ch++) {
                    double want = poly_int(e[ch], deg[ch], i, i + 1.0) / 12.92;
                    double got = aa_pixel(&ref, i, j)[ch], b = *aa_pixel(&bound, i, j);
                    worst = fmax(worst, fabs(got - want));
                    if (!(fabs(got - want) <= b + 1e-15))
                        fail_msg("%s: pixel (%d, %d) channel %d: %.17g, closed form %.17g "
                                 "(bound %.2g)",
                                 what, i, j, ch, got, want, b);
                }
        print_message("%s: every pixel within %.2g of the closed form\n", what, worst);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
}

static const aa_gradient_stop stack_stops[3] = {{0.0, {{1.0, 0.9, 0.002}}, 1.0},
                                                {0.6, {{0.2, 0.0005, 0.6}}, 1.0},
                                                {1.0, {{0.0, 0.05, 1.0}}, 1.0}};

static void test_many_layers_stack(void **state)
{
    (void)state;
    static const int ns[3] = {6, 8, 12};
    const double a = 0.3;
    aa_rgb bg = {{0.02, 0.3, 0.001}};
    for (int q = 0; q < (SAN_SUBSET ? 1 : 3); q++) {
        int n = ns[q];
        aa_image ref[2], bound[2];
        aa_truth_stats stats[2];
        for (int one = 0; one < 2; one++) {
            aa_scene *s = aa_scene_new(bg);
            for (int l = 0; l < (one ? 1 : n); l++) {
                disc_px(s, 8.0, 6.0, 5.5);
                aa_gradient g = grad_px(AA_GRADIENT_RADIAL, AA_SPREAD_REFLECT,
                                        (const double[6]){8.0, 6.0, 4.0, 7.0, 5.5, 0.5},
                                        stack_stops, 3);
                assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
                assert_int_equal(aa_scene_set_alpha(s, one ? 1.0 - pow(1.0 - a, n) : a), AA_OK);
            }
            assert_int_equal(aa_scene_finish(s), AA_OK);
            reference(s, W, H, &ref[one], &bound[one], &stats[one]);
            aa_scene_free(s);
        }
        char what[64];
        snprintf(what, sizeof what, "%d radial layers of alpha %g", n, a);
        expect_bound(what, &stats[0]);
        double worst = 0.0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                for (int ch = 0; ch < 3; ch++) {
                    double got = aa_pixel(&ref[0], i, j)[ch], want = aa_pixel(&ref[1], i, j)[ch];
                    double b = *aa_pixel(&bound[0], i, j) + *aa_pixel(&bound[1], i, j);
                    worst = fmax(worst, fabs(got - want));
                    if (!(fabs(got - want) <= b))
                        fail_msg("%s: pixel (%d, %d) channel %d: %.17g, one layer of alpha 1 - "
                                 "(1 - a)^n %.17g (bounds %.2g)",
                                 what, i, j, ch, got, want, b);
                }
        print_message("%s: every pixel within %.2g of one layer of alpha %.15g\n", what, worst,
                      1.0 - pow(1.0 - a, n));
        for (int one = 0; one < 2; one++)
            aa_image_free(&ref[one]), aa_image_free(&bound[one]);
    }
}

/* The pixels px against GSL as mpic_check, each pixel's reference that
 * of the scene mapped so that the pixel is a view of its own
 * (support_reference_part), the same picture on the same pixel square:
 * the mixed stack of 12 layers checks one pixel, and its whole view took
 * 9 s of CPU.
 * The stack of 7 keeps its whole view, whose windows where more than
 * THR_UNSURE layers' cover is unknown (truth.c) its two pixels miss. */
static size_t mpic_check_px(const char *what, mpic *p, const int (*px)[2], int npx)
{
    gw = gh = W;
    aa_scene *s = mpic_scene(p);
    aa_truth_stats all = {0};
    double worst = 0;
    for (int k = 0; k < npx; k++) {
        aa_image ref, bound;
        aa_truth_stats stats;
        support_reference_part(s, W, W, px[k][0], px[k][1], 1, 1, NULL, &ref, &bound, &stats);
        all.max_bound = fmax(all.max_bound, stats.max_bound);
        all.scanned += stats.scanned;
        for (int ch = 0; ch < 3; ch++) {
            p->ch = ch;
            double want = mpic_pixel(p, px[k][0], px[k][1]);
            double got = aa_pixel(&ref, 0, 0)[ch], b = *aa_pixel(&bound, 0, 0);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= b))
                fail_msg("%s: pixel (%d, %d) channel %d: %.17g, GSL 2-D %.17g (bound %.2g)", what,
                         px[k][0], px[k][1], ch, got, want, b);
        }
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    expect_bound(what, &all);
    print_message("%s: %d pixels x 3 channels within %.2g of GSL 2-D, %zu scanned\n", what, npx,
                  worst, all.scanned);
    aa_scene_free(s);
    gw = W, gh = H;
    return all.scanned;
}

static void test_many_layers_mixed(void **state)
{
    (void)state;
    static const int px[3][2] = {{6, 9}, {10, 5}, {4, 11}};
    mpic p = {12, {{0}}, {0.1, 0.05, 0.3}, 0};
    for (int l = 0; l < 12; l++) {
        mlayer *m = &p.l[l];
        double k = l;
        m->disc = l % 3 == 1;
        if (m->disc)
            m->r[0] = 6.5 + 0.3 * k, m->r[1] = 8.5 - 0.2 * k, m->r[2] = 6 + 0.1 * k;
        else
            m->r[0] = 1 + 0.25 * k, m->r[1] = 2 + 0.2 * k, m->r[2] = 14.5 - 0.1 * k,
            m->r[3] = 14 - 0.15 * k;
        m->kind = l % 2 ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR;
        if (m->kind == AA_GRADIENT_LINEAR) {
            double p6[6] = {2 + 0.5 * k, 3 - 0.2 * k, 13 - 0.3 * k, 11 + 0.4 * k, 0, 0};
            memcpy(m->p, p6, sizeof p6);
        } else {
            double p6[6] = {8 + 0.2 * k, 8 - 0.1 * k, 5 + 0.2 * k, 8.5, 7.5 + 0.1 * k, 0.3};
            memcpy(m->p, p6, sizeof p6);
        }
        m->spread = l % 3 == 2 ? AA_SPREAD_REFLECT : AA_SPREAD_PAD;
        m->n = l % 4 == 3 ? 2 : 3;
        m->st = l % 4 == 3 ? fading : l % 2 ? warm : three;
        m->alpha = 0.35 + 0.04 * k;
    }
    p.nl = 7;
    mpic_check("7 translucent layers", &p, px, 2);
    if (SAN_SUBSET)
        return;
    p.nl = 12;
    mpic_check_px("12 translucent layers", &p, px, 1);
}

/* Two identical translucent radial layers (one gradient: the composite a
 * polynomial in the shared t) whose red channel passes 0.04045 twice
 * within 0.0031 of t.  Written out: a = 0.6 (1 - t) the layer's opacity
 * times alpha, C = C1 t its encoded red over a black background, so the
 * composite is E(t) = (1 - (1 - a)^2) C, whose largest value, at t =
 * 0.54313, is 0.256955 C1 (maximised by ternary search, outside the
 * library); C1 = 0.15742186 (the stop's linear 0.021353654) puts it 4e-7
 * above the threshold, with roots at t = 0.541589 and 0.544676.  The
 * gradient is centred, of radius 1 px (t = rho, the distance to the
 * centre), and each of the four pixels around its centre spans a range
 * of t of 0.6 or more up to the stop at 1: the threshold's circles were
 * found at 64 points a piece, steps of 0.01 or more, and both roots fell
 * within one (pixel (7, 6) 4.8e-13 off against a bound of 9.7e-14).
 * The known answer: the picture depends on rho alone there (the discs of
 * radius 3 cover those pixels), so a pixel's integral is int f(rho)
 * L(rho) drho, L the length of the circle of radius rho inside the
 * pixel's square (the angles where it crosses the square's sides, each
 * arc between them in or out by its midpoint) and f the picture along a
 * ray (mpic_enc); GSL's QAG between the distances to the square's sides
 * and corners, where L has kinks, and the roots of E(rho) - 0.04045 and
 * rho = 1 (the last stop), where f has; the roots sampled at 2^16 points
 * and bisected.  (mpic_pixel's sampling at 256 points a row is too coarse
 * for a ring 0.003 px wide: it moved by 3e-13 at 4096.) */
static const aa_gradient_stop close_roots[2] = {{0.0, {{0, 0.2, 1}}, 1.0},
                                                {1.0, {{0.021353654058843805, 0.2, 1}}, 0.0}};

typedef struct ring_ctx {
    const mpic *p;
    double cx, cy, x0, y0; /* centre; pixel's corner */
} ring_ctx;

/* The length of the circle of radius rho about (cx, cy) inside the unit
 * square at (x0, y0). */
static double ring_len(const ring_ctx *c, double rho)
{
    double th[16];
    int n = 0;
    for (int k = 0; k < 4; k++) {
        int vert = k < 2; /* x = side, or y = side */
        double side = vert ? c->x0 + k : c->y0 + (k - 2), d = side - (vert ? c->cx : c->cy);
        if (fabs(d) >= rho)
            continue;
        double a = vert ? acos(d / rho) : asin(d / rho);
        double cand[2] = {a, vert ? -a : M_PI - a};
        for (int q = 0; q < 2; q++)
            th[n++] = fmod(cand[q] + 4 * M_PI, 2 * M_PI);
    }
    th[n++] = 0, th[n++] = 2 * M_PI;
    qsort(th, (size_t)n, sizeof *th, cmp_double);
    double len = 0;
    for (int k = 0; k + 1 < n; k++) {
        double m = 0.5 * (th[k] + th[k + 1]), x = c->cx + rho * cos(m), y = c->cy + rho * sin(m);
        if (x > c->x0 && x < c->x0 + 1 && y > c->y0 && y < c->y0 + 1)
            len += rho * (th[k + 1] - th[k]);
    }
    return len;
}

static double ring_f(double rho, void *v)
{
    const ring_ctx *c = v;
    return dec(mpic_enc(c->p, c->p->ch, c->cx + rho, c->cy)) * ring_len(c, rho);
}

static double ring_pixel(const mpic *p, double cx, double cy, int i, int j)
{
    ring_ctx c = {p, cx, cy, i, j};
    double cut[64], res, err, sum = 0;
    int n = 0;
    double dx[2] = {i - cx, i + 1 - cx}, dy[2] = {j - cy, j + 1 - cy};
    for (int a = 0; a < 2; a++) {
        cut[n++] = fabs(dx[a]), cut[n++] = fabs(dy[a]);
        for (int b = 0; b < 2; b++)
            cut[n++] = hypot(dx[a], dy[b]);
    }
    if (cx > i && cx < i + 1 && cy > j && cy < j + 1)
        cut[n++] = 0;
    cut[n++] = 1; /* the last stop */
    const int N = 1 << 16;
    double prev = mpic_enc(p, p->ch, cx, cy) - 0.04045;
    for (int k = 1; k <= N; k++) { /* the threshold's radii */
        double a = 1.5 * (k - 1) / N, b = 1.5 * k / N, g = mpic_enc(p, p->ch, cx + b, cy) - 0.04045;
        if ((g > 0) != (prev > 0)) {
            double ga = prev;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (a + b);
                if (m <= a || m >= b)
                    break;
                if ((mpic_enc(p, p->ch, cx + m, cy) - 0.04045 > 0) == (ga > 0))
                    a = m;
                else
                    b = m;
            }
            cut[n++] = b;
        }
        prev = g;
    }
    qsort(cut, (size_t)n, sizeof *cut, cmp_double);
    double lo = cut[0], hi = cut[n - 1]; /* the pixel's range of rho: nearest, farthest */
    if (cx > i && cx < i + 1 && cy > j && cy < j + 1)
        lo = 0;
    else
        lo = hypot(fmax(fmax(i - cx, cx - i - 1), 0), fmax(fmax(j - cy, cy - j - 1), 0));
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(1000);
    gsl_function F = {ring_f, &c};
    double at = lo;
    for (int k = 0; k <= n; k++) {
        double to = k < n ? cut[k] : hi;
        if (!(to > at))
            continue;
        if (to > hi)
            to = hi;
        gsl_integration_qag(&F, at, to, 1e-17, 1e-15, 1000, GSL_INTEG_GAUSS61, ws, &res, &err);
        sum += res;
        at = to;
    }
    gsl_integration_workspace_free(ws);
    return sum;
}

static void test_stack_close_roots(void **state)
{
    (void)state;
    const double cx = 8.2, cy = 6.3;
    static const int px[4][2] = {{7, 5}, {8, 5}, {7, 6}, {8, 6}};
    mpic p = {2, {{0}}, {0, enc(0.2), 1}, 0};
    for (int l = 0; l < 2; l++)
        p.l[l] = (mlayer){1, {8, 6, 3, 0}, AA_GRADIENT_RADIAL, {cx, cy, 1, cx, cy, 0},
                          AA_SPREAD_PAD, 2, close_roots, 0.6};
    gw = gh = W;
    aa_scene *s = mpic_scene(&p);
    aa_image ref, bound;
    aa_truth_stats stats;
    const char *what = "a stack passing the threshold twice within 0.0031 of t";
    reference(s, W, W, &ref, &bound, &stats);
    expect_bound(what, &stats);
    double worst = 0;
    for (int k = 0; k < 4; k++)
        for (int ch = 0; ch < 3; ch++) {
            p.ch = ch;
            double want = ring_pixel(&p, cx, cy, px[k][0], px[k][1]);
            double got = aa_pixel(&ref, px[k][0], px[k][1])[ch];
            double b = *aa_pixel(&bound, px[k][0], px[k][1]);
            worst = fmax(worst, fabs(got - want));
            if (!(fabs(got - want) <= b))
                fail_msg("%s: pixel (%d, %d) channel %d: %.17g, the polar integral %.17g "
                         "(bound %.2g)",
                         what, px[k][0], px[k][1], ch, got, want, b);
        }
    print_message("%s: 4 pixels x 3 channels within %.2g of the polar integral\n", what, worst);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
    gw = W, gh = H;
}

static const aa_gradient_stop grad_l[3] = {{0.0, {{0, 0, 0}}, 1.0},
                                           {0.4, {{0.016, 0.723, 0.246}}, 1.0},
                                           {1.0, {{1, 1, 1}}, 1.0}};
static const aa_gradient_stop grad_r[2] = {{0.0, {{1, 1, 1}}, 1.0},
                                           {1.0, {{0.0056, 0.0, 0.0331}}, 1.0}};

/* A focal radial gradient on its own end circle over a linear one on a
 * rectangle (a 64 x 64 scene that once took minutes a pixel at 48 x 48,
 * scaled by 1/4): the green channel passes the decoding's threshold
 * 0.04045 on the circle of t ~ 0.96, whose top (9.96, 5.62) lies inside
 * pixel (9, 5), so rows there run tangent to it, where the threshold's two
 * crossings of a row merge.  Against the 2-D quadrature of the picture
 * (mpic_pixel, the known answer from an independent integration) at that
 * pixel, its neighbours and where the circle's and the rectangle's edges
 * pass; the whole reference within its bound of 1e-12. */
static void test_threshold_tangent(void **state)
{
    (void)state;
    static const int px[6][2] = {{9, 5}, {10, 5}, {9, 6}, {8, 5}, {11, 7}, {3, 7}};
    mpic a = {2,
              {{0, {0.5, 0.75, 11.5, 8.25}, AA_GRADIENT_LINEAR, {1, 2, 14.5, 12.5, 0, 0},
                AA_SPREAD_PAD, 3, grad_l, 1.0},
               {1, {10, 10, 4.5, 0}, AA_GRADIENT_RADIAL, {10, 10, 4.5, 9, 8.5, 0}, AA_SPREAD_PAD,
                2, grad_r, 1.0}},
              {1, 1, 1},
              0};
    mpic_check("focal radial over linear, a row tangent to the threshold", &a, px, 6);
    /* the linear layer alone at the scene's own scale: the lines where
     * its composite passes the threshold cross the pixels' sides (the
     * box's row integral has a kink there, a breakpoint between rows) */
    static const int lx[6][2] = {{4, 10}, {3, 10}, {7, 4}, {4, 8}, {5, 8}, {2, 12}};
    mpic b = {1,
              {{0, {2, 3, 46, 33}, AA_GRADIENT_LINEAR, {4, 8, 58, 50, 0, 0}, AA_SPREAD_PAD, 3,
                grad_l, 1.0}},
              {1, 1, 1},
              0};
    mpic_check("linear across the threshold, box", &b, lx, 6);
}

/* The reference cache: a changed stop changes the view's key (the file's
 * bytes), so it never meets the old entry; the same file hits it. */
static void test_cache(void **state)
{
    (void)state;
    char spec[4400], cache[4200];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    const char *fmt = "<linearGradient id=\"g\"><stop/><stop offset=\"1\" stop-color=\"%s\"/>"
                      "</linearGradient><rect width=\"16\" height=\"12\" fill=\"url(#g)\"/>";
    char body[512];
    double sums[3];
    int hits[3];
    const char *colours[3] = {"white", "grey", "grey"};
    for (int k = 0; k < 3; k++) {
        snprintf(body, sizeof body, fmt, colours[k]);
        svg_spec("cached", body, spec, sizeof spec);
        aa_view v = {0};
        v.w = W, v.h = H;
        aa_filter_default(&v.filter);
        assert_int_equal(aa_pattern_parse(spec, &v.pattern), AA_OK);
        aa_image im;
        if (aa_reference(&v, cache, 1, &im, NULL, &hits[k]))
            fail_msg("%s", aa_last_error());
        sums[k] = channel_sum(&im, 0);
        aa_image_free(&im);
    }
    print_message("cache: sums %.6f %.6f %.6f, from the cache %d %d %d\n", sums[0], sums[1],
                  sums[2], hits[0], hits[1], hits[2]);
    assert_false(hits[0]);
    assert_false(hits[1]);
    assert_true(hits[2]);
    assert_true(sums[1] < sums[0]);
    assert_true(sums[2] == sums[1]);
}

/* A translucent radial gradient over a linear one whose t runs along y:
 * along a row the linear layer's t is constant, so the threshold's curve
 * E(x, y) = 0.04045 of the red channel is a circle of the radial's t
 * that changes from row to row, no circle of any one t.  Written out:
 * E = 0.6 CR(tR) + 0.4 CL(tL), CR = 0.2 (1 - tR), tR = |q - (7.5, 11)| / 4,
 * CL piecewise linear with a peak a at tL = 0.48 (the stop line y =
 * 7.76), tL = (y - 2) / 12; a = 0.0453681462 puts E(7.5, 7.745) at the
 * threshold (bisected outside the library), where dE/dx = 0: the curve's
 * lowest point, a horizontal tangent, inside pixel (7, 7), and it
 * crosses the stop line at x = 7.17 and 7.83, in the same pixel.
 * Against the 2-D quadrature of the picture (mpic_pixel) at that pixel
 * and its neighbours. */
static const aa_gradient_stop tan_r[2] = {{0.0, {{0.033104766570885055, 0.5, 0.5}}, 1.0},
                                          {1.0, {{0, 0.5, 0.5}}, 1.0}};
static const aa_gradient_stop tan_l[3] = {{0.0, {{0, 0.5, 0.5}}, 1.0},
                                          {0.48, {{0.003511466425239878, 0.5, 0.5}}, 1.0},
                                          {1.0, {{0, 0.5, 0.5}}, 1.0}};

static void test_mixed_tangent(void **state)
{
    (void)state;
    static const int px[3][2] = {{7, 7}, {6, 7}, {8, 7}};
    mpic p = {2,
              {{0, {0, 0, 16, 16}, AA_GRADIENT_LINEAR, {7.5, 2, 7.5, 14, 0, 0}, AA_SPREAD_PAD, 3,
                tan_l, 1.0},
               {1, {7.5, 11, 6, 0}, AA_GRADIENT_RADIAL, {7.5, 11, 4, 7.5, 11, 0}, AA_SPREAD_PAD, 2,
                tan_r, 0.6}},
              {0, 0, 0},
              0};
    mpic_check("radial over linear, the threshold's curve tangent to a row at a stop line", &p,
               px, 3);
}

/* The same linear layer under a radial one with a stop at t = 0.8 (the
 * circle of radius 3.2 about (7.5, 11)) whose encoded channel 0.046 breaks
 * its slope: the threshold's curve crosses that stop circle obliquely near
 * (4.64, 9.56) in pixel (4, 9) and, mirrored, in (10, 9) (located by
 * sampling E along the circle outside the library; 4.63 to 4.66 for a
 * threshold moved by 1e-4).  Against the 2-D quadrature of the picture. */
static const aa_gradient_stop circ_r[3] = {{0.0, {{0.033104766570885055, 0.5, 0.5}}, 1.0},
                                           {0.8, {{0.0035856293488019638, 0.5, 0.5}}, 1.0},
                                           {1.0, {{0, 0.5, 0.5}}, 1.0}};

static void test_mixed_stop_circle(void **state)
{
    (void)state;
    static const int px[2][2] = {{4, 9}, {10, 9}};
    mpic p = {2,
              {{0, {0, 0, 16, 16}, AA_GRADIENT_LINEAR, {7.5, 2, 7.5, 14, 0, 0}, AA_SPREAD_PAD, 3,
                tan_l, 1.0},
               {1, {7.5, 11, 6, 0}, AA_GRADIENT_RADIAL, {7.5, 11, 4, 7.5, 11, 0}, AA_SPREAD_PAD, 3,
                circ_r, 0.6}},
              {0, 0, 0},
              0};
    mpic_check("radial over linear, the threshold's curve across a radial stop circle", &p, px,
               2);
}

/* A threshold's curve closing into a thin lens between two rows of a
 * scan.  The front layer, a radial gradient at alpha 0.5 about (9.4992,
 * 47.4400) whose channel 0 (encoded) falls from 1 at t = 0.9 to 0 at t =
 * 1, the circle of radius 40, and rises again (reflect), over a linear
 * one whose channel 0 rises by 0.2 a pixel along u = (sin 0.05, cos
 * 0.05), the direction to that centre: the composite 0.5 C + 0.5 L is
 * least on the circle where L is, at M = (7.5, 7.49), 2.8e-5 below
 * 0.04045 there, and passes 0.04045 on a lens along the circle, x in
 * [7.352, 7.649], y in [7.4828, 7.4977] (area 2.5e-4; a grid of E at
 * 6.7e-4 x 4e-5 px in Python).  The circle crosses the pixel's sides at
 * y = 7.4681 and 7.5182, breakpoints, and a scan of 32 rows a window
 * takes the rows 7.4806 and 7.5056 between them: the lens's heights (its
 * lowest point and its two corners on the circle, where C turns) lie
 * between those: with that scan alone (the code before thr_certify) no
 * row's signature changed there, and the three pixels came within 1.6e-15
 * of the quadrature (QAG's own halving met the lens's rows), inside its
 * largest bound, 2.5e-14; certified, the lens's lowest row (7.48278) and
 * upper corner (7.49778) are slivers, and they came within 5.6e-17.
 * Against the 2-D quadrature of the picture (mpic_pixel). */
#define LENS_HALF 0.21404114048223255 /* 0.5 encoded, in linear light */
static const aa_gradient_stop lens_r[3] = {{0.0, {{1.0, LENS_HALF, LENS_HALF}}, 1.0},
                                           {0.9, {{1.0, LENS_HALF, LENS_HALF}}, 1.0},
                                           {1.0, {{0.0, LENS_HALF, LENS_HALF}}, 1.0}};
static const aa_gradient_stop lens_l[2] = {
    {0.0, {{3.8699690402476816e-05, LENS_HALF, LENS_HALF}}, 1.0}, /* 0.0005 encoded */
    {1.0, {{1.0, LENS_HALF, LENS_HALF}}, 1.0}};

/* The lens's picture: a radial gradient at alpha 0.5 over a linear one,
 * both filling the 16 x 16 view. */
static mpic lens_pic(void)
{
    mpic p = {2,
              {{0, {0, 0, 16, 16}, AA_GRADIENT_LINEAR,
                {7.479922430578072, 7.088783293502782, 7.729693329008287, 12.080037719826626, 0,
                 0},
                AA_SPREAD_PAD, 2, lens_l, 1.0},
               {0, {0, 0, 16, 16}, AA_GRADIENT_RADIAL,
                {9.499166770827133, 47.44001041579865, 40, 9.499166770827133, 47.44001041579865, 0},
                AA_SPREAD_REFLECT, 3, lens_r, 0.5}},
              {0, 0, 0},
              0};
    return p;
}

static void test_mixed_lens(void **state)
{
    (void)state;
    static const int px[3][2] = {{7, 7}, {6, 7}, {8, 7}};
    mpic p = lens_pic();
    mpic_check("radial over linear, the threshold's curve a thin lens between scan rows", &p, px,
               3);
}

/* The lens's picture with the radial layer's rectangle ending at x =
 * 7.45, across the lens (x in [7.352, 7.649]): in pixel (7, 7) the
 * threshold's curve now meets that edge, where the composite steps from
 * 0.5 C + 0.5 L to L, at the lens's two heights on x = 7.45 and where the
 * line L = 0.04045 (about 0.2 px below the lens) ends at the edge: each
 * a height where the row integral is not analytic, found by the boxes
 * that the edge crosses.  Then the same with the radial layer in linear
 * light, cut and filling the view (the oracle encodes its interpolated
 * linear channels, their change of piece at 0.0031308 a cut of its rows).
 * Against the 2-D quadrature of the picture (mpic_pixel), pixel (7, 7)
 * and its neighbours along the edge. */
static void test_mixed_edge(void **state)
{
    (void)state;
    static const int px[3][2] = {{7, 7}, {7, 6}, {7, 8}};
    mpic p = lens_pic();
    p.l[1].r[2] = 7.45;
    mpic_check("radial over linear, the lens cut by the radial layer's side", &p, px, 3);
    mpic_lin = 2u;
    mpic_check("the same, the radial layer in linear light", &p, px, 3);
    p.l[1].r[2] = 16;
    mpic_check("the radial layer in linear light filling the view", &p, px, 3);
    mpic_lin = 0;
}

/* The lens's picture with the radial layer the stroke of a cubic, 6 px
 * wide, round caps (an outline of offset pieces: harness/core/stroke.c),
 * its right side near x = 7.4546 at y = 7.5 (Python, the offset sampled at
 * 20001 parameters), across the lens (x in [7.352, 7.649]): in pixel (7,
 * 7) the threshold's curve meets the stroke's side as it met the
 * rectangle's in test_mixed_edge, now an offset curve of the cubic.  The
 * cubic's radius of curvature is at least 10.3 (the same sampling), above
 * the half width: the stroke is the tube about it, which the oracle's
 * point-in-stroke test (stroke_in, the distance to the cubic) reads.
 * Against the 2-D quadrature of the picture (mpic_pixel), pixel (7, 7) and
 * its neighbours along the side; every pixel's bound at most 1e-12. */
static const double side_cubic[9] = {4.1, -2, 5.3, 3, 3.5, 12, 5.1, 18, 3};
/* The same with its first control point on its start: B' vanishes there,
 * and the stroke's sides on t < 1/2 are offset.c's factored form. */
static const double cusp_cubic[9] = {4.1, -2, 4.1, -2, 3.5, 12, 5.1, 18, 3};

static void test_mixed_stroke(void **state)
{
    (void)state;
    static const int px[3][2] = {{7, 7}, {7, 6}, {7, 8}};
    mpic p = lens_pic();
    p.l[1].disc = 2;
    mpic_cubic = side_cubic;
    mpic_check("radial over linear, the lens cut by a stroked cubic's side", &p, px, 3);
    mpic_cubic = NULL;
}

/* An opaque scene, a linear gradient over the view and a radial one on a
 * disc (every span by the path of several gradients), where the linear
 * gradient's threshold line (t = 0.04045 / (24/255)) crosses rows at the
 * middle of a pixel's span: QAG's middle row between the breakpoints where
 * the line crosses the window's sides, in the ten pixels below (outside
 * the disc).  The isolation found 0.04045 in double at the span's first
 * midpoint and kept the whole span as the threshold's interval, with the
 * bound of the colour's spread across it: 8.7e-4 at those pixels.  The
 * SVG (a 48 x 48 scene moved by (-32, -4)) against mpic_pixel's 2-D
 * quadrature of the same picture (the bounding box's fractions worked
 * out by hand: the linear vector (0, 0) to (9.6, 48), the radial circle
 * at (18.6, 29.4) of radius 20.4, both moved), and every pixel's bound
 * at most 1e-12. */
static void test_threshold_mid_span(void **state)
{
    (void)state;
    static const char *const body =
        "<defs><linearGradient id=\"l\" x1=\"0\" y1=\"0\" x2=\"0.2\" y2=\"1\">"
        "<stop offset=\"0\" stop-color=\"#000\"/><stop offset=\"1\" stop-color=\"#181818\"/>"
        "</linearGradient><radialGradient id=\"r\" cx=\"0.4\" cy=\"0.6\" r=\"0.6\">"
        "<stop offset=\"0\" stop-color=\"#1c1c1c\"/>"
        "<stop offset=\"0.7\" stop-color=\"#040404\"/>"
        "<stop offset=\"1\" stop-color=\"#101010\"/></radialGradient></defs>"
        "<g transform=\"translate(-32 -4)\"><rect width=\"48\" height=\"48\" fill=\"url(#l)\"/>"
        "<circle cx=\"22\" cy=\"26\" r=\"17\" fill=\"url(#r)\"/></g>";
    static const int px[12][2] = {{11, 8}, {12, 8}, {13, 8}, {14, 8}, {6, 9}, {7, 9},
                                  {8, 9},  {9, 9},  {3, 10}, {4, 10}, {0, 11}, {2, 2}};
    double g24 = dec(24.0 / 255.0), g28 = dec(28.0 / 255.0), g4 = dec(4.0 / 255.0),
           g16 = dec(16.0 / 255.0);
    const aa_gradient_stop sl[2] = {{0.0, {{0, 0, 0}}, 1.0}, {1.0, {{g24, g24, g24}}, 1.0}};
    const aa_gradient_stop sr[3] = {
        {0.0, {{g28, g28, g28}}, 1.0}, {0.7, {{g4, g4, g4}}, 1.0}, {1.0, {{g16, g16, g16}}, 1.0}};
    mpic p = {2,
              {{0, {-32, -4, 16, 44}, AA_GRADIENT_LINEAR, {-32, -4, 9.6 - 32, 44, 0, 0},
                AA_SPREAD_PAD, 2, sl, 1.0},
               {1, {-10, 22, 17, 0}, AA_GRADIENT_RADIAL,
                {18.6 - 32, 29.4 - 4, 20.4, 18.6 - 32, 29.4 - 4, 0}, AA_SPREAD_PAD, 3, sr, 1.0}},
              {0, 0, 0},
              0};
    int st;
    aa_scene *sc = svg_scene("mid_span", body, &st);
    if (!sc)
        fail_msg("mid_span: %s", aa_last_error());
    aa_image ref, bound;
    aa_truth_stats stats;
    reference(sc, W, H, &ref, &bound, &stats);
    expect_bound("threshold line through the spans' middles", &stats);
    double worst = 0;
    for (int k = 0; k < 12; k++) {
        double want = mpic_pixel(&p, px[k][0], px[k][1]);
        double got = aa_pixel(&ref, px[k][0], px[k][1])[0];
        double b = *aa_pixel(&bound, px[k][0], px[k][1]);
        worst = fmax(worst, fabs(got - want));
        if (!(fabs(got - want) <= b))
            fail_msg("mid_span: pixel (%d, %d): %.17g, GSL 2-D %.17g (bound %.2g)", px[k][0],
                     px[k][1], got, want, b);
    }
    print_message("threshold line through the spans' middles: 12 pixels within %.2g of GSL 2-D\n",
                  worst);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(sc);
}

/* A radial gradient of the cone case at alpha 0.6 (focal circle of
 * radius 6 at (-12, -1), end circle of radius 6.5 at (28, 5): the focal
 * point outside the end circle, the tangent lines nearly parallel, 12.4
 * px apart at x = 0, P* far to the left) over an opaque linear gradient
 * along y, on an 8 x 8 view: the lower tangent line crosses row 7 (from
 * (0, 7.03) to (5.96, 8)), the upper one passes above the view; across
 * it the green channel jumps across the threshold (0 unpainted, above
 * 0.048 painted).  Green's threshold curve is the front arc of the
 * circle t = 0.58 (enc(0.022) (1 - t) 0.6 = 0.04045), across pixels (5,
 * 1) and (7, 7), its end on the lower line at x = 10, beyond the view;
 * blue's is a row (the linear layer's blue at 0.4 of it).  Before the
 * cone's t was bounded box by box every integrated pixel was scanned (64
 * of 64 under the box; under cone:r=1 a scan row of pixel (0, 3) was not
 * resolved within the work limit and the picture refused): none is now,
 * under either, and the bound is below 1e-12.  Against the 2-D
 * quadrature of the picture (mpic_pixel, its t from SVG's definition,
 * mlayer_cone_t) at (5, 1), (7, 7) and (2, 7). */
static const aa_gradient_stop cone_lin[2] = {{0.0, {{0.2, 0.0, 0.0}}, 1.0},
                                             {1.0, {{0.2, 0.0, 0.05}}, 1.0}};
static const aa_gradient_stop cone_rad[2] = {{0.0, {{0.5, 0.022, 0.0}}, 1.0},
                                             {1.0, {{0.35, 0.0, 0.0}}, 1.0}};

static void test_mixed_cone(void **state)
{
    (void)state;
    enum { V = 8 };
    mpic p = {2,
              {{0, {0, 0, V, V}, AA_GRADIENT_LINEAR, {-8, -4, -8, 16, 0, 0}, AA_SPREAD_PAD, 2,
                cone_lin, 1.0},
               {0, {0, 0, V, V}, AA_GRADIENT_RADIAL, {28, 5, 6.5, -12, -1, 6}, AA_SPREAD_PAD, 2,
                cone_rad, 0.6}},
              {0, 0, 0},
              0};
    static const int px[3][2] = {{5, 1}, {7, 7}, {2, 7}};
    gw = gh = V;
    aa_scene *s = mpic_scene(&p);
    for (int f = 0; f < (SAN_SUBSET ? 1 : 2); f++) {
        aa_image ref, bound;
        aa_truth_stats stats;
        support_view v = {V, V, 0, 0, 0, f ? "cone:r=1" : NULL, 1, 1, 0};
        support_reference(s, &v, &ref, &bound, &stats);
        print_message("cone over linear%s: %zu of %zu integrated pixels scanned\n",
                      f ? ", cone:r=1" : "", stats.scanned, stats.integrated);
        assert_true(stats.integrated > 0);
        assert_int_equal(stats.scanned, 0);
        expect_bound(f ? "cone over linear, cone:r=1" : "cone over linear", &stats);
        double worst = 0;
        for (int k = 0; k < 3 && !f; k++)
            for (int ch = 0; ch < 3; ch++) {
                p.ch = ch;
                double want = mpic_pixel(&p, px[k][0], px[k][1]);
                double got = aa_pixel(&ref, px[k][0], px[k][1])[ch];
                double b = *aa_pixel(&bound, px[k][0], px[k][1]);
                worst = fmax(worst, fabs(got - want));
                if (!(fabs(got - want) <= b))
                    fail_msg("cone over linear: pixel (%d, %d) channel %d: %.17g, GSL 2-D %.17g "
                             "(bound %.2g)",
                             px[k][0], px[k][1], ch, got, want, b);
            }
        if (!f)
            print_message("cone over linear: 3 pixels x 3 channels within %.2g of GSL 2-D\n",
                          worst);
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
    gw = W, gh = H;
}

/* The cone case's two other kinds at alpha 0.6 over an opaque linear
 * gradient along y (#000 at y = 2 to #404040 at y = 22, padded), the
 * stops #100000 and #603020 (their decoded values below), each against
 * the 2-D quadrature of its picture (mpic_pixel, t from SVG 2's
 * definition, mlayer_cone_t) pixel by pixel (mpic_check_px), none of
 * them scanned:
 *  - nested: the end circle (12, 12) r 3 inside the focal circle (13,
 *    12) r 10.  Red's threshold curve has its lowest point in pixel (12,
 *    2), where a row grazes it (2e-7 below 0.04045 at x = 13): with only
 *    the Lipschitz test for a painted cone layer the row's isolation ran
 *    out of work and the document was refused ("a row of the gradients'
 *    composite not resolved within the work limit").  t's second
 *    derivative along the row, -(lam0 mu1 - lam1 mu0)^2 / (4 a
 *    d^(3/2)), now bounds the Taylor test (truth.c, gen_cone_tpq);
 *  - the half-plane: the focal circle (8, 12) r 4 touching the end
 *    circle (12, 12) r 8 from inside, the edge x = 4.  Blue's curve
 *    grazes a row of pixel (8, 7) likewise (refused, the same way, after
 *    5 s of CPU); and the windows the edge crosses (columns 3 and 4 above
 *    row 11) were scanned, their boxes holding the edge taking t over
 *    the whole line: now t beyond c's least over twice b's greatest,
 *    the padded paint the last stop's; under tent:r=1 pixel (4, 8)'s
 *    window was scanned still, its slivers' strips across the edge
 *    taking E's range painted and not over the strip's whole width (now
 *    over the edge's x on the sliver's rows alone): certified now.
 * main took neither document (both 24 x 24 SVG files of these layers;
 * Chromium and resvg draw them). */
static const aa_gradient_stop nest_lin[2] = {{0.0, {{0, 0, 0}}, 1.0},
                                             {1.0,
                                              {{0.05126945837404324, 0.05126945837404324,
                                                0.05126945837404324}},
                                              1.0}};
static const aa_gradient_stop nest_rad[2] = {
    {0.0, {{0.005181516702338386, 0, 0}}, 1.0},
    {1.0, {{0.11697066775851084, 0.0295568344378088, 0.014443843596092545}}, 1.0}};

static void test_mixed_nested_half(void **state)
{
    (void)state;
    mpic p = {2,
              {{0, {0, 0, W, W}, AA_GRADIENT_LINEAR, {0, 2, 0, 22, 0, 0}, AA_SPREAD_PAD, 2,
                nest_lin, 1.0},
               {0, {0, 0, W, W}, AA_GRADIENT_RADIAL, {12, 12, 3, 13, 12, 10}, AA_SPREAD_PAD, 2,
                nest_rad, 0.6}},
              {0, 0, 0},
              0};
    static const int nest_px[2][2] = {{12, 2}, {12, 3}}, half_px[3][2] = {{8, 7}, {4, 5}, {3, 5}};
    assert_int_equal(mpic_check_px("nested cone over linear", &p, nest_px, 2), 0);
    const double half[6] = {12, 12, 8, 8, 12, 4};
    memcpy(p.l[1].p, half, sizeof half);
    assert_int_equal(mpic_check_px("half-plane over linear", &p, half_px, 3), 0);
    /* under tent:r=1 pixel (4, 8)'s window, the edge across it, certified too */
    gw = gh = W;
    aa_scene *s = mpic_scene(&p);
    expect_certified("half-plane over linear", s, 4, 8, "tent:r=1");
    aa_scene_free(s);
    gw = W, gh = H;
}

/* A cone-case radial gradient (focal circle (3, 10) r 1.5 outside the end
 * circle (14, 12) r 5; its stops and the linear gradient under it as
 * test_mixed_nested_half's) at alpha 0.6: inside the wedge t is (b +
 * sqrt(L0 L1)) / a, so across the lower tangent line L0 = 0 the
 * composite E moves like sqrt(L0), and the threshold's curve E = 0.04045
 * ends on the line, tangent to it, where E on the line (t = b / a) is
 * 0.04045: green's at (3.57, 8.41), blue's at (3.99, 8.35), both in pixel
 * (3, 8).  Its windows' boxes about those points were halved without end
 * and left to the scan (1 pixel under the box, 4 under tent:r=1 and
 * cone:r=1); now certified.  Pixel (3, 8) against the 2-D quadrature of
 * SVG 2's definition (mpic_pixel, mlayer_cone_t; its rows' events found
 * by sampling, the touching heights among them), and its window and
 * (4, 7)'s, both touching points in them, under tent:r=1 and cone:r=1
 * certified within 1e-12.  Then the end circle (36, 11) r 6.5 and the
 * focal circle (-4, 5) r 6, the lines nearly parallel, green's touching
 * point at (11.17, 1.03): under tent:r=1 pixel (10, 0)'s rows next to
 * that height put a threshold's place within 1e-19 of the line in the
 * square root of the distance, where the weight's fit over the piece's
 * x range, below x's resolution, was 0 / 0 and the row was refused
 * (truth.c, gen_rule_bound); certified now too. */
static void test_mixed_cone_touch(void **state)
{
    (void)state;
    mpic p = {2,
              {{0, {0, 0, W, W}, AA_GRADIENT_LINEAR, {0, 2, 0, 22, 0, 0}, AA_SPREAD_PAD, 2,
                nest_lin, 1.0},
               {0, {0, 0, W, W}, AA_GRADIENT_RADIAL, {14, 12, 5, 3, 10, 1.5}, AA_SPREAD_PAD, 2,
                nest_rad, 0.6}},
              {0, 0, 0},
              0};
    static const int px[1][2] = {{3, 8}}, fpx[2][2] = {{3, 8}, {4, 7}};
    static const char *const filt[2] = {"tent:r=1", "cone:r=1"};
    assert_int_equal(mpic_check_px("cone over linear, the curve touching a tangent line", &p, px,
                                   1),
                     0);
    gw = gh = W;
    for (int pass = 0; pass < 2; pass++) {
        if (pass) {
            const double par[6] = {36, 11, 6.5, -4, 5, 6};
            memcpy(p.l[1].p, par, sizeof par);
        }
        aa_scene *s = mpic_scene(&p);
        for (int f = 0; f < (pass ? 1 : 2); f++)
            for (int k = 0; k < (pass ? 1 : 2); k++)
                expect_certified("cone touching", s, pass ? 10 : fpx[k][0],
                                 pass ? 0 : fpx[k][1], filt[f]);
        aa_scene_free(s);
    }
    gw = W, gh = H;
}

/* Which pixels take the certified step and which the scan, as truth.c's
 * opening comment ("several gradients") states the rule: the lens's
 * scene, both layers filling the view (no edge in any window, a linear
 * and a radial gradient in sRGB), and the same with the radial layer's
 * rectangle ending at x = 8.5 (the windows of column 8 hold that edge, a
 * line, both layers painting in each: certified box by box), with the
 * radial layer in linear light, and with 32 more gradient layers (34 in
 * all, more than GEN_LAYERS, each a small square behind the lens's
 * opaque linear layer) have no pixel scanned, nor with the radial
 * layer's focal point moved outside its circle (the cone case; every
 * integrated pixel, 256, was while its kind left it to the scan); with
 * the edge at x = 8.5 under the cone filter of radius 1/2 (a radial
 * filter) none (the 16 windows of column 8 were while its slivers took a
 * crude bound); with the radial layer the stroke of test_mixed_stroke
 * (its sides offset curves of the cubic, taken box by box by
 * thr_offset_x; 32 pixels scanned when those windows were), and of that
 * cubic with a cusp at its start (the sides next to it in offset.c's
 * factored form; 36 when those were), none is. */
static void test_mixed_which_step(void **state)
{
    (void)state;
    static const char *what[8] = {"filling the view", "ending at x = 8.5", "in linear light",
                                  "of the cone case", "over 32 more gradients",
                                  "ending at x = 8.5, under cone:r=0.5",
                                  "a stroked cubic (test_mixed_stroke)",
                                  "a stroked cubic with a cusp at its start"};
    mpic p = lens_pic();
    gw = gh = W;
    for (int c = 0; c < 8; c++) {
        p.l[1].disc = c >= 6 ? 2 : 0;
        mpic_cubic = c == 6 ? side_cubic : c == 7 ? cusp_cubic : NULL;
        p.l[1].r[2] = c == 1 || c == 5 ? 8.5 : 16;
        p.l[1].p[4] = c == 3 ? 47.44001041579865 - 45 : 47.44001041579865; /* fy */
        mpic_lin = c == 2 ? 2u : 0u;
        aa_scene *s = c == 4 ? NULL : mpic_scene(&p);
        mpic_lin = 0;
        mpic_cubic = NULL;
        if (c == 4) { /* 34 gradient layers: 32 behind the lens's, a square of one each */
            s = aa_scene_new((aa_rgb){{0, 0, 0}});
            for (int k = 0; k < 34; k++) { /* front first: the lens's radial, linear, then */
                const mlayer *m = &p.l[k == 0 ? 1 : 0];
                double x = 0.5 * (k - 2);
                if (k < 2)
                    rect_px(s, (aa_rgb){{0, 0, 0}}, m->r[0], m->r[1], m->r[2], m->r[3]);
                else
                    rect_px(s, (aa_rgb){{0, 0, 0}}, x, 15.5, x + 0.25, 15.75);
                aa_gradient g = grad_px(m->kind, m->spread, m->p, m->st, m->n);
                assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
                if (m->alpha != 1.0)
                    assert_int_equal(aa_scene_set_alpha(s, m->alpha), AA_OK);
            }
            assert_int_equal(aa_scene_finish(s), AA_OK);
        }
        aa_image ref, bound;
        aa_truth_stats stats;
        support_view v = {W, W, 0, 0, 0, c == 5 ? "cone:r=0.5" : NULL, 1, 1, 0};
        support_reference(s, &v, &ref, &bound, &stats);
        print_message("radial layer %s: %zu of %zu integrated pixels scanned\n", what[c],
                      stats.scanned, stats.integrated);
        assert_true(stats.integrated > 0);
        assert_int_equal(stats.scanned, 0);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
    gw = W, gh = H;
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_pad),     cmocka_unit_test(test_repeat_reflect),
        cmocka_unit_test(test_against_2d),     cmocka_unit_test(test_methods),
        cmocka_unit_test(test_refusals),       cmocka_unit_test(test_radial_sampled),
        cmocka_unit_test(test_svg_linear),     cmocka_unit_test(test_svg_monotone),
        cmocka_unit_test(test_svg_degenerate), cmocka_unit_test(test_svg_refusals),
        cmocka_unit_test(test_cache),          cmocka_unit_test(test_radial_reference),
        cmocka_unit_test(test_several_gradients),
        cmocka_unit_test(test_threshold_tangent),
        cmocka_unit_test(test_many_layers_closed),
        cmocka_unit_test(test_many_layers_stack),
        cmocka_unit_test(test_many_layers_mixed),
        cmocka_unit_test(test_stack_close_roots),
        cmocka_unit_test(test_mixed_tangent),
        cmocka_unit_test(test_mixed_stop_circle),
        cmocka_unit_test(test_mixed_lens),
        cmocka_unit_test(test_mixed_edge),
        cmocka_unit_test(test_mixed_stroke),
        cmocka_unit_test(test_mixed_which_step),
        cmocka_unit_test(test_mixed_cone),
        cmocka_unit_test(test_mixed_nested_half),
        cmocka_unit_test(test_mixed_cone_touch),
        cmocka_unit_test(test_threshold_mid_span),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
