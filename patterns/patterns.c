/*
 * patterns.c: the table of pattern types, and building a pattern's scene.
 *
 * Adding a pattern is one file defining an aa_pattern_type plus one line
 * here; the tests loop over this table, so every pattern meets every
 * generic property.
 */
#include "patterns.h"

#include <stdlib.h>

const aa_pattern_type *const aa_pattern_types[] = {
    &aa_pattern_crow,
    &aa_pattern_catmull,
    &aa_pattern_slivers,
    &aa_pattern_star,
    &aa_pattern_feibush,
    &aa_pattern_fence,
    &aa_pattern_dots,
    &aa_pattern_rings,
    &aa_pattern_strokes,
    &aa_pattern_zoneplate,
    &aa_pattern_svg,
    &aa_pattern_text,
    NULL};

/* The patterns drawn at the view's size, and what they add to cache keys. */
static const struct {
    const aa_pattern_type *type;
    int (*build_at)(const double *p, int w, int h, aa_scene *s);
    int (*key)(const double *p, char *buf, size_t len);
    int (*own_size)(const double *p, int *w, int *h); /* NULL: none */
} sized[] = {{&aa_pattern_svg, aa__svg_build_at, aa__svg_key, aa__svg_own_size},
             {&aa_pattern_text, aa__text_build_at, aa__text_key, NULL}};

static int sized_index(const aa_spec *spec)
{
    for (size_t k = 0; k < sizeof sized / sizeof sized[0]; k++)
        if (spec->info == &sized[k].type->info)
            return (int)k;
    return -1;
}

int aa_pattern_sized(const aa_spec *spec) { return sized_index(spec) >= 0; }

int aa_pattern_has_own_size(const aa_spec *spec)
{
    int k = sized_index(spec);
    return k >= 0 && sized[k].own_size != NULL;
}

int aa_pattern_own_size(const aa_spec *spec, int *w, int *h)
{
    int k = sized_index(spec);
    if (k < 0 || !sized[k].own_size)
        return aa_fail(AA_EINVAL, "pattern %s has no size of its own: give the image's size "
                                  "(-s WxH)",
                       spec->info->name);
    return sized[k].own_size(spec->v, w, h);
}

int aa_pattern_key(const aa_spec *spec, char *buf, size_t len)
{
    int k = sized_index(spec);
    if (len)
        buf[0] = '\0';
    return k < 0 || !sized[k].key ? AA_OK : sized[k].key(spec->v, buf, len);
}

int aa_pattern_parse(const char *text, aa_spec *out)
{
    int st = aa_spec_parse(text, (const void *const *)aa_pattern_types, "pattern", out);
    if (st)
        return st;
    const aa_pattern_type *type = (const aa_pattern_type *)out->info;
    return type->check ? type->check(out->v) : AA_OK;
}

int aa_pattern_scene(const aa_spec *spec, aa_scene **out)
{
    return aa_pattern_scene_at(spec, 0, 0, out);
}

int aa_pattern_scene_at(const aa_spec *spec, int w, int h, aa_scene **out)
{
    const aa_pattern_type *type = (const aa_pattern_type *)spec->info;
    *out = NULL;
    int st = type->check ? type->check(spec->v) : AA_OK;
    if (st)
        return st;
    aa_scene *s = aa_scene_new(type->background);
    if (!s)
        return aa_fail(AA_ENOMEM, "out of memory for pattern %s", type->info.name);
    int k = sized_index(spec);
    if (k >= 0 && (w < 1 || h < 1))
        st = type->build(spec->v, s); /* refuses: no size */
    else if (k >= 0)
        st = sized[k].build_at(spec->v, w, h, s);
    else
        st = type->build(spec->v, s);
    if (st || (st = aa_scene_clip_unit(s)) ||
        (st = aa_scene_finish(s))) {
        aa_scene_free(s);
        return aa_fail_context(st, "pattern %s", type->info.name);
    }
    *out = s;
    return AA_OK;
}
