/*
 * calibration.c: Crow's colour-map calibration (Crow 1976, appendix,
 * "Grey scale compensation", pp. 88-92, figs. A.1-A.4), as a measurement.
 *
 * What Crow did.  His frame buffer's bytes went through a colour map (a
 * table, input byte to the 12-bit value driving the monitor) to a
 * television monitor, whose intensity follows a square law of its drive.
 * "To calibrate the system, the test pattern was displayed using a
 * pyramid-shaped presampling filter (as seen in figure 2.14).  The color
 * map was then adjusted until the strength of the moire fringes was
 * minimized (figures A.1 through A.3), that is, the system is calibrated
 * by subjective feedback."  Photometer readings of a linear grey scale
 * shown beside the pattern then "lay near a parabolic curve, i.e. the
 * function given by the square roots of the intensity readings was close
 * to linear ... At display intensities appropriate for viewing at normal
 * indoor light levels, the color map curve was almost linear, indicating
 * that the display was obeying the expected square law" (fig. A.4).  So
 * his finding: the fringes were weakest when the displayed intensity of a
 * stored value v was about v^2.
 *
 * What is measured here.  The stored image v is the test pattern (crow,
 * 256 x 256) under the two-dot pyramid (tent:r=1), made by Crow's own
 * table method (crowtable, fig. 2.14) and, beside it, the exact reference.
 * A display of total response exponent g shows intensity v^g (a colour
 * map v^p on a square-law tube: g = 2p; his three maps of figs. A.1-A.3,
 * linear, convex upward and concave upward, are taken as p = 1, 1/2 and 2:
 * g = 2, 1 and 4).  The eye (eye.c, s = AA_EYE_S pixels) sees the screen;
 * what it should see is the pattern itself seen by the same eye, the exact
 * reference under gauss:s=2 (a black and white pattern looks the same
 * through any response with 0 -> 0 and 1 -> 1).  For each g:
 *  - fringe: the standard deviation, over the right half of the image
 *    (columns W/2 and beyond, where the bands are at most four dots wide
 *    and reach and pass the Nyquist limit), of the eye's error: the
 *    moire fringes, without their mean;
 *  - eye_rmse: the RMSE of the eye's error over the whole image (fringes,
 *    the shift of the fine half's mean grey, and the filter's blur).
 * g runs from 0.5 to 4 in steps of 0.05; each measure's least value is
 * then found to 0.001 on a finer grid around its least grid point.
 *
 * The eye above averages intensity (its optics blur the light before the
 * retina responds).  If it averaged a lightness L = I^(1/2) instead (the
 * square root of intensity, as Crow's readings suggest), the same
 * measures would be those of exponent g/2, so their least would lie at
 * twice the g found here: that is reported beside.
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The fringe and eye measures of the image v shown with exponent g. */
static int measure(const aa_image *v, const aa_image *truth, double g, aa_image *shown,
                   double *fringe, double *eye)
{
    size_t n = (size_t)v->w * v->h * v->c;
    for (size_t k = 0; k < n; k++)
        shown->v[k] = v->v[k] > 0 ? pow(v->v[k], g) : 0.0;
    aa_image seen;
    int st = aa_eye_blur(shown, AA_EYE_S, &seen);
    if (st)
        return st;
    double s1 = 0, s2 = 0, all = 0;
    size_t m = 0;
    for (int j = 0; j < v->h; j++)
        for (int i = 0; i < v->w; i++)
            for (int c = 0; c < v->c; c++) {
                double d = aa_pixel(&seen, i, j)[c] - aa_pixel(truth, i, j)[c];
                all += d * d;
                if (i >= v->w / 2) {
                    s1 += d;
                    s2 += d * d;
                    m++;
                }
            }
    double mean = s1 / (double)m;
    *fringe = sqrt(fmax(0.0, s2 / (double)m - mean * mean));
    *eye = sqrt(all / (double)n);
    aa_image_free(&seen);
    return AA_OK;
}

/* The grid point where val is least (the first of equals). */
static int least_at(const double *val, int n)
{
    int k = 0;
    for (int q = 1; q < n; q++)
        if (val[q] < val[k])
            k = q;
    return k;
}

