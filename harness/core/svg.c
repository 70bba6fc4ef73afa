/*
 * svg.c: a placed scene written as an SVG document (core.h, "SVG").
 *
 * The document is in pixel units: width and height are the image's W and H,
 * the viewBox is 0 0 W H, and every coordinate is the placed scene's own
 * (aa_scene_place: pixel (i, j) covers [i, i+1] x [j, j+1]), so an SVG
 * renderer drawing the document at W x H sees what the methods see.  A
 * rectangle of the background colour covers the image; then one <path>
 * per layer, in painter's order: the scene keeps its layers front to back,
 * so the back layer is written first and the front layer last.  Each path
 * has the layer's fill rule (fill-rule nonzero or evenodd) and id "layerK"
 * (K the layer's index in the scene, 0 the front), and each closed contour
 * of the layer is one subpath "M x y", then "L x y" for a line segment and
 * "Q cx cy x y" for a quadratic Bezier arc and "C c1x c1y c2x c2y x y" for a
 * cubic one (the scene's own arcs, exactly), "A rx ry phi large sweep x y"
 * for each piece of an elliptical arc (below), then "Z".  A layer with no contour is a path with an empty d, which draws
 * nothing.
 *
 * Numbers are C-locale %.17g, which reads back to the same double.
 *
 * Elliptical arcs.  The scene keeps an arc in centre form, the points
 * c + M (cos t, sin t) for t from t0 to t1 with M = [u v] (columns u, v,
 * two conjugate semi-diameters); SVG's A command gives the ellipse by its
 * principal radii rx, ry and the rotation phi of its x axis, and the arc by
 * its ends and two flags (SVG 1.1 F.6.2).  The principal axes are M's
 * singular vectors: write M = R(phi) diag(p, q) R(theta) with R(a) the
 * rotation by a; multiplying out, with M = [[a, b], [c, d]] (a = ux,
 * b = vx, c = uy, d = vy),
 *     a + d = (p + q) cos(phi + theta),   c - b = (p + q) sin(phi + theta),
 *     a - d = (p - q) cos(phi - theta),   c + b = (p - q) sin(phi - theta),
 * so with E = (a + d)/2, H = (c - b)/2, F = (a - d)/2, G = (c + b)/2:
 *     p + q = 2 hypot(E, H),  p - q = 2 hypot(F, G),
 *     phi = (atan2(H, E) + atan2(G, F))/2.
 * R(theta) and a sign of q only turn or mirror the unit circle, so the
 * ellipse is c + R(phi) diag(p, |q|) (unit circle): rx = p along the
 * direction phi, ry = |q|, taken as |det M|/rx (no cancellation for a thin
 * ellipse).  When u and v are perpendicular (u . v = 0 exactly, every
 * circle and every ellipse with its axes along x and y) they are the
 * axes themselves: rx = |u|, ry = |v|, phi the direction of u, taken
 * modulo 180 degrees into (-90, 90], so that an ellipse along the axes
 * is written with its radii exactly and phi = 0.  The large-arc flag is |t1 - t0| > pi; the sweep flag is 1 when
 * the arc turns the way of increasing angle in the document's own
 * coordinates (x right, y down), the sign of the cross product of (P - c)
 * and P', which is det M (t1 - t0).  The arc is written as n equal pieces
 * of at most 90 degrees of t (n = 1 .. 4), each its own A command: an SVG
 * arc with equal ends draws nothing, so a full turn must be split anyway,
 * and a reader recovers an arc's centre through a square root
 * (SVG 1.1 F.6.5, step 3) whose radicand falls to zero, and loses half its
 * digits, as the arc nears a half turn; at 90 degrees the radicand is 1
 * for a circle.  Pieces end at c + M (cos t, sin t) at their t, the last
 * at the edge's own end.
 *
 * Colours.  SVG colours are sRGB-encoded (SVG 1.1 and CSS: rgb() values are
 * in the sRGB colour space, as display codes), and renderers composite them
 * in that encoded space.  A layer's linear colour c is written as
 * rgb(R%, G%, B%) with each percentage 100 * srgb_encode(c) at full
 * precision, never rounded to 8 bits: a renderer that honours it shows the
 * colour the scene means (1 is written 100% exactly, where the formula's
 * rounding would give 99.999999999999986%).  Colours 0 and 1, which every pattern of paths
 * here uses (black, white and the primaries), are 0% and 100% under any
 * encoding, so their meaning does not depend on it.  Percentages below
 * 1e-4 are written in fixed notation (CSS numbers before CSS Values 3 had
 * no exponent).
 *
 * Strokes.  A layer the scene keeps as a stroke (aa_scene_stroke) is
 * written as the stroke, not as its outline: a <path> of the source's path
 * in its own user units (subpaths open or closed as given, arcs as the A
 * pieces above) with fill="none", the stroke's colour, stroke-width,
 * stroke-linejoin, stroke-linecap, stroke-miterlimit, stroke-dasharray and
 * stroke-dashoffset when it is dashed, and the source's map (user units to
 * pixels) as transform="matrix(a b c d e f)" (SVG's order: x' = a x + c y
 * + e, y' = b x + d y + f), so that a renderer strokes it with its own
 * stroker in user space as SVG says, and the project's reader gives the
 * same stroke back.
 *
 * Clips.  Each clip of the scene (aa_scene_clip_begin) is a <clipPath
 * id="clipC"> in a <defs> before the layers, in pixel units (clipPathUnits
 * userSpaceOnUse, no transform), with clip-path="url(#clipW)" when it lies
 * within clip W; each member layer is a <path id="layerK"> in it with the
 * member's clip-rule, and clip-path="url(#clipG)" when the member has a
 * clip of its own (SVG 1.1 14.3.5 and CSS Masking 1: a child of a
 * clipPath may be clipped).  A clipped layer has clip-path="url(#clipG)";
 * a stroke (which carries its map as a transform, and a clip is in the
 * user space of the element referencing it) is wrapped in a <g> holding
 * it.  A member is never a stroke (aa_scene_stroke adds a painting layer),
 * so its path data is its fill, as a clipPath's child is.
 *
 * AA_SVG_MASK paints every layer white over a black background: for a scene
 * of one layer the rendered image is that layer's coverage of each pixel,
 * as the renderer computes it.
 */
