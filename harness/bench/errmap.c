/*
 * errmap.c: pictures of the error a reader can read.
 *
 *  - Colour maps.  magma (van der Walt and Smith 2015, matplotlib's
 *    perceptually uniform sequential maps, designed in CAM02-UCS; data
 *    published CC0 in matplotlib's lib/matplotlib/_cm_listed.py as 256 sRGB
 *    entries): every second entry and the last, 129 knots, interpolated
 *    linearly (within 0.002 of the full table).  The diverging
 *    map is Moreland's "cool to warm" (K. Moreland 2009, "Diverging Color
 *    Maps for Scientific Visualization", ISVC): computed here from its
 *    definition, the interpolation in his Msh space (the polar form of
 *    CIELAB) between the sRGB ends (59, 76, 192) and (180, 4, 38) through
 *    a white of M = max(M1, M2, 88), each unsaturated end's hue spun as his
 *    section 5 says, in 65 levels.  Both give sRGB codes in [0, 1].
 *  - The signed error map: each pixel's error of largest magnitude over
 *    its channels (method minus reference, linear light), with its sign,
 *    on the diverging map from -s (blue: darker than the reference) through
 *    0 (light grey) to +s (red: brighter), s the 99.5th percentile of the
 *    image's non-zero |errors| rounded up to 1, 2 or 5 times a power of
 *    ten (a few large errors would otherwise leave the rest faint), larger
 *    errors clipped (and never below 1e-6: rounding is shown as no error),
 *    so every map is auto-scaled and says its scale; a
 *    colour bar under the map with its ends (<= and >= where they clip) and
 *    middle labelled; an image smaller than 256 pixels is shown zoomed
 *    (nearest neighbour, at most 4 times), its caption saying so.  The unsigned map (FLIP's values) uses magma
 *    from 0 to 1, fixed (FLIP is already in [0, 1]).
 *  - The worst region: the k x k window (k = min(32, w, h)) of largest
 *    squared error (a summed-area table), shown zoomed (nearest neighbour,
 *    so pixels stay pixels): the reference, the image, the signed error on
 *    the image's scale, and FLIP's map of the window (computed on the
 *    window with a margin of 16 pixels, so the filters see its
 *    neighbourhood).
 */
