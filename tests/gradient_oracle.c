/*
 * gradient_oracle.c: the gradient pictures of the 2-D quadrature oracles
 * (gradient_oracle.h), from the definitions: SVG 2's linear gradient (t the
 * projection on P1 P2 over |P2 - P1|^2) and radial gradient with fr = 0 (t
 * the largest with |q - F - t D| = t r, D = C - F), sRGB's decoding
 * (IEC 61966-2-1).
 */
#include "gradient_oracle.h"

#include <math.h>
#include <stdlib.h>

const double go_taus[3] = {0.0, GO_T0, 1.0};

double go_dec(double e)
{
    if (e <= 0.0)
        return 0.0;
    if (e >= 1.0)
        return 1.0;
    return e <= GO_T0 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

int go_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double go_pic_t(const go_pic *p, double x, double y)
{
    if (p->radial && p->focal) {
        /* the largest t with |q - F - t D| = t r, D = C - F: A t^2 + 2 b t
         * - c = 0 with A = r^2 - |D|^2 > 0, b = (q - F).D, c = |q - F|^2 */
        double qx = x - p->fx, qy = y - p->fy, Dx = p->cx - p->fx, Dy = p->cy - p->fy;
        double A = p->r * p->r - Dx * Dx - Dy * Dy, b = qx * Dx + qy * Dy, c = qx * qx + qy * qy;
        return (-b + sqrt(b * b + A * c)) / A;
    }
    if (p->radial)
        return hypot(x - p->cx, y - p->cy) / p->r;
    double dx = p->x2 - p->x1, dy = p->y2 - p->y1;
    return ((x - p->x1) * dx + (y - p->y1) * dy) / (dx * dx + dy * dy);
}

double go_pic_at(const go_pic *p, double x, double y)
{
    if (!p->radial && !(x > p->rc[0] && x < p->rc[2] && y > p->rc[1] && y < p->rc[3]))
        return p->bg;
    double t = go_pic_t(p, x, y);
    return go_dec(t < 0 ? 0 : t > 1 ? 1 : t);
}

int go_tau_meet(const go_pic *p, double tau, int col, double at, double *out)
{
    if (p->radial) {
        /* the circle t = tau: centre F + tau D, radius tau r */
        double ccx = p->fx + tau * (p->cx - p->fx), ccy = p->fy + tau * (p->cy - p->fy);
        double rr = tau * p->r, d = col ? at - ccx : at - ccy, h = rr * rr - d * d;
        if (h <= 0)
            return 0;
        double c = col ? ccy : ccx;
        out[0] = c - sqrt(h), out[1] = c + sqrt(h);
        return 2;
    }
    double dx = p->x2 - p->x1, dy = p->y2 - p->y1, l2 = dx * dx + dy * dy;
    double k = col ? dy : dx;
    if (k == 0)
        return 0;
    out[0] = col ? p->y1 + (tau * l2 - (at - p->x1) * dx) / dy
                 : p->x1 + (tau * l2 - (at - p->y1) * dy) / dx;
    return 1;
}

double go_qags_cuts(const gsl_function *F, double *cut, int n, double lo, double hi,
                    double epsabs, double epsrel, gsl_integration_workspace *ws)
{
    qsort(cut, (size_t)n, sizeof *cut, go_cmp_double);
    double sum = 0, res, err;
    for (int k = 0; k + 1 < n; k++) {
        double a = fmax(cut[k], lo), b = fmin(cut[k + 1], hi);
        if (!(b > a))
            continue;
        gsl_integration_qags(F, a, b, epsabs, epsrel, 1000, ws, &res, &err);
        sum += res;
    }
    return sum;
}
