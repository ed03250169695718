/* test_scenario.c: the point count of a fill without filling
 * (mpm_scenario_count) is exactly the number of points the fill makes, for
 * rectangles, discs and polygons (convex or not, either orientation), with
 * edges that pass exactly through sub-cell centres (where the inside test
 * decides point by point), on meshes with an offset origin; and it counts
 * row by row: a mesh near the largest the code allows, filled with 8 x 8
 * points per unit (1.0e11 points), is counted exactly. The lithostatic pre-stress of a fill: sigma_yy from the
 * weight above, sigma_xx = sigma_zz = K0 sigma_yy with the default K0 =
 * nu/(1 - nu) or a given one, and each point's mass times exp(p/K).
 * Fills on boxes (mesh of dim = 3, a 3D store): a box of whole units gets
 * exactly n^3 points per unit, one at every sub-cell centre, with the
 * volume and mass of the box and the extents dx/2n, dy/2n, dz/2n; a
 * cylinder along each axis gets exactly the sub-cell centres inside it,
 * and its volume tends to pi R^2 L within a bound derived below; a prism
 * gets the centres inside its polygon and z range; regions that leave the
 * mesh and stores of the other dimension are refused. The state a fill
 * starts in (disconnected below rho_c) is the same on the plane and on
 * boxes. */
#define _DEFAULT_SOURCE /* M_PI */
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

/* ---- fills on boxes --------------------------------------------------------- */

#define REL 1e-12

/* Boxes of 0.5 x 0.25 x 0.4 m, 4 x 3 x 5 of them from (1, -2, 0.5). */
static void box_mesh_of(mpm_mesh *m)
{
  memset(m, 0, sizeof *m);
  m->dim = 3;
  m->nx = 4;
  m->ny = 3;
  m->nz = 5;
  m->x0 = 1.0;
  m->y0 = -2.0;
  m->z0 = 0.5;
  m->dx = 0.5;
  m->dy = 0.25;
  m->dz = 0.4;
  m->topology = MPM_TOPO_Q4;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(m, &err) == MPM_OK, "%s", err.msg);
}

/* A box fill (a rectangle over a z range) of the units u0 .. u1 - 1. */
static mpm_fill_config box_of(const mpm_mesh *m, const int u0[3], const int u1[3], int n)
{
  mpm_fill_config f;
  memset(&f, 0, sizeof f);
  f.shape = MPM_FILL_RECTANGLE;
  f.xmin = m->x0 + u0[0] * m->dx;
  f.xmax = m->x0 + u1[0] * m->dx;
  f.ymin = m->y0 + u0[1] * m->dy;
  f.ymax = m->y0 + u1[1] * m->dy;
  f.zmin = m->z0 + u0[2] * m->dz;
  f.zmax = m->z0 + u1[2] * m->dz;
  f.ppu = n;
  f.density = 1500.0;
  f.vx = 0.1;
  f.vy = -0.2;
  f.vz = 0.3;
  return f;
}

/* A fill on m without pre-stress (nu and rho_c as given). */
static int fill_on(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f, double rho_c,
                   mpm_err *err)
{
  mpm_material_params par;
  memset(&par, 0, sizeof par);
  par.nu = 0.3;
  par.rho_c = rho_c;
  return mpm_scenario_fill(pts, m, f, &par, -9.8, err);
}

static int near(double a, double b, double tol)
{
  return fabs(a - b) <= tol * fmax(fabs(a), fabs(b));
}

/* Units [1, 3) x [0, 2) x [1, 4), n = 3: 2 x 2 x 3 units of 27 points, one
 * at every sub-cell centre, with the volume and mass of the box, the
 * extents dx/2n, dy/2n, dz/2n, the fill's velocity and zero stress. */
