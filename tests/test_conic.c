/*
 * test_conic.c: the ground truth on elliptical arcs (AA_PIECE_CONIC pieces,
 * scenes built with aa_scene_arc_to), white on black, against closed forms
 * derived here, independently of the reference (which integrates along v
 * by Gauss-Kronrod quadrature between breakpoints):
 *
 *  - per pixel, the box-filtered value of a disk is the area of the disk
 *    inside the pixel's square: disk_rect below integrates the chord's
 *    clipped length along y in closed form (the antiderivative of
 *    sqrt(r^2 - u^2), written without cancellation), in long double;
 *    an axis-aligned ellipse is a disk scaled along x, a half disk a disk
 *    in a rectangle cut at the centre's height, an annulus a difference of
 *    disks.  Checked: a disk, a disk whose extremes lie on pixel lines, a
 *    tiny circle (r = 0.3) inside one pixel and one across four, a half
 *    disk (an arc and a line), an annulus (even-odd, and nonzero with the
 *    inner circle reversed), an ellipse, and circles of radius 10^4 and
 *    10^6 of which a cap is visible;
 *  - the sum of a reference over the image is the shape's area (pi r^2,
 *    pi a b for an ellipse rotated by 30 degrees, pi (a^2 - b^2) for the
 *    annulus, the visible part's area for the huge circle) under every
 *    filter whose translates by the pixel grid sum to 1: the box, the tent
 *    of radius 1, and the Gaussian of s = 1.4 (by Poisson's summation the
 *    translates sum to 1 + 2 exp(-2 pi^2 s^2) cos(...) + ..., off by 3e-17
 *    at most), the shape lying inside the image by more than the filter's
 *    reach.  The cone's translates do not sum to 1;
 *  - for a disk of radius a centred on a pixel centre, that pixel's value
 *    is the filter's mass within radius a: 1 - exp(-a^2 / (2 s^2)) for the
 *    Gaussian, 3 a^2 / r^2 - 2 a^3 / r^3 for the cone of radius r (the
 *    integral of 2 pi rho 3 (1 - rho / r) / (pi r^2) from 0 to a), and for
 *    the tent of radius 1 the integral of (1 - |x|)(1 - |y|) over the disk,
 *    pi a^2 - 8 a^3 / 3 + a^4 / 2 (by symmetry 4 times the quarter disk's
 *    integrals of 1, x, y and x y in polar coordinates).
 *
 *  - pie slices, circular segments and crossing circles by their areas:
 *    r^2 (t1 - t0) / 2, r^2 (th - sin th) / 2, and the lens between two
 *    circles, 2 r^2 acos(d / (2 r)) - (d / 2) sqrt(4 r^2 - d^2); 119 seeded
 *    random pie slices of ellipses (skewed conjugate semi-diameters, arcs
 *    either way) by |u x v| |t1 - t0| / 2.
 *
 * Every check asks for |reference - closed form| <= the reference's own
 * bound (plus the closed form's rounding, 1e-15) and every bound <=
 * AA_TRUTH_BOUND.  The one-piece-at-a-time path (AA__TRUTH_CROWD) is
 * checked the same way on disks and a circle of radius 1e-3, and against
 * the default per pixel within both bounds (random slices under the box
 * and the cone, circles passing 1e-3 and 1e-6 from pixel centres under the
 * cone; ten random scenes of crossing and meeting arcs under the Gaussian
 * and the cone), as is the QAG path (AA__TRUTH_QAG: the Gaussian without
 * its panels).  Also: the crossings of a conic piece with a circle (the cone's
 * breakpoints) lie on that circle, as many as a fine grid finds.
 */
#include "bench.h"
#include "support.h"
#include "truth_internal.h"

#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* The closed form's own rounding (long double, values below 10^4). */
#define CLOSED_ERR 1e-15

/* ---- closed forms ---- */

/* asin(z) - z: the series sum over n >= 1 of (2n)! / (4^n n!^2 (2n + 1))
 * z^(2n + 1) where |z| is small (no cancellation), else directly. */
static long double asin_less_z(long double z)
{
    if (fabsl(z) > 0.125L)
        return asinl(z) - z;
    long double z2 = z * z, a = 1, p = z, sum = 0;
    for (int n = 1; n < 60; n++) {
        a *= (2.0L * n - 1) / (2.0L * n);
        p *= z2;
        long double t = a * p / (2 * n + 1);
        sum += t;
        if (fabsl(t) <= 1e-24L * fabsl(sum))
            break;
    }
    return sum;
}

/* G(u) = integral from 0 to u of (sqrt(r^2 - t^2) - r) dt, |u| <= r.
 * The antiderivative of sqrt(r^2 - t^2) is (t w + r^2 asin(t / r)) / 2,
 * w = sqrt(r^2 - t^2); less r t that is (u (w - r) + r^2 (asin(u / r) -
 * u / r)) / 2, and w - r = -u^2 / (r + w). */
static long double G(long double r, long double u)
{
    long double w = sqrtl((r - u) * (r + u));
    return 0.5L * (-u * u * u / (r + w) + r * r * asin_less_z(u / r));
}

