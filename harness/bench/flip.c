/*
 * flip.c: LDR-FLIP, the perceived difference of two images flipped between
 * on a display (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and
 * Fairchild 2020, "FLIP: A Difference Evaluator for Alternating Images",
 * Proc. ACM Comput. Graph. Interact. Tech. 3(2), article 15), step by step
 * as the paper defines it, with its erratum (its publication page: on p. 10,
 * the achromatic channel is divided by 116, not 100).  Every constant below
 * is the paper's and the same in the authors' published implementations
 * (their 2020 C++ release and their NumPy version).
 *
 *  - Viewing condition: pixels per degree ppd = d (n / w) pi / 180 for a
 *    monitor w metres wide of n pixels seen from d metres; the paper's
 *    default, d = w = 0.7 m and n = 3840, is 67.02 (AA_FLIP_PPD).
 *  - Colour pipeline, spatial filtering: each image's linear RGB (sRGB
 *    primaries) to XYZ, to the opponent space YyCxCz against the display's
 *    white, RGB (1, 1, 1), that is D65: Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn -
 *    Y/Yn), Cz = 200 (Y/Yn - Z/Zn).  Each channel is convolved with its
 *    contrast sensitivity function, the sum of two Gaussians in frequency,
 *    A(f) = a1 e^(-b1 f^2) + a2 e^(-b2 f^2), in space S(x) = a1 sqrt(pi/b1)
 *    e^(-pi^2 x^2/b1) + a2 sqrt(pi/b2) e^(-pi^2 x^2/b2), x the distance in
 *    degrees (pixels / ppd); (a1, b1, a2, b2) = (1, 0.0047, 0, 1e-5)
 *    achromatic, (1, 0.0053, 0, 1e-5) red-green, (34.1, 0.04, 13.5, 0.025)
 *    blue-yellow.  The kernel is S on the (2 r + 1)^2 pixels around the
 *    centre, r = ceil(3 sqrt(bmax / (2 pi^2)) ppd) with bmax = 0.04 the
 *    largest b of all three (r = 10 at 67 ppd), normalised to sum 1.
 *  - Colour pipeline, perceptually uniform space: the filtered image back
 *    to linear RGB, clamped to [0, 1], to CIELAB (the same white; CIE 15's
 *    f with its exact 6/29), then the Hunt adjustment a* <- 0.01 L* a*,
 *    b* <- 0.01 L* b*.
 *  - Colour metric: HyAB, |dL*| + sqrt(da*^2 + db*^2), raised to qc = 0.7;
 *    cmax, the largest such difference, is green's against blue's (41.28);
 *    the error is mapped to [0, pt] linearly up to pc cmax, then linearly
 *    to [pt, 1] up to cmax, pc = 0.4, pt = 0.95: dEc in [0, 1].
 *  - Feature pipeline, on the unfiltered achromatic channel normalised to
 *    [0, 1], (Yy + 16) / 116 = Y/Yn: edges by the first derivative of a
 *    Gaussian, points by its second, sigma = w/2 ppd pixels with w = 0.082
 *    degrees (2.75 pixels at 67 ppd), radius ceil(3 sigma); the x kernels
 *    are -x g(x, y) and (x^2/sigma^2 - 1) g(x, y), each normalised so that
 *    its positive weights sum to 1 and its negative ones to -1, the y
 *    kernels their transposes; the feature difference is dEf =
 *    (max(| |e_r| - |e_t| |, | |p_r| - |p_t| |) / sqrt 2)^qf, qf = 0.5, |.|
 *    the magnitude of the (x, y) responses, in [0, 1].
 *  - Final difference: FLIP = dEc^(1 - dEf) per pixel, in [0, 1].
 *
 * Variants, where this file chooses otherwise than the paper:
 *  - the single number is the mean over the pixels, not the paper's
 *    weighted median of its pooling: the authors' later advice on the
 *    paper's publication page, and a figure every pixel counts in;
 *  - the images given are linear light and the display decodes sRGB: an
 *    sRGB-encoded image is compared as such (the paper's case); one under
 *    another encoding `enc` is compared as the same display shows its codes
 *    (Crow's square law, gamma:2, shows darker).  An image of fewer than 3
 *    channels is shown as grey (its first channel), one of more as RGB.
 *
 * Where the paper leaves room, decided here (as the authors' code does
 * unless said):
 *  - the filters reach past the image's border by its edge pixels
 *    (clamped coordinates, the authors' replicated border);
 *  - the sRGB matrix is IEC 61966-2-1's to 7 digits (the authors write it
 *    as ratios that differ by 1e-4); CIELAB's f has the exact 6/29 (the
 *    authors' 2020 release rounded it to 0.008856 and 7.787);
 *  - the 2-D kernels are applied as sums of separable ones, which they
 *    are: S at the distance sqrt(x^2 + y^2) is, per Gaussian term, a
 *    product of 1-D Gaussians, and the derivative kernels the derivative
 *    across times the Gaussian along (normalising each factor normalises
 *    the product); tests/test_flip.c evaluates the 2-D definitions tap by
 *    tap and agrees to rounding;
 *  - dEc is kept at most 1, which nothing reaches but green against blue
 *    (the paper's cmax is the largest difference in the RGB cube).
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define QC 0.7
#define PC 0.4
#define PT 0.95
#define QF 0.5
#define FEATURE_W 0.082 /* degrees */

