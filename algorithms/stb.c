/*
 * stb.c: stb_truetype's exact-area rasterizer as a peer (Sean Barrett's
 * stb_truetype.h, rasterizer version 2, reached through stbtt_Rasterize).
 *
 * Version 2 flattens curves into lines (stbtt_FlattenCurves: a quadratic is
 * halved until its midpoint lies within `flatness` pixels of its chord's; a
 * cubic arc goes in as STBTT_vcubic, flattened by stb's own cubic test:
 * split until the control polygon is at most `flatness` longer than the
 * chord in the sense long^2 - chord^2 <= flatness^2, which keeps the
 * polygon, and so the curve, within flatness/2 of the chord; an elliptical
 * arc, which stb's outlines do not have, goes in as at most four cubics of
 * at most 90 degrees each, aa_peer_arc_cubics, peer.h: within 2.7e-4 of
 * the ellipse's longer semi-axis, outside it),
 * then computes, for every pixel, the signed area to the right of each
 * line inside it, in single precision, and writes |sum| clamped to 1 as an
 * 8-bit coverage ("exact-area" in its own words: exact for the polygon
 * under its rule).  Our image receives coverage / 255, mixed between the
 * background and the layer's grey (peer.h).  The parameter `flatness` (px,
 * default 0.35, stb_truetype's own default for glyphs) is passed through.
 *
 * The rule.  stb has no even-odd rule: the coverage is the |accumulated
 * signed area|, a nonzero-like rule.  It is the intended coverage when the
 * winding number takes only the values 0 and one sign (every filled region
 * wound once, the same way): then nonzero and even-odd agree.  For an
 * even-odd layer init checks this exactly: between consecutive critical
 * heights (vertices, ends of y-monotone pieces, and the heights where two
 * pieces meet, aa_piece_meet) the order of the pieces along x does not
 * change, so one line through the middle of each such slab meets every
 * region; the winding numbers along those lines must stay in {0, 1} or in
 * {0, -1}.  Crow passes: each white band is its own closed path, all wound
 * alike.  Other even-odd scenes are refused.
 *
 * Tiles.  stbtt_Rasterize writes a whole bitmap; the image is rendered in
 * bands of BAND rows (y_off), each flattened and rasterized on its own into
 * its thread's BAND x W bytes, so memory is O(width) per thread and bands
 * run in parallel.  Rows do not depend on the band they are in.
 *
 * Strokes (aa_scene_stroke): stb_truetype has no stroker, so a stroke is
 * drawn from the scene's exact outline of it (aa_stroke_outline: lines and
 * circular arcs), filled as any outline, its arcs as the cubics above;
 * several strokes of one grey are one non-zero outline, their contours all
 * wound alike (peer.h).  The outline's pieces overlap (a rectangle per
 * segment, a sector or triangle per join), and stb's coverage, their
 * accumulated area clamped to 1, is too large in a pixel that two of them
 * share in part.
 *
 * Painted (peer.h): any other scene (colour, several layers, translucency,
 * groups of opacity, clips) is painted layer by layer: each layer's
 * contours (a stroke its exact outline, stb having no stroker) its own run
 * of vertices, rasterized per band into the thread's bitmap (stb_cover)
 * and composited over the layers behind (aa_peer_paint_band: a clip's
 * members rasterized so too, as the clip's mask multiplied into the
 * coverage of the layers it gates; a group's layers into the group's
 * buffer, composited with its opacity); an even-odd layer is checked on
 * its own as above (its crossings only, at every piece's critical
 * heights), and offset curves are refused in any layer.
 *
 * Limits: grey scenes of one layer or of strokes of one grey, or painted
 * layer by layer (peer.h), and the box filter only; 8-bit
 * coverage (up to 1/510 from rounding); single-precision geometry (at
 * 4096 px a coordinate's last bit is 2.4e-4 px); curves flattened; nonzero
 * coverage is |accumulated area| clamped to 1, which under-estimates where
 * opposite windings meet in a pixel and over-estimates where windings of 2
 * do (stb_truetype's own documentation says so); even-odd scenes only as
 * above.
 */
#include "core.h"
#include "methods.h"
#include "peer.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* Vertices in float (stb_truetype allows predefining its vertex type), so
 * positions are not rounded to 16-bit integers. */
#define stbtt_vertex_type float
typedef struct {
    stbtt_vertex_type x, y, cx, cy, cx1, cy1;
    unsigned char type, padding;
} stbtt_vertex;
#define stbtt_vertex stbtt_vertex

#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wstrict-prototypes"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <stb_truetype.h>
#pragma GCC diagnostic pop

