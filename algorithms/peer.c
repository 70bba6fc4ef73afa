/*
 * peer.c: the checks and helpers the peer rasterizers share (peer.h).
 */
#include "peer.h"
#include "core.h"
#include "path.h"

#include <math.h>

int aa_peer_check_filter(const char *name, const aa_filter *f)
{
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL,
                       "%s computes box-filter coverage only: it is measured against the box "
                       "reference (use -f box; tent, gauss and cone are not supported)",
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

void aa_peer_fill(aa_image *out, int j, int i0, int i1, double v)
{
    double *px = aa_pixel(out, 0, j) + 3 * (size_t)i0;
    for (int i = i0; i < i1; i++, px += 3)
        px[0] = px[1] = px[2] = v;
}

int aa_peer_paintable(const aa_scene *s)
{
    return !aa_scene_is_clipped(s) && (!aa_scene_is_grey(s) || !aa_scene_is_opaque(s) ||
                                       aa_scene_layer_count(s) > 1);
}

int aa_peer_painted_check(const char *name, const aa_scene *s, int strokes_filled)
{
    if (aa_scene_group_count(s) > 0)
        return aa_fail(AA_EINVAL,
                       "%s: this scene has groups of opacity (SVG's opacity on a group or on "
                       "a shape with a fill and a stroke), which its layer by layer painting "
                       "does not draw",
                       name);
    size_t ne;
    const aa_edge *e = aa_scene_edges(s, &ne);
    for (size_t k = 0; k < ne; k++)
        if (e[k].quad == 4 && (strokes_filled || aa_scene_layer_stroked(s, e[k].layer) < 0))
            return aa_fail(AA_EINVAL,
                           "%s: layer %d is filled from the exact offset curves of a Bezier "
                           "arc's stroke, which its outlines cannot hold",
                           name, e[k].layer);
    return AA_OK;
}

void aa_peer_background_row(const aa_scene *s, aa_image *out, int j, int n)
{
    const aa_rgb bg = aa_scene_background(s);
    double *px = aa_pixel(out, 0, j);
    for (int i = 0; i < n; i++, px += 3)
        px[0] = bg.c[0], px[1] = bg.c[1], px[2] = bg.c[2];
}

void aa_peer_composite_row(const aa_scene *s, int layer, const unsigned char *cov, int n,
                           double *px)
{
    const aa_rgb c = aa_scene_layer_colour(s, layer);
    const double alpha = aa_scene_layer_alpha(s, layer);
    double e[3];
    for (int q = 0; q < 3; q++)
        e[q] = alpha * aa_srgb_encode(c.c[q]);
    for (int i = 0; i < n; i++, px += 3) {
        if (!cov[i])
            continue;
        const double a = cov[i] / 255.0;
        for (int q = 0; q < 3; q++) {
            const double inside = alpha == 1.0 ? c.c[q]
                                               : aa_srgb_decode(e[q] + (1.0 - alpha) *
                                                                           aa_srgb_encode(px[q]));
            px[q] = a * inside + (1.0 - a) * px[q];
        }
    }
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
