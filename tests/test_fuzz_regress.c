/*
 * test_fuzz_regress.c: the fuzz targets' seed corpus and every input that
 * once crashed them (tests/fuzz/corpus/, tests/fuzz/regress/), run through
 * the same code as `make fuzz` on every `make test` (plain and under
 * ASan+UBSan): the spec parsers, the image readers, the reference cache's
 * reader, the results CSV reader and the stroker.  The targets abort on a broken
 * invariant (a spec whose canonical text parses differently, an image that
 * does not read back as written, a wrong reference served, a baseline row
 * the gate cannot trust accepted); the sanitizers catch the rest.
 */
#define AA_FUZZ_NO_MAIN
#include "fuzz/fuzz_baseline.c"
#include "fuzz/fuzz_cache.c"
#include "fuzz/fuzz_image.c"
#include "fuzz/fuzz_spec.c"
#include "fuzz/fuzz_stroke.c"
#include "fuzz/fuzz_svg.c"
#include "support.h"

#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

/* Feed every regular file of `dir` to fn; returns how many (0 if the
 * folder does not exist). */
static int feed(const char *dir, int (*fn)(const uint8_t *, size_t))
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        uint8_t buf[65536];
        size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        fn(buf, len);
        n++;
    }
    closedir(d);
    return n;
}

static void test_spec_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/spec", aa_fuzz_spec) >= 10);
    feed("tests/fuzz/regress/spec", aa_fuzz_spec);
    /* and a few made here: long, unterminated, all separators */
    static const char *more[] = {"crow:", "crow:curves", "crow:curves=", ":", ",,,", "x:y=1,y=2",
                                 "crow:curves=96,curves=96", "tent:r=1e-400", "gauss:s=0x10",
                                 "jitter:spp=16,seq=", "65536x65536", "0x0", "-1x5", "gamma:"};
    for (size_t k = 0; k < sizeof more / sizeof more[0]; k++)
        aa_fuzz_spec((const uint8_t *)more[k], strlen(more[k]));
    char big[5000];
    memset(big, 'a', sizeof big);
    aa_fuzz_spec((const uint8_t *)big, sizeof big);
}

static void test_image_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/image", aa_fuzz_image) >= 4);
    feed("tests/fuzz/regress/image", aa_fuzz_image);
}

static void test_cache_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/cache", aa_fuzz_cache) >= 4);
    feed("tests/fuzz/regress/cache", aa_fuzz_cache);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache_dir);
    assert_int_equal(system(cmd), 0);
}

static void test_baseline_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/baseline", aa_fuzz_baseline) >= 8);
    assert_true(feed("tests/fuzz/regress/baseline", aa_fuzz_baseline) >= 7);
}

static void test_svg_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/svg", aa_fuzz_svg) >= 8);
    feed("tests/fuzz/regress/svg", aa_fuzz_svg);
    /* and a few made here: cut short, empty, binary */
    static const char *more[] = {"", "<", "<svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M",
                                 "\xef\xbb\xbf<svg/>", "<?xml?><svg/>"};
    for (size_t k = 0; k < sizeof more / sizeof more[0]; k++)
        aa_fuzz_svg((const uint8_t *)more[k], strlen(more[k]));
}

static void test_stroke_inputs(void **state)
{
    (void)state;
    assert_true(feed("tests/fuzz/corpus/stroke", aa_fuzz_stroke) >= 8);
    feed("tests/fuzz/regress/stroke", aa_fuzz_stroke);
    /* and a few made here: empty, one byte, all ones */
    uint8_t ones[300];
    memset(ones, 0xff, sizeof ones);
    aa_fuzz_stroke(ones, 0);
    aa_fuzz_stroke(ones, 1);
    aa_fuzz_stroke(ones, sizeof ones);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_spec_inputs),
             cmocka_unit_test(test_image_inputs),
             cmocka_unit_test(test_cache_inputs),
             cmocka_unit_test(test_baseline_inputs),
             cmocka_unit_test(test_svg_inputs),
             cmocka_unit_test(test_stroke_inputs))
