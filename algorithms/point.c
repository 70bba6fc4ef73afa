/*
 * point.c: point sampling, one sample at each pixel centre (Crow 1976,
 * ch. 2, fig. 2.10: "the test pattern synthesized on a 256 by 256 dot grid
 * using techniques similar to those of conventional hidden-surface
 * algorithms").
 *
 * Each row asks the scene for the sorted crossings of the line through the
 * pixel centres and fills the runs of centres between crossings with one
 * colour: the cost is one crossing query per row plus a store per pixel,
 * whatever the scene.  It is the baseline every method is compared with:
 * no prefilter, so edges staircase, detail finer than a pixel aliases into
 * moire, and objects between centres vanish.
 *
 * On a field scene (core.h, "Fields": the zone plate) there are no
 * crossings: each centre takes the field's value (aa_scene_colour_at).
 * With gradient paint each centre of a run takes its own colour
 * (aa_scene_colour_of_at).
 *
 * Limits: it has no filter; it is measured against the box reference and
 * refuses other filters.  A centre exactly on an edge takes the colour to
 * the edge's left (the scene's crossing rule).
 */
#include "core.h"
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const aa_param point_params[] = {{0}};

static int point_check(const double *p, const aa_filter *f)
{
    (void)p;
    if (!aa_filter_is_box(f))
        return aa_fail(AA_EINVAL, "point sampling has no prefilter; it is measured against "
                                  "the box reference (use -f box)");
    return AA_OK;
}

/* Fill pixels [i0, i1) of a row with colour c. */
static void fill(double *row, int i0, int i1, aa_rgb c)
{
    double *px = row + 3 * (size_t)i0;
    for (int i = i0; i < i1; i++, px += 3)
        px[0] = c.c[0], px[1] = c.c[1], px[2] = c.c[2];
}

/* Fill pixels [i0, i1) of row y with the colour of winding `wind`: one
 * colour, or with gradient paint each centre's own (aa_scene_colour_of_at). */
static void fill_at(const aa_scene *placed, const int *wind, double *row, int i0, int i1,
                    double dx, double y)
{
    if (!aa_scene_has_gradients(placed)) {
        fill(row, i0, i1, aa_scene_colour_of(placed, wind));
        return;
    }
    for (int i = i0; i < i1; i++)
        fill(row, i, i + 1, aa_scene_colour_of_at(placed, wind, i + 0.5 + dx, y));
}

/* The first pixel whose centre i + 1/2 lies strictly right of x. */
static int first_right_of(double x, int w)
{
    double i = floor(x - 0.5) + 1.0;
    return i < 0 ? 0 : (i > w ? w : (int)i);
}

int aa_point_ws_init(aa_point_ws *ws, const aa_scene *placed)
{
    size_t npieces;
    aa_scene_pieces(placed, &npieces);
    ws->nl = aa_scene_layer_count(placed);
    if (ws->nl < 1)
        ws->nl = 1;
    ws->cap = npieces + 1;
    ws->cross = malloc(ws->cap * sizeof *ws->cross);
    ws->wind = malloc((size_t)ws->nl * sizeof *ws->wind);
    if (!ws->cross || !ws->wind) {
        aa_point_ws_free(ws);
        return aa_fail(AA_ENOMEM, "out of memory for crossings");
    }
    return AA_OK;
}

void aa_point_ws_free(aa_point_ws *ws)
{
    free(ws->cross);
    free(ws->wind);
    ws->cross = NULL;
    ws->wind = NULL;
}

void aa_point_row(const aa_scene *placed, aa_point_ws *ws, double dx, double y, double *row,
                  int w)
{
    if (aa_scene_field(placed, NULL, NULL, NULL)) {
        /* a field: its point function at every centre */
        for (int i = 0; i < w; i++)
            fill(row, i, i + 1, aa_scene_colour_at(placed, i + 0.5 + dx, y));
        return;
    }
    size_t n = aa_scene_crossings(placed, y, ws->cross, ws->cap);
    memset(ws->wind, 0, (size_t)ws->nl * sizeof *ws->wind);
    int i = 0;
    for (size_t k = 0; k < n && i < w; k++) {
        /* centres up to and including x = crossing - dx keep the colour
         * left of the crossing */
        int stop = first_right_of(ws->cross[k].x - dx, w);
        if (stop > i) {
            fill_at(placed, ws->wind, row, i, stop, dx, y);
            i = stop;
        }
        ws->wind[ws->cross[k].layer] += ws->cross[k].dir;
    }
    fill_at(placed, ws->wind, row, i, w, dx, y);
}

int aa_point_sample(const aa_scene *placed, double dx, double dy, int threads, aa_image *out)
{
    int status = AA_OK;
#pragma omp parallel num_threads(threads > 0 ? threads : 1)
    {
        aa_point_ws ws;
        int st = aa_point_ws_init(&ws, placed);
#pragma omp for schedule(static)
        for (int j = 0; j < out->h; j++)
            if (!st)
                aa_point_row(placed, &ws, dx, j + 0.5 + dy, aa_pixel(out, 0, j), out->w);
        if (!st)
            aa_point_ws_free(&ws);
        else {
#pragma omp atomic write
            status = st;
        }
    }
    return status ? aa_fail(status, "out of memory for crossings") : AA_OK;
}

static int point_render(void *state, const double *p, const aa_job *job, aa_image *out,
                        aa_counters *counters)
{
    (void)state, (void)p;
    counters->samples = (uint64_t)job->w * (uint64_t)job->h;
    counters->expensive_pixels = 0;
    return aa_point_sample(job->placed, 0.0, 0.0, job->threads, out);
}

const aa_method_type aa_method_point = {
    {"point", "one sample at each pixel centre (Crow fig. 2.10)", point_params},
    0,
    AA_METHOD_FIELDS | AA_METHOD_GRADIENTS,
    point_check,
    NULL,
    point_render,
    NULL};
