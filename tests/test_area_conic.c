/*
 * test_area_conic.c: the exact area method (algorithms/area.c) on scenes of
 * elliptical arcs (aa_scene_arc_to: AA_PIECE_CONIC pieces), and every
 * sampling method on a disk, against answers derived here independently of
 * both the method and the scene's pieces.
 *
 * The known answers.  An ellipse is the image of the unit circle under an
 * affine map x = c + M a (M's columns the semi-diameters u, v), so the area
 * of the ellipse inside a convex polygon is |det M| times the area of the
 * unit disc inside the polygon mapped back by M^-1.  That area is the sum,
 * over the polygon's edges AB, of the signed area of the disc inside the
 * triangle (O, A, B) (Green's theorem: the triangles' signed areas add up
 * to the polygon's): AB is cut where it meets the circle (a quadratic in
 * its parameter), and each part is a triangle with O if its middle lies
 * inside the circle, else the circular sector its ends subtend, of area
 * (angle)/2.  This uses the circle's equation only, not its angle form.
 * It is computed in long double (at 4096 px its rounding in double, about
 * 4e-13 a pixel, would hide the method's).
 * Pixel squares, clipped to a half plane or to a rectangle, are such
 * polygons.  Sums over the image: the ellipse's area pi |det M|.
 *
 *  - a disk, an ellipse turned by 30 degrees, an annulus (two circles, even
 *    odd), a half disk (a half circle closed by its diameter), each on a
 *    64x64 image and on a 61x47 one (where the placed circle is an
 *    ellipse), and a disk centred on a pixel corner (its pieces meet on
 *    cells' sides): every pixel within 1e-12 of the closed form, the sum
 *    within 1e-9 of the area (measured: at most 5e-15 and 2e-12);
 *  - 200 random ellipses (any turn, from a tenth of a pixel to past the
 *    image, thin ones, either rule), one at a time on 37x29: every pixel
 *    within 1e-12 of the closed form (measured 5e-15; 9.6e-15 over 2000);
 *  - pie slices of a turned ellipse (an arc between two radii; spans below
 *    and above pi; drawn both ways): arcs that end inside the ellipse's y
 *    range, where a line starts; every pixel within 1e-12 of the closed
 *    form on the pixel clipped to the sector (measured 3.2e-15);
 *  - a disk behind a square of another colour that overlaps it (the bands'
 *    crossings of the square's sides and the arc, aa_piece_meet): every
 *    pixel, each colour's share from the same closed form;
 *  - two crossing disks, in two layers and in one under each fill rule,
 *    at 64x64 and 48x48: every pixel within 1e-12 of the area of disk,
 *    disk and pixel by Green's theorem (arcs and sides cut where they
 *    meet; itself checked against the closed form above and, summed, the
 *    lens formula r1^2 a1 + r2^2 a2 - sqrt(..)/2); measured 2e-15;
 *  - a large disk (radius 1500 px on a 4096-pixel-wide image, rows near its
 *    top, middle and bottom): each pixel within 1e-11 of the closed form
 *    (measured: 9e-15);
 *  - every sampling method that takes a scene on a disk of radius 40 px at
 *    128x128 (the home filter: box, else Crow's tent, else the Gaussian):
 *    the image's mean within 2% of pi r^2 / (W H), and `point`'s exactly
 *    the count of pixel centres inside the disk, counted here; and
 *    crowtiler:area=exact,hidden=scan (the exact tent prefilter) summing
 *    to the disk's area within 1e-9 (the tent of radius 1 sums to one over
 *    the pixel centres).  A method
 *    that misread conic pieces (x constant along a piece, say) would be off
 *    by far more.  The peer rasterizers (AA_METHOD_SOME_SCENES) and
 *    external programs are left to their own tests.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* ------------------------------------------------------------------------
 * The closed form: the unit disc inside a convex polygon
 * ------------------------------------------------------------------------ */

/* The signed area of the unit disc inside the triangle (O, A, B). */
static long double disc_triangle(long double ax, long double ay, long double bx, long double by)
{
    long double dx = bx - ax, dy = by - ay;
    long double a = dx * dx + dy * dy, b = ax * dx + ay * dy, c = ax * ax + ay * ay - 1.0;
    long double cut[4] = {0.0, 0.0, 0.0, 1.0};
    int n = 1;
    long double disc = b * b - a * c;
    if (a > 0.0 && disc > 0.0) {
        /* the roots of a t^2 + 2 b t + c, without cancellation */
        long double q = -(b + copysignl(sqrtl(disc), b));
        long double t1 = q / a, t2 = q != 0.0 ? c / q : t1;
        if (t1 > t2) {
            long double t = t1;
            t1 = t2, t2 = t;
        }
        if (t1 > 0.0 && t1 < 1.0)
            cut[n++] = t1;
        if (t2 > 0.0 && t2 < 1.0)
            cut[n++] = t2;
    }
    cut[n++] = 1.0;
    long double sum = 0.0;
    for (int k = 0; k + 1 < n; k++) {
        long double ta = cut[k], tb = cut[k + 1], tm = 0.5 * (ta + tb);
        long double px = ax + ta * dx, py = ay + ta * dy, qx = ax + tb * dx, qy = ay + tb * dy;
        long double mx = ax + tm * dx, my = ay + tm * dy;
        /* P x Q = P x (Q - P): no cancellation for a short edge far out */
        long double cr = (tb - ta) * (px * dy - py * dx);
        if (mx * mx + my * my <= 1.0)
            sum += 0.5 * cr; /* the triangle (O, P, Q) */
        else
            sum += 0.5 * atan2l(cr, px * qx + py * qy); /* the sector */
    }
    return sum;
}

