/* test_scenario.c: the point count of a fill without filling
 * (mpm_scenario_count) is exactly the number of points the fill makes, for
 * rectangles, discs and polygons (convex or not, either orientation), with
 * edges that pass exactly through sub-cell centres (where the inside test
 * decides point by point), on meshes with an offset origin; and it counts
 * row by row: a mesh near the largest the code allows, filled with 8 x 8
 * points per unit (1.0e11 points), is counted exactly. The lithostatic pre-stress of a fill: sigma_yy from the
 * weight above, sigma_xx = sigma_zz = K0 sigma_yy with the default K0 =
 * nu/(1 - nu) or a given one, and each point's mass times exp(p/K). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "material/material.h"
#include "mesh/mesh.h"
#include "scenario/scenario.h"

static void mesh_of(mpm_mesh *m, int nx, int ny, double x0, double y0, double dx, double dy)
{
  memset(m, 0, sizeof *m);
  m->nx = nx;
  m->ny = ny;
  m->x0 = x0;
  m->y0 = y0;
  m->dx = dx;
  m->dy = dy;
  m->topology = MPM_TOPO_Q4;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(m, &err) == MPM_OK, "%s", err.msg);
}

static size_t filled(const mpm_fill_config *f, const mpm_mesh *m)
{
  mpm_material_params par;
  memset(&par, 0, sizeof par);
  par.nu = 0.3;
  mpm_points *pts = mpm_points_alloc(0);
  mpm_err err = {0};
  int rc = mpm_scenario_fill(pts, m, f, &par, -9.8, &err);
  size_t n = rc == MPM_OK ? pts->n : 0;
  ck_assert_msg(rc == MPM_OK || rc == MPM_EINPUT, "%s", err.msg);
  mpm_points_free(pts);
  return n;
}

static void same(const mpm_fill_config *f, const mpm_mesh *m, const char *what)
{
  size_t want = filled(f, m), got = mpm_scenario_count(f, m);
  ck_assert_msg(got == want, "%s: count %zu, fill %zu", what, got, want);
}

static double uniform(double lo, double hi)
{
  return lo + (hi - lo) * ((double)rand() / RAND_MAX);
}

/* A point on the sub-cell centre grid of m with ppu n, or near it. */
static double on_grid(double x0, double d, int n, int cells)
{
  int i = rand() % cells;
  double x = x0 + (i + 0.5) * (d / n);
  return rand() % 2 ? x : x + uniform(-0.3, 0.3) * d / n;
}

START_TEST(t_rectangles)
{
  srand(1);
  for (int k = 0; k < 300; k++) {
    mpm_mesh m;
    int n = 1 + rand() % 4;
    mesh_of(&m, 4 + rand() % 20, 4 + rand() % 20, uniform(-1, 1), uniform(-1, 1),
            uniform(0.01, 0.2), uniform(0.01, 0.2));
    mpm_fill_config f = {.shape = MPM_FILL_RECTANGLE, .ppu = n, .density = 1500};
    double a = on_grid(m.x0, m.dx, n, m.nx * n), b = on_grid(m.x0, m.dx, n, m.nx * n);
    double c = on_grid(m.y0, m.dy, n, m.ny * n), d = on_grid(m.y0, m.dy, n, m.ny * n);
    f.xmin = fmin(a, b);
    f.xmax = fmax(a, b);
    f.ymin = fmin(c, d);
    f.ymax = fmax(c, d);
    same(&f, &m, "rectangle");
  }
}
END_TEST

START_TEST(t_discs)
{
  srand(2);
  for (int k = 0; k < 300; k++) {
    mpm_mesh m;
    int n = 1 + rand() % 4;
    mesh_of(&m, 4 + rand() % 20, 4 + rand() % 20, uniform(-1, 1), uniform(-1, 1),
            uniform(0.01, 0.2), uniform(0.01, 0.2));
    mpm_fill_config f = {.shape = MPM_FILL_DISC, .ppu = n, .density = 1500};
    f.cx = on_grid(m.x0, m.dx, n, m.nx * n);
    f.cy = on_grid(m.y0, m.dy, n, m.ny * n);
    /* radii that reach sub-cell centres exactly along an axis, and others */
    f.radius = rand() % 2 ? (1 + rand() % 6) * m.dx / n : uniform(0.2, 4) * fmin(m.dx, m.dy);
    same(&f, &m, "disc");
  }
}
END_TEST

