/*
 * test_area_offset.c: `area` (algorithms/area.c, area_offset.c) on strokes
 * of Bezier arcs, whose outlines hold offset curves and evolutes
 * (AA_PIECE_OFFSET), against answers it does not compute itself:
 *
 *  - the box reference (harness/truth, its own integration of the same
 *    pieces: scanline crossings, then QAG over y), to 1e-12 per pixel, on
 *    a gentle arc, tight arcs whose offsets fold, a loop, a hook, three
 *    arcs with round joins and caps at two widths, dashes, a shear, and
 *    cusps (inside, and a control point on the start);
 *    with both integrators, and the same image on one thread and on two;
 *  - the tube formula: a butt-capped arc whose curvature radius exceeds
 *    half the width everywhere covers width x arc length (the normals do
 *    not cross), the arc length by GSL's QAG (61-point Gauss-Kronrod,
 *    1e-13); `area`'s image summed (a white shape's box image sums to its
 *    area), to 1e-12, and the same on dashes laid out here from the arc
 *    length;
 *  - the meetings `area` cuts its bands at (aa_piece_meet, whose pairs
 *    running side by side are decided by their slopes): every sign change
 *    of x_p - x_q seen at 400 heights over two pieces' common height, on
 *    every pair of a stroke's pieces with an offset piece, holds a meeting
 *    aa_piece_meet reports (ends shared by the two pieces aside), and one
 *    that area's form (aa__piece_meet_at, its polish stopped by an error
 *    estimate) reports, where x_p - x_q, evaluated here through
 *    aa_piece_x_at, is within 1e-13 of 0, and on the pairs of two offset
 *    pieces (area's polish in both parameters) within rounding of the
 *    root bisected here (test_offset_polish); and a vertical line 1e-6 to
 *    1e-10 inside an offset piece's x extreme, which it crosses twice
 *    close together, is met on both sides of the extreme (test_touch);
 *  - pairs of pieces that share an end point (a stroke's pieces meeting
 *    at a vertex, among them the normal lines and evolutes leaving the
 *    fold of an offset tangent to each other, and lines from an offset
 *    piece's end through its point a fraction of its height on, which
 *    meet it there again): every sign change of x_p - x_q sampled at
 *    2,050 heights (even and geometric towards the end) farther than
 *    1e-6 of the scale from the end holds a meeting of both forms, and
 *    each of area's meetings lies between such samples or where x_p -
 *    x_q is within 1e-13 of 0, never within that of the end
 *    (test_shared_ends);
 *  - pairs of a line and an evolute whose copies of the end point they
 *    share are stored an ulp apart (the normal line ending a fold's
 *    region and the evolute piece it ends on, each end found its own
 *    way), on the benchmark's rows at 256 px: held to what a shared end
 *    gives (test_shared_ends' rule), and with the line moved off the end
 *    by 1e-7 to 1e-11 px in x, either way, every sign change of x_p -
 *    x_q sampled, next to the end too, holds a meeting of area's form
 *    (test_touching_ends);
 *  - a pair asked over heights beyond or inside its common rows, no
 *    parameter known, and over the common heights aa__piece_meet_at takes
 *    from those with the parameters there given as area finds them where
 *    a piece begins or ends inside a band (the solve over the whole
 *    piece, area.c's seg_t_kept): the same meetings bit for bit
 *    (test_common_heights; area keeps those solves in its segs);
 *  - the tangents' cones by which area's form parts a pair at once
 *    (scene_piece.c, cones_apart): on every pair of a line or an offset
 *    piece and an offset piece of strokes (the benchmark's at 256 px,
 *    folds, a loop, a hook, round joins), over their common heights and
 *    parts of them, wherever the cones are said apart x_p - x_q sampled
 *    at 201 heights is monotone (no step back beyond 1e-12, at most one
 *    change of sign); and a line along an offset piece's tangent (its
 *    derivative evaluated) at 33 points of a range of its parameter is
 *    never said apart from it over that range, on an S whose tangents
 *    turn back at its inflection among others (test_cones);
 *  - the proof that a stroke's two sides (the offsets at d and -d of one
 *    cubic) never meet (aa__piece_sides_apart), against brute force
 *    written here on random cubics, widths and ranges, and refusing a Z
 *    whose sides meet, a loop and others built to (test_sides_apart);
 *  - a crossing's root near a turn of the offset's y: y at the parameter
 *    aa__offset_root returns is the line's, to rounding;
 *  - pixel (716, 793) of tests/bench_bezstroke.c's scene, against its area
 *    derived here from the one offset curve in it (test_vertex);
 *  - pixels (438, 998) and (880, 895) of the same scene, where two pieces
 *    left of the window end at one vertex stored at heights an ulp apart,
 *    against their area derived here exactly from the lines entering them
 *    (test_ulp_vertex): the reference (both paths) and `area`;
 *  - the quadrature's three forms of a cubic's nodes, eight a pass
 *    (AVX-512F), four at a time (AVX) and two at a time (SSE2), give the
 *    same segment bit for bit on 12,000 parts of the offset pieces and
 *    evolutes of three strokes, every rule taken (test_nodes: the tests
 *    above take the processor's form, so this holds the others to it);
 *  - the double-double form of area's roots and points (test_dd):
 *    every band line and cell side on the pieces of the benchmark's
 *    scene and a wide stroke, the point at the root within 2e-16 px of
 *    a __float128 evaluation written here and the root the double
 *    nearest it, the same bit for bit by fma and by Dekker's products;
 *  - the batched roots (aa__offset_roots: eight at a time in AVX-512F's
 *    lanes and four in AVX2's, test_roots_batch) the same bits as the
 *    roots asked one by one; and the rows' batches of single()'s side
 *    roots (area.c, side_ask) giving the same image bit for bit as the
 *    rows asking each alone (test_side_batch);
 *  - the start of a root at a cell's side after a part's first (side_guess,
 *    test_side_guess): nearer the root than the chord's, and within the
 *    solver's first double step far more often, on the benchmark's scene;
 *  - the quadrature's panels (test_panels): they tile each offset piece,
 *    each one's disc meets the tolerance by Trefethen's bound computed
 *    here, and its M bounds the integrand evaluated here in complex long
 *    double on the disc's circle;
 *  - the quadrature of a share (test_shares): the segment of parts inside
 *    one panel, 1e-7 of it wide to all of it, against the integral computed
 *    here in long double by Gauss-Legendre rules made here, within
 *    AR_QUAD_TOL plus the double sum's rounding, and the rule each share
 *    takes (area_offset_rule) the fewest points whose bound, computed here
 *    with powl, is within the tolerance;
 *  - parts reaching past their first panel (test_shares_across): against
 *    the same integral, whether one share of that panel (its disc holds
 *    the part's ellipse and 8 or 12 points meet the bound) or panel by
 *    panel, and the rule of one share the fewest points so bound;
 *  - the rule's test of 8 points without a division or a square root
 *    (test_rule_sure): wherever it tells 8 points, on random discs down to
 *    and beyond the ranges its powers are guarded for, the exact test
 *    (written here in double) tells 8 too and Trefethen's bound (long
 *    double) is within the tolerance; and it tells on nearly every share
 *    of 8 points of three strokes;
 *  - the parameters at a pair's common heights inside a band, solved from
 *    the piece's table's start (test_common_starts): the benchmark's scene
 *    at 256 px (rows 0 to 127) against the reference within its bound;
 *    and each of those solves (test_kept_solves): y at the root,
 *    evaluated here in __float128, within the solver's stated tolerance of
 *    the height asked, and the root inside the seg's parameter range;
 *  - parts reaching past their first panel that neither 8 nor 12 points
 *    may take as one share (test_shares_past: rho near 1, among them an
 *    evolute's panels next to a pole of its integrand): against the
 *    integral computed here adaptively in __float128, within AR_QUAD_TOL
 *    a panel the part meets;
 *  - a part's segment about the row's point (test_shares_at,
 *    area_offset_segment_at): against test_shares' integral, inside a panel,
 *    across panel ends and from a piece's end about its vertex moved off
 *    the curve, under the scenes' maps and one mixing x and y 3,000 px on;
 *  - area's gate on that point (test_rowpt_gate): shut under a map of
 *    condition number 12.5 (the image's bits as with no piece taking it),
 *    open under 3 and 1.
 *
 * Under the sanitizers (AA_SANITIZED: the Makefile's sanitizer build sets
 * it for the tests) a declared subset: test_shared_ends and test_cones
 * take the benchmark's row 0 only of its rows (not 4 to 16 too), beside
 * their strokes at 64 px, and test_touching_ends its rows 0, 4, 8, 12
 * and 16 (not all 20); the other rows take the same code paths with
 * other numbers (tests/README.md, "Tiers", says how that was checked),
 * and the plain build runs every case.
 */
#include "area_internal.h"
#include "path.h"
#include "oracle.h"
#include "scenes.h"
#include "support.h"
#include "tier.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_integration.h>

static void must(int st)
{
    if (st)
        fail_msg("status %d: %s", st, aa_last_error());
}

/* The stroke of nc chained cubics cs (2 + 6 nc numbers), filled white on
 * black through map m (NULL: none). */
static aa_scene *stroke_scene(const double *cs, int nc, const aa_stroke_style *st,
                              const double *m)
{
    aa_path in = {0};
    must(aa_path_move_to(&in, cs[0], cs[1]));
    for (int k = 0; k < nc; k++) {
        const double *q = cs + 2 + 6 * k;
        must(aa_path_cubic_to(&in, q[0], q[1], q[2], q[3], q[4], q[5]));
    }
    size_t noff;
    aa_scene *s = scenes_stroke_outline(&in, st, m, &noff);
    assert_true(noff > 0); /* the case is about offset pieces */
    aa_path_free(&in);
    return s;
}

/* `area` (both integrators, one and two threads) against the reference. */
static void against_reference(const char *what, const double *cs, int nc,
                              const aa_stroke_style *st, const double *m, int n)
{
    aa_scene *s = stroke_scene(cs, nc, st, m);
    support_view v = {.w = n, .h = n, .threads = 0};
    aa_image ref, a1, a2, bands;
    support_reference(s, &v, &ref, NULL, NULL);
    support_render("area", s, "box", n, n, 1, &a1, NULL);
    support_render("area", s, "box", n, n, 2, &a2, NULL);
    support_render("area:integrator=bands", s, "box", n, n, 1, &bands, NULL);
    int wi, wj;
    double e = support_max_diff(&a1, &ref, &wi, &wj), eb = support_max_diff(&bands, &ref, NULL, NULL);
    print_message("%-34s max |area - reference| %.1e (at %d,%d), bands %.1e\n", what, e, wi, wj,
                  eb);
    if (!(e < 1e-12) || !(eb < 1e-12))
        fail_msg("%s: area off the reference by %g (bands %g)", what, e, eb);
    assert_true(support_same_image(&a1, &a2));
    aa_image_free(&ref);
    aa_image_free(&a1);
    aa_image_free(&a2);
    aa_image_free(&bands);
    aa_scene_free(s);
}

/* Cubics (2 + 6 nc numbers, stroke_scene's) several tests stroke: a tight
 * arc whose offsets fold under a wide stroke, and three chained arcs. */
static const double tight[8] = {0.2, 0.2, 0.9, 0.3, 0.9, 0.7, 0.25, 0.75};
static const double loop[8] = {0.2, 0.8, 0.9, 0.1, 0.1, 0.1, 0.8, 0.8};
static const double hook[8] = {0.1, 0.9, 0.1, 0.1, 0.9, 0.1, 0.55, 0.5};
static const double three[20] = {0.1, 0.5, 0.3, 0.1,  0.5, 0.1,  0.6, 0.4, 0.7, 0.9,
                                 0.2, 0.6, 0.5, 0.5, 0.95, 0.2, 0.9, 0.8, 0.6, 0.85};

static void test_reference(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double shear[6] = {1.3, 0.2, 0.5, 0.8, -0.1, -0.05};
    const double dash[2] = {0.07, 0.03};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.05;
    against_reference("gentle, w 0.05", gentle, 1, &st, NULL, 64);
    st.width = 0.3;
    against_reference("tight, w 0.3 (folds)", tight, 1, &st, NULL, 64);
    against_reference("tight, w 0.3, sheared", tight, 1, &st, shear, 64);
    st.width = 1.0;
    against_reference("tight, w 1.0 (folds)", tight, 1, &st, NULL, 48);
    st.width = 0.5;
    against_reference("loop, w 0.5 (folds)", loop, 1, &st, NULL, 64);
    st.width = 0.4;
    against_reference("hook, w 0.4 (folds)", hook, 1, &st, NULL, 64);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 0.08;
    against_reference("3 arcs, round, w 0.08", three, 3, &st, NULL, 64);
    st.width = 0.4;
    against_reference("3 arcs, round, w 0.4", three, 3, &st, NULL, 48);
    st.join = AA_JOIN_MITER, st.cap = AA_CAP_SQUARE;
    st.width = 0.03;
    st.dash = dash, st.ndash = 2;
    against_reference("3 arcs, miter, square dashes", three, 3, &st, NULL, 64);
    /* cusps: B'(1/2) = 0 inside; a first control point on the start */
    const double cusp[8] = {0.2, 0.25, 0.8, 0.85, 0.2, 0.85, 0.8, 0.25};
    const double stop[8] = {0.2, 0.8, 0.2, 0.8, 0.9, 0.7, 0.6, 0.2};
    aa_stroke_style_default(&st);
    st.width = 0.1;
    against_reference("cusp, w 0.1", cusp, 1, &st, NULL, 64);
    st.width = 0.3;
    against_reference("cusp, w 0.3, sheared", cusp, 1, &st, shear, 48);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.dash = dash, st.ndash = 2;
    against_reference("cusp, round dashes, w 0.05", cusp, 1, &st, NULL, 64);
    st.dash = NULL, st.ndash = 0, st.width = 0.4;
    against_reference("P1 = P0, round, w 0.4", stop, 1, &st, NULL, 48);
}

/* ---- the tube formula ---- */

static void tube(const char *what, const double *c, double w, const double *dash, double off,
                 int n)
{
    for (int k = 0; k <= 1000; k++) /* the curvature radius above w/2 */
        assert_true(fabs(oracle_cubic_curvature(c, k / 1000.0)) * 0.5 * w < 0.99);
    double L = oracle_cubic_length(c, 0, 1), len = L;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = w;
    if (dash) {
        /* dash j covers [j P - off, j P - off + on] of [0, L] */
        double P = dash[0] + dash[1];
        len = 0;
        for (int j = 0; j * P - off < L; j++) {
            double a = fmax(j * P - off, 0), b = fmin(j * P - off + dash[0], L);
            if (b > a)
                len += b - a;
        }
        st.dash = dash, st.ndash = 2, st.dashoffset = off;
    }
    aa_scene *s = stroke_scene(c, 1, &st, NULL);
    aa_image im;
    support_render("area", s, "box", n, n, 1, &im, NULL);
    double got = support_channel_mean(&im, 0), want = w * len;
    print_message("%-34s area %.15f, want %.15f (%.1e)\n", what, got, want, got - want);
    if (!(fabs(got - want) < 1e-12))
        fail_msg("%s: area %.17g, want %.17g", what, got, want);
    aa_image_free(&im);
    aa_scene_free(s);
}

static void test_tube(void **state)
{
    (void)state;
    const double gentle[8] = {0.1, 0.5, 0.3, 0.2, 0.7, 0.8, 0.9, 0.45};
    const double s_curve[8] = {0.15, 0.2, 0.9, 0.25, 0.1, 0.75, 0.85, 0.8};
    const double dash[2] = {0.11, 0.05};
    tube("gentle S, w 0.05, 64 px", gentle, 0.05, NULL, 0, 64);
    tube("gentle S, w 0.05, 256 px", gentle, 0.05, NULL, 0, 256);
    tube("S across, w 0.02, 200 px", s_curve, 0.02, NULL, 0, 200);
    tube("S across, w 0.02, dashes", s_curve, 0.02, dash, 0.04, 128);
}

/* ---- meetings against sampled sign changes ---- */

/* Whether pieces p and q are a pair whose meetings are sought here: both
 * edges, one an offset piece at least, sharing rows [*lo, *hi]. */
static int offset_pair(const aa_piece *p, const aa_piece *q, double *lo, double *hi)
{
    if (!p->dir || !q->dir || (p->kind != AA_PIECE_OFFSET && q->kind != AA_PIECE_OFFSET))
        return 0;
    *lo = fmax(p->y0, q->y0), *hi = fmin(p->y1, q->y1);
    return *lo < *hi;
}

static int meetings(const char *what, const double *cs, int nc, const aa_stroke_style *st)
{
    aa_scene *s = stroke_scene(cs, nc, st, NULL);
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int pairs = 0, changes = 0, missed = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double lo, hi, ys[16];
            if (!offset_pair(p, q, &lo, &hi) || p->xmax < q->xmin || q->xmax < p->xmin)
                continue;
            pairs++;
            int m = aa_piece_meet(p, q, lo, hi, ys, 16);
            const double none[2] = {NAN, NAN};
            double ya[16];
            int ma = aa__piece_meet_at(p, q, lo, hi, none, none, ya, 16);
            double prev = NAN, yprev = lo;
            for (int j = 1; j < 400; j++) { /* inner heights: shared ends aside */
                double y = lo + (hi - lo) * j / 400.0;
                double d = aa_piece_x_at(p, y) - aa_piece_x_at(q, y);
                if (fabs(d) < 1e-9) {
                    prev = NAN; /* too near a meeting to tell its side */
                    continue;
                }
                if (prev == prev && (prev < 0) != (d < 0)) {
                    changes++;
                    int found = 0, found_a = 0;
                    for (int r = 0; r < m; r++)
                        found |= ys[r] >= yprev - 1e-9 && ys[r] <= y + 1e-9;
                    for (int r = 0; r < ma; r++) /* area's: at a root of x_p - x_q */
                        found_a |= ya[r] >= yprev - 1e-9 && ya[r] <= y + 1e-9 &&
                                   fabs(aa_piece_x_at(p, ya[r]) - aa_piece_x_at(q, ya[r])) <=
                                       1e-13;
                    if (!(found && found_a) && missed++ < 5)
                        print_message("%s: pieces %zu, %zu change sides in [%.17g, %.17g], "
                                      "not met (%d, area's %d)\n",
                                      what, i, k, yprev, y, found, found_a);
                }
                prev = d, yprev = y;
            }
        }
    print_message("%-34s %d pairs, %d sign changes sampled, %d not met\n", what, pairs,
                  changes, missed);
    assert_int_equal(missed, 0);
    aa_scene_free(s);
    return changes;
}

static void test_meetings(void **state)
{
    (void)state;
    /* smooth joins: the offsets of consecutive arcs run side by side */
    const double wave[20] = {0.05, 0.5, 0.15, 0.45, 0.25, 0.45, 0.35, 0.5, 0.45, 0.55,
                             0.55, 0.55, 0.65, 0.5, 0.75, 0.45, 0.85, 0.45, 0.95, 0.5};
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    int changes = 0;
    st.width = 0.08;
    changes += meetings("3 arcs, round, w 0.08", three, 3, &st);
    st.width = 0.01;
    changes += meetings("wave, round, w 0.01", wave, 3, &st);
    st.width = 0.06;
    changes += meetings("wave, round, w 0.06", wave, 3, &st);
    st.join = AA_JOIN_MITER, st.cap = AA_CAP_BUTT;
    st.width = 0.3;
    changes += meetings("tight, w 0.3 (folds)", tight, 1, &st);
    assert_true(changes > 0); /* the oracle saw crossings */
}

/* A vertical line p at x = xe + s delta, with xe the x extreme of an offset
 * piece q inside it at height ye (s: towards q's inside there), from q's
 * top to its bottom: x_q - x_p is -s delta at ye and of the other sign at
 * both ends (checked here), so the line crosses q on each side of ye,
 * about sqrt(2 delta / kappa) away (kappa: q's curvature there), a pair
 * nearly touching.  Both meetings must be reported by area's form and
 * the reference's, at heights where x_q - x_p (aa_piece_x_at) is within
 * 1e-13 of 0.  Returns the lines tried. */
static int touch(const char *what, const double *cs, int nc, const aa_stroke_style *st,
                 double delta)
{
    aa_scene *s = stroke_scene(cs, nc, st, NULL);
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int lines = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *q = &pc[k];
        double ts[2], xe, ye;
        if (q->kind != AA_PIECE_OFFSET ||
            aa__offset_turns(&q->oc, 0, fmin(q->ot0, q->ot1), fmax(q->ot0, q->ot1), ts) != 1)
            continue;
        aa_offset_point(&q->oc, ts[0], &xe, &ye, NULL, NULL);
        /* the side of q's inside: where its ends are */
        double sgn = q->x0 > xe ? 1.0 : -1.0, x = xe + sgn * delta;
        if (!(ye - q->y0 > 1e-3 && q->y1 - ye > 1e-3) || !((q->x0 - x) * sgn > 1e-4) ||
            !((q->x1 - x) * sgn > 1e-4))
            continue;
        aa_piece p;
        memset(&p, 0, sizeof p);
        p.kind = AA_PIECE_LINE, p.dir = 1;
        p.x0 = p.x1 = p.cx = p.xmin = p.xmax = x;
        p.y0 = q->y0, p.y1 = q->y1, p.cy = 0.5 * (p.y0 + p.y1), p.by = p.y1 - p.y0;
        assert_true((aa_piece_x_at(q, ye) - x) * sgn < 0.0); /* the extreme beyond the line */
        const double none[2] = {NAN, NAN};
        double ys[16], yr[16];
        int m = aa__piece_meet_at(&p, q, q->y0, q->y1, none, none, ys, 16);
        int mr = aa_piece_meet(&p, q, q->y0, q->y1, yr, 16);
        int above = 0, below = 0, off = 0;
        for (int r = 0; r < m; r++) {
            above += ys[r] < ye, below += ys[r] > ye;
            off += !(fabs(aa_piece_x_at(q, ys[r]) - x) <= 1e-13);
        }
        if (m != 2 || above != 1 || below != 1 || off || mr != 2 || !(yr[0] < ye && yr[1] > ye))
            fail_msg("%s: piece %zu, line %.3g inside its x extreme at (%.17g, %.17g): area's "
                     "meetings %d (%d above, %d below, %d off), the reference's %d",
                     what, k, delta, xe, ye, m, above, below, off, mr);
        lines++;
    }
    aa_scene_free(s);
    return lines;
}

static void test_touch(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    int lines = 0;
    for (int e = 6; e <= 10; e++) {
        st.width = 0.08;
        lines += touch("3 arcs, round, w 0.08", three, 3, &st, pow(10.0, -e));
        st.width = 0.3;
        lines += touch("tight, round, w 0.3", tight, 1, &st, pow(10.0, -e));
    }
    print_message("%d lines crossing an offset piece twice next to its x extreme, all met\n",
                  lines);
    assert_true(lines >= 10); /* the case was built */
}

/* A crossing of an offset curve is the root of y(t) = v: whatever path the
 * solver takes, the offset's y at the parameter it returns must be v to
 * long double's rounding of the coordinates (the equation itself is the
 * oracle, through the same evaluation of the curve, not the solver).  The
 * case: the left offset (d = 0.05) of the `tight` cubic below at 64 px,
 * crossed by the line y = 44.89 over a bracket near a turn of its y, where
 * Newton's steps in long double left the bracket or landed on its ends and
 * a solver that stopped after 8 of them returned y 1.4e-5 px off (up to
 * 3.5e-4 px in other calls the stroke tests make). */
static void test_root(void **state)
{
    (void)state;
    aa_offset_curve oc = {{0x1.999999999999ap-3, 0x1.cccccccccccc9p-1, -0x1.cccccccccccc5p-1,
                           0x1.333333333332bp-2, 0x1p-2, 0x1.cccccccccccc8p-1,
                           -0x1.cccccccccccc3p-2, 0},
                          {64, 0, 0, 64, 0, 0},
                          0.05,
                          0,
                          AA_OFFSET_CUBIC};
    const long double ta = 0x1.8a8d304019cdp-1, tb = 0x1.e3af7fdeab36ap-1;
    const long double target = 0xb.38df1a0932d3p+2L;
    long double X, Y, DX, DY, other;
    aa__offset_eval(&oc, ta, &X, &Y, &DX, &DY);
    const long double fa = Y - target;
    aa__offset_eval(&oc, tb, &X, &Y, &DX, &DY);
    assert_true((fa < 0) != (Y - target < 0)); /* a bracket */
    double slope;
    long double t = aa__offset_root(&oc, 1, ta, tb, fa, target, NAN, &other, &slope);
    aa__offset_eval(&oc, t, &X, &Y, &DX, &DY);
    print_message("root t %.21Lg: y - v = %.3Lg px, x %.17Lg (other %.17Lg)\n", t, Y - target,
                  X, other);
    assert_true(t >= ta && t <= tb);
    assert_true(fabsl(Y - target) <= 1e-15L);
    assert_true(fabsl(X - other) <= 1e-12L);
}

/* test_stops' and test_fix's curves, power basis x: b[0..3], y: b[4..7]:
 * P0 = P1 = (0, 0), P2 = (1, 1), P3 = (2, 0); the same reversed;
 * test_root's cubic; P = (0, 0), (1, 2), (2, -1), (3, 0); an ellipse
 * (centre, u, v); their stops by construction (test_stops' comment); and
 * two maps. */
static const double stops_b[5][8] = {{0, 0, 3, -1, 0, 0, 3, -3},
                                     {2, -3, 0, 1, 0, 3, -6, 3},
                                     {0x1.999999999999ap-3, 0x1.cccccccccccc9p-1,
                                      -0x1.cccccccccccc5p-1, 0x1.333333333332bp-2, 0x1p-2,
                                      0x1.cccccccccccc8p-1, -0x1.cccccccccccc3p-2, 0},
                                     {0, 3, 0, 0, 0, 6, -15, 9},
                                     {0.5, 0.5, 0.3, 0.1, -0.05, 0.2, 0, 0}};
static const int stops_want[5] = {1, 2, 2, 0, 0};
static const double stops_maps[2][6] = {{64, 0, 0, 64, 0, 0}, {64, 5, -7, 60, 3, 2}};

/* Curve c of stops_b at offset 0.1 (the evolute's when e) through map k. */
static void stops_curve(aa_offset_curve *oc, int c, int e, int k)
{
    memset(oc, 0, sizeof *oc);
    memcpy(oc->b, stops_b[c], sizeof oc->b);
    memcpy(oc->m, stops_maps[k], sizeof oc->m);
    oc->d = 0.1;
    oc->evolute = e;
    oc->base = c == 4 ? AA_OFFSET_ELLIPSE : AA_OFFSET_CUBIC;
}

/* aa__offset_eval_s given aa__offset_stops (the curve's stops found once)
 * against aa__offset_eval, which asks aa__offset_stop at every evaluation:
 * the same point and derivative, bit for bit, and the same point without
 * the derivative.  The stops expected by construction: a cubic whose
 * first control point lies on its start has B'(0) = 0 (bit 0), one whose
 * last lies on its end B'(1) = 0 (bit 1), as test_root's cubic's (B'(1) =
 * (0.9 - 1.8 + 0.9, 0.9 - 0.9)); a cubic without and an ellipse have
 * none. */
static void test_stops(void **state)
{
    (void)state;
    for (int c = 0; c < 5; c++)
        for (int e = 0; e < 2; e++)
            for (int k = 0; k < 2; k++) {
                aa_offset_curve oc;
                stops_curve(&oc, c, e, k);
                int stops = aa__offset_stops(&oc);
                double te, q[4];
                assert_int_equal(stops, stops_want[c]);
                assert_int_equal(stops & 1, aa__offset_stop(&oc, 0.25, &te, q));
                assert_int_equal(stops >> 1, aa__offset_stop(&oc, 0.75, &te, q));
                for (int i = 0; i <= 66; i++) {
                    long double t = i <= 64 ? i / 64.0L : (i == 65 ? 0.5L - 0x1p-40L : 0x1p-30L);
                    if (c < 4 && e && (t == 0 || t == 1))
                        continue; /* an evolute's point at a stop is 0/0 in the plain form */
                    long double x0, y0, dx0, dy0, x1, y1, dx1, dy1, x2, y2;
                    aa__offset_eval(&oc, t, &x0, &y0, &dx0, &dy0);
                    aa__offset_eval_s(&oc, stops, t, &x1, &y1, &dx1, &dy1);
                    aa__offset_eval_s(&oc, stops, t, &x2, &y2, NULL, NULL);
                    assert_true(x0 == x1 && y0 == y1 && dx0 == dx1 && dy0 == dy1);
                    assert_true(x0 == x2 && y0 == y2);
                }
            }
}

