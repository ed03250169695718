/* h5err.c: HDF5 errors as one mpm_err message; opening and closing (h5err.h). */
#include "io/h5err.h"

#include <stdio.h>
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
