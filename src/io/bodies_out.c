/* bodies_out.c: the rigid bodies of a run in its output (io.h,
 * mpm_io_output_bodies): per frame one row per body in DIR/bodies.csv and a
 * dataset /bodies/NNNNNN of run.h5 (one line of BODY_COLUMNS values per
 * body, in the input's order; the group's attributes name the bodies and
 * the columns), and with outlines their shapes for run.xdmf in /xdmf. A
 * resumed run cuts bodies.csv after the rows of its first nframes frames and
 * drops the later datasets (mpm_io_out_bodies_reopen; the outlines go with
 * the frames' other /xdmf datasets). */
#define _POSIX_C_SOURCE 200809L  /* fileno, ftruncate */

#include <stdlib.h>
#include <unistd.h>

#include "io/output_internal.h"

static const char *const columns[] = {"x", "y", "z", "angle", "vx", "vy", "vz", "omega",
                                      "fx", "fy", "fz", "tx", "ty", "tz", "pushed"};
enum { BODY_COLUMNS = sizeof columns / sizeof columns[0] };

static const char header[] = "frame,t,body,x,y,z,angle,vx,vy,vz,omega,fx,fy,fz,tx,ty,tz,pushed\n";

static void row_of(const mpm_body_state *b, double v[BODY_COLUMNS])
{
  const double r[BODY_COLUMNS] = {b->c[0], b->c[1], b->c[2], b->theta, b->v[0], b->v[1], b->v[2],
                                  b->v[3], b->f[0], b->f[1], b->f[2], b->tq[0], b->tq[1], b->tq[2],
                                  (double)b->npushed};
  memcpy(v, r, sizeof r);
}

/* /bodies with its attributes, created on the first frame. */
static hid_t bodies_group(mpm_io_output *out, int n, const char *const *names)
{
  if (H5Lexists(out->file, "bodies", H5P_DEFAULT) > 0)
    return H5Gopen2(out->file, "bodies", H5P_DEFAULT);
  hid_t g = H5Gcreate2(out->file, "bodies", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  char list[MPM_MAX_BODIES * (MPM_NAME_MAX + 1) + 1] = "", cols[256] = "";
  for (int k = 0; k < n; k++)
    snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? "," : "", names[k]);
  for (int k = 0; k < BODY_COLUMNS; k++)
    snprintf(cols + strlen(cols), sizeof cols - strlen(cols), "%s%s", k ? "," : "", columns[k]);
  if (g >= 0 && (mpm_io_h5_attr_string(g, "names", list) < 0 ||
                 mpm_io_h5_attr_string(g, "columns", cols) < 0 ||
                 mpm_io_h5_attr_string(g, "units", "m, rad, m/s, rad/s, N (plane N/m), N m "
                                       "(plane N m/m), points") < 0)) {
    mpm_io_h5_close(g);
    return H5I_INVALID_HID;
  }
  return g;
}

/* XDMF's cell codes in a Mixed topology: a polyline and a polygon are
 * followed by their number of vertices, a quadrilateral is not. */
enum { XDMF_POLYLINE = 2, XDMF_POLYGON = 3, XDMF_QUAD = 5 };

/* The outlines ol[n] of the frame being written to /xdmf: their vertices
 * (nv x 3), cells (a Mixed topology: a closed polyline per plane profile;
 * nv side quadrilaterals per prism and its two ends as polygons when
 * closed) and each cell's body; the counts to out->outline_*. */
