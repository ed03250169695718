/* output.c: run output in one directory (DESIGN.md, "Input, output, command line").
 *
 *   run.h5           root attributes version, command_line, input (resolved text);
 *                    /mesh       attributes of the background mesh, node lines;
 *                    /frames/NNNNNN  attributes time, npoints; one 1-D dataset
 *                                per point field, each with "unit" and
 *                                "description" attributes;
 *                    /xdmf/xy_NNNNNN  n x 2 virtual view of the frame's x and y
 *                                (no copy), the XY points of run.xdmf;
 *                    /xdmf/xyz_NNNNNN  for a 3D frame instead: n x 3, x y z;
 *                    /xdmf/vertex_NNNNNN  0..n-1, the Polyvertex connectivity,
 *                                shared by consecutive frames with n points.
 *   run.xdmf         XDMF 3 temporal collection of one Polyvertex grid per frame
 *                    (xdmf.c).
 *
 * A 3D store (pts->dim = 3) is written by the same code: its frames carry
 * the dim-3 fields of MPM_POINT_FIELDS too and an attribute dimension = 3,
 * and their XDMF geometry is XYZ (xdmf.c); a run opened on a mesh of boxes
 * has it in /mesh (nz, z0, dz, periodic_z and node_z besides the 2D
 * names). A 2D frame is written exactly as before the 3D fields came.
 *   diagnostics.csv  one mpm_diag row per frame.
 *
 * Every frame is flushed (H5Fflush, fflush) and run.xdmf is kept complete
 * after each frame, so a run killed midway leaves readable output. run.h5
 * uses the HDF5 1.8 file format (superblock v2) plus 1.10 virtual datasets:
 * attributes larger than 64 KiB (a long resolved input) are allowed, and a
 * run killed while the file is open leaves no "file open for writing" flag
 * that readers refuse. Everything but the XY views reads with HDF5 1.8. */
#define _POSIX_C_SOURCE 200809L

#include "config.h" /* PACKAGE_VERSION */

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "diag/flow.h"
#include "io/h5err.h"
#include "io/io.h"
#include "io/output_internal.h"

/* The DERIVED fields of MPM_POINT_FIELDS, derive_<key>. */
static void derive_p(const mpm_points *pts, double *v)
{
  mpm_diag_pressure(pts, v);
}

/* Every field of MPM_POINT_FIELDS, in its order: the order of the datasets in
 * each frame group, which is the default column order of mpm_io_extract. */
#define FIELD_REAL_(f, nm, d, u, D) {nm, u, d, FIELD_REAL, D, offsetof(mpm_points, f), NULL},
#define FIELD_INT_(f, nm, d, u, D) {nm, u, d, FIELD_INT, D, offsetof(mpm_points, f), NULL},
#define FIELD_DERIVED_(f, nm, d, u, D) {nm, u, d, FIELD_DERIVED, D, 0, derive_##f},
static const field_spec output_fields[] = {
  MPM_POINT_FIELDS(FIELD_REAL_, FIELD_INT_, FIELD_DERIVED_)
};
#undef FIELD_REAL_
#undef FIELD_INT_
#undef FIELD_DERIVED_
#define COUNT(a) (sizeof(a) / sizeof((a)[0]))
#define NFIELDS COUNT(output_fields)

/* The fields whose unit or description in MPM_POINT_FIELDS is that of plane
 * strain (per unit thickness, z out of plane), as a 3D frame writes them. */
static const struct { const char *name, *unit, *description; } fields_3d[] = {
  {"szz", "Pa", "Cauchy stress zz"},
  {"mass", "kg", "mass"},
  {"volume", "m^3", "true volume"},
};

/* The unit and description of field f in a frame of dimension dim. */
static void field_text(const field_spec *f, int dim, const char **unit, const char **desc)
{
  *unit = f->unit;
  *desc = f->description;
  for (size_t k = 0; dim == 3 && k < COUNT(fields_3d); k++)
    if (strcmp(f->name, fields_3d[k].name) == 0) {
      *unit = fields_3d[k].unit;
      *desc = fields_3d[k].description;
    }
}


/* ---- directory and paths --------------------------------------------------- */

