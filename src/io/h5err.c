/* h5err.c: HDF5 errors as one mpm_err message; opening and closing;
 * attributes and arrays (h5err.h). */
#include "io/h5err.h"

#include "core/points.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct reason_buf {
  char *buf;
  size_t len;
} reason_buf;

/* File-driver errors carry the system's own text after this key. */
static const char system_text_key[] = "error message = '";

/* Keep the innermost entry of the stack, which names the cause. */
static herr_t reason_first(unsigned n, const H5E_error2_t *e, void *data)
{
  const char *key = system_text_key;
  const size_t klen = sizeof system_text_key - 1;
  reason_buf *r = data;
  const char *desc = e->desc ? e->desc : "";
  const char *p = strstr(desc, key);
  const char *end = p ? strchr(p + klen, '\'') : NULL;
  (void)n;
  if (end)
    snprintf(r->buf, r->len, "%.*s", (int)(end - p - klen), p + klen);
  else
    snprintf(r->buf, r->len, "%s", desc);
  return 1;
}

static herr_t capture(hid_t stack, void *data)
{
  mpm_io_h5_quiet *q = data;
  reason_buf r = {q->reason, sizeof q->reason};
  if (!q->reason[0])
    H5Ewalk2(stack, H5E_WALK_UPWARD, reason_first, &r);
  return 0;
}

void mpm_io_h5_quiet_begin(mpm_io_h5_quiet *q)
{
  mpm_io_h5_init();   /* the first HDF5 call of every reader and writer */
  q->reason[0] = '\0';
  if (H5Eget_auto2(H5E_DEFAULT, &q->func, &q->data) < 0) {
    q->func = NULL;
    q->data = NULL;
  }
  H5Eset_auto2(H5E_DEFAULT, capture, q);
}

void mpm_io_h5_quiet_end(const mpm_io_h5_quiet *q)
{
  H5Eset_auto2(H5E_DEFAULT, q->func, q->data);
}

const char *mpm_io_h5_reason(const mpm_io_h5_quiet *q)
{
  return q->reason[0] ? q->reason : "HDF5 error";
}

int mpm_io_h5_fail(mpm_err *err, const mpm_io_h5_quiet *q, const char *what, const char *path)
{
  return mpm_err_set(err, MPM_EIO, "%s '%s': %s", what, path, mpm_io_h5_reason(q));
}

