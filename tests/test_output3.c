/* test_output3.c: the point store's dimension and the output of a 3D store.
 *
 * A 2D store has none of the 3D arrays (NULL) through every store operation;
 * a 3D store keeps every field of a point together through push, growth,
 * compaction, reordering and copying. A 3D run of a few hundred points with
 * a distinct value in every field (-0, the smallest subnormal and -DBL_MAX
 * among them) is written as frames and read back bit for bit, through the
 * frame reader and through extraction, which also selects a z range; the
 * layout of run.h5 and run.xdmf, a 3D checkpoint, a reopened 3D run and
 * damaged 3D frames are checked. A 2D run's frames have no 3D dataset.
 *
 * `test_output3 --write3 DIR` writes the 3D run to DIR and `--damage3 DIR`
 * removes field z of its last frame, for tests/cli-extract3.sh and
 * tests/paraview3.sh. */
#define _XOPEN_SOURCE 700

#include <check.h>
#include <float.h>
#include <ftw.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/points.h"
#include "diag/diag.h"
#include "io/h5err.h"
#include "io/io.h"
#include "tmpdir.h"
#include "mesh/mesh.h"

#define NFRAMES 3
#define NSIDE 10             /* points along x and y; 3 layers in z */

static const mpm_io_origin origin = {"test_output3", "test-revision", 1};

/* ---- the 3D run ------------------------------------------------------------- */

static size_t frame_npoints(int f)
{
  return f < 2 ? 300 : 240;   /* the last frame lost its top 60 points */
}

/* Positions on a lattice of 10 x 10 x 3 in the box [0, 1] x [0, 1] x [0, 0.3],
 * moved by frame: z of point i is 0.05 + 0.1 (i / 100) + 0.001 f. */
static void position(int f, size_t i, double *x, double *y, double *z)
{
  *x = 0.05 + 0.1 * (double)(i % NSIDE);
  *y = 0.05 + 0.1 * (double)(i / NSIDE % NSIDE);
  *z = 0.05 + 0.1 * (double)(i / (NSIDE * NSIDE)) + 0.001 * f;
}

/* A distinct value for every (frame, point, field k), and a few that a
 * lossy format would not keep. */
static double value(int f, size_t i, int k)
{
  if (f == 1 && i == 1 && k == 3)
    return -0.0;
  if (f == 1 && i == 2 && k == 5)
    return 4.9406564584124654e-324;
  if (f == 1 && i == 3 && k == 20)
    return -DBL_MAX;
  return (f + 1) / 3.0 + (double)i * 1e-3 + k * 1e-7 * (k % 2 ? -1.0 : 1.0);
}

/* Every field of point i of a store of frame f: value() in list order,
 * position() for x, y, z; state and id from i. */
static void fill_point(mpm_points *pts, size_t i, int f, size_t tag)
{
  int k = 0;
#define SET_(fl, nm, d, u, D)                                                 \
  if (mpm_points_has(pts, D))                                                 \
    pts->fl[i] = value(f, tag, k);                                            \
  k++;
  MPM_POINT_REAL_FIELDS(SET_)
#undef SET_
  double z;
  position(f, tag, &pts->x[i], &pts->y[i], pts->dim == 3 ? &pts->z[i] : &z);
  pts->state[i] = (int)((tag + (size_t)f) % 2);
  pts->id[i] = 2147480000 + (int)tag;
}

/* The store of frame f (NULL when out of memory). No check assertions
 * here and in write_run3: `--write3` runs them outside a test. */
static mpm_points *make_points(int f, int dim)
{
  size_t n = frame_npoints(f);
  mpm_points *pts = mpm_points_alloc_dim(4, dim);   /* grows while pushing */
  for (size_t k = 0; pts && k < n; k++) {
    size_t i;
    if (mpm_points_push(pts, &i) != MPM_OK) {
      mpm_points_free(pts);
      return NULL;
    }
    fill_point(pts, i, f, k);
  }
  return pts;
}

static mpm_points *frame_points(int f, int dim)
{
  mpm_points *pts = make_points(f, dim);
  ck_assert_ptr_nonnull(pts);
  return pts;
}

static int fill_box(mpm_mesh *m, mpm_err *err)
{
  memset(m, 0, sizeof *m);
  m->dim = 3;
  m->nx = m->ny = 10;
  m->nz = 3;
  m->dx = m->dy = m->dz = 0.1;
  m->periodic_z = 1;
  return mpm_mesh_setup(m, err);
}