/* Create one directory; an existing one is fine (a file in the way shows up
 * at the next level, or in make_dirs' final check). */
static int mkdir_one(const char *path, mpm_err *err)
{
  struct stat st;
  int e;
  if (mkdir(path, 0777) == 0 || errno == EEXIST)
    return MPM_OK;
  e = errno;
  if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) /* e.g. EROFS on an existing one */
    return MPM_OK;
  return mpm_err_set(err, MPM_EIO, "cannot create directory '%s': %s", path, strerror(e));
}

/* mkdir -p: create dir and its missing parents. */
static int make_dirs(const char *dir, mpm_err *err)
{
  char *p = malloc(strlen(dir) + 1);
  struct stat st;
  int rc = MPM_OK;
  if (!p)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory creating '%s'", dir);
  strcpy(p, dir);
  for (char *s = p + 1; rc == MPM_OK && *s; s++) {
    if (*s != '/')
      continue;
    *s = '\0';
    rc = mkdir_one(p, err);
    *s = '/';
  }
  if (rc == MPM_OK)
    rc = mkdir_one(p, err);
  free(p);
  if (rc == MPM_OK && stat(dir, &st) != 0)
    rc = mpm_err_set(err, MPM_EIO, "cannot create directory '%s': %s", dir, strerror(errno));
  else if (rc == MPM_OK && !S_ISDIR(st.st_mode))
    rc = mpm_err_set(err, MPM_EIO, "cannot create directory '%s': %s", dir, strerror(ENOTDIR));
  return rc;
}

/* ---- open ------------------------------------------------------------------- */

/* ---- the reserve ---------------------------------------------------------------
 * A run that fills its disk must still record that it failed and why, and
 * HDF5 needs some free space to flush run.h5 once a write has failed (its
 * metadata of the frame under way): the run holds RESERVE_BYTES in a file
 * of its directory while it writes and removes it before it records its
 * end (and when it closes). Best effort: no reserve where there is no room
 * for one. */
enum { RESERVE_BYTES = 64 * 1024 };

static void reserve_take(mpm_io_output *out)
{
  FILE *f = fopen(out->reserve_path, "wb");
  static const char zeros[4096];
  int bad = !f;
  for (size_t n = 0; !bad && n < RESERVE_BYTES; n += sizeof zeros)
    bad = fwrite(zeros, 1, sizeof zeros, f) != sizeof zeros;
  if (f)
    bad |= fclose(f) != 0;
  if (bad)
    unlink(out->reserve_path);
}

static void reserve_free(mpm_io_output *out)
{
  if (out->reserve_path)
    unlink(out->reserve_path);
}

static void output_free(mpm_io_output *out)
{
  if (!out)
    return;
  reserve_free(out);
  free(out->reserve_path);
  mpm_io_h5_close(out->xdmf_group);
  mpm_io_h5_close(out->frames);
  mpm_io_h5_close(out->file);
  if (out->csv)
    fclose(out->csv);
  if (out->xdmf)
    fclose(out->xdmf);
  if (out->bcsv)
    fclose(out->bcsv);
  if (out->bxdmf)
    fclose(out->bxdmf);
  free(out->bcsv_path);
  free(out->bxdmf_path);
  free(out->h5_path);
  free(out->csv_path);
  free(out->xdmf_path);
  free(out->work);
  free(out);
}

static mpm_io_output *output_alloc(const char *dir)
{
  mpm_io_output *out = calloc(1, sizeof *out);
  if (!out)
    return NULL;
  out->file = out->frames = out->xdmf_group = H5I_INVALID_HID;
  out->vertex_frame = -1;
  out->outline_frame = -1;
  out->dim = 2;
  out->fields = output_fields;
  out->nfields = NFIELDS;
  out->h5_path = mpm_io_path_join(dir, "run.h5");
  out->csv_path = mpm_io_path_join(dir, "diagnostics.csv");
  out->xdmf_path = mpm_io_path_join(dir, "run.xdmf");
  out->reserve_path = mpm_io_path_join(dir, ".granmpm-reserve");
  out->bcsv_path = mpm_io_path_join(dir, "bodies.csv");
  out->bxdmf_path = mpm_io_path_join(dir, "bodies.xdmf");
  if (!out->h5_path || !out->csv_path || !out->xdmf_path || !out->reserve_path ||
      !out->bcsv_path || !out->bxdmf_path) {
    output_free(out);
    return NULL;
  }
  return out;
}


