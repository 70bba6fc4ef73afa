/*
 * test_tables.c: the table-driven prefilters crowtable (Crow 1976) and
 * conetable (Feibush, Levoy and Cook 1980).
 *
 * Known answers are independent of the methods:
 *  - a half-plane: for a separable filter and an axis-aligned edge at u = e
 *    the exact value right of it is 1 - C(e - u_c), C the filter's 1-D
 *    integral (closed form: the tent's piecewise quadratic, the Gaussian's
 *    erfc); for the Gaussian, which is also circularly symmetric, the same
 *    holds for an edge at any angle with e - u_c the signed distance.
 *    The tabulated values must approach it within the error bound each
 *    method's header derives, which falls with the table resolution.
 *  - crow 128x128: the exact reference (aa_truth_render), every pixel within
 *    the derived bound, with the number of pieces near the pixel counted
 *    from the scene's own piece extents (not from the methods); conetable's
 *    cone weight on crow 64x64 against the exact cone reference (-f cone),
 *    and on a half-plane against the closed-form volume of a cut cone.
 *  - refusals through the CLI exit with status 2.
 */
#include "bench.h"
#include "oracle.h"
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

#define HW 24

/* Largest error against 1 - C(signed distance) over a HW x HW image of the
 * half-plane through (px, py) pixels at `angle`. */
static double half_plane_error(const char *method, const char *filter, double px, double py,
                               double angle)
{
    aa_filter f;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    aa_scene *s = scenes_half_plane(px / HW, py / HW, angle); /* white right of the line */
    aa_image img;
    support_render(method, s, filter, HW, HW, 2, &img, NULL);
    double nx = cos(angle), ny = -sin(angle), worst = 0.0;
    for (int j = 0; j < HW; j++)
        for (int i = 0; i < HW; i++) {
            double d = (i + 0.5 - px) * nx + (j + 0.5 - py) * ny; /* > 0: white side */
            /* separable: the 1-D cdf across the edge; the cone: its cut
             * volume (f.radius is its R) */
            double exact = aa_filter_is_separable(&f) ? 1.0 - aa_filter_cdf(&f, -d)
                                                       : 1.0 - oracle_cone_cut(d / f.radius);
            const double *v = aa_pixel(&img, i, j);
            for (int ch = 0; ch < 3; ch++) {
                if (!(v[ch] >= 0.0 && v[ch] <= 1.0))
                    fail_msg("%s: value %.17g outside [0, 1]", method, v[ch]);
                worst = fmax(worst, fabs(v[ch] - exact));
            }
        }
    aa_image_free(&img);
    aa_scene_free(s);
    return worst;
}

/* ---- crowtable ---- */

/* The header's per-piece bound: wx d / 2 (lookup) + 2 R w2 d (rows), with
 * d = 2R / ceil(2R res); `rows` 0 for an axis-aligned edge (its rows are
 * exact). */
static double crow_piece_bound(double wx, double R, int res, int rows)
{
    double d = 2.0 * R / ceil(2.0 * R * res);
    return wx * d / 2.0 + (rows ? 2.0 * R * wx * wx * d : 0.0);
}