#include "core.h"
#include "c_numbers_internal.h"
#include "path.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One channel of a linear colour as an sRGB percentage. */
static void put_percent(FILE *f, double linear)
{
    static const aa_encode srgb = {AA_ENCODE_SRGB, 0};
    /* the end points exactly: the formula gives 1 - 1e-16 for 1 */
    double p = linear >= 1.0 ? 100.0 : 100.0 * aa_encode_value(&srgb, linear);
    if (p > 0 && p < 1e-4) /* %.17g would write an exponent */
        fprintf(f, "%.*f%%", 16 - (int)floor(log10(p)), p);
    else
        fprintf(f, "%.17g%%", p);
}

static void put_colour(FILE *f, aa_rgb c)
{
    fputs("rgb(", f);
    for (int k = 0; k < 3; k++) {
        put_percent(f, c.c[k]);
        fputs(k < 2 ? "," : ")", f);
    }
}

/* Text for element content: & < > escaped. */
static void put_text(FILE *f, const char *text)
{
    for (const char *c = text; *c; c++) {
        if (*c == '&')
            fputs("&amp;", f);
        else if (*c == '<')
            fputs("&lt;", f);
        else if (*c == '>')
            fputs("&gt;", f);
        else
            fputc(*c, f);
    }
}

/* Elliptical arc edge e (quad == 3) as A commands (see the header). */
static void put_arc(FILE *f, const aa_edge *e)
{
    double a = e->ux, b = e->vx, c = e->uy, d = e->vy;
    double det = a * d - b * c, rx, ry, phi;
    if (a * b + c * d == 0.0) { /* u, v perpendicular: they are the axes */
        rx = hypot(a, c), ry = hypot(b, d);
        phi = atan2(c, a) * (180.0 / M_PI);
        /* the same ellipse turned half a turn: phi in (-90, 90], 0 for u
         * along either way of the x axis, so its cosine and sine are
         * exact */
        phi = phi > 90.0 ? phi - 180.0 : phi <= -90.0 ? phi + 180.0 : phi;
    } else {
        double E = (a + d) / 2, F = (a - d) / 2, G = (c + b) / 2, H = (c - b) / 2;
        rx = hypot(E, H) + hypot(F, G);
        ry = fabs(det) / rx;
        phi = (atan2(H, E) + atan2(G, F)) / 2 * (180.0 / M_PI);
    }
    double dt = e->t1 - e->t0;
    int n = (int)ceil(fabs(dt) / (M_PI / 2) - 1e-9); /* a hair over 90: rounding */
    n = n < 1 ? 1 : n > 4 ? 4 : n;
    double h = dt / n;
    int large = fabs(h) > M_PI, sweep = det * h > 0;
    for (int k = 1; k <= n; k++) {
        double t = e->t0 + k * h;
        double x = k == n ? e->x1 : e->cx + a * cos(t) + b * sin(t);
        double y = k == n ? e->y1 : e->cy + c * cos(t) + d * sin(t);
        fprintf(f, " A %.17g %.17g %.17g %d %d %.17g %.17g", rx, ry, phi, large, sweep, x, y);
    }
}