/* aa__offset_root_fix given aa__offset_fix_init's terms against the
 * solvers that find them at every root (aa__offset_root, with and without
 * a guess; aa__offset_solve_end given aa__offset_end's value at the far
 * end; aa__offset_root_xy, its root rounded to double, with its point
 * checked against the curve's there; aa__offset_root_fixd and
 * aa__offset_root_xyd, their arguments in double, against the long double
 * forms): the same root, the same other coordinate and slope, bit for bit,
 * and aa__offset_eval_s given the stops the same point as aa__offset_eval,
 * on test_stops' curves (offsets and evolutes, two maps), x and y, over 16
 * brackets of 1/32 each; the stops expected by construction as there, and
 * the terms' sizes the sums of the magnitudes of the x and the y terms
 * (a cubic's coefficients b[0..3] and b[4..7]; an ellipse's centre and
 * semi-diameters, x in b[0], b[2], b[4]). */
static void test_fix(void **state)
{
    (void)state;
    int roots = 0, dbl = 0, evals = 0;
    double worst = 0.0;
    for (int c = 0; c < 5; c++)
        for (int e = 0; e < 2; e++)
            for (int k = 0; k < 2; k++) {
                aa_offset_curve oc;
                stops_curve(&oc, c, e, k);
                aa__offset_fix fx;
                aa__offset_fix_init(&oc, &fx);
                const double *b = stops_b[c];
                double sx = c == 4 ? fabs(b[0]) + fabs(b[2]) + fabs(b[4])
                                   : fabs(b[0]) + fabs(b[1]) + fabs(b[2]) + fabs(b[3]);
                double sy = c == 4 ? fabs(b[1]) + fabs(b[3]) + fabs(b[5])
                                   : fabs(b[4]) + fabs(b[5]) + fabs(b[6]) + fabs(b[7]);
                assert_int_equal(fx.stops, stops_want[c]);
                assert_true(fx.sx == sx && fx.sy == sy);
                /* the evaluation given the stops (a cubic's offset away
                 * from them by its own form) the same bit for bit as the
                 * one that asks at each point, with and without the
                 * derivative */
                for (int i = 0; i <= 64; i++) {
                    long double t = i / 64.0L, X, Y, DX, DY, x, y, dx, dy;
                    aa__offset_eval(&oc, t, &X, &Y, &DX, &DY);
                    aa__offset_eval_s(&oc, fx.stops, t, &x, &y, &dx, &dy);
                    assert_true(x == X && y == Y && dx == DX && dy == DY);
                    aa__offset_eval_s(&oc, fx.stops, t, &x, &y, NULL, NULL);
                    assert_true(x == X && y == Y);
                    evals++;
                }
                for (int i = 0; i < 16; i++)
                    for (int coord = 0; coord < 2; coord++) {
                        long double ta = i / 16.0L + 1 / 64.0L, tb = ta + 1 / 32.0L;
                        long double X, Y, DX, DY;
                        aa__offset_eval(&oc, ta, &X, &Y, &DX, &DY);
                        long double va = coord ? Y : X;
                        aa__offset_eval(&oc, tb, &X, &Y, &DX, &DY);
                        long double vb = coord ? Y : X, target = 0.5L * (va + vb);
                        if (!(va < target && target < vb) && !(vb < target && target < va))
                            continue;
                        long double fa = va - target, o0, o1;
                        double s0, s1, guess = (double)(ta + 0.3L * (tb - ta));
                        long double r0 = aa__offset_root(&oc, coord, ta, tb, fa, target, NAN,
                                                         &o0, &s0);
                        long double r1 = aa__offset_root_fix(&oc, &fx, coord, ta, tb, fa, target,
                                                             NAN, NULL, &o1, &s1);
                        assert_true(r0 == r1 && o0 == o1 && s0 == s1);
                        r0 = aa__offset_root(&oc, coord, ta, tb, fa, target, guess, &o0, &s0);
                        r1 = aa__offset_root_fix(&oc, &fx, coord, ta, tb, fa, target, guess,
                                                 NULL, &o1, &s1);
                        assert_true(r0 == r1 && o0 == o1 && s0 == s1);
                        long double rg = r1;
                        double end[4];
                        aa__offset_end(&oc, coord, (double)tb, end);
                        r0 = aa__offset_solve_end(&oc, coord, (double)ta, (double)tb, fa, target,
                                                  end);
                        r1 = aa__offset_root_fix(&oc, &fx, coord, ta, tb, fa, target, NAN, end,
                                                 NULL, NULL);
                        assert_true(r0 == r1);
                        /* aa__offset_root_xy: the same root, rounded to
                         * double, and the point there from the root's last
                         * evaluation moved by its derivative, against the
                         * curve evaluated at the rounded root: within
                         * 2e-18 of the point's size (|x| + |y| + the map's
                         * 64 px; an evolute's grows as 1/c next to an
                         * inflection), the long double evaluations'
                         * rounding (a few units of 1.1e-19 of that size:
                         * at most 5.4e-19 seen) and the move's error (about
                         * 1e-22 of the second derivative); a move to the
                         * unrounded root would be off by the slope times up
                         * to half an ulp of t (up to 1.8e-12 px on these
                         * brackets).  And coordinate coord there at the
                         * target within the slope times the rounding of t
                         * and that tolerance (Newton's root, the point's
                         * Taylor form); from the guess too (eb 2), the
                         * root the same as aa__offset_root_fix's from it */
                        for (int eb = 0; eb < 3; eb++) {
                            long double xy[2], EX, EY, EDX, EDY;
                            double t = aa__offset_root_xy(&oc, &fx, coord, ta, tb, fa, target,
                                                          eb == 2 ? guess : NAN,
                                                          eb == 1 ? end : NULL, xy);
                            assert_true(t == (double)(eb == 2 ? rg : r1));
                            aa__offset_eval(&oc, t, &EX, &EY, &EDX, &EDY);
                            double dx = (double)fabsl(xy[0] - EX), dy = (double)fabsl(xy[1] - EY);
                            double tol = 2e-18 * ((double)(fabsl(EX) + fabsl(EY)) + 64);
                            worst = fmax(worst, fmax(dx, dy));
                            assert_true(dx <= tol && dy <= tol);
                            long double own = coord ? xy[1] : xy[0], sl = coord ? EDY : EDX;
                            assert_true(fabsl(own - target) <=
                                        fabsl(sl) * fabsl((long double)t - (eb == 2 ? rg : r1)) +
                                            tol);
                        }
                        /* with the bracket and the target in double (the
                         * target rounded, fa from it): aa__offset_root_fixd
                         * and aa__offset_root_xyd against the long double
                         * forms given the same values, bit for bit */
                        double td = (double)target, fd = (double)(va - td);
                        if (fd != 0 && (fd < 0) == (fa < 0)) {
                            for (int g = 0; g < 2; g++) {
                                double gs = g ? guess : NAN;
                                long double od, ol, xyd[2], xyl[2];
                                long double rl = aa__offset_root_fix(&oc, &fx, coord, ta, tb, fd,
                                                                     td, gs, NULL, &ol, NULL);
                                double rd = aa__offset_root_fixd(&oc, &fx, coord, (double)ta,
                                                                 (double)tb, fd, td, gs, &od);
                                assert_true(rd == (double)rl && od == ol);
                                double tl = aa__offset_root_xy(&oc, &fx, coord, ta, tb, fd, td,
                                                               gs, g ? NULL : end, xyl);
                                double tx = aa__offset_root_xyd(&oc, &fx, coord, (double)ta,
                                                                (double)tb, fd, td, gs,
                                                                g ? NULL : end, xyd);
                                assert_true(tx == tl && xyd[0] == xyl[0] && xyd[1] == xyl[1]);
                                dbl++;
                            }
                        }
                        roots++;
                    }
            }
    assert_true(dbl > 200 && evals == 20 * 65);
    print_message("%d brackets, each root the same bit for bit (%d in double); "
                  "aa__offset_root_xy's points "
                  "within %.2g px of the curve at its roots\n",
                  roots, dbl, worst);
    assert_true(roots > 200);
}

/* One pixel of tests/bench_bezstroke.c's scene, (716, 793) at 1024 px: the
 * stroke (2.5 px, round joins) of three of its cubics, subpath 15's 35th to
 * 37th (the same numbers as the benchmark's), against an answer derived
 * here.  Only the outer offset of the 36th cubic enters the pixel: it
 * starts at (715.98, 793.39), just left of it, at the vertex it shares
 * with a line across the stroke, and leaves by the bottom; the pixel's
 * value is then the area between the window's left side and that curve,
 *
 *     A = integral (x(t) - 716) y'(t) dt  from tc (x = 716) to te (y = 794),
 *
 * P = 1024 (B + d N), N = (-B'y, B'x)/|B'|, d = -1.25/1024, B the cubic
 * from its control points: the crossings by Newton's method and the
 * integral by 20-point Gauss-Legendre (GSL's nodes) on 8 panels, all in
 * long double (the integrand is analytic there; 10 points on 1 panel
 * agree to 1e-18).  A __float128 evaluation of the same gave
 * 0.023660496760506964.  `area` was 1.1e-13 off here: it evaluated the
 * curve at the piece's start, 4.2e-14 px from the vertex rounded to
 * double that the line across the stroke ends at, so that the outline left
 * a strip that high open across the pixel (area_internal.h,
 * offset_point); the reference's bound (5.3e-15) holds. */
static long double vx_b[4], vx_c[4]; /* the cubic's power basis, x and y */

static void vertex_eval(long double t, long double *x, long double *y, long double *dx,
                        long double *dy)
{
    const long double d = -1.25L / 1024.0L;
    long double X = vx_b[0] + t * (vx_b[1] + t * (vx_b[2] + t * vx_b[3]));
    long double Y = vx_c[0] + t * (vx_c[1] + t * (vx_c[2] + t * vx_c[3]));
    long double X1 = vx_b[1] + t * (2 * vx_b[2] + 3 * t * vx_b[3]);
    long double Y1 = vx_c[1] + t * (2 * vx_c[2] + 3 * t * vx_c[3]);
    long double X2 = 2 * vx_b[2] + 6 * t * vx_b[3], Y2 = 2 * vx_c[2] + 6 * t * vx_c[3];
    long double L = sqrtl(X1 * X1 + Y1 * Y1), k = (X1 * Y2 - Y1 * X2) / (L * L * L);
    *x = 1024 * (X - d * Y1 / L);
    *y = 1024 * (Y + d * X1 / L);
    *dx = 1024 * X1 * (1 - d * k); /* P' = B' (1 - d k) */
    *dy = 1024 * Y1 * (1 - d * k);
}

static long double vertex_root(int coord, long double target, long double t)
{
    for (int it = 0; it < 60; it++) {
        long double x, y, dx, dy;
        vertex_eval(t, &x, &y, &dx, &dy);
        long double step = ((coord ? y : x) - target) / (coord ? dy : dx);
        t -= step;
        if (fabsl(step) < 1e-21L)
            break;
    }
    return t;
}

static void test_vertex(void **state)
{
    (void)state;
    const int r = 15, n = 1024;
    double y = (r + 0.5) / 20.0, a = 0.004 + 0.0015 * r, dx = 0.9 / 50.0, x = 0.05;
    double cs[2 + 18];
    for (int k = 0; k < 35; k++)
        x += dx;
    cs[0] = x, cs[1] = y;
    for (int k = 35; k < 38; k++) {
        double s = (k % 2 ? -1.0 : 1.0) * a * (1.0 + 0.5 * sin(0.7 * k + r));
        double kink = k % 7 == 6 ? 0.3 * dx : 0.0, *q = cs + 2 + 6 * (k - 35);
        q[0] = x + dx / 3.0 + kink, q[1] = y + s, q[2] = x + 2.0 * dx / 3.0, q[3] = y + s;
        q[4] = x + dx, q[5] = y;
        if (k == 36) { /* its power basis from the control points */
            const double *p0 = q - 2, *p = q;
            long double P[4][2] = {{p0[0], p0[1]}, {p[0], p[1]}, {p[2], p[3]}, {p[4], p[5]}};
            for (int c = 0; c < 2; c++) {
                long double *o = c ? vx_c : vx_b;
                o[0] = P[0][c];
                o[1] = 3 * (P[1][c] - P[0][c]);
                o[2] = 3 * (P[2][c] - 2 * P[1][c] + P[0][c]);
                o[3] = P[3][c] - 3 * P[2][c] + 3 * P[1][c] - P[0][c];
            }
        }
        x += dx;
    }
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 2.5 / n;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    aa_scene *s = stroke_scene(cs, 3, &st, NULL);
    /* the premise: the curve starts left of the pixel and enters it */
    long double x0, y0, x1, y1, dx1, dy1;
    vertex_eval(0, &x0, &y0, &dx1, &dy1);
    assert_true(x0 > 715.9L && x0 < 716 && y0 > 793 && y0 < 794);
    long double tc = vertex_root(0, 716, 0.001L), te = vertex_root(1, 794, 0.006L);
    vertex_eval(tc, &x1, &y1, &dx1, &dy1);
    assert_true(tc > 0 && te > tc && y1 > 793 && y1 < 794);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(20);
    assert_non_null(gl);
    long double want = 0;
    for (int p = 0; p < 8; p++) {
        long double lo = tc + (te - tc) * p / 8, hi = tc + (te - tc) * (p + 1) / 8;
        for (size_t i = 0; i < 20; i++) {
            double xi, wi;
            gsl_integration_glfixed_point(-1, 1, i, &xi, &wi, gl);
            long double t = 0.5L * (lo + hi) + 0.5L * (hi - lo) * xi, px, py, pdx, pdy;
            vertex_eval(t, &px, &py, &pdx, &pdy);
            want += 0.5L * (hi - lo) * wi * (px - 716) * pdy;
        }
    }
    gsl_integration_glfixed_table_free(gl);
    /* the window holds no other piece: of the pieces in its rows (each
     * y-monotone, x sampled at 257 heights), only one reaches between
     * x = 716 and 717 */
    aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
    assert_non_null(placed);
    size_t np, inside = 0;
    const aa_piece *pc = aa_scene_pieces(placed, &np);
    for (size_t k = 0; k < np; k++) {
        double lo = fmax(pc[k].y0, 793), hi = fmin(pc[k].y1, 794);
        double most = -INFINITY, least = INFINITY;
        for (int i = 0; i <= 256 && lo < hi; i++) {
            double px = aa_piece_x_at(&pc[k], lo + (hi - lo) * i / 256);
            most = fmax(most, px), least = fmin(least, px);
        }
        inside += most > 716 && least < 717;
    }
    assert_int_equal(inside, 1);
    aa_scene_free(placed);
    support_view v = {.w = n, .h = n, .threads = 0};
    aa_image ref, bound, got;
    support_reference(s, &v, &ref, &bound, NULL);
    support_render("area", s, "box", n, n, 1, &got, NULL);
    double rv = aa_pixel(&ref, 716, 793)[0], b = aa_pixel(&bound, 716, 793)[0];
    double av = aa_pixel(&got, 716, 793)[0];
    print_message("pixel (716, 793): derived %.17Lg, reference %.1e off (bound %.1e), area "
                  "%.1e off\n",
                  want, (double)(rv - want), b, (double)(av - want));
    assert_true(fabsl(rv - want) <= b);
    assert_true(fabsl(av - want) <= 3e-14);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_image_free(&got);
    aa_scene_free(s);
}

/* ---- vertices whose heights differ by an ulp ---- */

/* The benchmark's (tests/bench_bezstroke.c) cubics k0 .. k1 - 1 of subpath
 * r, the same numbers as its own: 2 + 6 (k1 - k0) into cs. */
static void bench_cubics(int r, int k0, int k1, double *cs)
{
    double y = (r + 0.5) / 20.0, a = 0.004 + 0.0015 * r, dx = 0.9 / 50.0, x = 0.05;
    for (int k = 0; k < k0; k++)
        x += dx;
    cs[0] = x, cs[1] = y;
    for (int k = k0; k < k1; k++) {
        double s = (k % 2 ? -1.0 : 1.0) * a * (1.0 + 0.5 * sin(0.7 * k + r));
        double kink = k % 7 == 6 ? 0.3 * dx : 0.0, *q = cs + 2 + 6 * (k - k0);
        q[0] = x + dx / 3.0 + kink, q[1] = y + s, q[2] = x + 2.0 * dx / 3.0, q[3] = y + s;
        q[4] = x + dx, q[5] = y;
        x += dx;
    }
}

/* The stroke outline of the benchmark's subpaths rows[0..nr) (NULL: 0 to
 * nr - 1), each its 50 cubics, in style st */
static aa_scene *bench_rows_stroke_map(const int *rows, int nr, const aa_stroke_style *st,
                                      const double *m)
{
    aa_path in = {0};
    double cs[2 + 6 * 50];
    for (int r = 0; r < nr; r++) {
        bench_cubics(rows ? rows[r] : r, 0, 50, cs);
        must(aa_path_move_to(&in, cs[0], cs[1]));
        for (int k = 0; k < 50; k++) {
            const double *q = cs + 2 + 6 * k;
            must(aa_path_cubic_to(&in, q[0], q[1], q[2], q[3], q[4], q[5]));
        }
    }
    size_t noff;
    aa_scene *s = scenes_stroke_outline(&in, st, m, &noff);
    aa_path_free(&in);
    return s;
}

static aa_scene *bench_rows_stroke(const int *rows, int nr, const aa_stroke_style *st)
{
    return bench_rows_stroke_map(rows, nr, st, NULL);
}

/* The benchmark's scene at n px: its subpaths 0 to nr - 1, round joins and
 * caps, 2.5 px wide (tests/bench_bezstroke.c) */
static aa_scene *bench_scene_at(int n, int nr)
{
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / n;
    return bench_rows_stroke(NULL, nr, &st);
}

/* The n elements of `size` bytes at a shuffled (Fisher-Yates, a fixed LCG from seed) */
static void shuffle(void *a, size_t n, size_t size, uint64_t seed)
{
    unsigned char *p = a;
    uint64_t lcg = seed;
    for (size_t i = n - 1; n > 1 && i > 0; i--) {
        lcg = lcg * 6364136223846793005u + 1442695040888963407u;
        size_t j = (size_t)(lcg >> 33) % (i + 1);
        for (size_t b = 0; b < size; b++) {
            unsigned char t = p[i * size + b];
            p[i * size + b] = p[j * size + b], p[j * size + b] = t;
        }
    }
}

/* The benchmark's scene (its 20 rows of cubics stroked 2.5 px wide, round
 * joins and caps) placed at n x n px */
static aa_scene *bench_placed(int n)
{
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / n;
    aa_scene *s = bench_rows_stroke(NULL, 20, &st);
    aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
    assert_non_null(placed);
    aa_scene_free(s);
    return placed;
}

typedef __float128 q128;

static int q_cmp(q128 a, q128 b)
{
    return a < b ? -1 : a > b;
}

static void q_sort(q128 *v, int n) /* insertion sort: a few dozen values */
{
    for (int k = 1; k < n; k++)
        for (int m = k; m > 0 && q_cmp(v[m - 1], v[m]) > 0; m--) {
            q128 t = v[m];
            v[m] = v[m - 1], v[m - 1] = t;
        }
}

/* The box value of pixel (i, j) of a placed one-layer nonzero scene whose
 * pieces entering the window are lines, the others lying wholly left or
 * right of it over its rows (checked at 257 heights, 1e-3 px clear; the
 * test fails otherwise).  Derived here, not by the reference's method: the
 * rows are cut at every height where something changes (the lines' ends
 * and their crossings of the window's sides and of each other, the other
 * pieces' ends); between two such heights the covered length is linear in
 * y, so its integral is the height times its value at the middle, exactly.
 * All in __float128 from the pieces' doubles: the heights where two lines
 * cross are the only roundings, about 1e-31 px. */
#define LW_MAX 64
static q128 lines_window(const aa_scene *placed, int i, int j)
{
    size_t np;
    const aa_piece *pc = aa_scene_pieces(placed, &np);
    q128 lx0[LW_MAX], ly0[LW_MAX], lx1[LW_MAX], ly1[LW_MAX], ev[4 * LW_MAX + LW_MAX * LW_MAX];
    int ldir[LW_MAX], nl = 0, ne = 0;
    double oy0[4 * LW_MAX], oy1[4 * LW_MAX];
    int odir[4 * LW_MAX], no = 0;
    const q128 X0 = i, X1 = i + 1, Y0 = j, Y1 = j + 1;
    ev[ne++] = Y0, ev[ne++] = Y1;
    for (size_t k = 0; k < np; k++) {
        const aa_piece *p = &pc[k];
        if (!p->dir || !(p->y1 > j && p->y0 < j + 1))
            continue;
        if (p->y0 > j)
            ev[ne++] = p->y0;
        if (p->y1 < j + 1)
            ev[ne++] = p->y1;
        if (p->kind == AA_PIECE_LINE) {
            assert_true(nl < LW_MAX);
            lx0[nl] = p->x0, ly0[nl] = p->y0, lx1[nl] = p->x1, ly1[nl] = p->y1;
            ldir[nl++] = p->dir;
            continue;
        }
        double lo = fmax(p->y0, j), hi = fmin(p->y1, j + 1), most = -INFINITY, least = INFINITY;
        for (int q = 0; q <= 256; q++) {
            double x = aa_piece_x_at(p, lo + (hi - lo) * q / 256);
            most = fmax(most, x), least = fmin(least, x);
        }
        if (least > i + 1 + 1e-3)
            continue; /* right of the window: no part in it */
        assert_true(most < i - 1e-3); /* left: its winding only */
        assert_true(no < 4 * LW_MAX);
        oy0[no] = p->y0, oy1[no] = p->y1, odir[no++] = p->dir;
    }
    for (int a = 0; a < nl; a++) {
        q128 dxa = lx1[a] - lx0[a], dya = ly1[a] - ly0[a];
        for (int side = 0; side < 2 && dxa != 0; side++) { /* x = i, i + 1 */
            q128 y = ly0[a] + dya * ((side ? X1 : X0) - lx0[a]) / dxa;
            if (y > Y0 && y < Y1)
                ev[ne++] = y;
        }
        for (int b = a + 1; b < nl; b++) {
            q128 dxb = lx1[b] - lx0[b], dyb = ly1[b] - ly0[b], den = dxa * dyb - dya * dxb;
            if (den == 0)
                continue;
            q128 u = ((lx0[b] - lx0[a]) * dyb - (ly0[b] - ly0[a]) * dxb) / den, y = ly0[a] + u * dya;
            if (y > Y0 && y < Y1)
                ev[ne++] = y;
        }
    }
    q_sort(ev, ne);
    q128 area = 0;
    for (int e = 0; e + 1 < ne; e++) {
        if (!(ev[e + 1] > ev[e]))
            continue;
        q128 ym = 0.5 * (ev[e] + ev[e + 1]), xs[LW_MAX];
        int wind = 0, ds[LW_MAX], nx = 0;
        for (int k = 0; k < no; k++)
            wind += oy0[k] < ym && ym < oy1[k] ? odir[k] : 0;
        for (int k = 0; k < nl; k++) {
            if (!(ly0[k] < ym && ym < ly1[k]))
                continue;
            q128 x = lx0[k] + (lx1[k] - lx0[k]) * (ym - ly0[k]) / (ly1[k] - ly0[k]);
            int at = nx++;
            for (; at > 0 && xs[at - 1] > x; at--)
                xs[at] = xs[at - 1], ds[at] = ds[at - 1];
            xs[at] = x, ds[at] = ldir[k];
        }
        q128 cur = X0, len = 0;
        int k = 0;
        for (; k < nx && xs[k] <= X0; k++)
            wind += ds[k];
        for (; k <= nx; k++) {
            q128 next = k < nx && xs[k] < X1 ? xs[k] : X1;
            if (wind != 0)
                len += next - cur;
            cur = next;
            if (next == X1)
                break;
            wind += ds[k];
        }
        area += (ev[e + 1] - ev[e]) * len;
    }
    return area;
}

/* Pixels of tests/bench_bezstroke.c's scene where the stroke's lines
 * across it and its round joins' radii end at a vertex whose heights, as
 * the pieces store them, differ by an ulp (1.1e-13 px between 512 and
 * 1024), left of the window: (438, 998), the benchmark's largest
 * difference between `area` and the reference before the reference took
 * the winding left of the window at the exact height (5.7e-14, its bound
 * 1.8e-14), and (880, 895), which the stroke covers whole.  The reference
 * summed the winding numbers of the pieces left of the window at the
 * absolute height vc + s rounded to double, which puts a vertex within
 * half an ulp of it on the wrong side: on the rows between the two
 * heights, half its Gauss-Kronrod nodes saw the window empty.  The answer
 * here is lines_window's (the exact area of the window in the lines'
 * arrangement); the other pieces are the benchmark's own, three or four
 * cubics about the vertex. */
static void test_ulp_vertex(void **state)
{
    (void)state;
    static const struct {
        int r, k0, k1, i, j;
    } cases[] = {{19, 19, 23, 438, 998}, {17, 43, 47, 880, 895}};
    const int n = 1024;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double cs[2 + 6 * 4];
        bench_cubics(cases[c].r, cases[c].k0, cases[c].k1, cs);
        aa_stroke_style st;
        aa_stroke_style_default(&st);
        st.width = 2.5 / n;
        st.join = AA_JOIN_ROUND;
        st.cap = AA_CAP_ROUND;
        aa_scene *s = stroke_scene(cs, cases[c].k1 - cases[c].k0, &st, NULL);
        aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
        assert_non_null(placed);
        int i = cases[c].i, j = cases[c].j;
        q128 want = lines_window(placed, i, j);
        support_view v = {.w = n, .h = n, .threads = 0};
        aa_image ref, bound, crowd, cbound, got;
        support_reference(s, &v, &ref, &bound, NULL);
        support_reference_mode(placed, n, n, "box", AA__TRUTH_CROWD, &crowd, &cbound);
        support_render("area", s, "box", n, n, 1, &got, NULL);
        double rv = aa_pixel(&ref, i, j)[0], b = aa_pixel(&bound, i, j)[0];
        double cv = aa_pixel(&crowd, i, j)[0], cb = aa_pixel(&cbound, i, j)[0];
        double av = aa_pixel(&got, i, j)[0];
        print_message("pixel (%d, %d): derived 1 - %.4e, reference %.1e off (bound %.1e), one "
                      "piece at a time %.1e (bound %.1e), area %.1e off\n",
                      i, j, (double)(1 - want), (double)(rv - want), b, (double)(cv - want), cb,
                      (double)(av - want));
        assert_true(fabs((double)(rv - want)) <= b);
        assert_true(fabs((double)(cv - want)) <= cb);
        assert_true(fabs((double)(av - want)) <= 1e-14);
        aa_image_free(&ref);
        aa_image_free(&bound);
        aa_image_free(&crowd);
        aa_image_free(&cbound);
        aa_image_free(&got);
        aa_scene_free(placed);
        aa_scene_free(s);
    }
}

/* An offset piece's point at t and its derivative there, in __float128 from its
 * doubles (the formulas of offset.c's header: P = B + d N, P' = B' (1 -
 * d k); E = B + N L^3 / c, E' = N L (3 (B'.B'') c - L^2 c') / c^2), the
 * square root by two Newton steps from double's (each doubles the bits). */
static q128 q_sqrt(q128 x)
{
    if (!(x > 0))
        return 0;
    q128 r = sqrt((double)x);
    r = (r + x / r) / 2;
    return (r + x / r) / 2;
}