static void test_crow_half_plane_converges(void **state)
{
    (void)state;
    const struct {
        const char *filter;
        double wx, R;
    } cases[] = {{"box", 1.0, 0.5},
                 {"tent:r=0.5", 2.0, 0.5},
                 {"tent:r=1", 1.0, 1.0},
                 {"gauss", 1.0 / (0.5 * sqrt(2.0 * M_PI)), 8 * 0.5}};
    const int res[] = {2, 8, 32, 128};
    for (int c = 0; c < 4; c++) {
        int gauss = c == 3;
        double first = 0, last = 0;
        for (int k = 0; k < 4; k++) {
            char spec[64];
            snprintf(spec, sizeof spec, "crowtable:res=%d%s", res[k], gauss ? ",cut=8" : "");
            /* an edge at 10.3 px, off every table grid used */
            double e = half_plane_error(spec, cases[c].filter, 10.3, 0.0, 0.0);
            double bound = crow_piece_bound(cases[c].wx, cases[c].R, res[k], 0) + 1e-12;
            print_message("crowtable %-10s res=%-3d half-plane max error %.3e (bound %.3e)\n",
                          cases[c].filter, res[k], e, bound);
            if (!(e <= bound))
                fail_msg("%s %s: error %.3e above the bound %.3e", spec, cases[c].filter, e,
                         bound);
            if (k == 0)
                first = e;
            last = e;
        }
        /* converges: 64 times the resolution, the error well down */
        assert_true(last < first / 8.0);
    }
    /* the Gaussian is radial: a slanted edge has the same closed form; its
     * rows add the second term of the bound */
    for (int k = 0; k < 4; k++) {
        char spec[64];
        snprintf(spec, sizeof spec, "crowtable:res=%d,cut=8", res[k]);
        double e = half_plane_error(spec, "gauss", 11.7, 12.0, 0.5);
        double wx = 1.0 / (0.5 * sqrt(2.0 * M_PI));
        double bound = crow_piece_bound(wx, 4.0, res[k], 1) + 1e-12;
        print_message("crowtable gauss slanted res=%-3d max error %.3e (bound %.3e)\n", res[k],
                      e, bound);
        assert_true(e <= bound);
    }
}

/* The pieces near the square of half-width R around (cx, cy), from the
 * scene's own piece geometry: *count gets how many have an extent meeting
 * it, and the return value bounds their total x variation inside it (a
 * y-monotone quadratic turns at most once in x, so at most twice its x
 * extent within the square's rows, clipped to the square). */
static double pieces_near(const aa_scene *placed, double cx, double cy, double R, int *count)
{
    size_t n;
    const aa_piece *p = aa_scene_pieces(placed, &n);
    double var = 0.0;
    *count = 0;
    for (size_t q = 0; q < n; q++) {
        if (!(p[q].xmax >= cx - R && p[q].xmin <= cx + R && p[q].y1 >= cy - R &&
              p[q].y0 <= cy + R))
            continue;
        ++*count;
        double a = p[q].xmin, b = p[q].xmax;
        if (p[q].kind != AA_PIECE_FLAT)
            aa_piece_xrange(&p[q], fmax(cy - R, p[q].y0), fmin(cy + R, p[q].y1), &a, &b);
        double ext = fmin(b, cx + R) - fmax(a, cx - R);
        var += ext > 0.0 ? (p[q].kind == AA_PIECE_QUAD ? 2.0 : 1.0) * ext : 0.0;
    }
    return var;
}

typedef double bound_fn(const aa_filter *f, const char *method, int n, int pieces,
                        double xvar);

/* The exact references of crow used so far, by filter and size: several
 * methods are checked against the same one (crow 128x128 under gauss by
 * crowtable and twice by conetable, crow 64x64 under cone twice), and the
 * reference is most of the cost; it does not depend on the method. */
static struct {
    const char *filter;
    int n;
    aa_image ref;
} crow_refs[8];

static const aa_image *crow_reference(const aa_scene *s, const char *filter, int n)
{
    size_t k = 0;
    for (; k < sizeof crow_refs / sizeof *crow_refs && crow_refs[k].filter; k++)
        if (crow_refs[k].n == n && !strcmp(crow_refs[k].filter, filter))
            return &crow_refs[k].ref;
    assert_true(k < sizeof crow_refs / sizeof *crow_refs);
    support_reference(s, &(support_view){.w = n, .h = n, .filter = filter}, &crow_refs[k].ref,
                      NULL, NULL);
    crow_refs[k].filter = filter, crow_refs[k].n = n;
    return &crow_refs[k].ref;
}

static int free_crow_refs(void **state)
{
    (void)state;
    for (size_t k = 0; k < sizeof crow_refs / sizeof *crow_refs && crow_refs[k].filter; k++)
        aa_image_free(&crow_refs[k].ref);
    return 0;
}

/* Every pixel of crow n x n within bound(pieces near it) of the exact
 * reference; prints RMSE and max. */
