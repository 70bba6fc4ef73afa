/*
 * svgfile.c: an SVG file as a scene (patterns/README.md, `svg`), and the
 * reader under it (svgfile.h).
 *
 * The document is parsed by libxml2 without network access
 * (XML_PARSE_NONET), without loading a DTD or substituting entities (no
 * XML_PARSE_DTDLOAD, no XML_PARSE_NOENT), and a document declaring entities
 * in an internal DTD subset is refused, so no external entity is ever read
 * and no entity is expanded.  The tree is walked in document order; each
 * fill and each stroke becomes one layer of the scene, the last shape in the
 * document in front (painter's order), in pixel units exactly as a browser
 * draws the document at one CSS pixel per image pixel:
 *
 *   - the viewport is the root <svg>'s width and height (lengths; a
 *     percentage of the view's W or H, absent or auto the view's), at the
 *     image's top left corner; what falls outside it is clipped (the
 *     root's overflow is hidden), and everything no shape covers is black;
 *   - lengths as CSS Values 4 writes them (scan_length): px, in, cm, mm,
 *     Q, pt, pc at 96 px to the inch, em of font-size (inherited; lengths
 *     and the absolute-size keywords), ex as half an em (no font metrics:
 *     CSS's fallback), rem of the root's font-size, vw, vh, vmin and vmax
 *     of the view (the window the document is drawn in; not in the root's
 *     own size, which may make the view), and % of the nearest viewport's
 *     width, height or normalised diagonal (SVG 2, "Units");
 *   - structure (SVG 2): <use> (href or xlink:href to "#id", x, y, and
 *     width and height for <svg> and <symbol> targets; the target drawn
 *     as the use's child, inheriting from it; a missing target or a
 *     reference cycle draws nothing, as browsers do), <symbol> (drawn only
 *     through <use>; x, y, width and height laid out as a nested svg's;
 *     refX and refY its reference point, symbol_shift) and
 *     nested <svg>, each a viewport with its viewBox and
 *     preserveAspectRatio; a viewport of overflow hidden (the initial
 *     value) clips its content: a clip of the scene whose one member is
 *     the viewport's rectangle (viewport_clip), made only for content
 *     reaching beyond it by an exact bounds test (shape_clip); with
 *     overflow visible it is drawn unclipped; clip-path on a <use> clips
 *     in its user space, translate(x, y) included, and on a nested <svg>
 *     or a <symbol> in the user space it establishes (its content's),
 *     the viewport's clip within it (viewport_element);
 *   - conditional processing: systemLanguage, requiredExtensions and
 *     requiredFeatures (conditions_hold; requiredFonts and requiredFormats,
 *     SVG 1.1 Tiny's, true as browsers take them), and <switch> drawing
 *     its first child whose conditions hold (switch_choice);
 *   - style: the style attribute and <style> sheets, cascaded by CSS
 *     Cascade 4 (patterns/svgcss.c: selectors, specificity, order,
 *     !important; presentation attributes below every rule);
 *   - a declaration of an invalid value is ignored, the cascade going on
 *     (CSS 2.1, 4.2), and an invalid presentation attribute is its
 *     property's initial value (SVG 2), with a warning (prop, prop_check;
 *     geometry attributes: invalid_attr); what may be valid but is not
 *     read (a unit such as ch, a division by zero) is refused;
 *   - calc(), min(), max() and clamp() wherever a length, a number or an
 *     angle is read (scan_math); custom properties and var(), substituted
 *     before a value is parsed (var_subst); the CSS-wide keywords inherit,
 *     initial, unset and revert of every property read (css_wide);
 *   - a viewBox maps to the viewport by preserveAspectRatio (default
 *     xMidYMid meet; every alignment, meet, slice and none);
 *   - transform lists (matrix, translate, scale, rotate with or without a
 *     centre, skewX, skewY; in a declaration CSS Transforms 1's functions
 *     with units, about transform-origin in the reference box of
 *     transform-box, view-box, fill-box or stroke-box) compose from the
 *     root down and
 *     are applied to
 *     every point, control points included, which is exact for Bezier
 *     arcs under affine maps; an elliptical arc's centre maps as a point
 *     and its semi-diameters as vectors, which is exact too;
 *   - every shape is first a path in its user units (path.h): <path> with
 *     every command (M L H V Q T C S A Z, absolute and relative, implicit
 *     repeats, the number grammar of SVG paths; the arc command by SVG's
 *     implementation notes, aa_arc_endpoints; drawn up to the command with
 *     the first error, with a warning, SVG 2's error handling), <rect>
 *     with rounded corners
 *     by SVG 2's rules for rx and ry, <circle>, <ellipse>, <line>,
 *     <polygon>, <polyline>, in <g>; <title>, <desc>, <metadata> and
 *     <defs> (whose content is drawn only when referenced) draw nothing;
 *   - fill and fill-rule, as attributes or declarations; colours
 *     as CSS Color 4 writes them (names, transparent, currentColor, hex
 *     with or without alpha, rgb()/rgba() and hsl()/hsla() in the legacy
 *     and the modern forms; parse_colour) are sRGB and become linear light
 *     by the sRGB decoding; the fill closes every subpath (a line has
 *     none);
 *   - fill-opacity, stroke-opacity, the colours' alphas and opacity: a
 *     shape's alpha (`alpha` to the sink), or, for opacity on a group or
 *     on an element with both a fill and a stroke, a group composited as a
 *     whole (`group_begin`, `group_end`); color, paint-order, visibility
 *     and display;
 *   - stroke (a colour or none), stroke-width, stroke-linejoin (SVG 2's
 *     miter-clip and arcs too), stroke-linecap, stroke-miterlimit,
 *     stroke-dasharray and stroke-dashoffset (scaled by pathLength:
 *     path_length_dashes): the stroke is the path's outline in user units
 *     (aa_stroke_outline), a shape of its own after the fill, nonzero; the
 *     pattern keeps it as a stroke (aa_scene_stroke: a layer of its own
 *     with its source, so that peers stroke it themselves and `export`
 *     writes it as a stroke);
 *   - clipPath and clip-path="url(#id)" as the scene's clips (the sink's
 *     clip_begin, clip_end and clip; "clip paths" below), and clip-path as
 *     a basic shape and a geometry box ("basic shapes" below);
 *   - the root's transform and clip-path, those of its layout box: in CSS
 *     px outside its viewBox map, about the viewport's centre, the
 *     viewport clipping the content as transformed (aa_svg_read_at);
 *   - linearGradient and radialGradient as fill and stroke paint
 *     (url(#id) with an optional fallback; the sink's `gradient`;
 *     "gradients" below).
 *
 * Refused, naming the element and its line: strokes aa_stroke_outline
 * cannot draw exactly (a Bezier arc whose speed nearly vanishes, not within
 * rounding of 0; an arcs join stroke.c cannot draw), color-interpolation:
 * linearRGB on what is drawn (compositing in linear light, which no browser
 * does; on a gradient element it is read: "gradients"), <pattern> paint servers, the
 * radial gradients whose focal circle is their end circle (grad_resolve), text, images,
 * clip-path into other documents, the stroke-box of what holds a nested
 * <svg>, a <switch> or a use of a <symbol> and of a shape in a clipPath,
 * basic shapes and boxes on a nested <svg>
 * or a <symbol>, a
 * singular transform on the root, <text>, <g> and other non-shapes in a
 * clipPath, references to clip
 * paths forming a cycle, masks, filters, transform-box
 * stroke-box inside an object bounding box (its stroke not known there),
 * content beyond a viewport that clips when the sink takes no clips,
 * references to other documents, what svgcss.h refuses in a style
 * sheet, sheets for other media, any attribute or style property not
 * implemented (see css_known; in a rule, only when the rule matches a
 * drawn element), and any other element of the SVG namespace; elements of
 * other namespaces are not drawn (as a browser ignores them).  Malformed
 * XML, files over AA_SVG_MAX_BYTES, nesting deeper than AA_SVG_MAX_DEPTH
 * (<use> levels counted), more than AA_SVG_MAX_ELEMENTS elements drawn
 * (use instances counted), more than AA_SVG_MAX_SEGMENTS path segments (strokes'
 * outlines counted), numbers over AA_SVG_MAX_NUMBER and coordinates over
 * AA_SVG_MAX_COORD pixels are refused too.
 */
#include "svgfile.h"
#include "c_numbers_internal.h"
#include "svgcss.h"
#include "path.h"
#include "patterns.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <sys/stat.h>

#include <libxml/parser.h>
#include <libxml/tree.h>

#define SVG_NS "http://www.w3.org/2000/svg"
#define VAR_MAX_DEPTH 32     /* custom properties substituted within each other (var()) */
#define VAR_MAX_SUBST 10000L /* var() substitutions for one value */


/* ---- files ---- */

/* AA_EINVAL unless `path` names a regular file (a folder, a device or a
 * pipe is not a document) of at most `max` bytes. */
static int regular_file(const char *path, const char *what, size_t max)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return aa_fail(AA_EINVAL, "%s %s: %s", what, aa_echo(path), strerror(errno));
    if (!S_ISREG(st.st_mode))
        return aa_fail(AA_EINVAL, "%s %s is not a regular file", what, aa_echo(path));
    if ((unsigned long long)st.st_size > (unsigned long long)max)
        return aa_fail(AA_EINVAL, "%s %s is larger than %zu bytes", what, aa_echo(path), max);
    return AA_OK;
}

int aa_file_read_all(const char *path, size_t max, const char *what, char **data, size_t *len)
{
    *data = NULL;
    *len = 0;
    int rs = regular_file(path, what, max);
    if (rs)
        return rs;
    FILE *f = fopen(path, "rb");
    if (!f)
        return aa_fail(AA_EINVAL, "%s %s: %s", what, aa_echo(path), strerror(errno));
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap + 1);
    int st = buf ? AA_OK : aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(path));
    while (!st) {
        if (n == cap) {
            if (cap > max) {
                st = aa_fail(AA_EINVAL, "%s %s is larger than %zu bytes", what, aa_echo(path),
                             max);
                break;
            }
            char *b = realloc(buf, 2 * cap + 1);
            if (!b) {
                st = aa_fail(AA_ENOMEM, "out of memory reading %s", aa_echo(path));
                break;
            }
            buf = b, cap *= 2;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            if (ferror(f))
                st = aa_fail(AA_EIO, "cannot read %s %s", what, aa_echo(path));
            break;
        }
    }
    fclose(f);
    if (!st && n > max)
        st = aa_fail(AA_EINVAL, "%s %s is larger than %zu bytes", what, aa_echo(path), max);
    if (st) {
        free(buf);
        return st;
    }
    buf[n] = '\0';
    *data = buf;
    *len = n;
    return AA_OK;
}

int aa_file_hash(const char *path, unsigned long long *hash, size_t *len)
{
    int rs = regular_file(path, "file", SIZE_MAX);
    if (rs)
        return rs;
    FILE *f = fopen(path, "rb");
    if (!f)
        return aa_fail(AA_EINVAL, "%s: %s", aa_echo(path), strerror(errno));
    unsigned long long h = 1469598103934665603ull;
    unsigned char buf[65536];
    size_t n = 0, got;
    while ((got = fread(buf, 1, sizeof buf, f)) > 0) {
        for (size_t k = 0; k < got; k++) {
            h ^= buf[k];
            h *= 1099511628211ull;
        }
        n += got;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad)
        return aa_fail(AA_EIO, "cannot read %s", aa_echo(path));
    *hash = h;
    *len = n;
    return AA_OK;
}

/* ---- the reader's state ---- */

typedef struct mat {
    double a, b, c, d, e, f; /* x' = a x + c y + e, y' = b x + d y + f */
} mat;

/* A colour: sRGB-encoded channels in [0, 1] and an alpha, or the keyword
 * currentColor (resolved where it is used, CSS Color 4 "currentcolor"). */
typedef struct css_colour {
    double v[3], alpha;
    int current;
} css_colour;

/* The inherited paint properties (SVG 2's initial values in the root's
 * style: fill black, nonzero, no stroke, width 1, miter joins of limit 4,
 * butt caps, no dashes, opacities 1, color black, fill under the stroke,
 * visible). */
typedef struct style {
    css_colour fill, stroke, color; /* the paints, and the property color */
    /* a paint server (url(#id) to a linearGradient or radialGradient) in
     * place of the colour, or NULL */
    const xmlNode *fill_server, *stroke_server;
    int fill_none;
    aa_fill_rule rule;
    int stroke_none;
    double stroke_width;
    aa_line_join join;
    aa_line_cap cap;
    double miterlimit;
    double dash[AA_SVG_MAX_DASHES];
    size_t ndash; /* 0: none */
    double dashoffset;
    double fill_opacity, stroke_opacity; /* clamped to [0, 1] */
    int stroke_first;                     /* paint-order: the stroke under the fill */
    int visible;                          /* visibility: visible */
    aa_fill_rule clip_rule;               /* clip-rule, for the children of a clipPath */
    double font_size;                     /* font-size in px (initial medium, 16) */
} style;

/* An element with an id (the first of its id in document order). */
/* A clip given to the sink for a clipPath referenced in user space m
 * (with the object bounding box `box` under objectBoundingBox units)
 * inside clip `within`, kept so that shapes referencing it alike share it. */
typedef struct clip_made {
    const xmlNode *node;
    mat m;
    double box[4];
    int within, id;
} clip_made;

typedef struct reader {
    const aa_svg_sink *sink;
    void *ctx;
    const char *name;
    long segments;
    const xmlNode *node; /* the element being read, for messages */
    const char *grad_source; /* the gradient given next: its element and line */
    int grad_interpolation;  /* and its aa_interpolation */
    /* clip paths (svgfile.c, "clip paths") */
    const xmlNode *root;
    int clip;   /* the clip of the shapes given now (-1: none; -2 - k: the
                 * viewport vclip[k], given to the sink when first needed) */
    int nclips; /* clips given to the sink so far */
    const xmlNode *clip_stack[AA_SVG_MAX_CLIP_NESTING]; /* clipPaths being read */
    int nstack;
    clip_made *made;
    size_t nmade, capmade;
    /* structure, units and style sheets (below the reader's core) */
    aa_css *css;             /* the document's style sheets (NULL: none) */
    int from_css;            /* prop's last value came from a declaration */
    int unsupported;         /* the last value refused may be valid (prop_check) */
    const struct style *tsty; /* the style of the element whose transform is read, or
                               * NULL (its stroke box) */
    double font_size;        /* the element's font-size in px (em) */
    double vpw, vph;         /* the nearest viewport's size in user units (%) */
    double rem;              /* the root's font-size in px (rem) */
    double icbw, icbh;       /* the view's size in CSS px (vw, vh, vmin, vmax) */
    struct svg_ids *ids;     /* the elements with an id, sorted */
    long elements;           /* elements read, use instances counted */
    const xmlNode *use;      /* the <use> whose target is being read, or NULL */
    const xmlNode *chain[AA_SVG_MAX_DEPTH + 2]; /* the elements being read */
    int nvclip;              /* the viewports that clip (overflow hidden) */
    /* a bounding box being walked (geometry_box): the uses followed, the
     * use whose target is next, elements visited, nesting of the walk */
    const xmlNode *bchain[AA_SVG_MAX_DEPTH + 2];
    int nb, blevel;
    const xmlNode *bvia;
    long belements;
    struct svg_clip {
        mat m;               /* the viewport's coordinates to pixels */
        mat to;              /* and back */
        double box[4];       /* x0 y0 x1 y1 in them */
        const xmlNode *node; /* the <svg> or <symbol> */
        int outer;           /* the clip it lies within (as r->clip) */
        int id;              /* its clip given to the sink, or -1: not yet */
    } vclip[AA_SVG_MAX_DEPTH + 2];
    /* the <svg> or <symbol> whose own clip-path is being resolved, in its
     * content's user space (viewport_element), and its viewBox's size (or
     * its viewport's): what percentages in its content refer to */
    const xmlNode *clip_viewport;
    double clip_viewport_vb[2];
    /* the shape whose clip-path is being resolved where it is drawn, and
     * its style (its stroke-box); the root's viewport in CSS px */
    const xmlNode *csty_node;
    const struct style *csty;
    double rootw, rooth;
    int calc;  /* the last length scanned was a math function (scan_length) */
    int depth; /* r->chain[depth] is the element read last */
    /* custom properties being substituted (custom_value): the elements
     * and names, the first of a cycle found, substitutions made */
    const xmlNode *var_node[VAR_MAX_DEPTH];
    const char *var_name[VAR_MAX_DEPTH];
    int nvar, var_cycle;
    long var_count;
} reader;

/* AA_EINVAL naming the element and its line. */
static int fail_at(reader *r, const char *fmt, ...) AA_PRINTF(2, 3);
static int fail_at(reader *r, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (r->node)
        return aa_fail(AA_EINVAL, "%s: line %ld: <%s>: %s", r->name, xmlGetLineNo(r->node),
                       (const char *)r->node->name, msg);
    return aa_fail(AA_EINVAL, "%s: %s", r->name, msg);
}

static mat mat_mul(mat m, mat n) /* m then... m * n: apply n first, then m */
{
    mat o;
    o.a = m.a * n.a + m.c * n.b;
    o.b = m.b * n.a + m.d * n.b;
    o.c = m.a * n.c + m.c * n.d;
    o.d = m.b * n.c + m.d * n.d;
    o.e = m.a * n.e + m.c * n.f + m.e;
    o.f = m.b * n.e + m.d * n.f + m.f;
    return o;
}

static const mat identity = {1, 0, 0, 1, 0, 0};

/* ---- numbers ---- */

static int is_wsp(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

static const char *skip_wsp(const char *s)
{
    while (is_wsp((unsigned char)*s))
        s++;
    return s;
}

/* wsp* ","? wsp* */
static const char *skip_comma_wsp(const char *s)
{
    s = skip_wsp(s);
    if (*s == ',')
        s = skip_wsp(s + 1);
    return s;
}

/* A number of the SVG path grammar at *s: sign? (digits ("." digits?)? |
 * "." digits) (("e" | "E") sign? digits)?.  0 and *s advanced, or -1 when
 * there is none; -2 for a number out of range. */
static int scan_number(const char **s, double *v)
{
    const char *p = *s, *start = p;
    int digits = 0;
    if (*p == '+' || *p == '-')
        p++;
    while (isdigit((unsigned char)*p))
        p++, digits++;
    if (*p == '.') {
        p++;
        while (isdigit((unsigned char)*p))
            p++, digits++;
    }
    if (!digits)
        return -1;
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1;
        if (*q == '+' || *q == '-')
            q++;
        if (isdigit((unsigned char)*q)) {
            while (isdigit((unsigned char)*q))
                q++;
            p = q;
        }
    }
    char buf[128];
    size_t n = (size_t)(p - start);
    if (n >= sizeof buf) {
        /* long runs of digits: keep the value's magnitude honest */
        errno = 0;
        char *heap = strndup(start, n);
        if (!heap)
            return -2;
        *v = strtod(heap, NULL);
        free(heap);
    } else {
        memcpy(buf, start, n);
        buf[n] = '\0';
        *v = strtod(buf, NULL);
    }
    *s = p;
    if (!isfinite(*v) || fabs(*v) > AA_SVG_MAX_NUMBER)
        return -2;
    return 0;
}

/* ---- lengths ----
 *
 * CSS Values 4: the absolute units at 96 px to the inch (1in = 2.54cm =
 * 25.4mm = 101.6Q = 72pt = 6pc = 96px); em the element's font-size (the
 * parent's in font-size itself); ex half an em, CSS's value "where it is
 * impossible or impractical to determine the x-height" (the reader has no
 * font: a browser takes its default font's x-height, so an ex differs);
 * rem the root element's font-size (in the root's own font-size, the
 * initial medium, 16px); vw and vh 1% of the width and the height of the
 * initial containing block, which for an SVG document drawn alone is the
 * view it is drawn in (the window: the reader's view of W x H pixels at
 * `scale` pixels a CSS pixel, W / scale by H / scale CSS pixels), vmin
 * and vmax the smaller and the larger of them;
 * a percentage of the nearest viewport's width (x, width, cx, rx, x1,
 * x2), height (y, height, cy, ry, y1, y2) or normalised diagonal
 * sqrt((w^2 + h^2)/2) (any other length: r, stroke-width, dashes), SVG 2
 * "Units", in its user units (the viewBox's size when it has one). */

static const struct {
    const char *unit;
    double px;
} abs_units[] = {{"px", 1},           {"in", 96},         {"cm", 96 / 2.54}, {"mm", 96 / 25.4},
                 {"q", 96 / 101.6},   {"pt", 96.0 / 72},  {"pc", 16}};

/* The axis a percentage of the attribute or property `attr` refers to: 0
 * the width, 1 the height, 2 the normalised diagonal. */
static int length_axis(const char *attr)
{
    static const char *const xs[] = {"x", "cx", "rx", "x1", "x2", "width", "fx"};
    static const char *const ys[] = {"y", "cy", "ry", "y1", "y2", "height", "fy"};
    for (size_t k = 0; k < sizeof xs / sizeof xs[0]; k++) {
        if (!strcmp(attr, xs[k]))
            return 0;
        if (!strcmp(attr, ys[k]))
            return 1;
    }
    return 2;
}

/* the types of math functions' values (scan_math) */
enum { CALC_NUMBER, CALC_LENGTH, CALC_ANGLE, CALC_PERCENT };

static int scan_math(reader *r, const char **s, int pct, double pref, int want, double *v);
static int is_math(const char *s);

/* A number and its unit at *s (none, an absolute unit, em, ex, rem, the
 * viewport units or %) in px:
 * 0 and *s advanced; -1 for no number, -2 out of range, -3 a unit this
 * reader does not know (*s at it). */
static int scan_length(reader *r, const char **s, int axis, double *v)
{
    r->calc = 0;
    if (is_math(*s)) {
        const double w = r->vpw, h = r->vph;
        return scan_math(r, s, 1, axis == 0 ? w : axis == 1 ? h : sqrt((w * w + h * h) / 2),
                         CALC_LENGTH, v);
    }
    int k = scan_number(s, v);
    if (k == -2)
        r->unsupported = 1;
    if (k)
        return k;
    const char *u = *s;
    size_t n = 0;
    while (isalpha((unsigned char)u[n]))
        n++;
    if (u[0] == '%') {
        const double w = r->vpw, h = r->vph;
        *v *= (axis == 0 ? w : axis == 1 ? h : sqrt((w * w + h * h) / 2)) / 100;
        *s = u + 1;
    } else if (n) {
        size_t j, nu = sizeof abs_units / sizeof abs_units[0];
        for (j = 0; j < nu; j++)
            if (strlen(abs_units[j].unit) == n && !strncasecmp(u, abs_units[j].unit, n))
                break;
        if (j < nu)
            *v *= abs_units[j].px;
        else if (n == 2 && !strncasecmp(u, "em", 2))
            *v *= r->font_size;
        else if (n == 2 && !strncasecmp(u, "ex", 2))
            *v *= r->font_size / 2;
        else if (n == 3 && !strncasecmp(u, "rem", 3))
            *v *= r->rem;
        else if (n >= 2 && (u[0] == 'v' || u[0] == 'V') && !(r->icbw >= 0)) {
            r->unsupported = 1; /* in the root's size: the view is not known */
            return -3;
        } else if (n == 2 && !strncasecmp(u, "vw", 2))
            *v *= r->icbw / 100;
        else if (n == 2 && !strncasecmp(u, "vh", 2))
            *v *= r->icbh / 100;
        else if (n == 4 && !strncasecmp(u, "vmin", 4))
            *v *= fmin(r->icbw, r->icbh) / 100;
        else if (n == 4 && !strncasecmp(u, "vmax", 4))
            *v *= fmax(r->icbw, r->icbh) / 100;
        else {
            r->unsupported = 1; /* a unit of CSS (ch, lh...) may be valid */
            return -3;
        }
        *s = u + n;
    }
    if (isfinite(*v) && fabs(*v) <= AA_SVG_MAX_NUMBER)
        return 0;
    r->unsupported = 1;
    return -2;
}

/* ---- math functions ----
 *
 * CSS Values 4's calc(), min(), max() and clamp(), nested and with
 * parentheses: + and - (white space on both sides), * and /, on numbers,
 * lengths (every unit scan_length reads) and angles (deg, grad, rad,
 * turn), typed as CSS types them: a sum of one type, a product with at
 * least one number, a quotient by a number; a percentage is a length of
 * what the property's percentages refer to (`pref`, pct 1), or a
 * percentage of its own type, a hundredth where a number goes (an alpha
 * value, pct 2: calc(50% + 0.25) is invalid, as Chromium takes it), else
 * invalid (pct 0).  A
 * division by zero, infinite in CSS Values 4 (Chromium then draws the
 * largest value it holds), is out of range, so refused, as any number
 * over AA_SVG_MAX_NUMBER. */

typedef struct calc_ctx {
    reader *r;
    int pct;     /* 0 no percentage, 1 of pref, 2 a hundredth */
    double pref; /* 100% as a length */
    int depth;   /* nesting of parentheses and functions */
} calc_ctx;

/* The math function at s: 0 calc, 1 min, 2 max, 3 clamp, -1 none;
 * *n its name's length with the "(". */
static int math_function(const char *s, size_t *n)
{
    static const char *const names[] = {"calc(", "min(", "max(", "clamp("};
    for (int k = 0; k < 4; k++) {
        size_t m = strlen(names[k]);
        if (!strncasecmp(s, names[k], m)) {
            *n = m;
            return k;
        }
    }
    return -1;
}

static int is_math(const char *s)
{
    size_t n;
    return math_function(s, &n) >= 0;
}

static int calc_sum(calc_ctx *c, const char **s, double *v, int *t);

/* A value of a sum: a number, a dimension, a percentage, a sum in
 * parentheses or a math function: 0, or -1 invalid, -2 out of range, -3
 * a unit not read. */
static int calc_value(calc_ctx *c, const char **s, double *v, int *t)
{
    static const struct {
        const char *unit;
        double deg;
    } angles[] = {{"deg", 1}, {"grad", 0.9}, {"rad", 180 / M_PI}, {"turn", 360}};
    const char *p = skip_wsp(*s);
    size_t n = 1;
    int f = *p == '(' ? 0 : math_function(p, &n), e = 0;
    if (f >= 0) {
        if (++c->depth > 32) {
            c->r->unsupported = 1; /* the reader's limit */
            return -2;
        }
        p += n;
        double a[3];
        int na = 0;
        for (;;) {
            double x;
            int u;
            if ((e = calc_sum(c, &p, &x, &u)))
                return e;
            if (na && u != *t)
                return -1; /* min(), max(), clamp(): one type */
            *t = u;
            if (f == 3 && na < 3)
                a[na] = x;
            else if (f == 3)
                return -1;
            *v = !na || f == 0 ? x : f == 1 ? fmin(*v, x) : f == 2 ? fmax(*v, x) : *v;
            na++;
            if (*p != ',' || f == 0)
                break;
            p++;
        }
        if (*p != ')' || (f == 3 && na != 3))
            return -1;
        if (f == 3) /* clamp(min, value, max): max(min, min(value, max)) */
            *v = fmax(a[0], fmin(a[1], a[2]));
        c->depth--;
        p++;
    } else {
        const char *at = p;
        if (scan_number(&p, v))
            return -1;
        size_t m = 0;
        while (isalpha((unsigned char)p[m]))
            m++;
        *t = CALC_NUMBER;
        if (*p == '%') {
            if (!c->pct)
                return -1;
            *v *= c->pct == 1 ? c->pref / 100 : 0.01;
            *t = c->pct == 1 ? CALC_LENGTH : CALC_PERCENT;
            p++;
        } else if (m) {
            size_t k = 0;
            while (k < 4 && !(strlen(angles[k].unit) == m && !strncasecmp(p, angles[k].unit, m)))
                k++;
            if (k < 4) {
                *v *= angles[k].deg;
                *t = CALC_ANGLE;
                p += m;
            } else {
                p = at;
                if ((e = scan_length(c->r, &p, 2, v)))
                    return e; /* -3: a unit not read, r->unsupported set */
                *t = CALC_LENGTH;
            }
        }
    }
    if (!isfinite(*v) || fabs(*v) > AA_SVG_MAX_NUMBER) {
        c->r->unsupported = 1;
        return -2;
    }
    *s = p;
    return 0;
}

/* A product of values: * with a number on one side, / by a number. */
static int calc_product(calc_ctx *c, const char **s, double *v, int *t)
{
    int e = calc_value(c, s, v, t);
    while (!e) {
        const char *p = skip_wsp(*s);
        if (*p != '*' && *p != '/')
            break;
        const int times = *p == '*';
        double x;
        int u;
        p++;
        if ((e = calc_value(c, &p, &x, &u)))
            break;
        if (times) {
            if (*t != CALC_NUMBER && u != CALC_NUMBER)
                return -1;
            *v *= x;
            if (*t == CALC_NUMBER)
                *t = u;
        } else {
            if (u != CALC_NUMBER)
                return -1;
            if (x == 0) {
                c->r->unsupported = 1; /* infinite, or NaN */
                return -2;
            }
            *v /= x;
        }
        if (!isfinite(*v) || fabs(*v) > AA_SVG_MAX_NUMBER) {
            c->r->unsupported = 1;
            return -2;
        }
        *s = p;
    }
    return e;
}

/* A sum of products, + and - between white space; *s left after the
 * white space that ends it. */
static int calc_sum(calc_ctx *c, const char **s, double *v, int *t)
{
    int e = calc_product(c, s, v, t);
    while (!e && is_wsp((unsigned char)**s)) {
        const char *p = skip_wsp(*s);
        if ((*p != '+' && *p != '-') || !is_wsp((unsigned char)p[1]))
            break;
        const int minus = *p == '-';
        double x;
        int u;
        p++;
        if ((e = calc_product(c, &p, &x, &u)))
            break;
        if (u != *t)
            return -1;
        *v += minus ? -x : x;
        if (!isfinite(*v) || fabs(*v) > AA_SVG_MAX_NUMBER) {
            c->r->unsupported = 1;
            return -2;
        }
        *s = p;
    }
    if (!e)
        *s = skip_wsp(*s);
    return e;
}

/* A math function at *s of the type `want` (CALC_NUMBER, CALC_LENGTH: a
 * number too, in user units as SVG reads a number where a length goes,
 * as Chromium does, CALC_ANGLE), percentages as `pct` and `pref` say
 * (calc_ctx; a percentage where a number is wanted a hundredth).  0 and
 * *s advanced, r->calc set; -1 invalid, -2 out of range (refused). */
static int scan_math(reader *r, const char **s, int pct, double pref, int want, double *v)
{
    calc_ctx c = {r, pct, pref, 0};
    const char *p = *s;
    r->unsupported = 0;
    int t, e = calc_value(&c, &p, v, &t);
    if (e)
        return e;
    if (t != want && !(want == CALC_LENGTH && t == CALC_NUMBER) &&
        !(want == CALC_NUMBER && t == CALC_PERCENT))
        return -1;
    *s = p;
    r->calc = 1;
    return 0;
}

/* A whole attribute or property value that is one length. */
static int parse_length(reader *r, const char *attr, const char *text, double *v)
{
    const char *s = skip_wsp(text);
    int k = scan_length(r, &s, length_axis(attr), v);
    if (k == -2)
        return fail_at(r, "%s=\"%s\": the number is out of range (at most %g)", attr,
                       aa_echo(text), AA_SVG_MAX_NUMBER);
    if (k == -1)
        return fail_at(r, "%s=\"%s\" is not a number", attr, aa_echo(text));
    s = skip_wsp(s);
    if (k == -3 || *s)
        return fail_at(r, "%s=\"%s\" is not a length (a number, optionally of px, in, cm, mm, "
                          "Q, pt, pc, em, ex, rem, vw, vh, vmin, vmax or %%)",
                       attr, aa_echo(text));
    return AA_OK;
}

/* font-size (CSS Fonts 4): a length (em, ex and % of the parent's size),
 * or an absolute-size keyword, medium being 16px and the others its
 * multiples by the table of CSS Fonts 4 ("absolute-size"), or a
 * relative-size keyword, larger or smaller: the parent's size times or
 * over 1.2.  CSS Fonts 4 leaves that ratio to the user agent ("a ratio of
 * 1.2 is suggested" between consecutive sizes of its table, which the
 * table itself only roughly keeps); 1.2 is what Chromium and resvg take
 * whatever the parent's size (a 10px parent's larger is 12px in both), so
 * em and ex under it are theirs. */
