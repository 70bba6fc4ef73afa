/*
 * bench_bezstroke.c: speed of strokes of Bezier arcs (`make bench`): the
 * stroker, the box reference of the stroke, `point`, `area` and
 * `analytic`, on a path of
 * 1,000 cubic segments (20 wavy subpaths of 50 smooth cubics across the
 * square, stroked 2.5 px wide at 1024 px with round joins and caps; some
 * segments tight enough that their offsets fold).
 *
 * Prints, for W x H (default 1024x1024) with one thread: the time to
 * stroke the path (median of 5), the number of pieces of the scene, the
 * box reference's time (median of -r REPS renders, default 3, after none
 * untimed: each is seconds long; -r 0: none; then the least and the most)
 * with its largest bound, and `point`'s, `area`'s and `analytic`'s (under
 * the box, and under each filter of -f, repeatable) medians of -n N
 * renders (default 11, after one untimed: the image's pages, the caches;
 * then the least and the most), area/point and analytic/area (analytic
 * under each filter against area under the box), the ratios of the
 * medians; each in wall-clock time and in the process's CPU time (`cpu`),
 * which other processes sharing the core lengthen far less.  `point` and
 * `area` render in turns, one each a round, the order alternating, and
 * area/point is also the median of the rounds' ratios (with the least and
 * the most): a change of load on the shared machine then falls on both
 * alike, where one method's renders all after the other's took it alone
 * (area/point 2.7 to 3.8 in three runs on one build).  Each method's init
 * (its tables for the scene and the size, outside the renders' times) is
 * timed too, five times, and area/point is also given for one init and
 * one render, what a scene drawn once costs.  Figures are read, not
 * asserted.

 * --renders N: no timing and no reference: `point` and `area` each render
 * the scene N times, for counting instructions (valgrind --tool=callgrind
 * with N = 1 and N = 3: point_render's and area_render's inclusive counts'
 * differences halved are one render's, without the set-up).
 *
 * --check: the box reference once and `area` once: the pixels where area
 * is farther from the reference than the reference's own bound, their
 * count and the largest excess (and where), the sum over the image of
 * |area - reference| (each pixel's largest over its channels; in brackets
 * over every channel), and a hash of area's image (FNV-1a of its doubles'
 * bits) to tell an unchanged image from a moved one.
 *
 * usage: bench_bezstroke [-s WxH] [-r REPS] [-n N] [-f FILTER]... [--renders N |
 *        --check]
 */
#include "bench.h"
#include "path.h"
#include "truth.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* the most timed renders a method (-n) */
#define TIMED_MAX 101

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* FNV-1a (64 bits) over the bytes of an image's samples */
static uint64_t image_hash(const aa_image *im)
{
    uint64_t hsh = 1469598103934665603u;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++) {
            const double *px = aa_pixel(im, i, j);
            for (int c = 0; c < im->c; c++) {
                uint64_t b;
                memcpy(&b, &px[c], sizeof b);
                for (int k = 0; k < 8; k++)
                    hsh = (hsh ^ ((b >> (8 * k)) & 0xff)) * 1099511628211u;
            }
        }
    return hsh;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The process's CPU time in seconds: on a shared machine the time taken
 * from the core, which other processes' turns on it do not lengthen as
 * they do the wall-clock time (NaN if unavailable). */
static double cpu_now(void)
{
    struct timespec t;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t))
        return NAN;
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* 20 subpaths of 50 cubics each: a wave across the square whose
 * amplitude and wavelength change from subpath to subpath; consecutive
 * cubics share tangents (smooth) but for every seventh (a corner). */
static int build(aa_path *p)
{
    int st = AA_OK;
    for (int r = 0; r < 20 && !st; r++) {
        double y = (r + 0.5) / 20.0, a = 0.004 + 0.0015 * r, dx = 0.9 / 50.0;
        double x = 0.05;
        st = aa_path_move_to(p, x, y);
        for (int k = 0; k < 50 && !st; k++) {
            double s = (k % 2 ? -1.0 : 1.0) * a * (1.0 + 0.5 * sin(0.7 * k + r));
            double kink = k % 7 == 6 ? 0.3 * dx : 0.0;
            st = aa_path_cubic_to(p, x + dx / 3.0 + kink, y + s, x + 2.0 * dx / 3.0, y + s,
                                  x + dx, y);
            x += dx;
        }
    }
    return st;
}

