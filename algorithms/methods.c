/*
 * methods.c: the table of built-in method types, and their registration
 * into the core's method table (harness/core/method.c).
 *
 * Adding a method is one file defining an aa_method_type plus one line here
 * (or a plug-in: see aa_plugin_load).  The tests loop over this table, so
 * every method meets every generic property.  The core knows no method: this
 * file registers the table when the library starts, so the core links and
 * runs without the methods, and nothing below calls up into them.
 */
#include "methods.h"

const aa_method_type *const aa_method_types[] = {
    &aa_method_point,
    &aa_method_supersample,
    &aa_method_jitter,
    &aa_method_hexagon,
    &aa_method_trio,
    &aa_method_mlaa,
    &aa_method_fxaa,
    &aa_method_smaa,
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
    &aa_method_analytic,
    NULL};

/* Methods that need an optional program (external.c runs an SVG renderer):
 * not built in, since the generic tests render every built-in method; the
 * command adds them to the table at start (aa_method_add_optional). */
const aa_method_type *const aa_method_types_optional[] = {
    &aa_method_external,
    NULL};

int aa_method_add_builtin(void)
{
    static int done;
    if (done)
        return AA_OK;
    int st = aa_method_register(aa_method_types, "the built-in methods");
    done = !st;
    return st;
}

int aa_method_add_optional(void)
{
    int st = aa_method_add_builtin();
    if (st || !aa_method_types_optional[0] ||
        aa_table_find(aa_method_table(), aa_method_types_optional[0]->info.name))
        return st;
    return aa_method_register(aa_method_types_optional, "the optional methods");
}

/* At the library's start (the command, the tests' shared library, and any
 * program that links this file): the built-in methods before any plug-in's.
 * It cannot fail but by a defect the tests catch (test_methods); were it to,
 * the table would stay empty, aa_method_parse would refuse every method, and
 * a call of aa_method_add_builtin() would return the cause. */
__attribute__((constructor)) static void register_builtin(void)
{
    (void)aa_method_add_builtin();
}
