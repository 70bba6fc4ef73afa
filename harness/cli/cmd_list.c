/*
 * cmd_list.c: `aabench list [patterns|filters] [-v]`.
 */
#include "cli.h"

#include <string.h>

static void list_table(const void *const *table, int verbose)
{
    for (size_t k = 0; table[k]; k++) {
        const aa_info *info = table[k];
        printf("%s\t%s\n", info->name, info->summary);
        if (!verbose)
            continue;
        for (size_t p = 0; p < aa_param_count(info); p++) {
            const aa_param *q = &info->params[p];
            if (q->kind == AA_PARAM_CHOICE) {
                const char *start = q->choices;
                for (int w = 0; w < (int)q->def; w++)
                    start = strchr(start, '|') + 1;
                const char *stop = strchr(start, '|');
                int wl = stop ? (int)(stop - start) : (int)strlen(start);
                printf("    %s=%.*s  (%s)  %s\n", q->key, wl, start, q->choices, q->help);
            } else if (q->kind == AA_PARAM_WORD) {
                printf("    %s=%s  (a name)  %s\n", q->key, q->choices ? q->choices : "", q->help);
            } else if (q->kind == AA_PARAM_TEXT) {
                printf("    %s=%s  (text)  %s\n", q->key, q->choices ? q->choices : "", q->help);
            } else {
                printf("    %s=%.17g  (%s %.17g to %.17g)  %s\n", q->key, q->def,
                       q->kind == AA_PARAM_INT ? "integer" : (q->open_min ? "real, above" : "real"),
                       q->min, q->max, q->help);
            }
        }
    }
}

static void usage(FILE *out)
{
    fprintf(out, "usage: aabench list [methods|patterns|filters] [-v] [--plugin LIB.so]\n\n"
                 "Prints one line per type: name, tab, one-line summary.\n"
                 "  -v, --params       also list each type's parameters with default and range\n"
                 "      --plugin LIB   load methods from a shared library first (repeatable)\n");
}

int cmd_list(int argc, char **argv)
{
    static const struct option opts[] = {{"params", no_argument, 0, 'v'},
                                         {"plugin", required_argument, 0, 'P'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    int c, verbose = 0, st;
    cli_getopt_reset();
    while ((c = getopt_long(argc, argv, ":vh", opts, NULL)) != -1) {
        if (c == 'v')
            verbose = 1;
        else if (c == 'P') {
            if ((st = aa_plugin_load(optarg)))
                return cli_fail("list", st);
        } else if (c == 'h') {
            usage(stdout);
            return 0;
        } else
            return cli_bad_option("list", c, argv);
    }
    if (argc - optind > 1) {
        usage(stderr);
        return 2;
    }
    const char *what = optind < argc ? argv[optind] : NULL;
    if (what && strcmp(what, "methods") && strcmp(what, "patterns") && strcmp(what, "filters")) {
        fprintf(stderr, "aabench list: unknown list \"%s\" (methods, patterns or filters)\n",
                aa_echo(what));
        return 2;
    }
    if (!what || !strcmp(what, "methods")) {
        if (!what)
            printf("# methods\n");
        list_table(aa_method_table(), verbose);
    }
    if (!what || !strcmp(what, "patterns")) {
        if (!what)
            printf("# patterns\n");
        list_table((const void *const *)aa_pattern_types, verbose);
    }
    if (!what || !strcmp(what, "filters")) {
        if (!what)
            printf("# filters\n");
        list_table((const void *const *)aa_filter_types, verbose);
    }
    return 0;
}
