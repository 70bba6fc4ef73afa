/*
 * cmd_run.c: `aabench run`: the benchmark's main job.
 *
 * Runs a suite (or the patterns, sizes, filters and methods given) and writes
 * into results/runs/<UTC time>/ (results/latest points there) or --out DIR:
 * results.csv and results.json (rewritten after every case, atomically, so
 * an interrupted run keeps what it measured and no file is half-written),
 * images/ (EXR values, PNG for eyes, error maps), montage.png (the first
 * view's reference and methods side by side, labelled with name and RMSE),
 * plots/error_vs_time.png and plots/convergence.png.  At the end a table on
 * the terminal sorted by error; a progress bar on standard error while it
 * runs, when that is a terminal and CI is not set.
 */
#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define MAX_LIST 256

static volatile sig_atomic_t interrupted;

/* The first interrupt stops after the current case, with every file
 * complete; a second one quits at once. */
static void on_signal(int sig)
{
    static const char msg[] = "\naabench run: stopping after this case (again to quit now)\n";
    if (interrupted)
        _exit(130);
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
            "or DIR.  -p, -m, -s, -f may be repeated; given, they replace the suite's lists.\n"
            "A method runs only with the filters and scenes it takes (one line counts the\n"
            "pairs left out) unless -m and -f are both given.\n\n"
            "  --suite NAME      quick, default (the default), paper, full, vector or temporal\n"
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
            "  --no-images       do not write images/ and montage.png\n"
            "  --no-plots        do not draw plots/ (no convergence either)\n"
            "  --cache DIR       reference cache (default results/cache); --no-cache\n"
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

typedef struct list {
    const char *v[MAX_LIST];
    size_t n;
} list;

typedef struct run_args {
    const char *suite, *out, *cache;
    list p, m, s, f;
    int reps, threads, images, plots, quiet;
    int frames, window, motion_given;
    int isolate;          /* AA_ISOLATE_* */
    double case_timeout;  /* seconds */
    uint64_t seed;
    double t, vx, vy;
    aa_encode enc;
    double target_ci, budget;
    int seeds;
    int shard, shards;    /* --shard K/N; 0/0 unsharded */
    const char *resume;   /* --resume DIR */
} run_args;

static int push(list *l, const char *v, const char *what)
{
    if (l->n == MAX_LIST)
        return aa_fail(AA_EINVAL, "more than %d %s given", MAX_LIST, what);
    l->v[l->n++] = v;
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

static int parse(int argc, char **argv, run_args *a)
{
    enum { O_SUITE = 256, O_REPS, O_OUT, O_THREADS, O_SEED, O_TIME, O_MOTION, O_ENCODE,
           O_PLUGIN, O_NOIMAGES, O_NOPLOTS, O_CACHE, O_NOCACHE, O_LIST, O_FRAMES, O_WINDOW,
           O_TARGET, O_BUDGET, O_SEEDS, O_ISOLATE, O_NOISOLATE, O_CASE_TIMEOUT, O_SHARD,
           O_RESUME };
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
        {0, 0, 0, 0}};
    int c, st = AA_OK;
    cli_getopt_reset();
    while ((c = getopt_long(argc, argv, ":p:m:s:f:qh", opts, NULL)) != -1) {
        switch (c) {
        case O_SUITE: a->suite = optarg; break;
        case 'p': st = push(&a->p, optarg, "patterns"); break;
        case 'm': st = push(&a->m, optarg, "methods"); break;
        case 's': st = push(&a->s, optarg, "sizes"); break;
        case 'f': st = push(&a->f, optarg, "filters"); break;
        case O_REPS: st = cli_parse_int("--reps", optarg, 1, 1000, &a->reps); break;
        case O_OUT: a->out = optarg; break;
        case O_THREADS: st = cli_parse_int("--threads", optarg, 1, 1024, &a->threads); break;
        case O_SEED: st = cli_parse_seed(optarg, &a->seed); break;
        case O_TIME: st = cli_parse_real("--time", optarg, -1e9, 1e9, &a->t); break;
        case O_MOTION:
            st = cli_parse_pair("--motion", optarg, -1e6, 1e6, &a->vx, &a->vy);
            a->motion_given = 1;
            break;
        case O_FRAMES:
            st = cli_parse_int("--frames", optarg, 2, AA_TEMPORAL_MAX_FRAMES, &a->frames);
            break;
        case O_WINDOW:
            st = cli_parse_int("--window", optarg, 1, AA_TEMPORAL_MAX_FRAMES, &a->window);
            break;
        case O_ENCODE: st = aa_encode_parse(optarg, &a->enc); break;
        case O_TARGET: st = cli_parse_target(optarg, &a->target_ci); break;
        case O_BUDGET: st = cli_parse_budget(optarg, &a->budget); break;
        case O_SEEDS: st = cli_parse_int("--seeds", optarg, 1, 1000, &a->seeds); break;
        case O_PLUGIN: st = aa_plugin_load(optarg); break;
        case O_NOIMAGES: a->images = 0; break;
        case O_NOPLOTS: a->plots = 0; break;
        case O_CACHE: a->cache = optarg; break;
        case O_NOCACHE: a->cache = ""; break;
        case 'q': a->quiet = 1; break;
        case O_ISOLATE: a->isolate = AA_ISOLATE_ALL; break;
        case O_NOISOLATE: a->isolate = AA_ISOLATE_NONE; break;
        case O_CASE_TIMEOUT:
            st = cli_parse_real("--case-timeout", optarg, 0.001, 1e9, &a->case_timeout);
            break;
        case O_SHARD: st = parse_shard(optarg, &a->shard, &a->shards); break;
        case O_RESUME: a->resume = optarg; break;
        case O_LIST:
            for (const aa_suite *s = aa_suites; s->name; s++)
                printf("%s\t%s\n", s->name, s->summary);
            return 0;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("run", c, argv);
        }
        if (st)
            return cli_fail("run", st);
    }
    if (optind < argc) {
        fprintf(stderr, "aabench run: unexpected argument \"%s\"\n", aa_echo(argv[optind]));
        return 2;
    }
    return -1;
}

/* ---- output folder ---- */

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

typedef struct run_ctx {
    const char *dir;
    int bar;
    double t0;
    const aa_context *context; /* results.json's */
    /* every row so far: those of the groups run (nall) and of the one under
     * way (copied of them), saved after every case */
    aa_row *all;
    size_t nall, cap, copied;
    int sort; /* resumed: rows saved in the run's order (case_index) */
    size_t skipped; /* cases skipped as refused, this run's whole */
} run_ctx;

static int progress(void *vctx, size_t done, size_t total, const char *what)
{
    run_ctx *ctx = vctx;
    if (ctx->bar) {
        const int width = 30;
        int fill = total ? (int)(width * done / total) : width;
        double el = aa_now() - ctx->t0;
        fprintf(stderr, "\r\033[K[%.*s%*s] %zu/%zu %5.0fs %.60s", fill,
                "==============================", width - fill, "", done, total, el, what);
        if (done == total)
            fprintf(stderr, "\n");
        fflush(stderr);
    }
    return interrupted != 0;
}

static int by_case(const void *a, const void *b)
{
    const aa_row *x = a, *y = b;
    return x->case_index < y->case_index ? -1 : x->case_index > y->case_index;
}

static int save_rows(run_ctx *ctx, const aa_row *rows, size_t n);

static int save(void *vctx, const aa_row *rows, size_t n)
{
    run_ctx *ctx = vctx;
    if (!ctx->sort || n < 2)
        return save_rows(ctx, rows, n);
    /* a resumed run's rows, the kept and the new, in the run's order */
    aa_row *sorted = malloc(n * sizeof *sorted);
    if (!sorted)
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", n);
    memcpy(sorted, rows, n * sizeof *rows);
    qsort(sorted, n, sizeof *sorted, by_case);
    int st = save_rows(ctx, sorted, n);
    free(sorted);
    return st;
}

/* results.json first, results.csv last: a case in results.csv (which
 * resume, merge, diff and check read) is in results.json too, however the
 * run is stopped. */
static int save_rows(run_ctx *ctx, const aa_row *rows, size_t n)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/results.json", ctx->dir);
    if (!st && !(st = aa_results_write_json(path, ctx->context, rows, n)) &&
        !(st = aa_pathf(path, sizeof path, "%s/results.csv", ctx->dir)))
        st = aa_rows_write_csv(path, rows, n);
    return st;
}