START_TEST(t_box_of_whole_units)
{
  mpm_mesh m;
  box_mesh_of(&m);
  const int u0[3] = {1, 0, 1}, u1[3] = {3, 2, 4}, n = 3;
  mpm_fill_config f = box_of(&m, u0, u1, n);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_msg(fill_on(pts, &m, &f, 0.0, &err) == MPM_OK, "%s", err.msg);
  const int ns[3] = {(u1[0] - u0[0]) * n, (u1[1] - u0[1]) * n, (u1[2] - u0[2]) * n};
  const size_t want = (size_t)ns[0] * ns[1] * ns[2];
  ck_assert_uint_eq(pts->n, want);
  ck_assert_uint_eq(mpm_scenario_count(&f, &m), want);

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
          ck_assert_int_eq(mpm_mesh_locate(&m, x, u, l), 0);
          c += u[0] == i && u[1] == j && u[2] == k;
        }
        ck_assert_int_eq(c, n * n * n);
      }
  const double box = (f.xmax - f.xmin) * (f.ymax - f.ymin) * (f.zmax - f.zmin);
  ck_assert_msg(near(vol, box, REL), "volume %.17g, box %.17g", vol, box);
  ck_assert_msg(near(mass, f.density * box, REL), "mass %.17g", mass);
  mpm_points_free(pts);
}
END_TEST

/* A box that cuts units appends to a store that already has points. */
START_TEST(t_box_appends)
{
  mpm_mesh m;
  box_mesh_of(&m);
  const int u0[3] = {0, 0, 0}, u1[3] = {1, 1, 1};
  mpm_fill_config f = box_of(&m, u0, u1, 2);
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_OK);
  ck_assert_uint_eq(pts->n, 8);
  f.xmin = 1.3;                  /* sub-cells of 0.25: centres 1.375, 1.625, ... */
  f.xmax = 2.2;
  f.ppu = 2;
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_OK);
  ck_assert_uint_eq(pts->n, 8 + 4 * 2 * 2);   /* x: 1.375 1.625 1.875 2.125 */
  ck_assert(pts->x[8] == 1.375);
  mpm_points_free(pts);
}
END_TEST

/* A cylinder of radius R and length L about centre c along axis a: the
 * fill section of a 3D input (a disc with its axis: along z the circle
 * (cx, cy) over [zmin, zmax], along x (cy, cz) over [xmin, xmax], along y
 * (cx, cz) over [ymin, ymax]). */
static mpm_fill_config cylinder_of(int a, const double c[3], double R, double L, int n,
                                   double density)
{
  mpm_fill_config f;
  memset(&f, 0, sizeof f);
  f.shape = MPM_FILL_DISC;
  f.axis = a;
  f.cx = c[0];
  f.cy = c[1];
  f.cz = c[2];
  f.radius = R;
  double *lo[3] = {&f.xmin, &f.ymin, &f.zmin}, *hi[3] = {&f.xmax, &f.ymax, &f.zmax};
  *lo[a] = c[a] - 0.5 * L;
  *hi[a] = c[a] + 0.5 * L;
  f.ppu = n;
  f.density = density;
  return f;
}

/* The sub-cell centres inside a cylinder, counted directly over the whole
 * mesh with the test's own inside test: along its axis between the two
 * ends, across it within the radius of the axis. */
