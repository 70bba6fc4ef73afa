/*
 * cmd_prune.c: `aabench prune --keep N`: the oldest run folders removed
 * (aa_runs_prune, harness/bench/prune.h).
 */
#include "cli.h"
#include "prune.h"

#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench prune --keep N [--dry-run] [--results DIR]\n\n"
            "Removes the oldest run folders under DIR/runs (default results/runs), keeping the\n"
            "N newest by the UTC time in their names. Only folders named as a run names them\n"
            "(YYYYMMDDTHHMMSSZ[-K]) and holding run.json are touched; the one DIR/latest points\n"
            "to is always kept.\n\n"
            "  --keep N        the number of newest runs kept (0 or more)\n"
            "  -n, --dry-run   list what would be removed, remove nothing\n"
            "  --results DIR   the results folder (default results)\n"
            "Exit status: 0 done, 2 bad input, 3 input/output error.\n");
}

static void said(void *ctx, const char *dir)
{
    printf("%s %s\n", *(const int *)ctx ? "would remove" : "removed", dir);
}

int cmd_prune(int argc, char **argv)
{
    enum { O_KEEP = 256, O_RESULTS };
    static const struct option opts[] = {{"keep", required_argument, 0, O_KEEP},
                                         {"results", required_argument, 0, O_RESULTS},
                                         {"dry-run", no_argument, 0, 'n'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    int c, st = AA_OK, keep = -1, dry = 0;
    const char *results = "results";
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":nh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("prune", st);
        switch (c) {
        case O_KEEP: st = aa_parse_int("--keep", optarg, 0, 1000000, &keep); break;
        case O_RESULTS: results = optarg; break;
        case 'n': dry = 1; break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("prune", c, argv);
        }
        if (st)
            return cli_fail("prune", st);
    }
    if (argc > optind || keep < 0) {
        fprintf(stderr, "aabench prune: %s\n",
                argc > optind ? "unexpected argument" : "--keep N is needed");
        usage(stderr);
        return 2;
    }
    size_t removed = 0;
    st = aa_runs_prune(results, keep, dry, said, &dry, &removed);
    if (st)
        return cli_fail("prune", st);
    printf("%s %zu run folder%s\n", dry ? "would remove" : "removed", removed,
           removed == 1 ? "" : "s");
    return 0;
}
