/*
 * analytic.c: analytic rasterization under piecewise polynomial filters
 * (Manson and Schaefer 2013, "Analytic Rasterization of Curves with
 * Polynomial Filters", Computer Graphics Forum 32(2), Eurographics): the
 * convolution of the filter with the picture, an integral over area, turned
 * by Green's theorem into an integral along the shapes' boundaries, which
 * for a polynomial curve and a polynomial piece of the filter is the
 * integral of a polynomial, found exactly.
 *
 * What is the paper's.
 *  - The boundary integral.  For a separable filter w(u) w(v) with 1-D
 *    integral W(t) = integral of w from -infinity to t, the weight of a
 *    region R around the centre (cx, cy) is, by Green's theorem with the
 *    field (W(x - cx) w(y - cy), 0), whose curl is the filter,
 *
 *        integral over R of w(x - cx) w(y - cy) dx dy
 *            = - integral along the boundary of R of W(x - cx) w(y - cy) dy,
 *
 *    the boundary taken counter-clockwise in x right, y down coordinates
 *    (clockwise on screen).  Here it is written, as in Crow's "left areas
 *    minus right areas", per edge: the weight right of an edge over its
 *    rows [ya, yb] is
 *
 *        R(edge) = integral from ya to yb of w(y - cy) (1 - W(x(y) - cx)) dy
 *                = integral over t of w(y(t) - cy) (1 - W(x(t) - cx)) y'(t) dt,   (1)
 *
 *    the terms of the boundary integral of the paper, the constant 1 being
 *    the part of the field that integrates to the rows' weight.
 *  - The filters are piecewise polynomials; their support is cut into the
 *    cells of the pieces (the knots below, in u and v), and on each cell
 *    w and W are polynomials.  Cutting a curve where it crosses the knots'
 *    lines x = cx + k and y = cy + k leaves parts inside one cell each,
 *    where the integrand of (1) is a polynomial in the curve's parameter t.
 *  - The filters: box, tent (linear), the quadratic and cubic B-splines and
 *    Mitchell and Netravali's cubics (Catmull-Rom among them), all
 *    separable, and radially symmetric polynomials (see "Radial filters"); the curves: lines, quadratic and cubic
 *    Bezier arcs, and elliptical arcs (the paper's rational quadratics:
 *    see "Elliptical arcs" below for the rule used on them); beyond the
 *    paper, the offset curves and evolutes that outline strokes of Bezier
 *    and elliptical arcs, by a rule with a proven error bound (see
 *    "Offset curves").
 *
 * The closed forms.  With w of degree n on a cell (box 0, tent 1,
 * bspline:order=2 2, bspline:order=3 and mitchell 3), W of degree n + 1,
 * and a curve of degree d in t (line 1, quadratic 2, cubic 3), the
 * integrand of (1) on one part is a polynomial of degree
 *
 *     n d + (n + 1) d + (d - 1) = 2 d (n + 1) - 1,
 *
 * and the m-point Gauss-Legendre rule integrates every polynomial of degree
 * 2m - 1 exactly, so m = d (n + 1) points give the integral of each part,
 * in closed form, to rounding:
 *
 *     curve \ filter   box  tent  bspline:2  bspline:3, mitchell, catrom
 *     line              1     2       3          4
 *     quadratic         2     4       6          8
 *     cubic             3     6       9         12
 *     elliptical arc    6    10      14         18   (2 (2 n + 3): "Elliptical arcs")
 *     arc, 1st moments  8    12      16         20   (2 (2 n + 4): "Linear gradients")
 *
 * (The paper gives closed-form expressions, the polynomial integrated term
 * by term; the Gauss rule of the right degree is the same integral,
 * evaluated from the integrand's values: a variant in the means, chosen
 * because an expanded power basis can have coefficients far larger than
 * the integrand's values and lose digits to cancellation, while the Gauss
 * sum's weights are positive.  The nodes and weights are the roots of the
 * Legendre polynomial P_m and 2 / ((1 - x^2) P_m'(x)^2), found by Newton's
 * method in long double at init, for m up to 12.)
 * The filters' pieces are their definitions in patterns/README.md,
 * "Filters", written per cell about the cell's left knot here (the method
 * reads neither the harness's filter functions nor the reference): on
 * |t| in [a, b) a polynomial P(|t|), so on t in [-b, -a) P(-t) and on
 * [a, b) P(t), each shifted to the cell's left end (a Taylor shift); the
 * two cells about 0 are one where P is even (box, the B-splines, Mitchell:
 * no odd terms near 0; the tent's kink at 0 stays a knot).  W on a cell is
 * W at its left knot plus the integral of the cell's w (each coefficient
 * c_i s^i giving c_i s^(i+1)/(i+1)).
 *
 * What is chosen here (a variant in the means, not in the values).  The
 * paper rasterizes a scene of one shape at a time by scanlines, adding each
 * curve's terms to the pixels whose supports it crosses.  That is done here
 * wherever the picture is linear in the edges: where at most one layer
 * winds around a point, once (see "One layer at a time" below, where a
 * sweep at init finds the rows where this holds).  There each piece is cut
 * once at the knots' lines, each part gives its rule's points once for all
 * the pixels whose supports hold it, and the constant part of (1) is
 * carried along the row by a running sum, as area.c's cover.  Shapes that
 * overlap are not summed but painted, and the weight of an area hidden by
 * a front layer must not count: in the rows whose supports reach such
 * places, the pixel is a sum over the visible parts of the edges in its
 * support (visible.c, as `crowtiler:hidden=scan` does), each with its step
 * of colour,
 *
 *     sum over bands of (colour left of the support) (W(yb - cy) - W(ya - cy))
 *       + sum over visible parts of (step of colour across it) R(part),
 *
 * which is the filtered picture exactly, for any number of opaque layers in
 * painter's order and either fill rule.  The visible parts are found once
 * a block, over the rows of its slow rows and the whole width in tiles 8
 * px wide, and scattered as the pieces of the sum of shapes are, each with its step
 * of colour (see "The visible parts' scatter"; the per-pixel windows
 * remain for blocks whose faces have too many colours, and under the
 * radial filters).
 *
 * Error analysis: rounding, and the heights where pieces meet (found in
 * closed form by visible.c) and where they cross the knots' lines
 * (aa_piece_meet_x; a cubic's by cubic_cuts, to full precision): a cut
 * misplaced by e moves the part of width e into
 * the neighbouring cell's polynomial, whose value differs there by at most
 * e times the jump of w's derivative (w and W are continuous; the box's
 * steps are at the support's sides, where the window ends).  The scatter
 * sums more terms per pixel (every part left of it in its rows, through
 * the running sum, compensated): on crow at 32x30 3.9e-14 at most where
 * the visible parts gave 1.1e-14, at 128x128 under tent:r=1 1.1e-13 (1.2e-14),
 * at 1024x1024 1.8e-13 (7.6e-13).  Values are clamped to the filter's range (aa_filter_range: a rounding of 1e-16
 * past it).
 *
 * Known answers (tests/test_analytic.c; offset curves in
 * tests/test_analytic_stroke.c, see "Offset curves"): the exact reference
 * (aa_truth_render) within 1e-12 per pixel on crow, star, slivers,
 * catmull, feibush, SVG scenes of quadratic, cubic and elliptical arcs
 * (circles, a turned ellipse, a rounded rectangle, paths of SVG `A`) and
 * overlapping even-odd layers, under every filter taken; circles, turned
 * ellipses, a pie slice and arcs 0.3 px in radius in one layer and in two
 * overlapping; circles of radius 1e4 and 1e6 px; rows of both paths in one
 * image (overlapping layers above disjoint shapes wound +1 and -1), a
 * layer wound both ways, supports 12 px wide (tent:r=6) and with cells
 * wider than a pixel (tent:r=3.7), a piece far left of the image, the same
 * image at 1 and 2 threads; a white region's image sums
 * to its area (Archimedes' parabolic segment, 2/3 of its control triangle;
 * the area under y = x^3, 1/4; a disk and a turned ellipse, pi a b) under
 * the filters whose integer translates
 * sum to 1 (box, tent:r=1, the B-splines, Mitchell-Netravali, Catmull-Rom).
 * Linear gradients (tests/test_analytic_gradient.c): the reference
 * within 1e-12 per pixel (at most 1.4e-14 measured: three layers under
 * tent:r=0.65) on pad, repeat and reflect gradients in linear light on
 * lines, quadratic and cubic arcs, a sharp step, a clip, a ramp across
 * the sliver, stroked polylines and several layers in painter's order,
 * under box, tent, the B-splines, Mitchell and Catmull-Rom; a
 * black-to-white ramp across a rectangle sums to the integral of its
 * affine colour over the rectangle (closed form; 7.1e-14 off 74.78), a
 * repeated ramp over whole periods to half its area (8.5e-14 off 71.2);
 * on elliptical arcs (a circle, a turned ellipse and a rounded rectangle
 * under pad, repeat and reflect gradients) within 3.8e-15 under box,
 * tent:r=1, bspline:order=3 and Mitchell, on offset curves (a stroked
 * cubic and a stroked turned ellipse) within 3.0e-14; a disk under a ramp
 * along x sums to its area times the colour at its centre (9.9e-14 off
 * 81.4), a turned ellipse under an oblique ramp likewise (2.8e-14 off
 * 53.1).  A rule two degrees short on the arcs' first moments (4 n + 4
 * points) misses by 2.3e-12 under the box, an offset part's rule 3 points
 * short of the certified one by 4.8e-11; the rule one degree short (the
 * zeroth moment's, 4 n + 6) is not seen at 1e-12 on these scenes: on a
 * part its error is of the order of z^m (2 z)^N (see "Elliptical arcs"),
 * below 1e-13 on parts of at most a quarter of the ellipse.
 * Under radial:k=K,r=R (tests/test_analytic_radial.c): the reference within
 * 1e-12 per pixel on crow, crow raised to cubics, the cubic scene, a
 * pentagon, two overlapping layers, curves.svg and arcs.svg (largest
 * difference 1.1e-14), half-planes through a pixel centre 1/2, centred
 * disks 1 - (1 - a^2/R^2)^(K+1); offset curves in
 * tests/test_analytic_stroke.c ("Offset curves under the radial
 * filters").
 *
 * Radial filters.  The paper rasterizes with radially symmetric
 * polynomial filters too; radial:k=K,r=R (patterns/README.md, "Filters")
 * is w = c (1 - (u^2 + v^2)/R^2)^K on the disc D of radius R, c = (K + 1)/
 * (pi R^2): on D a polynomial in u and v, 0 outside.  Write w~ for the
 * polynomial continued past the rim, and its potential along x,
 *
 *     F(x, v) = integral from 0 to x of w~(s, v) ds
 *             = c R X sum_j binom(K, j) (-1)^j a2^(K-j) X^(2j) / (2j + 1),
 *     X = x/R, a2 = 1 - (v/R)^2,
 *
 * a polynomial of degree 2K + 1 in x and v, odd in x.  The weight of a
 * region G is the integral over G and D of w~, and by Green's theorem that
 * is the integral of F dy along the boundary of G and D: along the edges
 * of G inside D, and along the arcs of D's circle inside G.  In the terms
 * of (1): in the row at height v (relative to the centre) the chord of D
 * is |x| < ch = R sqrt(a2), and the weight right of x in it is
 * F(ch, v) - F(clamp(x, -ch, ch), v), where F(ch, v) = F(-ch, v) negated
 * is half the row's weight.  So for a part over rows [ya, yb],
 *
 *     R(part) = (M(yb) - M(ya))/2 - integral of F(clamp(x, -ch, ch), y) dy,
 *
 * M(v) the weight of the rows below v.  F(+-ch, v) is the circle's arc
 * parametrised by height: with v = R sin phi, the whole row's weight is
 * c R B a2^(K + 1/2), B = integral from -1 to 1 of (1 - t^2)^K, and
 * integrating it over v, a trigonometric polynomial in phi:
 *
 *     M(v) = 1/2 + Q I_p(phi),   I_p(phi) = integral from 0 to phi of cos^p,
 *     p = 2K + 2,   I_0 = phi,   I_p = cos^(p-1) sin / p + (p - 1)/p I_(p-2),
 *
 * Q = 1 / (2 I_p(pi/2)), I_p(pi/2) = pi/2 prod over even q <= p of
 * (q - 1)/q (the whole is 1: Q = c R^2 B, checked for K = 1: 2/(pi R^2)
 * R^2 4/3 = 1/(2 3 pi/16)).  The band term uses M in place of W of the
 * separable filters.  Along a part the clamp changes only where the curve
 * crosses the circle, the real roots in t of the polynomial
 * |P(t) - C|^2 - R^2 of degree 2d (6 for a cubic), isolated between the
 * roots of its derivatives (recursively) and bisected to the last bit; the
 * part is cut there and at the rows +-R.  A sub-part inside D gives the
 * Gauss-Legendre rule of d (K + 1) points (the integrand F(x(t), y(t))
 * y'(t) has degree (2K + 1) d + d - 1 = 2 d (K + 1) - 1; at most 12, for
 * cubics under K = 3): exact.  A sub-part outside D lies wholly left or
 * right of the disc in the rows it shares with it (the piece is monotone
 * in y, so it cannot pass from one side to the other without leaving the
 * disc's rows), where F(clamp) = +-F(ch): its integral is
 * +-(M(y1) - M(y0))/2.  A misplaced crossing costs nothing to first
 * order: the integrand is continuous there (the polynomial and the clamped
 * one agree on the circle), so a crossing off by e in t moves the result
 * by the jump of its derivative times e^2.  Elliptical arcs: the
 * crossings are the roots of a quartic in the half-angle tangent about
 * the part's middle angle (rad_right_of_arc), the sub-arcs inside D take
 * the arc's rule below with n = K (F(x, y) y' is a trigonometric
 * polynomial of degree 2 K + 2, as w (1 - W) y' of degree 2 n + 2 is),
 * those outside +-M/2 as above.  Radial filters take the visible parts in
 * every row: the per-edge scatter is written for the separable cells.
 * (Manson and Schaefer's own radial polynomials were not at hand; this
 * family, the polynomials in r^2 vanishing to order K at the rim, is the
 * one patterns/README.md defines.)
 *
 * Offset curves.  A stroke's outline (harness/core/stroke.c) holds offset
 * pieces (AA_PIECE_OFFSET): parts of P = B + d N of a cubic or an ellipse
 * B, or of its evolute, mapped, y-monotone, without folds or cusps
 * inside.  They are not polynomial (N carries 1/|B'|), so no rule of
 * fixed size is exact; but on a part inside one cell of the filter the
 * integrand of (1), w(y(t) - cy) (1 - W(x(t) - cx)) y'(t), is analytic
 * wherever the curve is, and Gauss-Legendre's error on it is bounded: n
 * points on a part of half width h err by at most
 *
 *     h 64 M / (15 (1 - rho^-2) rho^(2n))
 *
 * for the integrand analytic inside the Bernstein ellipse of parameter
 * rho about the part and at most M there (Trefethen, "Approximation
 * Theory and Approximation Practice", 2013, Theorem 19.3), the bound
 * `area` certifies its offset quadrature with (algorithms/area_offset.c).
 * The ellipse lies in the disc of radius R = h (rho + 1/rho)/2 about the
 * part's middle; there area_offset_speed bounds the speed |P'| <= V from
 * the curve's Taylor sums (and proves the disc free of zeros of |B'|^2, or
 * of the curvature for an evolute), so |y'| <= |row_y| V, y is within
 * |row_y| V R of its real value at the middle (row: the map's row), and
 * the cell's pieces are bounded term by term, |w| <= sum |w_i| (h_c +
 * |row_y| V R)^i (h_c the cell's width; W likewise): M = max|w| (1 +
 * max|W|) |row_y| V, the largest over the cells.  For rho in 1.5 .. 64 the
 * fewest n with the bound within 1e-16 is taken (at most 18 points), and a
 * part none holds is halved (as rho grows the bound falls as rho^-2n; a
 * part left uncertified after 50 halvings, its speed within rounding of
 * 0, refuses the render).  The cuts: the rows (y = cy + k) are found by
 * the offset solver in y (aa__offset_solve_d, Newton's method bracketed,
 * to rounding), the columns on the parts between x's turns (closed form,
 * aa__offset_turns) by the same solver in x, and the curve is cut at t =
 * 1/2 where an end is a stop (a cusp split off), where its evaluation
 * (aa__offset_eval, the same points as `area` and the reference use)
 * changes form, so that each part's integrand is one analytic function.
 * The per-pixel path takes every offset part in its support this way; the
 * scatters (a piece of the sum of shapes, or a run of visible parts over
 * its rows) cut the piece once at every knots' line of its rows and
 * columns and give each part's points to the general fast_part (the
 * rule's size is not a constant of the compiled loops).  Measured
 * (tests/test_analytic_stroke.c): 8.7e-14 at most from the reference on
 * a 64 px window of tests/bench_bezstroke.c's strokes (box; 5.2e-14 to
 * 6.7e-14 under tent:r=1, bspline:order=3, mitchell), 1.8e-14 on thick
 * strokes whose inner offsets fold (evolute pieces) at 24 px, and the
 * tube formula (a butt-capped stroke of a gentle cubic and a closed
 * ellipse's, width times length) within 7e-17 under the six filters whose
 * translates sum to 1.
 *
 * Offset curves under the radial filters.  As for the other curves (see
 * "Radial filters"), R(part) = (M(yb) - M(ya))/2 - integral of F(clamp(x,
 * -ch, ch), y) dy, the part cut where it crosses the filter's circle; but
 * those crossings are the zeros of g(t) = |P(t) - C|^2 - R^2, analytic and
 * not a polynomial, so they are isolated with a proof (rad_off_cross): an
 * interval of half width h about m is bisected until it is shown free of
 * them (|P - P(m)| <= V h, V area_offset_speed's bound on |P'| on the disc
 * of radius h; or g within 2 h (|g'(m)|/2 + D) of g(m), D the drift of
 * g'/2 = (P - C) . P' over the interval, from Cauchy's estimate |P''| <=
 * Vk/(Rk - h) on a disc of radius Rk = 2 h .. 256 h), or g' shown of one
 * sign on it (|g'(m)|/2 > D: one crossing at most, where g's signs at the
 * ends differ, then found by Newton's method kept in the bracket, to the
 * last bit), or every point of it shown within e of the circle with the
 * bound of the integral's change however it is taken, 2 h V c (3 e/R)^K
 * sqrt(3 R e), within 1e-16 of the part's share (a curve touching the
 * circle).  Each sub-part inside the disc takes the certified rule above
 * with the integrand F(x - cx, y - cy) y' (|F| bounded term by term on
 * the disc, rad_f_bound), each outside +-(M(y1) - M(y0))/2.  A curve that
 * runs along a pixel's circle within rounding (an arc concentric with it
 * and of its radius) is never shown off it: after 4096 intervals a part
 * (or at more than 64 cuts) the render is refused, as uncertain.
 * Measured (tests/test_analytic_stroke.c): 3.0e-14 at most from the
 * reference on a 24 px window of tests/bench_bezstroke.c's strokes under
 * radial:k=1,r=1, radial:k=2,r=1.5 and radial:k=3,r=2.3; a straight
 * stroke (a cubic of collinear control points, its offsets lines) within
 * 5.7e-15 of the same rectangle as a polygon and 8.3e-16 of 1/2 where its
 * side passes through a pixel centre; the offsets of a circle (an annulus)
 * within 1.4e-15 of the two circles as elliptical arcs, and 1.7e-16 at its
 * centre of the closed form (1 - a1^2/R^2)^(K+1) - (1 - a2^2/R^2)^(K+1).
 *
 * Linear gradients.  The paper also fills shapes with linear colour
 * gradients (its rasterizer's part on linear color gradients: the filter
 * times a colour affine in x and y, again a boundary integral of
 * polynomials).  In this project's conventions (patterns/README.md,
 * "Gradients") that is a linear gradient whose stops interpolate in
 * linear light (color-interpolation: linearRGB), opaque, in a scene of
 * opaque layers: at a point its colour is v(s(t)), t = gu (x - X1) +
 * gv (y - Y1) affine in the position ((X1, Y1) the image of the
 * gradient's first point), s the spread of t (pad, repeat, reflect) and
 * v the stops' linear values interpolated in s; the picture is
 * decode(encode(v)) (the layer paints encode(v), opaque, and the scene
 * decodes), which is v but on a sliver (below).  So each channel is
 * piecewise affine in t, its kinks at the stop lines t = tau: the
 * offsets, 0 and 1, every period again (repeat: n + o, reflect: 2n + o
 * and 2n + 2 - o), and the sliver's ends.  Between two stop lines (a
 * strip) the colour about the pixel's centre is c = a + gx u + gy v,
 * u = x - cx, v = y - cy, and the pixel's share of a region G of one
 * strip is a M0 + gx Mu + gy Mv, the moments
 *
 *     M0, Mu, Mv = integral over G of (1, u, v) w(u) w(v) du dv.
 *
 * Green's theorem takes the first moments to the boundary as it takes
 * the zeroth: with W1(t) = integral from -infinity to t of s w(s) ds
 * (on a cell a polynomial of degree n + 2: s w(s) = (k + s') w(s'),
 * integrated term by term), the fields (W1(u) w(v), 0) and (W(u) v w(v),
 * 0) have the curls u w(u) w(v) and v w(u) w(v), and per edge, as (1),
 * the moments right of it over its rows are
 *
 *     Ru(edge) = integral of w(v) (W1(inf) - W1(u(y))) dy,
 *     Rv(edge) = integral of v w(v) (1 - W(u(y))) dy,                    (2)
 *
 * (W1(inf) = 0 for these even filters; the computed one is used).  On a
 * part of a curve of degree d inside one cell the integrands have degree
 * n d + (n + 2) d + d - 1 = d (2 n + 3) - 1 (and (n + 1) d + (n + 1) d +
 * d - 1, the same, for Rv), so the Gauss-Legendre rule of d (n + 2)
 * points is exact for R0, Ru and Rv at once: 2 to 5 points on a line,
 * up to 15 on a cubic under the cubic filters.  The faces then carry
 * their colour functions instead of constants: the visible parts report
 * per band the face at the window's left side and per run the step of
 * the values across a part, here nine per face (a, gx, gy per channel,
 * about the pixel's centre), and the pixel is
 *
 *     sum over bands of a M0 + gx W1(inf) M0 + gy (W1(vb) - W1(va))
 *       + sum over runs of da R0 + dgx Ru + dgy Rv,
 *
 * M0 = W(vb) - W(va) the band's rows' weight: the region between two
 * neighbouring parts is the difference of their regions "right of", so
 * the sum telescopes as the constant one does, now with linear
 * functionals of the colour.  The stop lines are made geometry: each
 * line crossing the frame (the image, the filter's support about it and
 * 2 px) is added to a copy of the scene (aa__scene_copy_open) as a layer
 * behind every other, the half-plane t >= tau inside the frame, so that
 * visible.c cuts the bands where a stop line meets an edge, in closed
 * form as any two lines; a face's strip is the number of its gradient's
 * half-planes around it (nested: a prefix, found by bisection), and its
 * values are those of the front layer that covers it
 * (aa__scene_covers, clips included): a colour, or the strip's affine
 * colour.  A pixel whose window no piece (and no stop line) reaches lies
 * in one face, and its value is a there (the filter is even: its first
 * moments over the whole support vanish).  Every row of a gradient scene
 * takes these per-pixel visible parts (the scatters carry constant
 * steps).  The sliver: decode(encode(v)) is not v for v in (0.0031308,
 * V2), V2 = ((0.04045 + 0.055)/1.055)^2.4 = 0.0031308072831, where
 * encode's power piece is already below decode's threshold 0.04045 (the
 * two pieces of IEC 61966-2-1 do not meet exactly): there it is h(v) =
 * (1.055 v^p - 0.055)/12.92, p = 1/2.4, from 2.21e-9 to 2.33e-9 below v.
 * Its ends are stop lines, and on it the chord of h is taken: h is
 * concave there, |h''| = 1.055 p (1 - p) v^(p-2)/12.92 <= 183.2, so the
 * chord is within (V2 - 0.0031308)^2/8 x 183.2 = 1.2e-15 of h, and a
 * pixel within that of the picture (the weights sum to at most the
 * filter's range).  A gradient constant between two stops (both of one
 * colour, or the pad's ends) paints decode(encode(v)) exactly.
 *
 * Elliptical arcs and offset curves under a gradient.  On a part of an
 * arc (see "Elliptical arcs") x, y and y' are trigonometric polynomials
 * of degree 1 in phi, w(v) of degree n, W1(u) of n + 2, v w(v) and
 * 1 - W(u) of n + 1, so the integrands of (2), w(v) (W1(inf) - W1(u)) y'
 * and v w(v) (1 - W(u)) y', have the degree n + (n + 2) + 1 = (n + 1) +
 * (n + 1) + 1 = 2 n + 3, one more than the zeroth moment's 2 n + 2: the
 * arc's rule for N = 2 n + 3 (m = 2 n + 4 positive nodes, 4 n + 8 points:
 * box 8, tent 12, bspline:order=2 16, the cubics 20; its G_gk still exact,
 * 2 (m - 1) + 2 K <= 78 < 80) gives R0, Ru and Rv at once, exact.  On an
 * offset part the three integrands are analytic wherever the curve is,
 * and the rule is certified as the zeroth moment's ("Offset curves"), M
 * now bounding the part's term of the pixel, J0 |w (1 - W) y'| + J1 |w
 * (W1(inf) - W1(u)) y'| + J2 |v w (1 - W) y'|, J the largest steps of a,
 * gx and gy across the part over the channels (the run's jump): W1 on a
 * cell bounded term by term as W is (off_m1_bound), |v| by the support's
 * half width plus |row_y| V R.  So each part's error is within 1e-16 of
 * every channel, as a flat colour's, however steep the gradient.
 *
 * Linear gradients under the radial filters.  The paper takes both its
 * radial filters and colour gradients by boundary integrals of
 * polynomials; here the two are joined in this project's terms (see
 * "Radial filters" and "Linear gradients").  On a strip the colour is c =
 * a + gx u + gy v about the pixel's centre, and the pixel's share of a
 * region G is a M0 + gx Mu + gy Mv, the moments now over G and the disc D
 * of (1, u, v) w.  By rows, as for the zeroth moment: in the row at
 * height v the weight right of x is F(ch, v) - F(clamp(x, -ch, ch), v),
 * and its first moments are
 *
 *     along u:  H(x, v) = integral from clamp(x) to ch of s w~(s, v) ds,
 *     along v:  v (F(ch, v) - F(clamp(x), v)).
 *
 * s w~(s, v) = c s (a2 - s^2/R^2)^K is the derivative in s of -c R^2/(2
 * (K + 1)) (a2 - s^2/R^2)^(K + 1), which vanishes at s = +-ch, so
 *
 *     H(x, v) = c R^2/(2 (K + 1)) (1 - (x^2 + v^2)/R^2)^(K + 1)
 *
 * inside D and 0 outside it (right of the chord nothing is left, and left
 * of it the whole chord's first moment, 0: w is even): a polynomial of
 * degree 2 K + 2 continuous across the circle, where it vanishes, with
 * dH/dx = -x w.  In Green's terms H and v F are the potentials whose x
 * derivatives are -u w and v w; the circle's arcs add nothing to Mu (H is
 * 0 there) and to Mv what the rows' first moment gives:
 *
 *     M1(v) = integral from -R to v of s m(s) ds = -Q R/(2 K + 3) a2^(K + 3/2),
 *
 * m(s) = c R B a2^(K + 1/2) = (Q/R) a2^(K + 1/2) the row's weight (a2 = 1 -
 * s^2/R^2; d/dv of M1 is (Q/R) a2^(K + 1/2) v), M1(+-R) = 0.  So for a part
 * over rows [ya, yb], clamped to the disc's [lo, hi],
 *
 *     Ru(part) = integral of H(x, y) dy,
 *     Rv(part) = (M1(hi) - M1(lo))/2 - integral of v F(clamp(x), v) dy,     (3)
 *
 * and a band of rows [va, vb] gives M0 = M(vb) - M(va), Mu = 0 and Mv =
 * M1(vb) - M1(va).  The part is cut where it crosses the circle, as for
 * the zeroth moment and by the same code; on a sub-part inside D the
 * integrands H y' and v F y' have degree (2 K + 2) d + d - 1 = d (2 K +
 * 3) - 1 on a curve of degree d, so the Gauss-Legendre rule of d (K + 2)
 * points is exact for the three at once (3 to 5 points on a line, up to 15
 * on a cubic under K = 3), and on an elliptical arc they are
 * trigonometric polynomials of degree 2 K + 3, the first moments' arc rule
 * with n = K (4 K + 8 points) exact; on a sub-part outside D, Ru is 0 and
 * Rv +-(M1(y1) - M1(y0))/2 (+ right of the disc, - left), as R0's +-M/2.
 * H and v F(clamp(x)) are continuous across the circle, so a misplaced
 * crossing costs the square of its error, as for the zeroth moment.
 * Offset curves: their crossings are isolated as in "Offset curves under
 * the radial filters", the touching test now bounding J0 E0 + J1 EH + J2
 * (R + e) E0 (rad_off_cross), and a sub-part inside D takes the certified
 * rule with M the bound of J0 |F y'| + J1 |H y'| + J2 |v F y'| (|H| term by
 * term as |F|, rad_h_bound; |v| within R plus y's drift), so each part's
 * error is within 1e-16 of every channel, as under the separable filters.
 * The faces, stop lines and bands are those of "Linear gradients", the
 * window the disc's square.  Checked (tests/test_analytic_radial_gradient.c):
 * the half-plane x < x0 under a ramp along x and y < y0 under a ramp
 * along y against the 1-D integral of the ramp times the chord's weight,
 * c R B (1 - u^2/R^2)^(K + 1/2), by GSL's Gauss-Legendre rule (which
 * checks H, through the vertical edge, and M1, through the bands) within
 * 4.2e-16 under radial:k=1,r=1, radial:k=2,r=1.5 and radial:k=3,r=2; the
 * reference within 1e-12 per pixel under the three on a path of lines and
 * a cubic arc (a padded gradient with a sharp step) over a rectangle under
 * a repeated gradient, at 16x14 and 40x35 px (1.8e-15 at most), a circle
 * under a reflected gradient and a turned ellipse under a padded one
 * (6.7e-16), and a stroked cubic, its inner offset folding, under a
 * reflected gradient (1.1e-14).  H scaled by 1.001 is seen by the
 * half-plane (a pixel 6.4e-7 off the closed form) and by the reference on
 * both scenes (pixels 3.1e-6 and 1.3e-6 off), M1 negated by the half-plane
 * y < y0 (1.3e-3); the zeroth moment's rules, one degree short (d (K + 1)
 * points; on arcs 4 K + 6), miss by 1.1e-4 (the half-plane), 6.8e-7 (the
 * cubic's scene) and 1.2e-11 (the arcs' scene).  Cost: as under the
 * separable filters, every pixel whose disc's square a piece or a stop
 * line reaches takes its visible parts: on that circle and ellipse drawn
 * at 64x56 px (scale 4),
 * one thread, 101.9e6 instructions in analytic_render under
 * radial:k=2,r=1.5 against 8.3e6 for the same shapes in flat colours and
 * 169.4e6 for the gradients under bspline:order=3 (callgrind;
 * algorithms/README.md).
 *
 * Limits, refused by name: filters that are not piecewise polynomial
 * (gauss, lanczos, the cone, gauss:cut: the cone is 1 - r, not a
 * polynomial in x and y); an offset curve running along a pixel's radial
 * circle within rounding (above); field scenes (no edges).
 * Gradient paint is taken as above and refused otherwise, naming the
 * layer (and the gradient's element and line when read from SVG): a
 * linear gradient interpolating its stops in sRGB-encoded values (the
 * SVG default: its colour in linear light is the sRGB decoding, a power
 * 2.4 and a linear toe, of an affine function of x and y, not a
 * polynomial), radial gradients (t is not affine in the position), a
 * stop of opacity below 1, a translucent layer or group anywhere in a
 * gradient scene (translucent paint composites in sRGB-encoded values),
 * and a gradient repeating past 65536 stop lines across the frame.
 *
 * Cost.  Where the per-edge scatter holds (every row of crow and of scenes
 * of disjoint shapes): per part of a piece between two knots' lines, its
 * rule's points, the filter's pieces at them for the (support width)
 * rows and columns that hold it and their products (for the regular
 * filters of degree 1 to 3 two columns or rows at a time, in SSE2
 * vectors), then one running sum per row over the pixels some term or
 * carry reached, the runs of other pixels filled with their faces'
 * colours; the rule's size, the filter's degree and (for filters of unit
 * cells) the support's width are constants of the compiled loops, a
 * piece's parts are taken in one such function (compiled for AVX2 too,
 * chosen at load), and a piece with y linear in t (a line, crow's arcs)
 * has its points without the zero terms.  On crow 1024x1024, one thread
 * (algorithms/README.md, "Exact filtering beyond the box"): 60.8e6
 * instructions a render under tent:r=1 and 118.7e6 under
 * bspline:order=3 against area's 35.0e6 (callgrind), and a thread CPU
 * time per render of 2.0x area's box time under tent:r=1 and 3.3x under
 * bspline:order=3 (medians of 21 renders, two runs taking turns with the
 * build before on a loaded machine, where that build measured 2.1x to
 * 2.5x and 3.9x to 4.6x; the ratios move with the load).  On
 * elliptical arcs each part costs more, under every filter alike: its
 * cuts' angles and its middle's sine and cosine in long double, and 4 n +
 * 6 points; on 36 circles at 1024x1024 (algorithms/README.md) 8.9x area's
 * box time under the box, 11.0x under bspline:order=3, where the same
 * circles as 64-gons took 3.4x and 3.8x.  On the vector suite's scenes
 * at 1024x1024 (mono, shapes, rules, curves, logo; algorithms/README.md),
 * where layers overlap, under tent:r=1 1.2x to 2.0x area's box time and
 * under bspline:order=3 1.3x to 2.5x (two runs on a loaded machine; before
 * the visible parts' scatter 3.3x to 4.6x and 3.4x to 9.9x).  In the rows
 * where layers overlap, per block, the visible parts of one window (sorting each band's
 * pieces along x and one meeting test per neighbouring pair), each run of
 * them scattered as a piece is, with four values (its step of colour and
 * of the face's code); under the radial filters, per pixel whose support
 * meets an edge, the visible parts of its support and, per part, the rule
 * of the table above; other pixels are filled in runs.  Offset pieces
 * cost more per part: the bound's Taylor sums in long double, its rule (4
 * to 18 points) evaluated in long double, and per cut a root of the
 * offset solver; and a stroke's outline overlaps itself (each segment's
 * outline and each join a contour of its own, wound twice where they
 * overlap), so its rows take the visible parts' scatter, whose meetings
 * of offset pieces are sought by subdivision.  On tests/bench_bezstroke.c's
 * scene (1,000 stroked cubics, 1024x1024, one thread, CPU time, medians of
 * five, a loaded machine) 7.3x area's box time under the box, 8.1x under
 * tent:r=1 and 9.0x under bspline:order=3 (algorithms/README.md; 736x
 * at 256x256 when the visible parts took one window across the width and
 * solved the offset pieces' parameters again in every meeting test).
 * Under the radial filters offset pieces cost far more: every pixel whose
 * support meets one takes its own visible parts, and per part the
 * isolation of its circle crossings (a speed bound of nine discs per
 * interval, each crossing solved by Newton's method) before the rule: on
 * bench_bezstroke's scene at 256x256 (-s 256x256 -f radial:k=2,r=1.5,
 * one thread, CPU time, medians of five) 2.17 s under radial:k=2,r=1.5
 * against 350 ms under tent:r=1 and area's 102 ms (21x;
 * algorithms/README.md), half of it in the isolation and a third in its
 * root solving (perf, on 60 separate strokes).  The
 * image does
 * not depend on the thread count (rows are taken AN_BLOCK at a time by
 * the scatters, one at a time by the per-pixel visible parts, each from
 * the scene alone).  Counters: samples = 0, expensive_pixels =
 * pixels summed (the scatter's: the pixels some part's exact term reached).
 * Gradient scenes take the per-pixel visible parts in every row; there an
 * arc's part costs its cuts' angles and 4 n + 8 points, an offset part its
 * certified rule for the three moments: on 36 gradient circles at 256x256
 * (algorithms/README.md, "Filters and scenes") 310e6 instructions a
 * render under the box and 1319e6 under bspline:order=3, the same circles
 * as 64-gons 314e6 and 1231e6.
 */