static herr_t write_outlines(mpm_io_output *out, int n, const mpm_io_outline *ol)
{
  size_t nv = 0, ncell = 0, len = 0;
  for (int k = 0; k < n; k++) {
    const size_t v = (size_t)ol[k].nv;
    nv += v * (size_t)ol[k].nr;
    if (ol[k].nr == 1) {
      ncell += 1;
      len += v + 3;
    } else {
      ncell += v + 2 * (size_t)ol[k].caps;
      len += 5 * v + 2 * (size_t)ol[k].caps * (v + 2);
    }
  }
  double *xyz = malloc((nv ? nv : 1) * 3 * sizeof *xyz);
  int *cell = malloc((len ? len : 1) * sizeof *cell), *id = malloc((ncell ? ncell : 1) * sizeof *id);
  herr_t rc = xyz && cell && id ? 0 : -1;
  size_t pv = 0, pc = 0, pi = 0;
  for (int k = 0; k < n && rc >= 0; k++) {
    const int v = ol[k].nv, base = (int)pv;
    memcpy(xyz + 3 * pv, ol[k].xyz, (size_t)(3 * v * ol[k].nr) * sizeof *xyz);
    pv += (size_t)(v * ol[k].nr);
    if (ol[k].nr == 1) {
      cell[pc++] = XDMF_POLYLINE;
      cell[pc++] = v + 1;
      for (int i = 0; i <= v; i++)
        cell[pc++] = base + i % v;             /* closed: back to the first */
      id[pi++] = k;
      continue;
    }
    for (int i = 0; i < v; i++) {              /* the sides between the two rings */
      const int j = (i + 1) % v;
      cell[pc++] = XDMF_QUAD;
      cell[pc++] = base + i;
      cell[pc++] = base + j;
      cell[pc++] = base + v + j;
      cell[pc++] = base + v + i;
      id[pi++] = k;
    }
    for (int r = 0; r < 2 * ol[k].caps; r++) {  /* the closed ends */
      cell[pc++] = XDMF_POLYGON;
      cell[pc++] = v;
      for (int i = 0; i < v; i++)
        cell[pc++] = base + r * v + i;
      id[pi++] = k;
    }
  }
  char name[40];
  const hsize_t dims[2] = {(hsize_t)nv, 3};
  snprintf(name, sizeof name, "bodies_xyz_%06d", out->nframes);
  hid_t d = rc >= 0 ? mpm_io_h5_create_checked(out->xdmf_group, name, H5T_IEEE_F64LE, 2, dims)
                    : H5I_INVALID_HID;
  if (d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xyz) < 0)
    rc = -1;
  mpm_io_h5_close(d);
  snprintf(name, sizeof name, "bodies_cells_%06d", out->nframes);
  if (rc >= 0)
    rc = mpm_io_h5_write_array(out->xdmf_group, name, H5T_STD_I32LE, H5T_NATIVE_INT, len, cell,
                               NULL, "the bodies' outlines: XDMF Mixed topology");
  snprintf(name, sizeof name, "bodies_id_%06d", out->nframes);
  if (rc >= 0)
    rc = mpm_io_h5_write_array(out->xdmf_group, name, H5T_STD_I32LE, H5T_NATIVE_INT, ncell, id,
                               NULL, "the body of each outline cell (input order from 0)");
  free(xyz);
  free(cell);
  free(id);
  if (rc >= 0) {
    out->outline_frame = out->nframes;
    out->outline_nv = nv;
    out->outline_ncell = ncell;
    out->outline_len = len;
  }
  return rc;
}

int mpm_io_out_outline_counts(mpm_io_output *out, long frame)
{
  char name[40];
  snprintf(name, sizeof name, "bodies_cells_%06ld", frame);
  if (H5Lexists(out->xdmf_group, name, H5P_DEFAULT) <= 0)
    return 0;
  const char *what[3] = {"bodies_xyz_%06ld", "bodies_cells_%06ld", "bodies_id_%06ld"};
  hsize_t len[3] = {0, 0, 0};
  for (int k = 0; k < 3; k++) {
    snprintf(name, sizeof name, what[k], frame);
    hid_t d = H5Dopen2(out->xdmf_group, name, H5P_DEFAULT);
    hid_t sp = d >= 0 ? H5Dget_space(d) : H5I_INVALID_HID;
    hsize_t dims[2] = {0, 0};
    const int nd = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
    if (nd == (k == 0 ? 2 : 1) && H5Sget_simple_extent_dims(sp, dims, NULL) == nd &&
        (k > 0 || dims[1] == 3))
      len[k] = dims[0];
    mpm_io_h5_close(sp);
    mpm_io_h5_close(d);
    if (len[k] == 0)
      return -1;
  }
  out->outline_frame = (int)frame;
  out->outline_nv = (size_t)len[0];
  out->outline_len = (size_t)len[1];
  out->outline_ncell = (size_t)len[2];
  return 1;
}

