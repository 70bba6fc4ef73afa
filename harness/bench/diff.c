/*
 * diff.c: two runs compared case by case.
 *
 * Errors are exact, so a change in them is judged by one rule for both
 * gates, `check` and `diff` (aa_case_verdict): worse when the RMSE or the
 * largest error exceeds the old one by more than the relative tolerance
 * plus 1e-12; a case that ran and is now refused, fails, or is missing, or
 * one refused before that now runs, fails too.  Times are samples, so a
 * change in them is judged by the Mann-Whitney U test on the two runs'
 * repetition times (aa_mann_whitney, normal approximation with the tie
 * correction), which assumes nothing of their distribution; the effect
 * reported is the ratio of the medians.
 */
#include "bench.h"
#include "methods.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int aa_case_same(const aa_row *a, const aa_row *b)
{
    return !strcmp(a->pattern, b->pattern) && !strcmp(a->filter, b->filter) &&
           !strcmp(a->method, b->method) && a->w == b->w && a->h == b->h && a->t == b->t &&
           a->vx == b->vx && a->vy == b->vy && a->seed == b->seed;
}

static int worse(double now, double old, double tol)
{
    return now > old * (1.0 + tol) + AA_ERROR_ABS_TOLERANCE;
}

/* The same for a figure a row may lack (a baseline older than FLIP and
 * the edge RMSE, a view without edges): judged only when both have it. */
static int worse_opt(double now, double old, double tol)
{
    return isfinite(now) && isfinite(old) && worse(now, old, tol);
}

const char *aa_case_verdict(const aa_row *old, const aa_row *now, double tol, char *detail,
                            size_t len, int *confirmed)
{
    char scratch[8];
    if (!detail)
        detail = scratch, len = sizeof scratch;
    *confirmed = 0;
    detail[0] = '\0';
    if (!now) {
        snprintf(detail, len, "%s", old->ok ? "it ran" : "the baseline records it as refused");
        return "missing: the case is no longer run";
    }
    if (*old->inputs && *now->inputs && strcmp(old->inputs, now->inputs)) {
        snprintf(detail, len, "then %s, now %s", old->inputs, now->inputs);
        return "made from other input files";
    }
    if (now->failed) {
        snprintf(detail, len, "%s", now->note);
        return "now fails";
    }
    if (!old->ok && now->ok) {
        snprintf(detail, len,
                 "the baseline records it as not run (%s); it now runs (rmse %.9g): remake the "
                 "baseline to gate it",
                 old->note, now->m.rmse);
        return "now runs a case its baseline records as refused";
    }
    if (!old->ok) {
        *confirmed = 1; /* refused then, refused now */
        return NULL;
    }
    if (!now->ok) {
        snprintf(detail, len, "%s", now->note);
        return "now refused";
    }
    if (worse(now->m.rmse, old->m.rmse, tol) || worse(now->m.max_err, old->m.max_err, tol)) {
        snprintf(detail, len, "rmse %.9g (baseline %.9g, %+.3f%%), max_err %.9g (baseline %.9g)",
                 now->m.rmse, old->m.rmse, 100 * (now->m.rmse / old->m.rmse - 1),
                 now->m.max_err, old->m.max_err);
        return "error above its baseline";
    }
    if (worse_opt(now->m.edge_rmse, old->m.edge_rmse, tol) ||
        worse_opt(now->m.flip, old->m.flip, tol)) {
        snprintf(detail, len, "edge_rmse %.9g (baseline %.9g), flip %.9g (baseline %.9g)",
                 now->m.edge_rmse, old->m.edge_rmse, now->m.flip, old->m.flip);
        return "error above its baseline";
    }
    return NULL;
}

int aa_case_compare(const aa_row *old, const aa_row *now, double tol, aa_case_change *c)
{
    int confirmed;
    memset(c, 0, sizeof *c);
    c->old = old;
    c->now = now;
    c->rmse_change = c->time_ratio = c->u = c->z = c->p = NAN;
    c->regression = aa_case_verdict(old, now, tol, NULL, 0, &confirmed);
    if (old->ok && !now->ok) {
        c->refused = 1;
        return AA_OK;
    }
    if (!old->ok || !now->ok)
        return AA_OK;
    c->error_worse = worse(now->m.rmse, old->m.rmse, tol) ||
                     worse(now->m.max_err, old->m.max_err, tol) ||
                     worse_opt(now->m.edge_rmse, old->m.edge_rmse, tol) ||
                     worse_opt(now->m.flip, old->m.flip, tol);
    c->rmse_change = old->m.rmse > 0 ? now->m.rmse / old->m.rmse - 1 : 0.0;
    if (old->seconds > 0 && now->seconds > 0)
        c->time_ratio = now->seconds / old->seconds;
    c->noisy = old->timing.noisy || now->timing.noisy;
    if (old->timing.n >= 2 && now->timing.n >= 2) {
        int st = aa_mann_whitney(now->timing.wall, (size_t)now->timing.n, old->timing.wall,
                                 (size_t)old->timing.n, &c->u, &c->z, &c->p);
        if (st)
            return st;
        c->tested = 1;
        c->significant = c->p < AA_TIME_ALPHA;
    }
    return AA_OK;
}