/* Room in ctx->all for `more` rows after those kept. */
static int grow(run_ctx *ctx, size_t more)
{
    size_t need = ctx->nall + more;
    if (need <= ctx->cap)
        return AA_OK;
    size_t cap = ctx->cap ? ctx->cap : 64;
    while (cap < need)
        cap *= 2;
    aa_row *p = realloc(ctx->all, cap * sizeof *p);
    if (!p)
        return aa_fail(AA_ENOMEM, "out of memory for %zu results", need);
    ctx->all = p;
    ctx->cap = cap;
    return AA_OK;
}

/* After every case (aa_run_config.row_done): the rows of the earlier
 * groups and the group's so far, written out, so that a run that is
 * killed, or fails, keeps every case it measured. */
static int row_done(void *vctx, const aa_row *rows, size_t n)
{
    run_ctx *ctx = vctx;
    int st = grow(ctx, n);
    if (st)
        return st;
    memcpy(ctx->all + ctx->nall + ctx->copied, rows + ctx->copied,
           (n - ctx->copied) * sizeof *rows);
    ctx->copied = n;
    return save(ctx, ctx->all, ctx->nall + n);
}

/* ---- what runs after the cases ---- */

/* montage.png: the first view's reference and every method, side by side. */

#define MONTAGE_TILES 64
#define MONTAGE_LINES 2

