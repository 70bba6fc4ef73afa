/*
 * runfolder.c: a run folder as a library object (runfolder.h).
 *
 * A run's cases are its suite's cross products (or the lists given), each
 * numbered in the whole run's order.  create checks the whole plan before
 * anything is written, makes the folder and writes the manifest (run.json:
 * shard.c's aa_manifest) before any case; run measures the cases left and
 * saves results.json then results.csv after every case (atomically, so an
 * interrupted or killed run keeps what it measured and no file is half
 * written); open reads a folder back to resume it; merge joins the
 * folders of a run's shards; finish draws the montage (the first view's
 * reference and methods side by side, labelled with name and RMSE), the
 * error-against-time plot and the convergence of the sampling methods.
 * The run's command is recorded in the manifest as the words of `aabench
 * run` (aa_plan_parse reads them back): resume and merge rebuild the plan
 * from it.
 */
#include "bench.h"
#include "c_numbers_internal.h"
#include "oiio.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAX_GROUPS 64
#define MAX_WORDS (8 * AA_PLAN_MAX + 64)

/* The arrays of parsed lists, freed together with the run folder. */
typedef struct owned {
    void **v;
    size_t n, cap;
} owned;

static void owned_free(owned *o)
{
    while (o->n)
        free(o->v[--o->n]);
    free(o->v);
    o->v = NULL, o->cap = 0;
}

struct aa_runfolder {
    aa_plan plan;
    aa_run_options opt;
    aa_run_config cfgs[MAX_GROUPS];
    size_t ng, cases;
    int threads;
    owned o;
    unsigned char *masks[MAX_GROUPS];   /* the cases to run; NULL: all */
    unsigned char *refused[MAX_GROUPS]; /* the cases skipped as refused */
    char dir[4096], images[4200];
    int linked, sort, stopped, ran; /* ran: run, or made by a merge */
    aa_context context;
    const char **context_argv; /* a merge's */
    /* the words the plan came from (open, merge) or was made into */
    aa_manifest manifest;
    int have_manifest;
    char *words[MAX_WORDS];
    int nwords;
    /* every row so far: those of the groups run (nall) and of the one under
     * way (copied of them) */
    aa_row *all;
    size_t nall, cap, copied, kept, skipped;
};

/* ---- option values ---- */

int aa_parse_real(const char *name, const char *text, double lo, double hi, double *out)
{
    char *end;
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, name);
    if (st)
        return st;
    errno = 0;
    double v = strtod(text, &end);
    int range = errno == ERANGE;
    aa__c_numbers_end(&numbers);
    if (end == text || *end || range || !isfinite(v))
        return aa_fail(AA_EINVAL, "%s \"%s\" is not a finite number", name, aa_echo(text));
    if (v < lo || v > hi)
        return aa_fail(AA_EINVAL, "%s %s is out of range (%g to %g)", name, aa_echo(text), lo,
                       hi);
    *out = v;
    return AA_OK;
}

int aa_parse_int(const char *name, const char *text, long lo, long hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    /* digits too many for a long are a number out of range, not malformed */
    if (end != text && !*end && errno == ERANGE)
        return aa_fail(AA_EINVAL, "%s %s is out of range (%ld to %ld)", name, aa_echo(text), lo,
                       hi);
    if (end == text || *end || errno == ERANGE)
        return aa_fail(AA_EINVAL, "%s \"%s\" is not a whole number", name, aa_echo(text));
    if (v < lo || v > hi)
        return aa_fail(AA_EINVAL, "%s %s is out of range (%ld to %ld)", name, aa_echo(text), lo,
                       hi);
    *out = (int)v;
    return AA_OK;
}

int aa_option_once(aa_options_seen *seen, int code, const char *value,
                   const struct option *opts, const int *lists)
{
    const struct option *o = opts;
    while (o->name && o->val != code)
        o++;
    if (!o->name || o->has_arg == no_argument || !value)
        return AA_OK;
    for (const int *l = lists; l && *l; l++)
        if (*l == code)
            return AA_OK;
    for (int k = 0; k < seen->n; k++) {
        /* the same value again leaves nothing ignored (truth --warm S
         * beside --suite S, as the shard drivers give it) */
        if (seen->code[k] != code || !strcmp(seen->value[k], value))
            continue;
        char name[64];
        if (code > 0 && code < 128 && isalnum(code))
            snprintf(name, sizeof name, "-%c", code);
        else
            snprintf(name, sizeof name, "--%s", o->name);
        return aa_fail(AA_EINVAL,
                       "%s is given twice (%s %s, then %s %s): the first would be ignored; "
                       "give it once",
                       name, name, aa_echo(seen->value[k]), name, aa_echo(value));
    }
    if (seen->n < (int)(sizeof seen->code / sizeof seen->code[0])) {
        seen->code[seen->n] = code;
        seen->value[seen->n++] = value;
    }
    return AA_OK;
}

int aa_parse_seed(const char *text, uint64_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 10);
    if (end == text || *end || errno == ERANGE || text[0] == '-' || text[0] == ' ' ||
        text[0] == '+')
        return aa_fail(AA_EINVAL, "--seed \"%s\" is not a whole number from 0 to 2^64-1",
                       aa_echo(text));
    *out = v;
    return AA_OK;
}

int aa_parse_pair(const char *name, const char *text, double lo, double hi, double *a,
                  double *b)
{
    char buf[256];
    const char *comma = strchr(text, ',');
    if (!comma || strlen(text) >= sizeof buf)
        return aa_fail(AA_EINVAL, "%s \"%s\" is not two numbers X,Y", name, aa_echo(text));
    memcpy(buf, text, (size_t)(comma - text));
    buf[comma - text] = '\0';
    int st = aa_parse_real(name, buf, lo, hi, a);
    return st ? st : aa_parse_real(name, comma + 1, lo, hi, b);
}

int aa_parse_threads(const char *text, int *out)
{
    return aa_parse_int("--threads", text, 1, 1024, out);
}

int aa_parse_target(const char *text, double *out)
{
    double pct;
    int st = aa_parse_real("--target-ci", text, 0.01, 50, &pct);
    if (!st)
        *out = pct / 100;
    return st;
}

int aa_parse_budget(const char *text, double *out)
{
    return aa_parse_real("--budget", text, 0.001, 3600, out);
}

int aa_folder_check(const char *what, const char *path, size_t room)
{
    if (!path || !*path)
        return aa_fail(AA_EINVAL, "%s: no folder given", what);
    size_t n = strlen(path), max = AA_PATH_MAX - 1 - room;
    if (n > max)
        return aa_fail(AA_EINVAL,
                       "%s \"%s\": a folder name of %zu characters is too long (at most %zu, so "
                       "that the files in it have names within %d)",
                       what, aa_echo(path), n, max, AA_PATH_MAX - 1);
    char *prefix = malloc(n + 1);
    if (!prefix)
        return aa_fail(AA_ENOMEM, "out of memory");
    int st = AA_OK;
    /* each component within NAME_MAX, and each one that exists a folder */
    for (size_t start = 0, k = 0; k <= n && !st; k++) {
        if (k < n && path[k] != '/')
            continue;
        if (k - start > NAME_MAX)
            st = aa_fail(AA_EINVAL, "%s \"%s\": the name %s is longer than %d characters", what,
                         aa_echo(path), aa_echo(path + start), NAME_MAX);
        start = k + 1;
        if (st || k == 0)
            continue;
        memcpy(prefix, path, k);
        prefix[k] = '\0';
        struct stat sb;
        if (stat(prefix, &sb) == 0 && !S_ISDIR(sb.st_mode))
            st = aa_fail(AA_EIO, "%s \"%s\": %s is not a folder but a %s", what, aa_echo(path),
                         aa_echo(prefix), S_ISREG(sb.st_mode) ? "file" : "special file");
    }
    free(prefix);
    return st;
}

int aa_default_threads(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)(n > 1024 ? 1024 : n) : 1;
}

/* ---- the plan and its words ---- */

void aa_plan_default(aa_plan *plan)
{
    memset(plan, 0, sizeof *plan);
    plan->suite = "default";
    plan->seed = 1;
    plan->enc.kind = AA_ENCODE_SRGB;
}

void aa_run_options_default(aa_run_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->images = AA_IMAGES_SMALL;
    opt->plots = 1;
    opt->isolate = AA_ISOLATE_PLUGINS;
    opt->case_timeout = AA_CASE_TIMEOUT;
}

static int push(const char **v, size_t *n, const char *item, const char *what)
{
    if (*n == AA_PLAN_MAX)
        return aa_fail(AA_EINVAL, "more than %d %s given", AA_PLAN_MAX, what);
    v[(*n)++] = item;
    return AA_OK;
}

/* --shard K/N: 1 <= K <= N <= AA_SHARD_MAX. */
static int parse_shard(const char *text, int *k, int *n)
{
    char *end, *end2;
    errno = 0;
    long a = strtol(text, &end, 10), b = *end == '/' ? strtol(end + 1, &end2, 10) : 0;
    if (*end != '/' || *end2 || errno || !(*text >= '0' && *text <= '9') ||
        !(end[1] >= '0' && end[1] <= '9') || b < 1 || b > AA_SHARD_MAX || a < 1 || a > b)
        return aa_fail(AA_EINVAL,
                       "--shard \"%s\": expected K/N, the K-th of N parts, 1 <= K <= N <= %d",
                       aa_echo(text), AA_SHARD_MAX);
    *k = (int)a, *n = (int)b;
    return AA_OK;
}

/* A value given twice in one list (-p, -m, -s, -f): each case would run
 * twice, or once with its rows doubled.  Sizes are compared as sizes
 * (what aa_size_parse reads), the others as text. */
static int repeated(const char *const *v, size_t n, const char *flag, int sizes)
{
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++) {
            int wa, ha, wb, hb;
            int same = sizes && !aa_size_parse(v[a], &wa, &ha) && !aa_size_parse(v[b], &wb, &hb)
                           ? wa == wb && ha == hb
                           : !strcmp(v[a], v[b]);
            if (same)
                return aa_fail(AA_EINVAL,
                               "%s %s is given twice (%s %s): give each value once, "
                               "every case runs once",
                               flag, aa_echo(v[a]), flag, aa_echo(v[b]));
        }
    return AA_OK;
}

/* Options that would be ignored are refused: a resumed run goes on in its
 * own folder with its own shard, and a list names each value once. */
static int ignored_options(const aa_plan *plan, const aa_run_options *opt)
{
    int st;
    if (opt->resume && opt->out && strcmp(opt->resume, opt->out))
        return aa_fail(AA_EINVAL,
                       "--resume %s goes on in that folder: --out %s would be ignored (leave "
                       "--out out)",
                       aa_echo(opt->resume), aa_echo(opt->out));
    if (opt->resume && plan->shards)
        return aa_fail(AA_EINVAL,
                       "--resume %s goes on with the run's own shard: --shard would be ignored "
                       "(leave --shard out)",
                       aa_echo(opt->resume));
    if ((st = repeated(plan->patterns, plan->npatterns, "-p", 0)) ||
        (st = repeated(plan->methods, plan->nmethods, "-m", 0)) ||
        (st = repeated(plan->sizes, plan->nsizes, "-s", 1)) ||
        (st = repeated(plan->filters, plan->nfilters, "-f", 0)))
        return st;
    return AA_OK;
}

