/*
 * test_scene_stroke.c: strokes in the scene model (aa_scene_stroke, path.h):
 * the stroke layer's area against closed forms worked out here, the source
 * kept (a copy) and carried through transform, place and clip to the unit
 * square, the hash telling styles apart, failures leaving the scene as it
 * was, and the SVG reader's strokes kept as strokes.
 *
 * Known answers: a closed square of side a stroked with width w and miter
 * joins (a right angle's miter ratio is sqrt 2, under the limit 4) is the
 * square ring between sides a + w and a - w: area (a + w)^2 - (a - w)^2 =
 * 4 a w.  A map with determinant d multiplies areas by |d|.  The box
 * reference of a white shape on black sums to its area (the pixel values
 * over the pixel count, in pattern units).
 */
#include "bench.h"
#include "path.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

static const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};

static void must(int st)
{
    if (st)
        fail_msg("%s", aa_last_error());
}

/* A closed square of side a from (x, y). */
static void square(aa_path *p, double x, double y, double a)
{
    aa_path_init(p);
    must(aa_path_move_to(p, x, y));
    must(aa_path_line_to(p, x + a, y));
    must(aa_path_line_to(p, x + a, y + a));
    must(aa_path_line_to(p, x, y + a));
    must(aa_path_close(p));
}

/* The white area of a finished scene: its box reference on 64 x 64 pixels,
 * summed, over the pixel count. */
static double area_of(const aa_scene *s)
{
    aa_image im;
    support_reference(s, &(support_view){.w = 64, .h = 64, .threads = 1}, &im, NULL, NULL);
    double a = support_channel_mean(&im, 0);
    aa_image_free(&im);
    return a;
}

static void expect_near(const char *what, double got, double want, double tol)
{
    print_message("%-36s %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) <= tol))
        fail_msg("%s: %.17g, want %.17g", what, got, want);
}

static void test_square_ring_area(void **state)
{
    (void)state;
    const double a = 0.4, w = 0.05;
    aa_path p;
    square(&p, 0.3, 0.3, a);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, NULL, white));
    must(aa_scene_finish(s));
    expect_near("stroked square", area_of(s), 4 * a * w, 1e-12);
    aa_scene_free(s);

    /* through a map of determinant 0.5 * 0.75 (a shear too): the outline
     * is mapped, so the area is the ring's times |det| */
    const double m[6] = {0.5, 0.0, 0.25, 0.75, 0.1, 0.05};
    s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, m, white));
    must(aa_scene_finish(s));
    expect_near("stroked square, sheared", area_of(s), 4 * a * w * 0.5 * 0.75, 1e-12);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* The source is a copy: path, style, dashes and map, on its layer. */
