/*
 * fuzz.h: the fuzz targets (fuzz_spec.c, fuzz_image.c, fuzz_cache.c,
 * fuzz_baseline.c, fuzz_svg.c, fuzz_stroke.c), called by libFuzzer under `make fuzz` and by
 * test_fuzz_regress.c on every test run.
 */
#ifndef AA_FUZZ_H
#define AA_FUZZ_H

#include <stddef.h>
#include <stdint.h>

/* Each takes one input and returns 0; a broken invariant aborts. */
int aa_fuzz_spec(const uint8_t *data, size_t size);
int aa_fuzz_image(const uint8_t *data, size_t size);
int aa_fuzz_cache(const uint8_t *data, size_t size);
int aa_fuzz_baseline(const uint8_t *data, size_t size);
int aa_fuzz_svg(const uint8_t *data, size_t size);
int aa_fuzz_stroke(const uint8_t *data, size_t size);

/* libFuzzer's entry point, which it declares in no header of its own. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A target's definition of that entry point, calling fn; nothing where
 * test_fuzz_regress.c includes the targets (AA_FUZZ_NO_MAIN). */
#ifdef AA_FUZZ_NO_MAIN
#define AA_FUZZ_ENTRY(fn)
#else
#define AA_FUZZ_ENTRY(fn)                                                                          \
    int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)                                   \
    {                                                                                              \
        return fn(data, size);                                                                     \
    }
#endif

#endif