static void q_offset(const aa_offset_curve *oc, q128 t, q128 P[2], q128 dP[2])
{
    const double *b = oc->b, *m = oc->m;
    q128 T = t, B[2], U[2], V[2];
    for (int c = 0; c < 2; c++) {
        const double *k = b + 4 * c;
        B[c] = k[0] + T * (k[1] + T * (k[2] + T * (q128)k[3]));
        U[c] = k[1] + T * (2 * (q128)k[2] + 3 * T * (q128)k[3]);
        V[c] = 2 * (q128)k[2] + 6 * T * (q128)k[3];
    }
    q128 L2 = U[0] * U[0] + U[1] * U[1], L = q_sqrt(L2), c = U[0] * V[1] - U[1] * V[0];
    q128 r = oc->evolute ? L2 * L / c : (q128)oc->d; /* the normal's length */
    q128 p[2] = {B[0] - r * U[1] / L, B[1] + r * U[0] / L}, dp[2];
    if (!oc->evolute) {
        q128 f = 1 - oc->d * c / (L2 * L);
        dp[0] = U[0] * f, dp[1] = U[1] * f;
    } else {
        q128 cp = U[0] * 6 * (q128)b[7] - U[1] * 6 * (q128)b[3];
        q128 rp = L * (3 * (U[0] * V[0] + U[1] * V[1]) * c - L2 * cp) / (c * c);
        dp[0] = -rp * U[1] / L, dp[1] = rp * U[0] / L;
    }
    for (int k = 0; k < 2; k++) {
        P[k] = m[k] * p[0] + m[2 + k] * p[1] + m[4 + k];
        dP[k] = m[k] * dp[0] + m[2 + k] * dp[1];
    }
}

/* The ends ts[0..n) (returned n: 2 to 4) of the spans of [t0, t1], in
 * its direction, on which coordinate coord of oc is monotone: y on a
 * piece; x between its turns (aa__offset_turns) */
static int monotone_spans(const aa_offset_curve *oc, int coord, double t0, double t1,
                          double ts[4])
{
    double tt[2];
    int nt = 1, m = coord ? 0 : aa__offset_turns(oc, 0, fmin(t0, t1), fmax(t0, t1), tt);
    ts[0] = t0;
    for (int e = 0; e < m; e++)
        ts[nt++] = t0 < t1 ? tt[e] : tt[m - 1 - e];
    ts[nt++] = t1;
    return nt;
}

/* The double-double form of area's roots and points (offset.c,
 * aa__offset_fix_dd): on every offset piece of a cubic without stops in
 * tests/bench_bezstroke.c's scene at 1024 px (about 4,300 pieces; its
 * evolutes keep the long double form) and of the tight arc's wide stroke
 * at 1024 px (a half width of 154 px), at every band line y = j a piece
 * crosses (aa__offset_root_xyd, from the bracket's ends and from a start
 * 1e-5 off the root) and every cell side x = i between its x turns
 * (aa__offset_root_fixd, with its other coordinate):
 *  - the point given at the root against q_offset's there (__float128),
 *    within 2e-16 px: what the cell's and band's u and v take from it;
 *    at a side, y where x is the side's (q_offset's point moved along
 *    its tangent by the residual of x), which its callers pair with the
 *    side;
 *  - the root the double nearest the root: the line's coordinate there
 *    is no farther from the line than at either neighbouring double
 *    (q_offset, to 1e-20 px);
 *  - aa__offset_point_fix at 64 parameters a piece within 2e-16 px of
 *    q_offset;
 *  - the products by fma (where the processor has it) and by Dekker's
 *    split give the same roots and points, bit for bit.
 * With the normal term in double (d w / L) the points were up to 1.1e-15
 * px off on the benchmark's scene and 9e-14 px on the wide stroke; with
 * the base's lo dropped the first root's point was 2.9e-15 px off (x =
 * 52.6), with the normal term's lo dropped the first root was not the
 * nearest (4.8e-17 px farther than a neighbour). */
static void test_dd(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    const int n = 1024;
    int pieces = 0, evolutes = 0, roots = 0, pts = 0;
    double worst = 0.0, worst_root = 0.0;
    for (int sc = 0; sc < 2; sc++) {
        aa_scene *s;
        if (sc == 0) {
            st.width = 2.5 / n;
            s = bench_rows_stroke(NULL, 20, &st); /* the benchmark's 20 subpaths */
        } else {
            st.width = 0.3;
            s = stroke_scene(tight, 1, &st, NULL);
        }
        aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
        assert_non_null(placed);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            aa__offset_fix fx, fs;
            aa__offset_fix_dd(oc, &fx, 1);
            aa__offset_fix_dd(oc, &fs, 0);
            if (!fx.dd) {
                assert_true(oc->base != AA_OFFSET_CUBIC || oc->evolute || fx.stops);
                evolutes += oc->evolute;
                continue;
            }
            assert_int_equal(fs.dd, 1);
            pieces++;
            double t0 = pc[k].ot0, t1 = pc[k].ot1;
            /* the lines, y = j then x = i, strictly inside the piece's
             * range (its coordinate monotone on it: y on a piece; x
             * between its turns, aa__offset_turns) */
            for (int coord = 1; coord >= 0; coord--) {
                double ts[4];
                int nt = monotone_spans(oc, coord, t0, t1, ts);
                for (int e = 0; e + 1 < nt; e++) {
                    double a = ts[e], b = ts[e + 1];
                    q128 Pa[2], Pb[2], dPa[2];
                    q_offset(oc, a, Pa, dPa);
                    q_offset(oc, b, Pb, dPa);
                    double ca = (double)Pa[coord], cb = (double)Pb[coord];
                    double lo = fmin(ca, cb), hi = fmax(ca, cb);
                    for (double j = ceil(lo + 1e-9); j < hi - 1e-9; j++) {
                        double fa = ca - j, t[3];
                        long double xy[3][2], oth[3];
                        for (int g = 0; g < 2; g++) {
                            double guess = NAN;
                            if (g) { /* 1e-5 off the root, inside the bracket */
                                guess = t[0] + (b > a ? 1e-5 : -1e-5);
                                if (!(b > a ? guess < b : guess > b))
                                    continue;
                            }
                            if (coord) {
                                t[g] = aa__offset_root_xyd(oc, &fx, 1, a, b, fa, j, guess,
                                                           NULL, xy[g]);
                                t[2] = aa__offset_root_xyd(oc, &fs, 1, a, b, fa, j, guess, NULL,
                                                           xy[2]);
                                assert_true(xy[g][0] == xy[2][0] && xy[g][1] == xy[2][1]);
                            } else {
                                t[g] = aa__offset_root_fixd(oc, &fx, 0, a, b, fa, j, guess,
                                                            &oth[g]);
                                t[2] = aa__offset_root_fixd(oc, &fs, 0, a, b, fa, j, guess,
                                                            &oth[2]);
                                assert_true(oth[g] == oth[2]);
                                xy[g][0] = j, xy[g][1] = oth[g];
                            }
                            assert_true(t[g] == t[2]);
                            /* the point at t; the other coordinate at a
                             * side at the root itself (where x is the
                             * side's), P moved along its tangent by the
                             * residual of x */
                            q128 P[2], dP[2];
                            q_offset(oc, t[g], P, dP);
                            if (!coord)
                                P[1] += dP[1] / dP[0] * (j - P[0]);
                            for (int c = !coord; c < 2; c++) {
                                double d = fabs((double)(xy[g][c] - (long double)P[c]));
                                if (d > worst)
                                    worst = d;
                                if (!(d <= 2e-16))
                                    fail_msg("piece %zu line %s = %g, t %.17g: %c %.20Lg, "
                                             "__float128 %.20Lg (%.2g off)",
                                             k, coord ? "y" : "x", j, t[g], "xy"[c], xy[g][c],
                                             (long double)P[c], d);
                            }
                            /* the root: the double nearest it, the line's
                             * coordinate there nearer the line than at
                             * either neighbour (or at most 1e-20 px
                             * farther: a root within rounding of the
                             * middle between two) */
                            q_offset(oc, t[g], P, dP);
                            q128 e0 = P[coord] - j, Q[2], dQ[2];
                            for (int side = 0; side < 2; side++) {
                                q_offset(oc, nextafter(t[g], side ? INFINITY : -INFINITY), Q, dQ);
                                q128 e1 = Q[coord] - j;
                                double over = (double)((e0 < 0 ? -e0 : e0) - (e1 < 0 ? -e1 : e1));
                                if (over > worst_root)
                                    worst_root = over;
                                if (!(over <= 1e-20))
                                    fail_msg("piece %zu line %s = %g: t %.17g not the nearest "
                                             "(%.2g px farther than a neighbour)",
                                             k, coord ? "y" : "x", j, t[g], over);
                            }
                            roots++;
                        }
                    }
                }
            }
            for (int i = 0; i < 64; i++) {
                double t = t0 + (t1 - t0) * (i + 0.5) / 64;
                long double X, Y, x2, y2;
                aa__offset_point_fix(oc, &fx, t, &X, &Y);
                aa__offset_point_fix(oc, &fs, t, &x2, &y2);
                assert_true(X == x2 && Y == y2);
                q128 P[2], dP[2];
                q_offset(oc, t, P, dP);
                double e = fmax(fabs((double)(X - (long double)P[0])),
                                fabs((double)(Y - (long double)P[1])));
                if (e > worst)
                    worst = e;
                if (!(e <= 2e-16))
                    fail_msg("piece %zu t %.17g: (%.20Lg, %.20Lg), __float128 (%.20Lg, %.20Lg)", k,
                             t, X, Y, (long double)P[0], (long double)P[1]);
                pts++;
            }
        }
        aa_scene_free(placed);
        aa_scene_free(s);
    }
    print_message("%d offset pieces (%d evolutes left to the long double form), %d roots, %d "
                  "points: at most %.2g px off __float128, roots within %.2g px\n",
                  pieces, evolutes, roots, pts, worst, worst_root);
    assert_true(pieces > 4000 && evolutes > 0);
}

/* aa__offset_roots (offset.c: root_dd's common path eight requests at a
 * time in AVX-512F's lanes and four in AVX2's, the rest one by one; both
 * widths asked by aa__offset_roots_lanes) against
 * aa__offset_root_xyd and aa__offset_root_fixd asked one by one, which
 * test_dd holds to __float128: the same roots, points and other
 * coordinates bit for bit (memcmp), on lines across the offset pieces of
 * five strokes (the benchmark's cubics 2.5 and 24 px wide at 1024 px, the
 * tight arc 0.3 and 0.05 wide, whose offsets fold, and 0.3 wide under a
 * shear, whose map's rows both mix x and y), y = j and x = i where
 * x is monotone, from starts 1e-12 to 3e-2 of the bracket off the root
 * on either side (some outside it), none, an end, and fa 0; by fma's
 * double-double form, Dekker's and the long double form; shuffled, so
 * that a batch mixes curves, coordinates and outputs (the point, the
 * other coordinate, neither, or both asked: the point, the other left as
 * it was, as aa__offset_root_xyd gives it), asked in batches of 1 to 9;
 * and those of fma's form asked of the solver's FMA build alone
 * (aa__offset_root_dd_fma), which the two take where the processor has
 * no AVX-512F (else its AVX-512F build): the same bits. */
typedef struct rb_req {
    aa__offset_rootq q;
    int out; /* 0 the point, 1 the other coordinate, 2 neither, 3 both asked */
} rb_req;

static void test_roots_batch(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    const int n = 1024;
    size_t cap = 1 << 16, nr = 0, nfx = 0;
    rb_req *rq = malloc(cap * sizeof *rq);
    aa__offset_fix *fxs = malloc(3 * 4096 * sizeof *fxs);
    const double shear[6] = {1.3, 0.2, 0.5, 0.8, -0.1, -0.05};
    aa_scene *keep[8];
    int nkeep = 0;
    assert_non_null(rq);
    assert_non_null(fxs);
    static const double offs[] = {1e-12, 1e-7, 1e-5, 6e-5, 1e-4, 3e-4, 1e-3, 3e-2};
    for (int sc = 0; sc < 5; sc++) {
        aa_scene *s;
        if (sc < 2) {
            st.width = (sc ? 24.0 : 2.5) / n;
            s = bench_rows_stroke(NULL, 3, &st); /* three of the benchmark's rows */
        } else {
            st.width = sc == 3 ? 0.05 : 0.3;
            s = stroke_scene(tight, 1, &st, sc == 4 ? shear : NULL);
        }
        aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
        assert_non_null(placed);
        aa_scene_free(s);
        keep[nkeep++] = placed;
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            /* fma's form for most, Dekker's and the long double form for
             * every fifth and seventh piece */
            aa__offset_fix *fx = &fxs[nfx++];
            assert_true(nfx <= 3 * 4096);
            if (k % 7 == 3)
                aa__offset_fix_init(oc, fx);
            else
                aa__offset_fix_dd(oc, fx, k % 5 != 2);
            double t0 = pc[k].ot0, t1 = pc[k].ot1;
            for (int coord = 1; coord >= 0; coord--) {
                double ts[4];
                int nt = monotone_spans(oc, coord, t0, t1, ts);
                for (int e = 0; e + 1 < nt; e++) {
                    double a = ts[e], b = ts[e + 1], Pa[2], Pb[2];
                    aa_offset_point(oc, a, &Pa[0], &Pa[1], NULL, NULL);
                    aa_offset_point(oc, b, &Pb[0], &Pb[1], NULL, NULL);
                    double lo = fmin(Pa[coord], Pb[coord]), hi = fmax(Pa[coord], Pb[coord]);
                    for (double j = ceil(lo + 1e-9); j < hi - 1e-9; j += 3) {
                        double fa = Pa[coord] - j;
                        double root = aa__offset_root_fixd(oc, fx, coord, a, b, fa, j, NAN, NULL);
                        int ng = (int)(sizeof offs / sizeof *offs);
                        for (int g = 0; g < 2 * ng + 3; g++) {
                            double guess = NAN, f = fa;
                            if (g < 2 * ng)
                                guess = root + (g & 1 ? -1 : 1) * offs[g >> 1] * (b - a);
                            else if (g == 2 * ng + 1)
                                guess = a;
                            else if (g == 2 * ng + 2)
                                f = 0.0;
                            if (nr == cap) {
                                cap *= 2;
                                rq = realloc(rq, cap * sizeof *rq);
                                assert_non_null(rq);
                            }
                            rq[nr].q = (aa__offset_rootq){oc, fx, coord, a, b, f, j, guess,
                                                          NULL, NULL, NULL, 0.0};
                            rq[nr].out = (int)((nr * 7 + k) % 4);
                            nr++;
                        }
                    }
                }
            }
        }
    }
    shuffle(rq, nr, sizeof *rq, 12345);
    /* one by one, then in batches: outputs zeroed first, so that a long
     * double's padding compares equal too */
    long double(*want)[2] = calloc(nr, sizeof *want), (*got)[2] = calloc(nr, sizeof *got);
    long double *oth = calloc(nr, sizeof *oth); /* the other asked beside the point */
    double *twant = malloc(nr * sizeof *twant);
    aa__offset_rootq *bq = malloc(nr * sizeof *bq);
    assert_non_null(want);
    assert_non_null(got);
    assert_non_null(oth);
    assert_non_null(twant);
    assert_non_null(bq);
    size_t common = 0, nfma = 0;
    for (size_t i = 0; i < nr; i++) {
        const aa__offset_rootq *r = &rq[i].q;
        if (rq[i].out == 0 || rq[i].out == 3)
            twant[i] = aa__offset_root_xyd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa,
                                           r->target, r->guess, NULL, want[i]);
        else
            twant[i] = aa__offset_root_fixd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa,
                                            r->target, r->guess,
                                            rq[i].out == 1 ? &want[i][0] : NULL);
        if (r->fx->dd == 2) {
            /* the solver's build for FMA alone, which aa__offset_root_xyd
             * and _fixd take where the processor has no AVX-512F (else its
             * build for AVX-512F) */
            long double w2[2];
            memset(w2, 0, sizeof w2);
            int pt = rq[i].out == 0 || rq[i].out == 3;
            double t2 = aa__offset_root_dd_fma(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa,
                                               r->target, r->guess, NULL, pt ? w2 : NULL,
                                               rq[i].out == 1 ? &w2[0] : NULL);
            if (memcmp(&t2, &twant[i], sizeof t2) != 0 || memcmp(w2, want[i], sizeof w2) != 0)
                fail_msg("request %zu (coord %d, target %.17g, guess %.17g): t %.17g by the FMA "
                         "build, %.17g as asked; (%.20Lg, %.20Lg) against (%.20Lg, %.20Lg)",
                         i, r->coord, r->target, r->guess, t2, twant[i], w2[0], w2[1],
                         want[i][0], want[i][1]);
            nfma++;
        }
        bq[i] = *r;
        bq[i].xy = rq[i].out == 0 || rq[i].out == 3 ? got[i] : NULL;
        bq[i].other = rq[i].out == 1 ? &got[i][0] : rq[i].out == 3 ? &oth[i] : NULL;
        bq[i].t = NAN;
        common += r->fx->dd == 2 && r->fa != 0 &&
                  (r->ta < r->tb ? r->guess > r->ta && r->guess < r->tb
                                 : r->guess < r->ta && r->guess > r->tb);
    }
    /* both widths: eight lanes (AVX-512F, where the processor has it;
     * batches of five to eight) and four (two to four), each batch's
     * outputs cleared first */
    for (int lanes = 8; lanes >= 4; lanes -= 4) {
        for (size_t i = 0; i < nr; i++) {
            bq[i].t = NAN;
            memset(got[i], 0, sizeof got[i]);
            oth[i] = 0;
        }
        for (size_t i = 0, len = 1; i < nr; i += len, len = len % 9 + 1)
            aa__offset_roots_lanes(bq + i, nr - i < len ? nr - i : len, lanes);
        for (size_t i = 0; i < nr; i++) {
            if (memcmp(&bq[i].t, &twant[i], sizeof twant[i]) != 0 ||
                memcmp(got[i], want[i], sizeof want[i]) != 0 || oth[i] != 0)
                fail_msg("lanes %d, request %zu (coord %d, [%.17g, %.17g], target %.17g, guess "
                         "%.17g, fa %g, form %d): t %.17g, one by one %.17g; (%.20Lg, %.20Lg) "
                         "against (%.20Lg, %.20Lg); the other beside the point %.20Lg (left 0)",
                         lanes, i, bq[i].coord, bq[i].ta, bq[i].tb, bq[i].target, bq[i].guess,
                         bq[i].fa, bq[i].fx->dd, bq[i].t, twant[i], got[i][0], got[i][1],
                         want[i][0], want[i][1], oth[i]);
        }
    }
    int avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    print_message("%zu roots (%zu of them root_dd's common start, %s) in batches of 1 to 9: the "
                  "same bits as one by one, and %zu by fma's form the same by the solver's FMA "
                  "build (%s)\n",
                  nr, common,
                  !avx2 ? "no AVX2 and FMA here: one by one"
                  : __builtin_cpu_supports("avx512f")
                      ? "eight and four at a time in AVX-512F's and AVX2's lanes"
                      : "four at a time in AVX2's lanes, no AVX-512F here",
                  nfma,
                  __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")
                      ? "one by one by its AVX-512F build"
                      : "no AVX-512F and VL here: the same build");
    assert_true(nr > 20000 && common > nr / 2);
    free(want);
    free(got);
    free(oth);
    free(twant);
    free(bq);
    free(rq);
    free(fxs);
    for (int i = 0; i < nkeep; i++)
        aa_scene_free(keep[i]);
}

/* The stroke of cs (stroke_scene) placed on a size x size view. */
static aa_scene *placed_stroke(const double *cs, int nc, const aa_stroke_style *st, int size)
{
    aa_scene *s = stroke_scene(cs, nc, st, NULL);
    aa_scene *placed = aa_scene_place(s, size, size, 0, 0, 0);
    assert_non_null(placed);
    aa_scene_free(s);
    return placed;
}

/* The panels of an offset piece (area_offset.c, area_offset_panels; the
 * disc each keeps searched from the last panel's at its depth): they tile
 * the piece's parameter range in order, each m their middle; each panel's
 * disc (R, M) meets the quadrature's tolerance by Trefethen's bound, h 64
 * M/(15 (1 - rho^-2) rho^32) <= AR_QUAD_TOL with rho from R = h (rho +
 * 1/rho)/2, computed here in long double; and M bounds the integrand f =
 * ((B - Pa) x B' - d L)(1 - d c/L^3) (the curve's units, times half the
 * map's determinant) evaluated here in complex long double from the
 * cubic's power basis at 64 points on the disc's circle (the largest of
 * an analytic function on a disc is on its circle; L = sqrt(B'.B'), the
 * principal branch: on the disc |L^2 - L(m)^2| < L(m)^2, M's own proof),
 * for start points Pa at the panel's ends and middle; on the offsets
 * (not the evolutes, nor the factored form next to a cusp) of the tight
 * arc and the three arcs at three widths. */
static void test_panels(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    int pieces = 0, panels = 0, checked = 0;
    double worst = 0.0;
    for (int c = 0; c < 6; c++) {
        st.width = (const double[]){0.02, 0.08, 0.3}[c % 3];
        aa_scene *placed = placed_stroke(c < 3 ? tight : three, c < 3 ? 1 : 3, &st, 64);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET || pc[k].oc.base == AA_OFFSET_ELLIPSE)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            ar_panel *pan;
            size_t npan;
            must(area_offset_panels(oc, pc[k].ot0, pc[k].ot1, &pan, &npan));
            pieces++, panels += (int)npan;
            assert_true(npan > 0);
            assert_true(pan[0].a == fmin(pc[k].ot0, pc[k].ot1));
            assert_true(pan[npan - 1].b == fmax(pc[k].ot0, pc[k].ot1));
            long double b[8], det2 = 0.5L * fabsl((long double)oc->m[0] * oc->m[3] -
                                                  (long double)oc->m[2] * oc->m[1]);
            for (int i = 0; i < 8; i++)
                b[i] = oc->b[i];
            for (size_t i = 0; i < npan; i++) {
                const ar_panel *p = &pan[i];
                if (i + 1 < npan)
                    assert_true(p->b == pan[i + 1].a);
                assert_true(p->a < p->b && p->m == 0.5 * (p->a + p->b));
                long double h = 0.5L * ((long double)p->b - p->a), z = p->R / h;
                assert_true(z > 1);
                long double rho = z + sqrtl((z - 1) * (z + 1)), r32 = powl(rho, 32);
                long double e = h * 64 * p->M / (15 * (1 - 1 / (rho * rho)) * r32);
                if (!(e <= AR_QUAD_TOL * (1 + 1e-9L)))
                    fail_msg("piece %zu panel %zu: bound %Lg", k, i, e);
                if (oc->evolute || p->stop)
                    continue;
                long double d = oc->d;
                for (int a = 0; a < 3; a++) {
                    long double ta = a == 0 ? p->a : a == 1 ? p->m : p->b;
                    long double X1 = b[1] + ta * (2 * b[2] + 3 * ta * b[3]);
                    long double Y1 = b[5] + ta * (2 * b[6] + 3 * ta * b[7]), l = hypotl(X1, Y1);
                    long double pax = b[0] + ta * (b[1] + ta * (b[2] + ta * b[3])) - d * Y1 / l;
                    long double pay = b[4] + ta * (b[5] + ta * (b[6] + ta * b[7])) + d * X1 / l;
                    for (int j = 0; j < 64; j++) {
                        long double complex t = p->m + p->R * cexpl(I * (2 * M_PI * j / 64));
                        long double complex x = b[0] + t * (b[1] + t * (b[2] + t * b[3]));
                        long double complex y = b[4] + t * (b[5] + t * (b[6] + t * b[7]));
                        long double complex x1 = b[1] + t * (2 * b[2] + 3 * t * b[3]);
                        long double complex y1 = b[5] + t * (2 * b[6] + 3 * t * b[7]);
                        long double complex x2 = 2 * b[2] + 6 * t * b[3];
                        long double complex y2 = 2 * b[6] + 6 * t * b[7];
                        long double complex L = csqrtl(x1 * x1 + y1 * y1);
                        long double complex cc = x1 * y2 - y1 * x2;
                        long double complex f = ((x - pax) * y1 - (y - pay) * x1 - d * L) *
                                                (1 - d * cc / (L * L * L));
                        double v = (double)(cabsl(f) * det2);
                        if (!(v <= p->M))
                            fail_msg("piece %zu panel %zu: |f| %g on the disc over M %g", k,
                                     i, v, p->M);
                        worst = fmax(worst, v / p->M);
                        checked++;
                    }
                }
            }
            free(pan);
        }
        aa_scene_free(placed);
    }
    print_message("%d panels of %d offset pieces tile them and meet the bound; |f| at most %.2f "
                  "of M at %d points\n",
                  panels, pieces, worst, checked);
    assert_true(pieces > 0 && checked > 0);
}

/* The n-point Gauss-Legendre rule on [-1, 1] in long double, for
 * test_shares' own quadrature: each node by Newton's method on the
 * Legendre polynomial P_n (the three-term recurrence (k + 1) P_(k+1) =
 * (2 k + 1) x P_k - k P_(k-1)), its weight 2 / ((1 - x^2) P_n'(x)^2). */
static void gauss_legendre_l(int n, long double *x, long double *w)
{
    for (int i = 0; i < n; i++) {
        long double t = cosl(3.14159265358979323846264338327950288L * (i + 0.75L) / (n + 0.5L));
        long double dp = 1.0L;
        for (int it = 0; it < 100; it++) {
            long double p0 = 1.0L, p1 = t;
            for (int k = 1; k < n; k++) {
                long double p2 = ((2 * k + 1) * t * p1 - k * p0) / (k + 1);
                p0 = p1, p1 = p2;
            }
            dp = n * (t * p1 - p0) / (t * t - 1.0L);
            long double dt = p1 / dp;
            t -= dt;
            if (fabsl(dt) <= 1e-20L)
                break;
        }
        x[i] = t, w[i] = 2.0L / ((1.0L - t * t) * dp * dp);
    }
}

/* The base curve B of oc at t and B' (aabench.h, aa_offset_curve), mapped
 * by oc's map, in long double. */
static void base_l(const aa_offset_curve *oc, long double t, long double *x, long double *y,
                   long double *dx, long double *dy)
{
    const double *b = oc->b, *m = oc->m;
    long double X, Y, DX, DY;
    if (oc->base == AA_OFFSET_ELLIPSE) {
        long double c = cosl(t), sn = sinl(t);
        X = b[0] + b[2] * c + b[4] * sn, Y = b[1] + b[3] * c + b[5] * sn;
        DX = -b[2] * sn + b[4] * c, DY = -b[3] * sn + b[5] * c;
    } else {
        X = b[0] + t * (b[1] + t * (b[2] + t * (long double)b[3]));
        Y = b[4] + t * (b[5] + t * (b[6] + t * (long double)b[7]));
        DX = b[1] + t * (2 * b[2] + 3 * t * (long double)b[3]);
        DY = b[5] + t * (2 * b[6] + 3 * t * (long double)b[7]);
    }
    *x = m[0] * X + m[2] * Y + m[4], *y = m[1] * X + m[3] * Y + m[5];
    *dx = m[0] * DX + m[2] * DY, *dy = m[1] * DX + m[3] * DY;
}

/* 1/2 the integral of (P - P(ta)) x P' from ta to tb on oc (mapped: the
 * scene's units), P and P' from aa__offset_eval (long double), by the
 * n-point rule (x, w) on sub equal parts.  *mag: the size of what a double
 * sum of the integrand at its nodes adds and cancels, the integral of (|B
 * - Pa| + |P - B| + |B - Bm| + |Pa - Bm|) (|B'| + |P'|), B the base curve,
 * Pa = P(ta), Bm = B(pm) (the panel's middle, about which area_offset.c
 * takes its Taylor forms). */
static long double segment_l(const aa_offset_curve *oc, long double ta, long double tb,
                             long double pm, int sub, int n, const long double *x,
                             const long double *w, long double *mag)
{
    long double ax, ay, mx, my, dmx, dmy, s = 0.0L, a = 0.0L;
    aa__offset_eval(oc, ta, &ax, &ay, NULL, NULL);
    base_l(oc, pm, &mx, &my, &dmx, &dmy);
    for (int j = 0; j < sub; j++) {
        long double lo = ta + (tb - ta) * j / sub, hi = ta + (tb - ta) * (j + 1) / sub;
        long double h = 0.5L * (hi - lo), m = 0.5L * (lo + hi);
        for (int i = 0; i < n; i++) {
            long double px, py, dx, dy, bx, by, dbx, dby;
            aa__offset_eval(oc, m + h * x[i], &px, &py, &dx, &dy);
            base_l(oc, m + h * x[i], &bx, &by, &dbx, &dby);
            long double f = (px - ax) * dy - (py - ay) * dx;
            s += w[i] * h * f;
            a += w[i] * fabsl(h) *
                 (hypotl(bx - ax, by - ay) + hypotl(px - bx, py - by) +
                  hypotl(bx - mx, by - my) + hypotl(ax - mx, ay - my)) *
                 (hypotl(dbx, dby) + hypotl(dx, dy));
        }
    }
    *mag = a;
    return 0.5L * s;
}

