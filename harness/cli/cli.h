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
 * returns the exit status (cli_main.c).  main.c calls it; tests call it in
 * a forked child, without exec (tests/test_cli.c). */
int cli_main(int argc, char **argv);

/* The library's warning handler (aa_set_warn): "aabench: warning: MSG" on
 * stderr. */
void cli_warn(const char *message, void *ctx);
/* Print "aabench CMD: <last error>" to stderr; returns the exit code. */
int cli_fail(const char *cmd, int status);
/* Report a getopt failure (unknown option or missing argument). */
int cli_bad_option(const char *cmd, int c, char *const argv[]);
/* Reset getopt before a subcommand parses its arguments. */
void cli_getopt_reset(void);

int cli_parse_real(const char *name, const char *text, double lo, double hi, double *out);
int cli_parse_int(const char *name, const char *text, long lo, long hi, int *out);
int cli_parse_seed(const char *text, uint64_t *out);
int cli_parse_pair(const char *name, const char *text, double lo, double hi, double *a,
                   double *b);
/* The output file: a known image extension and a folder that exists and
 * can be written, checked before any work. */
int cli_check_output(const char *path);
/* A non-image output with a required extension (".json", ".csv"). */
int cli_check_output_file(const char *path, const char *ext);
/* A folder to write into (made if missing), checked before any work: its
 * name and each of its components short enough, with `room` characters
 * left for the names of the files written under it, and nothing in the
 * way that is not a folder.  `what` names it in messages ("--out"). */
#define CLI_PATH_MAX 4096
int cli_check_folder(const char *what, const char *path, size_t room);
/* SIGINT and SIGTERM: remove the temporary files still on disk and exit
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

/* The number of threads to use by default: all cores. */
int cli_default_threads(void);
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
/* Timing options shared by run, render and check: --target-ci PCT (a
 * percentage, 0.01 to 50, returned as a fraction) and --budget S. */
int cli_parse_target(const char *text, double *out);
int cli_parse_budget(const char *text, double *out);
/* The median render time in ms with its CI's relative half-width and a
 * mark for a noisy measurement: "12.345 +-1.2%", "12.345 +-9.9% *". */
void cli_time_text(const aa_row *r, char *buf, size_t len);
/* On stderr, a warning naming each case whose timing is marked noisy, with
 * the reasons; returns their count. */
size_t cli_warn_noisy(const char *cmd, const aa_row *rows, size_t n);

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

/* `run`'s machinery for other commands (cmd_run.c), given `run`'s own
 * arguments (argv[0] "run"): the references of the run's views into the
 * cache (truth --warm); and the end of a run for rows measured elsewhere
 * (merge: rows in the run's order, every case once, but the `refused`
 * cases the run skips), written into dir as
 * the run would have (results, montage, plots, table); the exit status. */
int cli_run_warm(int argc, char **argv);
int cli_run_write_merged(int argc, char **argv, const char *dir, aa_row *rows, size_t n,
                         size_t refused, int quiet);

#endif
