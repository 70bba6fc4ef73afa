/*
 * c_numbers.c: the C locale for numbers, per thread (c_numbers_internal.h).
 *
 * One locale object serves the whole process: made on first use, never
 * changed, never freed (uselocale only reads it).
 */
#include "core.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <pthread.h>
#include <string.h>

static locale_t c_locale = (locale_t)0;
static int c_locale_errno;
static pthread_once_t c_locale_once = PTHREAD_ONCE_INIT;

static void make_c_locale(void)
{
    c_locale = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    if (c_locale == (locale_t)0)
        c_locale_errno = errno;
}

int aa__c_numbers_begin(aa__c_numbers *n)
{
    pthread_once(&c_locale_once, make_c_locale);
    if (c_locale == (locale_t)0) {
        errno = c_locale_errno;
        return -1;
    }
    n->saved = uselocale(c_locale);
    return 0;
}

void aa__c_numbers_end(aa__c_numbers *n)
{
    uselocale(n->saved);
}

int aa__c_numbers_enter(aa__c_numbers *n, const char *what)
{
    if (aa__c_numbers_begin(n))
        return aa_fail(AA_ENOMEM, "%s: cannot make the C locale: %s", what, strerror(errno));
    return AA_OK;
}
