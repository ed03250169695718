/* checkpoint.c: DIR/checkpoint.h5, the state a run continues from
 * (core/state.h) and its resolved input.
 *
 *   root attributes  format, written_by; t, dt, step, n_sub, mass0,
 *                    mass_removed, nremoved, seeded, outlet_open, frames,
 *                    frame_next, check_next, npoints, next_id; dimension
 *                    (3 for a 3D store, absent for a 2D one)
 *   /input           the resolved input text (NUL-terminated characters)
 *   /points/NAME     one 1-D dataset per stored point field (MPM_POINT_FIELDS
 *                    and MPM_POINT_STATE_FIELDS that the store's dimension
 *                    has, by its output name), full precision
 *   /series/t, /series/mass  time and region mass of every frame so far
 *   /bodies/state, /bodies/pushed  with bodies: per body, in the input's order,
 *                    c[3], theta, v[4], f[3], tq[3] (14 values) and the count
 *                    of points put back on it (mpm_body_state)
 *
 * The file starts with a user block of USERBLOCK bytes, which HDF5 skips:
 * two lines of text, "granmpm checkpoint 2" and "checksum H of bytes 512
 * to N" (H a 64-bit checksum in hex of every byte after the block, N the
 * file's length). A checkpoint is checked when read: the checksum of the
 * file first, before HDF5 parses any of it (HDF5 1.10 reads a damaged
 * object header of this format past the end of its buffers), then the
 * values (every real finite; masses and volumes positive; states 0 or 1;
 * ids below next_id and unique; times, steps and counts in range), so that
 * a damaged or edited file is named as such rather than resumed into a
 * blow-up. A checkpoint without the block (format 1) is read with its
 * values checked.
 *
 * The file is assembled in memory (HDF5's core driver, no backing store),
 * then written with plain writes to checkpoint.h5.tmp in the same directory,
 * synced, and renamed over checkpoint.h5; the directory is synced too. A
 * full disk or any failed write is then an ordinary error from write(2)
 * (the temporary file removed, the previous checkpoint intact), never a
 * half-written HDF5 file. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/h5err.h"
#include "io/io.h"

#define FORMAT "granmpm checkpoint 2"
#define FORMAT_1 "granmpm checkpoint 1"   /* without the user block */
#define USERBLOCK 512                     /* HDF5's smallest user block */

/* Every stored point field: output name, int or double, where in the store. */
typedef struct stored_field {
  const char *name;
  int isint;
  int kind;        /* which stores have it (MPM_POINT_EVERY, _3D, _DEFGRAD) */
  size_t offset;
} stored_field;

/* 1 if a store of dimension dim, with the deformation gradients or not, has
 * field f (mpm_points_has). */
static int stored_in(const stored_field *f, int dim, int defgrad)
{
  return f->kind == MPM_POINT_EVERY || (f->kind == MPM_POINT_3D && dim == 3) ||
         (f->kind == MPM_POINT_DEFGRAD && defgrad);
}

#define REAL_(f, nm, d, u, D) {nm, 0, D, offsetof(mpm_points, f)},
#define INT_(f, nm, d, u, D) {nm, 1, D, offsetof(mpm_points, f)},
static const stored_field stored[] = {MPM_POINT_FIELDS(REAL_, INT_, MPM_POINT_SKIP_)
                                      MPM_POINT_STATE_FIELDS(REAL_)};
#undef REAL_
#undef INT_
#define NSTORED (sizeof stored / sizeof stored[0])

static void *field_array(const mpm_points *pts, const stored_field *f)
{
  return *(void *const *)(const void *)((const char *)pts + f->offset);
}

/* The scalar members of mpm_run_state, by attribute name; kind 0 double,
 * 1 long, 2 int. */
#define D_(m) {#m, 0, offsetof(mpm_run_state, m)}
#define L_(m) {#m, 1, offsetof(mpm_run_state, m)}
#define I_(m) {#m, 2, offsetof(mpm_run_state, m)}
static const struct { const char *name; int kind; size_t offset; } scalars[] = {
  D_(t), D_(dt), L_(step), I_(n_sub), D_(mass0), D_(mass_removed), L_(nremoved), I_(seeded),
  I_(outlet_open), L_(frames), L_(frame_next), L_(check_next),
};
#undef D_
#undef L_
#undef I_
#define NSCALARS (sizeof scalars / sizeof scalars[0])

