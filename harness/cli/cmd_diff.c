/*
 * cmd_diff.c: `aabench diff OLD NEW`: two runs compared case by case.
 *
 * OLD and NEW are run folders or results files (results.csv, or a
 * results.json read as JSON).  Per case of both: the error change, judged
 * by the one rule of both gates (aa_case_verdict, as `check` judges it:
 * worse beyond the relative tolerance plus 1e-12, now refused or failing,
 * or missing from NEW, is a regression), and the time
 * change, the ratio of the medians with the Mann-Whitney U test's p-value on
 * the two runs' repetition times (significant below 0.05).  The table is
 * sorted by effect: error regressions first, then the largest slow-downs
 * down to the largest speed-ups.  Exit 1 on a regression (a case of OLD
 * missing from NEW included) and, with --fail-slower PCT, when a time got
 * significantly slower by more than PCT%; 0 otherwise.
 */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench diff OLD NEW [--tolerance REL] [--fail-slower PCT] [-v]\n\n"
            "Compares two runs (run folders or their results.csv / results.json) case by\n"
            "case: the error change (worse beyond REL relative, default 0.001, plus 1e-12, is\n"
            "a regression, as is a case now refused, failing or missing from NEW: the rule\n"
            "of 'aabench check') and the time change (ratio of the medians; Mann-Whitney U on the\n"
            "repetition times, significant at p < 0.05). Sorted by effect.\n\n"
            "  --tolerance REL     relative tolerance on the errors (0 to 1)\n"
            "  --fail-slower PCT   also exit 1 when a time is significantly slower by more\n"
            "                      than PCT%%\n"
            "  -v, --verbose       also list the cases only in one run\n"
            "Exit status: 0 no regression, 1 a regression, 2 bad input, 3 input/output error.\n");
}

static int cmp_change(const void *a, const void *b)
{
    const aa_case_change *x = a, *y = b;
    int rx = x->regression != NULL, ry = y->regression != NULL;
    if (rx != ry)
        return ry - rx;
    double tx = isfinite(x->time_ratio) ? x->time_ratio : 1.0;
    double ty = isfinite(y->time_ratio) ? y->time_ratio : 1.0;
    return tx > ty ? -1 : tx < ty;
}

static void ms_text(const aa_row *r, char *buf, size_t len)
{
    if (!r->ok)
        snprintf(buf, len, "refused");
    else if (r->timing.n > 0 && isfinite(r->timing.ci_rel))
        snprintf(buf, len, "%.3f+-%.1f%%", r->seconds * 1e3, 100 * r->timing.ci_rel);
    else
        snprintf(buf, len, "%.3f", r->seconds * 1e3);
}

