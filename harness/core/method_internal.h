/*
 * method_internal.h: the method table's entry for the plug-in loader,
 * shared by method.c and plugin.c only.
 */
#ifndef AA_METHOD_INTERNAL_H
#define AA_METHOD_INTERNAL_H

#include "core.h"

/* Add a plug-in's method types (NULL-terminated) to the table in use;
 * `origin` names the plug-in in messages.  Refuses a type without a name,
 * summary or render, a name already in the table, more than AA_MAX_PARAMS
 * parameters, and a table that would grow past its limit; on refusal
 * nothing is added. */
int aa__method_register(const aa_method_type *const *types, const char *origin);

#endif
