/*
 * runreport.c: the run folder's report, index.html: what a reader opens
 * first.  For each view (pattern, size, filter) of the run, in the order
 * the run met them: the table of its methods sorted by RMSE (RMSE, edge
 * RMSE, largest error, FLIP, SSIM, PSNR, median render time; a refused or
 * failed case with its note), its montage, and each method's error map and
 * worst region (errmap.c); then the plots.  Only files present are shown
 * (a run with --no-images or --no-plots has none of those).  The page is
 * static HTML, no script, every image at its own size, pixel for pixel.
 */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int present(const char *dir, const char *rel)
{
    char path[4600];
    return !aa_pathf(path, sizeof path, "%s/%s", dir, rel) && access(path, R_OK) == 0;
}

/* 1 if rows[k] is the first of the rows with its view */
static int first_of_view(const aa_row *rows, size_t k)
{
    for (size_t q = 0; q < k; q++)
        if (aa_rows_same_view(&rows[q], &rows[k]))
            return 0;
    return 1;
}

/* the rows qsort's comparison looks the indices up in */
static const aa_row *sort_rows;
static int by_rmse(const void *a, const void *b)
{
    const aa_row *x = &sort_rows[*(const size_t *)a], *y = &sort_rows[*(const size_t *)b];
    if (x->ok != y->ok)
        return y->ok - x->ok;
    if (!x->ok)
        return 0;
    return (x->m.rmse > y->m.rmse) - (x->m.rmse < y->m.rmse);
}

static void num(FILE *m, const char *fmt, double v)
{
    fputs("<td>", m);
    if (isfinite(v))
        fprintf(m, fmt, v);
    else if (isinf(v))
        fputs("inf", m);
    else
        fputs("&ndash;", m);
    fputs("</td>", m);
}

/* images/STEM-SUFFIX for a row, when present: into rel. */
static int image_of(const char *dir, const aa_row *r, const char *suffix, char *rel, size_t len)
{
    char ps[512], fs[256], ms[512];
    aa_spec_slug(r->pattern, ps, sizeof ps);
    aa_spec_slug(r->filter, fs, sizeof fs);
    aa_spec_slug(r->method, ms, sizeof ms);
    snprintf(rel, len, "images/%s-%dx%d-%s-%s%s", ps, r->w, r->h, fs, ms, suffix);
    return present(dir, rel);
}

