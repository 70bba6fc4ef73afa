/*
 * test_gradient_renderers.c: gradient paint (linearGradient,
 * radialGradient) read by the pattern svg, against headless Chromium and
 * resvg drawing the same documents, and against colours worked by hand
 * from SVG 2's definitions.
 *
 * Four documents of small cells, each one feature (the tables below, each
 * cell's hand-worked colours in its comment): the linear gradients, the
 * radial ones, several gradients at a point (radial over linear, two
 * radial ones, a fading linear one over a radial one) and many (eight
 * translucent ones at a point; one cone-case gradient on two overlapping
 * shapes; Chromium and resvg only), all drawn by the
 * exact box reference (patterns/README.md,
 * "Gradients").  The reference's colours at the cells' points are first checked against the hand-worked
 * values, to 2e-3 in encoded values (the pixel's mean in linear light
 * against the colour at its centre: for a ramp of slope s per pixel they
 * differ by about (decode'' / decode') s^2 / 24 in encoded values, 1e-3
 * at most here, for the radial reflect's slope of 1/12 at 0.36), so the
 * renderers are held to the specification.
 *
 * Then each renderer's image is compared on the pixels where the picture
 * is smooth: the reference's encoded values' second differences along x
 * and along y, over the pixel's 3 x 3 neighbourhood, under 6/255 (an
 * edge or a sharp stop gives tenths; a radial ramp of radius r bends by
 * about 1 / (r rho) at a distance rho from its centre); every point of
 * the table must be among them.  The tolerance is 3/255 in encoded values:
 * the renderers interpolate stops in 8-bit or single-precision values and
 * round their output (one code each), and Chromium's Skia dithers
 * gradients (a code more); a wrong spread, focal point, unit, map or
 * stop is off by tens of codes.  Where a renderer draws a cell otherwise,
 * `differs` names it and the comment says who is wrong; the cell must then
 * differ and every other cell agree.
 *
 * The peers with gradients of their own (cairo, agg: test_peers) draw
 * every cell, one document a cell, and three cells more; each is held on
 * the smooth pixels to an allowance derived from its library's gradient
 * arithmetic (peer_quantum) plus the centre-against-box-mean difference
 * read from the reference (centre_allowance), not fitted to what they
 * draw; a peer named in a cell's `differs` must refuse that cell, naming
 * why.
 *
 * Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets it
 * for the tests), where the renderers are not run, a declared subset: the
 * points of the document of many gradients are checked on its rows 16 to 27
 * alone (a viewBox of the same document: the rows through both of its points
 * and their neighbourhoods), not on its whole image, whose eight translucent
 * gradients are most of the reference's time here.  The rows left out take
 * the same code paths with other numbers (tests/README.md, "Tiers", says how
 * that was checked); the sanitizers find memory and undefined-behaviour
 * errors along the paths taken, and the plain build runs every case.
 */
/* tier: full */
#include "bench.h"
#include "core.h"
#include "patterns.h"
#include "peer.h"
#include "support.h"
#include "tier.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#define CELL 40
#define COLS 3
#define ROWS 3
#define W (CELL * COLS)
#define H (CELL * ROWS)

/* the rows of the document of many gradients the subset draws */
#define MANY_Y0 16
#define MANY_ROWS 12

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "gradrender");
}

/* The box references of the documents drawn so far, by their text: the
 * same document is drawn by the reference for its points, for each peer
 * and for each renderer, and computed once a process (the reference is
 * most of this test's CPU). */
typedef struct drawn {
    char *text;
    aa_image ref;
} drawn;
static drawn *memo;
static size_t nmemo;

static int teardown(void **state)
{
    (void)state;
    for (size_t k = 0; k < nmemo; k++) {
        free(memo[k].text);
        aa_image_free(&memo[k].ref);
    }
    free(memo);
    return support_rmtree(dir);
}

static void image_copy(const aa_image *from, aa_image *to)
{
    assert_int_equal(aa_image_alloc(to, from->w, from->h, from->c), AA_OK);
    memcpy(to->v, from->v, (size_t)from->w * from->h * from->c * sizeof *from->v);
}

/* The document `text` (m bytes) written to path, its box reference at
 * w x h into ref: computed the first time, copied from the memo after. */
static void reference_of(const char *text, size_t m, const char *path, int w, int h,
                         aa_image *ref)
{
    support_write_file(path, text, m);
    for (size_t k = 0; k < nmemo; k++)
        if (memo[k].ref.w == w && memo[k].ref.h == h && strcmp(memo[k].text, text) == 0) {
            image_copy(&memo[k].ref, ref);
            return;
        }
    char spec[4200];
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    support_view v = {w, h, 0, 0, 0, NULL, 1, 0, 0};
    support_pattern_reference(spec, &v, ref, NULL, NULL);
    drawn *grown = realloc(memo, (nmemo + 1) * sizeof *memo);
    assert_non_null(grown);
    memo = grown;
    memo[nmemo].text = strdup(text);
    assert_non_null(memo[nmemo].text);
    image_copy(ref, &memo[nmemo].ref);
    nmemo++;
}

