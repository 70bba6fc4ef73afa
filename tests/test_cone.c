/*
 * test_cone.c: the cone filter's exact reference (truth.c with
 * -f cone:r=R) against derivations that share nothing with it.
 *
 *  - Brute force in polar coordinates around each pixel centre:
 *        P = int_0^2pi dphi int_0^R (3 / (pi R^2)) (1 - r / R) r I dr,
 *    along each ray the scene is constant between the ray's crossings of
 *    the scene's edges, found here from the test's own description of the
 *    scene (crow's arcs x = a_k + c_k (y - 1/2)^2 from patterns/README.md, or a
 *    test-only polygon), the colour of each span from the test's own point
 *    query (tests/oracle.c for crow, a crossing count for the polygon), and
 *    the radial integral of (1 - r/R) r over a span in closed form; the
 *    angle by GSL's adaptive Gauss-Kronrod (QAG, 61 points) between the
 *    angles where the ray integral is not smooth (rays through a vertex or
 *    an arc's end, tangent to an arc, or through an edge's crossing of the
 *    circle r = R), whose error estimate is the tolerance (plus the
 *    reference's own bound).  Without the circle's crossings QAG's
 *    estimate was seen 17 times too small (8e-15 for an error of 1.4e-13
 *    against the half-plane closed form below).  Measured: agreement to
 *    1e-14 or better on every pixel.  The
 *    reference integrates along rows in Cartesian coordinates with the
 *    closed-form row integral instead: the two meet only in the scene.
 *    Crow at 16x16 and 7x3 (many arcs a pixel), a polygon at 13x11.
 *  - Closed forms: a uniform region is exact (filled pixels bit for bit,
 *    integrated pixels whose disc no edge enters to 1e-14); a half-plane
 *    whose edge passes through the pixel centre gives 1/2 (the cone is
 *    symmetric); a half-plane at distance d = delta R from the centre
 *    covers, of the cone's volume,
 *
 *      V(delta) = (1/pi) [acos delta - 2 delta sqrt(1 - delta^2)
 *                         + delta^3 ln((1 + sqrt(1 - delta^2)) / delta)],
 *
 *    derived in polar coordinates: the part beyond the line is, for each
 *    angle phi from the normal within acos delta, the radii from
 *    delta sec phi to 1, so V = (6/pi) int_0^acos(delta) f(delta sec phi)
 *    dphi with f(a) = int_a^1 (1 - rho) rho drho = 1/6 - a^2/2 + a^3/3,
 *    and int sec^2 = tan, int sec^3 = (sec tan + ln(sec + tan)) / 2 at
 *    sec = 1/delta, tan = sqrt(1 - delta^2)/delta.  V(0) = 1/2, V(1) = 0.
 *    The formula is checked here against 20-point Gauss-Legendre on 64
 *    panels of that phi integral, then every pixel of 24x24 images of
 *    slanted half-planes (r = 1, 2.5) against it to 1e-12.
 *  - Every pixel's bound at most 1e-12; 1 and 2 threads bit-identical.
 *  - The samplers weigh by the cone's 2-D weight: supersample n=3 puts
 *    samples at offsets 0 and +-2/3 px, of weights (in units of the peak)
 *    1, 1/3 at the sides and c = 1 - 2 sqrt(2)/3 at the corners, so an
 *    edge between the middle and right columns gives exactly
 *    (1/3 + 2c) / (7/3 + 4c) = 0.17475 (a separable tent would give 1/5);
 *    jitter with many samples approaches the half-plane's closed form, and
 *    with one sample stays finite where the sample misses the disc.
 */
#include "bench.h"
#include "oracle.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

/* ---- the scenes, described a second time ---- */

#define MAX_ARCS 128
#define MAX_VERTS 16

/* A scene as the brute force sees it, in pattern units. */
typedef struct brute_scene {
    int crow; /* 1: crow with oracle's parameters; 0: the polygon */
    oracle_crow cp;
    int narcs;
    double a[MAX_ARCS], c[MAX_ARCS]; /* crow arcs: x = a + c (y - 1/2)^2 */
    int nv;
    double px[MAX_VERTS], py[MAX_VERTS]; /* polygon */
    aa_rgb fill, background;
    int W, H;
} brute_scene;

