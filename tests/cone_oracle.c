/*
 * cone_oracle.c: the cone case's picture from SVG 2's definition and the
 * circles' geometry (cone_oracle.h).
 */
#include "cone_oracle.h"

#include <math.h>
#include <string.h>

int co_region(const double p[6], co_half *hp, int *wedge, double apex[2])
{
    long double cx = p[0], cy = p[1], r = p[2], fx = p[3], fy = p[4], fr = p[5];
    long double L = hypotl(cx - fx, cy - fy), ux = (cx - fx) / L, uy = (cy - fy) / L;
    *wedge = 0;
    if (L + r < fr) /* the end circle strictly inside the focal one */
        return 0;
    if (r == fr) { /* the strip |(q - F) x u| <= r */
        hp[0] = (co_half){uy, -ux, r - (uy * fx - ux * fy)};
        hp[1] = (co_half){-uy, ux, r + (uy * fx - ux * fy)};
        return 2;
    }
    /* the wedge from P opening along s u, s the sign of r - fr (towards
     * C when the end circle is the larger) */
    long double px = (r * fx - fr * cx) / (r - fr), py = (r * fy - fr * cy) / (r - fr);
    long double s = r > fr ? 1.0L : -1.0L, sn = fabsl(r - fr) / L;
    long double cs = sqrtl(fmaxl(0.0L, 1.0L - sn * sn));
    *wedge = 1;
    apex[0] = (double)px, apex[1] = (double)py;
    for (int k = 0; k < 2; k++) {
        long double sg = k ? 1.0L : -1.0L;
        /* the tangent's direction: s u turned by +-theta */
        long double dx = s * (ux * cs - sg * uy * sn), dy = s * (uy * cs + sg * ux * sn);
        /* its normal towards the inside: the axis s u is inside */
        long double nx = -dy, ny = dx;
        if (nx * s * ux + ny * s * uy < 0)
            nx = -nx, ny = -ny;
        hp[k] = (co_half){nx, ny, -(nx * px + ny * py)};
    }
    return 2;
}

double co_t(const double p[6], double x, double y)
{
    long double Dx = p[0] - p[3], Dy = p[1] - p[4], dr = p[2] - p[5];
    long double qx = x - p[3], qy = y - p[4];
    /* |q - w D|^2 = (fr + w dr)^2: A w^2 - 2 B w + C = 0 */
    long double A = Dx * Dx + Dy * Dy - dr * dr, B = qx * Dx + qy * Dy + p[5] * dr;
    long double C = qx * qx + qy * qy - (long double)p[5] * p[5], disc = B * B - A * C;
    if (A == 0) { /* one root */
        long double w = C / (2 * B);
        return B != 0 && p[5] + w * dr >= 0 ? (double)w : NAN;
    }
    if (disc < 0)
        return NAN;
    long double w1 = (B + sqrtl(disc)) / A, w2 = (B - sqrtl(disc)) / A;
    if (w1 < w2) {
        long double tmp = w1;
        w1 = w2, w2 = tmp;
    }
    if (p[5] + w1 * dr >= 0)
        return (double)w1;
    if (p[5] + w2 * dr >= 0)
        return (double)w2;
    return NAN;
}

double co_clipped_area(double x0, double y0, double x1, double y1, const co_half *hp, int nh)
{
    long double P[16][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, Q[16][2];
    int n = 4;
    for (int h = 0; h < nh; h++) {
        int m = 0;
        for (int k = 0; k < n; k++) {
            const long double *a = P[k], *b = P[(k + 1) % n];
            long double fa = hp[h].nx * a[0] + hp[h].ny * a[1] + hp[h].k;
            long double fb = hp[h].nx * b[0] + hp[h].ny * b[1] + hp[h].k;
            if (fa >= 0)
                Q[m][0] = a[0], Q[m][1] = a[1], m++;
            if ((fa < 0) != (fb < 0)) {
                long double l = fa / (fa - fb);
                Q[m][0] = a[0] + l * (b[0] - a[0]), Q[m][1] = a[1] + l * (b[1] - a[1]), m++;
            }
        }
        memcpy(P, Q, sizeof P);
        n = m;
    }
    long double A = 0;
    for (int k = 0; k < n; k++)
        A += P[k][0] * P[(k + 1) % n][1] - P[(k + 1) % n][0] * P[k][1];
    return (double)(0.5L * fabsl(A));
}

int co_line_meet(const co_half *h, int col, double at, double *out)
{
    long double a = col ? h->ny : h->nx, b = col ? h->nx : h->ny;
    if (a == 0)
        return 0;
    out[0] = (double)(-(b * at + h->k) / a);
    return 1;
}

int co_circle_meet(const double p[6], double tau, int col, double at, double *out)
{
    double ccx = p[3] + tau * (p[0] - p[3]), ccy = p[4] + tau * (p[1] - p[4]);
    double rr = p[5] + tau * (p[2] - p[5]);
    if (rr < 0)
        return 0;
    double d = at - (col ? ccx : ccy), h = rr * rr - d * d;
    if (h <= 0)
        return 0;
    double c = col ? ccy : ccx;
    out[0] = c - sqrt(h), out[1] = c + sqrt(h);
    return 2;
}

double co_touch_y(const double p[6], double tau, const co_half *h)
{
    double ccx = p[3] + tau * (p[0] - p[3]), ccy = p[4] + tau * (p[1] - p[4]);
    long double nn = h->nx * h->nx + h->ny * h->ny;
    long double f = (h->nx * ccx + h->ny * ccy + h->k) / nn;
    return (double)(ccy - f * h->ny);
}
