/*
 * support.c: helpers shared by the tests (support.h).
 */
#define _GNU_SOURCE /* pipe2 */

#include "support.h"
#include "path.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

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

aa_scene *support_scene_part(const aa_scene *s, int sw, int sh, int x0, int y0, int w, int h)
{
    aa_scene *part = aa_scene_transform(s, (double)sw / w, (double)sh / h, -(double)x0 / w,
                                        -(double)y0 / h);
    assert_non_null(part);
    return part;
}

void support_reference_part(const aa_scene *s, int sw, int sh, int x0, int y0, int w, int h,
                            const char *filter, aa_image *out, aa_image *bound,
                            aa_truth_stats *stats)
{
    aa_scene *part = support_scene_part(s, sw, sh, x0, y0, w, h);
    support_view v = {w, h, 0, 0, 0, filter, 1, 1, 0};
    support_reference(part, &v, out, bound, stats);
    aa_scene_free(part);
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

/* ---- plane geometry for the stroke tests' closed forms ---- */

double support_shoelace(const double *xy, int n)
{
    double a = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        a += xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1];
    }
    return 0.5 * a;
}

void support_line_meet(const double p[2], const double d[2], const double q[2],
                       const double e[2], double out[2])
{
    double den = d[0] * e[1] - d[1] * e[0];
    double s = ((q[0] - p[0]) * e[1] - (q[1] - p[1]) * e[0]) / den;
    out[0] = p[0] + s * d[0];
    out[1] = p[1] + s * d[1];
}

double support_fill_area(const aa_path *p)
{
    aa_scene *s = aa_scene_new((aa_rgb){{0, 0, 0}});
    assert_non_null(s);
    if (aa_scene_layer(s, (aa_rgb){{1, 1, 1}}, AA_FILL_NONZERO) || aa_path_fill(p, NULL, s) ||
        aa_scene_finish(s))
        fail_msg("%s", aa_last_error());
    support_view v = {.w = 64, .h = 64, .threads = 1};
    aa_image im;
    support_reference(s, &v, &im, NULL, NULL);
    double area = support_channel_mean(&im, 0);
    aa_image_free(&im);
    aa_scene_free(s);
    return area;
}

aa_scene *support_svg_scene(const char *dir, const char *name, const char *body, int w, int h)
{
    char path[4200], doc[8192], spec[4400];
    snprintf(path, sizeof path, "%s/%s.svg", dir, name);
    int n = snprintf(doc, sizeof doc,
                     "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">%s"
                     "</svg>",
                     w, h, body);
    assert_true(n > 0 && (size_t)n < sizeof doc);
    support_write_file(path, doc, strlen(doc));
    snprintf(spec, sizeof spec, "svg:file=%s", path);
    aa_spec sp;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &sp) != AA_OK || aa_pattern_scene_at(&sp, w, h, &sc) != AA_OK)
        fail_msg("%s: %s", body, aa_last_error());
    return sc;
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

/* $AABENCH and args (NULL-ended), then from argv[n + 2] on the
 * environment with `env` (NAME=value, may be NULL) in place of that name
 * or added; one array to free(). */
static const char **command_argv(const char *const *args, const char *env, char ***envp)
{
    const char *exe = getenv("AABENCH");
    if (!exe || !*exe)
        fail_msg("$AABENCH (the command under test) is not set");
    size_t n = 0, ne = 0, name = env ? strcspn(env, "=") + 1 : 0;
    while (args[n])
        n++;
    while (environ[ne])
        ne++;
    const char **argv = calloc(n + ne + 4, sizeof *argv), **e = argv + n + 2;
    assert_non_null(argv);
    argv[0] = exe;
    memcpy(argv + 1, args, n * sizeof *argv);
    for (size_t k = 0; k < ne; k++)
        if (!env || strncmp(environ[k], env, name) != 0)
            *e++ = environ[k];
    *e = env;
    *envp = (char **)(argv + n + 2);
    return argv;
}