/* The strokes of test_shares and test_shares_across, c = 0 to 2: the
 * three arcs 0.02 wide, the tight arc 0.08, the three arcs 0.3, round
 * joins and caps, at 256 px. */
static aa_scene *shares_stroke(int c)
{
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = (const double[]){0.02, 0.08, 0.3}[c];
    return placed_stroke(c == 1 ? tight : three, c == 1 ? 1 : 3, &st, 256);
}

/* Offset piece pc as area's quadrature holds it; its panels returned,
 * the caller's to free. */
static ar_panel *shares_piece(const aa_piece *pc, const ar_quad *quad, ar_piece *ap)
{
    ar_panel *pan;
    size_t npan;
    must(area_offset_panels(&pc->oc, pc->ot0, pc->ot1, &pan, &npan));
    memset(ap, 0, sizeof *ap);
    ap->src = pc, ap->pan = pan, ap->npan = npan, ap->quad = quad;
    /* as area's init sets it on these maps (condition numbers at most 4),
     * where long double is wider than double at run time (not under
     * valgrind, whose x87 rounds to double) */
    ap->rowpt = aa_long_double_is_extended();
    return pan;
}

/* The quadrature of a share (area_offset.c, area_offset_segment on a part
 * inside one panel) against the integral computed here: 1/2 the integral
 * of (P - P(ta)) x P' in long double from aa__offset_eval's points and
 * derivatives, by Gauss-Legendre rules made here (20 points on 4 equal
 * parts, checked against 24 points on 6 to 1e-17 of the size and 1e-20
 * px^2), on parts of every width from 1e-7 of a panel to the whole of it,
 * on every offset piece, evolute and offset of an ellipse of three strokes
 * at 256 px.  Each within AR_QUAD_TOL, the bound each share is held to,
 * plus 8 ulps of the size its double sum's terms have (segment_l's mag:
 * the rounding of the start point and of the nodes relative to the
 * panel's middle; at most the tolerance on about half the parts, where a
 * wrong rule shows).  The rule each share takes (area_offset_rule) is the
 * one computed here from its panel's disc by Trefethen's bound (long
 * double, powl), where no rule's bound is within 1e-9 of the tolerance;
 * every rule of ar_quad is taken. */
static void test_shares(void **state)
{
    (void)state;
    ar_quad quad;
    must(area_quad_init(&quad));
    long double x1[20], w1[20], x2[24], w2[24];
    gauss_legendre_l(20, x1, w1);
    gauss_legendre_l(24, x2, w2);
    uint64_t rng = 987654321;
    int parts = 0, taken[AR_QUAD_RULES] = {0};
    double worst = 0.0, worst_fine = 0.0, oworst = 0.0;
    int fine = 0, ties = 0;
    for (int c = 0; c < 3; c++) {
        aa_scene *placed = shares_stroke(c);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            ar_piece ap;
            ar_panel *pan = shares_piece(&pc[k], &quad, &ap);
            size_t npan = ap.npan;
            for (int i = 0; i < 40; i++) {
                double u[3];
                for (int e = 0; e < 3; e++) { /* uniform in [0, 1), 53 bits */
                    rng = rng * 6364136223846793005u + 1442695040888963407u;
                    u[e] = (double)(rng >> 11) * 0x1p-53;
                }
                const ar_panel *p = &pan[(size_t)(u[2] * (double)npan)];
                double wd = (p->b - p->a) * pow(10.0, -7.0 * u[1]);
                double ta = p->a + (p->b - p->a - wd) * u[0], tb = fmin(ta + wd, p->b);
                if (!(tb > ta))
                    continue;
                double got = area_offset_segment(&ap, ta, tb);
                long double mag, mag2;
                long double want = segment_l(oc, ta, tb, p->m, 4, 20, x1, w1, &mag);
                long double want2 = segment_l(oc, ta, tb, p->m, 6, 24, x2, w2, &mag2);
                if (fabsl(want - want2) > oworst)
                    oworst = (double)fabsl(want - want2);
                if (!(fabsl(want - want2) <= 1e-17L * mag2 + 1e-20L))
                    fail_msg("piece %zu (evolute %d, base %d) [%.17g, %.17g] of panel [%.17g, "
                             "%.17g] R %g: %.6Lg %.6Lg apart, size %.3Lg",
                             k, oc->evolute, (int)oc->base, ta, tb, p->a, p->b, p->R,
                             want, want - want2, mag2);
                /* the rule the share's bound allows, computed here (long
                 * double, powl): area's choice (area_offset_rule, its
                 * products without division) the same but where the bound
                 * of the rule or the one before it is within 1e-9 of the
                 * tolerance */
                long double h = 0.5L * ((long double)tb - ta), mm = 0.5L * ((long double)ta + tb);
                long double Rs = p->R - fabsl(mm - p->m), e[AR_QUAD_RULES];
                int r = AR_QUAD_RULES - 1;
                if (Rs > h && p->M > 0) {
                    long double z = Rs / h, rho = z + sqrtl((z - 1) * (z + 1));
                    for (int j = 0; j < AR_QUAD_RULES; j++)
                        e[j] = h * 64 * p->M /
                               (15 * (1 - 1 / (rho * rho)) * powl(rho, 2 * quad.n[j]));
                    for (r = 0; r < AR_QUAD_RULES - 1 && !(e[r] <= AR_QUAD_TOL); r++)
                        ;
                    int ra = area_offset_rule(p, ta, tb);
                    int tie = fabsl(e[r] / AR_QUAD_TOL - 1) < 1e-9L ||
                              (r > 0 && fabsl(e[r - 1] / AR_QUAD_TOL - 1) < 1e-9L);
                    if (ra != r && !tie)
                        fail_msg("piece %zu [%.17g, %.17g]: %d points, here %d", k, ta, tb,
                                 quad.n[ra], quad.n[r]);
                    ties += tie;
                } else {
                    assert_int_equal(area_offset_rule(p, ta, tb), r);
                }
                taken[r]++;
                double err = fabs((double)(got - want));
                double tol = AR_QUAD_TOL + 8 * DBL_EPSILON * (double)mag;
                if (!(err <= tol))
                    fail_msg("piece %zu [%.17g, %.17g] (%d points): %.17g, here %.17Lg, %.2e off "
                             "(allowed %.2e)",
                             k, ta, tb, quad.n[r], got, want, err, tol);
                worst = fmax(worst, err / tol);
                if (tol <= 2 * AR_QUAD_TOL) { /* rounding at most the tolerance */
                    fine++;
                    worst_fine = fmax(worst_fine, err);
                }
                parts++;
            }
            free(pan);
        }
        aa_scene_free(placed);
    }
    print_message("%d shares within the bound plus rounding (at most %.2f of it; %d whose "
                  "rounding allowance is at most AR_QUAD_TOL, off by at most %.1e; the two "
                  "rules here at most %.1e apart; %d ties); rules",
                  parts, worst, fine, worst_fine, oworst, ties);
    for (int r = 0; r < AR_QUAD_RULES; r++)
        print_message(" %d points %d", quad.n[r], taken[r]);
    print_message("\n");
    assert_true(parts > 1000);
    for (int r = 0; r < AR_QUAD_RULES; r++)
        assert_true(taken[r] > 0);
}

/* Parts reaching past the end of their first panel (area_offset.c,
 * segment: taken as one share of that panel where the part's Bernstein
 * ellipse lies in its disc and 8 or 12 points meet the bound, else
 * panel by panel) against 1/2 the integral of (P - P(ta)) x P' computed
 * here as in test_shares (long double, 20 points on 4 parts), within
 * AR_QUAD_TOL plus 8 ulps of the size the double sum's terms have, on
 * parts from 1e-7 of their first panel wide to four times it, across each
 * panel end of every offset piece, evolute and ellipse's offset of the
 * tight and the three arcs at three widths at 256 px; the one-share path
 * counted here by Trefethen's bound for the part on the panel's disc
 * (long double, powl), and the rule area_offset_rule gives such a part
 * the fewest points whose bound that is within the tolerance. */
static void test_shares_across(void **state)
{
    (void)state;
    ar_quad quad;
    must(area_quad_init(&quad));
    long double x1[20], w1[20];
    gauss_legendre_l(20, x1, w1);
    uint64_t rng = 123456789;
    int parts = 0, one = 0, ties = 0, taken[AR_QUAD_RULES] = {0};
    double worst = 0.0;
    for (int c = 0; c < 3; c++) {
        aa_scene *placed = shares_stroke(c);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            ar_piece ap;
            ar_panel *pan = shares_piece(&pc[k], &quad, &ap);
            size_t npan = ap.npan;
            for (size_t j = 0; j + 1 < npan; j++) {
                const ar_panel *p = &pan[j];
                double tmax = pan[npan - 1].b;
                for (int i = 0; i < 16; i++) {
                    double u[2];
                    for (int e = 0; e < 2; e++) { /* uniform in [0, 1), 53 bits */
                        rng = rng * 6364136223846793005u + 1442695040888963407u;
                        u[e] = (double)(rng >> 11) * 0x1p-53;
                    }
                    double wd = 4.0 * (p->b - p->a) * pow(10.0, -7.0 * u[1]);
                    double ta = fmax(p->b - wd * u[0], p->a), tb = fmin(ta + wd, tmax);
                    if (!(ta < p->b && tb > p->b))
                        continue;
                    double got = area_offset_segment(&ap, i & 1 ? tb : ta, i & 1 ? ta : tb);
                    if (i & 1)
                        got = -got;
                    long double mag;
                    long double want = segment_l(oc, ta, tb, p->m, 4, 20, x1, w1, &mag);
                    double err = fabs((double)(got - want));
                    double tol = AR_QUAD_TOL + 8 * DBL_EPSILON * (double)mag;
                    if (!(err <= tol))
                        fail_msg("piece %zu [%.17g, %.17g] across %.17g: %.17g, here %.17Lg, "
                                 "%.2e off (allowed %.2e)",
                                 k, ta, tb, p->b, got, want, err, tol);
                    worst = fmax(worst, err / tol);
                    parts++;
                    /* one share of panel j: its ellipse in the disc and a
                     * rule before the last within the tolerance */
                    long double h = 0.5L * ((long double)tb - ta);
                    long double mm = 0.5L * ((long double)ta + tb);
                    long double Rs = p->R - fabsl(mm - p->m);
                    if (!(Rs > h && p->M > 0))
                        continue;
                    long double z = Rs / h, rho = z + sqrtl((z - 1) * (z + 1));
                    int r = 0;
                    long double e[AR_QUAD_RULES];
                    for (int q = 0; q < AR_QUAD_RULES; q++)
                        e[q] = h * 64 * p->M /
                               (15 * (1 - 1 / (rho * rho)) * powl(rho, 2 * quad.n[q]));
                    while (r < AR_QUAD_RULES - 1 && !(e[r] <= AR_QUAD_TOL))
                        r++;
                    if (r == AR_QUAD_RULES - 1)
                        continue;
                    int ra = area_offset_rule(p, ta, tb);
                    int tie = fabsl(e[r] / AR_QUAD_TOL - 1) < 1e-9L ||
                              (r > 0 && fabsl(e[r - 1] / AR_QUAD_TOL - 1) < 1e-9L);
                    if (ra != r && !tie)
                        fail_msg("piece %zu [%.17g, %.17g] across %.17g: %d points, here %d", k,
                                 ta, tb, p->b, quad.n[ra], quad.n[r]);
                    ties += tie;
                    taken[r]++;
                    one++;
                }
            }
            free(pan);
        }
        aa_scene_free(placed);
    }
    print_message("%d parts across a panel's end within the bound plus rounding (at most %.2f "
                  "of it), %d of them one share (%d ties); rules",
                  parts, worst, one, ties);
    for (int r = 0; r < AR_QUAD_RULES; r++)
        print_message(" %d points %d", quad.n[r], taken[r]);
    print_message("\n");
    assert_true(parts > 1000 && one > 100 && parts - one > 100);
    for (int r = 0; r < AR_QUAD_RULES - 1; r++)
        assert_true(taken[r] > 0);
}

/* A table of starts' piece: the offset at d = 0.1 of x = t, y = yb's cubic
 * in t (coefficients ascending), mapped 64 px to a unit, its table's YT_N
 * nodes (t, y, dt/dy, the interval ending there within the table's
 * tolerance: 1, or 0 on every interval where `marked`) at t0 + (t1 - t0)
 * k / 64, attached to *ap; the heights must rise (y monotone on [t0, t1],
 * as load_ytab asks). */
enum { YT_N = 65 };
static void table_piece(const char *name, const double yb[4], double t0, double t1, int marked,
                        aa_offset_curve *oc, double *nd, ar_piece *ap)
{
    memset(oc, 0, sizeof *oc);
    const double m[6] = {64, 0, 0, 64, 3, 2};
    oc->b[1] = 1;
    for (int i = 0; i < 4; i++)
        oc->b[4 + i] = yb[i];
    memcpy(oc->m, m, sizeof oc->m);
    oc->d = 0.1;
    oc->base = AA_OFFSET_CUBIC;
    for (int k = 0; k < YT_N; k++) {
        double e[4], t = t0 + (t1 - t0) * k / 64.0;
        aa__offset_end(oc, 1, t, e);
        nd[4 * k] = t, nd[4 * k + 1] = e[0] + e[1], nd[4 * k + 2] = 1.0 / e[2];
        nd[4 * k + 3] = !marked && k > 0;
        if (k > 0 && !(nd[4 * k + 1] > nd[4 * k - 3]))
            fail_msg("%s: the table's heights not rising at node %d", name, k);
    }
    memset(ap, 0, sizeof *ap);
    ap->nyt = YT_N;
    ytab_attach(ap, nd);
}

/* The test of the 8 points' rule without a division or a square root
 * (area_offset.c, rule8_sure, through area_offset_rule_sure): wherever it
 * tells 8 points, (a) the exact test tells 8 too, the base's operations
 * written here in double (z = Rs/h, rho = z + sqrt((z - 1)(z + 1)), r2 =
 * rho^2, r2^8 (r2 - 1) as (r2^4 (r2 - 1)) r2^4 against h K M r2, K =
 * 64 (1 + 1e-12) / (15 AR_QUAD_TOL)), and Trefethen's bound for 8 points,
 * computed here in long double, is within AR_QUAD_TOL; on 200,000 random
 * discs (h from 2^-80 to 2^30, z = Rs/h from 1 + 2^-40 to 2^61, M within a
 * relative 2^-60 to 1/2 of the 8 points' limit, a quarter anywhere from
 * 2^-1000 to 2^1000); and (b) it tells on at least 95% of the shares inside
 * a panel that take 8 points, on the offset pieces of test_shares' three
 * strokes (so it is not left dead). */
static void test_rule_sure(void **state)
{
    (void)state;
    const double K = 64.0 / (15.0 * AR_QUAD_TOL) * (1.0 + 1e-12);
    uint64_t rng = 42424242;
    int sure = 0, tried = 0, eight = 0, told = 0;
    long double worst = 0.0L;
    for (int i = 0; i < 200000; i++) {
        double u[6];
        for (int e = 0; e < 6; e++) { /* uniform in [0, 1), 53 bits */
            rng = rng * 6364136223846793005u + 1442695040888963407u;
            u[e] = (double)(rng >> 11) * 0x1p-53;
        }
        double h = ldexp(1.0 + u[0], (int)(-80 + 110 * u[1]));
        double Rs = h * (1.0 + ldexp(1.0 + u[2], (int)(-40 + 100 * u[3])));
        if (!(Rs > h) || !isfinite(Rs))
            continue;
        long double zl = (long double)Rs / h, rl = zl + sqrtl((zl - 1) * (zl + 1));
        long double r2l = rl * rl, lim = powl(r2l, 7) * (r2l - 1) / ((long double)h * K);
        double M;
        if (u[4] < 0.25) {
            M = ldexp(1.0 + u[0], (int)(-1000 + 2000 * u[4] * 4));
        } else {
            long double dl = ldexpl(1.0L, -(int)(1 + 60 * u[5]));
            M = (double)(lim * (u[4] < 0.625 ? 1 - dl : 1 + dl));
        }
        if (!(M > 0.0) || !isfinite(M))
            continue;
        ar_panel p;
        memset(&p, 0, sizeof p);
        p.R = Rs, p.M = M;
        tried++;
        if (!area_offset_rule_sure(&p, -h, h))
            continue;
        sure++;
        double z = Rs / h, rho = z + sqrt((z - 1.0) * (z + 1.0)), r2 = rho * rho;
        double need = h * K * M * r2;
        double p4 = r2 * r2 * (r2 * r2), pw = p4 * (r2 - 1.0) * p4;
        long double e8 = (long double)h * 64 * M / (15 * (1 - 1 / r2l) * powl(r2l, 8));
        if (!(pw >= need) || !(e8 <= AR_QUAD_TOL))
            fail_msg("h %a Rs %a M %a: 8 points told, the exact test %s (%.17g against "
                     "%.17g, %.3e apart); the bound %.6Le",
                     h, Rs, M, pw >= need ? "too" : "not", pw, need, pw / need - 1, e8);
        worst = fmaxl(worst, e8 / AR_QUAD_TOL);
    }
    /* (b) on the shares of three strokes */
    ar_quad quad;
    must(area_quad_init(&quad));
    for (int c = 0; c < 3; c++) {
        aa_scene *placed = shares_stroke(c);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            ar_piece ap;
            ar_panel *pan = shares_piece(&pc[k], &quad, &ap);
            for (int i = 0; i < 200; i++) {
                double v[3];
                for (int e = 0; e < 3; e++) {
                    rng = rng * 6364136223846793005u + 1442695040888963407u;
                    v[e] = (double)(rng >> 11) * 0x1p-53;
                }
                const ar_panel *q = &pan[(size_t)(v[2] * (double)ap.npan)];
                double wd = (q->b - q->a) * pow(10.0, -4.0 * v[1]);
                double ta = q->a + (q->b - q->a - wd) * v[0], tb = fmin(ta + wd, q->b);
                if (!(tb > ta) || area_offset_rule(q, ta, tb) != 0)
                    continue;
                eight++;
                told += area_offset_rule_sure(q, ta, tb);
            }
            free(pan);
        }
        aa_scene_free(placed);
    }
    print_message("%d random discs, %d told 8 points, the exact test 8 on each (its bound "
                  "at most %.4Lf of the tolerance); on three strokes %d of %d shares of 8 "
                  "points told\n",
                  tried, sure, worst, told, eight);
    assert_true(sure > 1000);
    assert_true(eight > 1000);
    if (!(told >= 0.95 * eight))
        fail_msg("8 points told on %d of %d shares that take them", told, eight);
}

/* area's band lines' starts on an offset piece (area_internal.h,
 * ytab_guess) from a table of nodes (t, y, dt/dy) made here as area.c's
 * load_offset makes them (y and its slope by aa__offset_end), at t = k/64
 * on the offset of x = t, y = t + 0.3 t^2 (rising in y: y' >= 1 - d k >
 * 0, its curvature k at most 0.6 and d = 0.1), mapped 64 px to a unit:
 * for 200 heights, the interval the walk ends on holds the height and is
 * the same from every start (hint), so the start is a function of the
 * height alone; and it is within 1e-8 of the root aa__offset_root finds
 * over the whole curve (the cubic Hermite form of t(y) on a 1/64 interval
 * errs by about h^4 t/384, h about 1.3 px, t about 1e-8 here) */
static void test_starts(void **state)
{
    (void)state;
    const double yb[4] = {0, 1, 0.3, 0};
    aa_offset_curve oc;
    double nd[4 * YT_N];
    ar_piece ap;
    table_piece("y = t + 0.3 t^2", yb, 0.0, 1.0, 0, &oc, nd, &ap);
    double worst = 0.0;
    for (int i = 1; i < 200; i++) {
        double yl = nd[1] + (nd[4 * YT_N - 3] - nd[1]) * i / 200.0;
        size_t h0 = 0;
        double g = ytab_guess(&ap, yl, &h0);
        assert_true(h0 < YT_N - 1 && nd[4 * h0 + 1] <= yl && yl < nd[4 * h0 + 5]);
        for (size_t hint = 0; hint < YT_N + 3; hint++) {
            size_t h = hint;
            double g2 = ytab_guess(&ap, yl, &h);
            assert_true(h == h0 && memcmp(&g, &g2, sizeof g) == 0);
        }
        long double X, Y;
        aa__offset_eval(&oc, 0, &X, &Y, NULL, NULL);
        double r = (double)aa__offset_root(&oc, 1, 0, 1, Y - yl, yl, NAN, NULL, NULL);
        worst = fmax(worst, fabs(g - r));
    }
    /* outside the table's heights: none */
    size_t h = 0;
    assert_true(isnan(ytab_guess(&ap, nd[1] - 0.5, &h)));
    assert_true(isnan(ytab_guess(&ap, nd[4 * YT_N - 3], &h)));
    /* a piece without a table (load_ytab's nyt 0 where the nodes' y do
     * not rise): none at any height */
    ap.nyt = 0;
    ytab_attach(&ap, nd);
    assert_true(isnan(ytab_guess(&ap, nd[4 * 32 + 1], &h)));
    print_message("199 heights: the starts within %.2g of the roots, the same from every hint\n",
                  worst);
    assert_true(worst <= 1e-8);
}

/* ---- meetings of pairs that share an end point ---- */

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The heights a shared end's test samples over [lo, lo + h] (2,000 + 50 of
 * them, sorted): evenly, then towards the end e (sg: the side of e the
 * heights lie on) at h 2^-j. */
static int end_heights(double *ys, double lo, double h, double e, double sg)
{
    int m = 0;
    for (int j = 1; j < 2000; j++)
        ys[m++] = lo + h * j / 2000.0;
    for (int j = 1; j <= 50; j++)
        ys[m++] = e + sg * ldexp(h, -j);
    qsort(ys, (size_t)m, sizeof *ys, cmp_dbl);
    return m;
}

/* Pieces p and q (one an offset piece) that share an end point E, whose
 * common heights [lo, hi] start (at_lo) or end at E: x_p - x_q sampled at
 * 2,000 heights evenly over [lo, hi] and at 2^-k of it from E (k = 1 ..
 * 50); each change of sign between neighbouring samples, both beyond
 * 1e-12 of 0 and the nearer farther than 1e-6 of the scale from E
 * (nearer, a meeting is E itself: scene_piece.c, near_shared_end), must
 * hold a meeting of area's form (aa__piece_meet_at) and of the
 * reference's (aa_piece_meet), and each of area's meetings must lie
 * farther than that from E, between two samples of opposite signs or
 * where x_p - x_q is within 1e-13 of 0 (a touch).  Adds the
 * sign changes to *changes, and 1 to *tangent if p and q leave E tangent
 * to each other (x_p - x_q within 1e-7 of the distance from E at 1e-4 of
 * [lo, hi] from it).  Returns the failures (their first few printed). */
static int shared_pair(const char *what, const aa_piece *p, const aa_piece *q, int at_lo,
                       int *changes, int *tangent)
{
    enum { NS = 2000 + 50 };
    double ys[NS];
    double lo = fmax(p->y0, q->y0), hi = fmin(p->y1, q->y1);
    double e = at_lo ? lo : hi, sg = at_lo ? 1.0 : -1.0, h = hi - lo;
    double res = 1e-6 * fmax(1.0, fabs(e));
    int m = end_heights(ys, lo, h, e, sg), bad = 0;
    const double none[2] = {NAN, NAN};
    double ya[16], yr[16];
    int na = aa__piece_meet_at(p, q, lo, hi, none, none, ya, 16);
    int nr = aa_piece_meet(p, q, lo, hi, yr, 16);
    int in_change[16] = {0};
    double prev = NAN, yprev = lo;
    for (int j = 0; j < m; j++) {
        double y = ys[j], d = aa_piece_x_at(p, y) - aa_piece_x_at(q, y);
        if (!(fabs(d) > 1e-12))
            continue; /* too near a meeting to tell its side */
        double near = at_lo ? yprev : y; /* the sample nearer the shared end */
        if (prev == prev && (prev < 0) != (d < 0) && fabs(near - e) > res) {
            (*changes)++;
            int fa = 0, fr = 0;
            for (int r = 0; r < na; r++)
                if (ya[r] >= yprev - 1e-9 && ya[r] <= y + 1e-9)
                    fa = in_change[r] = 1;
            for (int r = 0; r < nr; r++)
                fr |= yr[r] >= yprev - 1e-9 && yr[r] <= y + 1e-9;
            if (!(fa && fr) && bad++ < 3)
                print_message("%s: change of sides in [%.17g, %.17g] not met (area's %d, the "
                              "reference's %d)\n",
                              what, yprev, y, fa, fr);
        }
        prev = d, yprev = y;
    }
    for (int r = 0; r < na; r++) {
        double d = aa_piece_x_at(p, ya[r]) - aa_piece_x_at(q, ya[r]);
        if ((!(in_change[r] || fabs(d) <= 1e-13) || !(fabs(ya[r] - e) > res)) && bad++ < 3)
            print_message("%s: area's meeting at %.17g, x_p - x_q %.3g, %.3g from the shared "
                          "end\n",
                          what, ya[r], d, fabs(ya[r] - e));
    }
    double u = e + sg * 1e-4 * h;
    *tangent += fabs(aa_piece_x_at(p, u) - aa_piece_x_at(q, u)) <= 1e-7 * 1e-4 * h;
    return bad;
}

/* shared_pair on every pair of a placed scene's pieces that share an end
 * point, and on lines from each offset piece's ends through its point at
 * a fraction 1/2 and 1e-2 of its height from there, which meet it
 * there again.  Returns the pairs. */
static int shared_ends(const char *what, const aa_scene *s, int *tangent, int *all_changes)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int pairs = 0, changes = 0, bad = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double lo, hi;
            if (!offset_pair(p, q, &lo, &hi))
                continue;
            int at_lo = lo == p->y0 && lo == q->y0 && p->x0 == q->x0;
            int at_hi = hi == p->y1 && hi == q->y1 && p->x1 == q->x1;
            if (!at_lo && !at_hi)
                continue;
            pairs++;
            bad += shared_pair(what, p, q, at_lo, &changes, tangent);
        }
    const double fr[2] = {0.5, 1e-2};
    for (size_t k = 0; k < n; k++) {
        const aa_piece *q = &pc[k];
        if (q->kind != AA_PIECE_OFFSET || !q->dir)
            continue;
        for (int e = 0; e < 2; e++)
            for (int f = 0; f < 2; f++) {
                /* from end E = (xe, ye) through (xm, ym) to the other end's height */
                double xe = e ? q->x1 : q->x0, ye = e ? q->y1 : q->y0, yo = e ? q->y0 : q->y1;
                double ym = ye + fr[f] * (yo - ye), xm = aa_piece_x_at(q, ym);
                if (!(fabs(ym - ye) > 1e-5 * fmax(1.0, fabs(ye))))
                    continue;
                double xo = xe + (yo - ye) * (xm - xe) / (ym - ye);
                aa_piece p;
                memset(&p, 0, sizeof p);
                p.kind = AA_PIECE_LINE, p.dir = 1;
                p.x0 = e ? xo : xe, p.y0 = q->y0, p.x1 = e ? xe : xo, p.y1 = q->y1;
                p.cx = 0.5 * (p.x0 + p.x1), p.cy = 0.5 * (p.y0 + p.y1);
                p.bx = p.x1 - p.x0, p.by = p.y1 - p.y0;
                p.xmin = fmin(p.x0, p.x1), p.xmax = fmax(p.x0, p.x1);
                pairs++;
                bad += shared_pair(what, &p, q, !e, &changes, tangent);
            }
    }
    print_message("%-34s %d pairs sharing an end, %d sign changes sampled, %d not met or "
                  "off\n",
                  what, pairs, changes, bad);
    assert_int_equal(bad, 0);
    *all_changes += changes;
    return pairs;
}