/* Layer `layer`'s contours as path data. */
static void put_layer_data(FILE *f, const aa_scene *s, int layer)
{
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(s, &ne);
    const size_t *start = aa_scene_contours(s, &nc);
    int first = 1;
    for (size_t c = 0; c < nc; c++) {
        size_t a = start[c], b = start[c + 1];
        if (a == b || e[a].layer != layer)
            continue;
        fprintf(f, "%sM %.17g %.17g", first ? "" : "\n", e[a].x0, e[a].y0);
        first = 0;
        for (size_t k = a; k < b; k++) {
            if (e[k].quad == 3)
                put_arc(f, &e[k]);
            else if (e[k].quad == 2)
                fprintf(f, " C %.17g %.17g %.17g %.17g %.17g %.17g", e[k].cx, e[k].cy,
                        e[k].c2x, e[k].c2y, e[k].x1, e[k].y1);
            else if (e[k].quad)
                fprintf(f, " Q %.17g %.17g %.17g %.17g", e[k].cx, e[k].cy, e[k].x1, e[k].y1);
            else
                fprintf(f, " L %.17g %.17g", e[k].x1, e[k].y1);
        }
        fputs(" Z", f);
    }
}

/* A stroke source's path in its own user units: every subpath as given,
 * open or closed (Z only where the path closes it), arcs as A pieces. */