/* A fresh directory for this test's runs. */
static void make_tmpdir(char *dir)
{
  make_tmpdir_named(dir, "test-output3");
}

static int write_frame(mpm_io_output *out, int f, int dim, mpm_err *err)
{
  mpm_points *pts = make_points(f, dim);
  mpm_diag d;
  if (!pts)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  memset(&d, 0, sizeof d);
  d.t = 0.1 * f;
  d.npoints = pts->n;
  int rc = mpm_io_output_frame(out, pts, &d, err);
  mpm_points_free(pts);
  return rc;
}

/* The 3D run of NFRAMES frames in dir (made if needed); 0 or the status. */
static int write_run3(const char *dir, mpm_err *err)
{
  mpm_mesh m;
  mpm_io_output *out = NULL;
  int rc0 = fill_box(&m, err);
  if (rc0 != MPM_OK)
    return rc0;
  const char *input = "# 3D test run\nmesh {\n  shape = \"delta\"\n}\n";
  int rc = mpm_io_output_open(&out, dir, &origin, input, &m, err);
  for (int f = 0; rc == MPM_OK && f < NFRAMES; f++)
    rc = write_frame(out, f, 3, err);
  int rc2 = mpm_io_output_close(out, err);
  return rc != MPM_OK ? rc : rc2;
}

/* ---- reading back ------------------------------------------------------------- */

typedef struct text {
  char *buf;
  size_t len;
} text;

static int extract(const char *dir, int frame, const char *fields, const mpm_io_zrange *zr,
                   text *t, mpm_err *err)
{
  FILE *f = open_memstream(&t->buf, &t->len);
  ck_assert_ptr_nonnull(f);
  int rc = mpm_io_extract_in(dir, frame, fields, zr, f, err);
  fclose(f);
  return rc;
}

static char *read_file(const char *dir, const char *name)
{
  char path[DIR_MAX + 32];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "r");
  ck_assert_msg(f != NULL, "cannot open %s", path);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  rewind(f);
  char *s = malloc((size_t)n + 1);
  ck_assert_uint_eq(fread(s, 1, (size_t)n, f), (size_t)n);
  s[n] = '\0';
  fclose(f);
  return s;
}

static int count_substr(const char *s, const char *sub)
{
  int n = 0;
  for (const char *p = strstr(s, sub); p; p = strstr(p + 1, sub))
    n++;
  return n;
}

/* Every output field of a and b (the frame fields of MPM_POINT_FIELDS that
 * the stores have) bit for bit. */
static void same_output_fields(const mpm_points *a, const mpm_points *b)
{
  ck_assert_uint_eq(a->n, b->n);
  ck_assert_int_eq(a->dim, b->dim);
#define SAME_(f, nm, d, u, D)                                                  \
  ck_assert_msg(!mpm_points_has(a, D) || !memcmp(a->f, b->f, a->n * sizeof *a->f), \
                "field %s differs", nm);
  MPM_POINT_FIELDS(SAME_, SAME_, MPM_POINT_SKIP_)
#undef SAME_
}

/* Every stored field, and next_id. */
static void same_points(const mpm_points *a, const mpm_points *b)
{
  same_output_fields(a, b);
  ck_assert_int_eq(a->next_id, b->next_id);
#define SAME_(f, nm, d, u, D)                                                  \
  ck_assert_msg(!mpm_points_has(a, D) || !memcmp(a->f, b->f, a->n * sizeof *a->f), \
                "field %s differs", nm);
  MPM_POINT_STATE_FIELDS(SAME_)
#undef SAME_
}

/* The store's 3D arrays are all NULL (want_null) or all allocated. */
static void check_3d_arrays(const mpm_points *pts, int want_null)
{
  int n3 = 0;
#define NULL_(f, nm, d, u, D)                                                  \
  if ((D) == MPM_POINT_3D) {                                                  \
    n3++;                                                                     \
    ck_assert_msg((pts->f == NULL) == want_null, "field %s: %s", nm,           \
                  want_null ? "allocated in a 2D store" : "NULL in a 3D store"); \
  } else if ((D) == MPM_POINT_DEFGRAD) {                                      \
    ck_assert_msg((pts->f == NULL) == !pts->defgrad, "field %s of F, Fp: %s", nm, \
                  pts->defgrad ? "NULL with them" : "allocated without them");     \
  } else {                                                                    \
    ck_assert_msg(pts->f != NULL, "field %s NULL", nm);                       \
  }
  MPM_POINT_REAL_FIELDS(NULL_)
  MPM_POINT_INT_FIELDS(NULL_)
#undef NULL_
  /* z, vz, syz, szx, r1z, r2z, r3x..r3z; C: xz, yz, zx, zy, zz */
  ck_assert_int_eq(n3, 14);
}