int aa_plan_parse(int argc, char *const *argv, aa_plan *plan, aa_run_options *opt, int *asked)
{
    enum { O_SUITE = 256, O_REPS, O_OUT, O_THREADS, O_SEED, O_TIME, O_MOTION, O_ENCODE,
           O_PLUGIN, O_NOIMAGES, O_NOPLOTS, O_CACHE, O_NOCACHE, O_LIST, O_FRAMES, O_WINDOW,
           O_TARGET, O_BUDGET, O_SEEDS, O_ISOLATE, O_NOISOLATE, O_CASE_TIMEOUT, O_SHARD,
           O_RESUME, O_IMAGES };
    static const struct option opts[] = {
        {"suite", required_argument, 0, O_SUITE}, {"pattern", required_argument, 0, 'p'},
        {"method", required_argument, 0, 'm'},   {"size", required_argument, 0, 's'},
        {"filter", required_argument, 0, 'f'},   {"reps", required_argument, 0, O_REPS},
        {"out", required_argument, 0, O_OUT},    {"threads", required_argument, 0, O_THREADS},
        {"seed", required_argument, 0, O_SEED},  {"time", required_argument, 0, O_TIME},
        {"motion", required_argument, 0, O_MOTION}, {"encode", required_argument, 0, O_ENCODE},
        {"plugin", required_argument, 0, O_PLUGIN}, {"no-images", no_argument, 0, O_NOIMAGES},
        {"no-plots", no_argument, 0, O_NOPLOTS}, {"cache", required_argument, 0, O_CACHE},
        {"no-cache", no_argument, 0, O_NOCACHE}, {"list-suites", no_argument, 0, O_LIST},
        {"quiet", no_argument, 0, 'q'},          {"help", no_argument, 0, 'h'},
        {"frames", required_argument, 0, O_FRAMES}, {"window", required_argument, 0, O_WINDOW},
        {"target-ci", required_argument, 0, O_TARGET},
        {"budget", required_argument, 0, O_BUDGET},
        {"seeds", required_argument, 0, O_SEEDS},
        {"isolate", no_argument, 0, O_ISOLATE},
        {"no-isolate", no_argument, 0, O_NOISOLATE},
        {"case-timeout", required_argument, 0, O_CASE_TIMEOUT},
        {"shard", required_argument, 0, O_SHARD},
        {"resume", required_argument, 0, O_RESUME},
        {"images", required_argument, 0, O_IMAGES},
        {0, 0, 0, 0}};
    int c, st = AA_OK;
    *asked = 0;
    plan->argc = argc > 0 ? argc - 1 : 0;
    plan->argv = argc > 0 ? (const char *const *)argv + 1 : NULL;
    optind = 0; /* glibc: full reinitialisation */
    opterr = 0;
    /* -p, -m, -s, -f and --plugin take a value each time; the rest one */
    static const int lists[] = {'p', 'm', 's', 'f', O_PLUGIN, 0};
    aa_options_seen seen = {0};
    int images_given = 0;
    while ((c = getopt_long(argc, argv, ":p:m:s:f:qh", opts, NULL)) != -1) {
        if ((st = aa_option_once(&seen, c, optarg, opts, lists)))
            return st;
        switch (c) {
        case O_SUITE: plan->suite = optarg; break;
        case 'p': st = push(plan->patterns, &plan->npatterns, optarg, "patterns"); break;
        case 'm': st = push(plan->methods, &plan->nmethods, optarg, "methods"); break;
        case 's': st = push(plan->sizes, &plan->nsizes, optarg, "sizes"); break;
        case 'f': st = push(plan->filters, &plan->nfilters, optarg, "filters"); break;
        case O_REPS: st = aa_parse_int("--reps", optarg, 1, 1000, &plan->reps); break;
        case O_OUT: opt->out = optarg; break;
        case O_THREADS: st = aa_parse_threads(optarg, &opt->threads); break;
        case O_SEED: st = aa_parse_seed(optarg, &plan->seed); break;
        case O_TIME: st = aa_parse_real("--time", optarg, -1e9, 1e9, &plan->t); break;
        case O_MOTION:
            st = aa_parse_pair("--motion", optarg, -1e6, 1e6, &plan->vx, &plan->vy);
            plan->motion_given = 1;
            break;
        case O_FRAMES:
            st = aa_parse_int("--frames", optarg, 2, AA_TEMPORAL_MAX_FRAMES, &plan->frames);
            break;
        case O_WINDOW:
            st = aa_parse_int("--window", optarg, 1, AA_TEMPORAL_MAX_FRAMES, &plan->window);
            break;
        case O_ENCODE: st = aa_encode_parse(optarg, &plan->enc); break;
        case O_TARGET: st = aa_parse_target(optarg, &plan->target_ci); break;
        case O_BUDGET: st = aa_parse_budget(optarg, &plan->budget); break;
        case O_SEEDS: st = aa_parse_int("--seeds", optarg, 1, 1000, &plan->seeds); break;
        case O_PLUGIN: st = aa_plugin_load(optarg); break;
        case O_NOIMAGES:
        case O_IMAGES: {
            int which = AA_IMAGES_NONE;
            if (c == O_IMAGES && !strcmp(optarg, "small"))
                which = AA_IMAGES_SMALL;
            else if (c == O_IMAGES && !strcmp(optarg, "all"))
                which = AA_IMAGES_ALL;
            else if (c == O_IMAGES && strcmp(optarg, "none"))
                st = aa_fail(AA_EINVAL, "--images %s: none, small or all", aa_echo(optarg));
            if (!st && images_given && which != opt->images)
                st = aa_fail(AA_EINVAL, "--images and --no-images say different things: "
                                        "give one");
            opt->images = which;
            images_given = 1;
            break;
        }
        case O_NOPLOTS: opt->plots = 0; break;
        case O_CACHE: opt->cache = optarg; break;
        case O_NOCACHE: opt->cache = ""; break;
        case 'q': opt->quiet = 1; break;
        case O_ISOLATE: opt->isolate = AA_ISOLATE_ALL; break;
        case O_NOISOLATE: opt->isolate = AA_ISOLATE_NONE; break;
        case O_CASE_TIMEOUT:
            st = aa_parse_real("--case-timeout", optarg, 0.001, 1e9, &opt->case_timeout);
            break;
        case O_SHARD: st = parse_shard(optarg, &plan->shard, &plan->shards); break;
        case O_RESUME: opt->resume = optarg; break;
        case O_LIST: *asked = 'l'; return AA_OK;
        case 'h': *asked = 'h'; return AA_OK;
        default: {
            const char *arg = argv[optind - 1];
            *asked = '?';
            if (c == ':')
                return aa_fail(AA_EINVAL, "option %s needs a value", aa_echo(arg));
            if (optopt)
                return aa_fail(AA_EINVAL, "unknown option -%s",
                               aa_echo((char[]){(char)optopt, 0}));
            return aa_fail(AA_EINVAL, "unknown option %s", aa_echo(arg));
        }
        }
        if (st)
            return st;
    }
    if (optind < argc)
        return aa_fail(AA_EINVAL, "unexpected argument \"%s\"", aa_echo(argv[optind]));
    return ignored_options(plan, opt);
}

/* A word made by the run folder (freed with it). */
static int word(aa_runfolder *rf, const char *fmt, ...) AA_PRINTF(2, 3);
static int word(aa_runfolder *rf, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= sizeof buf)
        return aa_fail(AA_EINVAL, "a word of the run's command is too long: %.60s...", buf);
    char *w = rf->nwords < MAX_WORDS ? strdup(buf) : NULL;
    if (!w)
        return aa_fail(AA_ENOMEM, "out of memory");
    rf->words[rf->nwords++] = w;
    return AA_OK;
}

/* The words of a plan given without them: what aa_plan_parse reads back
 * as the same plan and recorded options. */
static int make_words(aa_runfolder *rf)
{
    const aa_plan *p = &rf->plan;
    const aa_run_options *o = &rf->opt;
    const struct {
        const char *flag;
        const char *const *v;
        size_t n;
    } lists[] = {{"-p", p->patterns, p->npatterns},
                 {"-s", p->sizes, p->nsizes},
                 {"-f", p->filters, p->nfilters},
                 {"-m", p->methods, p->nmethods}};
    int st = word(rf, "--suite=%s", p->suite);
    for (size_t l = 0; l < 4; l++)
        for (size_t k = 0; k < lists[l].n && !st; k++)
            st = word(rf, "%s%s", lists[l].flag, lists[l].v[k]);
    if (!st && p->reps)
        st = word(rf, "--reps=%d", p->reps);
    if (!st && p->target_ci)
        st = word(rf, "--target-ci=%.17g", p->target_ci * 100);
    if (!st && p->budget)
        st = word(rf, "--budget=%.17g", p->budget);
    if (!st && p->seeds)
        st = word(rf, "--seeds=%d", p->seeds);
    if (!st && p->seed != 1)
        st = word(rf, "--seed=%llu", (unsigned long long)p->seed);
    if (!st && p->t)
        st = word(rf, "--time=%.17g", p->t);
    if (!st && p->motion_given)
        st = word(rf, "--motion=%.17g,%.17g", p->vx, p->vy);
    if (!st && p->frames)
        st = word(rf, "--frames=%d", p->frames);
    if (!st && p->window)
        st = word(rf, "--window=%d", p->window);
    if (!st && p->enc.kind == AA_ENCODE_LINEAR)
        st = word(rf, "--encode=linear");
    if (!st && p->enc.kind == AA_ENCODE_GAMMA)
        st = word(rf, "--encode=gamma:%.17g", p->enc.gamma);
    if (!st && o->images != AA_IMAGES_SMALL)
        st = word(rf, o->images == AA_IMAGES_NONE ? "--no-images" : "--images=all");
    if (!st && !o->plots)
        st = word(rf, "--no-plots");
    if (!st && o->isolate != AA_ISOLATE_PLUGINS)
        st = word(rf, o->isolate == AA_ISOLATE_ALL ? "--isolate" : "--no-isolate");
    if (!st && o->case_timeout != AA_CASE_TIMEOUT)
        st = word(rf, "--case-timeout=%.17g", o->case_timeout);
    return st;
}

/* ---- the folder ---- */

static int make_run_dir(char *dir, size_t len, int *linked)
{
    char stamp[64];
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &tm);
    int st = aa_mkdirs("results/runs");
    if (st)
        return st;
    for (int k = 1; k < 100; k++) {
        if (k == 1)
            snprintf(dir, len, "results/runs/%s", stamp);
        else
            snprintf(dir, len, "results/runs/%s-%d", stamp, k);
        if (mkdir(dir, 0755) == 0) {
            /* results/latest -> runs/<stamp>, replaced atomically */
            char tmp[256];
            snprintf(tmp, sizeof tmp, "results/.latest.%ld", (long)getpid());
            unlink(tmp);
            *linked = symlink(dir + strlen("results/"), tmp) == 0 &&
                      rename(tmp, "results/latest") == 0;
            if (!*linked)
                unlink(tmp);
            return AA_OK;
        }
        if (errno != EEXIST)
            return aa_fail(AA_EIO, "cannot make %s: %s", dir, strerror(errno));
    }
    return aa_fail(AA_EIO, "cannot make a run folder under results/runs");
}

/* ---- progress and saving ---- */

static int progress(void *vrf, size_t done, size_t total, const char *what)
{
    aa_runfolder *rf = vrf;
    if (rf->opt.progress)
        rf->opt.progress(rf->opt.hook, done, total, what);
    if (rf->opt.interrupted && rf->opt.interrupted(rf->opt.hook))
        rf->stopped = 1;
    return rf->stopped;
}

static int by_case(const void *a, const void *b)
{
    const aa_row *x = a, *y = b;
    return x->case_index < y->case_index ? -1 : x->case_index > y->case_index;
}

/* results.json first, results.csv last: a case in results.csv (which
 * resume, merge, diff and check read) is in results.json too, however the
 * run is stopped. */
static int save_rows(aa_runfolder *rf, const aa_row *rows, size_t n)
{
    char path[4200];
    int st = aa_pathf(path, sizeof path, "%s/results.json", rf->dir);
    if (!st && !(st = aa_results_write_json(path, &rf->context, rows, n)) &&
        !(st = aa_pathf(path, sizeof path, "%s/results.csv", rf->dir)))
        st = aa_rows_write_csv(path, rows, n);
    return st;
}

static int save(aa_runfolder *rf, const aa_row *rows, size_t n)
{
    if (!rf->sort || n < 2)
        return save_rows(rf, rows, n);
    /* a resumed run's rows, the kept and the new, in the run's order */
    aa_row *sorted = malloc(n * sizeof *sorted);
    if (!sorted)
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", n);
    memcpy(sorted, rows, n * sizeof *rows);
    qsort(sorted, n, sizeof *sorted, by_case);
    int st = save_rows(rf, sorted, n);
    free(sorted);
    return st;
}

/* Room in rf->all for `more` rows after those kept. */
static int grow(aa_runfolder *rf, size_t more)
{
    size_t need = rf->nall + more;
    if (need <= rf->cap)
        return AA_OK;
    size_t cap = rf->cap ? rf->cap : 64;
    while (cap < need)
        cap *= 2;
    aa_row *p = realloc(rf->all, cap * sizeof *p);
    if (!p)
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", need);
    rf->all = p;
    rf->cap = cap;
    return AA_OK;
}

/* After every case (aa_run_config.row_done): the rows of the earlier
 * groups and the group's so far, written out, so that a run that is
 * killed, or fails, keeps every case it measured. */
static int row_done(void *vrf, const aa_row *rows, size_t n)
{
    aa_runfolder *rf = vrf;
    int st = grow(rf, n);
    if (st)
        return st;
    memcpy(rf->all + rf->nall + rf->copied, rows + rf->copied, (n - rf->copied) * sizeof *rows);
    rf->copied = n;
    return save(rf, rf->all, rf->nall + n);
}

/* ---- what runs after the cases ---- */

/* The montages: for each view (pattern, size, filter) of the run, its
 * reference and every method that ran on it, side by side:
 * montage.png the first view's, montage-PATTERN-WxH-FILTER.png each other's.  A
 * view larger than MONTAGE_SIDE shows its central MONTAGE_SIDE square
 * (tiles are copied, never resampled), and its labels say so. */

#define MONTAGE_TILES 64
#define MONTAGE_LINES 3
#define MONTAGE_SIDE 256

/* Its columns, for n tiles of width w. */
static int montage_columns(size_t n, int w)
{
    if (w <= 160)
        return n <= 6 ? (int)n : 6;
    return n <= 4 ? (int)n : (n <= 9 ? 3 : 4);
}

/* Its tiles, each read when the montage asks for it and freed once copied:
 * the reference (from the cache), then each method's EXR written by the
 * run; cropped to the window (x0, y0, tw, th). */
typedef struct montage_source {
    const char *dir;
    const char *cache; /* the run's reference cache (NULL: --no-cache) */
    const aa_row *rows;
    size_t row[MONTAGE_TILES]; /* tile k > 0 is rows[row[k]] */
    aa_view view;
    int x0, y0, tw, th;
    aa_image im, crop;
    char labels[MONTAGE_LINES][128];
} montage_source;

