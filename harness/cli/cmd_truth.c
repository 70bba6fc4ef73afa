/*
 * cmd_truth.c: `aabench truth`: the exact reference image of a pattern.
 */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench truth -p PATTERN [-s WxH] [-f FILTER] -o OUT [options]\n\n"
            "Writes the reference image: the pattern convolved with the filter at each\n"
            "pixel centre, exact to 1e-12 per pixel (GSL quadrature along y, exact along x).\n\n"
            "  -p, --pattern SPEC   pattern, e.g. crow or crow:curves=64 ('aabench list patterns')\n"            "                       or svg:file=scene.svg or text:ppem=12 (drawn in pixels)\n"
            "  -s, --size WxH       image size in pixels (default: an svg file's own size times\n"
            "                       its scale)\n"
            "  -f, --filter SPEC    box (default) or another of 'aabench list filters',\n"
            "                       e.g. tent:r=1, bspline:order=3, gauss:s=1,cut=2\n"
            "  -o, --out FILE       .exr .tif .pfm (float), .png (8-bit, display encoded), .txt\n"
            "      --time T         time in frames (default 0)\n"
            "      --motion VX,VY   motion in pixels per frame (default 0,0)\n"
            "      --threads N      threads (default: all cores)\n"
            "      --encode E       .png encoding: srgb (default), linear or gamma:G\n"
            "      --bound FILE     also write the per-pixel error bounds (1 channel)\n"
            "      --cache DIR      reference cache folder (default $AABENCH_CACHE, else\n"
            "                       results/cache in the source tree, else\n"
            "                       $XDG_CACHE_HOME/aabench)\n"
            "      --no-cache       neither read nor write the cache\n"
            "  -q, --quiet          print nothing on success\n\n"
            "usage: aabench truth --warm SUITE [run's options: -p, -s, -f, --motion, --cache,\n"
            "                    --threads, ...]\n\n"
            "Computes every reference `aabench run --suite SUITE` with those options would\n"
            "ask the cache for, and stores those missing, so the shards of a run on\n"
            "several machines sharing the cache folder start from it.\n");
}

/* --warm SUITE: run's own options, as `run --suite SUITE` takes them. */
static int warm(int argc, char **argv)
{
    char **args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return cli_fail("truth", aa_fail(AA_ENOMEM, "out of memory"));
    int n = 0;
    args[n++] = "run";
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "--warm") && k + 1 < argc) {
            args[n++] = "--suite", args[n++] = argv[++k];
        } else if (!strncmp(argv[k], "--warm=", 7)) {
            args[n++] = "--suite", args[n++] = argv[k] + 7;
        } else {
            args[n++] = argv[k];
        }
    }
    aa_plan plan;
    aa_run_options opt;
    int asked, st;
    size_t computed = 0, cached = 0;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    opt.cache = cli_cache_dir();
    st = aa_plan_parse(n, args, &plan, &opt, &asked);
    free(args);
    if (st)
        return asked == '?' ? cli_bad_usage("truth", st) : cli_fail("truth", st);
    if (asked == 'h' || asked == 'l') {
        usage(stdout);
        return 0;
    }
    if (!*opt.cache) {
        fprintf(stderr, "aabench truth: --warm needs a cache folder (not --no-cache)\n");
        return 2;
    }
    /* the cache is what it makes: one it cannot write is a failure */
    if ((st = cli_cache_writable(opt.cache))) {
        fprintf(stderr, "aabench truth: --warm: the reference cache %s cannot be written (%s)\n",
                aa_echo(opt.cache), aa_last_error());
        return aa_exit_code(st);
    }
    opt.note = cli_run_note;
    double t0 = aa_now();
    if ((st = aa_runfolder_warm(&plan, &opt, &computed, &cached)))
        return cli_fail("truth", st);
    if (!opt.quiet)
        printf("%zu reference%s of suite %s in %s: %zu computed, %zu already there (%.1f s)\n",
               computed + cached, computed + cached == 1 ? "" : "s", plan.suite, opt.cache,
               computed, cached, aa_now() - t0);
    return 0;
}

/* Progress on standard error (a terminal, CI unset: cli_progress_wanted)
 * once a reference has taken more than two seconds. */
typedef struct truth_progress {
    double t0;
    int shown;
} truth_progress;

static void show_progress(void *vctx, size_t done, size_t total)
{
    truth_progress *p = vctx;
    double el = aa_now() - p->t0;
    if (done >= total) {
        if (p->shown)
            fprintf(stderr, "\r\033[K");
        p->shown = 0;
    } else if (el > 2.0) {
        fprintf(stderr, "\r\033[Kreference: %zu/%zu pixels (%.0f%%), %.0f s", done, total,
                100.0 * (double)done / (double)total, el);
        p->shown = 1;
    }
    fflush(stderr);
}

typedef struct truth_args {
    const char *pattern, *size, *filter, *out, *bound, *cache;
    aa_view view;
    aa_encode enc;
    int threads, quiet;
} truth_args;