static int parse_font_size(reader *r, const char *v, double parent, double *out)
{
    static const struct {
        const char *name;
        double size;
    } sizes[] = {{"xx-small", 16 * 3.0 / 5}, {"x-small", 16 * 3.0 / 4}, {"small", 16 * 8.0 / 9},
                 {"medium", 16},             {"large", 16 * 6.0 / 5},  {"x-large", 16 * 3.0 / 2},
                 {"xx-large", 32},           {"xxx-large", 48}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        if (!strcasecmp(v, sizes[k].name)) {
            *out = sizes[k].size;
            return AA_OK;
        }
    if (!strcasecmp(v, "larger") || !strcasecmp(v, "smaller")) {
        *out = v[0] == 'l' || v[0] == 'L' ? parent * 1.2 : parent / 1.2;
        return AA_OK;
    }
    /* em and ex of the parent's size, % of it */
    const double own = r->font_size, w = r->vpw, h = r->vph;
    r->font_size = parent;
    r->vpw = r->vph = parent; /* a percentage: of the parent's font-size */
    int st = parse_length(r, "font-size", v, out);
    r->font_size = own, r->vpw = w, r->vph = h;
    if (!st && *out < 0 && r->calc)
        *out = 0; /* CSS Values 4: a math function's value clamped to the range */
    if (!st && *out < 0)
        st = fail_at(r, "font-size=\"%s\": a negative size is an error", aa_echo(v));
    return st;
}

/* ---- properties: attributes and the style attribute ---- */

/* The properties the reader implements.  Any other presentation attribute
 * or style property is refused: skipped, it would draw another picture
 * (transform in a style, transform-origin, blending, markers, conditional
 * processing...).  CSS names and keywords are matched without regard to
 * case; attribute names are XML and keep theirs. */
static const char *const css_known[] = {
    "display",          "fill",           "fill-rule",       "stroke",
    "opacity",          "fill-opacity",   "clip-path",       "mask",
    "filter",           "visibility",     "stroke-width",    "stroke-opacity",
    "stroke-linecap",   "stroke-linejoin", "stroke-miterlimit", "stroke-dasharray",
    "stroke-dashoffset", "color",         "paint-order",     "color-interpolation",
    "clip-rule",
    "font-size",        "overflow",       "transform",       "transform-origin",
    "transform-box",    "stop-color",     "stop-opacity",
    /* properties of text only, which is refused: they change no shape */
    "font-family",      "font-style",     "font-weight",     "font-variant",
    "font-stretch",
    /* SVG 1.1's background for filters (refused), which no browser drew
     * and SVG 2 dropped; Illustrator writes it on every root */
    "enable-background"};

/* Properties that change nothing the reader draws, accepted with the
 * values listed (any value where there is no list; case-insensitive) and
 * refused, naming the element and its line, with any other: a value that
 * would draw something else.  Editors write them on every element
 * (Inkscape's style attribute holds most of them at their initial
 * values). */
static const struct {
    const char *name, *values[4], *why;
} css_noop[] = {
    /* markers, blending, non-scaling strokes: drawn at their initial value
     * only (`inherit` of the inherited marker properties then gives none
     * too: every ancestor was read) */
    {"marker", {"none", "inherit"}, "markers are not drawn"},
    {"marker-start", {"none", "inherit"}, "markers are not drawn"},
    {"marker-mid", {"none", "inherit"}, "markers are not drawn"},
    {"marker-end", {"none", "inherit"}, "markers are not drawn"},
    {"mix-blend-mode", {"normal"}, "blending is not drawn"},
    {"vector-effect", {"none"}, "vector effects are not drawn"},
    /* an isolated group of normal blending and opacity 1 is the picture
     * of its content laid on the backdrop one by one: source-over is
     * associative (Compositing and Blending 1, "Isolation") */
    {"isolation", {"auto", "isolate"}, "auto or isolate"},
    /* how to antialias is what is measured: auto and geometricPrecision
     * ask for the geometry, the exact picture; crispEdges and
     * optimizeSpeed ask to trade it away (Chromium then draws aliased) */
    {"shape-rendering", {"auto", "geometricPrecision"},
     "crispEdges and optimizeSpeed ask for another picture than the exact one"},
    /* a hint of precision, no colour */
    {"color-rendering", {"auto", "optimizeSpeed", "optimizeQuality", "inherit"},
     "auto, optimizeSpeed or optimizeQuality"},
    /* of what is refused anyway: images, filter primitives */
    {"image-rendering", {NULL}, NULL},
    {"color-interpolation-filters", {NULL}, NULL},
    {"flood-color", {NULL}, NULL},
    {"flood-opacity", {NULL}, NULL},
    {"lighting-color", {NULL}, NULL},
    /* of SVG 2 drafts' <solidcolor>, which no browser draws (Inkscape
     * writes them everywhere) */
    {"solid-color", {NULL}, NULL},
    {"solid-opacity", {NULL}, NULL},
    /* interaction */
    {"pointer-events", {NULL}, NULL},
    {"cursor", {NULL}, NULL},
    /* text only (text is refused); not `font`, which sets font-size */
    {"line-height", {NULL}, NULL},
    {"letter-spacing", {NULL}, NULL},
    {"word-spacing", {NULL}, NULL},
    {"text-anchor", {NULL}, NULL},
    {"text-align", {NULL}, NULL},
    {"text-align-last", {NULL}, NULL},
    {"text-indent", {NULL}, NULL},
    {"text-transform", {NULL}, NULL},
    {"text-orientation", {NULL}, NULL},
    {"text-rendering", {NULL}, NULL},
    {"text-decoration", {NULL}, NULL},
    {"text-decoration-line", {NULL}, NULL},
    {"text-decoration-style", {NULL}, NULL},
    {"text-decoration-color", {NULL}, NULL},
    {"writing-mode", {NULL}, NULL},
    {"direction", {NULL}, NULL},
    {"unicode-bidi", {NULL}, NULL},
    {"baseline-shift", {NULL}, NULL},
    {"dominant-baseline", {NULL}, NULL},
    {"alignment-baseline", {NULL}, NULL},
    {"white-space", {NULL}, NULL},
    {"inline-size", {NULL}, NULL},
    {"shape-inside", {NULL}, NULL},
    {"shape-subtract", {NULL}, NULL},
    {"shape-padding", {NULL}, NULL},
    {"shape-margin", {NULL}, NULL},
    {"kerning", {NULL}, NULL},
    {"font-kerning", {NULL}, NULL},
    {"font-size-adjust", {NULL}, NULL},
    {"font-feature-settings", {NULL}, NULL},
    {"font-variation-settings", {NULL}, NULL},
    {"font-variant-ligatures", {NULL}, NULL},
    {"font-variant-caps", {NULL}, NULL},
    {"font-variant-numeric", {NULL}, NULL},
    {"font-variant-east-asian", {NULL}, NULL},
    {"font-variant-position", {NULL}, NULL},
    {"font-variant-alternates", {NULL}, NULL},
    {"-inkscape-font-specification", {NULL}, NULL},
    /* no property of CSS or SVG, so no browser reads them (CSS 2.1, 4.2:
     * a declaration of an unknown property is ignored): SVG 1.2 drafts'
     * flowed text's block-progression and Inkscape's own
     * filter-blend-mode and filter-gaussianBlur-deviation, which Inkscape
     * writes in the style of shapes */
    {"block-progression", {NULL}, NULL},
    {"filter-blend-mode", {NULL}, NULL},
    {"filter-gaussianBlur-deviation", {NULL}, NULL}};

static int css_noop_index(const char *name, size_t n)
{
    for (size_t k = 0; k < sizeof css_noop / sizeof css_noop[0]; k++)
        if (strlen(css_noop[k].name) == n && !strncasecmp(css_noop[k].name, name, n))
            return (int)k;
    return -1;
}

/* Attributes that are no property and draw nothing in a still picture:
 * accessibility (WAI-ARIA's role and aria-*), focus, language, and
 * custom data (data-*, as HTML names them and SVG 2 takes them). */
static int attr_nonrendering(const char *name)
{
    static const char *const names[] = {"role", "tabindex", "focusable", "lang"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(name, names[k]))
            return 1;
    return (!strncmp(name, "aria-", 5) && name[5]) || (!strncmp(name, "data-", 5) && name[5]);
}

/* width and height on a shape they are no geometry of (SVG 2 gives them
 * to rect, svg, image, foreignObject and use only; presentation attributes
 * apply only where their property does, so a browser reads nothing of
 * them on a path or another basic shape; icon editors write them there),
 * and r on an ellipse (SVG 2 gives r to circle only: an ellipse of r alone
 * has rx and ry auto, so radius 0, and Chromium and resvg draw nothing
 * of it, where Inkscape draws a circle). */
static int attr_inert_size(const xmlNode *node, const char *name)
{
    if (!strcmp(name, "r"))
        return !strcmp((const char *)node->name, "ellipse");
    static const char *const shapes[] = {"path",     "circle",   "ellipse", "line",
                                         "polyline", "polygon"};
    if (strcmp(name, "width") && strcmp(name, "height"))
        return 0;
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
        if (!strcmp((const char *)node->name, shapes[k]))
            return 1;
    return 0;
}

/* The attributes, beyond the properties, each element reads. */
static int attr_known(const xmlNode *node, const char *name)
{
    static const struct {
        const char *element, *attrs[12];
    } own[] = {{"clipPath", {"clipPathUnits"}},
               {"linearGradient", {"x1", "y1", "x2", "y2", "gradientUnits", "gradientTransform",
                                   "spreadMethod", "href"}},
               {"radialGradient", {"cx", "cy", "r", "fx", "fy", "fr", "gradientUnits",
                                   "gradientTransform", "spreadMethod", "href"}},
               {"stop", {"offset"}},
               {"svg", {"width", "height", "viewBox", "preserveAspectRatio", "version",
                        "baseProfile", "x", "y"}},
               {"rect", {"x", "y", "width", "height", "rx", "ry", "pathLength"}},
               {"circle", {"cx", "cy", "r", "pathLength"}},
               {"ellipse", {"cx", "cy", "rx", "ry", "pathLength"}},
               {"path", {"d", "pathLength"}},
               {"polygon", {"points", "pathLength"}},
               {"polyline", {"points", "pathLength"}},
               {"line", {"x1", "y1", "x2", "y2", "pathLength"}},
               {"use", {"x", "y", "width", "height", "href"}},
               {"symbol",
                {"viewBox", "preserveAspectRatio", "x", "y", "width", "height", "refX", "refY"}}};
    static const char *const any[] = {"id",          "class",          "style",
                                      "transform",   "systemLanguage", "requiredExtensions",
                                      "requiredFeatures", "requiredFonts", "requiredFormats"};
    for (size_t k = 0; k < sizeof any / sizeof any[0]; k++)
        if (!strcmp(name, any[k]))
            return 1;
    if (attr_nonrendering(name) || attr_inert_size(node, name) ||
        css_noop_index(name, strlen(name)) >= 0)
        return 1;
    for (size_t k = 0; k < sizeof css_known / sizeof css_known[0]; k++)
        if (!strcmp(name, css_known[k]))
            return 1;
    for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
        if (!strcmp((const char *)node->name, own[k].element))
            for (size_t j = 0; j < 12 && own[k].attrs[j]; j++)
                if (!strcmp(name, own[k].attrs[j]))
                    return 1;
    return 0;
}

/* Conditional processing (SVG 2, "Conditional processing"): 1 when the
 * element's conditions hold, 0 when one does not (the element and its
 * content are not drawn; in a <switch> the next child is tried).
 *   - systemLanguage: a comma-separated list of language tags, true when
 *     one is the reader's language, "en", or begins with "en-" (the
 *     language is a prefix of the tag followed by "-"), case-insensitive;
 *     an empty list is false;
 *   - requiredExtensions: a list of extension URLs, true when every one is
 *     supported; the reader supports none (it draws no foreignObject), so
 *     the attribute is false whenever it is given, as SVG 2 says of an
 *     empty list too (Chromium holds the XHTML namespace supported: a
 *     list of it alone is true there);
 *   - requiredFeatures: no longer in SVG 2, always true in browsers. */
static int conditions_hold(const xmlNode *node)
{
    xmlChar *e = xmlGetNoNsProp(node, (const xmlChar *)"requiredExtensions");
    if (e) {
        xmlFree(e);
        return 0;
    }
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)"systemLanguage");
    if (!t)
        return 1;
    int hold = 0;
    for (const char *s = (const char *)t; *s && !hold;) {
        s = skip_wsp(s);
        size_t n = strcspn(s, ",");
        size_t m = n;
        while (m && isspace((unsigned char)s[m - 1]))
            m--;
        hold = (m == 2 || (m > 2 && s[2] == '-')) && !strncasecmp(s, "en", 2);
        s += n + (s[n] == ',');
    }
    xmlFree(t);
    return hold;
}

static int is_svg(const xmlNode *node);
static int named(const xmlNode *node, const char *name);

/* The child of a <switch> drawn (SVG 2, "The switch element"): the first
 * direct child of the SVG namespace whose conditions hold, in *chosen
 * (NULL: none).  Elements of other namespaces are passed over (Chromium
 * and resvg draw none of them as a switch's child).  A chosen child
 * that draws nothing of itself (title, desc, metadata, defs, style, a
 * paint server, clipPath...) is refused: Chromium chooses it and draws
 * nothing, resvg passes it over and draws the next. */
static int switch_choice(reader *r, const xmlNode *sw, const xmlNode **chosen)
{
    static const char *const drawn[] = {"g",    "switch",  "svg",     "use",    "path",
                                        "rect", "circle",  "ellipse", "line",   "polygon",
                                        "polyline", "text", "image",  "foreignObject", "a"};
    *chosen = NULL;
    for (const xmlNode *c = sw->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE || !is_svg(c) || !conditions_hold(c))
            continue;
        for (size_t k = 0; k < sizeof drawn / sizeof drawn[0]; k++)
            if (named(c, drawn[k])) {
                *chosen = c;
                return AA_OK;
            }
        r->node = c;
        return fail_at(r, "<%s> as the child a <switch> draws is not supported (Chromium "
                          "draws nothing, resvg the next child)",
                       (const char *)c->name);
    }
    return AA_OK;
}

/* A declaration that applies to r->node (aa_css_each): refused unless
 * its property is implemented. */
static int check_decl(void *ctx, const char *name, size_t n, long line)
{
    reader *r = ctx;
    char at[48] = "";
    if (line)
        snprintf(at, sizeof at, " (style sheet line %ld)", line);
    if (!n)
        return fail_at(r, "style: \"%s\" is not a declaration (name: value)%s",
                       aa_echo(name), at);
    for (size_t k = 0; k < sizeof css_known / sizeof css_known[0]; k++)
        if (strlen(css_known[k]) == n && !strncasecmp(css_known[k], name, n))
            return AA_OK;
    if (css_noop_index(name, n) >= 0)
        return AA_OK;
    if (n > 2 && name[0] == '-' && name[1] == '-')
        return AA_OK; /* a custom property (var_subst) */
    char prop[64];
    snprintf(prop, sizeof prop, "%.*s", (int)n, name);
    return fail_at(r, "the style property %s is not supported%s", aa_echo(prop), at);
}

static int check_noop_values(reader *r, const xmlNode *node);

/* Refuse every attribute (of no namespace: others are not SVG's) and every
 * declaration of the style attribute and of the sheets' rules matching the
 * element that the reader does not know, and a property of css_noop of a
 * value that would draw something. */
static int check_props(reader *r, const xmlNode *node)
{
    for (const xmlAttr *a = node->properties; a; a = a->next)
        if (!a->ns && !attr_known(node, (const char *)a->name))
            return fail_at(r, "the attribute %s is not supported", aa_echo((const char *)a->name));
    xmlChar *css = xmlGetNoNsProp(node, (const xmlChar *)"style");
    int st = aa_css_each(r->css, node, (const char *)css, check_decl, r);
    xmlFree(css);
    return st ? st : check_noop_values(r, node);
}

/* SVG 2's initial values of the inherited properties (an invalid
 * presentation attribute takes it; for the others the initial value is
 * what their absence gives). */
static const struct {
    const char *key, *value;
} initial_values[] = {
    {"fill", "black"},           {"stroke", "none"},           {"color", "black"},
    {"fill-rule", "nonzero"},    {"clip-rule", "nonzero"},     {"stroke-width", "1"},
    {"stroke-linecap", "butt"},  {"stroke-linejoin", "miter"}, {"stroke-miterlimit", "4"},
    {"stroke-dasharray", "none"}, {"stroke-dashoffset", "0"},  {"fill-opacity", "1"},
    {"stroke-opacity", "1"},     {"visibility", "visible"},    {"paint-order", "normal"},
    {"color-interpolation", "sRGB"}, {"font-size", "medium"}};

static int prop_check(reader *r, const char *key, const char *v, int css, int *st);
static int clip_path_check(reader *r, const char *value);
static void warn_at(reader *r, const char *fmt, ...) AA_PRINTF(2, 3);

/* The last error's reason, without the file, line and element it names. */
static const char *last_reason(void)
{
    const char *m = aa_last_error(), *e = strstr(m, ">: ");
    return e ? e + 3 : m;
}

/* The initial values of the properties not inherited that the reader
 * reads (`initial`, and `unset` of them; CSS Transforms 1 gives
 * transform-origin 50% 50%, Chromium drawing it so, where an SVG
 * element's 0 0 comes from the user agent's sheet: user_agent_value). */
static const struct {
    const char *key, *value;
} initial_own[] = {{"opacity", "1"},         {"transform", "none"},     {"display", "inline"},
                   {"overflow", "visible"},  {"clip-path", "none"},     {"mask", "none"},
                   {"filter", "none"},       {"transform-box", "view-box"},
                   {"transform-origin", "50% 50%"}, {"stop-color", "black"},
                   {"stop-opacity", "1"}};

/* The initial value of `key`, *inherited set when the property is
 * inherited; NULL for a property of neither table. */
static const char *initial_of(const char *key, int *inherited)
{
    for (size_t k = 0; k < sizeof initial_values / sizeof initial_values[0]; k++)
        if (!strcmp(key, initial_values[k].key)) {
            *inherited = 1;
            return initial_values[k].value;
        }
    *inherited = 0;
    for (size_t k = 0; k < sizeof initial_own / sizeof initial_own[0]; k++)
        if (!strcmp(key, initial_own[k].key))
            return initial_own[k].value;
    return NULL;
}

/* What the user agent's sheet gives `key` on `node` (CSS Cascade 4's
 * revert goes back to it), or NULL: overflow hidden on a nested <svg>
 * and a <symbol> (SVG 2's sheet), transform-origin 0 0 on every element
 * but the root <svg> (CSS Transforms 1's sheet). */
static const char *user_agent_value(const char *key, const xmlNode *node)
{
    const int root = node->parent && node->parent->type == XML_DOCUMENT_NODE;
    if (!strcmp(key, "overflow") && !root &&
        (!strcmp((const char *)node->name, "svg") || !strcmp((const char *)node->name, "symbol")))
        return "hidden";
    if (!strcmp(key, "transform-origin") && !root)
        return "0 0";
    return NULL;
}

/* The element `node` inherits from: the one before it in r->chain (a
 * <use> for the root of what it draws), else its parent element; NULL for
 * the root. */
static const xmlNode *style_parent(const reader *r, const xmlNode *node)
{
    for (int k = 0; k <= r->depth && k < AA_SVG_MAX_DEPTH + 2; k++)
        if (r->chain[k] == node)
            return k ? r->chain[k - 1] : NULL;
    const xmlNode *p = node->parent;
    return p && p->type == XML_ELEMENT_NODE ? p : NULL;
}

/* ---- custom properties and var() ----
 *
 * CSS Custom Properties 1: a declaration --name: value (in a sheet or a
 * style attribute; names are case-sensitive) is inherited; var(--name)
 * or var(--name, fallback) in a value is replaced by the custom
 * property's value before the value is parsed, the fallback taken when
 * the property is not declared (its initial value, the guaranteed-invalid
 * one), declared initial, or in a cycle of references (every property of
 * the cycle is invalid).  A value left with a var() of neither, or
 * invalid once substituted, is invalid at computed-value time: the
 * declaration is unset (its inherited value or its initial one), not the
 * cascade's next (prop).  A presentation attribute takes var() alike, as
 * Chromium does.  The text is substituted, a space kept between what
 * would otherwise join into one token ("var(--n)px" stays two). */


static int is_name_char(int c) { return isalnum(c) || c == '-' || c == '_' || c >= 0x80; }

static int var_subst(reader *r, const xmlNode *node, const char *in, char *out, size_t len,
                     int *st);

/* 1 if v holds a var(). */
static int has_var(const char *v)
{
    for (const char *p = v; *p; p++)
        if (!strncasecmp(p, "var(", 4) && (p == v || !is_name_char((unsigned char)p[-1])))
            return 1;
    return 0;
}

/* The computed value of the custom property `name` on node into out: 1,
 * or 0 for the guaranteed-invalid value (*st set on an error). */
static int custom_value(reader *r, const xmlNode *node, const char *name, char *out, size_t len,
                        int *st)
{
    for (const xmlNode *e = node; e; e = style_parent(r, e)) {
        char v[1024];
        long line;
        xmlChar *css = xmlGetNoNsProp(e, (const xmlChar *)"style");
        int found = aa_css_value(r->css, e, (const char *)css, name, v, sizeof v, &line);
        xmlFree(css);
        if (found == -2) {
            *st = aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
            return 0;
        }
        if (found < 0) {
            *st = fail_at(r, "%s: value too long", name);
            return 0;
        }
        /* inherit, unset, revert: the parent's (the user agent's sheet
         * declares none) */
        if (!found || !strcasecmp(v, "inherit") || !strcasecmp(v, "unset") ||
            !strcasecmp(v, "revert") || !strcasecmp(v, "revert-layer"))
            continue;
        if (!strcasecmp(v, "initial"))
            return 0;
        for (int k = 0; k < r->nvar; k++)
            if (r->var_node[k] == e && !strcmp(r->var_name[k], name)) {
                if (!r->var_cycle || r->var_cycle > k + 1)
                    r->var_cycle = k + 1; /* a cycle from k up */
                return 0;
            }
        if (r->nvar == VAR_MAX_DEPTH) {
            *st = fail_at(r, "var(): custom properties referring to each other deeper than %d "
                             "are not supported",
                          VAR_MAX_DEPTH);
            return 0;
        }
        r->var_node[r->nvar] = e;
        r->var_name[r->nvar++] = name;
        int ok = var_subst(r, e, v, out, len, st);
        r->nvar--;
        if (r->var_cycle && r->var_cycle - 1 <= r->nvar) {
            if (r->var_cycle - 1 == r->nvar)
                r->var_cycle = 0;
            return 0; /* in a cycle */
        }
        return ok;
    }
    return 0;
}

/* Append a[0 .. n) to out[*o ..), a space first if `apart` and the two
 * would join. */
static int var_put(reader *r, char *out, size_t len, size_t *o, const char *a, size_t n,
                   int apart, int *st)
{
    if (apart && n && *o && is_name_char((unsigned char)out[*o - 1]) &&
        (is_name_char((unsigned char)a[0]) || a[0] == '%' || a[0] == '('))
        if (*o + 1 < len)
            out[(*o)++] = ' ';
    if (*o + n >= len) {
        *st = fail_at(r, "var(): the value substituted is too long (%zu bytes at most)", len - 1);
        return -1;
    }
    memcpy(out + *o, a, n);
    *o += n;
    out[*o] = '\0';
    return 0;
}

/* in with its var()s substituted for node into out: 1, or 0 when a var()
 * is of the guaranteed-invalid value without a fallback or malformed
 * (*st set on an error). */
static int var_subst(reader *r, const xmlNode *node, const char *in, char *out, size_t len,
                     int *st)
{
    size_t o = 0;
    out[0] = '\0';
    for (const char *s = in; *s;) {
        if (strncasecmp(s, "var(", 4) || (s > in && is_name_char((unsigned char)s[-1]))) {
            size_t n = 1;
            if (var_put(r, out, len, &o, s, n, 0, st))
                return 0;
            s += n;
            continue;
        }
        const char *p = skip_wsp(s + 4);
        size_t m = 0;
        while (is_name_char((unsigned char)p[m]))
            m++;
        char name[128];
        if (m < 3 || strncmp(p, "--", 2) || m >= sizeof name)
            return 0;
        memcpy(name, p, m);
        name[m] = '\0';
        const char *q = skip_wsp(p + m), *fb = NULL, *end = q;
        if (*q == ',') {
            int depth = 0;
            fb = q + 1;
            for (end = fb; *end && (*end != ')' || depth); end++)
                depth += *end == '(' ? 1 : *end == ')' ? -1 : 0;
        }
        if (*end != ')')
            return 0;
        if (++r->var_count > VAR_MAX_SUBST) {
            *st = fail_at(r, "var(): more than %ld substitutions in one value", VAR_MAX_SUBST);
            return 0;
        }
        char val[1024];
        int got = custom_value(r, node, name, val, sizeof val, st);
        if (!got && !*st && fb) {
            char f[1024];
            size_t n = (size_t)(end - fb);
            if (n >= sizeof f) {
                *st = fail_at(r, "var(): a fallback too long");
                return 0;
            }
            memcpy(f, fb, n);
            f[n] = '\0';
            got = var_subst(r, node, f, val, sizeof val, st);
        }
        if (*st || !got)
            return 0;
        const char *v = skip_wsp(val);
        size_t n = strlen(v);
        while (n && is_wsp((unsigned char)v[n - 1]))
            n--;
        if (var_put(r, out, len, &o, v, n, 1, st))
            return 0;
        s = end + 1;
        if (o && is_name_char((unsigned char)out[o - 1]) &&
            (is_name_char((unsigned char)*s) || *s == '%' || *s == '(') &&
            var_put(r, out, len, &o, " ", 1, 0, st))
            return 0;
    }
    return 1;
}

/* The CSS-wide keywords (CSS Cascade 4) in buf, the value of `key` for
 * node: initial is the initial value, unset inherit or initial as the
 * property is inherited or not, revert (revert-layer: no layers) the
 * user agent sheet's value or as unset; inherit of an inherited
 * property is left to the caller (which keeps the parent's), of one not
 * inherited is the parent's value (its cascade, prop), the parent's own
 * initial or user agent value when it declares none, and at the root
 * the initial value.  1, or 0 when the property is absent. */
static int prop(reader *r, const xmlNode *node, const char *key, char *buf, size_t len, int *st);

static int css_wide(reader *r, const xmlNode *node, const char *key, char *buf, size_t len,
                    int *st)
{
    int inherited;
    const char *initial = initial_of(key, &inherited), *ua;
    if (!initial)
        return 1; /* not read here (prop_check refused what it must) */
    if (!strcasecmp(buf, "revert") || !strcasecmp(buf, "revert-layer")) {
        if ((ua = user_agent_value(key, node))) {
            snprintf(buf, len, "%s", ua);
            return 1;
        }
        snprintf(buf, len, "unset");
    }
    if (!strcasecmp(buf, "unset"))
        snprintf(buf, len, "%s", inherited ? "inherit" : "initial");
    if (!strcasecmp(buf, "initial")) {
        snprintf(buf, len, "%s", initial);
        return 1;
    }
    if (inherited || strcasecmp(buf, "inherit"))
        return 1;
    const xmlNode *parent = style_parent(r, node);
    if (parent) {
        if (prop(r, parent, key, buf, len, st) || *st)
            return !*st;
        if ((ua = user_agent_value(key, parent)))
            initial = ua;
    }
    snprintf(buf, len, "%s", initial);
    r->from_css = 1;
    return 1;
}

/* The value of property `key` for the element: the cascade of the style
 * sheets and the style attribute (aa_css_value_nth) wins over the
 * presentation attribute, which is lower than any rule.  A declaration
 * whose value is invalid (prop_check) is ignored, the next in the
 * cascade taking its place (CSS 2.1, 4.2; CSS Syntax 3); a presentation
 * attribute whose value is invalid is its property's initial value (SVG 2,
 * "Attribute syntax"), or absent when that is the same, with a warning
 * naming it.  A value with var() is substituted (var_subst), unset when
 * invalid then; the CSS-wide keywords are resolved (css_wide).  A value
 * that may be valid but is not drawn is refused in *st.  Written into
 * buf; 1 if given (r->from_css: by a declaration, not the attribute). */
static int prop(reader *r, const xmlNode *node, const char *key, char *buf, size_t len, int *st)
{
    xmlChar *css = xmlGetNoNsProp(node, (const xmlChar *)"style");
    long line = 0;
    int found = 0, var = 0;
    /* the declarations in the cascade's order, the first valid one
     * winning (an invalid one is ignored, CSS 2.1 4.2); one with var()
     * is valid until its computed value is known */
    for (int nth = 0; !*st; nth++) {
        found = aa_css_value_nth(r->css, node, (const char *)css, key, nth, buf, len, &line);
        if (found <= 0)
            break;
        if ((var = has_var(buf)))
            break;
        int ok = prop_check(r, key, buf, 1, st);
        if (ok)
            break;
        found = 0;
        if (*st)
            break;
        if (line)
            warn_at(r, "style sheet line %ld: %s: \"%s\" is invalid (%s): the declaration is "
                       "ignored, as CSS says",
                    line, key, aa_echo(buf), last_reason());
        else
            warn_at(r, "style: %s: \"%s\" is invalid (%s): the declaration is ignored, as CSS "
                       "says",
                    key, aa_echo(buf), last_reason());
    }
    xmlFree(css);
    r->from_css = found > 0;
    if (*st)
        return 0;
    if (found == -2) {
        *st = aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
        return 0;
    }
    if (found < 0) {
        *st = fail_at(r, "style %s: value too long", key);
        return 0;
    }
    if (!found) {
        xmlChar *v = xmlGetNoNsProp(node, (const xmlChar *)key);
        if (!v)
            return 0;
        const char *a = skip_wsp((const char *)v);
        size_t n = strlen(a);
        while (n && is_wsp((unsigned char)a[n - 1]))
            n--;
        if (n >= len)
            *st = fail_at(r, "%s: value too long", key);
        else {
            memcpy(buf, a, n);
            buf[n] = '\0';
            found = 1;
        }
        xmlFree(v);
        const char *initial = NULL;
        if (found && !strcmp(key, "transform") &&
            (!strcasecmp(buf, "inherit") || !strcasecmp(buf, "initial") ||
             !strcasecmp(buf, "unset") || !strcasecmp(buf, "revert") ||
             !strcasecmp(buf, "revert-layer"))) {
            /* not SVG's transform list: ignored (Chromium ignores
             * transform="inherit", where it takes opacity="inherit") */
            warn_at(r, "transform=\"%s\" is not a transform list: ignored, as browsers ignore it",
                    aa_echo(buf));
            return 0;
        }
        if (found && !(var = has_var(buf)) && !prop_check(r, key, buf, 0, st) && !*st) {
            /* SVG 2, "Attribute syntax": an attribute that does not parse is
             * as if it were given its initial value */
            int inherited;
            initial = initial_of(key, &inherited);
            if (!inherited)
                initial = NULL;
            warn_at(r, "%s=\"%s\" is invalid (%s): %s%s, as SVG 2 says", key, aa_echo(buf),
                    last_reason(), initial ? "its initial value " : "ignored",
                    initial ? initial : "");
            if (initial)
                snprintf(buf, len, "%s", initial);
            found = initial != NULL;
        }
        if (*st)
            found = 0;
        r->from_css = 0;
    }
    if (!found)
        return 0;
    if (var) {
        const int from_css = r->from_css;
        char *sub = malloc(len);
        if (!sub) {
            *st = aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
            return 0;
        }
        r->var_count = 0;
        int ok = var_subst(r, node, buf, sub, len, st);
        if (ok && !*st) {
            const char *t = skip_wsp(sub);
            size_t n = strlen(t);
            while (n && is_wsp((unsigned char)t[n - 1]))
                n--;
            memmove(buf, t, n);
            buf[n] = '\0';
            ok = n && prop_check(r, key, buf, from_css, st);
        }
        free(sub);
        if (*st)
            return 0;
        if (!ok) {
            warn_at(r, "%s: a value with var() is invalid once substituted: unset, as CSS says",
                    key);
            snprintf(buf, len, "unset");
        }
        r->from_css = from_css;
    }
    return css_wide(r, node, key, buf, len, st);
}

/* The properties of css_noop with a list of values: refused with any
 * other (prop: in the cascade's order, an invalid declaration ignored). */
static int check_noop_values(reader *r, const xmlNode *node)
{
    char v[256];
    int st = AA_OK;
    for (size_t k = 0; k < sizeof css_noop / sizeof css_noop[0] && !st; k++) {
        if (!css_noop[k].values[0] || !prop(r, node, css_noop[k].name, v, sizeof v, &st) || st)
            continue;
        int ok = 0;
        for (int j = 0; j < 4 && css_noop[k].values[j] && !ok; j++)
            ok = !strcasecmp(v, css_noop[k].values[j]);
        if (ok)
            continue;
        /* a sheet's declaration: its line too (a declaration of these is
         * never invalid, so the winning one is the cascade's first) */
        long line = 0;
        char at[48] = "", w[256];
        if (r->from_css) {
            xmlChar *css = xmlGetNoNsProp(node, (const xmlChar *)"style");
            if (aa_css_value(r->css, node, (const char *)css, css_noop[k].name, w, sizeof w,
                             &line) <= 0)
                line = 0;
            xmlFree(css);
        }
        if (line)
            snprintf(at, sizeof at, " (style sheet line %ld)", line);
        st = fail_at(r, "%s=\"%s\" is not supported (%s)%s", css_noop[k].name, aa_echo(v),
                     css_noop[k].why, at);
    }
    return st;
}

/* ---- colours ---- */

static const struct {
    const char *name;
    unsigned rgb;
} named_colours[] = {
    {"aliceblue", 0xf0f8ff},
    {"antiquewhite", 0xfaebd7},
    {"aqua", 0x00ffff},
    {"aquamarine", 0x7fffd4},
    {"azure", 0xf0ffff},
    {"beige", 0xf5f5dc},
    {"bisque", 0xffe4c4},
    {"black", 0x000000},
    {"blanchedalmond", 0xffebcd},
    {"blue", 0x0000ff},
    {"blueviolet", 0x8a2be2},
    {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887},
    {"cadetblue", 0x5f9ea0},
    {"chartreuse", 0x7fff00},
    {"chocolate", 0xd2691e},
    {"coral", 0xff7f50},
    {"cornflowerblue", 0x6495ed},
    {"cornsilk", 0xfff8dc},
    {"crimson", 0xdc143c},
    {"cyan", 0x00ffff},
    {"darkblue", 0x00008b},
    {"darkcyan", 0x008b8b},
    {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9},
    {"darkgreen", 0x006400},
    {"darkgrey", 0xa9a9a9},
    {"darkkhaki", 0xbdb76b},
    {"darkmagenta", 0x8b008b},
    {"darkolivegreen", 0x556b2f},
    {"darkorange", 0xff8c00},
    {"darkorchid", 0x9932cc},
    {"darkred", 0x8b0000},
    {"darksalmon", 0xe9967a},
    {"darkseagreen", 0x8fbc8f},
    {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f},
    {"darkslategrey", 0x2f4f4f},
    {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3},
    {"deeppink", 0xff1493},
    {"deepskyblue", 0x00bfff},
    {"dimgray", 0x696969},
    {"dimgrey", 0x696969},
    {"dodgerblue", 0x1e90ff},
    {"firebrick", 0xb22222},
    {"floralwhite", 0xfffaf0},
    {"forestgreen", 0x228b22},
    {"fuchsia", 0xff00ff},
    {"gainsboro", 0xdcdcdc},
    {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700},
    {"goldenrod", 0xdaa520},
    {"gray", 0x808080},
    {"grey", 0x808080},
    {"green", 0x008000},
    {"greenyellow", 0xadff2f},
    {"honeydew", 0xf0fff0},
    {"hotpink", 0xff69b4},
    {"indianred", 0xcd5c5c},
    {"indigo", 0x4b0082},
    {"ivory", 0xfffff0},
    {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa},
    {"lavenderblush", 0xfff0f5},
    {"lawngreen", 0x7cfc00},
    {"lemonchiffon", 0xfffacd},
    {"lightblue", 0xadd8e6},
    {"lightcoral", 0xf08080},
    {"lightcyan", 0xe0ffff},
    {"lightgoldenrodyellow", 0xfafad2},
    {"lightgray", 0xd3d3d3},
    {"lightgreen", 0x90ee90},
    {"lightgrey", 0xd3d3d3},
    {"lightpink", 0xffb6c1},
    {"lightsalmon", 0xffa07a},
    {"lightseagreen", 0x20b2aa},
    {"lightskyblue", 0x87cefa},
    {"lightslategray", 0x778899},
    {"lightslategrey", 0x778899},
    {"lightsteelblue", 0xb0c4de},
    {"lightyellow", 0xffffe0},
    {"lime", 0x00ff00},
    {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6},
    {"magenta", 0xff00ff},
    {"maroon", 0x800000},
    {"mediumaquamarine", 0x66cdaa},
    {"mediumblue", 0x0000cd},
    {"mediumorchid", 0xba55d3},
    {"mediumpurple", 0x9370db},
    {"mediumseagreen", 0x3cb371},
    {"mediumslateblue", 0x7b68ee},
    {"mediumspringgreen", 0x00fa9a},
    {"mediumturquoise", 0x48d1cc},
    {"mediumvioletred", 0xc71585},
    {"midnightblue", 0x191970},
    {"mintcream", 0xf5fffa},
    {"mistyrose", 0xffe4e1},
    {"moccasin", 0xffe4b5},
    {"navajowhite", 0xffdead},
    {"navy", 0x000080},
    {"oldlace", 0xfdf5e6},
    {"olive", 0x808000},
    {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500},
    {"orangered", 0xff4500},
    {"orchid", 0xda70d6},
    {"palegoldenrod", 0xeee8aa},
    {"palegreen", 0x98fb98},
    {"paleturquoise", 0xafeeee},
    {"palevioletred", 0xdb7093},
    {"papayawhip", 0xffefd5},
    {"peachpuff", 0xffdab9},
    {"peru", 0xcd853f},
    {"pink", 0xffc0cb},
    {"plum", 0xdda0dd},
    {"powderblue", 0xb0e0e6},
    {"purple", 0x800080},
    {"red", 0xff0000},
    {"rosybrown", 0xbc8f8f},
    {"royalblue", 0x4169e1},
    {"saddlebrown", 0x8b4513},
    {"salmon", 0xfa8072},
    {"sandybrown", 0xf4a460},
    {"seagreen", 0x2e8b57},
    {"seashell", 0xfff5ee},
    {"sienna", 0xa0522d},
    {"silver", 0xc0c0c0},
    {"skyblue", 0x87ceeb},
    {"slateblue", 0x6a5acd},
    {"slategray", 0x708090},
    {"slategrey", 0x708090},
    {"snow", 0xfffafa},
    {"springgreen", 0x00ff7f},
    {"steelblue", 0x4682b4},
    {"tan", 0xd2b48c},
    {"teal", 0x008080},
    {"thistle", 0xd8bfd8},
    {"tomato", 0xff6347},
    {"turquoise", 0x40e0d0},
    {"violet", 0xee82ee},
    {"wheat", 0xf5deb3},
    {"white", 0xffffff},
    {"whitesmoke", 0xf5f5f5},
    {"yellow", 0xffff00},
    {"yellowgreen", 0x9acd32},
};

