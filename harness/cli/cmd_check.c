/*
 * cmd_check.c: `aabench check`: the regression gate.
 *
 * Reruns every case of the baseline (results/baseline.csv, made by
 * `aabench run --suite quick`, or any results.csv) and compares each
 * method's error with its baseline row: a case fails when its RMSE or its
 * maximum error exceeds the baseline's by more than the relative tolerance
 * (default 0.1%, plus 1e-12 absolute), when a method of the baseline no
 * longer exists, when it now refuses or fails a case it ran, or runs a case
 * the baseline records as refused (ok = 0: the refusal is confirmed, never
 * counted as within).  Render time is reported, not gated: each case is
 * timed by precision (as `run` does) and its change against the baseline's
 * repetition times is tested as `diff` does (Mann-Whitney U); --fail-slower
 * PCT makes a significant slow-down by more than PCT% fail too.  Methods from plug-ins are checked the same way
 * (--plugin, with a baseline of theirs), each case in a child process of its
 * own (--no-isolate to turn that off), so that a crash or a hang is a failed
 * case.  The baseline is read strictly (aa_rows_read_csv) and every view is
 * checked before any is run: a bad baseline is refused (exit 2), never
 * half-checked, and so is one made from input files (an SVG, a font) that
 * have changed since (its `inputs` column, aa_inputs_check).
 */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_TOLERANCE 1e-3

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench check [--baseline FILE] [--tolerance REL] [--plugin LIB.so]...\n\n"
            "Reruns the cases of the baseline (default results/baseline.csv, made by\n"
            "'aabench run --suite quick') and exits 1, naming each offender, when a method's\n"
            "RMSE or maximum error exceeds its baseline by more than REL relative (default\n"
            "0.001, i.e. 0.1%%) plus 1e-12, a baseline method is missing, now refused or\n"
            "failing, or runs a case the baseline records as refused.\n\n"
            "  --baseline FILE    the baseline CSV\n"
            "  --tolerance REL    relative tolerance on the errors (0 to 1)\n"
            "  --plugin LIB.so    load methods from a shared library (repeatable)\n"
            "  --threads N        threads (the results do not depend on it)\n"
            "  --cache DIR        reference cache; --no-cache\n"
            "  -v, --verbose      also print the cases that pass, and every time change\n"
            "  --fail-slower PCT  also fail a case significantly slower than its baseline by\n"
            "                     more than PCT%% (time is otherwise only reported)\n"
            "  --target-ci PCT, --budget S, --reps N   timing, as for 'aabench run'\n"
            "  --isolate          run every case in a child process (default: the methods\n"
            "                     of plug-ins); --no-isolate: none\n"
            "  --case-timeout S   an isolated case taking more than S seconds fails (600)\n"
            "\nExit status: 0 every case within, 1 a case failed, 2 bad input (a baseline\n"
            "that cannot be trusted included), 3 input/output error.\n");
}

static int same_view(const aa_row *a, const aa_row *b)
{
    return !strcmp(a->pattern, b->pattern) && !strcmp(a->filter, b->filter) && a->w == b->w &&
           a->h == b->h && a->t == b->t && a->vx == b->vx && a->vy == b->vy && a->seed == b->seed;
}

/* The baseline's cases on one view: its methods that exist (parsed), and
 * their rows. */
typedef struct view {
    size_t first;      /* the view's first row */
    size_t at, nm;     /* its methods: methods[at .. at + nm), rows which[...] */
    aa_run_spec pattern;
    aa_run_filter filter;
    aa_run_size wh;
} view;

/* Time changes against the baseline: reported; gated with --fail-slower. */
typedef struct time_report {
    aa_timing_plan plan;
    double slower; /* < 0: not gated */
    size_t slow, fast, same, untested, noisy, gate;
} time_report;

static int time_change(time_report *t, const aa_row *b, const aa_row *r, int verbose)
{
    aa_case_change c;
    int st = aa_case_compare(b, r, 0, &c);
    if (st || !r->ok)
        return st;
    t->noisy += c.noisy;
    if (!c.tested) {
        t->untested++;
        return AA_OK;
    }
    int slow = c.significant && c.time_ratio > 1, fast = c.significant && c.time_ratio < 1;
    int fails = slow && t->slower >= 0 && 100 * (c.time_ratio - 1) > t->slower;
    t->slow += slow, t->fast += fast, t->same += !slow && !fast, t->gate += fails;
    if (fails || verbose || (slow && t->slower < 0))
        printf("%s %s on %s %dx%d %s: time %+.1f%% (median %.4g ms, baseline %.4g ms; p = %.2g)%s\n",
               fails ? "FAIL" : "time", b->method, b->pattern, b->w, b->h, b->filter,
               100 * (c.time_ratio - 1), r->seconds * 1e3, b->seconds * 1e3, c.p,
               c.noisy ? ", noisy" : "");
    return AA_OK;
}