static hid_t scalar_type(int kind)
{
  return kind == 0 ? H5T_NATIVE_DOUBLE : kind == 1 ? H5T_NATIVE_LONG : H5T_NATIVE_INT;
}

/* ---- checksum ------------------------------------------------------------ */

/* len bytes into checksum h, eight at a time as a little-endian word (so
 * the same on any machine; FNV-1a's prime on words, and the high bits
 * folded down at each), so a damaged byte anywhere changes it. A file
 * summed in pieces gives the same when every piece but the last is a
 * multiple of 8 bytes. */
static uint64_t sum_bytes(uint64_t h, const void *p, size_t len)
{
  const unsigned char *b = p;
  const uint64_t prime = 0x100000001b3u;
  for (; len >= 8; b += 8, len -= 8) {
    uint64_t w = 0;
    for (int k = 7; k >= 0; k--)
      w = w << 8 | b[k];
    h = (h ^ w) * prime;
    h ^= h >> 29;
  }
  for (; len > 0; b++, len--)
    h = (h ^ *b) * prime;
  return h;
}

#define SUM_SEED 0xcbf29ce484222325u

/* The user block of a file of len bytes whose bytes after the block have
 * checksum sum, NUL-padded to USERBLOCK bytes. */
static void userblock(char *block, uint64_t sum, size_t len)
{
  memset(block, 0, USERBLOCK);
  snprintf(block, USERBLOCK, "%s\nchecksum %016llx of bytes %d to %zu\n", FORMAT,
           (unsigned long long)sum, USERBLOCK, len);
}

int mpm_io_checkpoint_seal(void *file, size_t len)
{
  if (!file || len < USERBLOCK)
    return -1;
  userblock(file, sum_bytes(SUM_SEED, (char *)file + USERBLOCK, len - USERBLOCK), len);
  return 0;
}

/* ---- writing --------------------------------------------------------------- */

static void *read_values(hid_t g, const char *name, hid_t type, size_t size, size_t n);

/* The bodies' state: BODY_VALUES doubles and a count per body. */
enum { BODY_VALUES = 14 };

static void body_values(mpm_body_state *b, double *v, int put)
{
  double *const at[] = {&b->c[0], &b->c[1], &b->c[2], &b->theta, &b->v[0], &b->v[1], &b->v[2],
                        &b->v[3], &b->f[0], &b->f[1], &b->f[2], &b->tq[0], &b->tq[1], &b->tq[2]};
  _Static_assert(sizeof at / sizeof at[0] == BODY_VALUES, "one slot per value");
  for (int k = 0; k < BODY_VALUES; k++) {
    if (put)
      *at[k] = v[k];
    else
      v[k] = *at[k];
  }
}