static hid_t create_h5(const char *path)
{
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS), fcpl = mpm_io_h5_file_create_plist();
  hid_t file = H5I_INVALID_HID;
  if (fapl >= 0 && fcpl >= 0 && H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V110) >= 0)
    file = H5Fcreate(path, H5F_ACC_TRUNC, fcpl, fapl);
  mpm_io_h5_close(fcpl);
  mpm_io_h5_close(fapl);
  return file;
}

static const char *known(const char *name)
{
  return name ? name : "unknown";
}

/* Coordinates of the n+1 mesh lines x0 + i dx. */
static herr_t write_lines(hid_t g, const char *name, int n, double x0, double dx,
                          const char *desc)
{
  size_t len = n >= 0 ? (size_t)n + 1 : 0;
  double *c = malloc((len ? len : 1) * sizeof *c);
  herr_t rc;
  if (!c)
    return -1;
  for (size_t i = 0; i < len; i++)
    c[i] = x0 + (double)i * dx;
  rc = mpm_io_h5_write_array(g, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, len, c, "m", desc);
  free(c);
  return rc;
}

/* /mesh: the units, origin and unit sizes, the periodic axes and the node
 * lines of each axis; the plane's topology and diagonal rule, or topology
 * "box" and the z axis of a 3D mesh. */
static herr_t write_mesh(hid_t file, const mpm_mesh *m)
{
  hid_t g = H5Gcreate2(file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = g < 0 ? -1 : 0;
  const int three = m->dim == 3;
  if (rc >= 0) /* a negative status in any term makes the OR negative */
    rc = mpm_io_h5_attr_int(g, "nx", m->nx) | mpm_io_h5_attr_int(g, "ny", m->ny) |
         (three ? mpm_io_h5_attr_int(g, "nz", m->nz) : 0) | mpm_io_h5_attr_double(g, "x0", m->x0) |
         mpm_io_h5_attr_double(g, "y0", m->y0) |
         (three ? mpm_io_h5_attr_double(g, "z0", m->z0) : 0) |
         mpm_io_h5_attr_double(g, "dx", m->dx) | mpm_io_h5_attr_double(g, "dy", m->dy) |
         (three ? mpm_io_h5_attr_double(g, "dz", m->dz) : 0);
  if (rc >= 0 && three)
    rc = mpm_io_h5_attr_string(g, "topology", "box");
  else if (rc >= 0)
    rc = mpm_io_h5_attr_string(g, "topology", known(mpm_mesh_topology_name(m->topology))) |
         mpm_io_h5_attr_string(g, "diagonal", known(mpm_mesh_diagonal_name(m->diagonal))) |
         mpm_io_h5_attr_double(g, "mirror_x", m->mirror_x);
  if (rc >= 0)
    rc = mpm_io_h5_attr_int(g, "periodic_x", m->periodic_x) |
         mpm_io_h5_attr_int(g, "periodic_y", m->periodic_y) |
         (three ? mpm_io_h5_attr_int(g, "periodic_z", m->periodic_z) : 0);
  if (rc >= 0)
    rc = write_lines(g, "node_x", m->nx, m->x0, m->dx,
                     three ? "x of the mesh planes normal to x" : "x of the vertical mesh lines");
  if (rc >= 0)
    rc = write_lines(g, "node_y", m->ny, m->y0, m->dy,
                     three ? "y of the mesh planes normal to y" : "y of the horizontal mesh lines");
  if (rc >= 0 && three)
    rc = write_lines(g, "node_z", m->nz, m->z0, m->dz, "z of the mesh planes normal to z");
  mpm_io_h5_close(g);
  return rc;
}

/* The time now, UTC, ISO 8601. */
static void utc_now(char *buf, size_t len)
{
  time_t now = time(NULL);
  struct tm tm;
  if (!gmtime_r(&now, &tm) || !strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tm))
    snprintf(buf, len, "unknown");
}

