/*
 * converge.c: how a method's error falls with samples per pixel.
 *
 * One fixed scene position measures one alignment of samples and edges;
 * regular grids in particular alias, so their error at one phase says
 * little (algorithms/README.md, "Convergence rates").  So the scene is shifted
 * by K random sub-pixel offsets (phase k: (dx, dy) uniform in [0, 1)^2
 * from the seed; the view is the pattern at time 1 moving (dx, dy)), and
 * at each samples-per-pixel count the RMSE is taken over all K phases
 * together (the root of the mean of the phases' mean squared errors), with
 * the phases' spread.  The slope of log RMSE against log spp comes from
 * gsl_fit_linear, its error from the fit's covariance: about -1/2 for
 * independent random samples, -3/4 for stratified ones on edges.
 *
 * The method's sample count is set through its `spp` parameter, or through
 * `n` (an n x n grid: spp must then be a square).
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

/* The method spec at `spp` samples per pixel. */
static int spec_at(const aa_spec *method, const aa_filter *f, int spp, aa_spec *out)
{
    const char *name = method->info->name;
    int st = aa_method_check(method, f);
    if (st)
        return st;
    *out = *method;
    int k = aa_spec_index(out->info, "spp");
    if (k >= 0) {
        out->v[k] = spp;
    } else if ((k = aa_spec_index(out->info, "n")) >= 0) {
        int n = (int)lround(sqrt((double)spp));
        if (n * n != spp)
            return aa_fail(AA_EINVAL, "method %s takes an n x n grid: spp %d is not a square",
                           name, spp);
        out->v[k] = n;
    } else {
        return aa_fail(AA_EINVAL, "method %s has no spp or n parameter to vary", name);
    }
    const aa_param *p = &out->info->params[k];
    if (out->v[k] < p->min || out->v[k] > p->max)
        return aa_fail(AA_EINVAL, "method %s: %s=%g is out of its range %g to %g", name, p->key,
                       out->v[k], p->min, p->max);
    return aa_method_check(out, f);
}

int aa_converge(const aa_spec *pattern, const aa_spec *method, const aa_filter *f, int w, int h,
                const int *spp, size_t nspp, int phases, uint64_t seed, int threads,
                const char *cache_dir, aa_convergence *out)
{
    return aa_converge_moving(pattern, method, f, w, h, 0.0, 0.0, 0.0, spp, nspp, phases, seed,
                              threads, cache_dir, out);
}

/* Phase k's job and reference view.  Still: the scene at time 1 moving by
 * the shift d (so a still convergence is what it always was).  Moving: the
 * scene translated by d, at time t moving (vx, vy) (a temporal method sees
 * the motion); its reference is the one frame displaced by t v + d. */
static int phase_job(aa_scene *scene, aa_scene **shifted, aa_view *view, const aa_filter *f,
                     double t, double vx, double vy, double dx, double dy, uint64_t seed,
                     int threads, aa_job *job)
{
    int w = view->w, h = view->h;
    view->t = 1.0;
    if (t == 0.0 && vx == 0.0 && vy == 0.0) {
        view->vx = dx, view->vy = dy;
        return aa_job_init(job, scene, w, h, 1.0, dx, dy, f, seed, threads);
    }
    view->vx = t * vx + dx, view->vy = t * vy + dy;
    if (!(*shifted = aa_scene_transform(scene, 1.0, 1.0, dx / w, dy / h)))
        return aa_fail_context(AA_EINVAL, "shifting the scene");
    return aa_job_init(job, *shifted, w, h, t, vx, vy, f, seed, threads);
}

