/*
 * test_methods.c: every method in the table (built-in, and the example
 * plug-in loaded at start) meets the generic properties, as GSL's rng tests
 * loop over every generator:
 *
 *  - a uniform scene renders exactly (every pixel is its colour); a method
 *    flagged AA_METHOD_SOME_SCENES may refuse the colour one with a message,
 *    and must then render it in grey exactly; these first checks use the
 *    box, or the Gaussian for a method that refuses the box (a circularly
 *    symmetric filter);
 *  - values are finite and in [0, 1];
 *  - the same seed gives the same image, 1 and 2 threads the same image, and
 *    a seeded method gives another image for another seed;
 *  - out-of-range, non-finite and unknown parameters are refused;
 *  - every filter is honoured or refused with a message;
 *  - the counters make sense;
 *  - on the zone plate (a field scene) a method samples the field, or
 *    refuses it if it does not declare AA_METHOD_FIELDS;
 *  - on a scene of cubic arcs (tests/scenes.c, scenes_cubics: turning
 *    points in x and y, a loop) a method renders the shape: values in
 *    [0, 1], 1 and 2 threads the same image, and within half the error of
 *    an image of the background alone from the reference of its filter.
 *
 * Every CHOICE parameter is run with each of its words.  Then the ordering
 * on crow 256x256 box that the methods exist to show: RMSE falls from point
 * to supersample n=3 to jitter spp=64 to area.
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 41
#define H 29

/* The specs to test for a method: the default, and one per word of each
 * CHOICE parameter. */
static int method_specs(const aa_info *info, char specs[][256], int max)
{
    int n = 0;
    snprintf(specs[n++], 256, "%s", info->name);
    for (size_t k = 0; k < aa_param_count(info) && n < max; k++) {
        const aa_param *p = &info->params[k];
        if (p->kind != AA_PARAM_CHOICE)
            continue;
        const char *start = p->choices;
        while (start && n < max) {
            const char *stop = strchr(start, '|');
            int len = stop ? (int)(stop - start) : (int)strlen(start);
            snprintf(specs[n++], 256, "%s:%s=%.*s", info->name, p->key, len, start);
            start = stop ? stop + 1 : NULL;
        }
    }
    return n;
}

/* A scene with no edge in view: one colour everywhere on the image. */
static aa_scene *uniform_scene(aa_rgb colour)
{
    const double xy[] = {-3, -3, 4, -3, 4, 4, -3, 4};
    return scenes_polygon(xy, 4, colour, (aa_rgb){{0, 0, 0}}, AA_FILL_NONZERO);
}

/* Render; returns the status (the image is allocated on success). */
static int render(const char *method, const aa_scene *scene, const char *filter, int w, int h,
                  uint64_t seed, int threads, aa_image *out, aa_counters *c)
{
    const support_view v = {.w = w, .h = h, .filter = filter, .seed = seed, .threads = threads};
    return support_render_view(method, scene, &v, out, c);
}

/* $AABENCH_METHODS (a comma-separated list of names), if set, limits the
 * generic loops to those methods: for working on one method. */
static size_t builtin_count; /* methods in the table before the plug-in */

static int selected(const char *name)
{
    /* $AABENCH_PLUGIN_ONLY (make check-plugin): only the plug-in's methods */
    if (getenv("AABENCH_PLUGIN_ONLY")) {
        const void *const *table = aa_method_table();
        for (size_t k = 0; k < builtin_count; k++)
            if (!strcmp(((const aa_info *)table[k])->name, name))
                return 0;
        return 1;
    }
    const char *list = getenv("AABENCH_METHODS");
    if (!list || !*list)
        return 1;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ',') && (p[n] == ',' || p[n] == '\0'))
            return 1;
    return 0;
}

static void for_each_spec(void (*check)(const char *spec, const aa_method_type *type))
{
    const void *const *table = aa_method_table();
    for (size_t k = 0; table[k]; k++) {
        if (!selected(((const aa_info *)table[k])->name))
            continue;
        char specs[32][256];
        int n = method_specs(table[k], specs, 32);
        for (int s = 0; s < n; s++)
            check(specs[s], table[k]);
    }
}

