/*
 * svgcss.h: the style sheets of an SVG document (<style> elements) and its
 * style attributes, and the cascade between them (patterns/svgcss.c; the
 * pattern `svg`, patterns/README.md).
 *
 * A sheet holds the rules of every <style> element of a document, in
 * document order.  The subset read is CSS 2.1's core grammar with
 * Selectors 4's type, universal, id, class and attribute selectors
 * ([a], [a=v], [a~=v], [a|=v], [a^=v], [a$=v], [a*=v]), :root, the
 * descendant and child combinators and selector lists; declarations with
 * !important.  A rule with a selector that could match but is outside the
 * subset (other pseudo-classes, pseudo-elements, the sibling combinators,
 * escapes) and every at-rule but @charset and @font-face are refused with
 * AA_EINVAL naming the sheet's line: dropped, they could change the
 * picture.  A selector of dynamic pseudo-classes only (:hover, :active,
 * :focus, :focus-visible, :focus-within, :visited, :target) never matches
 * a still picture and is left out of its list.
 */
#ifndef AA_SVGCSS_H
#define AA_SVGCSS_H

#include <stddef.h>

#include <libxml/tree.h>

typedef struct aa_css aa_css;

/* An empty sheet (AA_ENOMEM). */
int aa_css_new(aa_css **out);
void aa_css_free(aa_css *css);

/* Add the rules of the sheet text[0 ..) (of the document `name`, its
 * first character on line `line`): AA_EINVAL naming the line of anything
 * malformed or refused (nothing is added then). */
int aa_css_add(aa_css *css, const char *text, const char *name, long line);

/* The cascaded value of the property `key` (any case; a custom property,
 * --name, in its own case) for the element `node` from the sheet's rules
 * and the element's style attribute text `style` (may be NULL), by CSS
 * Cascade 4 within the author origin:
 * !important first, then the style attribute over any rule, then the
 * higher specificity, then the later declaration.  1 and the value
 * (trimmed, without !important) in buf[0 .. len) when one declares it,
 * else 0 (the presentation attribute, lower than any rule, is the
 * caller's); -1 when the value does not fit, AA_ENOMEM as -2.  *line: the
 * declaration's line in the sheet, 0 for the style attribute. */
int aa_css_value(aa_css *css, const xmlNode *node, const char *style, const char *key,
                 char *buf, size_t len, long *line);

/* The same for the nth (0: the best, as aa_css_value) of the declarations
 * of `key` that apply, in the cascade's order: 0 when there are no more.
 * A caller that finds a value invalid takes the next one (CSS Syntax 3 and
 * CSS 2.1, 4.2: a declaration with an invalid value is ignored, as if it
 * were not there). */
int aa_css_value_nth(aa_css *css, const xmlNode *node, const char *style, const char *key,
                     int nth, char *buf, size_t len, long *line);

/* Call fn for every declaration that applies to `node` (of the rules
 * matching it, then of `style`): its name name[0 .. n) and line (0 for
 * the style attribute); the first nonzero return is returned.  A
 * malformed declaration in `style` (not "name: value") is given with
 * n = 0 and name pointing at it. */
int aa_css_each(aa_css *css, const xmlNode *node, const char *style,
                int (*fn)(void *ctx, const char *name, size_t n, long line), void *ctx);

#endif
