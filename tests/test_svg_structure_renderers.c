/*
 * test_svg_structure_renderers.c: <use>, <symbol>, nested <svg>, CSS
 * lengths, style sheets and the cascade, the CSS transform property and
 * path data with an error, as browsers draw them: the exact box reference
 * of the pattern svg against headless Chromium and resvg (and librsvg)
 * drawing the same document, colour by colour away from edges.
 *
 * As tests/test_paint_renderers.c (whose harness this is): one document
 * of cells, each one feature, its colours at a few points worked by hand
 * from the specifications in its comment; the reference is checked
 * against those first, then each renderer against the reference on the
 * pixels whose 3 x 3 neighbourhood is of one colour, within 2/255.  A
 * cell a renderer draws otherwise names the renderer, and the comment
 * says who is wrong.
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
#define ROWS 4
#define W (CELL * COLS)
#define H (CELL * ROWS)

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "structrender");
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
};
#define NCELLS (sizeof cells / sizeof cells[0])

/* The document of every cell, and its box reference. */
static void document(char *path, size_t len, aa_image *ref)
{
    static char doc[1 << 15];
    size_t n = (size_t)snprintf(doc, sizeof doc,
                                "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"%d\" "
                                "height=\"%d\">\n<rect width=\"%d\" height=\"%d\"/>\n",
                                W, H, W, H);
    for (size_t k = 0; k < NCELLS; k++)
        n += (size_t)snprintf(doc + n, sizeof doc - n,
                              "<g transform=\"translate(%d %d)\">%s</g>\n",
                              (int)(k % COLS) * CELL, (int)(k / COLS) * CELL, cells[k].body);
    n += (size_t)snprintf(doc + n, sizeof doc - n, "</svg>\n");
    assert_true(n < sizeof doc);
    snprintf(path, len, "%s/structure.svg", dir);
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
static void test_reference(void **state)
{
    (void)state;
    char path[4200];
    aa_image ref;
    document(path, sizeof path, &ref);
    for (size_t k = 0; k < NCELLS; k++)
        for (int a = 0; a < cells[k].nat; a++) {
            int i = (int)(k % COLS) * CELL + cells[k].at[a].x;
            int j = (int)(k / COLS) * CELL + cells[k].at[a].y;
            if (!flat(&ref, i, j))
                fail_msg("%s: point (%d, %d) is not inside a region", cells[k].what,
                         cells[k].at[a].x, cells[k].at[a].y);
            for (int c = 0; c < 3; c++) {
                double got = enc(aa_pixel(&ref, i, j)[c]), want = cells[k].at[a].c[c];
                if (!(fabs(got - want) <= 1e-12))
                    fail_msg("%s: (%d, %d) channel %d is %.15g encoded, not %.15g",
                             cells[k].what, cells[k].at[a].x, cells[k].at[a].y, c, got, want);
            }
        }
    aa_image_free(&ref);
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

static int names(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = strstr(list, name); s; s = strstr(s + 1, name))
        if ((s == list || s[-1] == ' ') && (s[n] == '\0' || s[n] == ' '))
            return 1;
    return 0;
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
    snprintf(png, sizeof png, "%s/%s.png", dir, name);
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
        const int agrees = e <= 2.0 / 255 + 1e-9, known = names(cells[k].differs, name);
        print_message("%s, %s: largest difference %.1f/255 at (%d, %d)%s\n", name,
                      cells[k].what, e * 255, i, j,
                      agrees ? "" : known ? " (the renderer is wrong: noted)" : " DIFFERS");
        if (agrees == known) {
            print_message("%s, %s: %s\n", name, cells[k].what,
                          known ? "agrees, but the table says it differs" : "differs");
            bad++;
        }
    }
    aa_image_free(&img);
    aa_image_free(&ref);
    if (bad)
        fail_msg("%s: %d cells not as the table says", name, bad);
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

static void test_rsvg(void **state)
{
    (void)state;
    renderer("rsvg");
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_reference), cmocka_unit_test(test_chromium),
             cmocka_unit_test(test_resvg), cmocka_unit_test(test_rsvg))
