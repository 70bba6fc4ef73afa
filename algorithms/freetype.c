/*
 * freetype.c: FreeType's smooth rasterizer as a peer (FreeType 2,
 * src/smooth/ftgrays.c, reached through FT_Outline_Render).
 *
 * The rasterizer follows the same idea as our area method and as Crow's
 * "Left Areas - Right Areas = Area" (Crow 1976, ch. 3, fig. 3.13): every
 * edge adds a signed `area` to the cells it crosses and a `cover` to the
 * cell after, resolved in one sweep along the row.  It works in fixed point
 * and flattens curves: the outline is given in 26.6 (positions rounded to
 * 1/64 pixel), conic (quadratic) arcs are split into lines (ftgrays.c's
 * gray_render_conic, by a deviation bound), and the coverage of a pixel is
 * reported as 0 .. 255.  Our image receives coverage / 255 per pixel through
 * the direct-rendering callback (FT_RASTER_FLAG_DIRECT, gray_spans), mixed
 * between the background and the layer's grey.
 *
 * The outline is the placed scene's: one contour per path, lines as
 * on-curve points, quadratic arcs as a conic control point
 * (FT_CURVE_TAG_CONIC) and an on-curve end, cubic arcs as their two cubic
 * control points (FT_CURVE_TAG_CUBIC) and an on-curve end (FreeType
 * flattens them itself); FreeType's outlines have no elliptical arcs, so
 * each is given as at most four cubics of at most 90 degrees each
 * (aa_peer_arc_cubics, peer.h: within 2.7e-4 of the ellipse's longer
 * semi-axis, outside it), flattened in turn; the layer's even-odd rule sets
 * FT_OUTLINE_EVEN_ODD_FILL.  It is built once in init.
 *
 * Tiles.  FreeType 2.12's cell pool is small and fixed; a band of rows that
 * overflows it is halved in y, but a single row crossed by thousands of
 * edges still overflows (Raster_Overflow; crow's default 96 arcs fit, 4000
 * arcs 4096 px wide need tiles of 512 columns).  Its own
 * documentation allows a clip box for direct rendering (FT_RASTER_FLAG_CLIP,
 * clip_box in integer pixels): the image is rendered in bands of BAND rows,
 * each split into vertical tiles by halving its width on every overflow
 * (the width that worked is remembered per band).  Cells left of a clip box
 * carry their cover into it, so a pixel's coverage is the same in any tile:
 * the image does not depend on the tiling or the thread count.  Bands run
 * in parallel, one FT_Library per thread (FreeType's rule: a library is not
 * shared between threads).
 *
 * Strokes (aa_scene_stroke): FreeType's stroker (FT_Stroker, ftstroke.c)
 * works in the outline's pixel space with one radius and has no dashes.
 * When every stroke of the scene is undashed and mapped by a similarity
 * (a rotation or reflection times a scale k: then stroking the mapped path
 * with width k w is the mapped stroke, as SVG defines it), each source's
 * path is mapped to pixels and given to FT_Stroker (lines, conics, cubics,
 * arcs as aa_peer_arc_cubics' cubics; FT_STROKER_LINEJOIN_MITER_FIXED for
 * SVG's miter, a bevel past the limit), which offsets each curve by
 * cubics it fits itself, draws round joins and caps as arcs of cubics, and
 * the outlines of all strokes, wound alike, are rendered as one non-zero
 * outline; SVG 2's miter-clip is FT_STROKER_LINEJOIN_MITER_VARIABLE.
 * Otherwise (a dashed stroke, a non-uniform or sheared map, or SVG 2's
 * arcs join, which FT_Stroker cannot draw as SVG says) the scene's exact
 * outlines are filled as any outline, stated here rather than
 * approximated otherwise.
 *
 * Painted (peer.h): any other scene (colour, several layers, translucency,
 * groups of opacity, clips) is painted layer by layer: each layer's own
 * outline (its contours under its rule; a stroke by FT_Stroker when it can
 * draw it as above, else its exact outline) built in init, rendered per
 * band with its spans written as coverage bytes into the thread's BAND x W
 * buffer (ft_cover), then composited over the layers behind
 * (aa_peer_paint_band): a clip's members rendered so too, as the clip's
 * mask multiplied into the coverage of the layers it gates, and a group's
 * layers into the group's buffer, composited with its opacity.
 *
 * Limits: grey scenes of one layer or of strokes of one grey, or painted
 * layer by layer (peer.h), and the box filter only; 8-bit coverage (an error of up to 1/510 from rounding alone);
 * positions rounded to 1/64 px; arcs flattened; at most 32767 points and
 * contours (FT_Outline counts in shorts) and coordinates within 2^17 px:
 * larger scenes are refused.  Nonzero coverage is |accumulated area|
 * clamped to 1, which differs from exact nonzero coverage where contours
 * overlap inside a pixel.
 */
