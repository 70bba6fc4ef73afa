/*
 * image.c: images in memory and in files.
 *
 * Inside, an image is linear light in doubles (harness/README.md,
 * "Principles").  Files are chosen by extension (harness/README.md, "Command
 * line"):
 *
 *   .exr .tif .tiff .pfm  32-bit float, linear, the image's own channels;
 *   .png                  8 bits, display encoded (sRGB unless told), for eyes;
 *   .txt                  text, every value with %.17g, so nothing is lost.
 *
 * The binary formats go through OpenImageIO (oiio.cpp), except for writing
 * .pfm: OpenImageIO 2.4 (Debian 12) reads PFM but its PNM writer only makes
 * 8- and 16-bit PPM/PGM, so we write that simple format here.  The .txt
 * format is ours; its reader and writer are in image_txt.c.  OpenImageIO is
 * a module of its own, loaded the first time a file needs it (the end of
 * this file, and oiio.h), so neither .txt nor writing .pfm loads it.
 *
 * Every write goes to a temporary name beside the result and is renamed
 * into place (files.c), so a failure leaves no output behind.
 *
 * Text numbers are always C-locale text ('.' as decimal point), whatever
 * locale the program around the library has set: a .txt file or an encoding
 * spec must mean the same thing on every machine.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "core.h"
#include "oiio.h"
#include "image_internal.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <unistd.h>

/* Room for a temporary file name (PATH_MAX on Linux). */
#define TEMP_NAME_MAX 4096

/* ------------------------------------------------------------------------
 * Images in memory
 * ------------------------------------------------------------------------ */

/* w * h * c doubles, if that many bytes can be addressed. */
static int image_count(int w, int h, int c, size_t *n)
{
    size_t pixels = (size_t)w * (size_t)h; /* both <= INT_MAX: no overflow */
    if ((size_t)c > SIZE_MAX / sizeof(double) / pixels)
        return 0;
    *n = pixels * (size_t)c;
    return 1;
}

int aa_image_alloc(aa_image *im, int w, int h, int c)
{
    if (im == NULL)
        return aa_fail(AA_EINVAL, "aa_image_alloc: no image");
    *im = (aa_image){0};
    if (w <= 0 || h <= 0 || c <= 0)
        return aa_fail(AA_EINVAL, "image %d x %d x %d: sizes must be positive", w, h, c);
    size_t n;
    if (!image_count(w, h, c, &n))
        return aa_fail(AA_EINVAL, "image %d x %d x %d: too large to address on this machine", w,
                       h, c);
    /* Zeroed, so methods that accumulate can start from the image. */
    double *v = calloc(n, sizeof *v);
    if (v == NULL)
        return aa_fail(AA_ENOMEM, "image %d x %d x %d: out of memory (%zu bytes)", w, h, c,
                       n * sizeof *v);
    *im = (aa_image){.w = w, .h = h, .c = c, .v = v};
    return AA_OK;
}

void aa_image_free(aa_image *im)
{
    if (im == NULL)
        return;
    free(im->v);
    *im = (aa_image){0};
}

/* Number of values in an image that passed check_image. */
static size_t image_values(const aa_image *im)
{
    return (size_t)im->w * (size_t)im->h * (size_t)im->c;
}

/* ------------------------------------------------------------------------
 * Numbers as text
 * ------------------------------------------------------------------------ */

/* Skip digits; how many there were. */
static size_t skip_digits(const char **p, const char *end)
{
    const char *start = *p;
    while (*p < end && aa__is_digit(**p))
        (*p)++;
    return (size_t)(*p - start);
}

/* Plain decimal syntax, [+-]d[.d][(e|E)[+-]d] with at least one digit in
 * the mantissa.  strtod would also take hex floats, "inf", "nan" and
 * leading blanks, none of which %.17g of a finite value writes. */
static int decimal_syntax(const char *s, size_t len)
{
    const char *p = s, *end = s + len;
    if (p < end && (*p == '+' || *p == '-'))
        p++;
    size_t digits = skip_digits(&p, end);
    if (p < end && *p == '.') {
        p++;
        digits += skip_digits(&p, end);
    }
    if (digits == 0)
        return 0;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < end && (*p == '+' || *p == '-'))
            p++;
        if (skip_digits(&p, end) == 0)
            return 0;
    }
    return p == end;
}

