/*
 * test_image.c: images in memory and in files (harness/core/image.c,
 * image_txt.c, files.c, oiio.cpp), and the OpenImageIO module loaded only
 * when a file needs it.
 *
 * Every test works in a fresh folder (support_tmpdir); the teardown checks
 * that no temporary file (a name with a leading dot) was left behind, then
 * removes the folder.  Known answers say where they come from: none was
 * obtained by running the code under test.
 */
#define _XOPEN_SOURCE 700 /* nftw, for removing the test folder */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <ftw.h>
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sys/wait.h>
#include "bench.h"
#include "support.h"

/* ------------------------------------------------------------------------
 * The test folder
 * ------------------------------------------------------------------------ */

typedef struct fixture {
    char dir[PATH_MAX];
} fixture;

static int setup(void **state)
{
    fixture *fx = calloc(1, sizeof *fx);
    if (fx == NULL)
        return -1;
    if (support_tmpdir(fx->dir, sizeof fx->dir, "test-image") != 0) {
        free(fx);
        return -1;
    }
    *state = fx;
    return 0;
}

static int leftovers;

static int count_leftover(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    if (ftw->level > 0 && path[ftw->base] == '.') {
        print_error("temporary file left behind: %s\n", path);
        leftovers++;
    }
    return 0;
}

static int teardown(void **state)
{
    fixture *fx = *state;
    leftovers = 0;
    nftw(fx->dir, count_leftover, 16, FTW_PHYS);
    int failed = leftovers != 0;
    if (support_rmtree(fx->dir) != 0)
        failed = 1;
    free(fx);
    return failed ? -1 : 0;
}

/* A path in the test folder (valid until the next call). */
static const char *in_dir(void **state, const char *name)
{
    static char path[PATH_MAX + 64];
    fixture *fx = *state;
    snprintf(path, sizeof path, "%s/%s", fx->dir, name);
    return path;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Entries in a folder, besides "." and "..". */
static int entries(const char *dir)
{
    return support_count_entries(dir, NULL);
}

/* The whole content of a small file, NUL-terminated. */
static char *slurp(const char *path, size_t *len)
{
    static char buf[1 << 16];
    return support_read_file(path, buf, sizeof buf, len);
}

/* The refusal has this status and a message naming `what` (and "what:line:"
 * when line > 0). */
static void assert_refused(int status, int expected, const char *what, int line)
{
    const char *msg = aa_last_error();
    if (status != expected)
        print_error("status %d, expected %d; message: %s\n", status, expected, msg);
    assert_int_equal(status, expected);
    char want[PATH_MAX + 32];
    if (line > 0)
        snprintf(want, sizeof want, "%s:%d:", what, line);
    else
        snprintf(want, sizeof want, "%s", what);
    if (strstr(msg, want) == NULL)
        print_error("message '%s' does not name '%s'\n", msg, want);
    assert_non_null(strstr(msg, want));
}

/* Fill with a value per (i, j, k) that differs across channels, rows and
 * columns, so a transposed or reordered read shows. */
static void fill_distinct(aa_image *im, double scale)
{
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            for (int k = 0; k < im->c; k++)
                aa_pixel(im, i, j)[k] = scale * (1 + i + 16 * j + 256 * k);
}

/* The image is w x h with c channels. */
static void assert_shape(const aa_image *im, int w, int h, int c)
{
    assert_int_equal(im->w, w);
    assert_int_equal(im->h, h);
    assert_int_equal(im->c, c);
}

static void assert_same_bits(const aa_image *a, const aa_image *b)
{
    assert_shape(a, b->w, b->h, b->c);
    assert_memory_equal(a->v, b->v, (size_t)a->w * a->h * a->c * sizeof(double));
}

/* ------------------------------------------------------------------------
 * Images in memory
 * ------------------------------------------------------------------------ */

static void test_alloc(void **state)
{
    (void)state;
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 7, 3, 3), AA_OK);
    assert_shape(&im, 7, 3, 3);
    for (size_t k = 0; k < 7 * 3 * 3; k++)
        assert_true(im.v[k] == 0.0);
    /* aa_pixel's layout, from aabench.h: v[((j * w + i) * c + k]. */
    assert_ptr_equal(aa_pixel(&im, 2, 1), im.v + (1 * 7 + 2) * 3);
    aa_image_free(&im);
    assert_null(im.v);
    aa_image_free(&im); /* twice is fine */
    aa_image_free(NULL);

    const int bad[][3] = {{0, 1, 1}, {1, 0, 1}, {1, 1, 0}, {-1, 1, 1}, {1, 1, -3}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(aa_image_alloc(&im, bad[k][0], bad[k][1], bad[k][2]), AA_EINVAL);
        assert_null(im.v);
    }
    /* 2^31-1 cubed doubles is about 2^96 bytes: past any 64-bit size_t. */
    assert_int_equal(aa_image_alloc(&im, INT_MAX, INT_MAX, INT_MAX), AA_EINVAL);
    assert_null(im.v);
}

/* ------------------------------------------------------------------------
 * Display encoding
 * ------------------------------------------------------------------------ */

static void test_encode_parse_accepts(void **state)
{
    (void)state;
    aa_encode e;
    assert_int_equal(aa_encode_parse("srgb", &e), AA_OK);
    assert_int_equal(e.kind, AA_ENCODE_SRGB);
    assert_int_equal(aa_encode_parse("linear", &e), AA_OK);
    assert_int_equal(e.kind, AA_ENCODE_LINEAR);
    const struct {
        const char *text;
        double gamma;
    } ok[] = {{"gamma:1", 1}, {"gamma:2", 2}, {"gamma:2.2", 2.2}, {"gamma:4", 4},
              {"gamma:4.0", 4}, {"gamma:1e0", 1}, {"gamma:+3", 3}, {"gamma:.25e1", 2.5}};
    for (size_t k = 0; k < sizeof ok / sizeof ok[0]; k++) {
        assert_int_equal(aa_encode_parse(ok[k].text, &e), AA_OK);
        assert_int_equal(e.kind, AA_ENCODE_GAMMA);
        assert_true(e.gamma == ok[k].gamma);
    }
}

static void test_encode_parse_refuses(void **state)
{
    (void)state;
    const char *bad[] = {"",          "SRGB",        "sRGB",       "srgb ",      "lin",
                         "gamma",     "gamma:",      "gamma:0.99", "gamma:4.01", "gamma:0",
                         "gamma:-2",  "gamma:nan",   "gamma:inf",  "gamma:2x",   "gamma: 2",
                         "gamma:2 ",  "gamma:0x2p0", "gamma:2,2",  "gamma:1e999", "gamma=2",
                         "gamma:2:3", "rgb"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        aa_encode e = {AA_ENCODE_LINEAR, 1};
        int status = aa_encode_parse(bad[k], &e);
        if (status != AA_EINVAL)
            print_error("'%s' was accepted\n", bad[k]);
        assert_int_equal(status, AA_EINVAL);
        /* The message lists what is accepted. */
        assert_non_null(strstr(aa_last_error(), "srgb, linear, gamma:G"));
        assert_int_equal(e.kind, AA_ENCODE_LINEAR); /* untouched */
    }
    assert_int_equal(aa_encode_parse(NULL, &(aa_encode){0}), AA_EINVAL);
}

