/*
 * visible.c: the visible parts of a scene's edges near one pixel, with the
 * change of colour across each (visible.h explains the decomposition).
 */
#include "visible.h"
#include "core.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Narrowings of one band to the nearest meeting of neighbours before it is
 * taken as it is (a safeguard: each narrowing removes a meeting). */
#define VIS_MAX_NARROW 64

struct aa__vis_piece {
    const aa_piece *p;
    double lo, hi;         /* the piece's rows inside the window's rows */
    double run_lo, run_hi; /* the open run */
    double *jump;          /* its jump (dims values, in the workspace) */
    double t[2];           /* an offset piece's parameters at the band's ends */
    int id;                /* index in the scene */
    int open, inside;
};

struct aa__vis_order {
    double x; /* at the band's middle */
    int id;   /* ties: the scene's index */
    int li;   /* index into lp */
};

static size_t round_up(size_t n)
{
    return (n + 63) & ~(size_t)63;
}

/* Capacities for n pieces: heights (two ends and up to four crossings of the
 * window's sides per piece, one per flat piece, the rows' two ends), and a
 * flat piece's breaks (one per crossing piece, two per other flat piece). */
static size_t ev_cap(size_t n)
{
    return 9 * n + 4; /* a cubic crosses each side up to 3 times */
}
static size_t fx_cap(size_t n)
{
    return 3 * n + 4;
}

size_t aa__vis_size(const aa_scene *s, int dims)
{
    size_t n;
    aa_scene_pieces(s, &n);
    int nl = aa_scene_layer_count(s);
    size_t nw = (size_t)(nl > 0 ? nl : 1), d = (size_t)dims;
    return round_up(n * sizeof(aa__vis_piece)) + round_up(n * sizeof(aa__vis_order)) +
           round_up(n * sizeof(const aa_piece *)) + round_up(ev_cap(n) * sizeof(double)) +
           round_up(fx_cap(n) * sizeof(double)) + round_up(n * d * sizeof(double)) +
           3 * round_up(d * sizeof(double)) + 2 * round_up(nw * sizeof(int));
}

void aa__vis_bind(aa__vis *v, const aa_scene *s, int dims, void *block)
{
    size_t n, d = (size_t)dims;
    v->scene = s;
    v->base = aa_scene_pieces(s, &n);
    v->nl = aa_scene_layer_count(s);
    v->dims = dims;
    size_t nw = (size_t)(v->nl > 0 ? v->nl : 1);
    char *b = block;
    v->lp = (aa__vis_piece *)b, b += round_up(n * sizeof(aa__vis_piece));
    v->ord = (aa__vis_order *)b, b += round_up(n * sizeof(aa__vis_order));
    v->flats = (const aa_piece **)b, b += round_up(n * sizeof(const aa_piece *));
    v->ev = (double *)b, b += round_up(ev_cap(n) * sizeof(double));
    v->fx = (double *)b, b += round_up(fx_cap(n) * sizeof(double));
    v->jumps = (double *)b, b += round_up(n * d * sizeof(double));
    v->va = (double *)b, b += round_up(d * sizeof(double));
    v->vb = (double *)b, b += round_up(d * sizeof(double));
    v->vj = (double *)b, b += round_up(d * sizeof(double));
    v->wind = (int *)b, b += round_up(nw * sizeof(int));
    v->wind2 = (int *)b;
}

/* The values of a winding: the sink's, or the colour. */
static inline void values_of(const aa__vis *v, const aa__vis_sink *sk, const int *wind,
                             double *out)
{
    if (sk->values) {
        sk->values(sk->ctx, wind, out);
        return;
    }
    aa_rgb c = aa_scene_colour_of(v->scene, wind);
    out[0] = c.c[0], out[1] = c.c[1], out[2] = c.c[2];
}

static inline int nonzero(const double *j, int dims)
{
    for (int d = 0; d < dims; d++)
        if (j[d] != 0.0)
            return 1;
    return 0;
}

