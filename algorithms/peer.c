/*
 * peer.c: the checks and helpers the peer rasterizers share (peer.h).
 */
#include "peer.h"
#include "core.h"
#include "path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int aa_peer_check_filter(const char *name, const aa_filter *f)
{
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL,
                       "%s computes box-filter coverage only: it is measured against the box "
                       "reference (use -f box; no other filter is supported)",
                       name);
    return AA_OK;
}

int aa_peer_scene_read(const char *name, const aa_job *job, aa_peer_scene *ps)
{
    const aa_scene *s = job->placed;
    if (!aa_scene_is_grey(s))
        return aa_fail(AA_EINVAL,
                       "%s renders one coverage channel: it accepts grey scenes only (every "
                       "colour with equal R, G and B), and this scene has colour",
                       name);
    int n = aa_scene_layer_count(s);
    if (aa_scene_is_clipped(s))
        return aa_fail(AA_EINVAL,
                       "%s fills layers unclipped: this scene has clip paths, which it does "
                       "not apply",
                       name);
    if (!aa_scene_is_opaque(s))
        return aa_fail(AA_EINVAL,
                       "%s fills opaque layers only: this scene has translucent layers "
                       "(opacity below 1), which it does not composite",
                       name);
    ps->strokes = n > 0 && aa_scene_layer_stroked(s, 0) >= 0;
    if (n > 1) {
        /* several layers: only strokes of one grey, all mapped the same
         * way round (peer.h) */
        size_t nsrc;
        const aa_stroke_source *src = aa_scene_stroke_sources(s, &nsrc);
        int sign = 0;
        for (int l = 0; l < n; l++) {
            int k = aa_scene_layer_stroked(s, l);
            if (k < 0 || aa_scene_layer_colour(s, l).c[0] != aa_scene_layer_colour(s, 0).c[0])
                return aa_fail(AA_EINVAL,
                               "%s fills one layer: it accepts scenes of one layer, or of "
                               "several strokes of one grey, and this scene has %d layers "
                               "(layer %d is %s)",
                               name, n, l, k < 0 ? "a fill" : "of another grey");
            const double *m = src[k].m;
            int sg = m[0] * m[3] - m[1] * m[2] > 0 ? 1 : -1;
            if (sign && sg != sign)
                return aa_fail(AA_EINVAL,
                               "%s: the strokes of this scene are mapped some mirrored and "
                               "some not, so their outlines' windings could cancel in one "
                               "outline",
                               name);
            sign = sg;
        }
    }
    /* the exact offset curves of a Bezier arc's stroke (edge quad 4): no
     * peer's outline has them; a peer that strokes the source itself
     * (ps->strokes) draws the stroke from its path, and one that fills the
     * outline refuses it (aa_peer_refuse_offsets) */
    if (!ps->strokes) {
        int st = aa_peer_refuse_offsets(name, s);
        if (st)
            return st;
    }
    ps->layers = n;
    ps->bg = aa_scene_background(s).c[0];
    ps->fg = n ? aa_scene_layer_colour(s, 0).c[0] : ps->bg;
    ps->rule = n ? aa_scene_layer_rule(s, 0) : AA_FILL_NONZERO;
    return AA_OK;
}

int aa_peer_refuse_offsets(const char *name, const aa_scene *s)
{
    size_t ne;
    const aa_edge *e = aa_scene_edges(s, &ne);
    for (size_t k = 0; k < ne; k++)
        if (e[k].quad == 4)
            return aa_fail(AA_EINVAL,
                           "%s fills outlines of lines, Bezier arcs and elliptical arcs: this "
                           "scene's outline has the exact offset curves of a Bezier arc's "
                           "stroke (layer %d), which it cannot take",
                           name, e[k].layer);
    return AA_OK;
}

