/*
 * scenes.h: test-only scenes and scene-building steps shared by several
 * tests.  Every function fails the running test (cmocka) if the scene
 * cannot be built, so none returns NULL.
 */
#ifndef AA_TEST_SCENES_H
#define AA_TEST_SCENES_H

#include "bench.h"
#include "oracle.h"
#include "path.h"

/* The scene of a pattern spec ("crow", "star:spokes=7"), pattern units. */
aa_scene *scenes_pattern(const char *spec);
/* The same placed at w x h px (aa_pattern_scene_at: an SVG drawn at the
 * view's size), pattern units. */
aa_scene *scenes_pattern_at(const char *spec, int w, int h);

/* A closed path in the current layer: move to the first of n points (x, y
 * pairs in xy), lines to the others, close. */
void scenes_path(aa_scene *s, const double *xy, int n);
/* The same for an oracle polygon. */
void scenes_add_poly(aa_scene *s, const oracle_poly *p);
/* The rectangle [x0, x1] x [y0, y1] as a closed path (x0, y0) (x1, y0)
 * (x1, y1) (x0, y1). */
void scenes_rect(aa_scene *s, double x0, double y0, double x1, double y1);

/* Steps of a scene drawn in pixels of a w x h view, in pattern units (the
 * point (x, y) px at (x / w, y / h)), each checked: a layer of colour
 * (r, g, b) under rule; a move and a line to (x, y) px; the rectangle
 * [x0, x1] x [y0, y1] px as scenes_rect's closed path; a gradient of kind
 * and spread with points p in pixels (its map diag(1/w, 1/h)) and the n
 * stops st on the layer added last, interpolated in linear light unless
 * srgb. */
void scenes_layer(aa_scene *s, double r, double g, double b, aa_fill_rule rule);
void scenes_move_px(aa_scene *s, int w, int h, double x, double y);
void scenes_line_px(aa_scene *s, int w, int h, double x, double y);
void scenes_rect_px(aa_scene *s, int w, int h, double x0, double y0, double x1, double y1);
void scenes_gradient_px(aa_scene *s, int w, int h, int kind, int spread, const double p[6],
                        const aa_gradient_stop *st, int n, int srgb);

/* One polygon (n points, xy pairs) of colour `inside` under `rule` on
 * `outside`, finished. */
aa_scene *scenes_polygon(const double *xy, int n, aa_rgb inside, aa_rgb outside,
                         aa_fill_rule rule);
/* White rectangles {x0, y0, x1, y1} on black, one layer, finished. */
aa_scene *scenes_rects(const double (*r)[4], int n);
/* White on black: the region between the quadratic arc from (x0, y0) with
 * control point (cx, cy) to (x1, y1) and its chord, finished. */
aa_scene *scenes_arc_segment(double x0, double y0, double cx, double cy, double x1, double y1);

/* A copy of a finished scene, layer by layer and contour by contour: each
 * contour's first point moved to (with x and y swapped when `swap`), each
 * edge added by `edge` (its status checked), closed, finished. */
typedef int (*scenes_edge_fn)(aa_scene *s, const aa_edge *e);
aa_scene *scenes_rebuild(const aa_scene *src, int swap, scenes_edge_fn edge);

/* White on black, one nonzero layer inside the unit square, of cubic arcs
 * only: an S-shaped arc, arcs with turning points in y and in x, and a
 * second path whose one arc loops over itself (harness/README.md, "Scenes
 * and their queries"), finished. */
aa_scene *scenes_cubics(void);
/* On (0.1, 0.2, 0.3): a self-crossing even-odd path of cubic arcs in front
 * of a nonzero path of two crossing loops of quadratic arcs (wound twice
 * where they overlap), in colours apart in every channel, inside the unit
 * square.  Finished. */
aa_scene *scenes_overlapping_layers(void);
/* A white disk of radius a centred at (cx, cy) on black, one circular arc,
 * finished (units the caller's). */
aa_scene *scenes_disk(double cx, double cy, double a);
/* The shipped scene patterns/svg/NAME.svg (run from the source tree's root)
 * placed at n x n pixels. */
aa_scene *scenes_svg_at(const char *name, int n);
/* An SVG document's text written to dir/name and read as the pattern
 * svg:file= of it at w x h px (fails the test if it cannot). */
aa_scene *scenes_svg_text(const char *dir, const char *name, const char *text, int w, int h);
/* A copy of a finished scene (pattern units) with every quadratic arc
 * raised to the cubic of the same curve: controls P0 + 2/3 (C - P0) and
 * P1 + 2/3 (C - P1); lines as they were.  Finished. */
aa_scene *scenes_elevated(const aa_scene *s);

/* `fg` right of the line through (px, py) with direction angle `angle`
 * (radians) from the vertical (0: the region right of a vertical line), on
 * `bg`: a square of side L with one side on the line, so the line's unit
 * normal into fg is (cos angle, -sin angle).  Units are the caller's
 * (pattern units to place, or pixels to render as placed). */
aa_scene *scenes_half_plane_of(double px, double py, double angle, double L, aa_rgb fg,
                               aa_rgb bg);
/* White on black, L = 50 pattern units. */
aa_scene *scenes_half_plane(double px, double py, double angle);

/* Sixty overlapping triangles of distinct colours from the random stream of
 * `seed`: a point's colour changes within a pixel almost everywhere, so a
 * frame tells its sample positions apart. */
aa_scene *scenes_triangles(uint64_t seed);

/* The steady state of the exponential history h <- h + alpha (x_n - h)
 * of point samples x_n of the placed scene at pixel + Halton(2, 3) index
 * (n mod m), n = frame, as the sum over lag j < m of
 * alpha (1-alpha)^j / (1 - (1-alpha)^m) x_(n-j): temporal antialiasing
 * without reprojection, in closed form (out allocated). */
void scenes_history_steady(const aa_scene *placed, int w, int h, int frame, int m,
                           double alpha, aa_image *out);

/* The outline of the stroke of `in` (aa_stroke_outline) filled white on
 * black through map m (NULL: none), non-zero; *noffset (may be NULL): how
 * many of its pieces are offset curves (AA_PIECE_OFFSET). */
aa_scene *scenes_stroke_outline(const aa_path *in, const aa_stroke_style *st, const double *m,
                                size_t *noffset);

#endif
