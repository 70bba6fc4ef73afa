/*
 * test_image_faults.c: image files when the machine goes wrong.
 *
 *  - A full disk: every writer (the formats through OpenImageIO, .txt,
 *    .pfm, montages written a row at a time, aa_file_write_atomic, and the
 *    commands `truth` and `run`) fails with AA_EIO, exit status 3, leaves the
 *    previous file byte for byte and no temporary file (".aa-...").  A full
 *    disk is made without root with RLIMIT_FSIZE and SIGXFSZ ignored, in a
 *    child: writes past the limit fail with EFBIG, as they would with
 *    ENOSPC; limits just below the whole file's size reach the last write
 *    and the close.  Where tmpfs can be mounted, a really full one too.
 *  - Files cut short, or holding garbage after a valid header, are refused
 *    naming the file: by the library (AA_EIO) at every length tried, the
 *    TIFF reader's true return for missing strips and a PNG whose IEND
 *    chunk is missing included; by `compare` (exit status 3) once.
 *  - Loading and using OpenImageIO under an address-space limit
 *    (RLIMIT_AS) ends with a message and status 2 or 3, never a signal,
 *    whatever the limit.
 *  - Memory is counted before work: `compare` of files whose headers claim
 *    huge images is refused (status 2) from the headers, with what it needs
 *    and the limit, whether the limit is the machine, RLIMIT_AS,
 *    RLIMIT_DATA or a cgroup; `run` refuses a montage that cannot be made
 *    before it runs anything; a montage is made a row of tiles at a time.
 *  - NaN and infinities in files read by `compare` are counted, not refused;
 *    --json never prints a NaN or an infinity, and images that differ never
 *    get the identical images' PSNR; a .txt holding NaN is refused naming
 *    the file and the pixel.
 *
 * The command is $AABENCH (scripts/run-tests.sh).  Known answers are worked
 * out here from the definitions (sRGB, the montage's layout, the error
 * sums), never taken from the code under test.
 */
/* tier: full */
#define _XOPEN_SOURCE 700 /* nftw */

#include "bench.h"
#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

/* ------------------------------------------------------------------------
 * The test folder, files, and the command
 * ------------------------------------------------------------------------ */