int aa_peer_refuse_joins(const char *name, const aa_scene *s, int miter_clip, const char *what)
{
    size_t n;
    const aa_stroke_source *src = aa_scene_stroke_sources(s, &n);
    for (size_t k = 0; k < n; k++)
        if ((src[k].style.join == AA_JOIN_MITER_CLIP && !miter_clip) ||
            src[k].style.join == AA_JOIN_ARCS)
            return aa_fail(AA_EINVAL,
                           "%s: the stroke of layer %d has the join %s, which %s",
                           name, src[k].layer,
                           src[k].style.join == AA_JOIN_ARCS ? "arcs" : "miter-clip", what);
    return AA_OK;
}

void aa_peer_fill(aa_image *out, int j, int i0, int i1, double v)
{
    double *px = aa_pixel(out, 0, j) + 3 * (size_t)i0;
    for (int i = i0; i < i1; i++, px += 3)
        px[0] = px[1] = px[2] = v;
}

int aa_peer_paintable(const aa_scene *s)
{
    return aa_scene_is_clipped(s) || !aa_scene_is_grey(s) || !aa_scene_is_opaque(s) ||
           aa_scene_layer_count(s) > 1;
}

int aa_peer_painted_check(const char *name, const aa_scene *s, int strokes_filled)
{
    size_t ne;
    const aa_edge *e = aa_scene_edges(s, &ne);
    for (size_t k = 0; k < ne; k++)
        if (e[k].quad == 4 && (strokes_filled || aa_scene_layer_stroked(s, e[k].layer) < 0))
            return aa_fail(AA_EINVAL,
                           "%s: layer %d is filled from the exact offset curves of a Bezier "
                           "arc's stroke, which its outlines cannot hold",
                           name, e[k].layer);
    for (int l = 0; l < aa_scene_layer_count(s); l++)
        if (aa_scene_layer_gradient_interpolation(s, l) != AA_INTERPOLATE_SRGB) {
            const char *src = aa_scene_layer_gradient_source(s, l);
            return aa_fail(AA_EINVAL,
                           "%s: layer %d's gradient%s%s%s interpolates its stops in linear "
                           "light (color-interpolation: linearRGB), which the library's "
                           "gradients do not (they interpolate the values they are given): "
                           "refused, not drawn in sRGB-encoded values",
                           name, l, *src ? " (" : "", src, *src ? ")" : "");
        }
    return AA_OK;
}

void aa_peer_background_row(const aa_scene *s, aa_image *out, int j, int n)
{
    const aa_rgb bg = aa_scene_background(s);
    double *px = aa_pixel(out, 0, j);
    for (int i = 0; i < n; i++, px += 3)
        px[0] = bg.c[0], px[1] = bg.c[1], px[2] = bg.c[2];
}

/* One pixel v (three linear channels) under coverage a > 0 of a layer of
 * linear colour c, alpha `alpha` and encoded premultiplied colour e =
 * alpha encode(c): v = a inside + (1 - a) v (aa_peer_composite_row). */
static inline void composite_px(const aa_rgb *c, double alpha, const double e[3], double a,
                                double *px)
{
    for (int q = 0; q < 3; q++) {
        const double inside = alpha == 1.0
                                  ? c->c[q]
                                  : aa_srgb_decode(e[q] + (1.0 - alpha) * aa_srgb_encode(px[q]));
        px[q] = a * inside + (1.0 - a) * px[q];
    }
}

/* One pixel v under coverage a > 0 of paint of encoded premultiplied
 * colour e and alpha alpha (a gradient's, per pixel):
 * v = a decode(e + (1 - alpha) encode(v)) + (1 - a) v. */
static inline void composite_paint_px(const double e[3], double alpha, double a, double *px)
{
    for (int q = 0; q < 3; q++) {
        const double inside = aa_srgb_decode(e[q] + (1.0 - alpha) * aa_srgb_encode(px[q]));
        px[q] = a * inside + (1.0 - a) * px[q];
    }
}

void aa_peer_composite_row(const aa_scene *s, int layer, const unsigned char *cov, int n,
                           double *px)
{
    const aa_rgb c = aa_scene_layer_colour(s, layer);
    const double alpha = aa_scene_layer_alpha(s, layer);
    double e[3];
    for (int q = 0; q < 3; q++)
        e[q] = alpha * aa_srgb_encode(c.c[q]);
    for (int i = 0; i < n; i++, px += 3)
        if (cov[i])
            composite_px(&c, alpha, e, cov[i] / 255.0, px);
}

