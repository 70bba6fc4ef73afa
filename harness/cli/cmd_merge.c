/*
 * cmd_merge.c: `aabench merge DIR... --out DIR`: the folders of a run's
 * shards (run --shard K/N) joined into the whole run's results.
 *
 * Every folder's manifest (run.json) must name the same command, suite and
 * commit, and together their results must hold every case of the run
 * exactly once; a missing, duplicated or foreign shard is refused (exit 2)
 * naming it, before anything is written.  Then the rows, in the run's
 * order, are written as the unsharded run writes them (cmd_run.c does:
 * results.csv and .json, montage, plots, table); each row keeps the host
 * that measured it and its times.  The errors are the shards', which are
 * the unsharded run's: every case is computed the same way whichever
 * process runs it.
 */
#include "cli.h"

#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: aabench merge DIR... --out DIR [-q] [--cache DIR]\n\n"
            "Joins the folders of a run's shards ('aabench run --shard K/N --out DIR') into\n"
            "the whole run's results.csv, results.json, images/, montage.png, plots/ and\n"
            "table, as the run without --shard writes them.  The shards must come from the\n"
            "same command, suite and commit and hold every case exactly once.\n\n"
            "  --out DIR        the merged run's folder\n"
            "  --cache DIR      reference cache for the montage and plots (default\n"
            "                   results/cache, or $AABENCH_CACHE)\n"
            "  -q, --quiet      no table at the end\n\n"
            "Exit status: 0 done, 1 some cases failed (as in run), 2 a shard missing,\n"
            "duplicated or of another run, or bad usage, 3 input/output error.\n");
}

typedef struct shard {
    const char *dir;
    aa_manifest m;
    aa_row *rows;
    size_t n;
} shard;

/* The arguments of a manifest's command, joined for messages. */
static void command_text(const aa_manifest *m, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; k < m->argc && n + 1 < len; k++)
        n += (size_t)snprintf(buf + n, len - n, "%s%s", k ? " " : "", m->argv[k]);
}

static int same_command(const aa_manifest *a, const aa_manifest *b)
{
    if (a->argc != b->argc)
        return 0;
    for (int k = 0; k < a->argc; k++)
        if (strcmp(a->argv[k], b->argv[k]))
            return 0;
    return 1;
}

/* Refused: the message, exit status 2. */
static int refuse(const char *fmt, ...) AA_PRINTF(1, 2);
static int refuse(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "aabench merge: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    return 2;
}

/* Where a case's row is: its folder and its row there. */
typedef struct place {
    int shard; /* -1: nowhere yet */
    size_t row; /* REFUSED: skipped by the run, its method refusing the view */
} place;
#define REFUSED ((size_t)-1)

/* Every check before anything is written: the manifests agree, and the
 * rows hold each case of the run exactly once.  *owner (malloc'd) gives
 * each case's place. */
