/*
 * area.c: exact area sampling, the box filter integrated in closed form
 * (Catmull 1978, "A hidden-surface algorithm with anti-aliasing": the
 * average visible intensity over the pixel's square, "The pixel
 * integrater", fig. 1; Crow 1976, ch. 3, "Implementation of a tiler":
 * "Left Areas - Right Areas = Area", fig. 3.13).
 *
 * Rows.  The scene is walked one pixel row, the band [j, j+1], at a time.
 * Along any line of the band the colour is a step function of x that
 * changes only at the pieces' crossings, so a pixel's value is Crow's
 * signed sum: the colour at its left plus, for every piece, the colour jump
 * across the piece times the area of the pixel right of it (fig. 3.13, with
 * colour jumps in place of his +1 for left edges and -1 for right edges).
 * While no two pieces cross and none ends inside the band, the order of the
 * crossings along x is the same on every line of the band, so each piece's
 * jump is one constant: the colour difference of the winding numbers on its
 * two sides, front layers hiding those behind, fill rules applied.  The sum
 * is then exact for any number of layers and any winding numbers.  As in
 * FreeType's smooth rasterizer, a piece adds `area` to the cells it crosses
 * and `cover` (its height) to the cell after, resolved late in one sweep.
 *
 * Clusters.  The band's pieces, in x order, link the cells they touch into
 * clusters; between clusters no piece is met, the colour is constant and
 * known exactly from the winding numbers, and those pixels are filled
 * without integration.  Each cluster restarts from an exact colour: no
 * running sum across the row, flat pixels come out exactly, rounding cannot
 * build up.  The common cluster, one piece spanning the band through one or
 * two cells, writes its pixels directly.
 *
 * Arcs are integrated exactly.  Each piece is expanded about its point on
 * the line y = ja (ja a multiple of ANCHOR_ROWS, fixed, so no result
 * depends on the rows a thread did before), in extended precision from its
 * control points: at 4096 px an absolute coordinate's last bit is 5e-13 px.
 * Everything after that is in cell-local coordinates, u = x - cell and
 * v = y - row, and tau, the Bezier parameter from that point; a quadratic's
 * Taylor form is exact, and u stays within ANCHOR_ROWS times the slope.
 * Over a part of an arc inside one cell, tau from tau_a to tau_a + d, the
 * area of the cell right of it is
 *
 *     dy (1 - (u_a + u_b)/2) + d^3 (y' x'' - x' y'') / 12,
 *
 * the trapezoid under the chord plus the parabolic segment between chord
 * and arc (two thirds of its control triangle, Archimedes); y' x'' - x' y''
 * is one constant along a parabola, and dy = d (y'(tau_a) + ay d): no term
 * is large, so nothing cancels (difference forms throughout).  Pieces whose
 * y is quadratic in t (general arcs, x(y) with a square root) need no
 * special case: every integral is a polynomial in tau.
 *
 * Cubic arcs the same way: the Taylor form about T is exact with a cubic
 * term (cx3, cy3); the segment between chord and arc is, by Green's
 * theorem, half the integral of P x P' with P(s) = s a1 + s^2 a2 + s^3 a3
 * from the part's start, a1xa2 d^3/6 + a1xa3 d^4/4 + a2xa3 d^5/10 (a1, a2
 * the first two Taylor coefficients there, a3 the cubic's), subtracted
 * from the trapezoid as the parabola's is added (the same sign: for a
 * parabola it is d^3 (x' y'' - y' x'')/12).  A cubic has up to two x
 * extrema (te, te2) between which x is monotone; its parameter on a band
 * line or a cell side is the root of a monotone cubic, found by Newton's
 * method from the neighbouring root (area_cubic_near: a second-order step
 * along the curve from the line above), kept in the bracket, stopped when
 * the error left, at most max |f''/2| over the step times step^2 over f',
 * is below 2^-54 of the bracket (else the bracketed search,
 * area_cubic_root).  Where a
 * cubic meets another piece in a cluster, the band is cut at the heights
 * aa_piece_meet gives (polished to full precision).  The guess for a band
 * line comes from the anchor alone (the series of the inverse), so the
 * image does not depend on the rows a thread did before.  Measured on
 * crow's arcs raised to cubics at 1024x1024, one thread: area/point 1.37,
 * 1.47 on 48 stripes of S-shaped cubics, where crow measured 1.47 to 1.49
 * in the same runs (tests/bench_curves.c).
 *
 * Conic pieces (arcs of ellipses, AA_PIECE_CONIC: y = ey - er cos s,
 * x = ex + ea cos s + eb sin s, s rising from s0 to s1 in [0, pi]) the
 * same way, in the half-angle tangent about an anchor: the ellipse at
 * s = A, the middle angle of the piece's part in the anchor's rows, in
 * extended precision, and with tau = s - A, q = tan(tau/2) (|q| <= 1 on
 * those rows), sin tau = 2q/(1 + q^2) and 1 - cos tau = 2q^2/(1 + q^2):
 *
 *     u = U + 2q (g + ax q)/(1 + q^2),   v = Va + 2q (vy + ay q)/(1 + q^2),
 *
 * (g, vy) = P'(A) and (ax, ay) = -(P(A) - centre) (from cos(A + tau) =
 * cos A - cos A (1 - cos tau) - sin A sin tau), every term small near the
 * anchor, no trigonometry per row.  A band line or a cell side is then met
 * where a quadratic in q vanishes ((c + 2 ay) q^2 + 2 vy q + c for
 * v = Va - c), solved in the form without cancellation as a parabola's.
 * The ellipse is the image of the unit circle under the map (ea eb;
 * -er 0), of determinant eb er, and a circle's segment between chord and
 * arc over an angle d is (d - sin d)/2, so the area right of a part from
 * q_a to q_b in a cell is
 *
 *     dy (1 - (u_a + u_b)/2) - eb er (d - sin d)/2,
 *
 * with d = 2 atan p, p = (q_b - q_a)/(1 + q_a q_b), d - sin d =
 * 4p^3/3 - 8p^5/5 + ... (its series below p = 1/8), and the chord's
 * height dy = 2 (q_b - q_a) (vy (1 - q_a q_b) + ay (q_a + q_b)) /
 * ((1 + q_a^2)(1 + q_b^2)): no cancellation.  The segment lies left of the
 * arc's direction when eb er > 0, as for the parabola (whose d^3 (x' y'' -
 * y' x'')/12 is its limit).  x turns at most once on a piece, where
 * g q^2 - 2 ax q - g = 0 (the root of modulus <= 1): the part is split
 * there, as a parabola's.  Where a conic meets another piece in a cluster
 * the band is cut at the heights aa_piece_meet gives, as for cubics, but
 * for two conics: one, N(q)/(1 + q^2), put into the other's implicit
 * equation gives a quartic in q whose sign changes over the band
 * poly_roots finds (conic_crossings); arcs of one ellipse meet only at
 * their ends and are not asked (same_ellipse).  A
 * conic's ends come from its angle, off its exact end points by rounding,
 * so its extent in a band also holds those points: pieces that meet on a
 * cell's side (a circle centred on a pixel corner) then link their
 * clusters.  Measured (tests/test_area_conic.c): disks, a turned ellipse,
 * an annulus, half disks and a disk behind a square within 4e-15 a pixel
 * of the closed form (the disc inside a polygon), a disk of radius
 * 1500 px at 4096 px within 1e-14, two crossing disks within 3.4e-15 of
 * Green's theorem, pie slices within 3.2e-15, 200 random ellipses within
 * 5.4e-15; the quartic's crossings agreed with aa_piece_meet's in number
 * on every pair of 64 crossing ellipses at 1024x1024 and within 1.3e-12 px
 * in height (a cut's error costs its square).  Speed, area/point at
 * 1024x1024, one thread (tests/bench_curves.c): 2.1 on 200 concentric
 * circles, 2.2 on 256 disks, 2.8 on 64 crossing ellipses, crow 1.5 in the
 * same runs.
 *
 * Offset pieces (AA_PIECE_OFFSET: the offset curves and evolutes of Bezier
 * arcs in a stroke's outline, harness/core/offset.c) by quadrature with a
 * proven bound, not in closed form: their coordinates carry 1/|B'|, and
 * the area under them is an elliptic integral.  Their "tau" is the curve's
 * parameter t (times -1 where the piece runs up, so that tau rises down
 * it); a band line or a cell side is met where a coordinate of the curve,
 * monotone there, equals it (aa__offset_solve_from: Newton in double, then
 * in long double, bracketed; on a cubic's offset without stops, nearly
 * every piece, the second phase on its value evaluated as double-double
 * sums, in double: offset.c, aa__offset_fix_dd), x turns where
 * aa__offset_turns says, and u
 * and v are the curve's point in extended precision less the cell and the
 * band, but at the piece's ends, which are its own (x0, y0) and (x1, y1):
 * the outline's vertex, rounded to double, that the next piece ends at
 * (area_internal.h, offset_point).  The area right of a part is the
 * trapezoid under its chord less the segment between chord and arc, 1/2 the integral of (P - Pa) x P',
 * by Gauss-Legendre quadrature with an error of at most AR_QUAD_TOL
 * (1e-15 px^2) for each panel of the piece that the part meets, proven
 * from the integrand's bound on a disc about the panel (Trefethen's bound
 * for analytic integrands; area_offset.c's header has the derivation).
 * Where an offset piece meets another piece in a cluster the band is cut
 * at the heights aa_piece_meet gives, as for cubics.  Measured
 * (tests/test_area_offset.c): within 1.3e-14 a pixel of the box reference
 * on strokes of a gentle arc, tight arcs whose offsets fold, a loop, a
 * hook, three arcs with round joins and caps, square-capped dashes and a
 * sheared map; the tube formula (width x arc length, the length by GSL)
 * within 1.4e-17.  Speed: on 1,000 stroked cubics at 1024x1024, one thread
 * (tests/bench_bezstroke.c), area/point 2.79 by instructions (callgrind:
 * area 296 M a render, point 106 M), in CPU time 3.43 to 3.67 (three runs
 * on the shared machine at a load of about 4.5; area 55 to 75 ms, point
 * 16 to 21 ms): the crossings' root-finding (Newton
 * on the curve; the band lines and the heights inside a band started
 * from a table of t(y) made once a piece, load_ytab; a cell's side from
 * the chord's root, offset_tau_u) is 33% of area's instructions (the band
 * lines' 15%), the quadrature 19% (a cubic's nodes four at a time with
 * AVX),
 * the meetings of pieces in a cluster 12% (aa__piece_meet_at, given the
 * band's parameters of both segs, and where a piece begins or ends inside
 * the band the other's there, kept in its seg, seg_t_common: the pieces
 * of a stroke's overlapping
 * contours cross near every join; pairs running side by side are decided
 * by their slopes, scene_piece.c; polishing a meeting 3%, stopped by its
 * error estimate), sorting 1% (the
 * active list kept in the last row's x order, keep_order).
 * Each end of a part is evaluated once, for u and v together (seg_u,
 * part_area: the seg's memo of v, offset_keep), and some not at all: a
 * band's top takes v from the y its line's root had as the band above's
 * bottom, and a cell's side (and an order's key its u) from its root's
 * last evaluation (105 k long double evaluations a render where there
 * were 216 k).  Not yet within
 * the factor of 2 of other scenes (algorithms/README.md says where the
 * time goes).
 *
 * Translucent layers, groups of opacity, clips.  In such a scene the colour
 * at a point is the layers covering it composited back to front in
 * sRGB-encoded values, each group on its own first, a clipped layer
 * covering only inside its clip, the result decoded to linear light
 * (patterns/README.md).  That is still a function of the winding numbers
 * of every layer (clip members included), so the picture is still
 * constant between the crossings and everything above holds with the
 * colour of a winding state being the scene's own composite,
 * aa_scene_colour_of: the function the reference colours its regions by,
 * not a second compositor.  It depends on the state only through the set
 * of layers whose fill rule holds; each worker keeps the colours of the
 * sets it met (AR_CACHE_ENTRIES of them, emptied when full) keyed by that
 * set, and hands out copies from a small ring (colour_of's pointers stay
 * valid for the next AR_RING - 1 calls; the rows hold at most two;
 * area_composite.c).  In Catmull's integrater no layer hides the edges of
 * those behind it, so a pixel is split on every edge until a region holds
 * none, whose winding numbers at its centroid give its colour (its own
 * form, area_composite.c, chosen per cluster: the opaque scenes' form is
 * compiled as it was).  Opaque unclipped scenes take the path they always
 * took: colour_of scans for the front-most covering layer, and asks
 * whether the scene composites only where it scanned none (in a scene that
 * composites it scans none).  Instructions in area_render by callgrind, one
 * thread, 1024x1024, before and after: crow 48.54 and 48.77 million
 * (+0.48%), and on the other scenes of the vector suite +0.1% to +0.3%
 * (abut.svg +0.17%, shapes.svg +0.21%, strokes.svg +0.17%, text at 24 ppem
 * +0.17%).  Measured (tests/test_area_composite.c):
 * half-opacity and overlapping translucent rectangles, groups over
 * overlapping children, nested groups, a clipped disk, clips clipped in
 * turn and by an even-odd clip, every pixel within 3.2e-15 of the closed
 * form; on the SVG scenes of tests/test_svg_clip.c and test_opacity.c and
 * the shipped clips.svg within 2.9e-15 of the reference.
 *
 * Linear gradients (area_gradient.c, whose header has the derivation).  The
 * colour then varies inside a region, so no colour jump is constant and
 * the rows above do not apply: a scene with gradient paint takes rows of
 * its own (render_row_gradient), the clusters found as the sorted pass
 * finds them, every cluster by Catmull's integrater split on every edge
 * and every pixel between clusters as one region, its square.  On a
 * region the covering layers are fixed and the encoded composite is K0 +
 * K1 o + K2 o c in the gradient layer's paint (read from the scene's
 * compositor), affine in t between the stops; the integral of its sRGB
 * decoding over the region is, by Green's theorem, a sum over the
 * region's edges of closed forms in powers 3.4 and 4.4 of the shifted
 * value, cut at the stops, the spread's turns and the decoding's threshold
 * 0.04045, with a series where the value hardly changes along an edge.
 * Measured (tests/test_area_gradient.c): a black-to-white ramp over a
 * whole pixel within 1e-14 of the integral of the decoding written out
 * by hand (2.8e-16 off), and over three pixels and at half opacity; pad,
 * reflect, repeat, several stops, a sharp step, stop opacity,
 * gradientTransform rotated and skewed, both gradient units, a gradient
 * over and under flat translucent layers, in a group of opacity, under a
 * clip and on self-intersecting polygons: within 3.6e-15 of the exact
 * reference; 24 triangles, flat, translucent and gradient, over a repeated
 * gradient at 48x40 within 6.8e-14 (the reference's bounds on such scenes
 * are of that order: 3.4e-14 on the speed scene below).  Speed: 40 flat triangles and 4 gradient ones over a
 * repeated gradient (the crowded scene's kind), one thread, callgrind, one
 * render against three: area 776 M instructions a render at 256x256,
 * point 107 M (7.3 times); thread CPU time at 512x512, medians of 7 on a
 * machine at a load of 12: area 0.333 s, point 0.050 s.  Most of it is the
 * pixels between clusters, each its own square of four edges walked per
 * channel (pow, expm1 and log1p a piece); the reference took 45 s of
 * wall time at 512x512 on two threads.  Refused, each by name (a refusal, never an approximation):
 * radial gradients, gradients in scenes with curved pieces, a gradient
 * whose colour and opacity change between the same two stops, and a pixel
 * where two gradients show one over the other.
 *
 * Hidden surfaces.  Clusters where pieces cross, or end inside the band
 * (vertices, flat edges), need the per-pixel treatment Catmull describes
 * ("A correct solution for this filter requires a hidden-surface algorithm
 * at each pixel!"):
 *
 *  - integrator=catmull (the default), clusters of lines: each pixel goes
 *    to Catmull's recursive pixel integrater.  Split the pixel by the line
 *    of an edge of the front-most layer that still has edges inside the
 *    region, clip every edge into the two halves (the clipper of his
 *    "Clipping" section), recurse on both; a region in which the front
 *    layer has no edge left is wholly inside it (it hides everything behind:
 *    return its colour times the area) or wholly outside (go on with the
 *    layers behind); in a scene that composites, on every edge (above).
 *    His polygons are here the layers' regions under their fill rules: the
 *    winding numbers at the region's centroid decide inside or outside, so
 *    self-overlapping paths and holes need no polygon set operations.
 *    Horizontal edges take part as splitters.
 *  - clusters with arcs (and every cluster with integrator=bands): the
 *    cluster's band is cut at every vertex and every crossing of two pieces
 *    into sub-bands with a fixed order along x, each summed as above.  This
 *    is exact, not an approximation (no flattening): an arc meets a line
 *    where a quadratic in t vanishes, and another arc where a quartic does
 *    (the arc substituted in the other's implicit parabola), whose roots are
 *    isolated between those of its derivatives and bisected to full
 *    precision.
 *
 * Speed (crow 1024x1024 box, one core; see the measurements in the
 * comments at each choice): lines and quadratics, the common path, test
 * one flag (curved) in the piece's first cache line and keep part_area,
 * line_tau and u_at inline, the cubic, conic and offset cases out of line
 * (area/point 1.40 in thread CPU time, 21 renders of each taking turns,
 * medians of three runs 1.39 to 1.41, against 1.60 to 1.67 when each call
 * tested those cases on the piece's later cache lines).  A scene with no
 * curved piece at all (crow, polygons: ar_state.plain) takes a form of the
 * rows compiled without those cases, chosen once a row (render_row_plain:
 * no curved tests per piece, no out-of-line seg_u for the band's bottom,
 * no second x extremum), with the common cluster and the fill of the run
 * before it inline in the row and colour_of's test of a layer one mask; the
 * same arithmetic, so the same image bit for bit.  Instructions in
 * area_render (callgrind, one render against three, one thread): 48.77 M
 * a render before, 35.29 M after, point 36.10 M (area/point 1.35 to 0.98);
 * thread CPU time area/point 1.31 to 1.38 before and 1.02 to 1.10 after
 * (three runs of each build taking turns, medians of 21 renders, a load of
 * 15: tests/bench_analytic.c --cpu 21).  The per-row order
 * of the active list is kept,
 * so for most scenes the pieces arrive in x order and clusters are written
 * as they close, with a sorted pass only when a piece comes out of order;
 * one extended-precision expansion per piece every ANCHOR_ROWS rows, and
 * the tau and u of a band's bottom reused as the next band's top; fills in
 * whole 16-byte stores; non-temporal stores for images over STREAM_BYTES;
 * each thread's workspace on cache lines of its own.  Rows are shared out
 * by OpenMP in blocks.  Workspaces are made in init, O(width + pieces) per
 * thread; nothing is allocated while rendering.  Every sort breaks ties by
 * piece index and every row depends only on the scene, so the image is
 * bit-identical for any thread count.
 *
 * Counters: samples = 0 (no point of the scene is sampled);
 * expensive_pixels = the pixels some piece touches (integrated, by the cell
 * sweep or a pixel integrater), the others being filled; in a scene with
 * gradient paint also the pixels between clusters where a gradient shows
 * (each integrated over its square).
 *
 * Known answers (tests/test_area.c): Catmull's fig. 1 pixel is
 * (0, 0.25, 0.5); `crow` 256x256 equals the box reference within 1e-9 (in
 * practice 2e-15; 2e-14 at 4096 px wide).  Conics: tests/test_area_conic.c
 * (above).
 *
 * Limits.  The box filter only: tent and gauss are refused; of gradient
 * paint only linear gradients over straight edges (above).  Results carry rounding, about 1e-15 per pixel at 256
 * px and 1e-14 at 4096 px, and are clamped to [0, 1].  Catmull's
 * integrater takes polygons only; where arcs meet other edges in a pixel
 * the bands do the work, exactly, except that crossings closer than
 * CROSS_MARGIN (1e-12 px, in y) to a vertex or to the band's edge are not
 * split (an error below 1e-24), and arcs that touch
 * without crossing are not split (their order does not change).  In
 * Catmull's integrater edges within CM_EPS (1e-14 px) of a splitting line
 * count as lying on it.  A pixel with more than CM_MAX_EDGES edges goes to
 * the bands instead; a cluster's crossings are gathered up to
 * CM_MAX_EVENTS_GROWN (1,048,576) at a time (bounded memory, more passes
 * beyond).  Coordinates beyond 2^30 px lose
 * precision.  Whether a cluster's pieces cross is asked of every pair
 * whose extents overlap, or, in a cluster of more than AR_CROWD pieces, of
 * neighbours along x at mid-band only (a row of 65536 arcs 0.01 px apart:
 * 65535 tests where the pairs were 4e9).  Crossings inside a cluster with
 * vertices are found pair by pair among pieces whose extents overlap, and
 * its sub-bands each sweep all its pieces: a cluster crowded with both
 * vertices and pieces (feibush with 65536 stripes, along its top and
 * bottom edges) costs their product.  Two conics' crossings are the sign
 * changes of a quartic: where two ellipses touch without crossing they are
 * not split (as for parabolas); a root on the other half of the second
 * ellipse is told apart by the sign of its sin s with a margin of 1e-9
 * (such roots lie near that ellipse's top or bottom, a piece's end).  Two
 * pieces of one ellipse drawn twice (coincident arcs) have no order to
 * keep and are not split.  Offset pieces: each panel's quadrature error is
 * proven up to the rounding of the bound's own terms; a piece whose speed
 * or curvature (an evolute) is within rounding of 0 is refused, naming it
 * (area_offset.c).
 */
#include "core.h"
#include "methods.h"
#include "area_internal.h"

#include <float.h>
#include <gsl/gsl_poly.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { P_INTEGRATOR };
enum { INT_CATMULL, INT_BANDS };

static const aa_param area_params[] = {
    {"integrator", AA_PARAM_CHOICE, INT_CATMULL, 0, 0, 0, "catmull|bands",
     "pixels where edges cross or end: Catmull's recursive pixel integrater (polygons; "
     "arcs use bands) or exact y-bands everywhere"},
    {0}};

/* ------------------------------------------------------------------------
 * Small helpers
 * ------------------------------------------------------------------------ */

/* tau where u(tau) = k on a part where u' has sign `sg` (+1 or -1); for a
 * cubic, inside that part [lo, hi]. */
static inline double tau_of_u_in(const ar_seg *s, double k, double sg, double lo, double hi,
                                 double ul, double uh)
{
    if (s->p->offset) /* x = c0 + k */
        return offset_tau_u(s, lo, hi, ul - k, (double)s->c0 + k, ul, uh);
    /* the guess: the chord from lo to hi (ul, uh: u there) */
    double g = uh != ul ? lo + (hi - lo) * ((k - ul) / (uh - ul)) : 0.5 * (lo + hi);
    if (sg > 0.0)
        return area_cubic_near(s->U - k, s->g, s->ax, s->cx3, lo, hi, g);
    return area_cubic_near(k - s->U, -s->g, -s->ax, -s->cx3, lo, hi, g);
}

