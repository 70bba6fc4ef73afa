/*
 * support.c: helpers shared by the tests (support.h).
 */
#define _GNU_SOURCE /* dl_iterate_phdr, RTLD_NOLOAD */

#include "support.h"

#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <link.h>
#include <locale.h>
#include <math.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "cli.h"
#include "oiio.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

extern char **environ;

/* ---- rendering ---- */

static void filter_of(const char *filter, aa_filter *f)
{
    if (!filter)
        aa_filter_default(f);
    else if (aa_filter_parse(filter, f) != AA_OK)
        fail_msg("filter %s: %s", filter, aa_last_error());
}

static void view_filter(const support_view *v, aa_filter *f)
{
    filter_of(v->filter, f);
}

int support_parse_method(const char *method, const char *filter, aa_spec *spec)
{
    aa_filter f;
    aa_spec unused;
    filter_of(filter, &f);
    return aa_method_parse(method, &f, spec ? spec : &unused);
}

int support_render_view(const char *method, const aa_scene *scene, const support_view *v,
                        aa_image *out, aa_counters *c)
{
    aa_filter f;
    aa_spec spec;
    aa_job job;
    aa_counters unused;
    view_filter(v, &f);
    int st = aa_method_parse(method, &f, &spec);
    if (st)
        return st;
    assert_int_equal(aa_job_init(&job, scene, v->w, v->h, v->t, v->vx, v->vy, &f, v->seed,
                                 v->threads),
                     AA_OK);
    job.frame_only = v->frame_only;
    assert_int_equal(aa_image_alloc(out, v->w, v->h, 3), AA_OK);
    st = aa_method_run(&spec, &job, 1, out, c ? c : &unused, NULL);
    aa_job_free(&job);
    if (st)
        aa_image_free(out);
    return st;
}

void support_render_must(const char *method, const aa_scene *scene, const support_view *v,
                         aa_image *out, aa_counters *c)
{
    if (support_render_view(method, scene, v, out, c) != AA_OK)
        fail_msg("%s -f %s: %s", method, v->filter ? v->filter : "box", aa_last_error());
}

void support_render(const char *method, const aa_scene *scene, const char *filter, int w,
                    int h, int threads, aa_image *out, aa_counters *c)
{
    const support_view v = {.w = w, .h = h, .filter = filter, .seed = 1, .threads = threads};
    support_render_must(method, scene, &v, out, c);
}

void support_reference(const aa_scene *scene, const support_view *v, aa_image *out,
                       aa_image *bound, aa_truth_stats *stats)
{
    aa_filter f;
    view_filter(v, &f);
    aa_scene *placed = aa_scene_place(scene, v->w, v->h, v->t, v->vx, v->vy);
    assert_non_null(placed);
    assert_int_equal(aa_image_alloc(out, v->w, v->h, 3), AA_OK);
    if (bound)
        assert_int_equal(aa_image_alloc(bound, v->w, v->h, 1), AA_OK);
    assert_int_equal(aa_truth_render(placed, &f, v->threads, out, bound, stats), AA_OK);
    aa_scene_free(placed);
}

void support_pattern_reference(const char *pattern, const support_view *v, aa_image *out,
                               aa_image *bound, aa_truth_stats *stats)
{
    aa_spec spec;
    aa_scene *s = NULL;
    if (aa_pattern_parse(pattern, &spec) || aa_pattern_scene_at(&spec, v->w, v->h, &s))
        fail_msg("pattern %s: %s", pattern, aa_last_error());
    support_reference(s, v, out, bound, stats);
    aa_scene_free(s);
}

int support_scene_holds_cubics(void)
{
    aa_scene *probe = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(probe);
    int can = aa_scene_layer(probe, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) == AA_OK &&
              aa_scene_move_to(probe, 0, 0) == AA_OK &&
              aa_scene_cubic_to(probe, 0.1, 0.2, 0.3, 0.2, 0.4, 0) == AA_OK;
    aa_scene_free(probe);
    return can;
}

/* ---- comparing images ---- */

static size_t values(const aa_image *a, const aa_image *b)
{
    if (a->w != b->w || a->h != b->h || a->c != b->c)
        fail_msg("images of %dx%dx%d and %dx%dx%d compared", a->w, a->h, a->c, b->w, b->h, b->c);
    return (size_t)a->w * a->h * a->c;
}

double support_rmse(const aa_image *a, const aa_image *b)
{
    size_t n = values(a, b);
    double s = 0;
    for (size_t k = 0; k < n; k++)
        s += (a->v[k] - b->v[k]) * (a->v[k] - b->v[k]);
    return sqrt(s / (double)n);
}

double support_max_diff(const aa_image *a, const aa_image *b, int *wi, int *wj)
{
    values(a, b);
    double worst = 0;
    for (int j = 0; j < a->h; j++)
        for (int i = 0; i < a->w; i++)
            for (int ch = 0; ch < a->c; ch++) {
                double d = fabs(aa_pixel(a, i, j)[ch] - aa_pixel(b, i, j)[ch]);
                if (!(d <= worst)) {
                    worst = isnan(d) ? INFINITY : d;
                    if (wi)
                        *wi = i;
                    if (wj)
                        *wj = j;
                }
            }
    return worst;
}

int support_same_image(const aa_image *a, const aa_image *b)
{
    return memcmp(a->v, b->v, sizeof(double) * values(a, b)) == 0;
}

double support_channel_mean(const aa_image *im, int ch)
{
    double sum = 0.0;
    for (int j = 0; j < im->h; j++)
        for (int i = 0; i < im->w; i++)
            sum += aa_pixel(im, i, j)[ch];
    return sum / ((double)im->w * im->h);
}

/* ---- checks shared by several tests ---- */

