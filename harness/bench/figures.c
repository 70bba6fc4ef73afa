/*
 * figures.c: the seed papers' comparison figures, remade.
 *
 * Each figure is a list of panels rendered on one view (pattern, size,
 * scene position) and composed with aa_montage_write into DIR/NAME.png;
 * DIR/NAME.txt holds what the paper's figure shows and with which method,
 * what the paper claims for it, what stands in for the paper's method or
 * scene where this benchmark cannot use it (and why), the settings and, for
 * every panel, its RMSE and largest error against the exact reference under
 * the panel's own filter (aa_reference, aa_metrics_compute, linear light)
 * and what an observer's eye sees of it against what it sees of the scene
 * (eye.c).  DIR/index.html shows every figure present in DIR and, when
 * DIR/claims.html exists (claims.c), the table of the papers' claims.
 *
 * The figures: Crow 1976 (the thesis, University of Utah, UTEC-CSc-76-015)
 * figs. 2.10-2.14 (ch. 2, "Evaluating convolutional filters"), 3.14-3.19
 * (ch. 3, his filtering tiler against conventional tilers), A.1-A.4
 * (appendix, "Grey scale compensation": the colour maps and the
 * calibration, measured by calibration.c) and an extra on display
 * encodings; Catmull 1978 fig. 1 (one pixel's colour by each method);
 * Feibush, Levoy and Cook 1980 figs. 4b-4d; and, beyond the seeds, Manson
 * and Schaefer 2013's comparison of filters (analytic under four piecewise
 * polynomial filters).  Limits: the patterns are this
 * project's renditions of the papers' scenes (patterns/README.md), not
 * scans of the originals, and the panels are shown at the size they are
 * rendered (only fig-catmull-1 is magnified, by replicating pixels), so a
 * page viewer's scaling may add moire of its own.
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FIG_SEED 1

enum panel_kind {
    P_METHOD,    /* the method on the view */
    P_REFERENCE, /* the exact reference of the view */
    P_DOWN2,     /* the method at twice the size, box-averaged 2 x 2 down */
    P_ENCODED,   /* the method shown with an encoding, beside a grey ramp */
    P_MAP        /* the method shown with intensity v^g, beside a grey ramp */
};

typedef struct fig_panel {
    int kind;
    const char *method; /* method spec (not P_REFERENCE) */
    const char *label;
    const char *filter; /* NULL: the figure's */
    const char *enc;    /* P_ENCODED: display encoding */
    double g;           /* P_MAP: the display's response exponent */
} fig_panel;

#define M(m, l) {P_METHOD, m, l, NULL, NULL, 0}
#define MF(m, l, f) {P_METHOD, m, l, f, NULL, 0}
#define REF(l) {P_REFERENCE, NULL, l, NULL, NULL, 0}
#define D2(m, l) {P_DOWN2, m, l, NULL, NULL, 0}
#define D2F(m, l, f) {P_DOWN2, m, l, f, NULL, 0}
#define ENC(m, l, e) {P_ENCODED, m, l, NULL, e, 0}
#define MAP(m, l, g) {P_MAP, m, l, NULL, NULL, g}

typedef struct fig_def {
    const char *name;
    const char *title;
    const char *paper;  /* the paper's figure: where, what, made how */
    const char *claim;  /* what the paper claims for it */
    const char *stands; /* NULL, or what stands in for the paper's and why */
    const char *pattern;
    int w, h;
    const char *filter; /* the panels' filter unless a panel names its own */
    double sx, sy;      /* the scene moved by (sx, sy) pixels (time 1, motion sx, sy) */
    int magnify;        /* a 1 x 1 view shown as a swatch this many pixels a side */
    int columns, npanels;
    fig_panel panel[AA_FIGURE_PANELS];
    /* NULL: the panels above; else the figure's own measure, which writes
     * DIR/NAME.* itself (fig. A.4's calibration) */
    int (*make)(const struct fig_def *f, const char *dir, const char *cache_dir, int threads,
                aa_figure_result *r);
} fig_def;

static int figure_calibration(const fig_def *f, const char *dir, const char *cache_dir,
                              int threads, aa_figure_result *r);

