/*
 * eye.c: what an observer's eye sees of an image on a screen, for the
 * seed papers' comparisons between filters (figures.c, claims.c).
 *
 * The screen shows each pixel as a uniform square one pixel wide (the dot
 * of harness/core/core.h, "Displays"), black outside the image; the eye
 * blurs what it sees with a Gaussian of standard deviation s pixels (it
 * resolves detail up to about 1/(2 pi s) cycles per pixel: Crow 1976,
 * ch. 2, "Sampling": "the observer's eye will always serve as the
 * necessary final low-pass filter").  So the eye's image at a pixel centre
 * is a separable sum over the pixels of their values times
 * (Phi((d + 1/2)/s) - Phi((d - 1/2)/s)) along each axis, d the distance
 * between the centres and Phi the normal distribution function: exact, no
 * sampling.  What the eye sees of the scene itself, the pattern seen
 * through the same Gaussian, is the scene's exact reference under the
 * filter gauss:s=S (harness/README.md, "Ground truth"), so
 *
 *     eye error = eye(shown image) - reference under gauss:s=S
 *
 * is the error an observer sees, whatever filter made the image: the
 * moire of aliasing, a wrong display response, and the blur of the filter
 * itself (a filter wider than the eye's shows as error too).  It is an
 * error of what the eye sees at the pixel centres, in linear light.
 *
 * Weights farther than 6 s from the centre (below 1e-9) are dropped; the
 * kernel is renormalised over the rest, so a uniform image stays uniform
 * inside.
 */
#include "bench.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#define EYE_REACH 6.0

/* The sums over q < n of k[q] p[q step + m], each from 0 in order of q,
 * for m = 0 to 3 (sum4) or m = 0 (sum1). */
static void sum4(const double *k, const double *p, ptrdiff_t step, int n, double *out)
{
    double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
    for (int q = 0; q < n; q++, p += step) {
        const double kq = k[q];
        a0 += kq * p[0];
        a1 += kq * p[1];
        a2 += kq * p[2];
        a3 += kq * p[3];
    }
    out[0] = a0, out[1] = a1, out[2] = a2, out[3] = a3;
}

static double sum1(const double *k, const double *p, ptrdiff_t step, int n)
{
    double a = 0;
    for (int q = 0; q < n; q++, p += step)
        a += k[q] * *p;
    return a;
}

int aa_eye_blur(const aa_image *in, double s, aa_image *out)
{
    if (!(s > 0) || s > 64)
        return aa_fail(AA_EINVAL, "eye: s = %g px out of range (above 0 to 64)", s);
    int r = (int)ceil(EYE_REACH * s), c = in->c, w = in->w, h = in->h;
    double *k = malloc((size_t)(2 * r + 1) * sizeof *k);
    double *tmp = malloc((size_t)w * h * c * sizeof *tmp);
    int st = k && tmp ? aa_image_alloc(out, w, h, c)
                      : aa_fail(AA_ENOMEM, "eye: out of memory for %dx%d", w, h);
    if (st) {
        free(k);
        free(tmp);
        return st;
    }
    double sum = 0;
    for (int d = -r; d <= r; d++) {
        /* Phi(b) - Phi(a) = (erfc(-b/sqrt2) - erfc(-a/sqrt2))/2, cancellation-free
         * on each side of 0 */
        double a = (d - 0.5) / (s * M_SQRT2), b = (d + 0.5) / (s * M_SQRT2);
        double v = d >= 0 ? 0.5 * (erfc(a) - erfc(b)) : 0.5 * (erfc(-b) - erfc(-a));
        k[d + r] = v;
        sum += v;
    }
    for (int d = 0; d <= 2 * r; d++)
        k[d] /= sum;
    /* rows, then columns; outside the image is 0.  Each value is its terms
     * summed in order, from the left (the row pass) and from the top down
     * (the column pass), each into a variable that starts at 0.  Four
     * neighbouring values are summed side by side where they all have
     * every term, so that the loads of a term's weight and of the sums are
     * shared (what costs under AddressSanitizer is the loads). */
    const size_t row = (size_t)w * c;
    /* the values x with every term in the row: pixels r to w - r - 1 */
    const size_t in0 = (size_t)r * c, in1 = w > 2 * r ? (size_t)(w - r) * c : in0;
    for (int j = 0; j < h; j++) {
        const double *in_row = in->v + (size_t)j * row;
        double *t = tmp + (size_t)j * row;
        for (size_t x = 0; x < row;) {
            if (x >= in0 && x + 4 <= in1) {
                sum4(k, in_row + x - in0, c, 2 * r + 1, t + x);
                x += 4;
            } else {
                /* the pixel i of value x: its terms d with 0 <= i + d < w */
                const int i = (int)(x / (size_t)c);
                const int d0 = i < r ? -i : -r, d1 = w - 1 - i < r ? w - 1 - i : r;
                t[x] = sum1(k + d0 + r, in_row + x + (ptrdiff_t)d0 * c, c, d1 - d0 + 1);
                x++;
            }
        }
    }
    for (int j = 0; j < h; j++) {
        double *o = out->v + (size_t)j * row;
        const int lo = j - r < 0 ? 0 : j - r, hi = j + r >= h ? h - 1 : j + r;
        const double *kj = k + (lo - j + r), *t0 = tmp + (size_t)lo * row;
        size_t x = 0;
        for (; x + 4 <= row; x += 4)
            sum4(kj, t0 + x, (ptrdiff_t)row, hi - lo + 1, o + x);
        for (; x < row; x++)
            o[x] = sum1(kj, t0 + x, (ptrdiff_t)row, hi - lo + 1);
    }
    free(k);
    free(tmp);
    return AA_OK;
}

