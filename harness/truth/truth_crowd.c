/*
 * truth_crowd.c: the reference value of a crowded pixel, one piece at a
 * time (harness/README.md, "Ground truth").
 *
 * truth.c integrates the inner integral of the whole window along v,
 * between breakpoints: every piece's ends, its crossings of the lines where
 * the filter has a kink, the meetings of pairs.  A window that thousands of
 * pieces cross has thousands of breakpoints, and every evaluation of the
 * integrand costs every piece: the work grows as the square of the pieces
 * (crow with 65536 arcs 1e-5 apart did not finish a 2 x 2 image in two
 * minutes).  Here the same integral is taken apart by pieces.
 *
 * In coordinates relative to the pixel centre, window [-R, R]^2, the inner
 * integral at height s is (F the filter's cdf along x, w its weight in v;
 * for a radial filter w(s) (F(b) - F(a)) is the row's integral over [a, b])
 *
 *     G(s) = w(s) [ c_L(s) (F(R) - F(-R))
 *                   + sum over pieces k crossing the window at s of
 *                     dc_k(s) (F(R) - F(x_k(s))) ]
 *
 * with c_L the colour at the window's left side (-R, s) and dc_k the jump
 * of colour across piece k: the colour of the winding numbers just right
 * of its crossing minus just left (Abel's summation of the sum over
 * spans).  Between events, the ends of pieces, the heights where a piece
 * enters or leaves the window through x = -R or x = R, and where two
 * pieces meet inside it, the order of the pieces along x is fixed, and so
 * is every dc_k: each piece's term is then integrated on its own, between
 * its own breakpoints only (its crossings of the filter's kink lines, the
 * turning points at its ends), and the cost is the pieces times a few
 * Gauss-Kronrod passes, not the pieces squared.  For `crow` under the box
 * each term is a quadratic in s and the first pass is exact.
 *
 * The events come from a sweep along s over the window: the pieces inside
 * it are kept ordered by x; a piece is inserted where it begins or enters
 * (by bisection, comparing x just after the event), removed where it ends
 * or leaves, and two pieces are tested for meetings only when they become
 * neighbours in that order (Bentley and Ottmann's sweep: if the order
 * changes, two neighbours meet first), so meetings cost the pieces plus
 * the meetings, not all pairs (closed forms from aa_piece_meet; for two
 * general arcs the sign changes of a quartic, meet_general).  After each event only the pieces whose
 * winding to the left changed get a new dc (walking right from the change
 * until the winding numbers agree again with those kept), and a piece's
 * integral is split only where its own dc changes.  c_L changes only where
 * a piece crosses the window's left side (followed step by step), or at a
 * vertex or horizontal edge on it (computed afresh from the strip).
 *
 * Accuracy.  The quadrature is in long double (the 21-point Gauss-Kronrod
 * rule of QUADPACK and GSL with its constants to 33 digits, and its error
 * estimate with the long double epsilon), so that the sum of thousands of
 * terms of opposite signs keeps rounding near 1e-18 each: in double, as
 * GSL's QK21, the error estimates' rounding floor alone (50 eps of each
 * term) would add up to 1e-10 over 65536 arcs.  Each term is integrated
 * adaptively (bisection) to its share of TRUTH_EPSABS, in proportion to its
 * length times its largest jump.  The cone is taken in theta, v = R sin
 * theta, where the chord's square root at v = -R, R is smooth, and in u^4
 * next to its centre (v = 0) and next to each piece's closest approach to
 * it, where each term is singular on the scale of that distance; its
 * terms are bisected on the plain |K21 - G10| (see adapt), as are those of
 * pieces that turn at an end, under every filter.  The bound is
 * the sum of the estimates weighed by the jumps, plus rounding: for the
 * box, the crossings in long double (16 ulps of the piece's size), for
 * other filters also their cdf and weight in double (4 eps of the filter's
 * peak per unit height and jump), plus the Gaussian's truncated mass.
 * Checked against the sum over spans on the patterns under every filter,
 * against `area` on random scenes of crossing arcs and polygons, against
 * the closed form of crow, and against brute-force integration where the
 * two derivations disagreed (tests/test_truth.c).
 */
#include "truth.h"
#include "truth_internal.h"

#include <gsl/gsl_errno.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The Gauss-Kronrod 10/21 rule on [-1, 1] (QUADPACK's qk21, as GSL has
 * it; evaluated with 80 digits by L. W. Fullerton, Bell Labs, 1981). */
static const long double XGK[11] = {
    0.995657163025808080735527280689003L, 0.973906528517171720077964012084452L,
    0.930157491355708226001207180059508L, 0.865063366688984510732096688423493L,
    0.780817726586416897063717578345042L, 0.679409568299024406234327365114874L,
    0.562757134668604683339000099272694L, 0.433395394129247190799265943165784L,
    0.294392862701460198131126603103866L, 0.148874338981631210884826001129720L,
    0.000000000000000000000000000000000L};
static const long double WGK[11] = {
    0.011694638867371874278064396062192L, 0.032558162307964727478818972459390L,
    0.054755896574351996031381300244580L, 0.075039674810919952767043140916190L,
    0.093125454583697605535065465083366L, 0.109387158802297641899210590325805L,
    0.123491976262065851077958109831074L, 0.134709217311473325928054001771707L,
    0.142775938577060080797094273138717L, 0.147739104901338491374841515972068L,
    0.149445554002916905664936468389821L};
static const long double WG[5] = {
    0.066671344308688137593568809893332L, 0.149451349150580593145776339657697L,
    0.219086362515982043995534934228163L, 0.269266719309996355091226921569469L,
    0.295524224714752870173892994651338L};

/* Subintervals one term may be cut into before its estimate is taken as
 * it stands (it enters the bound). */
#define CROWD_PARTS 256
/* Two pieces closer than this along x (px) at an event are ordered by
 * where they go next (before their next meeting), not by their x there. */
#define CROWD_TIE 1e-13
/* After two pieces swap at a meeting, their next meeting is looked for
 * this far (px, in v, times the height's size) above it, and the order
 * just after a meeting is the one half way to the next: a meeting's height
 * is known to about 1e-12 of its size, so the same meeting is found again
 * just above, and a probe there fell before the true crossing (a swap was
 * missed; one of the random scenes of crossing arcs came out 0.08 off).  A
 * wrong order within the margin is an error of the margin times the
 * pieces' distance there, both of that order. */
#define CROWD_MARGIN 1e-10
/* Vertices and horizontal edges this close (px) to the window's left
 * side make the colour there computed afresh. */
#define CROWD_SIDE 1e-9
/* Batches of more insertions than this sort the whole order instead. */
#define CROWD_BULK 32
/* Winding numbers are kept per piece in the order (for the walk that stops
 * early) when the scene has at most this many layers. */
#define CROWD_WL_LAYERS 16

enum { CP_OFF, CP_LEFT, CP_IN, CP_RIGHT };
enum { EV_BASE, EV_END, EV_START, EV_CROSS, EV_MEET };

struct crowd_piece {
    const aa_piece *p;
    local_piece q;  /* relative to the centre */
    double lo, hi;  /* active heights, relative, within [-R, R] */
    double cross[6]; /* heights where it crosses x = -R or x = R */
    int ncross;
    int region, slot;
    int ev;          /* this batch: 1 touched, 2 ends */
    int stamp;       /* the batch its pair with its right neighbour was tested */
    int dirty, visit; /* the batch it was marked in, walked over in */
    double seg_a;    /* start of its open segment */
    double dc[3];
    int kink0, nkink; /* its own split heights in the pool */
    unsigned char turn_lo, turn_hi;
    double near;    /* radial: the height of its closest approach to the centre */
    double scale;   /* |x0| + |bx| + |ax| + R: the size of its numbers */
};

struct crowd_node {
    int l, r, up, size, prev, next, piece;
    unsigned prio;
};

struct crowd_event {
    double s;
    int type, a, b;
};

struct crowd_seg {
    int k; /* piece, or -1 for the window's left colour */
    double a, b;
    double dc[3];
};

/* What one pixel's sweep and integration share. */
typedef struct crowd {
    crowd_worker *cw;
    const aa_scene *scene;
    const aa_strip *strip;
    const aa_filter *f;
    double uc, vc, R;
    int box, radial, gauss, nc;
    size_t np;     /* pieces */
    size_t nlist;  /* in the window's order */
    int root, head; /* of the order (slots) */
    unsigned rng;
    int batch, w_changed;
    int *W;        /* winding numbers at (-R, s) */
    double base_a;
    aa_rgb base_c;
    double FR, FL; /* F(R), and F left of the window (box: -R; others 0) */
    double vkink[64];
    int nvkink;
    double vturn[3];
    int nvturn;
    int status;
    size_t swaps; /* meetings where two pieces changed places */
} crowd;