/* Page numbers of Crow 1976 are those of the thesis' table of contents. */
static const fig_def figures[] = {
    {"fig-crow-2.10",
     "Crow (1976) fig. 2.10: the test pattern on a 256 by 256 dot grid, one sample per dot",
     "Crow 1976, ch. 2, \"Evaluating convolutional filters\" (pp. 37-41), fig. 2.10: \"The test "
     "pattern synthesized on a 256 by 256 dot grid using techniques similar to those of "
     "conventional hidden-surface algorithms\": one sample at each dot. Made here with the same "
     "method: point.",
     "Jaggedness repeated with slight variation from curve to curve forms elliptical moire "
     "patterns, \"much easier to detect than jaggedness along a single edge\"; toward the right, "
     "where the detail is too fine to be resolved, \"similar patterns are caused by improper "
     "summing\". No number is given; the eye_rmse below measures the moire an eye sees.",
     NULL, "crow", 256, 256, "box", 0, 0, 0, 1, 1, {M("point", "point sampling")}, NULL},
    {"fig-crow-2.11",
     "Crow (1976) fig. 2.11: nine equally weighted samples per dot (3 x 3 supersampling, box)",
     "Crow 1976, ch. 2, \"Evaluating convolutional filters\" (pp. 37-41), fig. 2.11: \"The "
     "resulting pattern when nine equally weighted samples are taken per image dot\". Made here "
     "with the same method: supersample:n=3 under the box.",
     "Figs. 2.11-2.14 \"illustrate the effectiveness of various filters\"; no number is given. "
     "Against fig. 2.10 the moire should weaken; the eye_rmse below is comparable across figs. "
     "2.10-2.14 (the claims table ranks them).",
     NULL, "crow", 256, 256, "box", 0, 0, 0, 1, 1, {M("supersample:n=3", "3 x 3 samples, box")},
     NULL},
    {"fig-crow-2.12",
     "Crow (1976) fig. 2.12: 25 unequally weighted samples per dot (5 x 5 supersampling under "
     "the two-dot pyramid)",
     "Crow 1976, ch. 2, \"Evaluating convolutional filters\" (pp. 37-41), fig. 2.12: \"The "
     "resulting pattern when 25 unequally weighted samples are taken per image dot\". Made "
     "here with supersample:n=5 under tent:r=1.",
     "Figs. 2.11-2.14 \"illustrate the effectiveness of various filters\"; no number is given. "
     "Weighted samples should show less moire than the nine equal ones of fig. 2.11.",
     "Crow does not give the 25 weights. They are taken as a 5 x 5 grid over the two-dot square "
     "weighted by the pyramid (tent:r=1), the filter of fig. 2.14 and of his tiler, whose "
     "exact reference the panel is measured against.",
     "crow", 256, 256, "tent:r=1", 0, 0, 0, 1, 1,
     {M("supersample:n=5", "5 x 5 samples, pyramid")}, NULL},
    {"fig-crow-2.13",
     "Crow (1976) fig. 2.13: the pyramid of base one dot by Crow's table method, beside the "
     "exact reference and 5 x 5 supersampling",
     "Crow 1976, ch. 2, \"Evaluating convolutional filters\" (pp. 37-41), fig. 2.13: \"The "
     "resulting pattern when convolved with a roughly triangular filter with a base width "
     "roughly equal to the distance between sample points\", computed by his algorithm of "
     "\"Applying filters to computer-synthesized images\" (pp. 31-37, eqs. 5-8, figs. 2.7-2.8): "
     "partial-sum tables of the separable weight, one rectangle per edge. Made here with the "
     "same method, crowtable (form=crow), under tent:r=0.5.",
     "\"Experimental results have shown the algorithm to be quite effective in preventing the "
     "distracting effects\" (pp. 31-37); \"So far it has been sufficient to approximate the image "
     "function by forming a single rectangular area for each of these edges\" (fig. 2.8). No "
     "number is given: the first panel's error against the exact second panel is the "
     "rectangle's; the third panel samples the same filter.",
     "The tables' size is not given: 16 entries per dot here (crowtable's res=16).", "crow",
     256, 256, "tent:r=0.5", 0, 0, 0, 3, 3,
     {M("crowtable", "Crow's tables"), REF("exact reference"),
      M("supersample:n=5", "5 x 5 samples")},
     NULL},
    {"fig-crow-2.14",
     "Crow (1976) fig. 2.14: the pyramid of base two dots by Crow's table method, beside the "
     "exact reference and 5 x 5 supersampling",
     "Crow 1976, ch. 2, \"Evaluating convolutional filters\" (pp. 37-41), fig. 2.14: \"The "
     "resulting pattern when convolved with a roughly triangular filter with a base width of "
     "roughly twice the distance between sample points\", by his table method (pp. 31-37). "
     "Made here with the same method, crowtable (form=crow), under tent:r=1. The third panel, "
     "25 samples weighted by the same pyramid, is the image of fig. 2.12.",
     "The filter Crow keeps: \"The filters used in this work always cover an area two picture "
     "elements square\" (ch. 3, \"Implementation of a scanning algorithm\", pp. 56-60), and the "
     "appendix calibrates the display on this pattern \"using a pyramid-shaped presampling "
     "filter (as seen in figure 2.14)\" (pp. 88-92). Against fig. 2.13 the moire should weaken "
     "further (eye_rmse).",
     "The tables' size is not given: 16 entries per dot here (crowtable's res=16).", "crow",
     256, 256, "tent:r=1", 0, 0, 0, 3, 3,
     {M("crowtable", "Crow's tables"), REF("exact reference"),
      M("supersample:n=5", "5 x 5 samples (fig. 2.12)")},
     NULL},
    {"fig-crow-3.14",
     "Crow (1976) fig. 3.14: the filtering tiler beside a conventional tiler, 256 by 256",
     "Crow 1976, ch. 3, \"Implementation of a tiler\" (pp. 66-71), fig. 3.14: \"A 256 by 256 "
     "dot image comparing the filtering tiler with a conventional tiler\". The filtering tiler "
     "(figs. 3.12-3.13): left areas minus right areas under the two-dot pyramid, from the "
     "tables of ch. 2, polygons blended back to front (z-priority); the conventional tiler "
     "(fig. 3.11) samples each dot once. Made here with the same methods: crowtiler (tent:r=1) "
     "and point (box).",
     "\"Figures 3.14 through 3.17 compare the filtering tiler with conventional tilers\"; the "
     "filtering tiler should remove the staircases (\"the jaggies\") that the conventional one "
     "draws. No number is given; eye_rmse compares the two (each panel's rmse is against its "
     "own filter's reference).",
     "Crow does not say what object figs. 3.14-3.16 show. A Siemens star stands in (star: 36 "
     "white triangles, convex polygons as his tiler takes, with edges at every slope and "
     "detail finer than a dot toward the centre).",
     "star", 256, 256, "box", 0, 0, 0, 2, 2,
     {MF("crowtiler", "filtering tiler (tent:r=1)", "tent:r=1"),
      M("point", "conventional tiler (box)")},
     NULL},
    {"fig-crow-3.15",
     "Crow (1976) fig. 3.15: the filtering tiler beside a conventional tiler at doubled "
     "resolution, four dots averaged into one",
     "Crow 1976, ch. 3, \"Implementation of a tiler\" (pp. 66-71), fig. 3.15: \"The filtering "
     "tiler compared with a conventional tiler working at doubled resolution. Four dots have "
     "been averaged to give a single dot.\" Made here with the same methods: crowtiler "
     "(tent:r=1) at 256 x 256, point at 512 x 512 averaged 2 x 2.",
     "Ch. 1 (\"In Summary\", p. 16): doubling the resolution \"makes it possible to produce "
     "four different blends\", while \"an algorithm which blends at the base resolution should "
     "be able to produce superior pictures at the same viewing distance since it can be "
     "expected to produce many more possible blends\"; and doubling \"does not help the "
     "representation of very small objects\". Compare the panels' eye_rmse: on this star "
     "the filtering tiler and the doubled resolution tie (within about 1%), so the figure "
     "does not show the tiler superior; the claims table (claims.md) measures exact blending "
     "at the base resolution against doubling on several scenes.",
     "As fig. 3.14: a Siemens star stands in for Crow's unnamed object.", "star", 256, 256,
     "box", 0, 0, 0, 2, 2,
     {MF("crowtiler", "filtering tiler (tent:r=1)", "tent:r=1"),
      D2("point", "doubled resolution (box)")},
     NULL},
    {"fig-crow-3.16",
     "Crow (1976) fig. 3.16: the filtering, conventional and doubled-resolution tilers together",
     "Crow 1976, ch. 3, \"Implementation of a tiler\" (pp. 66-71), fig. 3.16: \"Images from the "
     "filtering tiler, the conventional tiler and the doubled-resolution tiler displayed "
     "together.\" Made here with crowtiler (tent:r=1), point, and point at 512 x 512 averaged "
     "2 x 2.",
     "As figs. 3.14-3.15: the filtering tiler at the base resolution should look best of the "
     "three, the doubled resolution in between (eye_rmse).",
     "As fig. 3.14: a Siemens star stands in for Crow's unnamed object.", "star", 256, 256,
     "box", 0, 0, 0, 3, 3,
     {MF("crowtiler", "filtering tiler (tent:r=1)", "tent:r=1"),
      M("point", "conventional tiler (box)"), D2("point", "doubled resolution (box)")},
     NULL},
    {"fig-crow-3.17",
     "Crow (1976) fig. 3.17: the three tilers on slender, nearly horizontal triangles",
     "Crow 1976, ch. 3, \"Implementation of a tiler\" (pp. 66-71), fig. 3.17: \"The three "
     "tilers compared on a particularly difficult type of object, very slender, nearly "
     "horizontal triangles.\" Made here with crowtiler (tent:r=1), point, and point at "
     "512 x 512 averaged 2 x 2.",
     "A long thin object point sampled may \"appear in some places and not in others, giving "
     "the appearance of a string of beads\" (ch. 1, \"The problem\", pp. 1-5); the filtering tiler \"does not "
     "ignore edge blocks with a vertical range of less than one line\" and, summing left minus "
     "right areas, \"very small polygons are properly handled\" (pp. 66-71). The filtering "
     "tiler should keep the triangles whole where the others break them (eye_rmse).",
     "Crow's triangles are not specified further: slivers (24 triangles 0.9 wide, 0.1 to 1.5 "
     "dots tall at their wide end, tilted by steps of 0.1 degree) stands in.",
     "slivers", 256, 256, "box", 0, 0, 0, 3, 3,
     {MF("crowtiler", "filtering tiler (tent:r=1)", "tent:r=1"),
      M("point", "conventional tiler (box)"), D2("point", "doubled resolution (box)")},
     NULL},
    {"fig-crow-3.18", "Crow (1976) fig. 3.18: the non-filtered test pattern (conventional tiler)",
     "Crow 1976, ch. 3 (after the summary, pp. 71-75), fig. 3.18: \"The non-filtered test "
     "pattern\", the test pattern of ch. 2 through the conventional tiler, as the pair of fig. "
     "3.19. Made here with the same method: point.",
     "With fig. 3.19: filtering in the tiler removes the moire and staircases of the "
     "non-filtered pattern (ch. 2, pp. 37-41). No number is given (eye_rmse).",
     "Crow gives the size of figs. 2.10 and 3.14 (256 by 256) but not of figs. 3.18-3.19; they "
     "are made here at the 512 by 512 of his frame buffer (appendix, pp. 88-92), not at fig. "
     "2.10's 256 by 256, which would repeat fig. 2.10. At this size the bands are 16 dots "
     "apart at the left and reach the Nyquist limit only at the right.",
     "crow", 512, 512, "box", 0, 0, 0, 1, 1, {M("point", "non-filtered (point)")}, NULL},
    {"fig-crow-3.19", "Crow (1976) fig. 3.19: the filtered test pattern (filtering tiler)",
     "Crow 1976, ch. 3 (after the summary, pp. 71-75), fig. 3.19: \"The filtered test pattern\", "
     "by his filtering tiler (figs. 3.12-3.13, two-dot pyramid). Made here with the same "
     "method: crowtiler under tent:r=1, with the exact reference beside it.",
     "With fig. 3.18: the filtering tiler removes the moire and staircases of the non-filtered "
     "pattern. No number is given (eye_rmse; the tiler's rmse is its tables' error).",
     "As fig. 3.18: 512 by 512, the size of Crow's frame buffer.", "crow", 512, 512, "tent:r=1",
     0, 0, 0, 2, 2, {M("crowtiler", "filtering tiler"), REF("exact reference")}, NULL},
    {"fig-crow-A.1",
     "Crow (1976) fig. A.1: the test pattern and a grey scale with a linear colour map, as this benchmark's model predicts it",
     "Crow 1976, appendix, \"Grey scale compensation\" (pp. 88-92), fig. A.1: \"Test pattern "
     "and grey scale with linear color map\", the pattern filtered by the pyramid of fig. 2.14 "
     "on a monitor that obeys \"the expected square law\": shown intensity = v^2 for a stored "
     "value v. Made here with crowtable under tent:r=1 (fig. 2.14's method), shown with "
     "intensity v^2, beside a linear grey scale shown the same way.",
     "Crow: \"At display intensities appropriate for viewing at normal indoor light levels, "
     "the color map curve was almost linear\" when the moire fringes were weakest: this map is "
     "his calibration. Measured (fig-crow-A.4): the fringes an eye sees are weakest where the "
     "shown intensity is linear in v (g = 1), not here (g = 2).",
     "A prediction, not Crow's photograph: his monitor is modelled as ideal square dots obeying "
     "the square law (no spot, no eye nonlinearity), the panel's pixels hold the intensity "
     "that model shows, v^2, and the PNG encodes that intensity for this screen.",
     "crow", 256, 256, "tent:r=1", 0, 0, 0, 1, 1,
     {MAP("crowtable", "model: linear map, shown v^2", 2)}, NULL},
    {"fig-crow-A.2",
     "Crow (1976) fig. A.2: the test pattern and a grey scale with a convex upward colour map, as this benchmark's model predicts it",
     "Crow 1976, appendix (pp. 88-92), fig. A.2: \"Test pattern and grey scale with convex "
     "upward color map\". Made here with crowtable under tent:r=1, the map taken as v^(1/2) on "
     "the square-law monitor: shown intensity v.",
     "Crow found this curve needed only \"at very low intensities such as used for figures "
     "2.11 through 2.14\". Measured (fig-crow-A.4): with the shown intensity linear in v (g = 1) "
     "the eye sees the least fringes.",
     "A prediction, not Crow's photograph (the model of fig. A.1). Crow does not give the "
     "curve's shape: v^(1/2) stands in for \"convex upward\", so that on his square-law "
     "monitor the shown intensity is v.",
     "crow", 256, 256, "tent:r=1", 0, 0, 0, 1, 1,
     {MAP("crowtable", "model: convex map, shown v", 1)}, NULL},
    {"fig-crow-A.3",
     "Crow (1976) fig. A.3: the test pattern and a grey scale with a concave upward colour map, as this benchmark's model predicts it",
     "Crow 1976, appendix (pp. 88-92), fig. A.3: \"Test pattern and grey scale with concave "
     "upward color map\". Made here with crowtable under tent:r=1, the map taken as v^2 on the "
     "square-law monitor: shown intensity v^4.",
     "A map bending the other way strengthens the fringes (Crow: \"grey level distortions can "
     "destroy the effect of measures taken to avoid aliasing\", abstract). Measured: eye_rmse "
     "below and fig-crow-A.4.",
     "A prediction, not Crow's photograph (the model of fig. A.1). Crow does not give the "
     "curve's shape: v^2 stands in for \"concave upward\" (shown intensity v^4 on his "
     "square-law monitor).",
     "crow", 256, 256, "tent:r=1", 0, 0, 0, 1, 1,
     {MAP("crowtable", "model: concave map, shown v^4", 4)}, NULL},
    {"fig-crow-A.4",
     "Crow (1976) fig. A.4, as a measurement: the grey scale's intensity under the three maps, "
     "and the moire an eye sees against the display's response exponent",
     "Crow 1976, appendix (pp. 88-92), fig. A.4: \"Intensity readings for figures A.1 through "
     "A.3\", photometer readings of the grey scale and their square roots. He calibrated by "
     "eye: \"The color map was then adjusted until the strength of the moire fringes was "
     "minimized\". Here the adjustment is a measurement (calibration.c): the pattern under the "
     "pyramid, by crowtable and exactly, shown with intensity v^g for g from 0.5 to 4, seen by "
     "an eye of s = 2 dots; the fringes are the standard deviation of the eye's error over the "
     "pattern's right half, where the bands reach the Nyquist limit.",
     "\"When the test pattern showed least evidence of moire fringes, the intensity readings "
     "lay near a parabolic curve, i.e. the function given by the square roots of the intensity "
     "readings was close to linear\": least moire at shown intensity v^2 (g = 2).",
     "Photometer readings of a real monitor cannot be remade: the left plot draws the three "
     "maps' shown intensity v^g (g = 2, 1, 4) and its square root; the right plot replaces the "
     "subjective adjustment by the measured fringes.",
     "crow", 256, 256, "tent:r=1", 0, 0, 0, 1, 0, {{0}}, figure_calibration},
    {"fig-crow-A-encodings",
     "Display encodings (an extra to Crow's appendix): the exact area image encoded linear, "
     "sRGB and with the square law, each beside a grey ramp encoded the same way",
     "Not a figure of the thesis: the image stored three ways and shown on an sRGB screen, "
     "i.e. a screen of response close to Crow's square law (appendix, pp. 88-92).",
     "Crow: \"Without such compensation, grey level distortions can destroy the effect of "
     "measures taken to avoid aliasing\" (abstract). Stored linear on a square-law screen the "
     "fine bands look too dark (eye_rmse); the sRGB encoding compensates the screen.",
     NULL, "crow", 256, 256, "box", 0, 0, 0, 3, 3,
     {ENC("area", "area, linear", "linear"), ENC("area", "area, sRGB", "srgb"),
      ENC("area", "area, gamma 2 (square law)", "gamma:2")},
     NULL},
    {"fig-catmull-1",
     "Catmull (1978) fig. 1: the colour of one pixel holding a hidden red, green and blue in "
     "front, by each method (64 x 64 swatches of the 1 x 1 image)",
     "Catmull 1978, \"Anti-aliasing\", fig. 1: one pixel holding a green square and a blue "
     "rectangle in front of a red rectangle they hide; his method, the pixel integrater "
     "(\"The pixel integrater\"), clips the polygons against the front one's edges "
     "recursively. Made here with area (integrator=catmull, his recursive integrater) beside "
     "two regular supersamplers and a jittered one.",
     "\"The correct integration would be 25% green, 25% black, 50% blue and no red. A simple "
     "minded algorithm that did not properly take into account what was hidden might "
     "distribute the intensities incorrectly and may even let some red show through.\"",
     "The pixel as Catmull draws it, unmoved: the exact value is (0, 0.25, 0.5), his split. "
     "Its centre lies on the corner of green and blue, so a single point sample's colour "
     "would depend on which side an edge's points are taken, which no result may depend on "
     "(patterns/README.md, \"Boundaries\"): point sampling is left out. The regular grids' "
     "samples (at 1/4, 3/4 and at 1/8 ... 7/8) miss every edge, so they are exact here; 16 "
     "independent random samples (jitter, seq=random) are not.",
     "catmull", 1, 1, "box", 0, 0, 64, 5, 5,
     {M("supersample:n=2", "supersample:n=2"), M("supersample:n=4", "supersample:n=4"),
      M("jitter:spp=16,seq=random", "jitter:spp=16,seq=random"), M("area", "area (Catmull)"),
      REF("exact reference")},
     NULL},
    {"fig-feibush-4b", "Feibush, Levoy and Cook (1980) fig. 4b: no filter, 512 x 512",
     "Feibush, Levoy and Cook 1980, sec. 3 (\"Examples\"), fig. 4b: \"No filter\": a polygon "
     "textured with red and white stripes in perspective, computed at 512 x 512. Made here "
     "with the same method: point, at 512 x 512.",
     "\"Displaying the polygon with no filtering is completely unsatisfactory due to the "
     "jaggedness of not only the edges of the polygon but also the stripes in the texture.\"",
     "The stripes are polygons of the scene (feibush), not a texture; 200 of them, so that "
     "across the square they run from about 2.4 dots wide (near edge) to 1 dot (far edge), "
     "near and beyond the Nyquist limit, where their moire shows. The paper does not give its "
     "number of stripes.",
     "feibush:stripes=200", 512, 512, "box", 0, 0, 0, 1, 1, {M("point", "no filter (point)")},
     NULL},
    {"fig-feibush-4c",
     "Feibush, Levoy and Cook (1980) fig. 4c: unweighted filter (exact area), 512 x 512",
     "Feibush, Levoy and Cook 1980, sec. 3, fig. 4c: \"an unweighted filter with a square "
     "convolution mask whose sides are equal to the distance between adjacent display "
     "pixels\": the box. Made here with area (exact under the box), at 512 x 512.",
     "\"Using an unweighted filter is better and nearly satisfactory along the edges, but "
     "Moire is still evident in the center of the polygon.\" (eye_rmse against figs. 4b and "
     "4d.)",
     "As fig. 4b: 200 stripes of the scene stand in for the texture.", "feibush:stripes=200",
     512, 512, "box", 0, 0, 0, 1, 1, {M("area", "unweighted (area)")}, NULL},
    {"fig-feibush-4d",
     "Feibush, Levoy and Cook (1980) fig. 4d: Gaussian filter (s = 1 pixel, mask radius 2 s) "
     "by their texture and edge filters, beside the exact reference, 512 x 512",
     "Feibush, Levoy and Cook 1980, sec. 3, fig. 4d: \"a filter with a Gaussian weighting "
     "function that has a standard deviation equal to the distance between adjacent display "
     "pixels. The convolution mask is a circle whose radius is equal to twice the standard "
     "deviation\": the texture filtered by texture points weighted from a two-dimensional "
     "table (sec. 2.4, fig. 2), weighted by the polygon's share from the edge filter, volumes "
     "over right triangles from a table (sec. 2.5, fig. 3). Made here with the same method, "
     "feibushtex, and beside it the edge filter alone on the stripes as polygons (conetable). "
     "Every panel, the exact reference too, is under their filter as they describe it: the "
     "Gaussian of s = 1 cut off at the circle of radius 2 s and divided by its volume there "
     "(\"the ratio of the shaded volume to the total volume\", fig. 3a), -f gauss:s=1,cut=2.",
     "\"The weighted filter, however, produces an excellent image.\" (eye_rmse and "
     "beat_energy against figs. 4b and 4c.)",
     "The texture is made from the scene (feibushtex.c): 1000 x 1000 texture points over the "
     "square's texture space, five per stripe, each the colour of the stripe it falls in; the "
     "paper's texture resolution is not given. 200 stripes, as fig. 4b.",
     "feibush:stripes=200", 512, 512, "gauss:s=1,cut=2", 0, 0, 0, 3, 3,
     {M("feibushtex:texels=1000", "texture filter (feibushtex)"),
      M("conetable", "edge filter alone (conetable)"), REF("exact reference")},
     NULL},
    {"fig-manson-filters",
     "Manson and Schaefer (2013): one vector scene rasterized exactly under the box, the tent, "
     "the cubic B-spline and Mitchell-Netravali",
     "Manson and Schaefer 2013, \"Analytic Rasterization of Curves with Polynomial Filters\" "
     "(Computer Graphics Forum 32(2)): vector art rasterized by their method, the convolution "
     "of a piecewise polynomial filter with shapes bounded by polynomial curves in closed "
     "form, under several such filters (its supplement compares different filters applied "
     "to different images). Made here with the same "
     "method, analytic, under the box, the tent (tent:r=1), the cubic B-spline "
     "(bspline:order=3) and Mitchell and Netravali's cubic (B = C = 1/3), on glyph outlines "
     "(quadratic arcs).",
     "\"We show that a polynomial expression can be used to rasterize any combination of "
     "polynomial curves and filters.\" (Each panel's RMSE and largest error are against the "
     "exact reference under its own filter: rounding, about 1e-15.)",
     "Glyph outlines of DejaVu Sans at 16 pixels per em (the text pattern) stand in for the "
     "paper's vector art, which is not at hand; text is one of its examples of vector "
     "content. The differences between the panels are the filters' own: the box keeps the "
     "edges sharpest and aliases most, the B-spline blurs, Mitchell-Netravali's negative "
     "lobes ring (values below 0 and above 1, shown clipped).",
     "text:ppem=16", 200, 28, "box", 0, 0, 0, 1, 4,
     {MF("analytic", "box", "box"), MF("analytic", "tent:r=1", "tent:r=1"),
      MF("analytic", "bspline:order=3", "bspline:order=3"),
      MF("analytic", "mitchell (B = C = 1/3)", "mitchell")},
     NULL},
};