#include "methods.h"
#include "path.h"
#include "peer.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include FT_STROKER_H

#define BAND 32            /* rows per parallel band */
#define FT_MAX_COORD 131072.0 /* px: the smooth rasterizer fails beyond about 2^18 */

typedef struct ft_state {
    aa_peer_scene ps;
    FT_Outline outline;
    FT_Library *lib; /* one per thread */
    int nlib;
    int *strip; /* per band: tile width that rendered without overflow */
    int nbands;
    /* painted (peer.h): each layer's outline, and one BAND x W coverage
     * buffer per thread */
    int painted, nlayers;
    FT_Outline *lo;
    unsigned char **cov;
    aa_peer_painter **pp; /* one per thread */
} ft_state;

typedef struct ft_target {
    aa_image *out;
    const aa_peer_scene *ps;
    int x0, x1, y0, y1; /* the tile: pixels [x0, x1) x [y0, y1) */
    unsigned char *cov;  /* painted: coverage of rows y0 .. y1 - 1, out->w bytes each */
} ft_target;

static const aa_param ft_params[] = {{0}};

static int ft_check(const double *p, const aa_filter *f)
{
    (void)p;
    return aa_peer_check_filter("freetype", f);
}

static void ft_release(void *state)
{
    ft_state *s = state;
    for (int k = 0; k < s->nlib; k++)
        if (s->lib[k])
            FT_Done_FreeType(s->lib[k]);
    free(s->lib);
    free(s->strip);
    free(s->outline.points);
    free(s->outline.tags);
    free(s->outline.contours);
    for (int l = 0; s->lo && l < s->nlayers; l++) {
        free(s->lo[l].points);
        free(s->lo[l].tags);
        free(s->lo[l].contours);
    }
    free(s->lo);
    for (int k = 0; s->cov && k < s->nlib; k++)
        free(s->cov[k]);
    free(s->cov);
    for (int k = 0; s->pp && k < s->nlib; k++)
        aa_peer_painter_free(s->pp[k]);
    free(s->pp);
    s->lo = NULL, s->cov = NULL, s->pp = NULL, s->nlayers = 0;
    s->lib = NULL, s->strip = NULL, s->nlib = 0;
    s->outline.points = NULL, s->outline.tags = NULL, s->outline.contours = NULL;
}

static FT_Pos to26_6(double v) { return (FT_Pos)lround(v * 64.0); }

/* Points an edge adds after its start: controls and the end. */
static size_t ft_edge_points(const aa_edge *e)
{
    if (e->quad == 3) {
        double c[AA_PEER_ARC_CUBICS][6];
        return 3 * (size_t)aa_peer_arc_cubics(e, c);
    }
    return e->quad == 2 ? 3 : e->quad ? 2 : 1;
}

/* Append point (x, y) px with `tag`, refusing coordinates beyond 26.6's
 * range here. */