/* The area of the unit disc inside the polygon (n points, xy pairs). */
static long double disc_polygon(const long double *xy, int n)
{
    long double sum = 0.0;
    for (int k = 0; k < n; k++) {
        int m = (k + 1) % n;
        sum += disc_triangle(xy[2 * k], xy[2 * k + 1], xy[2 * m], xy[2 * m + 1]);
    }
    return fabsl(sum);
}

/* An ellipse in pixel units: centre (cx, cy), semi-diameters u, v. */
typedef struct ellipse {
    long double cx, cy, ux, uy, vx, vy;
} ellipse;

/* The area of ellipse e inside the rectangle [x0, x1] x [y0, y1]. */
static double ellipse_rect(const ellipse *e, long double x0, long double y0, long double x1, long double y1)
{
    if (!(x0 < x1 && y0 < y1))
        return 0.0;
    long double det = e->ux * e->vy - e->uy * e->vx;
    const long double corner[8] = {x0, y0, x1, y0, x1, y1, x0, y1};
    long double q[8];
    for (int k = 0; k < 4; k++) {
        long double dx = corner[2 * k] - e->cx, dy = corner[2 * k + 1] - e->cy;
        q[2 * k] = (dx * e->vy - dy * e->vx) / det;
        q[2 * k + 1] = (e->ux * dy - e->uy * dx) / det;
    }
    return fabsl(det) * disc_polygon(q, 4);
}

/* The closed form itself, on shapes whose answers are known otherwise: the
 * whole disc, a half (a square through its centre), a quarter. */
static void test_closed_form(void **state)
{
    (void)state;
    const ellipse unit = {0, 0, 1, 0, 0, 1};
    assert_true(fabs(ellipse_rect(&unit, -2, -2, 2, 2) - M_PI) < 1e-15);
    assert_true(fabs(ellipse_rect(&unit, 0, -2, 2, 2) - M_PI / 2) < 1e-15);
    assert_true(fabs(ellipse_rect(&unit, 0, 0, 3, 3) - M_PI / 4) < 1e-15);
    /* the square inscribed, and the strip |x| < 1/2: 2 (asin(1/2) + (1/2)
     * sqrt(3)/2) */
    double h = sqrt(0.5);
    assert_true(fabs(ellipse_rect(&unit, -h, -h, h, h) - 2.0) < 1e-15);
    assert_true(fabs(ellipse_rect(&unit, -0.5, -2, 0.5, 2) - 2.0 * (M_PI / 6 + sqrt(3) / 4)) <
                1e-15);
    /* an ellipse of semi-axes 3 and 2 turned: pi 6 */
    const ellipse e = {1, 2, 3 * cos(0.3), 3 * sin(0.3), -2 * sin(0.3), 2 * cos(0.3)};
    assert_true(fabs(ellipse_rect(&e, -9, -9, 9, 9) - 6 * M_PI) < 1e-13);
}

/* ------------------------------------------------------------------------
 * Scenes and checks
 * ------------------------------------------------------------------------ */

/* The closed path of ellipse e (pattern units) as two half arcs. */
static void add_ellipse(aa_scene *s, const ellipse *e)
{
    double ax = e->cx + e->ux, ay = e->cy + e->uy, bx = e->cx - e->ux, by = e->cy - e->uy;
    assert_int_equal(aa_scene_move_to(s, ax, ay), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, 0, M_PI, bx,
                                     by),
                     AA_OK);
    assert_int_equal(aa_scene_arc_to(s, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, M_PI,
                                     2 * M_PI, ax, ay),
                     AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

/* Ellipse e (pattern units) placed on a w x h image. */
static ellipse placed(const ellipse *e, int w, int h)
{
    return (ellipse){e->cx * w, e->cy * h, e->ux * w, e->uy * h, e->vx * w, e->vy * h};
}

typedef double (*pixel_fn)(const void *ctx, int i, int j);

/* `area` (both integrators) on the scene at w x h against `truth` per
 * pixel (tol) and its sum against `total` (tol_sum); prints the worst. */
static void check_pixels(const char *what, const aa_scene *s, int w, int h, pixel_fn truth,
                         const void *ctx, double tol, double total, double tol_sum)
{
    const char *methods[2] = {"area", "area:integrator=bands"};
    for (int m = 0; m < 2; m++) {
        aa_image img;
        aa_counters c;
        support_render(methods[m], s, NULL, w, h, 2, &img, &c);
        double worst = 0.0, sum = 0.0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double v = aa_pixel(&img, i, j)[0], t = truth(ctx, i, j), d = fabs(v - t);
                sum += v;
                if (!(d <= tol))
                    fail_msg("%s %dx%d %s: pixel (%d, %d) is %.17g, the closed form %.17g "
                             "(%.3e off)",
                             what, w, h, methods[m], i, j, v, t, d);
                worst = d > worst ? d : worst;
            }
        if (!(fabs(sum - total) <= tol_sum))
            fail_msg("%s %dx%d %s: the pixels sum to %.17g, the area is %.17g", what, w, h,
                     methods[m], sum, total);
        printf("%-34s %5dx%-4d %-22s max |area - closed form| %.2e, sum off %.2e\n", what, w,
               h, methods[m], worst, fabs(sum - total));
        aa_image_free(&img);
    }
}

