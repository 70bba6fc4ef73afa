/*
 * test_opacity.c: translucent paint read by the pattern svg
 * (patterns/svgfile.c) into the scene model's alphas and groups
 * (harness/core/scene.c, aa_scene_colour_of), through the box reference,
 * the methods and `export`, against closed forms.
 *
 * Known answers, derived here and not from the code under test:
 *  - compositing (W3C Compositing and Blending Level 1, source-over, in
 *    sRGB-encoded values as browsers composite; SVG 2's group opacity):
 *    a colour c of alpha a over an opaque backdrop b is a c + (1 - a) b,
 *    channel by channel in encoded values; a group of opacity o whose own
 *    content is the colour g (opaque where the group draws) gives
 *    o g + (1 - o) b.  The reference's linear value is the encoded one
 *    decoded by the sRGB formula (IEC 61966-2-1), written out here;
 *  - the box reference of a region of one colour sums to the region's
 *    area times the colour: areas of rectangles and their intersections
 *    by hand;
 *  - CSS Color 4's colours worked by hand from its definitions: hsl()'s
 *    conversion f(n) = l - a max(-1, min(k - 3, 9 - k, 1)),
 *    k = (n + h/30) mod 12, a = s min(l, 1 - l) (hsl(120, 100%, 25%) is
 *    (0, 0.5, 0)), hex digits (#f008 is red at alpha 0x88/255), percentages
 *    and the alpha after "/" or as the fourth argument, clamping;
 *  - currentColor inherits as the keyword (CSS Color 4, "currentcolor":
 *    the used colour is the element's own color), visibility inherits and
 *    a child may show itself again, display: none hides the subtree.
 *
 * The methods: a translucent scene and an opaque scene of the same
 * picture (each region one opaque layer of its composited colour) must
 * give the same image to 1e-9 (the same samples see the same colours), or,
 * for a method whose image depends on how the edges are cut into pieces,
 * an error against the exact reference within 1.5 times the error on the
 * opaque scene; else the method must refuse the scene, naming the
 * translucent layers.  `area`, exact under the box, within 1e-12 of the
 * reference besides.
 */
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

#define W 16
#define H 12

static char dir[4096];

static int setup(void **state)
{
    (void)state;
    return support_tmpdir(dir, sizeof dir, "opacity");
}

static int teardown(void **state)
{
    (void)state;
    return support_rmtree(dir);
}

/* sRGB's decoding (IEC 61966-2-1), written out here. */
static double dec(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* `body` inside a root <svg> of w x h pixels over black, written to a file
 * of the temporary folder; its pattern spec into spec. */
static void svg_spec(const char *name, const char *body, int w, int h, char *spec,
                     size_t len)
{
    char path[4200], doc[8192];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    snprintf(doc, sizeof doc,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n%s\n</svg>\n",
             w, h, body);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, len, "svg:file=%s", path);
}

/* The pattern's scene of `body` at w x h, or NULL with the status in *st. */
static aa_scene *try_scene(const char *name, const char *body, int w, int h, int *st)
{
    char spec[4400];
    svg_spec(name, body, w, h, spec, sizeof spec);
    aa_spec s;
    aa_scene *sc = NULL;
    *st = aa_pattern_parse(spec, &s);
    if (!*st)
        *st = aa_pattern_scene_at(&s, w, h, &sc);
    return *st ? NULL : sc;
}

static aa_scene *scene_of(const char *name, const char *body, int w, int h)
{
    int st;
    aa_scene *sc = try_scene(name, body, w, h, &st);
    if (!sc)
        fail_msg("%s: %s", body, aa_last_error());
    return sc;
}

/* The box reference of `body` at W x H. */
static void box_of(const char *name, const char *body, aa_image *ref)
{
    aa_scene *sc = scene_of(name, body, W, H);
    support_view v = {W, H, 0, 0, 0, NULL, 1, 1, 0};
    support_reference(sc, &v, ref, NULL, NULL);
    aa_scene_free(sc);
}

