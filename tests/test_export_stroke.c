/*
 * test_export_stroke.c: strokes written as SVG strokes (harness/core/svg.c,
 * aa_scene_svg): a stroke layer becomes a <path> of its source with
 * fill="none", the stroke's properties and its map as transform, and the
 * project's SVG reader, which follows SVG's definition of those properties
 * (patterns/svgfile.c), must give the same stroke back.
 *
 * Known answers: the `strokes` pattern's area, the sum of its twelve
 * cells' closed forms (patterns/README.md, `strokes`), which the read-back
 * document's box reference must sum to; and the read-back reference must
 * equal the original's pixel for pixel (to 1e-9: only the 17-digit
 * numbers' rounding and the maps' composition differ).  A scene with a
 * dashed stroke under a non-uniform map and a shear, next to a fill, must
 * come back with the same sources (style, dashes, map) and image.
 */
#include "bench.h"
#include "path.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define W 96
#define H 96

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "export_stroke");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

static void must(int st)
{
    if (st)
        fail_msg("%s", aa_last_error());
}

/* The scene exported at W x H to `name`, read back as the `svg` pattern at
 * W x H: the scene read (pattern units). */
static aa_scene *round_trip(const aa_scene *s, const char *name, aa_svg_paint paint)
{
    char path[4400], spec[4500];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    aa_scene *placed = aa_scene_place(s, W, H, 0, 0, 0);
    assert_non_null(placed);
    must(aa_scene_svg_write(path, placed, W, H, paint, "round trip"));
    aa_scene_free(placed);
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec ps;
    must(aa_pattern_parse(spec, &ps));
    aa_scene *t;
    must(aa_pattern_scene_at(&ps, W, H, &t));
    return t;
}

/* The two scenes' box references at W x H, the largest difference; *sum
 * the first's mean of channel 0 (its white area). */
static double compare(const aa_scene *a, const aa_scene *b, double *sum)
{
    aa_image ia, ib;
    support_reference(a, &(support_view){.w = W, .h = H}, &ia, NULL, NULL);
    support_reference(b, &(support_view){.w = W, .h = H}, &ib, NULL, NULL);
    double d = support_max_diff(&ia, &ib, NULL, NULL);
    if (sum)
        *sum = support_channel_mean(&ib, 0);
    aa_image_free(&ia);
    aa_image_free(&ib);
    return d;
}

/* The same style, dashes and map (the path's own numbers differ: an arc
 * is written in pieces of at most 90 degrees and read back in the
 * reader's centre form; the images compare the geometry). */
static void same_source(const aa_stroke_source *a, const aa_stroke_source *b)
{
    assert_true(a->style.width == b->style.width);
    assert_int_equal(a->style.join, b->style.join);
    assert_int_equal(a->style.cap, b->style.cap);
    assert_true(a->style.miterlimit == b->style.miterlimit);
    assert_int_equal(a->style.ndash, b->style.ndash);
    for (size_t k = 0; k < a->style.ndash; k++)
        assert_true(a->style.dash[k] == b->style.dash[k]);
    assert_true(a->style.dashoffset == b->style.dashoffset);
    for (int k = 0; k < 6; k++)
        if (fabs(a->m[k] - b->m[k]) > 1e-14)
            fail_msg("map value %d: %.17g, read back %.17g", k, a->m[k], b->m[k]);
}

static void test_strokes_pattern(void **state)
{
    (void)state;
    aa_spec ps;
    must(aa_pattern_parse("strokes", &ps));
    aa_scene *s;
    must(aa_pattern_scene(&ps, &s));
    aa_scene *t = round_trip(s, "strokes.svg", AA_SVG_COLOURS);
    size_t na, nb;
    const aa_stroke_source *a = aa_scene_stroke_sources(s, &na);
    const aa_stroke_source *b = aa_scene_stroke_sources(t, &nb);
    assert_int_equal(na, 12);
    assert_int_equal(nb, 12);
    for (size_t k = 0; k < na; k++)
        same_source(&a[k], &b[k]);
    /* the twelve cells' closed forms, defaults w = 0.02, q = 50 degrees */
    const double w = 0.02, h = w / 2, q = 50 * M_PI / 180, L = 0.07;
    double want = 0;
    for (int r = 0; r < 4; r++) {
        double J = r == 0 ? h * h * tan(q / 2) : r == 1 ? h * h * q / 2 : h * h * sin(q) / 2;
        double shape = r == 3 ? w * 0.08 * 150 * M_PI / 180 : 2 * w * L - h * h * tan(q / 2) + J;
        want += 3 * shape + 2 * (M_PI * h * h / 2) + 2 * (w * h);
    }
    double area, d = compare(s, t, &area);
    print_message("strokes read back: max pixel difference %.2e, area %.15f, want %.15f\n", d,
                  area, want);
    assert_true(d < 1e-9);
    assert_true(fabs(area - want) < 1e-10 * want);
    aa_scene_free(t);
    aa_scene_free(s);
}

static void test_dashed_sheared(void **state)
{
    (void)state;
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}}, red = {{1, 0, 0}};
    aa_path p;
    aa_path_init(&p);
    /* an open path: a line, a circular arc (u = (r, 0), v = (0, r)) */
    must(aa_path_move_to(&p, 0.1, 0.3));
    must(aa_path_line_to(&p, 0.4, 0.3));
    must(aa_path_arc_to(&p, 0.4, 0.5, 0, -0.2, 0.2, 0, 0, M_PI / 2, 0.6, 0.5));
    double dash[3] = {0.08, 0.03, 0.02};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.04;
    st.join = AA_JOIN_BEVEL;
    st.cap = AA_CAP_ROUND;
    st.miterlimit = 2.5;
    st.dash = dash, st.ndash = 3, st.dashoffset = 0.015;
    const double m[6] = {1.2, 0.1, 0.3, 0.8, -0.05, 0.1}; /* non-uniform, sheared */
    aa_scene *s = aa_scene_new(black);
    must(aa_scene_stroke(s, &p, &st, m, red));
    must(aa_scene_layer(s, white, AA_FILL_EVENODD)); /* a fill behind it */
    must(aa_scene_move_to(s, 0.2, 0.6));
    must(aa_scene_line_to(s, 0.9, 0.6));
    must(aa_scene_line_to(s, 0.5, 0.95));
    must(aa_scene_finish(s));
    aa_scene *t = round_trip(s, "dashed.svg", AA_SVG_COLOURS);
    size_t na, nb;
    const aa_stroke_source *a = aa_scene_stroke_sources(s, &na);
    const aa_stroke_source *b = aa_scene_stroke_sources(t, &nb);
    assert_int_equal(na, 1);
    assert_int_equal(nb, 1);
    same_source(a, b);
    /* the stroke, the fill, and the document's background rectangle */
    assert_int_equal(aa_scene_layer_count(t), 3);
    assert_int_equal(aa_scene_layer_stroked(t, 0), 0);
    double d = compare(s, t, NULL);
    print_message("dashed, sheared stroke read back: max pixel difference %.2e\n", d);
    assert_true(d < 1e-9);
    aa_scene_free(t);

    /* the mask: the stroke in white */
    t = round_trip(s, "mask.svg", AA_SVG_MASK);
    assert_true(aa_scene_layer_colour(t, 0).c[1] == 1.0);
    aa_scene_free(t);
    aa_scene_free(s);
    aa_path_free(&p);
}

SUPPORT_MAIN(setup, teardown,
             cmocka_unit_test(test_strokes_pattern),
             cmocka_unit_test(test_dashed_sheared))