/* A set of white ellipses in one even-odd layer, nested (an annulus) or
 * one, possibly clipped to y >= ycut (a half disk: the region below the
 * line through the centre). */
typedef struct shape {
    ellipse e[2];
    int n;
    double ycut; /* pixel units; -INFINITY for none */
} shape;

static double shape_pixel(const void *ctx, int i, int j)
{
    const shape *sh = ctx;
    double y0 = j > sh->ycut ? j : sh->ycut;
    double v = 0.0;
    for (int k = 0; k < sh->n; k++)
        v += (k ? -1.0 : 1.0) * ellipse_rect(&sh->e[k], i, y0, i + 1.0, j + 1.0);
    return v;
}

static void check_shape(const char *what, const ellipse *pe, int n, int half, int w, int h)
{
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_EVENODD), AA_OK);
    shape sh = {.n = n, .ycut = -INFINITY};
    double total = 0.0;
    for (int k = 0; k < n; k++) {
        sh.e[k] = placed(&pe[k], w, h);
        double det = (double)fabsl(sh.e[k].ux * sh.e[k].vy - sh.e[k].uy * sh.e[k].vx);
        total += (k ? -1.0 : 1.0) * M_PI * det;
    }
    if (half) {
        /* the half with sin t >= 0 (t from 0 to pi, below the centre for
         * v = (0, r)), closed by the diameter */
        const ellipse *e = &pe[0];
        assert_int_equal(aa_scene_move_to(s, e->cx + e->ux, e->cy + e->uy), AA_OK);
        assert_int_equal(aa_scene_arc_to(s, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, 0, M_PI,
                                         e->cx - e->ux, e->cy - e->uy),
                         AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        sh.ycut = sh.e[0].cy;
        total *= 0.5;
    } else {
        for (int k = 0; k < n; k++)
            add_ellipse(s, &pe[k]);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    check_pixels(what, s, w, h, shape_pixel, &sh, 1e-12, total, 1e-9);
    aa_scene_free(s);
}

static const ellipse disk = {0.5 + 1.0 / 256, 0.5 - 3.0 / 512, 0.3, 0, 0, 0.3};

static void test_disk(void **state)
{
    (void)state;
    check_shape("disk", &disk, 1, 0, 64, 64);
    check_shape("disk", &disk, 1, 0, 61, 47);
    check_shape("disk", &disk, 1, 0, 5, 3);
    /* centred on a pixel corner: its pieces meet on cells' sides */
    const ellipse centred = {0.5, 0.5, 0.42, 0, 0, 0.42};
    check_shape("disk on a pixel corner", &centred, 1, 0, 64, 64);
}

static void test_rotated_ellipse(void **state)
{
    (void)state;
    double c = cos(M_PI / 6), s = sin(M_PI / 6);
    const ellipse e = {0.47, 0.52, 0.4 * c, 0.4 * s, -0.17 * s, 0.17 * c};
    check_shape("ellipse turned 30 degrees", &e, 1, 0, 64, 64);
    check_shape("ellipse turned 30 degrees", &e, 1, 0, 61, 47);
}

static void test_annulus(void **state)
{
    (void)state;
    const ellipse ring[2] = {{0.5, 0.5, 0.42, 0, 0, 0.42}, {0.51, 0.49, 0.2, 0, 0, 0.2}};
    check_shape("annulus", ring, 2, 0, 64, 64);
    check_shape("annulus", ring, 2, 0, 61, 47);
}

static void test_half_disk(void **state)
{
    (void)state;
    const ellipse e = {0.5 + 1.0 / 128, 0.4 + 1.0 / 1024, 0.35, 0, 0, 0.35};
    check_shape("half disk", &e, 1, 1, 64, 64);
    check_shape("half disk", &e, 1, 1, 61, 47);
    /* its centre and the diameter's ends on pixel corners */
    const ellipse corner = {0.5, 0.5, 0.375, 0, 0, 0.375};
    check_shape("half disk on pixel corners", &corner, 1, 1, 64, 64);
}

/* Random ellipses, one at a time: any turn, sizes from a tenth of a pixel
 * to past the image, thin ones, some reaching outside it (the sum is then
 * not checked), on 37x29 (so placed circles are ellipses too).  The
 * stream is a fixed one (aa_hash64 of the index). */
static void test_random_ellipses(void **state)
{
    (void)state;
    const int w = 37, h = 29;
    double worst = 0.0;
    for (int k = 0; k < 200; k++) {
        double r[6];
        for (int q = 0; q < 6; q++)
            r[q] = (double)(aa_hash64(1000003u * (uint64_t)k + (uint64_t)q) >> 11) * 0x1p-53;
        double size = pow(10.0, -2.5 + 2.7 * r[0]); /* 0.003 .. 1.6 pattern units */
        double a = size, b = size * (0.05 + 0.95 * r[1]), t = 2.0 * M_PI * r[2];
        ellipse pe = {0.1 + 0.8 * r[3], 0.1 + 0.8 * r[4], a * cos(t), a * sin(t), -b * sin(t),
                      b * cos(t)};
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, r[5] < 0.5 ? AA_FILL_NONZERO : AA_FILL_EVENODD),
                         AA_OK);
        add_ellipse(s, &pe);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        shape sh = {.e = {placed(&pe, w, h)}, .n = 1, .ycut = -INFINITY};
        aa_image img;
        support_render("area", s, NULL, w, h, 2, &img, NULL);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double v = aa_pixel(&img, i, j)[0], c = shape_pixel(&sh, i, j);
                if (!(fabs(v - c) <= 1e-12))
                    fail_msg("random ellipse %d (centre %.17g %.17g, u %.17g %.17g, v %.17g "
                             "%.17g): pixel (%d, %d) is %.17g, the closed form %.17g",
                             k, pe.cx, pe.cy, pe.ux, pe.uy, pe.vx, pe.vy, i, j, v, c);
                worst = fmax(worst, fabs(v - c));
            }
        aa_image_free(&img);
        aa_scene_free(s);
    }
    printf("200 random ellipses 37x29: max |area - closed form| %.2e\n", worst);
}

