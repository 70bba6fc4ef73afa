/*
 * frames.c: a stack of offset point-sampled frames, combined (frames.h).
 */
#include "core.h"
#include "frames.h"
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

void aa__frames_free(aa__frames *fs)
{
    if (fs->placed) {
        int n = fs->shared ? 1 : fs->n;
        for (int k = 0; k < n; k++)
            aa_scene_free(fs->placed[k]);
    }
    free(fs->placed);
    free(fs->scratch);
    free(fs->dots);
    memset(fs, 0, sizeof *fs);
}

static int same_job(const aa__frames *fs, const aa_job *job, int n)
{
    return fs->scratch && fs->pattern == job->pattern && fs->w == job->w && fs->h == job->h &&
           fs->threads == job->threads && fs->t == job->t && fs->vx == job->vx &&
           fs->vy == job->vy && fs->n == n;
}

int aa__frames_ready(aa__frames *fs, const aa_job *job, int n)
{
    if (same_job(fs, job, n))
        return AA_OK;
    aa__frames_free(fs);
    if (!(fs->placed = calloc((size_t)n, sizeof *fs->placed)))
        return aa_fail(AA_ENOMEM, "out of memory for %d frames", n);
    fs->pattern = job->pattern;
    fs->w = job->w, fs->h = job->h, fs->threads = job->threads;
    fs->t = job->t, fs->vx = job->vx, fs->vy = job->vy;
    fs->shared = job->vx == 0.0 && job->vy == 0.0;
    for (int k = 0; k < (fs->shared ? 1 : n); k++) {
        fs->placed[k] = aa_scene_place(job->pattern, job->w, job->h, job->t - k, job->vx,
                                       job->vy);
        fs->n = k + 1; /* what to free */
        if (!fs->placed[k]) {
            int st = aa_fail_context(AA_EINVAL, "placing frame %d", k);
            fs->n = k;
            aa__frames_free(fs);
            return st;
        }
    }
    fs->n = n;
    if (fs->shared)
        for (int k = 1; k < n; k++)
            fs->placed[k] = fs->placed[0];
    size_t len = (size_t)(job->threads > 0 ? job->threads : 1) * AA__FRAMES_BAND *
                 (size_t)job->w * 3;
    if (!(fs->scratch = malloc(len * sizeof *fs->scratch))) {
        aa__frames_free(fs);
        return aa_fail(AA_ENOMEM, "out of memory for %d scratch bands", job->threads);
    }
    return AA_OK;
}

static void blend(double *restrict m, const double *restrict x, size_t len, double wt)
{
#pragma omp simd
    for (size_t q = 0; q < len; q++)
        m[q] += (x[q] - m[q]) * wt;
}

int aa__frames_render(aa__frames *fs, const aa_job *job, int n, const double *dx,
                      const double *dy, const double *weight, aa_image *out,
                      aa_counters *counters)
{
    if (n < 1 || n > fs->n)
        return aa_fail(AA_EFAIL, "%d frames asked of a stack of %d", n, fs->n);
    const int w = job->w, bands = (job->h + AA__FRAMES_BAND - 1) / AA__FRAMES_BAND;
    int status = AA_OK;
#pragma omp parallel num_threads(job->threads)
    {
        int me = 0;
#ifdef _OPENMP
        me = omp_get_thread_num();
#endif
        double *scratch = fs->scratch + (size_t)me * AA__FRAMES_BAND * (size_t)w * 3;
        aa_point_ws ws;
        /* every frame's scene has the same pieces: one workspace serves all */
        int bad = aa_point_ws_init(&ws, fs->placed[0]);
#pragma omp for schedule(static)
        for (int b = 0; b < bands; b++) {
            if (bad)
                continue;
            const int j0 = b * AA__FRAMES_BAND;
            const int bh = job->h - j0 < AA__FRAMES_BAND ? job->h - j0 : AA__FRAMES_BAND;
            const size_t len = (size_t)bh * (size_t)w * 3;
            double *band = aa_pixel(out, 0, j0);
            for (int j = 0; j < bh; j++)
                aa_point_row(fs->placed[n - 1], &ws, dx[n - 1], j0 + j + 0.5 + dy[n - 1],
                             band + 3 * (size_t)j * (size_t)w, w);
            for (int k = n - 2; k >= 0; k--) {
                for (int j = 0; j < bh; j++)
                    aa_point_row(fs->placed[k], &ws, dx[k], j0 + j + 0.5 + dy[k],
                                 scratch + 3 * (size_t)j * (size_t)w, w);
                blend(band, scratch, len, weight[k]);
            }
        }
        if (!bad)
            aa_point_ws_free(&ws);
        else {
#pragma omp atomic write
            status = bad;
        }
    }
    if (status)
        return aa_fail(status, "out of memory while sampling the frames");
    counters->samples = (uint64_t)n * (uint64_t)job->w * (uint64_t)job->h;
    counters->expensive_pixels = 0;
    return AA_OK;
}

/* Per thread, for the screen: one row of w + 1 dots as sampled, a band of
 * AA__FRAMES_BAND + 1 rows of dots mixed along x (w values each), and for
 * each of the n frames the last such row of the band before. */
static size_t screen_per_thread(const aa__frames *fs)
{
    return (size_t)(fs->w + 1) * 3 +
           ((size_t)AA__FRAMES_BAND + 1 + (size_t)fs->n) * (size_t)fs->w * 3;
}