static size_t direct_count(const mpm_mesh *m, const mpm_fill_config *f)
{
  const int n = f->ppu, a = f->axis, b = (a + 1) % 3, cc = (a + 2) % 3;
  const double lo[3] = {f->xmin, f->ymin, f->zmin}, hi[3] = {f->xmax, f->ymax, f->zmax};
  const double centre[3] = {f->cx, f->cy, f->cz};
  size_t c = 0;
  for (long k = 0; k < (long)m->nz * n; k++)
    for (long j = 0; j < (long)m->ny * n; j++)
      for (long i = 0; i < (long)m->nx * n; i++) {
        const double x[3] = {m->x0 + (i + 0.5) * (m->dx / n), m->y0 + (j + 0.5) * (m->dy / n),
                             m->z0 + (k + 0.5) * (m->dz / n)};
        const double eb = x[b] - centre[b], ec = x[cc] - centre[cc];
        c += x[a] >= lo[a] && x[a] <= hi[a] && eb * eb + ec * ec <= f->radius * f->radius;
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
START_TEST(t_cylinder_converges)
{
  mpm_mesh m;
  box_mesh_of(&m);                      /* [1, 3] x [-2, -1.25] x [0.5, 2.5] */
  const double c[3] = {2.0, -1.6, 1.5};
  /* z in [0.55, 2.45] has sub-cell centres on both ends at n = 4: the
   * ends are part of the cylinder, and the fill takes them (a test of
   * |x - (lo + hi)/2| <= (hi - lo)/2 would round one end layer away) */
  const double R[3] = {0.3, 0.35, 0.3}, L[3] = {1.7, 0.7, 1.9};
  for (int a = 0; a < 3; a++) {
    double prev_bound = INFINITY;
    for (int n = 1; n <= 16; n *= 2) {
      const mpm_fill_config f = cylinder_of(a, c, R[a], L[a], n, 2000.0);
      mpm_points *pts = mpm_points_alloc_dim(0, 3);
      mpm_err err = {0};
      ck_assert_msg(fill_on(pts, &m, &f, 0.0, &err) == MPM_OK, "%s", err.msg);
      ck_assert_uint_eq(pts->n, direct_count(&m, &f));
      ck_assert_uint_eq(mpm_scenario_count(&f, &m), pts->n);
      double vol = 0.0, mass = 0.0;
      for (size_t p = 0; p < pts->n; p++) {
        const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
        ck_assert(mpm_scenario_inside(&f, 3, x));
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
 * m = rho V; mpm_scenario_count agrees. */
START_TEST(t_prism_appends_the_centres_inside)
{
  mpm_mesh m;
  box_mesh_of(&m);                      /* [1, 3] x [-2, -1.25] x [0.5, 2.5] */
  mpm_fill_config f;
  memset(&f, 0, sizeof f);
  f.shape = MPM_FILL_POLYGON;
  f.nvert = 3;
  const double vx[3] = {1.1, 2.93, 1.37}, vy[3] = {-1.97, -1.81, -1.3};
  memcpy(f.px, vx, sizeof vx);
  memcpy(f.py, vy, sizeof vy);
  f.zmin = 0.71;
  f.zmax = 2.03;
  f.ppu = 3;
  f.density = 1800.0;
  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  mpm_err err = {0};
  ck_assert_msg(fill_on(pts, &m, &f, 0.0, &err) == MPM_OK, "%s", err.msg);
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
  ck_assert_uint_eq(mpm_scenario_count(&f, &m), want);
  for (size_t p = 0; p < pts->n; p++) {
    const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
    ck_assert(mpm_scenario_inside(&f, 3, x));
    ck_assert(near(pts->mass[p], 1800.0 * pts->vol[p], REL));
  }
  mpm_points_free(pts);
}
END_TEST

/* Refused, with nothing appended and a count of 0: a store of the other
 * dimension, a region leaving the mesh along z or (a cylinder along y)
 * along x, no points per unit, no density, an empty range, a region with
 * no sub-cell centre. */
START_TEST(t_box_refused)
{
  mpm_mesh m;
  box_mesh_of(&m);
  const int u0[3] = {0, 0, 0}, u1[3] = {2, 2, 2};
  mpm_fill_config f = box_of(&m, u0, u1, 2);
  mpm_err err = {0};

  mpm_points *p2 = mpm_points_alloc(0);          /* a 2D store */
  ck_assert_int_eq(fill_on(p2, &m, &f, 0.0, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "dimension 2, the mesh 3") != NULL, "%s", err.msg);
  ck_assert_uint_eq(p2->n, 0);
  mpm_points_free(p2);

  mpm_points *pts = mpm_points_alloc_dim(0, 3);
  f.zmax = m.z0 + m.lz + 0.01;                   /* past the top of the mesh */
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "z range") && strstr(err.msg, "leaves the mesh"), "%s",
                err.msg);
  ck_assert_uint_eq(mpm_scenario_count(&f, &m), 0);

  /* radius 0.3 reaches x < x0 */
  const double c[3] = {m.x0 + 0.2, m.y0 + 0.3, m.z0 + 1.0};
  const mpm_fill_config cyl = cylinder_of(1, c, 0.3, 0.2, 2, 1000.0);
  ck_assert_int_eq(fill_on(pts, &m, &cyl, 0.0, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "x range") && strstr(err.msg, "leaves the mesh"), "%s",
                err.msg);
  ck_assert_uint_eq(pts->n, 0);

  f = box_of(&m, u0, u1, 0);
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 2);
  f.density = 0.0;
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 1);
  f.xmin = f.xmax = m.x0 + 0.1;                  /* empty */
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_EINPUT);
  f = box_of(&m, u0, u1, 1);
  f.xmax = m.x0 + 0.1;                           /* no unit centre in x <= x0 + 0.1 */
  ck_assert_int_eq(fill_on(pts, &m, &f, 0.0, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "no point centre"), "%s", err.msg);
  ck_assert_uint_eq(pts->n, 0);
  mpm_points_free(pts);
}
END_TEST

/* The state a fill starts in: below the critical density rho_c a fill is
 * disconnected (stress-free, [DK-silo] section 3), at or above it dense.
 * The same fills (a loose layer of 1400 kg/m^3 under rho_c = 1500 over a
 * layer at exactly rho_c and one at 1600) on the plane and on boxes with
 * the same x-y layout, 2 x 2 (x 2) points a unit: every point of a box
 * takes the state of the plane point at its (x, y), and the loose layer's
 * points, and only they, are disconnected in both; with rho_c = 0 (a model
 * without one) every point is dense. */
START_TEST(t_state_below_rho_c)
{
  mpm_mesh m2, m3;
  box_mesh_of(&m3);
  memset(&m2, 0, sizeof m2);
  m2.nx = m3.nx;
  m2.ny = m3.ny;
  m2.x0 = m3.x0;
  m2.y0 = m3.y0;
  m2.dx = m3.dx;
  m2.dy = m3.dy;
  m2.topology = MPM_TOPO_Q4;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m2, &err), MPM_OK);
  const double rho[3] = {1600.0, 1500.0, 1400.0};
  for (int crit = 0; crit < 2; crit++) {
    mpm_points *p2 = mpm_points_alloc(0), *p3 = mpm_points_alloc_dim(0, 3);
    for (int layer = 0; layer < 3; layer++) {
      const int u0[3] = {0, layer, 1}, u1[3] = {4, layer + 1, 3};
      mpm_fill_config f = box_of(&m3, u0, u1, 2);
      f.density = rho[layer];
      ck_assert_msg(fill_on(p2, &m2, &f, crit ? 1500.0 : 0.0, &err) == MPM_OK, "%s", err.msg);
      ck_assert_msg(fill_on(p3, &m3, &f, crit ? 1500.0 : 0.0, &err) == MPM_OK, "%s", err.msg);
    }
    ck_assert_uint_eq(p2->n, 3 * 4 * 4);
    ck_assert_uint_eq(p3->n, 2 * 2 * p2->n);     /* 2 units along z, 2 points a unit */
    size_t loose2 = 0, loose3 = 0;
    for (size_t p = 0; p < p2->n; p++) {
      const int want = crit && p2->y[p] > m2.y0 + 2 * m2.dy ? MPM_STATE_DISCONNECTED
                                                            : MPM_STATE_DENSE;
      ck_assert_int_eq(p2->state[p], want);
      loose2 += p2->state[p] == MPM_STATE_DISCONNECTED;
    }
    for (size_t q = 0; q < p3->n; q++) {
      size_t match = p2->n;
      for (size_t p = 0; p < p2->n; p++)
        if (p2->x[p] == p3->x[q] && p2->y[p] == p3->y[q])
          match = p;
      ck_assert_uint_lt(match, p2->n);
      ck_assert_int_eq(p3->state[q], p2->state[match]);
      loose3 += p3->state[q] == MPM_STATE_DISCONNECTED;
    }
    ck_assert_uint_eq(loose2, crit ? 16 : 0);   /* the loose layer: 4 units x 4 points */
    ck_assert_uint_eq(loose3, crit ? 64 : 0);   /* ... x 2 units x 2 points along z */
    mpm_points_free(p2);
    mpm_points_free(p3);
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
  TCase *tb = tcase_create("box");
  tcase_set_timeout(tb, 60);
  tcase_add_test(tb, t_box_of_whole_units);
  tcase_add_test(tb, t_box_appends);
  tcase_add_test(tb, t_cylinder_converges);
  tcase_add_test(tb, t_prism_appends_the_centres_inside);
  tcase_add_test(tb, t_box_refused);
  tcase_add_test(tb, t_state_below_rho_c);
  suite_add_tcase(su, tb);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
