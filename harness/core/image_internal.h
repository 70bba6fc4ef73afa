/*
 * image_internal.h: what image.c shares with image_txt.c, the reader and
 * writer of the .txt format.
 */
#ifndef AA_IMAGE_INTERNAL_H
#define AA_IMAGE_INTERNAL_H

#include "core.h"

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

#endif
