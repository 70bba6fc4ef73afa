/*
 * figures.c: the seed papers' comparison figures, remade.
 *
 * Each figure is a list of panels rendered on one view (pattern, size,
 * filter) and composed with aa_montage_write into DIR/NAME.png; DIR/NAME.txt
 * holds its settings and, for every panel, the RMSE and largest error
 * against the exact reference of the view (aa_reference, aa_metrics_compute,
 * linear light).  DIR/index.html shows every figure present in DIR.
 *
 * Figures follow Crow (1977) figs. 2.10-2.14, 3.17-3.19 and his remark on
 * display intensity (the square law; fig-crow-A), Catmull (1978) fig. 1
 * (one pixel's colour by each method) and Feibush, Levoy and Cook (1980)
 * figs. 4b-4d.  Limits: the patterns are this project's renditions of the
 * papers' scenes (patterns/README.md), not scans of the originals, and the panels
 * are shown at the size they are rendered (only fig-catmull-1 is
 * magnified, by replicating pixels), so a page viewer's scaling may add
 * moire of its own.
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FIG_SEED 1

enum panel_kind {
    P_METHOD,    /* the method on the view */
    P_REFERENCE, /* the exact reference of the view */
    P_DOWN2,     /* the method at twice the size, box-averaged 2 x 2 down */
    P_ENCODED    /* the method shown with an encoding, beside a grey ramp */
};

typedef struct fig_panel {
    int kind;
    const char *method; /* method spec (P_METHOD, P_DOWN2, P_ENCODED) */
    const char *label;
    const char *enc; /* P_ENCODED: display encoding */
} fig_panel;

typedef struct fig_def {
    const char *name;
    const char *title;
    const char *pattern;
    int w, h;
    const char *filter;
    int magnify; /* catmull: a 1 x 1 view shown as a swatch this many pixels a side */
    int columns;
    int npanels;
    fig_panel panel[AA_FIGURE_PANELS];
} fig_def;

static const fig_def figures[] = {
    {"fig-crow-2.10", "Crow (1977) fig. 2.10: point sampling, one sample at each pixel centre",
     "crow", 256, 256, "box", 0, 1, 1, {{P_METHOD, "point", "point", NULL}}},
    {"fig-crow-2.11", "Crow (1977) fig. 2.11: 3 x 3 supersampling, box filter", "crow", 256,
     256, "box", 0, 1, 1, {{P_METHOD, "supersample:n=3", "supersample:n=3", NULL}}},
    {"fig-crow-2.12", "Crow (1977) fig. 2.12: 5 x 5 supersampling weighted by a tent of radius 1",
     "crow", 256, 256, "tent:r=1", 0, 1, 1,
     {{P_METHOD, "supersample:n=5", "supersample:n=5", NULL}}},
    {"fig-crow-2.13",
     "Crow (1977) fig. 2.13: tent filter of radius 1/2, the exact reference beside 5 x 5 "
     "supersampling",
     "crow", 256, 256, "tent:r=0.5", 0, 2, 2,
     {{P_REFERENCE, NULL, "exact reference", NULL},
      {P_METHOD, "supersample:n=5", "supersample:n=5", NULL}}},
    {"fig-crow-2.14",
     "Crow (1977) fig. 2.14: tent filter of radius 1, the exact reference beside 5 x 5 "
     "supersampling",
     "crow", 256, 256, "tent:r=1", 0, 2, 2,
     {{P_REFERENCE, NULL, "exact reference", NULL},
      {P_METHOD, "supersample:n=5", "supersample:n=5", NULL}}},
    {"fig-crow-3.17",
     "Crow (1977) fig. 3.17: slender triangles by area sampling, point sampling, and point "
     "sampling at twice the resolution averaged 2 x 2 down",
     "slivers", 256, 256, "box", 0, 3, 3,
     {{P_METHOD, "area", "area", NULL},
      {P_METHOD, "point", "point", NULL},
      {P_DOWN2, "point", "point at 512x512, 2x2 mean", NULL}}},
    {"fig-crow-3.18", "Crow (1977) fig. 3.18: the parabolic pattern unfiltered (point sampling)",
     "crow", 256, 256, "box", 0, 1, 1, {{P_METHOD, "point", "unfiltered (point)", NULL}}},
    {"fig-crow-3.19", "Crow (1977) fig. 3.19: the parabolic pattern filtered (exact area)",
     "crow", 256, 256, "box", 0, 1, 1, {{P_METHOD, "area", "filtered (area)", NULL}}},
    {"fig-crow-A",
     "Crow (1977), display intensity: the area image encoded linear, sRGB and with the square "
     "law (gamma 2), each beside a ramp of linear intensity 0 to 1 encoded the same way",
     "crow", 256, 256, "box", 0, 3, 3,
     {{P_ENCODED, "area", "area, linear", "linear"},
      {P_ENCODED, "area", "area, sRGB", "srgb"},
      {P_ENCODED, "area", "area, gamma 2 (square law)", "gamma:2"}}},
    {"fig-catmull-1",
     "Catmull (1978) fig. 1: the colour of one pixel holding a hidden red, green and blue in "
     "front, by each method (64 x 64 swatches of the 1 x 1 image)",
     "catmull", 1, 1, "box", 64, 5, 5,
     {{P_METHOD, "point", "point", NULL},
      {P_METHOD, "supersample:n=4", "supersample:n=4", NULL},
      {P_METHOD, "jitter:spp=16", "jitter:spp=16", NULL},
      {P_METHOD, "area", "area", NULL},
      {P_REFERENCE, NULL, "exact reference", NULL}}},
    {"fig-feibush-4b", "Feibush, Levoy and Cook (1980) fig. 4b: point sampling", "feibush", 256,
     256, "box", 0, 1, 1, {{P_METHOD, "point", "point", NULL}}},
    {"fig-feibush-4c", "Feibush, Levoy and Cook (1980) fig. 4c: exact area (box filter)",
     "feibush", 256, 256, "box", 0, 1, 1, {{P_METHOD, "area", "area (box)", NULL}}},
    {"fig-feibush-4d",
     "Feibush, Levoy and Cook (1980) fig. 4d: Gaussian filter (s = 1 px), 5 x 5 supersampling "
     "beside the exact reference",
     "feibush", 256, 256, "gauss:s=1", 0, 2, 2,
     {{P_METHOD, "supersample:n=5", "supersample:n=5", NULL},
      {P_REFERENCE, NULL, "exact reference", NULL}}},
};