static int check_shards(shard *s, int ns, place **owner_out)
{
    char a[2048], b[2048];
    const aa_manifest *first = &s[0].m;
    *owner_out = NULL;
    for (int i = 1; i < ns; i++) {
        const aa_manifest *m = &s[i].m;
        if (!same_command(m, first)) {
            command_text(first, a, sizeof a);
            command_text(m, b, sizeof b);
            return refuse("%s is not a shard of the run of %s: its command is \"%s\", not "
                          "\"%s\"",
                          aa_echo(s[i].dir), s[0].dir, b, a);
        }
        if (strcmp(m->suite, first->suite))
            return refuse("%s is not a shard of the run of %s: its suite is %s, not %s",
                          aa_echo(s[i].dir), s[0].dir, m->suite, first->suite);
        if (strcmp(m->commit, first->commit) || m->dirty != first->dirty)
            return refuse("%s is not a shard of the run of %s: it was measured at commit "
                          "%s%s, not %s%s",
                          aa_echo(s[i].dir), s[0].dir, m->commit, m->dirty > 0 ? " (dirty)" : "",
                          first->commit, first->dirty > 0 ? " (dirty)" : "");
        if (m->cases != first->cases)
            return refuse("%s is not a shard of the run of %s: %zu cases, not %zu",
                          aa_echo(s[i].dir), s[0].dir, m->cases, first->cases);
        for (int j = 0; j < i; j++)
            if (s[j].m.shards == m->shards && s[j].m.shard == m->shard)
                return refuse("%s and %s are both shard %d/%d: a shard given twice",
                              aa_echo(s[j].dir), s[i].dir, m->shard, m->shards);
    }
    size_t cases = first->cases;
    place *owner = malloc((cases ? cases : 1) * sizeof *owner);
    int *planned = malloc((cases ? cases : 1) * sizeof *planned);
    if (!owner || !planned) {
        free(owner);
        free(planned);
        return cli_fail("merge", aa_fail(AA_ENOMEM, "out of memory for %zu cases", cases));
    }
    for (size_t c = 0; c < cases; c++)
        owner[c].shard = -1, planned[c] = -1;
    int code = 0;
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].m.nselected; k++)
            planned[s[i].m.selected[k]] = i;
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].n && !code; k++) {
            const aa_row *r = &s[i].rows[k];
            long c = r->case_index;
            if (c < 0 || (size_t)c >= cases)
                code = refuse("%s/results.csv, line %zu: %s on %s %dx%d %s has no case of the "
                              "run (%ld)",
                              aa_echo(s[i].dir), k + 2, r->method, r->pattern, r->w, r->h,
                              r->filter, c);
            else if (owner[c].shard >= 0)
                code = refuse("%s on %s %dx%d %s (case %ld) is in both %s and %s: a duplicated "
                              "shard",
                              r->method, r->pattern, r->w, r->h, r->filter, c,
                              s[owner[c].shard].dir, aa_echo(s[i].dir));
            else
                owner[c].shard = i, owner[c].row = k;
        }
    /* the cases skipped as refused: done, without rows */
    for (int i = 0; i < ns && !code; i++)
        for (size_t k = 0; k < s[i].m.nrefused && !code; k++) {
            size_t c = s[i].m.refused[k];
            if (owner[c].shard >= 0)
                code = refuse("case %zu is in both %s and %s: a duplicated shard", c,
                              s[owner[c].shard].dir, aa_echo(s[i].dir));
            else
                owner[c].shard = i, owner[c].row = REFUSED;
        }
    /* what is missing: a folder that stopped early, or a shard not given */
    for (size_t c = 0; c < cases && !code; c++) {
        if (owner[c].shard >= 0)
            continue;
        size_t left = 0;
        for (size_t d = c; d < cases; d++)
            left += owner[d].shard < 0;
        if (planned[c] >= 0) {
            const shard *sh = &s[planned[c]];
            code = refuse("%s (shard %d/%d) has not measured all its cases (%zu missing): "
                          "resume it with aabench run --resume %s",
                          aa_echo(sh->dir), sh->m.shard, sh->m.shards, left, sh->dir);
        } else {
            char missing[1024] = "";
            size_t n = 0;
            for (int k = 1; k <= first->shards && n + 1 < sizeof missing; k++) {
                int given = 0;
                for (int i = 0; i < ns; i++)
                    given |= s[i].m.shards == first->shards && s[i].m.shard == k;
                if (!given)
                    n += (size_t)snprintf(missing + n, sizeof missing - n, "%s%d/%d",
                                          n ? ", " : "", k, first->shards);
            }
            code = refuse("%zu case%s of the run %s in no folder given: shard%s %s missing",
                          left, left == 1 ? "" : "s", left == 1 ? "is" : "are",
                          strchr(missing, ',') ? "s" : "", *missing ? missing : "(of another count)");
        }
    }
    free(planned);
    if (code)
        free(owner);
    else
        *owner_out = owner;
    return code;
}

/* images/ of each shard into the merged folder's (the references each
 * shard wrote for its views are the same files). */
static int copy_images(const char *from, const char *to)
{
    char src[4200], dst[4200];
    int st = aa_pathf(src, sizeof src, "%s/images", from);
    if (st)
        return st;
    DIR *d = opendir(src);
    if (!d)
        return errno == ENOENT ? AA_OK : aa_fail(AA_EIO, "cannot read %s: %s", src, strerror(errno));
    if ((st = aa_pathf(dst, sizeof dst, "%s/images", to)) || (st = aa_mkdirs(dst))) {
        closedir(d);
        return st;
    }
    struct dirent *e;
    while (!st && (e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue; /* ., .. and temporary files */
        char a[4200], b[4200];
        if ((st = aa_pathf(a, sizeof a, "%s/%s", src, e->d_name)) ||
            (st = aa_pathf(b, sizeof b, "%s/%s", dst, e->d_name)))
            break;
        FILE *f = fopen(a, "rb");
        if (!f) {
            st = aa_fail(AA_EIO, "cannot read %s: %s", a, strerror(errno));
            break;
        }
        char *buf = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&buf, &len);
        char chunk[65536];
        size_t k;
        while (m && (k = fread(chunk, 1, sizeof chunk, f)) > 0)
            if (fwrite(chunk, 1, k, m) != k)
                break;
        int bad = ferror(f);
        fclose(f);
        if (!m || fclose(m) != 0 || bad)
            st = aa_fail(AA_EIO, "cannot read %s", a);
        else
            st = aa_file_write_atomic(b, buf, len);
        free(buf);
    }
    closedir(d);
    return st;
}

