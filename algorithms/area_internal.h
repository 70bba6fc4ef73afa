/*
 * area_internal.h: what the exact area method's rows (area.c) and Catmull's
 * recursive pixel integrater (area_catmull.c) share, with the colours of
 * scenes that composite (area_composite.c): the pieces as the
 * method reads them, the per-thread workspace, and the small helpers.
 */
#ifndef AA_AREA_INTERNAL_H
#define AA_AREA_INTERNAL_H

#include "core.h"

#include <math.h>
#include <stdint.h>
#if defined(__SSE2__) && defined(__x86_64__)
#include <emmintrin.h>
#define AR_STREAM 1
#else
#define AR_STREAM 0
#endif

/* Clusters of more segs than this are tested for crossings by neighbours
 * along x (area.c, any_crossing). */
#define AR_CROWD 64
/* Catmull's integrater works on at most this many edges in a pixel. */
#define CM_MAX_EDGES 48
#define CM_MAX_VERTS (CM_MAX_EDGES + 8)
/* Sub-band boundaries (and crossings) gathered per pass: room for this
 * many at first, doubled where a band has more, up to CM_MAX_EVENTS_GROWN
 * (24 bytes each, 24 MB); beyond that, more passes (bounded memory). */
#define CM_MAX_EVENTS 2048
#define CM_MAX_EVENTS_GROWN (1 << 20)
/* Crossings this close (in y, px) to a band's edge are not split. */
#define CROSS_MARGIN 1e-12
/* Catmull: edges this close (px) to a splitting line lie on it. */
#define CM_EPS 1e-14
/* Images larger than this are written with non-temporal stores.  Measured
 * on `crow` here: 1024^2 (24 MB) is faster with ordinary stores (it stays
 * in the last-level cache), 1536^2 (54 MB) and larger faster streamed
 * (4096^2: 17.1 against 18.6 ms). */
#define STREAM_BYTES (32.0 * 1024 * 1024)
/* Rows per extended-precision expansion of a piece. */
#define ANCHOR_ROWS 16
/* Integer range of cell origins. */
#define CELL_LIMIT 1073741824.0
/* Translucent layers, groups and clips: colours of winding states kept
 * per worker (entries, hash slots: a power of two, at least twice the
 * entries), and the ring of colours colour_of hands out (composite_colour). */
#define AR_CACHE_ENTRIES 1024
#define AR_CACHE_SLOTS 2048
#define AR_RING 4
/* Offset pieces (area_offset.c): the largest error bound of the quadrature
 * of one part's share of a panel (px^2), the panels' order, and the number
 * of Gauss-Legendre rules tried. */
#define AR_QUAD_TOL 1e-15
#define AR_QUAD_NMAX 16
#define AR_QUAD_RULES 3

/* Gauss-Legendre rules on [-1, 1]: rule r has n[r] points x, w from at[r]. */
typedef struct ar_quad {
    int n[AR_QUAD_RULES], at[AR_QUAD_RULES];
    double x[64], w[64];
    int avx; /* a cubic's nodes eight a pass (2: AVX-512F), four (1: AVX) or two */
} ar_quad;

/* A panel of an offset piece's parameter (area_offset.c): [a, b], its
 * middle m; on the disc |t - m| <= R the quadrature's integrand is at most
 * M (px^2, with the map's factor); bx, by: B's Taylor coefficients about m
 * (B(m + s) - B(m) = s (b1 + s (b2 + s b3)), [0] = 0); for the offsets of
 * an ellipse (AA_OFFSET_ELLIPSE) its semi-diameters at m instead, u' =
 * (bx[1], by[1]) and v' = (bx[2], by[2]): B(m + s) - B(m) = u' (cos s - 1)
 * + v' sin s. */
typedef struct ar_panel {
    double a, b, m, R, M;
    double bx[4], by[4];
    /* a cubic's factored form about te on this panel (aa__offset_stop at
     * m, found once): stop, te, Q's coefficients q */
    int stop;
    double te, q[4];
    /* B(m) mapped into the image (the curve's map), each coordinate as a
     * sum hi + lo of two doubles ([0] + [1], from long double): a part's
     * start from the row's point (area_offset_segment_at) */
    double qx[2], qy[2];
} ar_panel;

/* ------------------------------------------------------------------------
 * Pieces, as the method reads them (shared, read-only)
 * ------------------------------------------------------------------------ */

typedef struct ar_piece {
    /* what every row reads first, in one cache line */
    double y0, y1;     /* y range */
    double xmin, xmax; /* x extent of the whole piece */
    int flat, line, dir, layer;
    uint32_t id; /* index in the scene: the tie-break of every sort */
    int curved;  /* a cubic, conic or offset piece (0: a line or quadratic, the
                  * common path, whose tests stay in this cache line) */
    double byd;      /* by rounded, to find T */
    /* what band_roots reads of an offset piece, the 64 bytes after the
     * above (the fields are described below; ot0 and ot1 src's, copied) */
    int offset, ostops; /* ostops: its curve's stops (aa__offset_stops) */
    double ot0, ot1;
    const double *ytab;
    size_t nyt;
    double ytlo, ythi;
    const aa_piece *src; /* the scene's piece (crossings of cubics and conics) */
    double ayd;          /* ay rounded, to find T */
    double k6;           /* (y' x'' - x' y'') / 12, constant along a parabola */
    /* power basis from the control points, extended precision:
     * x(t) = x0 + t (bx + t (ax + t dx)), y(t) = y0 + t (by + t (ay + t dy)),
     * dx = dy = 0 but for cubics */
    long double x0, bx, ax, y0l, by, ay, dx, dy;
    int cubic;
    int conic;            /* an arc of an ellipse: its fields are src's */
    /* an offset piece's parts integrated about the row's point
     * (area_offset_segment_at): where long double is wider than double and
     * the map's condition number is at most 4, so that the start's error
     * in the image stays a few ulps of the coordinates; else about the
     * curve's own (rel_point, the point not given) */
    int rowpt;
    double dyd;           /* dy rounded */
    /* An offset piece (AA_PIECE_OFFSET): its "tau" is sg t (t the curve's
     * parameter, sg = +-1 so that tau rises down the piece); te, te2: tau
     * where x turns (ascending, infinite if none); its panels (npan of
     * them, state-owned) and the rules (area_offset.c); oend: y's
     * evaluation at its bottom ot1 (aa__offset_end), which every band
     * line's root would repeat; ofix: what its roots take from the curve
     * alone (aa__offset_fix_init); ytab: the nyt nodes of its table of
     * roots' starts in y (ytab_guess; area.c, load_ytab; state-owned, 4
     * doubles each, yt0 the first's index in the state's), ytlo and ythi
     * its first and last node's y (ytab_attach; NAN without a table):
     * ytab_guess's range, not read from the table's two ends each root;
     * ot0, ot1: src's (its t range), in band_roots' cache line */
    aa__offset_fix ofix;
    double sg, ote, ote2;
    double oend[4];
    const ar_panel *pan;
    size_t pan0, npan; /* pan0: the first panel's index in the state's */
    size_t yt0;
    const ar_quad *quad;
} ar_piece;

