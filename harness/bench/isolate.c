/*
 * isolate.c: one case of a run in a child process of its own.
 *
 * A method from a plug-in is code the harness has never seen: if it
 * crashes, aborts or never returns, the run must record that as the case's
 * outcome and go on, not end with it.  So the case runs in a child made by
 * fork(): the child renders, measures and sends back its row (and, when the
 * run writes images, the image) through a pipe, then ends with _exit.  The
 * parent waits up to the time-out; a child killed by a signal, one that
 * ends without a whole report, or one that runs out of time gives a failed
 * row: "crashed (signal 11)", "timed out after 600 s".  A child still
 * running ISOLATE_GRACE s after the time-out (the external method's
 * renderers end at the time-out itself: aa_external_time_limit) is sent
 * SIGTERM, which ends a renderer it started with its folder (external.c's
 * handler), and SIGKILL ISOLATE_TERM s later.  Everything the child needs
 * (the reference, the scene, the job) is in its copy of the parent's
 * memory; it writes no file of its own but in its temporary folder
 * (below), so a child killed halfway leaves nothing behind, and the parent
 * writes the images.
 *
 * OpenMP: GCC's libgomp is not fork-safe once its thread pool exists (the
 * child would wait forever for threads that were not copied), and the
 * parent has used it (references, metrics, the methods run in process).
 * Before each fork the parent releases its pool (omp_pause_resource_all
 * with omp_pause_hard, OpenMP 5.0; the next parallel region makes a new
 * one), and the child starts its own pool before the case, so that its
 * first render is not timed with the threads' start-up; so does the parent
 * after the case, for the methods it times itself.
 *
 * The child dies with its parent (PR_SET_PDEATHSIG on Linux): a run killed
 * with SIGKILL leaves no case running.
 *
 * Temporary files.  What a child or the programs it starts write in the
 * temporary folder (the external method's folder with its SVG and PNG, a
 * renderer's own files) would stay behind if the child were killed before
 * it removed them: by the time-out's SIGKILL, or by SIGTERM while the
 * method is still in init, before it watches for signals.  So the parent
 * makes a folder of the case's own in $TMPDIR (aabench-case-XXXXXX), the
 * child takes it as its TMPDIR, and the parent removes it, whatever it
 * holds, once the child has ended in any way.  (Where the folder cannot be
 * made, the case runs with the parent's TMPDIR, as before.)
 */
#define _XOPEN_SOURCE 700 /* nftw */
#include "bench.h"
#include "isolate_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifdef __linux__
#include <sys/prctl.h>
#endif

#ifdef _OPENMP
#include <omp.h>
#endif

/* The row of a case that failed (isolate_internal.h). */
void aa__row_failed(aa_row *row, const char *fmt, ...)
{
    char why[sizeof row->note];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    row->ok = 0;
    row->failed = 1;
    row->temporal = 0;
    snprintf(row->note, sizeof row->note, "failed: %.*s", (int)(sizeof row->note - 9), why);
}

#define REPORT_MAGIC 0x61616273636173ULL /* "aabscas" */

/* What the child sends: this, then the image's pixels if `pixels`. */
typedef struct report {
    uint64_t magic;
    int32_t status, pixels;
    char error[1024];
    aa_row row;
} report;

static int write_all(int fd, const void *data, size_t len)
{
    const char *p = data;
    while (len > 0) {
        ssize_t k = write(fd, p, len);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k;
        len -= (size_t)k;
    }
    return 0;
}

/* Seconds past a case's time-out before its child is killed. */
#define ISOLATE_GRACE 3.0
/* s between SIGTERM and SIGKILL for a child past its deadline: the
 * external method's handler of SIGTERM kills its renderer's group and
 * removes its folder at once (a few system calls), which even a loaded
 * machine schedules within this */
#define ISOLATE_TERM 2.0

/* A method that calls exit() in the child ends it here, with its status
 * and nothing else: the handlers that the parent's libraries registered
 * (the image module's bring some) would run in a process that has none of
 * their threads, and wait for them, or act for the parent. */
static void end_at_exit(int status, void *unused)
{
    (void)unused;
    _exit(status);
}

/* The case's temporary folder (see the header): made before the fork,
 * removed with all it holds after the child has ended. */
static int case_tmp_make(char *dir, size_t size)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !*tmp)
        tmp = "/tmp";
    int n = snprintf(dir, size, "%s/aabench-case-XXXXXX", tmp);
    if (n < 0 || (size_t)n >= size || !mkdtemp(dir)) {
        dir[0] = '\0';
        return 0;
    }
    return 1;
}

static int remove_one(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    remove(path);
    return 0; /* go on: remove what can be removed */
}