/* sRGB's encoding (IEC 61966-2-1), written out here. */
static double enc(double v)
{
    if (v <= 0)
        return 0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

typedef struct cell {
    const char *what, *body;
    struct {
        int x, y;
        double c[3];
    } at[3];
    int nat;
    const char *differs;
} cell;

/* Cells in cell coordinates (0 to 40), over black.  The black-to-white
 * ramp's encoded value is t itself; a pixel's centre is (x + 1/2, y +
 * 1/2). */
#define BW "<stop offset=\"0\" stop-color=\"black\"/><stop offset=\"1\" stop-color=\"white\"/>"
static const cell linear[] = {
    /* objectBoundingBox (the default) on [4, 36]^2, from its left to its
     * right side: t = (x + 1/2 - 4) / 32; at x = 20, 0.515625 */
    {"linear, objectBoundingBox",
     "<linearGradient id=\"l1\">" BW "</linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l1)\"/>",
     {{20, 20, {0.515625, 0.515625, 0.515625}}},
     1, ""},
    /* userSpaceOnUse from x = 4 to 36, three stops red, lime (50%), blue:
     * at x = 10, t = 6.5/32 = 0.203125, 0.40625 of the way from red to
     * lime: (0.59375, 0.40625, 0) */
    {"linear, userSpaceOnUse, three stops",
     "<linearGradient id=\"l2\" gradientUnits=\"userSpaceOnUse\" x1=\"4\" y1=\"0\" x2=\"36\" "
     "y2=\"0\"><stop offset=\"0\" stop-color=\"red\"/><stop offset=\"50%\" "
     "stop-color=\"lime\"/><stop offset=\"1\" stop-color=\"blue\"/></linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l2)\"/>",
     {{10, 20, {0.59375, 0.40625, 0}}},
     1, ""},
    /* reflect, the vector half the box (16 px): at x = 26, t = 22.5 / 16
     * = 1.40625, reflected 0.59375 */
    {"linear, reflect",
     "<linearGradient id=\"l3\" x2=\"0.5\" spreadMethod=\"reflect\">" BW "</linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l3)\"/>",
     {{26, 20, {0.59375, 0.59375, 0.59375}}},
     1, ""},
    /* repeat: the same t, 0.40625 */
    {"linear, repeat",
     "<linearGradient id=\"l4\" x2=\"0.5\" spreadMethod=\"repeat\">" BW "</linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l4)\"/>",
     {{26, 20, {0.40625, 0.40625, 0.40625}}},
     1, ""},
    /* gradientTransform rotate(90) in the box's units: the vector from
     * (0, 0) to (0, 1), top to bottom: at y = 10, t = 6.5 / 32 */
    {"linear, gradientTransform",
     "<linearGradient id=\"l5\" gradientTransform=\"rotate(90)\">" BW "</linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l5)\"/>",
     {{20, 10, {0.203125, 0.203125, 0.203125}}},
     1, ""},
    /* href: l1's stops, its own x1 = 1 and x2 = 0 (right to left): at
     * x = 20, t = 1 - 0.515625; xlink:href alike, with l1's vector */
    {"href and xlink:href",
     "<linearGradient id=\"l6\" href=\"#l1\" x1=\"1\" x2=\"0\"/>"
     "<linearGradient id=\"l6b\" xlink:href=\"#l6\" x1=\"0\" x2=\"1\"/>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"14\" fill=\"url(#l6)\"/>"
     "<rect x=\"4\" y=\"22\" width=\"32\" height=\"14\" fill=\"url(#l6b)\"/>",
     {{20, 10, {0.484375, 0.484375, 0.484375}}, {20, 28, {0.515625, 0.515625, 0.515625}}},
     2, ""},
    /* a stroke painted by l1 in the box of the geometry [8, 32]^2 (not
     * the stroke's): t = (x + 1/2 - 8) / 24; at x = 20, 0.5208333;
     * at x = 5, t < 0: black (pad) */
    {"stroke with a gradient",
     "<rect x=\"8\" y=\"8\" width=\"24\" height=\"24\" fill=\"none\" stroke=\"url(#l1)\" "
     "stroke-width=\"8\"/>",
     {{20, 6, {12.5 / 24, 12.5 / 24, 12.5 / 24}}, {5, 20, {0, 0, 0}}},
     2, ""},
    /* stop-opacity 0.5 at both stops, white to blue, over red: at x = 20,
     * t = 0.515625, the stop colour (1 - t, 1 - t, 1) at 0.5 over red:
     * (0.5 (1 - t) + 0.5, 0.5 (1 - t), 0.5) */
    {"stop-opacity over another layer",
     "<linearGradient id=\"l8\"><stop offset=\"0\" stop-color=\"white\" stop-opacity=\"0.5\"/>"
     "<stop offset=\"1\" stop-color=\"blue\" stop-opacity=\"0.5\"/></linearGradient>"
     "<rect width=\"40\" height=\"40\" fill=\"red\"/>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#l8)\"/>",
     {{20, 20, {0.7421875, 0.2421875, 0.5}}},
     1, ""},
    /* a missing gradient with a fallback colour (lime), one stop (a
     * colour: red), no stops (none: black shows) */
    {"fallback, one stop, no stops",
     "<linearGradient id=\"l9\"><stop stop-color=\"red\"/></linearGradient>"
     "<linearGradient id=\"l9b\"/>"
     "<rect x=\"4\" y=\"4\" width=\"14\" height=\"32\" fill=\"url(#nothing) lime\"/>"
     "<rect x=\"22\" y=\"4\" width=\"14\" height=\"14\" fill=\"url(#l9)\"/>"
     "<rect x=\"22\" y=\"22\" width=\"14\" height=\"14\" fill=\"url(#l9b)\"/>",
     {{10, 20, {0, 1, 0}}, {28, 10, {1, 0, 0}}, {28, 28, {0, 0, 0}}},
     3, ""},
};

#define WB "<stop offset=\"0\" stop-color=\"white\"/><stop offset=\"1\" stop-color=\"black\"/>"
static const cell radial[] = {
    /* centred on [4, 36]^2: centre (20, 20), r = 16, white to black: at
     * pixel (26, 20) the centre is 6.519 away (hypot(6.5, 0.5)), t =
     * 0.40744, encoded 1 - t */
    {"radial, centred",
     "<radialGradient id=\"r1\">" WB "</radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#r1)\"/>",
     {{26, 20, {0.59256, 0.59256, 0.59256}}},
     1, ""},
    /* the focal point at (0.25, 0.5) of the box, F = (12, 20), the end
     * circle C = (20, 20), r = 16: the point q lies on the circle of
     * centre F + t (C - F) and radius 16 t, so with q - F = (17.5, 0.5)
     * at pixel (29, 20), (17.5 - 8 t)^2 + 0.25 = 256 t^2, 192 t^2 + 280 t
     * - 306.5 = 0, t = (-280 + sqrt(313792)) / 384 = 0.72961, white to
     * black: 0.27039 */
    {"radial, focal point",
     "<radialGradient id=\"r2\" fx=\"0.25\">" WB "</radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#r2)\"/>",
     {{29, 20, {0.27039, 0.27039, 0.27039}}},
     1, ""},
    /* repeat with a focal radius: fr = 0.1 (3.2 px), r = 0.4 (12.8 px),
     * so t = (rho - 3.2) / 9.6 about the centre; at pixel (31, 31), rho =
     * hypot(11.5, 11.5) = 16.2635: t = 1.36078, repeated 0.36078, white to
     * black: 0.63922.  resvg draws it as if fr were 0 (t = rho / 12.8: 44
     * codes off at rho = 6, exactly that ramp): it does not read SVG 2's
     * fr, so resvg is wrong; Chromium agrees with the reference.  AGG
     * has no focal radius and refuses it (test_peers) */
    {"radial, fr and repeat",
     "<radialGradient id=\"r3\" r=\"0.4\" fr=\"0.1\" spreadMethod=\"repeat\">" WB
     "</radialGradient><rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#r3)\"/>",
     {{31, 31, {0.63922, 0.63922, 0.63922}}},
     1, "resvg agg"},
    /* reflect, userSpaceOnUse centre (20, 20), r 12: at pixel (31, 31),
     * rho = 16.2635, t = 1.35529, reflected 0.64471: 0.35529 */
    {"radial, userSpaceOnUse, reflect",
     "<radialGradient id=\"r4\" gradientUnits=\"userSpaceOnUse\" cx=\"20\" cy=\"20\" "
     "r=\"12\" spreadMethod=\"reflect\">" WB "</radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#r4)\"/>",
     {{31, 31, {0.35529, 0.35529, 0.35529}}},
     1, ""},
    /* on a circle, gradientTransform scale(1, 0.5) about the box's origin:
     * the circle of radius 0.5 at (0.5, 0.25): an ellipse over the top
     * half; at pixel (20, 8) (box units (0.515625, 0.140625)): distance
     * (0.015625, 0.109375 / 0.5) in gradient units, hypot 0.219307, t =
     * 0.43861: 0.56139 */
    {"radial, gradientTransform, on a circle",
     "<radialGradient id=\"r5\" gradientTransform=\"scale(1 0.5)\">" WB "</radialGradient>"
     "<circle cx=\"20\" cy=\"20\" r=\"16\" fill=\"url(#r5)\"/>",
     {{20, 8, {0.56139, 0.56139, 0.56139}}},
     1, ""},
};

/* Several gradients at a point (the reference's path of several
 * gradients, harness/truth/truth.c): source over in encoded values. */
static const cell mixed[] = {
    /* a radial gradient (centre (20, 20), r = 12, white to black) at
     * fill-opacity 0.5 over a linear one (black to white on [4, 36]):
     * at pixel (24, 20), linear t = 20.5 / 32 = 0.640625, radial rho =
     * hypot(4.5, 0.5) = 4.52769, 1 - rho / 12 = 0.622692: half of each,
     * 0.63166 */
    {"radial at half opacity over linear",
     "<linearGradient id=\"m1\">" BW "</linearGradient>"
     "<radialGradient id=\"m2\">" WB "</radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#m1)\"/>"
     "<circle cx=\"20\" cy=\"20\" r=\"12\" fill=\"url(#m2)\" fill-opacity=\"0.5\"/>",
     {{24, 20, {0.63166, 0.63166, 0.63166}}},
     1, ""},
    /* two radial gradients: white to black about (20, 20), r = 16, under
     * red to lime about (26, 20), r = 10, at fill-opacity 0.5: at pixel
     * (24, 24) the back one is 1 - hypot(4.5, 4.5) / 16 = 0.602252, the
     * front one's t = hypot(1.5, 4.5) / 10 = 0.474342: (0.525658,
     * 0.474342, 0); half of each: (0.563955, 0.538297, 0.301126) */
    {"two radial gradients",
     "<radialGradient id=\"m3\">" WB "</radialGradient>"
     "<radialGradient id=\"m4\"><stop offset=\"0\" stop-color=\"red\"/>"
     "<stop offset=\"1\" stop-color=\"lime\"/></radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#m3)\"/>"
     "<circle cx=\"26\" cy=\"20\" r=\"10\" fill=\"url(#m4)\" fill-opacity=\"0.5\"/>",
     {{24, 24, {0.563955, 0.538297, 0.301126}}},
     1, ""},
    /* white (opacity 1) to blue (opacity 0), linear on [4, 36], over the
     * radial white to black about (20, 20), r = 16: at pixel (20, 10), t =
     * 16.5 / 32 = 0.515625, the stop colour (1 - t, 1 - t, 1) at opacity
     * 1 - t over 1 - hypot(0.5, 9.5) / 16 = 0.405428: (0.443668,
     * 0.443668, 0.693424) */
    {"fading linear over radial",
     "<radialGradient id=\"m5\">" WB "</radialGradient>"
     "<linearGradient id=\"m6\"><stop offset=\"0\" stop-color=\"white\"/>"
     "<stop offset=\"1\" stop-color=\"blue\" stop-opacity=\"0\"/></linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#m5)\"/>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#m6)\"/>",
     {{20, 10, {0.443668, 0.443668, 0.693424}}},
     1, ""},
};

/* More than five gradient layers at a point, and one cone-case gradient
 * painting two shapes (the reference's fold and its path of one cone on
 * several layers: truth.c, "the fold", "one cone on several layers");
 * against Chromium and resvg only (renderer()).  The hand-worked colours
 * follow each layer back to front, source over in encoded values. */
static const cell many[] = {
    /* eight translucent gradients over black, at pixel (23, 24) (centre
     * (23.5, 24.5), where the picture is smooth):
     *  1. linear black to white on [4, 36]: t = 19.5 / 32 = 0.609375,
     *     opaque: 0.609375;
     *  2. radial white to black, centre (20, 20), r = 14, at 0.6: t =
     *     hypot(3.5, 4.5) / 14 = 0.407206, colour 0.592794: 0.599427;
     *  3. linear red to blue down [8, 32] at 0.5: t = 16.5 / 24 = 0.6875,
     *     (0.3125, 0, 0.6875): (0.455963, 0.299713, 0.643463);
     *  4. radial red to lime, centre (24, 18), r = 12, at 0.4: t =
     *     hypot(0.5, 6.5) / 12 = 0.543267, (0.456733, 0.543267, 0):
     *     (0.456271, 0.397135, 0.386078);
     *  5. linear white to blue of opacity 0 across [6, 34]: t = 17.5 / 28
     *     = 0.625, (0.375, 0.375, 1) at opacity 0.375: (0.425795,
     *     0.388834, 0.616299);
     *  6. radial lime to black, centre (16, 22), r = 13, focus (10.8, 22)
     *     (fx = 0.3 of [3, 29]), at 0.5: q - F = (12.7, 2.5), D = (5.2,
     *     0), |q - F - t D| = 13 t, so 141.96 t^2 + 132.08 t - 167.54 = 0,
     *     t = 0.716579, (0, 0.283421, 0): (0.212897, 0.336128, 0.308149);
     *  7. linear black to white along the diagonal of [4, 36]^2 at 0.3: t
     *     = (19.5 + 20.5) / 64 = 0.625: (0.336528, 0.422789, 0.403205);
     *  8. radial white to black, centre (20, 20), r = 8 (0.25 of 32),
     *     reflect, at 0.35: t = hypot(3.5, 4.5) / 8 = 0.712610, colour
     *     0.287390: (0.319330, 0.375400, 0.362670). */
    {"eight translucent gradients",
     "<linearGradient id=\"n1\">" BW "</linearGradient>"
     "<radialGradient id=\"n2\">" WB "</radialGradient>"
     "<linearGradient id=\"n3\" x2=\"0\" y2=\"1\"><stop offset=\"0\" stop-color=\"red\"/>"
     "<stop offset=\"1\" stop-color=\"blue\"/></linearGradient>"
     "<radialGradient id=\"n4\"><stop offset=\"0\" stop-color=\"red\"/>"
     "<stop offset=\"1\" stop-color=\"lime\"/></radialGradient>"
     "<linearGradient id=\"n5\"><stop offset=\"0\" stop-color=\"white\"/>"
     "<stop offset=\"1\" stop-color=\"blue\" stop-opacity=\"0\"/></linearGradient>"
     "<radialGradient id=\"n6\" fx=\"0.3\"><stop offset=\"0\" stop-color=\"lime\"/>"
     "<stop offset=\"1\" stop-color=\"black\"/></radialGradient>"
     "<linearGradient id=\"n7\" x2=\"1\" y2=\"1\">" BW "</linearGradient>"
     "<radialGradient id=\"n8\" r=\"0.25\" spreadMethod=\"reflect\">" WB "</radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#n1)\"/>"
     "<circle cx=\"20\" cy=\"20\" r=\"14\" fill=\"url(#n2)\" fill-opacity=\"0.6\"/>"
     "<rect x=\"8\" y=\"8\" width=\"24\" height=\"24\" fill=\"url(#n3)\" fill-opacity=\"0.5\"/>"
     "<circle cx=\"24\" cy=\"18\" r=\"12\" fill=\"url(#n4)\" fill-opacity=\"0.4\"/>"
     "<rect x=\"6\" y=\"10\" width=\"28\" height=\"22\" fill=\"url(#n5)\"/>"
     "<circle cx=\"16\" cy=\"22\" r=\"13\" fill=\"url(#n6)\" fill-opacity=\"0.5\"/>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#n7)\" fill-opacity=\"0.3\"/>"
     "<circle cx=\"20\" cy=\"20\" r=\"16\" fill=\"url(#n8)\" fill-opacity=\"0.35\"/>",
     {{23, 24, {0.319330, 0.375400, 0.362670}}},
     1, ""},
    /* one cone-case gradient (focus (6, 20) outside the end circle,
     * centre (26, 20), r = 6, fr = 0, user space) painting a rectangle at
     * 0.6 and a circle over it at 0.5, red to blue, over black: at pixel
     * (17, 20), q - F = (11.5, 0.5), D = (20, 0), a = |D|^2 - r^2 = 364,
     * b = q.D = 230, c = |q|^2 = 132.5, t = (b + sqrt(b^2 - a c)) / a =
     * (230 + sqrt(4670)) / 364 = 0.819608 (the larger root, r(t) >= 0),
     * inside the cone (its half-angle asin(6/20) = 17.5 degrees, the
     * point's 2.5): (0.180392, 0, 0.819608) at 0.5 over itself at 0.6,
     * 0.8 of it: (0.144314, 0, 0.655686); outside the cone black */
    {"one cone on two shapes",
     "<radialGradient id=\"k1\" gradientUnits=\"userSpaceOnUse\" cx=\"26\" cy=\"20\" r=\"6\" "
     "fx=\"6\" fy=\"20\"><stop offset=\"0\" stop-color=\"red\"/>"
     "<stop offset=\"1\" stop-color=\"blue\"/></radialGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#k1)\" fill-opacity=\"0.6\"/>"
     "<circle cx=\"20\" cy=\"20\" r=\"8\" fill=\"url(#k1)\" fill-opacity=\"0.5\"/>",
     {{17, 20, {0.144314, 0, 0.655686}}},
     1, ""},
};

/* The document of the cells, its rows y0 to y0 + h - 1 (a viewBox of them
 * where h < H), and their image: the box reference. */
static void document_rows(const cell *cells, size_t n, const char *name, int y0, int h,
                          char *path, size_t len, aa_image *ref)
{
    static char doc[1 << 15];
    char box[64] = "";
    if (h < H)
        snprintf(box, sizeof box, " viewBox=\"0 %d %d %d\"", y0, W, h);
    size_t m = (size_t)snprintf(doc, sizeof doc,
                                "<svg xmlns=\"http://www.w3.org/2000/svg\" "
                                "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" "
                                "height=\"%d\"%s>\n<rect width=\"%d\" height=\"%d\"/>\n",
                                W, h, box, W, H);
    for (size_t k = 0; k < n; k++)
        m += (size_t)snprintf(doc + m, sizeof doc - m,
                              "<g transform=\"translate(%d %d)\">%s</g>\n",
                              (int)(k % COLS) * CELL, (int)(k / COLS) * CELL, cells[k].body);
    m += (size_t)snprintf(doc + m, sizeof doc - m, "</svg>\n");
    assert_true(m < sizeof doc);
    snprintf(path, len, "%s/%s.svg", dir, name);
    reference_of(doc, m, path, W, h, ref);
}

/* The document of the cells and its image. */
static void document(const cell *cells, size_t n, const char *name, char *path, size_t len,
                     aa_image *ref)
{
    document_rows(cells, n, name, 0, H, path, len, ref);
}

/* 1 if the picture is smooth about pixel (i, j): every channel's encoded
 * second differences along x and y under 1/255 over its 3 x 3
 * neighbourhood. */
static int smooth_in(const aa_image *ref, int w, int h, int i, int j)
{
    if (i < 2 || j < 2 || i > w - 3 || j > h - 3)
        return 0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++)
            for (int c = 0; c < 3; c++) {
                int x = i + di, y = j + dj;
                double e = enc(aa_pixel(ref, x, y)[c]);
                double dx = enc(aa_pixel(ref, x - 1, y)[c]) + enc(aa_pixel(ref, x + 1, y)[c]) - 2 * e;
                double dy = enc(aa_pixel(ref, x, y - 1)[c]) + enc(aa_pixel(ref, x, y + 1)[c]) - 2 * e;
                if (!(fabs(dx) < 6.0 / 255 && fabs(dy) < 6.0 / 255))
                    return 0;
            }
    return 1;
}

