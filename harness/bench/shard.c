/*
 * shard.c: a run cut into shards by estimated cost, and the manifest
 * (run.json) that lets shards be merged and interrupted runs resumed.
 *
 * The partition must be the same on every machine that computes it: the
 * costs are integers, and every tie is broken by the case's number or the
 * shard's, so no floating point or hash order can move a case.  Costs are
 * estimates (pixels x samples), good enough to balance a sweep whose cases
 * differ by orders of magnitude; they are not times.
 *
 * The manifest is JSON, read and written with cJSON.
 */
#include "bench.h"

#include <cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t aa_run_case_count(const aa_run_config *cfg)
{
    return cfg->npatterns * cfg->nsizes * cfg->nfilters * cfg->nmethods;
}

/* The size index of case k (pattern, size, filter, method order). */
static size_t size_of_case(const aa_run_config *cfg, size_t k)
{
    return (k / (cfg->nmethods * cfg->nfilters)) % cfg->nsizes;
}

static int animated_run(const aa_run_config *cfg)
{
    return cfg->temporal || cfg->vx != 0.0 || cfg->vy != 0.0;
}

/* A spec's numeric parameter, or 0 when it has none (a choice's value is
 * the index of its word, not a number). */
static double param(const aa_spec *spec, const char *key)
{
    int i = aa_spec_index(spec->info, key);
    return i < 0 || spec->info->params[i].kind == AA_PARAM_CHOICE ? 0.0 : spec->v[i];
}

/* A case whose method refuses its filter costs nothing: the run skips it,
 * or gives a row saying so, without rendering (or needing the reference). */
static int refused(const aa_run_config *cfg, size_t k)
{
    const aa_spec *m = &cfg->methods[k % cfg->nmethods].spec;
    const aa_filter *f = &cfg->filters[(k / cfg->nmethods) % cfg->nfilters].filter;
    return aa_method_check(m, f) != AA_OK;
}

uint64_t aa_case_cost(const aa_run_config *cfg, size_t k)
{
    if (refused(cfg, k))
        return 0;
    const aa_run_size *s = &cfg->sizes[size_of_case(cfg, k)];
    const aa_spec *m = &cfg->methods[k % cfg->nmethods].spec;
    const aa_method_type *type = (const aa_method_type *)m->info;
    double spp = param(m, "spp"), n = param(m, "n");
    uint64_t samples = spp >= 1 ? (uint64_t)spp : n >= 1 ? (uint64_t)(n * n) : 1;
    if (type->flags & AA_METHOD_TEMPORAL) {
        /* the frames it renders for one image: its history, or its frames */
        double frames = param(m, "history") >= 1 ? param(m, "history") : param(m, "frames");
        samples *= frames >= 1 ? (uint64_t)frames : 1;
    }
    uint64_t cost = (uint64_t)s->w * (uint64_t)s->h * samples;
    if (animated_run(cfg))
        cost *= (uint64_t)(cfg->frames > 0 ? cfg->frames : 24);
    if (cfg->seeds > 1 && (type->flags & AA_METHOD_SEEDED))
        cost *= (uint64_t)cfg->seeds;
    return cost;
}

uint64_t aa_case_reference_cost(const aa_run_config *cfg, size_t k)
{
    if (refused(cfg, k))
        return 0;
    const aa_run_size *s = &cfg->sizes[size_of_case(cfg, k)];
    uint64_t cost = (uint64_t)s->w * (uint64_t)s->h * AA_SHARD_REFERENCE_WEIGHT;
    if (animated_run(cfg))
        cost *= (uint64_t)(cfg->frames > 0 ? cfg->frames : 24);
    return cost;
}

typedef struct plan_case {
    uint64_t cost, ref;
    size_t view; /* the view's number in the whole run */
    size_t index;
} plan_case;

/* Most costly first; ties by the case's number. */
static int by_cost(const void *a, const void *b)
{
    const plan_case *x = a, *y = b;
    if (x->cost != y->cost)
        return x->cost < y->cost ? 1 : -1;
    return x->index < y->index ? -1 : x->index > y->index;
}

