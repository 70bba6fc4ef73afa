/*
 * claims.c: the papers' quantitative claims (the seed papers', and those of
 * the post-processes that descend from Crow's), measured
 * (`aabench figures --claims`: DIR/claims.md and DIR/claims.html).
 *
 * Each claim is quoted with where it is made (paper, section, pages from
 * the paper's own table of contents where it has one), measured on the
 * same setting as far as this benchmark has it (the paper's own setting
 * where it names one: a single edge, small objects, exact areas for hidden
 * surfaces; scenes moved OFF pixel off the grid where alignment would
 * favour a method), and judged from margins fixed before measuring: "yes"
 * when the numbers agree with the claim as stated, "no" when they do not,
 * "partly" when one part or case holds and another not, "inconclusive"
 * when an interval holds the margin or errors tie, "not comparable" when
 * the setting cannot decide the claim; each verdict with a one-line reason.
 * Each claim is a row of the table `claims` (its texts, the specs it is
 * measured on, and its measure: the generic time sweep or a small function
 * of its own); aa_claim_check checks a row's specs.
 *
 * How things are measured.
 *  - Times: the interleaved ratio.  The two cases render in turns on one
 *    thread (aa_timing_measure, a fixed count of `reps` turns, each render
 *    after an untimed init, both warmed up once), so a slow spell of the
 *    shared machine falls on both; each turn gives a ratio, and the median
 *    of the ratios and its distribution-free 95% interval are quoted.  A
 *    claim's band is judged by the interval (aa_claim_band_verdict), never
 *    by one time.
 *  - Errors: RMSE against the exact reference under the method's filter
 *    (a method without a prefilter: the box), linear light; the error
 *    energy above 1/4 cycle per pixel (staircases and noise) and below it
 *    (moire) from metrics.c; and what an eye of s = AA_EYE_S pixels sees
 *    against the scene seen by the same eye (eye.c), which compares images
 *    made under different filters.
 *  - Motion: the temporal suite's setting, 128 x 128, moving (0.37, 0.11)
 *    pixel per frame over 24 frames, eye window 6 (temporal.c).
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct cx {
    const char *cache;
    int threads, reps;
    int (*progress)(void *ctx, const char *what);
    void *pctx;
} cx;

typedef struct tcase tcase;         /* a method timed on a view */
typedef struct tpair tpair;         /* the time of one case over another's */
typedef struct claim claim;         /* a claim's measured text and verdict */
typedef struct claim_row claim_row; /* a claim of the table */

/* A claim: a row of the table below.  Its texts say who claims what,
 * where, and on what setting it is measured; its specs, what it is
 * measured on (patterns, their size, the filter or each method's filter,
 * the methods); `measure`, how: time_sweep, a generic measure driven by
 * the row's pairs and band, or the claim's own small function.  A measure
 * fills its claim's result, and the next row's too when that row has none
 * (a claim measured on the same renders as the one before it). */
struct claim_row {
    const char *paper, *where, *claim, *setting;
    const char *const *patterns; /* NULL-terminated, as are the lists below */
    int size;
    const char *filter;          /* NULL: each method's own, `filters` */
    const char *const *filters;
    const char *const *methods;
    const char *const *labels;   /* the methods' names in the text */
    /* time_sweep: the pairs (a NULL label ends them), the text before and
     * after their ratios (printed with `digits` decimals), and the band
     * [lo, hi] in which a ratio holds the claim */
    const tpair *pairs;
    const char *head, *tail;
    int digits;
    double lo, hi;
    int (*measure)(const cx *x, const claim_row *d, claim *c);
    /* a setting that cannot decide the claim: why (the row is measured all
     * the same, and its verdict is "not comparable") */
    const char *not_comparable;
};

struct claim {
    const claim_row *row;
    char measured[2048];
    const char *verdict;
    char reason[512]; /* the verdict's reason, one line */
};

static void say(const cx *x, const char *what)
{
    if (x->progress)
        x->progress(x->pctx, what);
}

/* ---- running cases ---- */

/* The views' references computed with every thread before a timed run on
 * one, so the run reads them from the cache. */
static int prefetch(const cx *x, const aa_spec *pattern, int w, const aa_filter *f, double vx,
                    double vy, int frames)
{
    aa_view view;
    memset(&view, 0, sizeof view);
    view.pattern = *pattern;
    view.w = view.h = w;
    view.filter = *f;
    view.vx = vx, view.vy = vy;
    for (int k = 0; k < frames; k++) {
        aa_image ref;
        view.t = k;
        int st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL);
        if (st)
            return st;
        aa_image_free(&ref);
    }
    return AA_OK;
}

/* The methods on one view, measured (one render each, on one thread); with
 * motion, the temporal metrics over 24 frames too.  *rows is malloc'd, one
 * per method, in order. */
static int run_view(const cx *x, const char *pattern, int w, const char *filter,
                    const char *const *methods, size_t nm, double vx, double vy, aa_row **rows,
                    size_t *n)
{
    aa_run_spec p, *m = calloc(nm, sizeof *m);
    aa_run_size s = {w, w};
    aa_run_filter f;
    *rows = NULL;
    *n = 0;
    if (!m)
        return aa_fail(AA_ENOMEM, "out of memory");
    p.text = pattern;
    f.text = filter;
    int st = aa_pattern_parse(pattern, &p.spec);
    if (!st)
        st = aa_filter_parse(filter, &f.filter);
    for (size_t k = 0; k < nm && !st; k++) {
        m[k].text = methods[k];
        st = aa_spec_parse(methods[k], aa_method_table(), "method", &m[k].spec);
    }
    int moving = vx != 0 || vy != 0;
    if (!st)
        st = prefetch(x, &p.spec, w, &f.filter, vx, vy, moving ? 24 : 1);
    if (!st) {
        aa_run_config c;
        memset(&c, 0, sizeof c);
        c.patterns = &p, c.npatterns = 1;
        c.sizes = &s, c.nsizes = 1;
        c.filters = &f, c.nfilters = 1;
        c.methods = m, c.nmethods = nm;
        c.reps = 1; /* times: time_ratio */
        c.threads = 1;
        c.seed = 1;
        c.vx = vx, c.vy = vy;
        c.temporal = moving;
        c.frames = moving ? 24 : 0;
        c.window = moving ? 6 : 0;
        c.cache_dir = x->cache;
        c.enc.kind = AA_ENCODE_SRGB;
        char what[256];
        snprintf(what, sizeof what, "%s %dx%d %s", pattern, w, w, filter);
        say(x, what);
        st = aa_run(&c, rows, n);
    }
    free(m);
    if (!st)
        for (size_t k = 0; k < *n; k++)
            if (!(*rows)[k].ok)
                st = aa_fail(AA_EFAIL, "%s on %s: %s", (*rows)[k].method, pattern,
                             (*rows)[k].note);
    if (st) {
        free(*rows);
        *rows = NULL;
        return aa_fail_context(st, "claims: %s %dx%d %s", pattern, w, w, filter);
    }
    return AA_OK;
}

/* A method's image on a view placed `off` pixels right and down (rendered
 * with every thread, untimed), and what the eye sees of it (eye may be
 * NULL); m (may be NULL) gets the metrics against the reference under
 * mfilter, spp (may be NULL) the samples per pixel. */
static int image_at(const cx *x, const char *pattern, int w, const char *filter,
                    const char *method, double off, aa_image *img, double *eye,
                    const char *mfilter, aa_metrics *m, double *spp)
{
    aa_spec ps, ms;
    aa_filter f;
    aa_scene *scene = NULL;
    aa_job job;
    aa_counters counters;
    aa_image truth = {0};
    /* placed at time t = off moving (1, 1) pixel a frame: shifted by off */
    const double t = off, v = off != 0 ? 1 : 0;
    memset(&counters, 0, sizeof counters);
    int st = aa_pattern_parse(pattern, &ps);
    if (!st)
        st = aa_filter_parse(filter, &f);
    if (!st)
        st = aa_method_parse(method, &f, &ms);
    if (!st)
        st = aa_pattern_scene_at(&ps, w, w, &scene);
    if (st)
        return aa_fail_context(st, "claims: %s on %s", method, pattern);
    if (!(st = aa_job_init(&job, scene, w, w, t, v, v, &f, 1, x->threads))) {
        if (!(st = aa_image_alloc(img, w, w, 3)))
            st = aa_method_run(&ms, &job, 1, img, &counters, NULL);
        aa_job_free(&job);
    }
    if (!st && spp)
        *spp = (double)counters.samples / ((double)w * w);
    if (!st && eye &&
        !(st = aa_eye_truth(&ps, w, w, t, v, v, AA_EYE_S, x->cache, x->threads, &truth)))
        st = aa_eye_rmse(img, &truth, AA_EYE_S, eye);
    if (!st && m) {
        aa_view view;
        aa_image ref;
        memset(&view, 0, sizeof view);
        view.pattern = ps;
        view.w = view.h = w;
        view.t = t, view.vx = v, view.vy = v;
        if (!(st = aa_filter_parse(mfilter, &view.filter)) &&
            !(st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL))) {
            st = aa_metrics_compute(&ref, img, NULL, m);
            aa_image_free(&ref);
        }
    }
    aa_image_free(&truth);
    aa_scene_free(scene);
    return st ? aa_fail_context(st, "claims: %s on %s", method, pattern) : AA_OK;
}

/* The same, unmoved, with the metrics against the box reference. */
static int image_of(const cx *x, const char *pattern, int w, const char *filter,
                    const char *method, aa_image *img, double *eye, aa_metrics *box)
{
    return image_at(x, pattern, w, filter, method, 0, img, eye, "box", box, NULL);
}

/* A method's metrics on a view placed `off` pixels right and down (and
 * its eye RMSE, its samples per pixel; either may be NULL). */
static int metrics_at(const cx *x, const char *pattern, int w, const char *filter,
                      const char *method, double off, const char *mfilter, aa_metrics *m,
                      double *eye, double *spp)
{
    aa_image img = {0};
    int st = image_at(x, pattern, w, filter, method, off, &img, eye, mfilter, m, spp);
    aa_image_free(&img);
    return st;
}

/* What the eye sees of a method's image, and (beat may be NULL) the
 * image's energy near the Nyquist limit. */
static int eye_of(const cx *x, const char *pattern, int w, const char *filter,
                  const char *method, double *eye, double *beat)
{
    aa_image img = {0};
    int st = image_of(x, pattern, w, filter, method, &img, eye, NULL);
    if (!st && beat)
        st = aa_band_energy(&img, AA_BEAT_F0, beat);
    aa_image_free(&img);
    return st;
}

/* A timed case: a method on a view (frame_only: one displayed frame of a
 * temporal method). */
struct tcase {
    const char *pattern;
    int w;
    const char *filter, *method;
    int frame_only;
};

struct tpair {
    tcase a, b;
    const char *label;
};

typedef struct tstate {
    aa_scene *scene;
    aa_filter filter;
    aa_spec method;
    aa_job job;
    aa_image img;
    int job_made;
} tstate;

static void tstate_free(tstate *t)
{
    if (t->job_made)
        aa_job_free(&t->job);
    aa_image_free(&t->img);
    aa_scene_free(t->scene);
}

static int tstate_init(const tcase *c, tstate *t)
{
    aa_spec ps;
    memset(t, 0, sizeof *t);
    int st = aa_pattern_parse(c->pattern, &ps);
    if (!st)
        st = aa_filter_parse(c->filter, &t->filter);
    if (!st)
        st = aa_method_parse(c->method, &t->filter, &t->method);
    if (!st)
        st = aa_pattern_scene_at(&ps, c->w, c->w, &t->scene);
    if (!st && !(st = aa_job_init(&t->job, t->scene, c->w, c->w, 0, 0, 0, &t->filter, 1, 1))) {
        t->job_made = 1;
        t->job.frame_only = c->frame_only;
        st = aa_image_alloc(&t->img, c->w, c->w, 3);
    }
    return st ? aa_fail_context(st, "claims: %s on %s", c->method, c->pattern) : AA_OK;
}

/* A time ratio: the median of the pairs' ratios and its 95% interval
 * (aa_time_stats_compute: distribution-free, from order statistics). */
typedef struct tratio {
    double median, lo, hi;
} tratio;

static int render_case(void *ctx)
{
    tstate *t = ctx;
    aa_counters cn;
    double seconds;
    int st = aa_method_run(&t->method, &t->job, 1, &t->img, &cn, &seconds);
    if (!st) /* the render alone, its init left out */
        aa_method_report_seconds(seconds);
    return st;
}

/* The time of b over the time of a, on one thread, by the interleaved
 * ratio: aa_timing_measure renders a and b taking turns (each after an
 * untimed init, both warmed up once), `reps` turns, so that a slow spell
 * of the shared machine falls on both; the ratio of each turn's two times,
 * their median and its 95% interval. */
static int time_ratio(const cx *x, const tcase *a, const tcase *b, tratio *ratio)
{
    tstate t[2];
    int st = tstate_init(a, &t[0]);
    if (st)
        return st;
    if ((st = tstate_init(b, &t[1]))) {
        tstate_free(&t[0]);
        return st;
    }
    const int reps = x->reps < AA_TIMING_MAX_REPS ? x->reps : AA_TIMING_MAX_REPS;
    aa_timing *tm = calloc(2, sizeof *tm);
    double *r = malloc((size_t)reps * sizeof *r);
    if (!tm || !r)
        st = aa_fail(AA_ENOMEM, "out of memory");
    char what[256];
    snprintf(what, sizeof what, "timing %s / %s on %s", b->method, a->method, b->pattern);
    say(x, what);
    if (!st) {
        aa_timing_plan plan = {reps, 0, 0};
        aa_timed_fn fn[2] = {render_case, render_case};
        void *ctx[2] = {&t[0], &t[1]};
        int threads[2] = {1, 1};
        st = aa_timing_measure(&plan, 2, fn, ctx, threads, tm);
    }
    if (!st && (tm[0].n != reps || tm[1].n != reps))
        st = aa_fail(AA_EFAIL, "claims: %d and %d timed renders of %d", tm[0].n, tm[1].n, reps);
    for (int k = 0; k < reps && !st; k++)
        r[k] = tm[0].wall[k] > 0 ? tm[1].wall[k] / tm[0].wall[k] : NAN;
    aa_time_stats ts;
    if (!st)
        st = aa_time_stats_compute(r, (size_t)reps, &ts);
    if (!st)
        *ratio = (tratio){ts.median, ts.ci_lo, ts.ci_hi};
    free(r);
    free(tm);
    tstate_free(&t[0]);
    tstate_free(&t[1]);
    return st ? aa_fail_context(st, "claims: timing %s / %s on %s", b->method, a->method,
                                b->pattern)
              : AA_OK;
}