pid_t support_aabench_start(const char *const *args, const char *env, int fd_out, int fd_err,
                            unsigned long long fsize)
{
    char **envp;
    const char **argv = command_argv(args, env, &envp);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        /* the child: calls that are safe after a fork only, then the exec */
        struct rlimit r = {(rlim_t)fsize, (rlim_t)fsize};
        if (fsize > 0 && (signal(SIGXFSZ, SIG_IGN) == SIG_ERR || setrlimit(RLIMIT_FSIZE, &r)))
            _exit(126);
        if (dup2(fd_out, 1) < 0 || dup2(fd_err, 2) < 0)
            _exit(126);
        execve(argv[0], (char *const *)argv, envp);
        _exit(127);
    }
    if (pid < 0)
        fail_msg("cannot start %s: %s", argv[0], strerror(errno));
    free(argv);
    return pid;
}

pid_t support_aabench_spawn(const char *const *args, const char *env, const char *out,
                            const char *err)
{
    const char *names[2] = {out ? out : "/dev/null", err ? err : "/dev/null"};
    int fd[2];
    for (int k = 0; k < 2; k++)
        if ((fd[k] = open(names[k], O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)) < 0)
            fail_msg("cannot open %s: %s", names[k], strerror(errno));
    pid_t pid = support_aabench_start(args, env, fd[0], fd[1], 0);
    close(fd[0]);
    close(fd[1]);
    return pid;
}

pid_t support_waitpid(pid_t pid, int *status, int options)
{
    pid_t r;
    while ((r = waitpid(pid, status, options)) < 0 && errno == EINTR)
        ;
    return r;
}

