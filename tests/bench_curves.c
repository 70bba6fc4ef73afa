/*
 * bench_curves.c: speed of `area` against `point` on scenes of curved
 * edges (`make bench`): crow's parabolas, cubic arcs and elliptical arcs.
 *
 * Scenes, W x H (default 1024x1024), box filter:
 *  - crow: the pattern (96 parabolic arcs);
 *  - crow as cubics: the same curves, each arc raised to a cubic (controls
 *    P0 + 2/3 (C - P0), P1 + 2/3 (C - P1)): the same image, cubic pieces;
 *  - waves: 48 white stripes whose sides are S-shaped cubics from top to
 *    bottom (two turning points in x each), black between;
 *  - rings: 200 concentric circles in one even-odd layer, radii 0.002 to
 *    0.45 of the image (alternate white and black rings);
 *  - disks: a grid of 16 x 16 disks, radius 0.4 of their cell, each a
 *    circle of two half arcs;
 *  - ellipses: 64 ellipses turned by 0 to 180 degrees, overlapping, in
 *    one nonzero layer (pieces that cross).
 * For each, the median render time of `point` and `area` with one thread,
 * the two taking turns (aa_timing_measure: after a warm-up, exactly --reps
 * renders each, or with --reps 0 (the default) until both medians' 95% CIs
 * are within --target-ci PCT, default 2, or --budget S per method has
 * passed, default 1), and their ratio.  A noisy timing is marked *.
 * --scenes cubic|conic|all picks the scenes (crow is in every set, for
 * comparison).  Figures are read, not asserted.
 *
 * usage: bench_curves [-s WxH] [-t THREADS] [--reps N] [--target-ci PCT]
 *                     [--budget S] [--scenes cubic|conic|all]
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The scene finished when st is AA_OK; else freed, NULL. */
static aa_scene *finished(aa_scene *s, int st)
{
    if (!st)
        st = aa_scene_finish(s);
    if (st) {
        aa_scene_free(s);
        return NULL;
    }
    return s;
}

static aa_scene *elevated(const aa_scene *src)
{
    aa_scene *s = aa_scene_new(aa_scene_background(src));
    size_t ne, nc;
    const aa_edge *e = aa_scene_edges(src, &ne);
    const size_t *start = aa_scene_contours(src, &nc);
    int st = s ? AA_OK : AA_ENOMEM;
    for (int l = 0; l < aa_scene_layer_count(src) && !st; l++) {
        st = aa_scene_layer(s, aa_scene_layer_colour(src, l), aa_scene_layer_rule(src, l));
        for (size_t c = 0; c < nc && !st; c++) {
            if (start[c] == start[c + 1] || e[start[c]].layer != l)
                continue;
            st = aa_scene_move_to(s, e[start[c]].x0, e[start[c]].y0);
            for (size_t k = start[c]; k < start[c + 1] && !st; k++) {
                const aa_edge *d = &e[k];
                st = d->quad ? aa_scene_cubic_to(s, d->x0 + 2.0 / 3.0 * (d->cx - d->x0),
                                                 d->y0 + 2.0 / 3.0 * (d->cy - d->y0),
                                                 d->x1 + 2.0 / 3.0 * (d->cx - d->x1),
                                                 d->y1 + 2.0 / 3.0 * (d->cy - d->y1), d->x1,
                                                 d->y1)
                             : aa_scene_line_to(s, d->x1, d->y1);
            }
            if (!st)
                st = aa_scene_close(s);
        }
    }
    return finished(s, st);
}

static aa_scene *waves(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    int st = s ? aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) : AA_ENOMEM;
    for (int k = 0; k < 48 && !st; k++) {
        double x = (k + 0.25) / 48.0, w = 0.5 / 48.0, a = 0.03 + 0.0005 * k;
        if ((st = aa_scene_move_to(s, x, 0.0)) ||
            (st = aa_scene_cubic_to(s, x + a, 1.0 / 3.0, x - a, 2.0 / 3.0, x, 1.0)) ||
            (st = aa_scene_line_to(s, x + w, 1.0)) ||
            (st = aa_scene_cubic_to(s, x + w - a, 2.0 / 3.0, x + w + a, 1.0 / 3.0, x + w, 0.0)))
            break;
        st = aa_scene_close(s);
    }
    return finished(s, st);
}

