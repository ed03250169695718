/* input.c: the public entry points of the input reader (io.h): the defaults
 * of every key, and a load that reads, parses, collects, overrides and checks
 * a file into mpm_config, keeping only the first error. How the reader works
 * and which file holds what: input_internal.h. */
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

void mpm_io_input_defaults(mpm_config *cfg)
{
  memset(cfg, 0, sizeof *cfg);
  for (int k = 0; k < NKEYS; k++)
    if (mpm_io_in_keys[k].sec != S_FILL)
      mpm_io_in_store_default(cfg, &mpm_io_in_keys[k]);
  for (int k = 0; k < NKEYS; k++)  /* defaults that follow another key */
    if (mpm_io_in_keys[k].flags & KF_T0X10)
      *(double *)(void *)((char *)cfg + mpm_io_in_keys[k].off) = 10.0 * cfg->material.t0;
}

static int load(in_ctx *c, const char *path, int noverrides, mpm_config *cfg)
{
  char *buf = NULL;
  size_t len = 0;
  cfg_t *root = NULL;
  int rc = mpm_io_in_read_text(path, &buf, &len, c->err);
  if (rc == MPM_OK)
    rc = mpm_io_in_parse_text(c, buf, len, &root);
  if (rc == MPM_OK)
    rc = mpm_io_in_collect(c, root, cfg);
  if (rc == MPM_OK)
    rc = mpm_io_in_apply_overrides(c, cfg, noverrides);
  if (rc == MPM_OK)
    rc = mpm_io_in_validate(c, cfg);
  if (root)
    cfg_free(root);
  free(buf);
  return rc;
}

int mpm_io_input_load(const char *path, const char *const *overrides, int noverrides,
                      mpm_config *cfg, mpm_err *err)
{
  mpm_err_clear(err);
  if (!cfg || !path || noverrides < 0 || (noverrides > 0 && !overrides))
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_input_load: invalid arguments");
  mpm_io_input_defaults(cfg);
  mpm_io_in_copy_text(cfg->source, sizeof cfg->source, path);
  in_ctx *c = calloc(1, sizeof *c);
  if (!c)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", path);
  c->self = c;
  c->path = path;
  c->ovr = overrides;
  c->err = err;
  int rc = load(c, path, noverrides, cfg);
  free(c);
  if (rc != MPM_OK) {
    mpm_io_input_defaults(cfg);
    mpm_io_in_copy_text(cfg->source, sizeof cfg->source, path);
  }
  return rc;
}