/* ---- Painting clips and groups of opacity (peer.h) ----
 *
 * A band's workspace: masks of clips (band x w doubles each) and a group
 * buffer per level of nesting (band x w pixels of five doubles: k, the
 * coverage of the group, and Q, B, its encoded premultiplied colour and
 * alpha, each already times k).
 *
 * The masks follow a plan made once for the scene (plan_clips): a clip's
 * mask is made just before the first layer, back to front, that needs it
 * (gated by it, or by a clip made from it: the clip it is defined within
 * and its members' own clips are made first), into a slot that is given
 * back once its last use is past.  So each needed clip is made once per
 * band, and the slots are as many as the masks ever alive at once (a
 * scene clipping each element by a clip of its own needs one or two, not
 * one per clip). */
struct aa_peer_painter {
    int w, band, nclips, depth, nslots;
    double *mask;       /* nslots x band x w */
    double *group;      /* depth x band x w x 5 */
    unsigned char *own; /* per layer: 1 if its coverage has its clip applied */
    int *slot;          /* per clip: its mask's slot (-1: not needed) */
    int *order, *at;    /* the clips to make, in order, each before layer at[k] */
    int norder;
};

/* The plan's walk (plan_clips): clip c made (once) with what it is made
 * from; `uses` counts every use of a clip's mask (pass 0), and pass 1
 * gives slots, freeing a clip's slot when its uses run out. */
typedef struct plan_walk {
    aa_peer_painter *pp;
    const aa_scene *s;
    int pass, layer, *uses, *made, *free_slots, nfree;
} plan_walk;

static void plan_use(plan_walk *pw, int c)
{
    if (pw->pass == 0)
        pw->uses[c]++;
    else if (--pw->uses[c] == 0)
        pw->free_slots[pw->nfree++] = pw->pp->slot[c];
}

static void plan_make(plan_walk *pw, int c)
{
    if (pw->made[c] == pw->pass + 1)
        return;
    pw->made[c] = pw->pass + 1;
    const aa_scene *s = pw->s;
    const int within = aa_scene_clip_within(s, c);
    int first, count = aa_scene_clip_members(s, c, &first);
    if (within >= 0)
        plan_make(pw, within);
    for (int l = first; l < first + count; l++)
        if (aa_scene_layer_clip(s, l) >= 0)
            plan_make(pw, aa_scene_layer_clip(s, l));
    aa_peer_painter *pp = pw->pp;
    if (pw->pass == 1) { /* c's slot first, then its sources' given back */
        pp->slot[c] = pw->nfree ? pw->free_slots[--pw->nfree] : pp->nslots++;
        pp->order[pp->norder] = c;
        pp->at[pp->norder++] = pw->layer;
    }
    if (within >= 0)
        plan_use(pw, within);
    for (int l = first; l < first + count; l++)
        if (aa_scene_layer_clip(s, l) >= 0)
            plan_use(pw, aa_scene_layer_clip(s, l));
}

static int plan_clips(aa_peer_painter *pp, const aa_scene *s)
{
    const int nc = pp->nclips;
    plan_walk pw = {pp, s, 0, 0, calloc((size_t)nc, sizeof(int)), calloc((size_t)nc, sizeof(int)),
                    calloc((size_t)nc, sizeof(int)), 0};
    int ok = pw.uses && pw.made && pw.free_slots;
    for (pw.pass = 0; pw.pass < 2 && ok; pw.pass++)
        for (int l = aa_scene_layer_count(s) - 1; l >= 0; l--) {
            const int g = aa_scene_layer_clip(s, l);
            if (aa_scene_layer_clip_member(s, l) >= 0 || g < 0 || pp->own[l])
                continue;
            pw.layer = l;
            plan_make(&pw, g);
            plan_use(&pw, g);
        }
    free(pw.uses);
    free(pw.made);
    free(pw.free_slots);
    return ok;
}