int cmd_merge(int argc, char **argv)
{
    enum { O_OUT = 256, O_CACHE };
    static const struct option opts[] = {{"out", required_argument, 0, O_OUT},
                                         {"cache", required_argument, 0, O_CACHE},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *out = NULL, *cache = NULL;
    int quiet = 0, c, st;
    cli_getopt_reset();
    while ((c = getopt_long(argc, argv, ":qh", opts, NULL)) != -1) {
        switch (c) {
        case O_OUT: out = optarg; break;
        case O_CACHE: cache = optarg; break;
        case 'q': quiet = 1; break;
        case 'h': usage(stdout); return 0;
        default: return cli_bad_option("merge", c, argv);
        }
    }
    int ns = argc - optind;
    if (ns < 1 || !out) {
        usage(stderr);
        return 2;
    }
    if ((st = cli_check_folder("--out", out, strlen("/images/") + 256)))
        return cli_fail("merge", st);
    /* the merged folder is none of the shards' (their files would be
     * overwritten) */
    char real_out[PATH_MAX], real_dir[PATH_MAX];
    if (realpath(out, real_out))
        for (int i = optind; i < argc; i++)
            if (realpath(argv[i], real_dir) && !strcmp(real_out, real_dir))
                return refuse("--out %s is one of the shards' folders: merge into another",
                              aa_echo(out));
    shard *s = calloc((size_t)ns, sizeof *s);
    if (!s)
        return cli_fail("merge", aa_fail(AA_ENOMEM, "out of memory"));
    int code = 0;
    for (int i = 0; i < ns && !code; i++) {
        char path[4200];
        s[i].dir = argv[optind + i];
        if ((st = aa_pathf(path, sizeof path, "%s/run.json", s[i].dir)))
            code = cli_fail("merge", st);
        else if ((st = aa_manifest_read(path, &s[i].m)) == AA_EIO)
            code = refuse("%s is not a run's folder: %s", aa_echo(s[i].dir), aa_last_error());
        else if (st)
            code = cli_fail("merge", st);
        else if ((st = aa_pathf(path, sizeof path, "%s/results.csv", s[i].dir)))
            code = cli_fail("merge", st);
        else if (access(path, F_OK) == 0 && (st = aa_rows_read_csv(path, &s[i].rows, &s[i].n)))
            code = cli_fail("merge", st == AA_EIO ? AA_EINVAL : st);
    }
    place *owner = NULL;
    if (!code)
        code = check_shards(s, ns, &owner);
    aa_row *rows = NULL;
    size_t cases = code ? 0 : s[0].m.cases, n = 0, nrefused = 0;
    size_t *refused = NULL;
    if (!code && (!(rows = malloc((cases ? cases : 1) * sizeof *rows)) ||
                  !(refused = malloc((cases ? cases : 1) * sizeof *refused))))
        code = cli_fail("merge", aa_fail(AA_ENOMEM, "out of memory for %zu results", cases));
    for (size_t k = 0; !code && k < cases; k++) {
        if (owner[k].row == REFUSED)
            refused[nrefused++] = k;
        else
            rows[n++] = s[owner[k].shard].rows[owner[k].row];
    }
    if (!code && (st = aa_mkdirs(out)))
        code = cli_fail("merge", st);
    for (int i = 0; i < ns && !code; i++)
        if ((st = copy_images(s[i].dir, out)))
            code = cli_fail("merge", st);
    if (!code) {
        /* the merged folder's manifest: the whole run, one part */
        aa_manifest m = s[0].m;
        aa_context context;
        char path[4200];
        aa_context_collect(&context, 0, NULL, 0);
        m.shard = m.shards = 1;
        m.selected = malloc((cases ? cases : 1) * sizeof *m.selected);
        m.nselected = cases;
        m.refused = refused, m.nrefused = nrefused;
        snprintf(m.host, sizeof m.host, "%s", context.host);
        m.context = aa_context_json(&context, 0); /* the merging machine's */
        for (size_t k = 0; m.selected && k < cases; k++)
            m.selected[k] = k;
        if (!m.selected)
            st = aa_fail(AA_ENOMEM, "out of memory");
        else if (!(st = aa_pathf(path, sizeof path, "%s/run.json", out)))
            st = aa_manifest_write(path, &m);
        free(m.selected);
        free(m.context);
        if (st)
            code = cli_fail("merge", st);
    }
    if (!code) {
        /* `run` and the run's own arguments */
        const aa_manifest *m = &s[0].m;
        char **args = calloc((size_t)m->argc + 4, sizeof *args);
        int na = 0;
        if (!args) {
            code = cli_fail("merge", aa_fail(AA_ENOMEM, "out of memory"));
        } else {
            args[na++] = "run";
            for (int k = 0; k < m->argc; k++)
                args[na++] = m->argv[k];
            if (cache)
                args[na++] = "--cache", args[na++] = (char *)cache;
            code = cli_run_write_merged(na, args, out, rows, n, nrefused, quiet);
            free(args);
        }
    }
    free(rows);
    free(refused);
    free(owner);
    for (int i = 0; i < ns; i++) {
        aa_manifest_free(&s[i].m);
        free(s[i].rows);
    }
    free(s);
    return code;
}
