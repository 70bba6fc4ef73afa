/*
 * stroke.c: the stroke outline of a path (path.h, aa_stroke_outline): the
 * SVG 2 stroke shape ("Stroke shape", with stroke-linejoin, -linecap,
 * -miterlimit and dashing) of a path of lines, elliptical arcs and Bezier
 * arcs (those and the arcs that are not circles below), exactly,
 * as closed contours that all turn the same way (positive signed area),
 * each the sum of simple ones (less, at some joins, a triangle where two of
 * them overlap), so that the non-zero rule fills exactly the union of the
 * simple ones.
 *
 * The pieces of the union, h = width / 2:
 *  - a line segment: its rectangle, the segment swept by the normal of
 *    length 2h centred on it;
 *  - a circular arc of radius r from t0 to t1: the region swept by the same
 *    normal, the annular sector of radii r - h .. r + h; when h > r the
 *    normal passes through the centre, and the region is the sector of
 *    radius r + h plus the opposite sector (angles t + pi) of radius h - r.
 *    Arcs are cut into parts of at most a quarter turn, so that every
 *    piece of the union is simple;
 *  - a join at a vertex inside a subpath, between the tangent directions
 *    d_in and d_out there, on the outer side of the turn, whose outer
 *    offset points are A = P + h nA and B = P + h nB: bevel the triangle
 *    P A B; miter, when the miter length ratio 1/sin(theta/2) (theta the
 *    angle between the segments; 1/sin(theta/2) = 2/|nA + nB|) is at most
 *    the limit, the quadrilateral P A M B with the tip
 *    M = P + 2h (nA + nB)/|nA + nB|^2 where the outer edges' tangent lines
 *    meet (at an arc too: its tangent line, not the `arcs` join), else the
 *    bevel; round the circular sector of radius h about P from A to B;
 *    miter-clip the miter, or past the limit the miter cut by the line
 *    perpendicular to the outward bisector at limit h from P (SVG 2's
 *    stroke-miterlimit: half the limit times the width), a pentagon
 *    (clipped_miter); arcs the outer edges extended by their osculating
 *    circles to where they meet, cut by the limit along an arc
 *    (arcs_join, which says how, and SVG 2's fallbacks: miter-clip where
 *    both curvatures are 0, round where either is at least 1/h, the
 *    circles' radii changed alike until they touch where they do not
 *    meet; a Bezier arc's end whose control point is on it has curvature
 *    0 there, SVG 2's "a line should be used").  At a reversal miter-clip
 *    and arcs are the rectangle of width 2h and length limit h ahead of
 *    P (SVG 2's join for parallel tangents).
 *    With round joins and round caps every point within h of the path is
 *    covered (its nearest point on the path is inside a segment, on whose
 *    normal it lies, or a vertex or an end, in whose outward cone it
 *    lies), so the stroke is then exactly those points, as tests check.
 *    A straight vertex (d_in = d_out) has no join; a reversal
 *    (d_out = -d_in) has an empty bevel and miter (the ratio is infinite)
 *    and a half disk ahead of the vertex as its round join;
 *  - caps at the ends of an open subpath or a dash, in the outward
 *    direction d: butt nothing, square the rectangle of length h beyond the
 *    end, round the half disk beyond it;
 *  - a closed subpath joins its last segment to its first instead of caps.
 * A run's bodies whose ends are their normals (lines, annular sectors,
 * Bezier and elliptical arcs' parts without folds), the joins between them
 * and the caps at their ends are written as one contour, their shared
 * lines cancelled (the runs section below says how); the other bodies and
 * a closed subpath's last join are contours of their own.
 *
 * Choices where SVG leaves room, or where this differs from a renderer:
 *  - arcs falls back to round where "either curvature is greater than
 *    2/(stroke width)": SVG 2 gives the curvature no sign there, so its
 *    magnitude is taken, and at |k| = 1/h (an edge circle of radius 0)
 *    round too; Chromium, librsvg and resvg draw miter-clip and arcs as
 *    miter (Chromium's parser does not know them, librsvg strokes with
 *    Cairo; patterns/README.md has the figures);
 *  - zero-length segments are dropped before joins: a join is between the
 *    neighbouring segments of non-zero length (SVG 2 takes a zero-length
 *    segment's direction from its neighbours, which comes to the same); a
 *    line whose ends differ by rounding only (1e-14 of their magnitude)
 *    counts as of zero length;
 *  - a subpath with segments but no length (M p L p, M p Z) is drawn as its
 *    caps at p in the direction of the x axis: a disk for round, an
 *    axis-aligned square of side 2h for square, nothing for butt (nor when
 *    a dash pattern starts in a gap); a subpath that is only a move_to
 *    draws nothing (SVG 1.1, "a subpath consisting
 *    of a single moveto shall not be stroked");
 *  - dashes are laid along each subpath from its start by arc length (exact
 *    for lines and circular arcs, r |t1 - t0|), an odd list repeated, the
 *    offset taken modulo the pattern's length (a negative one too); each
 *    dash is an open run with caps at both ends and joins at the vertices
 *    strictly inside it; on a closed subpath the start is such a vertex: a
 *    dash through it (from 0 and to the length) is one dash, joined there,
 *    and a dash over the whole subpath leaves it closed; a dash of zero
 *    length is its caps in the path's direction there.
 *
 * Bezier arcs (quadratics raised to cubics, exactly, in the power basis)
 * and elliptical arcs that are not circles (the ellipse B(t) = c + u cos t
 * + v sin t, its parameter made increasing; curvature (u x v)/|B'|^3, its
 * extremes where B' . B'' = 0, a quarter turn apart): the region swept
 * by the normal of length 2h is the image of [t0, t1] x [-h, h] under F(t, s) = B(t) + s N(t), whose Jacobian is
 * |B'| (1 - s k(t)) (N the unit normal (-B'y, B'x)/|B'|, k the signed
 * curvature B' x B'' / |B'|^3).  By the degree of a map, the winding
 * number about p of the image of the boundary of a region where the
 * Jacobian has one sign, taken the positive way in (t, s) where it is
 * positive and the other way where it is negative, is the number of
 * preimages of p in the region: at least 0.  So the arc is cut where
 * |k| h = 1 and at the extremes of k (a polynomial of degree 6 in t, its
 * sign changes isolated between those of its derivatives), and each part
 * is one region between the offsets at -h and h where |k| h <= 1, or two,
 * split at the evolute s = 1/k, where the offset folds: the non-zero union
 * of these contours is exactly the swept region, however the offsets fold
 * or loop, and none of them need be simple.  Their boundaries are the
 * offsets, the evolute (exact pieces: aa_offset_curve, AA_PATH_OFFSET, on
 * the base curve AA_OFFSET_CUBIC or AA_OFFSET_ELLIPSE) and normal lines;
 * joins and caps are as for lines, with the arcs' end tangents.  Dashes
 * along Bezier and elliptical arcs by arc length: 16-point
 * Gauss-Legendre on halves until two levels agree to 1e-15 of the whole
 * (at most 2048 splits), and Newton's
 * method (kept in a bracket) for the parameter at a length.
 * Where a Bezier arc's speed |B'| vanishes (bez_piece) the normal is the
 * limit of those beside it: at an end whose control point is on it (SVG 2
 * takes the direction from the next distinct control point: the same), and
 * at a cusp inside, where the arc is split into arcs of their own with no
 * join between them (SVG 2 joins segments only at their boundaries, so
 * nothing is drawn ahead of the cusp's tip; Chromium, resvg and librsvg
 * draw a disk there).  A Bezier arc whose every control point is one of
 * its ends (`C a a b b`) is stroked as the line it is (bez_on_ends).
 * Refused (AA_EINVAL, naming it): an arcs join whose extension would
 * run backwards along a line or more than a half turn along a circle, or
 * whose cut by the miter limit does not cross each extension once (the
 * join is then not one simple region of lines and arcs); a Bezier arc whose
 * speed comes within 1e-9 of its size without being 0 to rounding (1e-12),
 * nearly a cusp; a subpath of more than DASH_MAX (10000) dashes.
 */
#include "path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void aa_stroke_style_default(aa_stroke_style *st)
{
    memset(st, 0, sizeof *st);
    st->width = 1;
    st->join = AA_JOIN_MITER;
    st->cap = AA_CAP_BUTT;
    st->miterlimit = 4;
    st->dash = NULL;
    st->ndash = 0;
    st->dashoffset = 0;
}

/* ---- contours: built, oriented, appended ---- */

/* One element of a contour: a line or an arc (c + u cos t + v sin t, t from
 * t0 to t1) to (x, y). */
typedef struct elem {
    int arc;
    double x, y;
    double cx, cy, ux, uy, vx, vy, t0, t1;
} elem;

#define CONTOUR_MAX 8

typedef struct contour {
    double sx, sy;
    int n;
    elem e[CONTOUR_MAX];
} contour;

static void c_begin(contour *c, double x, double y)
{
    c->sx = x;
    c->sy = y;
    c->n = 0;
}

static void c_line(contour *c, double x, double y)
{
    elem *e = &c->e[c->n++];
    memset(e, 0, sizeof *e);
    e->x = x;
    e->y = y;
}

static void arc_point(double cx, double cy, double ux, double uy, double vx, double vy, double t,
                      double *x, double *y)
{
    double ct = cos(t), st = sin(t);
    *x = cx + ux * ct + vx * st;
    *y = cy + uy * ct + vy * st;
}

/* An arc element; it ends at its point for t1. */
static void c_arc(contour *c, double cx, double cy, double ux, double uy, double vx, double vy,
                  double t0, double t1)
{
    elem *e = &c->e[c->n++];
    e->arc = 1;
    e->cx = cx, e->cy = cy, e->ux = ux, e->uy = uy, e->vx = vx, e->vy = vy;
    e->t0 = t0, e->t1 = t1;
    arc_point(cx, cy, ux, uy, vx, vy, t1, &e->x, &e->y);
}

/*
 * The signed area (1/2) integral of (x dy - y dx) around the contour, about
 * its start (to keep rounding relative to its size).  A line from a to b
 * gives (a x b)/2.  An arc P(t) = c + u cos t + v sin t gives
 *     (1/2) integral of P x P' dt,  P' = -u sin t + v cos t,
 *     P x P' = c x P' + (u x v)(cos^2 t + sin^2 t),
 * so (1/2) [c x (P(t1) - P(t0)) + (u x v)(t1 - t0)].
 */
static double c_area(const contour *c)
{
    double a = 0, px = 0, py = 0; /* the pen, relative to the start */
    for (int k = 0; k < c->n; k++) {
        const elem *e = &c->e[k];
        double x = e->x - c->sx, y = e->y - c->sy;
        if (e->arc) {
            double cx = e->cx - c->sx, cy = e->cy - c->sy;
            double ax, ay, bx, by;
            arc_point(cx, cy, e->ux, e->uy, e->vx, e->vy, e->t0, &ax, &ay);
            arc_point(cx, cy, e->ux, e->uy, e->vx, e->vy, e->t1, &bx, &by);
            double uv = e->ux * e->vy - e->uy * e->vx;
            a += cx * (by - ay) - cy * (bx - ax) + uv * (e->t1 - e->t0);
            /* the gap from the pen to the arc's own start (rounding) */
            a += px * ay - py * ax;
            px = bx, py = by;
            a += px * y - py * x;
        } else {
            a += px * y - py * x;
        }
        px = x, py = y;
    }
    /* the closing line back to the start (0, 0) adds nothing */
    return 0.5 * a;
}

static int emit_elem(aa_path *out, const elem *e, double x, double y, int reversed)
{
    if (!e->arc)
        return aa_path_line_to(out, x, y);
    return aa_path_arc_to(out, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy,
                          reversed ? e->t1 : e->t0, reversed ? e->t0 : e->t1, x, y);
}

/* Append the contour turning the positive way: reversed if its signed area
 * is negative; nothing if it is empty (zero area). */
static int c_emit(aa_path *out, const contour *c)
{
    double a = c_area(c);
    if (!isfinite(a))
        return aa_fail(AA_EINVAL, "stroke: the outline is out of range (not finite)");
    if (a == 0 || c->n == 0)
        return AA_OK;
    int st = aa_path_move_to(out, c->sx, c->sy);
    if (a > 0) {
        for (int k = 0; k < c->n && !st; k++)
            st = emit_elem(out, &c->e[k], c->e[k].x, c->e[k].y, 0);
    } else {
        /* backwards: the closing line first, then each element from its
         * end to its start (the end of the one before, or the start) */
        const elem *last = &c->e[c->n - 1];
        if (last->x != c->sx || last->y != c->sy)
            st = aa_path_line_to(out, last->x, last->y);
        for (int k = c->n - 1; k >= 0 && !st; k--) {
            double x = k > 0 ? c->e[k - 1].x : c->sx, y = k > 0 ? c->e[k - 1].y : c->sy;
            st = emit_elem(out, &c->e[k], x, y, 1);
        }
    }
    return st ? st : aa_path_close(out);
}

