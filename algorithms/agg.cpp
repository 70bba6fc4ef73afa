/*
 * agg.cpp: Anti-Grain Geometry's scanline rasterizer as a peer (AGG 2.6,
 * Debian libagg-dev: rasterizer_scanline_aa with scanline_u8).
 *
 * AGG accumulates, like FreeType's smooth rasterizer and Crow's "Left Areas
 * - Right Areas = Area" (Crow 1976, ch. 3, fig. 3.13), a signed area and a
 * cover per cell as edges are walked, in 24.8 fixed point (positions
 * rounded to 1/256 px), and resolves each cell's coverage in one sweep
 * along the row into 0 .. 255 (its aa_shift of 8; a full cell, 256, is
 * clamped to 255).  Its gamma is off (gamma_none: the coverage itself).
 * The fill rule is the layer's (fill_non_zero or fill_even_odd; nonzero
 * coverage is |winding area| clamped to full, as FreeType's).
 *
 * The outline is the placed scene's: one polygon per contour, lines as
 * line_to_d, each quadratic arc flattened by AGG's own curve3 and each
 * cubic one by its curve4, with the same method and scale (curves=div,
 * AGG's default, is curve3_div's recursive subdivision, which stops where
 * the arc is within 0.5/scale px of its chord; curves=inc is curve3_inc's
 * fixed steps, about a quarter of the arc's length times scale), with
 * `scale` AGG's approximation_scale (its default 1: 0.5 px).  Each
 * elliptical arc is AGG's own arc generator (agg::arc, the one its
 * ellipses and rounded shapes use) on the unit circle, its vertices mapped
 * by the affine map (agg::trans_affine) that takes the circle to the
 * ellipse, with the approximation scale times the map's Frobenius norm:
 * chords within 0.125/scale px of the ellipse (put_arc).  Arcs are
 * flattened in render, where AGG would flatten them, and only those whose
 * control triangle meets the band: an arc wholly above or below it is
 * replaced by its chord, which the clipper drops all the same.
 *
 * Our image receives the span's cover / 255 per pixel, mixed between the
 * background and the layer's grey (peer.h).  The cover is the value AGG's
 * own gray8 pixel format paints for white at full alpha over black
 * (lerp(0, 255, cover) = cover), so this is what AGG would draw.
 *
 * Bands: BAND rows at a time, each clipped by AGG's clipper in double
 * precision (rasterizer_sl_clip_dbl: nothing is converted to fixed point
 * before clipping, so coordinates far outside the image do not overflow;
 * parts left or right of the box become vertical lines on its edge, which
 * keeps the winding), bands in parallel, one rasterizer per thread.  A
 * row's coverage does not depend on its band.  AGG keeps cells in blocks of
 * 4096 and by default stops adding cells after 1024 blocks, silently; the
 * cap is raised here to 2^20 - 1 blocks (its 32-bit cell count's limit), so
 * no cell is dropped short of running out of memory.
 *
 * C++ stays in this file: the method's entries have C linkage (agg.h) and
 * catch every exception (AGG allocates with new), returning a status.  It
 * is compiled as C++20: AGG shifts negative covers left
 * (agg_rasterizer_scanline_aa.h, sweep_scanline), which C++17 leaves
 * undefined and C++20 defines as two's complement.
 *
 * Strokes: a layer kept as a stroke (aa_scene_stroke) is stroked by AGG
 * from its source (band_strokes): the path in user units (curves by
 * conv_curve, arcs by agg::arc), conv_dash for its dashes, conv_stroke
 * with its width, join, cap and miter limit, then conv_transform by its
 * map, as AGG's own SVG viewer does; the flattening and the round joins'
 * and caps' polygons use the approximation scale times the map's
 * Frobenius norm, so their tolerance holds in pixels.  Several strokes of
 * one grey are painted OVER each other (peer.h).
 *
 * Painted (peer.h): any other scene (colour, several layers, translucency,
 * groups of opacity, clips) is painted layer by layer (agg_cover): each
 * layer's contours under its rule, or its stroke by AGG's stroker as
 * above, swept into the band's covers and composited over the layers
 * behind (aa_peer_paint_band).  A clip is the coverage of its members,
 * swept by AGG's rasterizer as any layer, made a mask and multiplied into
 * the coverage of the layers it gates (AGG's own alpha mask,
 * alpha_mask_gray8, multiplies 8-bit covers by an 8-bit mask the same
 * way, taking the product to 8 bits besides, (255 + c m) >> 8; its
 * scanline boolean intersection multiplies the covers of two scanlines
 * alike); a group's layers go into the group's
 * buffer, composited with its opacity.
 *
 * Limits: grey scenes of one layer or of strokes of one grey, or painted
 * layer by layer (peer.h), and the box filter only; at most 32 dash lengths; 8-bit coverage (up to 1/510 from rounding alone); positions
 * rounded to 1/256 px; arcs flattened; the cover and area of a cell are
 * 32-bit integers (a cell crossed by some 2^15 edges would overflow them).
 */
#include "agg.h"

extern "C" {
#include "core.h"
#include "path.h"
#include "peer.h"
}