static void case_tmp_remove(const char *dir)
{
    if (*dir)
        nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

static void child(int fd, aa__case_fn fn, void *arg, aa_row *row, aa_image *img, int threads,
                  pid_t parent, const char *tmp)
{
    /* registered last, so run first */
    on_exit(end_at_exit, NULL);
    if (*tmp)
        setenv("TMPDIR", tmp, 1);
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
    /* SIGTERM from the parent past the deadline ends the child (after the
     * external method's own handler, while a renderer runs), not a handler
     * of the parent's that would go on with the run */
    signal(SIGTERM, SIG_DFL);
    if (getppid() != parent)
        _exit(120); /* the parent died before prctl */
#ifdef _OPENMP
    int nt = aa_thread_count(threads);
#pragma omp parallel num_threads(nt)
    {
    }
#else
    (void)threads;
#endif
    static report r; /* static: no large stack frame in the child */
    memset(&r, 0, sizeof r);
    r.magic = REPORT_MAGIC;
    r.row = *row;
    r.status = fn(arg, &r.row);
    if (r.status)
        snprintf(r.error, sizeof r.error, "%s", aa_last_error());
    r.pixels = img && !r.status && r.row.ok;
    size_t bytes = r.pixels ? (size_t)img->w * img->h * 3 * sizeof *img->v : 0;
    if (write_all(fd, &r, sizeof r) || (bytes && write_all(fd, img->v, bytes)))
        _exit(121);
    _exit(0);
}

/* Read what the child sends, until it is all there, the pipe is closed or
 * the deadline passes.  Returns 1 when the report (and its pixels) came
 * whole, 0 if not, -1 when the deadline passed. */
static int receive(int fd, report *r, aa_image *img, double deadline)
{
    size_t got = 0, want = sizeof *r, bytes = 0;
    for (;;) {
        size_t total = want + bytes;
        if (got == total)
            return 1;
        double left = deadline - aa_now();
        if (left <= 0)
            return -1;
        struct pollfd pfd = {fd, POLLIN, 0};
        int ms = left > 3600.0 ? 3600 * 1000 : (int)ceil(left * 1000);
        int k = poll(&pfd, 1, ms);
        if (k < 0 && errno == EINTR)
            continue; /* an interrupt: the run stops after this case */
        if (k < 0)
            return 0;
        if (k == 0)
            continue;
        char *dst;
        size_t room;
        if (got < want) {
            dst = (char *)r + got;
            room = want - got;
        } else {
            dst = (char *)img->v + (got - want);
            room = total - got;
        }
        ssize_t n = read(fd, dst, room);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return 0;
        got += (size_t)n;
        if (got == want) {
            if (r->magic != REPORT_MAGIC)
                return 0;
            if (r->pixels) {
                if (!img)
                    return 0;
                bytes = (size_t)img->w * img->h * 3 * sizeof *img->v;
            }
        }
    }
}

int aa__case_isolated(aa__case_fn fn, void *arg, aa_row *row, aa_image *img, double timeout,
                      int threads)
{
    int fds[2];
#ifdef _OPENMP
    if (omp_pause_resource_all(omp_pause_hard) != 0)
        return aa_fail(AA_EFAIL, "cannot run %s in a child process: the OpenMP runtime would not "
                                 "release its threads before fork",
                       row->method);
#endif
    if (pipe(fds) != 0)
        return aa_fail(AA_EIO, "cannot run %s in a child process: pipe: %s", row->method,
                       strerror(errno));
    fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    fcntl(fds[1], F_SETFD, FD_CLOEXEC);
    char tmp[PATH_MAX];
    case_tmp_make(tmp, sizeof tmp);
    /* the child must not write out what the parent's buffers hold */
    fflush(NULL);
    pid_t parent = getpid(), pid = fork();
    if (pid < 0) {
        int err = errno;
        close(fds[0]);
        close(fds[1]);
        case_tmp_remove(tmp);
        return aa_fail(AA_EIO, "cannot run %s in a child process: fork: %s", row->method,
                       strerror(err));
    }
    if (pid == 0) {
        close(fds[0]);
        child(fds[1], fn, arg, row, img, threads, parent, tmp);
    }
    close(fds[1]);
    report *r = malloc(sizeof *r);
    /* a grace of ISOLATE_GRACE s: a case whose method ends the programs it
     * started at the time-out (the external method: SIGTERM, half a second,
     * SIGKILL, its folder removed) reports that itself, which on a loaded
     * machine takes more than a second; a child still running then is
     * killed, and what it started is left */
    const double deadline = aa_now() + timeout + ISOLATE_GRACE;
    int whole = r ? receive(fds[0], r, img, deadline) : 0;
    close(fds[0]);
    /* the child ends now, or by the deadline (one that closed its end of
     * the pipe may still be running) */
    int status = 0;
    pid_t done;
    for (;;) {
        done = waitpid(pid, &status, WNOHANG);
        if (done < 0 && errno == EINTR)
            continue;
        if (done != 0 || whole < 0 || aa_now() >= deadline)
            break;
        struct timespec ts = {0, 5 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
    if (done <= 0) {
        if (whole >= 0 && aa_now() >= deadline)
            whole = -1;
        /* SIGTERM first: a renderer the child started is ended with its
         * folder (external.c's handler); SIGKILL if the child outlives
         * ISOLATE_TERM */
        kill(pid, SIGTERM);
        const double term_end = aa_now() + ISOLATE_TERM;
        for (;;) {
            done = waitpid(pid, &status, WNOHANG);
            if (done < 0 && errno == EINTR)
                continue;
            if (done != 0 || aa_now() >= term_end)
                break;
            struct timespec ts = {0, 5 * 1000 * 1000};
            nanosleep(&ts, NULL);
        }
        if (done <= 0) {
            kill(pid, SIGKILL);
            while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
                ;
        }
    }
    case_tmp_remove(tmp);
    int st = AA_OK;
    if (!r) {
        st = aa_fail(AA_ENOMEM, "out of memory");
    } else if (whole < 0) {
        aa__row_failed(row, "timed out after %g s", timeout);
    } else if (WIFSIGNALED(status)) {
        aa__row_failed(row, "crashed (signal %d)", WTERMSIG(status));
    } else if (!whole || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        aa__row_failed(row, "ended (exit status %d) without reporting its result",
                       WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    } else if (r->status) {
        r->error[sizeof r->error - 1] = '\0';
        st = aa_fail(r->status, "%s", r->error);
    } else {
        *row = r->row;
    }
    free(r);
#ifdef _OPENMP
    /* this process's threads again, before it times a method itself */
    int nt = aa_thread_count(threads);
#pragma omp parallel num_threads(nt)
    {
    }
#endif
    return st;
}