/* The polygon of n points xy as a contour. */
static void c_polygon(contour *c, const double *xy, int n)
{
    c_begin(c, xy[0], xy[1]);
    for (int k = 1; k < n; k++)
        c_line(c, xy[2 * k], xy[2 * k + 1]);
}

/* ---- pieces: the segments of non-zero length ---- */

typedef struct piece {
    int arc, bez;                          /* bez: a curve b (base), t from t0 < t1 */
    int nojoin;                            /* after a cusp: no join with the piece before */
    int base;                              /* AA_OFFSET_CUBIC or AA_OFFSET_ELLIPSE */
    double b[8];                           /* its power basis or c, u, v (aa_offset_curve) */
    double x0, y0, x1, y1;                 /* ends */
    double dx, dy;                         /* lines: the unit direction */
    double cx, cy, ux, uy, vx, vy, t0, t1; /* arcs: a circle, |u| = |v| = r */
    double r, len;
} piece;

typedef struct pieces {
    piece *p;
    size_t n, cap;
} pieces;

/* The array *a of n elements of `size` bytes with room for one more:
 * grown to twice its room (16 at first) when full; 0, or AA_EFAIL naming
 * `what` (nothing changed) if the memory cannot be had. */
static int grow(void **a, size_t n, size_t *cap, size_t size, const char *what)
{
    if (n < *cap)
        return AA_OK;
    size_t room = *cap ? 2 * *cap : 16;
    void *q = realloc(*a, room * size);
    if (!q)
        return aa_fail(AA_EFAIL, "out of memory for a stroke's %zu %s", room, what);
    *a = q;
    *cap = room;
    return AA_OK;
}

static int pieces_push(pieces *ps, const piece *p)
{
    void *a = ps->p;
    int st = grow(&a, ps->n, &ps->cap, sizeof *p, "segments");
    ps->p = a;
    if (st)
        return st;
    ps->p[ps->n++] = *p;
    return AA_OK;
}

/* B(t) and B'(t) of a curve piece (bez): a cubic in power basis, or the
 * ellipse c + u cos t + v sin t. */
static void bez_pt(const piece *p, double t, double *x, double *y)
{
    const double *b = p->b;
    if (p->base == AA_OFFSET_ELLIPSE) {
        double ct = cos(t), st = sin(t);
        *x = b[0] + b[2] * ct + b[4] * st;
        *y = b[1] + b[3] * ct + b[5] * st;
        return;
    }
    *x = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
    *y = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
}

static void bez_d1(const piece *p, double t, double *x, double *y)
{
    const double *b = p->b;
    if (p->base == AA_OFFSET_ELLIPSE) {
        double ct = cos(t), st = sin(t);
        *x = -b[2] * st + b[4] * ct;
        *y = -b[3] * st + b[5] * ct;
        return;
    }
    *x = b[1] + t * (2 * b[2] + 3 * t * b[3]);
    *y = b[5] + t * (2 * b[6] + 3 * t * b[7]);
}

/* On the half of [0, 1] next to an end te of a cubic piece where B'
 * vanishes (a control point on it, or a cusp split off):
 * aa__offset_stop's factored form B' = (t - te) Q, in which the direction
 * sg Q/|Q| (sg = 1 for te = 0, -1 for te = 1) and the curvature
 * X/(|t - te| |Q|^3), X = Q x Q', keep their precision near te; at te the
 * direction is that of B''(te) (or B''' where it is 0: SVG 2 takes the
 * direction to the next distinct control point, the same) and the
 * curvature is infinite of the sign of X (0 where X = 0: straight). */
static int bez_stop(const piece *p, double t, double *te, double q[4])
{
    aa_offset_curve oc = {{0}, {1, 0, 0, 1, 0, 0}, 0, 0, p->base};
    memcpy(oc.b, p->b, sizeof oc.b);
    return aa__offset_stop(&oc, t, te, q);
}

/* The unit tangent of a piece at its start or end, in the direction of
 * travel: a line's is the whole segment's (a short part of it may have
 * equal ends after rounding); an arc's never vanishes (u, v not parallel). */
static void piece_tangent(const piece *p, int at_end, double d[2])
{
    if (p->bez) {
        double t = at_end ? p->t1 : p->t0, x, y, te, q[4];
        bez_d1(p, t, &x, &y);
        if (bez_stop(p, t, &te, q)) {
            double sg = te == 0 ? 1 : -1;
            x = sg * (q[0] + q[1] * t), y = sg * (q[2] + q[3] * t);
            if (x == 0 && y == 0)
                x = q[1], y = q[3];
        }
        double l = hypot(x, y);
        d[0] = x / l;
        d[1] = y / l;
        return;
    }
    if (!p->arc) {
        d[0] = p->dx;
        d[1] = p->dy;
        return;
    }
    double t = at_end ? p->t1 : p->t0, sg = p->t1 > p->t0 ? 1.0 : -1.0;
    double x = sg * (-p->ux * sin(t) + p->vx * cos(t));
    double y = sg * (-p->uy * sin(t) + p->vy * cos(t));
    double l = hypot(x, y);
    d[0] = x / l;
    d[1] = y / l;
}

/* The part of a piece from arc length a to b (0 <= a < b <= len), ends
 * exact where they are the piece's. */
static double bez_length(const piece *p, double t0, double t1);
static double bez_t_at(const piece *p, double s);

static piece piece_part(const piece *p, double a, double b)
{
    piece q = *p;
    double fa = a / p->len, fb = b / p->len;
    if (p->bez) {
        if (a > 0) {
            q.t0 = bez_t_at(p, a);
            bez_pt(p, q.t0, &q.x0, &q.y0);
        }
        if (b < p->len) {
            q.t1 = bez_t_at(p, b);
            bez_pt(p, q.t1, &q.x1, &q.y1);
        }
    } else if (!p->arc) {
        if (a > 0)
            q.x0 = p->x0 + fa * (p->x1 - p->x0), q.y0 = p->y0 + fa * (p->y1 - p->y0);
        if (b < p->len)
            q.x1 = p->x0 + fb * (p->x1 - p->x0), q.y1 = p->y0 + fb * (p->y1 - p->y0);
    } else {
        double dt = p->t1 - p->t0;
        if (a > 0) {
            q.t0 = p->t0 + fa * dt;
            arc_point(p->cx, p->cy, p->ux, p->uy, p->vx, p->vy, q.t0, &q.x0, &q.y0);
        }
        if (b < p->len) {
            q.t1 = p->t0 + fb * dt;
            arc_point(p->cx, p->cy, p->ux, p->uy, p->vx, p->vy, q.t1, &q.x1, &q.y1);
        }
    }
    q.len = b - a;
    return q;
}

/* ---- runs: a run's bodies, joins and caps as one contour ----
 *
 * A strip is a part of a piece whose region is bounded by its offsets at -h
 * (right of the travel) and h (left) and by the normals at its ends: a
 * line's rectangle, an annular sector (h < r), a Bezier or elliptical
 * arc's part where |k| h <= 1.  Its contour turning the positive way is
 * the right side forward, the end normal from right to left, the left side
 * backward, the start normal.  A join's contour is P, A, its outer edge to
 * B, then B P; A and B are the strips' ends on the outer side, so the
 * halves of the normals from P to A and from B to P are edges of the join
 * and, the other way, of the strips.  A cap's contour is its edge from the
 * end normal's one end round to the other, closed by that normal.  So a
 * run's strips, the joins between them and its caps are one contour: the
 * right sides forward, at each join its outer edge if the outer side is
 * the right, else the lines to P and on; the last cap's edge or end
 * normal; the left sides backward, at each join its outer edge backward if
 * the outer side is the left, else the lines to P and on; the first cap's
 * edge or start normal.  As a sum of edges it is the sum of the strips',
 * the joins' and the caps' contours, the shared lines cancelled: its
 * winding number about every point is the sum of theirs, and the non-zero
 * rule fills the same union.  At each join the four lines on the normals
 * (two normals, two sides of the join) become two, from the inner ends to
 * P, or one between the inner ends where the triangle they leave out lies
 * in both strips (inner_cut: there the winding number is at least 2 and
 * stays at least 1), and a vertex straight on keeps none.  The ends meet
 * up to rounding only (a strip's ends are the offset's points, a join's
 * and a cap's come from the unit tangents): where they differ, a line
 * joins them, and the sliver between is the one the separate contours
 * had.  Ends farther apart than STRIP_GAP of the size leave the join or
 * cap a contour of its own. */

/* The largest gap, relative to the size (the coordinates and h), between a
 * strip's end and the join's point that should be on it. */
#define STRIP_GAP 1e-12

enum { STRIP_LINE, STRIP_ARC, STRIP_OFFSET };
/* a join's outer side (stroke_join) */
enum { JOIN_RIGHT, JOIN_LEFT, JOIN_STRAIGHT };
/* how a strip follows the one before it in a chain */
enum { LINK_DIRECT, LINK_RIGHT, LINK_LEFT, LINK_PIVOT };

typedef struct strip {
    int kind, link;
    int cut;                           /* the join's inner side one line (inner_cut) */
    double rs[2], re[2], ls[2], le[2]; /* right and left sides' starts and ends */
    double cx, cy, r[4], l[4];         /* arcs: c + r[0..1] cos t + r[2..3] sin t, left l */
    double a, b;                       /* arcs and offsets: the parameter from a to b */
    aa_offset_curve oc[2];             /* offsets: at -h and h */
    contour j;                         /* the join before it (LINK_PIVOT: P, sx sy) */
} strip;

/* A run being stroked: the chain of strips not yet written, and the join
 * before the next piece's first part. */
typedef struct run {
    aa_path *out;
    strip *s;
    size_t n, cap;
    int first, joined, outer; /* the next part is its piece's first; a join before it */
    int from_start;           /* the chain begins with the run's first part */
    contour j;
    int capped[2]; /* run_flush writes the caps at the start and the end */
    contour ends[2];
} run;

static int same_point(const double p[2], double x, double y, double tol)
{
    return fabs(p[0] - x) <= tol && fabs(p[1] - y) <= tol;
}

static int pen_to(aa_path *out, const double p[2])
{
    if (out->penx == p[0] && out->peny == p[1])
        return AA_OK;
    return aa_path_line_to(out, p[0], p[1]);
}

static int strip_right(aa_path *out, const strip *s)
{
    if (s->kind == STRIP_LINE)
        return aa_path_line_to(out, s->re[0], s->re[1]);
    if (s->kind == STRIP_ARC)
        return aa_path_arc_to(out, s->cx, s->cy, s->r[0], s->r[1], s->r[2], s->r[3], s->a, s->b,
                              s->re[0], s->re[1]);
    return aa_path_offset_to(out, &s->oc[0], s->a, s->b, s->re[0], s->re[1]);
}

static int strip_left_back(aa_path *out, const strip *s)
{
    if (s->kind == STRIP_LINE)
        return aa_path_line_to(out, s->ls[0], s->ls[1]);
    if (s->kind == STRIP_ARC)
        return aa_path_arc_to(out, s->cx, s->cy, s->l[0], s->l[1], s->l[2], s->l[3], s->b, s->a,
                              s->ls[0], s->ls[1]);
    return aa_path_offset_to(out, &s->oc[1], s->b, s->a, s->ls[0], s->ls[1]);
}

/* A join's outer edge, from A to B, or backwards from B to A. */
static int join_edge(aa_path *out, const contour *j, int back)
{
    int st = AA_OK;
    if (!back) {
        const double a[2] = {j->e[0].x, j->e[0].y};
        st = pen_to(out, a);
        for (int k = 1; k < j->n && !st; k++)
            st = emit_elem(out, &j->e[k], j->e[k].x, j->e[k].y, 0);
        return st;
    }
    const double b[2] = {j->e[j->n - 1].x, j->e[j->n - 1].y};
    st = pen_to(out, b);
    for (int k = j->n - 1; k >= 1 && !st; k--)
        st = emit_elem(out, &j->e[k], j->e[k - 1].x, j->e[k - 1].y, 1);
    return st;
}

/* A cap's edge (cap_contour: from the end normal's left end ahead round to
 * its right end) backwards: from its last point to its first. */
static int cap_back(aa_path *out, const contour *c)
{
    const double b[2] = {c->e[c->n - 1].x, c->e[c->n - 1].y};
    int st = pen_to(out, b);
    for (int k = c->n - 1; k >= 0 && !st; k--)
        st = emit_elem(out, &c->e[k], k > 0 ? c->e[k - 1].x : c->sx,
                       k > 0 ? c->e[k - 1].y : c->sy, 1);
    return st;
}

