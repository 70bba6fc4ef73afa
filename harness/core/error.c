/*
 * error.c: the library's one error path.
 *
 * A failing function records a message for its thread with aa_fail() and
 * returns the status; callers add context with aa_fail_context().  Nothing
 * is printed here: the command line decides what the user sees.  Warnings
 * (something was wrong and was worked around, such as a corrupt cache file
 * recomputed) go to the handler the program installs with aa_set_warn.
 */
#include "core.h"
#include "c_numbers_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define AA_ERROR_LEN 1024

static _Thread_local char last_error[AA_ERROR_LEN];

/* Messages quote numbers as specs and options write them: C-locale text
 * (in the caller's locale should the C locale be out of reach). */
static void format(char *buf, size_t len, const char *fmt, va_list ap)
{
    aa__c_numbers numbers;
    int c = aa__c_numbers_begin(&numbers) == 0;
    vsnprintf(buf, len, fmt, ap);
    if (c)
        aa__c_numbers_end(&numbers);
}

int aa_fail(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    format(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}

int aa_fail_context(int status, const char *fmt, ...)
{
    char context[AA_ERROR_LEN], old[AA_ERROR_LEN];
    va_list ap;
    va_start(ap, fmt);
    format(context, sizeof context, fmt, ap);
    va_end(ap);
    memcpy(old, last_error, sizeof old);
    /* "context: old", cut to fit */
    size_t n = strlen(context), m = strlen(old);
    if (n > AA_ERROR_LEN - 3)
        n = AA_ERROR_LEN - 3;
    memcpy(last_error, context, n);
    memcpy(last_error + n, ": ", 2);
    n += 2;
    if (m > AA_ERROR_LEN - 1 - n)
        m = AA_ERROR_LEN - 1 - n;
    memcpy(last_error + n, old, m);
    last_error[n + m] = '\0';
    return status;
}

static aa_warn_fn warn_fn;
static void *warn_ctx;

void aa_set_warn(aa_warn_fn fn, void *ctx)
{
    warn_fn = fn;
    warn_ctx = ctx;
}

void aa_warn(const char *fmt, ...)
{
    aa_warn_fn fn = warn_fn;
    if (!fn)
        return;
    char msg[AA_ERROR_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fn(msg, warn_ctx);
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
