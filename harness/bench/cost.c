/*
 * cost.c: a case's cost, estimated before it runs, so that a case that
 * would run for minutes says so first.
 *
 * The estimate, in units of roughly a nanosecond's work, is
 *
 *     E = W H S + sum over rows r of C_r^2
 *
 * where S is the method's samples per pixel (its `spp`, or n^2 for its
 * `n`, else 1), and C_r the number of the placed scene's pieces (y-monotone
 * parts of edges, flat ones left out) that cross pixel row r: the first
 * term is the work of a method that evaluates the scene at S points of each
 * pixel, the second that of an exact one (and of the reference) that meets
 * every pair of pieces crossing a row.  It needs one pass over the pieces
 * and one over the rows.  Past AA_COST_LIMIT a run warns before the view's
 * reference and cases: feibush:stripes=65536 at 48x48 (E about 6e11; it
 * runs for minutes under area) does; crow at 1024x1024 under area (E about
 * 1e7, a second) does not.
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The method's samples per pixel: `spp`, n^2 for `n`, else 1. */
static double samples_per_pixel(const aa_spec *method)
{
    int k = aa_spec_index(method->info, "spp");
    if (k >= 0)
        return fmax(1.0, method->v[k]);
    if ((k = aa_spec_index(method->info, "n")) >= 0)
        return fmax(1.0, method->v[k] * method->v[k]);
    return 1.0;
}

double aa_case_estimate(const aa_scene *placed, int w, int h, const aa_spec *method)
{
    size_t n;
    const aa_piece *p = aa_scene_pieces(placed, &n);
    double *cross = h > 0 ? calloc((size_t)h + 1, sizeof *cross) : NULL;
    double rows = 0;
    if (cross) {
        /* +1 at the first row a piece crosses, -1 after its last */
        for (size_t k = 0; k < n; k++) {
            if (p[k].kind == AA_PIECE_FLAT || !(p[k].y1 > 0) || !(p[k].y0 < h))
                continue;
            long a = (long)floor(fmax(p[k].y0, 0.0)), b = (long)ceil(fmin(p[k].y1, (double)h));
            if (b <= a)
                continue;
            cross[a] += 1, cross[b] -= 1;
        }
        double c = 0;
        for (int r = 0; r < h; r++) {
            c += cross[r];
            rows += c * c;
        }
        free(cross);
    } else if (h > 0) {
        rows = (double)n * (double)n * h; /* no memory: every piece on every row */
    }
    return (double)w * h * samples_per_pixel(method) + rows;
}

void aa_case_estimate_warn(const aa_run_config *cfg, const aa_view *view, const aa_scene *scene,
                       size_t first)
{
    aa_scene *placed = aa_scene_place(scene, view->w, view->h, cfg->t, cfg->vx, cfg->vy);
    if (!placed)
        return;
    for (size_t im = 0; im < cfg->nmethods; im++) {
        if (cfg->only && !cfg->only[first + im])
            continue;
        double e = aa_case_estimate(placed, view->w, view->h, &cfg->methods[im].spec);
        if (e > AA_COST_LIMIT) {
            /* named as the run shows them: as given, else canonical */
            char p[256], m[256];
            const aa_run_spec *ps = &cfg->patterns[0], *ms = &cfg->methods[im];
            for (size_t k = 0; k < cfg->npatterns; k++)
                if (cfg->patterns[k].spec.info == view->pattern.info &&
                    !memcmp(cfg->patterns[k].spec.v, view->pattern.v, sizeof view->pattern.v))
                    ps = &cfg->patterns[k];
            if (ps->text)
                snprintf(p, sizeof p, "%s", ps->text);
            else if (aa_spec_format(&view->pattern, p, sizeof p))
                snprintf(p, sizeof p, "%s", view->pattern.info->name);
            if (ms->text)
                snprintf(m, sizeof m, "%s", ms->text);
            else if (aa_spec_format(&ms->spec, m, sizeof m))
                snprintf(m, sizeof m, "%s", ms->spec.info->name);
            aa_warn("%s on %s %dx%d: estimated cost %.2g, past the limit %.0g (W H samples "
                    "per pixel + the sum over rows of the pieces crossing each, squared): it "
                    "may run for minutes",
                    m, p, view->w, view->h, e, AA_COST_LIMIT);
        }
    }
    aa_scene_free(placed);
}