int aa_results_load(const char *path, aa_row **rows, size_t *n)
{
    struct stat sb;
    char csv[4096];
    *rows = NULL;
    *n = 0;
    if (stat(path, &sb) != 0)
        return aa_fail(AA_EIO, "%s: %s", path, strerror(errno));
    if (S_ISDIR(sb.st_mode)) {
        int st = aa_pathf(csv, sizeof csv, "%s/results.csv", path);
        if (st)
            return st;
    } else {
        size_t len = strlen(path);
        if (len >= 5 && !strcmp(path + len - 5, ".json"))
            return aa_rows_read_json(path, rows, n);
        return aa_rows_read_csv(path, rows, n);
    }
    return aa_rows_read_csv(csv, rows, n);
}

int aa_pattern_inputs(const aa_spec *pattern, char *buf, size_t len)
{
    char key[512];
    int st = aa_pattern_key(pattern, key, sizeof key);
    if (len)
        buf[0] = '\0';
    if (st)
        return st;
    /* its lines joined by "; " */
    size_t n = 0, k = 0, end = strlen(key);
    while (end && key[end - 1] == '\n')
        key[--end] = '\0';
    for (; k < end && n + 3 < len; k++) {
        if (key[k] == '\n') {
            buf[n++] = ';', buf[n++] = ' ';
        } else {
            buf[n++] = key[k];
        }
    }
    if (k < end)
        return aa_fail(AA_EFAIL, "the inputs of a pattern: more than %zu characters", len - 1);
    buf[n] = '\0';
    return AA_OK;
}

/* The method's part of a case's inputs: a plug-in's library, or the
 * adapter an external method runs, by checksum ("" for neither); *file:
 * that file (NULL for neither). */
static int method_inputs(const aa_spec *method, char *buf, size_t len, const char **file,
                         char adapter[PATH_MAX])
{
    char sum[64];
    const char *kind = "plugin";
    buf[0] = '\0';
    *file = aa_method_file((const aa_method_type *)method->info);
    if (!*file && method->info == &aa_method_external.info) {
        /* none found: no file (the method refuses the case itself) */
        if (aa_external_adapter(method, adapter))
            return AA_OK;
        *file = adapter, kind = "adapter";
    }
    if (!*file)
        return AA_OK;
    int st = aa_file_checksum(*file, sum);
    if (st)
        return aa_fail_context(st, "the %s of %s", kind, method->info->name);
    snprintf(buf, len, "%s %s", kind, sum);
    return AA_OK;
}

int aa_case_inputs(const aa_spec *pattern, const aa_spec *method, char *buf, size_t len)
{
    char part[128], adapter[PATH_MAX];
    const char *file;
    int st = pattern ? aa_pattern_inputs(pattern, buf, len) : AA_OK;
    if (!pattern && len)
        buf[0] = '\0';
    if (st || !method || (st = method_inputs(method, part, sizeof part, &file, adapter)) || !*part)
        return st;
    size_t n = strlen(buf);
    if ((size_t)snprintf(buf + n, len - n, "%s%s", n ? "; " : "", part) >= len - n)
        return aa_fail(AA_EFAIL, "the inputs of a case: more than %zu characters", len - 1);
    return AA_OK;
}

int aa_inputs_check(const char *what, const aa_row *r)
{
    aa_spec pattern, method;
    char now[sizeof r->inputs], part[sizeof r->inputs], mpart[128], adapter[PATH_MAX];
    const char *file = NULL;
    if (!*r->inputs)
        return AA_OK;
    int st = aa_pattern_parse(r->pattern, &pattern);
    if (!st)
        st = aa_spec_parse(r->method, aa_method_table(), "method", &method);
    if (!st)
        st = aa_case_inputs(&pattern, &method, now, sizeof now);
    if (!st)
        st = aa_pattern_inputs(&pattern, part, sizeof part);
    if (!st)
        st = method_inputs(&method, mpart, sizeof mpart, &file, adapter);
    if (st)
        return aa_fail_context(st, "%s: the input files of %s on %s", aa_echo(what),
                               aa_echo(r->method), aa_echo(r->pattern));
    if (!strcmp(now, r->inputs))
        return AA_OK;
    /* which file: the pattern's, else the method's */
    size_t pl = strlen(part);
    int pattern_same = !strncmp(r->inputs, part, pl) &&
                       (r->inputs[pl] == '\0' || (pl ? r->inputs[pl] == ';' : 1));
    char which[1200];
    if (pattern_same && !file)
        snprintf(which, sizeof which, "the file %s ran (no longer found)", r->method);
    else if (!pattern_same || !file)
        snprintf(which, sizeof which, "the file of %s", r->pattern);
    else
        snprintf(which, sizeof which, "the %s %s of %s", mpart[0] == 'p' ? "plug-in" : "adapter",
                 file, r->method);
    return aa_fail(AA_EINVAL,
                   "%s: %s has changed since its rows were measured (then %s, now %s): its "
                   "results are of another scene or method",
                   aa_echo(what), aa_echo(which), r->inputs, *now ? now : "none");
}