/* patterns/README.md, `crow`: g_k, S, a_0, a_{k+1} = a_k + g_k, c_k. */
static void crow_arcs(brute_scene *b)
{
    int N = b->cp.curves;
    double S = 0.0, g[MAX_ARCS];
    for (int k = 0; k <= N - 2; k++) {
        g[k] = N == 2 ? b->cp.gap0 : b->cp.gap0 + (b->cp.gap1 - b->cp.gap0) * k / (N - 2);
        S += g[k];
    }
    b->a[0] = (1.0 - S) / 2.0;
    for (int k = 0; k < N - 1; k++)
        b->a[k + 1] = b->a[k] + g[k];
    for (int k = 0; k < N; k++)
        b->c[k] = b->cp.kmax * (1.0 - (double)k / (N - 1));
    b->narcs = N;
}

/* The colour at (x, y), pattern units. */
static aa_rgb brute_colour(const brute_scene *b, double x, double y)
{
    if (b->crow) {
        int white = oracle_crow_point(&b->cp, x, y);
        return white ? b->fill : b->background;
    }
    int inside = 0;
    for (int k = 0, m = b->nv - 1; k < b->nv; m = k++)
        if ((b->py[k] > y) != (b->py[m] > y) &&
            x < b->px[k] + (y - b->py[k]) * (b->px[m] - b->px[k]) / (b->py[m] - b->py[k]))
            inside = !inside;
    return inside ? b->fill : b->background;
}

typedef struct ray_ctx {
    const brute_scene *b;
    double uc, vc, R; /* pixel units */
    int channel;
    double *cut;      /* scratch for the ray's crossings */
} ray_ctx;

static int cmp_double(const void *p, const void *q)
{
    double x = *(const double *)p, y = *(const double *)q;
    return x < y ? -1 : (x > y);
}

/* Roots in (0, R) of A r^2 + B r + C = 0 appended to cut. */
static int quad_roots(double A, double B, double C, double R, double *cut, int n)
{
    double r[2];
    int m = 0;
    if (A == 0.0) {
        if (B != 0.0)
            r[m++] = -C / B;
    } else {
        double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            if (q != 0.0)
                r[m++] = q / A, r[m++] = C / q;
            else
                r[m++] = 0.0;
        }
    }
    for (int k = 0; k < m; k++)
        if (r[k] > 0.0 && r[k] < R)
            cut[n++] = r[k];
    return n;
}

/* int over the ray at angle phi of w(r) r I dr, w = 3/(pi R^2)(1 - r/R). */
static double ray(double phi, void *params)
{
    const ray_ctx *c = params;
    const brute_scene *b = c->b;
    double cx = cos(phi), sy = sin(phi), R = c->R;
    double X = c->uc / b->W, Y = c->vc / b->H, dx = cx / b->W, dy = sy / b->H;
    int n = 0;
    /* the unit square's sides (the pattern stops there) */
    n = quad_roots(0.0, dx, X, R, c->cut, n);
    n = quad_roots(0.0, dx, X - 1.0, R, c->cut, n);
    n = quad_roots(0.0, dy, Y, R, c->cut, n);
    n = quad_roots(0.0, dy, Y - 1.0, R, c->cut, n);
    if (b->crow) {
        /* a + c (Y + r dy - 1/2)^2 = X + r dx */
        double t = Y - 0.5;
        for (int k = 0; k < b->narcs; k++)
            n = quad_roots(b->c[k] * dy * dy, 2.0 * b->c[k] * t * dy - dx,
                           b->c[k] * t * t + b->a[k] - X, R, c->cut, n);
    } else {
        for (int k = 0, m = b->nv - 1; k < b->nv; m = k++) {
            /* (X, Y) + r (dx, dy) = P_m + s (P_k - P_m), 0 <= s <= 1 */
            double ex = b->px[k] - b->px[m], ey = b->py[k] - b->py[m];
            double den = dx * ey - dy * ex;
            if (den == 0.0)
                continue;
            double qx = b->px[m] - X, qy = b->py[m] - Y;
            double r = (qx * ey - qy * ex) / den, s = (qx * dy - qy * dx) / den;
            if (s >= 0.0 && s <= 1.0 && r > 0.0 && r < R)
                c->cut[n++] = r;
        }
    }
    qsort(c->cut, (size_t)n, sizeof *c->cut, cmp_double);
    double sum = 0.0, a = 0.0;
    for (int k = 0; k <= n; k++) {
        double e = k < n ? c->cut[k] : R;
        if (!(e > a))
            continue;
        double m = 0.5 * (a + e);
        double col = brute_colour(b, X + m * dx, Y + m * dy).c[c->channel];
        /* int_a^e (r - r^2 / R) dr */
        sum += col * ((e - a) * (0.5 * (a + e) - (a * a + a * e + e * e) / (3.0 * R)));
        a = e;
    }
    return 3.0 / (M_PI * R * R) * sum;
}