static void crow_within_n(const char *method, const char *filter, int n, double R,
                          bound_fn *bound)
{
    aa_scene *s = scenes_pattern("crow"), *placed = aa_scene_place(s, n, n, 0, 0, 0);
    aa_filter f;
    assert_non_null(placed);
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    aa_image img;
    const aa_image *ref = crow_reference(s, filter, n);
    support_render(method, s, filter, n, n, 2, &img, NULL);
    double sum = 0, worst = 0, worst_bound = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int k;
            double xvar = pieces_near(placed, i + 0.5, j + 0.5, R, &k);
            double b = bound(&f, method, n, k, xvar);
            for (int ch = 0; ch < 3; ch++) {
                double e = fabs(aa_pixel(&img, i, j)[ch] - aa_pixel(ref, i, j)[ch]);
                sum += e * e;
                worst = fmax(worst, e);
                worst_bound = fmax(worst_bound, b);
                if (!(e <= b))
                    fail_msg("%s %s: pixel (%d, %d) error %.3e above its bound %.3e", method,
                             filter, i, j, e, b);
            }
        }
    print_message("%s %-10s crow %dx%d: RMSE %.3e, max %.3e (largest bound %.3e)\n", method,
                  filter, n, n, sqrt(sum / ((double)n * n * 3)), worst, worst_bound);
    aa_image_free(&img);
    aa_scene_free(placed);
    aa_scene_free(s);
}

static void crow_within(const char *method, const char *filter, double R, bound_fn *bound)
{
    crow_within_n(method, filter, 128, R, bound);
}

/* crowtable's header bound at its defaults (res=16, cut=3): per piece
 * wx d / 2 for the lookups, and w2 (d / 2) times the pieces' x variation in
 * the square for the rows (the 2 R w2 d per piece of the header, with the
 * variation counted instead of bounded by 4R). */
static double crow_bound(const aa_filter *f, const char *method, int n, int pieces,
                         double xvar)
{
    (void)method, (void)n;
    double wx, R, trunc = 0.0;
    if (f->type == &aa_filter_gauss) {
        double s = f->spec.v[0], m = erf(3.0 / M_SQRT2);
        wx = 1.0 / (s * sqrt(2.0 * M_PI));
        R = 3.0 * s;
        trunc = 2.0 * (1.0 - m * m);
    } else {
        wx = aa_filter_weight(f, 0.0);
        R = f->radius;
    }
    double d = 2.0 * R / ceil(2.0 * R * 16);
    return pieces * crow_piece_bound(wx, R, 16, 0) + wx * wx * d / 2.0 * xvar + trunc + 1e-12;
}

static void test_crow_pattern_bound(void **state)
{
    (void)state;
    crow_within("crowtable", "tent:r=0.5", 0.5, crow_bound);
    crow_within("crowtable", "tent:r=1", 1.0, crow_bound);
    crow_within("crowtable", "gauss", 1.5, crow_bound);
}

/* ---- conetable ---- */

/* conetable's header bound on one chord end's interpolation error: the
 * variation of D over a table cell, at most (pi/2)/res * 1/(2 pi) along the
 * angle and c/(2 M sqrt(2 pi)) / res along the distance. */
static double cone_end_bound(double cut, int res)
{
    double M = -expm1(-0.5 * cut * cut);
    return (0.25 + cut / (2.0 * M * sqrt(2.0 * M_PI))) / res;
}

/* conetable (spec_fmt with its res) over half-planes at three angles: every
 * pixel within `bound` (two chord ends: one edge reaches the mask), and the
 * error falling by at least 8 from res 8 to res 256. */
static void table_half_planes(const char *spec_fmt, const char *filter,
                              double (*bound)(int res))
{
    const int res[] = {8, 32, 128, 256};
    const double angles[] = {0.0, 0.5, 1.2};
    for (int a = 0; a < 3; a++) {
        double first = 0, last = 0;
        for (int k = 0; k < 4; k++) {
            char spec[64];
            snprintf(spec, sizeof spec, spec_fmt, res[k]);
            double e = half_plane_error(spec, filter, 10.3, 12.2, angles[a]);
            double b = bound(res[k]);
            print_message("%s %s angle %.1f half-plane max error %.3e (bound %.3e)\n", spec,
                          filter, angles[a], e, b);
            if (!(e <= b))
                fail_msg("%s: error %.3e above the bound %.3e", spec, e, b);
            if (k == 0)
                first = e;
            last = e;
        }
        assert_true(last < first / 8.0);
    }
}