int aa_shard_plan(const aa_run_config *cfgs, size_t ng, int shard, int nshards,
                  unsigned char **masks, size_t *selected, uint64_t *cost)
{
    *selected = 0;
    if (cost)
        *cost = 0;
    for (size_t g = 0; g < ng; g++)
        masks[g] = NULL;
    if (nshards < 1 || nshards > AA_SHARD_MAX || shard < 1 || shard > nshards)
        return aa_fail(AA_EINVAL, "shard %d/%d out of range (1 <= K <= N <= %d)", shard, nshards,
                       AA_SHARD_MAX);
    size_t total = 0, nviews = 0;
    for (size_t g = 0; g < ng; g++)
        total += aa_run_case_count(&cfgs[g]);
    plan_case *pc = calloc(total ? total : 1, sizeof *pc);
    int *owner = calloc(total ? total : 1, sizeof *owner);
    uint64_t *load = calloc((size_t)nshards, sizeof *load);
    int st = AA_OK;
    if (!pc || !owner || !load) {
        st = aa_fail(AA_ENOMEM, "out of memory planning %zu cases", total);
        goto done;
    }
    for (size_t g = 0, i = 0; g < ng; g++) {
        const aa_run_config *c = &cfgs[g];
        size_t n = aa_run_case_count(c);
        for (size_t k = 0; k < n; k++, i++) {
            pc[i].cost = aa_case_cost(c, k);
            pc[i].ref = aa_case_reference_cost(c, k);
            pc[i].view = nviews + k / c->nmethods;
            pc[i].index = i;
        }
        nviews += n / (c->nmethods ? c->nmethods : 1);
    }
    /* which views each shard already visits: a bit per (shard, view) */
    size_t words = (nviews + 63) / 64;
    uint64_t *has = calloc((size_t)nshards * (words ? words : 1), sizeof *has);
    if (!has) {
        st = aa_fail(AA_ENOMEM, "out of memory planning %zu views", nviews);
        goto done;
    }
    qsort(pc, total, sizeof *pc, by_cost);
    for (size_t i = 0; i < total; i++) {
        int best = 0;
        uint64_t best_load = 0;
        for (int s = 0; s < nshards; s++) {
            const uint64_t *h = has + (size_t)s * words;
            int visits = (h[pc[i].view / 64] >> (pc[i].view % 64)) & 1;
            uint64_t l = load[s] + pc[i].cost + (visits ? 0 : pc[i].ref);
            if (s == 0 || l < best_load)
                best = s, best_load = l;
        }
        load[best] = best_load;
        has[(size_t)best * words + pc[i].view / 64] |= (uint64_t)1 << (pc[i].view % 64);
        owner[pc[i].index] = best;
    }
    free(has);
    if (cost)
        *cost = load[shard - 1];
    for (size_t g = 0, i = 0; g < ng && !st; g++) {
        size_t n = aa_run_case_count(&cfgs[g]);
        if (!(masks[g] = calloc(n ? n : 1, 1))) {
            st = aa_fail(AA_ENOMEM, "out of memory");
            break;
        }
        for (size_t k = 0; k < n; k++, i++)
            if (owner[i] == shard - 1) {
                masks[g][k] = 1;
                ++*selected;
            }
    }
done:
    if (st)
        for (size_t g = 0; g < ng; g++) {
            free(masks[g]);
            masks[g] = NULL;
        }
    free(pc);
    free(owner);
    free(load);
    return st;
}

/* ---- the manifest ---- */

int aa_manifest_skips(const char *arg, int *takes_value)
{
    static const struct {
        const char *name;
        int value;
    } skip[] = {{"--out", 1},      {"--resume", 1}, {"--shard", 1},  {"--cache", 1},
                {"--no-cache", 0}, {"-q", 0},       {"--quiet", 0}, {"--threads", 1}};
    *takes_value = 0;
    for (size_t k = 0; k < sizeof skip / sizeof *skip; k++) {
        size_t n = strlen(skip[k].name);
        if (!strncmp(arg, skip[k].name, n) && (arg[n] == '\0' || (arg[n] == '=' && skip[k].value))) {
            *takes_value = skip[k].value && arg[n] == '\0';
            return 1;
        }
    }
    return 0;
}

/* ---- checksums ---- */

#define FNV_START 0xcbf29ce484222325ull
static uint64_t fnv1a(const void *data, size_t n, uint64_t h)
{
    const unsigned char *b = data;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 0x100000001b3ull;
    return h;
}