void crowd_free(crowd_worker *cw)
{
    free(cw->cp);
    free(cw->node);
    free(cw->scratch);
    free(cw->scratch2);
    free(cw->wl);
    free(cw->heap);
    free(cw->seg);
    free(cw->kink);
    free(cw->touched);
    free(cw->meet);
    free(cw->dirty);
    free(cw->xs);
    free(cw->wind);
    free(cw->ev);
    if (cw->poly)
        gsl_poly_complex_workspace_free(cw->poly);
    memset(cw, 0, sizeof *cw);
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return AA_OK;
    size_t n = *cap ? *cap : 64;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * size);
    if (!q)
        return aa_fail(AA_ENOMEM, "out of memory for a crowded pixel (%zu items)", need);
    *p = q;
    *cap = n;
    return AA_OK;
}

/* Room for n pieces and the arrays that follow them. */
static int reserve_pieces(crowd_worker *cw, size_t n, int nl)
{
    if (n <= cw->cap_cp && nl <= cw->nl)
        return AA_OK;
    size_t cap = n > cw->cap_cp ? 2 * n : cw->cap_cp;
    int wl_layers = nl <= CROWD_WL_LAYERS ? nl : 0;
    void *p[6];
    p[0] = realloc(cw->cp, cap * sizeof *cw->cp);
    if (p[0])
        cw->cp = p[0];
    p[1] = realloc(cw->node, cap * sizeof *cw->node);
    if (p[1])
        cw->node = p[1];
    p[2] = realloc(cw->wl, (cap * (size_t)wl_layers + 1) * sizeof *cw->wl);
    if (p[2])
        cw->wl = p[2];
    p[3] = realloc(cw->touched, cap * sizeof *cw->touched);
    if (p[3])
        cw->touched = p[3];
    p[4] = realloc(cw->scratch2, 2 * cap * sizeof *cw->scratch2);
    if (p[4])
        cw->scratch2 = p[4];
    p[5] = realloc(cw->xs, cap * sizeof *cw->xs);
    if (p[5])
        cw->xs = p[5];
    for (int k = 0; k < 6; k++)
        if (!p[k])
            return aa_fail(AA_ENOMEM, "out of memory for a crowded pixel of %zu pieces", n);
    cw->cap_cp = cap;
    if (nl > cw->nl) {
        int *a = realloc(cw->wind, 3 * (size_t)nl * sizeof *a);
        if (!a)
            return aa_fail(AA_ENOMEM, "out of memory for %d layers", nl);
        cw->wind = a;
        cw->nl = nl;
    }
    return AA_OK;
}

/* ---- events: a binary heap by height ---- */

static int ev_less(const crowd_event *a, const crowd_event *b)
{
    return a->s < b->s || (a->s == b->s && a->type < b->type);
}

static void push(crowd *c, double s, int type, int a, int b)
{
    crowd_worker *cw = c->cw;
    if (c->status)
        return;
    if (cw->nheap == cw->cap_heap &&
        (c->status = grow((void **)&cw->heap, &cw->cap_heap, cw->nheap + 1, sizeof *cw->heap)))
        return;
    crowd_event e = {s, type, a, b}, *h = cw->heap;
    size_t k = cw->nheap++;
    while (k > 0 && ev_less(&e, &h[(k - 1) / 2])) {
        h[k] = h[(k - 1) / 2];
        k = (k - 1) / 2;
    }
    h[k] = e;
}

static crowd_event pop(crowd_worker *cw)
{
    crowd_event *h = cw->heap, top = h[0], last = h[--cw->nheap];
    size_t k = 0, n = cw->nheap;
    for (;;) {
        size_t l = 2 * k + 1, m = k;
        if (l < n && ev_less(&h[l], &last))
            m = l;
        if (l + 1 < n && ev_less(&h[l + 1], m == k ? &last : &h[l]))
            m = l + 1;
        if (m == k)
            break;
        h[k] = h[m];
        k = m;
    }
    if (n)
        h[k] = last;
    return top;
}

/* ---- one piece ---- */

static inline long double x_at(const crowd_piece *k, long double s)
{
    return k->q.x0 + truth_crossing_part(&k->q, s);
}

/* x at height s where piece k begins or ends (or enters or leaves the
 * window's rows): the scene's own point at the piece's ends.  A conic
 * piece's crossing there can be off by much more than the rounding of
 * the coordinates: at a turning point the end's height is the extreme's
 * rounded, and under the square root that rounding moves x by
 * sqrt(2 er 1e-16) (3e-9 px for a circle of radius 1e-3, more than
 * CROWD_SIDE). */
static long double end_x(const crowd *c, const crowd_piece *k, double s)
{
    if (s == k->lo && k->lo == k->p->y0 - c->vc)
        return (long double)k->p->x0 - c->uc;
    if (s == k->hi && k->hi == k->p->y1 - c->vc)
        return (long double)k->p->x1 - c->uc;
    return x_at(k, s);
}

/* x at height s as a function of s alone, for comparisons that must come
 * out the same each time they are asked.  x_at starts an offset piece's
 * root from its last crossing, and where it ends depends on that start in
 * the last bits: two pieces within rounding of each other then compared
 * one way, were swapped, and compared the other way, and the marked
 * pieces' pass (sweep, "Neighbours meeting at h itself") swapped them
 * back and forth to its limit of steps, every batch.  Here the root is
 * solved for from its bracket alone. */
static long double x_fixed(const crowd_piece *k, long double s)
{
    const local_piece *q = &k->q;
    if (!q->offset || !(s > q->y0) || !(s < q->y1))
        return x_at(k, s);
    const aa_piece *p = q->src;
    long double y = q->vc + s, x;
    aa__offset_root(&p->oc, 1, p->ot0, p->ot1, (long double)p->y0 - y, y, NAN, &x, NULL);
    return x - q->uc;
}

static int region_at(const crowd *c, const crowd_piece *k, double s)
{
    long double x = x_at(k, s);
    return x < -c->R ? CP_LEFT : (x >= c->R ? CP_RIGHT : CP_IN);
}

/* The region just after h: at the middle of the stretch up to its next
 * crossing of a side (or its end), where it cannot change. */
static int region_after(const crowd *c, const crowd_piece *k, double h)
{
    double next = k->hi;
    for (int m = 0; m < k->ncross; m++)
        if (k->cross[m] > h) {
            next = k->cross[m];
            break;
        }
    return region_at(c, k, h + 0.5 * (next - h));
}

static double margin(const crowd *c)
{
    return CROWD_MARGIN * fmax(1.0, fabs(c->vc) + c->R);
}

/* ---- where two pieces cross ---- */

/* The parameter of piece k where it meets line s (clamped to [0, 1]). */
static long double t_at(const crowd_piece *k, long double s)
{
    return truth_t_at(&k->q, s);
}

static inline long double cross2(long double ax, long double ay, long double bx, long double by)
{
    return ax * by - ay * bx;
}

/* Heights in (ya, yb) where the general arc b (y quadratic in its
 * parameter) and piece a cross, ascending: a's point P(t) substituted in
 * the implicit equation of b's parabola, E = P - Q0 = u C + u^2 D gives
 * cross(E, D) = u k and cross(E, C) = -u^2 k with k = cross(C, D), so
 * cross(E, D)^2 + k cross(E, C) = 0, a quartic in t (of degree 6 when a is
 * a cubic), and u = cross(E, D)/k must lie in [0, 1].  aa_piece_meet bisects on the pieces' extents for
 * such pairs and can run out of its budget where two arcs run side by
 * side (one of the random scenes of crossing arcs lost a crossing so). */