/* The chain written as one contour, and emptied. */
static int run_flush(run *R)
{
    if (R->n == 0)
        return AA_OK;
    R->from_start = 0;
    aa_path *out = R->out;
    const strip *s = R->s;
    int st = aa_path_move_to(out, s[0].rs[0], s[0].rs[1]);
    for (size_t k = 0; k < R->n && !st; k++) {
        if (k > 0) {
            if (s[k].link == LINK_RIGHT) {
                st = join_edge(out, &s[k].j, 0);
            } else if (s[k].link != LINK_DIRECT && !s[k].cut) {
                const double pv[2] = {s[k].j.sx, s[k].j.sy};
                st = pen_to(out, pv);
            }
            if (!st)
                st = pen_to(out, s[k].rs);
        }
        if (!st)
            st = strip_right(out, &s[k]);
    }
    if (!st)
        st = R->capped[1] ? cap_back(out, &R->ends[1]) : AA_OK;
    if (!st)
        st = pen_to(out, s[R->n - 1].le);
    for (size_t k = R->n; k-- > 0 && !st;) {
        st = strip_left_back(out, &s[k]);
        if (k > 0 && !st) {
            if (s[k].link == LINK_LEFT) {
                st = join_edge(out, &s[k].j, 1);
            } else if (s[k].link != LINK_DIRECT && !s[k].cut) {
                const double pv[2] = {s[k].j.sx, s[k].j.sy};
                st = pen_to(out, pv);
            }
            if (!st)
                st = pen_to(out, s[k - 1].le);
        }
    }
    if (!st && R->capped[0])
        st = cap_back(out, &R->ends[0]);
    R->n = 0;
    R->capped[0] = R->capped[1] = 0;
    return st ? st : aa_path_close(out);
}

/* The link from strip a to strip b across the pending join, or -1 if the
 * join's points are not on the strips' ends (up to STRIP_GAP). */
static int run_link(const run *R, const strip *a, const strip *b)
{
    const contour *j = &R->j;
    double size = fabs(j->sx) + fabs(j->sy) + fabs(a->re[0] - a->le[0]) +
                  fabs(a->re[1] - a->le[1]);
    double tol = STRIP_GAP * size;
    if (R->outer == JOIN_STRAIGHT)
        return same_point(a->re, b->rs[0], b->rs[1], tol) &&
                       same_point(a->le, b->ls[0], b->ls[1], tol)
                   ? LINK_DIRECT
                   : -1;
    /* P on both normals: each end normal's midpoint */
    if (!same_point(a->re, 2 * j->sx - a->le[0], 2 * j->sy - a->le[1], 2 * tol) ||
        !same_point(b->rs, 2 * j->sx - b->ls[0], 2 * j->sy - b->ls[1], 2 * tol))
        return -1;
    double area = c_area(j);
    if (j->n == 0 || area == 0)
        return LINK_PIVOT; /* no join: c_emit writes none */
    const double *A = &j->e[0].x, *B = &j->e[j->n - 1].x;
    if (R->outer == JOIN_RIGHT && area > 0 && same_point(a->re, A[0], A[1], tol) &&
        same_point(b->rs, B[0], B[1], tol))
        return LINK_RIGHT;
    if (R->outer == JOIN_LEFT && area < 0 && same_point(a->le, A[0], A[1], tol) &&
        same_point(b->ls, B[0], B[1], tol))
        return LINK_LEFT;
    return -1;
}

/* 1 if the lines from the inner ends of a join at P between strips a and b
 * to P (a's end normal's inner half, b's start normal's) can be one line
 * between those ends: the triangle T they leave out lies in both strips,
 * where the winding number is at least 2 (each strip's contour winds at
 * least once about each point of its region, every contour at least 0
 * times), so that it is at least 1 with or without T.  T (P and the inner
 * ends Ia, Ib) lies within h of P.  A point q of T is behind P along a's
 * travel, (q - P) . d_a <= 0 (Ib - P = h n, n the inner normal at b's start,
 * which makes an angle of 90 degrees and the turn with d_a), and 0 only on
 * a's end normal; so P, a's base curve's end, is not the nearest point of
 * that curve to q unless q is on its normal, and its start is not either
 * if it is more than 2h from P (|q - start| > 2h - h >= |q - P|): the
 * nearest point is inside, q on its normal within h, in a's region (a strip
 * has no fold: every normal of length h is in it).  The same for b, ahead of
 * P.  The base curve's ends: the strips' normals' midpoints. */
static int inner_cut(const strip *a, const strip *b, double px, double py)
{
    double ha = 0.5 * hypot(a->re[0] - a->le[0], a->re[1] - a->le[1]);
    double hb = 0.5 * hypot(b->rs[0] - b->ls[0], b->rs[1] - b->ls[1]);
    double ca = hypot(0.5 * (a->rs[0] + a->ls[0]) - px, 0.5 * (a->rs[1] + a->ls[1]) - py);
    double cb = hypot(0.5 * (b->re[0] + b->le[0]) - px, 0.5 * (b->re[1] + b->le[1]) - py);
    return ca > 2.0 * ha * (1 + 1e-6) && cb > 2.0 * hb * (1 + 1e-6);
}

static int corners_finite(const strip *s)
{
    return isfinite(s->rs[0]) && isfinite(s->rs[1]) && isfinite(s->re[0]) &&
           isfinite(s->re[1]) && isfinite(s->ls[0]) && isfinite(s->ls[1]) &&
           isfinite(s->le[0]) && isfinite(s->le[1]);
}

/* A strip, the next part of the run: joined to the chain, or a chain's
 * start (the chain before written, and the pending join on its own). */
static int run_strip(run *R, strip *s)
{
    if (!corners_finite(s))
        return aa_fail(AA_EINVAL, "stroke: the outline is out of range (not finite)");
    int link = -1, st = AA_OK;
    if (R->n > 0) {
        if (!R->first)
            link = LINK_DIRECT; /* the same piece's parts, on one normal */
        else if (R->joined)
            link = run_link(R, &R->s[R->n - 1], s);
    }
    if (link < 0) {
        st = run_flush(R);
        if (!st && R->first && R->joined)
            st = c_emit(R->out, &R->j);
        if (st)
            return st;
    } else if (link == LINK_RIGHT || link == LINK_LEFT || link == LINK_PIVOT) {
        s->j = R->j;
        s->cut = link != LINK_PIVOT && inner_cut(&R->s[R->n - 1], s, R->j.sx, R->j.sy);
    }
    s->link = link < 0 ? LINK_DIRECT : link;
    R->first = R->joined = 0;
    void *a = R->s;
    st = grow(&a, R->n, &R->cap, sizeof *s, "parts of a run");
    R->s = a;
    if (st)
        return st;
    R->s[R->n++] = *s;
    return AA_OK;
}

/* Before a part that is not a strip (contours of its own): the chain
 * written, and the pending join. */
static int run_break(run *R)
{
    int st = run_flush(R);
    R->from_start = 0;
    if (!st && R->first && R->joined)
        st = c_emit(R->out, &R->j);
    R->first = R->joined = 0;
    return st;
}

/* ---- the shapes ---- */

static int stroke_line(run *R, const piece *p, double h)
{
    double nx = -p->dy * h, ny = p->dx * h;
    strip q = {.kind = STRIP_LINE};
    q.rs[0] = p->x0 - nx, q.rs[1] = p->y0 - ny, q.re[0] = p->x1 - nx, q.re[1] = p->y1 - ny;
    q.ls[0] = p->x0 + nx, q.ls[1] = p->y0 + ny, q.le[0] = p->x1 + nx, q.le[1] = p->y1 + ny;
    /* a rectangle of no area after rounding (a dash's last sliver) is
     * none, as c_emit would leave it out */
    contour c;
    const double xy[8] = {q.rs[0], q.rs[1], q.re[0], q.re[1], q.le[0], q.le[1], q.ls[0], q.ls[1]};
    c_polygon(&c, xy, 4);
    if (c_area(&c) == 0)
        return run_break(R);
    return run_strip(R, &q);
}

/* The region swept by the normal of length 2h on the arc part [a, b]: an
 * annular sector (a strip) if h < r, else one or two sectors. */
static int stroke_arc_part(run *R, const piece *p, double a, double b, double h)
{
    double lu = hypot(p->ux, p->uy), lv = hypot(p->vx, p->vy);
    double R1 = p->r + h, rho = p->r - h;
    if (rho > 0) {
        /* the side towards the centre: left where the arc turns left */
        double ta[2], pa[2];
        piece_tangent(p, 0, ta);
        arc_point(0, 0, p->ux, p->uy, p->vx, p->vy, p->t0, &pa[0], &pa[1]);
        int left_in = -ta[1] * pa[0] + ta[0] * pa[1] < 0;
        double rr = left_in ? R1 : rho, rl = left_in ? rho : R1;
        strip q = {.kind = STRIP_ARC, .cx = p->cx, .cy = p->cy, .a = a, .b = b};
        q.r[0] = p->ux * (rr / lu), q.r[1] = p->uy * (rr / lu);
        q.r[2] = p->vx * (rr / lv), q.r[3] = p->vy * (rr / lv);
        q.l[0] = p->ux * (rl / lu), q.l[1] = p->uy * (rl / lu);
        q.l[2] = p->vx * (rl / lv), q.l[3] = p->vy * (rl / lv);
        arc_point(p->cx, p->cy, q.r[0], q.r[1], q.r[2], q.r[3], a, &q.rs[0], &q.rs[1]);
        arc_point(p->cx, p->cy, q.r[0], q.r[1], q.r[2], q.r[3], b, &q.re[0], &q.re[1]);
        arc_point(p->cx, p->cy, q.l[0], q.l[1], q.l[2], q.l[3], a, &q.ls[0], &q.ls[1]);
        arc_point(p->cx, p->cy, q.l[0], q.l[1], q.l[2], q.l[3], b, &q.le[0], &q.le[1]);
        contour c; /* none if of no area after rounding, as c_emit */
        c_begin(&c, q.rs[0], q.rs[1]);
        c_arc(&c, p->cx, p->cy, q.r[0], q.r[1], q.r[2], q.r[3], a, b);
        c_line(&c, q.le[0], q.le[1]);
        c_arc(&c, p->cx, p->cy, q.l[0], q.l[1], q.l[2], q.l[3], b, a);
        if (c_area(&c) == 0)
            return run_break(R);
        return run_strip(R, &q);
    }
    int st = run_break(R);
    if (st)
        return st;
    contour c;
    /* outer arc, radius R1 */
    double oux = p->ux * (R1 / lu), ouy = p->uy * (R1 / lu);
    double ovx = p->vx * (R1 / lv), ovy = p->vy * (R1 / lv);
    double x, y;
    arc_point(p->cx, p->cy, oux, ouy, ovx, ovy, a, &x, &y);
    c_begin(&c, x, y);
    c_arc(&c, p->cx, p->cy, oux, ouy, ovx, ovy, a, b);
    c_line(&c, p->cx, p->cy);
    st = c_emit(R->out, &c);
    if (st || rho == 0)
        return st;
    /* h > r: the opposite sector, radius h - r, at the angles t + pi */
    double k = -rho;
    double qux = -p->ux * (k / lu), quy = -p->uy * (k / lu);
    double qvx = -p->vx * (k / lv), qvy = -p->vy * (k / lv);
    c_begin(&c, p->cx, p->cy);
    arc_point(p->cx, p->cy, qux, quy, qvx, qvy, a, &x, &y);
    c_line(&c, x, y);
    c_arc(&c, p->cx, p->cy, qux, quy, qvx, qvy, a, b);
    return c_emit(R->out, &c);
}

static int stroke_arc(run *R, const piece *p, double h)
{
    double dt = p->t1 - p->t0;
    int parts = (int)ceil(fabs(dt) / (0.5 * M_PI));
    if (parts < 1)
        parts = 1;
    if (parts > 4)
        parts = 4;
    int st = AA_OK;
    for (int k = 0; k < parts && !st; k++) {
        double a = k == 0 ? p->t0 : p->t0 + dt * k / parts;
        double b = k == parts - 1 ? p->t1 : p->t0 + dt * (k + 1) / parts;
        st = stroke_arc_part(R, p, a, b, h);
    }
    return st;
}

/* ---- Bezier arcs ---- */

/* Polynomials in t, coefficients from the constant term, degree < PDEG. */
#define PDEG 8

static void pmul(const double *a, int na, const double *b, int nb, double *c)
{
    for (int k = 0; k < na + nb - 1; k++)
        c[k] = 0;
    for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++)
            c[i + j] += a[i] * b[j];
}

