/*
 * path.c: paths as drawn (path.h): building them, the SVG arc command's
 * endpoint parametrisation converted to centre form, and filling a path
 * into a scene through an affine map.
 */
#include "path.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void aa_path_init(aa_path *p)
{
    memset(p, 0, sizeof *p);
}

void aa_path_free(aa_path *p)
{
    if (!p)
        return;
    free(p->seg);
    aa_path_init(p);
}

static int finite2(double x, double y)
{
    return isfinite(x) && isfinite(y);
}

/* Append a segment; p[0..n) copied, the rest 0. */
static int push(aa_path *p, aa_path_op op, const double *v, int n)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 16;
        if (cap > ((size_t)-1) / sizeof *p->seg)
            return aa_fail(AA_EFAIL, "path too long");
        aa_path_seg *seg = realloc(p->seg, cap * sizeof *seg);
        if (!seg)
            return aa_fail(AA_EFAIL, "out of memory for a path of %zu segments", cap);
        p->seg = seg;
        p->cap = cap;
    }
    aa_path_seg *s = &p->seg[p->n++];
    memset(s, 0, sizeof *s);
    s->op = op;
    if (n > 0)
        memcpy(s->p, v, (size_t)n * sizeof *v);
    return AA_OK;
}

int aa_path_move_to(aa_path *p, double x, double y)
{
    if (!finite2(x, y))
        return aa_fail(AA_EINVAL, "path move_to (%g, %g) is not finite", x, y);
    const double v[2] = {x, y};
    int st = push(p, AA_PATH_MOVE, v, 2);
    if (st)
        return st;
    p->startx = p->penx = x;
    p->starty = p->peny = y;
    p->open = 1;
    return AA_OK;
}

/* A drawing command needs a current point: after a close, SVG starts the
 * next subpath at the closed one's start (an implicit move_to there). */
static int need_pen(aa_path *p, const char *what)
{
    if (p->open)
        return AA_OK;
    if (p->n > 0 && p->seg[p->n - 1].op == AA_PATH_CLOSE)
        return aa_path_move_to(p, p->startx, p->starty);
    return aa_fail(AA_EINVAL, "path %s without move_to", what);
}

int aa_path_line_to(aa_path *p, double x, double y)
{
    if (!finite2(x, y))
        return aa_fail(AA_EINVAL, "path line_to (%g, %g) is not finite", x, y);
    int st = need_pen(p, "line_to");
    if (st)
        return st;
    const double v[2] = {x, y};
    if ((st = push(p, AA_PATH_LINE, v, 2)))
        return st;
    p->penx = x;
    p->peny = y;
    return AA_OK;
}

int aa_path_quad_to(aa_path *p, double cx, double cy, double x, double y)
{
    if (!finite2(cx, cy) || !finite2(x, y))
        return aa_fail(AA_EINVAL, "path quad_to (%g, %g) (%g, %g) is not finite", cx, cy, x, y);
    int st = need_pen(p, "quad_to");
    if (st)
        return st;
    const double v[4] = {cx, cy, x, y};
    if ((st = push(p, AA_PATH_QUAD, v, 4)))
        return st;
    p->penx = x;
    p->peny = y;
    return AA_OK;
}

int aa_path_cubic_to(aa_path *p, double c1x, double c1y, double c2x, double c2y, double x,
                     double y)
{
    if (!finite2(c1x, c1y) || !finite2(c2x, c2y) || !finite2(x, y))
        return aa_fail(AA_EINVAL, "path cubic_to (%g, %g) (%g, %g) (%g, %g) is not finite", c1x,
                       c1y, c2x, c2y, x, y);
    int st = need_pen(p, "cubic_to");
    if (st)
        return st;
    const double v[6] = {c1x, c1y, c2x, c2y, x, y};
    if ((st = push(p, AA_PATH_CUBIC, v, 6)))
        return st;
    p->penx = x;
    p->peny = y;
    return AA_OK;
}

