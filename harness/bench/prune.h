/*
 * prune.h: old run folders removed (prune.c), `aabench prune`'s library.
 *
 * A run folder is a folder under RESULTS/runs named by its UTC start time,
 * YYYYMMDDTHHMMSSZ or YYYYMMDDTHHMMSSZ-K (the K-th made in that second),
 * holding run.json.  Anything else there is left alone.
 */
#ifndef AA_PRUNE_H
#define AA_PRUNE_H

#include <stddef.h>

/* The run folders of RESULTS/runs beyond the `keep` newest (by the time in
 * their names, then K) removed, with everything under them; the folder
 * RESULTS/latest points to is kept whatever its age.  With dry_run nothing
 * is removed.  `each` (may be NULL) is given each folder removed (or that
 * would be), oldest first; *removed (may be NULL) counts them.  keep < 0 is
 * AA_EINVAL; no RESULTS/runs is no run folder (AA_OK); a folder that cannot
 * be read or removed is AA_EIO, naming it. */
int aa_runs_prune(const char *results, long keep, int dry_run,
                  void (*each)(void *ctx, const char *dir), void *ctx, size_t *removed);

/* Whether NAME is a run folder's name: YYYYMMDDTHHMMSSZ[-K], K 2 to 99. */
int aa_runs_name(const char *name);

#endif