static void test_encode_value(void **state)
{
    (void)state;
    const aa_encode srgb = {AA_ENCODE_SRGB, 0}, lin = {AA_ENCODE_LINEAR, 1},
                    g2 = {AA_ENCODE_GAMMA, 2}, g4 = {AA_ENCODE_GAMMA, 4};
    /* sRGB (IEC 61966-2-1): 1.055 v^(1/2.4) - 0.055 above 0.0031308, else
     * 12.92 v.  Values by `bc -l`: 1.055*e(l(0.5)/2.4)-0.055. */
    assert_true(fabs(aa_encode_value(&srgb, 0.5) - 0.73535698305244949062) < 1e-15);
    assert_true(fabs(aa_encode_value(&srgb, 0.001) - 0.01292) < 1e-17);
    assert_true(aa_encode_value(&srgb, 0) == 0);
    assert_true(fabs(aa_encode_value(&srgb, 1) - 1) < 1e-15);
    /* The two branches meet at 0.0031308 to within 3e-8 (bc: 12.92 *
     * 0.0031308 = 0.040449936, the power law gives 0.0404499075). */
    assert_true(fabs(aa_encode_value(&srgb, 0.0031308) - 0.040449936) < 1e-15);
    assert_true(fabs(aa_encode_value(&srgb, nextafter(0.0031308, 1)) - 0.0404499075) < 1e-9);
    /* Clamping to [0, 1], and NaN to 0 (no NaN byte can be written). */
    assert_true(aa_encode_value(&srgb, -3) == 0);
    assert_true(fabs(aa_encode_value(&srgb, 7) - 1) < 1e-15);
    assert_true(aa_encode_value(&srgb, NAN) == 0);
    assert_true(aa_encode_value(&lin, 0.3) == 0.3);
    assert_true(aa_encode_value(&lin, 1.5) == 1);
    assert_true(aa_encode_value(&lin, -INFINITY) == 0);
    /* Power law: 0.25^(1/2) = 0.5 and 0.0625^(1/4) = 0.5 exactly. */
    assert_true(aa_encode_value(&g2, 0.25) == 0.5);
    assert_true(aa_encode_value(&g4, 0.0625) == 0.5);
}

static void test_ext_known(void **state)
{
    (void)state;
    const char *yes[] = {"a.exr", "a.EXR", "d/a.tif", "a.TiFf", "a.png", "a.pfm", "a.txt",
                         "x.y.png", "./a.Txt"};
    const char *no[] = {"a.jpg", "a", "a.", "a.pngx", "a.exr.gz", ".png", "d/.png", "d.png/",
                        "", "a.tx", "png"};
    for (size_t k = 0; k < sizeof yes / sizeof yes[0]; k++)
        assert_int_equal(aa_image_ext_known(yes[k]), 1);
    for (size_t k = 0; k < sizeof no / sizeof no[0]; k++)
        assert_int_equal(aa_image_ext_known(no[k]), 0);
}

/* ------------------------------------------------------------------------
 * The .txt format
 * ------------------------------------------------------------------------ */

/* Values that need all 17 digits, or are edge cases of printf and strtod. */
static const double awkward[] = {
    0.1, 1.0 / 3, 1e-300, -0.0, 5e-324, 1 - 0x1p-53, 0.0, -1.0, 1e300, DBL_MAX, -DBL_MIN,
    2.5, -7.25e-11, 0x1.fffffffffffffp-1022, 123456789.123456789,
};

static void test_txt_exact_text(void **state)
{
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 2, 1, 3), AA_OK);
    const double v[] = {0.1, 1.0 / 3, 1e-300, -0.0, 5e-324, 1 - 0x1p-53};
    memcpy(im.v, v, sizeof v);
    const char *path = in_dir(state, "exact.txt");
    assert_int_equal(aa_image_write_txt(path, &im), AA_OK);
    /* The format is harness/README.md's ("Command line").  The digits are the
     * exact binary values
     * (Python: decimal.Decimal(0.1) = 0.1000000000000000055511...,
     * Decimal(1/3) = 0.33333333333333331482..., Decimal(1e-300) =
     * 1.00000000000000002505...e-300, Decimal(5e-324) =
     * 4.94065645841246544176...e-324, Decimal(1-2**-53) =
     * 0.99999999999999988897...) rounded to 17 significant digits by hand;
     * %g drops trailing zeros (C11 7.21.6.1), so 1e-300 stays short. */
    const char *expected = "# aabench 2 1 3\n"
                           "0 0 0.10000000000000001 0.33333333333333331 1e-300\n"
                           "1 0 -0 4.9406564584124654e-324 0.99999999999999989\n";
    size_t len;
    const char *text = slurp(path, &len);
    assert_int_equal(len, strlen(expected));
    assert_string_equal(text, expected);
    aa_image_free(&im);
}

static void txt_round_trip(void **state, int w, int h, int c)
{
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, w, h, c), AA_OK);
    size_t n = (size_t)w * h * c, na = sizeof awkward / sizeof awkward[0];
    for (size_t k = 0; k < n; k++)
        im.v[k] = k < na ? awkward[k] : (double)k / 7 - 1;
    const char *path = in_dir(state, "round.txt");
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_same_bits(&im, &back); /* -0.0 keeps its sign */
    aa_image_free(&im);
    aa_image_free(&back);
}

static void test_txt_round_trip(void **state)
{
    txt_round_trip(state, 7, 3, 3);
    txt_round_trip(state, 1, 1, 1);
    txt_round_trip(state, 3, 7, 1);
    txt_round_trip(state, 5, 1, 4);
    txt_round_trip(state, 1, 6, 2);
}

static void test_txt_read_known(void **state)
{
    /* Written by hand from harness/README.md's format; blanks may be runs of spaces
     * or tabs and lines may end in CR LF. */
    const char text[] = "# aabench 2 2 2\n"
                        "0 0 0.5 -1e-3\n"
                        "1 0\t0.25   +3\r\n"
                        "0 1 1E2 .5\n"
                        "1 1 -0 7.\n";
    const char *path = in_dir(state, "known.txt");
    support_write_file(path, text, sizeof text - 1);
    aa_image im;
    assert_int_equal(aa_image_read_txt(path, &im), AA_OK);
    assert_shape(&im, 2, 2, 2);
    const double want[] = {0.5, -1e-3, 0.25, 3, 100, 0.5, -0.0, 7};
    assert_memory_equal(im.v, want, sizeof want);
    aa_image_free(&im);
}

/* A corrupt file: its text (with its length, for NUL bytes) and the line
 * the refusal must name (0: any line). */
typedef struct corrupt {
    const char *why;
    const char *text;
    size_t len;
    int line;
} corrupt;

#define CASE(why, text, line) {why, text, sizeof text - 1, line}

