/*
 * plot.c: plots with gnuplot (pngcairo).
 *
 * Each plot leaves three files: the data (.dat), the gnuplot script that
 * draws it (.gp, so a reader can restyle or re-run it), and the picture
 * (.png, drawn under a temporary name and renamed).
 *
 *   error_vs_time   RMSE against median render time, log-log, one panel per
 *                   view (pattern, size, filter), methods labelled, the
 *                   view's Pareto front (no other method both faster and more
 *                   accurate) drawn as a staircase; methods exact to rounding
 *                   (RMSE below 1e-9) sit on the panel's floor, a quarter of
 *                   the lowest other error, labelled with their error
 *   convergence     RMSE against samples per pixel, log-log, with each
 *                   method's fitted line and slope
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

static int same_view(const aa_row *a, const aa_row *b)
{
    return !strcmp(a->pattern, b->pattern) && !strcmp(a->filter, b->filter) && a->w == b->w &&
           a->h == b->h;
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
    double floors[64];
    char titles[64][256];
    if (!f || !view || !done) {
        if (f)
            fclose(f);
        free(view);
        free(done);
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s", dat);
    }
    /* per view, three blocks: the methods, those exact to rounding (drawn
     * on the floor, labelled with their error), and the Pareto front */
    for (size_t k = 0; k < n && views < 64; k++) {
        if (done[k] || !rows[k].ok || !(rows[k].seconds > 0))
            continue;
        size_t nv = 0;
        double lowest = INFINITY;
        for (size_t q = k; q < n; q++)
            if (!done[q] && rows[q].ok && rows[q].seconds > 0 && same_view(&rows[k], &rows[q])) {
                view[nv++] = &rows[q];
                done[q] = 1;
                if (rows[q].m.rmse >= EXACT)
                    lowest = fmin(lowest, rows[q].m.rmse);
            }
        qsort(view, nv, sizeof *view, cmp_time);
        double floor = isfinite(lowest) ? lowest / 4 : 1e-3;
        floors[views] = floor;
        snprintf(titles[views], sizeof titles[views], "%s %dx%d %s", rows[k].pattern, rows[k].w,
                 rows[k].h, rows[k].filter);
        fprintf(f, "# %s\n", titles[views]);
        for (size_t q = 0; q < nv; q++)
            if (view[q]->m.rmse >= EXACT)
                fprintf(f, "%.9g %.9g \"%s\"\n", view[q]->seconds, view[q]->m.rmse,
                        view[q]->method);
        fprintf(f, "\n\n");
        int exact = 0;
        for (size_t q = 0; q < nv; q++)
            if (view[q]->m.rmse < EXACT) {
                fprintf(f, "%.9g %.9g \"%s (%.1e)\"\n", view[q]->seconds, floor, view[q]->method,
                        view[q]->m.rmse);
                exact = 1;
            }
        if (!exact)
            fprintf(f, "nan nan \"\"\n");
        fprintf(f, "\n\n");
        double best = INFINITY;
        for (size_t q = 0; q < nv; q++)
            if (view[q]->m.rmse < best) {
                best = view[q]->m.rmse;
                fprintf(f, "%.9g %.9g\n", view[q]->seconds, fmax(best, floor));
            }
        fprintf(f, "\n\n");
        views++;
    }
    free(view);
    free(done);
    if (fclose(f) != 0) {
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s", dat);
    }
    if (views == 0) {
        unlink(tmp);
        return aa_fail(AA_EINVAL, "no measured rows to plot");
    }
    char script[65536];
    int cols = views == 1 ? 1 : (views <= 4 ? 2 : 3), rws = (views + cols - 1) / cols;
    FILE *s = fmemopen(script, sizeof script, "w");
    fprintf(s, "# error against time: made by aabench run; run with: gnuplot error_vs_time.gp\n"
               "set terminal pngcairo size %d,%d font 'DejaVu Sans,10'\n"
               "if (!exists('out')) out = 'error_vs_time.png'\n"
               "if (!exists('dat')) dat = 'error_vs_time.dat'\nset output out\n",
            640 * cols, 480 * rws + 40);
    fprintf(s, "set multiplot layout %d,%d title 'Error against render time (dashed: Pareto "
               "front; down-triangles: exact to rounding, drawn at the floor)'\n"
               "set logscale xy\nset grid\nunset key\n"
               "set xlabel 'render time, median (s)'\nset ylabel 'RMSE (linear light)'\n",
            rws, cols);
    for (int v = 0; v < views; v++) {
        fprintf(s, "set title ");
        gp_string(s, titles[v]);
        fprintf(s, "\nset yrange [%.9g:*]\n", floors[v] / 1.5);
        fprintf(s, "plot dat index %d using 1:2 with points pt 7 ps 1.1 lc 1, \\\n"
                   "     '' index %d using 1:2:3 with labels left offset 0.6,0.25 font ',7' "
                   "tc lt 1, \\\n"
                   "     '' index %d using 1:2 with points pt 11 ps 1.4 lc 2, \\\n"
                   "     '' index %d using 1:2:3 with labels left offset 0.7,0.3 font ',7' "
                   "tc lt 2, \\\n"
                   "     '' index %d using 1:2 with steps lw 1.2 dt 2 lc rgb 'gray40'\n",
                3 * v, 3 * v, 3 * v + 1, 3 * v + 1, 3 * v + 2);
    }
    fprintf(s, "unset multiplot\n");
    fclose(s);
    return draw(dir, "error_vs_time", script, tmp, "error_vs_time.dat");
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
    for (size_t k = 0; k < n; k++) {
        fprintf(f, "\"%s: slope %.3f +- %.3f\"\n", names[k], c[k].slope, c[k].slope_err);
        for (size_t q = 0; q < c[k].n; q++)
            fprintf(f, "%.9g %.9g %.9g %.9g\n", c[k].spp[q], c[k].rmse[q], c[k].rmse_sd[q],
                    exp(c[k].intercept) * pow(c[k].spp[q], c[k].slope));
        fprintf(f, "\n\n");
    }
    if (fclose(f) != 0) {
        unlink(tmp);
        return aa_fail(AA_EIO, "cannot write %s", dat);
    }
    char script[8192];
    FILE *s = fmemopen(script, sizeof script, "w");
    fprintf(s, "# convergence: made by aabench; run with: gnuplot convergence.gp\n"
               "set terminal pngcairo size 900,600 font 'DejaVu Sans,10'\n"
               "if (!exists('out')) out = 'convergence.png'\n"
               "if (!exists('dat')) dat = 'convergence.dat'\nset output out\n");
    fprintf(s, "set logscale xy\nset grid\nset key bottom left\n"
               "set xlabel 'samples per pixel'\nset ylabel 'RMSE over random sub-pixel shifts'\n"
               "set title ");
    gp_string(s, title);
    fprintf(s, "\nplot for [m=0:%zu] dat index m using 1:2 with points pt 7 lc m+1 "
               "title columnheader(1), \\\n"
               "     for [m=0:%zu] dat index m using 1:4 with lines lc m+1 notitle\n",
            n - 1, n - 1);
    fclose(s);
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
