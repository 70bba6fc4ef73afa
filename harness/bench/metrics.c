/*
 * metrics.c: error of an image against its reference (harness/README.md,
 * "Measuring").
 *
 *  - rmse, mae, max_err (and where), psnr = 10 log10(1 / mse): over every
 *    channel of every pixel, in linear light, and again after display
 *    encoding (sRGB, or Crow's square law: gamma:2);
 *  - aliasing energy: the power spectrum of the error image (the mean of its
 *    channels), by GSL's mixed-radix FFT of the rows then the columns.  The
 *    total equals the mean squared error of that channel mean (Parseval);
 *    it is split at half the Nyquist frequency: `alias_low` holds the
 *    frequencies below 1/4 cycle per pixel (in x and y), where aliased
 *    detail shows as moire, `alias_high` the band from there to the Nyquist
 *    frequency, where staircases and sample noise live;
 *  - SSIM (Wang, Bovik, Sheikh and Simoncelli 2004) on the display-encoded
 *    luma (Rec. 709 weights), 11x11 Gaussian window of s = 1.5, C1 =
 *    (0.01)^2, C2 = (0.03)^2, values in [0, 1]; the mean over the pixels
 *    whose window fits in the image (all pixels, window clipped and
 *    renormalised, for images smaller than 11 pixels).
 *
 * aa_metrics_compute refuses images holding NaN or infinities (a method
 * that makes one has failed); aa_metrics_compare, for image files, counts
 * the pixels where either image holds one instead, and leaves them out:
 * of the pointwise errors, and of the spectrum and SSIM as if both images
 * were 0 there.  When no pixel is left, every figure is NaN (none).
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fft_complex.h>

/* 1 if every channel of pixel p of both images is finite. */
static int pixel_finite(const aa_image *ref, const aa_image *img, size_t p)
{
    size_t c = (size_t)ref->c;
    for (size_t k = p * c; k < (p + 1) * c; k++)
        if (!isfinite(ref->v[k]) || !isfinite(img->v[k]))
            return 0;
    return 1;
}

/* The pointwise errors over the pixels where both images are finite.  The
 * sums are taken again relative to the largest error when they underflow
 * (errors below 1e-154 square to nothing) or overflow, so that images that
 * differ never get the rmse 0 and infinite PSNR of identical ones. */
static void pointwise(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                      size_t nonfinite, int nonfinite_differ, double *rmse, double *mae,
                      double *max_err, int *where, double *psnr)
{
    size_t pixels = (size_t)ref->w * ref->h, c = (size_t)ref->c, n = 0;
    double s2 = 0, s1 = 0, mx = -1;
    size_t at = 0;
    for (size_t p = 0; p < pixels; p++) {
        if (nonfinite && !pixel_finite(ref, img, p))
            continue;
        for (size_t k = p * c; k < (p + 1) * c; k++) {
            double a = ref->v[k], b = img->v[k];
            if (enc)
                a = aa_encode_value(enc, a), b = aa_encode_value(enc, b);
            double d = fabs(b - a);
            s1 += d;
            s2 += d * d;
            if (d > mx)
                mx = d, at = k;
        }
        n += c;
    }
    where[2] = (int)(at % c);
    at /= c;
    where[0] = (int)(at % (size_t)ref->w);
    where[1] = (int)(at / (size_t)ref->w);
    if (n == 0) { /* no finite pixel */
        *mae = *rmse = *max_err = *psnr = NAN;
        where[0] = where[1] = where[2] = -1;
        return;
    }
    *max_err = mx;
    double mse = s2 / (double)n;
    *mae = s1 / (double)n;
    *rmse = sqrt(mse);
    if (mx > 0 && isfinite(mx) && (!(mse > 1e-290) || !isfinite(s2) || !isfinite(s1))) {
        double r2 = 0, r1 = 0;
        for (size_t p = 0; p < pixels; p++) {
            if (nonfinite && !pixel_finite(ref, img, p))
                continue;
            for (size_t k = p * c; k < (p + 1) * c; k++) {
                double a = ref->v[k], b = img->v[k];
                if (enc)
                    a = aa_encode_value(enc, a), b = aa_encode_value(enc, b);
                double d = fabs(b - a) / mx;
                r1 += d;
                r2 += d * d;
            }
        }
        *mae = mx * (r1 / (double)n);
        *rmse = mx * sqrt(r2 / (double)n);
        *psnr = -20.0 * (log10(mx) + 0.5 * log10(r2 / (double)n));
        return;
    }
    if (mx > 0)
        *psnr = 10.0 * log10(1.0 / mse);
    else /* equal where finite: identical unless they differ elsewhere */
        *psnr = nonfinite_differ ? NAN : INFINITY;
}

