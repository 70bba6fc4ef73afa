/*
 * truth.c: the ground truth (harness/README.md, "Ground truth").
 *
 * The reference value of pixel (i, j) is the scene convolved with the
 * filter at the pixel centre (uc, vc) (patterns/README.md, "The reference
 * value"):
 *
 *     P = integral dv w(v - vc) integral du w(u - uc) I(u, v).
 *
 * The inner integral along u is exact: along the line v the scene is a
 * sequence of spans of constant colour bounded by the pieces' crossings,
 * and the filter's integral over a span is a difference of its cdf.
 *
 * Box and tent: the outer integral along v is done interval by interval
 * with GSL's adaptive Gauss-Kronrod (QAG), between breakpoints placed
 * wherever that inner function is not smooth: the ends of pieces (vertices,
 * and the turning points where arcs are split), horizontal edges, the
 * heights where a piece crosses a vertical line at which the filter has a
 * kink (the window's sides for the box; r, 0, -r for the tent), the
 * filter's own kinks along v, and the heights where two pieces meet.
 * Between breakpoints the integrand is smooth; for `crow` and the box it is
 * a polynomial of degree 2 and the first 21-point pass is exact.  Next to
 * a turning point x moves like the square root of the height, so there the
 * half interval is integrated in u = sqrt(|v - v_turn|); so is the half of
 * an interval that ends closer to a turning point than its own length.
 *
 * The Gaussian (untruncated; the window is the square of half-side R =
 * f->radius outside which its mass is below 1e-14): QAG alone needs some
 * 170 evaluations of the inner integral a pixel, as the integrand is
 * nowhere a polynomial.  But the filter is separable, so
 *
 *     P(i, j) = integral dv w(v - vc_j) G_i(v),
 *     G_i(v)  = integral du w(u - uc_i) I(u, v),
 *
 * and G_i, the inner integral of column i, does not depend on the row.  So
 * v is cut into panels of height h (2 s at most, aligned with the pixel
 * grid: h = 1/n or n pixels), G_i is computed once at the 21 Kronrod nodes
 * of each panel, and each pixel is a dot product of those values, over the
 * panels that cover [vc - R, vc + R], with a table of w(node - vc) times
 * the Kronrod weights that is the same for every row (one table per row
 * phase when h > 1; if 2 R < 1, s < 1/16, rows share no panel and QAG
 * does it all).  The 10-point Gauss rule embedded in the same nodes
 * gives the error estimate, |K21 - G10| summed over the panels: pessimistic
 * (it is G10's error; K21's is at the rounding level), measured below 1e-15
 * a panel for slopes up to 0.6 (crow's steepest).  A thread renders a block
 * of rows and keeps a ring of the panels its current row needs: memory
 * O(width), nothing allocated per pixel; a panel's values are a function
 * of the panel alone, so the image does not depend on the threads.
 *
 * The fixed rule is exact only where G_i is analytic on the panel.  It is
 * computed as the integral over the whole line of the colours defined by
 * the pieces near column i (those whose extent in the panel meets the
 * window [uc - R, uc + R]), extended beyond the window on either side:
 * that differs from the true inner integral by at most the filter's mass
 * outside the window, and is a smooth function of those pieces' crossings
 * as long as none of them begins or ends inside the panel, none is flat
 * there, none meets another piece there (tested exactly for pieces whose x
 * is quadratic in y, conservatively for others), none is steeper than
 * |dx/dy| = 1 (a nearly horizontal edge makes G_i change on a scale s /
 * |dx/dy|, too fast for the panel) and they are ordered consistently with
 * the pieces outside.  A column for which any of this fails in a panel
 * marks that panel, and every pixel that needs a marked panel, or whose
 * bound comes out above AA_TRUTH_BOUND / 4, is integrated by QAG as for
 * the other filters.  Uniform pixels are filled in both cases.  On crow
 * (1024 x 1024, s = 0.5) every non-uniform pixel takes the fixed rule; its
 * error bound is the estimate, plus twice the truncated mass (x and v),
 * plus rounding.  The cdf at a crossing comes from a table of Phi and its
 * Taylor coefficients (7 terms, steps of 1/32 standard deviation, error at
 * the rounding level), laid out so that one offset serves every column a
 * crossing is near.  Under QAG, the Gaussian adds as breakpoints the
 * heights where a piece crosses x = uc + k s (without them QAG can miss
 * the steep step of a nearly horizontal edge and still report a small
 * error) and where two arcs meet.
 *
 * The integration runs in coordinates relative to the pixel centre (or,
 * for panels, with crossings split into an exact part and a small one), and
 * the crossings are evaluated in extended precision (long double) from the
 * pieces' control points, so that at 4096 pixels, where an absolute
 * coordinate's last bit is 5e-13 px, the inner integral still carries only
 * rounding of the order of 1e-16.  The winding numbers left of the window
 * are taken at the same height, vc + s exactly (aa_strip_winding_left_at),
 * not at that sum rounded to double: rounded, a piece ending within half an
 * ulp of it was on the wrong side of the line while the local pieces, at s,
 * were not, and between two vertices an ulp apart in height (a stroke's
 * line across it and its join's radius ending at the same point, rounded
 * twice) about half the nodes saw the wrong winding: up to 5.7e-14 a pixel
 * (tests/bench_bezstroke.c's scene at 1024 px) against a bound of 1.8e-14.
 *
 * The cone (radial, not separable; filter.c) takes the QAG path with the
 * row's integral in place of the cdf difference: at height s the spans
 * between crossings are weighed by the closed-form integral of the row
 * over them (aa_filter_row_cdf, which clips them to the disc's chord), so
 * the inner integral stays exact.  Its breakpoints add v = 0, where the
 * row integral has a v^2 log|v| term, the heights where a piece crosses
 * the circle of radius R around the centre (the span's end leaves the
 * chord there and the integrand's second derivative jumps), and v = +-R,
 * where the chord closes like sqrt(R - |v|): the half intervals next to
 * them are integrated in u = sqrt(R - |v|), as at turning points, where
 * the integrand (about (R - |v|)^(3/2)) becomes smooth.  The height where
 * a piece passes closest to the centre, inside the disc, is a breakpoint
 * too, integrated in the square root of the distance to it on both sides
 * (truth_nearest_height): the row integral is singular at the centre, so
 * a piece passing at a distance d makes the inner integral change on the
 * scale d, which QAG's estimate does not see (a nearly horizontal line
 * 1e-4 from the centre came out 7.6e-13 off against an estimate of
 * 1.2e-14; with the breakpoint, 1e-15).
 *
 * A colour scene's pixel is integrated channel by channel, each with its
 * own QAG and its own error estimate, but the channels share the costly
 * part of the integrand: the winding numbers, the crossings and their
 * order at a height s are the same for the three.  Each evaluation computes
 * the three channels' sums in one pass (each with the operations it would
 * take alone) and keeps them in a per-thread memo keyed by the exact bits
 * of s; the second and third channels' QAG visit the same heights, unless
 * their bisection differs, and take the values from it.  A height not in
 * the memo is computed afresh, so every channel's value and estimate are
 * those of integrating it alone, to the bit.  The fixed rule's panels and
 * crowded windows already carry the three channels together.
 *
 * Crowded windows (more than TRUTH_CROWD local pieces, or more than
 * TRUTH_MAX_PAIRS of which two cross inside the window) are taken one
 * piece at a time (truth_crowd.c): the sum over spans is rewritten as the
 * colour at the window's left side plus, for each piece, its colour jump
 * times the filter's weight right of it, and a sweep along v over the
 * window finds where each jump changes; each piece's term is integrated
 * between its own breakpoints only.  The sum over spans would cost the
 * breakpoints of all pieces times all pieces at each evaluation: the
 * square of the pieces (a crow of 65536 arcs 1e-5 apart did not finish
 * 2 x 2 pixels in two minutes).  The patterns' default views never take
 * that path; their references are as before it.
 *
 * Cubic arcs (AA_PIECE_CUBIC) take the same paths.  Their crossings are
 * the roots of y(t) = s by Newton's method in long double, safeguarded by
 * bisection (truth_t_at); their breakpoints are their pieces' ends (the
 * edges are split at the roots of y'(t)), the sqrt-like turning points
 * where y' vanishes at an end, up to three crossings of each kink line
 * (aa_piece_meet_x), the meetings with other pieces (aa_piece_meet: roots
 * of a cubic against a line, Newton-polished bisection on exact extents
 * against an arc), and for the cone the crossings of the circle (degree 6,
 * circle_heights_cubic).  The Gaussian's panels take a cubic where its
 * slope stays under FAST_SLOPE (two quadratics in t positive on the
 * panel's part) and no other piece meets it there (aa_piece_meet); QAG
 * the rest.  Scenes without cubics are computed as before, to the bit.
 *
 * Conic pieces (AA_PIECE_CONIC, arcs of ellipses split at their extremes
 * in y) take the same paths.  A crossing comes from the piece's own angle
 * form in long double: at height s, c = (ey - s)/er and
 *     x = ex + ea c + eb sqrt((1 - c)(1 + c)),
 * with 1 - c = (s - top)/er and 1 + c = (bot - s)/er each taken directly
 * as the distance to the ellipse's top (ey - er) or bottom (ey + er), so
 * that next to a turning point, where the square root is ill-conditioned
 * in s (but the integral is not), the small factor carries no rounding of
 * c (truth_internal.h, truth_conic_part).  Their breakpoints are their
 * pieces' ends (the ends of the arc and its extremes in y: an end within
 * 0.01 of angle 0 or pi is a turning point and its half interval is
 * integrated in u = sqrt(|v - v_end|), which is harmless where x is smooth
 * there), their crossings of the kink lines (aa_piece_meet_x: the angle
 * from an acos), their meetings with other pieces (aa_piece_meet), and for
 * the cone their crossings of the circle of radius R: with the angle
 * a = am + 2 atan(t) over the part of the piece in the disc's rows, the
 * piece is a rational quadratic (qx(t), qy(t))/(1 + t^2), t in [-1, 1],
 * and the crossings are the sign changes of the quartic qx^2 + qy^2 -
 * R^2 (1 + t^2)^2, isolated between the roots of its derivatives and
 * bisected in long double (truth_sign_roots).  In a crowded window the
 * cone's breakpoint where a conic piece passes closest to the centre is a
 * sign change of the quintic w (Q . Q') - 2 t (Q . Q) (w = 1 + t^2, Q the
 * numerators), and any pair with a conic meets as aa_piece_meet finds.
 * The Gaussian's panels send every column near a conic piece to QAG.  At
 * a turning end the piece's height is the extreme's rounded, and under the
 * square root that rounding moves the crossing there by up to sqrt(2 er
 * 1e-16) (3e-9 px at er = 1e-3; its integral is 1e-16 of that): the crowd
 * path, which looks for vertices on the window's left side to 1e-9, takes
 * a piece's end from the scene's own point (it once kept the colour inside
 * a circle of radius 1e-3 below it: 1 off).  Checked against closed forms
 * per pixel (a disk's area in a pixel's square: 5.6e-16 at most; a circle
 * of radius 1e4, 2e-15), as sums (areas under box, tent and a Gaussian
 * whose translates sum to 1; 119 random slices of ellipses), the filters'
 * masses within a radius for centred disks, and the three paths against
 * each other (tests/test_conic.c).
 *
 * Gradient paint (patterns/README.md, "Gradients"), linear gradients under
 * the box filter: along a row a linear gradient's t is linear in x, so
 * between the x where some gradient layer's t passes a stop's offset or a
 * period's end (repeat, reflect) the composite's sRGB-encoded channels are
 * affine in x: each layer's stops interpolate linearly, and compositing
 * (source over, group opacity) is affine in every layer's colour while the
 * alphas are constant; a single gradient with stops of differing opacity
 * keeps it affine as long as it is the scene's only gradient (its alpha
 * then multiplies constants only); other scenes take the path of several
 * gradients (grad_mode).  The composite is read at the quarter and three-quarter
 * points of each such piece (the ends may lie on a jump) and extended
 * linearly to its ends, va and vb, and the piece's integral is its length
 * times the mean of the sRGB decoding over [va, vb] in closed form: v /
 * 12.92 below 0.04045, whose mean is the midpoint's; above, u^2.4 with u =
 * (v + 0.055)/1.055, whose mean is ua^2.4 expm1(3.4 log1p(d)) / (3.4 d),
 * d = (ub - ua)/ua (no cancellation however close va and vb are); a piece
 * straddling 0.04045 is split there.  No pixel is uniform.  The outer
 * integral's breakpoints add the heights where each line t = tau (tau a
 * stop's offset or a period's end, in the window's range of t) crosses the
 * window's sides, and where it meets each local piece (a cubic's roots
 * isolated between its turns and bisected; an arc's from an acos): there
 * the inner integral has a kink when the colour jumps across the line (a
 * sharp stop, repeat) and a jump in its second derivative otherwise.  The
 * decoding's own kink at 0.04045 (its slope goes from 1/12.92 to 0.0789, a
 * 2% step) leaves the inner integral continuously differentiable and is no
 * breakpoint: QAG's bisection takes it.
 *
 * Radial gradients (in scenes without linear ones; a span painted by two
 * takes the path of several gradients; "radial gradient paint" below):
 * along a row t is (b - sqrt(d)) / a, b affine and d quadratic in x, and
 * the decoded colour has no closed-form integral.  The row is cut
 * where t passes a stop's offset or a period's end, where a channel's
 * composite passes 0.04045, and where d is least; each piece takes a
 * 20-point Gauss-Legendre rule with a rigorous bound from the integrand's
 * analyticity in a Bernstein ellipse, halved until the bound is below
 * 2e-16 of its length.  The pixel's bound adds the largest row's bound
 * times the window's height.  The outer integral's breakpoints add, for
 * each such t (the threshold's as the composite at the window's centre
 * has it, and as it would with the gradient's layer covering the
 * centre), where its circle crosses the window's sides, its top and
 * bottom rows (the chord opens there like a square root of the height:
 * turning points, integrated in the square root of the distance), and
 * where it meets each local piece (a
 * polynomial of degree 6 for a cubic, 4 for an arc in the half-angle
 * parameter, its sign changes isolated between its derivative's roots
 * and bisected), and the row of P* where t is least.  Offset pieces
 * (strokes of curves) meet the stop lines and circles as two pieces meet
 * (offset_meets: the line's part across the window's rows as a line
 * piece, the circle, an ellipse in pixels, as its two halves between its
 * top and bottom as conic pieces, against the offset piece by
 * aa_piece_meet).  A window of more than TRUTH_MAX_PAIRS pieces takes the
 * same sum over spans, with the crowd path's sweep (truth_crowd.c,
 * crowd_events) for the heights where pieces meet in place of the pairs:
 * its events (ends, crossings of the window's sides, the meetings of
 * neighbours in the order along x, which find every crossing inside the
 * window) are breakpoints; past GRAD_CROWD_MAX pieces the pixel is
 * refused.
 *
 * Several gradients at a point (radial with linear, two radial ones, a
 * gradient of varying opacity with another: "several gradients" below):
 * the composite is affine in each layer's opacity and opacity times
 * channel, so a sum of products over the layers whose coefficients are
 * read from 3^n composites (n <= GEN_MAX = 5 layers painting a span;
 * from 6 to GEN_LAYERS = 32 the composite is folded layer by layer in
 * painter's order at each point, its bounds carried through the same fold
 * centred at each piece's midpoint: "the fold" below; more are refused).
 * Scenes of at most five layers a span keep the product form, to the bit.
 * The row is cut at every layer's stops, periods' ends and
 * radial x0; the decoding's threshold, now where a composite of several
 * t passes 0.04045, is isolated by bisection with a certified bound on
 * the composite's slope (intervals it cannot clear shrink to 1e-13 and
 * take their midpoint with their width times the slope bound as their
 * error; a midpoint where the composite is 0.04045 in double keeps the
 * interval that holds it: gen_bisect); each piece takes the 20-point rule with the Bernstein-ellipse
 * bound, the ellipse clear of every radial layer's branch points and, on
 * the power piece, of the zeros of e + 0.055 (shown by a bound on e's
 * change over the ellipse).  The outer breakpoints are the union of the
 * layers' own (stop lines and circles as above) and the threshold's
 * heights found by scanning (below); the threshold's curve is no circle
 * then, and between those heights its kink is left to QAG, as the linear
 * path's kink at 0.04045 is.  Its estimate does not always see the kink,
 * so the bound there is not proven: each layer's threshold circles
 * (threshold_taus) are the composite's with the other gradients at their
 * first stops, the threshold only where no other gradient paints, and n
 * identical translucent radial layers (tests/test_gradient.c,
 * test_many_layers_stack) came out up to 6.9e-13 off at 12 layers
 * against a bound of 1.6e-13.  Where radial layers share one t (a stack
 * of one gradient) the curve is a circle of that t again, and its
 * circles, where the composite with every such layer painting at t
 * passes 0.04045, are breakpoints (shared_threshold_taus): the stack
 * within 1.2e-14, inside its bound.  Those t are the roots of the
 * composite, a polynomial in t between the members' stops, built exactly
 * in the Bernstein basis with a bound on its rounding and isolated by
 * subdivision (Descartes' rule of signs), double roots and roots closer
 * than 2^-40 of the piece included (bz_roots); sampled at 64 points a
 * piece, two roots 0.0031 apart in t went unseen and a stack's pixel was
 * 4.8e-13 off against a bound of 9.7e-14, 2.6e-18 now (tests/
 * test_gradient.c, test_stack_close_roots).
 *
 * Where layers of different t mix, the threshold's curve is no circle or
 * line of one t, and its heights are certified by interval boxes
 * (thr_certify) where the window allows, found by a scan elsewhere.
 * Why they matter: the row integral F(y) = int dec(E(x, y)) w dx is analytic between
 * heights where the curve crosses rows transversally (the crossing x(y)
 * is analytic, and each side of it takes one of the decoding's pieces),
 * but not at the heights where the curve is tangent to a row (E = c and
 * dE/dx = 0) or crosses another of the row's cuts (a stop line or
 * circle, a piece, the window's side).  The decoding's slope steps by
 * 0.0013 at c = 0.04045 and its value by 2.3e-9 (IEC 61966-2-1's two
 * pieces do not meet: 0.04045 / 12.92 - (0.09545 / 1.055)^2.4), so at a
 * tangency F has a term 2.3e-9 times the chord, a square root of the
 * height's distance, besides the slope's (y - y0)^(3/2).  A radial
 * gradient at alpha 0.6 over a linear one whose t runs along y, the
 * curve's lowest point (a horizontal tangent) at (7.5, 7.745) in pixel
 * (7, 7) and the curve crossing the stop line y = 7.76 in that pixel,
 * came out 1.6e-12 off GSL's 2-D quadrature of the picture (mpic_pixel,
 * the same to the bit with 8 times its sampling) against a bound of
 * 2.3e-14; given that height as a turning point the pixel came inside
 * its bound, and pixel (6, 7), where the curve crosses the window's side
 * x = 7, stayed 3.5e-13 off against 2.9e-14.  So, in a scene whose
 * gradient layers are not all of one t and where something is
 * translucent (a layer's alpha, a group's opacity or a stop's opacity
 * below 1: else the composite at a point is one layer's paint, of one t,
 * and nothing mixes; scene_translucent; found once a render: thr_setup),
 * each pixel's heights are found as follows.
 *
 * Certified (thr_certify), where every gradient is linear or radial
 * (any number of them in the scene: a span that more than
 * GEN_LAYERS paint is refused as ever): the window's rows between its
 * first and last breakpoints are halved into boxes (across x too where a
 * box is 16 times wider than high and E depends on x there), and on each box E of
 * every channel and dE/dx are bounded in interval arithmetic (each
 * operation's result moved out by 2^-52 of itself and the least
 * subnormal; a layer's t, its paint affine in t on one stop segment (in
 * linear light each channel then encoded, on the side of 0.0031308 its
 * segment keeps to: "gradients in linear light"; across a stop, the
 * encoding of the linear values' range, widened by 3e-8 for its step
 * there), the composite's steps folded: aa_scene_fold, one for the whole window
 * where no piece enters it).  A box is free of events if, for every
 * channel, 0.04045 is outside E's range, or no cut meets the box (a stop
 * line or circle or a period's end of a layer that paints, the window's
 * side, a filter's kink or circle, a radial t whose derivative is not
 * bounded, a piece) and 0 is outside dE/dx's range: the curve then
 * crosses the box's rows transversally, x(y) analytic.  The first layer
 * whose stops cut the box (up to THR_SEG - 1 times) is taken one stop
 * segment at a time, each free as above with E on the segment, its stop
 * lines no cut where E on them (the layer's paint at that t from the
 * segment's side) is off 0.04045: the curve then does not meet them on
 * the box.  In linear light the curve of an opaque ramp (E = C passes
 * 0.04045 at v = 0.0031308073) runs 7e-7 px beside the cut at 0.0031308
 * in a ramp 96 px long, and with those lines always cuts the boxes
 * between them were halved on and on (tests/test_gradient_linrgb_renderers
 * past 75 s of CPU, stopped; 14.5 s so).  Where pieces (a
 * line, a quadratic or cubic arc, a conic piece, an offset piece) enter the window, a
 * layer none of whose pieces meets the box has one winding on it, that
 * at its centre; a piece's x over the box's rows is bounded in interval
 * arithmetic (a polynomial piece over a range of its parameter shown to
 * hold those rows, y(t) increasing; a conic's x over the rows; an offset
 * piece's B + d N or evolute over such a range, B, B', B'' bounded there
 * (offset.c's factored form next to a cubic's end where B' vanishes) and
 * |B'|^2, the evolute's B' x B'' too, shown off 0, else the piece may
 * meet any box of those rows: thr_offset_x), and a
 * layer whose piece may meet the box is taken both covered and not
 * (windings 1 and 0), every combination of up to THR_UNSURE such layers
 * folded, the box cut: free only if 0.04045 is outside E's range under
 * each (thr_box_at).  So the curve meets no piece on a free box, and
 * where it meets one, E = c on the piece, the boxes about that place are
 * halved into slivers; a piece's own ends, turning rows and meetings with
 * another piece or a stop are breakpoints already.  The others are halved until
 * 2^-32 of the window high (THR_SIDE); those left are slivers, their
 * rows merged (and with the rows between where less than 2^-32 of the
 * window apart), their ends breakpoints.  Between slivers F is analytic
 * (every height there lies in boxes shown free), and QAG's estimate is
 * the bound as between any breakpoints.  On a sliver [a, b] the pixel
 * takes F at its middle row m times b - a, with the declared bound (b -
 * a) sup |F(s) - F(m)| plus that row's own: for the box filter, |F(s) -
 * F(m)| <= int |dec(E(x, s)) - dec(E(x, m))| dx <= int (2.3 |E(x, s) -
 * E(x, m)| + 2.4e-9) dx (2.3 bounds the decoding's slope on [0, 1],
 * 2.4e-9 its step), and on each of 256 strips across the window |E(x, s)
 * - E(x, m)| is at most b - a times the largest |dE/dy| on the strip's
 * box (bounded as dE/dx is) where no stop, period's end or piece crosses it,
 * else the width of E's range there (where a piece crosses, each cover's,
 * and over the piece's x on those rows, where the cover may change between
 * s and m, the range over both covers together; a cone's tangent line
 * likewise, painted and not), such a strip halved up to
 * 8 times while that is above 1e-6 (thr_strip).  Under a separable filter the
 * sliver takes G(m), F = w(s) G(s), times the weight's integral over it,
 * with that bound times the weight's peak twice.  Under a radial filter
 * (F(s) = int dec(E(x, s)) w(x, s) dx, w = W(distance) on the mask's
 * chord) |F(s) - F(m)| <= int |w(x, s) - w(x, m)| dx + int w(x, m)
 * |dec(E(x, s)) - dec(E(x, m))| dx: the first at most L |s - m| times
 * the widest chord plus the drop J at the mask's edge times the chords'
 * difference, L bounding |W'| and J the drop per filter in closed form
 * (aa_filter_radial_slope), the second the strips' bound with W at each
 * strip's point nearest the centre (thr_radial_sliver); the sliver takes
 * F(m).  So every height where F is not analytic is a
 * breakpoint or inside a sliver whose bound is proven; a pixel that
 * takes more than 200000 boxes (THR_BOXES) keeps the boxes left whole as
 * slivers, with the same bound over their rows.  A period's end is a cut
 * but no jump for reflect (the paint turns back, continuous), and a
 * layer with no step of the window's fold (outside its region) is left
 * out: taken in, a linear gradient at its reflect end, whose range was
 * taken to hold the first stop's channel too, and the stop line of a
 * layer not painting there made a sliver of pixel (13, 1) in
 * test_several_gradients' "fading linear over linear" 1.3e-11 high with
 * a bound of 1.85 a unit of height (2.4e-11); 2.7e-14 now, as the scan
 * gave.  Its cost: a 48x48 radial gradient at fill-opacity 0.6 over a
 * linear one along y, both of dark stops, under the box (`valgrind
 * --tool=callgrind aabench truth -p svg:file=F --no-cache --threads 1`),
 * 5.06e9 instructions, 6.05e9 with the scan alone (its largest bound
 * 3e-14, 1.7e-13 with the scan, the values within 8.8e-16 of its);
 * tests/test_gradient 42.7 s of user CPU, 44.6 s with the scan alone,
 * tests/test_gradient_cone_filter 33.3 s, 32.1 s, each pair run one
 * after the other on the shared machine (`/usr/bin/time`).  A scene
 * without translucent layers of different t does not enter it (the same
 * image and bounds to the bit).  In windows that edges enter: a 48x48
 * linear gradient under a circle and a path (lines, a quadratic and a
 * cubic arc) of a radial gradient at fill-opacity 0.6 and 0.5, dark
 * stops, 6.52e9 instructions against 5.99e9 with those windows scanned
 * (263 pixels; its largest bound 1.9e-14, 9.8e-14 with the scan, the
 * values within 9.0e-15 of its, each difference inside both bounds);
 * tests/test_gradient 46.2 s of user CPU, 49.3 s before,
 * test_gradient_cone_filter 32.1 s, 36.8 s, not one after the other; in
 * linear light the references of tests/test_gradient_linrgb_renderers
 * 10.9 s, 7.0 s scanned, one after the other.  Where strokes' sides
 * enter (a 48x48 linear gradient under a cubic and a quadratic stroked
 * with a radial gradient at stroke-opacity 0.6 and 0.5, dark stops):
 * 1.92e9 instructions against 2.25e9 with those windows scanned (252
 * pixels; its largest bound 2.2e-14, 6.2e-14 with the scan, the values
 * within 2.7e-16).  A lens of the curve 0.015 px high along a radial
 * stop circle between two of the scan's rows (tests/test_gradient.c,
 * test_mixed_lens) is found: the scan does not see it.
 *
 * Under a radial filter windows that pieces enter are certified as well.
 * Its slivers once took 4 R times the weight's peak a unit of height,
 * only b - a, and those windows were scanned: test_mixed_tangent's
 * picture as a 16x16 document (both layers past the view) under cone:r=1
 * had bounds up to 1.9e-7 (pixel (9, 10)); with the bound above its
 * largest is 1.4e-13 (QAG's, 5.6e-14 at (9, 10)), the values the same to
 * the bit (`aabench truth -p svg:file=F -f cone:r=1 --no-cache -o v.txt
 * --bound b.txt`); with the radial layer on a disc of radius 6, 108
 * pixels scanned then, none now, the values within 4.1e-14 of the scan's
 * (inside both bounds), 2.55e10 instructions against 2.21e10 (`valgrind
 * --tool=callgrind`, --threads 1).
 *
 * The cone case (thr_cone_t): the wedge's linear forms L0, L1 ("the cone
 * case") in intervals over the box decide where the layer paints; a box
 * they show wholly painted takes t = (b + sqrt(L0 L1)) / a, or c / (b -
 * sqrt(L0 L1)) where b keeps below 0 (CONE_NESTED: |L0|^2 for d;
 * CONE_HALF: c / (2 b)), as a jet, tight next to a tangent line where b^2
 * - a c would cancel; one wholly unpainted takes the layer transparent;
 * one a tangent line (or the half-plane's edge) crosses is cut and takes
 * the layer both painted (t over the painted part: each form's range
 * clamped to its sign; across the half-plane's edge t beyond c's least
 * over twice b's greatest towards the pole, whose padded paint is the
 * last or first stop's: thr_paint clamps an unbounded t to the stops,
 * where the whole line's range of t had every stop's colour and the
 * windows along the edge were scanned, 22 of 576 on the 24x24 document
 * of the half-plane below) and not, as a piece's layer is covered and not,
 * up to THR_PART such layers.  A box holding P* is one of those (the
 * wedge), or has d's range reach 0 (CONE_NESTED: t's kink), a cut.  Where
 * the threshold's curve meets a tangent line it touches it: on the
 * painted side t = (b + u) / a, u = sqrt(L0 L1), so across the line L_k
 * = 0 E moves like sqrt(L_k), and the curve is half a parabola that ends
 * on the line, tangent to it, where E on the line (t = b / a) is
 * 0.04045.  Taken as a cut, a box of side h holding the line has E's
 * range about sqrt(h) wide, and the boxes along the line that hold
 * 0.04045 grow like h^(-1/2) in number.  So a box that one line crosses
 * (the other form above 0 on it; thr_cone_line) takes, painted, u t' =
 * (u b' + (L0' L1 + L0 L1') / 2) / a, bounded up to the line, in place
 * of t', and every other layer's derivative times u in [0, U]: u E',
 * whose sign is E''s where u > 0; and the line is a cut of the painted
 * case only where E on it (the layer's paint at b / a over the box) may
 * be 0.04045 (as a stop line bounding a segment is), of the unpainted
 * case always.  The curve then meets the line on no box free of events,
 * and crosses the rows of the painted part transversally there; the
 * boxes about the touching point are halved as about a transversal
 * crossing.  A window of a scene with a cone layer whose boxes still pass
 * THR_CONE_BOXES (50000) or whose slivers' bounds pass THR_CONE_LEFT
 * (1e-13) in all is left to the scan.  On a 24x24 document (a linear
 * gradient along y, #000 to #404040, under a cone-case radial gradient at
 * fill-opacity 0.6, focus (3, 10) and fr 1.5 outside the circle (14, 12)
 * of radius 5, dark stops; green's curve touches the lower line at
 * (3.57, 8.41), blue's at (3.99, 8.35)) 1 pixel of 576 was scanned under
 * the box, 4 under tent:r=1 and cone:r=1, none now; the values within
 * 3.0e-17 of the scan's (1.7e-18 under tent:r=1, 1.7e-17 under
 * cone:r=1), each difference inside both bounds, the others the same to
 * the bit, largest bound 1.7e-13 as before (not at those pixels; 2.9e-14
 * at pixel (3, 8), 1.8e-14 scanned); 2.66e9 instructions against
 * 5.41e9 (`valgrind --tool=callgrind aabench truth -p svg:file=F
 * --no-cache --threads 1`), 6.22e9 against 4.11e10 under tent:r=1,
 * 3.57e10 against 4.91e10 under cone:r=1 (each window left to the scan
 * took its 50000 boxes first).
 * Where a row passes within rounding of the touching point, the place
 * of the threshold next to the line in u (below) lies within 1e-19 of
 * it, and the pieces there have x ranges below x's resolution: under a
 * polynomial weight (tent) the weight's fit over such a piece was 0 / 0
 * and the row was refused (gen_rule_bound).
 * On a 16x16 one (focus (-4, 5), fr 6, outside the circle (36, 11) of
 * radius 6.5: the tangent lines nearly parallel, an arc of the curve
 * between them) 256 pixels were scanned, none now, 3.26e9 instructions
 * against 4.47e9, the values within 1.1e-16, largest bound 1.8e-13 both.
 * The same two layers with the end circle (12, 12) r 3 inside the focal
 * circle (13, 12) r 10 (nested), and with the focal circle (8, 12) r 4
 * touching the end circle (12, 12) r 8 inside (the half-plane x > 4),
 * stops #100000 to #603020: both were refused (a row grazing the curve's
 * lowest point: "a cone beside other gradients"); none of 576 pixels is
 * scanned now for the nested one (largest bound 1.5e-14, 2.69e9
 * instructions; under cone:r=1 none, 8.8e-14; tent:r=1 none, 6.4e-14),
 * for the half-plane none (1.6e-14, 1.77e9), none under cone:r=1 and
 * tent:r=1 (1.0e-13, 6.5e-14).  Its windows beside the edge under those
 * filters (pixels (4, 8), (4, 9)) were scanned until a sliver's strip
 * that a tangent line or the edge crosses took E's range over both cases
 * only over the line's x on the sliver's rows, elsewhere one case's
 * (thr_box, thr_cone_cross: a column's rows are painted alike but where
 * the line passes between them), as a piece's strip does: slivers of
 * 8e-9 px took 2.5e-5 a unit of height, past THR_CONE_LEFT in all.
 *
 * Scanned (thr_heights), elsewhere (an evolute in the window on the half
 * of a cubic next to an end where B' vanishes whose factored form
 * (offset.c) has Q x Q' not shown off 0, thr_offset_stopped; a window of
 * a cone layer left by the boxes, above): between the breakpoints, THR_ROWS = 32 rows a
 * window's height, and one just inside
 * each interval's ends; each row's signature is the count of the
 * threshold's places (gen_section's certified isolation) per channel in
 * each section of the row where layers of different t mix, in the row's
 * order.  Where two consecutive scan rows' signatures differ, the height
 * of the change is bisected to rounding and made a breakpoint (unless
 * within 1e-6 R of one already there, whose own change it is taken to
 * be: THR_NEAR): a place entering or leaving a section is the curve
 * crossing a cut (a stop line or circle, an edge, the window's side), and
 * a total that changes by two is a tangency, made a turning point too.
 * Those three pixels came within 1.1e-16 of the 2-D quadrature with it
 * (tests/test_gradient.c, test_mixed_tangent).  Not certified: a
 * tangency whose two places appear and vanish between two scan rows (a
 * bump of the curve thinner than 1/32 of the window) goes unseen, and
 * the bound there is QAG's estimate, not a proof: such pixels are
 * counted (aa_truth_stats' scanned, printed by `aabench truth`), not
 * refused.  The alternative of cells, a 2-D subdivision of the cells
 * the curve crosses, each taking the power piece across the curve with
 * the error |dec(E) - P(E)| <= 2.3e-9 + 0.0013 |E - c| <= 2.3e-9 +
 * 0.0013 |grad E| sqrt(2) h, needs cells of about h = 1.5e-6 px for
 * 1e-14 along a curve 1 px long with |grad E| ~ 1 / px (the value step
 * alone asks 2 h 2.3e-9 <= 1e-14): 1.3e6 cells a pixel, each with its
 * own rows.
 *
 * Scenes that do not mix take the paths above, to
 * the bit, except that the radial path's test of which layer a span
 * depends on now takes the other gradients as transparent (their
 * stand-in colour, the first stop's at the layer's alpha, could hide a
 * layer behind a translucent gradient).
 *
 * Gradients in linear light (color-interpolation: linearRGB; "gradients
 * in linear light" below): a scene with one takes the path of several
 * gradients for every span.  Such a layer's encoded channel is C =
 * encode(v), v its linear value affine in t; its stops are cut where a
 * channel's v passes 0.0031308 (the encoding's change of piece), so that
 * on each piece C is 12.92 v (affine, as an sRGB stop's) or 1.055 v^(1/2.4)
 * - 0.055, whose branch point v = 0 the ellipse must keep out.
 *
 * Radial gradients of the cone case (the focal circle not strictly inside
 * the end circle; "the cone case" below), under every filter: the row is
 * cut where it crosses the two lines tangent to every circle (d = b^2 -
 * a c is their forms' product); the
 * unpainted stretches take the composite without the layer, the painted
 * ones the cuts above, their pieces next to a tangent line integrated in
 * the square root of the distance to it, where t becomes analytic, with
 * the same rule and bound in that variable.  The outer breakpoints add
 * the tangent lines' crossings of the window's sides and of the pieces
 * and where each stop circle touches them (the circles touching inside,
 * a = 0: the half-plane's edge, where t has a pole, in place of the
 * lines).  Under the other filters the same path carries the row's weight
 * as a factor, the row cut also at the filter's kinks.  Beside other
 * gradients each span takes the path of the layers it depends on ("a
 * cone beside other gradients"); several layers of one cone take their
 * composite, a polynomial in the shared t, on the cone's path ("one cone
 * on several layers"); where the cone and another gradient (a second
 * cone too) paint one point, and for the cone in linear light, the path
 * of several gradients takes it with the cone's cuts (there).
 *
 * The other separable filters (tent, gauss, bspline, mitchell, catrom,
 * lanczos; "the other separable filters" below): every span of a
 * gradient scene takes the path of several gradients with the row's
 * integrand dec(e(x)) w(x - uc), cut also at the filter's kinks; each
 * piece's bound is the colour's times the weight's on the same Bernstein
 * ellipse.  The outer breakpoints add the stop lines' and circles'
 * crossings of every kink line x = uc + k, and, for linear gradients,
 * the lines where the composite at the window's centre passes the
 * decoding's threshold.  The Gaussian's fixed rule is not taken.
 *
 * The cost of that path (gen_piece, gen_section): a piece's bound is
 * sought on up to 14 ellipses, each a bound of the composite on it; the
 * search ends at the first ellipse whose bound is 2^-10 of the piece's
 * tolerance (2e-16 of its length), and the 10-point rule is taken where
 * its own bound, M rho^-20 on the same ellipse, is that small; a piece
 * whose first four ellipses' bounds all exceed 2^10 times the tolerance
 * is halved without trying the rest (under the polynomial filters and
 * the box, above the last depth).  The threshold's places are isolated
 * for the three channels in one halving, which computes the bounds on a
 * segment and the colour at its midpoint once for all three.  Each
 * channel's places are as before, to the bit; so are the pieces, but
 * where the search gave up early (a halving the full search might have
 * spared); a piece's value moves by at most the two rules' bounds (2^-9
 * of the tolerance) and its bound grows by at most 2^-10 of it: the arcs
 * and the stroked curves of tests/test_analytic_gradient.c under tent,
 * the cubic B-spline and Mitchell moved by at most 2.2e-16 a pixel, their
 * bounds by at most 1.2e-18 up (3.8e-17 down, where pieces were halved
 * more; harness/README.md, its figures).
 *
 * The radial filters (cone, cone:cut, gauss with cut, radial:k): every
 * span takes the same path, clipped to the support's chord at the row's
 * height s, with the row's weight w(sqrt(u^2 + s^2)) as the factor: the
 * Gaussian's and the radial polynomials' entire in u, the cone's with
 * branch points at u = +-i |s|, which bound the Bernstein ellipse; the
 * row is cut at uc too.  The outer breakpoints keep the radial filters'
 * own (v = 0, +-R, the pieces' crossings of the circle), and each stop's
 * line or circle adds its crossings of the support's circle and, for the
 * cone, the heights where it passes closest to the centre, as turning
 * points ("the radial filters: the weight along a row").
 *
 * Each pixel carries an error bound: QAG's estimate or the fixed rule's,
 * plus the weight of the Gaussian outside its truncation square, plus the
 * rounding.  Pixels whose window meets no piece are uniform: they take the
 * colour of their centre with no integration.  This path shares nothing
 * with the methods beyond the scene's own queries (the strip tells which
 * pieces are near a window and the winding numbers left of it).
 */
#include "truth.h"
#include "truth_internal.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_poly.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* Pairwise intersections are breakpoints only up to this many local pieces;
 * beyond it a window where pieces cross, and any window of more than
 * TRUTH_CROWD pieces, is taken one piece at a time (truth_crowd.c), whose
 * sweep finds every meeting (truth_internal.h, TRUTH_CROWD). */
#define TRUTH_MAX_PAIRS 48

typedef struct crossing {
    double x;
    int dir, layer;
} crossing;

/* The inner integrals of the three channels at one height s (exact bits),
 * valid while gen is the memo's current generation. */
typedef struct memo_slot {
    uint64_t key;
    unsigned gen;
    double v[3];
} memo_slot;

/* Heights the first channel's QAG evaluated in the current pixel, with all
 * three channels' values: the other channels' QAG visits the same heights
 * and looks them up.  Open addressing (linear probing) in a power of two
 * of slots, grown up to MEMO_MAX_SLOTS; a new generation per pixel empties
 * it without clearing. */
typedef struct memo {
    memo_slot *slot;
    size_t cap, used;
    unsigned gen;
} memo;

#define MEMO_MIN_SLOTS ((size_t)1 << 10)
#define MEMO_MAX_SLOTS ((size_t)1 << 16)

/* A linear gradient layer's t = tx x + ty y + t0 in pixel units, its spread
 * and its stops' offsets. */
typedef struct grad_plane {
    double tx, ty, t0;
    int spread, nstops;
    const aa_gradient_stop *stops;
} grad_plane;

/* A radial gradient of a scene without linear ones (truth.c, "radial
 * gradient paint"): its layer, its stops' encoded channels and
 * opacities (enc[4 k .. 4 k + 3]), the inverse of its map, F, D = C - F,
 * fr, dr = r - fr, a = D.D - dr^2 < 0, P* (px, py in the scene), and a
 * plane holding its spread and stops for grad_taus. */
#define RAD_GL 20 /* Gauss-Legendre nodes of a row's piece */
/* The shorter Gauss-Legendre rules a piece of the path of several
 * gradients takes where its bound allows (gen_piece). */
#define GEN_NLO 1
static const int GEN_LO[GEN_NLO] = {10};
typedef struct grad_radial {
    int layer, spread, nstops;
    const aa_gradient_stop *stops;
    double *enc;
    double inv[6], m[6], fx, fy, Dx, Dy, fr, dr, a, px, py;
    grad_plane plane;
    /* the cone case (aa_gradient_is_cone; "the cone case" below): cone
     * CONE_WEDGE (a > 0: d = L0 L1, the tangent lines' real forms, the
     * painted region where both are >= 0), CONE_NESTED (a < 0, dr < 0:
     * d = L0 L1 with L1 = conj L0, every point painted) or CONE_HALF (a =
     * 0: L0 = b times the sign of dr, the painted half-plane L0 > 0, L1 =
     * 1), else 0; lf[k]:
     * L_k's coefficients of x, y and 1 in pixels, lg[k] of qx, qy and 1
     * in the gradient's coordinates relative to F */
    int cone;
    double complex lf[2][3];
    double lg[2][3];
} grad_radial;
#define CONE_WEDGE 1
#define CONE_NESTED 2
#define CONE_HALF 3

#define GEN_MAX 5 /* gradient layers of one span read as 3^n composites ("several gradients") */
#define GEN_LAYERS 32 /* gradient layers painting one span, folded past GEN_MAX */

/* Any gradient layer for the path of several gradients at a point
 * ("several gradients"): its layer, spread, stops and their encoded
 * channels and opacities (enc[4 k .. 4 k + 3]), and its plane (linear) or
 * radial data. */
typedef struct gen_layer {
    int layer, spread, nstops, own_enc;
    /* lin: the gradient interpolates in linear light ("gradients in linear
     * light"): enc holds the stops' linear-light channels, not encoded */
    int lin;
    const aa_gradient_stop *stops;
    double *enc;
    const grad_plane *gp;
    const grad_radial *rg;
} gen_layer;

/* Most counts one row's signature of the threshold's places holds
 * (thr_heights): past them the pixel keeps its breakpoints. */
#define SIG_MAX 512

/* Most stop lines one pixel's window may meet (a repeating gradient finer
 * than that is refused). */
#define GRAD_MAX_BREAKS 4096
/* Most pieces near a pixel of gradient paint (truth.c's opening comment,
 * crowded windows): past them the pixel is refused. */
#define GRAD_CROWD_MAX 4096

typedef struct worker {
    const aa_scene *scene;
    /* gradient paint (grad set): the linear gradients' planes, and room
     * for the break values of t and the x of one span's pieces */
    int grad;
    grad_plane *gp;
    int ngp;
    double *gbuf;
    size_t cap_gbuf;
    /* a radial gradient (rad set): its rows' Gauss-Legendre nodes and
     * weights on [-1, 1], the current row's error bound and the pixel's
     * largest row bound */
    int rad, nrg;
    grad_radial *rg;
    double gl_x[RAD_GL], gl_w[RAD_GL];
    /* the shorter rules a piece of the path of several gradients may take
     * (gen_piece): GEN_LO[k] nodes and weights on [-1, 1] */
    double glo_x[GEN_NLO][RAD_GL], glo_w[GEN_NLO][RAD_GL];
    double rad_row_err, rad_err_max;
    /* every gradient layer (gl, ngl) with room for its layer and a paint,
     * and a second buffer of t values; gen: every span takes the path of
     * several gradients; gen_over: a span painted by more than GEN_LAYERS;
     * gen_stuck: a row not resolved within the work limit (gen_section,
     * gen_piece) */
    gen_layer *gl;
    int ngl, gen, gen_over, gen_stuck;
    /* scanning a window's rows for the threshold's heights (thr_heights):
     * per section of a span where layers of different t mix, the count
     * of the threshold's places per channel (sig, nsig; sig_over: more
     * than SIG_MAX); gen_mixed: the scene has such layers */
    int scan, sig_over, gen_mixed;
    size_t nsig;
    int sig[SIG_MAX];
    /* cone_mix: a cone-case gradient beside other gradients (each span by
     * mix_span); cone_over: the composite of several layers of one cone
     * whose polynomial's roots were not found (cone_span) */
    int cone_mix, cone_over;
    aa_gradient_stop **lin_stops; /* per layer: a linear-light gradient's stops, cut */
    size_t gen_work; /* gen_piece's halvings on the current span (GEN_PIECES) */
    int *gl_layer;
    double *gl_paint, *gbuf2;
    /* a span of more than GEN_MAX gradient layers: its composite's steps
     * (aa_scene_fold) and, per step, the index of its layer among the
     * span's (fold_sl; -1 a gradient layer taken transparent, -2 a layer
     * of its own colour) */
    aa_fold_step *fold;
    int *fold_sl, cap_fold;
    const aa_filter *f;
    aa_strip *strip;
    gsl_integration_workspace *ws;
    size_t limit;
    double *pts;
    size_t npts, cap_pts;
    /* heights (relative) where a piece turns (x ~ sqrt), grown as needed
     * (a window of many arcs, or a repeating radial gradient's stop
     * circles' top and bottom rows: once capped at 64, the rest left to
     * QAG's estimate); sing_oom: room for one was not had */
    double *sing;
    size_t nsing, cap_sing;
    int sing_oom;
    /* the threshold's events where layers of different t mix (thr_heights,
     * thr_certify): thr_on, the scene has such layers and something
     * translucent; thr_cert, its layers are of the kinds thr_certify takes;
     * the pixel's slivers (pairs of relative heights, nsliv pairs) whose
     * rows take a declared bound (triples: the ends, the bound of |F(s) -
     * F(m)| on them) */
    int thr_on, thr_cert;
    /* thr_cone: the scene has a layer of the cone case; thr_left: the
     * pixel's boxes left it to the scan (thr_boxes) */
    int thr_cone, thr_left;
    double *sliv;
    size_t nsliv, cap_sliv;
    local_piece *lp;
    crossing *cross;
    size_t nlp, cap_lp;
    int *wind;
    double uc, vc, R;
    double row_s; /* the current row's height relative to vc (inner_sums) */
    int channel;
    int shared; /* colour pixel: the channels share each height's crossings */
    memo memo;
    int box;
    int radial; /* not separable (cone): rows weighed by aa_filter_row_cdf */
    int unweighed; /* inner_sums leaves out the row's weight (a sliver's row) */
    gsl_poly_complex_workspace *poly; /* radial: the circle's crossings */
    crowd_worker crowd;               /* crowded pixels (truth_crowd.c) */
    const double *xmeet;              /* gradient paint there: the sweep's events */
    size_t nxmeet;
    int all_crowd;                    /* every pixel there (AA__TRUTH_CROWD) */
    size_t crowded;                   /* pixels it took */
    size_t scanned;                   /* pixels whose threshold heights were scanned */
} worker;

static void worker_free(worker *w)
{
    aa_strip_free(w->strip);
    if (w->ws)
        gsl_integration_workspace_free(w->ws);
    if (w->poly)
        gsl_poly_complex_workspace_free(w->poly);
    free(w->pts);
    free(w->sing);
    free(w->sliv);
    free(w->lp);
    free(w->cross);
    free(w->wind);
    free(w->memo.slot);
    free(w->gp);
    free(w->gbuf);
    for (int k = 0; k < w->nrg; k++)
        free(w->rg[k].enc);
    free(w->rg);
    for (int k = 0; k < w->ngl; k++)
        if (w->gl[k].own_enc)
            free(w->gl[k].enc);
    free(w->gl);
    if (w->lin_stops)
        for (int k = 0; k < aa_scene_layer_count(w->scene); k++)
            free(w->lin_stops[k]);
    free(w->lin_stops);
    free(w->gl_layer);
    free(w->gl_paint);
    free(w->fold);
    free(w->fold_sl);
    free(w->gbuf2);
    crowd_free(&w->crowd);
}

/* ---- gradient paint ---- */

/* The plane of t of gradient g (aa_gradient, linear), whose map m takes
 * gradient coordinates to pixels: t = ((q - P1).(P2 - P1)) / |P2 - P1|^2
 * with q = m^-1(x, y). */
static void grad_plane_of(const aa_gradient *g, grad_plane *gp)
{
    const double *m = g->m, *p = g->p;
    double det = m[0] * m[3] - m[1] * m[2];
    double i0 = m[3] / det, i1 = -m[1] / det, i2 = -m[2] / det, i3 = m[0] / det;
    double i4 = -(i0 * m[4] + i2 * m[5]), i5 = -(i1 * m[4] + i3 * m[5]);
    double dx = p[2] - p[0], dy = p[3] - p[1], l2 = dx * dx + dy * dy;
    gp->tx = (i0 * dx + i1 * dy) / l2;
    gp->ty = (i2 * dx + i3 * dy) / l2;
    gp->t0 = ((i4 - p[0]) * dx + (i5 - p[1]) * dy) / l2;
    gp->spread = g->spread;
    gp->nstops = g->nstops;
    gp->stops = g->stops;
}

/* The values of t in (ta, tb) where the colour of gp is not smooth: its
 * stops' offsets (pad), and for repeat and reflect those of every period
 * (n + o, n + 1 - o) and the periods' ends; at most cap written, the total
 * returned. */
static size_t grad_taus(const grad_plane *gp, double ta, double tb, double *out, size_t cap)
{
    size_t n = 0;
    if (gp->spread == AA_SPREAD_PAD) {
        for (int k = 0; k < gp->nstops; k++) {
            double o = gp->stops[k].offset;
            if (o > ta && o < tb && n++ < cap)
                out[n - 1] = o;
        }
        return n;
    }
    double lo = floor(ta), hi = ceil(tb);
    if (hi - lo > 4.0 * GRAD_MAX_BREAKS)
        return SIZE_MAX; /* refused by the caller */
    for (double p = lo; p <= hi; p++) {
        if (p > ta && p < tb && n++ < cap)
            out[n - 1] = p;
        for (int k = 0; k < gp->nstops; k++) {
            double o = gp->stops[k].offset, v[2] = {p + o, p + 1.0 - o};
            for (int q = 0; q < 2; q++)
                if (v[q] > ta && v[q] < tb && n++ < cap)
                    out[n - 1] = v[q];
        }
    }
    return n;
}

/* The mean of the sRGB decoding over [a, b] (both at least 0.04045): u^2.4
 * with u = (v + 0.055)/1.055, whose integral is 1.055 u^3.4 / 3.4; over
 * the interval that is ua^2.4 ((1 + d)^3.4 - 1) / (3.4 d), d = (ub - ua) /
 * ua, taken through log1p and expm1. */
static double pow_mean(double a, double b)
{
    double ua = (a + 0.055) / 1.055, d = ((b - a) / 1.055) / ua;
    double base = pow(ua, 2.4);
    if (d == 0.0)
        return base;
    return base * expm1(3.4 * log1p(d)) / (3.4 * d);
}

/* The mean of aa_srgb_decode over [va, vb] (either order), exactly: the
 * linear part's mean is its midpoint's, the power part's pow_mean, an
 * interval across 0.04045 split there. */
static double decode_mean(double va, double vb)
{
    const double T = 0.04045;
    if (va > vb) {
        double t = va;
        va = vb, vb = t;
    }
    if (vb <= T)
        return 0.5 * (va + vb) / 12.92;
    if (va >= T)
        return pow_mean(va, vb);
    double lam = (T - va) / (vb - va);
    return lam * 0.5 * (va + T) / 12.92 + (1.0 - lam) * pow_mean(T, vb);
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The integral over the span [xa, xb] (absolute x) of line y, winding
 * w->wind, of each channel of the decoded composite (box: weight 1). */
static void rad_span(worker *w, double xa, double xb, double y, int nch, double *sum);
static void gen_span(worker *w, double xa, double xb, double y, int nch, double *sum);

/* Under a radial filter, the span [*xa, *xb] of the row at height w->row_s
 * from the centre clipped to the support's chord; 0 if nothing is left
 * (or the row misses the support). */
static int chord_clip(const worker *w, double *xa, double *xb)
{
    if (!w->radial)
        return 1;
    double s = w->row_s, R = w->R;
    if (!(fabs(s) < R))
        return 0;
    double hc = sqrt((R - s) * (R + s));
    *xa = fmax(*xa, w->uc - hc), *xb = fmin(*xb, w->uc + hc);
    return *xb > *xa;
}
static void mix_span(worker *w, double xa, double xb, double y, int nch, double *sum);
static void grad_span(worker *w, double xa, double xb, double y, int nch, double *sum)
{
    if (w->cone_mix) {
        mix_span(w, xa, xb, y, nch, sum);
        return;
    }
    if (w->gen) {
        gen_span(w, xa, xb, y, nch, sum);
        return;
    }
    if (w->rad) {
        rad_span(w, xa, xb, y, nch, sum);
        return;
    }
    double *xs = w->gbuf;
    size_t nx = 0;
    xs[nx++] = xa;
    for (int g = 0; g < w->ngp; g++) {
        const grad_plane *gp = &w->gp[g];
        if (gp->tx == 0.0)
            continue; /* t constant along the line */
        double ta = gp->tx * xa + gp->ty * y + gp->t0, tb = gp->tx * xb + gp->ty * y + gp->t0;
        double *taus = xs + nx;
        size_t m = grad_taus(gp, fmin(ta, tb), fmax(ta, tb), taus, w->cap_gbuf - nx - 1);
        if (m > w->cap_gbuf - nx - 1)
            m = w->cap_gbuf - nx - 1; /* cannot happen: sized by the window's range */
        for (size_t k = 0; k < m; k++) {
            double x = (taus[k] - gp->ty * y - gp->t0) / gp->tx;
            if (x > xa && x < xb)
                xs[nx++] = x;
        }
    }
    qsort(xs + 1, nx - 1, sizeof *xs, cmp_dbl);
    xs[nx++] = xb;
    for (size_t k = 0; k + 1 < nx; k++) {
        double a = xs[k], b = xs[k + 1], h = b - a;
        if (!(h > 0.0))
            continue;
        double e1[3], e3[3];
        aa_scene_encoded_of_at(w->scene, w->wind, a + 0.25 * h, y, e1);
        aa_scene_encoded_of_at(w->scene, w->wind, a + 0.75 * h, y, e3);
        for (int ch = 0; ch < nch; ch++) {
            double va = 1.5 * e1[ch] - 0.5 * e3[ch], vb = 1.5 * e3[ch] - 0.5 * e1[ch];
            va = va < 0.0 ? 0.0 : (va > 1.0 ? 1.0 : va);
            vb = vb < 0.0 ? 0.0 : (vb > 1.0 ? 1.0 : vb);
            sum[ch] += h * decode_mean(va, vb);
        }
    }
}

/* The path a gradient scene takes (truth.c's opening comment): 0, linear
 * gradients in closed form (the composite affine along a row between
 * stops: no radial gradient, and no gradient of varying opacity with
 * another); 1, radial gradients only (a span painted by two of them takes
 * the path of several gradients); 2, every span by that path (also any
 * scene with a gradient in linear light). */
static int grad_mode(const aa_scene *scene)
{
    int n = aa_scene_layer_count(scene), ngrad = 0, varying = 0, radial = 0, linear = 0;
    for (int l = 0; l < n; l++) {
        aa_gradient g;
        if (!aa_scene_layer_gradient(scene, l, &g))
            continue;
        ngrad++;
        if (aa_scene_layer_gradient_interpolation(scene, l) != AA_INTERPOLATE_SRGB)
            return 2; /* linear light: gradients in linear light */
        if (g.kind != AA_GRADIENT_LINEAR)
            radial = 1;
        else
            linear = 1;
        for (int k = 1; k < g.nstops; k++)
            if (g.stops[k].opacity != g.stops[0].opacity)
                varying = 1;
    }
    if (radial && linear)
        return 2;
    if (radial)
        return 1;
    return varying && ngrad > 1 ? 2 : 0;
}

static void cone_init(grad_radial *r);

/* The radial gradient g of layer l appended to w->rg. */
static int rad_init(worker *w, int l, const aa_gradient *g, int lin)
{
    if (!w->rg) {
        int n = aa_scene_layer_count(w->scene);
        w->rg = calloc((size_t)(n > 0 ? n : 1), sizeof *w->rg);
        if (!w->rg)
            return aa_fail(AA_ENOMEM, "out of memory for radial gradients");
    }
    grad_radial *r = &w->rg[w->nrg++];
    const double *m = g->m, *p = g->p;
    double det = m[0] * m[3] - m[1] * m[2];
    r->inv[0] = m[3] / det, r->inv[1] = -m[1] / det;
    r->inv[2] = -m[2] / det, r->inv[3] = m[0] / det;
    r->inv[4] = -(r->inv[0] * m[4] + r->inv[2] * m[5]);
    r->inv[5] = -(r->inv[1] * m[4] + r->inv[3] * m[5]);
    memcpy(r->m, m, sizeof r->m);
    r->layer = l, r->spread = g->spread, r->nstops = g->nstops, r->stops = g->stops;
    r->fx = p[3], r->fy = p[4], r->fr = p[5];
    r->Dx = p[0] - p[3], r->Dy = p[1] - p[4], r->dr = p[2] - p[5];
    r->a = r->Dx * r->Dx + r->Dy * r->Dy - r->dr * r->dr;
    double ts = -r->fr / r->dr, qx = r->fx + ts * r->Dx, qy = r->fy + ts * r->Dy;
    r->px = m[0] * qx + m[2] * qy + m[4], r->py = m[1] * qx + m[3] * qy + m[5];
    r->plane.spread = g->spread, r->plane.nstops = g->nstops, r->plane.stops = g->stops;
    if (aa_gradient_is_cone(g))
        cone_init(r);
    r->enc = malloc((size_t)g->nstops * 4 * sizeof *r->enc);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(RAD_GL);
    if (!r->enc || !gl) {
        if (gl)
            gsl_integration_glfixed_table_free(gl);
        return aa_fail(AA_ENOMEM, "out of memory for a radial gradient");
    }
    for (int k = 0; k < g->nstops; k++) {
        for (int c = 0; c < 3; c++)
            r->enc[4 * k + c] = lin ? g->stops[k].colour.c[c] : aa_srgb_encode(g->stops[k].colour.c[c]);
        r->enc[4 * k + 3] = g->stops[k].opacity;
    }
    for (int k = 0; k < RAD_GL; k++)
        gsl_integration_glfixed_point(-1.0, 1.0, (size_t)k, &w->gl_x[k], &w->gl_w[k], gl);
    gsl_integration_glfixed_table_free(gl);
    w->rad = 1;
    gen_layer *q = &w->gl[w->ngl++];
    q->layer = l, q->spread = g->spread, q->nstops = g->nstops, q->stops = g->stops;
    q->enc = r->enc, q->rg = r, q->lin = lin;
    return AA_OK;
}

/* Linear gradient g of layer l appended to w->gp and w->gl. */
static int lin_init(worker *w, int l, const aa_gradient *g, int lin)
{
    grad_plane *gp = &w->gp[w->ngp++];
    grad_plane_of(g, gp);
    gen_layer *q = &w->gl[w->ngl++];
    q->layer = l, q->spread = g->spread, q->nstops = g->nstops, q->stops = g->stops;
    q->gp = gp;
    q->enc = malloc((size_t)g->nstops * 4 * sizeof *q->enc);
    if (!q->enc)
        return aa_fail(AA_ENOMEM, "out of memory for a linear gradient");
    q->own_enc = 1, q->lin = lin;
    for (int k = 0; k < g->nstops; k++) {
        for (int c = 0; c < 3; c++)
            q->enc[4 * k + c] = lin ? g->stops[k].colour.c[c] : aa_srgb_encode(g->stops[k].colour.c[c]);
        q->enc[4 * k + 3] = g->stops[k].opacity;
    }
    return AA_OK;
}

/* ---- gradients in linear light ----
 *
 * A gradient layer in linear light (aa_scene_layer_gradient_interpolation;
 * core.h) paints, at t, the encoded channels C = encode(v(t)) of its
 * stops' linear-light channels v interpolated in t (v affine between
 * stops), with the opacity interpolated as ever; C then composites as any
 * encoded channel does, so the composite keeps the form of "several
 * gradients" with C in place of an affine channel.  The stops are cut
 * where a channel's v passes LIN_T = 0.0031308, the encoding's change of
 * piece (lin_cut_stops: a stop added there with the interpolation's own
 * colour and opacity, so the picture does not change), and the cuts
 * become stop lines and circles like any other: the rows are cut there and
 * the outer integral takes them as breakpoints.  On a piece each channel
 * keeps to one side of LIN_T (decided at the piece's middle): below it C =
 * 12.92 v, affine in t, exactly the sRGB case; above it C = 1.055 v^p -
 * 0.055, p = 1/2.4, analytic wherever Re v > 0 (the principal power; its
 * branch point is v = 0).  The bounds on the Bernstein ellipse (gen_bounds)
 * take |v(z) - v(m)| <= |v1| P A (P bounding |t'| there, the segment from
 * m to z inside the ellipse), and require it below 0.9 v(m): then Re v >
 * 0.1 v(m) on the ellipse, |C| <= 1.055 (v(m) + |v1| P A)^p + 0.055 and
 * |C'| <= 1.055 p (v(m) - |v1| P A)^(p-1) |v1| |t'|; a linear layer's zero
 * of v, a real point of the row, also caps the ellipse's rho (gen_rule_bound).
 * The threshold's isolation takes the same bounds on the real segment and
 * Taylor's test the second derivative, |C''| <= 1.055 p (1 - p) vlo^(p-2)
 * v1^2 t'^2 + 1.055 p vlo^(p-1) |v1| |t''|, vlo = v(m) - |v1| P h
 * (gen_taylor).  The decoding's threshold 0.04045 is where the composite
 * passes it, isolated as ever; for an opaque layer with nothing over it e
 * = C, which passes 0.04045 at v = 0.0031308073, not at LIN_T (the two
 * pieces of IEC 61966-2-1 do not meet exactly), so that is a second cut a
 * few 1e-9 of v from the stop's.  The outer breakpoints where the
 * composite at the window's centre passes 0.04045 (rad_threshold_taus)
 * are placed by the secant of C between the stops, a hint for QAG only.
 */

/* A gradient in linear light: its stops with a stop added inside each
 * segment where a channel's linear value passes LIN_T (the sRGB
 * encoding's change of piece), its colour and opacity there the
 * interpolation's own, so that the picture is the same and each channel
 * stays on one piece of the encoding between stops ("gradients in linear
 * light").  g's stops become them (kept in w->lin_stops[l]). */
#define LIN_T 0.0031308
static int lin_cut_stops(worker *w, int l, aa_gradient *g)
{
    int nl = aa_scene_layer_count(w->scene), n = g->nstops;
    if (!w->lin_stops && !(w->lin_stops = calloc((size_t)(nl > 0 ? nl : 1), sizeof *w->lin_stops)))
        return aa_fail(AA_ENOMEM, "out of memory for a gradient's stops");
    aa_gradient_stop *o = malloc((size_t)(4 * n + 1) * sizeof *o);
    if (!o)
        return aa_fail(AA_ENOMEM, "out of memory for a gradient's stops");
    int m = 0;
    for (int k = 0; k < n; k++) {
        o[m++] = g->stops[k];
        if (k + 1 == n || !(g->stops[k + 1].offset > g->stops[k].offset))
            continue;
        const aa_gradient_stop *a = &g->stops[k], *b = &g->stops[k + 1];
        double f[3];
        int nf = 0;
        for (int c = 0; c < 3; c++) {
            double la = a->colour.c[c], lb = b->colour.c[c];
            if ((la < LIN_T && lb > LIN_T) || (la > LIN_T && lb < LIN_T))
                f[nf++] = (LIN_T - la) / (lb - la);
        }
        for (int i = 1; i < nf; i++) /* sorted (three at most) */
            for (int j = i; j > 0 && f[j] < f[j - 1]; j--) {
                double tmp = f[j];
                f[j] = f[j - 1], f[j - 1] = tmp;
            }
        for (int i = 0; i < nf; i++) {
            if (i > 0 && f[i] == f[i - 1])
                continue;
            aa_gradient_stop *q = &o[m++];
            q->offset = a->offset + f[i] * (b->offset - a->offset);
            if (!(q->offset > o[m - 2].offset && q->offset < b->offset)) {
                m--; /* rounded onto a stop: that stop is the cut */
                continue;
            }
            for (int c = 0; c < 3; c++)
                q->colour.c[c] = a->colour.c[c] + f[i] * (b->colour.c[c] - a->colour.c[c]);
            q->opacity = a->opacity + f[i] * (b->opacity - a->opacity);
        }
    }
    w->lin_stops[l] = o;
    g->stops = o, g->nstops = m;
    return AA_OK;
}

static void thr_setup(worker *w);

static int grad_init(worker *w)
{
    int n = aa_scene_layer_count(w->scene);
    size_t nn = (size_t)(n > 0 ? n : 1);
    w->gp = calloc(nn, sizeof *w->gp);
    w->gl = calloc(nn, sizeof *w->gl);
    w->gl_layer = calloc(nn, sizeof *w->gl_layer);
    w->gl_paint = calloc(4 * nn, sizeof *w->gl_paint);
    w->cap_gbuf = 4 * GRAD_MAX_BREAKS + 8;
    w->gbuf = malloc(w->cap_gbuf * sizeof *w->gbuf);
    w->gbuf2 = malloc(w->cap_gbuf * sizeof *w->gbuf2);
    w->cap_fold = aa_scene_fold_cap(w->scene) + 1;
    w->fold = malloc((size_t)w->cap_fold * sizeof *w->fold);
    w->fold_sl = malloc((size_t)w->cap_fold * sizeof *w->fold_sl);
    if (!w->gp || !w->gl || !w->gl_layer || !w->gl_paint || !w->gbuf || !w->gbuf2 || !w->fold ||
        !w->fold_sl)
        return aa_fail(AA_ENOMEM, "out of memory for gradient planes");
    int ngrad = 0, cone = 0;
    for (int l = 0; l < n; l++) {
        aa_gradient g;
        ngrad += aa_scene_layer_gradient(w->scene, l, &g);
    }
    for (int l = 0; l < n; l++) {
        aa_gradient g;
        if (!aa_scene_layer_gradient(w->scene, l, &g))
            continue;
        if (aa_gradient_is_cone(&g)) /* "the cone case" */
            cone = 1;
        int lin = aa_scene_layer_gradient_interpolation(w->scene, l) != AA_INTERPOLATE_SRGB, st;
        if (lin && (st = lin_cut_stops(w, l, &g)))
            return st;
        st = g.kind == AA_GRADIENT_LINEAR ? lin_init(w, l, &g, lin) : rad_init(w, l, &g, lin);
        if (st)
            return st;
    }
    for (int k = 0; k < w->ngl; k++)
        w->gl_layer[k] = w->gl[k].layer;
    gsl_integration_glfixed_table *gt = gsl_integration_glfixed_table_alloc(RAD_GL);
    if (!gt)
        return aa_fail(AA_ENOMEM, "out of memory for a Gauss-Legendre table");
    for (int k = 0; k < RAD_GL; k++)
        gsl_integration_glfixed_point(-1.0, 1.0, (size_t)k, &w->gl_x[k], &w->gl_w[k], gt);
    gsl_integration_glfixed_table_free(gt);
    for (int r = 0; r < GEN_NLO; r++) {
        if (!(gt = gsl_integration_glfixed_table_alloc((size_t)GEN_LO[r])))
            return aa_fail(AA_ENOMEM, "out of memory for a Gauss-Legendre table");
        for (int k = 0; k < GEN_LO[r]; k++)
            gsl_integration_glfixed_point(-1.0, 1.0, (size_t)k, &w->glo_x[r][k], &w->glo_w[r][k],
                                          gt);
        gsl_integration_glfixed_table_free(gt);
    }
    /* under the other filters every span takes the path of several
     * gradients, which carries the weight ("the other separable
     * filters"), but the cone case's, which carries it on its own path
     * ("the cone case") */
    w->gen = grad_mode(w->scene) == 2 || (!w->box && !cone);
    /* a cone beside other gradients: each span by the layer it depends
     * on ("a cone beside other gradients") */
    w->cone_mix = cone && ngrad > 1;
    w->grad = 1;
    thr_setup(w);
    return AA_OK;
}

/* The roots in [0, 1] of c0 + c1 t + c2 t^2 + c3 t^3, isolated between
 * its turns and bisected; at most 3 into ts. */
static int cubic_roots01(const double c[4], double ts[3])
{
    double cut[4] = {0.0, 0.0, 0.0, 0.0}, r0, r1;
    int nc = 0, n = 0;
    cut[nc++] = 0.0;
    int m = gsl_poly_solve_quadratic(3.0 * c[3], 2.0 * c[2], c[1], &r0, &r1);
    if (m > 0 && r0 > 0.0 && r0 < 1.0)
        cut[nc++] = r0;
    if (m > 1 && r1 > cut[nc - 1] && r1 < 1.0)
        cut[nc++] = r1;
    cut[nc++] = 1.0;
    for (int k = 0; k + 1 < nc; k++) {
        double a = cut[k], b = cut[k + 1];
        double fa = c[0] + a * (c[1] + a * (c[2] + a * c[3]));
        double fb = c[0] + b * (c[1] + b * (c[2] + b * c[3]));
        if (fa == 0.0) {
            if (!n || ts[n - 1] != a)
                ts[n++] = a;
            continue;
        }
        if ((fa < 0.0) == (fb < 0.0) || fb == 0.0)
            continue;
        for (int it = 0; it < 200 && b - a > 0.0; it++) {
            double mid = 0.5 * (a + b);
            if (mid <= a || mid >= b)
                break;
            double fm = c[0] + mid * (c[1] + mid * (c[2] + mid * c[3]));
            if ((fm < 0.0) == (fa < 0.0))
                a = mid, fa = fm;
            else
                b = mid;
        }
        ts[n++] = 0.5 * (a + b);
    }
    return n;
}

/* Breakpoints of gradient paint (truth.c's opening comment): where each
 * line t = tau of the window's range crosses the window's sides and meets
 * a local piece. */
static int add_abs(worker *w, double y, double lo, double hi);

/* ---- radial gradient paint ----
 *
 * A radial gradient (in a scene of radial gradients only, each span
 * painted by one of them at most: rad_span) along the row y: with q(x)
 * = m^-1(x, y) - F, D = C - F, dr = r - fr, t is the larger root of
 *     a t^2 - 2 b(x) t + c(x) = 0,   a = D.D - dr^2 < 0,
 *     b(x) = q.D + fr dr = b0 + b1 x,  c(x) = |q|^2 - fr^2 (quadratic),
 * t = (b - sqrt(d)) / a with d = b^2 - a c = d0 + d1 x + d2 x^2, d2 > 0
 * (aabench.h, aa_gradient).  d has no real zero except where the row
 * passes through the point P* = F - (fr / dr) D, where t takes its least
 * value -fr/dr (the degenerate circle's centre; the focus when fr = 0):
 * there d has a double zero at x0 = -d1 / (2 d2) and t a kink.  Elsewhere
 * t is analytic on the real line, with branch points at x0 +- i sqrt(dmin
 * / d2), dmin = d(x0).
 *
 * The row is cut where t passes a stop's offset or a period's end (the x
 * where c - 2 tau b + a tau^2 = 0 with fr + tau dr >= 0, a quadratic), at
 * x0, and where a channel's composite passes 0.04045, the sRGB decoding's
 * change of piece.  On each piece the layer's encoded channels and opacity
 * are affine in t and the composite e (aa_scene_encoded_with: K0 + K1 op +
 * K2 op C, read at three paints) is a polynomial E(t) of degree 2 at most;
 * the integrand f = dec(E(t(x))) is then analytic where d != 0 and, on the
 * power piece, E + 0.055 != 0, i.e. away from finitely many points: the
 * roots of d and the z where t(z) = tau0 for each root tau0 of E + 0.055
 * (c(z) - 2 tau0 b(z) + a tau0^2 = 0, solved in complex arithmetic; the
 * roots of the other branch are kept too, which only narrows the region).
 *
 * The piece [p, q] (mid m, half-length h) takes the 20-point Gauss-Legendre
 * rule, whose error for f analytic inside the Bernstein ellipse E_rho (foci
 * p and q, semi-axes sum rho h) and bounded there by M is at most
 *     h (64/15) M rho^(-40) / (rho^2 - 1)
 * (Trefethen, Approximation Theory and Approximation Practice, Thm 19.3,
 * scaled from [-1, 1]).  rho ranges below the ellipse through the nearest
 * excluded point, and M is bounded by the triangle inequality: on E_rho,
 * |z - x0| <= |m - x0| + h (rho + 1/rho)/2 = Z, |d(z)| <= d2 Z^2 + |dmin|,
 * |t(z)| <= (|b(m)| + |b1| h (rho + 1/rho)/2 + sqrt(d2 Z^2 + |dmin|)) / |a|
 * = T, |E| <= |E0| + |E1| T + |E2| T^2, and M = ((|E| + 0.055)/1.055)^2.4
 * or |E| / 12.92.  The least of the bounds at seven rho is taken; a piece
 * whose bound exceeds 2e-16 of its length is halved, down to 48 levels,
 * past which it keeps its length as the bound (f lies in [0, 1]).  The
 * row's bounds add up, and the pixel's bound adds the largest row's times
 * the window's height (integrate_pixel).  The bound is rigorous as
 * mathematics and computed in double, its own rounding not counted but
 * dmin's (RAD_DMIN_ULPS, the branch points' distance from it lowered); the
 * rounding of the nodes' values (a few ulps each, the weights summing to
 * 2) is within the gradient term of 64 ulps per unit of the window's width
 * that integrate_pixel adds.  A pixel whose pieces cannot reach the
 * target within 48 halvings (a row passing within about 1e-14 px of P*)
 * carries the larger bound, honestly.
 */
#define RAD_DEPTH 48
/* dmin's rounding (rad_row_at), ulps of dmin itself, the row's p0 and u as
 * formed in double (their own rounding, about an ulp of the coordinates
 * in the row's place relative to P*, not counted): counted in the bounds
 * (rad_bound, gen_layer_tp, gen_tpq), the branch points' distance from
 * dmin lowered by it (gen_rho's largest ellipse is taken from the
 * distance as it is; gen_layer_tp refuses an ellipse that reaches the
 * lowered one) and |t|'s bound from dmin raised */
#define RAD_DMIN_ULPS 16.0

typedef struct rad_row {
    double y, b0, b1, c0, c1, c2, d0, d1, d2, x0, dmin;
    double de; /* dmin's rounding: RAD_DMIN_ULPS of it (0 in the cone case, not read) */
} rad_row;

/* The row's coefficients: q(x) = (ux x + u0, vx x + v0). */
static void rad_row_at(const grad_radial *g, double y, rad_row *r)
{
    double ux = g->inv[0], vx = g->inv[1];
    double u0 = g->inv[2] * y + g->inv[4] - g->fx, v0 = g->inv[3] * y + g->inv[5] - g->fy;
    r->y = y;
    r->b1 = ux * g->Dx + vx * g->Dy;
    r->b0 = u0 * g->Dx + v0 * g->Dy + g->fr * g->dr;
    r->c2 = ux * ux + vx * vx;
    r->c1 = 2.0 * (ux * u0 + vx * v0);
    r->c0 = u0 * u0 + v0 * v0 - g->fr * g->fr;
    r->d2 = r->b1 * r->b1 - g->a * r->c2;
    r->d1 = 2.0 * r->b0 * r->b1 - g->a * r->c1;
    r->d0 = r->b0 * r->b0 - g->a * r->c0;
    r->x0 = -r->d1 / (2.0 * r->d2);
    if (g->cone || !(g->a < 0.0 && g->dr > 0.0)) {
        /* the cone case (a >= 0, or dr < 0) reads its tangent lines, not
         * dmin, and has no P* of this form where dr = 0 */
        r->dmin = r->d0 - r->d1 * r->d1 / (4.0 * r->d2);
        r->de = 0.0;
        return;
    }
    /* d0 - d1^2 / (4 d2) cancels near P*, where dmin is near 0 and its
     * terms are not.  With p = q - P* (P* = -(fr / dr) D relative to F),
     * b = p.D - (fr / dr) a and d = b^2 - a c = (p.D)^2 - a |p|^2 = p^T A
     * p, A = D D^T - a I (the constants cancel as a = |D|^2 - dr^2); along
     * the row p = p0 + x u, u = (ux, vx), d2 = u^T A u, and by Lagrange's
     * identity for a symmetric 2x2 A, dmin = (p0^T A p0 u^T A u - (p0^T A
     * u)^2) / d2 = det(A) (p0 x u)^2 / d2, det(A) = -a dr^2 > 0.  p0 x u
     * as Kahan's difference of products (fma: within 2 ulps of the p0
     * formed here), so dmin is within a few ulps of itself (RAD_DMIN_ULPS)
     * of the p0 and u the other coefficients take. */
    double k = g->fr / g->dr, px = u0 + k * g->Dx, py = v0 + k * g->Dy, w = py * ux;
    double cr = fma(px, vx, -w) + fma(-py, ux, w);
    r->dmin = -g->a * (g->dr * g->dr) * (cr * cr) / r->d2;
    r->de = RAD_DMIN_ULPS * DBL_EPSILON * r->dmin;
}

/* t at (x, y), as the scene computes it (aa__gradient_t): no cancellation. */
static double rad_t(const grad_radial *g, double x, double y)
{
    double qx = g->inv[0] * x + g->inv[2] * y + g->inv[4] - g->fx;
    double qy = g->inv[1] * x + g->inv[3] * y + g->inv[5] - g->fy;
    double b = qx * g->Dx + qy * g->Dy + g->fr * g->dr;
    double c = qx * qx + qy * qy - g->fr * g->fr;
    double disc = b * b - g->a * c;
    double sq = sqrt(disc > 0.0 ? disc : 0.0);
    return b > 0.0 ? c / (b + sq) : (b - sq) / g->a;
}

/* The x in (xa, xb) of row r where t = tau (none where the circle of tau
 * has negative radius); returns how many (0 to 2) into xs. */
static int rad_cross(const grad_radial *g, const rad_row *r, double tau, double xa, double xb,
                     double *xs)
{
    if (g->fr + tau * g->dr < 0.0)
        return 0;
    double x[2];
    int n = gsl_poly_solve_quadratic(r->c2, r->c1 - 2.0 * tau * r->b1,
                                     r->c0 - 2.0 * tau * r->b0 + g->a * tau * tau, &x[0], &x[1]),
        m = 0;
    for (int k = 0; k < n; k++)
        if (x[k] > xa && x[k] < xb)
            xs[m++] = x[k];
    return m;
}

/* t at s along row y (col 0: the point (s, y)) or column y (col 1: (y,
 * s)). */
static inline double rad_t_on(const grad_radial *g, int col, double s, double y)
{
    return col ? rad_t(g, y, s) : rad_t(g, s, y);
}

/* The least t over [xa, xb] of row y, or with col of column y over [xa,
 * xb] in y (t is quasiconvex: its sublevel sets are discs), by golden
 * section. */
static double rad_line_min(const grad_radial *g, int col, double xa, double xb, double y)
{
    const double k = 0.5 * (3.0 - sqrt(5.0));
    double a = xa, b = xb, c = a + k * (b - a), d = b - k * (b - a);
    double fc = rad_t_on(g, col, c, y), fd = rad_t_on(g, col, d, y);
    for (int it = 0; it < 90 && b - a > 1e-15 * (1.0 + fabs(a)); it++) {
        if (fc <= fd)
            b = d, d = c, fd = fc, c = a + k * (b - a), fc = rad_t_on(g, col, c, y);
        else
            a = c, c = d, fc = fd, d = b - k * (b - a), fd = rad_t_on(g, col, d, y);
    }
    return fmin(fmin(rad_t_on(g, col, xa, y), rad_t_on(g, col, xb, y)), fmin(fc, fd));
}

static double rad_row_min(const grad_radial *g, double xa, double xb, double y)
{
    return rad_line_min(g, 0, xa, xb, y);
}

/* The spread's linear form s = sg t + s0 on the piece whose t at its
 * middle is tm (aa__gradient_spread), and the layer's encoded channels and
 * opacity there as v0[c] + v1[c] t (aa__gradient_paint). */
static void paint_lin(int spread, const aa_gradient_stop *st, int n, const double *enc, double tm,
                      double v0[4], double v1[4])
{
    double sg = 1.0, s0 = 0.0;
    if (spread == AA_SPREAD_REPEAT)
        s0 = -floor(tm);
    else if (spread == AA_SPREAD_REFLECT) {
        double n2 = 2.0 * floor(0.5 * tm), f = tm - n2;
        if (f <= 1.0)
            s0 = -n2;
        else
            sg = -1.0, s0 = 2.0 + n2;
    } else if (tm < 0.0)
        sg = 0.0, s0 = 0.0;
    else if (tm > 1.0)
        sg = 0.0, s0 = 1.0;
    double sm = sg * tm + s0;
    if (!(sm >= st[0].offset) || sm >= st[n - 1].offset) {
        int k = sm >= st[n - 1].offset ? n - 1 : 0;
        for (int c = 0; c < 4; c++)
            v0[c] = enc[4 * k + c], v1[c] = 0.0;
        return;
    }
    int k = 0;
    while (k + 1 < n && st[k + 1].offset <= sm)
        k++;
    double w = st[k + 1].offset - st[k].offset;
    for (int c = 0; c < 4; c++) {
        double de = (enc[4 * k + 4 + c] - enc[4 * k + c]) / w;
        v1[c] = de * sg;
        v0[c] = enc[4 * k + c] + de * (s0 - st[k].offset);
    }
}

static void rad_paint_lin(const grad_radial *g, double tm, double v0[4], double v1[4])
{
    paint_lin(g->spread, g->stops, g->nstops, g->enc, tm, v0, v1);
}

/* The Bernstein parameter of z for [m - h, m + h]: the rho of the ellipse
 * through z. */
static double rad_rho(double complex z, double m, double h)
{
    double complex w = (z - m) / h;
    double r = cabs(w + csqrt(w - 1.0) * csqrt(w + 1.0));
    return r >= 1.0 ? r : 1.0 / r;
}

/* One channel on one piece: E0 + E1 t + ... + E_deg t^deg (deg 2 but
 * for several layers of one cone-case gradient, "one cone on several
 * layers"), its decoding's piece. */
#define CHAN_DEG (2 * GEN_MAX)
typedef struct rad_chan {
    double E[CHAN_DEG + 1];
    int deg, power;
} rad_chan;

/* E(t) of channel ch (Horner). */
static double chan_at(const rad_chan *ch, double t)
{
    double e = ch->E[ch->deg];
    for (int k = ch->deg - 1; k >= 0; k--)
        e = ch->E[k] + t * e;
    return e;
}

/* The roots of E(t) + add of channel ch, complex, into tau (at most
 * ch->deg); how many.  Degree above 2: GSL's companion-matrix solver,
 * each root then polished by Newton's method. */
static int chan_roots(const rad_chan *ch, double add, double complex *tau)
{
    double c[CHAN_DEG + 1];
    int n = ch->deg;
    memcpy(c, ch->E, (size_t)(n + 1) * sizeof *c);
    c[0] += add;
    while (n > 0 && c[n] == 0.0)
        n--;
    if (n == 0)
        return 0;
    if (n == 1) {
        tau[0] = -c[0] / c[1];
        return 1;
    }
    if (n == 2) {
        double complex sq = csqrt((double complex)(c[1] * c[1] - 4.0 * c[2] * c[0]));
        tau[0] = (-c[1] + sq) / (2.0 * c[2]);
        tau[1] = (-c[1] - sq) / (2.0 * c[2]);
        return 2;
    }
    double z[2 * CHAN_DEG];
    gsl_poly_complex_workspace *ws = gsl_poly_complex_workspace_alloc((size_t)n + 1);
    int ok = ws && gsl_poly_complex_solve(c, (size_t)n + 1, ws, z) == GSL_SUCCESS;
    if (ws)
        gsl_poly_complex_workspace_free(ws);
    if (!ok) /* no roots known: the caller's bound must not trust them */
        return -1;
    for (int k = 0; k < n; k++) {
        double complex r = z[2 * k] + _Complex_I * z[2 * k + 1];
        for (int it = 0; it < 3; it++) {
            double complex p = c[n], d = 0.0;
            for (int q = n - 1; q >= 0; q--)
                d = d * r + p, p = p * r + c[q];
            if (d == 0.0)
                break;
            r -= p / d;
        }
        tau[k] = r;
    }
    return n;
}

/* The x where E(t) + 0.055 = 0 for channel ch on its power piece: for each
 * (complex) root tau0 of E(t) + 0.055, both roots in x of row r's circle
 * quadratic at t = tau0; at most 2 deg into x, tau0 beside each in tau;
 * -1 if the roots are not known (chan_roots). */
static int rad_ezeros(const grad_radial *g, const rad_row *r, const rad_chan *ch,
                      double complex *tau, double complex *x)
{
    double complex taus[CHAN_DEG];
    int nt = chan_roots(ch, 0.055, taus), n = 0;
    if (nt < 0)
        return -1;
    for (int k = 0; k < nt; k++) {
        double complex t0 = taus[k], A2 = r->c2, A1 = r->c1 - 2.0 * t0 * r->b1,
                       A0 = r->c0 - 2.0 * t0 * r->b0 + g->a * t0 * t0;
        double complex sq = csqrt(A1 * A1 - 4.0 * A2 * A0);
        tau[n] = t0, x[n++] = (-A1 + sq) / (2.0 * A2);
        tau[n] = t0, x[n++] = (-A1 - sq) / (2.0 * A2);
    }
    return n;
}

/* The error bound of the Gauss-Legendre rule for channel ch on [m - h,
 * m + h] of row r (the comment above). */
static double rad_bound(const grad_radial *g, const rad_row *r, const rad_chan *ch, double m,
                        double h)
{
    double complex ex[6];
    int ne = 0;
    double dmin = fabs(r->dmin), dhi = dmin + r->de;
    double dlo = r->dmin >= 0.0 ? dmin - r->de : dmin;
    double sd = sqrt(dlo / r->d2);
    if (r->dmin >= 0.0) {
        ex[ne++] = r->x0 + _Complex_I * sd;
        ex[ne++] = r->x0 - _Complex_I * sd;
    } else {
        ex[ne++] = r->x0 + sd;
        ex[ne++] = r->x0 - sd;
    }
    if (ch->power) {
        double complex taus[4];
        ne += rad_ezeros(g, r, ch, taus, ex + ne);
    }
    double rmax = INFINITY;
    for (int k = 0; k < ne; k++)
        rmax = fmin(rmax, rad_rho(ex[k], m, h));
    if (!(rmax > 1.0 + 1e-9))
        return INFINITY;
    if (rmax > 64.0)
        rmax = 64.0;
    double best = INFINITY, bm = fabs(r->b0 + r->b1 * m);
    for (int k = 1; k < 8; k++) {
        double rho = 1.0 + (rmax - 1.0) * k / 8.0, semi = 0.5 * h * (rho + 1.0 / rho);
        double Z = fabs(m - r->x0) + semi;
        double T = (bm + fabs(r->b1) * semi + sqrt(r->d2 * Z * Z + dhi)) / fabs(g->a);
        double E = fabs(ch->E[0]) + fabs(ch->E[1]) * T + fabs(ch->E[2]) * T * T;
        double M = ch->power ? pow((E + 0.055) / 1.055, 2.4) : E / 12.92;
        double b = h * (64.0 / 15.0) * M * pow(rho, -2.0 * RAD_GL) / (rho * rho - 1.0);
        best = fmin(best, b);
    }
    return best;
}

/* The integral of the channels over [xa, xb] of row r (one piece), to
 * the bound, halving where needed; the bounds added into *err. */
static void rad_piece(worker *w, const grad_radial *g, const rad_row *r, const rad_chan *ch,
                      int nch, double xa, double xb, int depth, double *sum, double *err)
{
    double m = 0.5 * (xa + xb), h = 0.5 * (xb - xa), worst = 0.0;
    for (int c = 0; c < nch; c++)
        worst = fmax(worst, rad_bound(g, r, &ch[c], m, h));
    if (worst > 2e-16 * (xb - xa) && depth < RAD_DEPTH) {
        rad_piece(w, g, r, ch, nch, xa, m, depth + 1, sum, err);
        rad_piece(w, g, r, ch, nch, m, xb, depth + 1, sum, err);
        return;
    }
    double part[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < RAD_GL; k++) {
        double t = rad_t(g, m + h * w->gl_x[k], r->y);
        for (int c = 0; c < nch; c++) {
            double e = ch[c].E[0] + t * (ch[c].E[1] + t * ch[c].E[2]);
            double v = ch[c].power ? pow((e + 0.055) / 1.055, 2.4) : e / 12.92;
            part[c] += w->gl_w[k] * v;
        }
    }
    for (int c = 0; c < nch; c++)
        sum[c] += h * part[c];
    *err += fmin(worst, xb - xa);
}


/* A span's gradient layers with the row's data and, on a piece, each
 * layer's paint v0 + v1 t. */
typedef struct gen_span_ctx {
    int n, nch;
    const gen_layer *L[GEN_LAYERS];
    rad_row row[GEN_LAYERS];
    double v0[GEN_LAYERS][4], v1[GEN_LAYERS][4];
    /* pw[l][ch]: layer l's channel ch is in linear light on the encoding's
     * power piece here, v0 + v1 t its linear value and the encoded channel
     * lin_enc of it ("gradients in linear light"); 0: the encoded channel
     * is v0 + v1 t itself */
    int pw[GEN_LAYERS][3];
    /* enc0[l][ch]: lin_enc(v0) where pw[l][ch] and v1 = 0 (a stop's
     * colour held, or a channel the stops keep), the encoded channel at
     * every x of the piece whose t is finite (v0 + 0 t is v0 there) */
    double enc0[GEN_LAYERS][3];
    double K[3][243];
    int nk;
    /* K's nonzero terms of each channel, in a's order (gen_terms): term i
     * is tk[ch][i] times the product over its layers of nonzero index,
     * tl[ch][i][0 .. tn[ch][i] - 1] in l's order, their indices td (an
     * index 0's factor is 1: left out, the products the same bits) */
    int nt[3], tfin[3];
    double tk[3][243];
    unsigned char tn[3][243], tl[3][243][GEN_MAX], td[3][243][GEN_MAX];
    /* fold: more than GEN_MAX layers, the composite folded over the
     * scene's steps st[0 .. nst - 1] from base (sl: worker's fold_sl; the
     * comment above "several gradients at a point") in place of K */
    int fold, nst;
    const aa_fold_step *st;
    const int *sl;
    double base[3];
    double y;
    /* weighted: the separable filter's weight w(x - uc) multiplies the
     * row (every filter but the box; "the other separable filters") */
    int weighted;
    const aa_filter *f;
    double uc;
    /* radial: the weight is the radial filter's row at height s (relative
     * to the pixel's centre), wn its value at the centre ("radial
     * filters") */
    int radial;
    double s, wn;
    /* a cone-case layer ("a cone beside other gradients"): its L_k = lam
     * x + mu on the row; flat[l]: the layer's paint is constant on the
     * piece (unpainted, or padded beyond its stops), t then not read */
    double complex lam[GEN_LAYERS][2], mu[GEN_LAYERS][2];
    int flat[GEN_LAYERS];
    /* umode: the piece's variable is u, x = xr + eps u^2, from the zero
     * of layer ul's form L_uk (painted on the piece), where sqrt(d) = u
     * sqrt(P0 + P1 u^2); else the variable is x */
    int umode, ul;
    double xr, eps, P0, P1;
    /* in u: the x range of the whole stretch taken in u, sxm +- sxh (one
     * piece of a polynomial weight: the row is cut at its kinks) */
    double sxm, sxh;
    /* uroot[l]: layer l is of the same cone as ul (the same forms) and
     * takes ul's sqrt(d) = u sqrt(P) on the piece in u */
    int uroot[GEN_LAYERS];
} gen_span_ctx;

/* The weight along a row under a filter other than the box ("the other
 * separable filters", "the radial filters: the weight along a row"). */
static double rwt(const gen_span_ctx *c, double u);
static void wt_poly(const gen_span_ctx *c, double m, double h, double a[4]);
static double wt_bound(const gen_span_ctx *c, const double *a, double m, double h, double A,
                       double B);
static void wt_real(const gen_span_ctx *c, double m, double h, double *sup, double *slope);

/* ---- the cone case ----
 *
 * A radial gradient whose focal circle is not strictly inside its end
 * circle (aa_gradient_is_cone) paints the largest t whose circle, of
 * radius fr + t dr >= 0, passes through the point, and nothing where
 * there is none (aabench.h, aa_gradient).  With q the point relative to
 * F, d = b^2 - a c is a quadratic in q whose value and gradient (2 b D -
 * 2 a q) vanish at q* = t* D, t* = -fr/dr (the point P* where the radius
 * is 0), so d(q) = Q(q - q*) with Q(v) = (v.D)^2 - a |v|^2; in the frame
 * e = D/|D|, e' = (-e_y, e_x), with U = e.(q - q*) and V = e'.(q - q*),
 *     d = dr^2 U^2 - a V^2.
 *  - a > 0 (the cone proper, CONE_WEDGE): d = L0 L1, L0 = sg (|dr| U -
 *    sqrt(a) V), L1 = sg (|dr| U + sqrt(a) V), sg the sign of dr: the two
 *    lines through P* tangent to every circle, each a circle's envelope.
 *    The circles of radius >= 0 lie in the wedge ahead of P* (along sg D,
 *    within the half-angle asin(|dr|/|D|) < 90 degrees), where L0 >= 0
 *    and L1 >= 0; on the opposite wedge, where d >= 0 too, both roots
 *    have radius < 0, and where L0 and L1 differ in sign d < 0: the
 *    painted region is {L0 >= 0, L1 >= 0}.  There g(w) = |q - F - w D| -
 *    (fr + w dr), convex in w and rising without bound (|D| > |dr|), has
 *    its zeros t1 <= t2 and t = t2 = (b + sqrt d) / a.  The line where
 *    the radius is 0 (U = 0) meets the painted region at P* only, so it
 *    adds nothing else.  dr = 0 (the circles of one radius sliding along
 *    D) has no P*: d = |D|^2 (fr^2 - V^2) with q* = 0, L0 = |D| (fr - V),
 *    L1 = |D| (fr + V), the strip |V| <= fr, t as above.
 *  - a < 0 with dr < 0 (the end circle strictly inside the focal circle,
 *    CONE_NESTED): d = dr^2 U^2 + |a| V^2 >= 0, zero at P* only: the
 *    circles of radius >= 0 (t <= t*) are nested and shrink to P*, every
 *    point lies on one of them, and it is the smaller root, again (b +
 *    sqrt d) / a; L0 = dr U + i sqrt(-a) V and L1 its conjugate.
 *  - a = 0 (the focal circle touching the end circle from inside, at P*;
 *    CONE_HALF): the one root t = c / (2 b), of radius >= 0 exactly where
 *    sg b > 0 (c + 2 b fr / dr = |q - q*|^2 >= 0, as |D| = |dr|): the
 *    half-plane beyond the line through P* perpendicular to D, L0 = sg b,
 *    L1 = 1.  t runs to sg infinity at its edge (a pole, not a branch
 *    point): padded, the paint there is the last stop's or the first's,
 *    constant, and the stretch from the last stop circle to the edge is
 *    integrated exactly as such; the rule's bound takes |t| <= |c| / (2
 *    |b|) with |b| >= |b(m)| - |b1| A on the ellipse.  Repeat and reflect
 *    would repeat the stops without end at the edge: a window the edge
 *    passes is refused by name (rad_breakpoints_of).  Cutting a sliver
 *    of width eps off the edge and bounding it by its area times the
 *    largest colour is exact to a bound, but not to the reference's:
 *    along a row at distance delta from the edge t ~ k / delta (k of the
 *    order of the gradient's size over |D|), so the rest holds k / eps
 *    periods, each cut twice a row, and the 4096 stop lines a window may
 *    take (GRAD_MAX_BREAKS) leave eps ~ k / 4096, a bound near 1e-4 for
 *    1e-12.  Where the colour is a function of t alone the tail has an
 *    exact treatment (in t, x'(t) ~ k / t^2 is smooth, and integrating
 *    by parts against the periodic primitives of the colour less its
 *    mean leaves the mean times the sliver plus terms O(k / N^j) at the
 *    N-th period), but the composite with other layers, or the weight
 *    under the decoding, is no product of a periodic function of t and
 *    a smooth one of x; it is not built.
 * t is evaluated as (b + sqrt d) / a when b >= 0 and as c / (b - sqrt d)
 * otherwise (the same number; neither cancels), with d = L0 L1 from the
 * linear forms, exact to rounding however close to a tangent line (a = 0:
 * c / (2 b)).
 * {t >= tau} is the union of the discs of the circles t' >= tau of radius
 * >= 0, which is convex (their centres and radii affine in t'): t is
 * quasiconcave on the painted region, which is convex, so along a segment
 * its least is at the ends of the painted part and its greatest found by
 * golden section; over the window, its least among the corners, the
 * sides' crossings of the tangent lines (t = b / a there, affine along
 * each line) and P*, its greatest on the sides or at P*.
 *
 * Where the picture is not analytic along a row: where the row crosses
 * L0 = 0 or L1 = 0 (the paint starts or stops, and t moves like the square
 * root of the distance to the line), where t passes a stop's offset or a
 * period's end or the composite the decoding's threshold (on the circles
 * of those t, only the front arc, where t' = 2 b / a - tau <= tau, is a
 * curve of t = tau; the other roots rad_cross gives only cut the row where
 * nothing happens), and, for CONE_NESTED, the row's point nearest P* (t's
 * kink on the row through it; its branch points are the complex zeros of
 * L0 and L1, which approach the real axis there).  A painted stretch
 * between a zero of L_k and the next cut is integrated in u =
 * sqrt(|x - xr|), x = xr + eps u^2: with L_k = lk eps u^2 and the other
 * L_o = Lo(xr) + lo eps u^2,
 *     sqrt(d) = u sqrt(P(u^2)),  P(w) = eps lk Lo(xr) + lk lo w,
 * analytic in u but at the zeros of P (u^2 = -eps Lo(xr) / lo: the other
 * line's crossing, real or imaginary), so the integrand 2 u f(t(u)) takes
 * the 20-point rule with Trefethen's bound on the Bernstein ellipse in u,
 * |u| <= Zu = |m| + A there, |P| <= |P(0)| + |lk lo| Zu^2, |b| <= |b(xr)|
 * + |b1| Zu^2, |t| <= (|b| + Zu sqrt|P|) / |a| and M the colour's bound
 * times 2 Zu; the zeros of E(t) + 0.055 on the power piece (the z where
 * c - 2 tau0 b + a tau0^2 = 0, as rad_bound finds them) exclude u = +-
 * sqrt(eps (z - xr)).  Other pieces take the rule in x with the zeros of
 * L0 and L1 (complex for CONE_NESTED) excluded and |t| <= (|b(m)| + |b1| A
 * + sqrt(|L0| |L1|)) / |a|, |L_k| <= |L_k(m)| + |lk| A.  A stretch
 * whose paint is constant (every channel's E1 and E2 zero: pad beyond the
 * stops) is its length times the decoded colour, exactly; an unpainted
 * one the composite without the layer (its paint transparent).  Halving
 * and the bounds' sum are rad_piece's.
 *
 * Where the inner integral is not smooth in the height (outer
 * breakpoints, rad_breakpoints_of): the tangent lines' crossings of the
 * window's sides and their meetings with the local pieces (as a linear
 * gradient's stop lines, line_breaks), the row of P* (the lines cross and
 * the painted chord's length has a kink), the stop circles as for nested
 * circles (window's sides, top and bottom rows, pieces: a superset, as
 * only their front arcs are curves of the picture), and where each stop
 * circle touches the tangent lines, the ends of its front arc: near such a
 * point the part of a row where t < tau opens from the line like the
 * square of the height's distance to it, a jump in the inner integral's
 * second derivative; for CONE_HALF, the edge's crossings and meetings
 * (every circle touches it at P*, whose row is a breakpoint already).
 *
 * Under the other filters ("the cone case under the other filters"; the
 * separable ones and the radial ones) the path is the same with the
 * row's weight w as a factor of the integrand, as "the other separable
 * filters" and "the radial filters: the weight along a row" describe it:
 * the span clipped to the support's chord for a radial filter; each
 * painted stretch cut also at the filter's kinks uc + k (the radial
 * filters': uc), so that on every piece w is one entire function (a
 * polynomial, Lanczos's sincs, the Gaussian; the radial cone's branch
 * points uc +- i |s| are kept out of the ellipse, in x or, mapped, in u);
 * unpainted stretches and pieces of constant paint by the weight's cdf
 * difference (the radial filters': the row's), exactly.  A piece in x
 * takes the weight's bound on its ellipse (wt_bound) as a factor of M.
 * A piece in u from a tangent line takes it on the image of the ellipse
 * under x = xr + eps u^2: with |u| <= Zu and |Im u| <= B there, |z - xr|
 * <= Zu^2 and |Im z| = 2 |Re u| |Im u| <= 2 Zu B, so about the middle of
 * the piece's own x range (where the polynomial filters' piece is fitted,
 * wt_poly) the semi-axes |xr - xm| + Zu^2 and the lesser of that and 2 Zu
 * B serve.  A piece whose rule's bound fails keeps twice its length times
 * the weight's supremum on it.  The kinks are cut before any piece is
 * taken in u, so the piece next to a tangent line ends at the first kink,
 * stop or threshold: in x no Bernstein ellipse about a piece that ends at
 * a tangent line's crossing keeps out sqrt(d)'s branch point, which lies
 * on its end (rho = 1), and its bound is infinite however often it is
 * halved.  That is why the cone case alone does not take the path of
 * several gradients, which carries the other filters' weight for the
 * rest: it bounds a radial layer from rad_row's branch points, worked out
 * for nested circles (d2 > 0): here d's real zeros are the tangent lines'
 * crossings, the painted stretch's own ends, and where d2 = lam0 lam1 <
 * 0 (a row across the painted wedge) those points are not numbers at all
 * (a square root of a negative ratio).  That path takes a cone layer only
 * with the cone's own cuts, bounds and substitution in u ("a cone beside
 * other gradients").
 * The outer breakpoints were already the filters': the tangent lines' and
 * the stop circles' crossings of every kink line (kink_lines) and, under
 * a radial filter, of the support's circle, with their nearest approaches
 * to the centre (rad_filter_line, rad_filter_circle).
 * A span where the cone and another gradient paint one point, and the
 * cone in linear light, take the path of several gradients, which now
 * cuts the row at the cone's tangent lines and takes the pieces next to
 * them in u ("a cone beside other gradients").
 */

/* The cone case's linear forms of radial gradient r (the comment above). */
static void cone_init(grad_radial *r)
{
    double Dn = hypot(r->Dx, r->Dy), ex = 1.0, ey = 0.0;
    if (Dn > 0.0)
        ex = r->Dx / Dn, ey = r->Dy / Dn;
    double ts = r->dr != 0.0 ? -r->fr / r->dr : 0.0, qsx = ts * r->Dx, qsy = ts * r->Dy;
    double U[3] = {ex, ey, -(ex * qsx + ey * qsy)}, V[3] = {-ey, ex, ey * qsx - ex * qsy};
    double complex G[2][3];
    if (r->a == 0.0) {
        double sg = r->dr > 0.0 ? 1.0 : -1.0;
        r->cone = CONE_HALF;
        G[0][0] = sg * r->Dx, G[0][1] = sg * r->Dy, G[0][2] = sg * r->fr * r->dr;
        G[1][0] = G[1][1] = 0.0, G[1][2] = 1.0;
    } else if (r->a < 0.0) {
        double sa = sqrt(-r->a);
        r->cone = CONE_NESTED;
        for (int k = 0; k < 3; k++) {
            G[0][k] = r->dr * U[k] + _Complex_I * sa * V[k];
            G[1][k] = r->dr * U[k] - _Complex_I * sa * V[k];
        }
    } else if (r->dr == 0.0) {
        r->cone = CONE_WEDGE;
        for (int k = 0; k < 3; k++) {
            G[0][k] = -Dn * V[k] + (k == 2 ? Dn * r->fr : 0.0);
            G[1][k] = Dn * V[k] + (k == 2 ? Dn * r->fr : 0.0);
        }
        r->px = r->py = NAN; /* no P*: the circles keep their radius */
    } else {
        double sg = r->dr > 0.0 ? 1.0 : -1.0, sa = sqrt(r->a), adr = fabs(r->dr);
        r->cone = CONE_WEDGE;
        for (int k = 0; k < 3; k++) {
            G[0][k] = sg * (adr * U[k] - sa * V[k]);
            G[1][k] = sg * (adr * U[k] + sa * V[k]);
        }
    }
    const double *iv = r->inv;
    for (int k = 0; k < 2; k++) {
        for (int j = 0; j < 3; j++)
            r->lg[k][j] = creal(G[k][j]);
        r->lf[k][0] = G[k][0] * iv[0] + G[k][1] * iv[1];
        r->lf[k][1] = G[k][0] * iv[2] + G[k][1] * iv[3];
        r->lf[k][2] = G[k][0] * (iv[4] - r->fx) + G[k][1] * (iv[5] - r->fy) + G[k][2];
    }
}

/* d at (x, y) from the forms; *painted: whether the point is painted. */
static double cone_d(const grad_radial *g, double x, double y, int *painted)
{
    if (g->cone == CONE_NESTED) {
        double complex l = g->lf[0][0] * x + g->lf[0][1] * y + g->lf[0][2];
        *painted = 1;
        return creal(l) * creal(l) + cimag(l) * cimag(l);
    }
    double l0 = creal(g->lf[0][0]) * x + creal(g->lf[0][1]) * y + creal(g->lf[0][2]);
    double l1 = creal(g->lf[1][0]) * x + creal(g->lf[1][1]) * y + creal(g->lf[1][2]);
    *painted = l0 >= 0.0 && l1 >= 0.0;
    return l0 * l1;
}

/* t at (x, y) given sqrt(d) there (the comment above). */
static double cone_t_sq(const grad_radial *g, double x, double y, double sq)
{
    double qx = g->inv[0] * x + g->inv[2] * y + g->inv[4] - g->fx;
    double qy = g->inv[1] * x + g->inv[3] * y + g->inv[5] - g->fy;
    double b = qx * g->Dx + qy * g->Dy + g->fr * g->dr;
    if (g->a == 0.0) /* CONE_HALF: the one root */
        return (qx * qx + qy * qy - g->fr * g->fr) / (2.0 * b);
    if (b >= 0.0)
        return (b + sq) / g->a;
    return (qx * qx + qy * qy - g->fr * g->fr) / (b - sq);
}

/* t at (x, y) taking d < 0 (rounding next to a tangent line) as 0, the
 * point as painted. */
static double cone_t_near(const grad_radial *g, double x, double y)
{
    int p;
    double d = cone_d(g, x, y, &p);
    return cone_t_sq(g, x, y, sqrt(d > 0.0 ? d : 0.0));
}

static inline double cone_t_on(const grad_radial *g, int col, double s, double at)
{
    return col ? cone_t_near(g, at, s) : cone_t_near(g, s, at);
}

/* Widen the range [*lo, *hi] by t's range over the painted part of the
 * segment [sa, sb] of row at (col 0) or column at (col 1): the least at
 * the ends of each painted stretch, the greatest by golden section (t is
 * quasiconcave there; the comment above). */
static void cone_seg_range(const grad_radial *g, int col, double sa, double sb, double at,
                           double *lo, double *hi)
{
    double cut[4] = {sa, sb, sb, sb};
    int nc = 1;
    if (g->cone != CONE_NESTED)
        for (int k = 0; k < 2; k++) {
            double ls = creal(g->lf[k][col ? 1 : 0]);
            double l0 = creal(g->lf[k][col ? 0 : 1]) * at + creal(g->lf[k][2]);
            double s = ls != 0.0 ? -l0 / ls : NAN;
            if (s > sa && s < sb)
                cut[nc++] = s;
        }
    if (nc == 3 && cut[2] < cut[1]) {
        double tmp = cut[1];
        cut[1] = cut[2], cut[2] = tmp;
    }
    cut[nc++] = sb;
    const double k = 0.5 * (3.0 - sqrt(5.0));
    for (int q = 0; q + 1 < nc; q++) {
        double a = cut[q], b = cut[q + 1], mid = 0.5 * (a + b);
        int painted;
        if (!(b > a))
            continue;
        if (col)
            cone_d(g, at, mid, &painted);
        else
            cone_d(g, mid, at, &painted);
        if (!painted)
            continue;
        double ta = cone_t_on(g, col, a, at), tb = cone_t_on(g, col, b, at);
        *lo = fmin(*lo, fmin(ta, tb));
        double c = a + k * (b - a), e = b - k * (b - a);
        double fc = cone_t_on(g, col, c, at), fe = cone_t_on(g, col, e, at);
        for (int it = 0; it < 90 && b - a > 1e-15 * (1.0 + fabs(a)); it++) {
            if (fc >= fe)
                b = e, e = c, fe = fc, c = a + k * (b - a), fc = cone_t_on(g, col, c, at);
            else
                a = c, c = e, fc = fe, e = b - k * (b - a), fe = cone_t_on(g, col, e, at);
        }
        *hi = fmax(*hi, fmax(fmax(ta, tb), fmax(fc, fe)));
    }
}

/* The x where E(t) + 0.055 = 0 for channel ch on the power piece (both
 * roots of the circle's quadratic for each complex tau0; rad_bound), at
 * most 2 deg into z; -1 if the roots are not known.  A real root where the painted t is not tau0 is the
 * other root's (t' = 2 b / a - t, real across the painted region in the
 * cone case, unlike nested circles'), no singularity of the integrand:
 * left out (a real root where d < 0 lies beyond a tangent line's
 * crossing, itself excluded, and so outside every ellipse taken). */
static int cone_ezeros(const grad_radial *g, const rad_row *r, const rad_chan *ch,
                       double complex *z)
{
    if (!ch->power)
        return 0;
    double complex taus[2 * CHAN_DEG], xs[2 * CHAN_DEG];
    int nx = rad_ezeros(g, r, ch, taus, xs), n = 0;
    if (nx < 0)
        return -1;
    for (int k = 0; k < nx; k++) {
        double complex tau = taus[k], x = xs[k];
        if (cimag(x) == 0.0 && cimag(tau) == 0.0 && g->cone != CONE_HALF) {
            int painted;
            double d = cone_d(g, creal(x), r->y, &painted), tr = creal(tau);
            if (!(d > 0.0 &&
                  fabs(cone_t_near(g, creal(x), r->y) - tr) <= 1e-9 * (1.0 + fabs(tr))))
                continue;
        }
        z[n++] = x;
    }
    return n;
}

/* A row of a cone-case gradient: rad_row's coefficients and L_k = lam[k]
 * x + mu[k]. */
typedef struct cone_row {
    rad_row r;
    double complex lam[2], mu[2];
} cone_row;

/* Trefethen's bound (rad_bound) of the 20-point rule from the excluded
 * points ex[0 .. ne - 1] and, at each rho, the colour's bound on the
 * ellipse from |t| <= T(rho) as fn gives it (with the factor it returns in
 * *fac). */
typedef double (*cone_tbound)(const void *ctx, double rho, double *fac);
static double cone_rule_bound(const rad_chan *ch, const double complex *ex, int ne, double m,
                              double h, cone_tbound fn, const void *ctx)
{
    double rmax = INFINITY;
    for (int k = 0; k < ne; k++)
        rmax = fmin(rmax, rad_rho(ex[k], m, h));
    if (!(rmax > 1.0 + 1e-9))
        return INFINITY;
    if (rmax > 64.0)
        rmax = 64.0;
    double best = INFINITY;
    for (int k = 1; k < 8; k++) {
        double rho = 1.0 + (rmax - 1.0) * k / 8.0, fac = 1.0;
        double T = fn(ctx, rho, &fac);
        double E = fabs(ch->E[0]), Tk = 1.0;
        for (int q = 1; q <= ch->deg; q++) {
            Tk *= T;
            E += ch->E[q] != 0.0 ? fabs(ch->E[q]) * Tk : 0.0;
        }
        double M = fac * (ch->power ? pow((E + 0.055) / 1.055, 2.4) : E / 12.92);
        best = fmin(best, h * (64.0 / 15.0) * M * pow(rho, -2.0 * RAD_GL) / (rho * rho - 1.0));
    }
    return best;
}

/* A piece in x, [m - h, m + h]: (|b| + |sqrt d|) / |a| on the ellipse
 * (|z - m| <= A there); CONE_HALF: |c| / (2 |b|), |c(z)| <= |c(m)| +
 * |c'(m)| A + c2 A^2 and |b(z)| >= |b(m)| - |b1| A, infinite when the
 * ellipse may reach the pole b = 0. */
typedef struct cone_plain_ctx {
    const grad_radial *g;
    const cone_row *cr;
    double m, h;
    const gen_span_ctx *wc; /* the weight (cone_weight), or NULL under the box */
    double wa[4];
} cone_plain_ctx;
static double cone_plain_t(const void *ctx, double rho, double *fac)
{
    const cone_plain_ctx *c = ctx;
    const rad_row *r = &c->cr->r;
    double semi = 0.5 * c->h * (rho + 1.0 / rho), L[2], m = c->m;
    *fac = c->wc ? wt_bound(c->wc, c->wa, m, c->h, semi, 0.5 * c->h * (rho - 1.0 / rho)) : 1.0;
    if (c->g->cone == CONE_HALF) {
        double bl = fabs(r->b0 + r->b1 * m) - fabs(r->b1) * semi;
        double cz = fabs(r->c0 + m * (r->c1 + m * r->c2)) + fabs(r->c1 + 2.0 * r->c2 * m) * semi +
                    r->c2 * semi * semi;
        return bl > 0.0 ? cz / (2.0 * bl) : INFINITY;
    }
    for (int k = 0; k < 2; k++)
        L[k] = cabs(c->cr->lam[k] * m + c->cr->mu[k]) + cabs(c->cr->lam[k]) * semi;
    return (fabs(r->b0 + r->b1 * m) + fabs(r->b1) * semi + sqrt(L[0] * L[1])) / fabs(c->g->a);
}

/* A piece in u of a stretch from a zero xr of L_k (the comment above);
 * weighted, the weight's bound on the image of the ellipse, |z - xr| =
 * |u|^2 <= Zu^2 and |Im z| = 2 |Re u| |Im u| <= 2 Zu B there, about the
 * middle xm of the piece's own x range (half-length xh), where wa fits
 * the weight's polynomial piece ("the cone case under the other
 * filters"). */
typedef struct cone_root_ctx {
    double m, h, P0, P1, bxr, b1, a;
    const gen_span_ctx *wc;
    double wa[4], xr, xm, xh;
} cone_root_ctx;
static double cone_root_t(const void *ctx, double rho, double *fac)
{
    const cone_root_ctx *c = ctx;
    double Zu = fabs(c->m) + 0.5 * c->h * (rho + 1.0 / rho), Z2 = Zu * Zu;
    *fac = 2.0 * Zu;
    if (c->wc) {
        double A = fabs(c->xr - c->xm) + Z2, B = fmin(A, Zu * c->h * (rho - 1.0 / rho));
        *fac *= wt_bound(c->wc, c->wa, c->xm, c->xh, A, B);
    }
    return (fabs(c->bxr) + fabs(c->b1) * Z2 + Zu * sqrt(fabs(c->P0) + fabs(c->P1) * Z2)) /
           fabs(c->a);
}

/* The row's weight for the cone case under a filter other than the box
 * (w->box unset): the fields of gen_span_ctx that the weight's functions
 * read ("the other separable filters", "the radial filters"). */
static void cone_weight(const worker *w, gen_span_ctx *c)
{
    c->weighted = 1, c->f = w->f, c->uc = w->uc;
    c->radial = w->radial, c->s = w->row_s;
    c->wn = w->radial ? aa_filter_weight2(w->f, 0.0, 0.0) : 0.0;
}

/* The weight at x (inside the support's chord for a radial filter). */
static double cone_wt_at(const gen_span_ctx *c, double x)
{
    return c->radial ? rwt(c, x - c->uc) : aa_filter_weight(c->f, x - c->uc);
}

/* wt_poly's coefficients on [m - h, m + h] for a polynomial filter (the
 * separable ones but Lanczos and the Gaussian), else zeros. */
static void cone_wt_poly(const gen_span_ctx *c, double m, double h, double a[4])
{
    a[0] = a[1] = a[2] = a[3] = 0.0;
    if (!c->radial && c->f->type != &aa_filter_lanczos && c->f->type != &aa_filter_gauss)
        wt_poly(c, m, h, a);
}

/* The bound a piece takes when the rule's fails (f in [0, 1]): its
 * length, times twice the weight's supremum there when weighted (the
 * rule and the integral each within length times sup |w| of 0). */
static double cone_fallback(const gen_span_ctx *wc, double xa, double xb)
{
    if (!wc)
        return xb - xa;
    double sup, slope;
    wt_real(wc, 0.5 * (xa + xb), 0.5 * (xb - xa), &sup, &slope);
    return 2.0 * (xb - xa) * sup;
}

/* The radial cone filter's branch points uc +- i |s| (rwt), which the
 * ellipse must keep out, into ex; how many. */
static int cone_wt_branch(const gen_span_ctx *wc, double complex *ex)
{
    if (!wc || !wc->radial || wc->f->type != &aa_filter_cone)
        return 0;
    ex[0] = wc->uc + _Complex_I * fabs(wc->s);
    ex[1] = wc->uc - _Complex_I * fabs(wc->s);
    return 2;
}

/* The channels over [xa, xb] of the row (one piece in x), halving where
 * needed (rad_piece); wc the weight, NULL under the box. */
static void cone_plain(worker *w, const grad_radial *g, const cone_row *cr, const rad_chan *ch,
                       int nch, const gen_span_ctx *wc, double xa, double xb, int depth,
                       double *sum, double *err)
{
    const rad_row *r = &cr->r;
    double m = 0.5 * (xa + xb), h = 0.5 * (xb - xa), worst = 0.0;
    cone_plain_ctx ctx = {g, cr, m, h, wc, {0, 0, 0, 0}};
    if (wc)
        cone_wt_poly(wc, m, h, ctx.wa);
    for (int c = 0; c < nch; c++) {
        double complex ex[4 + 2 * CHAN_DEG];
        int ne = 0;
        for (int k = 0; k < 2; k++)
            if (cr->lam[k] != 0.0)
                ex[ne++] = -cr->mu[k] / cr->lam[k];
        int nz = cone_ezeros(g, r, &ch[c], ex + ne);
        if (nz < 0) {
            worst = INFINITY;
            continue;
        }
        ne += nz;
        ne += cone_wt_branch(wc, ex + ne);
        worst = fmax(worst, cone_rule_bound(&ch[c], ex, ne, m, h, cone_plain_t, &ctx));
    }
    if (worst > 2e-16 * (xb - xa) && depth < RAD_DEPTH) {
        cone_plain(w, g, cr, ch, nch, wc, xa, m, depth + 1, sum, err);
        cone_plain(w, g, cr, ch, nch, wc, m, xb, depth + 1, sum, err);
        return;
    }
    double part[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < RAD_GL; k++) {
        double x = m + h * w->gl_x[k], t = cone_t_near(g, x, r->y);
        double wk = wc ? w->gl_w[k] * cone_wt_at(wc, x) : w->gl_w[k];
        for (int c = 0; c < nch; c++) {
            double e = chan_at(&ch[c], t);
            part[c] += wk * (ch[c].power ? pow((e + 0.055) / 1.055, 2.4) : e / 12.92);
        }
    }
    for (int c = 0; c < nch; c++)
        sum[c] += h * part[c];
    *err += fmin(worst, cone_fallback(wc, xa, xb));
}

/* The channels over x = xr + eps u^2, u in [ua, ub], xr a zero of L_k:
 * the integrand 2 u f(t), halving where needed. */
static void cone_root(worker *w, const grad_radial *g, const cone_row *cr, const rad_chan *ch,
                      int nch, const gen_span_ctx *wc, double xr, double eps, int k, double ua,
                      double ub, int depth, double *sum, double *err)
{
    const rad_row *r = &cr->r;
    int o = 1 - k;
    double lk = creal(cr->lam[k]), lo = creal(cr->lam[o]), Lo = creal(cr->lam[o] * xr + cr->mu[o]);
    double m = 0.5 * (ua + ub), h = 0.5 * (ub - ua), worst = 0.0;
    /* the piece's x range, [xr + eps ua^2, xr + eps ub^2] in some order */
    double xa = xr + eps * ua * ua, xb = xr + eps * ub * ub, lo_x = fmin(xa, xb),
           hi_x = fmax(xa, xb);
    cone_root_ctx ctx = {m,    h,    eps * lk * Lo, lk * lo, r->b0 + r->b1 * xr, r->b1, g->a,
                         wc,   {0, 0, 0, 0},        xr,      0.5 * (lo_x + hi_x),
                         0.5 * (hi_x - lo_x)};
    if (wc)
        cone_wt_poly(wc, ctx.xm, ctx.xh, ctx.wa);
    for (int c = 0; c < nch; c++) {
        double complex ex[6 + 4 * CHAN_DEG], z[2 * CHAN_DEG], bp[2];
        int ne = 0, nz = cone_ezeros(g, r, &ch[c], z), nb = cone_wt_branch(wc, bp);
        if (nz < 0) {
            worst = INFINITY;
            continue;
        }
        if (ctx.P1 != 0.0) {
            double complex u0 = csqrt(-ctx.P0 / ctx.P1);
            ex[ne++] = u0, ex[ne++] = -u0;
        }
        for (int q = 0; q < nz; q++) {
            double complex u0 = csqrt(eps * (z[q] - xr));
            ex[ne++] = u0, ex[ne++] = -u0;
        }
        for (int q = 0; q < nb; q++) { /* the radial cone filter's, in u */
            double complex u0 = csqrt(eps * (bp[q] - xr));
            ex[ne++] = u0, ex[ne++] = -u0;
        }
        worst = fmax(worst, cone_rule_bound(&ch[c], ex, ne, m, h, cone_root_t, &ctx));
    }
    if (worst > 2e-16 * (ub * ub - ua * ua) && depth < RAD_DEPTH) {
        cone_root(w, g, cr, ch, nch, wc, xr, eps, k, ua, m, depth + 1, sum, err);
        cone_root(w, g, cr, ch, nch, wc, xr, eps, k, m, ub, depth + 1, sum, err);
        return;
    }
    double part[3] = {0.0, 0.0, 0.0};
    for (int q = 0; q < RAD_GL; q++) {
        double u = m + h * w->gl_x[q], u2 = u * u, P = ctx.P0 + ctx.P1 * u2, x = xr + eps * u2;
        double t = cone_t_sq(g, x, r->y, u * sqrt(P > 0.0 ? P : 0.0));
        double wq = w->gl_w[q] * 2.0 * u * (wc ? cone_wt_at(wc, x) : 1.0);
        for (int c = 0; c < nch; c++) {
            double e = chan_at(&ch[c], t);
            part[c] += wq * (ch[c].power ? pow((e + 0.055) / 1.055, 2.4) : e / 12.92);
        }
    }
    for (int c = 0; c < nch; c++)
        sum[c] += h * part[c];
    *err += fmin(worst, wc ? cone_fallback(wc, lo_x, hi_x) : ub * ub - ua * ua);
}

/* The x of the filter's kinks about the pixel's centre strictly inside
 * (a, b), appended to xs[nx ..] while nx < cap; returns the new count. */
static size_t add_kinks(const worker *w, double a, double b, double *xs, size_t nx, size_t cap)
{
    double kink[8];
    int nk = w->f->type->kinks(w->f->spec.v, kink);
    for (int j = 0; j < nk && nx < cap; j++)
        if (w->uc + kink[j] > a && w->uc + kink[j] < b)
            xs[nx++] = w->uc + kink[j];
    return nx;
}

/* The weight's integral over [xa, xb] of the current row (absolute x):
 * its length under the box, else the cdf's (the radial filters: the
 * row's) difference. */
static double span_weight(const worker *w, double xa, double xb)
{
    if (w->box)
        return xb - xa;
    if (w->radial)
        return aa_filter_row_cdf(w->f, w->row_s, xb - w->uc) -
               aa_filter_row_cdf(w->f, w->row_s, xa - w->uc);
    return aa_filter_cdf(w->f, xb - w->uc) - aa_filter_cdf(w->f, xa - w->uc);
}

/* ---- one cone on several layers ----
 *
 * Layers that all paint one cone-case gradient (the same gradient, map
 * and stops: two overlapping shapes of an SVG filled with it) have the
 * same t at every point, and on a piece between stops each layer's
 * opacity op = v0[3] + v1[3] t and channel C = v0[c] + v1[c] t are the
 * same affine functions of it.  The composite's channel is affine in
 * each layer's op and op C separately (source over and group opacity
 * are; "several gradients"), so with the n layers
 *     e = sum over a in {0, 1, 2}^n of K_a prod_l f[a_l],
 *     f[0] = 1, f[1] = op, f[2] = op C,
 * a polynomial in t of degree at most 2 n (cone_comp_poly): the cone's
 * path (cone_span) takes it as it takes one layer's quadratic, the
 * integrand dec(E(t)) analytic but where E + 0.055 = 0 on the power
 * piece (each complex root tau0 of that polynomial, found by GSL's
 * companion-matrix solver and polished by Newton's method, gives the two
 * x of the circle's quadratic at t = tau0, as for one layer), the rows
 * cut where E crosses 0.04045 (its real roots), and the rule's bound from
 * |E| <= sum |E_q| T^q on the ellipse, T the bound of |t| there.  For n =
 * 1, K_0 = e0, K_1 = e1 - e0, K_2 = e2 - e1 and E is the quadratic
 * above.  The K are read as for several gradients (mix_span): composites
 * at every choice of the three paints per layer, then differences.  More
 * than GEN_MAX such layers at a point take the path of several gradients
 * (gen_span: its fold, up to GEN_LAYERS; more are refused: gen_over), and
 * a polynomial whose roots the solver does not find refuses the pixel
 * (cone_over).
 */
typedef struct cone_comp {
    int n, nk;
    double K[3][243];
} cone_comp;

/* Channel c's E on a piece where op and C are v0 + v1 t (cc->n layers of
 * one cone), into ch (degree 2 n). */
static void cone_comp_poly(const cone_comp *cc, int c, const double v0[4], const double v1[4],
                           rad_chan *ch)
{
    double F[3][3] = {{1.0, 0.0, 0.0},
                      {v0[3], v1[3], 0.0},
                      {v0[3] * v0[c], v0[3] * v1[c] + v1[3] * v0[c], v1[3] * v1[c]}};
    static const int fd[3] = {0, 1, 2};
    ch->deg = 2 * cc->n;
    memset(ch->E, 0, sizeof ch->E);
    for (int a = 0; a < cc->nk; a++) {
        double k = cc->K[c][a];
        if (k == 0.0)
            continue;
        double p[CHAN_DEG + 1] = {1.0}, q[CHAN_DEG + 1];
        int dp = 0;
        for (int l = 0, r = a; l < cc->n; l++, r /= 3) {
            int i = r % 3;
            memset(q, 0, sizeof q);
            for (int u = 0; u <= dp; u++)
                for (int v = 0; v <= fd[i]; v++)
                    q[u + v] += p[u] * F[i][v];
            dp += fd[i];
            memcpy(p, q, sizeof p);
        }
        for (int u = 0; u <= dp; u++)
            ch->E[u] += k * p[u];
    }
}

/* The span [xa, xb] of row y painted (where it is) by the cone-case
 * gradient g alone, on one layer or several (the composite's K in cc:
 * "one cone on several layers"; rad_span, mix_span): cut where the row crosses the tangent lines (and, nested,
 * at its point nearest P*), each stretch unpainted (the layer
 * transparent) or cut at the stops and the threshold as rad_span cuts,
 * its end pieces at a tangent line in u (the comment above). */
static void cone_span(worker *w, const grad_radial *g, const cone_comp *cc, double xa,
                      double xb, double y, int nch, double *sum)
{
    cone_row cr;
    gen_span_ctx wcs, *wc = NULL;
    if (!w->box)
        cone_weight(w, &wcs), wc = &wcs;
    rad_row_at(g, y, &cr.r);
    for (int k = 0; k < 2; k++)
        cr.lam[k] = g->lf[k][0], cr.mu[k] = g->lf[k][1] * y + g->lf[k][2];
    double cut[4];
    int kind[4], nc = 0;
    cut[nc] = xa, kind[nc++] = -1;
    for (int k = 0; k < 2; k++) {
        double x = NAN;
        if (g->cone != CONE_NESTED && creal(cr.lam[k]) != 0.0)
            x = -creal(cr.mu[k]) / creal(cr.lam[k]);
        else if (g->cone == CONE_NESTED && k == 0)
            x = creal(-cr.mu[0] / cr.lam[0]); /* nearest P*: the zeros' real part */
        if (!(x > xa && x < xb))
            continue;
        int at = nc++;
        while (at > 1 && cut[at - 1] > x) {
            cut[at] = cut[at - 1], kind[at] = kind[at - 1];
            at--;
        }
        cut[at] = x, kind[at] = g->cone == CONE_WEDGE ? k : -1;
    }
    cut[nc] = xb, kind[nc++] = -1;
    double *xs = w->gbuf, err = 0.0;
    size_t cap = w->cap_gbuf - 8;
    for (int s = 0; s + 1 < nc; s++) {
        double p = cut[s], q = cut[s + 1];
        int painted;
        if (!(q > p))
            continue;
        cone_d(g, 0.5 * (p + q), y, &painted);
        if (!painted) {
            double wd = span_weight(w, p, q);
            for (int c = 0; c < nch; c++)
                sum[c] += wd * aa_srgb_decode(cc->K[c][0]);
            continue;
        }
        int kp = kind[s], kq = kind[s + 1];
        double tlo = -INFINITY, thi = INFINITY;
        if (g->spread != AA_SPREAD_PAD) {
            tlo = INFINITY, thi = -INFINITY;
            cone_seg_range(g, 0, p, q, y, &tlo, &thi);
            tlo -= 1e-12 * (1.0 + fabs(tlo));
            thi += 1e-12 * (1.0 + fabs(thi));
        }
        size_t nx = 0;
        xs[nx++] = p;
        size_t mt = grad_taus(&g->plane, tlo, thi, xs + nx, cap - nx);
        if (mt > (cap - nx) / 3)
            mt = 0; /* cannot happen: grad_breakpoints refused such windows */
        double *taus = xs + nx + 2 * mt;
        memmove(taus, xs + nx, mt * sizeof *xs);
        for (size_t k = 0; k < mt; k++)
            nx += (size_t)rad_cross(g, &cr.r, taus[k], p, q, xs + nx);
        if (wc) /* the filter's kinks: the weight one piece between them */
            nx = add_kinks(w, p, q, xs, nx, cap);
        qsort(xs + 1, nx - 1, sizeof *xs, cmp_dbl);
        xs[nx++] = q;
        for (size_t k = 0; k + 1 < nx; k++) {
            double a = xs[k], b = xs[k + 1];
            if (!(b > a))
                continue;
            double v0[4], v1[4];
            rad_paint_lin(g, cone_t_near(g, 0.5 * (a + b), y), v0, v1);
            rad_chan ch[3];
            double cuts[4 + 6 * CHAN_DEG];
            int ncut = 0, flat = 1;
            cuts[ncut++] = a;
            for (int c = 0; c < nch; c++) {
                if (cc->n == 1) {
                    double K0 = cc->K[c][0], K1 = cc->K[c][1], K2 = cc->K[c][2];
                    ch[c].deg = 2;
                    ch[c].E[0] = K0 + K1 * v0[3] + K2 * v0[3] * v0[c];
                    ch[c].E[1] = K1 * v1[3] + K2 * (v0[3] * v1[c] + v1[3] * v0[c]);
                    ch[c].E[2] = K2 * v1[3] * v1[c];
                } else
                    cone_comp_poly(cc, c, v0, v1, &ch[c]);
                int moves = 0;
                for (int qd = 1; qd <= ch[c].deg; qd++)
                    moves = moves || ch[c].E[qd] != 0.0;
                flat = flat && !moves;
                if (ch[c].deg == 2) {
                    double rt[2];
                    int n = gsl_poly_solve_quadratic(ch[c].E[2], ch[c].E[1],
                                                     ch[c].E[0] - 0.04045, &rt[0], &rt[1]);
                    if (ch[c].E[2] == 0.0 && ch[c].E[1] != 0.0)
                        n = 1, rt[0] = (0.04045 - ch[c].E[0]) / ch[c].E[1];
                    for (int qq = 0; qq < n; qq++)
                        ncut += rad_cross(g, &cr.r, rt[qq], a, b, cuts + ncut);
                    continue;
                }
                /* the real roots of E - 0.04045 (a pair of complex roots
                 * closer than 1e-9 to the axis is a double root where E
                 * touches the threshold without crossing it) */
                double complex rt[CHAN_DEG];
                int n = chan_roots(&ch[c], -0.04045, rt);
                if (n < 0) { /* the solver failed: the decoding's pieces unknown */
                    w->cone_over = 1;
                    return;
                }
                for (int qq = 0; qq < n; qq++)
                    if (fabs(cimag(rt[qq])) <= 1e-9 * (1.0 + fabs(creal(rt[qq]))))
                        ncut += rad_cross(g, &cr.r, creal(rt[qq]), a, b, cuts + ncut);
            }
            if (flat) { /* constant paint: exact */
                double wd = span_weight(w, a, b);
                for (int c = 0; c < nch; c++)
                    sum[c] += wd * aa_srgb_decode(ch[c].E[0]);
                continue;
            }
            qsort(cuts + 1, (size_t)(ncut - 1), sizeof *cuts, cmp_dbl);
            cuts[ncut++] = b;
            for (int qq = 0; qq + 1 < ncut; qq++) {
                double ca = cuts[qq], cb = cuts[qq + 1];
                if (!(cb > ca))
                    continue;
                double tm = cone_t_near(g, 0.5 * (ca + cb), y);
                for (int c = 0; c < nch; c++)
                    ch[c].power = chan_at(&ch[c], tm) > 0.04045;
                int lr = ca == p && kp >= 0, rr = cb == q && kq >= 0;
                if (lr && rr) {
                    double mid = 0.5 * (ca + cb);
                    cone_root(w, g, &cr, ch, nch, wc, ca, 1.0, kp, 0.0, sqrt(mid - ca), 0, sum,
                              &err);
                    cone_root(w, g, &cr, ch, nch, wc, cb, -1.0, kq, 0.0, sqrt(cb - mid), 0, sum,
                              &err);
                } else if (lr)
                    cone_root(w, g, &cr, ch, nch, wc, ca, 1.0, kp, 0.0, sqrt(cb - ca), 0, sum,
                              &err);
                else if (rr)
                    cone_root(w, g, &cr, ch, nch, wc, cb, -1.0, kq, 0.0, sqrt(cb - ca), 0, sum,
                              &err);
                else
                    cone_plain(w, g, &cr, ch, nch, wc, ca, cb, 0, sum, &err);
            }
        }
    }
    w->rad_row_err += err;
}

/* The span [xa, xb] of row y (winding w->wind): the one radial gradient
 * whose paint the composite there depends on (K1 or K2 not 0, the other
 * gradients transparent: a layer hidden by another gradient's stand-in
 * colour would not be), if any (a span of none is of constant colour; of
 * two, the path of several gradients, gen_span), cut as the comment above
 * says, each piece integrated by rad_piece. */
static void rad_span(worker *w, double xa, double xb, double y, int nch, double *sum)
{
    if (!chord_clip(w, &xa, &xb)) /* the span clipped to the support's chord */
        return;
    const grad_radial *g = NULL;
    /* the composite's K0, K1, K2 per channel (in a scene of radial
     * gradients only, w->gl[k] is w->rg[k]) */
    static const double P[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
    double *paints = w->gl_paint, e0[3], e1[3], e2[3];
    memset(paints, 0, 4 * (size_t)w->ngl * sizeof *paints);
    for (int k = 0; k < w->nrg; k++) {
        double f[3][3];
        for (int q = 0; q < 3; q++) {
            memcpy(paints + 4 * k, P[q], 4 * sizeof *paints);
            aa_scene_encoded_with_n(w->scene, w->wind, w->ngl, w->gl_layer, paints, f[q]);
        }
        memset(paints + 4 * k, 0, 4 * sizeof *paints);
        int dep = f[0][0] != f[1][0] || f[0][1] != f[1][1] || f[0][2] != f[1][2] ||
                  f[1][0] != f[2][0] || f[1][1] != f[2][1] || f[1][2] != f[2][2];
        if (dep && g) {
            gen_span(w, xa, xb, y, nch, sum);
            return;
        }
        if (dep || k == 0) {
            memcpy(e0, f[0], sizeof e0), memcpy(e1, f[1], sizeof e1), memcpy(e2, f[2], sizeof e2);
            if (dep)
                g = &w->rg[k];
        }
    }
    if (!g) { /* no radial gradient paints the span */
        double wd = span_weight(w, xa, xb);
        for (int c = 0; c < nch; c++)
            sum[c] += wd * aa_srgb_decode(e0[c]);
        return;
    }
    if (g->cone) {
        cone_comp cc;
        cc.n = 1, cc.nk = 3;
        for (int c = 0; c < 3; c++)
            cc.K[c][0] = e0[c], cc.K[c][1] = e1[c] - e0[c], cc.K[c][2] = e2[c] - e1[c];
        cone_span(w, g, &cc, xa, xb, y, nch, sum);
        return;
    }
    rad_row r;
    rad_row_at(g, y, &r);
    double *xs = w->gbuf;
    size_t nx = 0, cap = w->cap_gbuf - 8;
    xs[nx++] = xa;
    if (r.x0 > xa && r.x0 < xb)
        xs[nx++] = r.x0;
    double tlo = g->spread == AA_SPREAD_PAD ? -INFINITY : rad_row_min(g, xa, xb, y);
    double thi = fmax(rad_t(g, xa, y), rad_t(g, xb, y));
    size_t mt = grad_taus(&g->plane, tlo, thi, xs + nx, cap - nx);
    if (mt > (cap - nx) / 3)
        mt = 0; /* cannot happen: grad_breakpoints refused such windows */
    double *taus = xs + nx + 2 * mt;
    memmove(taus, xs + nx, mt * sizeof *xs);
    for (size_t k = 0; k < mt; k++)
        nx += (size_t)rad_cross(g, &r, taus[k], xa, xb, xs + nx);
    qsort(xs + 1, nx - 1, sizeof *xs, cmp_dbl);
    xs[nx++] = xb;
    double err = 0.0;
    for (size_t k = 0; k + 1 < nx; k++) {
        double a = xs[k], b = xs[k + 1];
        if (!(b > a))
            continue;
        double v0[4], v1[4];
        rad_paint_lin(g, rad_t(g, 0.5 * (a + b), y), v0, v1);
        rad_chan ch[3];
        double cuts[16];
        int nc = 0;
        cuts[nc++] = a;
        for (int c = 0; c < nch; c++) {
            /* e = K0 + K1 op + K2 op C, op = v0[3] + v1[3] t, C = v0[c] + v1[c] t */
            double K0 = e0[c], K1 = e1[c] - e0[c], K2 = e2[c] - e1[c];
            ch[c].E[0] = K0 + K1 * v0[3] + K2 * v0[3] * v0[c];
            ch[c].E[1] = K1 * v1[3] + K2 * (v0[3] * v1[c] + v1[3] * v0[c]);
            ch[c].E[2] = K2 * v1[3] * v1[c];
            ch[c].deg = 2;
            double rt[2];
            int n = gsl_poly_solve_quadratic(ch[c].E[2], ch[c].E[1], ch[c].E[0] - 0.04045, &rt[0],
                                             &rt[1]);
            if (ch[c].E[2] == 0.0 && ch[c].E[1] != 0.0)
                n = 1, rt[0] = (0.04045 - ch[c].E[0]) / ch[c].E[1];
            for (int q = 0; q < n; q++)
                nc += rad_cross(g, &r, rt[q], a, b, cuts + nc);
        }
        qsort(cuts + 1, (size_t)(nc - 1), sizeof *cuts, cmp_dbl);
        cuts[nc++] = b;
        for (int q = 0; q + 1 < nc; q++) {
            double ca = cuts[q], cb = cuts[q + 1];
            if (!(cb > ca))
                continue;
            double tm = rad_t(g, 0.5 * (ca + cb), y);
            for (int c = 0; c < nch; c++)
                ch[c].power = ch[c].E[0] + tm * (ch[c].E[1] + tm * ch[c].E[2]) > 0.04045;
            rad_piece(w, g, &r, ch, nch, ca, cb, 0, sum, &err);
        }
    }
    w->rad_row_err += err;
}

/* ---- several gradients at a point ----
 *
 * A span that two or more gradient layers paint (any kinds: linear, radial,
 * stops of differing opacities), and every span of a scene that mixes
 * linear with radial gradients or holds a gradient of varying opacity
 * with another gradient (grad_mode), takes this path.  The composite's
 * channel e is affine in each layer's opacity op and op times channel C
 * separately (source over and group opacity are; core.h,
 * aa_scene_encoded_with_n), so with the layers l of the span
 *     e = sum over a in {0, 1, 2}^n of K_a prod_l f_l[a_l],
 *     f[0] = 1, f[1] = op, f[2] = op C,
 * the K read from the composites at paints (0, 0, 0, 0), (0, 0, 0, 1) and
 * (1, 1, 1, 1) of each layer (3^n of them, n <= GEN_MAX, past which the
 * composite is folded layer by layer: "the fold" below; the others
 * transparent, which they are to the span: a layer the span does not
 * depend on with every other gradient transparent depends on none).  The
 * row is cut where any layer's t passes a stop's offset or a period's end
 * and at each radial layer's x0, so on a piece each op and C is affine in
 * its layer's t, and the integrand dec(e(x)) is analytic but for each
 * radial layer's branch points x0 +- i sqrt(dmin / d2), and, on the
 * decoding's power piece, the zeros of e + 0.055.
 *
 * The decoding's change of piece (e = 0.04045) is located by bisection
 * with a certified Lipschitz bound: on [u, v] with |e'| <= L, a channel
 * whose excess g = e - 0.04045 has one sign at u and v with |g(u)| +
 * |g(v)| > L (v - u) has no root there; other intervals are halved, down
 * to GEN_FUZZ (relative to the coordinates; where g is 0 in double at a
 * midpoint, each side of it to the last point of its end's sign:
 * gen_bisect), and an interval that small is
 * integrated by its midpoint with the bound width * min(1, 2.3 L width)
 * (the decoding's slope is below 2.3 on [0, 1]).  Elsewhere each piece
 * takes the 20-point Gauss-Legendre rule with the bound of Trefethen's
 * Thm 19.3 as radial gradients do, M and the analyticity from bounds on
 * the Bernstein ellipse E_rho, which lies in the rectangle |Re z - m| <=
 * A = h (rho + 1/rho)/2, |Im z| <= B = h (rho - 1/rho)/2: for a linear
 * layer |t| <= |t(m)| + |tx| A and |t'| = |tx|; for a radial one |t| <=
 * (|b(m)| + |b1| A + sqrt(d2 Z^2 + |dmin|)) / |a|, Z = |m - x0| + A, and
 * |t'| <= (|b1| + d2 Z / sqrt(d2 D1 D2)) / |a|, Dk a lower bound on the
 * distance from the branch point k to the rectangle (t' = (b1 - d'/(2
 * sqrt d)) / a, |d| = d2 |z - r1| |z - r2|), dmin's rounding (a few ulps
 * of itself, rad_row_at) counted: raised by it in T, lowered in the
 * branch points' distance and in P on the real segment (gen_layer_tp).
 * Then |f[1]| <= |o0| + |o1| T and so on, |e| <= sum |K_a| prod |f|, and
 * |e'| by the product rule.
 * On the power piece, with |e(z) - e(m)| <= A max |e'| (the segment from
 * m to z lies in the ellipse) below 0.9 (e(m) + 0.055), Re(e + 0.055) > 0
 * on the ellipse, so u^2.4 is analytic there and bounded by ((|e| +
 * 0.055) / 1.055)^2.4.  Pieces are halved until the bound is below 2e-16
 * of their length, as rad_piece does, and the bounds add into the row's.
 * On the real segment (the threshold's bisection) a radial layer's |t'| is
 * bounded by its supremum there, (|b1| + d2 Z / sqrt(d2 Z^2 + dmin)) /
 * |a|, finite through x0 (the bound from the branch points' distance is
 * not: rows through P* left intervals of 1e-13 relative bounded by their
 * width, 5.7e-12 at x = 66).  A row tangent to the threshold's curve away
 * from x0 gives the Lipschitz test little room about its double root
 * (with L ~ 0.07 and |g'| ~ 1e-5 at the roots of rows near the tangent,
 * a 48x48 crop of a focal radial gradient over a linear one took 650
 * million halvings on one pixel, then gave up on those rows with their
 * lengths as bounds: 246 s and a bound of 1), so an interval the test
 * fails is tried by Taylor's theorem next: with g'(m) exact and H >=
 * |g''| on [m - h, m + h],
 *     |g(m)| > |g'(m)| h + H h^2 / 2   : no root there;
 *     |g'(m)| > H h                    : g monotone there, so a root
 *                                        only if the ends' signs differ,
 *                                        and then one, found by halving on
 *                                        the signs alone.
 * Between them they leave O(1) intervals a level about a double root
 * (those within about 2.4 h of it) and O(1) about a simple one.  On the
 * real segment t'' of a radial layer is -d2 dmin / (a d^(3/2)) (t = (b -
 * sqrt d) / a, d = d2 (x - x0)^2 + dmin), so |t''| <= d2 |dmin| / (|a|
 * dlo^(3/2)) with dlo the least d there (0 when dmin = 0: t is affine on
 * each side of x0, which is a cut); |t'| is bounded as above, by its
 * value at the segment's point farthest from x0 when dmin >= 0 and
 * nearest when dmin < 0 (d2 u / sqrt(d2 u^2 + dmin) decreases in u then);
 * f[2]'' = 2 o1 c1 t'^2 + (o1 C + c1 op) t'' and the product rule twice
 * bound |e''|.  Like the rest, the tests are computed in double, their
 * own rounding not counted (a channel whose e' and bound on e'' are 0
 * is constant and crosses nothing, even if it equals 0.04045).  Past
 * GEN_BUDGET halvings on one piece, or more than GEN_MAX_FUZZ intervals
 * left, or GEN_PIECES pieces of the rule on one span, the pixel is
 * refused (naming it): that takes a channel within rounding of 0.04045
 * along a stretch of a row, and a length as the row's bound would not be
 * the reference's 1e-12.  An interval left (at most GEN_FUZZ wide) is integrated by its
 * midpoint with the bound width (2.3 L width + 2.4e-9), the last term
 * the decoding's own jump at 0.04045 (0.0031308073 - 0.0031308050).
 */
#define GEN_FUZZ 1e-13 /* the narrowest interval bisected for the threshold, relative */


/* ---- the other separable filters: the weight along a row ----
 *
 * Under a separable filter other than the box the row's integral is that
 * of dec(e(x)) w(x - uc).  The row is cut also at the filter's kinks
 * (uc + k for k of aa_filter_type.kinks), so that on a piece w is one
 * polynomial (tent: degree 1, bspline:order=2: 2, bspline:order=3,
 * mitchell, catrom: 3), or Lanczos's sinc(t) sinc(t / a) / M, or the
 * Gaussian: entire functions in every case, so the product is analytic
 * wherever the colour is and the 20-point rule keeps Trefethen's bound
 * with M the product of the colour's bound and the weight's on the
 * Bernstein ellipse E_rho about [m - h, m + h] (semi-axes A = h (rho +
 * 1/rho)/2, B = h (rho - 1/rho)/2):
 *  - a polynomial piece, written in s = (x - m)/h as sum a_k s^k (the
 *    cubic through its values at the four Chebyshev points cos((2k + 1)
 *    pi / 8), which is the piece itself, degree at most 3), has |w| <=
 *    sum |a_k| (A/h)^k there, as |z - m| <= A;
 *  - Lanczos: sinc(pi z) = int_0^1 cos(pi z u) du and |cos(x + i y)| <=
 *    cosh(y), so |w| <= cosh(pi B) cosh(pi B / a) / M, and 1/M = w(0);
 *  - the Gaussian: |exp(-z^2 / (2 s^2))| = exp(-(X^2 - Y^2) / (2 s^2))
 *    with |X| >= max(0, |m - uc| - A) and |Y| <= B.
 * On the real segment (rho = 1) these bound |w|; the slope, for the
 * threshold's narrow intervals, is bounded by sum k |a_k| / h, by pi (1 +
 * 1/a) / (2 M) for Lanczos (|d/dx sin(x)/x| < 1/2) and by w(0) e^(-1/2)
 * / s for the Gaussian.  The Gaussian is truncated to the window [-R,
 * R]^2 as elsewhere, its mass outside in the pixel's bound (f->lost: the
 * colour lies in [0, 1]).  In v the rows are weighed by w(v - vc) with
 * the filter's kinks as breakpoints (breakpoints()), and the lines t =
 * tau of a linear gradient, and the circles of a radial one, add their
 * crossings of every vertical line x = uc + k (and, for the Gaussian,
 * x = uc + k s, as the pieces do) to the outer breakpoints.  A row's
 * bound, times |w(v - vc)|, enters the pixel's as under the box. */

/* ---- the radial filters: the weight along a row ----
 *
 * Under a radial filter (cone, cone:cut, gauss with cut, radial:k) the
 * row at height s (relative to the pixel's centre) is weighed by w(u, s)
 * = wn g(sqrt(u^2 + s^2)), u = x - uc, on the chord |u| < c = sqrt(R^2 -
 * s^2) of the support's disc (R its radius, the mask's for the truncated
 * ones), 0 outside it; each span is clipped to the chord, so that inside
 * it the weight is the formula without its support test:
 *  - cone:r=r (any cut): wn (1 - sqrt(u^2 + s^2) / r);
 *  - gauss:s=S,cut=K: wn exp(-(u^2 + s^2) / (2 S^2));
 *  - radial:k=K,r=r: wn q^K, q = 1 - (u^2 + s^2) / r^2;
 * wn the weight at the centre (aa_filter_weight2(f, 0, 0)).  The last two
 * are entire in u; the cone's has branch points at u = +-i |s|, where u^2
 * + s^2 = 0, which the Bernstein ellipse must keep outside (its rho below
 * that of uc + i |s|; the branch cuts run from there away from the real
 * axis, and an ellipse, convex and symmetric about the axis, that holds
 * neither point holds no point of them).  The row is cut at uc as well
 * (the kink of |u| on the row s = 0, and the points nearest to the
 * branch points), and the rule's bound takes, on the ellipse E_rho about
 * [m - h, m + h] (|Re z - m| <= A, |Im z| <= B, |z - m| <= A; um = |m -
 * uc|):
 *  - cone: |sqrt(z^2 + s^2)| <= sqrt(|z|^2 + s^2), so |w| <= wn (1 +
 *    sqrt((um + A)^2 + s^2) / r);
 *  - Gaussian: |exp(-z^2 / (2 S^2))| = exp(-(X^2 - Y^2) / (2 S^2)) with
 *    |X| >= max(0, um - A), |Y| <= B, times exp(-s^2 / (2 S^2));
 *  - radial: with z - uc = (m - uc) + d, |d| <= A, q(z) = q(m) - (2 (m -
 *    uc) d + d^2) / r^2, so |q| <= |q(m)| + (2 um A + A^2) / r^2, and |w|
 *    <= wn that to the K.
 * On the real segment (the threshold's narrow intervals, and the rule's
 * fallback bound) |w| is at most its value at the point nearest the
 * centre, u = max(0, um - h) (each weight decreases with the distance),
 * and |w'| at most wn / r for the cone (|d sqrt(u^2 + s^2) / du| <= 1),
 * wn exp(-s^2 / (2 S^2)) e^(-1/2) / S for the Gaussian, and wn 2 K (um +
 * h) / r^2 for the radial polynomials (q in [0, 1] on the chord).  In v
 * the rows keep the radial filters' breakpoints (0, +-R as turning points,
 * the pieces' crossings of the circle, the cone's nearest approaches:
 * breakpoints()), and each stop's line or circle (and the decoding's
 * threshold's) adds its crossings of the support's circle, where the
 * chord's end passes from one side of it to the other, and, for the cone,
 * the heights where it passes closest to the centre, as turning points:
 * the cone's apex makes the inner integral change on the scale of that
 * distance there, as a piece's edge does (rad_filter_points). */

/* The radial filter's weight on the row c->s at u = x - uc, inside the
 * chord (the comment above). */
static double rwt(const gen_span_ctx *c, double u)
{
    const double *p = c->f->spec.v, s = c->s;
    if (c->f->type == &aa_filter_cone)
        return c->wn * (1.0 - hypot(u, s) / p[0]);
    if (c->f->type == &aa_filter_gauss_mask)
        return c->wn * exp(-0.5 * (u * u + s * s) / (p[0] * p[0]));
    double r = p[1], q = 1.0 - (u * u + s * s) / (r * r), v = q;
    for (int k = 1; k < (int)p[0]; k++)
        v *= q;
    return c->wn * v;
}

/* A bound of |w| on the ellipse of semi-axes A, B about m (the comment
 * above); B = 0, A = h: the real segment [m - h, m + h]. */
static double rwt_bound(const gen_span_ctx *c, double m, double A, double B)
{
    const double *p = c->f->spec.v, s = c->s;
    double um = fabs(m - c->uc), X = fmax(0.0, um - A);
    if (c->f->type == &aa_filter_cone) {
        if (B == 0.0)
            return c->wn * fmax(0.0, 1.0 - hypot(X, s) / p[0]);
        return c->wn * (1.0 + hypot(um + A, s) / p[0]);
    }
    if (c->f->type == &aa_filter_gauss_mask)
        return c->wn * exp((B * B - X * X - s * s) / (2.0 * p[0] * p[0]));
    double r = p[1], q;
    if (B == 0.0)
        q = fmax(0.0, 1.0 - (X * X + s * s) / (r * r));
    else
        q = fabs(1.0 - (um * um + s * s) / (r * r)) + (2.0 * um * A + A * A) / (r * r);
    double v = q;
    for (int k = 1; k < (int)p[0]; k++)
        v *= q;
    return c->wn * v;
}

/* |w'| on the real segment [m - h, m + h] (the comment above). */
static double rwt_slope(const gen_span_ctx *c, double m, double h)
{
    const double *p = c->f->spec.v, s = c->s;
    if (c->f->type == &aa_filter_cone)
        return c->wn / p[0];
    if (c->f->type == &aa_filter_gauss_mask)
        return c->wn * exp(-0.5 * (s / p[0]) * (s / p[0]) - 0.5) / p[0];
    return c->wn * 2.0 * p[0] * (fabs(m - c->uc) + h) / (p[1] * p[1]);
}

/* The weight's coefficients in s = (x - m) / h over [m - h, m + h] (a
 * piece of a polynomial filter between kinks): Newton's form through the
 * four Chebyshev points, expanded. */
static void wt_poly(const gen_span_ctx *c, double m, double h, double a[4])
{
    static const double sn[4] = {-0.92387953251128674, -0.38268343236508978,
                                 0.38268343236508978, 0.92387953251128674};
    double d[4];
    for (int k = 0; k < 4; k++)
        d[k] = aa_filter_weight(c->f, m + h * sn[k] - c->uc);
    for (int j = 1; j < 4; j++)
        for (int k = 3; k >= j; k--)
            d[k] = (d[k] - d[k - 1]) / (sn[k] - sn[k - j]);
    a[0] = d[3], a[1] = a[2] = a[3] = 0.0;
    for (int k = 2, deg = 0; k >= 0; k--, deg++) {
        /* a := a (s - sn[k]) + d[k] */
        for (int i = deg + 1; i > 0; i--)
            a[i] = a[i - 1] - sn[k] * a[i];
        a[0] = d[k] - sn[k] * a[0];
    }
}

/* A bound of |w(z - uc)| on the ellipse of semi-axes A, B about m (the
 * comment above; a: wt_poly's coefficients for a polynomial filter). */
static double wt_bound(const gen_span_ctx *c, const double *a, double m, double h, double A,
                       double B)
{
    const aa_filter *f = c->f;
    if (c->radial)
        return rwt_bound(c, m, A, B);
    if (f->type == &aa_filter_lanczos)
        return cosh(M_PI * B) * cosh(M_PI * B / f->spec.v[0]) * aa_filter_weight(f, 0.0);
    if (f->type == &aa_filter_gauss) {
        double s = f->spec.v[0], X = fmax(0.0, fabs(m - c->uc) - A);
        return aa_filter_weight(f, 0.0) * exp((B * B - X * X) / (2.0 * s * s));
    }
    double S = A / h;
    return fabs(a[0]) + S * (fabs(a[1]) + S * (fabs(a[2]) + S * fabs(a[3])));
}

/* |w| and |w'| on the real segment [m - h, m + h] into *sup, *slope. */
static void wt_real(const gen_span_ctx *c, double m, double h, double *sup, double *slope)
{
    const aa_filter *f = c->f;
    double a[4] = {0, 0, 0, 0};
    if (c->radial) {
        *slope = rwt_slope(c, m, h);
        *sup = rwt_bound(c, m, h, 0.0);
        return;
    }
    if (f->type == &aa_filter_lanczos)
        *slope = M_PI * (1.0 + 1.0 / f->spec.v[0]) * 0.5 * aa_filter_weight(f, 0.0);
    else if (f->type == &aa_filter_gauss)
        *slope = aa_filter_weight(f, 0.0) * exp(-0.5) / f->spec.v[0];
    else {
        wt_poly(c, m, h, a);
        *slope = (fabs(a[1]) + 2.0 * fabs(a[2]) + 3.0 * fabs(a[3])) / h;
    }
    *sup = wt_bound(c, a, m, h, h, 0.0);
}

/* The sRGB encoding's power piece, 1.055 v^(1/2.4) - 0.055, of a linear
 * value v above LIN_T (a channel of a gradient in linear light). */
static double lin_enc(double v) { return 1.055 * pow(v, 1.0 / 2.4) - 0.055; }

/* x at the piece's variable s (x itself, or u: "a cone beside other
 * gradients"). */
static inline double gen_x(const gen_span_ctx *c, double s)
{
    return c->umode ? c->xr + c->eps * s * s : s;
}

/* Layer l's t at x (a cone-case layer's painted t; not the layer a piece
 * in u starts from, whose t is gen_t's). */
static double gen_t_x(const gen_span_ctx *c, int l, double x)
{
    const gen_layer *g = c->L[l];
    if (g->rg && g->rg->cone)
        return c->flat[l] ? 0.0 : cone_t_near(g->rg, x, c->y);
    if (g->rg)
        return rad_t(g->rg, x, c->y);
    return g->gp->tx * x + g->gp->ty * c->y + g->gp->t0;
}

/* Layer l's t at the piece's variable s; the layer a piece in u starts
 * from takes sqrt(d) = u sqrt(P0 + P1 u^2) (cone_root). */
static double gen_t(const gen_span_ctx *c, int l, double s)
{
    if (c->umode && c->uroot[l] && !c->flat[l]) {
        double P = c->P0 + c->P1 * s * s;
        return cone_t_sq(c->L[l]->rg, gen_x(c, s), c->y, s * sqrt(P > 0.0 ? P : 0.0));
    }
    return gen_t_x(c, l, gen_x(c, s));
}

/* e of each channel at real x (on the current piece). */
static void fold_eval(const gen_span_ctx *c, double x, double *e);

/* The encoded value of layer l's channel ch at t, its linear value v =
 * v0 + v1 t (gen_span_ctx's pw, enc0): lin_enc(v0) kept for the piece
 * where v1 = 0, the same bits as lin_enc(v) at a finite t. */
static inline double gen_enc(const gen_span_ctx *c, int l, int ch, double t, double v)
{
    if (!c->pw[l][ch])
        return v;
    return c->v1[l][ch] == 0.0 && isfinite(t) ? c->enc0[l][ch] : lin_enc(v);
}

static void gen_eval(const gen_span_ctx *c, double x, double *e)
{
    double f[GEN_MAX][3][3];
    if (c->fold) {
        fold_eval(c, x, e);
        return;
    }
    for (int l = 0; l < c->n; l++) {
        double t = gen_t(c, l, x), op = c->v0[l][3] + c->v1[l][3] * t;
        for (int ch = 0; ch < c->nch; ch++) {
            double v = c->v0[l][ch] + c->v1[l][ch] * t;
            f[l][ch][0] = 1.0;
            f[l][ch][1] = op;
            f[l][ch][2] = op * gen_enc(c, l, ch, t, v);
        }
    }
    /* a zero term adds +-0 to s, which is never -0: left out */
    for (int ch = 0; ch < c->nch; ch++) {
        double s = 0.0;
        for (int i = 0; i < c->nt[ch]; i++) {
            double p = c->tk[ch][i];
            const unsigned char *tl = c->tl[ch][i], *td = c->td[ch][i];
            for (int j = 0; j < c->tn[ch][i] && p != 0.0; j++)
                p *= f[tl[j]][ch][td[j]];
            s += p;
        }
        e[ch] = s;
    }
}

/* K's nonzero terms (gen_span_ctx's tk, tn, tl, td) of each channel. */
static void gen_terms(gen_span_ctx *c)
{
    for (int ch = 0; ch < 3; ch++) {
        int i = 0;
        c->tfin[ch] = 1;
        for (int a = 0; a < c->nk; a++) {
            if (c->K[ch][a] == 0.0)
                continue;
            c->tfin[ch] &= isfinite(c->K[ch][a]) != 0;
            int m = 0;
            for (int l = 0, q = a; l < c->n; l++, q /= 3)
                if (q % 3)
                    c->tl[ch][i][m] = (unsigned char)l, c->td[ch][i][m++] = (unsigned char)(q % 3);
            c->tk[ch][i] = c->K[ch][a], c->tn[ch][i++] = (unsigned char)m;
        }
        c->nt[ch] = i;
    }
}

/* Bounds of |e| and |e'| of each channel on the ellipse of semi-axes A
 * and B about m (|z - m| <= A there; the branch points' distances are
 * bounded below by their distances to the rectangle |Re z - m| <= A,
 * |Im z| <= B that holds it: the comment above); 0 if a branch point may
 * lie in that rectangle.  B = 0, A = h: the real segment [m - h, m + h]. */
static int fold_bounds(const gen_span_ctx *c, double m, double A, double B, double *emax,
                       double *dmax);

/* Bounds T of |t| and P of |t'| of layer l on the rectangle |Re z - m|
 * <= A, |Im z| <= B in x (the comment above); 0 if a branch point (a pole)
 * may lie in it.  A cone-case layer ("a cone beside other gradients"):
 * t = (b + sqrt(L0 L1)) / a, t' = (b1 + (lam0 L1 + lam1 L0) / (2 sqrt(L0
 * L1))) / a, with |L_k| <= |L_k(m)| + |lam_k| A and |L_k| >= |lam_k| times
 * the distance from its zero to the rectangle; CONE_HALF t = c / (2 b),
 * t' = (c' b - c b1) / (2 b^2), |b| >= |b(m)| - |b1| A; a layer of
 * constant paint on the piece (flat) needs neither. */
static int gen_layer_tp(const gen_span_ctx *c, int l, double m, double A, double B, double *T,
                        double *P)
{
    const gen_layer *g = c->L[l];
    if (!g->rg) {
        *T = fabs(gen_t_x(c, l, m)) + fabs(g->gp->tx) * A;
        *P = fabs(g->gp->tx);
        return 1;
    }
    if (g->rg->cone) {
        const grad_radial *q = g->rg;
        const rad_row *r = &c->row[l];
        double bm = fabs(r->b0 + r->b1 * m), ia;
        if (c->flat[l]) {
            *T = *P = 0.0;
            return 1;
        }
        if (q->cone == CONE_HALF) {
            double bl = bm - fabs(r->b1) * A, c1 = fabs(r->c1 + 2.0 * r->c2 * m);
            double cz = fabs(r->c0 + m * (r->c1 + m * r->c2)) + c1 * A + r->c2 * A * A;
            if (!(bl > 0.0))
                return 0;
            *T = cz / (2.0 * bl);
            *P = ((c1 + 2.0 * r->c2 * A) * (bm + fabs(r->b1) * A) + cz * fabs(r->b1)) /
                 (2.0 * bl * bl);
            return 1;
        }
        ia = 1.0 / fabs(q->a);
        double Lu[2], Ll[2], sl = 0.0;
        for (int k = 0; k < 2; k++) {
            double complex lam = c->lam[l][k], mu = c->mu[l][k];
            Lu[k] = cabs(lam * m + mu) + cabs(lam) * A;
            if (lam == 0.0)
                Ll[k] = cabs(mu);
            else {
                double complex z = -mu / lam;
                Ll[k] = cabs(lam) * fmax(fabs(creal(z) - m) - A, fabs(cimag(z)) - B);
            }
        }
        if (Lu[0] == 0.0 || Lu[1] == 0.0) /* the row along a tangent line: d = 0 */
            sl = 0.0;
        else if (!(Ll[0] > 0.0 && Ll[1] > 0.0))
            return 0;
        else
            sl = 0.5 * (cabs(c->lam[l][0]) * sqrt(Lu[1] / Ll[0]) +
                        cabs(c->lam[l][1]) * sqrt(Lu[0] / Ll[1]));
        *T = (bm + fabs(r->b1) * A + sqrt(Lu[0] * Lu[1])) * ia;
        *P = (fabs(r->b1) + sl) * ia;
        return 1;
    }
    const rad_row *r = &c->row[l];
    /* dmin's rounding (rad_row_at: relative, RAD_DMIN_ULPS of itself,
     * where d0 - d1^2 / (4 d2) cancelled near P*) is counted: dmin up to
     * it larger in |t|'s bound, smaller in the branch points' distance
     * and in |t'|'s bound on the real segment (the focus 7.9e-6 px from a
     * row of a 2 px radial gradient left S 1.06e-6 of itself short with
     * the rounded difference: test_gradient_bound) */
    double ga = fabs(g->rg->a), dlo = fabs(r->dmin) - r->de, dhi = fabs(r->dmin) + r->de;
    double sd = sqrt((r->dmin >= 0.0 ? dlo : fabs(r->dmin)) / r->d2), D1, D2, ia = 1.0 / ga;
    if (B == 0.0 && r->dmin >= 0.0) {
        /* the real segment: |d'| / (2 sqrt d) = d2 u / sqrt(d2 u^2 +
         * dmin), u = |x - x0| <= Z, increasing in u, so at most its
         * value at Z (below sqrt(d2): finite even through x0, where t
         * is a cone) */
        double Z = fabs(m - r->x0) + A, dz = sqrt(r->d2 * Z * Z + dlo);
        *T = (fabs(r->b0 + r->b1 * m) + fabs(r->b1) * A + sqrt(r->d2 * Z * Z + dhi)) * ia;
        *P = (fabs(r->b1) + (dz > 0.0 ? r->d2 * Z / dz : 0.0)) * ia;
        return 1;
    }
    if (r->dmin >= 0.0)
        D1 = D2 = fmax(sd - B, fabs(r->x0 - m) - A);
    else
        D1 = fabs(r->x0 - sd - m) - A, D2 = fabs(r->x0 + sd - m) - A;
    if (!(D1 > 0.0 && D2 > 0.0))
        return 0;
    double Z = fabs(m - r->x0) + A;
    *T = (fabs(r->b0 + r->b1 * m) + fabs(r->b1) * A + sqrt(r->d2 * Z * Z + dhi)) * ia;
    *P = (fabs(r->b1) + r->d2 * Z / sqrt(r->d2 * D1 * D2)) * ia;
    return 1;
}

/* T and P (gen_layer_tp) on the ellipse of semi-axes A, B about m in the
 * piece's variable.  In u (x = xr + eps u^2; |u| <= Zu = |m| + A, u >= 0
 * on the piece): the ellipse's image lies in the rectangle Re(x - xr) eps
 * in [lo^2 - B^2, Zu^2], lo = max(0, m - A), |Im x| <= 2 Zu B, where the
 * layers' bounds in x hold, and |dt/du| = |t'(x)| 2 |u| <= 2 Zu P; the
 * layer the piece starts from has t = (b + u sqrt(P(u^2))) / a, dt/du =
 * (2 eps b1 u + (P0 + 2 P1 u^2) / sqrt(P)) / a, |P| >= |P1| |u - u0| |u +
 * u0| (u0^2 = -P0 / P1) with the distances to the rectangle |Re u - m| <=
 * A, |Im u| <= B. */
static int gen_layer_tp_s(const gen_span_ctx *c, int l, double m, double A, double B,
                          double *T, double *P)
{
    if (!c->umode)
        return gen_layer_tp(c, l, m, A, B, T, P);
    double Zu = fabs(m) + A, Z2 = Zu * Zu;
    if (c->uroot[l] && !c->flat[l]) {
        const rad_row *r = &c->row[l];
        double Plo = fabs(c->P0);
        if (c->P1 != 0.0) {
            double complex u0 = csqrt((double complex)(-c->P0 / c->P1));
            double d0 = fmax(fabs(creal(u0) - m) - A, fabs(cimag(u0)) - B);
            double d1 = fmax(fabs(-creal(u0) - m) - A, fabs(cimag(u0)) - B);
            Plo = d0 > 0.0 && d1 > 0.0 ? fabs(c->P1) * d0 * d1 : 0.0;
        }
        if (!(Plo > 0.0))
            return 0;
        double ia = 1.0 / fabs(c->L[l]->rg->a);
        *T = (fabs(r->b0 + r->b1 * c->xr) + fabs(r->b1) * Z2 +
              Zu * sqrt(fabs(c->P0) + fabs(c->P1) * Z2)) * ia;
        *P = (2.0 * fabs(r->b1) * Zu + (fabs(c->P0) + 2.0 * fabs(c->P1) * Z2) / sqrt(Plo)) * ia;
        return 1;
    }
    double lo = fmax(0.0, m - A), rl = lo * lo - B * B;
    double xc = c->xr + c->eps * 0.5 * (rl + Z2), Ax = 0.5 * (Z2 - rl), Bx = 2.0 * Zu * B;
    if (!gen_layer_tp(c, l, xc, Ax, Bx, T, P))
        return 0;
    *P *= 2.0 * Zu;
    return 1;
}

/* The probe told of every bound gen_bounds proves (truth.h,
 * aa__truth_set_gen_probe): tests only, one thread. */
static aa__gen_probe_fn gen_probe;
static void *gen_probe_ctx;

void aa__truth_set_gen_probe(aa__gen_probe_fn fn, void *ctx)
{
    gen_probe = fn;
    gen_probe_ctx = ctx;
}

static int gen_bounds_of(const gen_span_ctx *c, double m, double A, double B, double *emax,
                         double *dmax);

/* Bounds of |e| and |e'| of each channel on the ellipse of semi-axes A
 * and B about m in the piece's variable (B = 0, A = h: the real segment
 * [m - h, m + h]); 0 if none are had (the comment above "several
 * gradients at a point"). */
static int gen_bounds(const gen_span_ctx *c, double m, double A, double B, double *emax,
                      double *dmax)
{
    int ok = gen_bounds_of(c, m, A, B, emax, dmax);
    if (ok && gen_probe) {
        aa__gen_bound b = {c->y, m, A, B, c->umode, c->nch, c->fold, {0, 0, 0}, {0, 0, 0}};
        for (int ch = 0; ch < c->nch; ch++)
            b.emax[ch] = emax[ch], b.dmax[ch] = dmax[ch];
        gen_probe(gen_probe_ctx, &b);
    }
    return ok;
}

static int gen_bounds_of(const gen_span_ctx *c, double m, double A, double B, double *emax,
                         double *dmax)
{
    double T[GEN_MAX], P[GEN_MAX];
    if (c->fold)
        return fold_bounds(c, m, A, B, emax, dmax);
    for (int l = 0; l < c->n; l++)
        if (!gen_layer_tp_s(c, l, m, A, B, &T[l], &P[l]))
            return 0;
    for (int ch = 0; ch < c->nch; ch++) {
        double F[GEN_MAX][3], G[GEN_MAX][3];
        for (int l = 0; l < c->n; l++) {
            double o0 = fabs(c->v0[l][3]), o1 = fabs(c->v1[l][3]);
            double c0 = fabs(c->v0[l][ch]), c1 = fabs(c->v1[l][ch]);
            double op = o0 + o1 * T[l], cc = c0 + c1 * T[l], dc = c1 * P[l];
            if (c->pw[l][ch]) {
                /* the linear value v(z) = v(m) + v1 (t(z) - t(m)), |t(z) -
                 * t(m)| <= P |z - m| <= P A (the segment from m to z lies
                 * in the ellipse): with D = |v1| P A below 0.9 v(m), Re v
                 * > 0 there, so v^(1/2.4) is analytic (its branch point
                 * v = 0 outside), |C| <= 1.055 (v(m) + D)^(1/2.4) + 0.055
                 * and |C'| <= (1.055 / 2.4) |v|^(1/2.4 - 1) |v1| |t'| with
                 * |v| >= v(m) - D */
                double vm = c->v0[l][ch] + c->v1[l][ch] * gen_t(c, l, m), D = c1 * P[l] * A;
                if (!(D < 0.9 * vm))
                    return 0;
                cc = 1.055 * pow(vm + D, 1.0 / 2.4) + 0.055;
                dc = 1.055 / 2.4 * pow(vm - D, 1.0 / 2.4 - 1.0) * c1 * P[l];
            }
            F[l][0] = 1.0, F[l][1] = op, F[l][2] = op * cc;
            G[l][0] = 0.0, G[l][1] = o1 * P[l], G[l][2] = o1 * cc * P[l] + op * dc;
        }
        double se = 0.0, sdv = 0.0;
        int finite = c->tfin[ch];
        for (int l = 0; l < c->n; l++)
            finite &= isfinite(F[l][1]) && isfinite(F[l][2]);
        /* F and K finite: a layer of index 0 adds G 0 times a finite rest, +0,
         * to dsum, and its F of 1 leaves the products as they are; the
         * terms' layers of nonzero index alone give the same bits */
        for (int i = 0; finite && i < c->nt[ch]; i++) {
            const unsigned char *tl = c->tl[ch][i], *td = c->td[ch][i];
            double k = fabs(c->tk[ch][i]), p = k, dsum = 0.0;
            for (int l = 0; l < c->tn[ch][i]; l++) {
                double rest = k;
                for (int j = 0; j < c->tn[ch][i]; j++)
                    if (j != l)
                        rest *= F[tl[j]][td[j]];
                dsum += G[tl[l]][td[l]] * rest;
                p *= F[tl[l]][td[l]];
            }
            se += p;
            sdv += dsum;
        }
        for (int a = 0; !finite && a < c->nk; a++) {
            double k = fabs(c->K[ch][a]);
            if (k == 0.0)
                continue;
            double p = k, dsum = 0.0;
            for (int l = 0, q = a; l < c->n; l++, q /= 3) {
                /* product rule: d(prod) = sum_l G_l prod_{j != l} F_j */
                double rest = k;
                for (int j = 0, qj = a; j < c->n; j++, qj /= 3)
                    if (j != l)
                        rest *= F[j][qj % 3];
                dsum += G[l][q % 3] * rest;
                p *= F[l][q % 3];
            }
            se += p;
            sdv += dsum;
        }
        emax[ch] = se;
        dmax[ch] = sdv;
    }
    return 1;
}

/* The Bernstein parameter (rad_rho) of the point z of x in the piece's
 * variable: z itself, or in u the nearer of +-sqrt(eps (z - xr)). */
static double gen_rho(const gen_span_ctx *c, double complex z, double m, double h)
{
    if (!c->umode)
        return rad_rho(z, m, h);
    double complex u = csqrt(c->eps * (z - c->xr));
    return fmin(rad_rho(u, m, h), rad_rho(-u, m, h));
}

/* The error bound of the 20-point rule on [m - h, m + h] for the channels
 * (power[ch]: the decoding's power piece), e at m given; INFINITY if no
 * ellipse serves.  The bound is the least over the ellipses tried, but
 * the first ellipse whose bound is at most enough (0: none is) ends the
 * search with it: the caller's test against a larger tolerance comes out
 * the same, and the bound returned is still one of the ellipses' proven
 * bounds.  The same ellipse bounds the n-point rule by M rho^(-2 n) in
 * place of rho^(-2 RAD_GL): where that of a shorter rule, GEN_LO[*lo],
 * is at most enough on some ellipse, the search ends with it (*lo = -1:
 * none is; the 20-point rule's bound returned).  If the first four
 * ellipses' bounds all exceed giveup, the search ends too, with the least
 * of them (the caller halves the piece). */
static double gen_rule_bound(const gen_span_ctx *c, double m, double h, const int *power,
                             const double *em, double enough, double giveup, int *lo)
{
    *lo = -1;
    double rmax = 64.0;
    for (int l = 0; l < c->n; l++) {
        if (!c->L[l]->rg)
            continue;
        const rad_row *r = &c->row[l];
        if (c->L[l]->rg->cone) { /* the zeros of L0, L1 (CONE_HALF: b's) */
            if (c->flat[l])
                continue;
            if (c->umode && c->uroot[l]) { /* P's zeros, in u */
                if (c->P1 != 0.0) {
                    double complex u0 = csqrt((double complex)(-c->P0 / c->P1));
                    rmax = fmin(fmin(rmax, rad_rho(u0, m, h)), rad_rho(-u0, m, h));
                }
                continue;
            }
            for (int k = 0; k < 2; k++) {
                double complex lam = c->L[l]->rg->cone == CONE_HALF ? (k ? 0.0 : r->b1)
                                                                    : c->lam[l][k];
                double complex mu = c->L[l]->rg->cone == CONE_HALF ? r->b0 : c->mu[l][k];
                if (lam != 0.0)
                    rmax = fmin(rmax, gen_rho(c, -mu / lam, m, h));
            }
            continue;
        }
        double sd = sqrt(fabs(r->dmin) / r->d2);
        if (r->dmin >= 0.0)
            rmax = fmin(rmax, gen_rho(c, r->x0 + _Complex_I * sd, m, h));
        else
            rmax = fmin(fmin(rmax, gen_rho(c, r->x0 + sd, m, h)), gen_rho(c, r->x0 - sd, m, h));
    }
    if (c->radial && c->f->type == &aa_filter_cone) /* the cone's branch points */
        rmax = fmin(rmax, gen_rho(c, c->uc + _Complex_I * fabs(c->s), m, h));
    for (int l = 0; l < c->n; l++) /* linear light: v = 0 on a linear layer */
        for (int ch = 0; ch < c->nch; ch++)
            if (c->pw[l][ch] && !c->L[l]->rg && c->v1[l][ch] != 0.0 && c->L[l]->gp->tx != 0.0) {
                const grad_plane *gp = c->L[l]->gp;
                double x0 = (-c->v0[l][ch] / c->v1[l][ch] - gp->ty * c->y - gp->t0) / gp->tx;
                rmax = fmin(rmax, gen_rho(c, x0, m, h));
            }
    if (!(rmax > 1.0 + 1e-9))
        return INFINITY;
    double best = INFINITY, wa[4] = {0, 0, 0, 0}, xm = m, xh = h;
    int poly = c->weighted && !c->radial && c->f->type != &aa_filter_lanczos &&
               c->f->type != &aa_filter_gauss;
    if (c->umode) { /* the weight fitted about the piece's own x range */
        double xa = gen_x(c, m - h), xb = gen_x(c, m + h);
        xm = 0.5 * (xa + xb), xh = 0.5 * fabs(xb - xa);
    }
    /* a piece in u next to the line whose x range is below x's
     * resolution (u^2 below an ulp of x; a row within rounding of where
     * the threshold's curve touches the line puts a place there): the
     * weight's polynomial fitted over the whole stretch in u, one piece
     * of it, and bounded about that centre (wt_bound's disc, grown by
     * the distance between the centres) */
    double wm = xm, wh = xh;
    if (c->umode && poly && !(xh > 0.0) && c->sxh > 0.0)
        wm = c->sxm, wh = c->sxh;
    if (poly)
        wt_poly(c, wm, wh, wa);
    /* weighted, also rho at geometric steps towards rmax (the Gaussian's
     * bound grows like exp(B^2 / (2 s^2)): its best rho is small) */
    for (int k = 1; k < (c->weighted ? 15 : 8); k++) {
        if (k == 5 && best > giveup)
            break;
        double rho = k < 8 ? 1.0 + (rmax - 1.0) * k / 8.0 : pow(rmax, (k - 7) / 16.0),
               A = 0.5 * h * (rho + 1.0 / rho), B = 0.5 * h * (rho - 1.0 / rho), emax[3],
               dmax[3], worst = 0.0;
        if (!gen_bounds(c, m, A, B, emax, dmax))
            continue;
        for (int ch = 0; ch < c->nch; ch++) {
            double M;
            if (power[ch]) {
                if (!(A * dmax[ch] < 0.9 * (em[ch] + 0.055))) {
                    worst = INFINITY;
                    break;
                }
                M = pow((emax[ch] + 0.055) / 1.055, 2.4);
            } else
                M = emax[ch] / 12.92;
            worst = fmax(worst, M);
        }
        if (c->umode) {
            /* the factor 2 u, and the weight on the ellipse's image
             * (cone_root_t) */
            double Zu = fabs(m) + A;
            worst *= 2.0 * Zu;
            if (c->weighted) {
                double Aw = fabs(c->xr - xm) + Zu * Zu + fabs(xm - wm);
                worst *= wt_bound(c, wa, wm, wh, Aw, fmin(Aw, 2.0 * Zu * B));
            }
        } else if (c->weighted)
            worst *= wt_bound(c, wa, m, h, A, B);
        double F = h * (64.0 / 15.0) * worst / (rho * rho - 1.0);
        /* the 20-point rule's bound first: a shorter rule's, F rho^(-2 n)
         * with n < RAD_GL, is no smaller (rmax > 1 + 1e-9 puts rho above
         * 1 + 6e-11, so rho^(-2 n) is above rho^(-2 RAD_GL) by a factor of
         * 1 + 1.2e-9 at least, far more than pow's rounding), so where that
         * is not enough neither is any shorter one's, whose pows are then
         * not taken; the same bound and rule come out */
        double b20 = F * pow(rho, -2.0 * RAD_GL);
        for (int r = 0; r < GEN_NLO && b20 <= enough; r++) {
            double b = F * pow(rho, -2.0 * GEN_LO[r]);
            if (b <= enough) {
                *lo = r;
                return b;
            }
        }
        best = fmin(best, b20);
        if (best <= enough)
            break;
    }
    return best;
}

static double gen_decode(double e, int power)
{
    return power ? pow((e + 0.055) / 1.055, 2.4) : e / 12.92;
}

/* Pieces one span may take in all: past them the pixel is refused
 * (integrate_pixel), so that no row's halving to RAD_DEPTH levels runs
 * on unbounded. */
#define GEN_PIECES 65536

/* One piece free of the threshold, each channel on its decoding's piece
 * power[ch]: the 20-point rule, halved to the bound (rad_piece). */
static void gen_piece(worker *w, const gen_span_ctx *c, const int *power, double xa, double xb,
                      int depth, double *sum, double *err)
{
    double m = 0.5 * (xa + xb), h = 0.5 * (xb - xa), em[3];
    if (++w->gen_work > GEN_PIECES) {
        w->gen_stuck = 1;
        return;
    }
    gen_eval(c, m, em);
    /* a bound 2^-10 of the tolerance takes a shorter rule (gen_rule_bound):
     * its value differs from the 20-point rule's by at most that and its
     * own bound; and one 2^10 times it on the first four ellipses halves
     * the piece without trying the others (on a piece that is halved
     * most come out far above it), but at the last depth or under a
     * weight that is no polynomial, whose best ellipse may be small */
    int lo;
    double tol = 2e-16 * (xb - xa);
    int poly = !c->weighted || (!c->radial && c->f->type != &aa_filter_lanczos &&
                                c->f->type != &aa_filter_gauss);
    double bound = gen_rule_bound(c, m, h, power, em, 0x1p-10 * tol,
                                  poly && depth < RAD_DEPTH ? 0x1p10 * tol : INFINITY, &lo);
    if (lo < 0 && bound > tol && depth < RAD_DEPTH) {
        gen_piece(w, c, power, xa, m, depth + 1, sum, err);
        gen_piece(w, c, power, m, xb, depth + 1, sum, err);
        return;
    }
    double part[3] = {0.0, 0.0, 0.0};
    const double *gx = lo < 0 ? w->gl_x : w->glo_x[lo], *gw = lo < 0 ? w->gl_w : w->glo_w[lo];
    for (int k = 0, n = lo < 0 ? RAD_GL : GEN_LO[lo]; k < n; k++) {
        double e[3], x = m + h * gx[k];
        gen_eval(c, x, e);
        double wk = !c->weighted ? gw[k]
                    : c->radial  ? gw[k] * rwt(c, gen_x(c, x) - c->uc)
                                 : gw[k] * aa_filter_weight(c->f, gen_x(c, x) - c->uc);
        if (c->umode) /* dx = 2 u du */
            wk *= 2.0 * x;
        for (int ch = 0; ch < c->nch; ch++)
            part[ch] += wk * gen_decode(e[ch], power[ch]);
    }
    for (int ch = 0; ch < c->nch; ch++)
        sum[ch] += h * part[ch];
    /* the piece's x range (in u: [xr + eps xa^2, xr + eps xb^2]) */
    double pa = gen_x(c, xa), pb = gen_x(c, xb), lx = fabs(pb - pa);
    if (c->weighted) {
        /* the rule and the integral both within (xb - xa) sup |w| of 0 */
        double sup, slope;
        wt_real(c, 0.5 * (pa + pb), 0.5 * lx, &sup, &slope);
        *err += fmin(bound, 2.0 * lx * sup);
    } else
        *err += fmin(bound, lx);
}

/* Layer l's t(m) and t'(m) into *tm, *tp, and bounds |t| <= *T, |t'|
 * <= *P and |t''| <= *Q on the real segment [m - h, m + h] in x
 * (gen_taylor); 0 if none are had (a flat cone-case layer's are 0; a
 * painted one's: gen_cone_tpq). */
static int gen_cone_tpq(const gen_span_ctx *c, int l, double m, double h, double *tp, double *T,
                        double *P, double *Q);
static int gen_tpq(const gen_span_ctx *c, int l, double m, double h, double *tm, double *tp,
                   double *T, double *P, double *Q)
{
    const gen_layer *g = c->L[l];
    *tm = gen_t(c, l, m);
    if (g->rg && g->rg->cone) {
        if (!c->flat[l])
            return gen_cone_tpq(c, l, m, h, tp, T, P, Q);
        *tm = *tp = *T = *P = *Q = 0.0; /* its paint constant */
        return 1;
    }
    if (!g->rg) {
        *tp = g->gp->tx;
        *T = fabs(*tm) + fabs(*tp) * h, *P = fabs(*tp), *Q = 0.0;
        return 1;
    }
    const rad_row *r = &c->row[l];
    double ia = 1.0 / fabs(g->rg->a), um = fabs(m - r->x0);
    /* dmin's rounding (RAD_DMIN_ULPS of itself, rad_row_at) counted as
     * in gen_layer_tp: dmin raised in |t|'s bound and in |t''|'s
     * numerator, lowered where it lowers a bound's denominator */
    double de = r->de;
    double Z = um + h, lo = fmax(0.0, um - h), dlo = r->d2 * lo * lo + (r->dmin - de);
    if (r->dmin == 0.0) {
        if (!(um >= h))
            return 0; /* x0 inside: a kink, which is a cut */
        *Q = 0.0;
    } else if (dlo > 0.0)
        *Q = r->d2 * (fabs(r->dmin) + de) * ia / (dlo * sqrt(dlo));
    else
        return 0;
    double dm = r->d2 * um * um + r->dmin, dz = sqrt(r->d2 * Z * Z + (r->dmin + de));
    if (!(dm > 0.0))
        return 0;
    *tp = (r->b1 - r->d2 * (m - r->x0) / sqrt(dm)) / g->rg->a;
    double U = r->dmin >= 0.0 ? Z : lo, dU = sqrt(fmax(r->d2 * U * U + (r->dmin - de), 0.0));
    *T = (fabs(r->b0 + r->b1 * m) + fabs(r->b1) * h + dz) * ia;
    *P = (fabs(r->b1) + (dU > 0.0 ? r->d2 * U / dU : 0.0)) * ia;
    return 1;
}

/* A painted cone-case layer's t'(m) and bounds of |t|, |t'| and |t''| on
 * the real segment [m - h, m + h] of a piece in x ("a cone beside other
 * gradients": its ends are no tangent line's crossing, so d > 0 there).
 * With L_k = lam_k x + mu_k on the row, d = L0 L1, d' = lam0 L1 + lam1 L0
 * and d'' = 2 lam0 lam1, t = (b + sqrt d) / a has t' = (b1 + d' / (2
 * sqrt d)) / a and t'' = (2 d d'' - d'^2) / (4 a d^(3/2)) = -(lam0 mu1 -
 * lam1 mu0)^2 / (4 a d^(3/2)), the x terms cancelling; |d| >= |L0| |L1|
 * each bounded below by |lam_k| times its zero's distance from the
 * segment (gen_layer_tp's T and P).  CONE_HALF: t = c / (2 b), t' = (c'
 * b - c b1) / (2 b^2), t'' = c'' / (2 b) - c' b1 / b^2 + c b1^2 / b^3,
 * |b| >= |b(m)| - |b1| h > 0. */
static int gen_cone_tpq(const gen_span_ctx *c, int l, double m, double h, double *tp, double *T,
                        double *P, double *Q)
{
    const grad_radial *q = c->L[l]->rg;
    const rad_row *r = &c->row[l];
    if (!gen_layer_tp(c, l, m, h, 0.0, T, P))
        return 0;
    double bm = r->b0 + r->b1 * m;
    if (q->cone == CONE_HALF) {
        double bl = fabs(bm) - fabs(r->b1) * h, cm = r->c0 + m * (r->c1 + m * r->c2);
        double c1m = r->c1 + 2.0 * r->c2 * m, c1b = fabs(c1m) + 2.0 * r->c2 * h;
        double cz = fabs(cm) + fabs(c1m) * h + r->c2 * h * h;
        if (!(bl > 0.0))
            return 0;
        *tp = (c1m * bm - cm * r->b1) / (2.0 * bm * bm);
        *Q = r->c2 / bl + c1b * fabs(r->b1) / (bl * bl) + cz * r->b1 * r->b1 / (bl * bl * bl);
        return 1;
    }
    double complex lam0 = c->lam[l][0], lam1 = c->lam[l][1], mu0 = c->mu[l][0], mu1 = c->mu[l][1];
    double complex L0 = lam0 * m + mu0, L1 = lam1 * m + mu1;
    double dm = creal(L0 * L1), dpm = creal(lam0 * L1 + lam1 * L0), lo = 1.0;
    for (int k = 0; k < 2; k++) {
        double complex lam = c->lam[l][k], mu = c->mu[l][k];
        if (lam == 0.0)
            lo *= cabs(mu);
        else {
            double complex z = -mu / lam;
            lo *= cabs(lam) * fmax(fabs(creal(z) - m) - h, fabs(cimag(z)));
        }
    }
    if (!(lo > 0.0 && dm > 0.0))
        return 0;
    double k2 = cabs(lam0 * mu1 - lam1 * mu0);
    *tp = (r->b1 + dpm / (2.0 * sqrt(dm))) / q->a;
    *Q = k2 * k2 / (4.0 * fabs(q->a) * lo * sqrt(lo));
    return 1;
}

static int fold_taylor(const gen_span_ctx *c, int ch, double m, double h, double *d1, double *d2);

/* Channel ch's e'(m), exact, into *d1, and a bound of |e''| on the real
 * segment [m - h, m + h] into *d2 (the comment above "several gradients
 * at a point"); 0 if no bound is had (a radial layer's d reaching 0
 * there). */
static int gen_taylor(const gen_span_ctx *c, int ch, double m, double h, double *d1, double *d2)
{
    double f[GEN_MAX][3], fp[GEN_MAX][3], F[GEN_MAX][3], G[GEN_MAX][3], H[GEN_MAX][3];
    if (c->umode)
        return 0; /* in u: the Lipschitz test alone ("a cone beside other gradients") */
    if (c->fold)
        return fold_taylor(c, ch, m, h, d1, d2);
    for (int l = 0; l < c->n; l++) {
        double tm, tp, T, P, Q;
        if (!gen_tpq(c, l, m, h, &tm, &tp, &T, &P, &Q))
            return 0;
        double o0 = c->v0[l][3], o1 = c->v1[l][3], c0 = c->v0[l][ch], c1 = c->v1[l][ch];
        double op = o0 + o1 * tm, cc = c0 + c1 * tm;
        f[l][0] = 1.0, f[l][1] = op, f[l][2] = op * cc;
        fp[l][0] = 0.0, fp[l][1] = o1 * tp, fp[l][2] = (o1 * cc + c1 * op) * tp;
        double opb = fabs(o0) + fabs(o1) * T, ccb = fabs(c0) + fabs(c1) * T;
        F[l][0] = 1.0, F[l][1] = opb, F[l][2] = opb * ccb;
        G[l][0] = 0.0, G[l][1] = fabs(o1) * P, G[l][2] = (fabs(o1) * ccb + fabs(c1) * opb) * P;
        H[l][0] = 0.0, H[l][1] = fabs(o1) * Q;
        H[l][2] = 2.0 * fabs(o1 * c1) * P * P + (fabs(o1) * ccb + fabs(c1) * opb) * Q;
        if (c->pw[l][ch]) {
            /* linear light, C = 1.055 v^p - 0.055 (p = 1/2.4) of v = c0 +
             * c1 t: on the segment |v - v(m)| <= |c1| P h, so with vlo =
             * v(m) - |c1| P h > 0, |C| <= 1.055 (v(m) + |c1| P h)^p +
             * 0.055, |C'| <= 1.055 p vlo^(p-1) |c1| P and |C''| <= 1.055
             * p (1 - p) vlo^(p-2) c1^2 P^2 + 1.055 p vlo^(p-1) |c1| Q;
             * (op C)'' = o1 t'' C + 2 o1 t' C' + op C'' */
            const double pe = 1.0 / 2.4;
            double vm = c0 + c1 * tm, d = fabs(c1) * P * h, vlo = vm - d;
            if (!(vlo > 0.0))
                return 0;
            double Cm = lin_enc(vm), C1 = 1.055 * pe * pow(vm, pe - 1.0) * c1 * tp;
            double Cb = 1.055 * pow(vm + d, pe) + 0.055;
            double C1b = 1.055 * pe * pow(vlo, pe - 1.0) * fabs(c1) * P;
            double C2b = 1.055 * pe * (1.0 - pe) * pow(vlo, pe - 2.0) * c1 * c1 * P * P +
                         1.055 * pe * pow(vlo, pe - 1.0) * fabs(c1) * Q;
            f[l][2] = op * Cm, fp[l][2] = o1 * tp * Cm + op * C1;
            F[l][2] = opb * Cb, G[l][2] = fabs(o1) * P * Cb + opb * C1b;
            H[l][2] = fabs(o1) * Q * Cb + 2.0 * fabs(o1) * P * C1b + opb * C2b;
        }
    }
    double s1 = 0.0, s2 = 0.0;
    for (int a = 0; a < c->nk; a++) {
        double k = c->K[ch][a];
        if (k == 0.0)
            continue;
        int q[GEN_MAX];
        for (int l = 0, z = a; l < c->n; l++, z /= 3)
            q[l] = z % 3;
        for (int l = 0; l < c->n; l++) {
            /* e': sum_l f_l' prod_{j != l} f_j; |e''| <= sum_l H_l prod_{j
             * != l} F_j + sum_{l != i} G_l G_i prod_{j != l, i} F_j */
            double p1 = k * fp[l][q[l]], p2 = fabs(k) * H[l][q[l]];
            for (int j = 0; j < c->n; j++)
                if (j != l)
                    p1 *= f[j][q[j]], p2 *= F[j][q[j]];
            s1 += p1, s2 += p2;
            for (int i = 0; i < c->n; i++) {
                if (i == l)
                    continue;
                double p = fabs(k) * G[l][q[l]] * G[i][q[i]];
                for (int j = 0; j < c->n && p != 0.0; j++)
                    if (j != l && j != i)
                        p *= F[j][q[j]];
                s2 += p;
            }
        }
    }
    *d1 = s1, *d2 = s2;
    return 1;
}

/* ---- more than GEN_MAX layers: the fold ----
 *
 * Past GEN_MAX layers the 3^n coefficients are not read; the composite is
 * folded over the scene's steps (aa_scene_fold: the walk of core's
 * composite, back to front from the solid layer behind or the
 * background): each layer source over its group's accumulator, p := a C
 * + (1 - a) p and alpha := a + (1 - a) alpha (a the layer's alpha times
 * its opacity op, a C its alpha times op C), each group closed over its
 * parent's with its opacity o, p := o p_g + (1 - o alpha_g) p and alpha
 * := o alpha_g + (1 - o alpha_g) alpha; a gradient layer the span does
 * not depend on is transparent (skipped), as in K.  The value at x is
 * this fold in double (fold_eval).  The bounds carry, for every quantity
 * q of the fold (a layer's op, C, op C, each accumulator's p and alpha),
 * a jet on a region about m of radius A (the Bernstein ellipse, |z - m|
 * <= A, or the real segment, A = h): q(m), q'(m) (on the segment only),
 * D >= sup |q'|, H >= sup |q''| (the segment only) and S >= sup |q|.
 * A layer's jets come from its t's bounds (gen_layer_tp_s, gen_tpq: op =
 * o0 + o1 t has D = |o1| P, H = |o1| Q, S = |o0| + |o1| T; linear light
 * as in gen_bounds and gen_taylor; all in the piece's variable, u on a
 * piece in u, a flat layer's T = P = 0), and the fold's operations keep
 * them bounds:
 *     (r s)' = r' s + r s',  (r s)'' = r'' s + 2 r' s' + r s'',
 * so D(r s) = D_r S_s + S_r D_s, H(r s) = H_r S_s + 2 D_r D_s + S_r H_s,
 * S(r s) = S_r S_s, sums add, and S is also taken as |q(m)| + D A (the
 * segment from m to any point of the region lies in it, the ellipse
 * being convex).  That centred form is what keeps the bounds from
 * growing with the number of layers: |1 - a(z)| <= (1 - a(m)) + D_a A, a
 * factor at most about 1 per layer where |1 - a| <= 1 + |a| would give
 * 1.5^n (3e5 for n = 32, and the power piece's test A |e'| < 0.9 (e(m) +
 * 0.055) would halve the pieces as much).  The composite's channel jet
 * gives gen_bounds' |e| <= S, |e'| <= D and gen_taylor's e'(m) and |e''|
 * <= H, so the threshold's isolation and the rule's Bernstein-ellipse
 * bound are those of the path above, with the fold's bounds in place of
 * sum |K_a| prod F; gen_taylor's rule holds the same (in u no Taylor
 * bound: the Lipschitz test alone, "a cone beside other gradients").
 * Work per evaluation is one pass over the scene's steps, linear in the
 * layers. */
typedef struct gjet {
    double v, d, D, H, S;
} gjet;

static gjet jet_const(double k) { return (gjet){k, 0.0, 0.0, 0.0, fabs(k)}; }

static gjet jet_tight(gjet q, double A)
{
    q.S = fmin(q.S, fabs(q.v) + q.D * A);
    return q;
}

static gjet jet_scale(gjet q, double k)
{
    double ak = fabs(k);
    return (gjet){k * q.v, k * q.d, ak * q.D, ak * q.H, ak * q.S};
}

static gjet jet_mul(gjet r, gjet s, double A)
{
    gjet q = {r.v * s.v, r.d * s.v + r.v * s.d, r.D * s.S + r.S * s.D,
              r.H * s.S + 2.0 * r.D * s.D + r.S * s.H, r.S * s.S};
    return jet_tight(q, A);
}

/* ac + (1 - a) p */
static gjet jet_over(gjet ac, gjet a, gjet p, double A)
{
    gjet u = {1.0 - a.v, -a.d, a.D, a.H, 1.0 + a.S}, q;
    u = jet_tight(u, A);
    q = jet_mul(u, p, A);
    q.v += ac.v, q.d += ac.d, q.D += ac.D, q.H += ac.H, q.S += ac.S;
    return jet_tight(q, A);
}

/* The fold's channel ch given each of the span's layers' a (alpha times
 * op) and a C jets (the comment above). */
static gjet fold_run(const gen_span_ctx *c, int ch, const gjet *la, const gjet *lac, double A)
{
    gjet p[AA_SCENE_MAX_GROUP_DEPTH + 1], al[AA_SCENE_MAX_GROUP_DEPTH + 1];
    int d = 0;
    p[0] = jet_const(c->base[ch]), al[0] = jet_const(1.0);
    for (int k = 0; k < c->nst; k++) {
        const aa_fold_step *st = &c->st[k];
        if (st->op == AA_FOLD_OPEN) {
            d++;
            p[d] = al[d] = jet_const(0.0);
        } else if (st->op == AA_FOLD_CLOSE) {
            gjet op = jet_scale(p[d], st->a), oa = jet_scale(al[d], st->a);
            p[d - 1] = jet_over(op, oa, p[d - 1], A);
            al[d - 1] = jet_over(oa, oa, al[d - 1], A);
            d--;
        } else if (c->sl[k] >= 0) {
            int l = c->sl[k];
            p[d] = jet_over(lac[l], la[l], p[d], A);
            al[d] = jet_over(la[l], la[l], al[d], A);
        } else if (c->sl[k] == -2) {
            gjet a = jet_const(st->a);
            p[d] = jet_over(jet_const(st->a * st->c[ch]), a, p[d], A);
            al[d] = jet_over(a, a, al[d], A);
        }
    }
    return p[0];
}

/* e of each channel at real x by the fold. */
static void fold_eval(const gen_span_ctx *c, double x, double *e)
{
    double a[GEN_LAYERS], ac[GEN_LAYERS][3];
    double p[AA_SCENE_MAX_GROUP_DEPTH + 1][3], al[AA_SCENE_MAX_GROUP_DEPTH + 1];
    for (int l = 0; l < c->n; l++) {
        double t = gen_t(c, l, x), op = c->v0[l][3] + c->v1[l][3] * t;
        a[l] = op;
        for (int ch = 0; ch < c->nch; ch++) {
            double v = c->v0[l][ch] + c->v1[l][ch] * t;
            ac[l][ch] = op * gen_enc(c, l, ch, t, v);
        }
    }
    int d = 0;
    for (int ch = 0; ch < 3; ch++)
        p[0][ch] = c->base[ch];
    al[0] = 1.0;
    for (int k = 0; k < c->nst; k++) {
        const aa_fold_step *st = &c->st[k];
        if (st->op == AA_FOLD_OPEN) {
            d++;
            p[d][0] = p[d][1] = p[d][2] = al[d] = 0.0;
        } else if (st->op == AA_FOLD_CLOSE) {
            double oa = st->a * al[d];
            for (int ch = 0; ch < c->nch; ch++)
                p[d - 1][ch] = st->a * p[d][ch] + (1.0 - oa) * p[d - 1][ch];
            al[d - 1] = oa + (1.0 - oa) * al[d - 1];
            d--;
        } else if (c->sl[k] != -1) {
            int l = c->sl[k];
            double aa = l >= 0 ? st->a * a[l] : st->a;
            for (int ch = 0; ch < c->nch; ch++) {
                double acc = l >= 0 ? st->a * ac[l][ch] : st->a * st->c[ch];
                p[d][ch] = acc + (1.0 - aa) * p[d][ch];
            }
            al[d] = aa + (1.0 - aa) * al[d];
        }
    }
    for (int ch = 0; ch < c->nch; ch++)
        e[ch] = p[0][ch];
}

/* Layer l's jets of a (alpha times op) and a C, channel ch, on the region
 * of radius A about m: the ellipse (taylor 0; T, P its gen_layer_tp_s
 * bounds) or the segment (taylor 1; tm, tp, T, P, Q of gen_tpq); 0 if a
 * linear-light channel may reach its branch point there. */
static int fold_layer(const gen_span_ctx *c, int l, int ch, double A, int taylor, double tm,
                      double tp, double T, double P, double Q, double alpha, gjet *a, gjet *ac)
{
    double o0 = c->v0[l][3], o1 = c->v1[l][3], c0 = c->v0[l][ch], c1 = c->v1[l][ch];
    gjet op = {o0 + o1 * tm, o1 * tp, fabs(o1) * P, fabs(o1) * Q, fabs(o0) + fabs(o1) * T};
    gjet C = {c0 + c1 * tm, c1 * tp, fabs(c1) * P, fabs(c1) * Q, fabs(c0) + fabs(c1) * T};
    op = jet_tight(op, A), C = jet_tight(C, A);
    if (c->pw[l][ch]) {
        /* linear light, C = 1.055 v^p - 0.055 (p = 1/2.4): as gen_bounds
         * (the ellipse) and gen_taylor (the segment) bound it */
        const double pe = 1.0 / 2.4;
        double vm = c0 + c1 * tm, dv = fabs(c1) * P * A, vlo = vm - dv;
        if (!(taylor ? vlo > 0.0 : dv < 0.9 * vm))
            return 0;
        C.v = lin_enc(vm);
        C.d = 1.055 * pe * pow(vm, pe - 1.0) * c1 * tp;
        C.S = 1.055 * pow(vm + dv, pe) + 0.055;
        C.D = 1.055 * pe * pow(vlo, pe - 1.0) * fabs(c1) * P;
        C.H = 1.055 * pe * (1.0 - pe) * pow(vlo, pe - 2.0) * c1 * c1 * P * P +
              1.055 * pe * pow(vlo, pe - 1.0) * fabs(c1) * Q;
    }
    *a = jet_scale(op, alpha);
    *ac = jet_scale(jet_mul(op, C, A), alpha);
    return 1;
}

/* The layer's own alpha: that of the fold's step that paints it. */
static void fold_alphas(const gen_span_ctx *c, double *alpha)
{
    for (int l = 0; l < c->n; l++)
        alpha[l] = 0.0;
    for (int k = 0; k < c->nst; k++)
        if (c->st[k].op == AA_FOLD_LAYER && c->sl[k] >= 0)
            alpha[c->sl[k]] = c->st[k].a;
}

/* gen_bounds by the fold. */
static int fold_bounds(const gen_span_ctx *c, double m, double A, double B, double *emax,
                       double *dmax)
{
    double T[GEN_LAYERS], P[GEN_LAYERS], tm[GEN_LAYERS], alpha[GEN_LAYERS];
    gjet a[GEN_LAYERS], ac[GEN_LAYERS];
    fold_alphas(c, alpha);
    for (int l = 0; l < c->n; l++) {
        if (!gen_layer_tp_s(c, l, m, A, B, &T[l], &P[l]))
            return 0;
        tm[l] = gen_t(c, l, m);
    }
    for (int ch = 0; ch < c->nch; ch++) {
        for (int l = 0; l < c->n; l++)
            if (!fold_layer(c, l, ch, A, 0, tm[l], 0.0, T[l], P[l], 0.0, alpha[l], &a[l], &ac[l]))
                return 0;
        gjet e = fold_run(c, ch, a, ac, A);
        emax[ch] = e.S, dmax[ch] = e.D;
    }
    return 1;
}

/* gen_taylor by the fold. */
static int fold_taylor(const gen_span_ctx *c, int ch, double m, double h, double *d1, double *d2)
{
    double alpha[GEN_LAYERS];
    gjet a[GEN_LAYERS], ac[GEN_LAYERS];
    fold_alphas(c, alpha);
    for (int l = 0; l < c->n; l++) {
        double tm, tp, T, P, Q;
        if (!gen_tpq(c, l, m, h, &tm, &tp, &T, &P, &Q) ||
            !fold_layer(c, l, ch, h, 1, tm, tp, T, P, Q, alpha[l], &a[l], &ac[l]))
            return 0;
    }
    gjet e = fold_run(c, ch, a, ac, h);
    *d1 = e.d, *d2 = e.H;
    return 1;
}

/* Halving [*u, *v] to GEN_FUZZ on whether g (channel ch) is nonzero of
 * sign sg (< 0 or not): true at *u and false at *v if lo_true, the
 * reverse if not; 0, or 1 when the work budget ran out. */
static int gen_halve_sign(const gen_span_ctx *c, int ch, int sg, int lo_true, double *u,
                          double *v, size_t *budget)
{
    while (*v - *u > GEN_FUZZ * (1.0 + fabs(0.5 * (*u + *v)))) {
        double m = 0.5 * (*u + *v), e[3];
        if (!(m > *u && m < *v))
            break;
        if (*budget == 0)
            return 1;
        --*budget;
        gen_eval(c, m, e);
        double gm = e[ch] - 0.04045;
        int p = gm != 0.0 && (gm < 0.0) == sg;
        if (p == lo_true)
            *u = m;
        else
            *v = m;
    }
    return 0;
}

/* The one root of g, monotone on [u, v] with signs differing at the ends
 * (gu, gv), narrowed by halving on the signs to GEN_FUZZ and appended to
 * fz (none if at an end, where the piece is cut anyway).  A midpoint m
 * where g is 0 in double keeps the root in the interval: it once ended
 * the halving holding nothing, and the piece across the root took one
 * side's decoding (a stack's row 2.6e-11 off, whose composite crossed
 * 0.04045 with a slope of 1.7e-4, a few ulps a step).  Ending it there
 * instead left [u, v] as wide as it was, up to the whole piece, taken by
 * its midpoint with the bound of the colour's spread across it (8.7e-4
 * a row where a linear gradient's threshold line passed the middle of a
 * span: the first midpoint); so the halving goes on in [u, m] for the
 * last point of gu's sign and in [m, v] for the first of gv's, and the
 * interval between them (holding every zero) is kept, to GEN_FUZZ at
 * each end (gen_halve_sign). */
static size_t gen_bisect(const gen_span_ctx *c, int ch, double u, double gu, double v, double gv,
                         double *fz, size_t nf, size_t cap, size_t *budget)
{
    if (gu == 0.0 || gv == 0.0)
        return nf;
    while (v - u > GEN_FUZZ * (1.0 + fabs(0.5 * (u + v)))) {
        double m = 0.5 * (u + v), e[3];
        if (!(m > u && m < v))
            break;
        if (*budget == 0)
            return cap;
        --*budget;
        gen_eval(c, m, e);
        double gm = e[ch] - 0.04045;
        if (gm == 0.0) {
            /* the threshold at m: the last point of gu's sign in [u, m],
             * the first of gv's in [m, v] */
            double l = m, r = m;
            if (gen_halve_sign(c, ch, gu < 0.0, 1, &u, &l, budget) ||
                gen_halve_sign(c, ch, gv < 0.0, 0, &r, &v, budget))
                return cap;
            break;
        }
        if ((gm < 0.0) == (gu < 0.0))
            u = m, gu = gm;
        else
            v = m;
    }
    if (nf < cap)
        fz[2 * nf] = u, fz[2 * nf + 1] = v, nf++;
    return nf;
}

/* The threshold's places in [u, v] for the channels in the mask act (bit
 * ch; g = e - 0.04045 there gu[ch], gv[ch]): intervals no wider than
 * GEN_FUZZ that may hold a root appended to fz (pairs), at most cap pairs,
 * each channel's count added to cnt[ch]; the count returned (cap or more:
 * no room, or work).  Each channel's places and work are those of
 * isolating it alone; the channels share a halving's bounds on the
 * segment and its colour at the midpoint, computed once for all. */
static size_t gen_isolate_all(const gen_span_ctx *c, int act, double u, const double *gu,
                              double v, const double *gv, double *fz, size_t nf, size_t cap,
                              size_t *budget, size_t *cnt)
{
    double m = 0.5 * (u + v), h = 0.5 * (v - u), emax[3], dmax[3], e[3], gm[3] = {0, 0, 0};
    int bounds = -1, have_e = 0, next = 0;
    int leaf = v - u <= GEN_FUZZ * (1.0 + fabs(m)) || !(m > u && m < v);
    for (int ch = 0; ch < c->nch; ch++) {
        if (!(act >> ch & 1))
            continue;
        if (*budget == 0)
            return cap; /* too many intervals: the caller gives up on the piece */
        --*budget;
        if (gu[ch] != 0.0 && gv[ch] != 0.0 && (gu[ch] < 0.0) == (gv[ch] < 0.0)) {
            if (bounds < 0)
                bounds = gen_bounds(c, m, h, 0.0, emax, dmax);
            if (bounds && fabs(gu[ch]) + fabs(gv[ch]) > dmax[ch] * (v - u))
                continue; /* certified free of roots */
        }
        if (leaf) {
            if (nf < cap)
                fz[2 * nf] = u, fz[2 * nf + 1] = v, nf++, cnt[ch]++;
            continue;
        }
        double d1, d2;
        if (!have_e)
            gen_eval(c, m, e), have_e = 1;
        gm[ch] = e[ch] - 0.04045;
        if (gen_taylor(c, ch, m, h, &d1, &d2)) {
            if (d1 == 0.0 && d2 == 0.0)
                continue; /* constant there: no crossing, even at 0.04045 */
            if (fabs(gm[ch]) > fabs(d1) * h + 0.5 * d2 * h * h)
                continue; /* Taylor: no root */
            if (fabs(d1) > d2 * h) { /* monotone */
                if (gu[ch] != 0.0 && gv[ch] != 0.0 && (gu[ch] < 0.0) == (gv[ch] < 0.0))
                    continue;
                size_t before = nf;
                nf = gen_bisect(c, ch, u, gu[ch], v, gv[ch], fz, nf, cap, budget);
                if (nf >= cap)
                    return nf;
                cnt[ch] += nf - before;
                continue;
            }
        }
        next |= 1 << ch;
    }
    if (!next || nf >= cap)
        return nf;
    nf = gen_isolate_all(c, next, u, gu, m, gm, fz, nf, cap, budget, cnt);
    if (nf >= cap)
        return nf;
    return gen_isolate_all(c, next, m, gm, v, gv, fz, nf, cap, budget, cnt);
}

static int rad_same_t(const grad_radial *g, const grad_radial *h);

/* Whether layers l and m of the path of several gradients share one t
 * (the same plane, or radial gradients of the same map). */
static int gen_same_t(const gen_layer *l, const gen_layer *m)
{
    if (l->rg && m->rg)
        return rad_same_t(l->rg, m->rg);
    if (l->gp && m->gp)
        return l->gp->tx == m->gp->tx && l->gp->ty == m->gp->ty && l->gp->t0 == m->gp->t0;
    return 0;
}

/* Whether the span's layers are of different t (the threshold's curve is
 * no circle or line of one t there: thr_heights). */
static int gen_mixes(const gen_span_ctx *c)
{
    for (int l = 1; l < c->n; l++)
        if (!gen_same_t(c->L[0], c->L[l]))
            return 1;
    return 0;
}

/* Intervals that may hold the threshold, and halvings, one piece may
 * take; past them the pixel is refused (gen_section). */
#define GEN_MAX_FUZZ 256
#define GEN_BUDGET 20000

/* The piece [a, b] (no stop, period end or x0 inside): the threshold's
 * places isolated per channel, the intervals between them by gen_piece,
 * those that may hold a root by their midpoint. */
static void gen_section(worker *w, const gen_span_ctx *c, double a, double b, double *sum,
                        double *err)
{
    double fz[2 * GEN_MAX_FUZZ], ea[3], eb[3];
    size_t nf = 0, budget = GEN_BUDGET;
    gen_eval(c, a, ea);
    gen_eval(c, b, eb);
    int mixed = w->scan && gen_mixes(c);
    double ga[3] = {0, 0, 0}, gb[3] = {0, 0, 0};
    size_t cnt[3] = {0, 0, 0};
    for (int ch = 0; ch < c->nch; ch++)
        ga[ch] = ea[ch] - 0.04045, gb[ch] = eb[ch] - 0.04045;
    nf = gen_isolate_all(c, (1 << c->nch) - 1, a, ga, b, gb, fz, nf, GEN_MAX_FUZZ, &budget, cnt);
    for (int ch = 0; ch < c->nch && mixed && nf < GEN_MAX_FUZZ; ch++) {
        if (w->nsig < SIG_MAX)
            w->sig[w->nsig++] = (int)cnt[ch];
        else
            w->sig_over = 1;
    }
    if (nf >= GEN_MAX_FUZZ) { /* more places than room, or work: the pixel refused */
        w->gen_stuck = 1;
        return;
    }
    /* the intervals in order, merged where they overlap */
    qsort(fz, nf, 2 * sizeof *fz, cmp_dbl);
    double cur = a;
    for (size_t k = 0; k <= nf; k++) {
        double fa = k < nf ? fz[2 * k] : b, fb = k < nf ? fz[2 * k + 1] : b;
        while (k + 1 < nf && fz[2 * k + 2] <= fb)
            fb = fmax(fb, fz[2 * ++k + 1]);
        if (fa > cur) {
            double e[3];
            int power[3];
            gen_eval(c, 0.5 * (cur + fa), e);
            for (int ch = 0; ch < c->nch; ch++)
                power[ch] = e[ch] > 0.04045;
            gen_piece(w, c, power, cur, fa, 0, sum, err);
        }
        if (fb > fa) {
            double e[3], emax[3], dmax[3], wd = fb - fa, worst = 1.0;
            gen_eval(c, 0.5 * (fa + fb), e);
            if (gen_bounds(c, 0.5 * (fa + fb), 0.5 * wd, 0.0, emax, dmax)) {
                worst = 0.0;
                for (int ch = 0; ch < c->nch; ch++)
                    worst = fmax(worst, 2.3 * dmax[ch] * wd + 2.4e-9);
            }
            if (c->umode) {
                /* in u: the interval's x range [pa, pb] (the colour's
                 * spread over it is the same whichever the variable),
                 * weighed at x(mid), inside it */
                double pa = gen_x(c, fa), pb = gen_x(c, fb), lx = fabs(pb - pa);
                double xm = gen_x(c, 0.5 * (fa + fb)), wm = 1.0, sup = 1.0, slope = 0.0;
                if (!(lx > 0.0)) /* below x's resolution: its length from u */
                    lx = fmax((fb - fa) * (fb + fa) * (1.0 + 4.0 * DBL_EPSILON), 0x1p-1021);
                if (c->weighted) {
                    wm = c->radial ? rwt(c, xm - c->uc) : aa_filter_weight(c->f, xm - c->uc);
                    wt_real(c, 0.5 * (pa + pb), 0.5 * lx, &sup, &slope);
                }
                for (int ch = 0; ch < c->nch; ch++)
                    sum[ch] += lx * aa_srgb_decode(e[ch]) * wm;
                *err += lx * (sup * fmin(1.0, worst) + slope * lx);
            } else if (c->weighted) {
                /* |f w - f(m) w(m)| <= |f - f(m)| sup |w| + |f(m)| |w - w(m)|,
                 * f in [0, 1] */
                double mid = 0.5 * (fa + fb), sup, slope,
                       wm = c->radial ? rwt(c, mid - c->uc) : aa_filter_weight(c->f, mid - c->uc);
                wt_real(c, mid, 0.5 * wd, &sup, &slope);
                for (int ch = 0; ch < c->nch; ch++)
                    sum[ch] += wd * aa_srgb_decode(e[ch]) * wm;
                *err += wd * (sup * fmin(1.0, worst) + slope * wd);
            } else {
                for (int ch = 0; ch < c->nch; ch++)
                    sum[ch] += wd * aa_srgb_decode(e[ch]);
                *err += wd * fmin(1.0, worst);
            }
        }
        cur = fmax(cur, fb);
    }
}

/* The gradient layers span's colour depends on, at winding w->wind: a
 * layer whose paint set to transparent, opaque black and opaque white
 * (the others transparent) changes the composite.  Their indices in dep
 * (the first GEN_LAYERS), the last such layer of a cone-case gradient in
 * *cone (-1 if none; cone may be NULL), the composite with every layer
 * transparent in f0 (the span's colour where none is found); returns how
 * many were found.  w->gl_paint is left transparent. */
static int span_deps(worker *w, int dep[GEN_LAYERS], int *cone, double f0[3])
{
    static const double P[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
    int N = w->ngl, *layers = w->gl_layer, nd = 0;
    double *paints = w->gl_paint, f[3][3];
    memset(paints, 0, 4 * (size_t)N * sizeof *paints);
    if (cone)
        *cone = -1;
    for (int k = 0; k < N; k++) {
        for (int q = 0; q < 3; q++) {
            memcpy(paints + 4 * k, P[q], 4 * sizeof *paints);
            aa_scene_encoded_with_n(w->scene, w->wind, N, layers, paints, f[q]);
        }
        memset(paints + 4 * k, 0, 4 * sizeof *paints);
        if (f[0][0] != f[1][0] || f[0][1] != f[1][1] || f[0][2] != f[1][2] ||
            f[1][0] != f[2][0] || f[1][1] != f[2][1] || f[1][2] != f[2][2]) {
            if (nd < GEN_LAYERS)
                dep[nd] = k;
            nd++;
            if (cone && w->gl[k].rg && w->gl[k].rg->cone)
                *cone = k;
        }
    }
    if (N > 0)
        memcpy(f0, f[0], 3 * sizeof *f0);
    return nd;
}

/* The row's crossing of cone-case layer q's tangent line L_k = lam x + mu
 * = 0 (CONE_HALF: the edge, k = 0; CONE_NESTED: k = 0, the real part of
 * L0's zero, the row's point nearest P*), else NAN. */
static double cone_cross(const grad_radial *q, const double complex lam[2],
                         const double complex mu[2], int k)
{
    if (q->cone == CONE_NESTED)
        return k == 0 && lam[0] != 0.0 ? creal(-mu[0] / lam[0]) : NAN;
    if (q->cone == CONE_HALF && k == 1)
        return NAN;
    return creal(lam[k]) != 0.0 ? -creal(mu[k]) / creal(lam[k]) : NAN;
}

/* The piece's variable set to u from the zero xr of layer l's L_k, x =
 * xr + eps u^2 (cone_root: sqrt(d) = u sqrt(P0 + P1 u^2)). */
static void gen_root(gen_span_ctx *c, int l, int k, double xr, double eps)
{
    int o = 1 - k;
    double lk = creal(c->lam[l][k]), lo = creal(c->lam[l][o]);
    double Lo = creal(c->lam[l][o] * xr + c->mu[l][o]);
    c->umode = 1, c->ul = l, c->xr = xr, c->eps = eps;
    c->P0 = eps * lk * Lo, c->P1 = lk * lo;
    c->sxm = c->sxh = 0.0;
    for (int q = 0; q < c->n; q++) /* layers of the same cone: the same forms */
        c->uroot[q] = c->L[q]->rg && c->L[q]->rg->cone && !c->flat[q] &&
                      c->lam[q][0] == c->lam[l][0] && c->lam[q][1] == c->lam[l][1] &&
                      c->mu[q][0] == c->mu[l][0] && c->mu[q][1] == c->mu[l][1];
}

/* The span [xa, xb] of row y (winding w->wind) by the path above (past
 * GEN_MAX layers, the fold); a span painted by more than GEN_LAYERS
 * gradient layers sets w->gen_over and is left out (the pixel is
 * refused). */
static void gen_span(worker *w, double xa, double xb, double y, int nch, double *sum)
{
    static const double P[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
    int N = w->ngl, *layers = w->gl_layer, dep[GEN_LAYERS], nd;
    double *paints = w->gl_paint;
    if (!chord_clip(w, &xa, &xb)) /* the span clipped to the support's chord */
        return;
    double f[1][3];
    if ((nd = span_deps(w, dep, NULL, f[0])) > GEN_LAYERS) {
        w->gen_over = 1;
        return;
    }
    if (nd == 0) { /* of constant colour: weighted, the cdf's difference */
        double wd = w->box      ? xb - xa
                    : w->radial ? aa_filter_row_cdf(w->f, w->row_s, xb - w->uc) -
                                      aa_filter_row_cdf(w->f, w->row_s, xa - w->uc)
                                : aa_filter_cdf(w->f, xb - w->uc) - aa_filter_cdf(w->f, xa - w->uc);
        for (int c = 0; c < nch; c++)
            sum[c] += wd * aa_srgb_decode(f[0][c]);
        return;
    }
    gen_span_ctx c;
    c.n = nd, c.nch = nch, c.y = y, c.nk = 1;
    c.weighted = !w->box, c.f = w->f, c.uc = w->uc;
    c.radial = w->radial, c.s = w->row_s, c.wn = w->radial ? aa_filter_weight2(w->f, 0.0, 0.0) : 0.0;
    c.umode = 0, c.ul = -1, c.xr = c.eps = c.P0 = c.P1 = 0.0;
    c.fold = nd > GEN_MAX;
    for (int l = 0; l < nd; l++) {
        c.L[l] = &w->gl[dep[l]];
        if (!c.fold)
            c.nk *= 3;
        c.flat[l] = c.uroot[l] = 0;
        if (c.L[l]->rg)
            rad_row_at(c.L[l]->rg, y, &c.row[l]);
        if (c.L[l]->rg && c.L[l]->rg->cone)
            for (int k = 0; k < 2; k++)
                c.lam[l][k] = c.L[l]->rg->lf[k][0],
                c.mu[l][k] = c.L[l]->rg->lf[k][1] * y + c.L[l]->rg->lf[k][2];
    }
    if (c.fold) { /* the scene's steps, each gradient layer's index among the span's */
        int ns = aa_scene_fold(w->scene, w->wind, N, layers, w->fold, w->cap_fold, c.base);
        if (ns < 0) { /* cannot happen: cap_fold is aa_scene_fold_cap's */
            w->gen_stuck = 1;
            return;
        }
        c.st = w->fold, c.nst = ns, c.sl = w->fold_sl;
        for (int k = 0; k < ns; k++) {
            int sl = -2, L = w->fold[k].layer;
            for (int j = 0; j < N && sl == -2; j++)
                if (layers[j] == L)
                    sl = -1;
            for (int l = 0; l < nd && sl == -1; l++)
                if (layers[dep[l]] == L)
                    sl = l;
            w->fold_sl[k] = sl;
        }
    }
    /* the coefficients: composites at every choice of paints, then the
     * differences f1 - f0, f2 - f1 along each layer's index */
    for (int a = 0; a < c.nk && !c.fold; a++) {
        double e[3];
        for (int l = 0, q = a; l < nd; l++, q /= 3)
            memcpy(paints + 4 * dep[l], P[q % 3], 4 * sizeof *paints);
        aa_scene_encoded_with_n(w->scene, w->wind, N, layers, paints, e);
        for (int ch = 0; ch < 3; ch++)
            c.K[ch][a] = e[ch];
    }
    for (int l = 0, stride = 1; l < nd && !c.fold; l++, stride *= 3)
        for (int a = 0; a < c.nk; a++) {
            if ((a / stride) % 3 != 0)
                continue;
            for (int ch = 0; ch < 3; ch++) {
                double f0 = c.K[ch][a], f1 = c.K[ch][a + stride], f2 = c.K[ch][a + 2 * stride];
                c.K[ch][a + stride] = f1 - f0;
                c.K[ch][a + 2 * stride] = f2 - f1;
            }
        }
    if (!c.fold)
        gen_terms(&c);
    /* the cuts: stops and periods' ends of every layer, radial x0 */
    double *xs = w->gbuf;
    size_t nx = 0, cap = w->cap_gbuf - 8;
    xs[nx++] = xa;
    for (int l = 0; l < nd; l++) {
        const gen_layer *g = c.L[l];
        double *taus = w->gbuf2;
        if (g->rg && g->rg->cone) {
            /* a cone-case layer: cut where the row crosses its tangent
             * lines (the half-plane's edge; nested, at its point nearest
             * P*), and at its stop circles over its range of t on the
             * painted part (cone_span) */
            const grad_radial *q = g->rg;
            for (int k = 0; k < 2 && nx < cap; k++) {
                double x = cone_cross(q, c.lam[l], c.mu[l], k);
                if (x > xa && x < xb)
                    xs[nx++] = x;
            }
            double tlo = -INFINITY, thi = INFINITY;
            if (q->spread != AA_SPREAD_PAD) {
                tlo = INFINITY, thi = -INFINITY;
                cone_seg_range(q, 0, xa, xb, y, &tlo, &thi);
                tlo -= 1e-12 * (1.0 + fabs(tlo));
                thi += 1e-12 * (1.0 + fabs(thi));
            }
            size_t mt = tlo <= thi ? grad_taus(&q->plane, tlo, thi, taus, w->cap_gbuf) : 0;
            if (mt > w->cap_gbuf)
                mt = w->cap_gbuf;
            for (size_t k = 0; k < mt && nx + 2 < cap; k++)
                nx += (size_t)rad_cross(q, &c.row[l], taus[k], xa, xb, xs + nx);
        } else if (g->rg) {
            const rad_row *r = &c.row[l];
            if (r->x0 > xa && r->x0 < xb && nx < cap)
                xs[nx++] = r->x0;
            double tlo = g->rg->spread == AA_SPREAD_PAD ? -INFINITY : rad_row_min(g->rg, xa, xb, y);
            double thi = fmax(rad_t(g->rg, xa, y), rad_t(g->rg, xb, y));
            size_t mt = grad_taus(&g->rg->plane, tlo, thi, taus, w->cap_gbuf);
            if (mt > w->cap_gbuf)
                mt = w->cap_gbuf;
            for (size_t k = 0; k < mt && nx + 2 < cap; k++)
                nx += (size_t)rad_cross(g->rg, r, taus[k], xa, xb, xs + nx);
        } else if (g->gp->tx != 0.0) {
            const grad_plane *gp = g->gp;
            double ta = gp->tx * xa + gp->ty * y + gp->t0, tb = gp->tx * xb + gp->ty * y + gp->t0;
            size_t mt = grad_taus(gp, fmin(ta, tb), fmax(ta, tb), taus, w->cap_gbuf);
            if (mt > w->cap_gbuf)
                mt = w->cap_gbuf;
            for (size_t k = 0; k < mt && nx < cap; k++) {
                double x = (taus[k] - gp->ty * y - gp->t0) / gp->tx;
                if (x > xa && x < xb)
                    xs[nx++] = x;
            }
        }
    }
    if (c.weighted) /* the filter's kinks: w is one piece between them */
        nx = add_kinks(w, xa, xb, xs, nx, cap);
    qsort(xs + 1, nx - 1, sizeof *xs, cmp_dbl);
    xs[nx++] = xb;
    double err = 0.0;
    w->gen_work = 0;
    for (size_t k = 0; k + 1 < nx && !w->gen_stuck; k++) {
        double a = xs[k], b = xs[k + 1];
        if (!(b > a))
            continue;
        c.umode = 0;
        for (int l = 0; l < nd; l++) {
            const gen_layer *g = c.L[l];
            c.flat[l] = 0;
            if (g->rg && g->rg->cone) {
                int painted;
                cone_d(g->rg, 0.5 * (a + b), y, &painted);
                if (!painted) { /* the layer transparent here */
                    memset(c.v0[l], 0, sizeof c.v0[l]), memset(c.v1[l], 0, sizeof c.v1[l]);
                    memset(c.pw[l], 0, sizeof c.pw[l]);
                    c.flat[l] = 1;
                    continue;
                }
            }
            double tm = gen_t(&c, l, 0.5 * (a + b));
            paint_lin(g->spread, g->stops, g->nstops, g->enc, tm, c.v0[l], c.v1[l]);
            if (g->rg && g->rg->cone)
                c.flat[l] = c.v1[l][0] == 0.0 && c.v1[l][1] == 0.0 && c.v1[l][2] == 0.0 &&
                            c.v1[l][3] == 0.0;
            for (int ch = 0; ch < 3; ch++) {
                c.pw[l][ch] = 0;
                if (!g->lin)
                    continue;
                /* linear light: the stops cut where a channel passes
                 * LIN_T, so on the piece it keeps to one side: below,
                 * the encoding is 12.92 v, affine; above, its power */
                if (c.v0[l][ch] + c.v1[l][ch] * tm > LIN_T) {
                    c.pw[l][ch] = 1;
                    if (c.v1[l][ch] == 0.0)
                        c.enc0[l][ch] = lin_enc(c.v0[l][ch]);
                } else
                    c.v0[l][ch] *= 12.92, c.v1[l][ch] *= 12.92;
            }
        }
        /* a painted cone layer whose tangent line the row crosses at a
         * or b: the piece next to it in u ("a cone beside other
         * gradients"), halved at its middle if both ends are such */
        int la = -1, ka = -1, lb = -1, kb = -1;
        for (int l = 0; l < nd; l++) {
            const grad_radial *q = c.L[l]->rg;
            if (!q || q->cone != CONE_WEDGE || c.flat[l])
                continue;
            for (int kk = 0; kk < 2; kk++) {
                double x = cone_cross(q, c.lam[l], c.mu[l], kk);
                if (x == a && la < 0)
                    la = l, ka = kk;
                if (x == b && lb < 0)
                    lb = l, kb = kk;
            }
        }
        if (la < 0 && lb < 0) {
            gen_section(w, &c, a, b, sum, &err);
            continue;
        }
        double mid = 0.5 * (a + b);
        if (la >= 0) {
            double e = lb >= 0 ? mid : b;
            gen_root(&c, la, ka, a, 1.0);
            c.sxm = 0.5 * (a + e), c.sxh = 0.5 * (e - a);
            gen_section(w, &c, 0.0, sqrt(e - a), sum, &err);
        }
        if (lb >= 0 && !w->gen_stuck) {
            double e = la >= 0 ? mid : a;
            gen_root(&c, lb, kb, b, -1.0);
            c.sxm = 0.5 * (e + b), c.sxh = 0.5 * (b - e);
            gen_section(w, &c, 0.0, sqrt(b - e), sum, &err);
        }
        c.umode = 0;
    }
    w->rad_row_err += err;
}

/* ---- a cone beside other gradients ----
 *
 * A scene with a cone-case gradient and other gradient layers (any kind,
 * the others in linear light too) takes each span by the layers it
 * depends on, found as the path of several gradients finds them (the
 * composite at three paints of each layer, the others transparent): the
 * cone's layer alone, the cone's path (cone_span, its composite's K0,
 * K1, K2 read the same way, the span clipped to a radial filter's chord);
 * no cone among them, the path of several gradients (gen_span), as
 * without the cone; several layers all of one cone-case gradient
 * (cone_same), the cone's path with their composite ("one cone on several
 * layers"); the cone and another gradient together, or a cone in linear
 * light, the path of several gradients with the cone's own cuts:
 *  - the row is cut where it crosses each cone layer's tangent lines (the
 *    half-plane's edge; nested, at its point nearest P*), and at its stop
 *    circles over its range of t on the painted part (cone_seg_range), as
 *    cone_span cuts it; on an unpainted stretch the layer is transparent,
 *    its paint constant (as is a padded stretch beyond its stops: flat,
 *    its t then not read, so that the half-plane's pole at its edge, the
 *    stretch beyond the last stop circle, is no singularity);
 *  - a cone layer's t is its own (cone_t_near), and on a piece in x its
 *    bounds on the rectangle |Re z - m| <= A, |Im z| <= B (gen_layer_tp)
 *    are T = (|b(m)| + |b1| A + sqrt(|L0| |L1|)) / |a| and, with t' = (b1
 *    + (lam0 L1 + lam1 L0) / (2 sqrt(L0 L1))) / a, P = (|b1| + (|lam0|
 *    sqrt(|L1| / |L0|) + |lam1| sqrt(|L0| / |L1|)) / 2) / |a|, each |L_k|
 *    above by |L_k(m)| + |lam_k| A and below by |lam_k| times its zero's
 *    distance from the rectangle (CONE_HALF: t = c / (2 b), |b| >= |b(m)|
 *    - |b1| A); the Bernstein ellipse keeps the zeros of L0 and L1 out;
 *  - a painted piece one end of which is a tangent line's crossing xr
 *    (CONE_WEDGE; both ends: halved at its middle) is taken in u, x = xr
 *    + eps u^2, as cone_root takes it: the integrand 2 u dec(e(x(u)))
 *    w(x(u)); that layer's t (and that of any layer of the same cone,
 *    whose forms are the same: uroot) = (b + u sqrt(P(u^2))) / a is
 *    analytic in u
 *    but at P's zeros (the other line's crossing), with |t| <= (|b(xr)| +
 *    |b1| Zu^2 + Zu sqrt(|P0| + |P1| Zu^2)) / |a| and |dt/du| <= (2 |b1|
 *    Zu + (|P0| + 2 |P1| Zu^2) / sqrt(|P|)) / |a| on the ellipse in u
 *    (|u| <= Zu = m + A, |P| >= |P1| |u - u0| |u + u0| by the distances
 *    from +-u0 to the rectangle about it); the other layers' bounds in x
 *    hold on the image of that ellipse, inside the rectangle Re(x - xr)
 *    eps in [lo^2 - B^2, Zu^2] (lo = max(0, m - A)), |Im x| <= 2 Zu B,
 *    and |dt/du| <= 2 Zu |t'(x)|; their branch points (and the radial cone
 *    filter's, and a linear layer's v = 0 in linear light) map into u as
 *    +-sqrt(eps (z - xr)) for the ellipse's rho; the weight's bound is
 *    cone_root_t's, and M takes the factor 2 Zu.  The composite's bounds
 *    (gen_bounds: |e|, |e'| from the layers' T and P by the product rule;
 *    on the power piece Re(e + 0.055) > 0 from |e(z) - e(m)| <= A max
 *    |e'|; in linear light Re v > 0 likewise, keeping v = 0 out) are then
 *    those of several gradients in the piece's variable, and the
 *    threshold's isolation runs in it too, in u by the Lipschitz test
 *    alone (gen_taylor gives no bound there; the halving is then on the
 *    signs and the budget as ever, a row tangent to the threshold's curve
 *    at worst refusing the pixel by name), in x with Taylor's theorem as
 *    well, a painted cone layer's t'' bounded from its forms
 *    (gen_cone_tpq: t'' = -(lam0 mu1 - lam1 mu0)^2 / (4 a d^(3/2)),
 *    CONE_HALF's from c / (2 b)); with the Lipschitz test alone a row
 *    grazing the curve's lowest point (2e-7 below the threshold: a nested
 *    cone at alpha 0.6 over a linear gradient) ran out of work and the
 *    document was refused; a narrow interval in u is its x range times
 *    the colour at its middle, with the same bound;
 *  - past GEN_MAX layers at a point (a cone and other gradients, or more
 *    than GEN_MAX layers of one cone) the composite is folded ("the
 *    fold"), its bounds from the same layers' T and P in the piece's
 *    variable (gen_layer_tp_s) and no Taylor bound in u, as above; past
 *    GEN_LAYERS the pixel is refused.
 * The outer breakpoints are the union of the layers' own, as for several
 * gradients (grad_breakpoints): the cone's tangent lines and front arcs
 * among them.
 */
/* Whether cone-case gradients g and h are one gradient: the same map,
 * circles, spread and stops (then t and the paint are the same functions
 * of the point; "one cone on several layers"). */
static int cone_same(const grad_radial *g, const grad_radial *h)
{
    if (!g || !h || !g->cone || g->cone != h->cone || g->spread != h->spread ||
        g->nstops != h->nstops)
        return 0;
    for (int k = 0; k < 6; k++)
        if (g->m[k] != h->m[k] || g->inv[k] != h->inv[k])
            return 0;
    if (g->fx != h->fx || g->fy != h->fy || g->Dx != h->Dx || g->Dy != h->Dy ||
        g->fr != h->fr || g->dr != h->dr || g->a != h->a)
        return 0;
    for (int k = 0; k < g->nstops; k++)
        if (g->stops[k].offset != h->stops[k].offset)
            return 0;
    for (int k = 0; k < 4 * g->nstops; k++)
        if (g->enc[k] != h->enc[k])
            return 0;
    return 1;
}

static void mix_span(worker *w, double xa, double xb, double y, int nch, double *sum)
{
    static const double P[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
    int N = w->ngl, *layers = w->gl_layer, cone, dep[GEN_LAYERS], same = 1;
    double *paints = w->gl_paint, fz[3];
    int nd = span_deps(w, dep, &cone, fz);
    if (cone < 0 || w->gl[cone].lin) { /* no cone, or in linear light: several gradients */
        gen_span(w, xa, xb, y, nch, sum);
        return;
    }
    /* several layers: all of one cone-case gradient ("one cone on several
     * layers"), else the cone and another gradient at one point, on the
     * path of several gradients with the cone's cuts */
    for (int l = 1; l < nd && same; l++)
        same = l < GEN_MAX && cone_same(w->gl[dep[0]].rg, w->gl[dep[l]].rg);
    if (nd > 1 && !same) {
        gen_span(w, xa, xb, y, nch, sum);
        return;
    }
    if (!chord_clip(w, &xa, &xb)) /* the span clipped to the support's chord */
        return;
    /* the composite's K: composites at every choice of paints, then the
     * differences f1 - f0, f2 - f1 along each layer's index (gen_span) */
    cone_comp cc;
    cc.n = nd, cc.nk = 1;
    for (int l = 0; l < nd; l++)
        cc.nk *= 3;
    for (int a = 0; a < cc.nk; a++) {
        double e[3];
        for (int l = 0, q = a; l < nd; l++, q /= 3)
            memcpy(paints + 4 * dep[l], P[q % 3], 4 * sizeof *paints);
        aa_scene_encoded_with_n(w->scene, w->wind, N, layers, paints, e);
        for (int ch = 0; ch < 3; ch++)
            cc.K[ch][a] = e[ch];
    }
    for (int l = 0; l < nd; l++)
        memset(paints + 4 * dep[l], 0, 4 * sizeof *paints);
    for (int l = 0, stride = 1; l < nd; l++, stride *= 3)
        for (int a = 0; a < cc.nk; a++) {
            if ((a / stride) % 3 != 0)
                continue;
            for (int ch = 0; ch < 3; ch++) {
                double f0 = cc.K[ch][a], f1 = cc.K[ch][a + stride], f2 = cc.K[ch][a + 2 * stride];
                cc.K[ch][a + stride] = f1 - f0;
                cc.K[ch][a + 2 * stride] = f2 - f1;
            }
        }
    cone_span(w, w->gl[cone].rg, &cc, xa, xb, y, nch, sum);
}

/* The product of polynomials a (degree na) and b (degree nb) added, times
 * k, into out. */
static void poly_mul_add(const double *a, int na, const double *b, int nb, double k, double *out)
{
    for (int i = 0; i <= na; i++)
        for (int j = 0; j <= nb; j++)
            out[i + j] += k * a[i] * b[j];
}

/* The value at u of the polynomial c of degree n, in long double. */
static long double poly_at(const double *c, int n, long double u)
{
    long double f = 0.0L;
    for (int i = n; i >= 0; i--)
        f = f * u + c[i];
    return f;
}

/* The points in [lo, hi] where the polynomial c of degree n (at most 6)
 * changes sign: isolated between the roots of its derivative (found the
 * same way) and bisected; at most n into out, ascending.  A root of even
 * multiplicity (a tangency) is not a sign change and is not found. */
static int poly_sign_roots(const double *c, int n, double lo, double hi, double *out)
{
    while (n > 0 && c[n] == 0.0)
        n--;
    if (n == 0)
        return 0;
    double dc[6] = {0}, cut[8];
    int nc = 0, m = 0;
    for (int i = 1; i <= n; i++)
        dc[i - 1] = i * c[i];
    cut[nc++] = lo;
    nc += poly_sign_roots(dc, n - 1, lo, hi, cut + 1);
    cut[nc++] = hi;
    for (int k = 0; k + 1 < nc; k++) {
        double a = cut[k], b = cut[k + 1];
        long double fa = poly_at(c, n, a), fb = poly_at(c, n, b);
        if (fa == 0.0L) {
            if (!m || out[m - 1] != a)
                out[m++] = a;
            continue;
        }
        if ((fa < 0.0L) == (fb < 0.0L) || fb == 0.0L)
            continue;
        for (int it = 0; it < 200; it++) {
            double mid = 0.5 * (a + b);
            if (mid <= a || mid >= b)
                break;
            long double fm = poly_at(c, n, mid);
            if ((fm < 0.0L) == (fa < 0.0L))
                a = mid, fa = fm;
            else
                b = mid;
        }
        out[m++] = 0.5 * (a + b);
    }
    if (n > 0 && poly_at(c, n, hi) == 0.0L && (!m || out[m - 1] != hi))
        out[m++] = hi;
    return m;
}

/* The values of t in (ta, tb) where a channel of the composite at the
 * window's centre (winding numbers wind) passes the decoding's threshold
 * 0.04045: on each stop's segment e is quadratic in the segment's
 * parameter (rad_span); each root in every period of the range.  At most
 * cap into out, the total returned. */
static size_t rad_threshold_taus(const worker *w, const gen_layer *g, const int *wind,
                                 double ta, double tb, double *out, size_t cap)
{
    double p0[4] = {0, 0, 0, 0}, p1[4] = {0, 0, 0, 1}, p2[4] = {1, 1, 1, 1}, e0[3], e1[3], e2[3];
    aa_scene_encoded_with(w->scene, wind, g->layer, p0, e0);
    aa_scene_encoded_with(w->scene, wind, g->layer, p1, e1);
    aa_scene_encoded_with(w->scene, wind, g->layer, p2, e2);
    size_t n = 0;
    /* the periods: pad, the stops' own; repeat, [n, n + 1); reflect, pairs
     * [2n, 2n + 2) from even ends */
    double lo = g->spread == AA_SPREAD_PAD       ? 0.0
                : g->spread == AA_SPREAD_REFLECT ? 2.0 * floor(0.5 * ta)
                                                 : floor(ta);
    double hi = g->spread == AA_SPREAD_PAD ? 0.0 : ceil(tb);
    for (int k = 0; k + 1 < g->nstops; k++) {
        double o = g->stops[k].offset, dO = g->stops[k + 1].offset - o;
        if (!(dO > 0.0))
            continue;
        double ae[4], be[4];
        const double *a = g->enc + 4 * k, *b = a + 4;
        if (g->lin) { /* linear light: the encoded ends, as a secant (a breakpoint's place) */
            for (int c = 0; c < 3; c++)
                ae[c] = aa_srgb_encode(a[c]), be[c] = aa_srgb_encode(b[c]);
            ae[3] = a[3], be[3] = b[3];
            a = ae, b = be;
        }
        for (int c = 0; c < 3; c++) {
            /* e(l) = K0 + K1 op + K2 op C, op and C affine in l in [0, 1] */
            double K0 = e0[c], K1 = e1[c] - e0[c], K2 = e2[c] - e1[c];
            double q0 = K0 + K1 * a[3] + K2 * a[3] * a[c] - 0.04045;
            double q1 = K1 * (b[3] - a[3]) + K2 * (a[3] * (b[c] - a[c]) + (b[3] - a[3]) * a[c]);
            double q2 = K2 * (b[3] - a[3]) * (b[c] - a[c]), l[2];
            int nl = gsl_poly_solve_quadratic(q2, q1, q0, &l[0], &l[1]);
            if (q2 == 0.0 && q1 != 0.0)
                nl = 1, l[0] = -q0 / q1;
            for (int r = 0; r < nl; r++) {
                if (!(l[r] > 0.0 && l[r] < 1.0))
                    continue;
                double sv = o + l[r] * dO;
                int refl = g->spread == AA_SPREAD_REFLECT;
                for (double per = lo; per <= hi; per += refl ? 2.0 : 1.0) {
                    double v[2] = {per + sv, per + 2.0 - sv};
                    for (int q = 0; q < 1 + refl; q++)
                        if (v[q] > ta && v[q] < tb && n++ < cap)
                            out[n - 1] = v[q];
                }
            }
        }
    }
    return n;
}

static long double crossing_at(const local_piece *q, long double s);
static void note_turn(worker *w, double s);

/* The gradient layer of scene layer l. */
static const gen_layer *gl_of(const worker *w, int l)
{
    for (int k = 0; k < w->ngl; k++)
        if (w->gl[k].layer == l)
            return &w->gl[k];
    return &w->gl[0]; /* cannot happen: every gradient layer is in w->gl */
}

/* 1 if radial gradients g and h have the same t at every point (their
 * maps, focal points, D, fr and dr equal; neither of the cone case). */
static int rad_same_t(const grad_radial *g, const grad_radial *h)
{
    if (g->cone || h->cone)
        return 0;
    for (int k = 0; k < 6; k++)
        if (g->inv[k] != h->inv[k])
            return 0;
    return g->fx == h->fx && g->fy == h->fy && g->Dx == h->Dx && g->Dy == h->Dy &&
           g->fr == h->fr && g->dr == h->dr;
}

/* A polynomial in s in [0, 1] in Bernstein form, b[0 .. n], with err a
 * bound on how far every coefficient is from the exact polynomial's (the
 * one the same operations give in exact arithmetic): the composite of a
 * stack that shares one t (shared_threshold_taus).  Each operation is a
 * combination with nonnegative weights summing to 1 (elevation, product,
 * de Casteljau's halving) or a sum, so a coefficient's rounding is at most
 * (terms + 4) ulps of the largest magnitude it combines; ulps are taken
 * of double (DBL_EPSILON) though the arithmetic is in long double, which
 * holds where long double is only double (valgrind).  The degree of a
 * stack of n layers' composite is at most n + 1 (a layer's a C is
 * quadratic in t, and each over adds one to the degree behind it). */
#define BZ_MAX (GEN_LAYERS + 2)
typedef struct bz {
    int n;
    long double b[BZ_MAX + 1];
    double err;
} bz;

static double bz_mag(const bz *p)
{
    long double m = 0.0L;
    for (int i = 0; i <= p->n; i++)
        m = fmaxl(m, fabsl(p->b[i]));
    return (double)m;
}

static double bz_ulps(int terms, double mag) { return (terms + 4) * DBL_EPSILON * mag; }

/* The affine function of values f0, f1 at the ends, each computed from
 * terms of magnitude at most mag. */
static bz bz_affine(long double f0, long double f1, double mag)
{
    return (bz){1, {f0, f1}, bz_ulps(2, mag)};
}

static bz bz_const(long double k) { return (bz){0, {k}, 0.0}; }

/* p raised to degree m (>= its own). */
static bz bz_raise(bz p, int m)
{
    for (int n = p.n; n < m; n++) {
        bz q = {n + 1, {0}, p.err + bz_ulps(3, bz_mag(&p))};
        q.b[0] = p.b[0], q.b[n + 1] = p.b[n];
        for (int i = 1; i <= n; i++) {
            long double r = (long double)i / (n + 1);
            q.b[i] = r * p.b[i - 1] + (1.0L - r) * p.b[i];
        }
        p = q;
    }
    return p;
}

/* u p + v q (u, v exact constants); 0 if the degree would pass BZ_MAX. */
static bz bz_lin(long double u, bz p, long double v, bz q)
{
    int m = p.n > q.n ? p.n : q.n;
    p = bz_raise(p, m), q = bz_raise(q, m);
    bz r = {m, {0}, (double)(fabsl(u) * p.err + fabsl(v) * q.err)};
    for (int i = 0; i <= m; i++)
        r.b[i] = u * p.b[i] + v * q.b[i];
    r.err += bz_ulps(3, (double)(fabsl(u) * bz_mag(&p) + fabsl(v) * bz_mag(&q)));
    return r;
}

static int bz_mul(const bz *p, const bz *q, bz *r)
{
    int m = p->n, n = q->n;
    if (m + n > BZ_MAX)
        return 0;
    long double cm[BZ_MAX + 1], cn[BZ_MAX + 1], cmn[BZ_MAX + 1];
    cm[0] = cn[0] = cmn[0] = 1.0L; /* binomials, exact below 2^53 */
    for (int i = 1; i <= m + n; i++) {
        cm[i] = i <= m ? cm[i - 1] * (m - i + 1) / i : 0.0L;
        cn[i] = i <= n ? cn[i - 1] * (n - i + 1) / i : 0.0L;
        cmn[i] = cmn[i - 1] * (m + n - i + 1) / i;
    }
    double ma = bz_mag(p), mb = bz_mag(q);
    r->n = m + n;
    r->err = ma * q->err + mb * p->err + p->err * q->err + bz_ulps(m + n + 4, ma * mb);
    for (int k = 0; k <= m + n; k++) {
        long double s = 0.0L;
        for (int i = k > n ? k - n : 0; i <= m && i <= k; i++)
            s += cm[i] * cn[k - i] * p->b[i] * q->b[k - i];
        r->b[k] = s / cmn[k];
    }
    return 1;
}

/* ac + (1 - a) p: source over. */
static int bz_over(const bz *ac, const bz *a, const bz *p, bz *r)
{
    bz t;
    if (!bz_mul(a, p, &t))
        return 0;
    *r = bz_lin(1.0L, *ac, 1.0L, bz_lin(1.0L, *p, -1.0L, t));
    return r->n <= BZ_MAX;
}

/* p's value at s by de Casteljau. */
static long double bz_at(const bz *p, long double s)
{
    long double b[BZ_MAX + 1];
    memcpy(b, p->b, (size_t)(p->n + 1) * sizeof *b);
    for (int r = 1; r <= p->n; r++)
        for (int i = 0; i + r <= p->n; i++)
            b[i] = (1.0L - s) * b[i] + s * b[i + 1];
    return b[0];
}

/* p's halves on [0, 1/2] (lo) and [1/2, 1] (hi). */
static void bz_halve(const bz *p, bz *lo, bz *hi)
{
    long double b[BZ_MAX + 1];
    int n = p->n;
    memcpy(b, p->b, (size_t)(n + 1) * sizeof *b);
    double e = p->err + bz_ulps(n + 2, bz_mag(p));
    lo->n = hi->n = n, lo->err = hi->err = e;
    lo->b[0] = b[0], hi->b[n] = b[n];
    for (int r = 1; r <= n; r++) {
        for (int i = 0; i + r <= n; i++)
            b[i] = 0.5L * (b[i] + b[i + 1]);
        lo->b[r] = b[0], hi->b[n - r] = b[n - r];
    }
}

/* The places in (0, 1) where p's exact polynomial may vanish, certified
 * by subdivision (Descartes' rule of signs in the Bernstein basis): an
 * interval whose coefficients are all of one sign beyond err holds no
 * root; one whose coefficients' signs are all certain and change once
 * holds exactly one (the count of roots is at most the changes and of
 * their parity), bisected on p's values to rounding; any other is halved
 * down to a width of BZ_NARROW and then holds every root there is in it,
 * of any multiplicity (a double root, where the composite touches the
 * threshold, or two roots closer than that): its midpoint stands for
 * them, neighbouring such intervals merged into one.  Past BZ_WORK
 * intervals the rest are taken whole, each by its midpoint and ends.
 * The places, in increasing order, into s[] (at most cap); their count. */
#define BZ_NARROW 0x1p-40
#define BZ_WORK 4096
static size_t bz_roots(const bz *p, double *s, size_t cap)
{
    struct {
        bz q;
        double a, b;
    } *stk = malloc(64 * sizeof *stk);
    size_t n = 0;
    int top = 0, work = 0;
    double run_a = -1.0, run_b = -1.0; /* the narrow intervals being merged */
    if (!stk) { /* no room to look: every place the piece has */
        if (cap)
            s[n++] = 0.5;
        return n;
    }
#define BZ_EMIT(x)                                                                                 \
    do {                                                                                           \
        if (n < cap && (x) > 0.0 && (x) < 1.0 && (!n || (x) > s[n - 1]))                           \
            s[n++] = (x);                                                                          \
    } while (0)
#define BZ_FLUSH()                                                                                 \
    do {                                                                                           \
        if (run_a >= 0.0)                                                                          \
            BZ_EMIT(0.5 * (run_a + run_b));                                                        \
        run_a = run_b = -1.0;                                                                      \
    } while (0)
    stk[top].q = *p, stk[top].a = 0.0, stk[top].b = 1.0, top++;
    while (top > 0) {
        top--;
        bz q = stk[top].q;
        double a = stk[top].a, b = stk[top].b;
        int pos = 0, neg = 0, unsure = 0, changes = 0, last = 0;
        for (int i = 0; i <= q.n; i++) {
            int sg = q.b[i] > q.err ? 1 : q.b[i] < -q.err ? -1 : 0;
            pos += sg > 0, neg += sg < 0, unsure += sg == 0;
            if (sg && last && sg != last)
                changes++;
            if (sg)
                last = sg;
        }
        if (!unsure && (!pos || !neg))
            continue; /* no root */
        if (!unsure && changes == 1) { /* exactly one: bisected */
            BZ_FLUSH();
            long double lo = 0.0L, hi = 1.0L;
            int slo = q.b[0] > 0.0L;
            for (int it = 0; it < 80; it++) {
                long double mid = 0.5L * (lo + hi);
                if (!(mid > lo && mid < hi))
                    break;
                if ((bz_at(&q, mid) > 0.0L) == slo)
                    lo = mid;
                else
                    hi = mid;
            }
            BZ_EMIT(a + (b - a) * (double)(0.5L * (lo + hi)));
            continue;
        }
        if (b - a <= BZ_NARROW || ++work > BZ_WORK || top + 2 > 64) {
            if (run_a >= 0.0 && a <= run_b)
                run_b = b;
            else {
                BZ_FLUSH();
                run_a = a, run_b = b;
            }
            if (b - a > BZ_NARROW) { /* taken whole: its ends too */
                BZ_FLUSH();
                BZ_EMIT(a);
                BZ_EMIT(0.5 * (a + b));
                BZ_EMIT(b);
            }
            continue;
        }
        /* halved: the left half on top, so the intervals come in order */
        double m = 0.5 * (a + b);
        bz_halve(&q, &stk[top + 1].q, &stk[top].q);
        stk[top].a = m, stk[top].b = b;
        stk[top + 1].a = a, stk[top + 1].b = m;
        top += 2;
    }
    BZ_FLUSH();
#undef BZ_EMIT
#undef BZ_FLUSH
    free(stk);
    return n;
}

/* The values of t in (ta, tb) where the composite at winding numbers wind
 * passes or touches the decoding's threshold with every gradient layer
 * whose t is g's (rad_same_t; sRGB stops) painting at that t, the others
 * at their first stops, when there are two or more of them (a stack of
 * one gradient): the threshold's circles of the path of several gradients
 * (rad_threshold_taus takes the others at their first stops, and a
 * stack of n identical translucent layers came out up to 6.9e-13 off
 * against a bound of 1.6e-13 without these).  Between the members'
 * breaks of t (grad_taus) each paint is affine in t, and the composite,
 * the scene's fold (aa_scene_fold) with those paints, a polynomial in t
 * built exactly in the Bernstein basis of the piece with a bound on its
 * rounding (bz); its roots against 0.04045 are isolated by subdivision
 * (bz_roots), double roots and roots closer than 2^-40 of the piece
 * included.  Once 64 points a piece with their sign changes bisected: two
 * roots within one step went unseen (tests/test_gradient.c,
 * test_stack_close_roots).  For the first member only, the others' being
 * the same.  At most cap into out, the total returned. */
static size_t shared_threshold_taus(worker *w, const grad_radial *g, const int *wind, double ta,
                                    double tb, double *out, size_t cap)
{
    const gen_layer *ms[GEN_LAYERS];
    int lay[GEN_LAYERS], ns = 0;
    for (int k = 0; k < w->ngl && ns < GEN_LAYERS; k++) {
        const gen_layer *q = &w->gl[k];
        if (q->rg && !q->lin && rad_same_t(q->rg, g))
            ms[ns] = q, lay[ns++] = q->layer;
    }
    /* the members' circles are the same: found once, for the first */
    if (ns < 2 || ms[0]->rg != g || !(tb > ta) || !isfinite(ta) || !isfinite(tb))
        return 0;
    double *br = w->gbuf2, base[3];
    size_t nb = 0, bcap = w->cap_gbuf - 2, n = 0;
    br[nb++] = ta;
    for (int i = 0; i < ns; i++) {
        size_t m = grad_taus(&ms[i]->rg->plane, ta, tb, br + nb, bcap - nb);
        if (m > bcap - nb)
            return 0; /* too many breaks: the refusal is grad_breakpoints' */
        nb += m;
    }
    br[nb++] = tb;
    qsort(br, nb, sizeof *br, cmp_dbl);
    int nst = aa_scene_fold(w->scene, wind, ns, lay, w->fold, w->cap_fold, base), depth = 0;
    if (nst < 0)
        return 0; /* cannot happen: cap_fold is aa_scene_fold_cap's */
    for (int k = 0, d = 0; k < nst; k++) {
        d += w->fold[k].op == AA_FOLD_OPEN ? 1 : w->fold[k].op == AA_FOLD_CLOSE ? -1 : 0;
        depth = d > depth ? d : depth;
    }
    bz *p = malloc((size_t)(2 * depth + 2) * sizeof *p), *al = p + depth + 1;
    double *roots = malloc(2 * BZ_MAX * sizeof *roots);
    if (!p || !roots) {
        free(p), free(roots);
        return 0;
    }
    double v0[GEN_LAYERS][4], v1[GEN_LAYERS][4];
    for (size_t k = 0; k + 1 < nb; k++) {
        double u = br[k], v = br[k + 1];
        if (!(v > u))
            continue;
        for (int i = 0; i < ns; i++)
            paint_lin(ms[i]->spread, ms[i]->stops, ms[i]->nstops, ms[i]->enc, 0.5 * (u + v), v0[i],
                      v1[i]);
        for (int c = 0; c < 3; c++) {
            /* the fold of channel c in the piece's Bernstein basis */
            int d = 0, ok = 1;
            p[0] = bz_const(base[c]), al[0] = bz_const(1.0L);
            for (int st = 0; st < nst && ok; st++) {
                const aa_fold_step *s = &w->fold[st];
                int i = -1;
                for (int q = 0; q < ns && s->op == AA_FOLD_LAYER; q++)
                    if (lay[q] == s->layer)
                        i = q;
                if (s->op == AA_FOLD_OPEN) {
                    d++;
                    p[d] = al[d] = bz_const(0.0L);
                } else if (s->op == AA_FOLD_CLOSE) {
                    bz op = bz_lin(s->a, p[d], 0.0L, bz_const(0.0L));
                    bz oa = bz_lin(s->a, al[d], 0.0L, bz_const(0.0L)), r;
                    ok = bz_over(&op, &oa, &p[d - 1], &p[d - 1]) &&
                         bz_over(&oa, &oa, &al[d - 1], &r);
                    if (ok) /* (else r is unset, and the fold stops) */
                        al[d - 1] = r;
                    d--;
                } else {
                    bz a, ac, r;
                    if (i >= 0) { /* the member's a (alpha op) and a C, affine in t */
                        long double o0 = v0[i][3] + (long double)v1[i][3] * u;
                        long double o1 = v0[i][3] + (long double)v1[i][3] * v;
                        long double c0 = v0[i][c] + (long double)v1[i][c] * u;
                        long double c1 = v0[i][c] + (long double)v1[i][c] * v;
                        double tt = fmax(fabs(u), fabs(v));
                        bz op = bz_affine(s->a * o0, s->a * o1,
                                          s->a * (fabs(v0[i][3]) + fabs(v1[i][3]) * tt));
                        bz C = bz_affine(c0, c1, fabs(v0[i][c]) + fabs(v1[i][c]) * tt);
                        a = op;
                        ok = bz_mul(&op, &C, &ac);
                    } else
                        a = bz_const(s->a), ac = bz_const((long double)s->a * s->c[c]);
                    ok = ok && bz_over(&ac, &a, &p[d], &p[d]) && bz_over(&a, &a, &al[d], &r);
                    if (ok)
                        al[d] = r;
                }
            }
            size_t nr;
            if (ok) {
                bz q = bz_lin(1.0L, p[0], -(long double)0.04045, bz_const(1.0L));
                nr = bz_roots(&q, roots, 2 * BZ_MAX);
            } else /* cannot happen (the degree's bound, bz): the piece's middle */
                nr = 1, roots[0] = 0.5;
            for (size_t r = 0; r < nr; r++) {
                double t = u + (v - u) * roots[r];
                if (t > ta && t < tb && n++ < cap)
                    out[n - 1] = t;
            }
        }
    }
    free(p), free(roots);
    return n;
}

/* The values of t in (ta, tb) where the composite at the window's centre
 * passes the decoding's threshold (rad_threshold_taus; its winding
 * numbers: the strip's left of the window, and the local pieces crossing
 * the centre row left of it), and, if the centre is outside the
 * gradient's layer, the composite there with that layer's winding number
 * 1.  At most cap into out, the total returned. */
static size_t threshold_taus(worker *w, const gen_layer *g, double ta, double tb, double *out,
                             size_t cap)
{
    aa_strip_winding_left(w->strip, w->vc, w->wind);
    for (size_t k = 0; k < w->nlp; k++) {
        const local_piece *lq = &w->lp[k];
        if (!(0.0 >= lq->y0 && 0.0 < lq->y1))
            continue;
        if (lq->side ? lq->side < 0 : crossing_at(lq, 0.0L) < 0.0L)
            w->wind[lq->layer] += lq->dir;
    }
    size_t m = rad_threshold_taus(w, g, w->wind, ta, tb, out, cap);
    if (g->rg && m < cap)
        m += shared_threshold_taus(w, g->rg, w->wind, ta, tb, out + m, cap - m);
    if (w->wind[g->layer] == 0 && m < cap) {
        /* the centre outside the gradient's layer: also as if inside it
         * (and inside every layer of the same t, for the stack's) */
        w->wind[g->layer] = 1;
        m += rad_threshold_taus(w, g, w->wind, ta, tb, out + m, cap - m);
        if (g->rg && m < cap) {
            for (int k = 0; k < w->ngl; k++)
                if (w->gl[k].rg && rad_same_t(w->gl[k].rg, g->rg) && w->wind[w->gl[k].layer] == 0)
                    w->wind[w->gl[k].layer] = 1;
            m += shared_threshold_taus(w, g->rg, w->wind, ta, tb, out + m, cap - m);
        }
    }
    return m;
}

/* Outer breakpoints of a radial gradient (truth.c's opening comment): for
 * each tau of the window's range of t, where the circle of tau crosses the
 * window's sides, its top and bottom rows, and where it meets each local
 * piece; and the row of P*. */
/* The vertical lines (absolute x) where the inner integral's weight is
 * not smooth, for the gradients' breakpoints: the window's sides for the
 * box; for the other separable filters their kinks, the window's sides
 * and, for the Gaussian, x = uc + k s (as for the pieces, breakpoints()).
 * At most KINK_LINES. */
#define KINK_LINES 96
static int kink_lines(const worker *w, double *X)
{
    int n = 0;
    if (w->radial)
        return 0; /* no vertical line: the support's circle (rad_filter_line, _circle) */
    X[n++] = w->uc - w->R;
    X[n++] = w->uc + w->R;
    if (w->box)
        return n;
    double kink[8];
    int nk = w->f->type->kinks(w->f->spec.v, kink);
    for (int j = 0; j < nk; j++)
        if (kink[j] > -w->R && kink[j] < w->R)
            X[n++] = w->uc + kink[j];
    if (w->f->type == &aa_filter_gauss) {
        double sd = w->f->spec.v[0];
        for (double t = -floor(w->R / sd) * sd; t <= w->R && n < KINK_LINES; t += sd)
            X[n++] = w->uc + t;
    }
    return n;
}

/* Under a radial filter ("the radial filters: the weight along a row"):
 * where the line tx x + ty y + k = 0 crosses the support's circle about
 * (uc, vc), and, for the cone, the height of its point nearest the centre
 * if inside it, a turning point. */
static int rad_filter_line(worker *w, double tx, double ty, double k)
{
    double nn = hypot(tx, ty), R = w->R;
    if (!(nn > 0.0))
        return AA_OK;
    /* d: the centre's signed distance; the foot at centre - d n / |n|;
     * the line's direction (-ty, tx) / |n| */
    double d = (tx * w->uc + ty * w->vc + k) / nn, fy = w->vc - d * ty / nn;
    if (!(fabs(d) < R))
        return AA_OK;
    double hc = sqrt((R - d) * (R + d)), dy = tx / nn;
    int st = add_abs(w, fy + hc * dy, -INFINITY, INFINITY);
    if (!st)
        st = add_abs(w, fy - hc * dy, -INFINITY, INFINITY);
    if (!st && w->f->type == &aa_filter_cone) {
        st = add_abs(w, fy, -INFINITY, INFINITY);
        note_turn(w, fy - w->vc);
    }
    return st;
}

/* The same for the circle of tau of radial gradient g (radius rt >= 0,
 * G = m^-1(x, y) - F - tau D, k0 and k1 its constant terms): in pixels an
 * ellipse.  Its crossings of the support's circle, that circle's two
 * halves (uc, vc) +- R ((1 - u^2), 2 u) / (1 + u^2), u in [-1, 1],
 * substituted into |G|^2 = rt^2: a quartic's sign changes; for the cone,
 * where its distance to the centre is stationary: with the circle as
 * p(th) = m(F + tau D) + rt (cos th m1 + sin th m2) (m1, m2 the map's
 * columns) and a = m(F + tau D) - (uc, vc), the derivative of |p -
 * centre|^2 / (2 rt) is
 *     -sin th (a.m1) + cos th (a.m2) + rt (cos th sin th (|m2|^2 -
 *     |m1|^2) + (cos^2 th - sin^2 th) m1.m2),
 * in the half angle u (th = 2 atan u, and th + pi, which negates the
 * first two terms) times (1 + u^2)^2 a quartic, whose sign changes give
 * the stationary points: each inside the disc is a breakpoint and a
 * turning point (the nearest ones among them; the others only cost
 * time). */
static int rad_filter_circle(worker *w, const grad_radial *g, double rt, double k0, double k1,
                             double tau)
{
    const double *iv = g->inv, *m = g->m;
    double R = w->R, uc = w->uc, vc = w->vc;
    int st = AA_OK;
    for (int half = 0; half < 2 && !st; half++) {
        double sg = half ? -1.0 : 1.0, W[3] = {1.0, 0.0, 1.0};
        double X[3] = {uc + sg * R, 0.0, uc - sg * R}, Y[3] = {vc, sg * 2.0 * R, vc};
        double GX[3], GY[3], Q[7] = {0}, us[6];
        for (int i = 0; i < 3; i++) {
            GX[i] = iv[0] * X[i] + iv[2] * Y[i] + k0 * W[i];
            GY[i] = iv[1] * X[i] + iv[3] * Y[i] + k1 * W[i];
        }
        poly_mul_add(GX, 2, GX, 2, 1.0, Q);
        poly_mul_add(GY, 2, GY, 2, 1.0, Q);
        poly_mul_add(W, 2, W, 2, -rt * rt, Q);
        int nu = poly_sign_roots(Q, 4, -1.0, 1.0, us);
        for (int r = 0; r < nu && !st; r++) {
            double u = us[r];
            st = add_abs(w, (vc * (1.0 + u * u) + sg * 2.0 * R * u) / (1.0 + u * u), -INFINITY,
                         INFINITY);
        }
    }
    if (st || w->f->type != &aa_filter_cone)
        return st;
    double qx = g->fx + tau * g->Dx, qy = g->fy + tau * g->Dy;
    double ax = m[0] * qx + m[2] * qy + m[4] - uc, ay = m[1] * qx + m[3] * qy + m[5] - vc;
    double am1 = ax * m[0] + ay * m[1], am2 = ax * m[2] + ay * m[3];
    double dm = m[2] * m[2] + m[3] * m[3] - m[0] * m[0] - m[1] * m[1];
    double cm = m[0] * m[2] + m[1] * m[3];
    for (int half = 0; half < 2 && !st; half++) {
        double sg = half ? -1.0 : 1.0, W[3] = {1.0, 0.0, 1.0};
        double L1[3] = {sg * am2, -sg * 2.0 * am1, -sg * am2}, Q[7] = {0}, us[6];
        poly_mul_add(W, 2, L1, 2, 1.0, Q);
        Q[0] += rt * cm, Q[1] += rt * 2.0 * dm, Q[2] -= rt * 6.0 * cm;
        Q[3] -= rt * 2.0 * dm, Q[4] += rt * cm;
        int nu = poly_sign_roots(Q, 4, -1.0, 1.0, us);
        for (int r = 0; r < nu && !st; r++) {
            double th = 2.0 * atan(us[r]), co = sg * cos(th), si = sg * sin(th);
            double px = ax + rt * (co * m[0] + si * m[2]), py = ay + rt * (co * m[1] + si * m[3]);
            if (hypot(px, py) < R) {
                st = add_abs(w, vc + py, -INFINITY, INFINITY);
                note_turn(w, py);
            }
        }
    }
    return st;
}

/* Offset pieces (strokes of curves) against the curves t = tau of a
 * gradient: the curve as a piece of the scene's own kinds over the
 * window's rows (a line's part; a circle, in pixels an ellipse, as its
 * two halves between its top and bottom, conic pieces), and their
 * meetings from aa_piece_meet, which for an offset piece bisects on exact
 * extents, told apart by the two pieces' slope ranges, and polishes each
 * change of sign of the difference of their x by Newton's method (core.h):
 * the same search as for an offset piece against another piece. */
static int offset_meets(worker *w, const aa_piece *p, const aa_piece *q)
{
    double ys[16];
    int m = aa_piece_meet(p, q, w->vc - w->R, w->vc + w->R, ys, 16), st = AA_OK;
    for (int r = 0; r < m && !st; r++)
        st = add_abs(w, ys[r], -INFINITY, INFINITY);
    return st;
}

/* The line tx x + ty y + k = 0 (ty != 0 and, for a crossing, tx != 0). */
static int offset_meet_line(worker *w, const aa_piece *p, double tx, double ty, double k)
{
    if (tx == 0.0) /* horizontal: its height is a breakpoint in itself */
        return add_abs(w, -k / ty, -INFINITY, INFINITY);
    aa_piece q;
    memset(&q, 0, sizeof q);
    q.kind = AA_PIECE_LINE;
    q.dir = 1;
    q.y0 = w->vc - w->R, q.y1 = w->vc + w->R;
    q.x0 = -(k + ty * q.y0) / tx, q.x1 = -(k + ty * q.y1) / tx;
    q.cx = 0.5 * (q.x0 + q.x1), q.cy = 0.5 * (q.y0 + q.y1);
    q.bx = q.x1 - q.x0, q.by = q.y1 - q.y0;
    q.xmin = fmin(q.x0, q.x1), q.xmax = fmax(q.x0, q.x1);
    q.layer = -1, q.edge = -1;
    return offset_meets(w, p, &q);
}

/* The circle of tau of radial gradient g, radius rt in its own
 * coordinates: in pixels m(F + tau D) + rt (cos th m1 + sin th m2) (m1,
 * m2 the map's columns), an ellipse of centre (ex, ey) and half height er
 * = rt |(m1y, m2y)|; with th = s + phi - pi, phi = atan2(m2y, m1y), y =
 * ey - er cos s and x = ex + ea cos s +- eb sin s, s in [0, pi]: the two
 * halves (the conic piece's angle form, aabench.h). */
static int offset_meet_circle(worker *w, const aa_piece *p, const grad_radial *g, double tau,
                              double rt)
{
    const double *m = g->m;
    double er = rt * hypot(m[1], m[3]);
    if (!(er > 0.0))
        return AA_OK; /* a point: no crossing */
    double phi = atan2(m[3], m[1]), cp = cos(phi), sp = sin(phi);
    double qx = g->fx + tau * g->Dx, qy = g->fy + tau * g->Dy;
    double ex = m[0] * qx + m[2] * qy + m[4], ey = m[1] * qx + m[3] * qy + m[5];
    double ea = -rt * (m[0] * cp + m[2] * sp), eb = rt * (m[0] * sp - m[2] * cp);
    if (ey + er < w->vc - w->R || ey - er > w->vc + w->R)
        return AA_OK; /* not in the window's rows */
    int st = AA_OK;
    for (int half = 0; half < 2 && !st; half++) {
        aa_piece q;
        memset(&q, 0, sizeof q);
        q.kind = AA_PIECE_CONIC;
        q.dir = 1;
        q.ex = ex, q.ey = ey, q.er = er, q.ea = ea, q.eb = half ? -eb : eb;
        q.s0 = 0.0, q.s1 = M_PI;
        q.x0 = ex + ea, q.y0 = ey - er, q.x1 = ex - ea, q.y1 = ey + er;
        /* x = ex + rho cos(s - al) over [0, pi]: its extremes inside if
         * al (or al + pi) is, else at the ends; widened by rounding */
        double rho = hypot(q.ea, q.eb), al = atan2(q.eb, q.ea), tol = 1e-12 * (fabs(ex) + rho);
        q.xmax = (al >= 0.0 ? ex + rho : fmax(q.x0, q.x1)) + tol;
        q.xmin = (al <= 0.0 ? ex - rho : fmin(q.x0, q.x1)) - tol;
        q.layer = -1, q.edge = -1;
        st = offset_meets(w, p, &q);
    }
    return st;
}

/* The breakpoints of the line tx x + ty y + t0 = tau (a linear gradient's
 * stop line, a cone's tangent line): under a radial filter its crossings
 * of the support's circle (rad_filter_line), its crossings of the kink
 * lines XL and where it meets each local piece. */
static int line_breaks(worker *w, double tx, double ty, double t0, double tau,
                       const aa_piece *const *local, size_t n, const double *XL, int nxl)
{
    int st = AA_OK;
    if (w->radial)
        st = rad_filter_line(w, tx, ty, t0 - tau);
    if (ty != 0.0)
        for (int k = 0; k < nxl && !st; k++)
            st = add_abs(w, (tau - t0 - tx * XL[k]) / ty, -INFINITY, INFINITY);
    for (size_t k = 0; k < n && !st; k++) {
        const aa_piece *p = local[k];
        double ys[3];
        if (p->kind == AA_PIECE_FLAT)
            continue;
        if (ty == 0.0) {
            int mm = aa_piece_meet_x(p, (tau - t0) / tx, ys);
            for (int r = 0; r < mm && !st; r++)
                st = add_abs(w, ys[r], -INFINITY, INFINITY);
            continue;
        }
        if (p->kind == AA_PIECE_OFFSET) {
            st = offset_meet_line(w, p, tx, ty, t0 - tau);
            continue;
        }
        if (p->kind == AA_PIECE_CONIC) {
            /* A cos s + B sin s + C = 0 on the arc's angle s */
            double A = tx * p->ea - ty * p->er, B = tx * p->eb;
            double C = tx * p->ex + ty * p->ey + t0 - tau;
            double rho = hypot(A, B);
            if (!(rho > 0.0) || fabs(C) > rho)
                continue;
            double phi = atan2(B, A), a = acos(-C / rho);
            for (int r = 0; r < 2 && !st; r++) {
                double sang = phi + (r ? -a : a);
                for (int wrap = -2; wrap <= 2 && !st; wrap++) {
                    double sv = sang + 2.0 * M_PI * wrap;
                    if (sv >= p->s0 && sv <= p->s1)
                        st = add_abs(w, p->ey - p->er * cos(sv), -INFINITY, INFINITY);
                }
            }
            continue;
        }
        double c[4] = {tx * p->x0 + ty * p->y0 + t0 - tau,
                       tx * p->bx + ty * p->by, tx * p->ax + ty * p->ay,
                       tx * p->dx + ty * p->dy};
        double ts[3];
        int mm = cubic_roots01(c, ts);
        for (int r = 0; r < mm && !st; r++) {
            double t = ts[r];
            st = add_abs(w, p->y0 + t * (p->by + t * (p->ay + t * p->dy)), -INFINITY,
                         INFINITY);
        }
    }
    return st;
}

static int rad_breakpoints_of(worker *w, const grad_radial *g, const aa_piece *const *local,
                              size_t n, size_t *total)
{
    const double *iv = g->inv;
    double R = w->R, xl = w->uc - R, xr = w->uc + R, yt = w->vc - R, yb = w->vc + R;
    int st = add_abs(w, g->py, -INFINITY, INFINITY);
    /* t's range over the window: its largest at a corner (quasiconvex), its
     * least at P* if inside, else on a side; the cone case's over the
     * painted part of the window (quasiconcave: "the cone case") */
    double tmax = -INFINITY, tmin;
    double cx[4] = {xl, xr, xl, xr}, cy[4] = {yt, yt, yb, yb};
    if (g->cone) {
        tmin = INFINITY;
        cone_seg_range(g, 0, xl, xr, yt, &tmin, &tmax);
        cone_seg_range(g, 0, xl, xr, yb, &tmin, &tmax);
        cone_seg_range(g, 1, yt, yb, xl, &tmin, &tmax);
        cone_seg_range(g, 1, yt, yb, xr, &tmin, &tmax);
        if (g->px >= xl && g->px <= xr && g->py >= yt && g->py <= yb) {
            tmin = fmin(tmin, -g->fr / g->dr);
            tmax = fmax(tmax, -g->fr / g->dr);
        }
    } else {
        for (int k = 0; k < 4; k++)
            tmax = fmax(tmax, rad_t(g, cx[k], cy[k]));
        if (g->px >= xl && g->px <= xr && g->py >= yt && g->py <= yb)
            tmin = -g->fr / g->dr;
        else {
            /* sides: the rows' minima along the top and bottom, and the
             * columns' by the same golden section on the transposed map */
            tmin = fmin(rad_row_min(g, xl, xr, yt), rad_row_min(g, xl, xr, yb));
            /* the corners the columns add are the rows' ends, already in */
            for (int k = 0; k < 2; k++)
                tmin = fmin(tmin, rad_line_min(g, 1, yt, yb, k ? xr : xl));
        }
    }
    tmin -= 1e-12 * (1.0 + fabs(tmin));
    tmax += 1e-12 * (1.0 + fabs(tmax));
    double *taus = w->gbuf, XL[KINK_LINES];
    int nxl = kink_lines(w, XL);
    if (g->cone == CONE_WEDGE || g->cone == CONE_HALF) /* the tangent lines L_k = 0 */
        for (int k = 0; k < (g->cone == CONE_HALF ? 1 : 2) && !st; k++)
            st = line_breaks(w, creal(g->lf[k][0]), creal(g->lf[k][1]), creal(g->lf[k][2]), 0.0,
                             local, n, XL, nxl);
    if (g->cone == CONE_HALF && g->spread != AA_SPREAD_PAD && !st) {
        /* t runs to infinity at the half-plane's edge: its stops repeat
         * without end there */
        int pos = 0, neg = 0;
        for (int k = 0; k < 4; k++) {
            double l = creal(g->lf[0][0]) * cx[k] + creal(g->lf[0][1]) * cy[k] + creal(g->lf[0][2]);
            pos |= l >= 0.0, neg |= l <= 0.0;
        }
        if (pos && neg)
            return aa_fail(AA_EINVAL, "pixel (%g, %g): the edge of a cone-case radial "
                                      "gradient whose focal circle touches its end circle, where "
                                      "t runs to infinity, passes its window, and its %s spread "
                                      "repeats the stops without end there: refused",
                           w->uc - 0.5, w->vc - 0.5,
                           g->spread == AA_SPREAD_REPEAT ? "repeat" : "reflect");
    }
    if (g->cone && !(tmin <= tmax))
        return st; /* no painted point in the window */
    size_t m = grad_taus(&g->plane, tmin, tmax, taus, w->cap_gbuf);
    *total += m;
    if (m > GRAD_MAX_BREAKS || *total > GRAD_MAX_BREAKS)
        return aa_fail(AA_EINVAL, "a gradient's stops repeat more than %d times across the "
                                  "window of pixel (%g, %g): refused",
                       GRAD_MAX_BREAKS, w->uc - 0.5, w->vc - 0.5);
    /* and where the composite at the window's centre passes the
     * decoding's threshold (threshold_taus) */
    m += threshold_taus(w, gl_of(w, g->layer), tmin, tmax, taus + m, w->cap_gbuf - m);
    if (m > w->cap_gbuf)
        m = w->cap_gbuf;
    double det = iv[0] * iv[3] - iv[1] * iv[2], n01 = hypot(iv[0], iv[1]);
    for (size_t q = 0; q < m && !st; q++) {
        double tau = taus[q], rt = g->fr + tau * g->dr;
        if (rt < 0.0)
            continue;
        /* the cone's front arc of the circle ends where the circle touches
         * the tangent lines: the foot of the perpendicular from its centre
         * tau D (relative to F) on L_k = 0 */
        for (int k = 0; k < 2 && g->cone == CONE_WEDGE && !st; k++) {
            const double *l = g->lg[k];
            double ccx = tau * g->Dx, ccy = tau * g->Dy, nn = l[0] * l[0] + l[1] * l[1];
            double lc = (l[0] * ccx + l[1] * ccy + l[2]) / nn;
            double gx = g->fx + ccx - lc * l[0], gy = g->fy + ccy - lc * l[1];
            st = add_abs(w, g->m[1] * gx + g->m[3] * gy + g->m[5], -INFINITY, INFINITY);
        }
        /* the circle of tau: |G|^2 = rt^2, G = m^-1(x, y) - F - tau D */
        double k0 = iv[4] - g->fx - tau * g->Dx, k1 = iv[5] - g->fy - tau * g->Dy;
        /* the window's sides x = X (and the filter's kinks, kink_lines):
         * G = (iv0 X + k0 + iv2 y, iv1 X + k1 + iv3 y) */
        for (int k = 0; k < nxl && !st; k++) {
            double X = XL[k], a0 = iv[0] * X + k0, b0 = iv[1] * X + k1, ys[2];
            int nr = gsl_poly_solve_quadratic(iv[2] * iv[2] + iv[3] * iv[3],
                                              2.0 * (iv[2] * a0 + iv[3] * b0),
                                              a0 * a0 + b0 * b0 - rt * rt, &ys[0], &ys[1]);
            for (int r = 0; r < nr && !st; r++)
                st = add_abs(w, ys[r], -INFINITY, INFINITY);
        }
        /* top and bottom rows: the row's quadratic in x has a double root
         * where iv0 Gy - iv1 Gx = +-rt |(iv0, iv1)| (Lagrange's identity),
         * linear in y; the circle's chord opens there like a square root
         * of the height, so those rows are turning points too (their half
         * intervals integrated in the square root of the distance) */
        for (int sgn = -1; sgn <= 1 && !st; sgn += 2) {
            double ytan = (sgn * rt * n01 - (iv[0] * k1 - iv[1] * k0)) / det;
            st = add_abs(w, ytan, -INFINITY, INFINITY);
            note_turn(w, ytan - w->vc);
        }
        if (w->radial && !st)
            st = rad_filter_circle(w, g, rt, k0, k1, tau);
        /* local pieces: (X, Y) / W polynomials in the piece's parameter */
        for (size_t k = 0; k < n && !st; k++) {
            const aa_piece *p = local[k];
            if (p->kind == AA_PIECE_FLAT)
                continue;
            if (p->kind == AA_PIECE_OFFSET) {
                st = offset_meet_circle(w, p, g, tau, rt);
                continue;
            }
            double X[4] = {0}, Y[4] = {0}, W[4] = {0}, Q[7] = {0}, lo = 0.0, hi = 1.0, sm = 0.0;
            int deg;
            if (p->kind == AA_PIECE_CONIC) {
                /* the angle s = sm + 2 atan(u) about the arc's middle, u in
                 * [-tan((s1 - s0)/4), tan(...)] (the arcs are split at their
                 * extremes in y, so within [-1, 1]); cos and sin of 2 atan(u)
                 * are (1 - u^2)/W and 2u/W, W = 1 + u^2 */
                sm = 0.5 * (p->s0 + p->s1), hi = tan(0.25 * (p->s1 - p->s0)), lo = -hi;
                double A = p->ea * cos(sm) + p->eb * sin(sm), B = p->eb * cos(sm) - p->ea * sin(sm);
                double Cy = -p->er * cos(sm), Sy = p->er * sin(sm);
                X[0] = p->ex + A, X[1] = 2.0 * B, X[2] = p->ex - A;
                Y[0] = p->ey + Cy, Y[1] = 2.0 * Sy, Y[2] = p->ey - Cy;
                W[0] = 1.0, W[2] = 1.0;
                deg = 2;
            } else {
                X[0] = p->x0, X[1] = p->bx, X[2] = p->ax, X[3] = p->dx;
                Y[0] = p->y0, Y[1] = p->by, Y[2] = p->ay, Y[3] = p->dy;
                W[0] = 1.0;
                deg = 3;
            }
            double GX[4], GY[4];
            for (int i = 0; i <= deg; i++) {
                GX[i] = iv[0] * X[i] + iv[2] * Y[i] + k0 * W[i];
                GY[i] = iv[1] * X[i] + iv[3] * Y[i] + k1 * W[i];
            }
            poly_mul_add(GX, deg, GX, deg, 1.0, Q);
            poly_mul_add(GY, deg, GY, deg, 1.0, Q);
            poly_mul_add(W, deg, W, deg, -rt * rt, Q);
            double us[6];
            int nu = poly_sign_roots(Q, 2 * deg, lo, hi, us);
            for (int r = 0; r < nu && !st; r++) {
                double u = us[r], y;
                if (p->kind == AA_PIECE_CONIC)
                    y = p->ey - p->er * cos(sm + 2.0 * atan(u));
                else
                    y = p->y0 + u * (p->by + u * (p->ay + u * p->dy));
                st = add_abs(w, y, -INFINITY, INFINITY);
            }
        }
    }
    return st;
}

static int rad_breakpoints(worker *w, const aa_piece *const *local, size_t n)
{
    size_t total = 0;
    int st = AA_OK;
    for (int k = 0; k < w->nrg && !st; k++)
        st = rad_breakpoints_of(w, &w->rg[k], local, n, &total);
    return st;
}

static int grad_breakpoints(worker *w, const aa_piece *const *local, size_t n)
{
    if (w->rad) {
        int sr = rad_breakpoints(w, local, n);
        if (sr || !w->ngp)
            return sr;
    }
    double R = w->R, cx[4] = {w->uc - R, w->uc + R, w->uc - R, w->uc + R},
           cy[4] = {w->vc - R, w->vc - R, w->vc + R, w->vc + R};
    int st = AA_OK;
    size_t total = 0;
    double XL[KINK_LINES];
    int nxl = kink_lines(w, XL);
    for (int g = 0; g < w->ngp && !st; g++) {
        const grad_plane *gp = &w->gp[g];
        double tmin = INFINITY, tmax = -INFINITY;
        for (int k = 0; k < 4; k++) {
            double t = gp->tx * cx[k] + gp->ty * cy[k] + gp->t0;
            tmin = fmin(tmin, t), tmax = fmax(tmax, t);
        }
        double *taus = w->gbuf;
        size_t m = grad_taus(gp, tmin, tmax, taus, w->cap_gbuf);
        total += m;
        if (m > GRAD_MAX_BREAKS || total > GRAD_MAX_BREAKS)
            return aa_fail(AA_EINVAL, "a gradient's stops repeat more than %d times across the "
                                      "window of pixel (%g, %g): refused",
                           GRAD_MAX_BREAKS, w->uc - 0.5, w->vc - 0.5);
        /* and the lines where the composite at the window's centre
         * passes the decoding's threshold, whose crossings of the kink
         * lines (for the box, the window's sides) are breakpoints too (the
         * inner integral's derivatives jump there; without them a pixel
         * under tent:r=1 whose window's side the threshold's line crosses
         * came out 1.05e-13 off against a bound of 1.0e-13, with them
         * 7e-18; the box's row integral has a kink there, which QAG's
         * estimate can miss) */
        {
            const gen_layer *gl = NULL;
            for (int k = 0; k < w->ngl; k++)
                if (w->gl[k].gp == gp)
                    gl = &w->gl[k];
            if (gl)
                m += threshold_taus(w, gl, tmin, tmax, taus + m, w->cap_gbuf - m);
            if (m > w->cap_gbuf)
                m = w->cap_gbuf;
        }
        for (size_t q = 0; q < m && !st; q++)
            st = line_breaks(w, gp->tx, gp->ty, gp->t0, taus[q], local, n, XL, nxl);
    }
    return st;
}

/* On failure the worker is left empty, so worker_free is always safe. */
static int worker_init(worker *w, const aa_scene *scene, const aa_filter *f)
{
    memset(w, 0, sizeof *w);
    w->scene = scene;
    w->f = f;
    w->box = aa_filter_is_box(f);
    w->radial = !aa_filter_is_separable(f);
    w->R = f->radius;
    w->limit = 1024;
    w->strip = aa_strip_new(scene);
    w->ws = gsl_integration_workspace_alloc(w->limit);
    int nl = aa_scene_layer_count(scene);
    w->wind = calloc((size_t)(nl > 0 ? nl : 1), sizeof *w->wind);
    if (w->radial)
        w->poly = gsl_poly_complex_workspace_alloc(5);
    if (!w->strip || !w->ws || !w->wind || (w->radial && !w->poly)) {
        worker_free(w);
        memset(w, 0, sizeof *w);
        return aa_fail(AA_ENOMEM, "out of memory for a reference worker");
    }
    return AA_OK;
}

/* Record breakpoint s (relative to vc) if it is inside (-R, R). */
static int add_point(worker *w, double s)
{
    if (!(s > -w->R && s < w->R))
        return AA_OK;
    if (w->npts == w->cap_pts) {
        size_t n = w->cap_pts ? 2 * w->cap_pts : 64;
        double *p = realloc(w->pts, n * sizeof *p);
        if (!p)
            return aa_fail(AA_ENOMEM, "out of memory for breakpoints");
        w->pts = p;
        w->cap_pts = n;
    }
    w->pts[w->npts++] = s;
    return AA_OK;
}

/* Record the absolute height y if it lies in (lo, hi). */
static int add_abs(worker *w, double y, double lo, double hi)
{
    return y > lo && y < hi ? add_point(w, y - w->vc) : AA_OK;
}

/* Heights where pieces p and q meet inside the window: every kind of pair,
 * every filter (aa_piece_meet: closed forms, or bisection on exact extents
 * for two general arcs).  Where two edges cross, the inner integral has a
 * kink that QAG's error estimate does not always see. */
static int add_intersections(worker *w, const aa_piece *p, const aa_piece *q)
{
    double ys[16];
    int n = aa_piece_meet(p, q, w->vc - w->R, w->vc + w->R, ys, 16), st = AA_OK;
    for (int k = 0; k < n && !st; k++)
        st = add_abs(w, ys[k], -INFINITY, INFINITY);
    return st;
}

/* Remember a turning point s (relative) inside [-R, R]. */
static void note_turn(worker *w, double s)
{
    if (!(s >= -w->R && s <= w->R))
        return;
    if (w->nsing == w->cap_sing) {
        size_t cap = w->cap_sing ? 2 * w->cap_sing : 64;
        double *p = realloc(w->sing, cap * sizeof *p);
        if (!p) {
            w->sing_oom = 1;
            return;
        }
        w->sing = p, w->cap_sing = cap;
    }
    w->sing[w->nsing++] = s;
}

/* The nearest turning point at or below s (dir < 0), at or above it
 * (dir > 0); NaN if there is none. */
static double nearest_turn(const worker *w, double s, int dir)
{
    double e = NAN;
    for (size_t k = 0; k < w->nsing; k++) {
        double t = w->sing[k];
        if (dir < 0 ? t <= s && !(t <= e) : t >= s && !(t >= e))
            e = t;
    }
    return e;
}

static int add_circle(worker *w, const aa_piece *p)
{
    double ys[4];
    int n = truth_circle_heights(p, w->uc, w->vc, w->R, w->poly, ys), st = AA_OK;
    for (int k = 0; k < n && !st; k++)
        st = add_point(w, ys[k]);
    return st;
}

/* Breakpoints of the current pixel, relative to vc, sorted, from -R to R. */
static int breakpoints(worker *w, const aa_piece *const *local, size_t n)
{
    double kink[8];
    int nk = w->f->type->kinks(w->f->spec.v, kink), st = AA_OK;
    w->npts = 0;
    for (int k = 0; k < nk && !st; k++)
        st = add_point(w, kink[k]);
    if (w->f->type == &aa_filter_gauss) {
        /* Start QAG on panels two standard deviations wide, where one
         * 21-point pass integrates the Gaussian factor to rounding. */
        double sd = w->f->spec.v[0];
        for (double z = -w->R + 2.0 * sd; z < w->R && !st; z += 2.0 * sd)
            st = add_point(w, z);
    }
    w->nsing = 0;
    if (w->radial) {
        /* the chord closes like a square root at both ends */
        note_turn(w, -w->R);
        note_turn(w, w->R);
        /* and the v^2 log|v| term at 0 becomes u^5 log u, smooth enough
         * for one Gauss-Kronrod pass where in v QAG bisects a dozen times */
        note_turn(w, 0.0);
    }
    for (size_t k = 0; k < n && !st; k++) {
        const aa_piece *p = local[k];
        double ys[3];
        if ((st = add_abs(w, p->y0, -INFINITY, INFINITY)) ||
            (st = add_abs(w, p->y1, -INFINITY, INFINITY)))
            break;
        if (p->kind == AA_PIECE_FLAT)
            continue;
        /* an end where dy/dt = 0 (an arc's turning point in y, where
         * edges are split): there x - x_end grows like sqrt(y - y_end) */
        int tlo, thi;
        truth_turns(p, &tlo, &thi);
        if (tlo)
            note_turn(w, p->y0 - w->vc);
        if (thi)
            note_turn(w, p->y1 - w->vc);
        if (w->radial) {
            /* where the piece crosses the disc's rim: a span's end leaves
             * the chord there (the row integral has no kink in u inside) */
            st = add_circle(w, p);
        } else {
            /* where the piece crosses a vertical line at which the filter's
             * cdf has a kink (the window's sides for the box) */
            for (int j = 0; j < nk && !st; j++) {
                int m = aa_piece_meet_x(p, w->uc + kink[j], ys);
                for (int q = 0; q < m && !st; q++)
                    st = add_abs(w, ys[q], -INFINITY, INFINITY);
            }
        }
        /* Gaussian: where it crosses x = uc + k s.  A steep piece sweeps
         * the window in a short stretch of v, where the inner integral
         * rises like Phi on a scale s / |dx/dy|; without these points QAG
         * can miss such a step and still report a small error (seen with
         * a nearly horizontal edge: an error of 1e-12 against an estimate
         * of 2e-14).  Between them the piece moves by s along x. */
        if (w->f->type == &aa_filter_gauss) {
            double sd = w->f->spec.v[0];
            for (double t = -floor(w->R / sd) * sd; t <= w->R && !st; t += sd) {
                int m = aa_piece_meet_x(p, w->uc + t, ys);
                for (int q = 0; q < m && !st; q++)
                    st = add_abs(w, ys[q], -INFINITY, INFINITY);
            }
        }
        if (n <= TRUTH_MAX_PAIRS && !w->all_crowd)
            for (size_t q = k + 1; q < n && !st; q++)
                st = add_intersections(w, p, local[q]);
    }
    /* a crowded window of gradient paint: the sweep's events (meetings,
     * ends, crossings of the window's sides) in place of the pairs */
    for (size_t k = 0; k < w->nxmeet && !st; k++)
        st = add_point(w, w->xmeet[k]);
    /* Radial filters: where a piece passes closest to the centre, the row
     * integral (singular at the centre) makes the inner integral change on
     * the scale of that distance, too fast for QAG's estimate to see: a
     * nearly horizontal line 1e-4 from the centre came out 7.6e-13 off
     * with an estimate of 1.2e-14.  That height is a breakpoint, integrated
     * in the square root of the distance to it on both sides. */
    for (size_t k = 0; w->radial && k < w->nlp && !st; k++) {
        const local_piece *q = &w->lp[k];
        double near = truth_nearest_height(q, fmax((double)q->y0, -w->R),
                                           fmin((double)q->y1, w->R), w->R);
        if (near == near) {
            note_turn(w, near);
            st = add_point(w, near);
        }
    }
    if (!st && w->grad)
        st = grad_breakpoints(w, local, n);
    if (st)
        return st;
    /* make room for both ends: add_point only grows inside (-R, R) */
    if ((st = add_point(w, 0.0)) || (st = add_point(w, 0.0)))
        return st;
    w->npts -= 2;
    qsort(w->pts, w->npts, sizeof *w->pts, truth_cmp_double);
    memmove(w->pts + 1, w->pts, w->npts * sizeof *w->pts);
    w->pts[0] = -w->R;
    size_t m = 1;
    for (size_t k = 1; k <= w->npts; k++)
        if (w->pts[k] > w->pts[m - 1])
            w->pts[m++] = w->pts[k];
    w->pts[m++] = w->R;
    w->npts = m;
    return AA_OK;
}

/* Set up the local pieces of the current window relative to (uc, vc). */
static int load_local(worker *w, const aa_piece *const *local, size_t n)
{
    if (n > w->cap_lp) {
        size_t cap = 2 * n;
        local_piece *lp = realloc(w->lp, cap * sizeof *lp);
        if (lp)
            w->lp = lp;
        crossing *cr = realloc(w->cross, cap * sizeof *cr);
        if (cr)
            w->cross = cr;
        if (!lp || !cr)
            return aa_fail(AA_ENOMEM, "out of memory for %zu local pieces", n);
        w->cap_lp = cap;
    }
    w->nlp = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_piece *p = local[k];
        if (!p->dir)
            continue; /* flat: no crossing, only a breakpoint */
        truth_set_local(&w->lp[w->nlp++], p, w->uc, w->vc);
    }
    return AA_OK;
}

/* x - uc where the piece meets the line at height s = y - vc (active). */
static long double crossing_at(const local_piece *q, long double s)
{
    return q->x0 + truth_crossing_part(q, s);
}

/* The inner integral along u at height s = v - vc, times w(s) (for a
 * radial filter, the rows' own integrals), of channels 0 to nch - 1 into
 * out (nch is 1 for a grey scene).  Each channel's sum takes the same
 * operations in the same order whether it is computed alone or with the
 * others.  Coordinates are relative to the pixel centre; the window is
 * [-R, R]. */
static inline void inner_sums(worker *w, double s, int nch, double *out)
{
    double ws = w->box || w->radial || w->unweighed ? 1.0 : aa_filter_weight(w->f, s);
    if (ws == 0.0) {
        for (int ch = 0; ch < nch; ch++)
            out[ch] = 0.0;
        return;
    }
    double R = w->R;
    size_t nc = 0;
    aa_strip_winding_left_at(w->strip, w->vc, s, w->wind);
    for (size_t k = 0; k < w->nlp; k++) {
        const local_piece *q = &w->lp[k];
        if (!(s >= q->y0 && s < q->y1))
            continue;
        if (q->side) { /* the rows' side of the window, known (sides) */
            if (q->side < 0)
                w->wind[q->layer] += q->dir;
            continue;
        }
        long double xl = crossing_at(q, s);
        if (xl < -R) {
            w->wind[q->layer] += q->dir;
            continue;
        }
        if (xl >= R)
            continue;
        double x = (double)xl;
        size_t at = nc++;
        while (at > 0 && w->cross[at - 1].x > x) {
            w->cross[at] = w->cross[at - 1];
            at--;
        }
        w->cross[at].x = x;
        w->cross[at].dir = q->dir;
        w->cross[at].layer = q->layer;
    }
    double sum[3] = {0.0, 0.0, 0.0}, cur = -R, fcur = 0.0;
    w->rad_row_err = 0.0;
    w->row_s = s;
    for (size_t k = 0; k <= nc; k++) {
        double next = k < nc ? w->cross[k].x : R;
        if (next > cur && w->grad) {
            grad_span(w, w->uc + cur, w->uc + next, w->vc + s, nch, sum);
            cur = next;
        } else if (next > cur) {
            aa_rgb col = aa_scene_colour_of(w->scene, w->wind);
            double fnext = w->box      ? next
                           : w->radial ? aa_filter_row_cdf(w->f, s, next)
                                       : aa_filter_cdf(w->f, next);
            for (int ch = 0; ch < nch; ch++) {
                double c = col.c[ch];
                if (c != 0.0)
                    sum[ch] += c * (w->box ? next - cur : fnext - fcur);
            }
            cur = next;
            fcur = fnext;
        }
        if (k < nc)
            w->wind[w->cross[k].layer] += w->cross[k].dir;
    }
    for (int ch = 0; ch < nch; ch++)
        out[ch] = ws * sum[ch];
    /* the row's quadrature bound, weighed as the row is (box: 1) */
    if (fabs(ws) * w->rad_row_err > w->rad_err_max)
        w->rad_err_max = fabs(ws) * w->rad_row_err;
}

static size_t memo_home(uint64_t key, size_t cap)
{
    return (size_t)((key * UINT64_C(0x9E3779B97F4A7C15)) >> 32) & (cap - 1);
}

/* The slot of key in the current generation, or the empty slot where it
 * would go. */
static memo_slot *memo_find(const memo *m, uint64_t key)
{
    size_t k = memo_home(key, m->cap);
    while (m->slot[k].gen == m->gen && m->slot[k].key != key)
        k = (k + 1) & (m->cap - 1);
    return &m->slot[k];
}

/* Room for one more entry at a load of at most a half: the table doubled
 * (the current generation's entries moved) up to MEMO_MAX_SLOTS; 0 if
 * there is none (full, or no memory: the value is then not stored). */
static int memo_room(memo *m)
{
    if (2 * (m->used + 1) <= m->cap)
        return 1;
    if (m->cap >= MEMO_MAX_SLOTS)
        return 0;
    size_t cap = m->cap ? 2 * m->cap : MEMO_MIN_SLOTS;
    memo_slot *slot = calloc(cap, sizeof *slot);
    if (!slot)
        return 0;
    memo old = *m;
    m->slot = slot;
    m->cap = cap;
    for (size_t k = 0; k < old.cap; k++)
        if (old.slot[k].gen == old.gen)
            *memo_find(m, old.slot[k].key) = old.slot[k];
    free(old.slot);
    return 1;
}

/* Empty the memo for a new pixel. */
static void memo_next(memo *m)
{
    m->used = 0;
    if (++m->gen == 0) { /* wrapped: generation 0 marks empty slots */
        if (m->slot)
            memset(m->slot, 0, m->cap * sizeof *m->slot);
        m->gen = 1;
    }
}

/* The integrand of QAG: channel w->channel's inner integral at height s.
 * In a colour pixel every evaluation computes the three channels in one
 * pass and keeps them in the memo, where the later channels find them. */
static double integrand(double s, void *params)
{
    worker *w = params;
    double v[3];
    if (!w->shared) {
        inner_sums(w, s, 1, v);
        return v[0];
    }
    uint64_t key;
    memcpy(&key, &s, sizeof key);
    memo *m = &w->memo;
    if (m->used) {
        const memo_slot *e = memo_find(m, key);
        if (e->gen == m->gen)
            return e->v[w->channel];
    }
    inner_sums(w, s, 3, v);
    if (memo_room(m)) {
        memo_slot *e = memo_find(m, key);
        e->key = key;
        e->gen = m->gen;
        memcpy(e->v, v, sizeof e->v);
        m->used++;
    }
    return v[w->channel];
}

/* The integrand near a turning point e, in u with s = e + sign u^2: the
 * square root becomes smooth, and ds = 2 u du. */
typedef struct turn_ctx {
    worker *w;
    double e, sign;
} turn_ctx;

static double integrand_turn(double u, void *params)
{
    const turn_ctx *t = params;
    return 2.0 * u * integrand(t->e + t->sign * u * u, t->w);
}

/* One interval: a single 21-point Gauss-Kronrod pass, which is what QAG
 * starts with and is enough between breakpoints nearly always (for crow
 * under the box it is exact), then QAG's bisection only if its estimate is
 * above eps.  Calling the pass directly saves QAG's set-up per interval. */
static void qag(worker *w, gsl_function *F, double a, double b, double eps, double *res,
                double *err)
{
    double r = 0.0, e = 0.0, resabs, resasc;
    gsl_integration_qk21(F, a, b, &r, &e, &resabs, &resasc);
    if (!(e <= eps))
        gsl_integration_qag(F, a, b, eps, 0.0, w->limit, GSL_INTEG_GAUSS21, w->ws, &r, &e);
    *res += r;
    *err += e;
}

/* The outer integral as a sum over the breakpoints' intervals, each by
 * adaptive Gauss-Kronrod (QAG) on its own.  Between breakpoints the
 * integrand is smooth, so no extrapolation is wanted: QAG's, across all
 * the intervals at once, was seen to return a wrong value (2.6e-7 off)
 * with an estimate of 9e-15 on a pixel where two arcs turn.  A half
 * interval next to a turning point e is integrated in u = sqrt(|s - e|),
 * and so is one whose interval ends closer to e than its own length: x
 * moves like the square root there too, and with e just outside it the
 * Gauss-Kronrod pass converges slowly while its estimate (GSL's, which
 * trusts the Kronrod value) stays small.  A loop cubic turning 0.0044
 * above a kink's breakpoint under Mitchell's filter came out 1.1e-12 off
 * with an estimate of 9.4e-15 on the next interval, 0.49 long. */
/* Before the rows (a, b) are integrated: the side of the window each
 * offset piece present there lies wholly on, if it does (truth_offset_side,
 * two crossings solved for), so that inner_sums adds its winding or leaves
 * it out without solving for its crossing at each of QAG's heights (its
 * crossings with the window's sides are breakpoints for the box and the
 * tent: in 40% of those evaluations an offset piece lay outside).  Other
 * pieces' crossings are closed forms or cheap; they keep 0. */
static void sides(worker *w, double a, double b)
{
    for (size_t k = 0; k < w->nlp; k++) {
        local_piece *q = &w->lp[k];
        q->side = q->offset ? truth_offset_side(q, a, b, w->R) : 0;
    }
}

static double thr_in_sliver(const worker *w, double a, double b);

static void integrate_intervals(worker *w, double *result, double *abserr)
{
    gsl_function F = {integrand, w};
    double span = w->pts[w->npts - 1] - w->pts[0];
    *result = *abserr = 0.0;
    for (size_t k = 0; k + 1 < w->npts; k++) {
        double a = w->pts[k], b = w->pts[k + 1];
        double eps = fmax(TRUTH_EPSABS * (b - a) / span, 1e-17);
        double ea = nearest_turn(w, a, -1), eb = nearest_turn(w, b, 1);
        int ta = a - ea < b - a, tb = eb - b < b - a; /* false for NaN */
        sides(w, a, b);
        double dv = thr_in_sliver(w, a, b);
        if (dv >= 0.0) {
            /* a sliver of thr_certify: its middle row, and the declared
             * bound (F within dv of it on every row of the sliver) with
             * that row's own bound, over the sliver's height only; under
             * a separable filter the row without its weight (G, F = w G),
             * times the weight's integral over the sliver (dv bounds the
             * weight times |G(s) - G(m)|) */
            double v[3], keep = w->rad_err_max, pk = 1.0, ws = b - a;
            w->rad_err_max = 0.0;
            if (!w->box && !w->radial) {
                w->unweighed = 1;
                pk = fabs(aa_filter_weight(w->f, 0.0));
                ws = aa_filter_cdf(w->f, b) - aa_filter_cdf(w->f, a);
            }
            inner_sums(w, 0.5 * (a + b), w->shared ? 3 : 1, v);
            w->unweighed = 0;
            *result += ws * v[w->shared ? w->channel : 0];
            *abserr += (b - a) * (dv + pk * w->rad_err_max);
            w->rad_err_max = keep;
            continue;
        }
        if (!ta && !tb) {
            qag(w, &F, a, b, eps, result, abserr);
            continue;
        }
        double m = 0.5 * (a + b);
        turn_ctx lo = {w, ea, 1.0}, hi = {w, eb, -1.0};
        gsl_function G = {integrand_turn, &lo}, H = {integrand_turn, &hi};
        if (ta)
            qag(w, &G, sqrt(a - ea), sqrt(m - ea), 0.5 * eps, result, abserr);
        else
            qag(w, &F, a, m, 0.5 * eps, result, abserr);
        if (tb)
            qag(w, &H, sqrt(eb - b), sqrt(eb - m), 0.5 * eps, result, abserr);
        else
            qag(w, &F, m, b, 0.5 * eps, result, abserr);
    }
    for (size_t k = 0; k < w->nlp; k++)
        w->lp[k].side = 0; /* known for those rows only */
}

/* ---- the threshold's heights where layers of different t mix ----
 *
 * A row's signature: the counts of the threshold's places (gen_section)
 * per channel in each section of the row where layers of different t
 * mix, in the row's order; into sig (at most SIG_MAX), its length
 * returned, -1 if it did not fit or the row was refused. */
#define THR_ROWS 32   /* scan rows across the window's height */
#define THR_EVENTS 64 /* most heights found a pixel */
#define THR_NEAR 1e-6 /* changes closer to a breakpoint (times R) are its own */

typedef struct thr_sig {
    int n, v[SIG_MAX];
} thr_sig;

static void thr_row(worker *w, double s, int nch, thr_sig *out)
{
    double v[3];
    w->scan = 1, w->nsig = 0, w->sig_over = 0;
    inner_sums(w, s, nch, v);
    w->scan = 0;
    if (w->sig_over || w->gen_stuck || w->gen_over || w->cone_over) {
        w->gen_stuck = w->gen_over = w->cone_over = 0;
        out->n = -1;
        return;
    }
    out->n = (int)w->nsig;
    memcpy(out->v, w->sig, w->nsig * sizeof *w->sig);
}

static int thr_same(const thr_sig *a, const thr_sig *b)
{
    return a->n == b->n && (a->n <= 0 || !memcmp(a->v, b->v, (size_t)a->n * sizeof *a->v));
}

static int thr_total(const thr_sig *a)
{
    int t = 0;
    for (int k = 0; k < a->n; k++)
        t += a->v[k];
    return t;
}

/* ---- the threshold's events, certified (thr_certify) ----
 *
 * Interval arithmetic over boxes of the window (truth.c's opening
 * comment, "several gradients"): a range is a pair of doubles moved out
 * by one ulp after every operation (each is correctly rounded, to within
 * half an ulp, subnormal results included); a NaN makes it the whole
 * line.  A jet holds a quantity's range on the box and its
 * x-derivative's. */
#define THR_BOXES 200000 /* most boxes one pixel's subdivision takes */
#define THR_LEAVES 8192  /* room for the boxes kept, a pixel (merged as it fills) */
#define THR_SLIVERS 256  /* most slivers (their rows merged), a pixel */
#define THR_SIDE 0x1p-32 /* boxes are kept, not halved, once this times 2 R high */
#define THR_SEG 8        /* one layer's stop segments a box is taken in, one at a time */
#define THR_ASPECT 16.0  /* boxes are halved across x only if this many times wider than high */
#define THR_GAP 0x1p-32  /* slivers closer than this times 2 R are merged, the rows between kept */
#define THR_STRIP_DEPTH 8 /* a strip of the sliver bound halved in x at most this often */
#define THR_PART 3       /* most cone layers painting part of a box taken painted and not */
#define THR_CONE_LEFT 1e-13 /* slivers' bound past which a window of a cone layer is scanned */
#define THR_CONE_BOXES 50000 /* boxes past which a window of a cone layer is scanned */

typedef struct thr_iv {
    double lo, hi;
} thr_iv;

typedef struct thr_jet {
    thr_iv v, d;
} thr_jet;

/* A cone layer's tangent line crossing a box (thr_cone_line): on, the
 * layer's derivative returned times u = sqrt(L0 L1) in [0, U], and tl, t
 * on the line from its painted side. */
typedef struct thr_line {
    int on;
    double U;
    thr_iv tl;
} thr_line;

/* lo and hi moved out by |x| 2^-52 and the least subnormal: a correctly
 * rounded result is within 2^-53 |x| of the exact one (or half the least
 * subnormal), and the move, at least an ulp of x, survives its own
 * rounding to nearest (nextafter costs a call: once 44% of a mixed
 * scene's time) */
static thr_iv iv_out(double lo, double hi)
{
    if (lo != lo || hi != hi)
        return (thr_iv){-INFINITY, INFINITY};
    return (thr_iv){lo - (fabs(lo) * 0x1p-52 + 0x1p-1074), hi + (fabs(hi) * 0x1p-52 + 0x1p-1074)};
}

static inline double thr_min(double a, double b)
{
    return a < b ? a : b;
}

static inline double thr_max(double a, double b)
{
    return a > b ? a : b;
}

static thr_iv iv_k(double k)
{
    return (thr_iv){k, k};
}

static thr_iv iv_add(thr_iv a, thr_iv b)
{
    return iv_out(a.lo + b.lo, a.hi + b.hi);
}

static thr_iv iv_sub(thr_iv a, thr_iv b)
{
    return iv_out(a.lo - b.hi, a.hi - b.lo);
}

static thr_iv iv_mul(thr_iv a, thr_iv b)
{
    double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
    if (p0 != p0 || p1 != p1 || p2 != p2 || p3 != p3)
        return (thr_iv){-INFINITY, INFINITY};
    return iv_out(thr_min(thr_min(p0, p1), thr_min(p2, p3)),
                  thr_max(thr_max(p0, p1), thr_max(p2, p3)));
}

static thr_iv iv_sqr(thr_iv a)
{
    if (a.lo >= 0.0)
        return iv_out(a.lo * a.lo, a.hi * a.hi);
    if (a.hi <= 0.0)
        return iv_out(a.hi * a.hi, a.lo * a.lo);
    return iv_out(0.0, thr_max(a.lo * a.lo, a.hi * a.hi));
}

static thr_jet j_k(thr_iv v)
{
    return (thr_jet){v, {0.0, 0.0}};
}

static thr_jet j_add(thr_jet a, thr_jet b)
{
    return (thr_jet){iv_add(a.v, b.v), iv_add(a.d, b.d)};
}

static thr_jet j_sub(thr_jet a, thr_jet b)
{
    return (thr_jet){iv_sub(a.v, b.v), iv_sub(a.d, b.d)};
}

static thr_jet j_mul(thr_jet a, thr_jet b)
{
    return (thr_jet){iv_mul(a.v, b.v), iv_add(iv_mul(a.d, b.v), iv_mul(a.v, b.d))};
}

static thr_jet j_scale(double k, thr_jet a)
{
    return (thr_jet){iv_mul(iv_k(k), a.v), iv_mul(iv_k(k), a.d)};
}

static thr_jet j_sqr(thr_jet a)
{
    return (thr_jet){iv_sqr(a.v), iv_mul(iv_mul(iv_k(2.0), a.v), a.d)};
}

/* The square root; its derivative's range needs the root's range above 0
 * (else *bad is set and it is the whole line). */
static thr_jet j_sqrt(thr_jet a, int *bad)
{
    thr_jet r;
    if (!(a.v.hi >= 0.0)) {
        *bad = 1;
        return (thr_jet){{-INFINITY, INFINITY}, {-INFINITY, INFINITY}};
    }
    r.v = iv_out(sqrt(fmax(a.v.lo, 0.0)), sqrt(a.v.hi));
    if (!(r.v.lo > 0.0)) {
        *bad = 1;
        r.d = (thr_iv){-INFINITY, INFINITY};
    } else
        r.d = iv_mul(a.d, iv_out(0.5 / r.v.hi, 0.5 / r.v.lo));
    return r;
}

/* One pixel's data for the boxes: the composite's steps (aa_scene_fold,
 * the window's windings) with, per step, the index of its gradient layer
 * in w->gl (-1: a layer of its own colour), and each layer's t at the
 * pixel's centre (linear) or q there (radial) as ranges. */
typedef struct thr_ctx {
    worker *w;
    int nch, nst, nk;
    const aa_fold_step *st;
    const int *sl;
    double base[3], kink[8];
    unsigned char *used; /* per layer (ngl): it has a step of the fold */
    thr_jet *scr;        /* room for 5 ngl jets (thr_box) */
    int dy; /* the jets' derivative is along y, not x (thr_strip) */
    thr_iv *q0;
    double *buf;
    size_t cap;
    /* pieces entering the window (thr_window_clear): npc of them, their
     * indices in w->lp (pc); each box takes its own steps (thr_box_at) */
    int npc;
    const int *pc;
    struct thr_cache *cache;
    /* per layer of the cone case: its linear forms L0, L1 at the pixel's
     * centre (CONE_NESTED: L0's real and imaginary parts; 4 a layer), and
     * whether it paints the box (thr_t: 1 all of it, 0 none, 2 part) */
    thr_iv *lc;
    unsigned char *paint;
} thr_ctx;

/* 1 / a, the whole line where a's range holds 0. */
static thr_jet j_inv(thr_jet a)
{
    if (!(a.v.lo > 0.0 || a.v.hi < 0.0))
        return (thr_jet){{-INFINITY, INFINITY}, {-INFINITY, INFINITY}};
    thr_iv r = iv_out(1.0 / a.v.hi, 1.0 / a.v.lo);
    return (thr_jet){r, iv_sub(iv_k(0.0), iv_mul(a.d, iv_sqr(r)))};
}

/* A wedge's tangent line L_k0 = 0 crossing the box, the other form L_k1
 * above 0 on it (thr_cone_t; "a tangent line the curve touches" in
 * truth.c's opening comment): the layer paints part of the box (*paint
 * 2).  On that part t = (b + u) / a, u = sqrt(L0 L1) in [0, U] (or c /
 * (b - u) where b keeps below 0), its derivative t' = (b' + (L0' L1 +
 * L0 L1') / (2 u)) / a unbounded at the line; returned is u t' = (u b'
 * + (L0' L1 + L0 L1') / 2) / a, bounded, of t''s sign where u > 0, with
 * ln: U and t on the line, b / a (u = 0, L_k0 = 0). */
static thr_jet thr_cone_line(const grad_radial *r, thr_jet *L, int k0, thr_jet b, thr_jet cc,
                             unsigned char *paint, thr_line *ln)
{
    thr_iv ia = iv_out(1.0 / r->a, 1.0 / r->a), P[2];
    *paint = 2;
    for (int k = 0; k < 2; k++)
        P[k] = L[k].v;
    P[k0].lo = 0.0;
    thr_iv d = iv_mul(P[0], P[1]), u = iv_out(0.0, sqrt(fmax(d.hi, 0.0)));
    u.lo = 0.0;
    thr_jet t;
    t.v = iv_mul(iv_add(b.v, u), ia);
    if (b.v.lo + b.v.hi < 0.0) {
        thr_iv den = iv_sub(b.v, u);
        if (den.hi < 0.0)
            t.v = iv_mul(cc.v, iv_out(1.0 / den.hi, 1.0 / den.lo));
    }
    thr_iv dd = iv_add(iv_mul(L[0].d, P[1]), iv_mul(P[0], L[1].d));
    t.d = iv_mul(iv_add(iv_mul(u, b.d), iv_mul(iv_k(0.5), dd)), ia);
    ln->on = 1, ln->U = u.hi, ln->tl = iv_mul(b.v, ia);
    return t;
}

/* A layer of the cone case on the box (thr_t; "the cone case"): its
 * linear forms' ranges decide where it paints, {L0 >= 0, L1 >= 0}
 * (CONE_HALF: L0 > 0; CONE_NESTED: everywhere), *paint 1 on the whole
 * box, 0 nowhere, 2 on part of it (a tangent line or the half-plane's
 * edge crosses it: a cut, *bad set, the layer taken both painted and not
 * by thr_box).  Where it paints, t from the forms over the painted part
 * (each form's range clamped to its sign there): (b + sqrt d) / a with d
 * = L0 L1 (CONE_NESTED: |L0|^2), exact near a tangent line, or c / (b -
 * sqrt d) where b keeps below 0 (the two forms of cone_t_sq; neither
 * cancels), c / (2 b) for CONE_HALF.  d's range reaching 0 (the apex P*
 * in the box, or a tangent line) leaves t's derivative unbounded: *bad. */
static thr_jet thr_cone_t(const thr_ctx *c, int l, thr_jet b, thr_jet cc, thr_iv X, thr_iv S,
                          int *bad, unsigned char *paint, thr_line *ln)
{
    const grad_radial *r = c->w->gl[l].rg;
    thr_jet L[2];
    for (int k = 0; k < 2; k++) {
        const double complex *f = r->cone == CONE_NESTED ? r->lf[0] : r->lf[k];
        double f0 = k && r->cone == CONE_NESTED ? cimag(f[0]) : creal(f[0]);
        double f1 = k && r->cone == CONE_NESTED ? cimag(f[1]) : creal(f[1]);
        L[k].v = iv_add(c->lc[4 * l + k], iv_add(iv_mul(iv_k(f0), X), iv_mul(iv_k(f1), S)));
        L[k].d = iv_k(c->dy ? f1 : f0);
    }
    *paint = 1;
    if (r->cone != CONE_NESTED) {
        double least = r->cone == CONE_HALF ? 0x1p-1074 : 0.0; /* the edge is not painted */
        if (L[0].v.hi < least || L[1].v.hi < least) {
            *paint = 0;
            return (thr_jet){{0.0, 0.0}, {0.0, 0.0}};
        }
        int k0 = L[0].v.lo >= least; /* the form whose range may hold 0 */
        if (!(L[0].v.lo >= least && L[1].v.lo >= least) && ln && r->cone == CONE_WEDGE &&
            L[1 - k0].v.lo > 0.0)
            return thr_cone_line(r, L, k0, b, cc, paint, ln);
        if (!(L[0].v.lo >= least && L[1].v.lo >= least)) {
            *paint = 2, *bad = 1;
            for (int k = 0; k < 2; k++)
                L[k].v.lo = fmax(L[k].v.lo, 0.0), L[k].d = (thr_iv){-INFINITY, INFINITY};
            b.d = cc.d = (thr_iv){-INFINITY, INFINITY};
        }
    }
    if (r->cone == CONE_HALF) { /* b = sg L0 where it paints, t = c / (2 b) */
        thr_jet b2 = r->dr > 0.0 ? L[0] : j_scale(-1.0, L[0]);
        if (*paint == 2) {
            /* the edge crosses the box: on its painted part sg b in (0,
             * sg L0's greatest], so t = c / (2 b) lies beyond c's least
             * over twice that (sg c > 0) towards sg infinity, the pole;
             * a padded layer's paint there is its last or first stop's
             * (thr_paint), whatever the derivative */
            thr_iv v = {-INFINITY, INFINITY};
            double bh = L[0].v.hi, k = r->dr > 0.0 ? 1.0 : -1.0;
            thr_iv sc = k > 0.0 ? cc.v : (thr_iv){-cc.v.hi, -cc.v.lo};
            if (bh > 0.0 && sc.lo > 0.0) {
                double q = iv_out(sc.lo / (2.0 * bh), 0.0).lo;
                v = k > 0.0 ? (thr_iv){q, INFINITY} : (thr_iv){-INFINITY, -q};
            }
            return (thr_jet){v, {-INFINITY, INFINITY}};
        }
        return j_mul(cc, j_inv(j_scale(2.0, b2)));
    }
    thr_jet d = r->cone == CONE_NESTED ? j_add(j_sqr(L[0]), j_sqr(L[1])) : j_mul(L[0], L[1]);
    thr_jet sq = j_sqrt(d, bad);
    if (b.v.lo + b.v.hi < 0.0) {
        thr_jet den = j_sub(b, sq);
        if (den.v.hi < 0.0)
            return j_mul(cc, j_inv(den));
    }
    return j_mul(j_add(b, sq), j_k(iv_out(1.0 / r->a, 1.0 / r->a)));
}

/* Layer l's t on the box X x S (relative); *bad set where its derivative's
 * range is not had (a radial layer's discriminant near 0, a cone's
 * tangent line or P*); *paint: 1, or the cone case's (thr_cone_t). */
static thr_jet thr_t(const thr_ctx *c, int l, thr_iv X, thr_iv S, int *bad,
                     unsigned char *paint, thr_line *ln)
{
    const gen_layer *g = &c->w->gl[l];
    *paint = 1;
    if (g->gp) {
        const grad_plane *p = g->gp;
        thr_iv v = iv_add(c->q0[2 * l], iv_add(iv_mul(iv_k(p->tx), X), iv_mul(iv_k(p->ty), S)));
        return (thr_jet){v, iv_k(c->dy ? p->ty : p->tx)};
    }
    const grad_radial *r = g->rg;
    thr_jet qx = {
        iv_add(c->q0[2 * l], iv_add(iv_mul(iv_k(r->inv[0]), X), iv_mul(iv_k(r->inv[2]), S))),
        iv_k(r->inv[c->dy ? 2 : 0])};
    thr_jet qy = {
        iv_add(c->q0[2 * l + 1], iv_add(iv_mul(iv_k(r->inv[1]), X), iv_mul(iv_k(r->inv[3]), S))),
        iv_k(r->inv[c->dy ? 3 : 1])};
    thr_jet b = j_add(j_add(j_scale(r->Dx, qx), j_scale(r->Dy, qy)),
                      j_k(iv_mul(iv_k(r->fr), iv_k(r->dr))));
    thr_jet cc = j_sub(j_add(j_sqr(qx), j_sqr(qy)), j_k(iv_sqr(iv_k(r->fr))));
    if (r->cone)
        return thr_cone_t(c, l, b, cc, X, S, bad, paint, ln);
    thr_jet disc = j_sub(j_sqr(b), j_scale(r->a, cc));
    /* t = (b - sqrt(disc)) / a, a < 0 (rad_t's two forms are this) */
    return j_mul(j_sub(b, j_sqrt(disc, bad)), j_k(iv_out(1.0 / r->a, 1.0 / r->a)));
}

/* Where t = m falls in a period of the layer's stops (the spread). */
static double thr_period_place(int spread, double t)
{
    if (spread == AA_SPREAD_REPEAT)
        return t - floor(t);
    if (spread == AA_SPREAD_REFLECT) {
        double f = t - 2.0 * floor(0.5 * t);
        return f <= 1.0 ? f : 2.0 - f;
    }
    return t;
}

/* A channel of a layer in linear light ("gradients in linear light"):
 * its linear value v (a jet) on one piece of the cut stops becomes the
 * encoded C = 12.92 v below LIN_T (power 0), 1.055 v^p - 0.055 above it,
 * p = 1/2.4, increasing, its derivative 1.055 p v^(p - 1) v' decreasing
 * in v (not had where v's range reaches 0).  pow's error, below an ulp,
 * and the product's rounding are covered by 4 epsilons of the result. */
static thr_jet thr_encode(thr_jet v, int power)
{
    if (!power)
        return j_scale(12.92, v);
    const double p = 1.0 / 2.4, r = 4.0 * DBL_EPSILON;
    double lo = v.v.lo, hi = v.v.hi;
    thr_jet c;
    c.v = iv_out(lo > 0.0 ? 1.055 * pow(lo, p) * (1.0 - r) - 0.055 : -0.055,
                 1.055 * pow(fmax(hi, 0.0), p) * (1.0 + r) - 0.055);
    if (!(lo > 0.0)) {
        c.d = (thr_iv){-INFINITY, INFINITY};
        return c;
    }
    thr_iv D = iv_out(1.055 * p * pow(hi, p - 1.0) * (1.0 - r),
                      1.055 * p * pow(lo, p - 1.0) * (1.0 + r));
    c.d = iv_mul(v.d, D);
    return c;
}

/* Layer g's opacity and channels (p[3], p[0 .. 2]) where its t, in the
 * range t, lies in one stop segment, that of tm (thr_affine: the range's
 * middle): v0 + v1 t (paint_lin) with their rounding added; in linear
 * light each channel then encoded on the side of LIN_T the segment keeps
 * to, decided at tm as gen_section does. */
static void thr_affine_at(const gen_layer *g, thr_jet t, double tm, thr_jet p[4])
{
    double ta = t.v.lo, tb = t.v.hi, v0[4], v1[4];
    paint_lin(g->spread, g->stops, g->nstops, g->enc, tm, v0, v1);
    for (int k = 0; k < 4; k++) {
        double e = 8.0 * DBL_EPSILON * (fabs(v0[k]) + fabs(v1[k]) * fmax(fabs(ta), fabs(tb)));
        p[k].v = iv_add(iv_add(iv_k(v0[k]), iv_mul(iv_k(v1[k]), t.v)), (thr_iv){-e, e});
        p[k].d = iv_mul(iv_k(v1[k]), t.d);
        if (g->lin && k < 3)
            p[k] = thr_encode(p[k], v0[k] + v1[k] * tm > LIN_T);
    }
}

static void thr_affine(const gen_layer *g, thr_jet t, thr_jet p[4])
{
    thr_affine_at(g, t, 0.5 * (t.v.lo + t.v.hi), p);
}

/* Layer l's opacity and channels (p[3], p[0 .. 2]) on the box, its t
 * there given: one stop segment across the t range, v0 + v1 t with their
 * rounding (paint_lin) added; else (*cut set: a stop line or circle, or a
 * period's end, crosses the box) the ranges of the paint, which is
 * piecewise affine in t, from its values at the range's ends and at the
 * stops met inside (their own values: both sides of a sharp stop, the
 * first and last stops at a period's end), the derivative not had. */
static void thr_paint(const thr_ctx *c, int l, thr_jet t, thr_jet p[4], int *cut)
{
    const gen_layer *g = &c->w->gl[l];
    const grad_plane *gp = g->gp ? g->gp : &g->rg->plane;
    double ta = t.v.lo, tb = t.v.hi, v0[4], v1[4];
    if (g->rg && g->rg->cone && g->spread == AA_SPREAD_PAD && g->nstops > 0 &&
        (ta == -INFINITY || tb == INFINITY)) {
        /* a cone's t unbounded (the half-plane's pole): padded, the paint
         * of t is that of t clamped to the stops' offsets */
        double o0 = g->stops[0].offset, o1 = g->stops[g->nstops - 1].offset;
        ta = fmin(fmax(ta, o0), o1), tb = fmin(fmax(tb, o0), o1);
    }
    double pad = 8.0 * DBL_EPSILON * (1.0 + fmax(fabs(ta), fabs(tb)));
    size_t nb = ta == -INFINITY || tb == INFINITY
                    ? SIZE_MAX
                    : grad_taus(gp, ta - pad, tb + pad, c->buf, c->cap);
    if (nb == 0) {
        thr_affine(g, t, p);
        return;
    }
    *cut = 1;
    double lo[4], hi[4];
    for (int k = 0; k < 4; k++)
        lo[k] = INFINITY, hi[k] = -INFINITY;
    int all = nb > c->cap;
    for (int e = 0; e < 2 && !all; e++) {
        double te = e ? tb : ta;
        paint_lin(g->spread, g->stops, g->nstops, g->enc, te, v0, v1);
        for (int k = 0; k < 4; k++) {
            double v = v0[k] + v1[k] * te;
            lo[k] = fmin(lo[k], v), hi[k] = fmax(hi[k], v);
        }
    }
    for (size_t b = 0; b < (all ? 0 : nb); b++) {
        double m = thr_period_place(g->spread, c->buf[b]);
        /* a period's end: repeat jumps from the last stop to the first;
         * reflect turns back, continuous, at the first (m = 0) or the
         * last (m = 1) */
        int lo0 = m <= 1e-9, hi1 = m >= 1.0 - 1e-9, rep = g->spread == AA_SPREAD_REPEAT;
        int refl = g->spread == AA_SPREAD_REFLECT;
        for (int s = 0; s < g->nstops; s++) {
            int end = (s == 0 && ((rep && (lo0 || hi1)) || (refl && lo0))) ||
                      (s == g->nstops - 1 && ((rep && (lo0 || hi1)) || (refl && hi1)));
            if (!(fabs(g->stops[s].offset - m) <= 1e-9) && !end)
                continue;
            for (int k = 0; k < 4; k++)
                lo[k] = fmin(lo[k], g->enc[4 * s + k]), hi[k] = fmax(hi[k], g->enc[4 * s + k]);
        }
    }
    for (int s = 0; s < g->nstops && all; s++)
        for (int k = 0; k < 4; k++)
            lo[k] = fmin(lo[k], g->enc[4 * s + k]), hi[k] = fmax(hi[k], g->enc[4 * s + k]);
    for (int k = 0; k < 4; k++) {
        double e = 8.0 * DBL_EPSILON * fmax(fabs(lo[k]), fabs(hi[k]));
        if (g->lin && k < 3) {
            /* in linear light: the encoding of the linear values' range,
             * increasing but for its step at LIN_T, 2.9e-8 down (IEC
             * 61966-2-1's two pieces do not meet), and pow's rounding */
            lo[k] = aa_srgb_encode(lo[k]) - 3e-8, hi[k] = aa_srgb_encode(hi[k]) + 3e-8;
        }
        p[k].v = iv_out(lo[k] - e, hi[k] + e);
        p[k].d = (thr_iv){-INFINITY, INFINITY};
    }
}

/* E of each channel on the box (its jets), the layers' opacity a and
 * opacity times channel ac given: the composite's steps folded. */
static void thr_fold(const thr_ctx *c, const thr_jet *a, thr_jet (*ac)[3], thr_jet *E)
{
    for (int ch = 0; ch < c->nch; ch++) {
        thr_jet q[AA_SCENE_MAX_GROUP_DEPTH + 1], al[AA_SCENE_MAX_GROUP_DEPTH + 1];
        thr_jet one = j_k(iv_k(1.0));
        int d = 0;
        q[0] = j_k(iv_k(c->base[ch]));
        al[0] = one;
        for (int k = 0; k < c->nst; k++) {
            const aa_fold_step *st = &c->st[k];
            if (st->op == AA_FOLD_OPEN) {
                d++;
                q[d] = al[d] = j_k(iv_k(0.0));
            } else if (st->op == AA_FOLD_CLOSE) {
                thr_jet oa = j_scale(st->a, al[d]), rest = j_sub(one, oa);
                q[d - 1] = j_add(j_scale(st->a, q[d]), j_mul(rest, q[d - 1]));
                al[d - 1] = j_add(oa, j_mul(rest, al[d - 1]));
                d--;
            } else {
                int l = c->sl[k];
                thr_jet aa = l >= 0 ? j_scale(st->a, a[l]) : j_k(iv_k(st->a));
                thr_jet acc = l >= 0 ? j_scale(st->a, ac[l][ch])
                                     : j_k(iv_mul(iv_k(st->a), iv_k(st->c[ch])));
                thr_jet rest = j_sub(one, aa);
                q[d] = j_add(acc, j_mul(rest, q[d]));
                al[d] = j_add(aa, j_mul(rest, al[d]));
            }
        }
        E[ch] = q[0];
    }
}

/* The share of [x0, x1] over which the cone layers part[0 .. np - 1]'s
 * tangent lines (the half-plane's edge) that cross the box [x0, x1] x
 * [s0, s1] (relative) lie on its rows: each line L = f0 x + f1 s + l = 0
 * whose range there holds 0 moves |f1 / f0| (s1 - s0) in x over them (the
 * whole width where f0 is 0), with 1e-9 of that and 1e-14 of the window
 * for rounding; at most 1. */
static double thr_cone_cross(const thr_ctx *c, const int *part, int np, double x0, double x1,
                             double s0, double s1)
{
    thr_iv X = {x0, x1}, S = {s0, s1};
    double len = 0.0, wd = x1 - x0;
    for (int i = 0; i < np; i++) {
        const grad_radial *r = c->w->gl[part[i]].rg;
        for (int k = 0; k < (r->cone == CONE_HALF ? 1 : 2) && r->cone != CONE_NESTED; k++) {
            double f0 = creal(r->lf[k][0]), f1 = creal(r->lf[k][1]);
            thr_iv L = iv_add(c->lc[4 * part[i] + k],
                              iv_add(iv_mul(iv_k(f0), X), iv_mul(iv_k(f1), S)));
            if (!(L.lo <= 0.0 && L.hi >= 0.0))
                continue;
            len += f0 != 0.0 ? fabs(f1 / f0) * (s1 - s0) * (1.0 + 1e-9) + 1e-14 * c->w->R : wd;
        }
    }
    return wd > 0.0 ? fmin(1.0, len / wd) : 1.0;
}

/* Whether the box [x0, x1] x [s0, s1] (relative) may hold an event of
 * the threshold's curve: for some channel, 0.04045 is in E's range and,
 * unless a cut meets the box (a stop line or circle, the window's side,
 * a kink of the filter, a radial filter's circle), 0 is in dE/dx's.
 * *xfree: the composite does not depend on x (every gradient painting is
 * linear along y only, or the channel that may hold an event is constant
 * along x on the box: a radial layer padded beyond its last stop over a
 * linear one along y), so the curve is rows, each an event, and the box
 * is halved along y only.  cut0: a piece may cross the box (a cut).  wid
 * (may be NULL): the widest of the channels' ranges of E on the box.  un
 * (may be NULL, with wid): each channel's range merged into un[ch] and
 * un[3 + ch], for a caller that takes the box in several cases and needs
 * the range over all of them (thr_box_at). */
static int thr_box(const thr_ctx *c, double x0, double x1, double s0, double s1, int cut0,
                   int *xfree, double *wid, double *lip, double *un)
{
    const worker *w = c->w;
    *xfree = 1;
    for (int k = 0; k < c->nst; k++)
        if (c->st[k].op == AA_FOLD_LAYER && c->sl[k] >= 0) {
            const gen_layer *g = &w->gl[c->sl[k]];
            *xfree &= g->gp && g->gp->tx == 0.0;
        }
    thr_iv X = {x0, x1}, S = {s0, s1};
    thr_jet *a = c->scr, (*ac)[3] = (thr_jet(*)[3])(c->scr + w->ngl), *t = c->scr + 4 * w->ngl;
    int cut = cut0 || x0 <= -w->R || x1 >= w->R;
    for (int k = 0; k < c->nk; k++)
        cut |= c->kink[k] >= x0 && c->kink[k] <= x1;
    if (w->radial) {
        double nx = fmax(0.0, fmax(x0, -x1)), ny = fmax(0.0, fmax(s0, -s1));
        double fx = fmax(fabs(x0), fabs(x1)), fy = fmax(fabs(s0), fabs(s1));
        cut |= hypot(nx, ny) * (1.0 - 1e-15) <= w->R && hypot(fx, fy) * (1.0 + 1e-15) >= w->R;
    }
    /* the first layer whose stops cut the box (at most THR_SEG - 1 times)
     * is taken one segment of its t at a time: a jump of its paint at a
     * sharp stop or a period's end is then no threshold's place, and the
     * stop lines bounding the segment are cuts only where E on them may
     * be 0.04045 */
    double brk[THR_SEG + 1], elo[3] = {INFINITY, INFINITY, INFINITY};
    double ehi[3] = {-INFINITY, -INFINITY, -INFINITY};
    int split = -1, nbrk = 0, hit = 0, flat = 0, part[THR_PART], np = 0;
    /* ln: the one cone layer lnl whose tangent line crosses the box, its
     * derivative times u (thr_cone_line); a second one is a cut */
    thr_line ln = {0, 0.0, {0.0, 0.0}};
    int lnl = -1;
    for (int l = 0; l < w->ngl; l++) {
        int bad = 0;
        if (!c->used[l])
            continue;
        thr_line li = {0, 0.0, {0.0, 0.0}};
        t[l] = thr_t(c, l, X, S, &bad, &c->paint[l], &li);
        cut |= bad;
        if (li.on && lnl >= 0)
            cut = 1;
        else if (li.on)
            lnl = l, ln = li;
        if (c->paint[l] == 2 && np == THR_PART) { /* too many painting part of it: kept */
            if (wid)
                *wid = INFINITY;
            if (lip)
                *lip = INFINITY;
            return 1;
        }
        if (c->paint[l] == 2)
            part[np++] = l;
        const gen_layer *g = &w->gl[l];
        double ta = t[l].v.lo, tb = t[l].v.hi;
        double pad = 8.0 * DBL_EPSILON * (1.0 + fmax(fabs(ta), fabs(tb)));
        if (split >= 0 || !c->paint[l] || !(ta > -INFINITY && tb < INFINITY))
            continue;
        size_t nb = grad_taus(g->gp ? g->gp : &g->rg->plane, ta - pad, tb + pad, c->buf, c->cap);
        if (nb == 0 || nb >= THR_SEG)
            continue;
        split = l, nbrk = (int)nb;
        memcpy(brk + 1, c->buf, nb * sizeof *brk);
        qsort(brk + 1, nb, sizeof *brk, truth_cmp_double);
        brk[0] = -INFINITY, brk[nb + 1] = INFINITY;
    }
    /* a cone layer painting part of the box is taken painted and not
     * (bit k of m: part[k] painted), each folded, as a piece's layer is
     * taken covered and not (thr_box_at); the box is cut */
    unsigned char *on = c->paint;
    double mw[3] = {0.0, 0.0, 0.0}; /* each channel's widest range of one case */
    for (int m = 0; m < 1 << np && !(hit && !wid); m++) {
        double mlo[3] = {INFINITY, INFINITY, INFINITY}, mhi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int k = 0; k < np; k++)
            on[part[k]] = (m >> k) & 1 ? 2 : 0;
        int sp = split >= 0 && on[split] ? split : -1;
        /* the tangent line of layer lnl: a cut where it is not painted;
         * where it is, every other layer's derivative is taken times u
         * in [0, U] (as lnl's is), and the line a cut only where E on it
         * (the layer's paint at its t there) may be 0.04045: else the
         * curve meets it nowhere on the box, and where u > 0, u E' has
         * E''s sign */
        int lon = lnl >= 0 && on[lnl];
        thr_iv us = {0.0, ln.U};
        for (int j = 0; j <= (sp >= 0 ? nbrk : 0); j++) {
            int cj = cut || (lnl >= 0 && !lon);
            thr_jet ts = {{0.0, 0.0}, {0.0, 0.0}};
            for (int l = 0; l < w->ngl; l++) {
                thr_jet p[4];
                if (!c->used[l])
                    continue;
                if (!on[l]) { /* not painted: transparent */
                    a[l] = j_k(iv_k(0.0));
                    for (int ch = 0; ch < c->nch; ch++)
                        ac[l][ch] = a[l];
                    continue;
                }
                if (l == sp) {
                    ts = t[l];
                    ts.v.lo = fmax(ts.v.lo, brk[j]), ts.v.hi = fmin(ts.v.hi, brk[j + 1]);
                    if (!(ts.v.lo <= ts.v.hi))
                        goto next;
                    thr_affine(&w->gl[l], ts, p);
                } else
                    thr_paint(c, l, t[l], p, &cj);
                for (int k = 0; k < 4 && lon && l != lnl; k++)
                    p[k].d = iv_mul(p[k].d, us);
                a[l] = p[3];
                for (int ch = 0; ch < c->nch; ch++)
                    ac[l][ch] = j_mul(p[3], p[ch]);
            }
            thr_jet E[3];
            thr_fold(c, a, ac, E);
            /* the split layer's stop lines that bound the segment on the box:
             * a cut where the curve may meet one, E there (the layer's paint
             * at that t, from the segment's side) holding 0.04045 */
            for (int e = 0; e < 2 && sp >= 0 && !cj; e++) {
                double b = e ? brk[j + 1] : brk[j], tm = 0.5 * (ts.v.lo + ts.v.hi);
                if (b != (e ? ts.v.hi : ts.v.lo))
                    continue; /* not met on the box */
                thr_jet p[4], Eb[3], tb = {{b, b}, {0.0, 0.0}};
                thr_jet keep = a[split], kc[3];
                thr_affine_at(&w->gl[split], tb, tm, p);
                a[split] = p[3];
                for (int ch = 0; ch < c->nch; ch++)
                    kc[ch] = ac[split][ch], ac[split][ch] = j_mul(p[3], p[ch]);
                thr_fold(c, a, ac, Eb);
                a[split] = keep;
                for (int ch = 0; ch < c->nch; ch++) {
                    ac[split][ch] = kc[ch];
                    cj |= Eb[ch].v.lo <= 0.04045 && Eb[ch].v.hi >= 0.04045;
                }
            }
            if (lon && !cj) { /* E on the tangent line, from its painted side */
                thr_jet p[4], El[3], keep = a[lnl], kc[3];
                int lc = 0;
                thr_paint(c, lnl, j_k(ln.tl), p, &lc);
                a[lnl] = p[3];
                for (int ch = 0; ch < c->nch; ch++)
                    kc[ch] = ac[lnl][ch], ac[lnl][ch] = j_mul(p[3], p[ch]);
                thr_fold(c, a, ac, El);
                a[lnl] = keep;
                for (int ch = 0; ch < c->nch; ch++) {
                    ac[lnl][ch] = kc[ch];
                    cj |= El[ch].v.lo <= 0.04045 && El[ch].v.hi >= 0.04045;
                }
            }
            for (int ch = 0; ch < c->nch && wid; ch++) {
                elo[ch] = fmin(elo[ch], E[ch].v.lo), ehi[ch] = fmax(ehi[ch], E[ch].v.hi);
                mlo[ch] = fmin(mlo[ch], E[ch].v.lo), mhi[ch] = fmax(mhi[ch], E[ch].v.hi);
            }
            for (int ch = 0; ch < c->nch && lip; ch++) {
                double d = fmax(fabs(E[ch].d.lo), fabs(E[ch].d.hi));
                *lip = split >= 0 || np > 0 || !(d <= INFINITY) ? INFINITY : fmax(*lip, d);
            }
            for (int ch = 0; ch < c->nch && !hit; ch++) {
                thr_jet e = E[ch];
                if (!(e.v.lo <= 0.04045 && e.v.hi >= 0.04045))
                    continue;
                if (!cj && (e.d.lo > 0.0 || e.d.hi < 0.0))
                    continue;
                hit = 1;
                flat = !lon && e.d.lo >= -1e-300 && e.d.hi <= 1e-300;
            }
            if (hit && !wid) {
                *xfree |= flat;
                return 1;
            }
        next:;
        }
        for (int ch = 0; ch < c->nch && wid; ch++)
            if (mhi[ch] >= mlo[ch])
                mw[ch] = fmax(mw[ch], mhi[ch] - mlo[ch]);
    }
    /* cone layers painting part of the box: a column's two rows s and m
     * are painted alike but where a tangent line (the half-plane's edge)
     * passes between them, over at most its x on the box's rows
     * (thr_cone_cross); there E may take the range of every case
     * together, elsewhere that of one case: wid their mean over [x0, x1] */
    double fr = np > 0 && wid ? thr_cone_cross(c, part, np, x0, x1, s0, s1) : 0.0;
    for (int ch = 0; ch < c->nch && wid; ch++) {
        double all = ehi[ch] - elo[ch];
        *wid = fmax(*wid, np > 0 ? fmin(all, mw[ch] + all * fr) : all);
        if (un)
            un[ch] = fmin(un[ch], elo[ch]), un[3 + ch] = fmax(un[3 + ch], ehi[ch]);
    }
    return hit;
}

/* Whether offset piece p is an evolute whose parameters reach the half of
 * [0, 1] next to a cubic's end where B' vanishes, evaluated there in a
 * factored form (offset.c, aa__offset_stop), whose Q x Q' (q0 q3 - q2 q1,
 * a constant) is not shown off 0: the evolute is then the curve itself
 * there (offset.c's stop_eval), not bounded by thr_offset_iv. */
static int thr_offset_stopped(const aa_piece *p)
{
    int stops = aa__offset_stops(&p->oc);
    double lo = fmin(p->ot0, p->ot1), hi = fmax(p->ot0, p->ot1), te, q[4];
    for (int e = 0; e < 2 && p->oc.evolute; e++) {
        if (!((stops >> e) & 1) || !(e ? hi >= 0.5 : lo < 0.5) ||
            !aa__offset_stop(&p->oc, e ? 1.0 : 0.0, &te, q))
            continue;
        double a = q[0] * q[3], c = q[2] * q[1];
        if (!(fabs(a - c) > 1e-12 * (fabs(a) + fabs(c))))
            return 1;
    }
    return 0;
}

/* Where local piece q lies against the window [-R, R]^2: 2 outside its
 * rows, -1 wholly left of it, 1 wholly right, 0 entering it. */
static int thr_piece_side(const worker *w, local_piece *q)
{
    double R = w->R;
    if (q->y1 <= -R || q->y0 >= R)
        return 2;
    if (q->offset)
        return truth_offset_side(q, -R, R, R);
    double lo, hi;
    if (q->conic) {
        double e = (double)(fabsl(q->ea) + fabsl(q->eb));
        lo = (double)q->x0 - e, hi = (double)q->x0 + e;
    } else { /* x0 + t (bx + t (ax + t dx)), t in [0, 1] */
        thr_iv T = {0.0, 1.0}, p = iv_k((double)q->dx);
        p = iv_add(iv_mul(p, T), iv_k((double)q->ax));
        p = iv_add(iv_mul(p, T), iv_k((double)q->bx));
        p = iv_add(iv_mul(p, T), iv_k((double)q->x0));
        lo = p.lo, hi = p.hi;
    }
    double m = 1e-12 * (R + fabs(lo) + fabs(hi));
    return hi < -R - m ? -1 : lo > R + m ? 1 : 0;
}

/* Whether no local piece enters the window [-R, R]^2 (each wholly left or
 * right of it, or outside its rows: the windings are then one over the
 * window): 1, the windings at the centre row into w->wind; 0 if pieces
 * enter it (thr_certify takes them box by box); -1 if an offset piece
 * that thr_offset_x does not bound enters it (thr_offset_stopped: left to
 * the scan). */
static int thr_window_clear(worker *w)
{
    int clear = 1;
    aa_strip_winding_left_at(w->strip, w->vc, 0.0, w->wind);
    for (size_t k = 0; k < w->nlp; k++) {
        local_piece *q = &w->lp[k];
        int side = thr_piece_side(w, q);
        if (side == 0 && q->offset && thr_offset_stopped(q->src))
            return -1;
        if (side == 0)
            clear = 0;
        if (side == -1 && 0.0 >= q->y0 && 0.0 < q->y1)
            w->wind[q->layer] += q->dir;
    }
    return clear;
}

/* ---- boxes that pieces cross (a window that edges enter) ----
 *
 * A layer none of whose pieces meets a box has one winding over it (the
 * box is connected), that at the box's centre: the pieces left of the
 * window (aa_strip_winding_left_at) and the local ones left of the box on
 * that row.  A layer whose piece may meet the box is covered on part of
 * it or not: its winding is taken 0 and 1 (outside and inside under
 * either fill rule), each combination of such layers folded
 * (aa_scene_fold), up to THR_UNSURE layers (else the box is kept as one
 * that may hold an event), and the box is cut: free only if 0.04045 is
 * outside E's range under every combination.  The steps of each winding
 * met are kept (THR_FOLDS, the oldest replaced). */
#define THR_UNSURE 3 /* most layers of unknown cover a box is folded for (2^3 folds) */
#define THR_FOLDS 16 /* the steps of this many windings kept, a pixel */

typedef struct thr_fc {
    int nst, *key, *sl;
    aa_fold_step *st;
    double base[3];
    unsigned char *used; /* per layer (ngl) */
} thr_fc;

typedef struct thr_cache {
    int n, next, nl;
    int *wind;
    const int *side; /* per local piece, thr_piece_side */
    double *rows;    /* per piece entering (c->pc's order): the rows last asked, */
    thr_iv *px;      /* and thr_piece_x there (thr_strip asks the same rows often) */
    thr_fc e[THR_FOLDS];
} thr_cache;

/* A long double as a range holding it: its double, moved out by an ulp. */
static thr_iv iv_ld(long double v)
{
    double d = (double)v;
    return iv_out(d, d);
}

/* c0 + T (c1 + T (c2 + T c3)) over the range T. */
static thr_iv thr_cubic_iv(long double c0, long double c1, long double c2, long double c3,
                           thr_iv T)
{
    thr_iv p = iv_ld(c3);
    p = iv_add(iv_mul(p, T), iv_ld(c2));
    p = iv_add(iv_mul(p, T), iv_ld(c1));
    return iv_add(iv_mul(p, T), iv_ld(c0));
}

/* a / b, b's range not holding 0: the quotients of the ends. */
static thr_iv iv_div(thr_iv a, thr_iv b)
{
    double p0 = a.lo / b.lo, p1 = a.lo / b.hi, p2 = a.hi / b.lo, p3 = a.hi / b.hi;
    if (p0 != p0 || p1 != p1 || p2 != p2 || p3 != p3)
        return (thr_iv){-INFINITY, INFINITY};
    return iv_out(thr_min(thr_min(p0, p1), thr_min(p2, p3)),
                  thr_max(thr_max(p0, p1), thr_max(p2, p3)));
}

/* cos (sn 0) or sin (sn 1) over T: f(m) within |f'(m)| h + h^2 / 2 (|f''|
 * <= 1), m T's middle and h its half width, each rounded up; the libm's
 * error (below an ulp of 1) and that of f'(m) times h (h at most a few
 * pi) within the 2^-48 added. */
static thr_iv iv_trig(thr_iv T, int sn)
{
    double m = 0.5 * (T.lo + T.hi), h = thr_max(m - T.lo, T.hi - m) * (1.0 + 0x1p-50);
    double v = sn ? sin(m) : cos(m), dv = sn ? cos(m) : sin(m);
    double r = (fabs(dv) * h + 0.5 * h * h) * (1.0 + 0x1p-50) + 0x1p-48;
    if (!(r < 2.0))
        return (thr_iv){-1.0, 1.0};
    return (thr_iv){thr_max(v - r, -1.0), thr_min(v + r, 1.0)};
}

/* The hull of two ranges. */
static thr_iv iv_hull(thr_iv a, thr_iv b)
{
    return (thr_iv){thr_min(a.lo, b.lo), thr_max(a.hi, b.hi)};
}

/* The point of offset curve oc (aabench.h, aa_offset_curve) at the
 * parameters T, mapped, in ranges (X, Y): B, B' and B'' by Horner (an
 * ellipse's from iv_trig), the offset B + d perp(B')/|B'| (each of
 * B'/|B'|'s coordinates kept in [-1, 1]), the evolute B + perp(B') |B'|^2
 * / (B' x B''), as offset.c's offset_eval; on the half of [0, 1] next to
 * a cubic's end te where B' vanishes (stops, aa__offset_stops' bits: the
 * halves split at 0.5 as offset_eval splits them) its factored form, Q =
 * (q0 + q1 t, q2 + q3 t), s = t - te, sg = 1 at te = 0 and -1 at 1: the
 * offset B + d sg perp(Q)/|Q|, the evolute B + s |Q|^2 perp(Q) / (Q x
 * Q').  0 (not had) where |B'|^2 (|Q|^2) or the evolute's denominator may
 * vanish on T. */
static int thr_offset_iv(const aa_offset_curve *oc, int stops, thr_iv T, thr_iv *X, thr_iv *Y)
{
    const double *b = oc->b;
    thr_iv B[2], U[2], V[2], P[2], L2, S = {0.0, 0.0};
    double te = 0.0, q[4] = {0};
    int stop = 0;
    if (oc->base == AA_OFFSET_CUBIC && stops && T.lo < 0.5 && T.hi >= 0.5) {
        thr_iv X2, Y2;
        if (!thr_offset_iv(oc, stops, (thr_iv){T.lo, 0.5 - 0x1p-54}, X, Y) ||
            !thr_offset_iv(oc, stops, (thr_iv){0.5, T.hi}, &X2, &Y2))
            return 0;
        *X = iv_hull(*X, X2), *Y = iv_hull(*Y, Y2);
        return 1;
    }
    if (oc->base == AA_OFFSET_ELLIPSE) {
        thr_iv C = iv_trig(T, 0), Sn = iv_trig(T, 1);
        for (int i = 0; i < 2; i++) {
            thr_iv p = iv_add(iv_mul(iv_k(b[2 + i]), C), iv_mul(iv_k(b[4 + i]), Sn));
            B[i] = iv_add(iv_k(b[i]), p);
            U[i] = iv_sub(iv_mul(iv_k(b[4 + i]), C), iv_mul(iv_k(b[2 + i]), Sn));
            V[i] = (thr_iv){-p.hi, -p.lo};
        }
    } else {
        stop = (stops & (T.lo < 0.5 ? 1 : 2)) && aa__offset_stop(oc, T.lo, &te, q);
        for (int i = 0; i < 2; i++) {
            const double *c = b + 4 * i;
            B[i] = thr_cubic_iv(c[0], c[1], c[2], c[3], T);
            if (stop) { /* U: Q, V: Q' */
                U[i] = iv_add(iv_k(q[2 * i]), iv_mul(iv_k(q[2 * i + 1]), T));
                V[i] = iv_k(q[2 * i + 1]);
            } else {
                U[i] = thr_cubic_iv(c[1], 2.0L * c[2], 3.0L * c[3], 0.0L, T);
                V[i] = thr_cubic_iv(2.0L * c[2], 6.0L * c[3], 0.0L, 0.0L, T);
            }
        }
        if (stop)
            S = iv_sub(T, iv_k(te));
    }
    L2 = iv_add(iv_sqr(U[0]), iv_sqr(U[1]));
    if (!(L2.lo > 0.0))
        return 0;
    if (!oc->evolute) {
        thr_iv L = iv_out(sqrt(L2.lo), sqrt(L2.hi)), N[2];
        thr_iv D = iv_k(stop && te != 0.0 ? -oc->d : oc->d);
        for (int i = 0; i < 2; i++) {
            N[i] = iv_div(U[i], L);
            N[i].lo = thr_max(N[i].lo, -1.0), N[i].hi = thr_min(N[i].hi, 1.0);
        }
        P[0] = iv_sub(B[0], iv_mul(D, N[1]));
        P[1] = iv_add(B[1], iv_mul(D, N[0]));
    } else {
        thr_iv c = iv_sub(iv_mul(U[0], V[1]), iv_mul(U[1], V[0]));
        if (!(c.lo > 0.0 || c.hi < 0.0))
            return 0;
        thr_iv r = iv_div(stop ? iv_mul(S, L2) : L2, c);
        P[0] = iv_sub(B[0], iv_mul(r, U[1]));
        P[1] = iv_add(B[1], iv_mul(r, U[0]));
    }
    const double *m = oc->m;
    *X = iv_add(iv_add(iv_mul(iv_k(m[0]), P[0]), iv_mul(iv_k(m[2]), P[1])), iv_k(m[4]));
    *Y = iv_add(iv_add(iv_mul(iv_k(m[1]), P[0]), iv_mul(iv_k(m[3]), P[1])), iv_k(m[5]));
    return X->lo == X->lo && Y->lo == Y->lo && X->hi == X->hi && Y->hi == Y->hi;
}

/* thr_piece_x for an offset piece: y runs one
 * way from ot0 (the top) to ot1 (no fold, cusp or turn of y inside), so
 * the parameters of the rows [a, b] lie between ta and tb, ta the root of
 * y = a (aa__offset_solve_d) moved towards ot0 until y there is shown
 * below a less the margin (or ta is ot0), tb likewise; x over them by
 * thr_offset_iv.  The margin, 1e-12 of the piece's absolute coordinates'
 * size and the window's, holds the rounding of its crossings (long
 * double, truth_local.c).  Unbounded where thr_offset_iv has nothing. */
static thr_iv thr_offset_x(const worker *w, const local_piece *q, double a, double b)
{
    const aa_piece *p = q->src;
    const aa_offset_curve *oc = &p->oc;
    thr_iv all = {-INFINITY, INFINITY}, X, Y, vc = iv_ld(q->vc);
    int stops = aa__offset_stops(oc);
    double dir = p->ot1 > p->ot0 ? 1.0 : -1.0, m = 1e-12 * (w->R + (double)q->oscale), t[2];
    for (int e = 0; e < 2; e++) {
        double s = e ? b : a, end = e ? p->ot1 : p->ot0, way = e ? dir : -dir;
        if (e ? !(s < q->y1) : !(s > q->y0)) {
            t[e] = end;
            continue;
        }
        double y = (double)(q->vc + s), pad = 0x1p-40 * fabs(p->ot1 - p->ot0);
        double t0 = aa__offset_solve_d(oc, 1, p->ot0, p->ot1, p->y0 - y, y);
        if (t0 != t0)
            return all;
        for (;;) {
            double tt = t0 + way * pad;
            if (!((end - tt) * way > 0.0)) {
                t[e] = end;
                break;
            }
            if (!thr_offset_iv(oc, stops, iv_k(tt), &X, &Y))
                return all;
            Y = iv_sub(Y, vc);
            if (e ? Y.lo > s + m : Y.hi < s - m) {
                t[e] = tt;
                break;
            }
            pad *= 256.0;
        }
    }
    if (!thr_offset_iv(oc, stops, (thr_iv){thr_min(t[0], t[1]), thr_max(t[0], t[1])}, &X,
                       &Y))
        return all;
    X = iv_sub(X, iv_ld(q->uc));
    return iv_out(X.lo - m, X.hi + m);
}

/* The x of local piece q (a line, a quadratic or cubic arc, a conic
 * piece, an offset piece: thr_offset_x) on its rows [a, b] (inside its own): a
 * range holding them.  Widened by 1e-12 of its coefficients' size for the
 * rounding of the piece's coordinates relative to the centre (long
 * double, about 1e-19 of them).  A polynomial piece's y(t) increases on
 * [0, 1] (pieces are split at the roots of y'): the parameters of the
 * rows [a, b] lie in [ta, tb], ta the root at a (truth_t_at) moved down
 * until y(ta) is shown below a (or ta is 0), tb likewise; x over [ta, tb]
 * by Horner in intervals.  A conic's x is x0 + ea c + eb sqrt((1 - c)(1
 * + c)), c = (ey - s) / er (truth_conic_part), in intervals over the rows. */
static thr_iv thr_piece_x(const worker *w, const local_piece *q, double a, double b)
{
    double R = w->R;
    thr_iv X;
    if (q->offset)
        return thr_offset_x(w, q, a, b);
    if (q->conic) {
        thr_iv S = {a, b}, one = iv_k(1.0);
        double er = (double)q->er;
        thr_iv C = iv_mul(iv_sub(iv_ld(q->ey), S), iv_out(1.0 / er, 1.0 / er));
        thr_iv P = iv_mul(iv_sub(one, C), iv_add(one, C));
        thr_iv Q = iv_out(sqrt(fmax(P.lo, 0.0)), sqrt(fmax(P.hi, 0.0)));
        X = iv_add(iv_add(iv_ld(q->x0), iv_mul(iv_ld(q->ea), C)), iv_mul(iv_ld(q->eb), Q));
        double m = 1e-12 * (R + fabs((double)q->x0) + fabs((double)q->ea) +
                            fabs((double)q->eb) + fabs((double)q->ey) + er);
        return iv_out(X.lo - m, X.hi + m);
    }
    double my = 1e-12 * (R + fabs((double)q->y0) + fabs((double)q->by) + fabs((double)q->ay) +
                         fabs((double)q->dy));
    double t[2];
    for (int e = 0; e < 2; e++) {
        double s = e ? b : a, t0 = (double)truth_t_at(q, s), pad = 0x1p-40;
        for (;;) {
            double tt = e ? t0 + pad : t0 - pad;
            if (e ? !(tt < 1.0) : !(tt > 0.0)) {
                t[e] = e ? 1.0 : 0.0;
                break;
            }
            thr_iv Y = thr_cubic_iv(q->y0, q->by, q->ay, q->dy, iv_k(tt));
            if (e ? Y.lo > s + my : Y.hi < s - my) {
                t[e] = tt;
                break;
            }
            pad *= 256.0;
        }
    }
    X = thr_cubic_iv(q->x0, q->bx, q->ax, q->dx, (thr_iv){t[0], t[1]});
    double m = 1e-12 * (R + fabs((double)q->x0) + fabs((double)q->bx) + fabs((double)q->ax) +
                        fabs((double)q->dx));
    return iv_out(X.lo - m, X.hi + m);
}

/* The steps of the composite under the windings wind (the cache's), NULL
 * if not had. */
static const thr_fc *thr_fold_of(const thr_ctx *c, const int *wind)
{
    thr_cache *h = c->cache;
    worker *w = c->w;
    size_t kb = (size_t)h->nl * sizeof *wind;
    for (int k = 0; k < h->n; k++)
        if (!memcmp(h->e[k].key, wind, kb))
            return h->e[k].nst < 0 ? NULL : &h->e[k];
    thr_fc *f = &h->e[h->next];
    h->next = (h->next + 1) % THR_FOLDS;
    if (h->n < THR_FOLDS)
        h->n++;
    memcpy(f->key, wind, kb);
    f->nst = aa_scene_fold(w->scene, wind, w->ngl, w->gl_layer, f->st, w->cap_fold, f->base);
    memset(f->used, 0, (size_t)w->ngl);
    for (int k = 0; k < f->nst; k++) {
        f->sl[k] = -1;
        for (int l = 0; l < w->ngl && f->st[k].op == AA_FOLD_LAYER; l++)
            if (w->gl[l].layer == f->st[k].layer)
                f->sl[k] = l;
        if (f->sl[k] >= 0)
            f->used[f->sl[k]] = 1;
    }
    return f->nst < 0 ? NULL : f; /* cannot happen: cap_fold is aa_scene_fold_cap's */
}

/* thr_box on a box of a window that pieces enter: its windings found
 * (the comment above), thr_box under each combination, a cut where a
 * piece may cross it; the box not resolved (kept) where more than
 * THR_UNSURE layers' cover is unknown.  wid: the widest of each
 * combination's ranges of E; cross (may be NULL, with wid): the range of E
 * over every combination together times the length of the pieces' x on the
 * box's rows within [x0, x1], where the cover may differ from row to row. */
static int thr_box_at(const thr_ctx *c, double x0, double x1, double s0, double s1, int *xfree,
                      double *wid, double *lip, double *cross)
{
    if (cross)
        *cross = 0.0;
    if (c->npc == 0)
        return thr_box(c, x0, x1, s0, s1, 0, xfree, wid, lip, NULL);
    worker *w = c->w;
    thr_cache *h = c->cache;
    int *wind = h->wind, unsure[THR_UNSURE], nu = 0, over = 0;
    double sm = 0.5 * (s0 + s1), xc = 0.0; /* the pieces' x over the rows, on the box */
    aa_strip_winding_left_at(w->strip, w->vc, sm, wind);
    for (size_t k = 0; k < w->nlp; k++) {
        const local_piece *q = &w->lp[k];
        if (sm >= q->y0 && sm < q->y1 && h->side[k] == -1)
            wind[q->layer] += q->dir;
    }
    for (int i = 0; i < c->npc; i++) {
        const local_piece *q = &w->lp[c->pc[i]];
        double a = fmax(s0, (double)q->y0), b = fmin(s1, (double)q->y1);
        if (!(a <= b))
            continue;
        thr_iv X;
        if (h->rows[2 * i] == a && h->rows[2 * i + 1] == b) {
            X = h->px[i];
        } else {
            X = h->px[i] = thr_piece_x(w, q, a, b);
            h->rows[2 * i] = a, h->rows[2 * i + 1] = b;
        }
        if (X.lo > x1)
            continue;
        if (X.hi < x0) {
            if (sm >= q->y0 && sm < q->y1)
                wind[q->layer] += q->dir;
            continue;
        }
        xc += fmin(X.hi, x1) - fmax(X.lo, x0);
        int seen = 0;
        for (int j = 0; j < nu; j++)
            seen |= unsure[j] == q->layer;
        if (!seen && nu == THR_UNSURE)
            over = 1;
        else if (!seen)
            unsure[nu++] = q->layer;
    }
    *xfree = 0;
    if (over) {
        if (wid)
            *wid = INFINITY;
        if (lip)
            *lip = INFINITY;
        return 1;
    }
    /* E's range over every case of the unsure layers together: where a
     * piece passes between two rows the cover changes, and E with it */
    int hit = 0;
    double un[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int m = 0; m < 1 << nu && !(hit && !wid); m++) {
        for (int j = 0; j < nu; j++)
            wind[unsure[j]] = (m >> j) & 1;
        const thr_fc *f = thr_fold_of(c, wind);
        if (!f) {
            if (wid)
                *wid = INFINITY;
            if (lip)
                *lip = INFINITY;
            return 1;
        }
        thr_ctx cc = *c;
        int xf = 0;
        cc.nst = f->nst, cc.st = f->st, cc.sl = f->sl;
        memcpy(cc.base, f->base, sizeof cc.base);
        cc.used = f->used;
        hit |= thr_box(&cc, x0, x1, s0, s1, nu > 0, &xf, wid, lip, wid ? un : NULL);
        if (nu == 0)
            *xfree = xf;
    }
    for (int ch = 0; ch < c->nch && wid && cross && nu > 0; ch++)
        *cross = fmax(*cross, (un[3 + ch] - un[ch]) * fmin(xc, x1 - x0));
    if (nu > 0 && lip)
        *lip = INFINITY; /* E jumps along a column the piece crosses */
    return hit;
}

static int cmp_pair(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return (p[0] > q[0]) - (p[0] < q[0]);
}

/* The slivers' rows sorted and merged where they meet or are closer than
 * THR_GAP of the window (the rows between join the sliver: its bound
 * covers every row in it, and fewer intervals cost fewer rows). */
static void thr_merge(worker *w)
{
    qsort(w->sliv, w->nsliv, 3 * sizeof *w->sliv, cmp_pair);
    size_t m = 0;
    double gap = THR_GAP * 2.0 * w->R;
    for (size_t k = 0; k < w->nsliv; k++) {
        if (m > 0 && w->sliv[3 * k] <= w->sliv[3 * m - 2] + gap) {
            w->sliv[3 * m - 2] = fmax(w->sliv[3 * m - 2], w->sliv[3 * k + 1]);
            continue;
        }
        w->sliv[3 * m] = w->sliv[3 * k], w->sliv[3 * m + 1] = w->sliv[3 * k + 1];
        m++;
    }
    w->nsliv = m;
}

/* The integral over x in [x0, x1] of a bound of |E(x, s) - E(x, m)| for
 * rows s and m in [a, b], times 2.3 (the decoding's largest slope): on
 * the box, b - a times the largest |dE/dy| where no layer's stop or
 * period's end crosses it (E is then smooth along each column), else the
 * width of E's range, a strip whose bound is still wide (a jump of the
 * paint at a sharp stop) halved in x up to THR_STRIP_DEPTH times; times the
 * box's width.  Where pieces pass the box (thr_box_at), E's range is each
 * cover's, the widest, except over the pieces' x on the box's rows, where
 * the cover may differ between s and m: there the range over every cover
 * together (thr_box_at's cross). */
static double thr_strip(const thr_ctx *c, double x0, double x1, double a, double b, int depth)
{
    thr_ctx cy = *c;
    double wid = 0.0, lip = 0.0, xm = 0.5 * (x0 + x1);
    int xfree;
    cy.dy = 1;
    double cross;
    thr_box_at(&cy, x0, x1, a, b, &xfree, &wid, &lip, &cross);
    double d = fmin(wid, (b - a) * lip);
    if (d > 1e-6 && depth < THR_STRIP_DEPTH && xm > x0 && xm < x1)
        return thr_strip(c, x0, xm, a, b, depth + 1) + thr_strip(c, xm, x1, a, b, depth + 1);
    return 2.3 * (d * (x1 - x0) + cross);
}

/* The half chord of the filter's mask at row s, 0 outside it. */
static double thr_chord(double R, double s)
{
    double q = (R - s) * (R + s);
    return q > 0.0 ? sqrt(q) : 0.0;
}

/* A sliver's bound of |F(s) - F(m)| for rows s and m in [a, b] (m the
 * middle of an interval inside it: any row) under a radial filter, F(s)
 * = int dec(E(x, s)) w(x, s) dx (truth.c's opening comment, "several
 * gradients"):
 *   |F(s) - F(m)| <= int |w(x, s) - w(x, m)| dec(E(x, s)) dx
 *                    + int w(x, m) |dec(E(x, s)) - dec(E(x, m))| dx.
 * The first: dec(E) <= 1, and w = W(d) with |W'| <= L inside the mask
 * and a drop J at its edge (aa_filter_radial_slope): |w(x, s) - w(x, m)|
 * <= L |s - m| where both rows hold x in their chords (|d(x, s) - d(x,
 * m)| <= |s - m|), at most J + L |s - m| where one does (the other point
 * lies outside the mask, within |s - m| of its edge), 0 where neither;
 * those x lie in the widest chord, 2 cmax long, and the rows' chords
 * differ on at most 2 (cmax - cmin) (c(s) = sqrt(R^2 - s^2) is concave:
 * least at a or b, largest at 0 if the rows hold it, else at a or b).
 * The second: on each of 256 strips across the window, w(x, m) is at
 * most W at the strip's point nearest the centre on the rows [a, b] (W
 * does not increase), times the strip's thr_strip (2.3 |E(x, s) - E(x,
 * m)| over it) and the decoding's step 2.4e-9 times its width; a strip
 * outside the mask weighs 0 and is skipped. */
static double thr_radial_sliver(worker *w, const thr_ctx *c, double a, double b)
{
    double R = w->R, L, J;
    if (!aa_filter_radial_slope(w->f, &L, &J))
        return INFINITY;
    double h = b - a, ca = thr_chord(R, a), cb = thr_chord(R, b);
    double cmax = a <= 0.0 && b >= 0.0 ? R : fmax(ca, cb);
    double dc = cmax - fmin(ca, cb) + 4.0 * DBL_EPSILON * R; /* with the roots' rounding */
    double first = L * h * 2.0 * cmax + J * 2.0 * dc;
    double ny = a <= 0.0 && b >= 0.0 ? 0.0 : fmin(fabs(a), fabs(b)), second = 0.0;
    for (int i = 0; i < 256; i++) {
        double x0 = -R + 2.0 * R * i / 256, x1 = -R + 2.0 * R * (i + 1) / 256;
        double nx = x0 <= 0.0 && x1 >= 0.0 ? 0.0 : fmin(fabs(x0), fabs(x1));
        /* moved in by 1e-14 of itself: W there bounds W at the point */
        double wk = aa_filter_weight2(w->f, nx * (1.0 - 1e-14), ny * (1.0 - 1e-14));
        if (!(wk > 0.0))
            continue;
        second += wk * (thr_strip(c, x0, x1, a, b, 0) + (x1 - x0) * 2.4e-9);
    }
    return (first + second) * (1.0 + 1e-9);
}

/* The boxes of thr_certify, its context set up. */
static int thr_boxes(worker *w, thr_ctx *cp)
{
    thr_ctx c = *cp;
    double R = w->R;
    double side = THR_SIDE * 2.0 * R, box[4 * 256];
    int top = 0;
    size_t nbox = 0;
    box[0] = -R, box[1] = R, box[2] = w->pts[0], box[3] = w->pts[w->npts - 1];
    top = 1;
    w->nsliv = 0;
    int spent = 0; /* the work limit reached: what is left is kept whole */
    while (top > 0) {
        double *b = &box[4 * --top];
        double x0 = b[0], x1 = b[1], s0 = b[2], s1 = b[3];
        int xfree = 0;
        if (!spent && ++nbox > (w->thr_cone ? THR_CONE_BOXES : THR_BOXES))
            spent = 1;
        if (!spent && !thr_box_at(&c, x0, x1, s0, s1, &xfree, NULL, NULL, NULL))
            continue;
        double xm = 0.5 * (x0 + x1), sm = 0.5 * (s0 + s1);
        int byx = !xfree && x1 - x0 >= THR_ASPECT * (s1 - s0);
        int leaf = spent || top + 2 > 256 || s1 - s0 <= side ||
                   (byx ? !(xm > x0 && xm < x1) : !(sm > s0 && sm < s1));
        if (!leaf) {
            double *l = &box[4 * top++], *h = &box[4 * top++];
            l[0] = x0, l[1] = byx ? xm : x1, l[2] = s0, l[3] = byx ? s1 : sm;
            h[0] = byx ? xm : x0, h[1] = x1, h[2] = byx ? s0 : sm, h[3] = s1;
            continue;
        }
        if (w->nsliv == w->cap_sliv) {
            if (w->cap_sliv >= THR_LEAVES) { /* merged; past half full, the rest kept whole */
                thr_merge(w);
                spent |= w->nsliv > THR_LEAVES / 2;
            } else {
                size_t cap = w->cap_sliv ? 2 * w->cap_sliv : 16;
                double *p = realloc(w->sliv, 3 * cap * sizeof *p);
                if (!p)
                    return aa_fail(AA_ENOMEM, "out of memory for the threshold's slivers");
                w->sliv = p, w->cap_sliv = cap;
            }
        }
        w->sliv[3 * w->nsliv] = s0, w->sliv[3 * w->nsliv + 1] = s1;
        w->nsliv++;
    }
    if (w->nsliv == 0)
        return AA_OK;
    thr_merge(w);
    if (w->nsliv > THR_SLIVERS) { /* too many: one from the first to the last */
        w->sliv[1] = w->sliv[3 * w->nsliv - 2];
        w->nsliv = 1;
    }
    /* Each sliver's rows: |F(s) - F(m)| per unit of height, m its middle,
     * at most twice 2 R times the weight's peak (at the centre for every
     * filter here; |F| <= 2 R times it).  A radial filter: the weight's
     * change and the strips' (thr_radial_sliver).  The box: F(s) - F(m) is the
     * integral over the row of dec(E(x, s)) - dec(E(x, m)), at most 2.3
     * |E(x, s) - E(x, m)| (the decoding's slope is below 2.3 on [0, 1])
     * plus 2.4e-9 (its step at the threshold), and |E(x, s) - E(x, m)|
     * is bounded on 256 strips across the window (thr_strip).  A
     * separable filter: F = w(s) G(s), the sliver taken as G(m) times the
     * weight's integral over it (integrate_intervals), whose error is at
     * most the weight's peak times |G(s) - G(m)|, the box's bound times
     * the weight's peak again (|w(x)| under the row's integral). */
    double w0 = w->box || w->radial ? 1.0 : aa_filter_weight(w->f, 0.0);
    double pk = w->box ? 1.0 : w->radial ? aa_filter_weight2(w->f, 0.0, 0.0) : w0 * w0;
    double crude = 4.0 * R * fabs(pk);
    for (size_t k = 0; k < w->nsliv; k++) {
        double a = w->sliv[3 * k], b = w->sliv[3 * k + 1], wid = 0.0;
        w->sliv[3 * k + 2] = crude;
        if (w->radial) {
            w->sliv[3 * k + 2] = fmin(crude, thr_radial_sliver(w, &c, a, b));
            continue;
        }
        for (int i = 0; i < 256; i++)
            wid += thr_strip(&c, -R + 2.0 * R * i / 256, -R + 2.0 * R * (i + 1) / 256, a, b, 0);
        w->sliv[3 * k + 2] = fmin(crude, fabs(pk) * (wid + 2.0 * R * 2.4e-9) * (1.0 + 1e-9));
    }
    /* a cone-case layer's tangent line that the threshold's curve touches
     * (a circle of one t touches it) takes boxes without end about that
     * point: past the work limit, or slivers bounded above THR_CONE_LEFT
     * in all, the window is left to the scan (thr_heights) */
    double sum = 0.0;
    for (size_t k = 0; k < w->nsliv; k++)
        sum += (w->sliv[3 * k + 1] - w->sliv[3 * k]) * w->sliv[3 * k + 2];
    if (w->thr_cone && (spent || !(sum <= THR_CONE_LEFT))) {
        w->nsliv = 0, w->thr_left = 1;
        return AA_OK;
    }
    int st = AA_OK;
    for (size_t k = 0; k < w->nsliv && !st; k++) {
        double a = w->sliv[3 * k], b = w->sliv[3 * k + 1];
        if ((st = add_point(w, a)) || (st = add_point(w, b)))
            return st;
    }
    return AA_OK;
}

/* thr_certify in a window that pieces enter: the
 * pieces that enter it, room for the steps of THR_FOLDS windings, and the
 * boxes, each with its own windings (thr_box_at). */
static int thr_certify_edges(worker *w, thr_ctx *c, int *taken)
{
    thr_cache h = {0};
    int nl = aa_scene_layer_count(w->scene), cf = w->cap_fold;
    size_t per = (size_t)cf * sizeof(aa_fold_step) + (size_t)(cf + nl) * sizeof(int) +
                 (size_t)w->ngl;
    per = (per + 15) & ~(size_t)15; /* each entry's steps aligned */
    size_t ints = ((size_t)(nl + 1) + 2 * w->nlp) * sizeof(int);
    ints = (ints + 15) & ~(size_t)15;
    char *mem = malloc(THR_FOLDS * per + ints + w->nlp * (2 * sizeof(double) + sizeof(thr_iv)));
    if (!mem)
        return aa_fail(AA_ENOMEM, "out of memory for the threshold's boxes");
    h.nl = nl;
    for (int k = 0; k < THR_FOLDS; k++) {
        char *m = mem + k * per;
        h.e[k].st = (aa_fold_step *)(void *)m;
        h.e[k].sl = (int *)(void *)(m + (size_t)cf * sizeof(aa_fold_step));
        h.e[k].key = h.e[k].sl + cf;
        h.e[k].used = (unsigned char *)(h.e[k].key + nl);
    }
    h.wind = (int *)(void *)(mem + THR_FOLDS * per);
    int *pc = h.wind + nl + 1, *side = pc + w->nlp, npc = 0;
    for (size_t k = 0; k < w->nlp; k++)
        if ((side[k] = thr_piece_side(w, &w->lp[k])) == 0)
            pc[npc++] = (int)k;
    h.side = side;
    h.rows = (double *)(void *)(mem + THR_FOLDS * per + ints);
    h.px = (thr_iv *)(void *)(h.rows + 2 * w->nlp);
    for (size_t k = 0; k < 2 * w->nlp; k++)
        h.rows[k] = NAN;
    c->npc = npc, c->pc = pc, c->cache = &h;
    *taken = 1;
    int st = thr_boxes(w, c);
    free(mem);
    return st;
}

/* thr_certify in a window that no piece enters, its steps (c->nst, the
 * window's) had. */
static int thr_certify_clear(worker *w, thr_ctx *c, int *taken)
{
    *taken = 1;
    for (int k = 0; k < c->nst; k++) {
        w->fold_sl[k] = -1;
        for (int l = 0; l < w->ngl && w->fold[k].op == AA_FOLD_LAYER; l++)
            if (w->gl[l].layer == w->fold[k].layer)
                w->fold_sl[k] = l;
    }
    c->sl = w->fold_sl;
    for (int k = 0; k < c->nst; k++)
        if (c->st[k].op == AA_FOLD_LAYER && c->sl[k] >= 0)
            c->used[c->sl[k]] = 1;
    return thr_boxes(w, c);
}

/* The certified heights (the opening comment, "several gradients"): the
 * window's rows between its first and last breakpoints halved into boxes
 * until each is shown free of events (thr_box) or no side is above
 * THR_SIDE of the window; the rows of those kept become slivers, their
 * ends breakpoints.  edges: pieces enter the window (thr_window_clear),
 * each box takes its windings (thr_box_at).  *taken is 0 if the pixel is
 * not of the kind it takes (the composite's steps not had). */
static int thr_certify(worker *w, int nch, int edges, int *taken)
{
    thr_ctx c = {0};
    c.w = w, c.nch = nch, c.st = w->fold, c.buf = w->gbuf, c.cap = 64;
    *taken = 0;
    c.nk = w->f->type->kinks(w->f->spec.v, c.kink);
    size_t n = (size_t)w->ngl;
    char *mem = malloc(n * (6 * sizeof(thr_iv) + 5 * sizeof(thr_jet)) + 2 * n);
    if (!mem)
        return aa_fail(AA_ENOMEM, "out of memory for the threshold's boxes");
    thr_iv *q0 = (thr_iv *)(void *)mem, U = iv_k(w->uc), V = iv_k(w->vc);
    c.lc = q0 + 2 * n;
    c.scr = (thr_jet *)(void *)(c.lc + 4 * n);
    c.used = (unsigned char *)(c.scr + 5 * n);
    c.paint = c.used + n;
    memset(c.used, 0, n);
    for (int l = 0; l < w->ngl; l++) {
        const gen_layer *g = &w->gl[l];
        const grad_radial *r = g->rg;
        for (int k = 0; r && r->cone && k < 2; k++) { /* the cone's forms at the centre */
            const double complex *f = r->cone == CONE_NESTED ? r->lf[0] : r->lf[k];
            int im = k && r->cone == CONE_NESTED;
            double f0 = im ? cimag(f[0]) : creal(f[0]), f1 = im ? cimag(f[1]) : creal(f[1]);
            double f2 = im ? cimag(f[2]) : creal(f[2]);
            c.lc[4 * l + k] = iv_add(iv_add(iv_mul(iv_k(f0), U), iv_mul(iv_k(f1), V)), iv_k(f2));
        }
        if (g->gp) {
            q0[2 * l] = iv_add(iv_add(iv_mul(iv_k(g->gp->tx), U), iv_mul(iv_k(g->gp->ty), V)),
                               iv_k(g->gp->t0));
            continue;
        }
        const double *i = g->rg->inv;
        q0[2 * l] = iv_sub(iv_add(iv_add(iv_mul(iv_k(i[0]), U), iv_mul(iv_k(i[2]), V)), iv_k(i[4])),
                           iv_k(g->rg->fx));
        q0[2 * l + 1] = iv_sub(
            iv_add(iv_add(iv_mul(iv_k(i[1]), U), iv_mul(iv_k(i[3]), V)), iv_k(i[5])),
            iv_k(g->rg->fy));
    }
    c.q0 = q0;
    int st = AA_OK;
    if (edges)
        st = thr_certify_edges(w, &c, taken);
    else if ((c.nst = aa_scene_fold(w->scene, w->wind, w->ngl, w->gl_layer, w->fold,
                                    w->cap_fold, c.base)) >= 0)
        st = thr_certify_clear(w, &c, taken);
    free(mem);
    return st;
}

/* If the rows [a, b] lie in a sliver of thr_certify, its bound of |F(s) -
 * F(m)|; else -1. */
static double thr_in_sliver(const worker *w, double a, double b)
{
    for (size_t k = 0; k < w->nsliv; k++)
        if (a >= w->sliv[3 * k] && b <= w->sliv[3 * k + 1])
            return w->sliv[3 * k + 2];
    return -1.0;
}

/* Where layers of different t mix, the heights at which the threshold's
 * curve is tangent to a row or crosses another of the row's cuts (truth.c's
 * opening comment, "several gradients"): between the breakpoints, rows at
 * THR_ROWS per window height and just inside each interval's ends; where
 * two consecutive rows' signatures differ, the height where it changes
 * bisected to rounding and made a breakpoint, a turning point where the
 * total count changes by two (a tangency).  Not certified: two crossings
 * that appear and vanish between two scan rows go unseen.  Appended to the
 * breakpoints, sorted again. */
/* Whether anything in the scene can be seen through: a layer's alpha, a
 * group's opacity or a gradient stop's opacity below 1.  Without, the
 * composite at each point is the paint of the front layer painting there,
 * of one t, so no span mixes and thr_heights has nothing to find. */
static int scene_translucent(const worker *w)
{
    const aa_scene *s = w->scene;
    for (int k = 0; k < aa_scene_layer_count(s); k++)
        if (aa_scene_layer_alpha(s, k) < 1.0)
            return 1;
    for (int g = 0; g < aa_scene_group_count(s); g++)
        if (aa_scene_group_opacity(s, g) < 1.0)
            return 1;
    for (int k = 0; k < w->ngl; k++)
        for (int i = 0; i < w->gl[k].nstops; i++)
            if (w->gl[k].stops[i].opacity < 1.0)
                return 1;
    return 0;
}

/* Once a render: whether its layers are not all of one t and something is
 * translucent (thr_on), whether thr_certify takes the scene (thr_cert: no
 * field), and whether a layer is of the cone case (thr_cone). */
static void thr_setup(worker *w)
{
    int mixed = 0;
    for (int k = 1; k < w->ngl && !mixed; k++)
        mixed = !gen_same_t(&w->gl[0], &w->gl[k]);
    w->thr_on = mixed && scene_translucent(w);
    w->thr_cert = !aa_scene_field(w->scene, NULL, NULL, NULL);
    w->thr_cone = 0;
    for (int k = 0; k < w->ngl; k++)
        w->thr_cone |= w->gl[k].rg && w->gl[k].rg->cone;
}

/* The breakpoints sorted, each once. */
static void thr_sort(worker *w)
{
    qsort(w->pts, w->npts, sizeof *w->pts, truth_cmp_double);
    size_t m = 1;
    for (size_t k = 1; k < w->npts; k++)
        if (w->pts[k] > w->pts[m - 1])
            w->pts[m++] = w->pts[k];
    w->npts = m;
}

static int thr_heights(worker *w, int nch)
{
    w->nsliv = 0;
    if (!w->thr_on || w->npts < 2)
        return AA_OK;
    double found[THR_EVENTS];
    int nfound = 0, any = 0, taken = 0;
    int clear = w->thr_cert ? thr_window_clear(w) : -1;
    if (clear >= 0) {
        size_t n0 = w->npts;
        w->thr_left = 0;
        int st = thr_certify(w, nch, !clear, &taken);
        if (st)
            return st;
        if (taken && !w->thr_left) {
            if (w->npts > n0)
                thr_sort(w);
            return AA_OK;
        }
    }
    w->scanned++;
    thr_sig *a = malloc(3 * sizeof *a);
    if (!a)
        return aa_fail(AA_ENOMEM, "out of memory for the threshold's scan");
    thr_sig *sa = &a[0], *sb = &a[1], *sm = &a[2];
    for (size_t k = 0; k + 1 < w->npts && nfound < THR_EVENTS; k++) {
        double p = w->pts[k], q = w->pts[k + 1], d = 1e-9 * (q - p);
        int m = (int)ceil(THR_ROWS * (q - p) / (2.0 * w->R));
        if (m < 1)
            m = 1;
        double ya = p + d;
        thr_row(w, ya, nch, sa);
        for (int i = 1; i <= m + 1 && nfound < THR_EVENTS; i++) {
            double yb = i <= m ? p + (q - p) * (i - 0.5) / m : q - d;
            thr_row(w, yb, nch, sb);
            if (sa->n > 0 || sb->n > 0)
                any = 1;
            /* every change between ya and yb, lowest first */
            while (sa->n >= 0 && sb->n >= 0 && !thr_same(sa, sb) && nfound < THR_EVENTS) {
                double l = ya, h = yb;
                while (h - l > 4.0 * DBL_EPSILON * fmax(1.0, fabs(l))) {
                    double c = 0.5 * (l + h);
                    if (!(c > l && c < h))
                        break;
                    thr_row(w, c, nch, sm);
                    if (sm->n < 0)
                        break;
                    if (thr_same(sm, sa))
                        l = c;
                    else
                        h = c;
                }
                double e = 0.5 * (l + h);
                thr_row(w, h, nch, sm);
                if (sm->n < 0)
                    break;
                /* a change within THR_NEAR of a breakpoint is taken as
                 * that breakpoint's own (rows that close to a tangent stop
                 * circle carry row bounds of 1.2e-12: a pixel of
                 * test_many_layers_mixed once went over 1e-12) */
                if (e - p > THR_NEAR * w->R && q - e > THR_NEAR * w->R) {
                    found[nfound++] = e;
                    int dt = thr_total(sm) - thr_total(sa);
                    if (sm->n == sa->n && (dt == 2 || dt == -2))
                        note_turn(w, e);
                }
                ya = h;
                *sa = *sm;
            }
            ya = yb;
            *sa = *sb;
        }
    }
    free(a);
    if (!any || nfound == 0)
        return AA_OK;
    int st = AA_OK;
    for (int k = 0; k < nfound && !st; k++)
        st = add_point(w, found[k]);
    if (st)
        return st;
    thr_sort(w);
    return AA_OK;
}

static int reserve_workspace(worker *w, size_t npts)
{
    if (npts + 64 <= w->limit)
        return AA_OK;
    size_t limit = 2 * (npts + 64);
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(limit);
    if (!ws)
        return aa_fail(AA_ENOMEM, "out of memory for a quadrature workspace");
    gsl_integration_workspace_free(w->ws);
    w->ws = ws;
    w->limit = limit;
    return AA_OK;
}

/* Integrate one non-uniform pixel; writes its channels and error bound. */
static int integrate_pixel(worker *w, int grey, double *value, double *bound)
{
    size_t n;
    const aa_piece *const *local = aa_strip_local(w->strip, &n);
    int st;
    w->nxmeet = 0;
    if (w->grad && (n > TRUTH_MAX_PAIRS || w->all_crowd)) {
        /* gradient paint in a crowded window: the sum over spans, with the
         * crowd path's sweep for the meetings (truth.c's opening comment) */
        if (n > GRAD_CROWD_MAX)
            return aa_fail(AA_EINVAL, "pixel (%g, %g): %zu pieces near it in a scene with "
                                      "gradient paint, more than %d (each height of the "
                                      "reference's sum over spans costs every piece's crossing "
                                      "and its span's quadrature): refused; sample it with "
                                      "point, supersample or jitter",
                           w->uc - 0.5, w->vc - 0.5, n, GRAD_CROWD_MAX);
        if ((st = crowd_events(&w->crowd, w->scene, w->strip, w->f, w->uc, w->vc, local, n,
                               &w->xmeet, &w->nxmeet)))
            return st;
    } else if (n > TRUTH_MAX_PAIRS || w->all_crowd) {
        st = crowd_pixel(&w->crowd, w->scene, w->strip, w->f, w->uc, w->vc, local, n, grey,
                         n <= TRUTH_CROWD && !w->all_crowd, value, bound);
        if (st != CROWD_DECLINED) {
            w->crowded++;
            return st;
        }
    }
    if ((st = load_local(w, local, n)) || (st = breakpoints(w, local, n)) ||
        (w->grad && (st = thr_heights(w, grey ? 1 : 3))) || (st = reserve_workspace(w, w->npts)))
        return st;
    if (w->sing_oom) {
        w->sing_oom = 0;
        return aa_fail(AA_ENOMEM, "out of memory for the turning points of pixel (%g, %g)",
                       w->uc - 0.5, w->vc - 0.5);
    }
    double worst = 0.0;
    w->rad_err_max = 0.0;
    w->shared = !grey;
    if (w->shared)
        memo_next(&w->memo);
    for (int ch = 0; ch < (grey ? 1 : 3); ch++) {
        double result = 0.0, abserr = 0.0;
        w->channel = ch;
        integrate_intervals(w, &result, &abserr);
        value[ch] = result;
        worst = fmax(worst, abserr);
    }
    if (w->gen_stuck) {
        w->gen_stuck = w->gen_over = w->cone_over = 0;
        return aa_fail(AA_EINVAL, "pixel (%g, %g): a row of the gradients' composite not "
                                  "resolved within the work limit (the sRGB decoding's "
                                  "threshold 0.04045 isolated in at most %d places and %d "
                                  "halvings, at most %d Gauss-Legendre pieces a span): refused; "
                                  "sample it with point, supersample or jitter",
                       w->uc - 0.5, w->vc - 0.5, GEN_MAX_FUZZ, GEN_BUDGET, GEN_PIECES);
    }
    if (w->cone_over) {
        w->cone_over = w->gen_over = 0;
        return aa_fail(AA_EINVAL, "pixel (%g, %g): the composite of several layers of one "
                                  "cone-case radial gradient is a polynomial in t whose roots "
                                  "GSL's solver did not find (the sRGB decoding's pieces are "
                                  "unknown there): refused; sample it with point, supersample or "
                                  "jitter",
                       w->uc - 0.5, w->vc - 0.5);
    }
    if (w->gen_over) {
        w->gen_over = 0;
        return aa_fail(AA_EINVAL, "pixel (%g, %g): more than %d gradient layers paint one point "
                                  "(the reference folds at most that many layers' bounds a "
                                  "span): refused; sample it with point, supersample or jitter",
                       w->uc - 0.5, w->vc - 0.5, GEN_LAYERS);
    }
    if (grey)
        value[1] = value[2] = value[0];
    /* Rounding: relative crossings are within a few ulps of R (long double
     * arithmetic, then one rounding to double), and within a few long
     * double epsilons of the size of the piece's numbers (truth_piece_scale:
     * 1e-14 px on a circle of radius 1e6 whose centre is 1e6 px away); each
     * moves the inner integral by at most that times the filter's peak (for
     * the cone, the integral over v of the largest weight of a row,
     * 3 / (pi R)). */
    double peak = w->box      ? 1.0
                  : w->radial ? aa_filter_weight2(w->f, 0.0, 0.0) * w->R
                              : aa_filter_weight(w->f, 0.0);
    double scale = 0.0;
    for (size_t k = 0; k < w->nlp; k++)
        scale += truth_piece_scale(&w->lp[k]);
    long double leps = aa_long_double_is_extended() ? LDBL_EPSILON : DBL_EPSILON;
    *bound = worst + w->f->lost + 8.0 * DBL_EPSILON * fmax(w->R, 1.0) * peak * (double)n +
             (double)(8 * leps) * scale * peak;
    /* gradient paint: each piece's mean comes from two composites (a few
     * ulps each, doubled by the extension to the ends) and pow, expm1 and
     * log1p (an ulp or two each), over a window of width 2R */
    if (w->grad && w->box)
        *bound += 64.0 * DBL_EPSILON * 2.0 * w->R;
    else if (w->grad) /* the same per unit of the weights' largest absolute integrals */
        *bound += 64.0 * DBL_EPSILON * (2.0 * w->R * peak) * (2.0 * w->R * peak);
    /* radial gradient: the rows' quadrature bounds (rad_piece), the
     * largest over the window's height */
    *bound += w->rad_err_max * 2.0 * w->R;
    return AA_OK;
}

/* ------------------------------------------------------------------------
 * Rows and the whole image
 * ------------------------------------------------------------------------ */

typedef struct row_stats {
    size_t integrated, filled, fast, crowded, scanned;
    double max_bound;
    int worst_i, worst_j;
} row_stats;

typedef struct progress progress;
static void progress_add(progress *p, size_t pixels);

/* Row j.  fs, if not NULL, offers the fixed rule to the non-uniform
 * pixels (Gaussian); the others, or those it declines, take QAG.  prog, if
 * not NULL, is told of each pixel integrated and each run of uniform ones,
 * not of the row at its end: one crowded pixel can take seconds, and a row
 * of them minutes (tests/bench_bezstroke.c's scene at a few pixels). */
static int render_row(worker *w, panel_worker *fs, int j, aa_image *out, aa_image *bound,
                      row_stats *rs, progress *prog)
{
    double R = w->R;
    int grey = aa_scene_is_grey(w->scene);
    w->vc = j + 0.5;
    int st = aa_strip_begin(w->strip, w->vc - R, w->vc + R);
    if (st)
        return st;
    int phase = 0, panels = 0;
    for (int i = 0; i < out->w;) {
        double *px = aa_pixel(out, i, j), b;
        w->uc = i + 0.5;
        if (aa_strip_window(w->strip, w->uc - R, w->uc + R) == 0 && !w->grad) {
            /* a run of uniform windows: one colour, no integration */
            aa_rgb c;
            int end = aa_strip_uniform_run(w->strip, i, out->w, R, w->vc, w->wind, &c);
            b = w->f->lost;
            for (int k = i; k < end; k++, px += 3) {
                px[0] = c.c[0], px[1] = c.c[1], px[2] = c.c[2];
                if (bound)
                    *aa_pixel(bound, k, j) = b;
            }
            rs->filled += (size_t)(end - i);
            if (prog)
                progress_add(prog, (size_t)(end - i));
            if (b > rs->max_bound) {
                rs->max_bound = b;
                rs->worst_i = i;
                rs->worst_j = j;
            }
            i = end;
            continue;
        }
        /* the row's panels, computed when a pixel first needs them */
        if (fs && !panels && (st = fast_row(fs, j, &phase)))
            return st;
        panels = 1;
        if (fs && fast_pixel(fs, j, phase, i, grey, px, &b))
            rs->fast++;
        else if ((st = integrate_pixel(w, grey, px, &b)))
            return st;
        rs->integrated++;
        if (prog)
            progress_add(prog, 1);
        if (bound)
            *aa_pixel(bound, i, j) = b;
        if (b > rs->max_bound) {
            rs->max_bound = b;
            rs->worst_i = i;
            rs->worst_j = j;
        }
        i++;
    }
    return AA_OK;
}

/* A field scene: the field's own exact pixel integral (core.h,
 * "Fields"); every pixel counts as integrated. */
static int field_render(const aa_scene *placed, const aa_filter *f, int threads, aa_image *out,
                        aa_image *bound, aa_truth_stats *stats, size_t *nfast)
{
    const double *p;
    double map[4], max_bound = 0.0;
    int worst[2] = {-1, -1};
    const aa_field_type *field = aa_scene_field(placed, &p, NULL, map);
    int st = field->pixels(p, map, f, threads, out, bound, &max_bound, worst);
    if (st)
        return aa_fail_context(st, "field %s", field->name);
    if (stats) {
        stats->integrated = (size_t)out->w * (size_t)out->h;
        stats->filled = 0;
        stats->crowded = 0;
        stats->scanned = 0;
        stats->max_bound = max_bound;
        stats->worst_i = worst[0];
        stats->worst_j = worst[1];
    }
    if (nfast)
        *nfast = 0;
    return AA_OK;
}

/* ---- progress (truth.h, aa_truth_set_progress) ---- */

static aa_truth_progress_fn progress_fn;
static void *progress_ctx;
static double progress_interval = 0.1;

void aa_truth_set_progress(aa_truth_progress_fn fn, void *ctx)
{
    progress_fn = fn;
    progress_ctx = ctx;
}

void aa__truth_set_progress_interval(double seconds)
{
    progress_interval = seconds;
}

struct progress {
    aa_truth_progress_fn fn;
    void *ctx;
    size_t done, total;
    double last;
};

/* `pixels` more are done: tell, one thread at a time, at most ten times a
 * second (progress_interval). */
static void progress_add(progress *p, size_t pixels)
{
#pragma omp critical(aa_truth_progress)
    {
        p->done += pixels;
        double now = aa_now();
        if (now - p->last >= progress_interval && p->done < p->total) {
            p->last = now;
            p->fn(p->ctx, p->done, p->total);
        }
    }
}

int aa__truth_render_mode(const aa_scene *placed, const aa_filter *f, int threads, int mode,
                          aa_image *out, aa_image *bound, aa_truth_stats *stats, size_t *nfast)
{
    if (!out || !out->v || out->c != 3)
        return aa_fail(AA_EINVAL, "reference needs a 3-channel image");
    if (bound && (bound->w != out->w || bound->h != out->h || bound->c != 1))
        return aa_fail(AA_EINVAL, "reference bound image must be %dx%dx1", out->w, out->h);
    if (aa_scene_field(placed, NULL, NULL, NULL))
        return field_render(placed, f, threads, out, bound, stats, nfast);
    int grad = aa_scene_has_gradients(placed);
    gsl_set_error_handler_off(); /* QAG's status is judged by its error estimate */
    int status = AA_OK;
    char message[1024] = "";
    row_stats total = {0, 0, 0, 0, 0, 0.0, -1, -1};
#ifdef _OPENMP
    int nthreads = aa_thread_count(threads);
#else
    int nthreads = 1;
    (void)threads;
#endif
    /* The Gaussian takes the fixed rule, unless asked not to, or its panel
     * buffers would be unreasonably large, or the windows of neighbouring
     * rows do not overlap (s < 1/16: no panel to share, and QAG is then
     * as fast: measured on crow 256x256, s = 0.05), or long double is no
     * wider than double where it runs (the rule's node heights count on
     * the 64-bit mantissa; valgrind, for one, emulates the x87 in double:
     * its error then reached 1.2e-12 on a half-plane at s = 0.07), or the
     * scene has gradient paint (the panels carry constant colours only). */
    gauss_plan plan;
    int use_fast = 0;
    if (f->type == &aa_filter_gauss && mode == 0 && 2.0 * f->radius >= 1.0 &&
        aa_long_double_is_extended() && !grad) {
        if ((status = plan_init(&plan, f)))
            return status;
        use_fast = fast_bytes(&plan, out->w, aa_scene_is_grey(placed) ? 1 : 3) <= FAST_MAX_BYTES;
        if (!use_fast)
            plan_free(&plan);
    }
    /* Rows go to threads in blocks, so that a thread's panels serve many
     * rows; a panel's values do not depend on who computes it, so the image
     * does not depend on the blocks. */
    int rows = 1;
    if (use_fast)
        rows = nthreads == 1 ? out->h : (out->h + 4 * nthreads - 1) / (4 * nthreads);
    int nblocks = (out->h + rows - 1) / rows;
    progress prog = {progress_fn, progress_ctx, 0, (size_t)out->w * (size_t)out->h, aa_now()};
#pragma omp parallel num_threads(nthreads)
    {
        worker w;
        panel_worker fs;
        row_stats rs = {0, 0, 0, 0, 0, 0.0, -1, -1};
        int st = worker_init(&w, placed, f);
        if (!st && grad)
            st = grad_init(&w);
        w.all_crowd = mode == AA__TRUTH_CROWD;
        memset(&fs, 0, sizeof fs);
        if (!st && use_fast)
            st = fast_init(&fs, &plan, f, placed, out->w);
#pragma omp for schedule(dynamic, 1)
        for (int blk = 0; blk < nblocks; blk++) {
            fs.valid = 0;
            int j1 = (blk + 1) * rows < out->h ? (blk + 1) * rows : out->h;
            for (int j = blk * rows; j < j1 && st == AA_OK; j++) {
                st = render_row(&w, use_fast ? &fs : NULL, j, out, bound, &rs,
                                prog.fn ? &prog : NULL);
            }
        }
        rs.crowded = w.crowded;
        rs.scanned = w.scanned;
        worker_free(&w);
        fast_free(&fs);
#pragma omp critical(aa_truth_merge)
        {
            if (st && !status) {
                status = st;
                /* messages are per thread: carry this one to the caller's */
                snprintf(message, sizeof message, "%s", aa_last_error());
            }
            total.integrated += rs.integrated;
            total.filled += rs.filled;
            total.fast += rs.fast;
            total.crowded += rs.crowded;
            total.scanned += rs.scanned;
            if (rs.max_bound > total.max_bound ||
                (rs.max_bound == total.max_bound && rs.worst_j >= 0 &&
                 (total.worst_j < 0 || rs.worst_j < total.worst_j))) {
                total.max_bound = rs.max_bound;
                total.worst_i = rs.worst_i;
                total.worst_j = rs.worst_j;
            }
        }
    }
    if (use_fast)
        plan_free(&plan);
    if (prog.fn && !status)
        prog.fn(prog.ctx, prog.total, prog.total);
    if (status)
        aa_fail(status, "%s", message);
    if (stats) {
        stats->integrated = total.integrated;
        stats->filled = total.filled;
        stats->crowded = total.crowded;
        stats->scanned = total.scanned;
        stats->max_bound = total.max_bound;
        stats->worst_i = total.worst_i;
        stats->worst_j = total.worst_j;
    }
    if (nfast)
        *nfast = total.fast;
    return status;
}

int aa_truth_render(const aa_scene *placed, const aa_filter *f, int threads, aa_image *out,
                    aa_image *bound, aa_truth_stats *stats)
{
    return aa__truth_render_mode(placed, f, threads, 0, out, bound, stats, NULL);
}