/* Appending to a claim's measured text. */
static void add(claim *c, const char *fmt, ...) AA_PRINTF(2, 3);
static void add(claim *c, const char *fmt, ...)
{
    size_t n = strlen(c->measured);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->measured + n, sizeof c->measured - n, fmt, ap);
    va_end(ap);
}

/* The reason of a verdict, one line. */
static void because(claim *c, const char *verdict, const char *fmt, ...) AA_PRINTF(3, 4);
static void because(claim *c, const char *verdict, const char *fmt, ...)
{
    va_list ap;
    c->verdict = verdict;
    va_start(ap, fmt);
    vsnprintf(c->reason, sizeof c->reason, fmt, ap);
    va_end(ap);
}

/* A ratio and its interval in the text: "1.08 [1.02, 1.12]". */
static void add_ratio(claim *c, const tratio *r, int digits)
{
    add(c, "%.*f [%.*f, %.*f]", digits, r->median, digits, r->lo, digits, r->hi);
}

/* ---- verdicts ---- */

/* Errors within this share of each other are a tie, for every claim that
 * compares errors (fixed before measuring). */
#define TIE 0.10

const char *aa_claim_band_verdict(double ci_lo, double ci_hi, double lo, double hi)
{
    if (!(ci_lo <= ci_hi) || !(lo <= hi))
        return "inconclusive";
    if (ci_lo >= lo && ci_hi <= hi)
        return "yes";
    if (ci_hi < lo || ci_lo > hi)
        return "no";
    return "inconclusive";
}

int aa_claim_compare(double a, double b, double margin)
{
    if (a < b * (1 - margin))
        return -1;
    if (b < a * (1 - margin))
        return 1;
    return 0;
}

const char *aa_claim_tally(int yes, int no, int undecided)
{
    if (yes && no)
        return "partly";
    if (undecided || (!yes && !no))
        return "inconclusive";
    return yes ? "yes" : "no";
}

/* ---- the generic measure: a time sweep ---- */

/* The claims' moving setting: the temporal suite's motion per frame. */
#define MOVE_X 0.37
#define MOVE_Y 0.11

/* A list of the row's specs, ended by NULL. */
#define LIST(...) ((const char *const[]){__VA_ARGS__, NULL})

static int count_of(const char *const *list)
{
    int n = 0;
    while (list && list[n])
        n++;
    return n;
}

/* The filter of the row's method k: its own, else the row's. */
static const char *filter_of(const claim_row *d, int k)
{
    return d->filters ? d->filters[k] : d->filter;
}

/* The time of each pair's b over its a; each pair's verdict from its
 * interval against the band [lo, hi], the claim's from their tally. */
static int time_sweep(const cx *x, const claim_row *d, claim *c)
{
    int n = 0, yes = 0, no = 0;
    add(c, "%s", d->head);
    for (const tpair *p = d->pairs; p->label; p++, n++) {
        tratio ratio;
        int st = time_ratio(x, &p->a, &p->b, &ratio);
        if (st)
            return st;
        const char *v = aa_claim_band_verdict(ratio.lo, ratio.hi, d->lo, d->hi);
        yes += !strcmp(v, "yes");
        no += !strcmp(v, "no");
        add(c, "%s %s ", n ? ";" : "", p->label);
        add_ratio(c, &ratio, d->digits);
    }
    add(c, "%s", d->tail);
    const char *v = aa_claim_tally(yes, no, n - yes - no);
    because(c, v, "%d of %d intervals inside the band, %d wholly outside, %d across its end",
            yes, n, no, n - yes - no);
    return AA_OK;
}

/* ---- the claims' own measures ---- */

/* Scenes are placed this many pixels right and down where a grid would
 * favour a method (catmull:tiles=4 at 256 x 256 puts every edge on a pixel
 * boundary, where a regular grid is exact and corner samples sit on the
 * edges). */
#define OFF 0.3

/* Ramos and Borges: this row's cost (adaptive, methods[1], against point,
 * methods[0], and against the same corner sampler with its search off,
 * methods[4]) and the next row's quality (adaptive against the two grids,
 * methods[2] and [3]), the scenes placed OFF pixels off the grid. */
static int ramos_borges(const cx *x, const claim_row *d, claim *c)
{
    claim *cost = &c[0], *better = &c[1];
    const size_t nrb = (size_t)count_of(d->patterns);
    double sum_drop = 0, sum_same = 0;
    int yes = 0, no = 0;
    add(cost, "time without antialiasing / with (point; the corner sampler without its search):");
    add(better, "RMSE (samples per pixel), scenes moved %.1f pixel right and down:", OFF);
    for (size_t k = 0; k < nrb; k++) {
        tratio ratio, same;
        const char *scene = d->patterns[k];
        tcase a = {scene, d->size, d->filter, d->methods[1], 0},
              p = {scene, d->size, d->filter, d->methods[0], 0},
              q = {scene, d->size, d->filter, d->methods[4], 0};
        int st = time_ratio(x, &a, &p, &ratio);
        if (!st)
            st = time_ratio(x, &a, &q, &same);
        if (st)
            return st;
        sum_drop += 1 - ratio.median;
        sum_same += 1 - same.median;
        add(cost, "%s %s ", k ? ";" : "", scene);
        add_ratio(cost, &ratio, 2);
        add(cost, " and ");
        add_ratio(cost, &same, 2);
        aa_metrics m[3];
        double spp = 0;
        for (int q2 = 0; q2 < 3 && !st; q2++)
            st = metrics_at(x, scene, d->size, d->filter, d->methods[1 + q2], OFF, "box", &m[q2],
                            NULL, q2 ? NULL : &spp);
        if (st)
            return st;
        add(better, "%s %s: adaptive %.4f (%.2f), n=2 %.4f, n=3 %.4f", k ? ";" : "", scene,
            m[0].rmse, spp, m[1].rmse, m[2].rmse);
        int v = aa_claim_compare(m[0].rmse, m[1].rmse, TIE);
        yes += v < 0;
        no += v > 0;
    }
    double mean = sum_drop / (double)nrb, mean_same = sum_same / (double)nrb;
    add(cost, ". Mean drop %.0f%% against point, %.0f%% against the corner sampler without its "
              "search (the paper's experiment, in this renderer). The paper's renderer took a "
              "z-buffer decision at every pixel; this point sampler fills runs between "
              "crossings.",
        100 * mean, 100 * mean_same);
    because(cost, "not comparable",
            "the paper made \"no precise or systematic measurement\" and its baseline, a "
            "z-buffer renderer, is not this one (mean drop %.0f%% here against the same corner "
            "sampler, %.0f%% against point)",
            100 * mean_same, 100 * mean);
    add(better, ". Adaptive against n=2 (4 samples): better by more than %.0f%% on %d of %zu "
                "scenes, worse on %d; the single edge, where the paper makes its claim, is "
                "claim 17.",
        100 * TIE, yes, nrb, no);
    because(better, aa_claim_tally(yes, no, (int)nrb - yes - no),
            "off the grid, adaptive beats the 4-sample grid on %d of %zu scenes and loses on %d "
            "(thin bands and several edges between corners, the paper's sec. 6)",
            yes, nrb, no);
    return AA_OK;
}

/* The pixels of an image that hold one edge: the reference strictly
 * between black and white and no vertex within 2 pixels (verts: n points
 * in pattern units). */
static int single_edge(const aa_image *ref, int i, int j, const double *verts, int n)
{
    double v = ref->v[((size_t)j * (size_t)ref->w + (size_t)i) * 3];
    if (!(v > 1e-9 && v < 1 - 1e-9))
        return 0;
    for (int k = 0; k < n; k++) {
        double du = verts[2 * k] * ref->w - (i + 0.5), dv = verts[2 * k + 1] * ref->h - (j + 0.5);
        if (du * du + dv * dv < 4)
            return 0;
    }
    return 1;
}

/* The single edge (Ramos and Borges, sec. 3): over the pixels that hold
 * one edge of the triangle patterns/svg/edge.svg, the RMSE and largest
 * error of adaptive (methods[0]) and the grids (methods[1], [2]).  The
 * triangle's vertices, in pattern units, are those of the file. */
static int rb_edge(const cx *x, const claim_row *d, claim *c)
{
    static const double verts[] = {0.12, 0.17, 0.91, 0.33, 0.38, 0.93};
    const int w = d->size;
    aa_view view;
    aa_image ref = {0};
    memset(&view, 0, sizeof view);
    view.w = view.h = w;
    int st = aa_pattern_parse(d->patterns[0], &view.pattern);
    if (!st)
        st = aa_filter_parse("box", &view.filter);
    if (!st)
        st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL);
    double rmse[3] = {0}, worst[3] = {0};
    int npix = 0;
    for (int q = 0; q < 3 && !st; q++) {
        aa_image img = {0};
        double sum = 0;
        npix = 0;
        st = image_at(x, d->patterns[0], w, d->filter, d->methods[q], 0, &img, NULL, NULL, NULL,
                      NULL);
        for (int j = 0; j < w && !st; j++)
            for (int i = 0; i < w; i++) {
                if (!single_edge(&ref, i, j, verts, 3))
                    continue;
                size_t o = ((size_t)j * (size_t)w + (size_t)i) * 3;
                double e = fabs(img.v[o] - ref.v[o]);
                sum += e * e, npix++;
                worst[q] = fmax(worst[q], e);
            }
        rmse[q] = npix ? sqrt(sum / npix) : 0;
        aa_image_free(&img);
    }
    aa_image_free(&ref);
    if (st)
        return st;
    /* the search halves a border `depth` (5) times: a found point is within
     * 1/32 pixel of the edge, and the fan's area within 1/32 of the pixel */
    const double exact = 1.0 / 32;
    add(c, "over the %d pixels crossed by one edge: adaptive RMSE %.4f (max %.4f), n=2 %.4f "
           "(max %.3f), n=3 %.4f (max %.3f). \"Exact\" taken as a largest error within the "
           "search's resolution, 1/32.",
        npix, rmse[0], worst[0], rmse[1], worst[1], rmse[2], worst[2]);
    int exact_ok = worst[0] <= exact;
    int beats = aa_claim_compare(rmse[0], rmse[1], TIE) < 0 &&
                aa_claim_compare(rmse[0], rmse[2], TIE) < 0;
    because(c, exact_ok && beats ? "yes" : exact_ok || beats ? "partly" : "no",
            "largest error %.4f %s 1/32, RMSE %.0f and %.0f times smaller than the 4- and "
            "9-sample grids'",
            worst[0], exact_ok ? "within" : "beyond", rmse[1] / fmax(rmse[0], 1e-300),
            rmse[2] / fmax(rmse[0], 1e-300));
    return AA_OK;
}

/* The reference of a view under a filter (spec text). */
static int reference_of(const cx *x, const char *pattern, int w, const char *filter,
                        aa_image *out)
{
    aa_view view;
    memset(&view, 0, sizeof view);
    view.w = view.h = w;
    int st = aa_pattern_parse(pattern, &view.pattern);
    if (!st)
        st = aa_filter_parse(filter, &view.filter);
    if (!st)
        st = aa_reference(&view, x->cache, x->threads, out, NULL, NULL);
    return st;
}

/* The RMSE between what an eye of s pixels sees of two images. */
static int eye_diff(const aa_image *a, const aa_image *b, double s, double *rmse)
{
    aa_image ea = {0}, eb = {0};
    aa_metrics m;
    int st = aa_eye_blur(a, s, &ea);
    if (!st)
        st = aa_eye_blur(b, s, &eb);
    if (!st)
        st = aa_metrics_compute(&ea, &eb, NULL, &m);
    if (!st)
        *rmse = m.rmse;
    aa_image_free(&ea);
    aa_image_free(&eb);
    return st;
}

/* Catmull, "Anti-aliasing": at 128, 256 and 512 pixels, seen from the
 * same distance (an eye of s = 1, 2, 4 pixels: 1/128 of the picture), the
 * difference between two filtered pictures (the exact references under
 * the box and under the pyramid two pixels wide) and between point
 * sampling (methods[0]) and the box. */
static int catmull_resolution(const cx *x, const claim_row *d, claim *c)
{
    static const int sizes[] = {128, 256, 512};
    double df[3], dp[3];
    const char *pat = d->patterns[0];
    for (int k = 0; k < 3; k++) {
        aa_image box = {0}, tent = {0}, pt = {0};
        const double s = sizes[k] / 128.0;
        int st = reference_of(x, pat, sizes[k], "box", &box);
        if (!st)
            st = reference_of(x, pat, sizes[k], "tent:r=1", &tent);
        if (!st)
            st = image_at(x, pat, sizes[k], "box", d->methods[0], 0, &pt, NULL, NULL, NULL, NULL);
        if (!st)
            st = eye_diff(&box, &tent, s, &df[k]);
        if (!st)
            st = eye_diff(&pt, &box, s, &dp[k]);
        aa_image_free(&box);
        aa_image_free(&tent);
        aa_image_free(&pt);
        if (st)
            return st;
        add(c, "%s%dx%d (eye s = %g): box against pyramid %.5f, point against box %.5f",
            k ? "; " : "", sizes[k], sizes[k], s, df[k], dp[k]);
    }
    add(c, ". From 128 to 512 the filtered pictures' difference falls %.1f times, point's "
           "%.1f times (\"lowered\" taken as at least 2 times).",
        df[0] / df[2], dp[0] / dp[2]);
    int filt = df[2] < df[0] / 2, point_stays = dp[2] > dp[0] / 2;
    because(c, aa_claim_tally(filt + point_stays, !filt + !point_stays, 0),
            "seen from the same distance the filtered pictures' difference falls %.1f times "
            "from 128 to 512 pixels; point sampling's %s (%.1f times)",
            df[0] / df[2], point_stays ? "falls less than half as far" : "falls as well",
            dp[0] / dp[2]);
    return AA_OK;
}

/* Pfenning's blending errors: on each scene, the exact picture (area,
 * methods[0], which resolves what each pixel shows) against SVG renderers
 * that composite each shape's coverage as alpha (rsvg, Chromium), when
 * present; their largest error against the box reference. */