static double peval(const double *p, int n, double t)
{
    double r = 0;
    for (int k = n - 1; k >= 0; k--)
        r = r * t + p[k];
    return r;
}

/* The roots in (lo, hi), ascending, where p (n coefficients) changes sign:
 * between the roots of its derivative (found the same way) it is
 * monotone, and bisection finds each to full precision. */
static int sign_roots(const double *p, int n, double lo, double hi, double *r)
{
    while (n > 0 && p[n - 1] == 0)
        n--;
    if (n <= 1)
        return 0;
    double dp[PDEG], crit[PDEG];
    for (int k = 0; k + 1 < n; k++)
        dp[k] = (k + 1) * p[k + 1];
    int m = n > 2 ? sign_roots(dp, n - 1, lo, hi, crit) : 0, cnt = 0;
    double a = lo, fa = peval(p, n, lo);
    for (int k = 0; k <= m; k++) {
        double b = k < m ? crit[k] : hi, fb = peval(p, n, b);
        if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
            double x = a, y = b, fx = fa;
            for (int it = 0; it < 200; it++) {
                double mid = 0.5 * (x + y);
                if (!(mid > x && mid < y))
                    break;
                double fm = peval(p, n, mid);
                if (fm == 0) {
                    x = y = mid;
                    break;
                }
                if ((fm < 0) == (fx < 0))
                    x = mid, fx = fm;
                else
                    y = mid;
            }
            r[cnt++] = 0.5 * (x + y);
        }
        a = b, fa = fb;
    }
    return cnt;
}

/* The curvature of curve piece p at t: B' x B'' / |B'|^3 (the ellipse's
 * B' x B'' is u x v); near a cubic's end where B' vanishes by the factored
 * form (bez_stop). */
static double bez_curvature(const piece *p, double t)
{
    const double *b = p->b;
    double ux, uy, c, te, q[4];
    if (bez_stop(p, t, &te, q)) {
        double Qx = q[0] + q[1] * t, Qy = q[2] + q[3] * t, l = hypot(Qx, Qy);
        double X = Qx * q[3] - Qy * q[1], s = fabs(t - te);
        if (X == 0 || l == 0)
            return 0.0;
        return s == 0 ? copysign(INFINITY, X) : X / (s * l * l * l);
    }
    bez_d1(p, t, &ux, &uy);
    if (p->base == AA_OFFSET_ELLIPSE) {
        c = b[2] * b[5] - b[3] * b[4];
    } else {
        double vx = 2 * b[2] + 6 * t * b[3], vy = 2 * b[6] + 6 * t * b[7];
        c = ux * vy - uy * vx;
    }
    double L = hypot(ux, uy);
    return c / (L * L * L);
}

/* The extremes of the curvature in (lo, hi), ascending: the roots of
 * c' |B'|^2 - 3 c (B' . B''), c = B' x B'' (degree 6 at most); on the
 * ellipse c' = 0 and B' . B'' = (|u|^2 - |v|^2) sin t cos t + (u . v)
 * (sin^2 t - cos^2 t) = a cos 2t + b sin 2t, a = -(u . v), b = (|u|^2 -
 * |v|^2)/2, zero at 2t = atan2(b, a) + pi/2 + k pi (a quarter turn apart;
 * at most 5 on a range of 2 pi). */
static int bez_curvature_turns(const piece *p, double lo, double hi, double *r)
{
    const double *b = p->b;
    if (p->base == AA_OFFSET_ELLIPSE) {
        double a = -(b[2] * b[4] + b[3] * b[5]);
        double bb = 0.5 * ((b[2] * b[2] + b[3] * b[3]) - (b[4] * b[4] + b[5] * b[5]));
        if (a == 0 && bb == 0)
            return 0;
        double z = 0.5 * (atan2(bb, a) + 0.5 * M_PI), q = 0.5 * M_PI;
        double k = ceil((lo - z) / q);
        int n = 0;
        for (int j = -1; j < 7 && n < 6; j++) {
            double t = z + (k + j) * q;
            if (t > lo && t < hi && (n == 0 || t > r[n - 1]))
                r[n++] = t;
        }
        return n;
    }
    const double ux[3] = {b[1], 2 * b[2], 3 * b[3]}, uy[3] = {b[5], 2 * b[6], 3 * b[7]};
    const double vx[2] = {2 * b[2], 6 * b[3]}, vy[2] = {2 * b[6], 6 * b[7]};
    const double wx[1] = {6 * b[3]}, wy[1] = {6 * b[7]};
    double c[PDEG] = {0}, cp[PDEG] = {0}, l2[PDEG] = {0}, dot[PDEG] = {0}, t1[PDEG], t2[PDEG];
    double g[PDEG] = {0};
    pmul(ux, 3, vy, 2, t1), pmul(uy, 3, vx, 2, t2);
    for (int k = 0; k < 4; k++)
        c[k] = t1[k] - t2[k];
    pmul(ux, 3, wy, 1, t1), pmul(uy, 3, wx, 1, t2);
    for (int k = 0; k < 3; k++)
        cp[k] = t1[k] - t2[k];
    pmul(ux, 3, ux, 3, t1), pmul(uy, 3, uy, 3, t2);
    for (int k = 0; k < 5; k++)
        l2[k] = t1[k] + t2[k];
    pmul(ux, 3, vx, 2, t1), pmul(uy, 3, vy, 2, t2);
    for (int k = 0; k < 4; k++)
        dot[k] = t1[k] + t2[k];
    pmul(cp, 3, l2, 5, t1);
    pmul(c, 4, dot, 4, t2);
    for (int k = 0; k < 7; k++)
        g[k] = t1[k] - 3 * t2[k];
    return sign_roots(g, 7, lo, hi, r);
}

/* The point of curve piece p at t at distance d along its normal (evolute:
 * at its centre of curvature). */
static void bez_point(const piece *p, double t, int evolute, double d, double *x, double *y)
{
    aa_offset_curve oc = {{0}, {1, 0, 0, 1, 0, 0}, d, evolute, p->base};
    memcpy(oc.b, p->b, sizeof oc.b);
    aa_offset_point(&oc, t, x, y, NULL, NULL);
}

/* One boundary of a region: the offset at d, or the evolute. */
typedef struct side {
    int evolute;
    double d;
} side;

/* The region {B(t) + s N(t): u <= t <= v, s between side lo and side hi}
 * with the Jacobian |B'| (1 - s k) of one sign (positive: pos), as a
 * contour turning the positive way: the boundary in (t, s) taken
 * counterclockwise where the Jacobian is positive, clockwise where it is
 * negative, so that its winding number about a point is the number of the
 * point's preimages in the region (the degree of the map). */
static int bez_region(aa_path *out, const piece *p, double u, double v, side lo, side hi,
                      int pos)
{
    aa_offset_curve cl = {{0}, {1, 0, 0, 1, 0, 0}, lo.d, lo.evolute, p->base}, ch = cl;
    memcpy(cl.b, p->b, sizeof cl.b);
    ch.d = hi.d, ch.evolute = hi.evolute;
    memcpy(ch.b, p->b, sizeof ch.b);
    double lu[2], lv[2], hu[2], hv[2];
    bez_point(p, u, lo.evolute, lo.d, &lu[0], &lu[1]);
    bez_point(p, v, lo.evolute, lo.d, &lv[0], &lv[1]);
    bez_point(p, u, hi.evolute, hi.d, &hu[0], &hu[1]);
    bez_point(p, v, hi.evolute, hi.d, &hv[0], &hv[1]);
    int st = aa_path_move_to(out, lu[0], lu[1]);
    if (pos) {
        if (!st)
            st = aa_path_offset_to(out, &cl, u, v, lv[0], lv[1]);
        if (!st)
            st = aa_path_line_to(out, hv[0], hv[1]);
        if (!st)
            st = aa_path_offset_to(out, &ch, v, u, hu[0], hu[1]);
    } else {
        if (!st)
            st = aa_path_line_to(out, hu[0], hu[1]);
        if (!st)
            st = aa_path_offset_to(out, &ch, u, v, hv[0], hv[1]);
        if (!st)
            st = aa_path_line_to(out, lv[0], lv[1]);
        if (!st)
            st = aa_path_offset_to(out, &cl, v, u, lu[0], lu[1]);
    }
    return st ? st : aa_path_close(out);
}

/* The region swept by the normal of length 2h on a Bezier arc (SVG 2's
 * union of the normal segments), as contours whose union under the
 * non-zero rule is exactly that region, folds of the offsets included.
 * F(t, s) = B(t) + s N(t) on [t0, t1] x [-h, h] has Jacobian
 * |B'| (1 - s k(t)): the parameter is cut where |k| h = 1 and, for the
 * evolute's sake, at the extremes of k (between them k is monotone, so
 * each of k = 1/h and k = -1/h has at most one root there, bisected).  On a
 * part where |k| h <= 1 the Jacobian is positive on the whole strip: one
 * region between the offsets at -h and h.  Where k h > 1 it changes sign
 * at s = 1/k, the evolute: two regions, [-h, 1/k] (positive) and [1/k, h]
 * (negative); where k h < -1 the same with the signs swapped.  Each region
 * contributes its number of preimages of a point, at least 0, so the
 * winding number of all of them is positive exactly on the image. */
static int stroke_bez(run *R, const piece *p, double h)
{
    double cut[32], turns[8];
    int n = 0, nt = bez_curvature_turns(p, p->t0, p->t1, turns);
    double knots[10];
    int nk = 0;
    knots[nk++] = p->t0;
    for (int k = 0; k < nt; k++)
        knots[nk++] = turns[k];
    knots[nk++] = p->t1;
    cut[n++] = p->t0;
    for (int k = 0; k + 1 < nk; k++) {
        double a = knots[k], bnd = knots[k + 1], roots[2];
        int nr = 0;
        for (int sg = -1; sg <= 1; sg += 2) {
            double target = sg / h, fa = bez_curvature(p, a) - target;
            double fb = bez_curvature(p, bnd) - target;
            if (!((fa < 0 && fb > 0) || (fa > 0 && fb < 0)))
                continue;
            double x = a, y = bnd;
            for (int it = 0; it < 200; it++) {
                double mid = 0.5 * (x + y);
                if (!(mid > x && mid < y))
                    break;
                double fm = bez_curvature(p, mid) - target;
                if ((fm < 0) == (fa < 0))
                    x = mid;
                else
                    y = mid;
            }
            roots[nr++] = 0.5 * (x + y);
        }
        /* k is monotone here: k = 1/h and k = -1/h come in either order */
        if (nr == 2 && roots[0] > roots[1]) {
            double tmp = roots[0];
            roots[0] = roots[1], roots[1] = tmp;
        }
        for (int j = 0; j < nr; j++)
            if (n < 30 && roots[j] > cut[n - 1])
                cut[n++] = roots[j];
        if (k + 1 < nk - 1 && n < 30 && knots[k + 1] > cut[n - 1])
            cut[n++] = knots[k + 1];
    }
    if (p->t1 > cut[n - 1])
        cut[n++] = p->t1;
    else
        cut[n - 1] = p->t1;
    int st = AA_OK;
    const side minus = {0, -h}, plus = {0, h}, ev = {1, 0};
    for (int k = 0; k + 1 < n && !st; k++) {
        double u = cut[k], v = cut[k + 1];
        if (!(v > u))
            continue;
        double kh = bez_curvature(p, 0.5 * (u + v)) * h;
        if (kh <= 1 && kh >= -1) {
            /* consecutive parts without folds are one region: the cuts at
             * the curvature's extremes matter to the evolute only */
            while (k + 2 < n) {
                double w = cut[k + 2], kw = bez_curvature(p, 0.5 * (v + w)) * h;
                if (!(kw <= 1 && kw >= -1))
                    break;
                v = w;
                k++;
            }
            strip q = {.kind = STRIP_OFFSET, .a = u, .b = v};
            for (int i = 0; i < 2; i++) {
                aa_offset_curve oc = {{0}, {1, 0, 0, 1, 0, 0}, i ? h : -h, 0, p->base};
                memcpy(oc.b, p->b, sizeof oc.b);
                q.oc[i] = oc;
            }
            bez_point(p, u, 0, -h, &q.rs[0], &q.rs[1]);
            bez_point(p, v, 0, -h, &q.re[0], &q.re[1]);
            bez_point(p, u, 0, h, &q.ls[0], &q.ls[1]);
            bez_point(p, v, 0, h, &q.le[0], &q.le[1]);
            st = run_strip(R, &q);
        } else {
            st = run_break(R);
            if (!st)
                st = bez_region(R->out, p, u, v, minus, ev, kh > 1);
            if (!st)
                st = bez_region(R->out, p, u, v, ev, plus, kh < -1);
        }
    }
    return st;
}

