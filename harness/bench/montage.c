/*
 * montage.c: images side by side, each labelled, pixel for pixel.
 *
 * Tiles are copied, never resampled: a montage of antialiasing results that
 * rescaled its tiles would add moire of its own.  Labels are drawn with
 * OpenImageIO's text renderer (DejaVu Sans) above each tile.
 *
 * A montage can be far larger than any of its tiles (16 methods at 2048 x
 * 2048 are 4 GB of doubles), so it is never held whole: it is made one row
 * of cells at a time, in a band as wide as the montage and as tall as a
 * cell, which is written to the file (aa_image_out_rows) before the next
 * row is drawn.  The tiles come from a source one at a time, each given
 * back once copied, so a caller can read each from its file when it is
 * asked for.  A cell's labels and tile stay inside its band, so drawing
 * band by band gives the same pixels as drawing the whole montage.
 */
#include "bench.h"
#include "oiio.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GAP 8
#define FONT 13
#define LINE (FONT + 4)
/* A cell is at least this wide, so that a label of about 16 characters
 * ("RMSE 1.234e-02") shows whole beside small tiles; a longer one is cut at
 * its cell's side, never drawn over the next cell. */
#define LABEL_W 120

/* The dark grey ground, apart from black. */
#define GROUND 0.01

typedef struct layout {
    int columns, rows; /* cells */
    int cw, ch;        /* a cell, with the gap to its right and below */
    int w, h;          /* the montage */
} layout;

static int make_layout(size_t n, int columns, int tw, int th, int lines, layout *l)
{
    if (n == 0 || columns < 1 || tw < 1 || th < 1 || lines < 0 || lines > AA_TILE_LINES)
        return aa_fail(AA_EINVAL, "montage of %zu tiles of %dx%d in %d columns", n, tw, th,
                       columns);
    if (n > (size_t)AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "montage of %zu tiles: too many", n);
    l->rows = (int)((n + (size_t)columns - 1) / (size_t)columns);
    l->columns = (size_t)columns > n ? (int)n : columns;
    l->cw = (tw > LABEL_W ? tw : LABEL_W) + GAP;
    l->ch = th + lines * LINE + GAP + 4;
    double w = (double)l->columns * l->cw + GAP, h = (double)l->rows * l->ch + GAP;
    if (w > AA_MAX_SIDE || h > AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "montage of %zu tiles of %dx%d in %d columns would be %.0fx%.0f "
                       "pixels: a side is above %d", n, tw, th, l->columns, w, h, AA_MAX_SIDE);
    l->w = (int)w, l->h = (int)h;
    return AA_OK;
}

double aa_montage_bytes(size_t n, int columns, int tw, int th, int lines)
{
    layout l;
    if (make_layout(n, columns, tw, th, lines, &l) != AA_OK)
        return 0;
    /* the band of doubles, its 8-bit codes for a PNG, one tile and a label's
     * line */
    double band = (double)l.w * (l.ch + GAP) * 3;
    return band * sizeof(double) + band + (double)tw * th * 3 * sizeof(double) +
           (double)l.cw * LINE * 3 * sizeof(double);
}

int aa_montage_check(size_t n, int columns, int tw, int th, int lines)
{
    layout l;
    int st = make_layout(n, columns, tw, th, lines, &l);
    if (st)
        return st;
    char what[128];
    snprintf(what, sizeof what, "a montage of %zu tiles of %dx%d (%dx%d pixels, drawn a row at "
             "a time)", n, tw, th, l.w, l.h);
    return aa_memory_check(aa_montage_bytes(n, columns, tw, th, lines), what);
}

/* Draw tile k (labels, then the image) into the band of its row, whose top
 * is GAP above the cell. */
