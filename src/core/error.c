/* error.c: status texts and the error context. */
#include "core/error.h"

#include <stdio.h>
#include <string.h>

const char *mpm_err_string(int code)
{
#define MPM_ERROR_CASE_(name, msg) case name: return msg;
  switch (code) {
    MPM_ERROR_LIST(MPM_ERROR_CASE_)
  default:
    return "unknown error";
  }
#undef MPM_ERROR_CASE_
}

int mpm_err_set(mpm_err *err, int code, const char *fmt, ...)
{
  if (err) {
    va_list ap;
    err->code = code;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
  }
  return code;
}

int mpm_err_prefix(mpm_err *err, int code, const char *fmt, ...)
{
  if (err) {
    char below[MPM_ERR_MSG], context[MPM_ERR_MSG];
    va_list ap;
    snprintf(below, sizeof below, "%s", err->msg);
    va_start(ap, fmt);
    vsnprintf(context, sizeof context, fmt, ap);
    va_end(ap);
    mpm_err_set(err, code, "%s: %s", context, below);
  }
  return code;
}

void mpm_err_clear(mpm_err *err)
{
  if (err) {
    err->code = MPM_OK;
    err->msg[0] = '\0';
  }
}
