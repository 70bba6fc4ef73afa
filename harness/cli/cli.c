/*
 * cli.c: helpers shared by the subcommands.
 */
#include "cli.h"

#include <signal.h>

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_fail(const char *cmd, int status)
{
    fprintf(stderr, "aabench %s: %s\n", cmd, aa_last_error());
    return aa_exit_code(status);
}

int cli_bad_option(const char *cmd, int c, char *const argv[])
{
    const char *arg = argv[optind - 1];
    if (c == ':')
        fprintf(stderr, "aabench %s: option %s needs a value\n", cmd, aa_echo(arg));
    else if (optopt)
        fprintf(stderr, "aabench %s: unknown option -%s\n", cmd,
                aa_echo((char[]){(char)optopt, 0}));
    else
        fprintf(stderr, "aabench %s: unknown option %s\n", cmd, aa_echo(arg));
    fprintf(stderr, "Try 'aabench %s --help'.\n", cmd);
    return 2;
}

int cli_bad_usage(const char *cmd, int status)
{
    fprintf(stderr, "aabench %s: %s\nTry 'aabench %s --help'.\n", cmd, aa_last_error(), cmd);
    return aa_exit_code(status);
}

int cli_out_threads(int c, const char *arg, const char **out, int *threads)
{
    if (c == CLI_O_OUT) {
        *out = arg;
        return AA_OK;
    }
    return aa_parse_threads(arg, threads);
}

void cli_getopt_reset(void)
{
    optind = 0; /* glibc: full reinitialisation */
    opterr = 0;
}

/* The folder of `path` exists and can be written. */
static int check_folder(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (slash) {
        size_t n = (size_t)(slash - path);
        if (n >= sizeof dir)
            return aa_fail(AA_EINVAL, "output \"%s\": path too long (%zu characters, at most %zu)",
                           aa_echo(path), strlen(path), sizeof dir - 1);
        memcpy(dir, path, n);
        dir[n] = '\0';
        if (n == 0)
            strcpy(dir, "/");
    } else {
        strcpy(dir, ".");
    }
    struct stat sb;
    if (stat(dir, &sb) != 0)
        return aa_fail(AA_EIO, "output \"%s\": folder %s %s", aa_echo(path), aa_echo(dir),
                       errno == ENOENT ? "does not exist" : strerror(errno));
    if (!S_ISDIR(sb.st_mode))
        return aa_fail(AA_EIO, "output \"%s\": %s is a file, not a folder", aa_echo(path),
                       aa_echo(dir));
    /* Try it: access() says yes to root on a read-only file system, and
     * nothing short of making a file tells a full one. */
    char probe[4096];
    int st = aa_temp_name(path, probe, sizeof probe);
    if (st)
        return st;
    int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0)
        return aa_fail(AA_EIO, "output \"%s\": cannot write in folder %s: %s", aa_echo(path),
                       aa_echo(dir), strerror(errno));
    close(fd);
    unlink(probe);
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return aa_fail(AA_EIO, "output \"%s\" is a folder, not a file", aa_echo(path));
    return AA_OK;
}

int cli_view_size(const char *size, const aa_spec *pattern, int *w, int *h)
{
    return size ? aa_size_parse(size, w, h) : aa_pattern_own_size(pattern, w, h);
}

int cli_check_output(const char *path)
{
    if (!path || !*path)
        return aa_fail(AA_EINVAL, "no output file given (-o FILE)");
    if (!aa_image_ext_known(path))
        return aa_fail(AA_EINVAL,
                       "output \"%s\": unknown image type (use .exr, .tif, .png, .pfm or .txt)",
                       aa_echo(path));
    return check_folder(path);
}

int cli_check_output_file(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    if (n <= e || strcmp(path + n - e, ext) != 0)
        return aa_fail(AA_EINVAL, "output \"%s\" must end in %s", aa_echo(path), ext);
    return check_folder(path);
}

void cli_json_string(const char *text, char *buf, size_t len)
{
    size_t n = 0;
    if (len < 3) {
        if (len)
            buf[0] = '\0';
        return;
    }
    buf[n++] = '"';
    for (const unsigned char *c = (const unsigned char *)text; *c && n + 8 < len; c++) {
        if (*c == '"' || *c == '\\') {
            buf[n++] = '\\';
            buf[n++] = (char)*c;
        } else if (*c < 0x20) {
            n += (size_t)snprintf(buf + n, len - n, "\\u%04x", *c);
        } else {
            buf[n++] = (char)*c;
        }
    }
    buf[n++] = '"';
    buf[n] = '\0';
}

const char *cli_cache_dir(void)
{
    return aa_cache_dir_default();
}

int cli_cache_writable(const char *dir)
{
    char probe[4200], tmp[4400];
    int st = aa_mkdirs(dir);
    if (!st && !(st = aa_pathf(probe, sizeof probe, "%s/probe", dir)) &&
        !(st = aa_temp_name(probe, tmp, sizeof tmp))) {
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0)
            st = aa_fail(AA_EIO, "cannot create a file in it: %s", strerror(errno));
        else {
            close(fd);
            unlink(tmp);
        }
    }
    return st;
}

void cli_cache_usable(const char *cmd, const char *dir)
{
    if (dir && *dir && cli_cache_writable(dir))
        fprintf(stderr,
                "aabench %s: warning: the reference cache %s cannot be written (%s): every "
                "reference not in it is computed and not kept\n",
                cmd, aa_echo(dir), aa_last_error());
}

int cli_progress_wanted(void)
{
    const char *ci = getenv("CI");
    return isatty(2) && !(ci && *ci && strcmp(ci, "false") != 0);
}

void cli_warn(const char *message, void *ctx)
{
    (void)ctx;
    fprintf(stderr, "aabench: warning: %s\n", message);
}