static void test_source_kept(void **state)
{
    (void)state;
    aa_path p;
    square(&p, 0.2, 0.2, 0.5);
    double dash[3] = {0.05, 0.02, 0.01};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.02;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_SQUARE;
    st.miterlimit = 7;
    st.dash = dash, st.ndash = 3, st.dashoffset = 0.01;
    const double m[6] = {1, 0, 0, 1, 0.01, 0.02};
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_layer(s, white, AA_FILL_EVENODD)); /* a fill: layer 0 */
    must(aa_scene_move_to(s, 0.1, 0.1));
    must(aa_scene_line_to(s, 0.2, 0.1));
    must(aa_scene_line_to(s, 0.2, 0.2));
    must(aa_scene_stroke(s, &p, &st, m, white)); /* layer 1 */
    dash[0] = 99;           /* the caller's array changes: the scene's copy does not */
    p.seg[1].p[0] = 99;     /* nor its path */
    must(aa_scene_finish(s));
    size_t n;
    const aa_stroke_source *src = aa_scene_stroke_sources(s, &n);
    assert_int_equal(n, 1);
    assert_int_equal(aa_scene_layer_count(s), 2);
    assert_int_equal(aa_scene_layer_stroked(s, 0), -1);
    assert_int_equal(aa_scene_layer_stroked(s, 1), 0);
    assert_int_equal(aa_scene_layer_stroked(s, 2), -1);
    assert_int_equal(src->layer, 1);
    assert_int_equal(aa_scene_layer_rule(s, 1), AA_FILL_NONZERO);
    assert_int_equal(src->path.n, p.n);
    assert_true(src->path.seg != p.seg);
    assert_true(src->path.seg[1].p[0] == 0.7);
    assert_true(src->style.width == 0.02 && src->style.join == AA_JOIN_ROUND &&
                src->style.cap == AA_CAP_SQUARE && src->style.miterlimit == 7 &&
                src->style.dashoffset == 0.01);
    assert_int_equal(src->style.ndash, 3);
    assert_true(src->style.dash != dash);
    assert_true(src->style.dash[0] == 0.05 && src->style.dash[2] == 0.01);
    for (int k = 0; k < 6; k++)
        assert_true(src->m[k] == m[k]);
    /* the fill's open path was closed by the stroke's layer, as by any */
    size_t nc;
    aa_scene_contours(s, &nc);
    assert_true(nc > 1);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* Transform and place compose the map (x' = sx x + tx after m); the
 * transformed scene's area is the ring's times sx sy. */
static void test_source_transformed(void **state)
{
    (void)state;
    const double a = 0.4, w = 0.05;
    aa_path p;
    square(&p, 0.1, 0.1, a);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    const double m[6] = {1, 0, 0.5, 1, 0.05, 0.1}; /* a shear: det 1 */
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, m, white));
    must(aa_scene_finish(s));
    aa_scene *t = aa_scene_transform(s, 0.5, 0.75, 0.2, 0.1);
    assert_non_null(t);
    size_t n;
    const aa_stroke_source *src = aa_scene_stroke_sources(t, &n);
    assert_int_equal(n, 1);
    const double want[6] = {0.5, 0, 0.25, 0.75, 0.5 * 0.05 + 0.2, 0.75 * 0.1 + 0.1};
    for (int k = 0; k < 6; k++)
        if (fabs(src->m[k] - want[k]) > 1e-15)
            fail_msg("m[%d] = %.17g, want %.17g", k, src->m[k], want[k]);
    assert_int_equal(aa_scene_layer_stroked(t, 0), 0);
    expect_near("transformed stroke", area_of(t), 4 * a * w * 0.5 * 0.75, 1e-12);
    aa_scene *pl = aa_scene_place(s, 64, 32, 0, 0, 0);
    assert_non_null(pl);
    src = aa_scene_stroke_sources(pl, &n);
    assert_int_equal(n, 1);
    assert_true(fabs(src->m[2] - 32.0) < 1e-12 && fabs(src->m[3] - 32.0) < 1e-12 &&
                fabs(src->m[4] - 3.2) < 1e-12 && fabs(src->m[5] - 3.2) < 1e-12);
    aa_scene_free(pl);
    aa_scene_free(t);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* Clipping to the unit square puts a frame layer in front: the stroke's
 * layer and its source move back by one, the area inside stays. */
static void test_source_clipped(void **state)
{
    (void)state;
    aa_path p;
    square(&p, 0.5, 0.5, 0.8); /* reaches out of the unit square */
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.1;
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, NULL, white));
    must(aa_scene_clip_unit(s));
    must(aa_scene_finish(s));
    assert_int_equal(aa_scene_layer_count(s), 2);
    assert_int_equal(aa_scene_layer_stroked(s, 0), -1);
    assert_int_equal(aa_scene_layer_stroked(s, 1), 0);
    size_t n;
    assert_int_equal(aa_scene_stroke_sources(s, &n)->layer, 1);
    /* inside the unit square: the ring's corner at (0.5, 0.5), the two
     * sides inwards to the square's edge: [0.45, 1] x [0.45, 0.55] and
     * [0.45, 0.55] x [0.45, 1] less their overlap 0.1^2 */
    expect_near("clipped stroke", area_of(s), 2 * 0.55 * 0.1 - 0.01, 1e-12);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* The hash: equal for equal scenes, different when only the style
 * differs (a miter limit above a right angle's ratio sqrt 2 either way
 * gives the same outline, edge for edge), when the dashes or the map
 * differ. */
