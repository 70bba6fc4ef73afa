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
 * file needs it (.exr, .tif, and a file named .png or .pfm that is not a PNG
 * or a PFM), and never for .png (libpng, image_png.c), .txt or .pfm (read
 * and written in image.c).  The module exports one function,
 * aa__oiio_entry(), which returns the table of the others.  It is handed the library's aa_fail
 * rather than calling it by name, so it needs no symbol of the program that
 * loads it.
 *
 * Loading it runs the static constructors of those libraries, which may
 * throw (std::bad_alloc, std::system_error) or fail fatally in the loader
 * when memory is short, before any code of ours runs: no catch can stop
 * that ending the process.  So under a limit on the process's memory
 * (RLIMIT_AS or RLIMIT_DATA) image.c first loads the module in a child
 * process, with a margin of room taken away, and reports AA_ENOMEM naming
 * the limit if the child does not come back.
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
#define AA__OIIO_VERSION 2

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
typedef struct aa__oiio_out aa__oiio_out;

typedef struct aa__oiio_api {
    /* Create the new file `path` (it must not exist) and start writing a
     * W x H x C image to it in the file format named `format` (an extension
     * without the dot: "exr", "tif", "png"; given apart from `path` because
     * the file is written under a temporary name).  With `is_float`, the
     * samples are given as doubles and stored as 32-bit floats; otherwise
     * they are given as 8-bit codes already display-encoded by the caller,
     * and the file is tagged with the encoding `gamma` (as in aa__oiio_info)
     * when the format can say it (PNG: sRGB chunk or gAMA).  Every byte
     * goes through our own file descriptor, so every failing write, seek
     * and close is seen.  *out is NULL on failure; a file may remain at
     * `path`: the caller removes it. */
    int (*out_open)(const char *path, const char *format, int w, int h, int c, int is_float,
                    double gamma, aa__oiio_out **out);
    /* Rows [y0, y1) of the image, in order, as W x (y1 - y0) x C samples
     * of the kind given to out_open. */
    int (*out_rows)(aa__oiio_out *out, int y0, int y1, const void *pixels);
    /* Finish the file: OpenImageIO's close, then ours; AA_OK only if every
     * call and every write since out_open succeeded.  Frees `out`. */
    int (*out_close)(aa__oiio_out *out);
    /* Give up writing: close and free without checking; NULL is fine. */
    void (*out_abort)(aa__oiio_out *out);
    /* Open `path` and describe it in `info`; nothing is read or allocated
     * for the pixels, so the caller can check the sizes first.  Refuses deep
     * and volume images.  *in is NULL on failure. */
    int (*open)(const char *path, aa__oiio_in **in, aa__oiio_info *info);
    /* Read the first subimage into `pixels` (info.w * info.h * info.c
     * doubles) as stored, converted to double: integer samples become
     * stored / max (no display decoding).  A file that ends early or holds
     * damaged data is refused, even where OpenImageIO's read call returns
     * true and leaves the failure in its error state only. */
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
