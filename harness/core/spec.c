/*
 * spec.c: parameter specs "NAME" and "NAME:key=value,key=value".
 *
 * Patterns, filters and methods describe their parameters with a table of
 * aa_param (key, kind, default, range, help); one parser serves them all, so
 * every kind refuses bad input the same way: an unknown name lists the
 * known names, an unknown key lists the accepted keys, a bad value says the
 * accepted range.  Values are doubles in parameter order; a CHOICE value is
 * the index of its word.  Reals may be written as fractions ("4/256"), as
 * patterns/README.md writes its defaults.  A WORD value (a name found at run
 * time, such as an external renderer's) is the word's number in a table kept
 * for the life of the process, so that a spec stays an array of doubles:
 * equal words have equal numbers, and the canonical text prints the word.
 */
#define _POSIX_C_SOURCE 200809L
#include "core.h"
#include "c_numbers_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#define SPEC_MAX_TEXT 4096

size_t aa_param_count(const aa_info *info)
{
    size_t n = 0;
    if (info->params)
        while (info->params[n].kind != AA_PARAM_END)
            n++;
    return n;
}

int aa_spec_index(const aa_info *info, const char *key)
{
    size_t n = aa_param_count(info);
    for (size_t k = 0; k < n; k++)
        if (strcmp(info->params[k].key, key) == 0)
            return (int)k;
    return -1;
}

const aa_info *aa_table_find(const void *const *table, const char *name)
{
    for (size_t k = 0; table[k]; k++) {
        const aa_info *info = table[k];
        if (strcmp(info->name, name) == 0)
            return info;
    }
    return NULL;
}

/* ---- words (AA_PARAM_WORD) ---- */

/* 1 if `text` is a well-formed word (aabench.h, AA_PARAM_WORD). */
static int word_valid(const char *text)
{
    size_t n = strlen(text);
    if (n == 0 || n > AA_PARAM_WORD_MAX || !isalnum((unsigned char)text[0]))
        return 0;
    for (size_t k = 0; k < n; k++)
        if (!isalnum((unsigned char)text[k]) && !strchr("._-", text[k]))
            return 0;
    return 1;
}

/* ---- the words and texts of specs (AA_PARAM_WORD, AA_PARAM_TEXT) ---- */

/* The words and texts met so far, in one table, numbered from 1 (0 is the
 * empty text), malloc'd, never freed (they live as long as the specs that
 * number them), only appended to under the lock. */
#define TEXTS_MAX 4096
static char *text_table[TEXTS_MAX];
static int ntexts = 1;
static pthread_mutex_t texts_lock = PTHREAD_MUTEX_INITIALIZER;

/* The number of a text, added to the table if new; -1 when the table is
 * full or out of memory. */
static int text_number(const char *text)
{
    if (!*text)
        return 0;
    pthread_mutex_lock(&texts_lock);
    int found = -1;
    for (int k = 1; k < ntexts && found < 0; k++)
        if (!strcmp(text_table[k], text))
            found = k;
    if (found < 0 && ntexts < TEXTS_MAX && (text_table[ntexts] = strdup(text)))
        found = ntexts++;
    pthread_mutex_unlock(&texts_lock);
    return found;
}

const char *aa_param_text(double value)
{
    const char *t = "";
    pthread_mutex_lock(&texts_lock);
    if (value >= 1 && value < ntexts && value == floor(value))
        t = text_table[(int)value];
    pthread_mutex_unlock(&texts_lock);
    return t;
}

const char *aa_param_word(double value)
{
    return aa_param_text(value);
}

static int hex_digit(int c)
{
    return c >= '0' && c <= '9' ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
}

/* A TEXT value as given in a spec, "%XX" decoded into buf; AA_EINVAL (with
 * a message) for a '%' not followed by two hex digits, a NUL byte, a control
 * character not written %XX or a text longer than AA_PARAM_TEXT_MAX. */
