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
 * Cache file: CACHE_MAGIC, the key's length (uint32) and text, w, h, c
 * (int32), the count of pixels whose bounds are estimates (uint64:
 * aa_truth_stats.scanned), the largest error bound (double), w h c
 * doubles, then a 64-bit
 * checksum of everything after the magic; host byte order.  A file from
 * another version, or for another key (a hash collision), is a miss and is
 * recomputed.  A file of ours that does not hold together (short, long, a
 * checksum that does not match, values that are not finite) is corrupt: a
 * warning says so (aa_warn) and the reference is recomputed and stored
 * again.  Only regular files are opened (a FIFO would block the reader).
 * Files are written atomically, so concurrent writers of the same
 * reference (shards on a shared folder) leave one whole file.
 */
#include "truth.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Bump when the ground truth's results could change. */
#define TRUTH_VERSION 21/* 2: crowded windows one piece at a time (truth_crowd.c); 3: conic
                          * pieces, and the cone's breakpoint where a piece passes
                          * closest to the centre; 4: the square root substitution on
                          * intervals that end near a turning point; 5: which radial
                          * gradient a span depends on, decided with the other
                          * gradients transparent (one could hide behind another's
                          * stand-in colour); 6: offset curves' roots taken to
                          * convergence (aa__offset_root stopped after 8 steps); 7:
                          * under the box, the threshold's lines of a linear gradient
                          * crossing the window's sides as breakpoints, and the
                          * threshold isolated by Taylor's theorem (rows tangent to it
                          * had their lengths as bounds); 8: every turning point of a
                          * window kept (64 at most were: a repeating radial gradient's
                          * stop circles' tangent rows past them were left to QAG); 9:
                          * the winding left of the window at the exact height vc + s
                          * (aa_strip_winding_left_at), not that sum rounded to double:
                          * a piece ending within half an ulp of it was on the wrong
                          * side, up to 5.7e-14 a pixel beyond the bound at 1024 px;
                          * 10: crowded windows of more than CROWD_WL_LAYERS layers
                          * walk every colour jump again when the colour left of the
                          * window changes (only those right of the first changed
                          * piece were: values down to -1.4 under the B-spline);
                          * 11: the sRGB threshold's heights where translucent
                          * gradients of different t mix certified by interval boxes
                          * (thr_certify), not only scanned; 12: also in windows
                          * that edges (not offset curves) enter, box by box, for
                          * gradients in linear light and past 32 gradient layers;
                          * 13: the threshold met in double at a halving's midpoint
                          * kept to GEN_FUZZ (bounds of 8.7e-4 had the whole span);
                          * 14: windows that offset curves (strokes' sides) enter
                          * certified box by box too (thr_offset_x); under radial
                          * filters the threshold's slivers bounded by the weight's
                          * slope (4 R its peak a unit of height was), and windows
                          * that edges enter certified there too;
                          * 15: windows of cone-case gradients certified box by
                          * box (thr_cone_t); 16: a sliver's strip where a piece
                          * crosses it bounded over the piece's x by E's range
                          * over the covered and uncovered cases together, not
                          * the wider of the two; 17: a painted cone layer's t''
                          * bounded for the threshold's Taylor test, the
                          * half-plane's t across its edge in a box, and a
                          * sliver's strip that a cone's line crosses bounded
                          * over the line's x by both cases' range; 18: a box
                          * that a wedge's tangent line crosses free where E on
                          * the line is off 0.04045 and u E' (u = sqrt(L0 L1)) is
                          * off 0 (the curve touching the line was scanned), and
                          * a piece in u below x's resolution weighed by the fit
                          * over its stretch (0 / 0: the row refused); 19: in
                          * the crowded pixels' sweep, pieces made neighbours at
                          * a height where they meet put in their order just
                          * after it (three pieces through one point: values up
                          * to 1.26 on a white stroke); 20: a radial gradient's
                          * dmin without cancellation near P* and its rounding
                          * counted in the branch points' distance (bounds only:
                          * 1.9e-12 to 1.5e-14 on a focus's pixel); 21: a crowded
                          * window's pair just swapped at a meeting not swapped
                          * back by x at the meeting's height (a nearly
                          * horizontal piece: up to 2.5e-2 a pixel off) */
#define CACHE_MAGIC "aabench-reference 3\n" /* 3: the count scanned */

static int field_key(const aa_view *view, char *buf, size_t len);

/* The key's numbers are C-locale text, whatever the program's LC_NUMERIC:
 * the same view has the same key in every locale. */
int aa_view_key(const aa_view *view, char *buf, size_t len)
{
    char pattern[4096], filter[256];
    aa__c_numbers numbers;
    int st;
    if ((st = aa_spec_format_key(&view->pattern, pattern, sizeof pattern)) ||
        (st = aa_spec_format_key(&view->filter.spec, filter, sizeof filter)) ||
        (st = aa__c_numbers_enter(&numbers, "view key")))
        return st;
    int n = snprintf(buf, len, "truth %d\npattern %s\nsize %dx%d\nfilter %s\ntime %.17g\n"
                     "motion %.17g,%.17g\n",
                     TRUTH_VERSION, pattern, view->w, view->h, filter, view->t, view->vx,
                     view->vy);
    if (n < 0 || (size_t)n >= len)
        st = aa_fail(AA_EFAIL, "view key too long");
    else if (!(st = field_key(view, buf + n, len - (size_t)n))) {
        /* a pattern read from files adds their contents' hashes */
        size_t m = strlen(buf);
        st = aa_pattern_key(&view->pattern, buf + m, len - m);
    }
    aa__c_numbers_end(&numbers);
    return st;
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
    if (aa_pattern_sized(&view->pattern) || aa_pattern_scene(&view->pattern, &s) != AA_OK)
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

/* A 64-bit checksum: each 8-byte word, mixed with its position in the
 * stream, through SplitMix64's bijective finaliser, so a changed, moved or
 * swapped word changes the result.  Fed in pieces; a piece that is not a
 * whole number of words is only ever the last. */
typedef struct checksum {
    uint64_t h, k;
} checksum;

static void checksum_add(checksum *c, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (; n >= 8; n -= 8, p += 8, c->k++) {
        uint64_t w;
        memcpy(&w, p, 8);
        c->h = aa_hash64(c->h ^ w ^ (c->k * 0x9e3779b97f4a7c15ull));
    }
    if (n) {
        uint64_t w = 0;
        memcpy(&w, p, n);
        c->h = aa_hash64(c->h ^ w ^ ((uint64_t)n << 56) ^ (c->k++ * 0x9e3779b97f4a7c15ull));
    }
}

static size_t read_bytes(int fd, void *buf, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = read(fd, (char *)buf + got, n - got);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            break;
        got += (size_t)k;
    }
    return got;
}

/* Longest key a cache file may claim (ours are under 2 kB). */
#define KEY_MAX 65536

/* 1 on a hit (image filled), 0 on a miss.  The whole file is checked
 * against its checksum before its key is compared, so a damaged key warns
 * like damaged pixels, while a whole file of another view (a hash
 * collision) is a quiet miss. */
static int cache_read(const char *path, const char *key, int w, int h, const aa_filter *f,
                      aa_image *out, double *max_bound, size_t *scanned)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return 0;
    struct stat sb;
    if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
        close(fd);
        aa_warn("reference cache %s is not a regular file: not read; the reference is "
                "recomputed",
                path);
        return 0;
    }
    char magic[sizeof CACHE_MAGIC];
    uint32_t klen = 0;
    int32_t dims[3];
    uint64_t stored_sum, nscanned = 0;
    int hit = 0;
    const char *why = NULL;
    char *stored = NULL;
    checksum sum = {0, 0};
    if (read_bytes(fd, magic, sizeof CACHE_MAGIC - 1) != sizeof CACHE_MAGIC - 1 ||
        memcmp(magic, CACHE_MAGIC, sizeof CACHE_MAGIC - 1) != 0)
        goto done; /* not ours, or another version's: a miss */
    why = "cut short";
    if (read_bytes(fd, &klen, sizeof klen) != sizeof klen)
        goto done;
    if (klen > KEY_MAX) {
        why = "damaged (its key length is absurd)";
        goto done;
    }
    if (!(stored = malloc((size_t)klen + 1))) {
        why = "too large to read into memory";
        goto done;
    }
    if (read_bytes(fd, stored, klen) != klen || read_bytes(fd, dims, sizeof dims) != sizeof dims ||
        read_bytes(fd, &nscanned, sizeof nscanned) != sizeof nscanned ||
        read_bytes(fd, max_bound, sizeof *max_bound) != sizeof *max_bound)
        goto done;
    if (dims[0] < 1 || dims[1] < 1 || dims[0] > AA_MAX_SIDE || dims[1] > AA_MAX_SIDE ||
        dims[2] != 3) {
        why = "damaged (its size is absurd)";
        goto done;
    }
    size_t count = (size_t)dims[0] * (size_t)dims[1] * 3;
    uint64_t expect = (uint64_t)(sizeof CACHE_MAGIC - 1) + sizeof klen + klen + sizeof dims +
                      sizeof nscanned + sizeof *max_bound + count * sizeof(double) +
                      sizeof stored_sum;
    if ((uint64_t)sb.st_size != expect) {
        why = (uint64_t)sb.st_size < expect ? "cut short" : "of the wrong length";
        goto done;
    }
    checksum_add(&sum, &klen, sizeof klen);
    checksum_add(&sum, stored, klen);
    checksum_add(&sum, dims, sizeof dims);
    checksum_add(&sum, &nscanned, sizeof nscanned);
    checksum_add(&sum, max_bound, sizeof *max_bound);
    int ours = dims[0] == w && dims[1] == h;
    if (ours) {
        if (read_bytes(fd, out->v, count * sizeof *out->v) != count * sizeof *out->v)
            goto done;
        checksum_add(&sum, out->v, count * sizeof *out->v);
    } else { /* another size: read only to check the file */
        double chunk[4096];
        for (size_t left = count; left > 0;) {
            size_t n = left < 4096 ? left : 4096;
            if (read_bytes(fd, chunk, n * sizeof *chunk) != n * sizeof *chunk)
                goto done;
            checksum_add(&sum, chunk, n * sizeof *chunk);
            left -= n;
        }
    }
    if (read_bytes(fd, &stored_sum, sizeof stored_sum) != sizeof stored_sum)
        goto done;
    if (sum.h != stored_sum) {
        why = "damaged (its checksum does not match)";
        goto done;
    }
    why = NULL;
    if (klen != strlen(key) || memcmp(stored, key, klen) != 0)
        goto done; /* a whole file of another view under the same hash */
    if (!ours || !(*max_bound >= 0.0) || !isfinite(*max_bound) ||
        nscanned > (uint64_t)w * (uint64_t)h) {
        why = "inconsistent with its key";
        goto done;
    }
    /* a reference is within [0, 1] (wider by the negative lobes of its
     * filter, aa_filter_range) up to its own rounding (a pixel of 0 under
     * the tent can come out -1e-17) */
    double lo, hi;
    aa_filter_range(f, &lo, &hi);
    for (size_t k = 0; k < count; k++)
        if (!(out->v[k] >= lo - 1e-9 && out->v[k] <= hi + 1e-9)) {
            why = "holding a value outside the range of its filter";
            goto done;
        }
    *scanned = (size_t)nscanned;
    hit = 1;
