/*
 * cmd_render.c: `aabench render`: one method on one pattern, rendered once,
 * or timed when a timing option (--reps, --budget, --target-ci, --stats)
 * asks for it.
 */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench render -p PATTERN -m METHOD [-s WxH] [-f FILTER] -o OUT [options]\n\n"
            "Renders the pattern with the method once and writes the image; times it only\n"
            "when --reps, --budget, --target-ci or --stats is given.\n\n"
            "  -p, --pattern SPEC   pattern, e.g. crow ('aabench list patterns')\n"            "                       or svg:file=scene.svg or text:ppem=12 (drawn in pixels)\n"
            "  -m, --method SPEC    method, e.g. jitter:spp=16,seq=sobol ('aabench list methods -v')\n"
            "  -s, --size WxH       image size in pixels (default: an svg file's own size times\n"
            "                       its scale)\n"
            "  -f, --filter SPEC    box (default) or another of 'aabench list filters',\n"
            "                       e.g. tent:r=1, bspline:order=3, gauss:s=1,cut=2\n"
            "  -o, --out FILE       .exr .tif .pfm (float), .png (8-bit, display encoded), .txt\n"
            "      --seed N         seed of the random streams (default 1)\n"
            "      --time T         time in frames (default 0)\n"
            "      --motion VX,VY   motion in pixels per frame (default 0,0)\n"
            "      --frame-only     temporal methods: the single frame at T, not the eye's image\n"
            "      --threads N      threads (default: all cores); the image does not depend on it\n"
            "      --target-ci PCT  time until the 95%% CI of the median is within PCT%% of it\n"
            "                       (2 when timed), after one untimed warm-up render\n"
            "      --budget S       or until S seconds of renders have passed (1 when timed);\n"
            "                       at least 5 renders either way\n"
            "      --reps N         exactly N timed renders instead (overrides both)\n"
            "      --stats FILE     time it, and write the timing (every render's time and\n"
            "                       their statistics), counters and the context (commit,\n"
            "                       machine) as JSON\n"
            "      --plugin LIB.so  load methods from a shared library (repeatable)\n"
            "      --case-timeout S an external renderer still running S seconds after the\n"
            "                       start is killed, with what it started, and the render\n"
            "                       fails (default 600)\n"
            "      --encode E       .png encoding: srgb (default), linear or gamma:G\n"
            "  -q, --quiet          print nothing on success\n\n"
            "Outputs are written only when all of them can be. Exit status: 0 done, 1 the\n"
            "method gave a value outside [0, 1] or not finite (nothing written), 2 bad input,\n"
            "3 input/output error, 130 interrupted.\n");
}

typedef struct render_args {
    const char *pattern, *method, *size, *filter, *out, *stats;
    double t, vx, vy;
    uint64_t seed;
    int threads, reps, frame_only, quiet;
    aa_encode enc;
    double target_ci, budget, timeout;
} render_args;

/* Returns -1 to go on, or the exit code to stop with. */
static int parse(int argc, char **argv, render_args *a)
{
    enum { O_SEED = 256, O_TIME, O_MOTION, O_FRAME, O_REPS, O_STATS, O_PLUGIN,
           O_ENCODE, O_TARGET, O_BUDGET, O_TIMEOUT };
    static const struct option opts[] = {
        {"pattern", required_argument, 0, 'p'}, {"method", required_argument, 0, 'm'},
        {"size", required_argument, 0, 's'},    {"filter", required_argument, 0, 'f'},
        {"out", required_argument, 0, 'o'},     {"seed", required_argument, 0, O_SEED},
        {"time", required_argument, 0, O_TIME}, {"motion", required_argument, 0, O_MOTION},
        {"frame-only", no_argument, 0, O_FRAME}, CLI_OPTION_THREADS,
        {"reps", required_argument, 0, O_REPS}, {"stats", required_argument, 0, O_STATS},
        {"plugin", required_argument, 0, O_PLUGIN}, {"encode", required_argument, 0, O_ENCODE},
        {"quiet", no_argument, 0, 'q'},         {"help", no_argument, 0, 'h'},
        {"target-ci", required_argument, 0, O_TARGET},
        {"budget", required_argument, 0, O_BUDGET},
        {"case-timeout", required_argument, 0, O_TIMEOUT},
        {0, 0, 0, 0}};
    int c, st = AA_OK;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":p:m:s:f:o:qh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, (const int[]){O_PLUGIN, 0})))
            return cli_fail("render", st);
        switch (c) {
        case 'p': a->pattern = optarg; break;
        case 'm': a->method = optarg; break;
        case 's': a->size = optarg; break;
        case 'f': a->filter = optarg; break;
        case 'o': a->out = optarg; break;
        case 'q': a->quiet = 1; break;
        case O_SEED: st = aa_parse_seed(optarg, &a->seed); break;
        case O_TIME: st = aa_parse_real("--time", optarg, -1e9, 1e9, &a->t); break;
        case O_MOTION: st = aa_parse_pair("--motion", optarg, -1e6, 1e6, &a->vx, &a->vy); break;
        case O_FRAME: a->frame_only = 1; break;
        case O_REPS: st = aa_parse_int("--reps", optarg, 1, 1000, &a->reps); break;
        case O_STATS: a->stats = optarg; break;
        case O_PLUGIN: st = aa_plugin_load(optarg); break;
        case O_ENCODE: st = aa_encode_parse(optarg, &a->enc); break;
        case O_TARGET: st = aa_parse_target(optarg, &a->target_ci); break;
        case O_BUDGET: st = aa_parse_budget(optarg, &a->budget); break;
        case O_TIMEOUT: st = aa_parse_real("--case-timeout", optarg, 0.001, 1e9, &a->timeout); break;
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, NULL, &a->threads); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("render", c, argv);
        }
        if (st)
            return cli_fail("render", st);
    }
    if (optind < argc) {
        fprintf(stderr, "aabench render: unexpected argument \"%s\"\n", aa_echo(argv[optind]));
        return 2;
    }
    if (!a->pattern || !a->method || !a->out) {
        fprintf(stderr, "aabench render: -p PATTERN, -m METHOD and -o OUT are required\n");
        usage(stderr);
        return 2;
    }
    return -1;
}