double support_check_crow_box(const char *what, const oracle_crow *p, const aa_image *img,
                              double tol)
{
    double worst = 0;
    for (int j = 0; j < img->h; j++)
        for (int i = 0; i < img->w; i++) {
            double want = oracle_crow_box(p, img->w, img->h, i, j);
            const double *px = aa_pixel(img, i, j);
            double d = fabs(px[0] - want);
            worst = fmax(worst, d);
            if (!(d <= tol) || px[1] != px[0] || px[2] != px[0])
                fail_msg("%s %dx%d pixel (%d, %d): %.17g (%.17g, %.17g), closed form %.17g", what,
                         img->w, img->h, i, j, px[0], px[1], px[2], want);
        }
    return worst;
}

void support_check_rmse_order(const char *what, const aa_scene *scene, const support_view *v,
                              const char *const *methods, int n)
{
    aa_image ref, img;
    support_reference(scene, v, &ref, NULL, NULL);
    double last = INFINITY;
    for (int k = 0; k < n; k++) {
        aa_counters c;
        support_render_must(methods[k], scene, v, &img, &c);
        double e = support_rmse(&img, &ref);
        print_message("%s %dx%d %s: %-16s RMSE %.4e, %llu samples, %llu pixels sampled\n", what,
                      v->w, v->h, v->filter ? v->filter : "box", methods[k], e,
                      (unsigned long long)c.samples, (unsigned long long)c.expensive_pixels);
        aa_image_free(&img);
        if (!(e < last))
            fail_msg("%s: %s has RMSE %.4e, not below the previous method's %.4e", what,
                     methods[k], e, last);
        last = e;
    }
    aa_image_free(&ref);
}

/* ---- figures ---- */

const char *support_caption_field(const char *caption, int panel, const char *field)
{
    char key[32];
    snprintf(key, sizeof key, "panel %d:", panel);
    const char *p = strstr(caption, key);
    assert_non_null(p);
    p = strstr(p, field);
    assert_non_null(p);
    return p + strlen(field);
}

