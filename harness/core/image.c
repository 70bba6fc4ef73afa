/*
 * image.c: images in memory and in files.
 *
 * Inside, an image is linear light in doubles (harness/README.md,
 * "Principles").  Files are chosen by extension (harness/cli/README.md, "Image
 * files"):
 *
 *   .exr .tif .tiff .pfm  32-bit float, linear, the image's own channels;
 *   .png                  8 bits, display encoded (sRGB unless told), for eyes;
 *   .txt                  text, every value with %.17g, so nothing is lost.
 *
 * .png goes through libpng (image_png.c): the pictures a run writes and the
 * renderers' output the external method reads need none of OpenImageIO's
 * some 250 libraries.  The float formats go through OpenImageIO (oiio.cpp),
 * except for .pfm: OpenImageIO 2.4 (Debian 12) reads PFM but its PNM writer
 * only makes 8- and 16-bit PPM/PGM, so we write that simple format here,
 * and read it here too, which spares every command that compares .pfm
 * files the loading of OpenImageIO.  The .txt format is ours; its reader
 * and writer are in image_txt.c.  OpenImageIO is a module of its own,
 * loaded the first time a file needs it (the end of this file, and oiio.h),
 * so neither .png, .txt nor .pfm loads it (but for a file named .png that
 * is not a PNG, or .pfm that is not a PFM, read_file below).
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
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

/* Room for a temporary file name (PATH_MAX on Linux). */
#define TEMP_NAME_MAX 4096
/* Room for the message of a writer's failure, kept for later calls. */
#define AA_IMAGE_OUT_WHY 1024