/* tau where u(tau) = k on a part where u' has sign `sg` (+1 or -1), on a
 * line or a quadratic (tau_of_u_quad) or a conic.  For a conic, q where
 * u(q) = k: (K + 2 ax) q^2 + 2 g q + K = 0 (K = U - k), whose derivative
 * there has the sign of u' (u (1 + q^2) - k (1 + q^2) has derivative
 * u' (1 + q^2) where u = k). */
static inline double tau_of_u_quad(const ar_seg *s, double k, double sg)
{
    double c = s->U - k, g = s->g;
    double disc = g * g - 4.0 * s->ax * c, q = sqrt(disc > 0.0 ? disc : 0.0);
    if (sg * g > 0.0 || s->ax == 0.0)
        return -2.0 * c / (g + sg * q);
    return (-g + sg * q) / (2.0 * s->ax);
}

static inline double tau_of_u(const ar_seg *s, double k, double sg)
{
    if (s->p->curved && s->p->conic) {
        double c = s->U - k, g = s->g;
        double a = c + 2.0 * s->ax, disc = g * g - c * a, q = sqrt(disc > 0.0 ? disc : 0.0);
        double den = g + sg * q;
        if ((sg * g > 0.0 || a == 0.0) && den != 0.0)
            return -c / den;
        return a != 0.0 ? (-g + sg * q) / a : 0.0;
    }
    return tau_of_u_quad(s, k, sg);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

/* Ascending, v[0..n) none NaN: an insertion sort where there are few
 * (a band's events: qsort's calls through its comparison were most of
 * their sort), else qsort.  Equal values are equal bits (no -0: the events
 * are positive), so the result is the same either way. */
static void sort_doubles(double *v, size_t n)
{
    if (n > 32) {
        qsort(v, n, sizeof *v, cmp_double);
        return;
    }
    for (size_t a = 1; a < n; a++) {
        double x = v[a];
        size_t at = a;
        for (; at > 0 && v[at - 1] > x; at--)
            v[at] = v[at - 1];
        v[at] = x;
    }
}

/* a after b in the order by (key, id) */
static inline int key_after(const ar_key *a, const ar_key *b)
{
    return a->key != b->key ? !(a->key < b->key) : a->id > b->id;
}

/* Heapsort by (key, id), in place: what sort_keys falls back to.  In place
 * (no workspace: sort_keys sorts several of the worker's buffers) and with
 * the comparison inline, where qsort's merge sort called its comparison
 * through a pointer: the rows of a stroke scene, whose pieces arrive far out of x
 * order, took it in most rows (three fifths of sort_keys' instructions there;
 * the heapsort takes seven tenths of its instructions). */
/* v put into the heap k[0 .. n) at its hole `at`, moved down past the
 * larger of its children while they come after it. */
static inline void sift_down(ar_key *k, size_t at, size_t n, ar_key v)
{
    size_t c;
    while ((c = 2 * at + 1) < n) {
        if (c + 1 < n && key_after(&k[c + 1], &k[c]))
            c++;
        if (!key_after(&k[c], &v))
            break;
        k[at] = k[c];
        at = c;
    }
    k[at] = v;
}

static void heap_keys(ar_key *k, size_t n)
{
    for (size_t top = n / 2; top-- > 0;) /* heapify: largest at k[0] */
        sift_down(k, top, n, k[top]);
    for (size_t end = n; end-- > 1;) { /* move the largest behind the heap */
        ar_key v = k[end];
        k[end] = k[0];
        sift_down(k, 0, end, v);
    }
}

/* k[0..n) sorted by (key, id) by insertion within `budget` moves: 1 if
 * sorted, 0 (k still a permutation of its keys) if the budget ran out. */
static inline int insert_keys(ar_key *k, size_t n, size_t budget)
{
    size_t moves = 0;
    for (size_t a = 1; a < n; a++) {
        ar_key v = k[a];
        size_t at = a;
        while (at > 0 && key_after(&k[at - 1], &v)) {
            k[at] = k[at - 1];
            at--;
            if (++moves > budget) {
                k[at] = v;
                return 0;
            }
        }
        k[at] = v;
    }
    return 1;
}

/* Sort by (key, id): a total order, so the result does not depend on the
 * starting order.  Insertion sort (the common input is nearly sorted),
 * heapsort past a budget of moves. */
static void sort_keys(ar_key *k, size_t n)
{
    if (!insert_keys(k, n, 8 * n + 64))
        heap_keys(k, n);
}

/* ------------------------------------------------------------------------
 * Roots of a polynomial of degree <= 4 on (0, 1) where it changes sign
 * ------------------------------------------------------------------------ */

static double poly_eval(const double *c, int d, double s)
{
    double r = c[d];
    for (int k = d - 1; k >= 0; k--)
        r = r * s + c[k];
    return r;
}

/* Ascending roots in (0, 1) at which the sign changes: a touching root
 * (even multiplicity) is no crossing and is not reported. */
static int poly_roots(const double *c, int d, double *r)
{
    while (d > 0 && c[d] == 0.0)
        d--;
    if (d == 0)
        return 0;
    if (d == 1) {
        double s = -c[0] / c[1];
        if (s > 0.0 && s < 1.0) {
            r[0] = s;
            return 1;
        }
        return 0;
    }
    if (d == 2) {
        double disc = c[1] * c[1] - 4.0 * c[2] * c[0];
        if (!(disc > 0.0))
            return 0;
        double q = -0.5 * (c[1] + copysign(sqrt(disc), c[1]));
        double s[2] = {q / c[2], q != 0.0 ? c[0] / q : 0.0};
        if (s[0] > s[1]) {
            double t = s[0];
            s[0] = s[1], s[1] = t;
        }
        int n = 0;
        for (int k = 0; k < 2; k++)
            if (s[k] > 0.0 && s[k] < 1.0)
                r[n++] = s[k];
        return n;
    }
    /* isolate: between consecutive sign changes of the derivative the
     * polynomial is monotone, so bisection finds each crossing */
    double dc[4] = {0, 0, 0, 0}, crit[4];
    for (int k = 0; k < d; k++)
        dc[k] = (k + 1) * c[k + 1];
    int m = poly_roots(dc, d - 1, crit), n = 0;
    double a = 0.0, fa = poly_eval(c, d, 0.0);
    for (int k = 0; k <= m; k++) {
        double b = k < m ? crit[k] : 1.0, fb = poly_eval(c, d, b);
        if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
            double lo = a, hi = b, flo = fa;
            for (int it = 0; it < 200; it++) {
                double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi)
                    break;
                double fm = poly_eval(c, d, mid);
                if ((fm < 0.0) == (flo < 0.0) && fm != 0.0)
                    lo = mid, flo = fm;
                else
                    hi = mid;
            }
            r[n++] = 0.5 * (lo + hi);
        }
        a = b, fa = fb;
    }
    return n;
}

/* ------------------------------------------------------------------------
 * A piece in the band
 * ------------------------------------------------------------------------ */

/* d - sin d for the angle d = 2 atan p, without cancellation: with
 * 2 atan p = 2 (p - p^3/3 + ...) and sin d = 2p/(1 + p^2) = 2 (p - p^3 +
 * ...), d - sin d = sum over k >= 1 of (-1)^(k+1) 4k/(2k+1) p^(2k+1); its
 * first ten terms below |p| = 1/8 (the next is below 2^-59 of the sum),
 * the difference itself above (where it loses at most 7 bits of a
 * segment below 1 px^2 in a cell). */
static inline double d_minus_sin_half(double p)
{
    if (fabs(p) >= 0.125)
        return 2.0 * atan(p) - 2.0 / (p + 1.0 / p);
    double z = p * p;
    return p * z *
           (4.0 / 3 -
            z * (8.0 / 5 -
                 z * (12.0 / 7 -
                      z * (16.0 / 9 -
                           z * (20.0 / 11 -
                                z * (24.0 / 13 -
                                     z * (28.0 / 15 -
                                          z * (32.0 / 17 - z * (36.0 / 19 - z * (40.0 / 21))))))))));
}

/* A conic's angle s where y(s) = y, in closed form (aabench.h: y = ey -
 * er cos s): 2 asin(sqrt((1 - c)/2)) near the top, pi - 2 asin(sqrt((1 +
 * c)/2)) past the middle, with 1 -+ c from differences in extended
 * precision, so no bits are lost at the ellipse's top and bottom. */
static double conic_s_at(const aa_piece *q, double y)
{
    long double top = ((long double)y - ((long double)q->ey - q->er)) / q->er;
    if (top <= 1.0L) {
        double h = (double)(0.5L * top);
        return 2.0 * asin(sqrt(h > 0.0 ? h : 0.0));
    }
    double h = (double)(0.5L * (((long double)q->ey + q->er) - y) / q->er);
    return M_PI - 2.0 * asin(sqrt(h > 0.0 ? (h < 1.0 ? h : 1.0) : 0.0));
}

/* A conic about its point at the middle angle of its part in the anchor's
 * rows [ja, ja + ANCHOR_ROWS + 1] (so that |s - ang| <= pi/2 there, |q| <=
 * 1): the ellipse there in extended precision, then (ar_seg) u and v as
 * rational functions of q = tan((s - ang)/2), from cos(ang + tau) =
 * cos ang - cos ang (1 - cos tau) - sin ang sin tau and the like.  Its
 * ends' q by the band lines' closed form.  The x extremum: u'(q) = 0 where
 * g q^2 - 2 ax q - g = 0, the root of modulus <= 1 (the other is the same
 * point of the ellipse's other half turn, tau + pi). */
static void expand_conic(ar_seg *a, const ar_piece *p, int ja)
{
    const aa_piece *q = p->src;
    double ylo = ja, yhi = ja + ANCHOR_ROWS + 1.0;
    double sa = p->y0 >= ylo ? q->s0 : conic_s_at(q, ylo);
    double sb = p->y1 <= yhi ? q->s1 : conic_s_at(q, yhi);
    sa = sa < q->s0 ? q->s0 : (sa > q->s1 ? q->s1 : sa);
    sb = sb < sa ? sa : (sb > q->s1 ? q->s1 : sb);
    double A = 0.5 * (sa + sb);
    long double cA = cosl(A), sA = sinl(A), ea = q->ea, eb = q->eb, er = q->er;
    long double X = q->ex + (ea * cA + eb * sA), Y = ((long double)q->ey - ja) - er * cA;
    double c0 = floor((double)X);
    c0 = c0 < -CELL_LIMIT ? -CELL_LIMIT : (c0 > CELL_LIMIT ? CELL_LIMIT : c0);
    a->p = p;
    a->ja = ja;
    a->c0 = (int)c0;
    a->U = (double)(X - c0);
    a->Va = (double)Y;
    a->g = (double)(eb * cA - ea * sA);
    a->vy = (double)(er * sA);
    a->ax = (double)-(ea * cA + eb * sA);
    a->ay = (double)(er * cA);
    a->cx3 = a->cy3 = 0.0;
    a->ivy = 0.0;
    a->k6 = p->k6;
    a->t0 = p->y0 >= ylo ? conic_q_of_v(a, a->Va - (p->y0 - ja)) : -INFINITY;
    a->tend = p->y1 <= yhi ? conic_q_of_v(a, a->Va - (p->y1 - ja)) : INFINITY;
    double R = hypot(a->g, a->ax);
    a->te = R > 0.0 ? -a->g / (a->ax + copysign(R, a->ax)) : INFINITY;
    a->te2 = INFINITY;
    a->mline = INT_MIN;
}

/* A band line's start on an offset piece.  The line's root is sought on
 * the whole piece (offset_line_t: a function of the piece and the line
 * alone); from the piece's ends (the quadratic through the top's value
 * and the bottom's value and slope) the double phase took 2.69
 * evaluations a root on tests/bench_bezstroke.c's scene, where one
 * suffices from a start within about 1e-6 of the root.  The start comes
 * from a table made once a piece (load_ytab): nodes (t, y, dt/dy) along
 * it, y and its slope in double as the solver evaluates them
 * (aa__offset_end), between which t(y), the inverse of a coordinate
 * monotone on the piece, is the cubic Hermite form through both nodes'
 * values and slopes (yt_herm).  An interval is halved until the form at
 * its middle's y is within YT_TOL of the middle's t (the middle then kept
 * as a node too: the halves' forms are about 16 times closer), at most
 * YT_DEPTH times, and from YT_MIN halvings on not where an end's dt/dy
 * is over YT_TURN times the chord's (y turning at the piece's end, dt/dy
 * infinite there, where no halving brings the form within YT_TOL); an
 * interval left not within it is marked, and its lines start from the
 * root of y(t)'s Hermite form through its two nodes (area_internal.h,
 * yt_turn: exact where y is quadratic, as by a turn; from the piece's
 * ends before).  The heights inside a band (tau_of_v, key_u) start from
 * the table too.  Only the start: the bracket is the same and the root
 * Newton's, so a poor start costs steps, not accuracy.  A node is 4
 * doubles: t, y, dt/dy, and 1 where the interval ending at it is within
 * YT_TOL (0 at the first).  On tests/bench_bezstroke.c's scene at 1024 px
 * (algorithms/README.md): 115,222 nodes for 4,558 offset pieces, the
 * band lines' double evaluations 159,574 a render to 65,500, the heights'
 * 77,416 to 52,237.  A piece's halvings stop too at about YT_ROWS rows an
 * interval (the lines it serves are one a row: at 256 px the table had 8
 * nodes a row), and an interval stopped so is kept where its form is
 * within YT_ROWS_TOL: 70,140 nodes at 1024 px, 44,406 at 256 px (201,184). */
#define YT_TOL 3e-5
#define YT_DEPTH 8
#define YT_MIN 3
#define YT_TURN 4.0
#define YT_ROWS 2.0
#define YT_ROWS_TOL 0.1

/* An offset piece's point where it meets a band line at t: the root's
 * point xy, or the piece's own end where the root is one (offset_point;
 * X and Y may be xy) */
static inline void line_point(const ar_piece *p, double t, const long double xy[2],
                              long double *X, long double *Y)
{
    if (t == p->ot0 || t == p->ot1)
        offset_point(p, t, X, Y);
    else
        *X = xy[0], *Y = xy[1];
}

/* An offset piece's parameter t where it meets the line y = yl (fa = y0 -
 * yl: its top's height over it, negative) and its point there (X, Y): the
 * root's point (aa__offset_root_xy: the root's last evaluation moved to
 * it, where the point was evaluated again), or the piece's own end where
 * the root is one (offset_point).  A function of the piece and the line
 * alone, so a band's bottom and the next band's top agree whichever row
 * asks first. */
static double offset_line_t(const ar_piece *p, double fa, double yl, long double *X,
                            long double *Y, size_t *hint)
{
    long double xy[2];
    double t = aa__offset_root_xyd(&p->src->oc, &p->ofix, 1, p->ot0, p->ot1, fa, yl,
                                   ytab_guess(p, yl, hint), p->oend, xy);
    line_point(p, t, xy, X, Y);
    return t;
}

/* An offset piece: its cell from its point on the line y = ja (or its
 * top, if lower); its tau is sg t, so its fields are its ends' taus, its
 * x turns, and Va = -ja (V = -j in band j: y = v - V).  On the anchor's
 * line the point is kept as the first band's top (mline 0).  That line is
 * the last band's bottom where the worker did the row above with the seg
 * (its anchor ANCHOR_ROWS rows up): its root and point are then taken as
 * kept there (xline, yline), offset_line_t's for the same piece and line,
 * not solved again (on tests/bench_bezstroke.c's scene at 1024 px 3,492
 * roots a render). */
static void expand_offset(ar_seg *a, const ar_piece *p, int ja)
{
    const aa_piece *q = p->src;
    double t = q->ot0;
    long double X, Y;
    if (p->y0 < ja && a->p == p && a->mline != INT_MIN && a->ja + a->mline == ja)
        t = p->sg * a->tline, X = a->xline, Y = a->yline;
    else if (p->y0 < ja)
        t = offset_line_t(p, p->y0 - ja, ja, &X, &Y, &a->ythint);
    else
        offset_point(p, t, &X, &Y);
    double c0 = floor((double)X);
    c0 = c0 < -CELL_LIMIT ? -CELL_LIMIT : (c0 > CELL_LIMIT ? CELL_LIMIT : c0);
    a->p = p;
    a->ja = ja;
    a->c0 = (int)c0;
    a->U = (double)(X - c0);
    a->Va = -(double)ja;
    a->ax = a->ay = a->cx3 = a->cy3 = 0.0;
    a->ivy = a->k6 = 0.0;
    /* line_tau's root on the anchor's line */
    a->g = p->sg * t;
    a->vy = 0.0;
    a->t0 = p->sg * q->ot0;
    a->tend = p->sg * q->ot1;
    a->te = p->ote;
    a->te2 = p->ote2;
    a->mline = INT_MIN;
    if (p->y0 < ja)
        a->mline = 0, a->tline = a->g, a->uline = a->U, a->xline = X, a->yline = Y;
}

/* Expand piece p about its point on line y = ja (or its top, if lower),
 * in extended precision from its control points. */
static void expand(ar_seg *a, const ar_piece *p, int ja)
{
    if (p->conic) {
        expand_conic(a, p, ja);
        return;
    }
    if (p->offset) {
        expand_offset(a, p, ja);
        return;
    }
    long double T, X, Y;
    if (p->y0 >= ja) {
        T = 0.0L;
        X = p->x0;
        Y = p->y0l - ja;
    } else {
        /* T need not solve y(T) = ja exactly (Y keeps the residual), so it
         * is found in double; only x(T) and y(T) need the extra bits */
        double d = ja - p->y0, t;
        if (p->cubic) {
            t = area_cubic_root(-d, p->byd, p->ayd, p->dyd, 0.0, 1.0);
        } else if (p->ayd == 0.0) {
            t = d / p->byd;
        } else {
            double disc = p->byd * p->byd + 4.0 * p->ayd * d;
            double den = p->byd + sqrt(disc > 0.0 ? disc : 0.0);
            t = den > 0.0 ? 2.0 * d / den : 0.0;
        }
        T = t < 1.0 ? t : 1.0;
        if (p->cubic) {
            X = p->x0 + T * (p->bx + T * (p->ax + T * p->dx));
            Y = (p->y0l - ja) + T * (p->by + T * (p->ay + T * p->dy));
        } else {
            X = p->x0 + T * (p->bx + T * p->ax);
            Y = (p->y0l - ja) + T * (p->by + T * p->ay);
        }
    }
    /* the cell from the double value (x87 floorl and conversions reload
     * the control word: measured as 10% of the render) */
    double c0 = floor((double)X);
    c0 = c0 < -CELL_LIMIT ? -CELL_LIMIT : (c0 > CELL_LIMIT ? CELL_LIMIT : c0);
    a->p = p;
    a->ja = ja;
    a->c0 = (int)c0;
    a->U = (double)(X - c0);
    a->Va = (double)Y;
    a->g = (double)(p->bx + 2.0L * p->ax * T);
    a->vy = (double)(p->by + 2.0L * p->ay * T);
    a->ax = (double)p->ax;
    a->ay = (double)p->ay;
    a->tend = (double)(1.0L - T);
    a->t0 = (double)-T;
    a->cx3 = a->cy3 = 0.0;
    a->te2 = INFINITY;
    if (p->cubic) {
        /* the Taylor form about T: u = U + tau (g + tau (ax + tau cx3)) */
        a->g = (double)(p->bx + T * (2.0L * p->ax + 3.0L * T * p->dx));
        a->vy = (double)(p->by + T * (2.0L * p->ay + 3.0L * T * p->dy));
        a->ax = (double)(p->ax + 3.0L * T * p->dx);
        a->ay = (double)(p->ay + 3.0L * T * p->dy);
        a->cx3 = (double)p->dx;
        a->cy3 = (double)p->dy;
        double r[2];
        int n = gsl_poly_solve_quadratic(3.0 * a->cx3, 2.0 * a->ax, a->g, &r[0], &r[1]);
        a->te = n > 0 ? r[0] : INFINITY;
        a->te2 = n > 1 && r[1] > r[0] ? r[1] : INFINITY;
        a->ivy = a->vy > 0.0 ? 1.0 / a->vy : 0.0; /* the guesses' 1/d */
        a->k6 = 0.0;
        a->mline = INT_MIN;
        return;
    }
    a->te = a->ax != 0.0 ? -a->g / (2.0 * a->ax) : INFINITY;
    a->ivy = a->ay == 0.0 && a->vy > 0.0 ? 1.0 / a->vy : 0.0;
    a->k6 = p->k6;
    a->mline = INT_MIN;
}

/* tau where the piece meets the line y = ja + m (the same expression
 * whichever band asks, so a band's top equals the band above's bottom);
 * line_tau_quad for a line or a quadratic. */
static double line_tau_curved(const ar_seg *a, int m);

static inline double line_tau_quad(const ar_seg *a, int m)
{
    double c = a->Va - m;
    if (a->ay == 0.0)
        return -c * a->ivy;
    double disc = a->vy * a->vy - 4.0 * a->ay * c;
    double den = a->vy + sqrt(disc > 0.0 ? disc : 0.0);
    return den > 0.0 ? -2.0 * c / den : 0.0;
}

static inline double line_tau(const ar_seg *a, int m)
{
    if (a->p->curved)
        return line_tau_curved(a, m);
    return line_tau_quad(a, m);
}

/* An offset piece's tau on the line y = ja + m = -c (on the whole piece),
 * u there and its x and y (*x, *y): offset_line_t, the same call as
 * expand_offset's on the anchor's line, so the same root and point. */
static double offset_line(const ar_seg *a, int m, double *u, long double *x, long double *y)
{
    double c = a->Va - m;
    double t = offset_line_t(a->p, a->p->y0 + c, -c, x, y, &((ar_seg *)a)->ythint);
    *u = (double)(*x - a->c0);
    return a->p->sg * t;
}

/* line_tau of a cubic or conic piece (an offset piece's: offset_line) */
static double line_tau_curved(const ar_seg *a, int m)
{
    double c = a->Va - m;
    if (a->p->conic)
        return conic_q_of_v(a, c);
    if (a->p->cubic) {
        /* the guess: the series of the inverse about the anchor,
         * v(tau) - Va = d tau + q tau^2 + r tau^3 = h gives
         * tau = h/d - q h^2/d^3 + (2 q^2 - d r) h^3/d^5; a function of the
         * seg and the line alone (not of the rows done before), so the
         * image does not depend on the threads */
        double g = 0.0;
        if (a->vy > 0.0) {
            double r1 = a->ivy, x = -c * r1;
            g = x * (1.0 + x * r1 * (-a->ay + x * (2.0 * a->ay * a->ay * r1 - a->cy3)));
        }
        return area_cubic_near(c, a->vy, a->ay, a->cy3, a->t0, a->tend, g);
    }
    if (a->ay == 0.0)
        return -c * a->ivy;
    double disc = a->vy * a->vy - 4.0 * a->ay * c;
    double den = a->vy + sqrt(disc > 0.0 ? disc : 0.0);
    return den > 0.0 ? -2.0 * c / den : 0.0;
}