/* The groups holding layer l, outermost first, into chain; returns how
 * many. */
static int group_chain(const aa_scene *s, int l, int chain[AA_SCENE_MAX_GROUP_DEPTH])
{
    int n = 0;
    for (int g = aa_scene_layer_group(s, l); g >= 0 && n < AA_SCENE_MAX_GROUP_DEPTH;
         g = aa_scene_group_parent(s, g))
        chain[n++] = g;
    for (int a = 0, b = n - 1; a < b; a++, b--) {
        int t = chain[a];
        chain[a] = chain[b], chain[b] = t;
    }
    return n;
}

int aa_peer_painter_new(const char *name, const aa_scene *s, int w, int band,
                        const unsigned char *own, aa_peer_painter **out)
{
    *out = NULL;
    const int n = aa_scene_layer_count(s);
    aa_peer_painter *pp = calloc(1, sizeof *pp);
    if (!pp)
        return aa_fail(AA_ENOMEM, "%s: out of memory", name);
    pp->w = w, pp->band = band, pp->nclips = aa_scene_clip_count(s);
    const size_t nc = (size_t)pp->nclips + 1;
    if (!(pp->own = calloc((size_t)n + 1, 1)) || !(pp->slot = malloc(nc * sizeof *pp->slot)) ||
        !(pp->order = malloc(nc * sizeof *pp->order)) || !(pp->at = malloc(nc * sizeof *pp->at)))
        goto nomem;
    int chain[AA_SCENE_MAX_GROUP_DEPTH];
    for (int l = 0; l < n; l++) {
        int k = group_chain(s, l, chain);
        if (k > pp->depth)
            pp->depth = k;
        pp->own[l] = own && own[l];
    }
    for (int c = 0; c < pp->nclips; c++)
        pp->slot[c] = -1;
    if (pp->nclips && !plan_clips(pp, s))
        goto nomem;
    const size_t px = (size_t)w * (size_t)band;
    if (pp->nslots && !(pp->mask = malloc((size_t)pp->nslots * px * sizeof *pp->mask)))
        goto nomem;
    if (pp->depth && !(pp->group = malloc((size_t)pp->depth * px * 5 * sizeof *pp->group)))
        goto nomem;
    *out = pp;
    return AA_OK;
nomem:;
    const int nslots = pp->nslots, depth = pp->depth;
    aa_peer_painter_free(pp);
    return aa_fail(AA_ENOMEM,
                   "%s: out of memory for %d masks of clips and %d levels of groups on "
                   "%d x %d pixels",
                   name, nslots, depth, w, band);
}

void aa_peer_painter_free(aa_peer_painter *pp)
{
    if (!pp)
        return;
    free(pp->mask);
    free(pp->group);
    free(pp->own);
    free(pp->slot);
    free(pp->order);
    free(pp->at);
    free(pp);
}

/* Clip c's mask on rows [y0, y0 + rows), into its slot (the masks it is
 * made from are made already, plan_clips):
 *     M_c = M_within(c) (1 - prod over members m (1 - a_m M_gate(m))),
 * a_m the library's coverage of member m under its rule, the union of the
 * members by OVER (u = m + (1 - m) u, in turn), as the peers paint
 * strokes of one grey over each other. */
static int clip_mask(aa_peer_painter *pp, const aa_scene *s, aa_peer_cover_fn cover, void *ctx,
                     int y0, int rows, int c)
{
    const int w = pp->w;
    const size_t px = (size_t)w * (size_t)pp->band;
    double *m = pp->mask + (size_t)pp->slot[c] * px;
    memset(m, 0, (size_t)rows * (size_t)w * sizeof *m);
    int first, count = aa_scene_clip_members(s, c, &first);
    for (int l = first; l < first + count; l++) {
        const unsigned char *cov;
        size_t stride;
        int st = cover(ctx, l, y0, rows, &cov, &stride);
        if (st)
            return st;
        if (!cov)
            continue;
        const int g = aa_scene_layer_clip(s, l);
        const double *gm = g >= 0 ? pp->mask + (size_t)pp->slot[g] * px : NULL;
        for (int j = 0; j < rows; j++)
            for (int i = 0; i < w; i++) {
                const size_t k = (size_t)j * (size_t)w + (size_t)i;
                const unsigned char b = cov[(size_t)j * stride + (size_t)i];
                if (!b)
                    continue;
                const double a = gm ? b / 255.0 * gm[k] : b / 255.0;
                m[k] = a + (1.0 - a) * m[k];
            }
    }
    const int within = aa_scene_clip_within(s, c);
    if (within >= 0) {
        const double *wm = pp->mask + (size_t)pp->slot[within] * px;
        for (size_t k = 0; k < (size_t)rows * (size_t)w; k++)
            m[k] *= wm[k];
    }
    return AA_OK;
}

