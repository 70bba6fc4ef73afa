/*
 * test_figures_papers.c: the seed papers' figures and claims (figures.c,
 * eye.c, calibration.c) and the suites (suite.c, the run's pairing).
 *
 *  - The tables: every figure's row and every claim's row names specs that
 *    parse (its pattern, filters, methods, encodings, timed pairs), lists
 *    of one length and a measure; a row past the end is refused.
 *  - The figures: every title dates Crow's thesis 1976 (never 1977); no
 *    two figures are the same picture (aa_figure_key); the figures Crow,
 *    Catmull and Feibush et al. made with a method of their own are made
 *    with it (crowtable under Crow's pyramids for figs. 2.13-2.14, crowtiler
 *    for the tiler's figs. 3.14-3.17 and 3.19, area for Catmull's fig. 1,
 *    conetable at 512 x 512 for Feibush's fig. 4d).
 *  - Catmull's pixel as he draws it: the caption's exact value and his
 *    integrater's are his split (0, 1/4, 1/2), and the 2 x 2 grid, whose
 *    samples miss every edge, gives it too: known answers from the
 *    rectangles' areas, worked out by hand.
 *  - The eye: a white pixel on black seen through a Gaussian of s pixels
 *    has, at its own centre, (erf(1/(2 s sqrt 2)))^2 (the integral of the
 *    normal density over the pixel, squared), a uniform image stays
 *    uniform away from its border; the eye's view of the scene is within
 *    1e-3 of the exact reference under gauss:s=2; and the eye of the
 *    scene's exact box values differs from it by no more than the box's
 *    blur (small), while a wrong picture differs by far more.
 *  - Crow's calibration: a display whose intensity is linear in the stored
 *    value (g = 1) shows the least fringes (the stored values' local means
 *    are the scene's, and v^g with g > 1 darkens every mixed dot, with g < 1
 *    brightens it: Jensen's inequality), so the least lies near 1 and the
 *    fringes grow from g = 1 to g = 2 to g = 4.
 *  - Feibush et al.'s texture filter (feibushtex): on a quadrilateral of one
 *    colour it is that colour times the edge filter's share (conetable on
 *    the quadrilateral in white); on two stripes, a pixel inside a stripe is
 *    its colour exactly and one on their boundary about half of each.
 *  - The suites: every method family is in `quick` and `default`, each
 *    under a filter it accepts; `full` holds every family under every
 *    filter it accepts and the zone plate; a run of a suite leaves out the
 *    pairs a method refuses, in one line, and runs them when the method and
 *    the filter are both named.  The command under test is $AABENCH.
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
#include <unistd.h>

#include <cmocka.h>

static char dir[] = "/tmp/aabench-figp-XXXXXX";
static char output[65536];

static void test_tables(void **state)
{
    (void)state;
    assert_true(aa_figure_count() > 0);
    for (size_t k = 0; k < aa_figure_count(); k++)
        if (aa_figure_check(k) != AA_OK)
            fail_msg("%s", aa_last_error());
    assert_int_equal(aa_figure_check(aa_figure_count()), AA_EINVAL);
    assert_true(aa_claim_count() > 0);
    for (size_t k = 0; k < aa_claim_count(); k++)
        if (aa_claim_check(k) != AA_OK)
            fail_msg("%s", aa_last_error());
    assert_int_equal(aa_claim_check(aa_claim_count()), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "no claim"));
}

static void test_titles_1976(void **state)
{
    (void)state;
    for (size_t k = 0; k < aa_figure_count(); k++) {
        const char *t = aa_figure_title(k);
        assert_non_null(t);
        assert_null(strstr(t, "1977"));
        if (!strncmp(aa_figure_name(k), "fig-crow-", 9))
            assert_true(strstr(t, "1976") != NULL || strstr(t, "Crow's appendix") != NULL);
    }
    assert_null(aa_figure_title(aa_figure_count()));
}

static void test_figures_differ(void **state)
{
    (void)state;
    size_t n = aa_figure_count();
    char(*key)[2048] = calloc(n, sizeof *key);
    assert_non_null(key);
    for (size_t k = 0; k < n; k++)
        assert_int_equal(aa_figure_key(k, key[k], sizeof key[k]), 0);
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
            if (!strcmp(key[a], key[b]))
                fail_msg("%s and %s are the same picture", aa_figure_name(a), aa_figure_name(b));
    free(key);
}

/* The key of a named figure. */
static const char *key_of(const char *name, char *buf, size_t len)
{
    int k = aa_figure_find(name);
    assert_true(k >= 0);
    assert_int_equal(aa_figure_key((size_t)k, buf, len), 0);
    return buf;
}

