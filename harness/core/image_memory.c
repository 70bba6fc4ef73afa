/*
 * image_memory.c: an image in memory, made and freed (core.h, aa_image).
 * Every reader of an image file makes its image here: image.c for the
 * formats OpenImageIO reads, image_txt.c for .txt.
 */
#include "core.h"

#include <stdint.h>
#include <stdlib.h>

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
