/*
 * test_svg_structure.c: the SVG reader's structure, units and style sheets
 * (patterns/svgfile.c, patterns/svgcss.c): <use>, <symbol>, nested <svg>,
 * CSS lengths, <style> sheets and the cascade, the CSS transform
 * property, and path data drawn up to its first error.
 *
 * Every expected value is derived in the comment beside it from the
 * specifications (SVG 2 "Coordinate systems", "The 'use' element",
 * "Units", "Error handling in path data"; CSS Values 4, Cascade 4,
 * Selectors 4, Transforms 1), never read from the code under test.  The
 * box reference of white shapes over black sums to their area, and a
 * shape drawn through <use> must give the same picture, pixel by pixel,
 * as the same shape written where it lands (an independent construction).
 */
#include "bench.h"
#include "patterns.h"
#include "support.h"
#include "svgfile.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* ---- a sink that writes what it is given as text ---- */

static int s_shape(void *ctx, aa_rgb c, aa_fill_rule rule)
{
    (void)rule;
    return support_put(ctx, "%s%.17g %.17g %.17g;", ((support_text *)ctx)->n ? " " : "", c.c[0],
                       c.c[1], c.c[2]);
}
static int s_arc(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                 double t0, double t1, double x, double y)
{
    (void)ux, (void)uy, (void)vx, (void)vy, (void)t0, (void)t1;
    return support_put(ctx, " A %.17g %.17g to %.17g %.17g", cx, cy, x, y);
}

/* the path's commands by support_put_move and the others */
static const aa_svg_sink sink = {.shape = s_shape, .move_to = support_put_move,
                                 .line_to = support_put_line, .quad_to = support_put_quad,
                                 .cubic_to = support_put_cubic, .close = support_put_close,
                                 .arc_to = s_arc};

/* The same with clips: "[within W" .. " ]" around a clip's members, and
 * " clip N" after the shape drawn inside clip N. */
static int s_clip_begin(void *ctx, int within)
{
    return support_put(ctx, "%s[within %d", ((support_text *)ctx)->n ? " " : "", within);
}
static int s_clip_end(void *ctx) { return support_put(ctx, " ]"); }
static int s_clip(void *ctx, int clip) { return support_put(ctx, " clip %d", clip); }

static const aa_svg_sink clip_sink = {.shape = s_shape, .move_to = support_put_move,
                                      .line_to = support_put_line, .quad_to = support_put_quad,
                                      .cubic_to = support_put_cubic, .close = support_put_close,
                                      .arc_to = s_arc, .clip_begin = s_clip_begin,
                                      .clip_end = s_clip_end, .clip = s_clip};

#define OPEN "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\">"
#define BLACK "0 0 0;"
#define WHITE "1 1 1;"

/* Read `doc` on a 100 x 100 view; the sink's text, or fail. */
static const char *read_doc(const char *doc)
{
    static support_text t;
    t.n = 0;
    t.buf[0] = '\0';
    if (aa_svg_read(doc, strlen(doc), "test.svg", 100, 100, &sink, &t, NULL) != AA_OK)
        fail_msg("%s: %s", doc, aa_last_error());
    return t.buf;
}

static void expect(const char *doc, const char *want)
{
    const char *got = read_doc(doc);
    if (strcmp(got, want))
        fail_msg("%s\n  got  %s\n  want %s", doc, got, want);
}

/* The same through the sink that takes clips. */
static void expect_clips(const char *doc, const char *want)
{
    static support_text t;
    t.n = 0;
    t.buf[0] = '\0';
    if (aa_svg_read(doc, strlen(doc), "test.svg", 100, 100, &clip_sink, &t, NULL) != AA_OK)
        fail_msg("%s: %s", doc, aa_last_error());
    if (strcmp(t.buf, want))
        fail_msg("%s\n  got  %s\n  want %s", doc, t.buf, want);
}

static void refused_clips(const char *doc, const char *want1, const char *want2)
{
    static support_text t;
    t.n = 0;
    if (aa_svg_read(doc, strlen(doc), "test.svg", 100, 100, &clip_sink, &t, NULL) != AA_EINVAL)
        fail_msg("accepted: %s", doc);
    const char *msg = aa_last_error();
    if ((want1 && !strstr(msg, want1)) || (want2 && !strstr(msg, want2)))
        fail_msg("%s\n  message: %s\n  wanted: %s / %s", doc, msg, want1, want2 ? want2 : "");
}

static void expect_partial(const char *doc, const char *want, const char *warning);

/* `doc` is refused with a message containing want1 and want2. */
static void refused(const char *doc, const char *want1, const char *want2)
{
    support_text t = {.n = 0};
    if (aa_svg_read(doc, strlen(doc), "test.svg", 100, 100, &sink, &t, NULL) != AA_EINVAL)
        fail_msg("accepted: %s", doc);
    const char *msg = aa_last_error();
    if ((want1 && !strstr(msg, want1)) || (want2 && !strstr(msg, want2)))
        fail_msg("%s\n  message: %s\n  wanted: %s / %s", doc, msg, want1, want2 ? want2 : "");
}

/* ---- <use> ---- */

