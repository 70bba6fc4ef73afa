/*
 * peer.c: the checks and helpers the peer rasterizers share (peer.h).
 */
#include "peer.h"

int aa_peer_check_filter(const char *name, const aa_filter *f)
{
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL,
                       "%s computes box-filter coverage only: it is measured against the box "
                       "reference (use -f box; tent, gauss and cone are not supported)",
                       name);
    return AA_OK;
}

int aa_peer_scene_read(const char *name, const aa_job *job, aa_peer_scene *ps)
{
    const aa_scene *s = job->placed;
    if (!aa_scene_is_grey(s))
        return aa_fail(AA_EINVAL,
                       "%s renders one coverage channel: it accepts grey scenes only (every "
                       "colour with equal R, G and B), and this scene has colour",
                       name);
    int n = aa_scene_layer_count(s);
    if (n > 1)
        return aa_fail(AA_EINVAL,
                       "%s fills one layer: it accepts scenes of at most one layer, and this "
                       "scene has %d",
                       name, n);
    ps->layers = n;
    ps->bg = aa_scene_background(s).c[0];
    ps->fg = n ? aa_scene_layer_colour(s, 0).c[0] : ps->bg;
    ps->rule = n ? aa_scene_layer_rule(s, 0) : AA_FILL_NONZERO;
    return AA_OK;
}

void aa_peer_fill(aa_image *out, int j, int i0, int i1, double v)
{
    double *px = aa_pixel(out, 0, j) + 3 * (size_t)i0;
    for (int i = i0; i < i1; i++, px += 3)
        px[0] = px[1] = px[2] = v;
}
