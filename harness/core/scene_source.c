/*
 * scene_source.c: the stroke sources a scene keeps (path.h, "strokes in
 * the scene model"), carried through every operation on the scene, their
 * accessors, and the scene's hash.
 *
 * The sources are stored by ascending layer: layers are only ever added
 * with the next index, and clipping to the unit square shifts every layer
 * by one, so the order holds and a layer's source is found by bisection.
 * Nothing here calls path.c or stroke.c (scene.c calls this file, and
 * they call scene.c): a source's path is freed and copied by its arrays.
 */
#include "scene_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void source_free(aa_stroke_source *src)
{
    free(src->path.seg); /* the path's own storage (path.h): no call into path.c */
    src->path.seg = NULL;
    free((double *)src->style.dash);
    src->style.dash = NULL;
}

void aa__scene_strokes_free(aa_scene *s)
{
    for (size_t k = 0; k < s->nstrokes; k++)
        source_free(&s->strokes[k]);
    free(s->strokes);
    s->strokes = NULL;
    s->nstrokes = s->capstrokes = 0;
}

int aa__stroke_source_copy(aa_stroke_source *d, const aa_path *path, const aa_stroke_style *st,
                       const double m[6], int layer)
{
    memset(d, 0, sizeof *d);
    d->style = *st;
    d->style.dash = NULL;
    d->layer = layer;
    for (int k = 0; k < 6; k++)
        d->m[k] = m ? m[k] : (k == 0 || k == 3);
    if (path->n) {
        d->path.seg = malloc(path->n * sizeof *path->seg);
        if (!d->path.seg)
            return aa_fail(AA_ENOMEM, "out of memory for a stroke's path of %zu segments",
                           path->n);
        memcpy(d->path.seg, path->seg, path->n * sizeof *path->seg);
        d->path.n = d->path.cap = path->n;
    }
    d->path.penx = path->penx, d->path.peny = path->peny;
    d->path.startx = path->startx, d->path.starty = path->starty;
    d->path.open = path->open;
    if (st->dash && st->ndash) {
        double *dash = malloc(st->ndash * sizeof *dash);
        if (!dash) {
            free(d->path.seg);
            d->path.seg = NULL;
            d->path.n = d->path.cap = 0;
            return aa_fail(AA_ENOMEM, "out of memory for a stroke's %zu dashes", st->ndash);
        }
        memcpy(dash, st->dash, st->ndash * sizeof *dash);
        d->style.dash = dash;
    } else {
        d->style.ndash = 0;
    }
    return AA_OK;
}

int aa__scene_strokes_reserve(aa_scene *s, size_t need)
{
    if (need <= s->capstrokes)
        return AA_OK;
    size_t cap = s->capstrokes ? 2 * s->capstrokes : 8;
    while (cap < need)
        cap *= 2;
    aa_stroke_source *p = realloc(s->strokes, cap * sizeof *p);
    if (!p)
        return aa_fail(AA_ENOMEM, "out of memory for %zu stroke sources", need);
    s->strokes = p;
    s->capstrokes = cap;
    return AA_OK;
}

int aa__scene_strokes_copy(const aa_scene *s, aa_scene *t, double sx, double sy, double tx,
                           double ty)
{
    int st = aa__scene_strokes_reserve(t, s->nstrokes);
    for (size_t k = 0; k < s->nstrokes && !st; k++) {
        const aa_stroke_source *a = &s->strokes[k];
        /* (sx, sy, tx, ty) after a: its rows scaled, its offset moved */
        const double m[6] = {sx * a->m[0], sy * a->m[1], sx * a->m[2],
                             sy * a->m[3], sx * a->m[4] + tx, sy * a->m[5] + ty};
        for (int i = 0; i < 6 && !st; i++)
            if (!isfinite(m[i]))
                st = aa_fail(AA_EINVAL, "scene transform of a stroke's map overflows");
        if (!st && !(st = aa__stroke_source_copy(&t->strokes[t->nstrokes], &a->path,
                                                 &a->style, m, a->layer)))
            t->nstrokes++;
    }
    return st;
}

void aa__scene_strokes_shift(aa_scene *s, int by)
{
    for (size_t k = 0; k < s->nstrokes; k++)
        s->strokes[k].layer += by;
}

const aa_stroke_source *aa_scene_stroke_sources(const aa_scene *s, size_t *n)
{
    *n = s->nstrokes;
    return s->strokes;
}

int aa_scene_layer_stroked(const aa_scene *s, int layer)
{
    size_t lo = 0, hi = s->nstrokes;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (s->strokes[mid].layer < layer)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < s->nstrokes && s->strokes[lo].layer == layer ? (int)lo : -1;
}

