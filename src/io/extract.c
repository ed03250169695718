/* extract.c: one frame of a run directory as CSV, for gnuplot and scripts.
 *
 * Reads DIR/run.h5 as written by output.c: frame k is the group
 * /frames/NNNNNN (k in 6 digits) holding one 1-D dataset per point field.
 * The output has a header row of field names, then one row per point;
 * doubles are printed with %.17g, so they read back bit for bit, and integer
 * fields as integers. Columns are read in blocks of rows, so memory does not
 * grow with the number of points. A 3D frame lists its z fields like any
 * other; a z range keeps the rows with zmin <= z <= zmax (z read alongside,
 * printed or not). */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/h5err.h"
#include "io/io.h"

#define FIELD_NAME_MAX 64 /* longest field name, with the NUL */
#define FIELDS_MAX 64     /* datasets in one frame group */
#define COLUMNS_MAX 256   /* columns requested (names may repeat) */
#define BLOCK_ROWS 4096   /* rows read per block */

typedef struct field_names {
  int n;
  char name[FIELDS_MAX][FIELD_NAME_MAX];
} field_names;

/* ---- state of one extraction ------------------------------------------- */

typedef struct column {
  const char *name;
  hid_t dset;
  int isint;
  double *d;    /* BLOCK_ROWS values when !isint */
  long long *i; /* BLOCK_ROWS values when isint */
} column;

typedef struct extract_ctx {
  const char *dir;
  char *path; /* DIR/run.h5 */
  hid_t file;
  hid_t group; /* the frame */
  int frame;
  field_names avail;
  column col[COLUMNS_MAX];
  int ncol;
  const mpm_io_zrange *zr; /* NULL: every row */
  column zcol;             /* z, when zr is given */
  hsize_t npoints;
  mpm_io_h5_quiet quiet;
} extract_ctx;

static int h5_fail(mpm_err *err, const extract_ctx *c, const char *what)
{
  return mpm_io_h5_fail(err, &c->quiet, what, c->path);
}

/* ---- opening ------------------------------------------------------------- */

static int open_run(extract_ctx *c, mpm_err *err)
{
  struct stat st;
  size_t len = strlen(c->dir) + sizeof "/run.h5";
  c->path = malloc(len);
  if (!c->path)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory opening run '%s'", c->dir);
  snprintf(c->path, len, "%s/run.h5", c->dir);
  if (stat(c->path, &st) != 0)
    return mpm_err_set(err, MPM_EIO, "cannot open '%s': %s", c->path, strerror(errno));
  c->file = mpm_io_h5_open_read(c->path);
  if (c->file < 0)
    return h5_fail(err, c, "cannot open");
  return MPM_OK;
}

static int count_frames(extract_ctx *c, hsize_t *n, mpm_err *err)
{
  H5G_info_t info;
  hid_t g = H5Gopen2(c->file, "frames", H5P_DEFAULT);
  herr_t rc = g < 0 ? -1 : H5Gget_info(g, &info);
  mpm_io_h5_close(g);
  if (rc < 0)
    return h5_fail(err, c, "no frames group in");
  *n = info.nlinks;
  return MPM_OK;
}

/* Resolve frame (< 0: the last) and open its group. */
static int open_frame(extract_ctx *c, int frame, mpm_err *err)
{
  char name[48];
  hsize_t n = 0;
  int rc = count_frames(c, &n, err);
  if (rc != MPM_OK)
    return rc;
  if (n == 0)
    return mpm_err_set(err, MPM_EINPUT, "run '%s' has no frames", c->dir);
  if (frame < 0)
    frame = (int)(n - 1);
  if ((hsize_t)frame >= n)
    return mpm_err_set(err, MPM_EINPUT, "frame %d not in run '%s' (frames 0..%d)", frame,
                       c->dir, (int)(n - 1));
  c->frame = frame;
  snprintf(name, sizeof name, "frames/%06d", frame);
  c->group = H5Gopen2(c->file, name, H5P_DEFAULT);
  if (c->group < 0)
    return h5_fail(err, c, "cannot open frame group in");
  /* A damaged frame is an error, not a frame with a column less or with
   * rows that do not match its point count. */
  unsigned long long np = 0;
  int dim = 2;
  return mpm_io_frame_check(c->group, frame, c->path, &c->quiet, &np, &dim, err);
}

