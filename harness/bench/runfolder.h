/*
 * runfolder.h: a run folder as a library object (runfolder.c).
 *
 * A run measures a plan (what to measure: a suite's groups or the lists
 * given, the timing, the seeds, the motion, a shard) with options (where
 * and how: the folder, threads, cache, images and plots, isolation, the
 * caller's hooks) and writes a folder: run.json (the manifest, written
 * before any case), results.csv and results.json (rewritten after every
 * case), images/, montage.png and plots/.  The shape is SQLite's and
 * GSL's: an opaque object made by create (a new folder) or open (a folder
 * to resume, its manifest checked), then run, finish and free; every
 * function returns a status (AA_OK or an AA_E* code, aa_last_error() the
 * message).  The library prints nothing and installs no signal handler:
 * progress, interruption and notes go through the options' hooks.
 *
 *     aa_plan plan;
 *     aa_run_options opt;
 *     aa_runfolder *rf;
 *     aa_plan_default(&plan);
 *     aa_run_options_default(&opt);
 *     plan.suite = "quick";
 *     opt.out = "out";
 *     if (!(st = aa_runfolder_create(&plan, &opt, &rf)) && !(st = aa_runfolder_run(rf)))
 *         st = aa_runfolder_finish(rf);
 *     aa_runfolder_free(rf);
 */
#ifndef AA_RUNFOLDER_H
#define AA_RUNFOLDER_H

#include <stddef.h>
#include <stdint.h>

/* The most items of one list of a plan. */
#define AA_PLAN_MAX 256

/* What to measure.  A list given (n > 0) replaces the suite groups' own;
 * with all four given the run is their one cross product, every method
 * under every filter given (refusals are rows); otherwise a method runs
 * only with the views it takes and the cases it refuses are recorded as
 * refused.  The strings are the caller's and must outlive the run folder. */
typedef struct aa_plan {
    const char *suite; /* aa_suites' name; "default" */
    const char *patterns[AA_PLAN_MAX], *sizes[AA_PLAN_MAX], *filters[AA_PLAN_MAX],
        *methods[AA_PLAN_MAX];
    size_t npatterns, nsizes, nfilters, nmethods;
    int reps;          /* > 0: exactly that many timed renders; 0: by precision */
    double target_ci;  /* fraction (0: 2%) */
    double budget;     /* seconds (0: 1 s) */
    int seeds;         /* stochastic methods over this many seeds (0, 1: one) */
    uint64_t seed;     /* 1 */
    double t, vx, vy;  /* time in frames; motion in pixels per frame */
    int motion_given;  /* 0: the suite's own motion, if it has one */
    int frames, window; /* animated runs (0: the suite's, else 24 and 6) */
    aa_encode enc;     /* PNGs and *_enc metrics (sRGB) */
    int shard, shards; /* K of N (0 of 0: the whole run) */
    /* The words recorded as the run's command in run.json (those of
     * `aabench run` after "run"; the options that do not change the
     * results, aa_manifest_skips, are left out).  NULL: words made from
     * the plan and the options, which aa_plan_parse reads back. */
    int argc;
    const char *const *argv;
} aa_plan;

/* Which views' images a run writes (images/, the montages): none, those of
 * the run's smallest size and of every size up to AA_IMAGES_SIDE squared
 * pixels (a view of 1024x1024 takes about 1.6 MB of images, lossless), or
 * every view's. */
enum { AA_IMAGES_NONE, AA_IMAGES_SMALL, AA_IMAGES_ALL };
#define AA_IMAGES_SIDE 512

/* How and where.  The hooks may be NULL; `hook` is given to each. */
typedef struct aa_run_options {
    const char *out;   /* the folder; NULL: results/runs/<UTC time>, results/latest */
    const char *cache; /* reference cache folder; NULL or "": none */
    int threads;       /* 0: all cores */
    /* images/ and the montages: AA_IMAGES_* (AA_IMAGES_SMALL); plots/ (1) */
    int images, plots;
    int quiet;         /* for the caller (no table): the library prints nothing */
    const char *resume; /* for the caller: aa_plan_parse's --resume DIR */
    int isolate;       /* AA_ISOLATE_* (AA_ISOLATE_PLUGINS) */
    double case_timeout; /* seconds (AA_CASE_TIMEOUT) */
    /* The command line recorded in results.json's context (may be NULL);
     * a merge records "run", the run's own words, then these. */
    int argc;
    const char *const *argv;
    /* before each case and each reference: `done` of `total`, `what` */
    void (*progress)(void *hook, size_t done, size_t total, const char *what);
    /* asked before each case: non-zero stops the run there, every file
     * complete (a signal handler sets a flag; this reads it) */
    int (*interrupted)(void *hook);
    /* something the caller may show: a suite's external method whose
     * renderer is not installed, left out; a program older than its
     * checkout */
    void (*note)(void *hook, const char *message);
    void *hook;
} aa_run_options;

void aa_plan_default(aa_plan *plan);
void aa_run_options_default(aa_run_options *opt);

/* The words of `aabench run` (argv[0] "run", then its options) into a plan
 * and options (both set to their defaults first by the caller; each
 * option given replaces its field).  --plugin loads the library at once.
 * *asked: 'h' for --help, 'l' for --list-suites (parsing stops there), '?'
 * for an unknown option or a missing value (AA_EINVAL), else 0.
 * plan->argc/argv are set to argv[1..]: the words are the caller's. */
