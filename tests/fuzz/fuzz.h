/*
 * fuzz.h: the fuzz targets (fuzz_spec.c, fuzz_image.c, fuzz_cache.c,
 * fuzz_baseline.c, fuzz_svg.c), called by libFuzzer under `make fuzz` and by
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

/* libFuzzer's entry point, which it declares in no header of its own. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#endif