static int ft_put(FT_Outline *o, int *n, double x, double y, char tag)
{
    if (!(fabs(x) <= FT_MAX_COORD && fabs(y) <= FT_MAX_COORD))
        return aa_fail(AA_EINVAL,
                       "freetype: a point (%.17g, %.17g) px is beyond the %.0f px that 26.6 "
                       "fixed point keeps here",
                       x, y, FT_MAX_COORD);
    o->points[*n] = (FT_Vector){to26_6(x), to26_6(y)};
    o->tags[(*n)++] = tag;
    return AA_OK;
}

/* Edge e's controls (FreeType's conic or cubic tags) and its end, the end
 * left out when it is the contour's first point again (the contour closes
 * itself). */
static int ft_put_edge(FT_Outline *o, int *n, int first, const aa_edge *e, int last)
{
    int st = AA_OK;
    double c[AA_PEER_ARC_CUBICS][6];
    if (e->quad == 3) { /* cubics (peer.h): FreeType's outline has no arcs */
        int m = aa_peer_arc_cubics(e, c);
        for (int q = 0; q + 1 < m && !st; q++)
            if (!(st = ft_put(o, n, c[q][0], c[q][1], FT_CURVE_TAG_CUBIC)) &&
                !(st = ft_put(o, n, c[q][2], c[q][3], FT_CURVE_TAG_CUBIC)))
                st = ft_put(o, n, c[q][4], c[q][5], FT_CURVE_TAG_ON);
        if (!st && !(st = ft_put(o, n, c[m - 1][0], c[m - 1][1], FT_CURVE_TAG_CUBIC)))
            st = ft_put(o, n, c[m - 1][2], c[m - 1][3], FT_CURVE_TAG_CUBIC);
    } else if (e->quad == 2) { /* FreeType's cubic: two cubic control points */
        if (!(st = ft_put(o, n, e->cx, e->cy, FT_CURVE_TAG_CUBIC)))
            st = ft_put(o, n, e->c2x, e->c2y, FT_CURVE_TAG_CUBIC);
    } else if (e->quad) {
        st = ft_put(o, n, e->cx, e->cy, FT_CURVE_TAG_CONIC);
    }
    if (st)
        return st;
    FT_Vector end = {to26_6(e->x1), to26_6(e->y1)};
    if (last && end.x == o->points[first].x && end.y == o->points[first].y)
        return AA_OK;
    return ft_put(o, n, e->x1, e->y1, FT_CURVE_TAG_ON);
}

/* The outline of layer `layer`'s contours (-1: every contour) under
 * `rule`, into *o (its arrays allocated here). */
static int ft_build_outline(FT_Outline *o, const aa_scene *scene, int layer, aa_fill_rule rule)
{
    size_t nedges, ncont;
    const aa_edge *e = aa_scene_edges(scene, &nedges);
    const size_t *start = aa_scene_contours(scene, &ncont);
    /* at most: a start point, then each edge's controls and end */
    size_t cap = 0, nsel = 0;
    for (size_t c = 0; c < ncont && cap <= 32767; c++) {
        if (layer >= 0 && (start[c] == start[c + 1] || e[start[c]].layer != layer))
            continue;
        nsel++, cap++;
        for (size_t k = start[c]; k < start[c + 1] && cap <= 32767; k++)
            cap += ft_edge_points(&e[k]);
    }
    if (nsel > 32767 || cap > 32767)
        return aa_fail(AA_EINVAL,
                       "freetype: the scene has %zu paths and more than 32767 outline points "
                       "(%zu so far); FreeType's outline takes at most 32767 of each",
                       nsel, cap);
    o->points = malloc((cap ? cap : 1) * sizeof *o->points);
    o->tags = malloc(cap ? cap : 1);
    o->contours = malloc((nsel ? nsel : 1) * sizeof *o->contours);
    if (!o->points || !o->tags || !o->contours)
        return aa_fail(AA_ENOMEM, "freetype: out of memory for the outline");
    int n = 0, nc = 0, st = AA_OK;
    for (size_t c = 0; c < ncont && !st; c++) {
        size_t a = start[c], b = start[c + 1];
        if (a == b || (layer >= 0 && e[a].layer != layer))
            continue;
        int first = n;
        st = ft_put(o, &n, e[a].x0, e[a].y0, FT_CURVE_TAG_ON);
        for (size_t k = a; k < b && !st; k++)
            st = ft_put_edge(o, &n, first, &e[k], k + 1 == b);
        o->contours[nc++] = (short)(n - 1);
    }
    o->n_points = (short)n;
    o->n_contours = (short)nc;
    o->flags = rule == AA_FILL_EVENODD ? FT_OUTLINE_EVEN_ODD_FILL : FT_OUTLINE_NONE;
    return st;
}