/* What the eye sees of the scene: the exact box values of cells 1/k pixel
 * wide (the view at k times the size, the motion scaled with it), each a
 * uniform square seen through the Gaussian, at the centres of the image's
 * pixels. */
int aa_eye_truth(const aa_spec *pattern, int w, int h, double t, double vx, double vy,
                 double s, const char *cache_dir, int threads, aa_image *out)
{
    if (!(s > 0) || s > 64)
        return aa_fail(AA_EINVAL, "eye: s = %g px out of range (above 0 to 64)", s);
    const int k = w > 512 || h > 512 ? 2 : AA_EYE_CELLS;
    aa_view view;
    aa_image fine = {0};
    memset(&view, 0, sizeof view);
    view.pattern = *pattern;
    view.w = k * w, view.h = k * h;
    view.t = t, view.vx = k * vx, view.vy = k * vy;
    int st = aa_filter_parse("box", &view.filter);
    if (!st)
        st = aa_reference(&view, cache_dir, threads, &fine, NULL, NULL);
    if (st)
        return st;
    /* weights of the fine cells q around a pixel: the Gaussian's integral
     * over each cell, the cell's centre (q + 1/2)/k - (i + 1/2) pixels from
     * the pixel centre; cells beyond EYE_REACH s are dropped and the rest
     * renormalised */
    int r = (int)ceil(EYE_REACH * s * k), c = fine.c;
    int nw = 2 * r + k; /* cells q - k i = -r .. r + k - 1 */
    double *wt = malloc((size_t)nw * sizeof *wt);
    double *tmp = malloc((size_t)w * k * h * c * sizeof *tmp);
    if (!wt || !tmp || (st = aa_image_alloc(out, w, h, c))) {
        free(wt);
        free(tmp);
        aa_image_free(&fine);
        return st ? st : aa_fail(AA_ENOMEM, "eye: out of memory for %dx%d", w, h);
    }
    double sum = 0;
    for (int d = 0; d < nw; d++) {
        double centre = (d - r + 0.5) / k - 0.5; /* cell q = k i + d - r */
        double a = (centre - 0.5 / k) / (s * M_SQRT2), b = (centre + 0.5 / k) / (s * M_SQRT2);
        double v = a >= 0 ? 0.5 * (erfc(a) - erfc(b)) : 0.5 * (erfc(-b) - erfc(-a));
        wt[d] = v;
        sum += v;
    }
    for (int d = 0; d < nw; d++)
        wt[d] /= sum;
    const int fw = k * w, fh = k * h;
    /* rows: each fine row to the coarse columns */
    for (int j = 0; j < fh; j++)
        for (int i = 0; i < w; i++)
            for (int ch = 0; ch < c; ch++) {
                double acc = 0;
                for (int d = 0; d < nw; d++) {
                    int q = k * i + d - r;
                    if (q >= 0 && q < fw)
                        acc += wt[d] * fine.v[((size_t)j * fw + q) * c + ch];
                }
                tmp[((size_t)j * w + i) * c + ch] = acc;
            }
    /* columns: the fine rows to the coarse rows */
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            for (int ch = 0; ch < c; ch++) {
                double acc = 0;
                for (int d = 0; d < nw; d++) {
                    int q = k * j + d - r;
                    if (q >= 0 && q < fh)
                        acc += wt[d] * tmp[((size_t)q * w + i) * c + ch];
                }
                out->v[((size_t)j * w + i) * c + ch] = acc;
            }
    free(wt);
    free(tmp);
    aa_image_free(&fine);
    return AA_OK;
}

int aa_eye_rmse(const aa_image *shown, const aa_image *truth, double s, double *rmse)
{
    if (shown->w != truth->w || shown->h != truth->h || shown->c != truth->c)
        return aa_fail(AA_EINVAL, "eye: images of different sizes");
    aa_image seen;
    int st = aa_eye_blur(shown, s, &seen);
    if (st)
        return st;
    size_t n = (size_t)shown->w * shown->h * shown->c;
    double s2 = 0;
    for (size_t k = 0; k < n; k++) {
        double d = seen.v[k] - truth->v[k];
        s2 += d * d;
    }
    *rmse = sqrt(s2 / (double)n);
    aa_image_free(&seen);
    return AA_OK;
}

/* The image's spectral power with |fx| or |fy| above f0 cycles per pixel:
 * per pixel, the mean over the channels (FFT of the rows, then the
 * columns, as metrics.c).  Content there, just below or at the Nyquist
 * limit, beats with the grid of dots into visible fringes (Crow 1976, ch.
 * 2, "Sampling": "rastering"; Feibush et al. 1980, sec. 3: "Moire is still
 * evident" with the unweighted filter). */
int aa_band_energy(const aa_image *im, double f0, double *out)
{
    int w = im->w, h = im->h, c = im->c;
    size_t n = (size_t)w * h;
    double *z = malloc(2 * n * sizeof *z);
    if (!z)
        return aa_fail(AA_ENOMEM, "out of memory for the spectrum of %dx%d", w, h);
    int st = AA_OK;
    double band = 0;
    for (int ch = 0; ch < c && !st; ch++) {
        for (size_t p = 0; p < n; p++) {
            z[2 * p] = im->v[p * (size_t)c + (size_t)ch];
            z[2 * p + 1] = 0;
        }
        st = aa_fft2(z, w, h);
        for (int j = 0; j < h && !st; j++) {
            double fy = aa_fft_freq(j, h);
            for (int i = 0; i < w; i++) {
                size_t p = (size_t)j * w + i;
                if (aa_fft_freq(i, w) > f0 || fy > f0)
                    band += z[2 * p] * z[2 * p] + z[2 * p + 1] * z[2 * p + 1];
            }
        }
    }
    if (!st)
        *out = band / ((double)n * n) / c;
    free(z);
    return st;
}
