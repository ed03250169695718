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
#include "core/state.h"
#include "diag/diag.h"
#include "mesh/mesh.h"

/* Defaults of every key (docs/input-reference.md), those of the scheme
 * (mesh.dilatation, material.state_density, time.transfer, time.cfl) as in
 * a plane q4 run with uGIMP weights: a load resolves them by the run. */
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
 * "section.key", "fill.TITLE.key" or "body.TITLE.key" of cfg, the
 * configuration in loaded. */
int mpm_io_input_fail(mpm_io_input *in, const mpm_config *cfg, const char *key, mpm_err *err,
                      const char *fmt, ...) __attribute__((format(printf, 5, 6)));

/* Write cfg in input-file syntax; reading it back gives the same cfg. */
int mpm_io_input_write(FILE *f, const mpm_config *cfg);

/* The same as a new string (free it); NULL when out of memory. */
char *mpm_io_input_text(const mpm_config *cfg);

/* Run output: run.h5, run.xdmf and diagnostics.csv in one directory. */
typedef struct mpm_io_output mpm_io_output;

/* Where a run comes from, for the attributes of run.h5 (with the program
 * version, the host and the times, which io finds itself). */
typedef struct mpm_io_origin {
  const char *command_line;   /* as typed */
  const char *revision;       /* source revision of the program; NULL: "unknown" */
  int threads;                /* OpenMP threads of the run */
} mpm_io_origin;

/* Create dir (and parents) if needed and open the files for a run on mesh m
 * (NULL: none, and a plane run). run.h5's root attributes: version,
 * revision, command_line, input (the resolved text, mpm_io_input_write),
 * host, threads, start_time, end_time ("" until mpm_io_output_end), status
 * ("running" until then), failure ("" unless the run failed), resumed (0)
 * and resume_log (""). A 3D run's
 * frames take 3D stores (mpm_points_alloc_dim(n, 3)) and hold their dim-3
 * fields too, with an attribute dimension = 3 and XYZ points in run.xdmf;
 * its /mesh holds the attributes of the plane's mesh that a box has
 * (topology "box") and nz, z0, dz, periodic_z, node_z. */
int mpm_io_output_open(mpm_io_output **out, const char *dir, const mpm_io_origin *origin,
                       const char *input_text, const mpm_mesh *m, mpm_err *err);

/* Open the output of a run in dir to continue it after its first nframes
 * frames: later frames (written after the checkpoint it continues from) are
 * removed from run.h5, diagnostics.csv is cut after its nframes rows and
 * run.xdmf written again; resumed grows by one, resume_log gains a line
 * "START host=H threads=N: COMMAND", status is "running" again. */
int mpm_io_output_reopen(mpm_io_output **out, const char *dir, const mpm_io_origin *origin,
                         long nframes, mpm_err *err);

/* The end of a run in run.h5: end_time now, status ("finished", "stopped"
 * (resumable), "failed") and failure (why it failed: the error's one line;
 * NULL or "" otherwise). The three are written in place (the room for them
 * is taken when the run starts), so a run whose disk is full can still say
 * that it failed and why, where HDF5 can still write at all. */
int mpm_io_output_end(mpm_io_output *out, const char *status, const char *failure,
                      mpm_err *err);

/* Output directory dir (made when missing) taken by this process for
 * writing: a POSIX lock on DIR/.granmpm-lock, which names the holder ("granmpm pid P on
 * host H"). The lock ends with the process however it ends (a kill
 * included) or with mpm_io_dir_unlock(*fd). A directory another process
 * holds is MPM_EINPUT naming that holder. */
int mpm_io_dir_lock(const char *dir, int *fd, mpm_err *err);
void mpm_io_dir_unlock(int fd);

/* 1 when dir holds a run (run.h5 or checkpoint.h5), with *what the file. */
int mpm_io_output_occupied(const char *dir, const char **what);

/* Append one frame of point fields and one diagnostics row; the store's
 * dimension is the run's (MPM_EINVAL otherwise). */
int mpm_io_output_frame(mpm_io_output *out, const mpm_points *pts, const mpm_diag *d, mpm_err *err);

/* A body's outline for run.xdmf (bc/body.h, mpm_body_outline): nr rings
 * (1: the plane's profile; 2: the ends of a 3D prism) of nv vertices, vertex
 * i of ring r at xyz[3 (r nv + i)]; caps 1 when the rings bound closed end
 * faces. */
typedef struct mpm_io_outline {
  int nv, nr, caps;
  const double *xyz;
} mpm_io_outline;

/* The n rigid bodies of the frame about to be written (call before
 * mpm_io_output_frame; nothing for n = 0): a row per body in bodies.csv
 * (frame, t, body, x, y, z, angle, vx, vy, vz, omega, fx, fy, fz, tx, ty,
 * tz, pushed; created with its header on the first call) and the dataset
 * /bodies/NNNNNN of run.h5 (n x 15 values, the columns after `body`;
 * /bodies names the bodies and columns in attributes). names[k] is body k's
 * title. With outlines ol[n] (may be NULL) the frame's grid in run.xdmf
 * gets a second part, "bodies": each body's profile as a closed polyline in
 * the plane, its prism's sides (and closed ends) as faces in 3D, with the
 * cell field `body` (k); their data go to /xdmf/bodies_xyz_NNNNNN,
 * bodies_cells_NNNNNN and bodies_id_NNNNNN. */