/* Point i of pts holds the values of point `tag` of frame f, every field. */
static void check_point(const mpm_points *pts, size_t i, int f, size_t tag)
{
  mpm_points *want = mpm_points_alloc_dim(1, pts->dim);
  size_t j;
  ck_assert_int_eq(mpm_points_push(want, &j), MPM_OK);
  fill_point(want, j, f, tag);
#define SAME_(fl, nm, d, u, D)                                                 \
  ck_assert_msg(!mpm_points_has(pts, D) || !memcmp(&pts->fl[i], &want->fl[0], sizeof *pts->fl), \
                "field %s of point %zu (tag %zu) differs", nm, i, tag);
  MPM_POINT_REAL_FIELDS(SAME_)
  MPM_POINT_INT_FIELDS(SAME_)
#undef SAME_
  mpm_points_free(want);
}

/* ---- the store ------------------------------------------------------------------ */

/* A 2D store never allocates a 3D array: not when made, grown, pushed,
 * compacted, permuted or copied; mpm_points_set_dim adds them (zero) and
 * takes them away again. */
START_TEST(t_store_2d_has_no_3d_arrays)
{
  mpm_points *pts = frame_points(0, 2);
  check_3d_arrays(pts, 1);
  unsigned char *keep = malloc(pts->n);
  for (size_t i = 0; i < pts->n; i++)
    keep[i] = i % 3 != 0;
  mpm_points_compact(pts, keep);
  int *order = malloc(pts->n * sizeof *order);
  for (size_t k = 0; k < pts->n; k++)
    order[k] = (int)(pts->n - 1 - k);
  double *scratch = malloc(pts->n * sizeof *scratch);
  mpm_points_permute(pts, order, scratch);
  ck_assert_int_eq(mpm_points_reserve(pts, 5000), MPM_OK);
  check_3d_arrays(pts, 1);
  mpm_points *copy = mpm_points_alloc(0);
  ck_assert_int_eq(mpm_points_copy(copy, pts), MPM_OK);
  check_3d_arrays(copy, 1);
  same_points(pts, copy);
  ck_assert_int_eq(mpm_points_set_dim(copy, 3), MPM_OK);
  check_3d_arrays(copy, 0);
  for (size_t i = 0; i < copy->n; i++)
    ck_assert(copy->z[i] == 0.0 && copy->r3z[i] == 0.0 && copy->czz[i] == 0.0);
  ck_assert_int_eq(mpm_points_set_dim(copy, 2), MPM_OK);
  check_3d_arrays(copy, 1);
  ck_assert_int_eq(mpm_points_set_dim(copy, 4), MPM_EINVAL);
  ck_assert_ptr_null(mpm_points_alloc_dim(1, 1));
  mpm_points *plain = mpm_points_alloc(0);
  ck_assert_int_eq(plain->dim, 2);
  check_3d_arrays(plain, 1);
  mpm_points_free(plain);
  free(keep);
  free(order);
  free(scratch);
  mpm_points_free(copy);
  mpm_points_free(pts);
}
END_TEST

/* A 3D store of 300 points pushed into a store of room for 4 (grown on the
 * way), compacted (every third point removed), permuted (reversed, then
 * rotated) and copied: every field of every point goes with its point. */
