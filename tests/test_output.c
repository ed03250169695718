/* test_output.c: run output (run.h5, run.xdmf, diagnostics.csv) and frame
 * extraction. A run of three frames with known point values is written to a
 * temporary directory, then read back through mpm_io_extract and the HDF5 API:
 * every value must come back bit for bit. */
#define _XOPEN_SOURCE 700

#include "config.h" /* PACKAGE_VERSION */

#include <check.h>
#include <ftw.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/points.h"
#include "diag/diag.h"
#include "io/h5err.h"
#include "io/io.h"
#include "tmpdir.h"

#define NFRAMES 3

static const mpm_io_origin no_origin = {"", NULL, 1};

static const char *const all_fields[] = {"x", "y", "vx", "vy", "sxx", "syy", "szz", "sxy",
                                         "p", "mass", "volume", "state", "gdot_p", "g", "id",
                                         "r1x", "r1y", "r2x", "r2y"};
#define NALL ((int)(sizeof all_fields / sizeof all_fields[0]))

/* ---- the run written by every test --------------------------------------- */

static size_t frame_npoints(int f)
{
  return f < 2 ? 5 : 3; /* the last frame lost two points */
}

static double frame_time(int f)
{
  return 0.1 * f;
}

/* A distinct value for every (frame, point, field), plus a few special ones
 * that a lossy format would not reproduce. */
static double value(int f, size_t i, int k)
{
  if (f == 1 && i == 0 && k == 0)
    return -0.0;
  if (f == 1 && i == 1 && k == 2)
    return 4.9406564584124654e-324; /* smallest subnormal */
  if (f == 1 && i == 2 && k == 3)
    return -1.7976931348623157e308;
  return (f + 1) / 3.0 + (double)i * 0.1 + k * 1e-7 * (k % 2 ? -1.0 : 1.0);
}

static mpm_points *frame_points(int f)
{
  size_t n = frame_npoints(f);
  mpm_points *pts = mpm_points_alloc(n);
  ck_assert_ptr_nonnull(pts);
  for (size_t k = 0; k < n; k++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
    double *r[] = {pts->x, pts->y, pts->vx, pts->vy, pts->sxx, pts->syy, pts->szz, pts->sxy,
                   pts->mass, pts->vol, pts->gdp, pts->g, pts->r1x, pts->r1y, pts->r2x, pts->r2y};
    for (int c = 0; c < (int)(sizeof r / sizeof r[0]); c++)
      r[c][i] = value(f, i, c);
    pts->state[i] = (int)((i + (size_t)f) % 2);
    pts->id[i] = 2147483000 + 100 * f + (int)i;
  }
  return pts;
}

static void fill_mesh(mpm_mesh *m)
{
  memset(m, 0, sizeof *m);
  m->nx = 4;
  m->ny = 3;
  m->x0 = -0.5;
  m->y0 = 0.0;
  m->dx = 0.25;
  m->dy = 1.0 / 3.0;
  m->topology = MPM_TOPO_T3;
  m->diagonal = MPM_DIAG_MIRROR;
  m->mirror_x = 0.0;
  m->snx = m->nx + 1;
  m->sny = m->ny + 1;
  m->nnodes = m->snx * m->sny;
  m->lx = m->nx * m->dx;
  m->ly = m->ny * m->dy;
}

/* A fresh directory for this test's runs. */
static void make_tmpdir(char *dir)
{
  make_tmpdir_named(dir, "test-output");
}

static void write_frame(mpm_io_output *out, int f)
{
  mpm_err err = {0};
  mpm_points *pts = frame_points(f);
  mpm_diag d;
  mpm_diag_compute(pts, frame_time(f), &d);
  ck_assert_msg(mpm_io_output_frame(out, pts, &d, &err) == MPM_OK, "%s", err.msg);
  mpm_points_free(pts);
}

static mpm_io_output *open_run(const char *dir, const char *input)
{
  mpm_err err = {0};
  mpm_mesh m;
  mpm_io_output *out = NULL;
  fill_mesh(&m);
  const mpm_io_origin origin = {"granmpm run test.conf --set a.b=1", "test-revision", 3};
  ck_assert_msg(mpm_io_output_open(&out, dir, &origin, input, &m, &err) == MPM_OK, "%s", err.msg);
  ck_assert_ptr_nonnull(out);
  return out;
}

/* Temporary directory with a closed run of NFRAMES frames in it. */
static void write_run(char *dir)
{
  mpm_err err = {0};
  make_tmpdir(dir);
  mpm_io_output *out = open_run(dir, "[mesh]\nnx = 4\n");
  for (int f = 0; f < NFRAMES; f++)
    write_frame(out, f);
  ck_assert_msg(mpm_io_output_close(out, &err) == MPM_OK, "%s", err.msg);
}

/* ---- reading output back ------------------------------------------------------- */

typedef struct text {
  char *buf;
  size_t len;
} text;

static int extract(const char *dir, int frame, const char *fields, text *t, mpm_err *err)
{
  FILE *f = open_memstream(&t->buf, &t->len);
  ck_assert_ptr_nonnull(f);
  int rc = mpm_io_extract(dir, frame, fields, f, err);
  fclose(f);
  return rc;
}

static char *read_file(const char *dir, const char *name)
{
  char path[DIR_MAX + 32];
  snprintf(path, sizeof path, "%s%s%s", dir, name[0] ? "/" : "", name);
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

static int count_lines(const char *s)
{
  int n = 0;
  for (; *s; s++)
    n += *s == '\n';
  return n;
}

static int count_substr(const char *s, const char *sub)
{
  int n = 0;
  for (const char *p = strstr(s, sub); p; p = strstr(p + 1, sub))
    n++;
  return n;
}

/* Split s in place at sep; returns the number of pieces. */
static int split(char *s, char sep, char **piece, int max)
{
  int n = 0;
  piece[n++] = s;
  for (; *s && n < max; s++)
    if (*s == sep) {
      *s = '\0';
      piece[n++] = s + 1;
    }
  return n;
}

static int field_index(const char *name)
{
  for (int k = 0; k < NALL; k++)
    if (strcmp(all_fields[k], name) == 0)
      return k;
  ck_abort_msg("unexpected field '%s'", name);
  return -1;
}

/* Check one CSV cell against the value written for point i of pts. */
static void check_cell(const char *cell, const mpm_points *pts, const char *name, size_t i)
{
  const double *real[] = {pts->x, pts->y, pts->vx, pts->vy, pts->sxx, pts->syy, pts->szz,
                          pts->sxy, NULL, pts->mass, pts->vol, NULL, pts->gdp, pts->g, NULL,
                          pts->r1x, pts->r1y, pts->r2x, pts->r2y};
  int k = field_index(name);
  char want[64];
  if (strcmp(name, "state") == 0 || strcmp(name, "id") == 0) {
    snprintf(want, sizeof want, "%d", k == 11 ? pts->state[i] : pts->id[i]);
    ck_assert_str_eq(cell, want);
    return;
  }
  double w = real[k] ? real[k][i] : -(pts->sxx[i] + pts->syy[i] + pts->szz[i]) / 3.0;
  char *end;
  double got = strtod(cell, &end);
  ck_assert_msg(*end == '\0', "bad number '%s'", cell);
  ck_assert_msg(memcmp(&got, &w, sizeof got) == 0, "%s[%zu]: got %s, want %.17g", name, i,
                cell, w);
}

/* Compare extracted CSV with frame f: header names, then every value. */
static void check_table(char *csv, int f, const char *const *names, int nnames)
{
  char *line[64], *cell[64];
  mpm_points *pts = frame_points(f);
  int nl = split(csv, '\n', line, 64);
  ck_assert_int_eq(nl, (int)pts->n + 2); /* header, rows, empty piece after last '\n' */
  ck_assert_str_eq(line[nl - 1], "");
  ck_assert_int_eq(split(line[0], ',', cell, 64), nnames);
  for (int k = 0; k < nnames; k++)
    ck_assert_str_eq(cell[k], names[k]);
  for (size_t i = 0; i < pts->n; i++) {
    ck_assert_int_eq(split(line[i + 1], ',', cell, 64), nnames);
    for (int k = 0; k < nnames; k++)
      check_cell(cell[k], pts, names[k], i);
  }
  mpm_points_free(pts);
}

/* ---- tests ------------------------------------------------------------------------ */

START_TEST(t_extract_frame1_all)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  ck_assert_msg(extract(dir, 1, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 1, all_fields, NALL);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 1, "  ", &t, &err), MPM_OK); /* blank: all fields */
  ck_assert_int_eq(strncmp(t.buf, "x,y,vx,vy,sxx,syy,szz,sxy,p,mass,volume,state,gdot_p,g,id,"
                                  "r1x,r1y,r2x,r2y\n", 74),
                   0);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