/* sRGB-encoded v in [0, 1] to linear light. */
static double srgb_decode(double v)
{
    if (v <= 0)
        return 0;
    if (v >= 1)
        return 1;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

static int hex(int c)
{
    return c >= '0' && c <= '9' ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
}

/* The arguments of a colour function after its "(": up to four numbers,
 * each with its unit ('%', an angle's, or none), in the legacy form
 * (commas between all of them) or the modern one (white space, the alpha
 * after "/"); CSS Color 4, "rgb()" and "hsl()".  *n their count, *slash
 * whether an alpha was given in either form.  -1 on a syntax error. */
static int colour_args(const char *s, double x[4], char unit[4][5], int *n, int *legacy)
{
    *n = 0;
    *legacy = -1;
    s = skip_wsp(s);
    for (;;) {
        if (*n == 4)
            return -1;
        if (scan_number(&s, &x[*n]))
            return -1;
        size_t u = 0;
        while (u < 4 && (isalpha((unsigned char)*s) || *s == '%'))
            unit[*n][u++] = (char)tolower((unsigned char)*s++);
        if (isalpha((unsigned char)*s) || *s == '%')
            return -1;
        unit[*n][u] = '\0';
        (*n)++;
        s = skip_wsp(s);
        if (*s == ')')
            return *skip_wsp(s + 1) ? -1 : 0;
        if (*s == ',') {
            if (*legacy == 0)
                return -1;
            *legacy = 1;
            s = skip_wsp(s + 1);
        } else if (*s == '/') {
            if (*legacy == 1 || *n != 3)
                return -1;
            *legacy = 0;
            s = skip_wsp(s + 1);
        } else {
            if (*legacy == 1)
                return -1;
            *legacy = 0;
        }
    }
}

/* An <alpha-value> (a number, or a percentage), clamped to [0, 1]. */
static int alpha_value(double x, const char *unit, double *a)
{
    if (*unit && strcmp(unit, "%"))
        return -1;
    *a = *unit ? x / 100 : x;
    *a = *a < 0 ? 0 : *a > 1 ? 1 : *a;
    return 0;
}

/* HSL to sRGB (CSS Color 4, "Converting HSL colors to sRGB"): with hue h
 * in degrees, s and l in [0, 1], channel n (0, 8, 4 for red, green and
 * blue) is l - a max(-1, min(k - 3, 9 - k, 1)), k = (n + h/30) mod 12,
 * a = s min(l, 1 - l). */
static void hsl_to_rgb(double h, double sat, double l, double v[3])
{
    static const double n[3] = {0, 8, 4};
    h = fmod(h, 360);
    if (h < 0)
        h += 360;
    const double a = sat * fmin(l, 1 - l);
    for (int c = 0; c < 3; c++) {
        double k = fmod(n[c] + h / 30, 12);
        v[c] = l - a * fmax(-1, fmin(fmin(k - 3, 9 - k), 1));
    }
}

/* A colour value of the property `what` (CSS Color 4): a name (any case),
 * transparent, currentColor, #rgb, #rgba, #rrggbb, #rrggbbaa, rgb() and
 * rgba() (numbers or percentages, an alpha), hsl() and hsla() (a hue in
 * degrees or an angle, percentages, an alpha); legacy (commas) or modern
 * (white space, "/ alpha") forms. */
static int parse_colour(reader *r, const char *what, const char *text, css_colour *c)
{
    c->alpha = 1;
    c->current = 0;
    size_t n = strlen(text);
    if (!strcasecmp(text, "currentColor")) {
        c->current = 1;
        c->v[0] = c->v[1] = c->v[2] = 0;
        return AA_OK;
    }
    if (!strcasecmp(text, "transparent")) { /* rgb(0 0 0 / 0) */
        c->v[0] = c->v[1] = c->v[2] = 0;
        c->alpha = 0;
        return AA_OK;
    }
    if (text[0] == '#') {
        int d[8];
        if (n != 4 && n != 5 && n != 7 && n != 9)
            goto bad_hex;
        for (size_t k = 1; k < n; k++)
            if ((d[k - 1] = hex((unsigned char)text[k])) < 0)
                goto bad_hex;
        const int shorthand = n <= 5;
        for (int k = 0; k < 3; k++)
            c->v[k] = (shorthand ? d[k] * 17 : d[2 * k] * 16 + d[2 * k + 1]) / 255.0;
        if (n == 5)
            c->alpha = d[3] * 17 / 255.0;
        if (n == 9)
            c->alpha = (d[6] * 16 + d[7]) / 255.0;
        return AA_OK;
    }
    const int rgb = !strncasecmp(text, "rgb(", 4) || !strncasecmp(text, "rgba(", 5);
    const int hsl = !strncasecmp(text, "hsl(", 4) || !strncasecmp(text, "hsla(", 5);
    if (rgb || hsl) {
        double x[4];
        char unit[4][5];
        int m, legacy;
        if (colour_args(strchr(text, '(') + 1, x, unit, &m, &legacy) || m < 3)
            goto bad_function;
        if (m == 4 && alpha_value(x[3], unit[3], &c->alpha))
            goto bad_function;
        if (rgb) {
            /* legacy: all numbers or all percentages; modern: either each */
            for (int k = 0; k < 3; k++) {
                if ((*unit[k] && strcmp(unit[k], "%")) ||
                    (legacy == 1 && strcmp(unit[k], unit[0])))
                    goto bad_function;
                double v = *unit[k] ? x[k] / 100 : x[k] / 255;
                c->v[k] = v < 0 ? 0 : v > 1 ? 1 : v; /* CSS clamps */
            }
            return AA_OK;
        }
        static const struct {
            const char *name;
            double deg;
        } angles[] = {{"", 1}, {"deg", 1}, {"rad", 180 / M_PI}, {"grad", 0.9}, {"turn", 360}};
        size_t a = 0, na = sizeof angles / sizeof angles[0];
        while (a < na && strcmp(unit[0], angles[a].name))
            a++;
        if (a == na)
            goto bad_function;
        double sl[2];
        for (int k = 1; k < 3; k++) {
            /* legacy: percentages; modern: percentages or numbers (0 to 100) */
            if ((legacy == 1 && strcmp(unit[k], "%")) || (*unit[k] && strcmp(unit[k], "%")))
                goto bad_function;
            double v = x[k] / 100;
            sl[k - 1] = v < 0 ? 0 : v > 1 ? 1 : v;
        }
        hsl_to_rgb(x[0] * angles[a].deg, sl[0], sl[1], c->v);
        return AA_OK;
    }
    size_t k, count = sizeof named_colours / sizeof named_colours[0];
    for (k = 0; k < count; k++)
        if (!strcasecmp(named_colours[k].name, text))
            break;
    if (k == count)
        return fail_at(r, "%s=\"%s\" is not a colour this reader knows", what, aa_echo(text));
    unsigned x = named_colours[k].rgb;
    c->v[0] = (x >> 16) / 255.0, c->v[1] = ((x >> 8) & 255) / 255.0, c->v[2] = (x & 255) / 255.0;
    return AA_OK;
bad_hex:
    return fail_at(r, "%s=\"%s\" is not a colour (#rgb, #rgba, #rrggbb or #rrggbbaa)", what,
                   aa_echo(text));
bad_function:
    return fail_at(r, "%s=\"%s\" is not a colour (rgb(), rgba(), hsl() or hsla() as CSS "
                      "Color 4 writes them)",
                   what, aa_echo(text));
}

struct svg_ids;
static const xmlNode *find_id(const struct svg_ids *ids, const char *id);
static const xmlNode *find_href(const struct svg_ids *ids, const char *h);
static void warn_at(reader *r, const char *fmt, ...) AA_PRINTF(2, 3);
static int is_svg(const xmlNode *node);
static int named(const xmlNode *node, const char *name);

/* A paint value (of the property `what`, fill or stroke): a colour into
 * *c, none (*none = 1), or a paint server (*server, SVG 2 "Paint
 * servers": url(#id) naming a linearGradient or radialGradient of this
 * document, optionally followed by a fallback colour or none, used when
 * the reference names no gradient; without a fallback such a paint is
 * none, as browsers draw it, with a warning).  "inherit" is the caller's. */
static int parse_paint(reader *r, const char *what, const char *text, css_colour *c, int *none,
                       const xmlNode **server)
{
    *none = 0;
    *server = NULL;
    if (!strcasecmp(text, "none")) {
        *none = 1;
        return AA_OK;
    }
    if (strncasecmp(text, "url(", 4))
        return parse_colour(r, what, text, c);
    const char *a = skip_wsp(text + 4), *e, *rest;
    if (*a == '\'' || *a == '"') { /* url('#id') and url("#id") */
        const char *close = strchr(a + 1, *a);
        if (!close || *skip_wsp(close + 1) != ')')
            return fail_at(r, "%s=\"%s\" is not url(...)", what, aa_echo(text));
        a++, e = close, rest = skip_wsp(close + 1);
    } else {
        rest = e = strchr(a, ')');
        if (!e)
            return fail_at(r, "%s=\"%s\" is not url(...)", what, aa_echo(text));
        while (e > a && is_wsp((unsigned char)e[-1]))
            e--;
    }
    if (e - a < 2 || *a != '#')
        return fail_at(r, "%s=\"%s\": only a reference into this document (url(#id)) is "
                          "supported",
                       what, aa_echo(text));
    char id[1024];
    if ((size_t)(e - a) >= sizeof id)
        return fail_at(r, "%s=\"%s\": the id is too long", what, aa_echo(text));
    memcpy(id, a + 1, (size_t)(e - a - 1));
    id[e - a - 1] = '\0';
    const char *fallback = skip_wsp(rest + 1);
    const xmlNode *t = find_id(r->ids, id);
    if (t && is_svg(t) && named(t, "pattern"))
        return fail_at(r, "%s=\"%s\": patterns are not supported", what, aa_echo(text));
    if (t && is_svg(t) && (named(t, "linearGradient") || named(t, "radialGradient"))) {
        *server = t;
        return AA_OK;
    }
    if (!*fallback) {
        warn_at(r, "%s=\"%s\": no gradient has that id and there is no fallback colour: none, "
                   "as browsers draw it",
                what, aa_echo(text));
        *none = 1;
        return AA_OK;
    }
    if (!strcasecmp(fallback, "none")) {
        *none = 1;
        return AA_OK;
    }
    return parse_colour(r, what, fallback, c);
}

/* ---- transforms ---- */

/* cos and sin of an angle in degrees, exact at multiples of 90. */
static void cos_sin_deg(double deg, double *c, double *s)
{
    double q = deg / 90.0;
    if (q == floor(q)) {
        static const double cs[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        int k = (int)fmod(fmod(q, 4.0) + 4.0, 4.0);
        *c = cs[k][0], *s = cs[k][1];
        return;
    }
    double a = deg * (M_PI / 180.0);
    *c = cos(a), *s = sin(a);
}

static int tan_deg(reader *r, double deg, double *t)
{
    double m = fmod(deg, 180.0);
    if (m == 90.0 || m == -90.0)
        return fail_at(r, "a skew of %g degrees is infinite", deg);
    if (m == 0)
        *t = 0;
    else if (m == 45.0 || m == -135.0)
        *t = 1;
    else if (m == -45.0 || m == 135.0)
        *t = -1;
    else
        *t = tan(m * (M_PI / 180.0));
    return AA_OK;
}

static int parse_transform(reader *r, const char *text, mat *out)
{
    static const struct {
        const char *name;
        int min, max;
    } kinds[] = {{"matrix", 6, 6}, {"translate", 1, 2}, {"scale", 1, 2},
                 {"rotate", 1, 3}, {"skewX", 1, 1},     {"skewY", 1, 1}};
    mat m = identity;
    const char *s = skip_wsp(text);
    while (*s) {
        size_t kind, nk = sizeof kinds / sizeof kinds[0];
        for (kind = 0; kind < nk; kind++) {
            size_t l = strlen(kinds[kind].name);
            if (!strncmp(s, kinds[kind].name, l) && (s[l] == '(' || is_wsp((unsigned char)s[l]))) {
                s = skip_wsp(s + l);
                break;
            }
        }
        if (kind == nk || *s != '(')
            return fail_at(r, "transform=\"%s\" is malformed (matrix, translate, scale, rotate, "
                              "skewX or skewY expected)",
                           aa_echo(text));
        s = skip_wsp(s + 1);
        double a[6];
        int n = 0;
        while (*s != ')') {
            if (n == 6)
                return fail_at(r, "transform=\"%s\": too many numbers", aa_echo(text));
            int k = scan_number(&s, &a[n]);
            if (k == -2)
                return fail_at(r, "transform=\"%s\": a number is out of range", aa_echo(text));
            if (k)
                return fail_at(r, "transform=\"%s\" is malformed", aa_echo(text));
            n++;
            s = skip_comma_wsp(s);
        }
        s++;
        if (n < kinds[kind].min || n > kinds[kind].max || (kind == 3 && n == 2))
            return fail_at(r, "transform=\"%s\": %s takes %d%s numbers", aa_echo(text),
                           kinds[kind].name, kinds[kind].min,
                           kind == 0 ? "" : kind == 3 ? " or 3" : " or 2");
        mat t = identity;
        double c, sn, tn;
        switch (kind) {
        case 0:
            t = (mat){a[0], a[1], a[2], a[3], a[4], a[5]};
            break;
        case 1:
            t.e = a[0], t.f = n > 1 ? a[1] : 0;
            break;
        case 2:
            t.a = a[0], t.d = n > 1 ? a[1] : a[0];
            break;
        case 3:
            cos_sin_deg(a[0], &c, &sn);
            t = (mat){c, sn, -sn, c, 0, 0};
            if (n == 3) { /* translate(cx, cy) rotate(a) translate(-cx, -cy) */
                mat to = {1, 0, 0, 1, a[1], a[2]}, back = {1, 0, 0, 1, -a[1], -a[2]};
                t = mat_mul(to, mat_mul(t, back));
            }
            break;
        case 4:
            if (tan_deg(r, a[0], &tn))
                return AA_EINVAL;
            t.c = tn;
            break;
        default:
            if (tan_deg(r, a[0], &tn))
                return AA_EINVAL;
            t.b = tn;
            break;
        }
        m = mat_mul(m, t);
        s = skip_comma_wsp(s);
    }
    for (int k = 0; k < 6; k++) {
        double v = ((const double *)&m)[k];
        if (!isfinite(v) || fabs(v) > AA_SVG_MAX_NUMBER)
            return fail_at(r, "transform=\"%s\" is out of range", aa_echo(text));
    }
    *out = m;
    return AA_OK;
}

/* An angle of CSS (Values 4): a number of deg, rad, grad or turn, or a
 * unitless 0; in degrees. */
static int css_angle(reader *r, const char **s, double *deg)
{
    if (is_math(*s))
        return scan_math(r, s, 0, 0, CALC_ANGLE, deg) ? -1 : 0;
    static const struct {
        const char *unit;
        double deg;
    } units[] = {{"deg", 1}, {"grad", 0.9}, {"rad", 180 / M_PI}, {"turn", 360}};
    if (scan_number(s, deg))
        return -1;
    size_t n = 0;
    while (isalpha((unsigned char)(*s)[n]))
        n++;
    if (!n)
        return *deg == 0 ? 0 : -1;
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
        if (strlen(units[k].unit) == n && !strncasecmp(*s, units[k].unit, n)) {
            *deg *= units[k].deg;
            *s += n;
            return 0;
        }
    return -1;
}

/* A length of CSS at *s (a unit, or a unitless 0; any unitless number in
 * a presentation attribute, css 0, where SVG reads it in user units), a
 * percentage of `ref` (the reference box's size along the axis). */
static int css_length(reader *r, const char **s, double ref, int css, double *v)
{
    const char *a = *s;
    if (is_math(a))
        return scan_math(r, s, 1, ref, CALC_LENGTH, v) ? -1 : 0;
    if (scan_number(s, v))
        return -1;
    if (**s == '%') {
        *v *= ref / 100;
        (*s)++;
        return 0;
    }
    if (!isalpha((unsigned char)**s))
        return *v == 0 || !css ? 0 : -1; /* CSS: a length needs its unit */
    *s = a;
    return scan_length(r, s, 2, v) ? -1 : 0;
}

/* The property transform as CSS Transforms 1 writes it (in a style
 * attribute or a sheet): none, or a list of matrix(), translate(),
 * translateX(), translateY(), scale(), scaleX(), scaleY(), rotate(),
 * skew(), skewX(), skewY(), their arguments separated by commas, lengths
 * with units (percentages of the reference box box[2..3]), angles with
 * units.  The 3D functions are refused. */
static int parse_css_transform(reader *r, const char *text, const double box[4], mat *out)
{
    static const char *const kinds[] = {"matrix", "translate", "translateX", "translateY",
                                        "scale",  "scaleX",    "scaleY",     "rotate",
                                        "skew",   "skewX",     "skewY"};
    mat m = identity;
    const char *s = skip_wsp(text);
    if (!strcasecmp(s, "none")) {
        *out = m;
        return AA_OK;
    }
    while (*s) {
        size_t n = 0, kind, nk = sizeof kinds / sizeof kinds[0];
        while (isalnum((unsigned char)s[n]))
            n++;
        for (kind = 0; kind < nk; kind++)
            if (strlen(kinds[kind]) == n && !strncasecmp(s, kinds[kind], n))
                break;
        if (kind == nk || s[n] != '(')
            return fail_at(r, "transform: \"%s\" is not a CSS transform this reader draws "
                              "(matrix, translate, scale, rotate and skew and their X and Y "
                              "forms; no 3D)",
                           aa_echo(text));
        s = skip_wsp(s + n + 1);
        double a[6];
        int na = 0;
        while (*s != ')') {
            if (na == 6 || (na && *s != ','))
                goto bad;
            if (na)
                s = skip_wsp(s + 1);
            int e;
            if (kind == 0 || (kind >= 4 && kind <= 6)) /* numbers */
                e = scan_number(&s, &a[na]);
            else if (kind <= 3) /* lengths */
                e = css_length(r, &s, box[2 + (kind == 3 || (kind == 1 && na == 1))], 1,
                               &a[na]);
            else /* angles */
                e = css_angle(r, &s, &a[na]);
            if (e)
                goto bad;
            na++;
            s = skip_wsp(s);
        }
        s = skip_wsp(s + 1);
        static const int most[] = {6, 2, 1, 1, 2, 1, 1, 1, 2, 1, 1};
        if (na > most[kind] || na < (kind == 0 ? 6 : 1))
            goto bad;
        mat t = identity;
        double c, sn, tx, ty;
        switch (kind) {
        case 0:
            t = (mat){a[0], a[1], a[2], a[3], a[4], a[5]};
            break;
        case 1:
            t.e = a[0], t.f = na > 1 ? a[1] : 0;
            break;
        case 2:
            t.e = a[0];
            break;
        case 3:
            t.f = a[0];
            break;
        case 4:
            t.a = a[0], t.d = na > 1 ? a[1] : a[0];
            break;
        case 5:
            t.a = a[0];
            break;
        case 6:
            t.d = a[0];
            break;
        case 7:
            cos_sin_deg(a[0], &c, &sn);
            t = (mat){c, sn, -sn, c, 0, 0};
            break;
        default: /* skew(ax, ay), skewX(a), skewY(a) */
            tx = ty = 0;
            if ((kind != 10 && tan_deg(r, a[0], &tx)) ||
                (kind == 8 && na > 1 && tan_deg(r, a[1], &ty)) ||
                (kind == 10 && tan_deg(r, a[0], &ty)))
                return AA_EINVAL;
            t.c = tx, t.b = ty;
            break;
        }
        m = mat_mul(m, t);
    }
    for (int k = 0; k < 6; k++) {
        double v = ((const double *)&m)[k];
        if (!isfinite(v) || fabs(v) > AA_SVG_MAX_NUMBER)
            return fail_at(r, "transform: \"%s\" is out of range", aa_echo(text));
    }
    *out = m;
    return AA_OK;
bad:
    return fail_at(r, "transform: \"%s\" is malformed (CSS: arguments separated by commas, "
                      "lengths and angles with units)",
                   aa_echo(text));
}

/* transform-origin (CSS Transforms 1): one or two values (and a z of 0),
 * each a length (from the reference box's corner), a percentage of the
 * reference box box (x y w h) or a keyword (left, center, right; top,
 * center, bottom; two keywords in either order); one value leaves the
 * other center.  The point in user units into o[2]. */
static int parse_transform_origin(reader *r, const char *text, const double box[4], double o[2])
{
    const int css = r->from_css;
    static const struct {
        const char *name;
        int axis; /* 0 x, 1 y, 2 either */
        double f;
    } kw[] = {{"left", 0, 0}, {"right", 0, 1}, {"top", 1, 0}, {"bottom", 1, 1}, {"center", 2, 0.5}};
    int axis[3]; /* as kw, 3 a length */
    double v[3];
    int n = 0;
    const char *s = skip_wsp(text);
    while (*s) {
        if (n == 3)
            goto bad;
        size_t len = 0, k, nk = sizeof kw / sizeof kw[0];
        while (isalpha((unsigned char)s[len]))
            len++;
        if (len) {
            for (k = 0; k < nk; k++)
                if (strlen(kw[k].name) == len && !strncasecmp(s, kw[k].name, len))
                    break;
            if (k == nk || n == 2)
                goto bad;
            axis[n] = kw[k].axis, v[n] = kw[k].f;
            s += len;
        } else {
            if (css_length(r, &s, n < 2 ? box[2 + n] : 0, css, &v[n]))
                goto bad;
            axis[n] = 3;
        }
        n++;
        s = skip_wsp(s);
    }
    if (!n)
        goto bad;
    if (n == 3) {
        if (axis[2] != 3 || v[2] != 0) {
            r->unsupported = axis[2] == 3; /* a z other than 0 is 3D: valid, not drawn */
            goto bad;
        }
        n = 2;
    }
    if (n == 1)
        axis[1] = 2, v[1] = 0.5;
    if (axis[0] == 1 || axis[1] == 0) { /* keywords in the other order */
        if (axis[0] == 3 || axis[1] == 3)
            goto bad;
        int ta = axis[0];
        double tv = v[0];
        axis[0] = axis[1], v[0] = v[1], axis[1] = ta, v[1] = tv;
    }
    if (axis[0] == 1 || axis[1] == 0)
        goto bad;
    o[0] = box[0] + (axis[0] == 3 ? v[0] : v[0] * box[2]);
    o[1] = box[1] + (axis[1] == 3 ? v[1] : v[1] * box[3]);
    return AA_OK;
bad:
    return fail_at(r, "transform-origin=\"%s\" is malformed (one or two lengths, percentages "
                      "or keywords)",
                   aa_echo(text));
}

/* ---- paths in user units ---- */

static int is_svg(const xmlNode *node)
{
    return node->type == XML_ELEMENT_NODE && node->ns && node->ns->href &&
           !strcmp((const char *)node->ns->href, SVG_NS);
}

static int named(const xmlNode *node, const char *name)
{
    return !strcmp((const char *)node->name, name);
}


/* The element and its line before a message of the path or stroke code,
 * which knows no element. */
static int at_element(reader *r, int st)
{
    if (st && r->node)
        return aa_fail_context(st, "%s: line %ld: <%s>", r->name, xmlGetLineNo(r->node),
                               (const char *)r->node->name);
    return st;
}

static int count_segments(reader *r, size_t n)
{
    if (n > (size_t)AA_SVG_MAX_SEGMENTS || (r->segments += (long)n) > AA_SVG_MAX_SEGMENTS)
        return fail_at(r, "more than %d path segments in the document", AA_SVG_MAX_SEGMENTS);
    return AA_OK;
}

/* Segments appended to a path in user units, each counted. */
static int p_move(reader *r, aa_path *p, double x, double y)
{
    int st = count_segments(r, 1);
    return st ? st : at_element(r, aa_path_move_to(p, x, y));
}
static int p_line(reader *r, aa_path *p, double x, double y)
{
    int st = count_segments(r, 1);
    return st ? st : at_element(r, aa_path_line_to(p, x, y));
}
static int p_quad(reader *r, aa_path *p, double cx, double cy, double x, double y)
{
    int st = count_segments(r, 1);
    return st ? st : at_element(r, aa_path_quad_to(p, cx, cy, x, y));
}
static int p_cubic(reader *r, aa_path *p, const double q[6])
{
    int st = count_segments(r, 1);
    return st ? st : at_element(r, aa_path_cubic_to(p, q[0], q[1], q[2], q[3], q[4], q[5]));
}
/* c: cx cy ux uy vx vy t0 t1, as aa_edge */
static int p_arc(reader *r, aa_path *p, const double c[8], double x, double y)
{
    int st = count_segments(r, 1);
    return st ? st
              : at_element(r, aa_path_arc_to(p, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7],
                                             x, y));
}
static int p_close(reader *r, aa_path *p)
{
    int st = count_segments(r, 1);
    return st ? st : at_element(r, aa_path_close(p));
}

/* The quarter of the ellipse of centre (cx, cy) and radii rx, ry along the
 * axes from angle q pi/2 to (q + 1) pi/2 (q = 0: from (cx + rx, cy) to
 * (cx, cy + ry), the way of increasing y first), to the end (x, y). */
static int p_quarter(reader *r, aa_path *p, double cx, double cy, double rx, double ry, int q,
                     double x, double y)
{
    const double c[8] = {cx, cy, rx, 0, 0, ry, q * (M_PI / 2), (q + 1) * (M_PI / 2)};
    return p_arc(r, p, c, x, y);
}

/* ---- path data ---- */

/* A flag of the arc command: one character, 0 or 1 (SVG 2's path grammar:
 * "a1 1 0 00 1 1" has the flags 0 and 0). */
static int scan_flag(const char **s, double *v)
{
    if (**s != '0' && **s != '1')
        return -1;
    *v = **s - '0';
    (*s)++;
    return 0;
}

/* An error in path data (SVG 2, "Error handling in path data"): the
 * path is drawn up to, not including, the command with the error, as
 * browsers draw it; a warning names the element, its line and the error. */
static int path_error(reader *r, const char *fmt, ...) AA_PRINTF(2, 3);
static int path_error(reader *r, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    aa_warn("%s: line %ld: <%s>: %s: drawn up to the command before it", r->name,
            xmlGetLineNo(r->node), (const char *)r->node->name, msg);
    return AA_OK;
}

static int path_data(reader *r, aa_path *p, const char *d)
{
    const char *s = skip_wsp(d);
    char cmd = 0;
    double cx = 0, cy = 0, sx = 0, sy = 0; /* current point, subpath start */
    double qx = 0, qy = 0;                 /* last control point (for S and T) */
    char last = 0;                         /* the last command, upper case */
    int st, subpath = 0;                   /* a subpath was begun by M */
    int open = 0;                          /* a subpath is open (not ended by Z) */
    while (*s) {
        if (isalpha((unsigned char)*s)) {
            cmd = *s++;
            if (!strchr("MmLlHhVvQqTtCcSsZzAa", cmd))
                return path_error(r, "d: unknown path command '%c' at offset %ld", cmd,
                               (long)(s - 1 - d));
            if (!subpath && cmd != 'M' && cmd != 'm')
                return path_error(r, "d: path data must begin with M or m");
            s = skip_wsp(s);
        } else if (!cmd) {
            return path_error(r, "d: path data must begin with M or m");
        } else if (cmd == 'Z' || cmd == 'z') {
            return path_error(r, "d: a number after Z at offset %ld", (long)(s - d));
        }
        int up = toupper((unsigned char)cmd), rel = cmd != up;
        int need = up == 'M' || up == 'L' || up == 'T' ? 2
                   : up == 'H' || up == 'V'           ? 1
                   : up == 'Q' || up == 'S'           ? 4
                   : up == 'C'                        ? 6
                   : up == 'A'                        ? 7
                                                      : 0;
        double a[7];
        for (int k = 0; k < need; k++) {
            if (k)
                s = skip_comma_wsp(s);
            if (up == 'A' && (k == 3 || k == 4)) {
                if (scan_flag(&s, &a[k]))
                    return path_error(r, "d: %s at offset %ld (the arc's %s flag is 0 or 1)",
                                   *s ? "malformed flag" : "path data ends too early",
                                   (long)(s - d), k == 3 ? "large-arc" : "sweep");
                continue;
            }
            int e = scan_number(&s, &a[k]);
            if (e == -2)
                return fail_at(r, "d: a number out of range at offset %ld (at most %g)",
                               (long)(s - d), AA_SVG_MAX_NUMBER);
            if (e)
                return path_error(r, "d: %s at offset %ld (command %c needs %d numbers)",
                               *s ? "malformed number" : "path data ends too early",
                               (long)(s - d), cmd, need);
        }
        /* after Z, a drawing command starts a new subpath at the start point */
        if (up != 'M' && up != 'Z' && !open) {
            if ((st = p_move(r, p, sx, sy)))
                return st;
            open = 1;
        }
        double ox = rel ? cx : 0, oy = rel ? cy : 0;
        switch (up) {
        case 'M':
            cx = a[0] + ox, cy = a[1] + oy;
            sx = cx, sy = cy;
            subpath = open = 1;
            if ((st = p_move(r, p, cx, cy)))
                return st;
            cmd = rel ? 'l' : 'L'; /* implicit repeats are lines */
            break;
        case 'L':
            cx = a[0] + ox, cy = a[1] + oy;
            if ((st = p_line(r, p, cx, cy)))
                return st;
            break;
        case 'H':
            cx = a[0] + ox;
            if ((st = p_line(r, p, cx, cy)))
                return st;
            break;
        case 'V':
            cy = a[0] + oy;
            if ((st = p_line(r, p, cx, cy)))
                return st;
            break;
        case 'Q':
        case 'T': {
            double kx, ky;
            if (up == 'Q')
                kx = a[0] + ox, ky = a[1] + oy, a[0] = a[2], a[1] = a[3];
            else if (last == 'Q' || last == 'T')
                kx = 2 * cx - qx, ky = 2 * cy - qy;
            else
                kx = cx, ky = cy;
            cx = a[0] + ox, cy = a[1] + oy;
            qx = kx, qy = ky;
            if ((st = p_quad(r, p, kx, ky, cx, cy)))
                return st;
            break;
        }
        case 'C':
        case 'S': {
            double q[6];
            if (up == 'C') {
                q[0] = a[0] + ox, q[1] = a[1] + oy, q[2] = a[2] + ox, q[3] = a[3] + oy;
                q[4] = a[4] + ox, q[5] = a[5] + oy;
            } else {
                if (last == 'C' || last == 'S')
                    q[0] = 2 * cx - qx, q[1] = 2 * cy - qy;
                else
                    q[0] = cx, q[1] = cy;
                q[2] = a[0] + ox, q[3] = a[1] + oy, q[4] = a[2] + ox, q[5] = a[3] + oy;
            }
            qx = q[2], qy = q[3];
            cx = q[4], cy = q[5];
            if ((st = p_cubic(r, p, q)))
                return st;
            break;
        }
        case 'A': {
            /* rx ry x-axis-rotation large-arc-flag sweep-flag x y: the
             * implementation notes' conversion (aa_arc_endpoints) gives an
             * arc, a line (a zero radius) or nothing (equal ends) */
            double x = a[5] + ox, y = a[6] + oy, c[8];
            aa_arc_kind k;
            if (aa_arc_endpoints(cx, cy, a[0], a[1], a[2], a[3] != 0, a[4] != 0, x, y, c, &k))
                return at_element(r, AA_EINVAL);
            if (k == AA_ARC_CURVE)
                st = p_arc(r, p, c, x, y);
            else if (k == AA_ARC_LINE)
                st = p_line(r, p, x, y);
            else
                st = AA_OK;
            if (st)
                return st;
            cx = x, cy = y;
            break;
        }
        default: /* Z */
            if (open && (st = p_close(r, p)))
                return st;
            open = 0;
            cx = sx, cy = sy;
            break;
        }
        last = (char)up;
        s = skip_comma_wsp(s);
        if (up == 'Z' && *s == ',')
            return path_error(r, "d: a comma after Z at offset %ld", (long)(s - d));
    }
    return AA_OK;
}

/* ---- elements as paths ---- */

/* A warning naming the element and its line. */
static void warn_at(reader *r, const char *fmt, ...) AA_PRINTF(2, 3);
static void warn_at(reader *r, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (!r->node)
        aa_warn("%s: %s", r->name, msg);
    else
        aa_warn("%s: line %ld: <%s>: %s", r->name, xmlGetLineNo(r->node),
                (const char *)r->node->name, msg);
}

/* An invalid presentation attribute is ignored, as browsers ignore it
 * (SVG 2, "Presentation attributes": a value that does not parse has no
 * effect; Chromium, resvg and librsvg draw the element with the
 * property's default): 1 and a warning naming the element, its line and
 * the value when `text` is invalid, 0 when it may be valid but not read
 * here (a CSS function such as calc(), or a unit the reader does not know:
 * refused by the caller, never guessed).  `what` says what was wanted. */
static int invalid_attr(reader *r, const char *key, const char *text, const char *what)
{
    const char *s = skip_wsp(text);
    if (isalpha((unsigned char)*s)) {
        const int math = is_math(s);
        while (isalnum((unsigned char)*s) || *s == '-')
            s++;
        if (*s == '(' && (!math || r->unsupported))
            return 0; /* a function (a math function is read: invalid, but
                       * for a unit not read or a value out of range) */
    } else {
        double x;
        if (!scan_number(&s, &x) && isalpha((unsigned char)*s))
            return 0; /* a number and a unit */
    }
    warn_at(r, "%s=\"%s\" is not %s: ignored, as browsers ignore it", key, aa_echo(text), what);
    return 1;
}

/* The attribute `key` of node, its var()s substituted (var_subst; a value
 * invalid then is the initial value, as if absent, with a warning), or
 * NULL, freed by xmlFree; *st set on an error. */
static xmlChar *attr_var(reader *r, const xmlNode *node, const char *key, int *st)
{
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)key);
    if (!t || !has_var((const char *)t))
        return t;
    char out[1024];
    r->var_count = 0;
    int ok = var_subst(r, node, (const char *)t, out, sizeof out, st);
    if (!ok && !*st)
        warn_at(r, "%s=\"%s\": a var() of no value: its initial value, as CSS says", key,
                aa_echo((const char *)t));
    xmlFree(t);
    return ok && !*st ? xmlCharStrdup(out) : NULL;
}

static int attr_length(reader *r, const xmlNode *node, const char *key, double def, double *v)
{
    int st = AA_OK;
    xmlChar *t = attr_var(r, node, key, &st);
    if (st)
        return st;
    if (!t) {
        *v = def;
        return AA_OK;
    }
    double x;
    st = parse_length(r, key, (const char *)t, &x);
    if (st == AA_EINVAL && invalid_attr(r, key, (const char *)t, "a length"))
        x = def, st = AA_OK;
    xmlFree(t);
    if (!st)
        *v = x;
    return st;
}

/* A radius rx or ry of <rect> or <ellipse>: a length, or auto (also when
 * absent: *is_auto = 1); a negative value is invalid (SVG 2), so auto, as
 * browsers take it, with a warning. */
static int attr_radius(reader *r, const xmlNode *node, const char *key, double *v, int *is_auto)
{
    int st = AA_OK;
    xmlChar *t = attr_var(r, node, key, &st);
    *v = 0;
    if (st)
        return st;
    *is_auto = !t || !strcasecmp(skip_wsp((const char *)t), "auto");
    if (!*is_auto && !(st = parse_length(r, key, (const char *)t, v)) && *v < 0 && r->calc)
        *v = 0; /* CSS Values 4: a math function's value clamped to the range */
    else if (!*is_auto && !st && *v < 0) {
        /* SVG 2: a negative radius is invalid: auto */
        warn_at(r, "%s=\"%s\" is negative: auto, as browsers take it", key,
                aa_echo((const char *)t));
        *v = 0, *is_auto = 1;
    } else if (st == AA_EINVAL && invalid_attr(r, key, (const char *)t, "a length"))
        *v = 0, *is_auto = 1, st = AA_OK;
    xmlFree(t);
    return st;
}

/* <rect>: SVG 2's used radii (neither given: square corners; one given:
 * both take it; then each clamped to half the width or height) and its
 * path: from (x + rx, y) along the top, each corner a quarter of the
 * ellipse of radii rx, ry, closed.  Nothing if the width or height is 0. */
static int rect(reader *r, const xmlNode *node, aa_path *p)
{
    double x, y, w, h, rx, ry;
    int st, ax, ay;
    if ((st = attr_length(r, node, "x", 0, &x)) || (st = attr_length(r, node, "y", 0, &y)) ||
        (st = attr_length(r, node, "width", 0, &w)) ||
        (st = attr_length(r, node, "height", 0, &h)) ||
        (st = attr_radius(r, node, "rx", &rx, &ax)) || (st = attr_radius(r, node, "ry", &ry, &ay)))
        return st;
    if (w < 0 || h < 0) { /* SVG 2: invalid, so auto: 0, not drawn */
        warn_at(r, "a negative %s (%g): not drawn, as browsers do", w < 0 ? "width" : "height",
                w < 0 ? w : h);
        return AA_OK;
    }
    if (w == 0 || h == 0)
        return AA_OK; /* not drawn */
    if (ax && !ay)
        rx = ry;
    else if (ay && !ax)
        ry = rx;
    rx = fmin(rx, w / 2), ry = fmin(ry, h / 2);
    if (rx == 0 || ry == 0) {
        if ((st = p_move(r, p, x, y)) || (st = p_line(r, p, x + w, y)) ||
            (st = p_line(r, p, x + w, y + h)) || (st = p_line(r, p, x, y + h)))
            return st;
        return p_close(r, p);
    }
    /* the corners' centres; a side of length 0 (a radius of half the
     * width or height) is left out */
    const double x0 = x + rx, x1 = x + w - rx, y0 = y + ry, y1 = y + h - ry;
    if ((st = p_move(r, p, x0, y)) || (x1 > x0 && (st = p_line(r, p, x1, y))) ||
        (st = p_quarter(r, p, x1, y0, rx, ry, -1, x + w, y0)) ||
        (y1 > y0 && (st = p_line(r, p, x + w, y1))) ||
        (st = p_quarter(r, p, x1, y1, rx, ry, 0, x1, y + h)) ||
        (x1 > x0 && (st = p_line(r, p, x0, y + h))) ||
        (st = p_quarter(r, p, x0, y1, rx, ry, 1, x, y1)) ||
        (y1 > y0 && (st = p_line(r, p, x, y0))) ||
        (st = p_quarter(r, p, x0, y0, rx, ry, 2, x0, y)))
        return st;
    return p_close(r, p);
}

/* <circle> and <ellipse>: SVG 2's path, from (cx + rx, cy) through
 * (cx, cy + ry), (cx - rx, cy) and (cx, cy - ry), four quarter arcs,
 * closed.  An ellipse's auto radius is the other one.  A radius of 0
 * disables rendering; a negative one is invalid (SVG 2), so 0: nothing,
 * with a warning. */
static int ellipse(reader *r, const xmlNode *node, aa_path *p)
{
    double cx, cy, rx, ry;
    int st, ax = 0, ay = 0;
    if ((st = attr_length(r, node, "cx", 0, &cx)) || (st = attr_length(r, node, "cy", 0, &cy)))
        return st;
    if (named(node, "circle")) {
        if ((st = attr_length(r, node, "r", 0, &rx)))
            return st;
        if (rx < 0) { /* SVG 2: invalid, so 0: not drawn */
            warn_at(r, "a negative r (%g): not drawn, as browsers do", rx);
            return AA_OK;
        }
        ry = rx;
    } else {
        if ((st = attr_radius(r, node, "rx", &rx, &ax)) ||
            (st = attr_radius(r, node, "ry", &ry, &ay)))
            return st;
        if (ax)
            rx = ry;
        if (ay)
            ry = rx;
    }
    if (rx == 0 || ry == 0)
        return AA_OK; /* not drawn */
    if ((st = p_move(r, p, cx + rx, cy)) ||
        (st = p_quarter(r, p, cx, cy, rx, ry, 0, cx, cy + ry)) ||
        (st = p_quarter(r, p, cx, cy, rx, ry, 1, cx - rx, cy)) ||
        (st = p_quarter(r, p, cx, cy, rx, ry, 2, cx, cy - ry)) ||
        (st = p_quarter(r, p, cx, cy, rx, ry, 3, cx + rx, cy)))
        return st;
    return p_close(r, p);
}

