/*
 * fuzz_svg.c: libFuzzer target for the SVG reader (patterns/svgfile.c,
 * `make fuzz`).
 *
 * The input is an SVG document read for a 64 x 48 view.  The reader must
 * return a status and never crash, read out of bounds or leak; what it
 * gives the sink must be well formed (a shape before its first point, every
 * segment inside a subpath begun by a move, every subpath closed, finite
 * coordinates within AA_SVG_MAX_COORD, elliptical arcs whose whole ellipse
 * is within it, alphas and group opacities in [0, 1), an alpha right after
 * its shape, groups balanced and never inside a subpath; clips begun
 * outside any other clip's definition and any subpath, each within an
 * earlier one, ended, and clipping a shape right after it only once
 * ended), and the points, put into a scene as
 * the pattern does, must finish into a scene (cubics are refused by a scene
 * that cannot hold them, which is a status, not a fault).
 */
#include "bench.h"
#include "fuzz.h"
#include "svgfile.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct fuzz_sink {
    aa_scene *s;
    int shapes, open, groups, fresh; /* fresh: a shape with no point yet */
    int clips, in_clip;               /* clips begun; inside one's definition */
} fuzz_sink;

static void fuzz_point(double x, double y)
{
    if (!(fabs(x) <= AA_SVG_MAX_COORD && fabs(y) <= AA_SVG_MAX_COORD))
        abort();
}

static int fz_shape(void *ctx, aa_rgb c, aa_fill_rule rule)
{
    fuzz_sink *f = ctx;
    if (f->open)
        abort();
    for (int k = 0; k < 3; k++)
        if (!(c.c[k] >= 0 && c.c[k] <= 1))
            abort();
    f->shapes++;
    f->fresh = 1;
    return f->in_clip ? aa_scene_clip_layer(f->s, rule) : aa_scene_layer(f->s, c, rule);
}

static int fz_alpha(void *ctx, double a)
{
    fuzz_sink *f = ctx;
    if (!f->fresh || !(a >= 0 && a < 1))
        abort();
    return aa_scene_set_alpha(f->s, a);
}

static int fz_group_begin(void *ctx, double o)
{
    fuzz_sink *f = ctx;
    if (f->open || !(o >= 0 && o < 1))
        abort();
    f->groups++;
    f->fresh = 0;
    return aa_scene_group_begin(f->s, o);
}

static int fz_group_end(void *ctx)
{
    fuzz_sink *f = ctx;
    if (f->open || f->groups < 1)
        abort();
    f->groups--;
    f->fresh = 0;
    return aa_scene_group_end(f->s);
}

static int fz_clip_begin(void *ctx, int within)
{
    fuzz_sink *f = ctx;
    if (f->open || f->in_clip || within < -1 || within >= f->clips)
        abort();
    f->clips++;
    f->in_clip = 1;
    f->fresh = 0;
    return aa_scene_clip_begin(f->s, within);
}

static int fz_clip_end(void *ctx)
{
    fuzz_sink *f = ctx;
    if (f->open || !f->in_clip)
        abort();
    f->in_clip = 0;
    f->fresh = 0;
    return aa_scene_clip_end(f->s, NULL);
}

static int fz_clip(void *ctx, int clip)
{
    fuzz_sink *f = ctx;
    if (!f->fresh || clip < 0 || clip >= f->clips - f->in_clip)
        abort();
    return aa_scene_set_clip(f->s, clip);
}

static int fz_move(void *ctx, double x, double y)
{
    fuzz_sink *f = ctx;
    if (!f->shapes || f->open)
        abort();
    fuzz_point(x, y);
    f->open = 1;
    f->fresh = 0;
    return aa_scene_move_to(f->s, x / 64, y / 48);
}

static int fz_line(void *ctx, double x, double y)
{
    fuzz_sink *f = ctx;
    if (!f->open)
        abort();
    fuzz_point(x, y);
    return aa_scene_line_to(f->s, x / 64, y / 48);
}

static int fz_quad(void *ctx, double cx, double cy, double x, double y)
{
    fuzz_sink *f = ctx;
    if (!f->open)
        abort();
    fuzz_point(cx, cy);
    fuzz_point(x, y);
    return aa_scene_quad_to(f->s, cx / 64, cy / 48, x / 64, y / 48);
}

