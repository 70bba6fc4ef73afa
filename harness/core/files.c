/*
 * files.c: writing files so that a failure leaves nothing behind, folders,
 * and the clock.
 *
 * Every result file is written under a temporary name in its own folder and
 * renamed into place (harness/README.md, "Principles"): rename(2) within one file
 * system is atomic, so a reader sees either the old file or the whole new
 * one, and a run that fails or is interrupted leaves at most a hidden
 * temporary file, never a half-written result under the real name.
 *
 * We do not fsync before the rename: the promise is about runs that fail or
 * are killed, which rename alone keeps; fsync would add a disk flush to every
 * image and reference written and only helps against a power cut.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif

#include "core.h"

#include <stdarg.h>

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Room for a temporary file name (PATH_MAX on Linux). */
#define TEMP_NAME_MAX 4096

/* Shared by all threads, so two writers in one process never pick the same
 * name; the process id separates processes. */
static atomic_ulong temp_counter;

/* The file name part of `path`: after the last '/'. */
static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* The extension of a file name, from its last '.', or "" if none.  A leading
 * dot marks a hidden file, not an extension. */
static const char *extension(const char *base)
{
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? dot : base + strlen(base);
}

/* The temporary names handed out last, so an interrupted program can remove
 * those still on disk (aa_temp_cleanup, from a signal handler).  A slot is
 * read by the handler only while its state is READY; a name already renamed
 * into place no longer exists, and names are never reused (process id and
 * counter), so unlinking it again is harmless. */
#define TEMP_SLOTS 64
enum { SLOT_EMPTY, SLOT_WRITING, SLOT_READY };
static struct {
    atomic_int state;
    char name[TEMP_NAME_MAX];
} temp_slots[TEMP_SLOTS];

static void temp_remember(const char *name, unsigned long id)
{
    unsigned long k = id % TEMP_SLOTS;
    size_t n = strlen(name);
    if (n >= TEMP_NAME_MAX)
        return;
    atomic_store(&temp_slots[k].state, SLOT_WRITING);
    memcpy(temp_slots[k].name, name, n + 1);
    atomic_store(&temp_slots[k].state, SLOT_READY);
}

void aa_temp_cleanup(void)
{
    for (int k = 0; k < TEMP_SLOTS; k++)
        if (atomic_load(&temp_slots[k].state) == SLOT_READY)
            unlink(temp_slots[k].name); /* async-signal-safe */
}

int aa_temp_name(const char *path, char *buf, size_t len)
{
    if (path == NULL || buf == NULL || len == 0)
        return aa_fail(AA_EINVAL, "aa_temp_name: no path or no buffer");
    const char *base = base_name(path);
    if (*base == '\0')
        return aa_fail(AA_EINVAL, "%s: not a file name (ends with '/' or is empty)", path);
    const char *ext = extension(base);
    if (strlen(ext) > 16)
        ext = "";
    unsigned long n = atomic_fetch_add(&temp_counter, 1);
    /* Same folder, so the rename stays on one file system; a leading dot,
     * so tools listing results skip it; the process and a counter, so no two
     * writers share a name; short, so a result name near NAME_MAX still
     * has a temporary name; the real extension, so a writer that looks at
     * the name picks the right format. */
    int k = snprintf(buf, len, "%.*s.aa-%ld-%lu%s", (int)(base - path), path, (long)getpid(), n,
                     ext);
    if (k < 0 || (size_t)k >= len)
        return aa_fail(AA_EINVAL, "%s: temporary name too long for its buffer (%zu bytes)", path,
                       len);
    temp_remember(buf, n);
    return AA_OK;
}

/* write(2) until everything is out, resuming after signals. */
static int write_all(int fd, const char *data, size_t len)
{
    while (len > 0) {
        ssize_t k = write(fd, data, len);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            return -1;
        data += k;
        len -= (size_t)k;
    }
    return 0;
}

int aa_file_write_atomic(const char *path, const void *data, size_t len)
{
    char tmp[TEMP_NAME_MAX];
    if (data == NULL && len > 0)
        return aa_fail(AA_EINVAL, "%s: no data to write", path ? path : "(null)");
    int status = aa_temp_name(path, tmp, sizeof tmp);
    if (status != AA_OK)
        return status;
    /* O_EXCL: never write through a name someone else has just made. */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0)
        return aa_fail(AA_EIO, "%s: cannot create %s: %s", path, tmp, strerror(errno));
    const char *what = "write";
    int ok = write_all(fd, data, len) == 0;
    int err = errno;
    /* close can report a deferred write error (NFS, full disk). */
    if (close(fd) != 0 && ok) {
        ok = 0;
        err = errno;
    }
    if (ok && rename(tmp, path) != 0) {
        ok = 0;
        err = errno;
        what = "rename into place";
    }
    if (!ok) {
        unlink(tmp);
        return aa_fail(AA_EIO, "%s: cannot %s: %s", path, what, strerror(err));
    }
    return AA_OK;
}

/* Make one folder; an existing folder is fine, anything else in the way is
 * not. */
static int make_folder(const char *whole, const char *folder)
{
    if (mkdir(folder, 0777) == 0)
        return AA_OK;
    int err = errno;
    struct stat st;
    /* Some systems say EACCES or EROFS rather than EEXIST for a folder
     * that is already there, so ask what is there instead of trusting
     * errno. */
    if (stat(folder, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return AA_OK;
        return aa_fail(AA_EIO, "%s: cannot make folder %s: it exists and is not a folder",
                       whole, folder);
    }
    return aa_fail(AA_EIO, "%s: cannot make folder %s: %s", whole, folder, strerror(err));
}

int aa_mkdirs(const char *path)
{
    if (path == NULL || *path == '\0')
        return aa_fail(AA_EINVAL, "aa_mkdirs: empty folder name");
    size_t n = strlen(path);
    char *folder = malloc(n + 1);
    if (folder == NULL)
        return aa_fail(AA_ENOMEM, "%s: out of memory", path);
    memcpy(folder, path, n + 1);
    int status = AA_OK;
    /* Each prefix ending before a '/' (and the whole path) is a folder to
     * make, parents first.  Leading slashes name the root. */
    for (size_t k = 1; k <= n && status == AA_OK; k++) {
        if (k < n && (folder[k] != '/' || folder[k - 1] == '/'))
            continue;
        char saved = folder[k];
        folder[k] = '\0';
        status = make_folder(path, folder);
        folder[k] = saved;
    }
    free(folder);
    return status;
}

double aa_now(void)
{
    struct timespec t;
    /* CLOCK_MONOTONIC is required by POSIX.1-2008, so this cannot fail. */
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int aa_pathf(char *buf, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, len, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= len)
        return aa_fail(AA_EINVAL, "path too long (more than %zu characters): %s", len - 1,
                       aa_echo(buf));
    return AA_OK;
}