#define NFIG (sizeof figures / sizeof figures[0])

size_t aa_figure_count(void)
{
    return NFIG;
}

const char *aa_figure_name(size_t k)
{
    return k < NFIG ? figures[k].name : NULL;
}

const char *aa_figure_title(size_t k)
{
    return k < NFIG ? figures[k].title : NULL;
}

int aa_figure_key(size_t k, char *buf, size_t len)
{
    if (k >= NFIG)
        return aa_fail(AA_EINVAL, "no figure %zu (there are %zu)", k, NFIG);
    const fig_def *f = &figures[k];
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, "figure key");
    if (st)
        return st;
    size_t n = (size_t)snprintf(buf, len, "%s %dx%d %s moved %.17g,%.17g x%d%s", f->pattern,
                                f->w, f->h, f->filter, f->sx, f->sy, f->magnify,
                                f->make ? " calibration" : "");
    static const char *const kind[] = {"method", "reference", "down2", "encoded", "map"};
    for (int p = 0; p < f->npanels && n < len; p++) {
        const fig_panel *q = &f->panel[p];
        n += (size_t)snprintf(buf + n, len - n, "; %s %s %s %s %.17g", kind[q->kind],
                              q->method ? q->method : "-", q->filter ? q->filter : f->filter,
                              q->enc ? q->enc : "-", q->g);
    }
    aa__c_numbers_end(&numbers);
    return n < len ? AA_OK : aa_fail(AA_EINVAL, "figure key of %s: buffer too small", f->name);
}