/* The statistics: the older keys first, then every render's time and its
 * statistics (as in results.json's rows), then the run's context. */
static int write_stats(const char *path, const render_args *a, const aa_spec *pattern,
                       const aa_spec *method, const aa_filter *f, int w, int h,
                       const aa_timing *timing, const aa_counters *c, int threads)
{
    char ps[4096], ms[1024], fs[256];
    double med = timing->stats.median, pixels = (double)w * h;
    aa_spec_format(pattern, ps, sizeof ps);
    aa_spec_format(method, ms, sizeof ms);
    aa_spec_format(&f->spec, fs, sizeof fs);
    char pj[2048], mj[2048], gj[2048], fj[512];
    cli_json_string(ps, pj, sizeof pj);
    cli_json_string(ms, mj, sizeof mj);
    cli_json_string(a->method, gj, sizeof gj);
    cli_json_string(fs, fj, sizeof fj);
    aa_row *row = calloc(1, sizeof *row);
    aa_context context;
    int argc;
    const char *const *argv;
    cli_command_line(&argc, &argv);
    aa_context_collect(&context, argc, argv, threads);
    char *cj = aa_context_json(&context, 2), *tj = NULL, *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    if (row) {
        row->ok = 1;
        row->seeds = 1;
        row->timing = *timing;
        tj = aa_row_timing_json(row);
    }
    int st = AA_OK;
    if (!row || !cj || !tj || !out) {
        st = aa_fail(AA_ENOMEM, "out of memory writing the stats");
    } else {
        fprintf(out,
                "{\n  \"pattern\": %s,\n  \"method\": %s,\n  \"method_given\": %s,\n"
                "  \"filter\": %s,\n  \"size\": \"%dx%d\",\n  \"seed\": %llu,\n  \"time\": %.17g,\n"
                "  \"motion\": [%.17g, %.17g],\n  \"threads\": %d,\n  \"reps\": %d,\n"
                "  \"render_seconds\": %.9g,\n  \"render_seconds_min\": %.9g,\n"
                "  \"render_seconds_max\": %.9g,\n  \"init_seconds\": %.9g,\n"
                "  \"init_cpu_seconds\": %.9g,\n  \"pixels\": %.0f,\n  \"samples\": %llu,\n"
                "  \"expensive_pixels\": %llu,\n  \"ns_per_pixel\": %.6g,\n  \"ns_per_sample\": %.6g",
                pj, mj, gj, fj, w, h, (unsigned long long)a->seed, a->t, a->vx, a->vy, threads,
                timing->n, med, timing->stats.min, timing->stats.max, timing->init_seconds,
                timing->init_cpu, pixels,
                (unsigned long long)c->samples, (unsigned long long)c->expensive_pixels,
                med * 1e9 / pixels, c->samples ? med * 1e9 / (double)c->samples : 0.0);
        /* the row's members ", \"key\": value", one per line */
        fprintf(out, "%s,\n  \"context\": %s\n}\n", tj, cj);
    }
    if (out && fclose(out) != 0 && !st)
        st = aa_fail(AA_ENOMEM, "out of memory writing the stats");
    if (!st)
        st = aa_file_write_atomic(path, text, len);
    free(text);
    free(cj);
    free(tj);
    free(row);
    return st;
}

