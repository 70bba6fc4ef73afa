/*
 * context.c: what a results file says of the run that made it, as pyperf
 * and Google Benchmark record theirs: the commit and whether the tree was
 * dirty, the compiler and its flags, the CPU and its cores, the threads,
 * the OS and kernel, the libraries' versions, the date, the load and the
 * exact command line.
 *
 * The commit is the one the program was built from, compiled in by the
 * Makefile (build/build-info.h, written at build time, with whether the
 * tree was dirty and the libraries' versions from pkg-config: OpenImageIO's
 * is read there, so no image module is loaded to name it).  When the
 * program lives in a git checkout, the checkout's own commit and state at
 * run time are recorded beside it (git rev-parse HEAD; dirty when git status
 * --porcelain lists a tracked file changed): a checkout committed to or
 * edited after the build says so, and a run does not take the checkout's
 * commit for the program's.  GSL's version is also read at run time.
 */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "bench.h"

#include <errno.h>
#include <fcntl.h>
#include <gsl/gsl_version.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifdef AA_BUILD_INFO
#include "build-info.h" /* the build folder's, written by scripts/build-info.sh */
#endif
#ifndef AA_BUILD_COMMIT
#define AA_BUILD_COMMIT "unknown"
#endif
#ifndef AA_BUILD_DIRTY
#define AA_BUILD_DIRTY -1
#endif
#ifndef AA_BUILD_FLAGS
#define AA_BUILD_FLAGS "unknown"
#endif
#ifndef AA_VERSION_OIIO
#define AA_VERSION_OIIO ""
#endif
#ifndef AA_VERSION_FREETYPE
#define AA_VERSION_FREETYPE ""
#endif
#ifndef AA_VERSION_CAIRO
#define AA_VERSION_CAIRO ""
#endif
#ifndef AA_VERSION_STB
#define AA_VERSION_STB ""
#endif
#ifndef AA_VERSION_GSL
#define AA_VERSION_GSL GSL_VERSION
#endif

/* The first line a program prints (argv[0] looked up in PATH), standard
 * error discarded; 0 if it ran and exited 0. */
static int first_line(char *const argv[], char *buf, size_t len, int *any_output)
{
    int fd[2];
    buf[0] = '\0';
    *any_output = 0;
    fflush(NULL);
    if (pipe(fd) != 0)
        return -1;
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return -1;
    }
    if (pid == 0) {
        int null = open("/dev/null", O_RDWR);
        if (null < 0 || dup2(fd[1], 1) < 0 || dup2(null, 2) < 0 || dup2(null, 0) < 0)
            _exit(126);
        close(fd[0]);
        execvp(argv[0], argv);
        _exit(127);
    }
    close(fd[1]);
    size_t n = 0;
    char c;
    ssize_t r;
    int line_done = 0;
    for (;;) {
        r = read(fd[0], &c, 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        *any_output = 1;
        if (c == '\n')
            line_done = 1;
        if (!line_done && n + 1 < len)
            buf[n++] = c;
    }
    buf[n] = '\0';
    close(fd[0]);
    int status;
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : -1;
}

/* The commit and state of the checkout the program lives in, into
 * c->checkout and c->checkout_dirty; 0 if found. */
static int checkout_at_run_time(aa_context *c)
{
    char exe[4096], dir[4096], line[256];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return -1;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash)
        return -1;
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - exe), exe);
    int any;
    char *head[] = {"git", "-C", dir, "rev-parse", "HEAD", NULL};
    if (first_line(head, line, sizeof line, &any) || strlen(line) < 7)
        return -1;
    snprintf(c->checkout, sizeof c->checkout, "%.63s", line);
    char *status[] = {"git", "-C", dir, "status", "--porcelain", "--untracked-files=no", NULL};
    c->checkout_dirty = first_line(status, line, sizeof line, &any) ? -1 : any;
    return 0;
}

/* The value after "key" and a colon (/proc/cpuinfo) or '=' (os-release),
 * quotes removed, from the first line that starts with key. */
static void file_value(const char *path, const char *key, char sep, char *buf, size_t len)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    buf[0] = '\0';
    if (!f)
        return;
    size_t kl = strlen(key);
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, key, kl))
            continue;
        char *v = strchr(line + kl, sep);
        if (!v)
            continue;
        v++;
        while (*v == ' ' || *v == '\t' || *v == '"')
            v++;
        size_t m = strcspn(v, "\"\n");
        snprintf(buf, len, "%.*s", (int)m, v);
        break;
    }
    fclose(f);
}

const char *aa_build_commit(int *dirty)
{
    *dirty = AA_BUILD_DIRTY;
    return AA_BUILD_COMMIT;
}