static void view_section(FILE *m, const char *dir, const aa_row *rows, size_t n, size_t first,
                         int is_first, size_t *idx)
{
    const aa_row *r0 = &rows[first];
    size_t k = 0;
    for (size_t q = first; q < n; q++)
        if (aa_rows_same_view(&rows[q], r0))
            idx[k++] = q;
    sort_rows = rows;
    qsort(idx, k, sizeof *idx, by_rmse);
    char ps[512], fs[256], rel[2400];
    aa_spec_slug(r0->pattern, ps, sizeof ps);
    aa_spec_slug(r0->filter, fs, sizeof fs);
    fprintf(m, "<section id=\"%s-%dx%d-%s\">\n<h2>", ps, r0->w, r0->h, fs);
    aa_html_escape(m, r0->pattern);
    fprintf(m, " %dx%d, ", r0->w, r0->h);
    aa_html_escape(m, r0->filter);
    fputs("</h2>\n", m);
    /* the reference's own bound (each row of the view that compared with it holds it;
     * NaN in files written before it was recorded) */
    for (size_t q = 0; q < k; q++) {
        const aa_row *r = &rows[idx[q]];
        if (!r->ok || !isfinite(r->ref_bound))
            continue;
        if (r->ref_scanned > 0)
            fprintf(m, "<p class=\"small\">The exact reference: each pixel within its bound, "
                       "the largest %.2e; %.0f pixel%s bounded by an estimate, not a proof.</p>\n",
                    r->ref_bound, r->ref_scanned, r->ref_scanned == 1 ? "" : "s");
        else
            fprintf(m, "<p class=\"small\">The exact reference: each pixel within %.2e of the "
                       "filtered scene, proven; an error below that is not measured.</p>\n",
                    r->ref_bound);
        break;
    }
    fputs("<table>\n<tr><th>method</th><th>rmse</th><th>edge_rmse</th><th>max_err</th>"
          "<th>flip</th><th>ssim</th><th>psnr dB</th><th>ms (median)</th><th>init ms</th></tr>\n",
          m);
    for (size_t q = 0; q < k; q++) {
        const aa_row *r = &rows[idx[q]];
        fputs("<tr><td>", m);
        aa_html_escape(m, r->method);
        fputs("</td>", m);
        if (!r->ok) {
            fputs("<td colspan=\"8\" class=\"note\">", m);
            aa_html_escape(m, r->note);
            fputs("</td></tr>\n", m);
            continue;
        }
        num(m, "%.3e", r->m.rmse);
        num(m, "%.3e", r->m.edge_rmse);
        num(m, "%.3e", r->m.max_err);
        num(m, "%.4f", r->m.flip);
        num(m, "%.4f", r->m.ssim);
        num(m, "%.2f", r->m.psnr);
        fputs("<td>", m);
        if (isfinite(r->seconds))
            fprintf(m, "%.3f%s", r->seconds * 1e3, r->timing.noisy ? " *" : "");
        fputs("</td>", m);
        num(m, "%.3f", r->timing.init_seconds * 1e3); /* the init, once, outside those */
        fputs("</tr>\n", m);
    }
    fputs("</table>\n", m);
    if (is_first)
        snprintf(rel, sizeof rel, "montage.png");
    else
        snprintf(rel, sizeof rel, "montage-%s-%dx%d-%s.png", ps, r0->w, r0->h, fs);
    int montage = present(dir, rel);
    if (montage) {
        fputs("<h3>Montage</h3>\n<p class=\"small\">The exact reference first, then each method "
              "(views larger than 256x256: their centre), pixel for pixel.</p>\n",
              m);
        fprintf(m, "<img src=\"%s\" alt=\"montage\">\n", rel);
    }
    int header = 0;
    for (size_t q = 0; q < k; q++) {
        const aa_row *r = &rows[idx[q]];
        char worst[2400];
        if (!r->ok)
            continue;
        int e = image_of(dir, r, "-error.png", rel, sizeof rel);
        int w = image_of(dir, r, "-worst.png", worst, sizeof worst);
        if (!e && !w)
            continue;
        if (!header++)
            fputs("<h3>Error maps and worst regions</h3>\n<p class=\"small\">Left: the image "
                  "minus the reference in linear light (blue darker, red brighter), each map "
                  "scaled to its own errors, the scale on its bar. Right: the 32x32 window of "
                  "largest squared error, zoomed: reference, image, error and FLIP.</p>\n",
                  m);
        fputs("<div class=\"case\"><h4>", m);
        aa_html_escape(m, r->method);
        fputs("</h4>", m);
        if (e)
            fprintf(m, "<img src=\"%s\" alt=\"error map\">", rel);
        if (w)
            fprintf(m, "<img src=\"%s\" alt=\"worst region\">", worst);
        fputs("</div>\n", m);
    }
    size_t ran = 0;
    for (size_t q = 0; q < k; q++)
        ran += rows[idx[q]].ok != 0;
    if (ran && !header && !montage)
        fputs("<p class=\"small\">No images of this view: a run writes those of views up to "
              "512x512 pixels and of its smallest size (<code>aabench run --images all</code>: "
              "every view's; <code>--no-images</code>: none).</p>\n",
              m);
    fputs("</section>\n", m);
}

