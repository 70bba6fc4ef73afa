/*
 * edges.c: the error over the edge pixels only.
 *
 * A large flat background, which every method fills exactly, dilutes the
 * RMSE over the whole image: point sampling crow scores 0.18 at 256x256
 * and 0.090 at 1024x1024, the same staircases over four times the pixels,
 * and 0.28 and 0.27 over the edge pixels.  The edge RMSE is the RMSE
 * (linear light, every channel) over the pixels whose filter support meets
 * an edge of the scene, the only pixels where antialiasing has anything to
 * do.  The set is computed from the placed scene's geometry, not from the
 * images: pixel (i, j) is an edge pixel when a piece of the scene (a
 * y-monotone part of an edge, aa_scene_pieces) passes through the inside of
 * the square [i + 1/2 - r, i + 1/2 + r] x [j + 1/2 - r, j + 1/2 + r], r the
 * filter's support radius (aa_filter_support: box 1/2, tent r, cone r, a
 * Gaussian truncated at 3 s).  Decided here: the square is open, so an
 * edge lying exactly on a pixel's border (whose coverage there is 0 or 1)
 * does not make it an edge pixel; every piece counts, even one hidden
 * behind a layer in front (the set is a superset of the pixels whose value
 * is not flat).  For a half-plane x > x0 under the box filter the set is
 * the column floor(x0) when x0 is not an integer, and empty when it is.
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int aa_edge_mask(const aa_scene *placed, double r, int w, int h, unsigned char *mask)
{
    if (!(r > 0) || !isfinite(r))
        return aa_fail(AA_EINVAL, "edge pixels: support radius %g, not a positive number", r);
    memset(mask, 0, (size_t)w * h);
    size_t np;
    const aa_piece *pieces = aa_scene_pieces(placed, &np);
    for (size_t k = 0; k < np; k++) {
        const aa_piece *p = &pieces[k];
        int flat = p->kind == AA_PIECE_FLAT || p->y0 == p->y1;
        /* rows whose open band (j + 1/2 - r, j + 1/2 + r) meets [y0, y1] */
        double jlo = floor(p->y0 - 0.5 - r), jhi = ceil(p->y1 - 0.5 + r);
        if (jhi < 0 || jlo > h - 1)
            continue;
        for (int j = jlo < 0 ? 0 : (int)jlo; j <= (jhi > h - 1 ? h - 1 : (int)jhi); j++) {
            double blo = j + 0.5 - r, bhi = j + 0.5 + r, xl, xr;
            if (flat) {
                if (!(blo < p->y0 && p->y0 < bhi))
                    continue;
                xl = fmin(p->x0, p->x1), xr = fmax(p->x0, p->x1);
            } else {
                double ya = fmax(p->y0, blo), yb = fmin(p->y1, bhi);
                if (!(ya < yb))
                    continue;
                aa_piece_xrange(p, ya, yb, &xl, &xr);
            }
            /* columns whose open interval (i + 1/2 - r, i + 1/2 + r) meets
             * [xl, xr] in more than a point of its border */
            double ilo = floor(xl - 0.5 - r), ihi = ceil(xr - 0.5 + r);
            if (ihi < 0 || ilo > w - 1)
                continue;
            for (int i = ilo < 0 ? 0 : (int)ilo; i <= (ihi > w - 1 ? w - 1 : (int)ihi); i++) {
                double lo = i + 0.5 - r, hi = i + 0.5 + r;
                if (lo < xr && xl < hi)
                    mask[(size_t)j * w + i] = 1;
            }
        }
    }
    return AA_OK;
}

int aa_edge_rmse(const aa_image *ref, const aa_image *img, const unsigned char *mask,
                 double *rmse, size_t *count)
{
    if (ref->w != img->w || ref->h != img->h || ref->c != img->c)
        return aa_fail(AA_EINVAL, "edge RMSE of images of different sizes: %dx%dx%d and %dx%dx%d",
                       ref->w, ref->h, ref->c, img->w, img->h, img->c);
    size_t n = (size_t)ref->w * ref->h, c = (size_t)ref->c, m = 0;
    double s2 = 0;
    for (size_t p = 0; p < n; p++) {
        if (!mask[p])
            continue;
        int finite = 1;
        for (size_t k = p * c; k < (p + 1) * c; k++)
            finite &= isfinite(ref->v[k]) && isfinite(img->v[k]);
        if (!finite)
            continue;
        for (size_t k = p * c; k < (p + 1) * c; k++)
            s2 += (img->v[k] - ref->v[k]) * (img->v[k] - ref->v[k]);
        m++;
    }
    if (count)
        *count = m;
    *rmse = m ? sqrt(s2 / (double)(m * c)) : NAN;
    return AA_OK;
}

int aa_edge_mask_of_image(const aa_image *ref, unsigned char *mask)
{
    int w = ref->w, h = ref->h, c = ref->c;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const double *v = aa_pixel(ref, i, j);
            int edge = 0;
            for (int d = 0; d < 4 && !edge; d++) {
                int x = i + (d == 0) - (d == 1), y = j + (d == 2) - (d == 3);
                if (x < 0 || y < 0 || x >= w || y >= h)
                    continue;
                const double *u = aa_pixel(ref, x, y);
                for (int k = 0; k < c && !edge; k++)
                    edge = u[k] != v[k];
            }
            mask[(size_t)j * w + i] = (unsigned char)edge;
        }
    return AA_OK;
}