static void put_source_data(FILE *f, const aa_path *p)
{
    double px = 0, py = 0;
    for (size_t k = 0; k < p->n; k++) {
        const aa_path_seg *g = &p->seg[k];
        const double *q = g->p;
        const char *sep = k ? " " : "";
        switch (g->op) {
        case AA_PATH_MOVE:
            fprintf(f, "%sM %.17g %.17g", sep, q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_LINE:
            fprintf(f, "%sL %.17g %.17g", sep, q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_QUAD:
            fprintf(f, "%sQ %.17g %.17g %.17g %.17g", sep, q[0], q[1], q[2], q[3]);
            px = q[2], py = q[3];
            break;
        case AA_PATH_CUBIC:
            fprintf(f, "%sC %.17g %.17g %.17g %.17g %.17g %.17g", sep, q[0], q[1], q[2], q[3],
                    q[4], q[5]);
            px = q[4], py = q[5];
            break;
        case AA_PATH_ARC: {
            aa_edge e = {0};
            e.x0 = px, e.y0 = py, e.cx = q[0], e.cy = q[1];
            e.ux = q[2], e.uy = q[3], e.vx = q[4], e.vy = q[5], e.t0 = q[6], e.t1 = q[7];
            e.x1 = q[8], e.y1 = q[9], e.quad = 3;
            put_arc(f, &e); /* begins with its own space */
            px = q[8], py = q[9];
            break;
        }
        default:
            fprintf(f, "%sZ", sep);
            break;
        }
    }
}

/* Layer l drawn by its stroke source: the path in user units with the
 * stroke's properties and the source's map as the path's transform, so
 * that a renderer strokes it itself, as SVG says (the width in user
 * units, a non-uniform map transforming the outline). */
static void put_stroke(FILE *f, const aa_stroke_source *src, int l, aa_rgb colour,
                       double alpha)
{
    static const char *const joins[] = {"miter", "round", "bevel", "miter-clip", "arcs"};
    static const char *const caps[] = {"butt", "round", "square"};
    const aa_stroke_style *st = &src->style;
    fprintf(f, "<path id=\"layer%d\" fill=\"none\" stroke=\"", l);
    put_colour(f, colour);
    if (alpha < 1)
        fprintf(f, "\" stroke-opacity=\"%.17g", alpha);
    fprintf(f, "\" stroke-width=\"%.17g\" stroke-linejoin=\"%s\" stroke-linecap=\"%s\" "
               "stroke-miterlimit=\"%.17g\"",
            st->width, joins[st->join], caps[st->cap], st->miterlimit);
    if (st->ndash) {
        fputs(" stroke-dasharray=\"", f);
        for (size_t k = 0; k < st->ndash; k++)
            fprintf(f, "%s%.17g", k ? " " : "", st->dash[k]);
        fprintf(f, "\" stroke-dashoffset=\"%.17g\"", st->dashoffset);
    }
    fputs(" transform=\"matrix(", f);
    for (int k = 0; k < 6; k++)
        fprintf(f, "%s%.17g", k ? " " : "", src->m[k]);
    fputs(")\" d=\"", f);
    put_source_data(f, &src->path);
    fputs("\"/>\n", f);
}

static void put_document(FILE *f, const aa_scene *s, int w, int h, aa_svg_paint paint,
                         const char *desc)
{
    const aa_rgb black = {{0, 0, 0}}, white = {{1, 1, 1}};
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
               "viewBox=\"0 0 %d %d\">\n", w, h, w, h);
    if (desc && *desc) {
        fputs("<desc>", f);
        put_text(f, desc);
        fputs("</desc>\n", f);
    }
    fprintf(f, "<rect x=\"0\" y=\"0\" width=\"%d\" height=\"%d\" fill=\"", w, h);
    put_colour(f, paint == AA_SVG_MASK ? black : aa_scene_background(s));
    fputs("\"/>\n", f);
    size_t nsrc;
    const aa_stroke_source *src = aa_scene_stroke_sources(s, &nsrc);
    const int nclips = aa_scene_clip_count(s);
    if (nclips)
        fputs("<defs>\n", f);
    for (int c = 0; c < nclips; c++) {
        int first, n = aa_scene_clip_members(s, c, &first);
        fprintf(f, "<clipPath id=\"clip%d\" clipPathUnits=\"userSpaceOnUse\"", c);
        if (aa_scene_clip_within(s, c) >= 0)
            fprintf(f, " clip-path=\"url(#clip%d)\"", aa_scene_clip_within(s, c));
        fputs(">\n", f);
        for (int l = first; l < first + n; l++) {
            fprintf(f, "<path id=\"layer%d\" clip-rule=\"%s\"", l,
                    aa_scene_layer_rule(s, l) == AA_FILL_EVENODD ? "evenodd" : "nonzero");
            if (aa_scene_layer_clip(s, l) >= 0)
                fprintf(f, " clip-path=\"url(#clip%d)\"", aa_scene_layer_clip(s, l));
            fputs(" d=\"", f);
            put_layer_data(f, s, l);
            fputs("\"/>\n", f);
        }
        fputs("</clipPath>\n", f);
    }
    if (nclips)
        fputs("</defs>\n", f);
    /* translucency as SVG writes it (the mask is coverage only): a layer's
     * alpha as its fill-opacity or stroke-opacity, each group a <g> with
     * its opacity around its layers, opened and closed as the layers go
     * back to front */
    const int mask = paint == AA_SVG_MASK;
    int open[AA_SCENE_MAX_GROUP_DEPTH], depth = 0;
    for (int l = aa_scene_layer_count(s) - 1; l >= 0; l--) {
        if (aa_scene_layer_clip_member(s, l) >= 0)
            continue; /* written in its clipPath */
        int chain[AA_SCENE_MAX_GROUP_DEPTH], n = 0;
        for (int g = mask ? -1 : aa_scene_layer_group(s, l); g >= 0;
             g = aa_scene_group_parent(s, g))
            chain[n++] = g;
        int keep = 0;
        while (keep < depth && keep < n && open[keep] == chain[n - 1 - keep])
            keep++;
        for (; depth > keep; depth--)
            fputs("</g>\n", f);
        for (; depth < n; depth++) {
            open[depth] = chain[n - 1 - depth];
            fprintf(f, "<g opacity=\"%.17g\">\n", aa_scene_group_opacity(s, open[depth]));
        }
        const double alpha = mask ? 1 : aa_scene_layer_alpha(s, l);
        int k = aa_scene_layer_stroked(s, l), clip = aa_scene_layer_clip(s, l);
        if (k >= 0) {
            if (clip >= 0)
                fprintf(f, "<g clip-path=\"url(#clip%d)\">\n", clip);
            put_stroke(f, &src[k], l, mask ? white : aa_scene_layer_colour(s, l), alpha);
            if (clip >= 0)
                fputs("</g>\n", f);
            continue;
        }
        fprintf(f, "<path id=\"layer%d\" fill=\"", l);
        put_colour(f, mask ? white : aa_scene_layer_colour(s, l));
        if (alpha < 1)
            fprintf(f, "\" fill-opacity=\"%.17g", alpha);
        fprintf(f, "\" fill-rule=\"%s\"",
                aa_scene_layer_rule(s, l) == AA_FILL_EVENODD ? "evenodd" : "nonzero");
        if (clip >= 0)
            fprintf(f, " clip-path=\"url(#clip%d)\"", clip);
        fputs(" d=\"", f);
        put_layer_data(f, s, l);
        fputs("\"/>\n", f);
    }
    for (; depth > 0; depth--)
        fputs("</g>\n", f);
    fputs("</svg>\n", f);
}

int aa_scene_svg(const aa_scene *placed, int w, int h, aa_svg_paint paint, const char *desc,
                 char **text, size_t *len)
{
    *text = NULL;
    *len = 0;
    const aa_field_type *field = aa_scene_field(placed, NULL, NULL, NULL);
    if (field)
        return aa_fail(AA_EINVAL,
                       "the scene is the procedural field %s: it has no paths to write as SVG "
                       "(every pattern of paths can be written)",
                       field->name);
    if (w < 1 || h < 1)
        return aa_fail(AA_EINVAL, "SVG of a %dx%d image", w, h);
    if (aa_scene_has_gradients(placed))
        return aa_fail(AA_EINVAL, "the scene has gradient paint, which this writer does not "
                                  "write (its layers are written as colours)");
    size_t ne;
    const aa_edge *e = aa_scene_edges(placed, &ne);
    /* a stroke's layer is written as the stroke (its source), so only a
     * layer of offset curves that is not one cannot be written */
    for (size_t k = 0; k < ne; k++)
        if (e[k].quad == 4 && aa_scene_layer_stroked(placed, e[k].layer) < 0)
            return aa_fail(AA_EINVAL, "the scene has the exact offset curves of a stroke "
                                      "(edge %zu) in a layer that is not kept as a stroke, "
                                      "which SVG path data cannot write",
                           k);
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, "SVG");
    if (st)
        return st;
    char *buf = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&buf, &n);
    if (!f) {
        aa__c_numbers_end(&numbers);
        return aa_fail(AA_ENOMEM, "out of memory for the SVG");
    }
    put_document(f, placed, w, h, paint, desc);
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    aa__c_numbers_end(&numbers);
    if (bad) {
        free(buf);
        return aa_fail(AA_ENOMEM, "out of memory for the SVG");
    }
    *text = buf;
    *len = n;
    return AA_OK;
}

int aa_scene_svg_write(const char *path, const aa_scene *placed, int w, int h,
                       aa_svg_paint paint, const char *desc)
{
    char *text;
    size_t n;
    int st = aa_scene_svg(placed, w, h, paint, desc, &text, &n);
    if (st)
        return st;
    st = aa_file_write_atomic(path, text, n);
    free(text);
    return st;
}