aa__number_result aa__parse_number(const char *s, size_t len, double *v)
{
    if (!decimal_syntax(s, len))
        return AA__NUMBER_MALFORMED;
    char *end;
    /* ERANGE is no reason to refuse: an underflow is still the correctly
     * rounded value (5e-324 is one), and an overflow is caught as not
     * finite just below. */
    *v = strtod(s, &end);
    if (end != s + len)
        return AA__NUMBER_MALFORMED;
    return isfinite(*v) ? AA__NUMBER_OK : AA__NUMBER_NOT_FINITE;
}

/* ------------------------------------------------------------------------
 * Display encoding
 * ------------------------------------------------------------------------ */

static const char encode_accepted[] =
    "accepted: srgb, linear, gamma:G with G a number in [1, 4]";

int aa_encode_parse(const char *text, aa_encode *out)
{
    static const char prefix[] = "gamma:";
    if (text == NULL)
        return aa_fail(AA_EINVAL, "no encoding given (%s)", encode_accepted);
    if (strcmp(text, "srgb") == 0) {
        *out = (aa_encode){AA_ENCODE_SRGB, 0};
        return AA_OK;
    }
    if (strcmp(text, "linear") == 0) {
        *out = (aa_encode){AA_ENCODE_LINEAR, 1};
        return AA_OK;
    }
    if (strncmp(text, prefix, sizeof prefix - 1) != 0)
        return aa_fail(AA_EINVAL, "unknown encoding '%s' (%s)", aa_echo(text), encode_accepted);
    const char *g = text + sizeof prefix - 1;
    aa__c_numbers numbers;
    int status = aa__c_numbers_enter(&numbers, "encoding");
    if (status != AA_OK)
        return status;
    double gamma;
    aa__number_result r = aa__parse_number(g, strlen(g), &gamma);
    aa__c_numbers_end(&numbers);
    if (r != AA__NUMBER_OK || !(gamma >= 1 && gamma <= 4))
        return aa_fail(AA_EINVAL, "encoding '%s': gamma '%s' is not a number in [1, 4] (%s)",
                       aa_echo(text), aa_echo(g), encode_accepted);
    *out = (aa_encode){AA_ENCODE_GAMMA, gamma};
    return AA_OK;
}

/* IEC 61966-2-1 (sRGB), the encoding transfer function. */
static double srgb_encode(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

/* Its inverse, as the standard gives it. */
static double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

double aa_encode_value(const aa_encode *e, double linear)
{
    /* fmax before fmin: a NaN becomes 0, never a NaN byte. */
    double v = fmin(fmax(linear, 0.0), 1.0);
    switch (e->kind) {
    case AA_ENCODE_LINEAR: return v;
    case AA_ENCODE_GAMMA: return pow(v, 1 / e->gamma);
    case AA_ENCODE_SRGB:
    default: return srgb_encode(v);
    }
}

static int encode_valid(const aa_encode *e)
{
    switch (e->kind) {
    case AA_ENCODE_SRGB:
    case AA_ENCODE_LINEAR: return 1;
    case AA_ENCODE_GAMMA: return e->gamma >= 1 && e->gamma <= 4;
    default: return 0;
    }
}

/* The tag oiio.h uses for an encoding: 0 sRGB, else the power law's gamma. */
static double encode_gamma(const aa_encode *e)
{
    switch (e->kind) {
    case AA_ENCODE_LINEAR: return 1;
    case AA_ENCODE_GAMMA: return e->gamma;
    default: return 0;
    }
}

/* Linear light from a display-encoded value, for a file tagged `gamma`. */
static double decode_value(double gamma, double e)
{
    return gamma == 0 ? srgb_decode(e) : pow(e, gamma);
}

/* ------------------------------------------------------------------------
 * File formats
 * ------------------------------------------------------------------------ */

typedef enum format_kind { FORMAT_TXT, FORMAT_FLOAT, FORMAT_PFM, FORMAT_8BIT } format_kind;

typedef struct image_format {
    const char *ext;      /* lower case, with its dot */
    const char *oiio;     /* OpenImageIO's writer; NULL if we write it */
    format_kind kind;
    unsigned channels;    /* bit c set: c channels can be stored */
    const char *channels_why;
} image_format;

#define ONE_TO_FOUR 0x1eu  /* 1, 2, 3, 4 */
#define GREY_OR_RGB 0x0au  /* 1, 3 */

static const image_format formats[] = {
    {".exr", "exr", FORMAT_FLOAT, ONE_TO_FOUR, "1 to 4"},
    {".tif", "tif", FORMAT_FLOAT, ONE_TO_FOUR, "1 to 4"},
    {".tiff", "tiff", FORMAT_FLOAT, ONE_TO_FOUR, "1 to 4"},
    {".pfm", NULL, FORMAT_PFM, GREY_OR_RGB, "1 or 3 (all PFM can hold)"},
    /* PNG could hold 2 or 4, but every reader takes the last as alpha. */
    {".png", "png", FORMAT_8BIT, GREY_OR_RGB, "1 or 3 (2 or 4 would be read as alpha)"},
    {".txt", NULL, FORMAT_TXT, ONE_TO_FOUR, "1 to 4"}, /* last: txt_format */
};

#define FORMAT_COUNT (sizeof formats / sizeof formats[0])
static const image_format *const txt_format = &formats[FORMAT_COUNT - 1];

/* ASCII only: a locale must not change which files we accept. */
static int same_ignoring_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = *a >= 'A' && *a <= 'Z' ? (char)(*a - 'A' + 'a') : *a;
        if (x != *b)
            return 0;
    }
    return *a == *b;
}

