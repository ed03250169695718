/* error.h: status codes and error context for libgranmpm.
 *
 * Library functions return an int status (MPM_OK = 0 on success) and, when
 * given an mpm_err, record a one-line message with context (which point, which
 * key, which line). Only app/ prints or exits. */
#ifndef MPM_CORE_ERROR_H
#define MPM_CORE_ERROR_H

#include <stdarg.h>

/* X-macro list: enum name, default message. */
#define MPM_ERROR_LIST(X)                                   \
  X(MPM_OK,       "success")                                \
  X(MPM_ENOMEM,   "out of memory")                          \
  X(MPM_EINVAL,   "invalid argument")                       \
  X(MPM_EINPUT,   "invalid input")                          \
  X(MPM_EIO,      "input/output error")                     \
  X(MPM_EOUTSIDE, "material point left the mesh")           \
  X(MPM_ENONFINITE, "non-finite value")                     \
  X(MPM_ESOLVE,   "linear solve failed")

#define MPM_ERROR_ENUM_(name, msg) name,
enum mpm_status { MPM_ERROR_LIST(MPM_ERROR_ENUM_) MPM_NSTATUS };
#undef MPM_ERROR_ENUM_

#define MPM_ERR_MSG 512

/* Error context: code and a formatted message. Zero-initialise before use. */
typedef struct mpm_err {
  int code;
  char msg[MPM_ERR_MSG];
} mpm_err;

/* Default text of a status code. */
const char *mpm_err_string(int code);

/* Record code and a printf-style message in err (err may be NULL); returns code,
 * so callers write `return mpm_err_set(err, MPM_EINPUT, "...", ...);`. */
int mpm_err_set(mpm_err *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Put a printf-style context before err's message ("CONTEXT: message") and
 * set its code; returns code. For a caller that adds what it knows (the
 * step, the time) to an error from below. */
int mpm_err_prefix(mpm_err *err, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Reset err to MPM_OK with an empty message. */
void mpm_err_clear(mpm_err *err);

#endif