/* Sutherland-Hodgman: polygon p (n points) clipped to nx x + ny y >= 0,
 * into q; returns its point count. */
static int clip_half(const long double *p, int n, long double nx, long double ny, long double *q)
{
    int m = 0;
    for (int k = 0; k < n; k++) {
        int l = (k + 1) % n;
        long double dk = nx * p[2 * k] + ny * p[2 * k + 1], dl = nx * p[2 * l] + ny * p[2 * l + 1];
        if (dk >= 0)
            q[2 * m] = p[2 * k], q[2 * m + 1] = p[2 * k + 1], m++;
        if ((dk > 0 && dl < 0) || (dk < 0 && dl > 0)) {
            long double t = dk / (dk - dl);
            q[2 * m] = p[2 * k] + t * (p[2 * l] - p[2 * k]);
            q[2 * m + 1] = p[2 * k + 1] + t * (p[2 * l + 1] - p[2 * k + 1]);
            m++;
        }
    }
    return m;
}

/* A pie slice: the part of ellipse e for t in [ta, tb] (tb - ta < pi)
 * and its centre, i.e. the unit disc's sector mapped by M. */
typedef struct pie {
    ellipse e;
    double ta, tb;
    int whole_minus; /* 1: the ellipse minus this slice */
} pie;

static double pie_pixel(const void *ctx, int i, int j)
{
    const pie *P = ctx;
    const ellipse *e = &P->e;
    long double det = (long double)e->ux * e->vy - (long double)e->uy * e->vx;
    const double corner[8] = {i, j, i + 1.0, j, i + 1.0, j + 1.0, i, j + 1.0};
    long double q[16], r[16], t[16];
    for (int k = 0; k < 4; k++) {
        long double dx = corner[2 * k] - (long double)e->cx, dy = corner[2 * k + 1] - (long double)e->cy;
        q[2 * k] = (dx * e->vy - dy * e->vx) / det;
        q[2 * k + 1] = (e->ux * dy - e->uy * dx) / det;
    }
    /* the sector: cross((cos ta, sin ta), Y) >= 0, cross(Y, (cos tb, sin tb)) >= 0 */
    int n = clip_half(q, 4, -sinl(P->ta), cosl(P->ta), r);
    n = clip_half(r, n, sinl(P->tb), -cosl(P->tb), t);
    double slice = n >= 3 ? (double)(fabsl(det) * disc_polygon(t, n)) : 0.0;
    if (!P->whole_minus)
        return slice;
    return ellipse_rect(e, i, j, i + 1.0, j + 1.0) - slice;
}

/* Pie slices of a turned ellipse: arcs ending inside the ellipse's y range
 * (pieces that end where a line starts, not at a turn), spans below and
 * above pi (the latter the ellipse minus the other slice). */
