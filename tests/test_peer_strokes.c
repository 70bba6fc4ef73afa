/*
 * test_peer_strokes.c: the peers on strokes (algorithms/README.md, "Peers
 * and strokes"): cairo and agg stroke each stroke layer from its source
 * with their own strokers, freetype and stb fill the exact outlines as one
 * non-zero outline; each is measured against the box reference.
 *
 * Known answers: the `strokes` pattern's white area is the sum of its
 * cells' closed forms (patterns/README.md, `strokes`; tests/
 * test_strokes_pattern.c checks the reference against them to 1e-10), and
 * the reference image is exact to 1e-12 per pixel.
 *
 * Tolerances, and why: a peer's image differs from the exact coverage by
 * its antialiasing (8-bit coverage: up to 1/255 a pixel; positions in
 * fixed point) and by its approximation of arcs, round joins and caps by
 * chords within its flattening tolerance (0.1 to 0.5 px; a chord lies
 * inside the curve, so a curved edge of length l loses up to 2/3 t l of
 * area, a parabolic segment's).  On the 256 x 256 pattern (w = 5.1 px,
 * about 1,000 px of curved edge of which most is the arcs' and round
 * parts') that is at most about 1% of the white area of 2,660 px^2 at
 * t = 0.25 px: the sum must be within 2%.  The error concentrates on the
 * edges (a few hundred pixels of the 65,536): the RMSE must be under
 * 0.01 (the 8-bit rounding alone gives about 0.001, the flattening up to
 * a quarter of a pixel on some 3,000 edge pixels about 0.005).
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

static const char *const peers[] = {"cairo", "cairo:aa=good", "agg", "freetype", "stb"};
#define NPEERS (sizeof peers / sizeof peers[0])

static void must(int st)
{
    if (st)
        fail_msg("%s", aa_last_error());
}

/* The peer's image of the scene against the box reference: its RMSE, its
 * largest error, and its mean (white area) beside the reference's. */
static void measure(const char *peer, const aa_scene *s, int w, int h, double *rmse,
                    double *maxe, double *mean, double *ref_mean)
{
    const support_view v = {.w = w, .h = h, .seed = 1, .threads = 2};
    aa_image ref, img;
    support_reference(s, &v, &ref, NULL, NULL);
    if (support_render_view(peer, s, &v, &img, NULL))
        fail_msg("%s: %s", peer, aa_last_error());
    *rmse = support_rmse(&ref, &img);
    *maxe = support_max_diff(&ref, &img, NULL, NULL);
    *mean = support_channel_mean(&img, 0);
    *ref_mean = support_channel_mean(&ref, 0);
    aa_image_free(&ref);
    aa_image_free(&img);
}

static void test_strokes_pattern(void **state)
{
    (void)state;
    aa_spec ps;
    must(aa_pattern_parse("strokes", &ps));
    aa_scene *s;
    must(aa_pattern_scene(&ps, &s));
    /* the closed forms' sum at the defaults (w = 0.02, q = 50 degrees) */
    const double w = 0.02, h = w / 2, q = 50 * M_PI / 180, L = 0.07;
    double want = 0;
    for (int r = 0; r < 4; r++) {
        double J = r == 0 ? h * h * tan(q / 2) : r == 1 ? h * h * q / 2 : h * h * sin(q) / 2;
        double shape = r == 3 ? w * 0.08 * 150 * M_PI / 180 : 2 * w * L - h * h * tan(q / 2) + J;
        want += 3 * shape + 2 * (M_PI * h * h / 2) + 2 * (w * h);
    }
    for (size_t k = 0; k < NPEERS; k++) {
        double rmse, maxe, mean, ref_mean;
        measure(peers[k], s, 256, 256, &rmse, &maxe, &mean, &ref_mean);
        print_message("%-16s rmse %.3e  max %.3e  area %.6f (closed form %.6f, %+.2f%%)\n",
                      peers[k], rmse, maxe, mean, want, 100 * (mean - want) / want);
        assert_true(fabs(ref_mean - want) < 1e-10 * want);
        if (!(fabs(mean - want) < 0.02 * want))
            fail_msg("%s: area %.6f, closed form %.6f", peers[k], mean, want);
        if (!(rmse < 0.01))
            fail_msg("%s: rmse %.3e", peers[k], rmse);
    }
    aa_scene_free(s);
}