static int meet_general(const crowd_piece *a, const crowd_piece *b, double ya, double yb,
                        double *ys, int max)
{
    const local_piece *p = &a->q, *q = &b->q;
    long double ex = p->x0 - q->x0, ey = p->y0 - q->y0;
    long double k = cross2(q->bx, q->by, q->ax, q->ay);
    long double a0 = cross2(ex, ey, q->ax, q->ay), a1 = cross2(p->bx, p->by, q->ax, q->ay),
                a2 = cross2(p->ax, p->ay, q->ax, q->ay);
    long double b0 = cross2(ex, ey, q->bx, q->by), b1 = cross2(p->bx, p->by, q->bx, q->by),
                b2 = cross2(p->ax, p->ay, q->bx, q->by);
    /* a's cubic terms (zero but for a cubic) */
    long double a3 = cross2(p->dx, p->dy, q->ax, q->ay), b3 = cross2(p->dx, p->dy, q->bx, q->by);
    long double A[4] = {a0, a1, a2, a3}, B[4] = {b0, b1, b2, b3};
    long double f[7] = {0}, r[6];
    if (k != 0 && !a->q.cubic) {
        f[0] = a0 * a0 + k * b0;
        f[1] = 2 * a0 * a1 + k * b1;
        f[2] = a1 * a1 + 2 * a0 * a2 + k * b2;
        f[3] = 2 * a1 * a2;
        f[4] = a2 * a2;
    } else if (k != 0) {
        for (int i = 0; i < 4; i++) {
            f[i] += k * B[i];
            for (int j = 0; j < 4; j++)
                f[i + j] += A[i] * A[j];
        }
    } else { /* b straight: cross(E, C) = 0 */
        for (int i = 0; i < 4; i++)
            f[i] = B[i];
    }
    long double ta = t_at(a, ya), tb = t_at(a, yb);
    int n = truth_sign_roots(f, 6, ta, tb, r), m = 0;
    for (int j = 0; j < n && m < max; j++) {
        long double t = r[j];
        if (k != 0) {
            long double u = (a->q.cubic ? a0 + t * (a1 + t * (a2 + t * a3))
                                        : a0 + t * (a1 + t * a2)) / k;
            if (!(u >= -1e-9L && u <= 1 + 1e-9L))
                continue;
        }
        double y = (double)(a->q.cubic ? p->y0 + t * (p->by + t * (p->ay + t * p->dy))
                                        : p->y0 + t * (p->by + t * p->ay));
        if (y > ya && y < yb && (m == 0 || y > ys[m - 1]))
            ys[m++] = y;
    }
    return m;
}

/* Heights in (ya, yb) where pieces a and b meet, ascending (at most 16):
 * aa_piece_meet's closed forms for lines and arcs whose x is quadratic in
 * y, meet_general for two general arcs and for a cubic against a line or
 * an arc (a polynomial of degree 6), and aa_piece_meet for two cubics
 * (bisection on exact extents) and for any pair with a conic piece. */
static int meet(const crowd *c, const crowd_piece *a, const crowd_piece *b, double ya, double yb,
                double *ys)
{
    if (!(ya < yb))
        return 0;
    const aa_piece *p = a->p, *q = b->p;
    int pc = p->kind == AA_PIECE_CUBIC, qc = q->kind == AA_PIECE_CUBIC;
    int conic = p->kind == AA_PIECE_CONIC || q->kind == AA_PIECE_CONIC ||
                p->kind == AA_PIECE_OFFSET || q->kind == AA_PIECE_OFFSET;
    if (pc != qc && !conic)
        return pc ? meet_general(a, b, ya, yb, ys, 16) : meet_general(b, a, ya, yb, ys, 16);
    if (p->kind == AA_PIECE_QUAD && q->kind == AA_PIECE_QUAD && !(p->ay == 0.0 && q->ay == 0.0))
        return q->ay != 0.0 ? meet_general(a, b, ya, yb, ys, 16) : meet_general(b, a, ya, yb, ys, 16);
    int n = aa_piece_meet(p, q, c->vc + ya, c->vc + yb, ys, 16), m = 0;
    for (int j = 0; j < n; j++) {
        double s = ys[j] - c->vc;
        if (s > ya && s < yb)
            ys[m++] = s;
    }
    return m;
}

/* The first height in (ya, hi) where pieces a and b meet, or hi. */
static double next_meet(const crowd *c, const crowd_piece *a, const crowd_piece *b, double ya,
                        double hi)
{
    double ys[16];
    int n = meet(c, a, b, ya, hi, ys);
    return n > 0 ? ys[0] : hi;
}

/* The order of pieces a and b just after height h (negative: a left of b).
 * Apart at h by more than CROWD_TIE and than their motion in x over the
 * margin above h, their order there; else (a vertex they share, a meeting
 * at h) their order half way to their next meeting.  The
 * answer is a function of the pieces and h alone, the same each time and
 * the opposite with a and b exchanged: x_fixed decides wherever x_at's
 * last bits could (near the tie's threshold, and at the probe). */
static int cmp_after(const crowd *c, int ia, int ib, double h, int tie)
{
    const crowd_piece *a = &c->cw->cp[ia], *b = &c->cw->cp[ib];
    if (!tie) {
        /* apart by more than the tie and than the two move in x over the
         * margin above h: a meeting's height is known to a few ulps, and
         * on a nearly horizontal piece (|dx/dy| in the hundreds) those
         * are more than CROWD_TIE in x, so x at h can still show the
         * order from before a meeting the sweep has just passed; such a
         * pair is ordered half way to its next meeting, as at a tie */
        double e = margin(c);
        long double tol = CROWD_TIE + fabsl(x_fixed(a, h + e) - x_fixed(a, h)) +
                          fabsl(x_fixed(b, h + e) - x_fixed(b, h));
        long double d = x_at(a, h) - x_at(b, h);
        if (!(d > 2 * tol || d < -2 * tol))
            d = x_fixed(a, h) - x_fixed(b, h);
        if (d > tol || d < -tol)
            return d < 0 ? -1 : 1;
    }
    double hi = fmin(a->hi, b->hi);
    double from = h + margin(c), top = next_meet(c, a, b, from, hi);
    double probe = from < top ? from + 0.5 * (top - from) : h + 0.5 * (hi - h);
    long double d = x_fixed(a, probe) - x_fixed(b, probe);
    if (d != 0)
        return d < 0 ? -1 : 1;
    return ia < ib ? -1 : (ia > ib);
}

/* ---- the sweep ---- */

static int *wl_of(const crowd *c, int k)
{
    return c->cw->nl <= CROWD_WL_LAYERS ? c->cw->wl + (size_t)k * (size_t)c->cw->nl : NULL;
}

static void emit(crowd *c, int k, double a, double b, const double *dc)
{
    crowd_worker *cw = c->cw;
    if (c->status || !(b > a) || (dc[0] == 0.0 && dc[1] == 0.0 && dc[2] == 0.0))
        return;
    if (cw->nseg == cw->cap_seg &&
        (c->status = grow((void **)&cw->seg, &cw->cap_seg, cw->nseg + 1, sizeof *cw->seg)))
        return;
    crowd_seg *g = &cw->seg[cw->nseg++];
    g->k = k;
    g->a = a;
    g->b = b;
    memcpy(g->dc, dc, sizeof g->dc);
}

/* ---- the order along x: a treap of slots, threaded as a list ----
 *
 * The pieces inside the window are kept in a binary tree ordered along x,
 * balanced by random priorities (a treap), with subtree sizes (so a
 * slot's rank is a walk to the root) and each slot linked to its
 * neighbours: insertion by comparisons down the tree, removal, rank and
 * neighbours in O(log n), where an array kept in order cost O(n) an
 * event (measured: two thirds of a crowded feibush pixel).  Slots hold
 * pieces; two neighbours that cross swap their pieces, not their slots. */

static inline int tsize(const crowd_node *t, int x)
{
    return x < 0 ? 0 : t[x].size;
}

/* Rotate x above its parent. */
static void rotate_up(crowd *c, int x)
{
    crowd_node *t = c->cw->node;
    int p = t[x].up, g = t[p].up;
    if (t[p].l == x) {
        t[p].l = t[x].r;
        if (t[x].r >= 0)
            t[t[x].r].up = p;
        t[x].r = p;
    } else {
        t[p].r = t[x].l;
        if (t[x].l >= 0)
            t[t[x].l].up = p;
        t[x].l = p;
    }
    t[p].up = x;
    t[x].up = g;
    if (g < 0)
        c->root = x;
    else if (t[g].l == p)
        t[g].l = x;
    else
        t[g].r = x;
    t[p].size = tsize(t, t[p].l) + tsize(t, t[p].r) + 1;
    t[x].size = tsize(t, t[x].l) + tsize(t, t[x].r) + 1;
}

/* A fixed sequence per pixel: the tree's shape, and so the comparisons
 * made, never depend on the thread. */
static unsigned next_prio(crowd *c)
{
    unsigned x = c->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return c->rng = x;
}

