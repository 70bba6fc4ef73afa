/*
 * external.c: an SVG renderer outside aabench as a method
 * (`external:renderer=NAME`).
 *
 * The placed scene is written as SVG (harness/core/svg.c, the document
 * `aabench export` writes) and handed to an *adapter*: an executable
 * called NAME that runs one renderer,
 *
 *     NAME SVG W H OUT.png     draw the SVG at W x H pixels into an 8-bit PNG
 *     NAME --check             exit 0 if the renderer is there; otherwise say
 *                              what to install on stderr and exit 2
 *
 * exiting 0 on success, 2 when the renderer is missing (a refusal) and
 * anything else on failure, with its message last on stderr.  Adapters are
 * looked for in each folder of $AABENCH_RENDERERS (colon-separated), then in
 * the scripts/renderers/ of the source tree the program runs from
 * (aa_source_tree) and in the installed copy (AA_RENDERERS_INSTALLED, the
 * install prefix's); the first executable file of the
 * name is the one run.  scripts/renderers/README.md describes the shipped
 * adapters (rsvg, chromium, resvg) and how to add one.
 *
 * The image is read back with aa_image_read (a PNG through OpenImageIO) and
 * turned from 8-bit codes q into values by `decode`: `linear` takes q/255
 * as the value, `srgb` decodes q as sRGB.  SVG renderers composite in the
 * display-encoded (sRGB) space: where a white shape covers 50 % of a pixel
 * over black they write the code 128 (0.5 encoded, 0.214 in linear light
 * if decoded).  Measured against exact box coverage, such a renderer's
 * honest coverage is its encoded value: it needs decode=linear (the
 * default), which tests/test_external.c checks for each shipped adapter on
 * edges of known coverage (25 % and 50 % pixels read 0.25 and 0.5 within
 * 1/255).  A renderer that composited in linear light would need
 * decode=srgb.
 *
 * Scenes.  A scene of one layer (or none) is drawn as a mask (every layer
 * white over black, AA_SVG_MASK): the decoded value a of each pixel (the
 * mean of R, G and B) is the layer's coverage, and the pixel is
 * (1 - a) background + a colour, as for the peers, so a coverage of
 * exactly 0 or 1 gives the colours exactly, whatever they are.  A scene of
 * several layers is drawn in its own colours, each channel of each colour
 * (and of the background) 0 or 1, so that an 8-bit value means the same
 * under any encoding: the image's channels are the decoded values.  Other
 * colours on several layers are refused.  Shapes of two layers that share
 * an edge leak the background there, since a renderer composites each path
 * over what is below with its own coverage (the conflation artefact): that
 * is part of what is measured.
 *
 * Timing.  The SVG is written in init (untimed, as the peers build their
 * paths there), and init reads an image once so that the image reader is
 * loaded; each render is the whole adapter process, its start-up
 * included, plus reading the PNG back.  The method is flagged
 * AA_METHOD_EXTERNAL, and a run's row says so in its note.  The renderer's
 * own threads are its own: the image does not depend on job->threads.
 *
 * Processes.  Each adapter runs in a process group of its own, and is
 * waited for until the time limit (aa_external_time_limit: a run's
 * --case-timeout, render's; 600 s without one); then what it wrote is read
 * without waiting for a process it left behind holding its output, and its
 * group is killed, so nothing it started outlives it.  An adapter past the
 * limit is sent SIGTERM with its group, SIGKILL half a second later, and
 * the render fails with "timed out after S s"; SIGINT, SIGTERM or SIGHUP while it runs kill its group and
 * remove the temporary folder before the program's own handling.
 *
 * Limits: the box filter only; 8-bit values; whatever the renderer does
 * with coordinates (floats in Skia and resvg, 24.8 fixed point in Cairo
 * under librsvg); a renderer missing is a refusal (exit status 2) naming
 * what to install.
 *
 * This method is not in the built-in table (methods.c, aa_method_types):
 * the generic tests render every method there, and this one needs an
 * optional program.  It is in aa_method_types_optional, which the command
 * adds to the table at start (aa_method_add_optional).
 */
