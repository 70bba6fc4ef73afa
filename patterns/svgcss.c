/*
 * svgcss.c: style sheets and the cascade of the SVG reader (svgcss.h).
 *
 * Debian 12 ships no maintained C library for this: libcss-parser0 reads
 * CSS1 only (no child or attribute selectors), libcroco is gone, and
 * NetSurf's libcss is not packaged as a library.  The subset is small and
 * strict instead: anything outside it that could match an element is
 * refused, never skipped.
 *
 * A sheet is kept as its text with the comments blanked (newlines kept, so
 * lines still count), and for each rule its selectors and declarations as
 * spans of that text.  Specificity is Selectors 4's (a, b, c): ids;
 * classes, attribute selectors and pseudo-classes; types (the universal
 * selector counts nothing), compared in that order, packed as
 * a 2^20 + b 2^10 + c (each at most 32 per selector, so no carry).
 */
#include "svgcss.h"
#include "core.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAX_COMPOUNDS 32
#define MAX_PARTS 32

typedef struct span {
    const char *s;
    size_t n;
} span;

/* One simple selector of a compound: '#' id, '.' class, '[' attribute
 * (op 0 for [a], else one of = ~ | ^ $ *), ':' the pseudo-class :root. */
typedef struct part {
    char kind, op;
    span name, value;
} part;

/* A compound selector and the combinator before it (' ' descendant, '>'
 * child; 0 for the first). */
typedef struct compound {
    span type; /* n == 0: any */
    part parts[MAX_PARTS];
    int nparts;
    char comb;
} compound;

typedef struct selector {
    compound *c;
    int n;
    unsigned spec;
    size_t rule;
} selector;

typedef struct decl {
    span name, value;
    int important;
    long line;
} decl;

typedef struct rule {
    size_t first, n; /* its declarations */
} rule;

struct aa_css {
    char **texts; /* the sheets' texts, comments blanked */
    size_t ntexts, captexts;
    selector *sel;
    size_t nsel, capsel;
    decl *decl;
    size_t ndecl, capdecl;
    rule *rules;
    size_t nrules, caprules;
    const xmlNode *cached; /* the element of match[] */
    size_t *match, nmatch, capmatch;
};

int aa_css_new(aa_css **out)
{
    *out = calloc(1, sizeof **out);
    return *out ? AA_OK : aa_fail(AA_ENOMEM, "out of memory for a style sheet");
}

void aa_css_free(aa_css *css)
{
    if (!css)
        return;
    for (size_t k = 0; k < css->ntexts; k++)
        free(css->texts[k]);
    free(css->texts);
    for (size_t k = 0; k < css->nsel; k++)
        free(css->sel[k].c);
    free(css->sel);
    free(css->decl);
    free(css->rules);
    free(css->match);
    free(css);
}

static int grow(void **a, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return AA_OK;
    size_t c = *cap ? 2 * *cap : 16;
    while (c < need)
        c *= 2;
    void *b = realloc(*a, c * size);
    if (!b)
        return aa_fail(AA_ENOMEM, "out of memory for a style sheet");
    *a = b;
    *cap = c;
    return AA_OK;
}

