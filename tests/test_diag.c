/* test_diag.c: whole-body diagnostics against hand-computed values for 2D
 * and 3D stores, and the diagnostics CSV header and row of each dimension. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "diag/diag.h"

#define RTOL 1e-14

static void ck_close(double got, double want)
{
  double tol = RTOL * (fabs(want) > 1.0 ? fabs(want) : 1.0);
  ck_assert_msg(fabs(got - want) <= tol, "got %.17g, want %.17g", got, want);
}

typedef struct pt_init {
  double x, y, vx, vy, m, vol, sxx, syy, szz, sxy;
  int state;
} pt_init;

/* Three points:
 *   0: m 2, v (1, 2),    x (0, 0), s = (-3, -6, -9, 1) -> p 6
 *   1: m 1, v (-2, 0.5), x (3, 0), s = (-1, -1, -1, 0) -> p 1
 *   2: m 1, v (0, -4),   x (0, 6), stress-free, disconnected
 * K = (2*5 + 1*4.25 + 1*16)/2 = 15.125, M = 4, K/M = 3.78125,
 * P = (0, 0.5), x_c = (0.75, 1.5), p_m = (2*6 + 1)/4 = 3.25, V = 1. */
static const pt_init three[] = {
  {0, 0, 1, 2, 2, 0.5, -3, -6, -9, 1, MPM_STATE_DENSE},
  {3, 0, -2, 0.5, 1, 0.25, -1, -1, -1, 0, MPM_STATE_DENSE},
  {0, 6, 0, -4, 1, 0.25, 0, 0, 0, 0, MPM_STATE_DISCONNECTED},
};

static mpm_points *make_points(const pt_init *p, size_t n)
{
  mpm_points *pts = mpm_points_alloc(n);
  ck_assert_ptr_nonnull(pts);
  for (size_t k = 0; k < n; k++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
    pts->x[i] = p[k].x;
    pts->y[i] = p[k].y;
    pts->vx[i] = p[k].vx;
    pts->vy[i] = p[k].vy;
    pts->mass[i] = p[k].m;
    pts->vol[i] = p[k].vol;
    pts->sxx[i] = p[k].sxx;
    pts->syy[i] = p[k].syy;
    pts->szz[i] = p[k].szz;
    pts->sxy[i] = p[k].sxy;
    pts->state[i] = p[k].state;
  }
  return pts;
}

START_TEST(t_three_points)
{
  mpm_points *pts = make_points(three, 3);
  mpm_diag d;
  mpm_diag_compute(pts, 0.125, &d);
  ck_close(d.t, 0.125);
  ck_close(d.kinetic, 15.125);
  ck_close(d.kinetic_per_mass, 3.78125);
  ck_assert(mpm_diag_kinetic_per_mass(pts) == d.kinetic_per_mass);  /* same sums, same order */
  ck_assert_int_eq(d.stop, MPM_STOP_NONE);
  ck_close(d.px, 0.0);
  ck_close(d.py, 0.5);
  ck_close(d.mass, 4.0);
  ck_close(d.volume, 1.0);
  ck_close(d.xcm, 0.75);
  ck_close(d.ycm, 1.5);
  ck_close(d.pmean, 3.25);
  ck_assert_uint_eq(d.npoints, 3);
  ck_assert_uint_eq(d.ndisconnected, 1);
  mpm_points_free(pts);
}
END_TEST

/* A rigid translation of many points: K = M |v|^2 / 2 and P = M v exactly in
 * the limit; the sums must stay within round-off. */
START_TEST(t_uniform_motion)
{
  enum { N = 1000 };
  mpm_points *pts = mpm_points_alloc(N);
  mpm_diag d;
  for (size_t k = 0; k < N; k++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
    pts->x[i] = (double)(k % 10);
    pts->y[i] = (double)(k / 10);
    pts->vx[i] = 3.0;
    pts->vy[i] = -4.0;
    pts->mass[i] = 0.5;
    pts->vol[i] = 0.25;
    pts->sxx[i] = pts->syy[i] = pts->szz[i] = -100.0; /* p = 100 */
  }
  mpm_diag_compute(pts, 1.0, &d);
  ck_close(d.mass, 500.0);
  ck_close(d.kinetic, 0.5 * 500.0 * 25.0);
  ck_close(d.kinetic_per_mass, 12.5);
  ck_close(d.px, 1500.0);
  ck_close(d.py, -2000.0);
  ck_close(d.xcm, 4.5);
  ck_close(d.ycm, 49.5);
  ck_close(d.pmean, 100.0);
  ck_close(d.volume, 250.0);
  ck_assert_uint_eq(d.ndisconnected, 0);
  mpm_points_free(pts);
}
END_TEST