/* The format named by the end of `path`; the extension must follow a file
 * name, so "dir/.png" (a hidden file) has none. */
static const image_format *format_of(const char *path)
{
    size_t n = strlen(path);
    for (size_t k = 0; k < FORMAT_COUNT; k++) {
        size_t e = strlen(formats[k].ext);
        if (n > e && path[n - e - 1] != '/' && same_ignoring_case(path + n - e, formats[k].ext))
            return &formats[k];
    }
    return NULL;
}

int aa_image_ext_known(const char *path)
{
    return path != NULL && format_of(path) != NULL;
}

static int unknown_format(const char *path)
{
    char list[64] = "";
    for (size_t k = 0; k < FORMAT_COUNT; k++) {
        strcat(list, " ");
        strcat(list, formats[k].ext);
    }
    return aa_fail(AA_EINVAL, "%s: unknown image file extension (accepted:%s)", path, list);
}

/* ------------------------------------------------------------------------
 * Writing
 * ------------------------------------------------------------------------ */

/* An image the format can hold, and whose file can be read back. */
static int check_image(const char *path, const aa_image *im, const image_format *f)
{
    if (im == NULL || im->v == NULL || im->w <= 0 || im->h <= 0 || im->c <= 0)
        return aa_fail(AA_EINVAL, "%s: no image to write", path);
    if (im->w > AA_MAX_SIDE || im->h > AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "%s: image %d x %d: a side is above %d", path, im->w, im->h,
                       AA_MAX_SIDE);
    if (im->c > AA__IMAGE_MAX_CHANNELS || !(f->channels & (1u << im->c)))
        return aa_fail(AA_EINVAL, "%s: %d channels: %s takes %s", path, im->c, f->ext,
                       f->channels_why);
    return AA_OK;
}

/* What one write puts in its file. */
typedef struct write_job {
    const image_format *format;
    const aa_image *im;
    const unsigned char *bytes; /* display-encoded samples, for 8-bit files */
    double gamma;               /* their encoding (oiio.h) */
    const aa__oiio_api *oiio;   /* for the formats OpenImageIO writes */
} write_job;

int aa__image_stdio_write(const char *tmp, const aa_image *im,
                          int (*body)(FILE *f, const aa_image *im))
{
    /* "x": never write through a name someone else has just made. */
    FILE *f = fopen(tmp, "wbx");
    if (f == NULL)
        return aa_fail(AA_EIO, "cannot create %s: %s", tmp, strerror(errno));
    int failed = body(f, im) != 0;
    int err = errno;
    /* fclose flushes the last buffer, where a full disk shows. */
    if (fclose(f) != 0 && !failed) {
        failed = 1;
        err = errno;
    }
    return failed ? aa_fail(AA_EIO, "cannot write %s: %s", tmp, strerror(err)) : AA_OK;
}

/* PFM (Debevec's portable float map): "PF" (3 channels) or "Pf" (1), the
 * size, and a scale whose sign gives the byte order, negative for
 * little-endian; then 32-bit floats, rows from the bottom of the image up.
 * We always write little-endian, byte by byte, whatever this machine is. */