static void test_papers_methods(void **state)
{
    (void)state;
    char buf[2048];
    assert_non_null(strstr(key_of("fig-crow-2.13", buf, sizeof buf),
                           "method crowtable tent:r=0.5"));
    assert_non_null(strstr(key_of("fig-crow-2.14", buf, sizeof buf), "method crowtable tent:r=1"));
    static const char *const tiler[] = {"fig-crow-3.14", "fig-crow-3.15", "fig-crow-3.16",
                                        "fig-crow-3.17", "fig-crow-3.19"};
    for (int k = 0; k < 5; k++) {
        key_of(tiler[k], buf, sizeof buf);
        assert_non_null(strstr(buf, "method crowtiler tent:r=1"));
        assert_null(strstr(buf, "method area"));
    }
    /* fig. 3.17: the three tilers; fig. 3.18 is not fig. 2.10 again */
    key_of("fig-crow-3.17", buf, sizeof buf);
    assert_true(!strncmp(buf, "slivers ", 8));
    assert_non_null(strstr(buf, "down2 point"));
    assert_non_null(strstr(key_of("fig-feibush-4d", buf, sizeof buf), "method feibushtex"));
    assert_non_null(strstr(buf, "method conetable"));
    assert_non_null(strstr(buf, "512x512 gauss:s=1"));
    assert_non_null(strstr(key_of("fig-catmull-1", buf, sizeof buf), "method area"));
    /* the colour maps of figs. A.1-A.3: shown v^2, v, v^4 */
    assert_non_null(strstr(key_of("fig-crow-A.1", buf, sizeof buf), "map crowtable"));
    assert_non_null(strstr(buf, " 2"));
    assert_non_null(strstr(key_of("fig-crow-A.3", buf, sizeof buf), "map crowtable"));
    assert_non_null(strstr(key_of("fig-crow-A.4", buf, sizeof buf), "calibration"));
}

static char *slurp(const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    static char buf[65536];
    return support_read_file(path, buf, sizeof buf, NULL);
}

/* The rgb line of panel p (1-based) in a caption. */
static void caption_rgb(const char *text, int p, double rgb[3])
{
    const char *s = support_caption_field(text, p, "rgb: ");
    assert_int_equal(sscanf(s, "%lf %lf %lf", &rgb[0], &rgb[1], &rgb[2]), 3);
}

static void test_catmull_split(void **state)
{
    (void)state;
    int k = aa_figure_find("fig-catmull-1");
    aa_figure_result r;
    assert_int_equal(aa_figure_make((size_t)k, dir, NULL, 1, &r), 0);
    const char *cap = slurp("fig-catmull-1.txt");
    assert_non_null(strstr(cap, "claim: \"The correct integration would be 25% green"));
    double ref[3], ss2[3], area[3];
    caption_rgb(cap, 5, ref);  /* the exact reference */
    caption_rgb(cap, 1, ss2);  /* supersample:n=2 */
    caption_rgb(cap, 4, area); /* Catmull's integrater */
    /* Catmull's split: green [0, 1/2]^2 is 1/4, blue [0, 1] x [1/2, 1] is
     * 1/2, the red behind them none */
    assert_true(fabs(ref[0]) < 1e-6);
    assert_true(fabs(ref[1] - 0.25) < 1e-6);
    assert_true(fabs(ref[2] - 0.5) < 1e-6);
    for (int c = 0; c < 3; c++)
        assert_true(fabs(area[c] - ref[c]) < 1e-6);
    assert_true(r.panel[3].rmse < 1e-12);
    /* the 2 x 2 grid's samples (1/4, 1/4) green, (3/4, 1/4) black, (1/4,
     * 3/4) and (3/4, 3/4) blue: the split exactly */
    assert_true(ss2[0] == 0 && fabs(ss2[1] - 0.25) < 1e-12 && fabs(ss2[2] - 0.5) < 1e-12);
}

