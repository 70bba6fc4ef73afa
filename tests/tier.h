/*
 * tier.h: the cases of a test whose full tier is the same file compiled
 * with TIER_FULL set to 1 (its *_full.c; tests/README.md, "Tiers").
 * TIER(quick, full, san) is quick in the quick tier, full in the full
 * tier, san in the full tier under the sanitizers (AA_SANITIZED: the
 * Makefile's sanitizer build sets it for the tests), and TIER_NAME names
 * the one taken; FILTERS(...) is a list of filter specs ending in NULL.
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

#endif
