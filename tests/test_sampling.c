/*
 * test_sampling.c: the sampling methods `supersample` and `jitter`, each
 * known answer derived here independently of the code under test.
 *
 *  - supersample with the box is the plain mean of its n^2 point samples,
 *    asked of the scene directly (aa_scene_colour_at) at (i + (a+1/2)/n,
 *    j + (b+1/2)/n): Crow fig. 2.11 for n = 3.
 *  - supersample n=5 with tent:r=1 weighs its 25 samples as Crow's fig.
 *    2.12 implies: offsets 0, +-0.4, +-0.8, 1-D weights 1, 0.6, 0.2, so a
 *    sample weighs w_a w_b / 2.6^2 (read off with a tiny square around one
 *    sample position).
 *  - the msaa patterns sample exactly the positions of algorithms/README.md
 *    ("Standard multisample positions"), written out again here in its own
 *    notation (v/16 from the centre).
 *  - jitter stratified puts exactly one sample in each cell of the k x k
 *    grid (a scene that is white on one cell gives exactly 1/k^2); random
 *    does not.
 *  - GSL's sequences start as documented and as derived by hand: Sobol from
 *    its direction numbers (identity and Pascal matrix mod 2, Gray-code
 *    order), skipping the origin; niederreiter_2 is (0,0) followed by the
 *    same points; Halton starts at index 1.  gsl_qrng_alloc does not fail
 *    above the dimension limits (algorithms/README.md, "Quasi-random
 *    sequences in GSL").  Sobol's first 2^m points are not a (0,m,2)-net, with the origin
 *    put back they are; niederreiter's are.
 *  - the Owen-scrambled sets jitter uses remain (0,m,2)-nets (every
 *    elementary box of volume 2^-m holds exactly one sample, seen through a
 *    scene white on that box), Halton's remain one per 2^-a x 3^-b box, and
 *    the scrambles are unbiased (mean over many pixels = the exact area).
 *  - seeds: the same seed repeats bit for bit, another changes the image,
 *    and so does another frame; any thread count gives the same image.
 *  - on crow 256x256 box: RMSE(supersample n=3) < RMSE(point), and
 *    RMSE(jitter spp=64) < RMSE(supersample n=3), against aa_truth_render.
 *  - convergence over random sub-pixel shifts of a polygon: RMSE falls as
 *    spp^-3/4 for stratified jitter and spp^-1/2 for random (Mitchell 1996;
 *    algorithms/README.md, "Convergence rates"), slopes fitted over
 *    spp = 4..256.
 *  - tent and Gaussian are honoured: many samples approach their references.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_qrng.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

/* ---- helpers ---- */

/* A square of side `side` centred at (x, y), in pattern units. */
static aa_scene *dot_scene(double x, double y, double side)
{
    const double r[1][4] = {{x - side / 2, y - side / 2, x + side / 2, y + side / 2}};
    return scenes_rects(r, 1);
}

/* Several layers, RGB colours, a quadratic arc, both fill rules. */
static aa_scene *rgb_scene(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.9, 0.4, 0.1}}, AA_FILL_EVENODD), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.1, 0.15), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, 0.9, 0.05, 0.8, 0.7), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.2, 0.9), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    scenes_rect(s, 0.3, 0.3, 0.55, 0.62); /* a hole, even-odd */
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.2, 0.8, 0.6}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.05, 0.95), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.6, 0.02), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 0.97, 0.83), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* Render a method at time t with motion (vx, vy); allocates the image. */
static void render_at(const char *method, const aa_scene *scene, const char *filter, int w,
                      int h, double t, double vx, double vy, uint64_t seed, int threads,
                      aa_image *out, aa_counters *c)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .filter = filter,
                            .seed = seed, .threads = threads};
    support_render_must(method, scene, &v, out, c);
}

static void render(const char *method, const aa_scene *scene, const char *filter, int w, int h,
                   uint64_t seed, int threads, aa_image *out, aa_counters *c)
{
    render_at(method, scene, filter, w, h, 0, 0, 0, seed, threads, out, c);
}

