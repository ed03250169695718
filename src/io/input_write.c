/* input_write.c: the fully resolved input (every key, defaults included) in
 * input-file syntax, as stored with a run; reading it back gives the same
 * mpm_config. Numbers are written as in messages (the shortest text that reads
 * back exactly), names and paths quoted. */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

static void write_list(FILE *f, const double *v, int n)
{
  fputc('{', f);
  for (int i = 0; i < n; i++)
    fprintf(f, "%s%s", i ? ", " : "", mpm_io_in_num(v[i]).s);
  fputc('}', f);
}

/* The number of values of list kd in rec, within 0 ... MPM_MAX_POLY. */
static int list_count(const void *rec, const key_def *kd)
{
  const int n = *(const int *)(const void *)((const char *)rec + kd->noff);
  return n < 0 ? 0 : n > MPM_MAX_POLY ? MPM_MAX_POLY : n;
}

static void write_key(FILE *f, const void *rec, const key_def *kd)
{
  const char *p = (const char *)rec + kd->off;
  const char *name;
  fprintf(f, "  %s = ", kd->name);
  switch (kd->type) {
  case KT_INT: fprintf(f, "%d", *(const int *)(const void *)p); break;
  case KT_REAL:
    fputs(mpm_io_in_num(*(const double *)(const void *)p).s, f);
    break;
  case KT_BOOL: fputs(*(const int *)(const void *)p ? "true" : "false", f); break;
  case KT_ENUM:
    name = mpm_io_in_name_at(kd->kind, *(const int *)(const void *)p);
    fputs(mpm_io_in_quoted(name ? name : "?").s, f);
    break;
  case KT_LIST: write_list(f, (const double *)(const void *)p, list_count(rec, kd)); break;
  default:
    fputs(mpm_io_in_quoted(p).s, f);
    break;  /* names and paths */
  }
  fputc('\n', f);
}

/* Paths can be longer than a text: written directly, escaped the same way. */
static void write_path(FILE *f, const char *s)
{
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"' || *s == '\\' || *s == '$')
      fputc('\\', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

/* 1 for the gravity keys that the resolved input leaves out: gx, gy when
 * gravity came as angle and g (they are derived), angle and g otherwise. */
static int derived_key(const mpm_config *cfg, const key_def *kd)
{
  if (kd->sec != S_GRAVITY)
    return 0;
  const int polar = strcmp(kd->name, "angle") == 0 || strcmp(kd->name, "g") == 0;
  const int cart = strcmp(kd->name, "gx") == 0 || strcmp(kd->name, "gy") == 0;
  return cfg->gravity.use_angle ? cart : polar;
}

static void write_section(FILE *f, const mpm_config *cfg, int s)
{
  fprintf(f, "%s {\n", mpm_io_in_sec_names[s]);
  for (int k = 0; k < NKEYS; k++) {
    if (mpm_io_in_keys[k].sec != s || derived_key(cfg, &mpm_io_in_keys[k]) ||
        ((mpm_io_in_keys[k].flags & KF_3D) && cfg->mesh.nz == 0))
      continue;
    if (mpm_io_in_keys[k].type == KT_PATH) {
      fprintf(f, "  %s = ", mpm_io_in_keys[k].name);
      write_path(f, (const char *)cfg + mpm_io_in_keys[k].off);
      fputc('\n', f);
    } else {
      write_key(f, cfg, &mpm_io_in_keys[k]);
    }
  }
  fputs("}\n", f);
}

/* Item i of titled section t with the keys of its form only (a fill
 * cylinder: its axis, the span along it and the centre across it), and the
 * 3D keys in a 3D run. */
static void write_item(FILE *f, const mpm_config *cfg, int t, int i)
{
  const void *rec = mpm_io_in_item_of(cfg, t, i);
  const char *sec = mpm_io_in_sec_names[mpm_io_in_titled[t].sec];
  const char *title = mpm_io_in_title(cfg, t, i);
  const int dim3 = cfg->mesh.nz > 0;
  if (mpm_io_in_valid_title(title))
    fprintf(f, "%s %s {\n", sec, title);
  else
    fprintf(f, "%s %s%d {\n", sec, sec, i + 1);
  const int form = mpm_io_in_item_form(t, rec, dim3);
  for (int k = 0; k < NKEYS; k++) {
    const key_def *kd = &mpm_io_in_keys[k];
    if (kd->sec == mpm_io_in_titled[t].sec && (!kd->shapes || (kd->shapes & form)) &&
        (dim3 || !(kd->flags & KF_3D)))
      write_key(f, rec, kd);
  }
  fputs("}\n", f);
}

int mpm_io_input_write(FILE *f, const mpm_config *cfg)
{
  if (!f || !cfg)
    return MPM_EINVAL;
  fputs("# granmpm input, fully resolved", f);
  if (cfg->source[0]) {
    fputs(" from ", f);
    for (const char *p = cfg->source; *p && p < cfg->source + MPM_PATH_MAX; p++)
      fputc(iscntrl((unsigned char)*p) ? '?' : *p, f);
  }
  fputc('\n', f);
  for (int s = 0; s < NSEC; s++) {
    const int t = mpm_io_in_titled_of(s);
    if (t < 0)
      write_section(f, cfg, s);
    else
      for (int i = 0; i < mpm_io_in_count_of(cfg, t) && i < mpm_io_in_titled[t].max; i++)
        write_item(f, cfg, t, i);
  }
  return ferror(f) ? MPM_EIO : MPM_OK;
}

char *mpm_io_input_text(const mpm_config *cfg)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f)
    return NULL;
  const int rc = mpm_io_input_write(f, cfg);
  if (fclose(f) != 0 || rc != MPM_OK) {
    free(buf);
    return NULL;
  }
  return buf;
}
