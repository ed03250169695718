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

/* A loaded input kept with where each value came from (a file line, a
 * --set), so that checks made after the load (the fills, the run's size, its
 * time step: mpm_io_input_fail) report in the shape of the reader's own
 * errors. The overrides must outlive it. */
typedef struct mpm_io_input mpm_io_input;

/* mpm_io_input_load, keeping the input in *in (NULL on error). */
int mpm_io_input_open(mpm_io_input **in, const char *path, const char *const *overrides,
                      int noverrides, mpm_config *cfg, mpm_err *err);

/* The same from the text of an input (a resolved input stored with a run);
 * name stands for the file in messages. */
int mpm_io_input_open_text(mpm_io_input **in, const char *name, const char *content,
                           const char *const *overrides, int noverrides, mpm_config *cfg,
                           mpm_err *err);

void mpm_io_input_free(mpm_io_input *in);  /* accepts NULL */

/* MPM_EINPUT with "FILE:LINE: key 'KEY': MESSAGE" (or "--set '...': ..."),
 * LINE where KEY was set, else where its section opens. KEY is
 * "section.key" or "fill.TITLE.key" of cfg, the configuration in loaded. */
int mpm_io_input_fail(mpm_io_input *in, const mpm_config *cfg, const char *key, mpm_err *err,
                      const char *fmt, ...) __attribute__((format(printf, 5, 6)));

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