/* The value (channel 0) of a 1x1 render. */
static double one_pixel(const char *method, const aa_scene *scene, const char *filter,
                        uint64_t seed)
{
    aa_image img;
    render(method, scene, filter, 1, 1, seed, 1, &img, NULL);
    double v = img.v[0];
    aa_image_free(&img);
    return v;
}

static void truth(const aa_scene *scene, const char *filter, int w, int h, double t, double vx,
                  double vy, aa_image *out)
{
    const support_view v = {.w = w, .h = h, .t = t, .vx = vx, .vy = vy, .filter = filter};
    support_reference(scene, &v, out, NULL, NULL);
}

/* ---- supersample ---- */

/* Box: each pixel is the mean of the scene's colours at the n x n grid
 * points (i + (a+1/2)/n, j + (b+1/2)/n), asked of the scene directly. */
static void check_box_mean(const aa_scene *s, int w, int h, int n, double tol)
{
    char spec[64];
    snprintf(spec, sizeof spec, "supersample:n=%d", n);
    aa_image img;
    aa_counters c;
    render(spec, s, "box", w, h, 1, 2, &img, &c);
    aa_scene *placed = aa_scene_place(s, w, h, 0, 0, 0);
    double worst = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double sum[3] = {0, 0, 0};
            for (int b = 0; b < n; b++)
                for (int a = 0; a < n; a++) {
                    aa_rgb col = aa_scene_colour_at(placed, i + (a + 0.5) / n, j + (b + 0.5) / n);
                    for (int ch = 0; ch < 3; ch++)
                        sum[ch] += col.c[ch];
                }
            for (int ch = 0; ch < 3; ch++) {
                double want = sum[ch] / (n * n), got = aa_pixel(&img, i, j)[ch];
                if (fabs(got - want) > worst)
                    worst = fabs(got - want);
                if (!(fabs(got - want) <= tol))
                    fail_msg("%s %dx%d pixel (%d, %d) channel %d: %.17g, mean of samples %.17g",
                             spec, w, h, i, j, ch, got, want);
            }
        }
    /* every sampled pixel takes n^2 samples; the rest are filled */
    assert_true(c.samples == (uint64_t)n * n * c.expensive_pixels);
    assert_true(c.expensive_pixels > 0 && c.expensive_pixels <= (uint64_t)w * h);
    print_message("%-16s %3dx%-3d: max |pixel - mean of its %2d point samples| %.1e, %llu of "
                  "%d pixels sampled\n",
                  spec, w, h, n * n, worst, (unsigned long long)c.expensive_pixels, w * h);
    aa_scene_free(placed);
    aa_image_free(&img);
}

static void test_supersample_box_is_mean(void **state)
{
    (void)state;
    aa_scene *crow = scenes_pattern("crow"), *rgb = rgb_scene();
    /* crow's samples are 0 or 1: the count over n^2 is exact */
    for (int n = 1; n <= 5; n++)
        check_box_mean(crow, 61, 47, n, 0.0);
    /* RGB colours: sums in another order, so a few ulps */
    for (int n = 2; n <= 4; n++)
        check_box_mean(rgb, 37, 29, n, 1e-14);
    aa_scene_free(crow);
    aa_scene_free(rgb);
}

/* Crow fig. 2.12: n=5 over tent:r=1's support [-1, 1]^2.  Offsets
 * -1 + (2a+1)/5 = -0.8, -0.4, 0, 0.4, 0.8; tent weights 1 - |t| = 0.2, 0.6,
 * 1, 0.6, 0.2, summing to 2.6 per axis.  A square of side 0.05 around one
 * sample holds no other (they are 0.4 apart), so a 1x1 image of it is that
 * sample's normalised weight.  Fig. 2.11: box n=3, each of the nine 1/9. */