static int pfm_samples(FILE *f, const aa_image *im)
{
    for (int j = im->h - 1; j >= 0; j--) {
        const double *v = aa_pixel(im, 0, j);
        for (size_t k = 0; k < (size_t)im->w * (size_t)im->c; k++) {
            float x = (float)v[k]; /* round to nearest (C11 6.3.1.5) */
            uint32_t bits;
            memcpy(&bits, &x, sizeof bits);
            for (int b = 0; b < 32; b += 8)
                if (putc_unlocked((int)((bits >> b) & 0xffu), f) == EOF)
                    return -1;
        }
    }
    return 0;
}

static int pfm_body(FILE *f, const aa_image *im)
{
    if (fprintf(f, "%s\n%d %d\n-1.0\n", im->c == 3 ? "PF" : "Pf", im->w, im->h) < 0)
        return -1;
    /* One lock for the whole file, so putc_unlocked is allowed. */
    flockfile(f);
    int failed = pfm_samples(f, im);
    funlockfile(f);
    return failed;
}

static int write_file(const char *tmp, const write_job *job)
{
    const aa_image *im = job->im;
    switch (job->format->kind) {
    case FORMAT_TXT: return aa__txt_write_file(tmp, im);
    case FORMAT_PFM: return aa__image_stdio_write(tmp, im, pfm_body);
    case FORMAT_FLOAT:
        return job->oiio->write_float(tmp, job->format->oiio, im->w, im->h, im->c, im->v);
    case FORMAT_8BIT:
        return job->oiio->write_8bit(tmp, job->format->oiio, im->w, im->h, im->c, job->bytes,
                                     job->gamma);
    }
    return aa_fail(AA_EFAIL, "%s: unknown format kind", tmp);
}

/* Write under a temporary name and rename into place; on any failure the
 * temporary file is removed, so nothing is left behind. */
static int write_via_temp(const char *path, const write_job *job)
{
    char tmp[TEMP_NAME_MAX];
    int status = aa_temp_name(path, tmp, sizeof tmp);
    if (status != AA_OK)
        return status;
    status = write_file(tmp, job);
    if (status == AA_OK && rename(tmp, path) != 0)
        status = aa_fail(AA_EIO, "cannot rename %s into place: %s", tmp, strerror(errno));
    if (status != AA_OK) {
        remove(tmp); /* may not exist, if creating it failed */
        return aa_fail_context(status, "%s", path);
    }
    return AA_OK;
}

int aa_image_write_txt(const char *path, const aa_image *im)
{
    if (path == NULL)
        return aa_fail(AA_EINVAL, "aa_image_write_txt: no path");
    int status = check_image(path, im, txt_format);
    if (status == AA_OK)
        status = aa__txt_check_finite(path, im);
    if (status != AA_OK)
        return status;
    write_job job = {.format = txt_format, .im = im};
    return write_via_temp(path, &job);
}

/* Display-encode and round to the nearest 8-bit code (halves up). */
static int encode_bytes(const char *path, const aa_image *im, const aa_encode *e,
                        unsigned char **out)
{
    size_t n = image_values(im);
    unsigned char *q = malloc(n);
    if (q == NULL)
        return aa_fail(AA_ENOMEM, "%s: out of memory (%zu bytes)", path, n);
    for (size_t k = 0; k < n; k++)
        q[k] = (unsigned char)floor(aa_encode_value(e, im->v[k]) * 255 + 0.5);
    *out = q;
    return AA_OK;
}

int aa_image_write(const char *path, const aa_image *im, const aa_encode *enc)
{
    static const aa_encode srgb = {AA_ENCODE_SRGB, 0};
    if (path == NULL)
        return aa_fail(AA_EINVAL, "aa_image_write: no path");
    const image_format *f = format_of(path);
    if (f == NULL)
        return unknown_format(path);
    if (f->kind == FORMAT_TXT)
        return aa_image_write_txt(path, im);
    int status = check_image(path, im, f);
    if (status != AA_OK)
        return status;
    write_job job = {.format = f, .im = im};
    unsigned char *bytes = NULL;
    if (f->kind == FORMAT_8BIT) {
        if (enc == NULL)
            enc = &srgb;
        if (!encode_valid(enc))
            return aa_fail(AA_EINVAL, "%s: invalid display encoding", path);
        status = encode_bytes(path, im, enc, &bytes);
        if (status != AA_OK)
            return status;
        job.bytes = bytes;
        job.gamma = encode_gamma(enc);
    }
    /* Loaded before the temporary file is made, so a failure names `path`. */
    if (f->oiio != NULL && (job.oiio = aa__oiio(path)) == NULL)
        status = AA_EIO;
    else
        status = write_via_temp(path, &job);
    free(bytes);
    return status;
}

