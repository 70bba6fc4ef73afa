/*
 * plot.c: plots with gnuplot (pngcairo).
 *
 * Each plot leaves three files: the data (.dat), the gnuplot script that
 * draws it (.gp, so a reader can restyle or re-run it), and the picture
 * (.png, drawn under a temporary name and renamed).
 *
 *   error_vs_time   RMSE against median render time, log-log, one panel per
 *                   view (pattern, size, filter), each method family its own
 *                   colour and marker, horizontal bars for the 95% CI of the
 *                   median, each point numbered and a numbered key beside the
 *                   panel (names never overlap the points or each other),
 *                   noisy timings starred, the view's Pareto front (no other
 *                   method both faster and more accurate) drawn as a
 *                   staircase; methods exact to rounding (RMSE below 1e-9)
 *                   sit on the panel's floor, a quarter of the lowest other
 *                   error, their error given in the key
 *   convergence     RMSE against samples per pixel, log-log, one colour and
 *                   marker per method and sequence with its fitted line and
 *                   slope, and the theory's slopes for edges drawn dashed:
 *                   -1/2 (independent random), -3/4 (stratified, QMC)
 *
 * Numbers in the data and the scripts are C-locale text, whatever
 * LC_NUMERIC the program has set (gnuplot reads them so).
 */
#include "bench.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* Run gnuplot on `script` in folder `dir` with the assignments `assign`
 * (gnuplot commands run first, e.g. "out='x.png'"); its messages go to
 * `log`. */
static int gnuplot(const char *dir, const char *script, const char *assign, const char *log)
{
    /* The child must not inherit unwritten stdio buffers: it would write
     * them again when its streams are closed. */
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return aa_fail(AA_EIO, "cannot start gnuplot: %s", strerror(errno));
    if (pid == 0) {
        /* file descriptors only: no stdio in the child */
        int err = open(log, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (err < 0 || null < 0 || dup2(err, 2) < 0 || dup2(null, 1) < 0 || chdir(dir) != 0)
            _exit(126);
        execlp("gnuplot", "gnuplot", "-e", assign, script, (char *)NULL);
        _exit(127);
    }
    int status;
    if (waitpid(pid, &status, 0) < 0)
        return aa_fail(AA_EIO, "gnuplot: %s", strerror(errno));
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return aa_fail(AA_EIO, "gnuplot not found (Debian package gnuplot-nox)");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return aa_fail(AA_EIO, "gnuplot failed on %s (see %s)", script, log);
    return AA_OK;
}

/* The file name part of a path. */
static const char *base_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* gnuplot's string syntax into buf: single quotes, with '' for a quote. */
static void gp_quote(char *buf, size_t len, const char *s)
{
    size_t n = 0;
    if (n + 1 < len)
        buf[n++] = '\'';
    for (; *s && n + 3 < len; s++) {
        buf[n++] = *s;
        if (*s == '\'')
            buf[n++] = '\'';
    }
    if (n + 1 < len)
        buf[n++] = '\'';
    buf[n] = '\0';
}

/* Draw NAME.png in `dir` from the data at the temporary path `dat_tmp` (to
 * become dat_name) with `script_text`, which reads the variables `dat` and
 * `out` (and gives them the final names when unset, so the saved NAME.gp
 * remakes the picture by itself).  Every file is written under a unique
 * temporary name and renamed only once gnuplot has succeeded, so two runs
 * into one folder never use each other's files. */
static int draw(const char *dir, const char *name, const char *script_text, const char *dat_tmp,
                const char *dat_name)
{
    char gp[4096], png[4096], log[4096], gp_tmp[4096], png_tmp[4096], dat[4096];
    char assign[8192], q_out[2048], q_dat[2048];
    int st;
    if ((st = aa_pathf(gp, sizeof gp, "%s/%s.gp", dir, name)) ||
        (st = aa_pathf(png, sizeof png, "%s/%s.png", dir, name)) ||
        (st = aa_pathf(dat, sizeof dat, "%s/%s", dir, dat_name)) ||
        (st = aa_temp_name(gp, gp_tmp, sizeof gp_tmp)) ||
        (st = aa_temp_name(png, png_tmp, sizeof png_tmp)) ||
        (st = aa_pathf(log, sizeof log, "%s.log", gp_tmp))) {
        unlink(dat_tmp);
        return st;
    }
    gp_quote(q_out, sizeof q_out, base_of(png_tmp));
    gp_quote(q_dat, sizeof q_dat, base_of(dat_tmp));
    snprintf(assign, sizeof assign, "out=%s; dat=%s", q_out, q_dat);
    if ((st = aa_file_write_atomic(gp_tmp, script_text, strlen(script_text))) ||
        (st = gnuplot(dir, base_of(gp_tmp), assign, log)))
        goto fail;
    unlink(log);
    /* gnuplot exits 0 when its picture could not be written whole (a full
     * disk): the picture must end as a PNG ends */
    if ((st = aa_png_complete(png_tmp))) {
        st = aa_fail_context(st, "%s", png);
        goto fail;
    }
    if (rename(dat_tmp, dat) != 0 || rename(png_tmp, png) != 0 || rename(gp_tmp, gp) != 0) {
        st = aa_fail(AA_EIO, "cannot rename the plot %s into place: %s", png, strerror(errno));
        goto fail;
    }
    return AA_OK;
fail:
    unlink(dat_tmp);
    unlink(png_tmp);
    unlink(gp_tmp);
    return st;
}

static int cmp_time(const void *a, const void *b)
{
    const aa_row *const *x = a, *const *y = b;
    double s = (*x)->seconds, t = (*y)->seconds;
    return s < t ? -1 : s > t;
}

/* gnuplot's string syntax: single quotes, with '' for a quote. */
static void gp_string(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++)
        fputs(*s == '\'' ? "''" : (char[]){*s, 0}, f);
    fputc('\'', f);
}