static int text_decode(const aa_param *p, const char *text, char *buf)
{
    size_t n = 0;
    for (const char *c = text; *c; c++) {
        int ch = (unsigned char)*c;
        if (ch == '%') {
            int hi = hex_digit((unsigned char)c[1]), lo = hi < 0 ? -1 : hex_digit((unsigned char)c[2]);
            if (hi < 0 || lo < 0)
                return aa_fail(AA_EINVAL,
                               "%s=%s: '%%' must be followed by two hex digits (write ',' as "
                               "%%2C and '%%' as %%25)",
                               p->key, aa_echo(text));
            ch = hi * 16 + lo;
            if (ch == 0)
                return aa_fail(AA_EINVAL, "%s=%s: %%00 (a NUL byte) is not allowed", p->key,
                               aa_echo(text));
            c += 2;
        } else if (ch < 0x20 || ch == 0x7f) {
            return aa_fail(AA_EINVAL, "%s=%s: a control character must be written %%XX", p->key,
                           aa_echo(text));
        }
        if (n >= AA_PARAM_TEXT_MAX)
            return aa_fail(AA_EINVAL, "%s=%s: longer than %d bytes", p->key, aa_echo(text),
                           AA_PARAM_TEXT_MAX);
        buf[n++] = (char)ch;
    }
    buf[n] = '\0';
    return AA_OK;
}

/* A text as a spec writes it: ',', '%', control characters and DEL as %XX. */
static int text_encode(const char *text, char *buf, size_t len)
{
    size_t n = 0;
    for (const unsigned char *c = (const unsigned char *)text; *c; c++) {
        int m = *c == ',' || *c == '%' || *c < 0x20 || *c == 0x7f
                    ? snprintf(buf + n, len > n ? len - n : 0, "%%%02X", *c)
                    : snprintf(buf + n, len > n ? len - n : 0, "%c", *c);
        n += (size_t)m;
    }
    return n < len ? 0 : -1;
}

void aa_spec_default(const aa_info *info, aa_spec *out)
{
    size_t n = aa_param_count(info);
    memset(out, 0, sizeof *out);
    out->info = info;
    for (size_t k = 0; k < n && k < AA_MAX_PARAMS; k++) {
        const aa_param *p = &info->params[k];
        int w;
        /* a WORD's default is the word in `choices` (0, the empty word, if
         * that is malformed or the table is full: the method's check refuses
         * it) */
        if (p->kind == AA_PARAM_WORD)
            out->v[k] = p->choices && word_valid(p->choices) && (w = text_number(p->choices)) > 0
                            ? w
                            : 0;
        else if (p->kind == AA_PARAM_TEXT)
            out->v[k] = p->choices && strlen(p->choices) <= AA_PARAM_TEXT_MAX &&
                                (w = text_number(p->choices)) > 0
                            ? w
                            : 0;
        else
            out->v[k] = p->def;
    }
}

/* The length of the decimal number at s: [+-] digits [. digits] [e [+-] digits],
 * with digits on at least one side of the point; 0 where there is none.  strtod
 * alone would also take hexadecimal ("0x10" is 16), "inf" and "nan". */
static size_t decimal_length(const char *s)
{
    size_t n = 0, digits = 0;
    if (s[n] == '+' || s[n] == '-')
        n++;
    for (; isdigit((unsigned char)s[n]); n++)
        digits++;
    if (s[n] == '.')
        for (n++; isdigit((unsigned char)s[n]); n++)
            digits++;
    if (digits == 0)
        return 0;
    if (s[n] == 'e' || s[n] == 'E') {
        size_t e = n + 1;
        if (s[e] == '+' || s[e] == '-')
            e++;
        if (isdigit((unsigned char)s[e])) {
            while (isdigit((unsigned char)s[e]))
                e++;
            n = e;
        }
    }
    return n;
}

