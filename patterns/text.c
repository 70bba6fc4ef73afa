/*
 * text.c: a string's glyph outlines (patterns/README.md, `text`).
 *
 * The string (UTF-8) is shaped by HarfBuzz with the font's default features
 * (kerning, ligatures: hb_shape with no feature given, on a font made by
 * hb_ft_font_create_referenced from the FreeType face, so that its
 * advances are FreeType's unhinted ones), its direction, script and language
 * guessed from the text (hb_buffer_guess_segment_properties).  Each glyph
 * is loaded by FreeType at `ppem` pixels per em (FT_Set_Char_Size with
 * ppem * 64 at 72 dpi) with FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP: its
 * unhinted outline, in 26.6 fixed point as FreeType scales it, is
 * decomposed (FT_Outline_Decompose) into lines, quadratic arcs (TrueType's
 * conic points) and cubic arcs (CFF), every 26.6 number n becoming n / 64
 * pixels exactly.  The pen starts at (x, y) pixels, y the baseline
 * measured down from the top (y = 0: 2 plus the font's ascender at this
 * size, so that the tallest letters are inside the image); glyph k's origin
 * is the pen plus the sum of the advances before it plus its own offset,
 * and font units' y up becomes the image's y down.  The glyphs are one
 * white layer with the nonzero rule over black, as a rasterizer fills a
 * TrueType or CFF outline.
 */
#include "patterns.h"
#include "svgfile.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include <hb-ft.h>
#include <hb.h>

#ifndef AA_DEFAULT_FONT
#define AA_DEFAULT_FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

enum { STRING, FONT, PPEM, X, Y };

static const aa_param text_params[] = {
    {"string", AA_PARAM_TEXT, 0, 0, 0, 0, "Hamburgefonstiv AV fi",
     "the text (UTF-8; write ',' as %2C and '%' as %25)"},
    {"font", AA_PARAM_TEXT, 0, 0, 0, 0, AA_DEFAULT_FONT,
     "the font file (TrueType, OpenType or CFF, as FreeType reads them)"},
    {"ppem", AA_PARAM_INT, 16, 1, 1000, 0, NULL, "pixels per em, 1 to 1000"},
    {"x", AA_PARAM_REAL, 2, -1e6, 1e6, 0, NULL, "the pen's start, pixels from the left"},
    {"y", AA_PARAM_REAL, 0, -1e6, 1e6, 0, NULL,
     "the baseline, pixels from the top (0: 2 plus the font's ascender)"},
    {0}};

/* The code point of the well-formed UTF-8 sequence at s (RFC 3629: the
 * shortest form, no surrogate, at most U+10FFFF) and its length in *len; -1
 * where the bytes there are not one. */
static long utf8_code_point(const unsigned char *s, int *len)
{
    static const long least[] = {0, 0, 0x80, 0x800, 0x10000};
    int n = s[0] < 0x80 ? 1 : s[0] >= 0xc2 && s[0] < 0xe0 ? 2 : s[0] >= 0xe0 && s[0] < 0xf0 ? 3
                              : s[0] >= 0xf0 && s[0] < 0xf5                                ? 4
                                                                                           : 0;
    if (n == 0)
        return -1;
    long c = n == 1 ? s[0] : s[0] & (0x7f >> n);
    for (int k = 1; k < n; k++) {
        if ((s[k] & 0xc0) != 0x80)
            return -1;
        c = c << 6 | (s[k] & 0x3f);
    }
    if (c < least[n] || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff))
        return -1;
    *len = n;
    return c;
}

/* The string is UTF-8 without control characters (C0, DEL, C1), which no
 * font draws and HarfBuzz would shape as missing glyphs. */
static int check_string(const char *text)
{
    const unsigned char *s = (const unsigned char *)text;
    for (size_t at = 0; s[at];) {
        int len;
        long c = utf8_code_point(s + at, &len);
        if (c < 0)
            return aa_fail(AA_EINVAL, "pattern text: string is not UTF-8 (byte %zu is 0x%02x)",
                           at + 1, s[at]);
        if (c < 0x20 || (c >= 0x7f && c < 0xa0))
            return aa_fail(AA_EINVAL,
                           "pattern text: string has the control character U+%04lX at byte %zu",
                           c, at + 1);
        at += (size_t)len;
    }
    return AA_OK;
}

static int text_check(const double *p)
{
    if (!*aa_param_text(p[STRING]))
        return aa_fail(AA_EINVAL, "pattern text: string is empty (nothing to draw)");
    if (check_string(aa_param_text(p[STRING])))
        return AA_EINVAL;
    if (!*aa_param_text(p[FONT]))
        return aa_fail(AA_EINVAL, "pattern text: font is empty (a font file is needed)");
    return AA_OK;
}

static int text_build_unsized(const double *p, aa_scene *s)
{
    (void)p, (void)s;
    return aa_fail(AA_EINVAL, "pattern text is drawn at the view's size: build it with one");
}

/* Outline decomposition into the scene: 26.6 coordinates relative to the
 * glyph's origin (ox, oy in 26.6), pixels (px, py) for the pen's start, the
 * view's w, h. */
typedef struct glyph_ctx {
    aa_scene *s;
    long ox, oy;
    double px, py;
    int w, h, st;
} glyph_ctx;

static double gx(const glyph_ctx *g, const FT_Vector *v)
{
    return (g->px + (double)(g->ox + v->x) / 64.0) / g->w;
}

static double gy(const glyph_ctx *g, const FT_Vector *v)
{
    return (g->py - (double)(g->oy + v->y) / 64.0) / g->h;
}

