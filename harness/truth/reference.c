/*
 * reference.c: reference images of views, and their cache.
 *
 * A view is everything that defines a reference image: the pattern with all
 * its parameters, the size, the filter with its parameters, the time and the
 * motion.  Its canonical text (every parameter printed with %.17g, plus the
 * version of the ground-truth code) is the cache key; the file name is a
 * 64-bit FNV-1a hash of it, and the file holds the whole key, which is
 * compared on reading, so a hash collision is a miss, never a wrong image.
 *
 * Cache file: "aabench-reference\n", the key's length (uint32) and text,
 * w, h, c (int32), the largest error bound (double), then w h c doubles,
 * host byte order.  Anything that does not match is a miss and is
 * recomputed; files are written atomically.
 */
#include "truth.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Bump when the ground truth's results could change. */
#define TRUTH_VERSION 2 /* 2: crowded windows one piece at a time (truth_crowd.c) */
#define CACHE_MAGIC "aabench-reference\n"

static int field_key(const aa_view *view, char *buf, size_t len);

int aa_view_key(const aa_view *view, char *buf, size_t len)
{
    char pattern[1024], filter[256];
    int st;
    if ((st = aa_spec_format(&view->pattern, pattern, sizeof pattern)) ||
        (st = aa_spec_format(&view->filter.spec, filter, sizeof filter)))
        return st;
    int n = snprintf(buf, len, "truth %d\npattern %s\nsize %dx%d\nfilter %s\ntime %.17g\n"
                     "motion %.17g,%.17g\n",
                     TRUTH_VERSION, pattern, view->w, view->h, filter, view->t, view->vx,
                     view->vy);
    if (n < 0 || (size_t)n >= len)
        return aa_fail(AA_EFAIL, "view key too long");
    return field_key(view, buf + n, len - (size_t)n);
}

/* A field pattern (core.h, "Fields") adds a line naming the field, the
 * version of its integral and its parameters, so that a change to the
 * field's code or parameters is never served an old image.  A pattern that
 * cannot be built adds nothing (its reference fails anyway). */
static int field_key(const aa_view *view, char *buf, size_t len)
{
    aa_scene *s = NULL;
    const double *p;
    int np, n, st = AA_OK;
    if (aa_pattern_scene(&view->pattern, &s) != AA_OK)
        return AA_OK;
    const aa_field_type *field = aa_scene_field(s, &p, &np, NULL);
    if (field) {
        n = snprintf(buf, len, "field %s %d", field->name, field->version);
        for (int k = 0; k < np && n >= 0 && (size_t)n < len; k++)
            n += snprintf(buf + n, len - (size_t)n, " %.17g", p[k]);
        if (n >= 0 && (size_t)n < len)
            n += snprintf(buf + n, len - (size_t)n, "\n");
        if (n < 0 || (size_t)n >= len)
            st = aa_fail(AA_EFAIL, "view key too long");
    }
    aa_scene_free(s);
    return st;
}

static uint64_t fnv1a(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 1099511628211ull;
    }
    return h;
}

static int cache_path(const char *dir, const char *key, char *buf, size_t len)
{
    int n = snprintf(buf, len, "%s/ref-%016llx.bin", dir, (unsigned long long)fnv1a(key));
    if (n < 0 || (size_t)n >= len)
        return aa_fail(AA_EINVAL, "cache folder name too long: %s", dir);
    return AA_OK;
}

/* 1 on a hit (image filled), 0 on a miss. */
static int cache_read(const char *path, const char *key, int w, int h, aa_image *out,
                      double *max_bound)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char magic[sizeof CACHE_MAGIC];
    uint32_t klen = 0;
    int32_t dims[3];
    int hit = 0;
    char *stored = NULL;
    if (fread(magic, 1, sizeof CACHE_MAGIC - 1, f) != sizeof CACHE_MAGIC - 1 ||
        memcmp(magic, CACHE_MAGIC, sizeof CACHE_MAGIC - 1) != 0 ||
        fread(&klen, sizeof klen, 1, f) != 1 || klen != strlen(key))
        goto done;
    if (!(stored = malloc(klen + 1)) || fread(stored, 1, klen, f) != klen ||
        memcmp(stored, key, klen) != 0)
        goto done;
    if (fread(dims, sizeof dims, 1, f) != 1 || dims[0] != w || dims[1] != h || dims[2] != 3 ||
        fread(max_bound, sizeof *max_bound, 1, f) != 1)
        goto done;
    size_t count = (size_t)w * (size_t)h * 3;
    if (fread(out->v, sizeof *out->v, count, f) != count || fgetc(f) != EOF)
        goto done;
    hit = 1;
done:
    free(stored);
    fclose(f);
    return hit;
}

static int cache_write(const char *dir, const char *path, const char *key, const aa_image *im,
                       double max_bound)
{
    int st = aa_mkdirs(dir);
    if (st)
        return st;
    uint32_t klen = (uint32_t)strlen(key);
    int32_t dims[3] = {im->w, im->h, im->c};
    size_t pixels = (size_t)im->w * (size_t)im->h * (size_t)im->c * sizeof *im->v;
    size_t len = sizeof CACHE_MAGIC - 1 + sizeof klen + klen + sizeof dims + sizeof max_bound +
                 pixels;
    char *buf = malloc(len), *p = buf;
    if (!buf)
        return aa_fail(AA_ENOMEM, "out of memory writing the reference cache");
    memcpy(p, CACHE_MAGIC, sizeof CACHE_MAGIC - 1), p += sizeof CACHE_MAGIC - 1;
    memcpy(p, &klen, sizeof klen), p += sizeof klen;
    memcpy(p, key, klen), p += klen;
    memcpy(p, dims, sizeof dims), p += sizeof dims;
    memcpy(p, &max_bound, sizeof max_bound), p += sizeof max_bound;
    memcpy(p, im->v, pixels);
    st = aa_file_write_atomic(path, buf, len);
    free(buf);
    return st;
}

int aa_reference(const aa_view *view, const char *cache_dir, int threads, aa_image *out,
                 aa_truth_stats *stats, int *from_cache)
{
    char key[2048], path[4096];
    aa_truth_stats local;
    aa_scene *pattern = NULL, *placed = NULL;
    int st;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    if (from_cache)
        *from_cache = 0;
    if ((st = aa_size_check(view->w, view->h, 4, 1)) || (st = aa_view_key(view, key, sizeof key)))
        return st;
    if (cache_dir && (st = cache_path(cache_dir, key, path, sizeof path)))
        return st;
    if ((st = aa_image_alloc(out, view->w, view->h, 3)))
        return st;
    if (cache_dir && cache_read(path, key, view->w, view->h, out, &stats->max_bound)) {
        if (from_cache)
            *from_cache = 1;
        stats->worst_i = stats->worst_j = -1;
        return AA_OK;
    }
    if ((st = aa_pattern_scene(&view->pattern, &pattern)))
        goto fail;
    placed = aa_scene_place(pattern, view->w, view->h, view->t, view->vx, view->vy);
    if (!placed) {
        st = AA_EINVAL;
        goto fail;
    }
    if ((st = aa_truth_render(placed, &view->filter, threads, out, NULL, stats)))
        goto fail;
    aa_scene_free(placed);
    aa_scene_free(pattern);
    /* A cache that cannot be written costs time later, not correctness:
     * the image is still returned. */
    if (cache_dir)
        cache_write(cache_dir, path, key, out, stats->max_bound);
    return AA_OK;
fail:
    aa_scene_free(placed);
    aa_scene_free(pattern);
    aa_image_free(out);
    return st;
}