/* A piece as a worker sees it, one per piece, kept from row to row.
 *
 * Its expansion about its point on the line y = ja (or its top, if lower),
 * exact from the control points, in cell-local coordinates: u(tau) =
 * U + tau (g + tau ax) is x - c0 and v(tau) = Va + tau (vy + tau ay) is
 * y - ja, tau = t - T with T the parameter at that point.  One expansion
 * serves ANCHOR_ROWS rows.  Then its part inside the current band [j, j+1],
 * where v is y - j (V = Va - (j - ja)). */
typedef struct ar_seg {
    const ar_piece *p;
    int ja, c0, mline;
    double U, Va, g, vy, ax, ay;
    /* a cubic's terms (0 for others): u and v gain tau^3 cx3, tau^3 cy3 */
    double cx3, cy3;
    double t0;   /* tau at the piece's top (-T) */
    /* a cubic's (an offset piece's) second x extremum, not before te
     * (infinite if none, and where te is): seg_make and single_kind test
     * te < tb first */
    double te2;
    double te;   /* tau of the x extremum (infinite if none) */
    double ivy;  /* 1 / vy when ay = 0, and for a cubic (its guesses) */
    double k6;   /* (y' x'' - x' y'') / 12, constant along a parabola */
    double tend; /* tau at the piece's end */
    /* A conic (aa_piece, AA_PIECE_CONIC): its "tau" is q = tan((s - ang)/2),
     * the half-angle tangent about its point at s = ang, and
     * u = U + 2 q (g + ax q)/(1 + q^2), v = Va + 2 q (vy + ay q)/(1 + q^2)
     * (from sin tau and 1 - cos tau; (g, vy) = P'(ang), (ax, ay) =
     * -(P(ang) - centre)); k6 = -eb er / 2; t0, tend: q at the piece's
     * ends where they lie in the anchor's rows (else -+infinity).
     * An offset piece (AA_PIECE_OFFSET): g is its tau at its anchor point
     * (line_tau's root on the anchor's line); vy, ax, ay, cx3, cy3, ivy,
     * k6 are 0 */
    /* tau and u on the line y = ja + mline (the bottom of the last band
     * rendered): the next band's top, without solving again */
    double tline, uline;
    long double xline, yline; /* an offset piece's x and y there (the next band's top,
                               * and the next anchor's point: expand_offset) */
    size_t ythint;     /* an offset piece's last interval of its table (ytab_guess) */
    /* an offset piece: its v at up to four taus vt of the current band
     * (NAN: none), the ends of its parts: [2] and [3] the band's ends as
     * seg_make evaluated them, [0] and [1] the others (seg_u, part_area,
     * the cells' sides' roots), vn the one of those written next */
    double vt[4], vv[4];
    int vn;
    /* an offset piece: its parameters mt at up to two heights my inside
     * the band (absolute; NAN: none) where a pair's common heights began
     * or ended, solved over the whole piece as aa__piece_meet_at would
     * (pair_crossings), mn the one written next */
    double my[2], mt[2];
    int mn;
    /* an offset piece: its x xx at up to two heights xy (absolute; NAN:
     * none, from band_fields and worker_alloc) and parameters xt there, found for the first
     * pair of its band asking there (pair_crossings, aa__piece_end_x) and
     * kept for the others */
    double xy[2], xt[2], xx[2];
    /* the ends of the sub-bands of a band cut at its events (area.c,
     * cluster_bands; sub_key, sub_end) at up to two heights bv
     * (band-relative; NAN: none, from band_fields): tau bt, u for the
     * order bu (an offset piece's from its root's last evaluation, as
     * key_u's), u as seg_u gives it bx (NAN: not yet) and an offset
     * piece's v kept there bk; bn the one written next.  A sub-band's
     * bottom is the next one's top, and its order and its sweep both ask. */
    double bv[2], bt[2], bu[2], bx[2], bk[2];
    int bn;
    /* a sub-band sweep's part not yet added (area.c, sweep_part): from v =
     * wya (tau wt, u wu, an offset piece's v there wv) down to wyb (NAN:
     * none, set so by band_fields; INFINITY: open, lengthened through
     * every sub-band since, to where the sweep next finds the seg with
     * another jump or none, or to its end vb), its colour jump wdc */
    double wya, wyb, wt, wu, wv, wdc[3];
    /* the current band */
    double V;
    double ta, tb;  /* tau at the band's (or piece's) top and bottom */
    double ua, ub;  /* u there */
    double va, vb;  /* v there: max(0, y0 - j), min(1, y1 - j) */
    double lo, hi;  /* u extent inside the band */
    int ca, cb;     /* first and last cell touched, in [-1, W] */
    /* a seg alone in its cluster in two cells (cb = ca + 1): of single()'s
     * kind (the image's cells, single_kind), as side_ask found it for the
     * row's batches, taken by close_single (not tested again there); set
     * only on those segs, by side_ask in the row, and read only there */
    int kind;
    /* an offset piece's root on the line y = prej + 1 (the bottom of band
     * prej) and its point there, found before the band's segs are made
     * (area.c, band_roots; INT_MIN: none), taken by seg_make; then, on an
     * offset seg alone in its cluster and of single()'s kind in two cells,
     * the root on their common side (as asked: sg times tau) and y there
     * in prexy[1], asked in the row's batches before its clusters close
     * (area.c, side_ask) and taken by single() (the struct not grown: 640
     * bytes; at 672 the segs' indexing cost 0.69 M instructions a render
     * at 1024 px, 0.97 M at 256 px) */
    int prej;
    double pret;
    long double prexy[2];
} ar_seg;