int aa__frames_screen(aa__frames *fs)
{
    if (fs->dots)
        return AA_OK;
    size_t len = (size_t)(fs->threads > 0 ? fs->threads : 1) * screen_per_thread(fs);
    if (!(fs->dots = malloc(len * sizeof *fs->dots)))
        return aa_fail(AA_ENOMEM, "out of memory for the screen's dots (%d threads)",
                       fs->threads);
    memset(fs->dots, 0, len * sizeof *fs->dots); /* touched here, not in the timed render */
    return AA_OK;
}

/* Along one axis, offset d: f = floor(d), phi = d - f.  Pixel q is covered
 * by dot q - f (area 1 - phi) and dot q - f - 1 (area phi); the dots of a
 * frame are numbered from p0 = -f - 1, so these are dots q + 1 and q, and
 * q's value is x[q + 1] + phi (x[q] - x[q + 1]): a mix of two equal values
 * is that value exactly. */
static double axis(double d, int *p0)
{
    double f = floor(d);
    *p0 = -(int)f - 1;
    return d - f;
}

/* Output rows [a, a + bh) of frame k into out.  Dot rows a .. a + bh (of
 * the frame's numbering) are sampled into `dots` one at a time and mixed
 * along x into `band`; row a comes from `carry` when `have`, and the last
 * row is left in `carry` for the next band. */
static void screen_band(const aa__frames *fs, aa_point_ws *ws, int k, double dxk, double dyk,
                        int a, int bh, int w, double wt, int first, int have, double *dots,
                        double *band, double *carry, aa_image *out)
{
    int px0, py0;
    const double phx = axis(dxk, &px0), phy = axis(dyk, &py0);
    const size_t len = 3 * (size_t)w;
    if (have)
        memcpy(band, carry, len * sizeof *band);
    for (int r = have ? 1 : 0; r <= bh; r++) {
        aa_point_row(fs->placed[k], ws, dxk + px0, py0 + a + r + 0.5 + dyk, dots, w + 1);
        /* element q of a pixel row: dots q + 3 (area 1 - phx) and q (phx) */
        double *x = band + (size_t)r * len;
#pragma omp simd
        for (size_t q = 0; q < len; q++)
            x[q] = dots[q + 3] + phx * (dots[q] - dots[q + 3]);
    }
    memcpy(carry, band + (size_t)bh * len, len * sizeof *band);
    for (int r = 0; r < bh; r++) {
        /* output row a + r: mixed dot rows r + 1 (area 1 - phy) and r (phy) */
        const double *x1 = band + (size_t)(r + 1) * len, *x0 = band + (size_t)r * len;
        double *o = aa_pixel(out, 0, a + r);
        if (first) {
#pragma omp simd
            for (size_t q = 0; q < len; q++)
                o[q] = x1[q] + phy * (x0[q] - x1[q]);
        } else {
#pragma omp simd
            for (size_t q = 0; q < len; q++) {
                double v = x1[q] + phy * (x0[q] - x1[q]);
                o[q] += (v - o[q]) * wt;
            }
        }
    }
}

int aa__frames_render_screen(aa__frames *fs, const aa_job *job, int n, const double *dx,
                             const double *dy, const double *weight, aa_image *out,
                             aa_counters *counters)
{
    if (n < 1 || n > fs->n)
        return aa_fail(AA_EFAIL, "%d frames asked of a stack of %d", n, fs->n);
    if (!fs->dots)
        return aa_fail(AA_EFAIL, "the screen's dots were not made (aa__frames_screen)");
    for (int k = 0; k < n; k++)
        if (!(fabs(dx[k]) <= 1.0 && fabs(dy[k]) <= 1.0))
            return aa_fail(AA_EFAIL, "dots moved by (%g, %g): more than a pixel", dx[k], dy[k]);
    const int w = job->w, h = job->h;
    const size_t drow = 3 * (size_t)(w + 1);
    int status = AA_OK;
#pragma omp parallel num_threads(job->threads)
    {
        int me = 0, team = 1;
#ifdef _OPENMP
        me = omp_get_thread_num(), team = omp_get_num_threads();
#endif
        double *dots = fs->dots + (size_t)me * screen_per_thread(fs);
        double *band = dots + drow;
        double *carry = band + ((size_t)AA__FRAMES_BAND + 1) * 3 * (size_t)w; /* n rows */
        aa_point_ws ws;
        int bad = aa_point_ws_init(&ws, fs->placed[0]);
        /* a contiguous block of rows per thread, in bands; each band of a
         * frame starts from the last row of dots of the band before */
        const int j0 = (int)((long long)h * me / team), j1 = (int)((long long)h * (me + 1) / team);
        for (int a = j0; a < j1 && !bad; a += AA__FRAMES_BAND) {
            const int bh = j1 - a < AA__FRAMES_BAND ? j1 - a : AA__FRAMES_BAND;
            for (int k = n - 1; k >= 0; k--) /* oldest first */
                screen_band(fs, &ws, k, dx[k], dy[k], a, bh, w, weight[k], k == n - 1, a > j0,
                            dots, band, carry + (size_t)k * 3 * (size_t)w, out);
        }
        if (!bad)
            aa_point_ws_free(&ws);
        else {
#pragma omp atomic write
            status = bad;
        }
    }
    if (status)
        return aa_fail(status, "out of memory while sampling the frames");
    counters->samples = (uint64_t)n * (uint64_t)(w + 1) * (uint64_t)(h + 1);
    counters->expensive_pixels = 0;
    return AA_OK;
}

double aa__radical_inverse(uint64_t i, unsigned b)
{
    double inv = 1.0 / b, f = inv, r = 0.0;
    for (; i; i /= b, f *= inv)
        r += (double)(i % b) * f;
    return r;
}
