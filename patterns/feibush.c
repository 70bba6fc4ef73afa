/*
 * feibush.c: perspective stripes (Feibush, Levoy and Cook 1980, "Synthetic
 * texturing using digital filters", fig. 4; patterns/README.md, `feibush`).
 *
 * A square textured with M = stripes vertical stripes, alternately red
 * (1, 0, 0) and white (1, 1, 1), stripe 0 red, on black.  In texture space
 * (s, t) in [0, 1]^2 stripe m covers s in [m/M, (m+1)/M].  The square is
 * seen through the homography H taking the texture corners (0,0), (1,0),
 * (1,1), (0,1) to (0.32, 0.18), (0.72, 0.24), (0.97, 0.96), (0.04, 0.90).
 * A homography keeps lines straight, so stripe m is exactly the convex
 * quadrilateral H(m/M, 0), H((m+1)/M, 0), H((m+1)/M, 1), H(m/M, 1), and
 * the scene is polygons with an exact reference.  Red stripes form one
 * layer and white stripes another; they share edges but never overlap.
 *
 * H is the square-to-quadrilateral map (Heckbert 1989, "Fundamentals of
 * texture mapping", sec. 2.2.3):
 *   x = (a s + b t + c)/(g s + h t + 1),  y = (d s + e t + f)/(g s + h t + 1).
 *
 * Domain: 1 <= stripes <= FEIBUSH_MAX_STRIPES.
 */
#include "patterns.h"

#define FEIBUSH_MAX_STRIPES 65536

enum { STRIPES };

static const aa_param feibush_params[] = {
    {"stripes", AA_PARAM_INT, 24, 1, FEIBUSH_MAX_STRIPES, 0, NULL,
     "number of stripes across the square, 1 to 65536"},
    {0}};

/* The corners of the square in the pattern, in the order of the texture
 * corners (0,0), (1,0), (1,1), (0,1). */
static const double corner[4][2] = {{0.32, 0.18}, {0.72, 0.24}, {0.97, 0.96}, {0.04, 0.90}};

typedef struct homography {
    double a, b, c, d, e, f, g, h;
} homography;

static homography square_to_quad(void)
{
    const double x0 = corner[0][0], y0 = corner[0][1], x1 = corner[1][0], y1 = corner[1][1];
    const double x2 = corner[2][0], y2 = corner[2][1], x3 = corner[3][0], y3 = corner[3][1];
    double dx1 = x1 - x2, dx2 = x3 - x2, dx3 = x0 - x1 + x2 - x3;
    double dy1 = y1 - y2, dy2 = y3 - y2, dy3 = y0 - y1 + y2 - y3;
    double den = dx1 * dy2 - dx2 * dy1;
    homography H;
    H.g = (dx3 * dy2 - dx2 * dy3) / den;
    H.h = (dx1 * dy3 - dx3 * dy1) / den;
    H.a = x1 - x0 + H.g * x1, H.b = x3 - x0 + H.h * x3, H.c = x0;
    H.d = y1 - y0 + H.g * y1, H.e = y3 - y0 + H.h * y3, H.f = y0;
    return H;
}

static void map(const homography *H, double s, double t, double *x, double *y)
{
    double w = H->g * s + H->h * t + 1.0;
    *x = (H->a * s + H->b * t + H->c) / w;
    *y = (H->d * s + H->e * t + H->f) / w;
}

static int feibush_build(const double *p, aa_scene *s)
{
    const int M = (int)p[STRIPES];
    const homography H = square_to_quad();
    static const aa_rgb colour[2] = {{{1, 0, 0}}, {{1, 1, 1}}};
    int st = AA_OK;
    for (int c = 0; c < 2 && !st; c++) {
        if ((st = aa_scene_layer(s, colour[c], AA_FILL_NONZERO)))
            break;
        for (int m = c; m < M && !st; m += 2) {
            double s0 = (double)m / M, s1 = (double)(m + 1) / M, x[4], y[4];
            map(&H, s0, 0.0, &x[0], &y[0]);
            map(&H, s1, 0.0, &x[1], &y[1]);
            map(&H, s1, 1.0, &x[2], &y[2]);
            map(&H, s0, 1.0, &x[3], &y[3]);
            if ((st = aa_scene_move_to(s, x[0], y[0])) || (st = aa_scene_line_to(s, x[1], y[1])) ||
                (st = aa_scene_line_to(s, x[2], y[2])) || (st = aa_scene_line_to(s, x[3], y[3])))
                break;
            st = aa_scene_close(s);
        }
    }
    return st;
}

const aa_pattern_type aa_pattern_feibush = {
    {"feibush", "Feibush, Levoy and Cook's red and white stripes on a square in perspective",
     feibush_params},
    NULL,
    feibush_build,
    {{0, 0, 0}}};
