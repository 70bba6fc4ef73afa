/*
 * image_png.c: .png files through libpng, for image.c.
 *
 * PNG is the format of the pictures a run writes for eyes (montages, error
 * maps, zooms) and of the renderers' output the external method reads, so
 * it does not go through OpenImageIO, whose module brings some 250 shared
 * libraries (half a second a start, oiio.h): libpng alone does it.
 *
 * Written: 8 bits, grey or RGB, no alpha, not interlaced, the codes image.c
 * encoded, tagged with their display encoding the way OpenImageIO 2.4 tagged
 * the files this code replaces (so files stay equivalent):
 *
 *   sRGB        an sRGB chunk (rendering intent absolute colorimetric), with
 *               the gAMA (1/2.2) and cHRM (BT.709 primaries, D65) chunks the
 *               PNG specification (11.3.3.5) says an sRGB file should carry
 *               for readers that do not know sRGB;
 *   gamma G     a gAMA chunk of 1/G (stored = linear^(1/G));
 *   linear      a gAMA chunk of 1.
 *
 * (OpenImageIO also wrote an oFFs chunk of 0, 0 and a tEXt chunk
 * "oiio:ColorSpace", which only it reads; they say nothing the chunks above
 * do not, and are not written.)
 *
 * Every byte goes through our own descriptor with write(2), so every failing
 * write and the close are seen; the file is created with O_EXCL under the
 * temporary name image.c gives, and image.c renames or removes it.
 *
 * Read: any PNG (PNG specification, 11.2.2): palette images become RGB,
 * grey below 8 bits 8 bits, a tRNS chunk an alpha channel (the channels
 * OpenImageIO delivered too); samples as stored / max (255 or 65535), with
 * the encoding the file declares: an sRGB chunk, else a gAMA chunk, else
 * sRGB (oiio.h, aa__oiio_info.gamma).  A damaged file is refused: a bad CRC
 * in any chunk, ancillary ones included (a damaged gAMA would otherwise be
 * dropped and the file decoded as sRGB), image data that ends early, a
 * stream that does not decompress.  A file named .png that does not start
 * with the PNG signature is not ours to judge: image.c gives it to
 * OpenImageIO, which reads other formats by their content, as before.
 *
 * libpng reports errors by calling our handler, which records the message
 * with aa_fail() (naming the file) and longjmps back to the setjmp of the
 * function that called libpng; every such function frees what it holds
 * there.  Its warnings go to aa_warn(); nothing of libpng's reaches stderr
 * directly.  Its allocations go through png_alloc(), so that running out of
 * memory is AA_ENOMEM rather than an I/O error.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "core.h"
#include "image_internal.h"

#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <unistd.h>

#include <png.h>

/* What libpng's callbacks share with the function that called libpng. */
typedef struct png_ctx {
    const char *path;
    int fd;
    int err;     /* errno of the first failing write or read, else 0 */
    int nomem;   /* an allocation failed */
    int writing; /* say "cannot write" rather than "cannot read" */
} png_ctx;

/* libpng's error: record it, naming the file, then leave through the
 * setjmp of the caller (libpng requires that this not return). */
static void png_failed(png_structp png, png_const_charp msg)
{
    png_ctx *ctx = png_get_error_ptr(png);
    const char *what = ctx->writing ? "cannot write" : "cannot read";
    if (ctx->err != 0)
        aa_fail(AA_EIO, "%s: %s: %s", ctx->path, what, strerror(ctx->err));
    else if (ctx->nomem)
        aa_fail(AA_ENOMEM, "%s: out of memory in libpng", ctx->path);
    else
        aa_fail(AA_EIO, "%s: %s: %s", ctx->path, what, msg ? msg : "libpng gave no reason");
    png_longjmp(png, 1);
}

static void png_warned(png_structp png, png_const_charp msg)
{
    png_ctx *ctx = png_get_error_ptr(png);
    aa_warn("%s: libpng: %s", ctx->path, msg ? msg : "a warning without text");
}

static png_voidp png_alloc(png_structp png, png_alloc_size_t size)
{
    void *p = malloc(size);
    if (p == NULL) {
        png_ctx *ctx = png_get_mem_ptr(png);
        ctx->nomem = 1;
    }
    return p;
}

static void png_release(png_structp png, png_voidp p)
{
    (void)png;
    free(p);
}

/* The status of the failure png_failed recorded. */
static int png_status(const png_ctx *ctx)
{
    return ctx->err == 0 && ctx->nomem ? AA_ENOMEM : AA_EIO;
}

/* ------------------------------------------------------------------------
 * Writing
 * ------------------------------------------------------------------------ */

struct aa__png_out {
    png_ctx ctx;
    png_structp png;
    png_infop info;
    int w, h, c, next_row;
};

/* libpng's output: every byte through write(2), the first failure kept
 * (ENOSPC, EFBIG, EIO...) and raised as libpng's error. */