static int pfenning_conflation(const cx *x, const claim_row *d, claim *c)
{
    static const char *const peers[] = {"external:renderer=rsvg",
                                        "external:renderer=chromium"};
    int yes = 0, no = 0, cases = 0;
    for (int k = 0; d->patterns[k]; k++) {
        aa_metrics ma;
        int st = metrics_at(x, d->patterns[k], d->size, "box", d->methods[0], 0, "box", &ma, NULL,
                            NULL);
        if (st)
            return st;
        add(c, "%s%s: largest error exact (area) %.4f", k ? "; " : "", d->patterns[k],
            ma.max_err);
        for (int q = 0; q < 2; q++) {
            aa_metrics mp;
            aa_filter f;
            aa_spec spec;
            const char *name = strchr(peers[q], '=') + 1;
            if (aa_filter_parse("box", &f) || aa_method_parse(peers[q], &f, &spec)) {
                add(c, ", %s not installed", name);
                continue;
            }
            if ((st = metrics_at(x, d->patterns[k], d->size, "box", peers[q], 0, "box", &mp,
                                 NULL, NULL)))
                return st;
            add(c, ", %s %.4f (RMSE %.4f)", name, mp.max_err, mp.rmse);
            cases++;
            /* conflation: a peer's largest error at least 0.1 where the exact
             * picture's is under 0.01 (fixed beforehand; the slides' formula
             * gives up to 1/4 at a pixel half covered by each shape) */
            int shows = mp.max_err >= 0.1 && ma.max_err < 0.01;
            yes += shows, no += !shows;
        }
    }
    add(c, ". A largest error of 0.1 or more where the exact picture has none counts as a "
           "blending error (the slides' formula: up to 1/4 at a pixel each shape half covers).");
    because(c, cases ? aa_claim_tally(yes, no, 0) : "inconclusive",
            cases ? "coverage composited as alpha errs by 0.1 or more on %d of %d renders, the "
                    "exact picture by less than 0.01"
                  : "no renderer that composites coverage as alpha is installed (%d of %d)",
            yes, cases);
    return AA_OK;
}

/* Crow's small objects in motion (the temporal suite's setting): the
 * popping and flicker of each method under its own filter; the tiler
 * (methods[1]) "does not twinkle" where its flicker is under a tenth of
 * point sampling's (methods[0]) and its popping under 1% of the dots
 * (area, methods[2], beside: what blending exactly gives). */
static int crow_twinkle(const cx *x, const claim_row *d, claim *c)
{
    double pop[3], flick[3];
    for (int q = 0; q < 3; q++) {
        aa_row *r;
        size_t n;
        int st = run_view(x, d->patterns[0], d->size, filter_of(d, q), &d->methods[q], 1,
                          MOVE_X, MOVE_Y, &r, &n);
        if (st)
            return st;
        pop[q] = r[0].tm.popping, flick[q] = r[0].tm.flicker_mean;
        free(r);
        add(c, "%s%s: popping %.3f, flicker %.4f", q ? "; " : "", d->labels[q], pop[q],
            flick[q]);
    }
    add(c, ". \"Does not twinkle\" taken as flicker under a tenth of point's and popping "
           "under 0.01.");
    int calm = flick[1] < flick[0] / 10 && pop[1] < 0.01;
    because(c, calm ? "yes" : "no",
            "the tiler's flicker is %.0f%% of point's and %.1f%% of the dots pop",
            100 * flick[1] / flick[0], 100 * pop[1]);
    return AA_OK;
}

/* Crow's edge dots: the share f of dots whose box reference is neither
 * black nor white (grey scenes), at each size; the extra effort k on them
 * that doubles the image's cost is k = 1 + 1/f. */
static int crow_few(const cx *x, const claim_row *d, claim *c)
{
    static const int sizes[] = {256, 512};
    double most = 0;
    add(c, "share of dots an edge crosses (effort on them that doubles the cost):");
    for (int k = 0; d->patterns[k]; k++)
        for (int s = 0; s < 2; s++) {
            aa_view view;
            aa_image ref = {0};
            memset(&view, 0, sizeof view);
            view.w = view.h = sizes[s];
            int st = aa_pattern_parse(d->patterns[k], &view.pattern);
            if (!st)
                st = aa_filter_parse("box", &view.filter);
            if (!st)
                st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL);
            if (st)
                return st;
            size_t mixed = 0, n = (size_t)ref.w * (size_t)ref.h;
            for (size_t o = 0; o < n; o++)
                mixed += ref.v[3 * o] > 1e-9 && ref.v[3 * o] < 1 - 1e-9;
            aa_image_free(&ref);
            double f = (double)mixed / (double)n;
            most = fmax(most, f);
            add(c, "%s %s %dx%d %.3f (%.0f times)", k || s ? ";" : "", d->patterns[k], sizes[s],
                sizes[s], f, 1 + 1 / f);
        }
    add(c, ". \"Several times\" taken as at least 3 times, a share of at most 1/2.");
    because(c, most <= 0.5 ? "yes" : "no",
            "at most %.0f%% of the dots need blending, so %.0f times their effort doubles the cost",
            100 * most, 1 + 1 / most);
    return AA_OK;
}

/* Catmull: the spread of the total intensity over the frames, area
 * (methods[1]) against point (methods[0]). */
static int catmull_constant(const cx *x, const claim_row *d, claim *c)
{
    aa_row *r;
    size_t n;
    int st = run_view(x, d->patterns[0], d->size, d->filter, d->methods, 2, MOVE_X, MOVE_Y, &r,
                      &n);
    if (st)
        return st;
    add(c, "area %.1e, point %.3f.", r[1].tm.conservation, r[0].tm.conservation);
    int ok = r[1].tm.conservation < 1e-12 && r[0].tm.conservation > 1e-2;
    because(c, ok ? "yes" : "no",
            "area's total is constant to rounding (%.0e); point's swings by %.0f%% of its mean",
            r[1].tm.conservation, 100 * r[0].tm.conservation);
    free(r);
    return AA_OK;
}

/* Feibush, Levoy and Cook: what the eye sees and the beat energy of no
 * filter, the unweighted and the weighted filter (methods 0, 1, 2). */
static int feibush_quality(const cx *x, const claim_row *d, claim *c)
{
    double e[3], b[3];
    for (int k = 0; k < 3; k++) {
        int st = eye_of(x, d->patterns[0], d->size, filter_of(d, k), d->methods[k], &e[k], &b[k]);
        if (st)
            return st;
    }
    add(c, "eye RMSE: no filter %.4f, unweighted %.4f, weighted %.4f; beat energy: %.2e, "
           "%.2e, %.2e.",
        e[0], e[1], e[2], b[0], b[1], b[2]);
    add(c, " The unweighted filter removes the low-frequency moire of no filter (eye RMSE %.0f "
           "times smaller) but keeps %.0f times the weighted filter's fringe-making energy; "
           "the weighted filter's eye RMSE is mostly its blur.",
        e[0] / e[1], b[1] / b[2]);
    /* the three parts, each by a factor of 3 fixed beforehand: the
     * unweighted filter far better than none by eye; the weighted far
     * calmer than the unweighted; and the weighted better than the
     * unweighted by eye too (an "excellent image" against a "nearly
     * satisfactory" one) */
    int parts = (e[1] < e[0] / 3) + (b[2] < b[1] / 3);
    int by_eye = aa_claim_compare(e[2], e[1], TIE);
    because(c, aa_claim_tally(parts + (by_eye < 0), (2 - parts) + (by_eye > 0), by_eye == 0),
            "the weighted filter has %.0f times less fringe-making energy, but by eye RMSE the "
            "unweighted filter is %s",
            b[1] / b[2], by_eye > 0 ? "the better" : by_eye < 0 ? "the worse" : "as good");
    return AA_OK;
}

/* Crow, figs. 2.10-2.14: the last method (the pyramid two dots wide)
 * should show the least eye RMSE and the least beat energy. */
static int crow_filters(const cx *x, const claim_row *d, claim *c)
{
    const int nm = count_of(d->methods);
    double e[8], b[8];
    int best = 0, calm = 0;
    if (nm < 1 || nm > 8)
        return aa_fail(AA_EINVAL, "claims: %d methods for the filters' claim (1 to 8)", nm);
    add(c, "eye RMSE (beat energy):");
    for (int k = 0; k < nm; k++) {
        int st = eye_of(x, d->patterns[0], d->size, filter_of(d, k), d->methods[k], &e[k], &b[k]);
        if (st)
            return st;
        if (e[k] < e[best])
            best = k;
        if (b[k] < b[calm])
            calm = k;
        add(c, "%s %s %.4f (%.1e)", k ? ";" : "", d->labels[k], e[k], b[k]);
    }
    add(c, ". Least eye RMSE: %s; least beat energy: %s.", d->labels[best], d->labels[calm]);
    const int kept = nm - 1;
    because(c, best == kept && calm == kept   ? "yes"
               : best == kept || calm == kept ? "partly"
                                              : "no",
            "the kept pyramid is %s by eye RMSE and %s by beat energy",
            best == kept ? "the best" : "not the best", calm == kept ? "the best" : "not the best");
    return AA_OK;
}

/* Crow's rectangle per edge: crowtable (methods[0]) against 5 x 5
 * supersampling (methods[1]) and the exact tiler (methods[2]) on each
 * scene: sufficient where the tables' eye RMSE ties the exact filter's and
 * their RMSE beats 5 x 5's. */
static int crow_rectangle(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int yes = 0, no = 0;
    char failed[256] = "";
    for (int k = 0; k < np; k++) {
        const char *pat = d->patterns[k];
        tratio ratio;
        tcase t = {pat, d->size, d->filter, d->methods[0], 0},
              ss = {pat, d->size, d->filter, d->methods[1], 0};
        aa_metrics m[2];
        double e[3];
        int st = time_ratio(x, &ss, &t, &ratio);
        for (int q = 0; q < 3 && !st; q++)
            st = metrics_at(x, pat, d->size, d->filter, d->methods[q], 0, d->filter,
                            q < 2 ? &m[q] : NULL, &e[q], NULL);
        if (st)
            return st;
        add(c, "%s%s: RMSE against the exact pyramid: tables %.4f (max %.3f), 5x5 %.4f (max "
               "%.3f); eye RMSE: tables %.4f, exact %.4f, 5x5 %.4f; time, tables / 5x5: ",
            k ? "; " : "", pat, m[0].rmse, m[0].max_err, m[1].rmse, m[1].max_err, e[0], e[2], e[1]);
        add_ratio(c, &ratio, 2);
        int v = aa_claim_compare(e[0], e[2], TIE) <= 0 &&
                aa_claim_compare(m[0].rmse, m[1].rmse, TIE) < 0;
        int worse = aa_claim_compare(m[0].rmse, m[1].rmse, TIE) > 0 ||
                    aa_claim_compare(e[0], e[2], TIE) > 0;
        yes += v, no += !v && worse;
        if (!v) {
            size_t u = strlen(failed);
            snprintf(failed + u, sizeof failed - u, "%s%s (eye %.0f%% above exact, RMSE %.2f "
                                                    "times 5x5's)",
                     u ? ", " : "", pat, 100 * (e[0] / e[2] - 1), m[0].rmse / m[1].rmse);
        }
    }
    add(c, ".");
    because(c, aa_claim_tally(yes, no, np - yes - no),
            "the tables match the exact filter by eye and beat 5x5 in RMSE on %d of %d scenes%s%s",
            yes, np, *failed ? "; not on " : "", failed);
    return AA_OK;
}

/* Crow's base resolution (ch. 1, "In Summary"), the scenes placed OFF off
 * the grid: area (methods[0], blending at the base resolution) against the
 * doubled and the quadrupled resolution (methods[1], [2]) by eye (area is
 * the box reference itself, so its RMSE says nothing); the tiler
 * (methods[3]) beside; and on the small objects (the last scene), whether
 * doubling helps: point (methods[4]) against the doubled resolution. */
static int crow_base(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int wins = 0, losses = 0, tiler_ties = 0;
    double small[2] = {0, 0};
    for (int k = 0; k < np; k++) {
        double e[4];
        aa_metrics b[5];
        for (int q = 0; q < 5; q++) {
            int st = metrics_at(x, d->patterns[k], d->size, filter_of(d, q), d->methods[q], OFF,
                                "box", &b[q], q < 4 ? &e[q] : NULL, NULL);
            if (st)
                return st;
        }
        int v1 = aa_claim_compare(e[0], e[1], TIE), v2 = aa_claim_compare(e[0], e[2], TIE);
        wins += v1 < 0 && v2 < 0;
        losses += v1 > 0 || v2 > 0;
        tiler_ties += aa_claim_compare(e[3], e[1], TIE) == 0;
        add(c, "%s%s: eye area %.4f, doubled %.4f, quadrupled %.4f, tiler %.4f; RMSE point "
               "%.4f, doubled %.4f, quadrupled %.4f",
            k ? "; " : "", d->patterns[k], e[0], e[1], e[2], e[3], b[4].rmse, b[1].rmse,
            b[2].rmse);
        if (k == np - 1)
            small[0] = b[4].rmse, small[1] = b[1].rmse;
    }
    int helps = aa_claim_compare(small[1], small[0], TIE) < 0;
    add(c, ". Scenes moved %.1f pixel right and down. Blending at the base resolution beats "
           "both by eye on %d of %d scenes; Crow's tiler ties the doubled resolution on %d; on "
           "%s doubling %s point's error (%.4f to %.4f).",
        OFF, wins, np, tiler_ties, d->patterns[np - 1], helps ? "cuts" : "keeps", small[0],
        small[1]);
    /* two parts: the base resolution superior; doubling no help to small objects */
    const char *v1 = aa_claim_tally(wins == np, losses > 0, wins < np && !losses);
    int yes = !strcmp(v1, "yes") + !helps, no = !strcmp(v1, "no") + helps;
    because(c, aa_claim_tally(yes, no, 2 - yes - no),
            "exact blending beats doubling by eye on %d of %d scenes, but doubling %s the small "
            "objects' error",
            wins, np, helps ? "does cut" : "does not cut");
    return AA_OK;
}

/* Crow's z-priority: the largest error of methods[0] (priority) beyond
 * that of methods[1] (scan), the worst over the scenes (each of several
 * layers, placed OFF off the grid), against the reference under the
 * row's filter. */
