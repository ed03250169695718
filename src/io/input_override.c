/* input_override.c: the --set arguments, "section.key=value", applied in
 * order after the file: in a titled section "fill.KEY=value" sets a key in
 * every fill, "fill.TITLE.KEY=value" in one (bodies alike); a list is
 * "{1, 2, 3}" or "1, 2, 3"; one pair of quotes around a value is dropped.
 * Errors name the argument. */
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"
#include "io/text.h"

/* One pair of matching quotes around a --set value is dropped. */
static char *unquote(char *v)
{
  size_t n = strlen(v);
  if (n >= 2 && (v[0] == '"' || v[0] == '\'') && v[n - 1] == v[0]) {
    v[n - 1] = '\0';
    return v + 1;
  }
  return v;
}

/* "{1, 2, 3}" or "1, 2, 3" from a --set. */
static int override_list(in_ctx *c, void *rec, const where *w, char *v)
{
  const char *vals[MPM_MAX_POLY + 1];
  loc locs[MPM_MAX_POLY + 1];
  size_t n = strlen(v);
  if (n >= 2 && v[0] == '{' && v[n - 1] == '}') {
    v[n - 1] = '\0';
    v++;
  }
  int count = 0;
  for (char *p = v; count <= MPM_MAX_POLY;) {
    char *comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    vals[count] = unquote(mpm_io_text_trim(p));
    locs[count++] = w->at;
    if (!comma)
      break;
    p = comma + 1;
  }
  if (count == 1 && vals[0][0] == '\0')
    count = 0;
  return mpm_io_in_store_list(c, rec, w, vals, locs, count);
}

static int override_value(in_ctx *c, void *rec, const where *w, char *v)
{
  char *copy = malloc(strlen(v) + 1);
  if (!copy)
    return mpm_err_set(c->err, MPM_ENOMEM, "--set: out of memory");
  strcpy(copy, v);
  int rc = mpm_io_in_keys[w->key].type == KT_LIST ? override_list(c, rec, w, copy)
                                                  : mpm_io_in_store_value(c, rec, w, unquote(copy));
  free(copy);
  return rc;
}

static int item_index(const mpm_config *cfg, int t, const char *title)
{
  for (int i = 0; i < mpm_io_in_count_of(cfg, t); i++)
    if (strcmp(mpm_io_in_title(cfg, t, i), title) == 0)
      return i;
  return -1;
}

static text item_titles(const mpm_config *cfg, int t)
{
  text s = {{0}};
  const int n = mpm_io_in_count_of(cfg, t);
  for (int i = 0; i < n; i++)
    mpm_io_in_addf(&s, "%s%s", i ? ", " : "", mpm_io_in_title(cfg, t, i));
  if (n == 0)
    mpm_io_in_addf(&s, "the file has no %s section", mpm_io_in_sec_names[mpm_io_in_titled[t].sec]);
  return s;
}

/* A key of titled section t: "fill.KEY" sets it in every fill,
 * "fill.TITLE.KEY" in one. */
static int override_item(in_ctx *c, mpm_config *cfg, int t, where *w, char *rest, char *v)
{
  const char *sec = mpm_io_in_sec_names[w->sec];
  char *dot = strrchr(rest, '.'), *key = dot ? dot + 1 : rest;
  if (dot)
    *dot = '\0';
  w->key = mpm_io_in_find_key(w->sec, key);
  w->title = dot ? rest : NULL;
  if (w->key < 0)
    return mpm_io_in_fail_at(c, w, "%s", mpm_io_in_unknown_key_text(w->sec, w->title, key).s);
  if (dot) {
    w->item = item_index(cfg, t, rest);
    if (w->item < 0)
      return mpm_io_in_fail_at(c, w, "no %s titled '%s' (allowed: %s)", sec,
                               mpm_io_in_show(rest).s, item_titles(cfg, t).s);
    return override_value(c, mpm_io_in_item(cfg, t, w->item), w, v);
  }
  for (w->item = 0; w->item < mpm_io_in_count_of(cfg, t); w->item++)
    if (override_value(c, mpm_io_in_item(cfg, t, w->item), w, v) != MPM_OK)
      return MPM_EINPUT;
  return MPM_OK;
}

static int apply_override(in_ctx *c, mpm_config *cfg, int i, char *arg)
{
  where w = {.at = {0, i + 1}, .sec = -1, .key = -1, .item = -1};
  char *eq = strchr(arg, '=');
  if (!eq)
    return mpm_io_in_fail_at(c, &w, "expected section.key=value");
  *eq = '\0';
  char *name = mpm_io_text_trim(arg), *v = mpm_io_text_trim(eq + 1), *dot = strchr(name, '.');
  if (!dot)
    return mpm_io_in_fail_at(c, &w, "'%s' is not section.key (allowed sections: %s)",
                             mpm_io_in_show(name).s, mpm_io_in_section_list().s);
  *dot = '\0';
  w.sec = mpm_io_in_find_section(name);
  if (w.sec < 0)
    return mpm_io_in_fail_at(c, &w, "unknown section '%s' (allowed: %s)", mpm_io_in_show(name).s,
                             mpm_io_in_section_list().s);
  const int t = mpm_io_in_titled_of(w.sec);
  if (t >= 0)
    return override_item(c, cfg, t, &w, dot + 1, v);
  w.key = mpm_io_in_find_key(w.sec, dot + 1);
  if (w.key < 0)
    return mpm_io_in_fail_at(c, &w, "%s", mpm_io_in_unknown_key_text(w.sec, NULL, dot + 1).s);
  return override_value(c, cfg, &w, v);
}

int mpm_io_in_apply_overrides(in_ctx *c, mpm_config *cfg, int n)
{
  for (int i = 0; i < n; i++) {
    if (!c->ovr[i])
      return mpm_err_set(c->err, MPM_EINVAL, "--set number %d is missing", i + 1);
    char *arg = malloc(strlen(c->ovr[i]) + 1);
    if (!arg)
      return mpm_err_set(c->err, MPM_ENOMEM, "--set: out of memory");
    strcpy(arg, c->ovr[i]);
    int rc = apply_override(c, cfg, i, arg);
    free(arg);
    if (rc != MPM_OK)
      return rc;
  }
  return MPM_OK;
}