void aa_bytes_checksum(const void *data, size_t n, char sum[64])
{
    snprintf(sum, 64, "fnv1a %016llx bytes %zu", (unsigned long long)fnv1a(data, n, FNV_START),
             n);
}

int aa_file_checksum(const char *path, char sum[64])
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return aa_fail(AA_EIO, "cannot read %s: %s", aa_echo(path), strerror(errno));
    unsigned char chunk[65536];
    uint64_t h = FNV_START;
    size_t n = 0, k;
    while ((k = fread(chunk, 1, sizeof chunk, f)) > 0) {
        h = fnv1a(chunk, k, h);
        n += k;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad)
        return aa_fail(AA_EIO, "cannot read %s", aa_echo(path));
    snprintf(sum, 64, "fnv1a %016llx bytes %zu", (unsigned long long)h, n);
    return AA_OK;
}

int aa_manifest_write(const char *path, const aa_manifest *m)
{
    cJSON *o = cJSON_CreateObject(), *cmd = cJSON_CreateArray(), *sel = cJSON_CreateArray(),
          *ref = cJSON_CreateArray();
    int ok = o && cmd && sel && ref;
    for (int k = 0; ok && k < m->argc; k++)
        ok = cJSON_AddItemToArray(cmd, cJSON_CreateString(m->argv[k]));
    for (size_t k = 0; ok && k < m->nselected; k++)
        ok = cJSON_AddItemToArray(sel, cJSON_CreateNumber((double)m->selected[k]));
    for (size_t k = 0; ok && k < m->nrefused; k++)
        ok = cJSON_AddItemToArray(ref, cJSON_CreateNumber((double)m->refused[k]));
    if (ok) {
        cJSON_AddItemToObject(o, "command", cmd), cmd = NULL;
        ok = cJSON_AddStringToObject(o, "suite", m->suite) &&
             cJSON_AddStringToObject(o, "commit", m->commit) &&
             (m->dirty < 0 ? cJSON_AddNullToObject(o, "dirty") != NULL
                           : cJSON_AddBoolToObject(o, "dirty", m->dirty) != NULL) &&
             cJSON_AddStringToObject(o, "host", m->host) &&
             cJSON_AddNumberToObject(o, "shard", m->shard) &&
             cJSON_AddNumberToObject(o, "shards", m->shards) &&
             cJSON_AddNumberToObject(o, "cases", (double)m->cases);
    }
    if (ok) {
        cJSON_AddItemToObject(o, "selected", sel), sel = NULL;
        cJSON_AddItemToObject(o, "refused", ref), ref = NULL;
        cJSON *ctx = m->context ? cJSON_Parse(m->context) : cJSON_CreateNull();
        ok = ctx && cJSON_AddItemToObject(o, "context", ctx);
    }
    if (ok && m->ninputs) {
        cJSON *in = cJSON_AddObjectToObject(o, "inputs");
        ok = in != NULL;
        for (size_t k = 0; ok && k < m->ninputs; k++)
            ok = cJSON_AddStringToObject(in, m->inputs[k].what, m->inputs[k].inputs) != NULL;
    }
    if (ok && m->summed) {
        cJSON *sums = cJSON_AddObjectToObject(o, "checksums");
        ok = sums != NULL;
        for (size_t k = 0; ok && k < m->nsums; k++)
            ok = cJSON_AddStringToObject(sums, m->sums[k].name, m->sums[k].sum) != NULL;
    }
    char *text = ok ? cJSON_Print(o) : NULL;
    cJSON_Delete(o);
    cJSON_Delete(cmd);
    cJSON_Delete(sel);
    cJSON_Delete(ref);
    if (!text)
        return aa_fail(AA_ENOMEM, "out of memory writing %s", path);
    size_t len = strlen(text);
    text[len] = '\n'; /* overwrites the NUL: a line ends the file */
    int st = aa_file_write_atomic(path, text, len + 1);
    free(text);
    return st;
}

static int bad(const char *path, const char *member, const char *why)
{
    return aa_fail(AA_EINVAL, "%s: \"%s\" %s", path, member, why);
}

