/*
 * prune.c: old run folders removed (prune.h).
 */
#define _XOPEN_SOURCE 700
#include "prune.h"

#include "core.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int aa_runs_name(const char *name)
{
    /* YYYYMMDDTHHMMSSZ */
    for (int i = 0; i < 15; i++) {
        if (i == 8 ? name[i] != 'T' : !isdigit((unsigned char)name[i]))
            return 0;
    }
    if (name[15] != 'Z')
        return 0;
    if (name[16] == '\0')
        return 1;
    if (name[16] != '-' || !isdigit((unsigned char)name[17]) || name[17] == '0')
        return 0;
    if (name[18] == '\0')
        return name[17] >= '2';
    return isdigit((unsigned char)name[18]) && name[19] == '\0';
}

/* the second of the name, then K (1 when absent) */
static int run_cmp(const void *a, const void *b)
{
    const char *x = *(const char *const *)a, *y = *(const char *const *)b;
    int c = strncmp(x, y, 16);
    if (c)
        return c;
    long kx = x[16] ? strtol(x + 17, NULL, 10) : 1, ky = y[16] ? strtol(y + 17, NULL, 10) : 1;
    return (kx > ky) - (kx < ky);
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)ftw;
    int r = flag == FTW_DP ? rmdir(path) : unlink(path);
    if (r != 0) {
        aa_fail(AA_EIO, "cannot remove %s: %s", path, strerror(errno));
        return 1;
    }
    return 0;
}

int aa_runs_prune(const char *results, long keep, int dry_run,
                  void (*each)(void *ctx, const char *dir), void *ctx, size_t *removed)
{
    if (removed)
        *removed = 0;
    if (keep < 0)
        return aa_fail(AA_EINVAL, "--keep %ld: the number of runs kept is 0 or more", keep);
    char runs[PATH_MAX], path[PATH_MAX + 300], latest[PATH_MAX + 16], target[PATH_MAX];
    if (snprintf(runs, sizeof runs, "%s/runs", results) >= (int)sizeof runs)
        return aa_fail(AA_EINVAL, "%s: name too long", results);
    /* the name of the folder latest points to (runs/NAME), if any */
    const char *kept_name = NULL;
    snprintf(latest, sizeof latest, "%s/latest", results);
    ssize_t n = readlink(latest, target, sizeof target - 1);
    if (n > 0) {
        target[n] = '\0';
        char *slash = strrchr(target, '/');
        kept_name = slash ? slash + 1 : target;
    }
    DIR *d = opendir(runs);
    if (!d) {
        if (errno == ENOENT)
            return AA_OK;
        return aa_fail(AA_EIO, "cannot read %s: %s", runs, strerror(errno));
    }
    char **names = NULL;
    size_t count = 0, cap = 0;
    int st = AA_OK;
    struct dirent *e;
    errno = 0;
    while ((e = readdir(d)) != NULL) {
        struct stat sb;
        if (!aa_runs_name(e->d_name))
            continue;
        snprintf(path, sizeof path, "%s/%s/run.json", runs, e->d_name);
        if (stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
            continue;
        snprintf(path, sizeof path, "%s/%s", runs, e->d_name);
        if (lstat(path, &sb) != 0 || !S_ISDIR(sb.st_mode))
            continue; /* a link to a folder is not one to remove */
        if (count == cap) {
            cap = cap ? 2 * cap : 16;
            char **grown = realloc(names, cap * sizeof *names);
            if (!grown) {
                st = aa_fail(AA_ENOMEM, "out of memory listing %s", runs);
                break;
            }
            names = grown;
        }
        if (!(names[count] = strdup(e->d_name))) {
            st = aa_fail(AA_ENOMEM, "out of memory listing %s", runs);
            break;
        }
        count++;
    }
    closedir(d);
    if (!st && count > 0)
        qsort(names, count, sizeof *names, run_cmp);
    size_t old = count > (size_t)keep ? count - (size_t)keep : 0;
    for (size_t i = 0; !st && i < old; i++) {
        if (kept_name && !strcmp(names[i], kept_name))
            continue;
        snprintf(path, sizeof path, "%s/%.19s", runs, names[i]);
        if (!dry_run && nftw(path, remove_one, 16, FTW_DEPTH | FTW_PHYS) != 0) {
            st = AA_EIO;
            if (!strstr(aa_last_error(), path))
                st = aa_fail(AA_EIO, "cannot remove %s: %s", path, strerror(errno));
            break;
        }
        if (each)
            each(ctx, path);
        if (removed)
            (*removed)++;
    }
    for (size_t i = 0; i < count; i++)
        free(names[i]);
    free(names);
    return st;
}
