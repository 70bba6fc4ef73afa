/*
 * cmd_merge.c: `aabench merge DIR... --out DIR`: the folders of a run's
 * shards (run --shard K/N) joined into the whole run's results.
 *
 * Every folder's manifest (run.json) must name the same command, suite and
 * commit, and together their results must hold every case of the run
 * exactly once; a missing, duplicated or foreign shard is refused (exit 2)
 * naming it, before anything is written, and so is a shard whose cases are
 * not those the run's plan gives it or a row that is not its case (its
 * pattern, size, filter, method, canonical name, time, motion or seed), or
 * whose results.csv or images are not the files its run wrote: each
 * checked against the checksum its run.json records when its run ended.  Then the rows, in the run's
 * order, are written as the unsharded run writes them (the library's
 * aa_runfolder_merge and aa_runfolder_finish: results.csv and .json,
 * montage, plots; cmd_run.c's table); each row keeps the host
 * that measured it and its times.  The errors are the shards', which are
 * the unsharded run's: every case is computed the same way whichever
 * process runs it.
 */
#include "cli.h"

#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench merge DIR... --out DIR [-q] [--cache DIR]\n\n"
            "Joins the folders of a run's shards ('aabench run --shard K/N --out DIR') into\n"
            "the whole run's results.csv, results.json, images/, montage.png, plots/ and\n"
            "table, as the run without --shard writes them.  The shards must come from the\n"
            "same command, suite and commit and hold every case exactly once.\n\n"
            "  --out DIR        the merged run's folder\n"
            "  --cache DIR      reference cache for the montage and plots (default\n"
            "                   $AABENCH_CACHE, else results/cache in the source tree,\n"
            "                   else $XDG_CACHE_HOME/aabench)\n"
            "  -q, --quiet      no table at the end\n\n"
            "Exit status: 0 done, 1 some cases failed (as in run), 2 a shard missing,\n"
            "duplicated or of another run, or bad usage, 3 input/output error.\n");
}

int cmd_merge(int argc, char **argv)
{
    enum { O_CACHE = 256 };
    static const struct option opts[] = {CLI_OPTION_OUT,
                                         {"cache", required_argument, 0, O_CACHE},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    aa_run_options opt;
    const char *cache_words[2];
    int quiet = 0, c, st = AA_OK;
    aa_run_options_default(&opt);
    opt.cache = cli_cache_dir();
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":qh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("merge", st);
        switch (c) {
        case O_CACHE:
            /* recorded after the run's command in the results' context */
            opt.cache = cache_words[1] = optarg;
            cache_words[0] = "--cache";
            opt.argc = 2, opt.argv = cache_words;
            break;
        case 'q': quiet = 1; break;
        case CLI_O_OUT: st = cli_out_threads(c, optarg, &opt.out, NULL); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("merge", c, argv);
        }
        if (st)
            return cli_fail("merge", st);
    }
    int ns = argc - optind;
    if (ns < 1 || !opt.out) {
        usage(stderr);
        return 2;
    }
    opt.note = cli_run_note;
    cli_cache_usable("merge", opt.cache);
    aa_runfolder *rf;
    if ((st = aa_runfolder_merge((const char *const *)argv + optind, (size_t)ns, &opt, &rf)))
        return cli_fail("merge", st);
    st = aa_runfolder_finish(rf);
    int code = cli_run_report(rf, quiet, st);
    aa_runfolder_free(rf);
    return code;
}
