/*
 * plugin_faulty.c: methods that misbehave, for the fault tests
 * (tests/test_faults.c): a method whose image holds NaN, one whose values
 * leave [0, 1], one that crashes and one that never returns.  The last two
 * first leave a file in $TMPDIR (as a method that starts a renderer leaves
 * its files when it is killed): the run must remove it (isolate.c).  Built
 * like any plug-in, against aabench.h alone.
 */
#include "aabench.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const aa_param no_params[] = {{0}};

/* Grey 1/2 everywhere, then the fault at pixel (1, 2) channel 1 if the
 * image is large enough. */
static void fill(const aa_job *job, aa_image *out, double fault)
{
    for (int j = 0; j < job->h; j++)
        for (int i = 0; i < job->w; i++) {
            double *px = aa_pixel(out, i, j);
            px[0] = px[1] = px[2] = 0.5;
        }
    if (job->w > 1 && job->h > 2) {
        aa_pixel(out, 1, 2)[1] = fault;
        aa_pixel(out, job->w - 1, job->h - 1)[2] = fault;
    }
}

static int nan_render(void *state, const double *p, const aa_job *job, aa_image *out,
                      aa_counters *counters)
{
    (void)state, (void)p;
    fill(job, out, NAN);
    memset(counters, 0, sizeof *counters);
    return AA_OK;
}

static int over_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    (void)state, (void)p;
    fill(job, out, 1.5);
    memset(counters, 0, sizeof *counters);
    return AA_OK;
}

/* A file in $TMPDIR (or /tmp), named for the process, left there. */
static void leave_file(void)
{
    const char *tmp = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/aabench-faulty-%ld", tmp && *tmp ? tmp : "/tmp",
             (long)getpid());
    FILE *f = fopen(path, "w");
    if (f) {
        fputs("left by a method that was ended\n", f);
        fclose(f);
    }
}

static int crash_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    leave_file();
    raise(SIGSEGV);
    return AA_OK;
}

static int hang_render(void *state, const double *p, const aa_job *job, aa_image *out,
                       aa_counters *counters)
{
    (void)state, (void)p, (void)job, (void)out, (void)counters;
    leave_file();
    for (;;)
        pause();
    return AA_OK;
}

static const aa_method_type nanout = {
    .info = {"nanout", "fault test: NaN at two pixels", no_params}, .render = nan_render};
static const aa_method_type over = {
    .info = {"over", "fault test: 1.5 at two pixels", no_params}, .render = over_render};
static const aa_method_type crash = {
    .info = {"crash", "fault test: a segmentation fault", no_params}, .render = crash_render};
static const aa_method_type hang = {
    .info = {"hang", "fault test: never returns", no_params}, .render = hang_render};

const int aa_plugin_abi = AA_PLUGIN_ABI;
const aa_method_type *const aa_plugin_methods[] = {&nanout, &over, &crash, &hang, NULL};