static const corrupt corrupt_cases[] = {
    CASE("empty file", "", 1),
    CASE("no header", "0 0 1\n", 1),
    CASE("header missing C", "# aabench 2 1\n0 0 1\n1 0 1\n", 1),
    CASE("header with more", "# aabench 1 1 1 1\n0 0 1\n", 1),
    CASE("misspelt magic", "# aabenc 1 1 1\n0 0 1\n", 1),
    CASE("magic without space", "#aabench 1 1 1\n0 0 1\n", 1),
    CASE("width 0", "# aabench 0 1 1\n", 1),
    CASE("height 0", "# aabench 1 0 1\n", 1),
    CASE("width too large", "# aabench 65537 1 1\n", 1),
    CASE("height too large", "# aabench 1 65537 1\n", 1),
    CASE("0 channels", "# aabench 1 1 0\n", 1),
    CASE("5 channels", "# aabench 1 1 5\n0 0 1 2 3 4 5\n", 1),
    CASE("negative width", "# aabench -1 1 1\n", 1),
    CASE("width not a number", "# aabench 1x 1 1\n", 1),
    CASE("width overflows int", "# aabench 99999999999 1 1\n", 1),
    CASE("real width", "# aabench 1.0 1 1\n", 1),
    /* 65536^2 x 4 doubles is 128 GiB: refused by the size check on most
     * machines (line 1), or allocated lazily and refused at line 2. */
    CASE("huge image", "# aabench 65536 65536 4\n0 0 1 2 3 4\n", 0),
    CASE("column-major order", "# aabench 2 2 1\n0 0 1\n0 1 1\n1 0 1\n1 1 1\n", 3),
    CASE("repeated pixel", "# aabench 2 1 1\n0 0 1\n0 0 1\n", 3),
    CASE("skipped pixel", "# aabench 3 1 1\n0 0 1\n2 0 1\n", 3),
    CASE("negative index", "# aabench 1 1 1\n-0 0 1\n", 2),
    CASE("signed index", "# aabench 1 1 1\n+0 0 1\n", 2),
    CASE("missing index", "# aabench 1 1 1\n0\n", 2),
    CASE("empty pixel line", "# aabench 1 1 1\n\n", 2),
    CASE("missing value", "# aabench 2 1 2\n0 0 1 2\n1 0 1\n", 3),
    CASE("extra value", "# aabench 2 1 1\n0 0 1\n1 0 1 2\n", 3),
    CASE("missing line", "# aabench 2 1 1\n0 0 1\n", 3),
    CASE("missing all lines", "# aabench 2 1 1\n", 2),
    CASE("extra line", "# aabench 1 1 1\n0 0 1\n0 0 1\n", 3),
    CASE("extra blank line", "# aabench 1 1 1\n0 0 1\n\n", 3),
    CASE("no final newline", "# aabench 1 1 1\n0 0 0.12", 2),
    CASE("cut inside header", "# aabench 1 1", 1),
    CASE("nan", "# aabench 1 1 1\n0 0 nan\n", 2),
    CASE("NaN", "# aabench 1 1 1\n0 0 NaN\n", 2),
    CASE("inf", "# aabench 1 1 1\n0 0 inf\n", 2),
    CASE("-infinity", "# aabench 1 1 1\n0 0 -infinity\n", 2),
    CASE("overflow to inf", "# aabench 1 1 1\n0 0 1e999\n", 2),
    CASE("trailing garbage", "# aabench 1 1 1\n0 0 0.5x\n", 2),
    CASE("two points", "# aabench 1 1 1\n0 0 0..5\n", 2),
    CASE("no exponent digits", "# aabench 1 1 1\n0 0 1e\n", 2),
    CASE("hex float", "# aabench 1 1 1\n0 0 0x1p-3\n", 2),
    CASE("lone point", "# aabench 1 1 1\n0 0 .\n", 2),
    CASE("two signs", "# aabench 1 1 1\n0 0 --1\n", 2),
    CASE("decimal comma", "# aabench 1 1 2\n0 0 1,5 2\n", 2),
    CASE("exponent only", "# aabench 1 1 1\n0 0 e5\n", 2),
    CASE("NUL byte", "# aabench 1 1 1\n0 0 1\0\n", 2),
    CASE("NUL in header", "# aabench\0 1 1 1\n0 0 1\n", 1),
};

static void test_txt_corrupt(void **state)
{
    for (size_t k = 0; k < sizeof corrupt_cases / sizeof corrupt_cases[0]; k++) {
        const corrupt *c = &corrupt_cases[k];
        char name[32];
        snprintf(name, sizeof name, "corrupt-%02zu.txt", k);
        const char *path = in_dir(state, name);
        support_write_file(path, c->text, c->len);
        aa_image im = {1, 1, 1, (double *)&im}; /* garbage the reader must clear */
        int status = aa_image_read(path, &im);
        if (status != AA_EIO)
            print_error("case '%s' gave %d\n", c->why, status);
        assert_refused(status, AA_EIO, path, c->line);
        assert_null(im.v);
        assert_int_equal(im.w, 0);
    }
}

static void test_txt_long_line(void **state)
{
    /* Padding a value with blanks is allowed, but not without bound. */
    static char text[4096];
    int n = snprintf(text, sizeof text, "# aabench 1 1 1\n0 0 1");
    memset(text + n, ' ', 3000);
    text[n + 3000] = '\n';
    const char *path = in_dir(state, "long.txt");
    support_write_file(path, text, (size_t)n + 3001);
    aa_image im;
    assert_refused(aa_image_read_txt(path, &im), AA_EIO, path, 2);
    assert_null(im.v);
}

static void test_txt_refuses_non_finite(void **state)
{
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (size_t k = 0; k < 3; k++) {
        aa_image im;
        assert_int_equal(aa_image_alloc(&im, 3, 2, 2), AA_OK);
        aa_pixel(&im, 2, 1)[1] = bad[k];
        const char *path = in_dir(state, "nonfinite.txt");
        assert_refused(aa_image_write(path, &im, NULL), AA_EINVAL, "pixel (2, 1) channel 1", 0);
        assert_false(exists(path));
        aa_image_free(&im);
    }
    assert_int_equal(entries(((fixture *)*state)->dir), 0);
}

static void test_txt_locale(void **state)
{
    /* A host program may set a locale whose decimal point is a comma; the
     * files must not change.  scripts/install-deps.sh generates de_DE.UTF-8;
     * without it this fails rather than pass untried. */
    if (!setlocale(LC_ALL, "de_DE.UTF-8"))
        fail_msg("locale de_DE.UTF-8 is missing: scripts/install-deps.sh generates it");
    char probe[16];
    snprintf(probe, sizeof probe, "%g", 0.5);
    if (strcmp(probe, "0,5") != 0) {
        setlocale(LC_ALL, "C");
        fail_msg("de_DE.UTF-8 prints 0.5 as \"%s\", not with a decimal comma", probe);
    }
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, 1, 1, 2), AA_OK);
    im.v[0] = 0.5;
    im.v[1] = 0.1;
    const char *path = in_dir(state, "locale.txt");
    int status = aa_image_write_txt(path, &im);
    size_t len;
    char text[256];
    snprintf(text, sizeof text, "%s", slurp(path, &len));
    int read = aa_image_read_txt(path, &back);
    aa_encode e;
    int parsed = aa_encode_parse("gamma:2.5", &e);
    setlocale(LC_ALL, "C");
    assert_int_equal(status, AA_OK);
    assert_string_equal(text, "# aabench 1 1 2\n0 0 0.5 0.10000000000000001\n");
    assert_int_equal(read, AA_OK);
    assert_same_bits(&im, &back);
    assert_int_equal(parsed, AA_OK);
    assert_true(e.gamma == 2.5);
    aa_image_free(&im);
    aa_image_free(&back);
}