static int crow_priority(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    double worst = 0;
    for (int k = 0; k < np; k++) {
        aa_metrics m[2];
        for (int q = 0; q < 2; q++) {
            int st = metrics_at(x, d->patterns[k], d->size, d->filter, d->methods[q], OFF,
                                d->filter, &m[q], NULL, NULL);
            if (st)
                return st;
        }
        add(c, "%s%s: priority %.4f (max %.3f), scan %.4f (max %.3f)", k ? "; " : "",
            d->patterns[k], m[0].rmse, m[0].max_err, m[1].rmse, m[1].max_err);
        worst = fmax(worst, m[0].max_err - m[1].max_err);
    }
    add(c, ". Scenes moved %.1f pixel right and down. The z-priority errors sit where three "
           "surfaces share a dot or polygons meet without sharing an edge (his fig. 3.6); a "
           "largest error above 0.1 (a tenth of full scale, fixed beforehand) is visible.",
        OFF);
    because(c, worst < 0.1 ? "yes" : "partly",
            "priority's largest error exceeds scan's by %.3f: %s", worst,
            worst < 0.1 ? "not visible" : "visible at a few dots, acceptable elsewhere");
    return AA_OK;
}

/* Crow's temporal scheme: this row's cost (one frame of methods[1] and
 * [2] over point, methods[0]) and the next row's look (the next row's
 * methods point, hexagon, area moving over its patterns, the last of
 * them `dots`). */
static int crow_hexagon(const cx *x, const claim_row *d, claim *c)
{
    claim *cost = &c[0], *look = &c[1];
    const claim_row *dl = &d[1];
    int yes = 0, no = 0, ncase = 0;
    add(cost, "time of a frame / point's:");
    for (int k = 0; d->patterns[k]; k++, ncase++) {
        tratio fixed, screen;
        const char *scene = d->patterns[k];
        tcase p = {scene, d->size, d->filter, d->methods[0], 1},
              hf = {scene, d->size, d->filter, d->methods[1], 1},
              hs = {scene, d->size, d->filter, d->methods[2], 1};
        int st = time_ratio(x, &p, &hf, &fixed);
        if (!st)
            st = time_ratio(x, &p, &hs, &screen);
        if (st)
            return st;
        const char *v = aa_claim_band_verdict(fixed.lo, fixed.hi, 0, 1.25);
        yes += !strcmp(v, "yes"), no += !strcmp(v, "no");
        add(cost, "%s %s fixed ", k ? ";" : "", scene);
        add_ratio(cost, &fixed, 2);
        add(cost, ", screen ");
        add_ratio(cost, &screen, 2);
    }
    add(cost, " (\"virtually no\" taken as under 1.25, for display=fixed, his display).");
    because(cost, aa_claim_tally(yes, no, ncase - yes - no),
            "%d of %d intervals of a fixed frame's time lie under 1.25, %d wholly above", yes,
            ncase, no);

    const int nl = count_of(dl->patterns);
    int fewer = 0;
    add(look, "eye RMSE, hexagon / point:");
    for (int k = 0; k < nl - 1; k++) {
        aa_row *r;
        size_t n;
        int st = run_view(x, dl->patterns[k], dl->size, dl->filter, dl->methods, 3, MOVE_X,
                          MOVE_Y, &r, &n);
        if (st)
            return st;
        add(look, "%s %s %.4f / %.4f", k ? ";" : "", dl->patterns[k], r[1].tm.eye_rmse,
            r[0].tm.eye_rmse);
        fewer += r[1].tm.eye_rmse < 0.9 * r[0].tm.eye_rmse;
        free(r);
    }
    aa_row *dots;
    size_t n;
    int st = run_view(x, dl->patterns[nl - 1], dl->size, dl->filter, dl->methods, 3, MOVE_X,
                      MOVE_Y, &dots, &n);
    if (st)
        return st;
    add(look, ". dots: popping hexagon %.3f, point %.3f, area %.3f; flicker hexagon %.4f, "
              "point %.4f, area %.4f. A reduction of at least 10%% is counted as significant.",
        dots[1].tm.popping, dots[0].tm.popping, dots[2].tm.popping, dots[1].tm.flicker_mean,
        dots[0].tm.flicker_mean, dots[2].tm.flicker_mean);
    int flick = dots[1].tm.popping > 0.01 && dots[1].tm.flicker_mean > 10 * dots[2].tm.flicker_mean;
    because(look, fewer == nl - 1 && flick ? "yes" : (fewer || flick) ? "partly" : "no",
            "the eye's error falls by 10%% or more on %d of %d scenes; small objects %s",
            fewer, nl - 1, flick ? "pop and flicker" : "do not flicker measurably");
    free(dots);
    return AA_OK;
}

/* The point image of a scene under the best optical blur (the eye's
 * Gaussian, s from 0.25 to 1.5 pixel): its RMSE against the box reference
 * and the s that gives it. */
static int best_blur(const cx *x, const char *scene, int w, double *best, double *best_s)
{
    aa_image pimg = {0};
    aa_metrics pm;
    *best = INFINITY, *best_s = 0;
    int st = image_of(x, scene, w, "box", "point", &pimg, NULL, &pm);
    if (st)
        return st;
    aa_view view;
    aa_image ref = {0};
    memset(&view, 0, sizeof view);
    view.w = view.h = w;
    if (!(st = aa_pattern_parse(scene, &view.pattern)) &&
        !(st = aa_filter_parse("box", &view.filter)))
        st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL);
    for (double s = 0.25; s <= 1.5 + 1e-9 && !st; s += 0.05) {
        aa_image b;
        aa_metrics bm;
        if ((st = aa_eye_blur(&pimg, s, &b)))
            break;
        st = aa_metrics_compute(&ref, &b, NULL, &bm);
        aa_image_free(&b);
        if (!st && bm.rmse < *best)
            *best = bm.rmse, *best_s = s;
    }
    aa_image_free(&pimg);
    aa_image_free(&ref);
    return st;
}

/* Crow's post-processing: this row's trio (methods point, trio, area:
 * staircase energy on the first two scenes, lost detail on the others)
 * and the next row's recursive filter (methods[3]) against the best blur
 * of the point image. */
static int crow_post(const cx *x, const claim_row *d, claim *c)
{
    claim *trio = &c[0], *rec = &c[1];
    const int np = count_of(d->patterns);
    double removed_min = 1;
    int lost = 0, rec_no_better = 0;
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_row *r;
        size_t n;
        int st = run_view(x, scene, d->size, d->filter, d->methods, 4, 0, 0, &r, &n);
        if (st)
            return st;
        if (k < 2) {
            double removed = 1 - r[1].m.alias_high / r[0].m.alias_high;
            removed_min = fmin(removed_min, removed);
            add(trio, "%s%s: staircase energy point %.2e, trio %.2e (%.0f%% removed), area "
                      "%.1e",
                k ? "; " : "", scene, r[0].m.alias_high, r[1].m.alias_high, 100 * removed,
                r[2].m.alias_high);
            if (k == 0) {
                tratio ratio;
                tcase p = {scene, d->size, d->filter, d->methods[0], 0},
                      t = {scene, d->size, d->filter, d->methods[1], 0};
                if ((st = time_ratio(x, &p, &t, &ratio))) {
                    free(r);
                    return st;
                }
                add(trio, ", time trio / point ");
                add_ratio(trio, &ratio, 1);
            }
        } else {
            add(trio, "; %s: RMSE point %.4f, trio %.4f, area %.1e", scene, r[0].m.rmse,
                r[1].m.rmse, r[2].m.rmse);
            lost += r[1].m.rmse > 0.5 * r[0].m.rmse;
        }
        double best, best_s;
        if ((st = best_blur(x, scene, d->size, &best, &best_s))) {
            free(r);
            return st;
        }
        add(rec, "%s%s: point %.4f, recursive %.4f, blur %.4f (s = %.2f)", k ? "; " : "", scene,
            r[0].m.rmse, r[3].m.rmse, best, best_s);
        rec_no_better += r[3].m.rmse > 0.9 * best;
        free(r);
    }
    add(trio, ". Trio removes at least %.0f%% of the staircase energy, not all of it; lost "
              "detail stays lost on %d of %d scenes.",
        100 * removed_min, lost, np - 2);
    because(trio, removed_min > 0.95 ? (lost == np - 2 ? "yes" : "partly") : "partly",
            "trio leaves %.0f%% of the staircase energy (\"completely\" taken as 95%% "
            "removed); lost detail stays lost on %d of %d scenes",
            100 * (1 - removed_min), lost, np - 2);
    add(rec, ". The recursive filter does no better than the best blur (within 10%%) on %d of "
             "%d scenes.",
        rec_no_better, np);
    because(rec, rec_no_better == np ? "yes" : rec_no_better ? "partly" : "no",
            "the recursive filter is no better than the best optical blur on %d of %d scenes",
            rec_no_better, np);
    return AA_OK;
}

/* Morphological antialiasing (Reshetov): this row's quality and cost of
 * mlaa (methods[1]) against point (methods[0]), and the next row's
 * comparison of mlaa with 4x and 8x multisampling (methods[2], [3]).
 * Errors within TIE are a tie; the cost is the interleaved ratio mlaa /
 * point with its interval, judged against the band [0, 1.25] ("no
 * noticeable impact", fixed before measuring). */
static int mlaa_claims(const cx *x, const claim_row *d, claim *c)
{
    claim *cost = &c[0], *msaa = &c[1];
    const int np = count_of(d->patterns);
    int better = 0, worse = 0, between = 0, outside = 0;
    tratio ratio = {NAN, NAN, NAN};
    const char *timed = "";
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_row *r;
        size_t n;
        int st = run_view(x, scene, d->size, d->filter, d->methods, 4, 0, 0, &r, &n);
        if (st)
            return st;
        int v = aa_claim_compare(r[1].m.rmse, r[0].m.rmse, TIE);
        better += v < 0;
        worse += v > 0;
        int in = aa_claim_compare(r[1].m.rmse, r[2].m.rmse, TIE) <= 0 &&
                 aa_claim_compare(r[1].m.rmse, r[3].m.rmse, TIE) >= 0;
        between += in;
        outside += !in;
        add(cost, "%s%s: RMSE point %.4f, mlaa %.4f", k ? "; " : "", scene, r[0].m.rmse,
            r[1].m.rmse);
        add(msaa, "%s%s: mlaa %.4f, msaa4 %.4f, msaa8 %.4f", k ? "; " : "", scene,
            r[1].m.rmse, r[2].m.rmse, r[3].m.rmse);
        if (k == 0) {
            tcase p = {scene, d->size, d->filter, d->methods[0], 0},
                  m = {scene, d->size, d->filter, d->methods[1], 0};
            timed = scene;
            if ((st = time_ratio(x, &p, &m, &ratio))) {
                free(r);
                return st;
            }
        }
        free(r);
    }
    add(cost, ". Time mlaa / point on %s: ", timed);
    add_ratio(cost, &ratio, 2);
    add(cost, " (\"no noticeable impact\" taken as under 1.25). Quality improves on %d of %d "
              "scenes (errors within %.0f%% a tie).",
        better, np, 100 * TIE);
    const char *q = aa_claim_tally(better == np, better < np, 0);
    const char *t = aa_claim_band_verdict(ratio.lo, ratio.hi, 0, 1.25);
    if (strcmp(q, "yes"))
        because(cost, better ? "partly" : "no",
                "mlaa improves on point on %d of %d scenes (worse on %d)", better, np, worse);
    else if (!strcmp(t, "yes"))
        because(cost, "yes", "better on every scene, and the time ratio's interval is under 1.25");
    else
        because(cost, "partly",
                "better on every scene; the cost half is not comparable: the time over a point "
                "sampler that does almost no work per pixel (%.2f) overstates the cost over "
                "Reshetov's ray tracer",
                ratio.median);
    add(msaa, ". MLAA lies between them (within %.0f%%) on %d of %d scenes.", 100 * TIE,
        between, np);
    because(msaa, aa_claim_tally(between, outside, 0),
            "mlaa's RMSE lies between msaa8's and msaa4's on %d of %d scenes", between, np);
    return AA_OK;
}

/* SMAA against the approaches before it (mlaa, fxaa: methods[1], [2]) and
 * its distance to supersampling (methods[3]), point (methods[0]) beside.
 * A scene counts for the claim when smaa's RMSE is below both by more than
 * TIE, against it when above either by more than TIE; else it is a tie. */
static int smaa_claims(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int wins = 0, losses = 0, ties = 0;
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_row *r;
        size_t n;
        int st = run_view(x, scene, d->size, d->filter, d->methods, 5, 0, 0, &r, &n);
        if (st)
            return st;
        int vm = aa_claim_compare(r[3].m.rmse, r[1].m.rmse, TIE),
            vf = aa_claim_compare(r[3].m.rmse, r[2].m.rmse, TIE);
        if (vm < 0 && vf < 0)
            wins++;
        else if (vm > 0 || vf > 0)
            losses++;
        else
            ties++;
        add(c, "%s%s: point %.4f, mlaa %.4f, fxaa %.4f, smaa %.4f, 16x supersampling %.4f",
            k ? "; " : "", scene, r[0].m.rmse, r[1].m.rmse, r[2].m.rmse, r[3].m.rmse,
            r[4].m.rmse);
        free(r);
    }
    add(c, ". SMAA 1x is below both MLAA and FXAA on %d of %d scenes, above one of them on %d "
           "(errors within %.0f%% a tie).",
        wins, np, losses, 100 * TIE);
    because(c, aa_claim_tally(wins, losses, ties && !wins && !losses),
            "smaa below mlaa and fxaa on %d of %d scenes, above either on %d, tied on %d", wins,
            np, losses, ties);
    return AA_OK;
}

/* Crow's colour map: the calibration's least fringes (calibration.c). */
static int crow_colour_map(const cx *x, const claim_row *d, claim *c)
{
    (void)d;
    aa_calibration cal;
    say(x, "colour map calibration");
    int st = aa_crow_calibration(x->cache, x->threads, &cal);
    if (st)
        return st;
    add(c, "least fringes at g = %.3f (crowtable), %.3f (exact); fringes at g = 1, 2, 4: "
           "%.4f, %.4f, %.4f. With ideal square dots seen in linear light the least moire is "
           "at a linear response by construction (Jensen's inequality); g = 2 would be least "
           "only for an eye averaging the square root of intensity.",
        cal.gmin_fringe[0], cal.gmin_fringe[1], cal.map_fringe[0][1], cal.map_fringe[0][0],
        cal.map_fringe[0][2]);
    because(c, "not comparable",
            "the model has ideal square dots and a linear-light eye, where g = 1 is least by "
            "construction; Crow's CRT spot and the eye's nonlinearity are not modelled");
    return AA_OK;
}