static void host_name(char *buf, size_t len)
{
  if (gethostname(buf, len) != 0)
    snprintf(buf, len, "unknown");
  buf[len - 1] = '\0';
}

/* How a run stands: end_time, status and failure (why it failed), each with
 * room for any value from the start, so that the end of a run rewrites them
 * in place and needs no new space in the file (a full disk). */
enum { END_TIME_ROOM = 32, STATUS_ROOM = 16, FAILURE_ROOM = MPM_ERR_MSG };

static herr_t write_end(hid_t file, const char *end_time, const char *status,
                        const char *failure)
{
  herr_t rc = mpm_io_h5_attr_string_room(file, "status", status, STATUS_ROOM);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string_room(file, "failure", failure, FAILURE_ROOM);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string_room(file, "end_time", end_time, END_TIME_ROOM);
  return rc;
}

/* Provenance of a new run: program, command line, host, threads, start. */
static herr_t write_origin(hid_t file, const mpm_io_origin *o, const char *input)
{
  char now[32], host[256];
  utc_now(now, sizeof now);
  host_name(host, sizeof host);
  herr_t rc = mpm_io_h5_attr_string(file, "version", PACKAGE_VERSION);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "revision", o->revision ? o->revision : "unknown");
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "command_line", o->command_line);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "input", input);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "host", host);
  if (rc >= 0)
    rc = mpm_io_h5_attr_int(file, "threads", o->threads);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "start_time", now);
  if (rc >= 0)
    rc = write_end(file, "", "running", "");
  if (rc >= 0)
    rc = mpm_io_h5_attr_int(file, "resumed", 0);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "resume_log", "");
  return rc;
}