typedef struct ar_key {
    double key;
    uint32_t id, idx;
} ar_key;

/* Catmull: an edge clipped to the pixel, pixel-local coordinates. */
typedef struct cm_edge {
    double x0, y0, x1, y1;
    int layer;
} cm_edge;

typedef struct cm_level {
    int nv, ne;
    double vx[CM_MAX_VERTS], vy[CM_MAX_VERTS];
    cm_edge e[CM_MAX_EDGES];
} cm_level;

/* One thread's workspace.  Workers and everything they write are kept on
 * cache lines of their own (a shared line made two threads slower than
 * one). */
typedef struct ar_worker {
    _Alignas(64) uint32_t *active; /* indices into the sorted pieces */
    size_t nactive, next;
    size_t carried;   /* active[0..carried): pieces of the rows before */
    double first_end; /* the lowest bottom of an active piece */
    int row;          /* last row rendered (-2: none) */
    ar_seg *seg;     /* per sorted piece */
    uint32_t *list;  /* the current row's segs, in active order */
    /* the one pass's clusters of one seg in two cells (their segs), or the
     * sorted pass's clusters (each one's end and hi): area.c, side_ask */
    uint32_t *side;
    ar_key *order, *sub;
    ar_key *tops; /* a crowded band's segs by their tops (area.c, order_next) */
    /* 2 doubles a seg: u at the (sub-)band's two ends of each seg
     * order_ends orders; the right ends of reaching's segs before it */
    double *ends;
    /* 2 doubles a seg: the heights in the band (va, vb) of a cluster's
     * segs in its order by left ends, for cluster_bands' sub-bands' spans
     * and band_events' pairs */
    double *vab;
    double *acc, *cov; /* per cell and channel */
    int *wind, *wtmp;
    double *ev;
    size_t ev_room, cx_room; /* ev's and cx's room, CM_MAX_EVENTS or grown */
    /* the crossings band_events found (cx[0..ncx), in order of height after
     * it; cxfull: some were not kept) and the segs they touch at a
     * sub-band's top (mark[seg] == stamp), for cluster_bands' order of
     * the next sub-band from the one above */
    struct ar_cross {
        double v;
        uint32_t a, b;
    } *cx;
    size_t ncx;
    int cxfull;
    uint32_t *mark, stamp;
    /* what order_next changed: the sub-band's order's first chlo segs and
     * its last chtail are the order above's */
    size_t chlo, chtail;
    uint32_t *act; /* segs whose extent reaches the current one */
    uint32_t *pend; /* the cluster's segs with a part kept by sweep_part */
    size_t npend;
    cm_level *cm;
    uint64_t expensive;
    /* a scene that composites (ar_state.composite): the colours of the
     * winding states met, by the set of layers whose fill rule holds
     * (ckey: nwords words each; ccol: their colours; cslot: the hash
     * table, -1 empty; cn entries used); key: the state being looked up;
     * ring: the colours handed out, the last AR_RING */
    uint64_t *ckey, *key;
    double (*ccol)[3];
    int32_t *cslot;
    unsigned cn, ringn;
    double ring[AR_RING][3];
    /* a scene with gradient paint (area_gradient.c): the first pixel, in
     * row order, that the worker refused (gerr an AR_GERR_ kind, 0 none;
     * gi, gj the pixel; ga, gb the layers or counts the message names) */
    int gerr, gi, gj, ga, gb;
    /* and the last AR_GMEMO region states met (gkey: nwords words each,
     * the set of layers whose fill rule holds; gmemo their states; gnext
     * the slot written next, gn the slots in use) */
    uint64_t *gkey;
    struct ar_gstate *gmemo;
    unsigned gnext, gn;
} ar_worker;

#define AR_GMEMO 8

/* A region's colour in a gradient scene (area_gradient.c): g < 0 flat (c,
 * linear light), else gradient g's paint composited as e = K0 + K1 o +
 * K2 o c per encoded channel. */
typedef struct ar_gstate {
    int g;
    double c[3], K0[3], K1[3], K2[3];
} ar_gstate;

/* Gradients (area_gradient.c): the most stops or period ends a repeated
 * gradient may pass across a pixel (more is refused at load); an edge's
 * walk along t passes at most 4 times as many. */
#define AR_GKNOTS 4096
/* Why a pixel of a gradient scene is refused (area_gradient.c). */
enum { AR_GERR_NONE, AR_GERR_TWO_GRADIENTS, AR_GERR_EDGES, AR_GERR_KNOTS, AR_GERR_LINEAR_LIGHT };

/* A linear gradient layer as `area` reads it (area_gradient.c): t(x, y) =
 * gu x + gv y + g0 in pixel units; the knots of t (where the spread turns
 * or a stop is passed) are base + knot[k], base a multiple of the period
 * (0: pad, knots absolute); enc: the stops' encoded channels and opacity. */
