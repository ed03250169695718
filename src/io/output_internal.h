/* output_internal.h: what the run-output files of io/ share (output.c,
 * xdmf.c): the output object, the table of point fields a frame holds, and
 * the pieces of run.xdmf. Not part of the library's interface (names
 * mpm_io_out_*). */
#ifndef MPM_IO_OUTPUT_INTERNAL_H
#define MPM_IO_OUTPUT_INTERNAL_H

#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "core/points.h"
#include "io/h5err.h"
#include "io/io.h"

/* One output field: name in run.h5, unit, where it comes from. */
enum field_kind { FIELD_REAL, FIELD_INT, FIELD_DERIVED };

/* A derived field's n values from the stored fields. */
typedef void derive_fn(const mpm_points *pts, double *v);

typedef struct field_spec {
  const char *name;
  const char *unit;
  const char *description;
  int kind;      /* enum field_kind */
  int dim;       /* written to frames of this dimension and up */
  size_t offset; /* offsetof(mpm_points, array) for FIELD_REAL / FIELD_INT */
  derive_fn *derive; /* for FIELD_DERIVED */
} field_spec;

struct mpm_io_output {
  char *h5_path, *csv_path, *xdmf_path;
  char *reserve_path; /* space held while the run writes, freed to record its end */
  hid_t file;       /* run.h5 */
  hid_t frames;     /* /frames */
  hid_t xdmf_group; /* /xdmf */
  FILE *csv;
  FILE *xdmf;
  char *bcsv_path;  /* bodies.csv ... */
  FILE *bcsv;       /* ... open once a frame had bodies (bodies_out.c) */
  long xdmf_tail_pos; /* offset of the closing tags in run.xdmf */
  char *bxdmf_path;   /* bodies.xdmf ... */
  FILE *bxdmf;        /* ... open once a frame had body outlines (xdmf.c) */
  long bxdmf_tail_pos; /* offset of its closing tags */
  int nframes;
  int dim;           /* of the run's point stores: 2, or 3 (a mesh of boxes) */
  size_t vertex_n;   /* length of the newest /xdmf/vertex_NNNNNN */
  int vertex_frame;  /* its frame number, -1 before the first */
  int outline_frame; /* the frame whose body outlines are in /xdmf, -1: none */
  size_t outline_nv, outline_ncell, outline_len;  /* their vertices, cells, and the
                                                     length of the cell list */
  const field_spec *fields;  /* MPM_POINT_FIELDS in order: the frames' datasets */
  size_t nfields;
  double *work;      /* per-point scratch for derived fields */
  size_t work_cap;
};

/* Create path and write text to it (flushed). */
static inline int mpm_io_out_open_text(FILE **f, const char *path, const char *text,
                                       mpm_err *err)
{
  *f = fopen(path, "w");
  if (!*f)
    return mpm_err_set(err, MPM_EIO, "cannot create '%s': %s", path, strerror(errno));
  if (fputs(text, *f) < 0 || fflush(*f) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(errno));
  return MPM_OK;
}

/* The body outlines of frame `frame` in /xdmf (their counts to
 * out->outline_*), from the lengths of its datasets; 0 when the frame has
 * none, -1 on a damaged dataset. */
int mpm_io_out_outline_counts(mpm_io_output *out, long frame);

/* A resumed run's bodies after its first nframes frames: later /bodies
 * datasets dropped, bodies.csv (if any) cut and open for appending. */
int mpm_io_out_bodies_reopen(mpm_io_output *out, long nframes, mpm_err *err);

/* run.xdmf as an empty temporal collection (out->xdmf, its tail offset). */
int mpm_io_out_xdmf_open(mpm_io_output *out, mpm_err *err);

/* run.xdmf written again for frames 0 .. nframes-1 of run.h5. */
int mpm_io_out_xdmf_rebuild(mpm_io_output *out, long nframes, const mpm_io_h5_quiet *q,
                            mpm_err *err);

/* The grid of frame out->nframes (time t, n points, dimension dim) put
 * before run.xdmf's closing tags; none for n = 0. */
int mpm_io_out_xdmf_frame(mpm_io_output *out, double t, size_t n, int dim, mpm_err *err);

/* /xdmf/vertex_NNNNNN for a frame of n points, unless the newest has n. */
int mpm_io_out_vertices(mpm_io_output *out, size_t n, const mpm_io_h5_quiet *q, mpm_err *err);

/* /xdmf/xy_NNNNNN (xyz_NNNNNN for dim 3) of frame `frame` in group xg. */
herr_t mpm_io_out_xy_view(hid_t xg, int frame, size_t n, int dim);

#endif