static herr_t write_header(mpm_io_output *out, const mpm_io_origin *o, const char *input,
                           const mpm_mesh *m)
{
  herr_t rc = write_origin(out->file, o, input);
  if (rc >= 0 && m)
    rc = write_mesh(out->file, m);
  if (rc >= 0) {
    out->frames = H5Gcreate2(out->file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    out->xdmf_group = H5Gcreate2(out->file, "xdmf", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    rc = (out->frames < 0 || out->xdmf_group < 0) ? -1 : 0;
  }
  if (rc >= 0)
    rc = H5Fflush(out->file, H5F_SCOPE_LOCAL);
  return rc;
}

static int output_open(mpm_io_output **pout, const char *dir, const mpm_io_origin *o,
                       const char *input, const mpm_mesh *m, int dim, const mpm_io_h5_quiet *q,
                       mpm_err *err)
{
  int rc = make_dirs(dir, err);
  mpm_io_output *out;
  if (rc != MPM_OK)
    return rc;
  out = output_alloc(dir);
  if (!out)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory opening output in '%s'", dir);
  rc = mpm_io_out_open_text(&out->csv, out->csv_path, mpm_diag_csv_header(dim), err);
  if (rc == MPM_OK && unlink(out->bcsv_path) != 0 && errno != ENOENT)  /* an earlier run's */
    rc = mpm_err_set(err, MPM_EIO, "cannot remove '%s': %s", out->bcsv_path, strerror(errno));
  if (rc == MPM_OK)
    rc = mpm_io_out_xdmf_open(out, err);
  if (rc == MPM_OK) {
    out->file = create_h5(out->h5_path);
    if (out->file < 0)
      rc = mpm_io_h5_fail(err, q, "cannot create", out->h5_path);
  }
  if (rc == MPM_OK && write_header(out, o, input, m) < 0)
    rc = mpm_io_h5_fail(err, q, "cannot write header of", out->h5_path);
  if (rc == MPM_OK)
    reserve_take(out);
  if (rc != MPM_OK) {
    output_free(out);
    return rc;
  }
  *pout = out;
  return MPM_OK;
}

/* mpm_io_output_open and _open_dim: a mesh m of either dimension, or none
 * and the dimension of the stores. */
static int open_any(mpm_io_output **out, const char *dir, const mpm_io_origin *origin,
                    const char *input_text, const mpm_mesh *m, int dim, mpm_err *err)
{
  mpm_io_h5_quiet q;
  int rc;
  if (!out || !origin)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_open: no output handle or origin");
  *out = NULL;
  if (!dir || !dir[0])
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_open: empty output directory");
  mpm_io_h5_quiet_begin(&q);
  rc = output_open(out, dir, origin, input_text, m, dim, &q, err);
  mpm_io_h5_quiet_end(&q);
  if (rc == MPM_OK)
    (*out)->dim = dim;
  return rc;
}

int mpm_io_output_open(mpm_io_output **out, const char *dir, const mpm_io_origin *origin,
                       const char *input_text, const mpm_mesh *m, mpm_err *err)
{
  return open_any(out, dir, origin, input_text, m, m && m->dim == 3 ? 3 : 2, err);
}

int mpm_io_dir_lock(const char *dir, int *fd, mpm_err *err)
{
  *fd = -1;
  int rc = make_dirs(dir, err);
  char *path = rc == MPM_OK ? mpm_io_path_join(dir, ".granmpm-lock") : NULL;
  if (rc == MPM_OK && !path)
    rc = mpm_err_set(err, MPM_ENOMEM, "out of memory locking '%s'", dir);
  int f = rc == MPM_OK ? open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666) : -1;
  if (rc == MPM_OK && f < 0)
    rc = mpm_err_set(err, MPM_EIO, "cannot create '%s': %s", path, strerror(errno));
  struct flock l = {.l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = 0, .l_len = 0};
  if (rc == MPM_OK && fcntl(f, F_SETLK, &l) != 0) {
    const int e = errno;
    char holder[256] = "";
    const ssize_t n = pread(f, holder, sizeof holder - 1, 0);
    holder[n > 0 ? n : 0] = '\0';
    holder[strcspn(holder, "\n")] = '\0';
    rc = e == EACCES || e == EAGAIN
             ? mpm_err_set(err, MPM_EINPUT, "output directory '%s' is in use by %s: one run or "
                           "resume at a time writes a directory", dir,
                           holder[0] ? holder : "another granmpm")
             : mpm_err_set(err, MPM_EIO, "cannot lock '%s': %s", path, strerror(e));
  }
  if (rc == MPM_OK) {   /* who holds it, for the next one's message */
    char host[128] = "unknown host", text[256];
    gethostname(host, sizeof host - 1);
    host[sizeof host - 1] = '\0';
    const int len = snprintf(text, sizeof text, "granmpm pid %ld on host %s\n", (long)getpid(),
                             host);
    if (ftruncate(f, 0) != 0 || pwrite(f, text, (size_t)len, 0) != len)
      rc = mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(errno));
  }
  if (rc == MPM_OK)
    *fd = f;
  else if (f >= 0)
    close(f);
  free(path);
  return rc;
}

void mpm_io_dir_unlock(int fd)
{
  if (fd >= 0)
    close(fd);   /* the lock goes with it; the file stays, naming the last holder */
}

int mpm_io_output_occupied(const char *dir, const char **what)
{
  const char *const names[] = {"run.h5", "checkpoint.h5"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
    char *p = mpm_io_path_join(dir, names[k]);
    struct stat st;
    int there = p && stat(p, &st) == 0;
    free(p);
    if (there) {
      if (what)
        *what = names[k];
      return 1;
    }
  }
  return 0;
}

/* ---- reopening a run to append to it ---------------------------------------- */

/* Frames from `first` on (with their XY views and connectivity) removed:
 * written after the checkpoint a run continues from. */
static herr_t drop_frames(mpm_io_output *out, long first)
{
  char name[32];
  for (long k = first;; k++) {
    snprintf(name, sizeof name, "%06ld", k);
    if (H5Lexists(out->frames, name, H5P_DEFAULT) <= 0)
      return 0;
    if (H5Ldelete(out->frames, name, H5P_DEFAULT) < 0)
      return -1;
    const char *views[] = {"xy_%06ld", "xyz_%06ld", "vertex_%06ld", "bodies_xyz_%06ld",
                           "bodies_cells_%06ld", "bodies_id_%06ld"};
    for (int v = 0; v < (int)(sizeof views / sizeof views[0]); v++) {
      snprintf(name, sizeof name, views[v], k);
      if (H5Lexists(out->xdmf_group, name, H5P_DEFAULT) > 0 &&
          H5Ldelete(out->xdmf_group, name, H5P_DEFAULT) < 0)
        return -1;
    }
  }
}

