/* frame.c: read frames of a run directory back into a point store, and the
 * run's mesh, for post-processing (granmpm extract --profile, --series, ...).
 *
 * Reads DIR/run.h5 as written by output.c: /mesh attributes, the resolved
 * input (attribute "input", for the shape-function name) and frame groups
 * /frames/NNNNNN with attribute "time" and one dataset per stored point
 * field (MPM_POINT_FIELDS, by its output name). Extents (r1x, r1y, r2x, r2y)
 * are read when the frame has them. A 3D frame (attribute dimension = 3)
 * makes the store 3D and fills its dim-3 fields too; the mesh of a 3D run
 * (a box) is given as its x-y section, a Q4 mesh, for the measurements made
 * on the points' x and y. */
#define _POSIX_C_SOURCE 200809L

#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/h5err.h"
#include "io/io.h"

struct mpm_io_run {
  char path[MPM_PATH_MAX + 16];
  hid_t file;
  int nframes;
  int dim;                /* 3 for a run with a box mesh or 3D frames */
  mpm_io_h5_quiet quiet;  /* HDF5's error printing is off while the run is open */
};

static int fail(mpm_io_run *r, mpm_err *err, const char *what)
{
  return mpm_err_set(err, MPM_EIO, "%s in '%s': %s", what, r->path, mpm_io_h5_reason(&r->quiet));
}

int mpm_io_run_open(mpm_io_run **out, const char *dir, mpm_err *err)
{
  mpm_io_run *r = calloc(1, sizeof *r);
  *out = NULL;
  if (!r)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory opening run '%s'", dir);
  if (snprintf(r->path, sizeof r->path, "%s/run.h5", dir) >= (int)sizeof r->path) {
    free(r);
    return mpm_err_set(err, MPM_EINPUT, "run directory name too long: '%s'", dir);
  }
  mpm_io_h5_quiet_begin(&r->quiet);        /* errors become return codes */
  r->file = mpm_io_h5_open_read(r->path);  /* a running job may still write */
  if (r->file < 0) {
    int rc = mpm_err_set(err, MPM_EIO, "cannot open '%s' (not a run directory?): %s", r->path,
                         mpm_io_h5_reason(&r->quiet));
    mpm_io_run_close(r);
    return rc;
  }
  H5G_info_t info;
  hid_t g = H5Gopen2(r->file, "frames", H5P_DEFAULT);
  if (g < 0 || H5Gget_info(g, &info) < 0) {
    mpm_io_h5_close(g);
    int rc = fail(r, err, "no frames group");
    mpm_io_run_close(r);
    return rc;
  }
  r->nframes = (int)info.nlinks;
  r->dim = 2;
  if (H5Lexists(r->file, "mesh", H5P_DEFAULT) > 0 &&
      H5Aexists_by_name(r->file, "mesh", "nz", H5P_DEFAULT) > 0)
    r->dim = 3;
  else if (r->nframes > 0 && H5Lexists(g, "000000", H5P_DEFAULT) > 0 &&
           H5Aexists_by_name(g, "000000", "dimension", H5P_DEFAULT) > 0)
    r->dim = 3;   /* a 3D run without a mesh; a bad value is found reading the frame */
  H5Gclose(g);
  r->quiet.reason[0] = '\0';
  *out = r;
  return MPM_OK;
}

void mpm_io_run_close(mpm_io_run *r)
{
  if (!r)
    return;
  mpm_io_h5_close(r->file);
  mpm_io_h5_quiet_end(&r->quiet);
  free(r);
}

int mpm_io_run_nframes(const mpm_io_run *r)
{
  return r->nframes;
}

int mpm_io_run_dim(const mpm_io_run *r)
{
  return r->dim;
}


/* The value of `shape = "..."` inside the "mesh {" section of the resolved
 * input text (written by mpm_io_input_write, one key per line). */
static void shape_from_input(const char *text, char *shape, size_t len)
{
  const char *m = strstr(text, "\nmesh {");
  const char *end = m ? strstr(m, "\n}") : NULL;
  const char *k = m ? strstr(m, "\n  shape = \"") : NULL;
  snprintf(shape, len, "%s", "ugimp");
  if (k && (!end || k < end)) {
    k += strlen("\n  shape = \"");
    const char *q = strchr(k, '"');
    if (q && (size_t)(q - k) < len)
      snprintf(shape, len, "%.*s", (int)(q - k), k);
  }
}