static int stroke_piece(run *R, const piece *p, double h)
{
    if (p->bez)
        return stroke_bez(R, p, h);
    return p->arc ? stroke_arc(R, p, h) : stroke_line(R, p, h);
}

/* The clipped miter of miter-clip (and of arcs between straight edges):
 * the outer edges' tangent lines from A and B, cut by the line
 * perpendicular to the outward bisector m = (din - dout)/|din - dout| at
 * the distance L = miterlimit h from P (SVG 2, stroke-miterlimit: half
 * the limit times the width).  A . m = h cos(phi/2) and din . m =
 * sin(phi/2) > 0 (phi the turn), so the edge from A reaches the cut at
 * A + t din, t = (L - h cos(phi/2)) / sin(phi/2) >= 0 (L >= h), and the
 * one from B at B - t dout: the pentagon P A A' B' B.  A reversal
 * (dout = -din, m = din) gives the rectangle of width 2h and length L
 * ahead of P, SVG 2's join for parallel tangents. */
static void clipped_miter(contour *c, double px, double py, const double din[2],
                          const double dout[2], double ax, double ay, double bx, double by,
                          double L, double h)
{
    double mx = din[0] - dout[0], my = din[1] - dout[1], ml = hypot(mx, my);
    mx /= ml, my /= ml;
    double cs = ((ax - px) * mx + (ay - py) * my) / h, sn = din[0] * mx + din[1] * my;
    double t = (L - h * cs) / sn;
    const double xy[10] = {px, py, ax, ay, ax + t * din[0], ay + t * din[1],
                           bx - t * dout[0], by - t * dout[1], bx, by};
    c_polygon(c, xy, 5);
}

/* ---- the arcs join ---- */

/* One outer edge of an arcs join extended beyond the join: from its end
 * Q (A or B) in the direction d away from the segment (din after A, -dout
 * before B), a line (curvature 0) or the circle about the segment's
 * centre of curvature through Q: Q at parameter 0, the point at s
 * C + u cos s + v sin s (u = Q - C, v = r d), s growing away from the
 * segment. */
typedef struct jedge {
    int line;
    double qx, qy, dx, dy;
    double cx, cy, r, ux, uy, vx, vy;
} jedge;

static void je_set_circle(jedge *e, double cx, double cy)
{
    e->line = 0;
    e->cx = cx, e->cy = cy;
    e->ux = e->qx - cx, e->uy = e->qy - cy;
    e->r = hypot(e->ux, e->uy);
    e->vx = e->r * e->dx, e->vy = e->r * e->dy;
}

static void je_point(const jedge *e, double s, double *x, double *y)
{
    if (e->line) {
        *x = e->qx + s * e->dx, *y = e->qy + s * e->dy;
        return;
    }
    arc_point(e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, s, x, y);
}

/* The parameter of a point on the edge: along the line, or the circle's
 * angle from Q in [0, 2 pi). */
static double je_param(const jedge *e, double x, double y)
{
    if (e->line)
        return (x - e->qx) * e->dx + (y - e->qy) * e->dy;
    double r2 = e->r * e->r;
    double c = ((x - e->cx) * e->ux + (y - e->cy) * e->uy) / r2;
    double s = ((x - e->cx) * e->vx + (y - e->cy) * e->vy) / r2;
    double a = atan2(s, c);
    return a < 0 ? a + 2 * M_PI : a;
}

/* The points where two edges' circles (or a circle and a line) meet:
 * their count, at most 2, in xy. */
static int je_meet(const jedge *a, const jedge *b, double xy[4])
{
    if (a->line && b->line)
        return 0;
    if (a->line || b->line) {
        const jedge *l = a->line ? a : b, *c = a->line ? b : a;
        double t = (c->cx - l->qx) * l->dx + (c->cy - l->qy) * l->dy;
        double fx = l->qx + t * l->dx, fy = l->qy + t * l->dy;
        double d = hypot(c->cx - fx, c->cy - fy);
        if (!(d <= c->r))
            return 0;
        double s = sqrt(fmax(c->r * c->r - d * d, 0.0));
        xy[0] = fx - s * l->dx, xy[1] = fy - s * l->dy;
        xy[2] = fx + s * l->dx, xy[3] = fy + s * l->dy;
        return 2;
    }
    double ex = b->cx - a->cx, ey = b->cy - a->cy, d = hypot(ex, ey);
    if (!(d > 0) || d > a->r + b->r || d < fabs(a->r - b->r))
        return 0;
    ex /= d, ey /= d;
    double m = (a->r * a->r - b->r * b->r + d * d) / (2 * d);
    double s = sqrt(fmax(a->r * a->r - m * m, 0.0));
    double fx = a->cx + m * ex, fy = a->cy + m * ey;
    xy[0] = fx - s * ey, xy[1] = fy + s * ex;
    xy[2] = fx + s * ey, xy[3] = fy - s * ex;
    return 2;
}

/* SVG 2's fallback where the circles do not meet ("Adjusting the circles
 * for the arcs stroke-linejoin"): both radii changed by the same amount D
 * > 0, each centre moving along its normal at Q so that the circle stays
 * tangent to its edge there, until the circles just touch: apart, both
 * grow, |C1 - C2| = r1 + r2 + 2 D; one inside the other, the larger
 * shrinks and the smaller grows, |C1 - C2| = R - r - 2 D; with C_i(D) =
 * C_i + e_i D w_i (w_i the unit vector from Q_i to C_i, e_i = +-1),
 * |D0 + D w|^2 = (S + sigma D)^2 is a quadratic in D, of which the least
 * positive root is taken.  A circle and a line: the circle alone grows
 * until it touches the line, dist(C(D), line) = r + D, linear.  The
 * touching point in *x, *y and the edges moved; AA_EINVAL if no D. */
static int je_touch(jedge *a, jedge *b, double *x, double *y)
{
    if (a->line || b->line) {
        jedge *l = a->line ? a : b, *c = a->line ? b : a;
        double wx = (c->cx - c->qx) / c->r, wy = (c->cy - c->qy) / c->r;
        double nx = -l->dy, ny = l->dx;
        double f0 = (c->cx - l->qx) * nx + (c->cy - l->qy) * ny, g = wx * nx + wy * ny;
        double best = INFINITY;
        /* f0 + D g = +-(r + D) */
        if (g != 1) {
            double D = (c->r - f0) / (g - 1);
            if (D > 0 && D < best)
                best = D;
        }
        if (g != -1) {
            double D = (-c->r - f0) / (g + 1);
            if (D > 0 && D < best)
                best = D;
        }
        if (!isfinite(best))
            return AA_EINVAL;
        je_set_circle(c, c->qx + (c->r + best) * wx, c->qy + (c->r + best) * wy);
        double t = (c->cx - l->qx) * l->dx + (c->cy - l->qy) * l->dy;
        *x = l->qx + t * l->dx, *y = l->qy + t * l->dy;
        return AA_OK;
    }
    double d0x = a->cx - b->cx, d0y = a->cy - b->cy, d0 = hypot(d0x, d0y);
    double wax = (a->cx - a->qx) / a->r, way = (a->cy - a->qy) / a->r;
    double wbx = (b->cx - b->qx) / b->r, wby = (b->cy - b->qy) / b->r;
    int apart = d0 > a->r + b->r;
    double ea = 1, eb = 1, S = a->r + b->r, sigma = 2;
    if (!apart) {
        /* one inside the other */
        ea = a->r > b->r ? -1 : 1, eb = -ea;
        S = fabs(a->r - b->r), sigma = -2;
    }
    double wx = ea * wax - eb * wbx, wy = ea * way - eb * wby;
    double qa = wx * wx + wy * wy - sigma * sigma;
    double qb = 2 * (d0x * wx + d0y * wy - S * sigma), qc = d0 * d0 - S * S;
    double roots[2];
    int nr = 0;
    if (qa == 0) {
        if (qb != 0)
            roots[nr++] = -qc / qb;
    } else {
        double disc = qb * qb - 4 * qa * qc;
        if (disc >= 0) {
            double sq = sqrt(disc), q = -0.5 * (qb + copysign(sq, qb));
            roots[nr++] = q / qa;
            if (q != 0)
                roots[nr++] = qc / q;
        }
    }
    double best = INFINITY;
    for (int k = 0; k < nr; k++) {
        double D = roots[k];
        if (D > 0 && D < best && S + sigma * D >= 0 && a->r + ea * D > 0 && b->r + eb * D > 0)
            best = D;
    }
    if (!isfinite(best))
        return AA_EINVAL;
    je_set_circle(a, a->qx + (a->r + ea * best) * wax, a->qy + (a->r + ea * best) * way);
    je_set_circle(b, b->qx + (b->r + eb * best) * wbx, b->qy + (b->r + eb * best) * wby);
    /* the touching point: from the centre of the larger (or of a, apart)
     * towards the other's, at its radius */
    const jedge *big = apart || a->r >= b->r ? a : b, *small = big == a ? b : a;
    double ex = small->cx - big->cx, ey = small->cy - big->cy, el = hypot(ex, ey);
    if (!(el > 0))
        return AA_EINVAL;
    *x = big->cx + big->r * ex / el, *y = big->cy + big->r * ey / el;
    return AA_OK;
}

/* The parameters in [0, smax] where edge e crosses the line through Y
 * perpendicular to T, (Z - Y) . T = 0: their count (at most 2). */
static int je_cross(const jedge *e, double yx, double yy, double tx, double ty, double smax,
                    double *s)
{
    if (e->line) {
        double dt = e->dx * tx + e->dy * ty;
        if (dt == 0)
            return 0;
        double v = ((yx - e->qx) * tx + (yy - e->qy) * ty) / dt;
        if (v >= 0 && v <= smax) {
            s[0] = v;
            return 1;
        }
        return 0;
    }
    /* (C - Y) . T + (u . T) cos s + (v . T) sin s = 0 */
    double K = (e->cx - yx) * tx + (e->cy - yy) * ty;
    double A = e->ux * tx + e->uy * ty, B = e->vx * tx + e->vy * ty, R = hypot(A, B);
    if (!(R > 0) || fabs(K) > R)
        return 0;
    double ph = atan2(B, A), ac = acos(-K / R);
    int n = 0;
    for (int sg = -1; sg <= 1; sg += 2) {
        double v = ph + sg * ac;
        v = fmod(v, 2 * M_PI);
        if (v < 0)
            v += 2 * M_PI;
        if (v <= smax)
            s[n++] = v;
    }
    if (n == 2 && (s[0] == s[1]))
        n = 1;
    return n;
}

/* Append edge e from parameter s0 to s1 to the contour. */
static void je_append(contour *c, const jedge *e, double s0, double s1)
{
    if (e->line) {
        double x, y;
        je_point(e, s1, &x, &y);
        c_line(c, x, y);
        return;
    }
    c_arc(c, e->cx, e->cy, e->ux, e->uy, e->vx, e->vy, s0, s1);
}

static int arcs_refuse(double px, double py, const char *why)
{
    return aa_fail(AA_EINVAL, "stroke: the arcs join at (%g, %g) is not drawn: %s", px, py, why);
}

/*
 * The arcs join (SVG 2, "line join shape" and stroke-miterlimit) at P
 * between a segment ending with direction din and curvature kin and one
 * starting with dout and kout (signed: positive turning left; 0 for a
 * line), whose outer edges end at A and start at B.  Each outer edge is
 * extended by its osculating circle, which is concentric with the
 * segment's (the offset of a curve at distance h about its centre of
 * curvature), through A tangent to din (through B tangent to dout), or by
 * its tangent line where the curvature is 0; the join is the region
 * bounded by P A, the extension of the first edge to X, the point where
 * the two extensions meet nearest P, the extension of the second back to
 * B, and B P.  Where they do not meet, their radii are changed alike
 * until they touch (je_touch).  The miter limit: the length of the arc
 * from P tangent there to the outward bisector m and through X, by the
 * tangent-chord angle a = angle(m, X - P) chord |X - P| times a / sin a,
 * is at most L = miterlimit h, or the join is cut by the line normal to
 * that arc at arc length L from P, the side of P kept.  Refused (naming
 * the join): extensions that would reach X going backwards (a line) or
 * more than a half turn (a circle), and cuts that do not cross each
 * extension once.
 */