/* Angle of (x, y) pixel units from the centre, in [0, 2 pi), recorded if
 * the point lies within R. */
static int add_angle(double x, double y, double R, double *phi, int n)
{
    if (!(hypot(x, y) < R))
        return n;
    double a = atan2(y, x);
    phi[n++] = a < 0.0 ? a + 2.0 * M_PI : a;
    return n;
}

/* The angles at which the ray integral is not smooth (panel ends for the
 * quadrature): rays through a polygon's vertices or an arc's ends, and
 * rays tangent to an arc (there the crossings move like a square root).
 * For the arc X = A + C (Y - Y0)^2 (pixel units) the tangent from the
 * centre touches at Y - Y0 = s with C s^2 - 2 C e s - (A - Xc) = 0,
 * e = Yc - Y0 (the chord to the point is parallel to (2 C s, 1)). */
static int kink_angles(const brute_scene *b, double uc, double vc, double R, double *phi)
{
    int n = 0;
    if (!b->crow) {
        for (int k = 0, m = b->nv - 1; k < b->nv; m = k++) {
            double x0 = b->px[m] * b->W - uc, y0 = b->py[m] * b->H - vc;
            double ex = b->px[k] * b->W - uc - x0, ey = b->py[k] * b->H - vc - y0;
            n = add_angle(x0, y0, R, phi, n);
            /* where the edge crosses the circle r = R: the span's end
             * leaves the disc, a jump in the second derivative */
            double A = ex * ex + ey * ey, B = 2.0 * (x0 * ex + y0 * ey);
            double disc = B * B - 4.0 * A * (x0 * x0 + y0 * y0 - R * R);
            for (int sg = -1; sg <= 1 && disc >= 0.0; sg += 2) {
                double t = (-B + sg * sqrt(disc)) / (2.0 * A);
                if (t >= 0.0 && t <= 1.0)
                    n = add_angle(x0 + t * ex, y0 + t * ey, 2.0 * R, phi, n);
            }
        }
        return n;
    }
    double Y0 = 0.5 * b->H, e = vc - Y0;
    for (int k = 0; k < b->narcs; k++) {
        double A = b->a[k] * b->W, C = b->c[k] * b->W / ((double)b->H * b->H);
        n = add_angle(A + C * Y0 * Y0 - uc, -vc, R, phi, n);          /* ends, Y = 0 */
        n = add_angle(A + C * Y0 * Y0 - uc, b->H - vc, R, phi, n);    /*       Y = H */
        if (C == 0.0)
            continue;
        /* where the arc crosses the circle r = R: sign changes of
         * g(Y) = |(X(Y), Y) - centre|^2 - R^2 on 512 steps of the disc's
         * rows, then bisection (a crossing pair closer than a step is a
         * near tangency, whose angle is added below) */
        double ylo = fmax(vc - R, 0.0), yhi = fmin(vc + R, (double)b->H), gp = 0.0, yp = ylo;
        for (int q = 0; q <= 512 && ylo < yhi; q++) {
            double y = ylo + (yhi - ylo) * q / 512, x = A + C * (y - Y0) * (y - Y0);
            double g = (x - uc) * (x - uc) + (y - vc) * (y - vc) - R * R;
            if (q > 0 && (g < 0.0) != (gp < 0.0)) {
                double lo = yp, hi = y, glo = gp;
                for (int it = 0; it < 60; it++) {
                    double mid = 0.5 * (lo + hi), xm = A + C * (mid - Y0) * (mid - Y0);
                    double gm = (xm - uc) * (xm - uc) + (mid - vc) * (mid - vc) - R * R;
                    if ((gm < 0.0) == (glo < 0.0))
                        lo = mid, glo = gm;
                    else
                        hi = mid;
                }
                double ym = 0.5 * (lo + hi), xm = A + C * (ym - Y0) * (ym - Y0);
                n = add_angle(xm - uc, ym - vc, 2.0 * R, phi, n);
            }
            gp = g, yp = y;
        }
        double disc = e * e + (A - uc) / C;
        for (int sg = -1; sg <= 1 && disc >= 0.0; sg += 2) {
            double s = e + sg * sqrt(disc);
            if (s >= -Y0 && s <= Y0)
                n = add_angle(A + C * s * s - uc, s + Y0 - vc, R, phi, n);
        }
    }
    return n;
}

