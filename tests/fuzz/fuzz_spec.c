/*
 * fuzz_spec.c: libFuzzer target for the spec parsers (`make fuzz`).
 *
 * The input, as a NUL-terminated string, goes to every parser a command
 * line reaches: patterns, filters, methods (with the box filter and with
 * the parsed filter), sizes and display encodings.  A parse must return a
 * status and never crash, read out of bounds or leave a half-made spec; an
 * accepted pattern spec must also pass its own domain check again.
 */
#include "bench.h"
#include "fuzz.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int aa_fuzz_spec(const uint8_t *data, size_t size)
{
    /* statically linked: register the built-in methods (core.h) */
    if (aa_method_add_builtin())
        abort();
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    aa_spec spec;
    aa_filter f, box;
    aa_encode enc;
    int w, h;
    aa_filter_default(&box);
    if (aa_pattern_parse(text, &spec) == AA_OK) {
        char canon[1024];
        /* the canonical text parses back to the same values */
        if (aa_spec_format(&spec, canon, sizeof canon) == AA_OK) {
            aa_spec again;
            if (aa_pattern_parse(canon, &again) != AA_OK ||
                memcmp(again.v, spec.v, sizeof spec.v) != 0)
                abort();
        }
    }
    if (aa_filter_parse(text, &f) == AA_OK)
        (void)aa_method_parse("supersample", &f, &spec);
    (void)aa_method_parse(text, &box, &spec);
    (void)aa_size_parse(text, &w, &h);
    (void)aa_encode_parse(text, &enc);
    free(text);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_spec)