static void test_use(void **state)
{
    (void)state;
    /* the rect [1, 4] x [2, 6] moved by translate(10, 20) */
#define RECT_R "<defs><rect id=\"r\" x=\"1\" y=\"2\" width=\"3\" height=\"4\"/></defs>"
    expect(OPEN RECT_R "<use href=\"#r\" x=\"10\" y=\"20\"/></svg>",
           BLACK " M 11 22 L 14 22 L 14 26 L 11 26 Z");
    expect(OPEN RECT_R "<use xlink:href=\"#r\" x=\"10\" y=\"20\"/></svg>",
           BLACK " M 11 22 L 14 22 L 14 26 L 11 26 Z");
    /* href wins over xlink:href (SVG 2) */
    expect(OPEN RECT_R "<rect id=\"q\" width=\"1\" height=\"1\"/>"
                       "<use href=\"#r\" xlink:href=\"#q\" x=\"10\" y=\"20\"/></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z " BLACK " M 11 22 L 14 22 L 14 26 L 11 26 Z");
    /* the use's transform, then translate(x, y): scale(2) of (p + (1, 0)):
     * (1, 2) -> (4, 4), (4, 2) -> (10, 4), (4, 6) -> (10, 12) */
    expect(OPEN RECT_R "<use href=\"#r\" transform=\"scale(2)\" x=\"1\"/></svg>",
           BLACK " M 4 4 L 10 4 L 10 12 L 4 12 Z");
    /* the target inherits from the <use>: red (linear 1 0 0); its own
     * fill wins */
    expect(OPEN RECT_R "<use href=\"#r\" fill=\"red\"/></svg>",
           "1 0 0; M 1 2 L 4 2 L 4 6 L 1 6 Z");
    expect(OPEN "<defs><rect id=\"r\" width=\"1\" height=\"1\" fill=\"lime\"/></defs>"
                "<use href=\"#r\" fill=\"red\"/></svg>",
           "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* a use of a use: both translations */
    expect(OPEN RECT_R "<use id=\"u\" href=\"#r\" x=\"1\"/><use href=\"#u\" y=\"1\"/></svg>",
           BLACK " M 2 2 L 5 2 L 5 6 L 2 6 Z " BLACK " M 2 3 L 5 3 L 5 7 L 2 7 Z");
    /* the first element of an id in document order */
    expect(OPEN "<defs><rect id=\"d\" width=\"1\" height=\"1\"/><rect id=\"d\" width=\"2\" "
                "height=\"2\"/></defs><use href=\"#d\"/></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* a missing target, an empty href, no href: nothing (SVG 2: the use is
     * not rendered) */
    expect(OPEN "<use href=\"#nowhere\"/><use href=\"\"/><use/></svg>", "");
    /* cycles: a use referencing its ancestor, and two uses referencing
     * each other, are in error and draw nothing; the rest draws */
    expect(OPEN "<g id=\"g\"><rect width=\"1\" height=\"1\"/><use href=\"#g\" x=\"5\"/></g></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    expect(OPEN "<use id=\"a\" href=\"#b\"/><use id=\"b\" href=\"#a\"/></svg>", "");
    /* a use of the root, its ancestor */
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"top\"><rect width=\"1\" "
           "height=\"1\"/><use href=\"#top\" x=\"3\"/></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* g1 holds a rect and a use of g2, which uses g1: through g2's use
     * g1 would hold itself (its use is an ancestor): in error */
    expect(OPEN "<g id=\"g1\"><rect width=\"1\" height=\"1\"/><use href=\"#g2\"/></g>"
                "<defs><g id=\"g2\"><use href=\"#g1\" x=\"7\"/></g></defs></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* a symbol draws only through a use */
    expect(OPEN "<symbol id=\"s\"><rect width=\"1\" height=\"1\"/></symbol></svg>", "");
    /* the use's opacity: the target's alpha (a sink without alpha refuses) */
    refused(OPEN RECT_R "<use href=\"#r\" opacity=\"0.5\"/></svg>", "<use>", "opacity");
    refused(OPEN "<use href=\"other.svg#r\"/></svg>", "<use>", "another document");
    /* a billion laughs of uses is stopped by the element count */
    {
        static char doc[8192];
        size_t n = (size_t)snprintf(doc, sizeof doc, "%s<defs><g id=\"l0\"/>", OPEN);
        for (int k = 1; k <= 30; k++)
            n += (size_t)snprintf(doc + n, sizeof doc - n,
                                  "<g id=\"l%d\"><use href=\"#l%d\"/><use href=\"#l%d\"/></g>", k,
                                  k - 1, k - 1);
        snprintf(doc + n, sizeof doc - n, "</defs><use href=\"#l30\"/></svg>");
        refused(doc, "more than", "elements");
    }
}

/* ---- viewports: <symbol> and nested <svg> ---- */

static void test_viewports(void **state)
{
    (void)state;
    /* symbol viewBox 0 0 10 10 on a use of 20 x 40: meet, scale min(2, 4)
     * = 2, xMidYMid: (40 - 20)/2 = 10 down; the use's (5, 5) on top: the
     * rect [0, 10]^2 lands on [5, 25] x [15, 35] */
    expect(OPEN "<symbol id=\"s\" viewBox=\"0 0 10 10\"><rect width=\"10\" height=\"10\"/>"
                "</symbol><use href=\"#s\" x=\"5\" y=\"5\" width=\"20\" height=\"40\"/></svg>",
           BLACK " M 5 15 L 25 15 L 25 35 L 5 35 Z");
    /* preserveAspectRatio none: scale (2, 4) */
    expect(OPEN "<symbol id=\"s\" viewBox=\"0 0 10 10\" preserveAspectRatio=\"none\">"
                "<rect width=\"10\" height=\"10\"/></symbol>"
                "<use href=\"#s\" width=\"20\" height=\"40\"/></svg>",
           BLACK " M 0 0 L 20 0 L 20 40 L 0 40 Z");
    /* the symbol's own size, when the use gives none; 100% when neither
     * does: the viewport 100 x 100, a viewBox of 50 x 50: scale 2 */
    expect(OPEN "<symbol id=\"s\" viewBox=\"0 0 50 50\"><rect width=\"50\" height=\"50\"/>"
                "</symbol><use href=\"#s\"/></svg>",
           BLACK " M 0 0 L 100 0 L 100 100 L 0 100 Z");
    /* a nested svg at (10, 10) of 20 x 20, viewBox 0 0 10 10: scale 2;
     * 50% of its width and height (of the viewBox: 5) */
    expect(OPEN "<svg x=\"10\" y=\"10\" width=\"20\" height=\"20\" viewBox=\"0 0 10 10\">"
                "<rect width=\"50%\" height=\"50%\"/></svg></svg>",
           BLACK " M 10 10 L 20 10 L 20 20 L 10 20 Z");
    /* a use of an svg: the use's width and height replace the svg's */
    expect(OPEN "<defs><svg id=\"v\" width=\"1\" height=\"1\" viewBox=\"0 0 1 1\">"
                "<rect width=\"1\" height=\"1\"/></svg></defs>"
                "<use href=\"#v\" width=\"8\" height=\"8\"/></svg>",
           BLACK " M 0 0 L 8 0 L 8 8 L 0 8 Z");
    /* a viewport of no width draws nothing */
    expect(OPEN "<svg width=\"0\"><rect width=\"1\" height=\"1\"/></svg></svg>", "");
    /* content reaching beyond a viewport of overflow hidden (the initial
     * value): refused by a sink that takes no clips (test_viewport_clips
     * for one that does); touching its edges is inside; overflow visible
     * draws it whole */
    refused(OPEN "\n<svg width=\"10\" height=\"10\"><rect x=\"5\" width=\"5.001\" height=\"1\"/>"
                 "</svg></svg>",
            "line 2: <rect>", "beyond the viewport of the <svg> at line 2");
    expect(OPEN "<svg width=\"10\" height=\"10\"><rect x=\"5\" width=\"5\" height=\"10\"/>"
                "</svg></svg>",
           BLACK " M 5 0 L 10 0 L 10 10 L 5 10 Z");
    expect(OPEN "<svg width=\"10\" height=\"10\" overflow=\"visible\"><rect x=\"5\" "
                "width=\"50\" height=\"1\"/></svg></svg>",
           BLACK " M 5 0 L 55 0 L 55 1 L 5 1 Z");
    expect(OPEN "<symbol id=\"s\" style=\"overflow: auto\"><rect x=\"-5\" width=\"50\" "
                "height=\"1\"/></symbol><use href=\"#s\" width=\"10\" height=\"10\"/></svg>",
           BLACK " M -5 0 L 45 0 L 45 1 L -5 1 Z");
    refused(OPEN "<symbol id=\"s\"><rect x=\"-5\" width=\"50\" height=\"1\"/></symbol>"
                 "<use href=\"#s\" width=\"10\" height=\"10\"/></svg>",
            "<rect>", "<symbol>");
    /* bounds are exact, not of the control points: a disk of radius 5
     * touching a 10 x 10 viewport's sides, rotated 30 degrees with its
     * viewport, is inside; the arc's control-free ellipse is tested at its
     * extremes; a radius of 5.01 reaches beyond */
    read_doc(OPEN "<g transform=\"rotate(30)\"><svg width=\"10\" height=\"10\">"
                  "<circle cx=\"5\" cy=\"5\" r=\"5\"/></svg></g></svg>");
    refused(OPEN "<g transform=\"rotate(30)\"><svg width=\"10\" height=\"10\">"
                 "<circle cx=\"5\" cy=\"5\" r=\"5.01\"/></svg></g></svg>",
            "<circle>", "beyond");
    /* a cubic whose control points leave the viewport while the curve
     * stays in it: B(t) from (0, 0) over (10, 12) (10, 12) to (10, 0)
     * turns at y = 3 t (1 - t) 12 at t = 1/2: 9 */
    read_doc(OPEN "<svg width=\"10\" height=\"10\"><path d=\"M0 0 C 0 12 10 12 10 0\"/>"
                  "</svg></svg>");
    refused(OPEN "<svg width=\"10\" height=\"8\"><path d=\"M0 0 C 0 12 10 12 10 0\"/>"
                 "</svg></svg>",
            "<path>", "beyond");
    /* a stroke counts by its outline: 2 wide about x = 9 reaches 10 */
    read_doc(OPEN "<svg width=\"10\" height=\"10\"><line x1=\"9\" x2=\"9\" y1=\"1\" y2=\"9\" "
                  "stroke=\"red\" stroke-width=\"2\"/></svg></svg>");
    refused(OPEN "<svg width=\"10\" height=\"10\"><line x1=\"9\" x2=\"9\" y1=\"1\" y2=\"9\" "
                 "stroke=\"red\" stroke-width=\"2.1\"/></svg></svg>",
            "<line>", "beyond");
    refused(OPEN "<svg width=\"-1\"/></svg>", "<svg>", "negative");
    /* an invalid overflow is ignored (SVG 2: as if absent, the user agent
     * sheet's hidden) with a warning */
    expect_partial(OPEN "<svg width=\"1\" height=\"1\" overflow=\"sideways\"/></svg>", "",
                   "overflow=\"sideways\"");
    /* refX, refY (SVG 2, "The 'symbol' element"): the reference point, in
     * content coordinates after the viewBox map, lands on the use's (x,
     * y), the viewport with it.  viewBox 0 0 10 10 on 20 x 20 scales by 2:
     * (5, 5) is (10, 10) of the viewport, so the viewport's corner is at
     * (20, 30) - (10, 10) and the rect [0, 10]^2 on [10, 30] x [20, 40] */
    expect(OPEN "<symbol id=\"s\" viewBox=\"0 0 10 10\" refX=\"5\" refY=\"5\"><rect "
                "width=\"10\" height=\"10\"/></symbol><use href=\"#s\" x=\"20\" y=\"30\" "
                "width=\"20\" height=\"20\"/></svg>",
           BLACK " M 10 20 L 30 20 L 30 40 L 10 40 Z");
    /* keywords: right and bottom are the viewBox's right and bottom edges
     * (12, 14), at the viewport's (10, 10) (scale 1, the viewBox starting
     * at (2, 4)): the rect of the whole viewBox on [40, 50]^2 */
    expect(OPEN "<symbol id=\"s\" viewBox=\"2 4 10 10\" refX=\"right\" refY=\"BOTTOM\">"
                "<rect x=\"2\" y=\"4\" width=\"10\" height=\"10\"/></symbol><use "
                "href=\"#s\" x=\"50\" y=\"50\" width=\"10\" height=\"10\"/></svg>",
           BLACK " M 40 40 L 50 40 L 50 50 L 40 50 Z");
    /* without a viewBox center is half the viewport's width (20): 10 to
     * the left; refY absent moves nothing */
    expect(OPEN "<symbol id=\"s\" refX=\"center\"><rect width=\"20\" height=\"5\"/>"
                "</symbol><use href=\"#s\" x=\"30\" width=\"20\" height=\"20\"/></svg>",
           BLACK " M 20 0 L 40 0 L 40 5 L 20 5 Z");
    /* 50% of the viewBox's width, 5, after meet on 40 x 20 (scale 2, the
     * viewBox centred 10 in): 2 x 5 + 10 = 20 to the left; the rect [0,
     * 10]^2 of the viewBox on [10, 30] x [0, 20], then [40, 60] at x = 50 */
    expect(OPEN "<symbol id=\"s\" viewBox=\"0 0 10 10\" refX=\"50%\"><rect width=\"10\" "
                "height=\"10\"/></symbol><use href=\"#s\" x=\"50\" width=\"40\" "
                "height=\"20\"/></svg>",
           BLACK " M 40 0 L 60 0 L 60 20 L 40 20 Z");
    /* an invalid refX is its initial value (none: no shift), with a
     * warning */
    expect_partial(OPEN "<symbol id=\"s\" refX=\"middle\"><rect width=\"2\" height=\"1\"/>"
                        "</symbol><use href=\"#s\" x=\"3\"/></svg>",
                   BLACK " M 3 0 L 5 0 L 5 1 L 3 1 Z", "refX=\"middle\"");
    /* a symbol's x and y (SVG 2), where its reference point lands: refX
     * and refY (2, 2) at the symbol's (1, 2) from the use's (3, 0), so
     * the rect [0, 2] x [0, 1] moves by (1 - 2 + 3, 2 - 2) */
    expect(OPEN "<symbol id=\"s\" x=\"1\" y=\"2\" width=\"4\" height=\"4\" viewBox=\"0 0 4 4\" "
                "refX=\"2\" refY=\"2\" overflow=\"visible\"><rect width=\"2\" height=\"1\"/>"
                "</symbol><use href=\"#s\" x=\"3\"/></svg>",
           BLACK " M 2 0 L 4 0 L 4 1 L 2 1 Z");
}

/* Viewports that clip, through a sink that takes clips (SVG 2: a nested
 * <svg> or a used <symbol> of overflow hidden clips its content to its
 * viewport, x y width height in the user space it is in): the clip's one
 * member is that rectangle through the map there, within the clip the
 * viewport is drawn in, given when a shape first reaches beyond it. */
static void test_viewport_clips(void **state)
{
    (void)state;
    /* the viewport [2, 12] x [3, 13]; the rect [7, 27] x [3, 4] beyond it */
    expect_clips(OPEN "<svg x=\"2\" y=\"3\" width=\"10\" height=\"10\"><rect x=\"5\" "
                      "width=\"20\" height=\"1\"/></svg></svg>",
                 "[within -1 " BLACK " M 2 3 L 12 3 L 12 13 L 2 13 Z ] " BLACK
                 " clip 0 M 7 3 L 27 3 L 27 4 L 7 4 Z");
    /* a shape inside is drawn as without the viewport; two beyond share
     * one clip */
    expect_clips(OPEN "<svg width=\"10\" height=\"10\"><rect width=\"1\" height=\"1\"/>"
                      "<rect y=\"2\" width=\"20\" height=\"1\"/><rect y=\"4\" width=\"1\" "
                      "height=\"20\"/></svg></svg>",
                 BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z [within -1 " BLACK
                       " M 0 0 L 10 0 L 10 10 L 0 10 Z ] " BLACK
                       " clip 0 M 0 2 L 20 2 L 20 3 L 0 3 Z " BLACK
                       " clip 0 M 0 4 L 1 4 L 1 24 L 0 24 Z");
    /* a symbol used twice alike gives one clip; used elsewhere, another:
     * its viewport [0, 10]^2 at the use, then at translate(50, 0) */
    expect_clips(OPEN "<symbol id=\"s\"><rect x=\"-5\" width=\"20\" height=\"1\"/></symbol>"
                      "<use href=\"#s\" width=\"10\" height=\"10\"/>"
                      "<use href=\"#s\" width=\"10\" height=\"10\"/>"
                      "<use href=\"#s\" x=\"50\" width=\"10\" height=\"10\"/></svg>",
                 "[within -1 " BLACK " M 0 0 L 10 0 L 10 10 L 0 10 Z ] " BLACK
                 " clip 0 M -5 0 L 15 0 L 15 1 L -5 1 Z " BLACK
                 " clip 0 M -5 0 L 15 0 L 15 1 L -5 1 Z [within -1 " BLACK
                 " M 50 0 L 60 0 L 60 10 L 50 10 Z ] " BLACK
                 " clip 1 M 45 0 L 65 0 L 65 1 L 45 1 Z");
    /* under a skew, x' = x + y / 2: the viewport [0, 10] x [0, 20] is the
     * parallelogram (0, 0) (10, 0) (20, 20) (10, 20) */
    expect_clips(OPEN "<g transform=\"matrix(1 0 0.5 1 0 0)\"><svg width=\"10\" "
                      "height=\"20\"><rect width=\"30\" height=\"2\"/></svg></g></svg>",
                 "[within -1 " BLACK " M 0 0 L 10 0 L 20 20 L 10 20 Z ] " BLACK
                 " clip 0 M 0 0 L 30 0 L 31 2 L 1 2 Z");
    /* in a group with a clip-path: the viewport's clip lies within the
     * group's (an intersection); a shape inside the viewport keeps the
     * group's clip */
#define CLIP4 "<clipPath id=\"c\"><rect width=\"4\" height=\"4\"/></clipPath>"
    expect_clips(OPEN CLIP4 "<g clip-path=\"url(#c)\"><svg width=\"10\" height=\"10\">"
                            "<rect width=\"1\" height=\"1\"/><rect width=\"20\" height=\"1\"/>"
                            "</svg></g></svg>",
                 "[within -1 " BLACK " M 0 0 L 4 0 L 4 4 L 0 4 Z ] " BLACK
                 " clip 0 M 0 0 L 1 0 L 1 1 L 0 1 Z [within 0 " BLACK
                 " M 0 0 L 10 0 L 10 10 L 0 10 Z ] " BLACK " clip 1 M 0 0 L 20 0 L 20 1 L 0 1 Z");
    /* a clip-path inside a viewport: its clip within the viewport's */
    expect_clips(OPEN CLIP4 "<svg width=\"10\" height=\"10\"><rect width=\"20\" height=\"1\" "
                            "clip-path=\"url(#c)\"/></svg></svg>",
                 "[within -1 " BLACK " M 0 0 L 10 0 L 10 10 L 0 10 Z ] [within 0 " BLACK
                 " M 0 0 L 4 0 L 4 4 L 0 4 Z ] " BLACK " clip 1 M 0 0 L 20 0 L 20 1 L 0 1 Z");
    /* viewports in viewports: the inner [2, 7] x [0, 5] within the outer
     * [0, 10]^2; overflow visible makes no clip */
    expect_clips(OPEN "<svg width=\"10\" height=\"10\"><svg x=\"2\" width=\"5\" height=\"5\">"
                      "<rect width=\"20\" height=\"1\"/></svg></svg></svg>",
                 "[within -1 " BLACK " M 0 0 L 10 0 L 10 10 L 0 10 Z ] [within 0 " BLACK
                 " M 2 0 L 7 0 L 7 5 L 2 5 Z ] " BLACK " clip 1 M 2 0 L 22 0 L 22 1 L 2 1 Z");
    expect_clips(OPEN "<svg width=\"10\" height=\"10\"><svg width=\"5\" height=\"5\" "
                      "overflow=\"visible\"><rect width=\"8\" height=\"1\"/></svg></svg></svg>",
                 BLACK " M 0 0 L 8 0 L 8 1 L 0 1 Z");
    /* clip-path on a <use>: in its user space, translate(x, y) included
     * (SVG 2, "The 'use' element"; Chromium, resvg and librsvg alike) */
    expect_clips(OPEN CLIP4 "<defs><rect id=\"r\" width=\"10\" height=\"10\"/></defs>"
                            "<use href=\"#r\" x=\"20\" clip-path=\"url(#c)\"/></svg>",
                 "[within -1 " BLACK " M 20 0 L 24 0 L 24 4 L 20 4 Z ] " BLACK
                 " clip 0 M 20 0 L 30 0 L 30 10 L 20 10 Z");
    /* objectBoundingBox of a group holding a nested svg: its content
     * through translate(20, 20), unclipped (the rect [-20, 40] x [0, 20]
     * there: [0, 60] x [20, 40]; Chromium, resvg and librsvg take it so);
     * the unit rect [1/4, 1/2] x [0, 1] on it is [15, 30] x [20, 40] */
    expect_clips(OPEN "<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect "
                      "x=\"0.25\" width=\"0.25\" height=\"1\"/></clipPath><g "
                      "clip-path=\"url(#o)\"><svg x=\"20\" y=\"20\" width=\"20\" "
                      "height=\"20\"><rect x=\"-20\" width=\"60\" height=\"20\"/></svg></g>"
                      "</svg>",
                 "[within -1 " BLACK " M 15 20 L 30 20 L 30 40 L 15 40 Z ] [within 0 " BLACK
                 " M 20 20 L 40 20 L 40 40 L 20 40 Z ] " BLACK
                 " clip 1 M 0 20 L 60 20 L 60 40 L 0 40 Z");
    /* objectBoundingBox units for a use: the box in the clip's user space,
     * which has translate(x, y) in it, so the target's own box [0, 10]^2;
     * its left half [0, 5] x [0, 10] lands, moved by x = 20, on [20, 25] x
     * [0, 10] (were the box taken in the use's parent space, [20, 30]^2,
     * the clip would be [40, 45] x [0, 10] after the move; Chromium and
     * resvg draw the former) */
    expect_clips(OPEN "<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect "
                      "width=\"0.5\" height=\"1\"/></clipPath><defs><rect id=\"r\" "
                      "width=\"10\" height=\"10\"/></defs><use href=\"#r\" x=\"20\" "
                      "clip-path=\"url(#o)\"/></svg>",
                 "[within -1 " BLACK " M 20 0 L 25 0 L 25 10 L 20 10 Z ] " BLACK
                 " clip 0 M 20 0 L 30 0 L 30 10 L 20 10 Z");
    /* clip-path on the viewport element itself: in the user space it
     * establishes (its content's: the viewBox's scale 2 and x = 10 here),
     * so the rect [0, 4]^2 is [10, 18] x [0, 8]; the viewport's clip
     * [10, 30] x [0, 20] lies within it (clipped by both) */
    expect_clips(OPEN CLIP4 "<svg x=\"10\" width=\"20\" height=\"20\" viewBox=\"0 0 10 10\" "
                            "clip-path=\"url(#c)\"><rect width=\"20\" height=\"1\"/></svg></svg>",
                 "[within -1 " BLACK " M 10 0 L 18 0 L 18 8 L 10 8 Z ] [within 0 " BLACK
                 " M 10 0 L 30 0 L 30 20 L 10 20 Z ] " BLACK " clip 1 M 10 0 L 50 0 L 50 2 L 10 2 Z");
    /* on a symbol, alike, the use's translate(x, y) included: [0, 4]^2
     * scaled by 3 at (5, 0), within the viewport [5, 35] x [0, 30] */
    expect_clips(OPEN CLIP4 "<symbol id=\"s\" viewBox=\"0 0 10 10\" clip-path=\"url(#c)\">"
                            "<rect width=\"20\" height=\"1\"/></symbol>"
                            "<use href=\"#s\" x=\"5\" width=\"30\" height=\"30\"/></svg>",
                 "[within -1 " BLACK " M 5 0 L 17 0 L 17 12 L 5 12 Z ] [within 0 " BLACK
                 " M 5 0 L 35 0 L 35 30 L 5 30 Z ] " BLACK " clip 1 M 5 0 L 65 0 L 65 3 L 5 3 Z");
    /* its bounding box in the viewBox's coordinates is not computed */
    refused_clips(OPEN "<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect "
                       "width=\"0.5\" height=\"1\"/></clipPath><svg width=\"10\" "
                       "height=\"10\" clip-path=\"url(#o)\"/></svg>",
                  "<clipPath>", "objectBoundingBox");
    expect_clips(OPEN "<svg width=\"10\" height=\"10\" clip-path=\"none\"><rect width=\"1\" "
                      "height=\"1\"/></svg></svg>",
                 BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
#undef CLIP4
}

/* ---- units ---- */

static void test_units(void **state)
{
    (void)state;
    char want[512];
    /* CSS Values 4: 1in = 96px, 1cm = 96/2.54 px */
    snprintf(want, sizeof want, BLACK " M 0 0 L 96 0 L 96 %.17g L 0 %.17g Z", 96 / 2.54,
             96 / 2.54);
    expect(OPEN "<rect width=\"1in\" height=\"1cm\"/></svg>", want);
    /* x = 1mm = 96/25.4 px, y = 3pt = 3 x 96/72 = 4, width and height
     * 1pc = 16px (units in any case) */
    snprintf(want, sizeof want, BLACK " M %.17g 4 L %.17g 4 L %.17g 20 L %.17g 20 Z", 96 / 25.4,
             96 / 25.4 + 16, 96 / 25.4 + 16, 96 / 25.4);
    expect(OPEN "<rect x=\"1mm\" y=\"3pt\" width=\"1pc\" height=\"1PC\"/></svg>", want);
    /* em: the element's font-size (inherited), ex half of it (CSS Values 4
     * when no font metrics are used); font-size in em and % of the
     * parent's; medium is 16px, large 6/5 of it */
    expect(OPEN "<g font-size=\"20\"><rect width=\"2em\" height=\"1ex\"/></g></svg>",
           BLACK " M 0 0 L 40 0 L 40 10 L 0 10 Z");
    expect(OPEN "<g font-size=\"10px\"><g style=\"font-size: 2em\"><rect width=\"1em\" "
                "height=\"1em\" font-size=\"150%\"/></g></g></svg>",
           BLACK " M 0 0 L 30 0 L 30 30 L 0 30 Z");
    expect(OPEN "<rect width=\"1em\" height=\"1em\"/></svg>",
           BLACK " M 0 0 L 16 0 L 16 16 L 0 16 Z");
    /* the root's font-size is the em of its own width: 2em of 10px */
    {
        double vp[2];
        const char *doc = "<svg xmlns=\"http://www.w3.org/2000/svg\" font-size=\"10px\" "
                          "width=\"2em\" height=\"3ex\"/>";
        assert_int_equal(aa_svg_read(doc, strlen(doc), "t.svg", 1, 1, NULL, NULL, vp), AA_OK);
        if (!(vp[0] == 20 && vp[1] == 15))
            fail_msg("the root of 2em x 3ex at 10px: %g x %g", vp[0], vp[1]);
    }
    snprintf(want, sizeof want, BLACK " M 0 0 L %.17g 0 L %.17g 1 L 0 1 Z", 16 * 6.0 / 5,
             16 * 6.0 / 5);
    expect(OPEN "<rect width=\"1em\" height=\"1\" font-size=\"large\"/></svg>", want);
    /* %: of the viewport's width (x, width), height (y, height), and the
     * normalised diagonal sqrt((w^2 + h^2)/2) for r: on the root of
     * 100 x 50, r = 10% is sqrt(6250)/10 */
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"50\">"
           "<rect x=\"10%\" y=\"10%\" width=\"50%\" height=\"50%\"/></svg>",
           BLACK " M 10 5 L 60 5 L 60 30 L 10 30 Z");
    snprintf(want, sizeof want, BLACK " M %.17g 0", sqrt(6250) / 10);
    {
        const char *doc = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" "
                          "height=\"50\"><circle r=\"10%\"/></svg>";
        const char *got = read_doc(doc);
        if (strncmp(got, want, strlen(want)))
            fail_msg("got %s, want %s...", got, want);
    }
    /* the root's size in absolute units is its own size */
    double vp[2];
    static const char own[] = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1in\" "
                              "height=\"2.54cm\"/>";
    assert_int_equal(aa_svg_read(own, strlen(own), "t.svg", 1, 1, NULL, NULL, vp), AA_OK);
    assert_true(vp[0] == 96 && fabs(vp[1] - 96) < 1e-13);
    refused(OPEN "<rect width=\"1ch\" height=\"1\"/></svg>", "<rect>", "not a length");
    /* rem: the root's font-size (CSS Values 4), whatever the element's;
     * 16px, medium, when the root sets none; a rem in the root's own
     * font-size is of the initial 16px, so 2rem there is 32 */
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" font-size=\"10px\"><g font-size=\"30\">"
           "<rect width=\"2rem\" height=\"1REM\" font-size=\"40px\"/></g></svg>",
           BLACK " M 0 0 L 20 0 L 20 10 L 0 10 Z");
    expect(OPEN "<rect width=\"1rem\" height=\"1\" font-size=\"5\"/></svg>",
           BLACK " M 0 0 L 16 0 L 16 1 L 0 1 Z");
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" style=\"font-size: 2rem\">"
           "<rect width=\"1rem\" height=\"1\"/></svg>",
           BLACK " M 0 0 L 32 0 L 32 1 L 0 1 Z");
    /* vw, vh, vmin, vmax: 1% of the initial containing block's width,
     * height, smaller and larger side (CSS Values 4), for a document
     * drawn alone its window: here the view of 200 x 100, whatever the
     * root's own size (50 x 40); in CSS px, so in a nested svg's user
     * units, which its viewBox (0 0 25 25 on 50 x 50) doubles: 10vw is 20
     * there, 20px in user units 40 px */
    {
        static const char doc[] =
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"50\" height=\"40\">"
            "<rect x=\"1vw\" y=\"2vh\" width=\"10vmin\" height=\"10vmax\"/>"
            "<svg width=\"50\" height=\"50\" viewBox=\"0 0 25 25\"><rect width=\"10vw\" "
            "height=\"1VH\"/></svg></svg>";
        support_text t = {.n = 0};
        if (aa_svg_read(doc, strlen(doc), "test.svg", 200, 100, &sink, &t, NULL) != AA_OK)
            fail_msg("%s: %s", doc, aa_last_error());
        const char *wv = BLACK " M 2 2 L 12 2 L 12 22 L 2 22 Z " BLACK
                                 " M 0 0 L 40 0 L 40 2 L 0 2 Z";
        if (strcmp(t.buf, wv))
            fail_msg("%s\n  got  %s\n  wv %s", doc, t.buf, wv);
    }
    /* in the root's own size they are refused: the view may be that size */
    refused("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"50vw\"/>", "<svg>",
            "not a length");
    /* larger and smaller: the parent's size times and over 1.2 (CSS Fonts
     * 4 suggests the ratio; Chromium and resvg take it): of 10px, 12px and
     * 10/1.2 px; twice larger of 25px, 36px; xx-small and xxx-large are
     * CSS Fonts 4's 3/5 and 3 of medium's 16px */
    expect(OPEN "<g font-size=\"10px\"><rect width=\"1em\" height=\"1\" "
                "font-size=\"larger\"/></g></svg>",
           BLACK " M 0 0 L 12 0 L 12 1 L 0 1 Z");
    snprintf(want, sizeof want, BLACK " M 0 0 L %.17g 0 L %.17g 1 L 0 1 Z", 10 / 1.2, 10 / 1.2);
    expect(OPEN "<g font-size=\"10px\"><rect width=\"1em\" height=\"1\" "
                "style=\"font-size: SMALLER\"/></g></svg>",
           want);
    expect(OPEN "<g font-size=\"25px\"><g font-size=\"larger\"><rect width=\"1em\" "
                "height=\"1\" font-size=\"larger\"/></g></g></svg>",
           BLACK " M 0 0 L 36 0 L 36 1 L 0 1 Z");
    snprintf(want, sizeof want, BLACK " M 0 0 L %.17g 0 L %.17g 1 L 0 1 Z", 16 * 3.0 / 5,
             16 * 3.0 / 5);
    expect(OPEN "<rect width=\"1em\" height=\"1\" font-size=\"xx-small\"/></svg>", want);
    expect(OPEN "<rect width=\"1em\" height=\"1\" style=\"font-size: xxx-large\"/></svg>",
           BLACK " M 0 0 L 48 0 L 48 1 L 0 1 Z");
    /* a negative font-size is invalid (CSS Fonts 4): the initial medium,
     * 16px, for the attribute (SVG 2), the parent's 10px for a declaration
     * (ignored, CSS) */
    expect_partial(OPEN "<rect width=\"1em\" height=\"1\" font-size=\"-2px\"/></svg>",
                   BLACK " M 0 0 L 16 0 L 16 1 L 0 1 Z", "negative");
    expect_partial(OPEN "<g font-size=\"10px\"><rect width=\"1em\" height=\"1\" "
                        "style=\"font-size: -2px\"/></g></svg>",
                   BLACK " M 0 0 L 10 0 L 10 1 L 0 1 Z", "negative");
}

/* ---- conditional processing ---- */

static void test_conditions(void **state)
{
    (void)state;
    /* SVG 2, "Conditional processing": systemLanguage is true when one of
     * its comma-separated tags is the user's language or begins with it
     * and "-" (the reader's language is "en"), case-insensitive; an empty
     * list is false; requiredExtensions is true only when every extension
     * listed is supported (none is: false, the empty list too, as SVG 2
     * says); requiredFeatures is no longer SVG 2's: true.  Kept: the
     * rects at x = 1 ("en"), 3 ("EN-gb", the prefix followed by "-"), 5
     * (requiredFeatures); left out: 2 ("english"), 4 (""), 6 and 7
     * (requiredExtensions, one URL and none) */
    expect(OPEN "<rect x=\"1\" width=\"1\" height=\"1\" systemLanguage=\"en\"/>"
                "<rect x=\"2\" width=\"1\" height=\"1\" systemLanguage=\"english\"/>"
                "<rect x=\"3\" width=\"1\" height=\"1\" systemLanguage=\"fr, EN-gb\"/>"
                "<rect x=\"4\" width=\"1\" height=\"1\" systemLanguage=\"\"/>"
                "<rect x=\"5\" width=\"1\" height=\"1\" "
                "requiredFeatures=\"http://www.w3.org/TR/SVG11/feature#Shape\"/>"
                "<rect x=\"6\" width=\"1\" height=\"1\" "
                "requiredExtensions=\"http://example.org/x\"/>"
                "<rect x=\"7\" width=\"1\" height=\"1\" requiredExtensions=\"\"/></svg>",
           BLACK " M 1 0 L 2 0 L 2 1 L 1 1 Z " BLACK " M 3 0 L 4 0 L 4 1 L 3 1 Z " BLACK
                 " M 5 0 L 6 0 L 6 1 L 5 1 Z");
    /* a false condition on a group leaves out its content */
    expect(OPEN "<g systemLanguage=\"de\"><rect width=\"1\" height=\"1\"/></g>"
                "<rect x=\"2\" width=\"1\" height=\"1\"/></svg>",
           BLACK " M 2 0 L 3 0 L 3 1 L 2 1 Z");
    /* <switch> draws its first direct child whose conditions hold (SVG
     * 2, "The switch element"): of fr, en-US and none, the second */
    expect(OPEN "<switch fill=\"white\"><rect width=\"1\" height=\"1\" systemLanguage=\"fr\"/>"
                "<rect x=\"1\" width=\"1\" height=\"1\" systemLanguage=\"en-US\"/>"
                "<rect x=\"2\" width=\"1\" height=\"1\"/></switch></svg>",
           WHITE " M 1 0 L 2 0 L 2 1 L 1 1 Z");
    /* as Illustrator writes it: a foreignObject of an extension, then the
     * group drawn instead; elements of other namespaces are passed over */
    expect(OPEN "<switch><foreignObject requiredExtensions=\"http://ns.adobe.com/AI/10.0/\">"
                "<i xmlns=\"http://example.org/\"/></foreignObject>"
                "<x:i xmlns:x=\"http://example.org/\"/>"
                "<g><rect x=\"3\" width=\"1\" height=\"1\"/></g>"
                "<rect x=\"4\" width=\"1\" height=\"1\"/></switch></svg>",
           BLACK " M 3 0 L 4 0 L 4 1 L 3 1 Z");
    /* display and visibility do not take part in the choice (SVG 2): the
     * first child chosen, display none, draws nothing, and the second is
     * not drawn; a switch without a child whose conditions hold draws
     * nothing */
    expect(OPEN "<switch><rect width=\"1\" height=\"1\" display=\"none\"/>"
                "<rect x=\"1\" width=\"1\" height=\"1\"/></switch>"
                "<switch><rect width=\"1\" height=\"1\" requiredExtensions=\"\"/></switch>"
                "</svg>",
           "");
    /* a switch as a group: its transform and opacity are its child's */
    expect(OPEN "<switch transform=\"translate(5 6)\"><rect width=\"1\" height=\"1\"/></switch>"
                "</svg>",
           BLACK " M 5 6 L 6 6 L 6 7 L 5 7 Z");
    /* the root's false condition: nothing is drawn */
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" systemLanguage=\"fr\">"
           "<rect width=\"1\" height=\"1\"/></svg>",
           "");
    /* requiredFonts and requiredFormats (SVG 1.1 Tiny's, dropped by SVG
     * 2) are true: Chromium and resvg take the first child of each switch
     * (tests/test_paint_renderers.c's probe documents drew them so) */
    expect(OPEN "<switch><rect x=\"8\" width=\"1\" height=\"1\" requiredFonts=\"NoSuchFont\"/>"
                "<rect width=\"1\" height=\"1\"/></switch>"
                "<switch><rect x=\"9\" width=\"1\" height=\"1\" "
                "requiredFormats=\"image/x-none\"/><rect width=\"1\" height=\"1\"/></switch>"
                "</svg>",
           BLACK " M 8 0 L 9 0 L 9 1 L 8 1 Z " BLACK " M 9 0 L 10 0 L 10 1 L 9 1 Z");
    /* a title chosen is refused: Chromium chooses it (nothing drawn),
     * resvg passes over it */
    refused(OPEN "<switch><title>t</title><rect width=\"1\" height=\"1\"/></switch></svg>",
            "<title>", "<switch>");
}