static void png_put(png_structp png, png_bytep data, size_t size)
{
    png_ctx *ctx = png_get_io_ptr(png);
    size_t done = 0;
    while (ctx->err == 0 && done < size) {
        ssize_t k = write(ctx->fd, data + done, size - done);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            ctx->err = k < 0 ? errno : EIO;
        else
            done += (size_t)k;
    }
    if (ctx->err != 0)
        png_error(png, "write failed");
}

/* Nothing is buffered on our side. */
static void png_flush_none(png_structp png)
{
    (void)png;
}

/* Free everything of `out` without checking (the descriptor closed). */
static void out_release(aa__png_out *out)
{
    if (out->png != NULL)
        png_destroy_write_struct(&out->png, &out->info);
    if (out->ctx.fd >= 0)
        close(out->ctx.fd);
    free(out);
}

/* The chunks that state the encoding (the file comment above). */
static void put_encoding(png_structp png, png_infop info, double gamma)
{
    if (gamma == 0)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    else
        png_set_gAMA(png, info, 1 / gamma);
}

int aa__png_out_open(const char *path, int w, int h, int c, double gamma, aa__png_out **result)
{
    *result = NULL;
    aa__png_out *out = calloc(1, sizeof *out);
    if (out == NULL)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    out->ctx.path = path;
    out->ctx.writing = 1;
    out->w = w, out->h = h, out->c = c;
    /* O_EXCL: never write through a name someone else has just made. */
    out->ctx.fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (out->ctx.fd < 0) {
        int err = errno;
        free(out);
        return aa_fail(AA_EIO, "%s: cannot create: %s", path, strerror(err));
    }
    out->png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, &out->ctx, png_failed,
                                         png_warned, &out->ctx, png_alloc, png_release);
    if (out->png != NULL)
        out->info = png_create_info_struct(out->png);
    if (out->png == NULL || out->info == NULL) {
        out_release(out);
        return aa_fail(AA_ENOMEM, "%s: out of memory in libpng", path);
    }
    if (setjmp(png_jmpbuf(out->png))) {
        int status = png_status(&out->ctx);
        out_release(out);
        return status;
    }
    png_set_write_fn(out->png, &out->ctx, png_put, png_flush_none);
    png_set_IHDR(out->png, out->info, (png_uint_32)w, (png_uint_32)h, 8,
                 c == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    put_encoding(out->png, out->info, gamma);
    png_write_info(out->png, out->info);
    *result = out;
    return AA_OK;
}

int aa__png_out_rows(aa__png_out *out, int y0, int y1, const unsigned char *bytes)
{
    if (y0 != out->next_row || y1 <= y0 || y1 > out->h)
        return aa_fail(AA_EFAIL, "%s: rows %d to %d written out of order", out->ctx.path, y0,
                       y1);
    if (setjmp(png_jmpbuf(out->png)))
        return png_status(&out->ctx);
    size_t row = (size_t)out->w * (size_t)out->c;
    for (int y = y0; y < y1; y++) {
        /* libpng takes a non-const row, and only reads it */
        png_bytep p = (png_bytep)(uintptr_t)(bytes + (size_t)(y - y0) * row);
        png_write_row(out->png, p);
    }
    out->next_row = y1;
    return AA_OK;
}

/* The last IDAT and the IEND chunk: a full disk may only show here. */
static int write_end(aa__png_out *out)
{
    if (setjmp(png_jmpbuf(out->png)))
        return png_status(&out->ctx);
    png_write_end(out->png, NULL);
    return AA_OK;
}

int aa__png_out_close(aa__png_out *out)
{
    int status;
    if (out->next_row != out->h)
        status = aa_fail(AA_EFAIL, "%s: closed after %d of %d rows", out->ctx.path,
                         out->next_row, out->h);
    else
        status = write_end(out);
    if (status == AA_OK) {
        /* and close(2), which can report a deferred write error (NFS) */
        int fd = out->ctx.fd;
        out->ctx.fd = -1;
        if (close(fd) != 0)
            status = aa_fail(AA_EIO, "%s: cannot write: %s", out->ctx.path, strerror(errno));
    }
    out_release(out);
    return status;
}

void aa__png_out_abort(aa__png_out *out)
{
    if (out != NULL)
        out_release(out);
}

/* ------------------------------------------------------------------------
 * Reading
 * ------------------------------------------------------------------------ */

struct aa__png_in {
    png_ctx ctx;
    FILE *f;
    png_structp png;
    png_infop info;
    int w, h, c, bits;
};

static void in_release(aa__png_in *in)
{
    if (in->png != NULL)
        png_destroy_read_struct(&in->png, &in->info, NULL);
    if (in->f != NULL)
        fclose(in->f);
    free(in);
}

/* libpng's input: fread, a short read or an error raised as libpng's error
 * (a file cut short; aa_png_complete has usually refused it before). */