/* ---- strokes by FT_Stroker ---- */

/* FT_Stroker works in the outline's (device) space with one radius: it
 * strokes a source exactly as SVG asks only when the source's map is a
 * similarity (its columns orthogonal and of equal length: a rotation or
 * reflection times a scale k), where the stroke of the mapped path with
 * width k w is the mapped stroke; and it has no dashes, nor SVG 2's arcs
 * join (its miter-clip is FT_STROKER_LINEJOIN_MITER_VARIABLE: past the
 * limit the miter cut perpendicular to the bisector at the limit times the
 * radius from the vertex, ftstroke.c's ft_stroker_outside). */
static int ft_strokable(const aa_stroke_source *a)
{
    const double *m = a->m;
    const double c0 = m[0] * m[0] + m[1] * m[1], c1 = m[2] * m[2] + m[3] * m[3];
    const double dot = m[0] * m[2] + m[1] * m[3];
    return a->style.ndash == 0 && a->style.join <= AA_JOIN_MITER_CLIP &&
           fabs(c0 - c1) <= 1e-12 * (c0 + c1) && fabs(dot) <= 1e-12 * (c0 + c1);
}

static FT_Vector ft_map(const double *m, double x, double y)
{
    return (FT_Vector){to26_6(m[0] * x + m[2] * y + m[4]), to26_6(m[1] * x + m[3] * y + m[5])};
}

/* The source's path, mapped to pixels, given to the stroker: lines,
 * conics, cubics, each circular arc as the cubics of aa_peer_arc_cubics
 * (peer.h: at most 90 degrees each, within 2.7e-4 of the radius). */
static FT_Error ft_stroke_path(FT_Stroker k, const aa_stroke_source *a)
{
    const double *m = a->m;
    FT_Error err = 0;
    int open = 0;
    double px = 0, py = 0;
    for (size_t i = 0; i < a->path.n && !err; i++) {
        const aa_path_seg *g = &a->path.seg[i];
        const double *q = g->p;
        if (g->op == AA_PATH_MOVE) {
            if (open)
                err = FT_Stroker_EndSubPath(k);
            /* open unless the subpath ends with a close */
            size_t j = i + 1;
            while (j < a->path.n && a->path.seg[j].op != AA_PATH_MOVE &&
                   a->path.seg[j].op != AA_PATH_CLOSE)
                j++;
            int closed = j < a->path.n && a->path.seg[j].op == AA_PATH_CLOSE;
            FT_Vector v = ft_map(m, q[0], q[1]);
            if (!err)
                err = FT_Stroker_BeginSubPath(k, &v, !closed);
            open = 1, px = q[0], py = q[1];
            continue;
        }
        if (g->op == AA_PATH_CLOSE) {
            err = FT_Stroker_EndSubPath(k); /* draws the line back to the start */
            open = 0;
            continue;
        }
        if (g->op == AA_PATH_LINE) {
            FT_Vector v = ft_map(m, q[0], q[1]);
            err = FT_Stroker_LineTo(k, &v);
            px = q[0], py = q[1];
        } else if (g->op == AA_PATH_QUAD) {
            FT_Vector c = ft_map(m, q[0], q[1]), v = ft_map(m, q[2], q[3]);
            err = FT_Stroker_ConicTo(k, &c, &v);
            px = q[2], py = q[3];
        } else if (g->op == AA_PATH_CUBIC) {
            FT_Vector c1 = ft_map(m, q[0], q[1]), c2 = ft_map(m, q[2], q[3]);
            FT_Vector v = ft_map(m, q[4], q[5]);
            err = FT_Stroker_CubicTo(k, &c1, &c2, &v);
            px = q[4], py = q[5];
        } else { /* an arc, mapped to pixels as aa_path_fill maps it */
            aa_edge e = {0};
            e.x0 = m[0] * px + m[2] * py + m[4], e.y0 = m[1] * px + m[3] * py + m[5];
            e.cx = m[0] * q[0] + m[2] * q[1] + m[4], e.cy = m[1] * q[0] + m[3] * q[1] + m[5];
            e.ux = m[0] * q[2] + m[2] * q[3], e.uy = m[1] * q[2] + m[3] * q[3];
            e.vx = m[0] * q[4] + m[2] * q[5], e.vy = m[1] * q[4] + m[3] * q[5];
            e.t0 = q[6], e.t1 = q[7], e.quad = 3;
            e.x1 = m[0] * q[8] + m[2] * q[9] + m[4], e.y1 = m[1] * q[8] + m[3] * q[9] + m[5];
            double c[AA_PEER_ARC_CUBICS][6];
            int n = aa_peer_arc_cubics(&e, c);
            for (int r = 0; r < n && !err; r++) {
                FT_Vector c1 = {to26_6(c[r][0]), to26_6(c[r][1])};
                FT_Vector c2 = {to26_6(c[r][2]), to26_6(c[r][3])};
                FT_Vector v = {to26_6(c[r][4]), to26_6(c[r][5])};
                err = FT_Stroker_CubicTo(k, &c1, &c2, &v);
            }
            px = q[8], py = q[9];
        }
    }
    if (open && !err)
        err = FT_Stroker_EndSubPath(k);
    return err;
}