static char top[PATH_MAX];

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static int group_setup(void **state)
{
    (void)state;
    const char *tmp = getenv("TMPDIR");
    snprintf(top, sizeof top, "%s/aabench-image-faults-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (mkdtemp(top) == NULL)
        return -1;
    /* OpenImageIO's module loaded here, once (asking for the size of an
     * .exr that is not there loads it, then fails): the children of the
     * full-disk tests (support_in_child) are forks of this process and
     * use it as loaded, where each loaded it again, 0.9 s of CPU (1.6 s
     * sanitized) a child.  Loading writes no file, so what they test
     * under RLIMIT_FSIZE is the same. */
    char none[PATH_MAX + 32];
    int w, h, c;
    snprintf(none, sizeof none, "%s/none.exr", top);
    if (aa_image_file_size(none, &w, &h, &c) == AA_OK)
        return -1;
    return 0;
}

static int group_teardown(void **state)
{
    (void)state;
    return nftw(top, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

/* A fresh folder under top for one test. */
static const char *fresh(const char *name, char *buf, size_t len)
{
    if (snprintf(buf, len, "%s/%s", top, name) >= (int)len)
        fail_msg("path too long: %s/%s", top, name);
    assert_int_equal(mkdir(buf, 0777), 0);
    return buf;
}

static char *join(char *buf, size_t len, const char *dir, const char *name)
{
    if (snprintf(buf, len, "%s/%s", dir, name) >= (int)len)
        fail_msg("path too long: %s/%s", dir, name);
    return buf;
}

/* A fresh folder `name` (see fresh) and the paths of files in it: pairs
 * of a buffer of PATH_MAX + 32 bytes and a file name, then NULL. */
static void fresh_files(const char *name, ...)
{
    char dir[PATH_MAX];
    fresh(name, dir, sizeof dir);
    va_list ap;
    va_start(ap, name);
    for (char *buf; (buf = va_arg(ap, char *)) != NULL;)
        join(buf, PATH_MAX + 32, dir, va_arg(ap, const char *));
    va_end(ap);
}

/* dir/STEM.EXT (ext with its dot) into buf. */
static char *join_ext(char *buf, size_t len, const char *dir, const char *stem, const char *ext)
{
    char name[32];
    snprintf(name, sizeof name, "%s%s", stem, ext);
    return join(buf, len, dir, name);
}

static int temporaries;

static int count_temp(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag;
    if (strncmp(path + ftw->base, ".aa-", 4) == 0) {
        print_error("temporary file left behind: %s\n", path);
        temporaries++;
    }
    return 0;
}

/* Temporary files (".aa-...") anywhere under dir. */
static int temporaries_in(const char *dir)
{
    temporaries = 0;
    nftw(dir, count_temp, 16, FTW_PHYS);
    return temporaries;
}

/* The whole file, malloc'd; *len its size. */
static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        fail_msg("cannot open %s: %s", path, strerror(errno));
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    long n = ftell(f);
    assert_true(n >= 0);
    rewind(f);
    unsigned char *b = malloc((size_t)n + 1);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return b;
}

static void spill(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

static int same_as(const char *path, const unsigned char *data, size_t len)
{
    size_t n;
    unsigned char *b = slurp(path, &n);
    int same = n == len && memcmp(b, data, len) == 0;
    free(b);
    return same;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* How the command is run. */
typedef struct limits {
    rlim_t fsize; /* RLIMIT_FSIZE, with SIGXFSZ ignored; 0: none */
    rlim_t as;    /* RLIMIT_AS; 0: none */
    rlim_t data;  /* RLIMIT_DATA; 0: none */
    const char *cgroup_procs; /* join this cgroup first; NULL: stay */
} limits;

static char output[16384];

static void set_limit(int which, rlim_t v)
{
    struct rlimit r = {v, v};
    if (v != 0 && setrlimit(which, &r) != 0)
        _exit(126);
}

/* Run $AABENCH with args (NULL-terminated) under `lim` (may be NULL);
 * stdout and stderr go through a pipe (not a file: RLIMIT_FSIZE must not
 * stop them) into `output`.  The wait status.  Under a limit on memory or
 * in a cgroup the command is exec'd here, so that its start-up (the
 * loader, the image module's trial load) meets the limit; otherwise it
 * starts as every test starts it (support_aabench, or with a file size
 * limit support_aabench_start). */
static int run_cmd(const limits *lim, const char *const *args)
{
    const char *exe = getenv("AABENCH");
    if (exe == NULL || *exe == '\0')
        fail_msg("AABENCH is not set (scripts/run-tests.sh sets it)");
    if (lim == NULL)
        return support_aabench_wait_status(args, output, sizeof output);
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    pid_t pid;
    if (lim->as == 0 && lim->data == 0 && lim->cgroup_procs == NULL) {
        pid = support_aabench_start(args, NULL, fds[1], fds[1], lim->fsize);
    } else {
        const char *argv[40] = {exe};
        size_t n = 0;
        for (; args[n]; n++) {
            assert_true(n + 2 < sizeof argv / sizeof *argv);
            argv[n + 1] = args[n];
        }
        fflush(NULL);
        pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            close(fds[0]);
            dup2(fds[1], 1);
            dup2(fds[1], 2);
            if (lim->cgroup_procs != NULL) {
                FILE *f = fopen(lim->cgroup_procs, "w");
                if (f == NULL || fprintf(f, "%ld\n", (long)getpid()) < 0 || fclose(f) != 0)
                    _exit(125);
            }
            if (lim->fsize != 0)
                signal(SIGXFSZ, SIG_IGN);
            set_limit(RLIMIT_FSIZE, lim->fsize);
            set_limit(RLIMIT_AS, lim->as);
            set_limit(RLIMIT_DATA, lim->data);
            execv(exe, (char *const *)argv);
            _exit(127);
        }
    }
    close(fds[1]);
    size_t n = 0;
    ssize_t k;
    char sink[4096];
    while ((k = read(fds[0], n < sizeof output - 1 ? output + n : sink,
                     n < sizeof output - 1 ? sizeof output - 1 - n : sizeof sink)) != 0) {
        if (k < 0 && errno == EINTR)
            continue;
        assert_true(k > 0);
        if (n < sizeof output - 1)
            n += (size_t)k;
    }
    output[n] = '\0';
    close(fds[0]);
    int status;
    assert_int_equal(support_waitpid(pid, &status, 0), pid);
    return status;
}

/* The status is exit `code`, else fail saying what happened. */
static void expect_exit(int status, int code, const char *what)
{
    if (WIFEXITED(status) && WEXITSTATUS(status) == code)
        return;
    if (WIFSIGNALED(status))
        fail_msg("%s: ended by signal %d, expected exit %d; output:\n%s", what, WTERMSIG(status),
                 code, output);
    fail_msg("%s: exit %d, expected %d; output:\n%s", what, WEXITSTATUS(status), code, output);
}

static void expect_output(const char *text, const char *what)
{
    if (strstr(output, text) == NULL)
        fail_msg("%s: the output lacks \"%s\":\n%s", what, text, output);
}

/* Pseudo-random values in [0, 1) (Numerical Recipes' LCG). */
static void fill_random(aa_image *im, uint32_t seed)
{
    uint32_t x = seed;
    for (size_t k = 0; k < (size_t)im->w * im->h * im->c; k++) {
        x = x * 1664525u + 1013904223u;
        im->v[k] = (double)(x >> 8) / 16777216.0;
    }
}

static const char *const formats[] = {".png", ".exr", ".tif", ".txt", ".pfm"};
#define NFORMATS (sizeof formats / sizeof formats[0])
/* Under ASan every start of the command costs seconds: the sanitizer pass
 * takes the first two formats (one 8-bit, one float, both through
 * OpenImageIO), the plain pass all five. */
#if UNDER_ASAN
#define FORMATS_RUN ((size_t)2)
#else
#define FORMATS_RUN NFORMATS
#endif

/* ------------------------------------------------------------------------
 * A full disk
 * ------------------------------------------------------------------------ */

/* RLIMIT_FSIZE's soft limit, which can be raised again; 1 on success. */
static int set_limit_soft(rlim_t room)
{
    struct rlimit r;
    if (getrlimit(RLIMIT_FSIZE, &r) != 0)
        return 0;
    r.rlim_cur = room;
    return setrlimit(RLIMIT_FSIZE, &r) == 0;
}

/* In a child (its soft RLIMIT_FSIZE is lowered and put back): for every
 * format, a 16x16 file is there; writing a 96x96 image over it with room
 * for only part of it fails with AA_EIO naming the file and the reason,
 * and leaves the 16x16 file as it was and no temporary file; room for all
 * of it succeeds.  The rooms go from the first write to the very last
 * bytes (a PNG's IEND chunk, TIFF's directory, what fclose flushes). */
static int full_disk_writes(void *arg)
{
    const char *dir = arg;
    char path[PATH_MAX + 32], full[PATH_MAX + 32];
    signal(SIGXFSZ, SIG_IGN);
    aa_image im, prev;
    SUPPORT_CHILD_CHECK(aa_image_alloc(&im, 96, 96, 3) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_alloc(&prev, 16, 16, 3) == AA_OK);
    fill_random(&im, 96);
    fill_random(&prev, 16);
    for (size_t f = 0; f < FORMATS_RUN; f++) {
        snprintf(path, sizeof path, "%s/out%s", dir, formats[f]);
        snprintf(full, sizeof full, "%s/whole%s", dir, formats[f]);
        SUPPORT_CHILD_CHECK(aa_image_write(path, &prev, NULL) == AA_OK);
        SUPPORT_CHILD_CHECK(aa_image_write(full, &im, NULL) == AA_OK);
        size_t old_len, whole_len, new_len;
        unsigned char *old = slurp(path, &old_len);
        free(slurp(full, &whole_len));
        rlim_t room[] = {1, whole_len / 2, whole_len - 1, whole_len};
        for (size_t r = 0; r < sizeof room / sizeof room[0]; r++) {
            SUPPORT_CHILD_CHECK(set_limit_soft(room[r]));
            int st = aa_image_write(path, &im, NULL);
            SUPPORT_CHILD_CHECK(set_limit_soft(RLIM_INFINITY));
            if (room[r] == whole_len) {
                SUPPORT_CHILD_CHECK(st == AA_OK);
                free(slurp(path, &new_len));
                SUPPORT_CHILD_CHECK(new_len == whole_len);
                break;
            }
            if (st != AA_EIO || strstr(aa_last_error(), path) == NULL ||
                strstr(aa_last_error(), strerror(EFBIG)) == NULL)
                fprintf(stderr, "%s with room for %lu of %zu bytes: status %d, \"%s\"\n", path,
                        (unsigned long)room[r], whole_len, st, aa_last_error());
            SUPPORT_CHILD_CHECK(st == AA_EIO && strstr(aa_last_error(), path) != NULL);
            SUPPORT_CHILD_CHECK(strstr(aa_last_error(), strerror(EFBIG)) != NULL);
            SUPPORT_CHILD_CHECK(same_as(path, old, old_len));
            SUPPORT_CHILD_CHECK(temporaries_in(dir) == 0);
        }
        free(old);
    }
    aa_image_free(&im);
    aa_image_free(&prev);
    return 0;
}

/* The library's writers on a full disk (full_disk_writes), then the
 * command: its status 3, its message and the previous file kept. */
static void test_full_disk_truth(void **state)
{
    (void)state;
    char dir[PATH_MAX], path[PATH_MAX + 32];
    fresh("full-disk-truth", dir, sizeof dir);
    support_in_child(full_disk_writes, dir);
    join(path, sizeof path, dir, "cmd.png");
    aa_image prev;
    assert_int_equal(aa_image_alloc(&prev, 16, 16, 3), AA_OK);
    fill_random(&prev, 16);
    assert_int_equal(aa_image_write(path, &prev, NULL), AA_OK);
    aa_image_free(&prev);
    size_t old_len;
    unsigned char *old = slurp(path, &old_len);
    const char *big[] = {"truth", "-p", "crow", "-s", "96x96", "--no-cache", "-o", path, NULL};
    limits lim = {.fsize = 200}; /* less than any 96x96 PNG */
    expect_exit(run_cmd(&lim, big), 3, "truth on a full disk");
    expect_output(path, "truth on a full disk");
    expect_output(strerror(EFBIG), "truth on a full disk");
    assert_true(same_as(path, old, old_len));
    assert_int_equal(temporaries_in(dir), 0);
    free(old);
}

/* A run writes images/, results, montage.png and plots/ (gnuplot's PNG,
 * which gnuplot leaves cut short with status 0 on a full disk): with no
 * room, status 3, every file of the previous run as it was, no temporary
 * file.  With some room, the files written whole are new (results.csv
 * holds new times), the others as they were. */
static void test_full_disk_run(void **state)
{
    (void)state;
    char dir[PATH_MAX], out[PATH_MAX + 32], montage[PATH_MAX + 64], csv[PATH_MAX + 64];
    char plot[PATH_MAX + 64];
    fresh("full-disk-run", dir, sizeof dir);
    join(out, sizeof out, dir, "run");
    join(montage, sizeof montage, out, "montage.png");
    join(csv, sizeof csv, out, "results.csv");
    join(plot, sizeof plot, out, "plots/error_vs_time.png");
    const char *args[] = {"run", "-p", "crow", "-f", "box", "-s", "24x24", "-m", "point", "-m",
                          "area", "--reps", "1", "-q", "--no-cache", "--out", out, NULL};
    expect_exit(run_cmd(NULL, args), 0, "run");
    size_t mlen, clen, plen;
    unsigned char *m = slurp(montage, &mlen), *c = slurp(csv, &clen), *p = slurp(plot, &plen);
    /* the plot is the largest file: room below the montage stops there,
     * room above every other file (the worst regions' pictures are the
     * largest of images/) but the plot stops at the plot */
    size_t big = mlen;
    char images[PATH_MAX + 64];
    join(images, sizeof images, out, "images");
    DIR *d = opendir(images);
    assert_non_null(d);
    for (struct dirent *e; (e = readdir(d));) {
        char f[2 * PATH_MAX];
        struct stat sb;
        snprintf(f, sizeof f, "%s/%s", images, e->d_name);
        if (!stat(f, &sb) && S_ISREG(sb.st_mode) && (size_t)sb.st_size > big)
            big = (size_t)sb.st_size;
    }
    closedir(d);
    assert_true(big + 1000 < plen);
    rlim_t room[] = {1, 600, mlen - 1, big + 1000};
    for (size_t r = 0; r < sizeof room / sizeof room[0]; r++) {
        limits lim = {.fsize = room[r]};
        char what[64];
        snprintf(what, sizeof what, "run with room for %lu bytes", (unsigned long)room[r]);
        expect_exit(run_cmd(&lim, args), 3, what);
        expect_output(r < 3 ? strerror(EFBIG) : "error_vs_time", what);
        assert_true(r == 3 || same_as(montage, m, mlen));
        assert_true(room[r] > 1 || same_as(csv, c, clen));
        assert_true(same_as(plot, p, plen));
        assert_int_equal(temporaries_in(dir), 0);
    }
    free(m);
    free(c);
    free(p);
}

/* Before anything is written, the images of a montage and of each format
 * at its full size, and a text for aa_file_write_atomic. */
#define LIB_ROOM 3000

static int montage_tile_get(void *ctx, size_t k, aa_tile *tile)
{
    aa_image *tiles = ctx;
    tile->image = &tiles[k % 2];
    tile->label[0] = "a tile";
    tile->label[1] = NULL;
    return AA_OK;
}

/* In a child whose files may not grow beyond LIB_ROOM bytes: every writer
 * of the library fails with AA_EIO and leaves what was there. */
static int library_writers(void *arg)
{
    const char *dir = arg;
    char path[PATH_MAX + 64];
    signal(SIGXFSZ, SIG_IGN);
    aa_image im, tiles[2];
    SUPPORT_CHILD_CHECK(aa_image_alloc(&im, 64, 64, 3) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_alloc(&tiles[0], 40, 30, 3) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_alloc(&tiles[1], 40, 30, 3) == AA_OK);
    fill_random(&im, 7);
    fill_random(&tiles[0], 8);
    fill_random(&tiles[1], 9);
    /* the previous files, written with room */
    static const char old_text[] = "the previous file\n";
    for (size_t f = 0; f < FORMATS_RUN; f++) {
        snprintf(path, sizeof path, "%s/lib%s", dir, formats[f]);
        SUPPORT_CHILD_CHECK(aa_file_write_atomic(path, old_text, sizeof old_text - 1) == AA_OK);
    }
    snprintf(path, sizeof path, "%s/montage.png", dir);
    SUPPORT_CHILD_CHECK(aa_file_write_atomic(path, old_text, sizeof old_text - 1) == AA_OK);
    snprintf(path, sizeof path, "%s/atomic.json", dir);
    SUPPORT_CHILD_CHECK(aa_file_write_atomic(path, old_text, sizeof old_text - 1) == AA_OK);
    struct rlimit r = {LIB_ROOM, LIB_ROOM};
    SUPPORT_CHILD_CHECK(setrlimit(RLIMIT_FSIZE, &r) == 0);
    for (size_t f = 0; f < FORMATS_RUN; f++) {
        snprintf(path, sizeof path, "%s/lib%s", dir, formats[f]);
        SUPPORT_CHILD_CHECK(aa_image_write(path, &im, NULL) == AA_EIO);
        SUPPORT_CHILD_CHECK(strstr(aa_last_error(), path) != NULL);
        /* row by row: the failure shows at a row or at the end */
        aa_image_out *out;
        SUPPORT_CHILD_CHECK(aa_image_out_begin(path, im.w, im.h, im.c, NULL, &out) == AA_OK);
        int st = AA_OK;
        for (int j = 0; j < im.h && st == AA_OK; j++)
            st = aa_image_out_rows(out, aa_pixel(&im, 0, j), 1);
        if (st == AA_OK)
            st = aa_image_out_finish(out);
        else
            SUPPORT_CHILD_CHECK(aa_image_out_finish(out) == st);
        SUPPORT_CHILD_CHECK(st == AA_EIO);
    }
    aa_tile_source src = {.n = 6, .tw = 40, .th = 30, .lines = 1, .get = montage_tile_get,
                          .ctx = tiles};
    snprintf(path, sizeof path, "%s/montage.png", dir);
    SUPPORT_CHILD_CHECK(aa_montage_stream(path, &src, 3, NULL) == AA_EIO);
    char big[2 * LIB_ROOM];
    memset(big, 'x', sizeof big);
    snprintf(path, sizeof path, "%s/atomic.json", dir);
    SUPPORT_CHILD_CHECK(aa_file_write_atomic(path, big, sizeof big) == AA_EIO);
    SUPPORT_CHILD_CHECK(strstr(aa_last_error(), strerror(EFBIG)) != NULL);
    /* everything as it was */
    for (size_t f = 0; f < FORMATS_RUN + 2; f++) {
        if (f < FORMATS_RUN)
            snprintf(path, sizeof path, "%s/lib%s", dir, formats[f]);
        else
            snprintf(path, sizeof path, "%s/%s", dir, f == NFORMATS ? "montage.png" : "atomic.json");
        FILE *in = fopen(path, "rb");
        char back[64] = "";
        size_t n = in ? fread(back, 1, sizeof back - 1, in) : 0;
        if (in)
            fclose(in);
        back[n] = '\0';
        SUPPORT_CHILD_CHECK(strcmp(back, old_text) == 0);
    }
    aa_image_free(&im);
    aa_image_free(&tiles[0]);
    aa_image_free(&tiles[1]);
    return 0;
}

static void test_full_disk_library(void **state)
{
    (void)state;
    char dir[PATH_MAX];
    fresh("full-disk-library", dir, sizeof dir);
    support_in_child(library_writers, dir);
    assert_int_equal(temporaries_in(dir), 0);
}

/* What a test mounted or made, undone by its teardown even when it fails. */
static char mounted[PATH_MAX + 32], made_cgroup[256];

static int undo(void **state)
{
    (void)state;
    if (mounted[0] != '\0' && umount(mounted) != 0)
        print_error("cannot unmount %s: %s\n", mounted, strerror(errno));
    if (made_cgroup[0] != '\0' && rmdir(made_cgroup) != 0)
        print_error("cannot remove the cgroup %s: %s\n", made_cgroup, strerror(errno));
    mounted[0] = made_cgroup[0] = '\0';
    return 0;
}

/* A real full file system: a tmpfs of 64 KB, filled up. */
static void test_full_tmpfs(void **state)
{
    (void)state;
    char dir[PATH_MAX], mnt[PATH_MAX + 32], path[PATH_MAX + 64], filler[PATH_MAX + 64];
    fresh("tmpfs", dir, sizeof dir);
    join(mnt, sizeof mnt, dir, "mnt");
    assert_int_equal(mkdir(mnt, 0777), 0);
    if (mount("tmpfs", mnt, "tmpfs", 0, "size=64k") == 0)
        snprintf(mounted, sizeof mounted, "%s", mnt);
    else {
        print_message("skipped: cannot mount a tmpfs here (%s); the full disk is tested with "
                      "RLIMIT_FSIZE only\n", strerror(errno));
        skip();
    }
    join(filler, sizeof filler, mnt, "filler");
    /* the previous file, any 8x8 image of the format; the new one 96x96 */
    aa_image prev, im;
    assert_int_equal(aa_image_alloc(&prev, 8, 8, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&im, 96, 96, 3), AA_OK);
    fill_random(&prev, 8);
    fill_random(&im, 96);
    for (size_t f = 0; f < NFORMATS; f++) {
        join_ext(path, sizeof path, mnt, "out", formats[f]);
        assert_int_equal(aa_image_write(path, &prev, NULL), AA_OK);
        size_t old_len;
        unsigned char *old = slurp(path, &old_len);
        /* fill what is left */
        int fd = open(filler, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        assert_true(fd >= 0);
        char block[1024];
        memset(block, 'f', sizeof block);
        while (write(fd, block, sizeof block) > 0)
            ;
        while (write(fd, block, 1) > 0)
            ;
        close(fd);
        int st = aa_image_write(path, &im, NULL);
        if (st != AA_EIO || !strstr(aa_last_error(), path) ||
            !strstr(aa_last_error(), strerror(ENOSPC)))
            fail_msg("%s on a full tmpfs: status %d, \"%s\"", path, st, aa_last_error());
        assert_true(same_as(path, old, old_len));
        assert_int_equal(temporaries_in(mnt), 0);
        unlink(filler);
        free(old);
    }
    aa_image_free(&prev);
    aa_image_free(&im);
}

/* ------------------------------------------------------------------------
 * Files cut short, and garbage after a valid header
 * ------------------------------------------------------------------------ */

/* `compare good bad` ends with status 3, naming bad. */
static void compare_refused(const char *good, const char *bad)
{
    const char *args[] = {"compare", good, bad, NULL};
    expect_exit(run_cmd(NULL, args), 3, bad);
    expect_output(bad, bad);
}

/* For each of the n extensions: a fresh folder `name` holding a w x h x 3
 * image of fill_random(seed) written to whole.EXT; body gets the folder,
 * the extension, the file's path and its bytes. */
typedef void whole_file_body(const char *dir, const char *ext, const char *path,
                             const unsigned char *whole, size_t n);

static void for_whole_files(const char *name, int w, int h, uint32_t seed,
                            const char *const *exts, size_t nexts, whole_file_body *body)
{
    char dir[PATH_MAX], path[PATH_MAX + 32];
    fresh(name, dir, sizeof dir);
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, w, h, 3), AA_OK);
    fill_random(&im, seed);
    for (size_t f = 0; f < nexts; f++) {
        join_ext(path, sizeof path, dir, "whole", exts[f]);
        assert_int_equal(aa_image_write(path, &im, NULL), AA_OK);
        size_t n;
        unsigned char *whole = slurp(path, &n);
        body(dir, exts[f], path, whole, n);
        free(whole);
    }
    aa_image_free(&im);
}

static void cut_short(const char *dir, const char *ext, const char *path,
                      const unsigned char *whole, size_t n)
{
    char cut[PATH_MAX + 32];
    join_ext(cut, sizeof cut, dir, "cut", ext);
    /* the whole file reads: the refusals below are about the cuts */
    aa_image back;
    assert_int_equal(aa_image_read(path, &back), AA_OK);
    assert_int_equal(back.w * back.h * back.c, 37 * 23 * 3);
    aa_image_free(&back);
    size_t at[] = {0, 1, 7, 8, 33, 100, n / 4, n / 3, n / 2, 2 * n / 3, 3 * n / 4,
                   n - 100, n - 13, n - 12, n - 8, n - 4, n - 1};
    for (size_t k = 0; k < sizeof at / sizeof at[0]; k++) {
        if (at[k] >= n)
            continue;
        spill(cut, whole, at[k]);
        back = (aa_image){1, 1, 1, (double *)&back};
        int st = aa_image_read(cut, &back);
        if (st != AA_EIO)
            fail_msg("%s cut to %zu of %zu bytes: status %d, expected AA_EIO (%s)", ext, at[k],
                     n, st, st ? aa_last_error() : "read");
        if (strstr(aa_last_error(), cut) == NULL)
            fail_msg("%s cut to %zu bytes: the message does not name the file: %s", ext, at[k],
                     aa_last_error());
        assert_null(back.v);
    }
    /* and the command, once: status 3, naming the file */
    if (strcmp(ext, formats[0]) == 0) {
        spill(cut, whole, n / 2);
        compare_refused(path, cut);
    }
}

static void test_cut_short(void **state)
{
    (void)state;
    for_whole_files("cut", 37, 23, 12345, formats, FORMATS_RUN, cut_short);
}

static void garbage_after_header(const char *dir, const char *ext, const char *path,
                                 const unsigned char *b, size_t n)
{
    char bad[PATH_MAX + 32];
    join_ext(bad, sizeof bad, dir, "bad", ext);
    /* garbage from `keep` on, but for the last 12 bytes (a PNG's IEND
     * chunk: the file does not look cut short) */
    size_t keep[] = {n / 8, n / 4, n / 2};
    for (size_t k = 0; k < 3; k++) {
        unsigned char *g = malloc(n);
        assert_non_null(g);
        memcpy(g, b, n);
        uint32_t x = (uint32_t)(2654435761u * (k + 1));
        for (size_t q = keep[k]; q < n - 12; q++) {
            x = x * 1664525u + 1013904223u;
            g[q] = (unsigned char)(x >> 24);
        }
        spill(bad, g, n);
        free(g);
        aa_image back;
        int st = aa_image_read(bad, &back);
        if (st != AA_EIO)
            fail_msg("%s: garbage after byte %zu of %zu: status %d, expected AA_EIO", ext,
                     keep[k], n, st);
        assert_non_null(strstr(aa_last_error(), bad));
        if (k == 0 && strcmp(ext, formats[0]) == 0) /* the command, once */
            compare_refused(path, bad);
    }
}

static void test_garbage_after_header(void **state)
{
    (void)state;
    static const char *const binary[] = {".png", ".exr", ".tif"};
    for_whole_files("garbage", 64, 48, 99, binary, 3, garbage_after_header);
}

/* ------------------------------------------------------------------------
 * OpenImageIO under an address-space limit
 * ------------------------------------------------------------------------ */

static void test_address_space_limit(void **state)
{
    (void)state;
    if (UNDER_ASAN) {
        print_message("skipped under AddressSanitizer: it reserves terabytes of address space, "
                      "so RLIMIT_AS cannot be tested\n");
        skip();
    }
    char dir[PATH_MAX], path[PATH_MAX + 32];
    fresh("address-space", dir, sizeof dir);
    join(path, sizeof path, dir, "x.exr");
    const char *args[] = {"truth", "-p", "crow", "-s", "8x8", "-o", path, "--no-cache", NULL};
    /* Around what loading OpenImageIO needs (about 550 MB here, with its
     * libraries): below it the loading fails in the loader, in static
     * constructors (std::bad_alloc, std::system_error for a thread) or
     * fatally in glibc, depending on the megabyte.  An 8x8 image: it is the
     * loading that is tested, and an image of 64x64 doubles or less is
     * nothing beside steps of 44 MB (the same limits refuse here).  The
     * limits rise until the command succeeds: under a larger limit the
     * same start has more room (here 576 MB succeeds, and 620 did as well
     * when it was run too), so the refusals, each of them, are what the
     * sweep tests. */
    int refused = 0, done = 0;
    for (rlim_t mb = 400; mb <= 620 && !done; mb += 44) {
        limits lim = {.as = mb << 20};
        int st = run_cmd(&lim, args);
        char what[64];
        snprintf(what, sizeof what, "truth under RLIMIT_AS = %lu MB", (unsigned long)mb);
        if (WIFSIGNALED(st))
            fail_msg("%s: ended by signal %d:\n%s", what, WTERMSIG(st), output);
        int code = WEXITSTATUS(st);
        if (code != 0 && code != 2 && code != 3)
            fail_msg("%s: exit %d:\n%s", what, code, output);
        if (code != 0) {
            expect_output(path, what);
            refused++;
        } else
            done = 1;
    }
    /* the limits did bite */
    assert_true(refused > 0);
    /* and a write or a read that runs out of memory in OpenImageIO: here
     * writing the 2048x2048 EXR does at 640 MB ("out of memory in
     * OpenImageIO", status 3), reading the 1024x1024 one at 680 MB.  (A
     * 2048x2048 one to read is refused from its header at 640 and 680 MB,
     * as test_compare_counts_first tests, and read whole at 720 MB: it
     * never ran out inside OpenImageIO.)  The render is timed once: its
     * time is not tested, and its status at each limit is the timed
     * render's.  Each command is run under the limits in turn until it
     * succeeds, as above: here the render succeeds at 680 MB, so it is not
     * run again at 720 (it succeeded there too when it was), and compare
     * runs at all three. */
    char big[PATH_MAX + 32], mid[PATH_MAX + 32];
    join(big, sizeof big, dir, "big.exr");
    join(mid, sizeof mid, dir, "mid.exr");
    aa_image im;
    assert_int_equal(aa_image_alloc(&im, 1024, 1024, 3), AA_OK);
    fill_random(&im, 1024);
    assert_int_equal(aa_image_write(mid, &im, NULL), AA_OK);
    aa_image_free(&im);
    const char *render[] = {"render", "-p", "crow", "-m", "point", "-s", "2048x2048", "--reps",
                            "1", "-o", big, NULL};
    int rendered = 0, compared = 0;
    for (rlim_t mb = 640; mb <= 720; mb += 40) {
        limits lim = {.as = mb << 20};
        const char *cmp[] = {"compare", mid, mid, NULL};
        int st;
        if (!rendered) {
            st = run_cmd(&lim, render);
            assert_true(WIFEXITED(st) && WEXITSTATUS(st) != 1 && WEXITSTATUS(st) <= 3);
            rendered = WEXITSTATUS(st) == 0;
        }
        if (!compared) {
            st = run_cmd(&lim, cmp);
            assert_true(WIFEXITED(st) && WEXITSTATUS(st) != 1 && WEXITSTATUS(st) <= 3);
            compared = WEXITSTATUS(st) == 0;
        }
    }
}

/* ------------------------------------------------------------------------
 * Memory counted before work
 * ------------------------------------------------------------------------ */

/* A TIFF of 1.2 KB whose header claims W x H 8-bit RGB pixels, in one
 * uncompressed strip that is not there (TIFF 6.0, section 2: a little-endian
 * header, one IFD of 10 entries sorted by tag). */
static void claim_tiff(const char *path, uint32_t w, uint32_t h)
{
    unsigned char b[1200] = {'I', 'I', 42, 0, 8, 0, 0, 0};
    const struct {
        uint16_t tag, type;
        uint32_t value;
    } e[] = {{256, 4, w}, {257, 4, h},   {258, 3, 8},         {259, 3, 1}, {262, 3, 2},
             {273, 4, 200}, {277, 3, 3}, {278, 4, h}, {279, 4, w * h * 3}, {284, 3, 1}};
    size_t at = 8;
    b[at++] = 10, b[at++] = 0;
    for (size_t k = 0; k < 10; k++) {
        unsigned char *p = b + at;
        p[0] = (unsigned char)e[k].tag, p[1] = (unsigned char)(e[k].tag >> 8);
        p[2] = (unsigned char)e[k].type, p[3] = 0;
        p[4] = 1, p[5] = p[6] = p[7] = 0; /* count */
        for (int q = 0; q < 4; q++)        /* a SHORT sits in the first 2 bytes */
            p[8 + q] = (unsigned char)(e[k].value >> (8 * q));
        at += 12;
    }
    /* next IFD: none (zeros) */
    spill(path, b, sizeof b);
}

/* A PFM whose header claims W x H RGB pixels: the header, then exactly
 * W x H x 3 4-byte floats as harness/core/image.c wants them (pfm_head),
 * here a hole (a sparse file: no block of it is written).  It loads no
 * image module, so the limits' own checks below start the command without
 * OpenImageIO's 0.9 s of CPU (1.6 s sanitized); the .tif claim above keeps
 * the headers read through OpenImageIO counted too. */
static void claim_pfm(const char *path, uint32_t w, uint32_t h)
{
    char head[64];
    int n = snprintf(head, sizeof head, "PF\n%u %u\n-1.0\n", (unsigned)w, (unsigned)h);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, head, (size_t)n), n);
    assert_int_equal(ftruncate(fd, (off_t)n + (off_t)w * (off_t)h * 3 * 4), 0);
    assert_int_equal(close(fd), 0);
}

