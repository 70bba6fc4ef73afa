/*
 * temporal.c: the temporal metrics of an animated run (harness/README.md,
 * "Measuring": error of the eye-integrated image, flicker, conservation of
 * total intensity as a scene moves).
 *
 * The input is a sequence of n displayed frames (what a method shows at
 * times t0, t0 + 1, ..., t0 + n - 1: the single frame for a temporal method
 * rendered with frame_only, the image itself for every other method) and
 * the exact references at the same times.
 *
 *  - eye_rmse: the eye integrates about six frames (Crow 1976, ch. 4).  For
 *    every window of `window` consecutive frames, the mean of the frames
 *    (the eye's image) is compared with the mean of the references of the
 *    same frames (the reference integrated over the same times); eye_rmse is
 *    the root of the mean, over the n - window + 1 windows, of each
 *    window's mean squared error over every channel of every pixel.
 *  - flicker: for each channel of each pixel, the standard deviation over
 *    the n frames of (frame - reference frame), as a population deviation
 *    (divided by n), computed in two passes (mean, then squares about it).
 *    A constant offset gives 0, an offset alternating +e, -e over an even
 *    number of frames gives e.  flicker_mean and flicker_max are its mean
 *    and largest value over pixels and channels.  The reference is taken
 *    away so that a moving scene's own change is not counted as flicker.
 *  - conservation: the total intensity of a frame is the sum over pixels of
 *    the mean of its channels; conservation is (max - min)/mean of it over
 *    the frames (0 when every frame is black).  Area sampling keeps it
 *    constant while the scene stays in the image (Catmull 1978).
 *  - lag: how many frames the frames run behind the scene, the ghosting
 *    or smearing a history causes.  With e_k = frame k - reference k and
 *    d_k = reference k - reference k-1 (the scene's own change, k >= 1),
 *
 *        lag = - sum_k sum_q e_k(q) d_k(q) / sum_k sum_q d_k(q)^2
 *
 *    over every channel q of every pixel: the least-squares d in
 *    e_k = -d d_k, so frames that show the reference d frames late where
 *    it changes linearly (frame k = reference k - d d_k) give d, an error
 *    unrelated to the change gives about 0, and an exponential history
 *    h <- h + alpha (x - h) that follows nothing (no reprojection) gives
 *    up to (1 - alpha)/alpha, its mean age.  0 when the references never
 *    change (nothing can lag).  It can be negative (frames ahead).
 *  - popping (dots): the value of a dot in a frame is the sum over the
 *    pixels whose centre lies within 1.5 pixels (in x and in y) of the dot's
 *    centre at that frame's time, of the mean of the channels.  A dot pops
 *    between two consecutive frames when its value changes by more than half
 *    of its reference value there (the same sum over the references, the
 *    mean of the two frames').  popping is the fraction of (dot, pair of
 *    consecutive frames) that pop.  Point sampling makes small dots blink on
 *    and off (patterns/README.md, `dots`); area sampling never pops.
 *
 * Limits: the frames are whole images held in memory (n of them, plus n
 * references); the harness keeps n at most AA_TEMPORAL_MAX_FRAMES.
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int check_sequence(const aa_image *frames, const aa_image *refs, int n)
{
    if (n < 2 || n > AA_TEMPORAL_MAX_FRAMES)
        return aa_fail(AA_EINVAL, "temporal metrics need 2 to %d frames, not %d",
                       AA_TEMPORAL_MAX_FRAMES, n);
    for (int k = 0; k < n; k++)
        if (frames[k].w != refs[0].w || frames[k].h != refs[0].h || frames[k].c != refs[0].c ||
            refs[k].w != refs[0].w || refs[k].h != refs[0].h || refs[k].c != refs[0].c)
            return aa_fail(AA_EINVAL, "frame %d differs in size from the first reference", k);
    return AA_OK;
}

static double total_intensity(const aa_image *im)
{
    size_t n = (size_t)im->w * im->h;
    double s = 0.0;
    for (size_t p = 0; p < n; p++) {
        double v = 0.0;
        for (int c = 0; c < im->c; c++)
            v += im->v[p * (size_t)im->c + (size_t)c];
        s += v / im->c;
    }
    return s;
}

int aa_temporal_compute(const aa_image *frames, const aa_image *refs, int n, int window,
                        aa_temporal *out)
{
    int st = check_sequence(frames, refs, n);
    if (st)
        return st;
    if (window < 1 || window > n)
        return aa_fail(AA_EINVAL, "eye window %d out of range (1 to the %d frames)", window, n);
    memset(out, 0, sizeof *out);
    out->frames = n;
    out->window = window;
    out->popping = NAN;
    const size_t len = (size_t)refs[0].w * refs[0].h * refs[0].c;

    /* eye: sliding windows */
    double sum = 0.0;
    for (int end = window - 1; end < n; end++) {
        double se = 0.0;
        for (size_t q = 0; q < len; q++) {
            double d = 0.0;
            for (int k = end - window + 1; k <= end; k++)
                d += frames[k].v[q] - refs[k].v[q];
            d /= window;
            se += d * d;
        }
        sum += se / (double)len;
    }
    out->eye_rmse = sqrt(sum / (n - window + 1));

    /* flicker: two passes per channel of each pixel */
    double fsum = 0.0, fbig = 0.0;
    for (size_t q = 0; q < len; q++) {
        double m = 0.0, s2 = 0.0;
        for (int k = 0; k < n; k++)
            m += frames[k].v[q] - refs[k].v[q];
        m /= n;
        for (int k = 0; k < n; k++) {
            double d = frames[k].v[q] - refs[k].v[q] - m;
            s2 += d * d;
        }
        double sd = sqrt(s2 / n);
        fsum += sd;
        fbig = fmax(fbig, sd);
    }
    out->flicker_mean = fsum / (double)len;
    out->flicker_max = fbig;

    /* lag: the least-squares delay of the error along the scene's change */
    double num = 0.0, den = 0.0;
    for (int k = 1; k < n; k++)
        for (size_t q = 0; q < len; q++) {
            double d = refs[k].v[q] - refs[k - 1].v[q];
            num += (frames[k].v[q] - refs[k].v[q]) * d;
            den += d * d;
        }
    out->lag = den > 0.0 ? -num / den : 0.0;

    /* conservation */
    double lo = INFINITY, hi = -INFINITY, mean = 0.0;
    for (int k = 0; k < n; k++) {
        double s = total_intensity(&frames[k]);
        lo = fmin(lo, s);
        hi = fmax(hi, s);
        mean += s / n;
    }
    out->conservation = mean > 0.0 ? (hi - lo) / mean : 0.0;
    return AA_OK;
}

