/* input_text.c: the pieces input messages are made of (numbers as the writer
 * writes them, quoted names, allowed ranges, lists of keys and names, user
 * text cut and made printable) and the recording of the first error, in the
 * one shape of docs/input-reference.md:
 *     FILE:LINE: key 'section.key': what is wrong (allowed: ...)
 * or "--set 'section.key=value': ..." for a value from the command line. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

/* --------------------------------------------------------- message pieces */

/* Append to t, cut at its end. */
void mpm_io_in_addf(text *t, const char *fmt, ...)
{
  size_t n = strlen(t->s);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->s + n, sizeof t->s - n, fmt, ap);
  va_end(ap);
}

/* User text for a message: cut to SHOW_MAX, control characters as '?'. */
word mpm_io_in_show(const char *s)
{
  word w;
  size_t i = 0;
  for (; s[i] && i < SHOW_MAX; i++)
    w.s[i] = iscntrl((unsigned char)s[i]) ? '?' : s[i];
  if (s[i]) {
    memcpy(w.s + i, "...", 3);
    i += 3;
  }
  w.s[i] = '\0';
  return w;
}

/* v as written in messages and by the writer: integers below 1e6 in full,
 * otherwise the shortest "%g" text that reads back as v, with the exponent
 * trimmed ("1e9", "2.5e-7"). */
word mpm_io_in_num(double v)
{
  word w, r = {{0}};
  if (v == floor(v) && fabs(v) < 1e6) {
    snprintf(w.s, sizeof w.s, "%.0f", v);
    return w;
  }
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(w.s, sizeof w.s, "%.*g", prec, v);
    if (strtod(w.s, NULL) == v)
      break;
  }
  const char *e = strchr(w.s, 'e');
  if (!e)
    return w;
  size_t n = (size_t)(e - w.s) + 1;
  memcpy(r.s, w.s, n);
  const char *x = e + 1;
  if (*x == '-')
    r.s[n++] = '-';
  x += *x == '+' || *x == '-';
  while (*x == '0' && x[1])
    x++;
  memcpy(r.s + n, x, strlen(x) + 1);
  return r;
}

/* A computed value for a message, to 6 significant digits. */
word mpm_io_in_approx(double v)
{
  word w;
  snprintf(w.s, sizeof w.s, "%.6g", v);
  return mpm_io_in_num(strtod(w.s, NULL));
}

/* A name as written in an input file: double quotes, '\' '"' '$' escaped. */
word mpm_io_in_quoted(const char *s)
{
  word w;
  size_t n = 0;
  w.s[n++] = '"';
  for (; *s && n + 4 < sizeof w.s; s++) {
    if (*s == '"' || *s == '\\' || *s == '$')
      w.s[n++] = '\\';
    w.s[n++] = *s;
  }
  w.s[n++] = '"';
  w.s[n] = '\0';
  return w;
}

/* "q4", "t3", ... : the allowed names of a kind. */
text mpm_io_in_name_list(int kind)
{
  text t = {{0}};
  const char *s;
  for (int i = 0; (s = mpm_io_in_name_at(kind, i)); i++)
    mpm_io_in_addf(&t, "%s%s", i ? ", " : "", mpm_io_in_quoted(s).s);
  return t;
}

static int has_unit(const key_def *kd)
{
  return kd->unit && kd->unit[0] && strcmp(kd->unit, "-") != 0;
}

/* The allowed range of a numeric key: "1 ... 8", "> -1 and < 0.5",
 * "0, or 1e-12 ... 1e6 s". */
text mpm_io_in_range_text(const key_def *kd)
{
  text t = {{0}};
  int lo_open = kd->flags & KF_LO_OPEN, hi_open = kd->flags & KF_HI_OPEN;
  if (kd->flags & KF_ZERO_OFF)
    mpm_io_in_addf(&t, "0, or ");
  if (!lo_open && !hi_open)
    mpm_io_in_addf(&t, "%s ... %s", mpm_io_in_num(kd->lo).s, mpm_io_in_num(kd->hi).s);
  else
    mpm_io_in_addf(&t, "%s %s and %s %s", lo_open ? ">" : ">=", mpm_io_in_num(kd->lo).s,
                   hi_open ? "<" : "<=", mpm_io_in_num(kd->hi).s);
  if (has_unit(kd))
    mpm_io_in_addf(&t, " %s", kd->unit);
  return t;
}

/* What a key accepts, for "(allowed: ...)". */
text mpm_io_in_allowed_text(const key_def *kd)
{
  text t = {{0}};
  switch (kd->type) {
  case KT_BOOL:
    mpm_io_in_addf(&t, "true, false, yes, no, on, off");
    break;
  case KT_NAME:
  case KT_ENUM:
    t = mpm_io_in_name_list(kd->kind);
    break;
  case KT_PATH:
    mpm_io_in_addf(&t, "a path of 1 ... %d characters", MPM_PATH_MAX - 1);
    break;
  default:
    t = mpm_io_in_range_text(kd);
    break;
  }
  return t;
}

