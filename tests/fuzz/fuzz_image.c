/*
 * fuzz_image.c: libFuzzer target for the image readers (`make fuzz`).
 *
 * The input is written to a temporary file and read as .txt (aabench's own
 * text format, harness/core/image.c) and as .pfm (read by image.c too).  A
 * read must return a status and a whole image or nothing; a .txt image that
 * was read must write and read back identically.
 */
#include "bench.h"
#include "fuzz.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int put(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t n = fwrite(data, 1, size, f);
    return fclose(f) == 0 && n == size ? 0 : -1;
}

int aa_fuzz_image(const uint8_t *data, size_t size)
{
    char dir[] = "/tmp/aabench-fuzz-XXXXXX";
    if (!mkdtemp(dir))
        return 0;
    char txt[64], pfm[64], back[64];
    snprintf(txt, sizeof txt, "%s/in.txt", dir);
    snprintf(pfm, sizeof pfm, "%s/in.pfm", dir);
    snprintf(back, sizeof back, "%s/back.txt", dir);
    aa_image im = {0};
    if (put(txt, data, size) == 0 && aa_image_read(txt, &im) == AA_OK) {
        if (im.w < 1 || im.h < 1 || !im.v)
            abort();
        aa_image im2 = {0};
        if (aa_image_write(back, &im, NULL) == AA_OK && aa_image_read(back, &im2) == AA_OK) {
            if (im2.w != im.w || im2.h != im.h || im2.c != im.c ||
                memcmp(im.v, im2.v, (size_t)im.w * im.h * im.c * sizeof *im.v) != 0)
                abort();
        }
        aa_image_free(&im2);
        aa_image_free(&im);
        unlink(back);
    }
    if (put(pfm, data, size) == 0 && aa_image_read(pfm, &im) == AA_OK) {
        if (im.w < 1 || im.h < 1 || !im.v)
            abort();
        aa_image_free(&im);
    }
    unlink(txt);
    unlink(pfm);
    rmdir(dir);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_image)