/* ------------------------------------------------------------------------
 * Reading through OpenImageIO
 * ------------------------------------------------------------------------ */

/* 8-bit samples arrive as code / 255; snap back to the code and decode
 * through a table, which is exact and costs one pow per code, not per
 * sample. */
static void decode_8bit(aa_image *im, double gamma)
{
    double table[256];
    for (int q = 0; q < 256; q++)
        table[q] = decode_value(gamma, q / 255.0);
    size_t n = image_values(im);
    for (size_t k = 0; k < n; k++) {
        long q = lround(im->v[k] * 255);
        im->v[k] = table[q < 0 ? 0 : q > 255 ? 255 : q];
    }
}

static void decode_integers(aa_image *im, const aa__oiio_info *info)
{
    if (info->bits == 8) {
        decode_8bit(im, info->gamma);
        return;
    }
    size_t n = image_values(im);
    for (size_t k = 0; k < n; k++)
        im->v[k] = decode_value(info->gamma, im->v[k]);
}

/* Sizes from a file header, checked before anything is allocated. */
static int check_file_size(const char *path, const aa__oiio_info *info)
{
    if (info->w < 1 || info->w > AA_MAX_SIDE || info->h < 1 || info->h > AA_MAX_SIDE)
        return aa_fail(AA_EIO, "%s: image %d x %d: sides must be in [1, %d]", path, info->w,
                       info->h, AA_MAX_SIDE);
    if (info->c < 1 || info->c > AA__IMAGE_MAX_CHANNELS)
        return aa_fail(AA_EIO, "%s: %d channels: must be in [1, %d]", path, info->c,
                       AA__IMAGE_MAX_CHANNELS);
    if (aa_size_check(info->w, info->h, info->c, 1) != AA_OK)
        return aa_fail_context(AA_EIO, "%s", path);
    return AA_OK;
}

static int read_oiio(const char *path, aa_image *im)
{
    const aa__oiio_api *oiio = aa__oiio(path);
    if (oiio == NULL)
        return AA_EIO;
    aa__oiio_in *in;
    aa__oiio_info info;
    int status = oiio->open(path, &in, &info);
    if (status != AA_OK)
        return status;
    status = check_file_size(path, &info);
    if (status == AA_OK)
        status = aa_image_alloc(im, info.w, info.h, info.c);
    if (status == AA_OK)
        status = oiio->read(in, im->v);
    oiio->close(in);
    if (status != AA_OK) {
        aa_image_free(im);
        return status;
    }
    /* Float files hold linear light; integer files hold display codes. */
    if (!info.is_float)
        decode_integers(im, &info);
    return AA_OK;
}

int aa_image_read(const char *path, aa_image *im)
{
    if (path == NULL || im == NULL)
        return aa_fail(AA_EINVAL, "aa_image_read: no path or no image");
    *im = (aa_image){0};
    const image_format *f = format_of(path);
    if (f == NULL)
        return unknown_format(path);
    if (f->kind == FORMAT_TXT)
        return aa_image_read_txt(path, im);
    return read_oiio(path, im);
}

/* ------------------------------------------------------------------------
 * OpenImageIO, loaded on first use
 * ------------------------------------------------------------------------ */

/* Where `make install` puts the module: $(PREFIX)/lib/aabench, given by the
 * Makefile. */
#ifndef AA_OIIO_DIR
#define AA_OIIO_DIR "/usr/local/lib/aabench"
#endif

static pthread_once_t oiio_once = PTHREAD_ONCE_INIT;
static const aa__oiio_api *oiio_api;
/* Why oiio_api is NULL, for every caller's message. */
static char oiio_why[768];