int cmd_render(int argc, char **argv)
{
    render_args a;
    memset(&a, 0, sizeof a);
    a.seed = 1;
    a.reps = 0; /* by precision */
    a.enc.kind = AA_ENCODE_SRGB;
    int st, code = parse(argc, argv, &a);
    if (code >= 0)
        return code;
    aa_spec pattern, method;
    aa_filter f;
    int w, h;
    aa_external_time_limit(a.timeout); /* from here: the adapter's --check too */
    if ((st = aa_pattern_parse(a.pattern, &pattern)) || (st = cli_view_size(a.size, &pattern, &w, &h)) ||
        (st = aa_size_check(w, h, 3, 2)) ||
        (st = a.filter ? aa_filter_parse(a.filter, &f) : (aa_filter_default(&f), AA_OK)) ||
        (st = aa_method_parse(a.method, &f, &method)) || (st = cli_check_output(a.out)) ||
        (a.stats && (st = cli_check_output_file(a.stats, ".json"))))
        return cli_fail("render", st);
    int threads = a.threads > 0 ? a.threads : aa_default_threads();
    aa_scene *scene = NULL;
    aa_job job = {0};
    aa_image img = {0};
    aa_counters counters;
    aa_timing *timing = calloc(1, sizeof *timing);
    aa_timing_plan plan = {a.reps, a.target_ci, a.budget};
    /* timed only when asked: otherwise one render, and its time */
    int timed = a.reps > 0 || a.target_ci > 0 || a.budget > 0 || a.stats;
    double once = 0.0;
    if (!timing)
        return cli_fail("render", aa_fail(AA_ENOMEM, "out of memory"));
    if (!(st = aa_pattern_scene_at(&pattern, w, h, &scene)) &&
        !(st = aa_job_init(&job, scene, w, h, a.t, a.vx, a.vy, &f, a.seed, threads)) &&
        !(st = aa_image_alloc(&img, w, h, 3))) {
        job.frame_only = a.frame_only;
        double cost = aa_case_estimate(job.placed, w, h, &method);
        if (cost > AA_COST_LIMIT)
            aa_warn("estimated cost %.2g, past the limit %.0g (harness/bench/cost.c): the render "
                    "may run for minutes",
                    cost, AA_COST_LIMIT);
        st = timed ? aa_method_time(&method, &job, &plan, &img, &counters, timing)
                   : aa_method_run(&method, &job, 1, &img, &counters, &once);
    }
    int at[3];
    double bad_value = 0.0, lo, hi;
    aa_method_value_range(&f, &lo, &hi);
    size_t bad = st ? 0 : aa_image_bad_values(&img, lo, hi, at, &bad_value);
    if (bad) {
        char ms[1024];
        aa_spec_format(&method, ms, sizeof ms);
        st = aa_fail(AA_ECHECK,
                     "method %s gave %zu value%s outside [%.6g, %.6g] or not finite, the first "
                     "%.17g at pixel (%d, %d) channel %d: nothing written",
                     ms, bad, bad == 1 ? "" : "s", lo, hi, bad_value, at[0], at[1], at[2]);
    }
    /* every output written before any replaces what was there */
    cli_outputs outs = {0};
    const char *tmp;
    if (!st && !(st = cli_stage(&outs, a.out, &tmp)) &&
        (st = aa_image_write(tmp, &img, &a.enc)))
        st = aa_fail_context(st, "cannot write %s", a.out);
    if (!st && a.stats && !(st = cli_stage(&outs, a.stats, &tmp)))
        if ((st = write_stats(tmp, &a, &pattern, &method, &f, w, h, timing, &counters, threads)))
            st = aa_fail_context(st, "cannot write %s", a.stats);
    if (!st)
        st = cli_commit(&outs);
    else
        cli_discard(&outs);
    aa_image_free(&img);
    aa_job_free(&job);
    aa_scene_free(scene);
    if (st) {
        free(timing);
        return cli_fail("render", st);
    }
    if (!a.quiet && !timed) {
        char ms[1024];
        aa_spec_format(&method, ms, sizeof ms);
        printf("wrote %s: %s, %dx%d, rendered once in %.4f s (not timed: --reps, --budget or "
               "--target-ci times it), %llu samples, %llu expensive pixels\n",
               a.out, ms, w, h, once, (unsigned long long)counters.samples,
               (unsigned long long)counters.expensive_pixels);
    } else if (!a.quiet) {
        char ms[1024], ci[64] = "";
        aa_spec_format(&method, ms, sizeof ms);
        if (isfinite(timing->ci_rel))
            snprintf(ci, sizeof ci, " +-%.1f%% (95%% CI)", 100 * timing->ci_rel);
        else if (timing->n > 0) {
            snprintf(ci, sizeof ci, " (");
            aa_timing_ci_text(timing, ci + 2, sizeof ci - 3);
            strcat(ci, ")");
        }
        printf("wrote %s: %s, %dx%d, median %.4f s%s over %d render%s, %llu samples, %llu "
               "expensive pixels\n",
               a.out, ms, w, h, timing->stats.median, ci, timing->n, timing->n > 1 ? "s" : "",
               (unsigned long long)counters.samples,
               (unsigned long long)counters.expensive_pixels);
    }
    if (timed && timing->noisy) {
        fflush(stdout); /* after the line above */
        char why[128];
        aa_noisy_text(timing->noisy, why, sizeof why);
        fprintf(stderr, "aabench render: warning: the timing is noisy (%s): other processes used "
                        "%.2f cores; see \"A quiet measurement\" in harness/bench/README.md\n",
                why, timing->others_cores);
    }
    free(timing);
    return 0;
}