/* The cells of lo and hi at once (*a, *b), x's two lanes {lo, hi}, in
 * SSE2's packed doubles.  The cell of x (clamped to +-2^30): floor(x),
 * except that a negative integer gives the cell to its left (a piece
 * exactly on a cell's side may be put in either cell: its area share in the
 * other is zero): x clamped (maxpd and minpd, which take their second
 * operand where the first is NaN), truncated (cvttpd2dq: the clamped values
 * fit in an int), the comparison's mask -1 added. */
static inline void icell2(__m128d x, int *a, int *b)
{
    x = _mm_max_pd(x, _mm_set1_pd(-CELL_LIMIT));
    x = _mm_min_pd(x, _mm_set1_pd(CELL_LIMIT));
    __m128i neg = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmplt_pd(x, _mm_setzero_pd())), 0x08);
    __m128i c = _mm_add_epi32(_mm_cvttpd_epi32(x), neg);
    *a = _mm_cvtsi128_si32(c);
    *b = _mm_cvtsi128_si32(_mm_shuffle_epi32(c, 0x01));
}

/* An extent {lo, hi} (two lanes) grown to hold e: e < lo ? e : lo and
 * e > hi ? e : hi (minpd's and maxpd's choices), no branch */
static inline __m128d extent_with(__m128d x, double e)
{
    __m128d v = _mm_set1_pd(e);
    return _mm_move_sd(_mm_max_pd(v, x), _mm_min_pd(v, x));
}

/* u at tau t of an offset piece at an end of the band, its v kept in the
 * memo's slot k (offset_seg_u's values) */
static inline double offset_band_u(ar_seg *s, double t, int k)
{
    long double X, Y;
    offset_point(s->p, s->p->sg * t, &X, &Y);
    s->vt[k] = t, s->vv[k] = (double)(Y + s->V);
    return (double)(X - s->c0);
}

/* Piece p clipped to the band [j, j+1], in its seg s.  Returns 0 if it
 * lies right of the image.  `plain` (a constant where it is inlined): the
 * scene has no curved piece, so the cubic, conic and offset cases are
 * left out (their tests, seg_u's call, the second x extremum: te2 is
 * infinite on lines and quadratics); the same arithmetic either way. */
__attribute__((always_inline)) static inline int seg_make(ar_seg *s, const ar_piece *p, int j,
                                                          int W, const int plain)
{
    s->p = p;
    if (p->flat) {
        double lo = floor(p->xmin), hi = floor(p->xmax);
        if (lo >= W)
            return 0;
        s->ca = lo < -1 ? -1 : (int)lo;
        s->cb = hi < -1 ? -1 : (hi >= W ? W : (int)hi);
        s->va = s->vb = p->y0 - j;
        return 1;
    }
    /* One expansion serves ANCHOR_ROWS rows: a quadratic's Taylor form is
     * exact, and u stays within ANCHOR_ROWS times the slope of the anchor,
     * so rounding grows by at most that factor.  The anchor rows are fixed
     * (multiples of ANCHOR_ROWS), so the values do not depend on the rows
     * a thread rendered before. */
    int ja = j - j % ANCHOR_ROWS, m = j - ja;
    if (s->ja != ja)
        expand(s, p, ja);
    double ta, tb, ua, ub;
    /* (p->curved first: the common path reads no other cache line of p;
     * then p->offset, in the line band_roots has read, before p->conic,
     * four lines on, which an offset piece's seg need not read) */
    int curved = !plain && p->curved;
    int special = curved && (p->offset || p->conic);
    /* an offset piece's v at the band's ends, which part_area takes, is
     * kept in the memo's slots 2 and 3 as it is found (offset_keep's
     * values), the others cleared (none kept yet) */
    if (curved && p->offset)
        s->V = s->Va - (j - ja), s->vt[0] = s->vt[1] = NAN, s->vn = 0,
        s->my[0] = s->my[1] = NAN, s->mn = 0;
    if (p->y0 >= j) {
        ta = special ? s->t0 : 0.0;
        ua = !special ? s->U : p->offset ? offset_band_u(s, ta, 2) : seg_u(s, ta);
    } else if (s->mline == m) {
        ta = s->tline, ua = s->uline;
        /* an offset piece's v there from the y the band above kept: what
         * offset_v would give, bit for bit (same y, same V) */
        if (special && p->offset)
            s->vt[2] = ta, s->vv[2] = (double)(s->yline + s->V);
    } else if (plain) {
        ta = line_tau_quad(s, m), ua = u_quad(s, ta);
    } else if (special && p->offset) {
        long double x, y;
        ta = offset_line(s, m, &ua, &x, &y);
        s->vt[2] = ta, s->vv[2] = (double)(y + s->V);
    } else {
        ta = line_tau(s, m), ua = seg_u(s, ta);
    }
    if (p->y1 <= j + 1.0) {
        tb = s->tend;
        ub = plain ? u_quad(s, tb) : special && p->offset ? offset_band_u(s, tb, 3) : seg_u(s, tb);
    } else {
        /* kept as computed, so that the next band's top is what it would
         * compute itself */
        if (special && p->offset) {
            /* band_roots' root (offset_line's for the line: it asks every
             * offset seg made here, before, prej j) */
            tb = p->sg * s->pret;
            ub = (double)(s->prexy[0] - s->c0);
            s->vt[3] = tb, s->vv[3] = (double)(s->prexy[1] + s->V);
            /* the point kept as its bytes (two 16-byte moves), not
             * loaded onto the x87 stack and stored from it (fldt and
             * fstpt, the 80-bit store several micro-ops): by perf these
             * lines' samples about halved */
            memcpy(&s->xline, &s->prexy[0], sizeof s->xline);
            memcpy(&s->yline, &s->prexy[1], sizeof s->yline);
        } else {
            tb = plain ? line_tau_quad(s, m + 1) : line_tau(s, m + 1);
            ub = plain ? u_quad(s, tb) : seg_u(s, tb);
        }
        s->mline = m + 1, s->tline = tb, s->uline = ub;
    }
    if (!(tb >= ta))
        tb = ta, ub = ua;
    s->ta = ta, s->tb = tb;
    s->ua = ua, s->ub = ub;
    /* the extent in registers, stored once: stored field by field and
     * read back as a pair (icell2's load), the two stores were not
     * forwarded to the load, which waited for them to reach the cache;
     * the same values.  In two lanes {lo, hi}, its first ends ua < ub ?
     * ua : ub and ub > ua ? ub : ua by minpd and maxpd: the compiler made
     * a branch of the two choices on one comparison, and which way a seg
     * runs in x is its piece's (a stroke's two sides run opposite ways),
     * so that branch was mispredicted in most segs (callgrind's
     * --branch-sim: about 49,000 of 69,617 a render at 1024 px) */
    __m128d uab = _mm_set_pd(ub, ua), uba = _mm_shuffle_pd(uab, uab, 1);
    __m128d ext = _mm_move_sd(_mm_max_pd(uab, uba), _mm_min_pd(uab, uba));
    /* te2 >= te (expand's, and infinite where te is): neither inside
     * unless te < tb, as on few segs */
    if (s->te < tb) {
        if (s->te > ta)
            ext = extent_with(ext, plain ? u_quad(s, s->te) : u_at(s, s->te));
        if (!plain && s->te2 > ta && s->te2 < tb)
            ext = extent_with(ext, u_at(s, s->te2));
    }
    if (special) {
        /* a conic's ends come from its angle (an offset piece's from its
         * parameter), off its exact end points
         * (x0, y0) and (x1, y1) by rounding: where two pieces meet on a cell's
         * side, each end could fall in another cell, and the clusters
         * would not be linked; the extent holds the exact ends too */
        if (p->y0 >= j)
            ext = extent_with(ext, (double)(p->x0 - s->c0));
        if (p->y1 <= j + 1.0)
            ext = extent_with(ext, p->src->x1 - s->c0);
    }
    _mm_storel_pd(&s->lo, ext), _mm_storeh_pd(&s->hi, ext);
    int lo, hi;
    icell2(ext, &lo, &hi);
    lo += s->c0, hi += s->c0;
    if (lo >= W)
        return 0;
    s->ca = lo < -1 ? -1 : lo;
    s->cb = hi < -1 ? -1 : (hi >= W ? W : hi);
    return 1;
}

/* The band's fields that only the general cluster paths read: v at the
 * band's top line, and the seg's v range in the band.  Always inline, as
 * the path's other small functions (sub_end, part_flush, accumulate,
 * sweep, reaching, add_event): gcc kept them out of line; inline, the
 * render takes 2.1 M instructions fewer at 1024 px, 3.8 M at 256 px. */
__attribute__((always_inline)) static inline void band_fields(ar_seg *s, int j)
{
    const ar_piece *p = s->p;
    if (p->flat)
        return;
    s->V = s->Va - (j - s->ja);
    s->va = p->y0 > j ? p->y0 - j : 0.0;
    s->vb = p->y1 < j + 1.0 ? p->y1 - j : 1.0;
    s->bv[0] = s->bv[1] = NAN, s->bn = 0;
    s->wyb = NAN;
    s->xy[0] = s->xy[1] = NAN;
}

/* sub_key's root (tau *t, u *u) strictly inside the seg's heights in
 * the band, out of line: sub_key's look-up of its slots and the seg's
 * ends (half of its new heights) are inline, without a call */
static __attribute__((noinline)) void sub_root(const ar_seg *s, double v, double *t, double *u)
{
    if (s->p->curved && s->p->offset) {
        *t = offset_v_root(s, v, u);
    } else {
        double tt = solve_v(s, v);
        *t = tt, *u = u_at(s, tt);
    }
}

/* tau (*t) and u (*u) where v(tau) = v in the band, for a sub-band's
 * order: u at the band's ends as seg_make found it, inside it an offset
 * piece's from its root's last evaluation moved by its slope (key_u's),
 * the root the one tau_of_v finds (the same call); kept in the seg for
 * the band (bv), the slot's index returned. */
static inline int sub_key(const ar_seg *s, double v, double *t, double *u)
{
    ar_seg *w = (ar_seg *)s; /* the worker's own seg */
    int k = v == s->bv[0] ? 0 : v == s->bv[1] ? 1 : -1;
    if (k >= 0) {
        *t = s->bt[k], *u = s->bu[k];
        return k;
    }
    double tt, uu;
    if (v <= s->va)
        tt = s->ta, uu = s->ua;
    else if (v >= s->vb)
        tt = s->tb, uu = s->ub;
    else
        sub_root(s, v, &tt, &uu);
    k = s->bn;
    w->bv[k] = v, w->bt[k] = tt, w->bu[k] = uu, w->bx[k] = NAN, w->bn ^= 1;
    *t = tt, *u = uu;
    return k;
}

/* tau (*t) and u (*u) where v(tau) = v in the band, as the sweep takes
 * them: tau_of_v's root and seg_u there (an offset piece's point
 * evaluated, its v kept for part_area: offset_keep), each found once a
 * band (sub_key's slot) */
__attribute__((always_inline)) static inline void sub_end(const ar_seg *s, double v, double *t,
                                                         double *u)
{
    ar_seg *w = (ar_seg *)s;
    double uk;
    int k = sub_key(s, v, t, &uk), off = s->p->curved && s->p->offset;
    if (s->bx[k] != s->bx[k]) {
        if (off) { /* offset_seg_u's evaluation */
            long double X, Y;
            offset_point(s->p, s->p->sg * *t, &X, &Y);
            w->bk[k] = (double)(Y + s->V);
            w->bx[k] = (double)(X - s->c0);
        } else {
            w->bx[k] = u_at(s, *t);
        }
    }
    if (off)
        offset_keep(s, *t, s->bk[k]);
    *u = s->bx[k];
}

/* ------------------------------------------------------------------------
 * Cell accumulation (Crow's left areas minus right areas)
 * ------------------------------------------------------------------------ */

/* The area right of the part of s from tau ta to tb (u from ua to ub,
 * relative to its column) inside the column, and its height *dy
 * (part_area_quad: of a line or a quadratic). */
static double part_area_curved(const ar_seg *s, double ta, double tb, double ua, double ub,
                               double kc, double *dy);

static inline double part_area_quad(const ar_seg *s, double ta, double tb, double ua,
                                    double ub, double *dy)
{
    double d = tb - ta;
    *dy = d * (s->vy + s->ay * (ta + tb));
    return *dy * (1.0 - 0.5 * (ua + ub)) + d * d * d * s->k6;
}

static inline double part_area(const ar_seg *s, double ta, double tb, double ua, double ub,
                               double kc, double *dy)
{
    if (s->p->curved)
        return part_area_curved(s, ta, tb, ua, ub, kc, dy);
    return part_area_quad(s, ta, tb, ua, ub, dy);
}

/* A part of an offset piece that ends at an end of the piece: its chord
 * runs to the piece's own end V (offset_point: the outline's vertex,
 * rounded to double), while the segment between chord and arc
 * (area_offset_segment_at) is the curve's own, whose end E is up to about
 * an ulp of the coordinates from V (or, where the piece takes the row's
 * point, about V when ta is the piece's end: below).  The part is the arc
 * joined to V by the short edge E V: its area right is the trapezoids under V E, E E' and E' V'
 * less the segment, and this is those less the trapezoid under V V', the
 * polygon V E E' V' (ends that are no piece's end: E = V), minus its signed
 * area, 1/2 sum (v_Q - v_P)(u_P + u_Q) over its edges (the trapezoids' own
 * 1 (v_Q - v_P) cancel round it); u and v from x and y in long double, the
 * cell's column dropping out of the sum.  Without it, the triangle V E E'
 * (up to |E E'| |E V| / 2, 5e-14 on the benchmark's scene) stayed.  Where
 * one end alone is the piece's (the other a band line's, a cell side's or
 * a sub-band end's point: E = V there), the polygon is taken about the
 * piece's end, the other end from it by the part's chord (du, dv: u and v
 * at tb less those at ta, as the trapezoid takes them), not the point
 * evaluated there again: the triangle's area is 1/2 |E E'| times the
 * chord's distance across it, so the chord's rounding (and a side's
 * root's, about 1e-14 px) moves it by about 4e-14 times that (on
 * tests/bench_bezstroke.c's scene at 1024 px 5,948 evaluations a render,
 * 354 instructions each).  The segment is taken about the row's point at
 * ta (part_area_curved), V where ta is the piece's end: 1/2 (E - V) x (E'
 * - E) more than about E, which the polygon's area takes back (where the
 * piece takes the row's point: ar_piece's rowpt). */
__attribute__((noinline)) static double offset_end_poly(const ar_seg *s, double ta, double tb,
                                                        double du, double dv, int ea, int eb)
{
    const aa_piece *q = s->p->src;
    long double P[4][2], X, Y; /* V, E, E', V' as (x, y), about the piece's end */
    if (ea && eb) {
        offset_point(s->p, ta, &X, &Y);
        P[0][0] = P[1][0] = X, P[0][1] = P[1][1] = Y;
        offset_point(s->p, tb, &X, &Y);
        P[2][0] = P[3][0] = X, P[2][1] = P[3][1] = Y;
        aa__offset_eval_s(&q->oc, s->p->ostops, ta, &P[1][0], &P[1][1], NULL, NULL);
        aa__offset_eval_s(&q->oc, s->p->ostops, tb, &P[2][0], &P[2][1], NULL, NULL);
    } else {
        int e = ea ? 1 : 2, o = ea ? 3 : 0; /* E's slot, and the other end's */
        double t = ea ? ta : tb, sg = ea ? 1.0 : -1.0;
        offset_point(s->p, t, &X, &Y);
        P[3 - o][0] = X, P[3 - o][1] = Y;
        aa__offset_eval_s(&q->oc, s->p->ostops, t, &P[e][0], &P[e][1], NULL, NULL);
        P[o][0] = P[3 - e][0] = X + sg * du, P[o][1] = P[3 - e][1] = Y + sg * dv;
    }
    long double a = 0.0L, x0 = P[0][0], y0 = P[0][1];
    for (int k = 0; k < 4; k++) {
        const long double *A = P[k], *B = P[(k + 1) & 3];
        a += ((B[1] - y0) - (A[1] - y0)) * ((A[0] - x0) + (B[0] - x0));
    }
    if (ea && s->p->rowpt) /* the segment taken about V, not E: 1/2 (E - V) x (E' - E) more */
        a -= (P[1][0] - P[0][0]) * (P[2][1] - P[1][1]) - (P[1][1] - P[0][1]) * (P[2][0] - P[1][0]);
    return (double)(-0.5L * a);
}

/* offset_end_area's test inline, its polygon (6,021 of 96,297 parts a
 * render on tests/bench_bezstroke.c's scene at 1024 px) a call: the ends
 * from the piece's copies of src's ot0 and ot1 (its first cache lines),
 * the four comparisons two by two, without a branch. */
static inline double offset_end_area(const ar_seg *s, double ta, double tb, double du, double dv)
{
    const ar_piece *p = s->p;
    __m128d t = _mm_set_pd(tb, ta);
    int m = _mm_movemask_pd(_mm_or_pd(_mm_cmpeq_pd(t, _mm_set1_pd(p->ot0)),
                                      _mm_cmpeq_pd(t, _mm_set1_pd(p->ot1))));
    if (!m)
        return 0.0;
    return offset_end_poly(s, ta, tb, du, dv, m & 1, m >> 1);
}

/* part_area of a cubic, conic or offset piece (kc: the column's left
 * side x = c0 + kc, an offset piece's) */
static double part_area_curved(const ar_seg *s, double ta, double tb, double ua, double ub,
                               double kc, double *dy)
{
    double d = tb - ta;
    if (s->p->offset) {
        /* the chord's height from the ends, the segment between chord and
         * arc by quadrature with its bound (area_offset.c), about the
         * row's point at ta (x = c0 + kc + ua, y = v0 - V: the curve's, but
         * at the piece's end, offset_end_poly) where the piece takes it
         * (rowpt), else about the curve's own; v at the ends as kept
         * (offset_keep) */
        int kb = offset_slot(s, tb); /* looked up once: offset_v keeps nothing */
        double v0 = offset_v_kept(s, ta), v1 = kb >= 0 ? s->vv[kb] : offset_v(s, tb);
        if (kb < 0)
            offset_keep(s, tb, v1);
        *dy = v1 - v0;
        double sg = s->p->sg;
        return *dy * (1.0 - 0.5 * (ua + ub)) -
               area_offset_segment_at(s->p, sg * ta, sg * tb, s->c0 + kc,
                                      s->p->rowpt ? ua : NAN, -s->V, v0) +
               offset_end_area(s, sg * ta, sg * tb, ub - ua, *dy);
    }
    if (s->p->conic) {
        /* from q: the angle d = 2 atan(pq), pq = (tb - ta)/(1 + ta tb)
         * (tan of a difference of half angles), and the chord's height
         * v(tb) - v(ta) = 2 d (vy (1 - ta tb) + ay (ta + tb)) / ((1 + ta^2)
         * (1 + tb^2)), no cancellation; the elliptic segment between chord
         * and arc: the ellipse is the image of the unit circle under
         * (ea eb; -er 0), of determinant eb er, and the circle's segment
         * over an angle d is (d - sin d)/2, on the left of the arc's
         * direction when eb er > 0 (header) */
        double pq = d / (1.0 + ta * tb);
        *dy = 2.0 * d * (s->vy * (1.0 - ta * tb) + s->ay * (ta + tb)) /
              ((1.0 + ta * ta) * (1.0 + tb * tb));
        return *dy * (1.0 - 0.5 * (ua + ub)) + s->k6 * d_minus_sin_half(pq);
    }
    if (s->p->cubic) {
        /* Taylor coefficients at ta: (x', y'), (x'', y'')/2, the cubic's
         * terms; the area between the arc and its chord is, by Green's
         * theorem, 1/2 of the integral of P x P' over [0, d] with
         * P(s) = s a1 + s^2 a2 + s^3 a3:
         * a1xa2 d^3/6 + a1xa3 d^4/4 + a2xa3 d^5/10 (a x b = ax by - ay bx),
         * on the left of the arc's direction when positive. */
        double x1 = s->g + ta * (2.0 * s->ax + 3.0 * ta * s->cx3);
        double y1 = s->vy + ta * (2.0 * s->ay + 3.0 * ta * s->cy3);
        double x2 = s->ax + 3.0 * ta * s->cx3, y2 = s->ay + 3.0 * ta * s->cy3;
        double x3 = s->cx3, y3 = s->cy3;
        *dy = d * (y1 + d * (y2 + d * y3));
        double c12 = x1 * y2 - y1 * x2, c13 = x1 * y3 - y1 * x3, c23 = x2 * y3 - y2 * x3;
        double seg = d * d * d * (c12 * (1.0 / 6.0) + d * (c13 * 0.25 + d * c23 * 0.1));
        return *dy * (1.0 - 0.5 * (ua + ub)) - seg;
    }
    *dy = d * (s->vy + s->ay * (ta + tb));
    return *dy * (1.0 - 0.5 * (ua + ub)) + d * d * d * s->k6;
}

/* The part of s from tau ta to tb lies in local column k: add dc times
 * the area of the cell right of it, and times its height to the cover of
 * the cell after (the cells left of the image pass it on to cell 0). */
static inline void emit(ar_worker *wk, const ar_seg *s, double k, double ta, double tb,
                        double ua, double ub, const double *dc, int nch, int W)
{
    double dy, right = part_area(s, ta, tb, ua - k, ub - k, k, &dy);
    int col = s->c0 + (int)k;
    if (col < s->ca)
        col = s->ca;
    if (col > s->cb)
        col = s->cb;
    if (col >= W)
        return;
    if (col < 0) {
        for (int ch = 0; ch < nch; ch++)
            wk->cov[ch] += dc[ch] * dy;
        return;
    }
    double *acc = wk->acc + (size_t)col * nch, *cov = wk->cov + (size_t)(col + 1) * nch;
    for (int ch = 0; ch < nch; ch++) {
        acc[ch] += dc[ch] * right;
        cov[ch] += dc[ch] * dy;
    }
}

/* The cells an x-monotone part from u1 to u2 passes, in its direction
 * (right: u2 >= u1): the first k and the last kend, kend = k where the
 * part's rounding would put it before k. */
static inline void walk_cells(double u1, double u2, int right, double *k, double *kend)
{
    *k = right ? floor(u1) : ceil(u1) - 1.0;
    *kend = right ? ceil(u2) - 1.0 : floor(u2);
    if (right ? *kend < *k : *kend > *k)
        *kend = *k;
}

/* A side's root tb kept inside the part's rest [ta, t2] (ta where it is
 * below or NaN). */
static inline double in_part(double tb, double ta, double t2)
{
    tb = tb >= ta ? tb : ta;
    return tb > t2 ? t2 : tb;
}

/* walk on an offset piece: its sides after the first start from
 * side_guess through the side before (or the part's start) and the two
 * ends of what is left, the first from the chord (offset_tau_u's start).
 * The chord alone left the first double step beyond DD_D_STEP (offset.c),
 * and the root to root_d_more, on 71% of those later sides on
 * tests/bench_bezstroke.c's scene at 1024 px, the quadratic on 31%
 * (algorithms/README.md).  Apart from walk's loop: the point before kept
 * there cost the other pieces' walks more than it saved. */
