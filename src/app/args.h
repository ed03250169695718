/* args.h: what the granmpm commands share in reading their arguments and
 * reporting failures: usage errors, option values (numbers, --frame),
 * positional arguments and the exit status of a library error. */
#ifndef MPM_APP_ARGS_H
#define MPM_APP_ARGS_H

#include "core/error.h"

/* Exit status: 0 success, 1 a run failed (physical or I/O failure while
 * running), 2 bad usage or input (or a run refused before its first step),
 * 3 a run stopped by a signal after writing its checkpoint (resumable). */
enum mpm_app_exit {
  MPM_APP_EXIT_RUNTIME = 1, MPM_APP_EXIT_USAGE = 2, MPM_APP_EXIT_STOPPED = 3
};

#if defined(__GNUC__)
#define MPM_APP_PRINTF_(f, a) __attribute__((format(printf, f, a)))
#else
#define MPM_APP_PRINTF_(f, a)
#endif

/* "granmpm: MESSAGE (see 'granmpm --help')" on stderr; returns
 * MPM_APP_EXIT_USAGE. */
int mpm_app_usage(const char *fmt, ...) MPM_APP_PRINTF_(1, 2);

/* "granmpm: MESSAGE" of err on stderr; returns MPM_APP_EXIT_USAGE for bad
 * input or an unreadable run (MPM_EINPUT, MPM_EIO), else
 * MPM_APP_EXIT_RUNTIME. */
int mpm_app_fail(const mpm_err *err);

/* The whole of s as a finite decimal number (no hexadecimal); 1 on success. */
int mpm_app_arg_real(const char *s, double *v);

/* "A:B" with finite decimal A < B; 1 on success. */
int mpm_app_arg_pair(const char *s, double *a, double *b);

/* The whole of s as a whole number in [lo, hi] (written as any number:
 * "4", "4.0", "4e0"); 1 on success, *v untouched otherwise. */
int mpm_app_arg_int(const char *s, int lo, int hi, int *v);

/* The value of --frame of command cmd: "last" (-1) or a frame number
 * >= 0. Returns 0, or the usage exit status after saying what is wrong. */
int mpm_app_arg_frame(const char *cmd, const char *v, int *frame);

/* An argument of command cmd that is no known option: stored in the first
 * empty one of pos[0..npos) and 0 returned; an option ("-x", but not "-")
 * or one positional argument too many is a usage error (its exit status). */
int mpm_app_arg_positional(const char *cmd, const char *a, const char **pos, int npos);

#endif