static int arcs_join(contour *c, double px, double py, const double din[2],
                     const double dout[2], double kin, double kout, double ax, double ay,
                     double bx, double by, double L)
{
    jedge e[2];
    const double k[2] = {kin, kout};
    const double dir[2][2] = {{din[0], din[1]}, {dout[0], dout[1]}};
    for (int i = 0; i < 2; i++) {
        jedge *q = &e[i];
        memset(q, 0, sizeof *q);
        q->line = 1;
        q->qx = i ? bx : ax, q->qy = i ? by : ay;
        q->dx = i ? -dout[0] : din[0], q->dy = i ? -dout[1] : din[1];
        if (k[i] != 0)
            je_set_circle(q, px - dir[i][1] / k[i], py + dir[i][0] / k[i]);
    }
    double xy[4], x = 0, y = 0;
    int n = je_meet(&e[0], &e[1], xy);
    if (n > 0) {
        int best = 0;
        if (n == 2 && hypot(xy[2] - px, xy[3] - py) < hypot(xy[0] - px, xy[1] - py))
            best = 1;
        x = xy[2 * best], y = xy[2 * best + 1];
    } else if (je_touch(&e[0], &e[1], &x, &y)) {
        return arcs_refuse(px, py, "its circles cannot be made to touch");
    }
    double s[2];
    for (int i = 0; i < 2; i++) {
        s[i] = je_param(&e[i], x, y);
        if (e[i].line ? !(s[i] >= 0) : !(s[i] <= M_PI))
            return arcs_refuse(px, py, e[i].line ? "an edge's line meets the other edge's "
                                                   "circle behind the join"
                                                 : "an edge's circle turns more than a half "
                                                   "turn to meet the other");
    }
    /* the miter length along the arc from P tangent to m through X */
    double mx = din[0] - dout[0], my = din[1] - dout[1], ml = hypot(mx, my);
    mx /= ml, my /= ml;
    double cx = x - px, cy = y - py, chord = hypot(cx, cy);
    double cm = cx * mx + cy * my, cp = -cx * my + cy * mx; /* along m, along its left */
    double half = atan2(fabs(cp), cm), len = half > 0 ? chord * half / sin(half) : chord;
    c_begin(c, px, py);
    c_line(c, ax, ay);
    if (len <= L) {
        je_append(c, &e[0], 0, s[0]);
        je_append(c, &e[1], s[1], 0);
        return AA_OK;
    }
    /* the cut: Y at arc length L, T the arc's tangent there */
    double yx, yy, tx, ty;
    if (cp == 0) {
        yx = px + L * mx, yy = py + L * my, tx = mx, ty = my;
    } else {
        double rho = chord / (2 * sin(half)), psi = L / rho, sg = cp > 0 ? 1 : -1;
        if (!(psi < M_PI))
            return arcs_refuse(px, py, "its miter limit's arc passes a half turn");
        double sn = sin(psi), vs = 2 * sin(0.5 * psi) * sin(0.5 * psi);
        double lx = -my * sg, ly = mx * sg;
        yx = px + rho * (sn * mx + vs * lx), yy = py + rho * (sn * my + vs * ly);
        tx = cos(psi) * mx + sn * lx, ty = cos(psi) * my + sn * ly;
    }
    double cut[2], v[2];
    for (int i = 0; i < 2; i++) {
        double qx = i ? bx : ax, qy = i ? by : ay;
        if ((qx - yx) * tx + (qy - yy) * ty > 0 || je_cross(&e[i], yx, yy, tx, ty, s[i], v) != 1)
            return arcs_refuse(px, py, "its miter limit's cut does not cross each edge once");
        cut[i] = v[0];
    }
    je_append(c, &e[0], 0, cut[0]);
    double zx, zy;
    je_point(&e[1], cut[1], &zx, &zy);
    c_line(c, zx, zy);
    je_append(c, &e[1], cut[1], 0);
    return AA_OK;
}

/* The join at P between unit directions din and dout, with the segments'
 * curvatures there kin and kout (used by arcs only), as the contour P, A,
 * its outer edge to B (closed by B P; c->n = 0: no join, straight on or an
 * empty bevel at a reversal).  *outer: the side of the travel its outer
 * edge is on, JOIN_RIGHT or JOIN_LEFT (A and B the ends of the offsets at
 * -h or at h), or JOIN_STRAIGHT straight on. */
static int stroke_join(contour *c, int *outer, double px, double py, const double din[2],
                       const double dout[2], double kin, double kout,
                       const aa_stroke_style *style, double h)
{
    double cr = din[0] * dout[1] - din[1] * dout[0];
    double dot = din[0] * dout[0] + din[1] * dout[1];
    c->n = 0;
    c->sx = px, c->sy = py;
    /* the outer side: right of the travel for a left turn (cr > 0), else
     * left (a reversal, cr = 0, counts as a right turn) */
    *outer = cr > 0 ? JOIN_RIGHT : JOIN_LEFT;
    if (cr == 0 && dot > 0) {
        *outer = JOIN_STRAIGHT;
        return AA_OK;
    }
    double sg = cr > 0 ? -1.0 : 1.0;
    double nax = -sg * din[1], nay = sg * din[0];
    double nbx = -sg * dout[1], nby = sg * dout[0];
    double ax = px + h * nax, ay = py + h * nay, bx = px + h * nbx, by = py + h * nby;
    aa_line_join join = style->join;
    if (join == AA_JOIN_ARCS) {
        /* SVG 2: both curvatures 0, miter-clip; either beyond 1/h (the
         * edge's circle would have no radius or fold), round */
        if (kin == 0 && kout == 0) {
            join = AA_JOIN_MITER_CLIP;
        } else if (!(fabs(kin) * h < 1 && fabs(kout) * h < 1)) {
            join = AA_JOIN_ROUND;
        } else if (cr == 0) {
            clipped_miter(c, px, py, din, dout, ax, ay, bx, by, style->miterlimit * h, h);
            return AA_OK;
        } else {
            return arcs_join(c, px, py, din, dout, kin, kout, ax, ay, bx, by,
                             style->miterlimit * h);
        }
    }
    if (join == AA_JOIN_ROUND) {
        /* P + h (cos t nA + sin t din), t from 0 to the turn alpha, ends
         * at P + h nB (the turn of din to dout is that of nA to nB) */
        double alpha = atan2(fabs(cr), dot);
        c_begin(c, px, py);
        c_line(c, ax, ay);
        c_arc(c, px, py, h * nax, h * nay, h * din[0], h * din[1], 0, alpha);
        return AA_OK;
    }
    double sx = nax + nbx, sy = nay + nby, s2 = sx * sx + sy * sy;
    int within = s2 > 0 && 2.0 <= style->miterlimit * sqrt(s2);
    if ((join == AA_JOIN_MITER || join == AA_JOIN_MITER_CLIP) && within) {
        const double xy[8] = {px, py, ax, ay, px + 2 * h * sx / s2, py + 2 * h * sy / s2, bx, by};
        c_polygon(c, xy, 4);
    } else if (join == AA_JOIN_MITER_CLIP) {
        clipped_miter(c, px, py, din, dout, ax, ay, bx, by, style->miterlimit * h, h);
    } else if (s2 > 0) { /* a reversal's bevel is empty */
        const double xy[6] = {px, py, ax, ay, bx, by};
        c_polygon(c, xy, 3);
    }
    return AA_OK;
}

/* The cap at P with outward unit direction d. */
static void cap_contour(contour *c, double px, double py, const double d[2],
                        const aa_stroke_style *style, double h)
{
    double nx = -d[1] * h, ny = d[0] * h, ex = d[0] * h, ey = d[1] * h;
    c->n = 0;
    if (style->cap == AA_CAP_SQUARE) {
        const double xy[8] = {px + nx, py + ny, px + nx + ex, py + ny + ey,
                              px - nx + ex, py - ny + ey, px - nx, py - ny};
        c_polygon(c, xy, 4);
    } else if (style->cap == AA_CAP_ROUND) {
        /* P + h (cos t n + sin t d), t from 0 to pi: the half disk ahead */
        c_begin(c, px + nx, py + ny);
        c_arc(c, px, py, nx, ny, ex, ey, 0, M_PI);
    }
}

static int stroke_cap(aa_path *out, double px, double py, const double d[2],
                      const aa_stroke_style *style, double h)
{
    contour c;
    cap_contour(&c, px, py, d, style, h);
    return c.n ? c_emit(out, &c) : AA_OK;
}

/* A subpath of no length at P: its caps in the x axis's direction. */
static int stroke_dot(aa_path *out, double px, double py, const aa_stroke_style *style, double h)
{
    const double right[2] = {1, 0}, left[2] = {-1, 0};
    int st = stroke_cap(out, px, py, right, style, h);
    return st ? st : stroke_cap(out, px, py, left, style, h);
}

/* The signed curvature of a piece at its start or end, positive turning
 * left (the arcs join's): 0 on a line; a circle's 1/r, its sign that of
 * u x v times the direction of travel; a Bezier or elliptical arc's
 * B' x B'' / |B'|^3 (bez_curvature).  At a Bezier arc's end whose control
 * point is on it the curvature is infinite, and SVG 2 says to use a line
 * there ("if P0 and P1 ... are degenerate, the curvature will be infinite
 * and a line should be used"): 0. */
static double piece_curvature(const piece *p, int at_end)
{
    if (p->bez) {
        double k = bez_curvature(p, at_end ? p->t1 : p->t0);
        return isfinite(k) ? k : 0.0;
    }
    if (!p->arc)
        return 0.0;
    double uv = p->ux * p->vy - p->uy * p->vx, sg = p->t1 > p->t0 ? 1.0 : -1.0;
    return (uv > 0 ? sg : -sg) / p->r;
}

/* The join between pieces a (ending) and b (starting) at b's start, as a
 * contour (stroke_join). */
static int join_pieces(contour *c, int *outer, const piece *a, const piece *b,
                       const aa_stroke_style *style, double h)
{
    double din[2], dout[2], kin = 0, kout = 0;
    piece_tangent(a, 1, din);
    piece_tangent(b, 0, dout);
    if (style->join == AA_JOIN_ARCS)
        kin = piece_curvature(a, 1), kout = piece_curvature(b, 0);
    return stroke_join(c, outer, b->x0, b->y0, din, dout, kin, kout, style, h);
}

/* A run of pieces (a subpath or a dash): every piece, the joins between
 * them (with the pieces' strips one contour, the run's), and caps at its
 * ends or the join that closes it. */
static int stroke_run(aa_path *out, const piece *p, size_t n, int closed,
                      const aa_stroke_style *style, double h)
{
    run R = {0};
    R.out = out;
    R.from_start = 1;
    int st = AA_OK;
    double din[2], dout[2];
    for (size_t i = 0; i < n && !st; i++) {
        R.first = 1, R.joined = 0;
        if (i > 0 && !p[i].nojoin) {
            st = join_pieces(&R.j, &R.outer, &p[i - 1], &p[i], style, h);
            R.joined = !st;
        } else if (i > 0) {
            st = run_flush(&R); /* after a cusp: no join, and the chain ends */
        }
        if (!st)
            st = stroke_piece(&R, &p[i], h);
    }
    if (!st && !closed && n > 0) {
        /* the caps, each in the chain where it meets its end (from the
         * left end of the end normal ahead round to its right end, that
         * normal's line cancelled: the same sum), else on its own */
        piece_tangent(&p[0], 0, dout);
        const double back[2] = {-dout[0], -dout[1]};
        cap_contour(&R.ends[0], p[0].x0, p[0].y0, back, style, h);
        piece_tangent(&p[n - 1], 1, din);
        cap_contour(&R.ends[1], p[n - 1].x1, p[n - 1].y1, din, style, h);
        for (int e = 0; e < 2; e++) {
            const contour *c = &R.ends[e];
            if (R.n == 0 || (e == 0 && !R.from_start) || c->n == 0 || !(c_area(c) < 0))
                continue;
            /* the start cap runs from the right start to the left, the end
             * cap from the left end to the right */
            const strip *q = e ? &R.s[R.n - 1] : &R.s[0];
            const double *from = e ? q->le : q->rs, *to = e ? q->re : q->ls;
            double tol = STRIP_GAP * (fabs(from[0]) + fabs(from[1]) + 2 * h);
            R.capped[e] = same_point(from, c->sx, c->sy, tol) &&
                          same_point(to, c->e[c->n - 1].x, c->e[c->n - 1].y, tol);
        }
        for (int e = 0; e < 2 && !st; e++)
            if (!R.capped[e])
                st = c_emit(out, &R.ends[e]);
    }
    if (!st)
        st = run_flush(&R);
    free(R.s);
    if (st || n == 0 || !closed)
        return st;
    contour c;
    int outer;
    st = join_pieces(&c, &outer, &p[n - 1], &p[0], style, h);
    return st ? st : c_emit(out, &c);
}

/* ---- dashes ---- */

/* The most dashes one subpath may have. */
#define DASH_MAX 10000

/* The parts of the subpath's pieces from arc length a to b (a < b),
 * appended to dst. */