/* ---- the command under test ---- */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The command server (support.h says what it is for).  The test and the
 * server talk through a SOCK_SEQPACKET socket pair: a request is one
 * message (srv_head, then the folder, the arguments and the environment as
 * NUL-ended strings) with the two output descriptors attached; the server
 * answers SRV_START (the child's pid, or an errno) at once and SRV_EXIT
 * (its wait status) when the child ends. */

#define SRV_MSG 65536 /* the largest request */
#define SRV_LIVE 128  /* children of the server a test may have at once */

enum { SRV_START = 1, SRV_EXIT = 2 };

typedef struct srv_head {
    unsigned long long fsize; /* RLIMIT_FSIZE for the child; 0: unchanged */
    unsigned umask;
    int nargs, nenv;
} srv_head;

typedef struct srv_reply {
    int type;
    pid_t pid;
    int value; /* SRV_START: 0 or the fork's errno; SRV_EXIT: the wait status */
} srv_reply;

/* The test's side: two servers, one that never loads the image module and
 * one that loads it at its first request, for the starts that will read or
 * write an image (srv_wants_images): a fork of a process with the module's
 * ~250 libraries mapped copies their page tables, and its end unmaps them
 * (all starts from the one server: test_shard 9.2 core-s, test_cli 4.4,
 * test_run 2.0; shared out: 8.3, 3.9, 1.8).
 *
 * Under ASan, none, or the image server alone for a test that asks
 * (support_start_servers(1)), for the starts that the test does not wait
 * for (those it waits for are calls of cli_main() in its own process).  A sanitized start that does not load the module
 * costs about 0.1 s, most of it LeakSanitizer's check at the end, which a
 * fork pays as well, and in a fork of the image server that check walks
 * the memory of the module's libraries too: forks of the bare server were
 * measured to cost more than the execs (test_cli 15.2 -> 19.8 core-s,
 * test_shard 21.9 -> 26.2), and so were forks of the image server for
 * every start that names an image file or makes a montage (test_cli 14.0
 * -> 30.2: most of its starts are refused before any image is read),
 * while a sanitized start that loads the module costs about 1 s, which
 * the fork spares where the starts do load it (test_image_faults alone:
 * 32.4-41.0 core-s, median 34.8 of five runs, against 23.8-37.5, median
 * 27.9 of six; beside another test the two overlap). */
enum { SRV_BARE, SRV_IMAGES, SRV_N };
static int srv_wanted[SRV_N];
static int srv_fd[SRV_N] = {-1, -1}; /* the ends of the sockets; -1: no server */
static int srv_refused[SRV_N]; /* the server said it cannot start commands: exec them */
static pid_t srv_owner;   /* the process that started them (a fork of the test may not use them) */
static pid_t snap_owner;  /* the process whose start-up srv_env and the rest describe */
static char snap_locale[256]; /* its locale (LC_ALL) */
static pid_t srv_pid[SRV_N];
static char **srv_env;    /* the environment at the test's start, which the servers have (a copy) */
static struct rlimit srv_lim[RLIM_NLIMITS];
static sigset_t srv_mask; /* the signal mask it has */
static int srv_ignored[NSIG]; /* the signals it ignores */
static struct {
    pid_t pid;
    int server, ended, status;
} srv_kids[SRV_LIVE];

/* Variables that libraries read as they load, or that the command reads
 * once (the image module), so that a child of the server would not see a
 * change the test made after the server started. */
static int srv_startup_name(const char *entry)
{
    static const char *const prefixes[] = {"LD_",    "OMP_",           "GOMP_",         "KMP_",
                                           "ASAN_",  "UBSAN_",         "LSAN_",         "MSAN_",
                                           "TSAN_",  "MALLOC_",        "GLIBC_TUNABLES", "AABENCH_OIIO",
                                           "OIIO_",  "OPENIMAGEIO_",   "OPENEXR_",      "AABENCH_TEST_EXEC"};
    for (size_t k = 0; k < sizeof prefixes / sizeof *prefixes; k++)
        if (strncmp(entry, prefixes[k], strlen(prefixes[k])) == 0)
            return 1;
    return 0;
}

/* The entry NAME=... of env (NULL-ended) whose name is that of `entry`. */
static const char *srv_env_find(char *const *env, const char *entry)
{
    size_t len = strcspn(entry, "=");
    for (; env && *env; env++)
        if (strncmp(*env, entry, len) == 0 && (*env)[len] == '=')
            return *env;
    return NULL;
}

/* The value `entry` has in the environment of the child: `extra` (one
 * NAME=value) over environ. */
static const char *srv_env_now(const char *entry, const char *extra)
{
    size_t len = strcspn(entry, "=");
    if (extra && strncmp(extra, entry, len) == 0 && extra[len] == '=')
        return extra;
    return srv_env_find(environ, entry);
}

static int srv_same_entry(const char *a, const char *b)
{
    return (a == NULL && b == NULL) || (a != NULL && b != NULL && strcmp(a, b) == 0);
}

/* 1 if a process that starts as this test program did (the snapshot taken
 * by support_start_servers) runs the command as the command exec'd now
 * would (with `extra` added to the environment): the variables read at
 * start-up, the resource limits, the signal mask and the ignored signals
 * are as they were. */
static int srv_same_start(const char *extra)
{
    if (srv_env == NULL || getpid() != snap_owner)
        return 0;
    for (char **e = srv_env; *e; e++)
        if (srv_startup_name(*e) && !srv_same_entry(*e, srv_env_now(*e, extra)))
            return 0;
    for (char **e = environ; e && *e; e++)
        if (srv_startup_name(*e) && !srv_same_entry(srv_env_now(*e, extra), srv_env_find(srv_env, *e)))
            return 0;
    if (extra && srv_startup_name(extra) && !srv_same_entry(extra, srv_env_find(srv_env, extra)))
        return 0;
    for (int r = 0; r < RLIM_NLIMITS; r++) {
        struct rlimit now;
        if (getrlimit(r, &now) != 0 || now.rlim_cur != srv_lim[r].rlim_cur ||
            now.rlim_max != srv_lim[r].rlim_max)
            return 0;
    }
    sigset_t mask;
    if (sigprocmask(SIG_BLOCK, NULL, &mask) != 0)
        return 0;
    for (int sig = 1; sig < NSIG; sig++) {
        struct sigaction a;
        if (sigismember(&mask, sig) != sigismember(&srv_mask, sig))
            return 0;
        if (sigaction(sig, NULL, &a) == 0 && (a.sa_handler == SIG_IGN) != srv_ignored[sig])
            return 0;
    }
    return 1;
}

/* 1 if a child of the server would start as the command exec'd now would. */
static int srv_usable(const char *extra)
{
    return support_server_running() && srv_same_start(extra);
}

/* ---- the server's side ---- */

static int srv_sock = -1;             /* the server's end */
static int srv_chld[2] = {-1, -1};    /* SIGCHLD's self-pipe */

static void srv_on_chld(int sig)
{
    (void)sig;
    int saved = errno;
    if (write(srv_chld[1], "c", 1) < 0) {
        /* full: a wake-up is pending anyway */
    }
    errno = saved;
}

/* In a child about to become the command: standard output and error to
 * out and err (closed after), and RLIMIT_FSIZE fsize with SIGXFSZ ignored
 * if fsize > 0; ends the child with status 126 if it cannot. */
static void child_io(int out, int err, unsigned long long fsize)
{
    if (fsize > 0) {
        struct rlimit r = {(rlim_t)fsize, (rlim_t)fsize};
        signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &r) != 0)
            _exit(126);
    }
    if (dup2(out, 1) < 0 || dup2(err, 2) < 0)
        _exit(126);
    if (out > 2)
        close(out);
    if (err > 2 && err != out)
        close(err);
}

/* The child: becomes the command with the request in buf. */
static void srv_child(char *buf, int out, int err) __attribute__((noreturn));
static void srv_child(char *buf, int out, int err)
{
    close(srv_sock);
    close(srv_chld[0]);
    close(srv_chld[1]);
    signal(SIGCHLD, SIG_DFL);
    srv_head h;
    memcpy(&h, buf, sizeof h);
    char *p = buf + sizeof h, *cwd = p;
    p += strlen(p) + 1;
    char **argv = calloc((size_t)h.nargs + 1, sizeof *argv);
    if (argv == NULL)
        _exit(126);
    for (int k = 0; k < h.nargs; k++, p += strlen(p) + 1)
        argv[k] = p;
    clearenv();
    for (int k = 0; k < h.nenv; k++, p += strlen(p) + 1)
        if (putenv(p) != 0)
            _exit(126);
    if (chdir(cwd) != 0)
        _exit(126);
    umask((mode_t)h.umask);
    child_io(out, err, h.fsize);
    int code = cli_main(h.nargs, argv);
    /* The end of main() but the libraries' exit handlers: those of the
     * module's libraries would wait for threads that the server has and
     * a fork does not (the project registers none).  Under ASan, the leak
     * check that ends a program. */
    fflush(NULL);
#if defined(__SANITIZE_ADDRESS__)
    __lsan_do_leak_check();
#endif
    _exit(code);
}

/* The threads this process has (1 if it cannot tell). */
static int srv_threads(void)
{
    DIR *d = opendir("/proc/self/task");
    int n = 0;
    if (d == NULL)
        return 1;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += e->d_name[0] != '.';
    closedir(d);
    return n > 0 ? n : 1;
}