int mpm_io_run_mesh(const mpm_io_run *r, mpm_mesh *m, char *shape, size_t len,
                    mpm_err *err)
{
  hid_t g = H5Gopen2(r->file, "mesh", H5P_DEFAULT);
  char topo[16] = "", diag[16] = "";
  int rc = g < 0 ? -1 : 0;
  memset(m, 0, sizeof *m);
  if (rc == 0)
    rc = mpm_io_h5_attr_read(g, "nx", H5T_NATIVE_INT, &m->nx) | mpm_io_h5_attr_read(g, "ny", H5T_NATIVE_INT, &m->ny) |
         mpm_io_h5_attr_read(g, "x0", H5T_NATIVE_DOUBLE, &m->x0) |
         mpm_io_h5_attr_read(g, "y0", H5T_NATIVE_DOUBLE, &m->y0) |
         mpm_io_h5_attr_read(g, "dx", H5T_NATIVE_DOUBLE, &m->dx) |
         mpm_io_h5_attr_read(g, "dy", H5T_NATIVE_DOUBLE, &m->dy) |
         (r->dim == 3 ? 0 : mpm_io_h5_attr_read(g, "mirror_x", H5T_NATIVE_DOUBLE, &m->mirror_x)) |
         mpm_io_h5_attr_read(g, "periodic_x", H5T_NATIVE_INT, &m->periodic_x) |
         mpm_io_h5_attr_read(g, "periodic_y", H5T_NATIVE_INT, &m->periodic_y);
  for (int k = r->dim == 3; rc == 0 && k < 2; k++) {   /* a box: its x-y section, Q4 */
    hid_t a = H5Aopen(g, k ? "topology" : "diagonal", H5P_DEFAULT);
    hid_t t = a < 0 ? -1 : H5Aget_type(a);
    char *dst = k ? topo : diag;
    if (t < 0 || H5Tget_size(t) >= sizeof topo || H5Aread(a, t, dst) < 0)
      rc = -1;
    mpm_io_h5_close(t);
    mpm_io_h5_close(a);
  }
  mpm_io_h5_close(g);
  if (rc != 0)
    return fail((mpm_io_run *)r, err, "cannot read the mesh attributes");
  if (r->dim == 3) {
    if (strcmp(topo, "box") != 0)
      return fail((mpm_io_run *)r, err, "unknown 3D mesh topology");
    snprintf(topo, sizeof topo, "%s", mpm_mesh_topology_name(MPM_TOPO_Q4));
    snprintf(diag, sizeof diag, "%s", mpm_mesh_diagonal_name(MPM_DIAG_SLASH));
  }
  m->topology = mpm_mesh_topology_from_name(topo);
  m->diagonal = mpm_mesh_diagonal_from_name(diag);
  if (m->topology < 0 || m->diagonal < 0)
    return fail((mpm_io_run *)r, err, "unknown mesh topology or diagonal");
  if (shape && len) {
    char *text = mpm_io_h5_attr_text(r->file, "input");
    snprintf(shape, len, "%s", "ugimp");
    if (text)
      shape_from_input(text, shape, len);
    free(text);
  }
  return mpm_mesh_setup(m, err);
}

/* One 1-D dataset of n values into dst (double or int); -1 if missing. */
/* Field name of frame group g (n values) into dst: 0, or FIELD_MISSING,
 * FIELD_LENGTH (not n values), FIELD_TYPE (a damaged stored type or chunk index) or
 * FIELD_UNREADABLE (HDF5 failed: a damaged chunk fails its checksum). */
enum { FIELD_MISSING = -1, FIELD_LENGTH = -2, FIELD_TYPE = -3, FIELD_UNREADABLE = -4 };

static int read_field(hid_t g, const char *name, hid_t type, hsize_t n, void *dst)
{
  if (H5Lexists(g, name, H5P_DEFAULT) <= 0)
    return FIELD_MISSING;
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  hid_t s = d < 0 ? -1 : H5Dget_space(d);
  hsize_t dims[1] = {0};
  int rc = s >= 0 && H5Sget_simple_extent_ndims(s) == 1 &&
                   H5Sget_simple_extent_dims(s, dims, NULL) == 1
               ? (dims[0] == n ? 0 : FIELD_LENGTH)
               : FIELD_UNREADABLE;
  if (rc == 0 && !mpm_io_h5_type_ok(d, type))
    rc = FIELD_TYPE;
  if (rc == 0 && n > 0 && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, dst) < 0)
    rc = FIELD_UNREADABLE;
  mpm_io_h5_close(s);
  mpm_io_h5_close(d);
  return rc;
}