/* The filter a method's generic checks use: box, or gauss for a method
 * that refuses the box (a circularly symmetric one), or the tent of radius
 * 1 (Crow's tiler); NULL if it refuses all, with a message that must say
 * what it accepts. */
static const char *home_filter(const char *spec)
{
    const char *filters[] = {"box", "gauss", "tent:r=1"};
    for (int k = 0; k < 3; k++) {
        aa_filter f;
        aa_spec m;
        assert_int_equal(aa_filter_parse(filters[k], &f), AA_OK);
        if (aa_method_parse(spec, &f, &m) == AA_OK)
            return filters[k];
    }
    if (strlen(aa_last_error()) < 20)
        fail_msg("%s refuses box, gauss and tent without a clear message: \"%s\"", spec,
                 aa_last_error());
    return NULL;
}

static void check_uniform(const char *spec, const aa_method_type *type)
{
    aa_rgb colour = {{0.3, 0.5, 0.7}};
    const char *filter = home_filter(spec);
    if (!filter)
        return;
    aa_scene *s = uniform_scene(colour);
    aa_image img;
    aa_counters c;
    int st = render(spec, s, filter, W, H, 1, 2, &img, &c);
    /* the peers paint colour layer by layer (algorithms/peer.h): a layer
     * covering every pixel wholly gives its colour exactly */
    static const char *const peers[] = {"freetype", "stb", "cairo", "agg"};
    for (size_t k = 0; k < sizeof peers / sizeof peers[0]; k++) {
        size_t n = strlen(peers[k]);
        if (st && !strncmp(spec, peers[k], n) && (!spec[n] || spec[n] == ':'))
            fail_msg("%s refuses a colour scene: %s", spec, aa_last_error());
    }
    if (st == AA_EINVAL && (type->flags & AA_METHOD_SOME_SCENES)) {
        /* a method that says it refuses some scenes may refuse colour, with
         * a message; it must then take the same scene in grey */
        if (strlen(aa_last_error()) < 20)
            fail_msg("%s refuses a colour scene without a clear message: \"%s\"", spec,
                     aa_last_error());
        aa_scene_free(s);
        colour = (aa_rgb){{0.3, 0.3, 0.3}};
        s = uniform_scene(colour);
        st = render(spec, s, filter, W, H, 1, 2, &img, &c);
    }
    if (st)
        fail_msg("%s: %s", spec, aa_last_error());
    for (int p = 0; p < W * H; p++)
        for (int ch = 0; ch < 3; ch++)
            if (img.v[3 * p + ch] != colour.c[ch])
                fail_msg("%s: uniform scene pixel %d channel %d is %.17g, not %.17g", spec, p,
                         ch, img.v[3 * p + ch], colour.c[ch]);
    aa_image_free(&img);
    aa_scene_free(s);
}

static void test_uniform_exact(void **state)
{
    (void)state;
    for_each_spec(check_uniform);
}

/* Every value of a finite and in [0, 1]; the smallest and largest in *lo,
 * *hi. */
static void check_range(const char *spec, const char *what, const aa_image *a, double *lo,
                        double *hi)
{
    *lo = 1, *hi = 0;
    for (int p = 0; p < W * H * 3; p++) {
        if (!(a->v[p] >= 0.0 && a->v[p] <= 1.0))
            fail_msg("%s: %svalue %.17g at %d outside [0, 1]", spec, what, a->v[p], p);
        *lo = fmin(*lo, a->v[p]), *hi = fmax(*hi, a->v[p]);
    }
}

/* Render again with another seed or thread count: 1 if a comes back. */
static int same_again(const char *spec, const aa_scene *s, const char *filter, uint64_t seed,
                      int threads, const aa_image *a, aa_counters *c)
{
    aa_image b;
    assert_int_equal(render(spec, s, filter, W, H, seed, threads, &b, c), AA_OK);
    int same = support_same_image(a, &b);
    aa_image_free(&b);
    return same;
}