START_TEST(t_store_3d_keeps_fields_aligned)
{
  mpm_points *pts = frame_points(1, 3);
  check_3d_arrays(pts, 0);
  for (size_t i = 0; i < pts->n; i++)
    check_point(pts, i, 1, i);
  unsigned char *keep = malloc(pts->n);
  for (size_t i = 0; i < pts->n; i++)
    keep[i] = i % 3 != 0;
  mpm_points_compact(pts, keep);
  ck_assert_uint_eq(pts->n, 200);
  for (size_t i = 0; i < pts->n; i++)
    check_point(pts, i, 1, i / 2 * 3 + 1 + i % 2);
  const size_t n = pts->n;
  int *order = malloc(n * sizeof *order);
  for (size_t k = 0; k < n; k++)
    order[k] = (int)((n - 1 - k + 17) % n);
  double *scratch = malloc(n * sizeof *scratch);
  mpm_points_permute(pts, order, scratch);
  for (size_t k = 0; k < n; k++) {
    size_t was = (size_t)order[k];
    check_point(pts, k, 1, was / 2 * 3 + 1 + was % 2);
  }
  mpm_points *copy = mpm_points_alloc(0);            /* 2D: the copy makes it 3D */
  ck_assert_int_eq(mpm_points_copy(copy, pts), MPM_OK);
  ck_assert_int_eq(copy->dim, 3);
  same_points(pts, copy);
  size_t i;
  ck_assert_int_eq(mpm_points_push(copy, &i), MPM_OK);   /* a new point is zero */
  ck_assert(copy->z[i] == 0.0 && copy->vz[i] == 0.0 && copy->szx[i] == 0.0 &&
            copy->r3x[i] == 0.0 && copy->cyz[i] == 0.0);
  /* the full stress tensor of a 3D store; plane strain's has yz = zx = 0 */
  copy->syz[0] = 1.5;
  copy->szx[0] = -2.5;
  mpm_sym3 s = mpm_points_stress(copy, 0);
  ck_assert(s.xx == copy->sxx[0] && s.yy == copy->syy[0] && s.zz == copy->szz[0] &&
            s.xy == copy->sxy[0] && s.yz == 1.5 && s.zx == -2.5);
  mpm_points *flat = frame_points(0, 2);
  s = mpm_points_stress(flat, 0);
  ck_assert(s.yz == 0.0 && s.zx == 0.0);
  mpm_points_free(flat);
  free(keep);
  free(order);
  free(scratch);
  mpm_points_free(copy);
  mpm_points_free(pts);
}
END_TEST

/* ---- frames ------------------------------------------------------------------------ */

/* Every frame of the 3D run read back into a (2D) store: the store turns 3D
 * and every output field comes back bit for bit; fields that frames do not
 * hold (the APIC matrix) are zero. */