static int montage_get(void *vctx, size_t k, aa_tile *tile)
{
    montage_source *s = vctx;
    int st;
    if (k == 0) {
        if ((st = aa_reference(&s->view, s->cache, 0, &s->im, NULL, NULL)))
            return st;
        snprintf(s->labels[0], 128, "reference (%.100s)", s->rows[s->row[1]].filter);
        snprintf(s->labels[1], 128, "exact");
        if (s->tw < s->view.w || s->th < s->view.h)
            snprintf(s->labels[2], 128, "centre %dx%d", s->tw, s->th);
        else
            s->labels[2][0] = '\0';
    } else {
        const aa_row *r = &s->rows[s->row[k]];
        char path[4096], ps[512], fs[256], ms[512];
        aa_spec_slug(r->pattern, ps, sizeof ps);
        aa_spec_slug(r->filter, fs, sizeof fs);
        aa_spec_slug(r->method, ms, sizeof ms);
        /* the EXR written by the run holds the values */
        if ((st = aa_pathf(path, sizeof path, "%s/images/%s-%dx%d-%s-%s.exr", s->dir, ps, r->w,
                           r->h, fs, ms)) ||
            (st = aa_image_read(path, &s->im)))
            return st;
        snprintf(s->labels[0], 128, "%.120s", r->method);
        snprintf(s->labels[1], 128, "RMSE %.3g", r->m.rmse);
        snprintf(s->labels[2], 128, "FLIP %.3g", r->m.flip);
    }
    if (s->tw < s->im.w || s->th < s->im.h) {
        if ((st = aa_image_alloc(&s->crop, s->tw, s->th, s->im.c)))
            return st;
        for (int j = 0; j < s->th; j++)
            memcpy(aa_pixel(&s->crop, 0, j), aa_pixel(&s->im, s->x0, s->y0 + j),
                   sizeof(double) * (size_t)s->im.c * (size_t)s->tw);
        tile->image = &s->crop;
    } else {
        tile->image = &s->im;
    }
    tile->label[0] = s->labels[0];
    tile->label[1] = s->labels[1];
    tile->label[2] = s->labels[2][0] ? s->labels[2] : NULL;
    return AA_OK;
}

static void montage_put(void *vctx, size_t k)
{
    (void)k;
    aa_image_free(&((montage_source *)vctx)->im);
    aa_image_free(&((montage_source *)vctx)->crop);
}

/* The montage file of the view of row r. */
static int montage_path(char *path, size_t len, const char *dir, const aa_row *r)
{
    char ps[512], fs[256];
    aa_spec_slug(r->pattern, ps, sizeof ps);
    aa_spec_slug(r->filter, fs, sizeof fs);
    return aa_pathf(path, len, "%s/montage-%s-%dx%d-%s.png", dir, ps, r->w, r->h, fs);
}

static int write_view_montage(const char *dir, const char *cache, const aa_row *rows, size_t n,
                              size_t first, const aa_encode *enc, const char *path)
{
    montage_source s;
    memset(&s, 0, sizeof s);
    s.dir = dir, s.rows = rows, s.cache = cache;
    const aa_row *r0 = &rows[first];
    int st;
    if ((st = aa_pattern_parse(r0->pattern, &s.view.pattern)) ||
        (st = aa_filter_parse(r0->filter, &s.view.filter)))
        return st;
    s.view.w = r0->w, s.view.h = r0->h;
    s.view.t = r0->t, s.view.vx = r0->vx, s.view.vy = r0->vy;
    s.tw = r0->w < MONTAGE_SIDE ? r0->w : MONTAGE_SIDE;
    s.th = r0->h < MONTAGE_SIDE ? r0->h : MONTAGE_SIDE;
    s.x0 = (r0->w - s.tw) / 2, s.y0 = (r0->h - s.th) / 2;
    size_t nt = 1;
    for (size_t k = first; k < n && nt < MONTAGE_TILES; k++)
        if (rows[k].ok && aa_rows_same_view(&rows[k], r0) && rows[k].t == r0->t)
            s.row[nt++] = k;
    aa_tile_source src = {.n = nt, .tw = s.tw, .th = s.th, .lines = MONTAGE_LINES,
                          .get = montage_get, .put = montage_put, .ctx = &s};
    st = aa_montage_stream(path, &src, montage_columns(nt, s.tw), enc);
    aa_image_free(&s.im);
    aa_image_free(&s.crop);
    return st;
}

/* The most pixels of a view whose images are written (0: any view's): for
 * AA_IMAGES_SMALL the larger of AA_IMAGES_SIDE squared and the run's
 * smallest view, so that every run has some. */
static long images_max(int images, const aa_run_config *cfgs, size_t ng)
{
    if (images != AA_IMAGES_SMALL)
        return 0;
    long least = LONG_MAX;
    for (size_t g = 0; g < ng; g++)
        for (size_t s = 0; s < cfgs[g].nsizes; s++)
            if ((long)cfgs[g].sizes[s].w * cfgs[g].sizes[s].h < least)
                least = (long)cfgs[g].sizes[s].w * cfgs[g].sizes[s].h;
    long most = (long)AA_IMAGES_SIDE * AA_IMAGES_SIDE;
    return least > most && least < LONG_MAX ? least : most;
}

static int write_montage(const char *dir, const aa_run_config *first, const aa_row *rows,
                         size_t n, long max, const aa_encode *enc)
{
    int st = AA_OK;
    char path[4096];
    for (size_t k = 0; k < n && !st; k++) {
        if (!rows[k].ok)
            continue;
        size_t q = 0;
        while (q < k && !(rows[q].ok && aa_rows_same_view(&rows[q], &rows[k])))
            q++;
        if (q < k) /* drawn with an earlier row of its view */
            continue;
        int is_first = 1;
        for (q = 0; q < k; q++)
            is_first &= !rows[q].ok;
        if (max && (long)rows[k].w * rows[k].h > max)
            continue; /* no images of this view */
        if (!(st = is_first ? aa_pathf(path, sizeof path, "%s/montage.png", dir)
                            : montage_path(path, sizeof path, dir, &rows[k])))
            st = write_view_montage(dir, first->cache_dir, rows, n, k, enc, path);
    }
    /* everything was checked before the work: what fails now (the memory
     * it needs, under a limit) is the machine's, not the input's */
    if (st == AA_EINVAL) {
        char why[1024];
        snprintf(why, sizeof why, "%s", aa_last_error());
        st = aa_fail(AA_ENOMEM, "%s", why);
    }
    return st;
}

/* A method spec without its spp= or n= pair, to name a convergence curve
 * (which varies that count). */
static void without_count(const char *spec, char *buf, size_t len)
{
    const char *colon = strchr(spec, ':');
    size_t n = colon ? (size_t)(colon - spec) : strlen(spec);
    snprintf(buf, len, "%.*s", (int)n, spec);
    if (!colon)
        return;
    char rest[512];
    snprintf(rest, sizeof rest, "%s", colon + 1);
    int first = 1;
    for (char *pair = strtok(rest, ","); pair; pair = strtok(NULL, ",")) {
        if (!strncmp(pair, "spp=", 4) || !strncmp(pair, "n=", 2))
            continue;
        size_t used = strlen(buf);
        snprintf(buf + used, len - used, "%c%s", first ? ':' : ',', pair);
        first = 0;
    }
}

/* Convergence of the sampling methods among those run, on the first
 * pattern at 128x128 under the first filter. */
/* Whether the convergence, which runs in this process, may run a method:
 * not one that failed a case, nor one from a plug-in the run isolated. */
static int trusted(const aa_runfolder *rf, const aa_run_spec *m, const aa_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (rows[k].failed && !strcmp(rows[k].method, m->text))
            return 0;
    if (rf->opt.isolate == AA_ISOLATE_NONE)
        return 1;
    for (size_t k = 0; aa_method_types[k]; k++)
        if (&aa_method_types[k]->info == m->spec.info)
            return 1;
    return 0;
}

static int write_convergence(const char *dir, const aa_runfolder *rf, const aa_run_config *first,
                             int threads, const aa_row *rows, size_t nrows)
{
    const aa_run_spec *names[16];
    aa_convergence conv[16];
    size_t n = 0;
    const aa_spec *pspec = &first->patterns[0].spec;
    const aa_filter *f = &first->filters[0].filter;
    const char *pattern = first->patterns[0].text, *filter = first->filters[0].text;
    int st;
    static const int spp[] = {1, 4, 16, 64, 256};
    for (size_t k = 0; k < first->nmethods && n < 16; k++) {
        const aa_spec *mspec = &first->methods[k].spec;
        if (!trusted(rf, &first->methods[k], rows, nrows) || aa_method_check(mspec, f) ||
            (aa_spec_index(mspec->info, "spp") < 0 && aa_spec_index(mspec->info, "n") < 0))
            continue;
        /* one curve per method family variant: skip a spec that differs
         * from an earlier one only in its sample count */
        int seen = 0;
        for (size_t q = 0; q < n && !seen; q++) {
            const aa_spec *other = &names[q]->spec;
            if (other->info == mspec->info) {
                int same = 1;
                for (size_t p = 0; p < aa_param_count(mspec->info); p++) {
                    const char *key = mspec->info->params[p].key;
                    if (strcmp(key, "spp") && strcmp(key, "n") && other->v[p] != mspec->v[p])
                        same = 0;
                }
                seen = same;
            }
        }
        if (seen)
            continue;
        if ((st = aa_converge(pspec, mspec, f, 128, 128, spp, 5, 4, rf->plan.seed, threads,
                              first->cache_dir, &conv[n])) == AA_OK)
            names[n++] = &first->methods[k];
        else if (st != AA_EINVAL)
            return st;
    }
    if (n == 0)
        return AA_OK;
    char title[1024], labels[16][256];
    const char *shown[16];
    for (size_t k = 0; k < n; k++) {
        without_count(names[k]->text, labels[k], sizeof labels[k]);
        shown[k] = labels[k];
    }
    snprintf(title, sizeof title, "Convergence on %s 128x128 %s, 4 random sub-pixel shifts",
             pattern, filter);
    return aa_plot_convergence(dir, conv, shown, n, title);
}


static void *own(owned *o, size_t n, size_t size)
{
    if (o->n == o->cap) {
        size_t cap = o->cap ? 2 * o->cap : 64;
        void **v = realloc(o->v, cap * sizeof *v);
        if (!v)
            return NULL;
        o->v = v, o->cap = cap;
    }
    void *p = calloc(n ? n : 1, size);
    if (p)
        o->v[o->n++] = p;
    return p;
}

static size_t count(const char *const *v)
{
    size_t n = 0;
    while (v[n])
        n++;
    return n;
}

/* Each list is parsed where it comes in, and keeps the text it was given
 * as, for the results' columns and the image names. */
static int parse_patterns(owned *o, const char *const *text, size_t n, aa_run_spec **out)
{
    aa_run_spec *v = *out = own(o, n, sizeof *v);
    int st = v ? AA_OK : aa_fail(AA_ENOMEM, "out of memory");
    for (size_t k = 0; k < n && !st; k++) {
        v[k].text = text[k];
        st = aa_pattern_parse(text[k], &v[k].spec);
    }
    return st;
}

static int parse_sizes(owned *o, const char *const *text, size_t n, aa_run_size **out)
{
    aa_run_size *v = *out = own(o, n, sizeof *v);
    int st = v ? AA_OK : aa_fail(AA_ENOMEM, "out of memory");
    for (size_t k = 0; k < n && !st; k++)
        if (!(st = aa_size_parse(text[k], &v[k].w, &v[k].h)))
            st = aa_size_check(v[k].w, v[k].h, 3, 4);
    return st;
}

static int parse_filters(owned *o, const char *const *text, size_t n, aa_run_filter **out)
{
    aa_run_filter *v = *out = own(o, n, sizeof *v);
    int st = v ? AA_OK : aa_fail(AA_ENOMEM, "out of memory");
    for (size_t k = 0; k < n && !st; k++) {
        v[k].text = text[k];
        st = aa_filter_parse(text[k], &v[k].filter);
    }
    return st;
}

/* Whether a method accepts each filter is a result of the run, not a parse
 * error: only the spec is parsed here. */
static int parse_methods(owned *o, const char *const *text, size_t n, aa_run_spec **out)
{
    aa_run_spec *v = *out = own(o, n, sizeof *v);
    int st = v ? AA_OK : aa_fail(AA_ENOMEM, "out of memory");
    for (size_t k = 0; k < n && !st; k++) {
        v[k].text = text[k];
        st = aa_spec_parse(text[k], aa_method_table(), "method", &v[k].spec);
    }
    return st;
}

/* A suite's external methods (AA_METHOD_EXTERNAL) whose renderer is not
 * installed are left out, with a note on standard error: a suite lists
 * every renderer and runs those this machine has.  Given with -m, such a
 * method is refused as everywhere else. */
static size_t drop_missing_external(const char *suite, aa_run_spec *m, size_t n,
                                    const aa_run_options *opt)
{
    aa_filter box;
    aa_filter_default(&box);
    size_t kept = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_method_type *t = (const aa_method_type *)m[k].spec.info;
        if ((t->flags & AA_METHOD_EXTERNAL) && aa_method_check(&m[k].spec, &box) != AA_OK) {
            if (opt->note) {
                char note[2048];
                snprintf(note, sizeof note, "suite %s: leaving out %s: %s", suite, m[k].text,
                         aa_last_error());
                opt->note(opt->hook, note);
            }
            continue;
        }
        m[kept++] = m[k];
    }
    return kept;
}

/* The index in b of the first of a's values that b holds too, into *ia and
 * *ib; 0 if they share none. */
