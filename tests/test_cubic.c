/*
 * test_cubic.c: cubic Bezier arcs in the scene model (aa_scene_cubic_to),
 * against answers derived independently of the code under test.
 *
 *  - The region under y = x^3 (0 <= x <= 1), whose boundary is one cubic:
 *    x = t, y = t^3 is the Bezier with controls (0,0), (1/3,0), (2/3,0),
 *    (1,1) (Bernstein: x = 3 t (1-t)^2/3 + 3 t^2 (1-t) 2/3 + t^3 = t, and
 *    y = t^3).  Its area in the cell [a,b] x [c,d] is the integral over
 *    [a, b] of clamp(x^3 - c, 0, d - c) dx, which is x^4/4 - c x between
 *    cbrt(c) and cbrt(d) and (d - c) x beyond cbrt(d): the box-filtered
 *    value of every pixel in closed form (1/4 for the whole shape in one
 *    pixel).  The reference within 1e-12 of it, `area` within 1e-12,
 *    `point` the membership of each centre (x^3 against y), the peers
 *    within their 8-bit coverage and flattening.
 *  - An arch with a turning point in y, (0,0), (0,1), (1,1), (1,0), closed
 *    by its chord: x = 3t^2 - 2t^3, y = 3t(1-t), so the area is the
 *    integral of y x' dt = 18 int t^2 (1-t)^2 dt = 18 B(3,3) = 18/30 = 3/5;
 *    and the same arch turned a quarter (a turning point in x).  Scaled
 *    by s into the unit square: one pixel holding it all is 3/5 s^2.
 *  - A cubic that is secretly a quadratic (degree elevation: the controls
 *    P0 + 2/3 (C - P0) and P1 + 2/3 (C - P1) trace the same curve): `crow`
 *    rebuilt so gives crow's image to rounding, reference, `area` and every
 *    sampler, and the peers within their own rounding.
 *  - Random scenes of cubics (several layers, both fill rules, loops,
 *    crossings): the reference (adaptive quadrature, its own code path)
 *    within its bound of `area` (closed-form cell areas): two independent
 *    derivations.
 *  - Crossings: every piece is y-monotone and the pieces of an edge chain
 *    end to end; x at y, the meetings with a vertical line and between two
 *    pieces against bisection in long double on the Bernstein form; and
 *    `area`'s root of a monotone cubic from a guess (area_cubic_near,
 *    Newton's method with a stopping test) against bisection in long
 *    double, from guesses at the cubic's inflection, where f'' vanishes.
 *  - Export: cubic arcs are written as SVG C commands.
 */
#include "area_internal.h"
#include "bench.h"
#include "oracle.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

typedef long double ld;

/* Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) test_crowded_cubics draws the crossing lenses under the
 * cone on one of their four pixels (and its transposed pixel), not on all
 * four: the same crowded path of the cone's reference, which took most of
 * this test's time (tests/README.md, "Tiers", says how that was checked);
 * the plain build draws every pixel. */

static support_view box_view(int w, int h)
{
    return (support_view){.w = w, .h = h, .seed = 1, .threads = 2};
}

/* ---- the region under y = x^3 ---- */

static aa_scene *random_cubics(uint64_t seed);
static aa_scene *transposed(const aa_scene *src);