/* ------------------------------------------------------------------------
 * Float files: .exr .tif .tiff .pfm
 * ------------------------------------------------------------------------ */

static void float_round_trip(void **state, const char *name, int c)
{
    const char *path = in_dir(state, name);
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, 7, 3, c), AA_OK);

    /* Values a float holds exactly come back exactly (binary32 has a 24-bit
     * significand and exponents down to 2^-149, IEEE 754-2008 3.6):
     * multiples of 1/8, 2^-149, 2^100, -0.0. */
    fill_distinct(&im, -0.125);
    im.v[0] = 0x1p-149;
    im.v[1] = 0x1p100;
    im.v[2] = -0.0;
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_same_bits(&im, &back);
    aa_image_free(&back);

    /* Any value comes back as its nearest float (C11 6.3.1.5: the
     * conversion rounds to nearest), so compare with (double)(float)v. */
    for (size_t k = 0; k < 7 * 3 * (size_t)c; k++)
        im.v[k] = (k % 2 ? 1.0 : -1.0) * (double)(k + 1) / 3 + 1e-9 * (double)k;
    im.v[0] = 0.1;
    im.v[1] = 1e-300; /* below the smallest float: 0 */
    im.v[2] = 1 - 0x1p-53;
    im.v[3] = 1e300; /* above the largest float: infinity */
    im.v[4] = -1e300;
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_int_equal(back.c, c);
    for (size_t k = 0; k < 7 * 3 * (size_t)c; k++) {
        double want = (double)(float)im.v[k];
        if (back.v[k] != want)
            print_error("%s value %zu: %.17g read as %.17g, want %.17g\n", name, k, im.v[k],
                        back.v[k], want);
        assert_true(back.v[k] == want);
    }
    aa_image_free(&back);
    aa_image_free(&im);
}

static void test_float_round_trips(void **state)
{
    const char *names[] = {"a.exr", "a.tif", "a.TIFF", "a.EXR"};
    for (size_t k = 0; k < 4; k++)
        for (int c = 1; c <= 4; c++)
            float_round_trip(state, names[k], c);
    float_round_trip(state, "a.pfm", 1);
    float_round_trip(state, "a.pfm", 3);
    assert_int_equal(entries(((fixture *)*state)->dir), 5); /* a.exr a.tif a.TIFF a.EXR a.pfm */
}

/* A smooth float image (a product of slow sines, each value a float, so
 * every bit of it must come back) written as .exr: read back bit for bit,
 * and compressed: the file is smaller than its pixels alone uncompressed
 * (w * h * c * 4 bytes of binary32), let alone with the header. */
static void test_exr_compressed(void **state)
{
    const char *path = in_dir(state, "smooth.exr");
    enum { W = 128, H = 96, C = 3 };
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, W, H, C), AA_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < C; c++) {
                volatile float f = (float)(0.5 + 0.4 * sin(x / 17.0 + c) * cos(y / 23.0));
                im.v[((size_t)y * W + x) * C + c] = f;
            }
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_same_bits(&im, &back);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    const long long raw = (long long)W * H * C * 4;
    if (st.st_size >= raw / 2)
        print_error("smooth.exr: %lld bytes, the pixels uncompressed %lld\n",
                    (long long)st.st_size, raw);
    assert_true(st.st_size < raw / 2);
    aa_image_free(&back);
    aa_image_free(&im);
    assert_int_equal(unlink(path), 0);
}

/* A sampled image holds few distinct values: rings of three greys, as
 * point sampling gives, 12 bytes a pixel uncompressed, are written in
 * under 0.4 bytes a pixel (zlib's level 6 finds the repeats; OpenEXR's
 * default level 4 takes 0.56), and read back bit for bit. */
static void test_exr_sampled_compressed(void **state)
{
    const char *path = in_dir(state, "rings.exr");
    enum { W = 256, H = 256, C = 3 };
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, W, H, C), AA_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double r = hypot(x + 0.5 - 101.3, y + 0.5 - 87.9);
            volatile float f = (float)(((int)(r / 5.3) % 3) / 2.0 * 0.8 + 0.1);
            for (int c = 0; c < C; c++)
                im.v[((size_t)y * W + x) * C + c] = f;
        }
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_same_bits(&im, &back);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    if ((double)st.st_size >= 0.4 * W * H)
        print_error("rings.exr: %lld bytes, %.3f a pixel\n", (long long)st.st_size,
                    (double)st.st_size / (W * H));
    assert_true((double)st.st_size < 0.4 * W * H);
    aa_image_free(&back);
    aa_image_free(&im);
    assert_int_equal(unlink(path), 0);
}

/* 2 x 2 x 1 as a PFM holds it, by hand from the format's definition (Paul
 * Debevec, "PFM Portable Float Map", pauldebevec.com/Research/HDR/PFM):
 * "Pf" for one channel, width and height, a negative scale for
 * little-endian, then rows from the bottom of the image up.  The pixels are
 * (0,0) = 1, (1,0) = 2, (0,1) = 3, (1,1) = 4, as IEEE binary32: 1.0 =
 * 0x3f800000, 2.0 = 0x40000000, 3.0 = 0x40400000, 4.0 = 0x40800000. */
static const char pfm_known[] = "Pf\n2 2\n-1.0\n"
                                "\x00\x00\x40\x40" "\x00\x00\x80\x40"  /* bottom row: 3 4 */
                                "\x00\x00\x80\x3f" "\x00\x00\x00\x40"; /* top row: 1 2 */

/* A 2 x 2 grey PFM of the given bytes, written and read: its values as
 * want (four of them). */
static void pfm_read_as(void **state, const char *name, const char *bytes, size_t len,
                        const double *want)
{
    const char *path = in_dir(state, name);
    aa_image im;
    support_write_file(path, bytes, len);
    assert_int_equal(aa_image_read(path, &im), AA_OK);
    assert_shape(&im, 2, 2, 1);
    assert_memory_equal(im.v, want, 4 * sizeof *want);
    aa_image_free(&im);
}