/* The brute-force value of pixel (i, j), one channel, and its error
 * estimate (QAG's, summed over the panels between kink angles). */
static double brute_pixel(const brute_scene *b, double R, int i, int j, int ch,
                          gsl_integration_workspace *ws, double *err)
{
    double cut[MAX_ARCS * 2 + 8], phi[MAX_ARCS * 12 + 4 * MAX_VERTS + 2];
    ray_ctx c = {b, i + 0.5, j + 0.5, R, ch, cut};
    gsl_function F = {ray, &c};
    int n = kink_angles(b, c.uc, c.vc, R, phi + 1);
    qsort(phi + 1, (size_t)n, sizeof *phi, cmp_double);
    phi[0] = 0.0;
    phi[n + 1] = 2.0 * M_PI;
    double sum = 0.0;
    *err = 0.0;
    for (int k = 0; k <= n; k++) {
        double res, e;
        if (!(phi[k + 1] > phi[k]))
            continue;
        int st = gsl_integration_qag(&F, phi[k], phi[k + 1], 1e-14, 0.0, 20000,
                                     GSL_INTEG_GAUSS61, ws, &res, &e);
        if (st != GSL_SUCCESS)
            e = fmax(e, 1e-9); /* not converged: its estimate stands, loosened */
        sum += res;
        *err += e;
    }
    return sum;
}

/* The reference of the scene (built by the caller) against the brute
 * force, every pixel and channel. */
static void against_brute(const char *what, const aa_scene *s, const brute_scene *b,
                          const char *filter)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    aa_image ref, bound;
    aa_truth_stats st;
    support_reference(s, &(support_view){.w = b->W, .h = b->H, .filter = filter}, &ref, &bound,
                      &st);
    assert_true(st.max_bound <= AA_TRUTH_BOUND);
    gsl_set_error_handler_off();
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(20000);
    assert_non_null(ws);
    double worst = 0.0, worst_est = 0.0, R = f.spec.v[0];
    for (int j = 0; j < b->H; j++)
        for (int i = 0; i < b->W; i++) {
            double want = 0.0, err = 0.0;
            for (int ch = 0; ch < 3; ch++) {
                if (ch == 0 || !b->crow) /* crow is grey: one channel serves */
                    want = brute_pixel(b, R, i, j, ch, ws, &err);
                double got = aa_pixel(&ref, i, j)[ch], d = fabs(got - want);
                double tol = err + *aa_pixel(&bound, i, j) + 1e-14;
                worst = fmax(worst, d);
                worst_est = fmax(worst_est, err);
                if (!(d <= tol))
                    fail_msg("%s %s pixel (%d, %d) channel %d: reference %.17g, polar %.17g "
                             "(estimate %.2e)",
                             what, filter, i, j, ch, got, want, err);
            }
        }
    print_message("%s %s %dx%d: max |reference - polar| %.2e (largest polar estimate %.2e, "
                  "reference bound %.2e)\n",
                  what, filter, b->W, b->H, worst, worst_est, st.max_bound);
    gsl_integration_workspace_free(ws);
    aa_image_free(&ref);
    aa_image_free(&bound);
}

