/*
 * methods.c: the table of built-in method types.
 *
 * Adding a method is one file defining an aa_method_type plus one line here
 * (or a plug-in: see aa_plugin_load).  The tests loop over this table, so
 * every method meets every generic property.
 */
#include "methods.h"

const aa_method_type *const aa_method_types[] = {
    &aa_method_point,
    &aa_method_supersample,
    &aa_method_jitter,
    &aa_method_hexagon,
    &aa_method_trio,
    &aa_method_area,
    &aa_method_taa,
    &aa_method_cycle,
    &aa_method_adaptive,
    &aa_method_freetype,
    &aa_method_stb,
    &aa_method_cairo,
    &aa_method_agg,
    &aa_method_crowtable,
    &aa_method_conetable,
    &aa_method_crowtiler,
    &aa_method_feibushtex,
    NULL};

/* Methods that need an optional program (external.c runs an SVG renderer):
 * not built in, since the generic tests render every built-in method; the
 * command adds them to the table at start (aa_method_add_optional). */
const aa_method_type *const aa_method_types_optional[] = {
    &aa_method_external,
    NULL};
