/*
 * bench_conic.c: speed of `area` against `point` on scenes of elliptical
 * arcs (conic pieces, aa_scene_arc_to), beside the same on crow's parabolas
 * (`make bench`; tests/bench_cubic.c is its model).
 *
 * Scenes, W x H (default 1024x1024), box filter:
 *  - crow: the pattern (96 parabolic arcs), for comparison;
 *  - rings: 200 concentric circles in one even-odd layer, radii 0.002 to
 *    0.45 of the image (alternate white and black rings);
 *  - disks: a grid of 16 x 16 disks, radius 0.4 of their cell, each a
 *    circle of two half arcs;
 *  - ellipses: 64 ellipses turned by 0 to 180 degrees, overlapping, in
 *    one nonzero layer (pieces that cross).
 * For each, the median render time of `point` and `area` with one thread,
 * the two taking turns, exactly --reps renders each (default 5; 0: until
 * both medians' 95% CIs are within 2% or 1 s per method has passed), and
 * their ratio.  Figures are read, not asserted.
 *
 * usage: bench_conic [-s WxH] [-t THREADS] [--reps N]
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

/* point and area timed taking turns (aa_timing_measure). */
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
    int w = 1024, h = 1024, threads = 1;
    aa_timing_plan plan = {5, 0.0, 0.0};
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "-s") && k + 1 < argc && sscanf(argv[k + 1], "%dx%d", &w, &h) == 2)
            k++;
        else if (!strcmp(argv[k], "-t") && k + 1 < argc)
            threads = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--reps") && k + 1 < argc)
            plan.reps = atoi(argv[++k]);
        else {
            fprintf(stderr, "usage: bench_conic [-s WxH] [-t THREADS] [--reps N]\n");
            return 2;
        }
    }
    if (w < 1 || h < 1 || threads < 1 || plan.reps < 0) {
        fprintf(stderr, "bench_conic: bad size, thread count or repetitions\n");
        return 2;
    }
    aa_spec crow_spec;
    aa_scene *crow = NULL;
    if (aa_pattern_parse("crow", &crow_spec) || aa_pattern_scene(&crow_spec, &crow)) {
        fprintf(stderr, "bench_conic: %s\n", aa_last_error());
        return 3;
    }
    aa_scene *scenes[4] = {crow, rings(), disks(), ellipses()};
    const char *names[4] = {"crow (parabolas)", "rings (200 circles, even-odd)",
                            "disks (16 x 16)", "ellipses (64 turned, crossing)"};
    for (int k = 1; k < 4; k++)
        if (!scenes[k]) {
            fprintf(stderr, "bench_conic: %s: %s\n", names[k], aa_last_error());
            return 3;
        }
    printf("%dx%d box, %d thread%s; medians of %s\n", w, h, threads, threads > 1 ? "s" : "",
           plan.reps ? "a fixed count" : "renders by precision");
    printf("%-32s %12s %12s %10s\n", "scene", "point ms", "area ms", "area/point");
    int status = 0;
    for (int k = 0; k < 4; k++) {
        double med[2];
        int noisy[2];
        if (time_pair(scenes[k], w, h, threads, &plan, med, noisy)) {
            fprintf(stderr, "bench_conic: %s: %s\n", names[k], aa_last_error());
            status = 3;
            break;
        }
        printf("%-32s %11.3f%s %11.3f%s %10.2f\n", names[k], 1e3 * med[0], noisy[0] ? "*" : " ",
               1e3 * med[1], noisy[1] ? "*" : " ", med[1] / med[0]);
    }
    for (int k = 0; k < 4; k++)
        aa_scene_free(scenes[k]);
    return status;
}