static int cmp_ld(const void *a, const void *b)
{
    long double x = *(const long double *)a, y = *(const long double *)b;
    return x < y ? -1 : (x > y);
}

/* The area of the disk of centre (cx, cy) and radius r inside the
 * rectangle [x0, x1] x [y0, y1].  Along u = y - cy the chord is
 * [cx - w, cx + w], w = sqrt(r^2 - u^2); clipped to [x0, x1] its length is
 * min(x1, cx + w) - max(x0, cx - w) where positive.  Which of each pair is
 * taken changes only where w = |x0 - cx| or |x1 - cx|, and the length
 * reaches 0 only there or at w = 0: between those heights the length is
 * one of x1 - x0, (cx + r - x0) + (w - r), (x1 - cx + r) + (w - r),
 * 2 r + 2 (w - r), or 0, integrated with G. */
static long double disk_rect(long double cx, long double cy, long double r, long double x0,
                             long double x1, long double y0, long double y1)
{
    long double ua = fmaxl(y0 - cy, -r), ub = fminl(y1 - cy, r), br[6];
    if (!(ua < ub) || !(x0 < x1))
        return 0;
    int n = 0;
    br[n++] = ua;
    long double d[2] = {x0 - cx, x1 - cx};
    for (int k = 0; k < 2; k++)
        if (fabsl(d[k]) < r) {
            long double h = sqrtl((r - d[k]) * (r + d[k]));
            if (h > ua && h < ub)
                br[n++] = h;
            if (-h > ua && -h < ub)
                br[n++] = -h;
        }
    br[n++] = ub;
    qsort(br, (size_t)n, sizeof *br, cmp_ld);
    long double area = 0;
    for (int k = 0; k + 1 < n; k++) {
        long double a = br[k], b = br[k + 1], m = 0.5L * (a + b);
        if (!(b > a))
            continue;
        long double w = sqrtl((r - m) * (r + m));
        int right = cx + w < x1, left = cx - w > x0; /* the chord's own ends */
        long double top = right ? cx + w : x1, bot = left ? cx - w : x0;
        if (!(top > bot))
            continue;
        long double dG = G(r, b) - G(r, a), L = b - a;
        if (right && left)
            area += 2 * r * L + 2 * dG;
        else if (right)
            area += (cx + r - x0) * L + dG;
        else if (left)
            area += (x1 - cx + r) * L + dG;
        else
            area += (x1 - x0) * L;
    }
    return area;
}

/* The ellipse (x - cx)^2 / a^2 + (y - cy)^2 / b^2 <= 1 inside the
 * rectangle: x' = x b / a maps it to a disk of radius b, areas times b / a. */
static long double ellipse_rect(long double cx, long double cy, long double a, long double b,
                                long double x0, long double x1, long double y0, long double y1)
{
    long double k = b / a;
    return disk_rect(cx * k, cy, b, x0 * k, x1 * k, y0, y1) / k;
}

/* ---- scenes, in pixel units ---- */

static aa_scene *new_scene(aa_fill_rule rule)
{
    aa_scene *s = aa_scene_new(black);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, white, rule), AA_OK);
    return s;
}

/* A closed ellipse of centre c and semi-diameters u, v, one arc from t = 0
 * to 2 pi (or back), starting and ending at c + u. */