/* Frames read back into a point store: every field bit for bit, the time,
 * the mesh attributes, the default shape name (the input text written here
 * has no mesh section) and the frame range. */
START_TEST(t_run_frame_roundtrip)
{
  char dir[DIR_MAX], shape[16];
  mpm_err err = {0};
  mpm_io_run *r = NULL;
  mpm_mesh m, want;
  double t = -1.0;
  write_run(dir);
  ck_assert_msg(mpm_io_run_open(&r, dir, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(mpm_io_run_nframes(r), NFRAMES);
  ck_assert_msg(mpm_io_run_mesh(r, &m, shape, sizeof shape, &err) == MPM_OK, "%s", err.msg);
  fill_mesh(&want);
  ck_assert(m.nx == want.nx && m.ny == want.ny && m.x0 == want.x0 && m.dx == want.dx &&
            m.dy == want.dy && m.topology == want.topology && m.diagonal == want.diagonal &&
            m.nnodes == want.nnodes);
  ck_assert_str_eq(shape, "ugimp");
  mpm_points *pts = mpm_points_alloc(0);
  for (int f = -1; f < NFRAMES; f++) {
    int ff = f < 0 ? NFRAMES - 1 : f;
    mpm_points *w = frame_points(ff);
    ck_assert_msg(mpm_io_run_frame(r, f, pts, &t, &err) == MPM_OK, "%s", err.msg);
    ck_assert(t == frame_time(ff));
    ck_assert_uint_eq(pts->n, w->n);
    for (size_t i = 0; i < w->n; i++) {
      const double *a[] = {pts->x, pts->y, pts->vx, pts->vy, pts->sxx, pts->syy, pts->szz,
                           pts->sxy, pts->mass, pts->vol, pts->gdp, pts->g, pts->r1x,
                           pts->r1y, pts->r2x, pts->r2y};
      const double *b[] = {w->x, w->y, w->vx, w->vy, w->sxx, w->syy, w->szz, w->sxy, w->mass,
                           w->vol, w->gdp, w->g, w->r1x, w->r1y, w->r2x, w->r2y};
      for (size_t k = 0; k < sizeof a / sizeof a[0]; k++)
        ck_assert_msg(memcmp(&a[k][i], &b[k][i], sizeof(double)) == 0, "field %zu point %zu", k, i);
      ck_assert_int_eq(pts->state[i], w->state[i]);
      ck_assert_int_eq(pts->id[i], w->id[i]);
    }
    mpm_points_free(w);
  }
  ck_assert_int_eq(mpm_io_run_frame(r, NFRAMES, pts, &t, &err), MPM_EINPUT);
  mpm_points_free(pts);
  mpm_io_run_close(r);
  remove_tree(dir);
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_EIO);
  ck_assert_ptr_null(r);
}
END_TEST

START_TEST(t_extract_last)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  ck_assert_msg(extract(dir, -1, "", &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, NFRAMES - 1, all_fields, NALL);
  free(t.buf);
  t.buf = NULL;
  ck_assert_msg(extract(dir, 0, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 0, all_fields, NALL);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

static const char *const selected[] = {"vy", "id", "x", "p", "vy"};

START_TEST(t_extract_selection)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  ck_assert_msg(extract(dir, 1, " vy, id ,x,\tp,vy ", &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 1, selected, 5);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

START_TEST(t_extract_unknown_field)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  ck_assert_int_eq(extract(dir, 1, "x,foo", &t, &err), MPM_EINPUT);
  ck_assert_int_eq(err.code, MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "unknown field 'foo'") != NULL, "%s", err.msg);
  ck_assert_msg(strstr(err.msg, "(available: x, y, vx, vy, sxx, syy, szz, sxy, p, mass, "
                                "volume, state, gdot_p, g, id, r1x, r1y, r2x, r2y)") != NULL,
                "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 1, "x,,y", &t, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "empty field name") != NULL, "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 1, "x,", &t, &err), MPM_EINPUT);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

START_TEST(t_extract_frame_range)
{
  char dir[DIR_MAX], want[DIR_MAX + 64];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  ck_assert_int_eq(extract(dir, 12, NULL, &t, &err), MPM_EINPUT);
  snprintf(want, sizeof want, "frame 12 not in run '%s' (frames 0..2)", dir);
  ck_assert_str_eq(err.msg, want);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 3, NULL, &t, &err), MPM_EINPUT);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

START_TEST(t_extract_missing_run)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  text t = {0};
  make_tmpdir(dir);
  snprintf(path, sizeof path, "%s/nothing-here", dir);
  ck_assert_int_eq(extract(path, -1, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "nothing-here/run.h5") != NULL, "%s", err.msg);
  ck_assert_msg(strstr(err.msg, "No such file") != NULL, "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  /* a run.h5 that is not an HDF5 file */
  snprintf(path, sizeof path, "%s/run.h5", dir);
  FILE *f = fopen(path, "w");
  fputs("not hdf5\n", f);
  fclose(f);
  ck_assert_int_eq(extract(dir, -1, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, path) != NULL, "%s", err.msg);
  free(t.buf);
  remove_tree(dir);
}
END_TEST

START_TEST(t_xdmf)
{
  char dir[DIR_MAX], want[128];
  write_run(dir);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), NFRAMES);
  ck_assert_int_eq(count_substr(x, "CollectionType=\"Temporal\""), 1);
  ck_assert_int_eq(count_substr(x, "TopologyType=\"Polyvertex\""), NFRAMES);
  for (int f = 0; f < NFRAMES; f++) {
    snprintf(want, sizeof want, "<Time Value=\"%.17g\"/>", frame_time(f));
    ck_assert_msg(strstr(x, want) != NULL, "missing %s", want);
    snprintf(want, sizeof want, "NumberOfElements=\"%zu\"", frame_npoints(f));
    ck_assert(strstr(x, want) != NULL);
    for (int k = 0; k < NALL; k++) {
      snprintf(want, sizeof want, "run.h5:/frames/%06d/%s<", f, all_fields[k]);
      ck_assert_msg(strstr(x, want) != NULL, "missing %s", want);
    }
  }
  ck_assert_int_eq(count_substr(x, "<Geometry GeometryType=\"XY\">"), NFRAMES);
  for (int f = 0; f < NFRAMES; f++) {
    snprintf(want, sizeof want, "Dimensions=\"%zu 2\" NumberType=\"Float\" Precision=\"8\" "
             "Format=\"HDF\">run.h5:/xdmf/xy_%06d<", frame_npoints(f), f);
    ck_assert_msg(strstr(x, want) != NULL, "missing %s", want);
  }
  /* frames 0 and 1 share one connectivity; frame 2 has fewer points */
  ck_assert_int_eq(count_substr(x, "run.h5:/xdmf/vertex_000000<"), 2);
  ck_assert_int_eq(count_substr(x, "run.h5:/xdmf/vertex_000002<"), 1);
  ck_assert_int_eq(count_substr(x, "<Attribute "), NFRAMES * NALL);
  ck_assert_int_eq(count_substr(x, "</Xdmf>"), 1);
  size_t len = strlen(x);
  ck_assert_str_eq(x + len - strlen("</Xdmf>\n"), "</Xdmf>\n");
  free(x);
  remove_tree(dir);
}
END_TEST

