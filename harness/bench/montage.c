/*
 * montage.c: images side by side, each labelled, pixel for pixel.
 *
 * Tiles are copied, never resampled: a montage of antialiasing results that
 * rescaled its tiles would add moire of its own.  Labels are drawn with
 * OpenImageIO's text renderer (DejaVu Sans) above each tile.
 */
#include "bench.h"
#include "oiio.h"

#include <stdio.h>
#include <string.h>

#define GAP 8
#define FONT 13
#define LINE (FONT + 4)

/* The montage's size for n tiles of at most tw x th under `lines` lines of
 * label. */
static void montage_size(int tw, int th, size_t n, int columns, int lines, int *w, int *h)
{
    int rows = (int)((n + (size_t)columns - 1) / (size_t)columns);
    if ((size_t)columns > n)
        columns = (int)n;
    *w = columns * (tw + GAP) + GAP;
    *h = rows * (th + lines * LINE + GAP + 4) + GAP;
}

int aa_montage_check(int tw, int th, size_t n, int columns, int lines)
{
    if (n == 0 || columns < 1 || tw < 1 || th < 1 || tw > AA_MAX_SIDE || th > AA_MAX_SIDE ||
        lines < 0 || lines > AA_TILE_LINES || n > (size_t)AA_MAX_SIDE)
        return aa_fail(AA_EINVAL, "montage of %zu tiles of %dx%d in %d columns", n, tw, th,
                       columns);
    int w, h;
    montage_size(tw, th, n, columns, lines, &w, &h);
    int st = aa_size_check(w, h, 3, 1);
    return st ? aa_fail_context(st, "a montage of %zu tile%s of %dx%d in %d columns", n,
                                n == 1 ? "" : "s", tw, th, columns)
              : AA_OK;
}

int aa_montage_write(const char *path, const aa_tile *tiles, size_t n, int columns,
                     const aa_encode *enc)
{
    if (n == 0 || columns < 1)
        return aa_fail(AA_EINVAL, "montage of %zu tiles in %d columns", n, columns);
    int tw = 0, th = 0, lines = 0;
    for (size_t k = 0; k < n; k++) {
        if (tiles[k].image->c != 3)
            return aa_fail(AA_EINVAL, "montage tiles must have 3 channels");
        tw = tiles[k].image->w > tw ? tiles[k].image->w : tw;
        th = tiles[k].image->h > th ? tiles[k].image->h : th;
        int l = 0;
        while (l < AA_TILE_LINES && tiles[k].label[l])
            l++;
        lines = l > lines ? l : lines;
    }
    int st = aa_montage_check(tw, th, n, columns, lines);
    if (st)
        return st;
    if ((size_t)columns > n)
        columns = (int)n;
    int cw = tw + GAP, ch = th + lines * LINE + GAP + 4, mw, mh;
    montage_size(tw, th, n, columns, lines, &mw, &mh);
    aa_image m;
    if ((st = aa_image_alloc(&m, mw, mh, 3)))
        return st;
    for (size_t p = 0; p < (size_t)m.w * m.h * 3; p++)
        m.v[p] = 0.01; /* a dark grey ground, apart from black */
    const float white[3] = {1, 1, 1};
    for (size_t k = 0; k < n && !st; k++) {
        int x0 = GAP + (int)(k % (size_t)columns) * cw, y0 = GAP + (int)(k / (size_t)columns) * ch;
        for (int l = 0; l < AA_TILE_LINES && tiles[k].label[l] && !st; l++)
            st = aa__oiio_text(m.v, m.w, m.h, 3, x0, y0 + l * LINE, tiles[k].label[l], FONT, white);
        const aa_image *im = tiles[k].image;
        int ty = y0 + lines * LINE + 4;
        for (int j = 0; j < im->h; j++)
            memcpy(aa_pixel(&m, x0, ty + j), aa_pixel(im, 0, j), sizeof(double) * 3 * (size_t)im->w);
    }
    if (!st)
        st = aa_image_write(path, &m, enc);
    aa_image_free(&m);
    return st;
}