/* Insert piece k (its slot) where it goes just after h. */
static void order_insert(crowd *c, int k, double h)
{
    crowd_node *t = c->cw->node;
    int x = c->cw->cp[k].slot, cur = c->root, pred = -1, succ = -1;
    t[x].l = t[x].r = -1;
    t[x].size = 1;
    t[x].piece = k;
    t[x].prio = next_prio(c);
    c->nlist++;
    if (cur < 0) {
        c->root = c->head = x;
        t[x].up = t[x].prev = t[x].next = -1;
        return;
    }
    for (;;) {
        t[cur].size++;
        if (cmp_after(c, t[cur].piece, k, h, 0) < 0) {
            pred = cur;
            if (t[cur].r < 0) {
                t[cur].r = x;
                break;
            }
            cur = t[cur].r;
        } else {
            succ = cur;
            if (t[cur].l < 0) {
                t[cur].l = x;
                break;
            }
            cur = t[cur].l;
        }
    }
    t[x].up = cur;
    t[x].prev = pred;
    t[x].next = succ;
    if (pred >= 0)
        t[pred].next = x;
    else
        c->head = x;
    if (succ >= 0)
        t[succ].prev = x;
    while (t[x].up >= 0 && t[x].prio < t[t[x].up].prio)
        rotate_up(c, x);
}

static void order_remove(crowd *c, int k)
{
    crowd_node *t = c->cw->node;
    int x = c->cw->cp[k].slot;
    while (t[x].l >= 0 || t[x].r >= 0) {
        int l = t[x].l, r = t[x].r;
        rotate_up(c, l < 0 ? r : (r < 0 ? l : (t[l].prio < t[r].prio ? l : r)));
    }
    int p = t[x].up;
    if (p < 0) {
        c->root = -1;
    } else {
        if (t[p].l == x)
            t[p].l = -1;
        else
            t[p].r = -1;
        for (int q = p; q >= 0; q = t[q].up)
            t[q].size--;
    }
    if (t[x].prev >= 0)
        t[t[x].prev].next = t[x].next;
    else
        c->head = t[x].next;
    if (t[x].next >= 0)
        t[t[x].next].prev = t[x].prev;
    c->nlist--;
}

static int order_rank(const crowd *c, int x)
{
    const crowd_node *t = c->cw->node;
    int r = tsize(t, t[x].l);
    for (; t[x].up >= 0; x = t[x].up)
        if (t[t[x].up].r == x)
            r += tsize(t, t[t[x].up].l) + 1;
    return r;
}

/* Slots s[lo..hi) in order as a subtree of depth d (priorities growing
 * with depth: a valid treap); returns its root. */
static int build(crowd *c, const int *s, int lo, int hi, int up, unsigned d)
{
    if (lo >= hi)
        return -1;
    crowd_node *t = c->cw->node;
    int m = lo + (hi - lo) / 2, x = s[m];
    t[x].up = up;
    t[x].prio = d << 26;
    t[x].l = build(c, s, lo, m, x, d + 1);
    t[x].r = build(c, s, m + 1, hi, x, d + 1);
    t[x].size = hi - lo;
    return x;
}

/* The whole order from the slots s[0..n), in order. */
static void order_build(crowd *c, const int *s, int n)
{
    crowd_node *t = c->cw->node;
    c->root = build(c, s, 0, n, -1, 0);
    c->head = n ? s[0] : -1;
    c->nlist = (size_t)n;
    for (int m = 0; m < n; m++) {
        t[s[m]].prev = m > 0 ? s[m - 1] : -1;
        t[s[m]].next = m + 1 < n ? s[m + 1] : -1;
    }
}

/* qsort order of pieces just after the batch's height (the batch is one
 * thread's: the context is thread-local). */
static _Thread_local const crowd *sort_c;
static _Thread_local double sort_h;
static _Thread_local const long double *sort_x;

static int cmp_sorted(const void *pa, const void *pb)
{
    int a = *(const int *)pa, b = *(const int *)pb;
    long double d = sort_x[a] - sort_x[b];
    if (d > CROWD_TIE || d < -CROWD_TIE)
        return d < 0 ? -1 : 1;
    return cmp_after(sort_c, a, b, sort_h, 1);
}

/* Pieces a, b (a left of b, neighbours): their meetings above `from` in
 * the window become events. */
static void test_pair(crowd *c, int ia, int ib, double from)
{
    crowd_worker *cw = c->cw;
    crowd_piece *a = &cw->cp[ia], *b = &cw->cp[ib];
    if (a->stamp == c->batch)
        return;
    a->stamp = c->batch;
    double hi = fmin(fmin(a->hi, b->hi), c->R), ys[16];
    int n = meet(c, a, b, from, hi, ys);
    for (int k = 0; k < n; k++) {
        double s = ys[k];
        long double x = x_at(a, s);
        if (x < -c->R - CROWD_SIDE || x > c->R + CROWD_SIDE)
            continue; /* outside the window: both have left it by then */
        push(c, s, EV_MEET, ia, ib);
    }
}

/* The winding numbers at (-R, s), afresh: the strip's pieces left of the
 * window, and the local pieces crossing line s left of it. */
static void winding_afresh(crowd *c, double s, int *w)
{
    crowd_worker *cw = c->cw;
    aa_strip_winding_left_at(c->strip, c->vc, s, w);
    for (size_t k = 0; k < c->np; k++) {
        const crowd_piece *p = &cw->cp[k];
        if (s >= p->lo && s < p->hi && s >= p->q.y0 && s < p->q.y1 && x_at(p, s) < -c->R)
            w[p->q.layer] += p->q.dir;
    }
}

static void set_dc(const crowd *c, const int *w, int layer, int dir, double *dc)
{
    int *t = c->cw->wind + 2 * c->cw->nl;
    memcpy(t, w, (size_t)c->cw->nl * sizeof *t);
    aa_rgb a = aa_scene_colour_of(c->scene, t);
    t[layer] += dir;
    aa_rgb b = aa_scene_colour_of(c->scene, t);
    for (int ch = 0; ch < 3; ch++)
        dc[ch] = b.c[ch] - a.c[ch];
}

static void base_update(crowd *c, double h)
{
    aa_rgb col = aa_scene_colour_of(c->scene, c->W);
    if (memcmp(col.c, c->base_c.c, sizeof col.c)) {
        if (h > c->base_a)
            emit(c, -1, c->base_a, h, c->base_c.c);
        c->base_a = h;
        c->base_c = col;
    }
}

/* Mark piece k: its neighbours are tested for meetings after the batch,
 * from h (or from above h if it has just met one of them), and the colour
 * jumps are walked from it. */
static void add_dirty(crowd *c, size_t *nd, int k, int swapped)
{
    crowd_worker *cw = c->cw;
    if (c->status)
        return;
    if (2 * *nd + 2 > cw->cap_dirty &&
        (c->status = grow((void **)&cw->dirty, &cw->cap_dirty, 2 * *nd + 2, sizeof *cw->dirty)))
        return;
    cw->dirty[2 * *nd] = k;
    cw->dirty[2 * *nd + 1] = swapped;
    cw->cp[k].dirty = c->batch;
    ++*nd;
}

/* The colour jump of the piece in slot x from the winding numbers w left
 * of it, closing and opening its segment at h if it changed; w moves past
 * it.  Returns 1 if its winding numbers to the left are those kept. */
static int walk_one(crowd *c, int x, int *w, double h)
{
    crowd_worker *cw = c->cw;
    int k = cw->node[x].piece, nl = cw->nl;
    crowd_piece *p = &cw->cp[k];
    int *wk = wl_of(c, k), fresh = p->seg_a != p->seg_a; /* NaN: just inserted */
    int same = !fresh && wk && !memcmp(wk, w, (size_t)nl * sizeof *w);
    p->visit = c->batch;
    if (!same) {
        double dc[3];
        set_dc(c, w, p->q.layer, p->q.dir, dc);
        if (fresh) {
            p->seg_a = h;
            memcpy(p->dc, dc, sizeof dc);
        } else if (memcmp(dc, p->dc, sizeof dc)) {
            emit(c, k, p->seg_a, h, p->dc);
            p->seg_a = h;
            memcpy(p->dc, dc, sizeof dc);
        }
        if (wk)
            memcpy(wk, w, (size_t)nl * sizeof *w);
    }
    w[p->q.layer] += p->q.dir;
    return same;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return x < y ? -1 : (x > y);
}

