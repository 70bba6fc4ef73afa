/*
 * cmd_run.c: `aabench run`: the benchmark's main job, a thin client of the
 * library's run folder (harness/bench/runfolder.h).
 *
 * Reads the options (aa_plan_parse: the plan and the run's options), makes
 * or opens (--resume) the run folder, runs it and finishes it; what is its
 * own: the usage, the signal handlers (the first SIGINT, SIGTERM or SIGHUP
 * stops after the case under way, through the library's interrupt hook; a second
 * quits at once), the progress bar on standard error (a terminal, CI
 * unset), the check that a resumed command is the run's, and the table at
 * the end sorted by error, with the failed cases named.  `merge` prints its
 * merged run with the same report (cli_run_report).
 */
#include "cli.h"

#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static volatile sig_atomic_t interrupted;

/* The first interrupt stops after the current case, with every file
 * complete; a second one quits at once. */
static void on_signal(int sig)
{
    static const char msg[] = "\naabench run: stopping after this case (again to quit now)\n";
    if (interrupted) {
        aa_temp_cleanup(); /* the files being written: none is left half-written */
        _exit(130);
    }
    interrupted = sig;
    ssize_t w = write(2, msg, sizeof msg - 1);
    (void)w;
}

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench run [--suite NAME] [-p PATTERN]... [-m METHOD]... [-s WxH]...\n"
            "                   [-f FILTER]... [--reps N] [--out DIR] [options]\n\n"
            "Runs every method on every pattern x size x filter, measures error against the\n"
            "exact reference and render time, and writes results.csv, results.json, images/,\n"
            "montage.png and plots/ into results/runs/<UTC time>/ (results/latest links to it)\n"
            "or DIR.  -p, -m, -s, -f may be repeated; given, they replace the suite's lists\n"
            "(an svg pattern given without -s is measured at its own size).\n"
            "A method runs only with the filters and scenes it takes (one line counts the\n"
            "pairs left out) unless -m and -f are both given.\n\n"
            "  --suite NAME      quick, default (the default), paper, full, vector, strokes\n"
            "                    or temporal\n"
            "                    (--list-suites)\n"
            "  --target-ci PCT   time each case until the 95%% CI of its median is within\n"
            "                    PCT%% of it (default 2), after one untimed warm-up render\n"
            "  --budget S        or until S seconds of renders have passed (default 1);\n"
            "                    at least 5 renders either way\n"
            "  --reps N          exactly N timed renders instead (overrides both)\n"
            "  --seeds N         stochastic methods: the error over N seeds, mean and 95%% CI\n"
            "  --out DIR         output folder\n"
            "  --threads N       threads (default: all cores)\n"
            "  --seed N          seed of the random streams (default 1)\n"
            "  --time T          time in frames (default 0)\n"
            "  --motion VX,VY    motion in pixels per frame (default 0,0; the temporal\n"
            "                    suite's own: 0.37,0.11)\n"
            "  --frames N        animated runs: frames the temporal metrics are taken over,\n"
            "                    at times T, T+1, ... (default 24)\n"
            "  --window W        animated runs: frames the eye integrates (default 6)\n"
            "  --encode E        display encoding of PNGs and of the *_enc metrics: srgb\n"
            "                    (default), linear or gamma:G (gamma:2 is Crow's square law)\n"
            "  --plugin LIB.so   load methods from a shared library (repeatable)\n"
            "  --images WHICH    which views' images/ and montages to write: small (the\n"
            "                    default: sizes up to 512x512 and the run's smallest),\n"
            "                    all, or none\n"
            "  --no-images       --images none\n"
            "  --no-plots        do not draw plots/ (no convergence either)\n"
            "  --cache DIR       reference cache (default $AABENCH_CACHE, else\n"
            "                    results/cache in the source tree, else\n"
            "                    $XDG_CACHE_HOME/aabench); --no-cache\n"
            "  --list-suites     list the suites and exit\n"
            "  -q, --quiet       no table at the end\n"
            "  --isolate         run every case in a child process of its own (the default\n"
            "                    for methods from plug-ins): a crash or a hang is a failed\n"
            "                    case, and the run goes on\n"
            "  --no-isolate      run every case in this process\n"
            "  --case-timeout S  an isolated case taking more than S seconds fails (default\n"
            "                    600)\n"
            "  --shard K/N       run only the K-th of N parts of the cases (1 <= K <= N),\n"
            "                    balanced by estimated cost; 'aabench merge' joins the\n"
            "                    parts' folders into the whole run's results\n"
            "  --resume DIR      continue the run in DIR (interrupted, or a failed shard)\n"
            "                    with its own command and commit: the cases in its\n"
            "                    results are kept, the rest measured\n"
            "\nA case whose method gives an error, a value outside [0, 1] or not finite,\n"
            "crashes or times out is a failed case (ok=0 in results.csv, the reason in its\n"
            "note); the run goes on.  results.csv and results.json are rewritten after every\n"
            "case.\n"
            "Exit status: 0 done, 1 some cases failed, 2 bad input, 3 input/output error,\n"
            "130 interrupted.\n");
}