static int srv_find_log4cplus(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size;
    if (strstr(info->dlpi_name, "liblog4cplus") == NULL)
        return 0;
    snprintf(data, PATH_MAX, "%s", info->dlpi_name);
    return 1;
}

/* Stop the threads that the image module's libraries start as they load,
 * so that the server, whose forks become commands, has only its own
 * thread.  A fork has none of the others: under ASan, LeakSanitizer's
 * check at a child's end would warn on the command's standard error that
 * each "was not suspended. False leaks are possible".  On Debian 12 they
 * are the four of log4cplus's pool (OpenImageIO's DICOM reader links
 * DCMTK, which logs through log4cplus), which log4cplus::
 * shutdownThreadPool() joins; it has no C name. */
static void srv_stop_library_threads(void)
{
    char path[PATH_MAX] = "";
    if (dl_iterate_phdr(srv_find_log4cplus, path) == 0)
        return;
    void *lib = dlopen(path, RTLD_NOW | RTLD_NOLOAD);
    if (lib == NULL)
        return;
    void (*stop)(void);
    *(void **)&stop = dlsym(lib, "_ZN9log4cplus18shutdownThreadPoolEv");
    if (stop != NULL)
        stop();
    dlclose(lib);
}

static void srv_send(srv_reply r)
{
    while (send(srv_sock, &r, sizeof r, MSG_NOSIGNAL) < 0 && errno == EINTR)
        ;
}

/* The server's loop; ends when the test does.  With `images`, the image
 * module is loaded before the first child. */
static void srv_serve(int images) __attribute__((noreturn));
static void srv_serve(int images)
{
    char *buf = malloc(SRV_MSG);
    struct sigaction a;
    memset(&a, 0, sizeof a);
    a.sa_handler = srv_on_chld;
    a.sa_flags = SA_RESTART | SA_NOCLDSTOP;
    sigemptyset(&a.sa_mask);
    if (buf == NULL || pipe(srv_chld) != 0 || sigaction(SIGCHLD, &a, NULL) != 0)
        _exit(1);
    for (int k = 0; k < 2; k++)
        fcntl(srv_chld[k], F_SETFL, O_NONBLOCK);
    int loaded = 0, refuse = 0;
    for (;;) {
        struct pollfd p[2] = {{srv_sock, POLLIN, 0}, {srv_chld[0], POLLIN, 0}};
        if (poll(p, 2, -1) < 0) {
            if (errno == EINTR)
                continue;
            _exit(1);
        }
        char drain[64];
        while (read(srv_chld[0], drain, sizeof drain) > 0)
            ;
        int status;
        pid_t pid;
        while ((pid = waitpid(-1, &status, WNOHANG)) > 0)
            srv_send((srv_reply){SRV_EXIT, pid, status});
        if (!(p[0].revents & (POLLIN | POLLHUP | POLLERR)))
            continue;
        int fds[2] = {-1, -1};
        char ctl[CMSG_SPACE(sizeof fds)];
        struct iovec iov = {buf, SRV_MSG};
        struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl,
                           .msg_controllen = sizeof ctl};
        ssize_t n = recvmsg(srv_sock, &m, MSG_CMSG_CLOEXEC);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            _exit(0); /* the test has ended */
        struct cmsghdr *c = CMSG_FIRSTHDR(&m);
        if (c == NULL || c->cmsg_type != SCM_RIGHTS || c->cmsg_len != CMSG_LEN(sizeof fds) ||
            (size_t)n < sizeof(srv_head)) {
            srv_send((srv_reply){SRV_START, -1, EPROTO});
            continue;
        }
        memcpy(fds, CMSG_DATA(c), sizeof fds);
        if (images && !loaded) {
            /* no file opened: the module and its libraries only */
            aa__oiio("the command server");
            srv_stop_library_threads();
            /* under ASan, threads left would be LeakSanitizer's warnings in
             * every child's output: the commands are exec'd instead */
            refuse = SANITIZED && srv_threads() > 1;
            loaded = 1;
        }
        if (refuse) {
            close(fds[0]);
            close(fds[1]);
            srv_send((srv_reply){SRV_START, -1, ENOTSUP});
            continue;
        }
        fflush(NULL);
        pid = fork();
        if (pid == 0)
            srv_child(buf, fds[0], fds[1]);
        int e = pid < 0 ? errno : 0;
        close(fds[0]);
        close(fds[1]);
        srv_send((srv_reply){SRV_START, pid, e});
    }
}

void support_start_server(void)
{
    support_start_servers(0);
}