static int smooth(const aa_image *ref, int i, int j) { return smooth_in(ref, W, H, i, j); }

/* The cells' points on ref, the document's rows y0 to y0 + ref->h - 1. */
static void check_points_rows(const cell *cells, size_t n, int y0, const aa_image *ref)
{
    for (size_t k = 0; k < n; k++)
        for (int a = 0; a < cells[k].nat; a++) {
            int i = (int)(k % COLS) * CELL + cells[k].at[a].x;
            int j = (int)(k / COLS) * CELL + cells[k].at[a].y - y0;
            if (!smooth_in(ref, W, ref->h, i, j))
                fail_msg("%s: (%d, %d) is not where the picture is smooth", cells[k].what,
                         cells[k].at[a].x, cells[k].at[a].y);
            for (int c = 0; c < 3; c++) {
                double got = enc(aa_pixel(ref, i, j)[c]), want = cells[k].at[a].c[c];
                print_message("%s: (%d, %d) channel %d: %.5f, by hand %.5f\n", cells[k].what,
                              cells[k].at[a].x, cells[k].at[a].y, c, got, want);
                if (!(fabs(got - want) <= 2e-3))
                    fail_msg("%s: (%d, %d) channel %d is %.6f encoded, not %.6f",
                             cells[k].what, cells[k].at[a].x, cells[k].at[a].y, c, got, want);
            }
        }
}