/* Group buffer `level` (1 = outermost) closed with opacity o over the
 * level below it: into the canvas (level 1) as
 *     v = k decode(o Q/k + (1 - o B/k) encode(v)) + (1 - k) v,
 * else into the parent's buffer as Q' = o Q + (1 - o B) Q',
 * B' = o B + (1 - o B) B', k' = k + (1 - k) k' (peer.h). */
static void group_close(aa_peer_painter *pp, aa_image *out, int y0, int rows, int level,
                        double o)
{
    const int w = pp->w;
    const size_t px = (size_t)w * (size_t)pp->band;
    const double *g = pp->group + (size_t)(level - 1) * px * 5;
    double *d = level > 1 ? pp->group + (size_t)(level - 2) * px * 5 : NULL;
    for (int j = 0; j < rows; j++) {
        double *v = aa_pixel(out, 0, y0 + j);
        for (int i = 0; i < w; i++, v += 3) {
            const size_t k = (size_t)j * (size_t)w + (size_t)i;
            const double *b = g + 5 * k;
            if (!(b[0] > 0.0))
                continue;
            if (d) {
                double *p = d + 5 * k;
                const double ob = o * b[4];
                p[0] = b[0] + (1.0 - b[0]) * p[0];
                for (int q = 0; q < 3; q++)
                    p[1 + q] = o * b[1 + q] + (1.0 - ob) * p[1 + q];
                p[4] = ob + (1.0 - ob) * p[4];
                continue;
            }
            const double cov = b[0], oa = o * b[4] / cov;
            for (int q = 0; q < 3; q++) {
                const double inside =
                    aa_srgb_decode(o * b[1 + q] / cov + (1.0 - oa) * aa_srgb_encode(v[q]));
                v[q] = cov * inside + (1.0 - cov) * v[q];
            }
        }
    }
}

int aa__peer_shade_whole = 0;