static void test_supersample_crow_figures(void **state)
{
    (void)state;
    const struct {
        const char *method, *filter;
        double x, y, want;
    } cases[] = {
        {"supersample:n=5", "tent:r=1", 0.5, 0.5, 1.0 / (2.6 * 2.6)},
        {"supersample:n=5", "tent:r=1", 0.5 + 0.8, 0.5 + 0.8, 0.2 * 0.2 / (2.6 * 2.6)},
        {"supersample:n=5", "tent:r=1", 0.5 - 0.4, 0.5 + 0.8, 0.6 * 0.2 / (2.6 * 2.6)},
        {"supersample:n=5", "tent:r=1", 0.5 - 0.4, 0.5, 0.6 * 1.0 / (2.6 * 2.6)},
        {"supersample:n=5", "tent:r=1", 0.5 - 0.2, 0.5, 0.0}, /* between samples */
        {"supersample", "box", 1.0 / 6, 1.0 / 6, 1.0 / 9},
        {"supersample", "box", 0.5, 5.0 / 6, 1.0 / 9},
        {"supersample", "box", 1.0 / 3, 0.5, 0.0},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        aa_scene *s = dot_scene(cases[k].x, cases[k].y, 0.05);
        double v = one_pixel(cases[k].method, s, cases[k].filter, 1);
        if (!(fabs(v - cases[k].want) <= 1e-15))
            fail_msg("%s -f %s, dot at (%g, %g): %.17g, want %.17g", cases[k].method,
                     cases[k].filter, cases[k].x, cases[k].y, v, cases[k].want);
        aa_scene_free(s);
    }
}

/* algorithms/README.md, "Standard multisample positions": in 1/16 pixel from the
 * pixel centre, y down, i.e. at 0.5 + v/16 in the pixel. */
static const struct {
    const char *name;
    int n;
    int v[16][2];
} msaa[] = {
    {"msaa2", 2, {{4, 4}, {-4, -4}}},
    {"msaa4", 4, {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}},
    {"msaa8", 8, {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}},
    {"msaa16",
     16,
     {{1, 1}, {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5}, {5, 3}, {3, -5}, {-2, 6}, {0, -7},
      {-4, -6}, {-6, 4}, {-8, 0}, {7, -4}, {6, 7}, {-7, -8}}},
};

static int listed(int p, int x, int y)
{
    for (int k = 0; k < msaa[p].n; k++)
        if (msaa[p].v[k][0] == x && msaa[p].v[k][1] == y)
            return 1;
    return 0;
}

/* A dot of side 1/32 around each listed position gives exactly 1/N (box:
 * equal weights); around any other point of the 1/16 lattice, 0; dots on
 * all N, exactly 1.  Then the same in pixel (3, 2) of a 5x4 image. */
static void test_msaa_positions(void **state)
{
    (void)state;
    const double side = 1.0 / 32;
    for (int p = 0; p < 4; p++) {
        char spec[64];
        snprintf(spec, sizeof spec, "supersample:pattern=%s", msaa[p].name);
        int n = msaa[p].n, hits = 0;
        for (int y = -8; y <= 8; y++)
            for (int x = -8; x <= 8; x++) {
                aa_scene *s = dot_scene(0.5 + x / 16.0, 0.5 + y / 16.0, side);
                double v = one_pixel(spec, s, "box", 1);
                double want = listed(p, x, y) ? 1.0 / n : 0.0;
                if (v != want)
                    fail_msg("%s: dot at (%d, %d)/16 gives %.17g, want %.17g", spec, x, y, v,
                             want);
                hits += v > 0;
                aa_scene_free(s);
            }
        assert_int_equal(hits, n);
        /* all the dots, in pixel (3, 2) of a 5x4 image (pattern units) */
        double r[16][4];
        for (int k = 0; k < n; k++) {
            double x = (3.5 + msaa[p].v[k][0] / 16.0) / 5, y = (2.5 + msaa[p].v[k][1] / 16.0) / 4;
            r[k][0] = x - side / 10, r[k][1] = y - side / 8, r[k][2] = x + side / 10,
            r[k][3] = y + side / 8;
        }
        aa_scene *s = scenes_rects((const double(*)[4])r, n);
        aa_image img;
        render(spec, s, "box", 5, 4, 1, 1, &img, NULL);
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 5; i++)
                assert_true(aa_pixel(&img, i, j)[0] == (i == 3 && j == 2 ? 1.0 : 0.0));
        aa_image_free(&img);
        aa_scene_free(s);
    }
    /* tent:r=1 weighs msaa8's position (1,-3) by (1 - 1/16)(1 - 3/16),
     * normalised by the sum over all eight */
    double total = 0;
    for (int k = 0; k < 8; k++)
        total += (1 - abs(msaa[2].v[k][0]) / 16.0) * (1 - abs(msaa[2].v[k][1]) / 16.0);
    aa_scene *s = dot_scene(0.5 + 1 / 16.0, 0.5 - 3 / 16.0, side);
    double v = one_pixel("supersample:pattern=msaa8", s, "tent:r=1", 1);
    assert_true(fabs(v - (15.0 / 16) * (13.0 / 16) / total) <= 1e-15);
    aa_scene_free(s);
    /* n belongs to the grid; a filter that weighs every position zero */
    aa_filter f;
    aa_spec spec;
    assert_int_equal(aa_filter_parse("box", &f), AA_OK);
    assert_int_equal(aa_method_parse("supersample:n=5,pattern=msaa4", &f, &spec), AA_EINVAL);
    print_message("refused: %s\n", aa_last_error());
    assert_int_equal(aa_filter_parse("tent:r=0.25", &f), AA_OK);
    assert_int_equal(aa_method_parse("supersample:pattern=msaa2", &f, &spec), AA_EINVAL);
    print_message("refused: %s\n", aa_last_error());
}

