/*
 * plugin_failing.c: methods that fail in the ways plugin_faulty.c does
 * not, for tests/test_run_faults.c: one whose render returns an error, one
 * that aborts (SIGABRT) and one that ends the process (exit status 3); and
 * ones that break the contract otherwise: a status no aa_status has (42),
 * a negative count of samples, more expensive pixels than the image has;
 * and ones that harm the process they run in: one that calls exit(0),
 * one that leaves the rounding mode upward, one that writes 16 values past
 * the end of its image.
 * Built like any plug-in, against aabench.h alone.
 */
#include "aabench.h"

#include <fenv.h>
#include <stdlib.h>

static const aa_param no_params[] = {{0}};

static int fails_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    return aa_fail(AA_EFAIL, "fault test: this render fails on purpose");
}

static int aborts_render(void *state, const double *p, const aa_job *job, aa_image *out,
                         aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    abort();
}

static int quits_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    exit(3);
}

static const aa_method_type fails = {
    .info = {"fails", "fault test: render returns an error", no_params}, .render = fails_render};
static const aa_method_type aborts = {
    .info = {"aborts", "fault test: render aborts", no_params}, .render = aborts_render};
static const aa_method_type quits = {
    .info = {"quits", "fault test: render ends the process", no_params}, .render = quits_render};

/* Grey 1/2, with the counters of `bad` (0, 1, 2: see below). */
static void grey(const aa_job *job, aa_image *out, aa_counters *counters, int bad)
{
    for (int k = 0; k < job->w * job->h * 3; k++)
        out->v[k] = 0.5;
    counters->samples = bad == 1 ? (uint64_t)-5 : (uint64_t)job->w * job->h;
    counters->expensive_pixels = bad == 2 ? (uint64_t)job->w * job->h + 1 : 0;
}

static int odd_render(void *state, const double *p, const aa_job *job, aa_image *out,
                      aa_counters *counters)
{
    (void)state, (void)p;
    grey(job, out, counters, 0);
    return 42;
}

static int negative_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    (void)state, (void)p;
    grey(job, out, counters, 1);
    return AA_OK;
}

static int over_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    (void)state, (void)p;
    grey(job, out, counters, 2);
    return AA_OK;
}

static const aa_method_type odd = {
    .info = {"oddstatus", "fault test: render returns the status 42", no_params},
    .render = odd_render};
static const aa_method_type negative = {
    .info = {"negcount", "fault test: render counts -5 samples", no_params},
    .render = negative_render};
static const aa_method_type over = {
    .info = {"overcount", "fault test: render counts W x H + 1 expensive pixels", no_params},
    .render = over_render};

static int callsexit_render(void *state, const double *p, const aa_job *job, aa_image *out,
                            aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    exit(0);
}

static int rounding_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    (void)state, (void)p;
    grey(job, out, counters, 0);
    fesetround(FE_UPWARD);
    return AA_OK;
}

static int overrun_render(void *state, const double *p, const aa_job *job, aa_image *out,
                          aa_counters *counters)
{
    (void)state, (void)p;
    grey(job, out, counters, 0);
    volatile double *v = out->v;
    for (int k = 0; k < 16; k++)
        v[job->w * job->h * 3 + k] = 0.25;
    return AA_OK;
}

static const aa_method_type callsexit = {
    .info = {"callsexit", "fault test: render calls exit(0)", no_params},
    .render = callsexit_render};
static const aa_method_type rounding = {
    .info = {"rounding", "fault test: render leaves the rounding mode upward", no_params},
    .render = rounding_render};
static const aa_method_type overrun = {
    .info = {"overrun", "fault test: render writes 16 values past its image", no_params},
    .render = overrun_render};

const int aa_plugin_abi = AA_PLUGIN_ABI;
const aa_method_type *const aa_plugin_methods[] = {&fails, &aborts,   &quits, &odd,
                                                   &negative, &over, &callsexit, &rounding,
                                                   &overrun,  NULL};