static void png_get(png_structp png, png_bytep data, size_t size)
{
    aa__png_in *in = png_get_io_ptr(png);
    if (fread(data, 1, size, in->f) != size) {
        if (ferror(in->f))
            in->ctx.err = errno ? errno : EIO;
        png_error(png, "the file ends early");
    }
}

/* The display encoding the file declares (oiio.h: 0 for sRGB or none, else
 * G of stored = linear^(1/G)).  gAMA holds 100000 / G, rounded to an
 * integer (PNG specification, 11.3.3.2): G is only known to that.  A G in
 * hundredths that rounds to the same stored value is the one taken (gamma:2.2
 * is written as 45455 and read as 2.2); otherwise 100000 / stored, what the
 * file states. */
static double declared_gamma(png_structp png, png_infop info)
{
    int intent;
    if (png_get_sRGB(png, info, &intent))
        return 0;
    png_fixed_point stored;
    if (!png_get_gAMA_fixed(png, info, &stored) || stored <= 0)
        return 0;
    double g = 100000.0 / stored;
    double hundredths = round(g * 100) / 100;
    if (hundredths > 0 && lround(100000.0 / hundredths) == (long)stored)
        return hundredths;
    return g;
}

int aa__png_signature(const unsigned char head[8])
{
    return png_sig_cmp(head, 0, 8) == 0;
}

int aa__png_open(const char *path, aa__png_in **result, aa__oiio_info *info)
{
    *result = NULL;
    aa__png_in *in = calloc(1, sizeof *in);
    if (in == NULL)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    in->ctx.path = path;
    in->ctx.fd = -1;
    in->f = fopen(path, "rb");
    if (in->f == NULL) {
        int err = errno;
        free(in);
        return aa_fail(AA_EIO, "%s: cannot read: %s", path, strerror(err));
    }
    in->png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &in->ctx, png_failed, png_warned,
                                       &in->ctx, png_alloc, png_release);
    if (in->png != NULL)
        in->info = png_create_info_struct(in->png);
    if (in->png == NULL || in->info == NULL) {
        in_release(in);
        return aa_fail(AA_ENOMEM, "%s: out of memory in libpng", path);
    }
    if (setjmp(png_jmpbuf(in->png))) {
        int status = png_status(&in->ctx);
        in_release(in);
        return status;
    }
    png_set_read_fn(in->png, in, png_get);
    /* a damaged chunk, critical or not, is an error (the file comment) */
    png_set_crc_action(in->png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);
    png_read_info(in->png, in->info);
    /* palette to RGB, grey below 8 bits to 8, tRNS to alpha */
    png_set_expand(in->png);
    png_set_interlace_handling(in->png);
    png_read_update_info(in->png, in->info);
    info->w = in->w = (int)png_get_image_width(in->png, in->info);
    info->h = in->h = (int)png_get_image_height(in->png, in->info);
    info->c = in->c = png_get_channels(in->png, in->info);
    info->bits = in->bits = png_get_bit_depth(in->png, in->info);
    info->is_float = 0;
    info->gamma = declared_gamma(in->png, in->info);
    if (in->bits != 8 && in->bits != 16) {
        int bits = in->bits;
        in_release(in);
        return aa_fail(AA_EIO, "%s: cannot read: %d bits a sample after expansion", path, bits);
    }
    *result = in;
    return AA_OK;
}

int aa__png_read(aa__png_in *in, double *pixels)
{
    size_t row = (size_t)in->w * (size_t)in->c * (size_t)(in->bits / 8);
    /* allocated before the setjmp, freed on both ways out */
    unsigned char *bytes = malloc(row * (size_t)in->h);
    png_bytep *rows = malloc(sizeof *rows * (size_t)in->h);
    if (bytes == NULL || rows == NULL) {
        free(bytes);
        free(rows);
        return aa_fail(AA_ENOMEM, "%s: out of memory (%d x %d image)", in->ctx.path, in->w,
                       in->h);
    }
    if (setjmp(png_jmpbuf(in->png))) {
        free(bytes);
        free(rows);
        return png_status(&in->ctx);
    }
    for (int y = 0; y < in->h; y++)
        rows[y] = bytes + (size_t)y * row;
    png_read_image(in->png, rows);
    /* the chunks after the image, to IEND: their CRCs checked too */
    png_read_end(in->png, NULL);
    size_t n = (size_t)in->w * (size_t)in->h * (size_t)in->c;
    if (in->bits == 8) {
        for (size_t k = 0; k < n; k++)
            pixels[k] = bytes[k] / 255.0;
    } else {
        /* big-endian, as PNG stores them */
        for (size_t k = 0; k < n; k++)
            pixels[k] = (double)((unsigned)bytes[2 * k] << 8 | bytes[2 * k + 1]) / 65535.0;
    }
    free(bytes);
    free(rows);
    return AA_OK;
}

void aa__png_close(aa__png_in *in)
{
    if (in != NULL)
        in_release(in);
}