/* fn on each of the strokes the meetings' tests take: the benchmark's
 * cubics (tests/bench_bezstroke.c) at 256 px, 2.5 px wide, round joins
 * and caps (their offsets fold), every `step` of its 20 rows (a step of 20
 * or more: row 0 only); then the first `ncases` of tight (folds), a loop
 * and a hook whose pieces sharing an end cross again away from it
 * (mitred, butt-capped) and three arcs (round), at 64 px; fn adds to the
 * two counters n[0] and n[1].
 * Returns the sum of fn's returns. */
static int each_stroke(int step, int ncases,
                       int (*fn)(const char *, const aa_scene *, int *, int *), int n[2])
{
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / 256.0;
    double cs[2 + 6 * 10];
    int sum = 0;
    for (int r = 0; r < 20; r += step) {
        bench_cubics(r, 0, 10, cs);
        aa_scene *placed = placed_stroke(cs, 10, &st, 256);
        char what[64];
        snprintf(what, sizeof what, "benchmark's row %d, 256 px", r);
        sum += fn(what, placed, &n[0], &n[1]);
        aa_scene_free(placed);
    }
    const double *cases[4] = {tight, loop, hook, three};
    const int ncs[4] = {1, 1, 1, 3};
    const double widths[4] = {0.3, 0.5, 0.4, 0.08};
    const char *names[4] = {"tight, w 0.3 (folds), 64 px", "loop, w 0.5, 64 px",
                            "hook, w 0.4, 64 px", "3 arcs, round, w 0.08, 64 px"};
    for (int c = 0; c < ncases && c < 4; c++) {
        st.join = c == 3 ? AA_JOIN_ROUND : AA_JOIN_MITER;
        st.cap = c == 3 ? AA_CAP_ROUND : AA_CAP_BUTT;
        st.width = widths[c];
        aa_scene *placed = placed_stroke(cases[c], ncs[c], &st, 64);
        sum += fn(names[c], placed, &n[0], &n[1]);
        aa_scene_free(placed);
    }
    return sum;
}

static void test_shared_ends(void **state)
{
    (void)state;
    int tc[2] = {0, 0}; /* tangent, changes */
    /* the sanitizer build's subset: the benchmark's row 0 (SAN_SUBSET) */
    int pairs = each_stroke(SAN_SUBSET ? 20 : 4, 3, shared_ends, tc);
    print_message("%d pairs sharing an end, %d of them tangent there; %d sign changes\n", pairs,
                  tc[0], tc[1]);
    assert_true(tc[0] >= 10 && tc[1] >= 1); /* the cases were built */
}

/* Line p and the shared end E (at_lo: at the start of their common
 * heights) it nearly shares with evolute q, moved by dx in x, so that its
 * end is off the evolute by far more than rounding: x_p - x_q sampled as
 * shared_pair samples it; every change of sign between neighbouring
 * samples, both beyond 1e-12 of 0, must hold a meeting of area's form
 * (aa__piece_meet_at), near E too (E is no longer shared), and each of
 * area's meetings lie between such samples or where x_p - x_q is within
 * 1e-13 of 0.  Adds the changes to *changes and those within 1e-6 of the
 * scale of E (where the cut next to a shared end reports none) to *near.
 * Returns the failures (their first few printed). */
static int moved_pair(const char *what, const aa_piece *line, const aa_piece *q, int at_lo,
                      double dx, int *changes, int *near)
{
    enum { NS = 2000 + 50 };
    aa_piece p = *line;
    p.x0 += dx, p.x1 += dx, p.cx += dx, p.xmin += dx, p.xmax += dx;
    double ys[NS], lo = fmax(p.y0, q->y0), hi = fmin(p.y1, q->y1);
    double e = at_lo ? lo : hi, sg = at_lo ? 1.0 : -1.0, h = hi - lo;
    int m = end_heights(ys, lo, h, e, sg), bad = 0;
    const double none[2] = {NAN, NAN};
    double ya[16];
    int na = aa__piece_meet_at(&p, q, lo, hi, none, none, ya, 16), in_change[16] = {0};
    double prev = NAN, yprev = lo;
    for (int j = 0; j < m; j++) {
        double y = ys[j], d = aa_piece_x_at(&p, y) - aa_piece_x_at(q, y);
        if (!(fabs(d) > 1e-12))
            continue;
        if (prev == prev && (prev < 0) != (d < 0)) {
            (*changes)++;
            *near += fmin(fabs(yprev - e), fabs(y - e)) <= 1e-6 * fmax(1.0, fabs(e));
            int fa = 0;
            for (int r = 0; r < na; r++)
                if (ya[r] >= yprev - 1e-9 && ya[r] <= y + 1e-9)
                    fa = in_change[r] = 1;
            if (!fa && bad++ < 3)
                print_message("%s, line moved %.3g: change of sides in [%.17g, %.17g] (%.3g "
                              "from the end) not met\n",
                              what, dx, yprev, y, fabs(yprev - e));
        }
        prev = d, yprev = y;
    }
    for (int r = 0; r < na; r++) {
        double d = aa_piece_x_at(&p, ya[r]) - aa_piece_x_at(q, ya[r]);
        if (!(in_change[r] || fabs(d) <= 1e-13) && bad++ < 3)
            print_message("%s, line moved %.3g: area's meeting at %.17g, x_p - x_q %.3g\n", what,
                          dx, ya[r], d);
    }
    return bad;
}

/* The pairs of a line and an evolute of a placed scene that end at one
 * point stored apart by rounding: an end of each within 1e-12 px of the
 * other's in x and in y but not the same bits, at an end of their common
 * heights (where a folding offset's region ends, the normal line and the
 * evolute piece it ends on, each end found its own way).  Area's form
 * takes such an end as shared (scene_piece.c, ends_touch): shared_pair
 * holds it to what a shared end must give.  And with the line moved off
 * the end in x by 1e-7 to 1e-11 px, either way, far beyond rounding
 * (moved_pair), the end is no longer shared, and every change of sides,
 * next to it too, must be met.  n[0] counts the pairs, n[1] the changes
 * within 1e-6 of the scale of the end on the moved lines.  Returns the
 * pairs. */
static int touching_ends(const char *what, const aa_scene *s, int *n, int *near)
{
    size_t np;
    const aa_piece *pc = aa_scene_pieces(s, &np);
    int pairs = 0, changes = 0, moved = 0, bad = 0, nr = 0;
    for (size_t i = 0; i < np; i++)
        for (size_t k = 0; k < np; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double lo, hi;
            if (p->kind != AA_PIECE_LINE || q->kind != AA_PIECE_OFFSET || !q->oc.evolute ||
                !offset_pair(p, q, &lo, &hi))
                continue;
            for (int at_lo = 0; at_lo < 2; at_lo++) {
                /* E: the evolute's end at lo or hi, and the line's end next to it */
                double ye = at_lo ? lo : hi, xe, yl, xl;
                if (q->y0 == ye)
                    xe = q->x0;
                else if (q->y1 == ye)
                    xe = q->x1;
                else
                    continue;
                int l0 = fabs(p->y0 - ye) < fabs(p->y1 - ye);
                yl = l0 ? p->y0 : p->y1, xl = l0 ? p->x0 : p->x1;
                if (!(fabs(yl - ye) <= 1e-12 && fabs(xl - xe) <= 1e-12) ||
                    (yl == ye && xl == xe))
                    continue;
                pairs++;
                int tangent = 0;
                bad += shared_pair(what, p, q, at_lo, &changes, &tangent);
                const double dx[6] = {1e-7, -1e-7, 1e-9, -1e-9, 1e-11, -1e-11};
                for (int j = 0; j < 6; j++, moved++)
                    bad += moved_pair(what, p, q, at_lo, dx[j], &changes, &nr);
            }
        }
    print_message("%-34s %d pairs of a line and an evolute ending an ulp apart, %d lines "
                  "moved, %d sign changes sampled (%d next to the end), %d not met or off\n",
                  what, pairs, moved, changes, nr, bad);
    assert_int_equal(bad, 0);
    *n += pairs, *near += nr;
    return pairs;
}

/* Ends of a line and an evolute stored an ulp apart (touching_ends) on
 * the benchmark's rows at 256 px and the tight stroke's folds. */
static void test_touching_ends(void **state)
{
    (void)state;
    int n[2] = {0, 0};
    each_stroke(SAN_SUBSET ? 4 : 1, 1, touching_ends, n);
    print_message("%d pairs ending an ulp apart; %d changes of sides next to the end on the "
                  "moved lines\n",
                  n[0], n[1]);
    assert_true(n[0] >= 10 && n[1] >= 1); /* the cases were found */
}

/* ---- a pair's common heights asked with their parameters given ---- */

/* An offset piece's parameter at height y strictly inside its rows as area
 * finds it where a pair's common heights begin or end inside a band
 * (area.c, seg_t_kept): the solve over the whole piece; NAN elsewhere
 * (aa__piece_meet_at takes the piece's own ends itself). */
static double whole_solve(const aa_piece *p, double y)
{
    if (p->kind != AA_PIECE_OFFSET || !(y > p->y0 && y < p->y1))
        return NAN;
    return aa__offset_solve_d(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y);
}

/* Every offset pair of placed scene s asked over heights [ya, yb] beyond or
 * inside its common rows, with no parameters known, and over the common
 * heights [lo, hi] aa__piece_meet_at takes from those, with the
 * parameters there given (whole_solve): the same meetings bit for bit.
 * Returns the pairs asked. */
static int common_heights(const char *what, const aa_scene *s)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    const double none[2] = {NAN, NAN};
    int pairs = 0, bad = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double c0, c1;
            if (!offset_pair(p, q, &c0, &c1) || p->xmax < q->xmin || q->xmax < p->xmin)
                continue;
            /* beyond both ends; from a third of the way; up to two thirds */
            const double ya[3] = {c0 - 0.37, c0 + (c1 - c0) / 3.0, c0 - 0.5};
            const double yb[3] = {c1 + 0.41, c1 + 0.5, c0 + 2.0 * (c1 - c0) / 3.0};
            for (int w = 0; w < 3; w++) {
                double lo = fmax(c0, ya[w]), hi = fmin(c1, yb[w]), y1[16], y2[16];
                const double tp[2] = {whole_solve(p, lo), whole_solve(p, hi)};
                const double tq[2] = {whole_solve(q, lo), whole_solve(q, hi)};
                int m1 = aa__piece_meet_at(p, q, ya[w], yb[w], none, none, y1, 16);
                int m2 = aa__piece_meet_at(p, q, lo, hi, tp, tq, y2, 16);
                pairs++;
                int same = m1 == m2;
                for (int r = 0; same && r < m1; r++)
                    same = y1[r] == y2[r];
                if (!same && bad++ < 5)
                    print_message("%s: pieces %zu and %zu over [%.17g, %.17g]: %d meetings "
                                  "asked so, %d given the parameters\n",
                                  what, i, k, ya[w], yb[w], m1, m2);
            }
        }
    assert_int_equal(bad, 0);
    return pairs;
}

static void test_common_heights(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    int pairs = 0;
    double cs[2 + 6 * 10];
    st.width = 2.5 / 256.0;
    for (int r = 0; r < 20; r += 8) {
        bench_cubics(r, 0, 10, cs);
        aa_scene *placed = placed_stroke(cs, 10, &st, 256);
        char what[64];
        snprintf(what, sizeof what, "benchmark's row %d, 256 px", r);
        pairs += common_heights(what, placed);
        aa_scene_free(placed);
    }
    st.join = AA_JOIN_MITER, st.cap = AA_CAP_BUTT;
    st.width = 0.3;
    aa_scene *placed = placed_stroke(tight, 1, &st, 64);
    pairs += common_heights("tight, w 0.3 (folds), 64 px", placed);
    aa_scene_free(placed);
    print_message("%d pairs' heights asked both ways\n", pairs);
    assert_true(pairs > 100); /* the cases were built */
}

/* ---- the tangents' cones that part a pair at once ---- */

/* p's parameter at height y in its rows: its own at its ends, else the
 * solve over the whole piece (a line's: 0, not read) */
static double param_of(const aa_piece *p, double y)
{
    if (p->kind != AA_PIECE_OFFSET)
        return 0.0;
    if (!(y > p->y0))
        return p->ot0;
    if (!(y < p->y1))
        return p->ot1;
    return whole_solve(p, y);
}

/* Every pair of placed scene s's pieces, one an offset piece and the other
 * an offset piece or a line, over its common heights and parts of them
 * (the first and last thirds, 1e-3 of them in the middle, and 1e-6 of
 * the scale next to each end): where aa__piece_cones_apart says x_p - x_q
 * is strictly monotone, it is sampled here at 201 heights (aa_piece_x_at)
 * and must be: no step between neighbouring samples against the
 * direction from the first to the last beyond 1e-12 (their rounding), and
 * no more than one change of sign beyond 1e-12 of 0 (none away from an
 * end point they share).  Adds the parts said apart to *apart and those
 * not said so whose samples are not monotone to *seen (the oracle sees
 * such parts).  Returns the failures. */
static int cones(const char *what, const aa_scene *s, int *apart, int *seen)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int bad = 0, parts = 0, yes = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double c0, c1;
            if (!offset_pair(p, q, &c0, &c1) ||
                (p->kind != AA_PIECE_OFFSET && p->kind != AA_PIECE_LINE) ||
                (q->kind != AA_PIECE_OFFSET && q->kind != AA_PIECE_LINE))
                continue;
            double h = c1 - c0, e0 = 1e-6 * fmax(1.0, fabs(c0)), e1 = 1e-6 * fmax(1.0, fabs(c1));
            const double ya[5] = {c0, c0, c1 - h / 3.0, c0 + 0.4995 * h, c0};
            const double yb[5] = {c1, c0 + h / 3.0, c1, c0 + 0.5005 * h, c0 + e0};
            for (int w = 0; w < 6; w++) {
                double lo = w < 5 ? ya[w] : c1 - e1, hi = w < 5 ? yb[w] : c1;
                if (!(lo < hi) || !(lo >= c0 && hi <= c1))
                    continue;
                const double tp[2] = {param_of(p, lo), param_of(p, hi)};
                const double tq[2] = {param_of(q, lo), param_of(q, hi)};
                int said = aa__piece_cones_apart(p, q, tp, tq);
                double d[201];
                for (int j = 0; j <= 200; j++) {
                    double y = j == 200 ? hi : lo + (hi - lo) * j / 200.0;
                    d[j] = aa_piece_x_at(p, y) - aa_piece_x_at(q, y);
                }
                double dir = d[200] > d[0] ? 1.0 : -1.0, prev = NAN;
                int back = 0, changes = 0;
                for (int j = 0; j < 200; j++)
                    back += dir * (d[j + 1] - d[j]) < -1e-12;
                for (int j = 0; j <= 200; j++) {
                    if (!(fabs(d[j]) > 1e-12))
                        continue;
                    changes += prev == prev && (prev < 0) != (d[j] < 0);
                    prev = d[j];
                }
                parts++;
                yes += said;
                if (!said) {
                    *seen += back > 0;
                    continue;
                }
                if ((back > 0 || changes > 1) && bad++ < 5)
                    print_message("%s: pieces %zu and %zu over [%.17g, %.17g] said apart: %d "
                                  "steps back, %d changes of sign\n",
                                  what, i, k, lo, hi, back, changes);
            }
        }
    print_message("%-34s %d parts of pairs, %d said apart, %d not so\n", what, parts, yes, bad);
    *apart += yes;
    return bad;
}

/* The cones hold every tangent: for each offset piece of placed scene s,
 * over its whole parameters and the first and last thirds of them, a line
 * along its tangent (aa_offset_point's derivative) at each of 33 points
 * of that range must not be said apart from it (the line's direction lies
 * in the piece's cone there).  Returns the failures; adds the lines to
 * *lines. */
static int cone_holds(const char *what, const aa_scene *s, int *lines)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *q = &pc[k];
        if (q->kind != AA_PIECE_OFFSET || !q->dir)
            continue;
        double t0 = q->ot0, t1 = q->ot1, d = t1 - t0;
        const double ra[3] = {t0, t0, t1 - d / 3.0}, rb[3] = {t1, t0 + d / 3.0, t1};
        for (int w = 0; w < 3; w++)
            for (int j = 0; j <= 32; j++) {
                double t = ra[w] + (rb[w] - ra[w]) * j / 32.0, x, y, dx, dy;
                aa_offset_point(&q->oc, t, &x, &y, &dx, &dy);
                if (!(dy != 0.0) || !isfinite(dx) || !isfinite(dy))
                    continue;
                if (dy < 0.0)
                    dx = -dx, dy = -dy;
                aa_piece p;
                memset(&p, 0, sizeof p);
                p.kind = AA_PIECE_LINE, p.dir = 1;
                p.x0 = x, p.y0 = y, p.x1 = x + dx, p.y1 = y + dy;
                const double tp[2] = {0.0, 0.0}, tq[2] = {ra[w], rb[w]};
                (*lines)++;
                if (aa__piece_cones_apart(&p, q, tp, tq) && bad++ < 5)
                    print_message("%s: piece %zu over t in [%.17g, %.17g]: its tangent at %.17g "
                                  "is said outside its cone\n",
                                  what, k, ra[w], rb[w], t);
            }
    }
    return bad;
}

static void test_cones(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    int as[2] = {0, 0}; /* apart, seen */
    /* the sanitizer build's subset: the benchmark's row 0 (SAN_SUBSET) */
    int bad = each_stroke(SAN_SUBSET ? 20 : 8, 4, cones, as), apart, seen;
    /* an S: its offsets' tangents turn back at the base's inflection,
     * beyond the cone of their ends' */
    const double ess[8] = {0.1, 0.5, 0.45, -0.1, 0.55, 1.1, 0.9, 0.5};
    int lines = 0;
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 0.05;
    for (int c = 0; c < 2; c++) {
        aa_scene *placed = placed_stroke(c ? ess : tight, 1, &st, 64);
        bad += cone_holds(c ? "S, w 0.05, 64 px" : "tight, w 0.05, 64 px", placed, &lines);
        aa_scene_free(placed);
    }
    apart = as[0], seen = as[1];
    print_message("%d parts said apart, %d others seen not monotone; %d tangents held\n", apart,
                  seen, lines);
    assert_int_equal(bad, 0);
    assert_true(apart >= 1000 && seen >= 10 && lines >= 500); /* all kinds were met */
}


/* tests/bench_bezstroke.c's rows of cubics rows[0..nr) at px x px, 2.5 px
 * wide, round joins and caps, every pixel crowded with folded offsets,
 * evolutes and joins: `area` (its own code: rows, clusters, quadrature)
 * against the box reference, the largest difference (*e) and the values
 * above 1 plus the reference's bound (*over). */
static void crowd_rows(const int *rows, int nr, int px, double *e, int *over)
{
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / px;
    aa_scene *s = bench_rows_stroke(rows, nr, &st); /* one subpath a row */
    support_view v = {.w = px, .h = px, .threads = 0};
    aa_image ref, bound, a;
    support_reference(s, &v, &ref, &bound, NULL);
    support_render("area", s, "box", px, px, 1, &a, NULL);
    int wi, wj;
    *e = support_max_diff(&a, &ref, &wi, &wj);
    *over = 0;
    for (int j = 0; j < px; j++)
        for (int i = 0; i < px; i++)
            *over += aa_pixel(&ref, i, j)[0] > 1.0 + aa_pixel(&bound, i, j)[0];
    print_message("%d rows at %d px: max |area - reference| %.1e (at %d,%d), %d values over 1\n",
                  nr, px, *e, wi, wj, *over);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_image_free(&a);
    aa_scene_free(s);
}

/* The parts of offset pieces that end at a piece's end (the outline's
 * vertex, rounded to double) add the sliver between their chord to the
 * vertex and the chord the quadrature takes (area.c, offset_end_area),
 * about the vertex and the part's chord where the other end is a line's,
 * a side's or a sub-band's: the benchmark's row of cubics r = 10
 * (tests/bench_bezstroke.c, 50 cubics, round joins and caps, 2.5 px wide)
 * at 1024 px against the reference on the window of 128 x 64 pixels from
 * (640, 520), each pixel within the reference's bound and 2e-14 (3.7e-15
 * beyond it at most; 8.7e-14 with the chord taken the wrong way from the
 * vertex, 3.9e-14 with the sliver left out where one end is the piece's). */
static void test_end_chord(void **state)
{
    (void)state;
    const int r = 10, n = 1024, x0 = 640, y0 = 520, w = 128, h = 64;
    double cs[2 + 6 * 50];
    bench_cubics(r, 0, 50, cs);
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 2.5 / n;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    aa_scene *s = stroke_scene(cs, 50, &st, NULL);
    aa_image im, ref, bound;
    support_render("area", s, "box", n, n, 1, &im, NULL);
    support_reference_part(s, n, n, x0, y0, w, h, "box", &ref, &bound, NULL);
    double most = -INFINITY;
    int wi = -1, wj = -1;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            for (int c = 0; c < 3; c++) {
                double e = fabs(aa_pixel(&im, x0 + i, y0 + j)[c] - aa_pixel(&ref, i, j)[c]) -
                           aa_pixel(&bound, i, j)[0];
                if (e > most)
                    most = e, wi = x0 + i, wj = y0 + j;
            }
    print_message("row %d at %d px: |area - reference| at most %.2g beyond its bound (at %d, %d)\n",
                  r, n, most, wi, wj);
    if (!(most <= 2e-14))
        fail_msg("area %g beyond the reference's bound at (%d, %d)", most, wi, wj);
    aa_image_free(&im);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* The reference where three pieces meet at one point within rounding:
 * the benchmark's first two rows at 32 px (crowd_rows).  At pixel (21, 1)
 * of the benchmark's path an offset piece and two lines meet 2.2e-15
 * apart in x; the crowded pixels' sweep (truth_crowd.c) swapped the first
 * two there and left the third pair, made neighbours by the swap and
 * meeting at that very height, out of order below it: the benchmark's
 * path read 1.259 there (a white stroke on black), 152 of its pixels off
 * by more than 1e-9.  Against `area`, within 1e-12, and no value above
 * 1. */
static void test_crowd_meet_at_swap(void **state)
{
    (void)state;
    const int rows[2] = {0, 1};
    double e;
    int over;
    crowd_rows(rows, 2, 32, &e, &over);
    assert_true(e < 1e-12);
    assert_int_equal(over, 0);
}

/* `area`'s order of a crowded band's sub-bands, each from the one above
 * (area.c, order_next): the segs with no event at a sub-band's top keep
 * their order, the others are placed again, and a run of segs within
 * rounding of each other there whose order is not sure (two lines crossing
 * where another pair crosses an ulp away, each with its twin traced there
 * and back) is placed again in the next sub-band, all of it.  The
 * benchmark's rows 0, 4 and 5 at 64 px against the reference within
 * 1e-12: 0.046 off at (31, 0) when such runs kept their first order, 0.42
 * off at (42, 14) when the pairs crossing at a sub-band's top kept theirs,
 * 0.030 off at (8, 14) when only the unsure pair of a run was placed
 * again. */
static void test_crowd_next_order(void **state)
{
    (void)state;
    const int rows[3] = {0, 4, 5};
    double e;
    int over;
    crowd_rows(rows, 3, 64, &e, &over);
    assert_true(e < 1e-12);
    assert_int_equal(over, 0);
}

/* The meetings area's form polishes on a pair of offset pieces (scene
 * placed s): each change of sign of x_p - x_q between neighbours of 400
 * heights over their common heights (both beyond 1e-9 of 0) is bisected
 * here to its root y* (aa_piece_x_at, the reference's x, until the bracket
 * is two adjacent doubles), and aa__piece_meet_at must report a meeting
 * within 1e-12 of the scale plus 1e-14 px over the bracket's slope of y*:
 * the rounding of the two roots, where x_p - x_q is known to about 1e-15
 * px.  Adds the roots to *met and the largest error over its tolerance
 * (per mille) to *worst.  Returns the failures (their first few printed). */
static int offset_meets(const char *what, const aa_scene *s, int *met, int *worst)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t k = i + 1; k < n; k++) {
            const aa_piece *p = &pc[i], *q = &pc[k];
            double lo, hi, ya[16];
            if (p->kind != AA_PIECE_OFFSET || q->kind != AA_PIECE_OFFSET ||
                !offset_pair(p, q, &lo, &hi) || p->xmax < q->xmin || q->xmax < p->xmin)
                continue;
            const double none[2] = {NAN, NAN};
            int ma = aa__piece_meet_at(p, q, lo, hi, none, none, ya, 16);
            double prev = NAN, yprev = lo;
            for (int j = 1; j < 400; j++) {
                double y = lo + (hi - lo) * j / 400.0;
                double d = aa_piece_x_at(p, y) - aa_piece_x_at(q, y);
                if (fabs(d) < 1e-9) {
                    prev = NAN;
                    continue;
                }
                if (prev == prev && (prev < 0) != (d < 0)) {
                    double l = yprev, r = y;
                    for (;;) {
                        double m = 0.5 * (l + r);
                        if (!(m > l && m < r))
                            break;
                        double dm = aa_piece_x_at(p, m) - aa_piece_x_at(q, m);
                        if (dm == 0.0) {
                            l = r = m;
                            break;
                        }
                        if ((dm < 0) == (prev < 0))
                            l = m;
                        else
                            r = m;
                    }
                    double root = 0.5 * (l + r), slope = fabs(d - prev) / (y - yprev);
                    double tol = 1e-12 * fmax(1.0, fabs(root)) + 1e-14 / slope, err = INFINITY;
                    for (int e = 0; e < ma; e++)
                        err = fmin(err, fabs(ya[e] - root));
                    (*met)++;
                    if (err <= tol) {
                        int pm = (int)(1000.0 * err / tol);
                        *worst = pm > *worst ? pm : *worst;
                    } else if (bad++ < 5) {
                        print_message("%s: pieces %zu, %zu meet at %.17g (bisected), area's "
                                      "nearest %.3g off (tolerance %.3g)\n",
                                      what, i, k, root, err, tol);
                    }
                }
                prev = d, yprev = y;
            }
        }
    return bad;
}

/* Two offset pieces' meeting polished in both parameters at once
 * (scene_piece.c, polish_offsets: Newton's method on P(s) - Q(t), one
 * evaluation of each a step): on every pair of offset pieces of the
 * strokes each_stroke takes whose x extents overlap, each meeting
 * bisected here is reported by area's form to rounding (offset_meets). */
static void test_offset_polish(void **state)
{
    (void)state;
    int mw[2] = {0, 0}; /* met, worst */
    int bad = each_stroke(4, 4, offset_meets, mw);
    print_message("%d meetings of offset pieces, each within %.3f of its tolerance\n", mw[0],
                  mw[1] / 1000.0);
    assert_int_equal(bad, 0);
    assert_true(mw[0] >= 50); /* the pairs were met */
}

/* aa__offset_end_dd against aa__offset_end at t (on oc and fx, fx.dd
 * set): the coordinate e[0] + e[1] and the slope e[2], bit for bit */
static int end_dd_same(const char *what, const aa_offset_curve *oc, int coord, double t)
{
    double e[4], at, slope;
    aa__offset_end(oc, coord, t, e);
    aa__offset_end_dd(oc, coord, t, &at, &slope);
    double sum = e[0] + e[1];
    if (memcmp(&sum, &at, sizeof at) == 0 && memcmp(&e[2], &slope, sizeof slope) == 0)
        return 0;
    print_message("%s: coordinate %d at t = %.17g: %.17g, slope %.17g against aa__offset_end's "
                  "%.17g, %.17g\n",
                  what, coord, t, at, slope, sum, e[2]);
    return 1;
}

/* Every offset piece of s with the double-double form (aa__offset_fix_dd),
 * both coordinates at 65 parameters across it and its ends, under the
 * scene's map (its axes kept: one of each row's two terms 0) and under
 * one that turns them (both terms), each branch of the base's sum */