START_TEST(t_frames3_roundtrip)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  make_tmpdir(dir);
  ck_assert_msg(write_run3(dir, &err) == MPM_OK, "%s", err.msg);
  mpm_io_run *r = NULL;
  ck_assert_msg(mpm_io_run_open(&r, dir, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(mpm_io_run_nframes(r), NFRAMES);
  ck_assert_int_eq(mpm_io_run_dim(r), 3);
  mpm_points *got = mpm_points_alloc(0);
  for (int f = 0; f < NFRAMES; f++) {
    double t = -1.0;
    ck_assert_msg(mpm_io_run_frame(r, f, got, &t, &err) == MPM_OK, "%s", err.msg);
    ck_assert(t == 0.1 * f);
    ck_assert_int_eq(got->dim, 3);
    mpm_points *want = frame_points(f, 3);
    same_output_fields(want, got);
    for (size_t i = 0; i < got->n; i++)
      ck_assert(got->cxx[i] == 0.0 && got->czz[i] == 0.0);
    mpm_points_free(want);
  }
  /* the box mesh's x-y section, for the measurements made on x and y */
  mpm_mesh m;
  char shape[32];
  ck_assert_msg(mpm_io_run_mesh(r, &m, shape, sizeof shape, &err) == MPM_OK, "%s", err.msg);
  ck_assert(m.nx == 10 && m.ny == 10 && m.dx == 0.1 && m.topology == MPM_TOPO_Q4);
  ck_assert_str_eq(shape, "delta");
  mpm_io_run_close(r);
  mpm_points_free(got);
  remove_tree(dir);
}
END_TEST

static int has_attr(hid_t obj, const char *name)
{
  return H5Aexists(obj, name) > 0;
}

static char *attr_text(hid_t obj, const char *path, const char *name)
{
  hid_t d = H5Oopen(obj, path, H5P_DEFAULT);
  ck_assert_int_ge(d, 0);
  char *s = mpm_io_h5_attr_text(d, name);
  H5Oclose(d);
  ck_assert_ptr_nonnull(s);
  return s;
}

/* run.h5: a 3D frame has attribute dimension = 3, the 3D datasets, 3D units
 * for mass and volume, and an n x 3 XYZ view whose rows are (x, y, z); the
 * box mesh is in /mesh. run.xdmf: XYZ geometry and the 3D fields. */
START_TEST(t_frames3_layout)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  ck_assert_msg(write_run3(dir, &err) == MPM_OK, "%s", err.msg);
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert_int_ge(file, 0);
  hid_t g = H5Gopen2(file, "frames/000002", H5P_DEFAULT);
  int dim = 0;
  ck_assert_int_eq(mpm_io_h5_attr_read(g, "dimension", H5T_NATIVE_INT, &dim), 0);
  ck_assert_int_eq(dim, 3);
  const char *const d3[] = {"z", "vz", "syz", "szx", "r1z", "r2z", "r3x", "r3y", "r3z"};
  for (size_t k = 0; k < sizeof d3 / sizeof d3[0]; k++)
    ck_assert_int_eq(mpm_io_h5_array_length(g, d3[k]), 240);
  ck_assert_int_le(H5Lexists(g, "cxz", H5P_DEFAULT), 0);   /* scheme state: not in frames */
  char *s = attr_text(g, "mass", "unit");
  ck_assert_str_eq(s, "kg");
  free(s);
  s = attr_text(g, "volume", "unit");
  ck_assert_str_eq(s, "m^3");
  free(s);
  H5Gclose(g);
  hid_t v = H5Dopen2(file, "xdmf/xyz_000002", H5P_DEFAULT);
  ck_assert_int_ge(v, 0);
  hid_t sp = H5Dget_space(v);
  hsize_t dims[2];
  ck_assert_int_eq(H5Sget_simple_extent_dims(sp, dims, NULL), 2);
  ck_assert(dims[0] == 240 && dims[1] == 3);
  double *xyz = malloc(240 * 3 * sizeof *xyz);
  ck_assert_int_ge(H5Dread(v, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xyz), 0);
  for (size_t i = 0; i < 240; i++) {
    double x, y, z;
    position(2, i, &x, &y, &z);
    ck_assert(xyz[3 * i] == x && xyz[3 * i + 1] == y && xyz[3 * i + 2] == z);
  }
  free(xyz);
  H5Sclose(sp);
  H5Dclose(v);
  ck_assert_int_le(H5Lexists(file, "xdmf/xy_000000", H5P_DEFAULT), 0);
  hid_t mg = H5Gopen2(file, "mesh", H5P_DEFAULT);
  int nz = 0;
  ck_assert_int_eq(mpm_io_h5_attr_read(mg, "nz", H5T_NATIVE_INT, &nz), 0);
  ck_assert_int_eq(nz, 3);
  ck_assert_int_eq(mpm_io_h5_array_length(mg, "node_z"), 4);
  H5Gclose(mg);
  H5Fclose(file);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Geometry GeometryType=\"XYZ\">"), NFRAMES);
  ck_assert_int_eq(count_substr(x, "GeometryType=\"XY\""), 0);
  ck_assert_int_eq(count_substr(x, "Dimensions=\"300 3\""), 2);
  ck_assert_int_eq(count_substr(x, "Dimensions=\"240 3\""), 1);
  ck_assert_int_eq(count_substr(x, "<Attribute Name=\"z\""), NFRAMES);
  ck_assert_int_eq(count_substr(x, "<Attribute Name=\"r3z\""), NFRAMES);
  free(x);
  remove_tree(dir);
}
END_TEST

/* A 2D run's frames have no 3D dataset and no dimension attribute, and its
 * XDMF geometry stays XY; a 3D store is refused by a 2D run and the other
 * way round. */