static void test_hash(void **state)
{
    (void)state;
    aa_path p;
    square(&p, 0.2, 0.2, 0.5);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    unsigned long long h[5];
    size_t edges[5];
    for (int k = 0; k < 5; k++) {
        aa_stroke_style v = st;
        double dash[2] = {0.1, 0.05};
        double m[6] = {1, 0, 0, 1, 0, 0};
        if (k == 2)
            v.miterlimit = 3;
        if (k == 3)
            v.dash = dash, v.ndash = 2;
        if (k == 4)
            m[4] = 1e-3;
        aa_scene *s = aa_scene_new(black);
        must(aa_scene_stroke(s, &p, &v, m, white));
        must(aa_scene_finish(s));
        h[k] = aa_scene_hash(s);
        aa_scene_edges(s, &edges[k]);
        aa_scene_free(s);
    }
    assert_true(h[0] == h[1]);
    assert_int_equal(edges[0], edges[2]);
    assert_true(h[2] != h[0]);
    assert_true(h[3] != h[0] && h[3] != h[2]);
    assert_true(h[4] != h[0] && h[4] != h[2] && h[4] != h[3]);
    aa_path_free(&p);
}

/* Failures leave the scene as it was: a bad style (refused by the
 * outline, before anything is added) and a map that overflows (refused
 * while the outline is being added). */
static void test_failure_undone(void **state)
{
    (void)state;
    aa_path p;
    square(&p, 0.2, 0.2, 0.5);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, NULL, white));
    must(aa_scene_layer(s, white, AA_FILL_NONZERO));
    must(aa_scene_move_to(s, 0.1, 0.1));
    must(aa_scene_line_to(s, 0.3, 0.1));
    aa_stroke_style bad = st;
    bad.width = 0;
    assert_int_equal(aa_scene_stroke(s, &p, &bad, NULL, white), AA_EINVAL);
    print_message("zero width: %s\n", aa_last_error());
    const double huge[6] = {1e308, 0, 0, 1, 1.5e308, 0}; /* finite at x = 0.2, not at 0.7 */
    assert_int_not_equal(aa_scene_stroke(s, &p, &st, huge, white), AA_OK);
    print_message("overflowing map: %s\n", aa_last_error());
    const double nan[6] = {NAN, 0, 0, 1, 0, 0};
    assert_int_equal(aa_scene_stroke(s, &p, &st, nan, white), AA_EINVAL);
    /* the open path goes on where it was */
    must(aa_scene_line_to(s, 0.3, 0.3));
    must(aa_scene_finish(s));
    size_t n, ne;
    aa_scene_stroke_sources(s, &n);
    assert_int_equal(n, 1);
    assert_int_equal(aa_scene_layer_count(s), 2);
    aa_scene_edges(s, &ne);
    /* the same scene built without the failures */
    aa_scene *t = aa_scene_new(black);
    must(aa_scene_stroke(t, &p, &st, NULL, white));
    must(aa_scene_layer(t, white, AA_FILL_NONZERO));
    must(aa_scene_move_to(t, 0.1, 0.1));
    must(aa_scene_line_to(t, 0.3, 0.1));
    must(aa_scene_line_to(t, 0.3, 0.3));
    must(aa_scene_finish(t));
    assert_true(aa_scene_hash(s) == aa_scene_hash(t));
    aa_scene_free(t);
    aa_scene_free(s);
    aa_path_free(&p);
}

/* The SVG reader's strokes are strokes: strokes.svg's nine stroked
 * elements each give a source, on a layer of the non-zero rule. */
static void test_svg_strokes_kept(void **state)
{
    (void)state;
    char spec[4400];
    snprintf(spec, sizeof spec, "svg:file=%s/strokes.svg", aa_svg_dir());
    aa_spec ps;
    must(aa_pattern_parse(spec, &ps));
    aa_scene *s;
    must(aa_pattern_scene_at(&ps, 100, 100, &s));
    size_t n;
    const aa_stroke_source *src = aa_scene_stroke_sources(s, &n);
    assert_int_equal(n, 9);
    for (size_t k = 0; k < n; k++) {
        assert_int_equal(aa_scene_layer_stroked(s, src[k].layer), (int)k);
        assert_int_equal(aa_scene_layer_rule(s, src[k].layer), AA_FILL_NONZERO);
        /* user units (the viewBox, 100 wide) to the unit square */
        assert_true(fabs(src[k].m[0] - 0.01) < 1e-15 && fabs(src[k].m[3] - 0.01) < 1e-15);
    }
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_square_ring_area),
             cmocka_unit_test(test_source_kept),
             cmocka_unit_test(test_source_transformed),
             cmocka_unit_test(test_source_clipped),
             cmocka_unit_test(test_hash),
             cmocka_unit_test(test_failure_undone),
             cmocka_unit_test(test_svg_strokes_kept))