#include "methods.h"
#include "peer.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <dirent.h>

extern char **environ;

/* The adapters' installed copy (given by the Makefile from PREFIX). */
#ifndef AA_RENDERERS_INSTALLED
#define AA_RENDERERS_INSTALLED "/usr/local/lib/aabench/renderers"
#endif

enum { RENDERER, DECODE };
enum { DECODE_LINEAR, DECODE_SRGB };

static const aa_param external_params[] = {
    {"renderer", AA_PARAM_WORD, 0, 0, 0, 0, "rsvg",
     "the adapter to run: rsvg, chromium, resvg, or one's own (scripts/renderers/, "
     "$AABENCH_RENDERERS)"},
    {"decode", AA_PARAM_CHOICE, DECODE_LINEAR, 0, 0, 0, "linear|srgb",
     "what the 8-bit codes mean: linear (code/255; renderers that composite in sRGB "
     "space) or srgb (sRGB-decoded)"},
    {0}};

#define TAIL 400 /* characters of a program's output kept for messages */

typedef struct external_state {
    char adapter[PATH_MAX];
    char dir[PATH_MAX]; /* our temporary folder, "" if none */
    char svg[PATH_MAX], png[PATH_MAX];
    int mask;           /* 1: one layer (or none) drawn as its coverage */
    aa_rgb bg, fg;
    double srgb[256];   /* code -> sRGB-decoded value */
} external_state;

/* ---- finding an adapter ---- */

static int executable_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0;
}

/* The source tree's scripts/renderers into dir; 0 when the program does
 * not run from a source tree (or the path does not fit). */
static int tree_dir(char *dir, size_t len)
{
    const char *tree = aa_source_tree();
    return tree && aa_pathf(dir, len, "%s/scripts/renderers", tree) == AA_OK;
}

/* Call fn(dir, ctx) for each folder adapters are looked for in, in order;
 * stops when fn returns nonzero and returns that. */
static int each_dir(int (*fn)(const char *dir, void *ctx), void *ctx)
{
    const char *env = getenv("AABENCH_RENDERERS");
    char dir[PATH_MAX];
    int r;
    if (env) {
        for (const char *p = env; *p;) {
            size_t n = strcspn(p, ":");
            if (n > 0 && n < sizeof dir) {
                memcpy(dir, p, n);
                dir[n] = '\0';
                if ((r = fn(dir, ctx)))
                    return r;
            }
            p += n + (p[n] == ':');
        }
    }
    if (tree_dir(dir, sizeof dir) && (r = fn(dir, ctx)))
        return r;
    return fn(AA_RENDERERS_INSTALLED, ctx);
}

typedef struct find_ctx {
    const char *name;
    char *path;
} find_ctx;

static int find_in(const char *dir, void *ctx)
{
    find_ctx *f = ctx;
    char path[PATH_MAX];
    if (aa_pathf(path, sizeof path, "%s/%s", dir, f->name))
        return 0;
    if (!executable_file(path))
        return 0;
    memcpy(f->path, path, strlen(path) + 1);
    return 1;
}

typedef struct list_ctx {
    char *buf;
    size_t len, n;
} list_ctx;

/* 1 if `name` is one of the comma-separated names in `list`. */
static int listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ',' || p[n] == '\0'))
            return 1;
    return 0;
}

/* Append the adapters of `dir` (executable files, names that are words). */
static int list_in(const char *dir, void *ctx)
{
    list_ctx *l = ctx;
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        char path[PATH_MAX];
        if (e->d_name[0] == '.' || aa_pathf(path, sizeof path, "%s/%s", dir, e->d_name) ||
            !executable_file(path) || listed(l->buf, e->d_name))
            continue;
        int m = snprintf(l->buf + l->n, l->len - l->n, "%s%s", l->n ? ", " : "", e->d_name);
        if (m > 0 && (size_t)m < l->len - l->n)
            l->n += (size_t)m;
    }
    closedir(d);
    return 0;
}