START_TEST(t_frames2_have_no_3d_fields)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  mpm_io_output *out = NULL;
  ck_assert_int_eq(mpm_io_output_open(&out, dir, &origin, "", NULL, &err), MPM_OK);
  ck_assert_msg(write_frame(out, 0, 2, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(write_frame(out, 1, 3, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t g = H5Gopen2(file, "frames/000000", H5P_DEFAULT);
  ck_assert_int_ge(g, 0);
  ck_assert(!has_attr(g, "dimension"));
#define NO3_(f, nm, d, u, D) \
  ck_assert_int_eq(H5Lexists(g, nm, H5P_DEFAULT) > 0, (D) == 2);
  MPM_POINT_FIELDS(NO3_, NO3_, NO3_)
#undef NO3_
  H5Gclose(g);
  ck_assert_int_gt(H5Lexists(file, "xdmf/xy_000000", H5P_DEFAULT), 0);
  ck_assert_int_le(H5Lexists(file, "xdmf/xyz_000000", H5P_DEFAULT), 0);
  H5Fclose(file);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);   /* read back: the store turns 2D */
  mpm_io_run *r = NULL;
  double t;
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_run_dim(r), 2);
  ck_assert_msg(mpm_io_run_frame(r, 0, pts, &t, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(pts->dim, 2);
  check_3d_arrays(pts, 1);
  mpm_points *want = frame_points(0, 2);
  same_output_fields(want, pts);
  mpm_points_free(want);
  mpm_io_run_close(r);
  mpm_points_free(pts);
  text tx = {0};
  mpm_io_zrange zr = {0.0, 1.0};
  ck_assert_int_eq(extract(dir, 0, NULL, &zr, &tx, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "is 2D"), "%s", err.msg);
  free(tx.buf);
  remove_tree(dir);
  make_tmpdir(dir);                              /* a 3D run takes no 2D store */
  mpm_mesh m;
  ck_assert_int_eq(fill_box(&m, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_output_open(&out, dir, &origin, "", &m, &err), MPM_OK);
  ck_assert_int_eq(write_frame(out, 0, 2, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  remove_tree(dir);
}
END_TEST

/* The ids of the rows of an extracted CSV whose header includes id; their
 * count. */
static size_t extracted_ids(char *csv, int *ids, size_t max, int *has_z)
{
  char *save = NULL, *line = strtok_r(csv, "\n", &save);
  ck_assert_ptr_nonnull(line);
  int col = -1, c = 0;
  *has_z = 0;
  for (char *p = line, *q; p; p = q ? q + 1 : NULL, c++) {
    q = strchr(p, ',');
    size_t len = q ? (size_t)(q - p) : strlen(p);
    if (len == 2 && !strncmp(p, "id", 2))
      col = c;
    if (len == 1 && p[0] == 'z')
      *has_z = 1;
  }
  ck_assert_int_ge(col, 0);
  size_t n = 0;
  while ((line = strtok_r(NULL, "\n", &save)) != NULL) {
    const char *p = line;
    for (int k = 0; k < col; k++)
      p = strchr(p, ',') + 1;
    ck_assert_uint_lt(n, max);
    ids[n++] = atoi(p);
  }
  return n;
}

/* Extraction of a 3D frame: every field (z among them) bit for bit, and a z
 * range keeps exactly the points with zmin <= z <= zmax, in their order. */
START_TEST(t_extract3_z_range)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  make_tmpdir(dir);
  ck_assert_msg(write_run3(dir, &err) == MPM_OK, "%s", err.msg);
  text t = {0};
  /* every column of the last frame, z included, parsed back bit for bit */
  ck_assert_msg(extract(dir, -1, NULL, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  char *first = strchr(t.buf, '\n');
  ck_assert_ptr_nonnull(first);
  ck_assert(!strncmp(t.buf, "x,y,z,vx,vy,vz,sxx,syy,szz,sxy,syz,szx,p,mass,volume,state,gdot_p,"
                     "g,id,r1x,r1y,r1z,r2x,r2y,r2z,r3x,r3y,r3z\n", (size_t)(first - t.buf + 1)));
  mpm_points *want = frame_points(2, 3);
  char *row = first + 1;
  for (size_t i = 0; i < want->n; i++) {
    const double *col[] = {want->x, want->y, want->z, want->vx, want->vy, want->vz};
    for (int c = 0; c < 6; c++) {
      char *end;
      double v = strtod(row, &end);
      ck_assert_msg(!memcmp(&v, &col[c][i], sizeof v), "column %d of row %zu", c, i);
      row = end + 1;
    }
    row = strchr(row, '\n') + 1;
  }
  mpm_points_free(want);
  free(t.buf);
  /* frame 1: layers at z = 0.051, 0.151, 0.251 (zm: the middle one exactly,
   * a range of one value, both ends included) */
  double xm, ym, zm;
  position(1, 100, &xm, &ym, &zm);
  const struct { double zmin, zmax; size_t first, n; } cases[] = {
    {0.1, 0.2, 100, 100}, {zm, zm, 100, 100}, {-1.0, 1.0, 0, 300},
    {0.0, 0.06, 0, 100}, {0.0, 0.152, 0, 200}, {0.4, 0.5, 0, 0},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    mpm_io_zrange zr = {cases[k].zmin, cases[k].zmax};
    int ids[400], has_z = 0;
    t.buf = NULL;
    ck_assert_msg(extract(dir, 1, "id,x", &zr, &t, &err) == MPM_OK, "%s", err.msg);
    size_t n = extracted_ids(t.buf, ids, 400, &has_z);
    ck_assert_msg(n == cases[k].n, "range %g:%g: %zu rows (want %zu)", zr.zmin, zr.zmax, n,
                  cases[k].n);
    ck_assert(!has_z);
    for (size_t i = 0; i < n; i++)
      ck_assert_int_eq(ids[i], 2147480000 + (int)(cases[k].first + i));
    free(t.buf);
  }
  /* z requested as a column too: it lies in the range */
  mpm_io_zrange zr = {0.2, 0.3};
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 0, "z,id", &zr, &t, &err), MPM_OK);
  int ids[400], has_z = 0;
  ck_assert_uint_eq(extracted_ids(t.buf, ids, 400, &has_z), 100);
  ck_assert(has_z);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

/* A checkpoint of a 3D store reads back bit for bit, every stored field
 * (the APIC matrix's 3D entries among them), as a 3D store. */
START_TEST(t_checkpoint3_roundtrip)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  make_tmpdir(dir);
  double series_t[1] = {0.5}, series_m[1] = {2.0};
  mpm_run_state st = {.pts = frame_points(1, 3), .t = 0.5, .dt = 1e-4, .step = 5000,
                      .n_sub = 1, .mass0 = 2.0, .frames = 1, .frame_next = 2, .check_next = 1,
                      .nseries = 1, .series_t = series_t, .series_m = series_m};
  st.pts->next_id = 2147483647;   /* above every id (a checkpoint is checked) */
  ck_assert_msg(mpm_io_checkpoint_write(dir, &st, "input", "test", &err) == MPM_OK, "%s",
                err.msg);
  mpm_io_checkpoint ck;
  ck_assert_msg(mpm_io_checkpoint_read(dir, &ck, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(ck.state.pts->dim, 3);
  ck_assert_int_eq(ck.state.pts->defgrad, 0);
  same_points(st.pts, ck.state.pts);
  mpm_io_checkpoint_clear(&ck);
  /* with the deformation gradients of a model that carries them (any values) */
  ck_assert_int_eq(mpm_points_set_defgrad(st.pts, 1), MPM_OK);
  for (size_t p = 0; p < st.pts->n; p++)
    for (int e = 0; e < 9; e++) {
      st.pts->F[e / 3][e % 3][p] = value(2, p, e);
      st.pts->Fp[e / 3][e % 3][p] = value(3, p, e);
    }
  ck_assert_int_eq(mpm_io_checkpoint_write(dir, &st, "input", "test", &err), MPM_OK);
  ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_OK);
  ck_assert_int_eq(ck.state.pts->defgrad, 1);
  check_3d_arrays(ck.state.pts, 0);
  same_points(st.pts, ck.state.pts);
  mpm_io_checkpoint_clear(&ck);
  /* a 2D store's checkpoint stays 2D, without 3D arrays */
  mpm_points_free(st.pts);
  st.pts = frame_points(1, 2);
  st.pts->next_id = 2147483647;
  ck_assert_int_eq(mpm_io_checkpoint_write(dir, &st, "input", "test", &err), MPM_OK);
  ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_OK);
  ck_assert_int_eq(ck.state.pts->dim, 2);
  check_3d_arrays(ck.state.pts, 1);
  same_points(st.pts, ck.state.pts);
  mpm_io_checkpoint_clear(&ck);
  mpm_points_free(st.pts);
  remove_tree(dir);
}
END_TEST

/* A 3D run reopened after two frames: the third frame and its XYZ view are
 * gone, run.xdmf is written again with XYZ geometry, and a 3D frame can be
 * appended. */
START_TEST(t_reopen3)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  ck_assert_msg(write_run3(dir, &err) == MPM_OK, "%s", err.msg);
  mpm_io_output *out = NULL;
  ck_assert_msg(mpm_io_output_reopen(&out, dir, &origin, 2, &err) == MPM_OK, "%s", err.msg);
  snprintf(path, sizeof path, "%s/run.h5", dir);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Geometry GeometryType=\"XYZ\">"), 2);
  free(x);
  ck_assert_int_eq(write_frame(out, 2, 2, &err), MPM_EINVAL);
  ck_assert_msg(write_frame(out, 2, 3, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Geometry GeometryType=\"XYZ\">"), 3);
  free(x);
  mpm_io_run *r = NULL;
  mpm_points *got = mpm_points_alloc(0), *want = frame_points(2, 3);
  double t;
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_run_frame(r, 2, got, &t, &err), MPM_OK);
  same_output_fields(want, got);
  mpm_io_run_close(r);
  mpm_points_free(got);
  mpm_points_free(want);
  remove_tree(dir);
}
END_TEST

/* Damaged 3D frames are errors, not frames read as 2D or shorter: frame 1
 * without z, frame 2 with r3y of the wrong length, frame 0 with dimension 7. */
static void damage(const char *dir)
{
  char path[DIR_MAX + 32];
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_ge(H5Ldelete(f, "frames/000001/z", H5P_DEFAULT), 0);
  ck_assert_int_ge(H5Ldelete(f, "frames/000002/r3y", H5P_DEFAULT), 0);
  hid_t g = H5Gopen2(f, "frames/000002", H5P_DEFAULT);
  double v[3] = {1, 2, 3};
  ck_assert_int_ge(mpm_io_h5_write_array(g, "r3y", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, v,
                                         NULL, NULL), 0);
  H5Gclose(g);
  g = H5Gopen2(f, "frames/000000", H5P_DEFAULT);
  ck_assert_int_ge(mpm_io_h5_attr_int(g, "dimension", 7), 0);
  H5Gclose(g);
  H5Fclose(f);
}

START_TEST(t_damaged3)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  make_tmpdir(dir);
  ck_assert_msg(write_run3(dir, &err) == MPM_OK, "%s", err.msg);
  damage(dir);
  mpm_io_run *r = NULL;
  mpm_points *pts = mpm_points_alloc(0);
  double time;
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_run_frame(r, 1, pts, &time, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "frame 1 of ") && strstr(err.msg, "has no field 'z'"), "%s",
                err.msg);
  ck_assert_int_eq(mpm_io_run_frame(r, 2, pts, &time, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "field 'r3y'"), "%s", err.msg);
  ck_assert_int_eq(mpm_io_run_frame(r, 0, pts, &time, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "'dimension' is not 2 or 3"), "%s", err.msg);
  mpm_io_run_close(r);
  ck_assert_int_eq(extract(dir, 1, NULL, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "has no field 'z'"), "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 2, NULL, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "'r3y'"), "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 0, NULL, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "'dimension' is not 2 or 3"), "%s", err.msg);
  free(t.buf);
  mpm_points_free(pts);
  remove_tree(dir);
}
END_TEST