typedef struct ar_grad {
    int layer, spread, nstops, nknots;
    double gu, gv, g0, period;
    double *offset, (*enc)[4], *knot;
    /* lin: in linear light (area_gradient.c, "linear light"): lv[k] the
     * stops' linear channels and opacity */
    int lin;
    double (*lv)[4];
} ar_grad;

typedef struct ar_state {
    const aa_scene *scene;
    int w, nworkers;
    ar_piece *piece; /* by the row they enter in, then (xmin, id) (area.c, sort_pieces) */
    size_t npieces;
    /* each piece's layer and direction, 4 layer + dir + 1, side by side:
     * the windings a crowded sub-band's sweep starts from (area.c,
     * cluster_bands), summed over the head of its order, without a load
     * of each seg and its piece */
    int *ldir;
    int nl, nch;         /* layers; channels computed (1 for grey scenes) */
    /* 1 if the colour of a winding state is the scene's composite of the
     * layers covering it (translucent layers, groups of opacity, clips:
     * aa_scene_is_opaque is 0), not the front-most covering layer's;
     * nwords: 64-bit words of a state's key; nscan: layers colour_of
     * scans for the front-most (nl, or 0 in a scene that composites) */
    int composite, nwords, nscan;
    /* 1 if no piece is curved (cubic, conic or offset): the rows then take
     * render_row's form compiled without those cases (area.c) */
    int plain;
    double (*colour)[3]; /* per layer, then the background */
    int *evenodd;
    /* per layer, the bits of a winding number that put a point inside it:
     * 1 under even-odd, all under nonzero (colour_of's one test) */
    int *inside;
    ar_worker *workers;
    ar_panel *pan; /* the offset pieces' panels (cappan allocated) */
    size_t npan, cappan;
    double *ytab; /* the offset pieces' tables' nodes (capyt allocated) */
    size_t nyt, capyt;
    ar_quad quad;
    /* gradient paint (area_gradient.c): the linear gradient layers, and per
     * layer the index of its gradient, -1 for a layer painting its colour */
    ar_grad *grad;
    int ngrad, *gof;
} ar_state;

/* Row context passed through the cluster functions. */
typedef struct ar_row {
    const ar_state *S;
    ar_worker *wk;
    int j, W, integrator, stream;
    double *px; /* the row's first pixel */
    int grey;   /* nch == 1 and not stream: a pixel is one value stored thrice */
} ar_row;

/* Gradient scenes (area_gradient.c): the scene's gradients read, or a
 * refusal by name of what `area` cannot integrate exactly; freed with
 * the state. */
int area_gradient_load(ar_state *S, const aa_scene *scene);
void area_gradient_free(ar_state *S);
/* Pixels [i0, i1) of row r, all of winding state w (no edge inside). */
void area_gradient_run(const ar_row *r, int i0, int i1, const int *w);
/* The cluster of cells [lo, hi] of row r by Catmull's integrater split on
 * every edge, each region's integral of the decoded composite exact; 0 if
 * refused (the worker's gerr says why). */
int area_cluster_gradient(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                          const int *w);
/* The negative control of tests/test_area_gradient.c: 0 makes the
 * integration skip its split at the decoding's threshold (wrong on
 * purpose; the test must then fail).  1 always otherwise. */
extern int aa__area_gradient_split;

/* ------------------------------------------------------------------------
 * Small helpers shared by the rows and Catmull's integrater
 * ------------------------------------------------------------------------ */

/* The colour of winding state w in a scene that composites
 * (area_composite.c): a
 * pointer into the worker's ring, valid for the next AR_RING - 1 calls. */
const double *area_composite_colour(const ar_state *S, ar_worker *wk, const int *w);

/* The colour of winding state w: in an opaque scene the front-most layer's
 * whose fill rule holds (or the background), else the scene's composite.
 * A pointer that stays valid for AR_RING - 1 more calls on this worker
 * (forever in an opaque scene): callers hold at most two at once.  A scene
 * that composites scans no layer here (nscan = 0), so the opaque scenes'
 * path is the loop alone, tested for compositing only where no layer
 * covers. */
static inline const double *colour_of(const ar_state *S, ar_worker *wk, const int *w)
{
    int l = 0;
    for (; l < S->nscan; l++)
        if (w[l] & S->inside[l]) /* evenodd[l] ? w[l] & 1 : w[l] != 0 */
            return S->colour[l];
    if (l == 0 && S->composite) /* l = nl in an opaque scene */
        return area_composite_colour(S, wk, w);
    return S->colour[S->nl];
}

/* An offset piece's point at its curve's parameter t (extended
 * precision), its ends the piece's own: the outline's vertex where the
 * piece meets the next (a line across the stroke, a join's arc) is a point
 * rounded to double, (x0, y0) or (x1, y1), and the curve evaluated at ot0
 * or ot1 misses it by up to about an ulp of the coordinates (4.2e-14 px at
 * y = 793).  Taken as evaluated, the outline would not close: a strip of
 * that height right of the vertex, wound once more or less, across every
 * cell of the row up to the next one the piece's row finishes uniform
 * (1.1e-13 off in pixel (716, 793) of tests/bench_bezstroke.c's scene).
 * The reference takes the same ends (harness/truth, truth_offset_part).
 * Between them, the point as the piece's roots give it
 * (aa__offset_point_fix: the double-double form on a cubic's offset
 * without stops, else aa__offset_eval_s). */
static inline void offset_point(const ar_piece *p, double t, long double *X, long double *Y)
{
    const aa_piece *q = p->src;
    if (t == q->ot0) {
        *X = q->x0, *Y = q->y0;
    } else if (t == q->ot1) {
        *X = q->x1, *Y = q->y1;
    } else {
        aa__offset_point_fix(&q->oc, &p->ofix, t, X, Y);
    }
}

/* An offset piece's v at tau (y relative to the line y = -V; extended
 * precision, then rounded). */
static inline double offset_v(const ar_seg *s, double t)
{
    long double X, Y;
    offset_point(s->p, s->p->sg * t, &X, &Y);
    return (double)(Y + s->V);
}