#include "area_internal.h"
#include "core.h"
#include "methods.h"
#include "sampling.h"
#include "visible.h"

#include <float.h>
#include <gsl/gsl_poly.h>
#include <math.h>
#include <omp.h>
#if defined(__SSE2__) && defined(__x86_64__)
#include <emmintrin.h>
#define AN_SSE2 1
#else
#define AN_SSE2 0
#endif
#include <stdlib.h>
#include <string.h>

#define AN_MAX_CELLS 6
#define AN_MAX_GAUSS 12
/* points of a part's rule at most: Gauss-Legendre's 12, an arc's 18 */
#define AN_MAX_PTS 18
/* positive nodes of an arc's rule for the first moments at most (2 n + 4,
 * n <= 3: "Linear gradients") */
#define AN_ARC1_M 10
/* terms of the series of an arc's weights in z = alpha^2 <= 1/4 */
#define AN_ARC_K 30

static const aa_param analytic_params[] = {{0}};

/* A piecewise polynomial 1-D filter: cells [k[c], k[c+1]), on each
 * w(t) = sum w[c][i] s^i and W(t) = sum cdf[c][i] s^i, s = t - k[c]. */
typedef struct an_pp {
    int ncell, deg; /* deg: of w (n above) */
    double k[AN_MAX_CELLS + 1];
    double w[AN_MAX_CELLS][4];
    double cdf[AN_MAX_CELLS][5];
    /* the first moment W1(t) = integral of s w(s) from -infinity to t: on
     * cell c sum m1[c][i] s^i (s = t - k[c]); m1tot its whole (0 but for
     * rounding: the filters are even) ("Linear gradients") */
    double m1[AN_MAX_CELLS][6];
    double m1tot;
} an_pp;

/* The width of the visible parts' tiles (px) */
#define AN_TILE 8.0
/* how far (px) a tile's side keeps from a piece's extreme x */
#define AN_TILE_CLEAR 1e-6

/* A gradient layer's stop lines and strips (see "Linear gradients"): t =
 * gu (x - X1) + gv (y - Y1); its lines t = tl[q], q < nl, ascending, are
 * layers first + q of the copy of the scene (each the half-plane t >=
 * tl[q] within the copy's frame); strip q (nl + 1 of them) holds the
 * linear-light colour h[ch] + b[ch] (t - tm) of its t in (tl[q-1], tl[q]),
 * tm its middle. */
typedef struct an_gstrip {
    double tm, h[3], b[3];
} an_gstrip;
typedef struct an_glayer {
    int first, nl;
    double gu, gv, X1, Y1;
    an_gstrip *strip;
} an_glayer;
/* The scene with gradient paint it was made for (src, w x h), its copy
 * with the stop lines added behind its nreal layers, and by layer the
 * index of its gradient in g (-1: its colour). */
typedef struct an_grad {
    const aa_scene *src;
    int w, h, nreal, ng;
    aa_scene *aug;
    int *of;
    an_glayer *g;
} an_grad;

typedef struct an_state {
    aa__sampler sampler;
    an_grad grad;
    an_pp pp;
    /* elliptical arcs (see "Elliptical arcs"): the nodes u[g] of the arc's
     * rule, g < arc_m, and the coefficients of their weights in z */
    int arc_m;
    double arc_u[AN_MAX_PTS / 2], arc_wz[AN_MAX_PTS / 2][AN_ARC_K + 1];
    /* the arc's rule of one degree more, for the first moments of a
     * gradient's colour (see "Linear gradients"): arc1_m = arc_m + 1 */
    int arc1_m;
    double arc1_u[AN_ARC1_M], arc1_wz[AN_ARC1_M][AN_ARC_K + 1];
    /* Gauss-Legendre on [-1, 1]: gx[m][q], gw[m][q] for m points */
    double gx[AN_MAX_GAUSS + 1][AN_MAX_GAUSS], gw[AN_MAX_GAUSS + 1][AN_MAX_GAUSS];
    /* The knots' lines: x = n + ph[q] for every integer n (ph in [0, 1),
     * ascending), the lines x = cx + k of every pixel centre cx = i + 1/2
     * and knot k; likewise in y. */
    int nph;
    double ph[AN_MAX_CELLS + 1];
    int regular; /* deg + 1 cells of width 1 (fast_part_regular) */
    /* a regular filter's pieces by the column (row) c that holds a part:
     * the cell deg - c's coefficients of W (w) and its left knot, zero
     * past the last column (lanes of fast_part_regular's vectors) */
    _Alignas(16) double rcdf[5][4];
    _Alignas(16) double rw[4][4];
    double rk[4];
    int pad;     /* margins of the scatter's buffers: the support's width + 3 */
    /* The plan of the scene (see "One layer at a time"): for the scene
     * and height it was made for, which rows take the visible parts
     * (slow[j]), and each layer's value per unit of winding (coef, nv
     * values a layer: nv = 1 when every layer has the same step, which
     * is then coef1) over the background bg. */
    const aa_scene *plan_scene;
    int plan_h, plan_nl, nv;
    unsigned char *slow;
    /* every piece's least and greatest x (a vertical line's one x),
     * ascending, distinct: the visible parts' tiles' sides keep clear of
     * them (plan_vert, tile_side) */
    double *vert;
    size_t nvert;
    double *coef;
    /* the colour of each layer's face (winding s(L)), nl x 3; with nv = 1
     * those of the faces of winding -1, 0 and +1 (face1) */
    double *face;
    double face1[3][3];
    size_t fast_off; /* the scatter's buffers in a worker's scratch */
    aa_rgb bg, coef1;
    /* a radial filter (see "Radial filters"): k > 0, its radius, its
     * constant c_k and the marginal's Q; k = 0 for the separable ones */
    int rad_k;
    double rad_r, rad_c, rad_q;
    /* offset pieces (see "Offset curves"): Gauss-Legendre rules of 1 to
     * AN_MAX_PTS points, ogx[m][q], ogw[m][q] */
    double ogx[AN_MAX_PTS + 1][AN_MAX_PTS], ogw[AN_MAX_PTS + 1][AN_MAX_PTS];
} an_state;

typedef struct an_render {
    const an_state *S;
    const aa_scene *scene;
    double lo, hi; /* the filter's range */
    int *uncertain; /* set where an offset part's rule could not be certified */
} an_render;

/* ---- the filters' pieces (patterns/README.md, "Filters") ---- */

/* A symmetric filter by its pieces in x = |t|: on [xb[q], xb[q+1]) the
 * polynomial sum c[q][i] x^i. */
typedef struct an_def {
    int npiece;
    double xb[4];
    double c[3][4];
} an_def;

static int an_def_of(const aa_filter *f, an_def *d)
{
    const double *p = f->spec.v;
    memset(d, 0, sizeof *d);
    if (f->type == &aa_filter_box) {
        *d = (an_def){1, {0.0, 0.5}, {{1.0}}};
        return 0;
    }
    if (f->type == &aa_filter_tent) {
        double r = p[0];
        *d = (an_def){1, {0.0, r}, {{1.0 / r, -1.0 / (r * r)}}};
        return 0;
    }
    if (f->type == &aa_filter_bspline && p[0] == 2.0) {
        /* 3/4 - x^2; (3/2 - x)^2 / 2 = 9/8 - 3/2 x + x^2/2 */
        *d = (an_def){2, {0.0, 0.5, 1.5}, {{0.75, 0.0, -1.0}, {1.125, -1.5, 0.5}}};
        return 0;
    }
    double b, c;
    if (f->type == &aa_filter_bspline && p[0] == 3.0)
        b = 1.0, c = 0.0; /* (4 - 6x^2 + 3x^3)/6, (2 - x)^3/6: mitchell:b=1,c=0 */
    else if (f->type == &aa_filter_mitchell)
        b = p[0], c = p[1];
    else if (f->type == &aa_filter_catrom)
        b = 0.0, c = 0.5;
    else
        return -1;
    /* Mitchell and Netravali (1988, eq. 8) */
    *d = (an_def){2,
                  {0.0, 1.0, 2.0},
                  {{(6.0 - 2.0 * b) / 6.0, 0.0, (-18.0 + 12.0 * b + 6.0 * c) / 6.0,
                    (12.0 - 9.0 * b - 6.0 * c) / 6.0},
                   {(8.0 * b + 24.0 * c) / 6.0, (-12.0 * b - 48.0 * c) / 6.0,
                    (6.0 * b + 30.0 * c) / 6.0, (-b - 6.0 * c) / 6.0}}};
    return 0;
}

/* q(s) = P(x0 + sg s), P of degree 3 (a Taylor shift, then the sign). */
static void shift(const double *P, double x0, double sg, double *q)
{
    double a[4] = {P[0], P[1], P[2], P[3]};
    /* synthetic division by (x - x0), repeated: a becomes the Taylor
     * coefficients about x0 */
    for (int i = 0; i < 4; i++)
        for (int j = 2; j >= i; j--)
            a[j] += x0 * a[j + 1];
    double s = 1.0;
    for (int i = 0; i < 4; i++, s *= sg)
        q[i] = a[i] * s;
}

static void an_pp_make(const an_def *d, an_pp *pp)
{
    memset(pp, 0, sizeof *pp);
    int n = 0;
    /* the left half, outermost first: t in [-xb[q+1], -xb[q]), x = -t */
    for (int q = d->npiece - 1; q >= 0; q--) {
        pp->k[n] = -d->xb[q + 1];
        shift(d->c[q], d->xb[q + 1], -1.0, pp->w[n]);
        n++;
    }
    /* the right half: t in [xb[q], xb[q+1]), x = t */
    for (int q = 0; q < d->npiece; q++) {
        pp->k[n] = d->xb[q];
        shift(d->c[q], d->xb[q], 1.0, pp->w[n]);
        n++;
    }
    pp->k[n] = d->xb[d->npiece];
    /* the innermost piece even (no odd terms): its two cells are one */
    const double *c0 = d->c[0];
    if (c0[1] == 0.0 && c0[3] == 0.0) {
        int m = d->npiece - 1; /* the left innermost cell, [-xb[1], 0) */
        for (int i = m + 1; i < n; i++) {
            pp->k[i] = pp->k[i + 1];
            if (i + 1 < n)
                memcpy(pp->w[i], pp->w[i + 1], sizeof pp->w[i]);
        }
        n--;
    }
    pp->ncell = n;
    pp->deg = 0;
    for (int c = 0; c < n; c++)
        for (int i = 0; i < 4; i++)
            if (pp->w[c][i] != 0.0 && i > pp->deg)
                pp->deg = i;
    double acc = 0.0;
    for (int c = 0; c < n; c++) {
        double h = pp->k[c + 1] - pp->k[c], v = 0.0;
        pp->cdf[c][0] = acc;
        for (int i = 0; i < 4; i++)
            pp->cdf[c][i + 1] = pp->w[c][i] / (i + 1);
        for (int i = 4; i >= 1; i--)
            v = (v + pp->cdf[c][i]) * h;
        acc += v;
    }
    /* s w(s) = (k + s') sum w_i s'^i on the cell, s' = s - k: integrated,
     * k w_i s'^(i+1)/(i+1) + w_i s'^(i+2)/(i+2) */
    acc = 0.0;
    for (int c = 0; c < n; c++) {
        double h = pp->k[c + 1] - pp->k[c], v = 0.0;
        pp->m1[c][0] = acc;
        for (int i = 0; i < 4; i++) {
            pp->m1[c][i + 1] += pp->k[c] * pp->w[c][i] / (i + 1);
            pp->m1[c][i + 2] += pp->w[c][i] / (i + 2);
        }
        for (int i = 5; i >= 1; i--)
            v = (v + pp->m1[c][i]) * h;
        acc += v;
    }
    pp->m1tot = acc;
}

static inline int an_cell(const an_pp *pp, double t)
{
    int c = 0;
    while (c + 1 < pp->ncell && t >= pp->k[c + 1])
        c++;
    return c;
}

static inline double an_weight(const an_pp *pp, double t)
{
    if (!(t >= pp->k[0] && t < pp->k[pp->ncell]))
        return 0.0;
    int c = an_cell(pp, t);
    const double *a = pp->w[c];
    double s = t - pp->k[c];
    return a[0] + s * (a[1] + s * (a[2] + s * a[3]));
}

static inline double an_cdf(const an_pp *pp, double t)
{
    if (t < pp->k[0])
        return 0.0;
    if (t >= pp->k[pp->ncell])
        return 1.0;
    int c = an_cell(pp, t);
    const double *a = pp->cdf[c];
    double s = t - pp->k[c];
    return a[0] + s * (a[1] + s * (a[2] + s * (a[3] + s * a[4])));
}

/* W1(t), the first moment of w up to t */
static inline double an_m1(const an_pp *pp, double t)
{
    if (t < pp->k[0])
        return 0.0;
    if (t >= pp->k[pp->ncell])
        return pp->m1tot;
    int c = an_cell(pp, t);
    const double *a = pp->m1[c];
    double s = t - pp->k[c];
    return a[0] + s * (a[1] + s * (a[2] + s * (a[3] + s * (a[4] + s * a[5]))));
}

/* ---- elliptical arcs ----
 *
 * A conic piece is x = ex + ea cos s + eb sin s, y = ey - er cos s
 * (aabench.h, aa_piece).  Cut at the knots' lines like any piece, a part
 * [sa, sb] of it lies in one cell of every support, and about its middle
 * angle sm, with s = sm + phi, phi in [-om, om], om = (sb - sa)/2,
 *
 *     P(phi) = E + A cos phi + B sin phi = M - A k + B sg,
 *     k = 1 - cos phi = 2 sin^2(phi/2),   sg = sin phi,
 *     A = (ea cos sm + eb sin sm, -er cos sm),
 *     B = (eb cos sm - ea sin sm, er sin sm),   M = E + A = P(0),
 *     y'(phi) = By (1 - k) - Ay sg.
 *
 * On the part w(y - cy) (1 - W(x - cx)) y'(phi), the integrand of (1),
 * is a polynomial of total degree N = 2 n + 2 in (sg, k) (w of degree n,
 * W of n + 1, y' of 1: a trigonometric polynomial of degree N), and since
 * sg^2 = 2 k - k^2 it is p(k) + sg q(k) with p of degree N.  The term sg
 * q(k) is odd in phi and integrates to 0 over [-om, om].  Substituting
 * phi = 2 asin(alpha u), alpha = sin(om/2), u in [-1, 1] (the map of Da
 * Fies and Vianello 2012, "Trigonometric Gaussian quadrature on
 * subintervals of the period", whose rule is Gaussian in u; this one is
 * interpolatory in u^2, below), k = 2 alpha^2 u^2, sg = 2 alpha u
 * sqrt(1 - alpha^2 u^2) (odd in u) and dphi = 2 alpha du / sqrt(1 - z u^2),
 * z = alpha^2:
 *
 *     integral over the part = 2 alpha integral_-1^1 p(2 z u^2) r(u) du,
 *     r(u) = (1 - z u^2)^(-1/2),
 *
 * p(2 z v) a polynomial of degree N in v = u^2.  The rule: the m = N + 1
 * positive nodes u_g of the 2m-point Gauss-Legendre rule, v_g = u_g^2, and
 * the interpolatory weights in v,
 *
 *     Wt_g(z) = integral_-1^1 l_g(u^2) r(u) du
 *             = sum_k beta_k z^k G_gk,   G_gk = integral_-1^1 l_g(u^2) u^(2k) du,
 *
 * l_g the Lagrange polynomial of the nodes v, beta_k = C(2k, k)/4^k (the
 * binomial series of r), integrate every polynomial of degree N in v
 * times r exactly; p(v_g) is the mean of the integrand at +-u_g, which
 * drops the odd part exactly.  So each part takes 2m = 4 n + 6 points (box
 * 6, tent 10, bspline:order=2 14, the cubics 18), each of weight alpha
 * Wt_g(z) times y'.  G_gk is found at init by the 40-point Gauss-Legendre
 * rule in long double (exact: degree 2 (m - 1) + 2 k <= 76); the series is
 * cut after K = 30 terms with parts of om <= pi/3 (longer ones are split),
 * so z <= 1/4 and the tail is below 4^-31 |l_g| (2e-19 of the weights).
 * (The paper integrates rational quadratics in closed form; this rule is
 * the same integral, exact, and keeps every term local: with the arc of
 * length L = 2 R om in a cell, A k ~ L^2 / R and B sg ~ L, so no sum holds
 * a term of the size of the radius, and no cancellation grows as the part
 * shrinks: the weights tend to Gauss-Legendre's as z goes to 0.  A
 * Fourier series of the integrand over the whole period, the other exact
 * way, would hold terms of R^N, hopeless at R = 1e6.)
 *
 * Rounding.  The middle M is a long double sum of terms of the size of
 * the radius R (its error about R 1e-19); the points are M plus terms of
 * the size of the part (placed to about 1e-16 (|M| + L)).  The cuts are
 * angles in long double, found from heights (y = ey - er cos s, from the
 * distances to the ellipse's top or bottom as the scene does: s = 2
 * asin(sqrt(dt / (2 er)))) and from the knots' vertical lines (x = ex +
 * |(ea, eb)| cos(s - atan2(eb, ea))), so a cut lies on its line to about
 * R 1e-19 (where a double angle would give R 2e-16: 2e-10 at R = 1e6).
 * The piece's ends are its heights y0, y1 (arc_angle).  Per part the sum
 * has 2m terms of at most max|w| max|y'| 2 om: its rounding is a few 1e-16
 * of the filter's weight over the part, as for the polynomial pieces.
 * Measured (tests/test_analytic.c): 3.3e-15 at most from the reference on
 * circles of radius 1e4 px, 9.2e-14 at 1e6 px, where a 50-digit quadrature
 * of one box pixel puts analytic 7.6e-14 and the reference 1.6e-14 from
 * it (the R 1e-19 above); without arc_angle's care at the pieces' ends
 * (clamping to the double s0, s1) it was 5e-13 at 1e4 px. */

#define AN_PI 3.14159265358979323846264338327950288L

/* Gauss-Legendre nodes and weights of n points in long double */
static void gauss_ld(int n, long double *x, long double *w)
{
    for (int i = 0; i < n; i++) {
        long double t = cosl(AN_PI * (i + 0.75L) / (n + 0.5L)), dp = 1.0L;
        for (int it = 0; it < 100; it++) {
            long double p0 = 1.0L, p1 = t;
            for (int k = 2; k <= n; k++) {
                long double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                p0 = p1, p1 = p2;
            }
            dp = n * (t * p1 - p0) / (t * t - 1.0L);
            long double dt = p1 / dp;
            t -= dt;
            if (fabsl(dt) < 1e-19L)
                break;
        }
        long double p0 = 1.0L, p1 = t;
        for (int k = 2; k <= n; k++) {
            long double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
            p0 = p1, p1 = p2;
        }
        dp = n * (t * p1 - p0) / (t * t - 1.0L);
        x[i] = t;
        w[i] = 2.0L / ((1.0L - t * t) * dp * dp);
    }
}

/* The rules of 1 to AN_MAX_GAUSS points, rounded to double. */
static void gauss_make(an_state *S)
{
    for (int m = 1; m <= AN_MAX_GAUSS; m++) {
        long double x[AN_MAX_GAUSS], w[AN_MAX_GAUSS];
        gauss_ld(m, x, w);
        for (int i = 0; i < m; i++)
            S->gx[m][i] = (double)x[i], S->gw[m][i] = (double)w[i];
    }
}

/* An arc's rule of m positive nodes u[g] (exact for trigonometric
 * polynomials of degree m - 1 on a part, see above) and the coefficients
 * of their weights in z, wz[g][k]; m <= AN_ARC1_M (G_gk exact: 2 (m - 1) +
 * 2 AN_ARC_K <= 78 < 80). */
static void arc_rule(int m, double *u, double (*wz)[AN_ARC_K + 1])
{
    enum { NQ = 40 };
    long double gu[2 * AN_ARC1_M], gwu[2 * AN_ARC1_M], qx[NQ], qw[NQ], v[AN_ARC1_M];
    gauss_ld(2 * m, gu, gwu);
    gauss_ld(NQ, qx, qw);
    for (int g = 0; g < m; g++) { /* gauss_ld gives them descending: the first m are > 0 */
        u[g] = (double)gu[g];
        v[g] = gu[g] * gu[g];
    }
    for (int g = 0; g < m; g++) {
        long double beta = 1.0L;
        for (int k = 0; k <= AN_ARC_K; k++) {
            if (k > 0)
                beta *= (2.0L * k - 1.0L) / (2.0L * k);
            long double G = 0.0L;
            for (int q = 0; q < NQ; q++) {
                long double u2 = qx[q] * qx[q], l = 1.0L;
                for (int h = 0; h < m; h++)
                    if (h != g)
                        l *= (u2 - v[h]) / (v[g] - v[h]);
                G += qw[q] * l * powl(u2, k);
            }
            wz[g][k] = (double)(beta * G);
        }
    }
}

/* The arc's rules for a filter of degree n (see above): of degree 2 n + 2
 * for the zeroth moment, of 2 n + 3 for the first ("Linear gradients"). */
static void arc_make(an_state *S)
{
    S->arc_m = 2 * S->pp.deg + 3;
    arc_rule(S->arc_m, S->arc_u, S->arc_wz);
    S->arc1_m = 2 * S->pp.deg + 4;
    arc_rule(S->arc1_m, S->arc1_u, S->arc1_wz);
}