static void test_pfm_known(void **state)
{
    const char *path = in_dir(state, "known.pfm");
    support_write_file(path, pfm_known, sizeof pfm_known - 1);
    aa_image im;
    assert_int_equal(aa_image_read(path, &im), AA_OK);
    assert_shape(&im, 2, 2, 1);
    const double want[] = {1, 2, 3, 4};
    assert_memory_equal(im.v, want, sizeof want);

    /* Written back, the bytes are the same. */
    path = in_dir(state, "again.pfm");
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    size_t len;
    const char *text = slurp(path, &len);
    assert_int_equal(len, sizeof pfm_known - 1);
    assert_memory_equal(text, pfm_known, len);
    aa_image_free(&im);

    /* Three channels, 1 x 2: "PF", the bottom pixel (4, 5, 6) first, then
     * the top one (1, 2, 3); 5.0 = 0x40a00000, 6.0 = 0x40c00000. */
    static const char rgb[] = "PF\n1 2\n-1.0\n"
                              "\x00\x00\x80\x40" "\x00\x00\xa0\x40" "\x00\x00\xc0\x40"
                              "\x00\x00\x80\x3f" "\x00\x00\x00\x40" "\x00\x00\x40\x40";
    path = in_dir(state, "rgb.pfm");
    support_write_file(path, rgb, sizeof rgb - 1);
    assert_int_equal(aa_image_read(path, &im), AA_OK);
    assert_shape(&im, 1, 2, 3);
    const double want_rgb[] = {1, 2, 3, 4, 5, 6};
    assert_memory_equal(im.v, want_rgb, sizeof want_rgb);
    aa_image_free(&im);

    /* The scale's size multiplies the samples, as OpenImageIO 2.4's PFM
     * reader (pnminput.cpp) does: scales 0.5 and 4 of the values 3 4 / 1 2
     * above, little- and big-endian. */
    static const char half[] = "Pf\n2 2\n-0.5\n"
                               "\x00\x00\x40\x40" "\x00\x00\x80\x40"
                               "\x00\x00\x80\x3f" "\x00\x00\x00\x40";
    static const char four[] = "Pf\n2 2\n4\n"
                               "\x40\x40\x00\x00" "\x40\x80\x00\x00"
                               "\x3f\x80\x00\x00" "\x40\x00\x00\x00";
    const double want_half[] = {0.5, 1, 1.5, 2}, want_four[] = {4, 8, 12, 16};
    pfm_read_as(state, "half.pfm", half, sizeof half - 1, want_half);
    pfm_read_as(state, "four.pfm", four, sizeof four - 1, want_four);
}

/* A PFM's scale gives the byte order by its sign: 0, NaN or infinity is
 * none, and the samples are exactly W x H x C floats after the header (the
 * format's definition, as above).  Files breaking either are refused
 * (damaged: AA_EIO, naming the file) by reading and by the header's sizes;
 * a big-endian file (positive scale) of the right size is still read. */
static void test_pfm_damaged(void **state)
{
    static const char samples[] = "\x00\x00\x40\x40" "\x00\x00\x80\x40"
                                  "\x00\x00\x80\x3f" "\x00\x00\x00\x40";
    const struct {
        const char *name, *header, *tail, *says;
    } bad[] = {{"nan.pfm", "Pf\n2 2\nnan\n", "", "scale nan"},
               {"negnan.pfm", "Pf\n2 2\n-nan\n", "", "scale -nan"},
               {"zero.pfm", "Pf\n2 2\n0.0\n", "", "scale 0.0"},
               {"negzero.pfm", "Pf\n2 2\n-0\n", "", "scale -0"},
               {"inf.pfm", "Pf\n2 2\n-inf\n", "", "scale -inf"},
               {"word.pfm", "Pf\n2 2\n-1x\n", "", "scale -1x"},
               {"trailing.pfm", "Pf\n2 2\n-1.0\n", "x", "bytes after the samples"},
               {"twice.pfm", "Pf\n2 2\n-1.0\n", "\x00\x00\x40\x40", "bytes after"},
               {"short.pfm", "PF\n2 2\n-1.0\n", "", "cut short"}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char buf[128];
        size_t hl = strlen(bad[k].header), tl = strlen(bad[k].tail);
        if (!strcmp(bad[k].name, "twice.pfm"))
            tl = 4;
        memcpy(buf, bad[k].header, hl);
        memcpy(buf + hl, samples, 16);
        memcpy(buf + hl + 16, bad[k].tail, tl);
        const char *path = in_dir(state, bad[k].name);
        support_write_file(path, buf, hl + 16 + tl);
        aa_image im = {0};
        assert_refused(aa_image_read(path, &im), AA_EIO, bad[k].name, 0);
        assert_non_null(strstr(aa_last_error(), bad[k].says));
        assert_null(im.v);
        int w, h, c;
        assert_refused(aa_image_file_size(path, &w, &h, &c), AA_EIO, bad[k].name, 0);
        assert_non_null(strstr(aa_last_error(), bad[k].says));
    }
    /* Big-endian, the same values: 3 4 / 1 2 bottom up. */
    static const char be[] = "Pf\n2 2\n1.0\n"
                             "\x40\x40\x00\x00" "\x40\x80\x00\x00"
                             "\x3f\x80\x00\x00" "\x40\x00\x00\x00";
    const char *path = in_dir(state, "be.pfm");
    support_write_file(path, be, sizeof be - 1);
    aa_image im;
    assert_int_equal(aa_image_read(path, &im), AA_OK);
    const double want[] = {1, 2, 3, 4};
    assert_memory_equal(im.v, want, sizeof want);
    aa_image_free(&im);
}

/* ------------------------------------------------------------------------
 * 8-bit files: .png
 * ------------------------------------------------------------------------ */

/* IEC 61966-2-1, written out again here so the test does not lean on the
 * code it checks. */
