/*
 * test_patterns.c: the seed scenes of patterns/README.md against answers derived
 * independently of the scene model and the reference:
 *
 *  - catmull: the 1x1 box value (0, 0.25, 0.5), Catmull's own statement
 *    (Catmull 1978, fig. 1), from the reference and from `area`; no red
 *    anywhere when tiled (the red layer is wholly hidden);
 *  - star: the total white area S R^2 sin(pi/S)/2 (a wedge is an isosceles
 *    triangle with legs R and apex angle pi/S);
 *  - star: every pixel's box value by clipping each wedge to the pixel
 *    (Sutherland-Hodgman and the shoelace formula, tests/oracle.c), and
 *    sqrt(2) R^2 for the
 *    four quadrant pixels of a 4-spoke star;
 *  - fence: every pixel's box value in closed form, the covered length of
 *    the pixel's column range (whole periods plus a clipped remainder)
 *    times its row's overlap with [1/4, 3/4]; the total duty (1/2)^2 when
 *    whole periods fit, its closed form otherwise;
 *  - feibush: the area of each colour from its own homography, found here
 *    by solving the 8x8 linear system of the four corner correspondences
 *    with GSL (not Heckbert's closed form the pattern uses), integrating
 *    the Jacobian determinant det(M)/w^3 over each stripe's texture
 *    rectangle by nested GSL quadrature;
 *  - dots: the total area n^2 size^2;
 *  - slivers: the total area, triangle k having base h_k and height 0.9;
 *  - every pattern: the reference is within [0, 1] with its error bound
 *    within AA_TRUTH_BOUND; bad parameters are refused.
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
#include <gsl/gsl_integration.h>
#include <gsl/gsl_linalg.h>

/* The reference of a pattern spec at w x h under filter text, on one
 * thread: it does not depend on the threads (test_truth.c checks that),
 * and on two one thread spun, using CPU for nothing, while the other
 * finished the last rows of costly pixels. */
static void reference(const char *pattern, int w, int h, const char *filter, aa_image *img,
                      double *max_bound)
{
    aa_truth_stats st;
    support_pattern_reference(pattern,
                              &(support_view){.w = w, .h = h, .filter = filter, .threads = 1},
                              img, NULL, &st);
    if (max_bound)
        *max_bound = st.max_bound;
}

/* The pattern's integral (channel 0 of its box reference at w x h) within
 * 1e-12 relative of want; returns the reference's largest bound. */
static double check_integral(const char *spec, int w, int h, double want)
{
    aa_image img;
    double bound;
    reference(spec, w, h, "box", &img, &bound);
    double got = support_channel_mean(&img, 0);
    aa_image_free(&img);
    if (!(fabs(got - want) <= 1e-12 * want))
        fail_msg("%s: %.17g want %.17g (rel %.3g)", spec, got, want, (got - want) / want);
    return bound;
}

static void test_catmull_pixel(void **state)
{
    (void)state;
    aa_image img;
    reference("catmull", 1, 1, "box", &img, NULL);
    assert_true(fabs(img.v[0]) <= 1e-12);
    assert_true(fabs(img.v[1] - 0.25) <= 1e-12);
    assert_true(fabs(img.v[2] - 0.5) <= 1e-12);
    aa_image_free(&img);

    /* the exact method gives the same pixel */
    aa_scene *s = scenes_pattern("catmull");
    support_render("area", s, NULL, 1, 1, 1, &img, NULL);
    assert_true(fabs(img.v[0]) <= 1e-12);
    assert_true(fabs(img.v[1] - 0.25) <= 1e-12);
    assert_true(fabs(img.v[2] - 0.5) <= 1e-12);
    aa_image_free(&img);
    aa_scene_free(s);
}

