/*
 * test_analytic_stroke.c: `analytic` on the exact outlines of stroked
 * Bezier and elliptical arcs (offset curves and evolutes, AA_PIECE_OFFSET),
 * under the separable filters and the radial ones.
 *
 * Known answers, none from the method itself:
 *  - the exact reference of the harness's separate truth path
 *    (aa_truth_render: the rows' crossings with the pieces root-found, the
 *    filter integrated over the rows by its own quadrature), within 1e-12
 *    per pixel, under box, tent:r=1, bspline:order=3 and mitchell on the
 *    built-in `strokes` pattern and on the scene of tests/bench_bezstroke.c
 *    (20 wavy paths of 50 cubics, stroked 2.5 px wide with round joins and
 *    caps, some tight enough that their offsets fold) at 64 px, where
 *    neighbouring strokes overlap (rows of the visible parts' scatter) and
 *    others stand alone (rows of the per-edge scatter), and under box and
 *    tent:r=1 on an SVG drawn here (at 24 px) of thick strokes of tight
 *    cubics and of a turned ellipse whose inner offsets fold, a cubic with
 *    a cusp and overlapping layers of four colours; the same SVG at 96 px
 *    (box and tent:r=1) and 192 px (box), with `area` beside it (box);
 *  - where an offset folds, the normal line ending its region and the
 *    evolute leaving that end tangent to it, convex, meet only there (the
 *    derivation above fold_meetings): aa_piece_meet reports at most one
 *    meeting of such a pair beyond the end's rounding, next to it, at 96
 *    and 192 px;
 *  - the point-in-stroke oracle at random points (SVG 2's union of the
 *    normal segments; feet of the perpendiculars found by sampling and
 *    bisection) on that SVG's gold, white and elliptical strokes at 96 px;
 *  - the tube formula (a closed form): a butt-capped stroke of width w of
 *    a curve whose curvature radius exceeds w/2 everywhere covers w times
 *    the curve's length, and so does a closed stroke of a closed curve,
 *    so under a filter whose integer translates sum to 1 (box, tent:r=1,
 *    the B-splines, Mitchell-Netravali, Catmull-Rom) the image of the white
 *    stroke on black sums to that area (placed: times the view's w h) over
 *    an image holding its whole filtered support.  The lengths: a gentle
 *    cubic's by GSL's QAG (oracle_cubic_length), a closed ellipse's
 *    perimeter by the Gauss-Kummer series pi (a + b) sum binom(1/2, n)^2
 *    q^(2n), q = (a - b)/(a + b), and under a shear m the area times
 *    |det m|;
 *  - under the radial filters (radial:k=1,r=1, radial:k=2,r=1.5,
 *    radial:k=3,r=2.3): the reference within 1e-12 per pixel on a 24 px
 *    window of tests/bench_bezstroke.c's scene, at 1 and 2 threads
 *    (bit-identical); a straight stroke (a cubic of collinear, unevenly
 *    spaced control points, whose offsets are lines) within 1e-12 of the
 *    same rectangle as a polygon (the polynomial path, itself held to the
 *    reference in tests/test_analytic_radial.c), and 1/2 (a closed form:
 *    the filter is even about every line through its centre) where its
 *    side passes through a pixel centre; the offsets of a circle (an
 *    annulus) within 1e-12 of the two circles as elliptical arcs, and at
 *    the annulus's centre the closed form (1 - a1^2/R^2)^(K+1) -
 *    (1 - a2^2/R^2)^(K+1) (the weight of a centred disc of radius a being
 *    1 - (1 - a^2/R^2)^(K+1));
 *  - refusals by name: an offset running along a pixel's radial filter
 *    circle within rounding (a circle of the filter's radius about a pixel
 *    centre), whose crossings cannot be isolated.
 * Quick tier (about 3 s of CPU): the folding strokes at 24, 96 and 192 px
 * under separable filters; under a radial filter every pixel takes its
 * own visible parts, and the folding SVG is not in this tier.
 */
#include "oracle.h"
#include "path.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const char *const filters[] = {"box", "tent:r=1", "bspline:order=3", "mitchell"};
#define NF 4