static void check_points(const cell *cells, size_t n, const aa_image *ref)
{
    check_points_rows(cells, n, 0, ref);
}

static void test_points(void **state)
{
    (void)state;
    char path[4200];
    aa_image ref;
    document(linear, sizeof linear / sizeof *linear, "linear", path, sizeof path, &ref);
    check_points(linear, sizeof linear / sizeof *linear, &ref);
    aa_image_free(&ref);
    document(radial, sizeof radial / sizeof *radial, "radial", path, sizeof path, &ref);
    check_points(radial, sizeof radial / sizeof *radial, &ref);
    aa_image_free(&ref);
    document(mixed, sizeof mixed / sizeof *mixed, "mixed", path, sizeof path, &ref);
    check_points(mixed, sizeof mixed / sizeof *mixed, &ref);
    aa_image_free(&ref);
    if (SAN_SUBSET) {
        print_message("many: rows %d to %d\n", MANY_Y0, MANY_Y0 + MANY_ROWS - 1);
        document_rows(many, sizeof many / sizeof *many, "many", MANY_Y0, MANY_ROWS, path,
                      sizeof path, &ref);
        check_points_rows(many, sizeof many / sizeof *many, MANY_Y0, &ref);
    } else {
        document(many, sizeof many / sizeof *many, "many", path, sizeof path, &ref);
        check_points(many, sizeof many / sizeof *many, &ref);
    }
    aa_image_free(&ref);
}