START_TEST(t_diagnostics_csv)
{
  char dir[DIR_MAX], *line[8], row[512];
  write_run(dir);
  char *c = read_file(dir, "diagnostics.csv");
  ck_assert_int_eq(count_lines(c), 1 + NFRAMES);
  ck_assert_int_eq(split(c, '\n', line, 8), NFRAMES + 2);
  ck_assert_int_eq(strncmp(line[0], "t,", 2), 0);
  snprintf(row, sizeof row, "%s", mpm_diag_csv_header(2));
  row[strlen(row) - 1] = '\0';
  ck_assert_str_eq(line[0], row);
  for (int f = 0; f < NFRAMES; f++) {
    mpm_points *pts = frame_points(f);
    mpm_diag d;
    mpm_diag_compute(pts, frame_time(f), &d);
    ck_assert_int_eq(mpm_diag_csv_row(&d, 2, row, sizeof row), MPM_OK);
    row[strlen(row) - 1] = '\0';
    ck_assert_str_eq(line[f + 1], row);
    mpm_points_free(pts);
  }
  free(c);
  remove_tree(dir);
}
END_TEST

static char *read_attr_string(hid_t obj, const char *name)
{
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  ck_assert(a >= 0);
  hid_t type = H5Aget_type(a);
  size_t n = H5Tget_size(type);
  char *s = calloc(n + 1, 1);
  ck_assert(H5Aread(a, type, s) >= 0);
  H5Tclose(type);
  H5Aclose(a);
  return s;
}

static double read_attr_double(hid_t obj, const char *name)
{
  double v = 0.0;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  ck_assert(a >= 0);
  ck_assert(H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0);
  H5Aclose(a);
  return v;
}

static void check_attr_string(hid_t obj, const char *name, const char *want)
{
  char *s = read_attr_string(obj, name);
  ck_assert_str_eq(s, want);
  free(s);
}

/* n ints of dataset `name` of run.h5 in dir into v (at most cap). */
static size_t read_h5_ints(const char *dir, const char *name, int *v, size_t cap)
{
  char path[DIR_MAX + 32];
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  ck_assert_msg(d >= 0, "no %s", name);
  hid_t sp = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(sp);
  ck_assert(n > 0 && (size_t)n <= cap);
  ck_assert(H5Dread(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
  H5Sclose(sp);
  H5Dclose(d);
  H5Fclose(f);
  return (size_t)n;
}

/* Bodies' outlines in bodies.xdmf: frame 0 with a plane square and
 * triangle (one ring each), frame 1 without outlines. run.xdmf is as
 * without bodies; bodies.xdmf has one grid, frame 0's, whose Mixed topology
 * is the two closed polylines (XDMF code 2, vertex count, the ring and its
 * first vertex again), with XYZ vertices as given and the cell field
 * `body`. A new run in the directory removes bodies.xdmf and bodies.csv
 * until it writes its own. */
START_TEST(t_xdmf_bodies)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  make_tmpdir(dir);
  mpm_io_output *out = open_run(dir, "[mesh]\nnx = 4\n");
  const double sq[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, tri[] = {2, 0, 0, 3, 0, 0, 2, 1, 0};
  const mpm_io_outline ol[2] = {{.nv = 4, .nr = 1, .caps = 0, .xyz = sq},
                                {.nv = 3, .nr = 1, .caps = 0, .xyz = tri}};
  const char *names[2] = {"sq", "tri"};
  mpm_body_state b[2];
  memset(b, 0, sizeof b);
  ck_assert_msg(mpm_io_output_bodies(out, frame_time(0), 2, names, b, ol, &err) == MPM_OK, "%s",
                err.msg);
  write_frame(out, 0);
  ck_assert_msg(mpm_io_output_bodies(out, frame_time(1), 2, names, b, NULL, &err) == MPM_OK, "%s",
                err.msg);
  write_frame(out, 1);
  ck_assert_msg(mpm_io_output_close(out, &err) == MPM_OK, "%s", err.msg);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 2);
  ck_assert(strstr(x, "bodies") == NULL);
  free(x);
  x = read_file(dir, "bodies.xdmf");
  ck_assert_int_eq(count_substr(x, "CollectionType=\"Temporal\""), 1);
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"bodies_"), 1);
  ck_assert(strstr(x, "<Grid Name=\"bodies_000000\" GridType=\"Uniform\">") != NULL);
  ck_assert(strstr(x, "<Topology TopologyType=\"Mixed\" NumberOfElements=\"2\">") != NULL);
  ck_assert(strstr(x, "Dimensions=\"13\" NumberType=\"Int\" Precision=\"4\" "
                      "Format=\"HDF\">run.h5:/xdmf/bodies_cells_000000<") != NULL);
  ck_assert(strstr(x, "Dimensions=\"7 3\" NumberType=\"Float\" Precision=\"8\" "
                      "Format=\"HDF\">run.h5:/xdmf/bodies_xyz_000000<") != NULL);
  ck_assert(strstr(x, "<Attribute Name=\"body\" AttributeType=\"Scalar\" Center=\"Cell\">")
            != NULL);
  ck_assert(strstr(x, "bodies_cells_000001") == NULL);
  ck_assert_str_eq(x + strlen(x) - strlen("</Xdmf>\n"), "</Xdmf>\n");
  free(x);
  int v[32];
  const int cells[] = {2, 5, 0, 1, 2, 3, 0, 2, 4, 4, 5, 6, 4};
  ck_assert_uint_eq(read_h5_ints(dir, "xdmf/bodies_cells_000000", v, 32), 13);
  ck_assert(memcmp(v, cells, sizeof cells) == 0);
  ck_assert_uint_eq(read_h5_ints(dir, "xdmf/bodies_id_000000", v, 32), 2);
  ck_assert(v[0] == 0 && v[1] == 1);
  /* a new run without bodies in the same directory */
  char path[DIR_MAX + 32];
  out = open_run(dir, "[mesh]\nnx = 4\n");
  write_frame(out, 0);
  ck_assert_msg(mpm_io_output_close(out, &err) == MPM_OK, "%s", err.msg);
  const char *gone[] = {"bodies.xdmf", "bodies.csv"};
  for (int k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s/%s", dir, gone[k]);
    ck_assert_msg(access(path, F_OK) != 0, "%s left from the earlier run", gone[k]);
  }
  remove_tree(dir);
}
END_TEST

