/*
 * strip.c: windowed queries along a horizontal band of a scene.
 *
 * Per band [ya, yb] the strip gathers the pieces that meet it, with their x
 * extent inside the band, sorted by left and by right end.  Windows
 * [xl, xr] then sweep left to right: a piece enters when its left end
 * passes xr and leaves when its right end passes xl.  The pieces in between
 * are the window's local pieces; a piece that has left contributes to the
 * winding numbers of every point of the window:
 *
 *  - if it spans the whole band (a "full" piece) it meets every line of
 *    the band left of the window, so its direction is added once to `base`;
 *  - otherwise (it ends inside the band) it meets only the lines between its
 *    ends, so it is kept in the short `left` list and tested per query.
 *
 * So the winding at (x, y) in the window is base + the left pieces active
 * at y + the local pieces crossing line y left of x, and a window with no
 * local piece is uniform.  The cost of a window is its local pieces, not
 * the band's: on `crow` a window holds one or two arcs of the 96.
 */
#include "scene_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct strip_item {
    const aa_piece *p;
    double xmin, xmax; /* extent inside the band */
    int full;          /* meets every line of the band */
} strip_item;

typedef struct strip_key {
    double key;
    size_t index;
} strip_key;

typedef struct strip_cross {
    double x;
    int dir, layer;
} strip_cross;

struct aa_strip {
    const aa_scene *s;
    double ya, yb, xl, xr;
    strip_item *item; /* sorted by xmin */
    size_t n, cap;
    strip_key *by_max;
    size_t *pos;
    unsigned char *state; /* 0 waiting, 1 local, 2 left */
    size_t next_in, next_out;
    size_t partial; /* crossing pieces that end inside the band */
    size_t *local;
    const aa_piece **local_p;
    size_t nlocal;
    size_t *left;
    size_t nleft;
    int nl;
    int *base, *wind;
    strip_cross *cross;
    int failed;
};

aa_strip *aa_strip_new(const aa_scene *s)
{
    aa_strip *st = calloc(1, sizeof *st);
    if (!st) {
        aa_fail(AA_ENOMEM, "out of memory for a strip");
        return NULL;
    }
    st->s = s;
    st->nl = s->nlayers > 0 ? s->nlayers : 1;
    st->base = calloc((size_t)st->nl, sizeof *st->base);
    st->wind = calloc((size_t)st->nl, sizeof *st->wind);
    if (!st->base || !st->wind) {
        aa_strip_free(st);
        aa_fail(AA_ENOMEM, "out of memory for a strip");
        return NULL;
    }
    return st;
}

void aa_strip_free(aa_strip *st)
{
    if (!st)
        return;
    free(st->item);
    free(st->by_max);
    free(st->pos);
    free(st->state);
    free(st->local);
    free(st->local_p);
    free(st->left);
    free(st->base);
    free(st->wind);
    free(st->cross);
    free(st);
}

static int reserve(aa_strip *st, size_t need)
{
    if (need <= st->cap)
        return AA_OK;
    size_t n = st->cap ? st->cap : 64;
    while (n < need)
        n *= 2;
    void *p[8];
    p[0] = realloc(st->item, n * sizeof *st->item);
    if (p[0])
        st->item = p[0];
    p[1] = realloc(st->by_max, n * sizeof *st->by_max);
    if (p[1])
        st->by_max = p[1];
    p[2] = realloc(st->pos, n * sizeof *st->pos);
    if (p[2])
        st->pos = p[2];
    p[3] = realloc(st->state, n * sizeof *st->state);
    if (p[3])
        st->state = p[3];
    p[4] = realloc(st->local, n * sizeof *st->local);
    if (p[4])
        st->local = p[4];
    p[5] = realloc(st->local_p, n * sizeof *st->local_p);
    if (p[5])
        st->local_p = p[5];
    p[6] = realloc(st->left, n * sizeof *st->left);
    if (p[6])
        st->left = p[6];
    p[7] = realloc(st->cross, n * sizeof *st->cross);
    if (p[7])
        st->cross = p[7];
    for (int k = 0; k < 8; k++)
        if (!p[k])
            return aa_fail(AA_ENOMEM, "out of memory for a strip of %zu pieces", need);
    st->cap = n;
    return AA_OK;
}