static void must(int st)
{
    if (st)
        fail_msg("status %d: %s", st, aa_last_error());
}

/* Fails where analytic's image is more than 1e-12 from the reference's
 * under any of the filters; prints the largest difference and how many
 * pieces are offset pieces (none in `strokes`, of lines and circular
 * arcs, whose offsets are lines and circles). */
static void against_reference(const char *what, const aa_scene *s, int w, int h, int f0, int f1)
{
    size_t n, noff = 0;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    for (size_t k = 0; k < n; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    for (int f = f0; f < f1 && f < NF; f++) {
        aa_image a, r;
        support_render("analytic", s, filters[f], w, h, 2, &a, NULL);
        support_reference(s, &(support_view){.w = w, .h = h, .filter = filters[f], .threads = 2},
                          &r, NULL, NULL);
        double worst = support_within_reference(what, filters[f], &a, &r, 1e-12);
        print_message("%-28s %-16s %zu offset pieces, largest difference %.1e\n", what,
                      filters[f], noff, worst);
        aa_image_free(&a);
        aa_image_free(&r);
    }
}

static void test_strokes_pattern(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("strokes");
    against_reference("strokes", s, 40, 40, 0, NF);
    aa_scene_free(s);
}

/* tests/bench_bezstroke.c's scene at 1024 px (20 subpaths of 50 cubics
 * across the square, stroked 2.5 px wide, round joins and caps), seen
 * through the window of n x n px from (X0, Y0): the cubics k0 .. k1 of
 * subpath r, mapped to the window's unit square. */
static aa_scene *bezstroke_scene(int n, int r, int k0, int k1, double X0, double Y0)
{
    aa_path p = {0};
    double y = (r + 0.5) / 20.0, a = 0.004 + 0.0015 * r, dx = 0.9 / 50.0, x = 0.05 + k0 * dx;
#define WX(u) (((u) * 1024.0 - X0) / n)
#define WY(v) (((v) * 1024.0 - Y0) / n)
    must(aa_path_move_to(&p, WX(x), WY(y)));
    for (int k = k0; k <= k1; k++) {
        double s = (k % 2 ? -1.0 : 1.0) * a * (1.0 + 0.5 * sin(0.7 * k + r));
        double kink = k % 7 == 6 ? 0.3 * dx : 0.0;
        must(aa_path_cubic_to(&p, WX(x + dx / 3.0 + kink), WY(y + s), WX(x + 2.0 * dx / 3.0),
                              WY(y + s), WX(x + dx), WY(y)));
        x += dx;
    }
#undef WX
#undef WY
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 2.5 / n;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, NULL);
    aa_path_free(&p);
    return s;
}

static void test_bezstroke_scene(void **state)
{
    (void)state;
    /* subpath 10 (amplitude about 20 px) about its seventh cubic (a
     * corner): cubics 3 to 8, the window from (125, 505.6) */
    aa_scene *s = bezstroke_scene(64, 10, 3, 8, 125.0, 537.6 - 32.0);
    against_reference("bench_bezstroke, 64 px of it", s, 64, 64, 0, NF);
    aa_scene_free(s);
}

/* Thick strokes of tight curves: the inner offsets of the first two paths'
 * bends and of the ellipse's ends fold (curvature radius under the half
 * width: the ellipse's least, ry^2/rx = 1.6, against 5), the third path's
 * cubic has a cusp (its control polygon crosses itself symmetrically), and
 * the strokes overlap, each in front of the last. */