#include <cmath>
#include <cstring>
#include <new>
#include <vector>

#include <omp.h>

#pragma GCC diagnostic push
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wunknown-warning-option"
#endif
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wdeprecated-copy"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wclass-memaccess"
/* C++20 deprecates AGG's arithmetic between its enums and with doubles */
#pragma GCC diagnostic ignored "-Wdeprecated-enum-enum-conversion"
#pragma GCC diagnostic ignored "-Wdeprecated-enum-float-conversion"
/* gradient_lut::build_lut sets `end` in a loop that runs whenever it is
 * read (two stops or more), which GCC does not see at every -O level */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <agg_arc.h>
#include <agg_basics.h>
#include <agg_conv_curve.h>
#include <agg_conv_dash.h>
#include <agg_conv_stroke.h>
#include <agg_conv_transform.h>
#include <agg_curves.h>
#include <agg_gamma_functions.h>
#include <agg_path_storage.h>
#include <agg_rasterizer_scanline_aa.h>
#include <agg_rasterizer_sl_clip.h>
#include <agg_color_rgba.h>
#include <agg_gradient_lut.h>
#include <agg_scanline_u.h>
#include <agg_span_gradient.h>
#include <agg_span_interpolator_linear.h>
#include <agg_trans_affine.h>
#pragma GCC diagnostic pop