static int shared_spec(const aa_run_spec *a, size_t na, const aa_run_spec *b, size_t nb,
                       size_t *ia, size_t *ib)
{
    for (*ia = 0; *ia < na; ++*ia)
        for (*ib = 0; *ib < nb; ++*ib)
            if (!strcmp(a[*ia].text, b[*ib].text))
                return 1;
    return 0;
}

static int shared_filter(const aa_run_filter *a, size_t na, const aa_run_filter *b, size_t nb,
                         size_t *ia)
{
    for (*ia = 0; *ia < na; ++*ia)
        for (size_t k = 0; k < nb; k++)
            if (!strcmp(a[*ia].text, b[k].text))
                return 1;
    return 0;
}

static int shared_size(const aa_run_size *a, size_t na, const aa_run_size *b, size_t nb,
                       size_t *ia)
{
    for (*ia = 0; *ia < na; ++*ia)
        for (size_t k = 0; k < nb; k++)
            if (a[*ia].w == b[k].w && a[*ia].h == b[k].h)
                return 1;
    return 0;
}

/* Whether the list (n values) holds x: by text for specs and filters. */
typedef int holds_fn(const void *list, size_t n, const void *x);

static int holds_spec(const void *list, size_t n, const void *x)
{
    size_t i, j;
    return shared_spec(x, 1, list, n, &i, &j);
}

static int holds_filter(const void *list, size_t n, const void *x)
{
    size_t i;
    return shared_filter(x, 1, list, n, &i);
}

static int holds_size(const void *list, size_t n, const void *x)
{
    size_t i;
    return shared_size(x, 1, list, n, &i);
}

/* The values of a (na of them, each `size` bytes) that b holds, into a new
 * array *in (*nin of them), and those it does not, into *out (*nout). */
static int split_list(owned *o, const void *a, size_t na, size_t size, const void *b, size_t nb,
                      holds_fn *holds, const void **in, size_t *nin, const void **out,
                      size_t *nout)
{
    char *vin = own(o, na, size), *vout = own(o, na, size);
    if (!vin || !vout)
        return aa_fail(AA_ENOMEM, "out of memory");
    *nin = *nout = 0;
    for (size_t k = 0; k < na; k++) {
        const char *x = (const char *)a + k * size;
        if (holds(b, nb, x))
            memcpy(vin + (*nin)++ * size, x, size);
        else
            memcpy(vout + (*nout)++ * size, x, size);
    }
    *in = vin, *out = vout;
    return AA_OK;
}

/* cases_not_in's status when out holds too few configs (not an aa_status) */
#define TOO_MANY (-1)

/* The cases of c that d does not hold, as at most four cross products
 * sharing no case, into out[0 .. *n): c's patterns d lacks (with c's other
 * lists); of the patterns both have, the sizes d lacks; of the patterns and
 * sizes both have, the filters d lacks; of the patterns, sizes and filters
 * both have, the methods d lacks.  c itself when the two share no case,
 * none when d holds them all. */
static int cases_not_in(owned *o, const aa_run_config *c, const aa_run_config *d,
                        aa_run_config *out, size_t max, size_t *n)
{
    size_t ia, ib;
    *n = 0;
    if (!shared_spec(c->patterns, c->npatterns, d->patterns, d->npatterns, &ia, &ib) ||
        !shared_size(c->sizes, c->nsizes, d->sizes, d->nsizes, &ia) ||
        !shared_filter(c->filters, c->nfilters, d->filters, d->nfilters, &ia) ||
        !shared_spec(c->methods, c->nmethods, d->methods, d->nmethods, &ia, &ib)) {
        if (max < 1)
            return TOO_MANY;
        out[(*n)++] = *c;
        return AA_OK;
    }
    const void *pin, *pout, *sin, *sout, *fin, *fout, *min, *mout;
    size_t npin, npout, nsin, nsout, nfin, nfout, nmin, nmout;
    int st;
    if ((st = split_list(o, c->patterns, c->npatterns, sizeof *c->patterns, d->patterns,
                         d->npatterns, holds_spec, &pin, &npin, &pout, &npout)) ||
        (st = split_list(o, c->sizes, c->nsizes, sizeof *c->sizes, d->sizes, d->nsizes,
                         holds_size, &sin, &nsin, &sout, &nsout)) ||
        (st = split_list(o, c->filters, c->nfilters, sizeof *c->filters, d->filters,
                         d->nfilters, holds_filter, &fin, &nfin, &fout, &nfout)) ||
        (st = split_list(o, c->methods, c->nmethods, sizeof *c->methods, d->methods,
                         d->nmethods, holds_spec, &min, &nmin, &mout, &nmout)))
        return st;
    aa_run_config piece = *c;
    for (int k = 0; k < 4; k++) {
        piece.patterns = k ? pin : pout, piece.npatterns = k ? npin : npout;
        if (k >= 1)
            piece.sizes = k > 1 ? sin : sout, piece.nsizes = k > 1 ? nsin : nsout;
        if (k >= 2)
            piece.filters = k > 2 ? fin : fout, piece.nfilters = k > 2 ? nfin : nfout;
        if (k == 3)
            piece.methods = mout, piece.nmethods = nmout;
        if (!piece.npatterns || !piece.nsizes || !piece.nfilters || !piece.nmethods)
            continue;
        if (*n == max)
            return TOO_MANY;
        out[(*n)++] = piece;
    }
    return AA_OK;
}

/* Config c, less every case of cfgs[0 .. *ng), appended to cfgs as
 * cross products sharing no case (none when those hold all of c): no case
 * is measured twice, however the suite's groups meet once the lists given
 * replace theirs (--suite paper -p crow -s 32x32: two of its groups then
 * hold crow 32x32 box point; under -p, -f and -m every group of the default
 * suite is the same cross product). */
static int add_new_cases(owned *o, const aa_run_config *c, aa_run_config *cfgs, size_t max,
                         size_t *ng, const char *suite)
{
    aa_run_config work[MAX_GROUPS], next[MAX_GROUPS];
    size_t nw = 1;
    int st = AA_OK;
    work[0] = *c;
    for (size_t d = 0; d < *ng && nw && !st; d++) {
        size_t nn = 0, k;
        for (size_t w = 0; w < nw && !st; w++, nn += k)
            st = cases_not_in(o, &work[w], &cfgs[d], next + nn, MAX_GROUPS - nn, &k);
        memcpy(work, next, nn * sizeof *work);
        nw = nn;
    }
    if (st == TOO_MANY || (!st && *ng + nw > max))
        return aa_fail(AA_EINVAL,
                       "the suite %s with the lists given makes more than %zu cross "
                       "products: give -p, -s, -f and -m all (one cross product)",
                       suite, max);
    if (st)
        return st;
    memcpy(cfgs + *ng, work, nw * sizeof *work);
    *ng += nw;
    return AA_OK;
}

/* The cross products to run: the suite's groups, with any list given on the
 * command line replacing the groups' own.  The lists given are parsed once,
 * and shared by every group.  Patterns given without sizes: a pattern of a
 * size of its own (an svg file's, times its scale) is measured at that size
 * alone, the others at the groups' sizes; so each group becomes one cross
 * product for each size the patterns have of their own, and one for the
 * patterns without. */
static int groups_of(const aa_plan *a, const aa_suite *suite, owned *o, const aa_run_options *opt,
                     aa_run_config *cfgs, size_t max, size_t *ng)
{
    aa_run_spec *gp = NULL, *gm = NULL;
    aa_run_size *gs = NULL;
    aa_run_filter *gf = NULL;
    int st = AA_OK;
    *ng = 0;
    if ((a->npatterns && (st = parse_patterns(o, a->patterns, a->npatterns, &gp))) ||
        (a->nsizes && (st = parse_sizes(o, a->sizes, a->nsizes, &gs))) ||
        (a->nfilters && (st = parse_filters(o, a->filters, a->nfilters, &gf))) ||
        (a->nmethods && (st = parse_methods(o, a->methods, a->nmethods, &gm))))
        return st;
    /* the given patterns by class: class c holds cp[cstart[c] .. cstart[c] +
     * cn[c]), of size csize[c] (0x0: the groups' sizes) */
    size_t ncls = 1, cstart[AA_PLAN_MAX + 1] = {0}, cn[AA_PLAN_MAX + 1] = {0};
    aa_run_spec *cp = gp;
    aa_run_size *csize = NULL;
    if (a->npatterns && !a->nsizes) {
        aa_run_size *own_of = own(o, a->npatterns, sizeof *own_of);
        cp = own(o, a->npatterns, sizeof *cp);
        csize = own(o, a->npatterns, sizeof *csize);
        if (!own_of || !cp || !csize)
            return aa_fail(AA_ENOMEM, "out of memory");
        ncls = 0;
        for (size_t k = 0; k < a->npatterns; k++) {
            aa_run_size *z = &own_of[k];
            if (aa_pattern_has_own_size(&gp[k].spec) &&
                ((st = aa_pattern_own_size(&gp[k].spec, &z->w, &z->h)) ||
                 (st = aa_size_check(z->w, z->h, 3, 4))))
                return aa_fail_context(st, "pattern %s", gp[k].text);
            size_t c = 0;
            while (c < ncls && !(csize[c].w == z->w && csize[c].h == z->h))
                c++;
            if (c == ncls)
                csize[ncls++] = *z;
            cn[c]++;
        }
        for (size_t c = 1; c <= ncls; c++)
            cstart[c] = cstart[c - 1] + cn[c - 1];
        size_t at[AA_PLAN_MAX + 1];
        memcpy(at, cstart, sizeof at);
        for (size_t k = 0; k < a->npatterns; k++) {
            size_t c = 0;
            while (!(csize[c].w == own_of[k].w && csize[c].h == own_of[k].h))
                c++;
            cp[at[c]++] = gp[k];
        }
    }
    for (const aa_suite_group *g = suite->groups; g->patterns; g++) {
        aa_run_spec *p = cp, *m = gm;
        aa_run_size *s = gs;
        aa_run_filter *f = gf;
        size_t np = a->npatterns ? a->npatterns : count(g->patterns), ns = a->nsizes ? a->nsizes : count(g->sizes),
               nf = a->nfilters ? a->nfilters : count(g->filters), nm = a->nmethods ? a->nmethods : count(g->methods);
        if ((!a->npatterns && (st = parse_patterns(o, g->patterns, np, &p))) ||
            (!a->nsizes && (st = parse_sizes(o, g->sizes, ns, &s))) ||
            (!a->nfilters && (st = parse_filters(o, g->filters, nf, &f))) ||
            (!a->nmethods && (st = parse_methods(o, g->methods, nm, &m))))
            return st;
        if (!a->nmethods)
            nm = drop_missing_external(suite->name, m, nm, opt);
        for (size_t k = 0; k < ncls; k++) {
            aa_run_config one, *c = &one;
            memset(c, 0, sizeof *c);
            c->patterns = p, c->npatterns = np;
            c->sizes = s, c->nsizes = ns;
            if (csize) {
                c->patterns = cp + cstart[k], c->npatterns = cn[k];
                if (csize[k].w)
                    c->sizes = &csize[k], c->nsizes = 1;
            }
            c->filters = f, c->nfilters = nf;
            c->methods = m, c->nmethods = nm;
            if ((st = add_new_cases(o, c, cfgs, max, ng, suite->name)))
                return st;
        }
        if (a->npatterns && a->nsizes && a->nfilters && a->nmethods)
            break; /* everything given: one cross product */
    }
    return AA_OK;
}

/* Everything checked before any work or any file: every method runs some
 * case (a spec every filter of the run refuses, such as jitter:spp=15, is
 * bad input, as `render` says), the images' names fit, the montage can be
 * made, and the folders can be. */