static void walk_offset(ar_worker *wk, const ar_seg *s, double t1, double t2, double u1,
                        double u2, const double *dc, int nch, int W)
{
    int right = u2 >= u1;
    double k, kend;
    walk_cells(u1, u2, right, &k, &kend);
    if (k == kend) { /* one cell (most parts) */
        emit(wk, s, k, t1, t2, u1, u2, dc, nch, W);
        return;
    }
    double ta = t1, ua = u1, tp = NAN, up = NAN; /* (tp, up): the point before ta */
    for (;;) {
        double tb = t2, ub = u2;
        if (k != kend) {
            ub = right ? k + 1.0 : k;
            tb = offset_tau_at(s, ta, t2, ua - ub, (double)s->c0 + ub,
                               side_guess(tp, up, ta, ua, t2, u2, ub));
            tb = in_part(tb, ta, t2);
        }
        emit(wk, s, k, ta, tb, ua, ub, dc, nch, W);
        if (k == kend)
            break;
        tp = ta, up = ua;
        ta = tb, ua = ub;
        k += right ? 1.0 : -1.0;
    }
}

/* An x-monotone part from (t1, u1) to (t2, u2): walk its cells. */
static void walk(ar_worker *wk, const ar_seg *s, double t1, double t2, double u1, double u2,
                 const double *dc, int nch, int W)
{
    if (s->p->offset) {
        walk_offset(wk, s, t1, t2, u1, u2, dc, nch, W);
        return;
    }
    int right = u2 >= u1;
    double k, kend;
    walk_cells(u1, u2, right, &k, &kend);
    double ta = t1, ua = u1;
    for (;;) {
        double tb = t2, ub = u2;
        if (k != kend) {
            ub = right ? k + 1.0 : k;
            tb = s->p->cubic ? tau_of_u_in(s, ub, right ? 1.0 : -1.0, ta, t2, ua, u2)
                             : tau_of_u(s, ub, right ? 1.0 : -1.0);
            tb = in_part(tb, ta, t2);
        }
        emit(wk, s, k, ta, tb, ua, ub, dc, nch, W);
        if (k == kend)
            break;
        ta = tb, ua = ub;
        k += right ? 1.0 : -1.0;
    }
}

/* Add colour jump dc times the area right of s from tau t1 to t2. */
__attribute__((always_inline)) static inline void accumulate(ar_worker *wk, const ar_seg *s,
                                                            double t1, double t2, double u1,
                                                            double u2, const double *dc,
                                                            int nch, int W)
{
    if (s->te2 > t1 && s->te2 < t2) { /* a cubic's second x extremum */
        double ue = u_at(s, s->te2);
        accumulate(wk, s, t1, s->te2, u1, ue, dc, nch, W);
        walk(wk, s, s->te2, t2, ue, u2, dc, nch, W);
        return;
    }
    if (s->te > t1 && s->te < t2) {
        double ue = u_at(s, s->te);
        walk(wk, s, t1, s->te, u1, ue, dc, nch, W);
        walk(wk, s, s->te, t2, ue, u2, dc, nch, W);
        return;
    }
    walk(wk, s, t1, t2, u1, u2, dc, nch, W);
}

/* Write the cluster's cells [lo, hi] from colour cin plus the cells'
 * cover and area, clearing them for the next cluster. */
static void resolve(const ar_row *r, int lo, int hi, const double *cin)
{
    ar_worker *wk = r->wk;
    int nch = r->S->nch, a = lo < 0 ? 0 : lo, b = hi >= r->W ? r->W - 1 : hi;
    double run[3] = {cin[0], cin[1], cin[2]};
    for (int i = a; i <= b; i++) {
        double *acc = wk->acc + (size_t)i * nch, *cov = wk->cov + (size_t)i * nch;
        double v[3] = {0, 0, 0};
        for (int ch = 0; ch < nch; ch++) {
            run[ch] += cov[ch];
            v[ch] = run[ch] + acc[ch];
            acc[ch] = cov[ch] = 0.0;
        }
        if (nch == 1)
            v[1] = v[2] = v[0];
        store_px(r, r->px + 3 * (size_t)i, v);
    }
    for (int ch = 0; ch < nch; ch++)
        wk->cov[(size_t)(b + 1) * nch + ch] = 0.0;
}

/* Add s's kept part (sweep_part) times its colour jump. */
__attribute__((always_inline)) static inline void part_flush(ar_worker *wk, ar_seg *s, int nch,
                                                            int W)
{
    double t2, u2;
    if (s->p->curved && s->p->offset) /* its start's v, as sub_end kept it */
        offset_keep(s, s->wt, s->wv);
    sub_end(s, s->wyb, &t2, &u2);
    accumulate(wk, s, s->wt, t2, s->wu, u2, s->wdc, nch, W);
}

/* s's part from the top ya of a sub-band on, with colour jump dc.  The
 * area right of a part is the sum of the areas right of its pieces, so
 * where the part kept from the sub-bands above is open (wyb INFINITY: it
 * had this jump in the last sub-band the sweep walked it in, and the
 * same in those it passed by since, sweep's windings carried) with the
 * same jump (its neighbours' order changed, not the windings on its two
 * sides) it is lengthened, and added once (part_flush) when the jump
 * changes, the sweep finds none (part_stop), or the cluster ends
 * (sweep_end): one quadrature and one point evaluated where there were
 * one a sub-band.  On tests/bench_bezstroke.c's scene at 1024 px 8,651
 * of the 22,664 parts of the sub-bands' sweeps continued the part above,
 * at 256 px 15,051 of 39,922. */
static void sweep_part(ar_worker *wk, ar_seg *s, uint32_t idx, const double *dc, double ya,
                       int nch, int W)
{
    if (s->wyb == INFINITY) {
        if (s->wdc[0] == dc[0] && s->wdc[1] == dc[1] && s->wdc[2] == dc[2])
            return;
        s->wyb = ya;
    }
    if (s->wyb == s->wyb)
        part_flush(wk, s, nch, W);
    else
        wk->pend[wk->npend++] = idx;
    sub_end(s, ya, &s->wt, &s->wu);
    if (s->p->curved && s->p->offset)
        s->wv = s->vv[s->vn ^ 1]; /* the v sub_end kept last (offset_keep) */
    s->wya = ya, s->wyb = INFINITY;
    s->wdc[0] = dc[0], s->wdc[1] = dc[1], s->wdc[2] = dc[2];
}

/* s's open part (sweep_part) ends at ya: the sweep found it with no jump
 * in the sub-band below. */
static inline void part_stop(ar_seg *s, double ya)
{
    if (s->wyb == INFINITY)
        s->wyb = ya;
}

/* The cluster's kept parts added (after its last sub-band). */
static void sweep_end(const ar_row *r)
{
    ar_worker *wk = r->wk;
    for (size_t k = 0; k < wk->npend; k++) {
        ar_seg *s = &wk->seg[wk->pend[k]];
        if (s->wyb == INFINITY) /* open to the seg's end (the sub-bands' last yb, or before) */
            s->wyb = s->vb;
        if (s->wyb == s->wyb)
            part_flush(wk, s, r->S->nch, r->W);
        s->wyb = NAN;
    }
    wk->npend = 0;
}

/* Add, in order, the colour jump across each seg in keys[0..n) (sorted
 * along x) times its area in the band (whole: at once) or from the top ya
 * of a sub-band on (kept by sweep_part, open until the sweep finds the
 * seg with another jump or none, or it ends).  w holds the windings left
 * of the first; c their colour.  A colour depends on which layers cover
 * (colour_of, area_composite_colour's key), so where a seg leaves its
 * layer inside (or outside) it is not asked for; and an opaque scene's
 * colours are its layers' own, so the same pointer is the same colour (a
 * compositing scene's ring hands out another each call).  At 64 px on
 * tests/bench_bezstroke.c's scene about 2.3 M of the sweeps' 13.4 M segs
 * change the colour. */
__attribute__((always_inline)) static inline void sweep(const ar_row *r, const ar_key *keys,
                                                       size_t n, int *w, const double *c,
                                                       double ya, int whole)
{
    const ar_state *S = r->S;
    ar_seg *seg = r->wk->seg;
    for (size_t k = 0; k < n; k++) {
        ar_seg *s = &seg[keys[k].idx];
        int l = s->p->layer, was = w[l] & S->inside[l];
        w[l] += s->p->dir;
        if (!was == !(w[l] & S->inside[l])) { /* l inside or out as before: the colour too */
            part_stop(s, ya);
            continue;
        }
        const double *nx = colour_of(S, r->wk, w);
        if (nx == c) { /* one of an opaque scene's colours, again: no jump */
            part_stop(s, ya);
            continue;
        }
        double dc[3] = {nx[0] - c[0], nx[1] - c[1], nx[2] - c[2]};
        c = nx;
        if (dc[0] == 0.0 && dc[1] == 0.0 && dc[2] == 0.0) {
            part_stop(s, ya);
            continue;
        }
        if (whole)
            accumulate(r->wk, s, s->ta, s->tb, s->ua, s->ub, dc, S->nch, r->W);
        else
            sweep_part(r->wk, s, keys[k].idx, dc, ya, S->nch, r->W);
    }
}

/* ------------------------------------------------------------------------
 * Crossings of two pieces
 * ------------------------------------------------------------------------ */

/* 1 if conic pieces p and q are arcs of one ellipse: the same centre,
 * height and ea, and eb the same up to its sign (s -> -s draws the other
 * half).  An ellipse does not cross itself: its arcs meet at most at their
 * ends (the vertices, cut there already), so no meeting need be sought. */
static inline int same_ellipse(const aa_piece *p, const aa_piece *q)
{
    return p->ex == q->ex && p->ey == q->ey && p->er == q->er && p->ea == q->ea &&
           fabs(p->eb) == fabs(q->eb);
}

/* Heights v in (ya, yb), away from its ends, where conic segs p and q (of
 * two ellipses) cross: p is N(q)/W(q) in its half-angle tangent q (N
 * quadratic, W = 1 + q^2), q's ellipse is the unit circle under (ea eb;
 * -er 0) about its centre, so with D = N - C W the points of p on it have
 * A^2 + B^2 = W^2, A = (er Dx + ea Dy)/(eb er) (= W sin s), B = -Dy/er
 * (= W cos s): a quartic in q, taken over p's range in the band (shifted
 * to (0, 1)) and its sign changes found by poly_roots.  A root is on q's
 * piece when sin s >= 0 (the half of q's ellipse that the piece is part
 * of; the other half has the same heights).  0 and nothing found if q's
 * ellipse is flat (eb = 0). */
static int conic_crossings(const ar_seg *p, const ar_seg *q, double ya, double yb, double *out)
{
    const aa_piece *Q = q->p->src;
    double ea = Q->ea, eb = Q->eb, er = Q->er;
    double qa = tau_of_v(p, ya), qb = tau_of_v(p, yb), h = qb - qa;
    if (!(h > 0.0) || eb == 0.0)
        return 0;
    /* q's centre in p's cell and band: U + ax = ex - c0, V + ay = ey - j */
    double cx = ((double)q->c0 - (double)p->c0) + (q->U + q->ax), cy = q->V + q->ay;
    double dx[3] = {p->U - cx, 2.0 * p->g, (p->U - cx) + 2.0 * p->ax};
    double dy[3] = {p->V - cy, 2.0 * p->vy, (p->V - cy) + 2.0 * p->ay};
    double a[3], b[3], ieb = 1.0 / (eb * er);
    for (int k = 0; k < 3; k++) {
        a[k] = (er * dx[k] + ea * dy[k]) * ieb;
        b[k] = -dy[k] / er;
    }
    double c[5] = {a[0] * a[0] + b[0] * b[0] - 1.0, 2.0 * (a[0] * a[1] + b[0] * b[1]),
                   a[1] * a[1] + b[1] * b[1] + 2.0 * (a[0] * a[2] + b[0] * b[2]) - 2.0,
                   2.0 * (a[1] * a[2] + b[1] * b[2]), a[2] * a[2] + b[2] * b[2] - 1.0};
    /* q = qa + h sigma: the Taylor shift to qa, then the scale */
    for (int i = 0; i < 4; i++)
        for (int k = 3; k >= i; k--)
            c[k] += qa * c[k + 1];
    for (int k = 1; k <= 4; k++)
        c[k] *= pow(h, k);
    double r[4];
    int m = poly_roots(c, 4, r), n = 0;
    for (int i = 0; i < m; i++) {
        double t = qa + h * r[i], w = 1.0 + t * t;
        if (!(a[0] + t * (a[1] + t * a[2]) >= -1e-9 * w))
            continue; /* on the other half of q's ellipse */
        double v = p->V + 2.0 * t * (p->vy + p->ay * t) / w;
        if (v > ya + CROSS_MARGIN && v < yb - CROSS_MARGIN)
            out[n++] = v;
    }
    return n;
}

/* An offset seg's parameters t (sg tau) at band heights ya and yb where
 * they are its band's ends (ta, tb, solved already), else NaN
 * (aa__piece_meet_at solves for those). */
static void seg_t_at(const ar_seg *s, double ya, double yb, double t[2])
{
    t[0] = t[1] = NAN;
    if (!s->p->offset)
        return;
    if (ya == s->va)
        t[0] = s->p->sg * s->ta;
    if (yb == s->vb)
        t[1] = s->p->sg * s->tb;
}

void (*aa__area_kept_solve)(const aa_piece *p, double y, double r, double ta, double tb);

/* aa__area_kept_solve's call (tests only), out of line and cold: the solve tests the
 * pointer alone */
__attribute__((noinline, cold)) static void kept_solve_call(const ar_seg *s, double y, double r)
{
    aa__area_kept_solve(s->p->src, y, r, s->p->sg * s->ta, s->p->sg * s->tb);
}

/* An offset seg's parameter at height y (absolute) inside its piece, where
 * a pair's common heights begin or end away from the band's ends asked
 * about (band j = base), kept in the seg.  A vertex inside the band begins
 * one pair's common heights and ends another's (the two pieces meeting
 * there, each paired with the seg), so the second finds it kept.  The
 * solve is over the whole piece, as aa__piece_meet_at's own (offset_t_at),
 * but started from the piece's table (ytab_guess, the band lines' start;
 * else where the chord of the seg's parameters over its heights in the
 * band meets y), not from the piece's ends: a root as good (y within the
 * double solver's rounding of its terms, about 1e-12 px at 1024 px), not
 * always the same double.  On the 1,000 stroked cubics of
 * tests/bench_bezstroke.c the render at 1024 px 184.14 M instructions to
 * 182.77 M, at 256 px 223.32 M to 221.87 M (callgrind); the meetings
 * found moved by rounding (algorithms/README.md). */
static double seg_t_kept(const ar_seg *s, double y, double base)
{
    const aa_piece *p = s->p->src;
    if (y == s->my[0])
        return s->mt[0];
    if (y == s->my[1])
        return s->mt[1];
    ar_seg *w = (ar_seg *)s; /* the worker's own seg (offset_keep) */
    double g = ytab_guess(s->p, y, &w->ythint);
    if (g != g) {
        double ya = base + s->va, yb = base + s->vb, ta = s->p->sg * s->ta;
        g = yb > ya ? ta + (s->p->sg * s->tb - ta) * ((y - ya) / (yb - ya)) : NAN;
    }
    double r = aa__offset_solve_dg(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y, g);
    if (__builtin_expect(aa__area_kept_solve != NULL, 0))
        kept_solve_call(s, y, r);
    w->my[w->mn] = y, w->mt[w->mn] = r, w->mn ^= 1;
    return r;
}

/* An offset seg's parameters t at the pair's common heights lo >= ya and
 * hi <= yb, from seg_t_at's at ya and yb (NAN: unknown), as
 * aa__piece_meet_at would take them (param_known): t[0] at ya, the
 * piece's own at its ends, else the solve inside it, kept (seg_t_kept:
 * from the piece's table's start, so not always the double
 * aa__piece_meet_at's own solve from the piece's ends finds, but as
 * near the root); NAN left where it finds them at once. */
static inline void seg_t_common(const ar_seg *s, double lo, double hi, double ya, double yb,
                                double base, double t[2])
{
    const aa_piece *p = s->p->src;
    if (!s->p->offset)
        return;
    if (!(lo == ya && t[0] == t[0]))
        t[0] = lo > p->y0 ? seg_t_kept(s, lo, base) : NAN; /* lo < hi <= y1 */
    if (!(hi == yb && t[1] == t[1]))
        t[1] = hi < p->y1 ? seg_t_kept(s, hi, base) : NAN;
}

/* An offset seg's x at heights Y[0] and Y[1] (absolute), its parameters
 * there t (NAN: not known, x then NAN too, aa__piece_meet_atx finds it),
 * as aa__piece_end_x gives it, kept in the seg for the other pairs of the
 * band that ask there (a crowded band's seg is in several); NAN for other
 * kinds. */
static inline void seg_x_known(const ar_seg *s, const double Y[2], const double t[2],
                               double x[2])
{
    x[0] = x[1] = NAN;
    if (!s->p->offset)
        return;
    ar_seg *w = (ar_seg *)s; /* the worker's own seg */
    for (int e = 0; e < 2; e++) {
        if (Y[e] == s->xy[e] && t[e] == s->xt[e]) {
            x[e] = s->xx[e];
        } else if (t[e] == t[e]) {
            w->xy[e] = Y[e], w->xt[e] = t[e];
            x[e] = w->xx[e] = aa__piece_end_x(s->p->src, Y[e], t[e]);
        }
    }
}

/* Heights v in (ya, yb), away from its ends, where segs p and q cross.
 * Both are reparametrised over [ya, yb] as P(s) = Pa + s B + s^2 A in
 * coordinates relative to p's cell; the crossings are where P meets q's
 * implicit curve: for a line, cross(X - Qa, Bq) = 0; for a parabola,
 * cross(X - Qa, Aq)^2 = k cross(X - Qa, Bq), k = cross(Aq, Bq) (from
 * X - Qa = s Bq + s^2 Aq), a polynomial of degree <= 4 in s. */
static int pair_crossings(const ar_seg *p, const ar_seg *q, double ya, double yb, int j,
                          double *out)
{
    if (p->p->conic && q->p->conic) {
        if (same_ellipse(p->p->src, q->p->src))
            return 0;
        if (q->p->src->eb != 0.0)
            return conic_crossings(p, q, ya, yb, out);
    }
    if (p->p->cubic || q->p->cubic || p->p->conic || q->p->conic || p->p->offset ||
        q->p->offset) {
        /* a cubic or a conic: the scene's own meeting heights
         * (aa_piece_meet: roots of a cubic polynomial against a line,
         * bisection on exact extents against an arc), as band-local
         * heights */
        double base = j, ys[9], tp[2], tq[2], Ya = base + ya, Yb = base + yb;
        seg_t_at(p, ya, yb, tp);
        seg_t_at(q, ya, yb, tq);
        /* where a piece begins or ends inside [Ya, Yb], the other's
         * parameter there is kept in its seg (seg_t_common), asked for as
         * the pair's common heights [lo, hi] (seg_t_kept's solve) */
        const aa_piece *P = p->p->src, *Q = q->p->src;
        double lo = P->y0 > Q->y0 ? P->y0 : Q->y0, hi = P->y1 < Q->y1 ? P->y1 : Q->y1;
        lo = lo > Ya ? lo : Ya, hi = hi < Yb ? hi : Yb;
        if (lo < hi && P->dir && Q->dir &&
            (lo != Ya || hi != Yb || tp[0] != tp[0] || tp[1] != tp[1] || tq[0] != tq[0] ||
             tq[1] != tq[1])) {
            seg_t_common(p, lo, hi, Ya, Yb, base, tp);
            seg_t_common(q, lo, hi, Ya, Yb, base, tq);
            Ya = lo, Yb = hi;
        }
        const double Y[2] = {Ya, Yb};
        double xp[2], xq[2];
        seg_x_known(p, Y, tp, xp);
        seg_x_known(q, Y, tq, xq);
        int m = aa__piece_meet_atx(P, Q, Ya, Yb, tp, tq, xp, xq, ys, 9), n = 0;
        for (int i = 0; i < m; i++) {
            double v = ys[i] - base;
            if (v > ya + CROSS_MARGIN && v < yb - CROSS_MARGIN)
                out[n++] = v;
        }
        return n;
    }
    if (p->p->line && !q->p->line) {
        const ar_seg *t = p;
        p = q, q = t;
    }
    double pa = tau_of_v(p, ya), pb = tau_of_v(p, yb), qa = tau_of_v(q, ya), qb = tau_of_v(q, yb);
    double dp = pb - pa, dq = qb - qa, shift = (double)q->c0 - (double)p->c0;
    double Px = u_at(p, pa), Py = p->V + pa * (p->vy + pa * p->ay);
    double Bx = dp * (p->g + 2.0 * p->ax * pa), By = dp * (p->vy + 2.0 * p->ay * pa);
    double Ax = dp * dp * p->ax, Ay = dp * dp * p->ay;
    double Qx = shift + u_at(q, qa), Qy = q->V + qa * (q->vy + qa * q->ay);
    double Cx = dq * (q->g + 2.0 * q->ax * qa), Cy = dq * (q->vy + 2.0 * q->ay * qa);
    double Dx = dq * dq * q->ax, Dy = dq * dq * q->ay;
    double ex = Px - Qx, ey = Py - Qy;
    /* beta(s) = cross(P(s) - Qa, C) */
    double b0 = ex * Cy - ey * Cx, b1 = Bx * Cy - By * Cx, b2 = Ax * Cy - Ay * Cx;
    double k = Dx * Cy - Dy * Cx, c[5] = {0, 0, 0, 0, 0};
    double scale = (Cx * Cx + Cy * Cy) * sqrt(Dx * Dx + Dy * Dy);
    int arc = !q->p->line && fabs(k) > 1e-14 * scale;
    /* alpha(s) = cross(P(s) - Qa, D) */
    double a0 = ex * Dy - ey * Dx, a1 = Bx * Dy - By * Dx, a2 = Ax * Dy - Ay * Dx;
    if (arc) {
        c[0] = a0 * a0 - k * b0;
        c[1] = 2.0 * a0 * a1 - k * b1;
        c[2] = a1 * a1 + 2.0 * a0 * a2 - k * b2;
        c[3] = 2.0 * a1 * a2;
        c[4] = a2 * a2;
    } else {
        c[0] = b0, c[1] = b1, c[2] = b2;
    }
    double s[4];
    int m, n = 0;
    if (!arc && c[2] == 0.0) {
        /* linear (two lines: A = 0, not an arc): poly_roots' linear
         * case here, without its call and its scan for the degree, which
         * cost more than the root (9,685 pairs a render at 1024 px); the
         * same root */
        s[0] = c[1] != 0.0 ? -c[0] / c[1] : 0.0;
        m = s[0] > 0.0 && s[0] < 1.0;
    } else {
        m = poly_roots(c, 4, s);
    }
    for (int i = 0; i < m; i++) {
        if (arc) {
            double sig = -(a0 + s[i] * (a1 + s[i] * a2)) / k;
            if (!(sig >= -1e-9 && sig <= 1.0 + 1e-9))
                continue;
        }
        double v = Py + s[i] * (By + s[i] * Ay);
        if (v > ya + CROSS_MARGIN && v < yb - CROSS_MARGIN)
            out[n++] = v;
    }
    return n;
}

