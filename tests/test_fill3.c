/* test_fill3.c: 3D fills (mpm_scenario_fill3) on a mesh of boxes with an
 * offset origin and unequal unit sizes. A box of whole units gets exactly
 * n^3 points per unit, one at every sub-cell centre, with the volume and
 * mass of the box and the extents dx/2n, dy/2n, dz/2n; a cylinder along
 * each axis gets exactly the sub-cell centres inside it, and its volume
 * tends to pi R^2 L within a bound derived below; a prism gets the centres
 * inside its polygon and z range; regions that leave the
 * mesh and 2D stores are refused. */
#define _DEFAULT_SOURCE /* M_PI */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/box.h"
#include "scenario/scenario.h"

#define REL 1e-12

static void mesh_of(mpm_mesh3 *m)
{
  memset(m, 0, sizeof *m);
  m->nx = 4;
  m->ny = 3;
  m->nz = 5;
  m->x0 = 1.0;
  m->y0 = -2.0;
  m->z0 = 0.5;
  m->dx = 0.5;
  m->dy = 0.25;
  m->dz = 0.4;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh3_setup(m, &err) == MPM_OK, "%s", err.msg);
}

static mpm_fill3_region box_of(const mpm_mesh3 *m, const int u0[3], const int u1[3], int n)
{
  mpm_fill3_region f;
  memset(&f, 0, sizeof f);
  f.shape = MPM_FILL3_BOX;
  const double o[3] = {m->x0, m->y0, m->z0}, d[3] = {m->dx, m->dy, m->dz};
  for (int a = 0; a < 3; a++) {
    f.lo[a] = o[a] + u0[a] * d[a];
    f.hi[a] = o[a] + u1[a] * d[a];
  }
  f.ppu = n;
  f.density = 1500.0;
  f.v[0] = 0.1;
  f.v[1] = -0.2;
  f.v[2] = 0.3;
  return f;
}

static int near(double a, double b, double tol)
{
  return fabs(a - b) <= tol * fmax(fabs(a), fabs(b));
}