static int check_before_work(const aa_run_options *a, const aa_run_config *cfgs, size_t ng)
{
    int st;
    for (size_t g = 0; g < ng; g++)
        for (size_t m = 0; m < cfgs[g].nmethods; m++) {
            const aa_run_spec *spec = &cfgs[g].methods[m];
            int runs = 0;
            char why[1024] = "";
            /* the same method text in any group, under any of its filters */
            for (size_t h = 0; h < ng && !runs; h++)
                for (size_t q = 0; q < cfgs[h].nmethods && !runs; q++) {
                    const aa_run_spec *other = &cfgs[h].methods[q];
                    if (other != spec && strcmp(other->text, spec->text))
                        continue;
                    for (size_t f = 0; f < cfgs[h].nfilters && !runs; f++) {
                        if (!aa_method_check(&other->spec, &cfgs[h].filters[f].filter))
                            runs = 1;
                        else if (!*why)
                            snprintf(why, sizeof why, "%s", aa_last_error());
                    }
                }
            if (!runs)
                return aa_fail(AA_EINVAL, "%s (and so under every filter of the run)", why);
        }
    if (a->images) {
        /* images/PATTERN-WxH-FILTER-METHOD-error.png within NAME_MAX */
        for (size_t g = 0; g < ng; g++)
            for (size_t p = 0; p < cfgs[g].npatterns; p++)
                for (size_t s = 0; s < cfgs[g].nsizes; s++)
                    for (size_t f = 0; f < cfgs[g].nfilters; f++)
                        for (size_t m = 0; m < cfgs[g].nmethods; m++) {
                            char wh[64];
                            snprintf(wh, sizeof wh, "-%dx%d-", cfgs[g].sizes[s].w,
                                     cfgs[g].sizes[s].h);
                            size_t len = strlen(cfgs[g].patterns[p].text) + strlen(wh) +
                                         strlen(cfgs[g].filters[f].text) + 1 +
                                         strlen(cfgs[g].methods[m].text) +
                                         strlen("-reference-error.png");
                            if (len > NAME_MAX)
                                return aa_fail(
                                    AA_EINVAL,
                                    "the image names of %s on %s %s would be %zu characters "
                                    "long, more than a file name can be (%d): shorter specs, or "
                                    "--no-images",
                                    aa_echo(cfgs[g].methods[m].text),
                                    aa_echo(cfgs[g].patterns[p].text),
                                    aa_echo(cfgs[g].filters[f].text), len, NAME_MAX);
                        }
        /* The image module, loaded now (the images and the montage need it):
         * the address space it takes is in use for the checks below, as it
         * will be when the montage is drawn.  And with it, each view's
         * images (reference, image, error map, the metrics' planes). */
        if (!aa__oiio("montage.png"))
            return AA_EIO;
        long max = images_max(a->images, cfgs, ng);
        for (size_t g = 0; g < ng; g++)
            for (size_t s = 0; s < cfgs[g].nsizes; s++) {
                if (max && (long)cfgs[g].sizes[s].w * cfgs[g].sizes[s].h > max)
                    continue; /* no images of this size */
                if ((st = aa_size_check(cfgs[g].sizes[s].w, cfgs[g].sizes[s].h, 3, 4)))
                    return st;
                if ((st = aa_error_picture_check(cfgs[g].sizes[s].w, cfgs[g].sizes[s].h)))
                    return aa_fail_context(st, "-s %dx%d (or use --no-images)",
                                           cfgs[g].sizes[s].w, cfgs[g].sizes[s].h);
            }
        /* the montage: the first view's reference and up to 63 methods */
        size_t most = cfgs[0].nmethods < 63 ? cfgs[0].nmethods + 1 : 64;
        for (size_t nt = 1; nt <= most; nt++)
            if ((st = aa_montage_check(
                     nt, montage_columns(nt, cfgs[0].sizes[0].w),
                     cfgs[0].sizes[0].w < MONTAGE_SIDE ? cfgs[0].sizes[0].w : MONTAGE_SIDE,
                     cfgs[0].sizes[0].h < MONTAGE_SIDE ? cfgs[0].sizes[0].h : MONTAGE_SIDE,
                     MONTAGE_LINES)))
                return aa_fail_context(st, "montage.png (or use --no-images)");
    }
    /* the output folder, with room for images/NAME under it */
    if (a->out && (st = aa_folder_check("--out", a->out, strlen("/images/") + NAME_MAX)))
        return st;
    if (a->cache && *a->cache && (st = aa_folder_check("--cache", a->cache, 64)))
        return st;
    return AA_OK;
}


/* The run's groups from the plan and options, each checked and set up but
 * for its output folder; every case numbered (case_base) in the whole
 * run's order.  Everything is checked before any work or any file. */
static int prepare(aa_runfolder *rf)
{
    const aa_plan *a = &rf->plan;
    const aa_suite *suite = aa_suite_find(a->suite ? a->suite : "default");
    if (!suite)
        return aa_fail(AA_EINVAL, "unknown suite \"%s\" (quick, default, paper, full, temporal)",
                       aa_echo(a->suite));
    int st = groups_of(a, suite, &rf->o, &rf->opt, rf->cfgs, MAX_GROUPS, &rf->ng);
    if (st)
        return st;
    rf->threads = rf->opt.threads > 0 ? rf->opt.threads : aa_default_threads();
    const aa_suite_motion *mo = aa_suite_motion_find(suite->name);
    double vx = a->vx, vy = a->vy;
    if (mo && !a->motion_given)
        vx = mo->vx, vy = mo->vy;
    rf->cases = 0;
    for (size_t g = 0; g < rf->ng; g++) {
        aa_run_config *c = &rf->cfgs[g];
        c->reps = a->reps;
        c->target_ci = a->target_ci, c->budget = a->budget, c->seeds = a->seeds;
        c->threads = rf->threads;
        c->temporal = mo != NULL;
        c->frames = a->frames ? a->frames : mo ? mo->frames : 0;
        c->window = a->window ? a->window : mo ? mo->window : 0;
        c->isolate = rf->opt.isolate;
        c->case_timeout = rf->opt.case_timeout;
        c->seed = a->seed;
        c->t = a->t, c->vx = vx, c->vy = vy;
        c->cache_dir = rf->opt.cache && *rf->opt.cache ? rf->opt.cache : NULL;
        c->enc = a->enc;
        c->case_base = rf->cases;
        rf->cases += aa_run_case_count(c);
        if ((st = aa_run_check(c)))
            return st;
    }
    return check_before_work(&rf->opt, rf->cfgs, rf->ng);
}

/* The run's manifest (aa_manifest): its command without the words that
 * do not change the results. */
/* The run's input files (aa_manifest.inputs) as they are now: each
 * pattern and method of its groups that reads any, once. */
static void inputs_free(aa_manifest *m)
{
    for (size_t k = 0; k < m->ninputs; k++) {
        free(m->inputs[k].what);
        free(m->inputs[k].inputs);
    }
    free(m->inputs);
    m->inputs = NULL, m->ninputs = 0;
}

static int add_input(aa_manifest *m, size_t cap, const char *kind, const char *text,
                     const aa_spec *spec, const aa_spec *pattern, const aa_spec *method)
{
    char what[1200], buf[sizeof ((aa_row *)0)->inputs];
    if (text)
        snprintf(what, sizeof what, "%s %s", kind, text);
    else {
        int n = snprintf(what, sizeof what, "%s ", kind);
        if (aa_spec_format(spec, what + n, sizeof what - (size_t)n))
            snprintf(what + n, sizeof what - (size_t)n, "%s", spec->info->name);
    }
    for (size_t k = 0; k < m->ninputs; k++)
        if (!strcmp(m->inputs[k].what, what))
            return AA_OK;
    int st = aa_case_inputs(pattern, method, buf, sizeof buf);
    if (st || !*buf || m->ninputs == cap)
        return st;
    struct aa_manifest_input *in = &m->inputs[m->ninputs];
    if (!(in->what = strdup(what)) || !(in->inputs = strdup(buf))) {
        free(in->what);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    m->ninputs++;
    return AA_OK;
}

static int run_inputs(const aa_runfolder *rf, aa_manifest *m)
{
    size_t cap = 0;
    int st = AA_OK;
    m->inputs = NULL, m->ninputs = 0;
    for (size_t g = 0; g < rf->ng; g++)
        cap += rf->cfgs[g].npatterns + rf->cfgs[g].nmethods;
    if (!(m->inputs = calloc(cap ? cap : 1, sizeof *m->inputs)))
        return aa_fail(AA_ENOMEM, "out of memory");
    for (size_t g = 0; g < rf->ng && !st; g++) {
        const aa_run_config *c = &rf->cfgs[g];
        for (size_t k = 0; k < c->npatterns && !st; k++)
            st = add_input(m, cap, "pattern", c->patterns[k].text, &c->patterns[k].spec,
                           &c->patterns[k].spec, NULL);
        for (size_t k = 0; k < c->nmethods && !st; k++)
            st = add_input(m, cap, "method", c->methods[k].text, &c->methods[k].spec, NULL,
                           &c->methods[k].spec);
    }
    if (st)
        inputs_free(m);
    return st;
}

static int write_manifest(aa_runfolder *rf)
{
    aa_manifest m;
    char path[4200];
    int argc = rf->plan.argc, st = AA_OK;
    const char *const *argv = rf->plan.argv;
    if (!argv) {
        if ((st = make_words(rf)))
            return st;
        argc = rf->nwords, argv = (const char *const *)rf->words;
    }
    memset(&m, 0, sizeof m);
    m.argv = calloc((size_t)argc + 1, sizeof *m.argv);
    m.selected = calloc(rf->cases ? rf->cases : 1, sizeof *m.selected);
    if (!m.argv || !m.selected) {
        free(m.argv);
        free(m.selected);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    for (int k = 0; k < argc; k++) {
        int value;
        if (aa_manifest_skips(argv[k], &value))
            k += value;
        else
            m.argv[m.argc++] = (char *)argv[k];
    }
    snprintf(m.suite, sizeof m.suite, "%s", rf->plan.suite);
    snprintf(m.commit, sizeof m.commit, "%s", rf->context.commit);
    snprintf(m.host, sizeof m.host, "%s", rf->context.host);
    m.dirty = rf->context.dirty;
    m.shard = rf->plan.shards ? rf->plan.shard : 1;
    m.shards = rf->plan.shards ? rf->plan.shards : 1;
    m.cases = rf->cases;
    for (size_t g = 0; g < rf->ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&rf->cfgs[g]); k++)
            if (!rf->masks[g] || rf->masks[g][k])
                m.selected[m.nselected++] = rf->cfgs[g].case_base + k;
    m.context = aa_context_json(&rf->context, 0);
    st = m.context ? aa_pathf(path, sizeof path, "%s/run.json", rf->dir)
                   : aa_fail(AA_ENOMEM, "out of memory");
    if (!st)
        st = run_inputs(rf, &m);
    if (!st)
        st = aa_manifest_write(path, &m);
    inputs_free(&m);
    free(m.argv);
    free(m.selected);
    free(m.context);
    return st;
}

/* A resumed run: the rows of its results.csv kept, and their cases taken
 * out of the masks (made when the run had none).  A row that is not one of
 * the folder's cases is refused. */
static int resume_rows(aa_runfolder *rf)
{
    char path[4200];
    aa_row *rows = NULL;
    size_t n = 0, ng = rf->ng;
    aa_run_config *cfgs = rf->cfgs;
    unsigned char **masks = rf->masks;
    /* the files the run was started on (its manifest), as they are now */
    aa_manifest now = {0};
    int st = run_inputs(rf, &now);
    if (!st) {
        for (size_t k = 0; k < rf->manifest.ninputs && !st; k++) {
            const char *is = "none";
            for (size_t q = 0; q < now.ninputs; q++)
                if (!strcmp(now.inputs[q].what, rf->manifest.inputs[k].what))
                    is = now.inputs[q].inputs;
            if (strcmp(is, rf->manifest.inputs[k].inputs))
                st = aa_fail(AA_EINVAL,
                             "%s/run.json: the files of the %s have changed since the run "
                             "started (then %s, now %s): resume it with the same files, or "
                             "start it anew",
                             aa_echo(rf->dir), aa_echo(rf->manifest.inputs[k].what),
                             rf->manifest.inputs[k].inputs, is);
        }
        inputs_free(&now);
    }
    if (st)
        return st;
    st = aa_pathf(path, sizeof path, "%s/results.csv", rf->dir);
    if (st || access(path, F_OK) != 0)
        return st; /* stopped before its first case */
    if ((st = aa_rows_read_csv(path, &rows, &n)))
        return st;
    const aa_manifest *m = &rf->manifest;
    for (size_t g = 0; g < ng && !st; g++)
        if (!masks[g]) {
            size_t c = aa_run_case_count(&cfgs[g]);
            if (!(masks[g] = malloc(c ? c : 1)))
                st = aa_fail(AA_ENOMEM, "out of memory");
            else
                memset(masks[g], 1, c);
        }
    /* a pattern read from files: the files its kept rows were made from */
    for (size_t k = 0; k < n && !st; k++)
        if (!k || strcmp(rows[k].pattern, rows[k - 1].pattern) ||
            strcmp(rows[k].inputs, rows[k - 1].inputs))
            st = aa_inputs_check(path, &rows[k]);
    for (size_t k = 0; k < n && !st; k++) {
        long i = rows[k].case_index;
        size_t g = 0;
        while (g < ng && !(i >= 0 && (size_t)i >= cfgs[g].case_base &&
                           (size_t)i < cfgs[g].case_base + aa_run_case_count(&cfgs[g])))
            g++;
        if (g == ng || !masks[g][(size_t)i - cfgs[g].case_base])
            st = aa_fail(AA_EINVAL,
                         "%s, line %zu: %s on %s %dx%d %s is not a case this run has left to "
                         "measure (case %ld: another run's, or given twice)",
                         path, k + 2, rows[k].method, rows[k].pattern, rows[k].w, rows[k].h,
                         rows[k].filter, i);
        else
            masks[g][(size_t)i - cfgs[g].case_base] = 0;
    }
    /* the cases skipped before as refused are done too */
    for (size_t k = 0; k < m->nrefused && !st; k++)
        for (size_t g = 0; g < ng; g++)
            if (m->refused[k] >= cfgs[g].case_base &&
                m->refused[k] < cfgs[g].case_base + aa_run_case_count(&cfgs[g]))
                masks[g][m->refused[k] - cfgs[g].case_base] = 0;
    if (!st && n && !(st = grow(rf, n))) {
        memcpy(rf->all, rows, n * sizeof *rows);
        rf->nall = rf->kept = n;
    }
    free(rows);
    return st;
}

/* The cases this run skipped as refused, added to those its manifest
 * holds (a resumed run's earlier ones), so that they count as done for a
 * merge and a resume; rf->skipped: all of them. */
static int record_refused(aa_runfolder *rf)
{
    aa_manifest m;
    char path[4200];
    int st = aa_pathf(path, sizeof path, "%s/run.json", rf->dir);
    rf->skipped = 0;
    if (st || (st = aa_manifest_read(path, &m)))
        return st;
    size_t more = 0;
    for (size_t g = 0; g < rf->ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&rf->cfgs[g]); k++)
            more += rf->refused[g][k] != 0;
    size_t *all = realloc(m.refused, (m.nrefused + more + 1) * sizeof *all);
    if (!all) {
        aa_manifest_free(&m);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    m.refused = all;
    for (size_t g = 0; g < rf->ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&rf->cfgs[g]); k++)
            if (rf->refused[g][k])
                m.refused[m.nrefused++] = rf->cfgs[g].case_base + k;
    rf->skipped = m.nrefused;
    if (more)
        st = aa_manifest_write(path, &m);
    aa_manifest_free(&m);
    return st;
}

