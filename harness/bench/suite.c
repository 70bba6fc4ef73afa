/*
 * suite.c: the named suites of `aabench run` (harness/bench/README.md, "Runs and suites").
 *
 *   quick    every method family once on crow 128x128, each under a filter
 *            it accepts (box; tent:r=1 for Crow's tables and tiler and for
 *            analytic; gauss
 *            for Feibush et al.'s edge and texture filters): the regression
 *            gate's suite
 *            (results/baseline.csv); a few seconds
 *   default  every family at its main settings on crow 256x256 and
 *            1024x1024: the main job of `make run`
 *   paper    the settings of the seed papers' figures (figures.c)
 *   full     every method variant under every filter it accepts, on crow
 *            at both sizes; every family under every filter on the other
 *            seed scenes and the zone plate at 256x256
 *   vector   what a vector graphics or font rasterizer draws: crow, the SVG
 *            scenes shipped in patterns/svg and text at 12, 16 and 24 ppem,
 *            by area, the sampling methods, the in-process peers and the
 *            external renderers (one not installed is left out)
 *   strokes  strokes and conics: the `strokes` pattern, `rings`, the shipped
 *            strokes.svg and arcs.svg, by area, point, supersampling, the
 *            peers (cairo and agg with their own strokers) and the external
 *            renderers
 *
 * A suite's groups are cross products; `aabench run` leaves out the pairs a
 * method refuses (a filter it cannot honour, a scene it cannot take) and
 * says how many, so a group may list every filter.
 */
#include "bench.h"

#include <string.h>

#define LIST(...) ((const char *const[]){__VA_ARGS__, NULL})

static const aa_suite_group quick[] = {
    {LIST("crow"), LIST("128x128"), LIST("box"),
     LIST("point", "supersample", "jitter", "hexagon", "trio", "mlaa", "fxaa", "smaa", "area",
          "adaptive", "taa", "cycle", "freetype", "stb", "cairo", "agg")},
    {LIST("crow"), LIST("128x128"), LIST("tent:r=1"), LIST("crowtable", "crowtiler", "analytic")},
    {LIST("crow"), LIST("128x128"), LIST("gauss"), LIST("conetable", "feibushtex")},
    {NULL, NULL, NULL, NULL}};

static const aa_suite_group main_suite[] = {
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("box"),
     LIST("point", "supersample:n=3", "supersample:n=4", "supersample:pattern=msaa4",
          "supersample:pattern=msaa8", "jitter:spp=16", "jitter:spp=16,seq=random",
          "jitter:spp=16,seq=sobol", "jitter:spp=16,seq=halton", "jitter:spp=64", "hexagon",
          "trio", "trio:variant=sancha", "trio:variant=recursive", "mlaa", "fxaa", "smaa",
          "area", "adaptive", "taa", "cycle", "freetype", "stb", "cairo", "agg")},
    /* Crow's pyramid two dots wide (fig. 2.14): his tables and his tiler;
     * Manson and Schaefer's analytic rasterization, exact under it */
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("tent:r=1"),
     LIST("crowtable", "crowtable:form=rows", "crowtiler", "analytic")},
    /* Feibush et al.'s Gaussian of fig. 4d (s = 1 pixel, mask radius 2 s):
     * their edge filter, and their texture filter with the edge filter */
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("gauss:s=1"),
     LIST("conetable", "feibushtex")},
    {NULL, NULL, NULL, NULL}};

/* The settings of the figures (figures.c): Crow 1976 figs. 2.10-2.14,
 * 3.14-3.19; Feibush et al. 1980 figs. 4b-4d and the cone table (fig. 3a). */