static void test_pie_slices(void **state)
{
    (void)state;
    const int w = 48, h = 40;
    const double angles[4][2] = {{0.3, 2.0}, {2.5, 4.4}, {-1.2, 0.9}, {0.7, 0.7 + 4.0}};
    for (int k = 0; k < 8; k++) {
        /* the last four drawn the other way round, t falling */
        double c = cos(0.4), sn = sin(0.4), ta = angles[k % 4][0], tb = angles[k % 4][1];
        int back = k >= 4;
        ellipse pe = {0.48, 0.53, 0.35 * c, 0.35 * sn, -0.22 * sn, 0.22 * c};
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        double ax = pe.cx + pe.ux * cos(ta) + pe.vx * sin(ta), ay = pe.cy + pe.uy * cos(ta) + pe.vy * sin(ta);
        double bx = pe.cx + pe.ux * cos(tb) + pe.vx * sin(tb), by = pe.cy + pe.uy * cos(tb) + pe.vy * sin(tb);
        assert_int_equal(aa_scene_move_to(s, pe.cx, pe.cy), AA_OK);
        assert_int_equal(aa_scene_line_to(s, back ? bx : ax, back ? by : ay), AA_OK);
        assert_int_equal(aa_scene_arc_to(s, pe.cx, pe.cy, pe.ux, pe.uy, pe.vx, pe.vy,
                                         back ? tb : ta, back ? ta : tb, back ? ax : bx,
                                         back ? ay : by),
                         AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        pie P = {placed(&pe, w, h), ta, tb, 0};
        if (tb - ta > M_PI) /* the ellipse minus the slice from tb to ta + 2 pi */
            P.ta = tb, P.tb = ta + 2 * M_PI, P.whole_minus = 1;
        double det = (double)fabsl(P.e.ux * P.e.vy - P.e.uy * P.e.vx);
        double total = det * 0.5 * (tb - ta); /* the sector's area: (angle/2) |det M| */
        char what[64];
        snprintf(what, sizeof what, "pie slice t %.1f .. %.1f", back ? tb : ta, back ? ta : tb);
        check_pixels(what, s, w, h, pie_pixel, &P, 1e-12, total, 1e-9);
        aa_scene_free(s);
    }
}

/* A grey square in front of a white disk it overlaps, on black. */
typedef struct layered {
    ellipse e;
    double sq[4]; /* x0 y0 x1 y1, pixel units */
    double grey;
} layered;

static double layered_pixel(const void *ctx, int i, int j)
{
    const layered *L = ctx;
    double x0 = fmax(i, L->sq[0]), y0 = fmax(j, L->sq[1]);
    double x1 = fmin(i + 1.0, L->sq[2]), y1 = fmin(j + 1.0, L->sq[3]);
    double sq = x0 < x1 && y0 < y1 ? (x1 - x0) * (y1 - y0) : 0.0;
    double disk_all = ellipse_rect(&L->e, i, j, i + 1.0, j + 1.0);
    double disk_hidden = ellipse_rect(&L->e, x0, y0, x1, y1);
    return L->grey * sq + (disk_all - disk_hidden);
}

static void test_disk_behind_square(void **state)
{
    (void)state;
    const int sizes[2][2] = {{64, 64}, {61, 47}};
    for (int z = 0; z < 2; z++) {
        int w = sizes[z][0], h = sizes[z][1];
        const double grey = 0.25, sq[4] = {0.55, 0.3, 0.93, 0.71};
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{grey, grey, grey}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, sq[0], sq[1]), AA_OK);
        assert_int_equal(aa_scene_line_to(s, sq[2], sq[1]), AA_OK);
        assert_int_equal(aa_scene_line_to(s, sq[2], sq[3]), AA_OK);
        assert_int_equal(aa_scene_line_to(s, sq[0], sq[3]), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        add_ellipse(s, &disk);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        layered L = {placed(&disk, w, h), {sq[0] * w, sq[1] * h, sq[2] * w, sq[3] * h}, grey};
        double r2 = (double)fabsl(L.e.ux * L.e.vy - L.e.uy * L.e.vx);
        double sqa = (L.sq[2] - L.sq[0]) * (L.sq[3] - L.sq[1]);
        double hidden = ellipse_rect(&L.e, L.sq[0], L.sq[1], L.sq[2], L.sq[3]);
        double total = grey * sqa + M_PI * r2 - hidden;
        check_pixels("disk behind a square", s, w, h, layered_pixel, &L, 1e-12, total, 1e-9);
        aa_scene_free(s);
    }
}

/* ------------------------------------------------------------------------
 * Two disks and a pixel: the area of their intersection by Green's theorem
 * ------------------------------------------------------------------------ */

/* Green's theorem: an area is half the integral of x dy - y dx around its
 * boundary.  The boundary of (disk 1) n (disk 2) n (the pixel) is made of
 * arcs of each circle inside the other two sets and of the pixel's sides
 * inside both disks; each is cut where it meets the others' boundaries,
 * the cut points computed once and shared by the two boundaries that meet
 * there, and each part kept if its middle lies inside the other sets.  An
 * arc of circle (c, r) from point a to point b adds c_x (b_y - a_y) -
 * c_y (b_x - a_x) + r^2 (theta_b - theta_a), a segment a_x b_y - a_y b_x.
 * Long double, coordinates about the pixel's centre. */
typedef struct circ {
    long double x, y, r;
} circ;

#define PI_L 3.14159265358979323846264338327950288L

typedef struct cutpt {
    long double x, y, key;
} cutpt;

static int cmp_cut(const void *a, const void *b)
{
    long double p = ((const cutpt *)a)->key, q = ((const cutpt *)b)->key;
    return p < q ? -1 : p > q;
}