int aa_plan_parse(int argc, char *const *argv, aa_plan *plan, aa_run_options *opt, int *asked);

typedef struct aa_runfolder aa_runfolder;

/* A new run: the plan checked (every spec, size, image name, the montage,
 * the folders) before anything is written, then the folder made and its
 * manifest written.  *rf is NULL on failure. */
int aa_runfolder_create(const aa_plan *plan, const aa_run_options *opt, aa_runfolder **rf);
/* A run folder to resume: its manifest read and checked (a run folder, of
 * this program's commit), its plan and recorded options (images, plots,
 * isolation, time-out) its own, its shard too; of `opt` only the cache,
 * threads, quiet, command line and hooks are used.  The rows of its
 * results.csv are kept (each one of the run's cases left to measure, else
 * AA_EINVAL), and so are the cases recorded as refused. */
int aa_runfolder_open(const char *dir, const aa_run_options *opt, aa_runfolder **rf);
/* AA_OK if the manifest's run was measured at the commit this program was
 * built from (and as dirty), else AA_EINVAL saying both: what open checks
 * first.  The checkout's commit at run time does not count. */
int aa_manifest_same_commit(const aa_manifest *m);
/* The cases left, in the run's order, results saved after every case (a
 * resumed run's in case order); then the cases skipped as refused added
 * to the manifest.  AA_EFAIL "interrupted" when the interrupt hook
 * stopped it (aa_runfolder_interrupted); the rows measured are kept and
 * saved whatever the status.  Once per object (a merged one has run):
 * open the folder again to go on. */
int aa_runfolder_run(aa_runfolder *rf);
/* montage.png, plots/error_vs_time.png and plots/convergence.png (as the
 * options ask), if any case ran; nothing for a shard (the merge does). */
int aa_runfolder_finish(aa_runfolder *rf);
/* The shards' folders (run --shard K/N of one run) checked: the same
 * command, suite and commit, every case of the run exactly once, and
 * `opt->out` none of them; a missing, duplicated or foreign shard is
 * AA_EINVAL naming it, before anything is written.  Then opt->out holds
 * the whole run as the unsharded run writes it: run.json (one part),
 * results, images/ (the shards'); aa_runfolder_finish adds the montage
 * and plots.  The plan is the run's own; of `opt`, out, cache, threads,
 * quiet, command line and hooks are used. */
int aa_runfolder_merge(const char *const *dirs, size_t n, const aa_run_options *opt,
                       aa_runfolder **rf);
void aa_runfolder_free(aa_runfolder *rf);

/* The folder; its rows (a resumed run's in case order); the rows kept
 * from before (resume); the cases skipped as refused (the whole run's);
 * whether results/latest points to it; its shard (K and N, 1 of 1
 * unsharded); whether the interrupt hook stopped it. */
const char *aa_runfolder_dir(const aa_runfolder *rf);
const aa_row *aa_runfolder_rows(const aa_runfolder *rf, size_t *n);
size_t aa_runfolder_kept(const aa_runfolder *rf);
size_t aa_runfolder_refused(const aa_runfolder *rf);
int aa_runfolder_linked(const aa_runfolder *rf);
/* The most pixels of a view whose images the run writes (0: every view's;
 * its views with none: no images at all). */
long aa_runfolder_images_max(const aa_runfolder *rf);
void aa_runfolder_shard(const aa_runfolder *rf, int *k, int *n);
int aa_runfolder_interrupted(const aa_runfolder *rf);

/* The references a run of the plan would ask the cache (opt->cache, which
 * must be given) for, computed where missing: *computed and *cached count
 * them.  Nothing else is written. */
int aa_runfolder_warm(const aa_plan *plan, const aa_run_options *opt, size_t *computed,
                      size_t *cached);

/* A folder to write into (made if missing), checked before any work: its
 * name and each of its components short enough, with `room` characters
 * left for the names of the files written under it, and nothing in the
 * way that is not a folder.  `what` names it in messages ("--out"). */
#define AA_PATH_MAX 4096
int aa_folder_check(const char *what, const char *path, size_t room);
/* The number of threads by default: all cores (at most 1024). */
int aa_default_threads(void);

/* Option values, checked, as the command line gives them: `name` names
 * the option in messages.  Reals in the C locale whatever the locale. */
int aa_parse_real(const char *name, const char *text, double lo, double hi, double *out);
int aa_parse_int(const char *name, const char *text, long lo, long hi, int *out);
int aa_parse_seed(const char *text, uint64_t *out);
int aa_parse_pair(const char *name, const char *text, double lo, double hi, double *a,
                  double *b);
/* --threads N (1 to 1024), --target-ci PCT (0.01 to 50, a fraction out)
 * and --budget S. */
int aa_parse_threads(const char *text, int *out);
int aa_parse_target(const char *text, double *out);
int aa_parse_budget(const char *text, double *out);

/* An option that takes one value, given twice with different values, would
 * leave the first ignored: refused, naming the option and both values.  `seen` starts
 * zeroed and holds the values given so far; `code` is what getopt_long
 * returned and `opts` its table.  Options without a value (flags), codes
 * not in the table and `lists` (codes ending in 0: -p in run, --plugin)
 * pass. */
struct option;
typedef struct aa_options_seen {
    int n;
    int code[64];
    const char *value[64];
} aa_options_seen;
int aa_option_once(aa_options_seen *seen, int code, const char *value,
                   const struct option *opts, const int *lists);

#endif /* AA_RUNFOLDER_H */