static void test_eye(void **state)
{
    (void)state;
    aa_image im, out;
    const int n = 64;
    for (int s10 = 5; s10 <= 30; s10 += 5) {
        double s = s10 / 10.0;
        assert_int_equal(aa_image_alloc(&im, n, n, 3), 0);
        memset(im.v, 0, sizeof(double) * 3 * n * n);
        aa_pixel(&im, n / 2, n / 2)[1] = 1;
        assert_int_equal(aa_eye_blur(&im, s, &out), 0);
        double a = erf(1.0 / (2 * s * M_SQRT2));
        assert_true(fabs(aa_pixel(&out, n / 2, n / 2)[1] - a * a) < 1e-9);
        assert_true(aa_pixel(&out, n / 2, n / 2)[0] == 0);
        aa_image_free(&out);
        for (size_t k = 0; k < (size_t)3 * n * n; k++)
            im.v[k] = 0.3;
        assert_int_equal(aa_eye_blur(&im, s, &out), 0);
        assert_true(fabs(aa_pixel(&out, n / 2, n / 3)[2] - 0.3) < 1e-12);
        /* at the border, half the eye sees the black outside */
        assert_true(fabs(aa_pixel(&out, 0, n / 2)[2] - 0.3) > 0.03);
        aa_image_free(&out);
        aa_image_free(&im);
    }
    assert_int_equal(aa_eye_blur(&im, 0, &out), AA_EINVAL);
}

/* The reference (aa_reference) of crow at 64 x 64 under `filter`, the
 * pattern into *p. */
static void crow_reference_64(const char *filter, aa_spec *p, aa_image *out)
{
    aa_view v;
    memset(&v, 0, sizeof v);
    assert_int_equal(aa_pattern_parse("crow", p), 0);
    v.pattern = *p;
    v.w = v.h = 64;
    assert_int_equal(aa_filter_parse(filter, &v.filter), 0);
    assert_int_equal(aa_reference(&v, NULL, 2, out, NULL, NULL), 0);
}

/* The eye's view of crow at 64 x 64 (aa_eye_truth, s = AA_EYE_S = 2):
 * both tests below read the same one, so it is computed once and freed at
 * the end of main. */
static aa_image crow_eye;

static const aa_image *crow_eye_64(const aa_spec *p)
{
    if (!crow_eye.v)
        assert_int_equal(aa_eye_truth(p, 64, 64, 0, 0, 0, AA_EYE_S, NULL, 2, &crow_eye), 0);
    return &crow_eye;
}

/* The eye's view of the scene (fine box cells seen through the Gaussian)
 * against the exact reference under gauss:s=2 (truth.c's own path). */
static void test_eye_truth(void **state)
{
    (void)state;
    aa_spec p;
    aa_image exact;
    crow_reference_64("gauss:s=2", &p, &exact);
    assert_true(AA_EYE_S == 2.0); /* the eye's s is the reference's gauss:s=2 */
    assert_true(support_max_diff(&exact, crow_eye_64(&p), NULL, NULL) < 1e-3);
    aa_image_free(&exact);
}

static void test_eye_of_exact(void **state)
{
    (void)state;
    aa_spec p;
    aa_image box;
    double e;
    crow_reference_64("box", &p, &box);
    const aa_image *truth = crow_eye_64(&p);
    assert_int_equal(aa_eye_rmse(&box, truth, AA_EYE_S, &e), 0);
    assert_true(e > 0 && e < 0.02);
    /* a wrong picture is seen as wrong: the box image mirrored left to right */
    aa_image flip;
    assert_int_equal(aa_image_alloc(&flip, 64, 64, 3), 0);
    for (int j = 0; j < 64; j++)
        for (int i = 0; i < 64; i++)
            memcpy(aa_pixel(&flip, i, j), aa_pixel(&box, 63 - i, j), 3 * sizeof(double));
    double f;
    assert_int_equal(aa_eye_rmse(&flip, truth, AA_EYE_S, &f), 0);
    assert_true(f > 10 * e);
    aa_image_free(&flip);
    aa_image_free(&box);
}

static void test_calibration(void **state)
{
    (void)state;
    aa_calibration c;
    assert_int_equal(aa_crow_calibration(NULL, 2, &c), 0);
    assert_true(c.n == 71);
    for (int s = 0; s < 2; s++) {
        assert_true(fabs(c.gmin_fringe[s] - 1) < 0.05);
        assert_true(fabs(c.gmin_eye[s] - 1) < 0.05);
        /* figs. A.2 (g = 1), A.1 (g = 2), A.3 (g = 4) */
        assert_true(c.map_g[0] == 2 && c.map_g[1] == 1 && c.map_g[2] == 4);
        assert_true(c.map_fringe[s][1] < c.map_fringe[s][0]);
        assert_true(c.map_fringe[s][0] < c.map_fringe[s][2]);
    }
}

/* ---- Feibush et al.'s texture filter (feibushtex) ---- */