/* ---- the library's hooks: a progress bar, the interrupt flag, notes ---- */

typedef struct bar {
    int show;
    double t0;
} bar;

static void progress(void *vbar, size_t done, size_t total, const char *what)
{
    const bar *b = vbar;
    if (!b->show)
        return;
    const int width = 30;
    int fill = total ? (int)(width * done / total) : width;
    double el = aa_now() - b->t0;
    fprintf(stderr, "\r\033[K[%.*s%*s] %zu/%zu %5.0fs %.60s", fill,
            "==============================", width - fill, "", done, total, el, what);
    if (done == total)
        fprintf(stderr, "\n");
    fflush(stderr);
}

static int stop_asked(void *vbar)
{
    (void)vbar;
    return interrupted != 0;
}

void cli_run_note(void *hook, const char *message)
{
    (void)hook;
    fprintf(stderr, "aabench run: %s\n", message);
}

/* ---- the table ---- */

/* A name column's width: `least`, cut there, or wider where two different
 * names would be cut to the same text (crow:curves=8 and crow:curves=9 at
 * 10): one past their longest common start.  Sorted, the longest common
 * start of any two is that of two neighbours. */
typedef const char *(*row_name)(const aa_row *);
static const char *pattern_of(const aa_row *r) { return r->pattern; }
static const char *method_of(const aa_row *r) { return r->method; }
static const char *filter_of(const aa_row *r) { return r->filter; }

static int by_text(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static int name_width(const aa_row *const *order, size_t n, row_name name, int least)
{
    const char **v = malloc((n ? n : 1) * sizeof *v);
    size_t width = (size_t)least;
    if (!v)
        return 255; /* never cut */
    for (size_t k = 0; k < n; k++)
        v[k] = name(order[k]);
    qsort(v, n, sizeof *v, by_text);
    for (size_t k = 1; k < n; k++) {
        size_t c = 0;
        while (v[k - 1][c] && v[k - 1][c] == v[k][c])
            c++;
        if (v[k - 1][c] != v[k][c] && c + 1 > width)
            width = c + 1;
    }
    free(v);
    return width > 255 ? 255 : (int)width;
}

typedef struct widths {
    int method, pattern, filter;
} widths;

static widths widths_of(const aa_row *const *order, size_t n)
{
    widths w = {name_width(order, n, method_of, 30), name_width(order, n, pattern_of, 10),
                name_width(order, n, filter_of, 10)};
    return w;
}

static int cmp_rmse(const void *a, const void *b)
{
    const aa_row *x = *(const aa_row *const *)a, *y = *(const aa_row *const *)b;
    if (x->ok != y->ok)
        return y->ok - x->ok;
    return x->m.rmse < y->m.rmse ? -1 : x->m.rmse > y->m.rmse;
}

/* Animated runs: by pattern, then by the eye's error. */
static int cmp_eye(const void *a, const void *b)
{
    const aa_row *x = *(const aa_row *const *)a, *y = *(const aa_row *const *)b;
    int c = strcmp(x->pattern, y->pattern);
    if (c)
        return c;
    if (x->temporal != y->temporal)
        return y->temporal - x->temporal;
    if (!x->temporal)
        return cmp_rmse(a, b);
    return x->tm.eye_rmse < y->tm.eye_rmse ? -1 : x->tm.eye_rmse > y->tm.eye_rmse;
}

/* The temporal columns, and after the table the offsets the eye prefers:
 * per pattern, the method of least eye_rmse among those that sample points
 * in frames (temporal methods and point-sampled ones; area, exact, is the
 * floor), and the least flicker. */
static void print_temporal(const aa_row **order, size_t n)
{
    widths c = widths_of(order, n);
    printf("%-*s %-*s %-9s %10s %10s %10s %10s %8s %6s %6s\n", c.method, "method", c.pattern,
           "pattern", "size", "rmse", "eye_rmse", "flicker", "flick_max", "conserv", "lag",
           "pop");
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        char size[32];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        if (!r->ok || !r->temporal) {
            printf("%-*.*s %-*.*s %-9s %s\n", c.method, c.method, r->method, c.pattern,
                   c.pattern, r->pattern, size, r->note);
            continue;
        }
        printf("%-*.*s %-*.*s %-9s %10.3e %10.3e %10.3e %10.3e %8.2e %6.2f", c.method,
               c.method, r->method, c.pattern, c.pattern, r->pattern, size, r->m.rmse,
               r->tm.eye_rmse, r->tm.flicker_mean, r->tm.flicker_max, r->tm.conservation,
               r->tm.lag);
        if (isfinite(r->tm.popping))
            printf(" %6.3f", r->tm.popping);
        printf("\n");
    }
    printf("\nthe eye's preference (least eye_rmse; least mean flicker), area excluded:\n");
    for (size_t k = 0; k < n; k++) {
        if (k && !strcmp(order[k]->pattern, order[k - 1]->pattern))
            continue;
        const aa_row *best = NULL, *calm = NULL;
        for (size_t q = k; q < n && !strcmp(order[q]->pattern, order[k]->pattern); q++) {
            const aa_row *r = order[q];
            if (!r->ok || !r->temporal || !strncmp(r->method, "area", 4))
                continue;
            if (!best || r->tm.eye_rmse < best->tm.eye_rmse)
                best = r;
            if (!calm || r->tm.flicker_mean < calm->tm.flicker_mean)
                calm = r;
        }
        if (best)
            printf("  %-*.*s %s (eye_rmse %.3e); %s (flicker %.3e)\n", c.pattern, c.pattern,
                   order[k]->pattern, best->method, best->tm.eye_rmse, calm->method,
                   calm->tm.flicker_mean);
    }
}