/* A decimal number with its length checked, read with strtod. */
static int parse_decimal(const char *text, double *value, const char **end)
{
    size_t n = decimal_length(text);
    char *stop;
    if (n == 0)
        return -1;
    errno = 0;
    *value = strtod(text, &stop);
    if (stop != text + n || errno == ERANGE)
        return -1;
    *end = stop;
    return 0;
}

/* A finite number written as a decimal or as "p/q"; the whole text.  Needs
 * C-locale numbers (aa__c_numbers). */
static int parse_real(const char *text, double *value)
{
    const char *end;
    double num, den = 1.0;
    if (parse_decimal(text, &num, &end) != 0)
        return -1;
    if (*end == '/' && (parse_decimal(end + 1, &den, &end) != 0 || den == 0.0))
        return -1;
    if (*end)
        return -1;
    *value = num / den;
    return isfinite(*value) ? 0 : -1;
}

/* The words of a "a|b|c" choice list, for messages: "a, b or c". */
static void choice_words(const char *choices, char *buf, size_t len)
{
    size_t n = 0, words = 1;
    for (const char *c = choices; *c; c++)
        words += *c == '|';
    buf[0] = '\0';
    for (size_t w = 0; w < words; w++) {
        const char *start = choices;
        for (size_t k = 0; k < w; k++)
            start = strchr(start, '|') + 1;
        const char *stop = strchr(start, '|');
        size_t wl = stop ? (size_t)(stop - start) : strlen(start);
        const char *sep = w == 0 ? "" : (w + 1 == words ? " or " : ", ");
        int m = snprintf(buf + n, len > n ? len - n : 0, "%s%.*s", sep, (int)wl, start);
        if (m < 0 || (size_t)m >= len - n)
            return;
        n += (size_t)m;
    }
}

/* The accepted range of a numeric parameter, for messages. */
static void range_text(const aa_param *p, char *buf, size_t len)
{
    if (p->kind == AA_PARAM_INT)
        snprintf(buf, len, "an integer from %.17g to %.17g", p->min, p->max);
    else
        snprintf(buf, len, "a finite number %s %.17g and <= %.17g", p->open_min ? ">" : ">=",
                 p->min, p->max);
}

static int param_parse(const aa_param *p, const char *text, double *value)
{
    char what[256];
    double v;
    if (p->kind == AA_PARAM_CHOICE) {
        size_t tl = strlen(text), index = 0;
        const char *start = p->choices;
        for (;;) {
            const char *stop = strchr(start, '|');
            size_t wl = stop ? (size_t)(stop - start) : strlen(start);
            if (wl == tl && strncmp(start, text, tl) == 0) {
                *value = (double)index;
                return AA_OK;
            }
            if (!stop)
                break;
            start = stop + 1;
            index++;
        }
        choice_words(p->choices, what, sizeof what);
        return aa_fail(AA_EINVAL, "%s=%s: accepted values are %s", p->key, aa_echo(text), what);
    }
    if (p->kind == AA_PARAM_WORD) {
        if (!word_valid(text))
            return aa_fail(AA_EINVAL,
                           "%s=%s: not a name (expected letters, digits, '.', '_' and '-', "
                           "starting with a letter or digit, at most %d characters)",
                           p->key, text, AA_PARAM_WORD_MAX);
        int w = text_number(text);
        if (w < 0)
            return aa_fail(AA_EINVAL, "%s=%s: more than %d different names and texts given",
                           p->key, text, TEXTS_MAX - 1);
        *value = w;
        return AA_OK;
    }
    if (p->kind == AA_PARAM_TEXT) {
        char buf[AA_PARAM_TEXT_MAX + 1];
        if (text_decode(p, text, buf))
            return AA_EINVAL;
        int t = text_number(buf);
        if (t < 0)
            return aa_fail(AA_EINVAL, "%s=%s: more than %d different names and texts given",
                           p->key, aa_echo(text), TEXTS_MAX - 1);
        *value = t;
        return AA_OK;
    }
    range_text(p, what, sizeof what);
    if (parse_real(text, &v) != 0)
        return aa_fail(AA_EINVAL, "%s=%s: not a number (expected %s)", p->key, aa_echo(text),
                       what);
    if (p->kind == AA_PARAM_INT && v != floor(v))
        return aa_fail(AA_EINVAL, "%s=%s: not an integer (expected %s)", p->key, aa_echo(text),
                       what);
    if (v < p->min || v > p->max || (p->open_min && v == p->min))
        return aa_fail(AA_EINVAL, "%s=%s: out of range (expected %s)", p->key, aa_echo(text),
                       what);
    *value = v;
    return AA_OK;
}