static const aa_suite_group paper[] = {
    {LIST("crow"), LIST("256x256"), LIST("box"), LIST("point", "supersample:n=3", "area")},
    {LIST("crow"), LIST("256x256"), LIST("tent:r=1"),
     LIST("supersample:n=5", "crowtable", "crowtiler")},
    {LIST("crow"), LIST("256x256"), LIST("tent:r=0.5"), LIST("crowtable", "supersample:n=5")},
    {LIST("crow"), LIST("512x512"), LIST("box", "tent:r=1"), LIST("point", "crowtiler")},
    {LIST("star", "slivers"), LIST("256x256"), LIST("box", "tent:r=1"),
     LIST("point", "supersample:n=2", "crowtiler")},
    {LIST("feibush:stripes=200"), LIST("512x512"), LIST("box", "gauss:s=1"),
     LIST("point", "area", "conetable", "feibushtex:texels=1000")},
    {LIST("crow"), LIST("256x256"), LIST("cone"), LIST("conetable:weight=cone")},
    {NULL, NULL, NULL, NULL}};

/* Every family at its defaults, for the scenes besides crow. */
#define FAMILIES                                                                               \
    "point", "supersample", "jitter", "hexagon", "trio", "mlaa", "fxaa", "smaa", "area", "taa", \
        "cycle", "adaptive", "freetype", "stb", "cairo", "agg", "crowtable", "conetable",          \
        "crowtiler", "feibushtex", "analytic"

static const aa_suite_group full[] = {
    {LIST("crow"), LIST("256x256", "1024x1024"),
     LIST("box", "tent:r=0.5", "tent:r=1", "gauss", "gauss:s=1", "cone", "cone:r=2"),
     LIST("point", "supersample:n=2", "supersample:n=3", "supersample:n=4", "supersample:n=5",
          "supersample:n=8", "supersample:pattern=msaa2", "supersample:pattern=msaa4",
          "supersample:pattern=msaa8", "supersample:pattern=msaa16", "jitter:spp=4",
          "jitter:spp=16", "jitter:spp=64", "jitter:spp=256", "jitter:spp=16,seq=random",
          "jitter:spp=16,seq=sobol", "jitter:spp=16,seq=halton",
          "jitter:spp=16,seq=niederreiter", "jitter:spp=64,seq=sobol",
          "jitter:spp=16,seq=bluenoise", "hexagon",
          "hexagon:display=fixed", "trio", "trio:variant=halflines", "trio:variant=sancha",
          "trio:variant=recursive", "mlaa", "fxaa", "smaa", "smaa:rounding=1",
          "area", "area:integrator=bands", "taa", "taa:frames=16",
          "taa:reproject=none,clamp=none",
          "cycle", "cycle:positions=msaa16", "adaptive", "adaptive:tag=1", "freetype", "stb",
          "cairo", "agg", "agg:scale=4", "crowtable", "crowtable:form=rows", "crowtable:res=64",
          "conetable", "conetable:cut=3", "conetable:res=256", "crowtiler",
          "crowtiler:hidden=scan", "crowtiler:area=exact", "crowtiler:area=exact,hidden=scan",
          "feibushtex",
          "feibushtex:res=128", "analytic")},
    /* analytic under the polynomial filters beyond the tent */
    {LIST("crow"), LIST("256x256", "1024x1024"),
     LIST("bspline:order=2", "bspline:order=3", "mitchell", "catrom"), LIST("analytic")},
    /* and under the radial polynomial filters (per pixel: 256x256 only) */
    {LIST("crow"), LIST("256x256"), LIST("radial:k=1,r=1", "radial", "radial:k=3,r=2"),
     LIST("analytic", "supersample:n=4")},
    {LIST("catmull:tiles=3", "slivers", "star", "feibush", "fence", "dots"), LIST("256x256"),
     LIST("box", "tent:r=1", "gauss", "cone"), LIST(FAMILIES)},
    /* the zone plate has exact integrals for box, tent and gauss, and only
     * the methods that sample a field's point function take it */
    {LIST("zoneplate"), LIST("256x256"), LIST("box", "tent:r=1", "gauss"), LIST(FAMILIES)},
    {NULL, NULL, NULL, NULL}};

/* The shipped SVG scenes as pattern specs, "svg:file=DIR/NAME" with DIR
 * the folder aa_svg_dir finds (the source tree's or the install prefix's),
 * made when the library starts; a spec too long to make is left "svg:file="
 * (refused by the pattern when the suite runs). */
static const char *const svg_names[] = {"mono.svg", "shapes.svg", "rules.svg", "curves.svg",
                                        "logo.svg", "strokes.svg", "arcs.svg"};
