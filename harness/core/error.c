/*
 * error.c: the library's one error path.
 *
 * A failing function records a message for its thread with aa_fail() and
 * returns the status; callers add context with aa_fail_context().  Nothing
 * is printed here: the command line decides what the user sees.  Warnings
 * (something was wrong and was worked around, such as a corrupt cache file
 * recomputed) go to the handler the program installs with aa_set_warn.
 * A message is one line: control characters are escaped, and a message too
 * long for its buffer loses its middle, never its end (the reason), however
 * long an input it quotes; aa_echo shortens the input itself.
 */
#include "core.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define AA_ERROR_LEN 1024

static _Thread_local char last_error[AA_ERROR_LEN];

/* The whole message, however long, in malloc'd memory (NULL when out of
 * memory).  Messages quote numbers as specs and options write them:
 * C-locale text (in the caller's locale should the C locale be out of
 * reach). */
static char *format_alloc(const char *fmt, va_list ap)
{
    aa__c_numbers numbers;
    int c = aa__c_numbers_begin(&numbers) == 0;
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (s)
        vsnprintf(s, (size_t)n + 1, fmt, ap);
    if (c)
        aa__c_numbers_end(&numbers);
    return s;
}

/* A control character as text: \n, \t, \r, or \xHH. */
static size_t escape_char(unsigned char c, char out[5])
{
    if (c == '\n' || c == '\t' || c == '\r') {
        out[0] = '\\', out[1] = c == '\n' ? 'n' : c == '\t' ? 't' : 'r';
        return 2;
    }
    snprintf(out, 5, "\\x%02x", c);
    return 4;
}

static int is_control(unsigned char c)
{
    return c < 0x20 || c == 0x7f;
}

/* `src` into buf as one line: control characters escaped (an echoed input
 * may hold a newline or a terminal's escape sequence); if it is too long,
 * its middle gives way to " ... ", so that both the start (what failed)
 * and the end (why) survive a long input quoted in between.  Cuts fall
 * between UTF-8 characters. */
static void fit(char *buf, size_t len, const char *src)
{
    size_t n = 0;
    for (const unsigned char *c = (const unsigned char *)src; *c; c++) {
        char e[5];
        n += is_control(*c) ? escape_char(*c, e) : 1;
    }
    char *esc = malloc(n + 1);
    if (!esc) {
        snprintf(buf, len, "%s", src);
        return;
    }
    size_t k = 0;
    for (const unsigned char *c = (const unsigned char *)src; *c; c++) {
        if (is_control(*c))
            k += escape_char(*c, esc + k);
        else
            esc[k++] = (char)*c;
    }
    esc[k] = '\0';
    if (n < len) {
        memcpy(buf, esc, n + 1);
    } else {
        static const char gap[] = " ... ";
        size_t room = len - 1 - (sizeof gap - 1), head = room / 3, tail = room - head;
        size_t from = n - tail;
        while (head && ((unsigned char)esc[head] & 0xc0) == 0x80)
            head--; /* not inside a UTF-8 character */
        while (from < n && ((unsigned char)esc[from] & 0xc0) == 0x80)
            from++;
        memcpy(buf, esc, head);
        memcpy(buf + head, gap, sizeof gap - 1);
        memcpy(buf + head + sizeof gap - 1, esc + from, n - from + 1);
    }
    free(esc);
}

int aa_fail(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *s = format_alloc(fmt, ap);
    va_end(ap);
    if (s) {
        fit(last_error, sizeof last_error, s);
        free(s);
    } else {
        snprintf(last_error, sizeof last_error, "out of memory formatting an error: %s", fmt);
    }
    return status;
}

/* Here, not in c_numbers.c, which records no error (aa_fail uses it). */
int aa__c_numbers_enter(aa__c_numbers *n, const char *what)
{
    if (aa__c_numbers_begin(n))
        return aa_fail(AA_ENOMEM, "%s: cannot make the C locale: %s", what, strerror(errno));
    return AA_OK;
}

int aa_fail_context(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *context = format_alloc(fmt, ap);
    va_end(ap);
    /* "context: old", the middle given way if too long */
    size_t n = context ? strlen(context) : 0, m = strlen(last_error);
    char *both = context ? malloc(n + 2 + m + 1) : NULL;
    if (both) {
        memcpy(both, context, n);
        memcpy(both + n, ": ", 2);
        memcpy(both + n + 2, last_error, m + 1);
        fit(last_error, sizeof last_error, both);
    }
    free(both);
    free(context);
    return status;
}

static aa_warn_fn warn_fn;
static void *warn_ctx;

void aa_set_warn(aa_warn_fn fn, void *ctx)
{
    warn_fn = fn;
    warn_ctx = ctx;
}

aa_warn_fn aa_get_warn(void **ctx)
{
    if (ctx)
        *ctx = warn_ctx;
    return warn_fn;
}

void aa_warn(const char *fmt, ...)
{
    aa_warn_fn fn = warn_fn;
    if (!fn)
        return;
    char msg[AA_ERROR_LEN];
    va_list ap;
    va_start(ap, fmt);
    char *s = format_alloc(fmt, ap);
    va_end(ap);
    if (s)
        fit(msg, sizeof msg, s);
    else
        snprintf(msg, sizeof msg, "(out of memory formatting a warning) %s", fmt);
    free(s);
    fn(msg, warn_ctx);
}

#define ECHO_SLOTS 4
#define ECHO_KEEP 64 /* characters of a long input kept */

const char *aa_echo(const char *text)
{
    static _Thread_local char slot[ECHO_SLOTS][(ECHO_KEEP + 32) * 4 + 64];
    static _Thread_local unsigned next;
    char *buf = slot[next++ % ECHO_SLOTS];
    if (!text)
        return "(none)";
    size_t len = strlen(text), n = 0, shown = 0;
    const unsigned char *c = (const unsigned char *)text;
    /* short inputs whole; a long one cut after ECHO_KEEP characters, at a
     * UTF-8 character's start */
    size_t keep = len <= ECHO_KEEP + 32 ? len : ECHO_KEEP;
    while (keep > 0 && keep < len && (c[keep] & 0xc0) == 0x80)
        keep--;
    if (keep == 0)
        keep = len < ECHO_KEEP ? len : ECHO_KEEP; /* no character starts there: cut the bytes */
    for (; shown < keep; shown++) {
        if (is_control(c[shown]))
            n += escape_char(c[shown], buf + n);
        else
            buf[n++] = (char)c[shown];
    }
    buf[n] = '\0';
    if (keep < len)
        snprintf(buf + n, sizeof slot[0] - n, "...(%zu characters)", len);
    return buf;
}

const char *aa_last_error(void)
{
    return last_error;
}

int aa_exit_code(int status)
{
    switch (status) {
    case AA_OK: return 0;
    case AA_ECHECK: return 1;
    case AA_EINVAL: return 2;
    default: return 3;
    }
}
