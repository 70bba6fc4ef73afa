/*
 * test_peers.c: the peer rasterizers (freetype, stb, cairo, agg) on scenes whose
 * coverage is known in closed form, and their refusals.
 *
 * Known answers, independent of the code under test:
 *  - an axis-aligned rectangle: a pixel's coverage is the overlap of two
 *    intervals in x times that in y;
 *  - a half-plane x < a + b y: a pixel's coverage is
 *    (F(a + b (j+1) - i) - F(a + b j - i)) / b with F the antiderivative of
 *    clamp(t, 0, 1) (F = 0, t^2/2, t - 1/2 on t < 0, [0, 1], > 1);
 *  - one crow band (two parabolic arcs): its area is g0 - (c0 - c1)/12
 *    (patterns/crow.c, integral of the difference of the two parabolas),
 *    so the image's sum is W H times that.
 * Every vertex lies on a 1/64 px grid, so FreeType's 26.6 and Cairo's 24.8
 * fixed point and stb's floats hold it exactly; the images are powers of
 * two, so placing the scene (u = W x) is exact too.
 *
 * Tolerances are each peer's own quantisation:
 *  - 8-bit coverage: stb rounds to the nearest 1/255 (error <= 0.5/255);
 *    FreeType takes floor(256 a) clamped to 255 and we divide by 255
 *    (error <= 1/255); Cairo's A8 surface rounds its 8-bit alpha (1/255);
 *  - positions: FreeType computes cell crossings in 1/256 px (PIXEL_BITS 8),
 *    another 1/256 per edge pixel: 2/255 in all; Cairo's "best" and "good"
 *    scan converters sample sub-rows (tor scan converter, a grid of 15 and
 *    4 rows in 1.16) and their polygon areas are exact on axis-aligned
 *    edges on that grid (rectangle: 1/255); a sloped edge of slope b
 *    (dx/dy) is integrated by sub-rows, an error up to b/rows per pixel.
 * The crow band's sum carries flattening: each peer's bound is its
 * tolerance (px) times the arcs' length (2 arcs of about H px) over W H.
 * Elliptical arcs (each peer draws them its own way): see "elliptical
 * arcs" below.
 */
#include "bench.h"
#include "peer.h"
#include "scenes.h"
#include "support.h"

#include <fcntl.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#define W 16
#define H 16

typedef struct peer_case {
    const char *spec;
    double tol_rect, tol_slope; /* max error: rectangle, half-plane of slope 5/16 */
    double flat;                /* flattening tolerance, px */
} peer_case;

static const peer_case cases[] = {
    {"freetype", 1.0 / 255 + 1e-12, 2.0 / 255 + 1e-12, 0.25},
    {"stb", 0.5 / 255 + 1e-6, 0.5 / 255 + 1e-6, 0.35},
    {"stb:flatness=0.01", 0.5 / 255 + 1e-6, 0.5 / 255 + 1e-6, 0.01},
    {"cairo", 1.0 / 255 + 1e-12, 1.0 / 255 + 0.3125 / 15, 0.1},
    {"cairo:aa=good", 1.0 / 255 + 1e-12, 1.0 / 255 + 0.3125 / 4, 0.1},
    {"cairo:aa=good,tolerance=0.01", 1.0 / 255 + 1e-12, 1.0 / 255 + 0.3125 / 4, 0.01},
};
#define NCASES (sizeof cases / sizeof cases[0])

/* A one-layer grey scene (white on black) of one closed polygon given in
 * pixels of a W x H image (stored in pattern units). */
static aa_scene *polygon(const double *xy, int n, aa_fill_rule rule)
{
    double uv[16];
    assert_true(n <= 8);
    for (int k = 0; k < n; k++)
        uv[2 * k] = xy[2 * k] / W, uv[2 * k + 1] = xy[2 * k + 1] / H;
    return scenes_polygon(uv, n, (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}}, rule);
}

/* Render a scene with a method spec; returns the status. */
static int render(const char *spec, const aa_scene *scene, const char *filter, int w, int h,
                  int threads, aa_image *out)
{
    const support_view v = {.w = w, .h = h, .filter = filter, .seed = 1, .threads = threads};
    return support_render_view(spec, scene, &v, out, NULL);
}

static double overlap(double a0, double a1, double b0, double b1)
{
    double lo = fmax(a0, b0), hi = fmin(a1, b1);
    return hi > lo ? hi - lo : 0.0;
}

/* The largest error against want(i, j); every channel equal. */
static double max_error(const aa_image *img, double (*want)(int, int))
{
    double worst = 0.0;
    for (int j = 0; j < img->h; j++)
        for (int i = 0; i < img->w; i++) {
            const double *px = aa_pixel(img, i, j);
            assert_true(px[0] == px[1] && px[1] == px[2]);
            worst = fmax(worst, fabs(px[0] - want(i, j)));
        }
    return worst;
}

static const double RX0 = 2.25, RX1 = 7.625, RY0 = 1.5, RY1 = 5.125 + 8.0;