#define BAND 64 /* rows per band */
/* The scene is given to stb one pixel lower and read back with a y offset
 * one larger.  stb_truetype clamps an edge that ends above the bitmap's
 * first scanline only when that offset is not zero, and asserts otherwise
 * (a scene moved partly above the image stopped the program); a whole-pixel
 * shift changes nothing else. */
#define Y_SHIFT 1

enum { FLATNESS };

static const aa_param stb_params[] = {
    {"flatness", AA_PARAM_REAL, 0.35, 0.0, 100.0, 1, NULL,
     "curve flattening tolerance in pixels (stb_truetype's default 0.35)"},
    {0}};

typedef struct stb_state {
    aa_peer_scene ps;
    stbtt_vertex *v;
    int nv;
    unsigned char **buf; /* one BAND x W bitmap per thread */
    int nbuf;
    double lut[256];
    /* painted (peer.h): layer l's vertices are v[lv[l] .. lv[l + 1]) */
    int painted, nlayers;
    int *lv;
    aa_peer_painter **pp; /* one per thread */
} stb_state;

static int stb_check(const double *p, const aa_filter *f)
{
    (void)p;
    return aa_peer_check_filter("stb", f);
}

static void stb_release(void *state)
{
    stb_state *s = state;
    for (int k = 0; k < s->nbuf; k++)
        free(s->buf[k]);
    free(s->buf);
    free(s->v);
    free(s->lv);
    for (int k = 0; s->pp && k < s->nbuf; k++)
        aa_peer_painter_free(s->pp[k]);
    free(s->pp);
    s->buf = NULL, s->v = NULL, s->nbuf = 0, s->lv = NULL, s->pp = NULL;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int cmp_piece_xmin(const void *a, const void *b)
{
    const aa_piece *p = *(const aa_piece *const *)a, *q = *(const aa_piece *const *)b;
    return p->xmin < q->xmin ? -1 : p->xmin > q->xmin;
}

/* Even-odd by nonzero: the winding numbers of layer `layer`'s contours
 * (-1: of every contour) must stay within {0, s} for one sign s (see the
 * header).  The critical heights are every piece's, a superset of the
 * layer's, which only adds slabs.  AA_OK if so. */
static int stb_check_windings(const aa_scene *scene, int layer)
{
    size_t np;
    const aa_piece *pc = aa_scene_pieces(scene, &np);
    if (!np)
        return AA_OK;
    size_t cap = 2 * np + 16, n = 0;
    double *ys = malloc(cap * sizeof *ys);
    const aa_piece **by_x = malloc(np * sizeof *by_x);
    aa_crossing *cross = malloc((np + 1) * sizeof *cross);
    int st = (!ys || !by_x || !cross) ? aa_fail(AA_ENOMEM, "stb: out of memory") : AA_OK;
    for (size_t k = 0; k < np && !st; k++) {
        ys[n++] = pc[k].y0;
        ys[n++] = pc[k].y1;
        by_x[k] = &pc[k];
    }
    if (!st)
        qsort(by_x, np, sizeof *by_x, cmp_piece_xmin);
    /* meeting heights of pieces whose extents overlap */
    for (size_t a = 0; a < np && !st; a++)
        for (size_t b = a + 1; b < np && by_x[b]->xmin <= by_x[a]->xmax && !st; b++) {
            const aa_piece *p = by_x[a], *q = by_x[b];
            double ya = fmax(p->y0, q->y0), yb = fmin(p->y1, q->y1), m[9];
            if (!(ya < yb))
                continue;
            int nm = aa_piece_meet(p, q, ya, yb, m, 9); /* two cubics: up to 9 */
            for (int k = 0; k < nm && !st; k++) {
                if (n == cap) {
                    double *t = realloc(ys, 2 * cap * sizeof *ys);
                    if (!t) {
                        st = aa_fail(AA_ENOMEM, "stb: out of memory");
                        break;
                    }
                    ys = t, cap *= 2;
                }
                ys[n++] = m[k];
            }
        }
    if (!st)
        qsort(ys, n, sizeof *ys, cmp_double);
    int seen = 0; /* the sign of the nonzero windings met */
    for (size_t k = 0; k + 1 < n && !st; k++) {
        if (!(ys[k] < ys[k + 1]))
            continue;
        double y = 0.5 * (ys[k] + ys[k + 1]);
        size_t nc = aa_scene_crossings(scene, y, cross, np + 1);
        int wind = 0;
        for (size_t c = 0; c < nc && !st; c++) {
            if (layer >= 0 && cross[c].layer != layer)
                continue;
            wind += cross[c].dir;
            if (wind == 0)
                continue;
            if (wind > 1 || wind < -1 || (seen && wind != seen))
                st = aa_fail(AA_EINVAL,
                             "stb fills by nonzero only: %s%d has winding numbers %d and "
                             "%d (at y = %.17g px), so nonzero would not give its coverage; it "
                             "accepts even-odd layers whose filled regions are each wound "
                             "once, all the same way",
                             layer >= 0 ? "the even-odd layer " : "this even-odd scene's layer ",
                             layer >= 0 ? layer : 0, seen ? seen : wind, wind, y);
            seen = wind;
        }
    }
    free(ys);
    free(by_x);
    free(cross);
    return st;
}

/* Append a vertex of `type` ending at (x, y) px, with its control point
 * ctl[0..1] (vcurve) or points ctl[0..3] (vcubic), moved Y_SHIFT down. */
static void stb_vertex(stb_state *s, unsigned char type, double x, double y, const double *ctl)
{
    stbtt_vertex *v = &s->v[s->nv++];
    memset(v, 0, sizeof *v);
    v->type = type;
    v->x = (float)x, v->y = (float)(y + Y_SHIFT);
    if (type == STBTT_vcurve || type == STBTT_vcubic)
        v->cx = (float)ctl[0], v->cy = (float)(ctl[1] + Y_SHIFT);
    if (type == STBTT_vcubic)
        v->cx1 = (float)ctl[2], v->cy1 = (float)(ctl[3] + Y_SHIFT);
}

/* The vertices of contour c (a move, then its edges; an elliptical arc as
 * cubics, peer.h). */
static void stb_contour(stb_state *s, const aa_edge *e, const size_t *start, size_t c)
{
    stb_vertex(s, STBTT_vmove, e[start[c]].x0, e[start[c]].y0, NULL);
    for (size_t k = start[c]; k < start[c + 1]; k++) {
        const aa_edge *d = &e[k];
        if (d->quad == 3) { /* cubics (peer.h): stb's outlines have no arcs */
            double cub[AA_PEER_ARC_CUBICS][6];
            int m = aa_peer_arc_cubics(d, cub);
            for (int q = 0; q < m; q++)
                stb_vertex(s, STBTT_vcubic, cub[q][4], cub[q][5], cub[q]);
        } else if (d->quad == 2) {
            const double ctl[4] = {d->cx, d->cy, d->c2x, d->c2y};
            stb_vertex(s, STBTT_vcubic, d->x1, d->y1, ctl);
        } else if (d->quad) {
            const double ctl[2] = {d->cx, d->cy};
            stb_vertex(s, STBTT_vcurve, d->x1, d->y1, ctl);
        } else {
            stb_vertex(s, STBTT_vline, d->x1, d->y1, NULL);
        }
    }
}

/* Painted (peer.h): stb has no stroker, so every layer, stroke or fill,
 * is its exact outline (offset curves refused), an even-odd one checked
 * as above on its own. */
static int stb_init_painted(stb_state *s, const aa_scene *scene)
{
    int st = aa_peer_painted_check("stb", scene, 1);
    s->nlayers = aa_scene_layer_count(scene);
    for (int l = 0; l < s->nlayers && !st; l++)
        if (aa_scene_layer_rule(scene, l) == AA_FILL_EVENODD)
            st = stb_check_windings(scene, l);
    if (!st && !(s->lv = calloc((size_t)s->nlayers + 1, sizeof *s->lv)))
        st = aa_fail(AA_ENOMEM, "stb: out of memory");
    s->painted = 1;
    return st;
}

static int stb_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    stb_state *s = state;
    int st = aa_peer_scene_read("stb", job, &s->ps);
    if (st == AA_EINVAL && aa_peer_paintable(job->placed))
        st = stb_init_painted(s, job->placed);
    else if (!st) /* stb fills the strokes' exact outlines too (above) */
        st = aa_peer_refuse_offsets("stb", job->placed);
    if (!st && !s->painted && s->ps.layers && s->ps.rule == AA_FILL_EVENODD)
        st = stb_check_windings(job->placed, -1);
    size_t nedges, ncont;
    const aa_edge *e = aa_scene_edges(job->placed, &nedges);
    const size_t *start = aa_scene_contours(job->placed, &ncont);
    /* a move per contour, a vertex per edge, up to 4 for an arc */
    size_t nv = ncont;
    for (size_t k = 0; k < nedges; k++)
        nv += e[k].quad == 3 ? AA_PEER_ARC_CUBICS : 1;
    if (!st && nv > (size_t)INT32_MAX / 2)
        st = aa_fail(AA_EINVAL, "stb: %zu edges are more than stbtt_Rasterize counts", nedges);
    if (!st) {
        s->v = malloc((nv + 1) * sizeof *s->v);
        s->nbuf = job->threads > 0 ? job->threads : 1;
        s->buf = calloc((size_t)s->nbuf, sizeof *s->buf);
        if (!s->v || !s->buf)
            st = aa_fail(AA_ENOMEM, "stb: out of memory");
        for (int k = 0; k < s->nbuf && !st; k++)
            if (!(s->buf[k] = malloc((size_t)BAND * (size_t)job->w)))
                st = aa_fail(AA_ENOMEM, "stb: out of memory");
    }
    if (!st && s->painted) {
        if (!(s->pp = calloc((size_t)s->nbuf, sizeof *s->pp)))
            st = aa_fail(AA_ENOMEM, "stb: out of memory");
        for (int k = 0; k < s->nbuf && !st; k++)
            st = aa_peer_painter_new("stb", job->placed, job->w, BAND, NULL, &s->pp[k]);
    }
    if (!st && s->painted) { /* the contours layer by layer */
        for (int l = 0; l < s->nlayers; l++) {
            s->lv[l] = s->nv;
            for (size_t c = 0; c < ncont; c++)
                if (start[c] != start[c + 1] && e[start[c]].layer == l)
                    stb_contour(s, e, start, c);
        }
        s->lv[s->nlayers] = s->nv;
    } else {
        for (size_t c = 0; c < ncont && !st; c++)
            if (start[c] != start[c + 1])
                stb_contour(s, e, start, c);
    }
    for (int k = 0; k < 256; k++)
        s->lut[k] = aa_peer_mix(&s->ps, k / 255.0);
    if (st)
        stb_release(s);
    return st;
}