int main(int argc, char **argv)
{
    int w = 1024, h = 1024, reps = 3, nf = 1, renders = 0, check = 0, timed = 11;
    const char *filters[8] = {"box"};
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "-s") && k + 1 < argc && sscanf(argv[k + 1], "%dx%d", &w, &h) == 2)
            k++;
        else if (!strcmp(argv[k], "-r") && k + 1 < argc)
            reps = atoi(argv[++k]);
        else if (!strcmp(argv[k], "-n") && k + 1 < argc)
            timed = atoi(argv[++k]);
        else if (!strcmp(argv[k], "-f") && k + 1 < argc && nf < 8)
            filters[nf++] = argv[++k];
        else if (!strcmp(argv[k], "--renders") && k + 1 < argc)
            renders = atoi(argv[++k]);
        else if (!strcmp(argv[k], "--check"))
            check = 1;
        else {
            fprintf(stderr, "usage: bench_bezstroke [-s WxH] [-r REPS] [-n N] [-f FILTER]... "
                            "[--renders N | --check]\n");
            return 2;
        }
    }
    if (renders && check) {
        fprintf(stderr, "bench_bezstroke: --renders and --check exclude each other\n");
        return 2;
    }
    if (w < 1 || h < 1 || reps < 0 || reps > 100 || renders < 0 || timed < 1 ||
        timed > TIMED_MAX) {
        fprintf(stderr, "bench_bezstroke: bad size or repetitions\n");
        return 2;
    }
    if (aa_method_add_builtin()) {
        fprintf(stderr, "%s\n", aa_last_error());
        return 1;
    }
    aa_path path = {0}, out = {0};
    aa_stroke_style style;
    aa_stroke_style_default(&style);
    style.width = 2.5 / w;
    style.join = AA_JOIN_ROUND;
    style.cap = AA_CAP_ROUND;
    double t_stroke[5];
    int st = build(&path);
    for (int k = 0; k < 5 && !st; k++) {
        out.n = 0;
        double t0 = aa_now();
        st = aa_stroke_outline(&path, &style, &out);
        t_stroke[k] = aa_now() - t0;
    }
    aa_scene *s = st ? NULL : aa_scene_new((aa_rgb){{0, 0, 0}});
    if (!st && !s)
        st = AA_ENOMEM;
    if (!st && !(st = aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO)) &&
        !(st = aa_path_fill(&out, NULL, s)))
        st = aa_scene_finish(s);
    aa_scene *placed = st ? NULL : aa_scene_place(s, w, h, 0, 0, 0);
    if (st || !placed) {
        fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
        return 3;
    }
    size_t npieces, noff = 0;
    const aa_piece *pc = aa_scene_pieces(placed, &npieces);
    for (size_t k = 0; k < npieces; k++)
        noff += pc[k].kind == AA_PIECE_OFFSET;
    printf("%dx%d box, 1 thread: 1000 cubic segments stroked %.2f px wide, round joins and "
           "caps\n",
           w, h, style.width * w);
    printf("stroke outline      %10.3f ms (median of 5), %zu path segments\n",
           1e3 * median(t_stroke, 5), out.n);
    printf("scene               %zu pieces, %zu of them offset pieces\n", npieces, noff);
    aa_filter f;
    aa_image im, bound;
    if (aa_filter_parse("box", &f) || aa_image_alloc(&im, w, h, 3) ||
        aa_image_alloc(&bound, w, h, 1)) {
        fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
        return 3;
    }
    aa_job job;
    aa_spec spec;
    aa_method m;
    aa_counters c;
    if (renders || check) {
        /* point and area N times (--renders), or area once against the
         * reference (--check) */
        aa_image ref;
        if (check && (aa_image_alloc(&ref, w, h, 3) ||
                      aa_truth_render(placed, &f, 1, &ref, &bound, &(aa_truth_stats){0}))) {
            fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
            return 3;
        }
        for (int q = check; q < 2; q++) {
            const char *name = q ? "area" : "point";
            if (aa_job_init(&job, s, w, h, 0.0, 0.0, 0.0, &f, 1, 1) ||
                aa_method_parse(name, &f, &spec) || aa_method_init(&m, &spec, &job)) {
                fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
                return 3;
            }
            for (int k = 0; k < (check ? 1 : renders); k++)
                if (aa_method_render(&m, &job, &im, &c)) {
                    fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
                    return 3;
                }
            aa_method_free(&m);
            aa_job_free(&job);
            if (!check)
                printf("%-19s %d renders\n", name, renders);
        }
        if (check) {
            size_t beyond = 0;
            double most = 0.0, off = 0.0, sum = 0.0, sumc = 0.0;
            int wi = -1, wj = -1;
            for (int j = 0; j < h; j++)
                for (int i = 0; i < w; i++) {
                    double e = 0.0;
                    for (int ch = 0; ch < 3; ch++) {
                        double d = fabs(aa_pixel(&im, i, j)[ch] - aa_pixel(&ref, i, j)[ch]);
                        e = fmax(e, d);
                        sumc += d;
                    }
                    sum += e;
                    if (e > aa_pixel(&bound, i, j)[0]) {
                        beyond++;
                        off = fmax(off, e);
                        if (e - aa_pixel(&bound, i, j)[0] > most)
                            most = e - aa_pixel(&bound, i, j)[0], wi = i, wj = j;
                    }
                }
            printf("area against the box reference: %zu pixels beyond its bound, at most %.3g "
                   "off, at most %.3g beyond it (at (%d, %d)); sum of |area - reference| %.5g "
                   "(%.5g); area's image hash %016llx\n",
                   beyond, off, most, wi, wj, sum, sumc, (unsigned long long)image_hash(&im));
            aa_image_free(&ref);
        }
        aa_image_free(&im);
        aa_image_free(&bound);
        aa_scene_free(placed);
        aa_scene_free(s);
        aa_path_free(&path);
        aa_path_free(&out);
        return 0;
    }
    double t_ref[100], c_ref[100], worst = 0;
    aa_truth_stats stats;
    for (int k = 0; k < reps; k++) {
        double t0 = aa_now(), c0 = cpu_now();
        if (aa_truth_render(placed, &f, 1, &im, &bound, &stats)) {
            fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
            return 3;
        }
        t_ref[k] = aa_now() - t0;
        c_ref[k] = cpu_now() - c0;
    }
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            worst = fmax(worst, aa_pixel(&bound, i, j)[0]);
    if (reps) {
        double med = median(t_ref, reps), cmed = median(c_ref, reps); /* sorts them */
        printf("box reference       %10.3f ms (median of %d, %.3f .. %.3f), cpu %.3f ms (%.3f .. "
               "%.3f), largest bound %.1e\n",
               1e3 * med, reps, 1e3 * t_ref[0], 1e3 * t_ref[reps - 1], 1e3 * cmed,
               1e3 * c_ref[0], 1e3 * c_ref[reps - 1], worst);
    }
    /* point and area: each's init five times (the last kept), one render
     * each untimed (the image's pages, the caches), then N rounds of one
     * render each, the order alternating from round to round, so that a
     * change of load on the shared machine falls on both alike; each
     * round's area/point is a paired ratio, whose median and range are
     * given beside the ratio of the medians.  analytic after them, N
     * renders under each filter. */
    double t_m[10][TIMED_MAX], c_m[10][TIMED_MAX], med[10], cmed[10], t_i[10][5], c_i[10][5],
        imed[10], icmed[10], rt[TIMED_MAX], rc[TIMED_MAX];
    const char *names[10] = {"point", "area"};
    int nq = 2 + nf;
    for (int q = 2; q < nq; q++)
        names[q] = "analytic";
    aa_job jobs[2];
    aa_method ms[2];
    for (int q = 0; q < nq; q++) {
        const char *fname = q < 2 ? "box" : filters[q - 2];
        aa_job *jb = q < 2 ? &jobs[q] : &job;
        aa_method *mt = q < 2 ? &ms[q] : &m;
        if (aa_filter_parse(fname, &f) || aa_job_init(jb, s, w, h, 0.0, 0.0, 0.0, &f, 1, 1) ||
            aa_method_parse(names[q], &f, &spec)) {
            fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
            return 3;
        }
        /* the init (its tables for the scene and the size), five times, the
         * last kept for the renders */
        for (int k = 0; k < 5; k++) {
            double t0 = aa_now(), c0 = cpu_now();
            if (aa_method_init(mt, &spec, jb)) {
                fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
                return 3;
            }
            t_i[q][k] = aa_now() - t0;
            c_i[q][k] = cpu_now() - c0;
            if (k < 4)
                aa_method_free(mt);
        }
        if (q == 0)
            continue; /* point's renders with area's, below */
        int qs[2] = {0, 1}, nrun = q == 1 ? 2 : 1;
        if (q > 1)
            qs[0] = q;
        for (int r = -1; r < timed; r++) /* r = -1: the untimed render of each */
            for (int o = 0; o < nrun; o++) {
                int qq = qs[nrun == 2 && r >= 0 && r % 2 ? 1 - o : o];
                aa_job *jq = qq < 2 ? &jobs[qq] : &job;
                aa_method *mq = qq < 2 ? &ms[qq] : &m;
                double t0 = aa_now(), c0 = cpu_now();
                if (aa_method_render(mq, jq, &im, &c)) {
                    fprintf(stderr, "bench_bezstroke: %s\n", aa_last_error());
                    return 3;
                }
                if (r >= 0)
                    t_m[qq][r] = aa_now() - t0, c_m[qq][r] = cpu_now() - c0;
            }
        if (q == 1)
            for (int r = 0; r < timed; r++)
                rt[r] = t_m[1][r] / t_m[0][r], rc[r] = c_m[1][r] / c_m[0][r];
        for (int qq = q == 1 ? 0 : q; qq <= q; qq++) {
            aa_method_free(qq < 2 ? &ms[qq] : &m);
            aa_job_free(qq < 2 ? &jobs[qq] : &job);
            med[qq] = median(t_m[qq], timed); /* sorts them */
            cmed[qq] = median(c_m[qq], timed);
            imed[qq] = median(t_i[qq], 5);
            icmed[qq] = median(c_i[qq], 5);
            char label[64];
            snprintf(label, sizeof label, qq < 2 ? "%s" : "%s %s", names[qq],
                     qq < 2 ? "box" : filters[qq - 2]);
            printf("%-19s %10.3f ms (median of %d, %.3f .. %.3f), cpu %.3f ms (%.3f .. %.3f)\n",
                   label, 1e3 * med[qq], timed, 1e3 * t_m[qq][0], 1e3 * t_m[qq][timed - 1],
                   1e3 * cmed[qq], 1e3 * c_m[qq][0], 1e3 * c_m[qq][timed - 1]);
            printf("%-19s %10.3f ms (median of 5, %.3f .. %.3f), cpu %.3f ms (%.3f .. %.3f)\n",
                   "  its init", 1e3 * imed[qq], 1e3 * t_i[qq][0], 1e3 * t_i[qq][4],
                   1e3 * icmed[qq], 1e3 * c_i[qq][0], 1e3 * c_i[qq][4]);
        }
    }
    double mrt = median(rt, timed), mrc = median(rc, timed); /* sorts them */
    printf("area/point          %10.2f (cpu %.2f), of the medians\n", med[1] / med[0],
           cmed[1] / cmed[0]);
    printf("area/point, paired  %10.2f (%.2f .. %.2f), cpu %.2f (%.2f .. %.2f): the median "
           "of %d rounds' ratios\n",
           mrt, rt[0], rt[timed - 1], mrc, rc[0], rc[timed - 1], timed);
    printf("area/point, init + render once %4.2f (cpu %.2f)\n",
           (imed[1] + med[1]) / (imed[0] + med[0]), (icmed[1] + cmed[1]) / (icmed[0] + cmed[0]));
    for (int q = 2; q < nq; q++)
        printf("analytic/area       %10.2f (cpu %.2f) %s\n", med[q] / med[1], cmed[q] / cmed[1],
               filters[q - 2]);
    aa_image_free(&im);
    aa_image_free(&bound);
    aa_scene_free(placed);
    aa_scene_free(s);
    aa_path_free(&path);
    aa_path_free(&out);
    return 0;
}
