/*
 * cairo.c: Cairo's image-surface fill as a peer (cairo_fill on an A8 image
 * surface, Cairo 1.16's image backend and its scan converters).
 *
 * The scene's one layer is one Cairo path: lines as line_to, each quadratic
 * arc as the cubic Bezier that is the same curve (degree elevation, exact:
 * control points p0 + 2/3 (c - p0) and p1 + 2/3 (c - p1)), each cubic arc
 * as itself (curve_to), each elliptical arc as Cairo's own arc (cairo_arc
 * or cairo_arc_negative of the unit circle under the affine map that takes
 * it to the ellipse, cairo_put_arc: Cairo replaces it by cubics of at most
 * 180 degrees each, as many as its table of the cubic's error for the
 * transformed circle's major axis needs to stay within `tolerance`, so
 * 90-degree pieces or shorter for radii above 0.1/0.0185 = 5.4 px at the
 * default), every path closed.  Cairo flattens
 * curves to `tolerance` (px, Cairo's default 0.1)
 * and converts the polygon to coverage with the scan converter `aa` selects
 * (CAIRO_ANTIALIAS_BEST, GOOD or FAST: Cairo chooses the grid of each;
 * 1.16's image backend gives BEST and GOOD the same image on crow); the
 * A8 surface keeps coverage as 8 bits.  The fill rule is the layer's
 * (CAIRO_FILL_RULE_WINDING or EVEN_ODD).  Our image receives alpha / 255,
 * mixed between the background and the layer's grey (peer.h).
 *
 * Tiles: bands of BAND rows, each filled into its thread's BAND x W A8
 * surface through a translation, so memory is O(width) per thread and bands
 * run in parallel; the path is built once in init and appended per band.
 * A row's coverage does not depend on its band: Cairo's converters work row
 * by row (the translation is by whole pixels, exact in its 24.8 fixed
 * point).
 *
 * Strokes: a layer kept as a stroke (aa_scene_stroke) is stroked by Cairo
 * itself from its source (cairo_stroke_source: the path under the
 * source's map, cairo_stroke with its width, join, cap, miter limit and
 * dashes), not filled from our outline; several strokes of one grey are
 * painted in turn, OVER each other (peer.h).
 *
 * Painted: a scene of colour, of several layers, translucent, with groups
 * of opacity or clipped is painted layer by layer, Cairo's coverage of
 * each composited over the layers behind (cairo_init_painted, cairo_cover,
 * aa_peer_paint_band: peer.h): layers sharing an edge show the background
 * through their seam, as every renderer that uses coverage as alpha.  A
 * layer gated by a clip that is an intersection of paths is clipped by
 * Cairo itself (cairo_clip: cairo_clips, below); one gated by a union of
 * several members takes the clip's mask (peer.h).  Groups of opacity are
 * composited by peer.h's buffers, not by cairo_push_group: this peer's
 * surfaces hold coverage only (A8), and every colour is composited outside
 * Cairo in double precision, as for layers, where a group of Cairo's own
 * would be an ARGB32 surface of 8-bit colour in the scene's encoded values
 * (colour rounding besides the coverage measured here).
 *
 * Limits: the box filter only; 8-bit
 * coverage (up to 1/510 from rounding); positions in 24.8 fixed point
 * (1/256 px) and coordinates within Cairo's fixed-point range (about
 * 2^23 px, larger scenes are refused); curves flattened; fast (no
 * antialiasing) is point sampling by Cairo's own rule.
 */
#include "methods.h"
#include "peer.h"
#include "path.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cairo.h>

#define BAND 64 /* rows per band */
#define CAIRO_MAX_COORD 4194304.0 /* px */

enum { AA, TOLERANCE };
enum { AA_BEST, AA_GOOD, AA_FAST };

static const aa_param cairo_params[] = {
    {"aa", AA_PARAM_CHOICE, AA_BEST, 0, 0, 0, "best|good|fast",
     "Cairo's antialias mode (CAIRO_ANTIALIAS_BEST, GOOD, FAST)"},
    {"tolerance", AA_PARAM_REAL, 0.1, 0.0, 100.0, 1, NULL,
     "curve flattening tolerance in pixels (Cairo's default 0.1)"},
    {0}};

