/*
 * test_text.c: the pattern text (patterns/text.c) against FreeType and
 * HarfBuzz called directly: the glyphs' contours and ink bounds, a kerning
 * pair's advance, and the command's default.
 */
#include "bench.h"
#include "patterns.h"
#include "support.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_BBOX_H
#include FT_OUTLINE_H
#include <hb-ft.h>
#include <hb.h>

#define FONT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

/* The placed scene of a text spec on a w x h view. */
static aa_scene *placed_text(const char *spec, int w, int h)
{
    aa_spec s;
    aa_scene *sc = NULL;
    if (aa_pattern_parse(spec, &s) || aa_pattern_scene_at(&s, w, h, &sc))
        fail_msg("%s: %s", spec, aa_last_error());
    aa_scene *p = aa_scene_place(sc, w, h, 0, 0, 0);
    assert_non_null(p);
    aa_scene_free(sc);
    return p;
}

/* "Hamburgefonstiv" has no ligature in DejaVu Sans, so its glyphs are its
 * characters': the scene has one contour per FreeType contour of each
 * character's glyph (FT_Load_Char, unshaped), and its ink bounds are the
 * union of the glyphs' exact bounds (FT_Outline_Get_BBox) at the pen
 * positions HarfBuzz gives. */
static void test_contours_and_bounds(void **state)
{
    (void)state;
    const char *text = "Hamburgefonstiv";
    const int ppem = 24, W = 256, H = 40;
    FT_Library lib;
    FT_Face face;
    assert_int_equal(FT_Init_FreeType(&lib), 0);
    assert_int_equal(FT_New_Face(lib, FONT, 0, &face), 0);
    assert_int_equal(FT_Set_Char_Size(face, 0, ppem * 64, 72, 72), 0);
    size_t contours = 0;
    for (const char *c = text; *c; c++) {
        assert_int_equal(FT_Load_Char(face, (FT_ULong)*c, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP), 0);
        /* a contour of one point (DejaVu Sans's "u" has one) encloses
         * nothing and makes no path */
        const FT_Outline *o = &face->glyph->outline;
        for (int k = 0, first = 0; k < o->n_contours; first = o->contours[k++] + 1)
            contours += o->contours[k] > first;
    }
    /* the pen positions from HarfBuzz, the bounds from FreeType */
    hb_font_t *hf = hb_ft_font_create_referenced(face);
    hb_ft_font_set_load_flags(hf, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP);
    hb_buffer_t *b = hb_buffer_create();
    hb_buffer_add_utf8(b, text, -1, 0, -1);
    hb_buffer_guess_segment_properties(b);
    hb_shape(hf, b, NULL, 0);
    unsigned n;
    hb_glyph_info_t *info = hb_buffer_get_glyph_infos(b, &n);
    hb_glyph_position_t *pos = hb_buffer_get_glyph_positions(b, NULL);
    assert_int_equal(n, strlen(text));
    double baseline = 2 + FT_MulFix(face->ascender, face->size->metrics.y_scale) / 64.0;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    long pen = 0;
    for (unsigned k = 0; k < n; k++) {
        assert_int_equal(FT_Load_Glyph(face, info[k].codepoint, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP), 0);
        FT_BBox bb;
        assert_int_equal(FT_Outline_Get_BBox(&face->glyph->outline, &bb), 0);
        long ox = pen + pos[k].x_offset;
        x0 = fmin(x0, 3 + (ox + bb.xMin) / 64.0);
        x1 = fmax(x1, 3 + (ox + bb.xMax) / 64.0);
        y0 = fmin(y0, baseline - bb.yMax / 64.0);
        y1 = fmax(y1, baseline - bb.yMin / 64.0);
        pen += pos[k].x_advance;
    }
    hb_buffer_destroy(b);
    hb_font_destroy(hf);
    FT_Done_FreeType(lib);

    aa_scene *s = placed_text("text:string=Hamburgefonstiv,ppem=24,x=3", W, H);
    size_t nc;
    aa_scene_contours(s, &nc);
    assert_int_equal(nc, contours);
    double sx0, sy0, sx1, sy1;
    assert_int_equal(aa_scene_bounds(s, &sx0, &sy0, &sx1, &sy1), 1);
    printf("# ink bounds: scene [%.17g, %.17g] x [%.17g, %.17g], FreeType [%.17g, %.17g] x "
           "[%.17g, %.17g]\n",
           sx0, sx1, sy0, sy1, x0, x1, y0, y1);
    assert_true(fabs(sx0 - x0) < 1e-9 && fabs(sx1 - x1) < 1e-9);
    assert_true(fabs(sy0 - y0) < 1e-9 && fabs(sy1 - y1) < 1e-9);
    aa_scene_free(s);
}

/* "AV": HarfBuzz kerns the pair (DejaVu Sans's kerning); V stands where
 * HarfBuzz puts it, not at the unkerned advance of A. */