/* Units [1, 3) x [0, 2) x [1, 4), n = 3: 2 x 2 x 3 units of 27 points. */
START_TEST(box_of_whole_units)
{
  mpm_mesh3 m;
  mesh_of(&m);
  const int u0[3] = {1, 0, 1}, u1[3] = {3, 2, 4}, n = 3;
  mpm_fill3_region f = box_of(&m, u0, u1, n);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_msg(mpm_scenario_fill3(pts, &m, &f, &err) == MPM_OK, "%s", err.msg);
  const int ns[3] = {(u1[0] - u0[0]) * n, (u1[1] - u0[1]) * n, (u1[2] - u0[2]) * n};
  const size_t want = (size_t)ns[0] * ns[1] * ns[2];
  ck_assert_uint_eq(pts->n, want);
  ck_assert_uint_eq(mpm_scenario_count3(&f, &m), want);

  const double h[3] = {m.dx / n, m.dy / n, m.dz / n}, o[3] = {m.x0, m.y0, m.z0};
  const double vp = h[0] * h[1] * h[2];
  char *hit = calloc(want, 1);
  double vol = 0.0, mass = 0.0;
  for (size_t p = 0; p < pts->n; p++) {
    const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
    long s[3];
    for (int a = 0; a < 3; a++) {
      /* sub-cell index from the position, then the centre it must be */
      double t = (x[a] - o[a]) / h[a] - 0.5;
      s[a] = lround(t);
      ck_assert_msg(fabs(t - s[a]) < 1e-9, "point %zu off the sub-cell centres on axis %d",
                    p, a);
      ck_assert_msg(fabs(x[a] - (o[a] + (s[a] + 0.5) * h[a])) <= 1e-14 * (fabs(x[a]) + 1),
                    "point %zu axis %d", p, a);
      s[a] -= (long)u0[a] * n;
      ck_assert_msg(s[a] >= 0 && s[a] < ns[a], "point %zu outside the box on axis %d", p, a);
    }
    size_t id = ((size_t)s[2] * ns[1] + (size_t)s[1]) * ns[0] + (size_t)s[0];
    ck_assert_msg(!hit[id], "sub-cell centre filled twice");
    hit[id] = 1;
    ck_assert(near(pts->vol[p], vp, REL));
    ck_assert(near(pts->mass[p], f.density * vp, REL));
    ck_assert(near(pts->r1x[p], 0.5 * h[0], REL) && pts->r1y[p] == 0.0 && pts->r1z[p] == 0.0);
    ck_assert(near(pts->r2y[p], 0.5 * h[1], REL) && pts->r2x[p] == 0.0 && pts->r2z[p] == 0.0);
    ck_assert(near(pts->r3z[p], 0.5 * h[2], REL) && pts->r3x[p] == 0.0 && pts->r3y[p] == 0.0);
    ck_assert(pts->vx[p] == 0.1 && pts->vy[p] == -0.2 && pts->vz[p] == 0.3);
    ck_assert(pts->sxx[p] == 0.0 && pts->syy[p] == 0.0 && pts->szz[p] == 0.0 &&
              pts->sxy[p] == 0.0 && pts->syz[p] == 0.0 && pts->szx[p] == 0.0);
    vol += pts->vol[p];
    mass += pts->mass[p];
  }
  free(hit);
  /* n^3 points in every unit of the box */
  for (int k = u0[2]; k < u1[2]; k++)
    for (int j = u0[1]; j < u1[1]; j++)
      for (int i = u0[0]; i < u1[0]; i++) {
        int c = 0;
        for (size_t p = 0; p < pts->n; p++) {
          const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
          int u[3];
          double l[3];
          ck_assert_int_eq(mpm_mesh3_locate(&m, x, u, l), 0);
          c += u[0] == i && u[1] == j && u[2] == k;
        }
        ck_assert_int_eq(c, n * n * n);
      }
  const double box = (f.hi[0] - f.lo[0]) * (f.hi[1] - f.lo[1]) * (f.hi[2] - f.lo[2]);
  ck_assert_msg(near(vol, box, REL), "volume %.17g, box %.17g", vol, box);
  ck_assert_msg(near(mass, f.density * box, REL), "mass %.17g", mass);
  mpm_points_free(pts);
}
END_TEST

/* A box that cuts units appends to a store that already has points. */
START_TEST(box_appends)
{
  mpm_mesh3 m;
  mesh_of(&m);
  const int u0[3] = {0, 0, 0}, u1[3] = {1, 1, 1};
  mpm_fill3_region f = box_of(&m, u0, u1, 2);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_OK);
  ck_assert_uint_eq(pts->n, 8);
  f.lo[0] = 1.3;                 /* sub-cells of 0.25: centres 1.375, 1.625, ... */
  f.hi[0] = 2.2;
  f.ppu = 2;
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_OK);
  ck_assert_uint_eq(pts->n, 8 + 4 * 2 * 2);   /* x: 1.375 1.625 1.875 2.125 */
  ck_assert(pts->x[8] == 1.375);
  mpm_points_free(pts);
}
END_TEST

/* The sub-cell centres inside a cylinder, counted directly over the whole
 * mesh with the test's own inside test. */
static size_t direct_count(const mpm_mesh3 *m, const mpm_fill3_region *f)
{
  const int n = f->ppu;
  size_t c = 0;
  for (long k = 0; k < (long)m->nz * n; k++)
    for (long j = 0; j < (long)m->ny * n; j++)
      for (long i = 0; i < (long)m->nx * n; i++) {
        const double x[3] = {m->x0 + (i + 0.5) * (m->dx / n), m->y0 + (j + 0.5) * (m->dy / n),
                             m->z0 + (k + 0.5) * (m->dz / n)};
        const int a = f->axis, b = (a + 1) % 3, cc = (a + 2) % 3;
        double eb = x[b] - f->centre[b], ec = x[cc] - f->centre[cc];
        c += fabs(x[a] - f->centre[a]) <= 0.5 * f->length &&
             eb * eb + ec * ec <= f->radius * f->radius;
      }
  return c;
}

