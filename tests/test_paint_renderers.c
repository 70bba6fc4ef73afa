/*
 * test_paint_renderers.c: translucent paint, paint order, currentColor,
 * visibility, CSS colours, strokes (joins, caps, a Bezier arc's exact
 * offsets, dashes, ellipses, a cusp), clip paths, and <use>, <symbol>,
 * nested <svg> (viewports that clip, clip-path on a use), CSS lengths,
 * style sheets and the cascade, the CSS transform property and path data
 * with an error, invalid declarations and attributes, font-size larger,
 * a symbol's reference point, the object bounding box of a group holding
 * a use and of a use, a symbol's x and y, transform-box stroke-box,
 * pathLength, the units rem, vw and vmin, conditional processing with
 * <switch>, clip-path's basic shapes and geometry boxes, a transform on the
 * root, calc(), var() and the CSS-wide keywords, as browsers draw them:
 * the exact box reference of the pattern svg against headless Chromium and resvg (and
 * librsvg) drawing the same document, colour by colour away from edges.
 *
 * The scene is one document of small cells, each one feature (the table
 * `cells` says which, and what each cell's colours are by CSS Color 4 and
 * SVG 2, worked by hand in its comment); each renderer draws it once.
 * Antialiasing aside, the renderers and the reference must show the same
 * colours in the same places: compared on the pixels whose 3 x 3
 * neighbourhood is of one colour in the reference, in sRGB-encoded values
 * (the renderers' 8-bit codes), within 2/255 (a code of rounding in the
 * renderer's own compositing and one of its output).  The reference's
 * colours in those pixels are checked first against the hand-worked
 * values, so the renderers are held to the specification, not to the
 * code under test.  Where a renderer draws a cell otherwise, the table
 * names the renderer and says who is wrong: that cell must still differ
 * (so the note stays true), and every other cell must agree.  Chromium
 * also draws what `export` writes of the document's scene (aa_scene_svg:
 * clipPaths, groups, strokes as strokes), every cell as the reference but
 * those noted "chromium-export".
 *
 * The renderers are run through their adapters (scripts/renderers/),
 * skipped with a message when not installed (sh scripts/install-deps.sh
 * --with-renderers), and in the plain build only: their pictures do not
 * depend on how aabench was built.
 */