/* The peers paint a gradient layer only over its covered span of each
 * band (algorithms/peer.c, aa_peer_paint_band; agg.cpp's grad_interp
 * steps from the row's first pixel; cairo.c reads back the span of the
 * band pixman paints whole): on each document, each peer's image must be
 * the one painting every band's whole width gives (aa__peer_shade_whole),
 * bit for bit.  The documents' cells lie side by side, so each layer
 * covers a third of a row at most: a span begun at its first pixel with
 * AGG's own interpolator steps otherwise, as a narrower Cairo paint
 * rounds otherwise, and either fails here. */
static void test_peer_span(void **state)
{
    (void)state;
    static const char *const peers[] = {"cairo", "agg"};
    const struct {
        const cell *cells;
        size_t n;
        const char *name;
    } docs[] = {{linear, sizeof linear / sizeof *linear, "linear"},
                {radial, sizeof radial / sizeof *radial, "radial"},
                {mixed, sizeof mixed / sizeof *mixed, "mixed"}};
    int compared[2] = {0, 0};
    for (size_t d = 0; d < sizeof docs / sizeof *docs; d++) {
        char path[4200], spec[4300];
        aa_image ref;
        document(docs[d].cells, docs[d].n, docs[d].name, path, sizeof path, &ref);
        aa_image_free(&ref);
        snprintf(spec, sizeof spec, "svg:file=%s", path);
        aa_spec sp;
        aa_scene *sc = NULL;
        assert_int_equal(aa_pattern_parse(spec, &sp), AA_OK);
        assert_int_equal(aa_pattern_scene_at(&sp, W, H, &sc), AA_OK);
        for (size_t p = 0; p < 2; p++) {
            const support_view v = {.w = W, .h = H, .filter = "box", .seed = 1, .threads = 2};
            aa_image span, whole;
            aa__peer_shade_whole = 0;
            if (support_render_view(peers[p], sc, &v, &span, NULL) != AA_OK) {
                /* agg refuses a focal radius (test_peers holds it to that) */
                print_message("%s, %s: refused (%s)\n", peers[p], docs[d].name, aa_last_error());
                continue;
            }
            compared[p]++;
            aa__peer_shade_whole = 1;
            support_render_must(peers[p], sc, &v, &whole, NULL);
            aa__peer_shade_whole = 0;
            int wi = 0, wj = 0;
            const double e = support_max_diff(&span, &whole, &wi, &wj);
            print_message("%s, %s: span against whole rows: largest difference %g at (%d, %d)\n",
                          peers[p], docs[d].name, e, wi, wj);
            assert_true(support_same_image(&span, &whole));
            aa_image_free(&span);
            aa_image_free(&whole);
        }
        aa_scene_free(sc);
    }
    assert_int_equal(compared[0], 3); /* cairo draws every document */
    assert_true(compared[1] >= 1);
}