int aa_figure_find(const char *name)
{
    for (size_t k = 0; k < NFIG; k++)
        if (strcmp(figures[k].name, name) == 0)
            return (int)k;
    return -1;
}

int aa_figure_check(size_t k)
{
    if (k >= NFIG)
        return aa_fail(AA_EINVAL, "no figure %zu (there are %zu)", k, NFIG);
    const fig_def *f = &figures[k];
    aa_spec spec;
    aa_filter filter;
    aa_encode enc;
    if (!f->title || !f->paper || !f->claim)
        return aa_fail(AA_EINVAL, "%s: a text is missing", f->name);
    if (f->w < 1 || f->h < 1 || f->npanels < 0 || f->npanels > AA_FIGURE_PANELS)
        return aa_fail(AA_EINVAL, "%s: size %dx%d, %d panels", f->name, f->w, f->h, f->npanels);
    if (!f->make && (f->npanels < 1 || f->columns < 1))
        return aa_fail(AA_EINVAL, "%s: no panels and no measure of its own", f->name);
    int st = aa_pattern_parse(f->pattern, &spec);
    if (st)
        return aa_fail_context(st, "%s: pattern %s", f->name, f->pattern);
    for (int p = 0; p < f->npanels; p++) {
        const fig_panel *q = &f->panel[p];
        const char *ftext = q->filter ? q->filter : f->filter;
        if (!q->label)
            return aa_fail(AA_EINVAL, "%s: panel %d has no label", f->name, p + 1);
        if ((st = aa_filter_parse(ftext, &filter)))
            return aa_fail_context(st, "%s: panel %d: filter %s", f->name, p + 1, ftext);
        if (q->kind != P_REFERENCE && (!q->method || (st = aa_method_parse(q->method, &filter,
                                                                            &spec))))
            return q->method ? aa_fail_context(st, "%s: panel %d: method %s", f->name, p + 1,
                                               q->method)
                             : aa_fail(AA_EINVAL, "%s: panel %d has no method", f->name, p + 1);
        if (q->kind == P_ENCODED && (!q->enc || (st = aa_encode_parse(q->enc, &enc))))
            return aa_fail(AA_EINVAL, "%s: panel %d: no encoding it can show", f->name, p + 1);
    }
    return AA_OK;
}