static int fz_cubic(void *ctx, double a, double b, double c, double d, double x, double y)
{
    fuzz_sink *f = ctx;
    if (!f->open)
        abort();
    fuzz_point(a, b);
    fuzz_point(c, d);
    fuzz_point(x, y);
    return aa_scene_cubic_to(f->s, a / 64, b / 48, c / 64, d / 48, x / 64, y / 48);
}

static int fz_close(void *ctx)
{
    fuzz_sink *f = ctx;
    if (!f->open)
        abort();
    f->open = 0;
    return aa_scene_close(f->s);
}

/* An elliptical arc: its centre and end within the limits, its
 * semi-diameters finite and its ellipse within the limits too. */
static int fz_arc(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                  double t0, double t1, double x, double y)
{
    fuzz_sink *f = ctx;
    if (!f->open)
        abort();
    fuzz_point(cx, cy);
    fuzz_point(x, y);
    fuzz_point(fabs(cx) + hypot(ux, vx), fabs(cy) + hypot(uy, vy));
    if (!isfinite(t0) || !isfinite(t1))
        abort();
    return aa_scene_arc_to(f->s, cx / 64, cy / 48, ux / 64, uy / 48, vx / 64, vy / 48, t0, t1,
                           x / 64, y / 48);
}

/* A gradient right after its shape, outside clips: at least two stops,
 * offsets ascending in [0, 1], opacities in [0, 1], every number finite,
 * its source named (a string); its map to the unit square as the points'. */
static int fz_gradient(void *ctx, const aa_gradient *g, const char *source)
{
    fuzz_sink *f = ctx;
    if (!f->fresh || f->in_clip || g->nstops < 2 || !g->stops || !source)
        abort();
    for (int k = 0; k < g->nstops; k++)
        if (!(g->stops[k].offset >= 0 && g->stops[k].offset <= 1) ||
            (k && g->stops[k].offset < g->stops[k - 1].offset) ||
            !(g->stops[k].opacity >= 0 && g->stops[k].opacity <= 1))
            abort();
    for (int k = 0; k < 6; k++)
        if (!isfinite(g->p[k]) || !isfinite(g->m[k]))
            abort();
    aa_gradient h = *g;
    const double m[6] = {g->m[0] / 64, g->m[1] / 48, g->m[2] / 64,
                         g->m[3] / 48, g->m[4] / 64, g->m[5] / 48};
    memcpy(h.m, m, sizeof m);
    return aa_scene_set_gradient(f->s, &h);
}

/* A gradient's interpolation right after it: linear light, the only one
 * the reader passes on. */
static int fz_interpolation(void *ctx, int interpolation)
{
    fuzz_sink *f = ctx;
    if (interpolation != AA_INTERPOLATE_LINEAR_RGB)
        abort();
    return aa_scene_set_gradient_interpolation(f->s, interpolation);
}

static const aa_svg_sink fuzz_svg_sink = {
    fz_shape, fz_move,        fz_line,      fz_quad,       fz_cubic,     fz_close, fz_arc, NULL,
    fz_alpha, fz_group_begin, fz_group_end, fz_clip_begin, fz_clip_end, fz_clip, fz_gradient,
    fz_interpolation};

int aa_fuzz_svg(const uint8_t *data, size_t size)
{
    fuzz_sink f = {aa_scene_new((aa_rgb){{0, 0, 0}}), 0, 0, 0, 0, 0, 0};
    if (!f.s)
        return 0;
    double vp[2];
    int st = aa_svg_read((const char *)data, size, "fuzz.svg", 64, 48, &fuzz_svg_sink, &f, vp);
    if (st == AA_OK) {
        if (f.open || f.groups || f.in_clip || !(vp[0] > 0 && vp[1] > 0))
            abort();
        int fin = aa_scene_finish(f.s);
        if (fin != AA_OK && fin != AA_EINVAL && fin != AA_ENOMEM)
            abort();
    } else if (st != AA_EINVAL && st != AA_ENOMEM) {
        abort();
    }
    aa_scene_free(f.s);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_svg)