/* Append `add` to *o (grown), its orientation made `*want`'s (the
 * first stroke's): FT_Stroker's borders of one stroke wind one way (a
 * closed subpath's inner border the other way round inside it), so with
 * every stroke wound alike no two strokes' windings cancel under the
 * non-zero rule. */
static int ft_append(FT_Outline *o, FT_Outline *add, FT_Orientation *want)
{
    FT_Orientation got = FT_Outline_Get_Orientation(add);
    if (*want == FT_ORIENTATION_NONE)
        *want = got;
    else if (got != FT_ORIENTATION_NONE && got != *want)
        FT_Outline_Reverse(add);
    const int np = o->n_points + add->n_points, nc = o->n_contours + add->n_contours;
    if (np > 32767 || nc > 32767)
        return aa_fail(AA_EINVAL, "freetype: the strokes' outlines have more than 32767 points "
                                  "or contours, which FreeType's outline cannot hold");
    FT_Vector *pts = realloc(o->points, (size_t)(np ? np : 1) * sizeof *pts);
    if (pts)
        o->points = pts;
    char *tags = realloc(o->tags, (size_t)(np ? np : 1));
    if (tags)
        o->tags = tags;
    short *cont = realloc(o->contours, (size_t)(nc ? nc : 1) * sizeof *cont);
    if (cont)
        o->contours = cont;
    if (!pts || !tags || !cont)
        return aa_fail(AA_ENOMEM, "freetype: out of memory for the strokes' outline");
    memcpy(o->points + o->n_points, add->points, (size_t)add->n_points * sizeof *pts);
    memcpy(o->tags + o->n_points, add->tags, (size_t)add->n_points);
    for (int c = 0; c < add->n_contours; c++)
        o->contours[o->n_contours + c] = (short)(add->contours[c] + o->n_points);
    o->n_points = (short)np;
    o->n_contours = (short)nc;
    return AA_OK;
}

/* The outline of every stroke by FT_Stroker (radius k w/2 in 26.6, SVG's
 * joins: MITER_FIXED is the miter that becomes a bevel past the limit,
 * PostScript's and SVG's), one non-zero outline into *o; only source
 * `only` if it is not -1. */
