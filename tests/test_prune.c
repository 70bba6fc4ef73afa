/*
 * test_prune.c: aa_runs_prune and `aabench prune`: the oldest run folders
 * removed, the newest N kept by the UTC times in their names, the folder
 * results/latest points to kept, anything that is not a run folder left
 * alone.
 */
#include "bench.h"
#include "prune.h"
#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

static int setup(void **state)
{
    static char dir[512];
    if (support_tmpdir(dir, sizeof dir, "prune") != 0)
        return -1;
    *state = dir;
    return 0;
}

static void make_run(const char *results, const char *name, int with_json)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/runs/%s", results, name);
    assert_int_equal(aa_mkdirs(path), AA_OK);
    snprintf(path, sizeof path, "%s/runs/%s/images", results, name);
    assert_int_equal(aa_mkdirs(path), AA_OK);
    snprintf(path, sizeof path, "%s/runs/%s/images/a.png", results, name);
    support_write_file(path, "x", 1);
    if (with_json) {
        snprintf(path, sizeof path, "%s/runs/%s/run.json", results, name);
        support_write_file(path, "{}", 2);
    }
}

static int exists(const char *results, const char *name)
{
    char path[1024];
    struct stat st;
    snprintf(path, sizeof path, "%s/runs/%s", results, name);
    return stat(path, &st) == 0;
}

/* Run folders made out of time order; by their names, oldest first:
 * 20250101T000000Z, 20250101T000000Z-2, 20250101T000000Z-10 (K 10 after
 * K 2, though "-10" < "-2" as text), 20250301T120000Z, 20251231T235959Z,
 * 20260101T000000Z.  latest points to the oldest. */
static const char *const runs[] = {"20251231T235959Z", "20250101T000000Z-10", "20260101T000000Z",
                                   "20250101T000000Z", "20250301T120000Z", "20250101T000000Z-2"};
/* not run folders: no run.json, or a name a run does not have */
static const char *const others[] = {"20240101T000000Z", "notes", "20240101T000000Z-1",
                                     "2024-01-01"};

static void make_all(const char *results)
{
    char path[1024], link[1024];
    for (size_t i = 0; i < 6; i++)
        make_run(results, runs[i], 1);
    make_run(results, others[0], 0);
    for (size_t i = 1; i < 4; i++)
        make_run(results, others[i], 1);
    snprintf(path, sizeof path, "runs/20250101T000000Z");
    snprintf(link, sizeof link, "%s/latest", results);
    unlink(link);
    assert_int_equal(symlink(path, link), 0);
}

static void count_each(void *ctx, const char *dir)
{
    (void)dir;
    (*(int *)ctx)++;
}

static void test_prune_keeps_newest(void **state)
{
    char results[600];
    snprintf(results, sizeof results, "%s/results", (const char *)*state);
    make_all(results);
    int said = 0;
    size_t removed = 99;

    /* dry run: the count, nothing removed */
    assert_int_equal(aa_runs_prune(results, 2, 1, count_each, &said, &removed), AA_OK);
    /* 6 runs, 2 kept, latest's target kept: 3 */
    assert_int_equal(removed, 3);
    assert_int_equal(said, 3);
    for (size_t i = 0; i < 6; i++)
        assert_true(exists(results, runs[i]));

    said = 0;
    assert_int_equal(aa_runs_prune(results, 2, 0, count_each, &said, &removed), AA_OK);
    assert_int_equal(removed, 3);
    assert_int_equal(said, 3);
    assert_true(exists(results, "20260101T000000Z"));
    assert_true(exists(results, "20251231T235959Z"));
    assert_true(exists(results, "20250101T000000Z")); /* latest's */
    assert_false(exists(results, "20250301T120000Z"));
    assert_false(exists(results, "20250101T000000Z-10"));
    assert_false(exists(results, "20250101T000000Z-2"));
    for (size_t i = 0; i < 4; i++)
        assert_true(exists(results, others[i]));

    /* keep 0: all but latest's; a second time removes nothing */
    assert_int_equal(aa_runs_prune(results, 0, 0, NULL, NULL, &removed), AA_OK);
    assert_int_equal(removed, 2);
    assert_true(exists(results, "20250101T000000Z"));
    assert_false(exists(results, "20260101T000000Z"));
    assert_int_equal(aa_runs_prune(results, 0, 0, NULL, NULL, &removed), AA_OK);
    assert_int_equal(removed, 0);
    for (size_t i = 0; i < 4; i++)
        assert_true(exists(results, others[i]));
    support_rmtree(results);
}