/* The angle of conic piece p at height y, in long double.  Not clamped to
 * the piece's s0, s1: those are doubles, off by up to 2e-16 rad, which at
 * a turn in x moves the end along y by er 2e-16 (5e-13 at er = 1e4, a gap
 * between two pieces meeting there); the piece's ends are its heights y0,
 * y1, as for the other pieces. */
static long double arc_angle(const aa_piece *p, double y)
{
    long double er = p->er, dt = (long double)y - ((long double)p->ey - er),
                db = ((long double)p->ey + er) - (long double)y, s;
    dt = dt > 0.0L ? dt : 0.0L;
    db = db > 0.0L ? db : 0.0L;
    if (dt <= db)
        s = 2.0L * asinl(fminl(1.0L, sqrtl(dt / (2.0L * er))));
    else
        s = AN_PI - 2.0L * asinl(fminl(1.0L, sqrtl(db / (2.0L * er))));
    return s;
}

/* The angles in (sa, sb) where conic piece p meets the line x = X: x =
 * ex + R cos(s - a), R = |(ea, eb)|, a = atan2(eb, ea) (given, long
 * double).  Returns how many (at most 2), written to out. */
static int arc_meet_x(const aa_piece *p, long double R, long double a, double X, long double sa,
                      long double sb, long double *out)
{
    long double c = ((long double)X - p->ex) / R;
    if (!(R > 0.0L) || !(c >= -1.0L && c <= 1.0L))
        return 0;
    long double d = acosl(c);
    int n = 0;
    for (int sg = -1; sg <= 1; sg += 2)
        for (int k = -1; k <= 1; k++) {
            long double s = a + sg * d + 2.0L * AN_PI * k;
            if (s > sa && s < sb && n < 2 && (n == 0 || s != out[0]))
                out[n++] = s;
        }
    return n;
}

/* The points of the rule of m positive nodes u (weights' coefficients wz)
 * on the arc part [sa, sb] (om <= pi/3): X, Y, and the weight times
 * y'(phi) (D); its middle (xm, ym).  2 m points. */
static void arc_points_of(int m, const double *u, const double (*wzs)[AN_ARC_K + 1],
                          const aa_piece *p, long double sa, long double sb, double *X,
                          double *Y, double *D, double *xm, double *ym)
{
    long double sm = 0.5L * (sa + sb), cs = cosl(sm), sn = sinl(sm);
    double c = (double)cs, s = (double)sn;
    double Ax = p->ea * c + p->eb * s, Ay = -p->er * c;
    double Bx = p->eb * c - p->ea * s, By = p->er * s;
    double Mx = (double)(p->ex + p->ea * cs + p->eb * sn), My = (double)(p->ey - p->er * cs);
    double al = sin((double)(0.25L * (sb - sa))), z = al * al;
    *xm = Mx, *ym = My;
    for (int g = 0; g < m; g++) {
        const double *wz = wzs[g];
        double wt = wz[AN_ARC_K];
        for (int k = AN_ARC_K - 1; k >= 0; k--)
            wt = wz[k] + z * wt;
        wt *= al;
        double h = al * u[g], k = 2.0 * h * h, sg = 2.0 * h * sqrt(1.0 - h * h);
        double dx = Bx * sg - Ax * k, dy = By * sg - Ay * k;
        X[2 * g] = Mx + dx, Y[2 * g] = My + dy;
        D[2 * g] = wt * (By * (1.0 - k) - Ay * sg);
        X[2 * g + 1] = Mx + (-Bx * sg - Ax * k), Y[2 * g + 1] = My + (-By * sg - Ay * k);
        D[2 * g + 1] = wt * (By * (1.0 - k) + Ay * sg);
    }
}

/* The arc's rule's points on [sa, sb]: 2 arc_m points (arc_points_of). */
static void arc_points(const an_state *S, const aa_piece *p, long double sa, long double sb,
                       double *X, double *Y, double *D, double *xm, double *ym)
{
    arc_points_of(S->arc_m, S->arc_u, (const double(*)[AN_ARC_K + 1])S->arc_wz, p, sa, sb, X, Y,
                  D, xm, ym);
}

/* How many parts of om <= pi/3 the arc [sa, sb] is split into */
static inline int arc_splits(long double sa, long double sb)
{
    long double n = ceill((sb - sa) / (2.0L * AN_PI / 3.0L));
    return n < 1.0L ? 1 : (int)n;
}

static int cmp_ld(const void *a, const void *b)
{
    long double x = *(const long double *)a, y = *(const long double *)b;
    return (x > y) - (x < y);
}


/* ---- offset pieces (header, "Offset curves") ---- */

/* The largest error bound of one part's rule (in the filter's weight), and
 * the halvings of a part at most before a rule's bound is given up. */
#define AN_OFF_TOL 1e-16
#define AN_OFF_DEPTH 50

/* The rules of 1 to AN_MAX_PTS points for offset parts, rounded to double. */
static void off_rules_make(an_state *S)
{
    for (int m = 1; m <= AN_MAX_PTS; m++) {
        long double x[AN_MAX_PTS], w[AN_MAX_PTS];
        gauss_ld(m, x, w);
        for (int i = 0; i < m; i++)
            S->ogx[m][i] = (double)x[i], S->ogw[m][i] = (double)w[i];
    }
}

/* Bounds on the filter's pieces continued off the real line, at a point
 * within dw (of w's argument) resp. dW (of W's) of a real point of any
 * cell: |w| <= sum |w_i| (h_c + dw)^i, the cell c of width h_c whose
 * polynomial holds, the largest over the cells (returned); likewise |W|
 * in *bW. */
static double off_filter_bound(const an_pp *pp, double dw, double dW, double *bW)
{
    double bw = 0.0, bc = 0.0;
    for (int c = 0; c < pp->ncell; c++) {
        double hc = pp->k[c + 1] - pp->k[c], zw = hc + dw, zW = hc + dW, sw = 0.0, sW = 0.0;
        for (int i = 3; i >= 0; i--)
            sw = sw * zw + fabs(pp->w[c][i]);
        for (int i = 4; i >= 0; i--)
            sW = sW * zW + fabs(pp->cdf[c][i]);
        bw = fmax(bw, sw), bc = fmax(bc, sW);
    }
    *bW = bc;
    return bw;
}

/* The fewest points (at most AN_MAX_PTS) of the Gauss-Legendre rule whose
 * error bound on the part [t0, t1] of offset piece p is within
 * AN_OFF_TOL; 0 if none is.  The bound (Trefethen 2013, Theorem 19.3):
 * h 64 M / (15 (1 - rho^-2) rho^(2n)) for the integrand analytic in the
 * Bernstein ellipse of parameter rho about the part (half width h), inside
 * the disc of radius R = h (rho + 1/rho)/2 about its middle, where
 * |w(y - cy) (1 - W(x - cx)) y'| <= M: |P'| <= V there
 * (area_offset_speed, which also proves the disc free of the curve's
 * singularities), so y' and the distance of y from its value at the
 * middle are within |row| V and |row| V R (the map's row), and w, W
 * within off_filter_bound of those; under a radial filter the integrand is
 * F(x - cx, y - cy) y' on a part inside the disc, |F| within rad_f_bound
 * of x and y within |row| V R of a point of the disc (and under a
 * gradient H y' and v F y', |H| within rad_h_bound, |v| within R plus
 * y's drift). */
static double rad_f_bound(const an_state *S, double dx, double dv);
static double rad_h_bound(const an_state *S, double dx, double dv);

/* |W1| at a point within dW of a real point of any cell, as
 * off_filter_bound: sum |m1_i| (h_c + dW)^i, the largest over the cells. */
static double off_m1_bound(const an_pp *pp, double dW)
{
    double b = 0.0;
    for (int c = 0; c < pp->ncell; c++) {
        double z = pp->k[c + 1] - pp->k[c] + dW, sm = 0.0;
        for (int i = 5; i >= 0; i--)
            sm = sm * z + fabs(pp->m1[c][i]);
        b = fmax(b, sm);
    }
    return b;
}

/* off_points for the three moments of a gradient's colour at once (see
 * "Linear gradients"), weighted by J (the largest steps across the part
 * of a, gx and gy over the channels): the rule whose bound on the part's
 * term of the pixel, J0 E0 + J1 Eu + J2 Ev, is within AN_OFF_TOL, the
 * integrands' bounds w (1 - W) y', w (W1(inf) - W1) y' and v w (1 - W) y'
 * (|v| at most the support's half width plus y's drift); J NULL: the
 * zeroth moment alone, as off_points. */
static int off_points_j(const an_state *S, const aa_piece *p, double t0, double t1,
                        const double *J)
{
    static const double rhos[] = {1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 32.0, 64.0};
    enum { NR = sizeof rhos / sizeof *rhos };
    const aa_offset_curve *oc = &p->oc;
    double h = 0.5 * fabs(t1 - t0), mid = 0.5 * (t0 + t1), R[NR], V[NR];
    if (!(h > 0.0))
        return 1;
    for (int k = 0; k < NR; k++)
        R[k] = 0.5 * h * (rhos[k] + 1.0 / rhos[k]);
    area_offset_speed(oc, mid, NR, R, V);
    double nx = hypot(oc->m[0], oc->m[2]), ny = hypot(oc->m[1], oc->m[3]);
    int best = 0;
    for (int k = 0; k < NR && V[k] < INFINITY; k++) {
        double vy = ny * V[k], r2 = rhos[k] * rhos[k], M;
        if (S->rad_k) { /* a radial filter's integrand F(x - cx, y - cy) y' */
            double dx = nx * V[k] * R[k], dv = vy * R[k], bF = rad_f_bound(S, dx, dv);
            M = bF * vy;
            if (J) /* and H y', v F y' ("Linear gradients under the radial filters") */
                M = vy * (J[0] * bF + J[1] * rad_h_bound(S, dx, dv) +
                          J[2] * (S->rad_r + dv) * bF);
        } else {
            const an_pp *pp = &S->pp;
            double bW, bw = off_filter_bound(pp, vy * R[k], nx * V[k] * R[k], &bW);
            M = bw * (1.0 + bW) * vy;
            if (J) {
                double vmax = fmax(fabs(pp->k[0]), fabs(pp->k[pp->ncell])) + vy * R[k];
                double b1 = fabs(pp->m1tot) + off_m1_bound(pp, nx * V[k] * R[k]);
                M = bw * vy * (J[0] * (1.0 + bW) + J[1] * b1 + J[2] * vmax * (1.0 + bW));
            }
        }
        double need = h * 64.0 * M / (15.0 * (1.0 - 1.0 / r2) * AN_OFF_TOL) * (1.0 + 1e-12);
        if (!(need < INFINITY))
            continue;
        /* the fewest n with r2^n >= need, the powers by products */
        double pw = r2;
        int n = 1;
        while (pw < need && n <= AN_MAX_PTS)
            pw *= r2, n++;
        if (n <= AN_MAX_PTS && (!best || n < best))
            best = n;
    }
    return best;
}

static int off_points(const an_state *S, const aa_piece *p, double t0, double t1)
{
    return off_points_j(S, p, t0, t1, NULL);
}

/* The curve's parameter of offset piece p at height y in its rows. */
static double off_t_at(const aa_piece *p, double y)
{
    if (!(y > p->y0))
        return p->ot0;
    if (!(y < p->y1))
        return p->ot1;
    return aa__offset_solve_d(&p->oc, 1, p->ot0, p->ot1, p->y0 - y, y);
}

static inline void off_point(const aa_piece *p, int stops, double t, double *x, double *y,
                             double *dy)
{
    long double X, Y, DX, DY;
    aa__offset_eval_s(&p->oc, stops, t, &X, &Y, &DX, &DY);
    *x = (double)X, *y = (double)Y, *dy = (double)DY;
}

/* The parts of [lo, hi] (ascending parameters) between x's turns, where x
 * is monotone: their ends tb[0 .. n] and x there xb; returns n (1 to 3). */
static int off_monotone(const aa_piece *p, int stops, double lo, double hi, double *tb,
                        double *xb)
{
    tb[0] = lo;
    int n = aa__offset_turns(&p->oc, 0, lo, hi, tb + 1) + 1;
    tb[n] = hi;
    for (int k = 0; k <= n; k++) {
        double y, dy;
        off_point(p, stops, tb[k], &xb[k], &y, &dy);
    }
    return n;
}

/* The parameters where p meets the line x = X inside the parts of
 * off_monotone (one root a part whose ends lie strictly either side),
 * written to out; returns how many. */
static int off_meet_x(const aa_piece *p, const double *tb, const double *xb, int n, double X,
                      double *out)
{
    int c = 0;
    for (int k = 0; k < n; k++) {
        double fa = xb[k] - X, fb = xb[k + 1] - X;
        if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0))
            out[c++] = aa__offset_solve_d(&p->oc, 0, tb[k], tb[k + 1], fa, X);
    }
    return c;
}

/* Marks the render uncertain: 1, an offset part's rule not certified; 2,
 * a part's crossings of a radial filter's circle not isolated
 * (rad_off_cross). */
static void off_uncertain(int *flag, int why)
{
    __atomic_store_n(flag, why, __ATOMIC_RELAXED);
}

static inline double rad_f(const an_state *S, double x, double v);

/* The integral over the part [u, v] (u < v) of offset piece p by the
 * certified rule (off_points), halved where none is: under a separable
 * filter (radial 0; the part inside one cell of the pixel's support) of
 * w(y - cy) (1 - W(x - cx)) y' dt, under a radial one (the part inside the
 * disc) of F(x - cx, y - cy) y' dt. */
static double off_part(const an_render *Rn, const aa_piece *p, int stops, double u, double v,
                       double cx, double cy, int radial, int depth)
{
    const an_state *S = Rn->S;
    const an_pp *pp = &S->pp;
    int m = off_points(S, p, u, v);
    if (!m) {
        double mid = 0.5 * (u + v);
        if (depth < AN_OFF_DEPTH && mid > u && mid < v)
            return off_part(Rn, p, stops, u, mid, cx, cy, radial, depth + 1) +
                   off_part(Rn, p, stops, mid, v, cx, cy, radial, depth + 1);
        off_uncertain(Rn->uncertain, 1);
        m = AN_MAX_PTS;
    }
    double h = 0.5 * (v - u), mid = 0.5 * (u + v), sum = 0.0;
    for (int g = 0; g < m; g++) {
        double x, y, dy;
        off_point(p, stops, mid + h * S->ogx[m][g], &x, &y, &dy);
        if (radial)
            sum += S->ogw[m][g] * rad_f(S, x - cx, y - cy) * dy;
        else
            sum += S->ogw[m][g] * an_weight(pp, y - cy) * (1.0 - an_cdf(pp, x - cx)) * dy;
    }
    return h * sum;
}

#define AN_OFF_CUTS (3 + 4 * (AN_MAX_CELLS + 1))

/* The cuts of offset piece p over rows [ya, yb] for the pixel (cx, cy),
 * ascending, in ts (AN_OFF_CUTS at most; 0 if the rows hold none of it):
 * its parameters at ya and yb (*ta, *tb), t = 1/2 where the curve has a
 * stop, and where it crosses the knots' lines of the pixel's support. */
static int off_cuts(const an_pp *pp, const aa_piece *p, int stops, double ya, double yb,
                    double cx, double cy, double *ts, double *ta_, double *tb_)
{
    double ta = off_t_at(p, ya), tb = off_t_at(p, yb), lo = fmin(ta, tb), hi = fmax(ta, tb);
    *ta_ = ta, *tb_ = tb;
    if (!(lo < hi))
        return 0;
    double tbd[4], xbd[4];
    int n = 0;
    ts[n++] = lo;
    ts[n++] = hi;
    if (stops && 0.5 > lo && 0.5 < hi)
        ts[n++] = 0.5;
    for (int q = 0; q <= pp->ncell; q++) {
        double yk = cy + pp->k[q];
        if (yk > ya && yk < yb)
            ts[n++] = off_t_at(p, yk);
    }
    int nm = off_monotone(p, stops, lo, hi, tbd, xbd);
    for (int q = 0; q <= pp->ncell; q++)
        n += off_meet_x(p, tbd, xbd, nm, cx + pp->k[q], ts + n);
    aa__vis_sort(ts, (size_t)n);
    return n;
}

/* R(part) of (1) for offset piece p over rows [ya, yb]: cut where it
 * crosses the knots' lines of the pixel's support (and at t = 1/2 where
 * the curve has a stop, where its evaluation changes form), each part by
 * off_part. */
static double right_of_offset(const an_render *Rn, const aa_piece *p, double ya, double yb,
                              double cx, double cy)
{
    int stops = aa__offset_stops(&p->oc);
    double ts[AN_OFF_CUTS], ta, tb;
    int n = off_cuts(&Rn->S->pp, p, stops, ya, yb, cx, cy, ts, &ta, &tb);
    double sum = 0.0;
    for (int s = 0; s + 1 < n; s++)
        if (ts[s] < ts[s + 1])
            sum += off_part(Rn, p, stops, ts[s], ts[s + 1], cx, cy, 0, 0);
    return ta < tb ? sum : -sum;
}

/* ---- one pixel ---- */

typedef struct an_pixel {
    const an_render *R;
    double cx, cy;
    double acc[3];
    /* the bands since the last change of colour, rows [blo, bhi] (open:
     * any), their colour (band_merge) */
    int open;
    double blo, bhi;
    aa_rgb bc;
} an_pixel;

static inline int curve_degree(const aa_piece *p)
{
    return p->kind == AA_PIECE_CUBIC ? 3 : (p->kind == AA_PIECE_QUAD ? 2 : 1);
}

#define AN_ARC_CUTS (2 + 3 * (AN_MAX_CELLS + 1))

/* The cuts in angle of conic piece p over rows [ya, yb] for the pixel
 * (cx, cy), ascending, in ss (AN_ARC_CUTS at most): its angles at ya and
 * yb and where it crosses the inner knots' lines of the support. */
static int arc_cuts(const an_pp *pp, const aa_piece *p, double ya, double yb, double cx,
                    double cy, long double *ss)
{
    long double R = hypotl(p->ea, p->eb), ang = atan2l(p->eb, p->ea);
    int n = 0;
    ss[n++] = arc_angle(p, ya);
    ss[n++] = arc_angle(p, yb);
    for (int q = 1; q < pp->ncell; q++) {
        double yk = cy + pp->k[q];
        if (yk > ya && yk < yb)
            ss[n++] = arc_angle(p, yk);
        n += arc_meet_x(p, R, ang, cx + pp->k[q], ss[0], ss[1], ss + n);
    }
    qsort(ss, (size_t)n, sizeof *ss, cmp_ld);
    return n;
}

/* R(part) of (1) for a conic piece: the parts between the knots' lines in
 * angle (long double), each by the arc's rule */
static double right_of_arc(const an_state *S, const aa_piece *p, double ya, double yb,
                           double cx, double cy)
{
    const an_pp *pp = &S->pp;
    long double ss[AN_ARC_CUTS];
    int n = arc_cuts(pp, p, ya, yb, cx, cy, ss);
    double X[AN_MAX_PTS], Y[AN_MAX_PTS], D[AN_MAX_PTS], xm, ym, sum = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ss[s] < ss[s + 1]))
            continue;
        int ns = arc_splits(ss[s], ss[s + 1]);
        for (int r = 0; r < ns; r++) {
            long double a = ss[s] + (ss[s + 1] - ss[s]) * r / ns,
                        b = r + 1 == ns ? ss[s + 1] : ss[s] + (ss[s + 1] - ss[s]) * (r + 1) / ns;
            arc_points(S, p, a, b, X, Y, D, &xm, &ym);
            for (int g = 0; g < 2 * S->arc_m; g++)
                sum += D[g] * an_weight(pp, Y[g] - cy) * (1.0 - an_cdf(pp, X[g] - cx));
        }
    }
    return sum;
}

/* R(part) of (1): the weight right of piece p over rows [ya, yb] */
static double right_of(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                       double cy)
{
    if (p->kind == AA_PIECE_CONIC)
        return right_of_arc(S, p, ya, yb, cx, cy);
    const an_pp *pp = &S->pp;
    double ys[2 + 2 * (AN_MAX_CELLS + 1) * 3];
    int n = 0;
    ys[n++] = ya;
    ys[n++] = yb;
    for (int q = 1; q < pp->ncell; q++) {
        double yk = cy + pp->k[q], m[3];
        if (yk > ya && yk < yb)
            ys[n++] = yk;
        double xk = cx + pp->k[q];
        if (!(xk > p->xmin && xk < p->xmax)) /* the piece's extent misses the line */
            continue;
        int c = aa_piece_meet_x(p, xk, m);
        for (int r = 0; r < c; r++)
            if (m[r] > ya && m[r] < yb)
                ys[n++] = m[r];
    }
    aa__vis_sort(ys, (size_t)n);
    int m = curve_degree(p) * (pp->deg + 1);
    const double *gx = S->gx[m], *gw = S->gw[m];
    double sum = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ys[s] < ys[s + 1]))
            continue;
        double ta = ys[s] <= p->y0 ? 0.0 : aa_piece_t_at(p, ys[s]);
        double tb = ys[s + 1] >= p->y1 ? 1.0 : aa_piece_t_at(p, ys[s + 1]);
        double h = 0.5 * (tb - ta), mid = 0.5 * (ta + tb), part = 0.0;
        for (int g = 0; g < m; g++) {
            double t = mid + h * gx[g], x, y, dy;
            aa__piece_point(p, t, &x, &y, &dy);
            part += gw[g] * an_weight(pp, y - cy) * (1.0 - an_cdf(pp, x - cx)) * dy;
        }
        sum += h * part;
    }
    return sum;
}

static double rad_marg(const an_state *S, double v);

/* The pending bands (band_merge) added: their colour times the weight of
 * their rows, the marginal's difference over all of them at once. */
static void band_flush(an_pixel *P)
{
    if (!P->open)
        return;
    const an_state *S = P->R->S;
    double wy = S->rad_k ? rad_marg(S, P->bhi - P->cy) - rad_marg(S, P->blo - P->cy)
                         : an_cdf(&S->pp, P->bhi - P->cy) - an_cdf(&S->pp, P->blo - P->cy);
    P->open = 0;
    if (!(wy != 0.0))
        return;
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += wy * P->bc.c[ch];
}

/* A band of rows [ya, yb] across the whole window, of one state: its
 * colour times the filter's weight of those rows (the marginal's
 * difference), under the separable filters (an_band) and the radial ones
 * (rad_band), joined to the pending ones where
 * it continues them in the same colour: the visible parts cut a window's
 * rows at every meeting of two pieces, and two pieces of a stroke's
 * outline within rounding of each other were reported meeting every
 * 1e-12 px or so of their common stretch (before aa_piece_meet took such
 * pieces as meeting nowhere there: scene_piece.c, slopes_say), thousands
 * of bands a pixel, whose weights, each a difference of the marginal
 * rounded to 1e-16, summed to 5e-12 off one face's colour
 * (tests/test_analytic_stroke.c, folding strokes); joined, the
 * differences telescope and the face's weight is one difference. */
static void band_merge(an_pixel *P, double ya, double yb, const int *wind)
{
    aa_rgb c = aa_scene_colour_of(P->R->scene, wind);
    if (P->open && ya == P->bhi && !memcmp(c.c, P->bc.c, sizeof c.c)) {
        P->bhi = yb;
        return;
    }
    band_flush(P);
    P->open = 1, P->blo = ya, P->bhi = yb, P->bc = c;
}

static void an_band(void *ctx, double ya, double yb, const int *wind)
{
    band_merge(ctx, ya, yb, wind);
}

static void an_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                   int inside)
{
    an_pixel *P = ctx;
    (void)inside;
    double r = p->kind == AA_PIECE_OFFSET ? right_of_offset(P->R, p, ya, yb, P->cx, P->cy)
                                          : right_of(P->R->S, p, ya, yb, P->cx, P->cy);
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += jump[ch] * r;
}

static void shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const an_render *R = ctx;
    const an_pp *pp = &R->S->pp;
    aa__vis v;
    aa__vis_bind(&v, R->scene, 3, wk->own);
    an_pixel P = {R, i + 0.5, j + 0.5, {0.0, 0.0, 0.0}, 0, 0.0, 0.0, {{0.0, 0.0, 0.0}}};
    const aa__vis_sink sink = {an_band, an_run, NULL, NULL, &P, 3, 0, 0, 1};
    double lo = pp->k[0], hi = pp->k[pp->ncell];
    aa__vis_window(&v, wk->strip, P.cx + lo, P.cx + hi, P.cy + lo, P.cy + hi, &sink);
    band_flush(&P);
    for (int ch = 0; ch < 3; ch++) {
        double c = P.acc[ch];
        px[ch] = c < R->lo ? R->lo : (c > R->hi ? R->hi : c);
    }
}

/* ---- radially symmetric polynomial filters (header, "Radial filters") ---- */

/* F(x, v) = integral from 0 to x of the weight continued past the rim,
 * c (1 - (s^2 + v^2)/R^2)^k ds: with X = x/R and a2 = 1 - (v/R)^2,
 * c R sum_j binom(k, j) (-1)^j a2^(k-j) X^(2j+1) / (2j + 1). */
static inline double rad_f(const an_state *S, double x, double v)
{
    double R = S->rad_r, X = x / R, y = v / R, a2 = (1.0 - y) * (1.0 + y), z = X * X, h;
    switch (S->rad_k) {
    case 1:
        h = a2 - z / 3.0;
        break;
    case 2:
        h = a2 * a2 + z * (z / 5.0 - 2.0 / 3.0 * a2);
        break;
    default:
        h = a2 * a2 * a2 + z * (-a2 * a2 + z * (0.6 * a2 - z / 7.0));
        break;
    }
    return S->rad_c * R * X * h;
}

/* M(v), the weight of the rows below v (y down: of heights < v):
 * 1/2 + Q I_p(asin(v/R)), p = 2k + 2, I_p(phi) = integral from 0 to phi
 * of cos^p, by I_0 = phi, I_p = cos^(p-1) sin / p + (p - 1)/p I_(p-2);
 * Q = 1 / (2 I_p(pi/2)). */
static double rad_marg(const an_state *S, double v)
{
    double y = v / S->rad_r;
    if (y <= -1.0)
        return 0.0;
    if (y >= 1.0)
        return 1.0;
    double c = sqrt((1.0 - y) * (1.0 + y)), I = asin(y), cp = c;
    for (int p = 2; p <= 2 * S->rad_k + 2; p += 2) {
        I = cp * y / p + (p - 1.0) / p * I;
        cp *= c * c;
    }
    return 0.5 + S->rad_q * I;
}

/* The roots of the polynomial sum c[i] t^i of degree n (1 to 6) in the
 * open interval (a, b), ascending: the derivative's roots split (a, b)
 * into intervals where it is monotone, each bisected where its ends'
 * signs differ, to the last bit.  Returns the count. */
static int rad_roots(const double *c, int n, double a, double b, double *out)
{
    while (n > 0 && c[n] == 0.0)
        n--;
    if (n == 0)
        return 0;
    if (n == 1) {
        double t = -c[0] / c[1];
        if (t > a && t < b) {
            out[0] = t;
            return 1;
        }
        return 0;
    }
    double d[6], ends[8];
    for (int i = 1; i <= n; i++)
        d[i - 1] = i * c[i];
    int ne = 0;
    ends[ne++] = a;
    ne += rad_roots(d, n - 1, a, b, ends + ne);
    ends[ne++] = b;
    int m = 0;
    for (int q = 0; q + 1 < ne; q++) {
        double lo = ends[q], hi = ends[q + 1], flo = 0.0, fhi = 0.0;
        for (int i = n; i >= 0; i--) {
            flo = flo * lo + c[i];
            fhi = fhi * hi + c[i];
        }
        if (flo == 0.0 && q > 0) {
            if (m == 0 || out[m - 1] != lo)
                out[m++] = lo;
            continue;
        }
        if (!((flo < 0.0 && fhi > 0.0) || (flo > 0.0 && fhi < 0.0)))
            continue;
        for (;;) {
            double mid = 0.5 * (lo + hi), f = 0.0;
            if (!(mid > lo && mid < hi))
                break;
            for (int i = n; i >= 0; i--)
                f = f * mid + c[i];
            if ((f < 0.0) == (flo < 0.0) && f != 0.0)
                lo = mid;
            else
                hi = mid;
        }
        out[m++] = 0.5 * (lo + hi);
    }
    return m;
}

/* The cuts of polynomial piece p over rows [ya, yb] under a radial filter
 * (header, "Radial filters"): the rows clamped to the disc's, [*lo, *hi],
 * and ts[0 .. n) ascending in t, their ends and the crossings of the
 * circle between; 0 where the rows miss the disc. */
static int rad_cuts(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                    double cy, double ts[8], double *lo, double *hi)
{
    double R = S->rad_r;
    *lo = fmax(ya, cy - R), *hi = fmin(yb, cy + R);
    if (!(*lo < *hi))
        return 0;
    int n = 0;
    ts[n++] = *lo <= p->y0 ? 0.0 : aa_piece_t_at(p, *lo);
    double tb = *hi >= p->y1 ? 1.0 : aa_piece_t_at(p, *hi);
    /* |P(t) - C|^2 - R^2 in the power basis about t = 0 */
    double X[4] = {p->x0 - cx, p->bx, p->ax, p->dx}, Y[4] = {p->y0 - cy, p->by, p->ay, p->dy};
    double g[7] = {0.0};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            g[i + j] += X[i] * X[j] + Y[i] * Y[j];
    g[0] -= R * R;
    n += rad_roots(g, 6, ts[0], tb, ts + n);
    ts[n++] = tb;
    return n;
}