/* /xdmf/xy_NNNNNN reads as the frame's (x, y) pairs. */
static void check_xy_view(hid_t file, int f)
{
  char name[32];
  double xy[2 * 8];
  mpm_points *pts = frame_points(f);
  snprintf(name, sizeof name, "xdmf/xy_%06d", f);
  hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
  ck_assert(d >= 0);
  ck_assert(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xy) >= 0);
  for (size_t i = 0; i < pts->n; i++) {
    ck_assert(memcmp(&xy[2 * i], &pts->x[i], sizeof(double)) == 0);
    ck_assert(memcmp(&xy[2 * i + 1], &pts->y[i], sizeof(double)) == 0);
  }
  H5Dclose(d);
  mpm_points_free(pts);
}

/* Layout through the HDF5 API, with a resolved input larger than the 64 KiB
 * an attribute may hold in the compact (pre-1.8) format. */
START_TEST(t_h5_layout)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  size_t big = 100000;
  char *input = malloc(big + 1);
  for (size_t i = 0; i < big; i++)
    input[i] = i % 64 == 63 ? '\n' : (char)('a' + i % 26);
  input[big] = '\0';
  make_tmpdir(dir);
  mpm_io_output *out = open_run(dir, input);
  for (int f = 0; f < NFRAMES; f++)
    write_frame(out, f);
  ck_assert_msg(mpm_io_output_close(out, &err) == MPM_OK, "%s", err.msg);

  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  ck_assert(file >= 0);
  check_attr_string(file, "version", PACKAGE_VERSION);
  check_attr_string(file, "command_line", "granmpm run test.conf --set a.b=1");
  check_attr_string(file, "input", input);
  hid_t mesh = H5Gopen2(file, "mesh", H5P_DEFAULT);
  ck_assert(mesh >= 0);
  check_attr_string(mesh, "topology", "t3");
  check_attr_string(mesh, "diagonal", "mirror");
  ck_assert(read_attr_double(mesh, "dy") == 1.0 / 3.0);
  H5Gclose(mesh);
  for (int f = 0; f < NFRAMES; f++) {
    char name[32];
    snprintf(name, sizeof name, "frames/%06d", f);
    hid_t g = H5Gopen2(file, name, H5P_DEFAULT);
    ck_assert(g >= 0);
    ck_assert(read_attr_double(g, "time") == frame_time(f));
    hid_t d = H5Dopen2(g, "vx", H5P_DEFAULT);
    check_attr_string(d, "unit", "m/s");
    H5Dclose(d);
    d = H5Dopen2(g, "p", H5P_DEFAULT);
    check_attr_string(d, "unit", "Pa");
    H5Dclose(d);
    H5Gclose(g);
    check_xy_view(file, f);
  }
  H5Fclose(file);
  free(input);
  remove_tree(dir);
}
END_TEST

/* Extract in a separate process (this program, whose path main() leaves in
 * TEST_OUTPUT_PROGRAM, run again with --extract), as `granmpm extract` would
 * while a run is going; returns the exit status and the CSV in t. */
static int extract_in_child(const char *dir, int frame, text *t)
{
  char path[DIR_MAX + 32], num[16];
  int status;
  snprintf(path, sizeof path, "%s.csv", dir);
  snprintf(num, sizeof num, "%d", frame);
  pid_t pid = fork();
  ck_assert(pid >= 0);
  if (pid == 0) {
    const char *self = getenv("TEST_OUTPUT_PROGRAM");
    if (self && freopen(path, "w", stdout))
      execl(self, self, "--extract", dir, num, (char *)NULL);
    _exit(127);
  }
  ck_assert(waitpid(pid, &status, 0) == pid);
  ck_assert(WIFEXITED(status));
  t->buf = read_file(path, "");
  remove(path);
  return WEXITSTATUS(status);
}

/* A run still being written can be extracted from after each frame. */
START_TEST(t_live_extract)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  make_tmpdir(dir);
  mpm_io_output *out = open_run(dir, NULL);
  write_frame(out, 0);
  write_frame(out, 1);
  ck_assert_int_eq(extract_in_child(dir, -1, &t), MPM_OK);
  check_table(t.buf, 1, all_fields, NALL);
  free(t.buf);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 2);
  ck_assert_str_eq(x + strlen(x) - strlen("</Xdmf>\n"), "</Xdmf>\n");
  free(x);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  remove_tree(dir);
}
END_TEST

/* A run killed after two frames (no mpm_io_output_close) leaves both frames
 * readable and a complete run.xdmf. */