/* <line>: from (x1, y1) to (x2, y2), open (only a stroke draws it). */
static int line(reader *r, const xmlNode *node, aa_path *p)
{
    double v[4];
    static const char *const keys[4] = {"x1", "y1", "x2", "y2"};
    for (int k = 0; k < 4; k++) {
        int st = attr_length(r, node, keys[k], 0, &v[k]);
        if (st)
            return st;
    }
    int st = p_move(r, p, v[0], v[1]);
    return st ? st : p_line(r, p, v[2], v[3]);
}

/* <polygon> (closed) and <polyline> (open: a fill closes it, a stroke
 * does not). */
static int poly(reader *r, const xmlNode *node, aa_path *p)
{
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)"points");
    if (!t)
        return AA_OK;
    const char *s = skip_wsp((const char *)t);
    int st = AA_OK, n = 0;
    double xy[2];
    while (*s && !st) {
        int e = scan_number(&s, &xy[n & 1]);
        if (e)
            st = fail_at(r, "points: %s at offset %ld",
                         e == -2 ? "a number out of range" : "malformed number",
                         (long)(s - (const char *)t));
        else if (n++ & 1)
            st = n == 2 ? p_move(r, p, xy[0], xy[1]) : p_line(r, p, xy[0], xy[1]);
        s = skip_comma_wsp(s);
    }
    if (!st && (n & 1))
        st = fail_at(r, "points: an odd number of coordinates (%d)", n);
    if (!st && n && named(node, "polygon"))
        st = p_close(r, p);
    xmlFree(t);
    return st;
}

/* The element's shape as a path in its user units. */
static int shape_path(reader *r, const xmlNode *node, aa_path *p)
{
    if (named(node, "path")) {
        xmlChar *d = xmlGetNoNsProp(node, (const xmlChar *)"d");
        if (!d)
            return AA_OK;
        int st = path_data(r, p, (const char *)d);
        xmlFree(d);
        return st;
    }
    if (named(node, "rect"))
        return rect(r, node, p);
    if (named(node, "circle") || named(node, "ellipse"))
        return ellipse(r, node, p);
    if (named(node, "line"))
        return line(r, node, p);
    return poly(r, node, p);
}

/* ---- giving paths to the sink ---- */

static int point(reader *r, const mat *m, double x, double y, double *u, double *v)
{
    *u = m->a * x + m->c * y + m->e;
    *v = m->b * x + m->d * y + m->f;
    if (!(fabs(*u) <= AA_SVG_MAX_COORD && fabs(*v) <= AA_SVG_MAX_COORD))
        return fail_at(r, "the point (%g, %g) lands at (%g, %g) pixels, beyond %g", x, y, *u, *v,
                       AA_SVG_MAX_COORD);
    return AA_OK;
}

/* An elliptical arc (a[0..7] as aa_edge, a[8..9] its end) through m: the
 * image of the points c + u cos t + v sin t under an affine map is
 * m(c) + L u cos t + L v sin t (L its linear part), the same t.  A
 * singular map flattens the ellipse onto a segment of a line through the
 * arc's ends; a fill bounds the same region with the line from end to end
 * (no point off that line is crossed between them), which is given
 * instead.  A map that nearly flattens it (the scene's test of parallel
 * semi-diameters, core.h) is refused.  The whole ellipse must lie within
 * AA_SVG_MAX_COORD. */
static int give_arc(reader *r, const mat *m, const double a[10])
{
    double c[2], e[2];
    int st;
    if ((st = point(r, m, a[0], a[1], &c[0], &c[1])) ||
        (st = point(r, m, a[8], a[9], &e[0], &e[1])))
        return st;
    const double ux = m->a * a[2] + m->c * a[3], uy = m->b * a[2] + m->d * a[3];
    const double vx = m->a * a[4] + m->c * a[5], vy = m->b * a[4] + m->d * a[5];
    const double cross = ux * vy - uy * vx, size = hypot(ux, uy) + hypot(vx, vy);
    if (cross == 0)
        return r->sink->line_to(r->ctx, e[0], e[1]);
    if (!(fabs(cross) > 1e-12 * size * size))
        return fail_at(r, "the transform flattens an elliptical arc almost to a line (its "
                          "semi-diameters are parallel within 1e-12), which the scene "
                          "cannot hold");
    /* the ellipse's box: c +- (hypot(ux, vx), hypot(uy, vy)) */
    if (!(fabs(c[0]) + hypot(ux, vx) <= AA_SVG_MAX_COORD &&
          fabs(c[1]) + hypot(uy, vy) <= AA_SVG_MAX_COORD))
        return fail_at(r, "an elliptical arc's ellipse (centre (%g, %g) pixels) reaches "
                          "beyond %g pixels",
                       c[0], c[1], AA_SVG_MAX_COORD);
    return r->sink->arc_to(r->ctx, c[0], c[1], ux, uy, vx, vy, a[6], a[7], e[0], e[1]);
}

/* ---- exact bounds, and viewports that clip ---- */

static void box_add(double b[4], double x, double y)
{
    b[0] = fmin(b[0], x), b[1] = fmin(b[1], y), b[2] = fmax(b[2], x), b[3] = fmax(b[3], y);
}

/* The Bezier arc of degree deg (control values q[0..deg]) at t. */
static double bez(const double *q, int deg, double t)
{
    const double s = 1 - t;
    return deg == 2 ? s * s * q[0] + 2 * s * t * q[1] + t * t * q[2]
                    : s * s * s * q[0] + 3 * s * s * t * q[1] + 3 * s * t * t * q[2] +
                          t * t * t * q[3];
}

/* The bounds b (x0 y0 x1 y1) of a path in user units mapped by m, exact:
 * the ends of every segment and the points where a coordinate of a
 * mapped Bezier arc (a Bezier arc of the mapped control points) or of a
 * mapped elliptical arc turns (c + u cos t + v sin t turns in x where
 * tan t = v_x / u_x).  The offset curves of a stroke outline are bounded
 * by their Bezier arc's control points widened by the offset (an offset
 * point is b(t) + d n(t), within d of the arc's hull), which contains
 * them.  -1 for an evolute (a centre of curvature), not bounded here. */
static int path_bounds(const aa_path *p, const mat *m, double b[4])
{
    b[0] = b[1] = INFINITY, b[2] = b[3] = -INFINITY;
    double px = 0, py = 0, sx = 0, sy = 0; /* pen and start, user units */
#define MX(x, y) (m->a * (x) + m->c * (y) + m->e)
#define MY(x, y) (m->b * (x) + m->d * (y) + m->f)
    for (size_t i = 0; i < p->n; i++) {
        const aa_path_seg *g = &p->seg[i];
        const double *q = g->p;
        double cx[4], cy[4];
        int deg = 0;
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = q[0], sy = py = q[1];
            box_add(b, MX(px, py), MY(px, py));
            continue;
        case AA_PATH_LINE:
            px = q[0], py = q[1];
            box_add(b, MX(px, py), MY(px, py));
            continue;
        case AA_PATH_CLOSE:
            px = sx, py = sy;
            continue;
        case AA_PATH_QUAD:
        case AA_PATH_CUBIC:
            deg = g->op == AA_PATH_QUAD ? 2 : 3;
            cx[0] = MX(px, py), cy[0] = MY(px, py);
            for (int k = 1; k <= deg; k++)
                cx[k] = MX(q[2 * k - 2], q[2 * k - 1]), cy[k] = MY(q[2 * k - 2], q[2 * k - 1]);
            box_add(b, cx[deg], cy[deg]);
            for (int axis = 0; axis < 2; axis++) {
                const double *c = axis ? cy : cx;
                /* the derivative's roots in (0, 1): a t^2 + b t + c = 0 */
                double qa, qb, qc, t[2];
                int nt = 0;
                if (deg == 2)
                    qa = 0, qb = c[0] - 2 * c[1] + c[2], qc = c[1] - c[0];
                else
                    qa = -c[0] + 3 * c[1] - 3 * c[2] + c[3], qb = 2 * (c[0] - 2 * c[1] + c[2]),
                    qc = c[1] - c[0];
                if (qa == 0) {
                    if (qb != 0)
                        t[nt++] = -qc / qb;
                } else {
                    const double disc = qb * qb - 4 * qa * qc;
                    if (disc >= 0) {
                        const double sq = sqrt(disc);
                        t[nt++] = (-qb + sq) / (2 * qa);
                        t[nt++] = (-qb - sq) / (2 * qa);
                    }
                }
                for (int k = 0; k < nt; k++)
                    if (t[k] > 0 && t[k] < 1)
                        box_add(b, bez(cx, deg, t[k]), bez(cy, deg, t[k]));
            }
            px = q[2 * deg - 2], py = q[2 * deg - 1];
            continue;
        case AA_PATH_ARC: {
            const double ccx = MX(q[0], q[1]), ccy = MY(q[0], q[1]);
            const double ux = m->a * q[2] + m->c * q[3], uy = m->b * q[2] + m->d * q[3];
            const double vx = m->a * q[4] + m->c * q[5], vy = m->b * q[4] + m->d * q[5];
            const double lo = fmin(q[6], q[7]), hi = fmax(q[6], q[7]);
            box_add(b, ccx + ux * cos(q[6]) + vx * sin(q[6]), ccy + uy * cos(q[6]) + vy * sin(q[6]));
            box_add(b, MX(q[8], q[9]), MY(q[8], q[9]));
            for (int axis = 0; axis < 2; axis++) {
                const double t0 = axis ? atan2(vy, uy) : atan2(vx, ux);
                /* t0 + k pi within [lo, hi] */
                double k = ceil((lo - t0) / M_PI);
                for (int j = 0; j < 8; j++, k++) {
                    const double t = t0 + k * M_PI;
                    if (t > hi)
                        break;
                    if (t >= lo)
                        box_add(b, ccx + ux * cos(t) + vx * sin(t), ccy + uy * cos(t) + vy * sin(t));
                }
            }
            px = q[8], py = q[9];
            continue;
        }
        case AA_PATH_OFFSET: {
            if (q[9] != 0)
                return -1;
            double hb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
            for (int k = 0; k < 4; k++)
                box_add(hb, MX(q[2 * k], q[2 * k + 1]), MY(q[2 * k], q[2 * k + 1]));
            const double d = fabs(q[8]);
            const double wx = d * hypot(m->a, m->c), wy = d * hypot(m->b, m->d);
            box_add(b, hb[0] - wx, hb[1] - wy);
            box_add(b, hb[2] + wx, hb[3] + wy);
            px = q[12], py = q[13];
            continue;
        }
        default:
            return -1;
        }
    }
#undef MX
#undef MY
    return 0;
}

static int give_path(reader *r, const aa_path *p, const mat *m, aa_rgb colour,
                     aa_fill_rule rule, double alpha, const aa_gradient *grad);

/* Remember the clip `id` made of node referenced in user space m (with the
 * box `box`) within `within`, so that the same reference gives it again. */
static int clip_record(reader *r, const xmlNode *node, const mat *m, const double box[4],
                       int within, int id)
{
    if (r->nmade == r->capmade) {
        size_t c = r->capmade ? 2 * r->capmade : 16;
        clip_made *p = realloc(r->made, c * sizeof *p);
        if (!p)
            return aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
        r->made = p, r->capmade = c;
    }
    r->made[r->nmade++] = (clip_made){node, *m, {box[0], box[1], box[2], box[3]}, within, id};
    return AA_OK;
}

/* The clip c (as r->clip) given to the sink: a viewport's clip is made
 * when first needed, within its outer clip (made first), its one member
 * the viewport's rectangle [x0, x1] x [y0, y1] through the map m at the
 * viewport (a parallelogram in pixels, exact lines; nonzero).  The same
 * viewport at the same map and size within the same clip (a <symbol>
 * used alike twice) gives the clip made before, as clip paths do. */
static int viewport_clip(reader *r, int c, int *out)
{
    *out = c;
    if (c >= -1)
        return AA_OK;
    struct svg_clip *v = &r->vclip[-2 - c];
    if (v->id >= 0) {
        *out = v->id;
        return AA_OK;
    }
    int within, st;
    if ((st = viewport_clip(r, v->outer, &within)))
        return st;
    for (size_t k = 0; k < r->nmade; k++) {
        const clip_made *d = &r->made[k];
        if (d->node == v->node && d->within == within && !memcmp(&d->m, &v->m, sizeof v->m) &&
            !memcmp(d->box, v->box, sizeof v->box)) {
            *out = v->id = d->id;
            return AA_OK;
        }
    }
    aa_path p;
    aa_path_init(&p);
    const double *b = v->box;
    if (!(st = aa_path_move_to(&p, b[0], b[1])) && !(st = aa_path_line_to(&p, b[2], b[1])) &&
        !(st = aa_path_line_to(&p, b[2], b[3])) && !(st = aa_path_line_to(&p, b[0], b[3])) &&
        !(st = aa_path_close(&p)) && (st = r->sink->clip_begin(r->ctx, within)))
        st = at_element(r, st);
    if (!st) {
        const int was = r->clip;
        const aa_rgb none = {{0, 0, 0}};
        r->clip = -1;
        st = give_path(r, &p, &v->m, none, AA_FILL_NONZERO, 1.0, NULL);
        r->clip = was;
    }
    if (!st)
        st = r->sink->clip_end(r->ctx);
    aa_path_free(&p);
    if (st)
        return st;
    v->id = r->nclips++;
    *out = v->id;
    return clip_record(r, v->node, &v->m, v->box, within, v->id);
}

/* The clip of a path (in user units, mapped by m to pixels) drawn now:
 * r->clip, but a viewport that clips (a nested <svg> or a used <symbol>
 * of overflow hidden) the path lies wholly inside is passed over for the
 * clip it lies within, so that content inside its viewports is drawn
 * as without them and no clip is made for it.  The test is exact (the
 * path's bounds in the viewport's coordinates) but for rounding: 1e-9 of
 * the viewport's size, which changes no pixel's coverage by more than
 * that.  A sink without clips refuses a path that needs one. */
static int shape_clip(reader *r, const aa_path *p, const mat *m, int *out)
{
    int c = r->clip;
    while (c <= -2) {
        const struct svg_clip *v = &r->vclip[-2 - c];
        const mat g = mat_mul(v->to, *m);
        double b[4];
        const double eps =
            1e-9 * (fabs(v->box[0]) + fabs(v->box[1]) + fabs(v->box[2]) + fabs(v->box[3]));
        int e = path_bounds(p, &g, b);
        if (!e && b[0] >= v->box[0] - eps && b[1] >= v->box[1] - eps &&
            b[2] <= v->box[2] + eps && b[3] <= v->box[3] + eps) {
            c = v->outer;
            continue;
        }
        if (!r->sink->clip_begin || !r->sink->clip_end || !r->sink->clip)
            return fail_at(r, "%s the viewport of the <%s> at line %ld, which clips it "
                              "(overflow hidden), and clips are not taken here "
                              "(overflow=\"visible\" draws it unclipped)",
                           e ? "this stroke (of an evolute) may reach beyond"
                             : "this reaches beyond",
                           (const char *)v->node->name, xmlGetLineNo(v->node));
        break;
    }
    return viewport_clip(r, c, out);
}

/* A path in user units through m to the sink as one shape of colour
 * `colour` and rule `rule`, every subpath closed (a fill closes it); a
 * path without segments gives nothing. */
static int give_path(reader *r, const aa_path *p, const mat *m, aa_rgb colour,
                     aa_fill_rule rule, double alpha, const aa_gradient *grad)
{
    int st = AA_OK, open = 0;
    double sx = 0, sy = 0; /* the subpath's start, user units */
    const aa_svg_sink *k = r->sink;
    int clip = r->clip;
    if (p->n && (st = shape_clip(r, p, m, &clip)))
        return st;
    if (p->n && alpha < 1 && !k->alpha)
        return fail_at(r, "a translucent shape (alpha %g) is not taken here", alpha);
    if (p->n && grad && !k->gradient)
        return fail_at(r, "gradient paint is not taken here");
    if (p->n && (st = k->shape(r->ctx, colour, rule)))
        return st;
    if (p->n && grad && r->grad_interpolation != AA_INTERPOLATE_SRGB && !k->gradient_interpolation)
        return fail_at(r, "a gradient in linear light (color-interpolation: linearRGB) is not "
                          "taken here");
    if (p->n && grad && (st = k->gradient(r->ctx, grad, r->grad_source ? r->grad_source : "")))
        return st;
    if (p->n && grad && r->grad_interpolation != AA_INTERPOLATE_SRGB &&
        (st = k->gradient_interpolation(r->ctx, r->grad_interpolation)))
        return st;
    if (p->n && alpha < 1 && (st = k->alpha(r->ctx, alpha)))
        return st;
    if (p->n && clip >= 0 && (st = k->clip(r->ctx, clip)))
        return st;
    for (size_t i = 0; i < p->n && !st; i++) {
        const aa_path_seg *g = &p->seg[i];
        double q[6];
        if (g->op == AA_PATH_CLOSE) {
            if (open)
                st = k->close(r->ctx);
            open = 0;
            continue;
        }
        if (g->op == AA_PATH_MOVE || !open) { /* a segment after a close: from the start */
            if (g->op == AA_PATH_MOVE)
                sx = g->p[0], sy = g->p[1];
            if ((open && (st = k->close(r->ctx))) || (st = point(r, m, sx, sy, &q[0], &q[1])) ||
                (st = k->move_to(r->ctx, q[0], q[1])))
                break;
            open = 1;
            if (g->op == AA_PATH_MOVE)
                continue;
        }
        switch (g->op) {
        case AA_PATH_LINE:
            if (!(st = point(r, m, g->p[0], g->p[1], &q[0], &q[1])))
                st = k->line_to(r->ctx, q[0], q[1]);
            break;
        case AA_PATH_QUAD:
            if (!(st = point(r, m, g->p[0], g->p[1], &q[0], &q[1])) &&
                !(st = point(r, m, g->p[2], g->p[3], &q[2], &q[3])))
                st = k->quad_to(r->ctx, q[0], q[1], q[2], q[3]);
            break;
        case AA_PATH_CUBIC:
            for (int j = 0; j < 3 && !st; j++)
                st = point(r, m, g->p[2 * j], g->p[2 * j + 1], &q[2 * j], &q[2 * j + 1]);
            if (!st)
                st = k->cubic_to(r->ctx, q[0], q[1], q[2], q[3], q[4], q[5]);
            break;
        case AA_PATH_ARC:
            st = give_arc(r, m, g->p);
            break;
        case AA_PATH_OFFSET:
            /* an exact offset curve of a Bezier arc's stroke: the sink has
             * no such segment; one that keeps strokes as strokes (`stroke`,
             * told next) draws it from the source, and is given the
             * segment's end here; one that does not cannot draw it */
            if (!k->stroke)
                st = aa_fail(AA_EINVAL,
                             "%s: the stroke of a Bezier arc has exact offset curves, which "
                             "this reader's sink cannot take (it keeps no strokes)",
                             r->name);
            else if (!(st = point(r, m, g->p[12], g->p[13], &q[0], &q[1])))
                st = k->line_to(r->ctx, q[0], q[1]);
            break;
        default:
            st = aa_fail(AA_EFAIL, "%s: a path segment of unknown kind %d", r->name,
                         (int)g->op);
            break;
        }
    }
    if (!st && open)
        st = k->close(r->ctx);
    return st;
}

/* An upper bound of a path's length: lines exactly, Bezier arcs by their
 * control polygons (a Bezier arc is no longer than its control polygon),
 * elliptical arcs by (|u| + |v|) |t1 - t0| (the speed |-u sin t + v cos t|
 * is at most |u| + |v|). */
static double length_bound(const aa_path *p)
{
    double len = 0, px = 0, py = 0, sx = 0, sy = 0;
    for (size_t i = 0; i < p->n; i++) {
        const aa_path_seg *g = &p->seg[i];
        const double *q = g->p;
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = q[0], sy = py = q[1];
            break;
        case AA_PATH_LINE:
            len += hypot(q[0] - px, q[1] - py), px = q[0], py = q[1];
            break;
        case AA_PATH_QUAD:
            len += hypot(q[0] - px, q[1] - py) + hypot(q[2] - q[0], q[3] - q[1]);
            px = q[2], py = q[3];
            break;
        case AA_PATH_CUBIC:
            len += hypot(q[0] - px, q[1] - py) + hypot(q[2] - q[0], q[3] - q[1]) +
                   hypot(q[4] - q[2], q[5] - q[3]);
            px = q[4], py = q[5];
            break;
        case AA_PATH_ARC:
            len += (hypot(q[2], q[3]) + hypot(q[4], q[5])) * fabs(q[7] - q[6]);
            px = q[8], py = q[9];
            break;
        default:
            len += hypot(sx - px, sy - py), px = sx, py = sy;
            break;
        }
    }
    return len;
}

/* At most this many dashes in a stroke (each is a contour of several
 * segments in the outline). */
#define MAX_DASHES_DRAWN (AA_SVG_MAX_SEGMENTS / 8)

/* The stroke style of sty for the path p into *ss (its dashes pointing
 * into sty), refusing dash patterns of too many dashes. */
static int stroke_style_of(reader *r, const aa_path *p, const style *sty, aa_stroke_style *out)
{
    aa_stroke_style ss;
    aa_stroke_style_default(&ss);
    ss.width = sty->stroke_width;
    ss.join = sty->join;
    ss.cap = sty->cap;
    ss.miterlimit = sty->miterlimit;
    if (sty->ndash) {
        /* the pattern's period P is the sum of its values, twice that for
         * an odd count (repeated: 2 n values), of which every other one is
         * a dash; each subpath starts the pattern again, so a subpath of
         * length L has at most (L / P + 2) periods (one begun early by the
         * offset, one cut at the end) */
        double sum = 0, subpaths = 0;
        for (size_t k = 0; k < sty->ndash; k++)
            sum += sty->dash[k];
        for (size_t k = 0; k < p->n; k++)
            subpaths += p->seg[k].op == AA_PATH_MOVE;
        const int odd = sty->ndash & 1;
        const double period = odd ? 2 * sum : sum, per_period = odd ? (double)sty->ndash
                                                                     : sty->ndash / 2.0;
        const double dashes = per_period * (length_bound(p) / period + 2 * subpaths);
        if (!(dashes <= MAX_DASHES_DRAWN))
            return fail_at(r, "stroke-dasharray: the stroke would have about %.3g dashes, more "
                              "than %d",
                           dashes, MAX_DASHES_DRAWN);
        ss.dash = sty->dash;
        ss.ndash = sty->ndash;
        ss.dashoffset = sty->dashoffset;
    }
    *out = ss;
    return AA_OK;
}

/* The stroke style of sty for p into *ss and the stroke's outline
 * (aa_stroke_outline, in user units) into *out (made by aa_path_init; the
 * caller frees it either way). */
static int stroke_outline_of(reader *r, const aa_path *p, const style *sty, aa_stroke_style *ss,
                             aa_path *out)
{
    int st = stroke_style_of(r, p, sty, ss);
    if (!st && (st = aa_stroke_outline(p, ss, out))) /* the message begins "stroke: " */
        st = at_element(r, st);
    return st;
}

/* pathLength (SVG 2, "The pathLength attribute"): the author's length of
 * the path, onto which its computed length L (aa_path_length, in user
 * units, as dashes measure it) maps, so that the dash lengths and the
 * offset are scaled by L / pathLength.  Of no effect without dashes (the
 * reader draws no markers or text on a path).  A negative value or not a
 * number is an error: ignored with a warning, as Chromium and resvg draw
 * it.  0 is an infinite scale: a dash of non-zero length covers each
 * subpath (Chromium draws the stroke solid; resvg ignores pathLength
 * whatever its value, wrong by SVG 2); a first dash of 0 or a non-zero
 * offset, whose infinite scale leaves no one picture, is refused. */
static int path_length_dashes(reader *r, const xmlNode *node, const aa_path *p, style *sty)
{
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)"pathLength");
    if (!t)
        return AA_OK;
    const char *s = skip_wsp((const char *)t);
    double author;
    int st = AA_OK;
    if (scan_number(&s, &author) || *skip_wsp(s) || author < 0) {
        warn_at(r, "pathLength=\"%s\" is not a number of at least 0: ignored, as browsers "
                   "ignore it",
                aa_echo((const char *)t));
    } else if (sty->ndash && author == 0) {
        if (sty->dash[0] > 0 && sty->dashoffset == 0)
            sty->ndash = 0; /* one dash of infinite length */
        else
            st = fail_at(r, "pathLength=\"%s\" with a first dash of 0 or a dash offset is "
                            "not supported",
                         aa_echo((const char *)t));
    } else if (sty->ndash) {
        double len;
        if ((st = aa_path_length(p, &len)))
            st = at_element(r, st);
        else {
            const double k = len / author;
            for (size_t j = 0; j < sty->ndash; j++)
                sty->dash[j] *= k;
            sty->dashoffset *= k;
            for (size_t j = 0; j <= sty->ndash && !st; j++) {
                const double v = j < sty->ndash ? sty->dash[j] : sty->dashoffset;
                if (!(fabs(v) <= AA_SVG_MAX_NUMBER))
                    st = fail_at(r, "pathLength=\"%s\": the dashes it scales are out of range",
                                 aa_echo((const char *)t));
            }
            if (!(k > 0)) /* no length: the dashes all 0, none drawn as dashes */
                sty->ndash = 0;
        }
    }
    xmlFree(t);
    return st;
}

/* The element's stroke: its outline (aa_stroke_outline, in user units)
 * through m to the sink as a shape of the stroke's colour, nonzero. */
static int give_stroke(reader *r, const aa_path *p, const mat *m, const style *sty,
                       aa_rgb colour, double alpha, const aa_gradient *grad)
{
    aa_stroke_style ss;
    aa_path out;
    aa_path_init(&out);
    int st = stroke_outline_of(r, p, sty, &ss, &out);
    if (!st)
        st = count_segments(r, out.n);
    if (!st)
        st = give_path(r, &out, m, colour, AA_FILL_NONZERO, alpha, grad);
    if (!st && out.n && r->sink->stroke) {
        const double mm[6] = {m->a, m->b, m->c, m->d, m->e, m->f};
        st = r->sink->stroke(r->ctx, p, &ss, mm);
    }
    aa_path_free(&out);
    return st;
}

/* ---- elements ---- */

/* SVG 2's initial values of the paint properties. */
static void initial_style(style *sty)
{
    memset(sty, 0, sizeof *sty);
    sty->rule = AA_FILL_NONZERO;
    sty->stroke_none = 1;
    sty->stroke_width = 1;
    sty->join = AA_JOIN_MITER;
    sty->cap = AA_CAP_BUTT;
    sty->miterlimit = 4;
    sty->fill.alpha = sty->stroke.alpha = sty->color.alpha = 1;
    sty->fill_opacity = sty->stroke_opacity = 1;
    sty->visible = 1;
    sty->font_size = 16;
}

/* A keyword value of `key` among names[0 .. n) (CSS: any case): its index
 * into *out. */
static int keyword(reader *r, const char *key, const char *v, const char *const *names, int n,
                   int *out, const char *expect)
{
    for (int k = 0; k < n; k++)
        if (!strcasecmp(v, names[k])) {
            *out = k;
            return AA_OK;
        }
    return fail_at(r, "%s=\"%s\" is not supported (%s)", key, aa_echo(v), expect);
}

/* A whole value that is one number (no unit; a math function of one): 0,
 * or -1. */
static int plain_number(reader *r, const char *v, double *x)
{
    const char *s = v;
    r->calc = 0;
    if (is_math(s))
        return scan_math(r, &s, 0, 0, CALC_NUMBER, x) || *skip_wsp(s) ? -1 : 0;
    return scan_number(&s, x) || *skip_wsp(s) ? -1 : 0;
}

/* stroke-dasharray: none, or lengths separated by commas or white space;
 * a negative value is an error (refused), all zero is none (SVG 2). */
static int parse_dasharray(reader *r, const char *v, style *sty)
{
    if (!strcasecmp(v, "none")) {
        sty->ndash = 0;
        return AA_OK;
    }
    size_t n = 0;
    double sum = 0;
    const char *s = v;
    while (*s) {
        if (n == AA_SVG_MAX_DASHES) {
            r->unsupported = 1; /* the reader's limit, not an invalid value */
            return fail_at(r, "stroke-dasharray=\"%s\": more than %d values", aa_echo(v),
                           AA_SVG_MAX_DASHES);
        }
        double x;
        int e = scan_length(r, &s, 2, &x);
        if (e || (*s && !is_wsp((unsigned char)*s) && *s != ','))
            return fail_at(r, "stroke-dasharray=\"%s\": %s", aa_echo(v),
                           e == -2 ? "a value is out of range"
                                   : "not a list of lengths (numbers, optionally of px, in, "
                                     "cm, mm, Q, pt, pc, em, ex or %)");
        if (x < 0 && r->calc)
            x = 0; /* CSS Values 4: a math function's value clamped to the range */
        if (x < 0)
            return fail_at(r, "stroke-dasharray=\"%s\": a negative value is an error",
                           aa_echo(v));
        sty->dash[n++] = x;
        sum += x;
        s = skip_comma_wsp(s);
    }
    if (!n)
        return fail_at(r, "stroke-dasharray=\"%s\" is empty", aa_echo(v));
    sty->ndash = sum > 0 ? n : 0;
    return AA_OK;
}

/* The stroke properties but the paint (inherited: a value of inherit
 * keeps the parent's). */
static int stroke_props(reader *r, const xmlNode *node, style *sty)
{
    char v[1024];
    int st = AA_OK, k = 0;
    static const char *const joins[] = {"miter", "round", "bevel", "miter-clip", "arcs"};
    static const char *const caps[] = {"butt", "round", "square"};
    static const aa_line_join join_of[] = {AA_JOIN_MITER, AA_JOIN_ROUND, AA_JOIN_BEVEL,
                                           AA_JOIN_MITER_CLIP, AA_JOIN_ARCS};
    static const aa_line_cap cap_of[] = {AA_CAP_BUTT, AA_CAP_ROUND, AA_CAP_SQUARE};
#define GIVEN(key) (prop(r, node, key, v, sizeof v, &st) && strcasecmp(v, "inherit"))
    if (GIVEN("stroke-width")) {
        if ((st = parse_length(r, "stroke-width", v, &sty->stroke_width)))
            return st;
        if (sty->stroke_width < 0 && r->calc)
            sty->stroke_width = 0; /* CSS Values 4: clamped to the range */
        if (sty->stroke_width < 0)
            return fail_at(r, "stroke-width=\"%s\": a negative width is an error", aa_echo(v));
    }
    if (!st && GIVEN("stroke-linejoin")) {
        if ((st = keyword(r, "stroke-linejoin", v, joins, 5, &k,
                          "miter, round, bevel, miter-clip or arcs")))
            return st;
        sty->join = join_of[k];
    }
    if (!st && GIVEN("stroke-linecap")) {
        if ((st = keyword(r, "stroke-linecap", v, caps, 3, &k, "butt, round or square")))
            return st;
        sty->cap = cap_of[k];
    }
    if (!st && GIVEN("stroke-miterlimit")) {
        if (!plain_number(r, v, &sty->miterlimit) && r->calc && sty->miterlimit < 1)
            sty->miterlimit = 1; /* CSS Values 4: a math function's value clamped */
        if (plain_number(r, v, &sty->miterlimit) || !(sty->miterlimit >= 1))
            return fail_at(r, "stroke-miterlimit=\"%s\" is not a number of at least 1",
                           aa_echo(v));
    }
    if (!st && GIVEN("stroke-dasharray") && (st = parse_dasharray(r, v, sty)))
        return st;
    if (!st && GIVEN("stroke-dashoffset") &&
        (st = parse_length(r, "stroke-dashoffset", v, &sty->dashoffset)))
        return st;
#undef GIVEN
    return st;
}

/* An <alpha-value> of the property `key`: a number or a percentage,
 * clamped to [0, 1] (CSS Color 4; SVG 2's opacity properties). */
static int parse_opacity(reader *r, const char *key, const char *v, double *o)
{
    const char *s = v;
    if (is_math(s)) {
        if (scan_math(r, &s, 2, 0, CALC_NUMBER, o))
            return fail_at(r, "%s=\"%s\" is not a number or a percentage", key, aa_echo(v));
    } else if (scan_number(&s, o))
        return fail_at(r, "%s=\"%s\" is not a number or a percentage", key, aa_echo(v));
    else if (*s == '%')
        *o /= 100, s++;
    if (*skip_wsp(s))
        return fail_at(r, "%s=\"%s\" is not a number or a percentage", key, aa_echo(v));
    *o = *o < 0 ? 0 : *o > 1 ? 1 : *o;
    return AA_OK;
}

/* paint-order (SVG 2, "Controlling paint operation order"): normal, or
 * fill, stroke and markers in any order, each at most once, the ones left
 * out following in their normal order; *stroke_first when the stroke is
 * painted before the fill. */
static int parse_paint_order(reader *r, const char *v, int *stroke_first)
{
    if (!strcasecmp(v, "normal")) {
        *stroke_first = 0;
        return AA_OK;
    }
    static const char *const names[3] = {"fill", "stroke", "markers"};
    int seen[3] = {0, 0, 0}, order = 0, first = -1;
    for (const char *s = skip_wsp(v); *s; s = skip_wsp(s)) {
        size_t n = 0;
        while (s[n] && !is_wsp((unsigned char)s[n]))
            n++;
        int k = 0;
        while (k < 3 && !(strlen(names[k]) == n && !strncasecmp(s, names[k], n)))
            k++;
        if (k == 3 || seen[k])
            return fail_at(r, "paint-order=\"%s\" is not normal or fill, stroke and markers "
                              "each at most once",
                           aa_echo(v));
        seen[k] = ++order;
        if (k < 2 && first < 0)
            first = k;
        s += n;
    }
    if (!order)
        return fail_at(r, "paint-order=\"%s\" is empty", aa_echo(v));
    *stroke_first = first == 1;
    return AA_OK;
}

static void path_box(const aa_path *p, const mat *m, double box[4]);

/* The stroke bounding box of a shape (SVG 2, "Bounding boxes": its fill
 * box, p's exact bounds, grown by "the tightest rectangle ... that contains
 * the stroke shape of the element, with the assumption that the element
 * has no dash pattern" when the stroke is not none: the tightest, no
 * approximation; dashes, and so pathLength, play no part), x0 y0 x1 y1 in
 * b through m, b holding the fill box.  The stroke shape is the outline
 * aa_stroke_outline draws undashed, bounded exactly by path_box: lines,
 * circular arcs (their extremes in closed form) and the offset curves and
 * evolutes of stroked Bezier and elliptical arcs (their ends and the
 * closed-form parameters where x or y turns: where the base curve's
 * tangent is axis-aligned; a fold of the offset, where its tangent
 * vanishes, is an end of the outline's pieces, and so are the joins' and
 * caps' points; the evolutes lie inside the shape, on the normals within
 * h of the curve, and add nothing). */
static int stroke_box(reader *r, const aa_path *p, const style *sty, const mat *m, double b[4])
{
    if (sty->stroke_none || !(sty->stroke_width > 0))
        return AA_OK;
    style plain = *sty;
    plain.ndash = 0;
    aa_stroke_style ss;
    aa_path out;
    aa_path_init(&out);
    int st = stroke_outline_of(r, p, &plain, &ss, &out);
    if (!st)
        path_box(&out, m, b);
    aa_path_free(&out);
    return st;
}

/* The element's own transform composed into *m: the property transform
 * (CSS Transforms 1) as a presentation attribute (SVG's transform list,
 * parse_transform) or a declaration (CSS's syntax, parse_css_transform),
 * about transform-origin (initially 0 0 for SVG elements) in the
 * reference box of transform-box: view-box (initial; the nearest
 * viewport's user space, its origin at (0, 0), its size the viewBox's),
 * fill-box of a shape, its exact bounds in user units, or stroke-box, its
 * stroke bounding box (stroke_box; when the element's style is known,
 * r->tsty: not inside an object bounding box, where it is refused); CSS
 * Transforms 1 maps content-box to fill-box and border-box to stroke-box
 * for SVG elements. */