static void test_prune_order_of_k(void **state)
{
    /* keep 4 of the 6: the two oldest go, 20250101T000000Z (latest's, kept)
     * and 20250101T000000Z-2; -10 is newer than -2 */
    char results[600];
    snprintf(results, sizeof results, "%s/results", (const char *)*state);
    make_all(results);
    char link[700];
    snprintf(link, sizeof link, "%s/latest", results);
    assert_int_equal(unlink(link), 0); /* no latest: nothing kept besides the 4 */
    size_t removed = 0;
    assert_int_equal(aa_runs_prune(results, 4, 0, NULL, NULL, &removed), AA_OK);
    assert_int_equal(removed, 2);
    assert_false(exists(results, "20250101T000000Z"));
    assert_false(exists(results, "20250101T000000Z-2"));
    assert_true(exists(results, "20250101T000000Z-10"));
    assert_true(exists(results, "20250301T120000Z"));
    support_rmtree(results);
}

static void test_prune_refuses(void **state)
{
    char results[600];
    snprintf(results, sizeof results, "%s/none", (const char *)*state);
    size_t removed = 7;
    assert_int_equal(aa_runs_prune(results, -1, 0, NULL, NULL, &removed), AA_EINVAL);
    assert_int_equal(aa_runs_prune(results, 3, 0, NULL, NULL, &removed), AA_OK);
    assert_int_equal(removed, 0);
    assert_true(aa_runs_name("20250101T000000Z"));
    assert_true(aa_runs_name("20250101T000000Z-99"));
    assert_false(aa_runs_name("20250101T000000Z-1"));
    assert_false(aa_runs_name("20250101T000000Z-100"));
    assert_false(aa_runs_name("20250101X000000Z"));
    assert_false(aa_runs_name("latest"));
}

static void test_prune_command(void **state)
{
    char results[600], out[4096];
    snprintf(results, sizeof results, "%s/results", (const char *)*state);
    make_all(results);
    const char *dry[] = {"prune", "--keep", "2", "--dry-run", "--results", results, NULL};
    assert_int_equal(support_aabench(dry, out, sizeof out), 0);
    assert_non_null(strstr(out, "would remove 3 run folders"));
    assert_true(exists(results, "20250301T120000Z"));
    const char *bad[][7] = {{"prune", "--keep", "-1", "--results", results, NULL},
                            {"prune", "--keep", "x", "--results", results, NULL},
                            {"prune", "--keep", "0x2", "--results", results, NULL},
                            {"prune", "--results", results, NULL},
                            {"prune", "--keep", "1", "extra", NULL}};
    for (size_t i = 0; i < 5; i++)
        assert_int_equal(support_aabench(bad[i], out, sizeof out), 2);
    const char *help[] = {"prune", "--help", NULL};
    assert_int_equal(support_aabench(help, out, sizeof out), 0);
    assert_non_null(strstr(out, "--keep N"));
    const char *go[] = {"prune", "--keep", "2", "--results", results, NULL};
    assert_int_equal(support_aabench(go, out, sizeof out), 0);
    assert_non_null(strstr(out, "removed 3 run folders"));
    assert_false(exists(results, "20250301T120000Z"));
    assert_true(exists(results, "20250101T000000Z"));
    support_rmtree(results);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_prune_keeps_newest),
        cmocka_unit_test(test_prune_order_of_k),
        cmocka_unit_test(test_prune_refuses),
        cmocka_unit_test(test_prune_command),
    };
    return cmocka_run_group_tests(tests, setup, support_teardown_dir);
}
