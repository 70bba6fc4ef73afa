/*
 * cli_main.c: the `aabench` command line: finds the subcommand and runs it.
 * main.c only calls cli_main().
 */
#include "cli.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <string.h>

static const struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} commands[] = {
    {"list", cmd_list, "list patterns, filters and methods"},
    {"truth", cmd_truth, "write the exact reference image of a pattern"},
    {"render", cmd_render, "render a pattern with a method, timed"},
    {"export", cmd_export, "write a pattern's scene at a size as SVG"},
    {"run", cmd_run, "the benchmark: every method on a suite, measured and plotted"},
    {"check", cmd_check, "rerun the baseline's cases; exit 1 on a regression"},
    {"converge", cmd_converge, "RMSE against samples per pixel, and its slope"},
    {"compare", cmd_compare, "error metrics between two image files"},
    {"stress", cmd_stress, "numerical stress cases against a long double evaluation"},
    {"figures", cmd_figures, "the seed papers' comparison figures remade, with a gallery"},
    {"diff", cmd_diff, "two runs compared: error changes, and time changes with significance"},
    {"merge", cmd_merge, "join the folders of a run's shards into the whole run's results"},
    {"prune", cmd_prune, "remove the oldest run folders, keeping the N newest"},
    {NULL, NULL, NULL}};

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench COMMAND [options]\n\n"
                 "A benchmark and test harness for antialiasing methods.\n\ncommands:\n");
    for (const struct command *c = commands; c->name; c++)
        fprintf(out, "  %-8s %s\n", c->name, c->summary);
    fprintf(out, "\nSpecs are NAME or NAME:key=value,... (e.g. crow:curves=64, tent:r=1).\n"
                 "In a text value (svg:file=PATH, text:string=...) write ',' as %%2C, '%%' as %%25.\n"
                 "'aabench COMMAND --help' describes a command.\n"
                 "Exit status: 0 success, 1 a check failed, 2 bad input or usage,\n"
                 "3 input/output or internal error.\n");
}

/* The subcommand's exit status, unless what it wrote to standard output
 * did not all get there (a full disk, a closed pipe, /dev/full): then 3,
 * with a message, as for any other output. */
static int finish(const char *cmd, int status)
{
    errno = 0;
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "aabench%s%s: cannot write standard output: %s\n", cmd ? " " : "",
                cmd ? cmd : "", errno ? strerror(errno) : "write error");
        return 3;
    }
    return status;
}

int cli_main(int argc, char **argv)
{
    cli__set_command_line(argc, argv);
    cli_signals_install();
    aa_set_warn(cli_warn, NULL);
    /* external:renderer=NAME and any other method that runs a program */
    if (aa_method_add_optional()) {
        fprintf(stderr, "aabench: %s\n", aa_last_error());
        return 3;
    }
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return finish(NULL, 0);
    }
    if (!strcmp(argv[1], "--version")) {
        printf("aabench %s\n", AA_VERSION);
        return finish(NULL, 0);
    }
    /* The command never sets a locale, but a plug-in it loads might: its
     * numbers (options read, tables and files written) stay C-locale text. */
    aa__c_numbers numbers;
    if (aa__c_numbers_begin(&numbers)) {
        fprintf(stderr, "aabench: cannot make the C locale\n");
        return 3;
    }
    for (const struct command *c = commands; c->name; c++)
        if (!strcmp(argv[1], c->name)) {
            int code = c->run(argc - 1, argv + 1);
            aa__c_numbers_end(&numbers);
            return finish(c->name, code);
        }
    aa__c_numbers_end(&numbers);
    fprintf(stderr, "aabench: unknown command \"%s\"\n", aa_echo(argv[1]));
    usage(stderr);
    return 2;
}
