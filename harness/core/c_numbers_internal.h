/*
 * c_numbers_internal.h: numbers as C-locale text whatever locale the
 * program around the library has set (internal to aabench).
 *
 * Spec values, CSV and JSON numbers, the reference cache's keys, plot data
 * and the command line's numbers are read and written with '.' as the
 * decimal point.  A host program (or a plug-in) may set LC_NUMERIC to a
 * locale whose decimal point is a comma, which strtod and printf's %g, %f
 * and %e obey; between aa__c_numbers_begin and aa__c_numbers_end they
 * follow the C locale instead, on the calling thread only (uselocale,
 * POSIX.1-2008), and other threads and the program's own locale are left
 * alone.  Pairs nest.
 */
#ifndef AA_C_NUMBERS_INTERNAL_H
#define AA_C_NUMBERS_INTERNAL_H

#include <locale.h>
#include <stddef.h>

typedef struct aa__c_numbers {
    locale_t saved; /* the thread's locale before begin */
} aa__c_numbers;

/* 0, or -1 when the C locale cannot be made (out of memory, errno set):
 * then nothing changed, and aa__c_numbers_end must not be called.  Records
 * no error, so that aa_fail itself can use it. */
int aa__c_numbers_begin(aa__c_numbers *n);
void aa__c_numbers_end(aa__c_numbers *n);

/* aa__c_numbers_begin that records the failure for `what` (AA_ENOMEM;
 * error.c). */
int aa__c_numbers_enter(aa__c_numbers *n, const char *what);

static inline int aa__is_digit(char ch)
{
    return ch >= '0' && ch <= '9';
}

typedef enum aa__number_result {
    AA__NUMBER_OK,
    AA__NUMBER_MALFORMED,
    AA__NUMBER_NOT_FINITE
} aa__number_result;

/* The finite number spelled by s[0, len), which is followed by a character
 * that cannot continue a number (blank or NUL): plain decimal syntax only.
 * Needs aa__c_numbers. */
aa__number_result aa__parse_number(const char *s, size_t len, double *v);

#endif