static const char fold_svg[] =
    "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 100 100\">\n"
    "  <rect width=\"100\" height=\"100\" fill=\"#102030\"/>\n"
    "  <path d=\"M10 30 C 25 5, 30 5, 45 30 S 65 55, 90 20\" fill=\"none\" stroke=\"gold\"\n"
    "        stroke-width=\"9\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n"
    "  <path d=\"M12 62 C 40 97, 10 97, 40 62\" fill=\"none\" stroke=\"white\"\n"
    "        stroke-width=\"7\"/>\n"
    "  <path d=\"M50 90 C 90 50, 55 50, 95 90\" fill=\"none\" stroke=\"#6c6\" stroke-width=\"5\"\n"
    "        stroke-linecap=\"square\"/>\n"
    "  <ellipse cx=\"62\" cy=\"60\" rx=\"25\" ry=\"6.3\" fill=\"none\" stroke=\"rgb(200, 60, 40)\"\n"
    "           stroke-width=\"10\" transform=\"rotate(20 62 60)\"/>\n"
    "</svg>\n";

/* fold_svg drawn at n x n px (pattern units), read from a file in a
 * temporary folder of its own. */
static aa_scene *fold_scene(int n)
{
    char dir[256];
    assert_int_equal(support_tmpdir(dir, sizeof dir, "anastroke"), 0);
    aa_scene *s = scenes_svg_text(dir, "fold.svg", fold_svg, n, n);
    assert_int_equal(support_rmtree(dir), 0);
    size_t np, noff = 0;
    const aa_piece *pc = aa_scene_pieces(s, &np);
    for (size_t k = 0; k < np; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    assert_true(noff > 0);
    return s;
}

static void test_folding_svg(void **state)
{
    (void)state;
    aa_scene *s = fold_scene(24);
    against_reference("folding strokes (svg)", s, 24, 24, 0, 2);
    aa_scene_free(s);
}

/* ---- the folding strokes at 96 and 192 px ----
 *
 * Where an offset folds, its region ends on the normal line at the
 * parameter u where |k| h = 1, and the evolute's piece starts there, at
 * E(u) = B(u) + N(u)/k(u) = B(u) + h N(u), the line's end.  E' = (1/k)' N,
 * along the line: the evolute leaves that end tangent to the line, and it
 * is convex, turning by less than a half turn up to the curvature's
 * extreme where its piece ends (the base's tangent turns by less on these
 * bends), so it lies on one side of the line and meets it nowhere else.
 * The line's copy of the end and the evolute's, each rounded its own way,
 * may differ by a few ulps (D = x_line - x_evolute is then a small
 * constant plus c u^2 next to it, monotone for u > 0): at most one
 * meeting, next to the end.  Before aa_piece_meet recognised pieces
 * within rounding of each other there, it reported 966 meetings of such a
 * pair at 96 px, all between 8.0e-7 and 9.6e-7 px from the end, and the
 * visible parts' sweep, which starts each band at the last meeting, took
 * 27.4 s of CPU at 96 px. */

/* Fails unless every normal line and evolute piece of the placed scene
 * (n x n px) that share an end point (within 1e-9 px) meet within 3e-8 n
 * px of it only (the rounded ends' crossing is sqrt(delta/c) from it,
 * delta a few ulps of the coordinates and c, in 1/px, shrinking as 1/n:
 * up to 7.8e-7 px at 96 px, 1.6e-6 at 192), and at most once beyond the
 * end's own rounding (1e-12 relative: the end itself), over their common
 * rows and over the rows within 1e-4 px of the end. */
static void fold_meetings(const aa_scene *placed, int n)
{
    size_t np;
    const aa_piece *pc = aa_scene_pieces(placed, &np);
    int pairs = 0, most = 0;
    double far = 0.0;
    for (size_t i = 0; i < np; i++)
        for (size_t j = 0; j < np; j++) {
            const aa_piece *p = &pc[i], *q = &pc[j];
            if (p->kind != AA_PIECE_LINE || q->kind != AA_PIECE_OFFSET || !q->oc.evolute)
                continue;
            const double pe[2][2] = {{p->x0, p->y0}, {p->x1, p->y1}};
            const double qe[2][2] = {{q->x0, q->y0}, {q->x1, q->y1}};
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) {
                    if (!(hypot(pe[a][0] - qe[b][0], pe[a][1] - qe[b][1]) <= 1e-9))
                        continue;
                    double ye = qe[b][1], ys[64];
                    const double win[2][2] = {{-INFINITY, INFINITY}, {ye - 1e-4, ye + 1e-4}};
                    for (int w = 0; w < 2; w++) {
                        int m = aa_piece_meet(p, q, win[w][0], win[w][1], ys, 64), beyond = 0;
                        for (int r = 0; r < m; r++) {
                            far = fmax(far, fabs(ys[r] - ye));
                            if (!(fabs(ys[r] - ye) <= 3e-8 * n))
                                fail_msg("%d px: line %zu and evolute %zu meet at %.17g, %.3g px "
                                         "from their end",
                                         n, i, j, ys[r], ys[r] - ye);
                            beyond += fabs(ys[r] - ye) > 1e-12 * fmax(1.0, fabs(ye));
                        }
                        if (beyond > 1)
                            fail_msg("%d px: line %zu and evolute %zu meet %d times next to "
                                     "their end at %.17g",
                                     n, i, j, beyond, ye);
                        most = beyond > most ? beyond : most;
                    }
                    pairs++;
                }
        }
    print_message("folding strokes at %d px: %d ends shared by a normal line and an evolute, "
                  "at most %d meeting beyond the end, %.2g px from it at most\n",
                  n, pairs, most, far);
    assert_true(pairs > 0);
}