int mpm_io_run_frame(const mpm_io_run *r, int frame, mpm_points *pts, double *t,
                     mpm_err *err)
{
  char name[48];
  unsigned long long n = 0;
  if (frame < 0)
    frame = r->nframes - 1;
  if (frame < 0 || frame >= r->nframes)
    return mpm_err_set(err, MPM_EINPUT, "frame %d not in '%s' (frames 0..%d)", frame, r->path,
                       r->nframes - 1);
  snprintf(name, sizeof name, "frames/%06d", frame);
  hid_t g = H5Gopen2(r->file, name, H5P_DEFAULT);
  if (g < 0 || mpm_io_h5_attr_read(g, "time", H5T_NATIVE_DOUBLE, t) < 0) {
    mpm_io_h5_close(g);
    return mpm_err_set(err, MPM_EIO, "cannot read frame %d of '%s': %s (a damaged run)", frame,
                       r->path, mpm_io_h5_reason(&r->quiet));
  }
  int dim = 2;
  int rc = mpm_io_frame_check(g, frame, r->path, &r->quiet, &n, &dim, err);
  if (rc != MPM_OK) {
    H5Gclose(g);
    return rc;
  }
  pts->n = 0;
  if (mpm_points_set_dim(pts, dim) != MPM_OK || mpm_points_reserve(pts, (size_t)n) != MPM_OK) {
    H5Gclose(g);
    return mpm_err_set(err, MPM_ENOMEM, "out of memory reading frame %d of '%s'", frame, r->path);
  }
  pts->n = (size_t)n;
#define STORED_REAL_(f, nm, d, u, D) {nm, pts->f, sizeof *pts->f, 0, D},
#define STORED_INT_(f, nm, d, u, D) {nm, pts->f, sizeof *pts->f, 1, D},
  const struct { const char *name; void *dst; size_t size; int isint, dim; } field[] = {
    MPM_POINT_FIELDS(STORED_REAL_, STORED_INT_, MPM_POINT_SKIP_)
  };
#undef STORED_REAL_
#undef STORED_INT_
  for (size_t k = 0; rc == MPM_OK && k < sizeof field / sizeof field[0]; k++) {
    if (field[k].dim > dim)
      continue;
    const int got = read_field(g, field[k].name, field[k].isint ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                               n, field[k].dst);
    if (got == FIELD_MISSING && mpm_io_frame_field_optional(field[k].name))
      memset(field[k].dst, 0, (size_t)n * field[k].size);   /* written by an older version */
    else if (got == FIELD_TYPE)
      rc = mpm_err_set(err, MPM_EIO, "frame %d of '%s': field '%s': its stored type or layout is damaged "
                       "(a damaged run)", frame, r->path, field[k].name);
    else if (got == FIELD_LENGTH)
      rc = mpm_err_set(err, MPM_EIO, "frame %d of '%s': field '%s' does not hold npoints = %llu "
                       "values (a damaged run)", frame, r->path, field[k].name, n);
    else if (got != 0)
      rc = mpm_err_set(err, MPM_EIO, "frame %d of '%s': cannot read field '%s': %s (a damaged "
                       "run)", frame, r->path, field[k].name, mpm_io_h5_reason(&r->quiet));
  }
  H5Gclose(g);
  if (rc != MPM_OK)
    pts->n = 0;
  return rc;
}

/* ---- provenance ------------------------------------------------------------- */

static char *text_or_empty(hid_t obj, const char *name)
{
  char *t = mpm_io_h5_attr_text(obj, name);
  if (!t && (t = malloc(1)))
    t[0] = '\0';
  return t;
}

int mpm_io_run_provenance(const mpm_io_run *r, mpm_io_provenance *p, mpm_err *err)
{
  memset(p, 0, sizeof *p);
  char **texts[] = {&p->version, &p->revision, &p->command_line, &p->input, &p->host,
                    &p->start_time, &p->end_time, &p->status, &p->failure, &p->resume_log};
  const char *names[] = {"version", "revision", "command_line", "input", "host",
                         "start_time", "end_time", "status", "failure", "resume_log"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
    if (!(*texts[k] = text_or_empty(r->file, names[k]))) {
      mpm_io_run_provenance_clear(p);
      return mpm_err_set(err, MPM_ENOMEM, "out of memory reading '%s'", r->path);
    }
  p->threads = p->resumed = -1;                   /* -1: not recorded (an older run) */
  mpm_io_h5_attr_read(r->file, "threads", H5T_NATIVE_INT, &p->threads);
  mpm_io_h5_attr_read(r->file, "resumed", H5T_NATIVE_INT, &p->resumed);
  p->nframes = r->nframes;
  p->t_last = 0.0;
  if (r->nframes > 0) {
    char name[48];
    snprintf(name, sizeof name, "frames/%06d", r->nframes - 1);
    hid_t g = H5Gopen2(r->file, name, H5P_DEFAULT);
    if (g < 0 || mpm_io_h5_attr_read(g, "time", H5T_NATIVE_DOUBLE, &p->t_last) < 0)
      p->t_last = -1.0;
    mpm_io_h5_close(g);
  }
  return MPM_OK;
}

void mpm_io_run_provenance_clear(mpm_io_provenance *p)
{
  if (!p)
    return;
  char *texts[] = {p->version, p->revision, p->command_line, p->input, p->host,
                   p->start_time, p->end_time, p->status, p->failure, p->resume_log};
  for (size_t k = 0; k < sizeof texts / sizeof texts[0]; k++)
    free(texts[k]);
  memset(p, 0, sizeof *p);
}
