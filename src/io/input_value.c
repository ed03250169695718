/* input_value.c: one key's value, from its text (a file or a --set) to its
 * place in mpm_config or an item's record: integers, reals, booleans, names
 * of a table, paths and lists (polygons, a body's tables), each parsed whole
 * and checked against the key's range (a list of times also for its order),
 * with the place it was set on recorded; and the defaults of the key table. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

static loc *loc_of(in_ctx *c, int key, int item)
{
  return &c->at[item < 0 ? 0 : item][key];
}

static int starts_blank(const char *s)
{
  return *s == '\0' || isspace((unsigned char)*s);
}

/* 0: ok, 1: not an integer, 2: beyond long. */
static int parse_long(const char *s, long *v)
{
  char *end;
  if (starts_blank(s))
    return 1;
  errno = 0;
  *v = strtol(s, &end, 10);
  if (*end != '\0')
    return 1;
  return errno == ERANGE ? 2 : 0;
}

/* 0: ok (possibly non-finite), 1: not a number, 2: a hexadecimal number
 * (strtod reads them, but an input is for people: decimal only). A NaN
 * with a payload, "nan(0x7ff)", is a NaN, not a hexadecimal number. */
static int parse_double(const char *s, double *v)
{
  char *end;
  if (starts_blank(s))
    return 1;
  *v = strtod(s, &end);
  if (*end != '\0')
    return 1;
  const char *digits = s + (*s == '+' || *s == '-');
  return digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X') ? 2 : 0;
}

static int same_word(const char *a, const char *b)
{
  for (; *a && *b; a++, b++)
    if (tolower((unsigned char)*a) != *b)
      return 0;
  return *a == '\0' && *b == '\0';
}

static const char *const true_words[] = {"true", "yes", "on", NULL};
static const char *const false_words[] = {"false", "no", "off", NULL};

/* 0: ok, 1: not a boolean. */
static int parse_bool(const char *s, int *v)
{
  for (int i = 0; true_words[i]; i++) {
    if (same_word(s, true_words[i]) || same_word(s, false_words[i])) {
      *v = same_word(s, true_words[i]);
      return 0;
    }
  }
  return 1;
}

static int within_range(const key_def *kd, double v)
{
  if (!isfinite(v))
    return 0;
  if ((kd->flags & KF_ZERO_OFF) && v == 0.0)
    return 1;
  if ((kd->flags & KF_LO_OPEN) ? v <= kd->lo : v < kd->lo)
    return 0;
  if ((kd->flags & KF_HI_OPEN) ? v >= kd->hi : v > kd->hi)
    return 0;
  return 1;
}

static int store_int(in_ctx *c, const where *w, const char *s, int *out)
{
  long v;
  int st = parse_long(s, &v);
  if (st == 1)
    return mpm_io_in_fail_key(c, w, "expected an integer, got '%s'", mpm_io_in_show(s).s);
  if (st == 2 || !within_range(&mpm_io_in_keys[w->key], (double)v))
    return mpm_io_in_fail_range(c, w, s);
  *out = (int)v;
  return MPM_OK;
}

static int store_real(in_ctx *c, const where *w, const char *s, double *out)
{
  double v;
  int st = parse_double(s, &v);
  if (st == 2)
    return mpm_io_in_fail_key(c, w, "'%s' is a hexadecimal number (allowed: decimal numbers "
                              "such as 1500, 0.005, 2.5e-7)", mpm_io_in_show(s).s);
  if (st)
    return mpm_io_in_fail_key(c, w, "expected a number, got '%s'", mpm_io_in_show(s).s);
  if (!within_range(&mpm_io_in_keys[w->key], v))
    return mpm_io_in_fail_range(c, w, s);
  *out = v;
  return MPM_OK;
}

static int store_bool(in_ctx *c, const where *w, const char *s, int *out)
{
  if (parse_bool(s, out))
    return mpm_io_in_fail_key(c, w, "expected true or false, got '%s' (allowed: %s)",
                              mpm_io_in_show(s).s,
                              mpm_io_in_allowed_text(&mpm_io_in_keys[w->key]).s);
  return MPM_OK;
}

void mpm_io_in_copy_text(char *dst, size_t cap, const char *s)
{
  memset(dst, 0, cap);
  memcpy(dst, s, strlen(s) < cap ? strlen(s) : cap - 1);
}

/* A name of a table: stored as text (KT_NAME) or as its enum value (KT_ENUM). */
static int store_name(in_ctx *c, const where *w, const char *s, char *out)
{
  const key_def *kd = &mpm_io_in_keys[w->key];
  int v = strlen(s) < MPM_NAME_MAX ? mpm_io_in_name_value(kd->kind, s) : -1;
  if (v < 0)
    return mpm_io_in_fail_key(c, w, "unknown value '%s' (allowed: %s)", mpm_io_in_show(s).s,
                              mpm_io_in_name_list(kd->kind).s);
  if (kd->type == KT_ENUM)
    *(int *)out = v;
  else
    mpm_io_in_copy_text(out, MPM_NAME_MAX, s);
  return MPM_OK;
}

