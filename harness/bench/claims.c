/*
 * claims.c: the papers' quantitative claims (the seed papers', and those of
 * the post-processes that descend from Crow's), measured
 * (`aabench figures --claims`: DIR/claims.md and DIR/claims.html).
 *
 * Each claim is quoted with where it is made (paper, section, pages from
 * the paper's own table of contents where it has one), measured on the
 * same setting as far as this benchmark has it, and judged: "yes" when the
 * measurement agrees with the claim as stated, "no" when it does not (the
 * numbers say by how much), "partly" when one part holds and another not.
 * Each claim is a row of the table `claims` (its texts, the specs it is
 * measured on, and its measure: the generic time sweep or a small function
 * of its own); aa_claim_check checks a row's specs.
 *
 * How things are measured.
 *  - Times: `aa_run` on one thread, the median of `reps` renders after one
 *    untimed init, into an image touched beforehand (only the render is
 *    timed).  Ratios are taken between methods of the same run.  The machine
 *    is shared, so single times are noisy; medians of several renders, and
 *    ratios rather than times, are what is quoted.
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
};

struct claim {
    const claim_row *row;
    char measured[2048];
    const char *verdict;
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

/* A method's image on a view (rendered with every thread, untimed), and
 * what the eye sees of it; ref_box (may be NULL) gets the metrics against
 * the box reference. */