static void on_signal(int sig)
{
    (void)sig;
    aa_temp_cleanup();
    _exit(130);
}

void cli_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

int cli_stage(cli_outputs *o, const char *path, const char **tmp)
{
    if (o->n >= CLI_MAX_OUTPUTS)
        return aa_fail(AA_EFAIL, "too many outputs");
    int st = aa_temp_name(path, o->tmp[o->n], sizeof o->tmp[o->n]);
    if (st)
        return st;
    o->path[o->n] = path;
    *tmp = o->tmp[o->n++];
    return AA_OK;
}

void cli_discard(cli_outputs *o)
{
    for (int k = 0; k < o->n; k++)
        unlink(o->tmp[k]);
    o->n = 0;
}

int cli_commit(cli_outputs *o)
{
    for (int k = 0; k < o->n; k++)
        if (rename(o->tmp[k], o->path[k]) != 0) {
            int err = errno;
            for (int q = k; q < o->n; q++)
                unlink(o->tmp[q]);
            o->n = 0;
            return aa_fail(AA_EIO, "%s: cannot rename into place: %s", o->path[k],
                           strerror(err));
        }
    o->n = 0;
    return AA_OK;
}

/* ---- the command line and timing, for the results ---- */

static int whole_argc;
static const char *const *whole_argv;

void cli__set_command_line(int argc, char **argv)
{
    whole_argc = argc;
    whole_argv = (const char *const *)argv;
}

void cli_command_line(int *argc, const char *const **argv)
{
    *argc = whole_argc;
    *argv = whole_argv;
}

void cli_time_text(const aa_row *r, char *buf, size_t len)
{
    const aa_timing *t = &r->timing;
    char ci[64] = "";
    if (t->n > 0)
        aa_timing_ci_text(t, ci, sizeof ci);
    snprintf(buf, len, "%.3f%s%s%s", r->seconds * 1e3, *ci ? " " : "", ci, t->noisy ? " *" : "");
}

size_t cli_warn_noisy(const char *cmd, const aa_row *rows, size_t n)
{
    size_t noisy = 0;
    for (size_t k = 0; k < n; k++)
        noisy += rows[k].ok && rows[k].timing.noisy;
    if (!noisy)
        return 0;
    fflush(stdout); /* after the table, not inside it */
    fprintf(stderr,
            "aabench %s: warning: %zu of %zu timings are noisy (marked * and noisy = 1 in "
            "the results; 'ci': the CI target was not met, 'outliers': renders beyond 3 "
            "MADs moved the median by more than the target, 'busy': other processes used the "
            "cores, 'steal': the hypervisor took time, 'preempted': wall time well above CPU "
            "time). Compare them with care, and see \"A quiet measurement\" in "
            "harness/bench/README.md:\n",
            cmd, noisy, n);
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = &rows[k];
        if (!r->ok || !r->timing.noisy)
            continue;
        char why[128], ci[64], others[32] = "an unknown number of";
        aa_noisy_text(r->timing.noisy, why, sizeof why);
        aa_timing_ci_text(&r->timing, ci, sizeof ci);
        if (isfinite(r->timing.others_cores))
            snprintf(others, sizeof others, "%.2f", r->timing.others_cores);
        fprintf(stderr, "  %s on %s %dx%d %s, %d thread%s: %s (%s%s, %zu outliers of %d, "
                        "others used %s cores)\n",
                r->method, r->pattern, r->w, r->h, r->filter, r->threads,
                r->threads == 1 ? "" : "s", why, isfinite(r->timing.ci_rel) ? "CI " : "", ci,
                r->timing.stats.outliers, r->timing.n, others);
    }
    return noisy;
}

size_t cli_warn_references(const char *cmd, const aa_row *rows, size_t n)
{
    size_t views = 0;
    for (size_t k = 0; k < n; k++) {
        const aa_row *r = &rows[k];
        if (!aa_row_reference_unproven(rows, k))
            continue;
        if (!views++)
            fflush(stdout);
        fprintf(stderr,
                "aabench %s: warning: the reference of %s %dx%d %s is not proven everywhere: "
                "%.0f pixel%s bounded by an estimate, not a proof (where gradients of different "
                "t mix), its largest bound %.2g (the promise is %.0e): errors below that are not "
                "resolved (ref_scanned and ref_bound in the results)\n",
                cmd, r->pattern, r->w, r->h, r->filter, r->ref_scanned,
                r->ref_scanned == 1 ? "" : "s", r->ref_bound, AA_TRUTH_BOUND);
    }
    return views;
}

int cli_warn_parallelism(const char *cmd, const aa_row *rows, size_t n)
{
    size_t lo, hi;
    double ratio = aa_rows_parallelism(rows, n, &lo, &hi);
    if (!(ratio > AA_PARALLELISM_FACTOR))
        return 0;
    fflush(stdout);
    fprintf(stderr,
            "aabench %s: warning: the methods ran with different effective parallelism (CPU "
            "time / wall time), %.2f for %s on %s %dx%d %s (%d thread%s) to %.2f for %s on %s "
            "%dx%d %s (%d thread%s), %.1fx apart (more than %.1fx): their wall times are not a "
            "fair comparison as they stand (see the thr and cpu ms columns)\n",
            cmd, rows[lo].timing.cpu_share, rows[lo].method, rows[lo].pattern, rows[lo].w,
            rows[lo].h, rows[lo].filter, rows[lo].threads, rows[lo].threads == 1 ? "" : "s",
            rows[hi].timing.cpu_share, rows[hi].method, rows[hi].pattern, rows[hi].w, rows[hi].h,
            rows[hi].filter, rows[hi].threads, rows[hi].threads == 1 ? "" : "s", ratio,
            AA_PARALLELISM_FACTOR);
    return 1;
}