/* A dot's value in one image: the channel mean summed over the pixels
 * whose centre lies within 1.5 px of (x, y) in x and in y. */
static double dot_value(const aa_image *im, double x, double y)
{
    int i0 = (int)ceil(x - 2.0), i1 = (int)floor(x + 1.0);
    int j0 = (int)ceil(y - 2.0), j1 = (int)floor(y + 1.0);
    double s = 0.0;
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < im->h; j++)
        for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < im->w; i++) {
            if (fabs(i + 0.5 - x) > 1.5 || fabs(j + 0.5 - y) > 1.5)
                continue;
            const double *px = aa_pixel(im, i, j);
            double v = 0.0;
            for (int c = 0; c < im->c; c++)
                v += px[c];
            s += v / im->c;
        }
    return s;
}

int aa_temporal_popping(const aa_image *frames, const aa_image *refs, int n, const double *cx,
                        const double *cy, size_t ndots, const double *shift, double *out)
{
    int st = check_sequence(frames, refs, n);
    if (st)
        return st;
    if (ndots == 0)
        return aa_fail(AA_EINVAL, "popping needs at least one dot");
    size_t pops = 0, pairs = 0;
    for (size_t d = 0; d < ndots; d++) {
        double prev = 0.0, prev_ref = 0.0;
        for (int k = 0; k < n; k++) {
            double x = cx[d] + shift[2 * k], y = cy[d] + shift[2 * k + 1];
            double v = dot_value(&frames[k], x, y), r = dot_value(&refs[k], x, y);
            if (k > 0) {
                pairs++;
                pops += fabs(v - prev) > 0.5 * 0.5 * (r + prev_ref);
            }
            prev = v, prev_ref = r;
        }
    }
    *out = (double)pops / (double)pairs;
    return AA_OK;
}