hid_t mpm_io_h5_open_read(const char *path)
{
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  hid_t file = H5I_INVALID_HID;
  if (fapl < 0)
    return fapl;
#if H5_VERSION_GE(1, 10, 7)
  H5Pset_file_locking(fapl, 0, 1);
#endif
  file = H5Fopen(path, H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  return file;
}

herr_t mpm_io_h5_close(hid_t id)
{
  if (id < 0)
    return 0;
  switch (H5Iget_type(id)) {
  case H5I_FILE: return H5Fclose(id);
  case H5I_GROUP: return H5Gclose(id);
  case H5I_DATASET: return H5Dclose(id);
  case H5I_ATTR: return H5Aclose(id);
  case H5I_DATASPACE: return H5Sclose(id);
  case H5I_DATATYPE: return H5Tclose(id);
  case H5I_GENPROP_LST: return H5Pclose(id);
  default: return H5Idec_ref(id) < 0 ? -1 : 0;
  }
}

void mpm_io_h5_init(void)
{
  H5dont_atexit();
}

/* ---- attributes and arrays ------------------------------------------------ */

herr_t mpm_io_h5_attr_scalar(hid_t obj, const char *name, hid_t type, const void *v)
{
  if (H5Aexists(obj, name) > 0 && H5Adelete(obj, name) < 0)
    return -1;
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = space < 0 ? H5I_INVALID_HID
                         : H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t rc = attr < 0 ? -1 : H5Awrite(attr, type, v);
  mpm_io_h5_close(attr);
  mpm_io_h5_close(space);
  return rc;
}

herr_t mpm_io_h5_attr_double(hid_t obj, const char *name, double v)
{
  return mpm_io_h5_attr_scalar(obj, name, H5T_NATIVE_DOUBLE, &v);
}

herr_t mpm_io_h5_attr_int(hid_t obj, const char *name, int v)
{
  return mpm_io_h5_attr_scalar(obj, name, H5T_NATIVE_INT, &v);
}

herr_t mpm_io_h5_attr_long(hid_t obj, const char *name, long v)
{
  return mpm_io_h5_attr_scalar(obj, name, H5T_NATIVE_LONG, &v);
}

/* Fixed-length, NUL-terminated string attribute. */
herr_t mpm_io_h5_attr_string(hid_t obj, const char *name, const char *s)
{
  const char *v = s ? s : "";
  if (H5Aexists(obj, name) > 0 && H5Adelete(obj, name) < 0)
    return -1;
  hid_t type = H5Tcopy(H5T_C_S1);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5I_INVALID_HID;
  herr_t rc = -1;
  if (type >= 0 && space >= 0 && H5Tset_size(type, strlen(v) + 1) >= 0 &&
      H5Tset_strpad(type, H5T_STR_NULLTERM) >= 0) {
    attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    if (attr >= 0)
      rc = H5Awrite(attr, type, v);
  }
  mpm_io_h5_close(attr);
  mpm_io_h5_close(space);
  mpm_io_h5_close(type);
  return rc;
}

herr_t mpm_io_h5_attr_string_room(hid_t obj, const char *name, const char *s, size_t room)
{
  char *buf = calloc(room, 1);
  if (!buf)
    return -1;
  snprintf(buf, room, "%s", s ? s : "");
  herr_t rc = -1;
  hid_t a = H5Aexists(obj, name) > 0 ? H5Aopen(obj, name, H5P_DEFAULT) : H5I_INVALID_HID;
  hid_t t = a < 0 ? H5I_INVALID_HID : H5Aget_type(a);
  if (t >= 0 && H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t) &&
      H5Tget_size(t) == room) {
    rc = H5Awrite(a, t, buf);                 /* in place: no new space in the file */
  } else {
    mpm_io_h5_close(t);
    t = H5I_INVALID_HID;
    mpm_io_h5_close(a);
    a = H5I_INVALID_HID;
    hid_t space = H5Screate(H5S_SCALAR);
    t = H5Tcopy(H5T_C_S1);
    if ((H5Aexists(obj, name) <= 0 || H5Adelete(obj, name) >= 0) && space >= 0 && t >= 0 &&
        H5Tset_size(t, room) >= 0 && H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0 &&
        (a = H5Acreate2(obj, name, t, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0)
      rc = H5Awrite(a, t, buf);
    mpm_io_h5_close(space);
  }
  mpm_io_h5_close(t);
  mpm_io_h5_close(a);
  free(buf);
  return rc;
}

int mpm_io_h5_attr_read(hid_t obj, const char *name, hid_t type, void *v)
{
  if (H5Aexists(obj, name) <= 0)
    return -1;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t s = a < 0 ? H5I_INVALID_HID : H5Aget_space(a);
  herr_t rc = s < 0 || H5Sget_simple_extent_npoints(s) != 1 || !mpm_io_h5_type_ok(a, type)
                  ? -1
                  : H5Aread(a, type, v);
  mpm_io_h5_close(s);
  mpm_io_h5_close(a);
  return rc < 0 ? -1 : 0;
}

char *mpm_io_h5_attr_text(hid_t obj, const char *name)
{
  if (H5Aexists(obj, name) <= 0)
    return NULL;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  hid_t t = a < 0 ? H5I_INVALID_HID : H5Aget_type(a);
  hid_t s = a < 0 ? H5I_INVALID_HID : H5Aget_space(a);
  size_t n = t >= 0 && s >= 0 && H5Sget_simple_extent_npoints(s) == 1 &&
                     H5Tget_class(t) == H5T_STRING && !H5Tis_variable_str(t)
                 ? H5Tget_size(t)
                 : 0;
  mpm_io_h5_close(s);
  char *text = n ? malloc(n + 1) : NULL;
  if (text && H5Aread(a, t, text) < 0) {
    free(text);
    text = NULL;
  }
  if (text)
    text[n] = '\0';
  mpm_io_h5_close(t);
  mpm_io_h5_close(a);
  return text;
}

hid_t mpm_io_h5_file_create_plist(void)
{
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  if (fcpl >= 0 && H5Pset_istore_k(fcpl, 1) < 0) {
    H5Pclose(fcpl);
    return H5I_INVALID_HID;
  }
  return fcpl;
}

hid_t mpm_io_h5_create_checked(hid_t loc, const char *name, hid_t ftype, int rank,
                               const hsize_t *dims)
{
  hsize_t chunk[2] = {0, 0}, rows = 1;
  for (int d = 1; d < rank; d++)
    rows *= dims[d] > 0 ? dims[d] : 1;
  chunk[0] = MPM_IO_H5_CHUNK / rows > 0 ? MPM_IO_H5_CHUNK / rows : 1;
  if (dims[0] < chunk[0])
    chunk[0] = dims[0];
  for (int d = 1; d < rank; d++)
    chunk[d] = dims[d];
  int empty = 0;
  for (int d = 0; d < rank; d++)
    empty |= dims[d] == 0;
  hid_t space = H5Screate_simple(rank, dims, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  hid_t dset = H5I_INVALID_HID;
  if (space >= 0 && dcpl >= 0 &&
      (empty || (H5Pset_chunk(dcpl, rank, chunk) >= 0 && H5Pset_fletcher32(dcpl) >= 0)))
    dset = H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  mpm_io_h5_close(dcpl);
  mpm_io_h5_close(space);
  return dset;
}

herr_t mpm_io_h5_write_array(hid_t loc, const char *name, hid_t ftype, hid_t mtype, size_t n,
                             const void *buf, const char *unit, const char *desc)
{
  const hsize_t dims[1] = {(hsize_t)n};
  hid_t dset = mpm_io_h5_create_checked(loc, name, ftype, 1, dims);
  herr_t rc = dset < 0 ? -1 : 0;
  if (rc >= 0 && n > 0)
    rc = H5Dwrite(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  if (rc >= 0 && unit)
    rc = mpm_io_h5_attr_string(dset, "unit", unit);
  if (rc >= 0 && desc)
    rc = mpm_io_h5_attr_string(dset, "description", desc);
  mpm_io_h5_close(dset);
  return rc;
}

/* 1 if every chunk of dataset d (elements of size bytes) lies in its file
 * and holds at most a chunk's values and a checksum: the chunk index is not
 * checksummed, and a damaged chunk size has HDF5 allocate it. */
static int chunks_ok(hid_t d, size_t size)
{
  hid_t dcpl = H5Dget_create_plist(d), f = H5Iget_file_id(d), space = H5Dget_space(d);
  hsize_t chunk[2] = {0, 0}, n = 0, bytes = 0;
  int ok = dcpl >= 0 && f >= 0 && space >= 0 && H5Fget_filesize(f, &bytes) >= 0;
  if (ok && H5Pget_layout(dcpl) == H5D_CHUNKED) {
    const int rank = H5Pget_chunk(dcpl, 2, chunk);
    const hsize_t most = (rank >= 1 ? chunk[0] : 0) * (rank == 2 ? chunk[1] : 1) * size + 4;
    ok = rank >= 1 && rank <= 2 && H5Dget_num_chunks(d, space, &n) >= 0;
    for (hsize_t k = 0; ok && k < n; k++) {
      haddr_t addr = HADDR_UNDEF;
      hsize_t at = 0;
      ok = H5Dget_chunk_info(d, space, k, NULL, NULL, &addr, &at) >= 0 && at <= most &&
           addr != HADDR_UNDEF && addr <= bytes && at <= bytes - addr;
    }
  }
  mpm_io_h5_close(space);
  mpm_io_h5_close(f);
  mpm_io_h5_close(dcpl);
  return ok;
}

int mpm_io_h5_type_ok(hid_t d, hid_t mtype)
{
  const int attr = d >= 0 && H5Iget_type(d) == H5I_ATTR;
  hid_t t = d < 0 ? H5I_INVALID_HID : attr ? H5Aget_type(d) : H5Dget_type(d);
  const size_t size = t < 0 ? 0 : H5Tget_size(t);
  const int ok = t >= 0 && H5Tget_class(t) == H5Tget_class(mtype) && size >= 1 && size <= 8 &&
                 (attr || chunks_ok(d, size));
  mpm_io_h5_close(t);
  return ok;
}

long long mpm_io_h5_array_length(hid_t loc, const char *name)
{
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0)
    return -1;
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  hid_t s = d < 0 ? H5I_INVALID_HID : H5Dget_space(d);
  hsize_t dims[1] = {0};
  long long n = s >= 0 && H5Sget_simple_extent_ndims(s) == 1 &&
                        H5Sget_simple_extent_dims(s, dims, NULL) == 1
                    ? (long long)dims[0]
                    : -1;
  /* the data of a granmpm file are not compressed: more values than the
   * file has bytes is a damaged size, which must not be allocated */
  hid_t t = n > 0 ? H5Dget_type(d) : H5I_INVALID_HID;
  hid_t f = n > 0 ? H5Iget_file_id(d) : H5I_INVALID_HID;
  hsize_t bytes = 0;
  const size_t size = t >= 0 ? H5Tget_size(t) : 0;
  if (n > 0 && (size == 0 || f < 0 || H5Fget_filesize(f, &bytes) < 0 ||
                (hsize_t)n > bytes / size))
    n = -1;
  mpm_io_h5_close(f);
  mpm_io_h5_close(t);
  mpm_io_h5_close(s);
  mpm_io_h5_close(d);
  return n;
}

/* ---- frames ----------------------------------------------------------------- */

/* The extents came after the first runs: frames may lack them. */
static int optional_field(const char *name)
{
  return !strcmp(name, "r1x") || !strcmp(name, "r1y") || !strcmp(name, "r2x") ||
         !strcmp(name, "r2y");
}

int mpm_io_frame_field_optional(const char *name)
{
  return optional_field(name);
}

#define NAME_(f, nm, d, u, dim) {nm, dim},
static const struct { const char *name; int dim; } frame_fields[] = {
  MPM_POINT_FIELDS(NAME_, NAME_, NAME_)
};
#undef NAME_

int mpm_io_frame_dim(hid_t g)
{
  int dim = 2;
  if (H5Aexists(g, "dimension") <= 0)
    return 2;
  if (mpm_io_h5_attr_read(g, "dimension", H5T_NATIVE_INT, &dim) < 0 || (dim != 2 && dim != 3))
    return -1;
  return dim;
}

const char *mpm_io_frame_missing_field(hid_t g)
{
  int dim = mpm_io_frame_dim(g);
  if (dim < 0)
    return "dimension";
  for (size_t k = 0; k < sizeof frame_fields / sizeof frame_fields[0]; k++)
    if (frame_fields[k].dim <= dim && !optional_field(frame_fields[k].name) &&
        H5Lexists(g, frame_fields[k].name, H5P_DEFAULT) <= 0)
      return frame_fields[k].name;
  return NULL;
}

int mpm_io_frame_check(hid_t g, int frame, const char *path, const mpm_io_h5_quiet *q,
                       unsigned long long *n, int *dim, mpm_err *err)
{
  *n = 0;
  *dim = mpm_io_frame_dim(g);
  if (*dim < 0)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s': attribute 'dimension' is not 2 or 3 "
                       "(a damaged run)", frame, path);
  const char *missing = mpm_io_frame_missing_field(g);
  if (missing)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s' has no field '%s' (a damaged run)", frame,
                       path, missing);
  if (mpm_io_h5_attr_read(g, "npoints", H5T_NATIVE_ULLONG, n) < 0)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s': cannot read attribute 'npoints': %s (a "
                       "damaged run)", frame, path, mpm_io_h5_reason(q));
  const long long have = mpm_io_h5_array_length(g, "x");
  if (have < 0)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s': cannot read field 'x': %s (a damaged "
                       "run)", frame, path, mpm_io_h5_reason(q));
  if (have != (long long)*n)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s': npoints = %llu but field 'x' holds %lld "
                       "values (a damaged run)", frame, path, *n, have);
  return MPM_OK;
}

char *mpm_io_path_join(const char *dir, const char *name)
{
  size_t n = strlen(dir) + strlen(name) + 2;
  char *p = malloc(n);
  if (p)
    snprintf(p, n, "%s/%s", dir, name);
  return p;
}
