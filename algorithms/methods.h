/*
 * methods.h: the built-in method types (one file each) and their table.
 */
#ifndef AA_METHODS_H
#define AA_METHODS_H

#include "core.h"
#include "agg.h" /* aa_method_agg: agg.cpp is C++ */

extern const aa_method_type aa_method_point;
extern const aa_method_type aa_method_supersample;
extern const aa_method_type aa_method_jitter;
/* hexagon shows its frames through moving dots (core.h, "Displays") */
extern const aa_display_method_type aa_method_hexagon_display;
#define aa_method_hexagon (aa_method_hexagon_display.method)
extern const aa_method_type aa_method_trio;
extern const aa_method_type aa_method_mlaa;
extern const aa_method_type aa_method_fxaa;
extern const aa_method_type aa_method_smaa;
/* The shares of the pixels beside a run of a morphological method (morph.c,
 * step 3; SMAA's area table): the turn at the run's left and right ends
 * (0 none, 1 toward the near pixel's side, 2 the far side, 3 both) and the
 * pixel's distances to them; share[0] of the far colour goes to the near
 * pixel, share[1] of the near colour to the far pixel. */
void aa_morph_area(int e_left, int e_right, int d_left, int d_right, double share[2]);
/* The shares of the two pixels across the north side of a pixel on a
 * diagonal line of smaa (morph.c, step 8; SMAA's diagonal area table): the
 * crossing sides at the line's lower-left and upper-right ends (0 unknown,
 * 1 vertical, 2 horizontal, 3 both) and the pixel's distances to them, in
 * steps along the diagonal; share[0] of the colour above goes to the pixel,
 * share[1] of its colour to the pixel above. */
void aa_morph_diag_area(int e_left, int e_right, int d_left, int d_right, double share[2]);
extern const aa_method_type aa_method_area;
extern const aa_method_type aa_method_taa;
extern const aa_method_type aa_method_cycle;
extern const aa_method_type aa_method_adaptive;
extern const aa_method_type aa_method_freetype;
extern const aa_method_type aa_method_stb;
extern const aa_method_type aa_method_cairo;
extern const aa_method_type aa_method_crowtable;
extern const aa_method_type aa_method_conetable;
extern const aa_method_type aa_method_crowtiler;
extern const aa_method_type aa_method_analytic;
extern const aa_method_type aa_method_feibushtex;
/* runs an SVG renderer: in aa_method_types_optional, not the built-in table */
extern const aa_method_type aa_method_external;
/* The adapter file a spec of `external` runs (PATH_MAX bytes), as its
 * init finds it; AA_EINVAL when there is none. */
int aa_external_adapter(const aa_spec *spec, char *path);

/* The standard multisample positions of `count` samples (2, 4, 8 or 16;
 * NULL for another count), in 1/16 pixel from the pixel's centre, y down
 * (algorithms/README.md, "Standard multisample positions"; supersample.c):
 * supersample's pattern=msaaN and cycle's positions=msaaN. */
const signed char (*aa_msaa_positions(int count))[2];

/* Point-sample the placed scene at pixel centres offset by (dx, dy)
 * pixels into out (used by point, hexagon and trio). */
int aa_point_sample(const aa_scene *placed, double dx, double dy, int threads, aa_image *out);

/* One row of point samples with a caller's workspace (one per thread): the
 * line y, centres i + 1/2 + dx, into row[0 .. 3w).  No allocation. */
typedef struct aa_point_ws {
    aa_crossing *cross;
    size_t cap;
    int *wind;
    int nl;
} aa_point_ws;
int aa_point_ws_init(aa_point_ws *ws, const aa_scene *placed);
void aa_point_ws_free(aa_point_ws *ws);
void aa_point_row(const aa_scene *placed, aa_point_ws *ws, double dx, double y, double *row,
                  int w);

#endif
