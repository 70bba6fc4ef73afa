/*
 * c_numbers.c: the C locale for numbers, per thread, and a number read
 * from C-locale text (c_numbers_internal.h).
 *
 * One locale object serves the whole process: made on first use, never
 * changed, never freed (uselocale only reads it).
 */
#include "core.h"
#include "c_numbers_internal.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

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

/* ---- numbers as text ---- */

/* Skip digits; how many there were. */
static size_t skip_digits(const char **p, const char *end)
{
    const char *start = *p;
    while (*p < end && aa__is_digit(**p))
        (*p)++;
    return (size_t)(*p - start);
}

/* Plain decimal syntax, [+-]d[.d][(e|E)[+-]d] with at least one digit in
 * the mantissa.  strtod would also take hex floats, "inf", "nan" and
 * leading blanks, none of which %.17g of a finite value writes. */
static int decimal_syntax(const char *s, size_t len)
{
    const char *p = s, *end = s + len;
    if (p < end && (*p == '+' || *p == '-'))
        p++;
    size_t digits = skip_digits(&p, end);
    if (p < end && *p == '.') {
        p++;
        digits += skip_digits(&p, end);
    }
    if (digits == 0)
        return 0;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < end && (*p == '+' || *p == '-'))
            p++;
        if (skip_digits(&p, end) == 0)
            return 0;
    }
    return p == end;
}

aa__number_result aa__parse_number(const char *s, size_t len, double *v)
{
    if (!decimal_syntax(s, len))
        return AA__NUMBER_MALFORMED;
    char *end;
    /* ERANGE is no reason to refuse: an underflow is still the correctly
     * rounded value (5e-324 is one), and an overflow is caught as not
     * finite just below. */
    *v = strtod(s, &end);
    if (end != s + len)
        return AA__NUMBER_MALFORMED;
    return isfinite(*v) ? AA__NUMBER_OK : AA__NUMBER_NOT_FINITE;
}