/* The closed ellipse of centre c and semi-diameters u, v: two half arcs. */
static int ellipse(aa_scene *s, double cx, double cy, double ux, double uy, double vx, double vy)
{
    int st;
    if ((st = aa_scene_move_to(s, cx + ux, cy + uy)) ||
        (st = aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, 0.0, M_PI, cx - ux, cy - uy)) ||
        (st = aa_scene_arc_to(s, cx, cy, ux, uy, vx, vy, M_PI, 2.0 * M_PI, cx + ux, cy + uy)))
        return st;
    return aa_scene_close(s);
}

static aa_scene *rings(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    int st = s ? aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_EVENODD) : AA_ENOMEM;
    for (int k = 0; k < 200 && !st; k++) {
        double r = 0.002 + (0.45 - 0.002) * k / 199.0;
        st = ellipse(s, 0.5, 0.5, r, 0.0, 0.0, r);
    }
    return finished(s, st);
}

static aa_scene *disks(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    int st = s ? aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) : AA_ENOMEM;
    for (int k = 0; k < 256 && !st; k++) {
        double cell = 1.0 / 16.0, r = 0.4 * cell;
        st = ellipse(s, (k % 16 + 0.5) * cell, (k / 16 + 0.5) * cell, r, 0.0, 0.0, r);
    }
    return finished(s, st);
}

static aa_scene *ellipses(void)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    int st = s ? aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) : AA_ENOMEM;
    for (int k = 0; k < 64 && !st; k++) {
        double a = M_PI * k / 64.0, c = cos(a), sn = sin(a);
        double cx = 0.5 + 0.2 * cos(3.0 * a), cy = 0.5 + 0.2 * sin(2.0 * a);
        st = ellipse(s, cx, cy, 0.2 * c, 0.2 * sn, -0.05 * sn, 0.05 * c);
    }
    return finished(s, st);
}

typedef struct timed {
    aa_method m;
    const aa_job *job;
    aa_image out;
    aa_counters c;
} timed;

static int render_once(void *ctx)
{
    timed *t = ctx;
    return aa_method_render(&t->m, t->job, &t->out, &t->c);
}

/* point and area timed taking turns (aa_timing_measure), so that a load
 * that comes and goes falls on both alike. */
static int time_pair(const aa_scene *scene, int w, int h, int threads,
                     const aa_timing_plan *plan, double median[2], int noisy[2])
{
    const char *names[2] = {"point", "area"};
    aa_filter f;
    aa_job job;
    timed t[2];
    memset(t, 0, sizeof t);
    int st = aa_filter_parse("box", &f);
    if (st || (st = aa_job_init(&job, scene, w, h, 0.0, 0.0, 0.0, &f, 1, threads)))
        return st;
    for (int k = 0; k < 2 && !st; k++) {
        aa_spec spec;
        t[k].job = &job;
        if (!(st = aa_method_parse(names[k], &f, &spec)) &&
            !(st = aa_method_init(&t[k].m, &spec, &job)))
            st = aa_image_alloc(&t[k].out, w, h, 3);
    }
    if (!st) {
        aa_timed_fn const fn[2] = {render_once, render_once};
        void *const ctx[2] = {&t[0], &t[1]};
        const int th[2] = {threads, threads};
        aa_timing tm[2];
        st = aa_timing_measure(plan, 2, fn, ctx, th, tm);
        for (int k = 0; k < 2; k++) {
            median[k] = tm[k].stats.median;
            noisy[k] = tm[k].noisy != 0;
        }
    }
    for (int k = 0; k < 2; k++) {
        if (t[k].m.type)
            aa_method_free(&t[k].m);
        aa_image_free(&t[k].out);
    }
    aa_job_free(&job);
    return st;
}

