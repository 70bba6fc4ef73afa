/*
 * tier.h: the cases of a test whose full tier is the same file compiled
 * with TIER_FULL set to 1 (its *_full.c; tests/README.md, "Tiers").
 * TIER(quick, full, san) is quick in the quick tier, full in the full
 * tier, san in the full tier under the sanitizers (AA_SANITIZED: the
 * Makefile's sanitizer build sets it for the tests), and TIER_NAME names
 * the one taken; FILTERS(...) is a list of filter specs ending in NULL;
 * SAN_SUBSET and SAN_CASES_PRINT for a test of one tier with a sanitizer
 * subset (below).
 */
#ifndef AA_TEST_TIER_H
#define AA_TEST_TIER_H

#ifndef TIER_FULL
#define TIER_FULL 0
#endif
#if !TIER_FULL
#define TIER(quick, full, san) (quick)
#define TIER_NAME "quick"
#elif defined(AA_SANITIZED)
#define TIER(quick, full, san) (san)
#define TIER_NAME "full, the sanitizer build's subset"
#else
#define TIER(quick, full, san) (full)
#define TIER_NAME "full"
#endif
#define FILTERS(...) ((const char *const[]){__VA_ARGS__, NULL})

/* SAN_SUBSET: 1 in the sanitizer build (AA_SANITIZED), where a test may
 * run a declared subset of its cases (tests/README.md, "Tiers"), else 0;
 * SAN_CASES_PRINT() prints the line such a test begins with, which of the
 * two it runs (cmocka's print_message: where cmocka.h is included). */
#ifdef AA_SANITIZED
#define SAN_SUBSET 1
#else
#define SAN_SUBSET 0
#endif
#define SAN_CASES_PRINT()                                                                          \
    print_message("cases: %s\n", SAN_SUBSET ? "the sanitizer build's subset" : "all")

#endif