void support_start_servers(int images_under_asan)
{
    srv_wanted[SRV_BARE] = !SANITIZED;
    srv_wanted[SRV_IMAGES] = !SANITIZED || images_under_asan;
    const char *flag = getenv("AABENCH_TEST_EXEC");
    const char *exe = getenv("AABENCH");
    if ((flag && strcmp(flag, "1") == 0) || exe == NULL || *exe == '\0')
        return;
    /* only for the command built beside this program (build/tests/ and
     * build/aabench): the same objects */
    char self[PATH_MAX], sibling[PATH_MAX + 16], a[PATH_MAX], b[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        return;
    self[len] = '\0';
    char *slash = strrchr(self, '/');
    if (slash == NULL)
        return;
    *slash = '\0';
    snprintf(sibling, sizeof sibling, "%s/../aabench", self);
    if (realpath(sibling, a) == NULL || realpath(exe, b) == NULL || strcmp(a, b) != 0)
        return;
    size_t n = 0;
    while (environ && environ[n])
        n++;
    srv_env = calloc(n + 1, sizeof *srv_env);
    if (srv_env == NULL)
        return;
    for (size_t k = 0; k < n; k++)
        if ((srv_env[k] = strdup(environ[k])) == NULL)
            abort();
    for (int r = 0; r < RLIM_NLIMITS; r++)
        getrlimit(r, &srv_lim[r]);
    sigprocmask(SIG_BLOCK, NULL, &srv_mask);
    for (int sig = 1; sig < NSIG; sig++) {
        struct sigaction act;
        srv_ignored[sig] = sigaction(sig, NULL, &act) == 0 && act.sa_handler == SIG_IGN;
    }
    snap_owner = getpid();
    const char *locale = setlocale(LC_ALL, NULL);
    snprintf(snap_locale, sizeof snap_locale, "%s", locale ? locale : "");
    if (!srv_wanted[SRV_IMAGES])
        return;
    for (int which = 0; which < SRV_N; which++) {
        int sv[2];
        if (!srv_wanted[which])
            continue;
        if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) != 0)
            break;
        fflush(NULL);
        pid_t pid = fork();
        if (pid < 0) {
            close(sv[0]);
            close(sv[1]);
            break;
        }
        if (pid == 0) {
            for (int other = 0; other < which; other++)
                if (srv_fd[other] >= 0)
                    close(srv_fd[other]);
            close(sv[0]);
            srv_sock = sv[1];
            srv_serve(which == SRV_IMAGES);
        }
        close(sv[1]);
        srv_fd[which] = sv[0];
        srv_pid[which] = pid;
    }
    for (int which = 0; which < SRV_N; which++)
        if (srv_wanted[which] && srv_fd[which] < 0) { /* all wanted or none */
            for (int k = 0; k < SRV_N; k++)
                if (srv_fd[k] >= 0)
                    close(srv_fd[k]);
            srv_fd[0] = srv_fd[1] = -1;
            return;
        }
    srv_owner = getpid();
}

int support_server_running(void)
{
    return srv_fd[SRV_IMAGES] >= 0 && getpid() == srv_owner;
}

/* Take one reply into srv_kids (blocking unless `nohang`): 1 if one came,
 * 0 if none is waiting; fails the test if the server is gone. */
static int srv_take(int which, int nohang)
{
    srv_reply r;
    ssize_t n;
    while ((n = recv(srv_fd[which], &r, sizeof r, nohang ? MSG_DONTWAIT : 0)) < 0 &&
           errno == EINTR)
        ;
    if (n < 0 && nohang && (errno == EAGAIN || errno == EWOULDBLOCK))
        return 0;
    if (n != (ssize_t)sizeof r)
        fail_msg("the command server (pid %d) is gone: %s", (int)srv_pid[which],
                 n < 0 ? strerror(errno) : "no reply");
    if (r.type == SRV_EXIT)
        for (int k = 0; k < SRV_LIVE; k++)
            if (srv_kids[k].pid == r.pid && srv_kids[k].server == which && !srv_kids[k].ended) {
                srv_kids[k].ended = 1;
                srv_kids[k].status = r.value;
                return 1;
            }
    if (r.type == SRV_START) {
        int k = 0;
        while (k < SRV_LIVE && srv_kids[k].pid != 0)
            k++;
        if (r.pid < 0)
            fail_msg("the command server cannot fork: %s", strerror(r.value));
        if (k == SRV_LIVE)
            fail_msg("more than %d starts of the command at once", SRV_LIVE);
        srv_kids[k].pid = r.pid;
        srv_kids[k].server = which;
        srv_kids[k].ended = 0;
    }
    return 1;
}

static int srv_kid(pid_t pid)
{
    for (int k = 0; k < SRV_LIVE; k++)
        if (srv_kids[k].pid == pid && pid > 0)
            return k;
    return -1;
}

/* Append s and its NUL to buf at *at; 0 if it does not fit. */
static int srv_put(char *buf, size_t *at, const char *s)
{
    size_t len = strlen(s) + 1;
    if (*at + len > SRV_MSG)
        return 0;
    memcpy(buf + *at, s, len);
    *at += len;
    return 1;
}

/* 1 if the command argv will likely read or write an image through the
 * module: an argument names such a file (a .pfm is written without it,
 * read with it), or the subcommand makes a montage or figures unless told
 * not to.  A wrong guess costs time, nothing else. */
static int srv_wants_images(const char *const *argv)
{
    static const char *const ext[] = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg", ".hdr"};
    static const char *const makers[] = {"run", "merge", "figures", "converge"};
    int maker = 0, none = 0;
    for (size_t k = 0; argv[1] && k < sizeof makers / sizeof *makers; k++)
        maker |= strcmp(argv[1], makers[k]) == 0;
    for (int k = 1; argv[k]; k++) {
        const char *dot = strrchr(argv[k], '.');
        none |= strcmp(argv[k], "--no-images") == 0;
        for (size_t e = 0; dot && e < sizeof ext / sizeof *ext; e++)
            if (strcasecmp(dot, ext[e]) == 0)
                return 1;
        if (dot && strcasecmp(dot, ".pfm") == 0 && strcmp(argv[k - 1], "-o") != 0)
            return 1;
    }
    return maker && !none;
}

/* 1 if the command argv may load a plug-in: --plugin, or --resume of a
 * run that may name one. */
static int may_load_plugin(const char *const *argv)
{
    for (int k = 1; argv[k]; k++)
        if (strncmp(argv[k], "--plugin", 8) == 0 || strncmp(argv[k], "--resume", 8) == 0)
            return 1;
    return 0;
}

/* A child of the server running argv (argv[0] the program) with `extra`
 * added to the environment; -1 if the server cannot be used for it. */
