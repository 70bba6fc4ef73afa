/*
 * area_composite.c: the `area` method's colours in scenes that composite
 * (translucent layers, groups of opacity, clips; area.c, "Translucent
 * layers, groups of opacity, clips"): the scene's own composite of a
 * winding state, cached per worker; and Catmull's recursive pixel
 * integrater for them, which splits on every edge.  A file of its own, so
 * that the opaque scenes' integrater (area_catmull.c) is compiled as it
 * always was.
 */
#include "area_pixel.h"

#include <string.h>

/* The colour of winding state w in a scene with translucent layers, groups
 * of opacity or clips: the scene's own composite (aa_scene_colour_of, the
 * function the reference colours its regions by), which depends on w only
 * through the set of layers whose fill rule holds.  That set is the key of
 * the worker's cache; a miss composites and keeps the colour (a full cache
 * is emptied first: the colours handed out are copies in the ring, so no
 * pointer held by a caller is into the cache). */
const double *area_composite_colour(const ar_state *S, ar_worker *wk, const int *w)
{
    const size_t nw = (size_t)S->nwords;
    uint64_t *key = wk->key, h = 0;
    memset(key, 0, nw * sizeof *key);
    for (int l = 0; l < S->nl; l++)
        if (S->evenodd[l] ? (w[l] & 1) : (w[l] != 0))
            key[l >> 6] |= (uint64_t)1 << (l & 63);
    for (size_t k = 0; k < nw; k++)
        h = aa_hash64(h ^ key[k]) + k;
    size_t at = (size_t)h & (AR_CACHE_SLOTS - 1);
    const double *c = NULL;
    for (int32_t e; (e = wk->cslot[at]) >= 0; at = (at + 1) & (AR_CACHE_SLOTS - 1))
        if (!memcmp(wk->ckey + (size_t)e * nw, key, nw * sizeof *key)) {
            c = wk->ccol[e];
            break;
        }
    if (!c) {
        if (wk->cn == AR_CACHE_ENTRIES) {
            for (size_t k = 0; k < AR_CACHE_SLOTS; k++)
                wk->cslot[k] = -1;
            wk->cn = 0;
            at = (size_t)h & (AR_CACHE_SLOTS - 1);
        }
        int32_t e = (int32_t)wk->cn++;
        memcpy(wk->ckey + (size_t)e * nw, key, nw * sizeof *key);
        aa_rgb rgb = aa_scene_colour_of(S->scene, w);
        memcpy(wk->ccol[e], rgb.c, sizeof rgb.c);
        wk->cslot[at] = e;
        c = wk->ccol[e];
    }
    double *out = wk->ring[wk->ringn];
    wk->ringn = (wk->ringn + 1) % AR_RING;
    out[0] = c[0], out[1] = c[1], out[2] = c[2];
    return out;
}

/* A region of a compositing scene (cm_split_all): its colour is the
 * scene's composite of the covering layers. */
static void leaf_all(const ar_row *r, const cm_level *lv, double area, const int *wind, int i,
                     double *sum)
{
    (void)lv, (void)i;
    const double *c = colour_of(r->S, r->wk, wind);
    for (int ch = 0; ch < 3; ch++)
        sum[ch] += c[ch] * area;
}

static void cm_integrate_all(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                             int d, double *sum)
{
    cm_split_all(r, in, n, w, i, d, sum, leaf_all);
}

int area_cluster_catmull_all(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                             const int *w)
{
    return cm_cluster(r, in, n, lo, hi, w, cm_integrate_all);
}