START_TEST(t_empty)
{
  mpm_points *pts = mpm_points_alloc(0);
  mpm_diag d;
  mpm_diag_compute(pts, 2.0, &d);
  ck_assert(d.t == 2.0);
  ck_assert(d.kinetic == 0.0 && d.kinetic_per_mass == 0.0 && d.mass == 0.0);
  ck_assert(d.xcm == 0.0 && d.ycm == 0.0 && d.pmean == 0.0);
  ck_assert_uint_eq(d.npoints, 0);
  mpm_diag_compute(NULL, 3.0, &d);
  ck_assert(d.t == 3.0 && d.npoints == 0);
  mpm_points_free(pts);
}
END_TEST

START_TEST(t_csv_header)
{
  const char *h = mpm_diag_csv_header(2);
  ck_assert_str_eq(h, "t,kinetic,kinetic_per_mass,px,py,mass,volume,xcm,ycm,pmean,"
                      "npoints,ndisconnected,stop,mass_removed,nremoved,mass_region\n");
}
END_TEST

START_TEST(t_csv_row)
{
  mpm_points *pts = make_points(three, 3);
  mpm_diag d;
  char buf[512];
  double v[10];
  unsigned long np, nd;
  mpm_diag_compute(pts, 0.125, &d);
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, sizeof buf), MPM_OK);
  ck_assert_str_eq(buf, "0.125,15.125,3.78125,0,0.5,4,1,0.75,1.5,3.25,3,1,0,0,0,0\n");
  d.stop = MPM_STOP_KE;
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, sizeof buf), MPM_OK);
  int stop = -1;
  int got = sscanf(buf, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lu,%lu,%d", &v[0], &v[1],
                   &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9], &np, &nd, &stop);
  ck_assert_int_eq(got, 13);
  ck_assert_int_eq(stop, 2);
  ck_assert_uint_eq(np, 3);
  ck_assert_uint_eq(nd, 1);
  /* %.10g: ten significant digits */
  d.kinetic = 1.0 / 3.0;
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, sizeof buf), MPM_OK);
  ck_assert_ptr_nonnull(strstr(buf, ",0.3333333333,"));
  mpm_points_free(pts);
}
END_TEST

START_TEST(t_csv_row_small_buffer)
{
  mpm_diag d;
  char buf[16];
  memset(&d, 0, sizeof d);
  d.t = 1.0 / 3.0;
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, sizeof buf), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, 0), MPM_EINVAL);
  ck_assert_int_eq(mpm_diag_csv_row(NULL, 2, buf, sizeof buf), MPM_EINVAL);
}
END_TEST

/* The three points above in a 3D store, with z, vz and the shear stresses
 * syz, szx (which leave p alone):
 *   0: v (1, 2, 2),    x (0, 0, 1),  syz 5, szx 7
 *   1: v (-2, 0.5, -1), x (3, 0, -2)
 *   2: v (0, -4, 3),   x (0, 6, 4)
 * K = (2*9 + 1*5.25 + 1*25)/2 = 24.125, K/M = 6.03125, P = (0, 0.5, 6),
 * x_c = (0.75, 1.5, 1), p_m = 3.25, V = 1 (m^3). */
static const double three_z[3][3] = {{1, 2, 5}, {-2, -1, 0}, {4, 3, 0}}; /* z, vz, syz */

static mpm_points *make_points3(int with_z)
{
  mpm_points *pts = make_points(three, 3);
  ck_assert_int_eq(mpm_points_set_dim(pts, 3), MPM_OK);
  ck_assert_int_eq(pts->dim, 3);
  for (size_t i = 0; with_z && i < 3; i++) {
    pts->z[i] = three_z[i][0];
    pts->vz[i] = three_z[i][1];
    pts->syz[i] = three_z[i][2];
  }
  if (with_z)
    pts->szx[0] = 7.0;
  return pts;
}