static int collect(const piece *p, size_t n, double a, double b, pieces *dst)
{
    double s = 0;
    for (size_t k = 0; k < n; k++) {
        double e = s + p[k].len;
        double lo = fmax(a, s) - s, hi = fmin(b, e) - s;
        if (k == n - 1 && b >= e)
            hi = p[k].len;
        if (hi > lo) {
            piece q = lo <= 0 && hi >= p[k].len
                          ? p[k]
                          : piece_part(&p[k], fmax(lo, 0), fmin(hi, p[k].len));
            int st = pieces_push(dst, &q);
            if (st)
                return st;
        }
        s = e;
    }
    return AA_OK;
}

/* The dash from arc length a to b (a <= b) of the subpath's pieces. */
static int stroke_dash(aa_path *out, const piece *p, size_t n, double a, double b,
                       const aa_stroke_style *style, double h, pieces *tmp)
{
    tmp->n = 0;
    double s = 0;
    if (a == b) {
        /* caps only, in the direction of the path at a */
        size_t k = 0;
        while (k + 1 < n && s + p[k].len <= a)
            s += p[k++].len;
        double f = fmin(fmax(a - s, 0), p[k].len), d[2];
        piece q = p[k];
        if (f > 0 && f < p[k].len)
            q = piece_part(&p[k], 0, f);
        piece_tangent(&q, f > 0, d);
        double x = f > 0 ? q.x1 : q.x0, y = f > 0 ? q.y1 : q.y0;
        const double back[2] = {-d[0], -d[1]};
        int st = stroke_cap(out, x, y, d, style, h);
        return st ? st : stroke_cap(out, x, y, back, style, h);
    }
    int st = collect(p, n, a, b, tmp);
    return st ? st : stroke_run(out, tmp->p, tmp->n, 0, style, h);
}

/* Where in the pattern (m entries, of total length `period`) a subpath
 * starts: the entry's index (even: a dash), *pos how far into it. */
static size_t dash_phase(const aa_stroke_style *style, double period, double *pos)
{
    size_t m = style->ndash % 2 ? 2 * style->ndash : style->ndash;
    const double *d = style->dash;
    double p = fmod(style->dashoffset, period);
    if (p < 0)
        p += period;
    size_t i = 0;
    for (size_t guard = 0; guard < 2 * m && p > 0 && p >= d[i % style->ndash]; guard++) {
        p -= d[i % style->ndash];
        i = (i + 1) % m;
    }
    *pos = p;
    return i;
}

/* 1 if the pattern is in a dash where a subpath starts. */
static int dash_on_at_start(const aa_stroke_style *style)
{
    size_t m = style->ndash % 2 ? 2 * style->ndash : style->ndash;
    double period = 0, pos;
    for (size_t i = 0; i < m; i++)
        period += style->dash[i % style->ndash];
    return dash_phase(style, period, &pos) % 2 == 0;
}

/* The dashes of one subpath (SVG 2, "dash positions").  On a closed
 * subpath a dash that runs through its start (one from 0 and one to its
 * length) is one dash, joined there; a dash over all of it is the closed
 * subpath. */
static int stroke_dashed(aa_path *out, const piece *p, size_t n, int closed,
                         const aa_stroke_style *style, double h, pieces *tmp)
{
    size_t m = style->ndash % 2 ? 2 * style->ndash : style->ndash;
    const double *d = style->dash;
    double period = 0, total = 0;
    for (size_t i = 0; i < m; i++)
        period += d[i % style->ndash];
    for (size_t i = 0; i < n; i++)
        total += p[i].len;
    if (total / period * (0.5 * (double)m) > DASH_MAX)
        return aa_fail(AA_EINVAL, "stroke: the dash pattern (period %g) makes more than %d dashes "
                                  "on a subpath of length %g",
                       period, DASH_MAX, total);
    double pos;
    size_t i = dash_phase(style, period, &pos);
    double s = 0, rem = fmax(d[i % style->ndash] - fmax(pos, 0), 0);
    double head = -1; /* closed: the end of the dash from 0, held back */
    int st = AA_OK;
    for (long guard = 0; guard < 4L * DASH_MAX && !st; guard++) {
        double e = s + rem, b = fmin(e, total);
        /* a dash from s to b; one of length 0 also at the very end */
        if (i % 2 == 0 && (s < total || (rem == 0 && s == total))) {
            if (closed && s == 0 && b > 0 && head < 0) {
                if (b == total)
                    return stroke_run(out, p, n, 1, style, h);
                head = b;
            } else if (closed && head > 0 && b == total && s < total) {
                tmp->n = 0;
                if (!(st = collect(p, n, s, total, tmp)) && !(st = collect(p, n, 0, head, tmp)))
                    st = stroke_run(out, tmp->p, tmp->n, 0, style, h);
                head = -1;
            } else {
                st = stroke_dash(out, p, n, s, b, style, h, tmp);
            }
        }
        if (e > total)
            break;
        s = e;
        i = (i + 1) % m;
        rem = d[i % style->ndash];
    }
    if (!st && head > 0)
        st = stroke_dash(out, p, n, 0, head, style, h, tmp);
    return st;
}

/* ---- the path ---- */

static int check_style(const aa_stroke_style *st)
{
    if (!(st->width > 0) || !isfinite(st->width))
        return aa_fail(AA_EINVAL, "stroke: width %g is not a positive number", st->width);
    if ((int)st->join < AA_JOIN_MITER || (int)st->join > AA_JOIN_ARCS)
        return aa_fail(AA_EINVAL, "stroke: unknown line join %d", (int)st->join);
    if ((int)st->cap < AA_CAP_BUTT || (int)st->cap > AA_CAP_SQUARE)
        return aa_fail(AA_EINVAL, "stroke: unknown line cap %d", (int)st->cap);
    if (!(st->miterlimit >= 1) || !isfinite(st->miterlimit))
        return aa_fail(AA_EINVAL, "stroke: miter limit %g is not a number >= 1", st->miterlimit);
    if (!isfinite(st->dashoffset))
        return aa_fail(AA_EINVAL, "stroke: dash offset %g is not finite", st->dashoffset);
    if (st->ndash > 0) {
        if (!st->dash)
            return aa_fail(AA_EINVAL, "stroke: %zu dash lengths but no array", st->ndash);
        double sum = 0;
        for (size_t i = 0; i < st->ndash; i++) {
            if (!(st->dash[i] >= 0) || !isfinite(st->dash[i]))
                return aa_fail(AA_EINVAL, "stroke: dash length %zu (%g) is not a finite number "
                                          ">= 0",
                               i, st->dash[i]);
            sum += st->dash[i];
        }
        if (!(sum > 0) || !isfinite(sum))
            return aa_fail(AA_EINVAL, "stroke: the dash lengths add up to %g, not a positive "
                                      "finite length",
                           sum);
    }
    return AA_OK;
}

static double bez_length(const piece *p, double t0, double t1);

/* An elliptical arc: a circle's (|u| = |v| and u . v = 0 to 1e-12
 * relative) is a circular arc, whose offsets are circles; any other is a
 * curve piece on the ellipse B(t) = c + u cos t + v sin t, its parameter
 * made increasing (t -> -t, v -> -v where the arc runs backwards), its
 * length by Gauss-Legendre quadrature (bez_length). */
static int circle_piece(const aa_path_seg *g, size_t k, double px, double py, piece *p)
{
    const double *v = g->p;
    double lu = hypot(v[2], v[3]), lv = hypot(v[4], v[5]);
    if (fabs(lu - lv) > 1e-12 * (lu + lv) || fabs(v[2] * v[4] + v[3] * v[5]) > 1e-12 * lu * lv) {
        memset(p, 0, sizeof *p);
        int back = v[7] < v[6];
        p->bez = 1;
        p->base = AA_OFFSET_ELLIPSE;
        p->x0 = px, p->y0 = py, p->x1 = v[8], p->y1 = v[9];
        p->b[0] = v[0], p->b[1] = v[1], p->b[2] = v[2], p->b[3] = v[3];
        p->b[4] = back ? -v[4] : v[4], p->b[5] = back ? -v[5] : v[5];
        p->t0 = back ? -v[6] : v[6], p->t1 = back ? -v[7] : v[7];
        p->len = bez_length(p, p->t0, p->t1);
        if (!isfinite(p->len))
            return aa_fail(AA_EINVAL, "stroke: segment %zu is out of range", k);
        return AA_OK;
    }
    memset(p, 0, sizeof *p);
    p->arc = 1;
    p->x0 = px, p->y0 = py, p->x1 = v[8], p->y1 = v[9];
    p->cx = v[0], p->cy = v[1], p->ux = v[2], p->uy = v[3], p->vx = v[4], p->vy = v[5];
    p->t0 = v[6], p->t1 = v[7];
    p->r = 0.5 * (lu + lv);
    p->len = p->r * fabs(p->t1 - p->t0);
    return AA_OK;
}

/* A line; of length 0 (dropped) when its ends differ by rounding only, 1e-14
 * of their magnitude or less: its direction would be noise, and its joins
 * with it (a line closing a full circle whose end was computed, say). */
static int line_piece(double x0, double y0, double x1, double y1, piece *p)
{
    memset(p, 0, sizeof *p);
    p->x0 = x0, p->y0 = y0, p->x1 = x1, p->y1 = y1;
    p->len = hypot(x1 - x0, y1 - y0);
    if (p->len <= 1e-14 * (fabs(x0) + fabs(y0) + fabs(x1) + fabs(y1)))
        p->len = 0;
    if (p->len > 0) {
        p->dx = (x1 - x0) / p->len;
        p->dy = (y1 - y0) / p->len;
    }
    return AA_OK;
}

/* A Bezier arc from (px, py) in power basis, as up to three pieces (*n of
 * them; none if all its points are equal).  Where its speed |B'| vanishes
 * the normal is the limit of the normals on either side (SVG 2 takes the
 * direction of the path there from the next distinct control point, or,
 * inside a segment, from the curve itself; the normal line is the same
 * from both sides): at an end (a control point on it) the piece keeps it
 * (bez_stop); inside, at a cusp (B'x and B'y share a root; on a straight
 * arc, where it turns back), the arc is split there into arcs of their
 * own (power bases by the Taylor shift B(ta + (tb - ta) s), the speed at
 * the start of one after the cut set to exactly 0), the later one joined
 * to the earlier with no join, since SVG 2 joins segments only at their
 * boundaries: the stroke there is the union of the normals alone.  A zero
 * of the speed is taken within 1e-12 of the arc's size (the sum of its
 * coefficients' magnitudes); a speed within 1e-9 of it but not 1e-12 is
 * refused, naming it (nearly a cusp: the speed's zero is not known to be
 * one).  A straight arc is stroked as it is, its offsets lines in effect.
 * Lengths are by Gauss-Legendre quadrature (bez_length). */
static double bez_length(const piece *p, double t0, double t1);

/* Whether a Bezier arc's every control point is one of its two ends (and
 * the ends differ): editors write a line so, `C a a b b`.  Such an arc is
 * the segment from a to b, B(t) = a + f(t) (b - a), with f the Bernstein
 * sum of 0 and 1 weights, f(0) = 0, f(1) = 1 and f' >= 0 for every choice
 * (quadratic 0 0 1: 2t; 0 1 1: 2 - 2t; cubic 0 0 0 1: 3t^2; 0 0 1 1:
 * 6t(1 - t); 0 1 0 1: 3(1 - 2t)^2; 0 1 1 1: 3(1 - t)^2), so it is traced
 * once from a to b, by arc length as the line is, and SVG 2's directions
 * at its ends (towards the next distinct control point) are b - a: its
 * stroke is the line's exactly.  Its speed vanishes at both ends of
 * `C a a b b`, where the curvature of the straight arc is rounding's
 * quotient of zeros, so it is given to the stroker as the line it is. */
static int bez_on_ends(const aa_path_seg *g, double px, double py)
{
    int nc = g->op == AA_PATH_QUAD ? 1 : 2;
    double ex = g->p[2 * nc], ey = g->p[2 * nc + 1];
    if (px == ex && py == ey)
        return 0;
    for (int c = 0; c < nc; c++) {
        double x = g->p[2 * c], y = g->p[2 * c + 1];
        if (!((x == px && y == py) || (x == ex && y == ey)))
            return 0;
    }
    return 1;
}