static inline double rad_h(const an_state *S, double x, double v);
static double rad_marg1(const an_state *S, double v);

/* Half the weight of the rows [y0, y1] under a radial filter about the
 * row cy, (M(y1 - cy) - M(y0 - cy))/2, in h[0], and with mom that of the
 * first moment along y, (M1(y1 - cy) - M1(y0 - cy))/2, in h[1] (else 0):
 * of the disc's rows [lo, hi], where the walks below start; of a part
 * outside the disc, in its rows wholly left or right of the centre, which
 * takes -+h. */
__attribute__((always_inline)) static inline void rad_halves(const an_state *S, double y0,
                                                             double y1, double cy, int mom,
                                                             double h[2])
{
    h[0] = 0.5 * (rad_marg(S, y1 - cy) - rad_marg(S, y0 - cy));
    h[1] = mom ? 0.5 * (rad_marg1(S, y1 - cy) - rad_marg1(S, y0 - cy)) : 0.0;
}

/* The walk of polynomial piece p over rows [ya, yb] under a radial filter
 * that the zeroth moment (rad_right_of) and the first moments
 * (rad_mom_right_of) share: cut where it crosses the circle (rad_cuts);
 * between the cuts, a part whose middle lies inside the disc summed over
 * the rule of m points (gx, gw, on [-1, 1]); a part outside, in the disc's
 * rows, wholly left or right of it: +-M/2 (and +-M1/2).  mom and r as
 * rad_arc_walk's. */
__attribute__((always_inline)) static inline void
rad_curve_walk(const an_state *S, const aa_piece *p, double ya, double yb, double cx, double cy,
               int mom, int m, const double *gx, const double *gw, double r[3])
{
    double R = S->rad_r, lo, hi, ts[8], hv[2];
    r[0] = r[1] = r[2] = 0.0;
    int n = rad_cuts(S, p, ya, yb, cx, cy, ts, &lo, &hi);
    if (!n)
        return;
    rad_halves(S, lo, hi, cy, mom, hv);
    double s0 = hv[0], su = 0.0, sv = hv[1];
    for (int s = 0; s + 1 < n; s++) {
        double ta = ts[s], tc = ts[s + 1];
        if (!(ta < tc))
            continue;
        double h = 0.5 * (tc - ta), mid = 0.5 * (ta + tc), x, y, dy;
        aa__piece_point(p, mid, &x, &y, &dy);
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < R * R) {
            double a0 = 0.0, a1 = 0.0, a2 = 0.0;
            for (int q = 0; q < m; q++) {
                aa__piece_point(p, mid + h * gx[q], &x, &y, &dy);
                double u = x - cx, v = y - cy, f = gw[q] * rad_f(S, u, v) * dy;
                a0 += f;
                if (mom) {
                    a1 += gw[q] * rad_h(S, u, v) * dy;
                    a2 += v * f;
                }
            }
            s0 -= h * a0;
            if (mom)
                su += h * a1, sv -= h * a2;
        } else {
            double y0, y1, d;
            aa__piece_point(p, ta, &d, &y0, &d);
            aa__piece_point(p, tc, &d, &y1, &d);
            rad_halves(S, y0, y1, cy, mom, hv);
            s0 -= x > cx ? hv[0] : -hv[0];
            sv -= x > cx ? hv[1] : -hv[1];
        }
    }
    r[0] = s0, r[1] = su, r[2] = sv;
}

/* R(part) for polynomial piece p over rows [ya, yb] under a radial filter
 * (header, "Radial filters"; rad_curve_walk): inside the disc the rule of
 * d (K + 1) points. */
static double rad_right_of(const an_state *S, const aa_piece *p, double ya, double yb,
                           double cx, double cy)
{
    double r[3];
    int m = curve_degree(p) * (S->rad_k + 1);
    rad_curve_walk(S, p, ya, yb, cx, cy, 0, m, S->gx[m], S->gw[m], r);
    return r[0];
}

/* The cuts of conic piece p over rows [ya, yb] under a radial filter:
 * the rows clamped to the disc's, [*lo, *hi], and the angles ss[0 .. n)
 * ascending, their ends and the crossings of the circle between; 0 where
 * the rows miss the disc.  About the part's middle angle sm, s = sm +
 * phi, the piece is P - C = E + A cos phi + B sin phi, and with tau =
 * tan(phi/2) (|phi| <= pi/2 on a piece, so |tau| <= 1) (1 + tau^2)(P - C)
 * is the quadratic (E + A) + 2 B tau + (E - A) tau^2: the circle's
 * crossings are the roots of the quartic |(1 + tau^2)(P - C)|^2 - R^2
 * (1 + tau^2)^2. */
static int rad_arc_cuts(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                        double cy, long double ss[8], double *lo, double *hi)
{
    double R = S->rad_r;
    *lo = fmax(ya, cy - R), *hi = fmin(yb, cy + R);
    if (!(*lo < *hi))
        return 0;
    int n = 0;
    ss[n++] = arc_angle(p, *lo);
    long double sb = arc_angle(p, *hi), sm = 0.5L * (ss[0] + sb);
    double hw = (double)(0.5L * (sb - ss[0])), cm = cos((double)sm), sn = sin((double)sm);
    double Ex = p->ex - cx, Ey = p->ey - cy;
    double Ax = p->ea * cm + p->eb * sn, Bx = p->eb * cm - p->ea * sn;
    double Ay = -p->er * cm, By = p->er * sn;
    double qx[3] = {Ex + Ax, 2.0 * Bx, Ex - Ax}, qy[3] = {Ey + Ay, 2.0 * By, Ey - Ay};
    double g[7] = {0.0}, tau[6];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            g[i + j] += qx[i] * qx[j] + qy[i] * qy[j];
    g[0] -= R * R, g[2] -= 2.0 * R * R, g[4] -= R * R;
    double te = tan(0.5 * hw);
    int nr = rad_roots(g, 4, -te, te, tau);
    for (int q = 0; q < nr; q++) {
        long double s = sm + 2.0L * atanl(tau[q]);
        if (s > ss[n - 1] && s < sb)
            ss[n++] = s;
    }
    ss[n++] = sb;
    return n;
}

/* The walk of conic piece p over rows [ya, yb] under a radial filter that
 * the zeroth moment (rad_right_of_arc) and the first moments
 * (rad_mom_arc) share: cut where it crosses the circle (rad_arc_cuts);
 * between the cuts, a span whose middle lies inside the disc split into
 * parts of om <= pi/3 (arc_splits), each summed over the arc's rule of m
 * points (u, wz: arc_points_of); a span outside, +-M/2 (and +-M1/2).  mom
 * = 0: R(part) alone, in r[0]; 1: r[0 .. 2], R(part) and the first moments
 * along x and y (rad_mom_right_of).  Inlined with mom constant: the
 * zeroth's walk does none of the first moments' work. */
__attribute__((always_inline)) static inline void
rad_arc_walk(const an_state *S, const aa_piece *p, double ya, double yb, double cx, double cy,
             int mom, int m, const double *u, const double (*wz)[AN_ARC_K + 1], double r[3])
{
    double R = S->rad_r, lo, hi;
    long double ss[8];
    r[0] = r[1] = r[2] = 0.0;
    int n = rad_arc_cuts(S, p, ya, yb, cx, cy, ss, &lo, &hi);
    if (!n)
        return;
    double X[2 * AN_ARC1_M], Y[2 * AN_ARC1_M], D[2 * AN_ARC1_M], xm, ym, hv[2];
    rad_halves(S, lo, hi, cy, mom, hv);
    double s0 = hv[0], su = 0.0, sv = hv[1];
    for (int q = 0; q + 1 < n; q++) {
        long double a = ss[q], b = ss[q + 1], mid = 0.5L * (a + b);
        if (!(a < b))
            continue;
        double x = p->ex + (p->ea * cos((double)mid) + p->eb * sin((double)mid)),
               y = p->ey - p->er * cos((double)mid);
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < R * R) {
            int ns = arc_splits(a, b);
            for (int e = 0; e < ns; e++) {
                long double sa = a + (b - a) * e / ns;
                long double sb = e + 1 == ns ? b : a + (b - a) * (e + 1) / ns;
                arc_points_of(m, u, wz, p, sa, sb, X, Y, D, &xm, &ym);
                for (int g = 0; g < 2 * m; g++) {
                    double du = X[g] - cx, dv = Y[g] - cy, f = D[g] * rad_f(S, du, dv);
                    s0 -= f;
                    if (mom) {
                        su += D[g] * rad_h(S, du, dv);
                        sv -= dv * f;
                    }
                }
            }
        } else {
            double y0 = (double)(p->ey - p->er * cosl(a)), y1 = (double)(p->ey - p->er * cosl(b));
            rad_halves(S, y0, y1, cy, mom, hv);
            s0 -= x > cx ? hv[0] : -hv[0];
            sv -= x > cx ? hv[1] : -hv[1];
        }
    }
    r[0] = s0, r[1] = su, r[2] = sv;
}

/* R(part) for conic piece p over rows [ya, yb] under a radial filter
 * (rad_arc_walk): inside the disc the arc's rule of the filter's degree
 * n = K (the integrand F(x, y) y' is a trigonometric polynomial of degree
 * 2 K + 2, as w (1 - W) y' of degree 2 n + 2 is); outside, +-M/2. */
static double rad_right_of_arc(const an_state *S, const aa_piece *p, double ya, double yb,
                               double cx, double cy)
{
    double r[3];
    rad_arc_walk(S, p, ya, yb, cx, cy, 0, S->arc_m, S->arc_u,
                 (const double(*)[AN_ARC_K + 1])S->arc_wz, r);
    return r[0];
}

/* ---- offset pieces under a radial filter (header, "Offset curves") ---- */

/* A bound on |F(x, v)| (rad_f) at complex x and v within dx and dv of a
 * real point of the disc (|x|, |v| <= R): with X = x/R and a2 = 1 -
 * (v/R)^2, |X| <= 1 + dx/R and |a2| <= 1 + (1 + dv/R)^2, term by term. */
static double rad_f_bound(const an_state *S, double dx, double dv)
{
    double R = S->rad_r, X = 1.0 + dx / R, y = 1.0 + dv / R, a = 1.0 + y * y, z = X * X;
    double sum = 0.0, b = 1.0, zj = 1.0;
    for (int j = 0; j <= S->rad_k; j++) {
        double aj = 1.0;
        for (int i = j; i < S->rad_k; i++)
            aj *= a;
        sum += b * aj * zj / (2 * j + 1);
        b = b * (S->rad_k - j) / (j + 1);
        zj *= z;
    }
    return S->rad_c * R * X * sum * (1.0 + 1e-12);
}

/* The first moment along x right of x in the row at height v
 * ("Linear gradients under the radial filters"): H(x, v) = integral from x
 * to the chord's end of s w(s, v) ds = c R^2/(2 (K + 1)) (1 - (x^2 +
 * v^2)/R^2)^(K + 1) inside the disc (0 outside), here the polynomial
 * continued. */
static inline double rad_h(const an_state *S, double x, double v)
{
    double R = S->rad_r, X = x / R, y = v / R, q = (1.0 - y) * (1.0 + y) - X * X, h = q;
    for (int i = 0; i < S->rad_k; i++)
        h *= q;
    return S->rad_c * R * R / (2.0 * (S->rad_k + 1)) * h;
}

/* A bound on |H(x, v)| (rad_h) at complex x and v within dx and dv of a
 * real point of the disc: |1 - X^2 - y^2| <= 1 + (1 + dx/R)^2 + (1 +
 * dv/R)^2. */
static double rad_h_bound(const an_state *S, double dx, double dv)
{
    double R = S->rad_r, X = 1.0 + dx / R, y = 1.0 + dv / R, q = 1.0 + X * X + y * y, h = q;
    for (int i = 0; i < S->rad_k; i++)
        h *= q;
    return S->rad_c * R * R / (2.0 * (S->rad_k + 1)) * h * (1.0 + 1e-12);
}

/* M1(v) = integral over the rows below v of s times the row's weight
 * (Q/R) a2^(K + 1/2): -Q R/(2 K + 3) a2^(K + 3/2), a2 = 1 - (v/R)^2; 0
 * outside the disc's rows ("Linear gradients under the radial
 * filters"). */
static double rad_marg1(const an_state *S, double v)
{
    double y = v / S->rad_r;
    if (!(y > -1.0 && y < 1.0))
        return 0.0;
    double a2 = (1.0 - y) * (1.0 + y), p = a2 * sqrt(a2);
    for (int i = 0; i < S->rad_k; i++)
        p *= a2;
    return -S->rad_q * S->rad_r / (2 * S->rad_k + 3) * p;
}

/* The crossings of an offset piece with the filter's circle are sought on
 * at most this many intervals deep (halvings), and at most this many cuts
 * are kept per part (beyond: the render is refused, as uncertain). */
#define AN_RAD_DEPTH 64
#define AN_RAD_CUTS 64
/* intervals examined per part at most: a curve that runs within rounding
 * of the circle along a stretch (an arc concentric with it, of its
 * radius) is never proven off it, and would be halved to the last bit all
 * along; it is refused instead */
#define AN_RAD_WORK 4096

/* The point of p at t relative to the centre, (x, y), its derivative, g(t)
 * = x^2 + y^2 - R^2 and g'(t)/2 = (x, y) . P'(t), in long double. */
typedef struct an_gpt {
    long double x, y, dx, dy, g, s;
} an_gpt;

static an_gpt rad_g(const aa_piece *p, int stops, double t, double cx, double cy, double R)
{
    an_gpt q;
    aa__offset_eval_s(&p->oc, stops, t, &q.x, &q.y, &q.dx, &q.dy);
    q.x -= cx, q.y -= cy;
    q.g = (q.x - R) * (q.x + R) + q.y * q.y;
    q.s = q.x * q.dx + q.y * q.dy;
    return q;
}

static inline int opposite(long double a, long double b)
{
    return (a < 0 && b > 0) || (a > 0 && b < 0);
}

/* The one root of g in (a, b), where g is monotone and ga = g(a) and g(b)
 * have opposite signs: Newton's method kept in the bracket, bisection
 * where a step leaves it, until the bracket's ends are neighbours or a
 * step is below the last bit of t. */
static double rad_off_root(const aa_piece *p, int stops, double a, double b, long double ga,
                           double cx, double cy, double R)
{
    double t = 0.5 * (a + b);
    for (int it = 0; it < 200; it++) {
        an_gpt q = rad_g(p, stops, t, cx, cy, R);
        if (q.g == 0)
            return t;
        if (opposite(q.g, ga))
            b = t;
        else
            a = t, ga = q.g;
        double nt = q.s != 0 ? (double)(t - q.g / (2 * q.s)) : NAN;
        double mid = 0.5 * (a + b);
        if (!(mid > a && mid < b))
            break;
        if (!(nt > a && nt < b))
            nt = mid;
        if (fabs(nt - t) <= 4.0 * DBL_EPSILON * fabs(t) && nt != mid) {
            t = nt;
            break;
        }
        t = nt;
    }
    return t;
}

/* What rad_off_cross carries: the piece (evaluated with its stops), the
 * pixel's centre, the filter, half the part's length H, the cuts found
 * (out[0 .. n), n < 0: given up), the intervals examined, and under a
 * gradient the largest steps J of a, gx and gy across the part (NULL: a
 * flat colour's step, the zeroth moment alone). */
typedef struct an_iso {
    const an_state *S;
    const aa_piece *p;
    int stops;
    double cx, cy, H;
    double *out;
    int n, work;
    const double *J;
} an_iso;

static void iso_cut(an_iso *I, double t)
{
    if (I->n < 0)
        return;
    if (I->n >= AN_RAD_CUTS)
        I->n = -1;
    else
        I->out[I->n++] = t;
}

/* The cuts of an offset piece at its crossings with the circle of radius R
 * about C inside (a, b), where one analytic function holds (no stop's t =
 * 1/2 inside); g at the ends ga, gb.  On [m - h, m + h], with |P'| <= V0
 * on the disc of radius h about m (area_offset_speed) and so |P(t) - P(m)|
 * <= V0 h:
 *  - no crossing where |P(m) - C| is farther than V0 h from R;
 *  - with |P'| <= Vk on the disc of radius Rk = rho_k h (rho_k = 2 ..
 *    256), Cauchy's estimate gives |P''| <= Vk/(Rk - h) on the interval,
 *    so g'/2 = (P - C) . P' is within D = h (V0^2 + (|P(m) - C| + V0 h)
 *    Vk/(Rk - h)) of its value s at m, and g within 2 h (|s| + D) of g(m):
 *    no crossing where |g(m)| exceeds that;
 *  - at most one where |s| > D (g' of one sign), where g's signs at the
 *    ends differ: found by rad_off_root;
 *  - every point within e = G/R of the circle, G = |g(m)| + 2 h (|s| + D)
 *    (|g| = |r - R| (r + R) at distance r from C): there F(clamp(x)) and
 *    F(x) differ by at most c (3 e/R)^K sqrt(3 R e) (the chord's end moves
 *    by at most sqrt(|r^2 - R^2|), over which the continued weight is at
 *    most c |r^2/R^2 - 1|^K), so however the interval is taken (it is cut
 *    at its ends, a part of its own) the integral moves by at most 2 h V0
 *    times that: taken so where that is within AN_OFF_TOL h/H (so within
 *    AN_OFF_TOL over the part), as happens where the curve touches the
 *    circle.  Under a gradient the first moments' integrands move too:
 *    H (below rad_h) is c R^2/(2 (K + 1)) (1 - r^2/R^2)^(K + 1) on one
 *    side and 0 on the other, at most c R^2/(2 (K + 1)) (3 e/R)^(K + 1),
 *    and v F(clamp(x)) by |v| <= R + e times the zeroth's bound: the
 *    bound is J0 E0 + J1 EH + J2 (R + e) E0.
 * Neither proven, the interval is halved; one that cannot be (its ends
 * neighbours in double) is cut at its middle where g's signs at its ends
 * differ (any other crossings in it are within its width of it: a
 * misplaced crossing moves the integral by the square of the error, the
 * integrand being continuous across the circle).  Beyond AN_RAD_WORK
 * intervals or AN_RAD_CUTS cuts, given up (a curve running along the
 * circle within rounding, never proven off it). */
static void rad_off_cross(an_iso *I, double a, double b, long double ga, long double gb,
                          int depth)
{
    static const double rhos[] = {1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0};
    enum { NR = sizeof rhos / sizeof *rhos };
    if (I->n < 0)
        return;
    if (++I->work > AN_RAD_WORK) {
        I->n = -1;
        return;
    }
    const an_state *S = I->S;
    const aa_piece *p = I->p;
    double R = S->rad_r, m = 0.5 * (a + b), h = 0.5 * (b - a);
    if (!(m > a && m < b) || depth >= AN_RAD_DEPTH) {
        if (opposite(ga, gb))
            iso_cut(I, m > a && m < b ? m : a);
        return;
    }
    const aa_offset_curve *oc = &p->oc;
    double Rk[NR], V[NR];
    for (int k = 0; k < NR; k++)
        Rk[k] = rhos[k] * h;
    area_offset_speed(oc, m, NR, Rk, V);
    /* the map's bound: |(m z)_x| <= |row x| |z| for a complex vector z */
    double nf = hypot(hypot(oc->m[0], oc->m[2]), hypot(oc->m[1], oc->m[3]));
    an_gpt q = rad_g(p, I->stops, m, I->cx, I->cy, R);
    double d = (double)sqrtl(q.x * q.x + q.y * q.y), sp = (double)sqrtl(q.dx * q.dx + q.dy * q.dy);
    double ag = (double)fabsl(q.g), as = (double)fabsl(q.s);
    /* rounding of the point, of d and of g: far below these */
    double tol = 64.0 * DBL_EPSILON * (d + R), gtol = 2.0 * tol * (d + R);
    if (V[0] < INFINITY) {
        double v0 = nf * V[0], e = v0 * h, Gmin = INFINITY;
        if (d - e - tol > R || d + e + tol < R)
            return;
        for (int k = 1; k < NR && V[k] < INFINITY; k++) {
            double D = h * (v0 * v0 + (d + e) * nf * V[k] / (Rk[k] - h)) * (1.0 + 1e-12) +
                       64.0 * DBL_EPSILON * d * sp;
            double G = ag + 2.0 * h * (as + D) + gtol;
            if (ag > G - ag)
                return;
            if (as > D) { /* g monotone on [a, b] */
                if (opposite(ga, gb))
                    iso_cut(I, rad_off_root(p, I->stops, a, b, ga, I->cx, I->cy, R));
                return;
            }
            Gmin = fmin(Gmin, G);
        }
        double eps = Gmin / R;
        if (eps < R) {
            double E = S->rad_c * sqrt(3.0 * R * eps);
            for (int i = 0; i < S->rad_k; i++)
                E *= 3.0 * eps / R;
            if (I->J) {
                double EH = S->rad_c * R * R / (2.0 * (S->rad_k + 1));
                for (int i = 0; i <= S->rad_k; i++)
                    EH *= 3.0 * eps / R;
                E = I->J[0] * E + I->J[1] * EH + I->J[2] * (R + eps) * E;
            }
            if (2.0 * h * v0 * E <= AN_OFF_TOL * h / I->H) {
                iso_cut(I, a);
                iso_cut(I, b);
                return;
            }
        }
    }
    rad_off_cross(I, a, m, ga, q.g, depth + 1);
    if (q.g == 0) /* a crossing (or touching) at m itself */
        iso_cut(I, m);
    rad_off_cross(I, m, b, q.g, gb, depth + 1);
}

/* The cuts of offset piece p over the rows [lo, hi] (inside the disc's)
 * under a radial filter: its parameters at lo and hi (*ta, *tb), and
 * ts[0 .. n) ascending from min(ta, tb) to max(ta, tb), with the
 * crossings of the circle (rad_off_cross, certified for the steps J: see
 * an_iso) and t = 1/2 where the piece has a stop; n = 0 where the part is
 * empty, -1 where the crossings were not isolated. */
static int rad_off_cuts(const an_state *S, const aa_piece *p, int stops, double lo, double hi,
                        double cx, double cy, const double *J, double *ts, double *ta,
                        double *tb)
{
    double R = S->rad_r;
    *ta = off_t_at(p, lo), *tb = off_t_at(p, hi);
    double t0 = fmin(*ta, *tb), t1 = fmax(*ta, *tb);
    if (!(t0 < t1))
        return 0;
    double ends[3] = {t0, t1, t1};
    int ne = 2;
    if (stops && 0.5 > t0 && 0.5 < t1)
        ends[1] = 0.5, ne = 3;
    an_iso I = {S, p, stops, cx, cy, 0.5 * (t1 - t0), ts + 1, 0, 0, J};
    an_gpt ea = rad_g(p, stops, t0, cx, cy, R);
    for (int k = 1; k < ne && I.n >= 0; k++) {
        an_gpt eb = rad_g(p, stops, ends[k], cx, cy, R);
        rad_off_cross(&I, ends[k - 1], ends[k], ea.g, eb.g, 0);
        iso_cut(&I, ends[k]);
        ea = eb;
    }
    if (I.n < 0)
        return -1;
    ts[0] = t0;
    aa__vis_sort(ts, (size_t)(I.n + 1));
    return I.n + 1;
}

static void mom_off_part(const an_render *Rn, const aa_piece *p, int stops, double u, double v,
                         double cx, double cy, const double *J, int radial, int depth,
                         double r[3]);

/* The walk of offset piece p over rows [ya, yb] under a radial filter that
 * the zeroth moment (rad_right_of_offset) and the first moments
 * (rad_mom_offset) share: as rad_right_of, the piece cut where it crosses
 * the circle (rad_off_cuts; for the first moments the touching intervals
 * certified for J) and at t = 1/2 where it has a stop; the sub-parts inside
 * the disc by the certified rule (off_part; mom_off_part), those
 * outside, in the disc's rows, wholly left or right of it (y monotone),
 * where F(clamp) = +-F(ch): +-M/2 (and +-M1/2).  mom and r as
 * rad_arc_walk's. */
__attribute__((always_inline)) static inline void
rad_off_walk(const an_render *Rn, const aa_piece *p, double ya, double yb, double cx, double cy,
             int mom, const double *J, double r[3])
{
    const an_state *S = Rn->S;
    double R = S->rad_r, lo = fmax(ya, cy - R), hi = fmin(yb, cy + R);
    r[0] = r[1] = r[2] = 0.0;
    if (!(lo < hi))
        return;
    int stops = aa__offset_stops(&p->oc);
    double ts[AN_RAD_CUTS + 4], ta, tb, part[3] = {0.0, 0.0, 0.0};
    int n = rad_off_cuts(S, p, stops, lo, hi, cx, cy, J, ts, &ta, &tb);
    if (n < 0)
        off_uncertain(Rn->uncertain, 2);
    for (int s = 0; s + 1 < n; s++) {
        double u = ts[s], v = ts[s + 1];
        if (!(u < v))
            continue;
        double x, y, dy;
        off_point(p, stops, 0.5 * (u + v), &x, &y, &dy);
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < R * R) {
            if (mom)
                mom_off_part(Rn, p, stops, u, v, cx, cy, J, 1, 0, part);
            else
                part[0] += off_part(Rn, p, stops, u, v, cx, cy, 1, 0);
        } else {
            double y0, y1, d, hv[2];
            off_point(p, stops, u, &d, &y0, &d);
            off_point(p, stops, v, &d, &y1, &d);
            rad_halves(S, y0, y1, cy, mom, hv);
            part[0] += x > cx ? hv[0] : -hv[0];
            part[2] += x > cx ? hv[1] : -hv[1];
        }
    }
    double sg = ta < tb ? 1.0 : -1.0, hv[2];
    rad_halves(S, lo, hi, cy, mom, hv);
    r[0] = hv[0] - sg * part[0];
    if (mom) {
        r[1] = sg * part[1];
        r[2] = hv[1] - sg * part[2];
    }
}

/* R(part) for offset piece p over rows [ya, yb] under a radial filter
 * (rad_off_walk). */
static double rad_right_of_offset(const an_render *Rn, const aa_piece *p, double ya, double yb,
                                  double cx, double cy)
{
    double r[3];
    rad_off_walk(Rn, p, ya, yb, cx, cy, 0, NULL, r);
    return r[0];
}

static void rad_band(void *ctx, double ya, double yb, const int *wind)
{
    band_merge(ctx, ya, yb, wind);
}

static void rad_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                    int inside)
{
    an_pixel *P = ctx;
    (void)inside;
    double r = p->kind == AA_PIECE_CONIC    ? rad_right_of_arc(P->R->S, p, ya, yb, P->cx, P->cy)
               : p->kind == AA_PIECE_OFFSET ? rad_right_of_offset(P->R, p, ya, yb, P->cx, P->cy)
                                            : rad_right_of(P->R->S, p, ya, yb, P->cx, P->cy);
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += jump[ch] * r;
}

static void rad_shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const an_render *R = ctx;
    double r = R->S->rad_r;
    aa__vis v;
    aa__vis_bind(&v, R->scene, 3, wk->own);
    an_pixel P = {R, i + 0.5, j + 0.5, {0.0, 0.0, 0.0}, 0, 0.0, 0.0, {{0.0, 0.0, 0.0}}};
    const aa__vis_sink sink = {rad_band, rad_run, NULL, NULL, &P, 3, 0, 0, 1};
    aa__vis_window(&v, wk->strip, P.cx - r, P.cx + r, P.cy - r, P.cy + r, &sink);
    band_flush(&P);
    for (int ch = 0; ch < 3; ch++) {
        double c = P.acc[ch];
        px[ch] = c < R->lo ? R->lo : (c > R->hi ? R->hi : c);
    }
}

static int rad_render_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                          uint64_t *samples, uint64_t *expensive)
{
    const an_render *R = ctx;
    return aa__sampler_row(wk, j, R->S->rad_r, 0, rad_shade, ctx, out, samples, expensive);
}


