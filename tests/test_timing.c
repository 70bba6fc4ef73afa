/*
 * test_timing.c: the timing statistics against answers derived elsewhere,
 * and the repetition rule's counts.  No test asserts a time.
 *
 * Known answers and where they come from:
 *  - the ranks of the 95% confidence interval of the median: the published
 *    table of Campbell and Gardner (BMJ 1988, "Calculating confidence
 *    intervals for some non-parametric analyses", table 1, exact binomial
 *    ranks for n <= 50; Conover, "Practical nonparametric statistics", for
 *    n = 100: the 40th and 61st values), and the exact coverages
 *    1 - 2 P(B <= l - 1) as fractions over 2^n from integer binomial sums
 *    (n = 6: 62/64; n = 10: 1 - 22/1024; n = 20: 1 - 43400/2^20);
 *  - Mann-Whitney U: R's documented example (?wilcox.test, Hollander and
 *    Wolfe 1973 p. 69: permeability constants, W = 35, large-sample
 *    p = 0.1103 one-sided) and a small tied example worked by hand below;
 *  - the mean's interval: Student's t quantile t(0.975, 4) = 2.776 from the
 *    printed t table;
 *  - median, mean, standard deviation and MAD of {1, 2, 3, 4, 100} by hand.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

static void test_median_ci_table(void **state)
{
    (void)state;
    /* n, lower rank, upper rank (Campbell and Gardner 1988, table 1) */
    static const size_t table[][3] = {
        {6, 1, 6},    {7, 1, 7},    {8, 1, 8},    {9, 2, 8},    {10, 2, 9},
        {11, 2, 10},  {12, 3, 10},  {13, 3, 11},  {14, 3, 12},  {15, 4, 12},
        {16, 4, 13},  {17, 5, 13},  {18, 5, 14},  {19, 5, 15},  {20, 6, 15},
        {25, 8, 18},  {30, 10, 21}, {40, 14, 27}, {50, 18, 33}, {100, 40, 61}};
    for (size_t k = 0; k < sizeof table / sizeof *table; k++) {
        size_t lo, hi;
        double cov;
        assert_int_equal(aa_median_ci_ranks(table[k][0], 0.95, &lo, &hi, &cov), AA_OK);
        if (lo != table[k][1] || hi != table[k][2])
            fail_msg("n = %zu: ranks %zu, %zu; the table gives %zu, %zu", table[k][0], lo, hi,
                     table[k][1], table[k][2]);
        assert_true(cov >= 0.95 && cov < 1);
    }
    /* exact coverages: integer binomial sums over 2^n */
    size_t lo, hi;
    double cov;
    assert_int_equal(aa_median_ci_ranks(6, 0.95, &lo, &hi, &cov), AA_OK);
    assert_true(fabs(cov - 62.0 / 64.0) < 1e-14);
    assert_int_equal(aa_median_ci_ranks(10, 0.95, &lo, &hi, &cov), AA_OK);
    assert_true(fabs(cov - (1.0 - 22.0 / 1024.0)) < 1e-14);
    /* n = 20: P(B <= 5) = (1 + 20 + 190 + 1140 + 4845 + 15504) / 2^20 */
    assert_int_equal(aa_median_ci_ranks(20, 0.95, &lo, &hi, &cov), AA_OK);
    assert_true(fabs(cov - (1.0 - 2.0 * 21700.0 / 1048576.0)) < 1e-14);
    /* five values cannot give 95%: the widest interval covers 1 - 2/32 */
    assert_int_equal(aa_median_ci_ranks(5, 0.95, &lo, &hi, &cov), AA_EINVAL);
    assert_int_equal(aa_median_ci_ranks(0, 0.95, &lo, &hi, &cov), AA_EINVAL);
    /* a lower level: n = 5 at 90% is [x(1), x(5)] covering 30/32 */
    assert_int_equal(aa_median_ci_ranks(5, 0.90, &lo, &hi, &cov), AA_OK);
    assert_true(lo == 1 && hi == 5 && fabs(cov - 30.0 / 32.0) < 1e-14);
}

static void test_time_stats(void **state)
{
    (void)state;
    /* {1, 2, 3, 4, 100}: median 3, mean 22, sample variance
     * (441 + 400 + 361 + 324 + 6084) / 4 = 1902.5; absolute deviations from
     * the median {2, 1, 0, 1, 97}, their median 1, scaled 1.482602218505602
     * (1 / Phi^-1(3/4)); only 100 lies beyond 3 of those */
    const double x[] = {4, 100, 1, 3, 2};
    aa_time_stats s;
    assert_int_equal(aa_time_stats_compute(x, 5, &s), AA_OK);
    assert_true(s.n == 5 && s.median == 3 && s.mean == 22 && s.min == 1 && s.max == 100);
    assert_true(fabs(s.sd - sqrt(1902.5)) < 1e-12);
    assert_true(fabs(s.mad - 1.482602218505602) < 1e-9);
    assert_int_equal(s.outliers, 1);
    assert_true(isnan(s.ci_lo) && isnan(s.ci_hi) && isnan(s.ci_level)); /* n < 6 */
    /* 1..10 shuffled: median 5.5, interval [x(2), x(9)] = [2, 9] */
    const double y[] = {7, 3, 10, 1, 5, 9, 2, 8, 6, 4};
    assert_int_equal(aa_time_stats_compute(y, 10, &s), AA_OK);
    assert_true(s.median == 5.5 && s.ci_lo == 2 && s.ci_hi == 9);
    assert_true(fabs(s.ci_level - (1.0 - 22.0 / 1024.0)) < 1e-14);
    assert_int_equal(s.outliers, 0);
    assert_int_equal(aa_time_stats_compute(y, 0, &s), AA_OK);
    assert_true(s.n == 0 && isnan(s.median));
}

