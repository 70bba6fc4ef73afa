/*
 * timing.c: timing by precision, and the statistics it reports (core.h,
 * "timing and its statistics").
 *
 * The repetitions follow hyperfine, Google Benchmark and pyperf: a warm-up
 * render, then timed renders until the median is known to a target
 * precision or a budget runs out.  The precision is the distribution-free
 * confidence interval of the median by order statistics (render times are
 * skewed, with a long right tail, so no normal model is assumed).  The
 * machine is watched meanwhile: the load average, and /proc/stat's busy and
 * stolen time less this process's own CPU time, so a measurement taken
 * while other processes used the cores is marked, as hyperfine warns of
 * statistical outliers.  Distributions come from GSL (gsl_cdf_binomial_P,
 * gsl_cdf_tdist_Pinv, gsl_cdf_ugaussian_Q), sample statistics from
 * gsl_statistics.
 */
#include "core.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

/* ---- statistics ---- */

int aa_median_ci_ranks(size_t n, double level, size_t *lo, size_t *hi, double *coverage)
{
    if (!(level > 0 && level < 1))
        return aa_fail(AA_EINVAL, "confidence level %g out of range (0 to 1)", level);
    double tail = (1.0 - level) / 2;
    /* the largest l with P(B <= l - 1) <= tail; that probability grows with
     * l, so bisect over 1 .. floor((n + 1) / 2) */
    size_t a = 0, b = (n + 1) / 2; /* P(B <= a - 1) <= tail holds for a = 0 */
    if (n == 0 || gsl_cdf_binomial_P(0, 0.5, (unsigned)n) > tail)
        return aa_fail(AA_EINVAL, "%zu values are too few for a %g%% interval of the median", n,
                       100 * level);
    a = 1;
    while (a < b) {
        size_t m = (a + b + 1) / 2;
        if (gsl_cdf_binomial_P((unsigned)(m - 1), 0.5, (unsigned)n) <= tail)
            a = m;
        else
            b = m - 1;
    }
    *lo = a;
    *hi = n + 1 - a;
    *coverage = 1.0 - 2.0 * gsl_cdf_binomial_P((unsigned)(a - 1), 0.5, (unsigned)n);
    return AA_OK;
}

int aa_time_stats_compute(const double *x, size_t n, aa_time_stats *s)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->median = s->mean = s->sd = s->mad = s->min = s->max = NAN;
    s->ci_lo = s->ci_hi = s->ci_level = NAN;
    if (n == 0)
        return AA_OK;
    double *v = malloc(2 * n * sizeof *v);
    if (!v)
        return aa_fail(AA_ENOMEM, "out of memory for %zu times", n);
    memcpy(v, x, n * sizeof *v);
    gsl_sort(v, 1, n);
    s->median = gsl_stats_median_from_sorted_data(v, 1, n);
    s->mean = gsl_stats_mean(v, 1, n);
    s->sd = n > 1 ? gsl_stats_sd(v, 1, n) : NAN;
    s->mad = gsl_stats_mad(v, 1, n, v + n);
    s->min = v[0];
    s->max = v[n - 1];
    size_t lo, hi;
    double level;
    if (n >= 6 && !aa_median_ci_ranks(n, 0.95, &lo, &hi, &level)) {
        s->ci_lo = v[lo - 1];
        s->ci_hi = v[hi - 1];
        s->ci_level = level;
    }
    if (s->mad > 0)
        for (size_t k = 0; k < n; k++)
            s->outliers += fabs(v[k] - s->median) > 3 * s->mad;
    free(v);
    return AA_OK;
}

double aa_time_stats_outlier_shift(const double *x, size_t n)
{
    aa_time_stats s;
    if (n == 0 || aa_time_stats_compute(x, n, &s) || s.outliers == 0 || !(s.median > 0))
        return 0.0;
    double *kept = malloc(n * sizeof *kept);
    if (!kept)
        return NAN;
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (!(fabs(x[k] - s.median) > 3 * s.mad))
            kept[m++] = x[k];
    double shift = 0.0;
    if (m) {
        gsl_sort(kept, 1, m);
        double median = gsl_stats_median_from_sorted_data(kept, 1, m);
        shift = fabs(s.median - median) / median;
    }
    free(kept);
    return shift;
}

void aa_timing_ci_text(const aa_timing *t, char *buf, size_t len)
{
    if (t->n > 0 && isfinite(t->ci_rel))
        snprintf(buf, len, "+-%.1f%%", 100 * t->ci_rel);
    else if (t->n < AA_TIMING_CI_MIN_REPS)
        snprintf(buf, len, "CI needs %d renders", AA_TIMING_CI_MIN_REPS);
    else
        snprintf(buf, len, "no CI");
}