/* The point image of a scene under the best optical blur chosen by eye:
 * the blurred image (the eye's Gaussian of s from 0.25 to 1.5 pixel) that
 * an eye of AA_EYE_S sees closest to the scene; its eye RMSE, the s that
 * gives it, and its RMSE against the box reference. */
static int best_blur_eye(const cx *x, const char *scene, int w, double *best, double *best_s,
                         double *rmse)
{
    aa_image pimg = {0}, truth = {0}, ref = {0};
    aa_spec ps;
    *best = INFINITY, *best_s = 0, *rmse = NAN;
    int st = image_of(x, scene, w, "box", "point", &pimg, NULL, NULL);
    if (!st && !(st = aa_pattern_parse(scene, &ps)))
        st = aa_eye_truth(&ps, w, w, 0, 0, 0, AA_EYE_S, x->cache, x->threads, &truth);
    if (!st)
        st = reference_of(x, scene, w, "box", &ref);
    for (double s = 0.25; s <= 1.5 + 1e-9 && !st; s += 0.05) {
        aa_image b;
        aa_metrics bm;
        double e;
        if ((st = aa_eye_blur(&pimg, s, &b)))
            break;
        if (!(st = aa_eye_rmse(&b, &truth, AA_EYE_S, &e)) && e < *best) {
            *best = e, *best_s = s;
            if (!(st = aa_metrics_compute(&ref, &b, NULL, &bm)))
                *rmse = bm.rmse;
        }
        aa_image_free(&b);
    }
    aa_image_free(&pimg);
    aa_image_free(&truth);
    aa_image_free(&ref);
    return st;
}

/* Sancha's compromise (methods[1]) against the best optical blur of the
 * point image (methods[0]) by what the eye sees; a scene counts for the
 * claim when the compromise's eye RMSE is below the blur's by more than
 * TIE, against it when above by more than TIE. */
static int crow_sancha(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int better = 0, worse = 0;
    add(c, "eye RMSE (RMSE against the box reference):");
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        double es, ep, eb, sb, rb;
        aa_metrics ms, mp;
        aa_image img = {0};
        int st = image_of(x, scene, d->size, d->filter, d->methods[1], &img, &es, &ms);
        aa_image_free(&img);
        if (!st)
            st = image_of(x, scene, d->size, d->filter, d->methods[0], &img, &ep, &mp);
        aa_image_free(&img);
        if (!st)
            st = best_blur_eye(x, scene, d->size, &eb, &sb, &rb);
        if (st)
            return st;
        int v = aa_claim_compare(es, eb, TIE);
        better += v < 0, worse += v > 0;
        add(c, "%s %s: point %.4f (%.4f), sancha %.4f (%.4f), best blur %.4f (%.4f, s = %.2f)",
            k ? ";" : "", scene, ep, mp.rmse, es, ms.rmse, eb, rb, sb);
    }
    add(c, ". Sancha's compromise is below the best blur by eye on %d of %d scenes, above it on "
           "%d (within %.0f%% a tie).",
        better, np, worse, 100 * TIE);
    because(c, aa_claim_tally(better, worse, np - better - worse),
            "by eye the compromise beats the best optical blur on %d of %d scenes, loses on %d, "
            "ties on %d",
            better, np, worse, np - better - worse);
    return AA_OK;
}

/* The reference of a view placed `off` pixels right and down, as
 * image_at places it. */
static int reference_at(const cx *x, const char *pattern, int w, const char *filter, double off,
                        aa_image *out)
{
    aa_view view;
    memset(&view, 0, sizeof view);
    view.w = view.h = w;
    view.t = off, view.vx = view.vy = off != 0 ? 1 : 0;
    int st = aa_pattern_parse(pattern, &view.pattern);
    if (!st)
        st = aa_filter_parse(filter, &view.filter);
    if (!st)
        st = aa_reference(&view, x->cache, x->threads, out, NULL, NULL);
    return st;
}

/* The dots of img off from ref by more than e in some channel. */
static int dots_above(const aa_image *img, const aa_image *ref, double e)
{
    int n = 0;
    for (size_t o = 0; o < (size_t)img->w * (size_t)img->h; o++)
        for (int ch = 0; ch < 3; ch++)
            if (fabs(img->v[3 * o + ch] - ref->v[3 * o + ch]) > e) {
                n++;
                break;
            }
    return n;
}

/* Crow's z-buffer: the tiler with exact areas writing front to back into a
 * z-buffer (methods[0]), in the z-priority order (methods[1]) and by the
 * scanning algorithm (methods[2]), the scenes placed OFF off the grid:
 * the largest error against the reference and the dots off by more than
 * a tenth of full scale (visible, fixed beforehand). */
static int crow_zbuffer(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int lost = 0, worse = 0;
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_image ref = {0};
        double worst[3];
        int seen[3];
        int st = reference_at(x, scene, d->size, d->filter, OFF, &ref);
        for (int q = 0; q < 3 && !st; q++) {
            aa_image img = {0};
            aa_metrics m;
            st = image_at(x, scene, d->size, d->filter, d->methods[q], OFF, &img, NULL,
                          d->filter, &m, NULL);
            if (!st)
                worst[q] = m.max_err, seen[q] = dots_above(&img, &ref, 0.1);
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        if (st)
            return st;
        add(c, "%s%s: largest error z-buffer %.3f, priority %.3f, scan %.1e; dots off by more "
               "than 0.1: %d, %d, %d",
            k ? "; " : "", scene, worst[0], worst[1], worst[2], seen[0], seen[1], seen[2]);
        lost += worst[0] > 0.1 && worst[2] < 0.01;
        worse += seen[0] >= 2 * seen[1] && seen[0] > 0;
    }
    add(c, ". Scenes moved %.1f pixel right and down. A dot off by more than 0.1 (a tenth of "
           "full scale) counts as visible; \"many more problems\" taken as at least twice the "
           "z-priority's visible dots.",
        OFF);
    /* each scene a case of each part: the loss seen, and the more problems */
    because(c, aa_claim_tally(lost + worse, 2 * np - lost - worse, 0),
            "the z-buffer shows visible errors where the scanning algorithm has none on %d of %d "
            "scenes, and at least twice the z-priority's visible dots on %d",
            lost, np, worse);
    return AA_OK;
}

/* Catmull's thin line (patterns/svg/thinline.svg: ends THIN_X0, THIN_X1 of
 * the unit square): at 128, 256 and 512 pixels, the share of the columns
 * the line crosses where point sampling (methods[0]) shows nothing, and
 * what an eye seeing the picture from the same distance (s = 1, 2, 4
 * pixels) sees of point and area (methods[1]) against the line. */
#define THIN_X0 0.03
#define THIN_X1 0.97
static int catmull_thin(const cx *x, const claim_row *d, claim *c)
{
    static const int sizes[] = {128, 256, 512};
    const char *pat = d->patterns[0];
    double gaps[3], ep[3], ea[3];
    aa_spec ps;
    int st = aa_pattern_parse(pat, &ps);
    for (int k = 0; k < 3 && !st; k++) {
        const int w = sizes[k];
        const double s = w / 128.0;
        aa_image pt = {0}, ar = {0}, truth = {0};
        st = image_at(x, pat, w, d->filter, d->methods[0], 0, &pt, NULL, NULL, NULL, NULL);
        if (!st)
            st = image_at(x, pat, w, d->filter, d->methods[1], 0, &ar, NULL, NULL, NULL, NULL);
        if (!st)
            st = aa_eye_truth(&ps, w, w, 0, 0, 0, s, x->cache, x->threads, &truth);
        if (!st)
            st = aa_eye_rmse(&pt, &truth, s, &ep[k]);
        if (!st)
            st = aa_eye_rmse(&ar, &truth, s, &ea[k]);
        if (!st) {
            /* the columns wholly inside the line's span, two pixels in */
            int i0 = (int)ceil(THIN_X0 * w) + 2, i1 = (int)floor(THIN_X1 * w) - 2, dark = 0;
            for (int i = i0; i < i1; i++) {
                double most = 0;
                for (int j = 0; j < w; j++)
                    most = fmax(most, pt.v[((size_t)j * (size_t)w + (size_t)i) * 3]);
                dark += most == 0;
            }
            gaps[k] = (double)dark / (double)(i1 - i0);
        }
        aa_image_free(&pt);
        aa_image_free(&ar);
        aa_image_free(&truth);
        if (!st)
            add(c, "%s%dx%d (eye s = %g): point dark in %.0f%% of the line's columns; eye RMSE "
                   "point %.5f, area %.5f",
                k ? "; " : "", w, w, s, 100 * gaps[k], ep[k], ea[k]);
    }
    if (st)
        return st;
    int dotted = gaps[0] >= 0.25 && gaps[1] >= 0.25 && gaps[2] >= 0.25;
    int nice = ea[2] <= ea[0] / 2;
    int wrong = 1;
    for (int k = 0; k < 3; k++)
        wrong = wrong && aa_claim_compare(ep[k], ea[k], TIE) > 0;
    add(c, ". From 128 to 512 area's eye RMSE falls %.1f times, point's %.1f times. Dotted taken "
           "as a quarter of the columns dark or more; a nice line as area's eye RMSE falling "
           "at least 2 times; point wrong as its eye RMSE above area's by more than %.0f%% at "
           "every size.",
        ea[0] / ea[2], ep[0] / ep[2], 100 * TIE);
    because(c, aa_claim_tally(dotted + nice + wrong, 3 - dotted - nice - wrong, 0),
            "point leaves %.0f%% to %.0f%% of the columns dark (%s); area's eye error falls "
            "%.1f times (%s); point's eye error is %s area's at every size (%.0f times at 512)",
            100 * fmin(gaps[0], fmin(gaps[1], gaps[2])),
            100 * fmax(gaps[0], fmax(gaps[1], gaps[2])), dotted ? "dotted" : "not dotted",
            ea[0] / ea[2], nice ? "a nice line" : "not a nice line",
            wrong ? "above" : "not always above", ep[2] / ea[2]);
    return AA_OK;
}
#undef THIN_X0
#undef THIN_X1

/* Feibush et al.'s one table per filter shape: their edge filter
 * (methods[k], each under filters[k]: one shape at several sizes) against
 * the exact reference under the same filter, on each scene.  The table
 * serves every size when each RMSE is under half a step of their 8-bit
 * channels, 1/510 (fixed beforehand). */
static int feibush_sizes(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns), nm = count_of(d->methods);
    const double step = 1.0 / 510;
    int in = 0, n = 0;
    double most = 0;
    add(c, "RMSE (largest error) against the exact reference:");
    for (int k = 0; k < np; k++)
        for (int q = 0; q < nm; q++, n++) {
            aa_metrics m;
            int st = metrics_at(x, d->patterns[k], d->size, filter_of(d, q), d->methods[q], 0,
                                filter_of(d, q), &m, NULL, NULL);
            if (st)
                return st;
            in += m.rmse < step;
            most = fmax(most, m.rmse);
            add(c, "%s %s %s %.1e (%.1e)", n ? ";" : "", d->patterns[k], filter_of(d, q),
                m.rmse, m.max_err);
        }
    add(c, ". Half a step of 8 bits: %.1e.", step);
    because(c, in == n ? "yes" : in ? "partly" : "no",
            "%d of %d RMSEs under half an 8-bit step (largest %.1e), the same table read at "
            "every size",
            in, n, most);
    return AA_OK;
}

/* The RMSE over the pixels of a class (mask[o] non-zero), every channel. */
static double class_rmse(const aa_image *img, const aa_image *ref, const unsigned char *mask,
                         int *count)
{
    double sum = 0;
    int n = 0;
    for (size_t o = 0; o < (size_t)img->w * (size_t)img->h; o++) {
        if (!mask[o])
            continue;
        for (int ch = 0; ch < 3; ch++) {
            double e = img->v[3 * o + ch] - ref->v[3 * o + ch];
            sum += e * e;
        }
        n++;
    }
    *count = n;
    return n ? sqrt(sum / (3.0 * n)) : NAN;
}

/* Feibush et al.'s fig. 4e: on feibush:stripes=M (the square's corners,
 * in pattern units, those of patterns/feibush.c; its left edge from
 * corner 3 to corner 0), the error of each method (methods[k]) against the
 * exact reference over the dots along the polygon's left edge (the edge
 * filter's work) and over the dots inside the square along the stripes
 * (the texture filter's); equivalent when both are under half a step of
 * their 8-bit channels, 1/510 (fixed beforehand). */
static int feibush_edges(const cx *x, const claim_row *d, claim *c)
{
    static const double c0[2] = {0.32, 0.18}, c3[2] = {0.04, 0.90};
    const int w = d->size, nm = count_of(d->methods);
    const double step = 1.0 / 510;
    aa_image ref = {0};
    unsigned char *edge = calloc((size_t)w * (size_t)w, 1),
                  *stripe = calloc((size_t)w * (size_t)w, 1);
    int st = edge && stripe ? reference_of(x, d->patterns[0], w, d->filter, &ref)
                            : aa_fail(AA_ENOMEM, "out of memory");
    double ex = (c0[0] - c3[0]) * w, ey = (c0[1] - c3[1]) * w, len = hypot(ex, ey);
    for (int j = 0; j < w && !st; j++)
        for (int i = 0; i < w; i++) {
            size_t o = (size_t)j * (size_t)w + (size_t)i;
            double r = ref.v[3 * o], g = ref.v[3 * o + 1];
            double px = i + 0.5 - c3[0] * w, py = j + 0.5 - c3[1] * w;
            double along = (px * ex + py * ey) / len, across = (px * ey - py * ex) / len;
            edge[o] = r > 1e-9 && r < 1 - 1e-9 && fabs(across) < 3 && along > 4 && along < len - 4;
            stripe[o] = r > 1 - 1e-12 && g > 1e-9 && g < 1 - 1e-9;
        }
    double first[2] = {NAN, NAN};
    add(c, "RMSE over the dots along the left edge / along the stripes inside:");
    for (int k = 0; k < nm && !st; k++) {
        aa_image img = {0};
        st = image_at(x, d->patterns[0], w, d->filter, d->methods[k], 0, &img, NULL, NULL, NULL,
                      NULL);
        if (!st) {
            int ne, ns;
            double re = class_rmse(&img, &ref, edge, &ne), rs = class_rmse(&img, &ref, stripe, &ns);
            add(c, "%s %s %.1e / %.1e (%d and %d dots)", k ? ";" : "", d->labels[k], re, rs, ne,
                ns);
            if (k == 0)
                first[0] = re, first[1] = rs;
        }
        aa_image_free(&img);
    }
    aa_image_free(&ref);
    free(edge);
    free(stripe);
    if (st)
        return st;
    add(c, ". Equivalent taken as both under half a step of 8 bits, %.1e.", step);
    int edge_ok = first[0] < step, stripe_ok = first[1] < step;
    because(c, edge_ok && stripe_ok ? "yes" : "no",
            "their system errs by %.1e along the polygon's edge and %.1e along the stripes: %s",
            first[0], first[1],
            edge_ok && stripe_ok ? "both under half an 8-bit step"
            : edge_ok || stripe_ok ? "one under half an 8-bit step, the other not"
                                   : "neither under half an 8-bit step");
    return AA_OK;
}