int aa_converge_moving(const aa_spec *pattern, const aa_spec *method, const aa_filter *f, int w,
                       int h, double t, double vx, double vy, const int *spp, size_t nspp,
                       int phases, uint64_t seed, int threads, const char *cache_dir,
                       aa_convergence *out)
{
    int st;
    memset(out, 0, sizeof *out);
    if (nspp < 3 || nspp > 64) /* three points at least for the slope's error */
        return aa_fail(AA_EINVAL, "convergence needs 3 to 64 spp values, not %zu", nspp);
    if (!isfinite(t) || !isfinite(vx) || !isfinite(vy))
        return aa_fail(AA_EINVAL, "time and motion must be finite");
    if (phases < 1 || phases > 1024)
        return aa_fail(AA_EINVAL, "phases %d out of range (1 to 1024)", phases);
    for (size_t k = 0; k < nspp; k++) {
        aa_spec s;
        if (spp[k] < 1 || (k && spp[k] <= spp[k - 1]))
            return aa_fail(AA_EINVAL, "spp values must be positive and increasing");
        if ((st = spec_at(method, f, spp[k], &s)))
            return st;
    }
    aa_scene *scene = NULL;
    aa_image ref = {0}, img = {0};
    double *mse = calloc(nspp * (size_t)phases, sizeof *mse);
    if (!mse)
        return aa_fail(AA_ENOMEM, "out of memory");
    if ((st = aa_pattern_scene_at(pattern, w, h, &scene)) || (st = aa_image_alloc(&img, w, h, 3)))
        goto done;
    for (int k = 0; k < phases && !st; k++) {
        aa_rng rng;
        aa_rng_seed(&rng, seed, (uint64_t)k, 0x5eed);
        double dx = aa_rng_uniform(&rng), dy = aa_rng_uniform(&rng);
        aa_view view = {*pattern, w, h, *f, 1.0, 0.0, 0.0};
        aa_scene *shifted = NULL;
        aa_job job;
        if ((st = phase_job(scene, &shifted, &view, f, t, vx, vy, dx, dy, seed, threads, &job)))
        {
            aa_scene_free(shifted);
            break;
        }
        if ((st = aa_reference(&view, cache_dir, threads, &ref, NULL, NULL))) {
            aa_job_free(&job);
            aa_scene_free(shifted);
            break;
        }
        for (size_t q = 0; q < nspp && !st; q++) {
            aa_spec s;
            aa_counters c;
            aa_metrics m;
            double sec;
            if ((st = spec_at(method, f, spp[q], &s)) ||
                (st = aa_method_run(&s, &job, 1, &img, &c, &sec)) ||
                (st = aa_metrics_compute(&ref, &img, NULL, &m)))
                break;
            mse[q * (size_t)phases + (size_t)k] = m.rmse * m.rmse;
            out->seconds[q] += sec / phases;
        }
        aa_job_free(&job);
        aa_scene_free(shifted);
        aa_image_free(&ref);
    }
    if (st)
        goto done;
    double x[64], y[64];
    out->n = nspp;
    for (size_t q = 0; q < nspp; q++) {
        double sum = 0, s1 = 0, s2 = 0;
        for (int k = 0; k < phases; k++) {
            double e = mse[q * (size_t)phases + (size_t)k];
            sum += e;
            s1 += sqrt(e);
            s2 += e;
        }
        out->spp[q] = spp[q];
        out->rmse[q] = sqrt(sum / phases);
        double mean = s1 / phases;
        out->rmse_sd[q] = phases > 1 ? sqrt(fmax(0.0, (s2 - phases * mean * mean) / (phases - 1)))
                                     : 0.0;
        if (!(out->rmse[q] > 0)) {
            st = aa_fail(AA_EINVAL, "method %s has zero error at spp %d: no slope to fit",
                         method->info->name, spp[q]);
            goto done;
        }
        x[q] = log(out->spp[q]);
        y[q] = log(out->rmse[q]);
    }
    double c0, c1, cov00, cov01, cov11, sumsq;
    gsl_fit_linear(x, 1, y, 1, nspp, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
    out->intercept = c0;
    out->slope = c1;
    out->slope_err = sqrt(cov11);
done:
    free(mse);
    aa_image_free(&ref);
    aa_image_free(&img);
    aa_scene_free(scene);
    return st;
}