static int end_dd(const char *what, const aa_scene *s, int *pieces, int *evals)
{
    size_t n;
    const aa_piece *pc = aa_scene_pieces(s, &n);
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        if (pc[i].kind != AA_PIECE_OFFSET)
            continue;
        for (int turn = 0; turn < 2; turn++) {
            aa_offset_curve oc = pc[i].oc;
            if (turn) {
                double m0 = oc.m[0], m3 = oc.m[3];
                oc.m[0] = 0.8 * m0, oc.m[1] = 0.6 * m3, oc.m[2] = -0.6 * m0, oc.m[3] = 0.8 * m3;
            }
            aa__offset_fix fx, fs;
            aa__offset_fix_dd(&oc, &fx, 1);
            if (!fx.dd)
                continue;
            (*pieces)++;
            /* its coefficients hi + lo by fma's products (fx, where the
             * processor has it) and by Dekker's split (fs): the same bits
             * (under the turning map, whose products are not exact; the
             * scene's, a power of 2, leave every lo 0) */
            aa__offset_fix_dd(&oc, &fs, 0);
            if (memcmp(fx.dc, fs.dc, sizeof fx.dc) || memcmp(fx.du, fs.du, sizeof fx.du)) {
                print_message("%s: piece %zu's coefficients differ by fma and by Dekker's "
                              "split (map %d): x's t^1 %.17g + %.17g against %.17g + %.17g\n",
                              what, i, turn, fx.dc[1][0][0], fx.dc[1][1][0], fs.dc[1][0][0],
                              fs.dc[1][1][0]);
                if (bad++ >= 5)
                    return bad;
            }
            double t0 = pc[i].ot0, t1 = pc[i].ot1;
            for (int coord = 0; coord < 2; coord++)
                for (int j = 0; j <= 64; j++) {
                    double t = j == 64 ? t1 : t0 + (t1 - t0) * j / 64.0;
                    (*evals)++;
                    if (end_dd_same(what, &oc, coord, t) && bad++ >= 5)
                        return bad;
                }
        }
    }
    return bad;
}

/* The tables of the band lines' starts (area.c, yt_node) evaluate the
 * double-double form's pieces by aa__offset_end_dd: the same bits as
 * aa__offset_end (eval_dd against eval_parts without the stops), on the
 * strokes each_stroke takes, every row of the benchmark's at 256 px; and
 * aa__offset_fix_dd's coefficients the same by fma (offset.c,
 * fix_coefs_fma) as by Dekker's split. */
static void test_end_dd(void **state)
{
    (void)state;
    int pe[2] = {0, 0}; /* pieces, evaluations */
    int bad = each_stroke(1, 4, end_dd, pe);
    print_message("%d pieces, %d evaluations against aa__offset_end\n", pe[0], pe[1]);
    assert_int_equal(bad, 0);
    assert_true(pe[0] >= 1000);
}

/* The parts of offset pieces that start at a piece's end (its top, where
 * the part's first parameter is the piece's ot0 or ot1): offset_end_area's
 * test of both ends at once (area.c, the two comparisons of each end two
 * by two).  The benchmark's row 11 (tests/bench_bezstroke.c, 50 cubics,
 * round joins and caps, 2.5 px wide) at 1024 px against the reference on
 * the window of 128 x 64 pixels from (40, 544), its round cap and first
 * cubics: each pixel within the reference's bound and 1e-14, none beyond
 * the bound by more than that. */
static void test_end_top(void **state)
{
    (void)state;
    const int r = 11, n = 1024, x0 = 40, y0 = 544, w = 128, h = 64;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 2.5 / n;
    st.join = AA_JOIN_ROUND;
    st.cap = AA_CAP_ROUND;
    aa_scene *s = bench_rows_stroke(&r, 1, &st);
    aa_image im, ref, bound;
    support_render("area", s, "box", n, n, 1, &im, NULL);
    support_reference_part(s, n, n, x0, y0, w, h, "box", &ref, &bound, NULL);
    double most = -INFINITY;
    int wi = -1, wj = -1, over = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double e = fabs(aa_pixel(&im, x0 + i, y0 + j)[0] - aa_pixel(&ref, i, j)[0]) -
                       aa_pixel(&bound, i, j)[0];
            over += e > 0.0;
            if (e > most)
                most = e, wi = x0 + i, wj = y0 + j;
        }
    print_message("row %d at %d px: %d pixels beyond the reference's bound, at most %.2g (at %d, "
                  "%d)\n",
                  r, n, over, most, wi, wj);
    if (!(most <= 1e-14))
        fail_msg("area %g beyond the reference's bound at (%d, %d)", most, wi, wj);
    aa_image_free(&im);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* The quadrature's three forms of a cubic's nodes, bit for bit: eight a
 * pass (AVX-512F, area_offset.c nodes_512: 8, 12 and 16 points a pass of
 * eight lanes and their halves summed in the four-lane order), four at a
 * time (AVX) and two at a time (SSE2), on parts of the offset pieces of
 * three strokes (the tight arc's folds: evolutes), of every width down to
 * 1e-6 of the piece, so that every rule is taken; on a processor without
 * AVX-512F (or AVX) the forms it has.  The tests above take the
 * processor's form, so this holds the others to it. */
static void test_nodes(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    ar_quad quad;
    must(area_quad_init(&quad));
    const int has = quad.avx;
    assert_in_range(has, 0, 2); /* the choice's 0, 1 or 2, not a feature's bit */
    if (has < 2)
        print_message("no AVX-512F here: the eight-lane form not run\n");
    static const double *const curves[3] = {three, tight, hook};
    static const int ncs[3] = {3, 1, 1};
    static const double widths[3] = {0.08, 0.3, 0.12};
    uint64_t rng = 987654321;
    int parts = 0, evolutes = 0, rules[AR_QUAD_RULES] = {0};
    for (int c = 0; c < 3; c++) {
        st.width = widths[c];
        aa_scene *s = stroke_scene(curves[c], ncs[c], &st, NULL);
        aa_scene *placed = aa_scene_place(s, 64, 64, 0, 0, 0);
        assert_non_null(placed);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET || pc[k].oc.base == AA_OFFSET_ELLIPSE)
                continue;
            ar_panel *pan;
            size_t npan;
            must(area_offset_panels(&pc[k].oc, pc[k].ot0, pc[k].ot1, &pan, &npan));
            ar_piece ap;
            memset(&ap, 0, sizeof ap);
            ap.src = &pc[k], ap.pan = pan, ap.npan = npan, ap.quad = &quad;
            evolutes += pc[k].oc.evolute;
            for (int i = 0; i < 400; i++) {
                double u[2];
                for (int e = 0; e < 2; e++) { /* uniform in [0, 1), 53 bits */
                    rng = rng * 6364136223846793005u + 1442695040888963407u;
                    u[e] = (double)(rng >> 11) * 0x1p-53;
                }
                double w = pow(10.0, -6.0 * u[1]);
                double ta = pc[k].ot0 + (pc[k].ot1 - pc[k].ot0) * u[0] * (1.0 - w);
                double tb = ta + (pc[k].ot1 - pc[k].ot0) * w;
                /* a part inside one panel: its rule (tb < ta where the piece
                 * runs backwards, ot1 < ot0) */
                double lo = fmin(ta, tb), hi = fmax(ta, tb);
                for (size_t j = 0; j < npan; j++)
                    if (pan[j].a <= lo && hi <= pan[j].b) {
                        rules[area_offset_rule(&pan[j], lo, hi)]++;
                        break;
                    }
                double v[3];
                for (int f = 0; f < 3; f++) {
                    quad.avx = f == 0 ? has : f == 1 ? (has > 0) : 0;
                    v[f] = area_offset_segment(&ap, ta, tb);
                }
                quad.avx = has;
                if (memcmp(&v[0], &v[1], sizeof v[0]) || memcmp(&v[0], &v[2], sizeof v[0]))
                    fail_msg("piece %zu [%.17g, %.17g]: %.17g eight at a time, %.17g four, "
                             "%.17g two",
                             k, ta, tb, v[0], v[1], v[2]);
                assert_true(isfinite(v[0]));
                parts++;
            }
            free(pan);
        }
        aa_scene_free(placed);
        aa_scene_free(s);
    }
    print_message("%d parts (%d evolute pieces) the same %s ways; inside a panel %d, %d, "
                  "%d took 8, 12, 16 points\n",
                  parts, evolutes, has == 2 ? "three" : has ? "two" : "one (no AVX)", rules[0],
                  rules[1], rules[2]);
    assert_true(parts > 0 && evolutes > 0);
    for (int r = 0; r < AR_QUAD_RULES; r++)
        assert_true(rules[r] > 0);
}

/* side_guess (area_internal.h), the start area's walk (area.c) takes for
 * an offset piece's root at a cell's side after the first on an
 * x-monotone part: on the offset pieces of tests/bench_bezstroke.c's
 * scene at 1024 px (double-double form), every part between two band
 * lines (or a line and the piece's end) on which x has no turn
 * (aa__offset_turns), its ends' x from q_offset (__float128), each side x
 * = i it crosses solved as walk solves it (aa__offset_root_fixd over what
 * is left of the part, from the side before, the chord's start: test_dd
 * and test_root_starts hold the solver's roots from any start to the
 * double nearest the root, or within 1e-21 max(|t|, 1) of the root where
 * that does not decide it: near a middle between two doubles, and near t
 * = 0); from the second side on, side_guess's start through the side
 * before the last (or the part's start), the last and the part's end,
 * against the chord's from the last to the end: nearer the root on most
 * sides, and within the solver's first double step (DD_D_STEP, 1e-4 of
 * the parameter: a start beyond it costs more double steps, offset.c's
 * root_d_more) on many more of them. */
static void test_side_guess(void **state)
{
    (void)state;
    aa_scene *placed = bench_placed(1024);
    size_t np;
    const aa_piece *pc = aa_scene_pieces(placed, &np);
    int sides = 0, nearer = 0, near_q = 0, near_c = 0;
    double sum_q = 0.0, sum_c = 0.0;
    for (size_t k = 0; k < np; k++) {
        if (pc[k].kind != AA_PIECE_OFFSET)
            continue;
        const aa_offset_curve *oc = &pc[k].oc;
        aa__offset_fix fx;
        aa__offset_fix_dd(oc, &fx, 1);
        if (!fx.dd)
            continue;
        double t0 = pc[k].ot0, t1 = pc[k].ot1;
        q128 P0[2], P1[2], dP[2];
        q_offset(oc, t0, P0, dP);
        q_offset(oc, t1, P1, dP);
        double y0 = (double)P0[1], y1 = (double)P1[1], ta = t0;
        int up = y1 > y0;
        /* the parts [ta, tb] between the band lines y = j on the piece */
        for (double j = up ? floor(y0) + 1.0 : ceil(y0) - 1.0;; j += up ? 1.0 : -1.0) {
            int last = up ? !(j < y1) : !(j > y1);
            double tb = last ? t1 : aa__offset_root_fixd(oc, &fx, 1, t0, t1, y0 - j, j, NAN, NULL);
            double tt[2];
            if (aa__offset_turns(oc, 0, fmin(ta, tb), fmax(ta, tb), tt) == 0) {
                q128 Pa[2], Pb[2];
                q_offset(oc, ta, Pa, dP);
                q_offset(oc, tb, Pb, dP);
                double xa = (double)Pa[0], xb = (double)Pb[0];
                int right = xb > xa;
                double i0 = right ? floor(xa) + 1.0 : ceil(xa) - 1.0;
                /* the side before the last (tp, xp), the last (tl, xl) */
                double tp = NAN, xp = NAN, tl = ta, xl = xa;
                for (double i = i0; right ? i < xb : i > xb; i += right ? 1.0 : -1.0) {
                    double gc = tl + (tb - tl) * ((i - xl) / (xb - xl));
                    double gq = side_guess(tp, xp, tl, xl, tb, xb, i);
                    double t = aa__offset_root_fixd(oc, &fx, 0, tl, tb, xl - i, i, gc, NULL);
                    if (tp == tp) {
                        double eq = fabs(gq - t), ec = fabs(gc - t);
                        double step = 1e-4 * fmax(fabs(t), 1.0);
                        sides++;
                        nearer += eq <= ec;
                        near_q += eq <= step, near_c += ec <= step;
                        sum_q += eq, sum_c += ec;
                    }
                    tp = tl, xp = xl, tl = t, xl = i;
                }
            }
            if (last)
                break;
            ta = tb;
        }
    }
    aa_scene_free(placed);
    print_message("%d sides after a part's first: side_guess's start nearer the root than the "
                  "chord's on %d; within 1e-4 of it on %d against %d; the errors' sums %.3g "
                  "against %.3g\n",
                  sides, nearer, near_q, near_c, sum_q, sum_c);
    assert_true(sides > 3000);
    assert_true(nearer >= 0.9 * sides);
    assert_true(near_q >= 0.6 * sides && near_c <= 0.4 * sides);
    assert_true(sum_q <= 0.5 * sum_c);
}

/* The roots' independence of their start (offset.c: root_dd and root_ld,
 * as aa__offset_root_fixd gives them): on the offset pieces of
 * tests/bench_bezstroke.c's scene at 256 px (the double-double form's
 * cubics, and the evolutes and pieces with stops the long double form
 * solves), at lines y = j + 0.37 k (k = 0..2) across each piece and at
 * lines 1 to 4 doubles inside its start's height and inside its end's
 * (a band's end within rounding of the piece's end, as area's sub_key
 * meets them: roots near t = 0 at a forwards piece's start and a
 * backwards piece's end), each from four starts (none: the bracket's
 * ends; 1e-5 off the root; 0.37 of the bracket; its middle), each root t
 * against the root by q_offset (__float128): the line's distance e0 from
 * the point at t, and the root's from t, e0 / |y'| (|y'| the slope at
 * t; y is linear about the root over that distance).  The double-double
 * form stops where its error is judged within DD_EST max(|t|, 1) =
 * 1e-21 max(|t|, 1) (1e-5 of an ulp of t in [0.5, 1), but many ulps of t
 * below 1e-5, where ulps are finer): held to |t - root| <= 1e-20
 * max(|t|, 1) + ulp(t) / 2; the long double form rounds a root found in
 * long double, whose evaluation rounds (the point to about 2^-64 of its
 * terms' size, 1.4e-17 px at 256 px), so a root near a middle between
 * two doubles rounds to either: held to e0 - |y'| ulp(t) / 2 <= 4e-17
 * px (where |y'| is small, as on the small evolutes nearly flat in y,
 * that leaves t free over many ulps).  Roots not the nearest double (the
 * point at a neighbour nearer the line) and roots from two starts that
 * differ are counted and printed.  It failed with DD_EST 1e-13 (a
 * double-double root 2.78e-17 beyond the middle at t =
 * 0.49999999139946683), with the long double form's root taken from its
 * double phase (2.09e-16 px farther), with the double-double form's roots
 * below |t| = 1e-6 moved by 1e-19 (1e-19 off at t = 3.6e-16) and with
 * the long double form's where |y'| < 1e-3 px moved by 1e-9 (the point
 * 3.58e-16 px off at |y'| = 3.26e-7 px); a check of the root against its
 * two neighbouring doubles alone let the last two pass. */
static void test_root_starts(void **state)
{
    (void)state;
    aa_scene *placed = bench_placed(256);
    size_t np;
    const aa_piece *pc = aa_scene_pieces(placed, &np);
    /* [0]: the double-double form, [1]: the long double form */
    int roots[2] = {0, 0}, off[2] = {0, 0}, differ[2] = {0, 0}, near0 = 0, flat = 0;
    int differ_flat = 0;
    double worst_dd = 0.0, worst_dd_t = 0.0, worst_px = 0.0, worst_px_s = 0.0;
    for (size_t k = 0; k < np; k++) {
        if (pc[k].kind != AA_PIECE_OFFSET)
            continue;
        const aa_offset_curve *oc = &pc[k].oc;
        if (oc->base != AA_OFFSET_CUBIC)
            continue;
        aa__offset_fix fx;
        aa__offset_fix_dd(oc, &fx, 1);
        int form = fx.dd ? 0 : 1;
        double a = pc[k].ot0, b = pc[k].ot1;
        q128 Pa[2], Pb[2], dP[2];
        q_offset(oc, a, Pa, dP);
        q_offset(oc, b, Pb, dP);
        double ca = (double)Pa[1], cb = (double)Pb[1], dir = cb > ca ? 1.0 : -1.0;
        double lo = fmin(ca, cb), hi = fmax(ca, cb);
        /* the lines: 1 to 4 doubles inside the start's height and the
         * end's (a backwards piece's end is at t = 0), then j + 0.37 k
         * strictly inside the range */
        double lines[8 + 3 * 300];
        int nl = 0;
        double y = ca;
        for (int u = 0; u < 4; u++)
            lines[nl++] = y = nextafter(y, dir * INFINITY);
        y = cb;
        for (int u = 0; u < 4; u++)
            lines[nl++] = y = nextafter(y, -dir * INFINITY);
        for (double j = floor(lo); j < hi && nl + 3 <= (int)(sizeof lines / sizeof *lines);
             j++)
            for (int v = 0; v < 3; v++)
                if (j + 0.37 * v > lo + 1e-9 && j + 0.37 * v < hi - 1e-9)
                    lines[nl++] = j + 0.37 * v;
        for (int l = 0; l < nl; l++) {
            double yl = lines[l], fa = ca - yl, t[4];
            long double x;
            for (int g = 0; g < 4; g++) {
                double guess = g == 0   ? NAN
                               : g == 1 ? t[0] + (b > a ? 1e-5 : -1e-5)
                               : g == 2 ? a + 0.37 * (b - a)
                                        : 0.5 * (a + b);
                t[g] = aa__offset_root_fixd(oc, &fx, 1, a, b, fa, yl, guess, &x);
                q128 P[2], Q[2], dQ[2];
                q_offset(oc, t[g], P, dP);
                q128 e0 = P[1] - yl;
                e0 = e0 < 0 ? -e0 : e0;
                double slope = fabs((double)dP[1]), px = 0.0;
                for (int side = 0; side < 2; side++) {
                    q_offset(oc, nextafter(t[g], side ? INFINITY : -INFINITY), Q, dQ);
                    q128 e1 = Q[1] - yl;
                    e1 = e1 < 0 ? -e1 : e1;
                    if (e1 < e0 && (double)(e0 - e1) > px)
                        px = (double)(e0 - e1);
                }
                if (px > 0) {
                    off[form]++;
                    near0 += form == 0 && fabs(t[g]) < 1e-5;
                    flat += form == 1 && slope < 1e-3;
                }
                /* the root's distance from t, e0 / |y'| (__float128: y is
                 * linear about the root over it), beyond half an ulp of t;
                 * the long double form's in px, e0 beyond |y'| ulp / 2 */
                double ulp = nextafter(fabs(t[g]), INFINITY) - fabs(t[g]);
                double dist = (double)(e0 / (q128)slope), ex = (double)e0 - 0.5 * slope * ulp;
                double rel = (dist - 0.5 * ulp) / fmax(fabs(t[g]), 1.0);
                if (!form && rel > worst_dd)
                    worst_dd = rel, worst_dd_t = t[g];
                if (form && ex > worst_px)
                    worst_px = ex, worst_px_s = slope;
                if (form ? !(ex <= 4e-17) : !(rel <= 1e-20))
                    fail_msg("piece %zu (%s form) line y = %.17g from start %d: t %.17g, the "
                             "root %.3g from it (half an ulp %.3g), the point %.3g px from the "
                             "line (|y'| %.3g)",
                             k, form ? "long double" : "double-double", yl, g, t[g], dist,
                             0.5 * ulp, (double)e0, slope);
                roots[form]++;
                if (g && t[g] != t[0]) {
                    differ[form]++;
                    differ_flat += form == 1 && slope < 1e-3;
                }
            }
        }
    }
    aa_scene_free(placed);
    print_message("double-double form: %d roots, %d not the nearest double (%d of them below "
                  "t = 1e-5), the root at most %.3g max(|t|, 1) beyond half an ulp of t (t = "
                  "%.3g), %d differing by start; long double form: %d roots, %d not the nearest "
                  "(%d of them where |y'| < 1e-3 px), the point at most %.3g px beyond |y'| ulp "
                  "/ 2 (|y'| %.3g px), %d differing by start (%d where |y'| < 1e-3 px)\n",
                  roots[0], off[0], near0, worst_dd, worst_dd_t, differ[0], roots[1], off[1],
                  flat, worst_px, worst_px_s, differ[1], differ_flat);
    assert_true(roots[0] > 10000 && roots[1] > 10000);
}

/* area's starts of roots of y = yl on an interval of an offset piece's
 * table whose t(y) Hermite form is not within the table's tolerance
 * (area_internal.h: ytab_guess, yt_turn; y turning at the piece's end,
 * where dt/dy is infinite and load_ytab marks the intervals there): the
 * root of y(t)'s Hermite form through the nodes' heights and slopes, from
 * the root of its quadratic Taylor form about the end of the smaller
 * slope (the chord's where that has none) and two Newton steps.  On the
 * offsets (d = 0.1) of x = t and five y(t), mapped 64 px to a unit, each
 * tabled at t = k/64 in the direction y rises (load_ytab's order) with
 * every interval marked (so each start is yt_turn's): A y = t^2 (t from 0
 * to 1, the turn at the table's first node), B 2t - t^2 (0 to 1, the
 * turn at its last: yt_turn's branch about s = 1), C (1 - t)^2 and D 1 -
 * t^2 (1 to 0: backwards pieces, the turn at the first node and at the
 * last), E 3t^2 - 2t^3 (0 to 1, turns at both ends).  At 199 heights
 * evenly over the table, 40 heights 2^-k of the first interval above
 * the first node and 40 2^-k of the last below the last, each start
 * against the root bisected in the test on q_offset's y (__float128):
 * within 1e-6 of it on A to D (the solver's first double step, DD_D_STEP,
 * is 1e-4), within TURN_TOL_E on E, where y's cubic term makes the
 * quadratic's start about the turn farther off and its two Newton steps
 * leave more; no NaN.  At the heights of the nodes but the last (outside
 * the table's range) the start is the node's t (the quadratic's root s =
 * 0 is not strictly inside, and at the turn 0/0: it was NaN there).  It
 * failed with no Newton step after the quadratic's start (3.6e-6 off on
 * A) and with the quadratic taken about the other end (6.5e-6 off). */
#define TURN_TOL_E 2e-5
static void turn_case(const char *name, const double yb[4], double t0, double t1, double tol)
{
    aa_offset_curve oc;
    double nd[4 * YT_N];
    ar_piece ap;
    table_piece(name, yb, t0, t1, 1, &oc, nd, &ap);
    double worst = 0.0, worst_c = 0.0;
    int heights = 0, nodes = 0;
    for (int i = 1; i < 280 + YT_N - 1; i++) {
        double yl;
        if (i < 200)
            yl = nd[1] + (nd[4 * YT_N - 3] - nd[1]) * i / 200.0;
        else if (i < 240)
            yl = nd[1] + (nd[5] - nd[1]) * ldexp(1.0, -(i - 199));
        else if (i < 280)
            yl = nd[4 * YT_N - 3] - (nd[4 * YT_N - 3] - nd[4 * YT_N - 7]) * ldexp(1.0, -(i - 239));
        else
            yl = nd[4 * (i - 280) + 1];
        size_t h = 0;
        double g = ytab_guess(&ap, yl, &h);
        const double *na = nd + 4 * h, *nb = na + 4;
        if (i >= 280) { /* node i - 280's height: its t */
            if (!(h == (size_t)(i - 280) && g == na[0]))
                fail_msg("%s: at node %d's height %.17g the start %.17g (interval %zu), not "
                         "its t %.17g", name, i - 280, yl, g, h, nd[4 * (i - 280)]);
            nodes++;
            continue;
        }
        double c = na[0] + (nb[0] - na[0]) * ((yl - na[1]) / (nb[1] - na[1]));
        /* the root: y(t) - yl bisected on q_offset's y over the interval */
        double lo = na[0], hi = nb[0];
        for (int it = 0; it < 200 && nextafter(lo, hi) != hi; it++) {
            double mid = 0.5 * (lo + hi);
            q128 P[2], dP[2];
            q_offset(&oc, mid, P, dP);
            if (P[1] < yl)
                lo = mid;
            else
                hi = mid;
        }
        double e = fabs(g - lo), ec = fabs(c - lo);
        if (!(e <= tol))
            fail_msg("%s: y = %.17g (interval %zu): start %.17g, root %.17g (%.3g off; the "
                     "chord's %.3g)", name, yl, h, g, lo, e, ec);
        worst = fmax(worst, e), worst_c = fmax(worst_c, ec);
        heights++;
    }
    print_message("%s: %d heights, the starts within %.2g of the roots (the chord's within "
                  "%.2g); %d nodes' heights, each the node's t\n",
                  name, heights, worst, worst_c, nodes);
}

static void test_turn_starts(void **state)
{
    (void)state;
    const double ya[4] = {0, 0, 1, 0}, yb[4] = {0, 2, -1, 0}, yc[4] = {1, -2, 1, 0},
                 yd[4] = {1, 0, -1, 0}, ye[4] = {0, 0, 3, -2};
    turn_case("A, y = t^2", ya, 0, 1, 1e-6);
    turn_case("B, y = 2t - t^2", yb, 0, 1, 1e-6);
    turn_case("C, y = (1 - t)^2", yc, 1, 0, 1e-6);
    turn_case("D, y = 1 - t^2", yd, 1, 0, 1e-6);
    turn_case("E, y = 3t^2 - 2t^3", ye, 0, 1, TURN_TOL_E);
}

/* The offset of the cubic b (power basis, x then y) at distance d and its
 * derivative B'(1 - d k) at t, in long double (written here, not the
 * library's). */
static void sides_point(const double b[8], double d, long double t, long double o[2],
                        long double o1[2])
{
    long double p[2], v[2], a[2];
    for (int k = 0; k < 2; k++) {
        const double *c = b + 4 * k;
        p[k] = c[0] + t * (c[1] + t * (c[2] + t * (long double)c[3]));
        v[k] = c[1] + t * (2.0L * c[2] + 3.0L * c[3] * t);
        a[k] = 2.0L * c[2] + 6.0L * c[3] * t;
    }
    long double l = sqrtl(v[0] * v[0] + v[1] * v[1]);
    long double kap = (v[0] * a[1] - v[1] * a[0]) / (l * l * l);
    o[0] = p[0] - d * v[1] / l, o[1] = p[1] + d * v[0] / l;
    o1[0] = v[0] * (1.0L - d * kap), o1[1] = v[1] * (1.0L - d * kap);
}

/* Where the offsets of b at d (t in [pl, ph]) and at -d (u in [ql, qh])
 * come nearest, by brute force: a 64 x 64 grid of (t, u), then Newton's
 * method on O_d(t) - O_-d(u) = 0 from its 6 nearest cells, kept in the
 * ranges, in long double; the least distance found, *ts and *us there. */
static long double sides_nearest(const double b[8], double d, double pl, double ph, double ql,
                                 double qh, long double *ts, long double *us)
{
    enum { G = 64, S = 6 };
    long double bd[S], bt[S], bu[S], best = INFINITY;
    for (int k = 0; k < S; k++)
        bd[k] = INFINITY, bt[k] = pl, bu[k] = ql;
    for (int i = 0; i <= G; i++)
        for (int j = 0; j <= G; j++) {
            long double t = pl + (ph - pl) * (long double)i / G;
            long double u = ql + (qh - ql) * (long double)j / G;
            long double o[2], o1[2], r[2], r1[2];
            sides_point(b, d, t, o, o1);
            sides_point(b, -d, u, r, r1);
            long double e = hypotl(o[0] - r[0], o[1] - r[1]);
            int w = 0;
            for (int k = 1; k < S; k++)
                if (bd[k] > bd[w])
                    w = k;
            if (e < bd[w])
                bd[w] = e, bt[w] = t, bu[w] = u;
        }
    for (int k = 0; k < S; k++) {
        long double t = bt[k], u = bu[k], e = bd[k];
        for (int it = 0; it < 40; it++) {
            long double o[2], o1[2], r[2], r1[2];
            sides_point(b, d, t, o, o1);
            sides_point(b, -d, u, r, r1);
            long double fx = o[0] - r[0], fy = o[1] - r[1];
            e = hypotl(fx, fy);
            if (e < best)
                best = e, *ts = t, *us = u;
            long double det = -o1[0] * r1[1] + o1[1] * r1[0];
            if (!(fabsl(det) > 0.0L))
                break;
            long double dt = (-fx * r1[1] + fy * r1[0]) / det, du = (o1[0] * fy - o1[1] * fx) / det;
            t -= dt, u -= du;
            t = t < pl ? pl : (t > ph ? ph : t), u = u < ql ? ql : (u > qh ? qh : u);
        }
    }
    return best;
}

