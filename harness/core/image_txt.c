/*
 * image_txt.c: the .txt image format, aabench's own: a header line
 * "# aabench W H C", then one line "i j v0 .. v(C-1)" per pixel, row by row,
 * i fastest, every value written with %.17g so nothing is lost.
 *
 * The format is ours, so its reader is written to be strict and safe on
 * hostile input: nothing is allocated before the header's sizes are checked,
 * and every refusal names the file and the line.  Numbers are C-locale text
 * ('.' as decimal point) whatever locale the program has set.
 *
 * image.c chooses the format by extension, checks the image and writes
 * through a temporary name; this file holds the text itself.  Nothing here
 * needs OpenImageIO.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "core.h"
#include "image_internal.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Longest .txt line accepted: a pixel line is at most about 120 characters
 * ("65535 65535" and four %.17g values), so this leaves room for any
 * reasonable spacing while bounding what a hostile file can make us hold. */
#define TXT_LINE_MAX 1024

/* ------------------------------------------------------------------------
 * Writing .txt
 * ------------------------------------------------------------------------ */

int aa__txt_header(FILE *f, int w, int h, int c)
{
    return fprintf(f, "# aabench %d %d %d\n", w, h, c) < 0 ? -1 : 0;
}

static int txt_lines(FILE *f, const double *v, int w, int y0, int rows, int c)
{
    for (int j = 0; j < rows; j++) {
        for (int i = 0; i < w; i++) {
            const double *p = v + ((size_t)j * (size_t)w + (size_t)i) * (size_t)c;
            if (fprintf(f, "%d %d", i, y0 + j) < 0)
                return -1;
            /* 17 significant digits identify every double (IEEE 754-2008,
             * 5.12.2), so strtod gives back the same bits. */
            for (int k = 0; k < c; k++)
                if (fprintf(f, " %.17g", p[k]) < 0)
                    return -1;
            if (putc('\n', f) == EOF)
                return -1;
        }
    }
    return 0;
}

int aa__txt_rows(FILE *f, const double *v, int w, int y0, int rows, int c)
{
    aa__c_numbers numbers;
    if (aa__c_numbers_begin(&numbers) != 0)
        return -1;
    int failed = txt_lines(f, v, w, y0, rows, c);
    int err = errno;
    aa__c_numbers_end(&numbers);
    errno = err;
    return failed;
}

/* The reader refuses values that are not finite, so the writer refuses them
 * too, before any of them is written. */
int aa__txt_check_finite_rows(const char *path, const double *v, int w, int y0, int rows, int c)
{
    size_t n = (size_t)w * (size_t)rows * (size_t)c;
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(v[k])) {
            size_t pixel = k / (size_t)c;
            return aa_fail(AA_EINVAL, "%s: pixel (%zu, %zu) channel %zu is %g: .txt holds "
                           "finite values only", path, pixel % (size_t)w,
                           (size_t)y0 + pixel / (size_t)w, k % (size_t)c, v[k]);
        }
    }
    return AA_OK;
}

int aa__txt_check_finite(const char *path, const aa_image *im)
{
    return aa__txt_check_finite_rows(path, im->v, im->w, 0, im->h, im->c);
}

/* ------------------------------------------------------------------------
 * Reading .txt
 * ------------------------------------------------------------------------ */

typedef struct txt_reader {
    FILE *f;
    const char *path;
    unsigned long line;     /* number of the line in buf, from 1 */
    char buf[TXT_LINE_MAX]; /* that line, without its end */
} txt_reader;