/* ---- one layer at a time: the paper's per-edge scatter ----
 *
 * Where the colour is the background plus a fixed step per unit of one
 * layer's winding, the picture is linear in the windings, so in the edges:
 * with wind(x, y) the sum of dir over the pieces crossing line y left of x,
 *
 *     pixel = bg + sum over pieces p of dir(p) coef(layer p) R(p),
 *
 * R of (1) over p's rows in the pixel's support (the weights sum to 1).  No
 * visible parts are needed; each piece is cut once at the knots' lines
 * (x = n + ph, y = n + ph: every pixel's lines x = cx + k, y = cy + k), and
 * each part, inside one cell of every pixel's support it meets, gives its
 * rule's points once, for all those pixels: with a(g) = gw h y' w(y - cy)
 * at its points,
 *
 *     R = sum_g a(g) (1 - W(x_g - cx))
 *       = A - sum_g a(g) W(x_g - cx),     A = sum_g a(g),
 *
 * which is A for the pixels of the row whose support lies right of the part
 * (W = 0 there) and 0 left of it (W = 1).  A is added at the first column
 * whose support reaches the part and carried along the row by a running
 * sum (area.c's cover and accumulation); the columns whose support holds
 * the part take their sum of W (added as a difference of neighbours, so
 * the one running sum makes the row).  The rule needs fewer points where
 * the curve's degree in y or x is lower than its kind's (crow's arcs have
 * y linear in t): with dy, dx the degrees of y(t), x(t) the integrand has
 * degree n dy + (n + 1) dx + dy - 1.
 *
 * When it holds: the colour is bg + wind(L) coef(L) exactly where at most
 * one layer's winding is non-zero and it is s(L) = +1 or -1, the same sign
 * wherever layer L is seen (either rule then says inside, and coef(L) =
 * s(L) (colour at winding s(L) - bg)).  At init the scene is swept
 * (visible.c, every face between neighbouring pieces in every band of its
 * rows, eight rows at a time) and a band where a face breaks this marks
 * the rows whose supports reach it: those rows take the visible parts
 * (below, "The visible parts' scatter"); the others, this one.  A crossing of two pieces always
 * breaks it in one of the four faces about it, so do overlapping layers,
 * a path wound twice, and the zero-width face between the two copies of
 * an edge shared by abutting paths of one layer (conservative: such rows
 * take the visible parts).
 *
 * A pixel whose support no part reaches and no flat piece crosses lies
 * inside one face and takes its colour exactly, as the per-pixel path's
 * uniform runs give it: from the winding the running sum holds (within
 * rounding of an integer) when every layer has the same step and, of each
 * sign, the same colour (one value a piece, nv = 1), else from a fourth
 * value summing dir (L + 1), which in a face of layer L is (L + 1) s(L).
 * Each cell is marked where a part's exact term reached it (AN_TERM) or
 * where only a carry of the running sum was added (AN_CARRY: the column
 * right of a part's columns, the first column for a part left of every
 * support); the cells of unmarked pixels hold nothing, so a run of them
 * is one face, its colour stored eight pixels at a time without passing
 * the sum over them (the same values as one pixel at a time: the sum is
 * rounded once, at the run's start, and is an integer after it).
 *
 * Rows are taken AN_BLOCK at a time (the parts of a piece cut at the
 * block's support rows, which are knots' lines): a pixel's value sums its
 * terms in the scene's piece order whatever the threads. */

#define AN_BLOCK 64
/* a cell's marks (an_block's touched): a part's exact term reached the
 * pixel (or a flat piece crosses its support), or only a carry of the
 * running sum was added there; a pixel of neither has its support inside
 * one face and nothing in its cell of the running sum */
#define AN_TERM 1
#define AN_CARRY 2
/* values a piece carries when the layers' steps differ: colour and code */
#define AN_NV 4
/* distinct colours of faces the visible parts' scatter names by a code in
 * one block (vis_block); a block that meets more takes the per-pixel path */
#define AN_FACES 256

typedef struct an_check {
    an_state *S;
    int nl, h;
    double lo, hi; /* the band being swept */
    signed char *sign;
} an_check;

static void chk_band(void *ctx, double ya, double yb, const int *wind)
{
    an_check *C = ctx;
    (void)wind; /* left of the scene: no winding */
    C->lo = ya, C->hi = yb;
}

static void chk_values(void *ctx, const int *wind, double *out)
{
    an_check *C = ctx;
    const an_pp *pp = &C->S->pp;
    int seen = 0, bad = 0;
    out[0] = 0.0;
    for (int L = 0; L < C->nl; L++) {
        int w = wind[L];
        if (!w)
            continue;
        if (seen++ || (w != 1 && w != -1))
            bad = 1;
        else if (!C->sign[L])
            C->sign[L] = (signed char)w;
        else if (C->sign[L] != w)
            bad = 1;
    }
    if (!bad)
        return;
    /* rows whose support [j + 1/2 + k0, j + 1/2 + kn] meets the band, one
     * more each way */
    double k0 = pp->k[0], kn = pp->k[pp->ncell];
    double a = floor(C->lo - 0.5 - kn) - 1.0, b = floor(C->hi - 0.5 - k0) + 1.0;
    int ja = a < 0.0 ? 0 : (a > C->h ? C->h : (int)a);
    int jb = b < 0.0 ? -1 : (b >= C->h ? C->h - 1 : (int)b);
    for (int j = ja; j <= jb; j++)
        C->S->slow[j] = 1;
}

static void plan_free(an_state *S)
{
    free(S->slow);
    free(S->coef);
    free(S->face);
    free(S->vert);
    S->slow = NULL, S->coef = NULL, S->face = NULL, S->vert = NULL;
    S->nvert = 0;
    S->plan_scene = NULL;
    S->plan_h = 0;
}

/* S->vert: the x where a piece's x is extreme (its xmin and xmax: a
 * vertical piece's x, a curve's leftmost and rightmost points), sorted
 * and distinct.  The tiles' sides keep clear of
 * them (tile_side): where a curve is tangent to a side, its crossing's
 * height is found only to about the square root of rounding (1e-8 px),
 * and the two tiles, each solving it in its own band, would count a sliver
 * that high twice or not at all. */
static int plan_vert(an_state *S, const aa_scene *scene)
{
    size_t n, nv = 0;
    const aa_piece *p = aa_scene_pieces(scene, &n);
    for (size_t k = 0; k < n; k++)
        nv += p[k].kind != AA_PIECE_FLAT ? 2 : 0;
    S->vert = malloc((nv ? nv : 1) * sizeof *S->vert);
    if (!S->vert)
        return aa_fail(AA_ENOMEM, "out of memory for analytic's plan of the scene");
    S->nvert = 0;
    for (size_t k = 0; k < n; k++)
        if (p[k].kind != AA_PIECE_FLAT) {
            S->vert[S->nvert++] = p[k].xmin;
            S->vert[S->nvert++] = p[k].xmax;
        }
    aa__vis_sort(S->vert, S->nvert);
    size_t m = 0;
    for (size_t k = 0; k < S->nvert; k++)
        if (!m || S->vert[k] != S->vert[m - 1])
            S->vert[m++] = S->vert[k];
    S->nvert = m;
    return AA_OK;
}

/* Which rows the scene lets this path take, and the layers' steps. */
static int plan(an_state *S, const aa_scene *scene, int h)
{
    if (S->plan_scene == scene && S->plan_h == h)
        return AA_OK;
    plan_free(S);
    const an_pp *pp = &S->pp;
    int nl = aa_scene_layer_count(scene), nw = nl > 0 ? nl : 1, st = AA_OK;
    S->slow = calloc((size_t)(h > 0 ? h : 1), 1);
    S->coef = calloc((size_t)nw * 3, sizeof *S->coef);
    S->face = calloc((size_t)nw * 3, sizeof *S->face);
    signed char *sign = calloc((size_t)nw, 1);
    int *wind = calloc((size_t)nw, sizeof *wind);
    void *block = malloc(aa__vis_size(scene, 1));
    aa_strip *strip = aa_strip_new(scene);
    if (!S->slow || !S->coef || !S->face || !sign || !wind || !block || !strip) {
        st = aa_fail(AA_ENOMEM, "out of memory for analytic's plan of the scene");
        goto out;
    }
    if ((st = plan_vert(S, scene)))
        goto out;
    double sx0, sy0, sx1, sy1;
    if (aa_scene_bounds(scene, &sx0, &sy0, &sx1, &sy1)) {
        aa__vis v;
        an_check C = {S, nl, h, 0.0, 0.0, sign};
        const aa__vis_sink sink = {chk_band, NULL, NULL, chk_values, &C, 1, 0, 0, 0};
        aa__vis_bind(&v, scene, 1, block);
        double xl = sx0 - 1.0, xr = sx1 + 1.0;
        double ylo = fmax(0.5 + pp->k[0], sy0 - 1.0), yhi = fmin(h - 0.5 + pp->k[pp->ncell], sy1 + 1.0);
        for (double ya = ylo; ya < yhi; ya += 8.0) {
            double yb = fmin(ya + 8.0, yhi);
            if (aa_strip_begin(strip, ya, yb)) {
                st = aa_fail(AA_ENOMEM, "out of memory for a strip of the scene");
                goto out;
            }
            /* in tiles 8 px wide: the same faces, cut at the tiles' sides,
             * and the meetings sought among the pieces of one tile (across
             * the whole width, a strip of many offset pieces, each band cut
             * at every meeting of any two, took minutes) */
            for (double xa = xl; xa < xr; xa += 8.0) {
                double xb = fmin(xa + 8.0, xr);
                aa_strip_window(strip, xa, xb);
                aa__vis_window(&v, strip, xa, xb, ya, yb, &sink);
            }
        }
    }
    S->bg = aa_scene_colour_of(scene, wind);
    /* one value a piece (nv = 1) when every layer seen has the same step
     * and, of each sign, the same colour: the running sum is then the
     * winding itself; else the three channels and a fourth, the code
     * sum of dir (L + 1), which in a face of layer L is (L + 1) s(L) */
    S->nv = 1;
    int first = -1, seen[2] = {0, 0};
    for (int ch = 0; ch < 3; ch++)
        S->face1[0][ch] = S->face1[1][ch] = S->face1[2][ch] = S->bg.c[ch];
    for (int L = 0; L < nl; L++) {
        if (!sign[L])
            continue;
        wind[L] = sign[L];
        aa_rgb c = aa_scene_colour_of(scene, wind);
        wind[L] = 0;
        memcpy(&S->face[3 * L], c.c, sizeof c.c);
        for (int ch = 0; ch < 3; ch++)
            S->coef[3 * L + ch] = sign[L] * (c.c[ch] - S->bg.c[ch]);
        int sg = sign[L] > 0;
        if (first < 0)
            first = L;
        else if (memcmp(&S->coef[3 * L], &S->coef[3 * first], 3 * sizeof(double)) ||
                 (seen[sg] && memcmp(S->face1[2 * sg], c.c, sizeof c.c)))
            S->nv = AN_NV;
        seen[sg] = 1;
        memcpy(S->face1[2 * sg], c.c, sizeof c.c);
    }
    S->coef1 = (aa_rgb){{0.0, 0.0, 0.0}};
    if (first >= 0)
        memcpy(S->coef1.c, &S->coef[3 * first], sizeof S->coef1.c);
    S->plan_scene = scene;
    S->plan_h = h;
    S->plan_nl = nl;
out:
    aa_strip_free(strip);
    free(block);
    free(wind);
    free(sign);
    if (st)
        plan_free(S);
    return st;
}

/* The rule's size for piece p under a filter of degree n: from the degrees
 * of its y(t) and x(t) (power basis), see "One layer at a time" */
static inline int gauss_points(const aa_piece *p, int n)
{
    int dy = p->dy != 0.0 ? 3 : (p->ay != 0.0 ? 2 : 1);
    int dx = p->dx != 0.0 ? 3 : (p->ax != 0.0 ? 2 : (p->bx != 0.0 ? 1 : 0));
    return (n * dy + (n + 1) * dx + dy - 1) / 2 + 1;
}

/* Capacity of a piece's cuts in one block: the knots' lines it can cross
 * (each x line up to 3 times, a cubic) and its two ends. */
static size_t cut_cap(const an_state *S, int w)
{
    const an_pp *pp = &S->pp;
    double span = pp->k[pp->ncell] - pp->k[0];
    size_t ny = (size_t)S->nph * (size_t)(AN_BLOCK + span + 3.0);
    size_t nx = 3 * (size_t)S->nph * (size_t)(w + span + 3.0);
    return ny + nx + 2;
}

/* A block's buffers: rows j0 - pad .. j1 - 1 + pad, columns -pad .. w +
 * pad, pad = the support's width + 3 (the margins take the terms of
 * supports beyond the image, which the parts below write rather than test
 * for; the running sum starts in the left margin). */
static inline size_t block_cols(const an_state *S, int w)
{
    return (size_t)w + 2 * (size_t)S->pad + 1;
}

static inline size_t block_cells(const an_state *S, int w)
{
    return (size_t)(AN_BLOCK + 2 * S->pad) * block_cols(S, w);
}

static size_t fast_size(const an_state *S, int w)
{
    size_t cells = block_cells(S, w);
    size_t cover = cells * AN_NV * sizeof(double), touched = (cells + 63) & ~(size_t)63;
    size_t scratch = 2 * (size_t)S->pad * AN_MAX_PTS * sizeof(double);
    /* the cuts: 2 cap doubles (cap long doubles for an arc, 16 bytes to align them) */
    /* and the faces' colours of the visible parts' scatter (vis_block) */
    return cover + touched + scratch + 2 * cut_cap(S, w) * sizeof(double) + 16 +
           AN_FACES * 3 * sizeof(double);
}

typedef struct an_block {
    const an_state *S;
    int w, j0, j1, nv;
    double *cover;          /* nv values a cell */
    unsigned char *touched; /* a cell's marks: AN_TERM, AN_CARRY */
    size_t cols;            /* block_cols */
    int pad;
    double *wcol, *arow;    /* pad x AN_MAX_PTS each: W at the columns, a at the rows */
    double *ts;             /* 2 cap: the cuts of y, then of x */
    size_t cap;
    int *uncertain; /* an_render's */
} an_block;

/* the loops of a part's arithmetic, whose counts are constants of the
 * specialised copies, written out in full (-O2 does not) */
#if defined(__GNUC__) && !defined(__clang__)
#define AN_UNROLL _Pragma("GCC unroll 18")
#else
#define AN_UNROLL
#endif

/* floor(x) for |x| < 2^31 */
static inline int ifloor(double x)
{
    int i = (int)x;
    return i - (x < i);
}

/* Whether piece p (a line, quadratic or cubic) has y linear in t and x
 * of degree 2 at most (lines, and quadratics such as crow's arcs): its
 * points then take part_points' short form. */
static inline int piece_lin(const aa_piece *p)
{
    return p->ay == 0.0 && p->dy == 0.0 && p->dx == 0.0;
}

/* The rule's points of the part [t0, t1] of piece p: X, Y and the
 * weight times y' (D); its middle (xm, ym).  Returns 0 if the part lies
 * right of every support (W = 1: no terms), 2 if left of every support
 * (W = 0: the constant part alone, at column 0; X is not set), else 1.
 * (A part lies between two neighbouring knots' lines, and the supports'
 * ends are such lines, so its middle tells.)  lin: piece_lin(p), when
 * the points are aa__piece_point's Horner steps without the terms that
 * are zero, x0 + t (bx + t ax), y0 + t by and y' = by: each dropped step
 * added a zero, so the values are the same. */
__attribute__((always_inline)) static inline int
part_points(const an_block *B, const aa_piece *p, const int m, double t0, double t1, int lin,
            double *X, double *Y, double *D, double *xm, double *ym)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double *gx = S->gx[m], *gw = S->gw[m];
    double hh = 0.5 * (t1 - t0), mid = 0.5 * (t0 + t1), dum;
    if (lin) {
        const double x0 = p->x0, bx = p->bx, ax = p->ax, y0 = p->y0, by = p->by;
        *xm = x0 + mid * (bx + mid * ax), *ym = y0 + mid * by;
        if (!(*xm < B->w - 0.5 + pp->k[pp->ncell]))
            return 0;
        int left = *xm < 0.5 + pp->k[0];
        AN_UNROLL
        for (int g = 0; g < m; g++) {
            double t = mid + hh * gx[g];
            X[g] = x0 + t * (bx + t * ax);
            Y[g] = y0 + t * by;
            D[g] = gw[g] * hh * by;
        }
        return left ? 2 : 1;
    }
    aa__piece_point(p, mid, xm, ym, &dum);
    if (!(*xm < B->w - 0.5 + pp->k[pp->ncell]))
        return 0;
    int left = *xm < 0.5 + pp->k[0];
    for (int g = 0; g < m; g++) {
        double dy;
        aa__piece_point(p, mid + hh * gx[g], &X[g], &Y[g], &dy);
        D[g] = gw[g] * hh * dy;
    }
    return left ? 2 : 1;
}

/* The constant part alone (a part left of every support): A of each row
 * whose support holds it, at column 0. */
__attribute__((always_inline)) static inline void
part_left(const an_block *B, const double *val, const int m, const double *Y, const double *D,
          double ym, const int nv, const int N)
{
    const an_pp *pp = &B->S->pp;
    const double k0 = pp->k[0], kn = pp->k[pp->ncell];
    int jlo = ifloor(ym - 0.5 - kn) + 1, jhi = ifloor(ym - 0.5 - k0);
    if (jlo < B->j0)
        jlo = B->j0;
    if (jhi > B->j1 - 1)
        jhi = B->j1 - 1;
    for (int j = jlo; j <= jhi; j++) {
        double cy = j + 0.5;
        int cell = an_cell(pp, ym - cy);
        const double *b = pp->w[cell];
        double o = cy + pp->k[cell], A = 0.0;
        for (int g = 0; g < m; g++) {
            double u = Y[g] - o, v = b[N];
            for (int q = N - 1; q >= 0; q--)
                v = b[q] + u * v;
            A += D[g] * v;
        }
        size_t row = (size_t)(j - B->j0 + B->pad) * B->cols + (size_t)B->pad;
        double *cov = B->cover + row * nv;
        for (int v = 0; v < nv; v++)
            cov[v] += val[v] * A;
        B->touched[row] |= AN_CARRY;
    }
}

/* The terms of the part [t0, t1] of piece p (inside one cell of every
 * support it meets) in the block's rows, with values val[0 .. nv): any
 * filter. */
__attribute__((always_inline)) static inline void
fast_part(const an_block *B, const double *val, const int m, const double *X, const double *Y,
          const double *D, double xm, double ym, const int nv, const int N)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double k0 = pp->k[0], kn = pp->k[pp->ncell];
    int jlo = ifloor(ym - 0.5 - kn) + 1, jhi = ifloor(ym - 0.5 - k0);
    if (jlo < B->j0)
        jlo = B->j0;
    if (jhi > B->j1 - 1)
        jhi = B->j1 - 1;
    /* the columns whose support holds the part, and W at its points */
    int ilo = ifloor(xm - 0.5 - kn) + 1, ihi = ifloor(xm - 0.5 - k0);
    double *Wc = B->wcol;
    int ncol = ihi - ilo + 1;
    for (int c = 0; c < ncol; c++) {
        double cx = ilo + c + 0.5;
        int cell = an_cell(pp, xm - cx);
        const double *a = pp->cdf[cell];
        double o = cx + pp->k[cell];
        for (int g = 0; g < m; g++) {
            double u = X[g] - o, v = a[N + 1];
            for (int q = N; q >= 0; q--)
                v = a[q] + u * v;
            Wc[c * AN_MAX_PTS + g] = v;
        }
    }
    for (int j = jlo; j <= jhi; j++) {
        double cy = j + 0.5;
        int cell = an_cell(pp, ym - cy);
        const double *b = pp->w[cell];
        double o = cy + pp->k[cell], *a = B->arow, A = 0.0;
        for (int g = 0; g < m; g++) {
            double u = Y[g] - o, v = b[N];
            for (int q = N - 1; q >= 0; q--)
                v = b[q] + u * v;
            a[g] = D[g] * v;
            A += a[g];
        }
        size_t row = (size_t)(j - B->j0 + B->pad) * B->cols + (size_t)B->pad;
        double *cov = B->cover + row * nv;
        unsigned char *tch = B->touched + row;
        for (int v = 0; v < nv; v++)
            cov[(ptrdiff_t)ilo * nv + v] += val[v] * A;
        tch[ilo] |= AN_CARRY, tch[ihi + 1] |= AN_CARRY;
        for (int c = 0; c < ncol; c++) {
            double r = 0.0;
            for (int g = 0; g < m; g++)
                r += a[g] * Wc[c * AN_MAX_PTS + g];
            ptrdiff_t i = ilo + c;
            for (int v = 0; v < nv; v++) {
                cov[i * nv + v] -= val[v] * r;
                cov[(i + 1) * nv + v] += val[v] * r;
            }
            tch[i] |= AN_TERM;
        }
    }
}

/* The same for a regular filter: N + 1 cells of width 1 (box, tent:r=1,
 * the B-splines, Mitchell-Netravali but where its cubic near 0 is even):
 * exactly N + 1 rows and columns hold the part, the first in the last
 * cell, each next one cell to the left, so every count is a constant
 * (rows outside the block and columns outside the image fall in the
 * margins). */

#if AN_SSE2
/* fast_part_regular's arithmetic for N >= 1 in pairs of columns (rows):
 * lane c of a vector is column (row) c, the cell N - c's piece at the
 * same point.  Every value is the scalar version's, operation for
 * operation (Horner's steps, the sums over the points in their order), so
 * the image is the same to the bit; the vectors only do two columns' (or
 * rows') steps at once. */
__attribute__((always_inline)) static inline void
fast_part_regular_sse2(const an_block *B, const double *val, const int m, const double *X,
                       const double *Y, const double *D, double xm, double ym, const int nv,
                       const int N)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double kn = pp->k[pp->ncell];
    const int ns = N + 1, nh = (ns + 1) / 2;
    int jlo = ifloor(ym - 0.5 - kn) + 1, ilo = ifloor(xm - 0.5 - kn) + 1;
    double ox[4], oy[4];
    AN_UNROLL
    for (int c = 0; c < 2 * nh; c++) {
        ox[c] = ilo + c + 0.5 + S->rk[c];
        oy[c] = jlo + c + 0.5 + S->rk[c];
    }
    __m128d Wc[AN_MAX_PTS][2], a[AN_MAX_PTS][2], A[2];
    __m128d vox[2], voy[2];
    AN_UNROLL
    for (int h = 0; h < nh; h++) {
        vox[h] = _mm_loadu_pd(ox + 2 * h);
        voy[h] = _mm_loadu_pd(oy + 2 * h);
        A[h] = _mm_setzero_pd();
    }
    AN_UNROLL
    for (int g = 0; g < m; g++) {
        const __m128d x = _mm_set1_pd(X[g]), y = _mm_set1_pd(Y[g]), d = _mm_set1_pd(D[g]);
        AN_UNROLL
        for (int h = 0; h < nh; h++) {
            __m128d u = _mm_sub_pd(x, vox[h]), v = _mm_load_pd(&S->rcdf[N + 1][2 * h]);
            AN_UNROLL
            for (int e = N; e >= 0; e--)
                v = _mm_add_pd(_mm_load_pd(&S->rcdf[e][2 * h]), _mm_mul_pd(u, v));
            Wc[g][h] = v;
            u = _mm_sub_pd(y, voy[h]);
            v = _mm_load_pd(&S->rw[N][2 * h]);
            AN_UNROLL
            for (int e = N - 1; e >= 0; e--)
                v = _mm_add_pd(_mm_load_pd(&S->rw[e][2 * h]), _mm_mul_pd(u, v));
            a[g][h] = _mm_mul_pd(d, v);
            A[h] = _mm_add_pd(A[h], a[g][h]);
        }
    }
    double As[4];
    _mm_storeu_pd(As, A[0]);
    if (nh > 1)
        _mm_storeu_pd(As + 2, A[1]);
    /* the block's fields in locals: the marks' stores (bytes) may alias them */
    const size_t cols = B->cols;
    double *const cov0 = B->cover + ((size_t)(jlo - B->j0 + B->pad) * cols + (size_t)B->pad) * nv;
    unsigned char *const tch0 = B->touched + (size_t)(jlo - B->j0 + B->pad) * cols + (size_t)B->pad;
    AN_UNROLL
    for (int r = 0; r < ns; r++) {
        /* the row's products with the columns: x[c] = sum_g a[r][g] W[c][g] */
        __m128d x0 = _mm_setzero_pd(), x1 = _mm_setzero_pd();
        AN_UNROLL
        for (int g = 0; g < m; g++) {
            __m128d ar = (r & 1) ? _mm_unpackhi_pd(a[g][r >> 1], a[g][r >> 1])
                                 : _mm_unpacklo_pd(a[g][r >> 1], a[g][r >> 1]);
            x0 = _mm_add_pd(x0, _mm_mul_pd(ar, Wc[g][0]));
            if (nh > 1)
                x1 = _mm_add_pd(x1, _mm_mul_pd(ar, Wc[g][1]));
        }
        /* the row's differences d[c] = x[c-1] - x[c] (x[-1] = A, x[ns] =
         * 0: d[ns] = x[ns-1]), two at a time: d01 = (A, x0) - (x0, x1),
         * d23 = (x1, x2) - (x2, x3) (for ns = 3 x3 = 0, its cells' zero
         * coefficients: x2 - 0 = x2) */
        const __m128d d01 = _mm_sub_pd(_mm_unpacklo_pd(_mm_set_sd(As[r]), x0), x0);
        const __m128d d23 = _mm_sub_pd(_mm_shuffle_pd(x0, x1, 1), x1);
        double *cov = cov0 + (size_t)r * cols * nv;
        unsigned char *tch = tch0 + (size_t)r * cols;
        if (nv == 1) {
            /* cov[ilo + c] += val d[c], two cells at a time */
            const __m128d vv = _mm_set1_pd(val[0]);
            double *c0 = cov + ilo;
            _mm_storeu_pd(c0, _mm_add_pd(_mm_loadu_pd(c0), _mm_mul_pd(vv, d01)));
            if (ns == 2)
                c0[2] += val[0] * _mm_cvtsd_f64(_mm_unpackhi_pd(x0, x0));
            else {
                _mm_storeu_pd(c0 + 2, _mm_add_pd(_mm_loadu_pd(c0 + 2), _mm_mul_pd(vv, d23)));
                if (ns == 4)
                    c0[4] += val[0] * _mm_cvtsd_f64(_mm_unpackhi_pd(x1, x1));
            }
        } else {
            double d[5];
            _mm_storeu_pd(d, d01);
            if (ns == 2)
                _mm_storeh_pd(d + 2, x0);
            else {
                _mm_storeu_pd(d + 2, d23);
                if (ns == 4)
                    _mm_storeh_pd(d + 4, x1);
            }
            AN_UNROLL
            for (int c = 0; c <= ns; c++)
                AN_UNROLL
                for (int v = 0; v < nv; v++)
                    cov[(ptrdiff_t)(ilo + c) * nv + v] += val[v] * d[c];
        }
        /* the marks: AN_TERM at the ns columns, AN_CARRY after them */
        uint32_t m4, t4 = ns == 2   ? AN_TERM * 0x0101u + AN_CARRY * 0x10000u
                          : ns == 3 ? AN_TERM * 0x010101u + AN_CARRY * 0x1000000u
                                    : AN_TERM * 0x01010101u;
        memcpy(&m4, tch + ilo, sizeof m4);
        m4 |= t4;
        memcpy(tch + ilo, &m4, sizeof m4);
        if (ns == 4)
            tch[ilo + 4] |= AN_CARRY;
    }
}
#endif

__attribute__((always_inline)) static inline void
fast_part_regular(const an_block *B, const double *val, const int m, const double *X,
                  const double *Y, const double *D, double xm, double ym, const int nv,
                  const int N)
{
#if AN_SSE2
    if (N >= 1) {
        fast_part_regular_sse2(B, val, m, X, Y, D, xm, ym, nv, N);
        return;
    }
#endif
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double k0 = pp->k[0], kn = pp->k[pp->ncell];
    (void)k0;
    const int ns = N + 1;
    int jlo = ifloor(ym - 0.5 - kn) + 1, ilo = ifloor(xm - 0.5 - kn) + 1;
    double Wc[4][AN_MAX_PTS], a[4][AN_MAX_PTS], A[4];
    for (int c = 0; c < ns; c++) {
        const double *q = pp->cdf[ns - 1 - c];
        double o = ilo + c + 0.5 + pp->k[ns - 1 - c];
        for (int g = 0; g < m; g++) {
            double u = X[g] - o, v = q[N + 1];
            for (int e = N; e >= 0; e--)
                v = q[e] + u * v;
            Wc[c][g] = v;
        }
    }
    for (int r = 0; r < ns; r++) {
        const double *q = pp->w[ns - 1 - r];
        double o = jlo + r + 0.5 + pp->k[ns - 1 - r], s = 0.0;
        for (int g = 0; g < m; g++) {
            double u = Y[g] - o, v = q[N];
            for (int e = N - 1; e >= 0; e--)
                v = q[e] + u * v;
            a[r][g] = D[g] * v;
            s += a[r][g];
        }
        A[r] = s;
    }
    for (int r = 0; r < ns; r++) {
        size_t row = (size_t)(jlo + r - B->j0 + B->pad) * B->cols + (size_t)B->pad;
        double *cov = B->cover + row * nv;
        unsigned char *tch = B->touched + row;
        double d[5];
        d[0] = A[r];
        for (int c = 0; c < ns; c++) {
            double x = 0.0;
            for (int g = 0; g < m; g++)
                x += a[r][g] * Wc[c][g];
            d[c] -= x;
            d[c + 1] = x;
        }
        for (int c = 0; c <= ns; c++)
            for (int v = 0; v < nv; v++)
                cov[(ptrdiff_t)(ilo + c) * nv + v] += val[v] * d[c];
        for (int c = 0; c < ns; c++)
            tch[ilo + c] |= AN_TERM;
        tch[ilo + ns] |= AN_CARRY;
    }
}