/* The least of each measure (fringe, eye) on the finer grid between the
 * grid points beside its least grid point.  Each measure gives both, so
 * where the two least grid points are the same (as on crow: both near
 * g = 1), one walk of the finer grid serves both. */
static int refine(const aa_image *v, const aa_image *truth, aa_image *shown, const double *g,
                  int n, const double *fringe, const double *eye, double *gmin_fringe,
                  double *gmin_eye)
{
    const int k[2] = {least_at(fringe, n), least_at(eye, n)};
    double *gmin[2] = {gmin_fringe, gmin_eye};
    for (int which = 0; which < 2; which++) {
        if (which == 1 && k[1] == k[0])
            break; /* walked with the fringe's */
        const int both = which == 0 && k[1] == k[0];
        double lo = g[k[which] > 0 ? k[which] - 1 : k[which]];
        double hi = g[k[which] < n - 1 ? k[which] + 1 : k[which]];
        double best[2] = {INFINITY, INFINITY};
        *gmin[which] = g[k[which]];
        if (both)
            *gmin[1] = g[k[1]];
        for (double x = lo; x <= hi + 1e-12; x += 0.001) {
            double y[2];
            int st = measure(v, truth, x, shown, &y[0], &y[1]);
            if (st)
                return st;
            for (int m = 0; m < 2; m++)
                if ((m == which || both) && y[m] < best[m])
                    best[m] = y[m], *gmin[m] = x;
        }
    }
    return AA_OK;
}

int aa_crow_calibration(const char *cache_dir, int threads, aa_calibration *out)
{
    memset(out, 0, sizeof *out);
    aa_spec pattern, method;
    aa_filter tent;
    aa_scene *scene = NULL;
    aa_job job;
    aa_counters counters;
    aa_view view;
    aa_image img[2] = {{0}}, truth = {0}, shown = {0};
    const int w = 256, h = 256;
    int st = aa_pattern_parse("crow", &pattern);
    if (!st)
        st = aa_filter_parse("tent:r=1", &tent);
    if (!st)
        st = aa_method_parse("crowtable", &tent, &method);
    if (!st)
        st = aa_pattern_scene_at(&pattern, w, h, &scene);
    if (st)
        return st;
    memset(&view, 0, sizeof view);
    view.pattern = pattern;
    view.w = w, view.h = h;
    view.filter = tent;
    if ((st = aa_job_init(&job, scene, w, h, 0, 0, 0, &tent, 1, threads)))
        goto done;
    if (!(st = aa_image_alloc(&img[0], w, h, 3)))
        st = aa_method_run(&method, &job, 1, &img[0], &counters, NULL);
    aa_job_free(&job);
    if (!st)
        st = aa_reference(&view, cache_dir, threads, &img[1], NULL, NULL);
    if (!st)
        st = aa_eye_truth(&pattern, w, h, 0, 0, 0, AA_EYE_S, cache_dir, threads, &truth);
    if (!st)
        st = aa_image_alloc(&shown, w, h, 3);
    for (int q = 0; q < AA_CALIBRATION_MAX && !st; q++) {
        double g = 0.5 + 0.05 * q;
        if (g > 4 + 1e-9)
            break;
        out->g[q] = g;
        out->n = q + 1;
        for (int s = 0; s < 2 && !st; s++)
            st = measure(&img[s], &truth, g, &shown, &out->fringe[s][q], &out->eye[s][q]);
    }
    for (int s = 0; s < 2 && !st; s++)
        st = refine(&img[s], &truth, &shown, out->g, out->n, out->fringe[s], out->eye[s],
                    &out->gmin_fringe[s], &out->gmin_eye[s]);
    /* the three maps of figs. A.1-A.3 */
    static const double maps[3] = {2, 1, 4};
    for (int m = 0; m < 3 && !st; m++) {
        out->map_g[m] = maps[m];
        for (int s = 0; s < 2 && !st; s++)
            st = measure(&img[s], &truth, maps[m], &shown, &out->map_fringe[s][m],
                         &out->map_eye[s][m]);
    }
done:
    aa_image_free(&img[0]);
    aa_image_free(&img[1]);
    aa_image_free(&truth);
    aa_image_free(&shown);
    aa_scene_free(scene);
    return st;
}
