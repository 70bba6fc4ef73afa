/*
 * paths.c: where the program finds its data and keeps its reference cache
 * (core.h, "Where the data is").
 *
 * No folder of the build is compiled in: a program built in a source tree
 * finds the tree from its own file at run time, so the tree may move, and
 * an installed one finds its data under its prefix, beside its bin/ folder
 * (relocatable) or at the prefix it was built for (AA_DATA_DIR, which the
 * Makefile sets from PREFIX).
 *
 * The source tree is the folder holding harness/aabench.h and
 * patterns/svg/shapes.svg that is the folder of the running program
 * (/proc/self/exe) or one of the three above it (build/aabench,
 * build/tests/test_x, build/san/tests/test_x), else the same from the file
 * of the library's code (dladdr: a shared library of it loaded by another
 * program).  Found once, then kept.
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* dladdr */
#endif

#include "core.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef AA_DATA_DIR
#define AA_DATA_DIR "/usr/local/share/aabench"
#endif

/* levels above the file's folder where the tree's root may be */
#define TREE_UP 3

static char tree[PATH_MAX];   /* "" when not run from a source tree */
static char svg_dir[PATH_MAX];
static pthread_once_t found = PTHREAD_ONCE_INIT;

static int is_file(const char *dir, const char *name)
{
    char path[PATH_MAX];
    struct stat st;
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    return n > 0 && (size_t)n < sizeof path && stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The tree's root among the folders of `file` (resolved) and above it,
 * into tree; 1 if found. */
static int tree_above(const char *file)
{
    char dir[PATH_MAX];
    if (!file || !realpath(file, dir))
        return 0;
    for (int up = 0; up <= TREE_UP; up++) {
        char *slash = strrchr(dir, '/');
        if (!slash)
            return 0;
        if (slash == dir)
            slash[1] = '\0'; /* the root folder */
        else
            *slash = '\0';
        if (is_file(dir, "harness/aabench.h") && is_file(dir, "patterns/svg/shapes.svg")) {
            snprintf(tree, sizeof tree, "%s", dir);
            return 1;
        }
        if (slash == dir)
            return 0;
    }
    return 0;
}

static void find(void)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    Dl_info info;
    if (n > 0)
        exe[n] = '\0';
    if (!(n > 0 && tree_above(exe)) && dladdr((void *)tree_above, &info) && info.dli_fname &&
        info.dli_fname[0] == '/')
        tree_above(info.dli_fname);
    const char *env = getenv("AABENCH_SVG_DIR");
    if (env && *env) {
        snprintf(svg_dir, sizeof svg_dir, "%s", env);
        return;
    }
    if (*tree && aa_pathf(svg_dir, sizeof svg_dir, "%s/patterns/svg", tree) == AA_OK)
        return;
    /* PREFIX/bin/aabench: PREFIX/share/aabench/svg */
    if (n > 0) {
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            char cand[PATH_MAX], real[PATH_MAX];
            if (aa_pathf(cand, sizeof cand, "%s/../share/aabench/svg", exe) == AA_OK &&
                realpath(cand, real) && is_dir(real)) {
                snprintf(svg_dir, sizeof svg_dir, "%s", real);
                return;
            }
        }
    }
    snprintf(svg_dir, sizeof svg_dir, "%s/svg", AA_DATA_DIR);
}

const char *aa_source_tree(void)
{
    pthread_once(&found, find);
    return *tree ? tree : NULL;
}

const char *aa_svg_dir(void)
{
    pthread_once(&found, find);
    return svg_dir;
}

const char *aa_cache_dir_default(void)
{
    static _Thread_local char buf[PATH_MAX + 32];
    const char *env = getenv("AABENCH_CACHE");
    if (env && *env)
        return env;
    const char *root = aa_source_tree();
    char cwd[PATH_MAX];
    if (root && getcwd(cwd, sizeof cwd)) {
        size_t n = strlen(root);
        if (!strcmp(cwd, root))
            return "results/cache";
        if (!strncmp(cwd, root, n) && (cwd[n] == '/' || !strcmp(root, "/"))) {
            snprintf(buf, sizeof buf, "%s/results/cache", root);
            return buf;
        }
    }
    /* the XDG base directories: an XDG_CACHE_HOME that is not absolute is
     * to be ignored */
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (xdg && xdg[0] == '/' && strlen(xdg) < PATH_MAX) {
        snprintf(buf, sizeof buf, "%s/aabench", xdg);
        return buf;
    }
    if (home && home[0] == '/' && strlen(home) < PATH_MAX) {
        snprintf(buf, sizeof buf, "%s/.cache/aabench", home);
        return buf;
    }
    return "results/cache";
}