static void render_into(const char *method, const aa_scene *scene, const char *filter, int w,
                        aa_image *out)
{
    support_render(method, scene, filter, w, w, 2, out, NULL);
}

/* A quadrilateral of one colour: its texture is that colour, so the texture
 * filter gives it exactly and the pixel is the edge filter's share of it:
 * feibushtex = colour x conetable on the same quadrilateral in white. */
static void test_feibushtex_uniform(void **state)
{
    (void)state;
    static const double q[4][2] = {{0.3, 0.2}, {0.8, 0.25}, {0.9, 0.85}, {0.1, 0.7}};
    const aa_rgb colour = {{0.2, 0.6, 0.4}};
    aa_scene *s[2];
    for (int k = 0; k < 2; k++) {
        s[k] = aa_scene_new((aa_rgb){{0, 0, 0}});
        assert_int_equal(aa_scene_layer(s[k], k ? (aa_rgb){{1, 1, 1}} : colour,
                                        AA_FILL_NONZERO),
                         0);
        assert_int_equal(aa_scene_move_to(s[k], q[0][0], q[0][1]), 0);
        for (int c = 1; c < 4; c++)
            assert_int_equal(aa_scene_line_to(s[k], q[c][0], q[c][1]), 0);
        assert_int_equal(aa_scene_finish(s[k]), 0);
    }
    static const char *const filters[] = {"gauss:s=1", "cone:r=1.5"};
    for (int f = 0; f < 2; f++) {
        aa_image tex, edge;
        render_into("feibushtex", s[0], filters[f], 48, &tex);
        render_into("conetable", s[1], filters[f], 48, &edge);
        int inside = 0;
        for (int p = 0; p < 48 * 48; p++)
            for (int c = 0; c < 3; c++) {
                double want = colour.c[c] * edge.v[3 * p + c];
                if (fabs(tex.v[3 * p + c] - want) > 1e-12)
                    fail_msg("%s pixel %d channel %d: %.17g, not %.17g", filters[f], p, c,
                             tex.v[3 * p + c], want);
                inside += edge.v[3 * p + c] == 1.0 && tex.v[3 * p + c] == colour.c[c];
            }
        assert_true(inside > 300); /* the interior exactly the colour */
        aa_image_free(&tex);
        aa_image_free(&edge);
    }
    aa_scene_free(s[0]);
    aa_scene_free(s[1]);
}

/* Two stripes (feibush:stripes=2): a pixel whose mask lies inside one
 * stripe is that stripe's colour exactly; a pixel on the straight boundary
 * between them (a projective map keeps lines straight, and the circular
 * mask is symmetric about any line through its centre) takes about half of
 * each: green and blue near 1/2, red 1. */
static void test_feibushtex_stripes(void **state)
{
    (void)state;
    aa_spec ps;
    aa_scene *scene;
    assert_int_equal(aa_pattern_parse("feibush:stripes=2", &ps), 0);
    assert_int_equal(aa_pattern_scene(&ps, &scene), 0);
    aa_image im;
    const int w = 128;
    render_into("feibushtex:texels=512", scene, "gauss:s=1", w, &im);
    /* the square's homography (patterns/README.md, feibush), its corners
     * (0.32, 0.18), (0.72, 0.24), (0.97, 0.96), (0.04, 0.90) */
    const double x0 = 0.32, y0 = 0.18, x1 = 0.72, y1 = 0.24, x2 = 0.97, y2 = 0.96, x3 = 0.04,
                 y3 = 0.90;
    double dx1 = x1 - x2, dx2 = x3 - x2, dx3 = x0 - x1 + x2 - x3;
    double dy1 = y1 - y2, dy2 = y3 - y2, dy3 = y0 - y1 + y2 - y3;
    double den = dx1 * dy2 - dx2 * dy1;
    double g = (dx3 * dy2 - dx2 * dy3) / den, h = (dx1 * dy3 - dx3 * dy1) / den;
    double a = x1 - x0 + g * x1, b = x3 - x0 + h * x3, d = y1 - y0 + g * y1,
           e = y3 - y0 + h * y3;
    static const double st[3][2] = {{0.25, 0.5}, {0.75, 0.5}, {0.5, 0.5}};
    for (int k = 0; k < 3; k++) {
        double wq = g * st[k][0] + h * st[k][1] + 1;
        double x = (a * st[k][0] + b * st[k][1] + x0) / wq;
        double y = (d * st[k][0] + e * st[k][1] + y0) / wq;
        const double *v = aa_pixel(&im, (int)(x * w), (int)(y * w));
        if (k == 0)
            assert_true(v[0] == 1 && v[1] == 0 && v[2] == 0); /* stripe 0: red */
        else if (k == 1)
            assert_true(v[0] == 1 && v[1] == 1 && v[2] == 1); /* stripe 1: white */
        else
            assert_true(v[0] == 1 && fabs(v[1] - 0.5) < 0.15 && fabs(v[2] - 0.5) < 0.15);
    }
    aa_image_free(&im);
    aa_scene_free(scene);
}