/* The terms of a part from its rule's points (part_points, arc_points):
 * where 0, none; 2, the constant part alone; else by the filter's cells. */
__attribute__((always_inline)) static inline void
fast_terms(const an_block *B, const double *val, const int m, const double *X, const double *Y,
           const double *D, double xm, double ym, int where, const int nv, const int N)
{
    if (where == 2)
        part_left(B, val, m, Y, D, ym, nv, N);
    else if (where == 1 && B->S->regular)
        fast_part_regular(B, val, m, X, Y, D, xm, ym, nv, N);
    else if (where == 1)
        fast_part(B, val, m, X, Y, D, xm, ym, nv, N);
}

/* The parts of a polynomial piece between its cuts, ty (the horizontal
 * knots' lines' and both ends, ascending) and tx (the vertical ones',
 * ascending, between the ends), merged in order of t, each part's points
 * and terms: in one function a piece, whose loop holds the part's
 * arithmetic. */
__attribute__((always_inline)) static inline void
piece_parts(const an_block *B, const aa_piece *p, const double *val, const double *ty, size_t ny,
           const double *tx, size_t nx, int lin, const int M, const int nv, const int N)
{
    /* the block's fields in a local copy: the byte stores of the marks
     * cannot alias it, so they are not read again for every part */
    const an_block Bl = *B;
    B = &Bl;
    double prev = ty[0];
    size_t iy = 1, ix = 0;
    while (iy < ny) {
        double t = ix < nx && tx[ix] < ty[iy] ? tx[ix++] : ty[iy++];
        if (!(prev < t))
            continue;
        double X[AN_MAX_PTS], Y[AN_MAX_PTS], D[AN_MAX_PTS], xm, ym;
        int where = part_points(B, p, M, prev, t, lin, X, Y, D, &xm, &ym);
        fast_terms(B, val, M, X, Y, D, xm, ym, where, nv, N);
        prev = t;
    }
}

typedef void an_part_fn(const an_block *B, const aa_piece *p, const double *val,
                        const double *ty, size_t ny, const double *tx, size_t nx, int lin);
typedef void an_arc_fn(const an_block *B, const aa_piece *p, const double *val,
                       long double sa, long double sb);

/* AN_SPECIALIZE 1 (the default): a part of a polynomial piece with its
 * rule's size and the values' count constants, one function for each
 * filter degree and rule, and an arc's part one for each degree (the
 * loops unrolled by the compiler; the rows per degree below).  0: one
 * function for each kind, the same code with the sizes as arguments.  The
 * sanitizer build uses 0 (Makefile): the unrolled copies took about a
 * minute of CPU to compile under the sanitizers, a quarter of that
 * build's compiling, for speed it does not need; every statement of
 * fast_part and fast_part_regular runs there all the same. */
#ifndef AN_SPECIALIZE
#define AN_SPECIALIZE 1
#endif

/* AN_CLONES: each specialised copy compiled twice, for the processor's
 * AVX2 (its SSE2 operations in the VEX encoding, three operands, so fewer
 * register copies; no FMA: the same operations, the same values) and for
 * any x86-64, the one taken chosen once at load (GCC's target_clones) */
#if AN_SSE2 && defined(__GNUC__) && !defined(__clang__) && defined(__linux__)
#define AN_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define AN_CLONES
#endif

#if AN_SPECIALIZE
#define AN_PART(N, M)                                                               \
    AN_CLONES static void fast_part_##N##_##M(const an_block *B, const aa_piece *p, const double *val, \
                                    const double *ty, size_t ny, const double *tx,  \
                                    size_t nx, int lin)                             \
    {                                                                               \
        if (B->nv == 1)                                                             \
            piece_parts(B, p, val, ty, ny, tx, nx, lin, M, 1, N);                    \
        else                                                                        \
            piece_parts(B, p, val, ty, ny, tx, nx, lin, M, AN_NV, N);                \
    }
#define AN_PARTS(N)                                                                 \
    AN_PART(N, 1)                                                                   \
    AN_PART(N, 2)                                                                   \
    AN_PART(N, 3)                                                                   \
    AN_PART(N, 4)                                                                   \
    AN_PART(N, 5)                                                                   \
    AN_PART(N, 6)                                                                   \
    AN_PART(N, 7)                                                                   \
    AN_PART(N, 8)                                                                   \
    AN_PART(N, 9)                                                                   \
    AN_PART(N, 10)                                                                  \
    AN_PART(N, 11)                                                                  \
    AN_PART(N, 12)
AN_PARTS(0)
AN_PARTS(1)
AN_PARTS(2)
AN_PARTS(3)
#undef AN_PARTS
#undef AN_PART

#define AN_ROW(N)                                                                   \
    {NULL,                fast_part_##N##_1,  fast_part_##N##_2, fast_part_##N##_3,  \
     fast_part_##N##_4,   fast_part_##N##_5,  fast_part_##N##_6, fast_part_##N##_7,  \
     fast_part_##N##_8,   fast_part_##N##_9,  fast_part_##N##_10, fast_part_##N##_11, \
     fast_part_##N##_12}
/* [filter degree][rule's points] */
static an_part_fn *const fast_parts[4][AN_MAX_GAUSS + 1] = {AN_ROW(0), AN_ROW(1), AN_ROW(2),
                                                            AN_ROW(3)};
#undef AN_ROW

/* An arc's part by its rule (2 arc_m = 4 N + 6 points), N the filter's
 * degree and the values' count constants */
#define AN_ARC(N)                                                                   \
    static void fast_arc_##N(const an_block *B, const aa_piece *p, const double *val,  \
                             long double sa, long double sb)                        \
    {                                                                               \
        const an_pp *pp = &B->S->pp;                                                \
        double X[AN_MAX_PTS], Y[AN_MAX_PTS], D[AN_MAX_PTS], xm, ym;                 \
        arc_points(B->S, p, sa, sb, X, Y, D, &xm, &ym);                             \
        int where = !(xm < B->w - 0.5 + pp->k[pp->ncell]) ? 0                       \
                    : (xm < 0.5 + pp->k[0] ? 2 : 1);                                \
        if (B->nv == 1)                                                             \
            fast_terms(B, val, 4 * N + 6, X, Y, D, xm, ym, where, 1, N);            \
        else                                                                        \
            fast_terms(B, val, 4 * N + 6, X, Y, D, xm, ym, where, AN_NV, N);        \
    }
AN_ARC(0)
AN_ARC(1)
AN_ARC(2)
AN_ARC(3)
#undef AN_ARC

static an_arc_fn *const fast_arcs[4] = {fast_arc_0, fast_arc_1, fast_arc_2, fast_arc_3};
#define AN_PART_FOR(deg, m) fast_parts[deg][m]
#define AN_ARC_FOR(deg) fast_arcs[deg]
#else
/* The sizes from the block and the piece, as the tables are indexed. */
static void fast_part_any(const an_block *B, const aa_piece *p, const double *val,
                          const double *ty, size_t ny, const double *tx, size_t nx, int lin)
{
    const int N = B->S->pp.deg, M = gauss_points(p, N);
    piece_parts(B, p, val, ty, ny, tx, nx, lin, M, B->nv == 1 ? 1 : AN_NV, N);
}

static void fast_arc_any(const an_block *B, const aa_piece *p, const double *val,
                         long double sa, long double sb)
{
    const an_pp *pp = &B->S->pp;
    const int N = pp->deg;
    double X[AN_MAX_PTS], Y[AN_MAX_PTS], D[AN_MAX_PTS], xm, ym;
    arc_points(B->S, p, sa, sb, X, Y, D, &xm, &ym);
    int where = !(xm < B->w - 0.5 + pp->k[pp->ncell]) ? 0 : (xm < 0.5 + pp->k[0] ? 2 : 1);
    fast_terms(B, val, 4 * N + 6, X, Y, D, xm, ym, where, B->nv == 1 ? 1 : AN_NV, N);
}
#define AN_PART_FOR(deg, m) ((void)(m), fast_part_any)
#define AN_ARC_FOR(deg) ((void)(deg), fast_arc_any)
#endif


/* The terms of conic piece p in the block's rows: cut at the knots' lines
 * in angle (long double, see "Elliptical arcs"), sorted, each part (split
 * to om <= pi/3) by the arc's rule. */
static void fast_conic(const an_block *B, const aa_piece *p, const double *val, double lo,
                       double hi)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double XA = 0.5 + pp->k[0], XB = B->w - 0.5 + pp->k[pp->ncell];
    /* the cuts, in the cut buffer (2 cap doubles: room for cap long
     * doubles, aligned) */
    long double *ts = (long double *)(((uintptr_t)B->ts + 15) & ~(uintptr_t)15);
    size_t n = 0;
    long double sa = arc_angle(p, lo), sb = arc_angle(p, hi);
    ts[n++] = sa;
    for (double base = floor(lo); base <= hi; base += 1.0)
        for (int q = 0; q < S->nph; q++) {
            double Yk = base + S->ph[q];
            if (Yk > lo && Yk < hi)
                ts[n++] = arc_angle(p, Yk);
        }
    ts[n++] = sb;
    double xa, xb;
    aa_piece_xrange(p, lo, hi, &xa, &xb);
    /* widened: the extent is the double one; a line that misses gives no cut */
    xa -= 1e-9 * (1.0 + fabs(xa)), xb += 1e-9 * (1.0 + fabs(xb));
    double ca = fmax(xa, XA), cb = fmin(xb, XB);
    long double R = hypotl(p->ea, p->eb), ang = atan2l(p->eb, p->ea);
    for (double base = floor(ca); base <= cb; base += 1.0)
        for (int q = 0; q < S->nph; q++) {
            double X = base + S->ph[q];
            if (X >= XA && X <= XB && X >= xa && X <= xb)
                n += (size_t)arc_meet_x(p, R, ang, X, sa, sb, ts + n);
        }
    qsort(ts, n, sizeof *ts, cmp_ld);
    an_arc_fn *part = AN_ARC_FOR(pp->deg);
    for (size_t i = 0; i + 1 < n; i++) {
        if (!(ts[i] < ts[i + 1]))
            continue;
        int ns = arc_splits(ts[i], ts[i + 1]);
        for (int r = 0; r < ns; r++) {
            long double a = ts[i] + (ts[i + 1] - ts[i]) * r / ns,
                        b = r + 1 == ns ? ts[i + 1] : ts[i] + (ts[i + 1] - ts[i]) * (r + 1) / ns;
            part(B, p, val, a, b);
        }
    }
}

/* fast_terms with the filter's degree and the values' count constants (the
 * rule's size varies from part to part, so the general fast_part: the
 * regular filters' copies are unrolled for a constant size) */
#define AN_OFF_TERMS(N)                                                              \
    static void off_terms_##N(const an_block *B, const double *val, int m, const double *X, \
                              const double *Y, const double *D, double xm, double ym,   \
                              int where)                                             \
    {                                                                                \
        const int nv = B->nv == 1 ? 1 : AN_NV;                                       \
        if (where == 2 && nv == 1)                                                   \
            part_left(B, val, m, Y, D, ym, 1, N);                                    \
        else if (where == 2)                                                         \
            part_left(B, val, m, Y, D, ym, AN_NV, N);                                \
        else if (nv == 1)                                                            \
            fast_part(B, val, m, X, Y, D, xm, ym, 1, N);                             \
        else                                                                         \
            fast_part(B, val, m, X, Y, D, xm, ym, AN_NV, N);                         \
    }
AN_OFF_TERMS(0)
AN_OFF_TERMS(1)
AN_OFF_TERMS(2)
AN_OFF_TERMS(3)
#undef AN_OFF_TERMS

static void off_terms(const an_block *B, const double *val, int m, const double *X,
                      const double *Y, const double *D, double xm, double ym, int where)
{
    static void (*const fn[4])(const an_block *, const double *, int, const double *,
                               const double *, const double *, double, double,
                               int) = {off_terms_0, off_terms_1, off_terms_2, off_terms_3};
    fn[B->S->pp.deg](B, val, m, X, Y, D, xm, ym, where);
}

/* The terms of the part [u, v] (u < v) of offset piece p, inside one cell
 * of every support it meets, by its certified rule (halved where none
 * is); sg: the sign of the piece's direction in the parameter. */
static void fast_off_part(const an_block *B, const aa_piece *p, int stops, const double *val,
                          double u, double v, double sg, int depth)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    int m = off_points(S, p, u, v);
    if (!m) {
        double mid = 0.5 * (u + v);
        if (depth < AN_OFF_DEPTH && mid > u && mid < v) {
            fast_off_part(B, p, stops, val, u, mid, sg, depth + 1);
            fast_off_part(B, p, stops, val, mid, v, sg, depth + 1);
            return;
        }
        off_uncertain(B->uncertain, 1);
        m = AN_MAX_PTS;
    }
    double X[AN_MAX_PTS], Y[AN_MAX_PTS], D[AN_MAX_PTS], xm, ym, dy;
    double h = 0.5 * (v - u), mid = 0.5 * (u + v);
    off_point(p, stops, mid, &xm, &ym, &dy);
    int where = !(xm < B->w - 0.5 + pp->k[pp->ncell]) ? 0 : (xm < 0.5 + pp->k[0] ? 2 : 1);
    if (!where)
        return;
    for (int g = 0; g < m; g++) {
        off_point(p, stops, mid + h * S->ogx[m][g], &X[g], &Y[g], &dy);
        D[g] = sg * S->ogw[m][g] * h * dy;
    }
    off_terms(B, val, m, X, Y, D, xm, ym, where);
}

/* The terms of offset piece p in the block's rows [lo, hi]: cut at the
 * knots' lines (y: every line in the rows; x: on each part between x's
 * turns, every line the part crosses in the supports' span) and at t =
 * 1/2 where the curve has a stop, sorted in the parameter. */
static void fast_offset(const an_block *B, const aa_piece *p, const double *val, double lo,
                        double hi)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double XA = 0.5 + pp->k[0], XB = B->w - 0.5 + pp->k[pp->ncell];
    int stops = aa__offset_stops(&p->oc);
    double ta = off_t_at(p, lo), tb = off_t_at(p, hi), a = fmin(ta, tb), b = fmax(ta, tb);
    if (!(a < b))
        return;
    double *ts = B->ts, tbd[4], xbd[4];
    size_t n = 0;
    ts[n++] = a;
    ts[n++] = b;
    if (stops && 0.5 > a && 0.5 < b)
        ts[n++] = 0.5;
    for (double base = floor(lo); base <= hi; base += 1.0)
        for (int q = 0; q < S->nph; q++) {
            double Y = base + S->ph[q];
            if (Y > lo && Y < hi)
                ts[n++] = off_t_at(p, Y);
        }
    int nm = off_monotone(p, stops, a, b, tbd, xbd);
    for (int k = 0; k < nm; k++) {
        double xa = fmin(xbd[k], xbd[k + 1]), xb = fmax(xbd[k], xbd[k + 1]);
        double ca = fmax(xa, XA), cb = fmin(xb, XB);
        for (double base = floor(ca); base <= cb; base += 1.0)
            for (int q = 0; q < S->nph; q++) {
                double X = base + S->ph[q];
                if (X > xa && X < xb && X >= XA && X <= XB)
                    ts[n++] = aa__offset_solve_d(&p->oc, 0, tbd[k], tbd[k + 1], xbd[k] - X, X);
            }
    }
    aa__vis_sort(ts, n);
    double sg = ta < tb ? 1.0 : -1.0;
    for (size_t i = 0; i + 1 < n; i++)
        if (ts[i] < ts[i + 1])
            fast_off_part(B, p, stops, val, ts[i], ts[i + 1], sg, 0);
}

/* The root in [a, b] of f(t) = c + t (k1 + t (k2 + t k3)), increasing
 * there from a non-positive value to a non-negative one, from a guess t
 * near it, to 2^-54 of the root (area_cubic_newton: Newton's steps while
 * they stay in [a, b] and shrink, their error bounded over the whole
 * step; from the neighbouring line's root, a test reading f'' at the
 * step's start alone took a step of 1e-2 from where f'' vanishes, as on
 * the half of a symmetric arc, and left 1e-9 px). */
static inline double cubic_near(double c, double k1, double k2, double k3, double a, double b,
                                double t)
{
    return area_cubic_newton(c, k1, k2, k3, a, b, t, 0.0);
}

/* The cuts of cubic piece p over its rows [lo, hi] (ta, tb its parameters
 * there): ty[1 ..] the lines of y between, then tb; tx the lines of x
 * (XA <= X <= XB), ascending.  Each parameter is the root of a monotone
 * cubic found by Newton's method from the neighbouring cut's (cubic_near:
 * y rises along the piece, so the line above's root is a bracket's end
 * and the guess; a line of x, on each part between x's turns, from the
 * neighbouring line's root): on curves.svg under tent:r=1 at 1024x1024
 * about 170 instructions a root, where aa_piece_t_at's bracketed search
 * from [0, 1] took about 550.  The lines of x are solved in x directly,
 * not for a height (aa_piece_meet_x) and then for its parameter again,
 * and found in order of t, so not sorted. */
static void cubic_cuts(const an_state *S, const aa_piece *p, double lo, double hi, double ta,
                       double tb, double XA, double XB, double *ty, size_t *ny, double *tx,
                       size_t *nx)
{
    const double y0 = p->y0, by = p->by, ay = p->ay, dy = p->dy;
    double tp = ta;
    for (double base = floor(lo); base <= hi; base += 1.0)
        for (int q = 0; q < S->nph; q++) {
            double Y = base + S->ph[q];
            if (Y > lo && Y < hi)
                ty[(*ny)++] = tp = cubic_near(y0 - Y, by, ay, dy, tp, tb, tp);
        }
    ty[(*ny)++] = tb;
    /* x's turns inside (ta, tb) cut it into monotone parts */
    double u[4], r[2];
    int nu = 0;
    u[nu++] = ta;
    int nr = gsl_poly_solve_quadratic(3.0 * p->dx, 2.0 * p->ax, p->bx, &r[0], &r[1]);
    for (int k = 0; k < nr; k++)
        if (r[k] > u[nu - 1] && r[k] < tb)
            u[nu++] = r[k];
    u[nu++] = tb;
    const double x0 = p->x0, bx = p->bx, ax = p->ax, dx = p->dx;
    double xu = x0 + ta * (bx + ta * (ax + ta * dx));
    for (int k = 0; k + 1 < nu; k++) {
        double a = u[k], b = u[k + 1], xv = x0 + b * (bx + b * (ax + b * dx));
        double xa = fmin(xu, xv), xb = fmax(xu, xv), ca = fmax(xa, XA), cb = fmin(xb, XB);
        int up = xv > xu;
        size_t first = *nx;
        /* the lines in ascending X: rising x from a (each root above the
         * last), falling x from b (each below the last) */
        double tn = up ? a : b;
        for (double base = floor(ca); base <= cb; base += 1.0)
            for (int q = 0; q < S->nph; q++) {
                double X = base + S->ph[q];
                if (!(X > xa && X < xb && X >= XA && X <= XB))
                    continue;
                tn = up ? cubic_near(x0 - X, bx, ax, dx, tn, b, tn)
                        : cubic_near(X - x0, -bx, -ax, -dx, a, tn, tn);
                tx[(*nx)++] = tn;
            }
        if (!up) /* descending in t: reversed */
            for (size_t i = first, j = *nx ? *nx - 1 : 0; i < j; i++, j--) {
                double t = tx[i];
                tx[i] = tx[j], tx[j] = t;
            }
        xu = xv;
    }
}

/* The terms of piece p (values val[0 .. nv)) over rows [ya, yb] (a visible
 * part's; the whole piece's, p->y0 and p->y1, on the scatter's rows) in the
 * block's rows: cut at the knots' lines, in order of t (the lines of y in
 * order, those of x sorted apart and merged; a cubic's found in order,
 * cubic_cuts). */
static void fast_piece(const an_block *B, const aa_piece *p, const double *val, double ya,
                       double yb)
{
    const an_state *S = B->S;
    const an_pp *pp = &S->pp;
    const double k0 = pp->k[0], kn = pp->k[pp->ncell];
    const int w = B->w;
    const double Y0 = B->j0 + 0.5 + k0, Y1 = (B->j1 - 1) + 0.5 + kn;
    const double XA = 0.5 + k0, XB = w - 0.5 + kn;
    double lo = fmax(fmax(p->y0, ya), Y0), hi = fmin(fmin(p->y1, yb), Y1);
    if (!(lo < hi))
        return;
    if (p->kind == AA_PIECE_CONIC) {
        fast_conic(B, p, val, lo, hi);
        return;
    }
    if (p->kind == AA_PIECE_OFFSET) {
        fast_offset(B, p, val, lo, hi);
        return;
    }
    double *ty = B->ts, *tx = B->ts + B->cap;
    size_t ny = 0, nx = 0;
    double ta = lo <= p->y0 ? 0.0 : aa_piece_t_at(p, lo);
    double tb = hi >= p->y1 ? 1.0 : aa_piece_t_at(p, hi);
    ty[ny++] = ta;
    const int lin = piece_lin(p);
    if (p->kind == AA_PIECE_CUBIC) {
        cubic_cuts(S, p, lo, hi, ta, tb, XA, XB, ty, &ny, tx, &nx);
        AN_PART_FOR(pp->deg, gauss_points(p, pp->deg))(B, p, val, ty, ny, tx, nx, lin);
        return;
    }
    if (lin) {
        /* aa_piece_t_at's steps for y linear in t, inline */
        const double y0 = p->y0, y1 = p->y1, by = p->by;
        for (double base = floor(lo); base <= hi; base += 1.0)
            for (int q = 0; q < S->nph; q++) {
                double Y = base + S->ph[q], d = Y - y0, t;
                if (!(Y > lo && Y < hi))
                    continue;
                if (!(d > 0.0))
                    t = 0.0;
                else if (Y >= y1)
                    t = 1.0;
                else
                    t = d / by, t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
                ty[ny++] = t;
            }
    } else
        for (double base = floor(lo); base <= hi; base += 1.0)
            for (int q = 0; q < S->nph; q++) {
                double Y = base + S->ph[q];
                if (Y > lo && Y < hi)
                    ty[ny++] = aa_piece_t_at(p, Y);
            }
    ty[ny++] = tb;
    double xa, xb;
    aa_piece_xrange(p, lo, hi, &xa, &xb);
    double ca = fmax(xa, XA), cb = fmin(xb, XB);
    int line = p->kind == AA_PIECE_LINE;
    for (double base = floor(ca); base <= cb; base += 1.0)
        for (int q = 0; q < S->nph; q++) {
            double X = base + S->ph[q];
            if (!(X > xa && X < xb && X >= XA && X <= XB))
                continue;
            if (line) {
                double t = (X - p->x0) / p->bx;
                if (t > ta && t < tb)
                    tx[nx++] = t;
                continue;
            }
            double ys[3];
            int c = aa_piece_meet_x(p, X, ys);
            for (int r = 0; r < c; r++)
                if (ys[r] > lo && ys[r] < hi)
                    tx[nx++] = aa_piece_t_at(p, ys[r]);
        }
    if (line && p->bx < 0.0) /* descending in X: ascending reversed */
        for (size_t a = 0, b = nx ? nx - 1 : 0; a < b; a++, b--) {
            double t = tx[a];
            tx[a] = tx[b], tx[b] = t;
        }
    else if (!line)
        aa__vis_sort(tx, nx);
    /* ty holds both ends: every cut of tx lies between its first and last */
    AN_PART_FOR(pp->deg, gauss_points(p, pp->deg))(B, p, val, ty, ny, tx, nx, lin);
}

/* a + b, and its rounding error added to *e (Knuth's TwoSum) */
static inline double two_sum(double a, double b, double *e)
{
    double s = a + b, bb = s - a;
    *e += (a - (s - bb)) + (b - bb);
    return s;
}

/* The scatter's buffers of rows j0 .. j1-1 in the worker's scratch, for
 * nv values a cell. */
static an_block block_bind(const an_state *S, aa__sampler_worker *wk, int w, int j0, int j1,
                           int nv)
{
    const size_t cols = block_cols(S, w), cells = block_cells(S, w);
    char *own = (char *)wk->own + S->fast_off;
    an_block B = {S, w, j0, j1, nv, NULL, NULL, cols, S->pad, NULL, NULL, NULL, 0, NULL};
    B.cover = (double *)own;
    own += cells * AN_NV * sizeof(double);
    B.touched = (unsigned char *)own;
    own += (cells + 63) & ~(size_t)63;
    B.wcol = (double *)own;
    B.arow = B.wcol + (size_t)S->pad * AN_MAX_PTS;
    own += 2 * (size_t)S->pad * AN_MAX_PTS * sizeof(double);
    B.ts = (double *)own;
    B.cap = cut_cap(S, w);
    return B;
}

/* A flat piece has no terms, but the pixels whose supports it crosses are
 * not inside one face: marked, as the parts mark theirs. */
static void mark_flat(const an_block *B, const aa_piece *p)
{
    const an_pp *pp = &B->S->pp;
    const double k0 = pp->k[0], kn = pp->k[pp->ncell];
    const int w = B->w, pad = B->pad, j0 = B->j0, j1 = B->j1;
    if (!(p->y0 >= B->j0 + 0.5 + k0 && p->y0 <= (B->j1 - 1) + 0.5 + kn))
        return;
    /* rows and columns whose closed supports meet it: ceil, floor */
    int ja = -ifloor(-(p->y0 - 0.5 - kn)), jb = ifloor(p->y0 - 0.5 - k0);
    double xa = fmax(p->xmin, -2.0 * pad), xb = fmin(p->xmax, w + 2.0 * pad);
    int ia = -ifloor(-(xa - 0.5 - kn)), ib = ifloor(xb - 0.5 - k0);
    ja = ja < j0 ? j0 : ja, jb = jb > j1 - 1 ? j1 - 1 : jb;
    ia = ia < 0 ? 0 : ia, ib = ib > w - 1 ? w - 1 : ib;
    for (int j = ja; j <= jb; j++)
        if (ia <= ib)
            memset(B->touched + (size_t)(j - j0 + pad) * B->cols + (size_t)(pad + ia), AN_TERM,
                   (size_t)(ib - ia + 1));
}

/* Pixel i, unmarked, and the unmarked pixels after it take face colour f
 * (their cells hold nothing: the running sums stay as they are), eight
 * marks tested at a time; *px and *cov moved past them.  Returns the next
 * marked pixel's index (or w). */
static inline int fill_face(double **px, double **cov, const unsigned char *t, int i, int w,
                            const double *f)
{
    double *p = *px, *c = *cov;
    do {
        memcpy(p, f, 3 * sizeof *p);
        i++, p += 3, c += AN_NV;
        uint64_t t8;
        while (w - i >= 8 && (memcpy(&t8, t + i, sizeof t8), !t8)) {
            for (int e = 0; e < 8; e++, p += 3)
                memcpy(p, f, 3 * sizeof *p);
            i += 8, c += 8 * AN_NV;
        }
    } while (i < w && !t[i]);
    *px = p, *cov = c;
    return i;
}

/* The buffers' rows (ra .. rb, from the block's first margin row) that
 * hold terms of parts with y in [Y0, Y1], and marks of flat pieces there:
 * a part's rows are those whose supports hold its middle (ym, within
 * rounding of [Y0, Y1]: one row more each way), clipped to the block's
 * rows but by the regular filters' parts, which write their N + 1 rows
 * into the margins.  The other rows are left as every block leaves the
 * rows it wrote, zero, and neither read nor cleared. */
static void term_rows(const an_block *B, double Y0, double Y1, int *ra, int *rb)
{
    const an_pp *pp = &B->S->pp;
    const int base = B->j0 - B->pad, last = AN_BLOCK + 2 * B->pad - 1;
    int a = ifloor(Y0 - 0.5 - pp->k[pp->ncell]) - base, b = ifloor(Y1 - 0.5 - pp->k[0]) + 1 - base;
    *ra = a < 0 ? 0 : a;
    *rb = b > last ? last : b;
}

/* A row of the buffers whose values are not wanted, cleared: every cell a
 * part or flat piece wrote is marked (a part marks each cell of its terms,
 * AN_TERM, and those it carries into, AN_CARRY), so only the marked cells
 * are zeroed, eight marks tested at a time, and the marks (a row of the
 * margins holds a few parts' terms, where clearing all its cells stored
 * some 33 kB at 1024 px wide with four values a cell). */
