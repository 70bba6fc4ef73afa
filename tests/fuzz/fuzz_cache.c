/*
 * fuzz_cache.c: libFuzzer target for the reference cache's reader
 * (`make fuzz`).
 *
 * The input is put in the cache folder under the name of a small view's
 * reference, then that reference is asked for.  Whatever the file holds, the
 * answer must be the true reference, bit for bit (computed once, without the
 * cache): a damaged or forged file may cost a recomputation, never a wrong
 * image.
 */
#include "bench.h"
#include "fuzz.h"

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char cache_dir[256], cache_file[600];
static aa_view view;
static aa_image truth;

static void cache_setup(void)
{
    snprintf(cache_dir, sizeof cache_dir, "/tmp/aabench-fuzz-cache-%ld", (long)getpid());
    memset(&view, 0, sizeof view);
    if (aa_pattern_parse("crow:curves=8,kmax=0.05", &view.pattern) != AA_OK)
        abort();
    view.w = 5, view.h = 3;
    aa_filter_default(&view.filter);
    aa_image first;
    if (aa_reference(&view, NULL, 1, &truth, NULL, NULL) != AA_OK ||
        aa_reference(&view, cache_dir, 1, &first, NULL, NULL) != AA_OK)
        abort();
    aa_image_free(&first);
    DIR *d = opendir(cache_dir);
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (!strncmp(e->d_name, "ref-", 4))
            snprintf(cache_file, sizeof cache_file, "%s/%s", cache_dir, e->d_name);
    if (d)
        closedir(d);
    if (!cache_file[0])
        abort();
}

int aa_fuzz_cache(const uint8_t *data, size_t size)
{
    if (!cache_file[0])
        cache_setup();
    FILE *f = fopen(cache_file, "wb");
    if (!f)
        abort();
    if (size && fwrite(data, 1, size, f) != size)
        abort();
    if (fclose(f) != 0)
        abort();
    aa_image img;
    if (aa_reference(&view, cache_dir, 1, &img, NULL, NULL) != AA_OK)
        abort();
    if (memcmp(img.v, truth.v, (size_t)view.w * view.h * 3 * sizeof *img.v) != 0)
        abort(); /* a wrong reference was served */
    aa_image_free(&img);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_cache)
