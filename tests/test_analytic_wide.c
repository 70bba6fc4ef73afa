/*
 * test_analytic_wide.c: `analytic` on elliptical arcs under filters wider
 * than a pixel and a half, where the window of the visible parts
 * (algorithms/visible.c) takes in pairs of arcs that leave a common end
 * point tangent to each other: arcs.svg's crescent (the upper halves of a
 * circle and of an ellipse on one diameter) at 20 x 20 under tent:r=2.3,
 * which took minutes in aa_piece_meet (harness/core/scene_piece.c,
 * near_shared_end), under bspline:order=3 and mitchell, and at 64 x 64.
 *
 * Known answer, not the method's own: the exact reference of the
 * harness's separate truth path (aa_truth_render, its own quadrature of
 * the filter over the scene's rows), within 1e-12 per pixel and channel,
 * at 1 and 2 threads (bit-identical).  The meeting itself is checked in
 * tests/test_scene_conic.c (test_crescent_meetings: none inside any band,
 * from the two ellipses' equations).
 */
#include "bench.h"
#include "scenes.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

/* analytic within 1e-12 of the reference on s at n x n under filter f, at
 * 1 and 2 threads. */
static void against(const char *what, const aa_scene *s, int n, const char *f)
{
    support_method_against_reference("analytic", what, s, n, n, f);
}

static void test_arcs_wide(void **state)
{
    (void)state;
    const char *const flist[] = {"tent:r=2.3", "bspline:order=3", "mitchell", NULL};
    aa_scene *s = scenes_svg_at("arcs", 20);
    for (const char *const *f = flist; *f; f++)
        against("arcs.svg", s, 20, *f);
    aa_scene_free(s);
    s = scenes_svg_at("arcs", 64);
    against("arcs.svg", s, 64, "tent:r=2.3");
    aa_scene_free(s);
}

SUPPORT_MAIN(NULL, NULL, cmocka_unit_test(test_arcs_wide))