int aa_mean_ci(const double *x, size_t n, double level, double *mean, double *lo, double *hi)
{
    if (n < 2 || !(level > 0 && level < 1))
        return aa_fail(AA_EINVAL, "a mean's interval needs 2 values or more and 0 < level < 1");
    double m = gsl_stats_mean(x, 1, n), sd = gsl_stats_sd_m(x, 1, n, m);
    double half = gsl_cdf_tdist_Pinv(0.5 + level / 2, (double)(n - 1)) * sd / sqrt((double)n);
    *mean = m;
    *lo = m - half;
    *hi = m + half;
    return AA_OK;
}

typedef struct tagged {
    double v;
    int from_x;
} tagged;

static int cmp_tagged(const void *a, const void *b)
{
    double x = ((const tagged *)a)->v, y = ((const tagged *)b)->v;
    return x < y ? -1 : x > y;
}

int aa_mann_whitney(const double *x, size_t nx, const double *y, size_t ny, double *u, double *z,
                    double *p)
{
    if (nx == 0 || ny == 0)
        return aa_fail(AA_EINVAL, "the Mann-Whitney test needs values on both sides");
    size_t n = nx + ny;
    tagged *all = malloc(n * sizeof *all);
    if (!all)
        return aa_fail(AA_ENOMEM, "out of memory for %zu values", n);
    for (size_t k = 0; k < nx; k++)
        all[k] = (tagged){x[k], 1};
    for (size_t k = 0; k < ny; k++)
        all[nx + k] = (tagged){y[k], 0};
    qsort(all, n, sizeof *all, cmp_tagged);
    /* midranks; the ties' sum of t^3 - t for the variance */
    double rank_x = 0, ties = 0;
    for (size_t a = 0; a < n;) {
        size_t b = a;
        while (b + 1 < n && all[b + 1].v == all[a].v)
            b++;
        double mid = 0.5 * (double)(a + b) + 1.0, t = (double)(b - a + 1);
        for (size_t k = a; k <= b; k++)
            if (all[k].from_x)
                rank_x += mid;
        ties += t * t * t - t;
        a = b + 1;
    }
    free(all);
    double fx = (double)nx, fy = (double)ny, fn = (double)n;
    *u = rank_x - fx * (fx + 1) / 2;
    double var = fx * fy / 12.0 * ((fn + 1) - (n > 1 ? ties / (fn * (fn - 1)) : 0.0));
    if (!(var > 0)) {
        *z = 0;
        *p = 1;
        return AA_OK;
    }
    *z = (*u - fx * fy / 2) / sqrt(var);
    *p = fmin(1.0, 2 * gsl_cdf_ugaussian_Q(fabs(*z)));
    return AA_OK;
}

void aa_noisy_text(unsigned noisy, char *buf, size_t len)
{
    static const char *const names[] = {"ci", "outliers", "busy", "steal", "preempted"};
    size_t used = 0;
    if (len)
        buf[0] = '\0';
    for (unsigned k = 0; k < sizeof names / sizeof *names; k++)
        if (noisy & (1u << k)) {
            int m = snprintf(buf + used, len > used ? len - used : 0, "%s%s", used ? "+" : "",
                             names[k]);
            if (m > 0)
                used += (size_t)m;
        }
}

unsigned aa_noisy_parse(const char *text)
{
    static const char *const names[] = {"ci", "outliers", "busy", "steal", "preempted"};
    unsigned bits = 0;
    for (const char *p = text; p && *p;) {
        size_t m = strcspn(p, "+");
        for (unsigned k = 0; k < sizeof names / sizeof *names; k++)
            if (strlen(names[k]) == m && !strncmp(p, names[k], m))
                bits |= 1u << k;
        p += m;
        if (*p == '+')
            p++;
    }
    return bits;
}

/* ---- the machine around a measurement ---- */

/* This process's CPU seconds and its waited-for children's (an external
 * renderer's program runs in a child). */
static double own_cpu(void)
{
    struct rusage self, kids;
    if (getrusage(RUSAGE_SELF, &self) || getrusage(RUSAGE_CHILDREN, &kids))
        return NAN;
    return (double)self.ru_utime.tv_sec + 1e-6 * (double)self.ru_utime.tv_usec +
           (double)self.ru_stime.tv_sec + 1e-6 * (double)self.ru_stime.tv_usec +
           (double)kids.ru_utime.tv_sec + 1e-6 * (double)kids.ru_utime.tv_usec +
           (double)kids.ru_stime.tv_sec + 1e-6 * (double)kids.ru_stime.tv_usec;
}