START_TEST(t_three_points_3d)
{
  mpm_points *pts = make_points3(1);
  mpm_diag d;
  mpm_diag_compute(pts, 0.125, &d);
  ck_close(d.kinetic, 24.125);
  ck_close(d.kinetic_per_mass, 6.03125);
  ck_assert(mpm_diag_kinetic_per_mass(pts) == d.kinetic_per_mass);
  ck_close(d.px, 0.0);
  ck_close(d.py, 0.5);
  ck_close(d.pz, 6.0);
  ck_close(d.mass, 4.0);
  ck_close(d.volume, 1.0);
  ck_close(d.xcm, 0.75);
  ck_close(d.ycm, 1.5);
  ck_close(d.zcm, 1.0);
  ck_close(d.pmean, 3.25);
  ck_assert_uint_eq(d.npoints, 3);
  ck_assert_uint_eq(d.ndisconnected, 1);
  mpm_points_free(pts);
}
END_TEST

/* A 2D store has zero z fields; a 3D store with z = vz = 0 gives the 2D
 * store's values bit for bit. */
START_TEST(t_2d_equals_flat_3d)
{
  mpm_points *p2 = make_points(three, 3), *p3 = make_points3(0);
  mpm_diag a, b;
  mpm_diag_compute(p2, 0.5, &a);
  mpm_diag_compute(p3, 0.5, &b);
  ck_assert(a.pz == 0.0 && a.zcm == 0.0);
  ck_assert(a.kinetic == b.kinetic && a.kinetic_per_mass == b.kinetic_per_mass);
  ck_assert(a.px == b.px && a.py == b.py && b.pz == 0.0);
  ck_assert(a.mass == b.mass && a.volume == b.volume && a.pmean == b.pmean);
  ck_assert(a.xcm == b.xcm && a.ycm == b.ycm && b.zcm == 0.0);
  ck_assert(a.npoints == b.npoints && a.ndisconnected == b.ndisconnected);
  ck_assert(mpm_diag_kinetic_per_mass(p2) == mpm_diag_kinetic_per_mass(p3));
  mpm_points_free(p2);
  mpm_points_free(p3);
}
END_TEST

static int count_columns(const char *line)
{
  int n = 1;
  for (; *line && *line != '\n'; line++)
    n += *line == ',';
  return n;
}

START_TEST(t_csv_3d)
{
  const char *h2 = mpm_diag_csv_header(2), *h3 = mpm_diag_csv_header(3);
  mpm_points *pts = make_points3(1);
  mpm_diag d;
  char buf[512];
  double v[18];
  /* the 2D columns keep their positions; pz and zcm follow */
  ck_assert_int_eq(count_columns(h2), 16);
  ck_assert_int_eq(count_columns(h3), 18);
  ck_assert_int_eq(strncmp(h3, h2, strlen(h2) - 1), 0);
  ck_assert_str_eq(h3 + strlen(h2) - 1, ",pz,zcm\n");
  mpm_diag_compute(pts, 0.125, &d);
  ck_assert_int_eq(mpm_diag_csv_row(&d, 3, buf, sizeof buf), MPM_OK);
  ck_assert_str_eq(buf, "0.125,24.125,6.03125,0,0.5,4,1,0.75,1.5,3.25,3,1,0,0,0,0,6,1\n");
  ck_assert_int_eq(count_columns(buf), 18);
  int got = sscanf(buf, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf",
                   &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9],
                   &v[10], &v[11], &v[12], &v[13], &v[14], &v[15], &v[16], &v[17]);
  ck_assert_int_eq(got, 18);
  ck_assert(v[16] == 6.0 && v[17] == 1.0);
  /* the same diagnostics as a 2D row: the 2D columns only */
  ck_assert_int_eq(mpm_diag_csv_row(&d, 2, buf, sizeof buf), MPM_OK);
  ck_assert_str_eq(buf, "0.125,24.125,6.03125,0,0.5,4,1,0.75,1.5,3.25,3,1,0,0,0,0\n");
  /* room for the 2D part but not for pz and zcm */
  size_t n2 = strlen(buf);
  ck_assert_int_eq(mpm_diag_csv_row(&d, 3, buf, n2 + 2), MPM_EINVAL);
  ck_assert_str_eq(buf, "");
  mpm_points_free(pts);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("diag");
  TCase *tc = tcase_create("diag");
  tcase_add_test(tc, t_three_points);
  tcase_add_test(tc, t_uniform_motion);
  tcase_add_test(tc, t_empty);
  tcase_add_test(tc, t_csv_header);
  tcase_add_test(tc, t_csv_row);
  tcase_add_test(tc, t_csv_row_small_buffer);
  tcase_add_test(tc, t_three_points_3d);
  tcase_add_test(tc, t_2d_equals_flat_3d);
  tcase_add_test(tc, t_csv_3d);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