static int bez_piece(const aa_path_seg *g, size_t k, double px, double py, piece out[3], int *n)
{
    piece whole;
    memset(&whole, 0, sizeof whole);
    *n = 0;
    const double *v = g->p;
    double *b = whole.b;
    whole.bez = 1;
    whole.x0 = px, whole.y0 = py;
    if (g->op == AA_PATH_QUAD) {
        whole.x1 = v[2], whole.y1 = v[3];
        for (int c = 0; c < 2; c++) {
            double a = c ? py : px, q = v[c], e = v[2 + c];
            b[4 * c] = a, b[4 * c + 1] = 2 * (q - a), b[4 * c + 2] = a - 2 * q + e;
            b[4 * c + 3] = 0;
        }
    } else {
        whole.x1 = v[4], whole.y1 = v[5];
        for (int c = 0; c < 2; c++) {
            double a = c ? py : px, q = v[c], r = v[2 + c], e = v[4 + c];
            b[4 * c] = a, b[4 * c + 1] = 3 * (q - a), b[4 * c + 2] = 3 * (a - 2 * q + r);
            b[4 * c + 3] = (e - a) + 3 * (q - r);
        }
    }
    whole.t0 = 0, whole.t1 = 1;
    double size = 0;
    for (int j = 1; j < 8; j++)
        if (j != 4)
            size += fabs(b[j]);
    if (!isfinite(size))
        return aa_fail(AA_EINVAL, "stroke: segment %zu is out of range", k);
    if (size == 0)
        return AA_OK; /* all its points equal: of length 0 */
    /* the speed's least values: at the ends and where |B'|^2 (a quartic)
     * turns; a cusp is a double zero of |B'|^2, a sign change of its
     * derivative */
    const double qx[3] = {b[1], 2 * b[2], 3 * b[3]}, qy[3] = {b[5], 2 * b[6], 3 * b[7]};
    double l2[5], t1[5], t2[5], r[4], cut[4];
    pmul(qx, 3, qx, 3, t1), pmul(qy, 3, qy, 3, t2);
    for (int j = 0; j < 5; j++)
        l2[j] = t1[j] + t2[j];
    double dl[4] = {l2[1], 2 * l2[2], 3 * l2[3], 4 * l2[4]};
    int nr = sign_roots(dl, 4, 0, 1, r), ncut = 0;
    double cand[6] = {0, 1};
    for (int j = 0; j < nr; j++)
        cand[2 + j] = r[j];
    for (int j = 0; j < nr + 2; j++) {
        double ux, uy;
        bez_d1(&whole, cand[j], &ux, &uy);
        double sp = hypot(ux, uy);
        if (sp > 1e-12 * size && sp <= 1e-9 * size)
            return aa_fail(AA_EINVAL, "stroke: segment %zu is a Bezier arc whose speed nearly "
                                      "vanishes at t = %.17g (%g, within 1e-9 of its size but "
                                      "not 1e-12): too near a cusp to be drawn exactly",
                           k, cand[j], sp);
        if (j >= 2 && sp <= 1e-12 * size && ncut < 2)
            cut[ncut++] = cand[j];
    }
    double ends[4] = {0};
    ends[ncut + 1] = 1;
    for (int j = 0; j < ncut; j++)
        ends[j + 1] = cut[j];
    for (int j = 0; j <= ncut; j++) {
        piece *p = &out[*n];
        *p = whole;
        if (ncut > 0) {
            /* B(ta + h s) = c0 + s (h B'(ta)) + s^2 (h^2 (b2 + 3 b3 ta)) + s^3 h^3 b3 */
            double ta = ends[j], h = ends[j + 1] - ta;
            for (int c = 0; c < 2; c++) {
                const double *w = b + 4 * c;
                double *o = p->b + 4 * c;
                o[0] = w[0] + ta * (w[1] + ta * (w[2] + ta * w[3]));
                o[1] = j > 0 ? 0.0 : h * (w[1] + ta * (2 * w[2] + 3 * ta * w[3]));
                o[2] = h * h * (w[2] + 3 * ta * w[3]);
                o[3] = h * h * h * w[3];
            }
            if (j > 0) {
                p->nojoin = 1;
                p->x0 = out[*n - 1].x1, p->y0 = out[*n - 1].y1;
            }
            if (j < ncut)
                bez_pt(&whole, ends[j + 1], &p->x1, &p->y1);
        }
        p->len = bez_length(p, 0, 1);
        if (!isfinite(p->len))
            return aa_fail(AA_EINVAL, "stroke: segment %zu is out of range", k);
        ++*n;
    }
    return AA_OK;
}

/* Arc length of b from t0 to t1: 16-point Gauss-Legendre on halves until
 * two levels agree to 1e-15 of the whole (|B'| is analytic where it does
 * not vanish). */
static double gl16(const piece *p, double a, double c)
{
    static const double x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                0.9445750230732326, 0.9894009349916499};
    static const double w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                0.0622535239386479, 0.0271524594117541};
    double m = 0.5 * (a + c), r = 0.5 * (c - a), s = 0;
    for (int k = 0; k < 8; k++)
        for (int sg = -1; sg <= 1; sg += 2) {
            double ux, uy;
            bez_d1(p, m + sg * r * x[k], &ux, &uy);
            s += w[k] * hypot(ux, uy);
        }
    return r * s;
}

/* Adaptive: halves until two levels agree to tol (absolute, halved with
 * each split), at most `*budget` splits in all (then the finer level). */
static double bez_length_rec(const piece *p, double a, double c, double whole, double tol,
                             int *budget)
{
    double m = 0.5 * (a + c), l = gl16(p, a, m), r = gl16(p, m, c);
    if (fabs(l + r - whole) <= tol || --*budget < 0 || !(m > a && m < c))
        return l + r;
    return bez_length_rec(p, a, m, l, 0.5 * tol, budget) +
           bez_length_rec(p, m, c, r, 0.5 * tol, budget);
}

static double bez_length(const piece *p, double t0, double t1)
{
    double whole = gl16(p, t0, t1);
    int budget = 2048;
    return bez_length_rec(p, t0, t1, whole, 1e-15 * fabs(whole), &budget);
}

/* The parameter of Bezier piece p at arc length s from its start (0 < s <
 * len): Newton's method on the length (its derivative the speed), kept in
 * a bracket and bisected where a step leaves it, to 1e-15 of the length. */
static double bez_t_at(const piece *p, double s)
{
    double lo = p->t0, hi = p->t1, t = p->t0 + (p->t1 - p->t0) * (s / p->len);
    for (int it = 0; it < 100; it++) {
        double f = bez_length(p, p->t0, t) - s;
        if (fabs(f) <= 1e-15 * p->len)
            break;
        if (f < 0)
            lo = t;
        else
            hi = t;
        double ux, uy;
        bez_d1(p, t, &ux, &uy);
        double next = t - f / hypot(ux, uy);
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (next == t)
            break;
        t = next;
    }
    return t;
}

/* One subpath done: its pieces (of non-zero length) stroked or dashed, or
 * its dot if it has segments but no length. */
static int flush(aa_path *out, pieces *ps, int drawn, int closed, double px, double py,
                 const aa_stroke_style *style, double h, pieces *tmp)
{
    int st = AA_OK;
    if (ps->n == 0) {
        /* with dashes, only if the pattern starts in a dash */
        if (drawn && (style->ndash == 0 || dash_on_at_start(style)))
            st = stroke_dot(out, px, py, style, h);
    } else if (style->ndash > 0) {
        st = stroke_dashed(out, ps->p, ps->n, closed, style, h, tmp);
    } else {
        st = stroke_run(out, ps->p, ps->n, closed, style, h);
    }
    ps->n = 0;
    return st;
}

/* The pieces of drawing segment k (a line, an arc, a Bezier arc, or a
 * close's line back to the start (sx, sy)) from the pen (*px, *py), which
 * moves to its end: into parts, *np of them (at most 3), those of length 0
 * left out.  The stroke's outline and the path's length walk a path through
 * it alike, so that dashes scaled by a length the walk measured fit the
 * pieces the stroke lays them on. */
static int seg_pieces(const aa_path_seg *g, size_t k, double *px, double *py, double sx,
                      double sy, piece parts[3], int *np)
{
    int st = AA_OK;
    *np = 0;
    switch (g->op) {
    case AA_PATH_LINE:
    case AA_PATH_CLOSE: {
        double ex = g->op == AA_PATH_LINE ? g->p[0] : sx;
        double ey = g->op == AA_PATH_LINE ? g->p[1] : sy;
        if (g->op == AA_PATH_CLOSE && *px == sx && *py == sy)
            return AA_OK;
        line_piece(*px, *py, ex, ey, &parts[0]);
        *px = ex, *py = ey;
        *np = 1;
        break;
    }
    case AA_PATH_ARC:
        if ((st = circle_piece(g, k, *px, *py, &parts[0])))
            return st;
        *px = g->p[8], *py = g->p[9];
        *np = 1;
        break;
    case AA_PATH_QUAD:
    case AA_PATH_CUBIC: {
        double ex = g->op == AA_PATH_QUAD ? g->p[2] : g->p[4];
        double ey = g->op == AA_PATH_QUAD ? g->p[3] : g->p[5];
        if (bez_on_ends(g, *px, *py)) {
            /* its points are on the chord, traced from one end to the
             * other without turning back, its end directions the chord's:
             * the line's stroke, dashes included */
            line_piece(*px, *py, ex, ey, &parts[0]);
            *np = 1;
        } else if ((st = bez_piece(g, k, *px, *py, parts, np))) {
            return st;
        }
        *px = ex, *py = ey;
        break;
    }
    default:
        return aa_fail(AA_EINVAL, "stroke: segment %zu: unknown operation %d", k, (int)g->op);
    }
    int kept = 0;
    for (int j = 0; j < *np; j++) {
        if (!isfinite(parts[j].len))
            return aa_fail(AA_EINVAL, "stroke: segment %zu is out of range", k);
        if (parts[j].len > 0)
            parts[kept++] = parts[j];
    }
    *np = kept;
    return AA_OK;
}

static int outline(const aa_path *in, const aa_stroke_style *style, aa_path *out, pieces *ps,
                   pieces *tmp)
{
    double h = 0.5 * style->width;
    double sx = 0, sy = 0, px = 0, py = 0;
    int drawn = 0, started = 0, st = AA_OK;
    for (size_t k = 0; k < in->n && !st; k++) {
        const aa_path_seg *g = &in->seg[k];
        if (g->op == AA_PATH_MOVE) {
            if (started && (st = flush(out, ps, drawn, 0, sx, sy, style, h, tmp)))
                break;
            sx = px = g->p[0];
            sy = py = g->p[1];
            started = 1;
            drawn = 0;
            continue;
        }
        if (!started)
            return aa_fail(AA_EINVAL, "stroke: segment %zu comes before any move", k);
        piece parts[3];
        int np;
        if ((st = seg_pieces(g, k, &px, &py, sx, sy, parts, &np)))
            break;
        for (int j = 0; j < np && !st; j++)
            st = pieces_push(ps, &parts[j]);
        drawn = 1;
        if (!st && g->op == AA_PATH_CLOSE) {
            st = flush(out, ps, 1, 1, sx, sy, style, h, tmp);
            /* a segment after it starts again from the start (SVG) */
            drawn = 0;
        }
    }
    if (!st && started)
        st = flush(out, ps, drawn, 0, sx, sy, style, h, tmp);
    return st;
}

int aa_path_length(const aa_path *in, double *len)
{
    double sx = 0, sy = 0, px = 0, py = 0, sum = 0;
    int started = 0, st = AA_OK;
    for (size_t k = 0; k < in->n && !st; k++) {
        const aa_path_seg *g = &in->seg[k];
        piece parts[3];
        int np;
        if (g->op == AA_PATH_MOVE) {
            sx = px = g->p[0], sy = py = g->p[1];
            started = 1;
        } else if (!started) {
            return aa_fail(AA_EINVAL, "stroke: segment %zu comes before any move", k);
        } else if (!(st = seg_pieces(g, k, &px, &py, sx, sy, parts, &np))) {
            for (int j = 0; j < np; j++)
                sum += parts[j].len;
        }
    }
    if (!st && !isfinite(sum))
        st = aa_fail(AA_EINVAL, "stroke: the path's length is out of range");
    if (!st)
        *len = sum;
    return st;
}

int aa_stroke_outline(const aa_path *in, const aa_stroke_style *style, aa_path *out)
{
    int st = check_style(style);
    if (st)
        return st;
    if (in == out)
        return aa_fail(AA_EINVAL, "stroke: the outline cannot replace its own path");
    aa_path keep = *out;
    pieces ps = {0}, tmp = {0};
    st = outline(in, style, out, &ps, &tmp);
    free(ps.p);
    free(tmp.p);
    if (st) {
        /* leave `out` as it was: its segments so far (its array may have
         * moved) */
        out->n = keep.n;
        out->penx = keep.penx, out->peny = keep.peny;
        out->startx = keep.startx, out->starty = keep.starty;
        out->open = keep.open;
    }
    return st;
}