static inline int same(const double *a, const double *b, int dims)
{
    for (int d = 0; d < dims; d++)
        if (!(a[d] == b[d]))
            return 0;
    return 1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void aa__vis_sort(double *v, size_t n)
{
    if (n > 32) {
        qsort(v, n, sizeof *v, cmp_double);
        return;
    }
    for (size_t a = 1; a < n; a++) {
        double t = v[a];
        size_t b = a;
        while (b > 0 && v[b - 1] > t)
            v[b] = v[b - 1], b--;
        v[b] = t;
    }
}

static inline int before(const aa__vis_order *a, const aa__vis_order *b)
{
    return a->x < b->x || (a->x == b->x && a->id < b->id);
}

static int cmp_order(const void *a, const void *b)
{
    const aa__vis_order *x = a, *y = b;
    return before(y, x) - before(x, y);
}

static void sort_order(aa__vis_order *o, size_t n)
{
    if (n > 24) {
        qsort(o, n, sizeof *o, cmp_order);
        return;
    }
    for (size_t a = 1; a < n; a++) {
        aa__vis_order t = o[a];
        size_t b = a;
        while (b > 0 && before(&t, &o[b - 1])) {
            o[b] = o[b - 1];
            b--;
        }
        o[b] = t;
    }
}

static void flush(aa__vis_piece *P, const aa__vis_sink *sk, int dims)
{
    if (!P->open)
        return;
    P->open = 0;
    if (sk->run && (sk->zero_runs || (P->inside && nonzero(P->jump, dims))))
        sk->run(sk->ctx, P->p, P->run_lo, P->run_hi, P->jump, P->inside);
}

/* 1 if x (a piece's at a band's middle) is in the window: the piece is
 * then inside it all through the band (band_sweep's test). */
static inline int in_window(double x, double xl, double xr)
{
    return x >= xl && x <= xr;
}

/* One band [lo, hi] whose pieces (ord[0 .. na), sorted at its middle) meet
 * nowhere inside it: sweep left to right from the winding left of the
 * window, extending each piece's run or starting a new one. */
static void band_sweep(aa__vis *v, const aa_strip *st, double xl, double xr, double lo,
                       double hi, size_t na, const aa__vis_sink *sk)
{
    const int dims = v->dims;
    int *W = v->wind, told = 0;
    double *cl = v->va, *cr = v->vb, *j = v->vj;
    aa_strip_winding_left(st, 0.5 * (lo + hi), W);
    values_of(v, sk, W, cl);
    for (size_t a = 0; a < na; a++) {
        const aa__vis_order *o = &v->ord[a];
        aa__vis_piece *P = &v->lp[o->li];
        const aa_piece *p = P->p;
        if (!told && o->x >= xl) {
            if (sk->band)
                sk->band(sk->ctx, lo, hi, W);
            told = 1;
        }
        int inside = in_window(o->x, xl, xr);
        W[p->layer] += p->dir;
        values_of(v, sk, W, cr);
        for (int d = 0; d < dims; d++)
            j[d] = inside ? cr[d] - cl[d] : 0.0;
        double *t = cl;
        cl = cr, cr = t;
        if (P->open && P->run_hi == lo) {
            if (P->inside == inside && same(P->jump, j, dims)) {
                P->run_hi = hi;
                continue;
            }
            if (sk->merge_outside && (!inside || !P->inside)) {
                /* a part outside the window joins the run beside it */
                if (inside)
                    P->inside = 1, memcpy(P->jump, j, (size_t)dims * sizeof *j);
                P->run_hi = hi;
                continue;
            }
        }
        flush(P, sk, dims);
        P->open = 1;
        P->inside = inside;
        P->run_lo = lo;
        P->run_hi = hi;
        memcpy(P->jump, j, (size_t)dims * sizeof *j);
    }
    if (!told && sk->band)
        sk->band(sk->ctx, lo, hi, W);
}

/* The parts of flat piece f (at height y, clipped to [xl, xr]) between the
 * places its colours change, each with the colour above minus below. */
static void flat_parts(aa__vis *v, const aa_strip *st, const aa_piece *const *loc, size_t nloc,
                       const aa_piece *f, double xl, double xr, const aa__vis_sink *sk)
{
    double y = f->y0, a = fmax(f->xmin, xl), b = fmin(f->xmax, xr);
    int idf = (int)(f - v->base);
    size_t nx = 0;
    v->fx[nx++] = a;
    v->fx[nx++] = b;
    for (size_t q = 0; q < nloc; q++) {
        const aa_piece *g = loc[q];
        double x[2];
        int m = 0;
        if (g->kind == AA_PIECE_FLAT) {
            if (g != f && g->y0 == y)
                x[m++] = g->x0, x[m++] = g->x1;
        } else if (g->y0 <= y && y <= g->y1) {
            x[m++] = aa_piece_x_at(g, y);
        }
        for (int k = 0; k < m; k++)
            if (x[k] > a && x[k] < b)
                v->fx[nx++] = x[k];
    }
    aa__vis_sort(v->fx, nx);
    for (size_t k = 0; k + 1 < nx; k++) {
        double xa = v->fx[k], xb = v->fx[k + 1];
        if (!(xa < xb))
            continue;
        double xm = 0.5 * (xa + xb);
        /* below the flat piece: the scene's rule at height y */
        int *W = v->wind2;
        aa_strip_winding_left(st, y, W);
        for (size_t q = 0; q < nloc; q++) {
            const aa_piece *g = loc[q];
            if (g->dir && g->y0 <= y && y < g->y1 && aa_piece_x_at(g, y) < xm)
                W[g->layer] += g->dir;
        }
        /* above: undo the flat pieces here, the later ones first (crossing
         * down, a rightward flat edge lowers its layer's winding by one) */
        int df = 0;
        for (size_t q = 0; q < nloc; q++) {
            const aa_piece *g = loc[q];
            if (g->kind != AA_PIECE_FLAT || g->y0 != y || !(fmin(g->x0, g->x1) < xm) ||
                !(xm < fmax(g->x0, g->x1)))
                continue;
            int d = g->x1 > g->x0 ? -1 : 1, id = (int)(g - v->base);
            if (g == f)
                df = d;
            if (id >= idf)
                W[g->layer] -= d;
        }
        values_of(v, sk, W, v->va);
        W[f->layer] += df;
        values_of(v, sk, W, v->vb);
        for (int d = 0; d < v->dims; d++)
            v->vj[d] = v->va[d] - v->vb[d];
        if (nonzero(v->vj, v->dims))
            sk->flat(sk->ctx, f, xa, xb, y, v->vj);
    }
}

/* An offset piece's parameter at height y (the one aa_piece_meet would
 * solve for: its ends' outside its rows, else the offset solver's root in
 * y); NaN for other kinds, which take none. */
static double param_at(const aa_piece *p, double y)
{
    if (p->kind != AA_PIECE_OFFSET)
        return NAN;
    if (!(y > p->y0))
        return p->ot0;
    if (!(y < p->y1))
        return p->ot1;
    return aa__offset_solve_d(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y);
}

/* The parameters of the band's offset pieces (ord[0 .. na)) at height y,
 * as their e-th end (the same roots aa_piece_meet would solve for). */
static void params_at(aa__vis *v, size_t na, double y, int e)
{
    for (size_t a = 0; a < na; a++) {
        aa__vis_piece *P = &v->lp[v->ord[a].li];
        if (P->p->kind == AA_PIECE_OFFSET)
            P->t[e] = param_at(P->p, y);
    }
}

void aa__vis_window(aa__vis *v, const aa_strip *st, double xl, double xr, double ya, double yb,
                    const aa__vis_sink *sk)
{
    size_t nloc, k = 0, nf = 0, ne = 0;
    const aa_piece *const *loc = aa_strip_local(st, &nloc);
    int flats = sk->flat != NULL;
    for (size_t q = 0; q < nloc; q++) {
        const aa_piece *p = loc[q];
        if (p->kind == AA_PIECE_FLAT) {
            /* the winding left of the window may change at a flat piece's
             * height (a piece left of it ends there and the path goes on
             * along the flat one), whether or not flats are reported */
            if (p->y0 > ya && p->y0 < yb)
                v->ev[ne++] = p->y0;
            if (flats && p->y0 >= ya && p->y0 <= yb && fmax(p->xmin, xl) < fmin(p->xmax, xr))
                v->flats[nf++] = p;
            continue;
        }
        double lo = fmax(p->y0, ya), hi = fmin(p->y1, yb);
        if (!(lo < hi))
            continue;
        aa__vis_piece *P = &v->lp[k++];
        P->p = p;
        P->lo = lo;
        P->hi = hi;
        P->id = (int)(p - v->base);
        P->open = 0;
        P->jump = v->jumps + (k - 1) * (size_t)v->dims;
        v->ev[ne++] = lo;
        v->ev[ne++] = hi;
        const double side[2] = {xl, xr};
        double xa = p->xmin, xb = p->xmax;
        if ((xa < xl && xl < xb) || (xa < xr && xr < xb))
            aa_piece_xrange(p, lo, hi, &xa, &xb); /* its extent in the rows */
        for (int e = 0; e < 2; e++) {
            /* only a piece whose extent holds the side can cross it */
            if (!(xa < side[e] && side[e] < xb))
                continue;
            double ys[3];
            int m = aa_piece_meet_x(p, side[e], ys);
            for (int r = 0; r < m; r++)
                if (ys[r] > lo && ys[r] < hi)
                    v->ev[ne++] = ys[r];
        }
    }
    v->ev[ne++] = ya;
    v->ev[ne++] = yb;
    aa__vis_sort(v->ev, ne);
    for (size_t e = 0; e + 1 < ne; e++) {
        double e0 = v->ev[e], e1 = v->ev[e + 1];
        if (!(e0 < e1))
            continue;
        /* the pieces present all through: every end is a height above */
        size_t na = 0;
        for (size_t i = 0; i < k; i++)
            if (v->lp[i].lo <= e0 && v->lp[i].hi >= e1)
                v->ord[na++] = (aa__vis_order){0.0, v->lp[i].id, (int)i};
        double lo = e0;
        params_at(v, na, lo, 0);
        while (lo < e1) {
            double hi = e1;
            params_at(v, na, hi, 1);
            for (int it = 0;; it++) {
                double mid = 0.5 * (lo + hi);
                for (size_t a = 0; a < na; a++)
                    v->ord[a].x = aa_piece_x_at(v->lp[v->ord[a].li].p, mid);
                sort_order(v->ord, na);
                if (it >= VIS_MAX_NARROW)
                    break;
                double eps = 16.0 * DBL_EPSILON * fmax(1.0, fmax(fabs(lo), fabs(hi)));
                double m = hi;
                for (size_t a = 0; a + 1 < na; a++) {
                    double ys[2];
                    if (sk->inside_meets && !in_window(v->ord[a].x, xl, xr) &&
                        !in_window(v->ord[a + 1].x, xl, xr))
                        continue;
                    const aa__vis_piece *P = &v->lp[v->ord[a].li], *Q = &v->lp[v->ord[a + 1].li];
                    int nm = aa__piece_meet_at(P->p, Q->p, lo, hi, P->t, Q->t, ys, 2);
                    for (int r = 0; r < nm; r++)
                        if (ys[r] > lo + eps && ys[r] < hi - eps && ys[r] < m)
                            m = ys[r];
                }
                if (!(m < hi))
                    break;
                hi = m;
                params_at(v, na, hi, 1);
            }
            band_sweep(v, st, xl, xr, lo, hi, na, sk);
            for (size_t a = 0; a < na; a++) {
                aa__vis_piece *P = &v->lp[v->ord[a].li];
                P->t[0] = P->t[1];
            }
            lo = hi;
        }
    }
    for (size_t i = 0; i < k; i++)
        flush(&v->lp[i], sk, v->dims);
    for (size_t q = 0; q < nf; q++)
        flat_parts(v, st, loc, nloc, v->flats[q], xl, xr, sk);
}
