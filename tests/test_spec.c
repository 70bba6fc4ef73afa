/*
 * test_spec.c: parsing specs, parameters and sizes; every registered type
 * (patterns, filters) has a consistent parameter table.
 */
#include "bench.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

static const void *const *pattern_table(void) { return (const void *const *)aa_pattern_types; }
static const void *const *filter_table(void) { return (const void *const *)aa_filter_types; }

static void test_defaults(void **state)
{
    (void)state;
    aa_spec s;
    assert_int_equal(aa_spec_parse("crow", pattern_table(), "pattern", &s), AA_OK);
    /* patterns/README.md, `crow`: curves 96, kmax 0.6, gap0 4/256, gap1 0.5/256 */
    assert_true(s.v[0] == 96 && s.v[1] == 0.6 && s.v[2] == 4.0 / 256 && s.v[3] == 0.5 / 256);
    assert_int_equal(aa_spec_parse("tent", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 1.0); /* patterns/README.md, "Filters": default R = 1 */
    assert_int_equal(aa_spec_parse("gauss", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 0.5); /* patterns/README.md, "Filters": default S = 0.5 */
}

static void test_values(void **state)
{
    (void)state;
    aa_spec s;
    assert_int_equal(aa_spec_parse("crow:curves=64,gap0=4/256", pattern_table(), "pattern", &s),
                     AA_OK);
    assert_true(s.v[0] == 64 && s.v[2] == 0.015625);
    assert_int_equal(aa_spec_parse("tent:r=0.5", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 0.5);
    assert_int_equal(aa_spec_parse("gauss:s=1e0", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 1.0);
    /* the decimal forms: a leading point, a sign, an exponent with its sign */
    assert_int_equal(aa_spec_parse("tent:r=.25", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 0.25);
    assert_int_equal(aa_spec_parse("gauss:s=+2.5E-1", filter_table(), "filter", &s), AA_OK);
    assert_true(s.v[0] == 0.25);
    assert_int_equal(aa_spec_parse("crow:gap1=3./2e+1", pattern_table(), "pattern", &s), AA_OK);
    assert_true(s.v[3] == 3.0 / 20.0);
}

static void refused(const char *text, const void *const *table, const char *needle)
{
    aa_spec s;
    int st = aa_spec_parse(text, table, "thing", &s);
    if (st != AA_EINVAL || !strstr(aa_last_error(), needle))
        fail_msg("\"%s\": status %d, message \"%s\", expected it to mention \"%s\"", text, st,
                 aa_last_error(), needle);
}

static void test_refusals(void **state)
{
    (void)state;
    const void *const *p = pattern_table(), *const *f = filter_table();
    refused("", p, "empty");
    refused("nosuch", p, "known: crow");
    refused("crow:", p, "nothing after");
    refused("crow:bogus=1", p, "accepted: curves, kmax, gap0, gap1");
    refused("crow:curves", p, "not key=value");
    refused("crow:curves=", p, "not a number");
    refused("crow:curves=1.5", p, "not an integer");
    refused("crow:curves=0", p, "out of range");
    refused("crow:curves=1e9", p, "out of range");
    refused("crow:kmax=nan", p, "not a number");
    refused("crow:kmax=inf", p, "not a number");
    refused("crow:kmax=-inf", p, "not a number");
    refused("crow:kmax=0x", p, "not a number");
    /* decimal only: strtod would read these as 16, 0.5 and infinity */
    refused("crow:curves=0x10", p, "not a number");
    refused("crow:kmax=0x1p-1", p, "not a number");
    refused("crow:kmax=infinity", p, "not a number");
    refused("crow:kmax=.", p, "not a number");
    refused("crow:kmax=1e", p, "not a number");
    refused("crow:gap0=1/0x2", p, "not a number");
    refused("crow:kmax= 1", p, "not a number");
    refused("crow:gap0=1/0", p, "not a number");
    refused("crow:curves=4,curves=6", p, "twice");
    refused("tent:r=-1", f, "out of range");
    refused("tent:r=0", f, "out of range");
    refused("gauss:s=1e400", f, "not a number");
    refused("box:r=1", f, "accepted: none");
}

/* check(table, info) for every type of the pattern and filter tables. */
static void for_each_type(void (*check)(const void *const *table, const aa_info *info))
{
    const void *const *tables[] = {pattern_table(), filter_table()};
    for (int t = 0; t < 2; t++)
        for (size_t k = 0; tables[t][k]; k++)
            check(tables[t], tables[t][k]);
}

/* The type's canonical text parses back to the same values. */
static void round_trip(const void *const *table, const aa_info *info)
{
    aa_spec a, b;
    char text[2048];
    aa_spec_default(info, &a);
    assert_int_equal(aa_spec_format(&a, text, sizeof text), AA_OK);
    assert_int_equal(aa_spec_parse(text, table, "thing", &b), AA_OK);
    assert_memory_equal(a.v, b.v, sizeof a.v);
}

static void test_format_round_trip(void **state)
{
    (void)state;
    for_each_type(round_trip);
}

/* Numbers print in the shortest form that reads back to the same double
 * (the forms below are Python's repr of the same doubles), and the
 * reference cache's key keeps %.17g, so the cache's names do not change. */
static void test_format_shortest(void **state)
{
    (void)state;
    aa_spec s;
    char buf[512];
    assert_int_equal(aa_spec_parse("crow", pattern_table(), "pattern", &s), AA_OK);
    assert_int_equal(aa_spec_format(&s, buf, sizeof buf), AA_OK);
    assert_non_null(strstr(buf, ",kmax=0.6,"));
    assert_non_null(strstr(buf, ",gap0=0.015625,"));
    assert_int_equal(aa_spec_format_key(&s, buf, sizeof buf), AA_OK);
    assert_non_null(strstr(buf, ",kmax=0.59999999999999998,"));
    const struct {
        const char *in, *out;
    } cases[] = {{"gauss:s=1/3", "gauss:s=0.3333333333333333,cut=0"},
                 {"gauss:s=0.1", "gauss:s=0.1,cut=0"},
                 {"gauss:s=2", "gauss:s=2,cut=0"},
                 {"gauss:s=5e-2", "gauss:s=0.05,cut=0"},
                 {"gauss:s=0.30000000000000004", "gauss:s=0.30000000000000004,cut=0"},
                 {"gauss:s=7.123456789,cut=2", "gauss:s=7.123456789,cut=2"}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        assert_int_equal(aa_spec_parse(cases[k].in, filter_table(), "filter", &s), AA_OK);
        assert_int_equal(aa_spec_format(&s, buf, sizeof buf), AA_OK);
        assert_string_equal(buf, cases[k].out);
    }
    /* cut short: refused, never a shorter number */
    assert_int_equal(aa_spec_parse("gauss:s=1/3", filter_table(), "filter", &s), AA_OK);
    assert_int_equal(aa_spec_format(&s, buf, strlen("gauss:s=0.333") + 1), AA_EFAIL);
}

/* The type's parameter table is consistent: defaults inside their ranges,
 * keys unique, at most AA_MAX_PARAMS, a help text. */
static void consistent(const void *const *table, const aa_info *info)
{
    size_t n = aa_param_count(info);
    assert_true(n <= AA_MAX_PARAMS);
    assert_non_null(info->summary);
    assert_true(aa_table_find(table, info->name) == info);
    for (size_t q = 0; q < n; q++) {
        const aa_param *p = &info->params[q];
        assert_non_null(p->help);
        assert_int_equal(aa_spec_index(info, p->key), (int)q);
        if (p->kind != AA_PARAM_CHOICE)
            assert_true(p->def >= p->min && p->def <= p->max &&
                        !(p->open_min && p->def == p->min));
    }
}

/* Every parameter table is consistent. */
static void test_tables(void **state)
{
    (void)state;
    for_each_type(consistent);
}

static void test_sizes(void **state)
{
    (void)state;
    int w, h;
    assert_int_equal(aa_size_parse("256x129", &w, &h), AA_OK);
    assert_true(w == 256 && h == 129);
    assert_int_equal(aa_size_parse("1x1", &w, &h), AA_OK);
    const char *bad[] = {"", "256", "x256", "256x", "0x5", "5x0", "-5x5", "5x-5", "5.5x5",
                         "5x5x5", "65537x1", "99999999999x1", " 5x5", "5x5 ", "0x10"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
        if (aa_size_parse(bad[k], &w, &h) != AA_EINVAL)
            fail_msg("size \"%s\" accepted", bad[k]);
    /* 65536 x 65536 x 3 doubles is 103 GB: more than this machine's memory */
    assert_int_equal(aa_size_check(65536, 65536, 3, 1), AA_EINVAL);
    assert_non_null(strstr(aa_last_error(), "GB"));
    assert_int_equal(aa_size_check(256, 256, 3, 1), AA_OK);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_defaults),
             cmocka_unit_test(test_values),
             cmocka_unit_test(test_refusals),
             cmocka_unit_test(test_format_round_trip),
             cmocka_unit_test(test_format_shortest),
             cmocka_unit_test(test_tables),
             cmocka_unit_test(test_sizes))