static void test_folding_larger(void **state)
{
    (void)state;
    const char *const methods[] = {"analytic", "area"};
    for (int n = 96; n <= 192; n *= 2) {
        aa_scene *s = fold_scene(n);
        aa_scene *placed = aa_scene_place(s, n, n, 0.0, 0.0, 0.0);
        assert_non_null(placed);
        fold_meetings(placed, n);
        aa_scene_free(placed);
        for (int f = 0; f < (n == 96 ? 2 : 1); f++) {
            aa_image r;
            const support_view v = {.w = n, .h = n, .filter = filters[f], .threads = 2};
            support_reference(s, &v, &r, NULL, NULL);
            for (int k = 0; k < 2; k++) {
                if (k == 1 && f > 0)
                    continue; /* area is the box's alone */
                aa_image a;
                support_render(methods[k], s, filters[f], n, n, 2, &a, NULL);
                double worst = support_within_reference("folding strokes (svg)", filters[f], &a,
                                                        &r, 1e-12);
                print_message("folding strokes (svg) %d px %-8s %-9s largest difference %.1e\n",
                              n, methods[k], filters[f], worst);
                aa_image_free(&a);
            }
            aa_image_free(&r);
        }
        aa_scene_free(s);
    }
}

/* The point-in-stroke oracle (as in tests/test_bezstroke.c and
 * tests/test_ellipse_stroke.c) on fold_svg's strokes at 96 px: SVG 2's
 * stroke shape, the union of the normal segments of length h each side,
 * holds p iff some foot t of the perpendicular from p (p - C(t) normal to
 * C'(t)) has |p - C(t)| <= h (butt caps, the white cubic), or iff p is
 * within h of the path (round joins and caps, the gold cubics; a closed
 * smooth curve, the ellipse); the feet by oracle_curve_feet (sign changes
 * of (p - C) . C' at 4000 samples, bisected).  Each stroke's outline is
 * filled alone (white on black) through the view's map, 0.96 px a unit;
 * the green cubic (a cusp, square caps) is left to test_bezstroke's cusp
 * oracle. */
static uint64_t rng = 0x243f6a8885a308d3ull;

typedef struct fold_path {
    const double *cs; /* chained cubics: 2 + 6 nc numbers */
    int nc, round;
    double h;
    /* an ellipse c + u cos t + v sin t instead when ell */
    int ell;
    double c[2], u[2], v[2];
} fold_path;

static void cubic_at(const void *c, double t, double *x, double *y, double *dx, double *dy)
{
    oracle_cubic_at(c, t, x, y, dx, dy);
}

static void ellipse_at(const void *vp, double t, double *x, double *y, double *dx, double *dy)
{
    const fold_path *e = vp;
    *x = e->c[0] + e->u[0] * cos(t) + e->v[0] * sin(t);
    *y = e->c[1] + e->u[1] * cos(t) + e->v[1] * sin(t);
    *dx = -e->u[0] * sin(t) + e->v[0] * cos(t);
    *dy = -e->u[1] * sin(t) + e->v[1] * cos(t);
}