/* After a batch at h: new colour jumps where the winding to the left
 * changed.  Walk right from each marked piece, in order, until a piece
 * that is not marked has the winding numbers kept for it: the rest up to
 * the next marked piece is unchanged.  From the head if the left side's
 * colour changed or `all`; to the end if no winding numbers are kept (more
 * than CROWD_WL_LAYERS layers), then from the first marked piece unless
 * the left side's winding numbers changed: every piece's jump depends on
 * them. */
static void update_dc(crowd *c, size_t nd, int all, double h)
{
    crowd_worker *cw = c->cw;
    crowd_node *t = cw->node;
    int nl = cw->nl, *w = cw->wind + nl, *run = cw->scratch, nrun = 0;
    if (!c->nlist)
        return;
    if (all || !wl_of(c, 0)) {
        int x = c->head;
        memcpy(w, c->W, (size_t)nl * sizeof *w);
        if (!all && !c->w_changed) { /* from the first marked piece */
            int first = INT_MAX;
            for (size_t d = 0; d < nd; d++) {
                const crowd_piece *p = &cw->cp[cw->dirty[2 * d]];
                if (p->region == CP_IN) {
                    int r = order_rank(c, p->slot);
                    first = r < first ? r : first;
                }
            }
            for (int m = 0; x >= 0 && m < first; m++, x = t[x].next)
                w[cw->cp[t[x].piece].q.layer] += cw->cp[t[x].piece].q.dir;
        }
        for (; x >= 0; x = t[x].next)
            walk_one(c, x, w, h);
        return;
    }
    /* the marked pieces' ranks, ascending (rank * 2^20 would overflow:
     * sort ranks with their slots as pairs) */
    for (size_t d = 0; d < nd; d++) {
        const crowd_piece *p = &cw->cp[cw->dirty[2 * d]];
        if (p->region != CP_IN)
            continue;
        run[2 * nrun] = order_rank(c, p->slot);
        run[2 * nrun + 1] = p->slot;
        nrun++;
    }
    qsort(run, (size_t)nrun, 2 * sizeof *run, cmp_int);
    int from_head = c->w_changed;
    for (int r = -1; r < nrun; r++) {
        int x;
        if (r < 0) {
            if (!from_head)
                continue;
            x = c->head;
            memcpy(w, c->W, (size_t)nl * sizeof *w);
        } else {
            x = run[2 * r + 1];
            if (cw->cp[t[x].piece].visit == c->batch)
                continue; /* walked over already */
            int pv = t[x].prev;
            if (pv < 0) {
                memcpy(w, c->W, (size_t)nl * sizeof *w);
            } else {
                const crowd_piece *q = &cw->cp[t[pv].piece];
                memcpy(w, wl_of(c, t[pv].piece), (size_t)nl * sizeof *w);
                w[q->q.layer] += q->q.dir;
            }
        }
        for (; x >= 0; x = t[x].next) {
            const crowd_piece *p = &cw->cp[t[x].piece];
            int marked = p->dirty == c->batch;
            if (walk_one(c, x, w, h) && !marked)
                break;
        }
    }
}

/* Sort the run of the order from slot xa to slot xb (xa before xb) just
 * after h, moving pieces between the slots; returns 1 if anything moved. */
static int sort_run(crowd *c, int xa, int xb, double h, size_t *nd)
{
    crowd_worker *cw = c->cw;
    crowd_node *t = cw->node;
    int *s = cw->scratch, n = 0, moved = 0;
    for (int x = xa;; x = t[x].next) {
        s[n++] = x;
        if (x == xb)
            break;
    }
    int *pc = s + n;
    for (int m = 0; m < n; m++)
        pc[m] = t[s[m]].piece;
    for (int u = 1; u < n; u++) {
        int v = pc[u], at = u;
        while (at > 0 && cmp_after(c, pc[at - 1], v, h, 0) > 0) {
            pc[at] = pc[at - 1];
            at--;
            moved = 1;
        }
        pc[at] = v;
    }
    if (!moved)
        return 0;
    for (int m = 0; m < n; m++) {
        t[s[m]].piece = pc[m];
        cw->cp[pc[m]].slot = s[m];
        add_dirty(c, nd, pc[m], 1);
    }
    return 1;
}

