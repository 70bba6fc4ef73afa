/*
 * visible.h: the visible parts of a scene's edges near one pixel, with the
 * change of colour across each (internal to algorithms/; shared by
 * `conetable` and `crowtiler`).
 *
 * A scene of opaque layers is, inside a window, a picture of constant
 * colours separated by the visible parts of its edges.  An edge of a back
 * layer is hidden (no change of colour across it) where a front layer
 * covers it; an edge changes its colours where another edge meets it or
 * ends on it.  This module cuts the window's rows into bands at every
 * height where that can happen, so that inside a band each piece of edge
 * separates the same two colours all along:
 *
 *  - the ends of the local pieces inside the rows, the heights of the flat
 *    (horizontal) pieces, and the heights where a piece crosses the
 *    window's left or right side (so that a piece is wholly inside or
 *    wholly outside the window in a band);
 *  - the heights where two pieces meet (aa_piece_meet: crossings and
 *    touches).  Only neighbours in the order along x need testing: in an
 *    interval where no two neighbours meet, no two pieces meet (if p and q
 *    met at y* with no meeting nearer, every piece between them would be
 *    squeezed to the same point at y*, so some pair of neighbours would
 *    meet there).  A band is therefore narrowed to the nearest meeting of
 *    neighbours until none is left inside it.  A sink may ask
 *    (inside_meets) that only the pairs with a piece inside the window be
 *    tested: the pieces inside form one run of the order (x between two
 *    inside pieces' is inside), so the argument holds within it; a piece
 *    outside in a band is outside all through it (the band is cut where it
 *    crosses a side), so it meets no inside piece there, and two outside
 *    pieces that cross change only the order of windings added left of
 *    the window or after its last piece, never a part's jump.  With
 *    windows narrower than the pieces (analytic's tiles 8 px wide), most
 *    meetings of a row are of pieces outside the window.
 *
 * Inside a band the pieces are ordered along x at the band's middle (ties,
 * such as the shared edge of two abutting polygons, by their index in the
 * scene, the same order in every band), and swept left to right from the
 * winding numbers left of the window (aa_strip_winding_left): the winding
 * just left of each piece gives the colours on its two sides.  A piece's
 * change of colour is constant along it inside the band, because the
 * winding just left of it can only change where another piece meets it
 * (pieces outside the window never reach it: the window's non-local pieces
 * lie wholly left or right of it).
 *
 * What is reported, through the sink's callbacks:
 *
 *  - band(ya, yb, wind): each band, with the winding numbers just inside
 *    the window's left side (the colour there is constant in the band);
 *  - run(p, ya, yb, jump, inside): each maximal run of bands along a piece
 *    with one change of values: `jump` is the values just right of the
 *    piece minus the values just left of it; the values are the colour
 *    (3 of them) unless the sink maps winding numbers to values of its own
 *    (`values`, `dims` of them: the coverages of layers, say); `inside` says
 *    the run lies in the window (outside runs carry jump 0).  Runs with no
 *    jump or outside are reported only if the sink asks (zero_runs).
 *  - flat(p, xa, xb, y, jump): (if the sink has it) each part of a flat
 *    piece inside the window with one change of values, `jump` the values
 *    just above minus just below.  A flat part changes its values where a
 *    piece crosses its height or another flat piece at its height ends;
 *    coincident flat pieces are taken in the order of their index, so their
 *    jumps add up to the whole change.
 *
 * With these, the colour at any point (x, y) of the window is the band's
 * colour at the left side plus the jumps of the runs crossing line y left of
 * x: a picture made of "left areas minus right areas" (Crow 1976, fig.
 * 3.13) with the colours of the visible surfaces on each side of each edge,
 * or, summed over closed boundaries, the visible part of every polygon
 * (Feibush, Levoy and Cook 1980, sec. 2.3: "the visible portions of all the
 * polygons").
 *
 * Cost: per pixel, sorting the pieces of each band along x and one
 * meeting test per neighbouring pair; the bands are few (the pieces' ends
 * and meetings in the window).  Nothing is allocated: the workspace is
 * sized for the scene's piece count (aa__vis_size) and bound to a block
 * the caller owns (the sampler's per-thread scratch).
 */
#ifndef AA_VISIBLE_H
#define AA_VISIBLE_H

#include "aabench.h"

#include <math.h>
#include <stddef.h>

typedef struct aa__vis_sink {
    void (*band)(void *ctx, double ya, double yb, const int *wind);
    void (*run)(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                int inside);
    void (*flat)(void *ctx, const aa_piece *p, double xa, double xb, double y,
                 const double *jump);
    /* The values of a winding (NULL: the colour, aa_scene_colour_of). */
    void (*values)(void *ctx, const int *wind, double *out);
    void *ctx;
    int dims;      /* values per winding: 3 for the colour */
    int zero_runs; /* also report runs with no jump, and runs outside the window */
    /* a part of a piece outside the window joins the run beside it, taking
     * its jump (for weights that vanish outside the window, where the
     * piece's terms are zero whatever the jump: fewer cuts) */
    int merge_outside;
    /* meetings of two pieces both outside the window in a band (both left
     * of it, both right, or one each side) are not sought: they change no
     * part's jump, nor the winding at the window's left side, only where
     * bands are cut (for sinks whose results do not depend on that: runs,
     * and bands weighed only after consecutive ones of one colour merge) */
    int inside_meets;
} aa__vis_sink;