/* ---- jitter: stratification and seeds ---- */

/* A 1x1 image of a scene white on the box [x0, x1] x [y0, y1] is the share
 * of the pixel's samples in the box: `want` (within tol) for every seed
 * from 1 to `seeds`. */
static void check_share(const char *spec, double x0, double y0, double x1, double y1,
                        int seeds, double want, double tol)
{
    const double r[1][4] = {{x0, y0, x1, y1}};
    aa_scene *s = scenes_rects(r, 1);
    for (uint64_t seed = 1; seed <= (uint64_t)seeds; seed++) {
        double v = one_pixel(spec, s, "box", seed);
        if (!(fabs(v - want) <= tol))
            fail_msg("%s seed %llu: the box [%g, %g] x [%g, %g] holds %.17g of the samples, "
                     "not %.17g",
                     spec, (unsigned long long)seed, x0, x1, y0, y1, v, want);
    }
    aa_scene_free(s);
}

/* Stratified jitter puts exactly 1/k^2 of its samples in each cell of the
 * k x k grid, for every cell and seed. */
static void test_jitter_stratified_cells(void **state)
{
    (void)state;
    for (int k = 1; k <= 4; k++) {
        char spec[64];
        snprintf(spec, sizeof spec, "jitter:spp=%d", k * k);
        for (int b = 0; b < k; b++)
            for (int a = 0; a < k; a++)
                check_share(spec, (double)a / k, (double)b / k, (a + 1.0) / k, (b + 1.0) / k, 6,
                            1.0 / (k * k), 0.0);
    }
    /* random points are not stratified: some cell of 4x4 is missed or
     * doubled (16 independent points fill all 16 cells with probability
     * 16!/16^16, about 1e-6) */
    int off = 0;
    for (int cell = 0; cell < 16; cell++) {
        const double r[1][4] = {{(cell % 4) / 4.0, (cell / 4) / 4.0, (cell % 4 + 1) / 4.0,
                                 (cell / 4 + 1) / 4.0}};
        aa_scene *s = scenes_rects(r, 1);
        off += one_pixel("jitter:spp=16,seq=random", s, "box", 1) != 1.0 / 16;
        aa_scene_free(s);
    }
    print_message("seq=random, spp=16: %d of 16 cells do not hold exactly one sample\n", off);
    assert_true(off > 0);
    aa_filter f;
    aa_spec spec;
    aa_filter_default(&f);
    assert_int_equal(aa_method_parse("jitter:spp=12", &f, &spec), AA_EINVAL);
    print_message("refused: %s\n", aa_last_error());
    assert_int_equal(aa_method_parse("jitter:spp=12,seq=random", &f, &spec), AA_OK);
}

static const char *const seqs[] = {"stratified", "random", "sobol", "halton", "niederreiter"};

/* The same seed repeats bit for bit (and with 3 threads), another seed or
 * another frame changes the image. */