/* The resumption recorded: resumed + 1, a line "START host=H threads=N: COMMAND"
 * in resume_log, and the run running again. */
static herr_t record_resume(hid_t file, const mpm_io_origin *o)
{
  char now[32], host[256];
  int resumed = 0;
  utc_now(now, sizeof now);
  host_name(host, sizeof host);
  mpm_io_h5_attr_read(file, "resumed", H5T_NATIVE_INT, &resumed);
  char *old = mpm_io_h5_attr_text(file, "resume_log");
  const char *cmd = o->command_line ? o->command_line : "";
  size_t len = (old ? strlen(old) : 0) + strlen(now) + strlen(host) + strlen(cmd) + 64;
  char *log = malloc(len);
  herr_t rc = log ? 0 : -1;
  if (log)
    snprintf(log, len, "%s%s host=%s threads=%d: %s\n", old ? old : "", now, host, o->threads,
             cmd);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "resume_log", log);
  if (rc >= 0)
    rc = mpm_io_h5_attr_int(file, "resumed", resumed + 1);
  if (rc >= 0)
    rc = write_end(file, "", "running", "");
  free(old);
  free(log);
  return rc;
}

/* diagnostics.csv cut after its header and nframes rows, open for appending. */
static int reopen_csv(mpm_io_output *out, long nframes, mpm_err *err)
{
  out->csv = fopen(out->csv_path, "r+");
  if (!out->csv)
    return mpm_err_set(err, MPM_EIO, "cannot open '%s': %s", out->csv_path, strerror(errno));
  long rows = -1;                              /* the header is row -1 */
  int ch;
  while (rows < nframes && (ch = getc(out->csv)) != EOF)
    rows += ch == '\n';
  long end = ftell(out->csv);
  if (rows < nframes)
    return mpm_err_set(err, MPM_EIO, "'%s' has %ld rows, the run %ld frames", out->csv_path,
                       rows < 0 ? 0 : rows, nframes);
  if (end < 0 || fflush(out->csv) != 0 || ftruncate(fileno(out->csv), end) != 0 ||
      fseek(out->csv, 0, SEEK_END) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot cut '%s': %s", out->csv_path, strerror(errno));
  return MPM_OK;
}

static int output_reopen(mpm_io_output *out, const mpm_io_origin *o, long nframes,
                         const mpm_io_h5_quiet *q, mpm_err *err)
{
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0 && H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_V110) >= 0)
    out->file = H5Fopen(out->h5_path, H5F_ACC_RDWR, fapl);
  mpm_io_h5_close(fapl);
  if (out->file < 0)
    return mpm_io_h5_fail(err, q, "cannot open", out->h5_path);
  out->frames = H5Gopen2(out->file, "frames", H5P_DEFAULT);
  out->xdmf_group = H5Gopen2(out->file, "xdmf", H5P_DEFAULT);
  H5G_info_t info;
  if (out->frames < 0 || out->xdmf_group < 0 || H5Gget_info(out->frames, &info) < 0)
    return mpm_io_h5_fail(err, q, "no frames in", out->h5_path);
  if (H5Lexists(out->file, "mesh", H5P_DEFAULT) > 0 &&
      H5Aexists_by_name(out->file, "mesh", "nz", H5P_DEFAULT) > 0)
    out->dim = 3;                                /* a box mesh: a 3D run */
  if ((long long)info.nlinks < nframes)
    return mpm_err_set(err, MPM_EIO, "'%s' has %llu frames, the checkpoint counts %ld",
                       out->h5_path, (unsigned long long)info.nlinks, nframes);
  if (drop_frames(out, nframes) < 0 || record_resume(out->file, o) < 0 ||
      H5Fflush(out->file, H5F_SCOPE_LOCAL) < 0)
    return mpm_io_h5_fail(err, q, "cannot update", out->h5_path);
  int rc = reopen_csv(out, nframes, err);
  if (rc == MPM_OK)
    rc = mpm_io_out_bodies_reopen(out, nframes, err);
  if (rc == MPM_OK)
    rc = mpm_io_out_xdmf_rebuild(out, nframes, q, err);
  if (rc == MPM_OK)
    reserve_take(out);
  return rc;
}