static void test_catmull_hidden(void **state)
{
    (void)state;
    aa_image img;
    reference("catmull:tiles=3", 64, 64, "box", &img, NULL);
    /* per tile: green 1/4, blue 1/2, red 0 */
    assert_true(fabs(support_channel_mean(&img, 1) - 0.25) <= 1e-12);
    assert_true(fabs(support_channel_mean(&img, 2) - 0.5) <= 1e-12);
    for (size_t k = 0; k < (size_t)img.w * img.h; k++)
        assert_true(fabs(img.v[3 * k]) <= 1e-15);
    aa_image_free(&img);
}

/* Every pixel of a star: the wedges are disjoint triangles, so a pixel's box
 * value is the sum of the areas of the wedges clipped to it (polygon
 * clipping and the shoelace formula, independent of the scene model and the
 * reference) over the pixel's area.  Also spokes=4, rot=0 on 2x2: wedge k
 * spans the angles k pi/2 .. k pi/2 + pi/4 and lies wholly in one quadrant
 * pixel (R = 0.48 < 1/2), so every pixel is 4 R^2 sin(pi/4)/2 = sqrt(2) R^2. */
static void test_star_pixels(void **state)
{
    (void)state;
    const double R = 0.48;
    aa_image img;
    reference("star:spokes=4,rot=0", 2, 2, "box", &img, NULL);
    for (int k = 0; k < 4; k++)
        assert_true(fabs(img.v[3 * k] - sqrt(2.0) * R * R) <= 1e-12);
    aa_image_free(&img);

    const int S = 7, W = 23, H = 17;
    const double rot = 13.0 * M_PI / 180.0;
    reference("star:spokes=7,rot=13", W, H, "box", &img, NULL);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double want = 0.0;
            for (int k = 0; k < S; k++) {
                double a = 2.0 * M_PI * k / S + rot, b = a + M_PI / S;
                const oracle_poly tri = {3,
                                         {0.5, 0.5 + R * cos(a), 0.5 + R * cos(b)},
                                         {0.5, 0.5 + R * sin(a), 0.5 + R * sin(b)}};
                want += oracle_poly_area_in_rect(&tri, (double)i / W, (double)j / H,
                                                 (i + 1.0) / W, (j + 1.0) / H);
            }
            want *= (double)W * H;
            if (!(fabs(aa_pixel(&img, i, j)[0] - want) <= 1e-12))
                fail_msg("star pixel (%d, %d): %.17g want %.17g", i, j, aa_pixel(&img, i, j)[0],
                         want);
        }
    aa_image_free(&img);
}

static void test_star_area(void **state)
{
    (void)state;
    static const struct {
        const char *spec;
        int spokes, w, h;
    } cases[] = {{"star", 36, 256, 256}, {"star:spokes=7,rot=13", 7, 61, 47},
                 {"star:spokes=3,rot=0", 3, 32, 32}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double R = 0.48, S = cases[k].spokes;
        double want = S * R * R * sin(M_PI / S) / 2.0;
        assert_true(check_integral(cases[k].spec, cases[k].w, cases[k].h, want) <=
                    AA_TRUTH_BOUND);
    }
}

/* The white length of the fence in [1/4, x] (x clipped to [1/4, 3/4]). */
static double fence_run(double x, double per, double duty)
{
    x = fmin(fmax(x, 0.25), 0.75);
    double z = (x - 0.25) / per, whole = floor(z);
    return whole * duty * per + fmin((z - whole) * per, duty * per);
}

/* A fence spec with its period and duty, at w x h. */
typedef struct fence_case {
    const char *spec;
    double per, duty;
    int w, h;
} fence_case;

/* The fence's total intensity: the bars are (duty p) wide and 1/2 tall; when
 * a whole number q of periods fits in [1/4, 3/4] the total is exactly
 * duty (1/2)^2, otherwise (1/2) (q duty p + min(r, duty p)) with the
 * remainder r = 1/2 - q p.  The image size does not matter (box filter). */
static void test_fence_total(void **state)
{
    (void)state;
    static const fence_case cases[] = {{"fence:period=0.0625", 0.0625, 0.5, 48, 40},
                 {"fence:period=0.0625,duty=0.3", 0.0625, 0.3, 33, 31},
                 {"fence", 0.9 / 256, 0.5, 100, 64}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const double p = cases[k].per, on = cases[k].duty * p, q = floor(0.5 / p);
        double want = k < 2 ? cases[k].duty * 0.25 : 0.5 * (q * on + fmin(0.5 - q * p, on));
        check_integral(cases[k].spec, cases[k].w, cases[k].h, want);
    }
}

