/*
 * isolate_internal.h: running one case of a run in a child process, and
 * a case's failed row (isolate.c), internal to harness/bench.
 */
#ifndef AA_ISOLATE_INTERNAL_H
#define AA_ISOLATE_INTERNAL_H

#include "bench.h"

/* Mark a row failed: ok = 0, failed = 1, the note "failed: " and the
 * reason. */
void aa__row_failed(aa_row *row, const char *fmt, ...) AA_PRINTF(2, 3);

/* A case: fills *row (and the image it was given); a status only for the
 * harness's own failures. */
typedef int (*aa__case_fn)(void *arg, aa_row *row);

/* Run fn(arg, row) in a child process and bring back *row and, when img is
 * not NULL and the case ran (row->ok), the image's pixels into img (W x H x
 * 3, allocated by the caller, the one fn fills).  A child that dies of a
 * signal, ends without reporting, or takes longer than `timeout` seconds
 * (killed then) gives a failed row, the rest of *row (names, set by the
 * caller) kept.  `threads`: the case's thread count, whose OpenMP threads
 * the child starts before the case.  A status for failures of the harness
 * (fork, pipe) or those the case reported. */
int aa__case_isolated(aa__case_fn fn, void *arg, aa_row *row, aa_image *img, double timeout,
                      int threads);

#endif
