/*
 * scenes.c: test-only scenes shared by several tests (scenes.h).
 */
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

aa_scene *scenes_pattern(const char *text)
{
    aa_spec spec;
    aa_scene *s = NULL;
    if (aa_pattern_parse(text, &spec) || aa_pattern_scene(&spec, &s))
        fail_msg("pattern %s: %s", text, aa_last_error());
    return s;
}

void scenes_path(aa_scene *s, const double *xy, int n)
{
    assert_int_equal(aa_scene_move_to(s, xy[0], xy[1]), AA_OK);
    for (int k = 1; k < n; k++)
        assert_int_equal(aa_scene_line_to(s, xy[2 * k], xy[2 * k + 1]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

void scenes_add_poly(aa_scene *s, const oracle_poly *p)
{
    assert_int_equal(aa_scene_move_to(s, p->x[0], p->y[0]), AA_OK);
    for (int k = 1; k < p->n; k++)
        assert_int_equal(aa_scene_line_to(s, p->x[k], p->y[k]), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
}

void scenes_rect(aa_scene *s, double x0, double y0, double x1, double y1)
{
    const double xy[] = {x0, y0, x1, y0, x1, y1, x0, y1};
    scenes_path(s, xy, 4);
}

void scenes_layer(aa_scene *s, double r, double g, double b, aa_fill_rule rule)
{
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{r, g, b}}, rule), AA_OK);
}

void scenes_move_px(aa_scene *s, int w, int h, double x, double y)
{
    assert_int_equal(aa_scene_move_to(s, x / w, y / h), AA_OK);
}

void scenes_line_px(aa_scene *s, int w, int h, double x, double y)
{
    assert_int_equal(aa_scene_line_to(s, x / w, y / h), AA_OK);
}

void scenes_rect_px(aa_scene *s, int w, int h, double x0, double y0, double x1, double y1)
{
    scenes_rect(s, x0 / w, y0 / h, x1 / w, y1 / h);
}

void scenes_gradient_px(aa_scene *s, int w, int h, int kind, int spread, const double p[6],
                        const aa_gradient_stop *st, int n, int srgb)
{
    aa_gradient g = {kind, spread, {0}, {1.0 / w, 0, 0, 1.0 / h, 0, 0}, n, st};
    memcpy(g.p, p, sizeof g.p);
    assert_int_equal(aa_scene_set_gradient(s, &g), AA_OK);
    if (!srgb)
        assert_int_equal(aa_scene_set_gradient_interpolation(s, AA_INTERPOLATE_LINEAR_RGB),
                         AA_OK);
}

aa_scene *scenes_polygon(const double *xy, int n, aa_rgb inside, aa_rgb outside,
                         aa_fill_rule rule)
{
    aa_scene *s = aa_scene_new(outside);
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, inside, rule), AA_OK);
    scenes_path(s, xy, n);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_rects(const double (*r)[4], int n)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    for (int k = 0; k < n; k++)
        scenes_rect(s, r[k][0], r[k][1], r[k][2], r[k][3]);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_arc_segment(double x0, double y0, double cx, double cy, double x1, double y1)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, x0, y0), AA_OK);
    assert_int_equal(aa_scene_quad_to(s, cx, cy, x1, y1), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_half_plane_of(double px, double py, double angle, double L, aa_rgb fg,
                               aa_rgb bg)
{
    double dx = sin(angle), dy = cos(angle); /* along the edge, downwards */
    double nx = dy, ny = -dx;                /* into the fg side */
    const double xy[] = {px - L * dx,          py - L * dy,          px + L * dx,
                         py + L * dy,          px + L * dx + L * nx, py + L * dy + L * ny,
                         px - L * dx + L * nx, py - L * dy + L * ny};
    return scenes_polygon(xy, 4, fg, bg, AA_FILL_NONZERO);
}

aa_scene *scenes_half_plane(double px, double py, double angle)
{
    return scenes_half_plane_of(px, py, angle, 50.0, (aa_rgb){{1, 1, 1}}, (aa_rgb){{0, 0, 0}});
}

aa_scene *scenes_triangles(uint64_t seed)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0.05, 0.1, 0.15}});
    aa_rng r;
    aa_rng_seed(&r, seed, 0, 0);
    for (int k = 0; k < 60; k++) {
        aa_rgb c = {{(k % 7) / 6.0, (k % 5) / 4.0, (k % 11) / 10.0}};
        assert_int_equal(aa_scene_layer(s, c, AA_FILL_NONZERO), AA_OK);
        double cx = aa_rng_uniform(&r), cy = aa_rng_uniform(&r), xy[6];
        for (int v = 0; v < 3; v++) {
            xy[2 * v] = cx + 0.3 * (aa_rng_uniform(&r) - 0.5);
            xy[2 * v + 1] = cy + 0.3 * (aa_rng_uniform(&r) - 0.5);
        }
        scenes_path(s, xy, 3);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_cubics(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.1, 0.3), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.4, -0.05, 0.7, 0.65, 0.9, 0.2), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 1.05, 0.5, 0.6, 0.7, 0.85, 0.55), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.6, 0.45, 0.35, 0.75, 0.1, 0.3), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.15, 0.9), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.95, 0.55, 0.05, 0.55, 0.85, 0.95), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_rebuild(const aa_scene *src, int swap, scenes_edge_fn edge)
{
    aa_scene *s = aa_scene_new(aa_scene_background(src));
    assert_non_null(s);
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(src, &ne);
    const size_t *start = aa_scene_contours(src, &nc);
    for (int l = 0; l < aa_scene_layer_count(src); l++) {
        assert_int_equal(aa_scene_layer(s, aa_scene_layer_colour(src, l),
                                        aa_scene_layer_rule(src, l)),
                         AA_OK);
        for (size_t c = 0; c < nc; c++) {
            if (start[c] == start[c + 1] || e[start[c]].layer != l)
                continue;
            const aa_edge *first = &e[start[c]];
            assert_int_equal(swap ? aa_scene_move_to(s, first->y0, first->x0)
                                  : aa_scene_move_to(s, first->x0, first->y0),
                             AA_OK);
            for (size_t k = start[c]; k < start[c + 1]; k++)
                assert_int_equal(edge(s, &e[k]), AA_OK);
            assert_int_equal(aa_scene_close(s), AA_OK);
        }
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

/* A quadratic arc as the cubic of the same curve (degree elevation). */
static int elevated_edge(aa_scene *s, const aa_edge *d)
{
    if (!d->quad)
        return aa_scene_line_to(s, d->x1, d->y1);
    return aa_scene_cubic_to(s, d->x0 + 2.0 / 3.0 * (d->cx - d->x0),
                             d->y0 + 2.0 / 3.0 * (d->cy - d->y0),
                             d->x1 + 2.0 / 3.0 * (d->cx - d->x1),
                             d->y1 + 2.0 / 3.0 * (d->cy - d->y1), d->x1, d->y1);
}

aa_scene *scenes_elevated(const aa_scene *src)
{
    return scenes_rebuild(src, 0, elevated_edge);
}

/* The radical inverse of i in base b, written from its definition (the
 * digits of i mirrored about the point), apart from the library's. */
static double radical_inverse(unsigned i, unsigned b)
{
    double r = 0, f = 1.0 / b;
    for (; i; i /= b, f /= b)
        r += (i % b) * f;
    return r;
}

void scenes_history_steady(const aa_scene *placed, int w, int h, int frame, int m,
                           double alpha, aa_image *out)
{
    assert_int_equal(aa_image_alloc(out, w, h, 3), AA_OK);
    double norm = 1.0 - pow(1.0 - alpha, m);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double *px = aa_pixel(out, i, j);
            px[0] = px[1] = px[2] = 0;
            for (int lag = 0; lag < m; lag++) {
                unsigned q = (unsigned)(((frame - lag) % m + m) % m);
                aa_rgb c = aa_scene_colour_at(placed, i + radical_inverse(q, 2),
                                              j + radical_inverse(q, 3));
                double wt = alpha * pow(1.0 - alpha, lag) / norm;
                for (int ch = 0; ch < 3; ch++)
                    px[ch] += wt * c.c[ch];
            }
        }
}

aa_scene *scenes_stroke_outline(const aa_path *in, const aa_stroke_style *st, const double *m,
                                size_t *noffset)
{
    aa_path out = {0};
    if (aa_stroke_outline(in, st, &out))
        fail_msg("stroke outline: %s", aa_last_error());
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    if (aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) || aa_path_fill(&out, m, s) ||
        aa_scene_finish(s))
        fail_msg("stroke outline scene: %s", aa_last_error());
    aa_path_free(&out);
    if (noffset) {
        size_t n;
        const aa_piece *pc = aa_scene_pieces(s, &n);
        *noffset = 0;
        for (size_t k = 0; k < n; k++)
            *noffset += pc[k].kind == AA_PIECE_OFFSET;
    }
    return s;
}

