/*
 * scene.c: the scene model.
 *
 * A scene is opaque layers, front to back, each an RGB colour, a fill rule
 * (nonzero or even-odd) and closed paths of line segments, quadratic and
 * cubic Bezier arcs and elliptical arcs, over a background colour (harness/README.md, "The
 * three contracts").
 * Finishing a scene splits every edge at its y extrema into y-monotone
 * pieces stored top to bottom, so that a horizontal line meets a piece at
 * most once: x as a function of y is then a single root of a quadratic,
 * taken in the cancellation-free form, or for a cubic the one root of
 * y(t) = y in [0, 1], bracketed and polished by Newton's method
 * (scene_piece.c).
 *
 * Crossing rule: a piece meets the line y when y0 <= y < y1.  A path passing
 * through a vertex is counted once, a path turning at a vertex zero or two
 * times, and a horizontal piece never; so winding numbers along any line are
 * exact for closed paths.  The colour at a point is that of the front-most
 * layer whose fill rule holds for its winding number, when that layer is
 * opaque; layers of alpha below 1 and groups of opacity below 1 are
 * composited in painter's order in sRGB-encoded values (SVG and CSS:
 * browsers composite in the encoded values) and the result decoded to
 * linear light (colour_composite).
 * Clips (SVG's clipPath, "clips" below) are layers that paint nothing
 * and gate others: a gated layer covers a point only inside its clip.
 *
 * Pieces are indexed in bins along y (each piece listed in every bin it
 * overlaps), so the queries touch only the pieces near the line or
 * rectangle asked about.  Everything here is read-only once finished and
 * can be shared between threads.
 */
#include "scene_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A bin index larger than this many entries is coarsened. */
#define INDEX_MAX_ENTRIES ((size_t)1 << 24)
#define INDEX_MAX_BINS ((size_t)1 << 22)

/* ---- growing arrays ---- */

static int grow(void **array, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return AA_OK;
    size_t n = *cap ? *cap : 16;
    while (n < need) {
        if (n > SIZE_MAX / 2 / size)
            return aa_fail(AA_ENOMEM, "scene too large");
        n *= 2;
    }
    void *p = realloc(*array, n * size);
    if (!p)
        return aa_fail(AA_ENOMEM, "out of memory growing a scene to %zu items", need);
    *array = p;
    *cap = n;
    return AA_OK;
}

/* ---- building ---- */

aa_scene *aa_scene_new(aa_rgb background)
{
    aa_scene *s = calloc(1, sizeof *s);
    if (!s) {
        aa_fail(AA_ENOMEM, "out of memory for a scene");
        return NULL;
    }
    s->background = background;
    s->open_group = -1;
    s->open_clip = -1;
    return s;
}

void aa_scene_free(aa_scene *s)
{
    if (!s)
        return;
    free(s->colour);
    free(s->rule);
    free(s->alpha);
    free(s->encoded);
    free(s->group);
    free(s->groups);
    free(s->gate);
    free(s->member);
    free(s->clips);
    free(s->paint);
    for (int g = 0; g < s->ngrads; g++) {
        free(s->grads[g].stops);
        free(s->grads[g].enc);
    }
    free(s->grads);
    free(s->edges);
    free(s->contour);
    free(s->pieces);
    free(s->bin_start);
    free(s->bin_items);
    aa__scene_strokes_free(s);
    free(s);
}

/* sRGB's transfer functions (IEC 61966-2-1): the encoding of a linear
 * value, and its inverse. */
double aa_srgb_encode(double v)
{
    if (!(v > 0.0))
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

double aa_srgb_decode(double v)
{
    if (!(v > 0.0))
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static int check_colour(aa_rgb c)
{
    for (int k = 0; k < 3; k++)
        if (!(c.c[k] >= 0.0 && c.c[k] <= 1.0))
            return aa_fail(AA_EINVAL, "colour channel %d is %g, outside [0, 1]", k, c.c[k]);
    return AA_OK;
}

static int check_building(aa_scene *s)
{
    if (s->finished)
        return aa_fail(AA_EFAIL, "scene is finished: no more paths can be added");
    return AA_OK;
}

/* A new layer: one that paints (member -1) or a member of the clip being
 * defined. */
static int add_layer(aa_scene *s, aa_rgb colour, aa_fill_rule rule, int member)
{
    int st;
    if (rule != AA_FILL_NONZERO && rule != AA_FILL_EVENODD)
        return aa_fail(AA_EINVAL, "unknown fill rule %d", (int)rule);
    if (s->field)
        return aa_fail(AA_EINVAL, "scene is a field (%s): it has no layers", s->field->name);
    if (s->open && (st = aa_scene_close(s)))
        return st;
    size_t cap = s->caplayers;
    if ((st = grow((void **)&s->colour, &cap, (size_t)s->nlayers + 1, sizeof *s->colour)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->rule, &cap, (size_t)s->nlayers + 1, sizeof *s->rule)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->alpha, &cap, (size_t)s->nlayers + 1, sizeof *s->alpha)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->encoded, &cap, (size_t)s->nlayers + 1, sizeof *s->encoded)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->group, &cap, (size_t)s->nlayers + 1, sizeof *s->group)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->gate, &cap, (size_t)s->nlayers + 1, sizeof *s->gate)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->member, &cap, (size_t)s->nlayers + 1, sizeof *s->member)))
        return st;
    cap = s->caplayers;
    if ((st = grow((void **)&s->paint, &cap, (size_t)s->nlayers + 1, sizeof *s->paint)))
        return st;
    s->caplayers = cap;
    s->colour[s->nlayers] = colour;
    s->rule[s->nlayers] = rule;
    s->alpha[s->nlayers] = 1.0;
    for (int k = 0; k < 3; k++)
        s->encoded[s->nlayers].c[k] = aa_srgb_encode(colour.c[k]);
    /* a clip's member paints nothing: no group holds it */
    s->group[s->nlayers] = member < 0 ? s->open_group : -1;
    s->translucent |= member < 0 && s->open_group >= 0;
    s->gate[s->nlayers] = -1;
    s->member[s->nlayers] = member;
    s->paint[s->nlayers] = -1;
    s->current = s->nlayers++;
    return AA_OK;
}

int aa_scene_layer(aa_scene *s, aa_rgb colour, aa_fill_rule rule)
{
    int st = check_building(s);
    if (st || (st = check_colour(colour)))
        return st;
    if (s->open_clip >= 0)
        return aa_fail(AA_EINVAL, "a painting layer inside the definition of clip %d (its "
                                  "members are aa_scene_clip_layer's)",
                       s->open_clip);
    return add_layer(s, colour, rule, -1);
}

/* ---- clips ----
 *
 * A clip is geometry that paints nothing: the union of its member layers,
 * each the region where its own fill rule holds for its winding number
 * (and, when it has a clip of its own, inside that one too), intersected
 * with the clip it is defined within.  A layer gated by a clip paints a
 * point only where its fill rule holds and the point is inside the clip.
 * Whether a point is inside is a function of the winding numbers of the
 * member layers alone (in_clip), so the picture stays a function of the
 * winding numbers of every layer (aa_scene_colour_of), piecewise constant
 * between the pieces, and the reference integrates it exactly as before.
 * A clip refers only to clips ended before it began, so the references
 * have no cycle. */

int aa_scene_clip_begin(aa_scene *s, int within)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->field)
        return aa_fail(AA_EINVAL, "scene is a field (%s): it has no clips", s->field->name);
    if (s->open_clip >= 0)
        return aa_fail(AA_EINVAL, "clip %d is begun inside the definition of clip %d (define "
                                  "it first)",
                       s->nclips, s->open_clip);
    if (within < -1 || within >= s->nclips)
        return aa_fail(AA_EINVAL, "clip %d within clip %d, which is not defined yet", s->nclips,
                       within);
    if (within >= 0 && s->clips[within].depth >= AA_SCENE_MAX_CLIP_DEPTH)
        return aa_fail(AA_EINVAL, "clips nested deeper than %d", AA_SCENE_MAX_CLIP_DEPTH);
    if (s->open && (st = aa_scene_close(s)))
        return st;
    size_t cap = (size_t)s->capclips;
    if ((st = grow((void **)&s->clips, &cap, (size_t)s->nclips + 1, sizeof *s->clips)))
        return st;
    s->capclips = (int)cap;
    s->clips[s->nclips] = (aa_scene_clip){s->nlayers, 0, within,
                                          1 + (within >= 0 ? s->clips[within].depth : 0)};
    s->open_clip = s->nclips++;
    s->current = -1; /* no path before the first member */
    return AA_OK;
}

int aa_scene_clip_layer(aa_scene *s, aa_fill_rule rule)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->open_clip < 0)
        return aa_fail(AA_EINVAL, "a clip's member layer outside a clip's definition");
    const aa_rgb none = {{0, 0, 0}};
    if ((st = add_layer(s, none, rule, s->open_clip)))
        return st;
    s->clips[s->open_clip].count++;
    return AA_OK;
}

int aa_scene_clip_end(aa_scene *s, int *clip)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->open_clip < 0)
        return aa_fail(AA_EINVAL, "clip end without a clip");
    if (s->open && (st = aa_scene_close(s)))
        return st;
    if (clip)
        *clip = s->open_clip;
    s->open_clip = -1;
    s->current = -1; /* the next layer is a new one */
    return AA_OK;
}

int aa_scene_set_clip(aa_scene *s, int clip)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->current < 0 || !s->nlayers || s->current != s->nlayers - 1)
        return aa_fail(AA_EINVAL, "a clip set without a layer");
    if (clip < 0 || clip >= s->nclips || clip == s->open_clip)
        return aa_fail(AA_EINVAL, "layer %d clipped by clip %d, which is not defined", s->current,
                       clip);
    const int l = s->current;
    if (s->member[l] >= 0) { /* a member's own clip: its clip is then at least one deeper */
        aa_scene_clip *c = &s->clips[s->member[l]];
        if (s->clips[clip].depth >= AA_SCENE_MAX_CLIP_DEPTH)
            return aa_fail(AA_EINVAL, "clips nested deeper than %d", AA_SCENE_MAX_CLIP_DEPTH);
        if (c->depth < 1 + s->clips[clip].depth)
            c->depth = 1 + s->clips[clip].depth;
    }
    s->gate[l] = clip;
    return AA_OK;
}

int aa_scene_set_alpha(aa_scene *s, double alpha)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->nlayers)
        return aa_fail(AA_EINVAL, "alpha without a layer");
    if (s->member[s->nlayers - 1] >= 0)
        return aa_fail(AA_EINVAL, "alpha on a member of a clip, which paints nothing");
    if (!(alpha >= 0.0 && alpha <= 1.0))
        return aa_fail(AA_EINVAL, "alpha %g is outside [0, 1]", alpha);
    s->alpha[s->nlayers - 1] = alpha;
    s->translucent |= alpha < 1.0;
    return AA_OK;
}