static void take_snapshot(aa_machine_sample *s)
{
    memset(s, 0, sizeof *s);
    s->load = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &s->load) != 1)
            s->load = NAN;
        fclose(f);
    }
    f = fopen("/proc/stat", "r");
    if (f) {
        unsigned long long v[10] = {0};
        int got = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1],
                         &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9]);
        fclose(f);
        if (got >= 8) {
            /* user nice system idle iowait irq softirq steal (guest in user) */
            s->busy = v[0] + v[1] + v[2] + v[5] + v[6];
            s->steal = v[7];
            s->total = s->busy + v[3] + v[4] + v[7];
            s->have_stat = 1;
        }
    }
    s->own = own_cpu();
    s->wall = aa_now();
}

void aa_machine_use(const aa_machine_sample *a, const aa_machine_sample *b, long hz, long cores,
                    int threads, double *others, double *steal, double *allowance)
{
    *others = *steal = *allowance = NAN;
    double dt = b->wall - a->wall;
    if (!(dt > 0) || hz <= 0 || cores <= 0)
        return;
    double window = 2.0 * (double)cores / (double)hz / dt; /* the ticks' error, in cores */
    if (a->have_stat && b->have_stat && b->busy >= a->busy && b->total >= a->total) {
        unsigned long long total = b->total - a->total;
        *steal = total ? (double)(b->steal - a->steal) / (double)total : 0.0;
        if (window < AA_TIMING_STAT_WINDOW) {
            double busy = (double)(b->busy - a->busy) / (double)hz, own = b->own - a->own;
            if (isfinite(own)) {
                *others = fmin((double)cores, fmax(0.0, (busy - own) / dt));
                *allowance = window;
                return;
            }
        }
    }
    /* too short a window for the ticks, or no /proc/stat: the load average
     * around it, less this process's own threads */
    double load = fmin(a->load, b->load);
    if (isfinite(load)) {
        *others = fmin((double)cores, fmax(0.0, load - (double)(threads > 0 ? threads : 1)));
        *allowance = AA_TIMING_BUSY_LOAD;
    }
}

/* A render's CPU time so far: the calling thread's clock for one thread,
 * the process's for several, plus the children waited for. */
static double cpu_now(int threads)
{
    struct timespec t;
    struct rusage kids;
    if (clock_gettime(threads == 1 ? CLOCK_THREAD_CPUTIME_ID : CLOCK_PROCESS_CPUTIME_ID, &t) ||
        getrusage(RUSAGE_CHILDREN, &kids))
        return NAN;
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec + (double)kids.ru_utime.tv_sec +
           1e-6 * (double)kids.ru_utime.tv_usec + (double)kids.ru_stime.tv_sec +
           1e-6 * (double)kids.ru_stime.tv_usec;
}

void aa_timing_judge(aa_timing *t, double allowance, long cores)
{
    t->noisy = 0;
    /* the target counts when it was the rule, or when a fixed count still
     * gave an interval to judge */
    if (!t->target_met && (!t->fixed || isfinite(t->ci_rel)))
        t->noisy |= AA_NOISY_CI;
    /* outliers by their effect: they move the median beyond the target */
    if (t->stats.outliers && t->n > 0 &&
        aa_time_stats_outlier_shift(t->wall, (size_t)t->n) > t->target_ci)
        t->noisy |= AA_NOISY_OUTLIERS;
    if (t->others_cores > AA_TIMING_BUSY_CORES + (isfinite(allowance) ? allowance : 0))
        t->noisy |= AA_NOISY_BUSY;
    if (t->steal > 0.01 && cores > 0 && t->steal * (double)cores > allowance)
        t->noisy |= AA_NOISY_STEAL;
    if (t->threads == 1 && t->cpu_share < AA_TIMING_CPU_SHARE)
        t->noisy |= AA_NOISY_PREEMPTED;
}

/* ---- measuring ---- */

static void settle(aa_timing *t)
{
    aa_time_stats_compute(t->wall, (size_t)t->n, &t->stats);
    t->ci_rel = isfinite(t->stats.ci_lo) && t->stats.median > 0
                    ? (t->stats.ci_hi - t->stats.ci_lo) / 2 / t->stats.median
                    : NAN;
    t->target_met = t->ci_rel <= t->target_ci;
}

static int done(const aa_timing *t, const aa_timing_plan *plan, double spent, double budget)
{
    if (t->n >= AA_TIMING_MAX_REPS)
        return 1;
    if (plan->reps > 0)
        return t->n >= plan->reps;
    return t->n >= AA_TIMING_MIN_REPS && (t->target_met || spent >= budget);
}

/* the time a method reported for the render under way (-1: none) */
static _Thread_local double reported = -1;

void aa_method_report_seconds(double seconds)
{
    if (isfinite(seconds) && seconds >= 0)
        reported = seconds;
}