/* ---- suites ---- */

static int group_has(const aa_suite_group *g, const aa_method_type *type, const aa_filter *f)
{
    for (const char *const *m = g->methods; *m; m++) {
        aa_spec spec;
        if (aa_spec_parse(*m, aa_method_table(), "method", &spec) ||
            spec.info != &type->info)
            continue;
        for (const char *const *ft = g->filters; *ft; ft++) {
            aa_filter gf;
            assert_int_equal(aa_filter_parse(*ft, &gf), 0);
            if (f ? !strcmp(gf.type->info.name, f->type->info.name)
                  : aa_method_check(&spec, &gf) == AA_OK)
                return 1;
        }
    }
    return 0;
}

static int suite_has(const char *suite, const char *pattern, const aa_method_type *type,
                     const aa_filter *f)
{
    const aa_suite *s = aa_suite_find(suite);
    assert_non_null(s);
    for (const aa_suite_group *g = s->groups; g->patterns; g++) {
        int pat = 0;
        for (const char *const *p = g->patterns; *p; p++)
            pat |= !pattern || !strncmp(*p, pattern, strlen(pattern));
        if (pat && group_has(g, type, f))
            return 1;
    }
    return 0;
}

static void test_suites(void **state)
{
    (void)state;
    static const char *const filters[] = {"box", "tent:r=1", "gauss", "cone"};
    int fams = 0;
    for (const aa_method_type *const *t = aa_method_types; *t; t++, fams++) {
        assert_true(suite_has("quick", "crow", *t, NULL));
        assert_true(suite_has("default", "crow", *t, NULL));
        /* full: every filter the family's defaults accept, on crow */
        aa_spec spec;
        assert_int_equal(aa_spec_parse((*t)->info.name, aa_method_table(), "method", &spec), 0);
        for (int f = 0; f < 4; f++) {
            aa_filter flt;
            assert_int_equal(aa_filter_parse(filters[f], &flt), 0);
            if (aa_method_check(&spec, &flt) == AA_OK && !suite_has("full", "crow", *t, &flt))
                fail_msg("full lacks %s under %s", (*t)->info.name, filters[f]);
        }
    }
    assert_true(fams >= 15);
    /* the zone plate is in full */
    const aa_suite *full = aa_suite_find("full");
    int zp = 0;
    for (const aa_suite_group *g = full->groups; g->patterns; g++)
        for (const char *const *p = g->patterns; *p; p++)
            zp |= !strncmp(*p, "zoneplate", 9);
    assert_true(zp);
}

/* A run with skip_refused: point takes only the box, conetable only the
 * Gaussian and the cone (algorithms/README.md, "Filters and scenes"). */
static void test_run_pairs(void **state)
{
    (void)state;
    aa_run_spec p, m[2];
    aa_run_size s = {16, 16};
    aa_run_filter f[2];
    p.text = "crow";
    assert_int_equal(aa_pattern_parse("crow", &p.spec), 0);
    f[0].text = "box", f[1].text = "gauss";
    assert_int_equal(aa_filter_parse("box", &f[0].filter), 0);
    assert_int_equal(aa_filter_parse("gauss", &f[1].filter), 0);
    m[0].text = "point", m[1].text = "conetable";
    for (int k = 0; k < 2; k++)
        assert_int_equal(aa_spec_parse(m[k].text, aa_method_table(), "method", &m[k].spec), 0);
    for (int skip = 0; skip < 2; skip++) {
        aa_run_config c;
        size_t skipped = 0, n;
        aa_row *rows;
        memset(&c, 0, sizeof c);
        c.patterns = &p, c.npatterns = 1;
        c.sizes = &s, c.nsizes = 1;
        c.filters = f, c.nfilters = 2;
        c.methods = m, c.nmethods = 2;
        c.reps = 1, c.threads = 1, c.seed = 1;
        c.skip_refused = skip;
        c.skipped = &skipped;
        assert_int_equal(aa_run(&c, &rows, &n), 0);
        if (skip) {
            assert_int_equal(n, 2);
            assert_int_equal(skipped, 2);
            assert_string_equal(rows[0].method, "point");
            assert_string_equal(rows[0].filter, "box");
            assert_string_equal(rows[1].method, "conetable");
            assert_string_equal(rows[1].filter, "gauss");
            assert_true(rows[0].ok && rows[1].ok);
        } else {
            assert_int_equal(n, 4);
            assert_int_equal(skipped, 0);
            assert_true(rows[0].ok && !rows[1].ok && !rows[2].ok && rows[3].ok);
        }
        free(rows);
    }
}