/* sRGB decoding (IEC 61966-2-1): a value to display as `e` is stored as
 * its linear light, so the sRGB PNG writer gives back e. */
static double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* The intensity a panel shows for a stored linear value v. */
static double shown_value(const fig_panel *p, const aa_encode *e, double v)
{
    if (p->kind == P_MAP)
        return v > 0 ? pow(v, p->g) : 0.0;
    if (p->kind == P_ENCODED)
        return srgb_decode(aa_encode_value(e, v));
    return v;
}

/* The scene's time and motion for a figure moved by (sx, sy) pixels at
 * size w x h (a render at another size moves by the same fraction). */
static void motion_of(const fig_def *f, int w, double *t, double *vx, double *vy)
{
    int moved = f->sx != 0 || f->sy != 0;
    *t = moved ? 1.0 : 0.0;
    *vx = f->sx * w / f->w;
    *vy = f->sy * w / f->w;
}

/* Render one method at w x h into out (allocated here). */
static int render_method(const fig_def *f, const aa_scene *scene, const aa_filter *filter,
                         const char *method, int w, int h, int threads, aa_image *out)
{
    aa_spec spec;
    aa_job job;
    aa_counters counters;
    double t, vx, vy;
    motion_of(f, w, &t, &vx, &vy);
    int st = aa_method_parse(method, filter, &spec);
    if (st)
        return aa_fail_context(st, "%s", f->name);
    if ((st = aa_job_init(&job, scene, w, h, t, vx, vy, filter, FIG_SEED, threads)))
        return st;
    if (!(st = aa_image_alloc(out, w, h, 3))) {
        st = aa_method_run(&spec, &job, 1, out, &counters, NULL);
        if (st)
            aa_image_free(out);
    }
    aa_job_free(&job);
    return st ? aa_fail_context(st, "%s: %s", f->name, method) : AA_OK;
}

/* The 2 x 2 box mean of `big` (2w x 2h) into out (w x h). */
static int down2(const aa_image *big, aa_image *out)
{
    int st = aa_image_alloc(out, big->w / 2, big->h / 2, 3);
    if (st)
        return st;
    for (int j = 0; j < out->h; j++)
        for (int i = 0; i < out->w; i++)
            for (int k = 0; k < 3; k++)
                aa_pixel(out, i, j)[k] =
                    0.25 * (aa_pixel(big, 2 * i, 2 * j)[k] + aa_pixel(big, 2 * i + 1, 2 * j)[k] +
                            aa_pixel(big, 2 * i, 2 * j + 1)[k] +
                            aa_pixel(big, 2 * i + 1, 2 * j + 1)[k]);
    return AA_OK;
}

/* The tile of a panel: the image itself, a magnified swatch (pixels
 * replicated, on a ground wide enough for its label), or the image shown
 * through an encoding or a display response beside a grey ramp (linear
 * input 1 at the top to 0 at the bottom) shown the same way. */
#define RAMP_GAP 6
#define RAMP_W 32
#define SWATCH_GROUND 176
static int make_tile(const fig_def *f, const fig_panel *p, const aa_image *im, aa_image *tile)
{
    int st;
    if (f->magnify > 0) {
        int m = f->magnify, tw = m * im->w > SWATCH_GROUND ? m * im->w : SWATCH_GROUND;
        if ((st = aa_image_alloc(tile, tw, m * im->h, 3)))
            return st;
        for (size_t q = 0; q < (size_t)tile->w * tile->h * 3; q++)
            tile->v[q] = 0.01; /* the montage's ground */
        for (int j = 0; j < m * im->h; j++)
            for (int i = 0; i < m * im->w; i++)
                memcpy(aa_pixel(tile, i, j), aa_pixel(im, i / m, j / m), 3 * sizeof(double));
        return AA_OK;
    }
    if (p->kind == P_ENCODED || p->kind == P_MAP) {
        aa_encode e = {AA_ENCODE_LINEAR, 1};
        if (p->kind == P_ENCODED && (st = aa_encode_parse(p->enc, &e)))
            return st;
        if ((st = aa_image_alloc(tile, im->w + RAMP_GAP + RAMP_W, im->h, 3)))
            return st;
        for (int j = 0; j < im->h; j++) {
            double ramp = im->h > 1 ? 1.0 - (double)j / (im->h - 1) : 1.0;
            for (int i = 0; i < tile->w; i++) {
                double *t = aa_pixel(tile, i, j);
                for (int k = 0; k < 3; k++) {
                    if (i < im->w)
                        t[k] = shown_value(p, &e, aa_pixel(im, i, j)[k]);
                    else if (i < im->w + RAMP_GAP)
                        t[k] = 0.01;
                    else
                        t[k] = shown_value(p, &e, ramp);
                }
            }
        }
        return AA_OK;
    }
    if ((st = aa_image_alloc(tile, im->w, im->h, 3)))
        return st;
    memcpy(tile->v, im->v, sizeof(double) * 3 * (size_t)im->w * (size_t)im->h);
    return AA_OK;
}

void aa_html_escape(FILE *out, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '&': fputs("&amp;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fputc(*s, out);
        }
    }
}