/* Say why in oiio_why (cut to fit). */
static void oiio_say(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static void oiio_say(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(oiio_why, sizeof oiio_why, fmt, ap);
    va_end(ap);
}

#ifdef AA_OIIO_STATIC

/* Linked in (oiio.h): nothing to load. */
static void oiio_load(void)
{
    oiio_api = aa__oiio_entry(AA__OIIO_VERSION, aa_fail);
    if (oiio_api == NULL)
        oiio_say("the OpenImageIO code linked in is from another version of aabench");
}

#else

/* Load the module at `path` into oiio_api, or say why not in oiio_why. */
static void oiio_open(const char *path)
{
    void *module = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (module == NULL) {
        const char *err = dlerror();
        oiio_say("%s", err ? err : "dlopen failed");
        return;
    }
    void *sym = dlsym(module, AA__OIIO_ENTRY);
    if (sym == NULL) {
        const char *err = dlerror();
        oiio_say("%s", err ? err : "no " AA__OIIO_ENTRY);
        dlclose(module);
        return;
    }
    /* POSIX lets a dlsym result be a function; memcpy says so in ISO C. */
    const aa__oiio_api *(*entry)(int, aa__oiio_fail_fn);
    memcpy(&entry, &sym, sizeof entry);
    oiio_api = entry(AA__OIIO_VERSION, aa_fail);
    if (oiio_api == NULL) {
        oiio_say("it was built for another version of aabench");
        dlclose(module);
    }
    /* Otherwise kept for the life of the process: OpenImageIO keeps threads
     * and caches that must not be unloaded under it. */
}

/* Put "cannot load the OpenImageIO module NAME: " before oiio_why; `how`
 * says where the name came from. */
static void oiio_cannot_load(const char *name, const char *how)
{
    char why[sizeof oiio_why];
    memcpy(why, oiio_why, sizeof why);
    oiio_say("cannot load the OpenImageIO module %s%s: %s", name, how, why);
}

/* dir/aabench-oiio.so into buf (PATH_MAX); 0 if it does not fit. */
static int module_in(char *buf, const char *dir)
{
    int n = snprintf(buf, PATH_MAX, "%s/%s", dir, AA__OIIO_MODULE);
    return n > 0 && n < PATH_MAX;
}

/* The module is $AABENCH_OIIO when that is set (and only then, so a wrong
 * setting is reported, not passed over).  Otherwise it is looked for beside
 * the running program, in the folder above it (the test programs are in
 * build/tests/) and in AA_OIIO_DIR; the first that exists is the one loaded,
 * or whose failure is reported. */
static void oiio_load(void)
{
    const char *explicit_path = getenv("AABENCH_OIIO");
    if (explicit_path != NULL && *explicit_path != '\0') {
        oiio_open(explicit_path);
        if (oiio_api == NULL)
            oiio_cannot_load(explicit_path, " (AABENCH_OIIO)");
        return;
    }
    char exe[PATH_MAX], cand[3][PATH_MAX];
    int n = 0;
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        for (int up = 0; up < 2; up++) {
            char *slash = strrchr(exe, '/');
            if (slash == NULL)
                break;
            *slash = '\0';
            if (module_in(cand[n], *exe ? exe : "/"))
                n++;
        }
    }
    if (module_in(cand[n], AA_OIIO_DIR))
        n++;
    for (int k = 0; k < n; k++) {
        oiio_open(cand[k]);
        if (oiio_api != NULL)
            return;
        if (access(cand[k], F_OK) == 0) { /* there, but it does not load */
            oiio_cannot_load(cand[k], "");
            return;
        }
    }
    /* Found nowhere: each place, and the loader's word on the last. */
    char why[sizeof oiio_why];
    memcpy(why, oiio_why, sizeof why);
    oiio_say("the OpenImageIO module %s was not found: looked for %s%s%s%s%s "
             "(AABENCH_OIIO may give its path); %s", AA__OIIO_MODULE, n > 0 ? cand[0] : "",
             n > 1 ? ", " : "", n > 1 ? cand[1] : "", n > 2 ? ", " : "", n > 2 ? cand[2] : "",
             why);
}

#endif

const aa__oiio_api *aa__oiio(const char *path)
{
    pthread_once(&oiio_once, oiio_load);
    if (oiio_api == NULL)
        aa_fail(AA_EIO, "%s: %s", path, oiio_why);
    return oiio_api;
}

int aa__oiio_text(double *pixels, int w, int h, int c, int x, int y, const char *text, int size,
                  const float *colour)
{
    const aa__oiio_api *oiio = aa__oiio("montage labels");
    if (oiio == NULL)
        return AA_EIO;
    return oiio->text(pixels, w, h, c, x, y, text, size, colour);
}
