/* names.h: the one idiom for enum <-> name tables.
 *
 * Each module that owns an enum keeps one `static const char *const` table of
 * its names, indexed by the enum value, and exports `_from_name` and `_name`
 * built on these two helpers, so the input parser, the output writer and the
 * modules read the same table. */
#ifndef MPM_CORE_NAMES_H
#define MPM_CORE_NAMES_H

#include <string.h>

/* Index of s in table[0 .. n), -1 if absent (or s is NULL). */
static inline int mpm_names_index(const char *const *table, int n, const char *s)
{
  for (int i = 0; s && i < n; i++)
    if (strcmp(table[i], s) == 0)
      return i;
  return -1;
}

/* table[i] for 0 <= i < n, NULL otherwise. */
static inline const char *mpm_names_at(const char *const *table, int n, int i)
{
  return i >= 0 && i < n ? table[i] : NULL;
}

#define MPM_NAMES_COUNT(table) ((int)(sizeof(table) / sizeof((table)[0])))

#endif