int aa_peer_paint_band(aa_peer_painter *pp, const aa_scene *s, aa_peer_cover_fn cover,
                       aa_peer_shade_fn shade, void *ctx, aa_image *out, int y0, int rows)
{
    const int w = pp->w, n = aa_scene_layer_count(s);
    const size_t px = (size_t)w * (size_t)pp->band;
    for (int j = y0; j < y0 + rows; j++)
        aa_peer_background_row(s, out, j, w);
    int st = AA_OK, next = 0; /* next: the plan's next clip to make */
    int open[AA_SCENE_MAX_GROUP_DEPTH], depth = 0; /* the groups open, outermost first */
    for (int l = n - 1; l >= 0 && !st; l--) {
        if (aa_scene_layer_clip_member(s, l) >= 0)
            continue; /* a clip's member paints nothing */
        for (; next < pp->norder && pp->at[next] == l && !st; next++)
            st = clip_mask(pp, s, cover, ctx, y0, rows, pp->order[next]);
        if (st)
            break;
        int chain[AA_SCENE_MAX_GROUP_DEPTH], nc = group_chain(s, l, chain), keep = 0;
        while (keep < depth && keep < nc && open[keep] == chain[keep])
            keep++;
        for (; depth > keep; depth--)
            group_close(pp, out, y0, rows, depth, aa_scene_group_opacity(s, open[depth - 1]));
        for (; depth < nc; depth++) { /* open the layer's own, transparent */
            open[depth] = chain[depth];
            memset(pp->group + (size_t)depth * px * 5, 0,
                   (size_t)rows * (size_t)w * 5 * sizeof *pp->group);
        }
        const unsigned char *cov;
        size_t stride;
        if ((st = cover(ctx, l, y0, rows, &cov, &stride)) || !cov)
            continue;
        const int g = pp->own[l] ? -1 : aa_scene_layer_clip(s, l);
        const double *gm = g >= 0 ? pp->mask + (size_t)pp->slot[g] * px : NULL;
        /* gradient paint: the library's colour per pixel (peer.h) */
        const float *rgba = NULL;
        size_t rstride = 0;
        if (aa_scene_layer_gradient(s, l, NULL)) {
            if (!shade) {
                st = aa_fail(AA_EINVAL, "layer %d has gradient paint and this peer draws none",
                             l);
                break;
            }
            /* the paint is wanted only where the layer mixes in (a > 0
             * below): its covered span on the band, within its clip */
            int x0 = w, x1 = 0;
            for (int j = 0; j < rows; j++) {
                const unsigned char *cr = cov + (size_t)j * stride;
                const double *gr = gm ? gm + (size_t)j * (size_t)w : NULL;
                for (int i = 0; i < x0; i++)
                    if (cr[i] && (!gr || gr[i] > 0.0)) {
                        x0 = i;
                        break;
                    }
                for (int i = w - 1; i >= x1 && i >= x0; i--)
                    if (cr[i] && (!gr || gr[i] > 0.0)) {
                        x1 = i + 1;
                        break;
                    }
            }
            if (x0 >= x1)
                continue; /* nothing of the layer shows on the band */
            if (aa__peer_shade_whole)
                x0 = 0, x1 = w;
            if ((st = shade(ctx, l, y0, rows, x0, x1, &rgba, &rstride)))
                break;
        }
        if (!depth && !gm && !rgba) { /* as ever: bit for bit what painting did before clips */
            for (int j = 0; j < rows; j++)
                aa_peer_composite_row(s, l, cov + (size_t)j * stride, w, aa_pixel(out, 0, y0 + j));
            continue;
        }
        const aa_rgb c = aa_scene_layer_colour(s, l);
        const double alpha = aa_scene_layer_alpha(s, l);
        double e[3];
        for (int q = 0; q < 3; q++)
            e[q] = alpha * aa_srgb_encode(c.c[q]);
        double *buf = depth ? pp->group + (size_t)(depth - 1) * px * 5 : NULL;
        for (int j = 0; j < rows; j++) {
            double *v = aa_pixel(out, 0, y0 + j);
            for (int i = 0; i < w; i++, v += 3) {
                const size_t k = (size_t)j * (size_t)w + (size_t)i;
                const unsigned char b = cov[(size_t)j * stride + (size_t)i];
                const double a = gm ? b / 255.0 * gm[k] : b / 255.0;
                if (!(a > 0.0))
                    continue;
                double ep[3], ap = alpha; /* the pixel's encoded premultiplied paint */
                const double *ek = e;
                if (rgba) {
                    const float *r = rgba + (size_t)j * rstride + 4 * (size_t)i;
                    for (int q = 0; q < 3; q++)
                        ep[q] = alpha * r[q];
                    ap = alpha * r[3], ek = ep;
                }
                if (!buf) {
                    if (rgba)
                        composite_paint_px(ek, ap, a, v);
                    else
                        composite_px(&c, alpha, e, a, v);
                    continue;
                }
                /* into the group: the layer's encoded premultiplied colour
                 * under alpha a alpha, source over (peer.h) */
                double *p = buf + 5 * k;
                const double aa = a * ap;
                p[0] = a + (1.0 - a) * p[0];
                for (int q = 0; q < 3; q++)
                    p[1 + q] = a * ek[q] + (1.0 - aa) * p[1 + q];
                p[4] = aa + (1.0 - aa) * p[4];
            }
        }
    }
    for (; depth > 0 && !st; depth--)
        group_close(pp, out, y0, rows, depth, aa_scene_group_opacity(s, open[depth - 1]));
    return st;
}