/* The sum of channel ch over the image. */
static double channel_sum(const aa_image *im, int ch)
{
    return support_channel_mean(im, ch) * im->w * im->h;
}

static void expect_sum(const char *what, const aa_image *im, int ch, double want)
{
    double got = channel_sum(im, ch);
    print_message("%s, channel %d: sum %.15g, closed form %.15g\n", what, ch, got, want);
    if (!(fabs(got - want) <= 1e-12 * fmax(1, fabs(want))))
        fail_msg("%s, channel %d: the box reference sums to %.17g, not %.17g", what, ch, got,
                 want);
}

/* Pixel (i, j) is the encoded colour e (each channel decoded) to 1e-14. */
static void expect_pixel(const char *what, const aa_image *im, int i, int j, const double e[3])
{
    for (int k = 0; k < 3; k++) {
        double got = aa_pixel(im, i, j)[k], want = dec(e[k]);
        if (!(fabs(got - want) <= 1e-14))
            fail_msg("%s: pixel (%d, %d) channel %d is %.17g, not %.17g (encoded %g)", what, i,
                     j, k, got, want, e[k]);
    }
}

/* ---- closed forms ---- */

/* A half-opacity white rectangle over black, written every way SVG and
 * CSS allow: its box reference sums to its area times dec(0.5). */
static void test_half_white(void **state)
{
    (void)state;
    static const char *const paints[] = {
        "fill=\"white\" fill-opacity=\"0.5\"",
        "fill=\"white\" opacity=\"0.5\"",
        "fill=\"white\" style=\"fill-opacity: 50%\"",
        "fill=\"rgba(255, 255, 255, 0.5)\"",
        "fill=\"rgb(100% 100% 100% / 50%)\"",
        "fill=\"hsl(0 0% 100% / 0.5)\"",
        "fill=\"white\" fill-opacity=\"0.5\" stroke=\"red\" stroke-opacity=\"0\"",
        "fill=\"rgba(255, 255, 255, 0.25)\" fill-opacity=\"2\" opacity=\"2\"", /* clamped to 1 */
    };
    const double area = (13.75 - 2.25) * (9.25 - 1.5);
    for (size_t k = 0; k < sizeof paints / sizeof paints[0]; k++) {
        char body[512];
        snprintf(body, sizeof body,
                 "<rect x=\"2.25\" y=\"1.5\" width=\"11.5\" height=\"7.75\" %s/>", paints[k]);
        aa_image ref;
        box_of("half", body, &ref);
        const double a = k == 7 ? 0.25 : 0.5;
        for (int ch = 0; ch < 3; ch++)
            expect_sum(paints[k], &ref, ch, area * dec(a));
        aa_image_free(&ref);
    }
}

/* Two overlapping translucent rectangles: white at 0.5 behind red at 0.6.
 * Encoded, A alone is 0.5 grey, B alone (0.6, 0, 0), both
 * (0.6 + 0.4 x 0.5, 0.4 x 0.5, 0.4 x 0.5) = (0.8, 0.2, 0.2). */
static void test_two_overlapping(void **state)
{
    (void)state;
    const char *body =
        "<rect x=\"2.5\" y=\"1.75\" width=\"9.75\" height=\"7.75\" fill=\"white\" "
        "opacity=\"0.5\"/>\n"
        "<rect x=\"6.5\" y=\"4.25\" width=\"8.25\" height=\"7.25\" fill=\"#f00\" "
        "fill-opacity=\"0.6\"/>";
    aa_image ref;
    box_of("two", body, &ref);
    const double A = 9.75 * 7.75, B = 8.25 * 7.25, I = (12.25 - 6.5) * (9.5 - 4.25);
    expect_sum("two rectangles", &ref, 0, (A - I) * dec(0.5) + (B - I) * dec(0.6) + I * dec(0.8));
    expect_sum("two rectangles", &ref, 1, (A - I) * dec(0.5) + I * dec(0.2));
    expect_sum("two rectangles", &ref, 2, (A - I) * dec(0.5) + I * dec(0.2));
    expect_pixel("A alone", &ref, 3, 2, (const double[3]){0.5, 0.5, 0.5});
    expect_pixel("B alone", &ref, 13, 10, (const double[3]){0.6, 0, 0});
    expect_pixel("A and B", &ref, 8, 6, (const double[3]){0.8, 0.2, 0.2});
    aa_image_free(&ref);
}