/* Values are C-locale text, whatever the program's LC_NUMERIC. */
int aa_param_parse(const aa_param *p, const char *text, double *value)
{
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, "parameter");
    if (st)
        return st;
    st = param_parse(p, text, value);
    aa__c_numbers_end(&numbers);
    return st;
}

/* "name1, name2, name3" for an unknown-name message. */
static void table_names(const void *const *table, char *buf, size_t len)
{
    size_t n = 0;
    buf[0] = '\0';
    for (size_t k = 0; table[k]; k++) {
        const aa_info *info = table[k];
        int m = snprintf(buf + n, len - n, "%s%s", k ? ", " : "", info->name);
        if (m < 0 || (size_t)m >= len - n)
            return;
        n += (size_t)m;
    }
}

static void param_keys(const aa_info *info, char *buf, size_t len)
{
    size_t n = 0, count = aa_param_count(info);
    snprintf(buf, len, "%s", count ? "" : "none");
    for (size_t k = 0; k < count; k++) {
        int m = snprintf(buf + n, len - n, "%s%s", k ? ", " : "", info->params[k].key);
        if (m < 0 || (size_t)m >= len - n)
            return;
        n += (size_t)m;
    }
}

static int parse_pairs(char *rest, const aa_info *info, const char *what, aa_spec *out)
{
    int given[AA_MAX_PARAMS] = {0};
    char keys[512];
    char *pair = rest;
    while (pair) {
        char *next = strchr(pair, ',');
        if (next)
            *next++ = '\0';
        char *eq = strchr(pair, '=');
        if (!eq || eq == pair)
            return aa_fail(AA_EINVAL, "%s %s: \"%s\" is not key=value", what, info->name,
                           aa_echo(pair));
        *eq = '\0';
        int k = aa_spec_index(info, pair);
        if (k < 0) {
            param_keys(info, keys, sizeof keys);
            return aa_fail(AA_EINVAL, "%s %s has no parameter \"%s\" (accepted: %s)", what,
                           info->name, aa_echo(pair), keys);
        }
        if (given[k]++)
            return aa_fail(AA_EINVAL, "%s %s: %s given twice", what, info->name, pair);
        int st = aa_param_parse(&info->params[k], eq + 1, &out->v[k]);
        if (st)
            return aa_fail_context(st, "%s %s", what, info->name);
        pair = next;
    }
    return AA_OK;
}

int aa_spec_parse(const char *text, const void *const *table, const char *what,
                  aa_spec *out)
{
    char buf[SPEC_MAX_TEXT], names[1024];
    if (!text || !*text)
        return aa_fail(AA_EINVAL, "empty %s spec", what);
    if (strlen(text) >= sizeof buf)
        return aa_fail(AA_EINVAL, "%s spec longer than %d characters", what, SPEC_MAX_TEXT - 1);
    strcpy(buf, text);
    char *colon = strchr(buf, ':');
    if (colon)
        *colon = '\0';
    const aa_info *info = aa_table_find(table, buf);
    if (!info) {
        table_names(table, names, sizeof names);
        return aa_fail(AA_EINVAL, "unknown %s \"%s\" (known: %s)", what, aa_echo(buf), names);
    }
    if (aa_param_count(info) > AA_MAX_PARAMS)
        return aa_fail(AA_EFAIL, "%s %s declares too many parameters", what, info->name);
    aa_spec_default(info, out);
    if (colon && !colon[1])
        return aa_fail(AA_EINVAL, "%s %s: nothing after ':' (expected key=value,...)", what,
                       info->name);
    return colon ? parse_pairs(colon + 1, info, what, out) : AA_OK;
}