/* ---- gradients ----
 *
 * A gradient layer's colour at a point (aabench.h, aa_gradient;
 * patterns/README.md, "Gradients"): t from the point mapped back into the
 * gradient's coordinates, spread into [0, 1], and the stops' sRGB-encoded
 * channels and opacity interpolated there, each on its own, not
 * premultiplied: SVG's text leaves it implicit, the SVG working group
 * answered that colour and opacity interpolate independently (www-svg,
 * July 2006), and no browser interpolates SVG stops premultiplied (svgwg
 * issue 180), unlike CSS Images 3's gradients; Chromium and resvg agree
 * (tests/test_gradient_renderers.c).  That colour then composites as a
 * layer's own does.
 *
 * A gradient in linear light (aa_scene_set_gradient_interpolation,
 * AA_INTERPOLATE_LINEAR_RGB; SVG 1.1's color-interpolation="linearRGB" on
 * the gradient element, "the color interpolation ... in the linearized RGB
 * color space") interpolates instead the stops' linear-light channels, as
 * given, and encodes the result: encode(l_k + f (l_k+1 - l_k)), which then
 * composites in encoded values as any layer's colour (browsers composite
 * so whatever the property says: only the stops' interpolation changes).
 * The opacity interpolates as before, and the channels are not
 * premultiplied by it: Chromium, which draws the property, gives a stop
 * of opacity 0 the weight of its colour (black at opacity 0 to red over
 * white is (221, 126, 126) at t = 0.504, the composite of encode(0.504)
 * at opacity 0.504; premultiplied it would be (255, 126, 126)). */

static int invert_map(const double m[6], double inv[6])
{
    double det = m[0] * m[3] - m[1] * m[2];
    if (!(det != 0.0) || !isfinite(det))
        return 0;
    inv[0] = m[3] / det, inv[1] = -m[1] / det;
    inv[2] = -m[2] / det, inv[3] = m[0] / det;
    inv[4] = -(inv[0] * m[4] + inv[2] * m[5]);
    inv[5] = -(inv[1] * m[4] + inv[3] * m[5]);
    for (int k = 0; k < 6; k++)
        if (!isfinite(inv[k]))
            return 0;
    return 1;
}

static int check_gradient(const aa_gradient *g)
{
    if (g->kind != AA_GRADIENT_LINEAR && g->kind != AA_GRADIENT_RADIAL)
        return aa_fail(AA_EINVAL, "unknown gradient kind %d", g->kind);
    if (g->spread != AA_SPREAD_PAD && g->spread != AA_SPREAD_REFLECT &&
        g->spread != AA_SPREAD_REPEAT)
        return aa_fail(AA_EINVAL, "unknown gradient spread %d", g->spread);
    for (int k = 0; k < 6; k++)
        if (!isfinite(g->p[k]) || !isfinite(g->m[k]))
            return aa_fail(AA_EINVAL, "gradient %s %d is not finite",
                           isfinite(g->p[k]) ? "map entry" : "parameter", k);
    double inv[6];
    if (!invert_map(g->m, inv))
        return aa_fail(AA_EINVAL, "gradient map (%g %g %g %g %g %g) is not invertible",
                       g->m[0], g->m[1], g->m[2], g->m[3], g->m[4], g->m[5]);
    if (g->nstops < 1 || !g->stops)
        return aa_fail(AA_EINVAL, "gradient without stops (SVG paints none: give no layer)");
    for (int k = 0; k < g->nstops; k++) {
        const aa_gradient_stop *t = &g->stops[k];
        if (!(t->offset >= 0.0 && t->offset <= 1.0) ||
            (k && !(t->offset >= g->stops[k - 1].offset)))
            return aa_fail(AA_EINVAL, "gradient stop %d: offset %g is not in [0, 1] at or "
                                      "after the previous stop's",
                           k, t->offset);
        if (!(t->opacity >= 0.0 && t->opacity <= 1.0))
            return aa_fail(AA_EINVAL, "gradient stop %d: opacity %g is outside [0, 1]", k,
                           t->opacity);
        int st = check_colour(t->colour);
        if (st)
            return aa_fail_context(st, "gradient stop %d", k);
    }
    const double *p = g->p;
    if (g->kind == AA_GRADIENT_LINEAR) {
        if (p[0] == p[2] && p[1] == p[3])
            return aa_fail(AA_EINVAL, "linear gradient from (%g, %g) to itself: SVG paints it "
                                      "with its last stop, a colour",
                           p[0], p[1]);
    } else {
        if (!(p[2] > 0.0) || !(p[5] >= 0.0))
            return aa_fail(AA_EINVAL, "radial gradient of radius %g and focal radius %g: r "
                                      "must be positive and fr at least 0",
                           p[2], p[5]);
        if (p[0] == p[3] && p[1] == p[4] && p[2] == p[5])
            return aa_fail(AA_EINVAL,
                           "radial gradient: the focal circle (%g, %g) radius %g is the end "
                           "circle; SVG 2 paints nothing then: give no layer",
                           p[3], p[4], p[5]);
    }
    return AA_OK;
}

/* Append a copy of g to s's gradients (map m in place of g's); its index
 * into *index. */
static int add_gradient(aa_scene *s, const aa_gradient *g, const double m[6], int *index)
{
    size_t cap = (size_t)s->capgrads;
    int st = grow((void **)&s->grads, &cap, (size_t)s->ngrads + 1, sizeof *s->grads);
    if (st)
        return st;
    s->capgrads = (int)cap;
    aa_scene_gradient *d = &s->grads[s->ngrads];
    memset(d, 0, sizeof *d);
    d->stops = malloc((size_t)g->nstops * sizeof *d->stops);
    d->enc = malloc((size_t)g->nstops * 4 * sizeof *d->enc);
    if (!d->stops || !d->enc) {
        free(d->stops);
        free(d->enc);
        return aa_fail(AA_ENOMEM, "out of memory for a gradient");
    }
    memcpy(d->stops, g->stops, (size_t)g->nstops * sizeof *d->stops);
    d->g = *g;
    memcpy(d->g.m, m, sizeof d->g.m);
    d->g.stops = d->stops;
    d->cone = g->kind == AA_GRADIENT_RADIAL && aa_gradient_is_cone(g);
    for (int k = 0; k < g->nstops; k++) {
        for (int c = 0; c < 3; c++)
            d->enc[4 * k + c] = aa_srgb_encode(g->stops[k].colour.c[c]);
        d->enc[4 * k + 3] = g->stops[k].opacity;
    }
    if (!invert_map(d->g.m, d->inv)) {
        free(d->stops);
        free(d->enc);
        return aa_fail(AA_EINVAL, "gradient map is not invertible");
    }
    *index = s->ngrads++;
    return AA_OK;
}

int aa_scene_set_gradient(aa_scene *s, const aa_gradient *g)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->nlayers)
        return aa_fail(AA_EINVAL, "gradient without a layer");
    if (s->member[s->nlayers - 1] >= 0)
        return aa_fail(AA_EINVAL, "gradient on a member of a clip, which paints nothing");
    if (!g || (st = check_gradient(g)))
        return g ? st : aa_fail(AA_EINVAL, "no gradient given");
    int index;
    if ((st = add_gradient(s, g, g->m, &index)))
        return st;
    int l = s->nlayers - 1;
    s->paint[l] = index;
    /* aa_scene_colour_of's stand-in for the layer: its first stop */
    s->colour[l] = g->stops[0].colour;
    for (int k = 0; k < 3; k++)
        s->encoded[l].c[k] = aa_srgb_encode(g->stops[0].colour.c[k]);
    s->translucent = 1; /* aa_scene_is_opaque's contract no longer holds */
    return AA_OK;
}

double aa__gradient_t(const aa_scene_gradient *sg, double x, double y)
{
    const double *v = sg->inv, *p = sg->g.p;
    double u = v[0] * x + v[2] * y + v[4], w = v[1] * x + v[3] * y + v[5];
    if (sg->g.kind == AA_GRADIENT_LINEAR) {
        double dx = p[2] - p[0], dy = p[3] - p[1];
        return ((u - p[0]) * dx + (w - p[1]) * dy) / (dx * dx + dy * dy);
    }
    /* |q - F - t D| = fr + t dr, D = C - F, dr = r - fr: squared,
     *     a t^2 - 2 b t + c = 0,  a = D.D - dr^2,
     *     b = (q - F).D + fr dr,  c = |q - F|^2 - fr^2;
     * t is the largest root whose circle has radius fr + t dr >= 0 (SVG 2,
     * canvas's createRadialGradient), NaN where there is none.  With the
     * focal circle inside the end circle (a < 0) the circles are nested
     * and grow with t, so the point lies on exactly one of those with
     * radius >= 0: the larger root, (b - sqrt(b^2 - a c)) / a, taken as
     * c / (b + sqrt(b^2 - a c)) when b > 0 (no cancellation).  Otherwise
     * (the cone case) the roots are Q / a and c / Q, Q = b + sign(b)
     * sqrt(b^2 - a c) (no cancellation either), or c / (2 b) when a = 0;
     * the larger one of radius >= 0 is taken; none where b^2 < a c. */
    double qx = u - p[3], qy = w - p[4], Dx = p[0] - p[3], Dy = p[1] - p[4];
    double dr = p[2] - p[5];
    double a = Dx * Dx + Dy * Dy - dr * dr;
    double b = qx * Dx + qy * Dy + p[5] * dr;
    double c = qx * qx + qy * qy - p[5] * p[5];
    double disc = b * b - a * c;
    if (!sg->cone) {
        double sq = sqrt(disc > 0.0 ? disc : 0.0);
        if (b > 0.0)
            return c / (b + sq);
        return (b - sq) / a;
    }
    double r1, r2;
    if (a == 0.0) {
        if (b == 0.0)
            return NAN; /* c = 0 on a line of points at most: no single t */
        r1 = r2 = c / (2.0 * b);
    } else {
        if (disc < 0.0)
            return NAN;
        double Q = b + copysign(sqrt(disc), b);
        if (Q == 0.0) /* b = 0 and disc = 0: c = 0, the double root 0 */
            r1 = r2 = 0.0;
        else {
            r1 = Q / a, r2 = c / Q;
            if (r1 < r2) {
                double tmp = r1;
                r1 = r2, r2 = tmp;
            }
        }
    }
    if (p[5] + r1 * dr >= 0.0)
        return r1;
    if (p[5] + r2 * dr >= 0.0)
        return r2;
    return NAN;
}

int aa_gradient_is_cone(const aa_gradient *g)
{
    const double *p = g->p;
    return g->kind == AA_GRADIENT_RADIAL && !(hypot(p[0] - p[3], p[1] - p[4]) + p[5] < p[2]);
}

double aa__gradient_spread(int spread, double t)
{
    if (spread == AA_SPREAD_REPEAT)
        return t - floor(t);
    if (spread == AA_SPREAD_REFLECT) {
        double f = t - 2.0 * floor(0.5 * t); /* in [0, 2) */
        return f <= 1.0 ? f : 2.0 - f;
    }
    return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
}

void aa__gradient_paint(const aa_scene_gradient *sg, double t, double out[4])
{
    const aa_gradient_stop *st = sg->stops;
    int n = sg->g.nstops;
    const double *e = sg->enc;
    if (!(t >= st[0].offset)) { /* before the first stop (and NaN) */
        memcpy(out, e, 4 * sizeof *out);
        return;
    }
    if (t >= st[n - 1].offset) {
        memcpy(out, e + 4 * (n - 1), 4 * sizeof *out);
        return;
    }
    int k = 0; /* the last stop at or before t: st[k].offset <= t < st[k+1].offset */
    while (k + 1 < n && st[k + 1].offset <= t)
        k++;
    double f = (t - st[k].offset) / (st[k + 1].offset - st[k].offset);
    for (int c = 0; c < 4; c++)
        out[c] = e[4 * k + c] + f * (e[4 * k + 4 + c] - e[4 * k + c]);
    if (sg->interpolation == AA_INTERPOLATE_LINEAR_RGB)
        for (int c = 0; c < 3; c++) {
            double a = st[k].colour.c[c], b = st[k + 1].colour.c[c];
            out[c] = aa_srgb_encode(a + f * (b - a));
        }
}

