/*
 * strokes.c: every join and cap stroked, exactly as patterns/README.md,
 * `strokes`, defines it.
 *
 * A grid of 4 rows by 3 columns over the unit square, cell (c, r) centred
 * at ((c + 1/2)/3, (r + 1/2)/4), each cell one white stroke of width w on
 * black, kept as a stroke (aa_scene_stroke: the exact outline plus its
 * source, so that peers stroke it with their own strokers):
 *
 *   - rows 0, 1, 2: a bent polyline of two segments of length L = 0.07
 *     meeting at a vertex where the direction turns by q (`turn`), joined
 *     miter (row 0), round (row 1), bevel (row 2): the points
 *     V - L (cos(q/2), -sin(q/2)), V, V + L (cos(q/2), sin(q/2)) (y down: a
 *     caret with V on top), V = (cx, cy - L sin(q/2)/2) so that the
 *     polyline's box is centred in the cell;
 *   - row 3: a circular arc of radius R = 0.08 sweeping A = 150 degrees,
 *     symmetric about the vertical through the cell centre and bulging up:
 *     centre (cx, cy + R (1 + sin 15 deg)/2), from angle 165 to 15 degrees
 *     (measured upwards from the x axis), so its box is centred too;
 *   - columns 0, 1, 2: caps butt, round, square.
 *
 * The miter limit is SVG's 4: a turn q has the miter ratio 1/cos(q/2)
 * (1/sin of half the angle between the segments), at most 2 for q <= 120
 * degrees, so miters are never cut.  The whole grid is turned by `rot`
 * degrees about the centre (1/2, 1/2) through the stroke's map, which
 * turns the outline and leaves its area alone.
 *
 * Known answer (patterns/README.md), h = w/2:
 *     bent line  2 w L - h^2 tan(q/2) + J,  J = h^2 tan(q/2) (miter),
 *                h^2 q / 2 (round), h^2 sin(q) / 2 (bevel);
 *     arc        w R A;
 *     plus per end 0 (butt), pi h^2 / 2 (round), w h (square).
 * Within the domain nothing of one stroke overlaps another part of it
 * (h tan(q/2) <= 0.025 tan 60 deg < L, and the caps point away from the
 * rest) and the strokes stay 0.05 or more inside their cells.
 */
#include "patterns.h"
#include "path.h"

#include <math.h>

enum { WIDTH, TURN, ROT };

#define STROKES_L 0.07
#define STROKES_R 0.08
#define STROKES_SWEEP 150.0

static const aa_param strokes_params[] = {
    {"width", AA_PARAM_REAL, 0.02, 0.0, 0.05, 1, NULL,
     "w, the stroke width (pattern units): (0, 0.05]"},
    {"turn", AA_PARAM_REAL, 50.0, 0.0, 120.0, 0, NULL,
     "q, the turn at the polylines' vertex in degrees: 0 to 120"},
    {"rot", AA_PARAM_REAL, 7.0, -180.0, 180.0, 0, NULL,
     "the whole grid's rotation about the centre in degrees"},
    {0}};

static int strokes_build(const double *p, aa_scene *s)
{
    const aa_rgb white = {{1, 1, 1}};
    const double q = p[TURN] * (M_PI / 180.0), rot = p[ROT] * (M_PI / 180.0);
    const double cr = cos(rot), sr = sin(rot);
    /* x' = cr x - sr y + tx, y' = sr x + cr y + ty, (1/2, 1/2) fixed */
    const double m[6] = {cr, sr, -sr, cr, 0.5 - 0.5 * cr + 0.5 * sr, 0.5 - 0.5 * sr - 0.5 * cr};
    static const aa_line_join joins[3] = {AA_JOIN_MITER, AA_JOIN_ROUND, AA_JOIN_BEVEL};
    static const aa_line_cap caps[3] = {AA_CAP_BUTT, AA_CAP_ROUND, AA_CAP_SQUARE};
    int st = AA_OK;
    for (int r = 0; r < 4 && !st; r++)
        for (int c = 0; c < 3 && !st; c++) {
            const double cx = (c + 0.5) / 3.0, cy = (r + 0.5) / 4.0;
            aa_stroke_style ss;
            aa_stroke_style_default(&ss);
            ss.width = p[WIDTH];
            ss.cap = caps[c];
            aa_path path;
            aa_path_init(&path);
            if (r < 3) {
                const double hc = cos(q / 2), hs = sin(q / 2), L = STROKES_L;
                const double vx = cx, vy = cy - L * hs / 2;
                ss.join = joins[r];
                if (!(st = aa_path_move_to(&path, vx - L * hc, vy + L * hs)) &&
                    !(st = aa_path_line_to(&path, vx, vy)))
                    st = aa_path_line_to(&path, vx + L * hc, vy + L * hs);
            } else {
                /* angles measured upwards: the point at a is
                 * (ox + R cos a, oy - R sin a), aa_edge's form with
                 * u = (R, 0), v = (0, -R) */
                const double R = STROKES_R, half = STROKES_SWEEP / 2 * (M_PI / 180.0);
                const double a0 = M_PI / 2 + half, a1 = M_PI / 2 - half;
                const double ox = cx, oy = cy + R * (1 + sin(M_PI / 2 - half)) / 2;
                if (!(st = aa_path_move_to(&path, ox + R * cos(a0), oy - R * sin(a0))))
                    st = aa_path_arc_to(&path, ox, oy, R, 0, 0, -R, a0, a1, ox + R * cos(a1),
                                        oy - R * sin(a1));
            }
            if (!st)
                st = aa_scene_stroke(s, &path, &ss, m, white);
            aa_path_free(&path);
        }
    return st;
}

const aa_pattern_type aa_pattern_strokes = {
    {"strokes",
     "every join (miter, round, bevel) and cap (butt, round, square) stroked, and arcs: "
     "a 4 x 3 grid of known areas",
     strokes_params},
    NULL,
    strokes_build,
    {{0, 0, 0}}};