static herr_t write_bodies(hid_t file, const mpm_run_state *st)
{
  double v[MPM_MAX_BODIES * BODY_VALUES];
  long pushed[MPM_MAX_BODIES];
  for (int k = 0; k < st->nbody; k++) {
    mpm_body_state b = st->body[k];
    body_values(&b, v + BODY_VALUES * k, 0);
    pushed[k] = b.npushed;
  }
  hid_t g = H5Gcreate2(file, "bodies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = g < 0 ? -1 : 0;
  if (rc >= 0)
    rc = mpm_io_h5_write_array(g, "state", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                               (size_t)(BODY_VALUES * st->nbody), v, NULL,
                               "per body: c[3], theta, v[4], f[3], tq[3]");
  if (rc >= 0)
    rc = mpm_io_h5_write_array(g, "pushed", H5T_STD_I64LE, H5T_NATIVE_LONG, (size_t)st->nbody,
                               pushed, NULL, "points put back on each body");
  mpm_io_h5_close(g);
  return rc;
}

/* The bodies of a checkpoint (none when it has no /bodies). */
static int read_bodies(hid_t file, mpm_run_state *st, const char *path, const mpm_io_h5_quiet *q,
                       mpm_err *err)
{
  st->nbody = 0;
  if (H5Lexists(file, "bodies", H5P_DEFAULT) <= 0)
    return MPM_OK;
  hid_t g = H5Gopen2(file, "bodies", H5P_DEFAULT);
  const long long n = g < 0 ? -1 : mpm_io_h5_array_length(g, "pushed");
  double *v = NULL;
  long *pushed = NULL;
  if (n >= 0 && n <= MPM_MAX_BODIES) {
    v = read_values(g, "state", H5T_NATIVE_DOUBLE, sizeof *v, (size_t)(BODY_VALUES * n));
    pushed = read_values(g, "pushed", H5T_NATIVE_LONG, sizeof *pushed, (size_t)n);
  }
  mpm_io_h5_close(g);
  int rc = MPM_OK;
  if (!v || !pushed)
    rc = mpm_err_set(err, MPM_EIO, "'%s': cannot read the bodies' state: %s", path,
                     mpm_io_h5_reason(q));
  for (long long k = 0; rc == MPM_OK && k < n; k++) {
    body_values(&st->body[k], v + BODY_VALUES * k, 1);
    st->body[k].npushed = pushed[k];
  }
  if (rc == MPM_OK)
    st->nbody = (int)n;
  free(v);
  free(pushed);
  return rc;
}

static herr_t write_state(hid_t file, const mpm_run_state *st, const char *input,
                          const char *written_by)
{
  const mpm_points *P = st->pts;
  herr_t rc = mpm_io_h5_attr_string(file, "format", FORMAT);
  if (rc >= 0)
    rc = mpm_io_h5_attr_string(file, "written_by", written_by);
  if (rc >= 0)
    rc = mpm_io_h5_write_array(file, "input", H5T_NATIVE_CHAR, H5T_NATIVE_CHAR,
                               strlen(input) + 1, input, NULL, "the resolved input");
  for (size_t k = 0; rc >= 0 && k < NSCALARS; k++)
    rc = mpm_io_h5_attr_scalar(file, scalars[k].name, scalar_type(scalars[k].kind),
                               (const char *)st + scalars[k].offset);
  if (rc >= 0)
    rc = mpm_io_h5_attr_long(file, "npoints", (long)P->n);
  if (rc >= 0)
    rc = mpm_io_h5_attr_int(file, "next_id", P->next_id);
  if (rc >= 0 && P->dim != 2)
    rc = mpm_io_h5_attr_int(file, "dimension", P->dim);
  hid_t g = rc < 0 ? H5I_INVALID_HID
                   : H5Gcreate2(file, "points", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (size_t k = 0; g >= 0 && rc >= 0 && k < NSTORED; k++)
    if (stored_in(&stored[k], P->dim, P->defgrad))
      rc = mpm_io_h5_write_array(g, stored[k].name, stored[k].isint ? H5T_STD_I32LE : H5T_IEEE_F64LE,
                               stored[k].isint ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE, P->n,
                               field_array(P, &stored[k]), NULL, NULL);
  rc = g < 0 ? -1 : rc;
  mpm_io_h5_close(g);
  g = rc < 0 ? H5I_INVALID_HID : H5Gcreate2(file, "series", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g >= 0 && rc >= 0)
    rc = mpm_io_h5_write_array(g, "t", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, st->nseries,
                               st->series_t, "s", "time of each frame");
  if (g >= 0 && rc >= 0)
    rc = mpm_io_h5_write_array(g, "mass", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, st->nseries,
                               st->series_m, "kg/m", "mass in the region at each frame");
  rc = g < 0 ? -1 : rc;
  mpm_io_h5_close(g);
  return rc < 0 || st->nbody == 0 ? rc : write_bodies(file, st);
}

/* The checkpoint file in memory, its user block and HDF5 image (*image, *len;
 * free it). */
static int image_of(const mpm_run_state *st, const char *input, const char *written_by,
                    const char *name, void **image, size_t *len, mpm_err *err)
{
  mpm_io_h5_quiet q;
  mpm_io_h5_quiet_begin(&q);
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS), fcpl = mpm_io_h5_file_create_plist();
  hid_t file = H5I_INVALID_HID;
  /* the earliest format that holds the data: the image of a file with a
   * checksummed superblock (format 1.8 and later) fails its checksum when
   * read back (HDF5 1.10.8), so the input text is a dataset rather than an
   * attribute (attributes over 64 KiB need the 1.8 format) */
  if (fapl >= 0 && fcpl >= 0 && H5Pset_userblock(fcpl, USERBLOCK) >= 0 &&
      H5Pset_fapl_core(fapl, (size_t)1 << 20, 0) >= 0 &&
      H5Pset_libver_bounds(fapl, H5F_LIBVER_EARLIEST, H5F_LIBVER_V18) >= 0)
    file = H5Fcreate(name, H5F_ACC_TRUNC, fcpl, fapl);
  mpm_io_h5_close(fcpl);
  mpm_io_h5_close(fapl);
  int rc = MPM_OK;
  ssize_t n = -1;
  *image = NULL;
  if (file < 0 || write_state(file, st, input, written_by) < 0 ||
      H5Fflush(file, H5F_SCOPE_GLOBAL) < 0 || (n = H5Fget_file_image(file, NULL, 0)) <= 0)
    rc = mpm_io_h5_fail(err, &q, "cannot assemble checkpoint", name);
  else if (!(*image = malloc(USERBLOCK + (size_t)n)))
    rc = mpm_err_set(err, MPM_ENOMEM, "no memory for a checkpoint of %zd bytes", n);
  else if (H5Fget_file_image(file, (char *)*image + USERBLOCK, (size_t)n) != n)
    rc = mpm_io_h5_fail(err, &q, "cannot assemble checkpoint", name);
  else   /* the image starts at the superblock: the user block goes before it */
    mpm_io_checkpoint_seal(*image, USERBLOCK + (size_t)n);
  if (mpm_io_h5_close(file) < 0 && rc == MPM_OK)
    rc = mpm_io_h5_fail(err, &q, "cannot assemble checkpoint", name);
  mpm_io_h5_quiet_end(&q);
  if (rc != MPM_OK) {
    free(*image);
    *image = NULL;
  }
  *len = n > 0 ? USERBLOCK + (size_t)n : 0;
  return rc;
}

/* len bytes to a new file path, synced. */
static int write_file(const char *path, const void *buf, size_t len, mpm_err *err)
{
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd < 0)
    return mpm_err_set(err, MPM_EIO, "cannot create '%s': %s", path, strerror(errno));
  const char *p = buf;
  int e = 0;
  while (len > 0 && !e) {
    ssize_t w = write(fd, p, len);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      e = w < 0 ? errno : ENOSPC;
    else {
      p += w;
      len -= (size_t)w;
    }
  }
  if (!e && fsync(fd) != 0)
    e = errno;
  if (close(fd) != 0 && !e)
    e = errno;
  return e ? mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(e)) : MPM_OK;
}