typedef struct aa__vis_piece aa__vis_piece;
typedef struct aa__vis_order aa__vis_order;

/* The workspace of one thread (bound to the caller's block). */
typedef struct aa__vis {
    const aa_scene *scene;
    const aa_piece *base; /* the scene's pieces: a piece's index is p - base */
    int nl, dims;
    aa__vis_piece *lp;    /* local pieces that cross lines in the rows */
    aa__vis_order *ord;   /* a band's pieces along x */
    const aa_piece **flats;
    double *ev;           /* heights that cut the rows into bands */
    double *fx;           /* where a flat piece's values change */
    double *jumps;        /* dims per local piece: its open run's jump */
    double *va, *vb, *vj; /* dims each */
    int *wind, *wind2;
} aa__vis;

/* Bytes of workspace for a scene (its piece count and layers) and values of
 * `dims` numbers (dims per piece are kept: a run's jump). */
size_t aa__vis_size(const aa_scene *s, int dims);
/* Bind a workspace to `block` (aa__vis_size bytes, aligned for doubles). */
void aa__vis_bind(aa__vis *v, const aa_scene *s, int dims, void *block);

/* The visible parts of the edges in window [xl, xr] x rows [ya, yb] of the
 * strip's current window (whose band holds these rows, and whose window
 * holds [xl, xr]), reported to the sink. */
void aa__vis_window(aa__vis *v, const aa_strip *st, double xl, double xr, double ya, double yb,
                    const aa__vis_sink *sink);

/* The point of piece p (not flat) at its parameter t in [0, 1] (the t of
 * aa_piece_t_at), and dy/dt there: the power basis of aabench.h, or for a
 * conic its ellipse at angle s = s0 + t (s1 - s0). */
static inline void aa__piece_point(const aa_piece *p, double t, double *x, double *y,
                                   double *dydt)
{
    if (p->kind == AA_PIECE_OFFSET) {
        double w = p->ot1 - p->ot0, dx, dy;
        aa_offset_point(&p->oc, p->ot0 + t * w, x, y, &dx, &dy);
        *dydt = dy * w;
        return;
    }
    if (p->kind == AA_PIECE_CONIC) {
        double w = p->s1 - p->s0, s = p->s0 + t * w, c = cos(s), sn = sin(s);
        *x = p->ex + (p->ea * c + p->eb * sn);
        *y = p->ey - p->er * c;
        *dydt = p->er * sn * w;
        return;
    }
    *x = p->x0 + t * (p->bx + t * (p->ax + t * p->dx));
    *y = p->y0 + t * (p->by + t * (p->ay + t * p->dy));
    *dydt = p->by + t * (2.0 * p->ay + 3.0 * t * p->dy);
}

/* A bound on |P''(t)|/2 over the piece in its parameter t (for flattening
 * within a tolerance): |a| + 3 |d| for the power basis (d = 0 but for
 * cubics); for a conic (s1 - s0)^2 (|(ea, eb)| + er)/2, since P''(s) =
 * -(ea cos s + eb sin s, -er cos s). */
static inline double aa__piece_bend(const aa_piece *p)
{
    if (p->kind == AA_PIECE_OFFSET) {
        /* no closed form: twice the largest second difference of 16
         * steps, |P''|/2 ~ |P(t-e) - 2 P(t) + P(t+e)|/(2 e^2) (an estimate
         * for a flattening tolerance, not a bound) */
        double best = 0, px[17], py[17], w = p->ot1 - p->ot0;
        for (int k = 0; k <= 16; k++)
            aa_offset_point(&p->oc, p->ot0 + w * k / 16.0, &px[k], &py[k], NULL, NULL);
        for (int k = 1; k < 16; k++)
            best = fmax(best, hypot(px[k - 1] - 2 * px[k] + px[k + 1],
                                    py[k - 1] - 2 * py[k] + py[k + 1]));
        return 256.0 * best; /* |P''|/2 ~ 128 best, doubled */
    }
    if (p->kind == AA_PIECE_CONIC) {
        double w = p->s1 - p->s0;
        return 0.5 * w * w * (hypot(p->ea, p->eb) + p->er);
    }
    return hypot(fabs(p->ax) + 3.0 * fabs(p->dx), fabs(p->ay) + 3.0 * fabs(p->dy));
}

/* Sort n heights ascending: a few per pixel, usually (insertion sort;
 * qsort past a handful). */
void aa__vis_sort(double *v, size_t n);

#endif
