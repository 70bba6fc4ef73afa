/*
 * display.c: the reference of an image shown through a moving-dot display
 * (core.h, "Displays"; Crow 1976, ch. 4, "A temporal scheme").
 *
 * A method flagged AA_METHOD_DISPLAY shows frame k of its image on a
 * screen whose dots are moved by (dx_k, dy_k) from the pixel centres: the
 * dot of pixel p is a uniform square one pixel wide centred on
 * c_p + d_k, c_p = (i + 1/2, j + 1/2).  The dots of a frame tile the plane,
 * and the ring of dots just beyond the image's border is shown too, so the
 * screen is a flat field over the whole image.  The image the method
 * returns is the eye's: the weighted sum over its frames of the screen,
 * seen through the image's fixed pixel squares (the mean over each square),
 *
 *     E(q) = sum_k w_k sum_p x_k(p) a(q - p - d_k),
 *     a(u, v) = max(0, 1 - |u|) max(0, 1 - |v|)   (the area of square q that dot p covers),
 *
 * x_k(p) the value the method gives dot p in frame k (for the hexagon, the
 * scene at time t_k sampled at the dot's centre).  The reference is the
 * same screen showing in every dot its exact value,
 *
 *     R(q) = sum_k w_k sum_p r_k(p) a(q - p - d_k),
 *     r_k(p) = the scene at t_k convolved with the filter, at c_p + d_k,
 *
 * so the method and the reference are seen through the same dots, and
 * their difference is the method's error only: a display that moves the
 * dots blurs both alike.  With every d_k = 0 the screen is the ordinary
 * one and R is the ordinary reference.
 *
 * Per axis, with f = floor(d) and phi = d - f, a(q - p - d) is 1 - phi for
 * p = q - f, phi for p = q - f - 1, and 0 for every other p (|d| <= 1), so
 * each frame is a bilinear mix of four dots.  r_k comes from the ground
 * truth (aa_truth_render) of the scene placed at the frame's time and
 * moved by 1 - d_k pixels, on an image of (W + 2) x (H + 2): its pixel
 * p + 1 is dot p, for p from -1 to W (and H).  These images are not
 * cached: they cost one reference of the size each, for each frame.
 *
 * This is the harness's own evaluation of the display, written apart from
 * the method's (algorithms/frames.c); tests/test_crow_methods.c checks both
 * against areas worked out by hand.
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The weights and dot indices along one axis for offset d: the dot of
 * pixel q - f - a has weight wt[a], a = 0, 1. */
static void axis(double d, int *f, double wt[2])
{
    double fl = floor(d);
    *f = (int)fl;
    wt[1] = d - fl;
    wt[0] = 1.0 - wt[1];
}

int aa_display_reference_scene(const aa_scene *pattern, int w, int h, const aa_filter *filter,
                               double vx, double vy, const aa_display_frame *frames, int n,
                               int threads, aa_image *out)
{
    aa_scene *placed = NULL;
    aa_image dots = {0};
    int st;
    if (n < 1 || n > AA_DISPLAY_MAX_FRAMES)
        return aa_fail(AA_EINVAL, "a display of %d frames (1 to %d)", n, AA_DISPLAY_MAX_FRAMES);
    for (int k = 0; k < n; k++)
        if (!(fabs(frames[k].dx) <= 1.0 && fabs(frames[k].dy) <= 1.0))
            return aa_fail(AA_EINVAL, "display frame %d at (%g, %g): offsets must be within "
                                      "[-1, 1]",
                           k, frames[k].dx, frames[k].dy);
    if ((st = aa_size_check(w + 2, h + 2, 4, 1)) || (st = aa_image_alloc(out, w, h, 3)))
        return st;
    memset(out->v, 0, (size_t)w * (size_t)h * 3 * sizeof *out->v);
    if ((st = aa_image_alloc(&dots, w + 2, h + 2, 3)))
        goto done;
    for (int k = 0; k < n && !st; k++) {
        const aa_display_frame *fr = &frames[k];
        placed = aa_scene_place(pattern, w, h, 1.0, fr->t * vx + 1.0 - fr->dx,
                                fr->t * vy + 1.0 - fr->dy);
        if (!placed) {
            st = aa_fail_context(AA_EINVAL, "placing display frame %d", k);
            break;
        }
        if ((st = aa_truth_render(placed, filter, threads, &dots, NULL, NULL)))
            break;
        aa_scene_free(placed);
        placed = NULL;
        int fx, fy;
        double wx[2], wy[2];
        axis(fr->dx, &fx, wx);
        axis(fr->dy, &fy, wy);
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                double *o = aa_pixel(out, i, j);
                for (int b = 0; b < 2; b++)
                    for (int a = 0; a < 2; a++) {
                        double c = fr->weight * wx[a] * wy[b];
                        if (c == 0.0)
                            continue;
                        /* dot (i - fx - a, j - fy - b), pixel + 1 of dots */
                        const double *x = aa_pixel(&dots, i - fx - a + 1, j - fy - b + 1);
                        for (int ch = 0; ch < 3; ch++)
                            o[ch] += c * x[ch];
                    }
            }
    }
done:
    aa_scene_free(placed);
    aa_image_free(&dots);
    if (st)
        aa_image_free(out);
    return st;
}

int aa_display_reference(const aa_view *view, const aa_display_frame *frames, int n,
                         int threads, aa_image *out)
{
    aa_scene *pattern = NULL;
    int st = aa_pattern_scene_at(&view->pattern, view->w, view->h, &pattern);
    if (!st)
        st = aa_display_reference_scene(pattern, view->w, view->h, &view->filter, view->vx,
                                        view->vy, frames, n, threads, out);
    aa_scene_free(pattern);
    return st;
}

int aa_display_view_reference(const aa_view *view, const aa_spec *method, const aa_job *job,
                              int threads, aa_image *out, int *shown)
{
    aa_display_frame frames[AA_DISPLAY_MAX_FRAMES];
    int n, st = aa_method_display(method, job, frames, &n);
    *shown = 0;
    if (st || n == 0)
        return st;
    if ((st = aa_display_reference(view, frames, n, threads, out)))
        return st;
    *shown = 1;
    return AA_OK;
}