/* Two images of W x H x 3 doubles, and the error spectrum's W x H complex
 * doubles (the larger of the spectrum and SSIM's two lumas). */
/* Both images (3 doubles a pixel each), then the larger of the error
 * spectrum (2 doubles a pixel) and FLIP's work (flip.c: 6 planes of work,
 * both images' Lab (3 planes each) and features (2 each), and copies of
 * both images (3 each) where a value is not finite: 22 planes). */
static double compare_need(double w, double h)
{
    return 2 * w * h * 3 * 8 + 22 * w * h * 8;
}

static void test_compare_counts_first(void **state)
{
    (void)state;
    char huge[PATH_MAX + 32], big[PATH_MAX + 32];
    fresh_files("admission", huge, "huge.tif", big, "big.pfm", NULL);
    claim_tiff(huge, 65535, 65535);
    claim_pfm(big, 5000, 5000);
    /* 962 GB: more than half of any machine this runs on */
    char need[64];
    snprintf(need, sizeof need, "needs %.1f GB", compare_need(65535, 65535) / 1e9);
    const char *args[] = {"compare", huge, huge, NULL};
    expect_exit(run_cmd(NULL, args), 2, "compare of 65535x65535 headers");
    expect_output(need, "compare of 65535x65535 headers");
    expect_output("the limit is", "compare of 65535x65535 headers");
    if (UNDER_ASAN) {
        print_message("RLIMIT_AS and RLIMIT_DATA not tested under AddressSanitizer (it "
                      "reserves terabytes of address space)\n");
        return;
    }
    /* 5.6 GB, under limits of 1.5 GB */
    snprintf(need, sizeof need, "needs %.1f GB", compare_need(5000, 5000) / 1e9);
    const char *bigs[] = {"compare", big, big, NULL};
    limits as = {.as = (rlim_t)1500 << 20}, data = {.data = (rlim_t)1500 << 20};
    expect_exit(run_cmd(&as, bigs), 2, "compare under RLIMIT_AS");
    expect_output(need, "compare under RLIMIT_AS");
    expect_output("RLIMIT_AS", "compare under RLIMIT_AS");
    expect_exit(run_cmd(&data, bigs), 2, "compare under RLIMIT_DATA");
    expect_output(need, "compare under RLIMIT_DATA");
    expect_output("RLIMIT_DATA", "compare under RLIMIT_DATA");
}