START_TEST(t_killed_run)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  int status;
  make_tmpdir(dir);
  pid_t pid = fork();
  ck_assert(pid >= 0);
  if (pid == 0) {
    mpm_io_output *out = open_run(dir, NULL);
    write_frame(out, 0);
    write_frame(out, 1);
    raise(SIGKILL);
  }
  ck_assert(waitpid(pid, &status, 0) == pid);
  ck_assert(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  ck_assert_msg(extract(dir, -1, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 1, all_fields, NALL);
  free(t.buf);
  t.buf = NULL;
  ck_assert_msg(extract(dir, 0, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 0, all_fields, NALL);
  free(t.buf);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 2);
  ck_assert_str_eq(x + strlen(x) - strlen("</Xdmf>\n"), "</Xdmf>\n");
  free(x);
  char *c = read_file(dir, "diagnostics.csv");
  ck_assert_int_eq(count_lines(c), 3);
  free(c);
  remove_tree(dir);
}
END_TEST

START_TEST(t_empty_frame)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  make_tmpdir(dir);
  mpm_io_output *out = open_run(dir, "");
  mpm_points *pts = mpm_points_alloc(0);
  mpm_diag d;
  mpm_diag_compute(pts, 1.5, &d);
  ck_assert_int_eq(mpm_io_output_frame(out, pts, &d, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  ck_assert_msg(extract(dir, 0, "x,id", &t, &err) == MPM_OK, "%s", err.msg);
  ck_assert_str_eq(t.buf, "x,id\n");
  free(t.buf);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 0); /* no empty grids */
  free(x);
  char *c = read_file(dir, "diagnostics.csv");
  ck_assert_int_eq(count_lines(c), 2);
  free(c);
  mpm_points_free(pts);
  remove_tree(dir);
}
END_TEST

START_TEST(t_open_creates_parents)
{
  char dir[DIR_MAX], sub[DIR_MAX + 32];
  mpm_err err = {0};
  struct stat st;
  make_tmpdir(dir);
  snprintf(sub, sizeof sub, "%s/a/b//c/", dir);
  mpm_io_output *out = open_run(sub, NULL);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  snprintf(sub, sizeof sub, "%s/a/b/c/run.h5", dir);
  ck_assert_int_eq(stat(sub, &st), 0);
  /* opening again truncates */
  snprintf(sub, sizeof sub, "%s/a/b/c", dir);
  out = open_run(sub, NULL);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  remove_tree(dir);
}
END_TEST

START_TEST(t_open_fails)
{
  char dir[DIR_MAX], file[DIR_MAX + 32], sub[DIR_MAX + 64], want[DIR_MAX + 128];
  mpm_err err = {0};
  mpm_mesh m;
  mpm_io_output *out = NULL;
  fill_mesh(&m);
  make_tmpdir(dir);
  snprintf(file, sizeof file, "%s/plain", dir);
  FILE *f = fopen(file, "w");
  fclose(f);
  snprintf(sub, sizeof sub, "%s/run", file);
  ck_assert_int_eq(mpm_io_output_open(&out, sub, &no_origin, "", &m, &err), MPM_EIO);
  ck_assert_ptr_null(out);
  snprintf(want, sizeof want, "cannot create directory '%s': Not a directory", sub);
  ck_assert_str_eq(err.msg, want);
  ck_assert_int_eq(mpm_io_output_open(&out, file, &no_origin, "", &m, &err), MPM_EIO);
  ck_assert_int_eq(mpm_io_output_open(&out, "", &no_origin, "", &m, &err), MPM_EINVAL);
  /* run.h5 cannot be created: a directory is in the way */
  snprintf(sub, sizeof sub, "%s/run.h5", dir);
  ck_assert_int_eq(mkdir(sub, 0777), 0);
  ck_assert_int_eq(mpm_io_output_open(&out, dir, &no_origin, "", &m, &err), MPM_EIO);
  ck_assert_ptr_null(out);
  snprintf(want, sizeof want, "cannot create '%s/run.h5': Is a directory", dir);
  ck_assert_str_eq(err.msg, want);
  ck_assert_int_eq(mpm_io_output_close(NULL, &err), MPM_OK);
  remove_tree(dir);
}
END_TEST

/* ---- checkpoints, reopening, damaged runs --------------------------------------- */

static void same_points(const mpm_points *a, const mpm_points *b)
{
  ck_assert_uint_eq(a->n, b->n);
  ck_assert_int_eq(a->next_id, b->next_id);
  ck_assert_int_eq(a->dim, b->dim);
#define SAME_(f, nm, d, u, dim) \
  ck_assert_msg(a->n == 0 || !mpm_points_has(a, dim) || !memcmp(a->f, b->f, a->n * sizeof *a->f), \
                "field %s differs", nm);
  MPM_POINT_REAL_FIELDS(SAME_)
  MPM_POINT_INT_FIELDS(SAME_)
#undef SAME_
}

/* A checkpoint reads back bit for bit: every point field (with -0, the
 * smallest subnormal and -DBL_MAX among them), every scalar, the frame
 * series and an input text of 100 kB (more than an HDF5 attribute of the
 * 1.8 format holds); a second one replaces the first, leaving no temporary
 * file; a file that is not a checkpoint, or a truncated one, is MPM_EIO. */
START_TEST(t_checkpoint_roundtrip)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  struct stat sb;
  make_tmpdir(dir);
  double series_t[3] = {0.0, 0.1, 0.2}, series_m[3] = {3.5, 3.25, -0.0};
  mpm_run_state st = {.pts = frame_points(1), .t = 0.30000000000000004, .dt = 1.1e-5,
                      .step = 27273, .n_sub = 3, .mass0 = 12.5, .mass_removed = 1e-300,
                      .nremoved = 7, .seeded = 1, .outlet_open = 1, .frames = 3,
                      .frame_next = 4, .check_next = 2, .nseries = 3, .series_t = series_t,
                      .series_m = series_m};
  st.pts->next_id = 2147483647;
  char *input = malloc(100001);
  for (int i = 0; i < 100000; i++)
    input[i] = i % 80 == 79 ? '\n' : (char)('a' + i % 26);
  input[100000] = '\0';
  ck_assert_msg(mpm_io_checkpoint_write(dir, &st, "short", "0.1.0 (x)", &err) == MPM_OK, "%s",
                err.msg);
  ck_assert_msg(mpm_io_checkpoint_write(dir, &st, input, "0.1.0 (test)", &err) == MPM_OK, "%s",
                err.msg);
  snprintf(path, sizeof path, "%s/checkpoint.h5.tmp", dir);
  ck_assert_int_ne(stat(path, &sb), 0);
  mpm_io_checkpoint ck;
  ck_assert_msg(mpm_io_checkpoint_read(dir, &ck, &err) == MPM_OK, "%s", err.msg);
  same_points(st.pts, ck.state.pts);
  ck_assert_str_eq(ck.input, input);
  ck_assert_str_eq(ck.written_by, "0.1.0 (test)");
  ck_assert(ck.state.t == st.t && ck.state.dt == st.dt && ck.state.mass0 == st.mass0 &&
            ck.state.mass_removed == st.mass_removed);
  ck_assert(ck.state.step == 27273 && ck.state.n_sub == 3 && ck.state.nremoved == 7 &&
            ck.state.seeded == 1 && ck.state.outlet_open == 1 && ck.state.frames == 3 &&
            ck.state.frame_next == 4 && ck.state.check_next == 2);
  ck_assert_uint_eq(ck.state.nseries, 3);
  ck_assert(!memcmp(ck.state.series_t, series_t, sizeof series_t) &&
            !memcmp(ck.state.series_m, series_m, sizeof series_m));
  mpm_io_checkpoint_clear(&ck);
  double t = 0.0;
  long step = 0;
  ck_assert_int_eq(mpm_io_checkpoint_when(dir, &t, &step, &err), MPM_OK);
  ck_assert(t == st.t && step == 27273);
  /* damaged: cut in half, then not HDF5 at all */
  snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
  ck_assert_int_eq(stat(path, &sb), 0);
  ck_assert_int_eq(truncate(path, sb.st_size / 2), 0);
  ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_EIO);
  ck_assert_ptr_null(ck.state.pts);
  FILE *f = fopen(path, "w");
  fputs("not a checkpoint\n", f);
  fclose(f);
  ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_EIO);
  ck_assert_int_eq(mpm_io_checkpoint_remove(dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_checkpoint_remove(dir, &err), MPM_OK);  /* none: fine */
  ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_EIO);
  free(input);
  mpm_points_free(st.pts);
  remove_tree(dir);
}
END_TEST

/* A run reopened after its first two of three frames: the third frame is
 * gone from run.h5, diagnostics.csv and run.xdmf, a new third frame is
 * appended and reads back; the provenance records the resumption and the
 * end. */