done:
    if (why)
        aa_warn("reference cache %s is %s: recomputing it", path, why);
    free(stored);
    close(fd);
    return hit;
}

static int cache_write(const char *dir, const char *path, const char *key, const aa_image *im,
                       double max_bound, size_t scanned)
{
    int st = aa_mkdirs(dir);
    if (st)
        return st;
    uint32_t klen = (uint32_t)strlen(key);
    int32_t dims[3] = {im->w, im->h, im->c};
    uint64_t nscanned = scanned;
    size_t pixels = (size_t)im->w * (size_t)im->h * (size_t)im->c * sizeof *im->v;
    size_t len = sizeof CACHE_MAGIC - 1 + sizeof klen + klen + sizeof dims + sizeof nscanned +
                 sizeof max_bound + pixels + sizeof(uint64_t);
    char *buf = malloc(len), *p = buf;
    if (!buf)
        return aa_fail(AA_ENOMEM, "out of memory writing the reference cache");
    checksum sum = {0, 0};
    memcpy(p, CACHE_MAGIC, sizeof CACHE_MAGIC - 1), p += sizeof CACHE_MAGIC - 1;
    /* the same pieces, in the same order, as the reader checks */
    checksum_add(&sum, &klen, sizeof klen);
    checksum_add(&sum, key, klen);
    checksum_add(&sum, dims, sizeof dims);
    checksum_add(&sum, &nscanned, sizeof nscanned);
    checksum_add(&sum, &max_bound, sizeof max_bound);
    checksum_add(&sum, im->v, pixels);
    memcpy(p, &klen, sizeof klen), p += sizeof klen;
    memcpy(p, key, klen), p += klen;
    memcpy(p, dims, sizeof dims), p += sizeof dims;
    memcpy(p, &nscanned, sizeof nscanned), p += sizeof nscanned;
    memcpy(p, &max_bound, sizeof max_bound), p += sizeof max_bound;
    memcpy(p, im->v, pixels), p += pixels;
    memcpy(p, &sum.h, sizeof sum.h);
    st = aa_file_write_atomic(path, buf, len);
    free(buf);
    return st;
}

int aa_reference(const aa_view *view, const char *cache_dir, int threads, aa_image *out,
                 aa_truth_stats *stats, int *from_cache)
{
    char key[8192], path[4096];
    aa_truth_stats local;
    aa_scene *pattern = NULL, *placed = NULL;
    int st;
    *out = (aa_image){0}; /* empty on failure, whatever the caller passed */
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
    if (cache_dir && cache_read(path, key, view->w, view->h, &view->filter, out, &stats->max_bound,
                                &stats->scanned)) {
        if (from_cache)
            *from_cache = 1;
        stats->worst_i = stats->worst_j = -1;
        return AA_OK;
    }
    if ((st = aa_pattern_scene_at(&view->pattern, view->w, view->h, &pattern)))
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
        cache_write(cache_dir, path, key, out, stats->max_bound, stats->scanned);
    return AA_OK;
fail:
    aa_scene_free(placed);
    aa_scene_free(pattern);
    aa_image_free(out);
    return st;
}
