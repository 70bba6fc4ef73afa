/*
 * cmd_figures.c: `aabench figures [--out DIR] [--only NAME,...] [--claims]
 * [--reps N] [--threads N] [-q]`: the seed papers' comparison figures
 * remade (figures.c), a table of each panel's errors on standard output,
 * DIR/index.html a gallery of them; with --claims, the papers' quantitative
 * claims measured (claims.c) into DIR/claims.md and the gallery.
 */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench figures [--out DIR] [--only NAME,...] [--claims [--reps N]]\n"
                 "                       [--threads N] [-q]\n\n"
                 "Remakes the published comparison figures of the seed papers (Crow 1976,\n"
                 "Catmull 1978, Feibush, Levoy and Cook 1980): DIR/NAME.png with labelled\n"
                 "panels, DIR/NAME.txt with the paper's figure and claim, the settings and each\n"
                 "panel's RMSE and largest error against the exact reference, and\n"
                 "DIR/index.html, a gallery of the figures in DIR.  With --claims, measures\n"
                 "the papers' quantitative claims instead (DIR/claims.md, DIR/claims.html, and\n"
                 "the gallery's last section): each time ratio is the median over --reps\n"
                 "pairs of interleaved renders on one thread.  References are cached in\n"
                 "$AABENCH_CACHE (default: results/cache in the source tree, else\n"
                 "$XDG_CACHE_HOME/aabench).\n\n"
                 "      --out DIR       folder (default results/figures)\n"
                 "      --claims        measure the claims table (no figures unless --only)\n"
                 "      --reps N        --claims: pairs of renders timed per ratio (default 31)\n"
                 "      --only N,...    only these figures:\n");
    for (size_t k = 0; k < aa_figure_count(); k++)
        fprintf(out, "                        %s\n", aa_figure_name(k));
    fprintf(out, "      --threads N     threads (the images do not depend on it)\n"
                 "  -q, --quiet         no progress\n");
}

static int parse_only(const char *text, unsigned char *want, size_t n)
{
    char buf[1024];
    if (strlen(text) >= sizeof buf)
        return aa_fail(AA_EINVAL, "--only: list too long");
    strcpy(buf, text);
    memset(want, 0, n);
    int any = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k = aa_figure_find(tok);
        if (k < 0) {
            char names[2048] = "";
            for (size_t j = 0; j < n; j++) {
                strncat(names, j ? ", " : "", sizeof names - strlen(names) - 1);
                strncat(names, aa_figure_name(j), sizeof names - strlen(names) - 1);
            }
            return aa_fail(AA_EINVAL, "--only: no figure \"%s\" (accepted: %s)", tok, names);
        }
        want[k] = 1;
        any = 1;
    }
    if (!any)
        return aa_fail(AA_EINVAL, "--only: empty list (give figure names separated by commas)");
    return AA_OK;
}

static int claims_progress(void *ctx, const char *what)
{
    if (*(int *)ctx)
        fprintf(stderr, "\r\033[Kclaims: %.70s", what);
    return 0;
}

int cmd_figures(int argc, char **argv)
{
    enum { O_ONLY = 256, O_CLAIMS, O_REPS };
    static const struct option opts[] = {CLI_OPTION_OUT,
                                         {"only", required_argument, 0, O_ONLY},
                                         CLI_OPTION_THREADS,
                                         {"claims", no_argument, 0, O_CLAIMS},
                                         {"reps", required_argument, 0, O_REPS},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    enum { NMAX = 64 };
    const size_t n = aa_figure_count();
    unsigned char want[NMAX];
    const char *dir = "results/figures";
    int c, st = AA_OK, threads = aa_default_threads(), quiet = 0, claims = 0, only = 0;
    int reps = 31;
    if (n > NMAX)
        return cli_fail("figures", aa_fail(AA_EFAIL, "too many figures"));
    memset(want, 1, sizeof want);
    cli_getopt_reset();
    while (!st && (c = getopt_long(argc, argv, ":hq", opts, NULL)) != -1) {
        switch (c) {
        case O_ONLY:
            st = parse_only(optarg, want, n);
            only = 1;
            break;
        case O_CLAIMS: claims = 1; break;
        case O_REPS: st = aa_parse_int("--reps", optarg, 1, 1000, &reps); break;
        case 'q': quiet = 1; break;
        case CLI_O_OUT:
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, &dir, &threads); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("figures", c, argv);
        }
    }
    if (!st && optind < argc)
        st = aa_fail(AA_EINVAL, "unexpected argument \"%s\"", aa_echo(argv[optind]));
    if (!st && *dir == '\0')
        st = aa_fail(AA_EINVAL, "--out: empty folder name");
    if (!st)
        st = aa_mkdirs(dir);
    if (st)
        return cli_fail("figures", st);
    if (claims && !only)
        memset(want, 0, sizeof want);
    int show = !quiet && cli_progress_wanted();
    double t0 = aa_now();
    if (!claims || only)
        printf("%-21s %-30s %12s %12s %12s\n", "figure", "panel", "rmse", "max_err", "eye_rmse");
    for (size_t k = 0; k < n && !st; k++) {
        if (!want[k])
            continue;
        if (show)
            fprintf(stderr, "\r%-70s", aa_figure_name(k));
        aa_figure_result r;
        if ((st = aa_figure_make(k, dir, cli_cache_dir(), threads, &r)))
            break;
        if (show)
            fprintf(stderr, "\r%70s\r", "");
        if (r.npanels == 0)
            printf("%-21s %s\n", r.name, r.summary);
        for (int p = 0; p < r.npanels; p++) {
            char eye[32] = "-";
            if (isfinite(r.panel[p].eye_rmse))
                snprintf(eye, sizeof eye, "%12.4e", r.panel[p].eye_rmse);
            if (r.panel[p].reference)
                printf("%-21s %-30.30s %12s %12s %12s\n", r.name, r.panel[p].label, "reference",
                       "-", eye);
            else
                printf("%-21s %-30.30s %12.4e %12.4e %12s\n", r.name, r.panel[p].label,
                       r.panel[p].rmse, r.panel[p].max_err, eye);
        }
        fflush(stdout);
    }
    if (!st && claims) {
        st = aa_claims_make(dir, cli_cache_dir(), threads, reps, claims_progress, &show);
        if (show)
            fprintf(stderr, "\r\033[K");
        if (!st)
            printf("wrote %s/claims.md\n", dir);
    }
    if (!st)
        st = aa_figure_index(dir);
    if (st)
        return cli_fail("figures", st);
    printf("wrote %s/index.html (%.1f s)\n", dir, aa_now() - t0);
    return 0;
}