/* cut=8 leaves 1.3e-14 of the Gaussian outside the mask */
static double gauss_cut8_bound(int res)
{
    return 2.0 * cone_end_bound(8.0, res) + 3e-14;
}

static void test_cone_half_plane_converges(void **state)
{
    (void)state;
    /* the radial Gaussian over a half-plane: Phi(signed distance / s),
     * whatever the edge's angle */
    table_half_planes("conetable:cut=8,res=%d", "gauss", gauss_cut8_bound);
}

/* conetable's header bound at cut=C, res=N, tol=T (parsed from the method
 * spec): truncation 2 exp(-c^2/2), and per piece near the pixel two chord
 * ends per chord (n chords by the flattening rule) plus (2/3) tol L wmax
 * for the flattening, L bounded by the piece's y extent in the mask's rows
 * plus twice its x extent there. */
/* conetable's cut, res and tol as the method spec gives them, else its
 * defaults 2, 64 and 1e-3. */
static void conetable_options(const char *method, double *cut, int *res, double *tol)
{
    const char *q;
    *cut = (q = strstr(method, "cut=")) ? atof(q + 4) : 2.0;
    *res = (q = strstr(method, "res=")) ? atoi(q + 4) : 64;
    *tol = (q = strstr(method, "tol=")) ? atof(q + 4) : 1e-3;
}

static double cone_bound(const aa_filter *f, const char *method, int n, int pieces,
                         double xvar)
{
    double cut, tol;
    int res;
    conetable_options(method, &cut, &res, &tol);
    double s = f->spec.v[0], R = cut * s, M = -expm1(-0.5 * cut * cut);
    double wmax = 1.0 / (2.0 * M_PI * s * s * M);
    /* crow's arcs in the n px image: |a| <= n * (largest curvature term,
     * at most 1 pattern unit), the band 2R of n px in t */
    double dt = 2.0 * R / n, chords = ceil(sqrt(n * dt * dt / (4.0 * tol)));
    double trunc = 2.0 * exp(-0.5 * cut * cut);
    return trunc + pieces * (2.0 * chords * cone_end_bound(cut, res)) +
           (2.0 / 3.0) * tol * wmax * (pieces * 2.0 * R + xvar) + 1e-12;
}

static void test_cone_pattern_bound(void **state)
{
    (void)state;
    crow_within("conetable", "gauss", 2.0 * 0.5, cone_bound);
    crow_within("conetable:cut=4,res=256", "gauss", 4.0 * 0.5, cone_bound);
}

/* ---- conetable, weight=cone ---- */

/* The header's bound for the cone weight at res=N, tol=T: no truncation;
 * per chord end (1/4 + 3/(2 pi)) / res (|dD/dtheta| <= 1/(2 pi) over a
 * cell of pi/(2 res), |dD/du| <= 3/(2 pi) over 1/res); flattening
 * (2/3) tol L wmax with wmax = 3/(pi R^2); chords counted as for the
 * Gaussian. */
static double cone_end_bound_cone(int res)
{
    return (0.25 + 3.0 / (2.0 * M_PI)) / res;
}

static double cone_weight_bound(const aa_filter *f, const char *method, int n, int pieces,
                                double xvar)
{
    double cut, tol; /* cut: not for the cone weight (refused) */
    int res;
    conetable_options(method, &cut, &res, &tol);
    double R = f->spec.v[0], wmax = 3.0 / (M_PI * R * R);
    double dt = 2.0 * R / n, chords = ceil(sqrt(n * dt * dt / (4.0 * tol)));
    return pieces * (2.0 * chords * cone_end_bound_cone(res)) +
           (2.0 / 3.0) * tol * wmax * (pieces * 2.0 * R + xvar) + 1e-12;
}