/* A group of opacity 0.5 holding blue (A) under red (B), over a grey
 * backdrop 0.2: inside the group red hides blue, then the group is
 * composited as a whole: o g + (1 - o) 0.2.  Per element it would show
 * blue through red. */
static void test_group_opacity(void **state)
{
    (void)state;
    const char *body =
        "<rect width=\"16\" height=\"12\" fill=\"rgb(20%, 20%, 20%)\"/>\n"
        "<g opacity=\"0.5\">\n"
        "  <rect x=\"2.5\" y=\"1.75\" width=\"9.75\" height=\"7.75\" fill=\"blue\"/>\n"
        "  <rect x=\"6.5\" y=\"4.25\" width=\"8.25\" height=\"7.25\" fill=\"red\"/>\n"
        "</g>";
    aa_image ref;
    box_of("group", body, &ref);
    const double A = 9.75 * 7.75, B = 8.25 * 7.25, I = (12.25 - 6.5) * (9.5 - 4.25);
    const double rest = 16 * 12 - A - B + I;
    expect_sum("group", &ref, 0, rest * dec(0.2) + (A - I) * dec(0.1) + B * dec(0.6));
    expect_sum("group", &ref, 1, rest * dec(0.2) + (A - I) * dec(0.1) + B * dec(0.1));
    expect_sum("group", &ref, 2, rest * dec(0.2) + (A - I) * dec(0.6) + B * dec(0.1));
    expect_pixel("group overlap", &ref, 8, 6, (const double[3]){0.6, 0.1, 0.1});
    aa_image_free(&ref);
    /* nested groups multiply: 0.5 of 0.5 of white over black is 0.25,
     * and a translucent layer inside a group is composited inside it:
     * 0.5 x (0.5 white over the group's transparent) = 0.25 */
    box_of("nested",
           "<g opacity=\"0.5\"><g opacity=\"0.5\"><rect width=\"8\" height=\"12\" "
           "fill=\"white\"/></g><rect x=\"8\" width=\"8\" height=\"12\" fill=\"white\" "
           "fill-opacity=\"0.5\"/></g>",
           &ref);
    expect_pixel("nested groups", &ref, 3, 5, (const double[3]){0.25, 0.25, 0.25});
    expect_pixel("alpha in a group", &ref, 12, 5, (const double[3]){0.25, 0.25, 0.25});
    aa_image_free(&ref);
}

/* An element with a fill and a stroke and opacity 0.5: the two are a
 * group, so the stroke's inner half hides the fill before the group is
 * composited.  The rectangle [4, 12] x [3, 9] stroked 2 wide: the stroke
 * covers [3, 13] x [2, 10] less [5, 11] x [4, 8] (56 px), the fill alone
 * [5, 11] x [4, 8] (24 px).  paint-order: stroke puts the fill over the
 * stroke's inner half: the stroke shows on [3, 13] x [2, 10] less the
 * rectangle (32 px), the fill on 48 px. */