/* An offset piece's memo of v at the ends of its parts, each of which is
 * evaluated once for u and v together: seg_make and sweep take u at the
 * ends, part_area the chord's height from v there, and a part starts
 * where the last ended.  The value kept is the one offset_v gives (same
 * tau, same band), but at a cell's side, where it is the root's own
 * (offset_tau_u: the last long double evaluation of the root moved by
 * its slope over the last step, within about 1e-22 of y'' of offset_v's
 * at the root, and the same for both parts that end there).  The band's
 * ends, which seg_make evaluated, stay in slots of their own (a walk
 * across cells keeps its sides' roots in the others: each of its parts
 * then finds both its ends).  The seg is the worker's own, never shared:
 * the memo is written through the const pointers the row code passes
 * (the object itself is not const). */
static inline void offset_keep(const ar_seg *s, double t, double v)
{
    ar_seg *w = (ar_seg *)s;
    w->vt[w->vn] = t, w->vv[w->vn] = v, w->vn ^= 1;
}

/* the slot of tau t in the memo, -1 if none */
static inline int offset_slot(const ar_seg *s, double t)
{
    return t == s->vt[2] ? 2 : t == s->vt[3] ? 3 : t == s->vt[0] ? 0 : t == s->vt[1] ? 1 : -1;
}

static inline double offset_v_kept(const ar_seg *s, double t)
{
    int k = offset_slot(s, t);
    return k >= 0 ? s->vv[k] : offset_v(s, t);
}

/* u at tau on a line or a quadratic (cx3 = 0): u_at's common case, which
 * the rows of a scene without curved pieces call directly (area.c,
 * render_row). */
static inline double u_quad(const ar_seg *s, double t)
{
    return s->U + t * (s->g + t * s->ax);
}

static inline double u_at(const ar_seg *s, double t)
{
    if (!s->p->curved) /* cx3 = 0 */
        return u_quad(s, t);
    if (s->p->offset) {
        long double X, Y;
        offset_point(s->p, s->p->sg * t, &X, &Y);
        return (double)(X - s->c0);
    }
    if (s->p->conic) /* sin tau = 2q/(1 + q^2), 1 - cos tau = 2q^2/(1 + q^2) */
        return s->U + 2.0 * t * (s->g + s->ax * t) / (1.0 + t * t);
    return s->U + t * (s->g + t * (s->ax + t * s->cx3));
}

/* seg_u of an offset piece, giving its y there too (*y). */
static inline double offset_seg_u(const ar_seg *s, double t, long double *y)
{
    long double X, Y;
    offset_point(s->p, s->p->sg * t, &X, &Y);
    offset_keep(s, t, (double)(Y + s->V));
    *y = Y;
    return (double)(X - s->c0);
}

/* u_at, keeping an offset piece's v there (offset_keep). */
static inline double seg_u(const ar_seg *s, double t)
{
    if (!s->p->curved || !s->p->offset) /* curved first: the common path's cache line */
        return u_at(s, t);
    long double y;
    return offset_seg_u(s, t, &y);
}

/* The Hermite form of t at y between nodes a and b of an offset piece's
 * table of starts (area.c, before offset_line_t) */
static inline double yt_herm(const double *a, const double *b, double y)
{
    double h = b[1] - a[1], u = (y - a[1]) / h, u2 = u * u, u3 = u2 * u;
    return a[0] + (b[0] - a[0]) * (3.0 * u2 - 2.0 * u3) +
           h * (a[2] * (u3 - 2.0 * u2 + u) + b[2] * (u3 - u2));
}

/* The start of y = yl between nodes a and b where t(y)'s Hermite form is
 * not within the table's tolerance (y turning at an end, dt/dy large
 * there): the root of y(t)'s Hermite form through both nodes' heights
 * and slopes (dy/dt = 1 / (dt/dy)), a cubic in s = (t - a[0]) / (b[0] -
 * a[0]), from the root of its quadratic Taylor form about the end of the
 * smaller slope (the turn's: exact where y is quadratic, where the
 * chord's s is off by about its square root), by YT_TURN_STEPS Newton
 * steps; a's t at a's height (there the quadratic's root s = 0 is not
 * strictly inside, and at a turn it is 0/0); NaN where the root is not
 * strictly inside.  Within 2.1e-7 of the root by a y turn at either end,
 * forwards or backwards, where the chord is 3.9e-3 off, 9e-6 where y has
 * a cubic term too (tests/test_area_offset.c, test_turn_starts); before,
 * these lines' roots started from the piece's ends (the solver's
 * quadratic through them), about 936 instructions a root against about
 * 550 from a start within the first double step. */
#define YT_TURN_STEPS 2
static inline double yt_turn(const double *a, const double *b, double yl)
{
    double h = b[0] - a[0], dy = b[1] - a[1], c1 = h / a[2], mb = h / b[2];
    double c0 = a[1] - yl, c2 = 3.0 * dy - (2.0 * c1 + mb), c3 = (c1 + mb) - 2.0 * dy, s;
    if (c0 == 0.0) /* node a's height */
        return a[0];
    if (fabs(c1) <= fabs(mb)) { /* about s = 0: c0 + c1 s + c2 s^2, c0 of the sign
                                 * opposite dy's, cancellation-free */
        double q = c1 * c1 - 4.0 * c2 * c0;
        s = q >= 0 ? -2.0 * c0 / (c1 + copysign(sqrt(q), dy)) : -c0 / dy;
    } else { /* about s = 1 (u = s - 1): d0 + mb u + d2 u^2 */
        double d0 = b[1] - yl, d2 = c2 + 3.0 * c3, q = mb * mb - 4.0 * d2 * d0;
        s = 1.0 + (q >= 0 ? -2.0 * d0 / (mb + copysign(sqrt(q), dy)) : -d0 / dy);
    }
    for (int k = 0; k < YT_TURN_STEPS; k++)
        s -= (c0 + s * (c1 + s * (c2 + s * c3))) / (c1 + s * (2.0 * c2 + 3.0 * s * c3));
    double g = a[0] + s * h;
    return (a[0] < b[0] ? (g > a[0] && g < b[0]) : (g < a[0] && g > b[0])) ? g : NAN;
}

