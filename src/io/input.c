/* input.c: the public entry points of the input reader (io.h): the defaults
 * of every key, and a load that reads, parses, collects, overrides and checks
 * a file (or a text) into mpm_config, keeping only the first error; the
 * loaded input can be kept with where each value came from, so that checks
 * made after the load report in the same shape. How the reader works and
 * which file holds what: input_internal.h. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

void mpm_io_input_defaults(mpm_config *cfg)
{
  memset(cfg, 0, sizeof *cfg);
  for (int k = 0; k < NKEYS; k++)
    if (mpm_io_in_titled_of(mpm_io_in_keys[k].sec) < 0)
      mpm_io_in_store_default(cfg, &mpm_io_in_keys[k]);
  for (int k = 0; k < NKEYS; k++)  /* defaults that follow another key */
    if (mpm_io_in_keys[k].flags & KF_T0X10)
      *(double *)(void *)((char *)cfg + mpm_io_in_keys[k].off) = 10.0 * cfg->material.t0;
}

struct mpm_io_input {
  in_ctx *c;       /* the parse context, with where every key was set */
  char *path;      /* the name c->path points to */
};

/* Parse buf (len bytes, NUL-terminated, modified) into cfg. */
static int load(in_ctx *c, char *buf, size_t len, int noverrides, mpm_config *cfg)
{
  cfg_t *root = NULL;
  int rc = mpm_io_in_parse_text(c, buf, len, &root);
  if (rc == MPM_OK)
    rc = mpm_io_in_collect(c, root, cfg);
  if (rc == MPM_OK)
    rc = mpm_io_in_apply_overrides(c, cfg, noverrides);
  if (rc == MPM_OK)
    rc = mpm_io_in_validate(c, cfg);
  if (root)
    cfg_free(root);
  return rc;
}

void mpm_io_input_free(mpm_io_input *in)
{
  if (!in)
    return;
  free(in->c);
  free(in->path);
  free(in);
}

/* Open from a file (content NULL) or from content named `name`. */
static int open_input(mpm_io_input **out, const char *name, const char *content,
                      const char *const *overrides, int noverrides, mpm_config *cfg, mpm_err *err)
{
  mpm_err_clear(err);
  if (out)
    *out = NULL;
  if (!out || !cfg || !name || noverrides < 0 || (noverrides > 0 && !overrides))
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_input_load: invalid arguments");
  mpm_io_input_defaults(cfg);
  mpm_io_in_copy_text(cfg->source, sizeof cfg->source, name);
  mpm_io_input *in = calloc(1, sizeof *in);
  char *buf = NULL;
  size_t len = 0;
  if (!in || !(in->c = calloc(1, sizeof *in->c)) || !(in->path = malloc(strlen(name) + 1))) {
    mpm_io_input_free(in);
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", name);
  }
  strcpy(in->path, name);
  in_ctx *c = in->c;
  c->self = c;
  c->path = in->path;
  c->ovr = overrides;
  c->err = err;
  int rc = MPM_OK;
  if (content) {
    len = strlen(content);
    if (!(buf = malloc(len + 1)))
      rc = mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", name);
    else
      memcpy(buf, content, len + 1);
  } else {
    rc = mpm_io_in_read_text(name, &buf, &len, err);
  }
  if (rc == MPM_OK)
    rc = load(c, buf, len, noverrides, cfg);
  free(buf);
  if (rc != MPM_OK) {
    mpm_io_input_free(in);
    mpm_io_input_defaults(cfg);
    mpm_io_in_copy_text(cfg->source, sizeof cfg->source, name);
    return rc;
  }
  *out = in;
  return MPM_OK;
}

int mpm_io_input_open(mpm_io_input **in, const char *path, const char *const *overrides,
                      int noverrides, mpm_config *cfg, mpm_err *err)
{
  return open_input(in, path, NULL, overrides, noverrides, cfg, err);
}

int mpm_io_input_open_text(mpm_io_input **in, const char *name, const char *content,
                           const char *const *overrides, int noverrides, mpm_config *cfg,
                           mpm_err *err)
{
  if (!content)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_input_open_text: no text");
  return open_input(in, name, content, overrides, noverrides, cfg, err);
}

int mpm_io_input_load(const char *path, const char *const *overrides, int noverrides,
                      mpm_config *cfg, mpm_err *err)
{
  mpm_io_input *in = NULL;
  int rc = open_input(&in, path, NULL, overrides, noverrides, cfg, err);
  mpm_io_input_free(in);
  return rc;
}

/* "section.key" or "fill.TITLE.key" (any titled section) of cfg as a place
 * in the key table; 0 when it names no key. */
static int find_place(const mpm_config *cfg, const char *name, where *w)
{
  char buf[3 * MPM_NAME_MAX + 8];
  snprintf(buf, sizeof buf, "%s", name);
  char *dot = strchr(buf, '.'), *last = strrchr(buf, '.');
  if (!dot)
    return 0;
  *dot = '\0';
  w->sec = mpm_io_in_find_section(buf);
  w->item = -1;
  w->title = NULL;
  const int t = w->sec >= 0 ? mpm_io_in_titled_of(w->sec) : -1;
  if (t >= 0) {
    if (last == dot)
      return 0;
    *last = '\0';
    for (int i = 0; i < mpm_io_in_count_of(cfg, t); i++)
      if (strcmp(mpm_io_in_title(cfg, t, i), dot + 1) == 0)
        w->item = i;
    if (w->item < 0)
      return 0;
    w->title = mpm_io_in_title(cfg, t, w->item);
  } else if (w->sec < 0 || last != dot) {
    return 0;
  }
  w->key = mpm_io_in_find_key(w->sec, last + 1);
  return w->key >= 0;
}

int mpm_io_input_fail(mpm_io_input *in, const mpm_config *cfg, const char *key, mpm_err *err,
                      const char *fmt, ...)
{
  where w = {.sec = -1, .key = -1, .item = -1};
  char body[MPM_ERR_MSG];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(body, sizeof body, fmt, ap);
  va_end(ap);
  if (!in || !cfg || !find_place(cfg, key, &w))
    return mpm_err_set(err, MPM_EINPUT, "%s: key '%s': %s", cfg ? cfg->source : "?", key, body);
  in_ctx *c = in->c;
  w.at = c->at[w.item < 0 ? 0 : w.item][w.key];
  c->err = err;
  c->failed = 0;
  return mpm_io_in_fail_key(c, &w, "%s", body);
}