/* The directory's entries made durable (the rename); a file system that
 * cannot sync a directory is not an error. */
static void sync_dir(const char *dir)
{
  int fd = open(dir, O_RDONLY);
  if (fd >= 0) {
    fsync(fd);
    close(fd);
  }
}

int mpm_io_checkpoint_write(const char *dir, const mpm_run_state *st, const char *input_text,
                            const char *written_by, mpm_err *err)
{
  if (!dir || !st || !st->pts)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_checkpoint_write: invalid arguments");
  char *path = mpm_io_path_join(dir, "checkpoint.h5"), *tmp = mpm_io_path_join(dir, "checkpoint.h5.tmp");
  void *image = NULL;
  size_t len = 0;
  int rc = path && tmp ? MPM_OK : mpm_err_set(err, MPM_ENOMEM, "out of memory for a checkpoint");
  if (rc == MPM_OK)
    rc = image_of(st, input_text, written_by, tmp, &image, &len, err);
  if (rc == MPM_OK)
    rc = write_file(tmp, image, len, err);
  if (rc == MPM_OK && rename(tmp, path) != 0)
    rc = mpm_err_set(err, MPM_EIO, "cannot rename '%s' to '%s': %s", tmp, path, strerror(errno));
  if (rc == MPM_OK)
    sync_dir(dir);
  else if (tmp)
    unlink(tmp);
  free(image);
  free(path);
  free(tmp);
  return rc;
}

int mpm_io_checkpoint_remove(const char *dir, mpm_err *err)
{
  char *path = mpm_io_path_join(dir, "checkpoint.h5");
  if (!path)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  int rc = unlink(path) == 0 || errno == ENOENT
               ? MPM_OK
               : mpm_err_set(err, MPM_EIO, "cannot remove '%s': %s", path, strerror(errno));
  free(path);
  return rc;
}

/* ---- reading --------------------------------------------------------------- */