/* tier: full */
#include "bench.h"
#include "core.h"
#include "patterns.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define CELL 40
#define COLS 4
#define ROWS 22
#define W (CELL * COLS)
#define H (CELL * ROWS)

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "paintrender");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* sRGB's encoding (IEC 61966-2-1), written out here. */
static double enc(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

/* A cell: its content (in cell coordinates, 0 to 40), and points of it
 * with their encoded colour by the specifications.  `differs` names the
 * renderers that draw it otherwise (space-separated), or "". */
typedef struct cell {
    const char *what, *body;
    struct {
        int x, y;
        double c[3];
    } at[4];
    int nat;
    const char *differs;
} cell;

static const cell cells[] = {
    /* 0.5 white over black: 0.5 */
    {"fill-opacity", "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"white\" "
                     "fill-opacity=\"0.5\"/>",
     {{20, 20, {0.5, 0.5, 0.5}}},
     1, ""},
    /* white at 0.5 (A), then red at 0.6 (B): B over A is
     * (0.6 + 0.4 x 0.5, 0.4 x 0.5, 0.4 x 0.5) */
    {"two translucent rectangles",
     "<rect x=\"4\" y=\"4\" width=\"22\" height=\"22\" fill=\"white\" opacity=\"0.5\"/>"
     "<rect x=\"14\" y=\"14\" width=\"22\" height=\"22\" fill=\"rgba(255, 0, 0, 0.6)\"/>",
     {{8, 8, {0.5, 0.5, 0.5}}, {20, 20, {0.8, 0.2, 0.2}}, {32, 32, {0.6, 0, 0}}},
     3, ""},
    /* a group of 0.5 over grey 0.2: inside it red hides blue; then
     * 0.5 g + 0.5 x 0.2 */
    {"group opacity",
     "<rect width=\"40\" height=\"40\" fill=\"rgb(20%, 20%, 20%)\"/><g opacity=\"0.5\">"
     "<rect x=\"4\" y=\"4\" width=\"22\" height=\"22\" fill=\"blue\"/>"
     "<rect x=\"14\" y=\"14\" width=\"22\" height=\"22\" fill=\"red\"/></g>",
     {{8, 8, {0.1, 0.1, 0.6}}, {20, 20, {0.6, 0.1, 0.1}}, {2, 2, {0.2, 0.2, 0.2}}},
     3, ""},
    /* fill and stroke under one opacity: a group, the stroke's inner
     * half hiding the fill: 0.5 white on the stroke, 0.5 blue inside */
    {"opacity of a fill and a stroke",
     "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\" fill=\"blue\" stroke=\"white\" "
     "stroke-width=\"8\" opacity=\"0.5\"/>",
     {{12, 20, {0.5, 0.5, 0.5}}, {20, 20, {0, 0, 0.5}}, {7, 20, {0.5, 0.5, 0.5}}},
     3, ""},
    /* paint-order: stroke: the fill over the stroke's inner half */
    {"paint-order",
     "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\" fill=\"blue\" stroke=\"white\" "
     "stroke-width=\"8\" paint-order=\"stroke\"/>",
     {{12, 20, {0, 0, 1}}, {7, 20, {1, 1, 1}}},
     2, ""},
    /* a stroke at 0.25 over blue: (0.25, 0.25, 1) */
    {"stroke-opacity",
     "<rect width=\"40\" height=\"40\" fill=\"blue\"/><rect x=\"8\" y=\"8\" width=\"24\" "
     "height=\"24\" fill=\"none\" stroke=\"white\" stroke-width=\"8\" "
     "stroke-opacity=\"0.25\"/>",
     {{8, 20, {0.25, 0.25, 1}}, {20, 20, {0, 0, 1}}},
     2, ""},
    /* currentColor inherited as the keyword: each element's own color
     * (resvg paints the top one red, the colour of the <g> that set the
     * fill: wrong by CSS Color 4, "currentcolor") */
    {"currentColor",
     "<g color=\"red\" fill=\"currentColor\"><rect x=\"4\" y=\"4\" width=\"32\" "
     "height=\"14\" color=\"lime\"/><rect x=\"4\" y=\"22\" width=\"32\" height=\"14\"/></g>",
     {{20, 10, {0, 1, 0}}, {20, 30, {1, 0, 0}}},
     2, "resvg"},
    /* visibility: hidden inherited, visible again on a child; display:
     * none hides its subtree whatever the children say */
    {"visibility and display",
     "<g fill=\"white\" visibility=\"hidden\"><rect x=\"4\" y=\"4\" width=\"14\" "
     "height=\"32\"/><rect x=\"22\" y=\"4\" width=\"14\" height=\"14\" "
     "visibility=\"visible\"/></g><g display=\"none\"><rect x=\"22\" y=\"22\" width=\"14\" "
     "height=\"14\" fill=\"white\" display=\"inline\"/></g>",
     {{10, 20, {0, 0, 0}}, {28, 10, {1, 1, 1}}, {28, 28, {0, 0, 0}}},
     3, ""},
    /* hsl() in the legacy form and the modern one without units: (0,
     * 0.5, 0); blue at 0.5; 180 degrees is cyan; 30 degrees (1, 0.5, 0) */
    {"hsl",
     "<rect width=\"20\" height=\"20\" fill=\"hsl(120, 100%, 25%)\"/>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"hsla(240, 100%, 50%, 0.5)\"/>"
     "<rect y=\"20\" width=\"20\" height=\"20\" fill=\"hsl(180 100% 50%)\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"HSL(30, 100%, 50%)\"/>",
     {{10, 10, {0, 0.5, 0}}, {30, 10, {0, 0, 0.5}}, {10, 30, {0, 1, 1}}, {30, 30, {1, 0.5, 0}}},
     4, ""},
    /* the hue as an angle (CSS Color 4, <hue> = <number> | <angle>): half
     * a turn and 180 degrees are cyan, 200 grad too, 0 rad red (resvg
     * draws them black: it takes no angle unit) */
    {"hue angles",
     "<rect width=\"20\" height=\"20\" fill=\"hsl(0.5turn 100% 50%)\"/>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"hsl(180deg, 100%, 50%)\"/>"
     "<rect y=\"20\" width=\"20\" height=\"20\" fill=\"hsl(200grad 100% 50%)\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"hsl(0rad 100% 50%)\"/>",
     {{10, 10, {0, 1, 1}}, {30, 10, {0, 1, 1}}, {10, 30, {0, 1, 1}}, {30, 30, {1, 0, 0}}},
     4, "resvg"},
    /* the modern form's alpha after "/": (1, 0.5, 0) at 0.5, blue at
     * 0.25, lime at 0.75, blue at 0.5 (resvg draws them black: it takes
     * no "/") */
    {"modern alpha",
     "<rect width=\"20\" height=\"20\" fill=\"rgb(100% 50% 0% / 0.5)\"/>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"hsl(240 100% 50% / 25%)\"/>"
     "<rect y=\"20\" width=\"20\" height=\"20\" fill=\"rgba(0 255 0 / 0.75)\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"rgb(0 0 255 / 50%)\"/>",
     {{10, 10, {0.5, 0.25, 0}}, {30, 10, {0, 0, 0.25}}, {10, 30, {0, 0.75, 0}}, {30, 30, {0, 0, 0.5}}},
     4, "resvg"},
    /* the modern form takes numbers and percentages mixed (CSS Color 4
     * since the working group's resolution of 2023): numbers for hsl()'s
     * saturation and lightness read as percentages, yellow and 40% grey;
     * rgb(50% 255 0) (resvg draws the hsl() white, librsvg all three
     * black: both older than the resolution) */
    {"modern numbers and percentages",
     "<rect width=\"40\" height=\"14\" fill=\"hsl(60 100 50)\"/>"
     "<rect y=\"14\" width=\"40\" height=\"13\" fill=\"hsl(0 0 40)\"/>"
     "<rect y=\"27\" width=\"40\" height=\"13\" fill=\"rgb(50% 255 0)\"/>",
     {{20, 7, {1, 1, 0}}, {20, 20, {0.4, 0.4, 0.4}}, {20, 33, {0.5, 1, 0}}},
     3, "resvg rsvg"},
    /* alpha in hex and in rgba(): #f008 red at 136/255, #00ff0080 lime at
     * 128/255, (1, 0.5, 0) at 0.5, transparent over white */
    {"alpha in colours",
     "<rect width=\"20\" height=\"20\" fill=\"#f008\"/>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"#00ff0080\"/>"
     "<rect y=\"20\" width=\"20\" height=\"20\" fill=\"rgba(100%, 50%, 0%, 0.5)\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"white\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"transparent\"/>",
     {{10, 10, {136 / 255.0, 0, 0}},
      {30, 10, {0, 128 / 255.0, 0}},
      {10, 30, {0.5, 0.25, 0}},
      {30, 30, {1, 1, 1}}},
     4, ""},
    /* nested groups multiply (0.25); a translucent layer inside a group
     * is composited inside it (0.5 x 0.5) */
    {"nested groups",
     "<g opacity=\"0.5\"><g opacity=\"0.5\"><rect x=\"4\" y=\"4\" width=\"14\" height=\"32\" "
     "fill=\"white\"/></g><rect x=\"22\" y=\"4\" width=\"14\" height=\"32\" fill=\"white\" "
     "fill-opacity=\"0.5\"/></g>",
     {{10, 20, {0.25, 0.25, 0.25}}, {28, 20, {0.25, 0.25, 0.25}}},
     2, ""},
    /* names in any case, rgb() clamped, currentColor in a stroke */
    {"names and clamping",
     "<rect width=\"20\" height=\"40\" fill=\"DarkOrange\"/>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"rgb(300, -20, 51)\"/>"
     "<rect x=\"24\" y=\"24\" width=\"12\" height=\"12\" fill=\"none\" stroke=\"currentColor\" "
     "stroke-width=\"8\" color=\"#ABCDEF\"/>",
     {{10, 20, {1, 140 / 255.0, 0}}, {30, 10, {1, 0, 0.2}}, {22, 30, {0xab / 255.0, 0xcd / 255.0, 0xef / 255.0}}},
     3, ""},
    /* strokes (SVG 2, "Stroke shape"), white 8 wide on the black ground:
     * a right-angled miter join (miter length sqrt 2 x 8, under the limit
     * 4 x 8) fills the corner square [4, 12]^2 of the path's corner (8, 8),
     * so pixel (5, 5) is white; the inside of the angle is black; the
     * vertical leg covers x in [4, 12] */
    {"miter join",
     "<polyline points=\"8,34 8,8 34,8\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"8\"/>",
     {{5, 5, {1, 1, 1}}, {20, 20, {0, 0, 0}}, {8, 20, {1, 1, 1}}},
     3, ""},
    /* round join and caps: the join is the disk of radius 4 about (8, 8),
     * so pixels [2, 5]^2 (at least 4.24 from it) are black where a miter
     * would be white at [4, 5]; the round cap at (34, 8) reaches pixel
     * (35, 7), whose 3 x 3 pixels lie within 3.61 of the end */
    {"round join and caps",
     "<polyline points=\"8,34 8,8 34,8\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"8\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>",
     {{3, 3, {0, 0, 0}}, {35, 7, {1, 1, 1}}, {8, 20, {1, 1, 1}}},
     3, ""},
    /* a stroked cubic Bezier arc, 6 wide (its exact offset curves in the
     * reference): B(1/2) = (20, 10.5) with a horizontal tangent and
     * curvature radius 1296/156 = 8.3 > 3, so pixels [18, 21] x [9, 12]
     * are inside; B(0.1) = (6.62, 22.98), unit normal (0.91, 0.41): pixels
     * [5, 8] x [21, 24] lie within 1.1 of it across the curve; the arch's
     * inside at (19, 19) is black */
    {"stroked cubic",
     "<path d=\"M 4 30 C 12 4 28 4 36 30\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"6\"/>",
     {{19, 10, {1, 1, 1}}, {6, 22, {1, 1, 1}}, {19, 19, {0, 0, 0}}},
     3, ""},
    /* dashes "8 4" along the line from (4, 20) to (36, 20), 6 wide: dashes
     * over x in [4, 12], [16, 24], [28, 36], gaps [12, 16], [24, 28] */
    {"dashes",
     "<line x1=\"4\" y1=\"20\" x2=\"36\" y2=\"20\" stroke=\"white\" "
     "stroke-width=\"6\" stroke-dasharray=\"8 4\"/>",
     {{7, 19, {1, 1, 1}}, {13, 19, {0, 0, 0}}, {19, 19, {1, 1, 1}}, {25, 19, {0, 0, 0}}},
     4, ""},
    /* The next four: a closed smooth path's stroke is the points within h
     * of it (each lies on the normal at its nearest point); the colours
     * below by the distance from 13 x 13 points over each pixel's 3 x 3
     * neighbourhood to the curve, found by sampling it at 20,000 points
     * (4,000 a side or corner for the rect, through the inverse of its
     * transform), every one within h - 0.05 (white) or beyond h + 0.05
     * (black); worked outside the code under test.
     * An ellipse of semi-axes 16 and 8, 6 wide (curvature radii 4 to 32,
     * over h = 3: no fold): the distances are at most 2.06 on pixels (20,
     * 12), (4, 20) and (20, 28), at least 5.9 at the centre (20, 20) */
    {"stroked ellipse",
     "<ellipse cx=\"20\" cy=\"20\" rx=\"16\" ry=\"8\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"6\"/>",
     {{20, 12, {1, 1, 1}}, {20, 20, {0, 0, 0}}, {4, 20, {1, 1, 1}}, {20, 28, {1, 1, 1}}},
     4, ""},
    /* semi-axes 16 and 3, 10 wide: the curvature radius at the ends is
     * 9/16, under h = 5, so the inner offset folds; distances at most 3.0
     * at the centre (20, 20), 3.5 at (2, 20), 2.6 at (10, 20); at least 6
     * at (20, 30) */
    {"thick stroke on a thin ellipse",
     "<ellipse cx=\"20\" cy=\"20\" rx=\"16\" ry=\"3\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"10\"/>",
     {{20, 20, {1, 1, 1}}, {20, 30, {0, 0, 0}}, {2, 20, {1, 1, 1}}, {10, 20, {1, 1, 1}}},
     4, ""},
    /* a rect with corners of radii 10 and 4, 4 wide, stretched by 1.5
     * down after stroking (SVG: the stroke is made in user units): in
     * user units the distances are at most 1.33 at pixel (20, 6), 1.78 at
     * (6, 8) in a corner, at least 8.6 at (20, 20) */
    {"rounded rect rx != ry, stretched",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"21\" rx=\"10\" ry=\"4\" fill=\"none\" "
     "stroke=\"white\" stroke-width=\"4\" transform=\"scale(1 1.5)\"/>",
     {{20, 6, {1, 1, 1}}, {20, 20, {0, 0, 0}}, {6, 8, {1, 1, 1}}},
     3, ""},
    /* a cubic with a cusp at B(1/2) = (20, 25), arriving straight down
     * ((6,4) (34,32) (6,32) (34,4): B' = 28 (3 (1 - 2t)^2, 3 (1 - 2t)) at
     * scale 1), 10 wide: the stroke is the union of the normal segments
     * (SVG 2; no join inside a segment), found by the feet of p on
     * B'/(1 - 2t) (test_bezstroke.c, test_cusp): pixel (20, 27), below
     * the tip and within 5 of it, is on no normal segment, so black, as
     * (20, 33) is; (20, 22) and (12, 12) are within 1.8 and 3.0 of their
     * feet, white.  Chromium, resvg and librsvg all draw a disk of radius h
     * about the cusp (a round end there, like a round join), so pixels
     * below the tip such as (16, 27) white: wrong by SVG 2, whose stroke
     * shape is the union of the normal segments, with joins only at
     * segment boundaries (PDF's stroke says the same: points where
     * segments happen to meet receive no special treatment) */
    {"cusp",
     "<path d=\"M 6 4 C 34 32 6 32 34 4\" fill=\"none\" stroke=\"white\" "
     "stroke-width=\"10\"/>",
     {{20, 27, {0, 0, 0}}, {20, 22, {1, 1, 1}}, {12, 12, {1, 1, 1}}, {20, 33, {0, 0, 0}}},
     4, "chromium chromium-export resvg rsvg"},
    /* Clip paths (CSS Masking 1).  A white square [4, 36]^2 clipped by the
     * disk of radius 12 at (20, 20): white at its centre, black at (6, 6)
     * (distance 19.8 from it) */
    {"clip-path",
     "<clipPath id=\"k1\"><circle cx=\"20\" cy=\"20\" r=\"12\"/></clipPath>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"white\" "
     "clip-path=\"url(#k1)\"/>",
     {{20, 20, {1, 1, 1}}, {6, 6, {0, 0, 0}}},
     2, ""},
    /* clip-rule evenodd: a red cell clipped by one path of the squares
     * [4, 24]^2 and [16, 36]^2: red in either alone, black where they
     * overlap (winding 2, even) */
    {"clip-rule evenodd",
     "<clipPath id=\"k2\"><path clip-rule=\"evenodd\" "
     "d=\"M4 4 H24 V24 H4 Z M16 16 H36 V36 H16 Z\"/></clipPath>"
     "<rect width=\"40\" height=\"40\" fill=\"red\" clip-path=\"url(#k2)\"/>",
     {{8, 8, {1, 0, 0}}, {20, 20, {0, 0, 0}}, {32, 32, {1, 0, 0}}},
     3, ""},
    /* clipPathUnits objectBoundingBox: the ellipse of semi-axes 16 and 8 at
     * (20, 20) has the box [4, 36] x [12, 28]; x in [0.5, 1] of it is its
     * right half: white at (28, 20), black at (12, 20) */
    {"clipPathUnits objectBoundingBox",
     "<clipPath id=\"k3\" clipPathUnits=\"objectBoundingBox\"><rect x=\"0.5\" "
     "width=\"0.5\" height=\"1\"/></clipPath>"
     "<ellipse cx=\"20\" cy=\"20\" rx=\"16\" ry=\"8\" fill=\"white\" "
     "clip-path=\"url(#k3)\"/>",
     {{28, 20, {1, 1, 1}}, {12, 20, {0, 0, 0}}},
     2, ""},
    /* objectBoundingBox under the clipPath's transform: the unit square
     * maps onto the box first, then the transform moves it in user units
     * (Chromium's and resvg's order): the ellipse's box [4, 36] x [12, 28],
     * x in [0, 1/4] of it is [4, 12], translated by 1/2 to [4.5, 12.5]:
     * white at (8, 20), black at (24, 20) (where [1/2, 3/4] of the box
     * would be, the transform taken in box units).  librsvg takes it in
     * box units and draws [20, 28]; CSS Masking 1 and SVG 1.1 do not put
     * the two in an order in words, and the reader follows the browser
     * (Chromium, with resvg) */
    {"objectBoundingBox and transform",
     "<clipPath id=\"k3t\" clipPathUnits=\"objectBoundingBox\" "
     "transform=\"translate(0.5 0)\"><rect width=\"0.25\" height=\"1\"/></clipPath>"
     "<ellipse cx=\"20\" cy=\"20\" rx=\"16\" ry=\"8\" fill=\"white\" "
     "clip-path=\"url(#k3t)\"/>",
     {{8, 20, {1, 1, 1}}, {24, 20, {0, 0, 0}}},
     2, "rsvg"},
    /* objectBoundingBox for a <use>: its box in the clip's user space,
     * which has the use's translate(x, y) in it: the target rect [0, 16] x
     * [0, 8] used at (12, 16); the box's left half [0, 8] lands on [12,
     * 20]: white at (16, 20), black at (24, 20) (the box taken in the
     * parent's space, [12, 28], would clip to [24, 32]) */
    {"objectBoundingBox of a use",
     "<clipPath id=\"k3u\" clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" "
     "height=\"1\"/></clipPath><defs><rect id=\"k3r\" width=\"16\" height=\"8\" "
     "fill=\"white\"/></defs><use href=\"#k3r\" x=\"12\" y=\"16\" clip-path=\"url(#k3u)\"/>",
     {{16, 20, {1, 1, 1}}, {24, 20, {0, 0, 0}}},
     2, ""},
    /* <use> in a clipPath: the rect [2, 14] x [3, 17] through the use's
     * transform translate(1, 2) and its x = 2, y = 1, so [5, 17] x [6, 20]:
     * white at (11, 13), black at (3, 4); the square ring [20, 36]^2 less
     * [24, 32]^2 by the use's clip-rule evenodd, which its target
     * inherits: white at (22, 22), black in the hole at (28, 28) */
    {"use in a clipPath",
     "<defs><rect id=\"ku1\" x=\"2\" y=\"3\" width=\"12\" height=\"14\" fill=\"red\"/>"
     "<path id=\"ku2\" d=\"M20 20 H36 V36 H20 Z M24 24 H32 V32 H24 Z\"/></defs>"
     "<clipPath id=\"ku\"><use href=\"#ku1\" x=\"2\" y=\"1\" transform=\"translate(1 2)\"/>"
     "<use href=\"#ku2\" clip-rule=\"evenodd\"/></clipPath>"
     "<rect width=\"40\" height=\"40\" fill=\"white\" clip-path=\"url(#ku)\"/>",
     {{11, 13, {1, 1, 1}}, {3, 4, {0, 0, 0}}, {22, 22, {1, 1, 1}}, {28, 28, {0, 0, 0}}},
     4, ""},
    /* a clipPath's <use> must name a shape itself (CSS Masking 1:
     * "Indirect references are an error"): a use of the use of [4, 18]^2
     * at x = 18 adds nothing, black at (29, 11) (resvg draws it: wrong by
     * the spec); the target's visibility visible overrides the hidden it
     * would inherit from the use: [4, 18] x [22, 36] white at (11, 29); a
     * use of display none adds nothing: black at (11, 11) */
    {"use of a use in a clipPath",
     "<defs><rect id=\"kv1\" x=\"4\" y=\"4\" width=\"14\" height=\"14\"/>"
     "<use id=\"kv2\" href=\"#kv1\" x=\"18\"/><rect id=\"kv3\" x=\"4\" y=\"22\" "
     "width=\"14\" height=\"14\" visibility=\"visible\"/></defs>"
     "<clipPath id=\"kv\"><use href=\"#kv2\"/><use href=\"#kv3\" visibility=\"hidden\"/>"
     "<use href=\"#kv1\" display=\"none\"/></clipPath>"
     "<rect width=\"40\" height=\"40\" fill=\"white\" clip-path=\"url(#kv)\"/>",
     {{29, 11, {0, 0, 0}}, {11, 29, {1, 1, 1}}, {11, 11, {0, 0, 0}}},
     3, "resvg"},
    /* objectBoundingBox of a cubic: its box is the curve's, not its control
     * points' (SVG 2, "Bounding boxes"): M 4 30 C 4 6, 36 6, 36 30 reaches
     * up to y(1/2) = (30 + 18 + 18 + 30)/8 = 12 (its controls to 6), so
     * the box's upper half is y < 21: white at (20, 19) and (20, 14),
     * black at (20, 25).  resvg takes the box of the control points
     * (upper half y < 18) and leaves (20, 19) black; Chromium and librsvg
     * take the curve's */
    {"objectBoundingBox of a cubic",
     "<clipPath id=\"k3c\" clipPathUnits=\"objectBoundingBox\"><rect width=\"1\" "
     "height=\"0.5\"/></clipPath>"
     "<path d=\"M 4 30 C 4 6, 36 6, 36 30 Z\" fill=\"white\" clip-path=\"url(#k3c)\"/>",
     {{20, 19, {1, 1, 1}}, {20, 14, {1, 1, 1}}, {20, 25, {0, 0, 0}}},
     3, "resvg"},
    /* a clipPath clipped in turn: the disk of radius 10 at (14, 20) within
     * the disk of radius 10 at (26, 20): white at (20, 20) (6 from each),
     * black at (8, 20) and (32, 20) (in one disk only).  librsvg ignores
     * the clip-path of the clipPath and draws the whole first disk, where
     * CSS Masking 1 ("The clipPath element": clip-path applies to it, the
     * clip's region intersected with the referenced one) and SVG 1.1
     * (14.3.5) say otherwise; Chromium and resvg draw the lens */
    {"clip path of a clip path",
     "<clipPath id=\"k4b\"><circle cx=\"26\" cy=\"20\" r=\"10\"/></clipPath>"
     "<clipPath id=\"k4\" clip-path=\"url(#k4b)\"><circle cx=\"14\" cy=\"20\" r=\"10\"/>"
     "</clipPath><rect width=\"40\" height=\"40\" fill=\"white\" "
     "clip-path=\"url(#k4)\"/>",
     {{20, 20, {1, 1, 1}}, {8, 20, {0, 0, 0}}, {32, 20, {0, 0, 0}}},
     3, "rsvg"},
    /* a group of opacity 0.5 clipped by the disk of radius 12: white at
     * 0.5 over black, 0.5 encoded, inside; black outside */
    {"clip-path on a group with opacity",
     "<clipPath id=\"k5\"><circle cx=\"20\" cy=\"20\" r=\"12\"/></clipPath>"
     "<g opacity=\"0.5\" clip-path=\"url(#k5)\"><rect width=\"40\" height=\"40\" "
     "fill=\"white\"/></g>",
     {{20, 20, {0.5, 0.5, 0.5}}, {3, 3, {0, 0, 0}}},
     2, ""},
    /* a member with its own clip-path: x < 20 within the disk of radius
     * 14 at (20, 20), and the disk of radius 4 at (32, 20): white at
     * (12, 20) and (32, 20); black at (12, 4) (17.9 from the centre) and
     * (26, 20) (right of x = 20, 6 from the small disk).  librsvg ignores
     * the child's clip-path (the whole rectangle x < 20 clips), where SVG
     * 1.1 (14.3.5: a child of a clipPath may have clip-path) and CSS
     * Masking 1 say otherwise; Chromium and resvg apply it */
    {"clipPath child with its own clip-path",
     "<clipPath id=\"k6d\"><circle cx=\"20\" cy=\"20\" r=\"14\"/></clipPath>"
     "<clipPath id=\"k6\"><rect width=\"20\" height=\"40\" clip-path=\"url(#k6d)\"/>"
     "<circle cx=\"32\" cy=\"20\" r=\"4\"/></clipPath>"
     "<rect width=\"40\" height=\"40\" fill=\"white\" clip-path=\"url(#k6)\"/>",
     {{12, 20, {1, 1, 1}}, {32, 20, {1, 1, 1}}, {12, 4, {0, 0, 0}}, {26, 20, {0, 0, 0}}},
     4, "rsvg"},
    /* a reference to no element is as if clip-path were not given (SVG
     * 1.1's clip-path: a reference that is not valid is "treated as if it
     * hadn't been specified"): the square drawn whole */
    {"clip-path to no element",
     "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\" fill=\"white\" "
     "clip-path=\"url(#k7none)\"/>",
     {{20, 20, {1, 1, 1}}, {4, 4, {0, 0, 0}}},
     2, ""},
    /* so is a reference to an element that is not a clipPath (the same;
     * the web-platform test css-masking/clip-path-svg-content/
     * clip-path-invalid-reference.svg draws its square): the red square
     * and the white one drawn whole.  resvg draws nothing of the white
     * square: it treats the reference as an error that hides the element,
     * which the specification does not say (Chromium and librsvg draw
     * it) */
    {"clip-path to a rectangle",
     "<rect id=\"k8r\" x=\"2\" y=\"2\" width=\"8\" height=\"8\" fill=\"red\"/>"
     "<rect x=\"14\" y=\"14\" width=\"20\" height=\"20\" fill=\"white\" "
     "clip-path=\"url(#k8r)\"/>",
     {{6, 6, {1, 0, 0}}, {24, 24, {1, 1, 1}}, {12, 12, {0, 0, 0}}},
     3, "resvg"},
    /* the clipPath's transform, translate(10 0), moves its child x in
     * [0, 10] to [10, 20]; a hidden child adds nothing: white at (15, 20),
     * black at (5, 20) and (30, 20) */
    {"clipPath transform and a hidden child",
     "<clipPath id=\"k9t\" transform=\"translate(10 0)\"><rect width=\"10\" "
     "height=\"40\"/><rect width=\"40\" height=\"40\" visibility=\"hidden\"/>"
     "</clipPath><rect width=\"40\" height=\"40\" fill=\"white\" "
     "clip-path=\"url(#k9t)\"/>",
     {{15, 20, {1, 1, 1}}, {5, 20, {0, 0, 0}}, {30, 20, {0, 0, 0}}},
     3, ""},
    /* a stroke clipped: the line across at y = 20, 8 wide, clipped by
     * x < 20: white at (10, 20), black at (30, 20) */
    {"clipped stroke",
     "<clipPath id=\"k10\"><rect width=\"20\" height=\"40\"/></clipPath>"
     "<line x1=\"2\" y1=\"20\" x2=\"38\" y2=\"20\" stroke=\"white\" "
     "stroke-width=\"8\" clip-path=\"url(#k10)\"/>",
     {{10, 20, {1, 1, 1}}, {30, 20, {0, 0, 0}}},
     2, ""},
    /* Structure, units, style sheets and the CSS transform property
     * (SVG 2, CSS Values 4, CSS Cascade 4, CSS Transforms 1). */
    /* a rect without a fill used twice: it inherits each use's fill;
     * [4, 18]^2 white, [20, 34]^2 red */
    {"use inherits",
     "<defs><rect id=\"u1\" width=\"14\" height=\"14\"/></defs>"
     "<use href=\"#u1\" x=\"4\" y=\"4\" fill=\"white\"/><use href=\"#u1\" x=\"20\" y=\"20\" "
     "fill=\"red\"/>",
     {{10, 10, {1, 1, 1}}, {27, 27, {1, 0, 0}}, {28, 10, {0, 0, 0}}},
     3, ""},
    /* xlink:href under the use's transform, then its x and y: scale(2) of
     * [2, 16]^2 is [4, 32]^2 */
    {"use transform",
     "<use xlink:href=\"#u1\" transform=\"scale(2)\" x=\"2\" y=\"2\" fill=\"lime\"/>",
     {{20, 20, {0, 1, 0}}, {36, 36, {0, 0, 0}}, {30, 30, {0, 1, 0}}},
     3, ""},
    /* a symbol of viewBox 0 0 10 10 at (4, 4), 32 x 32: scale 3.2, its
     * disk of radius 5 about (5, 5) is the disk of radius 16 about
     * (20, 20) */
    {"symbol viewBox",
     "<symbol id=\"s1\" viewBox=\"0 0 10 10\"><circle cx=\"5\" cy=\"5\" r=\"5\" "
     "fill=\"lime\"/></symbol><use href=\"#s1\" x=\"4\" y=\"4\" width=\"32\" height=\"32\"/>",
     {{20, 20, {0, 1, 0}}, {6, 6, {0, 0, 0}}, {33, 20, {0, 1, 0}}},
     3, ""},
    /* a nested svg at (4, 4), 32 x 32, viewBox 0 0 20 10, xMinYMax meet:
     * scale min(1.6, 3.2) = 1.6, the box 32 x 16 at the bottom: y from
     * 20; the rect 50% (of the viewBox's 20: 10) x 100% (10) is
     * [4, 20] x [20, 36] */
    {"nested svg",
     "<svg x=\"4\" y=\"4\" width=\"32\" height=\"32\" viewBox=\"0 0 20 10\" "
     "preserveAspectRatio=\"xMinYMax meet\"><rect width=\"50%\" height=\"100%\" "
     "fill=\"aqua\"/></svg>",
     {{12, 28, {0, 1, 1}}, {12, 12, {0, 0, 0}}, {28, 28, {0, 0, 0}}},
     3, ""},
    /* absolute units at 96 px to the inch: x 0.1in = 9.6, y 5mm = 18.9,
     * width 18pt = 24, height 1pc = 16: [9.6, 33.6] x [18.9, 34.9] */
    {"units",
     "<rect x=\"0.1in\" y=\"5mm\" width=\"18pt\" height=\"1pc\" fill=\"white\"/>",
     {{20, 26, {1, 1, 1}}, {20, 14, {0, 0, 0}}, {5, 26, {0, 0, 0}}},
     3, ""},
    /* em of an inherited font-size of 8px: [4, 28] x [8, 20] */
    {"em",
     "<g font-size=\"8px\"><rect x=\"0.5em\" y=\"1em\" width=\"3em\" height=\"1.5em\" "
     "fill=\"yellow\"/></g>",
     {{16, 14, {1, 1, 0}}, {16, 30, {0, 0, 0}}, {34, 14, {0, 0, 0}}},
     3, ""},
    /* specificity: .c7 rect (0, 1, 1) red; .c7 > .b (0, 2, 0) lime over
     * it; #c7x (1, 0, 0) blue; .c7 rect.i yellow !important over the
     * style attribute's aqua (resvg paints that one aqua: wrong by CSS
     * Cascade 4, where an important declaration beats every normal one,
     * the style attribute's included; Chromium and librsvg agree) */
    {"sheet specificity",
     "<style>.c7 rect { fill: red } .c7 > .b { fill: lime } #c7x { fill: blue } "
     ".c7 rect.i { fill: yellow !important }</style><g class=\"c7\">"
     "<rect x=\"1\" y=\"1\" width=\"18\" height=\"18\"/>"
     "<rect class=\"b\" x=\"21\" y=\"1\" width=\"18\" height=\"18\"/>"
     "<rect id=\"c7x\" class=\"b\" x=\"1\" y=\"21\" width=\"18\" height=\"18\"/>"
     "<rect class=\"i\" style=\"fill: aqua\" x=\"21\" y=\"21\" width=\"18\" height=\"18\"/></g>",
     {{10, 10, {1, 0, 0}}, {30, 10, {0, 1, 0}}, {10, 30, {0, 0, 1}}, {30, 30, {1, 1, 0}}},
     4, "resvg"},
    /* a rule over the presentation attribute (lime, not red); the style
     * attribute over the rule (blue) */
    {"attribute and style",
     "<style>.c8 { fill: lime }</style><rect class=\"c8\" fill=\"red\" x=\"4\" y=\"4\" "
     "width=\"14\" height=\"32\"/><rect class=\"c8\" style=\"fill: blue\" x=\"22\" y=\"4\" "
     "width=\"14\" height=\"32\"/>",
     {{10, 20, {0, 1, 0}}, {28, 20, {0, 0, 1}}},
     2, ""},
    /* transform in a style: translateX(0.1in) scale(2, 1.5) of the rect
     * 12 x 20: [9.6, 33.6] x [0, 30] (resvg ignores transform in a style;
     * librsvg 2.54.7 drops a translation in inches, though CSS Values 4
     * makes every absolute length valid there, and with it the whole
     * declaration: both draw the rect untransformed, wrong) */
    {"CSS transform",
     "<rect width=\"12\" height=\"20\" fill=\"white\" style=\"transform: translateX(0.1in) "
     "scale(2, 1.5)\"/>",
     {{20, 15, {1, 1, 1}}, {5, 15, {0, 0, 0}}, {20, 36, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* rotate(90) about transform-origin (20, 20): (x, y) -> (40 - y, x),
     * the rect [10, 30] x [4, 12] to [28, 36] x [10, 30] (resvg and
     * librsvg ignore transform-origin, a presentation attribute in SVG 2
     * and a property of CSS Transforms 1, and rotate about (0, 0), out of
     * the cell: wrong) */
    {"transform-origin",
     "<rect x=\"10\" y=\"4\" width=\"20\" height=\"8\" fill=\"white\" transform=\"rotate(90)\" "
     "transform-origin=\"20 20\"/>",
     {{32, 20, {1, 1, 1}}, {20, 8, {0, 0, 0}}},
     2, "resvg rsvg"},
    /* transform-box fill-box: scale(0.5) about the centre (20, 20) of
     * the rect [4, 36]^2: [12, 28]^2 (resvg and librsvg draw the rect
     * whole: wrong by CSS Transforms 1) */
    {"transform-box",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"lime\" style=\"transform-box: "
     "fill-box; transform-origin: center; transform: scale(0.5)\"/>",
     {{20, 20, {0, 1, 0}}, {8, 8, {0, 0, 0}}, {25, 14, {0, 1, 0}}},
     3, "resvg rsvg"},
    /* path data drawn up to its error: the second subpath is the
     * triangle (4, 24), (36, 24), (36, 36) (the L with "x" dropped); at
     * x = 8 its diagonal is at y = 25.5 */
    {"path error",
     "<path fill=\"white\" d=\"M 4 4 L 36 4 L 36 20 L 4 20 Z M 4 24 L 36 24 L 36 36 L 4 x\"/>",
     {{20, 12, {1, 1, 1}}, {32, 27, {1, 1, 1}}, {8, 34, {0, 0, 0}}},
     3, ""},
    /* overflow visible: the nested svg's content beyond its 10 x 10 is
     * drawn */
    {"overflow visible",
     "<svg x=\"4\" y=\"4\" width=\"10\" height=\"10\" overflow=\"visible\"><rect width=\"32\" "
     "height=\"32\" fill=\"aqua\"/></svg>",
     {{30, 30, {0, 1, 1}}, {8, 8, {0, 1, 1}}, {38, 20, {0, 0, 0}}},
     3, ""},
    /* a use of its own ancestor (in error: nothing) and of a missing
     * element (nothing); the rest draws (librsvg 2.54.7 draws one copy of
     * the group at (20, 20) before it stops: wrong by SVG 2, "The 'use'
     * element": a use whose target is its ancestor is in error and not
     * rendered; Chromium and resvg draw nothing) */
    {"use in error",
     "<g id=\"c14\"><rect x=\"2\" y=\"2\" width=\"16\" height=\"16\" fill=\"fuchsia\"/>"
     "<use href=\"#c14\" x=\"20\" y=\"20\"/></g><use href=\"#nothing\"/>",
     {{10, 10, {1, 0, 1}}, {30, 30, {0, 0, 0}}},
     2, "rsvg"},
    /* %: of the nearest viewport's width, height and normalised
     * diagonal; here a nested svg of 40 x 20: r = 25% of sqrt((40^2 +
     * 20^2)/2) = 7.9, the disk about (50% of 40, 50% of 20) = (20, 10) */
    {"percentages",
     "<svg width=\"40\" height=\"20\"><circle cx=\"50%\" cy=\"50%\" r=\"25%\" "
     "fill=\"white\"/></svg>",
     {{20, 10, {1, 1, 1}}, {20, 4, {1, 1, 1}}, {20, 30, {0, 0, 0}}},
     3, ""},
    /* a nested svg of overflow hidden (the initial value) clips: the
     * rect [0, 40]^2 drawn in the viewport [8, 24] x [8, 32] shows only
     * there (SVG 2, "The effect of the 'overflow' property") */
    {"viewport clip",
     "<svg x=\"8\" y=\"8\" width=\"16\" height=\"24\"><rect x=\"-8\" y=\"-8\" width=\"40\" "
     "height=\"40\" fill=\"lime\"/></svg>",
     {{16, 20, {0, 1, 0}}, {4, 4, {0, 0, 0}}, {30, 20, {0, 0, 0}}},
     3, ""},
    /* a symbol of viewBox 0 0 10 10 used at (4, 12), 32 x 16: meet
     * scales by min(3.2, 1.6) = 1.6 and centres the viewBox 8 right, on
     * [12, 28]^2; its rect [-5, 15]^2 lands on [4, 36]^2 and the viewport
     * [4, 36] x [12, 28] (not the viewBox) keeps [4, 36] x [12, 28]
     * (librsvg 2.54.7 draws the rect whole: wrong by SVG 2, whose user
     * agent style sheet gives symbol overflow hidden; Chromium and resvg
     * clip it) */
    {"symbol clip",
     "<symbol id=\"vs2\" viewBox=\"0 0 10 10\"><rect x=\"-5\" y=\"-5\" width=\"20\" "
     "height=\"20\" fill=\"aqua\"/></symbol><use href=\"#vs2\" x=\"4\" y=\"12\" "
     "width=\"32\" height=\"16\"/>",
     {{8, 20, {0, 1, 1}}, {20, 20, {0, 1, 1}}, {20, 6, {0, 0, 0}}, {20, 33, {0, 0, 0}}},
     4, "rsvg"},
    /* a group's clip-path (the disk of radius 14 about (20, 20)) around a
     * viewport [10, 30]^2 rotated 30 degrees about (20, 20): their
     * intersection; the centre is yellow, the cell's corners and the
     * disk's edge beyond the square black */
    {"viewport in a clip",
     "<clipPath id=\"vc3\"><circle cx=\"20\" cy=\"20\" r=\"14\"/></clipPath>"
     "<g clip-path=\"url(#vc3)\"><g transform=\"rotate(30 20 20)\"><svg x=\"10\" "
     "y=\"10\" width=\"20\" height=\"20\"><rect x=\"-20\" y=\"-20\" width=\"60\" "
     "height=\"60\" fill=\"yellow\"/></svg></g></g>",
     {{20, 20, {1, 1, 0}}, {2, 2, {0, 0, 0}}, {20, 37, {0, 0, 0}}},
     3, ""},
    /* clip-path on a use, in its user space with translate(8, 8): the
     * square [0, 16]^2 there is [8, 24]^2, over the rect [8, 38]^2 */
    {"use clip-path",
     "<clipPath id=\"vc4\"><rect width=\"16\" height=\"16\"/></clipPath><defs><rect "
     "id=\"vr4\" width=\"30\" height=\"30\" fill=\"white\"/></defs><use href=\"#vr4\" "
     "x=\"8\" y=\"8\" clip-path=\"url(#vc4)\"/>",
     {{20, 20, {1, 1, 1}}, {30, 30, {0, 0, 0}}, {4, 4, {0, 0, 0}}},
     3, ""},
    /* objectBoundingBox of a group holding a nested svg at (8, 8): its
     * content through translate(8, 8), unclipped: the rect [-8, 24] x
     * [0, 24] there is [0, 32] x [8, 32], the unit rect [1/4, 1/2] x
     * [0, 1] on it [8, 16] x [8, 32] */
    {"box through a viewport",
     "<clipPath id=\"vo5\" clipPathUnits=\"objectBoundingBox\"><rect x=\"0.25\" "
     "width=\"0.25\" height=\"1\"/></clipPath><g clip-path=\"url(#vo5)\"><svg x=\"8\" "
     "y=\"8\" width=\"24\" height=\"24\"><rect x=\"-8\" width=\"32\" height=\"24\" "
     "fill=\"white\"/></svg></g>",
     {{12, 20, {1, 1, 1}}, {20, 20, {0, 0, 0}}, {4, 20, {0, 0, 0}}},
     3, ""},
    /* invalid declarations are ignored (CSS 2.1, 4.2), the cascade going
     * on: the earlier declaration (lime), the earlier rule (blue), the
     * presentation attribute (yellow), the parent's fill (red) (resvg
     * paints all four black: wrong by CSS; Chromium agrees) */
    {"invalid declarations",
     "<style>.c56 { fill: blue } .c56 { fill: bogus }</style><g fill=\"red\">"
     "<rect x=\"2\" y=\"2\" width=\"16\" height=\"16\" style=\"fill: lime; fill: bogus\"/>"
     "<rect class=\"c56\" x=\"22\" y=\"2\" width=\"16\" height=\"16\"/>"
     "<rect x=\"2\" y=\"22\" width=\"16\" height=\"16\" style=\"fill: bogus\" "
     "fill=\"yellow\"/><rect x=\"22\" y=\"22\" width=\"16\" height=\"16\" "
     "style=\"fill: 12px\"/></g>",
     {{10, 10, {0, 1, 0}}, {30, 10, {0, 0, 1}}, {10, 30, {1, 1, 0}}, {30, 30, {1, 0, 0}}},
     4, "resvg"},
    /* an invalid presentation attribute is its property's initial value
     * (SVG 2, "Attribute syntax": "the attribute is assumed to have been
     * specified as the given initial value"): fill black under a red
     * group, on white (Chromium takes the attribute as absent and paints
     * the parent's red, and so does librsvg: wrong by SVG 2; resvg agrees) */
    {"invalid attribute",
     "<rect width=\"40\" height=\"40\" fill=\"white\"/><g fill=\"red\"><rect x=\"8\" "
     "y=\"8\" width=\"24\" height=\"24\" fill=\"bogus\"/></g>",
     {{20, 20, {0, 0, 0}}, {4, 4, {1, 1, 1}}},
     2, "chromium rsvg"},
    /* font-size larger of 10px: 12px (the ratio 1.2), so 2em x 2.5em at
     * (4, 4) is [4, 28] x [4, 34] */
    {"font-size larger",
     "<g font-size=\"10px\"><rect x=\"4\" y=\"4\" width=\"2em\" height=\"2.5em\" "
     "fill=\"white\" font-size=\"larger\"/></g>",
     {{16, 20, {1, 1, 1}}, {32, 20, {0, 0, 0}}, {16, 37, {0, 0, 0}}},
     3, ""},
    /* a symbol's reference point (SVG 2, "The 'symbol' element": refX,
     * refY) at the use's (20, 20): viewBox 0 0 10 10 on 16 x 16, its
     * centre at (20, 20), the rect on [12, 28]^2 (Chromium, resvg and
     * librsvg ignore refX and refY and draw it on [20, 36]^2: wrong by
     * SVG 2) */
    {"symbol refX",
     "<symbol id=\"c59\" viewBox=\"0 0 10 10\" refX=\"center\" refY=\"center\"><rect "
     "width=\"10\" height=\"10\" fill=\"aqua\"/></symbol><use href=\"#c59\" x=\"20\" "
     "y=\"20\" width=\"16\" height=\"16\"/>",
     {{14, 14, {0, 1, 1}}, {20, 20, {0, 1, 1}}, {31, 31, {0, 0, 0}}},
     3, "chromium resvg rsvg"},
    /* a symbol's own x and y (SVG 2 gives <symbol> x, y, width, height,
     * laid out as a nested svg's): the viewport 16 x 16 at the symbol's
     * (10, 5) from the use's (4, 4), [14, 30] x [9, 25], clips the rect
     * 20 x 20: white at (22, 17), black at (8, 17), (22, 7) and (32, 20)
     * (resvg and librsvg ignore x and y and draw the rect from (4, 4),
     * white at the second and third: wrong by SVG 2) */
    {"symbol x and y",
     "<symbol id=\"sxy\" x=\"10\" y=\"5\" width=\"16\" height=\"16\"><rect width=\"20\" "
     "height=\"20\" fill=\"white\"/></symbol><use href=\"#sxy\" x=\"4\" y=\"4\"/>",
     {{22, 17, {1, 1, 1}}, {8, 17, {0, 0, 0}}, {22, 7, {0, 0, 0}}, {32, 20, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* objectBoundingBox of a group holding a use: the box [8, 32]^2 (the
     * used rect), its left half [8, 20] kept */
    {"box with a use",
     "<clipPath id=\"c60\" clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" "
     "height=\"1\"/></clipPath><defs><rect id=\"c60r\" width=\"24\" height=\"24\" "
     "fill=\"lime\"/></defs><g clip-path=\"url(#c60)\"><rect x=\"8\" y=\"8\" width=\"2\" "
     "height=\"24\" fill=\"lime\"/><use href=\"#c60r\" x=\"8\" y=\"8\"/></g>",
     {{14, 20, {0, 1, 0}}, {26, 20, {0, 0, 0}}},
     2, ""},
    /* transform-box stroke-box: the rect [10, 22]^2 stroked 4 wide has the
     * stroke box [8, 24]^2; scale(1.5) about its corner (8, 8): the stroke
     * on [8, 32]^2, its inner edge (12 and 20) at 14 and 26, lime inside
     * (resvg and librsvg ignore transform-box and scale about (0, 0):
     * wrong by CSS Transforms 1) */
    {"stroke-box",
     "<rect x=\"10\" y=\"10\" width=\"12\" height=\"12\" fill=\"lime\" stroke=\"blue\" "
     "stroke-width=\"4\" style=\"transform-box: stroke-box; transform-origin: 0 0; "
     "transform: scale(1.5)\"/>",
     {{20, 20, {0, 1, 0}}, {10, 20, {0, 0, 1}}, {30, 20, {0, 0, 1}}, {35, 20, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* pathLength (SVG 2): a line of 32 given as 16, so "2 2" dashes 4 on,
     * 4 off from x = 4: [4, 8] white, [8, 12] not (Chromium draws it so;
     * resvg and librsvg 2.54 ignore pathLength and dash 2 on, 2 off: [6,
     * 8] black and [10, 12] white, wrong by SVG 2) */
    {"pathLength",
     "<path d=\"M4 20 H36\" stroke=\"white\" stroke-width=\"12\" pathLength=\"16\" "
     "stroke-dasharray=\"2 2\"/>",
     {{6, 20, {1, 1, 1}}, {10, 20, {0, 0, 0}}, {22, 20, {1, 1, 1}}, {26, 20, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* rem, vw and vmin (CSS Values 4): 1rem is the root's font-size, 16px
     * (none set), 10vw and 10vmin a tenth of the 160 px wide view (its
     * smaller side): three white bars 16 wide (Chromium draws them so, the
     * document inline in a page whose root's font-size is 16px, the page
     * as wide as the view; resvg and librsvg 2.54 draw none: they take no
     * rem, vw or vmin, wrong by CSS Values 4) */
    {"rem and vw",
     "<g fill=\"white\"><rect x=\"4\" y=\"4\" width=\"1rem\" height=\"8\"/>"
     "<rect x=\"4\" y=\"16\" width=\"10vw\" height=\"8\"/>"
     "<rect x=\"4\" y=\"28\" width=\"10vmin\" height=\"8\"/></g>",
     {{12, 8, {1, 1, 1}}, {12, 20, {1, 1, 1}}, {12, 32, {1, 1, 1}}, {26, 20, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* conditional processing (SVG 2): the switch draws its first child
     * whose systemLanguage holds, "en" (lime); requiredExtensions of an
     * extension no renderer has is false, an empty systemLanguage too,
     * requiredFeatures always true (Chromium and resvg draw it so, their
     * language English; librsvg 2.54 takes its language from the locale,
     * here not English, so draws the blue, and holds the unknown extension
     * true, drawing the top right white: wrong by SVG 2) */
    {"switch and conditions",
     "<switch><rect width=\"20\" height=\"20\" fill=\"red\" systemLanguage=\"fr\"/>"
     "<rect width=\"20\" height=\"20\" fill=\"lime\" systemLanguage=\"de, en\"/>"
     "<rect width=\"20\" height=\"20\" fill=\"blue\"/></switch>"
     "<rect x=\"20\" width=\"20\" height=\"20\" fill=\"white\" "
     "requiredExtensions=\"http://example.org/x\"/>"
     "<rect y=\"20\" width=\"20\" height=\"20\" fill=\"white\" systemLanguage=\"\"/>"
     "<rect x=\"20\" y=\"20\" width=\"20\" height=\"20\" fill=\"white\" "
     "requiredFeatures=\"http://www.w3.org/TR/SVG11/feature#Shape\"/>",
     {{10, 10, {0, 1, 0}}, {30, 10, {0, 0, 0}}, {10, 30, {0, 0, 0}}, {30, 30, {1, 1, 1}}},
     4, "rsvg"},
    /* clip-path: circle(25% at 25% 50%) on the rect [4, 36] x [4, 28]
     * (no stroke: its stroke-box, the default box, is its fill box, 32 x
     * 24): the radius 25% of the box's normalised diagonal sqrt((32^2 +
     * 24^2) / 2) = 28.28, so 7.07, about (4 + 8, 4 + 12) = (12, 16) (CSS
     * Shapes 1): white there, black at (22, 16) and (12, 26) (resvg and
     * librsvg 2.54 draw no basic shape nor geometry box: they ignore the
     * clip-path, drawing the element unclipped, in this cell and the
     * next ones) */
    {"clip-path: circle()",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"24\" fill=\"white\" "
     "style=\"clip-path: circle(25% at 25% 50%)\"/>",
     {{12, 16, {1, 1, 1}}, {22, 16, {0, 0, 0}}, {12, 26, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* ellipse(closest-side farthest-side at 12px 10px) on the rect [4,
     * 36]^2: the centre (16, 14), rx the nearer side's 12, ry the farther
     * side's 22: white at (6, 14) ((9.5 / 12)^2 < 1) and (16, 30) ((16.5 /
     * 22)^2 < 1), black at (32, 14) (16.5 / 12 > 1) */
    {"clip-path: ellipse()",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"white\" "
     "style=\"clip-path: ellipse(closest-side farthest-side at 12px 10px)\"/>",
     {{6, 14, {1, 1, 1}}, {16, 30, {1, 1, 1}}, {32, 14, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* inset(2px 4px round 10px 0) of the stroke-box (the default) of the
     * rect [4, 36]^2 stroked 6 wide in red, [1, 39]^2: [5, 35] x [3, 37],
     * its top left and bottom right corners of radius 10 (centre (15,
     * 13)), the others square: red at (20, 4) and in the square top right
     * corner (33, 4), black at (5, 3) (more than 11 from the corner's
     * centre), white inside; with fill-box the red at (20, 4) would be
     * cut */
    {"clip-path: inset() round",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"white\" stroke=\"red\" "
     "stroke-width=\"6\" style=\"clip-path: inset(2px 4px round 10px 0)\"/>",
     {{20, 4, {1, 0, 0}}, {33, 4, {1, 0, 0}}, {5, 3, {0, 0, 0}}, {20, 20, {1, 1, 1}}},
     4, "resvg rsvg"},
    /* polygon(evenodd, ...) of two squares of the box [0, 40]^2, [4,
     * 24]^2 and [16, 36]^2, joined at their corners (the joining edge
     * there and back): their overlap [16, 24]^2 is covered twice, so
     * outside under evenodd: white at (8, 8) and (30, 30), black at (20,
     * 20) and (32, 8) */
    {"clip-path: polygon() evenodd",
     "<rect width=\"40\" height=\"40\" fill=\"white\" style=\"clip-path: polygon(evenodd, "
     "10% 10%, 60% 10%, 60% 60%, 10% 60%, 10% 10%, 40% 40%, 90% 40%, 90% 90%, 40% 90%, "
     "40% 40%)\"/>",
     {{8, 8, {1, 1, 1}}, {30, 30, {1, 1, 1}}, {20, 20, {0, 0, 0}}, {32, 8, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* path(evenodd, ...) in the fill-box of the rect [4, 36]^2, its
     * coordinates from the box's corner (4, 4): the ring between [4, 36]^2
     * and [12, 28]^2: white at (6, 6) and (10, 10) (which would be in the
     * hole were the path not moved to the box), black at (20, 20) */
    {"clip-path: path() in fill-box",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"white\" "
     "style=\"clip-path: path(evenodd, 'M0 0 H32 V32 H0 Z M8 8 H24 V24 H8 Z') fill-box\"/>",
     {{6, 6, {1, 1, 1}}, {10, 10, {1, 1, 1}}, {20, 20, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* a geometry box alone: fill-box keeps the rect [10, 30] x [4, 18]
     * and the inner half of its red stroke 8 wide, [10, 14] (red at 12),
     * cutting the outer half (black at 7); stroke-box keeps the whole
     * stroke (red at 7 in the second rect) */
    {"clip-path: fill-box and stroke-box",
     "<rect x=\"10\" y=\"4\" width=\"20\" height=\"14\" fill=\"white\" stroke=\"red\" "
     "stroke-width=\"8\" clip-path=\"fill-box\"/>"
     "<rect x=\"10\" y=\"28\" width=\"20\" height=\"6\" fill=\"white\" stroke=\"red\" "
     "stroke-width=\"8\" style=\"clip-path: stroke-box\"/>",
     {{12, 11, {1, 0, 0}}, {7, 11, {0, 0, 0}}, {20, 11, {1, 1, 1}}, {7, 31, {1, 0, 0}}},
     4, "resvg rsvg"},
    /* view-box: the nearest viewport's viewBox (the root's, 160 x 880 px,
     * at the origin of the cell's user space): circle(10px at 20px 20px)
     * there on a rect of the cell: white at (20, 20), black at (20, 34) */
    {"clip-path: view-box",
     "<rect width=\"40\" height=\"40\" fill=\"white\" "
     "style=\"clip-path: circle(10px at 20px 20px) view-box\"/>",
     {{20, 20, {1, 1, 1}}, {20, 34, {0, 0, 0}}, {34, 20, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* calc(), max() (CSS Values 4) in a 40 x 40 nested svg: the top rect
     * 50% + 2px = 22 wide, white; the bottom one max(10px, 50%) = 20
     * wide at opacity 25% * 2 = 0.5, white at 0.5 over black: 0.5 (resvg
     * and librsvg 2.54 read no math function: no width, nothing drawn,
     * wrong by CSS Values 4) */
    {"calc()",
     "<svg width=\"40\" height=\"40\"><rect width=\"calc(50% + 2px)\" height=\"20\" "
     "fill=\"white\"/><rect y=\"20\" width=\"max(10px, 50%)\" height=\"20\" fill=\"white\" "
     "style=\"opacity: calc(25% * 2)\"/></svg>",
     {{10, 10, {1, 1, 1}}, {30, 10, {0, 0, 0}}, {10, 30, {0.5, 0.5, 0.5}}, {30, 30, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* calc() in a stroke's width (20: y in [0, 20]) and dashes (10 on, 10
     * off from x = 0), and in the transform property: the lime rect [0,
     * 10] moved by 20 (resvg and librsvg 2.54 stroke 1 wide, undashed,
     * and leave the rect at 0: wrong by CSS Values 4) */
    {"calc() in strokes and transforms",
     "<path d=\"M0 10 H40\" stroke=\"white\" stroke-width=\"calc(10px * 2)\" "
     "stroke-dasharray=\"calc(5px + 5px) 10\"/><rect y=\"24\" width=\"10\" height=\"12\" "
     "fill=\"lime\" style=\"transform: translate(calc(10px + 10px), 0)\"/>",
     {{5, 10, {1, 1, 1}}, {15, 10, {0, 0, 0}}, {25, 30, {0, 1, 0}}, {5, 30, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* var() (CSS Custom Properties 1) under a blue group declaring --c
     * lime and --w 5px: a rect var(--c), 5px * 4 = 20 wide (lime at (10,
     * 10)); fill: var(--nope) over fill="red" and a cycle --a, --b are
     * invalid at computed-value time, so unset, the group's blue (at
     * (30, 10) and (10, 30)); var(--nope, white) the fallback (resvg and
     * librsvg 2.54 read no var(): wrong by CSS) */
    {"var()",
     "<g style=\"--c: lime; --w: 5px\" fill=\"blue\"><rect width=\"calc(var(--w) * 4)\" "
     "height=\"20\" fill=\"var(--c)\"/><rect y=\"20\" width=\"20\" height=\"20\" "
     "style=\"--a: var(--b); --b: var(--a); fill: var(--a)\"/><rect x=\"20\" y=\"20\" "
     "width=\"20\" height=\"20\" style=\"fill: var(--nope, white)\"/><rect x=\"20\" "
     "width=\"20\" height=\"20\" fill=\"red\" style=\"fill: var(--nope)\"/></g>",
     {{10, 10, {0, 1, 0}}, {30, 10, {0, 0, 1}}, {10, 30, {0, 0, 1}}, {30, 30, {1, 1, 1}}},
     4, "resvg rsvg"},
    /* CSS Cascade 4's keywords: opacity="inherit" under a group of 0.5 is
     * a group of 0.5 in it: white at 0.5, 0.5: 0.25; transform: inherit
     * takes the group's translate(10 0) again, the lime rect [10, 20] at
     * [30, 40]; opacity: unset is 1 (not inherited): 0.5 of the group
     * alone; transform: initial is none, over the attribute's translate(40
     * 0): white at (30, 30) (resvg ignores transform: inherit, librsvg
     * 2.54 it and transform: initial: wrong by CSS) */
    {"inherit, initial, unset",
     "<g opacity=\"0.5\"><rect width=\"20\" height=\"20\" fill=\"white\" opacity=\"inherit\"/>"
     "</g><g transform=\"translate(10 0)\"><rect x=\"10\" width=\"10\" height=\"20\" "
     "fill=\"lime\" style=\"transform: inherit\"/></g><g opacity=\"0.5\"><rect y=\"20\" "
     "width=\"20\" height=\"20\" fill=\"white\" style=\"opacity: unset\"/></g><rect x=\"20\" "
     "y=\"20\" width=\"20\" height=\"20\" fill=\"white\" transform=\"translate(40 0)\" "
     "style=\"transform: initial\"/>",
     {{10, 10, {0.25, 0.25, 0.25}}, {35, 10, {0, 1, 0}}, {10, 30, {0.5, 0.5, 0.5}},
      {30, 30, {1, 1, 1}}},
     4, "resvg rsvg"},
    /* clip-path on a nested svg (the last of its row: Chromium draws
     * beyond it, into the cell to its right), in the user space it establishes (the
     * viewBox's 16 units onto 32 px at (4, 4)): the rect [8, 28] x [4, 12]
     * is [20, 60] x [12, 28] in the cell, within the viewport [4, 36]^2, so
     * white on [20, 36] x [12, 28] only; (24, 8) would be white were the
     * clip in the parent's user space, (38, 20) were the viewport's clip
     * dropped (Chromium clips in the viewBox's space but drops the
     * viewport's clip, overflow hidden, when a clip-path is given: wrong by
     * SVG 2, "The effect of the 'overflow' property"; resvg clips by the
     * clip path in both the svg's user space and the parent's, [8, 28] x
     * [4, 12] here, and the two do not meet, so it draws nothing of the
     * cell (that rect under viewBox 0 0 50 50 onto 100 x 100 px at the
     * origin: resvg draws 48 px, [16, 28] x [8, 12], the rect in both
     * spaces intersected, where SVG 2 has 640); librsvg clips in the parent's user space, taking the
     * clipPath's units for the element's x, y, width and height, where
     * its content is not; the last cell, as Chromium's white beyond it
     * falls on the empty cell to its right) */
    {"clip-path on a nested svg",
     "<clipPath id=\"c64\"><rect x=\"8\" y=\"4\" width=\"20\" height=\"8\"/></clipPath>"
     "<svg x=\"4\" y=\"4\" width=\"32\" height=\"32\" viewBox=\"0 0 16 16\" "
     "clip-path=\"url(#c64)\"><rect x=\"-50\" y=\"-50\" width=\"100\" height=\"100\" "
     "fill=\"white\"/></svg>",
     {{28, 20, {1, 1, 1}}, {38, 20, {0, 0, 0}}, {24, 8, {0, 0, 0}}, {12, 20, {0, 0, 0}}},
     4, "chromium resvg rsvg"},
    /* xywh(4px 2px 50% 10px) of the rect [4, 36] x [4, 20]: [8, 24] x
     * [6, 16]; rect(2px auto 10px 50%) of the rect [4, 36] x [24, 36]:
     * top 2, right the box's right edge, bottom 10, left 16 from the
     * corner: [20, 36] x [26, 34]: white at (16, 10) and (28, 30), black
     * at (30, 10) and (12, 30) */
    {"clip-path: xywh() and rect()",
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"16\" fill=\"white\" "
     "style=\"clip-path: xywh(4px 2px 50% 10px)\"/>"
     "<rect x=\"4\" y=\"24\" width=\"32\" height=\"12\" fill=\"white\" "
     "style=\"clip-path: rect(2px auto 10px 50%)\"/>",
     {{16, 10, {1, 1, 1}}, {28, 30, {1, 1, 1}}, {30, 10, {0, 0, 0}}, {12, 30, {0, 0, 0}}},
     4, "resvg rsvg"},
    /* a basic shape on a group, in its fill-box (the object bounding box
     * [8, 32]^2): circle(50% at 0 0), radius 12 about (8, 8): white at
     * (12, 12), black at (28, 28) and (20, 8) */
    {"clip-path: circle() on a group",
     "<g style=\"clip-path: circle(50% at 0 0) fill-box\"><rect x=\"8\" y=\"8\" width=\"24\" "
     "height=\"24\" fill=\"white\"/></g>",
     {{12, 12, {1, 1, 1}}, {28, 28, {0, 0, 0}}, {22, 9, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* a group's stroke-box (the default box): its child's rect [10, 30]^2
     * stroked 8 wide in red, [6, 34]^2; inset(0 50% 0 0) keeps [6, 20] x
     * [6, 34]: red at (8, 20) (fill-box would cut it), white at (16, 20),
     * black at (25, 20) */
    {"clip-path: a group's stroke-box",
     "<g style=\"clip-path: inset(0 50% 0 0)\" stroke=\"red\" stroke-width=\"8\"><rect "
     "x=\"10\" y=\"10\" width=\"20\" height=\"20\" fill=\"white\"/></g>",
     {{8, 20, {1, 0, 0}}, {16, 20, {1, 1, 1}}, {25, 20, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* a use's stroke-box, in its space after translate(4, 4): its target's
     * [6, 26]^2 stroked 8 wide, [2, 30]^2; inset(0 50% 0 0) keeps x < 16
     * there, 20 in the cell: red at (8, 20) (fill-box would cut it),
     * white at (17, 20), black at (24, 20) */
    {"clip-path: a use's stroke-box",
     "<defs><rect id=\"r80\" x=\"6\" y=\"6\" width=\"20\" height=\"20\" fill=\"white\" "
     "stroke=\"red\" stroke-width=\"8\"/></defs><use href=\"#r80\" x=\"4\" y=\"4\" "
     "style=\"clip-path: inset(0 50% 0 0)\"/>",
     {{8, 20, {1, 0, 0}}, {17, 20, {1, 1, 1}}, {24, 20, {0, 0, 0}}},
     3, "resvg rsvg"},
    /* requiredFormats and requiredFonts (SVG 1.1 Tiny, not in SVG 2): true
     * in all three, the first child of each switch drawn, lime */
    {"requiredFormats and requiredFonts",
     "<switch><rect width=\"40\" height=\"20\" fill=\"lime\" requiredFormats=\"image/x-none\"/>"
     "<rect width=\"40\" height=\"20\" fill=\"red\"/></switch><switch><rect y=\"20\" "
     "width=\"40\" height=\"20\" fill=\"lime\" requiredFonts=\"NoSuchFont\"/><rect y=\"20\" "
     "width=\"40\" height=\"20\" fill=\"red\"/></switch>",
     {{20, 10, {0, 1, 0}}, {20, 30, {0, 1, 0}}},
     2, ""},
};

/* clip-path on a used symbol, as on the nested svg above, the use's x
 * and y placing its viewport (Chromium and resvg clip it in the viewBox's
 * space, as the reference; Chromium again drops the viewport's clip;
 * librsvg paints white outside the viewport, at (1, 1)): a document of
 * its own, as librsvg, given this cell among the others, drew five other
 * cells otherwise (cells holding clip paths, uses and a nested svg; alone
 * they agree) */
static const cell symbol_cells[] = {
    {"clip-path on a symbol",
     "<clipPath id=\"c65\"><rect x=\"8\" y=\"4\" width=\"20\" height=\"8\"/></clipPath>"
     "<symbol id=\"s65\" viewBox=\"0 0 16 16\" clip-path=\"url(#c65)\"><rect x=\"-50\" "
     "y=\"-50\" width=\"100\" height=\"100\" fill=\"white\"/></symbol>"
     "<use href=\"#s65\" x=\"4\" y=\"4\" width=\"32\" height=\"32\"/>",
     {{28, 20, {1, 1, 1}}, {38, 20, {0, 0, 0}}, {24, 8, {0, 0, 0}}, {12, 20, {0, 0, 0}}},
     4, "chromium rsvg"},
};

/* A transform on the root <svg>: rotate(180), about the centre of its
 * layout box (CSS Transforms 1's initial transform-origin, 50% 50%, for an
 * element with a layout box; Chromium turns it so), which maps the view
 * onto itself; the cell is written in the last cell's place, so that it
 * lands on the first, turned half a turn: the rect [4, 16] x [4, 24]
 * written is [24, 36] x [16, 36] drawn, white at (30, 26), black at (8,
 * 8) and (20, 10).  resvg turns it about the origin (0, 0), inside its
 * viewBox map, out of the view: it draws nothing, wrong by CSS Transforms
 * 1 (the root has a layout box, its transform-origin initially 50% 50%);
 * librsvg 2.54 turns it about the origin too, outside the viewBox map, and
 * draws nothing either */
static const cell root_cells[] = {
    {"transform on the root",
     "<rect x=\"4\" y=\"4\" width=\"12\" height=\"20\" fill=\"white\"/>",
     {{30, 26, {1, 1, 1}}, {8, 8, {0, 0, 0}}, {20, 10, {0, 0, 0}}},
     3, "resvg rsvg"},
};

/* The table drawn: cells, then symbol_cells, then root_cells with the
 * root's attributes root_attrs, each in the place of the cell numbered
 * from the last (each test runs on all three). */
static const cell *tab = cells;
static size_t ntab = sizeof cells / sizeof cells[0];
static const char *root_attrs = "";
#define NCELLS ntab

/* Run body on each table in turn. */
static void each_table(void (*body)(void *), void *arg)
{
    tab = cells, ntab = sizeof cells / sizeof cells[0];
    body(arg);
    tab = symbol_cells, ntab = sizeof symbol_cells / sizeof symbol_cells[0];
    body(arg);
    tab = root_cells, ntab = sizeof root_cells / sizeof root_cells[0];
    root_attrs = " transform=\"rotate(180)\"";
    body(arg);
    tab = cells, ntab = sizeof cells / sizeof cells[0], root_attrs = "";
}

/* The file name of the table drawn, after "paint" */
static const char *table_name(void)
{
    return tab == cells ? "" : tab == symbol_cells ? "-symbol" : "-root";
}

/* The document of every cell, and its box reference. */
static void document(char *path, size_t len, aa_image *ref)
{
    static char doc[1 << 15];
    size_t n = (size_t)snprintf(doc, sizeof doc,
                                "<svg xmlns=\"http://www.w3.org/2000/svg\" "
                                "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" "
                                "height=\"%d\"%s>\n<rect width=\"%d\" height=\"%d\"/>\n",
                                W, H, root_attrs, W, H);
    for (size_t k = 0; k < NCELLS; k++) {
        const size_t at = *root_attrs ? COLS * ROWS - 1 - k : k;
        n += (size_t)snprintf(doc + n, sizeof doc - n,
                              "<g transform=\"translate(%d %d)\">%s</g>\n",
                              (int)(at % COLS) * CELL, (int)(at / COLS) * CELL, tab[k].body);
    }
    n += (size_t)snprintf(doc + n, sizeof doc - n, "</svg>\n");
    assert_true(n < sizeof doc);
    snprintf(path, len, "%s/paint%s.svg", dir, table_name());
    support_write_file(path, doc, n);
    char spec[4200];
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    support_view v = {W, H, 0, 0, 0, NULL, 1, 0, 0};
    support_pattern_reference(spec, &v, ref, NULL, NULL);
}

/* 1 if the reference is of one colour (to 1e-12, its bound) on pixel
 * (i, j)'s 3 x 3 neighbourhood inside the view. */
static int flat(const aa_image *ref, int i, int j)
{
    if (i < 1 || j < 1 || i > W - 2 || j > H - 2)
        return 0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++)
            for (int k = 0; k < 3; k++)
                if (!(fabs(aa_pixel(ref, i + di, j + dj)[k] - aa_pixel(ref, i, j)[k]) <= 1e-12))
                    return 0;
    return 1;
}

/* The reference holds the hand-worked colours. */
static void reference_table(void *arg)
{
    (void)arg;
    char path[4200];
    aa_image ref;
    document(path, sizeof path, &ref);
    for (size_t k = 0; k < NCELLS; k++)
        for (int a = 0; a < tab[k].nat; a++) {
            int i = (int)(k % COLS) * CELL + tab[k].at[a].x;
            int j = (int)(k / COLS) * CELL + tab[k].at[a].y;
            if (!flat(&ref, i, j))
                fail_msg("%s: point (%d, %d) is not inside a region", tab[k].what,
                         tab[k].at[a].x, tab[k].at[a].y);
            for (int c = 0; c < 3; c++) {
                double got = enc(aa_pixel(&ref, i, j)[c]), want = tab[k].at[a].c[c];
                if (!(fabs(got - want) <= 1e-12))
                    fail_msg("%s: (%d, %d) channel %d is %.15g encoded, not %.15g",
                             tab[k].what, tab[k].at[a].x, tab[k].at[a].y, c, got, want);
            }
        }
    aa_image_free(&ref);
}

static void test_reference(void **state)
{
    (void)state;
    each_table(reference_table, NULL);
}

/* The largest encoded difference on the flat pixels of cell k. */
static double cell_error(const aa_image *ref, const aa_image *img, size_t k, int *wi, int *wj)
{
    double worst = 0;
    int x0 = (int)(k % COLS) * CELL, y0 = (int)(k / COLS) * CELL;
    for (int j = y0; j < y0 + CELL; j++)
        for (int i = x0; i < x0 + CELL; i++) {
            if (!flat(ref, i, j))
                continue;
            for (int c = 0; c < 3; c++) {
                double d = fabs(enc(aa_pixel(ref, i, j)[c]) - enc(aa_pixel(img, i, j)[c]));
                if (d > worst)
                    worst = d, *wi = i - x0, *wj = j - y0;
            }
        }
    return worst;
}

/* The paint document's scene written back as SVG (aa_scene_svg, what
 * `export` writes: clipPaths, groups, strokes as strokes) into path. */
static void exported(const char *doc, char *path, size_t len)
{
    char spec[4300];
    snprintf(spec, sizeof spec, "svg:file=%s", doc);
    aa_spec sp;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &sp) != AA_OK || aa_pattern_scene_at(&sp, W, H, &sc) != AA_OK)
        fail_msg("%s", aa_last_error());
    aa_scene *placed = aa_scene_place(sc, W, H, 0, 0, 0);
    assert_non_null(placed);
    snprintf(path, len, "%s/exported.svg", dir);
    if (aa_scene_svg_write(path, placed, W, H, AA_SVG_COLOURS, NULL) != AA_OK)
        fail_msg("%s", aa_last_error());
    aa_scene_free(placed);
    aa_scene_free(sc);
}

/* The renderer `name` on the paint document, or (export) on its scene
 * written back as SVG, against the reference cell by cell. */
typedef struct renderer_arg {
    const char *name;
    int export;
} renderer_arg;

static void renderer_table(void *arg)
{
    const char *name = ((const renderer_arg *)arg)->name;
    const int export = ((const renderer_arg *)arg)->export;
#if defined(__SANITIZE_ADDRESS__)
    print_message("%s: tested in the plain build\n", name);
    skip();
#endif
    const char *tree = aa_source_tree();
    if (!tree) {
        print_message("%s skipped: no source tree (its adapters)\n", name);
        skip();
    }
    char adapter[4200], cmd[13000], path[4200], png[4300];
    snprintf(adapter, sizeof adapter, "%s/scripts/renderers/%s", tree, name);
    assert_null(strchr(adapter, '\''));
    assert_null(strchr(dir, '\''));
    snprintf(cmd, sizeof cmd, "'%s' --check >/dev/null 2>&1", adapter);
    if (system(cmd) != 0) {
        print_message("%s skipped: not installed (sh scripts/install-deps.sh "
                      "--with-renderers)\n",
                      name);
        skip();
    }
    aa_image ref, img;
    document(path, sizeof path, &ref);
    if (export) {
        char doc[4200];
        snprintf(doc, sizeof doc, "%s", path);
        exported(doc, path, sizeof path);
    }
    snprintf(png, sizeof png, "%s/%s%s.png", dir, name, table_name());
    snprintf(cmd, sizeof cmd, "'%s' '%s' %d %d '%s' >/dev/null", adapter, path, W, H, png);
    if (system(cmd) != 0)
        fail_msg("%s failed on %s", name, path);
    if (aa_image_read(png, &img))
        fail_msg("%s", aa_last_error());
    assert_int_equal(img.w, W);
    assert_int_equal(img.h, H);
    int bad = 0;
    for (size_t k = 0; k < NCELLS; k++) {
        int i = 0, j = 0;
        double e = cell_error(&ref, &img, k, &i, &j);
        /* on what export writes, the cells noted "chromium-export" */
        const int agrees = e <= 2.0 / 255 + 1e-9,
                  known = support_names(tab[k].differs, export ? "chromium-export" : name);
        print_message("%s, %s: largest difference %.1f/255 at (%d, %d)%s\n", name,
                      tab[k].what, e * 255, i, j,
                      agrees ? "" : known ? " (the renderer is wrong: noted)" : " DIFFERS");
        if (agrees == known) {
            print_message("%s, %s: %s\n", name, tab[k].what,
                          known ? "agrees, but the table says it differs" : "differs");
            bad++;
        }
    }
    aa_image_free(&img);
    aa_image_free(&ref);
    if (bad)
        fail_msg("%s: %d cells not as the table says", name, bad);
}

static void renderer_on(const char *name, int export)
{
    renderer_arg a = {name, export};
    each_table(renderer_table, &a);
}

static void renderer(const char *name) { renderer_on(name, 0); }

static void test_chromium(void **state)
{
    (void)state;
    renderer("chromium");
}

/* Chromium on what `export` writes of the same scene: every cell as the
 * reference but those the table notes "chromium-export" (the cusp, a
 * stroke Chromium strokes itself; the cells Chromium reads wrong from the
 * document, a symbol's refX or an invalid attribute, are right there: the
 * scene written holds their geometry, none of the feature), so the
 * written clipPaths, groups and strokes mean what the scene means. */
static void test_chromium_export(void **state)
{
    (void)state;
    renderer_on("chromium", 1);
}

static void test_resvg(void **state)
{
    (void)state;
    renderer("resvg");
}

static void test_rsvg(void **state)
{
    (void)state;
    renderer("rsvg");
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_reference), cmocka_unit_test(test_chromium),
             cmocka_unit_test(test_chromium_export),
             cmocka_unit_test(test_resvg), cmocka_unit_test(test_rsvg))