static int ft_stroke_outline(FT_Outline *o, const aa_scene *scene, FT_Library lib, int only)
{
    static const FT_Stroker_LineJoin joins[] = {FT_STROKER_LINEJOIN_MITER_FIXED,
                                                FT_STROKER_LINEJOIN_ROUND,
                                                FT_STROKER_LINEJOIN_BEVEL,
                                                FT_STROKER_LINEJOIN_MITER_VARIABLE};
    static const FT_Stroker_LineCap caps[] = {FT_STROKER_LINECAP_BUTT, FT_STROKER_LINECAP_ROUND,
                                              FT_STROKER_LINECAP_SQUARE};
    size_t nsrc;
    const aa_stroke_source *src = aa_scene_stroke_sources(scene, &nsrc);
    FT_Orientation want = FT_ORIENTATION_NONE;
    FT_Stroker k;
    if (FT_Stroker_New(lib, &k))
        return aa_fail(AA_ENOMEM, "freetype: FT_Stroker_New failed");
    memset(o, 0, sizeof *o);
    int st = AA_OK;
    for (size_t i = 0; i < nsrc && !st; i++) {
        if (only >= 0 && i != (size_t)only)
            continue;
        const aa_stroke_source *a = &src[i];
        const double *m = a->m;
        const double scale = sqrt(fabs(m[0] * m[3] - m[1] * m[2]));
        FT_Stroker_Set(k, to26_6(a->style.width * scale / 2), caps[a->style.cap],
                       joins[a->style.join], (FT_Fixed)lround(a->style.miterlimit * 65536.0));
        FT_UInt np, nc;
        FT_Outline out;
        if (ft_stroke_path(k, a) || FT_Stroker_GetCounts(k, &np, &nc))
            st = aa_fail(AA_EFAIL, "freetype: FT_Stroker failed on stroke %zu", i);
        else if (np > 32767 || nc > 32767)
            st = aa_fail(AA_EINVAL, "freetype: a stroke's outline has more than 32767 points");
        else if (FT_Outline_New(lib, np, nc, &out))
            st = aa_fail(AA_ENOMEM, "freetype: out of memory for a stroke's outline");
        else {
            out.n_points = out.n_contours = 0;
            FT_Stroker_Export(k, &out);
            st = ft_append(o, &out, &want);
            FT_Outline_Done(lib, &out);
        }
        FT_Stroker_Rewind(k);
    }
    FT_Stroker_Done(k);
    o->flags = FT_OUTLINE_NONE; /* non-zero */
    return st;
}

/* Painted (peer.h): each layer's outline, a stroke's by FT_Stroker when
 * it can draw it as SVG says (ft_strokable), else the layer's exact
 * outline (offset curves refused), a fill's its contours under its rule;
 * and each thread's band of coverage. */
static int ft_init_painted(ft_state *s, const aa_scene *scene, int w)
{
    size_t nsrc, ne;
    const aa_stroke_source *src = aa_scene_stroke_sources(scene, &nsrc);
    const aa_edge *e = aa_scene_edges(scene, &ne);
    s->nlayers = aa_scene_layer_count(scene);
    s->lo = calloc((size_t)(s->nlayers ? s->nlayers : 1), sizeof *s->lo);
    s->cov = calloc((size_t)s->nlib, sizeof *s->cov);
    s->pp = calloc((size_t)s->nlib, sizeof *s->pp);
    if (!s->lo || !s->cov || !s->pp)
        return aa_fail(AA_ENOMEM, "freetype: out of memory");
    for (int k = 0; k < s->nlib; k++)
        if (!(s->cov[k] = malloc((size_t)BAND * (size_t)w)))
            return aa_fail(AA_ENOMEM, "freetype: out of memory");
    int st = AA_OK;
    for (int k = 0; k < s->nlib && !st; k++)
        st = aa_peer_painter_new("freetype", scene, w, BAND, NULL, &s->pp[k]);
    for (int l = 0; l < s->nlayers && !st; l++) {
        int k = aa_scene_layer_stroked(scene, l);
        if (k >= 0 && (size_t)k < nsrc && ft_strokable(&src[k])) {
            st = ft_stroke_outline(&s->lo[l], scene, s->lib[0], k);
            continue;
        }
        for (size_t q = 0; q < ne && !st; q++)
            if (e[q].quad == 4 && e[q].layer == l)
                st = aa_fail(AA_EINVAL,
                             "freetype: layer %d is a stroke FT_Stroker cannot draw as SVG "
                             "says (dashed, mapped other than by a similarity, or joined by "
                             "arcs), and its exact outline has the offset curves of a Bezier "
                             "arc, which FreeType's outline cannot hold",
                             l);
        if (!st)
            st = ft_build_outline(&s->lo[l], scene, l, aa_scene_layer_rule(scene, l));
    }
    return st;
}