static int is_ws(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

/* A character of a CSS identifier (no escapes: refused where met). */
static int is_ident(int c) { return isalnum(c) || c == '-' || c == '_' || c >= 0x80; }

/* Comments blanked to spaces (their newlines kept); -1 for one left open. */
static int blank_comments(char *s)
{
    char quote = 0;
    for (; *s; s++) {
        if (quote) {
            if (*s == '\\' && s[1])
                s++;
            else if (*s == quote)
                quote = 0;
        } else if (*s == '"' || *s == '\'') {
            quote = *s;
        } else if (s[0] == '/' && s[1] == '*') {
            char *e = strstr(s + 2, "*/");
            if (!e)
                return -1;
            for (; s < e + 2; s++)
                if (*s != '\n')
                    *s = ' ';
            s--;
        }
    }
    return 0;
}

static long lines_between(const char *a, const char *b)
{
    long n = 0;
    for (; a < b; a++)
        n += *a == '\n';
    return n;
}

/* The end of what starts at s, up to (not including) one of `stops` at
 * nesting depth 0 outside strings, or the end of the text (or `end`). */
static const char *scan_to(const char *s, const char *end, const char *stops)
{
    int depth = 0;
    char quote = 0;
    for (; s < end && *s; s++) {
        if (quote) {
            if (*s == '\\' && s + 1 < end)
                s++;
            else if (*s == quote)
                quote = 0;
        } else if (*s == '"' || *s == '\'')
            quote = *s;
        else if (*s == '(' || *s == '[')
            depth++;
        else if ((*s == ')' || *s == ']') && depth > 0)
            depth--;
        else if (!depth && strchr(stops, *s))
            return s;
    }
    return s;
}

static span trim(const char *a, const char *b)
{
    while (a < b && is_ws((unsigned char)*a))
        a++;
    while (b > a && is_ws((unsigned char)b[-1]))
        b--;
    return (span){a, (size_t)(b - a)};
}

/* One declaration a[0 .. b): 0 and *d, or -1 if it is not
 * "name: value [!important]" (a name of identifier characters, a value
 * not empty). */
static int parse_decl(const char *a, const char *b, decl *d)
{
    const char *colon = scan_to(a, b, ":");
    if (colon == b)
        return -1;
    d->name = trim(a, colon);
    if (!d->name.n)
        return -1;
    for (size_t k = 0; k < d->name.n; k++)
        if (!is_ident((unsigned char)d->name.s[k]))
            return -1;
    span v = trim(colon + 1, b);
    d->important = 0;
    const char *bang = scan_to(v.s, v.s + v.n, "!");
    if (bang < v.s + v.n) {
        span imp = trim(bang + 1, v.s + v.n);
        if (imp.n != 9 || strncasecmp(imp.s, "important", 9))
            return -1;
        d->important = 1;
        v = trim(v.s, bang);
    }
    if (!v.n)
        return -1;
    d->value = v;
    return 0;
}

/* ---- selectors ---- */

static int span_is(span s, const char *w)
{
    if (w[0] == '-' && w[1] == '-') /* a custom property's name keeps its case */
        return s.n == strlen(w) && !strncmp(s.s, w, s.n);
    return s.n == strlen(w) && !strncasecmp(s.s, w, s.n);
}

/* An identifier at *p (no escapes): its span, *p past it; n == 0 if none. */
static span ident(const char **p, const char *end)
{
    const char *a = *p;
    if (a < end && *a == '-')
        (*p)++;
    while (*p < end && is_ident((unsigned char)**p))
        (*p)++;
    span s = {a, (size_t)(*p - a)};
    if (s.n && (isdigit((unsigned char)a[0]) || (a[0] == '-' && (s.n == 1 ||
                                                               isdigit((unsigned char)a[1])))))
        s.n = 0, *p = a;
    return s;
}

/* One selector of a list, a[0 .. b), into *out (c malloc'd).  0, or 1 for
 * a selector that never matches a still picture (dynamic pseudo-classes),
 * or -1 with the reason in why. */
static int parse_selector(const char *a, const char *b, selector *out, const char **why)
{
    static const char *const dynamic[] = {"hover",        "active",       "focus",
                                          "focus-visible", "focus-within", "visited",
                                          "target"};
    compound *c = calloc(MAX_COMPOUNDS, sizeof *c);
    int n = 0, never = 0;
    unsigned ids = 0, classes = 0, types = 0;
    const char *p = a;
    char comb = 0;
    *why = "is malformed";
    if (!c) {
        *why = "is too large (out of memory)";
        return -1;
    }
    while (p < b && is_ws((unsigned char)*p))
        p++;
    while (p < b) {
        if (n == MAX_COMPOUNDS) {
            *why = "has more than 32 compound selectors";
            goto bad;
        }
        compound *k = &c[n];
        k->comb = comb;
        const char *start = p;
        if (*p == '*')
            p++;
        else if (is_ident((unsigned char)*p)) {
            k->type = ident(&p, b);
            if (!k->type.n)
                goto bad;
            types++;
        }
        if (p < b && *p == '|') {
            *why = "names a namespace (not supported)";
            goto bad;
        }
        while (p < b && strchr("#.[:", *p)) {
            if (k->nparts == MAX_PARTS) {
                *why = "has more than 32 simple selectors in a compound";
                goto bad;
            }
            part *q = &k->parts[k->nparts++];
            q->kind = *p++;
            q->op = 0;
            if (q->kind == ':' && p < b && *p == ':') {
                *why = "has a pseudo-element (not supported)";
                goto bad;
            }
            if (q->kind == '#' || q->kind == '.') {
                q->name = ident(&p, b);
                if (!q->name.n)
                    goto bad;
                if (q->kind == '#')
                    ids++;
                else
                    classes++;
            } else if (q->kind == ':') {
                q->name = ident(&p, b);
                if (!q->name.n || (p < b && *p == '(')) {
                    *why = "has a pseudo-class this reader does not match (only :root, and "
                           "the dynamic ones that never match a still picture)";
                    goto bad;
                }
                int dyn = 0;
                for (size_t j = 0; j < sizeof dynamic / sizeof dynamic[0]; j++)
                    dyn |= span_is(q->name, dynamic[j]);
                if (dyn)
                    never = 1;
                else if (!span_is(q->name, "root")) {
                    *why = "has a pseudo-class this reader does not match (only :root, and "
                           "the dynamic ones that never match a still picture)";
                    goto bad;
                }
                classes++;
            } else { /* [name op value] */
                while (p < b && is_ws((unsigned char)*p))
                    p++;
                q->name = ident(&p, b);
                if (!q->name.n)
                    goto bad;
                if (p < b && *p == '|' && !(p + 1 < b && p[1] == '=')) { /* not |= */
                    *why = "names a namespace (not supported)";
                    goto bad;
                }
                while (p < b && is_ws((unsigned char)*p))
                    p++;
                if (p < b && *p != ']') {
                    if (*p == '=')
                        q->op = '=', p++;
                    else if (p + 1 < b && strchr("~|^$*", *p) && p[1] == '=')
                        q->op = *p, p += 2;
                    else
                        goto bad;
                    while (p < b && is_ws((unsigned char)*p))
                        p++;
                    if (p < b && (*p == '"' || *p == '\'')) {
                        const char *e = memchr(p + 1, *p, (size_t)(b - p - 1));
                        if (!e)
                            goto bad;
                        q->value = (span){p + 1, (size_t)(e - p - 1)};
                        if (memchr(q->value.s, '\\', q->value.n)) {
                            *why = "has an escape (not supported)";
                            goto bad;
                        }
                        p = e + 1;
                    } else {
                        q->value = ident(&p, b);
                        if (!q->value.n)
                            goto bad;
                    }
                    while (p < b && is_ws((unsigned char)*p))
                        p++;
                }
                if (p >= b || *p != ']') {
                    if (p < b && isalpha((unsigned char)*p))
                        *why = "has an attribute selector with a case flag (not supported)";
                    goto bad;
                }
                p++;
                classes++;
            }
        }
        if (p == start)
            goto bad;
        if (p < b && *p == '\\') {
            *why = "has an escape (not supported)";
            goto bad;
        }
        n++;
        /* the combinator */
        int ws = 0;
        while (p < b && is_ws((unsigned char)*p))
            p++, ws = 1;
        if (p == b)
            break;
        if (*p == '>') {
            comb = '>';
            p++;
            while (p < b && is_ws((unsigned char)*p))
                p++;
            if (p == b)
                goto bad;
        } else if (*p == '+' || *p == '~') {
            *why = "has a sibling combinator (not supported)";
            goto bad;
        } else if (ws)
            comb = ' ';
        else
            goto bad;
    }
    if (!n)
        goto bad;
    if (ids > 32 || classes > 32 || types > 32) {
        *why = "is too specific (more than 32 of a kind)";
        goto bad;
    }
    out->c = c;
    out->n = n;
    out->spec = ids << 20 | classes << 10 | types;
    if (never) {
        free(c);
        out->c = NULL;
        return 1;
    }
    return 0;
bad:
    free(c);
    return -1;
}

/* ---- sheets ---- */

static int fail_line(const char *name, long line, const char *what, span s)
{
    return aa_fail(AA_EINVAL, "%s: line %ld: <style>: %s \"%.*s\" %s", name, line,
                   "the style sheet's", (int)(s.n > 80 ? 80 : s.n), s.s, what);
}

int aa_css_add(aa_css *css, const char *text, const char *name, long line)
{
    char *t = strdup(text);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory for a style sheet");
    const size_t nsel0 = css->nsel, ndecl0 = css->ndecl, nrules0 = css->nrules;
    int st = AA_OK;
    if (blank_comments(t)) {
        st = aa_fail(AA_EINVAL, "%s: line %ld: <style>: a comment is not closed", name, line);
        goto out;
    }
    const char *p = t, *end = t + strlen(t);
    while (!st) {
        while (p < end && is_ws((unsigned char)*p))
            p++;
        if (p == end)
            break;
        const long at = line + lines_between(t, p);
        if (!strncmp(p, "<!--", 4) || !strncmp(p, "-->", 3)) { /* CDO, CDC */
            p += *p == '<' ? 4 : 3;
            continue;
        }
        if (*p == '@') {
            const char *q = p + 1;
            span kw = ident(&q, end);
            const char *e = scan_to(q, end, ";{");
            if (span_is(kw, "charset") && e < end && *e == ';') {
                p = e + 1;
                continue;
            }
            if (span_is(kw, "font-face") && e < end && *e == '{') {
                /* fonts for text, which the reader refuses anyway */
                const char *close = scan_to(e + 1, end, "}");
                if (close == end) {
                    st = fail_line(name, at, "is not closed", (span){p, (size_t)(e - p)});
                    break;
                }
                p = close + 1;
                continue;
            }
            st = fail_line(name, at,
                           "is an at-rule this reader does not read (only @charset and "
                           "@font-face; a rule inside @media or @supports might apply)",
                           trim(p, e));
            break;
        }
        const char *open = scan_to(p, end, "{}");
        if (open == end || *open == '}') {
            st = fail_line(name, at, "is not a rule (selectors { declarations })",
                           trim(p, open));
            break;
        }
        const char *close = scan_to(open + 1, end, "}");
        if (close == end) {
            st = fail_line(name, at, "is not closed", trim(p, open));
            break;
        }
        /* the rule's declarations */
        if ((st = grow((void **)&css->rules, &css->caprules, css->nrules + 1, sizeof *css->rules)))
            break;
        rule *ru = &css->rules[css->nrules];
        ru->first = css->ndecl;
        ru->n = 0;
        for (const char *d = open + 1; d < close && !st;) {
            const char *e = scan_to(d, close, ";");
            span whole = trim(d, e);
            if (whole.n) {
                decl dc;
                long dl = line + lines_between(t, whole.s);
                if (parse_decl(whole.s, whole.s + whole.n, &dc)) {
                    st = fail_line(name, dl, "is not a declaration (name: value)", whole);
                    break;
                }
                dc.line = dl;
                if ((st = grow((void **)&css->decl, &css->capdecl, css->ndecl + 1,
                               sizeof *css->decl)))
                    break;
                css->decl[css->ndecl++] = dc;
                ru->n++;
            }
            d = e < close ? e + 1 : e;
        }
        if (st)
            break;
        /* its selectors */
        for (const char *s = p; s < open && !st;) {
            const char *e = scan_to(s, open, ",");
            selector sel;
            const char *why;
            int k = parse_selector(s, e, &sel, &why);
            if (k < 0) {
                st = fail_line(name, line + lines_between(t, s), why, trim(s, e));
                break;
            }
            if (k == 0) {
                sel.rule = css->nrules;
                if ((st = grow((void **)&css->sel, &css->capsel, css->nsel + 1,
                               sizeof *css->sel))) {
                    free(sel.c);
                    break;
                }
                css->sel[css->nsel++] = sel;
            }
            s = e < open ? e + 1 : e;
        }
        css->nrules++;
        p = close + 1;
    }
    if (!st && !(st = grow((void **)&css->texts, &css->captexts, css->ntexts + 1,
                           sizeof *css->texts))) {
        css->texts[css->ntexts++] = t;
        css->cached = NULL;
        return AA_OK;
    }
out:
    for (size_t k = nsel0; k < css->nsel; k++)
        free(css->sel[k].c);
    css->nsel = nsel0, css->ndecl = ndecl0, css->nrules = nrules0;
    free(t);
    return st;
}

/* ---- matching ---- */

static const xmlNode *parent_element(const xmlNode *n)
{
    n = n->parent;
    return n && n->type == XML_ELEMENT_NODE ? n : NULL;
}

static int node_is(const xmlChar *v, span s)
{
    return v && strlen((const char *)v) == s.n && !memcmp(v, s.s, s.n);
}

/* 1 if the white-space separated list v holds the word w. */
static int has_word(const char *v, span w)
{
    while (*v) {
        while (*v && is_ws((unsigned char)*v))
            v++;
        size_t n = 0;
        while (v[n] && !is_ws((unsigned char)v[n]))
            n++;
        if (n && n == w.n && !memcmp(v, w.s, n))
            return 1;
        v += n;
    }
    return 0;
}

static int match_part(const part *q, const xmlNode *node)
{
    if (q->kind == ':') /* :root */
        return node->parent && node->parent->type == XML_DOCUMENT_NODE;
    const char *key = q->kind == '#' ? "id" : q->kind == '.' ? "class" : NULL;
    char name[256];
    if (!key) {
        if (q->name.n >= sizeof name)
            return 0;
        memcpy(name, q->name.s, q->name.n);
        name[q->name.n] = '\0';
        key = name;
    }
    xmlChar *v = xmlGetNoNsProp(node, (const xmlChar *)key);
    if (!v)
        return 0;
    const char *s = (const char *)v;
    const size_t n = strlen(s), m = q->value.n;
    int ok;
    if (q->kind == '#')
        ok = node_is(v, q->name);
    else if (q->kind == '.')
        ok = has_word(s, q->name);
    else
        switch (q->op) {
        case 0:
            ok = 1;
            break;
        case '=':
            ok = node_is(v, q->value);
            break;
        case '~':
            ok = m && !memchr(q->value.s, ' ', m) && has_word(s, q->value);
            break;
        case '|':
            ok = n >= m && !memcmp(s, q->value.s, m) && (n == m || s[m] == '-');
            break;
        case '^':
            ok = m && n >= m && !memcmp(s, q->value.s, m);
            break;
        case '$':
            ok = m && n >= m && !memcmp(s + n - m, q->value.s, m);
            break;
        default: /* '*' */
            ok = 0;
            if (m)
                for (size_t k = 0; k + m <= n && !ok; k++)
                    ok = !memcmp(s + k, q->value.s, m);
            break;
        }
    xmlFree(v);
    return ok;
}

static int match_compound(const compound *k, const xmlNode *node)
{
    if (k->type.n && !node_is(node->name, k->type))
        return 0;
    for (int j = 0; j < k->nparts; j++)
        if (!match_part(&k->parts[j], node))
            return 0;
    return 1;
}

/* Compound k of s matches node, and those before it its ancestors as the
 * combinators say. */
static int match_from(const selector *s, int k, const xmlNode *node)
{
    if (!match_compound(&s->c[k], node))
        return 0;
    if (k == 0)
        return 1;
    for (const xmlNode *p = parent_element(node); p; p = parent_element(p)) {
        if (match_from(s, k - 1, p))
            return 1;
        if (s->c[k].comb == '>')
            return 0;
    }
    return 0;
}

/* The selectors matching node into css->match (cached for the last node). */
static int matches(aa_css *css, const xmlNode *node)
{
    if (css->cached == node)
        return AA_OK;
    css->cached = NULL;
    css->nmatch = 0;
    for (size_t k = 0; k < css->nsel; k++)
        if (match_from(&css->sel[k], css->sel[k].n - 1, node)) {
            int st = grow((void **)&css->match, &css->capmatch, css->nmatch + 1,
                          sizeof *css->match);
            if (st)
                return st;
            css->match[css->nmatch++] = k;
        }
    css->cached = node;
    return AA_OK;
}

/* ---- the cascade ---- */

/* The declarations of a style attribute, one at a time: 1 and *d (line
 * 0), or 0 at the end; a malformed one has name.n == 0 and name its text. */
static int next_inline(const char **p, const char *end, decl *d)
{
    for (;;) {
        if (*p >= end)
            return 0;
        const char *e = scan_to(*p, end, ";");
        span whole = trim(*p, e);
        *p = e < end ? e + 1 : e;
        if (!whole.n)
            continue;
        if (parse_decl(whole.s, whole.s + whole.n, d))
            d->name = (span){whole.s, 0}, d->value = whole;
        d->line = 0;
        return 1;
    }
}

static char *inline_copy(const char *style)
{
    char *t = strdup(style);
    if (t && blank_comments(t))
        t[0] = '\0'; /* an open comment runs to the end: nothing declared */
    return t;
}

/* 1 if the rank a (important, inline, specificity, order) is above b. */
static int rank_above(const long a[4], const long b[4])
{
    for (int k = 0; k < 4; k++)
        if (a[k] != b[k])
            return a[k] > b[k];
    return 0;
}

int aa_css_value_nth(aa_css *css, const xmlNode *node, const char *style, const char *key,
                     int nth, char *buf, size_t len, long *line)
{
    /* the n-th best is the best of those below the (n-1)-th: each pass
     * takes the best ranked below `below`, (important, inline,
     * specificity, order) compared in that order (the style attribute's
     * declarations are inline, 1, of no specificity) */
    long below[4] = {2, 0, 0, 0}, best[4];
    span value = {NULL, 0};
    long at = 0;
    char *t = NULL;
    if (style && !(t = inline_copy(style)))
        return -2;
    if (css && css->nsel && matches(css, node)) {
        free(t);
        return -2;
    }
    for (int pass = 0; pass <= nth; pass++) {
        best[0] = best[1] = best[2] = best[3] = -1;
        value = (span){NULL, 0};
        if (css && css->nsel)
            for (size_t i = 0; i < css->nmatch; i++) {
                const selector *s = &css->sel[css->match[i]];
                const rule *ru = &css->rules[s->rule];
                for (size_t j = ru->first; j < ru->first + ru->n; j++) {
                    const decl *d = &css->decl[j];
                    if (!span_is(d->name, key))
                        continue;
                    const long cand[4] = {d->important, 0, (long)s->spec, (long)j};
                    if (rank_above(below, cand) && rank_above(cand, best)) {
                        memcpy(best, cand, sizeof best);
                        value = d->value;
                        at = d->line;
                    }
                }
            }
        if (t) {
            const char *p = t, *end = t + strlen(t);
            decl d;
            long order = 0;
            while (next_inline(&p, end, &d)) {
                order++;
                if (!d.name.n || !span_is(d.name, key))
                    continue;
                const long cand[4] = {d.important, 1, 0, order};
                if (rank_above(below, cand) && rank_above(cand, best)) {
                    memcpy(best, cand, sizeof best);
                    value = d.value;
                    at = 0;
                }
            }
        }
        if (!value.s)
            break;
        memcpy(below, best, sizeof below);
    }
    int found = value.s != NULL;
    *line = found ? at : 0;
    if (found) {
        if (value.n >= len)
            found = -1;
        else {
            memcpy(buf, value.s, value.n);
            buf[value.n] = '\0';
        }
    }
    free(t);
    return found;
}

int aa_css_value(aa_css *css, const xmlNode *node, const char *style, const char *key,
                 char *buf, size_t len, long *line)
{
    return aa_css_value_nth(css, node, style, key, 0, buf, len, line);
}

int aa_css_each(aa_css *css, const xmlNode *node, const char *style,
                int (*fn)(void *ctx, const char *name, size_t n, long line), void *ctx)
{
    int st = AA_OK;
    if (css && css->nsel) {
        if ((st = matches(css, node)))
            return st;
        for (size_t i = 0; i < css->nmatch && !st; i++) {
            const rule *ru = &css->rules[css->sel[css->match[i]].rule];
            for (size_t j = ru->first; j < ru->first + ru->n && !st; j++)
                st = fn(ctx, css->decl[j].name.s, css->decl[j].name.n, css->decl[j].line);
        }
    }
    if (st || !style)
        return st;
    char *t = inline_copy(style);
    if (!t)
        return aa_fail(AA_ENOMEM, "out of memory reading a style attribute");
    const char *p = t, *end = t + strlen(t);
    decl d;
    while (!st && next_inline(&p, end, &d)) {
        if (d.name.n) {
            st = fn(ctx, d.name.s, d.name.n, 0);
            continue;
        }
        char bad[128]; /* a malformed declaration, as text */
        snprintf(bad, sizeof bad, "%.*s", (int)(d.value.n < 127 ? d.value.n : 127), d.value.s);
        st = fn(ctx, bad, 0, 0);
    }
    free(t);
    return st;
}