static void test_fence_pixels(void **state)
{
    (void)state;
    static const fence_case cases[] = {{"fence", 0.9 / 256, 0.5, 64, 64},
                 {"fence:period=0.013,duty=0.3", 0.013, 0.3, 61, 47},
                 {"fence:period=0.2,duty=1", 0.2, 1.0, 9, 5}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        aa_image img;
        reference(cases[k].spec, cases[k].w, cases[k].h, "box", &img, NULL);
        const int W = cases[k].w, H = cases[k].h;
        for (int j = 0; j < H; j++) {
            double ly = fmax(0.0, fmin((j + 1.0) / H, 0.75) - fmax((double)j / H, 0.25));
            for (int i = 0; i < W; i++) {
                double lx = fence_run((i + 1.0) / W, cases[k].per, cases[k].duty) -
                            fence_run((double)i / W, cases[k].per, cases[k].duty);
                double want = W * lx * H * ly;
                assert_true(fabs(aa_pixel(&img, i, j)[0] - want) <= 1e-12);
            }
        }
        aa_image_free(&img);
    }
}

/* The homography of the feibush square, from the 8x8 system of its four
 * corner correspondences: x (g s + h t + 1) = a s + b t + c, likewise y. */
static void feibush_matrix(double M[3][3])
{
    static const double st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const double xy[4][2] = {{0.32, 0.18}, {0.72, 0.24}, {0.97, 0.96}, {0.04, 0.90}};
    double A[64] = {0}, b[8];
    for (int k = 0; k < 4; k++) {
        double s = st[k][0], t = st[k][1], x = xy[k][0], y = xy[k][1];
        double *rx = &A[16 * k], *ry = rx + 8;
        /* unknowns a b c d e f g h */
        rx[0] = s, rx[1] = t, rx[2] = 1, rx[6] = -x * s, rx[7] = -x * t, b[2 * k] = x;
        ry[3] = s, ry[4] = t, ry[5] = 1, ry[6] = -y * s, ry[7] = -y * t, b[2 * k + 1] = y;
    }
    gsl_matrix_view Av = gsl_matrix_view_array(A, 8, 8);
    gsl_vector_view bv = gsl_vector_view_array(b, 8);
    gsl_vector *u = gsl_vector_alloc(8);
    gsl_permutation *perm = gsl_permutation_alloc(8);
    int sign;
    assert_int_equal(gsl_linalg_LU_decomp(&Av.matrix, perm, &sign), 0);
    assert_int_equal(gsl_linalg_LU_solve(&Av.matrix, perm, &bv.vector, u), 0);
    for (int k = 0; k < 8; k++)
        M[k / 3][k % 3] = gsl_vector_get(u, (size_t)k);
    M[2][2] = 1.0;
    gsl_vector_free(u);
    gsl_permutation_free(perm);
}

typedef struct jac_ctx {
    double (*M)[3];
    double det, s;
} jac_ctx;

/* |det J| of the projective map at (s, t): |det M| / w^3. */
static double jac_t(double t, void *p)
{
    jac_ctx *c = p;
    double w = c->M[2][0] * c->s + c->M[2][1] * t + c->M[2][2];
    return fabs(c->det) / (w * w * w);
}

static double jac_s(double s, void *p)
{
    jac_ctx *c = p;
    c->s = s;
    gsl_function F = {jac_t, c};
    double r, e;
    size_t n;
    gsl_integration_qng(&F, 0.0, 1.0, 1e-15, 1e-15, &r, &e, &n);
    return r;
}