/* The checks of aa_scene_arc_to (core.h): finite numbers, |t1 - t0| at
 * most 2 pi (beyond rounding), u and v not parallel, the pen the point for
 * t0 and (x, y) the point for t1 within 1e-9 of the size |u| + |v|. */
int aa_path_arc_to(aa_path *p, double cx, double cy, double ux, double uy, double vx, double vy,
                   double t0, double t1, double x, double y)
{
    if (!finite2(cx, cy) || !finite2(ux, uy) || !finite2(vx, vy) || !finite2(t0, t1) ||
        !finite2(x, y))
        return aa_fail(AA_EINVAL, "path arc_to: a number is not finite");
    int st = need_pen(p, "arc_to");
    if (st)
        return st;
    const double twopi = 2.0 * M_PI;
    if (!(fabs(t1 - t0) <= twopi * (1.0 + 1e-12)))
        return aa_fail(AA_EINVAL, "path arc_to: the sweep %.17g is more than 2 pi", t1 - t0);
    double size = hypot(ux, uy) + hypot(vx, vy);
    double cross = ux * vy - uy * vx;
    if (!(fabs(cross) > 1e-12 * size * size))
        return aa_fail(AA_EINVAL, "path arc_to: u (%g, %g) and v (%g, %g) are parallel "
                                  "(a degenerate ellipse: draw its lines instead)",
                       ux, uy, vx, vy);
    double tol = 1e-9 * size;
    double ax = cx + ux * cos(t0) + vx * sin(t0), ay = cy + uy * cos(t0) + vy * sin(t0);
    double bx = cx + ux * cos(t1) + vx * sin(t1), by = cy + uy * cos(t1) + vy * sin(t1);
    if (hypot(ax - p->penx, ay - p->peny) > tol)
        return aa_fail(AA_EINVAL, "path arc_to: the pen (%.17g, %.17g) is not the arc's start "
                                  "(%.17g, %.17g)",
                       p->penx, p->peny, ax, ay);
    if (hypot(bx - x, by - y) > tol)
        return aa_fail(AA_EINVAL, "path arc_to: the end (%.17g, %.17g) is not the arc's end "
                                  "(%.17g, %.17g)",
                       x, y, bx, by);
    if (t0 == t1)
        return AA_OK;
    const double v[10] = {cx, cy, ux, uy, vx, vy, t0, t1, x, y};
    if ((st = push(p, AA_PATH_ARC, v, 10)))
        return st;
    p->penx = x;
    p->peny = y;
    return AA_OK;
}

int aa_path_offset_to(aa_path *p, const aa_offset_curve *oc, double t0, double t1, double x,
                      double y)
{
    double v[15];
    memcpy(v, oc->b, 8 * sizeof *v);
    v[8] = oc->d, v[9] = oc->evolute ? 1 : 0, v[10] = t0, v[11] = t1, v[12] = x, v[13] = y;
    v[14] = oc->base;
    for (int k = 0; k < 15; k++)
        if (!isfinite(v[k]))
            return aa_fail(AA_EINVAL, "path offset_to: a number is not finite");
    int st = need_pen(p, "offset_to");
    if (st)
        return st;
    if ((st = push(p, AA_PATH_OFFSET, v, 15)))
        return st;
    p->penx = x;
    p->peny = y;
    return AA_OK;
}

int aa_path_close(aa_path *p)
{
    if (!p->open) {
        if (p->n > 0 && p->seg[p->n - 1].op == AA_PATH_CLOSE)
            return AA_OK; /* closed already */
        return aa_fail(AA_EINVAL, "path close without move_to");
    }
    int st = push(p, AA_PATH_CLOSE, NULL, 0);
    if (st)
        return st;
    p->penx = p->startx;
    p->peny = p->starty;
    p->open = 0;
    return AA_OK;
}

/* ---- the SVG arc command (SVG 1.1 F.6.5, F.6.6) ---- */