static double fold_distance(const void *vp, double px, double py, int *unsure)
{
    const fold_path *f = vp;
    if (f->ell)
        return oracle_curve_feet(ellipse_at, f, 0.0, 2.0 * M_PI, 4000, px, py, 1, f->h, unsure);
    double d = INFINITY;
    for (int k = 0; k < f->nc; k++) {
        double q[8] = {f->cs[6 * k], f->cs[6 * k + 1]};
        memcpy(q + 2, f->cs + 2 + 6 * k, 6 * sizeof *q);
        d = fmin(d, oracle_curve_feet(cubic_at, q, 0.0, 1.0, 4000, px, py, f->round, f->h,
                                      unsure));
    }
    return d;
}

static void fold_oracle(const char *what, const fold_path *f, double w, const double box[4])
{
    const double m[6] = {0.96, 0.0, 0.0, 0.96, 0.0, 0.0}; /* 100 units to 96 px */
    aa_path p = {0};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (f->round)
        st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    if (f->ell) {
        double x0 = f->c[0] + f->u[0], y0 = f->c[1] + f->u[1];
        must(aa_path_move_to(&p, x0, y0));
        must(aa_path_arc_to(&p, f->c[0], f->c[1], f->u[0], f->u[1], f->v[0], f->v[1], 0.0,
                            2.0 * M_PI, x0, y0));
        must(aa_path_close(&p));
    } else {
        must(aa_path_move_to(&p, f->cs[0], f->cs[1]));
        for (int k = 0; k < f->nc; k++) {
            const double *q = f->cs + 2 + 6 * k;
            must(aa_path_cubic_to(&p, q[0], q[1], q[2], q[3], q[4], q[5]));
        }
    }
    size_t noff;
    aa_scene *s = scenes_stroke_outline(&p, &st, m, &noff);
    assert_true(noff > 0);
    support_stroke_check(what, s, box, f->h, m, 2000, &rng, fold_distance, f);
    aa_scene_free(s);
    aa_path_free(&p);
}

static void test_folding_oracle(void **state)
{
    (void)state;
    /* gold: M10 30 C 25 5, 30 5, 45 30 S 65 55, 90 20 (S reflects the
     * last control point about (45, 30): 60 55) */
    const double gold[14] = {10, 30, 25, 5, 30, 5, 45, 30, 60, 55, 65, 55, 90, 20};
    const double white[8] = {12, 62, 40, 97, 10, 97, 40, 62};
    fold_oracle("gold, round, w 9", &(fold_path){gold, 2, 1, 4.5, 0, {0}, {0}, {0}}, 9,
                (const double[4]){0, -5, 100, 65});
    fold_oracle("white, butt, w 7", &(fold_path){white, 1, 0, 3.5, 0, {0}, {0}, {0}}, 7,
                (const double[4]){5, 52, 47, 97});
    /* the ellipse (62, 60), rx 25, ry 6.3, turned by 20 degrees */
    const double phi = 20.0 * M_PI / 180.0;
    fold_path e = {NULL, 0, 0, 5.0, 1, {62, 60},
                   {25 * cos(phi), 25 * sin(phi)}, {-6.3 * sin(phi), 6.3 * cos(phi)}};
    fold_oracle("ellipse, w 10", &e, 10, (const double[4]){30, 40, 94, 80});
}

/* ---- the tube formula ---- */

static const char *const sum_filters[] = {"box",      "tent:r=1", "bspline:order=2",
                                          "bspline:order=3", "mitchell", "catrom"};

/* The mean of analytic's image of s (white on black) at n x n under each
 * of sum_filters, against want (pattern units). */
