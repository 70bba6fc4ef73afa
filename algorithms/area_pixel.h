/*
 * area_pixel.h: what Catmull's recursive pixel integrater needs in a pixel,
 * shared by its two forms: for opaque scenes (area_catmull.c, splitting on
 * the front-most layer's edges) and for scenes that composite
 * (area_composite.c, splitting on every edge).  Static functions, each
 * file its own copy, so that neither form's code depends on the other.
 */
#ifndef AA_AREA_PIXEL_H
#define AA_AREA_PIXEL_H

#include "area_internal.h"

#include <string.h>

/* Winding numbers at pixel-local point (x, y) of pixel i. */
static void cm_winding(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                       double x, double y, int *out)
{
    memcpy(out, w, (size_t)r->S->nl * sizeof *w);
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &r->wk->seg[in[k].idx];
        if (s->p->flat || !(s->va <= y && y < s->vb))
            continue;
        if ((double)(s->c0 - i) + u_at(s, tau_of_v(s, y)) < x)
            out[s->p->layer] += s->p->dir;
    }
}

/* Split level d's region and edges by the line through e (keeping side
 * `side` of it) into level d + 1. */
/* A splitting line: side * (a x + b y + c) is the signed distance. */
typedef struct cm_line {
    double a, b, c, side;
} cm_line;

/* The distance of (x, y) from the line, zero within CM_EPS. */
static inline double cm_dist(const cm_line *l, double x, double y)
{
    double d = l->side * (l->a * x + l->b * y + l->c);
    return fabs(d) <= CM_EPS ? 0.0 : d;
}

static void cm_split(cm_level *from, cm_level *to, const cm_edge *e, double side)
{
    double a = e->y1 - e->y0, b = e->x0 - e->x1;
    double len = sqrt(a * a + b * b);
    a /= len, b /= len;
    cm_line L = {a, b, -(a * e->x0 + b * e->y0), side};
    /* the region: Sutherland-Hodgman against one side */
    to->nv = 0;
    for (int k = 0; k < from->nv; k++) {
        int m = (k + 1) % from->nv;
        double dk = cm_dist(&L, from->vx[k], from->vy[k]);
        double dm = cm_dist(&L, from->vx[m], from->vy[m]);
        if (dk >= 0.0 && to->nv < CM_MAX_VERTS) {
            to->vx[to->nv] = from->vx[k];
            to->vy[to->nv++] = from->vy[k];
        }
        if (((dk > 0.0 && dm < 0.0) || (dk < 0.0 && dm > 0.0)) && to->nv < CM_MAX_VERTS) {
            double t = dk / (dk - dm);
            to->vx[to->nv] = from->vx[k] + t * (from->vx[m] - from->vx[k]);
            to->vy[to->nv++] = from->vy[k] + t * (from->vy[m] - from->vy[k]);
        }
    }
    /* the edges: those on the line are clipped (dropped), the others cut */
    to->ne = 0;
    for (int k = 0; k < from->ne; k++) {
        const cm_edge *f = &from->e[k];
        if (f == e)
            continue;
        double d0 = cm_dist(&L, f->x0, f->y0), d1 = cm_dist(&L, f->x1, f->y1);
        if ((d0 <= 0.0 && d1 <= 0.0))
            continue; /* other side, or on the line */
        cm_edge g = *f;
        if (d0 < 0.0 || d1 < 0.0) {
            double t = d0 / (d0 - d1), x = f->x0 + t * (f->x1 - f->x0),
                   yy = f->y0 + t * (f->y1 - f->y0);
            if (d0 < 0.0)
                g.x0 = x, g.y0 = yy;
            else
                g.x1 = x, g.y1 = yy;
        }
        to->e[to->ne++] = g;
    }
}


/* Clip the segment to 0 <= x <= 1; 0 if nothing (of length) is left. */
static int clip_unit_x(cm_edge *e)
{
    double t0 = 0.0, t1 = 1.0, dx = e->x1 - e->x0;
    if (dx == 0.0) {
        if (!(e->x0 > 0.0 && e->x0 < 1.0))
            return 0;
    } else {
        double ta = (0.0 - e->x0) / dx, tb = (1.0 - e->x0) / dx;
        if (ta > tb) {
            double t = ta;
            ta = tb, tb = t;
        }
        t0 = fmax(t0, ta), t1 = fmin(t1, tb);
        if (!(t1 > t0))
            return 0;
    }
    double x0 = e->x0 + t0 * dx, y0 = e->y0 + t0 * (e->y1 - e->y0);
    double x1 = e->x0 + t1 * dx, y1 = e->y0 + t1 * (e->y1 - e->y0);
    e->x0 = fmin(fmax(x0, 0.0), 1.0), e->y0 = y0;
    e->x1 = fmin(fmax(x1, 0.0), 1.0), e->y1 = y1;
    return fabs(e->x1 - e->x0) + fabs(e->y1 - e->y0) > 1e-15;
}