/* cos and sin of phi degrees, exact at multiples of 90 degrees. */
static void degrees_cos_sin(double phi, double *c, double *s)
{
    double d = fmod(phi, 360.0);
    if (d < 0)
        d += 360.0;
    if (d == 0.0) {
        *c = 1, *s = 0;
    } else if (d == 90.0) {
        *c = 0, *s = 1;
    } else if (d == 180.0) {
        *c = -1, *s = 0;
    } else if (d == 270.0) {
        *c = 0, *s = -1;
    } else {
        double r = d * (M_PI / 180.0);
        *c = cos(r);
        *s = sin(r);
    }
}

/*
 * F.6.5 and F.6.6, in the frame of the ellipse's axes (primed): the half
 * chord (x1', y1') = R(-phi) ((x0 - x1)/2, (y0 - y1)/2).  With
 * Lambda = x1'^2/rx^2 + y1'^2/ry^2 the radii are scaled by sqrt(Lambda) when
 * Lambda > 1 (F.6.6 step 3), after which Lambda = 1.  The centre (F.6.5.2)
 *     c' = +-sqrt((rx^2 ry^2 - rx^2 y1'^2 - ry^2 x1'^2) /
 *                 (rx^2 y1'^2 + ry^2 x1'^2)) (rx y1'/ry, -ry x1'/rx),
 * the sign + when large != sweep; since rx^2 y1'^2 + ry^2 x1'^2 is
 * rx^2 ry^2 Lambda, the root is sqrt(1/Lambda - 1), without the
 * cancellation of the difference.  c = R(phi) c' + the chord's midpoint.
 * On the unit circle the start is a = ((x1' - cx')/rx, (y1' - cy')/ry) and
 * the end b = ((-x1' - cx')/rx, (-y1' - cy')/ry): theta1 = angle of a,
 * dtheta = the angle from a to b (atan2 of their cross and dot products),
 * made negative when sweep = 0 and positive when sweep = 1 (F.6.5.6).  The
 * ellipse is c + rx cos t (cos phi, sin phi) + ry sin t (-sin phi, cos phi):
 * u = rx (cos phi, sin phi), v = ry (-sin phi, cos phi), t from theta1 to
 * theta1 + dtheta.
 */
int aa_arc_endpoints(double x0, double y0, double rx, double ry, double phi, int large,
                     int sweep, double x1, double y1, double c[8], aa_arc_kind *kind)
{
    *kind = AA_ARC_NONE;
    if (!finite2(x0, y0) || !finite2(x1, y1) || !finite2(rx, ry) || !isfinite(phi))
        return aa_fail(AA_EINVAL, "SVG arc: a number is not finite");
    if (x0 == x1 && y0 == y1)
        return AA_OK; /* F.6.2: the ends are equal, nothing is drawn */
    rx = fabs(rx);
    ry = fabs(ry);
    if (rx == 0 || ry == 0) {
        *kind = AA_ARC_LINE; /* F.6.2: a straight line */
        return AA_OK;
    }
    double cp, sp;
    degrees_cos_sin(phi, &cp, &sp);
    double hx = 0.5 * (x0 - x1), hy = 0.5 * (y0 - y1);
    double x1p = cp * hx + sp * hy, y1p = -sp * hx + cp * hy;
    /* Lambda by the ratios, which neither overflow nor underflow early. */
    double qx = x1p / rx, qy = y1p / ry;
    double lambda = qx * qx + qy * qy;
    double root = 0;
    if (lambda > 1) {
        double k = sqrt(lambda);
        rx *= k;
        ry *= k;
    } else {
        root = sqrt(fmax(0.0, 1.0 / lambda - 1.0));
        if (large == sweep)
            root = -root;
    }
    double cxp = root * rx * (y1p / ry), cyp = -root * ry * (x1p / rx);
    double mx = 0.5 * (x0 + x1), my = 0.5 * (y0 + y1);
    double cx = cp * cxp - sp * cyp + mx, cy = sp * cxp + cp * cyp + my;
    double ax = (x1p - cxp) / rx, ay = (y1p - cyp) / ry;
    double bx = (-x1p - cxp) / rx, by = (-y1p - cyp) / ry;
    double theta1 = atan2(ay, ax);
    double dtheta = atan2(ax * by - ay * bx, ax * bx + ay * by);
    if (!sweep && dtheta > 0)
        dtheta -= 2.0 * M_PI;
    else if (sweep && dtheta < 0)
        dtheta += 2.0 * M_PI;
    c[0] = cx;
    c[1] = cy;
    c[2] = rx * cp;
    c[3] = rx * sp;
    c[4] = -ry * sp;
    c[5] = ry * cp;
    c[6] = theta1;
    c[7] = theta1 + dtheta;
    for (int i = 0; i < 8; i++)
        if (!isfinite(c[i]))
            return aa_fail(AA_EINVAL, "SVG arc from (%g, %g) to (%g, %g) radii (%g, %g): the "
                                      "ellipse is out of range",
                           x0, y0, x1, y1, rx, ry);
    *kind = AA_ARC_CURVE;
    return AA_OK;
}

