/*
 * main.c: the `aabench` command: finds the subcommand and runs it.
 */
#include "cli.h"
#include "c_numbers_internal.h"

#include <string.h>

static const struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} commands[] = {
    {"list", cmd_list, "list patterns, filters and methods"},
    {"truth", cmd_truth, "write the exact reference image of a pattern"},
    {"render", cmd_render, "render a pattern with a method, timed"},
    {"run", cmd_run, "the benchmark: every method on a suite, measured and plotted"},
    {"check", cmd_check, "rerun the baseline's cases; exit 1 on a regression"},
    {"converge", cmd_converge, "RMSE against samples per pixel, and its slope"},
    {"compare", cmd_compare, "error metrics between two image files"},
    {"stress", cmd_stress, "numerical stress cases against a long double evaluation"},
    {"figures", cmd_figures, "the seed papers' comparison figures remade, with a gallery"},
    {NULL, NULL, NULL}};

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench COMMAND [options]\n\n"
                 "A benchmark and test harness for antialiasing methods.\n\ncommands:\n");
    for (const struct command *c = commands; c->name; c++)
        fprintf(out, "  %-8s %s\n", c->name, c->summary);
    fprintf(out, "\nSpecs are NAME or NAME:key=value,... (e.g. crow:curves=64, tent:r=1).\n"
                 "'aabench COMMAND --help' describes a command.\n"
                 "Exit status: 0 success, 1 a check failed, 2 bad input or usage,\n"
                 "3 input/output or internal error.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("aabench %s\n", AA_VERSION);
        return 0;
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
            return code;
        }
    aa__c_numbers_end(&numbers);
    fprintf(stderr, "aabench: unknown command \"%s\"\n", argv[1]);
    usage(stderr);
    return 2;
}