static double srgb_from_linear(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static void test_png_srgb(void **state)
{
    for (int c = 1; c <= 3; c += 2) {
        const char *path = in_dir(state, c == 1 ? "grey.png" : "rgb.png");
        aa_image im, back;
        assert_int_equal(aa_image_alloc(&im, 101, 3, c), AA_OK);
        size_t n = (size_t)101 * 3 * c;
        for (size_t k = 0; k < n; k++)
            im.v[k] = (double)k / (double)(n - 1); /* 0 to 1, both ends */
        im.v[1] = -0.5; /* clamped to 0 */
        im.v[2] = 2.0;  /* clamped to 1 */
        im.v[3] = 0.5;
        assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
        assert_int_equal(aa_image_read(path, &back), AA_OK);
        assert_shape(&back, 101, 3, c);
        for (size_t k = 0; k < n; k++) {
            /* Round to the nearest of 256 codes: the code read back, put
             * through the encoding again, is within half a code of the
             * value's own encoding. */
            double v = fmin(fmax(im.v[k], 0), 1);
            double codes = fabs(srgb_from_linear(back.v[k]) - srgb_from_linear(v)) * 255;
            if (codes > 0.5 + 1e-9)
                print_error("value %zu: %.17g read as %.17g (%g codes apart)\n", k, v,
                            back.v[k], codes);
            assert_true(codes <= 0.5 + 1e-9);
        }
        assert_true(back.v[0] == 0);
        assert_true(back.v[1] == 0);
        assert_true(back.v[2] == 1);
        assert_true(back.v[n - 1] == 1);
        /* 0.5 encodes to 0.7353570 (bc -l: 1.055*e(l(0.5)/2.4)-0.055), code
         * 187.516 -> 188, which decodes to ((188/255 + 0.055)/1.055)^2.4 =
         * 0.50288645803256838517 (bc -l). */
        assert_true(fabs(back.v[3] - 0.50288645803256838517) < 1e-15);
        aa_image_free(&im);
        aa_image_free(&back);
    }
}

static void test_png_other_encodings(void **state)
{
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, 2, 1, 1), AA_OK);
    im.v[0] = 0.3;
    im.v[1] = 0.123;
    const char *path = in_dir(state, "enc.png");

    /* gamma 2: sqrt(0.3) * 255 = 139.669 -> code 140, read back as
     * (140/255)^2 = 0.30142252979623221838 (bc -l); the file says gamma 2,
     * so reading undoes that and not sRGB. */
    aa_encode e;
    assert_int_equal(aa_encode_parse("gamma:2", &e), AA_OK);
    assert_int_equal(aa_image_write(path, &im, &e), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_true(fabs(back.v[0] - 0.30142252979623221838) < 1e-15);
    aa_image_free(&back);

    /* linear: 0.123 * 255 = 31.365 -> code 31, read back as 31/255. */
    assert_int_equal(aa_encode_parse("linear", &e), AA_OK);
    assert_int_equal(aa_image_write(path, &im, &e), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_true(fabs(back.v[1] - 31.0 / 255) < 1e-16);
    aa_image_free(&back);

    /* The PNG specification (11.3.3.2): gAMA stores 100000 / G rounded to
     * an integer, so G is known to that.  gamma:2.2 is stored as 45455, and
     * read back as 2.2, the value in hundredths that rounds to it:
     * 0.3^(1/2.2) * 255 = 147.526 -> code 148, read back as (148/255)^2.2 =
     * 0.30212549635885279428 (python3 decimal, 40 digits). */
    assert_int_equal(aa_encode_parse("gamma:2.2", &e), AA_OK);
    assert_int_equal(aa_image_write(path, &im, &e), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_true(fabs(back.v[0] - 0.30212549635885279428) < 1e-15);
    aa_image_free(&back);
    /* gamma:2.345 is stored as 42644, and no value in hundredths rounds to
     * that: read back with the G the file states, 100000/42644.  0.3^(1/2.345)
     * * 255 = 152.603 -> code 153, read back as (153/255)^(100000/42644) =
     * 0.30183223429575855041 ((153/255)^2.345 would be 0.3018315835; python3
     * decimal, 40 digits). */
    assert_int_equal(aa_encode_parse("gamma:2.345", &e), AA_OK);
    assert_int_equal(aa_image_write(path, &im, &e), AA_OK);
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_true(fabs(back.v[0] - 0.30183223429575855041) < 1e-15);
    aa_image_free(&back);

    /* A damaged chunk is refused, an ancillary one too: with its gAMA
     * dropped (libpng's default for an ancillary chunk whose CRC fails) the
     * file would be decoded as sRGB. */
    size_t len;
    char *bytes = slurp(path, &len);
    char *gama = NULL;
    for (size_t k = 0; k + 8 < len && gama == NULL; k++)
        if (memcmp(bytes + k, "gAMA", 4) == 0)
            gama = bytes + k + 4;
    assert_non_null(gama);
    gama[3] ^= 1; /* a bit of 100000 / G: the CRC no longer matches */
    support_write_file(path, bytes, len);
    back = (aa_image){1, 1, 1, (double *)&back};
    assert_refused(aa_image_read(path, &back), AA_EIO, "enc.png", 0);
    assert_null(back.v);

    /* An encoding that did not come from the parser is refused. */
    aa_encode bad = {AA_ENCODE_GAMMA, 0.5};
    assert_refused(aa_image_write(in_dir(state, "bad.png"), &im, &bad), AA_EINVAL, "bad.png", 0);
    assert_false(exists(in_dir(state, "bad.png")));
    aa_image_free(&im);
}

/* ------------------------------------------------------------------------
 * Refusals
 * ------------------------------------------------------------------------ */

static void test_channels_refused(void **state)
{
    const struct {
        const char *name;
        int c;
    } bad[] = {{"x.png", 2}, {"x.png", 4}, {"x.pfm", 2}, {"x.pfm", 4},
               {"x.exr", 5}, {"x.tif", 6}, {"x.txt", 5}};
    /* An existing file under the name stays as it was. */
    char keep[PATH_MAX + 64];
    snprintf(keep, sizeof keep, "%s", in_dir(state, "x.png"));
    support_write_file(keep, "keep", 4);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const char *path = in_dir(state, bad[k].name);
        aa_image im;
        assert_int_equal(aa_image_alloc(&im, 2, 2, bad[k].c), AA_OK);
        assert_refused(aa_image_write(path, &im, NULL), AA_EINVAL, "channels", 0);
        aa_image_free(&im);
    }
    size_t len;
    assert_string_equal(slurp(keep, &len), "keep");
    assert_int_equal(entries(((fixture *)*state)->dir), 1);
}

static void test_unknown_extension(void **state)
{
    const char *names[] = {"x.jpg", "x", "x.png.bak", ".png"};
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 2, 2, 3), AA_OK);
    for (size_t k = 0; k < 4; k++) {
        const char *path = in_dir(state, names[k]);
        assert_refused(aa_image_write(path, &im, NULL), AA_EINVAL, ".exr .tif .tiff", 0);
        aa_image back;
        assert_refused(aa_image_read(path, &back), AA_EINVAL, path, 0);
        assert_non_null(strstr(aa_last_error(), ".png"));
        assert_non_null(strstr(aa_last_error(), ".txt"));
        assert_null(back.v);
    }
    assert_int_equal(entries(((fixture *)*state)->dir), 0);
    aa_image_free(&im);
}

static void test_missing_folder(void **state)
{
    const char *names[] = {"no/such/x.txt", "no/x.exr", "no/x.png", "no/x.pfm", "no/x.tif"};
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 3, 2, 3), AA_OK);
    for (size_t k = 0; k < 5; k++) {
        char path[PATH_MAX + 64];
        snprintf(path, sizeof path, "%s", in_dir(state, names[k]));
        assert_refused(aa_image_write(path, &im, NULL), AA_EIO, path, 0);
    }
    assert_refused(aa_file_write_atomic(in_dir(state, "no/x.json"), "{}", 2), AA_EIO, "x.json",
                   0);
    /* Nothing at all was made: no file, no folder. */
    assert_int_equal(entries(((fixture *)*state)->dir), 0);
    aa_image_free(&im);
}

