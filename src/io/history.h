/* history.h (io): velocity-gradient histories (pointrun/history.h) read from
 * and written to CSV files.
 *
 * File format: one row per node, "t, Lxx, Lxy, Lyx, Lyy"; an optional header
 * row with exactly these names (any case); '#' starts a comment; blank lines
 * are skipped; at least two rows; times strictly increasing. Errors are
 * MPM_EINPUT naming the file and line ("name:LINE: ..."). */
#ifndef MPM_IO_HISTORY_H
#define MPM_IO_HISTORY_H

#include <stdio.h>

#include "core/error.h"
#include "pointrun/history.h"

/* Read a CSV history from path ("-" reads stdin). */
int mpm_io_history_read(const char *path, mpm_history **out, mpm_err *err);

/* Parse a CSV history from f; name is used in messages ("name:LINE: ..."). */
int mpm_io_history_parse(FILE *f, const char *name, mpm_history **out, mpm_err *err);

/* Write h as CSV with a header row (readable by mpm_io_history_parse). */
int mpm_io_history_write(FILE *f, const mpm_history *h);

#endif