/* The folder's files as the run leaves them (results.csv and images/),
 * each with its checksum, recorded in its manifest when the run ended
 * (`ended`), so that a merge can tell a shard's files from edited or
 * damaged ones; a run that stopped records none. */
static int record_checksums(aa_runfolder *rf, int ended)
{
    aa_manifest m;
    char path[4200], images[4200];
    int st = aa_pathf(path, sizeof path, "%s/run.json", rf->dir);
    if (st || (st = aa_manifest_read(path, &m)))
        return st;
    for (size_t k = 0; k < m.nsums; k++)
        free(m.sums[k].name);
    m.nsums = 0, m.summed = 0;
    size_t cap = 1;
    DIR *d = NULL;
    if (ended) {
        if (!(st = aa_pathf(images, sizeof images, "%s/images", rf->dir)) &&
            !(d = opendir(images)) && errno != ENOENT)
            st = aa_fail(AA_EIO, "cannot read %s: %s", images, strerror(errno));
        struct dirent *e;
        while (!st && d && (e = readdir(d)))
            cap += e->d_name[0] != '.';
        if (d)
            rewinddir(d);
        struct aa_manifest_sum *sums = st ? NULL : realloc(m.sums, cap * sizeof *sums);
        if (!st && !sums)
            st = aa_fail(AA_ENOMEM, "out of memory");
        if (sums)
            m.sums = sums, m.summed = 1;
        char file[4200];
        if (!st && !(st = aa_pathf(file, sizeof file, "%s/results.csv", rf->dir)) &&
            access(file, F_OK) == 0 && !(st = aa_file_checksum(file, m.sums[0].sum))) {
            if (!(m.sums[0].name = strdup("results.csv")))
                st = aa_fail(AA_ENOMEM, "out of memory");
            else
                m.nsums = 1;
        }
        while (!st && d && (e = readdir(d)) && m.nsums < cap) {
            if (e->d_name[0] == '.')
                continue; /* ., .. and temporary files */
            struct aa_manifest_sum *x = &m.sums[m.nsums];
            if ((st = aa_pathf(file, sizeof file, "%s/%s", images, e->d_name)) ||
                (st = aa_file_checksum(file, x->sum)))
                break;
            size_t len = strlen(e->d_name) + sizeof "images/";
            if (!(x->name = malloc(len))) {
                st = aa_fail(AA_ENOMEM, "out of memory");
                break;
            }
            snprintf(x->name, len, "images/%s", e->d_name);
            m.nsums++;
        }
        if (d)
            closedir(d);
    }
    if (!st)
        st = aa_manifest_write(path, &m);
    aa_manifest_free(&m);
    return st;
}

/* ---- the object ---- */

void aa_runfolder_free(aa_runfolder *rf)
{
    if (!rf)
        return;
    for (size_t g = 0; g < MAX_GROUPS; g++)
        free(rf->masks[g]), free(rf->refused[g]);
    owned_free(&rf->o);
    for (int k = 0; k < rf->nwords; k++)
        free(rf->words[k]);
    if (rf->have_manifest)
        aa_manifest_free(&rf->manifest);
    free(rf->context_argv);
    free(rf->all);
    free(rf);
}

/* The hooks and the caller's settings of `opt` that a folder's own
 * command leaves to the caller. */
static void callers_options(aa_run_options *to, const aa_run_options *opt)
{
    to->cache = opt->cache;
    to->threads = opt->threads;
    to->quiet = opt->quiet;
    to->argc = opt->argc, to->argv = opt->argv;
    to->progress = opt->progress, to->interrupted = opt->interrupted, to->note = opt->note;
    to->hook = opt->hook;
}

/* The plan from the words of a manifest's command ("run" and them), the
 * caller's settings kept. */
static int plan_of_manifest(aa_runfolder *rf, const char *path, const aa_run_options *opt)
{
    const aa_manifest *m = &rf->manifest;
    char **args = calloc((size_t)m->argc + 2, sizeof *args);
    if (!args)
        return aa_fail(AA_ENOMEM, "out of memory");
    args[0] = "run";
    for (int k = 0; k < m->argc; k++)
        args[k + 1] = m->argv[k];
    aa_plan_default(&rf->plan);
    aa_run_options_default(&rf->opt);
    int asked, st = aa_plan_parse(m->argc + 1, args, &rf->plan, &rf->opt, &asked);
    free(args);
    if (!st && asked)
        st = aa_fail(AA_EINVAL, "its command is not a run's");
    if (st)
        return aa_fail_context(st, "%s", path);
    /* the words are the manifest's, kept with the run folder */
    rf->plan.argc = m->argc;
    rf->plan.argv = (const char *const *)m->argv;
    callers_options(&rf->opt, opt);
    rf->opt.resume = NULL;
    return AA_OK;
}

/* Everything but the manifest: the plan checked, the folder made, the
 * cases of the shard chosen, the context collected. */
static int set_up(aa_runfolder *rf)
{
    int st = prepare(rf);
    size_t selected;
    if (!st && rf->plan.shards > 1)
        st = aa_shard_plan(rf->cfgs, rf->ng, rf->plan.shard, rf->plan.shards, rf->masks,
                           &selected, NULL);
    if (st)
        return st;
    if (rf->opt.out) {
        if ((st = aa_pathf(rf->dir, sizeof rf->dir, "%s", rf->opt.out)) ||
            (st = aa_mkdirs(rf->dir)))
            return st;
    } else if ((st = make_run_dir(rf->dir, sizeof rf->dir, &rf->linked))) {
        return st;
    }
    if ((st = aa_pathf(rf->images, sizeof rf->images, "%s/images", rf->dir)))
        return st;
    for (size_t g = 0; g < rf->ng; g++)
        if (!(rf->refused[g] = calloc(aa_run_case_count(&rf->cfgs[g]) + 1, 1)))
            return aa_fail(AA_ENOMEM, "out of memory");
    aa_context_collect(&rf->context, rf->opt.argc, rf->opt.argv, rf->threads);
    const aa_context *c = &rf->context;
    if (rf->opt.note && c->checkout[0] && strcmp(c->checkout, c->commit)) {
        char msg[256];
        snprintf(msg, sizeof msg, "this aabench was built from commit %.12s%s, its checkout is at "
                 "%.12s: the run records the build's (make rebuilds it)", c->commit,
                 c->dirty > 0 ? " (dirty)" : "", c->checkout);
        rf->opt.note(rf->opt.hook, msg);
    }
    return AA_OK;
}

int aa_runfolder_create(const aa_plan *plan, const aa_run_options *opt, aa_runfolder **out)
{
    aa_runfolder *rf = calloc(1, sizeof *rf);
    *out = NULL;
    if (!rf)
        return aa_fail(AA_ENOMEM, "out of memory");
    rf->plan = *plan;
    rf->opt = *opt;
    int st = set_up(rf);
    if (!st)
        st = write_manifest(rf);
    if (st)
        aa_runfolder_free(rf);
    else
        *out = rf;
    return st;
}

/* The commit of this program and of the manifest's run agree. */
static int same_commit(const aa_manifest *m)
{
    /* the program's own build, not the checkout it lives in: a checkout
     * committed to while a run goes on still holds the same program */
    int dirty;
    const char *commit = aa_build_commit(&dirty);
    if (strcmp(commit, m->commit) || (m->dirty >= 0 && dirty >= 0 && m->dirty != dirty))
        return aa_fail(AA_EINVAL,
                       "the run was measured at commit %s%s, this program was built from %s%s: "
                       "resume it with that commit's aabench, or start a new run",
                       m->commit, m->dirty > 0 ? " (dirty)" : "", commit,
                       dirty > 0 ? " (dirty)" : "");
    return AA_OK;
}

int aa_manifest_same_commit(const aa_manifest *m)
{
    return same_commit(m);
}

/* A temporary file's name (aa_temp_name: ".aa-PID-N" and an extension)
 * whose writer is no longer running: left by a run that was killed. */
static int stale_temporary(const char *name)
{
    const char *c = name;
    if (strncmp(c, ".aa-", 4))
        return 0;
    c += 4;
    long pid = 0;
    if (!(*c >= '0' && *c <= '9'))
        return 0;
    while (*c >= '0' && *c <= '9' && pid < 1L << 30)
        pid = pid * 10 + (*c++ - '0');
    if (*c++ != '-' || !(*c >= '0' && *c <= '9'))
        return 0;
    while (*c >= '0' && *c <= '9')
        c++;
    if (*c && *c != '.')
        return 0;
    return pid > 0 && pid < 1L << 30 && kill((pid_t)pid, 0) != 0 && errno == ESRCH;
}

/* Remove the stale temporary files in `dir` and the folders right under
 * it (images/, plots/), regular files only; symbolic links are not
 * followed.  Returns how many were removed. */
static size_t remove_stale(const char *dir, int depth)
{
    DIR *d = opendir(dir);
    size_t removed = 0;
    if (!d)
        return 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        char path[4400];
        struct stat sb;
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") ||
            aa_pathf(path, sizeof path, "%s/%s", dir, e->d_name) || lstat(path, &sb))
            continue;
        if (S_ISDIR(sb.st_mode) && depth == 0)
            removed += remove_stale(path, 1);
        else if (S_ISREG(sb.st_mode) && stale_temporary(e->d_name) && unlink(path) == 0)
            removed++;
    }
    closedir(d);
    return removed;
}

int aa_runfolder_open(const char *dir, const aa_run_options *opt, aa_runfolder **out)
{
    char path[4200];
    aa_runfolder *rf = calloc(1, sizeof *rf);
    *out = NULL;
    if (!rf)
        return aa_fail(AA_ENOMEM, "out of memory");
    int st = aa_pathf(path, sizeof path, "%s/run.json", dir);
    if (!st && !(st = aa_manifest_read(path, &rf->manifest))) {
        rf->have_manifest = 1;
        if ((st = same_commit(&rf->manifest)))
            aa_fail_context(st, "%s", aa_echo(dir));
    }
    if (!st && !(st = plan_of_manifest(rf, path, opt))) {
        rf->plan.shard = rf->manifest.shard;
        rf->plan.shards = rf->manifest.shards > 1 ? rf->manifest.shards : 0;
        rf->opt.out = dir;
        rf->sort = 1;
        if (!(st = set_up(rf))) {
            /* a run killed outright (SIGKILL) leaves its temporary files */
            size_t stale = remove_stale(rf->dir, 0);
            if (stale && rf->opt.note) {
                char msg[160];
                snprintf(msg, sizeof msg, "removed %zu temporary file%s left by a run that was "
                         "killed", stale, stale == 1 ? "" : "s");
                rf->opt.note(rf->opt.hook, msg);
            }
            st = resume_rows(rf);
        }
    }
    if (st)
        aa_runfolder_free(rf);
    else
        *out = rf;
    return st;
}

int aa_runfolder_run(aa_runfolder *rf)
{
    int st = AA_OK;
    if (rf->ran)
        return aa_fail(AA_EINVAL, "%s: the run folder has run (open it again to resume it)",
                       rf->dir);
    rf->ran = 1;
    for (size_t g = 0; g < rf->ng && !st; g++) {
        aa_run_config *c = &rf->cfgs[g];
        c->images_dir = rf->opt.images ? rf->images : NULL;
        c->images_max = images_max(rf->opt.images, rf->cfgs, rf->ng);
        c->progress = progress;
        c->row_done = row_done;
        c->ctx = rf;
        c->only = rf->masks[g];
        /* a suite's cross products pair each method only with the views it
         * takes; a method and a filter both named are run as asked */
        c->skip_refused = !(rf->plan.nmethods && rf->plan.nfilters);
        c->skipped = NULL;
        c->refused = rf->refused[g];
        aa_row *rows = NULL;
        size_t n = 0;
        rf->copied = 0;
        st = aa_run(c, &rows, &n);
        /* the rows aa_run returns, whatever its status */
        int gst = grow(rf, n);
        if (!gst && n) {
            memcpy(rf->all + rf->nall, rows, n * sizeof *rows);
            rf->nall += n;
        } else if (!st) {
            st = gst;
        }
        rf->copied = 0;
        free(rows);
    }
    int rst = record_refused(rf);
    if (!st)
        st = rst;
    if (rf->sort && rf->nall > 1)
        qsort(rf->all, rf->nall, sizeof *rf->all, by_case);
    /* saved after every case already; once more so that a failed group's
     * rows are on disk whatever it stopped at */
    if (rf->nall) {
        int sst = save(rf, rf->all, rf->nall);
        if (!st)
            st = sst;
    }
    int cst = record_checksums(rf, !st);
    if (!st)
        st = cst;
    return st;
}