#define NFIG (sizeof figures / sizeof figures[0])

size_t aa_figure_count(void)
{
    return NFIG;
}

const char *aa_figure_name(size_t k)
{
    return k < NFIG ? figures[k].name : NULL;
}

int aa_figure_find(const char *name)
{
    for (size_t k = 0; k < NFIG; k++)
        if (strcmp(figures[k].name, name) == 0)
            return (int)k;
    return -1;
}

/* sRGB decoding (IEC 61966-2-1): a value to display as `e` is stored as
 * its linear light, so the sRGB PNG writer gives back e. */
static double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* Render one method on the view at w x h into out (allocated here). */
static int render_method(const fig_def *f, const aa_scene *scene, const aa_filter *filter,
                         const char *method, int w, int h, int threads, aa_image *out)
{
    aa_spec spec;
    aa_job job;
    aa_counters counters;
    int st = aa_method_parse(method, filter, &spec);
    if (st)
        return aa_fail_context(st, "%s", f->name);
    if ((st = aa_job_init(&job, scene, w, h, 0, 0, 0, filter, FIG_SEED, threads)))
        return st;
    if (!(st = aa_image_alloc(out, w, h, 3))) {
        st = aa_method_run(&spec, &job, 1, out, &counters, NULL);
        if (st)
            aa_image_free(out);
    }
    aa_job_free(&job);
    return st ? aa_fail_context(st, "%s: %s", f->name, method) : AA_OK;
}

/* The 2 x 2 box mean of `big` (2w x 2h) into out (w x h). */
static int down2(const aa_image *big, aa_image *out)
{
    int st = aa_image_alloc(out, big->w / 2, big->h / 2, 3);
    if (st)
        return st;
    for (int j = 0; j < out->h; j++)
        for (int i = 0; i < out->w; i++)
            for (int k = 0; k < 3; k++)
                aa_pixel(out, i, j)[k] =
                    0.25 * (aa_pixel(big, 2 * i, 2 * j)[k] + aa_pixel(big, 2 * i + 1, 2 * j)[k] +
                            aa_pixel(big, 2 * i, 2 * j + 1)[k] +
                            aa_pixel(big, 2 * i + 1, 2 * j + 1)[k]);
    return AA_OK;
}