static int ft_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    ft_state *s = state;
    int st = aa_peer_scene_read("freetype", job, &s->ps);
    /* strokes: FT_Stroker when it can draw every one of them as SVG says,
     * else the scene's exact outlines filled (freetype.c's header) */
    int stroker = 0;
    if (!st && s->ps.strokes) {
        size_t nsrc;
        const aa_stroke_source *src = aa_scene_stroke_sources(job->placed, &nsrc);
        stroker = 1;
        for (size_t k = 0; k < nsrc; k++)
            stroker &= ft_strokable(&src[k]);
    }
    if (!st && !stroker && s->ps.strokes)
        st = aa_peer_refuse_offsets("freetype", job->placed);
    if (st == AA_EINVAL && aa_peer_paintable(job->placed)) {
        /* painted (peer.h): offsets refused in the layers filled below */
        st = aa_peer_painted_check("freetype", job->placed, 0);
        s->painted = 1;
    } else if (!st && !stroker) {
        st = ft_build_outline(&s->outline, job->placed, -1, s->ps.rule);
    }
    if (!st) {
        s->nlib = job->threads > 0 ? job->threads : 1;
        s->nbands = (job->h + BAND - 1) / BAND;
        s->lib = calloc((size_t)s->nlib, sizeof *s->lib);
        s->strip = malloc((size_t)s->nbands * sizeof *s->strip);
        if (!s->lib || !s->strip)
            st = aa_fail(AA_ENOMEM, "freetype: out of memory");
        for (int k = 0; k < s->nbands && !st; k++)
            s->strip[k] = job->w;
        for (int k = 0; k < s->nlib && !st; k++)
            if (FT_Init_FreeType(&s->lib[k]))
                st = aa_fail(AA_EFAIL, "freetype: FT_Init_FreeType failed");
    }
    if (!st && stroker)
        st = ft_stroke_outline(&s->outline, job->placed, s->lib[0], -1);
    if (!st && s->painted)
        st = ft_init_painted(s, job->placed, job->w);
    if (st)
        ft_release(s);
    return st;
}

static void ft_spans(int y, int count, const FT_Span *spans, void *user)
{
    const ft_target *t = user;
    if (y < t->y0 || y >= t->y1)
        return;
    for (int k = 0; k < count; k++) {
        int i0 = spans[k].x, i1 = spans[k].x + spans[k].len;
        if (i0 < t->x0)
            i0 = t->x0;
        if (i1 > t->x1)
            i1 = t->x1;
        if (t->cov && i0 < i1)
            memset(t->cov + (size_t)(y - t->y0) * (size_t)t->out->w + (size_t)i0,
                   spans[k].coverage, (size_t)(i1 - i0));
        else if (i0 < i1)
            aa_peer_fill(t->out, y, i0, i1, aa_peer_mix(t->ps, spans[k].coverage / 255.0));
    }
}

/* Render outline o on pixels [x0, x1) x [y0, y1) in tiles of at most
 * *width columns, halving *width on overflow: into out (the grey path) or,
 * if cov is not NULL, as coverage bytes into cov (rows y0 .. y1 - 1). */