static void test_rename_fails(void **state)
{
    /* The temporary file is complete when the rename fails (a folder holds
     * the name): it must still be removed. */
    const char *names[] = {"d.txt", "d.exr", "d.png", "d.json"};
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 3, 2, 3), AA_OK);
    for (size_t k = 0; k < 4; k++) {
        char path[PATH_MAX + 64];
        snprintf(path, sizeof path, "%s", in_dir(state, names[k]));
        assert_int_equal(mkdir(path, 0777), 0);
        int status = k < 3 ? aa_image_write(path, &im, NULL) : aa_file_write_atomic(path, "x", 1);
        assert_refused(status, AA_EIO, path, 0);
    }
    assert_int_equal(entries(((fixture *)*state)->dir), 4); /* the folders only */
    aa_image_free(&im);
}

static void test_bad_binary_files(void **state)
{
    /* A real .exr with incompressible content, cut in half: the header
     * reads, the pixels do not. */
    const char *path = in_dir(state, "cut.exr");
    aa_image im, back;
    assert_int_equal(aa_image_alloc(&im, 64, 64, 3), AA_OK);
    uint32_t x = 12345;
    for (size_t k = 0; k < 64 * 64 * 3; k++) {
        x = x * 1664525u + 1013904223u; /* Numerical Recipes LCG */
        im.v[k] = (double)x / 4294967296.0;
    }
    assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(truncate(path, st.st_size / 2), 0);
    back = (aa_image){1, 1, 1, (double *)&back};
    assert_refused(aa_image_read(path, &back), AA_EIO, "cut.exr", 0);
    assert_null(back.v);
    /* Cut to its first 100 bytes, inside the header. */
    assert_int_equal(truncate(path, 100), 0);
    assert_refused(aa_image_read(path, &back), AA_EIO, "cut.exr", 0);
    assert_null(back.v);
    aa_image_free(&im);

    const struct {
        const char *name, *text;
    } junk[] = {{"empty.png", ""}, {"junk.tif", "not a tiff at all"},
                {"junk.pfm", "PF\n-3 2\n-1.0\n"}, {"huge.pfm", "Pf\n100000 1\n-1.0\n"},
                {"junk.exr", "v/1\x01\x02"}};
    for (size_t k = 0; k < sizeof junk / sizeof junk[0]; k++) {
        const char *p = in_dir(state, junk[k].name);
        support_write_file(p, junk[k].text, strlen(junk[k].text));
        assert_refused(aa_image_read(p, &back), AA_EIO, junk[k].name, 0);
        assert_null(back.v);
    }
    assert_refused(aa_image_read(in_dir(state, "absent.exr"), &back), AA_EIO, "absent.exr", 0);
    assert_refused(aa_image_read(in_dir(state, "absent.txt"), &back), AA_EIO, "absent.txt", 0);
}

/* ------------------------------------------------------------------------
 * files.c
 * ------------------------------------------------------------------------ */

static void test_temp_name(void **state)
{
    (void)state;
    char a[256], b[256], pid[32];
    snprintf(pid, sizeof pid, ".aa-%ld-", (long)getpid());
    assert_int_equal(aa_temp_name("out/x.y/img.exr", a, sizeof a), AA_OK);
    assert_int_equal(aa_temp_name("out/x.y/img.exr", b, sizeof b), AA_OK);
    assert_string_not_equal(a, b);
    /* Same folder, a leading dot, the process id, a counter, the extension;
     * short whatever the name (a name near NAME_MAX still has one). */
    assert_int_equal(strncmp(a, "out/x.y/", 8), 0);
    assert_int_equal(strncmp(a + 8, pid, strlen(pid)), 0);
    assert_string_equal(a + strlen(a) - 4, ".exr");
    assert_null(strchr(a + 8, '/'));
    assert_true(strlen(a + 8) < 40);

    assert_int_equal(aa_temp_name("plain", a, sizeof a), AA_OK);
    assert_int_equal(strncmp(a, pid, strlen(pid)), 0);
    assert_null(strchr(a, '/'));
    assert_null(strchr(a + strlen(pid), '.')); /* no extension */
    assert_int_equal(aa_temp_name("/r.TXT", a, sizeof a), AA_OK);
    assert_int_equal(strncmp(a + 1, pid, strlen(pid)), 0);
    assert_int_equal(a[0], '/');
    assert_string_equal(a + strlen(a) - 4, ".TXT");
    /* an absurdly long extension is dropped rather than kept */
    assert_int_equal(aa_temp_name("d/x.aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", a, sizeof a), AA_OK);
    assert_null(strchr(a + 2 + strlen(pid), '.'));

    assert_int_equal(aa_temp_name("dir/", a, sizeof a), AA_EINVAL);
    assert_int_equal(aa_temp_name("", a, sizeof a), AA_EINVAL);
    assert_int_equal(aa_temp_name("dir/x.exr", a, 8), AA_EINVAL);
}

static void test_mkdirs(void **state)
{
    char path[PATH_MAX + 64];
    snprintf(path, sizeof path, "%s", in_dir(state, "a/b//c/"));
    assert_int_equal(aa_mkdirs(path), AA_OK);
    assert_int_equal(aa_mkdirs(path), AA_OK); /* again: already there */
    struct stat st;
    assert_int_equal(stat(in_dir(state, "a/b/c"), &st), 0);
    assert_true(S_ISDIR(st.st_mode));
    assert_int_equal(aa_mkdirs(in_dir(state, "a")), AA_OK);
    assert_int_equal(aa_mkdirs("/"), AA_OK);
    assert_int_equal(aa_mkdirs("."), AA_OK);

    /* A file in the way. */
    support_write_file(in_dir(state, "a/f"), "x", 1);
    snprintf(path, sizeof path, "%s", in_dir(state, "a/f/g"));
    assert_refused(aa_mkdirs(path), AA_EIO, "a/f", 0);
    assert_false(exists(path));
    assert_int_equal(aa_mkdirs(""), AA_EINVAL);
}

static void test_write_atomic(void **state)
{
    const char *path = in_dir(state, "data.bin");
    const char data[] = "line one\n\0binary";
    assert_int_equal(aa_file_write_atomic(path, data, sizeof data), AA_OK);
    size_t len;
    const char *back = slurp(path, &len);
    assert_int_equal(len, sizeof data);
    assert_memory_equal(back, data, sizeof data);
    /* Replacing, and an empty file. */
    assert_int_equal(aa_file_write_atomic(path, "", 0), AA_OK);
    slurp(path, &len);
    assert_int_equal(len, 0);
    assert_int_equal(entries(((fixture *)*state)->dir), 1);
}

static void test_now(void **state)
{
    (void)state;
    /* Monotonic: never goes back, whatever the wall clock does. */
    double t0 = aa_now();
    double t1 = aa_now();
    assert_true(t0 > 0);
    assert_true(t1 >= t0);
}

/* ------------------------------------------------------------------------
 * The OpenImageIO module (aabench-oiio.so), loaded on first use
 * ------------------------------------------------------------------------ */

/* 1 if the module is mapped into this process, 0 if not, -1 if unknown. */
static int module_loaded(void)
{
    FILE *f = fopen("/proc/self/maps", "r");
    if (f == NULL)
        return -1;
    char line[PATH_MAX + 256];
    int found = 0;
    while (!found && fgets(line, sizeof line, f) != NULL)
        found = strstr(line, "/aabench-oiio.so") != NULL;
    fclose(f);
    return found;
}