/* ------------------------------------------------------------------------
 * Clusters
 * ------------------------------------------------------------------------ */

/* keys[0..n) = the cluster's segs ordered by the left end of their extent
 * (relative to cell lo), for finding pairs whose extents overlap. */
static void order_by_left(const ar_row *r, const ar_key *in, size_t n, int lo, ar_key *keys)
{
    const ar_seg *seg = r->wk->seg;
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &seg[in[k].idx];
        keys[k].key = s->p->flat ? s->p->xmin - lo : (double)(s->c0 - lo) + s->lo;
        keys[k].id = in[k].id;
        keys[k].idx = in[k].idx;
    }
    sort_keys(keys, n);
}

static inline double right_end(const ar_seg *s, int lo)
{
    return s->p->flat ? s->p->xmax - lo : (double)(s->c0 - lo) + s->hi;
}

/* The segs before keys[k] (in order of left end) whose extent reaches
 * past keys[k]'s left end: act[0..*nact) holds, in ascending order, those
 * that reached past the one before; drop those left behind for good (left
 * ends only grow).  So each seg is tested against the segs overlapping it
 * only, in the order of a scan over all those before it, not against every
 * one.  Extents that only touch (at one x) are not overlapping: the two
 * segs lie on either side of that x, may touch there, and never change
 * order (a stroke's inner join line and its offset leaving their common
 * vertex on either side of it). */
__attribute__((always_inline)) static inline void reaching(const ar_row *r, uint32_t *act,
                                                          size_t *nact, double left)
{
    double *right = r->wk->ends; /* act[a]'s right end (add_reaching's) */
    size_t keep = 0;
    for (size_t a = 0; a < *nact; a++)
        if (right[a] > left)
            act[keep] = act[a], right[keep++] = right[a];
    *nact = keep;
}

/* keys[k] (seg s) added to reaching's act[0..*nact), its right end kept
 * beside it (wk->ends, free while the crossings are sought) */
static inline void add_reaching(const ar_row *r, uint32_t *act, size_t *nact, size_t k,
                                const ar_seg *s, int lo)
{
    r->wk->ends[*nact] = right_end(s, lo);
    act[(*nact)++] = (uint32_t)k;
}

/* Does any pair of the cluster (all spanning the band) cross inside it?
 * Every pair whose extents overlap is tested. */
static int any_crossing(const ar_row *r, const ar_key *keys, size_t n, int lo)
{
    const ar_seg *seg = r->wk->seg;
    double out[9]; /* two cubics meet up to 9 times */
    uint32_t *act = r->wk->act;
    size_t nact = 0;
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &seg[keys[k].idx];
        reaching(r, act, &nact, keys[k].key);
        for (size_t a = 0; a < nact; a++)
            if (pair_crossings(&seg[keys[act[a]].idx], s, 0.0, 1.0, r->j, out))
                return 1;
        add_reaching(r, act, &nact, k, s, lo);
    }
    return 0;
}

/* The fewest segs a sub-band's order takes from the one above's
 * (order_next): fewer are ordered afresh from their ends at less cost. */
#define AR_NEXT_MIN 32

/* Order along x from the ends (order_ends): a pair of neighbours is in
 * order where it is apart by more than ORDER_GAP px at one end of the
 * (sub-)band and not reversed by more than ORDER_TIE px (rounding: two
 * pieces leaving one vertex) at the other. */
#define ORDER_GAP 1e-9
#define ORDER_TIE 1e-12

/* u at the top and the bottom of the band (sub = 0: the seg spans it) or
 * of the sub-band [ya, yb] (sub_key), relative to cell lo */
static inline void ends_u(const ar_seg *s, int lo, double ya, double yb, int sub, double *top,
                          double *bot)
{
    double base = (double)(s->c0 - lo), t, u;
    if (!sub) {
        *top = base + s->ua, *bot = base + s->ub;
        return;
    }
    sub_key(s, ya, &t, &u);
    *top = base + u;
    sub_key(s, yb, &t, &u);
    *bot = base + u;
}

/* 1 if two segs' x at each height of the (sub-)band is a function of
 * their x at its ends alone: two lines (x linear in y), or two offset
 * pieces of one curve over one range of its parameter (the outline traces
 * an offset curve's part between its folds twice), one x at every height.
 * Such a pair, in order at both ends up to rounding (ORDER_TIE), is in
 * that order inside (within rounding of each other where the ends are). */
static inline int same_track(const ar_seg *a, const ar_seg *b)
{
    const ar_piece *p = a->p, *q = b->p;
    if (p->line && q->line)
        return 1;
    if (!(p->offset && q->offset))
        return 0;
    const aa_piece *P = p->src, *Q = q->src;
    return ((P->ot0 == Q->ot0 && P->ot1 == Q->ot1) || (P->ot0 == Q->ot1 && P->ot1 == Q->ot0)) &&
           !memcmp(&P->oc, &Q->oc, sizeof P->oc);
}

/* keys[0..n) = in[0..n), segs none of which crosses another inside the
 * band or sub-band [ya, yb] (all spanning it), in their order along x
 * inside it, from u at its ends: sorted by the sum of the two, and kept
 * if each pair of neighbours is in order at both ends, apart at one
 * (ORDER_GAP).  Two that do not cross keep one order inside; at an end
 * they are in it or meet (a vertex on the band's line), up to rounding.
 * 0 if some pair is not so ordered (the same ends, pieces traced twice,
 * or ends within ORDER_GAP): the order is then taken at the middle,
 * a root on each offset piece (key_u), which the ends spare. */
static int order_ends(const ar_row *r, const ar_key *in, size_t n, int lo, double ya, double yb,
                      int sub, ar_key *keys)
{
    const ar_seg *seg = r->wk->seg;
    double *e = r->wk->ends, pt = 0.0, pb = 0.0; /* in[k]'s ends at e[2k], e[2k + 1] */
    for (size_t k = 0; k < n; k++) {
        ends_u(&seg[in[k].idx], lo, ya, yb, sub, &e[2 * k], &e[2 * k + 1]);
        keys[k].key = e[2 * k] + e[2 * k + 1];
        keys[k].id = in[k].id;
        keys[k].idx = (uint32_t)k; /* its place in `in` until sorted (by key and id alone) */
    }
    sort_keys(keys, n);
    for (size_t k = 0; k < n; k++) {
        uint32_t i = keys[k].idx;
        double top = e[2 * i], bot = e[2 * i + 1], dt = top - pt, db = bot - pb;
        keys[k].idx = in[i].idx;
        if (k > 0 && !((dt > ORDER_GAP && db > -ORDER_TIE) || (db > ORDER_GAP && dt > -ORDER_TIE) ||
                       (dt > -ORDER_TIE && db > -ORDER_TIE &&
                        same_track(&seg[keys[k - 1].idx], &seg[keys[k].idx])))) {
            for (k++; k < n; k++) /* the segs' own indices for the middle's order */
                keys[k].idx = in[keys[k].idx].idx;
            return 0;
        }
        pt = top, pb = bot;
    }
    return 1;
}

/* keys[0..n) = the cluster's segs (all spanning the band) in their order
 * along x at mid-band, relative to cell lo: the order of the whole band
 * when no two cross. */
static void order_mid(const ar_row *r, const ar_key *in, size_t n, int lo, ar_key *keys)
{
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &r->wk->seg[in[k].idx];
        keys[k].key = (double)(s->c0 - lo) + key_u(s, 0.5);
        keys[k].id = in[k].id;
        keys[k].idx = in[k].idx;
    }
    sort_keys(keys, n);
}

/* The same question for a crowded cluster, in its order at mid-band
 * (order_mid): only neighbours are tested.  If two segs cross, the order
 * changes, and the first change away from mid-band is between two segs
 * that are neighbours there (a seg between them would meet them at the
 * same point): n - 1 tests, where the pairs whose extents overlap grow as
 * the square of the crowd (65536 arcs 0.01 px apart in one row of crow). */
static int neighbours_cross(const ar_row *r, const ar_key *mid, size_t n)
{
    const ar_seg *seg = r->wk->seg;
    double out[9]; /* two cubics meet up to 9 times */
    for (size_t k = 0; k + 1 < n; k++)
        if (pair_crossings(&seg[mid[k].idx], &seg[mid[k + 1].idx], 0.0, 1.0, r->j, out))
            return 1;
    return 0;
}

/* No vertex, no crossing: one order along x for the whole band (keys, if
 * not NULL, is it already). */
static void cluster_fast(const ar_row *r, const ar_key *in, size_t n, int lo, int hi, int *w,
                         const double *cin, const ar_key *keys)
{
    if (!keys) {
        ar_key *k = r->wk->sub;
        if (n == 1)
            k[0] = in[0];
        else if (!order_ends(r, in, n, lo, 0.0, 1.0, 0, k))
            order_mid(r, in, n, lo, k);
        keys = k;
    }
    sweep(r, keys, n, w, cin, 0.0, 1);
    resolve(r, lo, hi, cin);
}

/* The sub-band boundaries of one pass over the band, from y up to lim, in
 * wk->ev (v). */
typedef struct ev_buf {
    double *v;
    size_t n, room; /* room: wk->ev_room */
    double y, lim;
    ar_worker *wk;
} ev_buf;

static void *line_alloc_as(size_t n, size_t size, int zero);

size_t aa__area_events_grown = CM_MAX_EVENTS_GROWN;

/* Twice the room of *p (*room elements of size bytes, n of them kept),
 * up to aa__area_events_grown (CM_MAX_EVENTS_GROWN): 1 if grown, 0 if at
 * that or out of memory (*p as it was).  A crowded cluster's band can
 * hold many more crossings than CM_MAX_EVENTS: without room for them,
 * each pass kept half and the next asked every pair again (bench_bezstroke
 * at 16 px: 634 passes and 32 million pairs a render). */
__attribute__((noinline, cold)) static int grow_room(void **p, size_t *room, size_t size, size_t n)
{
    if (*room >= aa__area_events_grown)
        return 0;
    void *q = line_alloc_as(2 * *room, size, 0);
    if (!q)
        return 0;
    memcpy(q, *p, n * size);
    free(*p);
    *p = q, *room *= 2;
    return 1;
}

/* Keep boundary v if it lies inside (y, lim).  When the buffer is full
 * and cannot grow, keep its lower half and lower lim to the first value
 * dropped: the next pass starts there and finds the rest again (bounded
 * memory). */
__attribute__((always_inline)) static inline void add_event(ev_buf *b, double v)
{
    if (!(v > b->y && v < b->lim))
        return;
    if (b->n == b->room && grow_room((void **)&b->wk->ev, &b->wk->ev_room, sizeof *b->v, b->n))
        b->v = b->wk->ev, b->room = b->wk->ev_room;
    if (b->n == b->room) {
        qsort(b->v, b->n, sizeof *b->v, cmp_double);
        b->n = b->n / 2;
        b->lim = b->v[b->n];
        if (!(v < b->lim))
            return;
    }
    b->v[b->n++] = v;
}

/* Keep the crossing of segs a and b at height v (inside the buffer's
 * heights) for the next sub-band's order (order_next); when the array is
 * full and cannot grow, those past the buffer's lim are dropped, and if
 * none is, the pass orders each sub-band afresh (cxfull). */
static void add_cross(ar_worker *wk, const ev_buf *b, double v, uint32_t a, uint32_t c)
{
    if (!(v > b->y && v < b->lim))
        return;
    if (wk->ncx == wk->cx_room)
        grow_room((void **)&wk->cx, &wk->cx_room, sizeof *wk->cx, wk->ncx);
    if (wk->ncx == wk->cx_room) {
        size_t m = 0;
        for (size_t k = 0; k < wk->ncx; k++)
            if (wk->cx[k].v < b->lim)
                wk->cx[m++] = wk->cx[k];
        wk->ncx = m;
        if (m == wk->cx_room) {
            wk->cxfull = 1;
            return;
        }
    }
    wk->cx[wk->ncx++] = (struct ar_cross){v, a, c};
}

static int cmp_cross(const void *a, const void *b)
{
    const struct ar_cross *x = a, *y = b;
    return x->v < y->v ? -1 : (x->v > y->v);
}

/* The crossings kept below lim, in order of height. */
static void sort_crosses(ar_worker *wk, double lim)
{
    size_t m = 0;
    for (size_t k = 0; k < wk->ncx; k++)
        if (wk->cx[k].v < lim)
            wk->cx[m++] = wk->cx[k];
    wk->ncx = m;
    if (m > 32) {
        qsort(wk->cx, m, sizeof *wk->cx, cmp_cross);
        return;
    }
    for (size_t a = 1; a < m; a++) { /* few: by insertion (sort_doubles') */
        struct ar_cross x = wk->cx[a];
        size_t at = a;
        while (at > 0 && wk->cx[at - 1].v > x.v) {
            wk->cx[at] = wk->cx[at - 1];
            at--;
        }
        wk->cx[at] = x;
    }
}

/* Heights inside (y, ylim) where the cluster's order along x changes:
 * vertices, flat edges, crossings.  keys: ordered by left end.  If there
 * are more than CM_MAX_EVENTS_GROWN (r->wk->ev grows to hold them up to
 * that), *ylim is lowered so that those found are all there are below it.
 * Returns the count, sorted, unique, in r->wk->ev. */
static size_t band_events(const ar_row *r, const ar_key *keys, size_t n, int lo, double y,
                          double *ylim)
{
    const ar_seg *seg = r->wk->seg;
    const double *vab = r->wk->vab; /* cluster_bands' heights of keys[k] */
    ev_buf b = {r->wk->ev, 0, r->wk->ev_room, y, *ylim, r->wk};
    double out[9]; /* two cubics meet up to 9 times */
    r->wk->ncx = 0, r->wk->cxfull = n < AR_NEXT_MIN; /* too few for order_next */
    uint32_t *act = r->wk->act;
    size_t nact = 0;
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &seg[keys[k].idx];
        add_event(&b, s->va);
        if (!s->p->flat)
            add_event(&b, s->vb);
        reaching(r, act, &nact, keys[k].key);
        if (!s->p->flat)
            for (size_t a = 0; a < nact; a++) {
                /* the larger top and smaller bottom written out (fmax
                 * and fmin are library calls; none of these is NaN),
                 * the other seg's from vab; a flat one (va = vb) is
                 * left out by the test */
                const double *tv = &vab[2 * (size_t)act[a]];
                double ya = s->va > tv[0] ? s->va : tv[0], yb = s->vb < tv[1] ? s->vb : tv[1];
                ya = ya > y ? ya : y, yb = yb < b.lim ? yb : b.lim;
                if (!(ya < yb))
                    continue;
                const ar_seg *t = &seg[keys[act[a]].idx];
                int c = pair_crossings(t, s, ya, yb, r->j, out);
                for (int i = 0; i < c; i++) {
                    add_event(&b, out[i]);
                    if (!r->wk->cxfull)
                        add_cross(r->wk, &b, out[i], keys[act[a]].idx, keys[k].idx);
                }
            }
        add_reaching(r, act, &nact, k, s, lo);
    }
    if (r->wk->ncx)
        sort_crosses(r->wk, b.lim);
    sort_doubles(b.v, b.n);
    size_t m = 0;
    for (size_t k = 0; k < b.n; k++)
        if (m == 0 || b.v[k] > b.v[m - 1])
            b.v[m++] = b.v[k];
    *ylim = b.lim;
    return m;
}

/* 1 if segs a and b are one curve: two offset pieces on one track
 * (same_track), or two lines each of whose ends lies within ORDER_TIE of
 * the other's line (the sides of round joins where the curve's normal is
 * the same on both sides of a vertex: from an offset's end to the vertex
 * and back), the order order_ends keeps for lines within ORDER_TIE of
 * each other: either order the same sweep where both are, up to that. */
static inline int twins(const ar_seg *a, const ar_seg *b)
{
    if (!(a->p->line && b->p->line))
        return a->p->offset && same_track(a, b);
    const aa_piece *P = a->p->src, *Q = b->p->src;
    double ex = P->x1 - P->x0, ey = P->y1 - P->y0, fx = Q->x1 - Q->x0, fy = Q->y1 - Q->y0;
    double tol = ORDER_TIE * ORDER_TIE;
    double c0 = ex * (Q->y0 - P->y0) - ey * (Q->x0 - P->x0);
    double c1 = ex * (Q->y1 - P->y0) - ey * (Q->x1 - P->x0);
    double c2 = fx * (P->y0 - Q->y0) - fy * (P->x0 - Q->x0);
    double c3 = fx * (P->y1 - Q->y0) - fy * (P->x1 - Q->x0);
    double le = ex * ex + ey * ey, lf = fx * fx + fy * fy;
    return c0 * c0 <= tol * le && c1 * c1 <= tol * le && c2 * c2 <= tol * lf &&
           c3 * c3 <= tol * lf;
}

/* 1 if seg a goes before seg b (left of it) in the sub-band [ya, yb],
 * neither crossing the other inside it: by their extents in the band where
 * those are apart, else order_ends' rule on the pair
 * (apart at one end, not reversed at the other), else their order at the
 * middle (key_u), as order_ends' fallback takes it, and for twins within
 * rounding of each other at both ends by the sum of their ends.  *kind: 2
 * if the ends decide, 1 if twins or the middle does (by more than
 * ORDER_GAP), 0 if the order may not hold below yb (a pair meeting near
 * the sub-band, whose order the next one decides). */
static int pair_order(const ar_row *r, const ar_key *a, const ar_key *b, int lo, double ya,
                      double yb, int *kind)
{
    const ar_seg *sa = &r->wk->seg[a->idx], *sb = &r->wk->seg[b->idx];
    double at, ab, bt, bb;
    if (!sa->p->flat && !sb->p->flat) {
        /* extents in the band (seg_make's lo and hi: the band's ends and
         * the x turns inside) apart by more than 2 ORDER_GAP: apart by
         * more than ORDER_GAP at both ends of every sub-band (each end
         * inside its extent up to rounding, about 1e-13 px), the ends'
         * rule's answer without their roots.  In a thumbnail most pairs
         * a sub-band's order compares lie far apart in x (order_next's
         * halving): on tests/bench_bezstroke.c's scene at 64 px 0.69 M
         * of 1.68 M pairs a render, at 32 px 1.96 M of 5.45 M */
        double base_a = (double)(sa->c0 - lo), base_b = (double)(sb->c0 - lo);
        *kind = 2;
        if ((base_b + sb->lo) - (base_a + sa->hi) > 2.0 * ORDER_GAP)
            return 1;
        if ((base_a + sa->lo) - (base_b + sb->hi) > 2.0 * ORDER_GAP)
            return 0;
    }
    ends_u(sa, lo, ya, yb, 1, &at, &ab);
    ends_u(sb, lo, ya, yb, 1, &bt, &bb);
    double dt = bt - at, db = bb - ab;
    *kind = 2;
    if ((dt > ORDER_GAP && db > -ORDER_TIE) || (db > ORDER_GAP && dt > -ORDER_TIE))
        return 1;
    if ((dt < -ORDER_GAP && db < ORDER_TIE) || (db < -ORDER_GAP && dt < ORDER_TIE))
        return 0;
    double ka, kb;
    *kind = 1;
    if (dt > -ORDER_TIE && db > -ORDER_TIE && dt < ORDER_TIE && db < ORDER_TIE &&
        twins(sa, sb)) {
        ka = at + ab, kb = bt + bb;
    } else {
        double vm = 0.5 * (ya + yb);
        ka = (double)(sa->c0 - lo) + key_u(sa, vm);
        kb = (double)(sb->c0 - lo) + key_u(sb, vm);
        *kind = fabs(ka - kb) > ORDER_GAP;
    }
    return ka < kb || (ka == kb && a->id < b->id);
}

/* The run of list[0..m) about list[k] whose neighbours the ends do not
 * part (pair_order's kind below 2: twins, pairs within rounding): if some
 * pair of it is not sure (kind 0), its segs are marked (to) to be placed
 * again in the next sub-band, all of them, since twins in it take either
 * order (a line and its twin, then an offset piece and its twin, the
 * middle pair unsure: the outer pair is too).  Returns the run's end. */
static size_t mark_run(const ar_row *r, const ar_key *list, size_t m, size_t k, int lo, double ya,
                       double yb, uint32_t to)
{
    size_t g0 = k, g1 = k;
    int kind, unsure = 0;
    while (g0 > 0) {
        pair_order(r, &list[g0 - 1], &list[g0], lo, ya, yb, &kind);
        if (kind == 2)
            break;
        unsure |= !kind;
        g0--;
    }
    while (g1 + 1 < m) {
        pair_order(r, &list[g1], &list[g1 + 1], lo, ya, yb, &kind);
        if (kind == 2)
            break;
        unsure |= !kind;
        g1++;
    }
    if (unsure)
        for (size_t i = g0; i <= g1; i++)
            r->wk->mark[list[i].idx] = to;
    return g1;
}

/* mark_run on the whole of list[0..m), ordered afresh. */
static void mark_unsure(const ar_row *r, const ar_key *list, size_t m, int lo, double ya,
                        double yb)
{
    for (size_t k = 0; k < m; k++)
        k = mark_run(r, list, m, k, lo, ya, yb, r->wk->stamp + 1);
}

/* list[0..m) = the order of the sub-band above [ya, yb] (no two of its
 * segs cross inside either): made the order of [ya, yb].  Only the segs
 * with an event at ya change places: those ending there leave, those
 * beginning there come in, and those crossing another there (band_events'
 * crossings, wk->cx from *ci on) are taken out; the rest keep their order
 * (two segs that neither cross nor end between two sub-bands keep it),
 * and the segs taken out and coming in are put in it one by one, each by
 * halving (pair_order: u at the sub-band's ends of O(log m) segs, not of
 * all).  keys[0..): the cluster; tops[0..ntops): its segs but the flat
 * ones by (their top va, their place in keys), *tc the first whose top
 * is not above the last sub-band's, so that those beginning at ya are
 * found there, not by a scan of the cluster; spare: room for all of it.
 * Returns the count, or 0 if the sub-band is better ordered afresh (too
 * many events: each placed seg's halving would take more roots than the
 * ends of all).  The first place changed and the count of the segs after
 * the last that are the order above's: wk->chlo, wk->chtail.  Each
 * entry's key is its seg's vb (cluster_bands sets it where it orders a
 * sub-band afresh), so that the segs ending at ya are found without a
 * load of each seg (640 bytes each, a cache line of each of n segs in
 * each of k sub-bands: at 32 px a third of flush's own time). */