static int in_disk(const circ *c, long double x, long double y)
{
    long double dx = x - c->x, dy = y - c->y;
    return dx * dx + dy * dy < c->r * c->r;
}

static int in_box(long double x, long double y)
{
    return x > -0.5L && x < 0.5L && y > -0.5L && y < 0.5L;
}

/* The points where circle c meets circle o and the pixel's side lines. */
static int circle_cuts(const circ *c, const circ *o, cutpt *out)
{
    int n = 0;
    long double dx = o->x - c->x, dy = o->y - c->y, d = sqrtl(dx * dx + dy * dy);
    if (d > 0 && d < c->r + o->r && d > fabsl(c->r - o->r)) {
        long double a = (c->r * c->r - o->r * o->r + d * d) / (2 * d);
        long double h = sqrtl(fmaxl(c->r * c->r - a * a, 0));
        for (int s = -1; s <= 1; s += 2)
            out[n++] = (cutpt){c->x + (a * dx - s * h * dy) / d, c->y + (a * dy + s * h * dx) / d, 0};
    }
    for (int k = 0; k < 4; k++) {
        long double v = k & 1 ? 0.5L : -0.5L;
        long double e = (k < 2 ? v - c->x : v - c->y), h2 = c->r * c->r - e * e;
        if (h2 <= 0)
            continue;
        long double h = sqrtl(h2);
        for (int s = -1; s <= 1; s += 2)
            out[n++] = k < 2 ? (cutpt){v, c->y + s * h, 0} : (cutpt){c->x + s * h, v, 0};
    }
    return n;
}

static long double arcs_of(const circ *c, const circ *o, const cutpt *all, int nall)
{
    cutpt cut[16];
    int n = 0;
    for (int k = 0; k < nall; k++) {
        long double dx = all[k].x - c->x, dy = all[k].y - c->y;
        /* the points on this circle */
        if (fabsl(sqrtl(dx * dx + dy * dy) - c->r) <= 1e-12L * (1 + c->r))
            cut[n++] = (cutpt){all[k].x, all[k].y, atan2l(dy, dx)};
    }
    qsort(cut, (size_t)n, sizeof *cut, cmp_cut);
    long double sum = 0;
    if (n == 0) { /* the whole circle, or nothing */
        if (in_disk(o, c->x + c->r, c->y) && in_box(c->x + c->r, c->y))
            sum += 2 * PI_L * c->r * c->r; /* c_x, c_y terms vanish on a closed circle */
        return sum;
    }
    for (int k = 0; k < n; k++) {
        const cutpt *a = &cut[k], *b = &cut[(k + 1) % n];
        long double ta = a->key, tb = b->key + (k + 1 == n ? 2 * PI_L : 0), tm = 0.5L * (ta + tb);
        long double mx = c->x + c->r * cosl(tm), my = c->y + c->r * sinl(tm);
        if (!(tb > ta) || !in_disk(o, mx, my) || !in_box(mx, my))
            continue;
        sum += c->x * (b->y - a->y) - c->y * (b->x - a->x) + c->r * c->r * (tb - ta);
    }
    return sum;
}

static long double sides_of(const circ *c1, const circ *c2, const cutpt *all, int nall)
{
    const long double cx[4] = {-0.5L, 0.5L, 0.5L, -0.5L}, cy[4] = {-0.5L, -0.5L, 0.5L, 0.5L};
    long double sum = 0;
    for (int k = 0; k < 4; k++) {
        long double ax = cx[k], ay = cy[k], bx = cx[(k + 1) % 4], by = cy[(k + 1) % 4];
        cutpt cut[20];
        int n = 0;
        cut[n++] = (cutpt){ax, ay, 0};
        cut[n++] = (cutpt){bx, by, 1};
        for (int q = 0; q < nall; q++) {
            long double t = ax == bx ? (all[q].y - ay) / (by - ay) : (all[q].x - ax) / (bx - ax);
            int on = ax == bx ? all[q].x == ax : all[q].y == ay;
            if (on && t > 0 && t < 1)
                cut[n++] = (cutpt){all[q].x, all[q].y, t};
        }
        qsort(cut, (size_t)n, sizeof *cut, cmp_cut);
        for (int q = 0; q + 1 < n; q++) {
            const cutpt *a = &cut[q], *b = &cut[q + 1];
            long double mx = 0.5L * (a->x + b->x), my = 0.5L * (a->y + b->y);
            if (b->key > a->key && in_disk(c1, mx, my) && in_disk(c2, mx, my))
                sum += a->x * b->y - a->y * b->x;
        }
    }
    return sum;
}

/* The area of disk 1 n disk 2 n pixel (i, j); disks in pixel units. */
static double two_disks_pixel(const ellipse *d1, const ellipse *d2, int i, int j)
{
    long double ox = i + 0.5L, oy = j + 0.5L;
    circ c1 = {d1->cx - ox, d1->cy - oy, d1->ux}, c2 = {d2->cx - ox, d2->cy - oy, d2->ux};
    cutpt all[24];
    int n = circle_cuts(&c1, &c2, all);
    n += circle_cuts(&c2, &c1, all + n);
    long double twice = arcs_of(&c1, &c2, all, n) + arcs_of(&c2, &c1, all, n) +
                        sides_of(&c1, &c2, all, n);
    return (double)(0.5L * twice);
}

