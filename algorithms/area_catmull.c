/*
 * area_catmull.c: Catmull's recursive pixel integrater (Catmull 1978), the
 * `area` method's path for pixels where polygon edges cross or end.  The
 * pixel's region is split (Sutherland-Hodgman) by the line through an edge
 * of the front-most layer present, recursively on both sides, until a
 * region holds no edge of a visible layer; each region then adds its area
 * times the colour seen there.  Scenes that composite (translucent layers,
 * groups, clips), where no layer hides the edges behind it, take the form
 * in area_composite.c instead.
 */
#include "area_pixel.h"

/* Catmull's integrater on level d: add colour times area of its region. */
static void cm_integrate(const ar_row *r, const ar_key *in, size_t n, const int *w, int i,
                         int d, double *sum)
{
    const ar_state *S = r->S;
    cm_level *lv = &r->wk->cm[d];
    double cx, cy, area = cm_region(lv, &cx, &cy);
    if (area == 0.0)
        return;
    /* the front-most layer with an edge left in the region */
    int front = S->nl;
    const cm_edge *split = NULL;
    for (int k = 0; k < lv->ne; k++)
        if (lv->e[k].layer < front)
            front = lv->e[k].layer, split = &lv->e[k];
    int *wind = r->wk->wtmp;
    cm_winding(r, in, n, w, i, cx, cy, wind);
    /* layers in front of it have no edge here: each is all in or all out */
    for (int l = 0; l < front; l++)
        if (S->evenodd[l] ? (wind[l] & 1) : (wind[l] != 0)) {
            for (int ch = 0; ch < 3; ch++)
                sum[ch] += S->colour[l][ch] * area;
            return;
        }
    if (!split) {
        const double *c = S->colour[S->nl];
        for (int ch = 0; ch < 3; ch++)
            sum[ch] += c[ch] * area;
        return;
    }
    cm_split(lv, lv + 1, split, 1.0);
    cm_integrate(r, in, n, w, i, d + 1, sum);
    cm_split(lv, lv + 1, split, -1.0);
    cm_integrate(r, in, n, w, i, d + 1, sum);
}


/* Every pixel of the cluster by Catmull's integrater; 0 if a pixel has too
 * many edges for it (nothing written then). */
int area_cluster_catmull(const ar_row *r, const ar_key *in, size_t n, int lo, int hi,
                           const int *w)
{
    return cm_cluster(r, in, n, lo, hi, w, cm_integrate);
}