/* stb's coverage of vertices v[0 .. nv) on rows [y0, y0 + rows) into buf
 * (rows x w bytes). */
static void stb_band(const double *p, stbtt_vertex *v, int nv, unsigned char *buf, int w,
                     int y0, int rows)
{
    memset(buf, 0, (size_t)rows * (size_t)w);
    if (!nv)
        return;
    stbtt__bitmap bm = {w, rows, w, buf};
    stbtt_Rasterize(&bm, (float)p[FLATNESS], v, nv, 1.0f, 1.0f, 0.0f, 0.0f, 0, y0 + Y_SHIFT, 0,
                    NULL);
}

/* Painted (peer.h): stb's coverage of layer l, into the thread's bitmap. */
typedef struct stb_cover_ctx {
    const stb_state *s;
    const double *p;
    unsigned char *buf;
    int w;
} stb_cover_ctx;

static int stb_cover(void *vctx, int layer, int y0, int rows, const unsigned char **cov,
                     size_t *stride)
{
    const stb_cover_ctx *c = vctx;
    const stb_state *s = c->s;
    stb_band(c->p, s->v + s->lv[layer], s->lv[layer + 1] - s->lv[layer], c->buf, c->w, y0,
             rows);
    *cov = c->buf;
    *stride = (size_t)c->w;
    return AA_OK;
}