/* The cgroup limit, where a memory cgroup can be made (v2 memory.max, else
 * v1 memory.limit_in_bytes). */
static void test_compare_cgroup(void **state)
{
    (void)state;
    char big[PATH_MAX + 32], cg[256], file[300];
    fresh_files("cgroup", big, "big.pfm", NULL);
    claim_pfm(big, 4000, 4000); /* needs 1.0 GB */
    /* the roots of a v2 and a v1 memory hierarchy, known by a file only
     * the cgroup file system has */
    const char *roots[] = {"/sys/fs/cgroup", "/sys/fs/cgroup/memory"};
    const char *marks[] = {"cgroup.controllers", "memory.limit_in_bytes"};
    const char *limit_files[] = {"memory.max", "memory.limit_in_bytes"};
    int made = -1, err = ENOENT;
    for (int v = 0; v < 2 && made < 0; v++) {
        snprintf(file, sizeof file, "%s/%s", roots[v], marks[v]);
        if (!exists(file))
            continue;
        snprintf(cg, sizeof cg, "%s/aabench-test-%ld", roots[v], (long)getpid());
        if (mkdir(cg, 0755) != 0) {
            err = errno;
            continue;
        }
        snprintf(file, sizeof file, "%s/%s", cg, limit_files[v]);
        char text[32];
        int n = snprintf(text, sizeof text, "%d\n", 512 << 20);
        int fd = open(file, O_WRONLY); /* never made: it is there or this is no cgroup */
        snprintf(made_cgroup, sizeof made_cgroup, "%s", cg);
        if (fd >= 0 && write(fd, text, (size_t)n) == n && close(fd) == 0) {
            made = v;
        } else {
            made_cgroup[0] = '\0';
            err = errno;
            if (fd >= 0)
                close(fd);
            rmdir(cg);
        }
    }
    if (made < 0) {
        print_message("skipped: cannot make a memory cgroup here (%s)\n", strerror(err));
        skip();
    }
    snprintf(file, sizeof file, "%s/cgroup.procs", cg);
    limits lim = {.cgroup_procs = file};
    const char *args[] = {"compare", big, big, NULL};
    int st = run_cmd(&lim, args);
    expect_exit(st, 2, "compare in a cgroup of 512 MB");
    expect_output(limit_files[made], "compare in a cgroup of 512 MB");
    char half[32];
    snprintf(half, sizeof half, "the limit is %.0f MB", (512 << 20) / 2 / 1e6);
    expect_output(half, "compare in a cgroup of 512 MB");
}