/* A whole number in [lo, hi]. */
static int whole(const cJSON *v, double lo, double hi)
{
    return cJSON_IsNumber(v) && v->valuedouble >= lo && v->valuedouble <= hi &&
           v->valuedouble == (double)(long long)v->valuedouble;
}

/* A manifest is small: more than this is not one. */
#define MANIFEST_MAX ((size_t)64 << 20)

static int read_text(const char *path, char **out)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return aa_fail(AA_EIO, "cannot read %s: %s", path, strerror(errno));
    char *buf = NULL;
    size_t len = 0, k;
    FILE *m = open_memstream(&buf, &len);
    char chunk[65536];
    int st = m ? AA_OK : aa_fail(AA_ENOMEM, "out of memory reading %s", path);
    while (!st && (k = fread(chunk, 1, sizeof chunk, f)) > 0)
        if (fwrite(chunk, 1, k, m) != k || ftell(m) > (long)MANIFEST_MAX)
            st = aa_fail(AA_EINVAL, "%s: too large for a manifest", path);
    if (!st && ferror(f))
        st = aa_fail(AA_EIO, "cannot read %s", path);
    fclose(f);
    if (m && fclose(m) != 0 && !st)
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
    if (st)
        free(buf);
    else
        *out = buf;
    return st;
}