/* The area of level lv's region (0 if none) and its centroid (cx, cy). */
static inline double cm_region(const cm_level *lv, double *cx_out, double *cy_out)
{
    double area = 0.0, cx = 0.0, cy = 0.0;
    if (lv->nv < 3)
        return 0.0;
    /* relative to the first vertex, so that a sliver's centroid is found
     * to its own size, not to the pixel's (a region 1e-9 px wide would
     * otherwise get a centroid 1e-7 px off, outside itself) */
    const double ox = lv->vx[0], oy = lv->vy[0];
    for (int k = 1; k + 1 < lv->nv; k++) {
        double ax = lv->vx[k] - ox, ay = lv->vy[k] - oy;
        double bx = lv->vx[k + 1] - ox, by = lv->vy[k + 1] - oy;
        double cr = ax * by - bx * ay;
        area += cr;
        cx += (ax + bx) * cr;
        cy += (ay + by) * cr;
    }
    if (area == 0.0)
        return 0.0;
    *cx_out = ox + cx / (3.0 * area), *cy_out = oy + cy / (3.0 * area);
    return 0.5 * fabs(area);
}

/* Level 0 for pixel i of the cluster: the pixel's square and the segs'
 * edges clipped to it; 0 if there are more than CM_MAX_EDGES. */
static inline int cm_pixel(const ar_row *r, const ar_key *in, size_t n, int i, cm_level *lv)
{
    lv->ne = 0;
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &r->wk->seg[in[k].idx];
        if (s->ca > i || s->cb < i)
            continue;
        cm_edge e;
        if (s->p->flat)
            e = (cm_edge){s->p->xmin - i, s->va, s->p->xmax - i, s->va, s->p->layer};
        else
            e = (cm_edge){(double)(s->c0 - i) + s->ua, s->va, (double)(s->c0 - i) + s->ub,
                          s->vb, s->p->layer};
        if (!clip_unit_x(&e))
            continue;
        if (lv->ne == CM_MAX_EDGES)
            return 0;
        lv->e[lv->ne++] = e;
    }
    lv->nv = 4;
    lv->vx[0] = 0, lv->vy[0] = 0, lv->vx[1] = 1, lv->vy[1] = 0;
    lv->vx[2] = 1, lv->vy[2] = 1, lv->vx[3] = 0, lv->vy[3] = 1;
    return 1;
}

/* Catmull's integrater on level d in a scene that composites: every
 * covering layer shows, so no layer hides the edges behind it.  Split on
 * any edge left (Catmull's clipper), until a region holds none; its winding
 * numbers are then one state throughout, read at its centroid (cx, cy), and
 * leaf adds the region's integral (area: its area; lv: its polygon) to sum. */
typedef void cm_leaf_fn(const ar_row *r, const cm_level *lv, double area, const int *wind,
                        int i, double *sum);
static inline void cm_split_all(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                                int d, double *sum, cm_leaf_fn *leaf)
{
    cm_level *lv = &r->wk->cm[d];
    double cx, cy, area = cm_region(lv, &cx, &cy);
    if (area == 0.0)
        return;
    if (lv->ne) {
        cm_split(lv, lv + 1, &lv->e[0], 1.0);
        cm_split_all(r, in, n, w, i, d + 1, sum, leaf);
        cm_split(lv, lv + 1, &lv->e[0], -1.0);
        cm_split_all(r, in, n, w, i, d + 1, sum, leaf);
        return;
    }
    int *wind = r->wk->wtmp;
    cm_winding(r, in, n, w, i, cx, cy, wind);
    leaf(r, lv, area, wind, i, sum);
}

/* Catmull's integrater of one form (integrate: cm_integrate or
 * cm_integrate_all) over every pixel of the cluster; 0 if a pixel has too
 * many edges for it (nothing written then: a first pass counts them). */
typedef void cm_integrate_fn(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                             int d, double *sum);
static inline int cm_cluster(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                             const int *w, cm_integrate_fn *integrate)
{
    int a = lo < 0 ? 0 : lo, b = hi >= r->W ? r->W - 1 : hi;
    for (int pass = 0; pass < 2; pass++)
        for (int i = a; i <= b; i++) {
            cm_level *lv = &r->wk->cm[0];
            if (!cm_pixel(r, in, n, i, lv))
                return 0;
            if (pass == 0)
                continue; /* first pass: only check the edge counts */
            double sum[3] = {0, 0, 0};
            integrate(r, in, n, w, i, 0, sum);
            store_px(r, r->px + 3 * (size_t)i, sum);
        }
    return 1;
}

#endif /* AA_AREA_PIXEL_H */