/* A memory stream's text written atomically. */
static int write_stream(const char *path, FILE *mem, char **buf, size_t *len)
{
    if (fflush(mem) != 0) {
        fclose(mem);
        free(*buf);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    fclose(mem);
    int st = aa_file_write_atomic(path, *buf, *len);
    free(*buf);
    return st;
}

/* `text` wrapped at 78 columns after `key: `, continuation lines indented. */
static void wrapped(FILE *m, const char *key, const char *text)
{
    const size_t start = (size_t)fprintf(m, "%s:", key);
    size_t col = start;
    const size_t indent = 2, width = 78;
    while (*text) {
        while (*text == ' ')
            text++;
        if (!*text)
            break;
        const char *sp = strchr(text, ' ');
        size_t n = sp ? (size_t)(sp - text) : strlen(text);
        if (col > start && col + 1 + n > width) {
            fprintf(m, "\n%*s", (int)indent, "");
            col = indent;
        } else {
            fputc(' ', m);
            col++;
        }
        fwrite(text, 1, n, m);
        col += n;
        text += n;
    }
    fputc('\n', m);
}

static void caption_head(FILE *m, const fig_def *f)
{
    fprintf(m, "%s\n%s\n\n", f->name, f->title);
    wrapped(m, "paper", f->paper);
    wrapped(m, "claim", f->claim);
    if (f->stands)
        wrapped(m, "stands in", f->stands);
    fputc('\n', m);
}

static int write_caption(const char *dir, const fig_def *f, const aa_figure_result *r)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/%s.txt", dir, f->name);
    if (st)
        return st;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    caption_head(m, f);
    fprintf(m, "pattern: %s\nsize: %dx%d\nfilter: %s", f->pattern, f->w, f->h, f->filter);
    for (int k = 0; k < f->npanels; k++)
        if (f->panel[k].filter) {
            fprintf(m, " (each panel's below)");
            break;
        }
    fprintf(m, "\nseed: %d\n", FIG_SEED);
    if (f->sx != 0 || f->sy != 0)
        fprintf(m, "scene moved: %g, %g pixels (time 1, motion %g,%g)\n", f->sx, f->sy, f->sx,
                f->sy);
    if (f->magnify)
        fprintf(m, "shown: each %dx%d image magnified %d times (pixels replicated)\n", f->w, f->h,
                f->magnify);
    fprintf(m, "remake: aabench figures --only %s\n", f->name);
    char errors[1024];
    int n = snprintf(errors, sizeof errors,
                     "rmse and max_err against the exact reference under the panel's filter at "
                     "%dx%d, linear light, all channels",
                     f->w, f->h);
    if (f->w >= 16 && n > 0 && (size_t)n < sizeof errors)
        snprintf(errors + n, sizeof errors - (size_t)n,
                 "; eye_rmse: what an eye of s = %g pixels sees of the panel shown as pixel "
                 "squares (the intensities it shows) against what it sees of the scene itself "
                 "(harness/bench/eye.c); beat_energy: the spectral power, per pixel and "
                 "channel, of what the panel shows above %g cycle per pixel in x or y, near "
                 "the Nyquist limit, where it beats with the grid of dots into visible fringes",
                 AA_EYE_S, AA_BEAT_F0);
    wrapped(m, "errors", errors);
    fprintf(m, "\n");
    for (int k = 0; k < r->npanels; k++) {
        const fig_panel *p = &f->panel[k];
        const aa_figure_panel *q = &r->panel[k];
        fprintf(m, "panel %d: %s\n", k + 1, p->label);
        switch (p->kind) {
        case P_REFERENCE: fprintf(m, "  method: exact reference\n"); break;
        case P_DOWN2:
            fprintf(m, "  method: %s at %dx%d, mean of each 2x2 block\n", p->method, 2 * f->w,
                    2 * f->h);
            break;
        case P_ENCODED: fprintf(m, "  method: %s\n  encoding: %s\n", p->method, p->enc); break;
        case P_MAP:
            fprintf(m, "  method: %s\n  shown: intensity v^%g of the stored value v, grey "
                       "scale beside\n",
                    p->method, p->g);
            break;
        default: fprintf(m, "  method: %s\n", p->method);
        }
        fprintf(m, "  filter: %s\n", q->filter);
        if (f->magnify)
            fprintf(m, "  rgb: %.6f %.6f %.6f\n", q->rgb[0], q->rgb[1], q->rgb[2]);
        fprintf(m, "  rmse: %.9e\n  max_err: %.9e\n", q->rmse, q->max_err);
        if (p->kind == P_ENCODED)
            fprintf(m, "  rmse_encoded: %.9e\n  max_err_encoded: %.9e\n", q->rmse_enc,
                    q->max_err_enc);
        if (f->w >= 16)
            fprintf(m, "  eye_rmse: %.9e\n  beat_energy: %.9e\n", q->eye_rmse, q->beat);
    }
    return write_stream(path, m, &buf, &len);
}

/* ---- fig. A.4: the calibration, measured and plotted ---- */

static int figure_calibration(const fig_def *f, const char *dir, const char *cache_dir,
                              int threads, aa_figure_result *r)
{
    aa_calibration c;
    int st = aa_crow_calibration(cache_dir, threads, &c);
    if (st)
        return aa_fail_context(st, "%s", f->name);
    char *data = NULL, *script = NULL, *cap = NULL;
    size_t dlen = 0, slen = 0, clen = 0;
    FILE *d = open_memstream(&data, &dlen);
    FILE *s = d ? open_memstream(&script, &slen) : NULL;
    if (!d || !s) {
        if (d)
            fclose(d);
        free(data);
        return aa_fail(AA_ENOMEM, "%s: out of memory", f->name);
    }
    /* index 0: the grey scale under the three maps; index 1: the sweep */
    fprintf(d, "# input v, shown v^2 (linear map), v (convex upward), v^4 (concave upward), "
               "and their square roots\n");
    for (int k = 0; k <= 100; k++) {
        double v = k / 100.0;
        fprintf(d, "%.4f %.9g %.9g %.9g %.9g %.9g %.9g\n", v, v * v, v, pow(v, 4), v, sqrt(v),
                v * v);
    }
    fprintf(d, "\n\n# g, fringes (crowtable, exact), eye_rmse (crowtable, exact)\n");
    for (int k = 0; k < c.n; k++)
        fprintf(d, "%.4f %.9g %.9g %.9g %.9g\n", c.g[k], c.fringe[0][k], c.fringe[1][k],
                c.eye[0][k], c.eye[1][k]);
    fclose(d);
    fprintf(s,
            "# Crow 1976 fig. A.4 as a measurement: made by aabench figures; run with: "
            "gnuplot %s.gp\n"
            "set terminal pngcairo size 1100,460 font 'DejaVu Sans,10'\n"
            "if (!exists('out')) out = '%s.png'\n"
            "if (!exists('dat')) dat = '%s.dat'\nset output out\n"
            "set multiplot layout 1,2\nset grid\n"
            "set title 'Grey scale on a square-law monitor (fig. A.4: readings and square roots)'\n"
            "set xlabel 'stored value v (linear grey scale)'\n"
            "set ylabel 'shown intensity (solid) and its square root (dashed)'\n"
            "set key top left\n"
            "plot dat index 0 using 1:2 with lines lw 2 lc 1 title 'A.1 linear map: v^2', \\\n"
            "     '' index 0 using 1:3 with lines lw 2 lc 2 title 'A.2 convex upward: v', \\\n"
            "     '' index 0 using 1:4 with lines lw 2 lc 3 title 'A.3 concave upward: v^4', \\\n"
            "     '' index 0 using 1:5 with lines dt 2 lc 1 notitle, \\\n"
            "     '' index 0 using 1:6 with lines dt 2 lc 2 notitle, \\\n"
            "     '' index 0 using 1:7 with lines dt 2 lc 3 notitle\n"
            "set title 'Moire seen by an eye of s = %g dots, pattern under the two-dot pyramid'\n"
            "set xlabel 'display response exponent g (shown intensity v^g)'\n"
            "set ylabel 'error the eye sees (linear light)'\nset key bottom right\n"
            "set arrow from 1,graph 0 to 1,graph 1 nohead dt 3 lc 2\n"
            "set arrow from 2,graph 0 to 2,graph 1 nohead dt 3 lc 1\n"
            "set arrow from 4,graph 0 to 4,graph 1 nohead dt 3 lc 3\n"
            "set label 'A.2' at 1.03,graph 0.95\nset label 'A.1 (Crow)' at 2.03,graph 0.95\n"
            "set label 'A.3' at 3.75,graph 0.95\n"
            "plot dat index 1 using 1:2 with lines lw 2 lc 4 title 'fringes, crowtable', \\\n"
            "     '' index 1 using 1:3 with lines lw 1 dt 2 lc 4 title 'fringes, exact', \\\n"
            "     '' index 1 using 1:4 with lines lw 2 lc 7 title 'eye rmse, crowtable', \\\n"
            "     '' index 1 using 1:5 with lines lw 1 dt 2 lc 7 title 'eye rmse, exact'\n"
            "unset multiplot\n",
            f->name, f->name, f->name, AA_EYE_S);
    fclose(s);
    st = aa_plot_script(dir, f->name, data, script);
    free(data);
    free(script);
    if (st)
        return aa_fail_context(st, "%s", f->name);
    char path[4096];
    if ((st = aa_pathf(path, sizeof path, "%s/%s.txt", dir, f->name)))
        return st;
    FILE *m = open_memstream(&cap, &clen);
    if (!m)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    caption_head(m, f);
    fprintf(m, "pattern: crow\nsize: 256x256\nfilter: tent:r=1 (stored values v: crowtable, "
               "and the exact reference)\n"
               "remake: aabench figures --only %s (data: %s.dat, plot: %s.gp)\n"
               "measures: fringes, the standard deviation of the eye's error (eye of s = %g "
               "pixels, linear light) over columns 128-255; eye_rmse, its RMSE over the "
               "image\n\n",
            f->name, f->name, f->name, AA_EYE_S);
    fprintf(m, "least fringes: g = %.3f (crowtable), %.3f (exact)\n", c.gmin_fringe[0],
            c.gmin_fringe[1]);
    fprintf(m, "least eye_rmse: g = %.3f (crowtable), %.3f (exact)\n", c.gmin_eye[0],
            c.gmin_eye[1]);
    fprintf(m, "an eye averaging the square root of intensity instead would see the least at "
               "twice these: g = %.3f (fringes, crowtable)\n",
            2 * c.gmin_fringe[0]);
    static const char *const maps[3] = {"A.1 linear map", "A.2 convex upward",
                                        "A.3 concave upward"};
    for (int k = 0; k < 3; k++)
        fprintf(m, "%s, shown v^%g: fringes %.4e (exact %.4e), eye_rmse %.4e (exact %.4e)\n",
                maps[k], c.map_g[k], c.map_fringe[0][k], c.map_fringe[1][k], c.map_eye[0][k],
                c.map_eye[1][k]);
    fprintf(m, "reproduced: %s. Crow's least moire was at g = 2 (his linear map on a "
               "square-law monitor); the eye of linear light measured here sees the least at "
               "g = %.2f, i.e. with the shown intensity linear in the stored value (his "
               "convex upward map, fig. A.2); his g = 2 holds only for an eye that averaged "
               "the square root of intensity.\n",
            fabs(c.gmin_fringe[0] - 2) < 0.25 ? "yes" : "no", c.gmin_fringe[0]);
    fprintf(m, "\ng fringes(crowtable) fringes(exact) eye_rmse(crowtable) eye_rmse(exact)\n");
    for (int k = 0; k < c.n; k += 5)
        fprintf(m, "%.2f %.4e %.4e %.4e %.4e\n", c.g[k], c.fringe[0][k], c.fringe[1][k],
                c.eye[0][k], c.eye[1][k]);
    if ((st = write_stream(path, m, &cap, &clen)))
        return st;
    r->npanels = 0;
    snprintf(r->summary, sizeof r->summary,
             "least fringes at g = %.3f (crowtable), %.3f (exact); Crow: g = 2",
             c.gmin_fringe[0], c.gmin_fringe[1]);
    return AA_OK;
}