/* Errors below this are exact to rounding: drawn on the panel's floor. */
#define EXACT 1e-9

/* Each method family (the spec's name) its own colour and marker, the same
 * in every panel and plot: colours from Okabe and Ito's palette (told apart
 * by colour-blind readers; its yellow darkened to show on white) and a few
 * more, markers filled then open. */
static const char *const family_colour[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                            "#E69F00", "#56B4E9", "#000000", "#A08800",
                                            "#7F3C8D", "#8C564B", "#666666", "#1B9E77"};
static const int family_marker[] = {7, 5, 9, 11, 13, 15, 4, 6, 8, 10, 12, 14, 1, 2, 3};
#define NCOLOURS (sizeof family_colour / sizeof *family_colour)
#define NMARKERS (sizeof family_marker / sizeof *family_marker)
#define MAX_FAMILIES 64

typedef struct families {
    char name[MAX_FAMILIES][64];
    int n;
} families;

/* The family of a method spec is its name; its index is its place in the
 * method table, so a family keeps its style from run to run (a name not in
 * the table comes after it, in order of appearance). */
static int family_of(families *f, const char *method)
{
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(method, ":"), method);
    if (f->n == 0) {
        const void *const *table = aa_method_table();
        for (size_t k = 0; table[k] && f->n < MAX_FAMILIES; k++)
            snprintf(f->name[f->n++], sizeof f->name[0], "%s",
                     ((const aa_info *)table[k])->name);
    }
    for (int k = 0; k < f->n; k++)
        if (!strcmp(f->name[k], name))
            return k;
    if (f->n == MAX_FAMILIES)
        return MAX_FAMILIES - 1;
    snprintf(f->name[f->n], sizeof f->name[0], "%s", name);
    return f->n++;
}

/* A style: colour and marker of family k, distinct for the first
 * NCOLOURS x NMARKERS families (colours cycle first, markers shift). */
static void family_style(int k, const char **colour, int *marker)
{
    *colour = family_colour[(size_t)k % NCOLOURS];
    *marker = family_marker[((size_t)k + (size_t)k / NCOLOURS) % NMARKERS];
}