/* ---- the peers (algorithms/cairo.c, agg.cpp: gradients of their own) ----
 *
 * Cells the peers draw besides the tables above: a sharp step (two stops
 * at one offset, repeated), a skewed reflected radial gradient with a
 * focal point inside a group of opacity over a flat disc, and a linear
 * gradient of varying stop opacity, rotated, clipped by a circle, over a
 * colour. */
static const cell own[] = {
    {"sharp steps, repeat",
     "<linearGradient id=\"p1\" gradientUnits=\"userSpaceOnUse\" x1=\"4\" x2=\"20\" "
     "spreadMethod=\"repeat\"><stop offset=\"0\" stop-color=\"red\"/><stop offset=\"0.5\" "
     "stop-color=\"yellow\"/><stop offset=\"0.5\" stop-color=\"blue\"/><stop offset=\"1\" "
     "stop-color=\"white\"/></linearGradient>"
     "<rect x=\"4\" y=\"4\" width=\"32\" height=\"32\" fill=\"url(#p1)\"/>",
     {{0}},
     0, "agg"},
    {"focal radial, skewed, reflect, in a group",
     "<radialGradient id=\"p2\" r=\"0.3\" fx=\"0.4\" fy=\"0.6\" spreadMethod=\"reflect\" "
     "gradientTransform=\"skewX(15)\"><stop offset=\"0\" stop-color=\"#ffd080\"/>"
     "<stop offset=\"0.6\" stop-color=\"teal\" stop-opacity=\"0.7\"/><stop offset=\"1\" "
     "stop-color=\"navy\"/></radialGradient>"
     "<circle cx=\"26\" cy=\"14\" r=\"10\" fill=\"#c04040\"/>"
     "<g opacity=\"0.6\"><rect x=\"2\" y=\"2\" width=\"36\" height=\"36\" fill=\"url(#p2)\"/>"
     "</g>",
     {{0}},
     0, ""},
    {"fading linear, rotated, clipped",
     "<clipPath id=\"c3\"><circle cx=\"20\" cy=\"20\" r=\"15\"/></clipPath>"
     "<linearGradient id=\"p3\" gradientTransform=\"rotate(30 0.5 0.5)\">"
     "<stop offset=\"0.1\" stop-color=\"lime\" stop-opacity=\"0.2\"/><stop offset=\"0.9\" "
     "stop-color=\"fuchsia\" stop-opacity=\"0.9\"/></linearGradient>"
     "<rect width=\"40\" height=\"40\" fill=\"#3050a0\"/>"
     "<rect x=\"2\" y=\"2\" width=\"36\" height=\"36\" fill=\"url(#p3)\" clip-path=\"url(#c3)\"/>",
     {{0}},
     0, ""},
};

/* Cell k of a table alone in a document of its own, CELL x CELL (the
 * cells before it in <defs>, for the gradients it refers to): its file
 * in path, its box reference into ref. */
static void cell_document(const cell *cells, size_t k, const char *name, char *path, size_t len,
                          aa_image *ref)
{
    static char doc[1 << 15];
    size_t m = (size_t)snprintf(doc, sizeof doc,
                                "<svg xmlns=\"http://www.w3.org/2000/svg\" "
                                "xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" "
                                "height=\"%d\">\n<defs>",
                                CELL, CELL);
    for (size_t b = 0; b < k; b++)
        m += (size_t)snprintf(doc + m, sizeof doc - m, "%s", cells[b].body);
    m += (size_t)snprintf(doc + m, sizeof doc - m,
                          "</defs>\n<rect width=\"%d\" height=\"%d\"/>\n%s\n</svg>\n", CELL,
                          CELL, cells[k].body);
    assert_true(m < sizeof doc);
    snprintf(path, len, "%s/%s.svg", dir, name);
    reference_of(doc, m, path, CELL, CELL, ref);
}

/* The quantisation a peer's gradient paint may add to a pixel's encoded
 * channel, summed over the scene's gradient layers (each composites at
 * most its own error through: v's weight in a layer over it is at most 1).
 * A layer's paint goes on as v = decode(alpha P + (1 - alpha A) enc v)
 * (peer.h), so an error dP in the premultiplied channel and dA in alpha
 * move the encoded result by at most dP + dA |...| <= dP + dA.
 *  - cairo: pixman interpolates in single precision at the centre's t
 *    (to 1/65536 of a period) and rounds P and A to 8 bits: half a code
 *    each, 1/255.
 *  - agg: the 256-entry table (agg.cpp): the colour of an entry is the
 *    stops' at a t' within 2.5/256 of the pixel's t, and t is resolved to
 *    1/4096 (its 1/16 units of a period of 256; for a radial gradient
 *    through the focal point's map, up to 2 r / (r - |F - C|) of those);
 *    each channel and the opacity rounded at the stops and floored by the
 *    table's dda: 1.5/255.  So a non-premultiplied channel of slope L in t
 *    (the largest over the stops' intervals) is off by up to
 *    L dt + 1.5/255, dt = 2.5/256 + k/4096; the opacity likewise when the
 *    stops' differ, else by its rounding alone (half a code, 0 for
 *    opacity 1); P = A c is off by A dc + c dA <= dc + dA, and the result
 *    by dc + 2 dA. */