static pid_t srv_start(const char *const *argv, const char *extra, int out, int err,
                       unsigned long long fsize)
{
    int which = srv_wants_images(argv) ? SRV_IMAGES : SRV_BARE;
    if (!srv_usable(extra) || srv_fd[which] < 0 || srv_refused[which])
        return -1;
    /* A plug-in may end a process with exit(), whose handlers would wait
     * for threads of the image module's libraries that a fork of the
     * server, where the module is loaded, does not have: a command that
     * loads one is exec'd. */
    if (may_load_plugin(argv))
        return -1;
    static char buf[SRV_MSG];
    char cwd[PATH_MAX];
    if (getcwd(cwd, sizeof cwd) == NULL)
        return -1;
    srv_head h = {fsize, 0, 0, 0};
    mode_t mask = umask(0);
    umask(mask);
    h.umask = (unsigned)mask;
    size_t at = sizeof h;
    int ok = srv_put(buf, &at, cwd);
    for (; ok && argv[h.nargs]; h.nargs++)
        ok = srv_put(buf, &at, argv[h.nargs]);
    for (char **e = environ; ok && e && *e; e++) {
        if (srv_env_now(*e, extra) != *e)
            continue; /* replaced by extra */
        ok = srv_put(buf, &at, *e);
        h.nenv++;
    }
    if (ok && extra) {
        ok = srv_put(buf, &at, extra);
        h.nenv++;
    }
    if (!ok)
        return -1; /* too long for one request: exec */
    memcpy(buf, &h, sizeof h);
    int fds[2] = {out, err};
    char ctl[CMSG_SPACE(sizeof fds)];
    memset(ctl, 0, sizeof ctl);
    struct iovec iov = {buf, at};
    struct msghdr m = {.msg_iov = &iov, .msg_iovlen = 1, .msg_control = ctl,
                       .msg_controllen = sizeof ctl};
    struct cmsghdr *c = CMSG_FIRSTHDR(&m);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof fds);
    memcpy(CMSG_DATA(c), fds, sizeof fds);
    ssize_t n;
    while ((n = sendmsg(srv_fd[which], &m, MSG_NOSIGNAL)) < 0 && errno == EINTR)
        ;
    if (n != (ssize_t)at)
        fail_msg("cannot send a start to the command server: %s", strerror(errno));
    /* replies for earlier children may come first */
    for (;;) {
        srv_reply r;
        while ((n = recv(srv_fd[which], &r, sizeof r, MSG_PEEK)) < 0 && errno == EINTR)
            ;
        if (n == (ssize_t)sizeof r && r.type == SRV_START && r.pid < 0 && r.value == ENOTSUP) {
            /* it will not start commands: exec this one and the next */
            while (recv(srv_fd[which], &r, sizeof r, 0) < 0 && errno == EINTR)
                ;
            srv_refused[which] = 1;
            return -1;
        }
        if (n == (ssize_t)sizeof r && r.type == SRV_START) {
            srv_take(which, 0);
            return r.pid;
        }
        srv_take(which, 0);
    }
}

/* The command exec'd in a fork of this process. */
static pid_t exec_start(const char *const *argv, const char *extra, int out, int err,
                        unsigned long long fsize)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        child_io(out, err, fsize);
        if (extra && putenv((char *)extra) != 0)
            _exit(126);
        execv(argv[0], (char *const *)argv);
        _exit(127);
    }
    return pid;
}

/* Start argv (argv[0] the program) one way or the other. */
static pid_t command_start(const char *const *argv, const char *extra, int out, int err,
                           unsigned long long fsize)
{
    pid_t pid = srv_start(argv, extra, out, err, fsize);
    if (pid < 0)
        pid = exec_start(argv, extra, out, err, fsize);
    if (pid < 0)
        fail_msg("cannot start %s: %s", argv[0], strerror(errno));
    return pid;
}

pid_t support_waitpid(pid_t pid, int *status, int options)
{
    int k = support_server_running() ? srv_kid(pid) : -1;
    if (k < 0)
        return waitpid(pid, status, options);
    while (!srv_kids[k].ended)
        if (!srv_take(srv_kids[k].server, options & WNOHANG))
            return 0;
    *status = srv_kids[k].status;
    srv_kids[k].pid = 0;
    return pid;
}

/* $AABENCH and args (NULL-ended), in a NULL-ended array to free(). */
static const char **command_argv(const char *const *args)
{
    const char *exe = getenv("AABENCH");
    if (!exe || !*exe)
        fail_msg("$AABENCH (the command under test) is not set");
    size_t n = 0;
    while (args[n])
        n++;
    const char **argv = calloc(n + 2, sizeof *argv);
    assert_non_null(argv);
    argv[0] = exe;
    memcpy(argv + 1, args, n * sizeof *argv);
    return argv;
}

/* ---- under ASan: the command in this process ---- */

/* Under ASan a start of the command that the test waits for is a call of
 * cli_main() in the test's own process, where nothing could differ from
 * the command exec'd (srv_same_start, no plug-in): a sanitized exec costs
 * about 0.1 s (the runtime's start, the loader, LeakSanitizer's check at
 * the end) and 1 s more when the command loads the image module, which
 * here is loaded once.  AddressSanitizer and UndefinedBehaviorSanitizer
 * watch the command as they watch the test, and LeakSanitizer's check at
 * the test's end finds what a command lost.  What the command changes in
 * the process is put back: its standard output and error (into a file of
 * its own here), the signal handlers and mask, the warning handler, the
 * folder and the umask.  SIGALRM ends the test if the command runs past
 * the time-out.  The plain build runs every start as a process of its own
 * (a fork of the server, or an exec), and test_cli compares each kind
 * with an exec, so a difference that this path made would show there. */

static int inproc_err = -1;    /* the test's standard error while a command runs */
static char inproc_late[1024]; /* what SIGALRM says then */

