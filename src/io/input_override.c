/* input_override.c: the --set arguments, "section.key=value", applied in
 * order after the file: "fill.KEY=value" sets a key in every fill,
 * "fill.TITLE.KEY=value" in one; a list is "{1, 2, 3}" or "1, 2, 3"; one
 * pair of quotes around a value is dropped. Errors name the argument. */
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

static int fill_index(const mpm_config *cfg, const char *title)
{
  for (int i = 0; i < cfg->nfill; i++)
    if (strcmp(cfg->fill[i].name, title) == 0)
      return i;
  return -1;
}

static text fill_titles(const mpm_config *cfg)
{
  text t = {{0}};
  for (int i = 0; i < cfg->nfill; i++)
    mpm_io_in_addf(&t, "%s%s", i ? ", " : "", cfg->fill[i].name);
  if (cfg->nfill == 0)
    mpm_io_in_addf(&t, "the file has no fill section");
  return t;
}

/* A fill key: "fill.KEY" sets it in every fill, "fill.TITLE.KEY" in one. */
static int override_fill(in_ctx *c, mpm_config *cfg, where *w, char *rest, char *v)
{
  char *dot = strrchr(rest, '.'), *key = dot ? dot + 1 : rest;
  if (dot)
    *dot = '\0';
  w->key = mpm_io_in_find_key(S_FILL, key);
  w->title = dot ? rest : NULL;
  if (w->key < 0)
    return mpm_io_in_fail_at(c, w, "%s", mpm_io_in_unknown_key_text(S_FILL, w->title, key).s);
  if (dot) {
    w->fill = fill_index(cfg, rest);
    if (w->fill < 0)
      return mpm_io_in_fail_at(c, w, "no fill titled '%s' (allowed: %s)", mpm_io_in_show(rest).s,
                               fill_titles(cfg).s);
    return override_value(c, &cfg->fill[w->fill], w, v);
  }
  for (w->fill = 0; w->fill < cfg->nfill; w->fill++)
    if (override_value(c, &cfg->fill[w->fill], w, v) != MPM_OK)
      return MPM_EINPUT;
  return MPM_OK;
}

static int apply_override(in_ctx *c, mpm_config *cfg, int i, char *arg)
{
  where w = {.at = {0, i + 1}, .sec = -1, .key = -1, .fill = -1};
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
  if (w.sec == S_FILL)
    return override_fill(c, cfg, &w, dot + 1, v);
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
