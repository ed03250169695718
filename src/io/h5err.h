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

/* No HDF5 clean-up at exit, called by mpm_io_h5_quiet_begin before the
 * first HDF5 call of every reader and writer. HDF5 1.10 leaves a file whose
 * close failed (a full disk) with an identifier to freed memory, and its
 * exit handler then crashes; after a damaged file (a metadata checksum
 * failed) the handler prints "infinite loop closing library" and a line of
 * its codes. Every file is closed explicitly instead. Harmless once HDF5
 * has started. */
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

/* A new dataset of rank 1 or 2 and type ftype whose data carry HDF5's
 * Fletcher32 checksum, so that a damaged byte is an error on reading
 * ("data error detected by Fletcher32 checksum") rather than a wrong value:
 * chunks of whole rows, at most MPM_IO_H5_CHUNK values (512 KiB of doubles,
 * under HDF5's default chunk cache of 1 MiB, so a reader of blocks of rows
 * reads and checks each chunk once); an empty one is contiguous. The
 * dataset's id, negative on failure. */
#define MPM_IO_H5_CHUNK 65536

/* The file-creation properties of run.h5 and checkpoint.h5 (close it): the
 * chunk index of each dataset a B-tree of nodes of 2 entries, about 120
 * bytes a dataset rather than HDF5's default 2 kB (the files keep the 1.8
 * format, which a reader can open while the run writes or after a kill). */
hid_t mpm_io_h5_file_create_plist(void);
hid_t mpm_io_h5_create_checked(hid_t loc, const char *name, hid_t ftype, int rank,
                               const hsize_t *dims);

/* A 1-D dataset of n values of memory type mtype, stored as ftype and
 * checked (mpm_io_h5_create_checked), with optional "unit" and
 * "description" attributes. */
herr_t mpm_io_h5_write_array(hid_t loc, const char *name, hid_t ftype, hid_t mtype, size_t n,
                             const void *buf, const char *unit, const char *desc);

/* 1 if the stored type of dataset or attribute d is of the class of memory
 * type mtype (integer, float) and of 1 to 8 bytes an element, as every
 * number granmpm writes, and a dataset's chunks lie in the file and hold
 * at most a chunk of values and a checksum; 0 for a damaged type, which
 * HDF5 1.10 would convert past the end of the reader's buffer, or a damaged
 * chunk index entry, whose size HDF5 would allocate. Every read of numbers
 * from a granmpm file checks it first. */
int mpm_io_h5_type_ok(hid_t d, hid_t mtype);

/* The length of the 1-D dataset `name` of loc, -1 if missing, not 1-D or
 * longer than its file could hold (a damaged size, never to be allocated). */
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

/* Frame group g (frame number frame of run file path), checked before its
 * fields are read: its dimension (*dim), every required field there, its
 * point count (*n) and field x of that many values (a damaged count must
 * not ask for 2^63 bytes). MPM_EIO naming what is wrong, with HDF5's cause
 * from q where a read failed. */
int mpm_io_frame_check(hid_t g, int frame, const char *path, const mpm_io_h5_quiet *q,
                       unsigned long long *n, int *dim, mpm_err *err);

/* "DIR/NAME" in a new string (free it); NULL when out of memory. */
char *mpm_io_path_join(const char *dir, const char *name);

/* Close an HDF5 identifier of any kind (file, group, dataset, attribute,
 * dataspace, datatype, property list); a negative one, never opened, is left
 * alone. Returns the status of the close, 0 for a negative identifier. */
herr_t mpm_io_h5_close(hid_t id);

#endif