START_TEST(t_reopen_truncates)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  text t = {0};
  write_run(dir);
  const mpm_io_origin again = {"granmpm resume x", "rev-2", 2};
  mpm_io_output *out = NULL;
  ck_assert_msg(mpm_io_output_reopen(&out, dir, &again, 2, &err) == MPM_OK, "%s", err.msg);
  char *c = read_file(dir, "diagnostics.csv");
  ck_assert_int_eq(count_lines(c), 3);
  free(c);
  char *x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 2);
  free(x);
  write_frame(out, 2);
  ck_assert_int_eq(mpm_io_output_end(out, "finished", NULL, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_output_close(out, &err), MPM_OK);
  ck_assert_msg(extract(dir, 2, NULL, &t, &err) == MPM_OK, "%s", err.msg);
  check_table(t.buf, 2, all_fields, NALL);
  free(t.buf);
  c = read_file(dir, "diagnostics.csv");
  ck_assert_int_eq(count_lines(c), 4);
  free(c);
  x = read_file(dir, "run.xdmf");
  ck_assert_int_eq(count_substr(x, "<Grid Name=\"frame_"), 3);
  free(x);
  mpm_io_run *r = NULL;
  mpm_io_provenance p;
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_run_provenance(r, &p, &err), MPM_OK);
  mpm_io_run_close(r);
  ck_assert_str_eq(p.version, PACKAGE_VERSION);
  ck_assert_str_eq(p.revision, "test-revision");
  ck_assert_str_eq(p.command_line, "granmpm run test.conf --set a.b=1");
  ck_assert_int_eq(p.threads, 3);
  ck_assert_int_eq(p.resumed, 1);
  ck_assert_str_eq(p.status, "finished");
  ck_assert_str_eq(p.failure, "");
  ck_assert_msg(strstr(p.resume_log, " threads=2: granmpm resume x\n"), "%s", p.resume_log);
  ck_assert_int_eq((int)strlen(p.start_time), 20);                 /* 2025-01-31T12:00:00Z */
  ck_assert_int_eq((int)strlen(p.end_time), 20);
  ck_assert_int_eq(p.nframes, 3);
  ck_assert(p.t_last == frame_time(2));
  mpm_io_run_provenance_clear(&p);
  remove_tree(dir);
}
END_TEST

/* Damaged runs are errors, found before anything large is allocated: a
 * frame without its x (extract used to print the other columns and exit
 * 0), a frame whose npoints says 2^60 (the frame reader asked for 2^63
 * bytes), a run.h5 cut short. */
START_TEST(t_damaged_run)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  text t = {0};
  mpm_io_run *r = NULL;
  double time;
  struct stat sb;
  write_run(dir);
  snprintf(path, sizeof path, "%s/run.h5", dir);
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  ck_assert_int_ge(f, 0);
  ck_assert_int_ge(H5Ldelete(f, "frames/000002/x", H5P_DEFAULT), 0);
  hid_t g = H5Gopen2(f, "frames/000001", H5P_DEFAULT), a = H5Aopen(g, "npoints", H5P_DEFAULT);
  unsigned long long huge = 1ULL << 60;
  ck_assert_int_ge(H5Awrite(a, H5T_NATIVE_ULLONG, &huge), 0);
  H5Aclose(a);
  H5Gclose(g);
  H5Fclose(f);
  mpm_points *pts = mpm_points_alloc(0);
  ck_assert_int_eq(extract(dir, -1, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "frame 2 of ") && strstr(err.msg, "has no field 'x'"), "%s",
                err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(extract(dir, 1, NULL, &t, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "npoints = 1152921504606846976 but field 'x' holds 5 values"),
                "%s", err.msg);
  free(t.buf);
  t.buf = NULL;
  ck_assert_int_eq(mpm_io_run_open(&r, dir, &err), MPM_OK);
  ck_assert_int_eq(mpm_io_run_frame(r, -1, pts, &time, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "has no field 'x'"), "%s", err.msg);
  ck_assert_int_eq(mpm_io_run_frame(r, 1, pts, &time, &err), MPM_EIO);
  ck_assert_msg(strstr(err.msg, "npoints = 1152921504606846976"), "%s", err.msg);
  ck_assert_int_eq(mpm_io_run_frame(r, 0, pts, &time, &err), MPM_OK);
  mpm_io_run_close(r);
  ck_assert_int_eq(stat(path, &sb), 0);
  ck_assert_int_eq(truncate(path, sb.st_size / 2), 0);
  ck_assert_int_ne(extract(dir, 0, NULL, &t, &err), MPM_OK);
  free(t.buf);
  r = NULL;
  int rc = mpm_io_run_open(&r, dir, &err);
  if (rc == MPM_OK)
    rc = mpm_io_run_frame(r, 0, pts, &time, &err) == MPM_OK &&
                 mpm_io_run_frame(r, -1, pts, &time, &err) == MPM_OK
             ? MPM_OK
             : MPM_EIO;
  ck_assert_int_eq(rc, MPM_EIO);
  mpm_io_run_close(r);
  mpm_points_free(pts);
  remove_tree(dir);
}
END_TEST

/* `test_output --extract DIR FRAME`: print one frame to stdout. */
static int extract_main(const char *dir, const char *frame)
{
  mpm_err err = {0};
  int rc = mpm_io_extract(dir, atoi(frame), NULL, stdout, &err);
  if (rc != MPM_OK)
    fprintf(stderr, "%s\n", err.msg);
  return rc;
}

/* A small valid state of n frames (frame_points(1), ids below next_id) with
 * the series in series_t and series_m (n values each). */
static mpm_run_state small_state(double *series_t, double *series_m, size_t n)
{
  mpm_run_state st = {.pts = frame_points(1), .t = 0.1, .dt = 1e-5, .step = 10000, .n_sub = 1,
                      .mass0 = 3.5, .frames = (long)n, .frame_next = (long)n + 1,
                      .check_next = 1, .nseries = n, .series_t = series_t,
                      .series_m = series_m};
  st.pts->next_id = 2147483647;
  return st;
}

/* The bytes of file path into buf (at most cap); their count. */
static size_t file_bytes(const char *path, unsigned char *buf, size_t cap)
{
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  const size_t len = fread(buf, 1, cap, f);
  fclose(f);
  return len;
}

/* A checkpoint is checked when read: a value out of range written with a
 * right checksum is named (point, id, field, value, allowed range). */