/* A run's montage shows at most 256 x 256 of a view, so a view of 65536 x
 * 1 is no longer too wide for one: the run goes ahead, its montage the
 * view's centre, as it does without images.  (A view whose error map cannot
 * be made is refused before anything runs: test_run_faults.) */
static void test_run_checks_montage_first(void **state)
{
    (void)state;
    char dir[PATH_MAX], out[PATH_MAX + 32];
    fresh("run-montage", dir, sizeof dir);
    join(out, sizeof out, dir, "run");
    /* The zone plate, whose reference of 65536 x 1 takes 0.2 s of CPU here
     * where crow's takes 16 s: the montage is refused from the sizes alone,
     * whatever the pattern. */
    const char *args[] = {"run", "-p", "zoneplate", "-f", "box", "-s", "65536x1", "-m", "point",
                          "--reps", "1", "--no-plots", "-q", "--out", out, NULL};
    expect_exit(run_cmd(NULL, args), 0, "run with a wide view");
    char montage[PATH_MAX + 64];
    join(montage, sizeof montage, out, "montage.png");
    aa_image im;
    assert_int_equal(aa_image_read(montage, &im), AA_OK);
    assert_true(im.w < 1000); /* two tiles of at most 256 and their gaps */
    aa_image_free(&im);
    const char *without[] = {"run", "-p", "zoneplate", "-f", "box", "-s", "65536x1", "-m",
                             "point", "--reps", "1", "--no-plots", "--no-images", "-q", "--out",
                             out, NULL};
    expect_exit(run_cmd(NULL, without), 0, "the same run without images");
}