START_TEST(t_polygons)
{
  srand(3);
  for (int k = 0; k < 300; k++) {
    mpm_mesh m;
    int n = 1 + rand() % 4;
    mesh_of(&m, 4 + rand() % 20, 4 + rand() % 20, uniform(-1, 1), uniform(-1, 1),
            uniform(0.01, 0.2), uniform(0.01, 0.2));
    mpm_fill_config f = {.shape = MPM_FILL_POLYGON, .ppu = n, .density = 1500};
    f.nvert = 3 + rand() % 10;                /* random, often self-crossing: even-odd */
    for (int v = 0; v < f.nvert; v++) {
      f.px[v] = on_grid(m.x0, m.dx, n, m.nx * n);
      f.py[v] = on_grid(m.y0, m.dy, n, m.ny * n);
    }
    same(&f, &m, "polygon");
  }
}
END_TEST

/* 4e4 x 4e4 units (1.6e9 nodes, near the mesh's limit of 2^31), 8 x 8
 * points each: 1.024e11 points, counted row by row (3.2e5 rows). */
START_TEST(t_billions)
{
  mpm_mesh m;
  mesh_of(&m, 40000, 40000, 0, 0, 0.01, 0.01);
  mpm_fill_config f = {.shape = MPM_FILL_RECTANGLE, .ppu = 8, .density = 1500,
                       .xmin = 0, .xmax = 400, .ymin = 0, .ymax = 400};
  ck_assert_uint_eq(mpm_scenario_count(&f, &m), (size_t)40000 * 40000 * 64);
}
END_TEST

/* A lithostatic fill 0.4 m deep, 2 x 2 points per 0.1 m unit, rho 1500
 * kg/m^3, g_y = -9.8 m/s^2, nu = 0.3, K = 1e6 Pa: every point has
 * sigma_yy = rho g_y (0.4 - y) (the weight of the layer above it, to the
 * fill's top face), sigma_xx = sigma_zz = K0 sigma_yy with K0 = 3/7 by
 * default (fill.k0 = 0), 1 (isotropic) or 0.5, and the mass rho V exp(p/K),
 * p = -(1 + 2 K0) sigma_yy / 3. */
START_TEST(t_lithostatic)
{
  const double k0s[3] = {0.0, 1.0, 0.5}, want_k0[3] = {0.3 / 0.7, 1.0, 0.5};
  mpm_mesh m;
  mesh_of(&m, 10, 10, 0, 0, 0.1, 0.1);
  mpm_material_params par;
  memset(&par, 0, sizeof par);
  par.nu = 0.3;
  par.K = 1e6;
  mpm_fill_config f = {.shape = MPM_FILL_RECTANGLE, .ppu = 2, .density = 1500, .xmin = 0,
                       .xmax = 0.5, .ymin = 0, .ymax = 0.4, .lithostatic = 1};
  const double vol = 0.05 * 0.05, sig = 1e-12 * 1500 * 9.8 * 0.4;
  for (int i = 0; i < 3; i++) {
    f.k0 = k0s[i];
    mpm_points *pts = mpm_points_alloc(0);
    mpm_err err = {0};
    ck_assert_msg(mpm_scenario_fill(pts, &m, &f, &par, -9.8, &err) == MPM_OK, "%s", err.msg);
    ck_assert_uint_eq(pts->n, 5 * 2 * 4 * 2);
    for (size_t p = 0; p < pts->n; p++) {
      const double syy = 1500 * -9.8 * (0.4 - pts->y[p]);
      const double pr = -(1.0 + 2.0 * want_k0[i]) * syy / 3.0;
      ck_assert_double_eq_tol(pts->syy[p], syy, sig);
      ck_assert_double_eq_tol(pts->sxx[p], want_k0[i] * syy, sig);
      ck_assert_double_eq_tol(pts->szz[p], want_k0[i] * syy, sig);
      ck_assert(pts->sxy[p] == 0.0);
      ck_assert_double_eq_tol(pts->mass[p], 1500 * vol * exp(pr / 1e6), 1e-14 * 1500 * vol);
    }
    mpm_points_free(pts);
  }
}
END_TEST

int main(void)
{
  Suite *su = suite_create("scenario");
  TCase *tc = tcase_create("count");
  tcase_add_test(tc, t_rectangles);
  tcase_add_test(tc, t_discs);
  tcase_add_test(tc, t_polygons);
  tcase_add_test(tc, t_billions);
  suite_add_tcase(su, tc);
  TCase *tl = tcase_create("lithostatic");
  tcase_add_test(tl, t_lithostatic);
  suite_add_tcase(su, tl);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