static void sums_to(const char *what, const aa_scene *s, int n, double want)
{
    for (size_t f = 0; f < sizeof sum_filters / sizeof *sum_filters; f++) {
        aa_image im;
        support_render("analytic", s, sum_filters[f], n, n, 2, &im, NULL);
        double got = support_channel_mean(&im, 0);
        print_message("%-28s %-16s area %.15f, want %.15f (%.1e)\n", what, sum_filters[f], got,
                      want, got - want);
        if (!(fabs(got - want) < 1e-12))
            fail_msg("%s under %s: area %.17g, want %.17g", what, sum_filters[f], got, want);
        aa_image_free(&im);
    }
}

static void test_tube(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st); /* butt caps */
    /* a gentle cubic: curvature radius above w/2 everywhere */
    const double c[8] = {0.25, 0.5, 0.35, 0.35, 0.65, 0.65, 0.75, 0.5};
    double w = 0.04;
    for (int k = 0; k <= 1000; k++)
        assert_true(fabs(oracle_cubic_curvature(c, k / 1000.0)) * 0.5 * w < 0.99);
    aa_path p = {0};
    st.width = w;
    must(aa_path_move_to(&p, c[0], c[1]));
    must(aa_path_cubic_to(&p, c[2], c[3], c[4], c[5], c[6], c[7]));
    size_t noff;
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, &noff);
    assert_true(noff > 0);
    sums_to("gentle cubic, butt", s, 64, w * oracle_cubic_length(c, 0, 1));
    aa_scene_free(s);
    aa_path_free(&p);
    /* a closed ellipse of semi-axes a, b turned by 0.5 (least curvature
     * radius b^2/a = 0.114 > w/2), and sheared after stroking */
    const double a = 0.35, b = 0.2, phi = 0.5;
    const double shear[6] = {0.8, 0.15, -0.3, 0.6, 0.3, 0.1};
    w = 0.05;
    st.width = w;
    double ux = a * cos(phi), uy = a * sin(phi), vx = -b * sin(phi), vy = b * cos(phi);
    must(aa_path_move_to(&p, 0.5 + ux, 0.5 + uy));
    must(aa_path_arc_to(&p, 0.5, 0.5, ux, uy, vx, vy, 0.0, 2.0 * M_PI, 0.5 + ux, 0.5 + uy));
    must(aa_path_close(&p));
    s = scenes_stroke_outline(&p, &st, NULL, &noff);
    assert_true(noff > 0);
    sums_to("closed ellipse", s, 64, w * oracle_ellipse_perimeter(a, b));
    aa_scene_free(s);
    s = scenes_stroke_outline(&p, &st, shear, &noff);
    assert_true(noff > 0);
    sums_to("closed ellipse, sheared", s, 64,
            fabs(shear[0] * shear[3] - shear[1] * shear[2]) * w * oracle_ellipse_perimeter(a, b));
    aa_scene_free(s);
    aa_path_free(&p);
}

/* ---- the radial filters ---- */

static const char *const rad_filters[] = {"radial:k=1,r=1", "radial:k=2,r=1.5",
                                          "radial:k=3,r=2.3"};
#define NRF 3

/* analytic under a radial filter within 1e-12 of the reference on s at
 * w x h, at 1 and 2 threads (bit-identical). */
static void rad_against_reference(const char *what, const aa_scene *s, int w, int h, int f0,
                                  int f1)
{
    for (int f = f0; f < f1 && f < NRF; f++)
        support_method_against_reference("analytic", what, s, w, h, rad_filters[f]);
}

