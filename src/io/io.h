/* io.h: input parsing and validation (libconfuse), run output (HDF5 frames,
 * XDMF, diagnostics CSV) and extraction of frames to CSV.
 *
 * Input errors are MPM_EINPUT with one line "FILE:LINE: key 'section.key': what
 * is wrong (allowed: ...)". io depends on core and the model/shape/mesh name
 * tables, never on the solver. */
#ifndef MPM_IO_IO_H
#define MPM_IO_IO_H

#include <stdio.h>

#include "core/config.h"
#include "core/error.h"
#include "core/points.h"
#include "diag/diag.h"
#include "mesh/mesh.h"

/* Defaults of every key (docs/input-reference.md). */
void mpm_io_input_defaults(mpm_config *cfg);

/* Parse path into cfg (defaults first), then apply overrides of the form
 * "section.key=value" in order, then validate every value and the model's
 * parameters. */
int mpm_io_input_load(const char *path, const char *const *overrides, int noverrides,
                      mpm_config *cfg, mpm_err *err);

/* Write cfg in input-file syntax; reading it back gives the same cfg. */
int mpm_io_input_write(FILE *f, const mpm_config *cfg);

/* Run output: run.h5, run.xdmf and diagnostics.csv in one directory. */
typedef struct mpm_io_output mpm_io_output;

/* Create dir (and parents) if needed and open the files. The version, the
 * command line and the resolved input text (mpm_io_input_write) are stored as
 * attributes of run.h5. */
int mpm_io_output_open(mpm_io_output **out, const char *dir, const char *cmdline,
                       const char *input_text, const mpm_mesh *m, mpm_err *err);

/* Append one frame of point fields and one diagnostics row. */
int mpm_io_output_frame(mpm_io_output *out, const mpm_points *pts, const mpm_diag *d, mpm_err *err);

/* Write run.xdmf and close everything; accepts NULL. */
int mpm_io_output_close(mpm_io_output *out, mpm_err *err);

/* Print one frame (frame < 0: the last) of run directory dir as CSV with a
 * header row; fields is a comma list of field names or NULL for all. */
int mpm_io_extract(const char *dir, int frame, const char *fields, FILE *out, mpm_err *err);

/* Frames of a run directory read back into a point store (frame.c), for
 * post-processing. */
typedef struct mpm_io_run mpm_io_run;

int mpm_io_run_open(mpm_io_run **r, const char *dir, mpm_err *err);
void mpm_io_run_close(mpm_io_run *r);  /* accepts NULL */
int mpm_io_run_nframes(const mpm_io_run *r);

/* The run's mesh (set up) and the name of its shape-function variant. */
int mpm_io_run_mesh(const mpm_io_run *r, mpm_mesh *m, char *shape, size_t len,
                    mpm_err *err);

/* Frame `frame` (< 0: the last) into pts (previous contents replaced) and
 * its time *t. Extents are zero when the run did not write them. */
int mpm_io_run_frame(const mpm_io_run *r, int frame, mpm_points *pts, double *t,
                     mpm_err *err);

#endif