/* --seeds N: the stochastic methods' mean RMSE over the seeds. */
static void print_seeds(const aa_row **order, size_t n)
{
    widths c = widths_of(order, n);
    int header = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        if (!r->ok || r->seeds < 2)
            continue;
        if (!header++)
            printf("\nover %d seeds (stochastic methods): mean RMSE and its 95%% CI\n", r->seeds);
        printf("  %-*.*s %-*.*s %4dx%-5d %-*.*s %.4e [%.4e, %.4e]\n", c.method, c.method,
               r->method, c.pattern, c.pattern, r->pattern, r->w, r->h, c.filter, c.filter,
               r->filter, r->rmse_mean, r->rmse_ci_lo, r->rmse_ci_hi);
    }
}

static void print_table(const aa_row *rows, size_t n)
{
    const aa_row **order = malloc(n * sizeof *order);
    if (!order)
        return;
    for (size_t k = 0; k < n; k++)
        order[k] = &rows[k];
    int temporal = 0;
    for (size_t k = 0; k < n; k++)
        temporal |= rows[k].temporal;
    qsort(order, n, sizeof *order, temporal ? cmp_eye : cmp_rmse);
    widths c = widths_of(order, n);
    printf("%-*s %-*s %-12s %-*s %10s %9s %9s %9s %6s %8s %-27s %3s %9s %9s %9s %6s\n",
           c.method, "method", c.pattern, "pattern", "size", c.filter, "filter", "rmse",
           "edge_rmse", "max_err", "ref_bound", "flip", "psnr", "ms, median +-CI", "thr",
           "cpu ms", "init ms", "ns/px", "exp%");
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        char size[32];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        if (!r->ok) {
            printf("%-*.*s %-*.*s %-12s %-*.*s %s\n", c.method, c.method, r->method, c.pattern,
                   c.pattern, r->pattern, size, c.filter, c.filter, r->filter, r->note);
            continue;
        }
        char ms[64];
        cli_time_text(r, ms, sizeof ms);
        char cpu[32] = "-"; /* the median render's CPU time, the threads' sum */
        if (r->timing.n > 0 && isfinite(r->timing.cpu_median))
            snprintf(cpu, sizeof cpu, "%.3f", r->timing.cpu_median * 1e3);
        char init[32] = "-"; /* the method's init, once, outside the renders' times */
        if (isfinite(r->timing.init_seconds))
            snprintf(init, sizeof init, "%.3f", r->timing.init_seconds * 1e3);
        /* the reference's largest per-pixel bound: errors below it are not measured;
         * "~" marks one with pixels bounded by an estimate (cli_warn_references) */
        char bound[32] = "-";
        if (isfinite(r->ref_bound))
            snprintf(bound, sizeof bound, "%s%.2e", r->ref_scanned > 0 ? "~" : "",
                     r->ref_bound);
        printf("%-*.*s %-*.*s %-12s %-*.*s %10.3e %9.2e %9.2e %9s %6.4f %8.2f %-27s %3d %9s "
               "%9s %9.2f %6.1f\n",
               c.method, c.method, r->method, c.pattern, c.pattern, r->pattern, size, c.filter,
               c.filter, r->filter, r->m.rmse, r->m.edge_rmse, r->m.max_err, bound, r->m.flip,
               r->m.psnr, ms, r->threads, cpu, init, r->ns_per_pixel,
               100 * r->expensive_fraction);
    }
    if (temporal) {
        printf("\n");
        print_temporal(order, n);
    }
    print_seeds(order, n);
    free(order);
}