static void check_range_and_determinism(const char *spec, const aa_method_type *type)
{
    const char *filter = home_filter(spec);
    if (!filter)
        return;
    aa_scene *s = scenes_pattern("crow");
    aa_image a;
    aa_counters ca, cb;
    double lo, hi;
    if (render(spec, s, filter, W, H, 7, 1, &a, &ca))
        fail_msg("%s: %s", spec, aa_last_error());
    check_range(spec, "", &a, &lo, &hi);
    if (!same_again(spec, s, filter, 7, 2, &a, &cb))
        fail_msg("%s: 1 and 2 threads give different images", spec);
    if (ca.samples != cb.samples || ca.expensive_pixels != cb.expensive_pixels)
        fail_msg("%s: 1 and 2 threads give different counters", spec);
    assert_true(ca.expensive_pixels <= (uint64_t)W * H);
    int differs = !same_again(spec, s, filter, 8, 2, &a, NULL);
    if (differs != ((type->flags & AA_METHOD_SEEDED) != 0))
        fail_msg("%s: another seed %s the image, but the method %s seeded", spec,
                 differs ? "changes" : "does not change", differs ? "is not" : "is");
    aa_image_free(&a);
    aa_scene_free(s);
}

static void test_range_and_determinism(void **state)
{
    (void)state;
    for_each_spec(check_range_and_determinism);
}

/* The zone plate, a field scene (core.h, "Fields"): a method that
 * declares AA_METHOD_FIELDS samples its point function (values in [0, 1],
 * not all one colour as the background would be, the same for 1 and 2
 * threads and for the same seed); any other is refused with exit status 2
 * and a message naming the field. */
static void check_zoneplate(const char *spec, const aa_method_type *type)
{
    aa_scene *s = scenes_pattern("zoneplate");
    aa_image a;
    aa_counters ca;
    const char *filter = home_filter(spec);
    if (!filter) {
        aa_scene_free(s);
        return;
    }
    int st = render(spec, s, filter, W, H, 7, 1, &a, &ca);
    if (!(type->flags & AA_METHOD_FIELDS)) {
        if (st != AA_EINVAL || aa_exit_code(st) != 2 || !strstr(aa_last_error(), "zoneplate"))
            fail_msg("%s: a field scene is not refused clearly (status %d, \"%s\")", spec, st,
                     aa_last_error());
        aa_scene_free(s);
        return;
    }
    if (st)
        fail_msg("%s: %s", spec, aa_last_error());
    double lo, hi;
    check_range(spec, "zoneplate ", &a, &lo, &hi);
    if (!(hi - lo > 0.5))
        fail_msg("%s: zoneplate image spans only [%g, %g]: not the rings", spec, lo, hi);
    assert_true(ca.samples >= (uint64_t)W * H);
    if (!same_again(spec, s, filter, 7, 2, &a, NULL))
        fail_msg("%s: zoneplate: 1 and 2 threads give different images", spec);
    if (!same_again(spec, s, filter, 7, 2, &a, NULL))
        fail_msg("%s: zoneplate: the same seed gives another image", spec);
    aa_image_free(&a);
    aa_scene_free(s);
}

static void test_zoneplate(void **state)
{
    (void)state;
    for_each_spec(check_zoneplate);
}

static void check_filters(const char *spec, const aa_method_type *type)
{
    (void)type;
    const char *filters[] = {"tent:r=0.5", "tent:r=1", "gauss", "gauss:s=1"};
    aa_scene *s = scenes_pattern("crow");
    for (int k = 0; k < 4; k++) {
        aa_image img;
        aa_counters c;
        int st = render(spec, s, filters[k], 19, 13, 1, 2, &img, &c);
        if (st == AA_EINVAL) {
            /* refused: the message must say what the method accepts */
            if (strlen(aa_last_error()) < 20)
                fail_msg("%s refuses %s without a clear message: \"%s\"", spec, filters[k],
                         aa_last_error());
            continue;
        }
        if (st)
            fail_msg("%s with %s: %s", spec, filters[k], aa_last_error());
        for (int p = 0; p < 19 * 13 * 3; p++)
            assert_true(img.v[p] >= 0.0 && img.v[p] <= 1.0);
        aa_image_free(&img);
    }
    aa_scene_free(s);
}

static void test_filters(void **state)
{
    (void)state;
    for_each_spec(check_filters);
}