/* Refuse the file at the current line. */
static int txt_refuse(const txt_reader *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static int txt_refuse(const txt_reader *r, const char *fmt, ...)
{
    char why[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    return aa_fail(AA_EIO, "%s:%lu: %s", r->path, r->line, why);
}

/* The next line into r->buf; *got is 0 at the end of the file.  A last line
 * without its newline is refused: it is what a cut-off file looks like, and
 * its last number may have lost digits. */
static int txt_next_line(txt_reader *r, int *got)
{
    size_t n = 0;
    int ch;
    r->line++;
    while ((ch = getc_unlocked(r->f)) != EOF && ch != '\n') {
        if (ch == '\0')
            return txt_refuse(r, "NUL byte: not a text file");
        if (n + 1 >= sizeof r->buf)
            return txt_refuse(r, "line longer than %d characters", TXT_LINE_MAX - 1);
        r->buf[n++] = (char)ch;
    }
    if (ferror(r->f))
        return txt_refuse(r, "read error: %s", strerror(errno));
    if (ch == EOF && n > 0)
        return txt_refuse(r, "the file ends inside this line (cut short?)");
    if (n > 0 && r->buf[n - 1] == '\r')
        n--; /* a file that went through Windows */
    r->buf[n] = '\0';
    *got = ch != EOF;
    return AA_OK;
}

typedef struct token {
    const char *s;
    size_t n;
} token;

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

/* The next blank-separated word of the line at *p; 0 if none is left. */
static int next_token(const char **p, token *t)
{
    while (is_blank(**p))
        (*p)++;
    if (**p == '\0')
        return 0;
    t->s = *p;
    while (**p != '\0' && !is_blank(**p))
        (*p)++;
    t->n = (size_t)(*p - t->s);
    return 1;
}

/* A count or index: decimal digits only, at most 9 so it fits an int. */
static int parse_count(const token *t, int *v)
{
    if (t->n == 0 || t->n > 9)
        return 0;
    int x = 0;
    for (size_t k = 0; k < t->n; k++) {
        if (!aa__is_digit(t->s[k]))
            return 0;
        x = 10 * x + (t->s[k] - '0');
    }
    *v = x;
    return 1;
}

/* How much of a token to show in a message ("%.*s"): a hostile file must
 * not fill the message with one long word. */
static int shown(const token *t)
{
    return t->n < 40 ? (int)t->n : 40;
}

static int txt_header(txt_reader *r, int *w, int *h, int *c)
{
    static const char expected[] = "expected the header '# aabench W H C'";
    int got;
    int status = txt_next_line(r, &got);
    if (status != AA_OK)
        return status;
    if (!got)
        return txt_refuse(r, "empty file: %s", expected);
    const char *p = r->buf;
    token t[6];
    int n = 0;
    while (n < 6 && next_token(&p, &t[n]))
        n++;
    if (n != 5 || t[0].n != 1 || t[0].s[0] != '#' || t[1].n != 7 ||
        memcmp(t[1].s, "aabench", 7) != 0)
        return txt_refuse(r, "%s", expected);
    if (!parse_count(&t[2], w) || !parse_count(&t[3], h) || !parse_count(&t[4], c))
        return txt_refuse(r, "%s with W, H, C whole numbers", expected);
    if (*w < 1 || *w > AA_MAX_SIDE || *h < 1 || *h > AA_MAX_SIDE)
        return txt_refuse(r, "image %d x %d: sides must be in [1, %d]", *w, *h, AA_MAX_SIDE);
    if (*c < 1 || *c > AA__IMAGE_MAX_CHANNELS)
        return txt_refuse(r, "%d channels: must be in [1, %d]", *c, AA__IMAGE_MAX_CHANNELS);
    return AA_OK;
}

/* "nan", "inf" or "infinity", in any case, signed or not: what printf
 * writes for values the format does not hold. */
static int non_finite_word(const token *t)
{
    static const char *const words[] = {"nan", "inf", "infinity"};
    const char *s = t->s;
    size_t n = t->n;
    if (n > 0 && (*s == '+' || *s == '-'))
        s++, n--;
    for (size_t w = 0; w < sizeof words / sizeof words[0]; w++) {
        if (strlen(words[w]) != n)
            continue;
        size_t k = 0;
        while (k < n && (s[k] | 0x20) == words[w][k])
            k++;
        if (k == n)
            return 1;
    }
    return 0;
}

/* One pixel line: "i j v0 .. v(c-1)" for pixel (i, j). */
static int txt_pixel(txt_reader *r, int i, int j, int c, double *v)
{
    int got;
    int status = txt_next_line(r, &got);
    if (status != AA_OK)
        return status;
    if (!got)
        return txt_refuse(r, "the file ends before pixel (%d, %d)", i, j);
    const char *p = r->buf;
    token ti, tj;
    int fi, fj;
    if (!next_token(&p, &ti) || !next_token(&p, &tj) || !parse_count(&ti, &fi) ||
        !parse_count(&tj, &fj))
        return txt_refuse(r, "expected pixel '%d %d' and %d values", i, j, c);
    if (fi != i || fj != j)
        return txt_refuse(r, "found pixel (%d, %d) where (%d, %d) belongs: pixels go row by "
                          "row, i fastest", fi, fj, i, j);
    for (int k = 0; k < c; k++) {
        token t;
        if (!next_token(&p, &t))
            return txt_refuse(r, "pixel (%d, %d) has %d values, expected %d", i, j, k, c);
        switch (aa__parse_number(t.s, t.n, &v[k])) {
        case AA__NUMBER_OK: break;
        case AA__NUMBER_NOT_FINITE:
            return txt_refuse(r, "pixel (%d, %d) channel %d: '%.*s' is not finite: .txt holds "
                              "finite values only", i, j, k, shown(&t), t.s);
        default:
            if (non_finite_word(&t))
                return txt_refuse(r, "pixel (%d, %d) channel %d: malformed number '%.*s': "
                                  ".txt holds finite values only", i, j, k, shown(&t), t.s);
            return txt_refuse(r, "pixel (%d, %d) channel %d: malformed number '%.*s'", i, j, k,
                              shown(&t), t.s);
        }
    }
    token extra;
    if (next_token(&p, &extra))
        return txt_refuse(r, "pixel (%d, %d) has more than %d values", i, j, c);
    return AA_OK;
}

static int txt_body(txt_reader *r, aa_image *im)
{
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++) {
            int status = txt_pixel(r, i, j, im->c, aa_pixel(im, i, j));
            if (status != AA_OK)
                return status;
        }
    int got;
    int status = txt_next_line(r, &got);
    if (status == AA_OK && got)
        status = txt_refuse(r, "a line after the last pixel");
    return status;
}

static int txt_read(txt_reader *r, aa_image *im)
{
    int w = 0, h = 0, c = 0;
    int status = txt_header(r, &w, &h, &c);
    if (status == AA_OK && aa_size_check(w, h, c, 1) != AA_OK)
        status = aa_fail_context(AA_EIO, "%s:%lu", r->path, r->line);
    if (status == AA_OK)
        status = aa_image_alloc(im, w, h, c);
    if (status == AA_OK)
        status = txt_body(r, im);
    return status;
}

int aa__txt_info(const char *path, int *w, int *h, int *c)
{
    txt_reader r = {.path = path};
    r.f = fopen(path, "r");
    if (r.f == NULL)
        return aa_fail(AA_EIO, "%s: cannot open: %s", path, strerror(errno));
    flockfile(r.f);
    int status = txt_header(&r, w, h, c);
    funlockfile(r.f);
    fclose(r.f);
    return status;
}

int aa_image_read_txt(const char *path, aa_image *im)
{
    if (path == NULL || im == NULL)
        return aa_fail(AA_EINVAL, "aa_image_read_txt: no path or no image");
    *im = (aa_image){0};
    txt_reader r = {.path = path};
    r.f = fopen(path, "r");
    if (r.f == NULL)
        return aa_fail(AA_EIO, "%s: cannot open: %s", path, strerror(errno));
    aa__c_numbers numbers;
    int status = aa__c_numbers_enter(&numbers, path);
    if (status == AA_OK) {
        /* One lock for the whole file, so getc_unlocked is allowed. */
        flockfile(r.f);
        status = txt_read(&r, im);
        funlockfile(r.f);
        aa__c_numbers_end(&numbers);
    }
    fclose(r.f);
    if (status != AA_OK)
        aa_image_free(im);
    return status;
}
