/*
 * agg.h: the C face of the AGG peer (agg.cpp, C++ inside).
 *
 * The method type is defined in C++ with C linkage; nothing else of
 * agg.cpp is visible, and no C++ exception leaves it (each entry catches
 * everything and returns a status, as harness/core/oiio.cpp does).
 */
#ifndef AA_AGG_H
#define AA_AGG_H

#include "aabench.h"

#ifdef __cplusplus
extern "C" {
#endif

extern const aa_method_type aa_method_agg;

#ifdef __cplusplus
}
#endif

#endif
