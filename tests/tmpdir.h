/* tmpdir.h: a fresh directory for a test's files and its removal, shared by
 * the tests that write runs (test_output, test_output3). The including file
 * defines _XOPEN_SOURCE 700 (mkdtemp, nftw) before any system header. */
#ifndef MPM_TESTS_TMPDIR_H
#define MPM_TESTS_TMPDIR_H

#include <check.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>

#define DIR_MAX 256

/* A fresh directory $TMPDIR/gm-NAME-XXXXXX (default /tmp) into dir[DIR_MAX]. */
static inline void make_tmpdir_named(char *dir, const char *name)
{
  const char *base = getenv("TMPDIR");
  snprintf(dir, DIR_MAX, "%s/gm-%s-XXXXXX", base && *base ? base : "/tmp", name);
  ck_assert_ptr_nonnull(mkdtemp(dir));
}

static inline int tmpdir_rm_entry(const char *path, const struct stat *st, int flag,
                                  struct FTW *ftw)
{
  (void)st;
  (void)flag;
  (void)ftw;
  return remove(path);
}

/* Remove dir and everything below it. */
static inline void remove_tree(const char *dir)
{
  nftw(dir, tmpdir_rm_entry, 16, FTW_DEPTH | FTW_PHYS);
}

#endif