/* Names of the frame's datasets in the order they were written (creation
 * order), or in name order for a group that does not track it. */
static int list_fields(extract_ctx *c, mpm_err *err)
{
  H5G_info_t info;
  char probe[FIELD_NAME_MAX];
  H5_index_t index = H5_INDEX_CRT_ORDER;
  if (H5Gget_info(c->group, &info) < 0)
    return h5_fail(err, c, "cannot list frame fields in");
  if (info.nlinks > FIELDS_MAX)
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s' has more than %d fields", c->frame,
                       c->path, FIELDS_MAX);
  if (info.nlinks > 0 && H5Lget_name_by_idx(c->group, ".", index, H5_ITER_INC, 0, probe,
                                            sizeof probe, H5P_DEFAULT) < 0) {
    index = H5_INDEX_NAME;
    c->quiet.reason[0] = '\0'; /* an expected failure, not the cause of a later one */
  }
  for (hsize_t k = 0; k < info.nlinks; k++) {
    ssize_t len = H5Lget_name_by_idx(c->group, ".", index, H5_ITER_INC, k, c->avail.name[k],
                                     FIELD_NAME_MAX, H5P_DEFAULT);
    if (len < 0 || len >= FIELD_NAME_MAX)
      return h5_fail(err, c, "cannot list frame fields in");
  }
  c->avail.n = (int)info.nlinks;
  return MPM_OK;
}

/* ---- field selection ------------------------------------------------------- */

static void available_list(const field_names *a, char *buf, size_t len)
{
  size_t used = 0;
  buf[0] = '\0';
  for (int k = 0; k < a->n && used < len; k++) {
    int w = snprintf(buf + used, len - used, "%s%s", k ? ", " : "", a->name[k]);
    if (w < 0)
      break;
    used += (size_t)w;
  }
}

static int find_field(const field_names *a, const char *name)
{
  for (int k = 0; k < a->n; k++)
    if (strcmp(a->name[k], name) == 0)
      return k;
  return -1;
}

static int add_column(extract_ctx *c, const char *name, mpm_err *err)
{
  int k = find_field(&c->avail, name);
  if (k < 0) {
    char list[320];
    available_list(&c->avail, list, sizeof list);
    return mpm_err_set(err, MPM_EINPUT, "unknown field '%s' in run '%s' (available: %s)", name,
                       c->dir, list);
  }
  if (c->ncol == COLUMNS_MAX)
    return mpm_err_set(err, MPM_EINPUT, "more than %d fields requested", COLUMNS_MAX);
  c->col[c->ncol].name = c->avail.name[k];
  c->col[c->ncol].dset = H5I_INVALID_HID;
  c->ncol++;
  return MPM_OK;
}

static int is_blank(const char *s)
{
  while (*s && isspace((unsigned char)*s))
    s++;
  return *s == '\0';
}

/* Copy the next comma-separated token of *s without surrounding blanks;
 * returns 1 if a comma follows it (another token is due). */
static int next_token(const char **s, char *tok, size_t len)
{
  const char *p = *s, *end;
  size_t n;
  int more;
  while (isspace((unsigned char)*p))
    p++;
  end = strchr(p, ',');
  if (!end)
    end = p + strlen(p);
  more = *end == ',';
  *s = more ? end + 1 : end;
  while (end > p && isspace((unsigned char)end[-1]))
    end--;
  n = (size_t)(end - p) < len - 1 ? (size_t)(end - p) : len - 1;
  memcpy(tok, p, n);
  tok[n] = '\0';
  return more;
}