/* Tiles made when asked: tile k is (k + 1) / 32 everywhere. */
typedef struct made_tiles {
    int w, h;
    aa_image im;
    int held, most_held;
} made_tiles;

static int made_get(void *ctx, size_t k, aa_tile *tile)
{
    made_tiles *t = ctx;
    int st = aa_image_alloc(&t->im, t->w, t->h, 3);
    if (st)
        return st;
    for (size_t q = 0; q < (size_t)t->w * t->h * 3; q++)
        t->im.v[q] = (double)(k + 1) / 32;
    t->held++;
    t->most_held = t->held > t->most_held ? t->held : t->most_held;
    tile->image = &t->im;
    tile->label[0] = "tile";
    tile->label[1] = NULL;
    return AA_OK;
}

static void made_put(void *ctx, size_t k)
{
    (void)k;
    made_tiles *t = ctx;
    aa_image_free(&t->im);
    t->held--;
}

/* The layout (montage.c): a gap of 8, label lines of 13 + 4 pixels, 4
 * more above the tile. */
#define M_GAP 8
#define M_LINE 17

static double address_space(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    unsigned long pages = 0;
    if (f != NULL) {
        if (fscanf(f, "%lu", &pages) != 1)
            pages = 0;
        fclose(f);
    }
    return (double)pages * (double)sysconf(_SC_PAGESIZE);
}

static int stream_montage(void *arg)
{
    const char *dir = arg;
    char path[PATH_MAX + 64];
    /* OpenImageIO loaded first, so what it takes is in use already */
    snprintf(path, sizeof path, "%s/warm.png", dir);
    aa_image tiny;
    SUPPORT_CHILD_CHECK(aa_image_alloc(&tiny, 2, 2, 3) == AA_OK);
    SUPPORT_CHILD_CHECK(aa_image_write(path, &tiny, NULL) == AA_OK);
    aa_image_free(&tiny);
    /* 16 tiles of 512 x 512 in 4 columns: held whole, the tiles and the
     * montage are 210 MB; a row at a time, 40 MB.  Allow 120 MB more. */
    made_tiles t = {.w = 512, .h = 512};
    aa_tile_source src = {.n = 16, .tw = 512, .th = 512, .lines = 1, .get = made_get,
                          .put = made_put, .ctx = &t};
    rlim_t room = (rlim_t)(address_space() + (120 << 20));
    struct rlimit r = {room, room};
    SUPPORT_CHILD_CHECK(setrlimit(RLIMIT_AS, &r) == 0);
    snprintf(path, sizeof path, "%s/montage.pfm", dir);
    SUPPORT_CHILD_CHECK(aa_montage_stream(path, &src, 4, NULL) == AA_OK);
    SUPPORT_CHILD_CHECK(t.most_held == 1 && t.held == 0);
    return 0;
}