static void test_fill_and_stroke(void **state)
{
    (void)state;
    const char *shape = "<rect x=\"4\" y=\"3\" width=\"8\" height=\"6\" fill=\"blue\" "
                        "stroke=\"white\" stroke-width=\"2\" %s/>";
    static const struct {
        const char *attrs;
        double stroke, fill; /* areas */
        double alpha;
    } cases[] = {{"opacity=\"0.5\"", 56, 24, 0.5},
                 {"opacity=\"0.5\" paint-order=\"stroke\"", 32, 48, 0.5},
                 {"style=\"paint-order: stroke markers\"", 32, 48, 1},
                 {"paint-order=\"markers fill\"", 56, 24, 1},
                 {"paint-order=\"normal\"", 56, 24, 1}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char body[512];
        snprintf(body, sizeof body, shape, cases[k].attrs);
        aa_image ref;
        box_of("both", body, &ref);
        const double a = dec(cases[k].alpha);
        expect_sum(cases[k].attrs, &ref, 0, cases[k].stroke * a);
        expect_sum(cases[k].attrs, &ref, 2, (cases[k].stroke + cases[k].fill) * a);
        aa_image_free(&ref);
    }
    /* a stroke's own opacity over another element's fill */
    aa_image ref;
    box_of("stroke",
           "<rect width=\"16\" height=\"12\" fill=\"blue\"/>"
           "<rect x=\"4\" y=\"3\" width=\"8\" height=\"6\" fill=\"none\" stroke=\"white\" "
           "stroke-width=\"2\" stroke-opacity=\"0.25\"/>",
           &ref);
    expect_pixel("stroke-opacity", &ref, 3, 5, (const double[3]){0.25, 0.25, 1});
    expect_sum("stroke-opacity", &ref, 0, 56 * dec(0.25));
    aa_image_free(&ref);
}

/* ---- colours ---- */

/* Each colour on a rectangle over the whole view, over black: every pixel
 * is the colour at its alpha, a c encoded. */