int mpm_io_output_bodies(mpm_io_output *out, double t, int n, const char *const *names,
                         const mpm_body_state *b, const mpm_io_outline *ol, mpm_err *err)
{
  if (!out || n < 0 || n > MPM_MAX_BODIES || (n > 0 && (!names || !b)))
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_bodies: invalid arguments");
  for (int k = 0; ol && k < n; k++)
    if (ol[k].nv < 1 || (ol[k].nr != 1 && ol[k].nr != 2) || !ol[k].xyz)
      return mpm_err_set(err, MPM_EINVAL, "mpm_io_output_bodies: invalid outline of body %d", k);
  if (n == 0)
    return MPM_OK;
  if (!out->bcsv) {                          /* the first frame of a new run */
    const int rc = mpm_io_out_open_text(&out->bcsv, out->bcsv_path, header, err);
    if (rc != MPM_OK)
      return rc;
  }
  double v[MPM_MAX_BODIES * BODY_COLUMNS];
  for (int k = 0; k < n; k++) {
    double *r = v + (size_t)BODY_COLUMNS * (size_t)k;
    row_of(&b[k], r);
    fprintf(out->bcsv, "%d,%.10g,%s", out->nframes, t, names[k]);
    for (int c = 0; c < BODY_COLUMNS; c++)
      fprintf(out->bcsv, ",%.10g", r[c]);
    fputc('\n', out->bcsv);
  }
  if (ferror(out->bcsv) || fflush(out->bcsv) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", out->bcsv_path, strerror(errno));
  mpm_io_h5_quiet q;
  mpm_io_h5_quiet_begin(&q);
  char name[32];
  snprintf(name, sizeof name, "%06d", out->nframes);
  hid_t g = bodies_group(out, n, names);
  const hsize_t dims[2] = {(hsize_t)n, BODY_COLUMNS};
  hid_t d = g >= 0 ? mpm_io_h5_create_checked(g, name, H5T_IEEE_F64LE, 2, dims)
                   : H5I_INVALID_HID;
  int rc = d >= 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0 &&
                   mpm_io_h5_attr_double(d, "time", t) >= 0 &&
                   (!ol || write_outlines(out, n, ol) >= 0)
               ? MPM_OK
               : mpm_io_h5_fail(err, &q, "cannot write the bodies of a frame to", out->h5_path);
  mpm_io_h5_close(d);
  mpm_io_h5_close(g);
  mpm_io_h5_quiet_end(&q);
  return rc;
}

int mpm_io_out_bodies_reopen(mpm_io_output *out, long nframes, mpm_err *err)
{
  char name[32];
  if (H5Lexists(out->file, "bodies", H5P_DEFAULT) > 0) {
    hid_t g = H5Gopen2(out->file, "bodies", H5P_DEFAULT);
    for (long k = nframes; g >= 0; k++) {
      snprintf(name, sizeof name, "%06ld", k);
      if (H5Lexists(g, name, H5P_DEFAULT) <= 0 || H5Ldelete(g, name, H5P_DEFAULT) < 0)
        break;
    }
    mpm_io_h5_close(g);
  }
  const char *path = out->bcsv_path;
  int rc = MPM_OK;
  out->bcsv = fopen(path, "r+");
  if (out->bcsv) {                           /* keep the header and the rows of frame < nframes */
    char line[1024];
    long keep = 0;
    int first = 1;
    while (fgets(line, sizeof line, out->bcsv)) {
      if (!first && strtol(line, NULL, 10) >= nframes)
        break;
      first = 0;
      keep = ftell(out->bcsv);
    }
    if (keep < 0 || fflush(out->bcsv) != 0 || ftruncate(fileno(out->bcsv), keep) != 0 ||
        fseek(out->bcsv, 0, SEEK_END) != 0)
      rc = mpm_err_set(err, MPM_EIO, "cannot cut '%s': %s", path, strerror(errno));
  } else if (errno != ENOENT) {
    rc = mpm_err_set(err, MPM_EIO, "cannot open '%s': %s", path, strerror(errno));
  }
  return rc;
}

/* ---- reading back ---------------------------------------------------------- */

/* The rows of frame k of /bodies (group g) as CSV, names the bodies' titles
 * separated by commas; MPM_EIO naming what is wrong. */
static int print_frame(hid_t g, long k, const char *names, FILE *out, const char *path,
                       mpm_err *err)
{
  char name[32];
  snprintf(name, sizeof name, "%06ld", k);
  hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
  hid_t sp = d >= 0 ? H5Dget_space(d) : H5I_INVALID_HID;
  hsize_t dims[2] = {0, 0};
  double t = 0.0, v[MPM_MAX_BODIES * BODY_COLUMNS];
  int ok = sp >= 0 && H5Sget_simple_extent_ndims(sp) == 2 &&
           H5Sget_simple_extent_dims(sp, dims, NULL) == 2 && dims[0] <= MPM_MAX_BODIES &&
           dims[1] == BODY_COLUMNS && mpm_io_h5_attr_read(d, "time", H5T_NATIVE_DOUBLE, &t) >= 0 &&
           mpm_io_h5_type_ok(d, H5T_NATIVE_DOUBLE) &&
           H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0;
  mpm_io_h5_close(sp);
  mpm_io_h5_close(d);
  if (!ok)
    return mpm_err_set(err, MPM_EIO,
                       "'%s': /bodies/%s is not (at most %d bodies) x %d values with a time",
                       path, name, MPM_MAX_BODIES, BODY_COLUMNS);
  const char *p = names;
  for (hsize_t b = 0; b < dims[0]; b++) {
    const size_t len = strcspn(p, ",");
    fprintf(out, "%ld,%.10g,%.*s", k, t, (int)len, p);
    for (int c = 0; c < BODY_COLUMNS; c++)
      fprintf(out, ",%.10g", v[b * BODY_COLUMNS + (hsize_t)c]);
    fputc('\n', out);
    p += len + (p[len] == ',');
  }
  return MPM_OK;
}

int mpm_io_extract_bodies(const char *dir, int frame, FILE *out, mpm_err *err)
{
  char *path = mpm_io_path_join(dir, "run.h5");
  if (!path)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  mpm_io_h5_quiet q;
  mpm_io_h5_quiet_begin(&q);
  hid_t file = mpm_io_h5_open_read(path);
  hid_t g = file >= 0 && H5Lexists(file, "bodies", H5P_DEFAULT) > 0
                ? H5Gopen2(file, "bodies", H5P_DEFAULT)
                : H5I_INVALID_HID;
  char *names = g >= 0 ? mpm_io_h5_attr_text(g, "names") : NULL;
  H5G_info_t info;
  int rc = MPM_OK;
  if (file < 0)
    rc = mpm_io_h5_fail(err, &q, "cannot open", path);
  else if (g < 0 || !names || H5Gget_info(g, &info) < 0)
    rc = mpm_err_set(err, MPM_EINPUT, "'%s' holds no bodies (a run without body sections)", path);
  else if (frame >= (long long)info.nlinks)
    rc = mpm_err_set(err, MPM_EINPUT, "'%s': no frame %d of the bodies (0 ... %llu)", path, frame,
                     (unsigned long long)info.nlinks - 1);
  if (rc == MPM_OK && info.nlinks == 0)
    rc = mpm_err_set(err, MPM_EINPUT, "'%s': the bodies have no frame yet", path);
  if (rc == MPM_OK) {
    const long n = (long)info.nlinks;
    const long first = frame == MPM_IO_ALL_FRAMES ? 0 : frame < 0 ? n - 1 : frame;
    const long end = frame == MPM_IO_ALL_FRAMES ? n : first + 1;
    fputs(header, out);
    for (long k = first; rc == MPM_OK && k < end; k++)
      rc = print_frame(g, k, names, out, path, err);
  }
  free(names);
  mpm_io_h5_close(g);
  mpm_io_h5_close(file);
  mpm_io_h5_quiet_end(&q);
  free(path);
  return rc;
}