static size_t order_next(const ar_row *r, const ar_key *keys, const ar_key *tops, size_t ntops,
                         size_t *tc, ar_key *list, size_t m, ar_key *spare, int lo, double ya,
                         double yb, size_t *ci)
{
    ar_worker *wk = r->wk;
    if (wk->stamp >= UINT32_MAX - 2) { /* wrapping: no mark may look current */
        memset(wk->mark, 0, (size_t)r->S->npieces * sizeof *wk->mark);
        wk->stamp = 0;
        return 0; /* the marks of segs to place again are gone */
    }
    uint32_t st = ++wk->stamp;
    for (; *ci < wk->ncx && !(wk->cx[*ci].v > ya); (*ci)++)
        if (wk->cx[*ci].v == ya)
            wk->mark[wk->cx[*ci].a] = wk->mark[wk->cx[*ci].b] = st;
    /* lo_ch: the first place changed; tail: the unchanged segs after the
     * last */
    size_t u = 0, nt = 0, lo_ch = m, tail = m;
    for (size_t k = 0; k < m; k++) {
        int out = !(list[k].key >= yb); /* ended at ya (the key: the seg's vb) */
        if (!out && wk->mark[list[k].idx] != st) {
            list[u++] = list[k];
            continue;
        }
        lo_ch = lo_ch < k ? lo_ch : k, tail = m - 1 - k;
        if (!out)
            spare[nt++] = list[k];
    }
    while (*tc < ntops && tops[*tc].key < ya) /* the segs begun at ya, in the cluster's order */
        (*tc)++;
    for (size_t k = *tc; k < ntops && tops[k].key == ya; k++) {
        double vb = wk->vab[2 * (size_t)tops[k].id + 1]; /* keys[id]'s, cluster_bands' */
        if (vb >= yb)
            spare[nt] = keys[tops[k].id], spare[nt++].key = vb, wk->mark[tops[k].idx] = st;
    }
    size_t bits = 1;
    while ((size_t)1 << bits <= u + nt)
        bits++;
    if (nt * bits > 2 * (u + nt))
        return 0;
    for (size_t k = 0; k < nt; k++) {
        size_t a = 0, b = u;
        int kind;
        while (a < b) {
            size_t h = a + (b - a) / 2;
            if (pair_order(r, &spare[k], &list[h], lo, ya, yb, &kind))
                b = h;
            else
                a = h + 1;
        }
        memmove(&list[a + 1], &list[a], (u - a) * sizeof *list);
        list[a] = spare[k];
        lo_ch = lo_ch < a ? lo_ch : a, tail = tail < u - a ? tail : u - a;
        u++;
    }
    wk->chlo = lo_ch, wk->chtail = tail;
    /* the runs about the segs placed, all of them between the first place
     * changed and the unchanged tail */
    for (size_t k = lo_ch, end = u - (tail < u ? tail : u); k < end; k++)
        if (wk->mark[list[k].idx] == st)
            k = mark_run(r, list, u, k, lo, ya, yb, st + 1);
    return u;
}

/* The band cut into sub-bands with a fixed order along x, each swept;
 * a sub-band's order from the one above where few segs change places
 * (order_next), else afresh. */
static void cluster_bands(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                          const int *w, const double *cin)
{
    ar_worker *wk = r->wk;
    ar_key *keys = wk->sub, *list = wk->sub + n;
    ar_key *span = list + n; /* keys[0..n) sits before list */
    ar_key *tops = wk->tops;
    order_by_left(r, in, n, lo, keys);
    double *vab = wk->vab; /* keys[k]'s va and vb at vab[2k], vab[2k + 1] */
    for (size_t k = 0; k < n; k++) {
        const ar_seg *s = &wk->seg[keys[k].idx];
        vab[2 * k] = s->va, vab[2 * k + 1] = s->vb;
    }
    double y = 0.0;
    size_t nl = (size_t)r->S->nl, m = 0, ntops = 0, tc = 0;
    int made = 0; /* tops[0..ntops): the segs by their tops (order_next's, made once) */
    while (y < 1.0) {
        double lim = 1.0;
        size_t ne = band_events(r, keys, n, lo, y, &lim), ci = 0;
        int above = 0; /* list[0..m) holds the order of the sub-band above */
        for (size_t e = 0; e <= ne; e++) {
            double ya = y, yb = e < ne ? wk->ev[e] : lim;
            y = yb;
            if (!(yb > ya))
                continue;
            size_t next = 0;
            if (above && m >= AR_NEXT_MIN && !wk->cxfull) {
                if (!made) {
                    for (size_t k = 0; k < n; k++) {
                        const ar_seg *s = &wk->seg[keys[k].idx];
                        if (!s->p->flat)
                            tops[ntops++] = (ar_key){s->va, (uint32_t)k, keys[k].idx};
                    }
                    sort_keys(tops, ntops);
                    made = 1;
                }
                next = order_next(r, keys, tops, ntops, &tc, list, m, span, lo, ya, yb, &ci);
            }
            if (next) {
                m = next;
            } else {
                /* the segs spanning the sub-band, ordered along x from
                 * their ends, else at its middle (a flat one has va = vb,
                 * seg_make's, so spans none: yb > ya) */
                double vm = 0.5 * (ya + yb);
                m = 0;
                for (size_t k = 0; k < n; k++)
                    if (vab[2 * k] <= ya && vab[2 * k + 1] >= yb)
                        span[m++] = keys[k];
                if (m <= 1) { /* one seg or none: in order, without its ends' roots */
                    memcpy(list, span, m * sizeof *list);
                } else if (!order_ends(r, span, m, lo, ya, yb, 1, list)) {
                    for (size_t k = 0; k < m; k++)
                        list[k].key = (double)(wk->seg[list[k].idx].c0 - lo) +
                                      key_u(&wk->seg[list[k].idx], vm);
                    sort_keys(list, m);
                }
                if (e < ne && m >= AR_NEXT_MIN && !wk->cxfull) { /* order_next's next */
                    for (size_t k = 0; k < m; k++) /* order_next reads a seg's vb there */
                        list[k].key = wk->seg[list[k].idx].vb;
                    mark_unsure(r, list, m, lo, ya, yb);
                }
            }
            above = m > 0;
            memcpy(wk->wtmp, w, nl * sizeof *w);
            /* from the one above: the segs before the first change and
             * after the last have the windings on their sides, so the
             * jumps, that they had (the windings right of the cluster
             * are one at every height of the band, its w's right of it),
             * their parts open (sweep_part); the sweep walks from the
             * first change to the last, the windings there summed from
             * the cluster's left */
            size_t a = 0, b = m;
            const double *c = cin;
            if (next) {
                a = wk->chlo < m ? wk->chlo : m;
                b = wk->chtail < m - a ? m - wk->chtail : a;
                if (a > 0 && b > a) {
                    const int *ld = r->S->ldir;
                    for (size_t k = 0; k < a; k++) {
                        int v = ld[list[k].idx];
                        wk->wtmp[v >> 2] += (v & 3) - 1;
                    }
                    c = colour_of(r->S, wk, wk->wtmp);
                }
            }
            sweep(r, list + a, b - a, wk->wtmp, c, ya, 0);
        }
    }
    sweep_end(r);
    resolve(r, lo, hi, cin);
}

/* Pixel cin + (nx - cin) area; grey scenes compute one channel. */
static inline void put(const ar_row *r, double *px, const double *cin, const double *nx,
                       double area)
{
    if (r->grey) {
        double v = clamp01(cin[0] + (nx[0] - cin[0]) * area);
        px[0] = v, px[1] = v, px[2] = v;
        return;
    }
    double v[3] = {cin[0] + (nx[0] - cin[0]) * area, cin[1] + (nx[1] - cin[1]) * area,
                   cin[2] + (nx[2] - cin[2]) * area};
    store_px(r, px, v);
}

/* Whether s is of single()'s kind: it spans the band and has no x extremum
 * inside it (te < tb first: te2 >= te, as seg_make tests them). */
static inline int single_kind(const ar_row *r, const ar_seg *s, const int plain)
{
    return s->p->y0 <= r->j && s->p->y1 >= r->j + 1.0 &&
           (!(s->te < s->tb) ||
            (!(s->te > s->ta) && (plain || !(s->te2 > s->ta && s->te2 < s->tb))));
}

/* single()'s side root on an offset piece, asked in the row's batch
 * (side_ask, kept in pret and prexy[1]): its y kept as offset_tau_at
 * keeps it */
static inline double side_taken(const ar_seg *s)
{
    double t = s->p->sg * s->pret;
    offset_keep(s, t, (double)(s->prexy[1] + s->V));
    return t;
}

/* The common cluster: one seg spanning the band, monotone in x, in one or
 * two cells of the image (single_kind and the cells checked), written
 * directly, without the cell arrays: a tenth of the cost of the general
 * path on `crow`.  w moves past the seg; returns the colour right of it.
 * `batch` (a constant where it is inlined): an offset piece's side root
 * is the row's batch's (side_ask asked it: single's kind, two cells) */
__attribute__((always_inline)) static inline const double *
single(const ar_row *r, const ar_seg *s, int *w, const double *cin, const int plain,
       const int batch)
{
    const ar_piece *p = s->p;
    w[p->layer] += p->dir;
    const double *nx = colour_of(r->S, r->wk, w);
    double *px = r->px + 3 * (size_t)s->ca, dy;
    double k = (double)(s->ca - s->c0); /* the left cell, local */
    if (s->ca == s->cb) {
        double a = plain ? part_area_quad(s, s->ta, s->tb, s->ua - k, s->ub - k, &dy)
                         : part_area(s, s->ta, s->tb, s->ua - k, s->ub - k, k, &dy);
        put(r, px, cin, nx, a);
        return nx;
    }
    /* two cells: the piece crosses their common side x = c0 + k + 1 */
    double dl, dr, al, ar;
    if (s->ub > s->ua) {
        double tc = plain ? tau_of_u_quad(s, k + 1.0, 1.0)
                    : batch && s->p->curved && s->p->offset ? side_taken(s)
                    : s->p->curved && (s->p->cubic || s->p->offset)
                        ? tau_of_u_in(s, k + 1.0, 1.0, s->ta, s->tb, s->ua, s->ub)
                        : tau_of_u(s, k + 1.0, 1.0);
        tc = tc < s->ta ? s->ta : (tc > s->tb ? s->tb : tc);
        if (plain) {
            al = part_area_quad(s, s->ta, tc, s->ua - k, 1.0, &dl);
            ar = part_area_quad(s, tc, s->tb, 0.0, s->ub - k - 1.0, &dr);
        } else {
            al = part_area(s, s->ta, tc, s->ua - k, 1.0, k, &dl);
            ar = part_area(s, tc, s->tb, 0.0, s->ub - k - 1.0, k + 1.0, &dr);
        }
    } else {
        double tc = plain ? tau_of_u_quad(s, k + 1.0, -1.0)
                    : batch && s->p->curved && s->p->offset ? side_taken(s)
                    : s->p->curved && (s->p->cubic || s->p->offset)
                        ? tau_of_u_in(s, k + 1.0, -1.0, s->ta, s->tb, s->ua, s->ub)
                        : tau_of_u(s, k + 1.0, -1.0);
        tc = tc < s->ta ? s->ta : (tc > s->tb ? s->tb : tc);
        if (plain) {
            ar = part_area_quad(s, s->ta, tc, s->ua - k - 1.0, 0.0, &dr);
            al = part_area_quad(s, tc, s->tb, 1.0, s->ub - k, &dl);
        } else {
            ar = part_area(s, s->ta, tc, s->ua - k - 1.0, 0.0, k + 1.0, &dr);
            al = part_area(s, tc, s->tb, 1.0, s->ub - k, k, &dl);
        }
    }
    put(r, px, cin, nx, al);
    put(r, px + 3, cin, nx, dl + ar);
    return nx;
}

/* One cluster: the segs in[0..n) link cells lo..hi; w holds the windings
 * left of it (updated to those right of it), cin their colour. */
static void cluster(const ar_row *r, const ar_key *in, size_t n, int lo, int hi, int *w,
                    const double *cin)
{
    const ar_seg *seg = r->wk->seg;
    int j = r->j, events = 0, lines = 1;
    for (size_t k = 0; k < n; k++) {
        ar_seg *s = &r->wk->seg[in[k].idx];
        const ar_piece *p = s->p;
        band_fields(s, j);
        events |= p->flat || p->y0 > j || p->y1 < j + 1.0;
        lines &= p->flat || p->line;
    }
    if (hi >= 0) {
        const ar_key *mid = NULL;
        if (!events && n > AR_CROWD) {
            ar_key *keys = r->wk->sub;
            order_mid(r, in, n, lo, keys);
            events = neighbours_cross(r, keys, n);
            mid = keys;
        } else if (!events && n >= 2) {
            ar_key *keys = r->wk->sub;
            order_by_left(r, in, n, lo, keys);
            events = any_crossing(r, keys, n, lo);
        }
        if (!events) {
            int *wf = r->wk->wtmp; /* the sweep moves a copy; w moves below */
            memcpy(wf, w, (size_t)r->S->nl * sizeof *w);
            cluster_fast(r, in, n, lo, hi, wf, cin, mid);
            if (mid) {
                /* every seg spans the band: the sweep passed them all */
                memcpy(w, wf, (size_t)r->S->nl * sizeof *w);
                return;
            }
        } else if (!(r->integrator == INT_CATMULL && lines &&
                     (r->S->composite ? area_cluster_catmull_all(r, in, n, lo, hi, w)
                                      : area_cluster_catmull(r, in, n, lo, hi, w)))) {
            cluster_bands(r, in, n, lo, hi, w, cin);
        }
    }
    /* the windings right of the cluster are those of any line of the band */
    double yref = j + 0.5;
    for (size_t k = 0; k < n; k++) {
        const ar_piece *p = seg[in[k].idx].p;
        if (!p->flat && p->y0 <= yref && yref < p->y1)
            w[p->layer] += p->dir;
    }
}

/* ------------------------------------------------------------------------
 * Rows
 * ------------------------------------------------------------------------ */

/* Fill pixels [i0, i1) of a row of W with colour c, two pixels (three
 * 16-byte stores) at a time.  Before a cluster (i1 < W) the last pair may
 * run one pixel into it, which the cluster writes next: no alignment head,
 * no tail loop, so a short run costs one predictable loop (mispredicted
 * branches in the ~100 short runs of a `crow` row were measured as a large
 * part of the render).  If `stream`, non-temporal and exact (the image is
 * larger than the caches: the stores then do not read the lines first). */
#if AR_STREAM
/* n > 0 pixels from p in whole chunks of 4 (v0, v1, v2: the colour's
 * 16-byte pattern), running over by up to 3 pixels. */
static inline void fill_chunks(double *p, int n, __m128d v0, __m128d v1, __m128d v2)
{
    do {
        _mm_storeu_pd(p, v0);
        _mm_storeu_pd(p + 2, v1);
        _mm_storeu_pd(p + 4, v2);
        _mm_storeu_pd(p + 6, v0);
        _mm_storeu_pd(p + 8, v1);
        _mm_storeu_pd(p + 10, v2);
        p += 12, n -= 4;
    } while (n > 0);
}
#endif

static void fill(double *px, int i0, int i1, int W, const double *c, int stream)
{
    double *p = px + 3 * (size_t)i0;
    int n = i1 - i0;
    if (n <= 0)
        return;
#if AR_STREAM
    if (stream) {
        double *end = px + 3 * (size_t)i1, pat[8] = {c[0], c[1], c[2], c[0],
                                                       c[1], c[2], c[0], c[1]};
        long long bits[6];
        memcpy(bits, pat, sizeof bits);
        int ph = 0;
        if ((uintptr_t)p & 15) {
            _mm_stream_si64((long long *)p++, bits[0]);
            ph = 1;
        }
        __m128d v0 = _mm_loadu_pd(pat + ph), v1 = _mm_loadu_pd(pat + ph + 2),
                v2 = _mm_loadu_pd(pat + ph + 4);
        for (; end - p >= 6; p += 6) {
            _mm_stream_pd(p, v0);
            _mm_stream_pd(p + 2, v1);
            _mm_stream_pd(p + 4, v2);
        }
        for (int k = ph; p < end; k++)
            _mm_stream_si64((long long *)p++, bits[k % 6]);
        return;
    }
    __m128d v0 = _mm_set_pd(c[1], c[0]), v1 = _mm_set_pd(c[0], c[2]), v2 = _mm_set_pd(c[2], c[1]);
    if (i0 + ((n + 3) & ~3) <= W) {
        /* whole chunks of 4 pixels: every pixel after the run is written
         * again later in the row, so running over is harmless */
        fill_chunks(p, n, v0, v1, v2);
        return;
    }
    if (i1 == W)
        n &= ~1;
    for (; n > 0; n -= 2, p += 6) {
        _mm_storeu_pd(p, v0);
        _mm_storeu_pd(p + 2, v1);
        _mm_storeu_pd(p + 4, v2);
    }
#else
    (void)stream;
    double pat[6] = {c[0], c[1], c[2], c[0], c[1], c[2]};
    if (i1 == W)
        n &= ~1;
    for (; n > 0; n -= 2, p += 6)
        memcpy(p, pat, sizeof pat);
#endif
    if (i1 == W && ((i1 - i0) & 1))
        p[0] = c[0], p[1] = c[1], p[2] = c[2];
}

/* fill for the run [i0, i1), i0 < i1, before a cluster of row r: in a
 * row that does not stream, its whole chunks inline (the call, its tests
 * and its pattern's set-up were a sixth of crow's render); the same
 * stores. */
static inline void fill_run(const ar_row *r, int i0, int i1, const double *c)
{
#if AR_STREAM
    int n = i1 - i0;
    if (!r->stream && i0 + ((n + 3) & ~3) <= r->W) {
        fill_chunks(r->px + 3 * (size_t)i0, n, _mm_set_pd(c[1], c[0]), _mm_set_pd(c[0], c[2]),
                    _mm_set_pd(c[2], c[1]));
        return;
    }
#endif
    fill(r->px, i0, i1, r->W, c, r->stream);
}

/* Bring the active list to row j: the pieces meeting the band, those of
 * the rows before in the order they were left in (keep_order), the new
 * ones after them in the order of the sorted pieces.  A new piece's table
 * hint (ytab_guess) is set to the table's first interval: its first band
 * line lies there, a node or two down.  Left as the render before left it
 * (the table's last interval), the first root walked back over the whole
 * table, its nodes out of the caches; the start is the same from any hint,
 * so the roots are. */
static void update_active(const ar_state *S, ar_worker *wk, int j)
{
    if (wk->row != j - 1) {
        wk->nactive = 0;
        wk->next = 0;
        wk->first_end = INFINITY;
    }
    wk->row = j;
    double bottom = j + 1.0;
    size_t m = wk->nactive;
    if (wk->first_end <= j) { /* some piece has ended: drop those */
        double first_end = INFINITY;
        m = 0;
        for (size_t k = 0; k < wk->nactive; k++) {
            double y1 = S->piece[wk->active[k]].y1;
            if (y1 > j) {
                wk->active[m++] = wk->active[k];
                first_end = y1 < first_end ? y1 : first_end;
            }
        }
        wk->first_end = first_end;
    }
    wk->carried = m;
    while (wk->next < S->npieces && S->piece[wk->next].y0 < bottom) {
        double y1 = S->piece[wk->next].y1;
        if (y1 > j) {
            wk->active[m++] = (uint32_t)wk->next;
            wk->first_end = y1 < wk->first_end ? y1 : wk->first_end;
            wk->seg[wk->next].ythint = 0;
        }
        wk->next++;
    }
    wk->nactive = m;
}

/* The cluster of the one seg s (cells lo..hi) if single() writes it:
 * the run before it from pixel *x in colour *c, then the seg; w and *c
 * move past it, *x to the next pixel to write.  Returns 0 (nothing
 * written) if s is not of single's kind (in two cells with `batch`, as
 * side_ask found it: every such cluster passed there first).  Inline in
 * the rows' passes, the one-pass order's (close_cluster) and the sorted
 * pass's. */
__attribute__((always_inline)) static inline int close_single(const ar_row *r, const ar_seg *s,
                                                              int lo, int hi, int *x, int *w,
                                                              const double **c, const int plain,
                                                              const int batch)
{
    if (batch && hi - lo == 1 ? !s->kind
                              : !(s->cb - s->ca <= 1 && s->ca >= 0 && s->cb < r->W &&
                                  single_kind(r, s, plain)))
        return 0;
    if (lo > *x)
        fill_run(r, *x, lo, *c);
    *c = single(r, s, w, *c, plain, batch);
    *x = hi + 1;
    return 1;
}

/* Write the row from pixel x to the end of the cluster keys[0..n) (cells
 * lo..hi): the run before it in colour *c, then the cluster; w and *c move
 * past it.  Returns the next pixel to write.  A cluster of one seg single()
 * writes does not come here (close_single, first). */
static int flush(const ar_row *r, ar_key *keys, size_t n, int lo, int hi, int x, int *w,
                 const double **c)
{
    if (lo > x)
        fill_run(r, x, lo, *c);
    double cin[3] = {(*c)[0], (*c)[1], (*c)[2]};
    cluster(r, keys, n, lo, hi, w, cin);
    *c = colour_of(r->S, r->wk, w);
    return hi + 1 > x ? (hi + 1 > r->W ? r->W : hi + 1) : x;
}

/* The cluster list[0..n) of the one-pass order: keys in canonical order,
 * the same as the sorted pass gives it. */
__attribute__((noinline)) static int flush_list(const ar_row *r, const uint32_t *list,
                                                size_t n, int lo, int hi, int x, int *w,
                                                const double **c)
{
    ar_seg *seg = r->wk->seg;
    ar_key *keys = r->wk->order;
    for (size_t k = 0; k < n; k++) {
        keys[k].key = seg[list[k]].ca;
        keys[k].id = seg[list[k]].p->id;
        keys[k].idx = list[k];
    }
    sort_keys(keys, n); /* canonical order, however the segs came */
    return flush(r, keys, n, lo, hi, x, w, c);
}

/* The image's cells of a cluster: the pixels that took more than a fill. */
static inline uint64_t cells_of(int lo, int hi, int W)
{
    int a = lo < 0 ? 0 : lo, b = hi >= W ? W - 1 : hi;
    return b >= a ? (uint64_t)(b - a + 1) : 0;
}

/* flush_list, with the common single seg inline (a call per piece was
 * measured at a tenth of the render). */
__attribute__((always_inline)) static inline int close_cluster(const ar_row *r,
                                                               const uint32_t *list, size_t n,
                                                               int lo, int hi, int x, int *w,
                                                               const double **c, const int plain,
                                                               const int batch)
{
    if (n == 1 && close_single(r, &r->wk->seg[list[0]], lo, hi, &x, w, c, plain, batch))
        return x;
    return flush_list(r, list, n, lo, hi, x, w, c);
}

/* The active list put in the order of the row's sorted pass (keys[0..n),
 * the segs made from wk->list, in order of cell): those pieces first, in
 * that order, then the active pieces that made no seg in the row, in their
 * own order.  The next row's pieces then arrive nearly in x order, so its
 * one pass closes its clusters as they come or its sorted pass is an
 * insertion sort of the few that moved: on a stroke scene, whose pieces
 * come in path order, every row took the sorted pass and its heapsort.  The
 * clusters and their order are canonical whatever the active list's order
 * (each cluster sorted by (cell, id)), so the image is the same. */
static void keep_order(ar_worker *wk, const ar_key *keys, size_t n)
{
    uint32_t *act = wk->active;
    size_t rest = 0, i = 0;
    for (size_t k = 0; k < wk->nactive; k++) { /* wk->list is act's made segs, in order */
        if (i < n && act[k] == wk->list[i])
            i++;
        else
            act[rest++] = act[k];
    }
    memmove(act + n, act, rest * sizeof *act);
    for (size_t k = 0; k < n; k++)
        act[k] = keys[k].idx;
}