/* ---- the hash ---- */

typedef struct hasher {
    unsigned long long h;
} hasher;

static void put_bytes(hasher *z, const void *data, size_t n)
{
    const unsigned char *b = data;
    for (size_t k = 0; k < n; k++) {
        z->h ^= b[k];
        z->h *= 1099511628211ull;
    }
}

/* Numbers by value, so padding never enters; -0 as 0 (the same geometry). */
static void put_double(hasher *z, double v)
{
    if (v == 0.0)
        v = 0.0;
    put_bytes(z, &v, sizeof v);
}

static void put_int(hasher *z, long long v) { put_bytes(z, &v, sizeof v); }

unsigned long long aa_scene_hash(const aa_scene *s)
{
    hasher z = {1469598103934665603ull};
    for (int k = 0; k < 3; k++)
        put_double(&z, s->background.c[k]);
    put_int(&z, s->nlayers);
    for (int l = 0; l < s->nlayers; l++) {
        for (int k = 0; k < 3; k++)
            put_double(&z, s->colour[l].c[k]);
        put_int(&z, s->rule[l]);
    }
    if (s->translucent) { /* opaque scenes keep the hash they always had */
        for (int l = 0; l < s->nlayers; l++) {
            put_double(&z, s->alpha[l]);
            put_int(&z, s->group[l]);
        }
        put_int(&z, s->ngroups);
        for (int g = 0; g < s->ngroups; g++) {
            put_int(&z, s->groups[g].parent);
            put_double(&z, s->groups[g].opacity);
        }
    }
    if (s->nclips) { /* unclipped scenes keep the hash they always had */
        put_int(&z, s->nclips);
        for (int c = 0; c < s->nclips; c++) {
            put_int(&z, s->clips[c].first);
            put_int(&z, s->clips[c].count);
            put_int(&z, s->clips[c].within);
        }
        for (int l = 0; l < s->nlayers; l++) {
            put_int(&z, s->gate[l]);
            put_int(&z, s->member[l]);
        }
    }
    put_int(&z, (long long)s->nedges);
    for (size_t k = 0; k < s->nedges; k++) {
        const aa_edge *e = &s->edges[k];
        const double v[14] = {e->x0, e->y0, e->cx, e->cy, e->x1, e->y1, e->c2x,
                              e->c2y, e->ux, e->uy, e->vx, e->vy, e->t0, e->t1};
        for (int i = 0; i < 14; i++)
            put_double(&z, v[i]);
        put_int(&z, e->quad);
        put_int(&z, e->layer);
        if (e->quad == 4 && e->oc.base != AA_OFFSET_CUBIC) {
            /* the offset curves of an ellipse (those of cubics were
             * hashed by their ends alone, and keep their hash) */
            put_int(&z, e->oc.base);
            put_int(&z, e->oc.evolute);
            put_double(&z, e->oc.d);
            for (int i = 0; i < 8; i++)
                put_double(&z, e->oc.b[i]);
            for (int i = 0; i < 6; i++)
                put_double(&z, e->oc.m[i]);
        }
    }
    put_int(&z, (long long)s->ncontours);
    for (size_t k = 0; k < s->ncontours; k++)
        put_int(&z, (long long)s->contour[k]);
    put_int(&z, (long long)s->nstrokes);
    for (size_t k = 0; k < s->nstrokes; k++) {
        const aa_stroke_source *a = &s->strokes[k];
        put_int(&z, a->layer);
        put_int(&z, (long long)a->path.n);
        for (size_t i = 0; i < a->path.n; i++) {
            put_int(&z, a->path.seg[i].op);
            for (int j = 0; j < 10; j++)
                put_double(&z, a->path.seg[i].p[j]);
        }
        put_double(&z, a->style.width);
        put_int(&z, a->style.join);
        put_int(&z, a->style.cap);
        put_double(&z, a->style.miterlimit);
        put_double(&z, a->style.dashoffset);
        put_int(&z, (long long)a->style.ndash);
        for (size_t i = 0; i < a->style.ndash; i++)
            put_double(&z, a->style.dash[i]);
        for (int i = 0; i < 6; i++)
            put_double(&z, a->m[i]);
    }
    if (s->field) {
        put_bytes(&z, s->field->name, strlen(s->field->name));
        put_int(&z, s->field->version);
        put_int(&z, s->fnparam);
        for (int k = 0; k < s->fnparam; k++)
            put_double(&z, s->fparam[k]);
        for (int k = 0; k < 4; k++)
            put_double(&z, s->fmap[k]);
    }
    return z.h;
}