static void test_mean_ci(void **state)
{
    (void)state;
    /* {1, ..., 5}: mean 3, s = sqrt(2.5), half-width t(0.975, 4) s / sqrt 5
     * with t = 2.776 (t table; 2.7764451 to more places) */
    const double x[] = {1, 2, 3, 4, 5};
    double m, lo, hi;
    assert_int_equal(aa_mean_ci(x, 5, 0.95, &m, &lo, &hi), AA_OK);
    double half = 2.7764451 * sqrt(2.5) / sqrt(5.0);
    assert_true(m == 3 && fabs(lo - (3 - half)) < 1e-6 && fabs(hi - (3 + half)) < 1e-6);
    assert_int_equal(aa_mean_ci(x, 1, 0.95, &m, &lo, &hi), AA_EINVAL);
}

static void test_mann_whitney_r_example(void **state)
{
    (void)state;
    /* R: x <- c(0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46);
     * y <- c(1.15, 0.88, 0.90, 0.74, 1.21);
     * wilcox.test(x, y, alternative = "greater", exact = FALSE,
     * correct = FALSE): W = 35, p-value = 0.1103 */
    const double x[] = {0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
    const double y[] = {1.15, 0.88, 0.90, 0.74, 1.21};
    double u, z, p;
    assert_int_equal(aa_mann_whitney(x, 10, y, 5, &u, &z, &p), AA_OK);
    assert_true(u == 35);
    assert_true(z > 0);
    assert_true(fabs(p / 2 - 0.1103) < 5e-5); /* one-sided is half the two-sided */
    /* the other way round: U of y is 10 x 5 - 35, z changes sign */
    double u2, z2, p2;
    assert_int_equal(aa_mann_whitney(y, 5, x, 10, &u2, &z2, &p2), AA_OK);
    assert_true(u2 == 15 && fabs(z2 + z) < 1e-12 && fabs(p2 - p) < 1e-12);
}

static void test_mann_whitney_ties(void **state)
{
    (void)state;
    /* x = {1, 2, 2, 3}, y = {2, 3, 3, 4}.  Sorted: 1x 2x 2x 2y 3x 3y 3y 4y;
     * midranks 1; 3, 3, 3; 6, 6, 6; 8.  Rank sum of x = 1 + 3 + 3 + 6 = 13,
     * U = 13 - 4 * 5 / 2 = 3, mean 4 * 4 / 2 = 8.  Ties: two groups of 3,
     * sum of t^3 - t = 48; variance 16/12 (9 - 48 / (8 * 7)) = 10.857142857;
     * z = -5 / sqrt(10.857142857) = -1.5174424467; two-sided p = 0.12916
     * (R: wilcox.test(c(1,2,2,3), c(2,3,3,4), correct = FALSE)). */
    const double x[] = {1, 2, 2, 3}, y[] = {2, 3, 3, 4};
    double u, z, p;
    assert_int_equal(aa_mann_whitney(x, 4, y, 4, &u, &z, &p), AA_OK);
    assert_true(u == 3);
    assert_true(fabs(z + 1.5174424467) < 1e-9);
    assert_true(fabs(p - 0.129155014) < 1e-8);
    /* all equal: no evidence either way */
    const double c[] = {5, 5, 5};
    assert_int_equal(aa_mann_whitney(c, 3, c, 3, &u, &z, &p), AA_OK);
    assert_true(u == 4.5 && z == 0 && p == 1);
    assert_int_equal(aa_mann_whitney(c, 0, c, 3, &u, &z, &p), AA_EINVAL);
}

static void test_noisy_text(void **state)
{
    (void)state;
    char buf[64];
    aa_noisy_text(0, buf, sizeof buf);
    assert_string_equal(buf, "");
    aa_noisy_text(AA_NOISY_CI | AA_NOISY_BUSY, buf, sizeof buf);
    assert_string_equal(buf, "ci+busy");
    aa_noisy_text(AA_NOISY_OUTLIERS | AA_NOISY_STEAL | AA_NOISY_PREEMPTED, buf, sizeof buf);
    assert_string_equal(buf, "outliers+steal+preempted");
}

static char dir[] = "/tmp/aabench-timing-XXXXXX";

/* A timing of the given render times under a 2% target, by precision,
 * on a quiet machine: one thread that got all its wall time in CPU. */
static void synthetic(aa_timing *t, const double *x, int n)
{
    memset(t, 0, sizeof *t);
    t->n = n, t->threads = 1, t->target_ci = 0.02, t->cpu_share = 1.0;
    memcpy(t->wall, x, (size_t)n * sizeof *x);
    memcpy(t->cpu, x, (size_t)n * sizeof *x);
    aa_time_stats_compute(x, (size_t)n, &t->stats);
    t->ci_rel = isfinite(t->stats.ci_lo) ? (t->stats.ci_hi - t->stats.ci_lo) / 2 / t->stats.median
                                         : NAN;
    t->target_met = t->ci_rel <= t->target_ci;
}

/* Noisy by effect, not by count. */
static void test_outliers_by_effect(void **state)
{
    (void)state;
    aa_timing *t = malloc(sizeof *t);
    assert_non_null(t);
    /* 1.000, 1.001, ..., 1.009 and two outliers, 5 and 6: one render in six.
     * Median (1.005 + 1.006) / 2 = 1.0055; the interval of 12 is
     * [x(3), x(10)] = [1.002, 1.009], half-width 0.0035 / 1.0055 = 0.35%,
     * within 2%.  The absolute deviations' median is (0.0025 + 0.0035) / 2
     * = 0.003, 3 MADs 3 x 1.4826 x 0.003 = 0.0133: only 5 and 6 lie beyond.
     * Without them the median is 1.0045, 0.1% from 1.0055: not noisy. */
    const double one_in_six[] = {1.003, 5.0,   1.000, 1.009, 1.001, 1.007,
                                 1.002, 1.008, 6.0,   1.004, 1.005, 1.006};
    synthetic(t, one_in_six, 12);
    assert_int_equal(t->stats.outliers, 2);
    assert_true(fabs(aa_time_stats_outlier_shift(one_in_six, 12) - 0.001 / 1.0045) < 1e-12);
    aa_timing_judge(t, 0.04, 2);
    if (t->noisy) {
        char why[64];
        aa_noisy_text(t->noisy, why, sizeof why);
        fail_msg("one outlier in six that leaves the median marked noisy: %s", why);
    }
    /* 1.00, 1.02, ..., 1.14 and four outliers 5, 6, 7, 8: the median of all
     * (x(6) + x(7)) / 2 = (1.10 + 1.12) / 2 = 1.11; deviations' median
     * (0.07 + 0.09) / 2 = 0.08, 3 MADs 0.356, so the four are outliers;
     * without them the median is (1.06 + 1.08) / 2 = 1.07, 0.04 / 1.07 =
     * 3.7% away: beyond the 2% target */
    const double moving[] = {1.00, 5.0, 1.02, 1.04, 6.0, 1.06, 1.08, 7.0, 1.10, 1.12, 8.0, 1.14};
    synthetic(t, moving, 12);
    assert_int_equal(t->stats.outliers, 4);
    assert_true(fabs(aa_time_stats_outlier_shift(moving, 12) - 0.04 / 1.07) < 1e-12);
    aa_timing_judge(t, 0.04, 2);
    assert_true(t->noisy & AA_NOISY_OUTLIERS);
    /* none: no shift */
    const double calm[] = {1, 2, 3, 4, 5, 6};
    assert_true(aa_time_stats_outlier_shift(calm, 6) == 0);
    free(t);
}

/* The machine's accounting from made counters: 100 ticks a second, 2
 * cores. */
static void test_machine_use(void **state)
{
    (void)state;
    aa_machine_sample a = {.wall = 10, .load = 2.2, .own = 3, .have_stat = 1,
                           .busy = 1000, .steal = 0, .total = 4000};
    aa_machine_sample b = a;
    double others, steal, allowance;
    /* one second, 1395 busy ticks (13.95 cores' worth) and none of it ours:
     * clamped to the 2 cores there are; the ticks' error 2 x 2 / 100 / 1 =
     * 0.04 cores */
    b.wall = 11, b.busy = a.busy + 1395, b.total = a.total + 1395;
    aa_machine_use(&a, &b, 100, 2, 1, &others, &steal, &allowance);
    assert_true(others == 2 && steal == 0 && fabs(allowance - 0.04) < 1e-12);
    aa_timing *t = malloc(sizeof *t);
    assert_non_null(t);
    const double x[] = {1, 1, 1, 1, 1, 1};
    synthetic(t, x, 6);
    t->others_cores = others;
    aa_timing_judge(t, allowance, 2);
    assert_int_equal(t->noisy, AA_NOISY_BUSY);
    /* 150 busy ticks, 1.5 s of them ours and our children's (an external
     * renderer's program): nobody else */
    b.busy = a.busy + 150, b.own = a.own + 1.5;
    aa_machine_use(&a, &b, 100, 2, 1, &others, &steal, &allowance);
    assert_true(others == 0);
    /* more CPU of ours than the ticks show (their rounding): 0, not less */
    b.busy = a.busy + 100, b.own = a.own + 1.9;
    aa_machine_use(&a, &b, 100, 2, 1, &others, &steal, &allowance);
    assert_true(others == 0);
    /* 10 ms: the ticks' error is 4 cores, too much; the lower load
     * average, 3.0, less our 2 threads: 1 core, beyond the load's 0.5 */
    b = a;
    a.load = 3.5, b.load = 3.0, b.wall = a.wall + 0.01, b.busy = a.busy + 7;
    aa_machine_use(&a, &b, 100, 2, 2, &others, &steal, &allowance);
    assert_true(others == 1 && allowance == AA_TIMING_BUSY_LOAD);
    t->others_cores = others;
    aa_timing_judge(t, allowance, 2);
    assert_int_equal(t->noisy, AA_NOISY_BUSY);
    /* the same window with the load of our own threads alone: quiet */
    a.load = b.load = 2.2;
    aa_machine_use(&a, &b, 100, 2, 2, &others, &steal, &allowance);
    assert_true(fabs(others - 0.2) < 1e-12);
    t->others_cores = others;
    aa_timing_judge(t, allowance, 2);
    assert_int_equal(t->noisy, 0);
    /* a load of 30: still at most the 2 cores */
    a.load = b.load = 30;
    aa_machine_use(&a, &b, 100, 2, 2, &others, &steal, &allowance);
    assert_true(others == 2);
    free(t);
}

/* Fewer renders than an interval needs: said so.  Five renders cover at
 * most 1 - 2 / 2^5 = 93.75% of the median, six 1 - 2 / 2^6 = 96.9%. */
static void test_ci_text(void **state)
{
    (void)state;
    aa_timing *t = calloc(1, sizeof *t);
    assert_non_null(t);
    char buf[64];
    const double x[] = {1.0, 1.1, 0.9, 1.05, 0.95, 1.0};
    synthetic(t, x, 5);
    aa_timing_ci_text(t, buf, sizeof buf);
    assert_string_equal(buf, "CI needs 6 renders");
    /* six: [x(1), x(6)] = [0.9, 1.1] about the median 1.0, +-10% */
    synthetic(t, x, 6);
    aa_timing_ci_text(t, buf, sizeof buf);
    assert_string_equal(buf, "+-10.0%");
    free(t);
}

/* Methods in one table that ran with different effective parallelism. */
static void test_parallelism(void **state)
{
    (void)state;
    aa_row *r = calloc(4, sizeof *r);
    assert_non_null(r);
    /* a plug-in's one thread all CPU (1.0), a 2-thread method waiting at its
     * barriers (0.4), one at 0.9, and a failed case of 0.1 that is not
     * counted: 1.0 / 0.4 = 2.5 apart */
    const double share[] = {1.0, 0.4, 0.9, 0.1};
    for (int k = 0; k < 4; k++) {
        r[k].ok = k < 3, r[k].threads = k == 1 ? 2 : 1;
        r[k].timing.n = 10, r[k].timing.cpu_share = share[k];
    }
    size_t lo, hi;
    double ratio = aa_rows_parallelism(r, 4, &lo, &hi);
    assert_true(lo == 1 && hi == 0 && fabs(ratio - 2.5) < 1e-12);
    assert_true(ratio > AA_PARALLELISM_FACTOR);
    /* 1.0 and 0.9 alone: 1.11 apart, fair */
    r[1].timing.cpu_share = NAN; /* an old file's row, without the column */
    ratio = aa_rows_parallelism(r, 4, &lo, &hi);
    assert_true(lo == 2 && hi == 0 && fabs(ratio - 1.0 / 0.9) < 1e-12);
    assert_false(ratio > AA_PARALLELISM_FACTOR);
    /* one row: nothing to compare */
    assert_true(aa_rows_parallelism(r, 1, &lo, &hi) == 1.0);
    free(r);
}

/* A warning printed after what precedes it on standard output, through a
 * pipe (where standard output is buffered): a fixed count of 6 renders
 * judged against a 0.01% target is noisy unless all six take the same
 * time to 0.02%. */
static void test_warning_order(void **state)
{
    (void)state;
    if (!getenv("AABENCH"))
        skip();
    static char out[1 << 16];
    char png[160], run[160];
    snprintf(png, sizeof png, "%s/order.png", dir);
    snprintf(run, sizeof run, "%s/order-run", dir);
    const char *render[] = {"render", "-p", "crow", "-m", "point", "-s", "96x96",
                            "--threads", "1", "--reps", "6", "--target-ci", "0.01",
                            "-o", png, NULL};
    assert_int_equal(support_aabench(render, out, sizeof out), 0);
    const char *wrote = strstr(out, "wrote "), *warning = strstr(out, "warning: the timing");
    assert_non_null(wrote);
    if (warning && warning < wrote)
        fail_msg("the warning came before the line it follows:\n%s", out);
    const char *runs[] = {"run", "-p", "crow", "-m", "point", "-m", "area", "-s", "48x48",
                          "-f", "box", "--threads", "1", "--reps", "6", "--target-ci", "0.01",
                          "--no-images", "--no-plots", "--no-cache", "--out", run, NULL};
    int st = support_aabench(runs, out, sizeof out);
    assert_true(st == 0);
    /* the table's two rows, each whole on its line, then the warnings */
    const char *point = strstr(out, "\npoint "), *area = strstr(out, "\narea ");
    warning = strstr(out, "aabench run: warning: ");
    assert_true(point && area);
    if (warning && (warning < point || warning < area || warning[-1] != '\n'))
        fail_msg("the warning came inside the table:\n%s", out);
    if (!warning)
        print_message("(no timing was noisy: the order was not put to the test)\n");
}

/* ---- the repetition rule: counts, never times ---- */

static int calls;
static int count_call(void *ctx)
{
    (void)ctx;
    calls++;
    return AA_OK;
}
static int fail_third(void *ctx)
{
    (void)ctx;
    return ++calls == 3 ? AA_EFAIL : AA_OK;
}

/* A render whose work is done by a child process, as an external
 * renderer's: the child spins a fixed count of steps, then writes its own
 * CPU time (its process clock) into a pipe before exiting; the render
 * waits for it. */
static double child_cpu;
static int child_render(void *ctx)
{
    (void)ctx;
    int fds[2];
    if (pipe(fds))
        return AA_EFAIL;
    pid_t pid = fork();
    if (pid < 0)
        return AA_EFAIL;
    if (pid == 0) {
        volatile double x = 0;
        for (long k = 0; k < 20000000; k++)
            x += 1e-9 * (double)k;
        struct timespec t;
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        double cpu = (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
        _exit(write(fds[1], &cpu, sizeof cpu) == (ssize_t)sizeof cpu ? 0 : 1);
    }
    close(fds[1]);
    ssize_t got = read(fds[0], &child_cpu, sizeof child_cpu);
    close(fds[0]);
    int ws;
    while (waitpid(pid, &ws, 0) < 0)
        ;
    return got == (ssize_t)sizeof child_cpu && WIFEXITED(ws) && !WEXITSTATUS(ws) ? AA_OK
                                                                                 : AA_EFAIL;
}

/* The child's CPU is the render's (RUSAGE_CHILDREN), not nothing: at least
 * what the child's own clock read before it wrote, less 1% for the
 * microseconds getrusage rounds to. */
static void test_child_cpu(void **state)
{
    (void)state;
    aa_timing *t = malloc(sizeof *t);
    assert_non_null(t);
    aa_timed_fn fn = child_render;
    void *ctx = NULL;
    int one = 1;
    aa_timing_plan plan = {.reps = 2};
    assert_int_equal(aa_timing_measure(&plan, 1, &fn, &ctx, &one, t), AA_OK);
    assert_true(child_cpu > 0);
    if (!(t->cpu[1] >= 0.99 * child_cpu - 1e-5))
        fail_msg("the render's CPU time %g s leaves out its child's %g s", t->cpu[1], child_cpu);
    free(t);
}

static void test_measure_counts(void **state)
{
    (void)state;
    aa_timing *t = malloc(2 * sizeof *t);
    assert_non_null(t);
    aa_timed_fn fn[2] = {count_call, count_call};
    void *ctx[2] = {NULL, NULL};
    int threads[2] = {1, 2};
    /* a fixed count: one warm-up, then exactly reps */
    aa_timing_plan fixed = {.reps = 7};
    calls = 0;
    assert_int_equal(aa_timing_measure(&fixed, 1, fn, ctx, threads, t), AA_OK);
    assert_int_equal(calls, 8);
    assert_true(t->n == 7 && t->fixed && t->stats.n == 7);
    assert_true(t->stats.min <= t->stats.median && t->stats.median <= t->stats.max);
    assert_true(t->stats.ci_lo <= t->stats.median && t->stats.median <= t->stats.ci_hi);
    assert_true(t->threads == 1 && t->elapsed >= 0);
    /* by precision, two functions taking turns: each warmed up, at least
     * the minimum, at most the maximum */
    aa_timing_plan adaptive = {.target_ci = 0.5, .budget = 0.01};
    calls = 0;
    assert_int_equal(aa_timing_measure(&adaptive, 2, fn, ctx, threads, t), AA_OK);
    for (int k = 0; k < 2; k++) {
        assert_true(t[k].n >= AA_TIMING_MIN_REPS && t[k].n <= AA_TIMING_MAX_REPS);
        assert_true(!t[k].fixed && t[k].threads == threads[k]);
        assert_true(t[k].target_ci == 0.5);
        /* noisy for the target exactly when it was not met */
        assert_int_equal(!!(t[k].noisy & AA_NOISY_CI), !t[k].target_met);
    }
    assert_int_equal(calls, 2 + t[0].n + t[1].n);
    /* defaults */
    aa_timing_plan none = {0};
    calls = 0;
    assert_int_equal(aa_timing_measure(&none, 1, fn, ctx, threads, t), AA_OK);
    assert_true(t->target_ci == AA_TIMING_TARGET && t->budget == AA_TIMING_BUDGET);
    /* a failure stops and is returned */
    fn[0] = fail_third;
    calls = 0;
    assert_int_equal(aa_timing_measure(&fixed, 1, fn, ctx, threads, t), AA_EFAIL);
    assert_int_equal(calls, 3);
    /* out of range */
    aa_timing_plan bad = {.reps = AA_TIMING_MAX_REPS + 1};
    assert_int_equal(aa_timing_measure(&bad, 1, fn, ctx, threads, t), AA_EINVAL);
    free(t);
}

/* A method whose init sleeps 50 ms and whose render fills grey: the
 * init's time is measured once, on its own, and at least the sleep
 * (POSIX: nanosleep returns no earlier than asked, barring a signal,
 * retried here). */
static int slow_inits;

static int slow_init(void *state, const double *p, const aa_job *job)
{
    (void)state, (void)p, (void)job;
    struct timespec left = {0, 50000000L};
    while (nanosleep(&left, &left))
        ;
    slow_inits++;
    return AA_OK;
}

static int grey_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    (void)state, (void)p;
    for (int j = 0; j < job->h; j++)
        for (int i = 0; i < job->w; i++)
            for (int c = 0; c < 3; c++)
                aa_pixel(out, i, j)[c] = 0.5;
    memset(counters, 0, sizeof *counters);
    return AA_OK;
}

static const aa_param no_params[] = {{0}};
static const aa_method_type slowinit = {
    .info = {"slowinit", "test: an init of 50 ms", no_params},
    .init = slow_init,
    .render = grey_render,
};

static void test_init_timed(void **state)
{
    (void)state;
    static const aa_method_type *const types[] = {&slowinit, NULL};
    assert_int_equal(aa_method_register(types, "test_timing"), AA_OK);
    aa_scene *scene = NULL;
    aa_spec pattern, method;
    aa_filter f;
    aa_job job;
    aa_image img;
    aa_counters c;
    aa_timing *t = malloc(sizeof *t);
    assert_non_null(t);
    aa_filter_default(&f);
    assert_int_equal(aa_pattern_parse("crow", &pattern), AA_OK);
    assert_int_equal(aa_pattern_scene_at(&pattern, 8, 8, &scene), AA_OK);
    assert_int_equal(aa_job_init(&job, scene, 8, 8, 0, 0, 0, &f, 1, 1), AA_OK);
    assert_int_equal(aa_image_alloc(&img, 8, 8, 3), AA_OK);
    assert_int_equal(aa_method_parse("slowinit", &f, &method), AA_OK);
    aa_timing_plan plan = {.reps = 3};
    slow_inits = 0;
    assert_int_equal(aa_method_time(&method, &job, &plan, &img, &c, t), AA_OK);
    assert_int_equal(slow_inits, 1); /* once, before the warm-up and 3 renders */
    assert_int_equal(t->n, 3);
    if (!(t->init_seconds >= 0.05))
        fail_msg("the init's time %g s is less than its 50 ms sleep", t->init_seconds);
    assert_true(isfinite(t->init_cpu) && t->init_cpu >= 0);
    /* a results file keeps it: results.csv's init_seconds read back */
    aa_row *row = calloc(1, sizeof *row), *back;
    size_t n;
    char csv[128];
    assert_non_null(row);
    snprintf(row->pattern, sizeof row->pattern, "crow");
    snprintf(row->filter, sizeof row->filter, "box");
    snprintf(row->method, sizeof row->method, "slowinit");
    row->w = row->h = 8, row->seed = 1, row->threads = 1, row->ok = 1, row->seeds = 1;
    row->timing = *t;
    row->seconds = t->stats.median, row->reps = t->n;
    snprintf(csv, sizeof csv, "%s/init.csv", dir);
    assert_int_equal(aa_rows_write_csv(csv, row, 1), AA_OK);
    assert_int_equal(aa_rows_read_csv(csv, &back, &n), AA_OK);
    assert_int_equal(n, 1);
    assert_true(fabs(back[0].timing.init_seconds - t->init_seconds) <= 1e-8 * t->init_seconds);
    assert_true(fabs(back[0].timing.init_cpu - t->init_cpu) <= 1e-8 * t->init_cpu + 1e-15);
    free(back);
    free(row);
    aa_image_free(&img);
    aa_job_free(&job);
    aa_scene_free(scene);
    free(t);
}

/* ---- results files, comparisons and the diff command ---- */

static void fill_row(aa_row *r, const char *method, double rmse, double scale)
{
    memset(r, 0, sizeof *r);
    snprintf(r->pattern, sizeof r->pattern, "crow");
    snprintf(r->filter, sizeof r->filter, "box");
    snprintf(r->method, sizeof r->method, "%s", method);
    snprintf(r->canonical, sizeof r->canonical, "%s", method);
    r->w = 16, r->h = 8, r->seed = 1, r->threads = 1, r->ok = 1;
    r->m.rmse = rmse, r->m.max_err = 2 * rmse;
    aa_timing *t = &r->timing;
    t->n = 10, t->threads = 1, t->target_ci = 0.02;
    for (int k = 0; k < 10; k++)
        t->wall[k] = t->cpu[k] = scale * (1.0 + 0.01 * k); /* 10 distinct times */
    aa_time_stats_compute(t->wall, 10, &t->stats);
    t->ci_rel = (t->stats.ci_hi - t->stats.ci_lo) / 2 / t->stats.median;
    r->seconds = t->stats.median, r->reps = 10, r->seeds = 1;
}

static char *slurp(const char *path)
{
    static char buf[1 << 16];
    return support_read_file(path, buf, sizeof buf, NULL);
}

static void test_results_round_trip(void **state)
{
    (void)state;
    aa_row *rows = calloc(2, sizeof *rows), *back;
    size_t n;
    char csv[128], json[128];
    assert_non_null(rows);
    fill_row(&rows[0], "point", 0.25, 1e-3);
    rows[0].timing.noisy = AA_NOISY_BUSY | AA_NOISY_OUTLIERS;
    fill_row(&rows[1], "jitter:spp=4", 0.125, 2e-3);
    rows[1].seeds = 3, rows[1].rmse_mean = 0.13, rows[1].rmse_ci_lo = 0.12;
    rows[1].rmse_ci_hi = 0.14;
    snprintf(csv, sizeof csv, "%s/results.csv", dir);
    snprintf(json, sizeof json, "%s/results.json", dir);
    assert_int_equal(aa_rows_write_csv(csv, rows, 2), AA_OK);
    assert_int_equal(aa_rows_read_csv(csv, &back, &n), AA_OK);
    assert_int_equal(n, 2);
    for (size_t k = 0; k < 2; k++) {
        assert_int_equal(back[k].timing.n, 10);
        for (int q = 0; q < 10; q++)
            assert_true(fabs(back[k].timing.wall[q] - rows[k].timing.wall[q]) <=
                        1e-8 * rows[k].timing.wall[q]);
        assert_true(back[k].timing.stats.ci_lo == back[k].timing.wall[1]); /* x(2) of 10 */
    }
    assert_int_equal(back[0].timing.noisy, AA_NOISY_BUSY | AA_NOISY_OUTLIERS);
    assert_int_equal(back[1].timing.noisy, 0);
    assert_true(back[1].seeds == 3 && back[1].rmse_mean == 0.13 && back[1].rmse_ci_hi == 0.14);
    free(back);
    /* results.json: an object, the context first, then the rows with their
     * times; the context names the command line given */
    aa_context ctx;
    const char *argv[] = {"aabench", "run", "--seeds", "3"};
    assert_int_equal(aa_context_collect(&ctx, 4, argv, 2), AA_OK);
    assert_int_equal(aa_results_write_json(json, &ctx, rows, 2), AA_OK);
    const char *t = slurp(json);
    assert_true(!strncmp(t, "{\n  \"context\": {", 16));
    const char *keys[] = {"\"commit\": ", "\"dirty\": ", "\"compiler\": ", "\"cflags\": ",
                          "\"cpu\": ", "\"cores\": ", "\"threads\": 2", "\"os\": ",
                          "\"kernel\": ", "\"gsl\": ", "\"openimageio\": ", "\"freetype\": ",
                          "\"cairo\": ", "\"stb\": ", "\"date\": ", "\"load\": [",
                          "\"command\": [\"aabench\", \"run\", \"--seeds\", \"3\"]",
                          "\"results\": [", "\"times\":[0.001,0.00101,",
                          "\"noisy\":true,\"noise\":\"outliers+busy\"", "\"seeds\":3"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
        if (!strstr(t, keys[k]))
            fail_msg("results.json lacks %s", keys[k]);
    /* the commit is the build's; the checkout the test lives in, as git
     * itself names it here, is recorded beside it ("" outside one) */
    assert_string_equal(ctx.commit_from, "build");
    char exe[4096], cmd[4200], head[128] = "";
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    assert_true(len > 0);
    exe[len] = '\0';
    *strrchr(exe, '/') = '\0';
    snprintf(cmd, sizeof cmd, "git -C '%s' rev-parse HEAD 2>/dev/null", exe);
    FILE *git = popen(cmd, "r");
    assert_non_null(git);
    if (!fgets(head, sizeof head, git))
        head[0] = '\0';
    int git_status = pclose(git);
    head[strcspn(head, "\n")] = '\0';
    if (git_status == 0 && head[0]) {
        assert_string_equal(ctx.checkout, head);
        assert_true(ctx.checkout_dirty == 0 || ctx.checkout_dirty == 1);
        snprintf(cmd, sizeof cmd, "\"checkout\": \"%s\"", head);
        assert_non_null(strstr(t, cmd));
    } else {
        assert_string_equal(ctx.checkout, "");
        assert_non_null(strstr(t, "\"checkout\": null"));
    }
    free(rows);
}

/* A results file of the columns written before the timing's (the
 * committed baseline's): read, with no times and one seed. */
static void test_old_results(void **state)
{
    (void)state;
    char csv[128];
    snprintf(csv, sizeof csv, "%s/old.csv", dir);
    FILE *f = fopen(csv, "w");
    assert_non_null(f);
    fputs("pattern,size,filter,method,canonical,spp,rmse,mae,max_err,render_seconds,threads,reps,"
          "seed,time,vx,vy,ok,note\n"
          "crow,128x128,box,point,point,1,0.257,0.1,0.65,0.00013,2,3,1,0,0,0,1,\n",
          f);
    fclose(f);
    aa_row *rows;
    size_t n;
    assert_int_equal(aa_rows_read_csv(csv, &rows, &n), AA_OK);
    assert_int_equal(n, 1);
    assert_true(rows[0].timing.n == 0 && rows[0].seeds == 1 && rows[0].seconds == 0.00013);
    assert_true(rows[0].timing.noisy == 0);
    /* no init columns: not measured, not 0 */
    assert_true(isnan(rows[0].timing.init_seconds) && isnan(rows[0].timing.init_cpu));
    /* nor the reference's bound and count scanned */
    assert_true(isnan(rows[0].ref_bound) && isnan(rows[0].ref_scanned));
    free(rows);
}

static void test_case_compare(void **state)
{
    (void)state;
    aa_row *r = calloc(2, sizeof *r);
    aa_case_change c;
    assert_non_null(r);
    /* errors: worse beyond (1 + tol) + 1e-12 */
    fill_row(&r[0], "point", 1.0, 1e-3);
    fill_row(&r[1], "point", 1.0011, 1e-3);
    assert_int_equal(aa_case_compare(&r[0], &r[1], 1e-3, &c), AA_OK);
    assert_true(c.error_worse && fabs(c.rmse_change - 0.0011) < 1e-12);
    r[1].m.rmse = 1.0009, r[1].m.max_err = 2.0018;
    assert_int_equal(aa_case_compare(&r[0], &r[1], 1e-3, &c), AA_OK);
    assert_false(c.error_worse);
    /* times: R's example as repetition times, now = x, before = y: U = 35,
     * two-sided p = 2 x 0.1103, not significant; ratio of the medians */
    const double x[] = {0.80, 0.83, 1.89, 1.04, 1.45, 1.38, 1.91, 1.64, 0.73, 1.46};
    const double y[] = {1.15, 0.88, 0.90, 0.74, 1.21};
    r[1].timing.n = 10, r[0].timing.n = 5;
    memcpy(r[1].timing.wall, x, sizeof x);
    memcpy(r[0].timing.wall, y, sizeof y);
    r[1].seconds = 1.415, r[0].seconds = 0.90; /* the medians */
    assert_int_equal(aa_case_compare(&r[0], &r[1], 1e-3, &c), AA_OK);
    assert_true(c.tested && c.u == 35 && fabs(c.p / 2 - 0.1103) < 5e-5 && !c.significant);
    assert_true(fabs(c.time_ratio - 1.415 / 0.90) < 1e-12);
    /* refused now */
    r[1].ok = 0;
    assert_int_equal(aa_case_compare(&r[0], &r[1], 1e-3, &c), AA_OK);
    assert_true(c.refused && !c.tested);
    free(r);
}

/* The diff command's exit status: 0, 1 on an error regression, 1 with
 * --fail-slower on a significant slow-down beyond it, 2 on bad input. */
static void test_diff_command(void **state)
{
    (void)state;
    const char *exe = getenv("AABENCH");
    if (!exe)
        skip();
    aa_row *r = calloc(2, sizeof *r);
    assert_non_null(r);
    char a[128], b[128], c[128], cmd[1024];
    snprintf(a, sizeof a, "%s/a.csv", dir);
    snprintf(b, sizeof b, "%s/b.csv", dir);
    snprintf(c, sizeof c, "%s/c.csv", dir);
    fill_row(&r[0], "point", 0.25, 1e-3);
    fill_row(&r[1], "area", 1e-16, 2e-3);
    assert_int_equal(aa_rows_write_csv(a, r, 2), AA_OK);
    /* b: every time doubled (all 10 above all 10: U = 100, p = 1.8e-4) */
    fill_row(&r[0], "point", 0.25, 2e-3);
    fill_row(&r[1], "area", 1e-16, 4e-3);
    assert_int_equal(aa_rows_write_csv(b, r, 2), AA_OK);
    /* c: the error of point worse */
    fill_row(&r[0], "point", 0.26, 1e-3);
    fill_row(&r[1], "area", 1e-16, 2e-3);
    assert_int_equal(aa_rows_write_csv(c, r, 2), AA_OK);
    struct {
        const char *args;
        int code;
    } cases[] = {{"diff %s %s", 0},
                 {"diff %s %s --fail-slower 50", 1},
                 {"diff %s %s --fail-slower 150", 0},
                 {"diff %s %s", 1},
                 {"diff %s", 2}};
    const char *second[] = {b, b, b, c, ""};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        char args[600];
        snprintf(args, sizeof args, cases[k].args, a, second[k]);
        snprintf(cmd, sizeof cmd, "'%s' %s > %s/out 2>&1", exe, args, dir);
        int st = system(cmd);
        if (!WIFEXITED(st) || WEXITSTATUS(st) != cases[k].code) {
            char out[256];
            snprintf(out, sizeof out, "%s/out", dir);
            fail_msg("aabench %s: exit %d, expected %d: %s", args, WEXITSTATUS(st),
                     cases[k].code, slurp(out));
        }
    }
    /* the slow-down is named as significant */
    snprintf(cmd, sizeof cmd, "'%s' diff %s %s > %s/out 2>&1", exe, a, b, dir);
    assert_int_equal(system(cmd), 0);
    char out[256];
    snprintf(out, sizeof out, "%s/out", dir);
    const char *text = slurp(out);
    assert_non_null(strstr(text, "+100.0%"));
    assert_non_null(strstr(text, "2 significantly slower"));
    free(r);
}

static int setup(void **state)
{
    *state = dir;
    return mkdtemp(dir) ? 0 : -1;
}

SUPPORT_MAIN(setup, support_teardown_dir,
             cmocka_unit_test(test_median_ci_table),
             cmocka_unit_test(test_time_stats),
             cmocka_unit_test(test_mean_ci),
             cmocka_unit_test(test_mann_whitney_r_example),
             cmocka_unit_test(test_mann_whitney_ties),
             cmocka_unit_test(test_noisy_text),
             cmocka_unit_test(test_outliers_by_effect),
             cmocka_unit_test(test_machine_use),
             cmocka_unit_test(test_ci_text),
             cmocka_unit_test(test_parallelism),
             cmocka_unit_test(test_warning_order),
             cmocka_unit_test(test_child_cpu),
             cmocka_unit_test(test_measure_counts),
             cmocka_unit_test(test_init_timed),
             cmocka_unit_test(test_results_round_trip),
             cmocka_unit_test(test_old_results),
             cmocka_unit_test(test_case_compare),
             cmocka_unit_test(test_diff_command))