/* Offset piece p's table of starts (its nyt nodes at n), and the range
 * of heights ytab_guess takes from it (NAN: no table) */
static inline void ytab_attach(ar_piece *p, const double *n)
{
    p->ytab = n;
    p->ytlo = p->nyt >= 2 ? n[1] : NAN;
    p->ythi = p->nyt >= 2 ? n[4 * (p->nyt - 1) + 1] : NAN;
}

/* The start of a root of y = yl on offset piece p from its table (on an
 * interval marked not within the table's tolerance, yt_turn's), NaN where
 * the table has none (the solver then starts as it would without).
 * The nodes' y rise strictly (load_ytab), so one interval holds yl and
 * the walk finds it from any *hint (the seg's last, kept by the worker:
 * the lines of successive bands are a node or two apart); the start is a
 * function of the piece and yl alone. */
static __attribute__((always_inline)) inline double ytab_guess(const ar_piece *p, double yl,
                                                              size_t *hint)
{
    const double *n = p->ytab;
    size_t last = p->nyt - 1, k = *hint;
    if (!(p->ytlo <= yl && yl < p->ythi)) /* ytab_attach's */
        return NAN;
    k = k < last ? k : last - 1;
    while (n[4 * k + 1] > yl)
        k--;
    while (n[4 * k + 5] <= yl)
        k++;
    *hint = k;
    const double *a = n + 4 * k, *b = a + 4;
    if (b[3] == 0.0)
        return yt_turn(a, b, yl);
    double g = yt_herm(a, b, yl);
    if (a[0] < b[0] ? (g > a[0] && g < b[0]) : (g < a[0] && g > b[0]))
        return g;
    return a[0] + (b[0] - a[0]) * ((yl - a[1]) / (b[1] - a[1]));
}

/* A cubic's root of c + tau (k1 + tau (k2 + tau k3)) in [a, b], where it
 * increases from a non-positive value to a non-negative one: Newton's
 * method kept in the bracket, bisection where a step would leave it, to
 * full precision. */
static inline double area_cubic_root(double c, double k1, double k2, double k3, double a, double b)
{
    double fa = c + a * (k1 + a * (k2 + a * k3)), fb = c + b * (k1 + b * (k2 + b * k3));
    if (!(fa < 0.0))
        return a;
    if (!(fb > 0.0))
        return b;
    double t = a - fa * (b - a) / (fb - fa);
    for (int it = 0; it < 100; it++) {
        if (!(t > a && t < b))
            t = 0.5 * (a + b);
        double f = c + t * (k1 + t * (k2 + t * k3));
        if (f == 0.0)
            return t;
        if (f < 0.0)
            a = t;
        else
            b = t;
        double m = 0.5 * (a + b);
        if (!(m > a && m < b))
            break;
        double df = k1 + t * (2.0 * k2 + 3.0 * t * k3);
        t = df > 0.0 ? t - f / df : m;
    }
    return t > a && t < b ? t : 0.5 * (a + b);
}
/* The same from a guess near the root: Newton's method alone while its
 * steps stay in [a, b] and shrink, until the error left after a step is
 * below 2^-54 of scale (one or two steps from a neighbouring band's
 * root; scale 0: of the root, or of 2^-10 near zero); the bracketed
 * search otherwise.  After the step s from t, f(t - s) = f''(u) s^2 / 2
 * for some u between (Taylor); f'' is linear, so over the step |f''| / 2
 * is at most h = |k2 + 3 k3 t| + 3 |k3 s|; f' is at least f'(t) - 4 h |s|
 * within two steps of t, where the root is if the test passes, so the
 * root lies within h s^2 over that of next.
 * With f'' read at t alone, a guess at an inflection (f''(t) = 0) passed
 * the test after one step of any size: from t = 0.5 on t^3 - 1.5 t^2 + t
 * - 0.2475, a step of 0.01 left the root 4e-6 away (tests/test_cubic.c,
 * test_cubic_near). */
static inline double area_cubic_newton(double c, double k1, double k2, double k3, double a,
                                       double b, double guess, double scale)
{
    double t = guess > a ? (guess < b ? guess : b) : a, last = INFINITY;
    for (int it = 0; it < 8; it++) {
        double f = c + t * (k1 + t * (k2 + t * k3));
        double df = k1 + t * (2.0 * k2 + 3.0 * t * k3);
        if (f == 0.0)
            return t;
        double step = f / df;
        if (!(df > 0.0) || !(fabs(step) < 0.5 * last))
            break;
        double next = t - step;
        if (!(next >= a && next <= b))
            break;
        double as = fabs(step), h = fabs(k2 + 3.0 * t * k3) + 3.0 * fabs(k3) * as;
        double tol = 0x1p-54 * (scale > 0.0 ? scale : fmax(fabs(next), 0x1p-10));
        if (h * as * as <= tol * (df - 4.0 * h * as))
            return next;
        t = next;
        last = fabs(step);
    }
    return area_cubic_root(c, k1, k2, k3, a, b);
}

/* area_cubic_newton to 2^-54 of the bracket [a, b] */
static inline double area_cubic_near(double c, double k1, double k2, double k3, double a,
                                     double b, double guess)
{
    return area_cubic_newton(c, k1, k2, k3, a, b, guess, b - a);
}

/* A conic's q where v(q) - v(0) = -c (c = V - v, or Va - m for a band
 * line): v = Va + 2 q (vy + ay q)/(1 + q^2) gives the quadratic
 * (c + 2 ay) q^2 + 2 vy q + c = 0, whose root on the rising branch (through
 * q = 0 at c = 0; vy = er sin ang >= 0) is taken in the form without
 * cancellation, as a parabola's. */