static void test_montage_row_at_a_time(void **state)
{
    (void)state;
    if (UNDER_ASAN || getenv("AABENCH_VALGRIND") != NULL) {
        print_message("skipped under %s: RLIMIT_AS cannot be used with it\n",
                      UNDER_ASAN ? "AddressSanitizer" : "valgrind");
        skip();
    }
    char dir[PATH_MAX], path[PATH_MAX + 32];
    fresh("montage", dir, sizeof dir);
    support_in_child(stream_montage, dir);
    /* The file, from the layout: W = 4 (512 + 8) + 8, H = 4 (512 + 17 +
     * 8 + 4) + 8; a .pfm holds float samples, rows bottom up after the
     * header "PF\nW H\n-1.0\n" (little-endian). */
    const int w = 4 * (512 + M_GAP) + M_GAP, h = 4 * (512 + M_LINE + M_GAP + 4) + M_GAP;
    char header[64];
    int hl = snprintf(header, sizeof header, "PF\n%d %d\n-1.0\n", w, h);
    size_t n;
    unsigned char *b = slurp(join(path, sizeof path, dir, "montage.pfm"), &n);
    assert_int_equal(n, (size_t)hl + (size_t)w * h * 12);
    assert_memory_equal(b, header, (size_t)hl);
    for (int k = 0; k < 16; k++) {
        /* the centre of tile k, and the ground just left of it */
        int x = M_GAP + (k % 4) * (512 + M_GAP) + 256;
        int y = M_GAP + (k / 4) * (512 + M_LINE + M_GAP + 4) + M_LINE + 4 + 256;
        int gx = x - 256 - 1;
        for (int q = 0; q < 2; q++) {
            int px = q ? gx : x;
            size_t at = (size_t)hl + (((size_t)(h - 1 - y) * w + (size_t)px) * 3) * 4;
            for (int c = 0; c < 3; c++) {
                float v;
                uint32_t bits = (uint32_t)b[at + 4 * c] | (uint32_t)b[at + 4 * c + 1] << 8 |
                                (uint32_t)b[at + 4 * c + 2] << 16 |
                                (uint32_t)b[at + 4 * c + 3] << 24;
                memcpy(&v, &bits, sizeof v);
                float want = q ? (float)0.01 : (float)((k + 1) / 32.0);
                if (v != want)
                    fail_msg("tile %d, %s: %.9g, expected %.9g", k, q ? "ground" : "centre",
                             (double)v, (double)want);
            }
        }
    }
    free(b);
}

/* ------------------------------------------------------------------------
 * NaN and infinities in compared files
 * ------------------------------------------------------------------------ */

/* The number after "\"key\": " in output, or NAN if it is null. */
static double json_value(const char *key)
{
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = strstr(output, pat);
    if (p == NULL)
        fail_msg("no %s in %s", key, output);
    p += strlen(pat);
    if (strncmp(p, "null", 4) == 0)
        return NAN;
    return strtod(p, NULL);
}