#define NSVG (sizeof svg_names / sizeof svg_names[0])
static char svg_spec[NSVG][AA_PARAM_TEXT_MAX + 32];
static const char *vector_patterns[] = {"crow",      svg_spec[0], svg_spec[1], svg_spec[2],
                                        svg_spec[3], svg_spec[4], NULL};

/* text into a spec's text value: ',' as %2C and '%' as %25 */
static int spec_text(char *buf, size_t len, const char *text)
{
    size_t n = 0;
    for (const char *c = text; *c; c++) {
        const char *put = *c == ',' ? "%2C" : *c == '%' ? "%25" : NULL;
        size_t m = put ? 3 : 1;
        if (n + m >= len)
            return 0;
        memcpy(buf + n, put ? put : c, m);
        n += m;
    }
    buf[n] = '\0';
    return 1;
}

__attribute__((constructor)) static void svg_specs_make(void)
{
    static const char prefix[] = "svg:file=";
    char path[AA_PARAM_TEXT_MAX + 1];
    for (size_t k = 0; k < NSVG; k++) {
        memcpy(svg_spec[k], prefix, sizeof prefix);
        if (aa_pathf(path, sizeof path, "%s/%s", aa_svg_dir(), svg_names[k]) == AA_OK &&
            !spec_text(svg_spec[k] + sizeof prefix - 1, sizeof svg_spec[k] - (sizeof prefix - 1),
                       path))
            svg_spec[k][sizeof prefix - 1] = '\0';
    }
}

#define VECTOR_METHODS                                                                            \
    LIST("area", "point", "supersample:n=4", "supersample:pattern=msaa8", "jitter:spp=16",       \
         "trio", "mlaa", "fxaa", "smaa",                                                          \
         "adaptive", "freetype", "stb", "cairo", "agg", "agg:scale=100",                          \
         "external:renderer=rsvg", "external:renderer=resvg", "external:renderer=chromium")

/* Strokes and conics: the `strokes` pattern (every join and cap, kept as
 * strokes, which cairo and agg stroke themselves), the conic moire `rings`,
 * and the shipped strokes.svg and arcs.svg (colour: the peers leave them
 * out). */
static const char *stroke_patterns[] = {"strokes", "rings", svg_spec[5], svg_spec[6], NULL};

#define STROKE_METHODS                                                                            \
    LIST("area", "point", "supersample:n=4", "freetype", "stb", "cairo", "agg",                  \
         "external:renderer=rsvg", "external:renderer=resvg", "external:renderer=chromium")

static const aa_suite_group strokes[] = {
    {stroke_patterns, LIST("256x256"), LIST("box"), STROKE_METHODS},
    {NULL, NULL, NULL, NULL}};

static const aa_suite_group vector[] = {
    {vector_patterns, LIST("256x256"), LIST("box"), VECTOR_METHODS},
    {LIST("text:ppem=12", "text:ppem=16", "text:ppem=24"), LIST("288x32"), LIST("box"),
     VECTOR_METHODS},
    {NULL, NULL, NULL, NULL}};

const aa_suite aa_suites[] = {
    {"quick", "every family once on crow 128x128 (the regression gate)", quick},
    {"default", "every family at its main settings on crow 256x256 and 1024x1024", main_suite},
    {"paper", "the settings of the seed papers' figures", paper},
    {"full", "every method variant under every filter it accepts; every scene; the zone plate",
     full},
    {"vector", "crow, the shipped SVG scenes and text at 12, 16 and 24 ppem: area, sampling, "
               "the peers and the external renderers",
     vector},
    {"strokes", "strokes and conics: the strokes pattern, rings, strokes.svg and arcs.svg: "
                "area, sampling, the peers' own strokers and the external renderers",
     strokes},
    {"temporal", "fence, dots, crow and star moving at sub-pixel speeds: temporal metrics",
     aa_suite_temporal_groups},
    {NULL, NULL, NULL}};

const aa_suite *aa_suite_find(const char *name)
{
    for (const aa_suite *s = aa_suites; s->name; s++)
        if (!strcmp(s->name, name))
            return s;
    return NULL;
}