/* Along each axis a, the fill of a cylinder of radius R and length L is the
 * product of the sub-squares (h_b x h_c) whose centres lie in the disc and
 * the sub-cells along a whose centres lie in the length. A square with its
 * centre in the disc lies in the disc grown by its half-diagonal
 * d = sqrt(h_b^2 + h_c^2) / 2, and every square meeting the disc shrunk by d
 * has its centre in the disc, so the area A_n lies in
 * [pi (R - d)^2, pi (R + d)^2]: |A_n - pi R^2| <= pi (2 R d + d^2). The centres
 * in a closed interval of length L number floor(L/h_a) or one more, so
 * |L_n - L| <= h_a. Then
 * |A_n L_n - pi R^2 L| <= pi (2 R d + d^2) (L + h_a) + pi R^2 h_a, O(1/n). */
START_TEST(cylinder_converges)
{
  mpm_mesh3 m;
  mesh_of(&m);                          /* [1, 3] x [-2, -1.25] x [0.5, 2.5] */
  const double c[3] = {2.0, -1.6, 1.5};
  const double R[3] = {0.3, 0.35, 0.3}, L[3] = {1.7, 0.7, 1.9};
  for (int a = 0; a < 3; a++) {
    double prev_bound = INFINITY;
    for (int n = 1; n <= 16; n *= 2) {
      mpm_fill3_region f;
      memset(&f, 0, sizeof f);
      f.shape = MPM_FILL3_CYLINDER;
      f.axis = a;
      memcpy(f.centre, c, sizeof c);
      f.radius = R[a];
      f.length = L[a];
      f.ppu = n;
      f.density = 2000.0;
      mpm_points *pts = mpm_points_alloc_dim(0, 3);
      mpm_err err = {0};
      ck_assert_msg(mpm_scenario_fill3(pts, &m, &f, &err) == MPM_OK, "%s", err.msg);
      ck_assert_uint_eq(pts->n, direct_count(&m, &f));
      ck_assert_uint_eq(mpm_scenario_count3(&f, &m), pts->n);
      double vol = 0.0, mass = 0.0;
      for (size_t p = 0; p < pts->n; p++) {
        const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
        ck_assert(mpm_scenario_inside3(&f, x));
        vol += pts->vol[p];
        mass += pts->mass[p];
      }
      ck_assert(near(mass, f.density * vol, REL));
      const double h[3] = {m.dx / n, m.dy / n, m.dz / n};
      const int b = (a + 1) % 3, cc = (a + 2) % 3;
      const double d = 0.5 * hypot(h[b], h[cc]);
      const double exact = M_PI * R[a] * R[a] * L[a];
      const double bound = M_PI * (2.0 * R[a] * d + d * d) * (L[a] + h[a]) +
                           M_PI * R[a] * R[a] * h[a];
      ck_assert_msg(fabs(vol - exact) <= bound * (1 + 1e-12),
                    "axis %d, n = %d: volume %g, pi R^2 L %g, bound %g", a, n, vol, exact,
                    bound);
      ck_assert(bound < prev_bound);
      prev_bound = bound;
      if (n == 16)
        ck_assert_msg(fabs(vol - exact) < 0.05 * exact, "axis %d: %g vs %g", a, vol, exact);
      mpm_points_free(pts);
    }
  }
}
END_TEST

/* A prism (a plane polygon extruded along z): a triangle in x-y over a z
 * range gets exactly the sub-cell centres inside it, counted directly with
 * the test's own barycentric test (no centre lies on a side here), all with
 * m = rho V; mpm_scenario_count3 agrees. */