static void no_json_nonfinite(void)
{
    static const char *const bad[] = {"nan", "NaN", "inf", "Inf", "Infinity"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        if (strstr(output, bad[k]) != NULL)
            fail_msg("JSON holds %s: %s", bad[k], output);
}

static void test_compare_nonfinite(void **state)
{
    (void)state;
    char ref[PATH_MAX + 32], img[PATH_MAX + 32], odd[PATH_MAX + 32];
    /* The library's figures from .exr files; the command's from the same
     * images as .pfm (32-bit floats too), which start it without loading
     * OpenImageIO's module: its output is what is tested there. */
    char pref[PATH_MAX + 32], pimg[PATH_MAX + 32], podd[PATH_MAX + 32];
    fresh_files("nonfinite", ref, "ref.exr", img, "img.exr", odd, "odd.exr", NULL);
    snprintf(pref, sizeof pref, "%.*s.pfm", (int)strlen(ref) - 4, ref);
    snprintf(pimg, sizeof pimg, "%.*s.pfm", (int)strlen(img) - 4, img);
    snprintf(podd, sizeof podd, "%.*s.pfm", (int)strlen(odd) - 4, odd);
    aa_image a, b;
    assert_int_equal(aa_image_alloc(&a, 8, 6, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&b, 8, 6, 3), AA_OK);
    for (size_t k = 0; k < 8 * 6 * 3; k++)
        a.v[k] = b.v[k] = 0.5;
    aa_pixel(&b, 1, 2)[0] = NAN;
    aa_pixel(&b, 3, 0)[2] = INFINITY;
    aa_pixel(&a, 5, 5)[1] = -INFINITY;
    assert_int_equal(aa_image_write(ref, &a, NULL), AA_OK);
    assert_int_equal(aa_image_write(pref, &a, NULL), AA_OK);
    assert_int_equal(aa_image_write(odd, &b, NULL), AA_OK); /* differs only where not finite */
    assert_int_equal(aa_image_write(podd, &b, NULL), AA_OK);
    for (int c = 0; c < 3; c++)
        aa_pixel(&b, 0, 0)[c] = 0.75;
    assert_int_equal(aa_image_write(img, &b, NULL), AA_OK);
    assert_int_equal(aa_image_write(pimg, &b, NULL), AA_OK);
    /* 3 pixels left out; of the 45 left, one differs by 0.25 in its 3
     * channels: mse = 3 (1/16) / 135.  The library's figures of the files
     * read back: */
    aa_image fa, fb, fo;
    aa_metrics m;
    assert_int_equal(aa_image_read(ref, &fa), AA_OK);
    assert_int_equal(aa_image_read(img, &fb), AA_OK);
    assert_int_equal(aa_image_read(odd, &fo), AA_OK);
    double mse = 3 * 0.0625 / 135;
    assert_int_equal(aa_metrics_compare(&fa, &fb, NULL, &m), AA_OK);
    assert_true(m.nonfinite == 3);
    assert_true(fabs(m.rmse - sqrt(mse)) < 1e-8 && fabs(m.max_err - 0.25) < 1e-8);
    assert_true(fabs(m.psnr - 10 * log10(1 / mse)) < 1e-6);
    /* identical files are infinitely alike, the same NaN and infinities
     * in both included */
    assert_int_equal(aa_metrics_compare(&fb, &fb, NULL, &m), AA_OK);
    assert_true(m.psnr == INFINITY && m.nonfinite == 2);
    /* differing only where a value is not finite: no PSNR */
    assert_int_equal(aa_metrics_compare(&fa, &fo, NULL, &m), AA_OK);
    assert_true(isnan(m.psnr) && isnan(m.psnr_enc) && m.rmse == 0 && m.nonfinite == 3);
    aa_image_free(&fa);
    aa_image_free(&fb);
    aa_image_free(&fo);
    /* the command: no NaN or infinity in its JSON (null), never the
     * identical images' 999 for images that differ */
    const char *same[] = {"compare", pref, podd, "--json", NULL};
    expect_exit(run_cmd(NULL, same), 0, "compare --json, differing where not finite");
    no_json_nonfinite();
    assert_true(isnan(json_value("psnr")) && isnan(json_value("psnr_enc")));
    assert_true(json_value("rmse") == 0 && json_value("nonfinite") == 3);
    /* the text says how many */
    const char *text[] = {"compare", pref, pimg, NULL};
    expect_exit(run_cmd(NULL, text), 0, "compare with NaN and infinities");
    expect_output("nonfinite    3 pixels", "compare with NaN and infinities");
    aa_image_free(&a);
    aa_image_free(&b);
}

/* When no pixel can be compared (every one holds a NaN or an infinity in
 * either image) there is no figure: the library gives NaN for each, the
 * command n/a (null in JSON) and exit status 1, never the "identical"
 * ssim 1 and alias 0 of images compared nowhere. */
static void test_compare_all_nonfinite(void **state)
{
    (void)state;
    aa_image a, b;
    assert_int_equal(aa_image_alloc(&a, 12, 12, 3), AA_OK);
    assert_int_equal(aa_image_alloc(&b, 12, 12, 3), AA_OK);
    for (size_t k = 0; k < 12 * 12 * 3; k++)
        a.v[k] = 0.5, b.v[k] = NAN;
    aa_pixel(&b, 4, 4)[0] = 0.5; /* still a NaN in the pixel's other channels */
    aa_metrics m;
    assert_int_equal(aa_metrics_compare(&a, &b, NULL, &m), AA_OK);
    assert_true(m.nonfinite == 144);
    const double v[] = {m.rmse,     m.mae,         m.max_err,   m.psnr,      m.rmse_enc,
                        m.mae_enc,  m.max_err_enc, m.psnr_enc,  m.alias_total,
                        m.alias_low, m.alias_high, m.ssim};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        if (!isnan(v[k]))
            fail_msg("figure %zu is %g where no pixel can be compared", k, v[k]);
    assert_true(m.max_at[0] == -1 && m.max_at[1] == -1 && m.max_at[2] == -1);
    aa_image_free(&a);
    aa_image_free(&b);

    /* The command, on PFM files written here ("Pf\nW H\n-1.0\n" then
     * little-endian floats): 2 x 1 pixels of 0.5, and of NaN. */
    char ref[PATH_MAX + 32], img[PATH_MAX + 32];
    fresh_files("allnan", ref, "ref.pfm", img, "nan.pfm", NULL);
    unsigned char half[] = {0x00, 0x00, 0x00, 0x3f}, nan[] = {0x00, 0x00, 0xc0, 0x7f};
    char buf[64];
    size_t hl = (size_t)snprintf(buf, sizeof buf, "Pf\n2 1\n-1.0\n");
    memcpy(buf + hl, half, 4), memcpy(buf + hl + 4, half, 4);
    support_write_file(ref, buf, hl + 8);
    memcpy(buf + hl, nan, 4), memcpy(buf + hl + 4, nan, 4);
    support_write_file(img, buf, hl + 8);
    const char *text[] = {"compare", ref, img, NULL};
    expect_exit(run_cmd(NULL, text), 1, "compare of an all-NaN image");
    expect_output("ssim         n/a", "compare of an all-NaN image");
    expect_output("alias_total  n/a", "compare of an all-NaN image");
    expect_output("rmse         n/a", "compare of an all-NaN image");
    if (strstr(output, "1.000000") || strstr(output, "e+00"))
        fail_msg("a figure where none can be compared:\n%s", output);
    const char *json[] = {"compare", ref, img, "--json", NULL};
    expect_exit(run_cmd(NULL, json), 1, "compare --json of an all-NaN image");
    no_json_nonfinite();
    static const char *const keys[] = {"rmse", "mae", "max_err", "psnr", "rmse_enc", "mae_enc",
                                       "max_err_enc", "psnr_enc", "alias_total", "alias_low",
                                       "alias_high", "ssim"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        if (!isnan(json_value(keys[k])))
            fail_msg("%s is not null:\n%s", keys[k], output);
    assert_true(json_value("nonfinite") == 2);
    /* One comparable pixel is enough for figures, and exit 0. */
    memcpy(buf + hl, half, 4);
    support_write_file(img, buf, hl + 8);
    expect_exit(run_cmd(NULL, json), 0, "compare --json, one pixel comparable");
    assert_true(json_value("rmse") == 0 && json_value("nonfinite") == 1);
}

/* Images that differ by 1e-170 (whose square underflows) are not
 * identical: rmse = 1e-170 / sqrt(16), psnr = -20 log10 of that. */
static void test_compare_tiny_difference(void **state)
{
    (void)state;
    char ref[PATH_MAX + 32], img[PATH_MAX + 32];
    fresh_files("tiny", ref, "ref.txt", img, "img.txt", NULL);
    char text[512];
    int n = snprintf(text, sizeof text, "# aabench 4 4 1\n");
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            n += snprintf(text + n, sizeof text - (size_t)n, "%d %d 0\n", i, j);
    spill(ref, text, (size_t)n);
    char *at = strstr(text, "\n2 1 0\n");
    assert_non_null(at);
    char tiny[512];
    snprintf(tiny, sizeof tiny, "%.*s\n2 1 1e-170\n%s", (int)(at - text), text, at + 7);
    spill(img, tiny, strlen(tiny));
    const char *args[] = {"compare", ref, img, "--json", NULL};
    expect_exit(run_cmd(NULL, args), 0, "compare of images 1e-170 apart");
    no_json_nonfinite();
    double rmse = 1e-170 / 4;
    assert_true(fabs(json_value("rmse") / rmse - 1) < 1e-8);
    assert_true(fabs(json_value("psnr") - (-20 * log10(rmse))) < 1e-6);
    assert_true(json_value("max_err") == 1e-170);
}

/* A .txt holding NaN or an infinity: refused, naming the file and the
 * pixel. */
static void test_txt_nan_named(void **state)
{
    (void)state;
    char ok[PATH_MAX + 32], bad[PATH_MAX + 32];
    fresh_files("txt-nan", ok, "ok.txt", bad, "bad.txt", NULL);
    static const char good[] = "# aabench 2 1 3\n0 0 0.5 0.25 1\n1 0 0 0 0.125\n";
    static const char nan[] = "# aabench 2 1 3\n0 0 0.5 0.25 1\n1 0 0 0 NaN\n";
    static const char inf[] = "# aabench 2 1 3\n0 0 0.5 -inf 1\n1 0 0 0 0\n";
    spill(ok, good, sizeof good - 1);
    spill(bad, nan, sizeof nan - 1);
    const char *args[] = {"compare", ok, bad, NULL};
    expect_exit(run_cmd(NULL, args), 3, "compare with a .txt holding NaN");
    expect_output(bad, "compare with a .txt holding NaN");
    expect_output("pixel (1, 0) channel 2", "compare with a .txt holding NaN");
    /* the reader's refusal, which compare reports */
    spill(bad, inf, sizeof inf - 1);
    aa_image im;
    int st = aa_image_read(bad, &im);
    if (st != AA_EIO || !strstr(aa_last_error(), bad) ||
        !strstr(aa_last_error(), "pixel (0, 0) channel 1"))
        fail_msg("a .txt holding -inf: status %d, \"%s\"", st, aa_last_error());
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        /* the two whose children write EXRs first, before this process
         * writes one itself: a child forked after that hangs in its own EXR
         * write (OpenEXR's thread pool is not there in the child) */
        cmocka_unit_test(test_full_disk_library),
        cmocka_unit_test(test_full_disk_truth),
        cmocka_unit_test(test_full_disk_run),
        cmocka_unit_test_teardown(test_full_tmpfs, undo),
        cmocka_unit_test(test_cut_short),
        cmocka_unit_test(test_garbage_after_header),
        cmocka_unit_test(test_address_space_limit),
        cmocka_unit_test(test_compare_counts_first),
        cmocka_unit_test_teardown(test_compare_cgroup, undo),
        cmocka_unit_test(test_run_checks_montage_first),
        cmocka_unit_test(test_montage_row_at_a_time),
        cmocka_unit_test(test_compare_nonfinite),
        cmocka_unit_test(test_compare_all_nonfinite),
        cmocka_unit_test(test_compare_tiny_difference),
        cmocka_unit_test(test_txt_nan_named),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
