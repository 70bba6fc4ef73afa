/*
 * suite.c: the named suites of `aabench run` (README.md, "The benchmark").
 *
 *   quick    every family once on crow 128x128 box: the regression gate's
 *            suite (results/baseline.csv); well under 30 s
 *   default  every family at its main settings on crow 256x256 and
 *            1024x1024 box: the main job of `make run`
 *   paper    the settings of the seed figures (Crow 1976 figs. 2.10-2.14;
 *            Feibush et al. 1980 fig. 3a, the cone table)
 *   full     every method variant, every filter, both sizes, on crow; the
 *            other seed scenes at 256x256
 *   vector   what a vector graphics or font rasterizer draws: crow, the SVG
 *            scenes shipped in patterns/svg and text at 12, 16 and 24 ppem,
 *            by area, the sampling methods, the in-process peers and the
 *            external renderers (a renderer not installed is a refused row)
 */
#include "bench.h"

#include <string.h>

#define LIST(...) ((const char *const[]){__VA_ARGS__, NULL})

static const aa_suite_group quick[] = {
    {LIST("crow"), LIST("128x128"), LIST("box"),
     LIST("point", "supersample", "jitter", "hexagon", "trio", "area", "adaptive", "taa",
          "cycle", "freetype", "stb", "cairo")},
    {NULL, NULL, NULL, NULL}};

static const aa_suite_group main_suite[] = {
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("box"),
     LIST("point", "supersample:n=3", "supersample:n=4", "supersample:pattern=msaa4",
          "supersample:pattern=msaa8", "jitter:spp=16", "jitter:spp=16,seq=random",
          "jitter:spp=16,seq=sobol", "jitter:spp=16,seq=halton", "jitter:spp=64", "hexagon",
          "trio", "trio:variant=sancha", "trio:variant=recursive", "area", "adaptive", "taa",
          "freetype", "stb", "cairo")},
    {NULL, NULL, NULL, NULL}};

/* Crow 1976: fig. 2.10 point sampled, 2.11 nine equal samples, 2.12 25
 * unequally weighted samples (tent base two pixels), 2.13 and 2.14 the
 * triangular filters of base one and two pixels (their references are the
 * exact images; sampled approximations beside them). */
static const aa_suite_group paper[] = {
    {LIST("crow"), LIST("256x256"), LIST("box"),
     LIST("point", "supersample:n=3", "jitter:spp=16", "area")},
    {LIST("crow"), LIST("256x256"), LIST("tent:r=1"),
     LIST("supersample:n=5", "supersample:n=3", "jitter:spp=64")},
    {LIST("crow"), LIST("256x256"), LIST("tent:r=0.5"),
     LIST("supersample:n=5", "jitter:spp=64")},
    /* Feibush, Levoy and Cook 1980, fig. 2f, 3a: the cone's volumes over
     * right triangles from a table, against the exact cone reference */
    {LIST("crow"), LIST("256x256"), LIST("cone"), LIST("conetable:weight=cone")},
    {NULL, NULL, NULL, NULL}};

static const aa_suite_group full[] = {
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("box"),
     LIST("point", "supersample:n=2", "supersample:n=3", "supersample:n=4", "supersample:n=8",
          "supersample:pattern=msaa2", "supersample:pattern=msaa4", "supersample:pattern=msaa8",
          "supersample:pattern=msaa16", "jitter:spp=4", "jitter:spp=16", "jitter:spp=64",
          "jitter:spp=256", "jitter:spp=16,seq=random", "jitter:spp=16,seq=sobol",
          "jitter:spp=16,seq=halton", "jitter:spp=16,seq=niederreiter", "hexagon", "trio",
          "trio:variant=sancha", "trio:variant=recursive", "area")},
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("tent:r=0.5", "tent:r=1", "gauss"),
     LIST("supersample:n=3", "supersample:n=5", "supersample:pattern=msaa8", "jitter:spp=16",
          "jitter:spp=64", "jitter:spp=64,seq=sobol")},
    {LIST("crow"), LIST("256x256", "1024x1024"), LIST("cone"),
     LIST("conetable:weight=cone", "supersample:n=5", "jitter:spp=64")},
    {LIST("catmull:tiles=3", "slivers", "star", "feibush", "fence", "dots"), LIST("256x256"),
     LIST("box"),
     LIST("point", "supersample:n=4", "supersample:pattern=msaa8", "jitter:spp=16",
          "jitter:spp=64", "hexagon", "trio", "area")},
    {LIST("slivers", "star", "feibush", "fence", "dots"), LIST("256x256"),
     LIST("tent:r=1", "gauss"), LIST("supersample:n=5", "jitter:spp=64")},
    {NULL, NULL, NULL, NULL}};

/* the shipped SVG scenes (the Makefile sets AA_SVG_DIR to the tree's) */
#ifndef AA_SVG_DIR
#define AA_SVG_DIR "patterns/svg"
#endif
#define VECTOR_METHODS                                                                            \
    LIST("area", "point", "supersample:n=4", "supersample:pattern=msaa8", "jitter:spp=16",       \
         "adaptive", "freetype", "stb", "cairo", "agg", "agg:scale=100",                          \
         "external:renderer=rsvg", "external:renderer=resvg", "external:renderer=chromium")

static const aa_suite_group vector[] = {
    {LIST("crow", "svg:file=" AA_SVG_DIR "/mono.svg", "svg:file=" AA_SVG_DIR "/shapes.svg",
          "svg:file=" AA_SVG_DIR "/rules.svg", "svg:file=" AA_SVG_DIR "/curves.svg",
          "svg:file=" AA_SVG_DIR "/logo.svg"),
     LIST("256x256"), LIST("box"), VECTOR_METHODS},
    {LIST("text:ppem=12", "text:ppem=16", "text:ppem=24"), LIST("288x32"), LIST("box"),
     VECTOR_METHODS},
    {NULL, NULL, NULL, NULL}};

const aa_suite aa_suites[] = {
    {"quick", "every family once on crow 128x128 box (the regression gate)", quick},
    {"default", "every family at its main settings on crow 256x256 and 1024x1024 box",
     main_suite},
    {"paper", "the settings of Crow's figures 2.10-2.14 and Feibush's cone table (fig. 3a)",
     paper},
    {"full", "every method variant under every filter", full},
    {"vector", "crow, the shipped SVG scenes and text at 12, 16 and 24 ppem: area, sampling, "
               "the peers and the external renderers",
     vector},
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