static int plot_error_vs_time(const char *dir, const aa_row *rows, size_t n)
{
    char dat[4096], tmp[4096];
    int st = aa_mkdirs(dir);
    if (st)
        return st;
    snprintf(dat, sizeof dat, "%s/error_vs_time.dat", dir);
    if ((st = aa_temp_name(dat, tmp, sizeof tmp)))
        return st;
    FILE *f = fopen(tmp, "w");
    const aa_row **view = malloc(n * sizeof *view);
    int *done = calloc(n, sizeof *done), views = 0;
    size_t script_len = 1 << 20;
    char *script = malloc(script_len);
    FILE *s = script ? fmemopen(script, script_len, "w") : NULL;
    families fam = {.n = 0};
    if (!f || !view || !done || !s) {
        if (f)
            fclose(f);
        if (s)
            fclose(s);
        free(script);
        free(view);
        free(done);
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s", dat);
    }
    /* the families in the order they first appear, so styles are stable */
    for (size_t k = 0; k < n; k++)
        if (rows[k].ok)
            family_of(&fam, rows[k].method);
    /* count the views for the layout */
    int nviews = 0;
    for (size_t k = 0; k < n; k++) {
        if (done[k] || !rows[k].ok || !(rows[k].seconds > 0))
            continue;
        nviews++;
        for (size_t q = k; q < n; q++)
            if (rows[q].ok && aa_rows_same_view(&rows[k], &rows[q]))
                done[q] = 1;
    }
    memset(done, 0, n * sizeof *done);
    int cols = nviews <= 3 ? 1 : 2, rws = (nviews + cols - 1) / cols;
    fprintf(s, "# error against time: made by aabench run; run with: gnuplot error_vs_time.gp\n"
               "set terminal pngcairo size %d,%d font 'DejaVu Sans,10'\n"
               "if (!exists('out')) out = 'error_vs_time.png'\n"
               "if (!exists('dat')) dat = 'error_vs_time.dat'\nset output out\n",
            1150 * cols, 600 * (rws > 0 ? rws : 1) + 50);
    fprintf(s, "set multiplot layout %d,%d title \"Error against render time: median, bars = "
               "95%% CI of the median; dashed: Pareto front; * noisy timing\" font ',12'\n"
               "set logscale xy\nset grid\nunset key\nset rmargin 52\n"
               "set format y '%%.0e'\n"
               "set xlabel 'render time, median and its 95%% CI (s)'\n"
               "set ylabel 'RMSE (linear light)'\n",
            rws > 0 ? rws : 1, cols);
    for (size_t k = 0; k < n && views < nviews; k++) {
        if (done[k] || !rows[k].ok || !(rows[k].seconds > 0))
            continue;
        size_t nv = 0;
        double lowest = INFINITY;
        for (size_t q = k; q < n; q++)
            if (!done[q] && rows[q].ok && rows[q].seconds > 0 &&
                aa_rows_same_view(&rows[k], &rows[q])) {
                view[nv++] = &rows[q];
                done[q] = 1;
                if (rows[q].m.rmse >= EXACT)
                    lowest = fmin(lowest, rows[q].m.rmse);
            }
        qsort(view, nv, sizeof *view, cmp_time);
        double floor = isfinite(lowest) ? lowest / 4 : 1e-3;
        char title[256];
        snprintf(title, sizeof title, "%s %dx%d %s, %d thread%s", rows[k].pattern, rows[k].w,
                 rows[k].h, rows[k].filter, rows[k].threads, rows[k].threads == 1 ? "" : "s");
        /* block 2v: x y xlo xhi family number label-x label-y; the label
         * (the method's number) sits in one of four corners by turn, so
         * neighbours' numbers fall apart */
        fprintf(f, "# %s\n", title);
        static const double corner[4][2] = {{1.12, 1.18}, {1.12, 0.85}, {0.80, 1.18},
                                            {0.80, 0.85}};
        for (size_t q = 0; q < nv; q++) {
            const aa_row *r = view[q];
            double y = r->m.rmse >= EXACT ? r->m.rmse : floor;
            double lo = isfinite(r->timing.stats.ci_lo) ? r->timing.stats.ci_lo : r->seconds;
            double hi = isfinite(r->timing.stats.ci_hi) ? r->timing.stats.ci_hi : r->seconds;
            fprintf(f, "%.9g %.9g %.9g %.9g %d %zu %.9g %.9g\n", r->seconds, y, lo, hi,
                    family_of(&fam, r->method), q + 1, r->seconds * corner[q % 4][0],
                    y * corner[q % 4][1]);
        }
        fprintf(f, "\n\n");
        double best = INFINITY;
        for (size_t q = 0; q < nv; q++)
            if (view[q]->m.rmse < best) {
                best = view[q]->m.rmse;
                fprintf(f, "%.9g %.9g\n", view[q]->seconds, fmax(best, floor));
            }
        fprintf(f, "\n\n");
        /* the panel: its numbered key at the right, each entry with its
         * family's marker */
        fprintf(s, "unset label\nset title ");
        gp_string(s, title);
        fprintf(s, "\nset yrange [%.9g:*]\n", floor / 1.5);
        double dy = fmin(0.05, 0.98 / (double)(nv ? nv : 1));
        for (size_t q = 0; q < nv; q++) {
            const aa_row *r = view[q];
            const char *colour;
            int marker;
            char entry[768];
            family_style(family_of(&fam, r->method), &colour, &marker);
            if (r->m.rmse >= EXACT)
                snprintf(entry, sizeof entry, "%zu  %.40s%s", q + 1, r->method,
                         r->timing.noisy ? " *" : "");
            else
                snprintf(entry, sizeof entry, "%zu  %.40s (RMSE %.0e, at the floor)%s", q + 1,
                         r->method, r->m.rmse, r->timing.noisy ? " *" : "");
            fprintf(s, "set label %zu ", q + 1);
            gp_string(s, entry);
            fprintf(s, " at graph 1.04, graph %.4f left front font ',8' point pt %d ps 0.9 "
                       "lc rgb '%s' offset 1.2,0\n",
                    1.0 - dy * (double)q, marker, colour);
        }
        fprintf(s, "plot ");
        int first = 1;
        for (int fi = 0; fi < fam.n; fi++) {
            int present = 0;
            for (size_t q = 0; q < nv && !present; q++)
                present = family_of(&fam, view[q]->method) == fi;
            if (!present)
                continue;
            const char *colour;
            int marker;
            family_style(fi, &colour, &marker);
            fprintf(s, "%sdat index %d using 1:($5==%d?$2:1/0):3:4 with xerrorbars pt %d ps 1.2 "
                       "lw 1.3 lc rgb '%s'",
                    first ? "" : ", \\\n     ", 2 * views, fi, marker, colour);
            first = 0;
        }
        fprintf(s, ", \\\n     dat index %d using 7:8:6 with labels font ',8' tc rgb 'gray20', "
                   "\\\n     dat index %d using 1:2 with steps lw 1.2 dt 2 lc rgb 'gray40'\n",
                2 * views, 2 * views + 1);
        views++;
    }
    fprintf(s, "unset multiplot\n");
    free(view);
    free(done);
    /* a write error sets the stream's flag; fclose writes the rest */
    int err = ferror(f);
    int bad_script = fclose(s) != 0;
    if (fclose(f) != 0 || err || bad_script) {
        free(script);
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s: %s", dat, strerror(errno));
    }
    if (views == 0) {
        free(script);
        unlink(tmp);
        return aa_fail(AA_EINVAL, "no measured rows to plot");
    }
    st = draw(dir, "error_vs_time", script, tmp, "error_vs_time.dat");
    free(script);
    return st;
}