/* Comma-separated keys of a section (the keys of some forms of a titled
 * section if shapes != 0). */
text mpm_io_in_key_list(int sec, int shapes)
{
  text t = {{0}};
  for (int k = 0; k < NKEYS; k++)
    if (mpm_io_in_keys[k].sec == sec && (!shapes || (mpm_io_in_keys[k].shapes & shapes)))
      mpm_io_in_addf(&t, "%s%s", t.s[0] ? ", " : "", mpm_io_in_keys[k].name);
  return t;
}

text mpm_io_in_section_list(void)
{
  text t = {{0}};
  for (int s = 0; s < NSEC; s++)
    mpm_io_in_addf(&t, "%s%s", s ? ", " : "", mpm_io_in_sec_names[s]);
  return t;
}

/* --------------------------------------------------------------- failures */

static int line_of(const in_ctx *c, const where *w)
{
  if (w->at.line > 0)
    return w->at.line;
  int line = 0;
  const int t = w->sec >= 0 ? mpm_io_in_titled_of(w->sec) : -1;
  if (t >= 0 && w->item >= 0)
    line = c->item_line[t][w->item];
  else if (w->sec >= 0 && t < 0)
    line = c->sec_line[w->sec];
  return line > 0 ? line : c->eof_line;
}

static text key_name(const where *w)
{
  text t = {{0}};
  const key_def *kd = &mpm_io_in_keys[w->key];
  if (mpm_io_in_titled_of(kd->sec) >= 0 && w->title)
    mpm_io_in_addf(&t, "%s.%s.%s", mpm_io_in_sec_names[kd->sec], mpm_io_in_show(w->title).s,
                   kd->name);
  else
    mpm_io_in_addf(&t, "%s.%s", mpm_io_in_sec_names[kd->sec], kd->name);
  return t;
}

/* Messages are one line whatever the user wrote. */
void mpm_io_in_one_line(mpm_err *err)
{
  if (err)
    for (char *p = err->msg; *p; p++)
      if (iscntrl((unsigned char)*p))
        *p = '?';
}

/* Record "LOCATION: [key 'NAME': ]message" (the first error only). */
static int failv(in_ctx *c, const where *w, int with_key, const char *fmt, va_list ap)
{
  if (c->failed)
    return MPM_EINPUT;
  c->failed = 1;
  char body[MPM_ERR_MSG], place[MPM_ERR_MSG];
  vsnprintf(body, sizeof body, fmt, ap);
  if (w->at.ovr > 0)
    snprintf(place, sizeof place, "--set '%s'", mpm_io_in_show(c->ovr[w->at.ovr - 1]).s);
  else
    snprintf(place, sizeof place, "%s:%d", c->path, line_of(c, w));
  if (with_key && w->key >= 0)
    mpm_err_set(c->err, MPM_EINPUT, "%s: key '%s': %s", place, key_name(w).s, body);
  else
    mpm_err_set(c->err, MPM_EINPUT, "%s: %s", place, body);
  mpm_io_in_one_line(c->err);
  return MPM_EINPUT;
}

int mpm_io_in_fail_key(in_ctx *c, const where *w, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(c, w, 1, fmt, ap);
  va_end(ap);
  return rc;
}

int mpm_io_in_fail_at(in_ctx *c, const where *w, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(c, w, 0, fmt, ap);
  va_end(ap);
  return rc;
}

int mpm_io_in_fail_range(in_ctx *c, const where *w, const char *value)
{
  return mpm_io_in_fail_key(c, w, "value %s out of range (allowed: %s)", mpm_io_in_show(value).s,
                            mpm_io_in_range_text(&mpm_io_in_keys[w->key]).s);
}

text mpm_io_in_unknown_key_text(int sec, const char *title, const char *name)
{
  text t = {{0}};
  if (mpm_io_in_titled_of(sec) >= 0 && title)
    mpm_io_in_addf(&t, "unknown key '%s.%s.%s'", mpm_io_in_sec_names[sec],
                   mpm_io_in_show(title).s, mpm_io_in_show(name).s);
  else
    mpm_io_in_addf(&t, "unknown key '%s.%s'", mpm_io_in_sec_names[sec], mpm_io_in_show(name).s);
  mpm_io_in_addf(&t, " (allowed keys in '%s': %s)", mpm_io_in_sec_names[sec],
                 mpm_io_in_key_list(sec, 0).s);
  return t;
}