static void test_kerning(void **state)
{
    (void)state;
    const int ppem = 48;
    FT_Library lib;
    FT_Face face;
    assert_int_equal(FT_Init_FreeType(&lib), 0);
    assert_int_equal(FT_New_Face(lib, FONT, 0, &face), 0);
    assert_int_equal(FT_Set_Char_Size(face, 0, ppem * 64, 72, 72), 0);
    hb_font_t *hf = hb_ft_font_create_referenced(face);
    hb_ft_font_set_load_flags(hf, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP);
    long adv[2];
    for (int kern = 0; kern < 2; kern++) {
        hb_buffer_t *b = hb_buffer_create();
        hb_buffer_add_utf8(b, "AV", -1, 0, -1);
        hb_buffer_guess_segment_properties(b);
        hb_feature_t off;
        assert_true(hb_feature_from_string("-kern", -1, &off));
        hb_shape(hf, b, kern ? NULL : &off, kern ? 0 : 1);
        unsigned n;
        hb_glyph_position_t *pos = hb_buffer_get_glyph_positions(b, &n);
        assert_int_equal(n, 2);
        adv[kern] = pos[0].x_advance;
        hb_buffer_destroy(b);
    }
    printf("# AV at %d ppem: A's advance %ld/64 px unkerned, %ld/64 kerned\n", ppem, adv[0], adv[1]);
    assert_true(adv[1] < adv[0]); /* the pair moves closer */
    /* V's ink left edge in the scene: 2 + (kerned advance + V's xMin) / 64 */
    FT_UInt gv = FT_Get_Char_Index(face, 'V');
    assert_int_equal(FT_Load_Glyph(face, gv, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP), 0);
    FT_BBox bb;
    assert_int_equal(FT_Outline_Get_BBox(&face->glyph->outline, &bb), 0);
    double vx1 = 2 + (adv[1] + bb.xMax) / 64.0;
    hb_font_destroy(hf);
    FT_Done_FreeType(lib);
    aa_scene *s = placed_text("text:string=AV,ppem=48", 128, 64);
    double x0, y0, x1, y1;
    aa_scene_bounds(s, &x0, &y0, &x1, &y1);
    assert_true(fabs(x1 - vx1) < 1e-9);
    assert_true(fabs(x1 - (vx1 + (adv[0] - adv[1]) / 64.0)) > 0.5);
    aa_scene_free(s);
}

/* Contours of a glyph with more than one point (those make paths). */
static size_t glyph_contours(FT_Face face, FT_UInt glyph)
{
    assert_int_equal(FT_Load_Glyph(face, glyph, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP), 0);
    const FT_Outline *o = &face->glyph->outline;
    size_t n = 0;
    for (int k = 0, first = 0; k < o->n_contours; first = o->contours[k++] + 1)
        n += o->contours[k] > first;
    return n;
}

/* "fi" is shaped into DejaVu Sans's ligature (U+FB01, through its GSUB
 * liga feature): the scene has that glyph's contours, not those of f and i. */
static void test_ligature(void **state)
{
    (void)state;
    FT_Library lib;
    FT_Face face;
    assert_int_equal(FT_Init_FreeType(&lib), 0);
    assert_int_equal(FT_New_Face(lib, FONT, 0, &face), 0);
    assert_int_equal(FT_Set_Char_Size(face, 0, 16 * 64, 72, 72), 0);
    FT_UInt lig = FT_Get_Char_Index(face, 0xFB01);
    assert_true(lig != 0);
    size_t want = glyph_contours(face, lig);
    size_t apart = glyph_contours(face, FT_Get_Char_Index(face, 'f')) +
                   glyph_contours(face, FT_Get_Char_Index(face, 'i'));
    FT_Done_FreeType(lib);
    assert_true(want != apart);
    aa_scene *s = placed_text("text:string=fi", 32, 24);
    size_t nc;
    aa_scene_contours(s, &nc);
    printf("# fi: %zu contours in the scene, %zu in the ligature, %zu in f and i\n", nc, want,
           apart);
    assert_int_equal(nc, want);
    aa_scene_free(s);
}

/* A CFF font (Cantarell, Debian fonts-cantarell): its outlines are cubic
 * arcs.  While the scene cannot hold cubics the pattern refuses cleanly,
 * saying so; once it can, the scene has the glyphs' contours and their
 * exact ink bounds (FreeType's FT_Outline_Get_BBox). */