typedef struct cairo_state {
    aa_peer_scene ps;
    cairo_path_t *path;
    cairo_surface_t **surf; /* one BAND x W A8 surface per thread */
    int nsurf;
    double lut[256];
    /* painted (scenes of colour, several layers or translucency): each
     * layer's path (NULL for a stroke, stroked from its source) */
    int painted, nlayers;
    cairo_path_t **lpath;
    aa_peer_painter **pp; /* one per thread */
    unsigned char *own;   /* per layer: clipped by Cairo itself (cairo_clips) */
    /* gradient paint (cairo_shade): per thread a BAND x W ARGB32 surface
     * and the paint as floats (peer.h) */
    cairo_surface_t **gsurf;
    float **paint;
} cairo_state;

static int cairo_check(const double *p, const aa_filter *f)
{
    (void)p;
    return aa_peer_check_filter("cairo", f);
}

static void cairo_release(void *state)
{
    cairo_state *s = state;
    for (int k = 0; k < s->nsurf; k++)
        if (s->surf[k])
            cairo_surface_destroy(s->surf[k]);
    free(s->surf);
    if (s->path)
        cairo_path_destroy(s->path);
    for (int l = 0; s->lpath && l < s->nlayers; l++)
        if (s->lpath[l])
            cairo_path_destroy(s->lpath[l]);
    free(s->lpath);
    for (int k = 0; s->pp && k < s->nsurf; k++)
        aa_peer_painter_free(s->pp[k]);
    free(s->pp);
    free(s->own);
    for (int k = 0; s->gsurf && k < s->nsurf; k++)
        if (s->gsurf[k])
            cairo_surface_destroy(s->gsurf[k]);
    for (int k = 0; s->paint && k < s->nsurf; k++)
        free(s->paint[k]);
    free(s->gsurf);
    free(s->paint);
    s->gsurf = NULL, s->paint = NULL;
    s->surf = NULL, s->path = NULL, s->nsurf = 0, s->lpath = NULL, s->nlayers = 0;
    s->pp = NULL, s->own = NULL;
}

/* Elliptical arc edge d in Cairo's own way: the unit circle's arc from t0
 * to t1 under the transformation (ux uy vx vy cx cy), which maps (cos t,
 * sin t) to (cx + ux cos t + vx sin t, cy + uy cos t + vy sin t) (the
 * matrix is xx yx xy yy x0 y0: x' = xx x + xy y + x0, y' = yx x + yy y +
 * y0).  u and v are never parallel, so the matrix is invertible (but for
 * underflow).  Cairo's
 * arc adds a line from the pen to the arc's start, the pen itself up to
 * rounding; a line to the edge's exact end after it keeps the path on the
 * scene's points. */
static void cairo_put_arc(cairo_t *cr, const aa_edge *d)
{
    /* an ellipse so small that det [u v] underflows (below 1e-150 px or
     * so) is its chord: Cairo refuses a matrix of determinant 0 */
    if (!(fabs(d->ux * d->vy - d->vx * d->uy) > 0.0)) {
        cairo_line_to(cr, d->x1, d->y1);
        return;
    }
    cairo_matrix_t m;
    cairo_matrix_init(&m, d->ux, d->uy, d->vx, d->vy, d->cx, d->cy);
    cairo_save(cr);
    cairo_transform(cr, &m);
    if (d->t1 >= d->t0)
        cairo_arc(cr, 0.0, 0.0, 1.0, d->t0, d->t1);
    else
        cairo_arc_negative(cr, 0.0, 0.0, 1.0, d->t0, d->t1);
    cairo_restore(cr);
    cairo_line_to(cr, d->x1, d->y1);
}

/* The largest |coordinate| edge k reaches, px (its controls, or for an
 * elliptical arc its whole ellipse). */