/* The failed cases, each on a line of its own and then all named in one,
 * on standard error: exit status 1 if any. */
static int report_failed(const aa_row *rows, size_t n)
{
    size_t failed = 0;
    for (size_t k = 0; k < n; k++) {
        if (!rows[k].failed)
            continue;
        failed++;
        const char *why = rows[k].note;
        if (!strncmp(why, "failed: ", 8))
            why += 8;
        fprintf(stderr, "aabench run: FAILED %s on %s %dx%d %s: %s\n", rows[k].method,
                rows[k].pattern, rows[k].w, rows[k].h, rows[k].filter, why);
    }
    if (!failed)
        return 0;
    fprintf(stderr, "aabench run: %zu of %zu case%s failed:", failed, n, n == 1 ? "" : "s");
    for (size_t k = 0, seen = 0; k < n; k++)
        if (rows[k].failed)
            fprintf(stderr, "%s %s on %s %dx%d %s", seen++ ? ";" : "", rows[k].method,
                    rows[k].pattern, rows[k].w, rows[k].h, rows[k].filter);
    fprintf(stderr, "\n");
    return 1;
}

/* After the cases: the table, the warnings; the exit status. */
int cli_run_report(aa_runfolder *rf, int quiet, int st)
{
    size_t nall;
    const aa_row *all = aa_runfolder_rows(rf, &nall);
    const char *dir = aa_runfolder_dir(rf);
    int shard, shards;
    aa_runfolder_shard(rf, &shard, &shards);
    if (interrupted) {
        fprintf(stderr, "\naabench run: interrupted; %zu result%s kept in %s (aabench run "
                        "--resume %s goes on)\n",
                nall, nall == 1 ? "" : "s", dir, dir);
        return 130;
    }
    if (st) {
        if (nall)
            fprintf(stderr, "aabench run: %zu result%s kept in %s/results.csv\n", nall,
                    nall == 1 ? "" : "s", dir);
        return cli_fail("run", st);
    }
    size_t skipped = aa_runfolder_refused(rf);
    if (skipped)
        printf("skipped %zu method and view pair%s the method refuses (a filter or a scene; "
               "name the method and the filter to run them)\n",
               skipped, skipped == 1 ? "" : "s");
    if (!quiet)
        print_table(all, nall);
    cli_warn_noisy("run", all, nall);
    cli_warn_references("run", all, nall);
    cli_warn_parallelism("run", all, nall);
    printf("results: %s/results.csv%s\n", dir, aa_runfolder_linked(rf) ? " (results/latest)" : "");
    /* the sizes whose views have no images (--images small) */
    long most = aa_runfolder_images_max(rf);
    char sizes[256] = "";
    size_t used = 0, large = 0;
    for (size_t k = 0; most && k < nall; k++) {
        size_t q = 0;
        while (q < k && !(all[q].w == all[k].w && all[q].h == all[k].h))
            q++;
        if (q < k || (long)all[k].w * all[k].h <= most)
            continue;
        if (used < sizeof sizes) {
            int c = snprintf(sizes + used, sizeof sizes - used, "%s%dx%d", large ? ", " : "",
                             all[k].w, all[k].h);
            used += c > 0 ? (size_t)c : 0;
        }
        large++;
    }
    if (large)
        printf("images: none of the views at %s, over %ld pixels (--images all writes "
               "them)\n",
               sizes, most);
    if (shards > 1)
        printf("shard %d/%d: %zu case%s; join the shards with aabench merge DIR... --out DIR\n",
               shard, shards, nall, nall == 1 ? "" : "s");
    return report_failed(all, nall);
}

/* The arguments of argv[1..] that a manifest keeps, joined by spaces. */
static void joined(int argc, char *const *argv, int skip, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; k < argc && n + 1 < len; k++) {
        int value;
        if (skip && aa_manifest_skips(argv[k], &value)) {
            k += value;
            continue;
        }
        n += (size_t)snprintf(buf + n, len - n, "%s%s", n ? " " : "", aa_echo(argv[k]));
    }
    if (n >= len && len > 4)
        memcpy(buf + len - 4, "...", 4);
}