/* Ramos and Borges' difficult cases (sec. 6), one scene each: the
 * polygons of each case are the only green of its scene, so what the
 * method misses of them is its green channel's error.  A case fails as the
 * paper says (the polygon ignored) when adaptive (methods[0]) misses at
 * least 90% of the green (its green RMSE within TIE of that of no green at
 * all); methods[1], [2] beside. */
static int rb_cases(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int ignored = 0;
    add(c, "green RMSE against the reference / the reference's own green RMS:");
    for (int k = 0; k < np; k++) {
        aa_image ref = {0};
        int st = reference_of(x, d->patterns[k], d->size, "box", &ref);
        double g0 = 0, share[3];
        const size_t n = (size_t)d->size * (size_t)d->size;
        for (size_t o = 0; o < n && !st; o++)
            g0 += ref.v[3 * o + 1] * ref.v[3 * o + 1];
        g0 = sqrt(g0 / (double)n);
        for (int q = 0; q < 3 && !st; q++) {
            aa_image img = {0};
            st = image_at(x, d->patterns[k], d->size, d->filter, d->methods[q], 0, &img, NULL,
                          NULL, NULL, NULL);
            double e = 0;
            for (size_t o = 0; o < n && !st; o++) {
                double v = img.v[3 * o + 1] - ref.v[3 * o + 1];
                e += v * v;
            }
            share[q] = sqrt(e / (double)n) / g0;
            aa_image_free(&img);
        }
        aa_image_free(&ref);
        if (st)
            return st;
        const char *name = strrchr(d->patterns[k], '/');
        add(c, "%s %s: %s %.2f, %s %.2f, %s %.2f", k ? ";" : "", name ? name + 1 : d->patterns[k],
            d->labels[0], share[0], d->labels[1], share[1], d->labels[2], share[2]);
        ignored += share[0] >= 1 - TIE;
    }
    add(c, ". A share of 1 is the green missed wholly; \"ignored\" taken as at least %.2f.",
        1 - TIE);
    because(c, aa_claim_tally(ignored, np - ignored, 0),
            "adaptive ignores the case's polygons on %d of %d scenes, as the paper says", ignored,
            np);
    return AA_OK;
}

/* ---- the claims ---- */

#define PAIR(p, w, f, ma, mb, label) {{p, w, f, ma, 0}, {p, w, f, mb, 0}, label}
#define FILTERS(p, w, m, label) {{p, w, "gauss:s=1", m, 0}, {p, w, "cone:r=2", m, 0}, label}
#define DOUBLE(p, m) {{p, 256, "box", m, 0}, {p, 512, "box", m, 0}, p " " m}