static void inproc_on_alarm(int sig)
{
    (void)sig;
    if (write(inproc_err, inproc_late, strlen(inproc_late)) < 0) {
        /* nothing more to say it with */
    }
    _exit(124);
}

/* 1 if t is one of the NULL-ended types. */
static int inproc_type_in(const void *t, const aa_method_type *const *types)
{
    for (size_t k = 0; types[k]; k++)
        if (t == (const void *)types[k])
            return 1;
    return 0;
}

/* 1 if argv (argv[0] the program) may run in this process: besides the
 * start-up, the method table holds the command's own methods only (not
 * those of a plug-in the test loaded) and the locale is the one the test
 * started with. */
static int inproc_usable(const char *const *argv)
{
    if (!SANITIZED || !srv_same_start(NULL) || may_load_plugin(argv))
        return 0;
    for (const void *const *t = aa_method_table(); *t; t++)
        if (!inproc_type_in(*t, aa_method_types) && !inproc_type_in(*t, aa_method_types_optional))
            return 0;
    const char *locale = setlocale(LC_ALL, NULL);
    return locale && strcmp(locale, snap_locale) == 0;
}

const char *support_start_kind(void)
{
    static const char *const none[] = {"aabench", NULL};
    if (inproc_usable(none))
        return "a call of cli_main() in the test's process";
    return support_server_running() ? "a fork of the command server" : NULL;
}

/* Run argv in this process with its output (standard output and error, as
 * through one pipe) into out (cap bytes with the NUL); its exit status. */
static int inproc_run(const char *const *argv, char *out, size_t cap, double limit)
{
    int n = 0;
    while (argv[n])
        n++;
    char **args = calloc((size_t)n + 1, sizeof *args);
    assert_non_null(args);
    memcpy(args, argv, (size_t)n * sizeof *args);
    int fd = memfd_create("aabench-output", MFD_CLOEXEC);
    if (fd < 0)
        fail_msg("memfd_create: %s", strerror(errno));
    char cwd[PATH_MAX];
    assert_non_null(getcwd(cwd, sizeof cwd));
    mode_t mask = umask(0);
    umask(mask);
    sigset_t blocked;
    sigprocmask(SIG_SETMASK, NULL, &blocked);
    static struct sigaction handlers[NSIG];
    for (int sig = 1; sig < NSIG; sig++)
        sigaction(sig, NULL, &handlers[sig]);
    void *warn_ctx;
    aa_warn_fn warn = aa_get_warn(&warn_ctx);

    unsigned pending = alarm(0); /* the test's own alarm, put back after */
    double start = now_seconds();
    fflush(NULL);
    int saved_out = fcntl(1, F_DUPFD_CLOEXEC, 3), saved_err = fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (saved_out < 0 || saved_err < 0 || dup2(fd, 1) < 0 || dup2(fd, 2) < 0)
        fail_msg("cannot send the command's output to a file: %s", strerror(errno));
    inproc_err = saved_err;
    snprintf(inproc_late, sizeof inproc_late,
             "\n%s %s ... (run in the test's process) ran past %g s (AABENCH_TEST_TIMEOUT): the "
             "test is ended\n",
             argv[0], argv[1] ? argv[1] : "", limit);
    struct sigaction al;
    memset(&al, 0, sizeof al);
    al.sa_handler = inproc_on_alarm;
    sigemptyset(&al.sa_mask);
    sigaction(SIGALRM, &al, NULL);
    alarm((unsigned)ceil(limit));
    int code = cli_main(n, args);
    alarm(0);
    fflush(NULL);
    clearerr(stdout);
    clearerr(stderr);
    if (dup2(saved_out, 1) < 0 || dup2(saved_err, 2) < 0)
        abort();
    close(saved_out);
    close(saved_err);
    inproc_err = -1;

    for (int sig = 1; sig < NSIG; sig++)
        sigaction(sig, &handlers[sig], NULL);
    sigprocmask(SIG_SETMASK, &blocked, NULL);
    if (pending) {
        double left = pending - (now_seconds() - start);
        alarm(left >= 1 ? (unsigned)left : 1);
    }
    aa_set_warn(warn, warn_ctx);
    umask(mask);
    char now[PATH_MAX];
    if (getcwd(now, sizeof now) == NULL || strcmp(now, cwd) != 0)
        assert_int_equal(chdir(cwd), 0);
    free(args);

    size_t len = 0;
    if (out && cap > 0) {
        ssize_t got;
        while (len < cap - 1 &&
               (got = pread(fd, out + len, cap - 1 - len, (off_t)len)) != 0) {
            if (got < 0 && errno == EINTR)
                continue;
            assert_true(got > 0);
            len += (size_t)got;
        }
        out[len] = '\0';
    }
    close(fd);
    return code;
}