/* ---- a figure of panels ---- */

/* The references of the figure's filters: up to one per panel. */
typedef struct fig_refs {
    int n;
    const char *text[AA_FIGURE_PANELS];
    aa_filter filter[AA_FIGURE_PANELS];
    aa_image ref[AA_FIGURE_PANELS];
} fig_refs;

static int reference_of(const fig_def *f, const aa_view *base, const char *text,
                        const char *cache_dir, int threads, fig_refs *refs, int *at)
{
    for (int k = 0; k < refs->n; k++)
        if (!strcmp(refs->text[k], text)) {
            *at = k;
            return AA_OK;
        }
    if (refs->n == AA_FIGURE_PANELS)
        return aa_fail(AA_EFAIL, "%s: too many filters", f->name);
    int k = refs->n;
    aa_view view = *base;
    int st = aa_filter_parse(text, &view.filter);
    if (!st)
        st = aa_reference(&view, cache_dir, threads, &refs->ref[k], NULL, NULL);
    if (st)
        return aa_fail_context(st, "%s: reference under %s", f->name, text);
    refs->text[k] = text;
    refs->filter[k] = view.filter;
    refs->n++;
    *at = k;
    return AA_OK;
}

/* A panel's image: the reference itself, the method at twice the size
 * averaged down, or the method (allocated here). */
static int panel_image(const fig_def *f, const fig_panel *fp, const aa_scene *scene,
                       const aa_image *ref, const aa_filter *filter, int threads, aa_image *img)
{
    int st;
    if (fp->kind == P_REFERENCE) {
        if (!(st = aa_image_alloc(img, ref->w, ref->h, 3)))
            memcpy(img->v, ref->v, sizeof(double) * 3 * (size_t)ref->w * (size_t)ref->h);
        return st;
    }
    if (fp->kind == P_DOWN2) {
        aa_image big = {0};
        st = render_method(f, scene, filter, fp->method, 2 * f->w, 2 * f->h, threads, &big);
        if (!st)
            st = down2(&big, img);
        aa_image_free(&big);
        return st;
    }
    return render_method(f, scene, filter, fp->method, f->w, f->h, threads, img);
}

/* A panel's errors against the reference (and, encoded, against it
 * encoded the same way); for a view of 16 pixels or more, what an eye sees
 * of what the panel shows and its beat energy. */
static int panel_measure(const fig_def *f, const fig_panel *fp, const char *ftext,
                         const aa_image *ref, const aa_image *img, const aa_image *eye_truth,
                         aa_figure_panel *q)
{
    aa_metrics met;
    aa_encode enc = {AA_ENCODE_SRGB, 2.2};
    int st;
    if (fp->kind == P_ENCODED && (st = aa_encode_parse(fp->enc, &enc)))
        return st;
    if ((st = aa_metrics_compute(ref, img, &enc, &met)))
        return st;
    snprintf(q->label, sizeof q->label, "%s", fp->label);
    snprintf(q->filter, sizeof q->filter, "%s", ftext);
    q->reference = fp->kind == P_REFERENCE;
    q->rmse = met.rmse, q->max_err = met.max_err;
    q->rmse_enc = met.rmse_enc, q->max_err_enc = met.max_err_enc;
    q->eye_rmse = q->beat = NAN;
    for (int c = 0; c < 3; c++)
        q->rgb[c] = img->v[c];
    if (f->w < 16)
        return AA_OK;
    aa_image shown;
    if ((st = aa_image_alloc(&shown, f->w, f->h, 3)))
        return st;
    for (size_t v = 0; v < (size_t)f->w * f->h * 3; v++)
        shown.v[v] = shown_value(fp, &enc, img->v[v]);
    st = aa_eye_rmse(&shown, eye_truth, AA_EYE_S, &q->eye_rmse);
    if (!st)
        st = aa_band_energy(&shown, AA_BEAT_F0, &q->beat);
    aa_image_free(&shown);
    return st;
}

/* A panel's three label lines (the third may be empty). */
static void panel_labels(const fig_def *f, const fig_panel *fp, const aa_figure_panel *q,
                         const char *ftext, char labels[3][128])
{
    snprintf(labels[0], 128, "%s", fp->label);
    if (f->magnify)
        snprintf(labels[1], 128, "RGB %.3f %.3f %.3f", q->rgb[0], q->rgb[1], q->rgb[2]);
    else if (fp->kind == P_REFERENCE)
        snprintf(labels[1], 128, "%s, exact", ftext);
    else
        snprintf(labels[1], 128, "RMSE %.3g  max %.3g", q->rmse, q->max_err);
    if (f->magnify && fp->kind != P_REFERENCE)
        snprintf(labels[2], 128, "RMSE %.3g", q->rmse);
    else if (!f->magnify)
        snprintf(labels[2], 128, "eye %.3g  beat %.2g", q->eye_rmse, q->beat);
}