/* --resume DIR: the run in DIR goes on with its own command (given again,
 * it must be the same) and only with the commit it was measured at. */
static int resume_check(const char *dir, int argc, char **argv)
{
    aa_manifest m;
    char path[4200], given[2048], recorded[2048];
    int st = aa_pathf(path, sizeof path, "%s/run.json", dir);
    if (!st && (st = aa_manifest_read(path, &m)) == AA_EIO) {
        fprintf(stderr, "aabench run: --resume %s: not a run folder (%s)\n", aa_echo(dir),
                aa_last_error());
        return 2;
    }
    if (st)
        return cli_fail("run", st == AA_EIO ? AA_EINVAL : st);
    joined(argc - 1, argv + 1, 1, given, sizeof given);
    joined(m.argc, m.argv, 0, recorded, sizeof recorded);
    int other = 0;
    for (int k = 1; k < argc; k++) {
        int value;
        if (aa_manifest_skips(argv[k], &value))
            k += value;
        else
            other = 1;
    }
    int code = -1;
    if (other && strcmp(given, recorded)) {
        fprintf(stderr, "aabench run: --resume %s: the command differs from the run's: it was "
                        "\"%s\", now \"%s\" (give no options to take the run's own)\n",
                aa_echo(dir), recorded, given);
        code = 2;
    } else if (aa_manifest_same_commit(&m)) {
        fprintf(stderr, "aabench run: --resume %s: %s\n", aa_echo(dir), aa_last_error());
        code = 2;
    }
    aa_manifest_free(&m);
    return code;
}

/* Without -f, the filters the run takes are its suite's: say which, once,
 * each named once. */
static void say_filters(const aa_plan *plan)
{
    const aa_suite *suite = aa_suite_find(plan->suite ? plan->suite : "default");
    if (plan->nfilters || !suite)
        return;
    const char *seen[64];
    size_t n = 0;
    for (const aa_suite_group *g = suite->groups; g->patterns; g++)
        for (const char *const *f = g->filters; f && *f && n < 64; f++) {
            size_t k = 0;
            while (k < n && strcmp(seen[k], *f))
                k++;
            if (k == n)
                seen[n++] = *f;
        }
    if (!n)
        return;
    fprintf(stderr, "aabench run: no -f given: the filters of suite %s,", suite->name);
    for (size_t k = 0; k < n; k++)
        fprintf(stderr, "%s %s", k ? "," : "", seen[k]);
    fprintf(stderr, " (-f FILTER to choose)\n");
}

int cmd_run(int argc, char **argv)
{
    aa_plan plan;
    aa_run_options opt;
    int asked, st, code;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    opt.cache = cli_cache_dir();
    if ((st = aa_plan_parse(argc, argv, &plan, &opt, &asked)))
        return asked == '?' ? cli_bad_usage("run", st) : cli_fail("run", st);
    if (asked == 'h') {
        usage(stdout);
        return 0;
    }
    if (asked == 'l') {
        for (const aa_suite *s = aa_suites; s->name; s++)
            printf("%s\t%s\n", s->name, s->summary);
        return 0;
    }
    if (opt.resume && (code = resume_check(opt.resume, argc, argv)) >= 0)
        return code;
    if (!opt.resume)
        say_filters(&plan);
    bar b = {cli_progress_wanted(), aa_now()};
    cli_command_line(&opt.argc, &opt.argv);
    opt.progress = progress, opt.interrupted = stop_asked, opt.note = cli_run_note;
    opt.hook = &b;
    /* SIGINT, SIGTERM and SIGHUP (the terminal closed) alike: the run
     * stops after the case under way, its rows kept */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    aa_runfolder *rf;
    st = opt.resume ? aa_runfolder_open(opt.resume, &opt, &rf)
                    : aa_runfolder_create(&plan, &opt, &rf);
    if (st)
        return cli_fail("run", st);
    cli_cache_usable("run", opt.cache);
    size_t kept = aa_runfolder_kept(rf);
    if (kept)
        fprintf(stderr, "aabench run: resuming %s: %zu case%s kept, measuring the rest\n",
                aa_runfolder_dir(rf), kept, kept == 1 ? "" : "s");
    st = aa_runfolder_run(rf);
    if (!st)
        st = aa_runfolder_finish(rf);
    code = cli_run_report(rf, opt.quiet, st);
    aa_runfolder_free(rf);
    return code;
}