static int image_of(const cx *x, const char *pattern, int w, const char *filter,
                    const char *method, aa_image *img, double *eye, aa_metrics *box)
{
    aa_spec ps, ms;
    aa_filter f;
    aa_scene *scene = NULL;
    aa_job job;
    aa_counters counters;
    aa_image truth = {0};
    int st = aa_pattern_parse(pattern, &ps);
    if (!st)
        st = aa_filter_parse(filter, &f);
    if (!st)
        st = aa_method_parse(method, &f, &ms);
    if (!st)
        st = aa_pattern_scene_at(&ps, w, w, &scene);
    if (st)
        return aa_fail_context(st, "claims: %s on %s", method, pattern);
    if (!(st = aa_job_init(&job, scene, w, w, 0, 0, 0, &f, 1, x->threads))) {
        if (!(st = aa_image_alloc(img, w, w, 3)))
            st = aa_method_run(&ms, &job, 1, img, &counters, NULL);
        aa_job_free(&job);
    }
    if (!st && eye &&
        !(st = aa_eye_truth(&ps, w, w, 0, 0, 0, AA_EYE_S, x->cache, x->threads, &truth)))
        st = aa_eye_rmse(img, &truth, AA_EYE_S, eye);
    if (!st && box) {
        aa_view view;
        aa_image ref;
        memset(&view, 0, sizeof view);
        view.pattern = ps;
        view.w = view.h = w;
        if (!(st = aa_filter_parse("box", &view.filter)) &&
            !(st = aa_reference(&view, x->cache, x->threads, &ref, NULL, NULL))) {
            st = aa_metrics_compute(&ref, img, NULL, box);
            aa_image_free(&ref);
        }
    }
    aa_image_free(&truth);
    aa_scene_free(scene);
    return st ? aa_fail_context(st, "claims: %s on %s", method, pattern) : AA_OK;
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

static int cmp_double(const void *a, const void *b)
{
    double u = *(const double *)a, v = *(const double *)b;
    return u < v ? -1 : u > v;
}

/* The time of b over the time of a, on one thread: `reps` pairs of single
 * renders (each after an untimed init), taken in the order a b, b a, a b,
 * ... so that a slow spell of the shared machine falls on both; the median
 * of the pairs' ratios. */
static int time_ratio(const cx *x, const tcase *a, const tcase *b, double *ratio)
{
    tstate ta, tb;
    int st = tstate_init(a, &ta);
    if (st)
        return st;
    if ((st = tstate_init(b, &tb))) {
        tstate_free(&ta);
        return st;
    }
    double *r = malloc((size_t)x->reps * sizeof *r);
    if (!r)
        st = aa_fail(AA_ENOMEM, "out of memory");
    char what[256];
    snprintf(what, sizeof what, "timing %s / %s on %s", b->method, a->method, b->pattern);
    say(x, what);
    for (int k = 0; k < x->reps && !st; k++) {
        double sa = 0, sb = 0;
        aa_counters cn;
        for (int o = 0; o < 2 && !st; o++) {
            int first_a = (k % 2 == 0) == (o == 0);
            tstate *t = first_a ? &ta : &tb;
            st = aa_method_run(&t->method, &t->job, 1, &t->img, &cn, first_a ? &sa : &sb);
        }
        r[k] = sb / sa;
    }
    if (!st) {
        qsort(r, (size_t)x->reps, sizeof *r, cmp_double);
        *ratio = x->reps % 2 ? r[x->reps / 2] : 0.5 * (r[x->reps / 2 - 1] + r[x->reps / 2]);
    }
    free(r);
    tstate_free(&ta);
    tstate_free(&tb);
    return st;
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

/* The time of each pair's b over its a; the claim holds where every ratio
 * lies in [lo, hi], partly where some do. */
static int time_sweep(const cx *x, const claim_row *d, claim *c)
{
    int n = 0, held = 0;
    add(c, "%s", d->head);
    for (const tpair *p = d->pairs; p->label; p++, n++) {
        double ratio;
        int st = time_ratio(x, &p->a, &p->b, &ratio);
        if (st)
            return st;
        held += ratio >= d->lo && ratio <= d->hi;
        add(c, "%s %s %.*f", n ? ";" : "", p->label, d->digits, ratio);
    }
    add(c, "%s", d->tail);
    c->verdict = held == n ? "yes" : held ? "partly" : "no";
    return AA_OK;
}

/* ---- the claims' own measures ---- */

/* Ramos and Borges: this row's cost (adaptive, methods[1], against point,
 * methods[0]) and the next row's quality (adaptive against the two grids,
 * methods[2] and [3]), on the same scenes. */
static int ramos_borges(const cx *x, const claim_row *d, claim *c)
{
    claim *cost = &c[0], *better = &c[1];
    const size_t nrb = (size_t)count_of(d->patterns);
    double sum_drop = 0;
    int wins2 = 0, wins3 = 0;
    add(cost, "time without antialiasing / with:");
    add(better, "RMSE (samples per pixel):");
    for (size_t k = 0; k < nrb; k++) {
        aa_row *r;
        size_t n;
        double ratio;
        const char *scene = d->patterns[k];
        tcase a = {scene, d->size, d->filter, d->methods[1], 0},
              p = {scene, d->size, d->filter, d->methods[0], 0};
        int st = time_ratio(x, &a, &p, &ratio);
        if (!st)
            st = run_view(x, scene, d->size, d->filter, d->methods, 4, 0, 0, &r, &n);
        if (st)
            return st;
        double drop = 1 - ratio;
        sum_drop += drop;
        add(cost, "%s %s %.2f (drop %.0f%%)", k ? ";" : "", scene, ratio, 100 * drop);
        add(better, "%s %s: adaptive %.4f (%.2f), n=2 %.4f, n=3 %.4f", k ? ";" : "", scene,
            r[1].m.rmse, r[1].spp, r[2].m.rmse, r[3].m.rmse);
        wins2 += r[1].m.rmse < r[2].m.rmse;
        wins3 += r[1].m.rmse < r[3].m.rmse;
        free(r);
    }
    double mean = sum_drop / (double)nrb;
    add(cost, ". Mean drop %.0f%%: antialiasing costs %.1f times point sampling. (This point "
              "sampler fills the runs of pixel centres between a row's crossings; the paper's "
              "renderer took a z-buffer decision at every pixel, which its antialiasing adds "
              "to.)",
        100 * mean, 1 / (1 - mean));
    cost->verdict = mean < 0.3 ? "yes" : "no";
    add(better, ". Adaptive beats n=2 (fewer samples) on %d of %zu scenes and n=3 (more) on "
                "%d of %zu; it loses where thin bands or several edges fall between corners "
                "(the paper's sec. 6).",
        wins2, nrb, wins3, nrb);
    better->verdict = wins2 == (int)nrb ? (wins3 == (int)nrb ? "yes" : "partly")
                                        : (wins2 > 0 ? "partly" : "no");
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
    c->verdict = r[1].tm.conservation < 1e-12 && r[0].tm.conservation > 1e-2 ? "yes" : "no";
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
    c->verdict = e[1] < e[0] / 3 && b[2] < b[1] / 3 ? "yes" : "no";
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
    c->verdict = best == kept && calm == kept   ? "yes"
                 : best == kept || calm == kept ? "partly"
                                                : "no";
    return AA_OK;
}

/* Crow's rectangle per edge: crowtable (methods[0]) against 5 x 5
 * supersampling (methods[1]) and the exact tiler (methods[2]). */
static int crow_rectangle(const cx *x, const claim_row *d, claim *c)
{
    const char *pat = d->patterns[0];
    aa_row *r;
    size_t n;
    double ratio;
    tcase t = {pat, d->size, d->filter, d->methods[0], 0},
          ss = {pat, d->size, d->filter, d->methods[1], 0};
    int st = time_ratio(x, &ss, &t, &ratio);
    if (!st)
        st = run_view(x, pat, d->size, d->filter, d->methods, 2, 0, 0, &r, &n);
    if (st)
        return st;
    double e_ct, e_ss, e_ref;
    if ((st = eye_of(x, pat, d->size, d->filter, d->methods[0], &e_ct, NULL)) ||
        (st = eye_of(x, pat, d->size, d->filter, d->methods[1], &e_ss, NULL)) ||
        (st = eye_of(x, pat, d->size, d->filter, d->methods[2], &e_ref, NULL))) {
        free(r);
        return st;
    }
    add(c, "RMSE against the exact pyramid: tables %.4f (max %.3f), 5x5 %.4f (max %.3f); eye "
           "RMSE: tables %.4f, exact %.4f, 5x5 %.4f; time, tables / 5x5: %.2f.",
        r[0].m.rmse, r[0].m.max_err, r[1].m.rmse, r[1].m.max_err, e_ct, e_ref, e_ss, ratio);
    c->verdict = e_ct < 1.1 * e_ref && r[0].m.rmse < r[1].m.rmse ? "yes" : "no";
    free(r);
    return AA_OK;
}

/* Crow's base resolution: area (methods[0]) against the doubled and the
 * quadrupled resolution (methods[1], [2]), the tiler (methods[3]) beside. */
static int crow_base(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int wins = 0;
    for (int k = 0; k < np; k++) {
        double e[4];
        aa_metrics b[3];
        aa_image img = {0};
        for (int q = 0; q < 4; q++) {
            int st = image_of(x, d->patterns[k], d->size, filter_of(d, q), d->methods[q], &img,
                              &e[q], q < 3 ? &b[q] : NULL);
            aa_image_free(&img);
            if (st)
                return st;
        }
        wins += e[0] < e[1] && e[0] < e[2] && b[0].rmse < b[1].rmse && b[0].rmse < b[2].rmse;
        add(c, "%s%s: RMSE area %.1e, doubled %.4f, quadrupled %.4f; eye area %.4f, doubled "
               "%.4f, quadrupled %.4f, tiler %.4f",
            k ? "; " : "", d->patterns[k], b[0].rmse, b[1].rmse, b[2].rmse, e[0], e[1], e[2],
            e[3]);
    }
    add(c, ". Blending at the base resolution wins on %d of %d scenes.", wins, np);
    c->verdict = wins == np ? "yes" : wins ? "partly" : "no";
    return AA_OK;
}

/* Crow's z-priority: the largest error of methods[0] (priority) beyond
 * that of methods[1] (scan), the worst over the scenes. */
static int crow_priority(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    double worst = 0;
    for (int k = 0; k < np; k++) {
        aa_row *r;
        size_t n;
        int st = run_view(x, d->patterns[k], d->size, d->filter, d->methods, 2, 0, 0, &r, &n);
        if (st)
            return st;
        add(c, "%s%s: priority %.4f (max %.3f), scan %.4f (max %.3f)", k ? "; " : "",
            d->patterns[k], r[0].m.rmse, r[0].m.max_err, r[1].m.rmse, r[1].m.max_err);
        worst = fmax(worst, r[0].m.max_err - r[1].m.max_err);
        free(r);
    }
    add(c, ". The z-priority errors sit where three surfaces share a dot or polygons meet "
           "without sharing an edge (his fig. 3.6); a largest error above 0.1 is visible.");
    c->verdict = worst < 0.1 ? "yes" : "partly";
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
    double worst = 0;
    add(cost, "time of a frame / point's:");
    for (int k = 0; d->patterns[k]; k++) {
        double fixed, screen;
        const char *scene = d->patterns[k];
        tcase p = {scene, d->size, d->filter, d->methods[0], 1},
              hf = {scene, d->size, d->filter, d->methods[1], 1},
              hs = {scene, d->size, d->filter, d->methods[2], 1};
        int st = time_ratio(x, &p, &hf, &fixed);
        if (!st)
            st = time_ratio(x, &p, &hs, &screen);
        if (st)
            return st;
        worst = fmax(worst, fixed);
        add(cost, "%s %s fixed %.2f, screen %.2f", k ? ";" : "", scene, fixed, screen);
    }
    add(cost, " (\"virtually no\" taken as under 1.25).");
    cost->verdict = worst < 1.25 ? "yes" : "no";

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
    look->verdict = fewer == nl - 1 && flick ? "yes" : (fewer || flick) ? "partly" : "no";
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
                double ratio;
                tcase p = {scene, d->size, d->filter, d->methods[0], 0},
                      t = {scene, d->size, d->filter, d->methods[1], 0};
                if ((st = time_ratio(x, &p, &t, &ratio))) {
                    free(r);
                    return st;
                }
                add(trio, ", time trio / point %.1f", ratio);
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
    trio->verdict = removed_min > 0.95 ? (lost == np - 2 ? "yes" : "partly") : "partly";
    add(rec, ". The recursive filter does no better than the best blur (within 10%%) on %d of "
             "%d scenes.",
        rec_no_better, np);
    rec->verdict = rec_no_better == np ? "yes" : rec_no_better ? "partly" : "no";
    return AA_OK;
}

/* Morphological antialiasing (Reshetov): this row's quality and cost of
 * mlaa (methods[1]) against point (methods[0]), and the next row's
 * comparison of mlaa with 4x and 8x multisampling (methods[2], [3]). */
static int mlaa_claims(const cx *x, const claim_row *d, claim *c)
{
    claim *cost = &c[0], *msaa = &c[1];
    const int np = count_of(d->patterns);
    int better = 0, between = 0;
    double ratio = 0;
    const char *timed = "";
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_row *r;
        size_t n;
        int st = run_view(x, scene, d->size, d->filter, d->methods, 4, 0, 0, &r, &n);
        if (st)
            return st;
        better += r[1].m.rmse < r[0].m.rmse;
        between += r[1].m.rmse <= r[2].m.rmse && r[1].m.rmse >= r[3].m.rmse;
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
    add(cost, ". Time mlaa / point on %s: %.1f (\"no noticeable impact\" taken as under "
              "1.25). Quality improves on %d of %d scenes.",
        timed, ratio, better, np);
    cost->verdict = better == np ? (ratio < 1.25 ? "yes" : "partly") : better ? "partly" : "no";
    add(msaa, ". MLAA lies between them on %d of %d scenes.", between, np);
    msaa->verdict = between == np ? "yes" : between ? "partly" : "no";
    return AA_OK;
}

/* SMAA against the approaches before it (mlaa, fxaa: methods[1], [2]) and
 * its distance to supersampling (methods[3]), point (methods[0]) beside. */
static int smaa_claims(const cx *x, const claim_row *d, claim *c)
{
    const int np = count_of(d->patterns);
    int wins = 0;
    for (int k = 0; k < np; k++) {
        const char *scene = d->patterns[k];
        aa_row *r;
        size_t n;
        int st = run_view(x, scene, d->size, d->filter, d->methods, 5, 0, 0, &r, &n);
        if (st)
            return st;
        wins += r[3].m.rmse < r[1].m.rmse && r[3].m.rmse < r[2].m.rmse;
        add(c, "%s%s: point %.4f, mlaa %.4f, fxaa %.4f, smaa %.4f, 16x supersampling %.4f",
            k ? "; " : "", scene, r[0].m.rmse, r[1].m.rmse, r[2].m.rmse, r[3].m.rmse,
            r[4].m.rmse);
        free(r);
    }
    add(c, ". SMAA 1x is below both MLAA and FXAA on %d of %d scenes.", wins, np);
    c->verdict = wins == np ? "yes" : wins ? "partly" : "no";
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
           "%.4f, %.4f, %.4f. In linear light the least moire is at a linear response (his "
           "convex upward map, fig. A.2), not his square law; g = 2 would be least only for "
           "an eye averaging the square root of intensity.",
        cal.gmin_fringe[0], cal.gmin_fringe[1], cal.map_fringe[0][1], cal.map_fringe[0][0],
        cal.map_fringe[0][2]);
    c->verdict = fabs(cal.gmin_fringe[0] - 2) < 0.25 ? "yes" : "no";
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
        .claim = "\"Executamos o algoritmo removendo o algoritmo de anti-aliasing e chegamos a "
            "um decréscimo de tempo inferior a 30% na média\": without the antialiasing "
            "the time falls by less than 30% on average (so antialiasing costs under "
            "1/0.7 = 1.43 times point sampling; under 1.3 times read as a 30% overhead).",
        .setting = "adaptive (the paper's method, tag=0) against point, crow, star, feibush, "
            "catmull:tiles=4 and slivers at 256x256, box; one thread, the median of "
            "the ratios of interleaved renders.",
        .patterns = LIST("crow", "star", "feibush", "catmull:tiles=4", "slivers"), .size = 256,
        .filter = "box",
        .methods = LIST("point", "adaptive", "supersample:n=2", "supersample:n=3"),
        .measure = ramos_borges,
    },
    {
        .paper = "Ramos and Borges",
        .where = "abstract; sec. 3",
        .claim = "\"in general, the algorithm produces a better result than that obtained "
            "with usual implementations of non-adaptative supersampling\"; for a single "
            "edge \"o método, neste caso, é muito melhor que super-amostragem simples\".",
        .setting = "adaptive against supersample:n=2 and n=3 (regular grids of 4 and 9 "
            "samples), the counts bracketing adaptive's own samples per pixel; same "
            "scenes; RMSE against the box reference.",
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
        .setting = "crow 256x256 under tent:r=1: crowtable (form=crow, 16 table entries per dot) "
            "against the exact reference and 5 x 5 supersampling of the same filter.",
        .patterns = LIST("crow"), .size = 256, .filter = "tent:r=1",
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
        .where = "ch. 1, \"Establishing a reference for image quality\", pp. 10-16; ch. 3, figs. "
            "3.15-3.17",
        .claim = "Doubling the resolution gives four blends of two surfaces, quadrupling 16; "
            "\"an algorithm which blends at the base resolution should be able to produce "
            "superior pictures at the same viewing distance\"; and doubling \"does not help "
            "the representation of very small objects\".",
        .setting = "256x256, box: area (blending exactly at the base resolution) against point at "
            "doubled and quadrupled resolution averaged down (supersample:n=2 and n=4, "
            "exactly those); crowtiler (tent:r=1) beside; RMSE against the box reference "
            "and eye RMSE.",
        .patterns = LIST("crow", "star", "slivers", "dots"), .size = 256,
        .filters = LIST("box", "box", "box", "tent:r=1"),
        .methods = LIST("area", "supersample:n=2", "supersample:n=4", "crowtiler"),
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
            "256x256; RMSE and largest error against the exact reference.",
        .patterns = LIST("feibush", "catmull:tiles=4", "slivers", "star"), .size = 256,
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
        .setting = "smaa (SMAA 1x's spatial filter, without its diagonal patterns) against "
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

static void html_cell(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        default: fputc(*s, f);
        }
    }
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
        "an untimed init), taken alternately a b, b a, ...; the machine was shared with other "
        "work, so single times are noisy and only such ratios are quoted. Errors: "
        "RMSE against the exact reference under the method's filter (point sampling and its "
        "post-processes: the box), linear light; \"eye RMSE\": what an eye of s = %g pixels "
        "sees of the image shown as pixel squares against what it sees of the scene itself "
        "(harness/bench/eye.c); \"staircase energy\": the error's power above 1/4 cycle per "
        "pixel; \"beat energy\": the image's own power above 0.35 cycle per pixel, which "
        "beats with the grid of dots into fringes. Reproduced: yes, no, or partly (one part "
        "holds, another not).";
    fprintf(m, intro, reps, AA_EYE_S);
    fprintf(m, "\n\n| # | paper, where | claim | setting | measured | reproduced |\n"
               "|---|---|---|---|---|---|\n");
    fputs("<p>", h);
    fprintf(h, intro, reps, AA_EYE_S);
    fputs("</p>\n<table>\n<tr><th>#</th><th>paper, where</th><th>claim</th><th>setting</th>"
          "<th>measured</th><th>reproduced</th></tr>\n",
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
        fprintf(m, " | **%s** |\n", c[k].verdict);
        fprintf(h, "<tr><td>%d</td><td>", k + 1);
        html_cell(h, c[k].row->paper);
        fputs(", ", h);
        html_cell(h, c[k].row->where);
        fputs("</td><td>", h);
        html_cell(h, c[k].row->claim);
        fputs("</td><td>", h);
        html_cell(h, c[k].row->setting);
        fputs("</td><td>", h);
        html_cell(h, c[k].measured);
        fprintf(h, "</td><td><b>%s</b></td></tr>\n", c[k].verdict);
    }
    fputs("</table>\n", h);
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