int cmd_diff(int argc, char **argv)
{
    enum { O_TOL = 256, O_SLOWER };
    static const struct option opts[] = {
        {"tolerance", required_argument, 0, O_TOL}, {"fail-slower", required_argument, 0, O_SLOWER},
        {"verbose", no_argument, 0, 'v'},         {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    double tol = 1e-3, slower = -1;
    int c, st = AA_OK, verbose = 0;
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":vh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, NULL)))
            return cli_fail("diff", st);
        switch (c) {
        case O_TOL: st = aa_parse_real("--tolerance", optarg, 0, 1, &tol); break;
        case O_SLOWER: st = aa_parse_real("--fail-slower", optarg, 0, 1e6, &slower); break;
        case 'v': verbose = 1; break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("diff", c, argv);
        }
        if (st)
            return cli_fail("diff", st);
    }
    if (argc - optind != 2) {
        fprintf(stderr, "aabench diff: two runs are needed, OLD and NEW\n");
        usage(stderr);
        return 2;
    }
    const char *old_path = argv[optind], *new_path = argv[optind + 1];
    aa_row *old = NULL, *now = NULL;
    size_t no = 0, nn = 0;
    if ((st = aa_results_load(old_path, &old, &no)) || (st = aa_results_load(new_path, &now, &nn))) {
        free(old);
        return cli_fail("diff", st);
    }
    aa_case_change *ch = calloc(no ? no : 1, sizeof *ch);
    int *matched = calloc(nn ? nn : 1, sizeof *matched);
    size_t n = 0, only_old = 0, missing = 0;
    if (!ch || !matched)
        st = aa_fail(AA_ENOMEM, "out of memory");
    for (size_t k = 0; k < no && !st; k++) {
        size_t q = 0;
        while (q < nn && (matched[q] || !aa_case_same(&old[k], &now[q])))
            q++;
        if (q == nn) {
            /* the gates' rule: a case missing from NEW fails */
            char detail[64];
            int confirmed;
            const char *why = aa_case_verdict(&old[k], NULL, tol, detail, sizeof detail,
                                              &confirmed);
            only_old++;
            missing += why != NULL;
            if (why)
                printf("REGRESSION %s on %s %dx%d %s: %s (%s in %s)\n", old[k].method,
                       old[k].pattern, old[k].w, old[k].h, old[k].filter, why, detail, old_path);
            continue;
        }
        matched[q] = 1;
        st = aa_case_compare(&old[k], &now[q], tol, &ch[n++]);
    }
    if (st) {
        free(ch);
        free(matched);
        free(old);
        free(now);
        return cli_fail("diff", st);
    }
    size_t only_new = 0;
    for (size_t q = 0; q < nn; q++)
        if (!matched[q]) {
            only_new++;
            if (verbose)
                printf("only in %s: %s on %s %dx%d %s\n", new_path, now[q].method, now[q].pattern,
                       now[q].w, now[q].h, now[q].filter);
        }
    qsort(ch, n, sizeof *ch, cmp_change);
    printf("%-30s %-18s %10s %9s %16s %16s %8s %8s  %s\n", "method", "view", "rmse", "change",
           "old ms", "new ms", "time", "p", "verdict");
    size_t worse = 0, slow = 0, fast = 0, gate = 0, untested = 0, noisy = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_case_change *x = &ch[k];
        const aa_row *o = x->old, *r = x->now;
        char view[64], om[32], nm[32], ratio[16] = "-", p[16] = "-", verdict[96];
        snprintf(view, sizeof view, "%.8s %dx%d %.6s", o->pattern, o->w, o->h, o->filter);
        ms_text(o, om, sizeof om);
        ms_text(r, nm, sizeof nm);
        if (isfinite(x->time_ratio))
            snprintf(ratio, sizeof ratio, "%+.1f%%", 100 * (x->time_ratio - 1));
        if (x->tested)
            snprintf(p, sizeof p, "%.2g", x->p);
        if (x->regression) {
            worse++;
            snprintf(verdict, sizeof verdict, "REGRESSION: %s", x->regression);
        } else if (!x->tested) {
            untested += isfinite(x->time_ratio);
            snprintf(verdict, sizeof verdict, "%s", isfinite(x->time_ratio)
                                                        ? "time not tested (no repetition times)"
                                                        : "-");
        } else if (x->significant && x->time_ratio > 1) {
            slow++;
            int fails = slower >= 0 && 100 * (x->time_ratio - 1) > slower;
            gate += fails;
            snprintf(verdict, sizeof verdict, "slower%s", fails ? " (beyond --fail-slower)" : "");
        } else if (x->significant && x->time_ratio < 1) {
            fast++;
            snprintf(verdict, sizeof verdict, "faster");
        } else {
            snprintf(verdict, sizeof verdict, "no significant change");
        }
        if (x->noisy) {
            noisy++;
            size_t used = strlen(verdict);
            snprintf(verdict + used, sizeof verdict - used, ", noisy");
        }
        char rc[24] = "-";
        if (isfinite(x->rmse_change))
            snprintf(rc, sizeof rc, x->rmse_change ? "%+.2g%%" : "0", 100 * x->rmse_change);
        printf("%-30.30s %-18.18s %10.3e %9s %16s %16s %8s %8s  %s\n", o->method, view,
               r->ok ? r->m.rmse : o->m.rmse, rc, om, nm, ratio, p, verdict);
    }
    worse += missing;
    printf("diff: %zu cases compared (%zu only in OLD, %zu only in NEW): %zu "
           "regression%s; time: %zu significantly slower, %zu faster (Mann-Whitney U, p < %g), "
           "%zu not tested; %zu noisy\n",
           n, only_old, only_new, worse, worse == 1 ? "" : "s", slow, fast, AA_TIME_ALPHA,
           untested, noisy);
    free(ch);
    free(matched);
    free(old);
    free(now);
    if (worse || gate) {
        if (gate)
            printf("diff: %zu case%s significantly slower by more than %g%%\n", gate,
                   gate == 1 ? "" : "s", slower);
        return 1;
    }
    return 0;
}