/* A dashed stroke with round caps and joins under a non-uniform, sheared
 * map (SVG: the outline is mapped, not the width): the peers that stroke
 * in user units under the map must agree with the exact reference as
 * closely as on the pattern. */
static void test_dashed_sheared(void **state)
{
    (void)state;
    aa_path p;
    aa_path_init(&p);
    must(aa_path_move_to(&p, 0.1, 0.2));
    must(aa_path_line_to(&p, 0.5, 0.2));
    must(aa_path_arc_to(&p, 0.5, 0.4, 0, -0.2, 0.2, 0, 0, M_PI / 2, 0.7, 0.4));
    must(aa_path_line_to(&p, 0.3, 0.6));
    double dash[3] = {0.12, 0.04, 0.03};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    st.dash = dash, st.ndash = 3, st.dashoffset = 0.02;
    const double m[6] = {1.1, 0.1, 0.25, 0.7, -0.05, 0.1};
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    must(aa_scene_stroke(s, &p, &st, m, (aa_rgb){{1, 1, 1}}));
    must(aa_scene_finish(s));
    for (size_t k = 0; k < NPEERS; k++) {
        double rmse, maxe, mean, ref_mean;
        measure(peers[k], s, 128, 128, &rmse, &maxe, &mean, &ref_mean);
        print_message("%-16s rmse %.3e  max %.3e  area %.6f (reference %.6f, %+.2f%%)\n",
                      peers[k], rmse, maxe, mean, ref_mean, 100 * (mean - ref_mean) / ref_mean);
        if (!(fabs(mean - ref_mean) < 0.02 * ref_mean) || !(rmse < 0.01))
            fail_msg("%s: area %.6f against %.6f, rmse %.3e", peers[k], mean, ref_mean, rmse);
    }
    aa_scene_free(s);
    aa_path_free(&p);
}

/* A fill beside a stroke, and strokes of two greys: painted layer by layer
 * by every peer (peer.h, "Painted"), each stroke by the peer's stroker or
 * from its exact outline as above, measured as the scenes above (the
 * layers do not meet, so no seam adds to the antialiasing). */
static void test_painted(void **state)
{
    (void)state;
    aa_path p;
    aa_path_init(&p);
    must(aa_path_move_to(&p, 0.2, 0.2));
    must(aa_path_line_to(&p, 0.8, 0.3));
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    for (int c = 0; c < 2; c++) {
        aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
        must(aa_scene_stroke(s, &p, &st, NULL, (aa_rgb){{1, 1, 1}}));
        if (c == 0) {
            must(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO));
            must(aa_scene_move_to(s, 0.1, 0.6));
            must(aa_scene_line_to(s, 0.5, 0.6));
            must(aa_scene_line_to(s, 0.3, 0.9));
        } else {
            must(aa_scene_stroke(s, &p, &st, (double[6]){1, 0, 0, 1, 0, 0.3},
                                 (aa_rgb){{0.5, 0.5, 0.5}}));
        }
        must(aa_scene_finish(s));
        for (size_t k = 0; k < NPEERS; k++) {
            double rmse, maxe, mean, ref_mean;
            measure(peers[k], s, 64, 64, &rmse, &maxe, &mean, &ref_mean);
            print_message("%-16s painted: rmse %.3e, mean %.6f (reference %.6f)\n", peers[k],
                          rmse, mean, ref_mean);
            if (!(rmse < 0.01 && fabs(mean - ref_mean) < 0.02 * ref_mean))
                fail_msg("%s: painted rmse %.3e, mean %.6f against %.6f", peers[k], rmse, mean,
                         ref_mean);
        }
        aa_scene_free(s);
    }
    aa_path_free(&p);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_strokes_pattern),
             cmocka_unit_test(test_dashed_sheared),
             cmocka_unit_test(test_painted))