START_TEST(t_checkpoint_values_checked)
{
  char dir[DIR_MAX];
  mpm_err err = {0};
  make_tmpdir(dir);
  double series_t[2] = {0.0, 0.1}, series_m[2] = {3.5, 3.25};
  const mpm_run_state good = small_state(series_t, series_m, 2);
  mpm_points *pts = mpm_points_alloc(0);
  ck_assert_ptr_nonnull(pts);
  const char *want[] = {
    "point 1 (id 2147483101): field 'mass' = nan (allowed: finite and > 0) (a damaged checkpoint)",
    "point 0 (id 2147483100): field 'volume' = -0 (allowed: finite and > 0)",
    "point 2 (id 2147483102): field 'g' = inf (allowed: finite)",
    "point 4 (id 2147483104): field 'state' = 1000000 (allowed: 0 or 1)",
    "point 3: field 'id' = -1 (allowed: 0 ... next_id - 1 = 2147483646)",
    "id 2147483100 is held by two points (allowed: unique ids)",
    "attribute 't' = nan (allowed: finite, >= 0)",
    "attribute 'n_sub' = 0 (allowed: finite, >= 1)",
    "attribute 'dt' = 0 (allowed: finite, > 0)",
    "frame series entry 1: t = 0.1 s, mass inf (allowed: finite)",
  };
  for (int c = 0; c < (int)(sizeof want / sizeof want[0]); c++) {
    mpm_run_state st = good;
    double sm[2] = {series_m[0], series_m[1]};
    st.series_m = sm;
    ck_assert_int_eq(mpm_points_copy(pts, good.pts), MPM_OK);
    st.pts = pts;
    switch (c) {
    case 0: pts->mass[1] = NAN; break;
    case 1: pts->vol[0] = -0.0; break;
    case 2: pts->g[2] = INFINITY; break;
    case 3: pts->state[4] = 1000000; break;
    case 4: pts->id[3] = -1; break;
    case 5: pts->id[4] = pts->id[0]; break;
    case 6: st.t = NAN; break;
    case 7: st.n_sub = 0; break;
    case 8: st.dt = 0.0; break;
    default: sm[1] = INFINITY; break;
    }
    ck_assert_int_eq(mpm_io_checkpoint_write(dir, &st, "input", "test", &err), MPM_OK);
    mpm_io_checkpoint ck;
    ck_assert_int_eq(mpm_io_checkpoint_read(dir, &ck, &err), MPM_EIO);
    ck_assert_msg(strstr(err.msg, want[c]) && strstr(err.msg, "/checkpoint.h5': "),
                  "case %d: %s", c, err.msg);
    ck_assert_ptr_null(ck.state.pts);
  }
  mpm_points_free(pts);
  mpm_points_free(good.pts);
  remove_tree(dir);
}
END_TEST

/* A damaged byte anywhere in a checkpoint: reading it either fails with one
 * line naming the damage, or (a byte HDF5 does not read) gives back the
 * state written, bit for bit: never another state. Every 7th byte. */
START_TEST(t_checkpoint_flipped_bytes)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  double series_t[2] = {0.0, 0.1}, series_m[2] = {3.5, 3.25};
  mpm_run_state st = small_state(series_t, series_m, 2);
  ck_assert_int_eq(mpm_io_checkpoint_write(dir, &st, "mesh {\n  nx = 4\n}\n", "test", &err),
                   MPM_OK);
  snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
  unsigned char *image = malloc(1 << 16);
  ck_assert_ptr_nonnull(image);
  const size_t len = file_bytes(path, image, 1 << 16);
  ck_assert(len > 1000 && len < 1 << 16);
  FILE *f;
  int failed = 0, same = 0, checksum = 0;
  for (size_t off = 0; off < len; off += 7) {
    image[off] ^= 0x5a;
    f = fopen(path, "wb");
    ck_assert_uint_eq(fwrite(image, 1, len, f), len);
    fclose(f);
    image[off] ^= 0x5a;
    mpm_io_checkpoint ck;
    if (mpm_io_checkpoint_read(dir, &ck, &err) != MPM_OK) {
      ck_assert_msg(err.msg[0] && !strchr(err.msg, '\n'), "byte %zu: '%s'", off, err.msg);
      checksum += strstr(err.msg, "checksum") != NULL;
      failed++;
      continue;
    }
    same_points(st.pts, ck.state.pts);
    ck_assert_msg(ck.state.t == st.t && ck.state.dt == st.dt && ck.state.step == st.step &&
                  ck.state.n_sub == st.n_sub && ck.state.mass0 == st.mass0 &&
                  ck.state.frames == st.frames && ck.state.frame_next == st.frame_next &&
                  ck.state.check_next == st.check_next && ck.state.nseries == 2 &&
                  !memcmp(ck.state.series_m, series_m, sizeof series_m) &&
                  !strcmp(ck.input, "mesh {\n  nx = 4\n}\n"), "byte %zu read as another state", off);
    mpm_io_checkpoint_clear(&ck);
    same++;
  }
  ck_assert_msg(failed > 0 && checksum > 0, "%d damaged, %d by a checksum, %d unused", failed,
                checksum, same);
  free(image);
  mpm_points_free(st.pts);
  remove_tree(dir);
}
END_TEST

/* mpm_io_checkpoint_seal writes the user block mpm_io_checkpoint_write
 * wrote, and over changed bytes one that passes the checksum, so that a
 * reader of the file (tests/fuzz/fuzz_checkpoint.c) gets past it to HDF5
 * and the values. */
START_TEST(t_checkpoint_seal)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  double series_t[1] = {0.0}, series_m[1] = {3.5};
  mpm_run_state st = small_state(series_t, series_m, 1);
  ck_assert_int_eq(mpm_io_checkpoint_write(dir, &st, "mesh {\n  nx = 4\n}\n", "test", &err),
                   MPM_OK);
  snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
  unsigned char *image = malloc(1 << 16), *again = malloc(1 << 16);
  ck_assert(image && again);
  const size_t len = file_bytes(path, image, 1 << 16);
  ck_assert(len > 1000 && len < 1 << 16);
  FILE *f;
  memcpy(again, image, len);
  memset(again, 'x', 512);
  ck_assert_int_eq(mpm_io_checkpoint_seal(again, len), 0);
  ck_assert_msg(memcmp(again, image, len) == 0, "the sealed block differs from the written one");
  ck_assert_int_eq(mpm_io_checkpoint_seal(again, 511), -1);
  again[len - 1] ^= 0x5a;                 /* a changed byte, sealed: no checksum refuses it */
  ck_assert_int_eq(mpm_io_checkpoint_seal(again, len), 0);
  f = fopen(path, "wb");
  ck_assert_uint_eq(fwrite(again, 1, len, f), len);
  fclose(f);
  mpm_io_checkpoint ck;
  if (mpm_io_checkpoint_read(dir, &ck, &err) != MPM_OK)
    ck_assert_msg(!strstr(err.msg, "do not match its checksum"), "refused by the block: %s",
                  err.msg);
  mpm_io_checkpoint_clear(&ck);
  free(image);
  free(again);
  mpm_points_free(st.pts);
  remove_tree(dir);
}
END_TEST

/* A damaged byte in a frame's data: extract names the frame, the field and
 * the checksum, in one line, where the point values would have been read
 * wrong before. */
START_TEST(t_frame_flipped_byte)
{
  char dir[DIR_MAX], path[DIR_MAX + 32];
  mpm_err err = {0};
  make_tmpdir(dir);
  write_run(dir);
  snprintf(path, sizeof path, "%s/run.h5", dir);
  /* the file offset of frame 1's field 'mass': HDF5 tells where its chunk is */
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(file, "frames/000001/mass", H5P_DEFAULT);
  haddr_t addr = HADDR_UNDEF;
  hsize_t size = 0, zero[1] = {0};
  ck_assert_int_ge(H5Dget_chunk_info_by_coord(d, zero, NULL, &addr, &size), 0);
  H5Dclose(d);
  H5Fclose(file);
  ck_assert(addr != HADDR_UNDEF && size == 5 * sizeof(double) + 4);
  FILE *f = fopen(path, "r+b");
  ck_assert_ptr_nonnull(f);
  ck_assert_int_eq(fseek(f, (long)addr + 9, SEEK_SET), 0);
  const int byte = fgetc(f);
  ck_assert_int_eq(fseek(f, (long)addr + 9, SEEK_SET), 0);
  fputc(byte ^ 0x10, f);
  fclose(f);
  char *out = NULL;
  size_t outlen = 0;
  FILE *o = open_memstream(&out, &outlen);
  ck_assert_int_eq(mpm_io_extract(dir, 1, "id,mass", o, &err), MPM_EIO);
  fclose(o);
  free(out);
  char want[DIR_MAX + 160];
  snprintf(want, sizeof want, "frame 1 of '%s': cannot read field 'mass': data error detected by "
           "Fletcher32 checksum (a damaged run)", path);
  ck_assert_str_eq(err.msg, want);
  remove_tree(dir);
}
END_TEST