static void test_radial_reference(void **state)
{
    (void)state;
    /* a 24 px window of the bench's strokes about a corner (cubics 5 to
     * 7 of subpath 10) */
    aa_scene *s = bezstroke_scene(24, 10, 5, 7, 140.0, 537.6 - 12.0);
    size_t n, noff = 0;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    for (size_t k = 0; k < n; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    assert_true(noff > 0);
    rad_against_reference("bench_bezstroke, 24 px", s, 24, 24, 0, NRF);
    aa_scene_free(s);
}

/* The largest difference between a and b over every channel and pixel. */
static double largest_difference(const aa_image *a, const aa_image *b)
{
    double worst = 0.0;
    for (int p = 0; p < 3 * a->w * a->h; p++)
        worst = fmax(worst, fabs(a->v[p] - b->v[p]));
    return worst;
}

/* Offsets of known shape against the same region outlined by the scene's
 * polynomial and conic pieces (a path the reference checks in
 * tests/test_analytic_radial.c), and closed forms at a pixel centre:
 *  - a straight stroke: a cubic with collinear control points spaced
 *    unevenly (its offsets are the lines at +-w/2, not linear in t),
 *    butt-capped, against the rectangle as a polygon; one side passes
 *    through a pixel centre whose filter disc it cuts and the rest of the
 *    rectangle covers (the caps and the far side out of reach), where the
 *    weight is 1/2 (the filter is even about every line through its
 *    centre);
 *  - the offsets at -+w/2 of a circle (of an ellipse's base): the annulus
 *    of radii rho -+ w/2 about a pixel centre, against the two circles as
 *    elliptical arcs (even-odd); at that centre, the radial weight inside
 *    radius a being 1 - (1 - a^2/R^2)^(K+1) (integrating 2 pi s c (1 -
 *    s^2/R^2)^K from 0 to a, c = (K + 1)/(pi R^2)), the annulus gives
 *    (1 - a1^2/R^2)^(K+1) - (1 - a2^2/R^2)^(K+1), the second term 0 where
 *    a2 >= R. */
static void test_radial_known(void **state)
{
    (void)state;
    const int N = 24;
    aa_stroke_style st;
    aa_stroke_style_default(&st); /* butt caps */
    /* the straight stroke, in pixels: from A along (ux, uy) for L, width
     * wd; its left side (x, y) - (wd/2) n passes through the centre of
     * pixel (11, 12) */
    const double ang = 0.37, ux = cos(ang), uy = sin(ang), nx = -uy, ny = ux, wd = 7.0,
                 L = 40.0;
    const double Cx = 11.5, Cy = 12.5;
    const double Ax = Cx + 0.5 * wd * nx - 0.5 * L * ux, Ay = Cy + 0.5 * wd * ny - 0.5 * L * uy;
#define P(v) ((v) / N)
    aa_path p = {0};
    st.width = P(wd);
    must(aa_path_move_to(&p, P(Ax), P(Ay)));
    must(aa_path_cubic_to(&p, P(Ax + 0.1 * L * ux), P(Ay + 0.1 * L * uy), P(Ax + 0.45 * L * ux),
                          P(Ay + 0.45 * L * uy), P(Ax + L * ux), P(Ay + L * uy)));
    size_t noff, n;
    aa_scene *s = scenes_stroke_outline(&p, &st, NULL, &noff);
    aa_path_free(&p);
    assert_true(noff > 0);
    double xy[8];
    for (int k = 0; k < 4; k++) {
        double t = k == 1 || k == 2 ? L : 0.0, o = k >= 2 ? -0.5 * wd : 0.5 * wd;
        xy[2 * k] = P(Ax + t * ux + o * nx), xy[2 * k + 1] = P(Ay + t * uy + o * ny);
    }
    aa_scene *poly = scenes_polygon(xy, 4, (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO);
    for (int f = 0; f < NRF; f++) {
        aa_image a, b;
        support_render("analytic", s, rad_filters[f], N, N, 2, &a, NULL);
        support_render("analytic", poly, rad_filters[f], N, N, 2, &b, NULL);
        double worst = largest_difference(&a, &b), half = a.v[3 * (12 * N + 11)];
        print_message("straight stroke %-18s against the polygon %.1e, at the side's pixel "
                      "%.17f (1/2: %.1e)\n",
                      rad_filters[f], worst, half, half - 0.5);
        if (!(worst < 1e-12))
            fail_msg("straight stroke under %s: %.3g from the polygon", rad_filters[f], worst);
        if (!(fabs(half - 0.5) < 1e-12))
            fail_msg("straight stroke under %s: %.17g at the side's pixel, want 1/2",
                     rad_filters[f], half);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    aa_scene_free(s);
    aa_scene_free(poly);
    /* the annulus about the centre of pixel (9, 10), outlined by the two
     * offsets at -+wa/2 of the circle of radius rho (the stroker draws a
     * circle's stroke with circular arcs: these are given as offset curves
     * of an ellipse's base, whose normal points inwards) */
    const double Ox = 9.5, Oy = 10.5, rho = 1.05, wa = 0.7, a1 = rho - 0.5 * wa, a2 = rho + 0.5 * wa;
    s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    must(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_EVENODD));
    for (int k = 0; k < 2; k++) {
        aa_offset_curve oc = {{P(Ox), P(Oy), P(rho), 0.0, 0.0, P(rho), 0.0, 0.0},
                              {1.0, 0.0, 0.0, 1.0, 0.0, 0.0},
                              P(k ? -0.5 * wa : 0.5 * wa),
                              0,
                              AA_OFFSET_ELLIPSE};
        double r = k ? a2 : a1;
        must(aa_scene_move_to(s, P(Ox + r), P(Oy)));
        must(aa_scene_offset_to(s, &oc, 0.0, 2.0 * M_PI, P(Ox + r), P(Oy)));
        must(aa_scene_close(s));
    }
    must(aa_scene_finish(s));
    noff = 0;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    for (size_t k = 0; k < n; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    assert_true(noff > 0);
    aa_scene *ring = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(ring);
    must(aa_scene_layer(ring, (aa_rgb){{1, 1, 1}}, AA_FILL_EVENODD));
    const double rr[2] = {a1, a2};
    for (int k = 0; k < 2; k++) {
        must(aa_scene_move_to(ring, P(Ox + rr[k]), P(Oy)));
        must(aa_scene_arc_to(ring, P(Ox), P(Oy), P(rr[k]), 0, 0, P(rr[k]), 0, 2 * M_PI,
                             P(Ox + rr[k]), P(Oy)));
        must(aa_scene_close(ring));
    }
    must(aa_scene_finish(ring));
    for (int f = 0; f < NRF; f++) {
        aa_filter flt;
        must(aa_filter_parse(rad_filters[f], &flt));
        int K = (int)flt.spec.v[0];
        double R = flt.spec.v[1];
        double want = pow(1.0 - a1 * a1 / (R * R), K + 1) -
                      (a2 < R ? pow(1.0 - a2 * a2 / (R * R), K + 1) : 0.0);
        aa_image a, b;
        support_render("analytic", s, rad_filters[f], N, N, 2, &a, NULL);
        support_render("analytic", ring, rad_filters[f], N, N, 2, &b, NULL);
        double worst = largest_difference(&a, &b), got = a.v[3 * (10 * N + 9)];
        print_message("circle's stroke %-18s against the arcs %.1e, at its centre %.17f "
                      "(closed form: %.1e)\n",
                      rad_filters[f], worst, got, got - want);
        if (!(worst < 1e-12))
            fail_msg("circle's stroke under %s: %.3g from the arcs", rad_filters[f], worst);
        if (!(fabs(got - want) < 1e-12))
            fail_msg("circle's stroke under %s: %.17g at its centre, want %.17g",
                     rad_filters[f], got, want);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    aa_scene_free(ring);
    /* the outer offset of radius 1.4 about the centre of pixel (9, 10)
     * under radial:k=2,r=1.4 runs along that pixel's filter circle, within
     * rounding of it all round: refused by name, not guessed */
    aa_image im;
    int rc = support_render_view("analytic", s, &(support_view){.w = N, .h = N,
                                                                .filter = "radial:k=2,r=1.4",
                                                                .threads = 1},
                                 &im, NULL);
    print_message("radius of the filter's circle: %s\n", rc ? aa_last_error() : "taken");
    assert_int_equal(rc, AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "circle"));
#undef P
    aa_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strokes_pattern), cmocka_unit_test(test_bezstroke_scene),
        cmocka_unit_test(test_folding_svg), cmocka_unit_test(test_folding_larger),
        cmocka_unit_test(test_folding_oracle), cmocka_unit_test(test_tube),
        cmocka_unit_test(test_radial_reference), cmocka_unit_test(test_radial_known)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