/* Run $AABENCH with args, its output in `output`; the exit status. */
static int run(const char *const *args)
{
    return support_aabench(args, output, sizeof output);
}

/* `aabench run` with the arguments given (NULL-terminated), then one
 * repetition on one thread, no images, plots or cache, into out: the exit
 * status. */
static int run_once(const char *const *what, const char *out)
{
    const char *args[40] = {"run"};
    int n = 1;
    while (*what && n < 28)
        args[n++] = *what++;
    const char *const rest[] = {"--reps", "1", "--no-images", "--no-plots", "--out", out,
                                "--threads", "1", "--no-cache", NULL};
    for (int k = 0; k < 10; k++)
        args[n++] = rest[k];
    return run(args);
}

static int count(const char *text, const char *what)
{
    int n = 0;
    for (const char *s = strstr(text, what); s; s = strstr(s + 1, what))
        n++;
    return n;
}

static void test_cli_pairs(void **state)
{
    (void)state;
    char out[600];
    snprintf(out, sizeof out, "%s/run", dir);
    /* the quick suite at a tiny size: every family once, none refused */
    const char *quick[] = {"--suite", "quick", "-s", "16x16", NULL};
    assert_int_equal(run_once(quick, out), 0);
    assert_int_equal(count(output, "skipped"), 0);
    assert_int_equal(count(output, "refused"), 0);
    aa_row *rows;
    size_t n;
    char csv[700];
    snprintf(csv, sizeof csv, "%s/results.csv", out);
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), 0);
    assert_int_equal(n, 21); /* harness/bench/suite.c: 16 under box, 3 + 2 */
    for (size_t k = 0; k < n; k++)
        assert_true(rows[k].ok);
    free(rows);
    /* methods named, filters from the default suite: one line for the
     * pairs left out (box: conetable; tent:r=1: both; gauss:s=1: point) */
    const char *some[] = {"-p", "crow", "-s", "16x16", "-m", "point", "-m", "conetable", NULL};
    assert_int_equal(run_once(some, out), 0);
    assert_int_equal(count(output, "skipped 4 method and view pairs"), 1);
    assert_int_equal(count(output, "refused"), 0);
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), 0);
    assert_int_equal(n, 2);
    free(rows);
    /* the method and the filters both named: run as asked, the refusal a
     * row of its own; a method that refuses every filter named is bad
     * input (exit 2, as `render` says), not a run of refusals */
    const char *named[] = {"-p", "crow", "-s", "16x16", "-m", "point", "-f", "box", "-f",
                           "gauss", NULL};
    assert_int_equal(run_once(named, out), 0);
    assert_int_equal(count(output, "skipped"), 0);
    assert_true(count(output, "refused") >= 1);
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), 0);
    assert_int_equal(n, 2);
    assert_true(rows[0].ok != rows[1].ok);
    free(rows);
    const char *refused[] = {"-p", "crow", "-s", "16x16", "-m", "point", "-f", "gauss", NULL};
    assert_int_equal(run_once(refused, out), 2);
    assert_true(count(output, "point") >= 1);
}

int main(void)
{
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tables),
        cmocka_unit_test(test_titles_1976),   cmocka_unit_test(test_figures_differ),
        cmocka_unit_test(test_papers_methods), cmocka_unit_test(test_catmull_split),
        cmocka_unit_test(test_eye),           cmocka_unit_test(test_eye_truth),
        cmocka_unit_test(test_eye_of_exact),
        cmocka_unit_test(test_calibration),   cmocka_unit_test(test_suites),
        cmocka_unit_test(test_run_pairs),     cmocka_unit_test(test_cli_pairs),
        cmocka_unit_test(test_feibushtex_uniform), cmocka_unit_test(test_feibushtex_stripes),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    aa_image_free(&crow_eye);
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        failed++;
    return failed;
}