static int figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                       aa_figure_result *r)
{
    if (k >= NFIG)
        return aa_fail(AA_EINVAL, "no figure %zu (there are %zu)", k, NFIG);
    const fig_def *f = &figures[k];
    memset(r, 0, sizeof *r);
    r->name = f->name;
    r->npanels = f->npanels;
    double t0 = aa_now();
    if (f->make) {
        int st = f->make(f, dir, cache_dir, threads, r);
        r->seconds = aa_now() - t0;
        return st;
    }
    aa_view view;
    memset(&view, 0, sizeof view);
    aa_scene *scene = NULL;
    fig_refs refs;
    aa_image eye_truth = {0}, imgs[AA_FIGURE_PANELS], tiles[AA_FIGURE_PANELS];
    aa_tile tl[AA_FIGURE_PANELS];
    char labels[AA_FIGURE_PANELS][3][128];
    memset(&refs, 0, sizeof refs);
    memset(imgs, 0, sizeof imgs);
    memset(tiles, 0, sizeof tiles);
    memset(tl, 0, sizeof tl);
    memset(labels, 0, sizeof labels); /* a panel may have no third line */
    int st = aa_pattern_parse(f->pattern, &view.pattern);
    view.w = f->w, view.h = f->h;
    motion_of(f, f->w, &view.t, &view.vx, &view.vy);
    if (!st)
        st = aa_pattern_scene_at(&view.pattern, view.w, view.h, &scene);
    if (!st && f->w >= 16)
        st = aa_eye_truth(&view.pattern, f->w, f->h, view.t, view.vx, view.vy, AA_EYE_S,
                          cache_dir, threads, &eye_truth);
    for (int p = 0; p < f->npanels && !st; p++) {
        const fig_panel *fp = &f->panel[p];
        const char *ftext = fp->filter ? fp->filter : f->filter;
        int at = 0;
        if ((st = reference_of(f, &view, ftext, cache_dir, threads, &refs, &at)) ||
            (st = panel_image(f, fp, scene, &refs.ref[at], &refs.filter[at], threads,
                              &imgs[p])) ||
            (st = panel_measure(f, fp, ftext, &refs.ref[at], &imgs[p], &eye_truth,
                                &r->panel[p])) ||
            (st = make_tile(f, fp, &imgs[p], &tiles[p])))
            break;
        panel_labels(f, fp, &r->panel[p], ftext, labels[p]);
        tl[p].image = &tiles[p];
        tl[p].label[0] = labels[p][0];
        tl[p].label[1] = labels[p][1];
        tl[p].label[2] = labels[p][2][0] ? labels[p][2] : NULL;
    }
    char path[4096];
    if (!st)
        st = aa_pathf(path, sizeof path, "%s/%s.png", dir, f->name);
    if (!st)
        st = aa_montage_write(path, tl, (size_t)f->npanels, f->columns, NULL);
    if (!st)
        st = write_caption(dir, f, r);
    for (int p = 0; p < AA_FIGURE_PANELS; p++) {
        aa_image_free(&imgs[p]);
        aa_image_free(&tiles[p]);
        aa_image_free(&refs.ref[p]);
    }
    aa_image_free(&eye_truth);
    aa_scene_free(scene);
    r->seconds = aa_now() - t0;
    return st;
}

/* The settings file and the panels' labels write C-locale numbers,
 * whatever LC_NUMERIC the program has set. */
int aa_figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                   aa_figure_result *r)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = figure_make(k, dir, cache_dir, threads, r);
    aa__c_numbers_end(&numbers);
    return st;
}

/* Read a whole small text file; NULL if absent. */
static char *slurp(const char *path)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0, n;
    char chunk[4096];
    while ((n = fread(chunk, 1, sizeof chunk, in)) > 0) {
        if (len + n + 1 > cap) {
            cap = 2 * (len + n + 1);
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(in);
                return NULL;
            }
            buf = nb;
        }
        memcpy(buf + len, chunk, n);
        len += n;
    }
    fclose(in);
    if (!buf)
        buf = calloc(1, 1);
    else
        buf[len] = '\0';
    return buf;
}

static int present(const char *dir, const char *name, const char *ext)
{
    char path[4096];
    if (aa_pathf(path, sizeof path, "%s/%s%s", dir, name, ext))
        return 0;
    FILE *t = fopen(path, "rb");
    if (t)
        fclose(t);
    return t != NULL;
}

int aa_figure_index(const char *dir)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/index.html", dir);
    if (st)
        return st;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<title>aabench: published figures remade</title>\n<style>\n"
          "body { background: #1a1a1a; color: #ddd; font-family: sans-serif; margin: 2em; }\n"
          "h1 { font-weight: normal; }\n"
          "figure { margin: 0 0 3em 0; padding: 1em; background: #262626; }\n"
          "figure img { display: block; image-rendering: pixelated; max-width: none; }\n"
          "figcaption h2 { font-size: 1.1em; margin: 0.8em 0 0.3em 0; }\n"
          "p.claim { color: #fc9; max-width: 60em; }\n"
          "pre { font-size: 0.85em; color: #bbb; white-space: pre-wrap; }\n"
          "nav a { color: #9cf; margin-right: 1em; }\n"
          "table { border-collapse: collapse; font-size: 0.85em; }\n"
          "td, th { border: 1px solid #555; padding: 0.3em 0.5em; vertical-align: top; "
          "text-align: left; }\n"
          "th { background: #333; }\n"
          "</style>\n</head>\n<body>\n<h1>Published figures, remade by aabench</h1>\n"
          "<p>Each image is shown at its own size, pixel for pixel. Errors are against the "
          "exact reference of the same pattern, size and filter, in linear light; eye errors "
          "compare what an eye sees of a panel with what it sees of the scene itself.</p>\n"
          "<nav>",
          m);
    int shown = 0, claims = present(dir, "claims", ".html");
    for (size_t k = 0; k < NFIG; k++)
        if (present(dir, figures[k].name, ".png"))
            fprintf(m, "<a href=\"#%s\">%s</a>", figures[k].name, figures[k].name);
    if (claims)
        fputs("<a href=\"#claims\">claims</a>", m);
    fputs("</nav>\n", m);
    for (size_t k = 0; k < NFIG; k++) {
        const fig_def *f = &figures[k];
        char txt[4096];
        if (!present(dir, f->name, ".png") ||
            aa_pathf(txt, sizeof txt, "%s/%s.txt", dir, f->name))
            continue;
        char *cap = slurp(txt);
        fprintf(m, "<figure id=\"%s\">\n<img src=\"%s.png\" alt=\"", f->name, f->name);
        aa_html_escape(m, f->title);
        fprintf(m, "\">\n<figcaption>\n<h2>%s</h2>\n<p>", f->name);
        aa_html_escape(m, f->title);
        fputs("</p>\n<p class=\"claim\">Claim: ", m);
        aa_html_escape(m, f->claim);
        fputs("</p>\n", m);
        if (cap) {
            fputs("<pre>", m);
            aa_html_escape(m, cap);
            fputs("</pre>\n", m);
            free(cap);
        }
        fputs("</figcaption>\n</figure>\n", m);
        shown++;
    }
    if (!shown)
        fputs("<p>No figures in this folder yet: run <code>aabench figures</code>.</p>\n", m);
    if (claims) {
        char cpath[4096];
        char *frag = aa_pathf(cpath, sizeof cpath, "%s/claims.html", dir) ? NULL : slurp(cpath);
        fputs("<section id=\"claims\">\n<h1>Published claims, measured</h1>\n", m);
        if (frag) {
            /* claims.html is a page of its own: its body only */
            char *from = strstr(frag, "<body>"), *to = from ? strstr(from, "</body>") : NULL;
            if (from && to)
                fwrite(from + 6, 1, (size_t)(to - from - 6), m);
            else
                fputs(frag, m);
            free(frag);
        }
        fputs("</section>\n", m);
    }
    fputs("</body>\n</html>\n", m);
    return write_stream(path, m, &buf, &len);
}