int aa_runfolder_finish(aa_runfolder *rf)
{
    char plots[4200];
    size_t ran = 0;
    int st = AA_OK;
    for (size_t k = 0; k < rf->nall; k++)
        ran += rf->all[k].ok != 0;
    if (!ran || rf->plan.shards > 1)
        return AA_OK;
    if (rf->opt.images)
        st = write_montage(rf->dir, &rf->cfgs[0], rf->all, rf->nall,
                           images_max(rf->opt.images, rf->cfgs, rf->ng), &rf->plan.enc);
    if (!st && rf->opt.plots && !(st = aa_pathf(plots, sizeof plots, "%s/plots", rf->dir)) &&
        !(st = aa_plot_error_vs_time(plots, rf->all, rf->nall)))
        st = write_convergence(plots, rf, &rf->cfgs[0], rf->threads, rf->all, rf->nall);
    if (!st)
        st = aa_run_report(rf->dir, rf->all, rf->nall);
    return st;
}

const char *aa_runfolder_dir(const aa_runfolder *rf) { return rf->dir; }
size_t aa_runfolder_kept(const aa_runfolder *rf) { return rf->kept; }
size_t aa_runfolder_refused(const aa_runfolder *rf) { return rf->skipped; }
int aa_runfolder_linked(const aa_runfolder *rf) { return rf->linked; }
long aa_runfolder_images_max(const aa_runfolder *rf)
{
    return images_max(rf->opt.images, rf->cfgs, rf->ng);
}
int aa_runfolder_interrupted(const aa_runfolder *rf) { return rf->stopped; }

const aa_row *aa_runfolder_rows(const aa_runfolder *rf, size_t *n)
{
    *n = rf->nall;
    return rf->all;
}

void aa_runfolder_shard(const aa_runfolder *rf, int *k, int *n)
{
    *k = rf->plan.shards > 1 ? rf->plan.shard : 1;
    *n = rf->plan.shards > 1 ? rf->plan.shards : 1;
}

int aa_runfolder_warm(const aa_plan *plan, const aa_run_options *opt, size_t *computed,
                      size_t *cached)
{
    if (!opt->cache || !*opt->cache)
        return aa_fail(AA_EINVAL, "no cache folder to warm");
    aa_runfolder *rf = calloc(1, sizeof *rf);
    if (!rf)
        return aa_fail(AA_ENOMEM, "out of memory");
    rf->plan = *plan;
    rf->opt = *opt;
    rf->opt.images = 0; /* nothing is written but the cache */
    int st = prepare(rf);
    for (size_t g = 0; g < rf->ng && !st; g++)
        st = aa_run_warm(&rf->cfgs[g], computed, cached);
    aa_runfolder_free(rf);
    return st;
}

/* ---- merging shards ---- */

typedef struct merge_shard {
    const char *dir;
    aa_manifest m;
    aa_row *rows;
    size_t n;
} merge_shard;

/* The checksum a shard's manifest records for a file of its folder (NULL:
 * none). */
static const char *sum_of(const aa_manifest *m, const char *name)
{
    for (size_t k = 0; k < m->nsums; k++)
        if (!strcmp(m->sums[k].name, name))
            return m->sums[k].sum;
    return NULL;
}

/* A shard's files are those its run left: results.csv and every image
 * with the checksum its manifest records, no image more or fewer; checked
 * before anything is written. */
static int shard_files_check(const merge_shard *sh)
{
    const aa_manifest *m = &sh->m;
    char path[4200], images[4200], sum[64];
    if (!m->summed)
        return aa_fail(AA_EINVAL,
                       "%s/run.json records no checksums of its files: its run has not ended "
                       "(resume it with aabench run --resume %s)",
                       aa_echo(sh->dir), aa_echo(sh->dir));
    int st = aa_pathf(path, sizeof path, "%s/results.csv", sh->dir);
    if (st)
        return st;
    const char *want = sum_of(m, "results.csv");
    int there = access(path, F_OK) == 0;
    if (there != (want != NULL))
        return aa_fail(AA_EINVAL, "%s: %s", aa_echo(path),
                       there ? "its run wrote none (a file added after it ended)"
                             : "missing, though its run wrote it");
    if (there && ((st = aa_file_checksum(path, sum)) || strcmp(sum, want)))
        return st ? st
                  : aa_fail(AA_EINVAL,
                            "%s is not the file its run wrote (%s, the run recorded %s): edited "
                            "or damaged",
                            aa_echo(path), sum, want);
    if ((st = aa_pathf(images, sizeof images, "%s/images", sh->dir)))
        return st;
    size_t seen = 0, listed = 0;
    for (size_t k = 0; k < m->nsums; k++)
        listed += !strncmp(m->sums[k].name, "images/", 7);
    DIR *d = opendir(images);
    if (!d && errno != ENOENT)
        return aa_fail(AA_EIO, "cannot read %s: %s", images, strerror(errno));
    struct dirent *e;
    while (!st && d && (e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char name[512];
        snprintf(name, sizeof name, "images/%.500s", e->d_name);
        want = sum_of(m, name);
        if ((st = aa_pathf(path, sizeof path, "%s/%s", images, e->d_name)))
            break;
        if (!want)
            st = aa_fail(AA_EINVAL, "%s: its run wrote no such image (a file added after it ended)",
                         aa_echo(path));
        else if (!(st = aa_file_checksum(path, sum)) && strcmp(sum, want))
            st = aa_fail(AA_EINVAL,
                         "%s is not the image its run wrote (%s, the run recorded %s): edited or "
                         "damaged",
                         aa_echo(path), sum, want);
        seen++;
    }
    if (d)
        closedir(d);
    if (!st && seen != listed)
        st = aa_fail(AA_EINVAL, "%s: %zu of the %zu images its run wrote are missing",
                     aa_echo(images), listed - seen, listed);
    return st;
}

/* The arguments of a manifest's command, joined for messages. */
static void command_text(const aa_manifest *m, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; k < m->argc && n + 1 < len; k++)
        n += (size_t)snprintf(buf + n, len - n, "%s%s", k ? " " : "", m->argv[k]);
}

static int same_command(const aa_manifest *a, const aa_manifest *b)
{
    if (a->argc != b->argc)
        return 0;
    for (int k = 0; k < a->argc; k++)
        if (strcmp(a->argv[k], b->argv[k]))
            return 0;
    return 1;
}

/* Where a case's row is: its folder and its row there. */
typedef struct place {
    int shard; /* -1: nowhere yet */
    size_t row; /* REFUSED: skipped by the run, its method refusing the view */
} place;
#define REFUSED ((size_t)-1)

/* Every check before anything is written: the manifests agree, and the
 * rows hold each case of the run exactly once.  *owner (malloc'd) gives
 * each case's place. */
static int check_shards(merge_shard *s, int ns, place **owner_out)
{
    char a[2048], b[2048];
    const aa_manifest *first = &s[0].m;
    *owner_out = NULL;
    for (int i = 1; i < ns; i++) {
        const aa_manifest *m = &s[i].m;
        if (!same_command(m, first)) {
            command_text(first, a, sizeof a);
            command_text(m, b, sizeof b);
            return aa_fail(AA_EINVAL, "%s is not a shard of the run of %s: its command is \"%s\", not "
                          "\"%s\"",
                          aa_echo(s[i].dir), s[0].dir, b, a);
        }
        if (strcmp(m->suite, first->suite))
            return aa_fail(AA_EINVAL, "%s is not a shard of the run of %s: its suite is %s, not %s",
                          aa_echo(s[i].dir), s[0].dir, m->suite, first->suite);
        if (strcmp(m->commit, first->commit) || m->dirty != first->dirty)
            return aa_fail(AA_EINVAL, "%s is not a shard of the run of %s: it was measured at commit "
                          "%s%s, not %s%s",
                          aa_echo(s[i].dir), s[0].dir, m->commit, m->dirty > 0 ? " (dirty)" : "",
                          first->commit, first->dirty > 0 ? " (dirty)" : "");
        if (m->cases != first->cases)
            return aa_fail(AA_EINVAL, "%s is not a shard of the run of %s: %zu cases, not %zu",
                          aa_echo(s[i].dir), s[0].dir, m->cases, first->cases);
        for (size_t k = 0; k < first->ninputs || k < m->ninputs; k++) {
            const struct aa_manifest_input *x = k < first->ninputs ? &first->inputs[k] : NULL,
                                           *y = k < m->ninputs ? &m->inputs[k] : NULL;
            if (!x || !y || strcmp(x->what, y->what) || strcmp(x->inputs, y->inputs))
                return aa_fail(AA_EINVAL,
                               "%s is not a shard of the run of %s: the files of the %s differ "
                               "(%s; %s): shards of two scenes or methods",
                               aa_echo(s[i].dir), s[0].dir, (x ? x : y)->what,
                               x ? x->inputs : "none", y ? y->inputs : "none");
        }
        for (int j = 0; j < i; j++)
            if (s[j].m.shards == m->shards && s[j].m.shard == m->shard)
                return aa_fail(AA_EINVAL, "%s and %s are both shard %d/%d: a shard given twice",
                              aa_echo(s[j].dir), s[i].dir, m->shard, m->shards);
    }
    size_t cases = first->cases;
    place *owner = malloc((cases ? cases : 1) * sizeof *owner);
    int *planned = malloc((cases ? cases : 1) * sizeof *planned);
    if (!owner || !planned) {
        free(owner);
        free(planned);
        return aa_fail(AA_ENOMEM, "out of memory for %zu cases", cases);
    }
    for (size_t c = 0; c < cases; c++)
        owner[c].shard = -1, planned[c] = -1;
    int code = 0;
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].m.nselected; k++)
            planned[s[i].m.selected[k]] = i;
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].n && !code; k++) {
            const aa_row *r = &s[i].rows[k];
            long c = r->case_index;
            if (c < 0 || (size_t)c >= cases)
                code = aa_fail(AA_EINVAL, "%s/results.csv, line %zu: %s on %s %dx%d %s has no case of the "
                              "run (%ld)",
                              aa_echo(s[i].dir), k + 2, r->method, r->pattern, r->w, r->h,
                              r->filter, c);
            else if (owner[c].shard >= 0)
                code = aa_fail(AA_EINVAL, "%s on %s %dx%d %s (case %ld) is in both %s and %s: a duplicated "
                              "shard",
                              r->method, r->pattern, r->w, r->h, r->filter, c,
                              s[owner[c].shard].dir, aa_echo(s[i].dir));
            else
                owner[c].shard = i, owner[c].row = k;
        }
    /* the cases skipped as refused: done, without rows */
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].m.nrefused && !code; k++) {
            size_t c = s[i].m.refused[k];
            if (owner[c].shard >= 0)
                code = aa_fail(AA_EINVAL, "case %zu is in both %s and %s: a duplicated shard", c,
                              s[owner[c].shard].dir, aa_echo(s[i].dir));
            else
                owner[c].shard = i, owner[c].row = REFUSED;
        }
    /* what is missing: a folder that stopped early, or a shard not given */
    for (size_t c = 0; c < cases && !code; c++) {
        if (owner[c].shard >= 0)
            continue;
        size_t left = 0;
        for (size_t d = c; d < cases; d++)
            left += owner[d].shard < 0;
        if (planned[c] >= 0) {
            const merge_shard *sh = &s[planned[c]];
            code = aa_fail(AA_EINVAL, "%s (shard %d/%d) has not measured all its cases (%zu missing): "
                          "resume it with aabench run --resume %s",
                          aa_echo(sh->dir), sh->m.shard, sh->m.shards, left, sh->dir);
        } else {
            char missing[1024] = "";
            size_t n = 0;
            for (int k = 1; k <= first->shards && n + 1 < sizeof missing; k++) {
                int given = 0;
                for (int i = 0; i < ns; i++)
                    given |= s[i].m.shards == first->shards && s[i].m.shard == k;
                if (!given)
                    n += (size_t)snprintf(missing + n, sizeof missing - n, "%s%d/%d",
                                          n ? ", " : "", k, first->shards);
            }
            code = aa_fail(AA_EINVAL, "%zu case%s of the run %s in no folder given: shard%s %s missing",
                          left, left == 1 ? "" : "s", left == 1 ? "is" : "are",
                          strchr(missing, ',') ? "s" : "", *missing ? missing : "(of another count)");
        }
    }
    free(planned);
    if (code)
        free(owner);
    else
        *owner_out = owner;
    return code;
}

/* images/ of each shard into the merged folder's (the references each
 * shard wrote for its views are the same files). */
static int copy_images(const char *from, const char *to)
{
    char src[4200], dst[4200];
    int st = aa_pathf(src, sizeof src, "%s/images", from);
    if (st)
        return st;
    DIR *d = opendir(src);
    if (!d)
        return errno == ENOENT ? AA_OK : aa_fail(AA_EIO, "cannot read %s: %s", src, strerror(errno));
    if ((st = aa_pathf(dst, sizeof dst, "%s/images", to)) || (st = aa_mkdirs(dst))) {
        closedir(d);
        return st;
    }
    struct dirent *e;
    while (!st && (e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue; /* ., .. and temporary files */
        char a[4200], b[4200];
        if ((st = aa_pathf(a, sizeof a, "%s/%s", src, e->d_name)) ||
            (st = aa_pathf(b, sizeof b, "%s/%s", dst, e->d_name)))
            break;
        FILE *f = fopen(a, "rb");
        if (!f) {
            st = aa_fail(AA_EIO, "cannot read %s: %s", a, strerror(errno));
            break;
        }
        char *buf = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&buf, &len);
        char chunk[65536];
        size_t k;
        while (m && (k = fread(chunk, 1, sizeof chunk, f)) > 0)
            if (fwrite(chunk, 1, k, m) != k)
                break;
        int bad = ferror(f);
        fclose(f);
        if (!m || fclose(m) != 0 || bad)
            st = aa_fail(AA_EIO, "cannot read %s", a);
        else
            st = aa_file_write_atomic(b, buf, len);
        free(buf);
    }
    closedir(d);
    return st;
}