/* n values of the 1-D dataset name of g into a new array of size bytes each. */
static void *read_values(hid_t g, const char *name, hid_t type, size_t size, size_t n)
{
  if (mpm_io_h5_array_length(g, name) != (long long)n)
    return NULL;
  void *v = malloc(n ? n * size : 1);
  hid_t d = v ? H5Dopen2(g, name, H5P_DEFAULT) : H5I_INVALID_HID;
  if (d < 0 || !mpm_io_h5_type_ok(d, type) ||
      (n > 0 && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0)) {
    free(v);
    v = NULL;
  }
  mpm_io_h5_close(d);
  return v;
}

static int read_points(hid_t file, mpm_run_state *st, const char *path, const mpm_io_h5_quiet *q,
                       mpm_err *err)
{
  long n = -1;
  int next_id = 0, dim = 2;
  hid_t g = H5Gopen2(file, "points", H5P_DEFAULT);
  if (g < 0 || mpm_io_h5_attr_read(file, "npoints", H5T_NATIVE_LONG, &n) < 0 || n < 0 ||
      mpm_io_h5_attr_read(file, "next_id", H5T_NATIVE_INT, &next_id) < 0) {
    mpm_io_h5_close(g);
    return mpm_err_set(err, MPM_EIO, "'%s': no points or no point count", path);
  }
  if (H5Aexists(file, "dimension") > 0 &&
      (mpm_io_h5_attr_read(file, "dimension", H5T_NATIVE_INT, &dim) < 0 || (dim != 2 && dim != 3))) {
    mpm_io_h5_close(g);
    return mpm_err_set(err, MPM_EIO, "'%s': attribute 'dimension' is not 2 or 3", path);
  }
  /* the deformation gradients: stored when the run's model carries them */
  const int defgrad = H5Lexists(g, "fxx", H5P_DEFAULT) > 0;
  for (size_t k = 0; k < NSTORED; k++)       /* counts first: no allocation from a bad one */
    if (stored_in(&stored[k], dim, defgrad) && mpm_io_h5_array_length(g, stored[k].name) != n) {
      mpm_io_h5_close(g);
      return mpm_err_set(err, MPM_EIO, "'%s': field '%s' does not hold npoints = %ld values",
                         path, stored[k].name, n);
    }
  st->pts = mpm_points_alloc_dim((size_t)n, dim);
  int rc = st->pts && mpm_points_set_defgrad(st->pts, defgrad) == MPM_OK
               ? MPM_OK : mpm_err_set(err, MPM_ENOMEM, "'%s': no memory for %ld points", path, n);
  for (size_t k = 0; rc == MPM_OK && k < NSTORED; k++) {
    if (!stored_in(&stored[k], dim, defgrad))
      continue;
    hid_t d = H5Dopen2(g, stored[k].name, H5P_DEFAULT);
    const hid_t mtype = stored[k].isint ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
    if (d >= 0 && !mpm_io_h5_type_ok(d, mtype))
      rc = mpm_err_set(err, MPM_EIO, "'%s': field '%s': its stored type or layout is damaged (a damaged "
                       "checkpoint)", path, stored[k].name);
    else if (d < 0 || (n > 0 && H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                        field_array(st->pts, &stored[k])) < 0))
      rc = mpm_err_set(err, MPM_EIO, "'%s': cannot read field '%s': %s (a damaged checkpoint)",
                       path, stored[k].name, mpm_io_h5_reason(q));
    mpm_io_h5_close(d);
  }
  mpm_io_h5_close(g);
  if (rc == MPM_OK) {
    st->pts->n = (size_t)n;
    st->pts->next_id = next_id;
  }
  return rc;
}

static int read_series(hid_t file, mpm_run_state *st, const char *path, const mpm_io_h5_quiet *q,
                       mpm_err *err)
{
  hid_t g = H5Gopen2(file, "series", H5P_DEFAULT);
  long long n = g < 0 ? -1 : mpm_io_h5_array_length(g, "t");
  if (n >= 0) {
    st->nseries = (size_t)n;
    st->series_t = read_values(g, "t", H5T_NATIVE_DOUBLE, sizeof(double), (size_t)n);
    st->series_m = read_values(g, "mass", H5T_NATIVE_DOUBLE, sizeof(double), (size_t)n);
  }
  mpm_io_h5_close(g);
  if (n < 0 || !st->series_t || !st->series_m)
    return mpm_err_set(err, MPM_EIO, "'%s': cannot read the frame series: %s", path,
                       mpm_io_h5_reason(q));
  return MPM_OK;
}