static int plot_convergence(const char *dir, const aa_convergence *c, const char *const *names,
                            size_t n, const char *title)
{
    char dat[4096], tmp[4096];
    int st = aa_mkdirs(dir);
    if (st)
        return st;
    if (n == 0)
        return aa_fail(AA_EINVAL, "no convergence to plot");
    snprintf(dat, sizeof dat, "%s/convergence.dat", dir);
    if ((st = aa_temp_name(dat, tmp, sizeof tmp)))
        return st;
    FILE *f = fopen(tmp, "w");
    if (!f)
        return aa_fail(AA_EIO, "cannot write %s", dat);
    double top = 0, x0 = INFINITY, x1 = 0;
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "\"%s: slope %.3f +- %.3f\"\n", names[k], c[k].slope, c[k].slope_err);
        for (size_t q = 0; q < c[k].n; q++) {
            fprintf(f, "%.9g %.9g %.9g %.9g\n", c[k].spp[q], c[k].rmse[q], c[k].rmse_sd[q],
                    exp(c[k].intercept) * pow(c[k].spp[q], c[k].slope));
            x1 = fmax(x1, c[k].spp[q]);
            if (c[k].spp[q] < x0)
                x0 = c[k].spp[q], top = c[k].rmse[q];
            else if (c[k].spp[q] == x0)
                top = fmax(top, c[k].rmse[q]);
        }
        fprintf(f, "\n\n");
    }
    int err = ferror(f);
    if (fclose(f) != 0 || err) {
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s: %s", dat, strerror(errno));
    }
    char script[16384];
    FILE *s = fmemopen(script, sizeof script, "w");
    fprintf(s, "# convergence: made by aabench; run with: gnuplot convergence.gp\n"
               "set terminal pngcairo size 1000,650 font 'DejaVu Sans,10'\n"
               "if (!exists('out')) out = 'convergence.png'\n"
               "if (!exists('dat')) dat = 'convergence.dat'\nset output out\n");
    fprintf(s, "set logscale xy\nset grid\nset key inside left bottom box opaque font ',9' "
               "spacing 1.2\n"
               "set xlabel 'samples per pixel'\nset ylabel 'RMSE over random sub-pixel shifts'\n"
               "set format y '%%.0e'\nset title ");
    gp_string(s, title);
    /* the theory's slopes for edges, drawn from above the first count's
     * highest error so they stand apart from the measured curves */
    fprintf(s, "\nx0 = %.9g; y0 = %.9g\nset xrange [x0 / 1.3:%.9g]\n"
               "random(x) = y0 * (x / x0)**(-0.5)\nstratified(x) = y0 * (x / x0)**(-0.75)\n",
            isfinite(x0) ? x0 : 1.0, top > 0 ? 1.8 * top : 1.0,
            isfinite(x0) ? fmax(x1, x0) * 1.3 : 10.0);
    fprintf(s, "plot random(x) with lines dt 2 lw 1.5 lc rgb 'gray30' "
               "title 'theory: spp^{-1/2} (independent random)', \\\n"
               "     stratified(x) with lines dt 3 lw 1.5 lc rgb 'gray30' "
               "title 'theory: spp^{-3/4} (stratified, QMC; edges)'");
    for (size_t k = 0; k < n; k++) {
        const char *colour;
        int marker;
        family_style((int)k, &colour, &marker);
        fprintf(s, ", \\\n     dat index %zu using 1:2 with points pt %d ps 1.3 lc rgb '%s' "
                   "title columnheader(1), \\\n"
                   "     dat index %zu using 1:4 with lines lw 1.5 lc rgb '%s' notitle",
                k, marker, colour, k, colour);
    }
    fprintf(s, "\n");
    if (fclose(s) != 0)
        return aa_fail(AA_EIO, "convergence script too long");
    return draw(dir, "convergence", script, tmp, "convergence.dat");
}