/* The next of a linear congruential sequence, in [0, 1). */
static double sides_rnd(uint64_t *lcg)
{
    *lcg = *lcg * 6364136223846793005u + 1442695040888963407u;
    return (double)(*lcg >> 11) * 0x1p-53;
}

/* (B(t) - B(s)) . T(phi) for cubic b, phi the mean of the directions of
 * B' at s and t: 0 where B(t) - B(s) is normal to T(phi), where the sides
 * at d and -d meet for the d below (sides_meet_d), in long double. */
static long double sides_g(const double b[8], long double s, long double t)
{
    long double o[2], o1[2], a[2], a1[2];
    sides_point(b, 0.0, s, a, a1);
    sides_point(b, 0.0, t, o, o1);
    long double phi = 0.5L * (atan2l(a1[1], a1[0]) + atan2l(o1[1], o1[0]));
    return (o[0] - a[0]) * cosl(phi) + (o[1] - a[1]) * sinl(phi);
}

/* A meeting of cubic b's sides: the root t0 of sides_g(b, 0, t) in [lo,
 * hi] (its sign at lo in *gl, at hi the other) by bisection, and the d at
 * which O_d(0) = O_-d(t0): B(t0) - B(0)'s component along N(phi) over 2
 * cos((theta(t0) - theta(0))/2), as d (N(0) + N(t0)) is that long. */
static double sides_meet_d(const double b[8], long double lo, long double hi, long double *t0,
                           long double *gl)
{
    long double s0 = 0.0L;
    *gl = sides_g(b, s0, lo);
    for (int it = 1; it < 200; it++) {
        long double t = 0.5L * (lo + hi), g = sides_g(b, s0, t);
        if ((g < 0) == (*gl < 0))
            lo = t;
        else
            hi = t;
    }
    long double a[2], a1[2], o[2], o1[2];
    *t0 = 0.5L * (lo + hi);
    sides_point(b, 0.0, s0, a, a1);
    sides_point(b, 0.0, *t0, o, o1);
    long double th0 = atan2l(a1[1], a1[0]), th1 = atan2l(o1[1], o1[0]);
    long double phi = 0.5L * (th0 + th1);
    return (double)(((o[0] - a[0]) * -sinl(phi) + (o[1] - a[1]) * cosl(phi)) /
                    (2.0L * cosl(0.5L * (th1 - th0))));
}

/* The cubic from 0 whose B' has the Bezier control vectors v[0..2]. */
static void sides_hodo(const double v[3][2], double b[8])
{
    for (int k = 0; k < 2; k++) {
        b[4 * k] = 0.0, b[4 * k + 1] = v[0][k], b[4 * k + 2] = v[1][k] - v[0][k];
        b[4 * k + 3] = (v[0][k] - 2.0 * v[1][k] + v[2][k]) / 3.0;
    }
}

/* Two offset pieces of cubic b, at d over [pl, ph] and at -d over [ql, qh]
 * of its parameter, under the map m (only what sides_apart reads). */
static void sides_pieces(const double b[8], const double m[6], double d, double pl, double ph,
                         double ql, double qh, aa_piece *p, aa_piece *q)
{
    memset(p, 0, sizeof *p);
    p->kind = AA_PIECE_OFFSET, p->dir = 1;
    memcpy(p->oc.b, b, sizeof p->oc.b);
    memcpy(p->oc.m, m, sizeof p->oc.m);
    p->oc.base = AA_OFFSET_CUBIC;
    *q = *p;
    p->oc.d = d, q->oc.d = -d;
    p->ot0 = pl, p->ot1 = ph, q->ot0 = qh, q->ot1 = ql;
}

/* The proof that a stroke's two sides never meet (aa__piece_sides_apart,
 * scene_piece.c's sides_apart): on random cubics, widths and parameter
 * ranges, every pair it accepts has no meeting by brute force
 * (sides_nearest: their least distance above 1e-6 of d; the pairs that
 * meet, below 1e-12 with the control points in [-1, 1], counted); and
 * cases built to meet, each refused: a Z whose directions span 100
 * degrees (from pi/2 on, the proof's cone, two points of it can face each
 * other across the stroke: sides at d and -d meet where B(t) - B(s) = d
 * (N(s) + N(t)), here found by a root of its component along the
 * directions' mean, (B(t) - B(s)) . T(phi), with s = 0, d its normal
 * component over 2 cos((theta(t) - theta(s))/2)), over the whole curve
 * and over two ranges each of which alone lies in a cone narrower than
 * pi/2 (the hull counts); a curve refused by v0 . v1 alone, met the same
 * way; a loop; two different cubics' offsets that cross; the same under a
 * map of determinant 0 and under two maps; evolutes; d = 0; and a cone
 * wider than pi/2 by v0 . v2 alone. */
static void test_sides_apart(void **state)
{
    (void)state;
    const double id[6] = {1, 0, 0, 1, 0, 0}, shear[6] = {2, 0.5, -0.75, 1.5, 3, -1};
    uint64_t lcg = 271828;
    int accepted = 0, meeting = 0, n = SAN_SUBSET ? 400 : 4000;
    long double least = INFINITY;
    for (int c = 0; c < n; c++) {
        double b[8], cp[8];
        for (int k = 0; k < 8; k++)
            cp[k] = 2.0 * sides_rnd(&lcg) - 1.0; /* control points x0..x3, y0..y3 */
        for (int k = 0; k < 2; k++) {
            const double *z = cp + 4 * k;
            b[4 * k] = z[0], b[4 * k + 1] = 3.0 * (z[1] - z[0]);
            b[4 * k + 2] = 3.0 * (z[2] - 2.0 * z[1] + z[0]);
            b[4 * k + 3] = z[3] - 3.0 * z[2] + 3.0 * z[1] - z[0];
        }
        double sg = sides_rnd(&lcg) < 0.5 ? -1.0 : 1.0, d = sg * 0.01 * pow(300.0, sides_rnd(&lcg));
        double r[4];
        for (int k = 0; k < 4; k++)
            r[k] = sides_rnd(&lcg);
        double pl = fmin(r[0], r[1]), ph = fmax(r[0], r[1]);
        double ql = fmin(r[2], r[3]), qh = fmax(r[2], r[3]);
        if (c % 3 == 0)
            pl = 0.0, ph = 1.0, ql = 0.0, qh = 1.0;
        if (!(ph > pl && qh > ql))
            continue;
        aa_piece p, q, ps, qs;
        sides_pieces(b, id, d, pl, ph, ql, qh, &p, &q);
        sides_pieces(b, shear, d, pl, ph, ql, qh, &ps, &qs);
        int said = aa__piece_sides_apart(&p, &q);
        assert_int_equal(said, aa__piece_sides_apart(&qs, &ps));
        long double ts = 0, us = 0, e = sides_nearest(b, d, pl, ph, ql, qh, &ts, &us);
        if (e < 1e-12L)
            meeting++;
        if (said) {
            accepted++;
            least = fminl(least, e / fabs(d));
            if (!(e > 1e-6L * fabs(d)))
                fail_msg("case %d: said apart, yet %.3Lg apart at t %.17Lg, u %.17Lg (d %.17g)",
                         c, e, ts, us, d);
        }
    }
    print_message("sides apart: %d of %d random pairs said apart, none meeting (least distance "
                  "%.3Lg of d); %d meeting, none said apart\n",
                  accepted, n, least, meeting);
    assert_true(accepted > n / 10 && meeting > n / 40);
    /* a Z: B' from (1, 0) through 30 (cos 100deg, sin 100deg) to (1, 0), its
     * directions from 0 to 98.1 degrees */
    double z[8], al = 100.0 * M_PI / 180.0, w1[2] = {30.0 * cos(al), 30.0 * sin(al)};
    for (int k = 0; k < 2; k++) {
        double w0 = k ? 0.0 : 1.0;
        z[4 * k] = 0.0, z[4 * k + 1] = w0, z[4 * k + 2] = w1[k] - w0;
        z[4 * k + 3] = (2.0 * w0 - 2.0 * w1[k]) / 3.0;
    }
    /* a root of g(s, t) = (B(t) - B(s)) . T(phi) with s < t, s = 0: g(0, 0.9)
     * > 0 > g(0, 1) = (2 + 30 cos 100deg)/3 */
    long double t0, gl;
    double dz = sides_meet_d(z, 0.9L, 1.0L, &t0, &gl);
    /* O_dz(0) = O_-dz(t0) up to dz's rounding: the sides at dz and -dz meet */
    long double ts = 0, us = 0, e = sides_nearest(z, dz, 0.0, 1.0, 0.0, 1.0, &ts, &us);
    print_message("a Z (directions from 0 to 98.1 degrees): its sides %.17g apart meet at t "
                  "%.6Lf and %.6Lf (%.3Lg apart)\n",
                  2.0 * dz, ts, us, e);
    assert_true(gl > 0.0L && e < 1e-12L && fabs(dz) > 0.1);
    for (int k = 0; k < 2; k++) {
        /* the whole Z, then the two ends' ranges holding the meeting */
        aa_piece p, q;
        double pl = k && ts > 0.5L ? 0.99 : 0.0, ph = k && ts < 0.5L ? 0.01 : 1.0;
        double ql = k && us > 0.5L ? 0.99 : 0.0, qh = k && us < 0.5L ? 0.01 : 1.0;
        assert_true(ts >= pl && ts <= ph && us >= ql && us <= qh);
        sides_pieces(z, id, dz, pl, ph, ql, qh, &p, &q);
        if (aa__piece_sides_apart(&p, &q) || aa__piece_sides_apart(&q, &p))
            fail_msg("the Z over [%g, %g] and [%g, %g] said apart; its sides meet", pl, ph, ql,
                     qh);
        /* each range alone within a cone narrower than pi/2 */
        sides_pieces(z, id, dz, pl, ph, pl, ph, &p, &q);
        assert_true(k == 0 || aa__piece_sides_apart(&p, &q));
        sides_pieces(z, id, dz, ql, qh, ql, qh, &p, &q);
        assert_true(k == 0 || aa__piece_sides_apart(&p, &q));
    }
    /* a loop: control points (0, 0), (1.5, 1), (-0.5, 1), (1, 0) */
    const double loopc[8] = {0, 4.5, -10.5, 7, 0, 3, -3, 0};
    aa_piece p, q;
    sides_pieces(loopc, id, 0.05, 0.0, 1.0, 0.0, 1.0, &p, &q);
    e = sides_nearest(loopc, 0.05, 0.0, 1.0, 0.0, 1.0, &ts, &us);
    assert_true(e < 1e-12L && !aa__piece_sides_apart(&p, &q));
    /* two cubics' offsets crossing: each straight, one base shifted */
    const double l1[8] = {0, 1, 0, 0, 0, 0.1, 0, 0};
    sides_pieces(l1, id, 0.2, 0.0, 1.0, 0.0, 1.0, &p, &q);
    assert_true(aa__piece_sides_apart(&p, &q));
    q.oc.b[4] = -0.45; /* its base 0.45 lower: its side at 0.2 meets p's */
    assert_false(aa__piece_sides_apart(&p, &q));
    q = p; /* one side twice: the same curve */
    assert_false(aa__piece_sides_apart(&p, &q));
    const double flat[6] = {1, 2, 0.5, 1, 0, 0}; /* determinant 0 */
    sides_pieces(l1, flat, 0.2, 0.0, 1.0, 0.0, 1.0, &p, &q);
    assert_false(aa__piece_sides_apart(&p, &q));
    /* the same line's sides under two maps: q's 0.4 higher, its side at
     * -0.2 on p's at 0.2 (the two sides of different curves) */
    sides_pieces(l1, id, 0.2, 0.0, 1.0, 0.0, 1.0, &p, &q);
    q.oc.m[5] = 0.4;
    assert_false(aa__piece_sides_apart(&p, &q) || aa__piece_sides_apart(&q, &p));
    /* evolutes (the centres of curvature, m(B + N/k), whatever d): at d and
     * -d one curve; and d = 0 and -0, both B itself */
    sides_pieces(l1, id, 0.2, 0.0, 1.0, 0.0, 1.0, &p, &q);
    p.oc.evolute = q.oc.evolute = 1;
    assert_false(aa__piece_sides_apart(&p, &q));
    sides_pieces(l1, id, 0.0, 0.0, 1.0, 0.0, 1.0, &p, &q);
    assert_false(aa__piece_sides_apart(&p, &q) || aa__piece_sides_apart(&q, &p));
    /* each of the cone's three tests alone refusing a pair: B' from 80
     * degrees through 5 (cos -80deg, sin -80deg) to (1, 0) (v0 . v1 < 0
     * alone), its sides meeting at the d of a root of g(0, t) (from a scan
     * of t), and from 0 through 80 to 160 degrees (v0 . v2 < 0 alone: the
     * cone wider than pi/2, outside the proof; the Z above has v1 . v2 < 0
     * alone) */
    const double r80 = 80.0 * M_PI / 180.0;
    const double vm[3][2] = {{cos(r80), sin(r80)}, {5.0 * cos(-r80), 5.0 * sin(-r80)}, {1, 0}};
    const double vw[3][2] = {{1, 0}, {cos(r80), sin(r80)}, {cos(2 * r80), sin(2 * r80)}};
    double bm[8], bw[8];
    sides_hodo(vm, bm);
    sides_hodo(vw, bw);
    for (int c = 0; c < 2; c++) {
        const double(*v)[2] = c ? vw : vm;
        double d01 = v[0][0] * v[1][0] + v[0][1] * v[1][1];
        double d02 = v[0][0] * v[2][0] + v[0][1] * v[2][1];
        double d12 = v[1][0] * v[2][0] + v[1][1] * v[2][1];
        if (c)
            assert_true(d01 > 0.1 && d02 < -0.1 && d12 > 0.1);
        else
            assert_true(d01 < -0.1 && d02 > 0.1 && d12 > 0.1);
    }
    long double tl = 0.0L, th = 0.0L;
    for (int k = 1; k < 64 && th == 0.0L; k++)
        if ((sides_g(bm, 0.0L, k / 64.0L) < 0) != (sides_g(bm, 0.0L, (k + 1) / 64.0L) < 0))
            tl = k / 64.0L, th = (k + 1) / 64.0L;
    double dm = sides_meet_d(bm, tl, th, &t0, &gl);
    e = sides_nearest(bm, dm, 0.0, 1.0, 0.0, 1.0, &ts, &us);
    print_message("B' of control vectors at 80, -80 and 0 degrees: its sides %.17g apart meet "
                  "at t %.6Lf and %.6Lf (%.3Lg apart)\n",
                  2.0 * fabs(dm), ts, us, e);
    assert_true(th > 0.0L && e < 1e-12L && fabs(dm) > 0.1);
    sides_pieces(bm, id, dm, 0.0, 1.0, 0.0, 1.0, &p, &q);
    assert_false(aa__piece_sides_apart(&p, &q) || aa__piece_sides_apart(&q, &p));
    sides_pieces(bw, id, 0.1, 0.0, 1.0, 0.0, 1.0, &p, &q);
    assert_false(aa__piece_sides_apart(&p, &q) || aa__piece_sides_apart(&q, &p));
}

/* The rows' batches of single()'s side roots (area.c, side_ask: the root
 * on the common side of an offset seg alone in its cluster in two cells,
 * asked in AVX-512F's or AVX2's lanes before the row's clusters close,
 * taken by single() without a test of its own) against the same rows
 * asking each of those roots alone (aa__area_side_batch 0: single()'s own
 * call of offset_tau_u, the form before the batches): the same image,
 * bit for bit, on tests/bench_bezstroke.c's scene at 1024 px (21,690
 * roots a render from the batches) and 256 px (2,330; and on two
 * threads), on three arcs 0.08 wide at 64 px and 0.4 wide at 48 px and
 * on a hook 0.4 wide at 64 px (segs of single's kind in the image's first
 * and last cells).  It failed with the taken root an ulp up (53,496
 * values of the image at 1024 px not the same bits, 5.55e-16 off at
 * most), with its y not kept (offset_keep: 79,038, 6.66e-16), with each
 * batch's roots given to the next seg (129,558, 0.521), with the one
 * pass's clusters at even cells not asked (37,566, 0.499), with the
 * sorted pass's last cluster's hi one more (735, 1) and with side_ask
 * not asking the segs in the first cell or in the last (on the arcs 0.4
 * wide: 6 values, 0.0926 off, at (0, 11); 12, 0.141 off, at (46, 37)). */
static void side_batch_case(const char *what, const aa_scene *s, int n, int threads)
{
    aa_image a, b;
    aa__area_side_batch = 1;
    support_render("area", s, "box", n, n, threads, &a, NULL);
    aa__area_side_batch = 0;
    support_render("area", s, "box", n, n, threads, &b, NULL);
    aa__area_side_batch = 1;
    size_t moved = 0, nv = (size_t)n * n * 3;
    for (size_t k = 0; k < nv; k++)
        moved += memcmp(&a.v[k], &b.v[k], sizeof a.v[k]) != 0;
    int wi = 0, wj = 0;
    double e = support_max_diff(&a, &b, &wi, &wj);
    print_message("%-28s %d thread(s): %zu values not the same bits, at most %.3g off (at %d, "
                  "%d)\n",
                  what, threads, moved, e, wi, wj);
    assert_true(support_same_image(&a, &b));
    aa_image_free(&a);
    aa_image_free(&b);
}

static void test_side_batch(void **state)
{
    (void)state;
    static const int sizes[2] = {1024, 256};
    for (int k = 0; k < 2; k++) {
        int n = sizes[k];
        aa_scene *s = bench_scene_at(n, 20);
        char what[40];
        snprintf(what, sizeof what, "the benchmark's, %d px", n);
        side_batch_case(what, s, n, 1);
        if (n == 256)
            side_batch_case(what, s, n, 2);
        aa_scene_free(s);
    }
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 0.08;
    aa_scene *s = stroke_scene(three, 3, &st, NULL);
    side_batch_case("3 arcs, round, w 0.08, 64 px", s, 64, 1);
    aa_scene_free(s);
    /* segs in the image's first and last cells (close_single's ca >= 0
     * and cb < W, which side_ask must test alike) */
    st.width = 0.4;
    s = stroke_scene(three, 3, &st, NULL);
    side_batch_case("3 arcs, round, w 0.4, 48 px", s, 48, 1);
    aa_scene_free(s);
    aa_stroke_style_default(&st);
    st.width = 0.4;
    s = stroke_scene(hook, 1, &st, NULL);
    side_batch_case("hook, w 0.4, 64 px", s, 64, 1);
    aa_scene_free(s);
}

/* ---- the parameters at a pair's common heights, from the table's start ---- */

/* Where a piece begins or ends inside a band, area solves the other
 * piece's parameter at that height (area.c, seg_t_kept) over the whole
 * piece from the piece's table's start (ytab_guess), not from its ends:
 * a root as good, not always the same double (the meetings found moved
 * by rounding, within 6e-7 px at 256 px where two pieces leave a shared
 * end tangent to each other).  The benchmark's scene (its 20 rows, round
 * joins and caps, 2.5 px wide) at 256 px, `area` against the reference's
 * pixels in rows 0 to 127 (its first ten rows of cubics), each within the
 * reference's bound plus 1e-14.  It failed with the table's start taken
 * as the root (2.63e-09 beyond the bound at (140, 57)). */
static void test_common_starts(void **state)
{
    (void)state;
    const int n = 256, h = 128;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / n;
    aa_scene *s = bench_rows_stroke(NULL, 20, &st);
    aa_image im, ref, bound;
    support_render("area", s, "box", n, n, 1, &im, NULL);
    support_reference_part(s, n, n, 0, 0, n, h, "box", &ref, &bound, NULL);
    double most = -INFINITY;
    int wi = -1, wj = -1, over = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < n; i++) {
            double e = fabs(aa_pixel(&im, i, j)[0] - aa_pixel(&ref, i, j)[0]) -
                       aa_pixel(&bound, i, j)[0];
            over += e > 0.0;
            if (e > most)
                most = e, wi = i, wj = j;
        }
    print_message("the benchmark's scene at %d px, rows 0 to %d: %d pixels beyond the "
                  "reference's bound, at most %.2g (at %d, %d)\n",
                  n, h - 1, over, most, wi, wj);
    if (!(most <= 1e-14))
        fail_msg("area %g beyond the reference's bound at (%d, %d)", most, wi, wj);
    aa_image_free(&im);
    aa_image_free(&ref);
    aa_image_free(&bound);
    aa_scene_free(s);
}

/* aa__offset_roots' double phase on, in the lanes (offset_lanes.h: solve_step's next point
 * where a lane's first evaluation does not stop, Newton's step, b where it passes b still
 * unseen, else the bracket's middle, then its second step; the lanes that stop at neither
 * go on alone), against aa__offset_root_xyd and aa__offset_root_fixd asked one by one (the
 * peer: root_dd takes the same steps in scalar registers): the same roots, points and other
 * coordinates bit for bit (memcmp).  Lines y = j and x = i across the offset pieces of the
 * benchmark's cubics (2.5 px wide at 1024 px) and the tight arc (0.3 and 0.05 wide) by
 * fma's double-double form, from starts spread over the bracket (its 23 inner 24ths and
 * within 1e-3 of either end), which test_roots_batch's, within 3e-2 of the root, do not
 * take far: Newton's first step beyond the bracket or over half its width; and each span's
 * line through its end b, whose root is at the bracket's end (the second step's stop on
 * the value and its clamp to the bracket), and the line x = 946.95 across the benchmark's
 * rows stroked 12 px wide (a lane going on alone with b's unseen mark inverted takes
 * another path there, its point 5e-17 px off); shuffled and asked in batches of 1 to 9,
 * eight and four lanes. */
static void far_line(aa__offset_rootq **rq, size_t *nr, size_t *cap, const aa_offset_curve *oc,
                     const aa__offset_fix *fx, int coord, double a, double b, double fa, double j)
{
    for (int g = 0; g < 27; g++) {
        /* the 24ths, then 1e-3 and 1e-5 from a and b */
        double w = g < 25 ? 1e-3 : 1e-5;
        double r = g < 23 ? (g + 1) / 24.0 : g & 1 ? 1.0 - w : w;
        if (*nr == *cap) {
            *cap *= 2;
            *rq = realloc(*rq, *cap * sizeof **rq);
            assert_non_null(*rq);
        }
        (*rq)[(*nr)++] =
            (aa__offset_rootq){oc, fx, coord, a, b, fa, j, a + r * (b - a), NULL, NULL, NULL, 0.0};
    }
}

static void test_roots_far(void **state)
{
    (void)state;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    const int n = 1024;
    size_t cap = 1 << 15, nr = 0, nfx = 0, nwide = 0;
    aa__offset_rootq *rq = malloc(cap * sizeof *rq);
    aa__offset_fix *fxs = malloc(4096 * sizeof *fxs);
    aa_scene *keep[4];
    assert_non_null(rq);
    assert_non_null(fxs);
    for (int sc = 0; sc < 4; sc++) {
        aa_scene *s;
        if (sc == 0 || sc == 3) {
            st.width = (sc ? 12.0 : 2.5) / n;
            s = bench_rows_stroke(NULL, 3, &st); /* three of the benchmark's rows */
        } else {
            st.width = sc == 2 ? 0.05 : 0.3;
            s = stroke_scene(tight, 1, &st, NULL);
        }
        aa_scene *placed = aa_scene_place(s, n, n, 0, 0, 0);
        assert_non_null(placed);
        aa_scene_free(s);
        keep[sc] = placed;
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            const aa_offset_curve *oc = &pc[k].oc;
            aa__offset_fix *fx = &fxs[nfx++];
            assert_true(nfx <= 4096);
            aa__offset_fix_dd(oc, fx, 1);
            double t0 = pc[k].ot0, t1 = pc[k].ot1;
            for (int coord = 1; coord >= 0; coord--) {
                double ts[4];
                int nt = monotone_spans(oc, coord, t0, t1, ts);
                for (int e = 0; e + 1 < nt; e++) {
                    double a = ts[e], b = ts[e + 1], Pa[2], Pb[2];
                    aa_offset_point(oc, a, &Pa[0], &Pa[1], NULL, NULL);
                    aa_offset_point(oc, b, &Pb[0], &Pb[1], NULL, NULL);
                    double lo = fmin(Pa[coord], Pb[coord]), hi = fmax(Pa[coord], Pb[coord]);
                    if (sc == 3) {
                        if (coord == 0 && lo < 946.95 && hi > 946.95) {
                            far_line(&rq, &nr, &cap, oc, fx, 0, a, b, Pa[0] - 946.95, 946.95);
                            nwide += 27;
                        }
                        continue;
                    }
                    for (double j = ceil(lo + 1e-9); j < hi - 1e-9; j += 5)
                        far_line(&rq, &nr, &cap, oc, fx, coord, a, b, Pa[coord] - j, j);
                    far_line(&rq, &nr, &cap, oc, fx, coord, a, b, Pa[coord] - Pb[coord],
                             Pb[coord]);
                }
            }
        }
    }
    shuffle(rq, nr, sizeof *rq, 6789);
    /* outputs zeroed first, so that a long double's padding compares
     * equal too; every third request asks the other coordinate, not the
     * point */
    long double(*want)[2] = calloc(nr, sizeof *want), (*got)[2] = calloc(nr, sizeof *got);
    double *twant = malloc(nr * sizeof *twant);
    aa__offset_rootq *bq = malloc(nr * sizeof *bq);
    assert_non_null(want);
    assert_non_null(got);
    assert_non_null(twant);
    assert_non_null(bq);
    for (size_t i = 0; i < nr; i++) {
        const aa__offset_rootq *r = &rq[i];
        if (i % 3)
            twant[i] = aa__offset_root_xyd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa,
                                           r->target, r->guess, NULL, want[i]);
        else
            twant[i] = aa__offset_root_fixd(r->oc, r->fx, r->coord, r->ta, r->tb, r->fa,
                                            r->target, r->guess, &want[i][0]);
    }
    for (int lanes = 8; lanes >= 4; lanes -= 4) {
        for (size_t i = 0; i < nr; i++) {
            bq[i] = rq[i], bq[i].t = NAN;
            memset(got[i], 0, sizeof got[i]);
            bq[i].xy = i % 3 ? got[i] : NULL;
            bq[i].other = i % 3 ? NULL : &got[i][0];
        }
        for (size_t i = 0, len = 1; i < nr; i += len, len = len % 9 + 1)
            aa__offset_roots_lanes(bq + i, nr - i < len ? nr - i : len, lanes);
        for (size_t i = 0; i < nr; i++)
            if (memcmp(&bq[i].t, &twant[i], sizeof twant[i]) != 0 ||
                memcmp(got[i], want[i], sizeof want[i]) != 0)
                fail_msg("lanes %d, request %zu (coord %d, [%.17g, %.17g], target %.17g, guess "
                         "%.17g): t %.17g, one by one %.17g; (%.20Lg, %.20Lg) against (%.20Lg, "
                         "%.20Lg)",
                         lanes, i, bq[i].coord, bq[i].ta, bq[i].tb, bq[i].target, bq[i].guess,
                         bq[i].t, twant[i], got[i][0], got[i][1], want[i][0], want[i][1]);
    }
    print_message("%zu roots from starts spread over their brackets (%zu on x = 946.95, 12 px "
                  "wide), in batches of 1 to 9: the same bits as one by one\n",
                  nr, nwide);
    assert_true(nr > 10000);
    assert_true(nwide >= 27);
    free(want);
    free(got);
    free(twant);
    free(bq);
    free(rq);
    free(fxs);
    for (int i = 0; i < 4; i++)
        aa_scene_free(keep[i]);
}

/* ---- each solve of the parameters at a pair's common heights ---- */