static void test_feibush_areas(void **state)
{
    (void)state;
    double M[3][3];
    feibush_matrix(M);
    jac_ctx c = {M, 0, 0};
    c.det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
            M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
            M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    static const int stripes[] = {24, 7};
    for (size_t k = 0; k < 2; k++) {
        int S = stripes[k];
        double red = 0.0, white = 0.0;
        for (int m = 0; m < S; m++) {
            gsl_function F = {jac_s, &c};
            double r, e;
            size_t n;
            gsl_integration_qng(&F, (double)m / S, (m + 1.0) / S, 1e-15, 1e-15, &r, &e, &n);
            *(m % 2 ? &white : &red) += r;
        }
        char spec[64];
        snprintf(spec, sizeof spec, "feibush:stripes=%d", S);
        aa_image img;
        reference(spec, 97, 83, "box", &img, NULL);
        /* red stripes are (1, 0, 0), white (1, 1, 1) */
        double r_all = support_channel_mean(&img, 0), g = support_channel_mean(&img, 1);
        assert_true(fabs(g - white) <= 1e-10);
        assert_true(fabs((r_all - g) - red) <= 1e-10);
        /* and the whole square by the shoelace formula */
        static const oracle_poly q = {4, {0.32, 0.72, 0.97, 0.04}, {0.18, 0.24, 0.96, 0.90}};
        assert_true(fabs(r_all - oracle_poly_area(&q)) <= 1e-12);
        aa_image_free(&img);
    }
}

static void test_dots_area(void **state)
{
    (void)state;
    static const struct {
        const char *spec;
        double n, size;
    } cases[] = {{"dots", 16, 0.3 / 256}, {"dots:n=5,size=0.01", 5, 0.01}};
    for (size_t k = 0; k < 2; k++)
        check_integral(cases[k].spec, 128, 96,
                       cases[k].n * cases[k].n * cases[k].size * cases[k].size);
}

static void test_slivers_area(void **state)
{
    (void)state;
    /* the default's outermost triangle pokes out of the unit square at the
     * bottom (y up to 1.0002), so the areas are clipped */
    static const struct {
        const char *spec;
        int K;
        double tilt, hmin, hmax;
    } cases[] = {{"slivers", 24, 0.1, 0.1 / 256, 1.5 / 256},
                 {"slivers:count=5,tilt=2,hmin=0.001,hmax=0.02", 5, 2, 0.001, 0.02},
                 {"slivers:count=1,hmin=0.003,hmax=0.003", 1, 0.1, 0.003, 0.003}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double want = 0.0;
        const int K = cases[k].K;
        for (int t = 0; t < K; t++) {
            double h = K == 1 ? cases[k].hmin
                              : cases[k].hmin + (cases[k].hmax - cases[k].hmin) * t / (K - 1.0);
            double y = (t + 0.5) / K;
            double d = 0.9 * tan((t - (K - 1) / 2.0) * cases[k].tilt * M_PI / 180);
            const oracle_poly tri = {3, {0.05, 0.95, 0.95}, {y, y + d - h / 2, y + d + h / 2}};
            want += oracle_poly_area_in_rect(&tri, 0.0, 0.0, 1.0, 1.0);
        }
        check_integral(cases[k].spec, 256, 256, want);
    }
}

/* Every pattern in the table: defaults build, the reference is in [0, 1]
 * within its bound, for every filter. */
static void test_every_pattern(void **state)
{
    (void)state;
    static const char *filters[] = {"box", "tent:r=1", "gauss"};
    SAN_CASES_PRINT();
    for (const aa_pattern_type *const *t = aa_pattern_types; *t; t++)
        for (size_t k = 0; k < 3; k++) {
            /* the sanitizer build's subset (SAN_SUBSET): rings, slivers
             * and feibush not under the Gaussian (the others take the
             * same paths of its rule there, star's crowded centre too) */
            const char *name = (*t)->info.name;
            if (SAN_SUBSET && k == 2 &&
                (!strcmp(name, "rings") || !strcmp(name, "slivers") || !strcmp(name, "feibush")))
                continue;
            /* rings at its default of 64 circles crowds 40 x 28 pixels
             * with conic pieces: seconds under the Gaussian; 16 circles
             * take every path of the reference all the same */
            const char *spec = strcmp((*t)->info.name, "rings") ? (*t)->info.name
                                                                : "rings:rings=16";
            aa_image img;
            double bound;
            reference(spec, 40, 28, filters[k], &img, &bound);
            assert_true(bound <= AA_TRUTH_BOUND);
            for (size_t q = 0; q < (size_t)3 * img.w * img.h; q++)
                assert_true(img.v[q] >= -1e-12 && img.v[q] <= 1 + 1e-12);
            aa_image_free(&img);
        }
}