static void clear_row(double *cov, unsigned char *tch, size_t cols, int nv)
{
    size_t i = 0;
    for (; i + 8 <= cols; i += 8) {
        uint64_t t8;
        memcpy(&t8, tch + i, sizeof t8);
        if (t8)
            for (size_t e = i; e < i + 8; e++)
                if (tch[e])
                    memset(cov + e * (size_t)nv, 0, (size_t)nv * sizeof *cov);
    }
    for (; i < cols; i++)
        if (tch[i])
            memset(cov + i * (size_t)nv, 0, (size_t)nv * sizeof *cov);
    memset(tch, 0, cols);
}

/* Rows j0 .. j1-1 (those not marked slow) by the scatter. */
static int fast_block(const an_render *R, aa__sampler_worker *wk, int j0, int j1, aa_image *out,
                      uint64_t *expensive)
{
    const an_state *S = R->S;
    const an_pp *pp = &S->pp;
    const int w = out->w, nv = S->nv;
    const int pad = S->pad;
    const size_t cols = block_cols(S, w);
    an_block B = block_bind(S, wk, w, j0, j1, nv);
    B.uncertain = R->uncertain;
    /* the rows of the supports of this path's rows (the first and last
     * not marked slow, and those between): no part outside them has a
     * term there */
    int fa = j0, fb = j1 - 1;
    while (S->slow[fa])
        fa++;
    while (S->slow[fb])
        fb--;
    double Y0 = fa + 0.5 + pp->k[0], Y1 = fb + 0.5 + pp->k[pp->ncell];
    double sx0, sy0, sx1, sy1;
    aa_scene_bounds(R->scene, &sx0, &sy0, &sx1, &sy1);
    if (aa_strip_begin(wk->strip, Y0, Y1))
        return 1;
    aa_strip_window(wk->strip, fmin(sx0, 0.0) - 1.0, w - 0.5 + pp->k[pp->ncell]);
    size_t nloc;
    const aa_piece *const *loc = aa_strip_local(wk->strip, &nloc);
    for (size_t q = 0; q < nloc; q++) {
        const aa_piece *p = loc[q];
        const double *cf = &S->coef[3 * p->layer];
        if (cf[0] == 0.0 && cf[1] == 0.0 && cf[2] == 0.0)
            continue; /* no step (its faces are the background's colour) */
        if (!p->dir) {
            if (p->y0 >= Y0 && p->y0 <= Y1)
                mark_flat(&B, p);
            continue;
        }
        double val[AN_NV];
        if (nv == 1)
            val[0] = p->dir;
        else {
            for (int v = 0; v < 3; v++)
                val[v] = p->dir * cf[v];
            val[3] = p->dir * (p->layer + 1.0);
        }
        fast_piece(&B, p, val, Y0, Y1);
    }
    const double lo = R->lo, hi = R->hi;
    int ra, rb;
    term_rows(&B, Y0, Y1, &ra, &rb);
    for (int r = ra; r <= rb; r++) {
        int j = j0 - pad + r;
        double *cov = B.cover + (size_t)r * cols * nv;
        unsigned char *tch = B.touched + (size_t)r * cols;
        if (j < j0 || j >= j1 || S->slow[j]) { /* margins and other paths' rows */
            clear_row(cov, tch, cols, nv);
            continue;
        }
        uint64_t touched = 0;
        /* a pixel no part or flat piece reached has its support inside one
         * face: its colour exactly, from the winding the running sum holds
         * (within rounding of an integer), and the sums set to their exact
         * values there, so that rounding does not carry from face to face */
        const unsigned char *t = tch + pad;
        double *px = aa_pixel(out, 0, j);
        if (nv == 1) {
            const double b0 = S->bg.c[0], b1 = S->bg.c[1], b2 = S->bg.c[2];
            const double c0 = S->coef1.c[0], c1 = S->coef1.c[1], c2 = S->coef1.c[2];
            /* a grey scene (crow): the three channels' values are one */
            const int gray = b0 == b1 && b1 == b2 && c0 == c1 && c1 == c2;
            /* the running sum compensated (two_sum): its rounding would
             * otherwise grow with the edges left of a pixel */
            double run = 0.0, comp = 0.0;
            for (int i = 0; i < pad; i++)
                run = two_sum(run, cov[i], &comp), cov[i] = 0.0;
            cov += pad;
            int i = 0;
            while (i < w) {
                if (!t[i]) {
                    /* a run of unmarked pixels: no term and no carry in
                     * their cells (zero already), so each takes the face
                     * the running sum's winding names, rounded once (as
                     * the first would, one pixel at a time, and the others
                     * after it, the sum then an integer); eight at a time
                     * where eight marks are zero */
                    double rs = run + comp;
                    run = (rs > 0.5) - (rs < -0.5), comp = 0.0;
                    const double *f = S->face1[1 + (int)run];
#if AN_SSE2
                    const __m128d f01 = _mm_loadu_pd(f), f20 = _mm_set_pd(f[0], f[2]),
                                  f12 = _mm_loadu_pd(f + 1);
                    /* eight pixels stored at a time, then the index
                     * moved past the unmarked ones among them (the first
                     * marked one's byte: the lowest non-zero of the eight,
                     * little-endian as x86-64 is); the marked pixels after
                     * the run are stored again, in order, below, so the
                     * run's length takes no branch */
                    while (w - i >= 8) {
                        uint64_t t8;
                        memcpy(&t8, t + i, sizeof t8);
                        for (int k = 0; k < 4; k++) {
                            _mm_storeu_pd(px + 6 * k, f01);
                            _mm_storeu_pd(px + 6 * k + 2, f20);
                            _mm_storeu_pd(px + 6 * k + 4, f12);
                        }
                        if (t8) {
                            int n = __builtin_ctzll(t8) >> 3;
                            i += n, px += 3 * n;
                            break;
                        }
                        i += 8, px += 24;
                    }
#endif
                    for (; i < w && !t[i]; i++, px += 3)
                        px[0] = f[0], px[1] = f[1], px[2] = f[2];
                    continue;
                }
                /* a marked pixel: its term or carry added */
                run = two_sum(run, cov[i], &comp);
                cov[i] = 0.0;
                double rs = run + comp;
                if (!(t[i] & AN_TERM)) {
                    run = (rs > 0.5) - (rs < -0.5), comp = 0.0;
                    memcpy(px, S->face1[1 + (int)run], 3 * sizeof *px);
                } else if (gray) {
                    double v = b0 + c0 * rs;
                    v = v < lo ? lo : v;
                    v = v > hi ? hi : v;
                    px[0] = v, px[1] = v, px[2] = v;
                    touched++;
                } else {
                    double v0 = b0 + c0 * rs, v1 = b1 + c1 * rs, v2 = b2 + c2 * rs;
                    /* branch-free clamps (minsd, maxsd) */
                    v0 = v0 < lo ? lo : v0, v1 = v1 < lo ? lo : v1, v2 = v2 < lo ? lo : v2;
                    px[0] = v0 > hi ? hi : v0, px[1] = v1 > hi ? hi : v1,
                    px[2] = v2 > hi ? hi : v2;
                    touched++;
                }
                i++, px += 3;
            }
            memset(cov + w, 0, (cols - (size_t)pad - (size_t)w) * sizeof *cov);
        } else {
            for (int i = 0; i < w; i++)
                touched += t[i] & AN_TERM;
            double r0 = 0.0, r1 = 0.0, r2 = 0.0, r3 = 0.0;
            for (int i = 0; i < pad; i++, cov += AN_NV) {
                r0 += cov[0], r1 += cov[1], r2 += cov[2], r3 += cov[3];
                cov[0] = cov[1] = cov[2] = cov[3] = 0.0;
            }
            int i = 0;
            while (i < w) {
                r0 += cov[0], r1 += cov[1], r2 += cov[2], r3 += cov[3];
                cov[0] = cov[1] = cov[2] = cov[3] = 0.0;
                if (!(t[i] & AN_TERM)) {
                    /* the code: (L + 1) s(L) in a face of layer L, 0 outside */
                    long k = lrint(r3), L = (k < 0 ? -k : k) - 1;
                    int in = L >= 0 && L < S->plan_nl;
                    double sg = k < 0 ? -1.0 : 1.0;
                    const double *f = in ? &S->face[3 * L] : S->bg.c;
                    /* the sums there exactly: s(L) coef(L), the code */
                    r0 = in ? sg * S->coef[3 * L] : 0.0;
                    r1 = in ? sg * S->coef[3 * L + 1] : 0.0;
                    r2 = in ? sg * S->coef[3 * L + 2] : 0.0;
                    r3 = in ? (double)k : 0.0;
                    /* the unmarked pixels after it hold nothing in their
                     * cells: the same sums, the same face (eight marks
                     * tested at a time) */
                    i = fill_face(&px, &cov, t, i, w, f);
                    continue;
                }
                i++, cov += AN_NV;
                double v0 = S->bg.c[0] + r0, v1 = S->bg.c[1] + r1, v2 = S->bg.c[2] + r2;
                v0 = v0 < lo ? lo : v0, v1 = v1 < lo ? lo : v1, v2 = v2 < lo ? lo : v2;
                px[0] = v0 > hi ? hi : v0, px[1] = v1 > hi ? hi : v1, px[2] = v2 > hi ? hi : v2;
                px += 3;
            }
            memset(cov, 0, (cols - (size_t)pad - (size_t)w) * AN_NV * sizeof *cov);
        }
        memset(tch, 0, cols);
        *expensive += touched;
    }
    return 0;
}

/* ---- the visible parts' scatter (the rows marked slow) ----
 *
 * In the rows the plan marks slow, the picture is not a sum of shapes, but
 * it is still a sum of visible parts: with the colour left of the scene
 * bg (every piece right of the window's left side), the pixel at centre
 * (cx, cy) is
 *
 *     bg + sum over visible parts of (step of colour across it) R(part),
 *
 * the per-pixel sum above with the window widened to the whole row: the
 * bands' colour at the left side is then bg, and their weights sum to the
 * filter's, 1, while a visible part outside the pixel's support gives
 * R = its rows' weight (left of it) or 0 (right).  The visible parts of a
 * window depend on the window only through its sides (where pieces are cut
 * and which parts count), so those of one window over the whole width of
 * the image and the rows of every slow row's support in the block, found
 * once (aa__vis_window), are the visible parts of every pixel's support
 * there, cut more finely.  The window is taken in tiles 8 px wide (the
 * first from the window's left side, the last to its right), whose
 * visible parts are the window's cut again at the tiles' sides: a step of
 * colour is the colour's jump across the piece at a point, whatever the
 * window, and each part lies in one tile (a piece is cut where it crosses a
 * side, and the part inside a tile is reported by it alone; a vertical
 * piece on a side would be in neither, and a curve tangent to a side
 * crosses it at a height known only to about 1e-8 px, so the sides keep
 * 1e-6 px clear of every piece's least and greatest x).  In
 * one window across the width every band was cut at every meeting of any
 * two pieces of the row and every neighbouring pair tested again in each:
 * on strokes' outlines, whose pieces meet often, most of the time.  A
 * piece is local to every tile its rows' x extent reaches, so each tile
 * seeks only the meetings of pairs with a piece inside it (visible.h,
 * inside_meets): else each tile sought again the meetings of every pair
 * of long pieces beside it (on curves.svg under tent:r=1, 4.4e6
 * instructions a render, a tenth, over the single window's).  Each
 * run of bands along a piece with one step of
 * colour is scattered as a piece of the sum of shapes is (fast_piece over
 * the run's rows), its step as its values, so one part's rule serves
 * every pixel whose support holds it and the constant part goes along the
 * row in the running sum.  The same terms as the per-pixel path's, summed
 * in another order: exact to rounding.
 *
 * The faces: a pixel no term reached (nor a flat piece crosses its
 * support) lies inside one face, and takes its colour exactly, as the
 * per-pixel path's uniform runs do.  The colour is named by a code: each
 * distinct colour met in the block gets the next integer (bg 0), and the
 * values are the colour and the code, so the running sum of the codes'
 * steps is, in a face, its code within rounding (the colour being a
 * function of the winding numbers, two faces of one colour share one code
 * whichever layers make them).  The sums are set to the face's exact
 * values there, so rounding does not carry from face to face.  A block
 * whose faces have more than AN_FACES colours, or whose first tile's left side
 * is not bg (it lies left of the scene's bounds: never), takes the
 * per-pixel path. */

typedef struct an_vis_ctx {
    const an_block *B;
    const aa_scene *scene;
    double *face; /* the colours by code, 3 a code; face 0 bg */
    int nface, bad;
    int first; /* the window is the leftmost tile (vis_band) */
} an_vis_ctx;

static void vis_values(void *ctx, const int *wind, double *out)
{
    an_vis_ctx *V = ctx;
    aa_rgb c = aa_scene_colour_of(V->scene, wind);
    int k = 0;
    while (k < V->nface && memcmp(&V->face[3 * k], c.c, sizeof c.c))
        k++;
    if (k == V->nface) {
        if (k == AN_FACES) {
            V->bad = 1;
            k = 0;
        } else {
            memcpy(&V->face[3 * k], c.c, sizeof c.c);
            V->nface++;
        }
    }
    out[0] = c.c[0], out[1] = c.c[1], out[2] = c.c[2], out[3] = k;
}

static void vis_band(void *ctx, double ya, double yb, const int *wind)
{
    an_vis_ctx *V = ctx;
    (void)ya, (void)yb;
    double c[AN_NV];
    vis_values(V, wind, c);
    if (V->first && c[3] != 0.0) /* the left side's colour is not bg */
        V->bad = 1;
}

static void vis_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                    int inside)
{
    an_vis_ctx *V = ctx;
    (void)inside;
    fast_piece(V->B, p, jump, ya, yb);
}

/* A tile's side at X or, where a piece's extreme x (S->vert) lies within
 * AN_TILE_CLEAR of X, the first X + k/64 where none does. */
static double tile_side(const an_state *S, double X)
{
    for (;;) {
        size_t a = 0, b = S->nvert;
        while (a < b) { /* the first vert >= X - AN_TILE_CLEAR */
            size_t m = a + (b - a) / 2;
            if (S->vert[m] < X - AN_TILE_CLEAR)
                a = m + 1;
            else
                b = m;
        }
        if (a == S->nvert || S->vert[a] > X + AN_TILE_CLEAR)
            return X;
        X += 1.0 / 64.0;
    }
}

/* The slow rows of rows j0 .. j1-1 by the visible parts' scatter: 0 done,
 * 1 the strip could not be built, 2 not done (the faces' colours, above:
 * the caller takes the per-pixel path; the buffers are left zeroed). */
static int vis_block(const an_render *R, aa__sampler_worker *wk, int j0, int j1, aa_image *out,
                     uint64_t *expensive)
{
    const an_state *S = R->S;
    const an_pp *pp = &S->pp;
    const int w = out->w, pad = S->pad;
    const size_t cols = block_cols(S, w);
    an_block B = block_bind(S, wk, w, j0, j1, AN_NV);
    B.uncertain = R->uncertain;
    int ja = j1, jb = j0 - 1;
    for (int j = j0; j < j1; j++)
        if (S->slow[j])
            ja = j < ja ? j : ja, jb = j;
    /* the rows of the slow rows' supports; the whole width */
    double Y0 = ja + 0.5 + pp->k[0], Y1 = jb + 0.5 + pp->k[pp->ncell];
    double sx0, sy0, sx1, sy1;
    aa_scene_bounds(R->scene, &sx0, &sy0, &sx1, &sy1);
    double xl = fmin(sx0, 0.0) - 1.0, xr = w - 0.5 + pp->k[pp->ncell];
    if (aa_strip_begin(wk->strip, Y0, Y1))
        return 1;
    an_vis_ctx V = {&B, R->scene,
                    (double *)((char *)wk->own + S->fast_off + fast_size(S, w)) - 3 * AN_FACES,
                    1, 0, 1};
    memcpy(V.face, S->bg.c, sizeof S->bg.c);
    aa__vis v;
    aa__vis_bind(&v, R->scene, AN_NV, wk->own);
    const aa__vis_sink sink = {vis_band, vis_run, NULL, vis_values, &V, AN_NV, 0, 0, 1};
    /* the window in tiles (see "The visible parts' scatter"): the first
     * from xl, the others AN_TILE px wide, the last to xr */
    for (double xa = xl, side = 0.5 + pp->k[0]; xa < xr && !V.bad;) {
        side = tile_side(S, fmax(side + AN_TILE, xa + AN_TILE));
        double xb = fmin(side, xr);
        aa_strip_window(wk->strip, xa, xb);
        size_t nloc;
        const aa_piece *const *loc = aa_strip_local(wk->strip, &nloc);
        for (size_t q = 0; q < nloc; q++)
            if (!loc[q]->dir && loc[q]->y0 >= Y0 && loc[q]->y0 <= Y1)
                mark_flat(&B, loc[q]);
        aa__vis_window(&v, wk->strip, xa, xb, Y0, Y1, &sink);
        V.first = 0;
        xa = xb;
    }
    const double lo = R->lo, hi = R->hi;
    const double *bg = S->bg.c;
    /* the rows a term can reach */
    int ra, rb;
    term_rows(&B, Y0, Y1, &ra, &rb);
    for (int r = ra; r <= rb; r++) {
        int j = j0 - pad + r;
        double *cov = B.cover + (size_t)r * cols * AN_NV;
        unsigned char *tch = B.touched + (size_t)r * cols;
        if (V.bad || j < j0 || j >= j1 || !S->slow[j]) { /* margins, other rows */
            clear_row(cov, tch, cols, AN_NV);
            continue;
        }
        const unsigned char *t = tch + pad;
        double *px = aa_pixel(out, 0, j);
        uint64_t touched = 0;
        double r0 = 0.0, r1 = 0.0, r2 = 0.0, r3 = 0.0;
        for (int i = 0; i < pad; i++, cov += AN_NV) {
            r0 += cov[0], r1 += cov[1], r2 += cov[2], r3 += cov[3];
            cov[0] = cov[1] = cov[2] = cov[3] = 0.0;
        }
        int i = 0;
        while (i < w) {
            r0 += cov[0], r1 += cov[1], r2 += cov[2], r3 += cov[3];
            cov[0] = cov[1] = cov[2] = cov[3] = 0.0;
            long k = lrint(r3);
            if (!(t[i] & AN_TERM) && k >= 0 && k < V.nface) {
                /* inside a face: its colour, and the sums there exactly;
                 * so are the unmarked pixels after it (their cells hold
                 * nothing: the same sums, the same face), eight marks
                 * tested at a time */
                const double *f = &V.face[3 * k];
                r0 = f[0] - bg[0], r1 = f[1] - bg[1], r2 = f[2] - bg[2], r3 = (double)k;
                i = fill_face(&px, &cov, t, i, w, f);
                continue;
            }
            i++, cov += AN_NV;
            touched++;
            double v0 = bg[0] + r0, v1 = bg[1] + r1, v2 = bg[2] + r2;
            v0 = v0 < lo ? lo : v0, v1 = v1 < lo ? lo : v1, v2 = v2 < lo ? lo : v2;
            px[0] = v0 > hi ? hi : v0, px[1] = v1 > hi ? hi : v1, px[2] = v2 > hi ? hi : v2;
            px += 3;
        }
        memset(cov, 0, (cols - (size_t)pad - (size_t)w) * AN_NV * sizeof *cov);
        memset(tch, 0, cols);
        *expensive += touched;
    }
    return V.bad ? 2 : 0;
}

static int render_block(const an_render *R, aa__sampler_worker *wk, int b, aa_image *out,
                        uint64_t *expensive)
{
    const an_state *S = R->S;
    int j0 = b * AN_BLOCK, j1 = j0 + AN_BLOCK < out->h ? j0 + AN_BLOCK : out->h, fast = 0,
        slow = 0;
    for (int j = j0; j < j1; j++)
        fast |= !S->slow[j], slow |= S->slow[j];
    if (fast && fast_block(R, wk, j0, j1, out, expensive))
        return 1;
    if (!slow)
        return 0;
    int st = vis_block(R, wk, j0, j1, out, expensive);
    if (st != 2)
        return st;
    uint64_t samples = 0;
    for (int j = j0; j < j1; j++)
        if (S->slow[j] &&
            aa__sampler_row(wk, j, S->pp.k[S->pp.ncell], 0, shade, R, out, &samples, expensive))
            return 1;
    return 0;
}

/* ---- linear gradients (header, "Linear gradients") ---- */

/* the sRGB encoding's change of piece (IEC 61966-2-1) */
#define AN_LIN_T 0.0031308
/* stop lines of one gradient across the frame, at most */
#define AN_MAX_LINES 65536

/* where the encoding's power piece reaches the decoding's threshold: the
 * end of the sliver (AN_LIN_T, an_lin_v2) on which decode(encode(v)) is
 * the power piece over 12.92 */
static double an_lin_v2(void) { return pow((0.04045 + 0.055) / 1.055, 2.4); }
static double an_lin_sliver(double v) { return (1.055 * pow(v, 1.0 / 2.4) - 0.055) / 12.92; }

/* The picture of an opaque gradient in linear light about t (not a
 * kink): its value h and slope b in t there, per channel. */
static void grad_colour(const aa_gradient *g, double t, double h[3], double b[3])
{
    double s, ds;
    if (g->spread == AA_SPREAD_PAD) {
        s = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        ds = t > 0.0 && t < 1.0 ? 1.0 : 0.0;
    } else if (g->spread == AA_SPREAD_REPEAT) {
        s = t - floor(t);
        ds = 1.0;
    } else { /* reflect: the distance to the nearest even integer */
        double r = t - 2.0 * floor(0.5 * t);
        s = r <= 1.0 ? r : 2.0 - r;
        ds = r <= 1.0 ? 1.0 : -1.0;
    }
    const aa_gradient_stop *st = g->stops;
    int n = g->nstops, a = 0;
    if (s <= st[0].offset || s >= st[n - 1].offset) {
        const aa_gradient_stop *e = s <= st[0].offset ? &st[0] : &st[n - 1];
        for (int ch = 0; ch < 3; ch++) {
            h[ch] = aa_srgb_decode(aa_srgb_encode(e->colour.c[ch]));
            b[ch] = 0.0;
        }
        return;
    }
    while (a + 2 < n && st[a + 1].offset <= s)
        a++;
    double span = st[a + 1].offset - st[a].offset, f = (s - st[a].offset) / span;
    double v2 = an_lin_v2(), hl = an_lin_sliver(AN_LIN_T);
    double chord = (an_lin_sliver(v2) - hl) / (v2 - AN_LIN_T);
    for (int ch = 0; ch < 3; ch++) {
        double ca = st[a].colour.c[ch], cb = st[a + 1].colour.c[ch];
        double v = ca + f * (cb - ca), dv = (cb - ca) / span * ds;
        if (dv == 0.0) {
            h[ch] = aa_srgb_decode(aa_srgb_encode(v));
            b[ch] = 0.0;
        } else if (v > AN_LIN_T && v < v2) { /* the sliver: its chord */
            h[ch] = hl + chord * (v - AN_LIN_T);
            b[ch] = chord * dv;
        } else {
            h[ch] = v;
            b[ch] = dv;
        }
    }
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y);
}

/* The kinks of the colour in the spread value s in [0, 1]: 0, 1, the
 * offsets, and in each interval between stops where a channel's value
 * passes AN_LIN_T or an_lin_v2 (the sliver's ends); ascending, distinct.
 * ks holds 2 + 7 nstops. */
static int grad_kinks(const aa_gradient *g, double *ks)
{
    int n = 0;
    double v2 = an_lin_v2(), thr[2] = {AN_LIN_T, v2};
    ks[n++] = 0.0;
    ks[n++] = 1.0;
    for (int k = 0; k < g->nstops; k++) {
        const aa_gradient_stop *a = &g->stops[k], *b = &g->stops[k + 1];
        ks[n++] = a->offset;
        if (k + 1 == g->nstops || !(b->offset > a->offset))
            continue;
        for (int ch = 0; ch < 3; ch++)
            for (int q = 0; q < 2; q++) {
                double ca = a->colour.c[ch], cb = b->colour.c[ch];
                if (!((ca < thr[q] && cb > thr[q]) || (ca > thr[q] && cb < thr[q])))
                    continue;
                double s = a->offset + (thr[q] - ca) / (cb - ca) * (b->offset - a->offset);
                if (s > a->offset && s < b->offset)
                    ks[n++] = s;
            }
    }
    qsort(ks, (size_t)n, sizeof *ks, cmp_d);
    int m = 0;
    for (int k = 0; k < n; k++)
        if (!m || ks[k] != ks[m - 1])
            ks[m++] = ks[k];
    return m;
}

/* The stop line t = tau as a layer of the copy: the half-plane t >= tau
 * inside the frame bx, by (a rectangle, counter-clockwise on screen),
 * clipped side by side (the crossings of the frame's sides in closed
 * form). */
static int grad_line(aa_scene *aug, const an_glayer *gl, double tau, const double *bx,
                     const double *by)
{
    double px[8], py[8];
    int n = 0, st;
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        double fi = gl->gu * (bx[i] - gl->X1) + gl->gv * (by[i] - gl->Y1) - tau;
        double fj = gl->gu * (bx[j] - gl->X1) + gl->gv * (by[j] - gl->Y1) - tau;
        if (fi >= 0.0)
            px[n] = bx[i], py[n++] = by[i];
        if ((fi < 0.0) == (fj < 0.0))
            continue;
        if (bx[i] == bx[j]) { /* a vertical side: t varies with y, gv != 0 */
            double y = gl->Y1 + (tau - gl->gu * (bx[i] - gl->X1)) / gl->gv;
            px[n] = bx[i], py[n++] = fmin(fmax(y, fmin(by[i], by[j])), fmax(by[i], by[j]));
        } else {
            double x = gl->X1 + (tau - gl->gv * (by[i] - gl->Y1)) / gl->gu;
            py[n] = by[i], px[n++] = fmin(fmax(x, fmin(bx[i], bx[j])), fmax(bx[i], bx[j]));
        }
    }
    if ((st = aa_scene_layer(aug, (aa_rgb){{0.0, 0.0, 0.0}}, AA_FILL_NONZERO)) ||
        (st = aa_scene_move_to(aug, px[0], py[0])))
        return st;
    for (int k = 1; k < n; k++)
        if ((st = aa_scene_line_to(aug, px[k], py[k])))
            return st;
    return aa_scene_close(aug);
}

static void grad_free(an_grad *G)
{
    for (int k = 0; k < G->ng; k++)
        free(G->g[k].strip);
    free(G->g);
    free(G->of);
    aa_scene_free(G->aug);
    memset(G, 0, sizeof *G);
}

/* What the gradient path takes (header, "Linear gradients"): refused by
 * name otherwise. */
static int grad_check(const aa_scene *s)
{
    int nl = aa_scene_layer_count(s);
    for (int l = 0; l < nl; l++) {
        aa_gradient g;
        if (aa_scene_layer_clip_member(s, l) >= 0)
            continue;
        int has = aa_scene_layer_gradient(s, l, &g);
        const char *src = has ? aa_scene_layer_gradient_source(s, l) : "";
        const char *o = *src ? " (" : "", *c = *src ? ")" : "";
        if (aa_scene_layer_alpha(s, l) != 1.0 || aa_scene_layer_group(s, l) >= 0)
            return aa_fail(AA_EINVAL,
                           "analytic: layer %d is translucent (its alpha or a group's opacity) "
                           "in a scene with gradient paint: translucent paint composites in "
                           "sRGB-encoded values, and over or of a gradient that is not a "
                           "polynomial in the position; refused (gradient scenes are taken "
                           "with opaque layers only)",
                           l);
        if (!has)
            continue;
        if (g.kind != AA_GRADIENT_LINEAR)
            return aa_fail(AA_EINVAL,
                           "analytic: layer %d's radial gradient%s%s%s is refused: its t is "
                           "not an affine function of the position, so its colour is no "
                           "polynomial on any region (linear gradients in linear light are "
                           "taken)",
                           l, o, src, c);
        if (aa_scene_layer_gradient_interpolation(s, l) != AA_INTERPOLATE_LINEAR_RGB)
            return aa_fail(AA_EINVAL,
                           "analytic: layer %d's linear gradient%s%s%s interpolates its stops "
                           "in sRGB-encoded values (the SVG default): its colour in linear "
                           "light is the sRGB decoding (a power 2.4) of an affine function of "
                           "the position, not a polynomial; refused (color-interpolation: "
                           "linearRGB is taken)",
                           l, o, src, c);
        for (int k = 0; k < g.nstops; k++)
            if (g.stops[k].opacity != 1.0)
                return aa_fail(AA_EINVAL,
                               "analytic: layer %d's linear gradient%s%s%s has stop %d of "
                               "opacity %g: a gradient of varying or partial opacity "
                               "composites in sRGB-encoded values, not a polynomial; "
                               "refused (opaque stops are taken)",
                               l, o, src, c, k, g.stops[k].opacity);
    }
    return AA_OK;
}

/* The copy of the scene with every gradient's stop lines across the
 * frame (the image and the filter's support about it, and 2 px), and
 * each strip's colour. */
