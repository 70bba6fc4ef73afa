/*
 * plugin_failing.c: methods that fail in the ways plugin_faulty.c does
 * not, for tests/test_run_faults.c: one whose render returns an error, one
 * that aborts (SIGABRT) and one that ends the process (exit status 3).
 * Built like any plug-in, against aabench.h alone.
 */
#include "aabench.h"

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

const int aa_plugin_abi = AA_PLUGIN_ABI;
const aa_method_type *const aa_plugin_methods[] = {&fails, &aborts, &quits, NULL};