int aa_context_collect(aa_context *c, int argc, const char *const *argv, int threads)
{
    memset(c, 0, sizeof *c);
    c->argc = argc;
    c->argv = argv;
    c->threads = threads;
    snprintf(c->commit, sizeof c->commit, "%s", aa_build_commit(&c->dirty));
    snprintf(c->commit_from, sizeof c->commit_from, "build");
    c->checkout_dirty = -1;
    if (checkout_at_run_time(c))
        c->checkout[0] = '\0';
#if defined(__clang__)
    snprintf(c->compiler, sizeof c->compiler, "clang %s", __clang_version__);
#elif defined(__GNUC__)
    snprintf(c->compiler, sizeof c->compiler, "gcc %s", __VERSION__);
#else
    snprintf(c->compiler, sizeof c->compiler, "unknown");
#endif
    snprintf(c->cflags, sizeof c->cflags, "%s", AA_BUILD_FLAGS);
    file_value("/proc/cpuinfo", "model name", ':', c->cpu, sizeof c->cpu);
    c->cores = (int)sysconf(_SC_NPROCESSORS_ONLN);
    cpu_set_t set;
    CPU_ZERO(&set);
    c->cores_allowed = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : c->cores;
    struct utsname u;
    if (uname(&u) == 0) {
        snprintf(c->kernel, sizeof c->kernel, "%.32s %.64s", u.sysname, u.release);
        snprintf(c->machine, sizeof c->machine, "%.63s", u.machine);
        snprintf(c->host, sizeof c->host, "%.63s", u.nodename);
    }
    file_value("/etc/os-release", "PRETTY_NAME", '=', c->os, sizeof c->os);
    FILE *g = fopen("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor", "r");
    if (g) {
        if (fgets(c->governor, sizeof c->governor, g))
            c->governor[strcspn(c->governor, "\n")] = '\0';
        fclose(g);
    }
    snprintf(c->gsl, sizeof c->gsl, "%s", gsl_version);
    snprintf(c->oiio, sizeof c->oiio, "%s", AA_VERSION_OIIO);
    snprintf(c->freetype, sizeof c->freetype, "%s", AA_VERSION_FREETYPE);
    snprintf(c->cairo, sizeof c->cairo, "%s", AA_VERSION_CAIRO);
    snprintf(c->stb, sizeof c->stb, "%s", AA_VERSION_STB);
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(c->date, sizeof c->date, "%Y-%m-%dT%H:%M:%SZ", &tm);
    c->load[0] = c->load[1] = c->load[2] = NAN;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf %lf %lf", &c->load[0], &c->load[1], &c->load[2]) != 3)
            c->load[0] = c->load[1] = c->load[2] = NAN;
        fclose(f);
    }
    return AA_OK;
}

static void json_str(FILE *f, const char *v)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)v; *c; c++) {
        if (*c == '"' || *c == '\\')
            fprintf(f, "\\%c", *c);
        else if (*c < 0x20)
            fprintf(f, "\\u%04x", *c);
        else
            fputc(*c, f);
    }
    fputc('"', f);
}

static void json_real(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.9g", v);
    else
        fputs("null", f);
}

char *aa_context_json(const aa_context *c, int indent)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return NULL;
    const int in = indent + 2;
    fprintf(f, "{\n%*s\"commit\": ", in, "");
    json_str(f, c->commit);
    fprintf(f, ",\n%*s\"dirty\": %s,\n%*s\"commit_from\": ", in, "",
            c->dirty < 0 ? "null" : c->dirty ? "true" : "false", in, "");
    json_str(f, c->commit_from);
    fprintf(f, ",\n%*s\"checkout\": ", in, "");
    if (c->checkout[0]) {
        json_str(f, c->checkout);
        fprintf(f, ",\n%*s\"checkout_dirty\": %s", in, "",
                c->checkout_dirty < 0 ? "null" : c->checkout_dirty ? "true" : "false");
    } else {
        fprintf(f, "null,\n%*s\"checkout_dirty\": null", in, "");
    }
    fprintf(f, ",\n%*s\"compiler\": ", in, "");
    json_str(f, c->compiler);
    fprintf(f, ",\n%*s\"cflags\": ", in, "");
    json_str(f, c->cflags);
    fprintf(f, ",\n%*s\"cpu\": ", in, "");
    json_str(f, c->cpu);
    fprintf(f, ",\n%*s\"cores\": %d,\n%*s\"cores_allowed\": %d,\n%*s\"threads\": %d", in, "",
            c->cores, in, "", c->cores_allowed, in, "", c->threads);
    fprintf(f, ",\n%*s\"governor\": ", in, "");
    json_str(f, c->governor);
    fprintf(f, ",\n%*s\"os\": ", in, "");
    json_str(f, c->os);
    fprintf(f, ",\n%*s\"kernel\": ", in, "");
    json_str(f, c->kernel);
    fprintf(f, ",\n%*s\"machine\": ", in, "");
    json_str(f, c->machine);
    fprintf(f, ",\n%*s\"host\": ", in, "");
    json_str(f, c->host);
    fprintf(f, ",\n%*s\"libraries\": {\"gsl\": ", in, "");
    json_str(f, c->gsl);
    fputs(", \"openimageio\": ", f);
    json_str(f, c->oiio);
    fputs(", \"freetype\": ", f);
    json_str(f, c->freetype);
    fputs(", \"cairo\": ", f);
    json_str(f, c->cairo);
    fputs(", \"stb\": ", f);
    json_str(f, c->stb);
    fprintf(f, "},\n%*s\"date\": ", in, "");
    json_str(f, c->date);
    fprintf(f, ",\n%*s\"load\": [", in, "");
    for (int k = 0; k < 3; k++) {
        json_real(f, c->load[k]);
        fputs(k < 2 ? ", " : "]", f);
    }
    fprintf(f, ",\n%*s\"command\": [", in, "");
    for (int k = 0; k < c->argc && c->argv; k++) {
        json_str(f, c->argv[k] ? c->argv[k] : "");
        if (k + 1 < c->argc)
            fputs(", ", f);
    }
    fprintf(f, "]\n%*s}", indent, "");
    if (fclose(f) != 0) {
        free(text);
        return NULL;
    }
    return text;
}
