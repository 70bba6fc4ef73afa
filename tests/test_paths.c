/*
 * test_paths.c: where a program built in the source tree finds its data
 * and its reference cache (harness/core/paths.c): the tree found from the
 * program's own file, the SVG scenes in it (the svg pattern's default file
 * and the vector suite), and the default cache folder inside and outside
 * the tree (the XDG base directory rules: $XDG_CACHE_HOME when absolute,
 * else ~/.cache).
 *
 * The expected tree is found another way: the test runs from it (make runs
 * every test from the tree's root), so it is the current folder or one
 * above it that holds harness/aabench.h.
 */
#include "bench.h"
#include "support.h"

#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

static char root[PATH_MAX];

/* The folder at or above the current one that holds harness/aabench.h. */
static void expected_root(void)
{
    if (*root)
        return;
    char dir[PATH_MAX];
    struct stat st;
    assert_non_null(getcwd(dir, sizeof dir));
    for (;;) {
        char probe[PATH_MAX + 32];
        snprintf(probe, sizeof probe, "%s/harness/aabench.h", dir);
        if (stat(probe, &st) == 0) {
            snprintf(root, sizeof root, "%s", dir);
            return;
        }
        char *slash = strrchr(dir, '/');
        if (!slash || slash == dir)
            fail_msg("run the test from the source tree (no harness/aabench.h above %s)", dir);
        *slash = '\0';
    }
}

static void test_source_tree(void **state)
{
    (void)state;
    expected_root();
    assert_non_null(aa_source_tree());
    assert_string_equal(aa_source_tree(), root);
}

static void test_svg_dir(void **state)
{
    (void)state;
    expected_root();
    char want[PATH_MAX + 64];
    const char *env = getenv("AABENCH_SVG_DIR");
    if (env && *env)
        snprintf(want, sizeof want, "%s", env);
    else
        snprintf(want, sizeof want, "%s/patterns/svg", root);
    assert_string_equal(aa_svg_dir(), want);

    /* the svg pattern's default file is the shipped shapes.svg there */
    aa_spec spec;
    char text[PATH_MAX + 64], expect[PATH_MAX + 128];
    assert_int_equal(aa_pattern_parse("svg", &spec), AA_OK);
    assert_int_equal(aa_spec_format(&spec, text, sizeof text), AA_OK);
    snprintf(expect, sizeof expect, "svg:file=%s/shapes.svg,scale=1", want);
    assert_string_equal(text, expect);

    /* the vector suite's first group: crow, then the five shipped scenes */
    static const char *const names[] = {"mono.svg", "shapes.svg", "rules.svg", "curves.svg",
                                        "logo.svg"};
    const aa_suite *vector = aa_suite_find("vector");
    assert_non_null(vector);
    const char *const *p = vector->groups[0].patterns;
    assert_string_equal(p[0], "crow");
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        snprintf(expect, sizeof expect, "svg:file=%s/%s", want, names[k]);
        assert_non_null(p[k + 1]);
        assert_string_equal(p[k + 1], expect);
        struct stat st;
        assert_int_equal(stat(p[k + 1] + strlen("svg:file="), &st), 0);
    }
    assert_null(p[6]);
}

/* Set or clear an environment variable. */
static void env(const char *name, const char *value)
{
    if (value)
        assert_int_equal(setenv(name, value, 1), 0);
    else
        assert_int_equal(unsetenv(name), 0);
}

static void test_cache_dir(void **state)
{
    (void)state;
    expected_root();
    char cwd[PATH_MAX], want[PATH_MAX + 64];
    assert_non_null(getcwd(cwd, sizeof cwd));
    static const char *const names[] = {"AABENCH_CACHE", "XDG_CACHE_HOME", "HOME"};
    char *saved[3];
    for (int k = 0; k < 3; k++)
        saved[k] = getenv(names[k]) ? strdup(getenv(names[k])) : NULL;
    env("AABENCH_CACHE", NULL);
    env("XDG_CACHE_HOME", "/xdg/cache");
    env("HOME", "/home/someone");

    /* inside the tree: its results/cache, relative at the root */
    assert_int_equal(chdir(root), 0);
    assert_string_equal(aa_cache_dir_default(), "results/cache");
    snprintf(want, sizeof want, "%s/harness", root);
    assert_int_equal(chdir(want), 0);
    snprintf(want, sizeof want, "%s/results/cache", root);
    assert_string_equal(aa_cache_dir_default(), want);

    /* outside it: $XDG_CACHE_HOME/aabench, else ~/.cache/aabench; an
     * XDG_CACHE_HOME that is not absolute is ignored */
    assert_int_equal(chdir("/"), 0);
    assert_string_equal(aa_cache_dir_default(), "/xdg/cache/aabench");
    env("XDG_CACHE_HOME", "relative/cache");
    assert_string_equal(aa_cache_dir_default(), "/home/someone/.cache/aabench");
    env("XDG_CACHE_HOME", NULL);
    assert_string_equal(aa_cache_dir_default(), "/home/someone/.cache/aabench");
    env("HOME", NULL);
    assert_string_equal(aa_cache_dir_default(), "results/cache");

    /* $AABENCH_CACHE wins everywhere */
    env("AABENCH_CACHE", "/some/cache");
    assert_string_equal(aa_cache_dir_default(), "/some/cache");
    assert_int_equal(chdir(root), 0);
    assert_string_equal(aa_cache_dir_default(), "/some/cache");
    assert_int_equal(chdir(cwd), 0);
    for (int k = 0; k < 3; k++) {
        env(names[k], saved[k]);
        free(saved[k]);
    }
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_source_tree),
             cmocka_unit_test(test_svg_dir),
             cmocka_unit_test(test_cache_dir))