static int element_transform(reader *r, const xmlNode *node, mat *m)
{
    char v[1024];
    int st = AA_OK;
    if (!prop(r, node, "transform", v, sizeof v, &st))
        return st;
    const int css = r->from_css;
    /* the root has a layout box (CSS Transforms 1): every transform-box is
     * its viewport in CSS px, and transform-origin is initially its centre
     * (Chromium turns it so) */
    const int root = node == r->root;
    double box[4] = {0, 0, root ? r->rootw : r->vpw, root ? r->rooth : r->vph};
    char kind[64];
    if (!root && prop(r, node, "transform-box", kind, sizeof kind, &st) &&
        strcasecmp(kind, "view-box")) {
        const int stroked = !strcasecmp(kind, "stroke-box") || !strcasecmp(kind, "border-box");
        if (strcasecmp(kind, "fill-box") && strcasecmp(kind, "content-box") && !stroked)
            return fail_at(r, "transform-box=\"%s\" is not supported (view-box, fill-box, "
                              "content-box, stroke-box or border-box)",
                           aa_echo(kind));
        if (stroked && !r->tsty) {
            r->node = node; /* named, not the element whose box is computed */
            return fail_at(r, "transform-box: %s inside an object bounding box is not "
                              "supported (the element's stroke is not known there)",
                           aa_echo(kind));
        }
        static const char *const shapes[] = {"path", "rect",    "circle",  "ellipse",
                                             "line", "polygon", "polyline"};
        int shape = 0;
        for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
            shape |= named(node, shapes[k]);
        if (!shape)
            return fail_at(r, "transform-box: %s is supported on shapes only", aa_echo(kind));
        aa_path p;
        aa_path_init(&p);
        double b[4];
        if (!(st = shape_path(r, node, &p)) && p.n && path_bounds(&p, &identity, b))
            st = fail_at(r, "transform-box: cannot bound the shape");
        if (!st && p.n && stroked) {
            b[0] = b[1] = INFINITY, b[2] = b[3] = -INFINITY;
            path_box(&p, &identity, b);
            st = stroke_box(r, &p, r->tsty, &identity, b);
        }
        if (!st && p.n)
            box[0] = b[0], box[1] = b[1], box[2] = b[2] - b[0], box[3] = b[3] - b[1];
        else if (!st)
            box[2] = box[3] = 0;
        aa_path_free(&p);
        r->node = node;
    }
    if (st)
        return st;
    mat own = identity;
    st = css ? parse_css_transform(r, v, box, &own) : parse_transform(r, v, &own);
    if (st == AA_EINVAL && !css &&
        (strstr(aa_last_error(), "malformed") || strstr(aa_last_error(), "takes") ||
         strstr(aa_last_error(), "too many"))) {
        /* not SVG's transform list (CSS syntax with units included):
         * ignored, as Chromium and resvg ignore it */
        warn_at(r, "transform=\"%s\" is not a transform list: ignored, as browsers ignore it",
                aa_echo(v));
        own = identity, st = AA_OK;
    }
    if (st)
        return st;
    double o[2] = {box[0] + (root ? box[2] / 2 : 0), box[1] + (root ? box[3] / 2 : 0)};
    if (prop(r, node, "transform-origin", v, sizeof v, &st) &&
        (st = parse_transform_origin(r, v, box, o)))
        return st;
    if (st)
        return st;
    if (o[0] != 0 || o[1] != 0) { /* translate(o) own translate(-o) */
        const mat to = {1, 0, 0, 1, o[0], o[1]}, back = {1, 0, 0, 1, -o[0], -o[1]};
        own = mat_mul(to, mat_mul(own, back));
    }
    *m = mat_mul(*m, own);
    return AA_OK;
}

/* 1 if the value v holds a function the reader does not read (calc(),
 * var(), url(), color(), a 3D transform...): a value that fails to parse
 * with one may still be valid CSS, so it is refused, never ignored. */
static int unknown_function(const char *v)
{
    static const char *const known[] = {"rgb",        "rgba",       "hsl",      "hsla",
                                        "matrix",     "translate",  "translatex",
                                        "translatey", "scale",      "scalex",   "scaley",
                                        "rotate",     "skew",       "skewx",    "skewy",
                                        "calc",       "min",        "max",      "clamp"};
    for (const char *p = v; *p; p++) {
        if (*p != '(')
            continue;
        const char *a = p;
        while (a > v && (isalnum((unsigned char)a[-1]) || a[-1] == '-' || a[-1] == '_'))
            a--;
        size_t n = (size_t)(p - a), k = 0;
        while (k < sizeof known / sizeof known[0] &&
               !(strlen(known[k]) == n && !strncasecmp(a, known[k], n)))
            k++;
        if (k == sizeof known / sizeof known[0])
            return 1;
    }
    return 0;
}

/* Whether v is a valid value of the property `key` (css: of a declaration,
 * else of a presentation attribute), by the parsers that read it: 1 valid
 * (or a property not checked here, read where it is used), 0 invalid (the
 * parser's reason in aa_last_error), or 0 with *st set when it may be
 * valid but is not drawn (a unit or a function not read, a number out of
 * range, a value named unsupported): refused, never ignored. */
static int prop_check(reader *r, const char *key, const char *v, int css, int *st)
{
    static const char *const displays[] = {
        "inline",          "block",           "run-in",       "flow",      "flow-root",
        "table",           "flex",            "grid",         "ruby",      "list-item",
        "contents",        "none",            "inline-block", "inline-table", "inline-flex",
        "inline-grid",     "table-row-group", "table-header-group", "table-footer-group",
        "table-row",       "table-cell",      "table-column-group", "table-column",
        "table-caption",   "ruby-base",       "ruby-text",    "ruby-base-container",
        "ruby-text-container"};
    static const char *const rules[] = {"nonzero", "evenodd"};
    static const char *const caps[] = {"butt", "round", "square"};
    static const char *const joins[] = {"miter", "round", "bevel", "miter-clip", "arcs"};
    static const char *const visibilities[] = {"visible", "hidden", "collapse"};
    static const char *const interpolations[] = {"auto", "sRGB", "linearRGB"};
    static const char *const overflows[] = {"visible", "hidden", "scroll", "clip", "auto"};
    static const char *const boxes[] = {"view-box", "fill-box", "stroke-box", "content-box",
                                        "border-box"};
    static const struct {
        const char *key;
        const char *const *names;
        int n;
    } keywords[] = {{"display", displays, sizeof displays / sizeof displays[0]},
                    {"fill-rule", rules, 2},
                    {"clip-rule", rules, 2},
                    {"stroke-linecap", caps, 3},
                    {"stroke-linejoin", joins, 5},
                    {"visibility", visibilities, 3},
                    {"color-interpolation", interpolations, 3},
                    {"overflow", overflows, 5},
                    {"transform-box", boxes, 5}};
    if (!strcasecmp(v, "inherit"))
        return 1;
    if (!strcasecmp(v, "initial") || !strcasecmp(v, "unset") || !strcasecmp(v, "revert") ||
        !strcasecmp(v, "revert-layer")) {
        /* CSS Cascade 4's keywords, of the properties whose initial value
         * the reader knows (css_wide); the others are refused */
        int inherited;
        if (initial_of(key, &inherited))
            return 1;
        *st = fail_at(r, "%s: %s is not supported here", key, aa_echo(v));
        return 0;
    }
    r->unsupported = 0;
    r->from_css = css; /* (transform-origin reads numbers without units in attributes) */
    int e = AA_OK, k;
    style sty;
    initial_style(&sty);
    css_colour c;
    double x;
    mat m = identity;
    for (size_t j = 0; j < sizeof keywords / sizeof keywords[0]; j++)
        if (!strcmp(key, keywords[j].key))
            e = keyword(r, key, v, keywords[j].names, keywords[j].n, &k, "a keyword");
    const xmlNode *server;
    if (!strcmp(key, "fill") || !strcmp(key, "stroke"))
        e = parse_paint(r, key, v, &c, &k, &server);
    else if (!strcmp(key, "color"))
        e = parse_colour(r, key, v, &c);
    else if (!strcmp(key, "font-size"))
        e = parse_font_size(r, v, 16, &x);
    else if (!strcmp(key, "stroke-width")) {
        if (!(e = parse_length(r, key, v, &x)) && x < 0 && !r->calc)
            e = fail_at(r, "stroke-width=\"%s\": a negative width is invalid", aa_echo(v));
    } else if (!strcmp(key, "stroke-miterlimit")) {
        if (plain_number(r, v, &x) || !(x >= 1 || r->calc))
            e = fail_at(r, "stroke-miterlimit=\"%s\" is not a number of at least 1",
                        aa_echo(v));
    } else if (!strcmp(key, "stroke-dasharray"))
        e = parse_dasharray(r, v, &sty);
    else if (!strcmp(key, "stroke-dashoffset"))
        e = parse_length(r, key, v, &x);
    else if (!strcmp(key, "opacity") || !strcmp(key, "fill-opacity") ||
             !strcmp(key, "stroke-opacity"))
        e = parse_opacity(r, key, v, &x);
    else if (!strcmp(key, "paint-order"))
        e = parse_paint_order(r, v, &k);
    else if (!strcmp(key, "clip-path"))
        e = clip_path_check(r, v);
    else if (!strcmp(key, "transform") && css) {
        const double box[4] = {0, 0, r->vpw, r->vph};
        e = parse_css_transform(r, v, box, &m);
    } else if (!strcmp(key, "transform-origin")) {
        const double box[4] = {0, 0, r->vpw, r->vph};
        double o[2];
        e = parse_transform_origin(r, v, box, o);
    }
    if (e == AA_OK)
        return 1;
    /* (clip-path's basic shapes are functions its check reads whole) */
    if (e == AA_EINVAL && !r->unsupported && (!strcmp(key, "clip-path") || !unknown_function(v)))
        return 0;
    *st = e;
    return 0;
}

/* The properties every element may set: style into *sty, the element's own
 * transform into *m, its opacity (not inherited) into *opacity; *skip = 1
 * for display: none. */