int aa_plot_error_vs_time(const char *dir, const aa_row *rows, size_t n)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = plot_error_vs_time(dir, rows, n);
    aa__c_numbers_end(&numbers);
    return st;
}

int aa_plot_convergence(const char *dir, const aa_convergence *c, const char *const *names,
                        size_t n, const char *title)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = plot_convergence(dir, c, names, n, title);
    aa__c_numbers_end(&numbers);
    return st;
}

static int plot_script(const char *dir, const char *name, const char *data, const char *script)
{
    char dat[4096], dat_name[1024], tmp[4096];
    int st = aa_mkdirs(dir);
    if (st)
        return st;
    snprintf(dat_name, sizeof dat_name, "%s.dat", name);
    if ((st = aa_pathf(dat, sizeof dat, "%s/%s", dir, dat_name)) ||
        (st = aa_temp_name(dat, tmp, sizeof tmp)))
        return st;
    FILE *f = fopen(tmp, "w");
    if (!f)
        return aa_fail(AA_EIO, "cannot write %s: %s", dat, strerror(errno));
    size_t len = strlen(data);
    int bad = fwrite(data, 1, len, f) != len;
    if (fclose(f) != 0 || bad) {
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s", dat);
    }
    return draw(dir, name, script, tmp, dat_name);
}

int aa_plot_script(const char *dir, const char *name, const char *data, const char *script)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, dir);
    if (st)
        return st;
    st = plot_script(dir, name, data, script);
    aa__c_numbers_end(&numbers);
    return st;
}