static void crow_case(const char *pattern, oracle_crow cp, int W, int H, const char *filter)
{
    aa_scene *s = scenes_pattern(pattern);
    brute_scene b;
    memset(&b, 0, sizeof b);
    b.crow = 1;
    b.cp = cp;
    crow_arcs(&b);
    b.fill = (aa_rgb){{1, 1, 1}};
    b.background = (aa_rgb){{0, 0, 0}};
    b.W = W, b.H = H;
    against_brute(pattern, s, &b, filter);
    aa_scene_free(s);
}

static void test_crow_polar(void **state)
{
    (void)state;
    oracle_crow d = oracle_crow_defaults();
    SAN_CASES_PRINT();
    /* the sanitizer build's subset (SAN_SUBSET): crow under the cone at
     * 7x3 only, not at 16x16 too */
    if (!SAN_SUBSET)
        crow_case("crow", d, 16, 16, "cone");
    crow_case("crow", d, 7, 3, "cone");
    crow_case("crow", d, 7, 3, "cone:r=2.5");
    oracle_crow o = {24, 0.1, 0.03, 0.004};
    crow_case("crow:curves=24,kmax=0.1,gap0=0.03,gap1=0.004", o, 19, 13, "cone:r=0.7");
}

/* A concave hexagon in colour over a coloured background, vertices inside
 * pixels, not symmetric. */