/* Run `body` in a child process, which starts with no module loaded (these
 * tests run first, and run every load in a child) and whose loading stays
 * there.  The child reports through its exit status: a cmocka assertion
 * there would go on to run the parent's remaining tests in the child. */
static void child(void **state, int (*body)(void *state))
{
    int loaded = module_loaded();
    if (loaded != 0)
        fail_msg("aabench-oiio.so is %s: this test must run before any that reads or "
                 "writes an OpenImageIO format", loaded < 0 ? "maybe loaded" : "loaded");
    support_in_child(body, state);
}

/* .txt reads and writes, .png reads and writes (libpng), .pfm reads and
 * writes (PFM is read and written by image.c) and looking at extensions
 * load no module; writing .exr (through OpenImageIO) loads it. */
static int txt_loads_nothing(void *state)
{
    char txt[PATH_MAX + 64], pfm[PATH_MAX + 64], png[PATH_MAX + 64];
    snprintf(txt, sizeof txt, "%s", in_dir(state, "a.txt"));
    snprintf(pfm, sizeof pfm, "%s", in_dir(state, "a.pfm"));
    snprintf(png, sizeof png, "%s", in_dir(state, "a.png"));
    aa_image im, back;
    SUPPORT_CHILD_CHECK(aa_image_alloc(&im, 3, 2, 3) == AA_OK);
    fill_distinct(&im, 0.125);
    SUPPORT_CHILD_CHECK(aa_image_write(txt, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_write_txt(txt, &im) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_read(txt, &back) == AA_OK);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(aa_image_read_txt(txt, &back) == AA_OK);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(aa_image_write(pfm, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_write(png, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_read(png, &back) == AA_OK);
    aa_image_free(&back);
    int w, h, c;
    SUPPORT_CHILD_CHECK(aa_image_file_size(png, &w, &h, &c) == AA_OK && w == 3 && h == 2 &&
                        c == 3);
    SUPPORT_CHILD_CHECK(aa_image_ext_known("x.exr") && aa_image_ext_known("x.png"));
    SUPPORT_CHILD_CHECK(aa_image_read(pfm, &back) == AA_OK);
    SUPPORT_CHILD_CHECK(back.w == 3 && back.h == 2 && back.c == 3);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(aa_image_file_size(pfm, &w, &h, &c) == AA_OK && w == 3 && h == 2 &&
                        c == 3);
    SUPPORT_CHILD_CHECK(module_loaded() == 0);
    char exr[PATH_MAX + 64];
    snprintf(exr, sizeof exr, "%s", in_dir(state, "a.exr"));
    SUPPORT_CHILD_CHECK(aa_image_write(exr, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(module_loaded() == 1);
    aa_image_free(&im);
    return 0;
}

static void test_module_on_demand(void **state)
{
    child(state, txt_loads_nothing);
}

/* A module that cannot be loaded: the formats that need it are refused with
 * AA_EIO, a message naming the image file, the module looked for and the
 * loader's reason, and no file; the others (.png through libpng and .pfm
 * among them) work as before.  A file named .pfm that is no PFM (here a
 * PNG) is left to OpenImageIO, and so refused. */
static int module_missing(void *state)
{
    static const char bogus[] = "/nonexistent/aabench-oiio.so";
    char exr[PATH_MAX + 64], png[PATH_MAX + 64], txt[PATH_MAX + 64], pfm[PATH_MAX + 64];
    snprintf(exr, sizeof exr, "%s", in_dir(state, "a.exr"));
    snprintf(png, sizeof png, "%s", in_dir(state, "a.png"));
    snprintf(txt, sizeof txt, "%s", in_dir(state, "a.txt"));
    snprintf(pfm, sizeof pfm, "%s", in_dir(state, "a.pfm"));
    SUPPORT_CHILD_CHECK(setenv("AABENCH_OIIO", bogus, 1) == 0);
    aa_image im, back;
    SUPPORT_CHILD_CHECK(aa_image_alloc(&im, 2, 2, 3) == AA_OK);
    fill_distinct(&im, 0.001);
    const char *msg = aa_last_error();
    for (int k = 0; k < 2; k++) { /* the second time from what the first found */
        SUPPORT_CHILD_CHECK(aa_image_write(exr, &im, NULL) == AA_EIO);
        SUPPORT_CHILD_CHECK(strstr(msg, exr) == msg && strstr(msg, bogus) &&
                            strstr(msg, "AABENCH_OIIO"));
        SUPPORT_CHILD_CHECK(strstr(msg, "No such file") != NULL); /* dlerror() */
        SUPPORT_CHILD_CHECK(!exists(exr));
    }
    SUPPORT_CHILD_CHECK(aa_image_write(png, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_read(png, &back) == AA_OK);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(aa_image_write(pfm, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_read(pfm, &back) == AA_OK);
    SUPPORT_CHILD_CHECK(back.w == 2 && back.h == 2 && back.c == 3);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(rename(png, pfm) == 0);
    SUPPORT_CHILD_CHECK(aa_image_read(pfm, &back) == AA_EIO);
    SUPPORT_CHILD_CHECK(strstr(msg, pfm) == msg && strstr(msg, bogus));
    SUPPORT_CHILD_CHECK(back.v == NULL);
    SUPPORT_CHILD_CHECK(aa_image_write(txt, &im, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_read(txt, &back) == AA_OK);
    aa_image_free(&back);
    SUPPORT_CHILD_CHECK(module_loaded() == 0);
    aa_image_free(&im);
    return 0;
}

static void test_module_missing(void **state)
{
    child(state, module_missing);
}

#define TEST(f) cmocka_unit_test_setup_teardown(f, setup, teardown)

SUPPORT_MAIN(NULL, NULL,
             /* first: they need a process that has not loaded the module yet */
             TEST(test_module_on_demand),
             TEST(test_module_missing),
             TEST(test_alloc),
             TEST(test_encode_parse_accepts),
             TEST(test_encode_parse_refuses),
             TEST(test_encode_value),
             TEST(test_ext_known),
             TEST(test_txt_exact_text),
             TEST(test_txt_round_trip),
             TEST(test_txt_read_known),
             TEST(test_txt_corrupt),
             TEST(test_txt_long_line),
             TEST(test_txt_refuses_non_finite),
             TEST(test_txt_locale),
             TEST(test_float_round_trips),
             TEST(test_exr_compressed),
             TEST(test_exr_sampled_compressed),
             TEST(test_pfm_known),
             TEST(test_pfm_damaged),
             TEST(test_png_srgb),
             TEST(test_png_other_encodings),
             TEST(test_channels_refused),
             TEST(test_unknown_extension),
             TEST(test_missing_folder),
             TEST(test_rename_fails),
             TEST(test_bad_binary_files),
             TEST(test_temp_name),
             TEST(test_mkdirs),
             TEST(test_write_atomic),
             TEST(test_now))