/* k[0..n) sorted by (key, id) (tmp: room for n), where its order is far
 * from x's (the pieces new in a band, in path order): runs of RUN_KEYS by
 * insertion, then merged in pairs.  sort_keys' insertion sort spent its
 * budget of moves on them first, then its heapsort sorted them again: 2.5 M
 * instructions a render on tests/bench_bezstroke.c's scene at 1024 px.  The
 * same order, (key, id) being a total one. */
#define RUN_KEYS 8
void area_sort_new_keys(ar_key *k, size_t n, ar_key *tmp)
{
    if (n <= 2 * RUN_KEYS) {
        sort_keys(k, n);
        return;
    }
    for (size_t a = 0; a < n; a += RUN_KEYS)
        sort_keys(k + a, n - a < RUN_KEYS ? n - a : RUN_KEYS);
    ar_key *src = k, *dst = tmp;
    for (size_t w = RUN_KEYS; w < n; w *= 2) {
        for (size_t a = 0; a < n; a += 2 * w) {
            size_t i = a, m = a + w < n ? a + w : n, j = m, e = a + 2 * w < n ? a + 2 * w : n;
            size_t o = a;
            while (i < m && j < e)
                dst[o++] = key_after(&src[i], &src[j]) ? src[j++] : src[i++];
            while (i < m)
                dst[o++] = src[i++];
            while (j < e)
                dst[o++] = src[j++];
        }
        ar_key *t = src;
        src = dst, dst = t;
    }
    if (src != k)
        memcpy(k, src, n * sizeof *k);
}

/* keys[0..n) sorted by (key, id) (`tmp`: room for n): the first nold (the
 * pieces carried from the rows before, kept in their x order there: few
 * out of place) and the rest (the pieces new in the band, nearly in x
 * order: sort_pieces) sorted apart, the new ones by insertion within 2
 * moves a key, else (pieces whose least x is far from their first row's)
 * by area_sort_new_keys, then merged.  (key, id) is a total order, so the
 * result is sort_keys' of all n. */
static void merge_keys(ar_key *keys, size_t nold, size_t n, ar_key *tmp)
{
    sort_keys(keys, nold);
    if (!insert_keys(keys + nold, n - nold, 2 * (n - nold)))
        area_sort_new_keys(keys + nold, n - nold, tmp);
    if (nold == 0 || nold == n || !key_after(&keys[nold - 1], &keys[nold]))
        return;
    size_t a = 0, b = nold, k = 0;
    while (a < nold && b < n)
        tmp[k++] = key_after(&keys[a], &keys[b]) ? keys[b++] : keys[a++];
    while (a < nold)
        tmp[k++] = keys[a++];
    memcpy(keys, tmp, k * sizeof *keys); /* keys[b..n) are in place */
}

/* A root band_roots found kept in its seg, with its point (line_point,
 * as offset_line_t's) */
static void band_root_done(const ar_piece *p, ar_seg *s, int j, const aa__offset_rootq *q)
{
    s->prej = j, s->pret = q->t;
    line_point(p, q->t, s->prexy, &s->prexy[0], &s->prexy[1]);
}

/* The roots of row j's bottom line y = j + 1 on its offset pieces that
 * seg_make takes there (every offset seg it makes reaching below the
 * line: offset_line's root for it), BAND_ROOTS at a time
 * (aa__offset_roots: the same roots and points, bit for bit, solved side
 * by side), kept in their segs for seg_make.  The active list gives the
 * pieces to come: the lines of the piece 2 BAND_AHEAD on (the first two
 * of ar_piece, what this loop reads) and its seg's hint are prefetched,
 * and the table nodes of the piece BAND_AHEAD on from its hint, which the
 * next line's walk (ytab_guess) starts from: loads, not values.  Four
 * nodes, the hint's line and the next two (a + 127): a band line is a
 * node or two on from the last, so the walk reads the node two on and
 * the interval it lands in, which the hint's line and the next alone
 * missed half the time (the 32-byte nodes two to a line). */
#define BAND_ROOTS 8
#define BAND_AHEAD 12
static void band_roots(const ar_state *S, ar_worker *wk, int j, int W)
{
    aa__offset_rootq q[BAND_ROOTS];
    const ar_piece *qp[BAND_ROOTS];
    ar_seg *qs[BAND_ROOTS];
    size_t n = 0;
    double yl = j + 1.0;
    for (size_t k = 0; k <= wk->nactive; k++) {
        if (k < wk->nactive) {
            uint32_t ix = wk->active[k];
            const ar_piece *p = &S->piece[ix];
            if (k + 2 * BAND_AHEAD < wk->nactive) {
                uint32_t ia = wk->active[k + 2 * BAND_AHEAD];
                const char *a = (const char *)&S->piece[ia];
                __builtin_prefetch(a), __builtin_prefetch(a + 64), __builtin_prefetch(a + 127);
                __builtin_prefetch(&wk->seg[ia].ythint);
            }
            if (k + BAND_AHEAD < wk->nactive) {
                uint32_t ia = wk->active[k + BAND_AHEAD];
                const ar_piece *pa = &S->piece[ia];
                size_t h = wk->seg[ia].ythint;
                if (pa->offset && h < pa->nyt) {
                    const char *a = (const char *)(pa->ytab + 4 * h);
                    __builtin_prefetch(a), __builtin_prefetch(a + 63), __builtin_prefetch(a + 127);
                }
            }
            if (!(p->curved && p->offset) || p->flat || p->xmin >= W || !(p->y1 > yl))
                continue;
            ar_seg *s = &wk->seg[ix];
            q[n] = (aa__offset_rootq){&p->src->oc, &p->ofix, 1, p->ot0, p->ot1, p->y0 - yl,
                                      yl, ytab_guess(p, yl, &s->ythint), p->oend, s->prexy,
                                      NULL, 0.0};
            qp[n] = p, qs[n++] = s;
            if (n < BAND_ROOTS)
                continue;
        }
        aa__offset_roots(q, n);
        for (size_t i = 0; i < n; i++)
            band_root_done(qp[i], qs[i], j, &q[i]);
        n = 0;
    }
}

/* The end of the sorted row's cluster that starts at keys[k] (the first
 * key past it) and its last cell (*hi) */
static inline size_t cluster_end(const ar_worker *wk, const ar_key *keys, size_t n, size_t k,
                                 int *hi)
{
    int h = wk->seg[keys[k].idx].cb;
    for (k++; k < n && wk->seg[keys[k].idx].ca <= h; k++)
        if (wk->seg[keys[k].idx].cb > h)
            h = wk->seg[keys[k].idx].cb;
    *hi = h;
    return k;
}

/* The batch's roots kept in their segs (side_taken's) */
static __attribute__((noinline)) void side_roots(aa__offset_rootq *q, ar_seg **qs, size_t n)
{
    aa__offset_roots(q, n);
    for (size_t i = 0; i < n; i++)
        qs[i]->pret = q[i].t;
}

/* The side root single() takes on seg s, alone in its cluster in two
 * cells, if s is an offset piece's of its kind (close_single's tests, on
 * the fields seg_make wrote, kept in s->kind whatever its piece:
 * close_single then takes them, and single() the root, without a test of
 * its own), asked in q[*n] (qs: the segs); the requests asked BAND_ROOTS at a
 * time when q is full (side_roots: aa__offset_roots, the same roots and
 * y, bit for bit, as offset_tau_u's alone), the rest by the caller
 * before the row's clusters close.  The clusters of one seg are known in
 * the one pass as the next cluster begins (render_row_k keeps those in
 * two cells in wk->side), in the sorted pass by a first walk of its
 * clusters (kept in wk->side for the second).  Of the segs of single's
 * kind in two cells, 22,024 a render at 1024 px and 3,792 at 256 px on
 * tests/bench_bezstroke.c's scene, 21,690 and 2,330 are alone in their
 * clusters and so asked here; the rest are in clusters of several. */
__attribute__((always_inline)) static inline void side_ask(const ar_row *r, ar_seg *s,
                                                          aa__offset_rootq *q, ar_seg **qs,
                                                          size_t *n)
{
    s->kind = s->ca >= 0 && s->cb < r->W && single_kind(r, s, 0);
    if (!(s->kind && s->p->curved && s->p->offset))
        return;
    double k = (double)(s->ca - s->c0) + 1.0; /* the common side, local */
    q[*n] = offset_side_q(s, s->ta, s->tb, s->ua - k, (double)s->c0 + k, s->ua, s->ub,
                          &s->prexy[1]);
    qs[(*n)++] = s;
    if (*n == BAND_ROOTS)
        side_roots(q, qs, *n), *n = 0;
}

/* Row j.  `plain`: S->plain, a constant in each of the three forms below
 * (render_row_plain, render_row_any, render_row_alone), chosen once a
 * row; `batch`: single()'s side roots asked in batches (side_ask). */
__attribute__((always_inline)) static inline void render_row_k(const ar_state *S, ar_worker *wk,
                                                               int j, int integrator, int stream,
                                                               aa_image *out, const int plain,
                                                               const int batch)
{
    int W = S->w;
    update_active(S, wk, j);
    ar_row r = {S, wk, j, W, integrator, stream, aa_pixel(out, 0, j), S->nch == 1 && !stream};
    int *w = wk->wind;
    memset(w, 0, (size_t)S->nl * sizeof *w);
    const double *c = colour_of(S, wk, w);
    if (!plain)
        band_roots(S, wk, j, W);
    /* One pass in the active list's order, which for most scenes (and
     * always for `crow`) is already the order along x: a cluster is written
     * as soon as a piece starts right of it.  A piece out of order sends the
     * row to the sorted pass below; both give the same clusters, each
     * sorted the same way, so the same image.  Rows with curved pieces
     * (not `plain`) make all their segs and check the order first, closing
     * the clusters after: their active list is kept in the last row's x
     * order (keep_order), where a piece that entered the band out of order
     * is found late in the row, and the clusters closed before it were
     * work thrown away. */
    size_t n = 0, first = 0, nold = 0, nq = 0, open = 0, ns = 0;
    int lo = 0, hi = 0, x = 0, ordered = 1;
    uint64_t cells = 0;
    aa__offset_rootq q[BAND_ROOTS];
    ar_seg *qs[BAND_ROOTS];
    for (size_t k = 0; k < wk->nactive; k++) {
        uint32_t ix = wk->active[k];
        const ar_piece *p = &S->piece[ix];
        if (p->xmin >= W || (p->flat && !(p->y0 > j && p->y0 < j + 1.0)))
            continue; /* right of the image, or flat on the band's edge */
        ar_seg *s = &wk->seg[ix];
        if (!seg_make(s, p, j, W, plain))
            continue;
        wk->list[n] = ix;
        nold += k < wk->carried;
        if (ordered && !plain) {
            /* not yet closed (below): a piece out of order late in the
             * row would throw away the clusters closed before it.  A
             * cluster of one seg (open: the cluster's first) is kept in
             * wk->side as the next begins, for side_ask */
            if (n == 0 || s->ca > hi) {
                if (batch && n - open == 1 && hi - lo == 1)
                    wk->side[ns++] = wk->list[open];
                open = n;
                lo = s->ca, hi = s->cb;
            } else if (s->ca >= lo) {
                hi = s->cb > hi ? s->cb : hi;
            } else {
                ordered = 0;
            }
        } else if (ordered) {
            if (n == first) {
                lo = s->ca, hi = s->cb;
            } else if (s->ca > hi) {
                cells += cells_of(lo, hi, W);
                x = close_cluster(&r, wk->list + first, n - first, lo, hi, x, w, &c, plain,
                                  batch);
                first = n;
                lo = s->ca, hi = s->cb;
            } else if (s->ca >= lo) {
                hi = s->cb > hi ? s->cb : hi;
            } else {
                ordered = 0;
            }
        }
        n++;
    }
    if (!plain && batch && ordered) {
        /* the side roots of the clusters of one seg, before any closes */
        if (n - open == 1 && hi - lo == 1)
            wk->side[ns++] = wk->list[open];
        for (size_t k = 0; k < ns; k++)
            side_ask(&r, &wk->seg[wk->side[k]], q, qs, &nq);
        if (nq)
            side_roots(q, qs, nq);
    }
    if (ordered && !plain) {
        for (size_t k = 0; k < n; k++) {
            const ar_seg *s = &wk->seg[wk->list[k]];
            if (k == first) {
                lo = s->ca, hi = s->cb;
            } else if (s->ca > hi) {
                cells += cells_of(lo, hi, W);
                x = close_cluster(&r, wk->list + first, k - first, lo, hi, x, w, &c, plain,
                                  batch);
                first = k;
                lo = s->ca, hi = s->cb;
            } else {
                hi = s->cb > hi ? s->cb : hi;
            }
        }
    }
    if (ordered) {
        if (n > first) {
            cells += cells_of(lo, hi, W);
            x = close_cluster(&r, wk->list + first, n - first, lo, hi, x, w, &c, plain, batch);
        }
        if (x < W)
            fill(r.px, x, W, W, c, stream);
        wk->expensive += cells;
        return;
    }
    /* the sorted pass, from the start of the row */
    ar_key *keys = wk->order;
    for (size_t k = 0; k < n; k++) {
        keys[k].key = wk->seg[wk->list[k]].ca;
        keys[k].id = wk->seg[wk->list[k]].p->id;
        keys[k].idx = wk->list[k];
    }
    if (plain) {
        sort_keys(keys, n);
    } else {
        merge_keys(keys, nold, n, wk->sub);
        keep_order(wk, keys, n);
    }
    if (!plain && batch) {
        /* the clusters found first (each one's end and hi in wk->side,
         * taken below) and the side roots of those of one seg asked
         * before any closes */
        size_t nc = 0;
        for (size_t k = 0; k < n;) {
            size_t f = k;
            int h;
            k = cluster_end(wk, keys, n, k, &h);
            wk->side[nc++] = (uint32_t)k, wk->side[nc++] = (uint32_t)h;
            if (k - f == 1 && h - wk->seg[keys[f].idx].ca == 1)
                side_ask(&r, &wk->seg[keys[f].idx], q, qs, &nq);
        }
        if (nq)
            side_roots(q, qs, nq);
    }
    memset(w, 0, (size_t)S->nl * sizeof *w);
    c = colour_of(S, wk, w);
    x = 0;
    for (size_t k = 0, nc = 0; k < n; nc += 2) {
        first = k;
        lo = wk->seg[keys[k].idx].ca;
        if (!plain && batch)
            k = wk->side[nc], hi = (int)wk->side[nc + 1];
        else
            k = cluster_end(wk, keys, n, k, &hi);
        wk->expensive += cells_of(lo, hi, W);
        /* a seg alone that single() writes inline, as in the one pass:
         * through flush it paid a call, a copy of the colour and a
         * colour_of after single's (tests/bench_bezstroke.c's scene at
         * 1024 px: 19,084 of the sorted pass's 23,944 clusters a render) */
        if (!(k - first == 1 && close_single(&r, &wk->seg[keys[first].idx], lo, hi, &x, w, &c,
                                             plain, batch)))
            x = flush(&r, keys + first, k - first, lo, hi, x, w, &c);
    }
    if (x < W)
        fill(r.px, x, W, W, c, stream);
}

/* The rows of a scene of lines and quadratics (crow and most polygons),
 * compiled without the curved pieces' cases, and of any scene. */
static void render_row_plain(const ar_state *S, ar_worker *wk, int j, int integrator, int stream,
                             aa_image *out)
{
    render_row_k(S, wk, j, integrator, stream, out, 1, 0);
}

static void render_row_any(const ar_state *S, ar_worker *wk, int j, int integrator, int stream,
                           aa_image *out)
{
    render_row_k(S, wk, j, integrator, stream, out, 0, 1);
}

/* render_row_any with single()'s side roots asked alone (aa__area_side_batch
 * 0: for a test) */
static void render_row_alone(const ar_state *S, ar_worker *wk, int j, int integrator,
                             int stream, aa_image *out)
{
    render_row_k(S, wk, j, integrator, stream, out, 0, 0);
}

int aa__area_side_batch = 1;

int aa__area_rowpt = 1;

/* Row j of a scene with gradient paint (area_gradient.c): the clusters
 * as the sorted pass finds them, every cluster by Catmull's integrater
 * split on every edge and every run between clusters pixel by pixel, each
 * region's integral of the decoded composite exact.  No colour-jump sum:
 * the colour varies inside a region. */
static void render_row_gradient(const ar_state *S, ar_worker *wk, int j, aa_image *out)
{
    int W = S->w;
    update_active(S, wk, j);
    ar_row r = {S, wk, j, W, INT_CATMULL, 0, aa_pixel(out, 0, j), 0};
    int *w = wk->wind;
    memset(w, 0, (size_t)S->nl * sizeof *w);
    ar_key *keys = wk->order;
    size_t n = 0;
    for (size_t k = 0; k < wk->nactive; k++) {
        uint32_t ix = wk->active[k];
        const ar_piece *p = &S->piece[ix];
        if (p->xmin >= W || (p->flat && !(p->y0 > j && p->y0 < j + 1.0)))
            continue;
        ar_seg *s = &wk->seg[ix];
        if (!seg_make(s, p, j, W, 1)) /* lines only (area_gradient_load) */
            continue;
        keys[n].key = s->ca;
        keys[n].id = p->id;
        keys[n].idx = ix;
        n++;
    }
    sort_keys(keys, n);
    int x = 0;
    for (size_t k = 0; k < n;) {
        size_t first = k;
        int lo = wk->seg[keys[k].idx].ca, hi = wk->seg[keys[k].idx].cb;
        for (k++; k < n && wk->seg[keys[k].idx].ca <= hi; k++)
            if (wk->seg[keys[k].idx].cb > hi)
                hi = wk->seg[keys[k].idx].cb;
        wk->expensive += cells_of(lo, hi, W);
        if (lo > x)
            area_gradient_run(&r, x, lo, w);
        for (size_t q = first; q < k; q++)
            band_fields(&wk->seg[keys[q].idx], j);
        if (hi >= 0)
            area_cluster_gradient(&r, keys + first, k - first, lo, hi, w);
        /* the windings right of the cluster are those of any line of the band */
        double yref = j + 0.5;
        for (size_t q = first; q < k; q++) {
            const ar_piece *p = wk->seg[keys[q].idx].p;
            if (!p->flat && p->y0 <= yref && yref < p->y1)
                w[p->layer] += p->dir;
        }
        x = hi + 1 > x ? (hi + 1 > W ? W : hi + 1) : x;
    }
    if (x < W)
        area_gradient_run(&r, x, W, w);
}

/* The first pixel a worker refused in a gradient scene, in row order,
 * reported (AA_OK if none). */
static int gradient_refusal(const ar_state *S)
{
    const ar_worker *f = NULL;
    for (int t = 0; t < S->nworkers; t++) {
        const ar_worker *wk = &S->workers[t];
        if (wk->gerr && (!f || wk->gj < f->gj || (wk->gj == f->gj && wk->gi < f->gi)))
            f = wk;
    }
    if (!f)
        return AA_OK;
    if (f->gerr == AR_GERR_TWO_GRADIENTS)
        return aa_fail(AA_EINVAL,
                       "area: pixel (%d, %d): the gradients of layers %d and %d both show "
                       "there, one composited over the other: the composite is a product of "
                       "two functions of the position and the integral of its sRGB decoding "
                       "has no closed form; refused, not approximated (use point, "
                       "supersample or jitter)",
                       f->gi, f->gj, f->ga, f->gb);
    if (f->gerr == AR_GERR_LINEAR_LIGHT)
        return aa_fail(AA_EINVAL,
                       "area: pixel (%d, %d): layer %d's gradient in linear light "
                       "(color-interpolation: linearRGB) shows there translucent or under "
                       "something translucent, where its encoded colour composited and "
                       "decoded has no closed-form integral (area draws it exactly where it "
                       "shows opaque with nothing over it); refused, not approximated (use "
                       "point, supersample or jitter)",
                       f->gi, f->gj, f->ga);
    if (f->gerr == AR_GERR_EDGES)
        return aa_fail(AA_EINVAL,
                       "area: pixel (%d, %d) of a gradient scene holds more than %d edges, "
                       "Catmull's integrater's limit (the bands that take such pixels in "
                       "scenes of flat colour integrate constant colours only): refused",
                       f->gi, f->gj, f->ga);
    return aa_fail(AA_EINVAL,
                   "area: pixel (%d, %d): layer %d's gradient passes more than %d stops or "
                   "period ends along one edge: refused",
                   f->gi, f->gj, f->ga, 4 * AR_GKNOTS);
}

/* ------------------------------------------------------------------------
 * State
 * ------------------------------------------------------------------------ */

static void state_free(ar_state *S)
{
    for (int t = 0; t < S->nworkers; t++) {
        ar_worker *wk = &S->workers[t];
        free(wk->active);
        free(wk->seg);
        free(wk->list);
        free(wk->side);
        free(wk->order);
        free(wk->sub);
        free(wk->tops);
        free(wk->ends);
        free(wk->vab);
        free(wk->acc);
        free(wk->cov);
        free(wk->wind);
        free(wk->wtmp);
        free(wk->ev);
        free(wk->cx);
        free(wk->mark);
        free(wk->act);
        free(wk->pend);
        free(wk->cm);
        free(wk->ckey);
        free(wk->key);
        free(wk->ccol);
        free(wk->cslot);
        free(wk->gkey);
        free(wk->gmemo);
    }
    free(S->workers);
    free(S->piece);
    free(S->ldir);
    free(S->colour);
    free(S->evenodd);
    free(S->inside);
    free(S->pan);
    free(S->ytab);
    area_gradient_free(S);
    memset(S, 0, sizeof *S);
}

/* A node of an offset piece's table of band lines' starts (ytab_guess) */
static void yt_node_of(const double e[4], double t, double nd[4])
{
    nd[0] = t, nd[1] = e[0] + e[1], nd[2] = 1.0 / e[2], nd[3] = 0.0;
}

/* On the double-double form's curves (q->ofix.dd) by aa__offset_end_dd:
 * the same sum and slope without the stops' tests, bit for bit (about a
 * fifth of the evaluation's instructions) */
static void yt_node(const ar_piece *q, double t, double nd[4])
{
    const aa_offset_curve *oc = &q->src->oc;
    if (q->ofix.dd) {
        double at, slope;
        aa__offset_end_dd(oc, 1, t, &at, &slope);
        nd[0] = t, nd[1] = at, nd[2] = 1.0 / slope, nd[3] = 0.0;
        return;
    }
    double e[4];
    aa__offset_end(oc, 1, t, e);
    yt_node_of(e, t, nd);
}

/* More room for the tables' nodes (load_pieces gives them all they need
 * at once: not taken) */
static __attribute__((noinline, cold)) int yt_grow(ar_state *S)
{
    size_t cap = S->capyt ? 2 * S->capyt : 1024;
    double *t = realloc(S->ytab, cap * 4 * sizeof *t);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for offset pieces' tables");
    S->ytab = t, S->capyt = cap;
    return AA_OK;
}