int aa_manifest_read(const char *path, aa_manifest *m)
{
    memset(m, 0, sizeof *m);
    char *text;
    int st = read_text(path, &text);
    if (st)
        return st;
    cJSON *o = cJSON_Parse(text);
    free(text);
    if (!cJSON_IsObject(o)) {
        cJSON_Delete(o);
        return aa_fail(AA_EINVAL, "%s is not a run's manifest (not a JSON object)", path);
    }
    const cJSON *cmd = cJSON_GetObjectItemCaseSensitive(o, "command");
    const cJSON *sel = cJSON_GetObjectItemCaseSensitive(o, "selected");
    const cJSON *v;
    static const char *const strings[] = {"suite", "commit", "host"};
    char *dst[] = {m->suite, m->commit, m->host};
    size_t cap[] = {sizeof m->suite, sizeof m->commit, sizeof m->host};
    if (!cJSON_IsArray(cmd)) {
        st = bad(path, "command", "is missing or not an array");
        goto done;
    }
    for (int k = 0; k < 3; k++) {
        v = cJSON_GetObjectItemCaseSensitive(o, strings[k]);
        if (!cJSON_IsString(v) || strlen(v->valuestring) >= cap[k]) {
            st = bad(path, strings[k], "is missing, not a string or too long");
            goto done;
        }
        snprintf(dst[k], cap[k], "%s", v->valuestring);
    }
    v = cJSON_GetObjectItemCaseSensitive(o, "dirty");
    m->dirty = cJSON_IsBool(v) ? cJSON_IsTrue(v) : -1;
    v = cJSON_GetObjectItemCaseSensitive(o, "shards");
    if (!whole(v, 1, AA_SHARD_MAX)) {
        st = bad(path, "shards", "is missing or not a count of shards");
        goto done;
    }
    m->shards = (int)v->valuedouble;
    v = cJSON_GetObjectItemCaseSensitive(o, "shard");
    if (!whole(v, 1, m->shards)) {
        st = bad(path, "shard", "is missing or not between 1 and the shards");
        goto done;
    }
    m->shard = (int)v->valuedouble;
    v = cJSON_GetObjectItemCaseSensitive(o, "cases");
    if (!whole(v, 0, 1e12)) {
        st = bad(path, "cases", "is missing or not a count");
        goto done;
    }
    m->cases = (size_t)v->valuedouble;
    if (!cJSON_IsArray(sel)) {
        st = bad(path, "selected", "is missing or not an array");
        goto done;
    }
    int nc = cJSON_GetArraySize(cmd), ns = cJSON_GetArraySize(sel);
    m->argv = calloc((size_t)nc + 1, sizeof *m->argv);
    m->selected = calloc(ns ? (size_t)ns : 1, sizeof *m->selected);
    if (!m->argv || !m->selected) {
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    cJSON_ArrayForEach(v, cmd)
    {
        if (!cJSON_IsString(v)) {
            st = bad(path, "command", "holds something other than strings");
            goto done;
        }
        if (!(m->argv[m->argc] = strdup(v->valuestring))) {
            st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
            goto done;
        }
        m->argc++;
    }
    cJSON_ArrayForEach(v, sel)
    {
        if (!whole(v, 0, (double)m->cases - 1)) {
            st = bad(path, "selected", "holds something other than a case of the run");
            goto done;
        }
        m->selected[m->nselected++] = (size_t)v->valuedouble;
    }
    /* refused: absent before the run's end */
    const cJSON *ref = cJSON_GetObjectItemCaseSensitive(o, "refused");
    if (ref && !cJSON_IsArray(ref)) {
        st = bad(path, "refused", "is not an array");
        goto done;
    }
    int nr = ref ? cJSON_GetArraySize(ref) : 0;
    if (!(m->refused = calloc(nr ? (size_t)nr : 1, sizeof *m->refused))) {
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    if (ref)
        cJSON_ArrayForEach(v, ref)
        {
            if (!whole(v, 0, (double)m->cases - 1)) {
                st = bad(path, "refused", "holds something other than a case of the run");
                goto done;
            }
            m->refused[m->nrefused++] = (size_t)v->valuedouble;
        }
    v = cJSON_GetObjectItemCaseSensitive(o, "context");
    if (cJSON_IsObject(v) && !(m->context = cJSON_Print(v))) {
        st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
        goto done;
    }
    /* inputs: absent for a run that reads no files (and in older ones) */
    v = cJSON_GetObjectItemCaseSensitive(o, "inputs");
    if (v) {
        const cJSON *x;
        if (!cJSON_IsObject(v)) {
            st = bad(path, "inputs", "is not an object");
            goto done;
        }
        int nin = cJSON_GetArraySize(v);
        if (!(m->inputs = calloc(nin ? (size_t)nin : 1, sizeof *m->inputs))) {
            st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
            goto done;
        }
        cJSON_ArrayForEach(x, v)
        {
            if (!cJSON_IsString(x) || !x->string ||
                (strncmp(x->string, "pattern ", 8) && strncmp(x->string, "method ", 7))) {
                st = bad(path, "inputs", "holds something other than a pattern's or a method's "
                                         "files");
                goto done;
            }
            struct aa_manifest_input *in = &m->inputs[m->ninputs];
            in->what = strdup(x->string);
            in->inputs = strdup(x->valuestring);
            m->ninputs++;
            if (!in->what || !in->inputs) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
                goto done;
            }
        }
    }
    /* checksums: absent before the run's end */
    v = cJSON_GetObjectItemCaseSensitive(o, "checksums");
    if (v) {
        const cJSON *x;
        if (!cJSON_IsObject(v)) {
            st = bad(path, "checksums", "is not an object");
            goto done;
        }
        int nsum = cJSON_GetArraySize(v);
        if (!(m->sums = calloc(nsum ? (size_t)nsum : 1, sizeof *m->sums))) {
            st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
            goto done;
        }
        m->summed = 1;
        cJSON_ArrayForEach(x, v)
        {
            if (!cJSON_IsString(x) || strlen(x->valuestring) >= sizeof m->sums->sum ||
                !x->string || !*x->string || strstr(x->string, "..")) {
                st = bad(path, "checksums", "holds something other than a file's checksum");
                goto done;
            }
            if (!(m->sums[m->nsums].name = strdup(x->string))) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", path);
                goto done;
            }
            snprintf(m->sums[m->nsums].sum, sizeof m->sums->sum, "%s", x->valuestring);
            m->nsums++;
        }
    }
done:
    cJSON_Delete(o);
    if (st)
        aa_manifest_free(m);
    return st;
}

void aa_manifest_free(aa_manifest *m)
{
    for (int k = 0; m->argv && k < m->argc; k++)
        free(m->argv[k]);
    free(m->argv);
    free(m->selected);
    free(m->refused);
    free(m->context);
    for (size_t k = 0; m->sums && k < m->nsums; k++)
        free(m->sums[k].name);
    free(m->sums);
    for (size_t k = 0; m->inputs && k < m->ninputs; k++) {
        free(m->inputs[k].what);
        free(m->inputs[k].inputs);
    }
    free(m->inputs);
    memset(m, 0, sizeof *m);
}