int aa_fft2(double *z, int w, int h)
{
    gsl_fft_complex_wavetable *tw = gsl_fft_complex_wavetable_alloc((size_t)w);
    gsl_fft_complex_wavetable *th = gsl_fft_complex_wavetable_alloc((size_t)h);
    /* GSL wants a workspace of each transform's own length */
    gsl_fft_complex_workspace *ws = gsl_fft_complex_workspace_alloc((size_t)w);
    gsl_fft_complex_workspace *wh = gsl_fft_complex_workspace_alloc((size_t)h);
    int st = AA_OK;
    if (!tw || !th || !ws || !wh)
        st = aa_fail(AA_ENOMEM, "out of memory for the spectrum of %dx%d", w, h);
    for (int j = 0; j < h && !st; j++)
        if (gsl_fft_complex_forward(z + 2 * (size_t)j * w, 1, (size_t)w, tw, ws))
            st = aa_fail(AA_EFAIL, "FFT of row %d failed", j);
    for (int i = 0; i < w && !st; i++)
        if (gsl_fft_complex_forward(z + 2 * (size_t)i, (size_t)w, (size_t)h, th, wh))
            st = aa_fail(AA_EFAIL, "FFT of column %d failed", i);
    if (tw)
        gsl_fft_complex_wavetable_free(tw);
    if (th)
        gsl_fft_complex_wavetable_free(th);
    if (ws)
        gsl_fft_complex_workspace_free(ws);
    if (wh)
        gsl_fft_complex_workspace_free(wh);
    return st;
}

/* FFT of the channel-mean error; energies per pixel. */
static int spectrum(const aa_image *ref, const aa_image *img, aa_metrics *m)
{
    int w = ref->w, h = ref->h, c = ref->c;
    size_t n = (size_t)w * h;
    double *z = malloc(2 * n * sizeof *z);
    if (!z)
        return aa_fail(AA_ENOMEM, "out of memory for the error spectrum of %dx%d", w, h);
    for (size_t p = 0; p < n; p++) {
        double e = 0;
        if (!m->nonfinite || pixel_finite(ref, img, p))
            for (int k = 0; k < c; k++)
                e += img->v[p * (size_t)c + (size_t)k] - ref->v[p * (size_t)c + (size_t)k];
        z[2 * p] = e / c;
        z[2 * p + 1] = 0;
    }
    int st = aa_fft2(z, w, h);
    double low = 0, high = 0;
    for (int j = 0; j < h && !st; j++) {
        double fy = aa_fft_freq(j, h);
        for (int i = 0; i < w; i++) {
            double fx = aa_fft_freq(i, w);
            size_t p = (size_t)j * w + i;
            double power = z[2 * p] * z[2 * p] + z[2 * p + 1] * z[2 * p + 1];
            if (fx < 0.25 && fy < 0.25)
                low += power;
            else
                high += power;
        }
    }
    /* Parseval: sum |Z|^2 = n sum |e|^2, so per pixel divide by n^2 */
    m->alias_low = low / ((double)n * n);
    m->alias_high = high / ((double)n * n);
    m->alias_total = m->alias_low + m->alias_high;
    free(z);
    return st;
}

static double luma(const aa_image *im, size_t p, const aa_encode *enc)
{
    const double *v = im->v + p * (size_t)im->c;
    double y = im->c >= 3 ? 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2] : v[0];
    return aa_encode_value(enc, y);
}

static int ssim(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                size_t nonfinite, double *out)
{
    const int r = 5;
    const double C1 = 1e-4, C2 = 9e-4;
    int w = ref->w, h = ref->h;
    size_t n = (size_t)w * h;
    double g[11], *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    if (!a || !b) {
        free(a);
        free(b);
        return aa_fail(AA_ENOMEM, "out of memory for SSIM");
    }
    for (int k = -r; k <= r; k++)
        g[k + r] = exp(-k * k / (2 * 1.5 * 1.5));
    for (size_t p = 0; p < n; p++) {
        if (nonfinite && !pixel_finite(ref, img, p))
            a[p] = b[p] = 0; /* left out: the same in both */
        else
            a[p] = luma(ref, p, enc), b[p] = luma(img, p, enc);
    }
    int inner = w > 2 * r && h > 2 * r;
    double sum = 0;
    size_t count = 0;
    for (int j = inner ? r : 0; j < (inner ? h - r : h); j++)
        for (int i = inner ? r : 0; i < (inner ? w - r : w); i++) {
            double sw = 0, ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
            for (int dj = -r; dj <= r; dj++) {
                if (j + dj < 0 || j + dj >= h)
                    continue;
                for (int di = -r; di <= r; di++) {
                    if (i + di < 0 || i + di >= w)
                        continue;
                    double wt = g[dj + r] * g[di + r];
                    size_t p = (size_t)(j + dj) * w + (size_t)(i + di);
                    sw += wt;
                    ma += wt * a[p], mb += wt * b[p];
                    aa += wt * a[p] * a[p], bb += wt * b[p] * b[p], ab += wt * a[p] * b[p];
                }
            }
            ma /= sw, mb /= sw;
            double va = aa / sw - ma * ma, vb = bb / sw - mb * mb, cov = ab / sw - ma * mb;
            sum += ((2 * ma * mb + C1) * (2 * cov + C2)) /
                   ((ma * ma + mb * mb + C1) * (va + vb + C2));
            count++;
        }
    free(a);
    free(b);
    *out = sum / (double)count;
    return AA_OK;
}