const aa_scene_gradient *aa__scene_layer_paint(const aa_scene *s, int layer)
{
    return s->paint[layer] < 0 ? NULL : &s->grads[s->paint[layer]];
}

int aa_scene_has_gradients(const aa_scene *s) { return s->ngrads > 0; }

int aa_scene_layer_gradient(const aa_scene *s, int layer, aa_gradient *g)
{
    if (layer < 0 || layer >= s->nlayers || s->paint[layer] < 0)
        return 0;
    if (g)
        *g = s->grads[s->paint[layer]].g;
    return 1;
}

int aa_scene_set_gradient_source(aa_scene *s, const char *source)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->nlayers || s->paint[s->nlayers - 1] < 0)
        return aa_fail(AA_EINVAL, "gradient source without a gradient layer");
    char *d = s->grads[s->paint[s->nlayers - 1]].source;
    snprintf(d, sizeof s->grads->source, "%s", source ? source : "");
    return AA_OK;
}

int aa_scene_set_gradient_interpolation(aa_scene *s, int interpolation)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->nlayers || s->paint[s->nlayers - 1] < 0)
        return aa_fail(AA_EINVAL, "gradient interpolation without a gradient layer");
    if (interpolation != AA_INTERPOLATE_SRGB && interpolation != AA_INTERPOLATE_LINEAR_RGB)
        return aa_fail(AA_EINVAL, "unknown gradient interpolation %d", interpolation);
    s->grads[s->paint[s->nlayers - 1]].interpolation = interpolation;
    return AA_OK;
}

int aa_scene_layer_gradient_interpolation(const aa_scene *s, int layer)
{
    if (layer < 0 || layer >= s->nlayers || s->paint[layer] < 0)
        return AA_INTERPOLATE_SRGB;
    return s->grads[s->paint[layer]].interpolation;
}

const char *aa_scene_layer_gradient_source(const aa_scene *s, int layer)
{
    if (layer < 0 || layer >= s->nlayers || s->paint[layer] < 0)
        return "";
    return s->grads[s->paint[layer]].source;
}

static int group_depth(const aa_scene *s, int g)
{
    int d = 0;
    for (; g >= 0; g = s->groups[g].parent)
        d++;
    return d;
}

int aa_scene_group_begin(aa_scene *s, double opacity)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!(opacity >= 0.0 && opacity <= 1.0))
        return aa_fail(AA_EINVAL, "group opacity %g is outside [0, 1]", opacity);
    if (group_depth(s, s->open_group) >= AA_SCENE_MAX_GROUP_DEPTH)
        return aa_fail(AA_EINVAL, "groups nested deeper than %d", AA_SCENE_MAX_GROUP_DEPTH);
    size_t cap = (size_t)s->capgroups;
    if ((st = grow((void **)&s->groups, &cap, (size_t)s->ngroups + 1, sizeof *s->groups)))
        return st;
    s->capgroups = (int)cap;
    s->groups[s->ngroups] = (aa_scene_group){s->open_group, opacity};
    s->open_group = s->ngroups++;
    return AA_OK;
}

int aa_scene_group_end(aa_scene *s)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->open_group < 0)
        return aa_fail(AA_EINVAL, "group end without a group");
    s->open_group = s->groups[s->open_group].parent;
    return AA_OK;
}

static int check_point(double x, double y)
{
    if (!isfinite(x) || !isfinite(y))
        return aa_fail(AA_EINVAL, "path point (%g, %g) is not finite", x, y);
    return AA_OK;
}

static int add_edge(aa_scene *s, double cx, double cy, double x, double y, int quad)
{
    return aa__add_edge3(s, cx, cy, 0.0, 0.0, x, y, quad);
}

int aa__add_edge3(aa_scene *s, double cx, double cy, double c2x, double c2y, double x, double y,
                  int quad)
{
    int st = grow((void **)&s->edges, &s->capedges, s->nedges + 1, sizeof *s->edges);
    if (st)
        return st;
    aa_edge *e = &s->edges[s->nedges++];
    e->x0 = s->penx;
    e->y0 = s->peny;
    e->cx = cx;
    e->cy = cy;
    e->x1 = x;
    e->y1 = y;
    e->quad = quad;
    e->layer = s->current;
    e->c2x = c2x;
    e->c2y = c2y;
    e->ux = e->uy = e->vx = e->vy = e->t0 = e->t1 = 0.0;
    s->penx = x;
    s->peny = y;
    return AA_OK;
}

int aa_scene_move_to(aa_scene *s, double x, double y)
{
    int st = check_building(s);
    if (st || (st = check_point(x, y)))
        return st;
    if (s->current < 0 || s->nlayers == 0)
        return aa_fail(AA_EFAIL, "path started before any layer");
    if (s->open && (st = aa_scene_close(s)))
        return st;
    s->open = 1;
    s->startx = s->penx = x;
    s->starty = s->peny = y;
    s->contour_first = s->nedges;
    return AA_OK;
}

int aa_scene_line_to(aa_scene *s, double x, double y)
{
    int st = check_building(s);
    if (st || (st = check_point(x, y)))
        return st;
    if (!s->open)
        return aa_fail(AA_EFAIL, "line_to without move_to");
    if (x == s->penx && y == s->peny)
        return AA_OK; /* a zero-length edge has no effect on any query */
    return add_edge(s, 0.5 * (s->penx + x), 0.5 * (s->peny + y), x, y, 0);
}

int aa_scene_quad_to(aa_scene *s, double cx, double cy, double x, double y)
{
    int st = check_building(s);
    if (st || (st = check_point(cx, cy)) || (st = check_point(x, y)))
        return st;
    if (!s->open)
        return aa_fail(AA_EFAIL, "quad_to without move_to");
    if (x == s->penx && y == s->peny && cx == x && cy == y)
        return AA_OK;
    return add_edge(s, cx, cy, x, y, 1);
}

int aa_scene_cubic_to(aa_scene *s, double c1x, double c1y, double c2x, double c2y, double x, double y)
{
    int st = check_building(s);
    if (st || (st = check_point(c1x, c1y)) || (st = check_point(c2x, c2y)) ||
        (st = check_point(x, y)))
        return st;
    if (!s->open)
        return aa_fail(AA_EFAIL, "cubic_to without move_to");
    if (x == s->penx && y == s->peny && c1x == x && c1y == y && c2x == x && c2y == y)
        return AA_OK;
    return aa__add_edge3(s, c1x, c1y, c2x, c2y, x, y, 2);
}

/* The point of the ellipse (c, u, v) at angle t. */
static void ellipse_point(const double *e, double t, double *x, double *y)
{
    double ct = cos(t), st = sin(t);
    *x = e[0] + e[2] * ct + e[4] * st;
    *y = e[1] + e[3] * ct + e[5] * st;
}

int aa__arc_check(double px, double py, double cx, double cy, double ux, double uy, double vx,
                  double vy, double t0, double t1, double x, double y)
{
    const double e[6] = {cx, cy, ux, uy, vx, vy};
    for (int k = 0; k < 6; k++)
        if (!isfinite(e[k]))
            return aa_fail(AA_EINVAL, "elliptical arc: centre or semi-diameter is not finite");
    if (!isfinite(t0) || !isfinite(t1) || !isfinite(x) || !isfinite(y))
        return aa_fail(AA_EINVAL, "elliptical arc: angle or end point is not finite");
    double size = hypot(ux, uy) + hypot(vx, vy);
    double cross = ux * vy - uy * vx;
    if (!(fabs(cross) > 1e-12 * size * size))
        return aa_fail(AA_EINVAL,
                       "elliptical arc: semi-diameters (%g, %g) and (%g, %g) are parallel "
                       "(a degenerate ellipse)",
                       ux, uy, vx, vy);
    if (!(fabs(t1 - t0) <= 2.0 * M_PI * (1.0 + 1e-12)))
        return aa_fail(AA_EINVAL, "elliptical arc: sweeps %g radians, more than 2 pi", t1 - t0);
    double ax, ay, bx, by, tol = 1e-9 * size;
    ellipse_point(e, t0, &ax, &ay);
    ellipse_point(e, t1, &bx, &by);
    if (!(hypot(ax - px, ay - py) <= tol))
        return aa_fail(AA_EINVAL,
                       "elliptical arc: starts at (%.17g, %.17g), not at the pen (%.17g, %.17g)",
                       ax, ay, px, py);
    if (!(hypot(bx - x, by - y) <= tol))
        return aa_fail(AA_EINVAL,
                       "elliptical arc: ends at (%.17g, %.17g), not at the end point given "
                       "(%.17g, %.17g)",
                       bx, by, x, y);
    return AA_OK;
}

int aa_scene_arc_to(aa_scene *s, double cx, double cy, double ux, double uy, double vx,
                    double vy, double t0, double t1, double x, double y)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->open)
        return aa_fail(AA_EFAIL, "arc_to without move_to");
    if ((st = aa__arc_check(s->penx, s->peny, cx, cy, ux, uy, vx, vy, t0, t1, x, y)))
        return st;
    if (t0 == t1)
        return AA_OK;
    if ((st = aa__add_edge3(s, cx, cy, 0.0, 0.0, x, y, 3)))
        return st;
    aa_edge *e = &s->edges[s->nedges - 1];
    e->ux = ux, e->uy = uy, e->vx = vx, e->vy = vy, e->t0 = t0, e->t1 = t1;
    return AA_OK;
}