static double cairo_edge_reach(const aa_edge *e)
{
    double r = fmax(fmax(fabs(e->x0), fabs(e->y0)), fmax(fabs(e->x1), fabs(e->y1)));
    if (e->quad == 3) {
        double hx, hy;
        aa_peer_arc_extent(e, &hx, &hy);
        return fmax(r, fmax(fabs(e->cx) + hx, fabs(e->cy) + hy));
    }
    r = fmax(r, fmax(fabs(e->cx), fabs(e->cy)));
    return e->quad == 2 ? fmax(r, fmax(fabs(e->c2x), fabs(e->c2y))) : r;
}

/* The path of layer `layer`'s contours (-1: every contour), built on a
 * scratch context and copied out into *out.  Arcs are turned into Cairo's
 * cubics here, so the scratch context has the method's tolerance. */
static int cairo_build_path(cairo_path_t **out, const aa_scene *scene, int layer,
                            double tolerance)
{
    size_t nedges, ncont;
    const aa_edge *e = aa_scene_edges(scene, &nedges);
    const size_t *start = aa_scene_contours(scene, &ncont);
    for (size_t k = 0; k < nedges; k++) {
        double r = cairo_edge_reach(&e[k]);
        if (!(r <= CAIRO_MAX_COORD))
            return aa_fail(AA_EINVAL,
                           "cairo: a coordinate of %.17g px is beyond the %.0f px that "
                           "Cairo's 24.8 fixed point keeps",
                           r, CAIRO_MAX_COORD);
    }
    cairo_surface_t *scratch = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(scratch);
    cairo_set_tolerance(cr, tolerance);
    for (size_t c = 0; c < ncont; c++) {
        if (start[c] == start[c + 1] || (layer >= 0 && e[start[c]].layer != layer))
            continue;
        cairo_move_to(cr, e[start[c]].x0, e[start[c]].y0);
        for (size_t k = start[c]; k < start[c + 1]; k++) {
            const aa_edge *d = &e[k];
            if (d->quad == 3)
                cairo_put_arc(cr, d);
            else if (d->quad == 2)
                cairo_curve_to(cr, d->cx, d->cy, d->c2x, d->c2y, d->x1, d->y1);
            else if (d->quad)
                cairo_curve_to(cr, d->x0 + 2.0 / 3.0 * (d->cx - d->x0),
                               d->y0 + 2.0 / 3.0 * (d->cy - d->y0),
                               d->x1 + 2.0 / 3.0 * (d->cx - d->x1),
                               d->y1 + 2.0 / 3.0 * (d->cy - d->y1), d->x1, d->y1);
            else
                cairo_line_to(cr, d->x1, d->y1);
        }
        cairo_close_path(cr);
    }
    *out = cairo_copy_path(cr);
    int st = cairo_status(cr) || !*out || (*out)->status
                 ? aa_fail(AA_ENOMEM, "cairo: cannot build the path (%s)",
                           cairo_status_to_string(cairo_status(cr)))
                 : AA_OK;
    cairo_destroy(cr);
    cairo_surface_destroy(scratch);
    return st;
}

/* A stroke source stroked by Cairo's stroker: the path built in user
 * units under the source's map (cairo_transform), so that Cairo strokes it
 * in user space as SVG says (a non-uniform map transforms the pen), with
 * the source's width, join, cap, miter limit and dashes; quadratic arcs
 * degree-elevated as above, cubic arcs as themselves, circular and
 * elliptical arcs by Cairo's arc (cairo_put_arc).  Cairo's stroker offsets
 * the flattened path (its polygon within `tolerance` of the curve) and
 * draws round joins and caps as polygons within the tolerance. */
