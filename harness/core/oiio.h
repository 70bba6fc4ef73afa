/*
 * oiio.h: internal C interface to OpenImageIO (harness/core/oiio.cpp).
 *
 * oiio.cpp is the project's only C++.  It moves pixels between memory and
 * files and nothing else: which formats are allowed, channel limits, display
 * encoding and the temporary-name dance all live in image.c.  No C++
 * exception crosses this interface; every failure is recorded with the
 * library's aa_fail() (naming the file) and returned as an aa_status: AA_EIO
 * for the file, AA_ENOMEM for memory, AA_EFAIL for anything else.
 *
 * OpenImageIO brings some 250 shared libraries with it (OpenCV, FFmpeg,
 * GDAL...), which would take half a second to load at every start of the
 * command.  So oiio.cpp is built into a module of its own,
 * aabench-oiio.so, linked against OpenImageIO, and the library does not link
 * either: image.c loads the module with dlopen() the first time an image
 * file needs it (.exr, .tif, .png, and reading .pfm), and never for .txt or
 * for writing .pfm.  The module exports one function, aa__oiio_entry(),
 * which returns the table of the others.  It is handed the library's aa_fail
 * rather than calling it by name, so it needs no symbol of the program that
 * loads it.
 *
 * Built with -DAA_OIIO_STATIC (the fuzzing build), image.c calls
 * aa__oiio_entry() directly and oiio.o is linked into the program.
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

/* The module's file name, and the symbol it exports. */
#define AA__OIIO_MODULE "aabench-oiio.so"
#define AA__OIIO_ENTRY "aa__oiio_entry"
/* Raised whenever the table or the meaning of an entry changes, so a module
 * from another build is refused rather than called wrongly. */
#define AA__OIIO_VERSION 1

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

typedef struct aa__oiio_api {
    /* Write `pixels` to `path` in the file format named `format` (an
     * extension without the dot: "exr", "tif", "png"), stored as 32-bit
     * float.  The format is given apart from `path` because the file is
     * written under a temporary name.  On failure a partial file may remain
     * at `path`: the caller removes it. */
    int (*write_float)(const char *path, const char *format, int w, int h, int c,
                       const double *pixels);
    /* The same for 8-bit samples already display-encoded by the caller; the
     * file is tagged with the encoding `gamma` (as in aa__oiio_info) when
     * the format can say it (PNG: sRGB chunk or gAMA). */
    int (*write_8bit)(const char *path, const char *format, int w, int h, int c,
                      const unsigned char *pixels, double gamma);
    /* Open `path` and describe it in `info`; nothing is read or allocated
     * for the pixels, so the caller can check the sizes first.  Refuses deep
     * and volume images.  *in is NULL on failure. */
    int (*open)(const char *path, aa__oiio_in **in, aa__oiio_info *info);
    /* Read the first subimage into `pixels` (info.w * info.h * info.c
     * doubles) as stored, converted to double: integer samples become
     * stored / max (no display decoding). */
    int (*read)(aa__oiio_in *in, double *pixels);
    /* Close and free; NULL is fine. */
    void (*close)(aa__oiio_in *in);
    /* Draw text (top-left at x, y; `size` pixels; colour of c floats) into
     * a W x H x C double buffer, with the DejaVu Sans font. */
    int (*text)(double *pixels, int w, int h, int c, int x, int y, const char *text, int size,
                const float *colour);
} aa__oiio_api;

/* The library's aa_fail (aabench.h). */
typedef int (*aa__oiio_fail_fn)(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* In the module: the table, with failures reported through `fail`; NULL if
 * `version` is not AA__OIIO_VERSION.  Called once, before any entry of the
 * table is used. */
const aa__oiio_api *aa__oiio_entry(int version, aa__oiio_fail_fn fail);

/* In image.c: the table, the module loaded on the first call (thread-safe);
 * NULL after recording an AA_EIO failure for `path` (the file that needed
 * it) that says which module was looked for and why it did not load. */
const aa__oiio_api *aa__oiio(const char *path);

/* The text entry through aa__oiio(), for montage.c. */
int aa__oiio_text(double *pixels, int w, int h, int c, int x, int y, const char *text, int size,
                  const float *colour);

#ifdef __cplusplus
}
#endif

#endif /* AA_OIIO_H */