int aa_scene_offset_to(aa_scene *s, const aa_offset_curve *oc, double t0, double t1, double x,
                       double y)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->open)
        return aa_fail(AA_EFAIL, "offset_to without move_to");
    for (int k = 0; k < 8; k++)
        if (!isfinite(oc->b[k]))
            return aa_fail(AA_EINVAL, "offset_to: the base curve is not finite");
    for (int k = 0; k < 6; k++)
        if (!isfinite(oc->m[k]))
            return aa_fail(AA_EINVAL, "offset_to: the map is not finite");
    if (oc->base != AA_OFFSET_CUBIC && oc->base != AA_OFFSET_ELLIPSE)
        return aa_fail(AA_EINVAL, "offset_to: unknown base curve %d", oc->base);
    int ell = oc->base == AA_OFFSET_ELLIPSE;
    if (!isfinite(oc->d) || !isfinite(t0) || !isfinite(t1) || !isfinite(x) || !isfinite(y) ||
        (!ell && (t0 < 0 || t0 > 1 || t1 < 0 || t1 > 1)) ||
        (ell && !(fabs(t1 - t0) <= 2.0 * M_PI * (1.0 + 1e-12))))
        return aa_fail(AA_EINVAL, "offset_to: distance %g, parameters %g .. %g or end (%g, %g) "
                                  "out of range",
                       oc->d, t0, t1, x, y);
    if (ell) {
        double lu = hypot(oc->b[2], oc->b[3]), lv = hypot(oc->b[4], oc->b[5]);
        double cross = oc->b[2] * oc->b[5] - oc->b[3] * oc->b[4];
        if (!(fabs(cross) > 1e-12 * (lu + lv) * (lu + lv)) || oc->b[6] != 0 || oc->b[7] != 0)
            return aa_fail(AA_EINVAL, "offset_to: the ellipse's semi-diameters (%g, %g) and "
                                      "(%g, %g) are parallel, or b[6], b[7] are not 0",
                           oc->b[2], oc->b[3], oc->b[4], oc->b[5]);
    }
    if (t0 == t1)
        return AA_OK;
    double a[2], b[2];
    aa_offset_point(oc, t0, &a[0], &a[1], NULL, NULL);
    aa_offset_point(oc, t1, &b[0], &b[1], NULL, NULL);
    double scale = fabs(a[0]) + fabs(a[1]) + fabs(b[0]) + fabs(b[1]) + hypot(a[0] - b[0], a[1] - b[1]);
    if (!(hypot(a[0] - s->penx, a[1] - s->peny) <= 1e-9 * scale) ||
        !(hypot(b[0] - x, b[1] - y) <= 1e-9 * scale))
        return aa_fail(AA_EINVAL, "offset_to: the curve runs from (%g, %g) to (%g, %g), not from "
                                  "the pen (%g, %g) to (%g, %g)",
                       a[0], a[1], b[0], b[1], s->penx, s->peny, x, y);
    if ((st = aa__add_edge3(s, 0.0, 0.0, 0.0, 0.0, x, y, 4)))
        return st;
    aa_edge *e = &s->edges[s->nedges - 1];
    e->cx = 0.5 * (e->x0 + e->x1), e->cy = 0.5 * (e->y0 + e->y1);
    e->t0 = t0, e->t1 = t1;
    e->oc = *oc;
    return AA_OK;
}

int aa_scene_close(aa_scene *s)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!s->open)
        return AA_OK;
    if ((s->penx != s->startx || s->peny != s->starty) &&
        (st = aa_scene_line_to(s, s->startx, s->starty)))
        return st;
    s->open = 0;
    if (s->nedges == s->contour_first)
        return AA_OK; /* an empty path */
    if ((st = grow((void **)&s->contour, &s->capcontours, s->ncontours + 2,
                   sizeof *s->contour)))
        return st;
    s->contour[s->ncontours++] = s->contour_first;
    return AA_OK;
}

/* ---- fields ---- */

int aa_scene_set_field(aa_scene *s, const aa_field_type *type, const double *p, int n)
{
    int st = check_building(s);
    if (st)
        return st;
    if (!type || !type->value || !type->pixels || n < 0 || n > AA_FIELD_MAX_PARAMS)
        return aa_fail(AA_EINVAL, "a field needs a value and a pixels function and at most "
                                  "%d parameters",
                       AA_FIELD_MAX_PARAMS);
    if (s->nlayers || s->nedges || s->field)
        return aa_fail(AA_EINVAL, "a scene is either layers of paths or one field, not both");
    for (int k = 0; k < n; k++)
        if (!isfinite(p[k]))
            return aa_fail(AA_EINVAL, "field %s: parameter %d is not finite", type->name, k);
    s->field = type;
    s->fnparam = n;
    memset(s->fparam, 0, sizeof s->fparam);
    if (n)
        memcpy(s->fparam, p, (size_t)n * sizeof *p);
    s->fmap[0] = s->fmap[1] = 1.0;
    s->fmap[2] = s->fmap[3] = 0.0;
    return AA_OK;
}

const aa_field_type *aa_scene_field(const aa_scene *s, const double **p, int *n,
                                    double map[4])
{
    if (p)
        *p = s->field ? s->fparam : NULL;
    if (n)
        *n = s->field ? s->fnparam : 0;
    if (map && s->field)
        memcpy(map, s->fmap, sizeof s->fmap);
    return s->field;
}

/* ---- pieces ---- */

/* Power basis of a piece from its control points. */
static void piece_basis(aa_piece *p, int cubic)
{
    p->dx = p->dy = 0.0;
    if (cubic) {
        aa__cubic_basis(p->y0, p->cy, p->c2y, p->y1, &p->by, &p->ay, &p->dy);
        aa__cubic_basis(p->x0, p->cx, p->c2x, p->x1, &p->bx, &p->ax, &p->dx);
    } else if (p->kind == AA_PIECE_QUAD) {
        p->ay = p->y0 - 2.0 * p->cy + p->y1;
        p->by = 2.0 * (p->cy - p->y0);
        p->ax = p->x0 - 2.0 * p->cx + p->x1;
        p->bx = 2.0 * (p->cx - p->x0);
    } else {
        p->ay = p->ax = 0.0;
        p->by = p->y1 - p->y0;
        p->bx = p->x1 - p->x0;
    }
    p->xmin = fmin(p->x0, p->x1);
    p->xmax = fmax(p->x0, p->x1);
    double ts[2];
    int n = 0;
    if (cubic)
        n = aa__cubic_turns(p->bx, p->ax, p->dx, ts);
    else if (p->kind == AA_PIECE_QUAD && p->ax != 0.0)
        ts[n++] = -p->bx / (2.0 * p->ax);
    for (int k = 0; k < n; k++) {
        double t = ts[k];
        if (t > 0.0 && t < 1.0) {
            double x = p->x0 + t * (p->bx + t * (p->ax + t * p->dx));
            p->xmin = fmin(p->xmin, x);
            p->xmax = fmax(p->xmax, x);
        }
    }
}

/* Store one y-monotone part top to bottom: q holds x0, y0, then the control
 * point(s), then x1, y1 (quad: 0 line, 1 quadratic, 2 cubic). */
static int add_piece(aa_scene *s, size_t *cap, const double *q, int quad, int layer,
                     size_t edge)
{
    int st = grow((void **)&s->pieces, cap, s->npieces + 1, sizeof *s->pieces);
    if (st)
        return st;
    aa_piece *p = &s->pieces[s->npieces++];
    memset(p, 0, sizeof *p);
    int cubic = quad == 2, last = cubic ? 6 : 4;
    int down = q[last + 1] >= q[1];
    const double *a = down ? q : q + last, *b = down ? q + last : q;
    p->x0 = a[0];
    p->y0 = a[1];
    if (cubic) { /* the controls swap when the edge runs up */
        const double *c1 = down ? q + 2 : q + 4, *c2 = down ? q + 4 : q + 2;
        p->cx = c1[0], p->cy = c1[1], p->c2x = c2[0], p->c2y = c2[1];
    } else {
        p->cx = q[2];
        p->cy = q[3];
    }
    p->x1 = b[0];
    p->y1 = b[1];
    p->layer = layer;
    p->edge = (int)edge;
    if (p->y0 == p->y1 && (!quad || p->cy == p->y0) && (!cubic || p->c2y == p->y0)) {
        p->kind = AA_PIECE_FLAT;
        p->dir = 0;
    } else {
        p->kind = cubic ? AA_PIECE_CUBIC : quad ? AA_PIECE_QUAD : AA_PIECE_LINE;
        p->dir = down ? 1 : -1;
        /* Keep the control point inside the y range: it is mathematically,
         * and clamping removes rounding that could spoil monotonicity.  A
         * monotone cubic's controls need not lie in its range, but its end
         * tangents point down: c1y >= y0 and c2y <= y1. */
        if (cubic) {
            p->cy = fmax(p->cy, p->y0);
            p->c2y = fmin(p->c2y, p->y1);
        } else if (quad) {
            p->cy = fmin(fmax(p->cy, p->y0), p->y1);
        }
    }
    piece_basis(p, cubic);
    return AA_OK;
}

/* De Casteljau: the cubic c (x0 y0 c1 c2 x1 y1, eight values) at t into
 * l and r, the split point's neighbouring controls at its height when it is
 * a y extremum (`turn`: the tangent is horizontal there). */
static void split_cubic(const double c[8], double t, int turn, double l[8], double r[8])
{
    for (int k = 0; k < 2; k++) {
        double p0 = c[k], p1 = c[2 + k], p2 = c[4 + k], p3 = c[6 + k];
        double p01 = p0 + t * (p1 - p0), p12 = p1 + t * (p2 - p1), p23 = p2 + t * (p3 - p2);
        double p012 = p01 + t * (p12 - p01), p123 = p12 + t * (p23 - p12);
        double m = p012 + t * (p123 - p012);
        if (k == 1 && turn)
            p012 = p123 = m;
        l[k] = p0, l[2 + k] = p01, l[4 + k] = p012, l[6 + k] = m;
        r[k] = m, r[2 + k] = p123, r[4 + k] = p23, r[6 + k] = p3;
    }
}

/* Elliptical arcs.  With y(t) = cy + uy cos t + vy sin t = cy + R cos(t - phi)
 * (R = |(uy, vy)|, phi = atan2(vy, uy)), y turns where t - phi is a multiple
 * of pi.  On a part where psi = t - phi (reduced to [0, 2 pi)) lies in
 * [0, pi], y falls as t grows and s = pi - psi; in [pi, 2 pi] it rises and
 * s = psi - pi; either way y = cy - R cos s with s in [0, pi] growing
 * downwards (aabench.h, aa_piece), and substituting t = phi + pi -+ s in
 * x(t) = cx + ux cos t + vx sin t gives x = cx + ea cos s + eb sin s with
 *     ea = -(ux cos phi + vx sin phi),  eb = -+(ux sin phi - vx cos phi).
 * Where a part ends at a turn, its end is the turn's exact point
 * (cy -+ R, cx +- ea), shared by the parts on either side; where it ends
 * at the edge's end, the end is the edge's own point, so contours close
 * exactly. */
static int add_conic_piece(aa_scene *s, size_t *cap, const aa_edge *e, size_t edge, double ta,
                           double tb, const double *pa, const double *pb)
{
    int st = grow((void **)&s->pieces, cap, s->npieces + 1, sizeof *s->pieces);
    if (st)
        return st;
    double R = hypot(e->uy, e->vy), phi = atan2(e->vy, e->uy);
    double cp = cos(phi), sp = sin(phi);
    double psi = 0.5 * (ta + tb) - phi;
    psi -= 2.0 * M_PI * floor(psi / (2.0 * M_PI));
    int falls = psi < M_PI; /* y falls as t grows */
    double shift = 0.5 * (ta + tb) - phi - psi; /* the multiple of 2 pi taken off */
    double psa = ta - phi - shift, psb = tb - phi - shift;
    double sa = falls ? M_PI - psa : psa - M_PI, sb = falls ? M_PI - psb : psb - M_PI;
    aa_piece *p = &s->pieces[s->npieces++];
    memset(p, 0, sizeof *p);
    p->ex = e->cx;
    p->ey = e->cy;
    p->er = R;
    p->ea = -(e->ux * cp + e->vx * sp);
    p->eb = falls ? -(e->ux * sp - e->vx * cp) : e->ux * sp - e->vx * cp;
    /* top: the end with the smaller s */
    const double *top = sa <= sb ? pa : pb, *bot = sa <= sb ? pb : pa;
    p->s0 = fmax(0.0, fmin(sa, sb));
    p->s1 = fmin(M_PI, fmax(sa, sb));
    p->x0 = top[0], p->y0 = top[1];
    p->x1 = bot[0], p->y1 = bot[1];
    p->layer = e->layer;
    p->edge = (int)edge;
    /* the edge runs down here when t and s grow together (y rises with t)
     * and t runs forwards, or both the other way */
    int forwards = e->t1 > e->t0;
    if (!(p->y1 > p->y0) || !(p->s1 > p->s0)) {
        p->kind = AA_PIECE_FLAT;
        p->dir = 0;
        p->xmin = fmin(p->x0, p->x1);
        p->xmax = fmax(p->x0, p->x1);
        return AA_OK;
    }
    p->kind = AA_PIECE_CONIC;
    p->dir = (!falls) == forwards ? 1 : -1;
    aa__conic_xrange(p, p->s0, p->s1, &p->xmin, &p->xmax);
    return AA_OK;
}