static void test_refusals(void **state)
{
    (void)state;
    static const char *bad[] = {
        "fence:period=0",          "fence:period=1e-6",   "fence:duty=0",
        "fence:duty=1.5",          "dots:n=0",            "dots:n=257",
        "dots:size=0",             "star:spokes=0",       "star:spokes=5000",
        "star:rot=nan",            "catmull:tiles=0",     "catmull:tiles=257",
        "slivers:count=0",         "slivers:hmin=-1e-3",  "slivers:hmin=0.01,hmax=0.001",
        "slivers:count=24,tilt=8", "feibush:stripes=0",   "feibush:stripes=70000",
        "star:spokes=3.5",         "catmull:depth=2"};
    aa_spec spec;
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        if (aa_pattern_parse(bad[k], &spec) == AA_OK)
            fail_msg("%s was accepted", bad[k]);
    }
    /* text strings: RFC 3629's well-formed UTF-8 without control characters
     * (%XX is a byte of the value) */
    static const char *bad_text[][2] = {
        {"text:string=a%FFb", "not UTF-8 (byte 2 is 0xff)"},
        {"text:string=%C0%AF", "not UTF-8 (byte 1 is 0xc0)"},       /* overlong '/' */
        {"text:string=%E0%80%AF", "not UTF-8 (byte 1 is 0xe0)"},    /* overlong '/' */
        {"text:string=%ED%A0%80", "not UTF-8 (byte 1 is 0xed)"},    /* surrogate D800 */
        {"text:string=%F4%90%80%80", "not UTF-8 (byte 1 is 0xf4)"}, /* U+110000 */
        {"text:string=ab%C3", "not UTF-8 (byte 3 is 0xc3)"},        /* cut short */
        {"text:string=a%0Ab", "control character U+000A at byte 2"},
        {"text:string=%7F", "control character U+007F at byte 1"},
        {"text:string=x%C2%85", "control character U+0085 at byte 2"}};
    for (size_t k = 0; k < sizeof bad_text / sizeof bad_text[0]; k++)
        if (aa_pattern_parse(bad_text[k][0], &spec) != AA_EINVAL ||
            !strstr(aa_last_error(), bad_text[k][1]))
            fail_msg("%s: \"%s\", expected \"%s\"", bad_text[k][0], aa_last_error(),
                     bad_text[k][1]);
    /* two-, three- and four-byte characters at the ends of their ranges */
    assert_int_equal(aa_pattern_parse("text:string=%C2%A0%DF%BF%E0%A0%80%EF%BF%BD%F0%90%80%80"
                                      "%F4%8F%BF%BF",
                                      &spec),
                     AA_OK);
    /* the limits themselves are accepted */
    assert_int_equal(aa_pattern_parse("fence:period=7.62939453125e-06", &spec), AA_OK);
    assert_int_equal(aa_pattern_parse("slivers:count=3,tilt=80,hmin=0,hmax=0", &spec), AA_OK);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_catmull_pixel),
             cmocka_unit_test(test_catmull_hidden),
             cmocka_unit_test(test_star_area),
             cmocka_unit_test(test_star_pixels),
             cmocka_unit_test(test_fence_pixels),
             cmocka_unit_test(test_fence_total),
             cmocka_unit_test(test_feibush_areas),
             cmocka_unit_test(test_dots_area),
             cmocka_unit_test(test_slivers_area),
             cmocka_unit_test(test_every_pattern),
             cmocka_unit_test(test_refusals))