/* linear sRGB (D65) to XYZ, IEC 61966-2-1 */
static const double RGB2XYZ[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                     {0.2126729, 0.7151522, 0.0721750},
                                     {0.0193339, 0.1191920, 0.9503041}};

double aa_flip_ppd(double distance, double width, int pixels)
{
    return distance * ((double)pixels / width) * M_PI / 180.0;
}

static void mat_inverse(const double m[3][3], double r[3][3])
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
}

static void white(double wn[3])
{
    for (int k = 0; k < 3; k++)
        wn[k] = RGB2XYZ[k][0] + RGB2XYZ[k][1] + RGB2XYZ[k][2];
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

/* Linear RGB to Hunt-adjusted CIELAB. */
static void rgb_to_hunt_lab(const double rgb[3], double lab[3])
{
    double wn[3], xyz[3];
    white(wn);
    for (int k = 0; k < 3; k++)
        xyz[k] = RGB2XYZ[k][0] * rgb[0] + RGB2XYZ[k][1] * rgb[1] + RGB2XYZ[k][2] * rgb[2];
    double fx = lab_f(xyz[0] / wn[0]), fy = lab_f(xyz[1] / wn[1]), fz = lab_f(xyz[2] / wn[2]);
    double L = 116 * fy - 16;
    lab[0] = L;
    lab[1] = 0.01 * L * 500 * (fx - fy);
    lab[2] = 0.01 * L * 200 * (fy - fz);
}

static double hyab(const double a[3], const double b[3])
{
    return fabs(a[0] - b[0]) + hypot(a[1] - b[1], a[2] - b[2]);
}

double aa_flip_cmax(void)
{
    const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    double g[3], b[3];
    rgb_to_hunt_lab(green, g);
    rgb_to_hunt_lab(blue, b);
    return pow(hyab(g, b), QC);
}

/* A Hunt-adjusted HyAB distance (before qc) to the colour error in [0, 1]. */
static double colour_error(double d, double cmax)
{
    double e = pow(d, QC);
    if (e < PC * cmax)
        return PT / (PC * cmax) * e;
    return fmin(1.0, PT + (e - PC * cmax) / (cmax - PC * cmax) * (1.0 - PT));
}

/* One line of n values (stride apart) convolved with k (2 r + 1 taps,
 * centred), clamped at its ends: through line, n + 2 r values. */
static void convolve_line(const double *src, size_t stride, int n, const double *k, int r,
                          double *line, double *dst)
{
    for (int q = -r; q < n + r; q++)
        line[q + r] = src[(size_t)(q < 0 ? 0 : q >= n ? n - 1 : q) * stride];
    for (int i = 0; i < n; i++) {
        double s = 0;
        for (int d = 0; d <= 2 * r; d++)
            s += k[d] * line[i + d];
        dst[(size_t)i * stride] = s;
    }
}

/* out = ky (down the columns) after kx (along the rows) applied to src,
 * clamped at the border; line holds max(w, h) + 2 r values. */
static void convolve(const double *src, double *dst, double *tmp, int w, int h, const double *kx,
                     const double *ky, int r, double *line)
{
    for (int j = 0; j < h; j++)
        convolve_line(src + (size_t)j * w, 1, w, kx, r, line, tmp + (size_t)j * w);
    for (int i = 0; i < w; i++)
        convolve_line(tmp + i, (size_t)w, h, ky, r, line, dst + i);
}

/* The displayed linear RGB of pixel p. */
static void displayed(const aa_image *im, size_t p, const aa_encode *enc, double rgb[3])
{
    for (int k = 0; k < 3; k++) {
        double v = im->v[p * (size_t)im->c + (size_t)(im->c >= 3 ? k : 0)];
        if (enc && enc->kind != AA_ENCODE_SRGB) {
            /* shown as the display shows an sRGB code */
            double code = aa_encode_value(enc, v);
            v = code <= 0.04045 ? code / 12.92 : pow((code + 0.055) / 1.055, 2.4);
        }
        rgb[k] = fmin(1.0, fmax(0.0, v));
    }
}

typedef struct flip_work {
    int w, h, rc, rf;
    double *csf[3][2]; /* per channel, per Gaussian term: 1-D kernel (2 rc + 1) */
    double cw[3][2];   /* its weight in the normalised 2-D kernel */
    double *g, *gd, *gdd; /* feature kernels (2 rf + 1) */
    double *chan[3], *acc, *tmp, *y, *line;
} flip_work;

static const double CSF[3][4] = {{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5},
                                 {34.1, 0.04, 13.5, 0.025}};

static int work_init(flip_work *fw, int w, int h, double ppd)
{
    memset(fw, 0, sizeof *fw);
    fw->w = w, fw->h = h;
    fw->rc = (int)ceil(3 * sqrt(0.04 / (2 * M_PI * M_PI)) * ppd);
    double sigma = FEATURE_W / 2 * ppd;
    fw->rf = (int)ceil(3 * sigma);
    int nc = 2 * fw->rc + 1, nf = 2 * fw->rf + 1;
    size_t n = (size_t)w * h;
    int ok = 1;
    for (int c = 0; c < 3; c++)
        for (int t = 0; t < 2; t++)
            ok &= (fw->csf[c][t] = malloc((size_t)nc * sizeof(double))) != NULL;
    ok &= (fw->g = malloc((size_t)nf * sizeof(double))) != NULL;
    ok &= (fw->gd = malloc((size_t)nf * sizeof(double))) != NULL;
    ok &= (fw->gdd = malloc((size_t)nf * sizeof(double))) != NULL;
    for (int c = 0; c < 3; c++)
        ok &= (fw->chan[c] = malloc(n * sizeof(double))) != NULL;
    ok &= (fw->acc = malloc(n * sizeof(double))) != NULL;
    ok &= (fw->tmp = malloc(n * sizeof(double))) != NULL;
    ok &= (fw->y = malloc(n * sizeof(double))) != NULL;
    int r = fw->rc > fw->rf ? fw->rc : fw->rf;
    ok &= (fw->line = malloc(((size_t)(w > h ? w : h) + 2 * (size_t)r) * sizeof(double))) != NULL;
    if (!ok)
        return aa_fail(AA_ENOMEM, "out of memory for FLIP of %dx%d", w, h);
    for (int c = 0; c < 3; c++) {
        double total = 0;
        for (int t = 0; t < 2; t++) {
            double a = CSF[c][2 * t], b = CSF[c][2 * t + 1], s = 0;
            for (int k = -fw->rc; k <= fw->rc; k++) {
                double x = k / ppd; /* degrees */
                fw->csf[c][t][k + fw->rc] = exp(-M_PI * M_PI * x * x / b);
                s += fw->csf[c][t][k + fw->rc];
            }
            /* each 1-D factor to sum 1; the term's 2-D weight a sqrt(pi/b) s^2 */
            for (int k = 0; k < nc; k++)
                fw->csf[c][t][k] /= s;
            fw->cw[c][t] = a * sqrt(M_PI / b) * s * s;
            total += fw->cw[c][t];
        }
        for (int t = 0; t < 2; t++)
            fw->cw[c][t] /= total;
    }
    double sg = 0, pos[2] = {0, 0}, neg[2] = {0, 0};
    for (int k = -fw->rf; k <= fw->rf; k++) {
        double g = exp(-k * k / (2 * sigma * sigma));
        fw->g[k + fw->rf] = g;
        fw->gd[k + fw->rf] = -k * g;
        fw->gdd[k + fw->rf] = (k * k / (sigma * sigma) - 1) * g;
        sg += g;
        for (int q = 0; q < 2; q++) {
            double v = q ? fw->gdd[k + fw->rf] : fw->gd[k + fw->rf];
            if (v > 0)
                pos[q] += v;
            else
                neg[q] -= v;
        }
    }
    for (int k = 0; k < nf; k++) {
        fw->g[k] /= sg;
        fw->gd[k] /= fw->gd[k] > 0 ? pos[0] : neg[0];
        fw->gdd[k] /= fw->gdd[k] > 0 ? pos[1] : neg[1];
    }
    return AA_OK;
}

static void work_free(flip_work *fw)
{
    for (int c = 0; c < 3; c++) {
        for (int t = 0; t < 2; t++)
            free(fw->csf[c][t]);
        free(fw->chan[c]);
    }
    free(fw->g), free(fw->gd), free(fw->gdd);
    free(fw->acc), free(fw->tmp), free(fw->y), free(fw->line);
}

/* One image: its filtered, Hunt-adjusted Lab (lab, 3 per pixel) and its
 * edge and point magnitudes (feat, 2 per pixel). */
static void prepare(flip_work *fw, const aa_image *im, const aa_encode *enc, double *lab,
                    double *feat)
{
    size_t n = (size_t)fw->w * fw->h;
    double wn[3], inv[3][3];
    white(wn);
    mat_inverse(RGB2XYZ, inv);
    for (size_t p = 0; p < n; p++) {
        double rgb[3], xyz[3];
        displayed(im, p, enc, rgb);
        for (int k = 0; k < 3; k++)
            xyz[k] = RGB2XYZ[k][0] * rgb[0] + RGB2XYZ[k][1] * rgb[1] + RGB2XYZ[k][2] * rgb[2];
        double x = xyz[0] / wn[0], y = xyz[1] / wn[1], z = xyz[2] / wn[2];
        fw->chan[0][p] = 116 * y - 16;
        fw->chan[1][p] = 500 * (x - y);
        fw->chan[2][p] = 200 * (y - z);
        fw->y[p] = y; /* (Yy + 16) / 116 */
    }
    for (int c = 0; c < 3; c++) {
        for (size_t p = 0; p < n; p++)
            lab[3 * p + (size_t)c] = 0;
        for (int t = 0; t < 2; t++) {
            if (fw->cw[c][t] == 0)
                continue;
            convolve(fw->chan[c], fw->acc, fw->tmp, fw->w, fw->h, fw->csf[c][t], fw->csf[c][t],
                     fw->rc, fw->line);
            for (size_t p = 0; p < n; p++)
                lab[3 * p + (size_t)c] += fw->cw[c][t] * fw->acc[p];
        }
    }
    for (size_t p = 0; p < n; p++) { /* YyCxCz to linear RGB, clamped, to Hunt Lab */
        double y = (lab[3 * p] + 16) / 116, x = lab[3 * p + 1] / 500 + y,
               z = y - lab[3 * p + 2] / 200;
        double xyz[3] = {x * wn[0], y * wn[1], z * wn[2]}, rgb[3];
        for (int k = 0; k < 3; k++)
            rgb[k] = fmin(1.0, fmax(0.0, inv[k][0] * xyz[0] + inv[k][1] * xyz[1] +
                                             inv[k][2] * xyz[2]));
        rgb_to_hunt_lab(rgb, lab + 3 * p);
    }
    /* features: x responses into chan[0], chan[1]; y ones into acc, chan[2] */
    convolve(fw->y, fw->chan[0], fw->tmp, fw->w, fw->h, fw->gd, fw->g, fw->rf, fw->line);
    convolve(fw->y, fw->acc, fw->tmp, fw->w, fw->h, fw->g, fw->gd, fw->rf, fw->line);
    for (size_t p = 0; p < n; p++)
        feat[2 * p] = hypot(fw->chan[0][p], fw->acc[p]);
    convolve(fw->y, fw->chan[1], fw->tmp, fw->w, fw->h, fw->gdd, fw->g, fw->rf, fw->line);
    convolve(fw->y, fw->chan[2], fw->tmp, fw->w, fw->h, fw->g, fw->gdd, fw->rf, fw->line);
    for (size_t p = 0; p < n; p++)
        feat[2 * p + 1] = hypot(fw->chan[1][p], fw->chan[2][p]);
}

int aa_flip(const aa_image *ref, const aa_image *img, const aa_encode *enc, double ppd,
            double *mean, aa_image *map)
{
    if (ref->w != img->w || ref->h != img->h || ref->c != img->c)
        return aa_fail(AA_EINVAL, "FLIP of images of different sizes: %dx%dx%d and %dx%dx%d",
                       ref->w, ref->h, ref->c, img->w, img->h, img->c);
    if (!(ppd > 0) || !isfinite(ppd))
        return aa_fail(AA_EINVAL, "FLIP: %g pixels per degree, not a positive number", ppd);
    size_t n = (size_t)ref->w * ref->h;
    flip_work fw;
    int st = work_init(&fw, ref->w, ref->h, ppd);
    double *lab = malloc(6 * n * sizeof *lab), *feat = malloc(4 * n * sizeof *feat);
    if (!st && (!lab || !feat))
        st = aa_fail(AA_ENOMEM, "out of memory for FLIP of %dx%d", ref->w, ref->h);
    if (!st && map && (st = aa_image_alloc(map, ref->w, ref->h, 1)))
        map = NULL;
    if (!st) {
        prepare(&fw, ref, enc, lab, feat);
        prepare(&fw, img, enc, lab + 3 * n, feat + 2 * n);
        double cmax = aa_flip_cmax(), sum = 0;
        for (size_t p = 0; p < n; p++) {
            double ec = colour_error(hyab(lab + 3 * p, lab + 3 * (n + p)), cmax);
            double de = fabs(feat[2 * p] - feat[2 * (n + p)]);
            double dp = fabs(feat[2 * p + 1] - feat[2 * (n + p) + 1]);
            double ef = pow(fmin(1.0, fmax(de, dp) / M_SQRT2), QF);
            double e = pow(ec, 1.0 - ef);
            sum += e;
            if (map)
                map->v[p] = e;
        }
        *mean = sum / (double)n;
    }
    free(lab);
    free(feat);
    work_free(&fw);
    return st;
}

double aa_flip_bytes(int w, int h)
{
    /* six planes of work, the two images' Lab (3 each) and features (2 each) */
    return 16.0 * w * h * sizeof(double);
}