/* The merged folder's manifest: the whole run, one part, measured by the
 * shards' commit and written on this machine. */
static int write_merged_manifest(const char *out, const aa_manifest *first, size_t cases,
                                 size_t *refused, size_t nrefused)
{
    aa_manifest m = *first;
    aa_context context;
    m.summed = 0, m.nsums = 0, m.sums = NULL; /* the shards' files, not this folder's */
    char path[4200];
    int st;
    aa_context_collect(&context, 0, NULL, 0);
    m.shard = m.shards = 1;
    m.selected = malloc((cases ? cases : 1) * sizeof *m.selected);
    m.nselected = cases;
    m.refused = refused, m.nrefused = nrefused;
    snprintf(m.host, sizeof m.host, "%s", context.host);
    m.context = aa_context_json(&context, 0); /* the merging machine's */
    for (size_t k = 0; m.selected && k < cases; k++)
        m.selected[k] = k;
    if (!m.selected)
        st = aa_fail(AA_ENOMEM, "out of memory");
    else if (!(st = aa_pathf(path, sizeof path, "%s/run.json", out)))
        st = aa_manifest_write(path, &m);
    free(m.selected);
    free(m.context);
    return st;
}

/* The text a run gives a spec in its rows (run.c): as given, else its
 * canonical text. */
static void spec_shown(const char *text, const aa_spec *spec, char *buf, size_t len)
{
    if (text)
        snprintf(buf, len, "%s", text);
    else if (aa_spec_format(spec, buf, len))
        snprintf(buf, len, "%s", spec->info->name);
}

/* A shard's row is the case it claims, case c of the run: the pattern,
 * size, filter and method of that case (the run's order: group, then
 * pattern, size, filter, method), its time, motion and seed, and a
 * canonical name that is the method's (a row may lack it only when it did
 * not run). */
static int row_is_case(const aa_runfolder *rf, const merge_shard *sh, const aa_row *r, size_t c)
{
    size_t g = 0;
    while (g < rf->ng && !(c >= rf->cfgs[g].case_base &&
                           c < rf->cfgs[g].case_base + aa_run_case_count(&rf->cfgs[g])))
        g++;
    if (g == rf->ng)
        return aa_fail(AA_EINVAL, "%s/results.csv: case %zu is not one of the run's",
                       aa_echo(sh->dir), c);
    const aa_run_config *cfg = &rf->cfgs[g];
    size_t k = c - cfg->case_base, nm = cfg->nmethods, nf = cfg->nfilters, nz = cfg->nsizes;
    const aa_run_spec *m = &cfg->methods[k % nm];
    const aa_run_filter *f = &cfg->filters[(k / nm) % nf];
    const aa_run_size *z = &cfg->sizes[(k / (nm * nf)) % nz];
    const aa_run_spec *p = &cfg->patterns[k / (nm * nf * nz)];
    char pattern[sizeof r->pattern], filter[sizeof r->filter], method[sizeof r->method];
    char canonical[sizeof r->canonical], why[640] = "";
    spec_shown(p->text, &p->spec, pattern, sizeof pattern);
    spec_shown(f->text, &f->filter.spec, filter, sizeof filter);
    spec_shown(m->text, &m->spec, method, sizeof method);
    if (aa_spec_format(&m->spec, canonical, sizeof canonical))
        canonical[0] = '\0';
    if (strcmp(r->pattern, pattern) || strcmp(r->filter, filter) || strcmp(r->method, method) ||
        r->w != z->w || r->h != z->h)
        snprintf(why, sizeof why, "case %zu of the run is %.120s on %.120s %dx%d %.60s", c,
                 method, pattern, z->w, z->h, filter);
    else if ((r->ok || *r->canonical) && strcmp(r->canonical, canonical))
        snprintf(why, sizeof why, "its canonical name \"%.100s\" is not the method's, \"%.100s\"",
                 r->canonical, canonical);
    else if (r->t != cfg->t || r->vx != cfg->vx || r->vy != cfg->vy || r->seed != cfg->seed)
        snprintf(why, sizeof why,
                 "its time, motion or seed (%g, %g %g, %llu) is not the run's (%g, %g %g, %llu)",
                 r->t, r->vx, r->vy, (unsigned long long)r->seed, cfg->t, cfg->vx, cfg->vy,
                 (unsigned long long)cfg->seed);
    if (!*why)
        return AA_OK;
    return aa_fail(AA_EINVAL, "%s/results.csv: the row of %s on %s %dx%d %s (case %zu) is not its "
                   "case: %s",
                   aa_echo(sh->dir), aa_echo(r->method), aa_echo(r->pattern), r->w, r->h,
                   aa_echo(r->filter), c, why);
}

/* A shard holds the cases the run's plan gives its shard K/N, no more, no
 * fewer: its manifest's count and selection are those aa_shard_plan makes
 * of the run's command. */
static int shard_is_planned(const aa_runfolder *rf, const char *dir, const aa_manifest *m)
{
    unsigned char *masks[MAX_GROUPS] = {0};
    size_t selected = 0;
    int st = aa_shard_plan(rf->cfgs, rf->ng, m->shard, m->shards, masks, &selected, NULL);
    if (st)
        return aa_fail_context(st, "%s/run.json", aa_echo(dir));
    int bad = selected != m->nselected;
    for (size_t k = 0; k < m->nselected && !bad; k++) {
        size_t c = m->selected[k], g = 0;
        while (g < rf->ng && !(c >= rf->cfgs[g].case_base &&
                               c < rf->cfgs[g].case_base + aa_run_case_count(&rf->cfgs[g])))
            g++;
        bad = g == rf->ng || !masks[g][c - rf->cfgs[g].case_base];
    }
    for (size_t g = 0; g < rf->ng; g++)
        free(masks[g]);
    if (bad)
        return aa_fail(AA_EINVAL, "%s/run.json: its cases (%zu) are not those of shard %d/%d of "
                       "the run (%zu): an edited manifest",
                       aa_echo(dir), m->nselected, m->shard, m->shards, selected);
    return AA_OK;
}

/* The merged run's plan (the first shard's command), checked against the
 * shards' cases and each row against its case; its rows in the run's
 * order. */
static int merged_run(aa_runfolder *rf, merge_shard *s, int ns, const place *owner,
                      size_t cases, size_t **refused, size_t *nrefused, const aa_run_options *opt)
{
    char path[4200];
    int st = aa_pathf(path, sizeof path, "%s/run.json", s[0].dir);
    rf->manifest = s[0].m; /* its words are the plan's */
    rf->have_manifest = 1;
    memset(&s[0].m, 0, sizeof s[0].m);
    if (!st)
        st = plan_of_manifest(rf, path, opt);
    if (st)
        return st;
    rf->opt.out = opt->out;
    rf->plan.shard = rf->plan.shards = 0; /* the whole run */
    if ((st = prepare(rf)))
        return st;
    if (rf->cases != cases)
        return aa_fail(AA_EINVAL, "the run's command has %zu cases, its shards' manifests %zu",
                       rf->cases, cases);
    for (int i = 0; i < ns; i++)
        if ((st = shard_is_planned(rf, s[i].dir, i ? &s[i].m : &rf->manifest)))
            return st;
    for (size_t k = 0; k < cases; k++)
        if (owner[k].row != REFUSED &&
            (st = row_is_case(rf, &s[owner[k].shard], &s[owner[k].shard].rows[owner[k].row], k)))
            return st;
    /* the shards were made from the same input files (an SVG, a font, a
     * plug-in) */
    for (int i = 0; i < ns; i++)
        for (size_t k = 0; k < s[i].n; k++) {
            const aa_row *r = &s[i].rows[k];
            for (int j = 0; j <= i; j++)
                for (size_t q = 0; q < (j < i ? s[j].n : k); q++)
                    if (!strcmp(s[j].rows[q].pattern, r->pattern) &&
                        !strcmp(s[j].rows[q].method, r->method)) {
                        if (strcmp(s[j].rows[q].inputs, r->inputs))
                            return aa_fail(AA_EINVAL,
                                           "%s and %s were made from different files of %s "
                                           "on %s (%s; %s): shards of two scenes or methods",
                                           aa_echo(s[j].dir), aa_echo(s[i].dir),
                                           aa_echo(r->method), aa_echo(r->pattern),
                                           *s[j].rows[q].inputs ? s[j].rows[q].inputs : "none",
                                           *r->inputs ? r->inputs : "none");
                        goto next_row; /* the first row of its pattern decides */
                    }
        next_row:;
        }
    if (!(rf->all = malloc((cases ? cases : 1) * sizeof *rf->all)) ||
        !(*refused = malloc((cases ? cases : 1) * sizeof **refused)))
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", cases);
    rf->cap = cases ? cases : 1;
    for (size_t k = 0; k < cases; k++) {
        if (owner[k].row == REFUSED)
            (*refused)[(*nrefused)++] = k;
        else
            rf->all[rf->nall++] = s[owner[k].shard].rows[owner[k].row];
    }
    if (rf->cases != rf->nall + *nrefused)
        return aa_fail(AA_EINVAL, "the run's command has %zu cases, the shards %zu", rf->cases,
                       rf->nall + *nrefused);
    /* the context's command: "run", the run's words, the caller's */
    const char **argv = calloc((size_t)rf->manifest.argc + (size_t)opt->argc + 2, sizeof *argv);
    if (!(rf->context_argv = argv))
        return aa_fail(AA_ENOMEM, "out of memory");
    int argc = 0;
    argv[argc++] = "run";
    for (int k = 0; k < rf->manifest.argc; k++)
        argv[argc++] = rf->manifest.argv[k];
    for (int k = 0; k < opt->argc; k++)
        argv[argc++] = opt->argv[k];
    aa_context_collect(&rf->context, argc, argv, rf->threads);
    rf->sort = 1;
    rf->ran = 1;
    rf->skipped = *nrefused;
    return aa_pathf(rf->dir, sizeof rf->dir, "%s", opt->out);
}

int aa_runfolder_merge(const char *const *dirs, size_t ndirs, const aa_run_options *opt,
                       aa_runfolder **out)
{
    *out = NULL;
    int ns = (int)ndirs, st;
    if (ndirs < 1 || ndirs > INT_MAX)
        return aa_fail(AA_EINVAL, "no shard's folder given");
    if ((st = aa_folder_check("--out", opt->out, strlen("/images/") + 256)))
        return st;
    /* the merged folder is none of the shards' (their files would be
     * overwritten) */
    char real_out[PATH_MAX], real_dir[PATH_MAX];
    if (realpath(opt->out, real_out))
        for (int i = 0; i < ns; i++)
            if (realpath(dirs[i], real_dir) && !strcmp(real_out, real_dir))
                return aa_fail(AA_EINVAL,
                               "--out %s is one of the shards' folders: merge into another",
                               aa_echo(opt->out));
    merge_shard *s = calloc((size_t)ns, sizeof *s);
    aa_runfolder *rf = calloc(1, sizeof *rf);
    if (!s || !rf) {
        free(s);
        free(rf);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    for (int i = 0; i < ns && !st; i++) {
        char path[4200];
        s[i].dir = dirs[i];
        if ((st = aa_pathf(path, sizeof path, "%s/run.json", s[i].dir)))
            break;
        if ((st = aa_manifest_read(path, &s[i].m)) == AA_EIO)
            st = aa_fail(AA_EINVAL, "%s is not a run's folder: %s", aa_echo(s[i].dir),
                         aa_last_error());
        else if (!st && !(st = aa_pathf(path, sizeof path, "%s/results.csv", s[i].dir)) &&
                 access(path, F_OK) == 0 &&
                 (st = aa_rows_read_csv(path, &s[i].rows, &s[i].n)) == AA_EIO)
            st = AA_EINVAL;
    }
    place *owner = NULL;
    size_t *refused = NULL, nrefused = 0, cases = 0;
    if (!st && !(st = check_shards(s, ns, &owner)))
        for (int i = 0; i < ns && !st; i++)
            st = shard_files_check(&s[i]);
    if (!st) {
        cases = s[0].m.cases;
        st = merged_run(rf, s, ns, owner, cases, &refused, &nrefused, opt);
    }
    if (!st)
        st = aa_mkdirs(opt->out);
    for (int i = 0; i < ns && !st; i++)
        st = copy_images(s[i].dir, opt->out);
    if (!st)
        st = write_merged_manifest(opt->out, &rf->manifest, cases, refused, nrefused);
    if (!st && rf->nall)
        st = save(rf, rf->all, rf->nall);
    free(refused);
    free(owner);
    for (int i = 0; i < ns; i++) {
        aa_manifest_free(&s[i].m);
        free(s[i].rows);
    }
    free(s);
    if (st)
        aa_runfolder_free(rf);
    else
        *out = rf;
    return st;
}