static void cairo_stroke_source(cairo_t *cr, const aa_stroke_source *src)
{
    static const cairo_line_join_t joins[] = {CAIRO_LINE_JOIN_MITER, CAIRO_LINE_JOIN_ROUND,
                                              CAIRO_LINE_JOIN_BEVEL};
    static const cairo_line_cap_t caps[] = {CAIRO_LINE_CAP_BUTT, CAIRO_LINE_CAP_ROUND,
                                            CAIRO_LINE_CAP_SQUARE};
    const double *m = src->m;
    cairo_matrix_t cm;
    cairo_matrix_init(&cm, m[0], m[1], m[2], m[3], m[4], m[5]);
    cairo_save(cr);
    cairo_transform(cr, &cm);
    cairo_new_path(cr);
    double px = 0, py = 0;
    for (size_t k = 0; k < src->path.n; k++) {
        const aa_path_seg *g = &src->path.seg[k];
        const double *q = g->p;
        switch (g->op) {
        case AA_PATH_MOVE:
            cairo_move_to(cr, q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_LINE:
            cairo_line_to(cr, q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_QUAD:
            cairo_curve_to(cr, px + 2.0 / 3.0 * (q[0] - px), py + 2.0 / 3.0 * (q[1] - py),
                           q[2] + 2.0 / 3.0 * (q[0] - q[2]), q[3] + 2.0 / 3.0 * (q[1] - q[3]),
                           q[2], q[3]);
            px = q[2], py = q[3];
            break;
        case AA_PATH_CUBIC:
            cairo_curve_to(cr, q[0], q[1], q[2], q[3], q[4], q[5]);
            px = q[4], py = q[5];
            break;
        case AA_PATH_ARC: {
            aa_edge d = {0};
            d.x0 = px, d.y0 = py, d.cx = q[0], d.cy = q[1], d.ux = q[2], d.uy = q[3];
            d.vx = q[4], d.vy = q[5], d.t0 = q[6], d.t1 = q[7], d.x1 = q[8], d.y1 = q[9];
            d.quad = 3;
            cairo_put_arc(cr, &d);
            px = q[8], py = q[9];
            break;
        }
        default:
            cairo_close_path(cr);
            break;
        }
    }
    cairo_set_line_width(cr, src->style.width);
    cairo_set_line_join(cr, joins[src->style.join]);
    cairo_set_line_cap(cr, caps[src->style.cap]);
    cairo_set_miter_limit(cr, src->style.miterlimit);
    cairo_set_dash(cr, src->style.dash, (int)src->style.ndash, src->style.dashoffset);
    cairo_stroke(cr); /* with the map still the CTM: the pen is in user units */
    cairo_restore(cr);
}

/*
 * Clips in Cairo's own way, where it has one: cairo_clip intersects the
 * clip with the current one, so a clip Cairo can hold is an intersection
 * of paths: a clip of one member (a path under its rule), that member's
 * own clip and the clip it is defined within each such a clip again
 * (cairo_clips).  A layer gated by one is filled or stroked after those
 * paths are clipped to (cairo_clip_to), and the clip is Cairo's: its
 * image compositor intersects the polygons of the clip and of the fill
 * (or renders the clip as a mask where it cannot, as for a stroke).  A
 * clip of several members, a union, is none: cairo_clip has no union, so
 * the layers it gates take the masks of peer.h (aa_peer_paint_band).
 */
static int cairo_clips(const cairo_state *s, const aa_scene *scene, int c)
{
    int first, count = aa_scene_clip_members(scene, c, &first);
    if (count != 1 || !s->lpath[first])
        return 0;
    const int within = aa_scene_clip_within(scene, c), g = aa_scene_layer_clip(scene, first);
    return (within < 0 || cairo_clips(s, scene, within)) && (g < 0 || cairo_clips(s, scene, g));
}

static void cairo_clip_to(cairo_t *cr, const cairo_state *s, const aa_scene *scene, int c)
{
    int first;
    aa_scene_clip_members(scene, c, &first);
    const int within = aa_scene_clip_within(scene, c), g = aa_scene_layer_clip(scene, first);
    if (within >= 0)
        cairo_clip_to(cr, s, scene, within);
    if (g >= 0)
        cairo_clip_to(cr, s, scene, g);
    cairo_new_path(cr);
    cairo_set_fill_rule(cr, aa_scene_layer_rule(scene, first) == AA_FILL_EVENODD
                                ? CAIRO_FILL_RULE_EVEN_ODD
                                : CAIRO_FILL_RULE_WINDING);
    cairo_append_path(cr, s->lpath[first]);
    cairo_clip(cr);
}

/* A scene the one-layer grey fill refuses (colour, several layers,
 * translucency) is painted layer by layer: Cairo's coverage of each layer
 * (its path filled with its rule, or its stroke stroked from the source)
 * on the A8 surface, composited here over the layers behind in linear
 * light, each layer's inside the scene's own colour there
 * (cairo_layered_band).  Each layer's coverage is its alpha: where layers
 * share an edge the background shows through their seam (conflation),
 * which the exact reference does not have; everything else is what the
 * one-layer fill measures (Cairo's coverage).  A layer filled from offset
 * curves (edge quad 4: no Cairo path holds them) and groups of opacity (a
 * group's coverage is not any one layer's) are refused. */
static int cairo_init_painted(cairo_state *s, const aa_scene *scene, double tolerance)
{
    int st = aa_peer_painted_check("cairo", scene, 0);
    if (st)
        return st;
    s->nlayers = aa_scene_layer_count(scene);
    if (s->nlayers && !(s->lpath = calloc((size_t)s->nlayers, sizeof *s->lpath)))
        return aa_fail(AA_ENOMEM, "cairo: out of memory");
    for (int l = 0; l < s->nlayers && !st; l++)
        if (aa_scene_layer_stroked(scene, l) < 0)
            st = cairo_build_path(&s->lpath[l], scene, l, tolerance);
    if (!st && aa_scene_is_clipped(scene)) {
        if (!(s->own = calloc((size_t)s->nlayers, 1)))
            return aa_fail(AA_ENOMEM, "cairo: out of memory");
        for (int l = 0; l < s->nlayers; l++) {
            const int c = aa_scene_layer_clip(scene, l);
            s->own[l] = aa_scene_layer_clip_member(scene, l) < 0 && c >= 0 &&
                        cairo_clips(s, scene, c);
        }
    }
    s->painted = 1;
    return st;
}

static int cairo_init(void *state, const double *p, const aa_job *job)
{
    cairo_state *s = state;
    /* Cairo's joins are miter (a bevel past the limit), round and bevel */
    int st = aa_peer_refuse_joins("cairo", job->placed, 0,
                                  "Cairo's stroker does not have (miter, round and bevel)");
    if (st)
        return st;
    st = aa_peer_scene_read("cairo", job, &s->ps);
    if (st == AA_EINVAL && aa_peer_paintable(job->placed))
        st = cairo_init_painted(s, job->placed, p[TOLERANCE]);
    else if (!st)
        st = cairo_build_path(&s->path, job->placed, -1, p[TOLERANCE]);
    if (!st) {
        s->nsurf = job->threads > 0 ? job->threads : 1;
        s->surf = calloc((size_t)s->nsurf, sizeof *s->surf);
        if (!s->surf)
            st = aa_fail(AA_ENOMEM, "cairo: out of memory");
        for (int k = 0; k < s->nsurf && !st; k++) {
            s->surf[k] = cairo_image_surface_create(CAIRO_FORMAT_A8, job->w, BAND);
            if (cairo_surface_status(s->surf[k]))
                st = aa_fail(AA_ENOMEM, "cairo: cannot make a %dx%d A8 surface", job->w,
                             BAND);
        }
    }
    if (!st && aa_scene_has_gradients(job->placed)) {
        if (!(s->gsurf = calloc((size_t)s->nsurf, sizeof *s->gsurf)) ||
            !(s->paint = calloc((size_t)s->nsurf, sizeof *s->paint)))
            st = aa_fail(AA_ENOMEM, "cairo: out of memory");
        for (int k = 0; k < s->nsurf && !st; k++) {
            s->gsurf[k] = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, job->w, BAND);
            if (cairo_surface_status(s->gsurf[k]) ||
                !(s->paint[k] = malloc((size_t)job->w * BAND * 4 * sizeof **s->paint)))
                st = aa_fail(AA_ENOMEM, "cairo: cannot make a %dx%d ARGB32 surface", job->w,
                             BAND);
        }
    }
    if (!st && s->painted) {
        if (!(s->pp = calloc((size_t)s->nsurf, sizeof *s->pp)))
            st = aa_fail(AA_ENOMEM, "cairo: out of memory");
        for (int k = 0; k < s->nsurf && !st; k++)
            st = aa_peer_painter_new("cairo", job->placed, job->w, BAND, s->own, &s->pp[k]);
    }
    for (int k = 0; k < 256 && !s->painted; k++)
        s->lut[k] = aa_peer_mix(&s->ps, k / 255.0);
    if (st)
        cairo_release(s);
    return st;
}

/* Painted mode (cairo_init_painted): Cairo's coverage of layer l on rows
 * [y0, y0 + rows), its path filled with its rule or its stroke stroked
 * from its source, on the thread's A8 surface. */
typedef struct cairo_cover_ctx {
    const cairo_state *s;
    cairo_surface_t *surf;
    const double *p;
    const aa_scene *scene;
    cairo_surface_t *gsurf; /* gradient paint (cairo_shade) */
    float *paint;
} cairo_cover_ctx;

static int cairo_cover(void *vctx, int l, int y0, int rows, const unsigned char **cov,
                       size_t *stride)
{
    static const cairo_antialias_t modes[] = {CAIRO_ANTIALIAS_BEST, CAIRO_ANTIALIAS_GOOD,
                                              CAIRO_ANTIALIAS_FAST};
    (void)rows;
    const cairo_cover_ctx *c = vctx;
    const cairo_state *s = c->s;
    cairo_surface_t *surf = c->surf;
    size_t nsrc;
    const aa_stroke_source *src = aa_scene_stroke_sources(c->scene, &nsrc);
    cairo_surface_flush(surf);
    unsigned char *data = cairo_image_surface_get_data(surf);
    int st = AA_OK, bstride = cairo_image_surface_get_stride(surf);
    memset(data, 0, (size_t)bstride * BAND);
    cairo_surface_mark_dirty(surf);
    cairo_t *cr = cairo_create(surf);
    cairo_set_antialias(cr, modes[(int)c->p[AA]]);
    cairo_set_tolerance(cr, c->p[TOLERANCE]);
    cairo_translate(cr, 0.0, -(double)y0);
    cairo_set_source_rgba(cr, 0, 0, 0, 1);
    if (s->own && s->own[l])
        cairo_clip_to(cr, s, c->scene, aa_scene_layer_clip(c->scene, l));
    int k = aa_scene_layer_stroked(c->scene, l);
    if (k >= 0 && (size_t)k < nsrc) {
        cairo_stroke_source(cr, &src[k]);
    } else if (s->lpath[l]) {
        cairo_set_fill_rule(cr, aa_scene_layer_rule(c->scene, l) == AA_FILL_EVENODD
                                    ? CAIRO_FILL_RULE_EVEN_ODD
                                    : CAIRO_FILL_RULE_WINDING);
        cairo_append_path(cr, s->lpath[l]);
        cairo_fill(cr);
    }
    if (cairo_status(cr))
        st = AA_EFAIL;
    cairo_destroy(cr);
    cairo_surface_flush(surf);
    *cov = data;
    *stride = (size_t)bstride;
    return st;
}

/*
 * Gradient paint (peer.h), by Cairo's own gradients: the layer's gradient
 * as a Cairo pattern, painted (CAIRO_OPERATOR_SOURCE) on the thread's
 * ARGB32 surface, which Cairo's image backend hands to pixman: pixman
 * samples the gradient at each pixel's centre, interpolates the stops'
 * colour and alpha each on its own in single precision (not premultiplied,
 * as SVG says), premultiplies and rounds to 8 bits.  Its colour then goes
 * over Cairo's coverage of the layer (cairo_cover) as peer.c composites.
 *  - linear: cairo_pattern_create_linear(x1, y1, x2, y2);
 *  - radial: cairo_pattern_create_radial(fx, fy, fr, cx, cy, r), Cairo's
 *    two circles, the start circle the focal one (SVG 2's and the canvas's
 *    gradient: the largest w whose circle passes through the point, of a
 *    radius of at least 0), so the focal radius is Cairo's own;
 * the stops by cairo_pattern_add_color_stop_rgba, their sRGB-encoded
 * colours and their opacity, in order (Cairo keeps stops of one offset in
 * the order they were added, and pixman takes the later one from that
 * offset on: SVG's sharp step); pad, reflect and repeat as
 * CAIRO_EXTEND_PAD, REFLECT and REPEAT; the gradient's map m (its space
 * to the scene's, gradientTransform and units composed) as the pattern's
 * matrix, which maps user space to the pattern's, so m inverted.  The
 * colour at a pixel is within half a code of the exact colour at its
 * centre in each premultiplied channel and in alpha
 * (tests/test_gradient_renderers.c).  pixman paints the whole band (see
 * below why), and only the layer's covered span [x0, x1) is converted.
 */
static int cairo_shade(void *vctx, int l, int y0, int rows, int x0, int x1, const float **rgba,
                       size_t *stride)
{
    static const cairo_extend_t extends[] = {CAIRO_EXTEND_PAD, CAIRO_EXTEND_REFLECT,
                                             CAIRO_EXTEND_REPEAT};
    const cairo_cover_ctx *c = vctx;
    aa_gradient g;
    aa_scene_layer_gradient(c->scene, l, &g);
    const double *q = g.p;
    cairo_pattern_t *pat = g.kind == AA_GRADIENT_LINEAR
                               ? cairo_pattern_create_linear(q[0], q[1], q[2], q[3])
                               : cairo_pattern_create_radial(q[3], q[4], q[5], q[0], q[1], q[2]);
    for (int k = 0; k < g.nstops; k++) {
        const aa_gradient_stop *t = &g.stops[k];
        cairo_pattern_add_color_stop_rgba(pat, t->offset, aa_srgb_encode(t->colour.c[0]),
                                          aa_srgb_encode(t->colour.c[1]),
                                          aa_srgb_encode(t->colour.c[2]), t->opacity);
    }
    cairo_pattern_set_extend(pat, extends[g.spread]);
    cairo_matrix_t m;
    cairo_matrix_init(&m, g.m[0], g.m[1], g.m[2], g.m[3], g.m[4], g.m[5]);
    int st = AA_OK;
    if (cairo_matrix_invert(&m) != CAIRO_STATUS_SUCCESS) {
        cairo_pattern_destroy(pat);
        return AA_EINVAL; /* the scene refuses a map that is not invertible */
    }
    cairo_pattern_set_matrix(pat, &m);
    /* the whole band painted, whatever the span: Cairo hands pixman the
     * pattern's matrix less an integer offset taken at the centre of the
     * operation's extents (_cairo_matrix_to_pixman_matrix_offset), and
     * pixman steps along a row from its first pixel, so a narrower paint
     * would round the colours otherwise (measured: 3580 of 115200 channels
     * changed on a test scene); only the span is read back */
    cairo_surface_t *surf = c->gsurf;
    cairo_t *cr = cairo_create(surf);
    cairo_translate(cr, 0.0, -(double)y0);
    cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
    cairo_set_source(cr, pat);
    cairo_paint(cr);
    if (cairo_status(cr) || cairo_pattern_status(pat))
        st = AA_EFAIL;
    cairo_destroy(cr);
    cairo_pattern_destroy(pat);
    cairo_surface_flush(surf);
    const unsigned char *data = cairo_image_surface_get_data(surf);
    const int bstride = cairo_image_surface_get_stride(surf);
    const int w = cairo_image_surface_get_width(surf);
    for (int j = 0; j < rows; j++) {
        const uint32_t *row = (const uint32_t *)(const void *)(data + (size_t)j * (size_t)bstride);
        float *out = c->paint + (size_t)j * (size_t)w * 4;
        out += 4 * (size_t)x0;
        for (int i = x0; i < x1; i++, out += 4) { /* ARGB32: premultiplied, alpha high */
            const uint32_t v = row[i];
            out[0] = (float)((v >> 16) & 255u) / 255.0f;
            out[1] = (float)((v >> 8) & 255u) / 255.0f;
            out[2] = (float)(v & 255u) / 255.0f;
            out[3] = (float)(v >> 24) / 255.0f;
        }
    }
    *rgba = c->paint;
    *stride = (size_t)w * 4;
    return st;
}

static int cairo_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    static const cairo_antialias_t modes[] = {CAIRO_ANTIALIAS_BEST, CAIRO_ANTIALIAS_GOOD,
                                              CAIRO_ANTIALIAS_FAST};
    cairo_state *s = state;
    counters->samples = 0;
    counters->expensive_pixels = 0;
    int nbands = (job->h + BAND - 1) / BAND, status = AA_OK;
#pragma omp parallel num_threads(s->nsurf)
    {
        cairo_surface_t *surf = s->surf[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nbands; b++) {
            int y0 = b * BAND, rows = y0 + BAND < job->h ? BAND : job->h - y0;
            if (s->painted) {
                const int th = omp_get_thread_num();
                cairo_cover_ctx c = {s, surf, p, job->placed, s->gsurf ? s->gsurf[th] : NULL,
                                     s->paint ? s->paint[th] : NULL};
                if (aa_peer_paint_band(s->pp[th], job->placed, cairo_cover, cairo_shade, &c, out,
                                       y0, rows)) {
#pragma omp atomic write
                    status = AA_EFAIL;
                }
                continue;
            }
            if (!s->ps.layers) {
                for (int j = y0; j < y0 + rows; j++)
                    aa_peer_fill(out, j, 0, job->w, s->ps.bg);
                continue;
            }
            cairo_surface_flush(surf);
            unsigned char *data = cairo_image_surface_get_data(surf);
            int stride = cairo_image_surface_get_stride(surf);
            memset(data, 0, (size_t)stride * BAND);
            cairo_surface_mark_dirty(surf);
            cairo_t *cr = cairo_create(surf);
            cairo_set_antialias(cr, modes[(int)p[AA]]);
            cairo_set_tolerance(cr, p[TOLERANCE]);
            cairo_set_fill_rule(cr, s->ps.rule == AA_FILL_EVENODD ? CAIRO_FILL_RULE_EVEN_ODD
                                                                  : CAIRO_FILL_RULE_WINDING);
            cairo_translate(cr, 0.0, -(double)y0);
            cairo_set_source_rgba(cr, 0, 0, 0, 1);
            if (s->ps.strokes) {
                /* each stroke from its source, painted OVER the others */
                size_t nsrc;
                const aa_stroke_source *src = aa_scene_stroke_sources(job->placed, &nsrc);
                for (size_t k = 0; k < nsrc; k++)
                    cairo_stroke_source(cr, &src[k]);
            } else {
                cairo_append_path(cr, s->path);
                cairo_fill(cr);
            }
            if (cairo_status(cr)) {
#pragma omp atomic write
                status = AA_EFAIL;
            }
            cairo_destroy(cr);
            cairo_surface_flush(surf);
            for (int j = 0; j < rows; j++) {
                const unsigned char *row = data + (size_t)j * stride;
                double *px = aa_pixel(out, 0, y0 + j);
                for (int i = 0; i < job->w; i++, px += 3)
                    px[0] = px[1] = px[2] = s->lut[row[i]];
            }
        }
    }
    return status ? aa_fail(status, "cairo: cairo_fill failed") : AA_OK;
}

const aa_method_type aa_method_cairo = {
    {"cairo", "peer: Cairo's A8 image-surface fill (8-bit coverage, curves flattened)",
     cairo_params},
    sizeof(cairo_state),
    AA_METHOD_SOME_SCENES | AA_METHOD_GRADIENTS,
    cairo_check,
    cairo_init,
    cairo_render,
    cairo_release};