static int stb_render(void *state, const double *p, const aa_job *job, aa_image *out,
                      aa_counters *counters)
{
    stb_state *s = state;
    counters->samples = 0;
    counters->expensive_pixels = 0;
    int nbands = (job->h + BAND - 1) / BAND;
#pragma omp parallel num_threads(s->nbuf)
    {
        unsigned char *buf = s->buf[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nbands; b++) {
            int y0 = b * BAND, rows = y0 + BAND < job->h ? BAND : job->h - y0;
            if (s->painted) { /* back to front (peer.h) */
                stb_cover_ctx c = {s, p, buf, job->w};
                aa_peer_paint_band(s->pp[omp_get_thread_num()], job->placed, stb_cover, NULL, &c,
                                   out, y0, rows);
                continue;
            }
            if (!s->ps.layers || !s->nv) {
                for (int j = y0; j < y0 + rows; j++)
                    aa_peer_fill(out, j, 0, job->w, s->ps.bg);
                continue;
            }
            stb_band(p, s->v, s->nv, buf, job->w, y0, rows);
            for (int j = 0; j < rows; j++) {
                const unsigned char *row = buf + (size_t)j * job->w;
                double *px = aa_pixel(out, 0, y0 + j);
                for (int i = 0; i < job->w; i++, px += 3)
                    px[0] = px[1] = px[2] = s->lut[row[i]];
            }
        }
    }
    return AA_OK;
}

const aa_method_type aa_method_stb = {
    {"stb", "peer: stb_truetype's exact-area rasterizer (8-bit coverage, curves flattened)",
     stb_params},
    sizeof(stb_state),
    AA_METHOD_SOME_SCENES,
    stb_check,
    stb_init,
    stb_render,
    stb_release};