static inline int yt_push(ar_state *S, const double nd[4], int ok)
{
    int st;
    if (S->nyt == S->capyt && (st = yt_grow(S)))
        return st;
    double *o = S->ytab + 4 * S->nyt++;
    o[0] = nd[0], o[1] = nd[1], o[2] = nd[2], o[3] = ok ? 1.0 : 0.0;
    return AA_OK;
}

/* The nodes after a, up to b (a pushed already) */
static int yt_rec(ar_state *S, const ar_piece *q, const double a[4], const double b[4],
                  int depth, int dmax)
{
    double m[4];
    yt_node(q, 0.5 * (a[0] + b[0]), m);
    int ok = fabs(yt_herm(a, b, m[1]) - m[0]) <= YT_TOL;
    double ch = fabs((b[0] - a[0]) / (b[1] - a[1]));
    int turn = !(fabs(a[2]) <= YT_TURN * ch && fabs(b[2]) <= YT_TURN * ch);
    if (!ok && depth >= dmax && dmax < YT_DEPTH) /* stopped by the piece's rows */
        ok = fabs(yt_herm(a, b, m[1]) - m[0]) <= YT_ROWS_TOL;
    if (ok || depth >= dmax || (depth >= YT_MIN && turn)) {
        int st = yt_push(S, m, ok);
        return st ? st : yt_push(S, b, ok);
    }
    int st = yt_rec(S, q, a, m, depth + 1, dmax);
    return st ? st : yt_rec(S, q, m, b, depth + 1, dmax);
}

/* An offset piece: tau = sg t rising down it, its x turns in tau, its
 * panels appended to S->pan (q->pan is set when all are made: the array
 * moves as it grows). */
static int load_offset(ar_state *S, ar_piece *q, const aa_piece *p)
{
    q->offset = 1;
    q->ot0 = p->ot0, q->ot1 = p->ot1;
    q->sg = p->ot1 > p->ot0 ? 1.0 : -1.0;
    aa__offset_end(&p->oc, 1, p->ot1, q->oend);
    q->ostops = aa__offset_stops(&p->oc);
    aa__offset_fix_dd(&p->oc, &q->ofix, 1);
    double ts[2];
    int n = aa__offset_turns(&p->oc, 0, fmin(p->ot0, p->ot1), fmax(p->ot0, p->ot1), ts);
    q->ote = q->ote2 = INFINITY;
    if (n > 0) {
        double a = q->sg * ts[0], b = n > 1 ? q->sg * ts[1] : INFINITY;
        q->ote = a < b ? a : b;
        q->ote2 = n > 1 ? (a < b ? b : a) : INFINITY;
    }
    size_t n0 = S->npan;
    int st = area_offset_panels_append(&p->oc, p->ot0, p->ot1, &S->pan, &S->npan, &S->cappan);
    if (st)
        return st;
    q->pan0 = n0;
    q->npan = S->npan - n0;
    q->quad = &S->quad;
    return AA_OK;
}

/* The most halvings of an offset piece's table: to about two rows an
 * interval (YT_ROWS), at most YT_DEPTH (-1: none) */
static int yt_dmax(const ar_piece *q)
{
    double rows = ceil(q->y1) - floor(q->y0), span = 0.5 * YT_ROWS; /* YT_ROWS 2^dmax */
    int dmax = -1;
    while (dmax < YT_DEPTH && span < rows)
        dmax++, span *= 2.0;
    return dmax;
}

/* An offset piece's table of band lines' starts, appended to S->ytab
 * (after every piece's panels: the two arrays grown in turns were copied
 * on most of their reallocations) */
static int load_ytab(ar_state *S, ar_piece *q)
{
    const aa_piece *p = q->src;
    double a[4], b[4];
    yt_node(q, p->ot0, a);
    yt_node_of(q->oend, p->ot1, b); /* its bottom's evaluation, load_offset's */
    q->yt0 = S->nyt;
    int dmax = yt_dmax(q);
    int st = yt_push(S, a, 0);
    if (st || (st = yt_rec(S, q, a, b, 0, dmax)))
        return st;
    q->nyt = S->nyt - q->yt0;
    /* the nodes' y rising strictly (ytab_guess's walk), else no table */
    for (size_t k = 1; k < q->nyt; k++)
        if (!(S->ytab[4 * (q->yt0 + k) + 1] > S->ytab[4 * (q->yt0 + k - 1) + 1])) {
            S->nyt = q->yt0, q->nyt = 0;
            break;
        }
    return AA_OK;
}

/* The row a piece enters the active list in (update_active: the first
 * row j with y0 < j + 1), those above the image in row 0 */
static inline double first_row(double y0)
{
    return y0 > 0.0 ? floor(y0) : 0.0;
}

/* The pieces put in order by the row they enter in (first_row), then by
 * (xmin, id), a total order: their keys sorted by (xmin, id)
 * (area_sort_new_keys, the comparison inline), then counted into their
 * rows in that order, and each piece copied once into its place.  The
 * pieces new in a row then come nearly in the order of their cells
 * (merge_keys): in (y0, id) order, a stroke's pieces came in path order,
 * and their sort was 1.0 M instructions a render on
 * tests/bench_bezstroke.c's scene at 1024 px.  A scene whose pieces begin
 * more rows down than twice their count (a piece far below) takes the
 * order by (y0, id): every row counted would cost more than the sort (and
 * so does one whose counts find no memory: the same rows, slower).  qsort
 * called its comparison through a pointer and permuted the pieces after
 * sorting pointers to them: 4.6 M instructions of the init at 1024 px. */
static int sort_pieces(ar_state *S)
{
    size_t n = S->npieces;
    if (n < 2)
        return AA_OK;
    ar_key *k = malloc(2 * n * sizeof *k);
    if (!k)
        return aa_fail(AA_ENOMEM, "out of memory for %zu pieces' order", n);
    ar_piece *p = S->piece;
    double last = 0.0;
    for (size_t i = 0; i < n; i++) {
        double r = first_row(p[i].y0);
        last = r > last ? r : last;
    }
    size_t *at = last <= (double)(2 * n) ? calloc((size_t)last + 2, sizeof *at) : NULL;
    if (at) {
        for (size_t i = 0; i < n; i++)
            k[i].key = p[i].xmin, k[i].id = p[i].id, k[i].idx = (uint32_t)i;
        area_sort_new_keys(k, n, k + n);
        for (size_t i = 0; i < n; i++) /* at[r + 1]: the pieces entering in row r */
            at[(size_t)first_row(p[i].y0) + 1]++;
        for (size_t r = 1; r <= (size_t)last; r++) /* at[r]: where row r's begin */
            at[r] += at[r - 1];
        for (size_t i = 0; i < n; i++)
            k[n + at[(size_t)first_row(p[k[i].idx].y0)]++] = k[i];
        memcpy(k, k + n, n * sizeof *k);
        free(at);
    } else {
        for (size_t i = 0; i < n; i++)
            k[i].key = p[i].y0, k[i].id = p[i].id, k[i].idx = (uint32_t)i;
        area_sort_new_keys(k, n, k + n);
    }
    /* in place, a cycle of the permutation at a time (k[j].idx = j: done) */
    for (size_t i = 0; i < n; i++) {
        if (k[i].idx == i)
            continue;
        ar_piece t = p[i];
        size_t j = i;
        for (size_t from; (from = k[j].idx) != i; j = from)
            p[j] = p[from], k[j].idx = (uint32_t)j;
        p[j] = t, k[j].idx = (uint32_t)j;
    }
    free(k);
    return AA_OK;
}

/* Panels an offset piece, the first guess at their room (4.4 on
 * tests/bench_bezstroke.c's scene at 1024 px, 2.4 at 256 px) */
#define PAN_GUESS 6

static int load_pieces(ar_state *S, const aa_scene *scene)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(scene, &n);
    if (n >= UINT32_MAX)
        return aa_fail(AA_EINVAL, "area: %zu pieces, more than it indexes", n);
    if (n && !(S->piece = calloc(n, sizeof *S->piece)))
        return aa_fail(AA_ENOMEM, "out of memory for %zu pieces", n);
    S->npieces = n;
    S->plain = 1;
    int st = area_quad_init(&S->quad);
    if (st)
        return st;
    /* the panels' room for PAN_GUESS a piece at once (grown as needed:
     * each reallocation copied them all) */
    size_t noff = 0;
    for (size_t k = 0; k < n; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    if (noff && !(S->pan = malloc(noff * PAN_GUESS * sizeof *S->pan)))
        return aa_fail(AA_ENOMEM, "out of memory for offset pieces' panels");
    S->cappan = noff * PAN_GUESS;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *p = &pc[k];
        ar_piece *q = &S->piece[k];
        long double x0 = p->x0, cx = p->cx, x1 = p->x1, y0 = p->y0, cy = p->cy, y1 = p->y1;
        q->flat = p->kind == AA_PIECE_FLAT;
        q->line = p->kind == AA_PIECE_LINE || p->kind == AA_PIECE_FLAT;
        q->cubic = p->kind == AA_PIECE_CUBIC;
        q->conic = p->kind == AA_PIECE_CONIC;
        q->curved = q->cubic || q->conic || p->kind == AA_PIECE_OFFSET;
        S->plain &= !q->curved;
        q->src = p;
        if (p->kind == AA_PIECE_OFFSET && (st = load_offset(S, q, p)))
            return st;
        q->x0 = x0, q->y0l = y0;
        q->dx = q->dy = 0;
        if (q->cubic) {
            long double c1x = cx, c1y = cy, c2x = p->c2x, c2y = p->c2y;
            q->bx = 3 * (c1x - x0), q->ax = 3 * (x0 - 2 * c1x + c2x);
            q->dx = (x1 - x0) + 3 * (c1x - c2x);
            q->by = 3 * (c1y - y0), q->ay = 3 * (y0 - 2 * c1y + c2y);
            q->dy = (y1 - y0) + 3 * (c1y - c2y);
        } else if (p->kind == AA_PIECE_QUAD) {
            q->ax = x0 - 2 * cx + x1, q->bx = 2 * (cx - x0);
            q->ay = y0 - 2 * cy + y1, q->by = 2 * (cy - y0);
        } else {
            q->ax = 0, q->bx = x1 - x0;
            q->ay = 0, q->by = y1 - y0;
        }
        q->y0 = p->y0, q->y1 = p->y1;
        q->xmin = p->xmin, q->xmax = p->xmax;
        q->byd = (double)q->by, q->ayd = (double)q->ay, q->dyd = (double)q->dy;
        /* y'(t) x'' - x'(t) y'' = (by + 2 ay t) 2 ax - (bx + 2 ax t) 2 ay
         * = 2 (by ax - bx ay) for every t */
        q->k6 = (double)((q->by * q->ax - q->bx * q->ay) / 6.0L);
        if (q->conic) /* the elliptic segment's factor (part_area) */
            q->k6 = -0.5 * p->eb * p->er;
        q->dir = p->dir;
        q->layer = p->layer;
        q->id = (uint32_t)k;
    }
    /* the tables' room at once, at most a node where yt_rec starts and two
     * a leaf, 2^dmax leaves (each reallocation copied the nodes: 1.9 M
     * instructions of the init on tests/bench_bezstroke.c's scene) */
    size_t nodes = 0;
    for (size_t k = 0; k < n; k++)
        if (S->piece[k].offset) {
            int d = yt_dmax(&S->piece[k]);
            nodes += 1 + ((size_t)2 << (d > 0 ? d : 0));
        }
    if (nodes && !(S->ytab = malloc(nodes * 4 * sizeof *S->ytab)))
        return aa_fail(AA_ENOMEM, "out of memory for offset pieces' tables");
    S->capyt = nodes;
    for (size_t k = 0; k < n; k++)
        if (S->piece[k].offset && (st = load_ytab(S, &S->piece[k])))
            return st;
    /* long double wider than double, as the platform declares it (under
     * valgrind, whose x87 rounds to double, the row's point is still taken,
     * B(m)'s lo then about an ulp of hi short: valgrind's images are not
     * exact to 1e-14) */
    const int extended = LDBL_MANT_DIG > DBL_MANT_DIG;
    for (size_t k = 0; k < n; k++)
        if (S->piece[k].offset) {
            ar_piece *q = &S->piece[k];
            q->pan = S->pan + q->pan0;
            ytab_attach(q, S->ytab + 4 * q->yt0);
            /* the map's |M|^2 / |det| (Frobenius) is c + 1/c, c its condition number */
            const double *m = q->src->oc.m;
            double det = m[0] * m[3] - m[1] * m[2];
            q->rowpt = aa__area_rowpt && extended &&
                       (m[0] * m[0] + m[1] * m[1] + m[2] * m[2] + m[3] * m[3]) <= 4.25 * fabs(det);
        }
    st = sort_pieces(S);
    if (st)
        return st;
    if (!(S->ldir = malloc((n ? n : 1) * sizeof *S->ldir)))
        return aa_fail(AA_ENOMEM, "out of memory for %zu pieces' layers", n);
    for (size_t k = 0; k < n; k++)
        S->ldir[k] = 4 * S->piece[k].layer + S->piece[k].dir + 1;
    return AA_OK;
}

static int load_colours(ar_state *S, const aa_scene *scene)
{
    int nl = aa_scene_layer_count(scene);
    S->nl = nl;
    S->colour = calloc((size_t)nl + 1, sizeof *S->colour);
    S->evenodd = calloc((size_t)nl + 1, sizeof *S->evenodd);
    S->inside = calloc((size_t)nl + 1, sizeof *S->inside);
    if (!S->colour || !S->evenodd || !S->inside)
        return aa_fail(AA_ENOMEM, "out of memory for %d layers", nl);
    for (int l = 0; l <= nl; l++) {
        aa_rgb c = l < nl ? aa_scene_layer_colour(scene, l) : aa_scene_background(scene);
        memcpy(S->colour[l], c.c, sizeof c.c);
        if (l < nl) {
            S->evenodd[l] = aa_scene_layer_rule(scene, l) == AA_FILL_EVENODD;
            S->inside[l] = S->evenodd[l] ? 1 : ~0;
        }
    }
    /* greys composite to greys (every channel the same arithmetic) */
    S->nch = aa_scene_is_grey(scene) ? 1 : 3;
    S->composite = !aa_scene_is_opaque(scene);
    S->nscan = S->composite ? 0 : nl;
    S->nwords = (nl + 63) / 64 > 0 ? (nl + 63) / 64 : 1;
    return AA_OK;
}

/* n items of `size` bytes on whole cache lines of their own, zeroed if
 * `zero` (else as the allocator gives them). */
static void *line_alloc_as(size_t n, size_t size, int zero)
{
    if (n && size > (SIZE_MAX - 64) / n)
        return NULL;
    size_t bytes = (n * size + 63) & ~(size_t)63;
    void *p = aligned_alloc(64, bytes ? bytes : 64);
    if (p && zero)
        memset(p, 0, bytes ? bytes : 64);
    return p;
}

static void *line_alloc(size_t n, size_t size)
{
    return line_alloc_as(n, size, 1);
}

static int worker_alloc(ar_worker *wk, const ar_state *S)
{
    size_t n = S->npieces ? S->npieces : 1, cells = ((size_t)S->w + 2) * (size_t)S->nch;
    size_t nl = (size_t)(S->nl > 0 ? S->nl : 1);
    /* Not cleared (the last argument 0): the lists of indices and keys and
     * the clip's levels are written up to their counts before they are
     * read, and a seg's fields by seg_make, expand and band_fields (its kind
     * by side_ask, read only on the segs it asked in the row), but for
     * those set below (its piece none, no anchor, no band line kept, its
     * table's hint the first interval, no x kept at a pair's ends, no
     * root of band_roots).
     * Clearing them was 6.4 M instructions of the init on
     * tests/bench_bezstroke.c's scene at 1024 px. */
    wk->active = line_alloc_as(n, sizeof *wk->active, 0);
    wk->seg = line_alloc_as(n, sizeof *wk->seg, 0);
    wk->list = line_alloc_as(n, sizeof *wk->list, 0);
    wk->side = line_alloc_as(2 * n, sizeof *wk->side, 0);
    wk->order = line_alloc_as(n, sizeof *wk->order, 0);
    wk->sub = line_alloc_as(3 * n, sizeof *wk->sub, 0);
    /* not cleared either (read only where written); by line_alloc_as as the
     * others: a plain malloc of it, between them, had glibc hand each init
     * fresh pages (page faults of a benchmark run 25.1 k to 39.7 k, the init
     * at 1024 px about 10 to 16 ms of CPU) */
    wk->tops = line_alloc_as(n, sizeof *wk->tops, 0);
    wk->ends = line_alloc_as(2 * n, sizeof *wk->ends, 0);
    wk->vab = line_alloc_as(2 * n, sizeof *wk->vab, 0);
    wk->acc = line_alloc(cells, sizeof *wk->acc);
    wk->cov = line_alloc(cells, sizeof *wk->cov);
    wk->wind = line_alloc(nl, sizeof *wk->wind);
    wk->wtmp = line_alloc(nl, sizeof *wk->wtmp);
    wk->ev = line_alloc(CM_MAX_EVENTS, sizeof *wk->ev);
    wk->cx = line_alloc(CM_MAX_EVENTS, sizeof *wk->cx);
    wk->ev_room = wk->cx_room = CM_MAX_EVENTS;
    wk->mark = line_alloc(n, sizeof *wk->mark);
    wk->act = line_alloc_as(n, sizeof *wk->act, 0);
    wk->pend = line_alloc_as(n, sizeof *wk->pend, 0);
    wk->cm = line_alloc_as(CM_MAX_EDGES + 2, sizeof *wk->cm, 0);
    if (S->composite) {
        wk->ckey = line_alloc((size_t)AR_CACHE_ENTRIES * (size_t)S->nwords, sizeof *wk->ckey);
        wk->key = line_alloc((size_t)S->nwords, sizeof *wk->key);
        wk->ccol = line_alloc(AR_CACHE_ENTRIES, sizeof *wk->ccol);
        wk->cslot = line_alloc(AR_CACHE_SLOTS, sizeof *wk->cslot);
        if (!wk->ckey || !wk->key || !wk->ccol || !wk->cslot)
            return aa_fail(AA_ENOMEM, "out of memory for an area colour cache (%d layers)",
                           S->nl);
        for (size_t k = 0; k < AR_CACHE_SLOTS; k++)
            wk->cslot[k] = -1;
    }
    if (S->ngrad) {
        wk->gkey = line_alloc((size_t)(AR_GMEMO + 1) * (size_t)S->nwords, sizeof *wk->gkey);
        wk->gmemo = line_alloc(AR_GMEMO, sizeof *wk->gmemo);
        if (!wk->gkey || !wk->gmemo)
            return aa_fail(AA_ENOMEM, "out of memory for an area gradient memo (%d layers)",
                           S->nl);
    }
    wk->row = -2;
    if (wk->seg)
        for (size_t k = 0; k < n; k++) {
            ar_seg *s = &wk->seg[k];
            s->p = NULL, s->ja = s->mline = s->prej = INT_MIN, s->ythint = 0;
            s->xy[0] = s->xy[1] = NAN;
        }
    if (!wk->active || !wk->seg || !wk->list || !wk->order || !wk->sub || !wk->acc || !wk->cov ||
        !wk->wind || !wk->wtmp || !wk->ev || !wk->cx || !wk->mark || !wk->cm || !wk->act ||
        !wk->pend || !wk->tops || !wk->ends || !wk->vab || !wk->side)
        return aa_fail(AA_ENOMEM, "out of memory for an area workspace (%zu pieces, %d px)", n,
                       S->w);
    return AA_OK;
}

/* Tables and workspaces for this job, made outside any timing (init), or
 * again if a render asks for another scene, width or more threads. */
static int state_ready(ar_state *S, const aa_job *job)
{
    if (S->scene == job->placed && S->w == job->w && S->nworkers >= job->threads)
        return AA_OK;
    state_free(S);
    S->w = job->w;
    int st;
    if ((st = load_pieces(S, job->placed)) || (st = load_colours(S, job->placed)) ||
        (st = area_gradient_load(S, job->placed)))
        goto fail;
    if (!(S->workers = line_alloc((size_t)job->threads, sizeof *S->workers))) {
        st = aa_fail(AA_ENOMEM, "out of memory for %d workers", job->threads);
        goto fail;
    }
    S->nworkers = job->threads;
    for (int t = 0; t < job->threads; t++)
        if ((st = worker_alloc(&S->workers[t], S)))
            goto fail;
    S->scene = job->placed;
    return AA_OK;
fail:
    state_free(S);
    return st;
}

/* ------------------------------------------------------------------------
 * The method
 * ------------------------------------------------------------------------ */

static int area_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "area integrates the box filter exactly and no other "
                                  "(use -f box; no other filter is supported)");
    return AA_OK;
}

/* The exact integration is of edges: a field scene has none (it would come
 * out as the background).  aa_method_init refuses it already, since the
 * type does not declare AA_METHOD_FIELDS; this is for direct calls. */
static int refuse_field(const aa_job *job)
{
    const aa_field_type *field = aa_scene_field(job->placed, NULL, NULL, NULL);
    if (field)
        return aa_fail(AA_EINVAL, "area integrates the edges of scenes of paths exactly; "
                                  "pattern %s is a procedural field without edges (its exact "
                                  "values are the reference itself): use a sampling method",
                       field->name);
    /* gradient paint: what area_gradient.c cannot integrate exactly is
     * refused when the state is made (area_gradient_load) */
    return AA_OK;
}

static int area_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    int st = refuse_field(job);
    return st ? st : state_ready(state, job);
}

static int area_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    ar_state *S = state;
    int st = refuse_field(job);
    if (!st)
        st = state_ready(S, job);
    if (st)
        return st;
    int integrator = (int)p[P_INTEGRATOR];
    /* non-temporal stores pay when the image does not fit in the caches */
    int stream = (double)job->w * job->h * 3 * sizeof(double) > STREAM_BYTES;
    uint64_t expensive = 0;
#pragma omp parallel num_threads(job->threads) reduction(+ : expensive)
    {
        ar_worker *wk = &S->workers[omp_get_thread_num()];
        wk->row = -2;
        wk->expensive = 0;
        wk->gerr = 0;
        wk->gn = 0, wk->gnext = 0;
#pragma omp for schedule(static)
        for (int j = 0; j < job->h; j++) {
            if (S->ngrad)
                render_row_gradient(S, wk, j, out);
            else
                (S->plain           ? render_row_plain
                 : aa__area_side_batch ? render_row_any
                                   : render_row_alone)(S, wk, j, integrator, stream, out);
        }
#if AR_STREAM
        if (stream)
            _mm_sfence(); /* order the non-temporal stores before the join */
#endif
        expensive += wk->expensive;
    }
    if (S->ngrad && (st = gradient_refusal(S)))
        return st;
    counters->samples = 0;
    counters->expensive_pixels = expensive;
    return AA_OK;
}

static void area_release(void *state)
{
    state_free(state);
}

const aa_method_type aa_method_area = {
    {"area",
     "exact box-filter area (Catmull 1978; Crow fig. 3.13), arcs integrated exactly; linear "
     "gradients exactly on scenes of straight edges (radial gradients, gradients with arcs, "
     "two gradients over one point refused)",
     area_params},
    sizeof(ar_state),
    AA_METHOD_GRADIENTS,
    area_check,
    area_init,
    area_render,
    area_release};