static const claim_row claims[] = {
    {
        .paper = "Ramos and Borges",
        .where = "sec. 7 (\"Resultados\")",
        .claim = "\"Embora não fizessemos uma medida precisa e sistemática, realizamos alguns "
            "testes gerando diversos tipos de cenas. Executamos o algoritmo removendo o "
            "algoritmo de anti-aliasing e chegamos a um decréscimo de tempo inferior a 30% na "
            "média\": though they made no precise or systematic measurement, in some tests "
            "on several kinds of scene the time fell by less than 30% on average without the "
            "antialiasing.",
        .setting = "adaptive (the paper's method, tag=0) against point (runs of pixel centres "
            "between crossings) and against adaptive:threshold=1 (the same corner sampler, "
            "every pixel's corners queried, its search never started: the antialiasing "
            "removed), crow, star, feibush, catmull:tiles=4 and slivers at 256x256, box; "
            "one thread, the median of the ratios of interleaved renders and its 95% "
            "interval.",
        .patterns = LIST("crow", "star", "feibush", "catmull:tiles=4", "slivers"), .size = 256,
        .filter = "box",
        .methods = LIST("point", "adaptive", "supersample:n=2", "supersample:n=3",
                        "adaptive:threshold=1"),
        .measure = ramos_borges,
    },
    {
        .paper = "Ramos and Borges",
        .where = "abstract; sec. 3",
        .claim = "\"in general, the algorithm produces a better result than that obtained "
            "with usual implementations of non-adaptative supersampling\"; for a single "
            "edge \"o método, neste caso, é muito melhor que super-amostragem simples\".",
        .setting = "adaptive against supersample:n=2 and n=3 (regular grids of 4 and 9 "
            "samples), the counts bracketing adaptive's own samples per pixel; the same "
            "scenes moved 0.3 pixel right and down (unmoved, catmull:tiles=4 puts every edge "
            "on a pixel boundary, where a grid is exact and corners sit on edges); RMSE "
            "against the box reference, errors within 10% a tie.",
        .patterns = LIST("crow", "star", "feibush", "catmull:tiles=4", "slivers"), .size = 256,
        .filter = "box",
        .methods = LIST("adaptive", "supersample:n=2", "supersample:n=3"),
    },
    {
        .paper = "Catmull 1978",
        .where = "\"Implementation\"",
        .claim = "\"The user can request jagged edges with the result that the program runs "
            "approximately three times faster for complicated pictures.\"",
        .setting = "area (Catmull's recursive pixel integrater where polygons cross a pixel) "
            "against point, on catmull:tiles=32 (256x256: pixels of three polygons), "
            "feibush:stripes=200 (512x512), star (256x256); one thread, the median of the "
            "ratios of interleaved renders.",
        .pairs = (const tpair[]){PAIR("catmull:tiles=32", 256, "box", "point", "area",
                                      "catmull:tiles=32"),
                                 PAIR("feibush:stripes=200", 512, "box", "point", "area",
                                      "feibush:stripes=200"),
                                 PAIR("star", 256, "box", "point", "area", "star"),
                                 {{0}, {0}, NULL}},
        .head = "area time / point time:", .digits = 1, .lo = 2, .hi = 4.5,
        .tail = " (\"approximately three\" taken as 2 to 4.5). Catmull's ratio is between his "
                "program with and without the integrater; here both fill the runs between "
                "crossings, so the ratio is the integrater's extra cost where edges are.",
        .measure = time_sweep,
    },
    {
        .paper = "Catmull 1978",
        .where = "\"Anti-aliasing\"",
        .claim = "\"The sum of all intensities for an area sampled picture will be constant under "
            "translation\", while with point sampling \"for a fine picket fence the picture "
            "can be all white in one picture and all black in the next\".",
        .setting = "fence (bars 0.9 pixel apart) at 128x128 moving (0.37, 0.11) pixel a frame, "
            "24 frames: (max - min)/mean of the total intensity.",
        .patterns = LIST("fence"), .size = 128, .filter = "box",
        .methods = LIST("point", "area"), .measure = catmull_constant,
    },
    {
        .paper = "Feibush, Levoy and Cook 1980",
        .where = "sec. 5 (\"Conclusions\")",
        .claim = "\"If the filter's weighting function is stored in a lookup table instead of "
            "being computed at each pixel, an image can be computed in the same amount of "
            "time regardless of the complexity of the filter.\"",
        .setting = "their edge filter (conetable) and their texture filter with it (feibushtex) "
            "with the Gaussian (gauss:s=1, mask radius 2 s) and with the cone (cone:r=2, "
            "the same mask): feibush:stripes=200 at 512x512 (the edge filter) and "
            "256x256 (the texture filter), feibush and crow at 256x256; one thread, the "
            "median of the ratios of interleaved renders.",
        .pairs = (const tpair[]){FILTERS("feibush:stripes=200", 512, "conetable",
                                         "conetable feibush:stripes=200 512x512"),
                                 FILTERS("feibush", 256, "conetable", "conetable feibush 256x256"),
                                 FILTERS("crow", 256, "conetable", "conetable crow 256x256"),
                                 FILTERS("feibush:stripes=200", 256, "feibushtex",
                                         "feibushtex feibush:stripes=200 256x256"),
                                 FILTERS("crow", 256, "feibushtex", "feibushtex crow 256x256"),
                                 {{0}, {0}, NULL}},
        .head = "time with the cone / with the Gaussian:", .digits = 2, .lo = 0.9, .hi = 1.1,
        .tail = " (the same within 10%). The mask's size still sets the time: the tables are "
                "read for each edge and texture point inside it.",
        .measure = time_sweep,
        .not_comparable = "both filters are read from tables here, so equal times hold by "
            "construction; nothing computes the weight at each point to compare with",
    },
    {
        .paper = "Feibush, Levoy and Cook 1980",
        .where = "sec. 3 (\"Examples\"), figs. 4b-4d",
        .claim = "No filter is \"completely unsatisfactory\"; \"an unweighted filter is better "
            "and nearly satisfactory along the edges, but Moire is still evident in the "
            "center of the polygon. The weighted filter, however, produces an excellent "
            "image.\"",
        .setting = "feibush:stripes=200 at 512x512 (fig-feibush-4b..4d): point, area (box) and "
            "their texture and edge filters (feibushtex:texels=1000, gauss:s=1, mask 2 s). "
            "The moire of point sampling lands at low "
            "frequencies, where an eye of s = 2 pixels sees it (eye RMSE); the unweighted "
            "filter's is the stripes' content just below the Nyquist limit, which beats "
            "with the dots into fringes (beat energy: the image's power above 0.35 cycle "
            "per pixel).",
        .patterns = LIST("feibush:stripes=200"), .size = 512,
        .filters = LIST("box", "box", "gauss:s=1"),
        .methods = LIST("point", "area", "feibushtex:texels=1000"), .measure = feibush_quality,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 2, \"Evaluating convolutional filters\", pp. 37-41, figs. 2.10-2.14",
        .claim = "The figures \"illustrate the effectiveness of various filters\"; the filter "
            "kept is the pyramid two dots wide (fig. 2.14; \"The filters used in this work "
            "always cover an area two picture elements square\", ch. 3, pp. 56-60).",
        .setting = "crow 256x256, the methods of figs. 2.10-2.14 (fig-crow-2.10..2.14): eye RMSE "
            "(what an eye of s = 2 pixels sees against the pattern seen by the same eye) "
            "and beat energy (power above 0.35 cycle per pixel).",
        .patterns = LIST("crow"), .size = 256,
        .filters = LIST("box", "box", "tent:r=1", "tent:r=0.5", "tent:r=1"),
        .methods = LIST("point", "supersample:n=3", "supersample:n=5", "crowtable", "crowtable"),
        .labels = LIST("2.10 point", "2.11 3x3", "2.12 5x5 pyramid", "2.13 tables r=1/2",
                       "2.14 tables r=1"),
        .measure = crow_filters,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 2, \"Applying filters to computer-synthesized images\", pp. 31-37, fig. 2.8",
        .claim = "\"So far it has been sufficient to approximate the image function by forming a "
            "single rectangular area for each of these edges.\"",
        .setting = "crow and star 256x256 under tent:r=1: crowtable (form=crow, 16 table "
            "entries per dot) against the exact reference and 5 x 5 supersampling of the "
            "same filter; errors within 10% a tie.",
        .patterns = LIST("crow", "star"), .size = 256, .filter = "tent:r=1",
        .methods = LIST("crowtable", "supersample:n=5", "crowtiler:area=exact,hidden=scan"),
        .measure = crow_rectangle,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 1, \"General approaches\", pp. 5-10",
        .claim = "\"Doubling the resolution multiplies the number of dots in the image by four, "
            "and the necessary computation by more than a factor of two.\"",
        .setting = "point, supersample:n=3 and area on crow and star at 256x256 and 512x512; one "
            "thread, the median of the ratios of interleaved renders.",
        .pairs = (const tpair[]){DOUBLE("crow", "point"), DOUBLE("crow", "supersample:n=3"),
                                 DOUBLE("crow", "area"), DOUBLE("star", "point"),
                                 DOUBLE("star", "supersample:n=3"), DOUBLE("star", "area"),
                                 {{0}, {0}, NULL}},
        .head = "time at 512 / at 256:", .digits = 1, .lo = 2, .hi = INFINITY,
        .tail = ". Work that follows the dots grows by four; work that follows the edges, as "
                "point's and area's runs between crossings do, by two.",
        .measure = time_sweep,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 1, \"In Summary\", p. 16",
        .claim = "Doubling the resolution gives four blends of two surfaces, quadrupling 16; "
            "\"an algorithm which blends at the base resolution should be able to produce "
            "superior pictures at the same viewing distance\"; and doubling \"does not help "
            "the representation of very small objects\".",
        .setting = "256x256, box, the scenes moved 0.3 pixel right and down: area (blending "
            "exactly at the base resolution) against point at doubled and quadrupled "
            "resolution averaged down (supersample:n=2 and n=4, exactly those), by eye "
            "RMSE (area is the box reference itself, so its RMSE decides nothing); "
            "crowtiler (tent:r=1) beside; on the small objects (dots), point against "
            "doubling by RMSE. Errors within 10% a tie.",
        .patterns = LIST("crow", "star", "slivers", "dots"), .size = 256,
        .filters = LIST("box", "box", "box", "tent:r=1", "box"),
        .methods = LIST("area", "supersample:n=2", "supersample:n=4", "crowtiler", "point"),
        .measure = crow_base,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 3, \"Implementation of a z-priority algorithm\", pp. 60-63",
        .claim = "\"quite acceptable images can be made with z-priority techniques. Only under "
            "the most pathological circumstances will errors be noticeable and then only "
            "by experienced observers.\"",
        .setting = "crowtiler with his z-priority blending and adjacent-polygon rule "
            "(hidden=priority) against his scanning algorithm (hidden=scan), tent:r=1, "
            "256x256, scenes whose polygons overlap or meet (star, one layer of wedges "
            "meeting only at its centre, left out), moved 0.3 pixel right and down; RMSE and "
            "largest error against the exact reference.",
        .patterns = LIST("feibush", "catmull:tiles=4", "slivers"), .size = 256,
        .filter = "tent:r=1",
        .methods = LIST("crowtiler", "crowtiler:hidden=scan"), .measure = crow_priority,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 4, \"A temporal scheme\", pp. 76-79",
        .claim = "\"The chief advantage of this scheme is that virtually no additional "
            "computation is required.\"",
        .setting = "one frame of hexagon (--frame-only: the dots sampled at a vertex of the "
            "hexagon) against point, crow and star at 256x256: display=fixed, the "
            "samples alone (Crow's display moved its dots by setting the low bits of "
            "its DACs, at no cost), and display=screen, which adds this benchmark's "
            "model of his moving dots seen through the pixel squares; one thread, the "
            "median of the ratios of interleaved renders.",
        .patterns = LIST("crow", "star"), .size = 256, .filter = "box",
        .methods = LIST("point", "hexagon:display=fixed", "hexagon"), .measure = crow_hexagon,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 4, \"A temporal scheme\", pp. 76-79",
        .claim = "\"The eye will integrate over several positions of the staircases "
            "significantly reducing the staircase effect\"; \"The chief disadvantage is "
            "that small objects will still disappear between dots and may sometimes "
            "flicker noticeably.\"",
        .setting = "the temporal suite's setting (128x128, moving 0.37, 0.11 pixel a frame, "
            "24 frames, eye window 6): eye RMSE of hexagon (Crow's screen, random "
            "path) against point on star and crow; on dots, the fraction of dots that "
            "pop and the flicker, against point and area.",
        .patterns = LIST("crow", "star", "dots"), .size = 128, .filter = "box",
        .methods = LIST("point", "hexagon", "area"),
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 4, \"Processing the completed image\", pp. 81-84, figs. 4.2-4.3",
        .claim = "Williams' trio scheme \"may be somewhat more expensive but promises to "
            "completely eliminate staircase effects\"; such schemes \"cannot restore "
            "details which have been lost\".",
        .setting = "trio (Crow's line between the mid dots of consecutive trios) against point "
            "and area, 256x256, box: the error energy above 1/4 cycle per pixel "
            "(staircases) on star and crow; RMSE on slivers and dots (lost detail); "
            "time of trio / point, one thread, the median of the ratios of "
            "interleaved renders.",
        .patterns = LIST("star", "crow", "slivers", "dots"), .size = 256, .filter = "box",
        .methods = LIST("point", "trio", "area", "trio:variant=recursive"), .measure = crow_post,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 4, \"Processing the completed image\", pp. 81-84",
        .claim = "The recursive filter (a dot averaged with the dot to its left and the one "
            "above): \"A brief experiment with this scheme proved unencouraging. Although "
            "the results can not be significantly improved over those obtained by "
            "blurring, the filtering scheme might provide more precise control than "
            "optical blurring.\"",
        .setting = "trio:variant=recursive (weight 1/4) against point and against the point "
            "image blurred optically (each dot a square seen through a Gaussian, the "
            "Gaussian's s from 0.25 to 1.5 pixel, the best), 256x256; RMSE against the "
            "box reference.",
        .patterns = LIST("star", "crow", "slivers", "dots"), .size = 256, .filter = "box",
        .methods = LIST("point", "trio:variant=recursive"),
    },
    {
        .paper = "Crow 1976",
        .where = "appendix, \"Grey scale compensation\", pp. 88-92, figs. A.1-A.4",
        .claim = "With the pattern under the pyramid filter, the colour map that minimised the "
            "moire fringes left the grey scale's intensity readings \"near a parabolic "
            "curve, i.e. the function given by the square roots of the intensity readings "
            "was close to linear\": least moire at shown intensity v^2.",
        .setting = "calibration.c (fig-crow-A.4): crow 256x256 under tent:r=1 by crowtable and "
            "exactly, shown with intensity v^g, g = 0.5 to 4; the fringes an eye of s = 2 "
            "pixels sees over the pattern's right half (standard deviation of its "
            "error).",
        .patterns = LIST("crow"), .size = 256, .filter = "tent:r=1",
        .methods = LIST("crowtable"), .measure = crow_colour_map,
    },
    {
        .paper = "Ramos and Borges",
        .where = "sec. 3 (\"Uma idéia geral do método\")",
        .claim = "\"É interessante notar que no caso de uma única aresta, o resultado é exato, "
            "uma vez que o centróide passa exatamente em cima da aresta. O método, neste caso, "
            "é muito melhor que super-amostragem simples\": with a single edge the result is "
            "exact, the centroid lying on the edge; much better than simple supersampling.",
        .setting = "a white triangle on black (patterns/svg/edge.svg, edges at slopes off the "
            "grid) at 64x64, box: adaptive against supersample:n=2 and n=3, over the pixels "
            "crossed by one edge (no vertex within 2 pixels); errors within 10% a tie.",
        .patterns = LIST("svg:file=patterns/svg/edge.svg"), .size = 64, .filter = "box",
        .methods = LIST("adaptive", "supersample:n=2", "supersample:n=3"), .measure = rb_edge,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 1, \"General approaches\", pp. 5-10",
        .claim = "\"relatively few of the dots which make up an image contribute to the edges "
            "and small details [Graham 1967]. [...] Therefore several times the effort can be "
            "expended to produce the dots which need blending before the expense of producing "
            "the entire image doubles.\"",
        .setting = "crow, star and slivers at 256x256 and 512x512: the share of dots whose box "
            "reference is neither black nor white (the dots an edge crosses).",
        .patterns = LIST("crow", "star", "slivers"), .size = 256, .measure = crow_few,
    },
    {
        .paper = "Catmull 1978",
        .where = "\"Anti-aliasing\"",
        .claim = "\"The difference between area sampling and better filters is quantitative "
            "since most reasonable filters would also integrate the intensities. The "
            "difference between filtered pictures is lowered as the resolution is increased "
            "since the sum of intensities in a local area will be the same or nearly so. We "
            "cannot say this when comparing point sampling with sampling of filtered images "
            "at high resolution.\"",
        .setting = "crow at 128x128, 256x256 and 512x512 seen from the same distance (an eye of "
            "s = 1, 2, 4 pixels): the RMSE between what the eye sees of the exact box and "
            "the exact pyramid (tent:r=1) pictures, and of point sampling and the box.",
        .patterns = LIST("crow"), .size = 128, .filter = "box", .methods = LIST("point"),
        .measure = catmull_resolution,
    },
    {
        .paper = "Pfenning 2003",
        .where = "slides 40-42 (\"Antialiasing Revisited\", \"Antialiasing with Multiple "
            "Polygons\")",
        .claim = "\"Set alpha-value of each pixel to covered fraction [...] This will blend "
            "background with foreground. Overlaps can lead to blending errors\"; with no "
            "overlap the second polygon is blended as C'd = (1 - alpha2) C'd + alpha2 C2.",
        .setting = "patterns/svg/abut.svg (a red and a green rectangle sharing an edge) and "
            "patterns/svg/coincident.svg (a white quadrilateral drawn over a blue one of the "
            "same outline), edges off the pixel grid, 64x64, box: SVG renderers that "
            "composite coverage as alpha (rsvg, Chromium, when installed) against the exact "
            "picture (area) and the exact reference.",
        .patterns = LIST("svg:file=patterns/svg/abut.svg", "svg:file=patterns/svg/coincident.svg"),
        .size = 64, .filter = "box", .methods = LIST("area"), .measure = pfenning_conflation,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 3, \"Implementation of a scanning algorithm\"",
        .claim = "\"Objects small enough to be contained in a single dot are treated as "
            "non-overlapping when more than one occurs in the same dot [...] If they do hide "
            "one another, then when the calculated intensity is incorrect it is consistently "
            "incorrect and does not twinkle in an animated sequence.\"",
        .setting = "dots (objects smaller than a dot) in the temporal suite's setting (128x128, "
            "moving 0.37, 0.11 pixel a frame, 24 frames): crowtiler (tent:r=1) against "
            "point and area (box): the share of dots that pop and the flicker.",
        .patterns = LIST("dots"), .size = 128, .filters = LIST("box", "tent:r=1", "box"),
        .methods = LIST("point", "crowtiler", "area"),
        .labels = LIST("point", "tiler", "area"), .measure = crow_twinkle,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 4, \"Processing the completed image\", pp. 81-84",
        .claim = "\"The simplest of these schemes was suggested by T. L. Sancha [...] and is "
            "based on the fact that staircase effects are most noticeable on high-contrast "
            "edges. [...] Whenever the intensity of neighboring dots differs by more than a "
            "preset amount, one of them is changed to a compromise intensity. [...] This "
            "scheme provides a way of selectively blurring the image which may yield more "
            "pleasing results than optical blurring.\"",
        .setting = "trio:variant=sancha (threshold 1/8, the upper-left dot of a pair changed) "
            "against the point image blurred optically (each dot a square seen through a "
            "Gaussian, s from 0.25 to 1.5 pixel, the s an eye sees best), star, crow, "
            "slivers and dots at 256x256: eye RMSE (an eye of s = 2 pixels against the "
            "scene seen by the same eye), the RMSE against the box reference beside; "
            "errors within 10% a tie.",
        .patterns = LIST("star", "crow", "slivers", "dots"), .size = 256, .filter = "box",
        .methods = LIST("point", "trio:variant=sancha"), .measure = crow_sancha,
    },
    {
        .paper = "Crow 1976",
        .where = "ch. 3, \"Comparison of three basic hidden-surface techniques\", pp. 49-56, "
            "fig. 3.7",
        .claim = "The z-buffer \"causes many more problems than need be dealt with in the "
            "z-priority algorithms. [...] a host of new problems arise when the new surface "
            "lies partially behind what has already been stored [Fig. 3.7]. In this case the "
            "blending information for the first surface has been lost and there is thus no "
            "way to smooth the resulting edge.\" \"In the worst case, the z-buffer loses the "
            "necessary blending information\".",
        .setting = "crowtiler with exact weighted areas (area=exact, so that the hidden "
            "surfaces alone err) as a z-buffer written front to back, the worst order "
            "(hidden=zbuffer: a dot keeps the first surface to reach it), in the z-priority "
            "order with his adjacent-polygon rule (hidden=priority) and by his scanning "
            "algorithm (hidden=scan), tent:r=1, 256x256, scenes of overlapping and abutting "
            "layers (feibush, catmull:tiles=4) moved 0.3 pixel right and down: the largest "
            "error against the exact reference and the dots off by more than 0.1.",
        .patterns = LIST("feibush", "catmull:tiles=4"), .size = 256, .filter = "tent:r=1",
        .methods = LIST("crowtiler:area=exact,hidden=zbuffer", "crowtiler:area=exact",
                        "crowtiler:area=exact,hidden=scan"),
        .measure = crow_zbuffer,
    },
    {
        .paper = "Catmull 1978",
        .where = "\"Anti-aliasing\"",
        .claim = "\"Point sampling of an unfiltered object is never correct at any resolution. "
            "It is frequently thought that the symptoms of aliasing will not be noticeable if "
            "the resolution is high enough. Unfortunately, this is not true.\" [...] \"A "
            "line that is much thinner than a pixel will appear dotted using point sampling "
            "and jagged using area sampling. As the resolution is increased, point sampling "
            "will still produce dots but area sampling will produce a nice line.\"",
        .setting = "patterns/svg/thinline.svg (a white line on black 0.1 pixel tall at "
            "128x128, its ends and slope 0.415 off the grid; the document scales with the "
            "view) at 128x128, 256x256 and 512x512 (0.1 to 0.4 pixel), box: point and area; "
            "the share of the line's columns point leaves dark, and the eye RMSE seen from "
            "the same distance (an eye of s = 1, 2, 4 pixels: 1/128 of the picture) against "
            "the line seen by the same eye.",
        .patterns = LIST("svg:file=patterns/svg/thinline.svg"), .size = 128, .filter = "box",
        .methods = LIST("point", "area"), .measure = catmull_thin,
    },
    {
        .paper = "Feibush, Levoy and Cook 1980",
        .where = "sec. 2.5 (\"Edge filtering\"), fig. 3f",
        .claim = "\"Each filter shape needs only one lookup table, regardless of the filter's "
            "absolute size. The filter size can be changed by scaling the indices to the "
            "lookup table.\"",
        .setting = "their edge filter (conetable: one table per shape, indexed by the distance "
            "to the edge's line over the mask's radius and an angle, 64 x 64 intervals) "
            "with the Gaussian in its mask of radius 2 s (gauss:s=S,cut=2, s = 0.5, 1, 2 "
            "pixels) and with the cone (cone:r=R, R = 1, 2, 4 pixels), feibush and crow at "
            "256x256: RMSE and largest error against the exact reference under the same "
            "filter.",
        .patterns = LIST("feibush", "crow"), .size = 256,
        .filters = LIST("gauss:s=0.5,cut=2", "gauss:s=1,cut=2", "gauss:s=2,cut=2", "cone:r=1",
                        "cone:r=2", "cone:r=4"),
        .methods = LIST("conetable", "conetable", "conetable", "conetable", "conetable",
                        "conetable"),
        .measure = feibush_sizes,
    },
    {
        .paper = "Feibush, Levoy and Cook 1980",
        .where = "sec. 3 (\"Examples\"), fig. 4e",
        .claim = "\"In the hardware magnification shown in Figure 4e, the polygon is inclined "
            "slightly more than in Figures 4b-d to enhance the visibility of the filtering. "
            "Notice that the filtering along the left edge of the polygon is equivalent to "
            "the filtering along the stripes of the texture.\"",
        .setting = "feibush:stripes=200 at 512x512 under their Gaussian (gauss:s=1,cut=2), the "
            "setting of fig. 4d (fig-feibush-4d; the more inclined polygon of 4e is not "
            "given): their texture filter with their edge filter (feibushtex:texels=1000, "
            "every texture point inside one stripe) and the edge filter alone on the "
            "stripes as polygons (conetable) beside; RMSE against the exact reference over "
            "the dots along the polygon's left edge (within 3 pixels of it, 4 pixels from "
            "its ends) and over the dots inside the square whose mask meets a stripe's "
            "edge.",
        .patterns = LIST("feibush:stripes=200"), .size = 512, .filter = "gauss:s=1,cut=2",
        .methods = LIST("feibushtex:texels=1000", "conetable"),
        .labels = LIST("texture and edge filters", "edge filter alone"),
        .measure = feibush_edges,
    },
    {
        .paper = "Ramos and Borges",
        .where = "sec. 6 (\"Casos particulares\"), cases a-d, fig. 4 (\"Casos desfavoráveis\")",
        .claim = "\"Esse algoritmo apresenta alguns casos difíceis, como mostrado na figura 4\": "
            "(a) polygons smaller than a pixel and wholly inside it, \"o algoritmo não tomará "
            "conhecimento destes polígonos\"; (b) polygons with vertices inside the pixel and "
            "all their edges on one border, \"o algoritmo ignorará o polígono\"; (c) more "
            "than one edge of different polygons on one border, \"O processo de busca "
            "binária detectará apenas uma variação por borda, e um dos polígonos será "
            "ignorado\"; (d) a very thin polygon across a pixel, \"o algoritmo pode falhar\".",
        .setting = "one 32x32 scene per case, box (patterns/svg/rb-inside.svg, rb-border.svg, "
            "rb-twoedges.svg, rb-thin.svg: the case's polygons placed against the pixel "
            "corners as the case needs, and the only green of the scene): adaptive (the "
            "paper's method, tag=0) against the exact reference, the share of the "
            "polygons' green it misses (its green RMSE over the reference's green RMS); "
            "adaptive:tag=1 (tagged pixels subdivided, an extension) and supersample:n=3 "
            "beside.",
        .patterns = LIST("svg:file=patterns/svg/rb-inside.svg",
                         "svg:file=patterns/svg/rb-border.svg",
                         "svg:file=patterns/svg/rb-twoedges.svg",
                         "svg:file=patterns/svg/rb-thin.svg"),
        .size = 32, .filter = "box",
        .methods = LIST("adaptive", "adaptive:tag=1", "supersample:n=3"),
        .labels = LIST("adaptive", "tag=1", "n=3"), .measure = rb_cases,
    },
    {
        .paper = "Reshetov 2009",
        .where = "\"Morphological antialiasing\", HPG, fig. 1 caption",
        .claim = "\"morphological antialiasing improves the quality of the rendered image "
            "without having a noticeable impact on performance.\"",
        .setting = "mlaa (the point-sampled image post-processed) against point, 256x256, box: "
            "RMSE against the box reference on crow, star, slivers and feibush; time of "
            "mlaa / point on crow, one thread, the median of the ratios of interleaved "
            "renders. (Reshetov's images were ray traced, which costs far more per pixel "
            "than this point sampler's runs between crossings.)",
        .patterns = LIST("crow", "star", "slivers", "feibush"), .size = 256, .filter = "box",
        .methods = LIST("point", "mlaa", "supersample:pattern=msaa4",
                        "supersample:pattern=msaa8"),
        .measure = mlaa_claims,
    },
    {
        .paper = "Jimenez, Masia, Echevarria, Navarro and Gutierrez 2011",
        .where = "\"Practical Morphological Antialiasing\", GPU Pro 2, abstract",
        .claim = "\"The quality of their results lies between 4x and 8x multisampling "
            "antialiasing\" (morphological antialiasing of the completed image).",
        .setting = "mlaa against the standard 4x and 8x multisample positions "
            "(supersample:pattern=msaa4, msaa8), box, 256x256, the same scenes: RMSE "
            "against the box reference.",
        .patterns = LIST("crow", "star", "slivers", "feibush"), .size = 256, .filter = "box",
        .methods = LIST("point", "mlaa", "supersample:pattern=msaa4",
                        "supersample:pattern=msaa8"),
    },
    {
        .paper = "Jimenez, Echevarria, Sousa and Gutierrez 2012",
        .where = "\"SMAA: Enhanced Subpixel Morphological Antialiasing\", Eurographics, "
            "abstract",
        .claim = "SMAA yields \"results of better overall quality than previous approaches "
            "while more closely converging to MSAA/SSAA references\".",
        .setting = "smaa (SMAA 1x's spatial filter, with its diagonal patterns) against "
            "the approaches before it, mlaa and fxaa (FXAA 3.11 quality), all on the "
            "same point samples, 256x256, box: RMSE against the box reference on crow, "
            "star, slivers and feibush; 4 x 4 supersampling beside.",
        .patterns = LIST("crow", "star", "slivers", "feibush"), .size = 256, .filter = "box",
        .methods = LIST("point", "mlaa", "fxaa", "smaa", "supersample:n=4"),
        .measure = smaa_claims,
    },
};
#undef PAIR
#undef FILTERS
#undef DOUBLE