int mpm_io_output_reopen(mpm_io_output **out, const char *dir, const mpm_io_origin *origin,
                         long nframes, mpm_err *err)
{
  mpm_io_h5_quiet q;
  if (!out || !origin || !dir || nframes < 0)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_reopen: invalid arguments");
  *out = output_alloc(dir);
  if (!*out)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory opening output in '%s'", dir);
  mpm_io_h5_quiet_begin(&q);
  int rc = output_reopen(*out, origin, nframes, &q, err);
  mpm_io_h5_quiet_end(&q);
  if (rc != MPM_OK) {
    output_free(*out);
    *out = NULL;
  }
  return rc;
}

int mpm_io_output_end(mpm_io_output *out, const char *status, const char *failure,
                      mpm_err *err)
{
  mpm_io_h5_quiet q;
  char now[32];
  if (!out)
    return MPM_OK;
  utc_now(now, sizeof now);
  reserve_free(out);                             /* room to record the end on a full disk */
  mpm_io_h5_quiet_begin(&q);
  int bad = write_end(out->file, now, status, failure) < 0 ||
            H5Fflush(out->file, H5F_SCOPE_LOCAL) < 0;
  int rc = bad ? mpm_io_h5_fail(err, &q, "cannot write the end of the run to", out->h5_path)
               : MPM_OK;
  mpm_io_h5_quiet_end(&q);
  return rc;
}

/* ---- frames ------------------------------------------------------------------ */

static int work_reserve(mpm_io_output *out, size_t n)
{
  if (n <= out->work_cap)
    return MPM_OK;
  double *w = realloc(out->work, n * sizeof *w);
  if (!w)
    return MPM_ENOMEM;
  out->work = w;
  out->work_cap = n;
  return MPM_OK;
}

/* Pointer to the values of one field; derived fields are computed into work. */
static const void *field_values(mpm_io_output *out, const field_spec *f, const mpm_points *pts)
{
  const char *base = (const char *)pts + f->offset;
  if (f->kind == FIELD_REAL)
    return *(double *const *)base;
  if (f->kind == FIELD_INT)
    return *(int *const *)base;
  f->derive(pts, out->work);
  return out->work;
}

static int write_fields(mpm_io_output *out, hid_t g, const mpm_points *pts,
                        const mpm_io_h5_quiet *q, mpm_err *err)
{
  for (size_t k = 0; k < NFIELDS; k++) {
    const field_spec *f = &output_fields[k];
    int isint = f->kind == FIELD_INT;
    const char *unit, *desc;
    if (f->dim > pts->dim)
      continue;
    field_text(f, pts->dim, &unit, &desc);
    herr_t rc = mpm_io_h5_write_array(g, f->name, isint ? H5T_STD_I32LE : H5T_IEEE_F64LE,
                            isint ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE, pts->n,
                            field_values(out, f, pts), unit, desc);
    if (rc < 0)
      return mpm_err_set(err, MPM_EIO, "cannot write field '%s' of frame %d to '%s': %s", f->name,
                         out->nframes, out->h5_path, mpm_io_h5_reason(q));
  }
  return MPM_OK;
}