static int sweep(crowd *c)
{
    crowd_worker *cw = c->cw;
    crowd_piece *cp = cw->cp;
    crowd_node *t = cw->node;
    int nl = cw->nl;
    double R = c->R;
    push(c, -R, EV_BASE, -1, -1);
    for (size_t k = 0; k < c->np; k++) {
        crowd_piece *p = &cp[k];
        push(c, p->lo, EV_START, (int)k, -1);
        if (p->hi < R)
            push(c, p->hi, EV_END, (int)k, -1);
        for (int m = 0; m < p->ncross; m++)
            push(c, p->cross[m], EV_CROSS, (int)k, -1);
    }
    memset(c->W, 0, (size_t)nl * sizeof *c->W); /* set at the first batch (EV_BASE) */
    c->nlist = 0;
    c->root = c->head = -1;
    c->rng = 2463534242u;
    c->base_a = -R;
    c->base_c.c[0] = c->base_c.c[1] = c->base_c.c[2] = NAN;
    c->batch = 0;
    while (cw->nheap && !c->status) {
        double h = cw->heap[0].s;
        if (h >= R)
            break;
        if (cw->record && h > -R) {
            if (cw->nev == cw->cap_ev &&
                (c->status = grow((void **)&cw->ev, &cw->cap_ev, cw->nev + 1, sizeof *cw->ev)))
                break;
            cw->ev[cw->nev++] = h;
        }
        c->batch++;
        size_t nt = 0, nm = 0, nd = 0, nin = 0;
        int need_w = 0, all = 0;
        c->w_changed = 0;
        while (cw->nheap && cw->heap[0].s == h) {
            crowd_event e = pop(cw);
            if (e.type == EV_BASE) {
                need_w = 1;
            } else if (e.type == EV_MEET) {
                if (2 * nm + 2 > cw->cap_meet &&
                    (c->status = grow((void **)&cw->meet, &cw->cap_meet, 2 * nm + 2,
                                      sizeof *cw->meet)))
                    break;
                cw->meet[2 * nm] = e.a;
                cw->meet[2 * nm + 1] = e.b;
                nm++;
            } else {
                crowd_piece *p = &cp[e.a];
                if (!p->ev)
                    cw->touched[nt++] = e.a;
                p->ev = e.type == EV_END ? 2 : (p->ev ? p->ev : 1);
                if (e.type != EV_CROSS) {
                    long double x = end_x(c, p, h) + R;
                    if (x <= CROWD_SIDE && x >= -CROWD_SIDE)
                        need_w = 1; /* a vertex on the left side */
                }
            }
        }
        if (c->status)
            break;
        double next = cw->nheap ? fmin(cw->heap[0].s, R) : R;
        /* pieces that end, begin, enter or leave */
        for (size_t u = 0; u < nt; u++) {
            int k = cw->touched[u];
            crowd_piece *p = &cp[k];
            int was = p->region, now = p->ev == 2 ? CP_OFF : region_after(c, p, h);
            if (was != CP_OFF && now != CP_OFF) {
                /* across the left side: the colour there changes */
                if (was == CP_LEFT && now != CP_LEFT) {
                    c->W[p->q.layer] -= p->q.dir;
                    c->w_changed = 1;
                } else if (was != CP_LEFT && now == CP_LEFT) {
                    c->W[p->q.layer] += p->q.dir;
                    c->w_changed = 1;
                }
            }
            if (was == CP_IN && now != CP_IN) {
                int x = p->slot;
                emit(c, k, p->seg_a, h, p->dc);
                if (t[x].prev >= 0)
                    add_dirty(c, &nd, t[t[x].prev].piece, 0);
                if (t[x].next >= 0)
                    add_dirty(c, &nd, t[t[x].next].piece, 0);
                order_remove(c, k);
            }
            if (was != CP_IN && now == CP_IN)
                cw->touched[nin++] = k; /* from here on: those to insert */
            p->region = now == CP_IN && was != CP_IN ? CP_OFF : now;
            p->ev = 0;
        }
        /* meetings: neighbours that cross change places */
        for (size_t m = 0; m < nm; m++) {
            int a = cw->meet[2 * m], b = cw->meet[2 * m + 1];
            if (cp[a].region != CP_IN || cp[b].region != CP_IN)
                continue;
            int xa = cp[a].slot, xb = cp[b].slot;
            if (t[xa].next == xb || t[xb].next == xa) {
                if (t[xb].next == xa) {
                    int u = xa;
                    xa = xb, xb = u;
                }
                int pa = t[xa].piece, pb = t[xb].piece;
                if (cmp_after(c, pa, pb, h, 1) <= 0)
                    continue;
                c->swaps++;
                t[xa].piece = pb, cp[pb].slot = xa;
                t[xb].piece = pa, cp[pa].slot = xb;
                add_dirty(c, &nd, pa, 1);
                add_dirty(c, &nd, pb, 1);
            } else {
                /* not neighbours (three through one point): sort the run */
                if (order_rank(c, xb) < order_rank(c, xa)) {
                    int u = xa;
                    xa = xb, xb = u;
                }
                if ((c->status = grow((void **)&cw->scratch, &cw->cap_scratch,
                                      2 * (size_t)(order_rank(c, xb) - order_rank(c, xa) + 1),
                                      sizeof *cw->scratch)))
                    break;
                c->swaps += (size_t)sort_run(c, xa, xb, h, &nd);
            }
        }
        if (c->status)
            break;
        /* insertions */
        if (nin > CROWD_BULK) {
            size_t m = 0;
            for (int x = c->head; x >= 0; x = t[x].next)
                cw->scratch2[m++] = t[x].piece;
            for (size_t u = 0; u < nin; u++) {
                int k = cw->touched[u];
                cp[k].region = CP_IN;
                cp[k].seg_a = NAN;
                cw->scratch2[m++] = k;
            }
            for (size_t u = 0; u < m; u++)
                cw->xs[cw->scratch2[u]] = x_at(&cp[cw->scratch2[u]], h);
            sort_c = c;
            sort_h = h;
            sort_x = cw->xs;
            qsort(cw->scratch2, m, sizeof *cw->scratch2, cmp_sorted);
            /* qsort's order, checked pair by pair as an insertion would */
            for (size_t u = 1; u < m; u++) {
                int v = cw->scratch2[u];
                size_t at = u;
                while (at > 0 && cmp_after(c, cw->scratch2[at - 1], v, h, 0) > 0) {
                    cw->scratch2[at] = cw->scratch2[at - 1];
                    at--;
                }
                cw->scratch2[at] = v;
            }
            /* slots: the pieces' own, in their new order */
            int *slots = cw->scratch2 + c->np;
            for (size_t u = 0; u < m; u++) {
                int k = cw->scratch2[u];
                slots[u] = cp[k].slot;
                t[cp[k].slot].piece = k;
            }
            order_build(c, slots, (int)m);
            for (size_t u = 0; u < m; u++)
                add_dirty(c, &nd, cw->scratch2[u], 0);
            all = 1;
        } else {
            for (size_t u = 0; u < nin; u++) {
                int k = cw->touched[u];
                cp[k].region = CP_IN;
                cp[k].seg_a = NAN;
                order_insert(c, k, h);
                add_dirty(c, &nd, k, 0);
            }
        }
        if (c->status)
            break;
        /* Neighbours meeting at h itself: a swap at a meeting, or an
         * insertion, can make neighbours of two pieces that meet at this
         * very height (three through one point within rounding: an offset
         * piece and two lines of tests/bench_bezstroke.c's path at 32 px,
         * 2.2e-15 apart there), whose meeting no event holds (test_pair
         * asks a swapped pair from h + margin on).  Each piece marked is
         * put in its order just after h against its neighbours
         * (cmp_after), as sort_run does a run; at most a few steps a
         * piece. */
        for (size_t d = 0, steps = 0; d < nd && steps < 4 * c->np + 16; d++) {
            int k = cw->dirty[2 * d];
            if (cp[k].region != CP_IN)
                continue;
            for (int side = 0; side < 2; side++)
                for (;;) {
                    int x = cp[k].slot, y = side ? t[x].next : t[x].prev;
                    if (y < 0 || steps >= 4 * c->np + 16)
                        break;
                    int o = t[y].piece;
                    if ((side ? cmp_after(c, k, o, h, 0) : cmp_after(c, o, k, h, 0)) <= 0)
                        break;
                    t[y].piece = k, cp[k].slot = y;
                    t[x].piece = o, cp[o].slot = x;
                    c->swaps++, steps++;
                    add_dirty(c, &nd, o, 1);
                    add_dirty(c, &nd, k, 1);
                }
        }
        if (c->status)
            break;
        /* the colour at the left side */
        if (need_w) {
            int *w = cw->wind + nl;
            winding_afresh(c, h + 0.5 * (next - h), w);
            if (memcmp(w, c->W, (size_t)nl * sizeof *w)) {
                memcpy(c->W, w, (size_t)nl * sizeof *w);
                c->w_changed = 1;
            }
        }
        base_update(c, h);
        if ((c->status = grow((void **)&cw->scratch, &cw->cap_scratch, 2 * nd + 2,
                              sizeof *cw->scratch)))
            break;
        update_dc(c, nd, all, h);
        /* new neighbours: their meetings */
        for (size_t d = 0; d < nd; d++) {
            int k = cw->dirty[2 * d];
            double from = cw->dirty[2 * d + 1] ? h + margin(c) : h;
            if (cp[k].region != CP_IN)
                continue;
            int x = cp[k].slot;
            if (t[x].prev >= 0)
                test_pair(c, t[t[x].prev].piece, k, from);
            if (t[x].next >= 0)
                test_pair(c, k, t[t[x].next].piece, from);
        }
    }
    for (int x = c->head; x >= 0; x = t[x].next) {
        crowd_piece *p = &cp[t[x].piece];
        emit(c, t[x].piece, p->seg_a, R, p->dc);
        p->region = CP_OFF;
    }
    emit(c, -1, c->base_a, R, c->base_c.c);
    cw->nheap = 0;
    return c->status;
}

/* ---- the terms' integrals ---- */

/* One term: piece k's, or (k NULL) the window's left colour for a radial
 * filter; in u with s = e + sign u^2 next to a turning point. */
typedef struct term {
    const crowd *c;
    const crowd_piece *k;
    long double e, sign;
    int turn;  /* 0, or the power p in t = e + sign u^p */
    int theta; /* radial: t is theta, s = R sin theta */
} term;

static long double term_at(const term *t, long double s)
{
    const crowd *c = t->c;
    long double R = c->R;
    if (!t->k)
        return aa_filter_row_cdf(c->f, (double)s, c->R) - aa_filter_row_cdf(c->f, (double)s, -c->R);
    long double x = x_at(t->k, s);
    if (c->box)
        return R - (x < -R ? -R : (x > R ? R : x));
    if (c->radial)
        return aa_filter_row_cdf(c->f, (double)s, c->R) -
               (x <= -R ? 0.0 : aa_filter_row_cdf(c->f, (double)s, x < R ? (double)x : c->R));
    /* left of the window the filter's mass from minus infinity, as truth.c
     * counts the colour left of the first crossing */
    double F = x <= -R ? c->FL : (x >= R ? c->FR : aa_filter_cdf(c->f, (double)x));
    return aa_filter_weight(c->f, (double)s) * ((long double)c->FR - F);
}

/* The term at the variable of integration u (turns, then theta). */
static inline long double term_eval(const term *t, long double u)
{
    long double v = u, jac = 1;
    if (t->turn == 2) {
        v = t->e + t->sign * u * u;
        jac = 2 * u;
    } else if (t->turn == 4) {
        long double u3 = u * u * u;
        v = t->e + t->sign * u3 * u;
        jac = 4 * u3;
    }
    if (!t->theta)
        return jac * term_at(t, v);
    long double R = t->c->R;
    return jac * R * cosl(v) * term_at(t, R * sinl(v));
}

/* The epsilon of long double where this runs: double's where an emulator
 * (valgrind) computes long double in double, as truth.c's fixed rule
 * checks too (aa_long_double_is_extended). */
static long double ld_epsilon(void)
{
    return aa_long_double_is_extended() ? LDBL_EPSILON : DBL_EPSILON;
}

/* The 21-point Gauss-Kronrod pass on [a, b] in long double, with QUADPACK's
 * error estimate (the scaled |K21 - G10|), the plain |K21 - G10| in *raw,
 * and, apart, the rounding floor (50 epsilon of the integral of |f|),
 * which bisection does not lower. */
