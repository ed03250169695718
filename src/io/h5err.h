/* h5err.h (private to io/): HDF5 errors as one mpm_err message, and the
 * opening and closing of HDF5 objects, and the attribute and array readers
 * and writers that output, checkpoints, extraction and the frame reader
 * share.
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

/* Before the first HDF5 call of a program that writes: no HDF5 clean-up at
 * exit. HDF5 1.10 leaves a file whose close failed (a full disk) with an
 * identifier to freed memory, and its exit handler then crashes; every file
 * is closed explicitly instead. Harmless once HDF5 has started. */
void mpm_io_h5_init(void);

/* Scalar attributes of a predefined type (an existing one of the same name
 * is replaced); 0 or negative as HDF5. A NULL string is written as "". */
herr_t mpm_io_h5_attr_scalar(hid_t obj, const char *name, hid_t type, const void *v);
herr_t mpm_io_h5_attr_double(hid_t obj, const char *name, double v);
herr_t mpm_io_h5_attr_int(hid_t obj, const char *name, int v);
herr_t mpm_io_h5_attr_long(hid_t obj, const char *name, long v);
herr_t mpm_io_h5_attr_string(hid_t obj, const char *name, const char *s);

/* A string attribute of room bytes (s cut to room - 1, NUL-padded): one of
 * that size already there is overwritten in place, which needs no new space
 * in the file (a run on a full disk can still record how it ended);
 * otherwise it is created (replacing one of another size or type). */
herr_t mpm_io_h5_attr_string_room(hid_t obj, const char *name, const char *s, size_t room);

/* A scalar attribute as type (H5T_NATIVE_*); 0 or -1. */
int mpm_io_h5_attr_read(hid_t obj, const char *name, hid_t type, void *v);

/* A string attribute as a NUL-terminated copy (free it); NULL when missing,
 * not a string or out of memory. */
char *mpm_io_h5_attr_text(hid_t obj, const char *name);

/* A 1-D dataset of n values of memory type mtype, stored as ftype, with
 * optional "unit" and "description" attributes. */
herr_t mpm_io_h5_write_array(hid_t loc, const char *name, hid_t ftype, hid_t mtype, size_t n,
                             const void *buf, const char *unit, const char *desc);

/* The length of the 1-D dataset `name` of loc, -1 if missing or not 1-D. */
long long mpm_io_h5_array_length(hid_t loc, const char *name);

/* Frames: every field of MPM_POINT_FIELDS that the frame's dimension has is
 * written to each; the 2D extents (r1x, r1y, r2x, r2y) are optional (older
 * runs lack them). The first required field frame group g lacks, NULL when
 * none is missing (a frame without one is damaged, never read as a shorter
 * frame); "dimension" when its dimension attribute is not 2 or 3. */
int mpm_io_frame_field_optional(const char *name);
const char *mpm_io_frame_missing_field(hid_t g);

/* The dimension of frame group g: its "dimension" attribute, written on 3D
 * frames only (2 when absent); -1 when it is there but not 2 or 3. */
int mpm_io_frame_dim(hid_t g);

/* "DIR/NAME" in a new string (free it); NULL when out of memory. */
char *mpm_io_path_join(const char *dir, const char *name);

/* Close an HDF5 identifier of any kind (file, group, dataset, attribute,
 * dataspace, datatype, property list); a negative one, never opened, is left
 * alone. Returns the status of the close, 0 for a negative identifier. */
herr_t mpm_io_h5_close(hid_t id);

#endif