/* Returns -1 to go on, or the exit code to stop with. */
static int parse(int argc, char **argv, truth_args *a)
{
    enum { O_TIME = 256, O_MOTION, O_ENCODE, O_BOUND, O_CACHE, O_NOCACHE };
    static const struct option opts[] = {
        {"pattern", required_argument, 0, 'p'}, {"size", required_argument, 0, 's'},
        {"filter", required_argument, 0, 'f'},  {"out", required_argument, 0, 'o'},
        {"time", required_argument, 0, O_TIME}, {"motion", required_argument, 0, O_MOTION},
        CLI_OPTION_THREADS,
        {"encode", required_argument, 0, O_ENCODE},
        {"bound", required_argument, 0, O_BOUND}, {"cache", required_argument, 0, O_CACHE},
        {"no-cache", no_argument, 0, O_NOCACHE}, {"quiet", no_argument, 0, 'q'},
        {"help", no_argument, 0, 'h'},          {0, 0, 0, 0}};
    int c, st = AA_OK;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":p:s:f:o:qh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("truth", st);
        switch (c) {
        case 'p': a->pattern = optarg; break;
        case 's': a->size = optarg; break;
        case 'f': a->filter = optarg; break;
        case 'o': a->out = optarg; break;
        case 'q': a->quiet = 1; break;
        case O_TIME: st = aa_parse_real("--time", optarg, -1e9, 1e9, &a->view.t); break;
        case O_MOTION:
            st = aa_parse_pair("--motion", optarg, -1e6, 1e6, &a->view.vx, &a->view.vy);
            break;
        case O_ENCODE: st = aa_encode_parse(optarg, &a->enc); break;
        case O_BOUND: a->bound = optarg; break;
        case O_CACHE: a->cache = optarg; break;
        case O_NOCACHE: a->cache = ""; break;
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, NULL, &a->threads); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("truth", c, argv);
        }
        if (st)
            return cli_fail("truth", st);
    }
    if (optind < argc) {
        fprintf(stderr, "aabench truth: unexpected argument \"%s\"\n", aa_echo(argv[optind]));
        return 2;
    }
    if (!a->pattern || !a->out) {
        fprintf(stderr, "aabench truth: -p PATTERN and -o OUT are required\n");
        usage(stderr);
        return 2;
    }
    return -1;
}

int cmd_truth(int argc, char **argv)
{
    for (int k = 1; k < argc; k++)
        if (!strcmp(argv[k], "--warm") || !strncmp(argv[k], "--warm=", 7))
            return warm(argc, argv);
    truth_args a;
    memset(&a, 0, sizeof a);
    a.cache = cli_cache_dir();
    a.enc.kind = AA_ENCODE_SRGB;
    int st, code = parse(argc, argv, &a);
    if (code >= 0)
        return code;
    if ((st = aa_pattern_parse(a.pattern, &a.view.pattern)) ||
        (st = cli_view_size(a.size, &a.view.pattern, &a.view.w, &a.view.h)) ||
        (st = aa_size_check(a.view.w, a.view.h, 4, 2)) ||
        (st = a.filter ? aa_filter_parse(a.filter, &a.view.filter)
                       : (aa_filter_default(&a.view.filter), AA_OK)) ||
        (st = cli_check_output(a.out)) || (a.bound && (st = cli_check_output(a.bound))))
        return cli_fail("truth", st);
    if (!a.bound)
        cli_cache_usable("truth", a.cache);

    aa_image img = {0}, bound = {0};
    aa_truth_stats stats;
    int cached = 0;
    double t0 = aa_now();
    truth_progress prog = {t0, 0};
    if (!a.quiet && cli_progress_wanted())
        aa_truth_set_progress(show_progress, &prog);
    if (a.bound) {
        aa_scene *pattern = NULL, *placed = NULL;
        if (!(st = aa_pattern_scene_at(&a.view.pattern, a.view.w, a.view.h, &pattern)) &&
            !(placed = aa_scene_place(pattern, a.view.w, a.view.h, a.view.t, a.view.vx,
                                      a.view.vy)))
            st = AA_EINVAL;
        if (!st && !(st = aa_image_alloc(&img, a.view.w, a.view.h, 3)) &&
            !(st = aa_image_alloc(&bound, a.view.w, a.view.h, 1)))
            st = aa_truth_render(placed, &a.view.filter, a.threads, &img, &bound, &stats);
        aa_scene_free(placed);
        aa_scene_free(pattern);
    } else {
        st = aa_reference(&a.view, *a.cache ? a.cache : NULL, a.threads, &img, &stats, &cached);
    }
    double seconds = aa_now() - t0;
    aa_truth_set_progress(NULL, NULL);
    if (prog.shown)
        fprintf(stderr, "\r\033[K");
    /* every output written before any replaces what was there */
    cli_outputs outs = {0};
    const char *tmp;
    if (!st && !(st = cli_stage(&outs, a.out, &tmp)) &&
        (st = aa_image_write(tmp, &img, &a.enc)))
        st = aa_fail_context(st, "cannot write %s", a.out);
    if (!st && a.bound && !(st = cli_stage(&outs, a.bound, &tmp)) &&
        (st = aa_image_write(tmp, &bound, NULL)))
        st = aa_fail_context(st, "cannot write %s", a.bound);
    if (!st)
        st = cli_commit(&outs);
    else
        cli_discard(&outs);
    aa_image_free(&img);
    aa_image_free(&bound);
    if (st)
        return cli_fail("truth", st);
    if (!a.quiet) {
        char spec[4096], filter[256];
        aa_spec_format(&a.view.pattern, spec, sizeof spec);
        aa_spec_format(&a.view.filter.spec, filter, sizeof filter);
        if (cached)
            printf("wrote %s: %s %dx%d %s, from the cache, max error bound %.2g\n", a.out, spec,
                   a.view.w, a.view.h, filter, stats.max_bound);
        else
            printf("wrote %s: %s %dx%d %s, %zu pixels integrated, %zu filled, max error bound "
                   "%.2g, %.3f s\n",
                   a.out, spec, a.view.w, a.view.h, filter, stats.integrated, stats.filled,
                   stats.max_bound, seconds);
        if (stats.scanned)
            printf("%zu pixels' threshold heights (gradients of different t mixing) scanned, "
                   "not certified: their bounds are QAG's estimates (truth.c, \"several "
                   "gradients\")\n",
                   stats.scanned);
    }
    return 0;
}