/* Two circles' lens: r1^2 acos(..) + r2^2 acos(..) - sqrt(..)/2. */
static double lens_area(double r1, double r2, double d)
{
    double a1 = acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1));
    double a2 = acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2));
    double k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    return r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * sqrt(k);
}

/* Two crossing disks: in two layers (a grey one in front), or in one
 * layer under each rule. */
typedef struct two {
    ellipse a, b;
    double wa, wb, wab; /* value = wa |A| + wb |B| + wab |A n B| */
} two;

static double two_pixel(const void *ctx, int i, int j)
{
    const two *T = ctx;
    const ellipse big = {i + 0.5, j + 0.5, 4.0, 0, 0, 4.0}; /* holds the pixel */
    double a = two_disks_pixel(&T->a, &big, i, j), b = two_disks_pixel(&T->b, &big, i, j);
    return T->wa * a + T->wb * b + T->wab * two_disks_pixel(&T->a, &T->b, i, j);
}

/* The Green's-theorem area against the disc-polygon closed form (one disk
 * inside a pixel-holding big one) and the lens formula (summed). */
static void test_two_disks_closed_form(void **state)
{
    (void)state;
    const ellipse d1 = {20.3, 21.7, 9.2, 0, 0, 9.2}, d2 = {27.1, 24.4, 6.3, 0, 0, 6.3};
    double worst = 0, lens = 0;
    for (int j = 0; j < 40; j++)
        for (int i = 0; i < 40; i++) {
            const ellipse big = {i + 0.5, j + 0.5, 4.0, 0, 0, 4.0};
            double g = two_disks_pixel(&d1, &big, i, j), c = ellipse_rect(&d1, i, j, i + 1, j + 1);
            worst = fmax(worst, fabs(g - c));
            lens += two_disks_pixel(&d1, &d2, i, j);
        }
    double d = hypot(d2.cx - d1.cx, d2.cy - d1.cy), want = lens_area(9.2, 6.3, d);
    printf("Green's theorem: one disk within %.2e of the disc-polygon form; lens %.15g, "
           "formula %.15g\n",
           worst, lens, want);
    assert_true(worst < 1e-14);
    assert_true(fabs(lens - want) < 1e-11);
}

static void test_two_disks(void **state)
{
    (void)state;
    const ellipse pa = {0.4 + 1.0 / 256, 0.45, 0.25, 0, 0, 0.25}, pb = {0.62, 0.55 - 1.0 / 512, 0.2, 0, 0, 0.2};
    const int sizes[2] = {64, 48}; /* square: the Green's-theorem form takes circles */
    for (int z = 0; z < 2; z++) {
        int w = sizes[z], h = sizes[z];
        for (int form = 0; form < 3; form++) {
            const double grey = 0.3;
            aa_scene *s = aa_scene_new(black);
            two T = {placed(&pa, w, h), placed(&pb, w, h), 1, 1, -1};
            if (form == 0) { /* a grey disk in front of a white one */
                assert_int_equal(aa_scene_layer(s, (aa_rgb){{grey, grey, grey}}, AA_FILL_NONZERO),
                                 AA_OK);
                add_ellipse(s, &pa);
                assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
                add_ellipse(s, &pb);
                T.wa = grey, T.wb = 1, T.wab = -1;
            } else {
                assert_int_equal(aa_scene_layer(s, white, form == 1 ? AA_FILL_NONZERO
                                                                    : AA_FILL_EVENODD),
                                 AA_OK);
                add_ellipse(s, &pa);
                add_ellipse(s, &pb);
                T.wab = form == 1 ? -1 : -2;
            }
            assert_int_equal(aa_scene_finish(s), AA_OK);
            double ra = T.a.ux, rb = T.b.ux, d = hypot(T.b.cx - T.a.cx, T.b.cy - T.a.cy);
            double total = T.wa * M_PI * ra * ra + T.wb * M_PI * rb * rb + T.wab * lens_area(ra, rb, d);
            const char *what[3] = {"two disks, layers", "two disks, nonzero", "two disks, even-odd"};
            check_pixels(what[form], s, w, h, two_pixel, &T, 1e-12, total, 1e-9);
            aa_scene_free(s);
        }
    }
}

/* A disk of radius 1500 px on a 4096 x 4096 image, rows rendered through
 * a view of a few rows: the scene placed in pixels and moved so that rows
 * near the disk's top, middle and bottom come to rows 0..7. */