static double peer_quantum(const aa_scene *placed, const char *peer)
{
    double q = 0;
    for (int l = 0; l < aa_scene_layer_count(placed); l++) {
        aa_gradient g;
        if (!aa_scene_layer_gradient(placed, l, &g))
            continue;
        if (!strcmp(peer, "cairo")) {
            q += 1.0 / 255;
            continue;
        }
        double lc = 0, la = 0;
        int varies = 0, opaque = 1;
        for (int k = 0; k < g.nstops; k++) {
            varies |= g.stops[k].opacity != g.stops[0].opacity;
            opaque &= g.stops[k].opacity == 1.0;
            if (k + 1 == g.nstops)
                break;
            const double dt = g.stops[k + 1].offset - g.stops[k].offset;
            if (!(dt > 0))
                continue;
            for (int c = 0; c < 3; c++)
                lc = fmax(lc, fabs(enc(g.stops[k + 1].colour.c[c]) - enc(g.stops[k].colour.c[c])) /
                                  dt);
            la = fmax(la, fabs(g.stops[k + 1].opacity - g.stops[k].opacity) / dt);
        }
        double k = 1;
        if (g.kind == AA_GRADIENT_RADIAL)
            k = 2 * g.p[2] / (g.p[2] - hypot(g.p[3] - g.p[0], g.p[4] - g.p[1]));
        const double dt = 2.5 / 256 + k / 4096;
        const double da = varies ? la * dt + 1.5 / 255 : opaque ? 0 : 0.5 / 255;
        q += lc * dt + 1.5 / 255 + 2 * da;
    }
    return q;
}

/* How far a pixel's colour at its centre may be from its box mean, in
 * encoded values, where the picture is smooth: with e the encoded value,
 * mean - centre is about (e_xx + e_yy) / 24 and, through the decoding's
 * curvature, (decode'' / decode') |grad e|^2 / 24, decode'' / decode' =
 * 1.4 / (e + 0.055) on the decoding's power piece (e > 0.04045; 0 on its
 * linear one).  e's derivatives from the reference's differences, the
 * largest over the pixel's 3 x 3 neighbourhood. */
static double centre_allowance(const aa_image *ref, int w, int h, int i, int j, int c)
{
    double worst = 0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++) {
            int x = i + di, y = j + dj;
            if (x < 1 || y < 1 || x > w - 2 || y > h - 2)
                return INFINITY;
            double e = enc(aa_pixel(ref, x, y)[c]);
            double l = enc(aa_pixel(ref, x - 1, y)[c]), r = enc(aa_pixel(ref, x + 1, y)[c]);
            double u = enc(aa_pixel(ref, x, y - 1)[c]), d = enc(aa_pixel(ref, x, y + 1)[c]);
            double curv = (fabs(l + r - 2 * e) + fabs(u + d - 2 * e)) / 24;
            double gx = (r - l) / 2, gy = (d - u) / 2;
            double bend = e > 0.04045 ? 1.4 / (e + 0.055) * (gx * gx + gy * gy) / 24 : 0;
            worst = fmax(worst, curv + bend);
        }
    return worst;
}

/* The peer on one cell: refused where the cell's `differs` names it (the
 * message printed), else on the smooth pixels (smooth() on the cell's own
 * image) within the quantisation and centre allowances of the reference;
 * its error over the whole cell (RMSE and largest, linear light: edges,
 * seams and all) printed. */
static void peer_cell(const char *peer, const cell *cells, size_t k, const char *name, int *bad)
{
    const cell *c = &cells[k];
    char path[4200], spec[4300];
    aa_image ref, img;
    cell_document(cells, k, name, path, sizeof path, &ref);
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec sp;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &sp) != AA_OK || aa_pattern_scene_at(&sp, CELL, CELL, &sc) != AA_OK)
        fail_msg("%s", aa_last_error());
    if (!aa_scene_has_gradients(sc)) { /* a cell of colours only (the fallback cell) */
        aa_image_free(&ref);
        aa_scene_free(sc);
        return;
    }
    const support_view v = {.w = CELL, .h = CELL, .filter = "box", .seed = 1, .threads = 2};
    const int refuses = support_names(c->differs, peer);
    int st = support_render_view(peer, sc, &v, &img, NULL);
    if (refuses) {
        print_message("%s, %s: refused: %s\n", peer, c->what, aa_last_error());
        if (st != AA_EINVAL) {
            print_message("%s, %s: drawn, but the table says it is refused\n", peer, c->what);
            (*bad)++;
        }
        if (!st)
            aa_image_free(&img);
        aa_image_free(&ref);
        aa_scene_free(sc);
        return;
    }
    if (st)
        fail_msg("%s, %s: %s", peer, c->what, aa_last_error());
    aa_scene *placed = aa_scene_place(sc, CELL, CELL, 0, 0, 0);
    assert_non_null(placed);
    const double q = peer_quantum(placed, peer);
    aa_scene_free(placed);
    double worst = 0, over = -INFINITY;
    int wi = 0, wj = 0, count = 0;
    for (int j = 0; j < CELL; j++)
        for (int i = 0; i < CELL; i++) {
            if (!smooth_in(&ref, CELL, CELL, i, j))
                continue;
            count++;
            for (int ch = 0; ch < 3; ch++) {
                double d = fabs(enc(aa_pixel(&ref, i, j)[ch]) - enc(aa_pixel(&img, i, j)[ch]));
                double allow = q + centre_allowance(&ref, CELL, CELL, i, j, ch);
                if (d > worst)
                    worst = d, wi = i, wj = j;
                if (d - allow > over)
                    over = d - allow;
            }
        }
    int mi, mj;
    const double rmse = support_rmse(&img, &ref), mx = support_max_diff(&img, &ref, &mi, &mj);
    print_message("%s, %s: %d smooth pixels, largest difference %.2f/255 at (%d, %d) (allowed "
                  "%.2f/255 of quantisation; largest excess over allowance %.2f/255); whole "
                  "cell: rmse %.3e, max %.3e at (%d, %d)\n",
                  peer, c->what, count, worst * 255, wi, wj, q * 255, over * 255, rmse, mx, mi,
                  mj);
    if (count < 100) {
        print_message("%s: only %d smooth pixels to compare\n", c->what, count);
        (*bad)++;
    }
    if (!(over <= 1e-9)) {
        print_message("%s, %s: DIFFERS beyond the allowance\n", peer, c->what);
        (*bad)++;
    }
    aa_image_free(&img);
    aa_image_free(&ref);
    aa_scene_free(sc);
}