START_TEST(prism_appends_the_centres_inside)
{
  mpm_mesh3 m;
  mesh_of(&m);                          /* [1, 3] x [-2, -1.25] x [0.5, 2.5] */
  mpm_fill_config poly;
  memset(&poly, 0, sizeof poly);
  poly.shape = MPM_FILL_POLYGON;
  poly.nvert = 3;
  const double vx[3] = {1.1, 2.93, 1.37}, vy[3] = {-1.97, -1.81, -1.3};
  memcpy(poly.px, vx, sizeof vx);
  memcpy(poly.py, vy, sizeof vy);
  poly.zmin = 0.71;
  poly.zmax = 2.03;
  poly.ppu = 3;
  poly.density = 1800.0;
  mpm_fill3_region f;
  mpm_scenario_region3(&poly, &f);
  ck_assert_int_eq(f.shape, MPM_FILL3_PRISM);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_msg(mpm_scenario_fill3(pts, &m, &f, &err) == MPM_OK, "%s", err.msg);
  const int n = 3;
  size_t want = 0;
  for (long k = 0; k < (long)m.nz * n; k++)
    for (long j = 0; j < (long)m.ny * n; j++)
      for (long i = 0; i < (long)m.nx * n; i++) {
        const double x = m.x0 + (i + 0.5) * (m.dx / n), y = m.y0 + (j + 0.5) * (m.dy / n);
        const double z = m.z0 + (k + 0.5) * (m.dz / n);
        const double det = (vy[1] - vy[2]) * (vx[0] - vx[2]) + (vx[2] - vx[1]) * (vy[0] - vy[2]);
        const double l0 = ((vy[1] - vy[2]) * (x - vx[2]) + (vx[2] - vx[1]) * (y - vy[2])) / det;
        const double l1 = ((vy[2] - vy[0]) * (x - vx[2]) + (vx[0] - vx[2]) * (y - vy[2])) / det;
        want += l0 > 0 && l1 > 0 && 1 - l0 - l1 > 0 && z >= 0.71 && z <= 2.03;
      }
  ck_assert_uint_gt(want, 100);
  ck_assert_uint_eq(pts->n, want);
  ck_assert_uint_eq(mpm_scenario_count3(&f, &m), want);
  for (size_t p = 0; p < pts->n; p++) {
    const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
    ck_assert(mpm_scenario_inside3(&f, x));
    ck_assert(near(pts->mass[p], 1800.0 * pts->vol[p], REL));
  }
  mpm_points_free(pts);
}
END_TEST

START_TEST(refused)
{
  mpm_mesh3 m;
  mesh_of(&m);
  const int u0[3] = {0, 0, 0}, u1[3] = {2, 2, 2};
  mpm_fill3_region f = box_of(&m, u0, u1, 2);
  mpm_err err = {0};

  mpm_points *p2 = mpm_points_alloc(0);          /* a 2D store */
  ck_assert_int_eq(mpm_scenario_fill3(p2, &m, &f, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "dimension 3") != NULL, "%s", err.msg);
  ck_assert_uint_eq(p2->n, 0);
  mpm_points_free(p2);

  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  f.hi[2] = m.z0 + m.lz + 0.01;                  /* past the top of the mesh */
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "z range") && strstr(err.msg, "leaves the mesh"), "%s",
                err.msg);
  ck_assert_uint_eq(mpm_scenario_count3(&f, &m), 0);

  mpm_fill3_region cyl;
  memset(&cyl, 0, sizeof cyl);
  cyl.shape = MPM_FILL3_CYLINDER;
  cyl.axis = 1;
  cyl.centre[0] = m.x0 + 0.2;                    /* radius 0.3 reaches x < x0 */
  cyl.centre[1] = m.y0 + 0.3;
  cyl.centre[2] = m.z0 + 1.0;
  cyl.radius = 0.3;
  cyl.length = 0.2;
  cyl.ppu = 2;
  cyl.density = 1000.0;
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &cyl, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "x range") && strstr(err.msg, "leaves the mesh"), "%s",
                err.msg);
  ck_assert_uint_eq(pts->n, 0);

  f = box_of(&m, u0, u1, 0);
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 2);
  f.density = 0.0;
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 1);
  f.lo[0] = f.hi[0] = m.x0 + 0.1;                /* empty */
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 1);
  f.hi[0] = m.x0 + 0.1;                          /* no unit centre in x <= x0 + 0.1 */
  ck_assert_int_eq(mpm_scenario_fill3(pts, &m, &f, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "no point centre"), "%s", err.msg);
  ck_assert_uint_eq(pts->n, 0);
  mpm_points_free(pts);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("fill3");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, box_of_whole_units);
  tcase_add_test(tc, box_appends);
  tcase_add_test(tc, cylinder_converges);
  tcase_add_test(tc, prism_appends_the_centres_inside);
  tcase_add_test(tc, refused);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