/* FLIP, the pixels left out (not finite in either image) set to 0 in both
 * copies when there are any. */
static int flip(const aa_image *ref, const aa_image *img, const aa_encode *enc, aa_metrics *m)
{
    if (!m->nonfinite)
        return aa_flip(ref, img, enc, AA_FLIP_PPD, &m->flip, NULL);
    aa_image a, b;
    int st = aa_image_alloc(&a, ref->w, ref->h, ref->c);
    if (st)
        return st;
    if ((st = aa_image_alloc(&b, ref->w, ref->h, ref->c))) {
        aa_image_free(&a);
        return st;
    }
    size_t pixels = (size_t)ref->w * ref->h, c = (size_t)ref->c;
    for (size_t p = 0; p < pixels; p++) {
        int keep = pixel_finite(ref, img, p);
        for (size_t k = p * c; k < (p + 1) * c; k++)
            a.v[k] = keep ? ref->v[k] : 0, b.v[k] = keep ? img->v[k] : 0;
    }
    st = aa_flip(&a, &b, enc, AA_FLIP_PPD, &m->flip, NULL);
    aa_image_free(&a);
    aa_image_free(&b);
    return st;
}

int aa_metrics_edges(const aa_scene *placed, double r, const aa_image *ref, const aa_image *img,
                     aa_metrics *m)
{
    unsigned char *mask = malloc((size_t)ref->w * ref->h);
    if (!mask)
        return aa_fail(AA_ENOMEM, "out of memory for the edge pixels of %dx%d", ref->w, ref->h);
    int st = placed ? aa_edge_mask(placed, r, ref->w, ref->h, mask)
                    : aa_edge_mask_of_image(ref, mask);
    if (!st)
        st = aa_edge_rmse(ref, img, mask, &m->edge_rmse, &m->edge_pixels);
    free(mask);
    return st;
}

static int metrics(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                   int count_nonfinite, aa_metrics *m)
{
    aa_encode srgb = {AA_ENCODE_SRGB, 0};
    if (!enc)
        enc = &srgb;
    if (ref->w != img->w || ref->h != img->h || ref->c != img->c)
        return aa_fail(AA_EINVAL, "images differ in size: %dx%dx%d and %dx%dx%d", ref->w, ref->h,
                       ref->c, img->w, img->h, img->c);
    memset(m, 0, sizeof *m);
    size_t pixels = (size_t)ref->w * ref->h, c = (size_t)ref->c;
    int differ = 0; /* where not finite: not the same NaN or infinity in both */
    for (size_t p = 0; p < pixels; p++) {
        if (pixel_finite(ref, img, p))
            continue;
        for (size_t k = p * c; k < (p + 1) * c; k++)
            differ |= !(ref->v[k] == img->v[k] || (isnan(ref->v[k]) && isnan(img->v[k])));
        if (!count_nonfinite) {
            size_t k = p * (size_t)ref->c;
            while (isfinite(ref->v[k]) && isfinite(img->v[k]))
                k++;
            return aa_fail(AA_EINVAL, "%s pixel (%zu, %zu) channel %zu is %g, not finite",
                           isfinite(ref->v[k]) ? "image" : "reference", p % (size_t)ref->w,
                           p / (size_t)ref->w, k % (size_t)ref->c,
                           isfinite(ref->v[k]) ? img->v[k] : ref->v[k]);
        }
        m->nonfinite++;
    }
    m->edge_rmse = m->flip = NAN;
    if (m->nonfinite == pixels) { /* nothing to compare: no figure at all */
        m->rmse = m->mae = m->max_err = m->psnr = NAN;
        m->rmse_enc = m->mae_enc = m->max_err_enc = m->psnr_enc = NAN;
        m->alias_total = m->alias_low = m->alias_high = m->ssim = NAN;
        m->max_at[0] = m->max_at[1] = m->max_at[2] = -1;
        return AA_OK;
    }
    pointwise(ref, img, NULL, m->nonfinite, differ, &m->rmse, &m->mae, &m->max_err, m->max_at,
              &m->psnr);
    int where[3];
    pointwise(ref, img, enc, m->nonfinite, differ, &m->rmse_enc, &m->mae_enc, &m->max_err_enc,
              where, &m->psnr_enc);
    gsl_set_error_handler_off();
    int st = spectrum(ref, img, m);
    if (!st)
        st = ssim(ref, img, enc, m->nonfinite, &m->ssim);
    return st ? st : flip(ref, img, enc, m);
}

int aa_metrics_compute(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                       aa_metrics *m)
{
    return metrics(ref, img, enc, 0, m);
}

int aa_metrics_compare(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                       aa_metrics *m)
{
    return metrics(ref, img, enc, 1, m);
}

double aa_metrics_bytes(int w, int h)
{
    /* the spectrum's complex image (freed before SSIM's two lumas, as
     * large), and GSL's tables and workspaces for a row and a column */
    double spectrum = 2.0 * w * h * sizeof(double) + 64.0 * ((double)w + h);
    double flip = aa_flip_bytes(w, h) + 2.0 * w * h * 3 * sizeof(double);
    return spectrum > flip ? spectrum : flip;
}