/* Its columns, for n tiles of width w. */
static int montage_columns(size_t n, int w)
{
    if (w <= 160)
        return n <= 6 ? (int)n : 6;
    return n <= 4 ? (int)n : (n <= 9 ? 3 : 4);
}

/* Its tiles, each read when the montage asks for it and freed once copied:
 * the reference (from the cache), then each method's EXR written by the
 * run. */
typedef struct montage_source {
    const char *dir;
    const char *cache; /* the run's reference cache (NULL: --no-cache) */
    const aa_row *rows;
    size_t row[MONTAGE_TILES]; /* tile k > 0 is rows[row[k]] */
    aa_view view;
    aa_image im;
    char labels[MONTAGE_LINES][128];
} montage_source;

static int montage_get(void *vctx, size_t k, aa_tile *tile)
{
    montage_source *s = vctx;
    int st;
    if (k == 0) {
        if ((st = aa_reference(&s->view, s->cache, 0, &s->im, NULL, NULL)))
            return st;
        snprintf(s->labels[0], 128, "reference (%.100s)", s->rows[0].filter);
        snprintf(s->labels[1], 128, "exact");
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
    }
    tile->image = &s->im;
    tile->label[0] = s->labels[0];
    tile->label[1] = s->labels[1];
    tile->label[2] = NULL;
    return AA_OK;
}

static void montage_put(void *vctx, size_t k)
{
    (void)k;
    aa_image_free(&((montage_source *)vctx)->im);
}