static double rect_cover(int i, int j)
{
    return overlap(RX0, RX1, i, i + 1.0) * overlap(RY0, RY1, j, j + 1.0);
}

static void test_rectangle(void **state)
{
    (void)state;
    const double xy[] = {RX0, RY0, RX1, RY0, RX1, RY1, RX0, RY1};
    for (int rule = 0; rule < 2; rule++) {
        aa_scene *s = polygon(xy, 4, (aa_fill_rule)rule);
        for (size_t k = 0; k < NCASES; k++) {
            aa_image img;
            support_render(cases[k].spec, s, "box", W, H, 2, &img, NULL);
            double e = max_error(&img, rect_cover);
            print_message("rectangle %-30s rule %d: max error %.3e (bound %.3e)\n",
                          cases[k].spec, rule, e, cases[k].tol_rect);
            if (!(e <= cases[k].tol_rect))
                fail_msg("%s: rectangle max error %.3e above %.3e", cases[k].spec, e,
                         cases[k].tol_rect);
            aa_image_free(&img);
        }
        aa_scene_free(s);
    }
}

/* Half-plane x < A + B y, as a polygon reaching beyond the image. */
static const double A = 3.5625, B = 0.3125;

static double F(double t) { return t < 0 ? 0.0 : t > 1 ? t - 0.5 : 0.5 * t * t; }

static double half_cover(int i, int j)
{
    return (F(A + B * (j + 1) - i) - F(A + B * j - i)) / B;
}