static void peer_table(const char *peer, const cell *cells, size_t n, const char *tag, int *bad)
{
    for (size_t k = 0; k < n; k++) {
        char name[64];
        snprintf(name, sizeof name, "%s-%s-%zu", peer, tag, k);
        peer_cell(peer, cells, k, name, bad);
    }
}

/* Cairo and AGG draw every gradient cell with their own gradients, each
 * within its derived allowance of the exact reference where the picture is
 * smooth; AGG refuses, naming why, the focal radius (r3) and the sharp
 * step (its table keeps one stop an offset); FreeType and stb refuse
 * gradient paint, naming it. */
static void test_peers(void **state)
{
    (void)state;
    static const char *const peers[] = {"cairo", "agg"};
    for (size_t p = 0; p < 2; p++) {
        int bad = 0;
        peer_table(peers[p], linear, sizeof linear / sizeof *linear, "linear", &bad);
        peer_table(peers[p], radial, sizeof radial / sizeof *radial, "radial", &bad);
        peer_table(peers[p], mixed, sizeof mixed / sizeof *mixed, "mixed", &bad);
        peer_table(peers[p], own, sizeof own / sizeof *own, "own", &bad);
        if (bad)
            fail_msg("%s: %d cells not as the tables say", peers[p], bad);
    }
    char path[4200], spec[4300];
    aa_image ref;
    cell_document(radial, 0, "nopeer", path, sizeof path, &ref);
    aa_image_free(&ref);
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec sp;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse(spec, &sp), AA_OK);
    assert_int_equal(aa_pattern_scene_at(&sp, CELL, CELL, &sc), AA_OK);
    static const char *const none[] = {"freetype", "stb"};
    for (size_t p = 0; p < 2; p++) {
        const support_view v = {.w = CELL, .h = CELL, .filter = "box", .seed = 1, .threads = 1};
        aa_image img;
        int st = support_render_view(none[p], sc, &v, &img, NULL);
        print_message("%s: %s\n", none[p], aa_last_error());
        assert_int_equal(st, AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "gradient"));
        assert_non_null(strstr(aa_last_error(), none[p]));
    }
    aa_scene_free(sc);
}

static void renderer_cells(const char *name, const cell *cells, size_t n, const char *docname)
{
    const char *tree = aa_source_tree();
    char adapter[4200], cmd[13000], path[4200], png[4300];
    snprintf(adapter, sizeof adapter, "%s/scripts/renderers/%s", tree, name);
    aa_image ref, img;
    document(cells, n, docname, path, sizeof path, &ref);
    snprintf(png, sizeof png, "%s/%s-%s.png", dir, name, docname);
    snprintf(cmd, sizeof cmd, "'%s' '%s' %d %d '%s' >/dev/null", adapter, path, W, H, png);
    if (system(cmd) != 0)
        fail_msg("%s failed on %s", name, path);
    if (aa_image_read(png, &img))
        fail_msg("%s", aa_last_error());
    assert_int_equal(img.w, W);
    assert_int_equal(img.h, H);
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        double worst = 0;
        int wi = 0, wj = 0, count = 0;
        int x0 = (int)(k % COLS) * CELL, y0 = (int)(k / COLS) * CELL;
        for (int j = y0; j < y0 + CELL; j++)
            for (int i = x0; i < x0 + CELL; i++) {
                if (!smooth(&ref, i, j))
                    continue;
                count++;
                for (int c = 0; c < 3; c++) {
                    double d = fabs(enc(aa_pixel(&ref, i, j)[c]) - enc(aa_pixel(&img, i, j)[c]));
                    if (d > worst)
                        worst = d, wi = i - x0, wj = j - y0;
                }
            }
        const int agrees = worst <= 3.0 / 255 + 1e-9, known = support_names(cells[k].differs, name);
        print_message("%s, %s: %d smooth pixels, largest difference %.1f/255 at (%d, %d)%s\n",
                      name, cells[k].what, count, worst * 255, wi, wj,
                      agrees ? "" : known ? " (the renderer is wrong: noted)" : " DIFFERS");
        if (count < 100)
            fail_msg("%s: only %d smooth pixels to compare", cells[k].what, count);
        if (agrees == known)
            bad++;
    }
    aa_image_free(&img);
    aa_image_free(&ref);
    if (bad)
        fail_msg("%s: %d cells not as the table says", name, bad);
}

static void renderer(const char *name)
{
#if defined(__SANITIZE_ADDRESS__)
    print_message("%s: tested in the plain build\n", name);
    skip();
#endif
    const char *tree = aa_source_tree();
    if (!tree) {
        print_message("%s skipped: no source tree (its adapters)\n", name);
        skip();
    }
    char adapter[4200], cmd[4400];
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
    renderer_cells(name, linear, sizeof linear / sizeof *linear, "linear");
    renderer_cells(name, radial, sizeof radial / sizeof *radial, "radial");
    renderer_cells(name, mixed, sizeof mixed / sizeof *mixed, "mixed");
    renderer_cells(name, many, sizeof many / sizeof *many, "many");
}

static void test_chromium(void **state)
{
    (void)state;
    renderer("chromium");
}

static void test_resvg(void **state)
{
    (void)state;
    renderer("resvg");
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points), cmocka_unit_test(test_peers),
        cmocka_unit_test(test_peer_span), cmocka_unit_test(test_chromium),
        cmocka_unit_test(test_resvg)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