/* The tile of a panel: the image itself, a magnified swatch (pixels
 * replicated, on a ground wide enough for its label), or the image encoded
 * with `enc` beside a ramp encoded the same way. */
#define RAMP_GAP 6
#define RAMP_W 32
#define SWATCH_GROUND 176
static int make_tile(const fig_def *f, const fig_panel *p, const aa_image *im, aa_image *tile)
{
    int st;
    if (f->magnify > 0) {
        int m = f->magnify, tw = m * im->w > SWATCH_GROUND ? m * im->w : SWATCH_GROUND;
        if ((st = aa_image_alloc(tile, tw, m * im->h, 3)))
            return st;
        for (size_t q = 0; q < (size_t)tile->w * tile->h * 3; q++)
            tile->v[q] = 0.01; /* the montage's ground */
        for (int j = 0; j < m * im->h; j++)
            for (int i = 0; i < m * im->w; i++)
                memcpy(aa_pixel(tile, i, j), aa_pixel(im, i / m, j / m), 3 * sizeof(double));
        return AA_OK;
    }
    if (p->kind == P_ENCODED) {
        aa_encode e;
        if ((st = aa_encode_parse(p->enc, &e)))
            return st;
        if ((st = aa_image_alloc(tile, im->w + RAMP_GAP + RAMP_W, im->h, 3)))
            return st;
        for (int j = 0; j < im->h; j++) {
            double ramp = im->h > 1 ? 1.0 - (double)j / (im->h - 1) : 1.0;
            for (int i = 0; i < tile->w; i++) {
                double *t = aa_pixel(tile, i, j);
                for (int k = 0; k < 3; k++) {
                    if (i < im->w)
                        t[k] = srgb_decode(aa_encode_value(&e, aa_pixel(im, i, j)[k]));
                    else if (i < im->w + RAMP_GAP)
                        t[k] = 0.01;
                    else
                        t[k] = srgb_decode(aa_encode_value(&e, ramp));
                }
            }
        }
        return AA_OK;
    }
    if ((st = aa_image_alloc(tile, im->w, im->h, 3)))
        return st;
    memcpy(tile->v, im->v, sizeof(double) * 3 * (size_t)im->w * (size_t)im->h);
    return AA_OK;
}

static void html_escape(FILE *out, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '&': fputs("&amp;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fputc(*s, out);
        }
    }
}

/* A memory stream's text written atomically. */
static int write_stream(const char *path, FILE *mem, char **buf, size_t *len)
{
    if (fflush(mem) != 0) {
        fclose(mem);
        free(*buf);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    fclose(mem);
    int st = aa_file_write_atomic(path, *buf, *len);
    free(*buf);
    return st;
}

static int write_caption(const char *dir, const fig_def *f, const aa_figure_result *r)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/%s.txt", dir, f->name);
    if (st)
        return st;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    fprintf(m, "%s\n%s\n\n", f->name, f->title);
    fprintf(m, "pattern: %s\nsize: %dx%d\nfilter: %s\nseed: %d\n", f->pattern, f->w, f->h,
            f->filter, FIG_SEED);
    if (f->magnify)
        fprintf(m, "shown: each %dx%d image magnified %d times (pixels replicated)\n", f->w, f->h,
                f->magnify);
    fprintf(m, "remake: aabench figures --only %s\n", f->name);
    fprintf(m, "errors: against the exact reference (%s, %dx%d), linear light, all channels\n\n",
            f->filter, f->w, f->h);
    for (int k = 0; k < r->npanels; k++) {
        const fig_panel *p = &f->panel[k];
        const aa_figure_panel *q = &r->panel[k];
        fprintf(m, "panel %d: %s\n", k + 1, p->label);
        switch (p->kind) {
        case P_REFERENCE: fprintf(m, "  method: exact reference\n"); break;
        case P_DOWN2:
            fprintf(m, "  method: %s at %dx%d, mean of each 2x2 block\n", p->method, 2 * f->w,
                    2 * f->h);
            break;
        case P_ENCODED: fprintf(m, "  method: %s\n  encoding: %s\n", p->method, p->enc); break;
        default: fprintf(m, "  method: %s\n", p->method);
        }
        if (f->magnify)
            fprintf(m, "  rgb: %.6f %.6f %.6f\n", q->rgb[0], q->rgb[1], q->rgb[2]);
        fprintf(m, "  rmse: %.9e\n  max_err: %.9e\n", q->rmse, q->max_err);
        if (p->kind == P_ENCODED)
            fprintf(m, "  rmse_encoded: %.9e\n  max_err_encoded: %.9e\n", q->rmse_enc,
                    q->max_err_enc);
    }
    return write_stream(path, m, &buf, &len);
}