static void test_half_plane(void **state)
{
    (void)state;
    const double xy[] = {-4, -1, A - B, -1, A + 17 * B, 17, -4, 17};
    aa_scene *s = polygon(xy, 4, AA_FILL_NONZERO);
    for (size_t k = 0; k < NCASES; k++) {
        aa_image img;
        support_render(cases[k].spec, s, "box", W, H, 1, &img, NULL);
        double e = max_error(&img, half_cover);
        print_message("half-plane %-30s: max error %.3e (bound %.3e)\n", cases[k].spec, e,
                      cases[k].tol_slope);
        if (!(e <= cases[k].tol_slope))
            fail_msg("%s: half-plane max error %.3e above %.3e", cases[k].spec, e,
                     cases[k].tol_slope);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* Many thin rectangles, two per pixel column: [i + 1/8, i + 3/8] and
 * [i + 5/8, i + 7/8] in x, [2.25, 13.5] in y, on a 1024 x 16 image.  Each
 * row crosses 4096 edges: more than FreeType 2.12's cell pool holds for one
 * row, so it renders in clipped tiles, which must not show (the coverage is
 * the closed-form overlap, within 1/255, in every pixel). */
static double thin_cover(int i, int j)
{
    (void)i;
    return 0.5 * overlap(2.25, 13.5, j, j + 1.0);
}

static void test_many_edges(void **state)
{
    (void)state;
    const int w = 1024, h = 16;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    for (int i = 0; i < w; i++)
        for (int k = 0; k < 2; k++) {
            double x0 = i + 0.125 + 0.5 * k, x1 = x0 + 0.25;
            scenes_rect(s, x0 / w, 2.25 / h, x1 / w, 13.5 / h);
        }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const char *peers[] = {"freetype", "stb", "cairo"};
    for (int k = 0; k < 3; k++) {
        aa_image img;
        support_render(peers[k], s, "box", w, h, 2, &img, NULL);
        double e = max_error(&img, thin_cover);
        print_message("4096 edges a row, %-8s: max error %.3e\n", peers[k], e);
        if (!(e <= 1.0 / 255 + 1e-6))
            fail_msg("%s: max error %.3e above 1/255 with 4096 edges a row", peers[k], e);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* One crow band: arcs are curves, not chords (a chord would lose about
 * c/6 of area per arc). */
static void test_crow_band_area(void **state)
{
    (void)state;
    const int n = 256;
    const double g0 = 0.25, c0 = 0.6; /* crow:curves=2: c1 = 0 */
    aa_scene *s = scenes_pattern("crow:curves=2,gap0=0.25,kmax=0.6");
    double want = g0 - c0 / 12.0;
    for (size_t k = 0; k < NCASES; k++) {
        aa_image img;
        support_render(cases[k].spec, s, "box", n, n, 2, &img, NULL);
        double area = support_channel_mean(&img, 0);
        /* flattening: at most `flat` px over two arcs of ~n px, plus 8-bit
         * rounding that does not cancel (at most 1/255 on 2 n edge pixels) */
        double bound = (cases[k].flat * 2.0 * n + 2.0 * n / 255.0) / ((double)n * n);
        print_message("crow band %-30s: area %.6f, closed form %.6f, bound %.2e\n",
                      cases[k].spec, area, want, bound);
        if (!(fabs(area - want) <= bound))
            fail_msg("%s: area %.9f, closed form %.9f (bound %.2e)", cases[k].spec, area,
                     want, bound);
        /* and not the chords' area, which differs by c0/6 */
        assert_true(fabs(area - want) < c0 / 60.0);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* ---- elliptical arcs ----
 *
 * Each peer approximates an arc its own way (algorithms/README.md): the
 * outline it fills, P, lies between the ellipse E shrunk and grown about
 * its centre, (1 - s_in) E and (1 + s_out) E.  For a convex E containing the
 * disc of radius smin (its shorter semi-axis) about its centre,
 * (1 - s) E + s smin B is inside E, so a polygon within d px inside the
 * ellipse lies outside (1 - d/smin) E; likewise a curve within d px
 * outside lies inside (1 + d/smin) E; and the cubics of
 * aa_peer_arc_cubics lie inside (1 + e) E, e = 2.7253e-4 (peer.h, derived
 * in peer.c; here taken as the bound it is, not recomputed).
 *   - FreeType flattens a cubic until both controls are within 1/6 px per
 *     coordinate of the chord's trisection points (ftgrays.c,
 *     gray_render_cubic: |2 P0 - 3 P1 + P3| <= ONE_PIXEL/2), so the curve is
 *     within (3/4)(1/6) sqrt 2 = 0.177 px of its chord; positions rounded
 *     to 1/64 px (0.011 px): d_in = 0.19, d_out = 0.02 px beyond e;
 *   - stb splits a cubic until long^2 - chord^2 <= flatness^2 (control
 *     polygon length `long`), which keeps it within flatness/2 of the chord
 *     (a polygon through a point h off the chord is at least
 *     sqrt(chord^2 + 4 h^2) long); floats: 1e-4 px;
 *   - Cairo's arc is cubics within `tolerance` of the circle, flattened
 *     within `tolerance`: d_in = d_out = tolerance + 1/256 (24.8);
 *   - AGG's arc is chords within 0.125/scale px of the ellipse, inside it
 *     (agg.cpp, put_arc): d_in = 0.125/scale + 1/256, d_out = 1/256.
 * Known answers, independent of the peers: the area of E is pi |det M|
 * (M = [u v]), so area(P) lies in [pi |det M| (1 - s_in)^2,
 * pi |det M| (1 + s_out)^2]; a pixel wholly inside (1 - s_in) E is wholly
 * inside P (value exactly 1), one wholly outside (1 + s_out) E wholly
 * outside (exactly 0); the others ("band" pixels) are off the exact
 * coverage of P by at most q each (8-bit rounding; Cairo's best scan
 * converter also samples 15 sub-rows a pixel: 1/15).  So the band pixels'
 * sum is area(P) minus the inside pixels' count, within their number
 * times q.  A peer that drops an arc, draws it on the wrong side or maps
 * it by the transposed matrix misses by whole pixels. */

typedef struct arc_case {
    const char *spec;
    double d_in, d_out, e, q; /* px, px, relative, per band pixel */
} arc_case;

static const arc_case arc_cases[] = {
    {"freetype", 0.19, 0.02, 2.7253e-4, 2.0 / 255},
    {"stb", 0.35 / 2 + 1e-4, 1e-4, 2.7253e-4, 1.0 / 255},
    {"stb:flatness=0.02", 0.01 + 1e-4, 1e-4, 2.7253e-4, 1.0 / 255},
    {"cairo", 0.1 + 1.0 / 256, 0.1 + 1.0 / 256, 0.0, 1.0 / 255 + 1.0 / 15},
    {"cairo:tolerance=0.01", 0.01 + 1.0 / 256, 0.01 + 1.0 / 256, 0.0, 1.0 / 255 + 1.0 / 15},
    {"agg", 0.125 + 1.0 / 256, 1.0 / 256, 0.0, 1.0 / 255},
    {"agg:scale=16", 0.125 / 16 + 1.0 / 256, 1.0 / 256, 0.0, 1.0 / 255},
};
#define NARC (sizeof arc_cases / sizeof arc_cases[0])

#define AW 128 /* the ellipse images: AW x AW */

/* An ellipse c + M (cos t, sin t) in pattern units, M = [u v]. */
typedef struct ellipse {
    double cx, cy, ux, uy, vx, vy;
} ellipse;

static double ell_x(const ellipse *e, double t) { return e->cx + e->ux * cos(t) + e->vx * sin(t); }
static double ell_y(const ellipse *e, double t) { return e->cy + e->uy * cos(t) + e->vy * sin(t); }

/* A white ellipse on black drawn as arcs at the angles t[0] .. t[n] (one
 * closed path; t[n] - t[0] = +-2 pi). */
static aa_scene *ellipse_scene(const ellipse *e, const double *t, int n, aa_fill_rule rule)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, rule), AA_OK);
    assert_int_equal(aa_scene_move_to(s, ell_x(e, t[0]), ell_y(e, t[0])), AA_OK);
    for (int k = 0; k < n; k++) {
        double x = k + 1 == n ? ell_x(e, t[0]) : ell_x(e, t[k + 1]);
        double y = k + 1 == n ? ell_y(e, t[0]) : ell_y(e, t[k + 1]);
        int st = aa_scene_arc_to(s, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, t[k], t[k + 1],
                                 x, y);
        if (st)
            fail_msg("aa_scene_arc_to: %s", aa_last_error());
    }
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The ellipse in pixels: |M^-1 (p - c)|, the "radius" of point p (1 on
 * the ellipse). */
typedef struct ellipse_px {
    double cx, cy, a, b, c, d; /* centre; M^-1 = [[a, b], [c, d]] */
    double det, smin;          /* det M, shorter semi-axis (px) */
} ellipse_px;

static ellipse_px ellipse_pixels(const ellipse *e)
{
    ellipse_px p;
    double ux = AW * e->ux, uy = AW * e->uy, vx = AW * e->vx, vy = AW * e->vy;
    p.cx = AW * e->cx, p.cy = AW * e->cy;
    p.det = ux * vy - vx * uy;
    p.a = vy / p.det, p.b = -vx / p.det, p.c = -uy / p.det, p.d = ux / p.det;
    /* singular values: the square roots of the eigenvalues of M^T M */
    double tr = ux * ux + uy * uy + vx * vx + vy * vy;
    p.smin = sqrt((tr - sqrt(tr * tr - 4 * p.det * p.det)) / 2);
    return p;
}

/* Point (x, y) px in the unit circle's coordinates. */
static void to_circle(const ellipse_px *p, double x, double y, double *X, double *Y)
{
    *X = p->a * (x - p->cx) + p->b * (y - p->cy);
    *Y = p->c * (x - p->cx) + p->d * (y - p->cy);
}

/* Distance from the origin to segment (x0, y0) - (x1, y1). */
static double seg_dist(double x0, double y0, double x1, double y1)
{
    double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? -(x0 * dx + y0 * dy) / l2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(x0 + t * dx, y0 + t * dy);
}

/* Pixel (i, j) against the ellipse scaled by `scale`: +1 wholly inside,
 * -1 wholly outside, 0 neither.  In the circle's coordinates the pixel is
 * a parallelogram; it is inside the disc of radius `scale` when its four
 * corners are (both convex), outside when the origin is outside it and
 * farther than `scale` from its four sides. */
static int pixel_side(const ellipse_px *p, int i, int j, double scale)
{
    double X[4], Y[4];
    const int ci[4] = {0, 1, 1, 0}, cj[4] = {0, 0, 1, 1};
    int inside = 1, origin_in = 1, sign = 0;
    double dmin = INFINITY;
    for (int k = 0; k < 4; k++)
        to_circle(p, i + ci[k], j + cj[k], &X[k], &Y[k]);
    for (int k = 0; k < 4; k++) {
        int l = (k + 1) % 4;
        inside &= hypot(X[k], Y[k]) < scale;
        dmin = fmin(dmin, seg_dist(X[k], Y[k], X[l], Y[l]));
        double cross = X[k] * Y[l] - Y[k] * X[l]; /* origin's side of edge k */
        int sg = cross > 0 ? 1 : cross < 0 ? -1 : 0;
        if (sg && sign && sg != sign)
            origin_in = 0;
        if (sg)
            sign = sg;
    }
    if (inside)
        return 1;
    return !origin_in && dmin > scale ? -1 : 0;
}

static void check_ellipse(const ellipse *e, const double *t, int n, aa_fill_rule rule,
                          const char *name)
{
    aa_scene *s = ellipse_scene(e, t, n, rule);
    ellipse_px p = ellipse_pixels(e);
    for (size_t k = 0; k < NARC; k++) {
        const arc_case *c = &arc_cases[k];
        double s_in = c->d_in / p.smin, s_out = c->e + c->d_out / p.smin;
        aa_image img;
        support_render(c->spec, s, "box", AW, AW, 2, &img, NULL);
        int nin = 0, nband = 0, bad = 0;
        double band_sum = 0.0;
        for (int j = 0; j < AW; j++)
            for (int i = 0; i < AW; i++) {
                double v = aa_pixel(&img, i, j)[0];
                if (pixel_side(&p, i, j, 1.0 - s_in) > 0) {
                    nin++;
                    bad += v != 1.0;
                } else if (pixel_side(&p, i, j, 1.0 + s_out) < 0) {
                    bad += v != 0.0;
                } else {
                    nband++;
                    band_sum += v;
                }
            }
        double a_lo = M_PI * fabs(p.det) * (1 - s_in) * (1 - s_in) - nin - nband * c->q;
        double a_hi = M_PI * fabs(p.det) * (1 + s_out) * (1 + s_out) - nin + nband * c->q;
        print_message("%-10s %-22s area %.4f px^2 (ellipse %.4f), band sum %.4f in [%.4f, "
                      "%.4f], %d band pixels, %d wrong inside or outside\n",
                      name, c->spec, support_channel_mean(&img, 0) * AW * AW,
                      M_PI * fabs(p.det), band_sum, a_lo, a_hi, nband, bad);
        if (bad)
            fail_msg("%s %s: %d pixels wholly inside or outside are not 1 or 0", name,
                     c->spec, bad);
        if (!(band_sum >= a_lo && band_sum <= a_hi))
            fail_msg("%s %s: the band pixels sum to %.6f, outside [%.6f, %.6f]", name,
                     c->spec, band_sum, a_lo, a_hi);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

/* aa_peer_arc_cubics on its own: ends exact, pieces of equal angle at most
 * 90 degrees, every point of every cubic, mapped back to the unit circle
 * by M^-1, at a radius in [1, 1 + e(h)] with e(h) = sqrt(1 + (4/27)
 * sin^6(h/4)/cos^2(h/4)) - 1 (Dokken and Daehlen 1990, as Cairo's arc
 * code quotes it), which a quarter turn reaches: its maximum 2.7253e-4 is
 * attained near t = 0.21 of each piece. */
static void test_arc_cubics(void **state)
{
    (void)state;
    const struct {
        double c[6], t0, t1;
        int n;
    } arcs[] = {
        {{3.0, -2.0, 40.0, 0.0, 0.0, 40.0}, 0.0, 2 * M_PI, 4},
        {{3.0, -2.0, 30.0, 10.0, 5.0, -25.0}, 0.3, 0.3 - 2 * M_PI, 4},
        {{0.5, 0.25, 7.0, 1.0, -2.0, 9.0}, 1.0, 2.0, 1},
        {{0.5, 0.25, 7.0, 1.0, -2.0, 9.0}, -1.0, 2.5, 3},
    };
    for (size_t k = 0; k < sizeof arcs / sizeof arcs[0]; k++) {
        aa_edge e = {0};
        const double *c = arcs[k].c;
        e.quad = 3, e.cx = c[0], e.cy = c[1], e.ux = c[2], e.uy = c[3], e.vx = c[4], e.vy = c[5];
        e.t0 = arcs[k].t0, e.t1 = arcs[k].t1;
        e.x0 = e.cx + e.ux * cos(e.t0) + e.vx * sin(e.t0);
        e.y0 = e.cy + e.uy * cos(e.t0) + e.vy * sin(e.t0);
        e.x1 = e.cx + e.ux * cos(e.t1) + e.vx * sin(e.t1) + 1e-13; /* exactly as given */
        e.y1 = e.cy + e.uy * cos(e.t1) + e.vy * sin(e.t1);
        double cub[AA_PEER_ARC_CUBICS][6];
        int n = aa_peer_arc_cubics(&e, cub);
        assert_int_equal(n, arcs[k].n);
        assert_true(cub[n - 1][4] == e.x1 && cub[n - 1][5] == e.y1);
        double h = (e.t1 - e.t0) / n;
        double want = sqrt(1 + 4.0 / 27 * pow(sin(h / 4), 6) / pow(cos(h / 4), 2)) - 1;
        double det = e.ux * e.vy - e.vx * e.uy, lo = INFINITY, hi = -INFINITY;
        double px = e.x0, py = e.y0;
        for (int q = 0; q < n; q++) {
            for (int s = 0; s <= 1000; s++) {
                double t = s / 1000.0, a = (1 - t) * (1 - t) * (1 - t), b = 3 * t * (1 - t) * (1 - t);
                double cc = 3 * t * t * (1 - t), d = t * t * t;
                double x = a * px + b * cub[q][0] + cc * cub[q][2] + d * cub[q][4] - e.cx;
                double y = a * py + b * cub[q][1] + cc * cub[q][3] + d * cub[q][5] - e.cy;
                double X = (e.vy * x - e.vx * y) / det, Y = (-e.uy * x + e.ux * y) / det;
                double r = hypot(X, Y) - 1;
                lo = fmin(lo, r), hi = fmax(hi, r);
            }
            px = cub[q][4], py = cub[q][5];
        }
        print_message("arc %zu: %d cubics, radius error in [%.3e, %.6e], closed form %.6e\n",
                      k, n, lo, hi, want);
        assert_true(lo >= -1e-12);
        assert_true(hi <= want * (1 + 1e-6) + 1e-12 && hi >= want * 0.999);
    }
}

/* A disc of two half arcs (t increasing), nonzero. */
static void test_arc_disc(void **state)
{
    (void)state;
    const ellipse e = {0.5 + 3.0 / 1024, 0.5 - 5.0 / 1024, 0.39, 0.0, 0.0, 0.39};
    const double t[] = {0.0, M_PI, 2 * M_PI};
    check_ellipse(&e, t, 2, AA_FILL_NONZERO, "disc");
}

/* A slanted ellipse of conjugate (not perpendicular) semi-diameters, one
 * arc of a whole turn with t decreasing, even-odd: the transposed matrix
 * draws another ellipse, which the inside and outside pixels catch. */
static void test_arc_ellipse_turn(void **state)
{
    (void)state;
    const ellipse e = {0.52, 0.47, 0.3, 0.1, 0.05, 0.25};
    const double t[] = {0.3, 0.3 - 2 * M_PI};
    check_ellipse(&e, t, 1, AA_FILL_EVENODD, "turn");
}

/* The same ellipse as three arcs of uneven angles, one of 5 degrees. */
static void test_arc_ellipse_pieces(void **state)
{
    (void)state;
    const ellipse e = {0.47, 0.52, -0.12, 0.28, 0.31, 0.02};
    const double t[] = {1.0, 3.5, 3.5 + 5 * M_PI / 180, 1.0 + 2 * M_PI};
    check_ellipse(&e, t, 3, AA_FILL_NONZERO, "pieces");
}

/* ---- Painting layers (peer.h, "Painted") ----
 *
 * Scenes of colour, of several layers or translucent are painted layer by
 * layer by every peer: its coverage a of each layer composited over what
 * is below in linear light, v = a inside + (1 - a) v, inside the layer's
 * colour (alpha 1) or its colour over v in sRGB-encoded values (the
 * scene's rule, IEC 61966-2-1 written out here).  Known answers:
 *  - two red rectangles sharing the edge x = 4.5 (the middle of column 4)
 *    on black: every other column is red exactly (full coverage is
 *    255/255 in each peer); column 4 is covered 1/2 by each, so it is
 *    1 - (1 - 1/2)^2 = 3/4 red (conflation: the background shows through
 *    the seam), where the exact reference is 1.  1 - (1 - a)(1 - b) moves
 *    by at most |da| + |db|, and each peer's 8-bit coverage of 1/2 is
 *    within 1/255 of it (the header's 8-bit tolerances; the edge x = 4.5
 *    is on every fixed-point grid), so 2/255 in all;
 *  - the same seam between two even-odd layers, each a rectangle holding
 *    a hole elsewhere: the same 3/4, and the holes' whole pixels black
 *    (stb takes only even-odd layers whose regions are wound once, and
 *    refuses the hole wound as its rectangle, winding 2);
 *  - a white rectangle of alpha 1/2 over all of black: encoded 1/2
 *    exactly, and blue in front of part of it: blue exactly.
 * Groups of opacity and clips: test_peer_clips.c. */
static double srgb_decode_here(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

static void rect_layer(aa_scene *s, aa_rgb c, double x0, double y0, double x1, double y1)
{
    assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
    scenes_rect(s, x0 / W, y0 / H, x1 / W, y1 / H);
}

static const char *const painters[] = {"freetype", "stb", "cairo", "cairo:aa=good", "agg"};
#define NPAINTERS (sizeof painters / sizeof painters[0])

/* The seam at x = 4.5 between layers 0 and 1 of s (rows all alike): column
 * 4 3/4 red within 2/255, the others red exactly outside `hole` (a
 * predicate on the pixel: black exactly there). */
static void check_seam(const char *spec, const aa_scene *s, int (*hole)(int i, int j))
{
    aa_image img;
    if (render(spec, s, "box", W, H, 2, &img))
        fail_msg("%s: %s", spec, aa_last_error());
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const double *px = aa_pixel(&img, i, j);
            double want = hole && hole(i, j) ? 0.0 : 1.0;
            if (i == 4) {
                if (!(fabs(px[0] - 0.75) <= 2.0 / 255 + 1e-12))
                    fail_msg("%s: seam pixel (4, %d) red %.6f, not 3/4 within 2/255", spec, j,
                             px[0]);
            } else if (px[0] != want) {
                fail_msg("%s: pixel (%d, %d) red %.17g, not %g", spec, i, j, px[0], want);
            }
            if (!(px[1] == 0.0 && px[2] == 0.0))
                fail_msg("%s: pixel (%d, %d) green %g, blue %g, not 0", spec, i, j, px[1], px[2]);
        }
    print_message("%-14s the seam's column reads %.4f red (3/4 by conflation), the exact "
                  "reference 1\n",
                  spec, aa_pixel(&img, 4, 0)[0]);
    aa_image_free(&img);
}

/* The holes of the even-odd seam scene: pixels [1, 3) x [2, 6) and
 * [8, 12) x [10, 14). */
static int evenodd_hole(int i, int j)
{
    return (i >= 1 && i < 3 && j >= 2 && j < 6) || (i >= 8 && i < 12 && j >= 10 && j < 14);
}

/* Red rectangle [x0, x1] x [0, H] px with the hole [hx0, hx1] x [hy0, hy1]
 * wound as the rectangle, or the other way round if `reversed`. */
static void holed_rect(aa_scene *s, double x0, double x1, const double h[4], int reversed)
{
    scenes_rect(s, x0 / W, 0, x1 / W, 1);
    if (!reversed) {
        scenes_rect(s, h[0] / W, h[1] / H, h[2] / W, h[3] / H);
        return;
    }
    const double xy[] = {h[0] / W, h[1] / H, h[0] / W, h[3] / H,
                         h[2] / W, h[3] / H, h[2] / W, h[1] / H};
    scenes_path(s, xy, 4);
}

/* Two even-odd red layers meeting at x = 4.5, holed as evenodd_hole. */
static aa_scene *evenodd_seam(int reversed)
{
    const aa_rgb red = {{1, 0, 0}};
    const double h0[4] = {1, 2, 3, 6}, h1[4] = {8, 10, 12, 14};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_EVENODD), AA_OK);
    holed_rect(s, 0, 4.5, h0, reversed);
    assert_int_equal(aa_scene_layer(s, red, AA_FILL_EVENODD), AA_OK);
    holed_rect(s, 4.5, W, h1, reversed);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_painted(void **state)
{
    (void)state;
    const aa_rgb red = {{1, 0, 0}}, white = {{1, 1, 1}}, blue = {{0, 0, 1}};
    /* the seam */
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_layer(s, red, 0, 0, 4.5, H);
    rect_layer(s, red, 4.5, 0, W, H);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    for (size_t k = 0; k < NPAINTERS; k++)
        check_seam(painters[k], s, NULL);
    aa_scene_free(s);
    /* the seam between two even-odd layers, each with a hole: wound as
     * its outside (winding 2, a hole by the rule), or the other way round
     * (winding 0, a hole under either rule: what stb takes, refusing the
     * first, whose windings it cannot tell from nonzero's) */
    for (int reversed = 0; reversed < 2; reversed++) {
        s = evenodd_seam(reversed);
        for (size_t k = 0; k < NPAINTERS; k++) {
            if (!reversed && !strcmp(painters[k], "stb")) {
                aa_image img;
                assert_int_equal(render(painters[k], s, "box", W, H, 1, &img), AA_EINVAL);
                assert_non_null(strstr(aa_last_error(), "even-odd layer"));
                continue;
            }
            check_seam(painters[k], s, evenodd_hole);
        }
        aa_scene_free(s);
    }
    /* translucency: front to back, blue (columns 12-15), the half white */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    rect_layer(s, blue, 12, 0, W, H);
    rect_layer(s, white, 0, 0, W, H);
    assert_int_equal(aa_scene_set_alpha(s, 0.5), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const double half = srgb_decode_here(0.5);
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        if (render(painters[k], s, "box", W, H, 1, &img))
            fail_msg("%s: %s", painters[k], aa_last_error());
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                for (int c = 0; c < 3; c++) {
                    double want = i >= 12 ? (c == 2 ? 1.0 : 0.0) : half;
                    double got = aa_pixel(&img, i, j)[c];
                    if (!(fabs(got - want) <= 1e-15))
                        fail_msg("%s: translucent: pixel (%d, %d) channel %d %.17g, not %.17g",
                                 painters[k], i, j, c, got, want);
                }
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

static void test_refusals_library(void **state)
{
    (void)state;
    const char *peers[] = {"freetype", "stb", "cairo", "agg"};
    const double tri[] = {0.25, 0.25, 0.75, 0.25, 0.5, 0.75};
    aa_scene *s = scenes_polygon(tri, 3, (aa_rgb){{1, 0.5, 0}}, (aa_rgb){{0, 0, 0}},
                                 AA_FILL_NONZERO);
    for (int k = 0; k < 4; k++) {
        aa_image img;
        /* colour is painted (test_painted); a filter other than box is not */
        assert_int_equal(render(peers[k], s, "tent:r=1", W, H, 1, &img), AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "box"));
    }
    aa_scene_free(s);
    /* two nested squares wound alike: winding 2 inside the inner one */
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    for (int rule = 0; rule < 2; rule++) {
        aa_scene_free(s);
        s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, (aa_fill_rule)rule), AA_OK);
        const double sq[2][4] = {{0.125, 0.125, 0.875, 0.875}, {0.25, 0.25, 0.5, 0.5}};
        for (int q = 0; q < 2; q++)
            scenes_rect(s, sq[q][0], sq[q][1], sq[q][2], sq[q][3]);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        aa_image img;
        int st = render("stb", s, "box", W, H, 1, &img);
        if (rule == AA_FILL_EVENODD) {
            assert_int_equal(st, AA_EINVAL);
            assert_non_null(strstr(aa_last_error(), "even-odd"));
        } else {
            /* nonzero: the inner square is filled too, as stb does it */
            assert_int_equal(st, AA_OK);
            assert_true(aa_pixel(&img, 5, 5)[0] == 1.0);
            aa_image_free(&img);
        }
        /* FreeType and Cairo have both rules: the inner square is a hole
         * under even-odd (pixels 4..7 lie inside it) */
        for (int k = 0; k < 3; k += 2) {
            assert_int_equal(render(peers[k], s, "box", W, H, 1, &img), AA_OK);
            assert_true(aa_pixel(&img, 5, 5)[0] == (rule == AA_FILL_EVENODD ? 0.0 : 1.0));
            assert_true(aa_pixel(&img, 10, 10)[0] == 1.0);
            aa_image_free(&img);
        }
    }
    aa_scene_free(s);
}

/* Through the command: several layers (crow reaching outside the unit
 * square gets a front layer of background), painted, and a tent filter:
 * exit 2.
 * One timed render on one thread, into a .pfm: what is checked is the exit
 * status and whether a file is written, not the timing, the threads or
 * the format (a .exr would load OpenImageIO, most of a start's time). */
static int run_cli(const char *method, const char *pattern, const char *filter,
                   const char *out)
{
    const char *args[] = {"render", "-p", pattern, "-m", method, "-f", filter, "-s", "32x32",
                          "-o", out, "--reps", "1", "--threads", "1", NULL};
    return support_aabench(args, NULL, 0);
}

static void test_refusals_cli(void **state)
{
    (void)state;
    const char *peers[] = {"freetype", "stb", "cairo"};
    char dir[256], out[300];
    assert_int_equal(support_tmpdir(dir, sizeof dir, "peers"), 0);
    snprintf(out, sizeof out, "%s/x.pfm", dir);
    /* Catmull's pixel (patterns/README.md, `catmull`), three layers, painted
     * by every peer (test_painted).  At 20 x 20 px every edge is on a
     * pixel boundary: each layer's coverage is 0 or 1, so the image is the
     * box reference exactly.  As one pixel the coverages are green
     * g = 1/4, blue b = 1/2 and red r = 0.35 x 0.8 = 0.28, and painting back
     * to front gives red r (1 - b)(1 - g) = 0.105, green g, blue
     * b (1 - g) = 0.375, where the exact value is (0, 1/4, 1/2): the red,
     * wholly hidden, shows through the seams (conflation, Catmull's
     * hidden-surface error).  Each coverage is within 1/255 of its value
     * from 8 bits; the red's edges at 0.1, 0.45 and 0.9 are not on the
     * fixed-point grids, and moving each of its four edges by half a step
     * changes its area by up to (0.35 + 0.8) x 2 x step/2: 0.018 for
     * FreeType's 1/64 px, 0.0045 for AGG's 1/256 px, which (1 - b)(1 - g)
     * = 3/8 scales to 0.0068 and 0.0017 of red.  Bounds: 0.01 on red,
     * 2/255 on green and blue.  Cairo's scan converters sample y = 0.1 and
     * 0.9 on their grid of sub-rows (1/15 or 1/4 px), an error up to 0.35/4
     * in the red's area, so Cairo is held to the 20 x 20 case only.
     * Through the command: one peer. */
    aa_spec spec;
    aa_scene *layered = NULL;
    assert_int_equal(aa_pattern_parse("catmull", &spec), AA_OK);
    assert_int_equal(aa_pattern_scene_at(&spec, 20, 20, &layered), AA_OK);
    assert_int_equal(aa_scene_layer_count(layered), 3);
    const support_view v = {.w = 20, .h = 20, .filter = "box", .seed = 1, .threads = 1};
    aa_image ref;
    support_reference(layered, &v, &ref, NULL, NULL);
    for (size_t k = 0; k < NPAINTERS; k++) {
        aa_image img;
        if (render(painters[k], layered, "box", 20, 20, 2, &img))
            fail_msg("%s: %s", painters[k], aa_last_error());
        double d = support_max_diff(&img, &ref, NULL, NULL);
        if (!(d == 0.0))
            fail_msg("%s: catmull at 20 x 20 differs from the box reference by %.3e",
                     painters[k], d);
        aa_image_free(&img);
        if (!strncmp(painters[k], "cairo", 5))
            continue;
        if (render(painters[k], layered, "box", 1, 1, 1, &img))
            fail_msg("%s: %s", painters[k], aa_last_error());
        const double *px = aa_pixel(&img, 0, 0);
        print_message("%-14s catmull as one pixel: (%.4f, %.4f, %.4f), painted (0.105, 0.25, "
                      "0.375), exact (0, 0.25, 0.5)\n",
                      painters[k], px[0], px[1], px[2]);
        if (!(fabs(px[0] - 0.105) <= 0.01 && fabs(px[1] - 0.25) <= 2.0 / 255 &&
              fabs(px[2] - 0.375) <= 2.0 / 255))
            fail_msg("%s: catmull as one pixel (%.6f, %.6f, %.6f), not (0.105, 0.25, 0.375)",
                     painters[k], px[0], px[1], px[2]);
        aa_image_free(&img);
    }
    aa_image_free(&ref);
    aa_scene_free(layered);
    for (int k = 0; k < 1; k++) {
        assert_int_equal(run_cli(peers[k], "crow", "tent:r=1", out), 2);
        assert_int_equal(access(out, F_OK), -1); /* nothing written */
        /* the same command with an accepted scene and filter succeeds, on
         * a scene of several layers too */
        assert_int_equal(run_cli(peers[k], "crow", "box", out), 0);
        assert_int_equal(unlink(out), 0);
        assert_int_equal(run_cli(peers[k], "catmull", "box", out), 0);
        assert_int_equal(unlink(out), 0);
    }
    assert_int_equal(rmdir(dir), 0);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_rectangle),
             cmocka_unit_test(test_half_plane),
             cmocka_unit_test(test_crow_band_area),
             cmocka_unit_test(test_many_edges),
             cmocka_unit_test(test_arc_cubics),
             cmocka_unit_test(test_arc_disc),
             cmocka_unit_test(test_arc_ellipse_turn),
             cmocka_unit_test(test_arc_ellipse_pieces),
             cmocka_unit_test(test_painted),
             cmocka_unit_test(test_refusals_library),
             cmocka_unit_test(test_refusals_cli))