static void test_colours(void **state)
{
    (void)state;
    static const struct {
        const char *value;
        double c[3], a;
    } cases[] = {
        {"hsl(120, 100%, 25%)", {0, 0.5, 0}, 1},
        {"hsl(120deg 100% 25%)", {0, 0.5, 0}, 1},
        {"HSLA(240, 100%, 50%, 0.5)", {0, 0, 1}, 0.5},
        {"hsl(0.5turn 100% 50% / 25%)", {0, 1, 1}, 0.25},
        {"hsl(200grad 100% 50%)", {0, 1, 1}, 1},
        {"hsl(-240 100% 50%)", {0, 1, 0}, 1},
        {"hsl(60 100 50)", {1, 1, 0}, 1},
        {"hsl(30, 100%, 50%)", {1, 0.5, 0}, 1},
        {"hsl(0, 0%, 40%)", {0.4, 0.4, 0.4}, 1},
        {"rgba(255, 0, 0, 0.25)", {1, 0, 0}, 0.25},
        {"rgb(100% 50% 0% / 0.5)", {1, 0.5, 0}, 0.5},
        {"rgb(255 127.5 0)", {1, 0.5, 0}, 1},
        {"rgb(50% 255 0)", {0.5, 1, 0}, 1},
        {"rgb(300, -20, 51)", {1, 0, 0.2}, 1},
        {"rgba(0,0,255,30%)", {0, 0, 1}, 0.3},
        {"rgb(0, 0, 255, 0.5)", {0, 0, 1}, 0.5},
        {"#f008", {1, 0, 0}, 0x88 / 255.0},
        {"#00ff0080", {0, 1, 0}, 0x80 / 255.0},
        {"#0000FF", {0, 0, 1}, 1},
        {"transparent", {0, 0, 0}, 0},
        {"ReD", {1, 0, 0}, 1},
        {"LightGoldenRodYellow", {250 / 255.0, 250 / 255.0, 210 / 255.0}, 1},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char body[512];
        snprintf(body, sizeof body, "<rect width=\"16\" height=\"12\" fill=\"%s\"/>",
                 cases[k].value);
        aa_scene *sc = scene_of("colour", body, W, H);
        aa_rgb got = aa_scene_colour_at(sc, 0.5, 0.5);
        for (int ch = 0; ch < 3; ch++) {
            double want = dec(cases[k].a * cases[k].c[ch]);
            if (!(fabs(got.c[ch] - want) <= 1e-14))
                fail_msg("%s: channel %d is %.17g, not %.17g", cases[k].value, ch, got.c[ch],
                         want);
        }
        aa_scene_free(sc);
    }
    /* what CSS Color 4 does not allow is invalid: as an attribute, the
     * initial fill, black (SVG 2), not the group's white: the sum 0; as a
     * declaration, ignored (CSS 2.1, 4.2), the group's white inherited: the
     * rect's area 16 x 12 */
    static const char *const bad[] = {
        "hsl(120, 100, 25%)", /* legacy: percentages */
        "rgb(255, 0 0)",      /* commas throughout or none */
        "rgb(255 0 0 / 1 1)", "rgb(1, 2, 3, 4, 5)", "rgb(50%, 255, 0)", /* legacy: one type */
        "#12345",             "#ggg",              "hsl(1em 1% 1%)",
        "rgb(255 0 0, 0.5)",  "hsl(none 0% 0%)",   "rgb()",
        "notacolour",
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        for (int decl = 0; decl < 2; decl++) {
            char body[512];
            snprintf(body, sizeof body,
                     decl ? "<g fill=\"white\"><rect width=\"16\" height=\"12\" style=\"fill: "
                            "%s\"/></g>"
                          : "<g fill=\"white\"><rect width=\"16\" height=\"12\" fill=\"%s\"/>"
                            "</g>",
                     bad[k]);
            aa_image im;
            box_of("bad", body, &im);
            expect_sum(bad[k], &im, 0, decl ? 16 * 12 : 0);
            aa_image_free(&im);
        }
}

/* currentColor is inherited as the keyword: the element's own color is
 * used.  color's initial value is black, as browsers give it. */
static void test_current_color(void **state)
{
    (void)state;
    aa_image ref;
    box_of("current",
           "<g color=\"red\" fill=\"currentColor\">"
           "<rect width=\"8\" height=\"12\" color=\"lime\"/>"
           "<rect x=\"8\" width=\"8\" height=\"6\"/>"
           "<rect x=\"8\" y=\"6\" width=\"8\" height=\"6\" fill=\"white\" "
           "style=\"color: rgba(0, 0, 255, 0.5); fill: currentcolor\" stroke=\"none\"/>"
           "</g>",
           &ref);
    expect_pixel("color on the element", &ref, 2, 2, (const double[3]){0, 1, 0});
    expect_pixel("color inherited", &ref, 12, 2, (const double[3]){1, 0, 0});
    expect_pixel("color with alpha", &ref, 12, 9, (const double[3]){0, 0, 0.5});
    aa_image_free(&ref);
    box_of("initial", "<rect width=\"16\" height=\"12\" fill=\"white\"/>"
                      "<rect width=\"8\" height=\"12\" fill=\"currentColor\"/>"
                      "<rect x=\"8\" width=\"8\" height=\"12\" stroke=\"currentColor\" "
                      "fill=\"none\" stroke-width=\"40\" color=\"currentColor\"/>",
           &ref);
    expect_pixel("initial color", &ref, 2, 2, (const double[3]){0, 0, 0});
    expect_pixel("color: currentColor inherits", &ref, 12, 2, (const double[3]){0, 0, 0});
    aa_image_free(&ref);
}

/* visibility hides an element but a child may set visible again;
 * display: none hides the whole subtree. */
static void test_visibility_display(void **state)
{
    (void)state;
    aa_image ref;
    box_of("visibility",
           "<g fill=\"white\" visibility=\"hidden\">"
           "<rect width=\"4\" height=\"12\"/>"
           "<rect x=\"4\" width=\"4\" height=\"12\" visibility=\"visible\"/>"
           "<rect x=\"8\" width=\"4\" height=\"12\" style=\"visibility: collapse\"/>"
           "</g>"
           "<g fill=\"white\" display=\"none\"><rect x=\"12\" width=\"4\" height=\"12\" "
           "display=\"inline\" visibility=\"visible\"/></g>",
           &ref);
    expect_pixel("hidden", &ref, 1, 1, (const double[3]){0, 0, 0});
    expect_pixel("visible in hidden", &ref, 5, 1, (const double[3]){1, 1, 1});
    expect_pixel("collapse", &ref, 9, 1, (const double[3]){0, 0, 0});
    expect_pixel("display none", &ref, 13, 1, (const double[3]){0, 0, 0});
    expect_sum("visibility", &ref, 0, 4 * 12);
    aa_image_free(&ref);
}

/* What is not drawn is refused by name; what is invalid is not. */
static void test_refusals(void **state)
{
    (void)state;
    static const struct {
        const char *body, *words;
    } cases[] = {
        {"<rect width=\"4\" height=\"4\" color-interpolation=\"linearRGB\" opacity=\"0.5\"/>",
         "color-interpolation"},
        {"<rect width=\"4\" height=\"4\" opacity=\"calc(1 / 0)\"/>", "opacity"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        int st;
        aa_scene *sc = try_scene("refused", cases[k].body, W, H, &st);
        if (sc)
            fail_msg("%s was taken", cases[k].body);
        assert_int_equal(st, AA_EINVAL);
        if (!strstr(aa_last_error(), cases[k].words) || !strstr(aa_last_error(), "<rect>"))
            fail_msg("%s: %s", cases[k].body, aa_last_error());
    }
    /* invalid values are not refused: a declaration is ignored, an
     * attribute is the initial value; each white 4 x 4 square is drawn
     * opaque and visible (16), or black by the initial color (0, not the
     * group's white) */
    static const struct {
        const char *body;
        double sum;
    } invalid[] = {
        {"<rect width=\"4\" height=\"4\" fill=\"white\" style=\"fill-opacity: half\"/>", 16},
        {"<rect width=\"4\" height=\"4\" fill=\"white\" paint-order=\"stroke stroke\"/>", 16},
        {"<rect width=\"4\" height=\"4\" fill=\"white\" visibility=\"gone\"/>", 16},
        {"<g color=\"white\"><rect width=\"4\" height=\"4\" fill=\"currentColor\" "
         "color=\"nocolour\"/></g>",
         0},
    };
    for (size_t k = 0; k < sizeof invalid / sizeof invalid[0]; k++) {
        aa_image im;
        box_of("invalid", invalid[k].body, &im);
        expect_sum(invalid[k].body, &im, 0, invalid[k].sum);
        aa_image_free(&im);
    }
}

/* ---- the methods and export ---- */

/* The translucent picture and the same picture in opaque layers, one per
 * region (the colours composited here: see test_two_overlapping; the
 * lime stroke at 0.3 as its ring). */
static const char *const translucent =
    "<rect x=\"1\" y=\"1\" width=\"30\" height=\"22\" fill=\"blue\"/>"
    "<rect x=\"3.3\" y=\"2.2\" width=\"17.4\" height=\"13.2\" fill=\"white\" opacity=\"0.5\"/>"
    "<rect x=\"10.6\" y=\"8.3\" width=\"17.5\" height=\"11.3\" fill=\"red\" "
    "fill-opacity=\"60%\"/>"
    "<rect x=\"0\" y=\"0\" width=\"32\" height=\"24\" fill=\"none\" stroke=\"lime\" "
    "stroke-width=\"1.5\" stroke-opacity=\"0.3\"/>";
/* encoded: blue (0, 0, 1); A over blue (0.5, 0.5, 1); B over blue
 * (0.6, 0, 0.4); B over A over blue (0.8, 0.2, 0.4); the lime stroke at
 * 0.3 over black (0, 0.3, 0): it is 0.25 px short of the blue */
static const char *const opaque =
    "<rect x=\"1\" y=\"1\" width=\"30\" height=\"22\" fill=\"blue\"/>"
    "<rect x=\"3.3\" y=\"2.2\" width=\"17.4\" height=\"13.2\" fill=\"rgb(50%, 50%, 100%)\"/>"
    "<rect x=\"10.6\" y=\"8.3\" width=\"17.5\" height=\"11.3\" fill=\"rgb(60%, 0%, 40%)\"/>"
    "<rect x=\"10.6\" y=\"8.3\" width=\"10.1\" height=\"7.1\" fill=\"rgb(80%, 20%, 40%)\"/>"
    "<path d=\"M -0.75 -0.75 H 32.75 V 24.75 H -0.75 Z M 0.75 0.75 V 23.25 H 31.25 V 0.75 Z\" "
    "fill=\"rgb(0%, 30%, 0%)\"/>";

/* Every method in the table on the translucent scene t and the opaque
 * scene o of the same picture; counts into taken and refused. */
static void methods_on(const char *name_t, const char *t_body, const char *name_o,
                       const char *o_body, int w, int h, int *taken, int *refused)
{
    aa_scene *t = scene_of(name_t, t_body, w, h);
    aa_scene *o = scene_of(name_o, o_body, w, h);
    assert_false(aa_scene_is_opaque(t));
    assert_true(aa_scene_is_opaque(o));
    static const char *const filters[] = {"box", "tent:r=1", "cone:r=1", "gauss:s=0.5"};
    /* the two pictures are the same: their references agree */
    for (size_t f = 0; f < sizeof filters / sizeof filters[0]; f++) {
        support_view v = {w, h, 0, 0, 0, filters[f], 1, 1, 0};
        aa_image rt, ro;
        support_reference(t, &v, &rt, NULL, NULL);
        support_reference(o, &v, &ro, NULL, NULL);
        double d = support_max_diff(&rt, &ro, NULL, NULL);
        if (!(d <= 1e-12))
            fail_msg("%s: references under %s differ by %.3e", name_t, filters[f], d);
        aa_image_free(&rt);
        aa_image_free(&ro);
    }
    /* every method at its defaults, and the settings that draw otherwise */
    static const char *const extra[] = {"crowtiler:hidden=scan", NULL};
    const aa_method_type *const *m = aa_method_types;
    for (const char *const *x = extra; *m || *x;) {
        const char *name = *m ? (*m++)->info.name : *x++;
        const char *filter = NULL;
        for (size_t f = 0; f < sizeof filters / sizeof filters[0] && !filter; f++)
            if (support_parse_method(name, filters[f], NULL) == AA_OK)
                filter = filters[f];
        if (!filter)
            fail_msg("%s takes none of the filters tried", name);
        support_view v = {w, h, 0, 0, 0, filter, 1, 1, 0};
        aa_image it, io;
        int so = support_render_view(name, o, &v, &io, NULL);
        int st = support_render_view(name, t, &v, &it, NULL);
        if (st) {
            if (so) { /* refused for another reason (colour, layers) */
                print_message("%s on %s: refuses the opaque scene too\n", name, name_t);
                continue;
            }
            aa_image_free(&io);
            if (!strstr(aa_last_error(), "translucent"))
                fail_msg("%s refuses %s without naming its translucent layers: %s", name,
                         name_t, aa_last_error());
            print_message("%s on %s refuses: %s\n", name, name_t, aa_last_error());
            (*refused)++;
            continue;
        }
        if (so)
            fail_msg("%s takes %s but not the opaque one: %s", name, name_t, aa_last_error());
        if (!strcmp(name, "area")) { /* exact under the box: the reference's bound */
            aa_image rt;
            support_reference(t, &v, &rt, NULL, NULL);
            double e = support_max_diff(&it, &rt, NULL, NULL);
            print_message("area on %s: %.3g from the reference\n", name_t, e);
            if (!(e <= 1e-12))
                fail_msg("area on %s: %.3g from the reference", name_t, e);
            aa_image_free(&rt);
        }
        double d = support_max_diff(&it, &io, NULL, NULL);
        if (!(d <= 1e-9)) {
            aa_image rt, ro;
            support_reference(t, &v, &rt, NULL, NULL);
            support_reference(o, &v, &ro, NULL, NULL);
            double et = support_rmse(&it, &rt), eo = support_rmse(&io, &ro);
            print_message("%s on %s: images differ by %.3e; RMSE %.3e (translucent), %.3e "
                          "(opaque)\n",
                          name, name_t, d, et, eo);
            if (!(et <= 1.5 * eo + 1e-9))
                fail_msg("%s: RMSE %.3e on %s, %.3e on the same picture opaque", name, et,
                         name_t, eo);
            aa_image_free(&rt);
            aa_image_free(&ro);
        }
        (*taken)++;
        aa_image_free(&it);
        aa_image_free(&io);
    }
    aa_scene_free(t);
    aa_scene_free(o);
}

static void test_methods(void **state)
{
    (void)state;
    int taken = 0, refused = 0;
    methods_on("translucent", translucent, "opaque", opaque, 32, 24, &taken, &refused);
    /* one grey layer: opaque, the peers' one-layer grey path; translucent,
     * painted (algorithms/peer.h) */
    methods_on("grey", "<rect x=\"3.3\" y=\"2.2\" width=\"17.4\" height=\"13.2\" fill=\"white\" "
                       "fill-opacity=\"0.5\"/>",
               "grey-opaque", "<rect x=\"3.3\" y=\"2.2\" width=\"17.4\" height=\"13.2\" "
                              "fill=\"rgb(50%, 50%, 50%)\"/>",
               32, 24, &taken, &refused);
    print_message("%d times a method drew a translucent scene, %d times it refused it\n", taken,
                  refused);
    assert_true(taken > 0 && refused > 0);
}

/* export writes the alphas and groups back: the document read again has
 * the same box reference. */
static void test_export(void **state)
{
    (void)state;
    const char *body =
        "<rect width=\"32\" height=\"24\" fill=\"rgb(20%, 40%, 60%)\"/>"
        "<g opacity=\"0.6\"><rect x=\"2.5\" y=\"1.5\" width=\"20\" height=\"12\" fill=\"red\" "
        "fill-opacity=\"0.7\"/><g opacity=\"0.5\"><circle cx=\"16\" cy=\"12\" r=\"7.3\" "
        "fill=\"yellow\" stroke=\"white\" stroke-width=\"2\" stroke-opacity=\"0.4\"/></g></g>"
        "<rect x=\"12.25\" y=\"6.5\" width=\"15\" height=\"14\" fill=\"lime\" stroke=\"black\" "
        "opacity=\"0.35\"/>";
    const int w = 32, h = 24;
    aa_scene *sc = scene_of("export", body, w, h);
    assert_int_equal(aa_scene_group_count(sc), 3);
    aa_scene *placed = aa_scene_place(sc, w, h, 0, 0, 0);
    assert_non_null(placed);
    char path[4200];
    snprintf(path, sizeof path, "%s/exported.svg", dir);
    if (aa_scene_svg_write(path, placed, w, h, AA_SVG_COLOURS, "round trip"))
        fail_msg("%s", aa_last_error());
    static char text[1 << 16];
    support_read_file(path, text, sizeof text, NULL);
    assert_non_null(strstr(text, "<g opacity=\"0.59999999999999998\">"));
    assert_non_null(strstr(text, "fill-opacity=\"0.69999999999999996\""));
    assert_non_null(strstr(text, "stroke-opacity=\"0.40000000000000002\""));
    char spec[4400];
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec s;
    aa_scene *back = NULL;
    if (aa_pattern_parse(spec, &s) || aa_pattern_scene_at(&s, w, h, &back))
        fail_msg("%s", aa_last_error());
    support_view v = {w, h, 0, 0, 0, NULL, 1, 1, 0};
    aa_image r1, r2;
    support_reference(sc, &v, &r1, NULL, NULL);
    support_reference(back, &v, &r2, NULL, NULL);
    double d = support_max_diff(&r1, &r2, NULL, NULL);
    print_message("exported and read back: the box references differ by %.3e\n", d);
    assert_true(d <= 1e-12);
    aa_image_free(&r1);
    aa_image_free(&r2);
    aa_scene_free(back);
    aa_scene_free(placed);
    aa_scene_free(sc);
}

SUPPORT_MAIN(setup, teardown, cmocka_unit_test(test_half_white),
             cmocka_unit_test(test_two_overlapping), cmocka_unit_test(test_group_opacity),
             cmocka_unit_test(test_fill_and_stroke), cmocka_unit_test(test_colours),
             cmocka_unit_test(test_current_color), cmocka_unit_test(test_visibility_display),
             cmocka_unit_test(test_refusals), cmocka_unit_test(test_methods),
             cmocka_unit_test(test_export))
