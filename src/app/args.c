/* args.c: argument reading and failure reports shared by the granmpm
 * commands (args.h). */
#include "app/args.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mpm_app_usage(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fputs("granmpm: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputs(" (see 'granmpm --help')\n", stderr);
  va_end(ap);
  return MPM_APP_EXIT_USAGE;
}

int mpm_app_fail(const mpm_err *err)
{
  fprintf(stderr, "granmpm: %s\n", err->msg);
  return err->code == MPM_EINPUT || err->code == MPM_EIO ? MPM_APP_EXIT_USAGE
                                                         : MPM_APP_EXIT_RUNTIME;
}

int mpm_app_arg_real(const char *s, double *v)
{
  char *end;
  *v = strtod(s, &end);
  return *s != '\0' && *end == '\0' && isfinite(*v) && !strpbrk(s, "xX");  /* decimal only */
}

int mpm_app_arg_pair(const char *s, double *a, double *b)
{
  char buf[128];
  const char *c = strchr(s, ':');
  if (!c || (size_t)(c - s) >= sizeof buf)
    return 0;
  memcpy(buf, s, (size_t)(c - s));
  buf[c - s] = '\0';
  return mpm_app_arg_real(buf, a) && mpm_app_arg_real(c + 1, b) && *a < *b;
}

int mpm_app_arg_int(const char *s, int lo, int hi, int *v)
{
  double d;
  if (!mpm_app_arg_real(s, &d) || d < lo || d > hi || d != floor(d))
    return 0;
  *v = (int)d;
  return 1;
}

int mpm_app_arg_frame(const char *cmd, const char *v, int *frame)
{
  if (strcmp(v, "last") == 0)
    *frame = -1;
  else if (!mpm_app_arg_int(v, 0, 1000000000, frame))
    return mpm_app_usage("%s: --frame expects a frame number >= 0 or 'last', got '%s'", cmd, v);
  return 0;
}

int mpm_app_arg_positional(const char *cmd, const char *a, const char **pos, int npos)
{
  if (a[0] == '-' && a[1] != '\0')
    return mpm_app_usage("%s: unknown or incomplete option '%s'", cmd, a);
  for (int k = 0; k < npos; k++)
    if (!pos[k]) {
      pos[k] = a;
      return 0;
    }
  return mpm_app_usage("%s: unexpected argument '%s'", cmd, a);
}