#define NCLAIMS (sizeof claims / sizeof claims[0])

size_t aa_claim_count(void)
{
    return NCLAIMS;
}

/* One spec of claim k parsed: a pattern (filter NULL) or a method under
 * `filter`. */
static int check_spec(size_t k, const char *what, const char *text, const char *filter)
{
    aa_spec spec;
    aa_filter f;
    int st;
    if (!text || (!strcmp(what, "method") && !filter))
        return aa_fail(AA_EINVAL, "claim %zu (%s): a %s %s is missing", k + 1, claims[k].paper,
                       what, text ? "filter" : "spec");
    if (!strcmp(what, "pattern"))
        st = aa_pattern_parse(text, &spec);
    else if (!(st = aa_filter_parse(filter, &f)))
        st = aa_method_parse(text, &f, &spec);
    return st ? aa_fail_context(st, "claim %zu (%s): %s %s", k + 1, claims[k].paper, what, text)
              : AA_OK;
}

int aa_claim_check(size_t k)
{
    if (k >= NCLAIMS)
        return aa_fail(AA_EINVAL, "no claim %zu (there are %zu)", k + 1, NCLAIMS);
    const claim_row *d = &claims[k];
    if (!d->paper || !d->where || !d->claim || !d->setting)
        return aa_fail(AA_EINVAL, "claim %zu: a text is missing", k + 1);
    if (!d->measure && (k == 0 || !claims[k - 1].measure))
        return aa_fail(AA_EINVAL, "claim %zu (%s): no measure, and none before it", k + 1,
                       d->paper);
    if (!d->pairs && (count_of(d->patterns) < 1 || d->size < 1))
        return aa_fail(AA_EINVAL, "claim %zu (%s): no pattern or size", k + 1, d->paper);
    int st = AA_OK;
    const int nm = count_of(d->methods);
    if (d->filters && count_of(d->filters) != nm)
        return aa_fail(AA_EINVAL, "claim %zu (%s): %d filters for %d methods", k + 1, d->paper,
                       count_of(d->filters), nm);
    if (d->labels && count_of(d->labels) != nm)
        return aa_fail(AA_EINVAL, "claim %zu (%s): %d labels for %d methods", k + 1, d->paper,
                       count_of(d->labels), nm);
    for (int p = 0; d->patterns && d->patterns[p] && !st; p++)
        st = check_spec(k, "pattern", d->patterns[p], NULL);
    for (int m = 0; m < nm && !st; m++)
        st = check_spec(k, "method", d->methods[m], filter_of(d, m));
    for (const tpair *p = d->pairs; p && p->label && !st; p++)
        for (int s = 0; s < 2 && !st; s++) {
            const tcase *c = s ? &p->b : &p->a;
            if (c->w < 1)
                st = aa_fail(AA_EINVAL, "claim %zu (%s): %s: no size", k + 1, d->paper,
                             p->label);
            else if (!(st = check_spec(k, "pattern", c->pattern, NULL)))
                st = check_spec(k, "method", c->method, c->filter);
        }
    if (!st && d->measure == time_sweep && (!d->pairs || !d->pairs[0].label || !d->head ||
                                            !d->tail || !(d->lo <= d->hi)))
        st = aa_fail(AA_EINVAL, "claim %zu (%s): a time sweep without pairs, texts or band",
                     k + 1, d->paper);
    return st;
}

/* ---- writing ---- */

static void md_cell(FILE *f, const char *s)
{
    for (; *s; s++)
        if (*s == '|')
            fputs("\\|", f);
        else
            fputc(*s, f);
}

static int write_text(const char *dir, const char *name, const char *text, size_t len)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/%s", dir, name);
    if (!st)
        st = aa_file_write_atomic(path, text, len);
    return st;
}

static int write_claims(const char *dir, const claim *c, int n, int reps)
{
    char *md = NULL, *html = NULL;
    size_t mlen = 0, hlen = 0;
    FILE *m = open_memstream(&md, &mlen);
    FILE *h = m ? open_memstream(&html, &hlen) : NULL;
    if (!m || !h) {
        if (m)
            fclose(m);
        free(md);
        return aa_fail(AA_ENOMEM, "claims: out of memory");
    }
    static const char intro[] =
        "Made by `aabench figures --claims` (harness/bench/claims.c). Times: one thread, "
        "each ratio the median over %d pairs of single renders of the two cases (each after "
        "an untimed init), taken in turns a b, a b, ... (aa_timing_measure), both warmed up "
        "once; the machine was shared with other work, so single times are noisy and only "
        "such ratios are quoted. Errors: "
        "RMSE against the exact reference under the method's filter (point sampling and its "
        "post-processes: the box), linear light; \"eye RMSE\": what an eye of s = %g pixels "
        "sees of the image shown as pixel squares against what it sees of the scene itself "
        "(harness/bench/eye.c); \"staircase energy\": the error's power above 1/4 cycle per "
        "pixel; \"beat energy\": the image's own power above 0.35 cycle per pixel, which "
        "beats with the grid of dots into fringes. Each time ratio is given as its median and "
        "[95%% interval]. Verdicts, each from a margin fixed before measuring: yes (the "
        "numbers agree with the claim), no (they do not), partly (one part or case holds, "
        "another not), inconclusive (a ratio's interval holds an end of the claim's band, or "
        "errors tie within 10%%), not comparable (this setting cannot decide the claim); "
        "each with its reason.";
    fprintf(m, intro, reps, AA_EYE_S);
    fprintf(m, "\n\n| # | paper, where | claim | setting | measured | verdict |\n"
               "|---|---|---|---|---|---|\n");
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<title>aabench: the papers' claims, measured</title>\n</head>\n<body>\n"
          "<style>\n"
          ".claims { border-collapse: collapse; font: 13px sans-serif; }\n"
          ".claims td, .claims th { border: 1px solid #999; padding: 4px; "
          "vertical-align: top; }\n"
          ".claims th { background: #ddd; color: #000; }\n"
          ".claims td { background: #fff; color: #000; }\n"
          ".claims td.v-yes { background: #c6efce; }\n"
          ".claims td.v-partly { background: #ffeb9c; }\n"
          ".claims td.v-no { background: #ffc7ce; }\n"
          ".claims td.v-inconclusive { background: #dde4ee; }\n"
          ".claims td.v-not-comparable { background: #e4e4e4; }\n"
          "</style>\n<h1>The papers' claims, measured</h1>\n<h2>How</h2>\n<p>",
          h);
    fprintf(h, intro, reps, AA_EYE_S);
    fputs("</p>\n<h2>Claims</h2>\n<table class=\"claims\">\n<tr><th>#</th><th>paper, where</th>"
          "<th>claim</th><th>setting</th><th>measured</th><th>verdict</th></tr>\n",
          h);
    for (int k = 0; k < n; k++) {
        fprintf(m, "| %d | ", k + 1);
        md_cell(m, c[k].row->paper);
        fputs(", ", m);
        md_cell(m, c[k].row->where);
        fputs(" | ", m);
        md_cell(m, c[k].row->claim);
        fputs(" | ", m);
        md_cell(m, c[k].row->setting);
        fputs(" | ", m);
        md_cell(m, c[k].measured);
        fprintf(m, " | **%s**: ", c[k].verdict);
        md_cell(m, c[k].reason);
        fputs(" |\n", m);
        fprintf(h, "<tr><td>%d</td><td>", k + 1);
        aa_html_escape(h, c[k].row->paper);
        fputs(", ", h);
        aa_html_escape(h, c[k].row->where);
        fputs("</td><td>", h);
        aa_html_escape(h, c[k].row->claim);
        fputs("</td><td>", h);
        aa_html_escape(h, c[k].row->setting);
        fputs("</td><td>", h);
        aa_html_escape(h, c[k].measured);
        fputs("</td><td class=\"v-", h);
        for (const char *v = c[k].verdict; *v; v++)
            fputc(*v == ' ' ? '-' : *v, h);
        fprintf(h, "\"><b>%s</b>: ", c[k].verdict);
        aa_html_escape(h, c[k].reason);
        fputs("</td></tr>\n", h);
    }
    fputs("</table>\n</body>\n</html>\n", h);
    int bad = fflush(m) != 0 || fflush(h) != 0;
    fclose(m);
    fclose(h);
    int st = bad ? aa_fail(AA_ENOMEM, "claims: out of memory") : AA_OK;
    if (!st)
        st = write_text(dir, "claims.md", md, mlen);
    if (!st)
        st = write_text(dir, "claims.html", html, hlen);
    free(md);
    free(html);
    return st;
}

static int claims_make(const char *dir, const cx *x)
{
    claim *c = calloc(NCLAIMS, sizeof *c);
    if (!c)
        return aa_fail(AA_ENOMEM, "claims: out of memory");
    int st = AA_OK;
    for (size_t k = 0; k < NCLAIMS; k++)
        c[k].row = &claims[k];
    for (size_t k = 0; k < NCLAIMS && !st; k++)
        if (claims[k].measure)
            st = claims[k].measure(x, &claims[k], &c[k]);
    for (size_t k = 0; k < NCLAIMS && !st; k++)
        if (claims[k].not_comparable)
            because(&c[k], "not comparable", "%s", claims[k].not_comparable);
    if (!st)
        st = write_claims(dir, c, (int)NCLAIMS, x->reps);
    free(c);
    return st;
}

int aa_claims_make(const char *dir, const char *cache_dir, int threads, int reps,
                   int (*progress)(void *ctx, const char *what), void *ctx)
{
    if (reps < 1 || reps > 1000)
        return aa_fail(AA_EINVAL, "claims: reps %d out of range (1 to 1000)", reps);
    cx x = {cache_dir, threads > 0 ? threads : 1, reps, progress, ctx};
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = claims_make(dir, &x);
    aa__c_numbers_end(&numbers);
    return st;
}