static void test_jitter_seeds(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    const int w = 53, h = 37;
    const size_t bytes = sizeof(double) * w * h * 3;
    for (int q = 0; q < 5; q++) {
        char spec[64];
        snprintf(spec, sizeof spec, "jitter:spp=16,seq=%s", seqs[q]);
        aa_image a, b, c, d, e;
        render(spec, s, "tent:r=0.75", w, h, 42, 1, &a, NULL);
        render(spec, s, "tent:r=0.75", w, h, 42, 3, &b, NULL);
        render(spec, s, "tent:r=0.75", w, h, 43, 2, &c, NULL);
        render_at(spec, s, "tent:r=0.75", w, h, 0, 0, 0, 42, 2, &d, NULL);
        render_at(spec, s, "tent:r=0.75", w, h, 1, 0, 0, 42, 2, &e, NULL); /* frame 1, still */
        if (memcmp(a.v, b.v, bytes) || memcmp(a.v, d.v, bytes))
            fail_msg("%s: the same seed gives another image", spec);
        if (!memcmp(a.v, c.v, bytes))
            fail_msg("%s: another seed gives the same image", spec);
        if (!memcmp(a.v, e.v, bytes))
            fail_msg("%s: another frame gives the same image", spec);
        aa_image_free(&a), aa_image_free(&b), aa_image_free(&c), aa_image_free(&d);
        aa_image_free(&e);
    }
    /* in two dimensions sobol (origin first) and niederreiter_2 are the
     * same point set, so, scrambled alike, the same image */
    aa_image a, b;
    render("jitter:spp=16,seq=sobol", s, "box", w, h, 5, 2, &a, NULL);
    render("jitter:spp=16,seq=niederreiter", s, "box", w, h, 5, 2, &b, NULL);
    assert_memory_equal(a.v, b.v, bytes);
    aa_image_free(&a), aa_image_free(&b);
    aa_scene_free(s);
}

/* ---- the quasi-random sequences ---- */

/* Sobol point n (n >= 1) in two dimensions, from first principles: Gray
 * code g = n ^ (n >> 1); x XORs 2^-(k+1) over the bits k of g (identity
 * generator matrix: van der Corput), y XORs column k of the Pascal matrix
 * mod 2, i.e. digit r+1 is C(k, r) mod 2 (primitive polynomial x + 1). */
static void sobol_by_hand(unsigned n, double *x, double *y)
{
    unsigned g = n ^ (n >> 1);
    uint32_t X = 0, Y = 0;
    for (int k = 0; k < 30; k++) {
        if (!(g >> k & 1u))
            continue;
        X ^= 1u << (29 - k);
        for (int r = 0; r <= k; r++) {
            /* C(k, r) is odd iff r's bits are a subset of k's (Lucas) */
            if ((r & k) == r)
                Y ^= 1u << (29 - r);
        }
    }
    *x = ldexp(X, -30);
    *y = ldexp(Y, -30);
}

static double radical_inverse(unsigned n, unsigned base)
{
    double v = 0, f = 1.0 / base;
    for (; n; n /= base, f /= base)
        v += (n % base) * f;
    return v;
}

/* Is {(x_k, y_k)} a (0,m,2)-net in base 2: exactly one point in each
 * elementary box 2^-p x 2^-q, p + q = m? */
static int is_net(const double *x, const double *y, int m)
{
    int n = 1 << m, *count = calloc((size_t)n, sizeof *count), ok = 1;
    for (int p = 0; p <= m && ok; p++) {
        memset(count, 0, (size_t)n * sizeof *count);
        for (int k = 0; k < n; k++) {
            int a = (int)floor(ldexp(x[k], p)), b = (int)floor(ldexp(y[k], m - p));
            count[(a << (m - p)) | b]++;
        }
        for (int k = 0; k < n; k++)
            ok = ok && count[k] == 1;
    }
    free(count);
    return ok;
}

