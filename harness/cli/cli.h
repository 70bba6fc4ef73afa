/*
 * cli.h: what the `aabench` subcommands share.  The command line is a thin
 * client of the library (as lua.c is of Lua): each subcommand parses its
 * options, checks everything before any work, calls the library and maps
 * the status to an exit code (0 ok, 1 check failed, 2 bad input or usage,
 * 3 input/output or internal error).
 */
#ifndef AA_CLI_H
#define AA_CLI_H

#include "bench.h"

#include <getopt.h>
#include <stdint.h>
#include <stdio.h>

/* The whole command line: argv[0] the program, argv[1] the subcommand;
 * returns the exit status (cli_main.c).  main.c calls it. */
int cli_main(int argc, char **argv);

/* The library's warning handler (aa_set_warn): "aabench: warning: MSG" on
 * stderr. */
void cli_warn(const char *message, void *ctx);
/* Print "aabench CMD: <last error>" to stderr; returns the exit code. */
int cli_fail(const char *cmd, int status);
/* Report a getopt failure (unknown option or missing argument). */
int cli_bad_option(const char *cmd, int c, char *const argv[]);
/* Report a bad option found by the library's parser (aa_plan_parse): the
 * message and a pointer to --help; exit status 2. */
int cli_bad_usage(const char *cmd, int status);
/* --out DIR and --threads N, read one way by every command that takes
 * them: their entries of a getopt_long table, and their values (c is
 * CLI_O_OUT or CLI_O_THREADS; the pointer of the other may be NULL).
 * `run` reads them through the library's aa_plan_parse, which checks
 * --threads with the same aa_parse_threads. */
enum { CLI_O_OUT = 0x4000, CLI_O_THREADS };
#define CLI_OPTION_OUT {"out", required_argument, 0, CLI_O_OUT}
#define CLI_OPTION_THREADS {"threads", required_argument, 0, CLI_O_THREADS}
int cli_out_threads(int c, const char *arg, const char **out, int *threads);
/* Reset getopt before a subcommand parses its arguments. */
void cli_getopt_reset(void);

/* The output file: a known image extension and a folder that exists and
 * can be written, checked before any work. */
int cli_check_output(const char *path);
/* The view's size: -s WxH when given (size not NULL), else the pattern's
 * own size (aa_pattern_own_size: an svg file's size times its scale). */
int cli_view_size(const char *size, const aa_spec *pattern, int *w, int *h);
/* A non-image output with a required extension (".json", ".csv"). */
int cli_check_output_file(const char *path, const char *ext);
/* A reference cache that cannot be written (a folder that cannot be made,
 * or created in) is said once, on standard error, before the work; the
 * references are then computed and not kept, with no word each. */
void cli_cache_usable(const char *cmd, const char *dir);
/* The probe of cli_cache_usable: the folder made if missing and a file
 * created in it and removed; else the status, the reason in aa_last_error. */
int cli_cache_writable(const char *dir);
/* SIGINT, SIGTERM and SIGHUP: remove the temporary files still on disk and exit
 * with status 130 (installed first thing by cli_main; `run` installs its
 * own, which lets the case under way finish). */
void cli_signals_install(void);

/* Outputs written all or nothing: each is written under a temporary name
 * (cli_stage gives it), and only when every one has been written are they
 * renamed into place (cli_commit); otherwise none is (cli_discard). */
#define CLI_MAX_OUTPUTS 4
typedef struct cli_outputs {
    int n;
    const char *path[CLI_MAX_OUTPUTS];
    char tmp[CLI_MAX_OUTPUTS][4096];
} cli_outputs;
/* The temporary name to write `path` under. */
int cli_stage(cli_outputs *o, const char *path, const char **tmp);
int cli_commit(cli_outputs *o);
void cli_discard(cli_outputs *o);

/* `text` as a JSON string literal (quoted, escaped) into buf. */
void cli_json_string(const char *text, char *buf, size_t len);
/* Default cache folder (aa_cache_dir_default): $AABENCH_CACHE, else
 * results/cache inside the source tree, else $XDG_CACHE_HOME/aabench. */
const char *cli_cache_dir(void);
/* 1 if stderr is a terminal and CI is not set: progress may be shown. */
int cli_progress_wanted(void);

/* The whole command line cli_main was given (argv[0] the program), for the
 * results' context. */
void cli_command_line(int *argc, const char *const **argv);
void cli__set_command_line(int argc, char **argv); /* by cli_main */
/* The median render time in ms with its CI's relative half-width and a
 * mark for a noisy measurement: "12.345 +-1.2%", "12.345 +-9.9% *",
 * "12.345 CI needs 6 renders" (aa_timing_ci_text); "12.345" with no times. */
void cli_time_text(const aa_row *r, char *buf, size_t len);
/* On stderr, a warning naming each case whose timing is marked noisy, with
 * the reasons; returns their count. */
size_t cli_warn_noisy(const char *cmd, const aa_row *rows, size_t n);
/* A warning on stderr for each view whose reference is not proven
 * everywhere (pixels' bounds estimated, or a bound above AA_TRUTH_BOUND);
 * the count of such views. */
size_t cli_warn_references(const char *cmd, const aa_row *rows, size_t n);
/* On stderr, a warning when the rows' effective parallelism (CPU time /
 * wall time) differs by more than AA_PARALLELISM_FACTOR (aa_rows_parallelism),
 * naming the two ends; 1 if warned.  Standard output is flushed first. */
int cli_warn_parallelism(const char *cmd, const aa_row *rows, size_t n);

int cmd_list(int argc, char **argv);
int cmd_truth(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_export(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_stress(int argc, char **argv);
int cmd_figures(int argc, char **argv);
int cmd_run(int argc, char **argv);
int cmd_check(int argc, char **argv);
int cmd_converge(int argc, char **argv);
int cmd_diff(int argc, char **argv);
int cmd_merge(int argc, char **argv);
int cmd_prune(int argc, char **argv);

/* `run`'s printing, for `merge` and `truth --warm` too (cmd_run.c): a note
 * of the library's (a suite's method left out) on standard error; after
 * the cases, the interruption or the error, the table (unless quiet), the
 * noisy timings, where the results are, the failed cases; the exit
 * status. */
void cli_run_note(void *hook, const char *message);
int cli_run_report(aa_runfolder *rf, int quiet, int status);

#endif