static int ft_band(ft_state *s, FT_Library lib, FT_Outline *o, aa_image *out, unsigned char *cov,
                   int y0, int y1, int *width)
{
    int x0 = 0;
    while (x0 < out->w) {
        int x1 = x0 + *width < out->w ? x0 + *width : out->w;
        ft_target t = {out, &s->ps, x0, x1, y0, y1, cov};
        FT_Raster_Params rp = {0};
        rp.source = o;
        rp.flags = FT_RASTER_FLAG_AA | FT_RASTER_FLAG_DIRECT | FT_RASTER_FLAG_CLIP;
        rp.gray_spans = ft_spans;
        rp.user = &t;
        rp.clip_box = (FT_BBox){x0, y0, x1, y1};
        FT_Error err = FT_Outline_Render(lib, o, &rp);
        if (err == FT_Err_Raster_Overflow && *width > 1) {
            *width = (*width + 1) / 2; /* rows already swept are rewritten alike */
            continue;
        }
        if (err)
            return err == FT_Err_Raster_Overflow ? AA_EINVAL : AA_EFAIL;
        x0 = x1;
    }
    return AA_OK;
}

/* Painted (peer.h): FreeType's coverage of layer l on the band's rows,
 * into the thread's coverage buffer (NULL for a layer of no outline). */
typedef struct ft_cover_ctx {
    ft_state *s;
    FT_Library lib;
    aa_image *out;
    unsigned char *cov;
    int *width;
} ft_cover_ctx;

static int ft_cover(void *vctx, int layer, int y0, int rows, const unsigned char **cov,
                    size_t *stride)
{
    const ft_cover_ctx *c = vctx;
    FT_Outline *o = &c->s->lo[layer];
    *cov = NULL;
    *stride = (size_t)c->out->w;
    if (!o->n_points)
        return AA_OK;
    memset(c->cov, 0, (size_t)rows * (size_t)c->out->w);
    *cov = c->cov;
    return ft_band(c->s, c->lib, o, c->out, c->cov, y0, y0 + rows, c->width);
}

static int ft_render(void *state, const double *p, const aa_job *job, aa_image *out,
                     aa_counters *counters)
{
    (void)p;
    ft_state *s = state;
    int status = AA_OK;
    counters->samples = 0;
    counters->expensive_pixels = 0;
#pragma omp parallel num_threads(s->nlib)
    {
        FT_Library lib = s->lib[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < s->nbands; b++) {
            int y0 = b * BAND, y1 = y0 + BAND < job->h ? y0 + BAND : job->h;
            if (s->painted) { /* back to front (peer.h) */
                ft_cover_ctx c = {s, lib, out, s->cov[omp_get_thread_num()], &s->strip[b]};
                int st = aa_peer_paint_band(s->pp[omp_get_thread_num()], job->placed, ft_cover,
                                            NULL, &c, out, y0, y1 - y0);
                if (st) {
#pragma omp atomic write
                    status = st;
                }
                continue;
            }
            for (int j = y0; j < y1; j++)
                aa_peer_fill(out, j, 0, job->w, s->ps.bg);
            if (!s->ps.layers || !s->outline.n_points)
                continue;
            int st = ft_band(s, lib, &s->outline, out, NULL, y0, y1, &s->strip[b]);
            if (st) {
#pragma omp atomic write
                status = st;
            }
        }
    }
    if (status == AA_EINVAL)
        return aa_fail(AA_EINVAL, "freetype: the rasterizer's cell pool overflows even on "
                                  "one-pixel-wide tiles: too many edges in one pixel column");
    if (status)
        return aa_fail(status, "freetype: FT_Outline_Render failed");
    return AA_OK;
}

const aa_method_type aa_method_freetype = {
    {"freetype", "peer: FreeType's smooth rasterizer (8-bit coverage, 26.6 outline)",
     ft_params},
    sizeof(ft_state),
    AA_METHOD_SOME_SCENES,
    ft_check,
    ft_init,
    ft_render,
    ft_release};