static void test_gsl_sequences(void **state)
{
    (void)state;
    gsl_set_error_handler_off();
    enum { N = 1024 };
    static double sx[N + 1], sy[N + 1], nx[N], ny[N];
    gsl_qrng *sob = gsl_qrng_alloc(gsl_qrng_sobol, 2), *nie = gsl_qrng_alloc(gsl_qrng_niederreiter_2, 2),
             *hal = gsl_qrng_alloc(gsl_qrng_halton, 2);
    assert_non_null(sob), assert_non_null(nie), assert_non_null(hal);
    sx[0] = sy[0] = 0; /* the origin GSL's Sobol sequence skips */
    for (unsigned k = 0; k < N; k++) {
        double v[2], hx, hy;
        assert_int_equal(gsl_qrng_get(sob, v), 0);
        sx[k + 1] = v[0], sy[k + 1] = v[1];
        sobol_by_hand(k + 1, &hx, &hy);
        if (v[0] != hx || v[1] != hy)
            fail_msg("GSL Sobol point %u is (%.17g, %.17g), by hand (%.17g, %.17g)", k + 1, v[0],
                     v[1], hx, hy);
        assert_int_equal(gsl_qrng_get(nie, v), 0);
        nx[k] = v[0], ny[k] = v[1];
        if (v[0] != sx[k] || v[1] != sy[k])
            fail_msg("GSL niederreiter_2 point %u differs from Sobol point %u", k, k);
        assert_int_equal(gsl_qrng_get(hal, v), 0);
        if (fabs(v[0] - radical_inverse(k + 1, 2)) > 1e-15 ||
            fabs(v[1] - radical_inverse(k + 1, 3)) > 1e-15)
            fail_msg("GSL Halton point %u is not the radical inverses of %u", k, k + 1);
    }
    /* the GSL manual's Sobol example starts 0.5 0.5, 0.75 0.25, 0.25 0.75 */
    assert_true(sx[1] == 0.5 && sy[1] == 0.5 && sx[2] == 0.75 && sy[2] == 0.25);
    assert_true(sx[3] == 0.25 && sy[3] == 0.75 && sx[4] == 0.375 && sy[4] == 0.375);
    for (int m = 1; m <= 10; m++) {
        /* GSL's own first 2^m Sobol points: not a net (y 1/4-strata of the
         * first four: 1/2, 1/4, 3/4, 3/8) */
        assert_false(is_net(sx + 1, sy + 1, m));
        assert_true(is_net(sx, sy, m));
        assert_true(is_net(nx, ny, m));
    }
    gsl_qrng_free(sob), gsl_qrng_free(nie), gsl_qrng_free(hal);
    /* the trap: beyond the dimension limits (sobol 40, niederreiter_2 12)
     * gsl_qrng_alloc does not fail.  (Its points there are not to be
     * read: valgrind finds sobol's made of uninitialised memory.) */
    gsl_qrng *big = gsl_qrng_alloc(gsl_qrng_sobol, 41);
    assert_non_null(big);
    gsl_qrng_free(big);
    big = gsl_qrng_alloc(gsl_qrng_niederreiter_2, 13);
    assert_non_null(big);
    gsl_qrng_free(big);
}

/* Every elementary box of volume 2^-m gets exactly one of the 2^m samples
 * of a scrambled (0,m,2)-net, whatever the seed; through 1x1 renders of a
 * scene white on that box. */
static void test_scrambled_nets(void **state)
{
    (void)state;
    const char *net_seqs[] = {"sobol", "niederreiter"};
    for (int q = 0; q < 2; q++)
        for (int m = 2; m <= 4; m += 2) {
            char spec[64];
            snprintf(spec, sizeof spec, "jitter:spp=%d,seq=%s", 1 << m, net_seqs[q]);
            for (int p = 0; p <= m; p++)
                for (int a = 0; a < (1 << p); a++)
                    for (int b = 0; b < (1 << (m - p)); b++)
                        check_share(spec, ldexp(a, -p), ldexp(b, p - m), ldexp(a + 1, -p),
                                    ldexp(b + 1, p - m), 3, ldexp(1, -m), 0.0);
        }
    /* Halton: N = 2^a 3^b points, one in each 2^-a x 3^-b box */
    const int shapes[][2] = {{1, 1}, {2, 1}, {1, 2}, {3, 1}};
    for (int k = 0; k < 4; k++) {
        int nx = 1 << shapes[k][0], ny = shapes[k][1] == 1 ? 3 : 9;
        char spec[64];
        snprintf(spec, sizeof spec, "jitter:spp=%d,seq=halton", nx * ny);
        for (int a = 0; a < nx; a++)
            for (int b = 0; b < ny; b++)
                check_share(spec, (double)a / nx, (double)b / ny, (a + 1.0) / nx, (b + 1.0) / ny,
                            3, 1.0 / (nx * ny), 1e-15);
    }
}

