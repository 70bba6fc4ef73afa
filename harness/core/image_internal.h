/*
 * image_internal.h: what image.c shares with image_txt.c, the reader and
 * writer of the .txt format, and with image_png.c, that of .png files.
 */
#ifndef AA_IMAGE_INTERNAL_H
#define AA_IMAGE_INTERNAL_H

#include "core.h"
#include "oiio.h"

#include <locale.h>
#include <stddef.h>
#include <stdio.h>

/* RGB plus one: what every format here can hold, and more than any image the
 * harness makes (RGB results, 1-channel bounds). */
#define AA__IMAGE_MAX_CHANNELS 4

/* Numbers in files and specs are C-locale text (c_numbers_internal.h). */
#include "c_numbers_internal.h"

/* The .txt format (image_txt.c): the header line, then rows y0 .. y0 +
 * rows - 1 of a W-wide image of C channels (v holds just those rows).
 * Both return -1 with errno set on a write error. */
int aa__txt_header(FILE *f, int w, int h, int c);
int aa__txt_rows(FILE *f, const double *v, int w, int y0, int rows, int c);
/* The sizes a .txt file's header gives, checked as the reader does. */
int aa__txt_info(const char *path, int *w, int *h, int *c);
/* The format holds finite values only: refuse the others before they are
 * written, naming the pixel. */
int aa__txt_check_finite(const char *path, const aa_image *im);
int aa__txt_check_finite_rows(const char *path, const double *v, int w, int y0, int rows, int c);

/* .png through libpng (image_png.c), as oiio.h's entries do for the other
 * formats, with the same contracts: out_open creates `path` (O_EXCL) for a
 * W x H x C image of 8-bit codes tagged with the encoding `gamma` (0 sRGB,
 * else the power law's G); rows in order; close finishes and checks every
 * write and the close, abort gives up; every one frees the writer but
 * rows.  open describes a file in `info` (w, h, c, bits 8 or 16, gamma)
 * without reading its pixels; read reads them as stored / max; close
 * frees.  Every failure is recorded with aa_fail naming the file. */
typedef struct aa__png_out aa__png_out;
int aa__png_out_open(const char *path, int w, int h, int c, double gamma, aa__png_out **out);
int aa__png_out_rows(aa__png_out *out, int y0, int y1, const unsigned char *bytes);
int aa__png_out_close(aa__png_out *out);
void aa__png_out_abort(aa__png_out *out);
typedef struct aa__png_in aa__png_in;
/* 1 if the first 8 bytes of a file are the PNG signature. */
int aa__png_signature(const unsigned char head[8]);
int aa__png_open(const char *path, aa__png_in **in, aa__oiio_info *info);
int aa__png_read(aa__png_in *in, double *pixels);
void aa__png_close(aa__png_in *in);

#endif