/* The shortest %.Ng (N from 1 to 17) that reads back to the same double:
 * 0.6, not 0.59999999999999998.  In the C locale (the caller's
 * aa__c_numbers_enter), so strtod reads what snprintf wrote. */
static int shortest(char *buf, size_t len, double v)
{
    char t[40];
    int m = 0;
    for (int digits = 1; digits <= 17; digits++) {
        m = snprintf(t, sizeof t, "%.*g", digits, v);
        if (strtod(t, NULL) == v)
            break;
    }
    return snprintf(buf, len, "%s", t) < 0 ? -1 : m;
}

static int spec_format(const aa_spec *spec, char *buf, size_t len, int exact)
{
    const aa_info *info = spec->info;
    size_t count = aa_param_count(info);
    aa__c_numbers numbers;
    int st = aa__c_numbers_enter(&numbers, info->name);
    if (st)
        return st;
    int m = snprintf(buf, len, "%s", info->name);
    size_t n = m > 0 ? (size_t)m : 0;
    for (size_t k = 0; k < count && n < len; k++) {
        const aa_param *p = &info->params[k];
        if (p->kind == AA_PARAM_CHOICE) {
            const char *start = p->choices;
            for (int w = 0; w < (int)spec->v[k]; w++)
                start = strchr(start, '|') + 1;
            const char *stop = strchr(start, '|');
            int wl = stop ? (int)(stop - start) : (int)strlen(start);
            m = snprintf(buf + n, len - n, "%c%s=%.*s", k ? ',' : ':', p->key, wl, start);
        } else if (p->kind == AA_PARAM_WORD) {
            m = snprintf(buf + n, len - n, "%c%s=%s", k ? ',' : ':', p->key,
                         aa_param_word(spec->v[k]));
        } else if (p->kind == AA_PARAM_TEXT) {
            m = snprintf(buf + n, len - n, "%c%s=", k ? ',' : ':', p->key);
            if (m >= 0 && (size_t)m < len - n &&
                text_encode(aa_param_text(spec->v[k]), buf + n + m, len - n - (size_t)m))
                m = (int)(len - n); /* does not fit */
            else if (m >= 0 && (size_t)m < len - n)
                m += (int)strlen(buf + n + m);
        } else {
            m = snprintf(buf + n, len - n, "%c%s=", k ? ',' : ':', p->key);
            if (m >= 0 && (size_t)m < len - n) {
                int v = exact ? snprintf(buf + n + m, len - n - (size_t)m, "%.17g", spec->v[k])
                              : shortest(buf + n + m, len - n - (size_t)m, spec->v[k]);
                m = v < 0 ? v : m + v;
            }
        }
        if (m < 0)
            break;
        n += (size_t)m;
    }
    aa__c_numbers_end(&numbers);
    if (n >= len)
        return aa_fail(AA_EFAIL, "spec of %s does not fit in %zu characters", info->name, len);
    return AA_OK;
}

int aa_spec_format(const aa_spec *spec, char *buf, size_t len)
{
    return spec_format(spec, buf, len, 0);
}

int aa_spec_format_key(const aa_spec *spec, char *buf, size_t len)
{
    return spec_format(spec, buf, len, 1);
}

/* ---- sizes ---- */

/* Digits only, any number of them: a side too large to hold is out of
 * range, not malformed (AA_MAX_SIDE + 1 stands for it). */
static int parse_side(const char *s, const char *end, int *out)
{
    long v = 0;
    if (s == end)
        return -1;
    for (const char *c = s; c < end; c++) {
        if (!isdigit((unsigned char)*c))
            return -1;
        v = v * 10 + (*c - '0');
        if (v > AA_MAX_SIDE)
            v = AA_MAX_SIDE + 1;
    }
    *out = (int)v;
    return 0;
}