/* Scrambled points are uniformly distributed: every pixel of a 64x64 image
 * holds the same off-centre rectangle [0.13, 0.37] x [0.55, 0.84] (area
 * 0.0696), each pixel scrambled independently, so the image mean estimates
 * the expected pixel value, which must be the area.  The tolerance is five
 * standard errors, the spread measured over the pixels themselves. */
static void test_scrambles_unbiased(void **state)
{
    (void)state;
    enum { W = 64 };
    static double r[W * W][4];
    for (int j = 0; j < W; j++)
        for (int i = 0; i < W; i++) {
            double *q = r[j * W + i];
            q[0] = (i + 0.13) / W, q[1] = (j + 0.55) / W, q[2] = (i + 0.37) / W,
            q[3] = (j + 0.84) / W;
        }
    aa_scene *s = scenes_rects((const double(*)[4])r, W * W);
    const double area = 0.24 * 0.29;
    for (int q = 0; q < 5; q++)
        for (int spp = 4; spp <= 16; spp *= 4) {
            char spec[64];
            snprintf(spec, sizeof spec, "jitter:spp=%d,seq=%s", spp, seqs[q]);
            aa_image img;
            render(spec, s, "box", W, W, 9, 2, &img, NULL);
            double sum = 0, sum2 = 0;
            for (int k = 0; k < W * W; k++)
                sum += img.v[3 * k], sum2 += img.v[3 * k] * img.v[3 * k];
            double mean = sum / (W * W), var = sum2 / (W * W) - mean * mean;
            double se = sqrt(var / (W * W));
            print_message("%-30s mean %.5f (area %.5f), standard error %.5f\n", spec, mean, area,
                          se);
            if (!(fabs(mean - area) <= 5 * se + 1e-12))
                fail_msg("%s: mean pixel %.6f, area %.6f: off by %.1f standard errors", spec,
                         mean, area, fabs(mean - area) / se);
            aa_image_free(&img);
        }
    aa_scene_free(s);
}

/* ---- error against the reference ---- */

static void test_rmse_crow(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    const char *order[] = {"point", "supersample:n=3", "jitter:spp=64"};
    const support_view v = {.w = 256, .h = 256, .filter = "box", .seed = 1, .threads = 2};
    support_check_rmse_order("crow", s, &v, order, 3);
    aa_scene_free(s);
}

/* The filters are honoured: on a scene of edges (several layers, RGB, an
 * arc), many samples come close to the reference of the method's own
 * filter, and much closer than to the box reference (so the filter did
 * change the image).  The Gaussian truncated at 3s loses 1 - erf(3/sqrt
 * 2)^2 = 0.54% of its weight, which bounds what is left for it. */
static void test_filters_converge(void **state)
{
    (void)state;
    aa_scene *s = rgb_scene();
    /* bounds: a few times the RMSE seen, which for the Gaussian is mostly
     * its truncation (its 0.54% of weight beyond 3s, across edges of
     * contrast up to 0.8) */
    const char *filters[] = {"tent:r=0.5", "tent:r=1", "gauss", "gauss:s=1"};
    const double bound[] = {3e-3, 3e-3, 5e-3, 8e-3};
    aa_image box;
    truth(s, "box", 40, 32, 0, 0, 0, &box);
    for (int k = 0; k < 4; k++) {
        aa_image ref, a, b, c;
        truth(s, filters[k], 40, 32, 0, 0, 0, &ref);
        render("supersample:n=4", s, filters[k], 40, 32, 1, 2, &c, NULL);
        render("supersample:n=24", s, filters[k], 40, 32, 1, 2, &a, NULL);
        render("jitter:spp=576", s, filters[k], 40, 32, 1, 2, &b, NULL);
        double ec = support_rmse(&c, &ref), ea = support_rmse(&a, &ref);
        double eb = support_rmse(&b, &ref);
        double ebox = support_rmse(&a, &box);
        print_message("rgb 40x32 %-10s: RMSE supersample n=4 %.2e, n=24 %.2e, jitter spp=576 "
                      "%.2e; n=24 against the box reference %.2e\n",
                      filters[k], ec, ea, eb, ebox);
        assert_true(ea < bound[k] && eb < bound[k]);
        assert_true(ea < ec / 3);
        assert_true(ebox > 5 * ea);
        aa_image_free(&ref), aa_image_free(&a), aa_image_free(&b), aa_image_free(&c);
    }
    aa_image_free(&box);
    aa_scene_free(s);
}

