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
    &aa_pattern_zoneplate,
    NULL};

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
    const aa_pattern_type *type = (const aa_pattern_type *)spec->info;
    *out = NULL;
    int st = type->check ? type->check(spec->v) : AA_OK;
    if (st)
        return st;
    aa_scene *s = aa_scene_new(type->background);
    if (!s)
        return aa_fail(AA_ENOMEM, "out of memory for pattern %s", type->info.name);
    if ((st = type->build(spec->v, s)) || (st = aa_scene_clip_unit(s)) ||
        (st = aa_scene_finish(s))) {
        aa_scene_free(s);
        return aa_fail_context(st, "pattern %s", type->info.name);
    }
    *out = s;
    return AA_OK;
}