static int visit_band(void *ctx, const aa_piece *p)
{
    aa_strip *st = ctx;
    double ya = st->ya, yb = st->yb;
    if (p->dir ? !(p->y0 <= yb && p->y1 > ya) : !(ya < p->y0 && p->y0 < yb))
        return 0;
    if (st->failed || (st->n == st->cap && reserve(st, st->n + 1))) {
        st->failed = 1;
        return 0;
    }
    strip_item *it = &st->item[st->n++];
    it->p = p;
    it->full = p->dir && p->y0 <= ya && p->y1 > yb;
    st->partial += p->dir && !it->full;
    aa_piece_xrange(p, ya, yb, &it->xmin, &it->xmax);
    return 1;
}

static int cmp_item(const void *a, const void *b)
{
    const strip_item *p = a, *q = b;
    if (p->xmin != q->xmin)
        return p->xmin < q->xmin ? -1 : 1;
    return p->p < q->p ? -1 : (p->p > q->p);
}

static int cmp_key(const void *a, const void *b)
{
    const strip_key *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->index < q->index ? -1 : (p->index > q->index);
}

/* The pieces come from the index in path order, which along a band is
 * nearly sorted by x one way or the other (scene_internal.h, AA__NEAR_SORT;
 * measured: a third of a sampling method's time on crow went to qsort). */
AA__NEAR_SORT(sort_items, strip_item, cmp_item)
AA__NEAR_SORT(sort_keys, strip_key, cmp_key)

int aa_strip_begin(aa_strip *st, double ya, double yb)
{
    if (!(ya <= yb) || !isfinite(ya) || !isfinite(yb))
        return aa_fail(AA_EINVAL, "strip band [%g, %g] is not an interval", ya, yb);
    st->ya = ya;
    st->yb = yb;
    st->n = 0;
    st->partial = 0;
    st->failed = 0;
    aa__scene_gather(st->s, ya, yb, visit_band, st);
    if (st->failed)
        return AA_ENOMEM;
    if (st->n == 0) { /* nothing in the band: every window is uniform */
        st->next_in = st->next_out = st->nlocal = st->nleft = 0;
        memset(st->base, 0, (size_t)st->nl * sizeof *st->base);
        return AA_OK;
    }
    sort_items(st->item, st->n);
    for (size_t k = 0; k < st->n; k++) {
        st->by_max[k].key = st->item[k].xmax;
        st->by_max[k].index = k;
        st->state[k] = 0;
    }
    sort_keys(st->by_max, st->n);
    st->next_in = st->next_out = st->nlocal = st->nleft = 0;
    st->xl = st->xr = -INFINITY;
    memset(st->base, 0, (size_t)st->nl * sizeof *st->base);
    return AA_OK;
}

static void enter(aa_strip *st, size_t k)
{
    st->state[k] = 1;
    st->pos[k] = st->nlocal;
    st->local[st->nlocal] = k;
    st->local_p[st->nlocal++] = st->item[k].p;
}

static void leave(aa_strip *st, size_t k)
{
    if (st->state[k] == 1) {
        size_t at = st->pos[k], last = st->local[--st->nlocal];
        st->local[at] = last;
        st->local_p[at] = st->item[last].p;
        st->pos[last] = at;
    }
    st->state[k] = 2;
    const strip_item *it = &st->item[k];
    if (!it->p->dir)
        return;
    if (it->full)
        st->base[it->p->layer] += it->p->dir;
    else
        st->left[st->nleft++] = k;
}

size_t aa_strip_window(aa_strip *st, double xl, double xr)
{
    st->xl = xl;
    st->xr = xr;
    while (st->next_in < st->n && st->item[st->next_in].xmin < xr)
        enter(st, st->next_in++);
    while (st->next_out < st->n && st->by_max[st->next_out].key <= xl)
        leave(st, st->by_max[st->next_out++].index);
    return st->nlocal;
}

const aa_piece *const *aa_strip_local(const aa_strip *st, size_t *n)
{
    *n = st->nlocal;
    return st->local_p;
}

static inline int active(const aa_piece *p, double y)
{
    return p->y0 <= y && y < p->y1;
}

int aa_strip_all_full(const aa_strip *st)
{
    return st->partial == 0;
}

double aa_strip_next_entry(const aa_strip *st)
{
    return st->next_in < st->n ? st->item[st->next_in].xmin : INFINITY;
}