/* ---- the values of a checkpoint read back --------------------------------- */

/* MPM_EIO naming a wrong value of the checkpoint at path. */
static int damaged(mpm_err *err, const char *path, const char *what)
{
  return mpm_err_set(err, MPM_EIO, "'%s': %s (a damaged checkpoint)", path, what);
}

static int cmp_int(const void *a, const void *b)
{
  const int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* Point p's values: every stored real finite, mass and volume positive,
 * state 0 or 1, id in [0, next_id). */
static int check_point(const mpm_points *P, size_t p, const char *path, mpm_err *err)
{
  char what[200];
  for (size_t k = 0; k < NSTORED; k++) {
    if (!stored_in(&stored[k], P->dim, P->defgrad) || stored[k].isint)
      continue;
    const double *a = field_array(P, &stored[k]), v = a[p];
    const int positive = a == P->mass || a == P->vol;   /* the others: finite */
    if (!isfinite(v) || (positive && !(v > 0.0))) {
      snprintf(what, sizeof what, "point %zu (id %d): field '%s' = %g (allowed: %s)", p, P->id[p],
               stored[k].name, v, positive ? "finite and > 0" : "finite");
      return damaged(err, path, what);
    }
  }
  if (P->state[p] != MPM_STATE_DENSE && P->state[p] != MPM_STATE_DISCONNECTED) {
    snprintf(what, sizeof what, "point %zu (id %d): field 'state' = %d (allowed: 0 or 1)", p,
             P->id[p], P->state[p]);
    return damaged(err, path, what);
  }
  if (P->id[p] < 0 || P->id[p] >= P->next_id) {
    snprintf(what, sizeof what, "point %zu: field 'id' = %d (allowed: 0 ... next_id - 1 = %d)", p,
             P->id[p], P->next_id - 1);
    return damaged(err, path, what);
  }
  return MPM_OK;
}

/* Every value of a checkpoint read back, in range (the banner). */
static int check_values(const mpm_run_state *st, const char *path, mpm_err *err)
{
  char what[200];
  const struct { const char *name; double v, lo; int strict; } range[] = {
    {"t", st->t, 0.0, 0},           {"dt", st->dt, 0.0, 1},
    {"step", (double)st->step, 0.0, 0}, {"n_sub", st->n_sub, 1.0, 0},
    {"mass0", st->mass0, 0.0, 0},   {"mass_removed", st->mass_removed, 0.0, 0},
    {"nremoved", (double)st->nremoved, 0.0, 0}, {"frames", (double)st->frames, 0.0, 0},
    {"frame_next", (double)st->frame_next, 0.0, 0},
    {"check_next", (double)st->check_next, 0.0, 0},
  };
  for (size_t k = 0; k < sizeof range / sizeof range[0]; k++)
    if (!isfinite(range[k].v) || (range[k].strict ? !(range[k].v > range[k].lo)
                                                  : !(range[k].v >= range[k].lo))) {
      snprintf(what, sizeof what, "attribute '%s' = %g (allowed: finite, %s %g)", range[k].name,
               range[k].v, range[k].strict ? ">" : ">=", range[k].lo);
      return damaged(err, path, what);
    }
  if ((st->seeded != 0 && st->seeded != 1) || (st->outlet_open != 0 && st->outlet_open != 1)) {
    snprintf(what, sizeof what, "attribute 'seeded' = %d or 'outlet_open' = %d (allowed: 0 or 1)",
             st->seeded, st->outlet_open);
    return damaged(err, path, what);
  }
  const mpm_points *P = st->pts;
  for (size_t p = 0; p < P->n; p++)
    if (check_point(P, p, path, err) != MPM_OK)
      return MPM_EIO;
  int *ids = malloc(P->n ? P->n * sizeof *ids : 1);
  if (!ids)
    return mpm_err_set(err, MPM_ENOMEM, "'%s': no memory to check %zu ids", path, P->n);
  memcpy(ids, P->id, P->n * sizeof *ids);
  qsort(ids, P->n, sizeof *ids, cmp_int);
  size_t twice = P->n;
  for (size_t p = 1; p < P->n && twice == P->n; p++)
    if (ids[p] == ids[p - 1])
      twice = p;
  const int dup = twice < P->n ? ids[twice] : 0;
  free(ids);
  if (twice < P->n) {
    snprintf(what, sizeof what, "id %d is held by two points (allowed: unique ids)", dup);
    return damaged(err, path, what);
  }
  for (size_t k = 0; k < st->nseries; k++)
    if (!isfinite(st->series_t[k]) || !isfinite(st->series_m[k])) {
      snprintf(what, sizeof what, "frame series entry %zu: t = %g s, mass %g (allowed: finite)", k,
               st->series_t[k], st->series_m[k]);
      return damaged(err, path, what);
    }
  for (int b = 0; b < st->nbody; b++) {
    mpm_body_state s = st->body[b];
    double v[BODY_VALUES];
    body_values(&s, v, 0);
    for (int k = 0; k < BODY_VALUES; k++)
      if (!isfinite(v[k]) || s.npushed < 0) {
        snprintf(what, sizeof what, "body %d: state value %d = %g, points put back %ld (allowed: "
                 "finite, >= 0)", b, k, v[k], s.npushed);
        return damaged(err, path, what);
      }
  }
  return MPM_OK;
}

static int read_checkpoint(hid_t file, mpm_io_checkpoint *ck, const char *path, int summed,
                           const mpm_io_h5_quiet *q, mpm_err *err)
{
  char *format = mpm_io_h5_attr_text(file, "format");
  const int version = !format ? 0 : strcmp(format, FORMAT) == 0 ? 2
                                  : strcmp(format, FORMAT_1) == 0 ? 1 : 0;
  free(format);
  if (!version)
    return mpm_err_set(err, MPM_EIO, "'%s' is not a granmpm checkpoint (format '%s' expected)",
                       path, FORMAT);
  if (version == 2 && !summed)
    return damaged(err, path, "format 2 without the block of its checksum");
  char *by = mpm_io_h5_attr_text(file, "written_by");
  snprintf(ck->written_by, sizeof ck->written_by, "%s", by ? by : "unknown");
  free(by);
  for (size_t k = 0; k < NSCALARS; k++)
    if (mpm_io_h5_attr_read(file, scalars[k].name, scalar_type(scalars[k].kind),
                            (char *)&ck->state + scalars[k].offset) < 0)
      return mpm_err_set(err, MPM_EIO, "'%s': no attribute '%s': %s", path, scalars[k].name,
                         mpm_io_h5_reason(q));
  long long n = mpm_io_h5_array_length(file, "input");
  ck->input = n > 0 ? read_values(file, "input", H5T_NATIVE_CHAR, 1, (size_t)n) : NULL;
  if (!ck->input || ck->input[n - 1] != '\0')
    return mpm_err_set(err, MPM_EIO, "'%s': no resolved input: %s", path, mpm_io_h5_reason(q));
  int rc = read_points(file, &ck->state, path, q, err);
  if (rc == MPM_OK)
    rc = read_series(file, &ck->state, path, q, err);
  if (rc == MPM_OK)
    rc = read_bodies(file, &ck->state, path, q, err);
  return rc == MPM_OK ? check_values(&ck->state, path, err) : rc;
}

/* What to read of an open checkpoint: all of it into ck, or its time and
 * step only. */
typedef struct reading {
  mpm_io_checkpoint *ck;
  double *t;
  long *step;
} reading;

static int read_open(hid_t file, const reading *r, const char *path, int summed,
                     const mpm_io_h5_quiet *q,
                     mpm_err *err)
{
  if (r->ck)
    return read_checkpoint(file, r->ck, path, summed, q, err);
  if (mpm_io_h5_attr_read(file, "t", H5T_NATIVE_DOUBLE, r->t) != 0 ||
      mpm_io_h5_attr_read(file, "step", H5T_NATIVE_LONG, r->step) != 0)
    return mpm_io_h5_fail(err, q, "cannot read", path);
  return MPM_OK;
}

/* The file at path against the checksum of its user block, read in blocks
 * before HDF5 sees it (*summed = 1); a file of format 1 (HDF5's signature
 * at its start, no user block) passes with *summed = 0. */
static int verify_file(const char *path, int *summed, mpm_err *err)
{
  *summed = 0;
  static const char hdf5_signature[8] = "\211HDF\r\n\032\n";
  char block[USERBLOCK + 1], line[sizeof FORMAT + 1];
  FILE *f = fopen(path, "rb");
  if (!f)
    return mpm_err_set(err, MPM_EIO, "cannot open '%s': %s", path, strerror(errno));
  const size_t got = fread(block, 1, USERBLOCK, f);
  block[got] = '\0';
  unsigned long long sum = 0;
  size_t len = 0;
  int first = 0, at = 0, rc = MPM_OK;
  snprintf(line, sizeof line, "%s\n", FORMAT);
  if (got >= sizeof hdf5_signature && !memcmp(block, hdf5_signature, sizeof hdf5_signature)) {
    fclose(f);
    return MPM_OK;
  }
  if (got < USERBLOCK || strncmp(block, line, strlen(line)) != 0)
    rc = damaged(err, path, "not a granmpm checkpoint: its first line is not '" FORMAT "'");
  else if (sscanf(block + strlen(line), "checksum %16llx of bytes %d to %zu%n", &sum, &first,
                  &len, &at) != 3 || at == 0 || first != USERBLOCK)
    rc = damaged(err, path, "its second line is not 'checksum H of bytes 512 to N'");
  uint64_t h = SUM_SEED;
  size_t total = got;
  const size_t bufsize = (size_t)1 << 16;   /* a multiple of 8 (sum_bytes) */
  char *buf = rc == MPM_OK ? malloc(bufsize) : NULL;
  if (rc == MPM_OK && !buf)
    rc = mpm_err_set(err, MPM_ENOMEM, "no memory to read '%s'", path);
  for (size_t n; rc == MPM_OK && (n = fread(buf, 1, bufsize, f)) > 0; total += n)
    h = sum_bytes(h, buf, n);
  free(buf);
  if (rc == MPM_OK && ferror(f))
    rc = mpm_err_set(err, MPM_EIO, "cannot read '%s': %s", path, strerror(errno));
  fclose(f);
  char what[160];
  if (rc == MPM_OK && total != len) {
    snprintf(what, sizeof what, "%zu bytes where its header says %zu (a cut or extended file)",
             total, len);
    rc = damaged(err, path, what);
  } else if (rc == MPM_OK && h != (uint64_t)sum) {
    rc = damaged(err, path, "its bytes do not match its checksum");
  }
  *summed = rc == MPM_OK;
  return rc;
}

/* Open DIR/checkpoint.h5 and read it as r says. */
static int read_dir(const char *dir, const reading *r, mpm_err *err)
{
  char *path = mpm_io_path_join(dir, "checkpoint.h5");
  struct stat sb;
  if (!path)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  if (stat(path, &sb) != 0) {
    int rc = mpm_err_set(err, MPM_EIO, "cannot open '%s': %s", path, strerror(errno));
    free(path);
    return rc;
  }
  int summed = 0;
  if (verify_file(path, &summed, err) != MPM_OK) {
    free(path);
    return MPM_EIO;
  }
  mpm_io_h5_quiet q;
  mpm_io_h5_quiet_begin(&q);
  hid_t file = mpm_io_h5_open_read(path);
  int rc = file < 0 ? mpm_io_h5_fail(err, &q, "cannot open", path)
                    : read_open(file, r, path, summed, &q, err);
  mpm_io_h5_close(file);
  mpm_io_h5_quiet_end(&q);
  free(path);
  return rc;
}

int mpm_io_checkpoint_read(const char *dir, mpm_io_checkpoint *ck, mpm_err *err)
{
  memset(ck, 0, sizeof *ck);
  const reading r = {.ck = ck};
  int rc = read_dir(dir, &r, err);
  if (rc != MPM_OK)
    mpm_io_checkpoint_clear(ck);
  return rc;
}

int mpm_io_checkpoint_when(const char *dir, double *t, long *step, mpm_err *err)
{
  const reading r = {.t = t, .step = step};
  return read_dir(dir, &r, err);
}

void mpm_io_checkpoint_clear(mpm_io_checkpoint *ck)
{
  if (!ck)
    return;
  mpm_points_free(ck->state.pts);
  free(ck->state.series_t);
  free(ck->state.series_m);
  free(ck->input);
  memset(ck, 0, sizeof *ck);
}