/* ---- filling ---- */

static void map_point(const double m[6], double x, double y, double *ox, double *oy)
{
    if (!m) {
        *ox = x, *oy = y;
        return;
    }
    *ox = m[0] * x + m[2] * y + m[4];
    *oy = m[1] * x + m[3] * y + m[5];
}

static void map_vector(const double m[6], double x, double y, double *ox, double *oy)
{
    if (!m) {
        *ox = x, *oy = y;
        return;
    }
    *ox = m[0] * x + m[2] * y;
    *oy = m[1] * x + m[3] * y;
}

/* An affine map takes c + u cos t + v sin t to m(c) + L u cos t + L v sin t
 * (L its linear part): the same t, the centre mapped, u and v by L. */
int aa_path_fill(const aa_path *path, const double m[6], aa_scene *s)
{
    if (m)
        for (int i = 0; i < 6; i++)
            if (!isfinite(m[i]))
                return aa_fail(AA_EINVAL, "path fill: the map is not finite");
    for (size_t i = 0; i < path->n; i++) {
        const aa_path_seg *g = &path->seg[i];
        const double *p = g->p;
        double x, y, ax, ay, bx, by, ux, uy, vx, vy;
        int st = AA_OK;
        switch (g->op) {
        case AA_PATH_MOVE:
            map_point(m, p[0], p[1], &x, &y);
            st = aa_scene_move_to(s, x, y);
            break;
        case AA_PATH_LINE:
            map_point(m, p[0], p[1], &x, &y);
            st = aa_scene_line_to(s, x, y);
            break;
        case AA_PATH_QUAD:
            map_point(m, p[0], p[1], &ax, &ay);
            map_point(m, p[2], p[3], &x, &y);
            st = aa_scene_quad_to(s, ax, ay, x, y);
            break;
        case AA_PATH_CUBIC:
            map_point(m, p[0], p[1], &ax, &ay);
            map_point(m, p[2], p[3], &bx, &by);
            map_point(m, p[4], p[5], &x, &y);
            st = aa_scene_cubic_to(s, ax, ay, bx, by, x, y);
            break;
        case AA_PATH_ARC:
            map_point(m, p[0], p[1], &ax, &ay);
            map_vector(m, p[2], p[3], &ux, &uy);
            map_vector(m, p[4], p[5], &vx, &vy);
            map_point(m, p[8], p[9], &x, &y);
            st = aa_scene_arc_to(s, ax, ay, ux, uy, vx, vy, p[6], p[7], x, y);
            break;
        case AA_PATH_OFFSET: {
            aa_offset_curve oc = {{0}, {1, 0, 0, 1, 0, 0}, p[8], p[9] != 0, (int)p[14]};
            memcpy(oc.b, p, sizeof oc.b);
            if (m)
                memcpy(oc.m, m, sizeof oc.m);
            map_point(m, p[12], p[13], &x, &y);
            st = aa_scene_offset_to(s, &oc, p[10], p[11], x, y);
            break;
        }
        case AA_PATH_CLOSE:
            st = aa_scene_close(s);
            break;
        default:
            st = aa_fail(AA_EINVAL, "path segment %zu: unknown operation %d", i, (int)g->op);
        }
        if (st)
            return st;
    }
    return aa_scene_close(s);
}