static int figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                       aa_figure_result *r)
{
    if (k >= NFIG)
        return aa_fail(AA_EINVAL, "no figure %zu (there are %zu)", k, NFIG);
    const fig_def *f = &figures[k];
    memset(r, 0, sizeof *r);
    r->name = f->name;
    r->npanels = f->npanels;
    double t0 = aa_now();
    aa_view view;
    memset(&view, 0, sizeof view);
    aa_scene *scene = NULL;
    aa_image ref = {0}, imgs[AA_FIGURE_PANELS], tiles[AA_FIGURE_PANELS];
    aa_tile tl[AA_FIGURE_PANELS];
    char labels[AA_FIGURE_PANELS][3][128];
    memset(imgs, 0, sizeof imgs);
    memset(tiles, 0, sizeof tiles);
    memset(tl, 0, sizeof tl);
    memset(labels, 0, sizeof labels); /* a panel may have no third line */
    int st = aa_pattern_parse(f->pattern, &view.pattern);
    if (!st)
        st = aa_filter_parse(f->filter, &view.filter);
    view.w = f->w, view.h = f->h;
    if (!st)
        st = aa_pattern_scene_at(&view.pattern, view.w, view.h, &scene);
    if (!st)
        st = aa_reference(&view, cache_dir, threads, &ref, NULL, NULL);
    for (int p = 0; p < f->npanels && !st; p++) {
        const fig_panel *fp = &f->panel[p];
        aa_figure_panel *q = &r->panel[p];
        if (fp->kind == P_REFERENCE) {
            if (!(st = aa_image_alloc(&imgs[p], ref.w, ref.h, 3)))
                memcpy(imgs[p].v, ref.v, sizeof(double) * 3 * (size_t)ref.w * (size_t)ref.h);
        } else if (fp->kind == P_DOWN2) {
            aa_image big = {0};
            st = render_method(f, scene, &view.filter, fp->method, 2 * f->w, 2 * f->h, threads,
                               &big);
            if (!st)
                st = down2(&big, &imgs[p]);
            aa_image_free(&big);
        } else {
            st = render_method(f, scene, &view.filter, fp->method, f->w, f->h, threads, &imgs[p]);
        }
        if (st)
            break;
        aa_metrics met;
        aa_encode enc = {AA_ENCODE_SRGB, 2.2};
        if (fp->kind == P_ENCODED && (st = aa_encode_parse(fp->enc, &enc)))
            break;
        if ((st = aa_metrics_compute(&ref, &imgs[p], &enc, &met)))
            break;
        snprintf(q->label, sizeof q->label, "%s", fp->label);
        q->reference = fp->kind == P_REFERENCE;
        q->rmse = met.rmse, q->max_err = met.max_err;
        q->rmse_enc = met.rmse_enc, q->max_err_enc = met.max_err_enc;
        for (int c = 0; c < 3; c++)
            q->rgb[c] = imgs[p].v[c];
        if ((st = make_tile(f, fp, &imgs[p], &tiles[p])))
            break;
        tl[p].image = &tiles[p];
        snprintf(labels[p][0], sizeof labels[p][0], "%s", fp->label);
        if (f->magnify)
            snprintf(labels[p][1], sizeof labels[p][1], "RGB %.3f %.3f %.3f", q->rgb[0],
                     q->rgb[1], q->rgb[2]);
        else if (fp->kind == P_REFERENCE)
            snprintf(labels[p][1], sizeof labels[p][1], "%s", f->filter);
        else
            snprintf(labels[p][1], sizeof labels[p][1], "RMSE %.3g  max %.3g", q->rmse,
                     q->max_err);
        if (f->magnify && fp->kind != P_REFERENCE)
            snprintf(labels[p][2], sizeof labels[p][2], "RMSE %.3g", q->rmse);
        else if (fp->kind == P_ENCODED)
            snprintf(labels[p][2], sizeof labels[p][2], "encoded RMSE %.3g", q->rmse_enc);
        tl[p].label[0] = labels[p][0];
        tl[p].label[1] = labels[p][1];
        tl[p].label[2] = labels[p][2][0] ? labels[p][2] : NULL;
    }
    char path[4096];
    if (!st)
        st = aa_pathf(path, sizeof path, "%s/%s.png", dir, f->name);
    if (!st)
        st = aa_montage_write(path, tl, (size_t)f->npanels, f->columns, NULL);
    if (!st)
        st = write_caption(dir, f, r);
    for (int p = 0; p < AA_FIGURE_PANELS; p++) {
        aa_image_free(&imgs[p]);
        aa_image_free(&tiles[p]);
    }
    aa_image_free(&ref);
    aa_scene_free(scene);
    r->seconds = aa_now() - t0;
    return st;
}