int mpm_io_output_bodies(mpm_io_output *out, double t, int n, const char *const *names,
                         const mpm_body_state *b, const mpm_io_outline *ol, mpm_err *err);

/* The bodies of a run (run.h5's /bodies) as bodies.csv has them: every
 * frame (MPM_IO_ALL_FRAMES), the last (-1) or one; MPM_EINPUT for a run
 * without bodies or a frame it does not have. */
#define MPM_IO_ALL_FRAMES (-2)
int mpm_io_extract_bodies(const char *dir, int frame, FILE *out, mpm_err *err);

/* Write run.xdmf and close everything; accepts NULL. */
int mpm_io_output_close(mpm_io_output *out, mpm_err *err);

/* ---- checkpoints (checkpoint.c) ----------------------------------------------
 * DIR/checkpoint.h5: a run's state (core/state.h) and its resolved input,
 * written whole to DIR/checkpoint.h5.tmp (assembled in memory, written with
 * one write and fsync) and renamed over the previous one, so a checkpoint is
 * either the old one or the new one, never half of each. */
int mpm_io_checkpoint_write(const char *dir, const mpm_run_state *st, const char *input_text,
                            const char *written_by, mpm_err *err);

/* A checkpoint read back: the state (its points and series allocated), the
 * resolved input and the program that wrote it ("VERSION (REVISION)"). */
typedef struct mpm_io_checkpoint {
  mpm_run_state state;
  char *input;
  char written_by[128];
} mpm_io_checkpoint;

int mpm_io_checkpoint_read(const char *dir, mpm_io_checkpoint *ck, mpm_err *err);
void mpm_io_checkpoint_clear(mpm_io_checkpoint *ck);   /* frees what read allocated */

/* The time and step of DIR/checkpoint.h5, without reading its points. */
int mpm_io_checkpoint_when(const char *dir, double *t, long *step, mpm_err *err);

/* Write the user block of a checkpoint (its first 512 bytes: the format and
 * the checksum of every later byte) over the start of the len bytes at
 * file, as mpm_io_checkpoint_write does, whatever the later bytes hold: for
 * tests that make a file whose checksum passes, so that its HDF5 and its
 * values are what is checked. -1 when len is shorter than the block. */
int mpm_io_checkpoint_seal(void *file, size_t len);

/* Remove DIR/checkpoint.h5 (a finished run needs none); none there is fine. */
int mpm_io_checkpoint_remove(const char *dir, mpm_err *err);

/* Print one frame (frame < 0: the last) of run directory dir as CSV with a
 * header row; fields is a comma list of field names or NULL for all. */
int mpm_io_extract(const char *dir, int frame, const char *fields, FILE *out, mpm_err *err);

/* A slab of a 3D run: the points with zmin <= z <= zmax. */
typedef struct mpm_io_zrange {
  double zmin, zmax;
} mpm_io_zrange;

/* mpm_io_extract of the points in zr only (NULL: every point); a 2D frame
 * has no z (MPM_EINPUT). */
int mpm_io_extract_in(const char *dir, int frame, const char *fields, const mpm_io_zrange *zr,
                      FILE *out, mpm_err *err);

/* Frames of a run directory read back into a point store (frame.c), for
 * post-processing. */
typedef struct mpm_io_run mpm_io_run;

int mpm_io_run_open(mpm_io_run **r, const char *dir, mpm_err *err);
void mpm_io_run_close(mpm_io_run *r);  /* accepts NULL */
int mpm_io_run_nframes(const mpm_io_run *r);

/* 3 for a 3D run (a box mesh, or 3D frames), else 2. */
int mpm_io_run_dim(const mpm_io_run *r);

/* The run's mesh (set up) and the name of its shape-function variant; for a
 * 3D run, the x-y section of its box mesh as a Q4 mesh. */
int mpm_io_run_mesh(const mpm_io_run *r, mpm_mesh *m, char *shape, size_t len,
                    mpm_err *err);

/* Frame `frame` (< 0: the last) into pts (previous contents replaced, its
 * dimension made the frame's) and its time *t. Extents are zero when the
 * run did not write them; a frame
 * that lacks another field, or whose npoints does not match its data, is
 * MPM_EIO (a damaged run), found before anything is allocated. */
int mpm_io_run_frame(const mpm_io_run *r, int frame, mpm_points *pts, double *t,
                     mpm_err *err);

/* Where a run came from and how it ended: run.h5's root attributes
 * (mpm_io_output_open; "" for those an older run lacks) and its frames. */
typedef struct mpm_io_provenance {
  char *version, *revision, *command_line, *input, *host;
  char *start_time, *end_time, *status, *failure, *resume_log;  /* failure: why a failed
                                                                    run failed, or "" */
  int threads, resumed;       /* -1: not recorded */
  int nframes;
  double t_last;              /* time of the last frame [s] */
} mpm_io_provenance;

int mpm_io_run_provenance(const mpm_io_run *r, mpm_io_provenance *p, mpm_err *err);
void mpm_io_run_provenance_clear(mpm_io_provenance *p);  /* accepts NULL */

#endif