/* Where adapter `name` is, into path (PATH_MAX); AA_EINVAL if nowhere. */
static int adapter_find(const char *name, char *path)
{
    find_ctx f = {name, path};
    if (!*name)
        return aa_fail(AA_EINVAL, "external needs renderer=NAME (an adapter: rsvg, chromium, "
                                  "resvg, or one's own in scripts/renderers/)");
    if (each_dir(find_in, &f))
        return AA_OK;
    char known[512] = "";
    list_ctx l = {known, sizeof known, 0};
    each_dir(list_in, &l);
    const char *env = getenv("AABENCH_RENDERERS");
    char tree[PATH_MAX];
    int in_tree = tree_dir(tree, sizeof tree);
    return aa_fail(AA_EINVAL,
                   "no renderer adapter \"%s\" (looked in %s%s%s%s%s; adapters "
                   "found: %s); an adapter is an executable there taking SVG W H OUT.png",
                   name, env ? env : "", env ? ", " : "", in_tree ? tree : "",
                   in_tree ? " and " : "", AA_RENDERERS_INSTALLED, *known ? known : "none");
}

/* ---- running a program ---- */

/* How long an adapter may run.  A caller sets a limit for what follows
 * (aa_external_time_limit: a run for each case, `render` for its renders);
 * without one, each program gets its own DEFAULT_LIMIT seconds. */
#define DEFAULT_LIMIT 600.0
#define TERM_GRACE 0.5 /* s between SIGTERM and SIGKILL at the limit */
static double limit_seconds, limit_at; /* limit_at 0: none set */

void aa_external_time_limit(double seconds)
{
    limit_seconds = seconds > 0 ? seconds : 0;
    limit_at = seconds > 0 ? aa_now() + seconds : 0;
}

/* The adapter under way, for the signal handlers: its process group (0 if
 * none), and the files and folder to remove if the process is ended. */
static volatile sig_atomic_t running_group, interrupted_by;
static const char *volatile running_files[3];
static struct sigaction old_actions[3];
static const int caught[3] = {SIGINT, SIGTERM, SIGHUP};

/* A signal while an adapter runs: its group killed and our files removed
 * (both async-signal-safe), then whatever the program would have done. */
static void on_signal(int sig)
{
    int e = errno;
    if (running_group > 0)
        kill(-(pid_t)running_group, SIGKILL);
    interrupted_by = sig;
    for (int k = 0; k < 3; k++)
        if (caught[k] == sig) {
            if (running_files[0]) {
                unlink(running_files[0]);
                unlink(running_files[1]);
                rmdir(running_files[2]);
            }
            const struct sigaction *old = &old_actions[k];
            if (old->sa_flags & SA_SIGINFO) {
                old->sa_sigaction(sig, NULL, NULL);
            } else if (old->sa_handler == SIG_DFL) {
                sigaction(sig, old, NULL);
                raise(sig); /* delivered when this handler returns */
            } else if (old->sa_handler != SIG_IGN) {
                old->sa_handler(sig);
            }
        }
    errno = e;
}

static void catch_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int k = 0; k < 3; k++)
        sigaddset(&sa.sa_mask, caught[k]);
    interrupted_by = 0;
    for (int k = 0; k < 3; k++)
        sigaction(caught[k], &sa, &old_actions[k]);
}

static void release_signals(void)
{
    for (int k = 0; k < 3; k++) {
        struct sigaction now;
        /* a handler that put the old action back already (SIG_DFL) */
        if (sigaction(caught[k], NULL, &now) == 0 && now.sa_handler == on_signal)
            sigaction(caught[k], &old_actions[k], NULL);
    }
    running_group = 0;
}

/* Append what fd holds now (without waiting) to keep, of which the last
 * TAIL characters are kept; 1 at the end of the file. */
static int drain(int fd, char *keep, size_t *kept)
{
    char buf[4096];
    for (;;) {
        ssize_t n = read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return errno != EAGAIN && errno != EWOULDBLOCK;
        if (n == 0)
            return 1;
        for (ssize_t k = 0; k < n; k++) {
            if (*kept == 2 * TAIL) { /* keep the last TAIL */
                memmove(keep, keep + TAIL, TAIL);
                *kept = TAIL;
            }
            keep[(*kept)++] = buf[k];
        }
    }
}