/* The settings file and the panels' labels write C-locale numbers,
 * whatever LC_NUMERIC the program has set. */
int aa_figure_make(size_t k, const char *dir, const char *cache_dir, int threads,
                   aa_figure_result *r)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = figure_make(k, dir, cache_dir, threads, r);
    aa__c_numbers_end(&numbers);
    return st;
}

/* Read a whole small text file; NULL if absent. */
static char *slurp(const char *path)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0, n;
    char chunk[4096];
    while ((n = fread(chunk, 1, sizeof chunk, in)) > 0) {
        if (len + n + 1 > cap) {
            cap = 2 * (len + n + 1);
            char *nb = realloc(buf, cap);
            if (!nb) {
                free(buf);
                fclose(in);
                return NULL;
            }
            buf = nb;
        }
        memcpy(buf + len, chunk, n);
        len += n;
    }
    fclose(in);
    if (!buf)
        buf = calloc(1, 1);
    else
        buf[len] = '\0';
    return buf;
}

int aa_figure_index(const char *dir)
{
    char path[4096];
    int st = aa_pathf(path, sizeof path, "%s/index.html", dir);
    if (st)
        return st;
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<title>aabench: published figures remade</title>\n<style>\n"
          "body { background: #1a1a1a; color: #ddd; font-family: sans-serif; margin: 2em; }\n"
          "h1 { font-weight: normal; }\n"
          "figure { margin: 0 0 3em 0; padding: 1em; background: #262626; }\n"
          "figure img { display: block; image-rendering: pixelated; max-width: none; }\n"
          "figcaption h2 { font-size: 1.1em; margin: 0.8em 0 0.3em 0; }\n"
          "pre { font-size: 0.85em; color: #bbb; white-space: pre-wrap; }\n"
          "nav a { color: #9cf; margin-right: 1em; }\n"
          "</style>\n</head>\n<body>\n<h1>Published figures, remade by aabench</h1>\n"
          "<p>Each image is shown at its own size, pixel for pixel. Errors are against the "
          "exact reference of the same pattern, size and filter, in linear light.</p>\n<nav>",
          m);
    int shown = 0;
    for (size_t k = 0; k < NFIG; k++) {
        char png[4096];
        if (aa_pathf(png, sizeof png, "%s/%s.png", dir, figures[k].name) == AA_OK) {
            FILE *t = fopen(png, "rb");
            if (t) {
                fclose(t);
                fprintf(m, "<a href=\"#%s\">%s</a>", figures[k].name, figures[k].name);
            }
        }
    }
    fputs("</nav>\n", m);
    for (size_t k = 0; k < NFIG; k++) {
        const fig_def *f = &figures[k];
        char png[4096], txt[4096];
        if (aa_pathf(png, sizeof png, "%s/%s.png", dir, f->name) ||
            aa_pathf(txt, sizeof txt, "%s/%s.txt", dir, f->name))
            continue;
        FILE *t = fopen(png, "rb");
        if (!t)
            continue;
        fclose(t);
        char *cap = slurp(txt);
        fprintf(m, "<figure id=\"%s\">\n<img src=\"%s.png\" alt=\"", f->name, f->name);
        html_escape(m, f->title);
        fprintf(m, "\">\n<figcaption>\n<h2>%s</h2>\n<p>", f->name);
        html_escape(m, f->title);
        fputs("</p>\n", m);
        if (cap) {
            fputs("<pre>", m);
            html_escape(m, cap);
            fputs("</pre>\n", m);
            free(cap);
        }
        fputs("</figcaption>\n</figure>\n", m);
        shown++;
    }
    if (!shown)
        fputs("<p>No figures in this folder yet: run <code>aabench figures</code>.</p>\n", m);
    fputs("</body>\n</html>\n", m);
    return write_stream(path, m, &buf, &len);
}