static aa_scene *cube_region(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 1.0 / 3.0, 0, 2.0 / 3.0, 0, 1, 1), AA_OK);
    assert_int_equal(aa_scene_line_to(s, 1, 0), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* integral over [a, b] of clamp(x^3 - c, 0, d - c) dx (0 <= a <= b <= 1). */
static ld cube_cell(ld a, ld b, ld c, ld d)
{
    ld xc = cbrtl(c), xd = cbrtl(d), sum = 0;
    ld lo = fmaxl(a, xc), hi = fminl(b, xd);
    if (lo < hi)
        sum += (hi * hi * hi * hi - lo * lo * lo * lo) / 4 - c * (hi - lo);
    lo = fmaxl(a, xd);
    if (lo < b)
        sum += (d - c) * (b - lo);
    return sum;
}

/* The box-filtered value of pixel (i, j) of the region at w x h. */
static double cube_pixel(int w, int h, int i, int j)
{
    ld a = (ld)i / w, b = (ld)(i + 1) / w, c = (ld)j / h, d = (ld)(j + 1) / h;
    return (double)(cube_cell(a, b, c, d) * w * h);
}

static double max_cube_error(const aa_image *im)
{
    double worst = 0.0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            worst = fmax(worst, fabs(aa_pixel(im, i, j)[0] - cube_pixel(im->w, im->h, i, j)));
    return worst;
}

static void test_cube_region(void **state)
{
    (void)state;
    aa_scene *s = cube_region();
    const int sizes[][2] = {{1, 1}, {8, 8}, {17, 5}, {64, 48}};
    for (int k = 0; k < 4; k++) {
        support_view v = box_view(sizes[k][0], sizes[k][1]);
        aa_image ref, bound, img;
        support_reference(s, &v, &ref, &bound, NULL);
        double e = max_cube_error(&ref);
        print_message("cube region %dx%d: reference off the closed form by %.3g\n", v.w, v.h, e);
        if (!(e <= AA_TRUTH_BOUND))
            fail_msg("reference %dx%d off the closed form by %g", v.w, v.h, e);
        for (int m = 0; m < 2; m++) {
            const char *method = m ? "area:integrator=bands" : "area";
            support_render_must(method, s, &v, &img, NULL);
            e = max_cube_error(&img);
            print_message("cube region %dx%d: %s off by %.3g\n", v.w, v.h, method, e);
            if (!(e <= 1e-12))
                fail_msg("%s %dx%d off the closed form by %g", method, v.w, v.h, e);
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        aa_image_free(&bound);
    }
    aa_scene_free(s);
}

/* point samples each centre: inside when 0 < x < 1 and y < x^3 (centres
 * within 1e-9 of the curve are skipped: either side is right there). */
static void test_cube_point(void **state)
{
    (void)state;
    aa_scene *s = cube_region();
    const int w = 61, h = 37;
    support_view v = box_view(w, h);
    aa_image img;
    support_render_must("point", s, &v, &img, NULL);
    int checked = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            ld x = (i + 0.5L) / w, y = (j + 0.5L) / h;
            if (fabsl(x * x * x - y) < 1e-9L)
                continue;
            double want = x * x * x > y ? 1.0 : 0.0;
            if (aa_pixel(&img, i, j)[0] != want)
                fail_msg("point (%d, %d): %g, the centre is %s", i, j, aa_pixel(&img, i, j)[0],
                         want ? "inside" : "outside");
            checked++;
        }
    assert_true(checked > w * h - 4);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* The peers take the cubic natively (FreeType's cubic, Cairo's curve_to,
 * stb_truetype's vcubic, AGG's curve4): each flattens it its own way and
 * keeps 8-bit coverage, so they are held to their usual accuracy (on crow's
 * parabolas their largest errors are 0.06 to 0.34 at 128x128): at most
 * 0.15 off the closed form in a pixel and 0.02 in RMSE; the chord in place
 * of the curve would be 0.3 off in RMSE. */
static void test_cube_peers(void **state)
{
    (void)state;
    aa_scene *s = cube_region();
    const char *peers[] = {"freetype", "cairo", "stb", "agg"};
    support_view v = box_view(32, 32);
    double e[4], r[4];
    for (int k = 0; k < 4; k++) {
        aa_image img;
        support_render_must(peers[k], s, &v, &img, NULL);
        e[k] = max_cube_error(&img);
        double sum = 0.0;
        for (int j = 0; j < v.h; j++)
            for (int i = 0; i < v.w; i++) {
                double d = aa_pixel(&img, i, j)[0] - cube_pixel(v.w, v.h, i, j);
                sum += d * d;
            }
        r[k] = sqrt(sum / (v.w * v.h));
        print_message("cube region 32x32: %s off by %.3g at most, RMSE %.3g\n", peers[k], e[k],
                      r[k]);
        aa_image_free(&img);
    }
    for (int k = 0; k < 4; k++)
        if (!(e[k] <= 0.15) || !(r[k] <= 0.02))
            fail_msg("%s off the closed form by %g (RMSE %g)", peers[k], e[k], r[k]);
    aa_scene_free(s);
}

/* ---- the arch: a turning point in y, then in x ---- */

static aa_scene *arch(int turned, double sc, double off)
{
    double p[8] = {0, 0, 0, 1, 1, 1, 1, 0};
    if (turned)
        for (int k = 0; k < 8; k += 2) {
            double t = p[k];
            p[k] = p[k + 1], p[k + 1] = t;
        }
    for (int k = 0; k < 8; k++)
        p[k] = off + sc * p[k];
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_EVENODD), AA_OK);
    assert_int_equal(aa_scene_move_to(s, p[0], p[1]), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, p[2], p[3], p[4], p[5], p[6], p[7]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_arch(void **state)
{
    (void)state;
    const double sc = 0.9, off = 0.05, want = 0.6 * sc * sc;
    for (int turned = 0; turned < 2; turned++) {
        aa_scene *s = arch(turned, sc, off);
        size_t np;
        aa_scene_pieces(s, &np);
        /* the arc splits at its turning point (t = 1/2) when it is in y */
        assert_int_equal(np, turned ? 2 : 3);
        support_view v = box_view(1, 1);
        aa_image ref, img;
        support_reference(s, &v, &ref, NULL, NULL);
        double e = fabs(ref.v[0] - want);
        print_message("arch%s 1x1: reference off 3/5 s^2 by %.3g\n", turned ? " turned" : "", e);
        if (!(e <= AA_TRUTH_BOUND))
            fail_msg("arch (turned %d): reference %.17g, want %.17g", turned, ref.v[0], want);
        for (int m = 0; m < 2; m++) {
            const char *method = m ? "area:integrator=bands" : "area";
            support_render_must(method, s, &v, &img, NULL);
            if (!(fabs(img.v[0] - want) <= 1e-13))
                fail_msg("arch (turned %d): %s %.17g, want %.17g", turned, method, img.v[0],
                         want);
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        /* at 9 x 7 the pixels sum to the same area */
        v = box_view(9, 7);
        support_reference(s, &v, &ref, NULL, NULL);
        support_render_must("area", s, &v, &img, NULL);
        double sr = 0, sa = 0;
        for (int k = 0; k < 9 * 7; k++)
            sr += ref.v[3 * k], sa += img.v[3 * k];
        if (!(fabs(sr / 63 - want) <= 1e-12) || !(fabs(sa / 63 - want) <= 1e-13))
            fail_msg("arch (turned %d) 9x7: mean %.17g (reference), %.17g (area), want %.17g",
                     turned, sr / 63, sa / 63, want);
        double d = support_max_diff(&ref, &img, NULL, NULL);
        if (!(d <= 2e-12))
            fail_msg("arch (turned %d) 9x7: area off the reference by %g", turned, d);
        aa_image_free(&ref);
        aa_image_free(&img);
        aa_scene_free(s);
    }
}

/* ---- a cubic that is secretly a quadratic ---- */

static void test_elevated_crow(void **state)
{
    (void)state;
    aa_scene *q = scenes_pattern("crow"), *c = scenes_elevated(q);
    size_t n;
    const aa_piece *pc = aa_scene_pieces(c, &n);
    size_t cubics = 0, quads = 0, ne;
    for (size_t k = 0; k < n; k++)
        cubics += pc[k].kind == AA_PIECE_CUBIC;
    const aa_edge *e = aa_scene_edges(q, &ne);
    for (size_t k = 0; k < ne; k++)
        quads += e[k].quad == 1;
    assert_true(quads > 64 && cubics >= quads);
    support_view v = box_view(48, 40);
    aa_image a, b;
    support_reference(q, &v, &a, NULL, NULL);
    support_reference(c, &v, &b, NULL, NULL);
    double d = support_max_diff(&a, &b, NULL, NULL);
    print_message("crow elevated 48x40: reference differs by %.3g\n", d);
    if (!(d <= 2 * AA_TRUTH_BOUND))
        fail_msg("crow as cubics: reference differs by %g", d);
    aa_image_free(&a);
    aa_image_free(&b);
    /* methods: exact ones to rounding, samplers but for samples within
     * rounding of an edge (none expected at these positions) */
    struct {
        const char *method;
        double tol;
    } m[] = {{"area", 1e-13},    {"area:integrator=bands", 1e-13}, {"point", 0.0},
             {"supersample", 0.0}, {"jitter", 0.0},                 {"adaptive:tag=1", 0.0}};
    for (size_t k = 0; k < sizeof m / sizeof *m; k++) {
        support_render_must(m[k].method, q, &v, &a, NULL);
        support_render_must(m[k].method, c, &v, &b, NULL);
        d = support_max_diff(&a, &b, NULL, NULL);
        print_message("crow elevated 48x40: %s differs by %.3g\n", m[k].method, d);
        if (!(d <= m[k].tol))
            fail_msg("crow as cubics: %s differs by %g (at most %g)", m[k].method, d, m[k].tol);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    /* the peers flatten cubics and parabolas differently: about as far
     * from the reference on either (RMSE within a third, plus 8-bit
     * rounding); FreeType's smooth rasterizer flattens a cubic by a
     * coarser test than a conic (measured: twice the RMSE on this view):
     * within 2.5 times there */
    const char *peers[] = {"freetype", "cairo", "stb", "agg"};
    const double factor[] = {2.5, 1.35, 1.35, 1.35};
    aa_image ref;
    support_reference(q, &v, &ref, NULL, NULL);
    for (int k = 0; k < 4; k++) {
        support_render_must(peers[k], q, &v, &a, NULL);
        support_render_must(peers[k], c, &v, &b, NULL);
        double ra = support_rmse(&a, &ref), rb = support_rmse(&b, &ref);
        print_message("crow 48x40: %s RMSE %.4g on parabolas, %.4g on the same as cubics\n",
                      peers[k], ra, rb);
        if (!(rb <= factor[k] * ra + 2.0 / 255))
            fail_msg("crow as cubics: %s RMSE %g, against %g as parabolas", peers[k], rb, ra);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    aa_image_free(&ref);
    aa_scene_free(q);
    aa_scene_free(c);
}

/* Every method of the table but the peers (their flattening differs, above),
 * under the box or the first filter it takes: crow as cubics gives crow's
 * image to rounding (samplers exactly, unless a sample falls within
 * rounding of an edge; conetable to its flattening). */
static void test_elevated_every_method(void **state)
{
    (void)state;
    aa_scene *q = scenes_pattern("crow"), *c = scenes_elevated(q);
    const char *peers[] = {"freetype", "cairo", "stb", "agg"};
    const char *filters[] = {"box", "tent:r=1", "gauss", "cone"};
    const void *const *table = aa_method_table();
    int tested = 0;
    for (size_t k = 0; table[k]; k++) {
        const char *name = ((const aa_info *)table[k])->name;
        int peer = 0;
        for (int p = 0; p < 4; p++)
            peer |= !strcmp(name, peers[p]);
        const char *filter = NULL;
        for (int f = 0; f < 4 && !filter; f++) {
            aa_filter fl;
            aa_spec spec;
            assert_int_equal(aa_filter_parse(filters[f], &fl), AA_OK);
            if (aa_method_parse(name, &fl, &spec) == AA_OK)
                filter = filters[f];
        }
        if (peer || !filter)
            continue;
        support_view v = box_view(24, 20);
        v.filter = filter;
        aa_image a, b;
        if (support_render_view(name, q, &v, &a, NULL) != AA_OK)
            continue; /* refuses crow itself */
        support_render_must(name, c, &v, &b, NULL);
        double d = support_max_diff(&a, &b, NULL, NULL);
        print_message("crow elevated 24x20 %s under %s: differs by %.3g\n", name, filter, d);
        /* conetable replaces arcs by chords to tol = 1e-3 px, steps counted
         * on each visible part: the two forms' parts and steps differ in
         * their last bits, and its image by a part of that (measured 2e-4,
         * falling with tol: 7e-6 at tol=1e-6) */
        double tol = !strcmp(name, "conetable") ? 1e-3 : 1e-12;
        if (!(d <= tol))
            fail_msg("crow as cubics: %s under %s differs by %g", name, filter, d);
        aa_image_free(&a);
        aa_image_free(&b);
        tested++;
    }
    assert_true(tested >= 10);
    aa_scene_free(q);
    aa_scene_free(c);
}

/* The scene mirrored in the diagonal (x and y swapped), finished. */
static int transposed_edge(aa_scene *s, const aa_edge *d)
{
    return d->quad == 2 ? aa_scene_cubic_to(s, d->cy, d->cx, d->c2y, d->c2x, d->y1, d->x1)
           : d->quad    ? aa_scene_quad_to(s, d->cy, d->cx, d->y1, d->x1)
                        : aa_scene_line_to(s, d->y1, d->x1);
}

static aa_scene *transposed(const aa_scene *src)
{
    return scenes_rebuild(src, 1, transposed_edge);
}

/* The Gaussian is symmetric in x and y: the reference of a scene of cubics
 * and that of the scene mirrored in the diagonal, mirrored back, agree
 * within their bounds.  The two take different paths (a piece of one is
 * split at turning points in the other's x; the fixed rule on panels takes
 * a cubic where its slope stays under 1 and no other piece meets it,
 * QAG the rest). */
static void test_gauss_transposed(void **state)
{
    (void)state;
    aa_scene *scenes[2] = {scenes_cubics(), random_cubics(11)};
    for (int k = 0; k < 2; k++) {
        aa_scene *t = transposed(scenes[k]);
        /* small: a pixel of the random scene has some 40 pieces in its
         * window, crossing each other, and takes 0.1 s under the Gaussian */
        support_view v = box_view(k ? 6 : 15, k ? 4 : 11), vt = box_view(k ? 4 : 11, k ? 6 : 15);
        v.filter = vt.filter = "gauss";
        aa_image a, ab, b, bb;
        support_reference(scenes[k], &v, &a, &ab, NULL);
        support_reference(t, &vt, &b, &bb, NULL);
        double worst = 0.0;
        for (int j = 0; j < v.h; j++)
            for (int i = 0; i < v.w; i++)
                for (int ch = 0; ch < 3; ch++) {
                    double e = fabs(aa_pixel(&a, i, j)[ch] - aa_pixel(&b, j, i)[ch]);
                    double bound = aa_pixel(&ab, i, j)[0] + aa_pixel(&bb, j, i)[0];
                    worst = fmax(worst, e);
                    if (!(e <= bound + 1e-13))
                        fail_msg("scene %d pixel (%d, %d): %.17g, transposed %.17g (bounds %g)",
                                 k, i, j, aa_pixel(&a, i, j)[ch], aa_pixel(&b, j, i)[ch], bound);
                }
        print_message("gauss, scene %d of cubics and its transpose: %.3g apart\n", k, worst);
        aa_image_free(&a);
        aa_image_free(&ab);
        aa_image_free(&b);
        aa_image_free(&bb);
        aa_scene_free(t);
        aa_scene_free(scenes[k]);
    }
}

/* ---- random scenes of cubics: reference against area ---- */

static aa_scene *random_cubics(uint64_t seed)
{
    aa_rng r;
    aa_rng_seed(&r, seed, 0, 0);
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    for (int l = 0; l < 2; l++) {
        aa_rgb c = {{aa_rng_uniform(&r), aa_rng_uniform(&r), aa_rng_uniform(&r)}};
        assert_int_equal(aa_scene_layer(s, c, l ? AA_FILL_EVENODD : AA_FILL_NONZERO), AA_OK);
        for (int p = 0; p < 2; p++) {
            assert_int_equal(aa_scene_move_to(s, 0.1 + 0.8 * aa_rng_uniform(&r),
                                              0.1 + 0.8 * aa_rng_uniform(&r)),
                             AA_OK);
            int arcs = 2 + (int)(3 * aa_rng_uniform(&r));
            for (int a = 0; a < arcs; a++) {
                double v[6];
                for (int k = 0; k < 6; k++)
                    v[k] = 0.05 + 0.9 * aa_rng_uniform(&r);
                assert_int_equal(aa_scene_cubic_to(s, v[0], v[1], v[2], v[3], v[4], v[5]),
                                 AA_OK);
            }
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

static void test_random_reference_vs_area(void **state)
{
    (void)state;
    double worst = 0.0;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        aa_scene *s = random_cubics(seed);
        support_view v = box_view(24, 20);
        aa_image ref, bound, img;
        support_reference(s, &v, &ref, &bound, NULL);
        for (int m = 0; m < 2; m++) {
            const char *method = m ? "area:integrator=bands" : "area";
            support_render_must(method, s, &v, &img, NULL);
            for (int j = 0; j < v.h; j++)
                for (int i = 0; i < v.w; i++)
                    for (int ch = 0; ch < 3; ch++) {
                        double e = fabs(aa_pixel(&img, i, j)[ch] - aa_pixel(&ref, i, j)[ch]);
                        double b = aa_pixel(&bound, i, j)[0];
                        worst = fmax(worst, e);
                        if (!(e <= b + 1e-12))
                            fail_msg("seed %d %s pixel (%d, %d) channel %d: %.17g, reference "
                                     "%.17g (bound %g)",
                                     (int)seed, method, i, j, ch, aa_pixel(&img, i, j)[ch],
                                     aa_pixel(&ref, i, j)[ch], b);
                    }
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_scene_free(s);
    }
    print_message("random cubic scenes 24x20: area within %.3g of the reference\n", worst);
}

/* The reference under every filter: crow's parabolas as cubics take other
 * paths (no Gaussian panels, QAG with the crossings of a cubic; for the
 * cone the heights where a cubic meets the circle, of degree 6) and must
 * give the same image to the bound. */
static void test_elevated_filters(void **state)
{
    (void)state;
    aa_scene *q = scenes_pattern("crow"), *c = scenes_elevated(q);
    const char *filters[] = {"tent:r=1", "tent:r=0.5", "gauss", "cone"};
    for (int k = 0; k < 4; k++) {
        support_view v = box_view(20, 16);
        v.filter = filters[k];
        aa_image a, b;
        support_reference(q, &v, &a, NULL, NULL);
        support_reference(c, &v, &b, NULL, NULL);
        double d = support_max_diff(&a, &b, NULL, NULL);
        print_message("crow elevated 20x16 %s: reference differs by %.3g\n", filters[k], d);
        if (!(d <= 2 * AA_TRUTH_BOUND))
            fail_msg("crow as cubics under %s: reference differs by %g", filters[k], d);
        aa_image_free(&a);
        aa_image_free(&b);
    }
    /* crowtiler:area=exact integrates the area right of each piece under
     * Crow's pyramid by Gauss-Legendre, exact for parabolas (4 points) and
     * cubics (6 points): the same image to rounding */
    support_view v = box_view(20, 16);
    v.filter = "tent:r=1";
    aa_image a, b;
    const char *tiler = "crowtiler:area=exact,hidden=scan";
    support_render_must(tiler, q, &v, &a, NULL);
    support_render_must(tiler, c, &v, &b, NULL);
    double d = support_max_diff(&a, &b, NULL, NULL);
    print_message("crow elevated 20x16: %s differs by %.3g\n", tiler, d);
    if (!(d <= 1e-12))
        fail_msg("crow as cubics: %s differs by %g", tiler, d);
    aa_image_free(&a);
    aa_image_free(&b);
    aa_scene_free(q);
    aa_scene_free(c);
}

/* A crowded window: 48 thin lenses of two cubics each, all crossing near
 * the centre, so that a pixel's window holds more pieces than the
 * reference sums as a whole and it takes them one at a time (truth_crowd.c:
 * a sweep with the pieces in order along x, meetings between neighbours,
 * those of a cubic and an arc from a polynomial of degree 6, of two cubics
 * by bisection and Newton): against `area` (its crowded clusters tested by
 * neighbours) within the reference's bound. */
static void test_crowded_cubics(void **state)
{
    (void)state;
    enum { N = 48 };
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < N; k++) {
        double th = 3.14159 * (k + 0.37) / N, ux = cos(th), uy = sin(th);
        double nx = -uy, ny = ux, L = 0.42, w = 0.004 + 0.0001 * k;
        double cx = 0.5 + 0.01 * sin(3.0 * k), cy = 0.5 + 0.01 * cos(5.0 * k);
        double px = cx - L * ux, py = cy - L * uy, qx = cx + L * ux, qy = cy + L * uy;
        double dx = (qx - px) / 3.0, dy = (qy - py) / 3.0;
        assert_int_equal(aa_scene_move_to(s, px, py), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, px + dx + w * nx, py + dy + w * ny,
                                           px + 2 * dx + 2 * w * nx, py + 2 * dy + 2 * w * ny,
                                           qx, qy),
                         AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, qx - dx - 2 * w * nx, qy - dy - 2 * w * ny,
                                           qx - 2 * dx - w * nx, qy - 2 * dy - w * ny, px, py),
                         AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    const int sizes[][2] = {{3, 3}, {7, 5}};
    for (int z = 0; z < 2; z++) {
        support_view v = box_view(sizes[z][0], sizes[z][1]);
        aa_image ref, bound, img;
        aa_truth_stats ts;
        support_reference(s, &v, &ref, &bound, &ts);
        assert_true(ts.crowded > 0);
        support_render_must("area", s, &v, &img, NULL);
        double worst = 0.0;
        for (int j = 0; j < v.h; j++)
            for (int i = 0; i < v.w; i++) {
                double e = fabs(aa_pixel(&img, i, j)[0] - aa_pixel(&ref, i, j)[0]);
                worst = fmax(worst, e);
                if (!(e <= aa_pixel(&bound, i, j)[0] + 1e-12))
                    fail_msg("%dx%d pixel (%d, %d): area %.17g, reference %.17g (bound %g)",
                             v.w, v.h, i, j, aa_pixel(&img, i, j)[0], aa_pixel(&ref, i, j)[0],
                             aa_pixel(&bound, i, j)[0]);
            }
        print_message("48 crossing cubic lenses %dx%d: %zu crowded pixels, area within %.3g of "
                      "the reference\n",
                      v.w, v.h, ts.crowded, worst);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_image_free(&img);
    }
    /* under the cone (radial: its crowded path adds the crossings of the
     * circle, degree 6 for a cubic, and each piece's closest approach to
     * the centre, degree 5), against the transposed scene: the cone is
     * symmetric in x and y */
    aa_scene *t = transposed(s);
    support_view v = box_view(2, 2);
    v.filter = "cone";
    aa_image a, ab, b, bb;
    aa_truth_stats sa, sb;
    /* the subset (SAN_SUBSET): pixel (1, 0) alone against the transposed
     * scene's (0, 1), each a 1x1 view of its own (support_scene_part) */
    int n = SAN_SUBSET ? 1 : 2, i0 = SAN_SUBSET;
    if (SAN_SUBSET) {
        aa_scene *ps = support_scene_part(s, 2, 2, 1, 0, 1, 1);
        aa_scene *pt = support_scene_part(t, 2, 2, 0, 1, 1, 1);
        v.w = v.h = 1;
        support_reference(ps, &v, &a, &ab, &sa);
        support_reference(pt, &v, &b, &bb, &sb);
        aa_scene_free(ps);
        aa_scene_free(pt);
    } else {
        support_reference(s, &v, &a, &ab, &sa);
        support_reference(t, &v, &b, &bb, &sb);
    }
    assert_true(sa.crowded > 0 && sb.crowded > 0);
    double worst = 0.0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double e = fabs(aa_pixel(&a, i, j)[0] - aa_pixel(&b, j, i)[0]);
            double bound = aa_pixel(&ab, i, j)[0] + aa_pixel(&bb, j, i)[0];
            worst = fmax(worst, e);
            if (!(e <= bound + 1e-13))
                fail_msg("cone pixel (%d, %d): %.17g, transposed %.17g (bounds %g)", i + i0, j,
                         aa_pixel(&a, i, j)[0], aa_pixel(&b, j, i)[0], bound);
        }
    print_message("48 crossing cubic lenses %dx%d under the cone: %zu crowded pixels, %.3g from "
                  "the transposed scene's\n",
                  n, n, sa.crowded, worst);
    aa_image_free(&a);
    aa_image_free(&ab);
    aa_image_free(&b);
    aa_image_free(&bb);
    aa_scene_free(t);
    aa_scene_free(s);
}

/* ---- crossings ---- */

/* The Bernstein form of one coordinate, in long double. */
static ld bern(const double *c, ld t)
{
    ld u = 1 - t;
    return u * u * u * c[0] + 3 * u * u * t * c[1] + 3 * u * t * t * c[2] + t * t * t * c[3];
}

/* A piece's control points, top to bottom, per coordinate. */
static void controls(const aa_piece *p, double x[4], double y[4])
{
    x[0] = p->x0, x[1] = p->cx, x[2] = p->c2x, x[3] = p->x1;
    y[0] = p->y0, y[1] = p->cy, y[2] = p->c2y, y[3] = p->y1;
}

/* The parameter where y(t) = y by bisection (y increasing on the piece):
 * 200 halvings, less those that would repeat the last one exactly (once a
 * halving leaves the bracket as it was, every later one takes the same
 * midpoint to the same side: the answer is the same, in a third of the
 * time where the bracket closes on adjacent long doubles after 64). */
static ld bisect_y(const double *cy, ld y)
{
    ld a = 0, b = 1;
    for (int it = 0; it < 200; it++) {
        ld m = (a + b) / 2, a0 = a, b0 = b;
        if (bern(cy, m) < y)
            a = m;
        else
            b = m;
        if (a == a0 && b == b0)
            break;
    }
    return (a + b) / 2;
}

static void test_pieces_and_crossings(void **state)
{
    (void)state;
    double worst_x = 0, worst_meet = 0;
    int meets = 0;
    for (uint64_t seed = 1; seed <= 40; seed++) {
        aa_rng r;
        aa_rng_seed(&r, seed, 1, 0);
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
        double v[8];
        for (int k = 0; k < 8; k++)
            v[k] = 100.0 * aa_rng_uniform(&r);
        assert_int_equal(aa_scene_move_to(s, v[0], v[1]), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, v[2], v[3], v[4], v[5], v[6], v[7]), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        /* the turning points in y: where 3 (P1 - P0) (1-t)^2 + 6 (P2 - P1)
         * t (1-t) + 3 (P3 - P2) t^2 vanishes, counted by sign changes on a
         * fine grid */
        int turns = 0;
        double prev = v[3] - v[1];
        for (int k = 1; k <= 100000; k++) {
            ld t = k / 100000.0L, u = 1 - t;
            double d = (double)((v[3] - v[1]) * u * u + 2 * (v[5] - v[3]) * t * u +
                                (v[7] - v[5]) * t * t);
            if ((d < 0) != (prev < 0) && d != 0)
                turns++;
            prev = d != 0 ? d : prev;
        }
        size_t np;
        const aa_piece *pc = aa_scene_pieces(s, &np);
        size_t cubic = 0;
        for (size_t k = 0; k < np; k++)
            cubic += pc[k].kind == AA_PIECE_CUBIC;
        assert_int_equal(cubic, (size_t)turns + 1);
        for (size_t k = 0; k < np; k++) {
            const aa_piece *p = &pc[k];
            if (p->kind != AA_PIECE_CUBIC)
                continue;
            double cx[4], cy[4];
            controls(p, cx, cy);
            /* y-monotone: increasing along t on a fine grid (to rounding) */
            ld last = bern(cy, 0);
            for (int q = 1; q <= 1000; q++) {
                ld y = bern(cy, q / 1000.0L);
                if (!(y >= last - 1e-12L))
                    fail_msg("seed %d piece %zu: y falls from %.17Lg to %.17Lg", (int)seed, k,
                             last, y);
                last = y;
            }
            /* x at y against bisection */
            for (int q = 1; q < 50; q++) {
                double y = p->y0 + (p->y1 - p->y0) * q / 50.0;
                ld x = bern(cx, bisect_y(cy, y));
                double e = fabs((double)(aa_piece_x_at(p, y) - x));
                worst_x = fmax(worst_x, e);
                if (!(e <= 1e-12))
                    fail_msg("seed %d: x at y = %.17g is %.17g, bisection %.17Lg", (int)seed, y,
                             aa_piece_x_at(p, y), x);
            }
            /* the vertical line through the middle of its x extent: every
             * sign change of x(t) - X on a grid is a meeting reported */
            double X = 0.5 * (p->xmin + p->xmax), ys[3];
            int n = aa_piece_meet_x(p, X, ys), found = 0;
            ld t0 = 0, f0 = bern(cx, 0) - X;
            for (int q = 1; q <= 20000; q++) {
                ld t1 = q / 20000.0L, f1 = bern(cx, t1) - X;
                if ((f0 < 0) != (f1 < 0)) {
                    ld a = t0, b = t1;
                    for (int it = 0; it < 200; it++) {
                        ld m = (a + b) / 2;
                        if (((bern(cx, m) - X) < 0) == (f0 < 0))
                            a = m;
                        else
                            b = m;
                    }
                    ld y = bern(cy, (a + b) / 2);
                    int hit = 0;
                    for (int j = 0; j < n; j++)
                        hit |= fabsl(ys[j] - y) <= 1e-9L;
                    if (!hit)
                        fail_msg("seed %d: x = %g met at y = %.17Lg, not reported", (int)seed, X,
                                 y);
                    found++;
                }
                t0 = t1, f0 = f1;
            }
            assert_int_equal(n, found);
        }
        /* the crossings of a line: sorted, each an x of a piece there */
        aa_crossing cr[8];
        double y = 0.5 * (v[1] + v[7]) + 0.123;
        size_t nc = aa_scene_crossings(s, y, cr, 8);
        for (size_t k = 1; k < nc && nc <= 8; k++)
            assert_true(cr[k - 1].x <= cr[k].x);
        assert_int_equal(nc % 2, 0); /* a closed path */
        aa_scene_free(s);
    }
    /* two pieces that cross: the meeting heights against bisection on the
     * difference of their x at y (each x by bisection in long double) */
    for (uint64_t seed = 1; seed <= 30; seed++) {
        aa_rng r;
        aa_rng_seed(&r, seed, 2, 0);
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
        for (int e = 0; e < 2; e++) {
            /* y increasing controls: one monotone piece each */
            double y[4] = {0, 0, 0, 0};
            for (int k = 1; k < 4; k++)
                y[k] = y[k - 1] + 10.0 * aa_rng_uniform(&r);
            double x[4];
            for (int k = 0; k < 4; k++)
                x[k] = 30.0 * aa_rng_uniform(&r);
            assert_int_equal(aa_scene_move_to(s, x[0], y[0]), AA_OK);
            assert_int_equal(aa_scene_cubic_to(s, x[1], y[1], x[2], y[2], x[3], y[3]), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
        assert_int_equal(aa_scene_finish(s), AA_OK);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(s, &np);
        const aa_piece *p = NULL, *q = NULL;
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_CUBIC)
                continue;
            if (!p)
                p = &pc[k];
            else if (!q)
                q = &pc[k];
        }
        assert_non_null(p);
        assert_non_null(q);
        double lo = fmax(p->y0, q->y0), hi = fmin(p->y1, q->y1), ys[16];
        if (!(lo < hi)) {
            aa_scene_free(s);
            continue;
        }
        int n = aa_piece_meet(p, q, lo, hi, ys, 16), found = 0;
        double px[4], py[4], qx[4], qy[4];
        controls(p, px, py);
        controls(q, qx, qy);
        const int N = 4000;
        ld y0 = lo, d0 = bern(px, bisect_y(py, y0)) - bern(qx, bisect_y(qy, y0));
        for (int k = 1; k <= N; k++) {
            ld y1 = lo + (hi - lo) * (ld)k / N;
            ld d1 = bern(px, bisect_y(py, y1)) - bern(qx, bisect_y(qy, y1));
            if (d1 != 0 && (d0 < 0) != (d1 < 0) && k < N) {
                ld a = y0, b = y1;
                for (int it = 0; it < 80; it++) {
                    ld m = (a + b) / 2;
                    ld dm = bern(px, bisect_y(py, m)) - bern(qx, bisect_y(qy, m));
                    if ((dm < 0) == (d0 < 0))
                        a = m;
                    else
                        b = m;
                }
                ld at = (a + b) / 2;
                double best = INFINITY;
                for (int j = 0; j < n; j++)
                    best = fmin(best, (double)fabsl(ys[j] - at));
                if (!(best <= 1e-12))
                    fail_msg("seed %d: the pieces cross at y = %.17Lg, not reported (%d found)",
                             (int)seed, at, n);
                worst_meet = fmax(worst_meet, best);
                found++;
            }
            y0 = y1, d0 = d1;
        }
        meets += found;
        assert_true(n >= found);
        aa_scene_free(s);
    }
    assert_true(meets > 5);
    print_message("cubic pieces: x at y within %.3g of bisection; %d crossings of two cubics, "
                  "within %.3g\n",
                  worst_x, meets, worst_meet);
}

/* ---- export ---- */

static void test_export(void **state)
{
    (void)state;
    aa_scene *s = cube_region(), *placed = aa_scene_place(s, 30, 30, 0, 0, 0);
    assert_non_null(placed);
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(aa_scene_svg(placed, 30, 30, AA_SVG_COLOURS, NULL, &text, &len), AA_OK);
    char want[256];
    snprintf(want, sizeof want, "M %.17g %.17g C %.17g %.17g %.17g %.17g %.17g %.17g", 0.0, 0.0,
             10.0, 0.0, 20.0, 0.0, 30.0, 30.0);
    if (!strstr(text, want))
        fail_msg("the SVG has no \"%s\":\n%s", want, text);
    free(text);
    aa_scene_free(placed);
    aa_scene_free(s);
}

/* ---- building ---- */

static void test_building(void **state)
{
    (void)state;
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    /* before move_to, and non-finite points, are refused */
    assert_int_equal(aa_scene_cubic_to(s, 0, 0, 1, 1, 2, 2), AA_EFAIL);
    assert_int_equal(aa_scene_move_to(s, 0, 0), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, NAN, 0, 1, 1, 2, 2), AA_EINVAL);
    assert_int_equal(aa_scene_cubic_to(s, 0, 0, 1, INFINITY, 2, 2), AA_EINVAL);
    /* a cubic of one point adds nothing */
    assert_int_equal(aa_scene_cubic_to(s, 0, 0, 0, 0, 0, 0), AA_OK);
    size_t ne;
    aa_scene_edges(s, &ne);
    assert_int_equal(ne, 0);
    assert_int_equal(aa_scene_cubic_to(s, 1, 0, 1, 1, 0, 1), AA_OK);
    const aa_edge *e = aa_scene_edges(s, &ne);
    assert_int_equal(ne, 1);
    assert_int_equal(e[0].quad, 2);
    assert_true(e[0].cx == 1 && e[0].cy == 0 && e[0].c2x == 1 && e[0].c2y == 1);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0, 0, 1, 1, 2, 2), AA_EFAIL);
    /* bounds: the curve's, not the control polygon's: x(t) = 3t(1-t) has
     * its maximum 3/4 at t = 1/2 */
    double x0, y0, x1, y1;
    assert_int_equal(aa_scene_bounds(s, &x0, &y0, &x1, &y1), 1);
    assert_true(fabs(x1 - 0.75) < 1e-15 && x0 == 0 && y0 == 0 && y1 == 1);
    aa_scene_free(s);
    /* clipping to the unit square reads the curve too: x(t) = 0.5 + 3 t (1-t)
     * (c - 0.5) peaks at 0.5 + 0.75 (c - 0.5), inside for c = 1.1 (0.95)
     * though its controls are outside, outside for c = 1.3 (1.1): a frame
     * layer then */
    const double cs[2] = {1.1, 1.3};
    for (int k = 0; k < 2; k++) {
        s = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
        assert_int_equal(aa_scene_move_to(s, 0.5, 0.1), AA_OK);
        assert_int_equal(aa_scene_cubic_to(s, cs[k], 0.3, cs[k], 0.7, 0.5, 0.9), AA_OK);
        assert_int_equal(aa_scene_clip_unit(s), AA_OK);
        assert_int_equal(aa_scene_finish(s), AA_OK);
        assert_int_equal(aa_scene_layer_count(s), k ? 2 : 1);
        /* and the point query: inside at (0.9, 0.5) only when c = 1.3
         * would reach it, clipped away then by the frame (x > 1 only) */
        aa_scene_bounds(s, &x0, &y0, &x1, &y1);
        if (!k)
            assert_true(fabs(x1 - (0.5 + 0.75 * (cs[k] - 0.5))) < 1e-15);
        assert_true(aa_scene_colour_at(s, 0.9, 0.5).c[0] == 1.0);
        assert_true(aa_scene_colour_at(s, 0.97, 0.5).c[0] == (k ? 1.0 : 0.0));
        aa_scene_free(s);
    }
}

/* The root of f(t) = c + t (k1 + t (k2 + t k3)) in [0, 1] by bisection in
 * long double, f increasing there (the oracle of test_cubic_near). */
static long double bisect_cubic(double c, double k1, double k2, double k3)
{
    long double lo = 0.0L, hi = 1.0L;
    for (int it = 0; it < 200 && hi - lo > 0.0L; it++) {
        long double m = 0.5L * (lo + hi);
        if (!(m > lo && m < hi))
            break;
        long double f = c + m * (k1 + m * (k2 + m * (long double)k3));
        if (f < 0.0L)
            lo = m;
        else
            hi = m;
    }
    return 0.5L * (lo + hi);
}

/* area_cubic_near from a guess at the cubic's inflection: f(t) = t^3 -
 * 1.5 t^2 + t + c has f'' = 0 at t = 1/2 and f' >= 1/4 on [0, 1], so
 * every root is simple and Newton's first step from 1/2 is f(1/2) / (1/4).
 * Its error after that step is |f''(u)| s^2 / (2 f'), u between the step's
 * ends, not 0: a stopping test that reads f'' at the guess alone (zero
 * there) took the first step as final, 4e-6 from the root when the step
 * is 0.01.  Steps of 1e-1 to 1e-6 either way; the root within 2^-49 of
 * the bracket [0, 1] (the function's promise, 2^-54, plus f's rounding
 * in double near the root, a few ulps of its terms' size 1/4, over
 * f' >= 1/4: 2^-52 at 4 ulps; 2^-49 leaves room for another rounding of
 * the sum, far below the old test's 4e-6 at a step of 0.01). */
static void test_cubic_near(void **state)
{
    (void)state;
    const double steps[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
    double worst = 0.0;
    for (int i = 0; i < 6; i++)
        for (int sg = -1; sg <= 1; sg += 2) {
            /* f(1/2) = c + 1/4, so a first step of sg steps[i] */
            double c = -0.25 + sg * 0.25 * steps[i];
            double t = area_cubic_near(c, 1.0, -1.5, 1.0, 0.0, 1.0, 0.5);
            long double r = bisect_cubic(c, 1.0, -1.5, 1.0);
            double e = (double)fabsl((long double)t - r);
            if (e > worst)
                worst = e;
            if (e > 0x1p-49)
                print_message("step %g: root %.17g, bisection %.20Lg, %.3g apart\n",
                              sg * steps[i], t, r, e);
            assert_true(e <= 0x1p-49);
        }
    print_message("area_cubic_near from the inflection: within %.3g of the root\n", worst);
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_building),
        cmocka_unit_test(test_cube_region),
        cmocka_unit_test(test_cube_point),
        cmocka_unit_test(test_cube_peers),
        cmocka_unit_test(test_arch),
        cmocka_unit_test(test_elevated_crow),
        cmocka_unit_test(test_elevated_filters),
        cmocka_unit_test(test_elevated_every_method),
        cmocka_unit_test(test_gauss_transposed),
        cmocka_unit_test(test_random_reference_vs_area),
        cmocka_unit_test(test_crowded_cubics),
        cmocka_unit_test(test_pieces_and_crossings),
        cmocka_unit_test(test_export),
        cmocka_unit_test(test_cubic_near),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