static int write_frame_h5(mpm_io_output *out, const mpm_points *pts, double t,
                          const mpm_io_h5_quiet *q, mpm_err *err)
{
  char name[32];
  hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  hid_t g = H5I_INVALID_HID;
  int rc = MPM_OK;
  snprintf(name, sizeof name, "%06d", out->nframes);
  /* creation order lets readers list the fields in the order written */
  if (gcpl >= 0 &&
      H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) >= 0)
    g = H5Gcreate2(out->frames, name, H5P_DEFAULT, gcpl, H5P_DEFAULT);
  mpm_io_h5_close(gcpl);
  if (g < 0 || mpm_io_h5_attr_double(g, "time", t) < 0 ||
      mpm_io_h5_attr_scalar(g, "npoints", H5T_NATIVE_ULLONG, &(unsigned long long){pts->n}) < 0 ||
      (pts->dim != 2 && mpm_io_h5_attr_int(g, "dimension", pts->dim) < 0))
    rc = mpm_io_h5_fail(err, q, "cannot create frame group in", out->h5_path);
  if (rc == MPM_OK)
    rc = write_fields(out, g, pts, q, err);
  mpm_io_h5_close(g);
  if (rc == MPM_OK)
    rc = mpm_io_out_vertices(out, pts->n, q, err);
  if (rc == MPM_OK && pts->n > 0 &&
      mpm_io_out_xy_view(out->xdmf_group, out->nframes, pts->n, pts->dim) < 0)
    rc = mpm_io_h5_fail(err, q, "cannot write XY view to", out->h5_path);
  if (rc == MPM_OK && H5Fflush(out->file, H5F_SCOPE_LOCAL) < 0)
    rc = mpm_io_h5_fail(err, q, "cannot flush", out->h5_path);
  return rc;
}

static int write_csv_row(mpm_io_output *out, const mpm_diag *d, mpm_err *err)
{
  char row[512];
  if (mpm_diag_csv_row(d, out->dim, row, sizeof row) != MPM_OK)
    return mpm_err_set(err, MPM_EINVAL, "diagnostics row of frame %d too long", out->nframes);
  if (fputs(row, out->csv) < 0 || fflush(out->csv) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", out->csv_path, strerror(errno));
  return MPM_OK;
}

int mpm_io_output_frame(mpm_io_output *out, const mpm_points *pts, const mpm_diag *d, mpm_err *err)
{
  mpm_io_h5_quiet q;
  int rc;
  if (!out || !pts || !d)
    return mpm_err_set(err, MPM_EINVAL,
                       "mpm_io_output_frame: missing output, points or diagnostics");
  if (pts->dim != out->dim)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_frame: a %dD store for the %dD run '%s'",
                       pts->dim, out->dim, out->h5_path);
  if (work_reserve(out, pts->n) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory writing frame %d", out->nframes);
  mpm_io_h5_quiet_begin(&q);
  rc = write_frame_h5(out, pts, d->t, &q, err);
  mpm_io_h5_quiet_end(&q);
  if (rc == MPM_OK)
    rc = write_csv_row(out, d, err);
  if (rc == MPM_OK)
    rc = mpm_io_out_xdmf_frame(out, d->t, pts->n, pts->dim, err);
  if (rc == MPM_OK)
    out->nframes++;
  return rc;
}

/* ---- close -------------------------------------------------------------------- */

static int close_text(FILE **f, const char *path, int rc, mpm_err *err)
{
  if (*f && fclose(*f) != 0 && rc == MPM_OK)
    rc = mpm_err_set(err, MPM_EIO, "cannot close '%s': %s", path, strerror(errno));
  *f = NULL;
  return rc;
}

static int close_h5(mpm_io_output *out, const mpm_io_h5_quiet *q, mpm_err *err)
{
  int bad = 0;
  bad |= mpm_io_h5_close(out->xdmf_group) < 0;
  bad |= mpm_io_h5_close(out->frames) < 0;
  bad |= mpm_io_h5_close(out->file) < 0;
  out->xdmf_group = out->frames = out->file = H5I_INVALID_HID;
  return bad ? mpm_io_h5_fail(err, q, "cannot close", out->h5_path) : MPM_OK;
}

int mpm_io_output_close(mpm_io_output *out, mpm_err *err)
{
  mpm_io_h5_quiet q;
  int rc;
  if (!out)
    return MPM_OK;
  mpm_io_h5_quiet_begin(&q);
  rc = close_h5(out, &q, err);
  mpm_io_h5_quiet_end(&q);
  rc = close_text(&out->csv, out->csv_path, rc, err);
  rc = close_text(&out->xdmf, out->xdmf_path, rc, err);
  rc = close_text(&out->bcsv, out->bcsv_path, rc, err);
  rc = close_text(&out->bxdmf, out->bxdmf_path, rc, err);
  output_free(out);
  return rc;
}