/* What test_kept_solves gathers from area's solves (aa__area_kept_solve) */
static struct {
    int solves, over, outside, cubic;
    double worst, worst_out; /* the residual / its allowance; beyond the range / allowance */
    double wy, wr, wta, wtb, we, wtol;
} kept;

/* One of seg_t_kept's solves (area.c): r, the piece's parameter at height
 * y, held to the solver's stated stop (offset.c, solve_double: its double
 * evaluation of y within 2 DBL_EPSILON of the size of its terms, the
 * curve's coefficients times the map's, the map's offset, the normal term
 * and the target, or a Newton step within 1e-12, which leaves an error of
 * its square), here |y(r) - y| <= 4 DBL_EPSILON (size + |normal term|) +
 * |y'(r)| ulp(r) (twice the stop: that evaluation's own rounding, measured
 * within it, at most 0.49 and 0.51 of this at 256 and 1024 px; and r's): y(r) and y' by q_offset (__float128, from the curve's doubles);
 * and r within the seg's parameters at its band's ends [ta, tb] (either
 * order), beyond them only by the allowance over |y'|. */
static void kept_solve(const aa_piece *p, double y, double r, double ta, double tb)
{
    const aa_offset_curve *oc = &p->oc;
    kept.solves++;
    if (oc->base != AA_OFFSET_CUBIC)
        return; /* q_offset's are cubics' (none else in the scenes here) */
    kept.cubic++;
    q128 P[2], dP[2];
    q_offset(oc, r, P, dP);
    const double *b = oc->b, *m = oc->m;
    double sx = 0.0, sy = 0.0;
    for (int i = 0; i < 4; i++)
        sx += fabs(b[i]), sy += fabs(b[4 + i]);
    /* the normal term: y less the base curve's mapped y */
    q128 T = r, bx = b[0] + T * (b[1] + T * (b[2] + T * (q128)b[3]));
    q128 by = b[4] + T * (b[5] + T * (b[6] + T * (q128)b[7]));
    q128 nq = P[1] - (m[1] * bx + m[3] * by + m[5]);
    double size = fabs(m[1]) * sx + fabs(m[3]) * sy + fabs(m[5]) + fabs(y);
    double dn = fabs((double)nq), slope = fabs((double)dP[1]);
    double ulp = nextafter(fabs(r), INFINITY) - fabs(r);
    double tol = 4 * DBL_EPSILON * (size + dn) + slope * ulp;
    q128 eq = P[1] - y;
    double e = fabs((double)eq), ratio = e / tol;
    double lo = fmin(ta, tb), hi = fmax(ta, tb);
    double out = r < lo ? lo - r : r > hi ? r - hi : 0.0, ro = out * slope / tol;
    kept.over += !(ratio <= 1.0);
    kept.outside += !(ro <= 1.0);
    if (ratio > kept.worst || !(ratio == ratio))
        kept.worst = ratio, kept.wy = y, kept.wr = r, kept.we = e, kept.wtol = tol;
    if (ro > kept.worst_out)
        kept.worst_out = ro, kept.wta = ta, kept.wtb = tb;
}

/* area's solves of an offset seg's parameter where a pair's common heights
 * begin or end inside a band (area.c, seg_t_kept, from the piece's
 * table's start or the chord of the seg's parameters in the band), each
 * held directly (kept_solve, through aa__area_kept_solve): its residual
 * |y(r) - y| evaluated here in __float128 within the solver's stated
 * tolerance, and r inside the seg's parameters at its band's ends, over
 * every solve of a render of the benchmark's scene at 256 px and 1024 px
 * (4,323 and 2,651 solves; the residual at most 0.49 and 0.51 of its
 * allowance, none outside the range) and of the tight arc's folding
 * strokes (0.3 wide at 64 px, also sheared; 1.0 wide at 48 px).
 * test_common_starts, against the reference, let a root moved by 1e-5 of
 * the piece's parameter range pass; this failed with the root moved by
 * 1e-9, 1e-12, 1e-13 and 1e-14 of the range (at 256 px 4,288, 3,917,
 * 2,289 and 30 residuals beyond the allowance, at most 1.4e5, 139, 13.9
 * and 1.4 times it), not with 3e-15 (0.58), and with the solve replaced
 * by the root at y on the piece's neighbour beyond a turn of y at either
 * end (2,663 solves outside the seg's range; the residuals within their
 * allowance, 0.47 at most). */
static void kept_case(const char *what, const aa_scene *s, int n)
{
    aa_image im;
    memset(&kept, 0, sizeof kept);
    aa__area_kept_solve = kept_solve;
    /* one thread: the render's workers call kept_solve, and kept is not locked */
    support_render("area", s, "box", n, n, 1, &im, NULL);
    aa__area_kept_solve = NULL;
    aa_image_free(&im);
    print_message("%-28s %d solves (%d of cubics' offsets): the residual at most %.3g of its "
                  "allowance (%.3g px of %.3g at y = %.17g, r = %.17g), %d beyond it; beyond "
                  "the seg's range at most %.3g of the allowance, %d beyond it\n",
                  what, kept.solves, kept.cubic, kept.worst, kept.we, kept.wtol, kept.wy,
                  kept.wr, kept.over, kept.worst_out, kept.outside);
    if (kept.over || kept.outside)
        fail_msg("%s: %d solves beyond the residual's allowance (%.3g of it at y = %.17g, r = "
                 "%.17g), %d outside the seg's range (%.3g of the allowance, [%.17g, %.17g])",
                 what, kept.over, kept.worst, kept.wy, kept.wr, kept.outside, kept.worst_out,
                 kept.wta, kept.wtb);
    assert_true(kept.cubic > 0 && kept.cubic == kept.solves);
}

static void test_kept_solves(void **state)
{
    (void)state;
    static const int sizes[2] = {256, 1024};
    for (int k = 0; k < 2; k++) {
        int n = sizes[k];
        aa_scene *s = bench_scene_at(n, 20);
        char what[40];
        snprintf(what, sizeof what, "the benchmark's, %d px", n);
        kept_case(what, s, n);
        aa_scene_free(s);
    }
    static const double shear[6] = {1.3, 0.2, 0.5, 0.8, -0.1, -0.05}; /* test_reference's */
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.width = 0.3;
    aa_scene *s = stroke_scene(tight, 1, &st, NULL);
    kept_case("tight, w 0.3, 64 px", s, 64);
    aa_scene_free(s);
    s = stroke_scene(tight, 1, &st, shear);
    kept_case("tight, w 0.3, sheared, 64 px", s, 64);
    aa_scene_free(s);
    st.width = 1.0;
    s = stroke_scene(tight, 1, &st, NULL);
    kept_case("tight, w 1.0, 48 px", s, 48);
    aa_scene_free(s);
}

/* ---- parts reaching past their panel: never the 16-point rule in one share ---- */

/* The 20-point rule (x, w) on [lo, hi] of 1/2 (P - Pa) x P', P and P'
 * from q_offset (__float128); *g the same of |(P - Pa) x P'|. */
static q128 q_gl20(const aa_offset_curve *oc, const q128 Pa[2], q128 lo, q128 hi,
                   const long double *x, const long double *w, q128 *g)
{
    q128 h = (hi - lo) / 2, m = (lo + hi) / 2, s = 0, a = 0;
    for (int i = 0; i < 20; i++) {
        q128 P[2], dP[2];
        q_offset(oc, m + h * x[i], P, dP);
        q128 f = (P[0] - Pa[0]) * dP[1] - (P[1] - Pa[1]) * dP[0];
        s += w[i] * f, a += w[i] * (f < 0 ? -f : f);
    }
    *g = (h < 0 ? -h : h) * a / 2;
    return h * s / 2;
}

/* 1/2 the integral of (P - Pa) x P' over [lo, hi], adaptively: given
 * whole, the 20-point rule's value there, the same rule on each half,
 * their sum taken where it is within 1e-24 px^2 plus 1e-20 of the size of
 * its terms (q_gl20's g) of whole, else each half so again (at most to
 * depth 30: *deep counts the intervals that stopped there). */
static q128 q_adapt(const aa_offset_curve *oc, const q128 Pa[2], q128 lo, q128 hi, q128 whole,
                    const long double *x, const long double *w, int depth, int *deep)
{
    q128 mid = (lo + hi) / 2, ga, gb;
    q128 a = q_gl20(oc, Pa, lo, mid, x, w, &ga), b = q_gl20(oc, Pa, mid, hi, x, w, &gb);
    q128 e = a + b - whole;
    if ((e < 0 ? -e : e) <= 1e-24 + 1e-20 * (ga + gb))
        return a + b;
    if (depth >= 30) {
        (*deep)++;
        return a + b;
    }
    return q_adapt(oc, Pa, lo, mid, a, x, w, depth + 1, deep) +
           q_adapt(oc, Pa, mid, hi, b, x, w, depth + 1, deep);
}

/* test_shares_past's counts */
typedef struct {
    int parts, no812, no16, deep, met;
    double worst, worst_no812;
} past_stats;

/* test_shares_past on `per` parts from each panel but the last of offset
 * piece pc (a cubic's offset or evolute) */
static void past_piece(const char *what, const aa_piece *pc, const ar_quad *quad,
                       const long double *x1, const long double *w1, int per, uint64_t *rng,
                       past_stats *st)
{
    const aa_offset_curve *oc = &pc->oc;
    ar_piece ap;
    ar_panel *pan = shares_piece(pc, quad, &ap);
    size_t npan = ap.npan;
    double tmax = pan[npan - 1].b;
    for (size_t j = 0; j + 1 < npan; j++) {
        const ar_panel *p = &pan[j];
        double hmax = fmin(p->m + p->R, tmax);
        for (int i = 0; i < per; i++) {
            double u[2];
            for (int e = 0; e < 2; e++) { /* uniform in [0, 1), 53 bits */
                *rng = *rng * 6364136223846793005u + 1442695040888963407u;
                u[e] = (double)(*rng >> 11) * 0x1p-53;
            }
            double ta = p->b - (p->b - p->a) * u[0];
            double tb = hmax - (hmax - p->b) * pow(10.0, -3.0 * u[1]);
            if (!(ta >= p->a && ta < p->b && tb > p->b && tb < hmax))
                continue;
            double got = area_offset_segment(&ap, i & 1 ? tb : ta, i & 1 ? ta : tb);
            if (i & 1)
                got = -got;
            int dp = 0;
            q128 Pa[2], dPa[2], g;
            q_offset(oc, ta, Pa, dPa);
            q128 want = q_adapt(oc, Pa, ta, tb, q_gl20(oc, Pa, ta, tb, x1, w1, &g), x1, w1, 0,
                                &dp);
            long double mag;
            segment_l(oc, ta, tb, p->m, 4, 20, x1, w1, &mag);
            st->deep += dp;
            int panels = 0;
            for (size_t q = j; q < npan && pan[q].a < tb; q++)
                panels++;
            double err = fabs((double)(got - want));
            double tol = panels * AR_QUAD_TOL + 8 * DBL_EPSILON * (double)mag;
            /* the part's rho on the panel's disc, and each rule's bound */
            long double h = 0.5L * ((long double)tb - ta), mm = 0.5L * ((long double)ta + tb);
            long double z = (p->R - fabsl(mm - p->m)) / h;
            long double rho = z + sqrtl((z - 1) * (z + 1)), e[AR_QUAD_RULES];
            for (int q = 0; q < AR_QUAD_RULES; q++)
                e[q] = h * 64 * p->M / (15 * (1 - 1 / (rho * rho)) * powl(rho, 2 * quad->n[q]));
            int cannot = z > 1 && !(e[0] <= AR_QUAD_TOL) && !(e[1] <= AR_QUAD_TOL);
            if (!(err <= tol))
                fail_msg("%s: [%.17g, %.17g] from panel [%.17g, %.17g] (R %g, %d panels; 8 and "
                         "12 points' bounds %s): %.17g, here %.17g, %.2e off (allowed %.2e)",
                         what, ta, tb, p->a, p->b, p->R, panels,
                         cannot ? "beyond the tolerance" : "one within it", got, (double)want,
                         err, tol);
            st->worst = fmax(st->worst, err / tol);
            st->parts++;
            st->met += panels;
            if (cannot) {
                st->no812++;
                st->no16 += !(e[2] <= AR_QUAD_TOL);
                st->worst_no812 = fmax(st->worst_no812, err / tol);
            }
        }
    }
    free(pan);
}

/* Parts reaching past the end of their first panel whose Bernstein
 * ellipse lies in that panel's disc (area_offset.c, segment).  The
 * panel's M bounds the integrand on its disc, so on such a part's ellipse
 * (rho from the room R - |m' - m| about the part's middle m') an n-point
 * rule errs by at most h 64 M / (15 (1 - rho^-2) rho^(2n)), and one whose
 * bound is within AR_QUAD_TOL may take the part as one share.  The
 * 16-point rule rule_or_none gives where 8 and 12 fail is not such a rule:
 * unchecked, it is a share's inside a panel (its rho at least the
 * panel's, so its bound at most the panel's, which the panel meets), and
 * a part reaching past its panel's rho may be near 1; such a part goes
 * panel by panel, each share within AR_QUAD_TOL.  Here, from inside each
 * panel (but the last) to past its end, up to where the part's ellipse
 * leaves the disc (hi < m + R, many near there, rho near 1): the evolute
 * of x = t, y = k (t - 1/2)^3 (k = 1 and 10, 64 px to a unit) on [0.1,
 * 0.47], 0.03 short of its inflection, where c = B' x B'' (linear in t:
 * its lower bound on a disc exact along the axis) vanishes, a pole of the
 * integrand just beyond the discs of the panels next to the end; and 2
 * parts a panel of the offsets and evolutes of the three arcs 0.02 and
 * 0.3 wide and the tight arc 0.08 wide at 256 px (shares_stroke).
 * area_offset_segment against 1/2 the integral of (P - P(ta)) x P'
 * computed here adaptively (q_adapt: 20-point Gauss-Legendre on
 * q_offset's __float128 points, halved until the halves agree within
 * 1e-24 px^2 plus 1e-20 of their size; the rule's nodes in long double,
 * so the integral within about 1e-19 of its size), within AR_QUAD_TOL for each panel the part meets
 * plus 8 ulps of the size the double sum's terms have (segment_l's mag).
 * Each rule's bound is computed here (long double, powl) to count the
 * parts neither 8 nor 12 points may take as one share, and of them those
 * beyond 16 points' bound too (the evolutes: 128 parts, at most 0.029 of
 * the allowance, 122 and 110; the strokes: 244, 0.020, 238 and 227).  It
 * failed with such parts let take 16 points as one share (the evolute's,
 * k 1, [0.28384, 0.46966] over 5 panels: 4.54e-07 off, allowed 1.75e-10);
 * on the strokes' pieces alone that passed (their 244 parts at most 0.022
 * of the allowance; 976 parts, 8 a panel, at most 0.026: their
 * integrands' poles lie far outside the discs). */
static void test_shares_past(void **state)
{
    (void)state;
    ar_quad quad;
    must(area_quad_init(&quad));
    long double x1[20], w1[20];
    gauss_legendre_l(20, x1, w1);
    uint64_t rng = 192837465;
    past_stats ev = {0}, sk = {0};
    for (int c = 0; c < 2; c++) {
        double k = c ? 10.0 : 1.0;
        aa_piece pc;
        memset(&pc, 0, sizeof pc);
        pc.kind = AA_PIECE_OFFSET, pc.dir = 1;
        aa_offset_curve *oc = &pc.oc;
        oc->b[1] = 1; /* x = t; y = k (t - 1/2)^3 */
        oc->b[4] = -0.125 * k, oc->b[5] = 0.75 * k, oc->b[6] = -1.5 * k, oc->b[7] = k;
        const double m[6] = {64, 0, 0, 64, 3, 2};
        memcpy(oc->m, m, sizeof m);
        oc->evolute = 1;
        oc->base = AA_OFFSET_CUBIC;
        pc.ot0 = 0.1, pc.ot1 = 0.47;
        past_piece(c ? "evolute, k 10" : "evolute, k 1", &pc, &quad, x1, w1, 16, &rng, &ev);
    }
    for (int c = 0; c < 3; c++) {
        aa_scene *placed = shares_stroke(c);
        size_t np;
        const aa_piece *pc = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pc[k].kind != AA_PIECE_OFFSET)
                continue;
            if (pc[k].oc.base != AA_OFFSET_CUBIC)
                continue; /* q_offset evaluates a cubic's; these strokes have none other */
            past_piece("stroke", &pc[k], &quad, x1, w1, 2, &rng, &sk);
        }
        aa_scene_free(placed);
    }
    past_stats *sts[2] = {&ev, &sk};
    for (int c = 0; c < 2; c++) {
        past_stats *st = sts[c];
        print_message("%s: %d parts past their first panel (%d panels met) within AR_QUAD_TOL a "
                      "panel plus rounding (at most %.3f of it); %d that 8 and 12 points' "
                      "bounds cannot take as one share (at most %.3f), %d of them beyond 16 "
                      "points' bound too; %d intervals here at the depth limit\n",
                      c ? "the strokes' pieces" : "the evolutes", st->parts, st->met, st->worst,
                      st->no812, st->worst_no812, st->no16, st->deep);
        assert_true(st->no16 > 100);
        assert_int_equal(st->deep, 0);
    }
}

/* The point (X, Y) of the image as the rows hold it: a corner of its cell
 * (*x0, *y0, integers) and the rest, rounded to double (*u, *v). */
static void cell_split(long double X, long double Y, double *x0, double *u, double *y0,
                       double *v)
{
    *x0 = (double)floorl(X), *y0 = (double)floorl(Y);
    *u = (double)(X - *x0), *v = (double)(Y - *y0);
}

/* A share's segment about the row's point (area_offset_segment_at: the
 * start from the point the row holds, a cell's corner and the rest, less
 * the panel's B(m) kept in the image as hi + lo, mapped back by the map's
 * inverse) against 1/2 the integral of (P - P(t1)) x P' from t1 to t2
 * computed in long double as in test_shares (20 points on 4 parts), the
 * point given at t1, either end of the part: parts inside one panel and
 * parts across each panel end (1e-7 of the panel wide to four times it),
 * on every offset piece, evolute and ellipse's offset of the three
 * strokes of test_shares at 256 px, under the scenes' maps and under the
 * same followed by a map that mixes x and y and moves them 3,000 px (its
 * B(m) about 3,000 px from the origin, where a double's ulp is 4.5e-13);
 * and parts from each piece's end, where the row's point is the outline's
 * vertex V, not the curve's E (here E moved by 3e-10 px): about V, the
 * integral about E plus 1/2 (E - V) x (P(t2) - E).  Each within
 * AR_QUAD_TOL plus 8 ulps of the size the double sum's terms have
 * (segment_l's mag), as test_shares holds area_offset_segment. */
static void test_shares_at(void **state)
{
    (void)state;
    ar_quad quad;
    must(area_quad_init(&quad));
    long double x1[20], w1[20];
    gauss_legendre_l(20, x1, w1);
    uint64_t rng = 192837465;
    int parts = 0, ends = 0, past = 0;
    double worst = 0.0;
    for (int c = 0; c < 6; c++) {
        aa_scene *placed = shares_stroke(c % 3);
        size_t np;
        const aa_piece *pcs = aa_scene_pieces(placed, &np);
        for (size_t k = 0; k < np; k++) {
            if (pcs[k].kind != AA_PIECE_OFFSET)
                continue;
            aa_piece pm = pcs[k];
            if (c >= 3) { /* (0.8 -0.6; 0.7 0.9) after the scene's map, and 3,000 px on */
                const double *m = pcs[k].oc.m;
                for (int j = 0; j < 3; j++) {
                    pm.oc.m[2 * j] = 0.8 * m[2 * j] - 0.6 * m[2 * j + 1];
                    pm.oc.m[2 * j + 1] = 0.7 * m[2 * j] + 0.9 * m[2 * j + 1];
                }
                pm.oc.m[4] += 3000.25, pm.oc.m[5] -= 2999.75;
            }
            const aa_offset_curve *oc = &pm.oc;
            ar_piece ap;
            ar_panel *pan = shares_piece(&pm, &quad, &ap);
            ap.ot0 = pm.ot0, ap.ot1 = pm.ot1;
            size_t npan = ap.npan;
            double tmin = pan[0].a, tmax = pan[npan - 1].b;
            for (int i = 0; i < 48 + 16 * (int)npan; i++) {
                double r[3];
                for (int e = 0; e < 3; e++) { /* uniform in [0, 1), 53 bits */
                    rng = rng * 6364136223846793005u + 1442695040888963407u;
                    r[e] = (double)(rng >> 11) * 0x1p-53;
                }
                double ta, tb;
                const ar_panel *p;
                int end = i < 48 ? i % 2 : -1; /* from t = tmin (0) or tmax (1) */
                if (end >= 0) {
                    p = &pan[end ? npan - 1 : 0];
                    double wd = 4.0 * (p->b - p->a) * pow(10.0, -7.0 * r[1]);
                    ta = end ? tmax : tmin;
                    tb = end ? fmax(tmax - wd, tmin) : fmin(tmin + wd, tmax);
                    if (i % 4 >= 2 && npan > 1) { /* just into the next panel */
                        const ar_panel *q = &pan[end ? npan - 2 : 1];
                        wd = 0.5 * (q->b - q->a) * pow(10.0, -7.0 * r[1]);
                        tb = end ? q->b - wd : q->a + wd;
                    }
                    if (end)
                        p = &pan[npan > 1 && tb < p->a ? npan - 2 : npan - 1];
                    past += end ? tb < pan[npan - 1].a : tb > pan[0].b;
                } else if (i % 2) { /* inside panel j */
                    p = &pan[(size_t)(r[2] * (double)npan)];
                    double wd = (p->b - p->a) * pow(10.0, -7.0 * r[1]);
                    ta = p->a + (p->b - p->a - wd) * r[0], tb = fmin(ta + wd, p->b);
                } else { /* across panel j's end */
                    size_t j = (size_t)(r[2] * (double)(npan - 1));
                    p = &pan[j];
                    if (j + 1 >= npan)
                        continue;
                    double wd = 4.0 * (p->b - p->a) * pow(10.0, -7.0 * r[1]);
                    ta = fmax(p->b - wd * r[0], p->a), tb = fmin(ta + wd, tmax);
                    if (i % 4 == 2) { /* the point given at the part's upper end */
                        double t = ta;
                        ta = tb, tb = t;
                    }
                }
                if (!(ta != tb))
                    continue;
                long double X, Y, X2, Y2, mag;
                aa__offset_eval(oc, ta, &X, &Y, NULL, NULL);
                long double want = segment_l(oc, ta, tb, p->m, 4, 20, x1, w1, &mag);
                if (end >= 0) { /* about V = E + (3e-10, -2e-10) */
                    long double Vx = X + 3e-10L, Vy = Y - 2e-10L;
                    aa__offset_eval(oc, tb, &X2, &Y2, NULL, NULL);
                    want += 0.5L * ((X - Vx) * (Y2 - Y) - (Y - Vy) * (X2 - X));
                    X = Vx, Y = Vy;
                    ends++;
                }
                double x0, u, y0, v;
                cell_split(X, Y, &x0, &u, &y0, &v);
                double got = area_offset_segment_at(&ap, ta, tb, x0, u, y0, v);
                double err = fabs((double)(got - want));
                double tol = AR_QUAD_TOL + 8 * DBL_EPSILON * (double)mag;
                if (!(err <= tol))
                    fail_msg("map %d piece %zu [%.17g, %.17g] (panel [%.17g, %.17g]): %.17g, "
                             "here %.17Lg, %.2e off (allowed %.2e)",
                             c, k, ta, tb, p->a, p->b, got, want, err, tol);
                worst = fmax(worst, err / tol);
                parts++;
            }
            free(pan);
        }
        aa_scene_free(placed);
    }
    print_message("%d parts about the row's point within the bound plus rounding (at most "
                  "%.2f of it), %d of them from a piece's end about its vertex (%d reaching "
                  "past the end's panel)\n",
                  parts, worst, ends, past);
    assert_true(parts > 4000 && ends > 1000 && past > 100);
}

/* area's gate on the row's point (area.c, load_pieces: ar_piece's rowpt,
 * the map's |M|^2 / |det| at most 4.25, a condition number of at most 4):
 * the image with the gate as built against the image with no piece taking
 * the row's point (aa__area_rowpt 0), the benchmark's first 4 rows of
 * cubics stroked 2.5 px wide at 256 px under maps of condition number
 * 12.5 (rotate(30) scale(1 0.08)) and 3 (rotate(30) scale(1 1/3)) and a
 * uniform one: the same bits under the first (the gate shut: the start
 * from rel_point, the polygon's vertices about the first panel, no vertex
 * term), not under the others (the gate open), so that a gate that let
 * the first through, or shut on the others, fails. */
static void test_rowpt_gate(void **state)
{
    (void)state;
    const double c = cos(M_PI / 6), s = sin(M_PI / 6);
    const double squash[6] = {c, s, -s * 0.08, c * 0.08, 0, 0};
    const double third[6] = {c, s, -s / 3, c / 3, 0, 0};
    const double *maps[3] = {squash, third, NULL};
    static const char *const names[3] = {"condition number 12.5", "condition number 3",
                                         "uniform"};
    const int n = 256;
    aa_stroke_style st;
    aa_stroke_style_default(&st);
    st.join = AA_JOIN_ROUND, st.cap = AA_CAP_ROUND;
    st.width = 2.5 / n;
    int bad = 0;
    for (int k = 0; k < 3; k++) {
        aa_scene *sc = bench_rows_stroke_map(NULL, 4, &st, maps[k]);
        aa_image a, b;
        support_render("area", sc, "box", n, n, 1, &a, NULL);
        aa__area_rowpt = 0;
        support_render("area", sc, "box", n, n, 1, &b, NULL);
        aa__area_rowpt = 1;
        size_t moved = 0, nv = (size_t)n * n * 3;
        for (size_t v = 0; v < nv; v++)
            moved += memcmp(&a.v[v], &b.v[v], sizeof a.v[v]) != 0;
        print_message("%-22s %zu values moved by the row's point\n", names[k], moved);
        bad |= k == 0 ? moved != 0 : moved == 0;
        aa_image_free(&a);
        aa_image_free(&b);
        aa_scene_free(sc);
    }
    if (bad)
        fail_msg("the gate on the row's point not as its maps' condition numbers say");
}

int main(void)
{
    SAN_CASES_PRINT();
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_reference),
                                       cmocka_unit_test(test_tube),
                                       cmocka_unit_test(test_meetings),
                                       cmocka_unit_test(test_touch),
                                       cmocka_unit_test(test_root),
                                       cmocka_unit_test(test_stops),
                                       cmocka_unit_test(test_fix),
                                       cmocka_unit_test(test_vertex),
                                       cmocka_unit_test(test_ulp_vertex),
                                       cmocka_unit_test(test_dd),
                                       cmocka_unit_test(test_roots_batch),
                                       cmocka_unit_test(test_nodes),
                                       cmocka_unit_test(test_panels),
                                       cmocka_unit_test(test_shares),
                                       cmocka_unit_test(test_shares_across),
                                       cmocka_unit_test(test_rule_sure),
                                       cmocka_unit_test(test_starts),
                                       cmocka_unit_test(test_shared_ends),
                                       cmocka_unit_test(test_touching_ends),
                                       cmocka_unit_test(test_common_heights),
                                       cmocka_unit_test(test_cones),
                                       cmocka_unit_test(test_crowd_meet_at_swap),
                                       cmocka_unit_test(test_end_chord),
                                       cmocka_unit_test(test_crowd_next_order),
                                       cmocka_unit_test(test_offset_polish),
                                       cmocka_unit_test(test_end_dd),
                                       cmocka_unit_test(test_end_top),
                                       cmocka_unit_test(test_side_guess),
                                       cmocka_unit_test(test_root_starts),
                                       cmocka_unit_test(test_turn_starts),
                                       cmocka_unit_test(test_sides_apart),
                                       cmocka_unit_test(test_side_batch),
                                       cmocka_unit_test(test_common_starts),
                                       cmocka_unit_test(test_roots_far),
                                       cmocka_unit_test(test_kept_solves),
                                       cmocka_unit_test(test_shares_past),
                                       cmocka_unit_test(test_shares_at),
                                       cmocka_unit_test(test_rowpt_gate)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