/*
 * The cubic of a piece of angle h = b - a of the arc
 * P(t) = c + u cos t + v sin t, whose tangent is P'(t) = -u sin t + v cos t:
 *     P(a),  P(a) + k P'(a),  P(b) - k P'(b),  P(b),   k = 4/3 tan(h/4).
 * The ellipse is the image of the unit circle under the affine map
 * x -> c + [u v] x, and an affine map takes a Bezier arc to the arc of the
 * mapped control points, so it is enough to fit the circle.  Take the unit
 * circle's arc from -theta to theta (theta = h/2): by symmetry the cubic
 * with controls at distance k along the two end tangents is symmetric
 * about the x axis, and asking its midpoint B(1/2) = (P0 + 3 P1 + 3 P2 +
 * P3)/8 to lie on the circle gives, in x,
 *     (2 cos theta + 6 (cos theta + k sin theta)) / 8 = 1,
 *     k = 4 (1 - cos theta) / (3 sin theta) = 4/3 tan(theta/2) = 4/3 tan(h/4).
 * Its error: |B(t)|^2 - 1 is a polynomial of degree 6 with double roots at
 * t = 0 and 1 (on the circle and tangent there) and at t = 1/2 (on the
 * circle, and symmetric), so it is C t^2 (1-t)^2 (2t-1)^2 with C = |A|^2/4,
 * A = P3 - P0 + 3 (P1 - P2) the cubic's leading coefficient.  Here
 * A = (0, 6 k cos theta - 4 sin theta) = (0, -8 s^3/(1 + s^2)),
 * s = tan(theta/2), and the maximum of t^2 (1-t)^2 (2t-1)^2 is 1/108
 * (at t (1-t) = 1/6), so
 *     max |B|^2 - 1 = 4 s^6 / (27 (1 + s^2)^2)
 *                   = (4/27) sin^6(h/4) / cos^2(h/4)   (>= 0: outside),
 * 5.4513e-4 for h = 90 degrees: the radius grows by at most 2.7253e-4.
 * Mapped by [u v], the cubic stays between the ellipse and the ellipse
 * scaled by 1 + e about its centre.
 */
int aa_peer_arc_cubics(const aa_edge *e, double c[AA_PEER_ARC_CUBICS][6])
{
    double dt = e->t1 - e->t0;
    /* |dt| <= 2 pi up to rounding: a last piece a hair over 90 degrees
     * from that rounding is kept rather than made a fifth */
    int n = (int)ceil(fabs(dt) / (M_PI / 2) - 1e-9);
    if (n < 1)
        n = 1;
    if (n > AA_PEER_ARC_CUBICS)
        n = AA_PEER_ARC_CUBICS;
    double h = dt / n, k = 4.0 / 3.0 * tan(h / 4.0);
    double ca = cos(e->t0), sa = sin(e->t0);
    double px = e->x0, py = e->y0;
    for (int q = 0; q < n; q++) {
        double b = q + 1 == n ? e->t1 : e->t0 + (q + 1) * h;
        double cb = cos(b), sb = sin(b);
        double qx = q + 1 == n ? e->x1 : e->cx + e->ux * cb + e->vx * sb;
        double qy = q + 1 == n ? e->y1 : e->cy + e->uy * cb + e->vy * sb;
        c[q][0] = px + k * (-e->ux * sa + e->vx * ca);
        c[q][1] = py + k * (-e->uy * sa + e->vy * ca);
        c[q][2] = qx - k * (-e->ux * sb + e->vx * cb);
        c[q][3] = qy - k * (-e->uy * sb + e->vy * cb);
        c[q][4] = qx, c[q][5] = qy;
        px = qx, py = qy, ca = cb, sa = sb;
    }
    return n;
}

void aa_peer_arc_extent(const aa_edge *e, double *hx, double *hy)
{
    *hx = hypot(e->ux, e->vx);
    *hy = hypot(e->uy, e->vy);
}