/* Split an elliptical arc edge at its y turns into conic pieces. */
static int build_conic(aa_scene *s, size_t *cap, const aa_edge *e, size_t k)
{
    double lo = fmin(e->t0, e->t1), hi = fmax(e->t0, e->t1);
    double R = hypot(e->uy, e->vy), phi = atan2(e->vy, e->uy);
    double cp = cos(phi), sp = sin(phi), ea = -(e->ux * cp + e->vx * sp);
    /* the ends in the order of t */
    double first[2] = {e->x0, e->y0}, last[2] = {e->x1, e->y1};
    if (e->t0 > e->t1) {
        first[0] = e->x1, first[1] = e->y1;
        last[0] = e->x0, last[1] = e->y0;
    }
    double prev_t = lo, prev[2] = {first[0], first[1]};
    /* turns: t = phi + j pi inside (lo, hi) */
    double j = ceil((lo - phi) / M_PI);
    for (;; j += 1.0) {
        double t = phi + j * M_PI;
        if (!(t < hi))
            break;
        if (!(t > lo))
            continue;
        /* j even: psi = 0 mod 2 pi, y = cy + R (bottom), x = cx - ea
         * (s = pi); j odd: the top, y = cy - R, x = cx + ea (s = 0) */
        int even = fmod(fabs(j), 2.0) == 0.0;
        double at[2] = {even ? e->cx - ea : e->cx + ea, even ? e->cy + R : e->cy - R};
        int st = add_conic_piece(s, cap, e, k, prev_t, t, prev, at);
        if (st)
            return st;
        prev_t = t;
        prev[0] = at[0], prev[1] = at[1];
    }
    return add_conic_piece(s, cap, e, k, prev_t, hi, prev, last);
}

/* One y-monotone part of offset edge e from parameter ta (point pa) to tb
 * (point pb), in the edge's order. */
static int add_offset_piece(aa_scene *s, size_t *cap, const aa_edge *e, size_t edge, double ta,
                            double tb, const double *pa, const double *pb)
{
    int st = grow((void **)&s->pieces, cap, s->npieces + 1, sizeof *s->pieces);
    if (st)
        return st;
    aa_piece *p = &s->pieces[s->npieces++];
    memset(p, 0, sizeof *p);
    int down = pb[1] >= pa[1];
    const double *top = down ? pa : pb, *bot = down ? pb : pa;
    p->x0 = top[0], p->y0 = top[1], p->x1 = bot[0], p->y1 = bot[1];
    p->cx = 0.5 * (p->x0 + p->x1), p->cy = 0.5 * (p->y0 + p->y1);
    p->layer = e->layer;
    p->edge = (int)edge;
    p->oc = e->oc;
    p->ot0 = down ? ta : tb;
    p->ot1 = down ? tb : ta;
    if (!(p->y1 > p->y0)) {
        p->kind = AA_PIECE_FLAT;
        p->dir = 0;
        p->xmin = fmin(p->x0, p->x1);
        p->xmax = fmax(p->x0, p->x1);
        return AA_OK;
    }
    p->kind = AA_PIECE_OFFSET;
    p->dir = down ? 1 : -1;
    p->xmin = fmin(p->x0, p->x1);
    p->xmax = fmax(p->x0, p->x1);
    double ts[2];
    int n = aa__offset_turns(&p->oc, 0, fmin(ta, tb), fmax(ta, tb), ts);
    for (int j = 0; j < n; j++) {
        double x, y;
        aa_offset_point(&p->oc, ts[j], &x, &y, NULL, NULL);
        p->xmin = fmin(p->xmin, x);
        p->xmax = fmax(p->xmax, x);
    }
    return AA_OK;
}

/* Split an offset edge at its y turns (closed form: aa__offset_turns). */
static int build_offset(aa_scene *s, size_t *cap, const aa_edge *e, size_t k)
{
    double lo = fmin(e->t0, e->t1), hi = fmax(e->t0, e->t1), ts[2];
    int n = aa__offset_turns(&e->oc, 1, lo, hi, ts);
    int fwd = e->t1 > e->t0;
    double prev_t = e->t0, prev[2] = {e->x0, e->y0};
    for (int j = 0; j < n; j++) {
        double t = fwd ? ts[j] : ts[n - 1 - j], at[2];
        aa_offset_point(&e->oc, t, &at[0], &at[1], NULL, NULL);
        int st = add_offset_piece(s, cap, e, k, prev_t, t, prev, at);
        if (st)
            return st;
        prev_t = t;
        prev[0] = at[0], prev[1] = at[1];
    }
    const double last[2] = {e->x1, e->y1};
    return add_offset_piece(s, cap, e, k, prev_t, e->t1, prev, last);
}

/* Split each edge at its y extrema into monotone pieces. */
static int build_pieces(aa_scene *s)
{
    size_t cap = 0;
    s->npieces = 0;
    for (size_t k = 0; k < s->nedges; k++) {
        const aa_edge *e = &s->edges[k];
        int st;
        if (e->quad == 3) {
            if ((st = build_conic(s, &cap, e, k)))
                return st;
            continue;
        }
        if (e->quad == 4) {
            if ((st = build_offset(s, &cap, e, k)))
                return st;
            continue;
        }
        if (e->quad == 2) {
            double c[8] = {e->x0, e->y0, e->cx, e->cy, e->c2x, e->c2y, e->x1, e->y1};
            double k1, k2, k3, ts[2], l[8], r[8], rest[8];
            aa__cubic_basis(e->y0, e->cy, e->c2y, e->y1, &k1, &k2, &k3);
            int n = aa__cubic_turns(k1, k2, k3, ts);
            memcpy(rest, c, sizeof rest);
            double done = 0.0;
            for (int m = 0; m < n; m++) {
                double t = (ts[m] - done) / (1.0 - done);
                if (!(t > 0.0 && t < 1.0))
                    continue;
                split_cubic(rest, t, 1, l, r);
                if ((st = add_piece(s, &cap, l, 2, e->layer, k)))
                    return st;
                memcpy(rest, r, sizeof rest);
                done = ts[m];
            }
            if ((st = add_piece(s, &cap, rest, 2, e->layer, k)))
                return st;
            continue;
        }
        double q[6] = {e->x0, e->y0, e->cx, e->cy, e->x1, e->y1};
        double den = e->y0 - 2.0 * e->cy + e->y1;
        double t = e->quad && den != 0.0 ? (e->y0 - e->cy) / den : -1.0;
        if (t > 0.0 && t < 1.0) {
            /* de Casteljau at t; the split point is the y extremum, where the
             * tangent is horizontal, so both inner controls share its y. */
            double ax = e->x0 + t * (e->cx - e->x0), ay = e->y0 + t * (e->cy - e->y0);
            double bx = e->cx + t * (e->x1 - e->cx), by = e->cy + t * (e->y1 - e->cy);
            double mx = ax + t * (bx - ax), my = ay + t * (by - ay);
            double first[6] = {e->x0, e->y0, ax, my, mx, my};
            double second[6] = {mx, my, bx, my, e->x1, e->y1};
            if ((st = add_piece(s, &cap, first, 1, e->layer, k)) ||
                (st = add_piece(s, &cap, second, 1, e->layer, k)))
                return st;
        } else if ((st = add_piece(s, &cap, q, e->quad, e->layer, k))) {
            return st;
        }
    }
    return AA_OK;
}

/* ---- the y index ---- */

static size_t bin_of(const aa_scene *s, double y)
{
    double b = floor((y - s->iy0) / s->ihb);
    if (!(b > 0.0))
        return 0;
    if (b >= (double)s->nbins)
        return s->nbins - 1;
    return (size_t)b;
}

static size_t index_entries(aa_scene *s)
{
    size_t n = 0;
    for (size_t k = 0; k < s->npieces; k++)
        n += bin_of(s, s->pieces[k].y1) - bin_of(s, s->pieces[k].y0) + 1;
    return n;
}

/* Bins of height about `hint` over the pieces' y range, coarsened until
 * the index has at most max(INDEX_MAX_ENTRIES, 8 n) entries. */
static int build_index(aa_scene *s, double hint)
{
    double y0 = s->by0, y1 = s->by1, extent = y1 - y0;
    if (s->npieces >= UINT32_MAX)
        return aa_fail(AA_EINVAL, "scene has %zu pieces, more than the index holds", s->npieces);
    size_t nb = 1, limit = s->npieces * 8 > INDEX_MAX_ENTRIES ? s->npieces * 8 : INDEX_MAX_ENTRIES;
    if (s->npieces && extent > 0.0 && hint > 0.0) {
        double want = ceil(extent / hint);
        nb = want >= (double)INDEX_MAX_BINS ? INDEX_MAX_BINS : (size_t)want;
        if (nb < 1)
            nb = 1;
    }
    s->iy0 = y0;
    for (;;) {
        s->nbins = nb;
        s->ihb = extent > 0.0 ? extent / (double)nb : 1.0;
        if (nb == 1 || index_entries(s) <= limit)
            break;
        nb /= 2;
    }
    free(s->bin_start);
    free(s->bin_items);
    s->bin_items = NULL;
    s->bin_start = calloc(s->nbins + 1, sizeof *s->bin_start);
    size_t entries = index_entries(s);
    if (!s->bin_start || (entries && !(s->bin_items = malloc(entries * sizeof *s->bin_items))))
        return aa_fail(AA_ENOMEM, "out of memory indexing %zu pieces", s->npieces);
    for (size_t k = 0; k < s->npieces; k++)
        for (size_t b = bin_of(s, s->pieces[k].y0); b <= bin_of(s, s->pieces[k].y1); b++)
            s->bin_start[b + 1]++;
    for (size_t b = 0; b < s->nbins; b++)
        s->bin_start[b + 1] += s->bin_start[b];
    size_t *fill = malloc(s->nbins * sizeof *fill);
    if (!fill)
        return aa_fail(AA_ENOMEM, "out of memory indexing %zu pieces", s->npieces);
    memcpy(fill, s->bin_start, s->nbins * sizeof *fill);
    for (size_t k = 0; k < s->npieces; k++)
        for (size_t b = bin_of(s, s->pieces[k].y0); b <= bin_of(s, s->pieces[k].y1); b++)
            s->bin_items[fill[b]++] = (uint32_t)k;
    free(fill);
    return AA_OK;
}