#define CFF_FONT "/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf"
static void test_cff(void **state)
{
    (void)state;
    FILE *f = fopen(CFF_FONT, "rb");
    if (!f) {
        printf("# skipped: no CFF font at %s (apt-get install fonts-cantarell)\n", CFF_FONT);
        skip();
    }
    fclose(f);
    int can = support_scene_holds_cubics();
    aa_spec s;
    aa_scene *sc = NULL;
    assert_int_equal(aa_pattern_parse("text:string=o,ppem=40,font=" CFF_FONT, &s), AA_OK);
    int st = aa_pattern_scene_at(&s, 64, 64, &sc);
    if (!can) {
        assert_int_equal(st, AA_EINVAL);
        assert_non_null(strstr(aa_last_error(), "cubic"));
        assert_null(sc);
        printf("# skipped: aa_scene_cubic_to refuses, and so does the CFF text (%s)\n",
               aa_last_error());
        skip();
    }
    assert_int_equal(st, AA_OK);
    FT_Library lib;
    FT_Face face;
    assert_int_equal(FT_Init_FreeType(&lib), 0);
    assert_int_equal(FT_New_Face(lib, CFF_FONT, 0, &face), 0);
    assert_int_equal(FT_Set_Char_Size(face, 0, 40 * 64, 72, 72), 0);
    size_t want = glyph_contours(face, FT_Get_Char_Index(face, 'o'));
    FT_BBox bb;
    assert_int_equal(FT_Outline_Get_BBox(&face->glyph->outline, &bb), 0);
    double baseline = 2 + FT_MulFix(face->ascender, face->size->metrics.y_scale) / 64.0;
    FT_Done_FreeType(lib);
    aa_scene *p = aa_scene_place(sc, 64, 64, 0, 0, 0);
    assert_non_null(p);
    size_t nc;
    aa_scene_contours(p, &nc);
    assert_int_equal(nc, want);
    double x0, y0, x1, y1;
    aa_scene_bounds(p, &x0, &y0, &x1, &y1);
    assert_true(fabs(x0 - (2 + bb.xMin / 64.0)) < 1e-9 && fabs(x1 - (2 + bb.xMax / 64.0)) < 1e-9);
    assert_true(fabs(y0 - (baseline - bb.yMax / 64.0)) < 1e-9 &&
                fabs(y1 - (baseline - bb.yMin / 64.0)) < 1e-9);
    aa_scene_free(p);
    aa_scene_free(sc);
}

/* The library's refusals; the command draws with the default font. */
static void test_command(void **state)
{
    (void)state;
    char out[8192], dir[4096], txt[4200];
    static const char *const refused[][2] = {{"text:font=/nonexistent.ttf", "nonexistent.ttf"},
                                             {"text:string=", "string"}};
    for (size_t k = 0; k < 2; k++) {
        aa_spec s;
        aa_scene *sc = NULL;
        int st = aa_pattern_parse(refused[k][0], &s);
        if (st == AA_OK)
            st = aa_pattern_scene_at(&s, 64, 32, &sc);
        aa_scene_free(sc);
        if (st != AA_EINVAL || !strstr(aa_last_error(), refused[k][1]))
            fail_msg("%s: status %d, \"%s\"", refused[k][0], st, aa_last_error());
    }
    assert_int_equal(support_tmpdir(dir, sizeof dir, "text"), 0);
    snprintf(txt, sizeof txt, "%s/t.txt", dir);
    const char *def[] = {"truth", "-p", "text", "-s", "256x32", "-o", txt, NULL};
    assert_int_equal(support_aabench(def, out, sizeof out), 0);
    /* commas through %2C */
    aa_spec s;
    assert_int_equal(aa_pattern_parse("text:string=a%2Cb", &s), AA_OK);
    assert_string_equal(aa_param_text(s.v[0]), "a,b");
    support_rmtree(dir);
}

/* The reference of text is a coverage: in [0, 1], grey, and its total (the
 * box reference's sum) is the ink's area, which is the same at any
 * position in the image (moving by a whole pixel). */
static void test_reference(void **state)
{
    (void)state;
    aa_image a, b;
    support_pattern_reference("text:string=fi AV,ppem=12", &(support_view){.w = 64, .h = 20}, &a,
                              NULL, NULL);
    support_pattern_reference("text:string=fi AV,ppem=12,x=3", &(support_view){.w = 64, .h = 20},
                              &b, NULL, NULL);
    double sa = 0, sb = 0;
    for (size_t k = 0; k < (size_t)3 * a.w * a.h; k++) {
        assert_true(a.v[k] >= -1e-12 && a.v[k] <= 1 + 1e-12);
        sa += a.v[k], sb += b.v[k];
    }
    assert_true(sa > 10 && fabs(sa - sb) < 1e-9 * sa);
    aa_image_free(&a);
    aa_image_free(&b);
}

SUPPORT_MAIN(NULL, NULL,
             cmocka_unit_test(test_contours_and_bounds),
             cmocka_unit_test(test_kerning),
             cmocka_unit_test(test_ligature),
             cmocka_unit_test(test_cff),
             cmocka_unit_test(test_command),
             cmocka_unit_test(test_reference))