/* A polygon with straight edges at several angles, in pattern units. */
static aa_scene *polygon_scene(void)
{
    const double xy[] = {0.11, 0.17, 0.83, 0.09, 0.91, 0.71, 0.43, 0.93, 0.21, 0.62};
    return scenes_polygon(xy, 5, white, black, AA_FILL_NONZERO);
}

/* RMSE against spp over random sub-pixel shifts (t = 1 with motion (vx,
 * vy) in [0,1)^2), and the least-squares slope of log RMSE on log spp. */
static double convergence_slope(const aa_scene *s, const char *seq, int shifts)
{
    enum { W = 48, NS = 4 };
    const int spps[NS] = {4, 16, 64, 256};
    double lx[NS], ly[NS], mse[NS] = {0};
    aa_rng shift;
    aa_rng_seed(&shift, 2024, 0, 0);
    for (int k = 0; k < shifts; k++) {
        double vx = aa_rng_uniform(&shift), vy = aa_rng_uniform(&shift);
        aa_image ref, img;
        truth(s, "box", W, W, 1, vx, vy, &ref);
        for (int q = 0; q < NS; q++) {
            char spec[64];
            snprintf(spec, sizeof spec, "jitter:spp=%d,seq=%s", spps[q], seq);
            render_at(spec, s, "box", W, W, 1, vx, vy, 100 + k, 2, &img, NULL);
            double e = support_rmse(&img, &ref);
            mse[q] += e * e / shifts;
            aa_image_free(&img);
        }
        aa_image_free(&ref);
    }
    for (int q = 0; q < NS; q++)
        lx[q] = log(spps[q]), ly[q] = 0.5 * log(mse[q]);
    double c0, c1, cov00, cov01, cov11, sumsq;
    gsl_fit_linear(lx, 1, ly, 1, NS, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    print_message("%-12s RMSE at spp 4, 16, 64, 256: %.3e %.3e %.3e %.3e; slope %.3f\n", seq,
                  sqrt(mse[0]), sqrt(mse[1]), sqrt(mse[2]), sqrt(mse[3]), c1);
    return c1;
}

/* Mitchell (1996), algorithms/README.md, "Convergence rates": for an edge,
 * RMSE ~ spp^-3/4 stratified,
 * spp^-1/2 random.  The fit over 16 shifts of a polygon on 48x48 (about
 * 170 edge pixels each) has a standard error near 0.01; the bands below
 * are several times that, and the seeds are fixed. */
static void test_convergence(void **state)
{
    (void)state;
    aa_scene *s = polygon_scene();
    double strat = convergence_slope(s, "stratified", 16);
    double rnd = convergence_slope(s, "random", 16);
    double sob = convergence_slope(s, "sobol", 16);
    assert_true(strat > -0.9 && strat < -0.65);
    assert_true(rnd > -0.58 && rnd < -0.42);
    assert_true(strat < rnd - 0.15);
    assert_true(sob > -0.95 && sob < -0.65); /* scrambled (0,m,2)-nets: also spp^-3/4 */
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_supersample_box_is_mean),
             cmocka_unit_test(test_supersample_crow_figures),
             cmocka_unit_test(test_msaa_positions),
             cmocka_unit_test(test_jitter_stratified_cells),
             cmocka_unit_test(test_jitter_seeds),
             cmocka_unit_test(test_gsl_sequences),
             cmocka_unit_test(test_scrambled_nets),
             cmocka_unit_test(test_scrambles_unbiased),
             cmocka_unit_test(test_rmse_crow),
             cmocka_unit_test(test_filters_converge),
             cmocka_unit_test(test_convergence))