int support_wait(pid_t pid)
{
    int status;
    assert_int_equal(support_waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* support_aabench_interrupted, with the wait status. */
static int aabench_wait_status(const char *const *args, int interrupt_ms, char *out, size_t cap)
{
    const char *limit_text = getenv("AABENCH_TEST_TIMEOUT");
    double limit = limit_text && atof(limit_text) > 0 ? atof(limit_text) : SUPPORT_TIMEOUT;
    int fds[2];
    assert_int_equal(pipe2(fds, O_CLOEXEC), 0);
    double start = now_seconds();
    pid_t pid = support_aabench_start(args, NULL, fds[1], fds[1], 0);
    close(fds[1]);
    size_t len = 0;
    int interrupted = interrupt_ms <= 0, status = 0, open_pipe = 1;
    /* its output until it closes, then its end; SIGINT after interrupt_ms,
     * SIGKILL after the time-out */
    for (;;) {
        double t = now_seconds() - start;
        if (t >= limit) {
            kill(pid, SIGKILL);
            support_waitpid(pid, &status, 0);
            if (out && cap > 0)
                out[len] = '\0';
            fail_msg("%s %s ... ran past %g s (AABENCH_TEST_TIMEOUT) and was killed; output: %s",
                     getenv("AABENCH"), args[0] ? args[0] : "", limit, out ? out : "");
        }
        if (!interrupted && t * 1000.0 >= interrupt_ms) {
            kill(pid, SIGINT);
            interrupted = 1;
        }
        if (!open_pipe) { /* a child of the command may hold the output */
            if (support_waitpid(pid, &status, WNOHANG) == pid)
                break;
            poll(NULL, 0, 5);
            continue;
        }
        double next = interrupted ? limit : fmin(limit, interrupt_ms / 1000.0);
        struct pollfd p = {fds[0], POLLIN, 0};
        char chunk[4096];
        ssize_t got = poll(&p, 1, (int)ceil(1000.0 * (next - t))) > 0
                          ? read(fds[0], chunk, sizeof chunk) : -1;
        open_pipe = got != 0;
        if (got > 0 && out && cap > 1 && len < cap - 1) {
            size_t take = (size_t)got < cap - 1 - len ? (size_t)got : cap - 1 - len;
            memcpy(out + len, chunk, take);
            len += take;
        }
    }
    close(fds[0]);
    if (out && cap > 0)
        out[len] = '\0';
    return status;
}

int support_aabench_wait_status(const char *const *args, char *out, size_t cap)
{
    return aabench_wait_status(args, 0, out, cap);
}

int support_aabench_interrupted(const char *const *args, int interrupt_ms, char *out,
                                size_t cap)
{
    int status = aabench_wait_status(args, interrupt_ms, out, cap);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int support_aabench(const char *const *args, char *out, size_t cap)
{
    return support_aabench_interrupted(args, 0, out, cap);
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
    int code = support_wait(pid);
    if (code > 128)
        fail_msg("the child was ended by signal %d", code - 128);
    if (code != 0)
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

/* ---- text written piece by piece ---- */

int support_put(support_text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int m = vsnprintf(t->buf + t->n, sizeof t->buf - t->n, fmt, ap);
    va_end(ap);
    assert_true(m >= 0 && (size_t)m < sizeof t->buf - t->n);
    t->n += (size_t)m;
    return AA_OK;
}

int support_put_move(void *ctx, double x, double y)
{
    return support_put(ctx, " M %.17g %.17g", x, y);
}

int support_put_line(void *ctx, double x, double y)
{
    return support_put(ctx, " L %.17g %.17g", x, y);
}

int support_put_quad(void *ctx, double cx, double cy, double x, double y)
{
    return support_put(ctx, " Q %.17g %.17g %.17g %.17g", cx, cy, x, y);
}

int support_put_cubic(void *ctx, double ax, double ay, double bx, double by, double x, double y)
{
    return support_put(ctx, " C %.17g %.17g %.17g %.17g %.17g %.17g", ax, ay, bx, by, x, y);
}

int support_put_close(void *ctx)
{
    return support_put(ctx, " Z");
}

int support_names(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = strstr(list, name); s; s = strstr(s + 1, name))
        if ((s == list || s[-1] == ' ') && (s[n] == '\0' || s[n] == ' '))
            return 1;
    return 0;
}

/* ---- random numbers ---- */

double support_xorshift(uint64_t *s)
{
    *s ^= *s << 13, *s ^= *s >> 7, *s ^= *s << 17;
    return (double)(*s >> 11) * 0x1p-53;
}

double support_uniform(uint64_t *s, double a, double b)
{
    return a + (b - a) * support_xorshift(s);
}

/* ---- the point-in-stroke check ---- */

void support_stroke_check(const char *what, const aa_scene *s, const double box[4], double h,
                          const double *m, int npts, uint64_t *rng,
                          support_distance_fn distance, const void *ctx)
{
    int tested = 0, inside = 0, wrong = 0;
    for (int i = 0; i < npts; i++) {
        double px = support_uniform(rng, box[0], box[2]), py = support_uniform(rng, box[1], box[3]);
        int unsure = 0;
        double d = distance(ctx, px, py, &unsure);
        if (unsure || fabs(d - h) < 1e-7)
            continue;
        double qx = px, qy = py;
        if (m)
            qx = m[0] * px + m[2] * py + m[4], qy = m[1] * px + m[3] * py + m[5];
        int want = d <= h, got = aa_scene_colour_at(s, qx, qy).c[0] > 0.5;
        tested++;
        inside += want;
        if (want != got && wrong++ < 5)
            print_message("%s: (%.17g, %.17g) distance %.17g, h %g: stroke says %d\n", what,
                          px, py, d, h, got);
    }
    print_message("%-40s %d points (%d inside), %d wrong\n", what, tested, inside, wrong);
    assert_int_equal(wrong, 0);
    assert_true(inside > tested / 20 && inside < tested);
}

void support_reference_mode(const aa_scene *s, int w, int h, const char *filter, int mode,
                            aa_image *img, aa_image *bound)
{
    aa_filter f;
    aa_truth_stats st;
    assert_int_equal(aa_filter_parse(filter, &f), AA_OK);
    assert_int_equal(aa_image_alloc(img, w, h, 3), AA_OK);
    assert_int_equal(aa_image_alloc(bound, w, h, 1), AA_OK);
    if (aa__truth_render_mode(s, &f, 0, mode, img, bound, &st, NULL))
        fail_msg("reference under %s: %s", filter, aa_last_error());
    assert_true(st.max_bound <= AA_TRUTH_BOUND);
}

void support_check_value(const char *what, const char *filter, int i, int j, double got, double b,
                         double want, double err, double *worst)
{
    double d = fabs(got - want);
    if (!(d <= b + err))
        fail_msg("%s under %s, pixel (%d, %d): reference %.17g, expected %.17g (bound %.2e, "
                 "answer's error %.2e)",
                 what, filter, i, j, got, want, b, err);
    *worst = fmax(*worst, d);
}

double support_within_reference(const char *what, const char *filter, const aa_image *got,
                                const aa_image *r, double tol)
{
    double worst = 0.0;
    size_t n = (size_t)got->w * got->h * 3;
    for (size_t k = 0; k < n; k++) {
        double d = fabs(got->v[k] - r->v[k]);
        if (!(d <= tol))
            fail_msg("%s %dx%d under %s: pixel (%zu, %zu) channel %zu: %.17g, reference %.17g",
                     what, got->w, got->h, filter, k / 3 % (size_t)got->w,
                     k / 3 / (size_t)got->w, k % 3, got->v[k], r->v[k]);
        worst = fmax(worst, d);
    }
    return worst;
}

double support_method_against_reference(const char *method, const char *what, const aa_scene *s,
                                        int w, int h, const char *filter)
{
    aa_image a, a1, r;
    support_render(method, s, filter, w, h, 2, &a, NULL);
    support_render(method, s, filter, w, h, 1, &a1, NULL);
    support_reference(s, &(support_view){.w = w, .h = h, .filter = filter, .threads = 2}, &r,
                      NULL, NULL);
    double worst = support_within_reference(what, filter, &a, &r, 1e-12);
    if (!support_same_image(&a, &a1))
        fail_msg("%s under %s: %s on 1 and 2 threads differ", what, filter, method);
    print_message("%-22s %dx%-4d %-18s largest difference %.1e\n", what, w, h, filter, worst);
    aa_image_free(&a);
    aa_image_free(&a1);
    aa_image_free(&r);
    return worst;
}

double support_method_against_part(const char *method, const char *what, const aa_scene *s,
                                   int sw, int sh, int x0, int y0, int w, int h,
                                   const char *filter)
{
    aa_scene *part = support_scene_part(s, sw, sh, x0, y0, w, h);
    char name[128];
    snprintf(name, sizeof name, "%s, [%d, %d) x [%d, %d)", what, x0, x0 + w, y0, y0 + h);
    double worst = support_method_against_reference(method, name, part, w, h, filter);
    aa_scene_free(part);
    return worst;
}

double support_method_against_filters(const char *method, const char *what, const aa_scene *s,
                                      int w, int h, const char *const *fl)
{
    double worst = 0.0;
    for (; *fl; fl++)
        worst = fmax(worst, support_method_against_reference(method, what, s, w, h, *fl));
    print_message("%-28s largest difference over the filters %.1e\n", what, worst);
    return worst;
}

int support_lib_run(const char *const *args, const char *cache, size_t *failed)
{
    int argc = 0, asked;
    while (args[argc])
        argc++;
    aa_plan plan;
    aa_run_options opt;
    aa_runfolder *rf = NULL;
    aa_plan_default(&plan);
    aa_run_options_default(&opt);
    if (cache)
        opt.cache = cache;
    if (failed)
        *failed = 0;
    int st = aa_plan_parse(argc, (char *const *)args, &plan, &opt, &asked);
    if (!st && !(st = aa_runfolder_create(&plan, &opt, &rf)) && !(st = aa_runfolder_run(rf)))
        st = aa_runfolder_finish(rf);
    if (rf && failed) {
        size_t n;
        const aa_row *rows = aa_runfolder_rows(rf, &n);
        for (size_t k = 0; k < n; k++)
            *failed += rows[k].failed != 0;
    }
    aa_runfolder_free(rf);
    return st;
}