#include "bench.h"
#include "oiio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* magma, 129 of its 256 entries: indices 0, 2, ..., 254 and 255 */
static const double MAGMA[129][3] = {
    {0.001462, 0.000466, 0.013866}, {0.003279, 0.002305, 0.023708},
    {0.005950, 0.004843, 0.037130}, {0.009426, 0.008022, 0.052844},
    {0.013708, 0.011771, 0.068667}, {0.018815, 0.016026, 0.084584},
    {0.024792, 0.020715, 0.100676}, {0.031696, 0.025765, 0.116965},
    {0.039608, 0.031090, 0.133515}, {0.048062, 0.036607, 0.150327},
    {0.056615, 0.042160, 0.167446}, {0.065330, 0.047318, 0.184892},
    {0.074257, 0.052017, 0.202660}, {0.083446, 0.056225, 0.220755},
    {0.092949, 0.059904, 0.239164}, {0.102815, 0.063010, 0.257854},
    {0.113094, 0.065492, 0.276784}, {0.123833, 0.067295, 0.295879},
    {0.135053, 0.068391, 0.315000}, {0.146785, 0.068738, 0.334011},
    {0.159018, 0.068354, 0.352688}, {0.171713, 0.067305, 0.370771},
    {0.184801, 0.065732, 0.387973}, {0.198177, 0.063862, 0.404009},
    {0.211718, 0.061992, 0.418647}, {0.225302, 0.060445, 0.431742},
    {0.238826, 0.059517, 0.443256}, {0.252220, 0.059415, 0.453248},
    {0.265447, 0.060237, 0.461840}, {0.278493, 0.061978, 0.469190},
    {0.291366, 0.064553, 0.475462}, {0.304081, 0.067835, 0.480812},
    {0.316654, 0.071690, 0.485380}, {0.329114, 0.075972, 0.489287},
    {0.341482, 0.080564, 0.492631}, {0.353773, 0.085373, 0.495501},
    {0.366012, 0.090314, 0.497960}, {0.378211, 0.095332, 0.500067},
    {0.390384, 0.100379, 0.501864}, {0.402548, 0.105420, 0.503386},
    {0.414709, 0.110431, 0.504662}, {0.426877, 0.115395, 0.505714},
    {0.439062, 0.120298, 0.506555}, {0.451271, 0.125132, 0.507198},
    {0.463508, 0.129893, 0.507652}, {0.475780, 0.134577, 0.507921},
    {0.488088, 0.139186, 0.508011}, {0.500438, 0.143719, 0.507920},
    {0.512831, 0.148179, 0.507648}, {0.525270, 0.152569, 0.507192},
    {0.537755, 0.156894, 0.506551}, {0.550287, 0.161158, 0.505719},
    {0.562866, 0.165368, 0.504692}, {0.575490, 0.169530, 0.503466},
    {0.588158, 0.173652, 0.502035}, {0.600868, 0.177743, 0.500394},
    {0.613617, 0.181811, 0.498536}, {0.626401, 0.185867, 0.496456},
    {0.639216, 0.189921, 0.494150}, {0.652056, 0.193986, 0.491611},
    {0.664915, 0.198075, 0.488836}, {0.677786, 0.202203, 0.485819},
    {0.690661, 0.206384, 0.482558}, {0.703532, 0.210638, 0.479049},
    {0.716387, 0.214982, 0.475290}, {0.729216, 0.219437, 0.471279},
    {0.742004, 0.224025, 0.467018}, {0.754737, 0.228772, 0.462509},
    {0.767398, 0.233705, 0.457755}, {0.779968, 0.238851, 0.452765},
    {0.792427, 0.244242, 0.447543}, {0.804752, 0.249911, 0.442102},
    {0.816914, 0.255895, 0.436461}, {0.828886, 0.262229, 0.430644},
    {0.840636, 0.268953, 0.424666}, {0.852126, 0.276106, 0.418573},
    {0.863320, 0.283729, 0.412403}, {0.874176, 0.291859, 0.406205},
    {0.884651, 0.300530, 0.400047}, {0.894700, 0.309773, 0.393995},
    {0.904281, 0.319610, 0.388137}, {0.913354, 0.330052, 0.382563},
    {0.921884, 0.341098, 0.377376}, {0.929845, 0.352734, 0.372677},
    {0.937221, 0.364929, 0.368567}, {0.944006, 0.377643, 0.365136},
    {0.950210, 0.390820, 0.362468}, {0.955849, 0.404400, 0.360619},
    {0.960949, 0.418323, 0.359630}, {0.965549, 0.432519, 0.359529},
    {0.969680, 0.446936, 0.360311}, {0.973381, 0.461520, 0.361965},
    {0.976690, 0.476226, 0.364466}, {0.979645, 0.491014, 0.367783},
    {0.982279, 0.505851, 0.371874}, {0.984622, 0.520713, 0.376698},
    {0.986700, 0.535582, 0.382210}, {0.988533, 0.550446, 0.388365},
    {0.990138, 0.565296, 0.395122}, {0.991558, 0.580107, 0.402441},
    {0.992785, 0.594891, 0.410283}, {0.993834, 0.609644, 0.418613},
    {0.994738, 0.624350, 0.427397}, {0.995480, 0.639027, 0.436607},
    {0.996096, 0.653659, 0.446213}, {0.996580, 0.668256, 0.456192},
    {0.996925, 0.682828, 0.466526}, {0.997186, 0.697349, 0.477182},
    {0.997325, 0.711848, 0.488154}, {0.997351, 0.726324, 0.499428},
    {0.997285, 0.740772, 0.510983}, {0.997138, 0.755190, 0.522806},
    {0.996898, 0.769591, 0.534892}, {0.996571, 0.783977, 0.547233},
    {0.996162, 0.798348, 0.559820}, {0.995680, 0.812706, 0.572645},
    {0.995131, 0.827052, 0.585701}, {0.994524, 0.841387, 0.598983},
    {0.993866, 0.855711, 0.612482}, {0.993170, 0.870024, 0.626189},
    {0.992440, 0.884330, 0.640099}, {0.991688, 0.898627, 0.654202},
    {0.990930, 0.912915, 0.668481}, {0.990175, 0.927196, 0.682926},
    {0.989434, 0.941470, 0.697519}, {0.988717, 0.955742, 0.712242},
    {0.988033, 0.970012, 0.727077}, {0.987387, 0.984288, 0.742002},
    {0.987053, 0.991438, 0.749504}
};