aa_scene *scenes_overlapping_layers(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0.1, 0.2, 0.3}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.9, 0.05, 0.6}}, AA_FILL_EVENODD), AA_OK);
    assert_int_equal(aa_scene_move_to(s, 0.15, 0.2), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.9, 0.1, 0.1, 0.9, 0.85, 0.8), AA_OK);
    assert_int_equal(aa_scene_cubic_to(s, 0.95, 0.3, 0.3, 0.95, 0.15, 0.2), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{0.3, 0.8, 0.15}}, AA_FILL_NONZERO), AA_OK);
    for (int turn = 0; turn < 2; turn++) {
        double d = 0.037 * turn; /* the second turn moved: the two cross */
        assert_int_equal(aa_scene_move_to(s, 0.3 + d, 0.55 + d), AA_OK);
        assert_int_equal(aa_scene_quad_to(s, 0.5 + d, 0.1 + d, 0.72 + d, 0.5 + d), AA_OK);
        assert_int_equal(aa_scene_quad_to(s, 0.55 + d, 0.95 + d, 0.3 + d, 0.55 + d), AA_OK);
        assert_int_equal(aa_scene_close(s), AA_OK);
    }
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}

aa_scene *scenes_pattern_at(const char *spec, int w, int h)
{
    aa_spec ps;
    aa_scene *s = NULL;
    if (aa_pattern_parse(spec, &ps) || aa_pattern_scene_at(&ps, w, h, &s))
        fail_msg("pattern %s: %s", spec, aa_last_error());
    return s;
}

aa_scene *scenes_svg_at(const char *name, int n)
{
    char spec[128];
    snprintf(spec, sizeof spec, "svg:file=patterns/svg/%s.svg", name);
    return scenes_pattern_at(spec, n, n);
}

aa_scene *scenes_svg_text(const char *dir, const char *name, const char *text, int w, int h)
{
    char path[4200], spec[4300];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    support_write_file(path, text, strlen(text));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    return scenes_pattern_at(spec, w, h);
}

aa_scene *scenes_disk(double cx, double cy, double a)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    assert_int_equal(aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO), AA_OK);
    assert_int_equal(aa_scene_move_to(s, cx + a, cy), AA_OK);
    assert_int_equal(aa_scene_arc_to(s, cx, cy, a, 0, 0, a, 0, 2 * M_PI, cx + a, cy), AA_OK);
    assert_int_equal(aa_scene_close(s), AA_OK);
    assert_int_equal(aa_scene_finish(s), AA_OK);
    return s;
}