static int cb_move(const FT_Vector *to, void *user)
{
    glyph_ctx *g = user;
    g->st = aa_scene_move_to(g->s, gx(g, to), gy(g, to));
    return g->st ? 1 : 0;
}

static int cb_line(const FT_Vector *to, void *user)
{
    glyph_ctx *g = user;
    g->st = aa_scene_line_to(g->s, gx(g, to), gy(g, to));
    return g->st ? 1 : 0;
}

static int cb_conic(const FT_Vector *c, const FT_Vector *to, void *user)
{
    glyph_ctx *g = user;
    g->st = aa_scene_quad_to(g->s, gx(g, c), gy(g, c), gx(g, to), gy(g, to));
    return g->st ? 1 : 0;
}

static int cb_cubic(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *user)
{
    glyph_ctx *g = user;
    g->st = aa_scene_cubic_to(g->s, gx(g, c1), gy(g, c1), gx(g, c2), gy(g, c2), gx(g, to),
                              gy(g, to));
    return g->st ? 1 : 0;
}

int aa__text_build_at(const double *p, int w, int h, aa_scene *s)
{
    const char *text = aa_param_text(p[STRING]), *font = aa_param_text(p[FONT]);
    const int ppem = (int)p[PPEM];
    FT_Library lib = NULL;
    FT_Face face = NULL;
    hb_font_t *hbf = NULL;
    hb_buffer_t *buf = NULL;
    int st = AA_OK;
    if (FT_Init_FreeType(&lib))
        return aa_fail(AA_ENOMEM, "pattern text: FreeType cannot start");
    if (FT_New_Face(lib, font, 0, &face)) {
        st = aa_fail(AA_EINVAL, "pattern text: font %s cannot be read (not a font FreeType knows, "
                                "or no such file)",
                     aa_echo(font));
        goto done;
    }
    if (!FT_IS_SCALABLE(face)) {
        st = aa_fail(AA_EINVAL, "pattern text: font %s has no outlines", aa_echo(font));
        goto done;
    }
    if (FT_Set_Char_Size(face, 0, (FT_F26Dot6)ppem * 64, 72, 72)) {
        st = aa_fail(AA_EINVAL, "pattern text: font %s cannot be set to %d ppem", aa_echo(font),
                     ppem);
        goto done;
    }
    const FT_Int32 flags = FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP;
    hbf = hb_ft_font_create_referenced(face);
    buf = hb_buffer_create();
    if (!hbf || !buf || !hb_buffer_allocation_successful(buf)) {
        st = aa_fail(AA_ENOMEM, "out of memory shaping text");
        goto done;
    }
    hb_ft_font_set_load_flags(hbf, flags);
    hb_buffer_add_utf8(buf, text, -1, 0, -1);
    hb_buffer_guess_segment_properties(buf);
    hb_shape(hbf, buf, NULL, 0);
    unsigned n = 0;
    const hb_glyph_info_t *info = hb_buffer_get_glyph_infos(buf, &n);
    const hb_glyph_position_t *pos = hb_buffer_get_glyph_positions(buf, NULL);
    const aa_rgb white = {{1, 1, 1}};
    if ((st = aa_scene_layer(s, white, AA_FILL_NONZERO)))
        goto done;
    glyph_ctx g = {s, 0, 0, p[X], p[Y], w, h, AA_OK};
    if (p[Y] == 0) /* 2 + the ascender, 26.6 as FreeType scales it unhinted */
        g.py = 2 + (double)FT_MulFix(face->ascender, face->size->metrics.y_scale) / 64.0;
    static const FT_Outline_Funcs funcs = {cb_move, cb_line, cb_conic, cb_cubic, 0, 0};
    long penx = 0, peny = 0;
    for (unsigned k = 0; k < n && !st; k++) {
        if (FT_Load_Glyph(face, info[k].codepoint, flags) ||
            face->glyph->format != FT_GLYPH_FORMAT_OUTLINE) {
            st = aa_fail(AA_EINVAL, "pattern text: glyph %u of font %s cannot be loaded as an "
                                    "outline",
                         info[k].codepoint, aa_echo(font));
            break;
        }
        g.ox = penx + pos[k].x_offset;
        g.oy = peny + pos[k].y_offset;
        if (FT_Outline_Decompose(&face->glyph->outline, &funcs, &g))
            st = g.st ? aa_fail_context(g.st, "font %s", aa_echo(font))
                      : aa_fail(AA_EINVAL, "pattern text: the outline of glyph %u is malformed",
                                info[k].codepoint);
        penx += pos[k].x_advance;
        peny += pos[k].y_advance;
    }
    if (!st)
        st = aa_scene_close(s);
done:
    if (buf)
        hb_buffer_destroy(buf);
    if (hbf)
        hb_font_destroy(hbf); /* releases the face it references */
    else if (face)
        FT_Done_Face(face);
    FT_Done_FreeType(lib);
    return st;
}

int aa__text_key(const double *p, char *buf, size_t len)
{
    unsigned long long hash;
    size_t n;
    int st = aa_file_hash(aa_param_text(p[FONT]), &hash, &n);
    if (st)
        return st;
    if ((size_t)snprintf(buf, len, "font fnv1a %016llx bytes %zu freetype %d.%d.%d harfbuzz %s\n",
                         hash, n, FREETYPE_MAJOR, FREETYPE_MINOR, FREETYPE_PATCH,
                         hb_version_string()) >= len)
        return aa_fail(AA_EFAIL, "view key too long");
    return AA_OK;
}

const aa_pattern_type aa_pattern_text = {
    {"text", "a string's glyph outlines, FreeType and HarfBuzz, white on black", text_params},
    text_check,
    text_build_unsized,
    {{0, 0, 0}}};