/* Run argv (argv[0] a path) in a process group of its own, with standard
 * input from /dev/null and its standard output and error into a pipe, of
 * which the last TAIL characters' last non-empty line is kept in `tail`.
 * It is waited for until the time limit; then what it wrote is read
 * (without waiting for a process it left behind holding the pipe), and its
 * group is killed, so that nothing it started outlives it.  `files`: the
 * two files and the folder to remove if a signal ends the program (NULL:
 * none).  *status: the exit status, or 128 plus the signal that ended
 * it. */
static int run_program(char *const argv[], const char *const files[3], int *status,
                       char tail[TAIL + 1])
{
    int fd[2];
    tail[0] = '\0';
    if (pipe(fd))
        return aa_fail(AA_EIO, "cannot make a pipe: %s", strerror(errno));
    fcntl(fd[0], F_SETFD, FD_CLOEXEC);
    fcntl(fd[1], F_SETFD, FD_CLOEXEC);
    fcntl(fd[0], F_SETFL, fcntl(fd[0], F_GETFL) | O_NONBLOCK);
    const double seconds = limit_at > 0 ? limit_seconds : DEFAULT_LIMIT;
    const double deadline = limit_at > 0 ? limit_at : aa_now() + DEFAULT_LIMIT;
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t attr;
    pid_t pid;
    int err = posix_spawn_file_actions_init(&fa);
    if (!err && (err = posix_spawnattr_init(&attr)))
        posix_spawn_file_actions_destroy(&fa);
    if (!err)
        err = posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    if (!err)
        err = posix_spawnattr_setpgroup(&attr, 0);
    if (!err)
        err = posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    if (!err)
        err = posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
    if (!err)
        err = posix_spawn_file_actions_adddup2(&fa, fd[1], 2);
    if (!err) {
        for (int k = 0; k < 3; k++)
            running_files[k] = files ? files[k] : NULL;
        catch_signals();
        err = posix_spawn(&pid, argv[0], &fa, &attr, argv, environ);
        if (!err)
            running_group = pid;
        else
            release_signals();
    }
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&attr);
    close(fd[1]);
    if (err) {
        close(fd[0]);
        return aa_fail(AA_EIO, "cannot run %s: %s", argv[0], strerror(err));
    }
    /* its end, seen without reaping it (so that its group's number is not
     * reused before the group is killed) */
    int pidfd = -1;
#ifdef SYS_pidfd_open
    pidfd = (int)syscall(SYS_pidfd_open, pid, 0);
#endif
    char keep[2 * TAIL + 1];
    size_t kept = 0;
    int eof = 0, timed_out = 0;
    for (;;) {
        siginfo_t si;
        si.si_pid = 0;
        if (waitid(P_PID, (id_t)pid, &si, WEXITED | WNOHANG | WNOWAIT) == 0 && si.si_pid == pid)
            break;
        if (interrupted_by)
            break;
        double left = deadline - aa_now();
        if (left <= 0) {
            timed_out = 1;
            break;
        }
        struct pollfd p[2] = {{eof ? -1 : fd[0], POLLIN, 0}, {pidfd, POLLIN, 0}};
        /* without a pidfd, its end is looked for every millisecond */
        int ms = pidfd < 0 ? 1 : left > 3600.0 ? 3600 * 1000 : (int)ceil(left * 1000);
        if (poll(p, 2, ms) > 0 && !eof && (p[0].revents & (POLLIN | POLLHUP | POLLERR)))
            eof = drain(fd[0], keep, &kept);
    }
    if (timed_out) {
        /* asked to end first (an adapter's own clean-up runs), for at most
         * TERM_GRACE s */
        kill(-pid, SIGTERM);
        const double end = aa_now() + TERM_GRACE;
        for (double left; (left = end - aa_now()) > 0;) {
            siginfo_t si;
            si.si_pid = 0;
            if (waitid(P_PID, (id_t)pid, &si, WEXITED | WNOHANG | WNOWAIT) == 0 &&
                si.si_pid == pid)
                break;
            struct pollfd p = {pidfd, POLLIN, 0};
            poll(&p, 1, pidfd < 0 ? 1 : (int)ceil(left * 1000));
        }
    }
    if (!eof)
        drain(fd[0], keep, &kept);
    kill(-pid, SIGKILL);
    int ws = 0;
    while (waitpid(pid, &ws, 0) < 0 && errno == EINTR)
        ;
    int sig = interrupted_by;
    release_signals();
    for (int k = 0; k < 3; k++)
        running_files[k] = NULL;
    close(fd[0]);
    if (pidfd >= 0)
        close(pidfd);
    if (timed_out)
        return aa_fail(AA_EIO, "%s timed out after %g s (killed, with what it started)", argv[0],
                       seconds);
    if (sig)
        return aa_fail(AA_EIO, "%s interrupted (signal %d): killed, with what it started",
                       argv[0], sig);
    *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : WIFSIGNALED(ws) ? 128 + WTERMSIG(ws) : 255;
    /* the last non-empty line */
    keep[kept] = '\0';
    while (kept && (keep[kept - 1] == '\n' || keep[kept - 1] == '\r' || keep[kept - 1] == ' '))
        keep[--kept] = '\0';
    const char *line = strrchr(keep, '\n');
    line = line ? line + 1 : keep;
    size_t n = strlen(line);
    if (n > TAIL)
        line += n - TAIL, n = TAIL;
    memcpy(tail, line, n);
    tail[n] = '\0';
    return AA_OK;
}

