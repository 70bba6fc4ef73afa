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

double aa__radical_inverse(uint64_t i, unsigned b)
{
    double inv = 1.0 / b, f = inv, r = 0.0;
    for (; i; i /= b, f *= inv)
        r += (double)(i % b) * f;
    return r;
}