/* ---- style sheets and the cascade ---- */

/* The colours of the shapes a document gives, in order. */
static void expect_colours(const char *doc, const char *const *want, int n)
{
    const char *got = read_doc(doc);
    const char *s = got;
    for (int k = 0; k < n; k++) {
        size_t len = strlen(want[k]);
        if (k)
            s = strstr(s, "Z ");
        if (!s || (k && (s += 2, 0)) || strncmp(s, want[k], len) || s[len] != ';')
            fail_msg("shape %d: want %s\n  got %s", k, want[k], got);
    }
}

#define R(attrs) "<rect width=\"1\" height=\"1\" " attrs "/>"

static void test_sheets(void **state)
{
    (void)state;
    /* Specificity (a, b, c) = (ids; classes, attributes, pseudo-classes;
     * types), Selectors 4; the higher wins, then the later rule; the style
     * attribute wins over every rule and a presentation attribute loses
     * to every rule (CSS Cascade 4, SVG 2 "Presentation attributes").
     * Colours (linear light): red 1 0 0, lime 0 1 0, blue 0 0 1, yellow
     * 1 1 0, white 1 1 1, aqua 0 1 1, fuchsia 1 0 1. */
    static const char doc[] =
        OPEN "<style>\n"
             "rect { fill: red }\n"                  /* (0, 0, 1) */
             ".a { fill: lime }\n"                   /* (0, 1, 0) */
             "#x { fill: blue }\n"                   /* (1, 0, 0) */
             "g > rect.a { fill: yellow }\n"         /* (0, 1, 2) */
             "g rect { fill: white }\n"              /* (0, 0, 2) */
             ".o { fill: red } .o { fill: aqua }\n"  /* equal: the later */
             "rect[height=\"2\"] { fill: fuchsia }\n" /* (0, 1, 1) */
             "rect:hover, .h { fill: aqua }\n"       /* :hover never matches */
             "svg > g.k circle { fill: lime }\n"     /* (0, 1, 3) */
             "/* a comment { fill: red } */\n"
             "</style>\n"
             R("") /* rect: red */
             R("class=\"a\"") /* .a over rect: lime */
             R("class=\"a\" id=\"x\"") /* #x: blue */
             R("class=\"o\"") /* .o, later: aqua */
             "<rect width=\"1\" height=\"2\"/>" /* [height="2"] (0,1,1): fuchsia */
             R("class=\"h\"") /* .h: aqua */
             "<g>" R("class=\"a\"") /* g > rect.a (0,1,2): yellow */
             R("") /* g rect (0,0,2): white */
             R("fill=\"blue\"") /* the attribute loses: white */
             R("style=\"fill: blue\"") /* the style attribute wins: blue */
             "</g>"
             "<g class=\"k\"><circle r=\"1\"/></g>" /* svg > g.k circle: lime */
             "</svg>";
    static const char *const want[] = {"1 0 0", "0 1 0", "0 0 1", "0 1 1", "1 0 1", "0 1 1",
                                       "1 1 0", "1 1 1", "1 1 1", "0 0 1", "0 1 0"};
    expect_colours(doc, want, (int)(sizeof want / sizeof want[0]));
    /* !important: an important rule beats the style attribute, an
     * important style attribute beats it; importance beats specificity */
    static const char imp[] =
        OPEN "<style>.i { fill: lime !important } #y { fill: red } "
             "rect { fill: blue ! IMPORTANT }</style>"
             R("class=\"i\" style=\"fill: red\"") /* lime */
             R("class=\"i\" style=\"fill: aqua !important\"") /* aqua */
             R("id=\"y\"") /* blue (important, though of lower specificity) */
             "</svg>";
    static const char *const want_imp[] = {"0 1 0", "0 1 1", "0 0 1"};
    expect_colours(imp, want_imp, 3);
    /* inherited from a rule on the parent; the later of two style
     * attribute declarations */
    static const char inh[] = OPEN "<style>g { fill: lime; stroke-width: 3 }</style>"
                                   "<g>" R("") "</g>" R("style=\"fill: red; fill: aqua\"")
                                   "</svg>";
    static const char *const want_inh[] = {"0 1 0", "0 1 1"};
    expect_colours(inh, want_inh, 2);
    /* attribute selectors (Selectors 4): [a] present, [a=v] equal, [a~=v]
     * a word of a white-space list, [a|=v] v or v followed by "-", [a^=v]
     * a prefix, [a$=v] a suffix, [a*=v] a substring; the empty string
     * matches nothing for ~=, ^=, $= and *= */
    static const char attrs[] =
        OPEN "<style>rect { fill: black } [id] { fill: red } [id=\"p\"] { fill: lime } "
             "[class~=\"two\"] { fill: blue } [class|=\"en\"] { fill: yellow } "
             "[id^=\"pre\"] { fill: aqua } [id$=\"fix\"] { fill: fuchsia } "
             "[id*=\"mid\"] { fill: white } [class^=\"\"] { fill: red }</style>"
             R("id=\"q\"")            /* [id]: red */
             R("id=\"p\"")            /* [id=p] (0,1,0) later than [id]: lime */
             R("class=\"one two\"")   /* blue */
             R("class=\"en-GB\"")     /* yellow */
             R("class=\"eng\"")       /* |= wants "en" or "en-": black */
             R("id=\"prelude\"")      /* aqua */
             R("id=\"suffix\"")       /* fuchsia */
             R("id=\"amidst\"")       /* white */
             "</svg>";
    static const char *const want_attrs[] = {"1 0 0", "0 1 0", "0 0 1", "1 1 0",
                                             "0 0 0", "0 1 1", "1 0 1", "1 1 1"};
    expect_colours(attrs, want_attrs, 8);
    /* combinators: a descendant at any depth, found past a non-matching
     * nearer ancestor; a child only under its parent; :root is the root */
    static const char comb[] =
        OPEN "<style>.a .c { fill: lime } .b > .c { fill: blue } :root > g > .d { fill: red } "
             ".a > .e { fill: white }</style>"
             "<g class=\"a\"><g class=\"x\"><g class=\"y\">" R("class=\"c\"")  /* lime */
             R("class=\"e\"")                      /* .a > .e: not a child: black */
             "</g></g></g>"
             "<g class=\"b\"><g>" R("class=\"c\"") "</g></g>" /* .b > .c fails; no .a: black */
             "<g>" R("class=\"d\"") "</g>"                     /* red */
             "<g><g>" R("class=\"d\"") "</g></g>"              /* not the root's grandchild: black */
             "</svg>";
    static const char *const want_comb[] = {"0 1 0", "0 0 0", "0 0 0", "1 0 0", "0 0 0"};
    expect_colours(comb, want_comb, 5);
    /* a sheet that is not CSS is not read; one for another medium is
     * refused, and so is anything outside the subset that might match */
    expect(OPEN "<style type=\"text/x-other\">rect { bogus }</style>" R("") "</svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    refused(OPEN "<style media=\"print\">rect{fill:red}</style></svg>", "<style>", "media");
    refused(OPEN "\n<style>\nrect{fill:red}\n@media screen { rect { fill: lime } }</style></svg>",
            "line 4: <style>", "at-rule");
    refused(OPEN "<style>rect + rect {fill:red}</style></svg>", "<style>", "sibling");
    refused(OPEN "<style>rect::before {fill:red}</style></svg>", "<style>", "pseudo-element");
    refused(OPEN "<style>rect:nth-child(2) {fill:red}</style></svg>", "<style>", "pseudo-class");
    refused(OPEN "<style>rect { fill: red</style></svg>", "<style>", "not closed");
    refused(OPEN "<style>rect { fill }</style></svg>", "<style>", "not a declaration");
    refused(OPEN "<style>/* open</style></svg>", "<style>", "comment");
    refused(OPEN "<style>svg|rect { fill: red }</style></svg>", "<style>", "namespace");
    /* a property the reader does not draw, in a rule that matches: refused
     * naming the sheet's line; in one that matches nothing: harmless */
    refused(OPEN "<style>\n\n.m { mix-blend-mode: multiply }</style>" R("class=\"m\"") "</svg>",
            "mix-blend-mode", "(style sheet line 3)");
    expect(OPEN "<style>.m { mix-blend-mode: multiply }</style>" R("") "</svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* as Illustrator writes a file: a class sheet in CDATA, an XML
     * comment, enable-background (no effect in any browser) */
    expect("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!-- Generator: x -->\n"
           "<svg version=\"1.1\" xmlns=\"http://www.w3.org/2000/svg\" x=\"0px\" y=\"0px\" "
           "viewBox=\"0 0 10 10\" style=\"enable-background:new 0 0 10 10;\" "
           "xml:space=\"preserve\"><style type=\"text/css\"><![CDATA[\n\t.st0{fill:#FFFFFF;}\n"
           "]]></style><rect class=\"st0\" width=\"10\" height=\"10\"/></svg>",
           WHITE " M 0 0 L 100 0 L 100 100 L 0 100 Z");
    /* @charset and @font-face are read past */
    expect(OPEN "<style>@charset \"utf-8\"; @font-face { font-family: x; src: url(a.ttf) } "
                "rect { fill: white }</style>" R("") "</svg>",
           WHITE " M 0 0 L 1 0 L 1 1 L 0 1 Z");
}

/* ---- the CSS transform property ---- */

static void test_css_transform(void **state)
{
    (void)state;
    /* CSS Transforms 1: rotate(90deg) of (1, 0) is (0, 1), then
     * translate(10px, 5px): (10, 6) */
    expect(OPEN "<path style=\"transform: translate(10px, 5px) rotate(90deg)\" d=\"M1 0\"/>"
                "</svg>",
           BLACK " M 10 6 Z");
    /* lengths in units: translateX(1in) = 96; rotate(0.25turn) */
    expect(OPEN "<style>.t { transform: translateX(1in) rotate(0.25turn) }</style>"
                "<path class=\"t\" d=\"M1 0\"/></svg>",
           BLACK " M 96 1 Z");
    /* a sheet's transform wins over the attribute */
    expect(OPEN "<style>path { transform: none }</style>"
                "<path transform=\"translate(5 5)\" d=\"M1 0\"/></svg>",
           BLACK " M 1 0 Z");
    /* transform-origin: rotate(90) about (10, 10) takes (11, 10) to
     * (10, 11) */
    expect(OPEN "<path transform=\"rotate(90)\" transform-origin=\"10 10\" d=\"M11 10\"/></svg>",
           BLACK " M 10 11 Z");
    expect(OPEN "<path style=\"transform: rotate(90deg); transform-origin: 10px 10px\" "
                "d=\"M11 10\"/></svg>",
           BLACK " M 10 11 Z");
    /* transform-box fill-box: the rect [10, 14] x [10, 12] scaled by 2
     * about its centre (12, 11) (transform-origin 50% 50%, center):
     * (10, 10) -> (8, 9), (14, 12) -> (16, 13) */
    expect(OPEN "<rect x=\"10\" y=\"10\" width=\"4\" height=\"2\" style=\"transform: "
                "scale(2); transform-box: fill-box; transform-origin: center\"/></svg>",
           BLACK " M 8 9 L 16 9 L 16 13 L 8 13 Z");
    expect(OPEN "<rect x=\"10\" y=\"10\" width=\"4\" height=\"2\" style=\"transform: "
                "scale(2); transform-box: fill-box; transform-origin: 50% 50%\"/></svg>",
           BLACK " M 8 9 L 16 9 L 16 13 L 8 13 Z");
    /* fill-box without an origin: its top left corner (10, 10) stays */
    expect(OPEN "<rect x=\"10\" y=\"10\" width=\"4\" height=\"2\" style=\"transform: "
                "scale(2); transform-box: fill-box\"/></svg>",
           BLACK " M 10 10 L 18 10 L 18 14 L 10 14 Z");
    /* transform-box stroke-box (SVG 2's stroke bounding box): the rect
     * [10, 14] x [10, 12] stroked 2 wide with miter joins has the box [9,
     * 15] x [9, 13]; scale(2) about its corner (9, 9) takes (10, 10) to
     * (11, 11) and (14, 12) to (19, 15); border-box is stroke-box for SVG
     * (CSS Transforms 1) */
    static const char *const stroked[] = {"stroke-box", "border-box"};
    for (int k = 0; k < 2; k++) {
        char doc[512];
        snprintf(doc, sizeof doc,
                 OPEN "<rect x=\"10\" y=\"10\" width=\"4\" height=\"2\" stroke=\"white\" "
                      "stroke-width=\"2\" style=\"transform: scale(2); transform-box: %s\"/>"
                      "</svg>",
                 stroked[k]);
        const char *got = read_doc(doc);
        const char *want = BLACK " M 11 11 L 19 11 L 19 15 L 11 15 Z 1 1 1;";
        if (strncmp(got, want, strlen(want)))
            fail_msg("%s\n  got  %s\n  want %s...", doc, got, want);
    }
    /* without a stroke the stroke box is the fill box: (10, 10) stays */
    expect(OPEN "<rect x=\"10\" y=\"10\" width=\"4\" height=\"2\" style=\"transform: "
                "scale(2); transform-box: stroke-box\"/></svg>",
           BLACK " M 10 10 L 18 10 L 18 14 L 10 14 Z");
    /* refused inside an object bounding box, where the stroke is not known
     * (the stroke box of offset curves: test_stroke_box.c) */
    refused_clips(OPEN "<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect "
                       "width=\"1\" height=\"1\"/></clipPath><g clip-path=\"url(#o)\"><rect "
                       "width=\"1\" height=\"1\" stroke=\"white\" style=\"transform: "
                       "scale(2); transform-box: stroke-box\"/></g></svg>",
                  "<rect>", "object bounding box");
    /* keywords in either order: right top of the view-box (100 x 100) */
    expect(OPEN "<path transform=\"scale(2)\" transform-origin=\"top right\" d=\"M99 1\"/></svg>",
           BLACK " M 98 2 Z");
    /* numbers without units are invalid in CSS's translate(): the
     * declaration is ignored, the attribute's transform applies */
    expect_partial(OPEN "<path transform=\"translate(1 2)\" style=\"transform: translate(10, "
                        "5)\" d=\"M0 0\"/></svg>",
                   BLACK " M 1 2 Z", "ignored");
    refused(OPEN "<path style=\"transform: rotateX(10deg)\" d=\"M0 0\"/></svg>", "<path>",
            "no 3D");
    /* the root's transform as a declaration: translate(3px, 4px), the
     * origin (the viewport's centre) not mattering */
    expect("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"100\"><style>"
           "svg { transform: translate(3px, 4px) }</style><path d=\"M1 1\"/></svg>",
           BLACK " M 4 5 Z");
}

/* ---- path data errors ---- */

static char warned[4096];
static void keep_warning(const char *msg, void *ctx)
{
    (void)ctx;
    snprintf(warned, sizeof warned, "%s", msg);
}

static void expect_partial(const char *doc, const char *want, const char *warning)
{
    void *octx;
    aa_warn_fn old = aa_get_warn(&octx);
    warned[0] = '\0';
    aa_set_warn(keep_warning, NULL);
    const char *got = read_doc(doc);
    aa_set_warn(old, octx);
    if (strcmp(got, want))
        fail_msg("%s\n  got  %s\n  want %s", doc, got, want);
    if (!strstr(warned, warning) || !strstr(warned, "test.svg: line "))
        fail_msg("%s: warning \"%s\", wanted %s", doc, warned, warning);
}

static void test_path_errors(void **state)
{
    (void)state;
    /* SVG 2: drawn up to, not including, the command with the first
     * error */
    expect_partial(OPEN "\n<path d=\"M 1 1 L 2 2 L 3 x\"/></svg>", BLACK " M 1 1 L 2 2 Z",
                   "line 2");
    expect_partial(OPEN "<path d=\"M0 0 L 4 0 A 5 5 0 2 1 10 10\"/></svg>", BLACK " M 0 0 L 4 0 Z",
                   "large-arc");
    expect_partial(OPEN "<path d=\"M0 0 L 4 0 a 5 5 0 0\"/></svg>", BLACK " M 0 0 L 4 0 Z",
                   "ends too early");
    expect_partial(OPEN "<path d=\"M 1 1 z 3\"/></svg>", BLACK " M 1 1 Z", "after Z");
    expect_partial(OPEN "<path d=\"M 1 1 L 2 1 B 3\"/></svg>", BLACK " M 1 1 L 2 1 Z",
                   "unknown path command");
    /* an implicit repeat is a command of its own */
    expect_partial(OPEN "<path d=\"M 1 1 2 2 3\"/></svg>", BLACK " M 1 1 L 2 2 Z",
                   "ends too early");
    expect_partial(OPEN "<path d=\"L 1 1\"/></svg>", "", "must begin with M");
    /* a number beyond the reader's range is still refused */
    refused(OPEN "<path d=\"M 1 1 L 1e10 0\"/></svg>", "<path>", "out of range");
}

/* ---- invalid attributes ---- */

/* SVG 2, "Presentation attributes": an attribute whose value does not
 * parse is ignored, the property taking its default (verified with
 * Chromium, resvg and librsvg: x="zz" draws at 0, a negative width or r
 * draws nothing, opacity="half" draws opaque, transform="spin(3)" and
 * transform="translate(10px, 0)" draw untransformed); a warning names it.
 * What may be valid but is not read here (a unit such as ch, in calc()
 * too; a division by zero) is still refused, and so is an invalid declaration in
 * CSS, where the cascade would fall to a lower one. */
static void test_invalid_attributes(void **state)
{
    (void)state;
    expect_partial(OPEN "<rect x=\"zz\" width=\"2\" height=\"1\"/></svg>",
                   BLACK " M 0 0 L 2 0 L 2 1 L 0 1 Z", "x=\"zz\"");
    expect_partial(OPEN "<rect width=\"-2\" height=\"1\"/></svg>", "", "negative width");
    expect_partial(OPEN "<circle r=\"-1\"/></svg>", "", "negative r");
    /* a negative ry is auto: the other, 1 */
    expect_partial(OPEN "<ellipse rx=\"1\" ry=\"-2\"/></svg>",
                   BLACK " M 1 0 A 0 0 to 0 1 A 0 0 to -1 0 A 0 0 to 0 -1 A 0 0 to 1 0 Z",
                   "ry=\"-2\"");
    /* rx=-1 is auto, and both auto are square corners */
    expect_partial(OPEN "<rect width=\"1\" height=\"1\" rx=\"-1\"/></svg>",
                   BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z", "rx=\"-1\"");
    /* an invalid inherited property's attribute is its initial value (SVG
     * 2, "Attribute syntax"), not the parent's: fill-opacity 1 drawn where
     * the parent's 0 would draw nothing, fill black under a red group
     * (resvg agrees; Chromium takes the attribute as absent, the
     * parent's value, as CSS takes an invalid declaration) */
    expect_partial(OPEN "<g fill-opacity=\"0\"><rect width=\"1\" height=\"1\" "
                        "fill=\"white\" fill-opacity=\"half\"/></g></svg>",
                   WHITE " M 0 0 L 1 0 L 1 1 L 0 1 Z", "fill-opacity=\"half\"");
    expect_partial(OPEN "<g fill=\"red\">" R("fill=\"bogus\"") "</g></svg>",
                   BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z", "initial value black");
    expect_partial(OPEN "<path transform=\"spin(3)\" d=\"M1 0\"/></svg>", BLACK " M 1 0 Z",
                   "transform=\"spin(3)\"");
    expect_partial(OPEN "<path transform=\"translate(10px, 0)\" d=\"M1 0\"/></svg>",
                   BLACK " M 1 0 Z", "not a transform list");
    refused(OPEN "<rect width=\"1ch\" height=\"1\"/></svg>", "<rect>", "not a length");
    refused(OPEN "<rect width=\"calc(1ch + 1px)\" height=\"1\"/></svg>", "<rect>",
            "calc(");
    refused(OPEN "<rect width=\"calc(1px / 0)\" height=\"1\"/></svg>", "<rect>",
            "out of range");
}

/* ---- math functions, custom properties, the CSS-wide keywords ---- */

/* CSS Values 4's calc(), min(), max() and clamp() wherever a length or a
 * number is read, on the 100 x 100 view (100% of its width is 100 px):
 * each rect's corners worked by hand from the expressions. */
static void test_calc(void **state)
{
    (void)state;
    /* 50% + 2px = 52, 10 * 2 = 20 (a number alone: user units, as
     * Chromium takes height="calc(10 * 2)") */
    expect(OPEN "<rect width=\"calc(50% + 2px)\" height=\"calc(10 * 2)\"/></svg>",
           BLACK " M 0 0 L 52 0 L 52 20 L 0 20 Z");
    /* (1 + 2) * 2 = 6; min(5, 3, 4) = 3; max(1, 2) = 2; clamp(1, 10, 4)
     * = 4; nested calc() */
    expect(OPEN "<rect x=\"calc((1px + 2px) * 2)\" y=\"min(5px, 3px, 4px)\" "
                "width=\"max(1px, calc(2px))\" height=\"clamp(1px, 10px, 4px)\"/></svg>",
           BLACK " M 6 3 L 8 3 L 8 7 L 6 7 Z");
    /* em of the element's font-size, itself calc(1em + 10px) of the
     * parent's 10: 20, plus 10% of 100: 30; 1in / 4 = 24, 3mm * 0 = 0 */
    expect(OPEN "<g font-size=\"10\"><rect width=\"calc(1em + 10%)\" height=\"1\" "
                "font-size=\"calc(1em + 10px)\"/><rect width=\"calc(1in / 4 - 3mm * 0)\" "
                "height=\"1\"/></g></svg>",
           BLACK " M 0 0 L 30 0 L 30 1 L 0 1 Z " BLACK " M 0 0 L 24 0 L 24 1 L 0 1 Z");
    /* a length and a number added or compared, - without white space, a
     * length times a length: invalid, so the attribute is ignored (width
     * 0: nothing) */
    expect_partial(OPEN "<rect width=\"max(1px, 2)\" height=\"1\"/></svg>", "",
                   "not a length");
    expect_partial(OPEN "<rect width=\"calc(10px + 10)\" height=\"1\"/></svg>", "",
                   "not a length");
    expect_partial(OPEN "<rect width=\"calc(10px -5px)\" height=\"1\"/></svg>", "",
                   "not a length");
    expect_partial(OPEN "<rect width=\"calc(2px * 2px)\" height=\"1\"/></svg>", "",
                   "not a length");
    /* an opacity of a percentage and a number added: invalid, ignored
     * (opaque: drawn by this sink of no translucent shapes), as Chromium
     * draws opacity: calc(50% + 0.25); calc(50%) is 0.5, refused here */
    expect_partial(OPEN R("fill=\"white\" style=\"opacity: calc(50% + 0.25)\"") "</svg>",
                   WHITE " M 0 0 L 1 0 L 1 1 L 0 1 Z", "opacity");
    refused(OPEN R("fill=\"white\" style=\"opacity: calc(50%)\"") "</svg>", "<rect>",
            "alpha 0.5");
    /* a negative width of a math function is clamped to 0 (CSS Values 4):
     * no stroke, where -4 written out is ignored (the width 1) */
    expect(OPEN R("stroke=\"white\" style=\"stroke-width: calc(0px - 4px)\"") "</svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* the transform property's lengths (50% of the view box's height, 50)
     * and angles (a quarter turn less 90 degrees: none) */
    expect(OPEN R("style=\"transform: translate(calc(5px + 5px), calc(50% - 50px)) "
                  "rotate(calc(0.25turn - 90deg))\"") "</svg>",
           BLACK " M 10 0 L 11 0 L 11 1 L 10 1 Z");
    /* a unit not read (ch), a division by zero: refused */
    refused(OPEN R("stroke=\"white\" style=\"stroke-width: max(1px, 1ch)\"") "</svg>", "<rect>",
            "stroke-width");
    refused(OPEN R("style=\"transform: rotate(calc(1deg / 0))\"") "</svg>", "<rect>",
            "transform");
}

/* CSS Custom Properties 1: --name declarations, inherited, and var()
 * substituted before the value is parsed (Chromium draws each case so:
 * tests/test_paint_renderers.c's cells). */
static void test_var(void **state)
{
    (void)state;
    /* on the element, through a group, in an attribute, inside calc() */
    expect(OPEN R("style=\"--c: lime; fill: var(--c)\"") "</svg>",
           "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    expect(OPEN "<g style=\"--c: lime\">" R("fill=\"var(--c)\"") "</g></svg>",
           "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    expect(OPEN "<style>g { --w: 5px }</style><g><rect width=\"calc(var(--w) * 2)\" "
                "height=\"1\"/></g></svg>",
           BLACK " M 0 0 L 10 0 L 10 1 L 0 1 Z");
    /* declared on the root (its style attribute, a sheet's rule for it):
     * inherited by its children and theirs (the root was once passed over,
     * each such var() of no value) */
    static const char *const roots[] = {
        "<svg xmlns=\"http://www.w3.org/2000/svg\" style=\"--c: lime; --w: 5px\">",
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><style>svg { --c: lime; --w: 5px }</style>"};
    for (int k = 0; k < 2; k++) {
        char doc[600];
        snprintf(doc, sizeof doc,
                 "%s<rect width=\"1\" height=\"1\" fill=\"var(--c)\"/><g><rect y=\"2\" "
                 "width=\"calc(var(--w) * 2)\" height=\"1\"/></g></svg>",
                 roots[k]);
        expect(doc, "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z " BLACK " M 0 2 L 10 2 L 10 3 L 0 3 Z");
    }
    /* from the <use>, not the element's document parent */
    expect(OPEN "<defs style=\"--c: red\">" "<rect id=\"u\" width=\"1\" height=\"1\" "
                "style=\"fill: var(--c)\"/></defs><use href=\"#u\" style=\"--c: lime\"/></svg>",
           "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* names keep their case: --c is lime, --C red */
    expect(OPEN R("style=\"--c: lime; --C: red; fill: var(--c)\"") "</svg>",
           "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* the fallback, for a property not declared, declared initial, or in
     * a cycle (the whole cycle invalid, fallbacks in it too) */
    expect(OPEN R("style=\"fill: var(--nope, blue)\"") R("style=\"--i: initial; "
                  "fill: var(--i, blue)\"")
                R("style=\"--a: var(--b, lime); --b: var(--a); fill: var(--a, blue)\"") "</svg>",
           "0 0 1; M 0 0 L 1 0 L 1 1 L 0 1 Z 0 0 1; M 0 0 L 1 0 L 1 1 L 0 1 Z 0 0 1; M 0 0 L 1 0 "
           "L 1 1 L 0 1 Z");
    /* invalid at computed-value time: unset, the parent's red (fill is
     * inherited), not the attribute's blue below it: a var() of nothing,
     * a cycle, a value invalid once substituted */
    expect(OPEN "<g fill=\"red\">" R("fill=\"blue\" style=\"fill: var(--nope)\"")
                R("style=\"--a: var(--b); --b: var(--a); fill: var(--a)\"")
                R("style=\"--c: 12; fill: var(--c)\"") "</g></svg>",
           "1 0 0; M 0 0 L 1 0 L 1 1 L 0 1 Z 1 0 0; M 0 0 L 1 0 L 1 1 L 0 1 Z 1 0 0; M 0 0 L 1 0 "
           "L 1 1 L 0 1 Z");
    /* and of a property not inherited, its initial value: no transform */
    expect_partial(OPEN R("style=\"transform: translate(20px); transform: var(--nope)\" "
                          "transform=\"translate(10 0)\"") "</svg>",
                   BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z", "unset");
    /* substituted as tokens: "5" and "px" stay two, so not a length */
    expect_partial(OPEN "<g style=\"--n: 5\"><rect width=\"var(--n)px\" height=\"1\"/></g></svg>",
                   "", "not a length");
    /* a value growing past the reader's 1023 bytes: refused */
    char doc[2048] = OPEN "<rect width=\"1\" height=\"1\" style=\"--a0: 1 1";
    for (int k = 1; k <= 12; k++)
        snprintf(doc + strlen(doc), sizeof doc - strlen(doc), "; --a%d: var(--a%d) var(--a%d)",
                 k, k - 1, k - 1);
    snprintf(doc + strlen(doc), sizeof doc - strlen(doc), "; stroke-dasharray: var(--a12)\"/>"
             "</svg>");
    refused(doc, "<rect>", "too long");
}

/* CSS Cascade 4's inherit, initial, unset and revert, of the properties
 * inherited and not (Chromium draws each case so: the cells of
 * tests/test_paint_renderers.c). */
static void test_css_wide(void **state)
{
    (void)state;
    /* transform: inherit takes the parent's translate(10 0) again: 4 +
     * 10 + 10; as an attribute it is not a transform list, ignored: 14 */
    expect(OPEN "<g transform=\"translate(4 0)\"><g transform=\"translate(10 0)\">"
                R("style=\"transform: inherit\"") "</g></g></svg>",
           BLACK " M 24 0 L 25 0 L 25 1 L 24 1 Z");
    expect_partial(OPEN "<g transform=\"translate(4 0)\"><g transform=\"translate(10 0)\">"
                   R("transform=\"inherit\"") "</g></g></svg>",
                   BLACK " M 14 0 L 15 0 L 15 1 L 14 1 Z", "not a transform list");
    /* initial and unset of transform: none, over the attribute's */
    expect(OPEN R("transform=\"translate(20 0)\" style=\"transform: initial\"")
                R("transform=\"translate(20 0)\" style=\"transform: unset\"") "</svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z " BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* fill="initial" as an attribute: black under a red group */
    expect(OPEN "<g fill=\"red\">" R("fill=\"initial\"") "</g></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* transform-origin: initial is CSS's 50% 50%, of the view box (100 x
     * 100): scale(2) about (50, 50) maps x to 2x - 50; revert is the
     * user agent's 0 0 */
    expect(OPEN R("style=\"transform: scale(2); transform-origin: initial\"")
                R("style=\"transform: scale(2); transform-origin: revert\"") "</svg>",
           BLACK " M -50 -50 L -48 -50 L -48 -48 L -50 -48 Z " BLACK
                 " M 0 0 L 2 0 L 2 2 L 0 2 Z");
    /* overflow: initial is visible, drawn unclipped by a sink of no clips;
     * revert is the user agent's hidden, which clips: refused here; inherit
     * from a group, visible */
    expect(OPEN "<svg width=\"10\" height=\"10\" style=\"overflow: initial\"><rect x=\"-5\" "
                "width=\"20\" height=\"1\"/></svg></svg>",
           BLACK " M -5 0 L 15 0 L 15 1 L -5 1 Z");
    expect(OPEN "<g><svg width=\"10\" height=\"10\" overflow=\"inherit\"><rect x=\"-5\" "
                "width=\"20\" height=\"1\"/></svg></g></svg>",
           BLACK " M -5 0 L 15 0 L 15 1 L -5 1 Z");
    refused(OPEN "<svg width=\"10\" height=\"10\" style=\"overflow: revert\"><rect x=\"-5\" "
                 "width=\"20\" height=\"1\"/></svg></svg>",
            "<svg>", "clips");
    /* stroke-width: revert is unset, inherit: the group's 0 draws no
     * stroke */
    expect(OPEN "<g stroke-width=\"0\">" R("stroke=\"white\" style=\"stroke-width: revert\"")
                "</g></svg>",
           BLACK " M 0 0 L 1 0 L 1 1 L 0 1 Z");
}

/* ---- invalid declarations ---- */

/* CSS 2.1, 4.2 (and CSS Syntax 3): a declaration whose value is invalid is
 * ignored, the cascade going on as if it were not there: the declaration
 * before it, a rule of lower precedence, the presentation attribute, the
 * parent's value (inherited properties) or the initial one.  Chromium
 * draws every case below so (checked: tests/test_paint_renderers.c).  What
 * may be valid but is not drawn is still refused. */
static void test_invalid_declarations(void **state)
{
    (void)state;
    /* the earlier declaration of the same style attribute */
    expect_partial(OPEN R("style=\"fill: lime; fill: bogus\"") "</svg>",
                   "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z", "ignored");
    /* the earlier rule of the same specificity */
    expect_partial(OPEN "<style>.q { fill: blue } .q { fill: bogus }</style>"
                        R("class=\"q\" fill=\"lime\"") "</svg>",
                   "0 0 1; M 0 0 L 1 0 L 1 1 L 0 1 Z", "style sheet line 1");
    /* an invalid !important one: the style attribute's below it */
    expect_partial(OPEN "<style>.q { fill: 12px !important }</style>"
                        R("class=\"q\" style=\"fill: blue\"") "</svg>",
                   "0 0 1; M 0 0 L 1 0 L 1 1 L 0 1 Z", "ignored");
    /* the presentation attribute */
    expect_partial(OPEN R("style=\"fill: bogus\" fill=\"lime\"") "</svg>",
                   "0 1 0; M 0 0 L 1 0 L 1 1 L 0 1 Z", "ignored");
    /* none of them: inherited from the parent */
    expect_partial(OPEN "<g fill=\"red\">" R("style=\"fill: rgb(1, 2)\"") "</g></svg>",
                   "1 0 0; M 0 0 L 1 0 L 1 1 L 0 1 Z", "ignored");
    /* display: the attribute's none, under an invalid declaration */
    expect_partial(OPEN R("display=\"none\" style=\"display: 4\"") "</svg>", "", "ignored");
    /* opacity: half is ignored: opaque, drawn */
    expect_partial(OPEN R("fill=\"white\" style=\"opacity: half\"") "</svg>",
                   WHITE " M 0 0 L 1 0 L 1 1 L 0 1 Z", "opacity");
    /* a negative stroke-width, an unknown keyword, a malformed dash list:
     * ignored (the rect's stroke then has the width 1 of the attribute's
     * absence: its outline is drawn, a second shape) */
    {
        const char *got = read_doc(OPEN R("stroke=\"white\" style=\"stroke-width: -1; "
                                          "stroke-linecap: flat; stroke-dasharray: 1 -2\"")
                                       "</svg>");
        assert_non_null(strstr(got, "1 1 1;"));
    }
    /* CSS Cascade 4's initial and unset of an inherited property: its
     * initial value (black) and the parent's (red) */
    expect(OPEN "<g fill=\"red\">" R("style=\"fill: initial\"") R("style=\"fill: UNSET\"")
                "</g></svg>",
           "0 0 0; M 0 0 L 1 0 L 1 1 L 0 1 Z 1 0 0; M 0 0 L 1 0 L 1 1 L 0 1 Z");
    /* valid, not drawn: refused naming the element */
    refused(OPEN R("style=\"mix-blend-mode: revert\"") "</svg>", "<rect>", "revert");
    refused(OPEN R("style=\"opacity: calc(1 / 0)\"") "</svg>", "<rect>", "opacity");
    refused(OPEN R("style=\"stroke-width: 1ch\"") "</svg>", "<rect>", "not a length");
    refused(OPEN R("style=\"filter: blur(1px)\"") "</svg>", "<rect>", "filters");
    refused(OPEN R("style=\"color-interpolation: linearRGB\"") "</svg>", "<rect>",
            "linear light");
    refused(OPEN R("style=\"fill: color(display-p3 1 0 0)\"") "</svg>", "<rect>", "fill");
    refused(OPEN R("style=\"stroke-width: 1e12\"") "</svg>", "<rect>", "out of range");
}

/* ---- pictures: box references against closed forms ---- */

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "svgstructure");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

static void reference(const char *name, const char *doc, int w, int h, aa_image *img)
{
    char path[4200], spec[4400];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    support_pattern_reference(spec, &(support_view){.w = w, .h = h}, img, NULL, NULL);
}

static double image_sum(const aa_image *img)
{
    double s = 0;
    for (int j = 0; j < img->h; j++)
        for (int i = 0; i < img->w; i++)
            s += aa_pixel(img, i, j)[0];
    return s;
}

/* sRGB's decoding (IEC 61966-2-1), written out here. */
static double dec(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static void test_pictures(void **state)
{
    (void)state;
    aa_image a, b;
    /* opacity: inherit takes the group's own 0.5 (opacity is not
     * inherited: the rect is a group of 0.5 inside the group of 0.5, as
     * Chromium and resvg draw it): white at 0.5 over black is the encoded
     * 0.5, at 0.5 again 0.25 (source over in encoded values), linear
     * dec(0.25), on a rect of 8.5 x 4.5 = 38.25; its width calc(50% -
     * 7.5px) of the 32 px view */
    reference("opacity inherit",
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"32\">"
              "<g opacity=\"0.5\"><rect x=\"2\" y=\"3\" width=\"calc(50% - 7.5px)\" "
              "height=\"4.5\" fill=\"white\" style=\"opacity: inherit\"/></g></svg>",
              32, 32, &a);
    double sum = image_sum(&a);
    print_message("opacity inherit: sum %.17g, 38.25 dec(0.25) %.17g\n", sum,
                  38.25 * dec(0.25));
    assert_true(fabs(sum - 38.25 * dec(0.25)) < 1e-12);
    aa_image_free(&a);
    /* a use of a white rect [1.25, 9.75] x [2.5, 7] moved by (13.5, 17.25)
     * against the rect written at [14.75, 23.25] x [19.75, 24.25]: the
     * same picture, pixel by pixel, and its sum the area 8.5 x 4.5 */
    reference("use",
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"32\">"
              "<defs><rect id=\"r\" x=\"1.25\" y=\"2.5\" width=\"8.5\" height=\"4.5\" "
              "fill=\"white\"/></defs><use href=\"#r\" x=\"13.5\" y=\"17.25\"/></svg>",
              32, 32, &a);
    reference("direct",
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"32\">"
              "<rect x=\"14.75\" y=\"19.75\" width=\"8.5\" height=\"4.5\" fill=\"white\"/></svg>",
              32, 32, &b);
    for (int j = 0; j < 32; j++)
        for (int i = 0; i < 32; i++)
            for (int c = 0; c < 3; c++)
                if (fabs(aa_pixel(&a, i, j)[c] - aa_pixel(&b, i, j)[c]) > 1e-15)
                    fail_msg("pixel (%d, %d): use %.17g, direct %.17g", i, j,
                             aa_pixel(&a, i, j)[c], aa_pixel(&b, i, j)[c]);
    double s = image_sum(&a);
    print_message("use: sum %.17g, area %.17g, error %.3g\n", s, 8.5 * 4.5, s - 8.5 * 4.5);
    assert_true(fabs(s - 8.5 * 4.5) < 1e-12);
    aa_image_free(&a);
    aa_image_free(&b);
    /* a symbol of viewBox 0 0 4 3 holding a disk of radius 1.5 at (2,
     * 1.5), used at 24 x 24: meet scales by min(6, 8) = 6, so the disk's
     * radius is 9 and its area 81 pi */
    reference("symbol",
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"32\" height=\"32\">"
              "<symbol id=\"s\" viewBox=\"0 0 4 3\"><circle cx=\"2\" cy=\"1.5\" r=\"1.5\" "
              "fill=\"white\"/></symbol><use href=\"#s\" x=\"3.5\" y=\"2.25\" width=\"24\" "
              "height=\"24\"/></svg>",
              32, 32, &a);
    s = image_sum(&a);
    print_message("symbol: sum %.17g, 81 pi %.17g, error %.3g\n", s, 81 * M_PI, s - 81 * M_PI);
    assert_true(fabs(s - 81 * M_PI) < 1e-9);
    aa_image_free(&a);
    /* viewports that clip, against closed forms (the scene's exact
     * clips): a nested svg of 20 x 20 at (5.5, 7.25) holding a white disk
     * of radius 15 centred at its corner: the quarter disk, 225 pi / 4 */
#define VSVG(body)                                                                   \
    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"64\" height=\"64\" fill=\"white\">" \
    body "</svg>"
    static const struct {
        const char *name, *doc, *what;
        double area;
    } vp[] = {
        {"quarter", VSVG("<svg x=\"5.5\" y=\"7.25\" width=\"20\" height=\"20\">"
                         "<circle r=\"15\"/></svg>"),
         "225 pi / 4", 225 * M_PI / 4},
        /* the same under rotate(30) about (32, 32): a rotation keeps areas */
        {"quarter, rotated",
         VSVG("<g transform=\"rotate(30 32 32)\"><svg x=\"22\" y=\"22\" width=\"20\" "
              "height=\"20\"><circle r=\"15\"/></svg></g>"),
         "225 pi / 4", 225 * M_PI / 4},
        /* under skewX(30) (determinant 1): the rect [-10, 40] x [5, 15]
         * cut to the viewport's [0, 20] x [5, 15]: 200 */
        {"skewed", VSVG("<g transform=\"translate(10 10) skewX(30)\"><svg width=\"20\" "
                        "height=\"20\"><rect x=\"-10\" y=\"5\" width=\"50\" height=\"10\"/>"
                        "</svg></g>"),
         "200", 200},
        /* a symbol of viewBox 0 0 10 10 used at 20 x 30: meet scales by
         * 2 and centres it 5 down; the rect [-5, 25] x [-5, 7] of the
         * viewBox lands on [-10, 50] x [-5, 19] and the viewport (not the
         * viewBox) [0, 20] x [0, 30] keeps [0, 20] x [0, 19]: 380; the
         * use at (3, 4) moves it whole */
        {"symbol", VSVG("<symbol id=\"s\" viewBox=\"0 0 10 10\"><rect x=\"-5\" y=\"-5\" "
                        "width=\"30\" height=\"12\"/></symbol><use href=\"#s\" x=\"3\" "
                        "y=\"4\" width=\"20\" height=\"30\"/>"),
         "380", 380},
        /* overflow visible: the disk whole, 225 pi */
        {"visible", VSVG("<svg x=\"20\" y=\"20\" width=\"20\" height=\"20\" "
                         "overflow=\"visible\"><circle cx=\"10\" cy=\"10\" r=\"15\"/></svg>"),
         "225 pi", 225 * M_PI},
        /* a group's clip-path (the disk of radius 10 at the viewport's
         * corner) and the viewport (20 x 20) over a rect covering both:
         * the quarter disk of radius 10, 25 pi */
        {"group clip", VSVG("<clipPath id=\"c\"><circle cx=\"10\" cy=\"10\" r=\"10\"/>"
                            "</clipPath><g clip-path=\"url(#c)\"><svg x=\"10\" y=\"10\" "
                            "width=\"20\" height=\"20\"><rect x=\"-10\" y=\"-10\" width=\"60\" "
                            "height=\"60\"/></svg></g>"),
         "25 pi", 25 * M_PI},
        /* objectBoundingBox of a group holding a nested svg of viewBox
         * 0 0 10 10 at (20, 20), 20 x 20: its rect [0, 10]^2 is [20, 40]^2,
         * the box, whose left half the unit rect [0, 1/2] x [0, 1] keeps:
         * 10 x 20 */
        {"box through a viewport",
         VSVG("<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" "
              "height=\"1\"/></clipPath><g clip-path=\"url(#o)\"><svg x=\"20\" y=\"20\" "
              "width=\"20\" height=\"20\" viewBox=\"0 0 10 10\"><rect width=\"10\" "
              "height=\"10\"/></svg></g>"),
         "200", 200},
        /* a symbol's reference point at the use's (x, y): the disk of
         * radius 2 about the centre of viewBox 0 0 4 4, used at (0, 0) as
         * 16 x 16 with refX and refY center, is centred on the view's
         * corner, radius 8: the view keeps a quarter, 16 pi (64 pi were
         * the reference point ignored) */
        {"symbol refX", VSVG("<symbol id=\"s\" viewBox=\"0 0 4 4\" refX=\"center\" "
                             "refY=\"center\"><circle cx=\"2\" cy=\"2\" r=\"2\"/></symbol>"
                             "<use href=\"#s\" width=\"16\" height=\"16\"/>"),
         "16 pi", 16 * M_PI},
        /* objectBoundingBox of a group holding a use: the box holds the
         * used rect [10, 30]^2 (and the rect [10, 12] x [10, 30]), so its
         * left half [10, 20] x [10, 30] is kept: 200 (20, were the use
         * left out of the box) */
        {"box with a use",
         VSVG("<defs><rect id=\"u\" width=\"20\" height=\"20\"/></defs><clipPath id=\"o\" "
              "clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" height=\"1\"/>"
              "</clipPath><g clip-path=\"url(#o)\"><rect x=\"10\" y=\"10\" width=\"2\" "
              "height=\"20\"/><use href=\"#u\" x=\"10\" y=\"10\"/></g>"),
         "200", 200},
        /* the same through a symbol with its reference point: the symbol's
         * rect lands on [22, 42]^2 (its centre at the use's (32, 32)), the
         * group's box is [0, 42] x [22, 42] with the rect [0, 2] x [22,
         * 42], and its left half [0, 21] keeps that rect only: 40 (120 with
         * the symbol's box unshifted, 20 without the use) */
        {"box with a symbol's use",
         VSVG("<symbol id=\"s\" viewBox=\"0 0 10 10\" refX=\"center\" refY=\"center\">"
              "<rect width=\"10\" height=\"10\"/></symbol><clipPath id=\"o\" "
              "clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" height=\"1\"/>"
              "</clipPath><g clip-path=\"url(#o)\"><rect y=\"22\" width=\"2\" "
              "height=\"20\"/><use href=\"#s\" x=\"32\" y=\"32\" width=\"20\" "
              "height=\"20\"/></g>"),
         "40", 40},
        /* a symbol's own x and y, laid out as a nested svg's (SVG 2): its
         * viewport 20 x 10 at x = -25% of the view's 64 (-16) and y = 5
         * clips the rect 30 x 30: the use at (0, 0) shows [0, 4] x [5, 15]
         * of it, 40; a second use 12 wide at (0, 30) puts its viewport on
         * [-16, -4], out of view (x ignored: 200 + 120) */
        {"symbol x and y",
         VSVG("<symbol id=\"s\" x=\"-25%\" y=\"5\" width=\"20\" height=\"10\"><rect "
              "width=\"30\" height=\"30\"/></symbol><use href=\"#s\"/><use href=\"#s\" "
              "y=\"30\" width=\"12\"/>"),
         "40", 40},
        /* objectBoundingBox for a use under a rotation: its box in the
         * clip's user space (translate(x, y) in it) is its target's, the
         * disk of radius 10 scaled by 1.5, [-15, 15]^2; the left half x < 0
         * keeps half the disk, 112.5 pi (nothing, the box taken in the
         * use's parent space: [17, 47] there, its half [17, 32] moved by
         * (32, 32) misses the disk) */
        {"box of a use",
         VSVG("<defs><circle id=\"d\" r=\"10\" transform=\"scale(1.5)\"/></defs>"
              "<clipPath id=\"o\" clipPathUnits=\"objectBoundingBox\"><rect width=\"0.5\" "
              "height=\"1\"/></clipPath><use href=\"#d\" x=\"32\" y=\"32\" "
              "transform=\"rotate(30 32 32)\" clip-path=\"url(#o)\"/>"),
         "112.5 pi", 112.5 * M_PI},
        /* transform-box stroke-box: the white rect [10, 30]^2 stroked
         * white 4 wide is the square [8, 32]^2, its stroke box;
         * translate(-50%) moves it half that box's width, 12, to [-4, 20] x
         * [8, 32], which the view cuts to 20 x 24: 480 (528 by the fill
         * box's 20, 0 by the view box's 64) */
        {"stroke-box translate",
         VSVG("<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\" stroke=\"white\" "
              "stroke-width=\"4\" style=\"transform-box: stroke-box; transform: "
              "translate(-50%, 0)\"/>"),
         "480", 480},
        /* a disk of radius 8 about (20, 20) stroked 4 wide: the disk of
         * radius 10, its stroke box [10, 30]^2; rotate(180deg) about the
         * box's corner (10, 10) puts its centre on the view's corner (0,
         * 0): a quarter of it is drawn, 25 pi */
        {"stroke-box rotation",
         VSVG("<circle cx=\"20\" cy=\"20\" r=\"8\" stroke=\"white\" stroke-width=\"4\" "
              "style=\"transform-box: stroke-box; transform-origin: 0 0; transform: "
              "rotate(180deg)\"/>"),
         "25 pi", 25 * M_PI},
        /* a clip-path inside the viewport: the disk of radius 8 at the
         * viewport's right edge, cut by it: half the disk, 32 pi */
        {"clip inside", VSVG("<svg x=\"4\" y=\"4\" width=\"20\" height=\"20\"><clipPath "
                             "id=\"c\"><circle cx=\"20\" cy=\"10\" r=\"8\"/></clipPath>"
                             "<rect x=\"-4\" y=\"-4\" width=\"50\" height=\"50\" "
                             "clip-path=\"url(#c)\"/></svg>"),
         "32 pi", 32 * M_PI},
    };
#undef VSVG
    for (size_t k = 0; k < sizeof vp / sizeof vp[0]; k++) {
        reference("viewport", vp[k].doc, 64, 64, &a);
        s = image_sum(&a);
        print_message("%s: sum %.17g, %s %.17g, error %.3g\n", vp[k].name, s, vp[k].what,
                      vp[k].area, s - vp[k].area);
        if (!(fabs(s - vp[k].area) < 1e-9))
            fail_msg("%s: the reference sums to %.17g, the area is %.17g", vp[k].name, s,
                     vp[k].area);
        aa_image_free(&a);
    }
    /* 1in x 1cm: 96 x 96/2.54 = 3628.3464566929133 px^2 */
    reference("units",
              "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"128\" height=\"64\">"
              "<rect x=\"0.5cm\" y=\"3pt\" width=\"1in\" height=\"1cm\" fill=\"white\"/></svg>",
              128, 64, &a);
    s = image_sum(&a);
    print_message("1in x 1cm: sum %.17g, area %.17g, error %.3g\n", s, 96 * 96 / 2.54,
                  s - 96 * 96 / 2.54);
    assert_true(fabs(s - 96 * 96 / 2.54) < 1e-10);
    aa_image_free(&a);
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_use), cmocka_unit_test(test_viewports),
             cmocka_unit_test(test_viewport_clips),
             cmocka_unit_test(test_units), cmocka_unit_test(test_conditions),
             cmocka_unit_test(test_sheets),
             cmocka_unit_test(test_css_transform), cmocka_unit_test(test_path_errors),
             cmocka_unit_test(test_invalid_attributes),
             cmocka_unit_test(test_invalid_declarations), cmocka_unit_test(test_calc),
             cmocka_unit_test(test_var), cmocka_unit_test(test_css_wide),
             cmocka_unit_test(test_pictures))