/* fields: comma list of names (blanks around names ignored); NULL or blank
 * selects every field of the frame in the order written. */
static int select_fields(extract_ctx *c, const char *fields, mpm_err *err)
{
  const char *s = fields;
  int more;
  if (!fields || is_blank(fields)) {
    for (int k = 0; k < c->avail.n; k++)
      add_column(c, c->avail.name[k], err);
    return MPM_OK;
  }
  do {
    char tok[FIELD_NAME_MAX + 64];
    int rc;
    more = next_token(&s, tok, sizeof tok);
    if (!tok[0])
      return mpm_err_set(err, MPM_EINPUT, "empty field name in '%s'", fields);
    rc = add_column(c, tok, err);
    if (rc != MPM_OK)
      return rc;
  } while (more);
  return MPM_OK;
}

/* ---- reading and printing ---------------------------------------------------- */

/* Open one column's dataset and check it is 1-D with npoints values. */
static int open_column(extract_ctx *c, column *col, mpm_err *err)
{
  hsize_t dims[1] = {0};
  hid_t space, type;
  int rank;
  col->dset = H5Dopen2(c->group, col->name, H5P_DEFAULT);
  if (col->dset < 0)
    return h5_fail(err, c, "cannot open field in");
  space = H5Dget_space(col->dset);
  rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
  if (rank == 1)
    H5Sget_simple_extent_dims(space, dims, NULL);
  mpm_io_h5_close(space);
  type = H5Dget_type(col->dset);
  col->isint = type >= 0 && H5Tget_class(type) == H5T_INTEGER;
  mpm_io_h5_close(type);
  if (!mpm_io_h5_type_ok(col->dset, col->isint ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE))
    return mpm_err_set(err, MPM_EIO, "frame %d of '%s': field '%s': its stored type or layout is damaged "
                       "(a damaged run)", c->frame, c->path, col->name);
  if (col == c->col)
    c->npoints = dims[0]; /* the first column sets the row count */
  if (rank != 1 || dims[0] != c->npoints)
    return mpm_err_set(err, MPM_EIO, "field '%s' of frame %d in '%s' is not one value per point",
                       col->name, c->frame, c->path);
  if (col->isint)
    col->i = malloc(BLOCK_ROWS * sizeof *col->i);
  else
    col->d = malloc(BLOCK_ROWS * sizeof *col->d);
  if (!col->i && !col->d)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory reading '%s'", c->path);
  return MPM_OK;
}

/* Read rows [start, start + count) of one column. */
static herr_t read_block(const column *col, hsize_t start, hsize_t count)
{
  hid_t fs = H5Dget_space(col->dset);
  hid_t ms = H5Screate_simple(1, &count, NULL);
  herr_t rc = (fs < 0 || ms < 0) ? -1
              : H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &count, NULL);
  if (rc >= 0)
    rc = col->isint ? H5Dread(col->dset, H5T_NATIVE_LLONG, ms, fs, H5P_DEFAULT, col->i)
                    : H5Dread(col->dset, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, col->d);
  mpm_io_h5_close(ms);
  mpm_io_h5_close(fs);
  return rc;
}

static void print_header(const extract_ctx *c, FILE *out)
{
  for (int k = 0; k < c->ncol; k++)
    fprintf(out, "%s%s", k ? "," : "", c->col[k].name);
  fputc('\n', out);
}

static void print_rows(const extract_ctx *c, size_t count, FILE *out)
{
  for (size_t r = 0; r < count; r++) {
    if (c->zr && !(c->zcol.d[r] >= c->zr->zmin && c->zcol.d[r] <= c->zr->zmax))
      continue;
    for (int k = 0; k < c->ncol; k++) {
      const column *col = &c->col[k];
      if (k)
        fputc(',', out);
      if (col->isint)
        fprintf(out, "%lld", col->i[r]);
      else
        fprintf(out, "%.17g", col->d[r]);
    }
    fputc('\n', out);
  }
}