static void test_cone_weight_crow(void **state)
{
    (void)state;
    crow_within_n("conetable:weight=cone", "cone", 64, 1.0, cone_weight_bound);
    crow_within_n("conetable", "cone:r=1.5", 64, 1.5, cone_weight_bound);
    crow_within_n("conetable:weight=cone,res=256", "cone", 64, 1.0, cone_weight_bound);
}

static double cone_table_bound(int res)
{
    return 2.0 * cone_end_bound_cone(res) + 3e-14;
}

/* A half-plane through the cone's table: the cut cone's volume. */
static void test_cone_weight_half_plane(void **state)
{
    (void)state;
    table_half_planes("conetable:weight=cone,res=%d", "cone:r=2", cone_table_bound);
}

/* ---- refusals ---- */

/* The library refuses the method under the filter (AA_EINVAL), with a
 * message holding `words`. */
static void refused(const char *method, const char *filter, const char *words)
{
    aa_filter f;
    aa_spec spec;
    int st = aa_filter_parse(filter, &f);
    if (st == AA_OK)
        st = aa_method_parse(method, &f, &spec);
    if (st != AA_EINVAL || !strstr(aa_last_error(), words))
        fail_msg("%s -f %s: status %d, \"%s\" (expected %d and \"%s\")", method, filter, st,
                 st ? aa_last_error() : "", AA_EINVAL, words);
}

/* The same through the command: exit 2, the message, nothing written. */
static void refused_cli(const char *method, const char *filter, const char *words)
{
    char out[4096];
    const char *args[] = {"render", "-p", "crow", "-s", "8x8", "-m", method, "-f", filter,
                          "-o", "/tmp/aabench-tables-never.pfm", NULL};
    int code = support_aabench(args, out, sizeof out);
    if (code != 2 || !strstr(out, words))
        fail_msg("%s -f %s: exit %d, \"%s\" (expected 2 and \"%s\")", method, filter, code, out,
                 words);
    assert_int_equal(access("/tmp/aabench-tables-never.pfm", F_OK), -1);
}

static void test_refusals(void **state)
{
    (void)state;
    /* the tables' own limits: method, filter, words the message must hold */
    static const char *const limits[][3] = {
        {"crowtable:cut=4", "tent", "truncates the Gaussian only"},
        {"crowtable:res=0", "box", "res"},
        {"conetable:weight=cone", "gauss", "use -f cone:r=R"},
        {"conetable:weight=gauss", "cone", "use -f gauss:s=S"},
        {"conetable:weight=cone,cut=3", "cone", "leave cut out"},
    };
    for (size_t k = 0; k < sizeof limits / sizeof *limits; k++)
        refused(limits[k][0], limits[k][1], limits[k][2]);
    /* conetable's circular mask: filters it cannot form or that are bad */
    static const char *const masks[][2] = {{"box", "circular mask"},
                                           {"tent:r=1", "circular mask"},
                                           {"radial", "the Gaussian and the cone"},
                                           {"cone:r=0", "out of range"},
                                           {"cone:r=nan", "not a number"}};
    for (size_t k = 0; k < sizeof masks / sizeof *masks; k++)
        refused("conetable", masks[k][0], masks[k][1]);
    /* methods that cannot form a filter that is not separable say what
     * they accept */
    static const char *const separable[][2] = {
        {"crowtable", "separable filter"}, {"area", "box"}, {"point", "box"}, {"trio", "box"}};
    for (size_t k = 0; k < sizeof separable / sizeof *separable; k++)
        refused(separable[k][0], "cone", separable[k][1]);
    refused_cli(limits[0][0], limits[0][1], limits[0][2]);
}

SUPPORT_MAIN(NULL, free_crow_refs,
             cmocka_unit_test(test_crow_half_plane_converges),
             cmocka_unit_test(test_crow_pattern_bound),
             cmocka_unit_test(test_cone_half_plane_converges),
             cmocka_unit_test(test_cone_pattern_bound),
             cmocka_unit_test(test_cone_weight_crow),
             cmocka_unit_test(test_cone_weight_half_plane),
             cmocka_unit_test(test_refusals))