size_t aa__scene_gather(const aa_scene *s, double ya, double yb, aa__visit visit, void *ctx)
{
    size_t count = 0;
    if (!s->npieces || yb < s->by0 || ya > s->by1)
        return 0;
    size_t qa = bin_of(s, ya), qb = bin_of(s, yb);
    for (size_t b = qa; b <= qb; b++) {
        for (size_t e = s->bin_start[b]; e < s->bin_start[b + 1]; e++) {
            const aa_piece *p = &s->pieces[s->bin_items[e]];
            size_t first = bin_of(s, p->y0);
            if (b != (first > qa ? first : qa))
                continue; /* reported from an earlier bin of this query */
            if (p->y0 > yb || p->y1 < ya)
                continue;
            count += visit(ctx, p) != 0;
        }
    }
    return count;
}

static void compute_bounds(aa_scene *s)
{
    s->has_bounds = s->nedges > 0;
    s->bx0 = s->by0 = s->bx1 = s->by1 = 0.0;
    for (size_t k = 0; k < s->npieces; k++) {
        const aa_piece *p = &s->pieces[k];
        if (k == 0) {
            s->bx0 = p->xmin;
            s->bx1 = p->xmax;
            s->by0 = p->y0;
            s->by1 = p->y1;
        }
        s->bx0 = fmin(s->bx0, p->xmin);
        s->bx1 = fmax(s->bx1, p->xmax);
        s->by0 = fmin(s->by0, p->y0);
        s->by1 = fmax(s->by1, p->y1);
    }
}

static int finish(aa_scene *s, double hint)
{
    int st;
    if ((st = build_pieces(s)))
        return st;
    compute_bounds(s);
    if ((st = build_index(s, hint)))
        return st;
    s->grey = 1;
    for (int l = -1; l < s->nlayers; l++) {
        if (l >= 0 && s->member[l] >= 0)
            continue; /* a clip's member paints nothing */
        aa_rgb c = l < 0 ? s->background : s->colour[l];
        if (c.c[0] != c.c[1] || c.c[1] != c.c[2])
            s->grey = 0;
        const aa_scene_gradient *g = l >= 0 && s->paint[l] >= 0 ? &s->grads[s->paint[l]] : NULL;
        for (int k = 0; g && k < g->g.nstops; k++) {
            c = g->stops[k].colour;
            if (c.c[0] != c.c[1] || c.c[1] != c.c[2])
                s->grey = 0;
        }
    }
    if ((st = grow((void **)&s->contour, &s->capcontours, s->ncontours + 1,
                   sizeof *s->contour)))
        return st;
    s->contour[s->ncontours] = s->nedges; /* sentinel */
    if (s->field) {
        s->grey = s->field->grey;
        s->has_bounds = 1;
        s->bx0 = s->by0 = -INFINITY;
        s->bx1 = s->by1 = INFINITY;
    }
    s->finished = 1;
    return AA_OK;
}

int aa_scene_finish(aa_scene *s)
{
    int st = check_building(s);
    if (st || (st = check_colour(s->background)))
        return st;
    if (s->open_group >= 0)
        return aa_fail(AA_EINVAL, "a group of the scene is not ended");
    if (s->open_clip >= 0)
        return aa_fail(AA_EINVAL, "clip %d of the scene is not ended", s->open_clip);
    if (s->open && (st = aa_scene_close(s)))
        return st;
    /* Pattern units: about 256 bins over the unit square. */
    return finish(s, 1.0 / 256.0);
}

/* Extent of one coordinate of a quadratic Bezier (the curve, not its
 * control polygon). */
static void curve_extent(double a, double c, double b, int quad, double *lo, double *hi)
{
    *lo = fmin(a, b);
    *hi = fmax(a, b);
    double den = a - 2.0 * c + b;
    if (quad && den != 0.0) {
        double t = (a - c) / den;
        if (t > 0.0 && t < 1.0) {
            double v = (1 - t) * (1 - t) * a + 2 * t * (1 - t) * c + t * t * b;
            *lo = fmin(*lo, v);
            *hi = fmax(*hi, v);
        }
    }
}

/* The same for a cubic's coordinate, controls a, c, d, b. */
static void cubic_extent(double a, double c, double d, double b, double *lo, double *hi)
{
    double k1, k2, k3, ts[2];
    aa__cubic_basis(a, c, d, b, &k1, &k2, &k3);
    *lo = fmin(a, b);
    *hi = fmax(a, b);
    int n = aa__cubic_turns(k1, k2, k3, ts);
    for (int k = 0; k < n; k++) {
        double v = a + ts[k] * (k1 + ts[k] * (k2 + ts[k] * k3));
        *lo = fmin(*lo, v);
        *hi = fmax(*hi, v);
    }
}

/* The extent of one coordinate c + u cos t + v sin t = c + R cos(t - a) of
 * an elliptical arc edge over its t range: its ends and the turns at
 * t = a + j pi between. */
static void arc_extent(double c, double u, double v, double end0, double end1, double t0,
                       double t1, double *lo, double *hi)
{
    double a = atan2(v, u), R = hypot(u, v), tl = fmin(t0, t1), th = fmax(t0, t1);
    *lo = fmin(end0, end1);
    *hi = fmax(end0, end1);
    for (double j = ceil((tl - a) / M_PI); a + j * M_PI < th; j += 1.0) {
        double v2 = fmod(fabs(j), 2.0) == 0.0 ? c + R : c - R;
        *lo = fmin(*lo, v2);
        *hi = fmax(*hi, v2);
    }
}

int aa_scene_clip_unit(aa_scene *s)
{
    int st = check_building(s);
    if (st)
        return st;
    if (s->open_clip >= 0)
        return aa_fail(AA_EINVAL, "clip to the unit square inside the definition of clip %d",
                       s->open_clip);
    if (s->open && (st = aa_scene_close(s)))
        return st;
    double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
    for (size_t k = 0; k < s->nedges; k++) {
        const aa_edge *e = &s->edges[k];
        double lo, hi;
        if (e->quad == 4) {
            double ts[2], t0 = fmin(e->t0, e->t1), t1 = fmax(e->t0, e->t1);
            x0 = fmin(x0, fmin(e->x0, e->x1)), x1 = fmax(x1, fmax(e->x0, e->x1));
            y0 = fmin(y0, fmin(e->y0, e->y1)), y1 = fmax(y1, fmax(e->y0, e->y1));
            for (int c = 0; c < 2; c++) {
                int n = aa__offset_turns(&e->oc, c, t0, t1, ts);
                for (int j = 0; j < n; j++) {
                    double x, y;
                    aa_offset_point(&e->oc, ts[j], &x, &y, NULL, NULL);
                    x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
                }
            }
            continue;
        }
        if (e->quad == 3) {
            arc_extent(e->cx, e->ux, e->vx, e->x0, e->x1, e->t0, e->t1, &lo, &hi);
            x0 = fmin(x0, lo), x1 = fmax(x1, hi);
            arc_extent(e->cy, e->uy, e->vy, e->y0, e->y1, e->t0, e->t1, &lo, &hi);
            y0 = fmin(y0, lo), y1 = fmax(y1, hi);
            continue;
        }
        if (e->quad == 2)
            cubic_extent(e->x0, e->cx, e->c2x, e->x1, &lo, &hi);
        else
            curve_extent(e->x0, e->cx, e->x1, e->quad, &lo, &hi);
        x0 = fmin(x0, lo), x1 = fmax(x1, hi);
        if (e->quad == 2)
            cubic_extent(e->y0, e->cy, e->c2y, e->y1, &lo, &hi);
        else
            curve_extent(e->y0, e->cy, e->y1, e->quad, &lo, &hi);
        y0 = fmin(y0, lo), y1 = fmax(y1, hi);
    }
    if (x0 >= 0 && y0 >= 0 && x1 <= 1 && y1 <= 1)
        return AA_OK; /* nothing reaches outside */
    /* A new front layer of the background colour: a frame around the unit
     * square (even-odd of the outer rectangle and the square). */
    if ((st = aa_scene_layer(s, s->background, AA_FILL_EVENODD)))
        return st;
    int front = s->nlayers - 1;
    aa_rgb colour = s->colour[front];
    memmove(s->colour + 1, s->colour, (size_t)front * sizeof *s->colour);
    memmove(s->rule + 1, s->rule, (size_t)front * sizeof *s->rule);
    memmove(s->alpha + 1, s->alpha, (size_t)front * sizeof *s->alpha);
    memmove(s->encoded + 1, s->encoded, (size_t)front * sizeof *s->encoded);
    memmove(s->group + 1, s->group, (size_t)front * sizeof *s->group);
    memmove(s->gate + 1, s->gate, (size_t)front * sizeof *s->gate);
    memmove(s->member + 1, s->member, (size_t)front * sizeof *s->member);
    memmove(s->paint + 1, s->paint, (size_t)front * sizeof *s->paint);
    s->gate[0] = s->member[0] = s->paint[0] = -1;
    for (int c = 0; c < s->nclips; c++) /* their members moved back by one */
        s->clips[c].first++;
    s->colour[0] = colour;
    s->rule[0] = AA_FILL_EVENODD;
    s->alpha[0] = 1.0;
    s->group[0] = -1;
    for (int k = 0; k < 3; k++)
        s->encoded[0].c[k] = aa_srgb_encode(colour.c[k]);
    for (size_t k = 0; k < s->nedges; k++)
        s->edges[k].layer++;
    aa__scene_strokes_shift(s, 1);
    s->current = 0;
    x0 -= 1, y0 -= 1, x1 += 1, y1 += 1;
    double rect[2][4] = {{x0, y0, x1, y1}, {0, 0, 1, 1}};
    for (int r = 0; r < 2; r++) {
        const double *q = rect[r];
        if ((st = aa_scene_move_to(s, q[0], q[1])) || (st = aa_scene_line_to(s, q[2], q[1])) ||
            (st = aa_scene_line_to(s, q[2], q[3])) || (st = aa_scene_line_to(s, q[0], q[3])) ||
            (st = aa_scene_close(s)))
            return st;
    }
    return AA_OK;
}

/* aa__scene_transform's copy, before it is finished (NULL on failure,
 * reported). */
