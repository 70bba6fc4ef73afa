/*
 * cmd_converge.c: `aabench converge`: RMSE against samples per pixel.
 */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench converge -p PATTERN -m METHOD -s WxH --spp 1,4,16,... [--phases K]\n"
            "                        [-f FILTER] [--time T] [--motion VX,VY] [--seed N]\n"
            "                        [--threads N] [--out DIR] [--cache DIR | --no-cache]\n"
            "                        [--plugin LIB.so]...\n\n"
            "Measures the RMSE of METHOD at each samples-per-pixel count over K random\n"
            "sub-pixel shifts of the scene (default 8), fits the slope of log RMSE against\n"
            "log spp by least squares and prints it on the last line as 'slope S +- E'.\n"
            "The method's spp parameter is set (or n, for an n x n grid: spp must be squares).\n"
            "--time T and --motion VX,VY place the scene at time T (frames) moving VX,VY\n"
            "pixels per frame, the shifts added; the reference is that frame's.\n"
            "With --out DIR, also draws DIR/convergence.png.  References are cached in\n"
            "--cache DIR (default $AABENCH_CACHE, else results/cache in the source tree,\n"
            "else $XDG_CACHE_HOME/aabench); --plugin loads methods from a shared library.\n");
}

int cmd_converge(int argc, char **argv)
{
    enum { O_SPP = 256, O_PHASES, O_SEED, O_CACHE, O_NOCACHE, O_PLUGIN,
           O_TIME, O_MOTION };
    static const struct option opts[] = {
        {"pattern", required_argument, 0, 'p'}, {"method", required_argument, 0, 'm'},
        {"size", required_argument, 0, 's'},    {"filter", required_argument, 0, 'f'},
        {"spp", required_argument, 0, O_SPP},   {"phases", required_argument, 0, O_PHASES},
        {"seed", required_argument, 0, O_SEED}, CLI_OPTION_THREADS,
        CLI_OPTION_OUT,   {"cache", required_argument, 0, O_CACHE},
        {"no-cache", no_argument, 0, O_NOCACHE}, {"plugin", required_argument, 0, O_PLUGIN},
        {"time", required_argument, 0, O_TIME}, {"motion", required_argument, 0, O_MOTION},
        {"help", no_argument, 0, 'h'},          {0, 0, 0, 0}};
    const char *pattern = NULL, *method = NULL, *size = NULL, *filter = NULL, *spps = NULL,
               *out = NULL, *cache = cli_cache_dir();
    int c, st = AA_OK, phases = 8, threads = 0;
    uint64_t seed = 1;
    double tm = 0.0, vx = 0.0, vy = 0.0;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":p:m:s:f:h", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, (const int[]){O_PLUGIN, 0})))
            return cli_fail("converge", st);
        switch (c) {
        case 'p': pattern = optarg; break;
        case 'm': method = optarg; break;
        case 's': size = optarg; break;
        case 'f': filter = optarg; break;
        case O_SPP: spps = optarg; break;
        case O_PHASES: st = aa_parse_int("--phases", optarg, 1, 1024, &phases); break;
        case O_SEED: st = aa_parse_seed(optarg, &seed); break;
        case O_CACHE: cache = optarg; break;
        case O_NOCACHE: cache = ""; break;
        case O_PLUGIN: st = aa_plugin_load(optarg); break;
        case O_TIME: st = aa_parse_real("--time", optarg, -1e9, 1e9, &tm); break;
        case O_MOTION: st = aa_parse_pair("--motion", optarg, -1e6, 1e6, &vx, &vy); break;
        case CLI_O_OUT:
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, &out, &threads); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("converge", c, argv);
        }
        if (st)
            return cli_fail("converge", st);
    }
    if (optind < argc || !pattern || !method || !size || !spps) {
        fprintf(stderr, "aabench converge: -p PATTERN, -m METHOD, -s WxH and --spp LIST are "
                        "required\n");
        usage(stderr);
        return 2;
    }
    int spp[64], w, h;
    size_t n = 0;
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", spps);
    for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
        if (n == 64)
            return aa_fail(AA_EINVAL, "more than 64 spp values"), cli_fail("converge", AA_EINVAL);
        if ((st = aa_parse_int("--spp value", t, 1, 1 << 20, &spp[n++])))
            return cli_fail("converge", st);
    }
    aa_spec pspec, mspec;
    aa_filter f;
    aa_convergence conv;
    if ((st = aa_pattern_parse(pattern, &pspec)) || (st = aa_size_parse(size, &w, &h)) ||
        (st = aa_size_check(w, h, 3, 3)) ||
        (st = filter ? aa_filter_parse(filter, &f) : (aa_filter_default(&f), AA_OK)) ||
        (st = aa_method_parse(method, &f, &mspec)) ||
        (cli_cache_usable("converge", cache), 0) ||
        (st = aa_converge_moving(&pspec, &mspec, &f, w, h, tm, vx, vy, spp, n, phases, seed,
                          threads > 0 ? threads : aa_default_threads(), *cache ? cache : NULL,
                          &conv)))
        return cli_fail("converge", st);
    printf("# %s on %s %s %s, %d phases\n# spp rmse rmse_sd seconds\n", method, pattern, size,
           filter ? filter : "box", phases);
    for (size_t k = 0; k < conv.n; k++)
        printf("%g %.6e %.3e %.4f\n", conv.spp[k], conv.rmse[k], conv.rmse_sd[k], conv.seconds[k]);
    if (out) {
        const char *names[1] = {method};
        char title[1024];
        snprintf(title, sizeof title, "Convergence of %s on %s %s %s, %d shifts", method, pattern,
                 size, filter ? filter : "box", phases);
        if ((st = aa_plot_convergence(out, &conv, names, 1, title)))
            return cli_fail("converge", st);
    }
    printf("slope %.4f +- %.4f\n", conv.slope, conv.slope_err);
    return 0;
}
