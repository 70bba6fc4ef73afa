/*
 * patterns.h: the pattern types (one file each) and their table.
 */
#ifndef AA_PATTERNS_H
#define AA_PATTERNS_H

#include "core.h"

extern const aa_pattern_type aa_pattern_crow;
extern const aa_pattern_type aa_pattern_catmull;
extern const aa_pattern_type aa_pattern_slivers;
extern const aa_pattern_type aa_pattern_star;
extern const aa_pattern_type aa_pattern_feibush;
extern const aa_pattern_type aa_pattern_fence;
extern const aa_pattern_type aa_pattern_dots;
extern const aa_pattern_type aa_pattern_rings;
extern const aa_pattern_type aa_pattern_strokes;
extern const aa_pattern_type aa_pattern_zoneplate;
extern const aa_pattern_type aa_pattern_svg;
extern const aa_pattern_type aa_pattern_text;

/* Patterns drawn at the view's size (core.h, aa_pattern_scene_at): their
 * scene for a view of w x h pixels, and the lines their files add to a
 * view's cache key (aa_pattern_key). */
int aa__svg_build_at(const double *p, int w, int h, aa_scene *s);
int aa__svg_key(const double *p, char *buf, size_t len);
int aa__svg_own_size(const double *p, int *w, int *h);
int aa__text_build_at(const double *p, int w, int h, aa_scene *s);
int aa__text_key(const double *p, char *buf, size_t len);

#endif