static aa_scene *transform_open(const aa_scene *s, double sx, double sy, double tx, double ty)
{
    if (!s->finished) {
        aa_fail(AA_EFAIL, "transform of an unfinished scene");
        return NULL;
    }
    if (!(sx > 0 && sy > 0 && isfinite(sx) && isfinite(sy) && isfinite(tx) && isfinite(ty))) {
        aa_fail(AA_EINVAL, "scene transform (%g, %g, %g, %g) is not a positive scaling",
                sx, sy, tx, ty);
        return NULL;
    }
    aa_scene *t = aa_scene_new(s->background);
    if (!t)
        return NULL;
    int st = AA_OK;
    for (int l = 0; l < s->nlayers && !st; l++)
        st = add_layer(t, s->colour[l], s->rule[l], s->member[l]);
    if (!st && s->ngroups) {
        size_t cap = 0;
        if (!(st = grow((void **)&t->groups, &cap, (size_t)s->ngroups, sizeof *t->groups))) {
            memcpy(t->groups, s->groups, (size_t)s->ngroups * sizeof *t->groups);
            t->ngroups = t->capgroups = s->ngroups;
        }
    }
    if (!st && s->nclips) {
        size_t cap = 0;
        if (!(st = grow((void **)&t->clips, &cap, (size_t)s->nclips, sizeof *t->clips))) {
            memcpy(t->clips, s->clips, (size_t)s->nclips * sizeof *t->clips);
            t->nclips = t->capclips = s->nclips;
        }
    }
    if (!st && s->nlayers) {
        memcpy(t->alpha, s->alpha, (size_t)s->nlayers * sizeof *t->alpha);
        memcpy(t->group, s->group, (size_t)s->nlayers * sizeof *t->group);
        memcpy(t->gate, s->gate, (size_t)s->nlayers * sizeof *t->gate);
        memcpy(t->colour, s->colour, (size_t)s->nlayers * sizeof *t->colour);
        memcpy(t->encoded, s->encoded, (size_t)s->nlayers * sizeof *t->encoded);
        t->translucent = s->translucent;
    }
    for (int l = 0; l < s->nlayers && !st; l++) {
        if (s->paint[l] < 0)
            continue;
        /* the gradient's map followed by this one */
        const double *o = s->grads[s->paint[l]].g.m;
        double m[6] = {sx * o[0], sy * o[1], sx * o[2], sy * o[3], sx * o[4] + tx,
                       sy * o[5] + ty};
        st = add_gradient(t, &s->grads[s->paint[l]].g, m, &t->paint[l]);
        if (!st) {
            memcpy(t->grads[t->paint[l]].source, s->grads[s->paint[l]].source,
                   sizeof t->grads[t->paint[l]].source);
            t->grads[t->paint[l]].interpolation = s->grads[s->paint[l]].interpolation;
        }
    }
    if (!st && s->nedges) {
        t->edges = malloc(s->nedges * sizeof *t->edges);
        t->contour = malloc((s->ncontours + 1) * sizeof *t->contour);
        if (!t->edges || !t->contour)
            st = aa_fail(AA_ENOMEM, "out of memory copying a scene");
    }
    if (!st) {
        t->capedges = t->nedges = s->nedges;
        for (size_t k = 0; k < s->nedges; k++) {
            const aa_edge *e = &s->edges[k];
            aa_edge *d = &t->edges[k];
            *d = *e;
            d->x0 = sx * e->x0 + tx, d->y0 = sy * e->y0 + ty;
            d->cx = sx * e->cx + tx, d->cy = sy * e->cy + ty;
            d->x1 = sx * e->x1 + tx, d->y1 = sy * e->y1 + ty;
            if (e->quad == 2)
                d->c2x = sx * e->c2x + tx, d->c2y = sy * e->c2y + ty;
            if (e->quad == 3) /* centre mapped above, semi-diameters scaled */
                d->ux = sx * e->ux, d->uy = sy * e->uy, d->vx = sx * e->vx, d->vy = sy * e->vy;
            if (e->quad == 4) { /* compose the curve's map with this one */
                double *m = d->oc.m;
                const double *o = e->oc.m;
                m[0] = sx * o[0], m[2] = sx * o[2], m[4] = sx * o[4] + tx;
                m[1] = sy * o[1], m[3] = sy * o[3], m[5] = sy * o[5] + ty;
            }
            if (!e->quad || e->quad == 4) { /* keep lines' control points exactly midway */
                d->cx = 0.5 * (d->x0 + d->x1);
                d->cy = 0.5 * (d->y0 + d->y1);
            }
            if (!isfinite(d->x0) || !isfinite(d->y0) || !isfinite(d->x1) ||
                !isfinite(d->y1) || !isfinite(d->cx) || !isfinite(d->cy) ||
                !isfinite(d->c2x) || !isfinite(d->c2y) || !isfinite(d->ux) ||
                !isfinite(d->uy) || !isfinite(d->vx) || !isfinite(d->vy))
                st = aa_fail(AA_EINVAL, "scene transform overflows");
        }
        if (s->nedges) {
            t->capcontours = s->ncontours + 1;
            t->ncontours = s->ncontours;
            memcpy(t->contour, s->contour, s->ncontours * sizeof *t->contour);
        }
    }
    if (!st)
        st = aa__scene_strokes_copy(s, t, sx, sy, tx, ty);
    if (!st && s->field) {
        /* compose the map: the field's point goes to s's, then through this one */
        t->field = s->field;
        memcpy(t->fparam, s->fparam, sizeof t->fparam);
        t->fnparam = s->fnparam;
        t->fmap[0] = sx * s->fmap[0];
        t->fmap[1] = sy * s->fmap[1];
        t->fmap[2] = sx * s->fmap[2] + tx;
        t->fmap[3] = sy * s->fmap[3] + ty;
        for (int k = 0; k < 4; k++)
            if (!isfinite(t->fmap[k]) || (k < 2 && !(t->fmap[k] > 0.0)))
                st = aa_fail(AA_EINVAL, "scene transform of the field overflows");
    }
    if (st) {
        aa_scene_free(t);
        return NULL;
    }
    return t;
}

aa_scene *aa__scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty,
                              double hint)
{
    aa_scene *t = transform_open(s, sx, sy, tx, ty);
    if (t && finish(t, hint)) {
        aa_scene_free(t);
        return NULL;
    }
    return t;
}

aa_scene *aa__scene_copy_open(const aa_scene *s) { return transform_open(s, 1.0, 1.0, 0.0, 0.0); }

int aa__scene_finish_copy(aa_scene *s, double hint)
{
    int st = check_building(s);
    if (!st && s->open)
        st = aa_scene_close(s);
    return st ? st : finish(s, hint);
}

aa_scene *aa_scene_transform(const aa_scene *s, double sx, double sy, double tx, double ty)
{
    return aa__scene_transform(s, sx, sy, tx, ty, sy / 256.0);
}

aa_scene *aa_scene_place(const aa_scene *s, int w, int h, double t, double vx, double vy)
{
    if (w < 1 || h < 1 || !isfinite(t) || !isfinite(vx) || !isfinite(vy)) {
        aa_fail(AA_EINVAL, "cannot place a scene on %dx%d at time %g moving (%g, %g)", w, h,
                t, vx, vy);
        return NULL;
    }
    /* One bin per pixel row: a row's strip then reads one or two bins. */
    return aa__scene_transform(s, (double)w, (double)h, t * vx, t * vy, 1.0);
}

/* ---- reading ---- */

aa_rgb aa_scene_background(const aa_scene *s) { return s->background; }
int aa_scene_layer_count(const aa_scene *s) { return s->nlayers; }
aa_rgb aa_scene_layer_colour(const aa_scene *s, int layer) { return s->colour[layer]; }
aa_fill_rule aa_scene_layer_rule(const aa_scene *s, int layer) { return s->rule[layer]; }
int aa_scene_is_grey(const aa_scene *s) { return s->grey; }

const aa_edge *aa_scene_edges(const aa_scene *s, size_t *n)
{
    *n = s->nedges;
    return s->edges;
}

const size_t *aa_scene_contours(const aa_scene *s, size_t *ncontours)
{
    *ncontours = s->ncontours;
    return s->contour;
}

const aa_piece *aa_scene_pieces(const aa_scene *s, size_t *n)
{
    *n = s->npieces;
    return s->pieces;
}

int aa_scene_bounds(const aa_scene *s, double *x0, double *y0, double *x1, double *y1)
{
    *x0 = s->bx0;
    *y0 = s->by0;
    *x1 = s->bx1;
    *y1 = s->by1;
    return s->has_bounds;
}

int aa_scene_is_opaque(const aa_scene *s) { return !s->translucent && !s->nclips; }
int aa_scene_is_clipped(const aa_scene *s) { return s->nclips > 0; }
int aa_scene_clip_count(const aa_scene *s) { return s->nclips; }
int aa_scene_layer_clip(const aa_scene *s, int layer) { return s->gate[layer]; }
int aa_scene_layer_clip_member(const aa_scene *s, int layer) { return s->member[layer]; }
int aa_scene_clip_within(const aa_scene *s, int clip) { return s->clips[clip].within; }
int aa_scene_clip_members(const aa_scene *s, int clip, int *first)
{
    *first = s->clips[clip].first;
    return s->clips[clip].count;
}
double aa_scene_layer_alpha(const aa_scene *s, int layer) { return s->alpha[layer]; }
int aa_scene_layer_group(const aa_scene *s, int layer) { return s->group[layer]; }
int aa_scene_group_count(const aa_scene *s) { return s->ngroups; }
int aa_scene_group_parent(const aa_scene *s, int group) { return s->groups[group].parent; }
double aa_scene_group_opacity(const aa_scene *s, int group) { return s->groups[group].opacity; }

static int fills(const aa_scene *s, const int *wind, int l)
{
    return s->rule[l] == AA_FILL_EVENODD ? (wind[l] & 1) : wind[l] != 0;
}

/* 1 if the point of winding numbers `wind` is inside clip c: inside the
 * clip it is defined within, and where some member's fill rule holds and
 * the point is inside that member's own clip.  Clips refer to earlier
 * clips only and at most AA_SCENE_MAX_CLIP_DEPTH deep, so this ends. */
static int in_clip(const aa_scene *s, const int *wind, int c)
{
    const aa_scene_clip *k = &s->clips[c];
    if (k->within >= 0 && !in_clip(s, wind, k->within))
        return 0;
    for (int l = k->first; l < k->first + k->count; l++)
        if (fills(s, wind, l) && (s->gate[l] < 0 || in_clip(s, wind, s->gate[l])))
            return 1;
    return 0;
}

/* 1 if layer l paints the point: it paints (it is no clip's member), its
 * fill rule holds, and the point is inside its clip. */
static int covers(const aa_scene *s, const int *wind, int l)
{
    if (!fills(s, wind, l))
        return 0;
    return !s->nclips || (s->member[l] < 0 && (s->gate[l] < 0 || in_clip(s, wind, s->gate[l])));
}

int aa__scene_covers(const aa_scene *s, const int *wind, int layer)
{
    return covers(s, wind, layer);
}

/* An accumulator of premultiplied encoded colour p and alpha a. */
typedef struct premul { double p[3], a; } premul;

/* The layers covering a point, `first` the front-most of them (not solid),
 * composited back to front from the front-most solid one behind it (alpha
 * 1, in no group) or the background: each layer source over the innermost
 * open group's accumulator, each group (opened at its back-most covering
 * layer) composited over its parent with its opacity when the next layer
 * lies outside it (W3C Compositing and Blending Level 1, "source-over";
 * group opacity as SVG 2's `opacity`: the group's result times the
 * opacity, then source over). */
/* Layer l's sRGB-encoded colour and alpha at (x, y) (at: a gradient layer
 * paints its colour there; else every layer its own colour); the layers
 * ol[0 .. nol - 1] paint ov[4 k .. 4 k + 3] (encoded channels and opacity)
 * instead. */
static double layer_paint(const aa_scene *s, int l, int at, double x, double y, int nol,
                          const int *ol, const double *ov, double e[3])
{
    for (int k = 0; k < nol; k++)
        if (l == ol[k]) {
            const double *v = ov + 4 * k;
            e[0] = v[0], e[1] = v[1], e[2] = v[2];
            return s->alpha[l] * v[3];
        }
    if (at && s->paint[l] >= 0) {
        const aa_scene_gradient *g = &s->grads[s->paint[l]];
        double v[4], t = aa__gradient_t(g, x, y);
        aa__gradient_paint(g, aa__gradient_spread(g->g.spread, t), v);
        if (isnan(t)) /* the cone case, on no circle: unpainted */
            v[3] = 0.0;
        e[0] = v[0], e[1] = v[1], e[2] = v[2];
        return s->alpha[l] * v[3];
    }
    e[0] = s->encoded[l].c[0], e[1] = s->encoded[l].c[1], e[2] = s->encoded[l].c[2];
    return s->alpha[l];
}