static void time_summary(const time_report *t)
{
    printf("check: time %s: %zu significantly slower, %zu faster, %zu unchanged (Mann-Whitney U, "
           "p < %g); %zu not tested (the baseline has no repetition times); %zu noisy\n",
           t->slower >= 0 ? "(gated by --fail-slower)" : "(informational)", t->slow, t->fast,
           t->same, AA_TIME_ALPHA, t->untested, t->noisy);
}

int cmd_check(int argc, char **argv)
{
    enum { O_BASELINE = 256, O_TOL, O_PLUGIN, O_CACHE, O_NOCACHE,
           O_ISOLATE, O_NOISOLATE, O_CASE_TIMEOUT, O_SLOWER, O_TARGET, O_BUDGET, O_REPS };
    static const struct option opts[] = {
        {"baseline", required_argument, 0, O_BASELINE}, {"tolerance", required_argument, 0, O_TOL},
        {"plugin", required_argument, 0, O_PLUGIN},   CLI_OPTION_THREADS,
        {"cache", required_argument, 0, O_CACHE},     {"no-cache", no_argument, 0, O_NOCACHE},
        {"verbose", no_argument, 0, 'v'},             {"help", no_argument, 0, 'h'},
        {"isolate", no_argument, 0, O_ISOLATE},
        {"no-isolate", no_argument, 0, O_NOISOLATE},
        {"case-timeout", required_argument, 0, O_CASE_TIMEOUT},
        {"fail-slower", required_argument, 0, O_SLOWER},
        {"target-ci", required_argument, 0, O_TARGET},
        {"budget", required_argument, 0, O_BUDGET},
        {"reps", required_argument, 0, O_REPS},
        {0, 0, 0, 0}};
    const char *baseline = "results/baseline.csv", *cache = cli_cache_dir();
    double tol = DEFAULT_TOLERANCE, timeout = AA_CASE_TIMEOUT;
    int c, st = AA_OK, threads = 0, verbose = 0, isolate = AA_ISOLATE_PLUGINS;
    time_report times = {.slower = -1};
    cli_getopt_reset();
    aa_options_seen seen = {0};
    while ((c = getopt_long(argc, argv, ":vh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, (const int[]){O_PLUGIN, 0})))
            return cli_fail("check", st);
        switch (c) {
        case O_BASELINE: baseline = optarg; break;
        case O_TOL: st = aa_parse_real("--tolerance", optarg, 0, 1, &tol); break;
        case O_PLUGIN: st = aa_plugin_load(optarg); break;
        case O_CACHE: cache = optarg; break;
        case O_NOCACHE: cache = ""; break;
        case 'v': verbose = 1; break;
        case O_ISOLATE: isolate = AA_ISOLATE_ALL; break;
        case O_NOISOLATE: isolate = AA_ISOLATE_NONE; break;
        case O_CASE_TIMEOUT:
            st = aa_parse_real("--case-timeout", optarg, 0.001, 1e9, &timeout);
            break;
        case O_SLOWER: st = aa_parse_real("--fail-slower", optarg, 0, 1e6, &times.slower); break;
        case O_TARGET: st = aa_parse_target(optarg, &times.plan.target_ci); break;
        case O_BUDGET: st = aa_parse_budget(optarg, &times.plan.budget); break;
        case O_REPS: st = aa_parse_int("--reps", optarg, 1, 1000, &times.plan.reps); break;
        case CLI_O_THREADS: st = cli_out_threads(c, optarg, NULL, &threads); break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("check", c, argv);
        }
        if (st)
            return cli_fail("check", st);
    }
    if (optind < argc) {
        fprintf(stderr, "aabench check: unexpected argument \"%s\"\n", aa_echo(argv[optind]));
        return 2;
    }
    if (*cache && (st = aa_folder_check("--cache", cache, 64)))
        return cli_fail("check", st);
    cli_cache_usable("check", cache);
    aa_row *base = NULL;
    size_t nb = 0;
    if ((st = aa_rows_read_csv(baseline, &base, &nb)))
        return cli_fail("check", st);
    if (nb == 0) {
        free(base);
        fprintf(stderr, "aabench check: %s holds no cases\n", aa_echo(baseline));
        return 2;
    }
    if (threads <= 0)
        threads = aa_default_threads();
    int *done = calloc(nb, sizeof *done);
    aa_run_spec *methods = malloc(nb * sizeof *methods);
    size_t *which = malloc(nb * sizeof *which);
    view *views = malloc(nb * sizeof *views);
    size_t offenders = 0, checked = 0, confirmed = 0, nv = 0, nm = 0;
    if (!done || !methods || !which || !views)
        st = aa_fail(AA_ENOMEM, "out of memory for %zu cases", nb);
    /* every view and method parsed, and every view checked, before any work */
    for (size_t k = 0; k < nb && !st; k++) {
        if (done[k])
            continue;
        view *v = &views[nv];
        v->first = k, v->at = nm, v->nm = 0;
        /* the baseline's methods on this view that still exist */
        for (size_t q = k; q < nb; q++) {
            if (done[q] || !same_view(&base[k], &base[q]))
                continue;
            done[q] = 1;
            methods[nm].text = base[q].method;
            if (aa_spec_parse(base[q].method, aa_method_table(), "method", &methods[nm].spec)) {
                char name[128];
                snprintf(name, sizeof name, "%.*s", (int)strcspn(base[q].method, ":"),
                         base[q].method);
                if (!aa_table_find(aa_method_table(), name))
                    printf("FAIL %s on %s %dx%d %s: no method \"%s\" is built in or loaded; if "
                           "a plug-in defines it, load it with --plugin LIB.so\n",
                           base[q].method, base[q].pattern, base[q].w, base[q].h, base[q].filter,
                           name);
                else
                    printf("FAIL %s on %s %dx%d %s: %s\n", base[q].method, base[q].pattern,
                           base[q].w, base[q].h, base[q].filter, aa_last_error());
                offenders++;
                continue;
            }
            which[nm++] = q;
            v->nm++;
        }
        if (v->nm == 0)
            continue;
        /* the view, parsed once for all its methods (the reader checked it
         * parses) */
        v->pattern = (aa_run_spec){.text = base[k].pattern};
        v->filter = (aa_run_filter){.text = base[k].filter};
        v->wh = (aa_run_size){base[k].w, base[k].h};
        if ((st = aa_pattern_parse(base[k].pattern, &v->pattern.spec)) ||
            (st = aa_filter_parse(base[k].filter, &v->filter.filter)))
            break;
        /* a pattern read from files: the files the baseline was made from */
        for (size_t q = 0; q < v->nm && !st; q++)
            st = aa_inputs_check(baseline, &base[which[v->at + q]]);
        if (st)
            break;
        nv++;
    }
    aa_run_config *cfgs = st ? NULL : calloc(nv ? nv : 1, sizeof *cfgs);
    if (!st && !cfgs)
        st = aa_fail(AA_ENOMEM, "out of memory for %zu views", nv);
    for (size_t i = 0; i < nv && !st; i++) {
        const view *v = &views[i];
        const aa_row *b = &base[v->first];
        aa_run_config *cfg = &cfgs[i];
        cfg->patterns = &v->pattern, cfg->npatterns = 1;
        cfg->sizes = &v->wh, cfg->nsizes = 1;
        cfg->filters = &v->filter, cfg->nfilters = 1;
        cfg->methods = methods + v->at, cfg->nmethods = v->nm;
        cfg->reps = times.plan.reps, cfg->target_ci = times.plan.target_ci;
        cfg->budget = times.plan.budget;
        cfg->threads = threads, cfg->seed = b->seed;
        cfg->t = b->t, cfg->vx = b->vx, cfg->vy = b->vy;
        cfg->cache_dir = *cache ? cache : NULL;
        cfg->enc.kind = AA_ENCODE_SRGB;
        cfg->isolate = isolate;
        cfg->case_timeout = timeout;
        if ((st = aa_run_check(cfg)))
            st = aa_fail_context(st, "%s: the case %s on %s %dx%d %s", aa_echo(baseline),
                                 aa_echo(b->method), aa_echo(b->pattern), b->w, b->h,
                                 aa_echo(b->filter));
    }
    for (size_t i = 0; i < nv && !st; i++) {
        const view *v = &views[i];
        char size[32];
        snprintf(size, sizeof size, "%dx%d", v->wh.w, v->wh.h);
        aa_row *now = NULL;
        size_t nn = 0;
        if ((st = aa_run(&cfgs[i], &now, &nn))) {
            free(now);
            break;
        }
        for (size_t m = 0; m < nn; m++) {
            const aa_row *b = &base[which[v->at + m]], *r = &now[m];
            char detail[1200];
            int ok_refused;
            checked++;
            const char *why = aa_case_verdict(b, r, tol, detail, sizeof detail, &ok_refused);
            if (!why && !ok_refused && (st = time_change(&times, b, r, verbose)))
                break;
            if (why) {
                printf("FAIL %s on %s %s %s: %s: %s\n", b->method, b->pattern, size, b->filter, why,
                       detail);
                offenders++;
            } else if (ok_refused) {
                confirmed++;
                if (verbose)
                    printf("ok   %s on %s %s %s: refused, as the baseline records (%s)\n",
                           b->method, b->pattern, size, b->filter, r->note);
            } else if (verbose) {
                printf("ok   %s on %s %s %s: rmse %.9g (baseline %.9g)\n", b->method, b->pattern,
                       size, b->filter, r->m.rmse, b->m.rmse);
            }
        }
        free(now);
    }
    free(cfgs);
    free(done);
    free(methods);
    free(which);
    free(views);
    free(base);
    if (st)
        return cli_fail("check", st);
    time_summary(&times);
    offenders += times.gate;
    if (offenders) {
        printf("check: %zu of %zu cases failed against %s (tolerance %g relative)\n", offenders,
               nb, baseline, tol);
        return 1;
    }
    printf("check: %zu cases within %g of %s", checked - confirmed, tol, baseline);
    if (confirmed)
        printf(", %zu refusal%s confirmed", confirmed, confirmed == 1 ? "" : "s");
    printf("\n");
    return 0;
}