void aa__truth_gk21l(long double (*f)(long double, const void *), const void *ctx, long double a,
                     long double b, long double *result, long double *abserr, long double *raw,
                     long double *floor)
{
    long double center = 0.5L * (a + b), half = 0.5L * (b - a), fc = f(center, ctx);
    long double resg = 0, resk = WGK[10] * fc, resabs = fabsl(resk), fv1[10], fv2[10];
    for (int j = 0; j < 5; j++) {
        int jtw = 2 * j + 1;
        long double absc = half * XGK[jtw], f1 = f(center - absc, ctx), f2 = f(center + absc, ctx);
        fv1[jtw] = f1, fv2[jtw] = f2;
        resg += WG[j] * (f1 + f2);
        resk += WGK[jtw] * (f1 + f2);
        resabs += WGK[jtw] * (fabsl(f1) + fabsl(f2));
    }
    for (int j = 0; j < 5; j++) {
        int jtwm1 = 2 * j;
        long double absc = half * XGK[jtwm1], f1 = f(center - absc, ctx),
                    f2 = f(center + absc, ctx);
        fv1[jtwm1] = f1, fv2[jtwm1] = f2;
        resk += WGK[jtwm1] * (f1 + f2);
        resabs += WGK[jtwm1] * (fabsl(f1) + fabsl(f2));
    }
    long double reskh = 0.5L * resk, resasc = WGK[10] * fabsl(fc - reskh);
    for (int j = 0; j < 10; j++)
        resasc += WGK[j] * (fabsl(fv1[j] - reskh) + fabsl(fv2[j] - reskh));
    long double ah = fabsl(half), err = fabsl((resk - resg) * half);
    *raw = err;
    resasc *= ah;
    resabs *= ah;
    if (resasc != 0 && err != 0) {
        long double r = 200 * err / resasc;
        err = r < 1 ? resasc * r * sqrtl(r) : resasc;
    }
    *result = resk * half;
    *abserr = err;
    *floor = 50 * ld_epsilon() * resabs;
}

static long double term_fn(long double u, const void *ctx)
{
    return term_eval(ctx, u);
}

/* Bisect until each part's estimate is within its share of eps (at most
 * *parts parts in all).  For a radial filter the estimate is the plain
 * |K21 - G10|: QUADPACK's scaling of it (its 1.5th power) assumes the rule
 * converges as for an analytic function, and near the cone's centre each
 * term is singular on the scale of its piece's distance from it (the
 * branch points of sqrt(x^2 + v^2)): a line 1e-3 from the centre was off
 * by 9e-14 with a scaled estimate of 7e-15.  Bisecting on the plain one is
 * what the other filters' terms, smooth or polynomial, do not need, but
 * for a piece that turns at an end: a breakpoint just past the turning
 * point (a kink line crossing an ellipse 4e-5 below its top) leaves the
 * square root's branch point just outside the next interval, where the
 * scaled estimate said 7.6e-15 of an error of 2.5e-14 (Gaussian, s =
 * 0.5). */
static void adapt(const term *t, long double a, long double b, long double eps, int *parts,
                  long double *res, long double *err)
{
    long double r, e, raw, fl, m = 0.5L * (a + b);
    aa__truth_gk21l(term_fn, t, a, b, &r, &e, &raw, &fl);
    if (t->theta || (t->k && (t->k->turn_lo || t->k->turn_hi)))
        e = raw; /* see above */
    if (e <= eps || e <= fl || *parts <= 0 || !(m > a && m < b)) {
        *res += r;
        *err += e > fl ? e : fl;
        return;
    }
    --*parts;
    adapt(t, a, m, 0.5L * eps, parts, res, err);
    adapt(t, m, b, 0.5L * eps, parts, res, err);
}

/* [a, b] with no breakpoint inside: ta, tb say whether an end is a
 * turning point, where the half next to it is taken in u with
 * |s - end| = u^ta (2: x moves like a square root there; 4: the cone's
 * centre, where each piece's term has its own v^2 log|v|: u^4 leaves
 * u^11 log u, which the rule integrates to rounding, where u^2 left
 * u^5 log u and errors of 5e-14 that the estimate did not see). */
static void interval(term *t, long double a, long double b, int ta, int tb, long double eps,
                     int *parts, long double *res, long double *err)
{
    if (!ta && !tb) {
        t->turn = 0;
        adapt(t, a, b, eps, parts, res, err);
        return;
    }
    long double m = 0.5L * (a + b);
    if (ta) {
        t->turn = ta, t->e = a, t->sign = 1;
        adapt(t, 0, ta == 2 ? sqrtl(m - a) : sqrtl(sqrtl(m - a)), 0.5L * eps, parts, res, err);
    } else {
        t->turn = 0;
        adapt(t, a, m, 0.5L * eps, parts, res, err);
    }
    if (tb) {
        t->turn = tb, t->e = b, t->sign = -1;
        adapt(t, 0, tb == 2 ? sqrtl(b - m) : sqrtl(sqrtl(b - m)), 0.5L * eps, parts, res, err);
    } else {
        t->turn = 0;
        adapt(t, m, b, 0.5L * eps, parts, res, err);
    }
}

/* The power of the turn at s shared by every term (radial: the centre),
 * or 0. */
static int vturn(const crowd *c, double s)
{
    for (int k = 0; k < c->nvturn; k++)
        if (c->vturn[k] == s)
            return 4;
    return 0;
}

/* The variable of integration at height s: s, or for a radial filter
 * theta = asin(s / R).  The disc's chord closes like sqrt(R^2 - s^2) at
 * s = -R and R, and each term has that square root (as the sum of them
 * does, where much of it cancels): in theta it is R cos theta, smooth.
 * A piece crossing the circle next to the chord's end (a kink at 1 - 4e-5
 * R, beside the square root) was integrated in s with an error of 2e-13
 * that the estimate put at 2e-15. */
static long double var_of(const crowd *c, double s)
{
    if (!c->radial)
        return s;
    long double r = (long double)s / c->R;
    return asinl(r < -1 ? -1 : (r > 1 ? 1 : r));
}

static int turn_at(const crowd *c, const crowd_piece *k, double s)
{
    int p = vturn(c, s);
    if (!p && k && ((k->turn_lo && s == k->lo) || (k->turn_hi && s == k->hi)))
        p = 2;
    if (!p && k && s == k->near)
        p = 4;
    return p;
}

/* A term's integral over [a, b], cut at the global breakpoints (the
 * filter's kinks in v, the Gaussian's panels) and the piece's own. */
static void term_integral(const crowd *c, const crowd_piece *k, double a, double b,
                          long double eps, long double *res, long double *err)
{
    term t = {c, k, 0, 0, 0, c->radial};
    const double *own = k ? c->cw->kink + k->kink0 : NULL;
    int nown = k ? k->nkink : 0, iv = 0, io = 0, parts = CROWD_PARTS;
    while (iv < c->nvkink && c->vkink[iv] <= a)
        iv++;
    while (io < nown && own[io] <= a)
        io++;
    double u = a;
    long double span = (long double)b - a;
    for (;;) {
        double v = b;
        if (iv < c->nvkink && c->vkink[iv] < v)
            v = c->vkink[iv];
        if (io < nown && own[io] < v)
            v = own[io];
        int tu = turn_at(c, k, u), tv = turn_at(c, k, v);
        if (v > u)
            interval(&t, var_of(c, u), var_of(c, v), tu, tv, eps * ((long double)v - u) / span,
                     &parts, res, err);
        if (v >= b)
            break;
        while (iv < c->nvkink && c->vkink[iv] <= v)
            iv++;
        while (io < nown && own[io] <= v)
            io++;
        u = v;
    }
}

static double max_abs3(const double *v)
{
    return fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
}

/* ---- the pixel ---- */

/* Piece k's own breakpoints in (lo, hi): where it crosses the lines x at
 * which the filter's cdf has a kink inside the window (tent: 0), for the
 * Gaussian the lines x = m s, for a radial filter the circle of radius R. */