/* Number of values in an image that passed check_image. */
static size_t image_values(const aa_image *im)
{
    return (size_t)im->w * (size_t)im->h * (size_t)im->c;
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
    const char *oiio;     /* OpenImageIO's writer; NULL if not OpenImageIO's */
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
    {".png", NULL, FORMAT_8BIT, GREY_OR_RGB, "1 or 3 (2 or 4 would be read as alpha)"},
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

/* Finish a file written with stdio: a write error sets the stream's error
 * flag even when later calls succeed, and fflush then fclose write the
 * last buffer, where a full disk shows. */
static int stdio_close(FILE *f, const char *tmp)
{
    int failed = 0, err = 0;
    if (fflush(f) != 0 || ferror(f)) {
        failed = 1;
        err = errno ? errno : EIO;
    }
    if (fclose(f) != 0 && !failed) {
        failed = 1;
        err = errno;
    }
    return failed ? aa_fail(AA_EIO, "cannot write %s: %s", tmp, strerror(err)) : AA_OK;
}

/* One image being written, row by row (core.h). */
struct aa_image_out {
    const image_format *format;
    char *path;              /* the result */
    char tmp[TEMP_NAME_MAX]; /* the temporary name it is written under */
    int w, h, c, next_row;
    aa_encode enc;           /* for 8-bit files */
    FILE *f;                 /* .txt and .pfm, written here */
    off_t pfm_data;          /* where the .pfm samples start */
    const aa__oiio_api *oiio;
    aa__oiio_out *oo;        /* the formats OpenImageIO writes */
    aa__png_out *po;         /* .png, through libpng */
    unsigned char *bytes;    /* display-encoded rows, for 8-bit files */
    size_t nbytes;
    int status;              /* the first failure, kept for later calls */
    char why[AA_IMAGE_OUT_WHY];
};

/* Remove what was made and keep the failure (and its message) for every
 * later call on `out`. */
static int out_failed(aa_image_out *out, int status)
{
    if (out->f != NULL) {
        fclose(out->f);
        out->f = NULL;
    }
    if (out->oo != NULL) {
        out->oiio->out_abort(out->oo);
        out->oo = NULL;
    }
    if (out->po != NULL) {
        aa__png_out_abort(out->po);
        out->po = NULL;
    }
    remove(out->tmp); /* may not exist, if creating it failed */
    aa_fail_context(status, "%s", out->path);
    out->status = status;
    snprintf(out->why, sizeof out->why, "%s", aa_last_error());
    return status;
}

static void out_free(aa_image_out *out)
{
    free(out->bytes);
    free(out->path);
    free(out);
}

/* The .pfm header (Debevec's portable float map): "PF" (3 channels) or
 * "Pf" (1), the size, and a scale whose sign gives the byte order,
 * negative for little-endian.  The samples follow, rows from the bottom of
 * the image up. */
static int pfm_header(aa_image_out *out)
{
    if (fprintf(out->f, "%s\n%d %d\n-1.0\n", out->c == 3 ? "PF" : "Pf", out->w, out->h) < 0)
        return -1;
    out->pfm_data = ftello(out->f);
    return out->pfm_data < 0 ? -1 : 0;
}

/* Rows y0 .. y0 + rows - 1 of a .pfm: 32-bit floats, little-endian byte by
 * byte whatever this machine is.  Their place in the file is one block,
 * written from its first byte: the lowest of the rows first. */
static int pfm_rows(aa_image_out *out, const double *v, int y0, int rows)
{
    size_t row_values = (size_t)out->w * (size_t)out->c;
    off_t at = out->pfm_data + (off_t)(out->h - y0 - rows) * (off_t)(row_values * 4);
    if (fseeko(out->f, at, SEEK_SET) != 0)
        return -1;
    int failed = 0;
    /* One lock for the whole block, so putc_unlocked is allowed. */
    flockfile(out->f);
    for (int j = rows - 1; j >= 0 && !failed; j--) {
        const double *row = v + (size_t)j * row_values;
        for (size_t k = 0; k < row_values && !failed; k++) {
            float x = (float)row[k]; /* round to nearest (C11 6.3.1.5) */
            uint32_t bits;
            memcpy(&bits, &x, sizeof bits);
            for (int b = 0; b < 32 && !failed; b += 8)
                failed = putc_unlocked((int)((bits >> b) & 0xffu), out->f) == EOF;
        }
    }
    funlockfile(out->f);
    return failed ? -1 : 0;
}

/* Display-encode and round to the nearest 8-bit code (halves up). */
static void encode_bytes(const aa_encode *e, const double *v, size_t n, unsigned char *q)
{
    for (size_t k = 0; k < n; k++)
        q[k] = (unsigned char)floor(aa_encode_value(e, v[k]) * 255 + 0.5);
}

static int check_out_size(const char *path, int w, int h, int c, const image_format *f)
{
    if (w <= 0 || h <= 0 || c <= 0)
        return aa_fail(AA_EINVAL, "%s: image %d x %d x %d: sizes must be positive", path, w, h,
                       c);
    if (w > AA_MAX_SIDE || h > AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "%s: image %d x %d: a side is above %d", path, w, h,
                       AA_MAX_SIDE);
    if (c > AA__IMAGE_MAX_CHANNELS || !(f->channels & (1u << c)))
        return aa_fail(AA_EINVAL, "%s: %d channels: %s takes %s", path, c, f->ext,
                       f->channels_why);
    return AA_OK;
}

int aa_image_out_begin(const char *path, int w, int h, int c, const aa_encode *enc,
                       aa_image_out **result)
{
    static const aa_encode srgb = {AA_ENCODE_SRGB, 0};
    if (result == NULL)
        return aa_fail(AA_EINVAL, "aa_image_out_begin: nowhere to put the writer");
    *result = NULL;
    if (path == NULL)
        return aa_fail(AA_EINVAL, "aa_image_out_begin: no path");
    const image_format *f = format_of(path);
    if (f == NULL)
        return unknown_format(path);
    int status = check_out_size(path, w, h, c, f);
    if (status != AA_OK)
        return status;
    if (enc == NULL)
        enc = &srgb;
    if (f->kind == FORMAT_8BIT && !encode_valid(enc))
        return aa_fail(AA_EINVAL, "%s: invalid display encoding", path);
    aa_image_out *out = calloc(1, sizeof *out);
    if (out == NULL || (out->path = strdup(path)) == NULL) {
        free(out);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    out->format = f;
    out->w = w, out->h = h, out->c = c;
    out->enc = *enc;
    /* Loaded before the temporary file is made, so a failure names `path`. */
    if (f->oiio != NULL && (out->oiio = aa__oiio(path)) == NULL) {
        out_free(out);
        return AA_EIO;
    }
    status = aa_temp_name(path, out->tmp, sizeof out->tmp);
    if (status != AA_OK) {
        out_free(out);
        return status;
    }
    switch (f->kind) {
    case FORMAT_FLOAT:
        status = out->oiio->out_open(out->tmp, f->oiio, w, h, c, 1, 0, &out->oo);
        break;
    case FORMAT_8BIT:
        status = aa__png_out_open(out->tmp, w, h, c, encode_gamma(enc), &out->po);
        break;
    case FORMAT_TXT:
    case FORMAT_PFM:
        /* "x": never write through a name someone else has just made. */
        out->f = fopen(out->tmp, "wbx");
        if (out->f == NULL) {
            status = aa_fail(AA_EIO, "cannot create %s: %s", out->tmp, strerror(errno));
            break;
        }
        if ((f->kind == FORMAT_TXT ? aa__txt_header(out->f, w, h, c) : pfm_header(out)) != 0)
            status = aa_fail(AA_EIO, "cannot write %s: %s", out->tmp, strerror(errno));
        break;
    }
    if (status != AA_OK) {
        out_failed(out, status);
        out_free(out);
        return status;
    }
    *result = out;
    return AA_OK;
}

int aa_image_out_rows(aa_image_out *out, const double *v, int rows)
{
    if (out == NULL)
        return aa_fail(AA_EINVAL, "aa_image_out_rows: no writer");
    if (out->status != AA_OK)
        return aa_fail(out->status, "%s", out->why);
    if (v == NULL || rows < 1 || rows > out->h - out->next_row)
        return out_failed(out, aa_fail(AA_EINVAL, "%d rows given after %d of %d", rows,
                                       out->next_row, out->h));
    size_t n = (size_t)out->w * (size_t)rows * (size_t)out->c;
    int y0 = out->next_row, status = AA_OK;
    switch (out->format->kind) {
    case FORMAT_FLOAT:
        status = out->oiio->out_rows(out->oo, y0, y0 + rows, v);
        break;
    case FORMAT_8BIT:
        if (n > out->nbytes) {
            unsigned char *grown = realloc(out->bytes, n);
            if (grown == NULL) {
                status = aa_fail(AA_ENOMEM, "out of memory (%zu bytes)", n);
                break;
            }
            out->bytes = grown;
            out->nbytes = n;
        }
        encode_bytes(&out->enc, v, n, out->bytes);
        status = aa__png_out_rows(out->po, y0, y0 + rows, out->bytes);
        break;
    case FORMAT_TXT:
        status = aa__txt_check_finite_rows(out->path, v, out->w, y0, rows, out->c);
        if (status == AA_OK && aa__txt_rows(out->f, v, out->w, y0, rows, out->c) != 0)
            status = aa_fail(AA_EIO, "cannot write %s: %s", out->tmp, strerror(errno));
        break;
    case FORMAT_PFM:
        if (pfm_rows(out, v, y0, rows) != 0)
            status = aa_fail(AA_EIO, "cannot write %s: %s", out->tmp, strerror(errno));
        break;
    }
    if (status != AA_OK)
        return out_failed(out, status);
    out->next_row += rows;
    return AA_OK;
}

int aa_image_out_finish(aa_image_out *out)
{
    if (out == NULL)
        return aa_fail(AA_EINVAL, "aa_image_out_finish: no writer");
    int status = out->status;
    if (status != AA_OK) {
        status = aa_fail(status, "%s", out->why);
        out_free(out);
        return status;
    }
    if (out->next_row != out->h)
        status = aa_fail(AA_EINVAL, "finished after %d of %d rows", out->next_row, out->h);
    else if (out->oo != NULL) {
        status = out->oiio->out_close(out->oo);
        out->oo = NULL;
    } else if (out->po != NULL) {
        status = aa__png_out_close(out->po);
        out->po = NULL;
    } else {
        FILE *f = out->f;
        out->f = NULL;
        status = stdio_close(f, out->tmp);
    }
    if (status == AA_OK && rename(out->tmp, out->path) != 0)
        status = aa_fail(AA_EIO, "cannot rename %s into place: %s", out->tmp, strerror(errno));
    if (status != AA_OK)
        out_failed(out, status);
    out_free(out);
    return status;
}

void aa_image_out_abort(aa_image_out *out)
{
    if (out == NULL)
        return;
    if (out->status == AA_OK) {
        /* keep the caller's message: this is its failure, not ours */
        char saved[AA_IMAGE_OUT_WHY];
        snprintf(saved, sizeof saved, "%s", aa_last_error());
        out_failed(out, AA_EFAIL);
        aa_fail(AA_EFAIL, "%s", saved);
    }
    out_free(out);
}

/* The whole image (checked by the caller) to path through the writer
 * (aa_image_out_begin; encoded by enc, or NULL): its rows at once, then
 * finished, or aborted where they fail. */
static int write_whole(const char *path, const aa_image *im, const aa_encode *enc)
{
    aa_image_out *out;
    int status = aa_image_out_begin(path, im->w, im->h, im->c, enc, &out);
    if (status == AA_OK && (status = aa_image_out_rows(out, im->v, im->h)) != AA_OK) {
        aa_image_out_abort(out);
        return status;
    }
    return status == AA_OK ? aa_image_out_finish(out) : status;
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
    return write_whole(path, im, NULL);
}

int aa_image_write(const char *path, const aa_image *im, const aa_encode *enc)
{
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
    return write_whole(path, im, enc);
}

/* ------------------------------------------------------------------------
 * Reading through libpng and OpenImageIO
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
static int check_file_sides(const char *path, const aa__oiio_info *info)
{
    if (info->w < 1 || info->w > AA_MAX_SIDE || info->h < 1 || info->h > AA_MAX_SIDE)
        return aa_fail(AA_EIO, "%s: image %d x %d: sides must be in [1, %d]", path, info->w,
                       info->h, AA_MAX_SIDE);
    if (info->c < 1 || info->c > AA__IMAGE_MAX_CHANNELS)
        return aa_fail(AA_EIO, "%s: %d channels: must be in [1, %d]", path, info->c,
                       AA__IMAGE_MAX_CHANNELS);
    return AA_OK;
}

static int check_file_size(const char *path, const aa__oiio_info *info)
{
    int status = check_file_sides(path, info);
    if (status == AA_OK && aa_size_check(info->w, info->h, info->c, 1) != AA_OK)
        status = aa_fail_context(AA_EIO, "%s", path);
    return status;
}

/* A PNG ends with its IEND chunk.  OpenImageIO stops reading at the last
 * row, so a file cut inside that chunk (or just before it) reads whole:
 * such a file is refused all the same, as cut short.  A file that cannot be
 * read here, or does not start as a PNG, is left to its reader, which says
 * what is wrong with it. */
int aa_png_complete(const char *path)
{
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    unsigned char head[8], tail[12];
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return AA_OK;
    int png = fread(head, 1, sizeof head, f) == sizeof head && !memcmp(head, magic, sizeof magic);
    int whole = !png || (fseeko(f, -(off_t)sizeof tail, SEEK_END) == 0 &&
                         fread(tail, 1, sizeof tail, f) == sizeof tail &&
                         !memcmp(tail, iend, sizeof iend));
    int failed = ferror(f);
    fclose(f);
    if (!whole && !failed)
        return aa_fail(AA_EIO, "%s: the PNG file does not end with its IEND chunk (cut "
                       "short: was the disk full?)", path);
    return AA_OK;
}

/* What a PFM header says (pfm_head below). */
typedef struct pfm_info {
    int is_pfm;    /* the file starts as a PFM: the rest is filled in */
    aa__oiio_info info;
    off_t data;    /* where the samples start */
    int big;       /* big-endian samples (a positive scale) */
    float scale;   /* the scale's size, which multiplies every sample */
} pfm_info;

/* A PFM (Debevec's portable float map) is "PF" (3 channels) or "Pf" (1),
 * white space, the width, white space, the height, white space, the scale
 * (its sign the byte order: never 0, NaN or infinite), one white-space
 * character, then exactly width x height x channels 4-byte floats.
 * OpenImageIO takes a NaN or zero scale and ignores bytes after the
 * samples: such files are refused here as damaged.  A file that starts as
 * a PFM, whatever its name, is read here (p->is_pfm); any other is left to
 * its reader (OpenImageIO reads a file by its content), and so is one that
 * cannot be read, unless `own` (a .pfm name): then it is refused here. */
static int pfm_head(const char *path, int own, pfm_info *p)
{
    *p = (pfm_info){0};
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return own ? aa_fail(AA_EIO, "%s: cannot read: %s", path, strerror(errno)) : AA_OK;
    char head[128];
    size_t n = fread(head, 1, sizeof head - 1, f);
    head[n] = '\0';
    off_t size = fseeko(f, 0, SEEK_END) == 0 ? ftello(f) : -1;
    int err = errno;
    int failed = ferror(f) || size < 0;
    fclose(f);
    if (failed)
        return own ? aa_fail(AA_EIO, "%s: cannot read: %s", path, strerror(err)) : AA_OK;
    if (n < 3 || head[0] != 'P' || (head[1] != 'F' && head[1] != 'f') ||
        !strchr(" \t\r\n", head[2]))
        return AA_OK;
    const char *s = head + 2;
    long side[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        while (*s && strchr(" \t\r\n", *s))
            s++;
        int digits = 0;
        for (; *s >= '0' && *s <= '9' && digits < 10; s++, digits++)
            side[k] = side[k] * 10 + (*s - '0');
        if (digits == 0 || digits == 10 || side[k] < 1 || !*s || !strchr(" \t\r\n", *s))
            return aa_fail(AA_EIO,
                           "%s: cannot read: the PFM header does not give a width and a height",
                           path);
    }
    while (*s && strchr(" \t\r\n", *s))
        s++;
    size_t len = strcspn(s, " \t\r\n");
    char word[64];
    if (len == 0 || len >= sizeof word || !s[len])
        return aa_fail(AA_EIO, "%s: cannot read: the PFM header does not give a scale", path);
    memcpy(word, s, len);
    word[len] = '\0';
    char *end;
    double scale = strtod(word, &end);
    if (*end || !isfinite(scale) || scale == 0)
        return aa_fail(AA_EIO,
                       "%s: cannot read: the PFM scale %s is not a nonzero number (its "
                       "sign gives the byte order)", path, word);
    int c = head[1] == 'F' ? 3 : 1;
    double header = (double)(s + len + 1 - head);
    double want = header + 4.0 * (double)side[0] * (double)side[1] * c;
    if ((double)size != want)
        return aa_fail(AA_EIO,
                       "%s: cannot read: the PFM file holds %.0f bytes where its header "
                       "calls for %.0f (%s)", path, (double)size, want,
                       (double)size < want ? "cut short" : "bytes after the samples");
    p->info.w = (int)side[0]; /* at most 9 digits */
    p->info.h = (int)side[1];
    p->info.c = c;
    p->info.is_float = 1;
    p->info.bits = 32;
    p->data = (off_t)header;
    p->big = scale > 0;
    p->scale = (float)fabs(scale);
    p->is_pfm = 1;
    return AA_OK;
}

/* The samples of a PFM whose header pfm_head read into `p`, into `im`
 * (allocated by the caller): rows from the bottom of the image up, 4-byte
 * floats in the byte order the scale's sign gives, whatever this machine's
 * is, multiplied in float by the scale's size, as OpenImageIO's reader
 * does (files this library writes say 1). */
static int pfm_read(const char *path, const pfm_info *p, aa_image *im)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return aa_fail(AA_EIO, "%s: cannot read: %s", path, strerror(errno));
    size_t row_values = (size_t)im->w * (size_t)im->c;
    unsigned char *row = malloc(row_values * 4);
    if (row == NULL) {
        fclose(f);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    int status = AA_OK;
    if (fseeko(f, p->data, SEEK_SET) != 0)
        status = aa_fail(AA_EIO, "%s: cannot read: %s", path, strerror(errno));
    for (int y = im->h - 1; y >= 0 && status == AA_OK; y--) {
        if (fread(row, 4, row_values, f) != row_values) {
            status = aa_fail(AA_EIO, "%s: cannot read: %s", path,
                             ferror(f) ? strerror(errno) : "the file ends before its samples");
            break;
        }
        double *v = im->v + (size_t)y * row_values;
        for (size_t k = 0; k < row_values; k++) {
            const unsigned char *b = row + 4 * k;
            uint32_t bits = p->big ? (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 |
                                         (uint32_t)b[2] << 8 | b[3]
                                   : (uint32_t)b[3] << 24 | (uint32_t)b[2] << 16 |
                                         (uint32_t)b[1] << 8 | b[0];
            float x;
            memcpy(&x, &bits, sizeof x);
            x *= p->scale;
            v[k] = x;
        }
    }
    free(row);
    fclose(f);
    return status;
}

/* A file that starts as a PFM, read here: no module to load. */
static int read_pfm(const char *path, const pfm_info *p, aa_image *im)
{
    int status = check_file_size(path, &p->info);
    if (status == AA_OK)
        status = aa_image_alloc(im, p->info.w, p->info.h, p->info.c);
    if (status == AA_OK)
        status = pfm_read(path, p, im);
    if (status != AA_OK)
        aa_image_free(im);
    return status;
}

/* Whether a .png file is read by libpng: 1 unless 8 bytes of it could be
 * read and are not the PNG signature.  Such a file is something else under
 * a .png name, which OpenImageIO reads by its content as it always did; a
 * file shorter than a signature or one that cannot be opened is refused by
 * libpng's reader, which says so. */
static int png_reads(const char *path)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return 1;
    unsigned char head[8];
    ssize_t n = read(fd, head, sizeof head);
    close(fd);
    return n != (ssize_t)sizeof head || aa__png_signature(head);
}

/* A .png file through libpng (image_png.c). */
static int read_png(const char *path, aa_image *im)
{
    aa__png_in *in;
    aa__oiio_info info;
    int status = aa__png_open(path, &in, &info);
    if (status != AA_OK)
        return status;
    status = check_file_size(path, &info);
    if (status == AA_OK)
        status = aa_image_alloc(im, info.w, info.h, info.c);
    if (status == AA_OK)
        status = aa__png_read(in, im->v);
    aa__png_close(in);
    if (status != AA_OK) {
        aa_image_free(im);
        return status;
    }
    decode_integers(im, &info);
    return AA_OK;
}

static int read_file(const char *path, const image_format *f, aa_image *im)
{
    /* Before a reader reads it: libpng would refuse a PNG cut short too,
     * but not one cut inside or just before its IEND chunk. */
    int status = aa_png_complete(path);
    pfm_info pfm = {0};
    if (status == AA_OK)
        status = pfm_head(path, f->kind == FORMAT_PFM, &pfm);
    if (status != AA_OK)
        return status;
    if (f->kind == FORMAT_8BIT && png_reads(path))
        return read_png(path, im);
    if (pfm.is_pfm)
        return read_pfm(path, &pfm, im);
    const aa__oiio_api *oiio = aa__oiio(path);
    if (oiio == NULL)
        return AA_EIO;
    aa__oiio_in *in;
    aa__oiio_info info;
    status = oiio->open(path, &in, &info);
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

int aa_image_file_size(const char *path, int *w, int *h, int *c)
{
    if (path == NULL || w == NULL || h == NULL || c == NULL)
        return aa_fail(AA_EINVAL, "aa_image_file_size: no path or nowhere to put the sizes");
    const image_format *f = format_of(path);
    if (f == NULL)
        return unknown_format(path);
    if (f->kind == FORMAT_TXT)
        return aa__txt_info(path, w, h, c);
    pfm_info pfm = {0};
    int status = pfm_head(path, f->kind == FORMAT_PFM, &pfm);
    if (status != AA_OK)
        return status;
    if (pfm.is_pfm) {
        status = check_file_sides(path, &pfm.info);
        if (status == AA_OK)
            *w = pfm.info.w, *h = pfm.info.h, *c = pfm.info.c;
        return status;
    }
    aa__oiio_info info;
    if (f->kind == FORMAT_8BIT && png_reads(path)) {
        aa__png_in *png;
        status = aa__png_open(path, &png, &info);
        if (status != AA_OK)
            return status;
        aa__png_close(png);
        status = check_file_sides(path, &info);
        if (status == AA_OK)
            *w = info.w, *h = info.h, *c = info.c;
        return status;
    }
    const aa__oiio_api *oiio = aa__oiio(path);
    if (oiio == NULL)
        return AA_EIO;
    aa__oiio_in *in;
    status = oiio->open(path, &in, &info);
    if (status != AA_OK)
        return status;
    oiio->close(in);
    status = check_file_sides(path, &info);
    if (status == AA_OK)
        *w = info.w, *h = info.h, *c = info.c;
    return status;
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
    return read_file(path, f, im);
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
/* Why oiio_api is NULL, for every caller's message, and the status. */
static char oiio_why[768];
static int oiio_status = AA_EIO;

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

/* Loading the module runs the static constructors of the ~250 libraries
 * under OpenImageIO.  Under a limit on this process's memory (RLIMIT_AS, as
 * `ulimit -v` sets, or RLIMIT_DATA), some of them fail in ways that end the
 * process before any code of ours can catch anything: a C++ exception out
 * of a constructor (std::bad_alloc, std::system_error when a thread cannot
 * be started) is std::terminate, and the loader's own failures to allocate
 * thread-local storage or to load libgcc_s for unwinding are fatal errors.
 * Which one happens depends on the limit to the megabyte.
 *
 * So under such a limit the module is first loaded by a child process (a
 * copy of this one, with the same memory in use, and a margin taken away):
 * only if the child loads it is it loaded here.  Otherwise the failure is
 * reported as out of memory, naming the limit.  Without a limit (the usual
 * case) this costs nothing. */

/* Room the trial leaves unused (below). */
#define OIIO_TRIAL_MARGIN ((size_t)64 << 20)

/* The soft limit that applies, in bytes, and its name; 0 if none. */
static double memory_limit(const char **name)
{
    struct rlimit r;
    double limit = 0;
    if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
        limit = (double)r.rlim_cur;
        *name = "address space (RLIMIT_AS, ulimit -v)";
    }
    if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY &&
        (limit == 0 || (double)r.rlim_cur < limit)) {
        limit = (double)r.rlim_cur;
        *name = "data size (RLIMIT_DATA, ulimit -d)";
    }
    return limit;
}

/* 1 if the module may be loaded here: there is no limit, or a child
 * loaded it with room to spare, or no child could be asked.  0 after
 * saying in oiio_why what the child met. */
static int oiio_trial(const char *path)
{
    const char *what = NULL;
    double limit = memory_limit(&what);
    int fds[2];
    if (limit == 0 || access(path, F_OK) != 0 || pipe(fds) != 0)
        return 1;
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return 1; /* no trial: try here */
    }
    if (pid == 0) {
        /* The child: whatever the libraries print as they die is not for
         * the user; the parent says what happened.  Only the loader's
         * message comes back, through the pipe. */
        close(fds[0]);
        int null = open("/dev/null", O_WRONLY);
        if (null >= 0)
            dup2(null, STDERR_FILENO);
        /* The child has one thread where this process may have several,
         * each of which the loader gives thread-local storage: it loads
         * with OIIO_TRIAL_MARGIN bytes less room (writable, so RLIMIT_DATA
         * counts them too; never touched), so that a close call in the
         * child is a failure here too. */
        if (mmap(NULL, OIIO_TRIAL_MARGIN, PROT_READ | PROT_WRITE,
                 MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0) == MAP_FAILED)
            _exit(2);
        if (dlopen(path, RTLD_NOW | RTLD_LOCAL) != NULL)
            _exit(0);
        const char *err = dlerror();
        if (err != NULL && write(fds[1], err, strlen(err)) < 0)
            _exit(1);
        _exit(1);
    }
    close(fds[1]);
    char said[256];
    size_t n = 0;
    ssize_t k;
    while (n < sizeof said - 1 &&
           ((k = read(fds[0], said + n, sizeof said - 1 - n)) > 0 || (k < 0 && errno == EINTR)))
        n += k > 0 ? (size_t)k : 0;
    said[n] = '\0';
    close(fds[0]);
    int ws;
    pid_t got;
    while ((got = waitpid(pid, &ws, 0)) < 0 && errno == EINTR)
        ;
    if (got != pid)
        return 1; /* reaped elsewhere (SIGCHLD ignored): try here */
    if (WIFEXITED(ws) && WEXITSTATUS(ws) == 0)
        return 1;
    char how[400];
    if (WIFEXITED(ws) && WEXITSTATUS(ws) == 1)
        snprintf(how, sizeof how, "failed: %s", n ? said : "no reason given");
    else if (WIFEXITED(ws) && WEXITSTATUS(ws) == 2)
        snprintf(how, sizeof how, "found no room for a margin of %zu MB",
                 OIIO_TRIAL_MARGIN >> 20);
    else if (WIFSIGNALED(ws))
        snprintf(how, sizeof how, "was ended by signal %d (%s)", WTERMSIG(ws),
                 strsignal(WTERMSIG(ws)));
    else
        snprintf(how, sizeof how, "ended with exit status %d", WEXITSTATUS(ws));
    oiio_say("not enough memory to load it under this process's limit of %.0f MB of %s (a "
             "trial load in a child process, with %zu MB to spare, %s); raise the limit",
             limit / 1e6, what, OIIO_TRIAL_MARGIN >> 20, how);
    oiio_status = AA_ENOMEM;
    return 0;
}

/* Load the module at `path` into oiio_api, or say why not in oiio_why. */
static void oiio_open(const char *path)
{
    if (!oiio_trial(path))
        return;
    /* RTLD_LAZY: a function of the ~250 libraries is bound when first
     * called, not all at load (a quarter less CPU a load, 0.56 -> 0.42 s
     * here); the module was linked with -z defs, so every symbol it needs
     * is there, and the trial above loads with RTLD_NOW, the most the
     * loader may need. */
    void *module = dlopen(path, RTLD_LAZY | RTLD_LOCAL);
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
        aa_fail(oiio_status, "%s: %s", path, oiio_why);
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