static void test_large_disk(void **state)
{
    (void)state;
    const int w = 4096, h = 8;
    const double r = 1500.0, cx = 2048.3, rows[3] = {2048.0 - 1500.0 - 2.0, 2040.0, 2048 + 1500 - 6};
    for (int k = 0; k < 3; k++) {
        /* pattern units on a w x h image: x * w, y * h; the disk's centre
         * at (cx, 2048.7 - rows[k]) pixels */
        double cy = 2048.7 - rows[k];
        ellipse pe = {cx / w, cy / h, r / w, 0, 0, r / h};
        aa_scene *s = aa_scene_new(black);
        assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
        add_ellipse(s, &pe);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        shape sh = {.e = {placed(&pe, w, h)}, .n = 1, .ycut = -INFINITY};
        aa_image img;
        support_render("area", s, NULL, w, h, 2, &img, NULL);
        double worst = 0.0;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double v = aa_pixel(&img, i, j)[0], t = shape_pixel(&sh, i, j);
                if (!(fabs(v - t) <= 1e-11))
                    fail_msg("large disk, rows from %g: pixel (%d, %d) is %.17g, the closed "
                             "form %.17g",
                             rows[k], i, j, v, t);
                worst = fmax(worst, fabs(v - t));
            }
        printf("disk r=1500 px, 4096 wide, rows %-6g max |area - closed form| %.2e\n", rows[k],
               worst);
        aa_image_free(&img);
        aa_scene_free(s);
    }
}

/* ------------------------------------------------------------------------
 * Every sampling method on a disk
 * ------------------------------------------------------------------------ */

/* The filter a method takes: box, else Crow's tent, else the Gaussian (as
 * tests/test_methods.c); NULL if none. */
static const char *home_filter(const char *spec)
{
    const char *filters[] = {"box", "tent:r=1", "gauss"};
    for (int k = 0; k < 3; k++) {
        aa_filter f;
        aa_spec m;
        assert_int_equal(aa_filter_parse(filters[k], &f), AA_OK);
        if (aa_method_parse(spec, &f, &m) == AA_OK)
            return filters[k];
    }
    return NULL;
}

static void test_methods_on_disk(void **state)
{
    (void)state;
    const int w = 128, h = 128;
    const ellipse pe = {0.5 + 1.0 / 512, 0.5 - 1.0 / 256, 40.0 / 128, 0, 0, 40.0 / 128};
    const ellipse e = placed(&pe, w, h);
    const double r = e.ux, area = M_PI * r * r;
    aa_scene *s = aa_scene_new(black);
    assert_int_equal(aa_scene_layer(s, white, AA_FILL_NONZERO), AA_OK);
    add_ellipse(s, &pe);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    /* pixel centres inside the disk, counted */
    long inside = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double dx = i + 0.5 - e.cx, dy = j + 0.5 - e.cy;
            inside += dx * dx + dy * dy < r * r;
        }
    const void *const *table = aa_method_table();
    int tested = 0;
    for (size_t k = 0; table[k]; k++) {
        const aa_method_type *type = table[k];
        if (type->flags & (AA_METHOD_SOME_SCENES | AA_METHOD_EXTERNAL))
            continue;
        const char *name = type->info.name, *filter = home_filter(name);
        if (!filter)
            continue;
        const support_view v = {.w = w, .h = h, .filter = filter, .seed = 3, .threads = 2};
        aa_image img;
        int st = support_render_view(name, s, &v, &img, NULL);
        if (st)
            fail_msg("%s on a disk: %s", name, aa_last_error());
        double sum = 0.0;
        for (int p = 0; p < w * h; p++)
            sum += img.v[3 * p];
        double off = fabs(sum - area) / area;
        printf("%-14s %-9s mean %.6f, disk %.6f (%.2e relative)\n", name, filter, sum / (w * h),
               area / (w * h), off);
        if (!strcmp(name, "point") && sum != (double)inside)
            fail_msg("point on a disk: %.17g pixels white, %ld centres inside", sum, inside);
        if (!(off <= 0.02))
            fail_msg("%s on a disk: mean %.6f, the disk covers %.6f", name, sum / (w * h),
                     area / (w * h));
        aa_image_free(&img);
        tested++;
    }
    assert_true(tested >= 10);
    /* Crow's tiler with exact areas and his scanning hidden surfaces is the
     * exact tent prefilter (its conic parts by 8-point Gauss-Legendre in
     * the angle): the tent of radius 1 sums to one over the pixel centres,
     * so its image sums to the disk's area to rounding */
    const support_view v = {.w = w, .h = h, .filter = "tent:r=1", .seed = 3, .threads = 2};
    aa_image img;
    support_render_must("crowtiler:area=exact,hidden=scan", s, &v, &img, NULL);
    double sum = 0.0;
    for (int p = 0; p < w * h; p++)
        sum += img.v[3 * p];
    printf("crowtiler:area=exact,hidden=scan: the sum %.15g, the disk %.15g\n", sum, area);
    assert_true(fabs(sum - area) <= 1e-9 * area);
    aa_image_free(&img);
    aa_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_form),
        cmocka_unit_test(test_disk),
        cmocka_unit_test(test_rotated_ellipse),
        cmocka_unit_test(test_annulus),
        cmocka_unit_test(test_half_disk),
        cmocka_unit_test(test_random_ellipses),
        cmocka_unit_test(test_pie_slices),
        cmocka_unit_test(test_disk_behind_square),
        cmocka_unit_test(test_two_disks_closed_form),
        cmocka_unit_test(test_two_disks),
        cmocka_unit_test(test_large_disk),
        cmocka_unit_test(test_methods_on_disk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