static inline double conic_q_of_v(const ar_seg *s, double c)
{
    double disc = s->vy * s->vy - c * (c + 2.0 * s->ay);
    double den = s->vy + sqrt(disc > 0.0 ? disc : 0.0);
    return den > 0.0 ? -c / den : 0.0;
}

/* An offset piece's tau where coordinate coord (0 x, 1 y) is target,
 * between taus a and b, fa: its value at a less target (its sign). */
static inline double offset_tau(const ar_seg *s, int coord, double a, double b, double fa,
                                double target)
{
    double sg = s->p->sg, g = coord ? ytab_guess(s->p, target, &((ar_seg *)s)->ythint) : NAN;
    return sg * aa__offset_root_fixd(&s->p->src->oc, &s->p->ofix, coord, sg * a, sg * b, fa,
                                     target, g, NULL);
}

/* offset_tau where x is target (a cell's side), from guess g (strictly
 * inside [a, b], else the solver's own start), keeping v there as the
 * root gives it (offset_keep). */
static inline double offset_tau_at(const ar_seg *s, double a, double b, double fa, double target,
                                   double g)
{
    double sg = s->p->sg;
    long double y;
    double t = sg * aa__offset_root_fixd(&s->p->src->oc, &s->p->ofix, 0, sg * a, sg * b, fa,
                                         target, sg * g, &y);
    offset_keep(s, t, (double)(y + s->V));
    return t;
}

/* offset_tau_at from the chord's guess.  ua and ub are u at a and b (the
 * part is x-monotone between them): the solver starts where their chord
 * meets the side, b's sign taken from ub and b not evaluated (without the
 * guess it evaluated b for the quadratic through a, b and b's slope, a
 * start about as near the root: on tests/bench_bezstroke.c's scene 2.6
 * double evaluations a side became 2.0). */
static inline double offset_chord(const ar_seg *s, double a, double b, double target, double ua,
                                  double ub)
{
    double k = target - s->c0;
    return ub != ua ? a + (b - a) * ((k - ua) / (ub - ua)) : NAN;
}

/* offset_tau_at from offset_chord's start */
static inline double offset_tau_u(const ar_seg *s, double a, double b, double fa, double target,
                                  double ua, double ub)
{
    return offset_tau_at(s, a, b, fa, target, offset_chord(s, a, b, target, ua, ub));
}

/* offset_tau_u's root as a request of aa__offset_roots (the same
 * arguments: the same root bit for bit), y there into *y: the root is
 * sg times the request's t, offset_keep'd as offset_tau_at keeps it */
static inline aa__offset_rootq offset_side_q(const ar_seg *s, double a, double b, double fa,
                                             double target, double ua, double ub,
                                             long double *y)
{
    double sg = s->p->sg, g = offset_chord(s, a, b, target, ua, ub);
    return (aa__offset_rootq){&s->p->src->oc, &s->p->ofix, 0, sg * a, sg * b, fa, target, sg * g,
                              NULL, NULL, y, 0.0};
}

/* A start for an offset piece's root where u = k (u1 < k < u2 or u1 > k >
 * u2) on an x-monotone part from (t1, u1) to (t2, u2), given the point
 * (t0, u0) before t1 on it (t0 NAN: none): the quadratic in u through the
 * three (Newton's divided differences), if strictly between t1 and t2;
 * else the chord's from t1 to t2, offset_tau_u's (area.c, walk_offset: a
 * cell's sides after the first, t0 the side before or the part's start;
 * tests/test_area_offset.c, test_side_guess). */
static inline double side_guess(double t0, double u0, double t1, double u1, double t2, double u2,
                                double k)
{
    if (t0 == t0) {
        double d12 = (t2 - t1) / (u2 - u1), d01 = (t1 - t0) / (u1 - u0);
        double g = t1 + (k - u1) * (d12 + (k - u2) * ((d12 - d01) / (u2 - u0)));
        if (t1 < t2 ? (g > t1 && g < t2) : (g < t1 && g > t2))
            return g;
    }
    return t1 + (t2 - t1) * ((k - u1) / (u2 - u1));
}

/* tau where v(tau) = v: the root on the rising branch (y' >= 0 on a piece),
 * in the cancellation-free form. */
static inline double solve_v(const ar_seg *s, double v)
{
    double c = s->V - v;
    if (s->p->offset) /* y = v - V, between the band's ends */
        return offset_tau(s, 1, s->ta, s->tb, s->va - v, v - s->V);
    if (s->p->conic)
        return conic_q_of_v(s, c);
    if (s->p->cubic) /* from the linear guess */
        return area_cubic_near(c, s->vy, s->ay, s->cy3, s->t0, s->tend, -c * s->ivy);
    if (s->ay == 0.0)
        return -c / s->vy;
    double disc = s->vy * s->vy - 4.0 * s->ay * c;
    double den = s->vy + sqrt(disc > 0.0 ? disc : 0.0);
    return den > 0.0 ? -2.0 * c / den : 0.0;
}

/* The same inside the band, exact at the ends of the seg. */
static inline double tau_of_v(const ar_seg *s, double v)
{
    if (v <= s->va)
        return s->ta;
    if (v >= s->vb)
        return s->tb;
    return solve_v(s, v);
}

/* An offset seg's tau where v(tau) = v strictly inside the band's
 * heights (the root from the table's start), and u there (*u) from the
 * root's last evaluation moved by its slope over the last step
 * (aa__offset_root's other coordinate, within about 1e-22 of x'' of the
 * root's own x), not a second evaluation. */