static int draw_cell(const aa_tile_source *src, const layout *l, size_t k, aa_image *band)
{
    aa_tile tile = {0};
    int st = src->get(src->ctx, k, &tile);
    if (st)
        return st;
    const aa_image *im = tile.image;
    const float white[3] = {1, 1, 1};
    int x0 = GAP + (int)(k % (size_t)l->columns) * l->cw, y0 = GAP;
    if (im == NULL || im->c != 3 || im->w > src->tw ||
        im->h > l->ch - GAP - 4 - src->lines * LINE)
        st = aa_fail(AA_EINVAL, "montage tile %zu: %dx%dx%d, where tiles of at most %dx%dx3 were "
                     "announced", k, im ? im->w : 0, im ? im->h : 0, im ? im->c : 0,
                     src->tw, l->ch - GAP - 4 - src->lines * LINE);
    /* each label drawn on the cell's width alone, then copied: cut there */
    aa_image line = {0};
    if (!st && src->lines > 0 && tile.label[0])
        st = aa_image_alloc(&line, l->cw - GAP, LINE, 3);
    for (int j = 0; j < src->lines && tile.label[j] && !st; j++) {
        for (size_t p = 0; p < (size_t)line.w * LINE * 3; p++)
            line.v[p] = GROUND;
        st = aa__oiio_text(line.v, line.w, line.h, 3, 0, 0, tile.label[j], FONT, white);
        for (int r = 0; r < LINE && !st; r++)
            memcpy(aa_pixel(band, x0, y0 + j * LINE + r), aa_pixel(&line, 0, r),
                   sizeof(double) * 3 * (size_t)line.w);
    }
    aa_image_free(&line);
    int ty = y0 + src->lines * LINE + 4;
    for (int j = 0; j < (im ? im->h : 0) && !st; j++)
        memcpy(aa_pixel(band, x0, ty + j), aa_pixel(im, 0, j), sizeof(double) * 3 * (size_t)im->w);
    if (src->put)
        src->put(src->ctx, k);
    return st;
}

int aa_montage_stream(const char *path, const aa_tile_source *src, int columns,
                      const aa_encode *enc)
{
    layout l;
    int st = make_layout(src->n, columns, src->tw, src->th, src->lines, &l);
    if (st)
        return st;
    char what[128];
    snprintf(what, sizeof what, "the montage %s (%dx%d pixels, drawn a row at a time)", path, l.w,
             l.h);
    /* the band and its codes; the caller counts its tiles */
    double band_values = (double)l.w * (l.ch + GAP) * 3;
    if ((st = aa_memory_check(band_values * (sizeof(double) + 1), what)))
        return st;
    aa_image band = {0};
    aa_image_out *out = NULL;
    if ((st = aa_image_alloc(&band, l.w, l.ch + GAP, 3)) ||
        (st = aa_image_out_begin(path, l.w, l.h, 3, enc, &out))) {
        aa_image_free(&band);
        return st;
    }
    for (int r = 0; r < l.rows && !st; r++) {
        /* row r's cells start at GAP + r ch; its band at r ch, and the last
         * band takes the gap below the last row too */
        int rows = l.ch + (r == l.rows - 1 ? GAP : 0);
        band.h = rows;
        for (size_t p = 0; p < (size_t)l.w * (size_t)rows * 3; p++)
            band.v[p] = GROUND;
        for (int c = 0; c < l.columns && !st; c++) {
            size_t k = (size_t)r * (size_t)l.columns + (size_t)c;
            if (k < src->n)
                st = draw_cell(src, &l, k, &band);
        }
        if (!st)
            st = aa_image_out_rows(out, band.v, rows);
    }
    if (st)
        aa_image_out_abort(out);
    else
        st = aa_image_out_finish(out);
    aa_image_free(&band);
    return st;
}

/* ---- a montage of tiles all in memory ---- */

typedef struct array_source {
    const aa_tile *tiles;
} array_source;

static int array_get(void *ctx, size_t k, aa_tile *tile)
{
    *tile = ((const array_source *)ctx)->tiles[k];
    return AA_OK;
}

int aa_montage_write(const char *path, const aa_tile *tiles, size_t n, int columns,
                     const aa_encode *enc)
{
    if (n == 0 || columns < 1)
        return aa_fail(AA_EINVAL, "montage of %zu tiles in %d columns", n, columns);
    array_source as = {tiles};
    aa_tile_source src = {.n = n, .get = array_get, .ctx = &as};
    for (size_t k = 0; k < n; k++) {
        if (tiles[k].image->c != 3)
            return aa_fail(AA_EINVAL, "montage tiles must have 3 channels");
        src.tw = tiles[k].image->w > src.tw ? tiles[k].image->w : src.tw;
        src.th = tiles[k].image->h > src.th ? tiles[k].image->h : src.th;
        int l = 0;
        while (l < AA_TILE_LINES && tiles[k].label[l])
            l++;
        src.lines = l > src.lines ? l : src.lines;
    }
    return aa_montage_stream(path, &src, columns, enc);
}
