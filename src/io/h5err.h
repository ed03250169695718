/* h5err.h (private to io/): HDF5 errors as one mpm_err message, and the
 * opening and closing of HDF5 objects that output, extraction and the frame
 * reader share.
 *
 * Between mpm_io_h5_quiet_begin and mpm_io_h5_quiet_end HDF5's automatic error
 * printing is replaced by a handler that keeps the innermost message of the
 * first failing call (later clean-up calls clear HDF5's own stack; for
 * file-driver errors, the system's own text); the previous handler is then
 * restored. */
#ifndef MPM_IO_H5ERR_H
#define MPM_IO_H5ERR_H

#include <hdf5.h>

#include "core/error.h"

typedef struct mpm_io_h5_quiet {
  H5E_auto2_t func;   /* the handler to restore */
  void *data;
  char reason[200];   /* the first failure's cause, "" while none */
} mpm_io_h5_quiet;

void mpm_io_h5_quiet_begin(mpm_io_h5_quiet *q);
void mpm_io_h5_quiet_end(const mpm_io_h5_quiet *q);

/* The kept cause, or "HDF5 error" when none was kept. */
const char *mpm_io_h5_reason(const mpm_io_h5_quiet *q);

/* MPM_EIO with "WHAT 'PATH': REASON" (REASON "HDF5 error" when none was kept). */
int mpm_io_h5_fail(mpm_err *err, const mpm_io_h5_quiet *q, const char *what, const char *path);

/* Open an existing run.h5 read-only without the HDF5 file lock, so a run
 * that is still writing (and flushes after every frame) can be read. */
hid_t mpm_io_h5_open_read(const char *path);

/* Close an HDF5 identifier of any kind (file, group, dataset, attribute,
 * dataspace, datatype, property list); a negative one, never opened, is left
 * alone. Returns the status of the close, 0 for a negative identifier. */
herr_t mpm_io_h5_close(hid_t id);

#endif