static int grad_build(an_state *S, const aa_job *job)
{
    an_grad *G = &S->grad;
    const aa_scene *s = job->placed;
    if (G->src == s && G->w == job->w && G->h == job->h)
        return AA_OK;
    grad_free(G);
    int st = grad_check(s), nl = aa_scene_layer_count(s), nlines = 0;
    if (st)
        return st;
    double M = ceil(S->rad_k ? S->rad_r : S->pp.k[S->pp.ncell]) + 2.0;
    const double bx[4] = {-M, job->w + M, job->w + M, -M}, by[4] = {-M, -M, job->h + M,
                                                                     job->h + M};
    G->nreal = nl;
    G->of = malloc((size_t)(nl > 0 ? nl : 1) * sizeof *G->of);
    G->g = calloc((size_t)(nl > 0 ? nl : 1), sizeof *G->g);
    if (!G->of || !G->g) {
        grad_free(G);
        return aa_fail(AA_ENOMEM, "out of memory for gradient lines");
    }
    if (!(G->aug = aa__scene_copy_open(s))) { /* reported */
        grad_free(G);
        return AA_ENOMEM;
    }
    double *tl = NULL;
    for (int l = 0; l < nl && !st; l++) {
        aa_gradient g;
        G->of[l] = -1;
        if (aa_scene_layer_clip_member(s, l) >= 0 || !aa_scene_layer_gradient(s, l, &g))
            continue;
        an_glayer *gl = &G->g[G->ng];
        G->of[l] = G->ng++;
        /* t = (q - P1).d / |d|^2, q = m^-1 (p): with P the scene's image of
         * P1, t = (m^-T d).(p - P) / |d|^2 */
        const double *m = g.m, *q = g.p;
        double dx = q[2] - q[0], dy = q[3] - q[1], det = m[0] * m[3] - m[2] * m[1];
        double dd = det * (dx * dx + dy * dy);
        gl->gu = (m[3] * dx - m[1] * dy) / dd;
        gl->gv = (m[0] * dy - m[2] * dx) / dd;
        gl->X1 = m[0] * q[0] + m[2] * q[1] + m[4];
        gl->Y1 = m[1] * q[0] + m[3] * q[1] + m[5];
        double tmin = INFINITY, tmax = -INFINITY;
        for (int k = 0; k < 4; k++) {
            double t = gl->gu * (bx[k] - gl->X1) + gl->gv * (by[k] - gl->Y1);
            tmin = fmin(tmin, t), tmax = fmax(tmax, t);
        }
        double ks[2 + 7 * 64], *kk = ks;
        if (g.nstops > 64 && !(kk = malloc((size_t)(2 + 7 * g.nstops) * sizeof *kk))) {
            st = aa_fail(AA_ENOMEM, "out of memory for gradient lines");
            break;
        }
        int nk = grad_kinks(&g, kk);
        /* the periods (of 1, or 2 reflected) the frame meets */
        double per = g.spread == AA_SPREAD_PAD ? 1.0
                     : g.spread == AA_SPREAD_REPEAT
                         ? floor(tmax) - floor(tmin) + 1.0
                         : floor(0.5 * tmax) - floor(0.5 * tmin) + 1.0;
        double cap = per * (g.spread == AA_SPREAD_REFLECT ? 2.0 : 1.0) * nk;
        if (!(cap <= AN_MAX_LINES)) {
            const char *src = aa_scene_layer_gradient_source(s, l);
            if (kk != ks)
                free(kk);
            st = aa_fail(AA_EINVAL,
                         "analytic: layer %d's linear gradient%s%s%s repeats %.0f times "
                         "across the image: more than %d stop lines; refused",
                         l, *src ? " (" : "", src, *src ? ")" : "", per, AN_MAX_LINES);
            break;
        }
        free(tl);
        if (!(tl = malloc((size_t)(cap + 1) * sizeof *tl))) {
            if (kk != ks)
                free(kk);
            st = aa_fail(AA_ENOMEM, "out of memory for gradient lines");
            break;
        }
        int n = 0;
        if (g.spread == AA_SPREAD_PAD)
            for (int k = 0; k < nk; k++)
                tl[n++] = kk[k];
        else
            for (double b = g.spread == AA_SPREAD_REPEAT ? floor(tmin) : 2.0 * floor(0.5 * tmin);
                 b <= tmax; b += g.spread == AA_SPREAD_REPEAT ? 1.0 : 2.0)
                for (int k = 0; k < nk; k++) {
                    tl[n++] = b + kk[k];
                    if (g.spread == AA_SPREAD_REFLECT)
                        tl[n++] = b + 2.0 - kk[k];
                }
        if (kk != ks)
            free(kk);
        qsort(tl, (size_t)n, sizeof *tl, cmp_d);
        int keep = 0;
        for (int k = 0; k < n; k++)
            if (tl[k] > tmin && tl[k] < tmax && (!keep || tl[k] != tl[keep - 1]))
                tl[keep++] = tl[k];
        gl->first = nl + nlines;
        gl->nl = keep;
        nlines += keep;
        if (!(gl->strip = malloc((size_t)(keep + 1) * sizeof *gl->strip))) {
            st = aa_fail(AA_ENOMEM, "out of memory for gradient lines");
            break;
        }
        for (int k = 0; k <= keep; k++) {
            double lo = k ? tl[k - 1] : tmin, hi = k < keep ? tl[k] : tmax;
            gl->strip[k].tm = 0.5 * (lo + hi);
            grad_colour(&g, gl->strip[k].tm, gl->strip[k].h, gl->strip[k].b);
        }
        for (int k = 0; k < keep && !st; k++)
            st = grad_line(G->aug, gl, tl[k], bx, by);
    }
    free(tl);
    if (!st)
        st = aa__scene_finish_copy(G->aug, 1.0);
    if (st) {
        grad_free(G);
        return st;
    }
    G->src = s, G->w = job->w, G->h = job->h;
    return AA_OK;
}

/* A face's colour about the pixel's centre (cx, cy): out[3 ch] its value
 * at the centre, out[3 ch + 1] and out[3 ch + 2] its slopes in x and y. */
static void grad_face(const an_state *S, const int *wind, double cx, double cy, double *out)
{
    const an_grad *G = &S->grad;
    int l = 0;
    while (l < G->nreal && !aa__scene_covers(G->aug, wind, l))
        l++;
    if (l == G->nreal || G->of[l] < 0) {
        aa_rgb c = l == G->nreal ? aa_scene_background(G->aug) : aa_scene_layer_colour(G->aug, l);
        for (int ch = 0; ch < 3; ch++)
            out[3 * ch] = c.c[ch], out[3 * ch + 1] = out[3 * ch + 2] = 0.0;
        return;
    }
    const an_glayer *gl = &G->g[G->of[l]];
    /* the half-planes t >= tl[q] are nested: the point is inside a prefix
     * of them, its strip the prefix's length */
    int lo = 0, hi = gl->nl;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (wind[gl->first + mid] != 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    const an_gstrip *sp = &gl->strip[lo];
    double t = gl->gu * (cx - gl->X1) + gl->gv * (cy - gl->Y1);
    for (int ch = 0; ch < 3; ch++) {
        double b = sp->b[ch];
        out[3 * ch] = sp->h[ch] + b * (t - sp->tm);
        out[3 * ch + 1] = b * gl->gu;
        out[3 * ch + 2] = b * gl->gv;
    }
}

/* The three moments right of piece p over rows [ya, yb] about (cx, cy):
 * r[0] = R of (1), r[1] = integral of w(v) (W1(inf) - W1(x - cx)) dy,
 * r[2] = integral of w(v) v (1 - W(x - cx)) dy, v = y - cy: each a
 * polynomial in t of degree at most d (n + 2) + ... (header), integrated
 * by the rule of d (n + 2) points per part between the knots' lines. */
static void mom_right_of(const an_state *S, const aa_piece *p, double ya, double yb,
                         double cx, double cy, double r[3])
{
    const an_pp *pp = &S->pp;
    double ys[2 + 2 * (AN_MAX_CELLS + 1) * 3];
    int n = 0;
    ys[n++] = ya;
    ys[n++] = yb;
    for (int q = 1; q < pp->ncell; q++) {
        double yk = cy + pp->k[q], m[3];
        if (yk > ya && yk < yb)
            ys[n++] = yk;
        double xk = cx + pp->k[q];
        if (!(xk > p->xmin && xk < p->xmax))
            continue;
        int c = aa_piece_meet_x(p, xk, m);
        for (int k = 0; k < c; k++)
            if (m[k] > ya && m[k] < yb)
                ys[n++] = m[k];
    }
    aa__vis_sort(ys, (size_t)n);
    int m = curve_degree(p) * (pp->deg + 2);
    const double *gx = S->ogx[m], *gw = S->ogw[m];
    r[0] = r[1] = r[2] = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ys[s] < ys[s + 1]))
            continue;
        double ta = ys[s] <= p->y0 ? 0.0 : aa_piece_t_at(p, ys[s]);
        double tb = ys[s + 1] >= p->y1 ? 1.0 : aa_piece_t_at(p, ys[s + 1]);
        double h = 0.5 * (tb - ta), mid = 0.5 * (ta + tb), a0 = 0.0, a1 = 0.0, a2 = 0.0;
        for (int g = 0; g < m; g++) {
            double t = mid + h * gx[g], x, y, dy;
            aa__piece_point(p, t, &x, &y, &dy);
            double v = y - cy, u = x - cx, wv = gw[g] * an_weight(pp, v) * dy;
            double right = 1.0 - an_cdf(pp, u);
            a0 += wv * right;
            a1 += wv * (pp->m1tot - an_m1(pp, u));
            a2 += wv * v * right;
        }
        r[0] += h * a0, r[1] += h * a1, r[2] += h * a2;
    }
}

/* The three moments of mom_right_of for conic piece p: its parts between
 * the knots' lines (arc_cuts), each by the arc's rule of one degree more
 * (2 arc1_m = 4 n + 8 points: the integrands are trigonometric
 * polynomials of degree 2 n + 3 on a part, header). */
static void mom_arc(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                    double cy, double r[3])
{
    const an_pp *pp = &S->pp;
    long double ss[AN_ARC_CUTS];
    int n = arc_cuts(pp, p, ya, yb, cx, cy, ss);
    double X[2 * AN_ARC1_M], Y[2 * AN_ARC1_M], D[2 * AN_ARC1_M], xm, ym;
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int s = 0; s + 1 < n; s++) {
        if (!(ss[s] < ss[s + 1]))
            continue;
        int ns = arc_splits(ss[s], ss[s + 1]);
        for (int q = 0; q < ns; q++) {
            long double a = ss[s] + (ss[s + 1] - ss[s]) * q / ns,
                        b = q + 1 == ns ? ss[s + 1] : ss[s] + (ss[s + 1] - ss[s]) * (q + 1) / ns;
            arc_points_of(S->arc1_m, S->arc1_u, (const double(*)[AN_ARC_K + 1])S->arc1_wz, p,
                          a, b, X, Y, D, &xm, &ym);
            for (int g = 0; g < 2 * S->arc1_m; g++) {
                double v = Y[g] - cy, u = X[g] - cx, wv = D[g] * an_weight(pp, v);
                double right = 1.0 - an_cdf(pp, u);
                a0 += wv * right;
                a1 += wv * (pp->m1tot - an_m1(pp, u));
                a2 += wv * v * right;
            }
        }
    }
    r[0] = a0, r[1] = a1, r[2] = a2;
}

/* The three moments over the part [u, v] (u < v) of offset piece p, added
 * to r, by the rule certified for them weighted by J (off_points_j),
 * halved where none is: under a separable filter (radial 0; the part
 * inside one cell of the pixel's support) mom_right_of's, under a radial
 * one (the part inside the disc) the integrals of F y', H y' and v F y'. */
static void mom_off_part(const an_render *Rn, const aa_piece *p, int stops, double u, double v,
                         double cx, double cy, const double *J, int radial, int depth,
                         double r[3])
{
    const an_state *S = Rn->S;
    const an_pp *pp = &S->pp;
    int m = off_points_j(S, p, u, v, J);
    if (!m) {
        double mid = 0.5 * (u + v);
        if (depth < AN_OFF_DEPTH && mid > u && mid < v) {
            mom_off_part(Rn, p, stops, u, mid, cx, cy, J, radial, depth + 1, r);
            mom_off_part(Rn, p, stops, mid, v, cx, cy, J, radial, depth + 1, r);
            return;
        }
        off_uncertain(Rn->uncertain, 1);
        m = AN_MAX_PTS;
    }
    double h = 0.5 * (v - u), mid = 0.5 * (u + v), a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int g = 0; g < m; g++) {
        double x, y, dy;
        off_point(p, stops, mid + h * S->ogx[m][g], &x, &y, &dy);
        if (radial) {
            double du = x - cx, dv = y - cy, f = S->ogw[m][g] * rad_f(S, du, dv) * dy;
            a0 += f;
            a1 += S->ogw[m][g] * rad_h(S, du, dv) * dy;
            a2 += dv * f;
        } else {
            double vv = y - cy, wv = S->ogw[m][g] * an_weight(pp, vv) * dy;
            double right = 1.0 - an_cdf(pp, x - cx);
            a0 += wv * right;
            a1 += wv * (pp->m1tot - an_m1(pp, x - cx));
            a2 += wv * vv * right;
        }
    }
    r[0] += h * a0, r[1] += h * a1, r[2] += h * a2;
}

/* The three moments of mom_right_of for offset piece p: its parts between
 * the knots' lines (off_cuts), each by mom_off_part. */
static void mom_offset(const an_render *Rn, const aa_piece *p, double ya, double yb, double cx,
                       double cy, const double *J, double r[3])
{
    int stops = aa__offset_stops(&p->oc);
    double ts[AN_OFF_CUTS], ta, tb;
    int n = off_cuts(&Rn->S->pp, p, stops, ya, yb, cx, cy, ts, &ta, &tb);
    r[0] = r[1] = r[2] = 0.0;
    for (int s = 0; s + 1 < n; s++)
        if (ts[s] < ts[s + 1])
            mom_off_part(Rn, p, stops, ts[s], ts[s + 1], cx, cy, J, 0, 0, r);
    if (!(ta < tb))
        r[0] = -r[0], r[1] = -r[1], r[2] = -r[2];
}

/* The three moments right of piece p over rows [ya, yb] under a radial
 * filter ("Linear gradients under the radial filters"): r[0] = R of the
 * radial section, r[1] = integral of H(x - cx, v) dy, r[2] = (M1(hi) -
 * M1(lo))/2 - integral of v F(clamp(x - cx), v) dy, v = y - cy, the piece
 * cut at the circle as for the zeroth (rad_curve_walk); inside the disc the
 * rule of d (K + 2) points (the integrands H y' and v F y' have degree
 * d (2 K + 3) - 1), outside +-(M(y1) - M(y0))/2, 0 and +-(M1(y1) -
 * M1(y0))/2. */
static void rad_mom_right_of(const an_state *S, const aa_piece *p, double ya, double yb,
                             double cx, double cy, double r[3])
{
    int m = curve_degree(p) * (S->rad_k + 2);
    rad_curve_walk(S, p, ya, yb, cx, cy, 1, m, S->ogx[m], S->ogw[m], r);
}

/* The three moments of rad_mom_right_of for conic piece p (rad_arc_walk):
 * inside the disc the arc's rule of one degree more (2 arc1_m = 4 K + 8
 * points: H y' and v F y' are trigonometric polynomials of degree 2 K + 3
 * on a part). */
static void rad_mom_arc(const an_state *S, const aa_piece *p, double ya, double yb, double cx,
                        double cy, double r[3])
{
    rad_arc_walk(S, p, ya, yb, cx, cy, 1, S->arc1_m, S->arc1_u,
                 (const double(*)[AN_ARC_K + 1])S->arc1_wz, r);
}

/* The three moments of rad_mom_right_of for offset piece p
 * (rad_off_walk): the sub-parts inside the disc by mom_off_part. */
static void rad_mom_offset(const an_render *Rn, const aa_piece *p, double ya, double yb,
                           double cx, double cy, const double *J, double r[3])
{
    rad_off_walk(Rn, p, ya, yb, cx, cy, 1, J, r);
}

typedef struct an_gpixel {
    const an_render *R;
    double cx, cy;
    double acc[3];
    /* the pending bands, rows [blo, bhi], and their face's values */
    int open;
    double blo, bhi, bv[9];
} an_gpixel;

static void gp_values(void *ctx, const int *wind, double *out)
{
    const an_gpixel *P = ctx;
    grad_face(P->R->S, wind, P->cx, P->cy, out);
}

/* The pending bands: their face's colour integrated over their rows, the
 * whole width: M0 = W(vb) - W(va), Mu = W1(inf) M0, Mv = W1(vb) - W1(va)
 * (under a radial filter M0 = M(vb) - M(va), Mu = 0, Mv = M1(vb) -
 * M1(va)). */
static void gp_flush(an_gpixel *P)
{
    if (!P->open)
        return;
    const an_state *S = P->R->S;
    const an_pp *pp = &S->pp;
    double va = P->blo - P->cy, vb = P->bhi - P->cy, m0, mu, mv;
    if (S->rad_k) { /* the whole rows' Mu vanish: the chords are even */
        m0 = rad_marg(S, vb) - rad_marg(S, va), mu = 0.0;
        mv = rad_marg1(S, vb) - rad_marg1(S, va);
    } else {
        m0 = an_cdf(pp, vb) - an_cdf(pp, va), mv = an_m1(pp, vb) - an_m1(pp, va);
        mu = pp->m1tot * m0;
    }
    P->open = 0;
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += P->bv[3 * ch] * m0 + P->bv[3 * ch + 1] * mu + P->bv[3 * ch + 2] * mv;
}

static void gp_band(void *ctx, double ya, double yb, const int *wind)
{
    an_gpixel *P = ctx;
    double v[9];
    gp_values(ctx, wind, v);
    if (P->open && ya == P->bhi && !memcmp(v, P->bv, sizeof v)) {
        P->bhi = yb;
        return;
    }
    gp_flush(P);
    P->open = 1, P->blo = ya, P->bhi = yb;
    memcpy(P->bv, v, sizeof v);
}

static void gp_run(void *ctx, const aa_piece *p, double ya, double yb, const double *jump,
                   int inside)
{
    an_gpixel *P = ctx;
    double r[3];
    const an_state *S = P->R->S;
    (void)inside;
    if (p->kind == AA_PIECE_CONIC) {
        if (S->rad_k)
            rad_mom_arc(S, p, ya, yb, P->cx, P->cy, r);
        else
            mom_arc(S, p, ya, yb, P->cx, P->cy, r);
    } else if (p->kind == AA_PIECE_OFFSET) {
        double J[3] = {0.0, 0.0, 0.0};
        for (int ch = 0; ch < 3; ch++)
            for (int k = 0; k < 3; k++)
                J[k] = fmax(J[k], fabs(jump[3 * ch + k]));
        if (S->rad_k)
            rad_mom_offset(P->R, p, ya, yb, P->cx, P->cy, J, r);
        else
            mom_offset(P->R, p, ya, yb, P->cx, P->cy, J, r);
    } else if (S->rad_k) {
        rad_mom_right_of(S, p, ya, yb, P->cx, P->cy, r);
    } else {
        mom_right_of(S, p, ya, yb, P->cx, P->cy, r);
    }
    for (int ch = 0; ch < 3; ch++)
        P->acc[ch] += jump[3 * ch] * r[0] + jump[3 * ch + 1] * r[1] + jump[3 * ch + 2] * r[2];
}

/* The filter's support about the pixel's centre, [lo, hi] in x and y:
 * the outer knots, or the disc's square under a radial filter. */
static void grad_support(const an_state *S, double *lo, double *hi)
{
    *lo = S->rad_k ? -S->rad_r : S->pp.k[0];
    *hi = S->rad_k ? S->rad_r : S->pp.k[S->pp.ncell];
}

static void grad_shade(const void *ctx, aa__sampler_worker *wk, int i, int j, double *px)
{
    const an_render *R = ctx;
    aa__vis v;
    aa__vis_bind(&v, R->scene, 9, wk->own);
    an_gpixel P = {R, i + 0.5, j + 0.5, {0.0, 0.0, 0.0}, 0, 0.0, 0.0, {0.0}};
    const aa__vis_sink sink = {gp_band, gp_run, NULL, gp_values, &P, 9, 0, 0, 0};
    double lo, hi;
    grad_support(R->S, &lo, &hi);
    aa__vis_window(&v, wk->strip, P.cx + lo, P.cx + hi, P.cy + lo, P.cy + hi, &sink);
    gp_flush(&P);
    for (int ch = 0; ch < 3; ch++) {
        double c = P.acc[ch];
        px[ch] = c < R->lo ? R->lo : (c > R->hi ? R->hi : c);
    }
}

/* A row of a gradient scene: a pixel whose window no piece (stop lines
 * included) reaches lies in one face of affine colour, and its value is
 * that colour at its centre (the filter is even: its first moments over
 * the whole support vanish); the others by their visible parts. */
static int grad_row(const void *ctx, aa__sampler_worker *wk, int j, aa_image *out,
                    uint64_t *samples, uint64_t *expensive)
{
    const an_render *R = ctx;
    double lo, hi, cy = j + 0.5;
    grad_support(R->S, &lo, &hi);
    (void)samples;
    if (aa_strip_begin(wk->strip, cy + lo, cy + hi))
        return 1;
    for (int i = 0; i < out->w; i++) {
        double cx = i + 0.5, *px = aa_pixel(out, i, j);
        if (aa_strip_window(wk->strip, cx + lo, cx + hi) == 0) {
            double v[9];
            aa_strip_winding_left(wk->strip, cy, wk->wind);
            grad_face(R->S, wk->wind, cx, cy, v);
            for (int ch = 0; ch < 3; ch++)
                px[ch] = v[3 * ch] < R->lo ? R->lo : (v[3 * ch] > R->hi ? R->hi : v[3 * ch]);
            continue;
        }
        ++*expensive;
        grad_shade(ctx, wk, i, j, px);
    }
    return 0;
}

/* ---- the method ---- */

static int analytic_check(const double *p, const aa_filter *f)
{
    an_def d;
    (void)p;
    if (f->type != &aa_filter_radial && an_def_of(f, &d))
        return aa_fail(AA_EINVAL,
                       "analytic integrates piecewise polynomial filters only (box, tent, "
                       "bspline, mitchell, catrom, radial); %s is not one (the Gaussian, "
                       "Lanczos and the cone are not polynomials)",
                       f->type->info.name);
    return AA_OK;
}

static int prepare(an_state *S, const aa_job *job)
{
    if (aa_scene_has_gradients(job->placed)) { /* "Linear gradients" */
        int st = grad_build(S, job);
        if (st)
            return st;
        aa_job aj = *job;
        aj.placed = S->grad.aug;
        return aa__sampler_ready(&S->sampler, &aj, aa__vis_size(S->grad.aug, 9));
    }
    int st;
    if (S->rad_k) /* every row takes the visible parts */
        return aa__sampler_ready(&S->sampler, job, aa__vis_size(job->placed, 3));
    if ((st = plan(S, job->placed, job->h)))
        return st;
    /* the visible parts' workspace, then the scatter's buffers (left zeroed
     * after each block: the sampler's scratch starts zeroed) */
    S->fast_off = (aa__vis_size(job->placed, AN_NV) + 63) & ~(size_t)63;
    return aa__sampler_ready(&S->sampler, job, S->fast_off + fast_size(S, job->w));
}

/* The lines of the knots: x = cx + k = n + frac(1/2 + k). */
static void knot_lines(an_state *S)
{
    const an_pp *pp = &S->pp;
    S->nph = 0;
    for (int q = 0; q <= pp->ncell; q++) {
        double f = 0.5 + pp->k[q];
        f -= floor(f);
        int seen = 0;
        for (int r = 0; r < S->nph; r++)
            seen |= S->ph[r] == f;
        if (!seen)
            S->ph[S->nph++] = f;
    }
    aa__vis_sort(S->ph, (size_t)S->nph);
    S->pad = (int)ceil(pp->k[pp->ncell] - pp->k[0]) + 3;
    S->regular = pp->ncell == pp->deg + 1;
    for (int c = 0; c < pp->ncell; c++)
        S->regular &= pp->k[c + 1] - pp->k[c] == 1.0;
    memset(S->rcdf, 0, sizeof S->rcdf);
    memset(S->rw, 0, sizeof S->rw);
    memset(S->rk, 0, sizeof S->rk);
    for (int c = 0; S->regular && c <= pp->deg; c++) {
        int cell = pp->deg - c;
        for (int e = 0; e <= pp->deg + 1; e++)
            S->rcdf[e][c] = pp->cdf[cell][e];
        for (int e = 0; e <= pp->deg; e++)
            S->rw[e][c] = pp->w[cell][e];
        S->rk[c] = pp->k[cell];
    }
}

static int analytic_init(void *state, const double *p, const aa_job *job)
{
    an_state *S = state;
    an_def d;
    int st = analytic_check(p, &job->filter);
    if (st)
        return st;
    S->rad_k = 0;
    if (job->filter.type == &aa_filter_radial) {
        /* c_k = (k + 1)/(pi R^2); Q = 1/(2 I_p(pi/2)), I_p(pi/2) = pi/2
         * prod over even q <= p of (q - 1)/q */
        double R = job->filter.spec.v[1], half = M_PI / 2.0;
        S->rad_k = (int)job->filter.spec.v[0];
        S->rad_r = R;
        S->rad_c = (S->rad_k + 1.0) / (M_PI * R * R);
        for (int q = 2; q <= 2 * S->rad_k + 2; q += 2)
            half *= (q - 1.0) / q;
        S->rad_q = 0.5 / half;
        gauss_make(S);
        S->pp.deg = S->rad_k; /* the arc's rule of degree 2 K + 2 */
        arc_make(S);
        off_rules_make(S);
        return prepare(S, job);
    }
    an_def_of(&job->filter, &d);
    an_pp_make(&d, &S->pp);
    knot_lines(S);
    gauss_make(S);
    arc_make(S);
    off_rules_make(S);
    return prepare(S, job);
}

/* An image with an offset part whose rule's bound was not met (its speed
 * or a denominator within rounding of 0 on it, after AN_OFF_DEPTH
 * halvings), or whose crossings of a radial filter's circle were not
 * isolated (rad_off_cross), is refused: its values are not certified. */
static int off_certified(int uncertain)
{
    if (!uncertain)
        return AA_OK;
    if (uncertain == 2)
        return aa_fail(AA_EINVAL,
                       "analytic: an offset curve (a stroke's outline) whose crossings with "
                       "a pixel's radial filter circle it cannot isolate (more than %d "
                       "cuts, or the curve within rounding of the circle along a stretch, as "
                       "an arc concentric with it of its radius): refused",
                       AN_RAD_CUTS);
    return aa_fail(AA_EINVAL,
                   "analytic: an offset curve (a stroke's outline) with a part whose "
                   "quadrature bound (%g) it cannot meet (its speed or curvature within "
                   "rounding of 0 there): refused",
                   AN_OFF_TOL);
}

static int analytic_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    an_state *S = state;
    (void)p;
    int st = prepare(S, job);
    if (st)
        return st;
    int uncertain = 0;
    an_render R = {S, job->placed, 0.0, 1.0, &uncertain};
    aa_filter_range(&job->filter, &R.lo, &R.hi);
    if (aa_scene_has_gradients(job->placed)) {
        aa_job aj = *job;
        aj.placed = R.scene = S->grad.aug;
        st = aa__sampler_render(&S->sampler, &aj, out, grad_row, &R, counters);
        return st ? st : off_certified(uncertain);
    }
    if (S->rad_k) {
        st = aa__sampler_render(&S->sampler, job, out, rad_render_row, &R, counters);
        return st ? st : off_certified(uncertain);
    }
    /* blocks of rows shared among threads (a pixel's value does not
     * depend on how) */
    uint64_t expensive = 0;
    int failed = 0, nb = (job->h + AN_BLOCK - 1) / AN_BLOCK;
#pragma omp parallel num_threads(job->threads) reduction(+ : expensive)
    {
        aa__sampler_worker *wk = &S->sampler.workers[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nb; b++) {
            int stop;
#pragma omp atomic read
            stop = failed;
            if (!stop && render_block(&R, wk, b, out, &expensive)) {
#pragma omp atomic write
                failed = 1;
            }
        }
    }
    if (failed)
        return aa_fail(AA_ENOMEM, "out of memory for a strip of the scene");
    counters->samples = 0;
    counters->expensive_pixels = expensive;
    return off_certified(uncertain);
}

static void analytic_release(void *state)
{
    an_state *S = state;
    aa__sampler_free(&S->sampler);
    plan_free(S);
    grad_free(&S->grad);
}

const aa_method_type aa_method_analytic = {
    {"analytic",
     "exact under piecewise polynomial filters: Green's theorem per filter cell and curve "
     "degree (Manson and Schaefer 2013)",
     analytic_params},
    sizeof(an_state),
    /* gradient paint but opaque linear gradients in linear light: refused
     * at init, naming the layer ("Linear gradients"); every scene's pieces
     * taken (an uncertified offset part refuses its render) */
    AA_METHOD_GRADIENTS,
    analytic_check,
    analytic_init,
    analytic_render,
    analytic_release};
