/*
 * oiio.h: internal C interface to OpenImageIO (harness/core/oiio.cpp).
 *
 * oiio.cpp is the project's only C++.  It moves pixels between memory and
 * files and nothing else: which formats are allowed, channel limits, display
 * encoding and the temporary-name dance all live in image.c.  No C++
 * exception crosses this interface; every failure is recorded with aa_fail()
 * (naming the file) and returned as an aa_status: AA_EIO for the file,
 * AA_ENOMEM for memory, AA_EFAIL for anything else.
 *
 * Pixels are W x H x C, row-major, channels interleaved, top row first, as
 * in aa_image.  Every channel is a value: none is treated as alpha.
 */
#ifndef AA_OIIO_H
#define AA_OIIO_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* What an opened file holds. */
typedef struct aa__oiio_info {
    int w, h, c;
    int is_float; /* samples stored as floating point (else integers) */
    int bits;     /* bits per sample as delivered (8 for 8-bit files) */
    /* The display encoding the file declares for integer samples: 0 for
     * sRGB (also when it declares nothing), otherwise the gamma G of the
     * power law stored = linear^(1/G), 1 meaning linear. */
    double gamma;
} aa__oiio_info;

typedef struct aa__oiio_in aa__oiio_in;

/* Write `pixels` to `path` in the file format named `format` (an extension
 * without the dot: "exr", "tif", "pfm"), stored as 32-bit float.  The format
 * is given apart from `path` because the file is written under a temporary
 * name.  On failure a partial file may remain at `path`: the caller removes
 * it. */
int aa__oiio_write_float(const char *path, const char *format, int w, int h, int c,
                         const double *pixels);

/* The same for 8-bit samples already display-encoded by the caller; the
 * file is tagged with the encoding `gamma` (as in aa__oiio_info) when the
 * format can say it (PNG: sRGB chunk or gAMA). */
int aa__oiio_write_8bit(const char *path, const char *format, int w, int h, int c,
                        const unsigned char *pixels, double gamma);

/* Open `path` and describe it in `info`; nothing is read or allocated for
 * the pixels, so the caller can check the sizes first.  Refuses deep and
 * volume images.  *in is NULL on failure. */
int aa__oiio_open(const char *path, aa__oiio_in **in, aa__oiio_info *info);

/* Read the first subimage into `pixels` (info.w * info.h * info.c doubles)
 * as stored, converted to double: integer samples become stored / max
 * (no display decoding). */
int aa__oiio_read(aa__oiio_in *in, double *pixels);

/* Draw text (top-left at x, y; `size` pixels; colour of c floats) into a
 * W x H x C double buffer, with OpenImageIO's default font. */
int aa__oiio_text(double *pixels, int w, int h, int c, int x, int y, const char *text, int size,
                  const float *colour);

/* Close and free; NULL is fine. */
void aa__oiio_close(aa__oiio_in *in);

#ifdef __cplusplus
}
#endif

#endif /* AA_OIIO_H */
