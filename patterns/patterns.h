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
extern const aa_pattern_type aa_pattern_zoneplate;

#endif