static void test_polygon_polar(void **state)
{
    (void)state;
    brute_scene b;
    memset(&b, 0, sizeof b);
    const double x[] = {0.12, 0.83, 0.71, 0.47, 0.52, 0.2};
    const double y[] = {0.17, 0.08, 0.91, 0.55, 0.87, 0.74};
    b.nv = 6;
    memcpy(b.px, x, sizeof x);
    memcpy(b.py, y, sizeof y);
    b.fill = (aa_rgb){{0.9, 0.3, 0.6}};
    b.background = (aa_rgb){{0.1, 0.2, 0.05}};
    b.W = 13, b.H = 11;
    aa_scene *s = aa_scene_new(b.background);
    assert_int_equal(aa_scene_layer(s, b.fill, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x[0], y[0]), AA_OK);
    for (int k = 1; k < 6; k++)
        assert_int_equal(aa_scene_line_to(s, x[k], y[k]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    against_brute("polygon", s, &b, "cone");
    against_brute("polygon", s, &b, "cone:r=1.7");
    aa_scene_free(s);
}

/* ---- closed forms ---- */

/* The same fraction as (6/pi) int_0^acos(delta) f(delta sec phi) dphi by
 * 20-point Gauss-Legendre on 64 panels (f is a polynomial in sec phi,
 * smooth on the interval). */
static double cone_cut_quadrature(double delta)
{
    gsl_integration_glfixed_table *t = gsl_integration_glfixed_table_alloc(20);
    assert_non_null(t);
    double top = acos(delta), sum = 0.0;
    for (int p = 0; p < 64; p++) {
        double a = top * p / 64, b = top * (p + 1) / 64;
        for (size_t k = 0; k < 20; k++) {
            double xi, wi;
            gsl_integration_glfixed_point(a, b, k, &xi, &wi, t);
            double q = delta / cos(xi);
            sum += wi * (1.0 / 6.0 - q * q / 2.0 + q * q * q / 3.0);
        }
    }
    gsl_integration_glfixed_table_free(t);
    return 6.0 / M_PI * sum;
}

#define HW 24

static void half_plane_case(const char *filter, double px, double py, double angle)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    double R = f.spec.v[0];
    aa_scene *s = scenes_half_plane(px / HW, py / HW, angle); /* white right of the line */
    aa_image img;
    aa_truth_stats st;
    support_reference(s, &(support_view){.w = HW, .h = HW, .filter = filter, .threads = 2}, &img,
                      NULL, &st);
    assert_true(st.max_bound <= AA_TRUTH_BOUND);
    double nx = cos(angle), ny = -sin(angle), worst = 0.0;
    for (int j = 0; j < HW; j++)
        for (int i = 0; i < HW; i++) {
            double d = (i + 0.5 - px) * nx + (j + 0.5 - py) * ny; /* > 0: white side */
            double want = 1.0 - oracle_cone_cut(d / R);
            for (int ch = 0; ch < 3; ch++) {
                double got = aa_pixel(&img, i, j)[ch], e = fabs(got - want);
                worst = fmax(worst, e);
                if (!(e <= 1e-12))
                    fail_msg("%s half-plane angle %g: pixel (%d, %d) at distance %.6f: %.17g, "
                             "closed form %.17g",
                             filter, angle, i, j, d, got, want);
                /* no edge in the disc: uniform, to rounding */
                if (fabs(d) > R && !(e <= 1e-14))
                    fail_msg("%s: pixel (%d, %d) outside the edge's reach is %.17g", filter, i,
                             j, got);
            }
        }
    print_message("%s half-plane angle %.2f: max error against the closed form %.2e\n", filter,
                  angle, worst);
    aa_image_free(&img);
    aa_scene_free(s);
}

static void test_half_plane_closed_form(void **state)
{
    (void)state;
    assert_true(oracle_cone_cut(0.0) == 0.5 && oracle_cone_cut(1.0) == 0.0);
    for (double delta = 0.01; delta < 1.0; delta += 0.07) {
        double a = oracle_cone_cut(delta), b = cone_cut_quadrature(delta);
        if (fabs(a - b) > 1e-15)
            fail_msg("V(%g): closed form %.17g, quadrature %.17g", delta, a, b);
    }
    const double angles[] = {0.0, 0.5, 1.2, M_PI / 4, 2.0};
    for (int k = 0; k < 5; k++) {
        half_plane_case("cone", 10.3, 12.2, angles[k]);
        half_plane_case("cone:r=2.5", 11.7, 9.6, angles[k]);
    }
    half_plane_case("cone:r=0.3", 11.0, 12.0, 0.0); /* edges on pixel boundaries */
}

/* An edge through the pixel centre halves the cone's volume: exactly 1/2
 * (to the reference's rounding). */
static void test_edge_through_centre(void **state)
{
    (void)state;
    const double angles[] = {0.0, 0.3, 1.1, M_PI / 4, M_PI / 2, 2.6};
    const char *filters[] = {"cone", "cone:r=0.6", "cone:r=3"};
    for (int q = 0; q < 3; q++)
        for (int k = 0; k < 6; k++) {
            aa_scene *s = scenes_half_plane(12.5 / HW, 7.5 / HW, angles[k]);
            aa_image img;
            const support_view view = {.w = HW, .h = HW, .filter = filters[q], .threads = 1};
            support_reference(s, &view, &img, NULL, NULL);
            double v = aa_pixel(&img, 12, 7)[1];
            if (!(fabs(v - 0.5) <= 1e-13))
                fail_msg("%s edge through the centre at angle %g: %.17g", filters[q],
                         angles[k], v);
            aa_image_free(&img);
            aa_scene_free(s);
        }
}

/* A uniform scene: every pixel filled with its colour, bit for bit; a
 * diamond's corner pixels whose square the edges enter but whose disc
 * they miss are integrated and exact to rounding. */
static void test_uniform(void **state)
{
    (void)state;
    const aa_rgb c = {{0.25, 0.5, 0.75}};
    aa_scene *s = aa_scene_new(c);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    aa_image img;
    aa_truth_stats st;
    support_reference(s, &(support_view){.w = 9, .h = 7, .filter = "cone:r=1.5"}, &img, NULL,
                      &st);
    assert_true(st.integrated == 0 && st.filled == 63);
    for (int j = 0; j < 7; j++)
        for (int i = 0; i < 9; i++)
            for (int ch = 0; ch < 3; ch++)
                assert_true(aa_pixel(&img, i, j)[ch] == c.c[ch]);
    aa_image_free(&img);
    aa_scene_free(s);
    /* the line x + y = 20.5 px (45 degrees) on 24x24: pixel (9, 9) has its
     * centre at distance 1.5 / sqrt 2 = 1.06 > r = 1 of it, but the line
     * enters its square [8.5, 10.5]^2 */
    const double xy[] = {20.5 / HW, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 20.5 / HW};
    s = scenes_polygon(xy, 5, c, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO);
    support_reference(s, &(support_view){.w = HW, .h = HW, .filter = "cone"}, &img, NULL, &st);
    const int inside[][2] = {{9, 9}, {11, 11}, {2, 16}};
    for (int k = 0; k < 3; k++) {
        int i = inside[k][0], j = inside[k][1];
        double side = i + j + 1.0 - 20.5; /* < 0: black side */
        for (int ch = 0; ch < 3; ch++) {
            double want = side < 0 ? 0.0 : c.c[ch], got = aa_pixel(&img, i, j)[ch];
            if (!(fabs(got - want) <= 1e-14))
                fail_msg("pixel (%d, %d): %.17g, expected %g", i, j, got, want);
        }
    }
    aa_image_free(&img);
    aa_scene_free(s);
}

/* The image does not depend on the thread count; the cache key names the
 * cone and its radius. */
static void test_threads_and_key(void **state)
{
    (void)state;
    aa_spec spec;
    aa_filter f;
    assert_int_equal(aa_pattern_parse("crow", &spec), AA_OK);
    assert_int_equal(aa_filter_parse("cone:r=1.25", &f), AA_OK);
    aa_image a, b;
    support_view v = {.w = 33, .h = 21, .filter = "cone:r=1.25", .threads = 1};
    support_pattern_reference("crow", &v, &a, NULL, NULL);
    v.threads = 2;
    support_pattern_reference("crow", &v, &b, NULL, NULL);
    assert_memory_equal(a.v, b.v, sizeof(double) * 33 * 21 * 3);
    aa_view view = {spec, 33, 21, f, 0.0, 0.0, 0.0};
    char key[2048];
    assert_int_equal(aa_view_key(&view, key, sizeof key), AA_OK);
    assert_non_null(strstr(key, "filter cone:r=1.25"));
    aa_image_free(&a);
    aa_image_free(&b);
}

static void render_method(const char *method, const char *filter, const aa_scene *s, int w,
                          int h, aa_image *img)
{
    const support_view v = {.w = w, .h = h, .filter = filter, .seed = 7, .threads = 2};
    support_render_must(method, s, &v, img, NULL);
}

static void test_samplers(void **state)
{
    (void)state;
    /* the edge at x = 12.5 + 0.5 px: pixel 12's right column of samples */
    aa_scene *s = scenes_half_plane(13.0 / HW, 0.5, 0.0);
    aa_image img;
    render_method("supersample", "cone", s, HW, HW, &img);
    double c = 1.0 - 2.0 * sqrt(2.0) / 3.0, want = (1.0 / 3.0 + 2.0 * c) / (7.0 / 3.0 + 4.0 * c);
    for (int ch = 0; ch < 3; ch++)
        if (!(fabs(aa_pixel(&img, 12, 10)[ch] - want) <= 1e-15))
            fail_msg("supersample -f cone: %.17g, expected %.17g", aa_pixel(&img, 12, 10)[ch],
                     want);
    aa_image_free(&img);
    aa_scene_free(s);
    /* jitter, 4096 samples a pixel, against the closed form of a slanted
     * half-plane (the estimator's spread is about 0.5 / sqrt(4096 pi / 4)) */
    s = scenes_half_plane(10.3 / HW, 12.2 / HW, 0.5);
    render_method("jitter:spp=4096", "cone", s, HW, HW, &img);
    double worst = 0.0, nx = cos(0.5), ny = -sin(0.5);
    for (int j = 0; j < HW; j++)
        for (int i = 0; i < HW; i++) {
            double d = (i + 0.5 - 10.3) * nx + (j + 0.5 - 12.2) * ny;
            worst = fmax(worst, fabs(aa_pixel(&img, i, j)[0] - (1.0 - oracle_cone_cut(d))));
        }
    print_message("jitter:spp=4096 -f cone half-plane: max error %.2e\n", worst);
    assert_true(worst < 0.03);
    aa_image_free(&img);
    /* one sample, often outside the disc: values stay in [0, 1] */
    render_method("jitter:spp=1,seq=random", "cone", s, HW, HW, &img);
    for (size_t k = 0; k < (size_t)HW * HW * 3; k++)
        assert_true(img.v[k] >= 0.0 && img.v[k] <= 1.0);
    aa_image_free(&img);
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_half_plane_closed_form),
             cmocka_unit_test(test_edge_through_centre),
             cmocka_unit_test(test_uniform),
             cmocka_unit_test(test_threads_and_key),
             cmocka_unit_test(test_samplers),
             cmocka_unit_test(test_polygon_polar),
             cmocka_unit_test(test_crow_polar))