/* `test_output3 --damage3 DIR`: remove field z of the last frame. */
static int damage_main(const char *dir)
{
  char path[DIR_MAX + 32];
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  int bad = f < 0 || H5Ldelete(f, "frames/000002/z", H5P_DEFAULT) < 0;
  return (f >= 0 && H5Fclose(f) < 0) || bad;
}

int main(int argc, char **argv)
{
  if (argc == 3 && strcmp(argv[1], "--write3") == 0) {
    mpm_err err = {0};
    if (write_run3(argv[2], &err) != MPM_OK) {
      fprintf(stderr, "%s\n", err.msg);
      return 1;
    }
    return 0;
  }
  if (argc == 3 && strcmp(argv[1], "--damage3") == 0)
    return damage_main(argv[2]);
  Suite *s = suite_create("output3");
  TCase *tc = tcase_create("output3");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_store_2d_has_no_3d_arrays);
  tcase_add_test(tc, t_store_3d_keeps_fields_aligned);
  tcase_add_test(tc, t_frames3_roundtrip);
  tcase_add_test(tc, t_frames3_layout);
  tcase_add_test(tc, t_frames2_have_no_3d_fields);
  tcase_add_test(tc, t_extract3_z_range);
  tcase_add_test(tc, t_checkpoint3_roundtrip);
  tcase_add_test(tc, t_reopen3);
  tcase_add_test(tc, t_damaged3);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? 0 : 1;
}