static int store_path(in_ctx *c, const where *w, const char *s, char *out)
{
  size_t n = strlen(s);
  if (n == 0 || n >= MPM_PATH_MAX)
    return mpm_io_in_fail_key(c, w, "%zu characters (allowed: a path of 1 ... %d characters)", n,
                              MPM_PATH_MAX - 1);
  for (const char *p = s; *p; p++)
    if (iscntrl((unsigned char)*p))
      return mpm_io_in_fail_key(c, w,
                                "'%s' contains a control character (allowed: printable characters)",
                                mpm_io_in_show(s).s);
  mpm_io_in_copy_text(out, MPM_PATH_MAX, s);
  return MPM_OK;
}

/* Parse s as the value of key w->key into rec (mpm_config, or the record of
 * item w->item of a titled section). */
int mpm_io_in_store_value(in_ctx *c, void *rec, const where *w, const char *s)
{
  const key_def *kd = &mpm_io_in_keys[w->key];
  char *p = (char *)rec + kd->off;
  int rc = MPM_EINPUT;
  switch (kd->type) {
  case KT_INT: rc = store_int(c, w, s, (int *)(void *)p); break;
  case KT_REAL: rc = store_real(c, w, s, (double *)(void *)p); break;
  case KT_BOOL: rc = store_bool(c, w, s, (int *)(void *)p); break;
  case KT_NAME:
  case KT_ENUM: rc = store_name(c, w, s, p); break;
  case KT_PATH: rc = store_path(c, w, s, p); break;
  default: break;
  }
  if (rc == MPM_OK)
    *loc_of(c, w->key, w->item) = w->at;
  return rc;
}

/* A list's values in increasing order (KF_RISING): the first that is not
 * larger than the one before is refused at its own place. */
static int check_rising(in_ctx *c, const where *w, const double *v, const char *const *vals,
                        const loc *locs, int n)
{
  for (int i = 1; i < n; i++)
    if (!(v[i] > v[i - 1])) {
      where e = *w;
      e.at = locs[i];
      return mpm_io_in_fail_key(c, &e, "value %s is not larger than the one before it, %s "
                                "(allowed: strictly increasing values)",
                                mpm_io_in_show(vals[i]).s, mpm_io_in_show(vals[i - 1]).s);
    }
  return MPM_OK;
}

/* A list (polygon coordinates, a body's times or velocities): n values,
 * each with its own location. */
int mpm_io_in_store_list(in_ctx *c, void *rec, const where *w, const char *const *vals,
                         const loc *locs, int n)
{
  const key_def *kd = &mpm_io_in_keys[w->key];
  double *arr = (double *)(void *)((char *)rec + kd->off);
  if (n > MPM_MAX_POLY) {
    where e = *w;
    e.at = locs[MPM_MAX_POLY];
    if (strcmp(kd->name, "x") == 0 || strcmp(kd->name, "y") == 0)  /* a polygon's */
      return mpm_io_in_fail_key(c, &e, "more than %d values (allowed: 3 ... %d vertices)",
                                MPM_MAX_POLY, MPM_MAX_POLY);
    return mpm_io_in_fail_key(c, &e, "more than %d values (allowed: at most %d values)",
                              MPM_MAX_POLY, MPM_MAX_POLY);
  }
  memset(arr, 0, MPM_MAX_POLY * sizeof *arr);
  for (int i = 0; i < n; i++) {
    where e = *w;
    e.at = locs[i];
    if (store_real(c, &e, vals[i], &arr[i]) != MPM_OK)
      return MPM_EINPUT;
  }
  if ((kd->flags & KF_RISING) && check_rising(c, w, arr, vals, locs, n) != MPM_OK)
    return MPM_EINPUT;
  c->nlist[w->item < 0 ? 0 : w->item][w->key] = n;
  *loc_of(c, w->key, w->item) = n > 0 ? locs[0] : w->at;
  return MPM_OK;
}

void mpm_io_in_store_default(void *rec, const key_def *kd)
{
  char *p = (char *)rec + kd->off;
  switch (kd->type) {
  case KT_INT:
  case KT_BOOL: *(int *)(void *)p = (int)kd->def; break;
  case KT_REAL: *(double *)(void *)p = kd->def; break;
  case KT_NAME:
    mpm_io_in_copy_text(p, MPM_NAME_MAX, kd->sdef);
    break;
  case KT_ENUM:
    *(int *)(void *)p = mpm_io_in_name_value(kd->kind, kd->sdef);
    break;
  case KT_PATH:
    mpm_io_in_copy_text(p, MPM_PATH_MAX, kd->sdef);
    break;
  default: break;
  }
}