static int element_props(reader *r, const xmlNode *node, style *sty, mat *m, int *skip,
                         double *opacity)
{
    char v[1024];
    int st = AA_OK, none;
    *skip = 0;
    *opacity = 1;
    if ((st = check_props(r, node)))
        return st;
    if (prop(r, node, "display", v, sizeof v, &st) && !strcasecmp(v, "none")) {
        *skip = 1;
        return AA_OK;
    }
    if (st)
        return st;
    if (prop(r, node, "font-size", v, sizeof v, &st) && strcasecmp(v, "inherit") &&
        (st = parse_font_size(r, v, sty->font_size, &sty->font_size)))
        return st;
    if (st)
        return st;
    r->font_size = sty->font_size; /* em in the element's lengths */
    if (prop(r, node, "color", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        css_colour c;
        if ((st = parse_colour(r, "color", v, &c)))
            return st;
        if (!c.current) /* color: currentColor is color: inherit */
            sty->color = c;
    }
    if (st)
        return st;
    static const char *const paints[2] = {"fill", "stroke"};
    for (int k = 0; k < 2; k++)
        if (prop(r, node, paints[k], v, sizeof v, &st) && strcasecmp(v, "inherit")) {
            css_colour c = {{0, 0, 0}, 1, 0};
            const xmlNode *server;
            if ((st = parse_paint(r, paints[k], v, &c, &none, &server)))
                return st;
            *(k ? &sty->stroke_none : &sty->fill_none) = none;
            *(k ? &sty->stroke_server : &sty->fill_server) = server;
            if (!none && !server)
                *(k ? &sty->stroke : &sty->fill) = c;
        } else if (st)
            return st;
    if (prop(r, node, "fill-rule", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        if (!strcasecmp(v, "nonzero"))
            sty->rule = AA_FILL_NONZERO;
        else if (!strcasecmp(v, "evenodd"))
            sty->rule = AA_FILL_EVENODD;
        else
            return fail_at(r, "fill-rule=\"%s\" (nonzero or evenodd)", aa_echo(v));
    }
    if (!st && prop(r, node, "clip-rule", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        if (!strcasecmp(v, "nonzero"))
            sty->clip_rule = AA_FILL_NONZERO;
        else if (!strcasecmp(v, "evenodd"))
            sty->clip_rule = AA_FILL_EVENODD;
        else
            return fail_at(r, "clip-rule=\"%s\" (nonzero or evenodd)", aa_echo(v));
    }
    if (!st)
        st = stroke_props(r, node, sty);
    static const char *const opacities[] = {"opacity", "fill-opacity", "stroke-opacity"};
    double *const to[3] = {opacity, &sty->fill_opacity, &sty->stroke_opacity};
    for (int k = 0; k < 3 && !st; k++)
        if (prop(r, node, opacities[k], v, sizeof v, &st) && !st) {
            if (!strcasecmp(v, "inherit"))
                continue; /* the inherited properties keep the parent's */
            double o;
            st = parse_opacity(r, opacities[k], v, &o);
            if (!st)
                *to[k] = o;
            else if (st == AA_EINVAL && !r->from_css &&
                     invalid_attr(r, opacities[k], v, "a number or a percentage"))
                st = AA_OK; /* the default: 1, or the parent's */
        }
    if (!st && prop(r, node, "paint-order", v, sizeof v, &st) && strcasecmp(v, "inherit"))
        st = parse_paint_order(r, v, &sty->stroke_first);
    if (!st && prop(r, node, "color-interpolation", v, sizeof v, &st) &&
        strcasecmp(v, "inherit") && strcasecmp(v, "auto") && strcasecmp(v, "sRGB"))
        return fail_at(r, "color-interpolation=\"%s\" is not supported (compositing in "
                          "linear light; auto or sRGB)",
                       aa_echo(v));
    /* clip-path is read where the element is drawn (clip_of) */
    static const char *const refused[] = {"mask", "filter"};
    for (int k = 0; k < 2 && !st; k++)
        if (prop(r, node, refused[k], v, sizeof v, &st) && strcasecmp(v, "none"))
            return fail_at(r, "%s=\"%s\": %s not supported", refused[k], aa_echo(v),
                           k == 0 ? "masks are" : "filters are");
    if (!st && prop(r, node, "visibility", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        if (!strcasecmp(v, "visible"))
            sty->visible = 1;
        else if (!strcasecmp(v, "hidden") || !strcasecmp(v, "collapse"))
            sty->visible = 0;
        else
            return fail_at(r, "visibility=\"%s\" (visible, hidden or collapse)", aa_echo(v));
    }
    if (st)
        return st;
    r->tsty = sty;
    st = element_transform(r, node, m);
    r->tsty = NULL;
    return st;
}

/* A paint's colour in linear light and its alpha (currentColor: the
 * element's color). */
static aa_rgb paint_rgb(const style *sty, const css_colour *c, double *alpha)
{
    const css_colour *u = c->current ? &sty->color : c;
    aa_rgb out;
    for (int k = 0; k < 3; k++)
        out.c[k] = srgb_decode(u->v[k]);
    *alpha = u->alpha;
    return out;
}

/* A group composited as a whole with opacity o around what draw gives. */
static int group_begin(reader *r, double o)
{
    if (!r->sink->group_begin || !r->sink->group_end)
        return fail_at(r, "opacity %g on a group is not taken here", o);
    return r->sink->group_begin(r->ctx, o);
}

/* ---- clip paths ----
 *
 * CSS Masking 1 (clip-path, clipPath) as exact geometry: a clipPath
 * referenced by an element becomes a clip of the scene (the sink's
 * clip_begin .. clip_end, aa_scene_clip_begin), its members the fill
 * geometry of its children, each with its clip-rule, and the element's
 * shapes are drawn inside it (`clip`).
 *
 *   - clip-path="url(#id)" (or url('#id'), url("#id")) on a shape, a <g>,
 *     a child of a clipPath or a clipPath itself (on the root <svg>, in
 *     the CSS px of its layout box, objectBoundingBox its viewport); none
 *     is no clip.  A reference to no element, or to an element that is not a
 *     clipPath, is as if clip-path were not given (SVG 1.1's clip-path: a
 *     reference that is not valid is "treated as if it hadn't been
 *     specified"; the web-platform test css-masking/clip-path-svg-content/
 *     clip-path-invalid-reference.svg and Chromium draw the element
 *     unclipped).  References that come back to a clipPath being read form
 *     a cycle, an error.  Other URLs are refused; basic shapes and
 *     geometry boxes are read below (basic_clip).
 *   - The clip is in the user space of the element referencing it (its
 *     own transform applied, SVG 1.1 14.3.5), then the clipPath's own
 *     transform; with clipPathUnits="objectBoundingBox" the unit square
 *     maps onto the element's object bounding box before that transform
 *     (a point p of the content is at m(T(B(p))), as Chromium and resvg
 *     draw it): the box of its
 *     fill geometry in its user space (SVG 2, "Bounding boxes"), exact for Bezier and
 *     elliptical arcs (their extremes in closed form, geometry_box), of a
 *     group the union of its children's, each through its transform, of a
 *     nested <svg> its content's through x, y and its viewBox map, not cut
 *     by its viewport (as Chromium, resvg and librsvg take it); for a
 *     clip-path on a nested <svg> or a <symbol> itself, whose clip is in
 *     the user space the element establishes, its content's in that space
 *     (content_box; Chromium and resvg alike).  A
 *     box of no width or no height is refused.
 *   - The clip is the union of the clipPath's children: <path>, <rect>,
 *     <circle>, <ellipse>, <polygon>, <polyline> (a <line> has no area),
 *     each's fill geometry through its transform, with its clip-rule
 *     (inherited), inside its own clip-path if it has one; fill, stroke
 *     and opacities do not matter.  A child with display="none" or
 *     visibility hidden or collapse adds nothing (CSS Masking 1, "The
 *     clipPath element");
 *     visibility and clip-rule inherit into the clipPath from its
 *     ancestors, not from the referencing element.  The clipPath's own
 *     clip-path clips the clip (an intersection), in the referencing
 *     element's user space and bounding box.  The display of the clipPath
 *     and its ancestors does not matter (it is referenced, never drawn).
 *     A <use> child adds its target's fill geometry through the use's
 *     transform and translate(x, y), then the target's (its clip-path in
 *     the space after translate(x, y), the target's own within it), the
 *     target's clip-rule and visibility inherited from the use as by a
 *     child; the target must be a shape itself ("Indirect references are
 *     an error", CSS Masking 1): a use of a <g> or of another <use>, or of
 *     nothing, adds nothing, as Chromium draws it (resvg draws a use of a
 *     use).  <text> children are refused (not supported), as is any other
 *     element (not in a clipPath's content model).
 *   - An element's clip lies within the clip of every ancestor group:
 *     the intersection, as the group's content is clipped as a whole.
 *     So it does within the clip of a <use> (its clip-path in its user
 *     space, translate(x, y) included) and of every viewport that clips
 *     around it (a nested <svg> or a used <symbol> of overflow hidden:
 *     a clip whose one member is the viewport's rectangle, made when
 *     first needed, before the clip that lies within it begins).
 *
 * A clipPath referenced alike (the same user space, box and outer clip)
 * by several elements is given once. */

struct svg_ids;
static const xmlNode *find_id(const struct svg_ids *ids, const char *id);

static void clips_free(reader *r)
{
    free(r->made);
    r->made = NULL;
    r->nmade = r->capmade = 0;
}

/* The extent of one coordinate of a Bezier arc of degree n
 * (1, 2 or 3; q its n + 1 control values) grown into [*lo, *hi]: its ends
 * and where its derivative vanishes inside (0, 1), in closed form (the
 * derivative of a cubic is the quadratic (e0 - 2 e1 + e2) t^2 + 2 (e1 -
 * e0) t + e0 times 3, e_i the differences of the control values; of a
 * quadratic, linear). */
static void bezier_extent(const double *q, int n, double *lo, double *hi)
{
    *lo = fmin(*lo, fmin(q[0], q[n]));
    *hi = fmax(*hi, fmax(q[0], q[n]));
    double ts[2];
    int nt = 0;
    if (n == 2) {
        const double den = q[0] - 2 * q[1] + q[2];
        if (den != 0)
            ts[nt++] = (q[0] - q[1]) / den;
    } else if (n == 3) {
        const double e0 = q[1] - q[0], e1 = q[2] - q[1], e2 = q[3] - q[2];
        const double a = e0 - 2 * e1 + e2, b = e1 - e0, c = e0; /* a t^2 + 2 b t + c */
        if (a == 0) {
            if (b != 0)
                ts[nt++] = -c / (2 * b);
        } else {
            const double disc = b * b - a * c;
            if (disc >= 0) {
                /* the root of larger magnitude without cancellation, the
                 * other from their product c / a */
                const double sq = sqrt(disc), big = -(b + copysign(sq, b));
                if (big != 0) {
                    ts[nt++] = big / a;
                    ts[nt++] = c / big;
                } else {
                    ts[nt++] = 0; /* b = disc = 0: a double root at 0 */
                }
            }
        }
    }
    for (int k = 0; k < nt; k++) {
        const double t = ts[k], u = 1 - t;
        if (!(t > 0 && t < 1))
            continue;
        double v;
        if (n == 2)
            v = u * u * q[0] + 2 * t * u * q[1] + t * t * q[2];
        else
            v = u * u * u * q[0] + 3 * t * u * u * q[1] + 3 * t * t * u * q[2] +
                t * t * t * q[3];
        *lo = fmin(*lo, v);
        *hi = fmax(*hi, v);
    }
}

/* A path's fill geometry through m, grown into box (x0 y0 x1 y1): Bezier
 * arcs map to Bezier arcs of the mapped control points; an elliptical arc
 * c + u cos t + v sin t to m(c) + L u cos t + L v sin t, each coordinate
 * c + R cos(t - a) (R = hypot(u, v), a = atan2(v, u)), extreme at
 * t = a + j pi. */
static void path_box(const aa_path *p, const mat *m, double box[4])
{
    double px = 0, py = 0, sx = 0, sy = 0; /* the pen and the subpath's start, mapped */
    for (size_t i = 0; i < p->n; i++) {
        const aa_path_seg *g = &p->seg[i];
        const double *v = g->p;
        double q[2][4];
        int deg = 0;
        switch (g->op) {
        case AA_PATH_MOVE:
            sx = px = m->a * v[0] + m->c * v[1] + m->e;
            sy = py = m->b * v[0] + m->d * v[1] + m->f;
            q[0][0] = px, q[1][0] = py;
            break;
        case AA_PATH_LINE:
        case AA_PATH_QUAD:
        case AA_PATH_CUBIC:
            deg = g->op == AA_PATH_LINE ? 1 : g->op == AA_PATH_QUAD ? 2 : 3;
            q[0][0] = px, q[1][0] = py;
            for (int j = 0; j < deg; j++) {
                q[0][j + 1] = m->a * v[2 * j] + m->c * v[2 * j + 1] + m->e;
                q[1][j + 1] = m->b * v[2 * j] + m->d * v[2 * j + 1] + m->f;
            }
            px = q[0][deg], py = q[1][deg];
            break;
        case AA_PATH_ARC: {
            const double c[2] = {m->a * v[0] + m->c * v[1] + m->e, m->b * v[0] + m->d * v[1] + m->f};
            const double u[2] = {m->a * v[2] + m->c * v[3], m->b * v[2] + m->d * v[3]};
            const double w[2] = {m->a * v[4] + m->c * v[5], m->b * v[4] + m->d * v[5]};
            const double tl = fmin(v[6], v[7]), th = fmax(v[6], v[7]);
            px = m->a * v[8] + m->c * v[9] + m->e;
            py = m->b * v[8] + m->d * v[9] + m->f;
            const double end[2] = {px, py};
            for (int k = 0; k < 2; k++) {
                box[k] = fmin(box[k], end[k]), box[k + 2] = fmax(box[k + 2], end[k]);
                const double a = atan2(w[k], u[k]), R = hypot(u[k], w[k]);
                for (double j = ceil((tl - a) / M_PI); a + j * M_PI < th; j += 1.0) {
                    const double e = fmod(fabs(j), 2.0) == 0.0 ? c[k] + R : c[k] - R;
                    box[k] = fmin(box[k], e), box[k + 2] = fmax(box[k + 2], e);
                }
            }
            continue;
        }
        case AA_PATH_OFFSET: {
            /* an offset curve or evolute of a stroke's outline (stroke_box),
             * through m: its ends and where a mapped coordinate turns, in
             * closed form (aa__offset_turns; the outline's pieces have no
             * fold inside, where the offset's tangent would vanish) */
            aa_offset_curve oc = {{0}, {m->a, m->b, m->c, m->d, m->e, m->f}, v[8], v[9] != 0,
                                  (int)v[14]};
            memcpy(oc.b, v, sizeof oc.b);
            const double lo = fmin(v[10], v[11]), hi = fmax(v[10], v[11]);
            double t[6] = {lo, hi};
            int nt = 2;
            for (int k = 0; k < 2; k++)
                nt += aa__offset_turns(&oc, k, lo, hi, t + nt);
            for (int j = 0; j < nt; j++) {
                double x, y;
                aa_offset_point(&oc, t[j], &x, &y, NULL, NULL);
                box[0] = fmin(box[0], x), box[2] = fmax(box[2], x);
                box[1] = fmin(box[1], y), box[3] = fmax(box[3], y);
            }
            px = m->a * v[12] + m->c * v[13] + m->e;
            py = m->b * v[12] + m->d * v[13] + m->f;
            box[0] = fmin(box[0], px), box[2] = fmax(box[2], px);
            box[1] = fmin(box[1], py), box[3] = fmax(box[3], py);
            continue;
        }
        default: /* a close: back to the start, a point already counted */
            px = sx, py = sy;
            continue;
        }
        for (int k = 0; k < 2; k++)
            bezier_extent(q[k], deg, &box[k], &box[k + 2]);
    }
}

static int viewbox_map(reader *r, const xmlNode *node, double vw, double vh, mat *m,
                       double vb[2]);
static int viewport_side(reader *r, const xmlNode *node, const xmlNode *over, const char *key,
                         double *v);
static int use_target(reader *r, const xmlNode *node, const xmlNode **out);
static int symbol_shift(reader *r, const xmlNode *node, const mat *vbm, const double vb[2],
                        double s[2]);

/* 1 if the use `node`'s target is the use or one of its ancestors, or of
 * the uses the bounding box walk has followed to reach it: a reference
 * cycle, in error (nothing, as where it is drawn). */
static int bbox_cycle(const reader *r, const xmlNode *node, const xmlNode *target)
{
    for (int k = 0; k <= r->nb; k++)
        for (const xmlNode *a = k < r->nb ? r->bchain[k] : node; a; a = a->parent)
            if (a == target)
                return 1;
    return 0;
}

static int geometry_walk(reader *r, const xmlNode *node, const mat *m, double box[4], int depth);

/* The fill geometry of node and what it holds through m, grown into box
 * (SVG 2's object bounding box: shapes, and groups by their children, each
 * through its own transform; a <use> by its target's, through translate(x,
 * y), as the target is drawn there; elements with display="none" and
 * those that draw nothing are left out).  A walk visits at most
 * AA_SVG_MAX_ELEMENTS elements, uses' instances counted, as a drawing. */
static int geometry_box(reader *r, const xmlNode *node, const mat *m, double box[4], int depth)
{
    if (!r->blevel++)
        r->belements = 0, r->nb = 0, r->bvia = NULL;
    int st = geometry_walk(r, node, m, box, depth);
    r->blevel--;
    return st;
}

static int geometry_walk(reader *r, const xmlNode *node, const mat *m, double box[4], int depth)
{
    static const char *const shapes[] = {"path",    "rect",    "circle",  "ellipse",
                                         "line",    "polygon", "polyline"};
    /* the use whose target node is, if it is one */
    const xmlNode *via = r->bvia;
    r->bvia = NULL;
    if (!is_svg(node) || depth > AA_SVG_MAX_DEPTH)
        return AA_OK; /* another namespace; too deep is refused where drawn */
    if (++r->belements > AA_SVG_MAX_ELEMENTS)
        return fail_at(r, "a bounding box of more than %d elements (use instances counted)",
                       AA_SVG_MAX_ELEMENTS);
    char v[64];
    int st = AA_OK;
    const xmlNode *was = r->node;
    r->node = node;
    if ((prop(r, node, "display", v, sizeof v, &st) && !strcasecmp(v, "none")) ||
        !conditions_hold(node)) {
        r->node = was;
        return AA_OK;
    }
    int shape = 0;
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
        shape |= named(node, shapes[k]);
    if (!st && shape) {
        aa_path p;
        aa_path_init(&p);
        if (!(st = shape_path(r, node, &p)))
            path_box(&p, m, box);
        aa_path_free(&p);
    } else if (!st && named(node, "use")) {
        /* its target through translate(x, y) and the target's own
         * transform, as use_element draws it */
        const xmlNode *target;
        double x = 0, y = 0;
        if (!(st = use_target(r, node, &target)) && target && !bbox_cycle(r, node, target) &&
            !(st = attr_length(r, node, "x", 0, &x)) &&
            !(st = attr_length(r, node, "y", 0, &y))) {
            const mat at = {1, 0, 0, 1, x, y};
            mat mt = mat_mul(*m, at);
            r->bchain[r->nb++] = node;
            if (!(st = element_transform(r, target, &mt))) {
                r->bvia = node;
                st = geometry_walk(r, target, &mt, box, depth + 1);
            }
            r->nb--;
        }
    } else if (!st && (named(node, "g") || named(node, "svg") ||
                       (via && named(node, "symbol")))) {
        /* a nested <svg>, or a symbol or svg a use draws: its content
         * through translate(x, y) (its own, and a symbol's
         * reference point's shift) and its viewBox map, of the use's width
         * and height where it gives them, unclipped (its overflow does not
         * change the box: Chromium, resvg and librsvg alike); one of no
         * area adds nothing */
        mat mv = *m;
        double vb[2] = {r->vpw, r->vph}, pw = r->vpw, ph = r->vph;
        int drawn = 1;
        if ((named(node, "svg") && node != r->root) || named(node, "symbol")) {
            double x = 0, y = 0, w = 0, h = 0, sh[2] = {0, 0};
            mat vbm;
            if (!(st = attr_length(r, node, "x", 0, &x)))
                st = attr_length(r, node, "y", 0, &y);
            if (!st && !(st = viewport_side(r, node, via, "width", &w)) &&
                !(st = viewport_side(r, node, via, "height", &h)) &&
                (drawn = w > 0 && h > 0) && !(st = viewbox_map(r, node, w, h, &vbm, vb)) &&
                !(st = symbol_shift(r, node, &vbm, vb, sh))) {
                const mat at = {1, 0, 0, 1, x + sh[0], y + sh[1]};
                mv = mat_mul(*m, mat_mul(at, vbm));
            }
        }
        r->vpw = vb[0], r->vph = vb[1];
        for (const xmlNode *c = node->children; c && !st && drawn; c = c->next) {
            if (c->type != XML_ELEMENT_NODE)
                continue;
            mat mc = mv;
            if (!(st = element_transform(r, c, &mc)))
                st = geometry_walk(r, c, &mc, box, depth + 1);
        }
        r->vpw = pw, r->vph = ph;
    } else if (!st && named(node, "switch")) {
        /* the child it draws */
        const xmlNode *c;
        if (!(st = switch_choice(r, node, &c)) && c) {
            mat mc = *m;
            if (!(st = element_transform(r, c, &mc)))
                st = geometry_walk(r, c, &mc, box, depth + 1);
        }
    }
    r->node = was;
    return st;
}

/* The clip-path value: *id the fragment of url(#id) (in buf), NULL for
 * none. */
static int clip_ref(reader *r, const char *v, char *buf, size_t len, const char **id)
{
    *id = NULL;
    if (!strcasecmp(v, "none"))
        return AA_OK;
    if (strncasecmp(v, "url(", 4))
        return fail_at(r, "clip-path=\"%s\": only url(#id) is supported (CSS basic shapes and "
                          "geometry boxes are not)",
                       aa_echo(v));
    const char *a = skip_wsp(v + 4), *e = strrchr(a, ')');
    if (!e || *skip_wsp(e + 1))
        return fail_at(r, "clip-path=\"%s\" is not url(...)", aa_echo(v));
    while (e > a && is_wsp((unsigned char)e[-1]))
        e--;
    if (e > a && (*a == '\'' || *a == '"')) {
        if (e - a < 2 || e[-1] != *a)
            return fail_at(r, "clip-path=\"%s\": an unclosed quote", aa_echo(v));
        a++, e--;
    }
    if (a == e || *a != '#' || e - a < 2)
        return fail_at(r, "clip-path=\"%s\": only a reference into this document "
                          "(url(#id)) is supported",
                       aa_echo(v));
    if ((size_t)(e - a) > len)
        return fail_at(r, "clip-path=\"%s\": the id is too long", aa_echo(v));
    memcpy(buf, a + 1, (size_t)(e - a - 1));
    buf[e - a - 1] = '\0';
    *id = buf;
    return AA_OK;
}

static int clip_resolve(reader *r, const char *value, const xmlNode *ref, const mat *m,
                        int outer, int *out);

/* One element's clip-rule and visibility over the inherited ones in sty. */
static int clip_style(reader *r, const xmlNode *node, style *sty)
{
    char v[64];
    int st = AA_OK;
    r->node = node;
    if (prop(r, node, "clip-rule", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        if (!strcasecmp(v, "nonzero") || !strcasecmp(v, "evenodd"))
            sty->clip_rule = strcasecmp(v, "nonzero") ? AA_FILL_EVENODD : AA_FILL_NONZERO;
        else
            st = fail_at(r, "clip-rule=\"%s\" (nonzero or evenodd)", aa_echo(v));
    }
    if (!st && prop(r, node, "visibility", v, sizeof v, &st) && strcasecmp(v, "inherit")) {
        if (!strcasecmp(v, "visible"))
            sty->visible = 1;
        else if (!strcasecmp(v, "hidden") || !strcasecmp(v, "collapse"))
            sty->visible = 0;
        else
            st = fail_at(r, "visibility=\"%s\" (visible, hidden or collapse)", aa_echo(v));
    }
    return st;
}

/* The clip of node: its clip-path resolved in its user space m within
 * `outer` (outer itself when it has none). */
static int clip_of(reader *r, const xmlNode *node, const mat *m, int outer, int *out)
{
    char v[1024];
    int st = AA_OK;
    *out = outer;
    r->node = node;
    if (!prop(r, node, "clip-path", v, sizeof v, &st))
        return st;
    return clip_resolve(r, v, node, m, outer, out);
}

/* clip-rule and visibility inherited into a clipPath from its ancestors
 * (the root down), then its own: CSS Masking 1, properties inherit into
 * the clipPath from its ancestors, not from the referencing element. */
static int clip_inherited(reader *r, const xmlNode *cp, style *sty)
{
    const xmlNode *chain[AA_SVG_MAX_DEPTH + 2];
    int n = 0, st = AA_OK;
    for (const xmlNode *a = cp; a && a->type == XML_ELEMENT_NODE; a = a->parent) {
        if (n == AA_SVG_MAX_DEPTH + 2)
            return fail_at(r, "elements nested deeper than %d", AA_SVG_MAX_DEPTH);
        chain[n++] = a;
    }
    while (n-- > 0 && !st)
        st = clip_style(r, chain[n], sty);
    return st;
}

/* A child of a clipPath as a member: its path in user units, its map, its
 * clip-rule and its own clip. */
typedef struct clip_member {
    aa_path path;
    mat m;
    aa_fill_rule rule;
    int gate;
} clip_member;

/* The bounding box of the content of a nested <svg> or a <symbol> in the
 * user space it establishes (SVG 2's getBBox of the element: the union of
 * its children's boxes, each through its transform; geometry_walk), the
 * percentages in it of its viewBox's size vb, added to box. */
static int content_box(reader *r, const xmlNode *node, const double vb[2], double box[4])
{
    if (!r->blevel++)
        r->belements = 0, r->nb = 0, r->bvia = NULL;
    const double pw = r->vpw, ph = r->vph;
    r->vpw = vb[0], r->vph = vb[1];
    int st = AA_OK;
    for (const xmlNode *c = node->children; c && !st; c = c->next) {
        if (c->type != XML_ELEMENT_NODE)
            continue;
        mat mc = identity;
        if (!(st = element_transform(r, c, &mc)))
            st = geometry_walk(r, c, &mc, box, 1);
    }
    r->vpw = pw, r->vph = ph;
    r->blevel--;
    return st;
}

/* The clipPath cp referenced by `ref` (whose user space is m, whose clip
 * outside is `outer`) given to the sink: its number into *out. */
static int clip_make(reader *r, const xmlNode *cp, const xmlNode *ref, const mat *m, int outer,
                     int *out)
{
    char v[1024];
    int st = AA_OK;
    r->node = cp;
    if ((st = check_props(r, cp)))
        return st;
    /* the content's user space: m, then the clipPath's transform, then the
     * object bounding box (its unit square onto the box, in the user space
     * the transform maps: p -> m(T(B(p))), as Chromium and resvg compose
     * them) */
    mat mc = *m;
    double box[4] = {0, 0, 0, 0};
    xmlChar *units = xmlGetNoNsProp(cp, (const xmlChar *)"clipPathUnits");
    int obb = 0;
    if (units) {
        const char *u = skip_wsp((const char *)units);
        size_t n = strlen(u);
        while (n && is_wsp((unsigned char)u[n - 1]))
            n--;
        if (n == 17 && !strncmp(u, "objectBoundingBox", n))
            obb = 1;
        else if (!(n == 14 && !strncmp(u, "userSpaceOnUse", n)))
            st = fail_at(r, "clipPathUnits=\"%s\" (userSpaceOnUse or objectBoundingBox)",
                         aa_echo((const char *)units));
        xmlFree(units);
        if (st)
            return st;
    }
    if (obb && ref == r->root) {
        /* the root: its layout box, the viewport in CSS px (CSS Masking 1:
         * an element with a layout box takes its border box) */
        box[2] = r->rootw, box[3] = r->rooth;
    } else if (obb && ref == r->clip_viewport) {
        /* a nested <svg> or a <symbol>: the clip is in the user space the
         * element establishes, and so is the box, its content's there
         * (content_box; Chromium draws it so) */
        double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        if ((st = content_box(r, ref, r->clip_viewport_vb, b)))
            return st;
        r->node = cp;
        if (!(b[2] > b[0] && b[3] > b[1]))
            return fail_at(r, "clipPathUnits=\"objectBoundingBox\" for the <%s> of line %ld, "
                              "whose content's bounding box has no width or no height",
                           (const char *)ref->name, xmlGetLineNo(ref));
        memcpy(box, b, sizeof box);
    } else if (obb) {
        /* the box in the clip's user space: for a <use>, that space has
         * translate(x, y) in it (use_element), so the box is its target's
         * as the use draws it, less that translation (Chromium and resvg
         * alike: a use at x = 20 of a rect at 10 clipped to the box's left
         * half keeps 30 to 50) */
        double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY}, x = 0, y = 0;
        if (named(ref, "use") &&
            ((st = attr_length(r, ref, "x", 0, &x)) || (st = attr_length(r, ref, "y", 0, &y))))
            return st;
        const mat back = {1, 0, 0, 1, -x, -y};
        if ((st = geometry_box(r, ref, &back, b, 0)))
            return st;
        r->node = cp;
        if (!(b[2] > b[0] && b[3] > b[1]))
            return fail_at(r, "clipPathUnits=\"objectBoundingBox\" for the <%s> of line %ld, "
                              "whose bounding box has no width or no height",
                           (const char *)ref->name, xmlGetLineNo(ref));
        memcpy(box, b, sizeof box);
    }
    if ((st = element_transform(r, cp, &mc)))
        return st;
    if (obb) {
        const mat bb = {box[2] - box[0], 0, 0, box[3] - box[1], box[0], box[1]};
        mc = mat_mul(mc, bb);
    }
    /* referenced alike before: the same clip */
    for (size_t k = 0; k < r->nmade; k++) {
        const clip_made *c = &r->made[k];
        if (c->node == cp && c->within == outer && !memcmp(&c->m, m, sizeof *m) &&
            !memcmp(c->box, box, sizeof box)) {
            *out = c->id;
            return AA_OK;
        }
    }
    /* its own clip-path, in the referencing element's user space and box */
    int within = outer;
    r->node = cp;
    if (prop(r, cp, "clip-path", v, sizeof v, &st) && !st)
        st = clip_resolve(r, v, ref, m, outer, &within);
    if (st)
        return st;
    style inh;
    initial_style(&inh);
    if ((st = clip_inherited(r, cp, &inh)))
        return st;
    /* the members, their own clips given first (no clip begins inside
     * another's definition) */
    size_t n = 0;
    for (const xmlNode *c = cp->children; c; c = c->next)
        n += c->type == XML_ELEMENT_NODE;
    clip_member *mem = n ? calloc(n, sizeof *mem) : NULL;
    if (n && !mem)
        return aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
    size_t nm = 0;
    static const char *const shapes[] = {"path", "rect", "circle", "ellipse", "polygon",
                                         "polyline", "line"};
    for (const xmlNode *c = cp->children; c && !st; c = c->next) {
        if (c->type != XML_ELEMENT_NODE || !is_svg(c) || !conditions_hold(c))
            continue;
        r->node = c;
        if (named(c, "title") || named(c, "desc") || named(c, "metadata"))
            continue;
        int use = named(c, "use"), shape = 0;
        for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
            shape |= named(c, shapes[k]);
        if (!shape && !use) {
            st = named(c, "text")
                     ? fail_at(r, "<%s> in a <clipPath> is not supported", (const char *)c->name)
                     : fail_at(r, "not allowed in a <clipPath> (CSS Masking 1: shapes, text "
                                  "and use)");
            break;
        }
        /* a <use>: its target, which must be a shape itself (CSS Masking
         * 1: "it must directly reference path, text or basic shapes
         * elements. Indirect references are an error"); one that is not
         * (a <g>, another <use>) or is missing adds nothing, as Chromium
         * draws it (resvg draws a use of a use) */
        const xmlNode *t = c;
        if (use) {
            if ((st = check_props(r, c)))
                break;
            if (prop(r, c, "display", v, sizeof v, &st) && !strcasecmp(v, "none"))
                continue;
            if (st || (st = use_target(r, c, &t)))
                break;
            int direct = 0;
            for (size_t k = 0; t && is_svg(t) && k < sizeof shapes / sizeof shapes[0]; k++)
                direct |= named(t, shapes[k]);
            if (!direct || !conditions_hold(t))
                continue;
            r->node = t;
        }
        /* the shape's own properties; a use's first, inherited by its
         * target as by a child (its shadow tree) */
        style cs = inh;
        if (use && (st = clip_style(r, c, &cs)))
            break;
        if ((st = check_props(r, t)))
            break;
        if (prop(r, t, "display", v, sizeof v, &st) && !strcasecmp(v, "none"))
            continue;
        static const char *const refused[] = {"mask", "filter"};
        for (int k = 0; k < 2 && !st; k++)
            if (prop(r, t, refused[k], v, sizeof v, &st) && strcasecmp(v, "none"))
                st = fail_at(r, "%s=\"%s\": %s not supported", refused[k], aa_echo(v),
                             k == 0 ? "masks are" : "filters are");
        if (st || (st = clip_style(r, t, &cs)))
            break;
        if (!cs.visible || named(t, "line")) /* hidden, or no area */
            continue;
        clip_member *k = &mem[nm];
        aa_path_init(&k->path);
        k->m = mc;
        k->rule = cs.clip_rule;
        nm++;
        int gate = -1;
        if (use) {
            /* the use's transform, then translate(x, y), in which space its
             * own clip-path lies (as use_element draws it) */
            double x, y;
            if ((st = element_transform(r, c, &k->m)) ||
                (st = attr_length(r, c, "x", 0, &x)) || (st = attr_length(r, c, "y", 0, &y)))
                break;
            const mat at = {1, 0, 0, 1, x, y};
            k->m = mat_mul(k->m, at);
            if ((st = clip_of(r, c, &k->m, -1, &gate)))
                break;
        }
        if ((st = element_transform(r, t, &k->m)) || (st = shape_path(r, t, &k->path)) ||
            (st = clip_of(r, t, &k->m, gate, &k->gate)))
            break;
    }
    if (!st && (st = r->sink->clip_begin(r->ctx, within)))
        st = at_element(r, st);
    const int was = r->clip;
    const aa_rgb none = {{0, 0, 0}};
    for (size_t k = 0; k < nm && !st; k++) {
        r->clip = mem[k].gate;
        st = give_path(r, &mem[k].path, &mem[k].m, none, mem[k].rule, 1.0, NULL);
    }
    r->clip = was;
    if (!st)
        st = r->sink->clip_end(r->ctx);
    for (size_t k = 0; k < nm; k++)
        aa_path_free(&mem[k].path);
    free(mem);
    if (st)
        return st;
    *out = r->nclips++;
    return clip_record(r, cp, m, box, outer, *out);
}

/* ---- clip-path: basic shapes and geometry boxes ----
 *
 * CSS Masking 1's clip-path = <basic-shape> || <geometry-box>, made a clip
 * of one member: the shape (CSS Shapes 1: inset(), circle(), ellipse(),
 * polygon(), path(), xywh(), rect()) in the element's user space, placed
 * and sized by the reference box, or the box itself when no shape is
 * given.  For an element without a CSS layout box (every SVG element but
 * the root) border-box and margin-box are stroke-box, padding-box and
 * content-box fill-box, and the box defaults to border-box, so stroke-box
 * (Chromium draws it so: a shape's stroke inside clip-path: inset(0) is
 * kept whole); view-box is the nearest viewport's viewBox (its origin and
 * size; the viewport's size without one).  The root <svg> has a layout
 * box: every box is its viewport's rectangle, in CSS px before its
 * viewBox map (as Chromium draws it).  Percentages are of the box's width
 * or height, a circle's radius of its normalised diagonal sqrt((w^2 + h^2)
 * / 2); the shape's coordinates start at the box's top left corner. */

/* A length or percentage of a basic shape at *s: *pct 1 for a percentage
 * (v in percent), else v in user units; whitespace after it skipped. */
static int bs_lp(reader *r, const char **s, double *v, int *pct)
{
    const char *a = *s;
    if (!scan_number(s, v) && **s == '%') {
        *pct = 1;
        *s = skip_wsp(*s + 1);
        return 0;
    }
    *s = a;
    *pct = 0;
    if (css_length(r, s, 0, 1, v)) {
        *s = a;
        return -1;
    }
    *s = skip_wsp(*s);
    return 0;
}

/* A length or percentage of `ref` at *s. */
static int bs_len(reader *r, const char **s, double ref, double *v)
{
    int pct;
    if (bs_lp(r, s, v, &pct))
        return -1;
    if (pct)
        *v *= ref / 100;
    return 0;
}

/* 1 and *s past it (and whitespace) if the keyword w is at *s. */
static int bs_word(const char **s, const char *w)
{
    const size_t n = strlen(w);
    const char c = (*s)[n];
    if (strncasecmp(*s, w, n) || isalnum((unsigned char)c) || c == '-' || c == '_')
        return 0;
    *s = skip_wsp(*s + n);
    return 1;
}

/* A comma and whitespace at *s: 1 if there was one. */
static int bs_comma(const char **s)
{
    if (**s != ',')
        return 0;
    *s = skip_wsp(*s + 1);
    return 1;
}

/* A <position> (CSS Values 4: one value; two, x then y or two keywords in
 * either order; four, a side and an offset for each axis) in the box b
 * (x y w h) into c. */
static int bs_position(reader *r, const char **s, const double b[4], double c[2])
{
    /* each value: a keyword (0 left, 1 right, 2 top, 3 bottom, 4 center)
     * or 5 a length-percentage */
    static const char *const kw[] = {"left", "right", "top", "bottom", "center"};
    int kind[4], pct[4], n = 0;
    double v[4];
    while (**s && **s != ')' && **s != ',') {
        if (n == 4)
            return -1;
        int k = 0;
        while (k < 5 && !bs_word(s, kw[k]))
            k++;
        if (k == 5 && bs_lp(r, s, &v[n], &pct[n]))
            return -1;
        kind[n++] = k;
    }
    /* x and y as a fraction of the box (f, when frac) or an offset from
     * its left or top */
    double off[2] = {0, 0}, f[2] = {0.5, 0.5};
    int frac[2] = {1, 1};
    if (n == 1) {
        if (kind[0] == 5)
            frac[0] = pct[0], f[0] = v[0] / 100, off[0] = v[0];
        else if (kind[0] < 4)
            f[kind[0] / 2] = kind[0] & 1;
    } else if (n == 2) {
        int a = 0, bb = 1;
        /* two keywords with the vertical first, or center and a horizontal */
        if (kind[0] != 5 && kind[1] != 5 &&
            (kind[0] == 2 || kind[0] == 3 || kind[1] == 0 || kind[1] == 1))
            a = 1, bb = 0;
        if (kind[a] == 2 || kind[a] == 3 || kind[bb] == 0 || kind[bb] == 1)
            return -1;
        const int ax[2] = {a, bb};
        for (int k = 0; k < 2; k++) {
            const int i = ax[k];
            if (kind[i] == 5)
                frac[k] = pct[i], f[k] = v[i] / 100, off[k] = v[i];
            else if (kind[i] != 4)
                f[k] = kind[i] & 1;
        }
    } else if (n == 4) {
        if (kind[0] > 3 || kind[2] > 3 || kind[1] != 5 || kind[3] != 5 ||
            kind[0] / 2 == kind[2] / 2)
            return -1;
        for (int k = 0; k < 4; k += 2) {
            const int axis = kind[k] / 2, far = kind[k] & 1;
            const double d = pct[k + 1] ? v[k + 1] / 100 * b[2 + axis] : v[k + 1];
            frac[axis] = 0;
            off[axis] = far ? b[2 + axis] - d : d;
        }
    } else
        return -1;
    for (int k = 0; k < 2; k++)
        c[k] = b[k] + (frac[k] ? f[k] * b[2 + k] : off[k]);
    return 0;
}

/* border-radius's values after `round` (CSS Backgrounds 3: one to four
 * horizontal radii, then optionally / and one to four vertical ones;
 * percentages of the box's width and height) into rad[corner][axis], the
 * corners top left, top right, bottom right, bottom left. */
static int bs_radii(reader *r, const char **s, const double b[4], double rad[4][2])
{
    double v[2][4];
    int pct[2][4], n[2] = {0, 0};
    for (int axis = 0; axis < 2; axis++) {
        while (**s && **s != ')' && **s != '/') {
            if (n[axis] == 4 || bs_lp(r, s, &v[axis][n[axis]], &pct[axis][n[axis]]) ||
                v[axis][n[axis]] < 0)
                return -1;
            n[axis]++;
        }
        if (!n[axis])
            return -1;
        if (axis == 0 && **s != '/') {
            memcpy(v[1], v[0], sizeof v[0]);
            memcpy(pct[1], pct[0], sizeof pct[0]);
            n[1] = n[0];
            break;
        }
        if (axis == 0)
            *s = skip_wsp(*s + 1);
    }
    /* the omitted corners: bottom right as top left, top right's for the
     * others */
    static const int from[4][4] = {{0, 0, 0, 0}, {0, 1, 0, 1}, {0, 1, 2, 1}, {0, 1, 2, 3}};
    for (int axis = 0; axis < 2; axis++)
        for (int k = 0; k < 4; k++) {
            const int j = from[n[axis] - 1][k];
            rad[k][axis] = pct[axis][j] ? v[axis][j] / 100 * b[2 + axis] : v[axis][j];
        }
    return 0;
}

/* The rectangle x0 y0 x1 y1 with corners of radii rad (as bs_radii),
 * scaled down together when they do not fit (CSS Backgrounds 3: by the
 * least ratio of a side to the sum of its two radii), a corner with a
 * radius of 0 square; nothing when it has no area. */
static int bs_rect(reader *r, aa_path *p, double x0, double y0, double x1, double y1,
                   double rad[4][2])
{
    if (!(x1 > x0 && y1 > y0))
        return AA_OK;
    const double w = x1 - x0, h = y1 - y0;
    const double sums[4] = {rad[0][0] + rad[1][0], rad[1][1] + rad[2][1], rad[2][0] + rad[3][0],
                            rad[3][1] + rad[0][1]};
    double f = 1;
    for (int k = 0; k < 4; k++)
        if (sums[k] > 0)
            f = fmin(f, (k & 1 ? h : w) / sums[k]);
    for (int k = 0; k < 4; k++) {
        rad[k][0] *= f, rad[k][1] *= f;
        if (!(rad[k][0] > 0 && rad[k][1] > 0))
            rad[k][0] = rad[k][1] = 0;
    }
    /* the corners' ends along the sides, clockwise from the top left's
     * end on the top side */
    const double tl[2] = {rad[0][0], rad[0][1]}, tr[2] = {rad[1][0], rad[1][1]};
    const double br[2] = {rad[2][0], rad[2][1]}, bl[2] = {rad[3][0], rad[3][1]};
    int st;
    if ((st = p_move(r, p, x0 + tl[0], y0)))
        return st;
    if (x1 - tr[0] > x0 + tl[0] && (st = p_line(r, p, x1 - tr[0], y0)))
        return st;
    if (tr[0] > 0 &&
        (st = p_quarter(r, p, x1 - tr[0], y0 + tr[1], tr[0], tr[1], -1, x1, y0 + tr[1])))
        return st;
    if (y1 - br[1] > y0 + tr[1] && (st = p_line(r, p, x1, y1 - br[1])))
        return st;
    if (br[0] > 0 &&
        (st = p_quarter(r, p, x1 - br[0], y1 - br[1], br[0], br[1], 0, x1 - br[0], y1)))
        return st;
    if (x0 + bl[0] < x1 - br[0] && (st = p_line(r, p, x0 + bl[0], y1)))
        return st;
    if (bl[0] > 0 &&
        (st = p_quarter(r, p, x0 + bl[0], y1 - bl[1], bl[0], bl[1], 1, x0, y1 - bl[1])))
        return st;
    if (y0 + tl[1] < y1 - bl[1] && (st = p_line(r, p, x0, y0 + tl[1])))
        return st;
    if (tl[0] > 0 &&
        (st = p_quarter(r, p, x0 + tl[0], y0 + tl[1], tl[0], tl[1], 2, x0 + tl[0], y0)))
        return st;
    return p_close(r, p);
}

/* The ellipse of centre c and radii rx, ry: four quarters, closed, as
 * <ellipse> draws it; nothing if a radius is 0. */
static int bs_ellipse(reader *r, aa_path *p, const double c[2], double rx, double ry)
{
    int st;
    if (!(rx > 0 && ry > 0))
        return AA_OK;
    if ((st = p_move(r, p, c[0] + rx, c[1])) ||
        (st = p_quarter(r, p, c[0], c[1], rx, ry, 0, c[0], c[1] + ry)) ||
        (st = p_quarter(r, p, c[0], c[1], rx, ry, 1, c[0] - rx, c[1])) ||
        (st = p_quarter(r, p, c[0], c[1], rx, ry, 2, c[0], c[1] - ry)) ||
        (st = p_quarter(r, p, c[0], c[1], rx, ry, 3, c[0] + rx, c[1])))
        return st;
    return p_close(r, p);
}

/* A fill-rule and a comma at the start of polygon() or path(), if there. */
static void bs_rule(const char **s, aa_fill_rule *rule)
{
    const char *a = *s;
    int k = bs_word(s, "nonzero") ? 1 : bs_word(s, "evenodd") ? 2 : 0;
    if (k && bs_comma(s))
        *rule = k == 2 ? AA_FILL_EVENODD : AA_FILL_NONZERO;
    else
        *s = a;
}

/* The basic shape `fn` (its name n characters long; s its arguments, up
 * to the closing parenthesis) in the box b (x y w h) as a path in user
 * units and its fill rule (path(): in the units from the box's corner,
 * shift); -1 malformed, else 0 with *st the status of making it. */
static int bs_shape(reader *r, const char *fn, size_t n, const char **s, const double b[4],
                    aa_path *p, aa_fill_rule *rule, double shift[2], int *st)
{
    static const char *const names[] = {"inset", "circle", "ellipse", "polygon",
                                        "path",  "xywh",   "rect"};
    size_t kind = 0;
    while (kind < 7 && !(strlen(names[kind]) == n && !strncasecmp(fn, names[kind], n)))
        kind++;
    if (kind == 7)
        return -1;
    *rule = AA_FILL_NONZERO;
    double rad[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
    double e[4], c[2];
    if (kind == 1 || kind == 2) { /* circle(), ellipse() */
        /* the radii: closest-side (initial), farthest-side or a length */
        int side[2] = {1, 1}, nr = 0;
        double rr[2];
        while (nr < (kind == 1 ? 1 : 2) && **s != ')' && strncasecmp(*s, "at", 2)) {
            if (bs_word(s, "closest-side"))
                side[nr] = 1;
            else if (bs_word(s, "farthest-side"))
                side[nr] = 2;
            else {
                const double ref = kind == 1 ? sqrt((b[2] * b[2] + b[3] * b[3]) / 2) : b[2 + nr];
                if (bs_len(r, s, ref, &rr[nr]) || rr[nr] < 0)
                    return -1;
                side[nr] = 0;
            }
            nr++;
        }
        if (kind == 2 && nr == 1)
            return -1;
        c[0] = b[0] + b[2] / 2, c[1] = b[1] + b[3] / 2;
        if (bs_word(s, "at") && bs_position(r, s, b, c))
            return -1;
        if (**s != ')')
            return -1;
        const double dx[2] = {fabs(c[0] - b[0]), fabs(b[0] + b[2] - c[0])};
        const double dy[2] = {fabs(c[1] - b[1]), fabs(b[1] + b[3] - c[1])};
        double rx, ry;
        if (kind == 1) {
            rx = side[0] == 0 ? rr[0]
                 : side[0] == 1 ? fmin(fmin(dx[0], dx[1]), fmin(dy[0], dy[1]))
                                : fmax(fmax(dx[0], dx[1]), fmax(dy[0], dy[1]));
            ry = rx;
        } else {
            rx = side[0] == 0 ? rr[0] : side[0] == 1 ? fmin(dx[0], dx[1]) : fmax(dx[0], dx[1]);
            ry = side[1] == 0 ? rr[1] : side[1] == 1 ? fmin(dy[0], dy[1]) : fmax(dy[0], dy[1]);
        }
        *st = bs_ellipse(r, p, c, rx, ry);
        return 0;
    }
    if (kind == 3) { /* polygon([rule,] x y, ...) */
        bs_rule(s, rule);
        int k = 0;
        do {
            double xy[2];
            if (bs_len(r, s, b[2], &xy[0]) || bs_len(r, s, b[3], &xy[1]))
                return -1;
            *st = k++ ? p_line(r, p, b[0] + xy[0], b[1] + xy[1])
                      : p_move(r, p, b[0] + xy[0], b[1] + xy[1]);
            if (*st)
                return 0;
        } while (bs_comma(s));
        if (**s != ')')
            return -1;
        *st = p_close(r, p);
        return 0;
    }
    if (kind == 4) { /* path([rule,] "data"), from the box's corner (shift) */
        bs_rule(s, rule);
        const char q = **s;
        const char *end = q == '"' || q == '\'' ? strchr(*s + 1, q) : NULL;
        if (!end || *skip_wsp(end + 1) != ')')
            return -1;
        char *d = strndup(*s + 1, (size_t)(end - *s - 1));
        if (!d) {
            *st = aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
            return 0;
        }
        *st = path_data(r, p, d);
        free(d);
        shift[0] = b[0], shift[1] = b[1];
        *s = skip_wsp(end + 1);
        return 0;
    }
    /* inset() (one to four insets, as margin writes them), xywh() (x, y,
     * width, height) and rect() (its edges from the top and the left, auto
     * the box's edge): four values, each a percentage of the box's height
     * (the first and third of inset() and rect(), the second and fourth of
     * xywh()) or width; then round and the radii */
    int ne = 0, pct[4] = {0, 0, 0, 0}, autos[4] = {0, 0, 0, 0};
    while (ne < 4 && **s != ')' && strncasecmp(*s, "round", 5)) {
        if (kind == 6 && bs_word(s, "auto"))
            autos[ne] = 1;
        else if (bs_lp(r, s, &e[ne], &pct[ne]))
            return -1;
        ne++;
    }
    if (!ne || (kind != 0 && ne < 4))
        return -1;
    if (bs_word(s, "round") && bs_radii(r, s, b, rad))
        return -1;
    if (**s != ')')
        return -1;
    /* value k of the four, of the box's height or width */
    static const int from[4][4] = {{0, 0, 0, 0}, {0, 1, 0, 1}, {0, 1, 2, 1}, {0, 1, 2, 3}};
    double t[4];
    for (int k = 0; k < 4; k++) {
        const int j = kind == 0 ? from[ne - 1][k] : k, vert = kind == 5 ? k & 1 : !(k & 1);
        t[k] = autos[j] ? (k == 1 ? b[2] : k == 2 ? b[3] : 0)
               : pct[j] ? e[j] / 100 * b[2 + vert]
                        : e[j];
    }
    double x0, y0, x1, y1;
    if (kind == 0) {
        /* insets adding up to more than the box: both reduced in
         * proportion to fit it (CSS Shapes 1) */
        for (int k = 0; k < 2; k++) {
            const double sum = t[k] + t[k + 2], size = b[3 - k];
            if (sum > size && sum > 0)
                t[k] *= size / sum, t[k + 2] *= size / sum;
        }
        x0 = b[0] + t[3], y0 = b[1] + t[0], x1 = b[0] + b[2] - t[1], y1 = b[1] + b[3] - t[2];
    } else if (kind == 5) {
        if (t[2] < 0 || t[3] < 0)
            return -1;
        x0 = b[0] + t[0], y0 = b[1] + t[1], x1 = x0 + t[2], y1 = y0 + t[3];
    } else { /* an edge before its opposite one is put on it */
        x0 = b[0] + t[3], y0 = b[1] + t[0];
        x1 = b[0] + fmax(t[1], t[3]), y1 = b[1] + fmax(t[2], t[0]);
    }
    *st = bs_rect(r, p, x0, y0, x1, y1, rad);
    return 0;
}

/* A shape's stroke bounding box (SVG 2, "Bounding boxes"): the path p's
 * fill geometry through m grown into e, and its undashed stroke outline's
 * when it is stroked (style sty; stroke_box). */
static int clip_stroke_box(reader *r, const aa_path *p, const style *sty, const mat *m,
                           double e[4])
{
    path_box(p, m, e);
    return stroke_box(r, p, sty, m, e);
}

/* The stroke bounding box of node (its style sty, m its user space to the
 * box's) grown into e (SVG 2, "Bounding boxes"): of a shape, its fill box
 * grown by its stroke outline's exact bounds when it is stroked
 * (clip_stroke_box); of a <g>, the union of its children's, each through
 * its transform (elements with display="none", and those never drawn
 * where they stand, adding nothing); of a <use>, its target's through
 * translate(x, y) and the target's transform, the target's style
 * inherited from the use (a missing target or a reference cycle adding
 * nothing, as it draws nothing).  A nested <svg>, a <symbol>, a <switch>
 * or any other element is refused.  At most AA_SVG_MAX_ELEMENTS elements
 * are visited, uses' instances counted (r->belements; r->bchain the uses
 * followed, as geometry_walk's). */
static int stroke_walk(reader *r, const xmlNode *node, const style *sty, const mat *m,
                       double e[4], int depth)
{
    static const char *const shapes[] = {"path", "rect",    "circle",  "ellipse",
                                         "line", "polygon", "polyline"};
    static const char *const silent[] = {"title",  "desc",           "metadata", "defs",
                                         "style",  "clipPath",       "linearGradient",
                                         "filter", "radialGradient", "mask",     "marker",
                                         "pattern"};
    r->node = node;
    if (depth > AA_SVG_MAX_DEPTH)
        return fail_at(r, "elements nested deeper than %d", AA_SVG_MAX_DEPTH);
    if (++r->belements > AA_SVG_MAX_ELEMENTS)
        return fail_at(r, "a bounding box of more than %d elements (use instances counted)",
                       AA_SVG_MAX_ELEMENTS);
    int shape = 0, st = AA_OK;
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
        shape |= named(node, shapes[k]);
    if (shape) {
        aa_path p;
        aa_path_init(&p);
        if (!(st = shape_path(r, node, &p)) && p.n)
            st = clip_stroke_box(r, &p, sty, m, e);
        aa_path_free(&p);
        return st;
    }
    if (named(node, "use")) {
        const xmlNode *t;
        double x, y;
        if ((st = use_target(r, node, &t)) || !t || !is_svg(t) || bbox_cycle(r, node, t))
            return st;
        if ((st = attr_length(r, node, "x", 0, &x)) || (st = attr_length(r, node, "y", 0, &y)))
            return st;
        if (!conditions_hold(t))
            return AA_OK;
        int drawn = named(t, "g");
        for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
            drawn |= named(t, shapes[k]);
        if (!drawn) {
            r->node = node;
            return fail_at(r, "clip-path: the stroke-box (border-box, margin-box, or no box "
                              "given) of a use of a <%s> is not supported: give fill-box or "
                              "view-box",
                           (const char *)t->name);
        }
        const mat at = {1, 0, 0, 1, x, y};
        mat mt = mat_mul(*m, at);
        style ts = *sty;
        int skip;
        double opacity;
        r->node = t;
        if ((st = element_props(r, t, &ts, &mt, &skip, &opacity)) || skip)
            return st;
        r->bchain[r->nb++] = node;
        st = stroke_walk(r, t, &ts, &mt, e, depth + 1);
        r->nb--;
        return st;
    }
    if (!named(node, "g"))
        return fail_at(r, "clip-path: the stroke-box (border-box, margin-box, or no box given) "
                          "of a <%s> is not supported: give fill-box or view-box",
                       (const char *)node->name);
    for (const xmlNode *c = node->children; c && !st; c = c->next) {
        if (!is_svg(c) || !conditions_hold(c))
            continue;
        int quiet = 0;
        for (size_t k = 0; k < sizeof silent / sizeof silent[0]; k++)
            quiet |= named(c, silent[k]);
        if (quiet)
            continue;
        style cs = *sty;
        mat mc = *m;
        int skip;
        double opacity;
        r->node = c;
        if (!(st = element_props(r, c, &cs, &mc, &skip, &opacity)) && !skip)
            st = stroke_walk(r, c, &cs, &mc, e, depth + 1);
    }
    return st;
}

/* The reference box `kind` (0 fill-box, 1 stroke-box, 2 view-box) of the
 * element ref in its user space (where its clip-path lies), x y w h into
 * b: of the root, its viewport in CSS px; of a shape, its exact bounds,
 * and its stroke bounding box when its style is known (r->csty: where it
 * is drawn); of a <g> or a <use>, its stroke bounding box (stroke_walk,
 * its style known likewise) or its object bounding box as
 * clipPathUnits="objectBoundingBox" takes it; a use's less its
 * translate(x, y), which its user space holds; a box of nothing is the
 * point (0, 0). */
static int bs_box(reader *r, const xmlNode *ref, int kind, double b[4])
{
    static const char *const shapes[] = {"path", "rect",    "circle",  "ellipse",
                                         "line", "polygon", "polyline"};
    b[0] = b[1] = b[2] = b[3] = 0;
    if (ref == r->root) {
        b[2] = r->rootw, b[3] = r->rooth;
        return AA_OK;
    }
    if (ref == r->clip_viewport)
        return fail_at(r, "clip-path: basic shapes and geometry boxes on a nested <svg> or a "
                          "<symbol> are not supported");
    if (kind == 2) {
        b[2] = r->vpw, b[3] = r->vph;
        return AA_OK;
    }
    int shape = 0, st = AA_OK;
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
        shape |= named(ref, shapes[k]);
    double e[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    const int group = named(ref, "g") || named(ref, "use");
    if (kind == 1 && !((shape || group) && r->csty_node == ref))
        return fail_at(r, "clip-path: the stroke-box (border-box, margin-box, or no box given) "
                          "of a <%s>%s is not supported: give fill-box or view-box",
                       (const char *)ref->name, shape ? " in a <clipPath>" : "");
    if (kind == 1 && group) {
        /* in the space of its clip-path: a use's has its translate(x, y),
         * which the walk applies */
        double x = 0, y = 0;
        if (named(ref, "use") &&
            ((st = attr_length(r, ref, "x", 0, &x)) || (st = attr_length(r, ref, "y", 0, &y))))
            return st;
        const mat back = {1, 0, 0, 1, -x, -y};
        const double em = r->font_size; /* the element's, which its content changes */
        if (!r->blevel++)
            r->belements = 0, r->nb = 0, r->bvia = NULL;
        st = stroke_walk(r, ref, r->csty, &back, e, 1);
        r->blevel--;
        r->font_size = em;
    } else if (shape) {
        aa_path p;
        aa_path_init(&p);
        if (!(st = shape_path(r, ref, &p)) && p.n) {
            if (kind == 1)
                st = clip_stroke_box(r, &p, r->csty, &identity, e);
            else
                path_box(&p, &identity, e);
        }
        aa_path_free(&p);
    } else {
        double x = 0, y = 0;
        if (named(ref, "use") &&
            ((st = attr_length(r, ref, "x", 0, &x)) || (st = attr_length(r, ref, "y", 0, &y))))
            return st;
        const mat back = {1, 0, 0, 1, -x, -y};
        st = geometry_box(r, ref, &back, e, 0);
    }
    r->node = ref;
    if (!st && e[2] >= e[0] && e[3] >= e[1])
        b[0] = e[0], b[1] = e[1], b[2] = e[2] - e[0], b[3] = e[3] - e[1];
    return st;
}

/* `value` as CSS Masking 1's <basic-shape> || <geometry-box>, each at most
 * once, in either order: the shape's function (*fn, its name *fnlen
 * characters long, its arguments at *args; NULL for none) and the box
 * (*kind: 0 fill-box, 1 stroke-box, 2 view-box, -1 none given); 1 if
 * malformed. */
static int basic_parse(const char *value, const char **fn, size_t *fnlen, const char **args,
                       int *kind)
{
    static const char *const boxes[] = {"fill-box",    "content-box", "padding-box",
                                        "stroke-box",  "border-box",  "margin-box",
                                        "view-box"};
    static const int kinds[] = {0, 0, 0, 1, 1, 1, 2};
    const char *s = skip_wsp(value);
    *fn = *args = NULL, *fnlen = 0, *kind = -1;
    for (int item = 0; item < 2 && *s; item++) {
        size_t n = 0;
        while (isalnum((unsigned char)s[n]) || s[n] == '-')
            n++;
        if (s[n] == '(' && !*fn) {
            *fn = s, *fnlen = n, *args = skip_wsp(s + n + 1);
            int depth = 1;
            for (s += n + 1; *s && depth; s++) /* to its closing parenthesis */
                depth += *s == '(' ? 1 : *s == ')' ? -1 : 0;
            if (depth)
                return 1;
        } else {
            size_t k = 0;
            while (k < 7 && !(strlen(boxes[k]) == n && !strncasecmp(s, boxes[k], n)))
                k++;
            if (k == 7 || *kind >= 0)
                return 1;
            *kind = kinds[k];
            s += n;
        }
        s = skip_wsp(s);
    }
    return *s || (!*fn && *kind < 0);
}

static int clip_path_invalid(reader *r, const char *value)
{
    return fail_at(r, "clip-path=\"%s\" is not url(#id), none, or a basic shape (inset(), "
                      "circle(), ellipse(), polygon(), path(), xywh(), rect()) and a geometry "
                      "box",
                   aa_echo(value));
}

/* Whether `value` is a valid clip-path (prop_check): none, a URL (read
 * where it is resolved) or a basic shape and a geometry box by their
 * grammar, the shape made once in a box of 100 x 100 to check its
 * arguments; AA_EINVAL naming it if not. */
static int clip_path_check(reader *r, const char *value)
{
    const char *fn, *args;
    size_t fnlen;
    int kind, st = AA_OK;
    const char *v = skip_wsp(value);
    if (!strcasecmp(v, "none") || !strncasecmp(v, "url(", 4))
        return AA_OK;
    if (basic_parse(v, &fn, &fnlen, &args, &kind))
        return clip_path_invalid(r, value);
    if (!fn)
        return AA_OK;
    const double b[4] = {0, 0, 100, 100};
    aa_path p;
    aa_path_init(&p);
    aa_fill_rule rule;
    double shift[2] = {0, 0};
    if (bs_shape(r, fn, fnlen, &args, b, &p, &rule, shift, &st))
        st = clip_path_invalid(r, value);
    aa_path_free(&p);
    return st;
}

/* The clip of a clip-path of basic shape and geometry box `value` on ref
 * (whose user space is m) within `outer`: one member, the shape in the
 * box (or the box), its number into *out. */
static int basic_clip(reader *r, const char *value, const xmlNode *ref, const mat *m, int outer,
                      int *out)
{
    const char *fn, *args;
    size_t fnlen;
    int kind;
    if (basic_parse(value, &fn, &fnlen, &args, &kind))
        goto bad;
    int st = AA_OK;
    if (!r->sink->clip_begin || !r->sink->clip_end || !r->sink->clip)
        return fail_at(r, "clip paths are not taken here");
    double b[4];
    if ((st = bs_box(r, ref, kind < 0 ? 1 : kind, b)))
        return st;
    aa_path p;
    aa_path_init(&p);
    aa_fill_rule rule = AA_FILL_NONZERO;
    double shift[2] = {0, 0};
    double none[4][2] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
    r->node = ref;
    if (!fn)
        st = bs_rect(r, &p, b[0], b[1], b[0] + b[2], b[1] + b[3], none);
    else if (bs_shape(r, fn, fnlen, &args, b, &p, &rule, shift, &st)) {
        aa_path_free(&p);
        goto bad;
    }
    mat mp = *m;
    if (shift[0] != 0 || shift[1] != 0) {
        const mat at = {1, 0, 0, 1, shift[0], shift[1]};
        mp = mat_mul(*m, at);
    }
    if (!st)
        st = viewport_clip(r, outer, &outer);
    if (!st && (st = r->sink->clip_begin(r->ctx, outer)))
        st = at_element(r, st);
    if (!st) {
        const int was = r->clip;
        const aa_rgb black = {{0, 0, 0}};
        r->clip = -1;
        st = give_path(r, &p, &mp, black, rule, 1.0, NULL);
        r->clip = was;
        if (!st)
            st = r->sink->clip_end(r->ctx);
    }
    aa_path_free(&p);
    if (!st)
        *out = r->nclips++;
    return st;
bad:
    return clip_path_invalid(r, value);
}

static int clip_resolve(reader *r, const char *value, const xmlNode *ref, const mat *m,
                        int outer, int *out)
{
    char buf[1024];
    const char *id;
    int st;
    *out = outer;
    const char *s = skip_wsp(value);
    if (strcasecmp(s, "none") && strncasecmp(s, "url(", 4))
        return basic_clip(r, value, ref, m, outer, out);
    if ((st = clip_ref(r, value, buf, sizeof buf, &id)) || !id)
        return st;
    const xmlNode *cp = find_id(r->ids, id);
    if (!cp || !is_svg(cp) || !named(cp, "clipPath"))
        return AA_OK; /* as if not given (CSS Masking 1) */
    for (int k = 0; k < r->nstack; k++)
        if (r->clip_stack[k] == cp)
            return fail_at(r, "clip-path=\"%s\": the references to clip paths form a cycle "
                              "(back to the <clipPath> of line %ld)",
                           aa_echo(value), xmlGetLineNo(cp));
    if (r->nstack == AA_SVG_MAX_CLIP_NESTING)
        return fail_at(r, "clip paths referenced inside clip paths deeper than %d",
                       AA_SVG_MAX_CLIP_NESTING);
    if (!r->sink->clip_begin || !r->sink->clip_end || !r->sink->clip)
        return fail_at(r, "clip paths are not taken here");
    /* the clip it lies within, a viewport's made now if not yet (before
     * this one begins) */
    if ((st = viewport_clip(r, outer, &outer)))
        return st;
    r->clip_stack[r->nstack++] = cp;
    st = clip_make(r, cp, ref, m, outer, out);
    r->nstack--;
    return st;
}

/* ---- gradients (paint servers) ----
 *
 * A fill or stroke of url(#id) naming a linearGradient or radialGradient
 * (SVG 2, "Paint servers"; patterns/README.md, "Gradients"): the
 * gradient's attributes are its own or, where it has none, those of the
 * gradient its href (or xlink:href) names, and so on along the chain
 * (a cycle is refused); its stops are those of the first gradient of the
 * chain that has any.  gradientUnits objectBoundingBox (the default)
 * measures x1 .. fr in the bounding box of the element's geometry (its
 * fill's, for a stroke too), as numbers or percentages of it;
 * userSpaceOnUse in the element's user space, as lengths.
 * gradientTransform maps the gradient's coordinates into those units.
 * Stops: offset a number or a percentage clamped to [0, 1] and raised to
 * the largest offset before it; stop-color (default black; currentColor
 * the stop's color) and stop-opacity (default 1) as attributes, style or
 * sheet rules, their product with the colour's alpha the stop's opacity.
 * No stops paint nothing; one stop, or a linear gradient whose two points
 * coincide, or a radial one of radius 0, paint the (last) stop's colour;
 * an objectBoundingBox gradient on geometry of zero width or height paints
 * nothing (SVG 1.1, 7.11 "Object bounding box units").  A radial gradient
 * whose focal circle is not strictly inside its end circle (the cone case)
 * is read as any other: the scene draws the cone SVG 2 defines and leaves
 * the rest unpainted (aa_gradient_is_cone); one whose focal circle is its
 * end circle, which SVG 2 paints with nothing, is refused, as the scene
 * refuses it (aa_scene_set_gradient).  Each gradient goes to the sink with
 * its element and line, which the scene keeps for the messages that refuse
 * it later (aa_scene_set_gradient_source). */

#define GRAD_MAX_CHAIN 32     /* gradients along an href chain */
#define GRAD_MAX_STOPS 4096   /* stops of one gradient */

/* A resolved paint: none, a colour of alpha, or a gradient (its stops
 * malloc'd, g.m its map to pixels). */
typedef struct paint_res {
    int none, grad;
    aa_rgb colour;
    double alpha;
    aa_gradient g;
    aa_gradient_stop *stops;
    int interpolation; /* aa_interpolation: the gradient element's color-interpolation */
    char source[192];  /* the gradient element and its line, for messages */
} paint_res;

/* The chain of gradients from g along href: at most GRAD_MAX_CHAIN, a
 * cycle refused; a reference to a missing element ends it. */
static int grad_chain(reader *r, const xmlNode *g, const xmlNode **chain, int *n)
{
    *n = 0;
    while (g) {
        for (int k = 0; k < *n; k++)
            if (chain[k] == g)
                return fail_at(r, "the gradients' href references form a cycle (through "
                                  "line %ld)",
                               xmlGetLineNo(g));
        if (*n == GRAD_MAX_CHAIN)
            return fail_at(r, "more than %d gradients along an href chain", GRAD_MAX_CHAIN);
        chain[(*n)++] = g;
        xmlChar *href = xmlGetNoNsProp(g, (const xmlChar *)"href");
        if (!href)
            href = xmlGetNsProp(g, (const xmlChar *)"href",
                                (const xmlChar *)"http://www.w3.org/1999/xlink");
        if (!href)
            break;
        const char *h = skip_wsp((const char *)href);
        const xmlNode *next = NULL;
        int st = AA_OK;
        if (*h && *h != '#')
            st = fail_at(r, "gradient at line %ld: href=\"%s\": a reference to another "
                            "document is not supported",
                         xmlGetLineNo(g), aa_echo(h));
        else if (*h) {
            next = find_href(r->ids, h);
            if (next && !(is_svg(next) && (named(next, "linearGradient") ||
                                           named(next, "radialGradient"))))
                next = NULL; /* not a gradient: nothing to inherit */
        }
        xmlFree(href);
        if (st)
            return st;
        g = next;
    }
    return AA_OK;
}

/* The first value of attribute key along the chain (malloc'd by libxml2;
 * a kind's own attributes are refused on the other kind, check_props, so
 * a linear gradient inherits from a radial one only what both have). */
static xmlChar *grad_attr(const xmlNode *const *chain, int n, const char *key)
{
    for (int k = 0; k < n; k++) {
        xmlChar *v = xmlGetNoNsProp(chain[k], (const xmlChar *)key);
        if (v)
            return v;
    }
    return NULL;
}

/* A coordinate of the gradient: in objectBoundingBox units a number or a
 * percentage (a fraction of the box), in userSpaceOnUse a length (% of
 * the viewport). */
static int grad_coord(reader *r, const xmlNode *const *chain, int n, const char *key,
                      const char *def, int bbox, double *v, int *given)
{
    xmlChar *a = grad_attr(chain, n, key);
    const char *t = a ? (const char *)a : def;
    if (given)
        *given = a != NULL;
    int st = AA_OK;
    if (bbox) {
        const char *q = skip_wsp(t);
        if (scan_number(&q, v))
            st = fail_at(r, "gradient %s=\"%s\" is not a number or a percentage", key,
                         aa_echo(t));
        else {
            if (*q == '%')
                *v /= 100, q++;
            if (*skip_wsp(q))
                st = fail_at(r, "gradient %s=\"%s\": in objectBoundingBox units only a number "
                                "or a percentage",
                             key, aa_echo(t));
        }
    } else
        st = parse_length(r, key, t, v);
    xmlFree(a);
    return st;
}

/* The colour of a stop (stop-color, stop-opacity; currentColor the
 * stop's own color or its ancestors'). */
static int stop_colour(reader *r, const xmlNode *stop, aa_rgb *c, double *opacity)
{
    char v[256];
    int st = AA_OK;
    css_colour col = {{0, 0, 0}, 1, 0};
    if (prop(r, stop, "stop-color", v, sizeof v, &st) && strcasecmp(v, "inherit") &&
        (st = parse_colour(r, "stop-color", v, &col)))
        return st;
    if (st)
        return st;
    if (col.current) {
        col = (css_colour){{0, 0, 0}, 1, 0};
        for (const xmlNode *a = stop; a && a->type == XML_ELEMENT_NODE; a = a->parent) {
            css_colour cc;
            if (prop(r, a, "color", v, sizeof v, &st) && strcasecmp(v, "inherit") &&
                strcasecmp(v, "currentColor")) {
                if ((st = parse_colour(r, "color", v, &cc)))
                    return st;
                col = cc;
                break;
            }
            if (st)
                return st;
        }
    }
    double o = 1;
    if (prop(r, stop, "stop-opacity", v, sizeof v, &st) && strcasecmp(v, "inherit") &&
        (st = parse_opacity(r, "stop-opacity", v, &o)))
        return st;
    if (st)
        return st;
    for (int k = 0; k < 3; k++)
        c->c[k] = srgb_decode(col.v[k]);
    *opacity = o * col.alpha;
    return AA_OK;
}

/* The stops of the first gradient along the chain that has any. */
static int grad_stops(reader *r, const xmlNode *const *chain, int n, paint_res *out)
{
    int count = 0, st = AA_OK;
    const xmlNode *owner = NULL;
    for (int k = 0; k < n && !owner; k++)
        for (const xmlNode *c = chain[k]->children; c; c = c->next)
            if (c->type == XML_ELEMENT_NODE && is_svg(c) && named(c, "stop")) {
                owner = chain[k];
                break;
            }
    if (!owner)
        return AA_OK;
    for (const xmlNode *c = owner->children; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && is_svg(c) && named(c, "stop"))
            count++;
    if (count > GRAD_MAX_STOPS)
        return fail_at(r, "a gradient of more than %d stops", GRAD_MAX_STOPS);
    out->stops = malloc((size_t)count * sizeof *out->stops);
    if (!out->stops)
        return aa_fail(AA_ENOMEM, "out of memory reading %s", r->name);
    const xmlNode *keep = r->node;
    double last = 0;
    int m = 0;
    for (const xmlNode *c = owner->children; c && !st; c = c->next) {
        if (c->type != XML_ELEMENT_NODE || !is_svg(c))
            continue;
        r->node = c;
        if (!named(c, "stop")) {
            static const char *const quiet[] = {"title", "desc", "metadata"};
            int ok = 0;
            for (int q = 0; q < 3; q++)
                ok |= named(c, quiet[q]);
            if (!ok)
                st = fail_at(r, "not supported in a gradient (only <stop>)");
            continue;
        }
        if ((st = check_props(r, c)))
            break;
        aa_gradient_stop *s = &out->stops[m];
        double off = 0;
        xmlChar *o = xmlGetNoNsProp(c, (const xmlChar *)"offset");
        if (o) {
            const char *q = skip_wsp((const char *)o);
            if (scan_number(&q, &off))
                off = NAN;
            else if (*q == '%')
                off /= 100, q++;
            if (off != off || *skip_wsp(q)) {
                if (!invalid_attr(r, "offset", (const char *)o, "a number or a percentage"))
                    st = fail_at(r, "offset=\"%s\" is not supported", aa_echo((const char *)o));
                off = 0;
            }
            xmlFree(o);
        }
        if (st)
            break;
        /* clamped to [0, 1], and at least the largest offset before */
        off = off < 0 ? 0 : off > 1 ? 1 : off;
        if (off < last)
            off = last;
        last = off;
        s->offset = off;
        st = stop_colour(r, c, &s->colour, &s->opacity);
        m++;
    }
    r->node = keep;
    out->g.nstops = m;
    return st;
}

/* A paint server's paint for the element whose geometry p is in user
 * space m (to pixels): none, a colour, or a gradient with its map. */
static int grad_resolve(reader *r, const xmlNode *server, const aa_path *p, const mat *m,
                        paint_res *out)
{
    memset(out, 0, sizeof *out);
    const xmlNode *chain[GRAD_MAX_CHAIN];
    int n, st, given;
    const xmlNode *keep = r->node;
    r->node = server;
    snprintf(out->source, sizeof out->source, "%s: line %ld: <%s>", r->name,
             xmlGetLineNo(server), (const char *)server->name);
    if ((st = grad_chain(r, server, chain, &n)))
        return st;
    for (int k = 0; k < n; k++) {
        r->node = chain[k];
        if ((st = check_props(r, chain[k])))
            return st;
    }
    /* color-interpolation of the gradient element: a property, inherited
     * (SVG 1.1, "color-interpolation": "inherited: yes"), so the gradient
     * element's own value, else its parent's and so on up the element
     * tree, not the shape's it paints (a paint server's properties are
     * its own and its ancestors') nor the href chain's (href passes on
     * attributes the element lacks, and stops, not properties: SVG 1.1,
     * 13.2.2 and 13.2.3, xlink:href).  linearRGB interpolates the stops
     * in linear light (SVG 1.1, 13.2.1: "the color interpolation ... in
     * the linearized RGB color space"; aa_scene_set_gradient_interpolation),
     * as Chromium draws it; resvg ignores the property (as auto).  auto
     * and sRGB keep sRGB-encoded values (auto: "the user agent can
     * choose", and every browser chooses sRGB). */
    out->interpolation = AA_INTERPOLATE_SRGB;
    for (const xmlNode *a = server; a && a->type == XML_ELEMENT_NODE; a = a->parent) {
        char v[64];
        r->node = a;
        if (!prop(r, a, "color-interpolation", v, sizeof v, &st)) {
            if (st)
                return st;
            continue;
        }
        if (!strcasecmp(v, "inherit"))
            continue;
        if (!strcasecmp(v, "linearRGB"))
            out->interpolation = AA_INTERPOLATE_LINEAR_RGB;
        break; /* the nearest value given decides */
    }
    r->node = server;
    const int radial = named(server, "radialGradient");
    int bbox = 1, spread = AA_SPREAD_PAD;
    xmlChar *a = grad_attr(chain, n, "gradientUnits");
    if (a && !strcmp((const char *)a, "userSpaceOnUse"))
        bbox = 0;
    else if (a && strcmp((const char *)a, "objectBoundingBox"))
        st = fail_at(r, "gradientUnits=\"%s\" (userSpaceOnUse or objectBoundingBox)",
                     aa_echo((const char *)a));
    xmlFree(a);
    a = grad_attr(chain, n, "spreadMethod");
    if (!st && a) {
        if (!strcmp((const char *)a, "reflect"))
            spread = AA_SPREAD_REFLECT;
        else if (!strcmp((const char *)a, "repeat"))
            spread = AA_SPREAD_REPEAT;
        else if (strcmp((const char *)a, "pad"))
            st = fail_at(r, "spreadMethod=\"%s\" (pad, reflect or repeat)",
                         aa_echo((const char *)a));
    }
    xmlFree(a);
    mat G = identity;
    a = grad_attr(chain, n, "gradientTransform");
    if (!st && a)
        st = parse_transform(r, (const char *)a, &G);
    xmlFree(a);
    double v[6];
    if (!st && !radial) {
        static const char *const keys[4] = {"x1", "y1", "x2", "y2"};
        static const char *const defs[4] = {"0%", "0%", "100%", "0%"};
        for (int k = 0; k < 4 && !st; k++)
            st = grad_coord(r, chain, n, keys[k], defs[k], bbox, &v[k], NULL);
        v[4] = v[5] = 0;
    } else if (!st) {
        static const char *const keys[3] = {"cx", "cy", "r"};
        for (int k = 0; k < 3 && !st; k++)
            st = grad_coord(r, chain, n, keys[k], "50%", bbox, &v[k], NULL);
        if (!st && (st = grad_coord(r, chain, n, "fx", "0", bbox, &v[3], &given)) == AA_OK &&
            !given)
            v[3] = v[0]; /* fx defaults to cx */
        if (!st && (st = grad_coord(r, chain, n, "fy", "0", bbox, &v[4], &given)) == AA_OK &&
            !given)
            v[4] = v[1];
        if (!st)
            st = grad_coord(r, chain, n, "fr", "0%", bbox, &v[5], NULL);
        if (!st && (v[2] < 0 || v[5] < 0))
            st = fail_at(r, "radialGradient: a negative %s (%g) is an error",
                         v[2] < 0 ? "r" : "fr", v[2] < 0 ? v[2] : v[5]);
    }
    if (!st)
        st = grad_stops(r, chain, n, out);
    r->node = keep;
    if (st) {
        free(out->stops);
        out->stops = NULL;
        return st;
    }
    const int ns = out->g.nstops;
    if (!ns) { /* no stops: as none */
        out->none = 1;
        return AA_OK;
    }
    /* one stop, or a degenerate vector or radius: the last stop's colour */
    const int solid = ns == 1 || (!radial && v[0] == v[2] && v[1] == v[3]) ||
                      (radial && v[2] == 0);
    if (solid) {
        out->colour = out->stops[ns - 1].colour;
        out->alpha = out->stops[ns - 1].opacity;
        free(out->stops);
        out->stops = NULL;
        return AA_OK;
    }
    mat B = identity;
    if (bbox) {
        double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        path_box(p, &identity, box);
        if (!(box[2] > box[0] && box[3] > box[1])) { /* no width or no height: none */
            out->none = 1;
            free(out->stops);
            out->stops = NULL;
            return AA_OK;
        }
        B = (mat){box[2] - box[0], 0, 0, box[3] - box[1], box[0], box[1]};
    }
    const mat M = mat_mul(*m, mat_mul(B, G));
    out->grad = 1;
    out->g.kind = radial ? AA_GRADIENT_RADIAL : AA_GRADIENT_LINEAR;
    out->g.spread = spread;
    memcpy(out->g.p, v, sizeof v);
    const double mm[6] = {M.a, M.b, M.c, M.d, M.e, M.f};
    memcpy(out->g.m, mm, sizeof mm);
    out->g.stops = out->stops;
    if (radial && v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) {
        r->node = server;
        st = fail_at(r, "the focal circle (fx %g, fy %g, fr %g) is the end circle: SVG 2 then "
                        "paints nothing, which is refused",
                     v[3], v[4], v[5]);
        r->node = keep;
        free(out->stops);
        out->stops = NULL;
        out->grad = 0;
    }
    return st;
}

static int element(reader *r, const xmlNode *node, style sty, mat m, int depth);
static int structure(reader *r, const xmlNode *node, const xmlNode *via, style sty, mat m,
                     int depth);

static int children(reader *r, const xmlNode *node, style sty, mat m, int depth)
{
    for (const xmlNode *c = node->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE)
            continue;
        int st = element(r, c, sty, m, depth + 1);
        if (st)
            return st;
    }
    return AA_OK;
}

static int element(reader *r, const xmlNode *node, style sty, mat m, int depth)
{
    r->node = node;
    const xmlNode *via = r->use; /* the <use> this element is the target of */
    r->use = NULL;
    if (depth > AA_SVG_MAX_DEPTH)
        return fail_at(r, "elements nested deeper than %d", AA_SVG_MAX_DEPTH);
    r->chain[depth] = node;
    r->depth = depth;
    if (++r->elements > AA_SVG_MAX_ELEMENTS)
        return fail_at(r, "more than %d elements drawn (<use> instances counted)",
                       AA_SVG_MAX_ELEMENTS);
    if (!is_svg(node))
        return AA_OK; /* another namespace: not drawn */
    /* a clipPath is drawn only where it is referenced (clip_of); filters,
     * masks, markers and patterns are never drawn where they stand either
     * (SVG 2 and Filter Effects 1: "never rendered directly"), and a
     * reference to one is refused where it is made (the filter, mask and
     * marker properties, a url() paint naming a pattern), so one defined
     * and not used changes nothing; SVG 1.2 drafts' flowed text
     * (flowRoot, which Inkscape writes) is no SVG element, and Chromium
     * and resvg draw nothing of it or its content */
    static const char *const silent[] = {"title",   "desc",           "metadata",
                                         "defs",    "clipPath",       "linearGradient",
                                         "radialGradient", "filter",  "mask",
                                         "marker",  "pattern",        "flowRoot"};
    for (size_t k = 0; k < sizeof silent / sizeof silent[0]; k++)
        if (named(node, silent[k]))
            return AA_OK;
    if (!conditions_hold(node))
        return AA_OK; /* not drawn, with its content */
    int skip, st;
    if (named(node, "svg") || named(node, "use") || named(node, "symbol") ||
        named(node, "style"))
        return structure(r, node, via, sty, m, depth);
    static const char *const shapes[] = {"path",    "rect",    "circle",  "ellipse",
                                         "line",    "polygon", "polyline"};
    int shape = 0;
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++)
        shape |= named(node, shapes[k]);
    const int group = named(node, "g") || named(node, "switch");
    if (!shape && !group) {
        static const struct {
            const char *name, *why;
        } known[] = {{"text", "text is not supported (the pattern text draws glyphs)"},
                     {"image", "images are not supported"}};
        for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
            if (named(node, known[k].name))
                return fail_at(r, "%s", known[k].why);
        return fail_at(r, "this element is not supported");
    }
    double opacity;
    if ((st = element_props(r, node, &sty, &m, &skip, &opacity)) || skip || opacity == 0)
        return st;
    /* its clip-path, in its user space (m, its own transform applied)
     * within the clip of its ancestors; the shapes it gives are drawn
     * inside that clip */
    const int outer = r->clip;
    int clip;
    if (group) {
        r->csty_node = node, r->csty = &sty;
        st = clip_of(r, node, &m, outer, &clip);
        r->csty_node = NULL, r->csty = NULL;
        if (st)
            return st;
        r->node = node;
        /* a group of opacity below 1 is composited as a whole (SVG 2,
         * "Group opacity": its content drawn on its own, then over what is
         * below at that opacity) */
        if (opacity < 1 && (st = group_begin(r, opacity)))
            return st;
        r->clip = clip;
        if (named(node, "g"))
            st = children(r, node, sty, m, depth);
        else { /* a switch: the child it draws */
            const xmlNode *c;
            if (!(st = switch_choice(r, node, &c)) && c)
                st = element(r, c, sty, m, depth + 1);
        }
        r->clip = outer;
        if (!st && opacity < 1) {
            r->node = node;
            st = r->sink->group_end(r->ctx);
        }
        return st;
    }
    double fa, sa;
    aa_rgb fc = paint_rgb(&sty, &sty.fill, &fa), sc = paint_rgb(&sty, &sty.stroke, &sa);
    if (sty.fill_server)
        fa = 1;
    if (sty.stroke_server)
        sa = 1;
    fa *= sty.fill_opacity, sa *= sty.stroke_opacity;
    /* a line has no area: only its stroke draws; a hidden element or a
     * paint of alpha 0 draws nothing */
    int fill = !sty.fill_none && !named(node, "line") && sty.visible && fa > 0;
    int stroke = !sty.stroke_none && sty.stroke_width > 0 && sty.visible && sa > 0;
    if (!fill && !stroke)
        return AA_OK;
    r->csty_node = node, r->csty = &sty;
    st = clip_of(r, node, &m, outer, &clip);
    r->csty_node = NULL, r->csty = NULL;
    if (st)
        return st;
    r->node = node;
    aa_path p;
    aa_path_init(&p);
    st = shape_path(r, node, &p);
    if (!st && stroke)
        st = path_length_dashes(r, node, &p, &sty);
    /* paint servers: resolved against the geometry (its bounding box) */
    paint_res fp = {0}, sp = {0};
    if (!st && fill && sty.fill_server && !(st = grad_resolve(r, sty.fill_server, &p, &m, &fp))) {
        fill = !fp.none;
        if (!fp.grad)
            fc = fp.colour, fa *= fp.alpha;
        fill = fill && fa > 0;
    }
    if (!st && stroke && sty.stroke_server &&
        !(st = grad_resolve(r, sty.stroke_server, &p, &m, &sp))) {
        stroke = !sp.none;
        if (!sp.grad)
            sc = sp.colour, sa *= sp.alpha;
        stroke = stroke && sa > 0;
    }
    r->node = node;
    /* the element's opacity: its one painted shape's alpha, or both
     * composited as a group */
    const int grouped = fill && stroke && opacity < 1;
    if (!grouped)
        fa *= opacity, sa *= opacity;
    r->clip = clip;
    if (!st && grouped)
        st = group_begin(r, opacity);
    /* paint-order: the fill, then the stroke over it, unless the stroke is
     * first */
    for (int k = 0; k < 2 && !st; k++) {
        if (k == sty.stroke_first && fill) {
            r->grad_source = fp.source, r->grad_interpolation = fp.interpolation;
            st = give_path(r, &p, &m, fc, sty.rule, fa, fp.grad ? &fp.g : NULL);
        } else if (k != sty.stroke_first && stroke) {
            r->grad_source = sp.source, r->grad_interpolation = sp.interpolation;
            st = give_stroke(r, &p, &m, &sty, sc, sa, sp.grad ? &sp.g : NULL);
        }
    }
    r->grad_source = NULL, r->grad_interpolation = AA_INTERPOLATE_SRGB;
    if (!st && grouped)
        st = r->sink->group_end(r->ctx);
    r->clip = outer;
    aa_path_free(&p);
    free(fp.stops);
    free(sp.stops);
    return st;
}

/* ---- structure: <use>, <symbol>, nested <svg>, <style> ---- */

/* The elements with an id, sorted by id and then document order, so that
 * a reference finds the first in the document (getElementById). */
typedef struct svg_ids {
    struct svg_id {
        xmlChar *id;
        const xmlNode *node;
        size_t order;
    } *e;
    size_t n, cap;
} svg_ids;

static int id_cmp(const void *a, const void *b)
{
    const struct svg_id *x = a, *y = b;
    int c = strcmp((const char *)x->id, (const char *)y->id);
    return c ? c : x->order < y->order ? -1 : x->order > y->order;
}

static int collect_ids(svg_ids *ids, const xmlNode *node)
{
    for (; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE)
            continue;
        xmlChar *id = xmlGetNoNsProp(node, (const xmlChar *)"id");
        if (id) {
            if (ids->n == ids->cap) {
                size_t cap = ids->cap ? 2 * ids->cap : 64;
                struct svg_id *e = realloc(ids->e, cap * sizeof *e);
                if (!e) {
                    xmlFree(id);
                    return aa_fail(AA_ENOMEM, "out of memory indexing ids");
                }
                ids->e = e, ids->cap = cap;
            }
            ids->e[ids->n] = (struct svg_id){id, node, ids->n};
            ids->n++;
        }
        int st = collect_ids(ids, node->children);
        if (st)
            return st;
    }
    return AA_OK;
}

static void free_ids(svg_ids *ids)
{
    for (size_t k = 0; k < ids->n; k++)
        xmlFree(ids->e[k].id);
    free(ids->e);
}

static const xmlNode *find_id(const struct svg_ids *ids, const char *id)
{
    size_t lo = 0, hi = ids->n;
    while (lo < hi) { /* the first element not below id */
        size_t mid = lo + (hi - lo) / 2;
        if (strcmp((const char *)ids->e[mid].id, id) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < ids->n && !strcmp((const char *)ids->e[lo].id, id) ? ids->e[lo].node : NULL;
}

/* The element a same-document reference "#id" names (h at its '#';
 * trailing white space dropped), or NULL. */
static const xmlNode *find_href(const struct svg_ids *ids, const char *h)
{
    char id[1024];
    snprintf(id, sizeof id, "%s", h + 1);
    size_t n = strlen(id);
    while (n && is_wsp((unsigned char)id[n - 1]))
        id[--n] = '\0';
    return find_id(ids, id);
}

/* The style sheets of every <style> element of the SVG namespace, in
 * document order (a sheet applies to the whole document wherever it is):
 * type absent, empty or text/css (another type is not CSS, and browsers
 * skip it), media absent, empty, all or screen (a sheet for another
 * medium might apply: refused). */
static int read_sheets(reader *r, const xmlNode *node)
{
    for (; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE)
            continue;
        int st = AA_OK;
        if (is_svg(node) && named(node, "style")) {
            r->node = node;
            xmlChar *type = xmlGetNoNsProp(node, (const xmlChar *)"type");
            xmlChar *media = xmlGetNoNsProp(node, (const xmlChar *)"media");
            const char *t = type ? skip_wsp((const char *)type) : "";
            const char *md = media ? skip_wsp((const char *)media) : "";
            const int css = !*t || !strcasecmp(t, "text/css");
            if (css && *md && strcasecmp(md, "all") && strcasecmp(md, "screen"))
                st = fail_at(r, "media=\"%s\": a sheet for other media is not supported",
                             aa_echo(md));
            for (const xmlAttr *a = node->properties; a && !st; a = a->next)
                if (!a->ns && strcmp((const char *)a->name, "type") &&
                    strcmp((const char *)a->name, "media") &&
                    strcmp((const char *)a->name, "id") && strcmp((const char *)a->name, "title"))
                    st = fail_at(r, "the attribute %s is not supported",
                                 aa_echo((const char *)a->name));
            if (!st && css) {
                xmlChar *text = xmlNodeGetContent(node);
                /* libxml2 numbers a text node by its last line: the
                 * sheet is taken to start on the start tag's line */
                long line = xmlGetLineNo(node);
                if (!r->css)
                    st = aa_css_new(&r->css);
                if (!st)
                    st = aa_css_add(r->css, text ? (const char *)text : "", r->name, line);
                xmlFree(text);
            }
            xmlFree(type);
            xmlFree(media);
            if (st)
                return st;
            continue;
        }
        if ((st = read_sheets(r, node->children)))
            return st;
    }
    return AA_OK;
}

/* m^-1, or 1 when m is singular. */
static int mat_inverse(const mat *m, mat *out)
{
    const double det = m->a * m->d - m->b * m->c;
    if (!(det != 0) || !isfinite(1 / det))
        return 1;
    out->a = m->d / det, out->b = -m->b / det, out->c = -m->c / det, out->d = m->a / det;
    out->e = -(out->a * m->e + out->c * m->f);
    out->f = -(out->b * m->e + out->d * m->f);
    return 0;
}

/* The map of a viewBox (of node, if it has one) onto a viewport of vw x
 * vh at the origin by its preserveAspectRatio, as for the root
 * (root_map): *m, and the viewBox's size in vb (the viewport's without
 * one). */
static int viewbox_map(reader *r, const xmlNode *node, double vw, double vh, mat *m, double vb[2])
{
    *m = identity;
    vb[0] = vw, vb[1] = vh;
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)"viewBox");
    if (!t)
        return AA_OK;
    double b[4];
    const char *s = skip_wsp((const char *)t);
    int st = AA_OK;
    for (int k = 0; k < 4 && !st; k++) {
        if (k)
            s = skip_comma_wsp(s);
        if (scan_number(&s, &b[k]))
            st = fail_at(r, "viewBox=\"%s\" is not four numbers", aa_echo((const char *)t));
    }
    if (!st && *skip_wsp(s))
        st = fail_at(r, "viewBox=\"%s\" is not four numbers", aa_echo((const char *)t));
    if (!st && (b[2] <= 0 || b[3] <= 0))
        st = fail_at(r, "viewBox=\"%s\": its width and height must be positive",
                     aa_echo((const char *)t));
    xmlFree(t);
    if (st)
        return st;
    double sx = vw / b[2], sy = vh / b[3], ax = 0.5, ay = 0.5;
    int none = 0, slice = 0;
    t = xmlGetNoNsProp(node, (const xmlChar *)"preserveAspectRatio");
    if (t) {
        char align[16] = "", mos[16] = "meet";
        int n = sscanf((const char *)t, " %15s %15s", align, mos);
        if (n >= 1 && !strcmp(align, "defer")) /* only for images */
            n = sscanf((const char *)t, " defer %15s %15s", align, mos);
        static const char *const xs[3] = {"xMin", "xMid", "xMax"};
        static const char *const ys[3] = {"YMin", "YMid", "YMax"};
        int ok = n >= 1 && (!strcmp(mos, "meet") || !strcmp(mos, "slice"));
        if (ok && !strcmp(align, "none"))
            none = 1;
        else if (ok) {
            ok = 0;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    if (!strncmp(align, xs[i], 4) && !strcmp(align + 4, ys[j]))
                        ax = i / 2.0, ay = j / 2.0, ok = 1;
        }
        slice = !strcmp(mos, "slice");
        if (!ok)
            st = fail_at(r, "preserveAspectRatio=\"%s\" is malformed", aa_echo((const char *)t));
        xmlFree(t);
        if (st)
            return st;
    }
    if (!none) {
        double k = slice ? fmax(sx, sy) : fmin(sx, sy);
        sx = sy = k;
    }
    m->a = sx, m->d = sy;
    m->e = -b[0] * sx + (none ? 0 : ax * (vw - b[2] * sx));
    m->f = -b[1] * sy + (none ? 0 : ay * (vh - b[3] * sy));
    vb[0] = b[2], vb[1] = b[3];
    return AA_OK;
}

/* A length attribute `key` of `node`, or when `over` (a <use>) gives it
 * (and not auto), of `over`; auto or absent: 100% (of the viewport). */
static int viewport_side(reader *r, const xmlNode *node, const xmlNode *over, const char *key,
                         double *v)
{
    const xmlNode *from[2] = {over, node};
    for (int k = 0; k < 2; k++) {
        if (!from[k])
            continue;
        xmlChar *t = xmlGetNoNsProp(from[k], (const xmlChar *)key);
        if (!t)
            continue;
        const char *s = skip_wsp((const char *)t);
        int st = AA_OK, is_auto = !strncasecmp(s, "auto", 4) && !*skip_wsp(s + 4);
        if (!is_auto) {
            r->node = from[k];
            st = parse_length(r, key, s, v);
            if (!st && *v < 0)
                st = fail_at(r, "a negative %s is an error", key);
            r->node = node;
        }
        xmlFree(t);
        if (st || !is_auto)
            return st;
    }
    *v = key[0] == 'w' ? r->vpw : r->vph;
    return AA_OK;
}

/* A <symbol>'s reference point (SVG 2, "The 'symbol' element": refX and
 * refY, in the symbol's content coordinates, after its viewBox and
 * preserveAspectRatio) is placed at the symbol's (x, y), the whole
 * viewport moving with it: *s, the shift to add in the viewport's
 * coordinates, is minus the point mapped by the viewBox map vbm (a scale
 * and a translation).  A length (a number, a unit, % of the viewBox's
 * width or height: vb) or left, center, right (top, center, bottom): the
 * viewBox's left edge, middle and right edge in content coordinates (the
 * viewport's, 0 to its size, without a viewBox).  Absent: no shift on
 * that axis, which is not refX="0" when the viewBox does not start at 0
 * or meet leaves room (SVG 2 keeps the old placement for symbols that do
 * not say). */
static int symbol_shift(reader *r, const xmlNode *node, const mat *vbm, const double vb[2],
                        double s[2])
{
    static const char *const keys[2] = {"refX", "refY"};
    static const char *const words[2][3] = {{"left", "center", "right"},
                                            {"top", "center", "bottom"}};
    s[0] = s[1] = 0;
    if (!named(node, "symbol"))
        return AA_OK;
    /* the viewBox's origin in content coordinates: vbm maps it to
     * (vbm.e + vbm.a b0, ...) and a viewBox of size vb starts at b0 */
    double b0[2] = {0, 0};
    xmlChar *t = xmlGetNoNsProp(node, (const xmlChar *)"viewBox");
    if (t) { /* read already by viewbox_map, so four numbers */
        const char *p = skip_wsp((const char *)t);
        for (int k = 0; k < 2; k++) {
            if (k)
                p = skip_comma_wsp(p);
            (void)scan_number(&p, &b0[k]);
        }
        xmlFree(t);
    }
    int st = AA_OK;
    for (int k = 0; k < 2 && !st; k++) {
        t = xmlGetNoNsProp(node, (const xmlChar *)keys[k]);
        if (!t)
            continue;
        const char *v = skip_wsp((const char *)t);
        char word[16] = "";
        sscanf(v, "%15[a-zA-Z]", word);
        double ref = 0;
        int j = 0;
        while (j < 3 && strcasecmp(word, words[k][j]))
            j++;
        if (j < 3 && !*skip_wsp(v + strlen(word)))
            ref = b0[k] + vb[k] * j / 2;
        else {
            /* % of the viewBox's width or height: the viewport's size for
             * the axis is the viewBox's here */
            const double w = r->vpw, h = r->vph;
            r->vpw = vb[0], r->vph = vb[1];
            st = parse_length(r, k ? "y" : "x", v, &ref);
            r->vpw = w, r->vph = h;
            if (st == AA_EINVAL && invalid_attr(r, keys[k], v, "a length or a keyword")) {
                st = AA_OK; /* SVG 2: the initial value, no shift */
                xmlFree(t);
                continue;
            }
        }
        xmlFree(t);
        if (!st)
            s[k] = -(k ? vbm->d * ref + vbm->f : vbm->a * ref + vbm->e);
    }
    return st;
}

/* A nested <svg>, or a <symbol> drawn as the target of the <use> via (SVG
 * 2, "The 'use' element": its width and height, unless auto, replace the
 * target's): a new viewport at (x, y) of its width and height (auto or
 * absent: 100%) in the user units it is in, its viewBox mapped onto it;
 * percentages within it refer to the viewBox's size (or the viewport's).
 * overflow (initially hidden for both, by SVG 2's user agent style sheet)
 * hidden, scroll or clip clips its content to the viewport (CSS Overflow
 * 3; SVG 2, "The effect of the 'overflow' property"): the viewport's
 * rectangle x, y, width, height in the user space the element is in (not
 * the viewBox, which meet may leave smaller) becomes a clip within the
 * clip the element is drawn in, made when a shape first reaches beyond
 * it (shape_clip, viewport_clip); visible and auto (SVG: as visible) do
 * not clip. */
static int viewport_element(reader *r, const xmlNode *node, const xmlNode *via, style sty, mat m,
                            int depth, double opacity)
{
    double x = 0, y = 0, w, h;
    int st;
    /* a nested svg's x and y, and a symbol's (SVG 2 gives <symbol> x, y,
     * width and height, laid out as a nested svg's: Chromium and Firefox
     * draw them so, resvg and librsvg ignore x and y) */
    if ((named(node, "svg") || named(node, "symbol")) &&
        ((st = attr_length(r, node, "x", 0, &x)) || (st = attr_length(r, node, "y", 0, &y))))
        return st;
    if ((st = viewport_side(r, node, via, "width", &w)) ||
        (st = viewport_side(r, node, via, "height", &h)))
        return st;
    if (w == 0 || h == 0)
        return AA_OK; /* SVG: a viewport of no area draws nothing */
    char v[1024];
    int clip = 1;
    if (prop(r, node, "overflow", v, sizeof v, &st)) {
        if (!strcasecmp(v, "visible") || !strcasecmp(v, "auto"))
            clip = 0;
        else if (strcasecmp(v, "hidden") && strcasecmp(v, "scroll") && strcasecmp(v, "clip"))
            return fail_at(r, "overflow=\"%s\" (visible, hidden, scroll, clip or auto)",
                           aa_echo(v));
    }
    if (st)
        return st;
    mat vbm, to;
    double vb[2], sh[2];
    if ((st = viewbox_map(r, node, w, h, &vbm, vb)) ||
        (st = symbol_shift(r, node, &vbm, vb, sh)))
        return st;
    x += sh[0], y += sh[1]; /* the viewport moves with the reference point */
    const mat at = {1, 0, 0, 1, x, y};
    const mat inner = mat_mul(m, mat_mul(at, vbm));
    /* clip-path on the viewport element itself: in the user space the
     * element establishes, its content's (CSS Masking 1, userSpaceOnUse:
     * "the user coordinate system for the element referencing the
     * clipPath"; SVG 1.1: the viewBox "establishes a new user space"), so
     * inner, the viewBox map and (x, y) (and a use's translate(x, y))
     * applied, as Chromium and resvg clip a symbol; the viewport's own
     * clip (overflow) is made within it, so the content is clipped by
     * both (tests/test_svg_clip.c: Chromium drops the viewport's clip
     * when a nested svg has a clip-path, resvg does not draw such an svg,
     * librsvg clips in the parent's user space and not a symbol) */
    const int outer = r->clip;
    int cp;
    r->clip_viewport = node;
    r->clip_viewport_vb[0] = vb[0], r->clip_viewport_vb[1] = vb[1];
    st = clip_of(r, node, &inner, outer, &cp);
    r->clip_viewport = NULL;
    if (st)
        return st;
    r->node = node;
    if (clip) {
        if (mat_inverse(&m, &to))
            return fail_at(r, "a viewport that clips under a singular transform is not "
                              "supported");
        r->vclip[r->nvclip] = (struct svg_clip){m, to, {x, y, x + w, y + h}, node, cp, -1};
        r->clip = -2 - r->nvclip++;
    } else
        r->clip = cp;
    const double pw = r->vpw, ph = r->vph;
    r->vpw = vb[0], r->vph = vb[1];
    if (opacity < 1)
        st = group_begin(r, opacity);
    if (!st)
        st = children(r, node, sty, inner, depth);
    if (!st && opacity < 1) {
        r->node = node;
        st = r->sink->group_end(r->ctx);
    }
    r->vpw = pw, r->vph = ph;
    if (clip)
        --r->nvclip;
    r->clip = outer;
    return st;
}

/* The target of the <use> node (href, or xlink:href, "#id": the first
 * element of that id) into *out, NULL when it has none or it is missing; a
 * reference to another document is refused (never loaded). */
static int use_target(reader *r, const xmlNode *node, const xmlNode **out)
{
    *out = NULL;
    xmlChar *href = xmlGetNoNsProp(node, (const xmlChar *)"href");
    if (!href)
        href = xmlGetNsProp(node, (const xmlChar *)"href",
                            (const xmlChar *)"http://www.w3.org/1999/xlink");
    if (!href)
        return AA_OK;
    const char *h = skip_wsp((const char *)href);
    int st = AA_OK;
    const xmlNode *target = NULL;
    if (!*h) /* no reference: nothing */
        ;
    else if (*h != '#')
        st = fail_at(r, "href=\"%s\": a reference to another document is not supported",
                     aa_echo(h));
    else {
        target = find_href(r->ids, h);
    }
    xmlFree(href);
    *out = st ? NULL : target;
    return st;
}

/* <use> (SVG 2, "The 'use' element"): its target (href, or xlink:href,
 * "#id": the first element of that id) drawn as its child, so that the
 * target's properties inherit from the <use> (style sheets match the
 * target where it is in the document), under the use's transform and
 * then translate(x, y).  A target that is missing, or that is the <use>
 * or one of its ancestors (through the targets being drawn: a reference
 * cycle), puts the use in error: it draws nothing, as browsers do.  A
 * reference to another document is refused (never loaded). */
static int use_element(reader *r, const xmlNode *node, style sty, mat m, int depth,
                       double opacity)
{
    const xmlNode *target;
    int st = use_target(r, node, &target);
    if (st || !target)
        return st;
    for (int k = 0; k <= depth; k++)
        if (r->chain[k] == target)
            return AA_OK; /* a cycle: in error */
    double x, y;
    if ((st = attr_length(r, node, "x", 0, &x)) || (st = attr_length(r, node, "y", 0, &y)))
        return st;
    const mat at = {1, 0, 0, 1, x, y};
    m = mat_mul(m, at);
    /* its clip-path in its user space, translate(x, y) included (SVG 2:
     * x and y are a transform appended to the use's; Chromium, resvg and
     * librsvg clip there), within the clip it is drawn in */
    const int outer = r->clip;
    int clip;
    r->csty_node = node, r->csty = &sty;
    st = clip_of(r, node, &m, outer, &clip);
    r->csty_node = NULL, r->csty = NULL;
    if (st)
        return st;
    r->node = node;
    if (opacity < 1 && (st = group_begin(r, opacity)))
        return st;
    r->use = node;
    r->clip = clip;
    st = element(r, target, sty, m, depth + 1);
    r->clip = outer;
    r->use = NULL;
    if (!st && opacity < 1) {
        r->node = node;
        st = r->sink->group_end(r->ctx);
    }
    return st;
}

static int structure(reader *r, const xmlNode *node, const xmlNode *via, style sty, mat m,
                     int depth)
{
    if (named(node, "style"))
        return AA_OK; /* read before the walk (read_sheets) */
    if (named(node, "symbol") && !via)
        return AA_OK; /* drawn only as the target of a <use> */
    int skip, st;
    double opacity;
    if ((st = element_props(r, node, &sty, &m, &skip, &opacity)) || skip || opacity == 0)
        return st;
    if (named(node, "use"))
        return use_element(r, node, sty, m, depth, opacity);
    return viewport_element(r, node, via, sty, m, depth, opacity);
}

/* The viewport and the root's map from user units to pixels. */
static int root_map(reader *r, const xmlNode *root, double w, double h, mat *m, double vp[2],
                    int given[2])
{
    double vw = w, vh = h;
    int st;
    static const char *const sides[2] = {"width", "height"};
    for (int k = 0; k < 2; k++) {
        given[k] = 0;
        xmlChar *t = xmlGetNoNsProp(root, (const xmlChar *)sides[k]);
        if (!t)
            continue;
        const char *s = skip_wsp((const char *)t);
        if (!strcmp(s, "100%") || !strcmp(s, "auto"))
            st = AA_OK;
        else
            st = parse_length(r, sides[k], s, k ? &vh : &vw), given[k] = !strchr(s, '%');
        xmlFree(t);
        if (st)
            return st;
        if ((k ? vh : vw) <= 0)
            return fail_at(r, "%s must be positive", sides[k]);
        if ((k ? vh : vw) > AA_SVG_MAX_COORD)
            return fail_at(r, "%s is larger than %g", sides[k], AA_SVG_MAX_COORD);
    }
    vp[0] = vw, vp[1] = vh;
    double vb[2];
    return viewbox_map(r, root, vw, vh, m, vb);
}

/* 1 if the document declares entities (an internal DTD subset with
 * declarations). */
static int declares_entities(const xmlDoc *doc)
{
    const xmlDtd *dtd = doc->intSubset;
    if (!dtd)
        return 0;
    for (const xmlNode *c = dtd->children; c; c = c->next)
        if (c->type == XML_ENTITY_DECL)
            return 1;
    return 0;
}

int aa_svg_read(const char *data, size_t len, const char *name, int w, int h,
                const aa_svg_sink *sink, void *ctx, double viewport[2])
{
    return aa_svg_read_at(data, len, name, w, h, 1, sink, ctx, viewport);
}

int aa_svg_read_at(const char *data, size_t len, const char *name, int w, int h, double scale,
                   const aa_svg_sink *sink, void *ctx, double viewport[2])
{
    reader r = {.sink = sink, .ctx = ctx, .name = name, .clip = -1};
    double vp[2] = {0, 0};
    int given[2] = {0, 0};
    if (!sink) /* the size only: the view does not matter */
        w = h = 1;
    if (w < 1 || h < 1)
        return aa_fail(AA_EINVAL, "%s: a view of %dx%d pixels", name, w, h);
    if (!(scale >= AA_SVG_MIN_SCALE && scale <= AA_SVG_MAX_SCALE))
        return aa_fail(AA_EINVAL, "%s: scale %g is outside [%g, %g]", name, scale,
                       AA_SVG_MIN_SCALE, AA_SVG_MAX_SCALE);
    if (len > AA_SVG_MAX_BYTES)
        return aa_fail(AA_EINVAL, "%s: larger than %u bytes", name, AA_SVG_MAX_BYTES);
    xmlParserCtxtPtr parser = xmlNewParserCtxt();
    if (!parser)
        return aa_fail(AA_ENOMEM, "out of memory parsing %s", name);
    xmlDocPtr doc = xmlCtxtReadMemory(parser, data, (int)len, NULL, NULL,
                                      XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING |
                                          XML_PARSE_NOCDATA);
    int st = AA_OK;
    if (!doc) {
        const xmlError *e = xmlCtxtGetLastError(parser);
        char msg[256] = "not well-formed XML";
        if (e && e->message) {
            snprintf(msg, sizeof msg, "%s", e->message);
            msg[strcspn(msg, "\n")] = '\0';
        }
        st = aa_fail(AA_EINVAL, "%s: line %d: malformed XML: %s", name, e ? e->line : 0, msg);
        xmlFreeParserCtxt(parser);
        return st;
    }
    xmlFreeParserCtxt(parser);
    const xmlNode *root = xmlDocGetRootElement(doc);
    aa__c_numbers numbers;
    if (declares_entities(doc))
        st = aa_fail(AA_EINVAL, "%s: entity declarations are not supported", name);
    else if (!root || !is_svg(root) || !named(root, "svg"))
        st = aa_fail(AA_EINVAL, "%s: the root element is not <svg> in the SVG namespace (%s)",
                     name, SVG_NS);
    else if (!(st = aa__c_numbers_enter(&numbers, "SVG"))) {
        mat m;
        style sty;
        initial_style(&sty);
        int skip;
        r.node = root;
        r.root = root;
        double opacity = 1;
        /* the ids, the style sheets; percentages in the root's size are of
         * the view's, em of the initial font-size */
        svg_ids ids = {NULL, 0, 0};
        r.ids = &ids;
        r.font_size = r.rem = 16;
        r.vpw = r.icbw = w / scale, r.vph = r.icbh = h / scale;
        if (!st && !(st = collect_ids(&ids, root))) {
            if (ids.n)
                qsort(ids.e, ids.n, sizeof *ids.e, id_cmp);
            st = read_sheets(&r, root);
        }
        r.node = root;
        /* a use of the root is a cycle; its children, read at depth 2,
         * find it as their parent in the chain (style_parent: the
         * properties they inherit from it, custom ones too) */
        r.chain[0] = r.chain[1] = root;
        char fs[256];
        if (!st && prop(&r, root, "font-size", fs, sizeof fs, &st) && !st &&
            strcasecmp(fs, "inherit"))
        {
            double size;
            if (!(st = parse_font_size(&r, fs, 16, &size)))
                r.font_size = r.rem = size; /* em and rem in the root's size */
        }
        /* at `scale` pixels a CSS pixel: the document laid out in a view of
         * (w, h) / scale CSS pixels, then everything scaled */
        double vb[2];
        mat vbm, root_vb = identity;
        const mat zoom = {scale, 0, 0, scale, 0, 0};
        /* the view units in the root's size are refused: the view may be
         * that size */
        r.icbw = r.icbh = NAN;
        if (!st)
            st = root_map(&r, root, w / scale, h / scale, &m, vp, given);
        r.icbw = w / scale, r.icbh = h / scale;
        if (!st && !(st = viewbox_map(&r, root, vp[0], vp[1], &vbm, vb))) {
            r.vpw = vb[0], r.vph = vb[1]; /* percentages in the document */
            r.rootw = vp[0], r.rooth = vp[1];
            root_vb = m;
            m = mat_mul(zoom, m);
            vp[0] *= scale, vp[1] *= scale;
            if (!sink && !(given[0] && given[1]))
                st = fail_at(&r, "the root has no size of its own (width and height in px): "
                                 "give the view's size");
        }
        /* the root's transform and clip-path are those of its layout box:
         * in CSS px, its viewport (0, 0, width, height) there, outside its
         * viewBox map (CSS Transforms 1 and CSS Masking 1 on an element with
         * a layout box, as Chromium draws an <svg> in a page), the viewport
         * clipping its content as transformed (a clip of the scene, which
         * the caller's clip to the untransformed viewport would not be:
         * viewport[] is then the view) */
        mat top = zoom;
        if (!st && sink && !(st = element_props(&r, root, &sty, &top, &skip, &opacity)) &&
            !skip && opacity > 0 && conditions_hold(root)) {
            m = mat_mul(top, root_vb);
            int cp;
            st = clip_of(&r, root, &top, -1, &cp);
            r.node = root;
            r.clip = cp;
            if (!st && memcmp(&top, &zoom, sizeof top)) {
                mat to;
                if (mat_inverse(&top, &to))
                    st = fail_at(&r, "a singular transform on the root <svg> is not supported");
                else {
                    r.vclip[0] =
                        (struct svg_clip){top, to, {0, 0, r.rootw, r.rooth}, root, cp, -1};
                    r.nvclip = 1, r.clip = -2;
                    vp[0] = w, vp[1] = h;
                }
            }
            /* the root's opacity: its content as a group */
            if (!st && opacity < 1)
                st = group_begin(&r, opacity);
            if (!st)
                st = children(&r, root, sty, m, 1);
            if (!st && opacity < 1)
                st = r.sink->group_end(r.ctx);
        }
        free_ids(&ids);
        aa_css_free(r.css);
        aa__c_numbers_end(&numbers);
    }
    clips_free(&r);
    xmlFreeDoc(doc);
    if (!st && viewport)
        viewport[0] = vp[0], viewport[1] = vp[1];
    return st;
}

int aa_svg_read_file(const char *path, int w, int h, const aa_svg_sink *sink, void *ctx,
                     double viewport[2])
{
    return aa_svg_read_file_at(path, w, h, 1, sink, ctx, viewport);
}

int aa_svg_read_file_at(const char *path, int w, int h, double scale, const aa_svg_sink *sink,
                        void *ctx, double viewport[2])
{
    char *data;
    size_t len;
    int st = aa_file_read_all(path, AA_SVG_MAX_BYTES, "SVG file", &data, &len);
    if (st)
        return st;
    char name[256];
    snprintf(name, sizeof name, "%s", aa_echo(path));
    st = aa_svg_read_at(data, len, name, w, h, scale, sink, ctx, viewport);
    free(data);
    return st;
}

/* ------------------------------------------------------------------------
 * The pattern `svg`: the shapes recorded in document order, then put into
 * the scene front first (the last shape is the front layer), each point
 * (u, v) in pixels as (u / W, v / H) in pattern units, which placing maps
 * back to (u, v) (exactly when W and H are powers of two).
 * ------------------------------------------------------------------------ */

enum { SVG_FILE, SVG_SCALE };

/* The default file: the shipped shapes.svg, in the folder of the shipped
 * scenes (aa_svg_dir: the source tree's, or the install prefix's), set
 * when the library starts, since a parameter's default is read before any
 * call here.  Empty if the path is too long: svg_check refuses it then. */
static char default_file[AA_PARAM_TEXT_MAX + 1];

__attribute__((constructor)) static void default_file_set(void)
{
    if (aa_pathf(default_file, sizeof default_file, "%s/shapes.svg", aa_svg_dir()))
        default_file[0] = '\0';
}

static const aa_param svg_params[] = {
    {"file", AA_PARAM_TEXT, 0, 0, 0, 0, default_file,
     "the SVG file (a path; write ',' as %2C and '%' as %25)"},
    {"scale", AA_PARAM_REAL, 1, AA_SVG_MIN_SCALE, AA_SVG_MAX_SCALE, 0, NULL,
     "image pixels per CSS pixel (as rsvg-convert -z); without -s the image is the file's "
     "own size times this"},
    {0}};

typedef struct rec_op {
    int op; /* 0 move, 1 line, 2 quad, 3 cubic, 4 close, 5 elliptical arc */
    double v[10];
} rec_op;

typedef struct rec_shape {
    aa_rgb colour;
    aa_fill_rule rule;
    size_t first, n;
    long stroke; /* its source in the recording's strokes, or -1 for a fill */
    double alpha;
    int group;   /* 0 a shape; +1 a group's beginning, -1 its end (of opacity alpha) */
    /* clips: +1 a clip's beginning (within the clip `clip`), -1 its end,
     * 0 a shape (clipped by `clip`, -1 none); member: a clip's member */
    int clipmark, clip, member;
    long grad; /* its gradient in the recording's gradients, or -1: its colour */
} rec_shape;

/* A stroke's source as the reader gave it (its own copies). */
typedef struct rec_stroke {
    aa_path path;
    aa_stroke_style style;
    double dash[AA_SVG_MAX_DASHES];
    double m[6];
} rec_stroke;

typedef struct recording {
    rec_shape *shapes;
    size_t nshapes, capshapes;
    rec_stroke *strokes;
    size_t nstrokes, capstrokes;
    rec_op *ops;
    size_t nops, capops;
    double lo[2], hi[2]; /* the bounds of every op's box (op_box) */
    int in_clip;         /* inside a clip's definition */
    aa_gradient *grads;  /* the shapes' gradients, each with its own stops */
    size_t ngrads, capgrads;
    char (*sources)[192]; /* each gradient's element and line */
    size_t capsources;
    int *interps; /* each gradient's aa_interpolation */
    size_t capinterps;
} recording;

static int grow(void **a, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return AA_OK;
    size_t c = *cap ? 2 * *cap : 64;
    while (c < need)
        c *= 2;
    void *p = realloc(*a, c * size);
    if (!p)
        return aa_fail(AA_ENOMEM, "out of memory reading an SVG");
    *a = p, *cap = c;
    return AA_OK;
}

static int rec_shape_fn(void *ctx, aa_rgb colour, aa_fill_rule rule)
{
    recording *r = ctx;
    int st = grow((void **)&r->shapes, &r->capshapes, r->nshapes + 1, sizeof *r->shapes);
    if (!st)
        r->shapes[r->nshapes++] = (rec_shape){colour, rule, r->nops, 0, -1, 1.0, 0, 0, -1,
                                              r->in_clip, -1};
    return st;
}

/* The last shape's gradient: a copy, its stops its own. */
static int rec_gradient_fn(void *ctx, const aa_gradient *g, const char *source)
{
    recording *r = ctx;
    if (!r->nshapes)
        return aa_fail(AA_EFAIL, "a gradient without its shape");
    int st = grow((void **)&r->grads, &r->capgrads, r->ngrads + 1, sizeof *r->grads);
    if (!st)
        st = grow((void **)&r->sources, &r->capsources, r->ngrads + 1, sizeof *r->sources);
    if (!st)
        st = grow((void **)&r->interps, &r->capinterps, r->ngrads + 1, sizeof *r->interps);
    if (st)
        return st;
    snprintf(r->sources[r->ngrads], sizeof *r->sources, "%s", source);
    r->interps[r->ngrads] = AA_INTERPOLATE_SRGB;
    aa_gradient_stop *stops = malloc((size_t)(g->nstops > 0 ? g->nstops : 1) * sizeof *stops);
    if (!stops)
        return aa_fail(AA_ENOMEM, "out of memory reading an SVG");
    memcpy(stops, g->stops, (size_t)g->nstops * sizeof *stops);
    r->grads[r->ngrads] = *g;
    r->grads[r->ngrads].stops = stops;
    r->shapes[r->nshapes - 1].grad = (long)r->ngrads++;
    return AA_OK;
}

/* A recorded shape's gradient on the scene's layer added last, its map
 * from pixels to the unit square (x / W, y / H). */
static int rec_put_gradient(aa_scene *s, const recording *rec, const rec_shape *sh, int w,
                            int h)
{
    if (sh->grad < 0)
        return AA_OK;
    aa_gradient g = rec->grads[sh->grad];
    const double *m = rec->grads[sh->grad].m;
    const double to[6] = {m[0] / w, m[1] / h, m[2] / w, m[3] / h, m[4] / w, m[5] / h};
    memcpy(g.m, to, sizeof to);
    int st = aa_scene_set_gradient(s, &g);
    if (!st && rec->interps[sh->grad] != AA_INTERPOLATE_SRGB)
        st = aa_scene_set_gradient_interpolation(s, rec->interps[sh->grad]);
    return st ? st : aa_scene_set_gradient_source(s, rec->sources[sh->grad]);
}

/* The last shape's gradient's interpolation (after rec_gradient_fn). */
static int rec_interpolation_fn(void *ctx, int interpolation)
{
    recording *r = ctx;
    if (!r->ngrads || r->shapes[r->nshapes - 1].grad != (long)r->ngrads - 1)
        return aa_fail(AA_EFAIL, "a gradient interpolation without its gradient");
    r->interps[r->ngrads - 1] = interpolation;
    return AA_OK;
}

static int rec_alpha_fn(void *ctx, double alpha)
{
    recording *r = ctx;
    r->shapes[r->nshapes - 1].alpha = alpha;
    return AA_OK;
}

/* A group's beginning and end as marks among the shapes, each with the
 * group's opacity (the scene is built front first: from the end). */
static int rec_group(recording *r, int mark, double opacity)
{
    int st = grow((void **)&r->shapes, &r->capshapes, r->nshapes + 1, sizeof *r->shapes);
    if (!st)
        r->shapes[r->nshapes++] = (rec_shape){{{0, 0, 0}}, AA_FILL_NONZERO, r->nops, 0, -1,
                                              opacity, mark, 0, -1, 0, -1};
    return st;
}

static int rec_group_begin(void *ctx, double opacity) { return rec_group(ctx, 1, opacity); }

static int rec_group_end(void *ctx)
{
    recording *r = ctx;
    /* the opacity of the group this ends: the last beginning not yet ended */
    int open = 0;
    for (size_t k = r->nshapes; k-- > 0;) {
        open += r->shapes[k].group;
        if (open > 0)
            return rec_group(r, -1, r->shapes[k].alpha);
    }
    return aa_fail(AA_EFAIL, "a group's end without its beginning");
}

/* The source of the stroke whose outline was the last shape. */
static int rec_stroke_fn(void *ctx, const aa_path *path, const aa_stroke_style *ss,
                         const double m[6])
{
    recording *r = ctx;
    if (!r->nshapes || ss->ndash > AA_SVG_MAX_DASHES)
        return aa_fail(AA_EFAIL, "a stroke's source without its outline");
    int st = grow((void **)&r->strokes, &r->capstrokes, r->nstrokes + 1, sizeof *r->strokes);
    if (st)
        return st;
    rec_stroke *k = &r->strokes[r->nstrokes];
    memset(k, 0, sizeof *k);
    if (path->n && !(k->path.seg = malloc(path->n * sizeof *path->seg)))
        return aa_fail(AA_ENOMEM, "out of memory reading an SVG");
    if (path->n)
        memcpy(k->path.seg, path->seg, path->n * sizeof *path->seg);
    k->path.n = k->path.cap = path->n;
    k->style = *ss;
    if (ss->ndash)
        memcpy(k->dash, ss->dash, ss->ndash * sizeof *ss->dash);
    k->style.dash = ss->ndash ? k->dash : NULL;
    memcpy(k->m, m, sizeof k->m);
    r->shapes[r->nshapes - 1].stroke = (long)r->nstrokes++;
    return AA_OK;
}

/* A box (x0 y0 x1 y1) holding what the op draws: its points and control
 * points (a Bezier arc lies in their hull), for an elliptical arc its
 * end and the whole ellipse's box, centre +- (hypot(ux, vx), hypot(uy, vy))
 * (the extremes of cx + ux cos t + vx sin t over t).  0 for a close. */
static int op_box(const rec_op *o, double box[4])
{
    const double *v = o->v;
    box[0] = box[1] = INFINITY, box[2] = box[3] = -INFINITY;
    int np = o->op == 0 || o->op == 1 ? 1 : o->op == 2 ? 2 : o->op == 3 ? 3 : 0;
    if (o->op == 5) {
        const double hx = hypot(v[2], v[4]), hy = hypot(v[3], v[5]);
        box[0] = fmin(v[0] - hx, v[8]), box[2] = fmax(v[0] + hx, v[8]);
        box[1] = fmin(v[1] - hy, v[9]), box[3] = fmax(v[1] + hy, v[9]);
        return 1;
    }
    for (int q = 0; q < np; q++) {
        box[0] = fmin(box[0], v[2 * q]), box[2] = fmax(box[2], v[2 * q]);
        box[1] = fmin(box[1], v[2 * q + 1]), box[3] = fmax(box[3], v[2 * q + 1]);
    }
    return np > 0;
}

static int rec_op_add(recording *r, int op, const double *v, int n)
{
    int st = grow((void **)&r->ops, &r->capops, r->nops + 1, sizeof *r->ops);
    if (st)
        return st;
    rec_op *o = &r->ops[r->nops++];
    o->op = op;
    for (int k = 0; k < n; k++)
        o->v[k] = v[k];
    double box[4];
    if (op_box(o, box))
        for (int k = 0; k < 2; k++) {
            r->lo[k] = fmin(r->lo[k], box[k]);
            r->hi[k] = fmax(r->hi[k], box[k + 2]);
        }
    r->shapes[r->nshapes - 1].n++;
    return AA_OK;
}

static int rec_move(void *ctx, double x, double y)
{
    double v[2] = {x, y};
    return rec_op_add(ctx, 0, v, 2);
}
static int rec_line(void *ctx, double x, double y)
{
    double v[2] = {x, y};
    return rec_op_add(ctx, 1, v, 2);
}
static int rec_quad(void *ctx, double cx, double cy, double x, double y)
{
    double v[4] = {cx, cy, x, y};
    return rec_op_add(ctx, 2, v, 4);
}
static int rec_cubic(void *ctx, double c1x, double c1y, double c2x, double c2y, double x,
                     double y)
{
    double v[6] = {c1x, c1y, c2x, c2y, x, y};
    return rec_op_add(ctx, 3, v, 6);
}
static int rec_close(void *ctx) { return rec_op_add(ctx, 4, NULL, 0); }
static int rec_arc(void *ctx, double cx, double cy, double ux, double uy, double vx, double vy,
                   double t0, double t1, double x, double y)
{
    double v[10] = {cx, cy, ux, uy, vx, vy, t0, t1, x, y};
    return rec_op_add(ctx, 5, v, 10);
}

/* A clip's beginning and end as marks among the shapes, its members the
 * shapes between (marked `member`); a shape's clip on the shape. */
static int rec_clip_mark(recording *r, int mark, int within)
{
    int st = grow((void **)&r->shapes, &r->capshapes, r->nshapes + 1, sizeof *r->shapes);
    if (!st)
        r->shapes[r->nshapes++] = (rec_shape){{{0, 0, 0}}, AA_FILL_NONZERO, r->nops, 0, -1,
                                              1.0, 0, mark, within, 0, -1};
    r->in_clip = mark > 0;
    return st;
}

static int rec_clip_begin(void *ctx, int within) { return rec_clip_mark(ctx, 1, within); }
static int rec_clip_end(void *ctx) { return rec_clip_mark(ctx, -1, -1); }

static int rec_clip_fn(void *ctx, int clip)
{
    recording *r = ctx;
    r->shapes[r->nshapes - 1].clip = clip;
    return AA_OK;
}

static const aa_svg_sink recording_sink = {
    rec_shape_fn,    rec_move,     rec_line,        rec_quad,     rec_cubic,
    rec_close,       rec_arc,      rec_stroke_fn,   rec_alpha_fn, rec_group_begin,
    rec_group_end,   rec_clip_begin, rec_clip_end,  rec_clip_fn,  rec_gradient_fn,
    rec_interpolation_fn};

static int svg_check(const double *p)
{
    if (!*aa_param_text(p[SVG_FILE]))
        return aa_fail(AA_EINVAL, "pattern svg needs file=PATH (an SVG file)");
    return AA_OK;
}

static int svg_build_unsized(const double *p, aa_scene *s)
{
    (void)s;
    return aa_fail(AA_EINVAL, "pattern svg (%s) is drawn at the view's size: build it with one",
                   aa_echo(aa_param_text(p[SVG_FILE])));
}

/* A recorded shape's ops into the scene's current layer, each point (u, v)
 * in pixels as (u / W, v / H). */
static int rec_put_ops(aa_scene *s, const recording *rec, const rec_shape *sh, int w, int h)
{
    int st = AA_OK;
    for (size_t i = sh->first; i < sh->first + sh->n && !st; i++) {
        const rec_op *o = &rec->ops[i];
        const double *v = o->v;
        switch (o->op) {
        case 0:
            st = aa_scene_move_to(s, v[0] / w, v[1] / h);
            break;
        case 1:
            st = aa_scene_line_to(s, v[0] / w, v[1] / h);
            break;
        case 2:
            st = aa_scene_quad_to(s, v[0] / w, v[1] / h, v[2] / w, v[3] / h);
            break;
        case 3:
            st = aa_scene_cubic_to(s, v[0] / w, v[1] / h, v[2] / w, v[3] / h, v[4] / w,
                                   v[5] / h);
            break;
        case 5: /* (x, y) -> (x / W, y / H) is linear: the semi-diameters scale too */
            st = aa_scene_arc_to(s, v[0] / w, v[1] / h, v[2] / w, v[3] / h, v[4] / w,
                                 v[5] / h, v[6], v[7], v[8] / w, v[9] / h);
            break;
        default:
            st = aa_scene_close(s);
            break;
        }
    }
    return st;
}

int aa__svg_build_at(const double *p, int w, int h, aa_scene *s)
{
    recording rec = {0};
    double vp[2] = {0, 0};
    rec.lo[0] = rec.lo[1] = 0;
    rec.hi[0] = rec.hi[1] = 0;
    int st = aa_svg_read_file_at(aa_param_text(p[SVG_FILE]), w, h, p[SVG_SCALE],
                                 &recording_sink, &rec, vp);
    const int read_ok = st == AA_OK;
    /* content beyond the viewport: a front layer of the background colour
     * over everything outside it (even-odd of a larger rectangle and the
     * viewport) */
    if (!st && (rec.lo[0] < 0 || rec.lo[1] < 0 || rec.hi[0] > vp[0] || rec.hi[1] > vp[1])) {
        const aa_rgb black = {{0, 0, 0}};
        double o[4] = {fmin(rec.lo[0], 0) - 1, fmin(rec.lo[1], 0) - 1,
                       fmax(rec.hi[0], vp[0]) + 1, fmax(rec.hi[1], vp[1]) + 1};
        double q[2][4] = {{o[0] / w, o[1] / h, o[2] / w, o[3] / h},
                          {0, 0, vp[0] / w, vp[1] / h}};
        st = aa_scene_layer(s, black, AA_FILL_EVENODD);
        for (int k = 0; k < 2 && !st; k++) {
            const double *r = q[k];
            if ((st = aa_scene_move_to(s, r[0], r[1])) || (st = aa_scene_line_to(s, r[2], r[1])) ||
                (st = aa_scene_line_to(s, r[2], r[3])) || (st = aa_scene_line_to(s, r[0], r[3])))
                break;
            st = aa_scene_close(s);
        }
    }
    /* shapes front first; a run of consecutive shapes of one colour and
     * fill rule whose boxes (op_box) are pairwise disjoint is one
     * layer (a point is inside at most one of them, so the union under
     * either rule is the same picture; the reference's cost grows with the
     * layers) */
    double (*box)[4] = rec.nshapes ? malloc(rec.nshapes * sizeof *box) : NULL;
    if (!st && rec.nshapes && !box)
        st = aa_fail(AA_ENOMEM, "out of memory reading an SVG");
    for (size_t k = 0; k < rec.nshapes && !st; k++) {
        const rec_shape *sh = &rec.shapes[k];
        box[k][0] = box[k][1] = INFINITY, box[k][2] = box[k][3] = -INFINITY;
        for (size_t i = sh->first; i < sh->first + sh->n; i++) {
            double b[4];
            if (op_box(&rec.ops[i], b))
                for (int q = 0; q < 2; q++) {
                    box[k][q] = fmin(box[k][q], b[q]);
                    box[k][q + 2] = fmax(box[k][q + 2], b[q + 2]);
                }
        }
    }
    /* the clips first, in the order the reader numbered them (a clip
     * refers to earlier ones only), so that the scene numbers them alike */
    for (size_t k = 0; k < rec.nshapes && !st; k++) {
        const rec_shape *sh = &rec.shapes[k];
        if (sh->clipmark)
            st = sh->clipmark > 0 ? aa_scene_clip_begin(s, sh->clip) : aa_scene_clip_end(s, NULL);
        else if (sh->member && sh->n) {
            if (!(st = aa_scene_clip_layer(s, sh->rule)) &&
                !(sh->clip >= 0 && (st = aa_scene_set_clip(s, sh->clip))))
                st = rec_put_ops(s, &rec, sh, w, h);
        }
    }
    size_t group = 0, group_first = 0; /* shapes in the current layer, the front one */
    for (size_t k = rec.nshapes; k-- > 0 && !st;) {
        const rec_shape *sh = &rec.shapes[k];
        if (sh->clipmark || sh->member)
            continue;
        if (sh->group) { /* front first: a group's end opens it */
            st = sh->group < 0 ? aa_scene_group_begin(s, sh->alpha) : aa_scene_group_end(s);
            group = 0;
            continue;
        }
        if (!sh->n)
            continue;
        if (sh->stroke >= 0) {
            /* a stroke is a layer of its own, its source kept with it: the
             * outline again, from the source, mapped to the unit square
             * (x / W, y / H after the reader's map) */
            const rec_stroke *ks = &rec.strokes[sh->stroke];
            const double m[6] = {ks->m[0] / w, ks->m[1] / h, ks->m[2] / w,
                                 ks->m[3] / h, ks->m[4] / w, ks->m[5] / h};
            st = aa_scene_stroke(s, &ks->path, &ks->style, m, sh->colour);
            if (!st)
                st = rec_put_gradient(s, &rec, sh, w, h);
            if (!st && sh->alpha < 1)
                st = aa_scene_set_alpha(s, sh->alpha);
            if (!st && sh->clip >= 0)
                st = aa_scene_set_clip(s, sh->clip);
            group = 0;
            continue;
        }
        int join = group > 0 && group < 256 && rec.shapes[group_first].stroke < 0;
        const rec_shape *front = join ? &rec.shapes[group_first] : NULL;
        if (join)
            join = front->grad < 0 && sh->grad < 0 && front->rule == sh->rule &&
                   front->alpha == sh->alpha &&
                   front->clip == sh->clip &&
                   !memcmp(&front->colour, &sh->colour, sizeof sh->colour);
        for (size_t q = k + 1; join && q <= group_first; q++)
            if (rec.shapes[q].n && !(box[k][2] < box[q][0] || box[q][2] < box[k][0] ||
                                     box[k][3] < box[q][1] || box[q][3] < box[k][1]))
                join = 0;
        if (!join) {
            if ((st = aa_scene_layer(s, sh->colour, sh->rule)) ||
                (st = rec_put_gradient(s, &rec, sh, w, h)) ||
                (sh->alpha < 1 && (st = aa_scene_set_alpha(s, sh->alpha))) ||
                (sh->clip >= 0 && (st = aa_scene_set_clip(s, sh->clip))))
                break;
            group = 0, group_first = k;
        }
        group++;
        st = rec_put_ops(s, &rec, sh, w, h);
    }
    free(box);
    if (st && read_ok) /* the scene's refusal (a cubic arc it cannot hold, say) */
        st = aa_fail_context(st, "SVG file %s", aa_echo(aa_param_text(p[SVG_FILE])));
    free(rec.shapes);
    free(rec.ops);
    for (size_t k = 0; k < rec.nstrokes; k++)
        aa_path_free(&rec.strokes[k].path);
    free(rec.strokes);
    for (size_t k = 0; k < rec.ngrads; k++)
        free((void *)rec.grads[k].stops);
    free(rec.grads);
    free(rec.sources);
    free(rec.interps);
    return st;
}

int aa__svg_own_size(const double *p, int *w, int *h)
{
    double vp[2];
    int st = aa_svg_read_file_at(aa_param_text(p[SVG_FILE]), 1, 1, p[SVG_SCALE], NULL, NULL, vp);
    if (st)
        return st;
    /* whole pixels, up to rounding of the product */
    const double fw = ceil(vp[0] * (1 - 1e-12)), fh = ceil(vp[1] * (1 - 1e-12));
    if (!(fw >= 1 && fh >= 1 && fw <= AA_MAX_SIDE && fh <= AA_MAX_SIDE))
        return aa_fail(AA_EINVAL, "SVG file %s: its own size times %g is %gx%g pixels",
                       aa_echo(aa_param_text(p[SVG_FILE])), p[SVG_SCALE], vp[0], vp[1]);
    *w = (int)fw, *h = (int)fh;
    return AA_OK;
}

int aa__svg_key(const double *p, char *buf, size_t len)
{
    unsigned long long hash;
    size_t n;
    const char *path = aa_param_text(p[SVG_FILE]);
    int st = aa_file_hash(path, &hash, &n);
    if (st)
        return st;
    if ((size_t)snprintf(buf, len, "file fnv1a %016llx bytes %zu\n", hash, n) >= len)
        return aa_fail(AA_EFAIL, "view key too long");
    return AA_OK;
}

const aa_pattern_type aa_pattern_svg = {
    {"svg", "an SVG file's filled and stroked shapes, in pixels as a browser draws it",
     svg_params},
    svg_check,
    svg_build_unsized,
    {{0, 0, 0}}};