/* `adapter --check`: AA_OK if the renderer is there. */
static int adapter_check(const char *name, const char *path)
{
    char tail[TAIL + 1], arg[] = "--check", prog[PATH_MAX];
    snprintf(prog, sizeof prog, "%s", path);
    char *argv[] = {prog, arg, NULL};
    int status, st = run_program(argv, NULL, &status, tail);
    if (st)
        return st;
    if (status == 0)
        return AA_OK;
    return aa_fail(AA_EINVAL, "renderer %s is not available%s %s", name,
                   status == 2 ? ":" : " (its --check failed):",
                   *tail ? tail : "(it said nothing)");
}

/* ---- the method ---- */

static int external_check(const double *p, const aa_filter *f)
{
    char path[PATH_MAX];
    const char *name = aa_param_word(p[RENDERER]);
    int st = aa_peer_check_filter("external", f);
    if (!st)
        st = adapter_find(name, path);
    if (!st)
        st = adapter_check(name, path);
    return st;
}

static void external_release(void *state)
{
    external_state *s = state;
    if (!*s->dir)
        return;
    unlink(s->svg);
    unlink(s->png);
    rmdir(s->dir);
    s->dir[0] = '\0';
}

static double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

/* 1 if every channel of c is 0 or 1. */
static int binary_colour(aa_rgb c)
{
    for (int k = 0; k < 3; k++)
        if (c.c[k] != 0.0 && c.c[k] != 1.0)
            return 0;
    return 1;
}

/* Our own folder for the SVG and the PNG. */
static int make_dir(external_state *s)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !*tmp)
        tmp = "/tmp";
    int st = aa_pathf(s->dir, sizeof s->dir, "%s/aabench-external-XXXXXX", tmp);
    if (st)
        return st;
    if (!mkdtemp(s->dir)) {
        int e = errno;
        s->dir[0] = '\0';
        return aa_fail(AA_EIO, "cannot make a folder in %s: %s", tmp, strerror(e));
    }
    if ((st = aa_pathf(s->svg, sizeof s->svg, "%s/scene.svg", s->dir)) ||
        (st = aa_pathf(s->png, sizeof s->png, "%s/image.png", s->dir)))
        return st;
    return AA_OK;
}