int aa_run_report(const char *dir, const aa_row *rows, size_t n)
{
    char path[4200];
    int st = aa_pathf(path, sizeof path, "%s/index.html", dir);
    if (st)
        return st;
    size_t *idx = malloc((n ? n : 1) * sizeof *idx);
    char *buf = NULL;
    size_t len = 0;
    FILE *m = idx ? open_memstream(&buf, &len) : NULL;
    if (!m) {
        free(idx);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<title>aabench run</title>\n<style>\n"
          "body { background: #fafafa; color: #222; font-family: sans-serif; margin: 2em; }\n"
          "h1, h2 { font-weight: normal; }\n"
          "section { margin: 2em 0 3em 0; }\n"
          "img { display: block; image-rendering: pixelated; max-width: none; margin: 0.5em 0; }\n"
          "div.case { display: inline-block; vertical-align: top; margin: 0 1.5em 1em 0; }\n"
          "div.case img { display: inline-block; margin-right: 0.5em; vertical-align: top; }\n"
          "h4 { margin: 0.3em 0; font-weight: normal; font-family: monospace; }\n"
          "table { border-collapse: collapse; font-size: 0.9em; }\n"
          "td, th { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }\n"
          "td:first-child, th:first-child { text-align: left; font-family: monospace; }\n"
          "th { background: #e8e8e8; }\n td.note { text-align: left; color: #844; }\n"
          "p { max-width: 62em; } p.small { font-size: 0.9em; color: #555; }\n"
          "nav a { margin-right: 1em; }\n"
          "</style>\n</head>\n<body>\n<h1>aabench run</h1>\n",
          m);
    const char *base = strrchr(dir, '/');
    fputs("<p>Folder <code>", m);
    aa_html_escape(m, base && base[1] ? base + 1 : dir);
    fputs("</code>: results.csv and results.json hold every number below. Errors are against "
          "the exact reference of the same pattern, size and filter: <b>rmse</b> and "
          "<b>max_err</b> over every channel of every pixel in linear light; <b>edge_rmse</b> "
          "over the pixels whose filter support meets an edge of the scene only, where "
          "antialiasing has work to do; <b>flip</b> the mean LDR-FLIP (Andersson et al. 2020) of "
          "the display-encoded images seen at 67 pixels per degree (a 0.7 m wide 3840-pixel "
          "monitor at 0.7 m), 0 for no visible difference, 1 the largest; <b>ssim</b> on the "
          "encoded luma. A time marked * was measured while the machine was busy.</p>\n<nav>",
          m);
    for (size_t k = 0; k < n; k++) {
        if (!first_of_view(rows, k))
            continue;
        char ps[512], fs[256];
        aa_spec_slug(rows[k].pattern, ps, sizeof ps);
        aa_spec_slug(rows[k].filter, fs, sizeof fs);
        fprintf(m, "<a href=\"#%s-%dx%d-%s\">", ps, rows[k].w, rows[k].h, fs);
        aa_html_escape(m, rows[k].pattern);
        fprintf(m, " %dx%d ", rows[k].w, rows[k].h);
        aa_html_escape(m, rows[k].filter);
        fputs("</a>", m);
    }
    if (present(dir, "plots/error_vs_time.png"))
        fputs("<a href=\"#plots\">plots</a>", m);
    fputs("</nav>\n", m);
    int first_done = 0;
    for (size_t k = 0; k < n; k++) {
        if (!first_of_view(rows, k))
            continue;
        /* montage.png is the first view that has a case that ran */
        int is_first = 0;
        if (!first_done) {
            for (size_t p = k; p < n && !is_first; p++)
                is_first = rows[p].ok && aa_rows_same_view(&rows[p], &rows[k]);
            first_done = is_first;
        }
        view_section(m, dir, rows, n, k, is_first, idx);
    }
    if (present(dir, "plots/error_vs_time.png")) {
        fputs("<section id=\"plots\"><h2>Plots</h2>\n<p class=\"small\">RMSE against the median "
              "render time, one panel per view, the Pareto front dashed.</p>\n"
              "<img src=\"plots/error_vs_time.png\" alt=\"error against time\">\n",
              m);
        if (present(dir, "plots/convergence.png"))
            fputs("<img src=\"plots/convergence.png\" alt=\"convergence\">\n", m);
        fputs("</section>\n", m);
    }
    fputs("</body>\n</html>\n", m);
    free(idx);
    if (fflush(m) != 0) {
        fclose(m);
        free(buf);
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    }
    fclose(m);
    st = aa_file_write_atomic(path, buf, len);
    free(buf);
    return st;
}
