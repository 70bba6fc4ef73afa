/*
 * fuzz_baseline.c: libFuzzer target for the results and baseline CSV
 * reader (`make fuzz`), the input of `aabench check`'s regression gate.
 *
 * The input is read as a results CSV (aa_rows_parse_csv).  Refused or
 * accepted, it must not crash; a refusal leaves no rows.  An accepted file
 * must hold only rows the gate can trust: finite errors within [0, 1] in a
 * row that ran, the largest error's pixel inside the image, no measurement
 * in a row that did not but a reason, a size in range, a finite time and
 * motion, and a pattern and filter that parse.  And what the writer makes
 * of them must read back to the same text: write, read, write gives the
 * text the first write gave.
 */
#include "bench.h"
#include "fuzz.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int trusted(const aa_row *r)
{
    aa_spec p;
    aa_filter f;
    if (r->w < 1 || r->h < 1 || r->w > AA_MAX_SIDE || r->h > AA_MAX_SIDE || !isfinite(r->t) ||
        !isfinite(r->vx) || !isfinite(r->vy) || aa_pattern_parse(r->pattern, &p) ||
        aa_filter_parse(r->filter, &f) || !*r->method)
        return 0;
    if (!r->ok)
        return *r->note && r->m.rmse == 0 && r->m.max_err == 0 && !r->temporal;
    return r->m.rmse >= 0 && r->m.rmse <= 1 && r->m.max_err >= 0 && r->m.max_err <= 1 &&
           r->m.mae >= 0 && r->m.mae <= 1 && r->m.max_at[0] < r->w && r->m.max_at[1] < r->h;
}

/* The file `rows` are written to, read back into memory. */
static char *written(const aa_row *rows, size_t n, const char *path, size_t *len)
{
    if (aa_rows_write_csv(path, rows, n) != AA_OK)
        abort();
    FILE *f = fopen(path, "rb");
    if (!f)
        abort();
    char *buf = malloc(1 << 20);
    if (!buf)
        abort();
    *len = fread(buf, 1, 1 << 20, f);
    fclose(f);
    return buf;
}

int aa_fuzz_baseline(const uint8_t *data, size_t size)
{
    aa_row *rows = (aa_row *)1;
    size_t n = 7;
    if (aa_rows_parse_csv("fuzz.csv", (const char *)data, size, &rows, &n) != AA_OK) {
        if (rows || n)
            abort(); /* a refusal leaves nothing behind */
        return 0;
    }
    for (size_t k = 0; k < n; k++)
        if (!trusted(&rows[k]))
            abort(); /* a row the gate cannot trust was accepted */
    if (n && n <= 64) {
        char path[64];
        snprintf(path, sizeof path, "/tmp/aabench-fuzz-baseline-%ld.csv", (long)getpid());
        size_t l1, l2, m;
        char *a = written(rows, n, path, &l1);
        aa_row *again;
        if (aa_rows_parse_csv("again.csv", a, l1, &again, &m) != AA_OK || m != n)
            abort(); /* what was written does not read back */
        char *b = written(again, m, path, &l2);
        if (l1 != l2 || memcmp(a, b, l1))
            abort();
        unlink(path);
        free(a);
        free(b);
        free(again);
    }
    free(rows);
    return 0;
}

AA_FUZZ_ENTRY(aa_fuzz_baseline)