static int unreadable(mpm_err *err, const extract_ctx *c, const column *col)
{
  return mpm_err_set(err, MPM_EIO, "frame %d of '%s': cannot read field '%s': %s (a damaged run)",
                     c->frame, c->path, col->name, mpm_io_h5_reason(&c->quiet));
}

static int print_frame(extract_ctx *c, FILE *out, mpm_err *err)
{
  for (int k = 0; k < c->ncol; k++) {
    int rc = open_column(c, &c->col[k], err);
    if (rc != MPM_OK)
      return rc;
  }
  if (c->zr) {
    int rc;
    if (mpm_io_frame_dim(c->group) != 3)
      return mpm_err_set(err, MPM_EINPUT, "frame %d of run '%s' is 2D: it has no z to select "
                         "a range of", c->frame, c->dir);
    c->zcol.name = "z";
    if ((rc = open_column(c, &c->zcol, err)) != MPM_OK)
      return rc;
    if (c->zcol.isint)
      return mpm_err_set(err, MPM_EIO, "field 'z' of frame %d in '%s' is not real (a damaged "
                         "run)", c->frame, c->path);
  }
  print_header(c, out);
  for (hsize_t start = 0; start < c->npoints; start += BLOCK_ROWS) {
    hsize_t count = c->npoints - start < BLOCK_ROWS ? c->npoints - start : BLOCK_ROWS;
    for (int k = 0; k < c->ncol; k++)
      if (read_block(&c->col[k], start, count) < 0)
        return unreadable(err, c, &c->col[k]);
    if (c->zr && read_block(&c->zcol, start, count) < 0)
      return unreadable(err, c, &c->zcol);
    print_rows(c, (size_t)count, out);
  }
  if (fflush(out) != 0 || ferror(out))
    return mpm_err_set(err, MPM_EIO, "cannot write extracted frame %d of run '%s': %s",
                       c->frame, c->dir, strerror(errno));
  return MPM_OK;
}

static void ctx_close(extract_ctx *c)
{
  for (int k = 0; k < c->ncol; k++)
    if (c->col[k].dset >= 0)
      H5Dclose(c->col[k].dset);
  mpm_io_h5_close(c->zcol.dset);
  mpm_io_h5_close(c->group);
  mpm_io_h5_close(c->file);
}

static void ctx_free(extract_ctx *c)
{
  for (int k = 0; k < c->ncol; k++) {
    free(c->col[k].d);
    free(c->col[k].i);
  }
  free(c->zcol.d);
  free(c->zcol.i);
  free(c->path);
  free(c);
}

int mpm_io_extract(const char *dir, int frame, const char *fields, FILE *out, mpm_err *err)
{
  return mpm_io_extract_in(dir, frame, fields, NULL, out, err);
}

int mpm_io_extract_in(const char *dir, int frame, const char *fields, const mpm_io_zrange *zr,
                      FILE *out, mpm_err *err)
{
  extract_ctx *c;
  int rc;
  if (!dir || !out)
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_extract: missing run directory or output stream");
  if (zr && !(zr->zmin <= zr->zmax))
    return mpm_err_set(err, MPM_EINVAL, "mpm_io_extract: empty z range");
  c = calloc(1, sizeof *c);
  if (!c)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory extracting from '%s'", dir);
  c->dir = dir;
  c->zr = zr;
  c->file = c->group = c->zcol.dset = H5I_INVALID_HID;
  mpm_io_h5_quiet_begin(&c->quiet);
  rc = open_run(c, err);
  if (rc == MPM_OK)
    rc = open_frame(c, frame, err);
  if (rc == MPM_OK)
    rc = list_fields(c, err);
  if (rc == MPM_OK)
    rc = select_fields(c, fields, err);
  if (rc == MPM_OK)
    rc = print_frame(c, out, err);
  ctx_close(c);
  mpm_io_h5_quiet_end(&c->quiet);
  ctx_free(c);
  return rc;
}