int aa_strip_uniform_run(const aa_strip *st, int i, int w, double r, double y, int *wind,
                         aa_rgb *colour)
{
    /* with no piece local, nothing can leave before something enters: the
     * windows whose right end i' + 1/2 + r is at most the next entry are
     * uniform, and of the same colour */
    double last = floor(aa_strip_next_entry(st) - 0.5 - r);
    int end = last >= (double)(w - 1) ? w : (int)last + 1;
    aa_strip_winding_left(st, y, wind);
    *colour = aa_scene_colour_of(st->s, wind);
    return end > i ? end : i + 1;
}

void aa_strip_winding_left(const aa_strip *st, double y, int *wind)
{
    for (int l = 0; l < st->nl; l++) /* usually one layer: no memcpy call */
        wind[l] = st->base[l];
    for (size_t k = 0; k < st->nleft; k++) {
        const aa_piece *p = st->item[st->left[k]].p;
        if (active(p, y))
            wind[p->layer] += p->dir;
    }
}

/* The line y = yc + s, the sum exact: hi + lo, hi the sum rounded and lo
 * its rounding error (Knuth's two-sum), |lo| at most half the gap from hi
 * to its neighbour on lo's side.  No double lies strictly between hi and
 * hi + lo, so pieces' ends (doubles) compare with hi + lo as with hi if
 * lo >= 0, and as with the double below hi if lo < 0 (y0 <= hi + lo is
 * then y0 < hi, and hi + lo < y1 is hi <= y1): the line y of
 * aa_strip_winding_left, at no extra cost a piece. */
void aa_strip_winding_left_at(const aa_strip *st, double yc, double s, int *wind)
{
    double hi = yc + s, b = hi - yc, lo = (yc - (hi - b)) + (s - b);
    aa_strip_winding_left(st, lo < 0.0 ? nextafter(hi, -INFINITY) : hi, wind);
}

void aa_strip_winding(const aa_strip *st, double x, double y, int *wind)
{
    aa_strip_winding_left(st, y, wind);
    for (size_t k = 0; k < st->nlocal; k++) {
        const aa_piece *p = st->local_p[k];
        if (p->dir && active(p, y) && aa_piece_x_at(p, y) < x)
            wind[p->layer] += p->dir;
    }
}

aa_rgb aa_strip_colour_at(const aa_strip *st, double x, double y)
{
    /* a stack array for the usual few layers: the strip is not written */
    int small[32], *wind = st->nl <= 32 ? small : st->wind;
    aa_strip_winding(st, x, y, wind);
    return aa_scene_colour_of_at(st->s, wind, x, y);
}

static int same_colour(aa_rgb a, aa_rgb b)
{
    return a.c[0] == b.c[0] && a.c[1] == b.c[1] && a.c[2] == b.c[2];
}

size_t aa_strip_spans(aa_strip *st, double y, aa_span *out, size_t cap)
{
    double xl = st->xl, xr = st->xr;
    size_t nc = 0, m = 0;
    aa_strip_winding(st, xl, y, st->wind);
    for (size_t k = 0; k < st->nlocal; k++) {
        const aa_piece *p = st->local_p[k];
        if (!p->dir || !active(p, y))
            continue;
        double x = aa_piece_x_at(p, y);
        if (x < xl || x >= xr)
            continue;
        /* insertion sort: a window holds few crossings */
        size_t at = nc++;
        while (at > 0 && st->cross[at - 1].x > x) {
            st->cross[at] = st->cross[at - 1];
            at--;
        }
        st->cross[at].x = x;
        st->cross[at].dir = p->dir;
        st->cross[at].layer = p->layer;
    }
    double cur = xl;
    for (size_t k = 0; k <= nc; k++) {
        double next = k < nc ? st->cross[k].x : xr;
        if (next > cur) {
            aa_rgb c = aa_scene_colour_of(st->s, st->wind);
            if (m > 0 && m <= cap && same_colour(out[m - 1].colour, c)) {
                out[m - 1].x1 = next;
            } else {
                if (m < cap) {
                    out[m].x0 = cur;
                    out[m].x1 = next;
                    out[m].colour = c;
                }
                m++;
            }
            cur = next;
        }
        if (k < nc)
            st->wind[st->cross[k].layer] += st->cross[k].dir;
    }
    return m;
}