static int write_montage(const char *dir, const aa_run_config *first, const aa_row *rows,
                         size_t n, const aa_encode *enc)
{
    if (n == 0)
        return AA_OK;
    montage_source s;
    memset(&s, 0, sizeof s);
    s.dir = dir, s.rows = rows, s.cache = first->cache_dir;
    int st;
    s.view.pattern = first->patterns[0].spec;
    s.view.filter = first->filters[0].filter;
    s.view.w = rows[0].w, s.view.h = rows[0].h;
    s.view.t = rows[0].t, s.view.vx = rows[0].vx, s.view.vy = rows[0].vy;
    size_t nt = 1;
    for (size_t k = 0; k < n && nt < MONTAGE_TILES; k++)
        if (rows[k].ok && !strcmp(rows[k].pattern, rows[0].pattern) &&
            !strcmp(rows[k].filter, rows[0].filter) && rows[k].w == rows[0].w &&
            rows[k].h == rows[0].h)
            s.row[nt++] = k;
    aa_tile_source src = {.n = nt, .tw = rows[0].w, .th = rows[0].h, .lines = MONTAGE_LINES,
                          .get = montage_get, .put = montage_put, .ctx = &s};
    char path[4096];
    if (!(st = aa_pathf(path, sizeof path, "%s/montage.png", dir)))
        st = aa_montage_stream(path, &src, montage_columns(nt, rows[0].w), enc);
    aa_image_free(&s.im);
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
static int trusted(const run_args *a, const aa_run_spec *m, const aa_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (rows[k].failed && !strcmp(rows[k].method, m->text))
            return 0;
    if (a->isolate == AA_ISOLATE_NONE)
        return 1;
    for (size_t k = 0; aa_method_types[k]; k++)
        if (&aa_method_types[k]->info == m->spec.info)
            return 1;
    return 0;
}

static int write_convergence(const char *dir, const run_args *a, const aa_run_config *first,
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
        if (!trusted(a, &first->methods[k], rows, nrows) || aa_method_check(mspec, f) ||
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
        if ((st = aa_converge(pspec, mspec, f, 128, 128, spp, 5, 4, a->seed, threads,
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
    printf("%-30s %-10s %-9s %10s %10s %10s %10s %8s %6s\n", "method", "pattern", "size",
           "rmse", "eye_rmse", "flicker", "flick_max", "conserv", "pop");
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        char size[32];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        if (!r->ok || !r->temporal) {
            printf("%-30.30s %-10.10s %-9s %s\n", r->method, r->pattern, size, r->note);
            continue;
        }
        printf("%-30.30s %-10.10s %-9s %10.3e %10.3e %10.3e %10.3e %8.2e", r->method, r->pattern,
               size, r->m.rmse, r->tm.eye_rmse, r->tm.flicker_mean, r->tm.flicker_max,
               r->tm.conservation);
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
            printf("  %-10.10s %s (eye_rmse %.3e); %s (flicker %.3e)\n", order[k]->pattern,
                   best->method, best->tm.eye_rmse, calm->method, calm->tm.flicker_mean);
    }
}

/* --seeds N: the stochastic methods' mean RMSE over the seeds. */
static void print_seeds(const aa_row **order, size_t n)
{
    int header = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        if (!r->ok || r->seeds < 2)
            continue;
        if (!header++)
            printf("\nover %d seeds (stochastic methods): mean RMSE and its 95%% CI\n", r->seeds);
        printf("  %-30.30s %-10.10s %4dx%-5d %-10.10s %.4e [%.4e, %.4e]\n", r->method, r->pattern,
               r->w, r->h, r->filter, r->rmse_mean, r->rmse_ci_lo, r->rmse_ci_hi);
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
    printf("%-30s %-10s %-12s %-10s %10s %9s %8s %-20s %9s %6s\n", "method", "pattern", "size",
           "filter", "rmse", "max_err", "psnr", "ms, median +-CI", "ns/px", "exp%");
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = order[k];
        char size[32];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        if (!r->ok) {
            printf("%-30.30s %-10.10s %-12s %-10.10s %s\n", r->method, r->pattern, size, r->filter,
                   r->note);
            continue;
        }
        char ms[64];
        cli_time_text(r, ms, sizeof ms);
        printf("%-30.30s %-10.10s %-12s %-10.10s %10.3e %9.2e %8.2f %-20s %9.2f %6.1f\n",
               r->method, r->pattern, size, r->filter, r->m.rmse, r->m.max_err, r->m.psnr, ms,
               r->ns_per_pixel, 100 * r->expensive_fraction);
    }
    if (temporal) {
        printf("\n");
        print_temporal(order, n);
    }
    print_seeds(order, n);
    free(order);
}

/* ---- the command ---- */

/* ---- the lists, parsed once ---- */

#define MAX_GROUPS 16

/* The arrays of parsed lists, freed together at the end of the run. */
typedef struct owned {
    void *v[4 * (MAX_GROUPS + 1)];
    size_t n;
} owned;

static void *own(owned *o, size_t n, size_t size)
{
    void *p = o->n < sizeof o->v / sizeof o->v[0] ? calloc(n ? n : 1, size) : NULL;
    if (p)
        o->v[o->n++] = p;
    return p;
}

static void owned_free(owned *o)
{
    while (o->n)
        free(o->v[--o->n]);
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
static size_t drop_missing_external(const char *suite, aa_run_spec *m, size_t n)
{
    aa_filter box;
    aa_filter_default(&box);
    size_t kept = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_method_type *t = (const aa_method_type *)m[k].spec.info;
        if ((t->flags & AA_METHOD_EXTERNAL) && aa_method_check(&m[k].spec, &box) != AA_OK) {
            fprintf(stderr, "aabench run: suite %s: leaving out %s: %s\n", suite, m[k].text,
                    aa_last_error());
            continue;
        }
        m[kept++] = m[k];
    }
    return kept;
}

/* The cross products to run: the suite's groups, with any list given on the
 * command line replacing the groups' own.  The lists given are parsed once,
 * and shared by every group. */
static int groups_of(const run_args *a, const aa_suite *suite, owned *o, aa_run_config *cfgs,
                     size_t max, size_t *ng)
{
    aa_run_spec *gp = NULL, *gm = NULL;
    aa_run_size *gs = NULL;
    aa_run_filter *gf = NULL;
    int st = AA_OK;
    *ng = 0;
    if ((a->p.n && (st = parse_patterns(o, a->p.v, a->p.n, &gp))) ||
        (a->s.n && (st = parse_sizes(o, a->s.v, a->s.n, &gs))) ||
        (a->f.n && (st = parse_filters(o, a->f.v, a->f.n, &gf))) ||
        (a->m.n && (st = parse_methods(o, a->m.v, a->m.n, &gm))))
        return st;
    for (const aa_suite_group *g = suite->groups; g->patterns && *ng < max; g++) {
        aa_run_config *c = &cfgs[(*ng)++];
        aa_run_spec *p = gp, *m = gm;
        aa_run_size *s = gs;
        aa_run_filter *f = gf;
        size_t np = a->p.n ? a->p.n : count(g->patterns), ns = a->s.n ? a->s.n : count(g->sizes),
               nf = a->f.n ? a->f.n : count(g->filters), nm = a->m.n ? a->m.n : count(g->methods);
        if ((!a->p.n && (st = parse_patterns(o, g->patterns, np, &p))) ||
            (!a->s.n && (st = parse_sizes(o, g->sizes, ns, &s))) ||
            (!a->f.n && (st = parse_filters(o, g->filters, nf, &f))) ||
            (!a->m.n && (st = parse_methods(o, g->methods, nm, &m))))
            return st;
        if (!a->m.n)
            nm = drop_missing_external(suite->name, m, nm);
        memset(c, 0, sizeof *c);
        c->patterns = p, c->npatterns = np;
        c->sizes = s, c->nsizes = ns;
        c->filters = f, c->nfilters = nf;
        c->methods = m, c->nmethods = nm;
        if (a->p.n && a->s.n && a->f.n && a->m.n)
            break; /* everything given: one cross product */
    }
    return AA_OK;
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

/* Everything checked before any work or any file: every method runs some
 * case (a spec every filter of the run refuses, such as jitter:spp=15, is
 * bad input, as `render` says), the images' names fit, the montage can be
 * made, and the folders can be. */
static int check_before_work(const run_args *a, const aa_run_config *cfgs, size_t ng)
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
        /* the montage: the first view's reference and up to 63 methods */
        size_t most = cfgs[0].nmethods < 63 ? cfgs[0].nmethods + 1 : 64;
        for (size_t nt = 1; nt <= most; nt++)
            if ((st = aa_montage_check(nt, montage_columns(nt, cfgs[0].sizes[0].w),
                                       cfgs[0].sizes[0].w, cfgs[0].sizes[0].h, MONTAGE_LINES)))
                return aa_fail_context(st, "montage.png (or use --no-images)");
    }
    /* the output folder, with room for images/NAME under it */
    if (a->out && (st = cli_check_folder("--out", a->out, strlen("/images/") + NAME_MAX)))
        return st;
    if (*a->cache && (st = cli_check_folder("--cache", a->cache, 64)))
        return st;
    return AA_OK;
}

/* The run's groups from the options, each checked and set up but for its
 * output folder; every case numbered (case_base) in the whole run's order.
 * Everything is checked before any work or any file. */
static int prepare(run_args *a, const aa_suite *suite, owned *o, aa_run_config *cfgs,
                   size_t *ng, int *threads, size_t *cases)
{
    int st = groups_of(a, suite, o, cfgs, MAX_GROUPS, ng);
    if (st)
        return st;
    *threads = a->threads > 0 ? a->threads : cli_default_threads();
    const aa_suite_motion *mo = aa_suite_motion_find(suite->name);
    if (mo && !a->motion_given)
        a->vx = mo->vx, a->vy = mo->vy;
    *cases = 0;
    for (size_t g = 0; g < *ng; g++) {
        aa_run_config *c = &cfgs[g];
        c->reps = a->reps;
        c->target_ci = a->target_ci, c->budget = a->budget, c->seeds = a->seeds;
        c->threads = *threads;
        c->temporal = mo != NULL;
        c->frames = a->frames ? a->frames : mo ? mo->frames : 0;
        c->window = a->window ? a->window : mo ? mo->window : 0;
        c->isolate = a->isolate;
        c->case_timeout = a->case_timeout;
        c->seed = a->seed;
        c->t = a->t, c->vx = a->vx, c->vy = a->vy;
        c->cache_dir = *a->cache ? a->cache : NULL;
        c->enc = a->enc;
        c->case_base = *cases;
        *cases += aa_run_case_count(c);
        if ((st = aa_run_check(c)))
            return st;
    }
    return check_before_work(a, cfgs, *ng);
}

/* After the cases: the montage and plots, the table, the warnings; the
 * exit status.  A shard makes neither montage nor plots: the merge of the
 * shards does, over the whole run. */
static int finish_run(const run_args *a, const aa_run_config *cfgs, int threads,
                      const char *dir, int linked, run_ctx *ctx, int st)
{
    char plots[4200];
    aa_row *all = ctx->all;
    size_t nall = ctx->nall;
    if (ctx->sort && nall > 1)
        qsort(all, nall, sizeof *all, by_case);
    /* saved after every case already; once more so that a failed group's
     * rows are on disk whatever it stopped at */
    if (nall) {
        int sst = save(ctx, all, nall);
        if (!st)
            st = sst;
    }
    size_t ran = 0;
    for (size_t k = 0; k < nall; k++)
        ran += all[k].ok != 0;
    if (!st && ran && a->shards <= 1) {
        if (a->images)
            st = write_montage(dir, &cfgs[0], all, nall, &a->enc);
        if (!st && a->plots && !(st = aa_pathf(plots, sizeof plots, "%s/plots", dir))) {
            if (!(st = aa_plot_error_vs_time(plots, all, nall)))
                st = write_convergence(plots, a, &cfgs[0], threads, all, nall);
        }
    }
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
    if (ctx->skipped)
        printf("skipped %zu method and view pair%s the method refuses (a filter or a scene; "
               "name the method and the filter to run them)\n",
               ctx->skipped, ctx->skipped == 1 ? "" : "s");
    if (!a->quiet)
        print_table(all, nall);
    cli_warn_noisy("run", all, nall);
    printf("results: %s/results.csv%s\n", dir, linked ? " (results/latest)" : "");
    if (a->shards > 1)
        printf("shard %d/%d: %zu case%s; join the shards with aabench merge DIR... --out DIR\n",
               a->shard, a->shards, nall, nall == 1 ? "" : "s");
    return report_failed(all, nall);
}

/* The run's manifest (bench.h, aa_manifest): its command without the
 * arguments that do not change the results. */
static int write_manifest(const char *dir, const run_args *a, const aa_context *context,
                          size_t cases, unsigned char *const *masks, const aa_run_config *cfgs,
                          size_t ng)
{
    aa_manifest m;
    char path[4200];
    int argc, st;
    const char *const *argv;
    memset(&m, 0, sizeof m);
    cli_command_line(&argc, &argv);
    m.argv = calloc((size_t)argc + 1, sizeof *m.argv);
    m.selected = calloc(cases ? cases : 1, sizeof *m.selected);
    if (!m.argv || !m.selected) {
        free(m.argv);
        free(m.selected);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    for (int k = 2; k < argc; k++) {
        int value;
        if (aa_manifest_skips(argv[k], &value))
            k += value;
        else
            m.argv[m.argc++] = (char *)argv[k];
    }
    snprintf(m.suite, sizeof m.suite, "%s", a->suite);
    snprintf(m.commit, sizeof m.commit, "%s", context->commit);
    snprintf(m.host, sizeof m.host, "%s", context->host);
    m.dirty = context->dirty;
    m.shard = a->shards ? a->shard : 1;
    m.shards = a->shards ? a->shards : 1;
    m.cases = cases;
    for (size_t g = 0; g < ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&cfgs[g]); k++)
            if (!masks[g] || masks[g][k])
                m.selected[m.nselected++] = cfgs[g].case_base + k;
    m.context = aa_context_json(context, 0);
    st = m.context ? aa_pathf(path, sizeof path, "%s/run.json", dir)
                   : aa_fail(AA_ENOMEM, "out of memory");
    if (!st)
        st = aa_manifest_write(path, &m);
    free(m.argv);
    free(m.selected);
    free(m.context);
    return st;
}

/* A resumed run: the rows of DIR/results.csv kept, and their cases taken
 * out of the masks (made when the run had none).  A row that is not one of
 * the folder's cases is refused. */
static int resume_rows(const char *dir, aa_run_config *cfgs, size_t ng, unsigned char **masks,
                       run_ctx *ctx)
{
    char path[4200];
    aa_row *rows = NULL;
    size_t n = 0;
    int st = aa_pathf(path, sizeof path, "%s/results.csv", dir);
    if (st || access(path, F_OK) != 0)
        return st; /* stopped before its first case */
    if ((st = aa_rows_read_csv(path, &rows, &n)))
        return st;
    aa_manifest m;
    if ((st = aa_pathf(path, sizeof path, "%s/run.json", dir)) ||
        (st = aa_manifest_read(path, &m))) {
        free(rows);
        return st;
    }
    for (size_t g = 0; g < ng && !st; g++)
        if (!masks[g]) {
            size_t c = aa_run_case_count(&cfgs[g]);
            if (!(masks[g] = malloc(c ? c : 1)))
                st = aa_fail(AA_ENOMEM, "out of memory");
            else
                memset(masks[g], 1, c);
        }
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
    for (size_t k = 0; k < m.nrefused && !st; k++)
        for (size_t g = 0; g < ng; g++)
            if (m.refused[k] >= cfgs[g].case_base &&
                m.refused[k] < cfgs[g].case_base + aa_run_case_count(&cfgs[g]))
                masks[g][m.refused[k] - cfgs[g].case_base] = 0;
    aa_manifest_free(&m);
    if (!st && n && !(st = grow(ctx, n))) {
        memcpy(ctx->all, rows, n * sizeof *rows);
        ctx->nall = n;
    }
    free(rows);
    return st;
}

/* The cases this run skipped as refused, added to those its manifest
 * holds (a resumed run's earlier ones), so that they count as done for
 * `merge` and `run --resume`; *total: all of them. */
static int record_refused(const char *dir, const aa_run_config *cfgs, size_t ng,
                          unsigned char *const *refused, size_t *total)
{
    aa_manifest m;
    char path[4200];
    int st = aa_pathf(path, sizeof path, "%s/run.json", dir);
    *total = 0;
    if (st || (st = aa_manifest_read(path, &m)))
        return st;
    size_t more = 0;
    for (size_t g = 0; g < ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&cfgs[g]); k++)
            more += refused[g][k] != 0;
    size_t *all = realloc(m.refused, (m.nrefused + more + 1) * sizeof *all);
    if (!all) {
        aa_manifest_free(&m);
        return aa_fail(AA_ENOMEM, "out of memory");
    }
    m.refused = all;
    for (size_t g = 0; g < ng; g++)
        for (size_t k = 0; k < aa_run_case_count(&cfgs[g]); k++)
            if (refused[g][k])
                m.refused[m.nrefused++] = cfgs[g].case_base + k;
    *total = m.nrefused;
    if (more)
        st = aa_manifest_write(path, &m);
    aa_manifest_free(&m);
    return st;
}

/* Run the suite's cross products (or those given) and write everything. */
static int run_suite(run_args *a, const aa_suite *suite, owned *o)
{
    aa_run_config cfgs[MAX_GROUPS];
    unsigned char *masks[MAX_GROUPS] = {0}, *refused[MAX_GROUPS] = {0};
    size_t ng, cases, selected = 0;
    int threads, code = 0;
    int st = prepare(a, suite, o, cfgs, &ng, &threads, &cases);
    if (st)
        return cli_fail("run", st);
    if (a->shards > 1 &&
        (st = aa_shard_plan(cfgs, ng, a->shard, a->shards, masks, &selected, NULL)))
        return cli_fail("run", st);
    char dir[4096], images[4200];
    int linked = 0;
    if (a->out) {
        if ((st = aa_pathf(dir, sizeof dir, "%s", a->out)) || (st = aa_mkdirs(dir)))
            goto fail;
    } else if ((st = make_run_dir(dir, sizeof dir, &linked))) {
        goto fail;
    }
    if ((st = aa_pathf(images, sizeof images, "%s/images", dir)))
        goto fail;
    for (size_t g = 0; g < ng; g++)
        if (!(refused[g] = calloc(aa_run_case_count(&cfgs[g]) + 1, 1))) {
            st = aa_fail(AA_ENOMEM, "out of memory");
            goto fail;
        }
    aa_context context;
    int argc;
    const char *const *argv;
    cli_command_line(&argc, &argv);
    aa_context_collect(&context, argc, argv, threads);
    run_ctx ctx = {dir, cli_progress_wanted(), aa_now(), &context, NULL, 0, 0, 0, 0, 0};
    if (a->resume) {
        ctx.sort = 1;
        if ((st = resume_rows(dir, cfgs, ng, masks, &ctx)))
            goto fail;
        if (ctx.nall)
            fprintf(stderr, "aabench run: resuming %s: %zu case%s kept, measuring the rest\n",
                    dir, ctx.nall, ctx.nall == 1 ? "" : "s");
    } else if ((st = write_manifest(dir, a, &context, cases, masks, cfgs, ng))) {
        goto fail;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    size_t skipped = 0;
    st = AA_OK;
    for (size_t g = 0; g < ng && !st; g++) {
        aa_run_config *c = &cfgs[g];
        c->images_dir = a->images ? images : NULL;
        c->progress = progress;
        c->row_done = row_done;
        c->ctx = &ctx;
        c->only = masks[g];
        /* a suite's cross products pair each method only with the views it
         * takes; a method and a filter both named are run as asked */
        c->skip_refused = !(a->m.n && a->f.n);
        c->skipped = &skipped;
        c->refused = refused[g];
        aa_row *rows = NULL;
        size_t n = 0;
        ctx.copied = 0;
        st = aa_run(c, &rows, &n);
        /* the rows aa_run returns, whatever its status */
        int gst = grow(&ctx, n);
        if (!gst && n) {
            memcpy(ctx.all + ctx.nall, rows, n * sizeof *rows);
            ctx.nall += n;
        } else if (!st) {
            st = gst;
        }
        ctx.copied = 0;
        free(rows);
    }
    (void)skipped; /* counted per case in refused[], kept with the manifest */
    int rst = record_refused(dir, cfgs, ng, refused, &ctx.skipped);
    if (!st)
        st = rst;
    code = finish_run(a, cfgs, threads, dir, linked, &ctx, st);
    free(ctx.all);
    for (size_t g = 0; g < ng; g++)
        free(masks[g]), free(refused[g]);
    return code;
fail:
    for (size_t g = 0; g < ng; g++)
        free(masks[g]), free(refused[g]);
    return cli_fail("run", st);
}

static void run_defaults(run_args *a)
{
    memset(a, 0, sizeof *a);
    a->suite = "default";
    a->reps = 0; /* by precision */
    a->images = a->plots = 1;
    a->seed = 1;
    a->cache = cli_cache_dir();
    a->enc.kind = AA_ENCODE_SRGB;
    a->isolate = AA_ISOLATE_PLUGINS;
    a->case_timeout = AA_CASE_TIMEOUT;
}

static const aa_suite *suite_of(const run_args *a)
{
    const aa_suite *suite = aa_suite_find(a->suite);
    if (!suite)
        fprintf(stderr,
                "aabench run: unknown suite \"%s\" (quick, default, paper, full, temporal)\n",
                aa_echo(a->suite));
    return suite;
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
static int resume(const char *dir, int argc, char **argv)
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
    if (other && strcmp(given, recorded)) {
        fprintf(stderr, "aabench run: --resume %s: the command differs from the run's: it was "
                        "\"%s\", now \"%s\" (give no options to take the run's own)\n",
                aa_echo(dir), recorded, given);
        aa_manifest_free(&m);
        return 2;
    }
    aa_context now;
    aa_context_collect(&now, 0, NULL, 1);
    if (strcmp(now.commit, m.commit) || (m.dirty >= 0 && now.dirty >= 0 && m.dirty != now.dirty)) {
        fprintf(stderr, "aabench run: --resume %s: the run was measured at commit %s%s, this "
                        "program is at %s%s: resume it with that commit's aabench, or start a "
                        "new run\n",
                aa_echo(dir), m.commit, m.dirty > 0 ? " (dirty)" : "", now.commit,
                now.dirty > 0 ? " (dirty)" : "");
        aa_manifest_free(&m);
        return 2;
    }
    /* "run", the run's own arguments, its shard and folder, and the options
     * given that do not change the results (--cache, -q, --threads) */
    char shard[64];
    char **args = calloc((size_t)m.argc + (size_t)argc + 8, sizeof *args);
    if (!args) {
        aa_manifest_free(&m);
        return cli_fail("run", aa_fail(AA_ENOMEM, "out of memory"));
    }
    int n = 0;
    args[n++] = "run";
    for (int k = 0; k < m.argc; k++)
        args[n++] = m.argv[k];
    snprintf(shard, sizeof shard, "%d/%d", m.shard, m.shards);
    if (m.shards > 1)
        args[n++] = "--shard", args[n++] = shard;
    args[n++] = "--out", args[n++] = (char *)dir;
    for (int k = 1; k < argc; k++) {
        int value;
        if (aa_manifest_skips(argv[k], &value) && strncmp(argv[k], "--out", 5) &&
            strncmp(argv[k], "--resume", 8) && strncmp(argv[k], "--shard", 7)) {
            args[n++] = argv[k];
            if (value && k + 1 < argc)
                args[n++] = argv[++k];
        } else {
            k += value;
        }
    }
    run_args a;
    run_defaults(&a);
    int code = parse(n, args, &a);
    if (code < 0) {
        a.resume = dir;
        const aa_suite *suite = suite_of(&a);
        owned o = {{0}, 0};
        code = suite ? run_suite(&a, suite, &o) : 2;
        owned_free(&o);
    }
    free(args);
    aa_manifest_free(&m);
    return code;
}

int cmd_run(int argc, char **argv)
{
    run_args a;
    run_defaults(&a);
    int code = parse(argc, argv, &a);
    if (code >= 0)
        return code;
    if (a.resume)
        return resume(a.resume, argc, argv);
    const aa_suite *suite = suite_of(&a);
    if (!suite)
        return 2;
    owned o = {{0}, 0};
    code = run_suite(&a, suite, &o);
    owned_free(&o);
    return code;
}

/* ---- for other commands: a run's references, and a merged run ---- */

int cli_run_warm(int argc, char **argv)
{
    run_args a;
    run_defaults(&a);
    int code = parse(argc, argv, &a);
    if (code >= 0)
        return code;
    const aa_suite *suite = suite_of(&a);
    if (!suite)
        return 2;
    if (!*a.cache) {
        fprintf(stderr, "aabench truth: --warm needs a cache folder (not --no-cache)\n");
        return 2;
    }
    aa_run_config cfgs[MAX_GROUPS];
    size_t ng, cases, computed = 0, cached = 0;
    int threads, st;
    owned o = {{0}, 0};
    a.images = 0; /* nothing is written but the cache */
    st = prepare(&a, suite, &o, cfgs, &ng, &threads, &cases);
    double t0 = aa_now();
    for (size_t g = 0; g < ng && !st; g++)
        st = aa_run_warm(&cfgs[g], &computed, &cached);
    owned_free(&o);
    if (st)
        return cli_fail("truth", st);
    if (!a.quiet)
        printf("%zu reference%s of suite %s in %s: %zu computed, %zu already there (%.1f s)\n",
               computed + cached, computed + cached == 1 ? "" : "s", a.suite, a.cache, computed,
               cached, aa_now() - t0);
    return 0;
}

int cli_run_write_merged(int argc, char **argv, const char *dir, aa_row *rows, size_t n,
                         size_t refused, int quiet)
{
    run_args a;
    run_defaults(&a);
    int code = parse(argc, argv, &a);
    if (code >= 0)
        return code == 0 ? 2 : code; /* --help or --list-suites: not a run's command */
    const aa_suite *suite = suite_of(&a);
    if (!suite)
        return 2;
    a.quiet |= quiet;
    a.shard = a.shards = 0; /* the whole run */
    aa_run_config cfgs[MAX_GROUPS];
    size_t ng, cases;
    int threads;
    owned o = {{0}, 0};
    int st = prepare(&a, suite, &o, cfgs, &ng, &threads, &cases);
    if (!st && cases != n + refused)
        st = aa_fail(AA_EINVAL, "the run's command has %zu cases, the shards %zu", cases,
                     n + refused);
    if (st) {
        owned_free(&o);
        return cli_fail("merge", st);
    }
    aa_context context;
    aa_context_collect(&context, argc, (const char *const *)argv, threads);
    run_ctx ctx = {dir, 0, aa_now(), &context, rows, n, n, 0, 1, refused};
    code = finish_run(&a, cfgs, threads, dir, 0, &ctx, AA_OK);
    owned_free(&o);
    return code;
}