static void composite_encoded(const aa_scene *s, const int *wind, int first, int at, double x,
                              double y, int nol, const int *ol, const double *ov, double out[3])
{
    int base = first + 1;
    double be[3];
    while (base < s->nlayers && !(covers(s, wind, base) && s->group[base] < 0 &&
                                  layer_paint(s, base, at, x, y, nol, ol, ov, be) == 1.0))
        base++;
    premul acc[AA_SCENE_MAX_GROUP_DEPTH + 1];
    int gid[AA_SCENE_MAX_GROUP_DEPTH + 1], depth = 0;
    for (int k = 0; k < 3; k++)
        acc[0].p[k] = base < s->nlayers ? be[k] : aa_srgb_encode(s->background.c[k]);
    acc[0].a = 1.0;
    gid[0] = -1;
    for (int l = base - 1; l >= first; l--) {
        if (!covers(s, wind, l))
            continue;
        /* the layer's groups, outermost first */
        int chain[AA_SCENE_MAX_GROUP_DEPTH], n = 0;
        for (int g = s->group[l]; g >= 0; g = s->groups[g].parent)
            chain[n++] = g;
        int keep = 0; /* groups open now that hold the layer */
        while (keep < depth && keep < n && gid[keep + 1] == chain[n - 1 - keep])
            keep++;
        for (; depth > keep; depth--) { /* close the groups left */
            const double o = s->groups[gid[depth]].opacity, oa = o * acc[depth].a;
            premul *d = &acc[depth - 1];
            for (int k = 0; k < 3; k++)
                d->p[k] = o * acc[depth].p[k] + (1.0 - oa) * d->p[k];
            d->a = oa + (1.0 - oa) * d->a;
        }
        for (; depth < n; depth++) { /* open the layer's own */
            gid[depth + 1] = chain[n - 1 - depth];
            acc[depth + 1] = (premul){{0.0, 0.0, 0.0}, 0.0};
        }
        double e[3];
        const double a = layer_paint(s, l, at, x, y, nol, ol, ov, e);
        premul *d = &acc[depth];
        for (int k = 0; k < 3; k++)
            d->p[k] = a * e[k] + (1.0 - a) * d->p[k];
        d->a = a + (1.0 - a) * d->a;
    }
    for (; depth > 0; depth--) {
        const double o = s->groups[gid[depth]].opacity, oa = o * acc[depth].a;
        premul *d = &acc[depth - 1];
        for (int k = 0; k < 3; k++)
            d->p[k] = o * acc[depth].p[k] + (1.0 - oa) * d->p[k];
        d->a = oa + (1.0 - oa) * d->a;
    }
    for (int k = 0; k < 3; k++)
        out[k] = acc[0].p[k];
}

static aa_rgb colour_composite(const aa_scene *s, const int *wind, int first, int at, double x,
                               double y)
{
    double e[3];
    composite_encoded(s, wind, first, at, x, y, 0, NULL, NULL, e);
    aa_rgb c;
    for (int k = 0; k < 3; k++)
        c.c[k] = aa_srgb_decode(e[k]);
    return c;
}

aa_rgb aa_scene_colour_of(const aa_scene *s, const int *wind)
{
    for (int l = 0; l < s->nlayers; l++)
        if (covers(s, wind, l)) {
            if (s->alpha[l] == 1.0 && s->group[l] < 0)
                return s->colour[l];
            return colour_composite(s, wind, l, 0, 0.0, 0.0);
        }
    return s->background;
}

void aa_scene_encoded_of_at(const aa_scene *s, const int *wind, double x, double y, double e[3])
{
    for (int l = 0; l < s->nlayers; l++)
        if (covers(s, wind, l)) {
            composite_encoded(s, wind, l, 1, x, y, 0, NULL, NULL, e);
            return;
        }
    for (int k = 0; k < 3; k++)
        e[k] = aa_srgb_encode(s->background.c[k]);
}

void aa_scene_encoded_with(const aa_scene *s, const int *wind, int layer, const double paint[4],
                           double e[3])
{
    for (int l = 0; l < s->nlayers; l++)
        if (covers(s, wind, l)) {
            composite_encoded(s, wind, l, 0, 0.0, 0.0, 1, &layer, paint, e);
            return;
        }
    for (int k = 0; k < 3; k++)
        e[k] = aa_srgb_encode(s->background.c[k]);
}

void aa_scene_encoded_with_n(const aa_scene *s, const int *wind, int n, const int *layers,
                             const double *paints, double e[3])
{
    for (int l = 0; l < s->nlayers; l++)
        if (covers(s, wind, l)) {
            composite_encoded(s, wind, l, 0, 0.0, 0.0, n, layers, paints, e);
            return;
        }
    for (int k = 0; k < 3; k++)
        e[k] = aa_srgb_encode(s->background.c[k]);
}

int aa_scene_fold_cap(const aa_scene *s) { return s->nlayers + 2 * s->ngroups; }

/* composite_encoded's walk, written out as steps (core.h): each group's
 * layers are contiguous, so it is opened and closed at most once. */
int aa_scene_fold(const aa_scene *s, const int *wind, int n, const int *layers, aa_fold_step *steps,
                  int cap, double base[3])
{
    int b = 0, ns = 0, depth = 0, gid[AA_SCENE_MAX_GROUP_DEPTH + 1];
    for (;; b++) {
        int listed = 0;
        for (int k = 0; k < n && !listed && b < s->nlayers; k++)
            listed = layers[k] == b;
        if (b >= s->nlayers ||
            (!listed && covers(s, wind, b) && s->group[b] < 0 && s->alpha[b] == 1.0))
            break;
    }
    for (int k = 0; k < 3; k++)
        base[k] = b < s->nlayers ? s->encoded[b].c[k] : aa_srgb_encode(s->background.c[k]);
    gid[0] = -1;
    for (int l = b - 1; l >= -1; l--) {
        if (l >= 0 && !covers(s, wind, l))
            continue;
        int chain[AA_SCENE_MAX_GROUP_DEPTH], nc = 0, keep = 0;
        if (l >= 0)
            for (int g = s->group[l]; g >= 0; g = s->groups[g].parent)
                chain[nc++] = g;
        while (keep < depth && keep < nc && gid[keep + 1] == chain[nc - 1 - keep])
            keep++;
        for (; depth > keep; depth--) {
            if (ns >= cap)
                return -1;
            steps[ns++] = (aa_fold_step){AA_FOLD_CLOSE, -1, s->groups[gid[depth]].opacity, {0, 0, 0}};
        }
        if (l < 0)
            break;
        for (; depth < nc; depth++) {
            if (ns >= cap)
                return -1;
            gid[depth + 1] = chain[nc - 1 - depth];
            steps[ns++] = (aa_fold_step){AA_FOLD_OPEN, -1, 0.0, {0, 0, 0}};
        }
        if (ns >= cap)
            return -1;
        aa_fold_step *st = &steps[ns++];
        double e[3];
        st->op = AA_FOLD_LAYER, st->layer = l;
        st->a = layer_paint(s, l, 0, 0.0, 0.0, 0, NULL, NULL, e);
        memcpy(st->c, e, sizeof e);
    }
    return ns;
}

aa_rgb aa_scene_colour_of_at(const aa_scene *s, const int *wind, double x, double y)
{
    if (!s->ngrads)
        return aa_scene_colour_of(s, wind);
    for (int l = 0; l < s->nlayers; l++)
        if (covers(s, wind, l)) {
            if (s->alpha[l] == 1.0 && s->group[l] < 0 && s->paint[l] < 0)
                return s->colour[l];
            return colour_composite(s, wind, l, 1, x, y);
        }
    return s->background;
}

/* ---- point and line queries ---- */

struct point_ctx {
    const aa_scene *s;
    double x, y;
    int *wind;
};

static int visit_point(void *vctx, const aa_piece *p)
{
    struct point_ctx *ctx = vctx;
    if (p->dir && p->y0 <= ctx->y && ctx->y < p->y1 && aa_piece_x_at(p, ctx->y) < ctx->x)
        ctx->wind[p->layer] += p->dir;
    return 0;
}

aa_rgb aa_scene_colour_at(const aa_scene *s, double x, double y)
{
    if (s->field)
        return s->field->value(s->fparam, (x - s->fmap[2]) / s->fmap[0],
                               (y - s->fmap[3]) / s->fmap[1]);
    int small[16], *wind = small;
    if (s->nlayers > 16 && !(wind = calloc((size_t)s->nlayers, sizeof *wind)))
        return s->background; /* cannot happen in practice: tiny allocation */
    memset(wind, 0, (size_t)(s->nlayers < 16 ? 16 : s->nlayers) * sizeof *wind);
    struct point_ctx ctx = {s, x, y, wind};
    aa__scene_gather(s, y, y, visit_point, &ctx);
    aa_rgb c = aa_scene_colour_of_at(s, wind, x, y);
    if (wind != small)
        free(wind);
    return c;
}

struct line_ctx {
    double y;
    aa_crossing *out;
    size_t cap, n;
};

static int visit_line(void *vctx, const aa_piece *p)
{
    struct line_ctx *ctx = vctx;
    if (!p->dir || !(p->y0 <= ctx->y && ctx->y < p->y1))
        return 0;
    if (ctx->n < ctx->cap) {
        aa_crossing *c = &ctx->out[ctx->n];
        c->x = aa_piece_x_at(p, ctx->y);
        c->dir = p->dir;
        c->layer = p->layer;
    }
    ctx->n++;
    return 1;
}

static int cmp_crossing(const void *a, const void *b)
{
    const aa_crossing *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->layer != q->layer)
        return p->layer - q->layer;
    return p->dir - q->dir;
}

/* A line's crossings come from the pieces in path order, nearly sorted one
 * way or the other (scene_internal.h, AA__NEAR_SORT).  Crossings that
 * compare equal are equal in every field, so the order is the one order. */
AA__NEAR_SORT(sort_crossings, aa_crossing, cmp_crossing)

size_t aa_scene_crossings(const aa_scene *s, double y, aa_crossing *out, size_t cap)
{
    struct line_ctx ctx = {y, out, cap, 0};
    aa__scene_gather(s, y, y, visit_line, &ctx);
    if (ctx.n > 1 && ctx.n <= cap)
        sort_crossings(out, ctx.n);
    return ctx.n;
}

struct touch_ctx {
    const aa_scene *s;
    double x0, y0, x1, y1;
    size_t *out;
    size_t cap, n;
};

static int visit_touch(void *vctx, const aa_piece *p)
{
    struct touch_ctx *ctx = vctx;
    double lo, hi;
    aa_piece_xrange(p, ctx->y0, ctx->y1, &lo, &hi);
    if (hi < ctx->x0 || lo > ctx->x1)
        return 0;
    if (ctx->n < ctx->cap)
        ctx->out[ctx->n] = (size_t)(p - ctx->s->pieces);
    ctx->n++;
    return 1;
}

size_t aa_scene_touching(const aa_scene *s, double x0, double y0, double x1, double y1,
                         size_t *out, size_t cap)
{
    struct touch_ctx ctx = {s, x0, y0, x1, y1, out, cap, 0};
    aa__scene_gather(s, y0, y1, visit_touch, &ctx);
    return ctx.n;
}