void aa_colormap_magma(double t, double rgb[3])
{
    double x = (t > 0 ? (t < 1 ? t : 1) : 0) * 255;
    int i = (int)(x / 2);
    if (i > 127)
        i = 127;
    double a = 2.0 * i, b = i == 127 ? 255.0 : 2.0 * (i + 1), f = (x - a) / (b - a);
    for (int k = 0; k < 3; k++)
        rgb[k] = MAGMA[i][k] + (MAGMA[i + 1][k] - MAGMA[i][k]) * f;
}

/* ---- Moreland's cool to warm, in Msh ---- */

static const double M_RGB2XYZ[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                       {0.2126729, 0.7151522, 0.0721750},
                                       {0.0193339, 0.1191920, 0.9503041}};
static const double M_XYZ2RGB[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                       {-0.9692660, 1.8760108, 0.0415560},
                                       {0.0556434, -0.2040259, 1.0572252}};
static const double WHITE[3] = {0.95047, 1.0, 1.08883};

static double srgb_decode(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double srgb_encode(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static double f_lab(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

static double f_lab_inv(double t)
{
    const double d = 6.0 / 29.0;
    return t > d ? t * t * t : 3 * d * d * (t - 4.0 / 29.0);
}

static void code_to_msh(const double code[3], double msh[3])
{
    double lin[3], xyz[3];
    for (int k = 0; k < 3; k++)
        lin[k] = srgb_decode(code[k]);
    for (int k = 0; k < 3; k++)
        xyz[k] = M_RGB2XYZ[k][0] * lin[0] + M_RGB2XYZ[k][1] * lin[1] + M_RGB2XYZ[k][2] * lin[2];
    double fx = f_lab(xyz[0] / WHITE[0]), fy = f_lab(xyz[1] / WHITE[1]),
           fz = f_lab(xyz[2] / WHITE[2]);
    double L = 116 * fy - 16, a = 500 * (fx - fy), b = 200 * (fy - fz);
    msh[0] = sqrt(L * L + a * a + b * b);
    msh[1] = msh[0] > 0 ? acos(L / msh[0]) : 0;
    msh[2] = atan2(b, a);
}

static void msh_to_code(const double msh[3], double code[3])
{
    double L = msh[0] * cos(msh[1]), a = msh[0] * sin(msh[1]) * cos(msh[2]),
           b = msh[0] * sin(msh[1]) * sin(msh[2]);
    double fy = (L + 16) / 116, fx = fy + a / 500, fz = fy - b / 200;
    double xyz[3] = {WHITE[0] * f_lab_inv(fx), WHITE[1] * f_lab_inv(fy), WHITE[2] * f_lab_inv(fz)};
    for (int k = 0; k < 3; k++)
        code[k] = srgb_encode(M_XYZ2RGB[k][0] * xyz[0] + M_XYZ2RGB[k][1] * xyz[1] +
                              M_XYZ2RGB[k][2] * xyz[2]);
}

/* Moreland's hue of an unsaturated end beside a saturated one (M, s, h),
 * at the unsaturated end's magnitude mu. */
static double adjust_hue(const double msh[3], double mu)
{
    if (msh[0] >= mu)
        return msh[2];
    double spin = msh[1] * sqrt(mu * mu - msh[0] * msh[0]) / (msh[0] * sin(msh[1]));
    return msh[2] > -M_PI / 3 ? msh[2] + spin : msh[2] - spin;
}

void aa_colormap_diverging(double t, double rgb[3])
{
    /* 65 levels (32 either side of 0): flat regions stay flat in the PNG,
     * which keeps the maps small, and the eye tells no more apart */
    t = round((t > -1 ? (t < 1 ? t : 1) : -1) * 32) / 32;
    const double cool[3] = {59 / 255.0, 76 / 255.0, 192 / 255.0},
                 warm[3] = {180 / 255.0, 4 / 255.0, 38 / 255.0};
    double u = (t > -1 ? (t < 1 ? t : 1) : -1) * 0.5 + 0.5; /* [0, 1] */
    double m1[3], m2[3], m[3];
    code_to_msh(cool, m1);
    code_to_msh(warm, m2);
    double dh = fabs(m1[2] - m2[2]);
    if (m1[1] > 0.05 && m2[1] > 0.05 && dh > M_PI / 3) {
        double mid = fmax(fmax(m1[0], m2[0]), 88.0);
        if (u < 0.5) {
            m2[0] = mid, m2[1] = 0, m2[2] = 0;
            u = 2 * u;
        } else {
            m1[0] = mid, m1[1] = 0, m1[2] = 0;
            u = 2 * u - 1;
        }
    }
    if (m1[1] < 0.05 && m2[1] > 0.05)
        m1[2] = adjust_hue(m2, m1[0]);
    else if (m2[1] < 0.05 && m1[1] > 0.05)
        m2[2] = adjust_hue(m1, m2[0]);
    for (int k = 0; k < 3; k++)
        m[k] = (1 - u) * m1[k] + u * m2[k];
    msh_to_code(m, rgb);
}

/* ---- the pictures ---- */

double aa_nice_scale(double x)
{
    if (!(x > 0) || !isfinite(x))
        return 1;
    double p = pow(10, floor(log10(x)));
    const double steps[] = {1, 2, 5, 10};
    for (int k = 0; k < 4; k++)
        if (x <= steps[k] * p * (1 + 1e-12))
            return steps[k] * p;
    return 10 * p;
}

/* The signed error of pixel (i, j): its channel error of largest size. */
static double signed_error(const aa_image *ref, const aa_image *img, int i, int j)
{
    const double *a = aa_pixel(ref, i, j), *b = aa_pixel(img, i, j);
    double e = 0;
    for (int k = 0; k < ref->c; k++) {
        double d = b[k] - a[k];
        if (isfinite(d) && fabs(d) > fabs(e))
            e = d;
    }
    return e;
}

#define BAR_H 12
#define LABEL 11
#define TEXT_H (LABEL + 4)
#define PAD 4
#define MIN_W 220

static void put(aa_image *out, int x, int y, const double rgb[3])
{
    if (x < 0 || y < 0 || x >= out->w || y >= out->h)
        return;
    double *p = aa_pixel(out, x, y);
    p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2];
}

static int text(aa_image *out, int x, int y, const char *s)
{
    const float grey[3] = {0.9f, 0.9f, 0.9f};
    return aa__oiio_text(out->v, out->w, out->h, 3, x, y, s, LABEL, grey);
}

/* A colour bar of width w at (x, y): signed from -s to s (sign 2: the
 * ends clip larger errors), else 0 to s, labelled at its ends and middle. */
static int colour_bar(aa_image *out, int x, int y, int w, int sign, double s)
{
    for (int i = 0; i < w; i++) {
        double t = (i + 0.5) / w, rgb[3];
        if (sign)
            aa_colormap_diverging(2 * t - 1, rgb);
        else
            aa_colormap_magma(t, rgb);
        for (int j = 0; j < BAR_H; j++)
            put(out, x + i, y + j, rgb);
    }
    char lo[32], mid[32], hi[32];
    if (sign) {
        snprintf(lo, sizeof lo, "%s-%.3g", sign == 2 ? "<=" : "", s);
        snprintf(mid, sizeof mid, "0");
        snprintf(hi, sizeof hi, "%s+%.3g", sign == 2 ? ">=" : "", s);
    } else {
        snprintf(lo, sizeof lo, "0");
        snprintf(mid, sizeof mid, "%.3g", s / 2);
        snprintf(hi, sizeof hi, "%.3g", s);
    }
    int ty = y + BAR_H + 2, st;
    int cw = LABEL * 6 / 10; /* about a character's width */
    if ((st = text(out, x, ty, lo)) ||
        (st = text(out, x + w / 2 - cw * (int)strlen(mid) / 2, ty, mid)))
        return st;
    return text(out, x + w - (cw + 2) * (int)strlen(hi) - 2, ty, hi);
}

static void fill(aa_image *out, double v)
{
    for (size_t k = 0; k < (size_t)out->w * out->h * 3; k++)
        out->v[k] = v;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double aa_error_scale(const aa_image *ref, const aa_image *img, double *largest)
{
    size_t n = (size_t)ref->w * ref->h, m = 0;
    double *e = malloc(n * sizeof *e), mx = 0;
    for (int j = 0; j < ref->h; j++)
        for (int i = 0; i < ref->w; i++) {
            double d = fabs(signed_error(ref, img, i, j));
            mx = fmax(mx, d);
            if (e && d > 0)
                e[m++] = d;
        }
    if (largest)
        *largest = mx;
    double s = mx;
    if (e && m) { /* the 99.5th percentile of the non-zero errors */
        qsort(e, m, sizeof *e, cmp_double);
        s = e[(size_t)floor(0.995 * (double)(m - 1))];
    }
    free(e);
    /* rounding is no error: below 1e-6 the map is flat */
    return mx > 0 ? aa_nice_scale(fmax(s, 1e-6)) : 0;
}

/* The error map's zoom: small images are shown larger (nearest neighbour),
 * up to 256 pixels and 4 times. */
int aa_error_picture_zoom(int w, int h)
{
    int side = w > h ? w : h, z = side > 0 ? 256 / side : 1;
    return z < 1 ? 1 : z > 4 ? 4 : z;
}

int aa_picture_write(const char *path, aa_image *pic)
{
    /* the codes back to linear values, written sRGB-encoded and tagged so
     * (a file tagged linear would be brightened again by a browser) */
    for (size_t k = 0; k < (size_t)pic->w * pic->h * (size_t)pic->c; k++)
        pic->v[k] = srgb_decode(pic->v[k]);
    aa_encode srgb = {AA_ENCODE_SRGB, 0};
    return aa_image_write(path, pic, &srgb);
}

int aa_error_picture_check(int w, int h)
{
    int z = aa_error_picture_zoom(w, h);
    double zw = (double)w * z, zh = (double)h * z;
    double pw = zw > MIN_W ? zw : MIN_W, ph = zh + TEXT_H + PAD + BAR_H + 2 + TEXT_H;
    if (pw > AA_MAX_SIDE || ph > AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "the error map of a %dx%d image would be %.0fx%.0f pixels: a "
                       "side is above %d", w, h, pw, ph, AA_MAX_SIDE);
    return aa_size_check((int)pw, (int)ph, 3, 2);
}

int aa_error_picture(const aa_image *ref, const aa_image *img, const char *caption,
                     aa_image *out, double *scale)
{
    if (ref->w != img->w || ref->h != img->h || ref->c != img->c)
        return aa_fail(AA_EINVAL, "error map of images of different sizes: %dx%d and %dx%d",
                       ref->w, ref->h, img->w, img->h);
    int w = ref->w, h = ref->h;
    double mx, s = aa_error_scale(ref, img, &mx);
    if (scale)
        *scale = s;
    if (s == 0)
        s = 1;
    int z = aa_error_picture_zoom(w, h), zw = w * z, zh = h * z;
    int pw = zw > MIN_W ? zw : MIN_W;
    int top = caption ? TEXT_H : 0;
    int st = aa_image_alloc(out, pw, top + zh + PAD + BAR_H + 2 + TEXT_H, 3);
    if (st)
        return st;
    fill(out, 0.12);
    int x0 = (pw - zw) / 2;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double rgb[3];
            aa_colormap_diverging(signed_error(ref, img, i, j) / s, rgb);
            for (int dj = 0; dj < z; dj++)
                for (int di = 0; di < z; di++)
                    put(out, x0 + i * z + di, top + j * z + dj, rgb);
        }
    if (caption) {
        char line[160];
        if (z > 1)
            snprintf(line, sizeof line, "%.120s, x%d", caption, z);
        else
            snprintf(line, sizeof line, "%.120s", caption);
        if ((st = text(out, 2, 1, line)))
            return st;
    }
    return colour_bar(out, 4, top + zh + PAD, pw - 8, mx > s ? 2 : 1, s);
}

int aa_flip_picture(const aa_image *map, const char *caption, aa_image *out)
{
    int w = map->w, h = map->h, pw = w > MIN_W ? w : MIN_W, top = caption ? TEXT_H : 0;
    int st = aa_image_alloc(out, pw, top + h + PAD + BAR_H + 2 + TEXT_H, 3);
    if (st)
        return st;
    fill(out, 0.12);
    int x0 = (pw - w) / 2;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double rgb[3];
            aa_colormap_magma(map->v[(size_t)j * w + i], rgb);
            put(out, x0 + i, top + j, rgb);
        }
    if (caption && (st = text(out, 2, 1, caption)))
        return st;
    return colour_bar(out, 4, top + h + PAD, pw - 8, 0, 1);
}

int aa_worst_window(const aa_image *ref, const aa_image *img, int k, int *x0, int *y0)
{
    int w = ref->w, h = ref->h;
    if (k > w)
        k = w;
    if (k > h)
        k = h;
    double *sat = calloc((size_t)(w + 1) * (h + 1), sizeof *sat);
    if (!sat)
        return aa_fail(AA_ENOMEM, "out of memory for the worst region of %dx%d", w, h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double e = 0;
            const double *a = aa_pixel(ref, i, j), *b = aa_pixel(img, i, j);
            for (int c = 0; c < ref->c; c++)
                if (isfinite(b[c] - a[c]))
                    e += (b[c] - a[c]) * (b[c] - a[c]);
            sat[(size_t)(j + 1) * (w + 1) + i + 1] = e + sat[(size_t)j * (w + 1) + i + 1] +
                                                     sat[(size_t)(j + 1) * (w + 1) + i] -
                                                     sat[(size_t)j * (w + 1) + i];
        }
    double best = -1;
    *x0 = *y0 = 0;
    for (int j = 0; j + k <= h; j++)
        for (int i = 0; i + k <= w; i++) {
            double s = sat[(size_t)(j + k) * (w + 1) + i + k] - sat[(size_t)j * (w + 1) + i + k] -
                       sat[(size_t)(j + k) * (w + 1) + i] + sat[(size_t)j * (w + 1) + i];
            if (s > best + 1e-15 * fabs(best))
                best = s, *x0 = i, *y0 = j;
        }
    free(sat);
    return AA_OK;
}

#define WORST 32
#define MARGIN 16

int aa_worst_picture(const aa_image *ref, const aa_image *img, const aa_encode *enc,
                     aa_image *out, int *wx, int *wy)
{
    const aa_encode srgb = {AA_ENCODE_SRGB, 0};
    if (!enc)
        enc = &srgb;
    int st, x0, y0;
    if ((st = aa_worst_window(ref, img, WORST, &x0, &y0)))
        return st;
    int k = WORST < ref->w ? WORST : ref->w;
    if (k > ref->h)
        k = ref->h;
    int zoom = 192 / k > 1 ? 192 / k : 1, z = k * zoom;
    /* the window with its margin, for FLIP */
    int mx0 = x0 - MARGIN > 0 ? x0 - MARGIN : 0, my0 = y0 - MARGIN > 0 ? y0 - MARGIN : 0;
    int mx1 = x0 + k + MARGIN < ref->w ? x0 + k + MARGIN : ref->w;
    int my1 = y0 + k + MARGIN < ref->h ? y0 + k + MARGIN : ref->h;
    aa_image a = {0}, b = {0}, map = {0};
    double flip = 0, mxe = 0;
    if ((st = aa_image_alloc(&a, mx1 - mx0, my1 - my0, ref->c)) ||
        (st = aa_image_alloc(&b, mx1 - mx0, my1 - my0, ref->c)))
        goto done;
    for (int j = my0; j < my1; j++) {
        memcpy(aa_pixel(&a, 0, j - my0), aa_pixel(ref, mx0, j),
               sizeof(double) * (size_t)ref->c * (size_t)(mx1 - mx0));
        memcpy(aa_pixel(&b, 0, j - my0), aa_pixel(img, mx0, j),
               sizeof(double) * (size_t)ref->c * (size_t)(mx1 - mx0));
    }
    for (size_t q = 0; q < (size_t)a.w * a.h * (size_t)a.c; q++) /* FLIP wants finite values */
        if (!isfinite(a.v[q]) || !isfinite(b.v[q]))
            a.v[q] = b.v[q] = 0;
    if ((st = aa_flip(&a, &b, enc, AA_FLIP_PPD, &flip, &map)))
        goto done;
    for (int j = y0; j < y0 + k; j++)
        for (int i = x0; i < x0 + k; i++)
            mxe = fmax(mxe, fabs(signed_error(ref, img, i, j)));
    double s = aa_nice_scale(fmax(mxe, 1e-6));
    int gap = 6, top = TEXT_H;
    int pw = 4 * z + 5 * gap, ph = top + z + gap + BAR_H + 2 + TEXT_H;
    if ((st = aa_image_alloc(out, pw, ph, 3)))
        goto done;
    fill(out, 0.12);
    static const char *const names[4] = {"Reference", "Image", "Error", "FLIP"};
    for (int p = 0; p < 4 && !st; p++) {
        int px = gap + p * (z + gap);
        st = text(out, px, 1, names[p]);
        for (int j = 0; j < z && !st; j++)
            for (int i = 0; i < z; i++) {
                int si = x0 + i / zoom, sj = y0 + j / zoom;
                double rgb[3];
                if (p < 2) {
                    const double *v = aa_pixel(p ? img : ref, si, sj);
                    for (int c = 0; c < 3; c++)
                        rgb[c] = aa_encode_value(enc, fmin(1, fmax(0, v[ref->c >= 3 ? c : 0])));
                } else if (p == 2) {
                    aa_colormap_diverging(signed_error(ref, img, si, sj) / s, rgb);
                } else {
                    aa_colormap_magma(map.v[(size_t)(sj - my0) * map.w + (si - mx0)], rgb);
                }
                put(out, px + i, top + j, rgb);
            }
    }
    int by = top + z + gap;
    if (!st)
        st = colour_bar(out, gap + 2 * (z + gap), by, z, 1, s);
    if (!st)
        st = colour_bar(out, gap + 3 * (z + gap), by, z, 0, 1);
    if (!st) {
        char where[96];
        snprintf(where, sizeof where, "pixels (%d, %d) to (%d, %d), x%d", x0, y0, x0 + k - 1,
                 y0 + k - 1, zoom);
        st = text(out, gap, by + 2, where);
    }
    if (wx)
        *wx = x0;
    if (wy)
        *wy = y0;
done:
    if (st)
        aa_image_free(out);
    aa_image_free(&a);
    aa_image_free(&b);
    aa_image_free(&map);
    return st;
}