int aa_size_parse(const char *text, int *w, int *h)
{
    const char *x = text ? strchr(text, 'x') : NULL;
    int ww, hh;
    if (!x || parse_side(text, x, &ww) || parse_side(x + 1, x + 1 + strlen(x + 1), &hh))
        return aa_fail(AA_EINVAL, "size \"%s\" is not WxH (two whole numbers, e.g. 256x256)",
                       aa_echo(text ? text : ""));
    if (ww < 1 || hh < 1 || ww > AA_MAX_SIDE || hh > AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "size \"%s\" is out of range: each side must be from 1 to %d",
                       aa_echo(text), AA_MAX_SIDE);
    *w = ww;
    *h = hh;
    return AA_OK;
}

/* ---- memory ---- */

/* Physical memory in bytes, or 0 if unknown. */
static double physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? (double)pages * (double)size : 0.0;
}

/* The number in a one-line file such as memory.max; 0 for "max", absent
 * or unreadable, and for the v1 "no limit" (a number near 2^63). */
static double limit_file(const char *path)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    char line[64];
    double v = 0;
    if (fgets(line, sizeof line, f) != NULL && isdigit((unsigned char)line[0]))
        v = strtod(line, NULL);
    fclose(f);
    return v > 0 && v < 0x1p60 ? v : 0;
}

/* The smaller of two limits, 0 meaning none. */
static double smaller(double a, double b)
{
    return a == 0 ? b : b == 0 ? a : (a < b ? a : b);
}

/* The cgroup memory limit of this process, or 0: version 2 (memory.max of
 * its cgroup and of every cgroup above it, up to the root of the
 * hierarchy this process sees) and version 1 (memory.limit_in_bytes). */
static double cgroup_limit(const char **version)
{
    double v2 = limit_file("/sys/fs/cgroup/memory.max");
    double v1 = limit_file("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    FILE *f = fopen("/proc/self/cgroup", "r");
    char line[1024], path[1200];
    while (f != NULL && fgets(line, sizeof line, f) != NULL) {
        /* "ID:CONTROLLERS:PATH"; version 2 is "0::PATH" */
        line[strcspn(line, "\n")] = '\0';
        char *c1 = strchr(line, ':'), *c2 = c1 != NULL ? strchr(c1 + 1, ':') : NULL;
        if (c2 == NULL || c2[1] != '/')
            continue;
        *c2 = '\0';
        int v2line = strcmp(line, "0:") == 0, memory = 0;
        for (char *w = c1 + 1; *w && !memory; w += strcspn(w, ","), w += *w == ',')
            memory = strncmp(w, "memory", 6) == 0 && (w[6] == ',' || w[6] == '\0');
        if (!v2line && !memory)
            continue;
        const char *dir = c2 + 1;
        /* the cgroup, then each cgroup above it */
        char cg[1024];
        snprintf(cg, sizeof cg, "%s", dir);
        for (;;) {
            size_t n = strlen(cg);
            while (n > 1 && cg[n - 1] == '/')
                cg[--n] = '\0';
            if (v2line) {
                snprintf(path, sizeof path, "/sys/fs/cgroup%s/memory.max", cg);
                v2 = smaller(v2, limit_file(path));
            } else {
                snprintf(path, sizeof path, "/sys/fs/cgroup/memory%s/memory.limit_in_bytes", cg);
                v1 = smaller(v1, limit_file(path));
            }
            char *slash = strrchr(cg, '/');
            if (slash == NULL || slash == cg)
                break;
            *slash = '\0';
        }
    }
    if (f != NULL)
        fclose(f);
    *version = v2 != 0 && (v1 == 0 || v2 <= v1) ? "the cgroup's memory.max"
                                                 : "the cgroup's memory.limit_in_bytes";
    return smaller(v2, v1);
}

/* Address space and data in use by this process (/proc/self/statm: size,
 * and data + stack), in bytes; 0 if unknown. */
static void in_use(double *vm, double *data)
{
    *vm = *data = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f == NULL)
        return;
    unsigned long size, rss, shared, text, lib, dat;
    long page = sysconf(_SC_PAGESIZE);
    if (fscanf(f, "%lu %lu %lu %lu %lu %lu", &size, &rss, &shared, &text, &lib, &dat) == 6 &&
        page > 0) {
        *vm = (double)size * (double)page;
        *data = (double)dat * (double)page;
    }
    fclose(f);
}

