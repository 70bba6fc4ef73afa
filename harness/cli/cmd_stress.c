/*
 * cmd_stress.c: `aabench stress [--out DIR] [--only N,...] [--threads N]
 * [-q]`: the numerical stress suite (stress.c), a table on standard output,
 * stress.csv in DIR, exit 1 if any case fails its bound.
 */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench stress [--out DIR] [--only K,...] [--threads N] [-q]\n\n"
            "Scenes at the limits of the geometry (Crow's pattern from straight to its\n"
            "validity limit, gaps of 1e-7, 65536 curves; scenes moved by up to 1e6 pixels;\n"
            "sizes 1x1, 1x8192, 8192x1 and odd primes; slivers down to 1e-9 px; degenerate\n"
            "polygons).  For each: the largest error of the box reference and of `area`\n"
            "against a long double evaluation of the same scene, the count of NaN and Inf,\n"
            "and whether every method's values are finite and in [0, 1].  Bounds: the\n"
            "reference 1e-12, area 1e-11, each plus 1e-15 per pixel the scene is moved.\n"
            "Exit status 1 if a case fails.\n\n"
            "      --out DIR     write DIR/stress.csv (default results/stress)\n"
            "      --only K,...  run only these cases (numbers from the table, 1-based)\n"
            "      --threads N   threads (the results do not depend on it)\n"
            "  -q, --quiet       no progress\n");
}

static int parse_only(const char *text, unsigned char *want, size_t n)
{
    char buf[512];
    if (strlen(text) >= sizeof buf)
        return aa_fail(AA_EINVAL, "--only: list too long");
    strcpy(buf, text);
    memset(want, 0, n);
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k;
        if (aa_parse_int("--only", tok, 1, (long)n, &k))
            return AA_EINVAL;
        want[k - 1] = 1;
    }
    return AA_OK;
}

int cmd_stress(int argc, char **argv)
{
    enum { O_ONLY = 256 };
    static const struct option opts[] = {CLI_OPTION_OUT,
                                         {"only", required_argument, 0, O_ONLY},
                                         CLI_OPTION_THREADS,
                                         {"quiet", no_argument, 0, 'q'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const size_t n = aa_stress_count();
    unsigned char *want = malloc(n);
    aa_stress_result *res = calloc(n, sizeof *res);
    const char *dir = "results/stress";
    int c, st = AA_OK, threads = aa_default_threads(), quiet = 0, code = 0;
    if (!want || !res) {
        free(want);
        free(res);
        return cli_fail("stress", aa_fail(AA_ENOMEM, "out of memory"));
    }
    memset(want, 1, n);
    cli_getopt_reset();
    while (!st && (c = getopt_long(argc, argv, ":hq", opts, NULL)) != -1) {
        switch (c) {
        case O_ONLY: st = parse_only(optarg, want, n); break;
        case 'q': quiet = 1; break;
        case CLI_O_OUT:
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, &dir, &threads); break;
        case 'h':
            usage(stdout);
            free(want);
            free(res);
            return 0;
        default:
            free(want);
            free(res);
            return cli_bad_option("stress", c, argv);
        }
    }
    if (!st && optind < argc)
        st = aa_fail(AA_EINVAL, "unexpected argument \"%s\"", aa_echo(argv[optind]));
    char csv[4096];
    if (!st)
        st = aa_pathf(csv, sizeof csv, "%s/stress.csv", dir);
    if (!st)
        st = aa_mkdirs(dir);
    if (st) {
        free(want);
        free(res);
        return cli_fail("stress", st);
    }
    int show = !quiet && cli_progress_wanted();
    printf("%-3s %-46s %-10s %10s %9s %10s %9s %5s %7s  %s\n", "#", "case", "size", "ref_err",
           "bound", "area_err", "bound", "nan", "methods", "result");
    size_t failed = 0, ran = 0;
    for (size_t k = 0; k < n && !st; k++) {
        if (!want[k])
            continue;
        if (show)
            fprintf(stderr, "\r[%zu/%zu] %-60s", k + 1, n, aa_stress_name(k));
        aa_stress_result *r = &res[k];
        if ((st = aa_stress_run_case(k, threads, r)))
            break;
        ran++;
        failed += !r->pass;
        char size[32];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        if (show)
            fprintf(stderr, "\r%80s\r", "");
        printf("%-3zu %-46s %-10s %10.2e %9.1e %10.2e %9.1e %5zu %3d+%-3d  %s\n", k + 1, r->name,
               size, r->ref_err, r->ref_bound, r->area_err, r->area_bound, r->nonfinite,
               r->methods, r->refused, r->pass ? "pass" : "FAIL");
        if (r->out_of_range)
            printf("    %zu method values outside [0, 1]\n", r->out_of_range);
        fflush(stdout);
    }
    if (!st) {
        /* the CSV, written whole or not at all */
        size_t cap = 256 + ran * 256, len = 0;
        char *buf = malloc(cap);
        if (!buf)
            st = aa_fail(AA_ENOMEM, "out of memory");
        else {
            len += (size_t)snprintf(buf + len, cap - len,
                                    "case,size,ref_err,ref_bound,area_err,area_bound,nonfinite,"
                                    "out_of_range,methods,refused,pass\n");
            for (size_t k = 0; k < n; k++)
                if (want[k])
                    len += (size_t)snprintf(buf + len, cap - len,
                                            "\"%s\",%dx%d,%.6g,%.6g,%.6g,%.6g,%zu,%zu,%d,%d,%d\n",
                                            res[k].name, res[k].w, res[k].h, res[k].ref_err,
                                            res[k].ref_bound, res[k].area_err, res[k].area_bound,
                                            res[k].nonfinite, res[k].out_of_range, res[k].methods,
                                            res[k].refused, res[k].pass);
            st = aa_file_write_atomic(csv, buf, len);
            free(buf);
        }
    }
    if (st)
        code = cli_fail("stress", st);
    else {
        printf("stress: %zu of %zu cases passed; %s\n", ran - failed, ran, csv);
        code = failed ? 1 : 0;
    }
    free(want);
    free(res);
    return code;
}