/* Out of range, not finite, not an integer, unknown: all refused. */
static void test_bad_parameters(void **state)
{
    (void)state;
    const void *const *table = aa_method_table();
    aa_filter box;
    aa_spec spec;
    aa_filter_default(&box);
    for (size_t k = 0; table[k]; k++) {
        const aa_info *info = table[k];
        char text[512];
        snprintf(text, sizeof text, "%s:no_such_key=1", info->name);
        assert_int_equal(aa_method_parse(text, &box, &spec), AA_EINVAL);
        for (size_t q = 0; q < aa_param_count(info); q++) {
            const aa_param *p = &info->params[q];
            const char *bad[4] = {"nan", "inf", "", ""};
            char below[64], above[64];
            if (p->kind == AA_PARAM_CHOICE) {
                bad[2] = "no-such-word";
                bad[3] = "1";
            } else {
                snprintf(below, sizeof below, "%.17g", p->min - (p->kind == AA_PARAM_INT ? 1 : fabs(p->min) + 1));
                snprintf(above, sizeof above, "%.17g", p->max + (p->kind == AA_PARAM_INT ? 1 : fabs(p->max) + 1));
                bad[2] = below;
                bad[3] = above;
            }
            for (int b = 0; b < 4; b++) {
                snprintf(text, sizeof text, "%s:%s=%s", info->name, p->key, bad[b]);
                if (aa_method_parse(text, &box, &spec) != AA_EINVAL)
                    fail_msg("method spec \"%s\" accepted", text);
            }
        }
    }
}

/* point: each pixel is the scene's colour at its centre. */
static void test_point_is_centres(void **state)
{
    (void)state;
    aa_scene *s = scenes_pattern("crow");
    aa_image img;
    aa_counters c;
    assert_int_equal(render("point", s, "box", 97, 61, 1, 2, &img, &c), AA_OK);
    aa_scene *placed = aa_scene_place(s, 97, 61, 0, 0, 0);
    for (int j = 0; j < 61; j++)
        for (int i = 0; i < 97; i++)
            assert_true(aa_pixel(&img, i, j)[0] == aa_scene_colour_at(placed, i + 0.5, j + 0.5).c[0]);
    assert_true(c.samples == 97 * 61);
    aa_scene_free(placed);
    aa_image_free(&img);
    aa_scene_free(s);
}

/* The reference of the cubic arcs under each home filter (box, gauss,
 * tent:r=1), computed once for every method that uses that filter: it does
 * not depend on the method, and computing it per spec was most of the
 * cubics' cost. */
static struct {
    const char *filter;
    aa_image ref;
} cubic_refs[3];

static const aa_image *cubics_reference(const aa_scene *s, const char *filter)
{
    size_t k = 0;
    for (; k < sizeof cubic_refs / sizeof *cubic_refs && cubic_refs[k].filter; k++)
        if (!strcmp(cubic_refs[k].filter, filter))
            return &cubic_refs[k].ref;
    assert_true(k < sizeof cubic_refs / sizeof *cubic_refs);
    const support_view v = {.w = W, .h = H, .filter = filter, .threads = 2};
    support_reference(s, &v, &cubic_refs[k].ref, NULL, NULL);
    cubic_refs[k].filter = filter;
    return &cubic_refs[k].ref;
}

/* Cubic arcs: every method takes them (samplers through the crossings,
 * exact methods through the pieces, peers natively). */
static void check_cubics(const char *spec, const aa_method_type *type)
{
    (void)type;
    const char *filter = home_filter(spec);
    if (!filter)
        return;
    aa_scene *s = scenes_cubics();
    aa_image a, empty;
    double lo, hi;
    if (render(spec, s, filter, W, H, 7, 1, &a, NULL))
        fail_msg("%s: cubics: %s", spec, aa_last_error());
    check_range(spec, "cubics ", &a, &lo, &hi);
    if (!same_again(spec, s, filter, 7, 2, &a, NULL))
        fail_msg("%s: cubics: 1 and 2 threads give different images", spec);
    const aa_image *ref = cubics_reference(s, filter);
    assert_int_equal(aa_image_alloc(&empty, W, H, 3), AA_OK);
    for (size_t k = 0; k < (size_t)W * H * 3; k++)
        empty.v[k] = 0.0;
    double e = support_rmse(&a, ref), e0 = support_rmse(&empty, ref);
    if (!(e <= 0.5 * e0))
        fail_msg("%s: cubics: RMSE %g against the reference under %s (the background alone: "
                 "%g)",
                 spec, e, filter, e0);
    aa_image_free(&a);
    aa_image_free(&empty);
    aa_scene_free(s);
}