int aa_timing_measure(const aa_timing_plan *plan, size_t k, aa_timed_fn const *fn,
                      void *const *ctx, const int *threads, aa_timing *out)
{
    if (plan->reps < 0 || plan->reps > AA_TIMING_MAX_REPS || plan->target_ci < 0 ||
        plan->budget < 0)
        return aa_fail(AA_EINVAL, "timing plan out of range (reps 0 to %d, target and budget "
                                  ">= 0)",
                       AA_TIMING_MAX_REPS);
    double target = plan->target_ci > 0 ? plan->target_ci : AA_TIMING_TARGET;
    double budget = (plan->budget > 0 ? plan->budget : AA_TIMING_BUDGET) * (double)k;
    int *finished = calloc(k ? k : 1, sizeof *finished);
    if (!finished)
        return aa_fail(AA_ENOMEM, "out of memory");
    for (size_t i = 0; i < k; i++) {
        memset(&out[i], 0, sizeof out[i]);
        out[i].threads = threads[i];
        out[i].fixed = plan->reps > 0;
        out[i].target_ci = target;
        out[i].budget = budget / (double)k;
    }
    aa_machine_sample before, after;
    take_snapshot(&before);
    int st = AA_OK;
    for (size_t i = 0; i < k && !st; i++)
        st = fn[i](ctx[i]); /* warm-up */
    double spent = 0;
    for (size_t left = k; left && !st;) {
        for (size_t i = 0; i < k && !st; i++) {
            if (finished[i])
                continue;
            aa_timing *t = &out[i];
            reported = -1;
            double c0 = cpu_now(t->threads), w0 = aa_now();
            st = fn[i](ctx[i]);
            double w1 = aa_now(), c1 = cpu_now(t->threads);
            t->wall[t->n] = w1 - w0;
            t->cpu[t->n] = c1 - c0;
            if (reported >= 0) /* the program's own time, its start-up left out */
                t->wall[t->n] = t->cpu[t->n] = reported, t->reported++;
            t->n++;
            spent += w1 - w0;
        }
        for (size_t i = 0; i < k && !st; i++) {
            if (finished[i])
                continue;
            if (plan->reps == 0 && out[i].n >= 6)
                settle(&out[i]);
            if (done(&out[i], plan, spent, budget))
                finished[i] = 1, left--;
        }
    }
    take_snapshot(&after);
    free(finished);
    if (st)
        return st;
    double others, steal, allowance;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int most = 1;
    for (size_t i = 0; i < k; i++)
        most = out[i].threads > most ? out[i].threads : most;
    aa_machine_use(&before, &after, sysconf(_SC_CLK_TCK), cores, most, &others, &steal,
                   &allowance);
    for (size_t i = 0; i < k; i++) {
        aa_timing *t = &out[i];
        settle(t);
        double cw = 0, ww = 0, cpus[AA_TIMING_MAX_REPS];
        for (int r = 0; r < t->n; r++)
            cw += t->cpu[r], ww += t->wall[r], cpus[r] = t->cpu[r];
        gsl_sort(cpus, 1, (size_t)t->n);
        t->cpu_median = t->n ? gsl_stats_median_from_sorted_data(cpus, 1, (size_t)t->n) : NAN;
        t->cpu_share = ww > 0 ? cw / ww : NAN;
        t->load_before = before.load;
        t->load_after = after.load;
        t->others_cores = others;
        t->steal = steal;
        t->elapsed = after.wall - before.wall;
        aa_timing_judge(t, allowance, cores);
    }
    return AA_OK;
}

/* ---- a method, timed ---- */

typedef struct method_ctx {
    aa_method *m;
    const aa_job *job;
    aa_image *out;
    aa_counters *counters;
} method_ctx;

static int render_once(void *vctx)
{
    method_ctx *c = vctx;
    return aa_method_render(c->m, c->job, c->out, c->counters);
}

int aa_method_time(const aa_spec *spec, const aa_job *job, const aa_timing_plan *plan,
                   aa_image *out, aa_counters *counters, aa_timing *timing)
{
    aa_method m;
    /* the init on its own clocks (the process's CPU: an init may use
     * several threads whatever the job's count) */
    double w0 = aa_now(), c0 = cpu_now(0);
    int st = aa_method_init(&m, spec, job);
    double w1 = aa_now(), c1 = cpu_now(0);
    if (st)
        return st;
    /* touch the output once: page faults are not the method's cost */
    memset(out->v, 0, (size_t)out->w * (size_t)out->h * 3 * sizeof *out->v);
    method_ctx c = {&m, job, out, counters};
    aa_timed_fn fn = render_once;
    void *ctx = &c;
    st = aa_timing_measure(plan, 1, &fn, &ctx, &job->threads, timing);
    timing->init_seconds = w1 - w0;
    timing->init_cpu = c1 - c0;
    aa_method_free(&m);
    return st;
}