/* `test_output --damage DIR FRAME`: remove field x of frame FRAME of DIR's
 * run.h5 and set npoints of frame 0 to 2^60 (for tests/cli-faults.sh). */
static int damage_main(const char *dir, const char *frame)
{
  char path[DIR_MAX + 32], name[64];
  snprintf(path, sizeof path, "%s/run.h5", dir);
  snprintf(name, sizeof name, "frames/%06d/x", atoi(frame));
  hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
  hid_t g = f < 0 ? -1 : H5Gopen2(f, "frames/000000", H5P_DEFAULT);
  hid_t a = g < 0 ? -1 : H5Aopen(g, "npoints", H5P_DEFAULT);
  unsigned long long huge = 1ULL << 60;
  int bad = a < 0 || H5Awrite(a, H5T_NATIVE_ULLONG, &huge) < 0 || H5Ldelete(f, name, H5P_DEFAULT) < 0;
  H5Aclose(a);
  H5Gclose(g);
  return H5Fclose(f) < 0 || bad;
}

/* The bytes of dataset d's values as type t (its storage also holds
 * checksums). */
static hsize_t data_size(hid_t d, hid_t t)
{
  hid_t sp = d < 0 || t < 0 ? -1 : H5Dget_space(d);
  hssize_t n = sp < 0 ? 0 : H5Sget_simple_extent_npoints(sp);
  if (sp >= 0)
    H5Sclose(sp);
  return n > 0 ? (hsize_t)n * H5Tget_size(t) : 0;
}

static herr_t same_dataset(hid_t ga, const char *name, const H5L_info_t *info, void *gb)
{
  (void)info;
  hid_t da = H5Dopen2(ga, name, H5P_DEFAULT), db = H5Dopen2(*(hid_t *)gb, name, H5P_DEFAULT);
  hid_t ta = da < 0 ? -1 : H5Dget_type(da);
  hsize_t na = data_size(da, ta), nb = data_size(db, ta);
  char *a = malloc(na + 1), *b = malloc(nb + 1);
  int same = da >= 0 && db >= 0 && ta >= 0 && na == nb && a && b &&
             H5Dread(da, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, a) >= 0 &&
             H5Dread(db, ta, H5S_ALL, H5S_ALL, H5P_DEFAULT, b) >= 0 && !memcmp(a, b, na);
  if (!same)
    fprintf(stderr, "dataset %s differs\n", name);
  free(a);
  free(b);
  H5Tclose(ta);
  H5Dclose(da);
  H5Dclose(db);
  return same ? 0 : 1;
}

/* `test_output --same-frames A B`: every frame of A/run.h5 and B/run.h5,
 * dataset by dataset, byte for byte (for tests/cli-survive.sh). */
static int same_frames_main(const char *dir_a, const char *dir_b)
{
  char pa[DIR_MAX + 32], pb[DIR_MAX + 32], name[32];
  snprintf(pa, sizeof pa, "%s/run.h5", dir_a);
  snprintf(pb, sizeof pb, "%s/run.h5", dir_b);
  hid_t fa = H5Fopen(pa, H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(pb, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t fra = fa < 0 ? -1 : H5Gopen2(fa, "frames", H5P_DEFAULT);
  hid_t frb = fb < 0 ? -1 : H5Gopen2(fb, "frames", H5P_DEFAULT);
  H5G_info_t ia, ib;
  int bad = fra < 0 || frb < 0 || H5Gget_info(fra, &ia) < 0 || H5Gget_info(frb, &ib) < 0 ||
            ia.nlinks != ib.nlinks || ia.nlinks == 0;
  if (bad)
    fprintf(stderr, "frame counts differ or are missing\n");
  for (hsize_t k = 0; !bad && k < ia.nlinks; k++) {
    snprintf(name, sizeof name, "%06llu", (unsigned long long)k);
    hid_t ga = H5Gopen2(fra, name, H5P_DEFAULT), gb = H5Gopen2(frb, name, H5P_DEFAULT);
    double ta = 0, tb = 1;
    bad = ga < 0 || gb < 0 || mpm_io_h5_attr_read(ga, "time", H5T_NATIVE_DOUBLE, &ta) < 0 ||
          mpm_io_h5_attr_read(gb, "time", H5T_NATIVE_DOUBLE, &tb) < 0 ||
          memcmp(&ta, &tb, sizeof ta) != 0 ||
          H5Literate(ga, H5_INDEX_NAME, H5_ITER_INC, NULL, same_dataset, &gb) != 0;
    if (bad)
      fprintf(stderr, "frame %s differs\n", name);
    H5Gclose(ga);
    H5Gclose(gb);
  }
  H5Gclose(fra);
  H5Gclose(frb);
  H5Fclose(fa);
  H5Fclose(fb);
  return bad;
}

int main(int argc, char **argv)
{
  if (argc == 4 && strcmp(argv[1], "--same-frames") == 0)
    return same_frames_main(argv[2], argv[3]);
  if (argc == 4 && strcmp(argv[1], "--extract") == 0)
    return extract_main(argv[2], argv[3]);
  if (argc == 4 && strcmp(argv[1], "--damage") == 0)
    return damage_main(argv[2], argv[3]);
  setenv("TEST_OUTPUT_PROGRAM", argv[0], 1);
  Suite *s = suite_create("output");
  TCase *tc = tcase_create("output");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_extract_frame1_all);
  tcase_add_test(tc, t_extract_last);
  tcase_add_test(tc, t_run_frame_roundtrip);
  tcase_add_test(tc, t_extract_selection);
  tcase_add_test(tc, t_extract_unknown_field);
  tcase_add_test(tc, t_extract_frame_range);
  tcase_add_test(tc, t_extract_missing_run);
  tcase_add_test(tc, t_xdmf);
  tcase_add_test(tc, t_xdmf_bodies);
  tcase_add_test(tc, t_diagnostics_csv);
  tcase_add_test(tc, t_h5_layout);
  tcase_add_test(tc, t_live_extract);
  tcase_add_test(tc, t_killed_run);
  tcase_add_test(tc, t_empty_frame);
  tcase_add_test(tc, t_open_creates_parents);
  tcase_add_test(tc, t_open_fails);
  tcase_add_test(tc, t_checkpoint_roundtrip);
  tcase_add_test(tc, t_checkpoint_values_checked);
  tcase_add_test(tc, t_checkpoint_flipped_bytes);
  tcase_add_test(tc, t_checkpoint_seal);
  tcase_add_test(tc, t_frame_flipped_byte);
  tcase_add_test(tc, t_reopen_truncates);
  tcase_add_test(tc, t_damaged_run);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