static void test_cubics(void **state)
{
    (void)state;
    for_each_spec(check_cubics);
    for (size_t k = 0; k < sizeof cubic_refs / sizeof *cubic_refs && cubic_refs[k].filter; k++) {
        aa_image_free(&cubic_refs[k].ref);
        cubic_refs[k].filter = NULL;
    }
}

/* The example plug-in's method is in the table and renders like the mean of
 * its four samples. */
static void test_plugin(void **state)
{
    (void)state;
    if (getenv("AABENCH_PLUGIN_ONLY"))
        skip(); /* another plug-in than the example */
    aa_filter box;
    aa_spec spec;
    aa_filter_default(&box);
    assert_int_equal(aa_method_parse("centre4", &box, &spec), AA_OK);
    /* loading it twice is refused: the name is taken */
    char path[4096];
    snprintf(path, sizeof path, "%s", getenv("AABENCH_PLUGIN"));
    assert_int_equal(aa_plugin_load(path), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "already defined"));
    assert_int_equal(aa_plugin_load("/nonexistent/plugin.so"), AA_EIO);
}

/* The ordering the methods exist to show: each finer than the last. */
static void test_rmse_order(void **state)
{
    (void)state;
    const char *order[] = {"point", "supersample:n=3", "jitter:spp=64", "area"};
    aa_scene *s = scenes_pattern("crow");
    const support_view v = {.w = 256, .h = 256, .seed = 1, .threads = 2};
    support_check_rmse_order("crow", s, &v, order, 4);
    aa_scene_free(s);
}

/* The names of the methods the plug-in added, joined by ", ". */
static size_t plugin_names(char *buf, size_t len)
{
    const void *const *table = aa_method_table();
    size_t n = 0, used = 0;
    buf[0] = '\0';
    for (size_t k = builtin_count; table[k]; k++, n++) {
        int m = snprintf(buf + used, len - used, "%s%s", n ? ", " : "",
                         ((const aa_info *)table[k])->name);
        if (m < 0 || (size_t)m >= len - used)
            break;
        used += (size_t)m;
    }
    return n;
}

/* make check-plugin names the methods it tests: the example plug-in's
 * only method is centre4 (tests/plugin_example.c). */
static void test_plugin_names(void **state)
{
    (void)state;
    if (getenv("AABENCH_PLUGIN_ONLY"))
        skip(); /* another plug-in than the example */
    char names[4096];
    assert_int_equal(plugin_names(names, sizeof names), 1);
    assert_string_equal(names, "centre4");
}

static int setup(void **state)
{
    (void)state;
    const char *plugin = getenv("AABENCH_PLUGIN");
    const void *const *table = aa_method_table();
    for (builtin_count = 0; table[builtin_count]; builtin_count++)
        ;
    if (!plugin || aa_plugin_load(plugin)) {
        fprintf(stderr, "test_methods: cannot load the example plug-in $AABENCH_PLUGIN: %s\n",
                plugin ? aa_last_error() : "not set");
        return -1;
    }
    if (getenv("AABENCH_PLUGIN_ONLY")) {
        char names[4096];
        if (!plugin_names(names, sizeof names)) {
            fprintf(stderr, "check-plugin: %s adds no method\n", plugin);
            return -1;
        }
        printf("check-plugin: testing the methods of %s: %s\n", plugin, names);
        fflush(stdout);
    }
    return 0;
}

SUPPORT_MAIN(setup, NULL,
             cmocka_unit_test(test_uniform_exact),
             cmocka_unit_test(test_range_and_determinism),
             cmocka_unit_test(test_zoneplate),
             cmocka_unit_test(test_cubics),
             cmocka_unit_test(test_filters),
             cmocka_unit_test(test_bad_parameters),
             cmocka_unit_test(test_point_is_centres),
             cmocka_unit_test(test_plugin),
             cmocka_unit_test(test_plugin_names),
             cmocka_unit_test(test_rmse_order))