/* support_aabench_interrupted, with the wait status. */
static int aabench_wait_status(const char *const *args, int interrupt_ms, char *out, size_t cap)
{
    const char *limit_text = getenv("AABENCH_TEST_TIMEOUT");
    double limit = limit_text && atof(limit_text) > 0 ? atof(limit_text) : SUPPORT_TIMEOUT;
    const char **argv = command_argv(args);
    if (interrupt_ms <= 0 && inproc_usable(argv)) {
        int code = inproc_run(argv, out, cap, limit);
        free(argv);
        return code << 8; /* the wait status of exit(code) */
    }
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    double start = now_seconds();
    pid_t pid = command_start(argv, NULL, fds[1], fds[1], 0);
    free(argv);
    close(fds[1]);
    size_t len = 0;
    int open_pipe = 1, interrupted = interrupt_ms <= 0, status = 0, done = 0, timed_out = 0;
    while (!done) {
        double t = now_seconds() - start;
        if (t >= limit) {
            timed_out = 1;
            kill(pid, SIGKILL);
            support_waitpid(pid, &status, 0);
            break;
        }
        if (!interrupted && t * 1000.0 >= interrupt_ms) {
            kill(pid, SIGINT);
            interrupted = 1;
        }
        double next = limit;
        if (!interrupted)
            next = fmin(next, interrupt_ms / 1000.0);
        int wait_ms = (int)ceil(1000.0 * (next - t));
        if (!open_pipe) {
            /* the output is closed: wait for the exit, a little at a time */
            pid_t r = support_waitpid(pid, &status, WNOHANG);
            if (r == pid)
                done = 1;
            else
                poll(NULL, 0, wait_ms < 10 ? wait_ms : 10);
            continue;
        }
        struct pollfd p = {fds[0], POLLIN, 0};
        int ready = poll(&p, 1, wait_ms > 0 ? wait_ms : 0);
        if (ready <= 0)
            continue;
        char chunk[4096];
        ssize_t got = read(fds[0], chunk, sizeof chunk);
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0) {
            open_pipe = 0;
            continue;
        }
        if (out && cap > 1 && len < cap - 1) {
            size_t take = (size_t)got < cap - 1 - len ? (size_t)got : cap - 1 - len;
            memcpy(out + len, chunk, take);
            len += take;
        }
    }
    close(fds[0]);
    if (out && cap > 0)
        out[len] = '\0';
    if (timed_out)
        fail_msg("%s %s ... ran past %g s (AABENCH_TEST_TIMEOUT) and was killed; output: %s",
                 getenv("AABENCH"), args[0] ? args[0] : "", limit, out ? out : "");
    return status;
}

int support_aabench_interrupted(const char *const *args, int interrupt_ms, char *out,
                                size_t cap)
{
    int status = aabench_wait_status(args, interrupt_ms, out, cap);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int support_aabench_wait_status(const char *const *args, char *out, size_t cap)
{
    return aabench_wait_status(args, 0, out, cap);
}

int support_aabench(const char *const *args, char *out, size_t cap)
{
    return support_aabench_interrupted(args, 0, out, cap);
}

pid_t support_aabench_start(const char *const *args, const char *env, int fd_out, int fd_err,
                            unsigned long long fsize)
{
    const char **argv = command_argv(args);
    pid_t pid = command_start(argv, env, fd_out, fd_err, fsize);
    free(argv);
    return pid;
}

pid_t support_aabench_spawn(const char *const *args, const char *env, const char *out,
                            const char *err)
{
    int fo = open(out ? out : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    int fe = open(err ? err : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fo < 0 || fe < 0)
        fail_msg("cannot open %s: %s", fo < 0 ? (out ? out : "/dev/null") : (err ? err : "/dev/null"),
                 strerror(errno));
    pid_t pid = support_aabench_start(args, env, fo, fe, 0);
    close(fo);
    close(fe);
    return pid;
}

int support_wait(pid_t pid)
{
    int status;
    assert_int_equal(support_waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* ---- checks in a child process ---- */

void support_in_child(int (*body)(void *arg), void *arg)
{
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        int failed = body(arg);
        fflush(NULL);
        _exit(failed);
    }
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    if (WIFSIGNALED(status))
        fail_msg("the child was ended by signal %d", WTERMSIG(status));
    if (WEXITSTATUS(status) != 0)
        fail_msg("the child's checks failed (above)");
}

/* ---- temporary folders and files ---- */

int support_tmpdir(char *buf, size_t len, const char *tag)
{
    const char *tmp = getenv("TMPDIR");
    int n = snprintf(buf, len, "%s/aabench-%s-XXXXXX", tmp && *tmp ? tmp : "/tmp", tag);
    if (n < 0 || (size_t)n >= len) {
        errno = ENAMETOOLONG;
        return -1;
    }
    return mkdtemp(buf) ? 0 : -1;
}

int support_rmtree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return -1;
    if (!S_ISDIR(st.st_mode))
        return unlink(path);
    DIR *d = opendir(path);
    if (!d)
        return -1;
    int failed = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        size_t need = strlen(path) + strlen(e->d_name) + 2;
        char *sub = malloc(need);
        if (!sub) {
            failed = 1;
            break;
        }
        snprintf(sub, need, "%s/%s", path, e->d_name);
        failed |= support_rmtree(sub) != 0;
        free(sub);
    }
    closedir(d);
    return rmdir(path) != 0 || failed ? -1 : 0;
}

void support_write_file(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        fail_msg("cannot write %s: %s", path, strerror(errno));
    assert_int_equal(fwrite(data, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

char *support_read_file(const char *path, char *buf, size_t cap, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot read %s: %s", path, strerror(errno));
    size_t n = fread(buf, 1, cap - 1, f);
    int more = fgetc(f) != EOF;
    fclose(f);
    if (more)
        fail_msg("%s is larger than the %zu bytes read", path, cap - 1);
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

void support_cache_file(const char *dir, char *path, size_t len)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        fail_msg("cannot read the cache folder %s: %s", dir, strerror(errno));
    int found = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        size_t n = strlen(e->d_name);
        if (strncmp(e->d_name, "ref-", 4) == 0 && n > 8 && strcmp(e->d_name + n - 4, ".bin") == 0) {
            snprintf(path, len, "%s/%s", dir, e->d_name);
            found++;
        }
    }
    closedir(d);
    if (found != 1)
        fail_msg("%d reference cache files in %s, expected one", found, dir);
}

int support_count_entries(const char *dir, const char *except)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..") &&
             !(except && !strcmp(e->d_name, except));
    closedir(d);
    return n;
}

int support_teardown_dir(void **state)
{
    return *state && support_rmtree(*state) == 0 ? 0 : -1;
}