static int own_kinks(crowd *c, crowd_piece *k, const double *kx, int nkx)
{
    crowd_worker *cw = c->cw;
    double ys[8];
    k->kink0 = (int)cw->nkink;
    k->nkink = 0;
    for (int j = 0; j < nkx; j++) {
        int m;
        if (c->radial) {
            m = truth_circle_heights(k->p, c->uc, c->vc, c->R, cw->poly, ys);
        } else {
            m = aa_piece_meet_x(k->p, c->uc + kx[j], ys);
            for (int q = 0; q < m; q++)
                ys[q] -= c->vc;
        }
        int st = grow((void **)&cw->kink, &cw->cap_kink, cw->nkink + (size_t)m, sizeof *cw->kink);
        if (st)
            return st;
        for (int q = 0; q < m; q++)
            if (ys[q] > k->lo && ys[q] < k->hi)
                cw->kink[cw->nkink++] = ys[q];
    }
    k->near = NAN;
    if (c->radial && !grow((void **)&cw->kink, &cw->cap_kink, cw->nkink + 1, sizeof *cw->kink)) {
        /* Where the piece passes closest to the centre, its term changes on
         * the scale of that distance (rho = sqrt(x^2 + v^2) there), too fast
         * for the rule's estimate to see on a long interval (a line 1e-3
         * from the centre: an error of 1e-12 against an estimate of 3e-16):
         * that height is a breakpoint, taken in u^4 on both sides, as the
         * centre is (truth_nearest_height). */
        k->near = truth_nearest_height(&k->q, k->lo, k->hi, c->R);
        if (k->near == k->near)
            cw->kink[cw->nkink++] = k->near;
    }
    k->nkink = (int)(cw->nkink - (size_t)k->kink0);
    if (k->nkink > 1)
        qsort(cw->kink + k->kink0, (size_t)k->nkink, sizeof *cw->kink, truth_cmp_double);
    return AA_OK;
}

int crowd_pixel(crowd_worker *cw, const aa_scene *scene, const aa_strip *strip,
                const aa_filter *f, double uc, double vc, const aa_piece *const *local, size_t n,
                int grey, int only_crossed, double *value, double *bound)
{
    int nl = aa_scene_layer_count(scene), st;
    nl = nl > 0 ? nl : 1;
    if ((st = reserve_pieces(cw, n, nl)))
        return st;
    crowd c;
    memset(&c, 0, sizeof c);
    c.cw = cw;
    c.scene = scene;
    c.strip = strip;
    c.f = f;
    c.uc = uc;
    c.vc = vc;
    c.R = f->radius;
    c.box = aa_filter_is_box(f);
    c.radial = !aa_filter_is_separable(f);
    c.gauss = f->type == &aa_filter_gauss;
    c.nc = grey ? 1 : 3;
    c.W = cw->wind;
    double R = c.R;
    if (c.radial && !cw->poly && !(cw->poly = gsl_poly_complex_workspace_alloc(5)))
        return aa_fail(AA_ENOMEM, "out of memory for a polynomial workspace");
    if (!c.radial) {
        c.FR = c.box ? R : aa_filter_cdf(f, R);
        c.FL = c.box ? -R : 0.0; /* from minus infinity, as truth.c */
    }
    /* breakpoints shared by every term: the filter's kinks in v, the
     * Gaussian's panels of two standard deviations (as truth.c's) */
    double kink[8], kx[64];
    int nk = f->type->kinks(f->spec.v, kink), nkx = 0;
    for (int k = 0; k < nk; k++)
        if (kink[k] > -R && kink[k] < R)
            c.vkink[c.nvkink++] = kink[k];
    if (c.gauss) {
        double sd = f->spec.v[0];
        for (double z = -R + 2.0 * sd; z < R && c.nvkink < 32; z += 2.0 * sd)
            c.vkink[c.nvkink++] = z;
        for (double t = -floor(R / sd) * sd; t <= R && nkx < 64; t += sd)
            if (t > -R && t < R)
                kx[nkx++] = t;
    } else if (c.radial) {
        nkx = 1; /* the circle */
        c.vturn[c.nvturn++] = 0.0;
    } else {
        for (int k = 0; k < nk; k++)
            if (kink[k] > -R && kink[k] < R)
                kx[nkx++] = kink[k];
    }
    qsort(c.vkink, (size_t)c.nvkink, sizeof *c.vkink, truth_cmp_double);
    /* the pieces */
    cw->nheap = 0;
    cw->nseg = 0;
    cw->nkink = 0;
    for (size_t k = 0; k < n && !st; k++) {
        const aa_piece *p = local[k];
        if (!p->dir) {
            /* a horizontal edge on the left side: the colour there changes */
            double y = p->y0 - vc, l = uc - R;
            if (y > -R && y < R && p->xmin <= l + CROWD_SIDE && p->xmax >= l - CROWD_SIDE)
                push(&c, y, EV_BASE, -1, -1);
            continue;
        }
        double lo = fmax(p->y0 - vc, -R), hi = fmin(p->y1 - vc, R);
        if (!(lo < hi))
            continue;
        crowd_piece *q = &cw->cp[c.np];
        memset(q, 0, sizeof *q);
        q->p = p;
        truth_set_local(&q->q, p, uc, vc);
        q->lo = lo;
        q->hi = hi;
        for (int side = -1; side <= 1; side += 2) {
            double ys[3];
            int m = aa_piece_meet_x(p, uc + side * R, ys);
            for (int j = 0; j < m; j++)
                if (ys[j] - vc > lo && ys[j] - vc < hi)
                    q->cross[q->ncross++] = ys[j] - vc;
        }
        qsort(q->cross, (size_t)q->ncross, sizeof *q->cross, truth_cmp_double);
        q->region = CP_OFF;
        q->slot = (int)c.np;
        q->seg_a = NAN;
        int tlo, thi;
        truth_turns(p, &tlo, &thi);
        q->turn_lo = tlo && lo == p->y0 - vc;
        q->turn_hi = thi && hi == p->y1 - vc;
        q->scale = truth_piece_scale(&q->q) + R;
        st = own_kinks(&c, q, kx, nkx);
        c.np++;
    }
    if (st || (st = sweep(&c)))
        return st;
    if (cw->record)
        return AA_OK; /* crowd_events: the sweep's heights only */
    if (only_crossed && !c.swaps)
        return CROWD_DECLINED;
    /* the integrals: each term to its share of TRUTH_EPSABS */
    /* Shares by length and jump, never looser per unit of height than
     * truth.c's intervals (TRUTH_EPSABS over 2R): the estimate can fall
     * short of the error while a term varies fast (a nearly horizontal
     * piece through the cone's centre: 1.9e-13 against 4e-14), and
     * bisecting further is what catches it. */
    double total = 2.0 * R;
    for (size_t g = 0; g < cw->nseg; g++)
        total += (cw->seg[g].b - cw->seg[g].a) * max_abs3(cw->seg[g].dc);
    long double acc[3] = {0, 0, 0}, err = 0, rnd = 0, leps = ld_epsilon();
    double xpeak = c.box ? 1.0 : c.radial ? aa_filter_weight2(f, 0, 0) : pow(aa_filter_weight(f, 0), 2);
    double vpeak = c.box ? 1.0 : c.radial ? aa_filter_weight2(f, 0, 0) * R : aa_filter_weight(f, 0);
    for (size_t g = 0; g < cw->nseg; g++) {
        const crowd_seg *s = &cw->seg[g];
        double wmax = max_abs3(s->dc), len = s->b - s->a;
        long double res = 0, e = 0, eps = TRUTH_EPSABS * len * wmax / total;
        const crowd_piece *k = s->k >= 0 ? &cw->cp[s->k] : NULL;
        if (!k && !c.radial) {
            /* the left side's colour: the whole row's weight, exactly */
            long double fb = c.box ? s->b : aa_filter_cdf(f, s->b);
            long double fa = c.box ? s->a : aa_filter_cdf(f, s->a);
            res = ((long double)c.FR - c.FL) * (fb - fa);
        } else {
            term_integral(&c, k, s->a, s->b, eps, &res, &e);
        }
        for (int ch = 0; ch < c.nc; ch++)
            acc[ch] += s->dc[ch] * res;
        err += wmax * e;
        rnd += wmax * len *
               (16 * leps * (k ? k->scale : R) * xpeak + (c.box ? 0 : 4 * DBL_EPSILON * vpeak));
    }
    for (int ch = 0; ch < 3; ch++)
        value[ch] = (double)acc[grey ? 0 : ch];
    *bound = (double)(err + rnd) + f->lost + 2 * DBL_EPSILON;
    return AA_OK;
}

int crowd_events(crowd_worker *cw, const aa_scene *scene, const aa_strip *strip,
                 const aa_filter *f, double uc, double vc, const aa_piece *const *local, size_t n,
                 const double **hs, size_t *nh)
{
    cw->record = 1;
    cw->nev = 0;
    int st = crowd_pixel(cw, scene, strip, f, uc, vc, local, n, 0, 0, NULL, NULL);
    cw->record = 0;
    *hs = cw->ev;
    *nh = st ? 0 : cw->nev;
    return st;
}