namespace {

const int BAND = 64;                        /* rows per band */
const unsigned CELL_BLOCKS = (1u << 20) - 1; /* AGG's cap on blocks of 4096 cells */

enum { SCALE, CURVES };
enum { CURVES_DIV, CURVES_INC };

const aa_param agg_params[] = {
    {"scale", AA_PARAM_REAL, 1.0, 0.0, 10000.0, 1, nullptr,
     "AGG's approximation_scale for arcs: div flattens to within 0.5/scale px, elliptical "
     "arcs to within 0.125/scale px (AGG's default 1)"},
    {"curves", AA_PARAM_CHOICE, CURVES_DIV, 0, 0, 0, "div|inc",
     "AGG's arc approximation: div (curve3_div, recursive subdivision, AGG's default) or inc "
     "(curve3_inc, fixed steps)"},
    {nullptr, AA_PARAM_END, 0, 0, 0, 0, nullptr, nullptr}};

typedef agg::rasterizer_scanline_aa<agg::rasterizer_sl_clip_dbl> rasterizer;

/* One thread's rasterizer, scanline, arc flatteners and band of covers. */
struct worker {
    rasterizer ras;
    agg::scanline_u8 sl;
    agg::curve3 curve;
    agg::curve4 curve4;
    agg::arc ellipse;
    std::vector<unsigned char> band;
    std::vector<float> paint;      /* a gradient layer's paint on the band (grad_shade) */
    std::vector<agg::rgba8> span;  /* one row of it, as span_gradient makes it */
    aa_peer_painter *painter; /* painted (peer.h) */
    worker() : ras(CELL_BLOCKS), painter(nullptr) {}
    ~worker() { aa_peer_painter_free(painter); }
    worker(const worker &) = delete;
    worker &operator=(const worker &) = delete;
};

struct agg_work {
    std::vector<worker *> workers;
    ~agg_work()
    {
        for (worker *w : workers)
            delete w;
    }
};

struct agg_state {
    aa_peer_scene ps;
    double lut[256];
    agg_work *work;
    int nthreads;
    int painted; /* the scene painted layer by layer (peer.h) */
};

/* Elliptical arc edge d as AGG draws an ellipse under a transformation:
 * its own arc generator (agg::arc) on the unit circle from t0 to t1,
 * counter-clockwise in the angle (increasing) if t1 > t0, each vertex
 * mapped by the affine map (agg::trans_affine: x' = sx x + shx y + tx,
 * y' = shy x + sy y + ty, constructed as sx shy shx sy tx ty) that takes
 * (cos t, sin t) to (cx + ux cos t + vx sin t, cy + uy cos t + vy sin t).
 * agg::arc steps the angle by da = 2 acos(r/(r + 0.125/scale)) (r = 1
 * here), so each chord is within 0.125/scale of the circle; the map
 * stretches no distance by more than its Frobenius norm
 * F = sqrt(|u|^2 + |v|^2), so with the approximation scale `scale` F the
 * chords are within 0.125/scale px of the ellipse (and inside it).  The
 * first vertex is the pen and the last is replaced by the edge's exact
 * end. */
void put_arc(worker &wk, const aa_edge &d, double scale)
{
    const agg::trans_affine m(d.ux, d.uy, d.vx, d.vy, d.cx, d.cy);
    double f = std::hypot(std::hypot(d.ux, d.uy), std::hypot(d.vx, d.vy));
    wk.ellipse.init(0.0, 0.0, 1.0, 1.0, d.t0, d.t1, d.t1 >= d.t0);
    wk.ellipse.approximation_scale(scale * f);
    wk.ellipse.rewind(0);
    double x, y, px = 0.0, py = 0.0;
    unsigned cmd = wk.ellipse.vertex(&x, &y); /* the start: the pen */
    int pending = 0;
    while (!agg::is_stop(cmd = wk.ellipse.vertex(&x, &y))) {
        if (pending)
            wk.ras.line_to_d(px, py);
        m.transform(&x, &y);
        px = x, py = y, pending = 1;
    }
    wk.ras.line_to_d(d.x1, d.y1);
}

/* AGG's dash generator holds at most this many lengths (vcgen_dash). */
const size_t AGG_MAX_DASHES = 32;

/* The coverage AGG's rasterizer holds, painted OVER rows [y0, y0 + rows)
 * of the band: a + c - a c in 0 .. 255 (a painted over nothing, a = 0, is
 * c itself). */
void sweep_over(worker &wk, int w, int y0, int rows)
{
    rasterizer &ras = wk.ras;
    if (!ras.rewind_scanlines())
        return;
    wk.sl.reset(ras.min_x(), ras.max_x());
    while (ras.sweep_scanline(wk.sl)) {
        int y = wk.sl.y();
        if (y < y0 || y >= y0 + rows)
            continue;
        unsigned char *row = wk.band.data() + (size_t)(y - y0) * (size_t)w;
        unsigned n = wk.sl.num_spans();
        agg::scanline_u8::const_iterator span = wk.sl.begin();
        for (; n; n--, ++span) {
            int x = span->x, len = span->len;
            const agg::int8u *covers = span->covers;
            for (int i = 0; i < len; i++, x++)
                if (x >= 0 && x < w) {
                    unsigned a = row[x], c = covers[i];
                    row[x] = (unsigned char)(c + (a * (255 - c) + 127) / 255);
                }
        }
    }
}

/* A stroke source's path in its user units as an AGG path: lines,
 * quadratic and cubic arcs as AGG's curve3 and curve4 commands (flattened
 * by conv_curve), each circular or elliptical arc as agg::arc's chords of
 * the unit circle mapped to the ellipse (as put_arc, the scale given in
 * user units), its last vertex the arc's exact end. */
void source_path(agg::path_storage &path, const aa_stroke_source &src, double scale)
{
    double px = 0.0, py = 0.0;
    for (size_t k = 0; k < src.path.n; k++) {
        const aa_path_seg &g = src.path.seg[k];
        const double *q = g.p;
        switch (g.op) {
        case AA_PATH_MOVE:
            path.move_to(q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_LINE:
            path.line_to(q[0], q[1]);
            px = q[0], py = q[1];
            break;
        case AA_PATH_QUAD:
            path.curve3(q[0], q[1], q[2], q[3]);
            px = q[2], py = q[3];
            break;
        case AA_PATH_CUBIC:
            path.curve4(q[0], q[1], q[2], q[3], q[4], q[5]);
            px = q[4], py = q[5];
            break;
        case AA_PATH_ARC: {
            const agg::trans_affine m(q[2], q[3], q[4], q[5], q[0], q[1]);
            double f = std::hypot(std::hypot(q[2], q[3]), std::hypot(q[4], q[5]));
            agg::arc a(0.0, 0.0, 1.0, 1.0, q[6], q[7], q[7] >= q[6]);
            a.approximation_scale(scale * f);
            a.rewind(0);
            double x, y, lx = 0.0, ly = 0.0;
            unsigned cmd = a.vertex(&x, &y); /* the start: the pen */
            int pending = 0;
            while (!agg::is_stop(cmd = a.vertex(&x, &y))) {
                if (pending)
                    path.line_to(lx, ly);
                m.transform(&x, &y);
                lx = x, ly = y, pending = 1;
            }
            path.line_to(q[8], q[9]);
            px = q[8], py = q[9];
            break;
        }
        default:
            path.close_polygon();
            break;
        }
    }
    (void)px, (void)py;
}

/* The stroke of `src` (its flattened path, dashed or not) into the
 * rasterizer: conv_stroke in user units with the source's width, join,
 * cap and miter limit, then conv_transform by the source's map, so that a
 * non-uniform map transforms the outline as SVG says.  SVG's miter is
 * AGG's miter_join_revert (a bevel past the limit); SVG 2's miter-clip is
 * its miter_join, which past the limit cuts the miter where the distance
 * along the bisector from the vertex is the limit times half the width
 * (math_stroke's calc_miter: the edges' points moved towards the tip by
 * (lim - dbevel) / (di - dbevel), lim = limit w/2), SVG 2's cut; arcs is
 * refused (agg_init). */
template <class Src>
void add_stroke(rasterizer &ras, Src &in, const aa_stroke_source &src, double scale)
{
    static const agg::line_join_e joins[] = {agg::miter_join_revert, agg::round_join,
                                             agg::bevel_join, agg::miter_join};
    static const agg::line_cap_e caps[] = {agg::butt_cap, agg::round_cap, agg::square_cap};
    agg::conv_stroke<Src> stroke(in);
    stroke.width(src.style.width);
    stroke.line_join(joins[src.style.join]);
    stroke.line_cap(caps[src.style.cap]);
    stroke.miter_limit(src.style.miterlimit);
    stroke.approximation_scale(scale);
    agg::trans_affine m(src.m[0], src.m[1], src.m[2], src.m[3], src.m[4], src.m[5]);
    agg::conv_transform<agg::conv_stroke<Src>> mapped(stroke, m);
    ras.add_path(mapped);
}

/* Rows [y0, y0 + rows) of the band: each stroke of the scene (or only
 * source `only`, if it is not -1) by AGG's stroker, painted OVER the
 * others.  Curves are flattened in user units
 * to AGG's tolerance divided by the map's largest stretch (its Frobenius
 * norm bounds it), so within it in pixels. */
void band_strokes(worker &wk, const aa_scene *scene, const double *p, int w, int y0, int rows,
                  int only)
{
    size_t nsrc;
    const aa_stroke_source *src = aa_scene_stroke_sources(scene, &nsrc);
    std::memset(wk.band.data(), 0, (size_t)rows * (size_t)w);
    for (size_t k = 0; k < nsrc; k++) {
        if (only >= 0 && k != (size_t)only)
            continue;
        const aa_stroke_source &a = src[k];
        const double norm = std::hypot(std::hypot(a.m[0], a.m[1]), std::hypot(a.m[2], a.m[3]));
        const double scale = p[SCALE] * norm;
        rasterizer &ras = wk.ras;
        ras.reset();
        ras.gamma(agg::gamma_none());
        ras.filling_rule(agg::fill_non_zero);
        ras.clip_box(0.0, (double)y0, (double)w, (double)(y0 + rows));
        agg::path_storage path;
        source_path(path, a, scale);
        agg::conv_curve<agg::path_storage> curved(path);
        curved.approximation_method((int)p[CURVES] == CURVES_INC ? agg::curve_inc
                                                                 : agg::curve_div);
        curved.approximation_scale(scale);
        if (a.style.ndash) {
            /* an odd count repeats (SVG), so AGG gets it twice */
            agg::conv_dash<agg::conv_curve<agg::path_storage>> dashed(curved);
            const size_t n = a.style.ndash % 2 ? 2 * a.style.ndash : a.style.ndash;
            for (size_t i = 0; i + 1 < n; i += 2)
                dashed.add_dash(a.style.dash[i % a.style.ndash],
                                a.style.dash[(i + 1) % a.style.ndash]);
            dashed.dash_start(a.style.dashoffset);
            add_stroke(ras, dashed, a, scale);
        } else {
            add_stroke(ras, curved, a, scale);
        }
        sweep_over(wk, w, y0, rows);
    }
}

/* Fill rows [y0, y0 + rows) of band coverage from the scene's contours
 * of layer `layer` (-1: every contour) under `rule`. */
void band_fill(worker &wk, const aa_scene *scene, int layer, aa_fill_rule rule, const double *p,
               int w, int y0, int rows)
{
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(scene, &ne);
    const size_t *start = aa_scene_contours(scene, &nc);
    const double ya = y0, yb = y0 + rows;
    std::memset(wk.band.data(), 0, (size_t)rows * (size_t)w);
    rasterizer &ras = wk.ras;
    ras.reset();
    ras.gamma(agg::gamma_none());
    ras.filling_rule(rule == AA_FILL_EVENODD ? agg::fill_even_odd : agg::fill_non_zero);
    ras.clip_box(0.0, ya, (double)w, yb);
    wk.curve.approximation_method((int)p[CURVES] == CURVES_INC ? agg::curve_inc : agg::curve_div);
    wk.curve.approximation_scale(p[SCALE]);
    wk.curve4.approximation_method((int)p[CURVES] == CURVES_INC ? agg::curve_inc : agg::curve_div);
    wk.curve4.approximation_scale(p[SCALE]);
    for (size_t c = 0; c < nc; c++) {
        if (start[c] == start[c + 1] || (layer >= 0 && e[start[c]].layer != layer))
            continue;
        ras.move_to_d(e[start[c]].x0, e[start[c]].y0);
        for (size_t k = start[c]; k < start[c + 1]; k++) {
            const aa_edge &d = e[k];
            double top = std::fmin(d.y0, std::fmin(d.cy, d.y1));
            double bottom = std::fmax(d.y0, std::fmax(d.cy, d.y1));
            if (d.quad == 2) /* the convex hull: the controls too */
                top = std::fmin(top, d.c2y), bottom = std::fmax(bottom, d.c2y);
            if (d.quad == 3) { /* the whole ellipse, centre +- its half height */
                double h = std::hypot(d.uy, d.vy);
                top = d.cy - h, bottom = d.cy + h;
            }
            if (!d.quad || bottom < ya || top > yb) {
                ras.line_to_d(d.x1, d.y1);
                continue;
            }
            if (d.quad == 3) {
                put_arc(wk, d, p[SCALE]);
                continue;
            }
            double x, y;
            if (d.quad == 2) { /* AGG's curve4 */
                wk.curve4.init(d.x0, d.y0, d.cx, d.cy, d.c2x, d.c2y, d.x1, d.y1);
                wk.curve4.rewind(0);
                unsigned cmd = wk.curve4.vertex(&x, &y); /* the start point */
                while (!agg::is_stop(cmd = wk.curve4.vertex(&x, &y)))
                    ras.line_to_d(x, y);
                continue;
            }
            wk.curve.init(d.x0, d.y0, d.cx, d.cy, d.x1, d.y1);
            wk.curve.rewind(0);
            unsigned cmd = wk.curve.vertex(&x, &y); /* the start point: already there */
            while (!agg::is_stop(cmd = wk.curve.vertex(&x, &y)))
                ras.line_to_d(x, y);
        }
        ras.close_polygon();
    }
    sweep_over(wk, w, y0, rows);
}

/* The grey path's band: the strokes OVER each other, or the one layer. */
void band_cover(worker &wk, const aa_scene *scene, const aa_peer_scene &ps, const double *p,
                int w, int y0, int rows)
{
    if (ps.strokes)
        band_strokes(wk, scene, p, w, y0, rows, -1);
    else
        band_fill(wk, scene, -1, ps.rule, p, w, y0, rows);
}

/* Painted (peer.h): AGG's coverage of layer l (its stroke by AGG's
 * stroker, or its contours under its rule) in the worker's band; AGG's
 * exceptions end here, as statuses, before they reach peer.c. */
struct cover_ctx {
    worker *wk;
    const aa_scene *scene;
    const double *p;
    int w, h;
};

int agg_cover(void *vctx, int l, int y0, int rows, const unsigned char **cov, size_t *stride)
{
    const cover_ctx &c = *static_cast<const cover_ctx *>(vctx);
    *cov = nullptr;
    *stride = (size_t)c.w;
    try {
        int k = aa_scene_layer_stroked(c.scene, l);
        if (k >= 0)
            band_strokes(*c.wk, c.scene, c.p, c.w, y0, rows, k);
        else
            band_fill(*c.wk, c.scene, l, aa_scene_layer_rule(c.scene, l), c.p, c.w, y0, rows);
    } catch (const std::bad_alloc &) {
        return AA_ENOMEM;
    } catch (...) {
        return AA_EFAIL;
    }
    *cov = c.wk->band.data();
    return AA_OK;
}

/*
 * Gradient paint (peer.h), by AGG's span_gradient: the span generator
 * render_scanlines_aa would call for the layer, asked here for whole rows
 * (span_gradient::generate at the pixels' centres), its colours
 * composited by peer.c over the coverage AGG swept (agg_cover).
 *
 * AGG's gradients are integer: span_interpolator_linear maps each pixel's
 * centre through a trans_affine into the gradient's space in 1/256 units
 * (subpixel_shift 8), span_gradient takes those to 1/16 units
 * (gradient_subpixel_shift 4), the gradient function gives a distance d in
 * 1/16 units, and the colour is entry (d - d1) 256 / (d2 - d1) of a
 * 256-entry colour table (gradient_lut), clamped to [0, 255] (pad); the
 * adaptors gradient_repeat_adaptor and gradient_reflect_adaptor fold d
 * into [0, d2] first.  So the space is scaled to D = 256 units a period
 * (d1 = 0, d2 = D): t is resolved to 1/4096 and its index is floor(256 t).
 *  - linear: gradient_x of gx = D (q - P1).(P2 - P1) / |P2 - P1|^2, q the
 *    pixel mapped back by the gradient's map m (the trans_affine is that
 *    composition);
 *  - radial: gradient_radial_focus, the circle of radius D about the
 *    origin and the focal point F inside it, in the space of
 *    (D / r) (q - C): d is D times the w whose circle F + w (C - F) of
 *    radius w r passes through the point (AGG solves the same quadratic),
 *    SVG 2's two circles with a focal radius of 0.  AGG has no focal
 *    radius: fr > 0 is refused.  It rounds F to 1/16 unit (1/4096 of r).
 * The table (gradient_lut with color_interpolator<rgba8>): the stops'
 * sRGB-encoded colours and opacities as rgba8 (rounded to 8 bits), entry
 * i for t in [i/256, (i + 1)/256), between two stops of offsets o0 < o1 a
 * dda of count end - start + 1 from entry start = round(256 o0) to end =
 * round(256 o1), each channel floored to 8 bits; colour and opacity
 * interpolated each on its own, not premultiplied, as SVG says.  Entry
 * i's colour is the stops' at some t' within 2.5/256 of every t it stands
 * for (the dda's count, one more than its entries, and the offsets'
 * rounding): so a channel of slope L per unit of t is within L 2.5/256
 * plus 1.5/255 (rounding and floor) of the exact colour, at a t resolved
 * to 1/4096 (tests/test_gradient_renderers.c holds AGG to that).  The
 * table keeps one stop of several at one offset (build_lut's
 * remove_duplicates keeps the first, after an unstable sort), so a sharp
 * step, two stops at one offset of different colours, is refused.
 * span_gradient's arithmetic is in int: (d - d1) 256 overflows past 2^31
 * for |t| beyond 2048 periods, so a gradient reaching |t| > 2000 inside
 * the image is refused.
 */
const double GRAD_D = 256.0; /* gradient units a period */
const double GRAD_MAX_T = 2000.0;

typedef agg::gradient_lut<agg::color_interpolator<agg::rgba8>, 256> grad_lut;
/* AGG's linear interpolator, begun at a row's pixel 0 whatever the
 * span asked for: span_interpolator_linear runs a dda from the mapped
 * first pixel's centre to the mapped end of the span, rounded to 1/256, so
 * a span begun at x0 or ending short of the row would step otherwise than
 * the whole row does.  begin(x0 + 0.5, y, n) begins the whole row of w
 * pixels at 0.5 and steps x0 pixels on, so each pixel's coordinates are
 * the whole row's, to the bit (agg_shade paints the covered span only). */
class grad_interp : public agg::span_interpolator_linear<>
{
  public:
    grad_interp(agg::trans_affine &mtx, int w) : agg::span_interpolator_linear<>(mtx), m_w(w) {}
    void begin(double x, double y, unsigned len)
    {
        (void)len;
        agg::span_interpolator_linear<>::begin(0.5, y, (unsigned)m_w);
        for (int k = (int)(x - 0.5); k > 0; k--)
            ++*this;
    }

  private:
    int m_w;
};

/* The gradient of layer l into AGG's terms: the map from pixels to
 * gradient units, the focal point (radial) and the table.  Returns a
 * status (refusals as the comment above says, naming the layer). */
int grad_setup(const aa_scene *scene, int l, int w, int h, agg::trans_affine &mtx, double f[2],
               grad_lut *lut)
{
    aa_gradient g;
    aa_scene_layer_gradient(scene, l, &g);
    const double *m = g.m, *p = g.p;
    const double det = m[0] * m[3] - m[1] * m[2];
    /* the inverse map, pixels to the gradient's coordinates */
    const double a = m[3] / det, b = -m[1] / det, c = -m[2] / det, d = m[0] / det;
    const double e = -(a * m[4] + c * m[5]), ff = -(b * m[4] + d * m[5]);
    double tmax = 0.0;
    if (g.kind == AA_GRADIENT_LINEAR) {
        const double dx = p[2] - p[0], dy = p[3] - p[1], n = dx * dx + dy * dy;
        const double ux = GRAD_D * dx / n, uy = GRAD_D * dy / n;
        mtx = agg::trans_affine(ux * a + uy * b, 0.0, ux * c + uy * d, 0.0,
                                ux * (e - p[0]) + uy * (ff - p[1]), 0.0);
        f[0] = f[1] = 0.0;
    } else {
        if (p[5] > 0.0)
            return aa_fail(AA_EINVAL,
                           "agg: layer %d's radial gradient has a focal radius (fr = %g): "
                           "AGG's gradient_radial_focus has a focal point only",
                           l, p[5]);
        if (aa_gradient_is_cone(&g))
            return aa_fail(AA_EINVAL,
                           "agg: layer %d's radial gradient has its focal point (%g, %g) on "
                           "or outside its circle: SVG 2 paints a cone there and "
                           "gradient_radial_focus does not",
                           l, p[3], p[4]);
        const double k = GRAD_D / p[2];
        mtx = agg::trans_affine(k * a, k * b, k * c, k * d, k * (e - p[0]), k * (ff - p[1]));
        f[0] = k * (p[3] - p[0]), f[1] = k * (p[4] - p[1]);
    }
    /* |t| over the image (its corners, a pixel beyond: the map is affine);
     * radial: t <= (|g| + |F|) / (D - |F|) at a point g */
    const double fr = std::hypot(f[0], f[1]);
    for (int q = 0; q < 4; q++) {
        double x = q & 1 ? w + 1.0 : -1.0, y = q & 2 ? h + 1.0 : -1.0;
        mtx.transform(&x, &y);
        const double t = g.kind == AA_GRADIENT_LINEAR
                             ? std::fabs(x) / GRAD_D
                             : (std::hypot(x, y) + fr) / (GRAD_D - fr);
        tmax = std::fmax(tmax, std::fmax(t, std::fmax(std::fabs(x), std::fabs(y)) / GRAD_D));
    }
    if (!(tmax <= GRAD_MAX_T))
        return aa_fail(AA_EINVAL,
                       "agg: layer %d's gradient reaches %.3g periods inside the image, "
                       "beyond the %.0f AGG's integer gradient arithmetic holds",
                       l, tmax, GRAD_MAX_T);
    const aa_gradient_stop *st = g.stops;
    for (int k = 0; k + 1 < g.nstops; k++)
        if (st[k].offset == st[k + 1].offset &&
            (st[k].opacity != st[k + 1].opacity || st[k].colour.c[0] != st[k + 1].colour.c[0] ||
             st[k].colour.c[1] != st[k + 1].colour.c[1] ||
             st[k].colour.c[2] != st[k + 1].colour.c[2]))
            return aa_fail(AA_EINVAL,
                           "agg: layer %d's gradient steps sharply at offset %g (stops %d and "
                           "%d): AGG's gradient_lut keeps one stop at an offset",
                           l, st[k].offset, k, k + 1);
    if (lut) {
        lut->remove_all();
        for (int k = 0; k < g.nstops; k++) {
            const aa_rgb &cc = st[k].colour;
            lut->add_color(st[k].offset,
                           agg::rgba8(agg::rgba(aa_srgb_encode(cc.c[0]), aa_srgb_encode(cc.c[1]),
                                                aa_srgb_encode(cc.c[2]), st[k].opacity)));
        }
        if (g.nstops == 1 || st[0].offset == st[g.nstops - 1].offset) {
            /* one colour: build_lut needs two stops (it leaves the table
             * as it was otherwise) */
            lut->remove_all();
            const aa_rgb &cc = st[0].colour;
            const agg::rgba8 one(agg::rgba(aa_srgb_encode(cc.c[0]), aa_srgb_encode(cc.c[1]),
                                           aa_srgb_encode(cc.c[2]), st[0].opacity));
            lut->add_color(0.0, one);
            lut->add_color(1.0, one);
        }
        lut->build_lut();
    }
    return AA_OK;
}

int grad_setup_check(const aa_scene *scene, int l, int w, int h)
{
    agg::trans_affine mtx;
    double f[2];
    return grad_setup(scene, l, w, h, mtx, f, nullptr);
}

/* Rows [y0, y0 + rows) of the paint, by span_gradient with gradient
 * function gf, as premultiplied floats (peer.h). */
template <class GF>
void grad_rows(worker &wk, grad_interp &interp, GF &gf, grad_lut &lut, int w, int y0, int rows,
               int x0, int x1)
{
    agg::span_gradient<agg::rgba8, grad_interp, GF, grad_lut> sg(interp, gf, lut, 0.0, GRAD_D);
    for (int j = 0; j < rows; j++) {
        sg.generate(wk.span.data(), x0, y0 + j, (unsigned)(x1 - x0));
        float *out = wk.paint.data() + ((size_t)j * (size_t)w + (size_t)x0) * 4;
        for (int i = 0; i < x1 - x0; i++, out += 4) {
            const agg::rgba8 &c = wk.span[(size_t)i];
            const float a = c.a / 255.0f;
            out[0] = c.r / 255.0f * a, out[1] = c.g / 255.0f * a, out[2] = c.b / 255.0f * a;
            out[3] = a;
        }
    }
}

template <class GF>
void grad_spread(worker &wk, int spread, grad_interp &interp, GF &gf, grad_lut &lut, int w,
                 int y0, int rows, int x0, int x1)
{
    if (spread == AA_SPREAD_REPEAT) {
        agg::gradient_repeat_adaptor<GF> r(gf);
        grad_rows(wk, interp, r, lut, w, y0, rows, x0, x1);
    } else if (spread == AA_SPREAD_REFLECT) {
        agg::gradient_reflect_adaptor<GF> r(gf);
        grad_rows(wk, interp, r, lut, w, y0, rows, x0, x1);
    } else {
        grad_rows(wk, interp, gf, lut, w, y0, rows, x0, x1);
    }
}

/* Painted (peer.h): AGG's paint of gradient layer l on rows [y0, y0 +
 * rows), columns [x0, x1) (grad_interp: as the whole row paints them). */
int agg_shade(void *vctx, int l, int y0, int rows, int x0, int x1, const float **rgba,
              size_t *stride)
{
    const cover_ctx &c = *static_cast<const cover_ctx *>(vctx);
    worker &wk = *c.wk;
    *rgba = nullptr;
    *stride = (size_t)c.w * 4;
    try {
        agg::trans_affine mtx;
        double f[2];
        grad_lut lut;
        int st = grad_setup(c.scene, l, c.w, c.h, mtx, f, &lut);
        if (st)
            return st;
        aa_gradient g;
        aa_scene_layer_gradient(c.scene, l, &g);
        grad_interp interp(mtx, c.w);
        if (g.kind == AA_GRADIENT_LINEAR) {
            agg::gradient_x gf;
            grad_spread(wk, g.spread, interp, gf, lut, c.w, y0, rows, x0, x1);
        } else {
            agg::gradient_radial_focus gf(GRAD_D, f[0], f[1]);
            grad_spread(wk, g.spread, interp, gf, lut, c.w, y0, rows, x0, x1);
        }
    } catch (const std::bad_alloc &) {
        return AA_ENOMEM;
    } catch (...) {
        return AA_EFAIL;
    }
    *rgba = wk.paint.data();
    return AA_OK;
}

int agg_check(const double *p, const aa_filter *f)
{
    (void)p;
    return aa_peer_check_filter("agg", f);
}

void agg_release(void *state)
{
    agg_state *s = static_cast<agg_state *>(state);
    delete s->work;
    s->work = nullptr;
}

int agg_init(void *state, const double *p, const aa_job *job)
{
    (void)p;
    agg_state *s = static_cast<agg_state *>(state);
    /* SVG 2's miter-clip is AGG's miter_join (add_stroke); arcs it has
     * not: refused by name */
    int st = aa_peer_refuse_joins("agg", job->placed, 1,
                                  "AGG's stroker does not have (miter_join_revert, round_join, "
                                  "bevel_join and miter_join)");
    if (st)
        return st;
    st = aa_peer_scene_read("agg", job, &s->ps);
    s->painted = 0;
    if (st == AA_EINVAL && aa_peer_paintable(job->placed)) {
        /* strokes by AGG's stroker: only filled layers' offsets refused */
        if ((st = aa_peer_painted_check("agg", job->placed, 0)))
            return st;
        s->painted = 1;
        /* gradient paint AGG cannot draw as SVG means it, refused here
         * (grad_setup) */
        for (int l = 0; l < aa_scene_layer_count(job->placed); l++)
            if (aa_scene_layer_gradient(job->placed, l, nullptr) &&
                (st = grad_setup_check(job->placed, l, job->w, job->h)))
                return st;
    }
    if (st)
        return st;
    size_t nsrc;
    const aa_stroke_source *src = aa_scene_stroke_sources(job->placed, &nsrc);
    for (size_t k = 0; k < nsrc; k++) {
        size_t n = src[k].style.ndash % 2 ? 2 * src[k].style.ndash : src[k].style.ndash;
        if (n > AGG_MAX_DASHES)
            return aa_fail(AA_EINVAL,
                           "agg: a stroke's dash pattern has %zu lengths (an odd count is "
                           "repeated), more than the %zu AGG's dash generator holds",
                           n, AGG_MAX_DASHES);
    }
    for (int k = 0; k < 256; k++)
        s->lut[k] = aa_peer_mix(&s->ps, k / 255.0);
    s->nthreads = job->threads > 0 ? job->threads : 1;
    try {
        s->work = new agg_work;
        for (int k = 0; k < s->nthreads; k++) {
            s->work->workers.push_back(nullptr);
            s->work->workers.back() = new worker;
            s->work->workers.back()->band.resize((size_t)BAND * (size_t)job->w);
            if (aa_scene_has_gradients(job->placed)) {
                s->work->workers.back()->paint.resize((size_t)BAND * (size_t)job->w * 4);
                s->work->workers.back()->span.resize((size_t)job->w);
            }
            if (s->painted) {
                int st = aa_peer_painter_new("agg", job->placed, job->w, BAND, nullptr,
                                             &s->work->workers.back()->painter);
                if (st) {
                    agg_release(s);
                    return st;
                }
            }
        }
    } catch (const std::bad_alloc &) {
        agg_release(s);
        return aa_fail(AA_ENOMEM, "agg: out of memory for %d rasterizers", s->nthreads);
    } catch (...) {
        agg_release(s);
        return aa_fail(AA_EFAIL, "agg: cannot make its rasterizers");
    }
    return AA_OK;
}

int agg_render(void *state, const double *p, const aa_job *job, aa_image *out,
               aa_counters *counters)
{
    agg_state *s = static_cast<agg_state *>(state);
    counters->samples = 0;
    counters->expensive_pixels = 0;
    int nbands = (job->h + BAND - 1) / BAND, status = AA_OK;
#pragma omp parallel num_threads(s->nthreads)
    {
        worker &wk = *s->work->workers[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nbands; b++) {
            int y0 = b * BAND, rows = y0 + BAND < job->h ? BAND : job->h - y0;
            if (!s->painted && !s->ps.layers) {
                for (int j = y0; j < y0 + rows; j++)
                    aa_peer_fill(out, j, 0, job->w, s->ps.bg);
                continue;
            }
            int st = AA_OK;
            try {
                if (s->painted) {
                    cover_ctx c = {&wk, job->placed, p, job->w, job->h};
                    st = aa_peer_paint_band(wk.painter, job->placed, agg_cover, agg_shade, &c,
                                            out, y0, rows);
                    if (st) {
#pragma omp atomic write
                        status = st;
                    }
                    continue;
                }
                band_cover(wk, job->placed, s->ps, p, job->w, y0, rows);
            } catch (const std::bad_alloc &) {
                st = AA_ENOMEM;
            } catch (...) {
                st = AA_EFAIL;
            }
            if (st) {
#pragma omp atomic write
                status = st;
                continue;
            }
            for (int j = 0; j < rows; j++) {
                const unsigned char *row = wk.band.data() + (size_t)j * (size_t)job->w;
                double *px = aa_pixel(out, 0, y0 + j);
                for (int i = 0; i < job->w; i++, px += 3)
                    px[0] = px[1] = px[2] = s->lut[row[i]];
            }
        }
    }
    if (status == AA_ENOMEM)
        return aa_fail(AA_ENOMEM, "agg: out of memory rasterizing");
    return status ? aa_fail(status, "agg: rasterizing failed") : AA_OK;
}

} // namespace

extern "C" const aa_method_type aa_method_agg = {
    {"agg", "peer: Anti-Grain Geometry's scanline rasterizer (8-bit coverage, arcs flattened)",
     agg_params},
    sizeof(agg_state),
    AA_METHOD_SOME_SCENES | AA_METHOD_GRADIENTS,
    agg_check,
    agg_init,
    agg_render,
    agg_release};