static __attribute__((always_inline)) inline double offset_v_root(const ar_seg *s, double v,
                                                                  double *u)
{
    double sg = s->p->sg, g = ytab_guess(s->p, v - s->V, &((ar_seg *)s)->ythint);
    long double x;
    double t = sg * aa__offset_root_fixd(&s->p->src->oc, &s->p->ofix, 1, sg * s->ta, sg * s->tb,
                                         s->va - v, v - s->V, g, &x);
    *u = (double)(x - s->c0);
    return t;
}

/* u where v(tau) = v in the band, for an order's key: an offset piece's
 * offset_v_root's. */
static inline double key_u(const ar_seg *s, double v)
{
    if (!(s->p->curved && s->p->offset) || v <= s->va || v >= s->vb)
        return u_at(s, tau_of_v(s, v));
    double u;
    offset_v_root(s, v, &u);
    return u;
}

/* Rounding may step just outside [0, 1]. */
static inline double clamp01(double v)
{
    v = v > 0.0 ? v : 0.0; /* maxsd, minsd: no branch */
    return v < 1.0 ? v : 1.0;
}

/* Store one pixel, clamped, non-temporal when the row streams. */
static inline void store_px(const ar_row *r, double *px, const double *v)
{
    /* scalars straight to the image: going through a small array cost a
     * store-forwarding stall per pixel (measured: a fifth of the render) */
    double c0 = clamp01(v[0]), c1 = clamp01(v[1]), c2 = clamp01(v[2]);
#if AR_STREAM
    if (r->stream) {
        _mm_stream_si64((long long *)px, _mm_cvtsi128_si64(_mm_castpd_si128(_mm_set_sd(c0))));
        _mm_stream_si64((long long *)px + 1,
                        _mm_cvtsi128_si64(_mm_castpd_si128(_mm_set_sd(c1))));
        _mm_stream_si64((long long *)px + 2,
                        _mm_cvtsi128_si64(_mm_castpd_si128(_mm_set_sd(c2))));
        return;
    }
#else
    (void)r;
#endif
    px[0] = c0, px[1] = c1, px[2] = c2;
}

/* Catmull's integrater on the cluster of cells [lo, hi] of row r: 0 if it
 * declines (too many edges, or arcs) and the bands must do it. */
int area_cluster_catmull(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                           const int *w);
/* The same in a scene that composites (area_composite.c): every edge
 * splits, each region's colour the scene's composite. */
int area_cluster_catmull_all(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                             const int *w);

/* k[0..n) sorted by (key, id), ascending (tmp: room for n): the row's
 * pieces new in its band (area.c, merge_keys) */
void area_sort_new_keys(ar_key *k, size_t n, ar_key *tmp);
/* Tests only: 1 (as built), the rows of scenes with curved pieces ask
 * single()'s side roots on offset pieces in batches before their clusters
 * close (area.c, side_ask); 0, single() asks each alone.  The same roots,
 * bit for bit (tests/test_area_offset.c, test_side_batch). */
extern int aa__area_side_batch;
/* Tests only: 1 (as built), offset pieces take the row's point where their
 * map lets them (ar_piece's rowpt); 0, none does (tests/test_area_offset.c,
 * test_rowpt_gate). */
extern int aa__area_rowpt;
/* Tests only: NULL (as built), else called with each solve of seg_t_kept
 * (area.c: an offset seg's parameter r at height y inside its band, where
 * a pair's common heights begin or end), the piece and the seg's
 * parameters at its band's ends ta and tb (tests/test_area_offset.c,
 * test_kept_solves).  It is called from the render's worker threads: the
 * callback must be thread-safe, or the render run on one thread. */
extern void (*aa__area_kept_solve)(const aa_piece *p, double y, double r, double ta, double tb);
/* Tests only: CM_MAX_EVENTS_GROWN (as built), the room band_events' heights
 * and crossings grow to in a crowded band before it takes more passes;
 * CM_MAX_EVENTS, they do not grow (a pass per CM_MAX_EVENTS / 2 of them
 * beyond the first, every pair asked again each pass: tests/test_area.c,
 * test_crowded_passes). */
extern size_t aa__area_events_grown;

/* Offset pieces (area_offset.c): the rules; a piece's panels from t0 to t1
 * (*out to be freed), or appended to an array (*n of *cap used, grown
 * geometrically; on a failure *n is as it was); 1/2 the integral of (P - P(ta)) x P' from t = ta to
 * tb, the segment between the part and its chord, in px^2 (with its
 * proven bound, AR_QUAD_TOL per panel it meets); _at: the same about the
 * point (x0 + u, y0 + v) of the image (P(ta) as the row holds it, or the
 * outline's vertex at the piece's end ta), the sums not rounded. */
int area_quad_init(ar_quad *q);
int area_offset_panels(const aa_offset_curve *oc, double t0, double t1, ar_panel **out,
                       size_t *n);
int area_offset_panels_append(const aa_offset_curve *oc, double t0, double t1, ar_panel **arr,
                              size_t *n, size_t *cap);
double area_offset_segment(const ar_piece *pc, double ta, double tb);
double area_offset_segment_at(const ar_piece *pc, double ta, double tb, double x0, double u,
                              double y0, double v);
/* The rule (index into ar_quad) the share [al, be] of panel p takes: the
 * fewest points whose bound is within AR_QUAD_TOL. */
int area_offset_rule(const ar_panel *p, double al, double be);
/* 1 where the test of area_offset_rule's 8 points without a division or a
 * square root (area_offset.c, rule8_sure) tells that share [al, be] of
 * panel p takes 8 points, 0 where it cannot tell (the exact test then
 * decides). */
int area_offset_rule_sure(const ar_panel *p, double al, double be);
/* A bound on the speed |P'| of an offset curve or evolute (unmapped, its
 * own units) on each disc |t - m| <= R[k], k < n, R ascending: INFINITY
 * from the first disc that may hold a zero of a denominator on (the form
 * aa__offset_eval takes at m: the factored one next to a stop). */
void area_offset_speed(const aa_offset_curve *oc, double m, int n, const double *R, double *V);

#endif /* AA_AREA_INTERNAL_H */