/* "1.5 GB" or "300 MB". */
static void bytes_text(double b, char *buf, size_t len)
{
    if (b >= 1e9)
        snprintf(buf, len, "%.1f GB", b / 1e9);
    else
        snprintf(buf, len, "%.0f MB", b / 1e6);
}

double aa_memory_budget(char *why, size_t len)
{
    char a[32], b[32];
    double budget = 0, phys = physical_memory();
    const char *version = NULL;
    double cg = cgroup_limit(&version);
    if (why != NULL && len > 0)
        why[0] = '\0';
    /* The machine, or this process's cgroup: half of it, the rest for
     * everything else. */
    if (phys > 0 && (cg == 0 || phys <= cg)) {
        budget = phys / 2;
        bytes_text(phys, a, sizeof a);
        if (why != NULL)
            snprintf(why, len, "half of this machine's %s", a);
    } else if (cg > 0) {
        budget = cg / 2;
        bytes_text(cg, a, sizeof a);
        if (why != NULL)
            snprintf(why, len, "half of %s, %s", version, a);
    }
    /* Limits of this process (setrlimit, ulimit -v / -d): what is left. */
    double vm, data;
    in_use(&vm, &data);
    struct rlimit r;
    if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
        double left = (double)r.rlim_cur - vm;
        left = left > 0 ? left : 1;
        if (budget == 0 || left < budget) {
            budget = left;
            bytes_text((double)r.rlim_cur, a, sizeof a);
            bytes_text(vm, b, sizeof b);
            if (why != NULL)
                snprintf(why, len, "what is left of this process's address-space limit "
                         "RLIMIT_AS (ulimit -v) of %s, %s being in use", a, b);
        }
    }
    if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
        double left = (double)r.rlim_cur - data;
        left = left > 0 ? left : 1;
        if (budget == 0 || left < budget) {
            budget = left;
            bytes_text((double)r.rlim_cur, a, sizeof a);
            bytes_text(data, b, sizeof b);
            if (why != NULL)
                snprintf(why, len, "what is left of this process's data limit RLIMIT_DATA "
                         "(ulimit -d) of %s, %s being in use", a, b);
        }
    }
    return budget;
}

int aa_memory_check(double bytes, const char *what)
{
    char why[256], need[32], have[32];
    if (!(bytes <= (double)SIZE_MAX / 2))
        return aa_fail(AA_EINVAL, "%s is too large to address", what);
    double budget = aa_memory_budget(why, sizeof why);
    if (budget > 0 && bytes > budget) {
        bytes_text(bytes, need, sizeof need);
        bytes_text(budget, have, sizeof have);
        return aa_fail(AA_EINVAL, "%s needs %s of memory; the limit is %s (%s)", what, need,
                       have, why);
    }
    return AA_OK;
}

int aa_size_check(int w, int h, int channels, int copies)
{
    if (w < 1 || h < 1 || w > AA_MAX_SIDE || h > AA_MAX_SIDE || channels < 1 || copies < 1)
        return aa_fail(AA_EINVAL, "image size %dx%dx%d out of range (sides 1 to %d)", w, h,
                       channels, AA_MAX_SIDE);
    char what[64];
    snprintf(what, sizeof what, "size %dx%d (%d image%s of %d channel%s)", w, h, copies,
             copies == 1 ? "" : "s", channels, channels == 1 ? "" : "s");
    return aa_memory_check((double)w * h * channels * copies * sizeof(double), what);
}