int main(int argc, char **argv)
{
    /* statically linked: register the built-in methods (core.h) */
    if (aa_method_add_builtin()) {
        fprintf(stderr, "%s\n", aa_last_error());
        return 1;
    }
    int w = 1024, h = 1024, threads = 1, cubic = 1, conic = 1;
    aa_timing_plan plan = {0, 0.0, 0.0};
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "-s") && k + 1 < argc && sscanf(argv[k + 1], "%dx%d", &w, &h) == 2)
            k++;
        else if (!strcmp(argv[k], "-t") && k + 1 < argc)
            threads = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--reps") && k + 1 < argc)
            plan.reps = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--target-ci") && k + 1 < argc)
            plan.target_ci = atof(argv[++k]) / 100.0;
        else if (!strcmp(argv[k], "--budget") && k + 1 < argc)
            plan.budget = atof(argv[++k]);
        else if (!strcmp(argv[k], "--scenes") && k + 1 < argc) {
            const char *v = argv[++k];
            cubic = !strcmp(v, "cubic") || !strcmp(v, "all");
            conic = !strcmp(v, "conic") || !strcmp(v, "all");
            if (!cubic && !conic) {
                fprintf(stderr, "bench_curves: --scenes takes cubic, conic or all, not '%s'\n", v);
                return 2;
            }
        } else {
            fprintf(stderr, "usage: bench_curves [-s WxH] [-t THREADS] [--reps N] "
                            "[--target-ci PCT] [--budget S] [--scenes cubic|conic|all]\n");
            return 2;
        }
    }
    if (w < 1 || h < 1 || threads < 1 || plan.reps < 0 || plan.target_ci < 0 || plan.budget < 0) {
        fprintf(stderr, "bench_curves: bad size, thread count, repetitions, target or budget\n");
        return 2;
    }
    aa_spec crow_spec;
    aa_scene *crow = NULL;
    if (aa_pattern_parse("crow", &crow_spec) || aa_pattern_scene(&crow_spec, &crow)) {
        fprintf(stderr, "bench_curves: %s\n", aa_last_error());
        return 3;
    }
    enum { N = 6 };
    aa_scene *scenes[N] = {crow,
                           cubic ? elevated(crow) : NULL,
                           cubic ? waves() : NULL,
                           conic ? rings() : NULL,
                           conic ? disks() : NULL,
                           conic ? ellipses() : NULL};
    const char *names[N] = {"crow (parabolas)",
                            "crow as cubics",
                            "waves (48 stripes of cubics)",
                            "rings (200 circles, even-odd)",
                            "disks (16 x 16)",
                            "ellipses (64 turned, crossing)"};
    const int wanted[N] = {1, cubic, cubic, conic, conic, conic};
    int status = 0;
    for (int k = 1; k < N; k++)
        if (wanted[k] && !scenes[k]) {
            fprintf(stderr, "bench_curves: %s: %s\n", names[k], aa_last_error());
            status = 3;
        }
    if (!status) {
        printf("%dx%d box, %d thread%s; medians of %s\n", w, h, threads, threads > 1 ? "s" : "",
               plan.reps ? "a fixed count" : "renders by precision");
        printf("%-32s %12s %12s %10s\n", "scene", "point ms", "area ms", "area/point");
    }
    for (int k = 0; k < N && !status; k++) {
        double med[2];
        int noisy[2];
        if (!wanted[k])
            continue;
        if (time_pair(scenes[k], w, h, threads, &plan, med, noisy)) {
            fprintf(stderr, "bench_curves: %s: %s\n", names[k], aa_last_error());
            status = 3;
            break;
        }
        printf("%-32s %11.3f%s %11.3f%s %10.2f\n", names[k], 1e3 * med[0], noisy[0] ? "*" : " ",
               1e3 * med[1], noisy[1] ? "*" : " ", med[1] / med[0]);
    }
    for (int k = 0; k < N; k++)
        aa_scene_free(scenes[k]);
    return status;
}