static int external_init(void *state, const double *p, const aa_job *job)
{
    external_state *s = state;
    const aa_scene *scene = job->placed;
    const char *name = aa_param_word(p[RENDERER]);
    int n = aa_scene_layer_count(scene), st;
    if ((st = adapter_find(name, s->adapter)))
        return st;
    /* the mask and the colour mapping read coverage, not composited colour */
    if (aa_scene_is_clipped(scene))
        return aa_fail(AA_EINVAL, "external maps a renderer's coverage back to the layers' "
                                  "colours: this scene has clip paths, which it does not "
                                  "take");
    if (!aa_scene_is_opaque(scene))
        return aa_fail(AA_EINVAL, "external maps a renderer's coverage back to the layers' "
                                  "colours: this scene has translucent layers (opacity below "
                                  "1), which it does not take");
    s->mask = n <= 1;
    s->bg = aa_scene_background(scene);
    s->fg = n ? aa_scene_layer_colour(scene, 0) : s->bg;
    if (!s->mask) {
        for (int l = -1; l < n; l++) {
            aa_rgb c = l < 0 ? s->bg : aa_scene_layer_colour(scene, l);
            if (!binary_colour(c))
                return aa_fail(AA_EINVAL,
                               "external draws a scene of several layers in its own colours, "
                               "which must be 0 or 1 in every channel (8-bit values would "
                               "round others); %s %d is (%.17g, %.17g, %.17g)",
                               l < 0 ? "the background" : "layer", l, c.c[0], c.c[1], c.c[2]);
        }
    }
    for (int q = 0; q < 256; q++)
        s->srgb[q] = srgb_decode(q / 255.0);
    char desc[256];
    snprintf(desc, sizeof desc, "aabench external:renderer=%s: the placed scene at %dx%d, %s",
             name, job->w, job->h,
             s->mask ? "its layer white over black (coverage)" : "in its colours");
    if ((st = make_dir(s)) ||
        (st = aa_scene_svg_write(s->svg, scene, job->w, job->h,
                                 s->mask ? AA_SVG_MASK : AA_SVG_COLOURS, desc))) {
        external_release(s);
        return st;
    }
    /* load the image reader now, untimed: write and read a 1x1 PNG */
    aa_image one = {0}, back = {0};
    if (!(st = aa_image_alloc(&one, 1, 1, 3))) {
        one.v[0] = one.v[1] = one.v[2] = 0.5;
        if (!(st = aa_image_write(s->png, &one, NULL)))
            st = aa_image_read(s->png, &back);
        unlink(s->png);
    }
    aa_image_free(&one);
    aa_image_free(&back);
    if (st)
        external_release(s);
    return st;
}

/* The 8-bit code of a value aa_image_read gave (an undeclared or sRGB 8-bit
 * file is decoded as sRGB); -1 if it is none. */
static int code_of(const external_state *s, double v)
{
    static const aa_encode srgb = {AA_ENCODE_SRGB, 0};
    long q0 = lround(aa_encode_value(&srgb, v) * 255.0);
    int best = -1;
    for (long q = q0 - 1; q <= q0 + 1; q++)
        if (q >= 0 && q <= 255 && fabs(s->srgb[q] - v) <= 1e-9 &&
            (best < 0 || fabs(s->srgb[q] - v) < fabs(s->srgb[best] - v)))
            best = (int)q;
    return best;
}

/* The image read back into `out`. */
static int convert(const external_state *s, const double *p, const char *name, const aa_image *im,
                   aa_image *out)
{
    int c = im->c, alpha = c == 2 || c == 4 ? c - 1 : -1, grey = c < 3;
    int linear = (int)p[DECODE] == DECODE_LINEAR;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++) {
            const double *px = aa_pixel(im, i, j);
            double v[3];
            for (int k = 0; k < c; k++) {
                int q = code_of(s, px[k]);
                if (q < 0)
                    return aa_fail(AA_EIO,
                                   "renderer %s: pixel (%d, %d) channel %d is no 8-bit "
                                   "sRGB code (%.17g): adapters write 8-bit PNGs that declare no "
                                   "encoding, or sRGB",
                                   name, i, j, k, px[k]);
                if (k == alpha) {
                    if (q != 255)
                        return aa_fail(AA_EIO,
                                       "renderer %s left pixel (%d, %d) transparent "
                                       "(alpha %d/255), though the SVG's background is opaque",
                                       name, i, j, q);
                } else if (k < 3 && (!grey || k == 0)) {
                    v[k] = linear ? q / 255.0 : s->srgb[q];
                }
            }
            if (grey)
                v[1] = v[2] = v[0];
            double *o = aa_pixel(out, i, j);
            if (s->mask) {
                double a = (v[0] + v[1] + v[2]) / 3.0;
                for (int k = 0; k < 3; k++)
                    o[k] = (1.0 - a) * s->bg.c[k] + a * s->fg.c[k];
            } else {
                for (int k = 0; k < 3; k++)
                    o[k] = v[k];
            }
        }
    return AA_OK;
}