static void add_ellipse(aa_scene *s, double cx, double cy, double ux, double uy, double vx,
                        double vy, int reversed)
{
    assert_int_equal(aa_scene_move_to(s, cx + ux, cy + uy), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, 0, reversed ? -2 * M_PI : 2 * M_PI,
                                     cx + ux, cy + uy),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

static aa_scene *disk_scene(double cx, double cy, double r)
{
    aa_scene *s = new_scene(AA_FILL_NONZERO);
    add_ellipse(s, cx, cy, r, 0, 0, r, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* The reference of a scene in pixel units, with its bounds and stats. */
static void ref(const aa_scene *s, int w, int h, const char *filter, int mode, aa_image *img,
                aa_image *bound, aa_truth_stats *st)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    assert_int_equal(aa_image_alloc(img, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(bound, w, h, 1), AA_OK);
    int status = aa__truth_render_mode(s, &f, 0, mode, img, bound, st, NULL);
    if (status)
        fail_msg("reference: %s", aa_last_error());
}

/* The area of a shape inside pixel (i, j). */
typedef long double (*area_fn)(const void *shape, long double x0, long double x1, long double y0,
                               long double y1);

typedef struct disk {
    long double cx, cy, r;
    long double r_in;   /* annulus: the hole's radius (0: none) */
    int half;           /* 1: only y >= cy */
    long double a, b;   /* an axis-aligned ellipse when a > 0 */
} disk;

static long double shape_rect(const void *shape, long double x0, long double x1, long double y0,
                              long double y1)
{
    const disk *d = shape;
    if (d->half)
        y0 = fmaxl(y0, d->cy);
    if (d->a > 0)
        return ellipse_rect(d->cx, d->cy, d->a, d->b, x0, x1, y0, y1);
    long double A = disk_rect(d->cx, d->cy, d->r, x0, x1, y0, y1);
    if (d->r_in > 0)
        A -= disk_rect(d->cx, d->cy, d->r_in, x0, x1, y0, y1);
    return A;
}

/* Every pixel of the box reference against the shape's area in it, each
 * within its bound, and every bound at most `cap`; the largest error, and
 * the largest bound into *max_bound. */
static double check_pixels_cap(const char *what, const aa_scene *s, int w, int h, int mode,
                               const disk *d, double cap, double *max_bound)
{
    aa_image img, bound;
    aa_truth_stats st;
    ref(s, w, h, "box", mode, &img, &bound, &st);
    double worst = 0, wb = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double want = (double)shape_rect(d, i, i + 1, j, j + 1);
            double got = aa_pixel(&img, i, j)[0], b = *aa_pixel(&bound, i, j), e = fabs(got - want);
            worst = fmax(worst, e);
            wb = fmax(wb, b);
            if (!(e <= b + CLOSED_ERR) || !(b <= cap))
                fail_msg("%s pixel (%d, %d): reference %.17g, closed form %.17g, error %.2e, "
                         "bound %.2e", what, i, j, got, want, e, b);
        }
    print_message("%-40s %dx%d box%s: max |ref - closed form| %.2e, max bound %.2e, %zu "
                  "integrated\n", what, w, h, mode == AA__TRUTH_CROWD ? " (crowd)" : "", worst, wb,
                  st.integrated);
    *max_bound = wb;
    aa_image_free(&img);
    aa_image_free(&bound);
    return worst;
}

static double check_pixels(const char *what, const aa_scene *s, int w, int h, int mode,
                           const disk *d, double *max_bound)
{
    return check_pixels_cap(what, s, w, h, mode, d, AA_TRUTH_BOUND, max_bound);
}

/* The sum of the reference over the image against `area`, within the sum
 * of the bounds. */
static void check_sum_mode(const char *what, const aa_scene *s, int w, int h,
                           const char *filter, int mode, double area)
{
    aa_image img, bound;
    aa_truth_stats st;
    ref(s, w, h, filter, mode, &img, &bound, &st);
    long double sum = 0, bsum = 0;
    for (int k = 0; k < w * h; k++) {
        sum += img.v[3 * k];
        bsum += bound.v[k];
    }
    double e = fabs((double)(sum - area));
    print_message("%-40s %dx%d %-12s%s sum - area %.2e (sum of bounds %.2e, max %.2e)\n", what,
                  w, h, filter, mode == AA__TRUTH_CROWD ? " (crowd)" : mode == AA__TRUTH_QAG ? " (QAG)" : "",
                  e, (double)bsum,
                  st.max_bound);
    assert_true(st.max_bound <= AA_TRUTH_BOUND);
    if (!(e <= bsum + 1e-13))
        fail_msg("%s %s mode %d: sum %.17g, area %.17g", what, filter, mode, (double)sum, area);
    aa_image_free(&img);
    aa_image_free(&bound);
}

static void check_sum(const char *what, const aa_scene *s, int w, int h, const char *filter,
                      double area)
{
    check_sum_mode(what, s, w, h, filter, 0, area);
}

/* ---- tests ---- */

static void test_disk(void **state)
{
    (void)state;
    const double cx = 23.37, cy = 19.81, r = 9.6;
    aa_scene *s = disk_scene(cx, cy, r);
    disk d = {cx, cy, r, 0, 0, 0, 0};
    double b;
    check_pixels("disk r = 9.6", s, 48, 40, 0, &d, &b);
    check_pixels("disk r = 9.6", s, 48, 40, AA__TRUTH_CROWD, &d, &b);
    aa_scene_free(s);
    /* sums: the disk is 12.4 px or more inside the image */
    s = disk_scene(32.37, 31.81, 7.3);
    const char *filters[] = {"box", "tent:r=1", "gauss:s=1.4"};
    for (int k = 0; k < 3; k++)
        check_sum("disk r = 7.3", s, 64, 64, filters[k], M_PI * 7.3 * 7.3);
    aa_scene_free(s);
}

/* Extremes on pixel lines: the top at y = 18, the bottom at 42, the sides
 * at x = 20 and 44 (tangent to the box's window sides there). */
static void test_disk_on_grid(void **state)
{
    (void)state;
    aa_scene *s = disk_scene(32, 30, 12);
    disk d = {32, 30, 12, 0, 0, 0, 0};
    double b;
    check_pixels("disk on the grid", s, 64, 64, 0, &d, &b);
    check_sum("disk on the grid", s, 64, 64, "tent:r=1", M_PI * 144);
    aa_scene_free(s);
}

/* A circle of radius 0.3 inside one pixel, centred on its centre (the
 * filters' masses within radius 0.3), and one across four pixels. */
static void test_tiny(void **state)
{
    (void)state;
    const double a = 0.3;
    aa_scene *s = disk_scene(8.5, 6.5, a);
    disk d = {8.5, 6.5, a, 0, 0, 0, 0};
    double b;
    check_pixels("tiny circle, centred", s, 16, 12, 0, &d, &b);
    struct {
        const char *filter;
        double want;
    } centred[] = {
        {"box", M_PI * a * a},
        {"tent:r=1", M_PI * a * a - 8 * a * a * a / 3 + a * a * a * a / 2},
        {"gauss:s=0.5", -expm1(-a * a / (2 * 0.25))},
        {"gauss:s=0.2", -expm1(-a * a / (2 * 0.04))},
        {"cone:r=1", 3 * a * a - 2 * a * a * a},
        {"cone:r=0.5", 3 * a * a / 0.25 - 2 * a * a * a / 0.125},
    };
    for (size_t k = 0; k < sizeof centred / sizeof *centred; k++)
        for (int mode = 0; mode <= AA__TRUTH_CROWD; mode++) {
            aa_image img, bound;
            aa_truth_stats st;
            ref(s, 16, 12, centred[k].filter, mode, &img, &bound, &st);
            double got = aa_pixel(&img, 8, 6)[0], bd = *aa_pixel(&bound, 8, 6);
            double e = fabs(got - centred[k].want);
            print_message("tiny circle, centred, %-12s mode %d: %.17f, error %.2e, bound %.2e\n",
                          centred[k].filter, mode, got, e, bd);
            if (!(e <= bd + CLOSED_ERR) || !(bd <= AA_TRUTH_BOUND))
                fail_msg("%s mode %d: reference %.17g, closed form %.17g", centred[k].filter,
                         mode, got, centred[k].want);
            aa_image_free(&img);
            aa_image_free(&bound);
        }
    aa_scene_free(s);
    s = disk_scene(10.1, 10.9, a);
    disk d2 = {10.1, 10.9, a, 0, 0, 0, 0};
    check_pixels("tiny circle across four pixels", s, 16, 16, 0, &d2, &b);
    check_sum("tiny circle across four pixels", s, 16, 16, "tent:r=1", M_PI * a * a);
    aa_scene_free(s);
    /* radius 1e-3 on a pixel centre: its extremes lie on the sides of the
     * neighbours' windows (the crowd path once kept the colour inside it
     * on a neighbour's left side below it: 1 off) */
    s = disk_scene(8.5, 8.5, 1e-3);
    for (int mode = 0; mode <= AA__TRUTH_CROWD; mode++) {
        check_sum_mode("circle r = 1e-3 on a pixel centre", s, 16, 16, "tent:r=1", mode,
                       M_PI * 1e-6);
        check_sum_mode("circle r = 1e-3 on a pixel centre", s, 16, 16, "box", mode, M_PI * 1e-6);
    }
    aa_scene_free(s);
}

/* The lower half (y >= cy) of a disk: the arc t = 0 .. pi, closed by the
 * diameter. */
static void test_half_disk(void **state)
{
    (void)state;
    const double cx = 20.25, cy = 14.6, r = 11.3;
    aa_scene *s = new_scene(AA_FILL_NONZERO);
    assert_int_equal(aa_scene_move_to(s, cx + r, cy), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, r, 0, 0, r, 0, M_PI, cx - r, cy), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    disk d = {cx, cy, r, 0, 1, 0, 0};
    double b;
    check_pixels("half disk", s, 40, 32, 0, &d, &b);
    check_pixels("half disk", s, 40, 32, AA__TRUTH_CROWD, &d, &b);
    aa_scene_free(s);
}

/* An annulus: even-odd with both circles the same way round, nonzero with
 * the inner one reversed. */
static void test_annulus(void **state)
{
    (void)state;
    const double cx = 30.6, cy = 29.2, ra = 13.4, rb = 6.1;
    for (int nonzero = 0; nonzero <= 1; nonzero++) {
        aa_scene *s = new_scene(nonzero ? AA_FILL_NONZERO : AA_FILL_EVENODD);
        add_ellipse(s, cx, cy, ra, 0, 0, ra, 0);
        add_ellipse(s, cx, cy, rb, 0, 0, rb, nonzero);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        disk d = {cx, cy, ra, rb, 0, 0, 0};
        double b;
        const char *what = nonzero ? "annulus, nonzero" : "annulus, even-odd";
        check_pixels(what, s, 60, 60, 0, &d, &b);
        check_sum(what, s, 60, 60, nonzero ? "gauss:s=1.4" : "tent:r=1",
                  M_PI * (ra * ra - rb * rb));
        aa_scene_free(s);
    }
}

/* An axis-aligned ellipse per pixel; one rotated by 30 degrees (centre c,
 * u = a (cos 30, sin 30), v = b (-sin 30, cos 30)) by its area pi a b. */
static void test_ellipse(void **state)
{
    (void)state;
    const double a = 13.5, b = 6.25;
    aa_scene *s = new_scene(AA_FILL_NONZERO);
    add_ellipse(s, 24.3, 16.7, a, 0, 0, b, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    disk d = {24.3, 16.7, 0, 0, 0, a, b};
    double mb;
    check_pixels("ellipse 13.5 x 6.25", s, 48, 32, 0, &d, &mb);
    aa_scene_free(s);
    const double c = cos(M_PI / 6), sn = sin(M_PI / 6);
    s = new_scene(AA_FILL_NONZERO);
    add_ellipse(s, 32.2, 31.7, a * c, a * sn, -b * sn, b * c, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const char *filters[] = {"box", "tent:r=1", "gauss:s=1.4"};
    for (int k = 0; k < 3; k++)
        check_sum("ellipse rotated by 30 degrees", s, 64, 64, filters[k], M_PI * a * b);
    aa_scene_free(s);
}

/* A circle of radius 10^4 whose rightmost point is at (40, 32): only a cap
 * 0.05 px deep at the image's top and bottom rows is visible, the rest of
 * the image left of it is inside.  Centre x = 40 - 10^4 is exact. */
static void test_huge(void **state)
{
    (void)state;
    const double r = 1e4, cx = 40 - r, cy = 32;
    aa_scene *s = disk_scene(cx, cy, r);
    disk d = {cx, cy, r, 0, 0, 0, 0};
    double b;
    check_pixels("circle r = 1e4, a cap", s, 64, 64, 0, &d, &b);
    check_sum("circle r = 1e4, a cap", s, 64, 64, "box",
              (double)disk_rect(cx, cy, r, 0, 64, 0, 64));
    aa_scene_free(s);
    /* Radius 1e6: the crossings, sums of terms of 1e6 in long double, are
     * off by 1e-13 (the error came out 1.6e-14 where the bound said 1.3e-14
     * before it counted the size of the pieces' numbers): the bound must
     * still hold, though it exceeds AA_TRUTH_BOUND (about 1.7e-12). */
    const double R = 1e6, CX = 40 - R;
    s = disk_scene(CX, cy, R);
    disk D = {CX, cy, R, 0, 0, 0, 0};
    check_pixels_cap("circle r = 1e6, a cap", s, 64, 64, 0, &D, 1e-11, &b);
    assert_true(b > AA_TRUTH_BOUND); /* said so */
    aa_scene_free(s);
}

/* Arcs that start and end away from the ellipse's extremes, and arcs that
 * meet: a pie slice (the arc from angle t0 to t1 and two radii: area
 * r^2 (t1 - t0) / 2), a circular segment (the arc and its chord: r^2 (th -
 * sin th) / 2 for the angle th it spans), and two circles of radius r,
 * centres d apart, crossing: their lens has area 2 r^2 acos(d / (2 r)) -
 * (d / 2) sqrt(4 r^2 - d^2), so nonzero covers 2 pi r^2 - lens and
 * even-odd 2 pi r^2 - 2 lens.  Sums under the box and the tent of radius
 * 1; the crowd path per pixel against the default. */
static void test_slices_and_meetings(void **state)
{
    (void)state;
    const double cx = 20.3, cy = 19.6, r = 11.7, t0 = 0.37, t1 = 2.9;
    aa_scene *s = new_scene(AA_FILL_NONZERO);
    assert_int_equal(aa_scene_move_to(s, cx, cy), AA_OK);
    assert_int_equal(aa_scene_line_to(s, cx + r * cos(t0), cy + r * sin(t0)), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, r, 0, 0, r, t0, t1, cx + r * cos(t1),
                                     cy + r * sin(t1)), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_sum("pie slice", s, 40, 40, "box", r * r * (t1 - t0) / 2);
    check_sum("pie slice", s, 40, 40, "tent:r=1", r * r * (t1 - t0) / 2);
    aa_scene_free(s);
    /* the segment of the arc from -1.1 to 1.9 (y up and down, x both ways) */
    const double a0 = -1.1, a1 = 1.9;
    s = new_scene(AA_FILL_NONZERO);
    assert_int_equal(aa_scene_move_to(s, cx + r * cos(a0), cy + r * sin(a0)), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, r, 0, 0, r, a0, a1, cx + r * cos(a1),
                                     cy + r * sin(a1)), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_sum("circular segment", s, 40, 40, "box", r * r * ((a1 - a0) - sin(a1 - a0)) / 2);
    aa_scene_free(s);
    const double rr = 8, d = 6.3, lens = 2 * rr * rr * acos(d / (2 * rr)) -
                                         d / 2 * sqrt(4 * rr * rr - d * d);
    for (int nonzero = 0; nonzero <= 1; nonzero++) {
        s = new_scene(nonzero ? AA_FILL_NONZERO : AA_FILL_EVENODD);
        add_ellipse(s, 20.2, 20.7, rr, 0, 0, rr, 0);
        add_ellipse(s, 20.2 + d * 0.6, 20.7 + d * 0.8, rr, 0, 0, rr, 0);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        double area = 2 * M_PI * rr * rr - (nonzero ? 1 : 2) * lens;
        const char *what = nonzero ? "two circles crossing, nonzero" : "two circles crossing, even-odd";
        check_sum(what, s, 44, 44, "box", area);
        check_sum(what, s, 44, 44, "tent:r=1", area);
        aa_image a, b, ba, bb;
        aa_truth_stats sa, sb;
        ref(s, 44, 44, "cone:r=1", 0, &a, &ba, &sa);
        ref(s, 44, 44, "cone:r=1", AA__TRUTH_CROWD, &b, &bb, &sb);
        double worst = 0;
        for (int p = 0; p < 44 * 44; p++) {
            double e = fabs(a.v[3 * p] - b.v[3 * p]);
            worst = fmax(worst, e);
            if (!(e <= ba.v[p] + bb.v[p]))
                fail_msg("%s pixel %d: default %.17g, crowd %.17g", what, p, a.v[3 * p],
                         b.v[3 * p]);
        }
        print_message("%-40s cone: max |default - crowd| %.2e, bounds %.1e %.1e\n", what, worst,
                      sa.max_bound, sb.max_bound);
        assert_true(sa.max_bound <= AA_TRUTH_BOUND && sb.max_bound <= AA_TRUTH_BOUND);
        aa_image_free(&a);
        aa_image_free(&b);
        aa_image_free(&ba);
        aa_image_free(&bb);
        aa_scene_free(s);
    }
}

/* Seeded random pie slices of ellipses: centre c, conjugate semi-diameters
 * u, v (any angle between them), the arc from t0 to t1 (either way, up to
 * a full turn) and the two radii.  The slice is the image of a circular
 * sector under the linear map (u, v), so its area is |u x v| |t1 - t0| / 2;
 * the box reference sums to it, and the crowd path agrees with the default
 * per pixel within their bounds, under the box and (for the cone, every
 * other scene) the cone, whose default path once missed by 5e-14, beyond
 * its bound of 1.2e-14, where an arc passed 1e-4 from a pixel's centre
 * (slice 17). */
static void random_slices(const char *filter, int step)
{
    const int w = 24, h = 24;
    int box = !strcmp(filter, "box");
    double worst_sum = 0, worst_pix = 0, worst_bound = 0;
    for (int sc = 1; sc < 120; sc += step) {
        aa_rng rng;
        aa_rng_seed(&rng, 27, (uint64_t)sc, 0);
        double q[8];
        for (int k = 0; k < 8; k++)
            q[k] = aa_rng_uniform(&rng);
        double cx = 8 + 8 * q[0], cy = 8 + 8 * q[1], a = 1 + 6 * q[2], b = 0.05 + 6 * q[3];
        double th = 2 * M_PI * q[4], sk = 0.3 + 2.5 * q[5]; /* angle from u to v */
        double ux = a * cos(th), uy = a * sin(th), vx = b * cos(th + sk), vy = b * sin(th + sk);
        double t0 = 2 * M_PI * q[6] - M_PI, dt = (sc % 3 == 0 ? -1 : 1) * (0.05 + 6.2 * q[7]);
        double t1 = t0 + dt;
        aa_scene *s = new_scene(AA_FILL_NONZERO);
        assert_int_equal(aa_scene_move_to(s, cx, cy), AA_OK);
        assert_int_equal(aa_scene_line_to(s, cx + ux * cos(t0) + vx * sin(t0),
                                          cy + uy * cos(t0) + vy * sin(t0)), AA_OK);
        assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, t0, t1,
                                         cx + ux * cos(t1) + vx * sin(t1),
                                         cy + uy * cos(t1) + vy * sin(t1)), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        double area = fabs(ux * vy - uy * vx) * fabs(dt) / 2;
        aa_image img[2], bound[2];
        aa_truth_stats st[2];
        ref(s, w, h, filter, 0, &img[0], &bound[0], &st[0]);
        ref(s, w, h, filter, AA__TRUTH_CROWD, &img[1], &bound[1], &st[1]);
        long double sum = 0, bsum = 0;
        for (int p = 0; p < w * h; p++) {
            sum += img[0].v[3 * p];
            bsum += bound[0].v[p];
            double e = fabs(img[0].v[3 * p] - img[1].v[3 * p]);
            worst_pix = fmax(worst_pix, e);
            if (!(e <= bound[0].v[p] + bound[1].v[p]))
                fail_msg("slice %d pixel (%d, %d): default %.17g, crowd %.17g, bounds %.1e %.1e",
                         sc, p % w, p / w, img[0].v[3 * p], img[1].v[3 * p], bound[0].v[p],
                         bound[1].v[p]);
        }
        double e = box ? fabs((double)(sum - area)) : 0;
        worst_sum = fmax(worst_sum, e);
        worst_bound = fmax(worst_bound, fmax(st[0].max_bound, st[1].max_bound));
        if (!(e <= bsum + 1e-13))
            fail_msg("slice %d: sum %.17g, area %.17g (sum of bounds %.1e)", sc, (double)sum, area,
                     (double)bsum);
        assert_true(st[0].max_bound <= AA_TRUTH_BOUND && st[1].max_bound <= AA_TRUTH_BOUND);
        for (int m = 0; m < 2; m++) {
            aa_image_free(&img[m]);
            aa_image_free(&bound[m]);
        }
        aa_scene_free(s);
    }
    print_message("%d random pie slices of ellipses, %s: max |default - crowd| %.2e, max "
                  "bound %.2e", (119 + step - 1) / step, filter, worst_pix, worst_bound);
    if (box)
        print_message(", max |sum - area| %.2e", worst_sum);
    print_message("\n");
}

static void test_random_slices(void **state)
{
    (void)state;
    random_slices("box", 1);
    random_slices("cone:r=1", 2);
}

/* Seeded random scenes of three elliptical arcs (one closed by a parabolic
 * arc) that cross, turn and meet, even-odd and nonzero, under the Gaussian
 * and the cone: the crowd path agrees with the default per pixel within
 * both bounds.  Scene 66 under the Gaussian once came out 2.5e-14 off in
 * the crowd path with a bound of 7.6e-15 (a kink line crossing an ellipse
 * just below its top). */
static void test_random_crossing_arcs(void **state)
{
    (void)state;
    const int w = 20, h = 20;
    const char *filters[] = {"gauss:s=0.5", "cone:r=1"};
    for (int fi = 0; fi < 2; fi++) {
        double worst = 0;
        for (int sc = 60; sc < 70; sc++) {
            aa_rng rng;
            aa_rng_seed(&rng, 31, (uint64_t)sc, 0);
            aa_scene *s = new_scene(sc % 2 ? AA_FILL_EVENODD : AA_FILL_NONZERO);
            for (int e = 0; e < 3; e++) {
                double q[8];
                for (int k = 0; k < 8; k++)
                    q[k] = aa_rng_uniform(&rng);
                double cx = 5 + 10 * q[0], cy = 5 + 10 * q[1], a = 1 + 6 * q[2], b = 0.3 + 5 * q[3];
                double th = 2 * M_PI * q[4], sk = 0.3 + 2.5 * q[5];
                double ux = a * cos(th), uy = a * sin(th), vx = b * cos(th + sk), vy = b * sin(th + sk);
                double t0 = 2 * M_PI * q[6] - M_PI, t1 = t0 + (e % 2 ? -1 : 1) * (0.3 + 5.9 * q[7]);
                double x0 = cx + ux * cos(t0) + vx * sin(t0), y0 = cy + uy * cos(t0) + vy * sin(t0);
                assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
                assert_int_equal(aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, t0, t1,
                                                 cx + ux * cos(t1) + vx * sin(t1),
                                                 cy + uy * cos(t1) + vy * sin(t1)), AA_OK);
                if (e == 2)
                    assert_int_equal(aa_scene_quad_to(s, cx + 3, cy - 4, x0, y0), AA_OK);
                assert_int_equal(aa_scene_close(s), AA_OK);
            }
            assert_int_equal(aa_scene_finish(s), AA_OK);
            aa_image img[2], bound[2];
            aa_truth_stats st[2];
            ref(s, w, h, filters[fi], 0, &img[0], &bound[0], &st[0]);
            ref(s, w, h, filters[fi], AA__TRUTH_CROWD, &img[1], &bound[1], &st[1]);
            for (int p = 0; p < w * h; p++) {
                double e = fabs(img[0].v[3 * p] - img[1].v[3 * p]);
                worst = fmax(worst, e);
                if (!(e <= bound[0].v[p] + bound[1].v[p]))
                    fail_msg("scene %d %s pixel (%d, %d): default %.17g, crowd %.17g, bounds "
                             "%.1e %.1e", sc, filters[fi], p % w, p / w, img[0].v[3 * p],
                             img[1].v[3 * p], bound[0].v[p], bound[1].v[p]);
            }
            assert_true(st[0].max_bound <= AA_TRUTH_BOUND && st[1].max_bound <= AA_TRUTH_BOUND);
            for (int m = 0; m < 2; m++) {
                aa_image_free(&img[m]);
                aa_image_free(&bound[m]);
            }
            aa_scene_free(s);
        }
        print_message("10 random scenes of crossing arcs, %-12s max |default - crowd| %.2e\n",
                      filters[fi], worst);
    }
}

/* The QAG path against the default (the Gaussian's panels, which send
 * conic pieces to QAG) and the crowd path, on a rotated ellipse crossing
 * a line, under the Gaussian and the cone: within their bounds. */
static void test_paths_agree(void **state)
{
    (void)state;
    aa_scene *s = new_scene(AA_FILL_EVENODD);
    add_ellipse(s, 12.3, 10.1, 7.5 * 0.8, 7.5 * 0.6, -3.2 * 0.6, 3.2 * 0.8, 0);
    assert_int_equal(aa_scene_move_to(s, 2.2, 3.1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 21.7, 15.3), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 3.4, 18.9), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const char *filters[] = {"gauss:s=0.5", "cone:r=1", "tent:r=0.7"};
    for (int k = 0; k < 3; k++) {
        aa_image img[3], bound[3];
        aa_truth_stats st[3];
        for (int mode = 0; mode < 3; mode++)
            ref(s, 24, 20, filters[k], mode, &img[mode], &bound[mode], &st[mode]);
        double worst = 0;
        for (int p = 0; p < 24 * 20; p++)
            for (int mode = 1; mode < 3; mode++) {
                double e = fabs(img[0].v[3 * p] - img[mode].v[3 * p]);
                worst = fmax(worst, e);
                if (!(e <= bound[0].v[p] + bound[mode].v[p]))
                    fail_msg("%s pixel %d: default %.17g, mode %d %.17g", filters[k], p,
                             img[0].v[3 * p], mode, img[mode].v[3 * p]);
            }
        print_message("ellipse and triangle, %-12s max |default - QAG, crowd| %.2e, bounds "
                      "%.1e %.1e %.1e\n", filters[k], worst, st[0].max_bound, st[1].max_bound,
                      st[2].max_bound);
        for (int mode = 0; mode < 3; mode++) {
            assert_true(st[mode].max_bound <= AA_TRUTH_BOUND);
            aa_image_free(&img[mode]);
            aa_image_free(&bound[mode]);
        }
    }
    aa_scene_free(s);
}

/* Circles passing 1e-3 px and 1e-6 px from pixel centres, under the cone:
 * there a piece's term changes on the scale of that distance (the crowd
 * path's breakpoint where a piece passes closest to the centre); the three
 * paths within their bounds. */
static void test_near_centre(void **state)
{
    (void)state;
    aa_scene *s = new_scene(AA_FILL_NONZERO);
    add_ellipse(s, 4.5 + 2.001, 5.5, 2, 0, 0, 2, 0);
    add_ellipse(s, 12.5, 5.5 - 1.5 - 1e-6, 1.2, 0, 0, 1.5, 0);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img[3], bound[3];
    aa_truth_stats st[3];
    for (int mode = 0; mode < 3; mode++)
        ref(s, 16, 10, "cone:r=1", mode, &img[mode], &bound[mode], &st[mode]);
    double worst = 0;
    for (int p = 0; p < 16 * 10; p++)
        for (int mode = 1; mode < 3; mode++) {
            double e = fabs(img[0].v[3 * p] - img[mode].v[3 * p]);
            worst = fmax(worst, e);
            if (!(e <= bound[0].v[p] + bound[mode].v[p]))
                fail_msg("pixel %d: default %.17g, mode %d %.17g", p, img[0].v[3 * p], mode,
                         img[mode].v[3 * p]);
        }
    print_message("circles near pixel centres, cone: max |default - QAG, crowd| %.2e, bounds "
                  "%.1e %.1e %.1e\n", worst, st[0].max_bound, st[1].max_bound, st[2].max_bound);
    for (int mode = 0; mode < 3; mode++) {
        assert_true(st[mode].max_bound <= AA_TRUTH_BOUND);
        aa_image_free(&img[mode]);
        aa_image_free(&bound[mode]);
    }
    aa_scene_free(s);
}

/* truth_circle_heights on conic pieces: each height found is where the
 * piece is at distance R from the centre (the piece's x there from the
 * circle's own equation, not from the reference's crossing), and as many
 * are found as sign changes of that distance less R on a fine grid. */
static void test_circle_heights(void **state)
{
    (void)state;
    const double cx = 10.3, cy = 9.7, r = 3.1;
    aa_scene *s = disk_scene(cx, cy, r);
    size_t np;
    const aa_piece *pc = aa_scene_pieces(s, &np);
    gsl_poly_complex_workspace *ws = gsl_poly_complex_workspace_alloc(5);
    assert_non_null(ws);
    int total = 0;
    for (size_t k = 0; k < np; k++) {
        const aa_piece *p = &pc[k];
        assert_int_equal(p->kind, AA_PIECE_CONIC);
        for (double uc = 6.5; uc < 14; uc += 1.0)
            for (double vc = 5.5; vc < 14; vc += 1.0) {
                double ys[4], R = 1.0;
                int n = truth_circle_heights(p, uc, vc, R, ws, ys);
                /* x on the piece's side of the circle: sign of x - cx */
                double side = p->xmin + p->xmax < 2 * cx ? -1 : 1;
                int changes = 0;
                double prev = NAN;
                for (int q = 0; q <= 4000; q++) {
                    double y = fmax(p->y0, vc - R) + (fmin(p->y1, vc + R) - fmax(p->y0, vc - R)) * q / 4000.0;
                    double x = cx + side * sqrt(fmax(0.0, r * r - (y - cy) * (y - cy)));
                    double g = hypot(x - uc, y - vc) - R;
                    if (q > 0 && (g < 0) != (prev < 0) && g != 0)
                        changes++;
                    prev = g;
                }
                assert_int_equal(n, changes);
                for (int q = 0; q < n; q++) {
                    double y = vc + ys[q];
                    double x = cx + side * sqrt(fmax(0.0, r * r - (y - cy) * (y - cy)));
                    assert_true(fabs(hypot(x - uc, y - vc) - R) < 1e-9);
                }
                total += n;
            }
    }
    print_message("circle crossings of conic pieces: %d found, each on the circle\n", total);
    assert_true(total > 20);
    gsl_poly_complex_workspace_free(ws);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_disk),
             cmocka_unit_test(test_disk_on_grid),
             cmocka_unit_test(test_tiny),
             cmocka_unit_test(test_half_disk),
             cmocka_unit_test(test_annulus),
             cmocka_unit_test(test_ellipse),
             cmocka_unit_test(test_huge),
             cmocka_unit_test(test_slices_and_meetings),
             cmocka_unit_test(test_random_slices),
             cmocka_unit_test(test_random_crossing_arcs),
             cmocka_unit_test(test_paths_agree),
             cmocka_unit_test(test_near_centre),
             cmocka_unit_test(test_circle_heights))