/* An adapter that can time its renderer's own drawing (in-process, start-up
 * left out) says so in its last line: "render-seconds: D[.D...]", plain
 * decimal digits (read by hand: whatever the locale), in (0, 1e6] (others
 * are refused with a warning).  1 and *seconds if the line is one. */
static int own_seconds(const char *line, double *seconds)
{
    static const char key[] = "render-seconds: ";
    if (strncmp(line, key, sizeof key - 1))
        return 0;
    const char *c = line + sizeof key - 1;
    double v = 0, scale = 1;
    int digits = 0, point = 0;
    for (; *c; c++) {
        if (*c == '.' && !point) {
            point = 1;
        } else if (*c >= '0' && *c <= '9' && digits < 30) {
            digits++;
            if (point)
                v += (scale /= 10) * (*c - '0');
            else
                v = 10 * v + (*c - '0');
        } else {
            return 0;
        }
    }
    if (!digits)
        return 0;
    *seconds = v;
    return 1;
}

static int external_render(void *state, const double *p, const aa_job *job, aa_image *out,
                           aa_counters *counters)
{
    external_state *s = state;
    const char *name = aa_param_word(p[RENDERER]);
    counters->samples = 0;
    counters->expensive_pixels = 0;
    char w[16], h[16], tail[TAIL + 1];
    snprintf(w, sizeof w, "%d", job->w);
    snprintf(h, sizeof h, "%d", job->h);
    char *argv[] = {s->adapter, s->svg, w, h, s->png, NULL};
    int status, st;
    unlink(s->png);
    const char *files[3] = {s->svg, s->png, s->dir};
    if ((st = run_program(argv, files, &status, tail)))
        return aa_fail_context(st, "renderer %s", name);
    if (status == 2)
        return aa_fail(AA_EINVAL, "renderer %s refused: %s", name,
                       *tail ? tail : "(it said nothing)");
    if (status)
        return aa_fail(AA_EIO, "renderer %s failed (exit status %d): %s", name, status,
                       *tail ? tail : "(it said nothing)");
    double seconds;
    if (own_seconds(tail, &seconds)) {
        if (seconds > 0 && seconds <= 1e6)
            aa_method_report_seconds(seconds);
        else
            aa_warn("renderer %s: \"%s\" is no time (outside (0, 1e6] s): the render is timed "
                    "by its whole process instead",
                    name, tail);
    }
    aa_image im = {0};
    if ((st = aa_image_read(s->png, &im)))
        return aa_fail_context(st, "renderer %s's image", name);
    if (im.w != job->w || im.h != job->h || im.c < 1 || im.c > 4)
        st = aa_fail(AA_EIO, "renderer %s wrote a %dx%d image of %d channels, not %dx%d",
                     name, im.w, im.h, im.c, job->w, job->h);
    else
        st = convert(s, p, name, &im, out);
    aa_image_free(&im);
    return st;
}

const aa_method_type aa_method_external = {
    {"external",
     "an SVG renderer run as a program through an adapter (librsvg, Chromium, resvg, or one's "
     "own): time is its own drawing where the adapter reports it, else its whole process",
     external_params},
    sizeof(external_state),
    AA_METHOD_SOME_SCENES | AA_METHOD_EXTERNAL,
    external_check,
    external_init,
    external_render,
    external_release};

int aa_external_adapter(const aa_spec *spec, char *path)
{
    if (spec->info != &aa_method_external.info)
        return aa_fail(AA_EINVAL, "%s is not the external method", spec->info->name);
    return adapter_find(aa_param_word(spec->v[RENDERER]), path);
}
