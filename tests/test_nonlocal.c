/* test_nonlocal.c: element fluidity and its Laplacian (MODEL.md section 5
 * steps 1-2), tested from the equations: mass-weighted averages of the dense
 * points only; the 5-point Laplacian of g = a + b x + c y + e x^2 + f y^2 is
 * 2e + 2f in the interior; each ghost rule on each edge reproduces the field
 * it stands for (even about a Neumann face, odd about a Dirichlet face,
 * periodic); empty neighbours act as Neumann faces; the explicit diffusion
 * limit (dt/n_sub) A^2 d^2/t0 (2/dx^2 + 2/dy^2) <= 1 is sharp. The unit mean
 * of p^-1/2 (material.p_sample = "unit") is the mean of q^-1/2 of a linear q:
 * in 1D 2 / (sqrt(q_lo) + sqrt(q_hi)), in 2D a quadrature of it; a linear
 * pressure field is reconstructed exactly, up to a free surface where it
 * falls to 0. The extent rule (material.g_average = "extent") from its
 * definition: a point whose extent lies in one unit counts exactly as under
 * the centre rule; otherwise each unit gets the fraction of the extent's
 * area inside it (1/4 each about a corner, 0.3 / 0.7 across a face), parts
 * beyond a non-periodic edge dropped and the rest renormalised, periodic
 * edges wrapped; a point reads the weighted mean of lap_e over the filled
 * units it overlaps. */
#define _DEFAULT_SOURCE /* M_PI */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/nonlocal.h"

/* Locate n points at (x, y) in ws, with the extents r = {r1x, r1y, r2x, r2y}
 * (arrays of n) when r is not NULL: the points as a store. */
static int locate_xy(mpm_nonlocal *ws, const mpm_mesh *m, size_t n, const double *x,
                     const double *y, const double *const r[4], mpm_err *err)
{
  mpm_points *P = mpm_points_alloc(n);
  ck_assert_ptr_nonnull(P);
  for (size_t p = 0; p < n; p++) {
    size_t q;
    ck_assert_int_eq(mpm_points_push(P, &q), MPM_OK);
    P->x[q] = x[p];
    P->y[q] = y[p];
    if (r) {
      P->r1x[q] = r[0][p];
      P->r1y[q] = r[1][p];
      P->r2x[q] = r[2][p];
      P->r2y[q] = r[3][p];
    }
  }
  const int rc = mpm_nonlocal_locate(ws, m, P, err);
  mpm_points_free(P);
  return rc;
}

/* 1 if unit (i, j) holds dense mass. */
static int filled(const mpm_nonlocal *ws, int i, int j)
{
  return ws->sm[i + ws->grid.n[0] * j] > 0.0;
}

enum { LEFT = 0, RIGHT, BOTTOM, TOP };

static mpm_mesh make_mesh(int nx, int ny, double dx, double dy, int px, int py)
{
  mpm_mesh m = {.nx = nx, .ny = ny, .x0 = -0.37, .y0 = 1.25, .dx = dx, .dy = dy,
                .topology = MPM_TOPO_Q4, .periodic_x = px, .periodic_y = py};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

typedef double (*field_fn)(const double *c, double x, double y);

/* Point cloud: ppu x ppu points per unit at random positions inside it, each
 * carrying the field value at its unit centre (so g_e is that value to round-off),
 * random masses; units with fill(i, j) == 0 get no dense points. */
typedef struct cloud {
  size_t n;
  double *x, *y, *m, *g;
  unsigned char *dense;
} cloud;

static void cloud_free(cloud *c)
{
  free(c->x);
  free(c->y);
  free(c->m);
  free(c->g);
  free(c->dense);
}

static cloud make_cloud(const mpm_mesh *m, int ppu, field_fn f, const double *coef,
                        int (*fill)(int i, int j), unsigned long seed)
{
  size_t cap = (size_t)m->nx * m->ny * ppu * ppu;
  cloud c = {0, malloc(cap * sizeof(double)), malloc(cap * sizeof(double)),
             malloc(cap * sizeof(double)), malloc(cap * sizeof(double)), malloc(cap)};
  for (int j = 0; j < m->ny; j++)
    for (int i = 0; i < m->nx; i++) {
      if (fill && !fill(i, j))
        continue;
      double xc = m->x0 + (i + 0.5) * m->dx, yc = m->y0 + (j + 0.5) * m->dy;
      for (int k = 0; k < ppu * ppu; k++) {
        c.x[c.n] = m->x0 + (i + 0.05 + 0.9 * lcg(&seed)) * m->dx;
        c.y[c.n] = m->y0 + (j + 0.05 + 0.9 * lcg(&seed)) * m->dy;
        c.m[c.n] = 0.5 + lcg(&seed);
        c.g[c.n] = f(coef, xc, yc);
        c.dense[c.n] = 1;
        c.n++;
      }
    }
  return c;
}

/* Workspace, located and averaged, Laplacian computed. */
static mpm_nonlocal *run(const mpm_mesh *m, const int edge[4], const cloud *c)
{
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, m, edge, MPM_NONLOCAL_CENTRE, 4, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(ws, m, c->n, c->x, c->y, NULL, &err), MPM_OK);
  mpm_nonlocal_average(ws, c->n, c->m, c->g, c->dense);
  mpm_nonlocal_laplacian(ws);
  return ws;
}

static double quad_field(const double *c, double x, double y)
{
  return c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * y * y;
}

/* Round-off bound of a 5-point Laplacian of values up to gmax: each second
 * difference cancels terms of size 4 gmax; 16 eps of that covers it. */
static double lap_tol(double gmax, double dx, double dy)
{
  return 16.0 * DBL_EPSILON * 4.0 * gmax * (1.0 / (dx * dx) + 1.0 / (dy * dy));
}

/* ------------------------------------------------------------------ */

/* g_e = sum m g / sum m over the dense points of the unit; others ignored. */
START_TEST(t_average_mass_weighted)
{
  mpm_mesh m = make_mesh(5, 4, 0.1, 0.07, 0, 0);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  enum { N = 400 };
  double x[N], y[N], ms[N], g[N], sm[20] = {0}, smg[20] = {0};
  unsigned char dense[N];
  unsigned long s = 5u;
  for (int p = 0; p < N; p++) {
    x[p] = m.x0 + m.lx * lcg(&s);
    y[p] = m.y0 + 0.75 * m.ly * lcg(&s);      /* the top row stays empty */
    ms[p] = 0.1 + lcg(&s);
    g[p] = 10.0 * lcg(&s);
    dense[p] = lcg(&s) < 0.7;
    int i = (int)((x[p] - m.x0) / m.dx), j = (int)((y[p] - m.y0) / m.dy);
    if (dense[p]) {
      sm[i + 5 * j] += ms[p];
      smg[i + 5 * j] += ms[p] * g[p];
    }
  }
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_CENTRE, 1, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(ws, &m, N, x, y, NULL, &err), MPM_OK);  /* grows */
  mpm_nonlocal_average(ws, N, ms, g, dense);
  mpm_nonlocal_laplacian(ws);
  for (int j = 0; j < 4; j++)
    for (int i = 0; i < 5; i++) {
      int e = i + 5 * j;
      ck_assert_int_eq(filled(ws, i, j), sm[e] > 0.0);
      if (sm[e] > 0.0)
        ck_assert_double_eq_tol(ws->ge[e], smg[e] / sm[e], 1e-14 * 10.0);
      else {
        ck_assert_double_eq(ws->ge[e], 0.0);
        ck_assert_double_eq(ws->lap[e], 0.0);
      }
    }
  for (int j = 3, i = 0; i < 5; i++)
    ck_assert(!filled(ws, i, j));
  /* a point reads its own unit's Laplacian */
  for (int p = 0; p < N; p++) {
    int i = (int)((x[p] - m.x0) / m.dx), j = (int)((y[p] - m.y0) / m.dy);
    ck_assert_double_eq(mpm_nonlocal_point_lap(ws, (size_t)p), ws->lap[i + 5 * j]);
  }
  mpm_nonlocal_free(ws);
}
END_TEST

/* Interior units: the 5-point Laplacian of a quadratic is exactly 2e + 2f. */
START_TEST(t_quadratic_interior_exact)
{
  mpm_mesh m = make_mesh(9, 7, 0.013, 0.021, 0, 0);
  int edge[4] = {MPM_BC_NOSLIP, MPM_BC_FREE, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY};
  const double coef[5] = {2.0, -3.0, 1.5, 40.0, -25.0};
  cloud c = make_cloud(&m, 3, quad_field, coef, NULL, 11u);
  mpm_nonlocal *ws = run(&m, edge, &c);
  double gmax = 0.0;
  for (size_t p = 0; p < c.n; p++)
    gmax = fmax(gmax, fabs(c.g[p]));
  int checked = 0;
  for (int j = 1; j < m.ny - 1; j++)
    for (int i = 1; i < m.nx - 1; i++) {
      ck_assert_double_eq_tol(ws->lap[i + m.nx * j], 2.0 * coef[3] + 2.0 * coef[4],
                              lap_tol(gmax, m.dx, m.dy));
      checked++;
    }
  ck_assert_int_eq(checked, 7 * 5);
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}
END_TEST

/* Fields for the ghost rules about the face at coordinate a along axis ax
 * (0: x, 1: y): even e (s)^2 + 1 about a Neumann face (the ghost g_e equals the
 * field at the mirrored centre), odd s + k s^3 about a Dirichlet face (the ghost
 * -g_e equals it). Their 5-point Laplacians are exact: 2e and 6 k s. */
static double even_field(const double *c, double x, double y)
{
  double s = (c[0] == 0.0 ? x : y) - c[1];
  return 1.0 + c[2] * s * s;
}

static double odd_field(const double *c, double x, double y)
{
  double s = (c[0] == 0.0 ? x : y) - c[1];
  return s + c[2] * s * s * s;
}

/* For edge k: the axis, the face coordinate, the boundary layer index. */
static void edge_geometry(const mpm_mesh *m, int k, int *axis, double *face)
{
  *axis = k < 2 ? 0 : 1;
  if (k == LEFT)
    *face = m->x0;
  else if (k == RIGHT)
    *face = m->x0 + m->lx;
  else if (k == BOTTOM)
    *face = m->y0;
  else
    *face = m->y0 + m->ly;
}

/* Every unit's Laplacian for one edge under test; the direction along the edge
 * is periodic so the field is one-dimensional and the other ghosts play no part. */
static void check_edge_rule(int k, int kind)
{
  int axis;
  double face;
  mpm_mesh m = k < 2 ? make_mesh(6, 3, 0.02, 0.05, 0, 1) : make_mesh(3, 6, 0.05, 0.02, 1, 0);
  edge_geometry(&m, k, &axis, &face);
  int edge[4];
  for (int q = 0; q < 4; q++)
    edge[q] = (q < 2) == (k < 2) ? MPM_BC_FREE : MPM_BC_PERIODIC;
  edge[k] = kind;
  int dirichlet = kind == MPM_BC_NOSLIP;
  const double coef[3] = {axis, face, dirichlet ? 300.0 : 250.0};
  cloud c = make_cloud(&m, 2, dirichlet ? odd_field : even_field, coef, NULL, 3u + (unsigned)k);
  mpm_nonlocal *ws = run(&m, edge, &c);
  double h = axis == 0 ? m.dx : m.dy;
  int n = axis == 0 ? m.nx : m.ny;
  int bl = (k == LEFT || k == BOTTOM) ? 0 : n - 1;    /* boundary layer next to the face */
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++) {
      int l = axis == 0 ? i : j;
      double xc = m.x0 + (i + 0.5) * m.dx, yc = m.y0 + (j + 0.5) * m.dy;
      double s = (axis == 0 ? xc : yc) - face, lap = ws->lap[i + m.nx * j];
      double gmax = 1.0 + 300.0 * 0.3 * 0.3 * 0.3 + 0.3;
      if (l == bl) {
        double want = dirichlet ? 6.0 * coef[2] * s : 2.0 * coef[2];
        ck_assert_msg(fabs(lap - want) <= lap_tol(gmax, h, h),
                      "edge %d kind %d unit (%d,%d): lap %.17g want %.17g", k, kind, i, j, lap, want);
      } else if (l != n - 1 - bl) {
        double want = dirichlet ? 6.0 * coef[2] * s : 2.0 * coef[2];   /* interior, exact */
        ck_assert_double_eq_tol(lap, want, lap_tol(gmax, h, h));
      } else {
        /* the opposite edge is free (Neumann): one-sided formula */
        double g0 = ws->ge[i + m.nx * j];
        int di = axis == 0 ? (l == 0 ? 1 : -1) : 0, dj = axis == 1 ? (l == 0 ? 1 : -1) : 0;
        double g1 = ws->ge[(i + di) + m.nx * (j + dj)];
        ck_assert_double_eq_tol(lap, (g1 - g0) / (h * h), lap_tol(gmax, h, h));
      }
    }
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}

START_TEST(t_ghost_rules_each_edge)
{
  const int kinds[] = {MPM_BC_FREE, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY, MPM_BC_NOSLIP};
  for (int k = 0; k < 4; k++)
    for (int q = 0; q < 4; q++)
      check_edge_rule(k, kinds[q]);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(MPM_BC_NOSLIP), MPM_GHOST_DIRICHLET);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(MPM_BC_FREE), MPM_GHOST_NEUMANN);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(MPM_BC_FRICTIONLESS), MPM_GHOST_NEUMANN);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(MPM_BC_SYMMETRY), MPM_GHOST_NEUMANN);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(MPM_BC_PERIODIC), MPM_GHOST_PERIODIC);
  ck_assert_int_eq(mpm_nonlocal_ghost_of_bc(99), -1);
}
END_TEST

/* One unit between four walls: every neighbour is a ghost. */
START_TEST(t_single_unit_corners)
{
  mpm_mesh m = make_mesh(1, 1, 0.5, 0.25, 0, 0);
  const double coef[5] = {3.0, 0, 0, 0, 0};
  cloud c = make_cloud(&m, 1, quad_field, coef, NULL, 1u);
  int all_d[4] = {MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP};
  mpm_nonlocal *ws = run(&m, all_d, &c);
  ck_assert_double_eq_tol(ws->lap[0], -4.0 * 3.0 / 0.25 - 4.0 * 3.0 / 0.0625, 1e-12);
  mpm_nonlocal_free(ws);
  int mixed[4] = {MPM_BC_NOSLIP, MPM_BC_FREE, MPM_BC_SYMMETRY, MPM_BC_NOSLIP};
  ws = run(&m, mixed, &c);
  ck_assert_double_eq_tol(ws->lap[0], -2.0 * 3.0 / 0.25 - 2.0 * 3.0 / 0.0625, 1e-12);
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}
END_TEST

/* An empty neighbour acts as a Neumann face: a field even about the interface
 * between filled and empty units has the exact Laplacian 2e next to it. */
static int fill_left_three(int i, int j)
{
  (void)j;
  return i < 3 || i == 5;   /* unit 5 filled but isolated: all-Neumann, lap 0 in x */
}

START_TEST(t_empty_neighbour_neumann)
{
  mpm_mesh m = make_mesh(7, 3, 0.03, 0.04, 0, 1);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  const double coef[3] = {0.0, m.x0 + 3.0 * m.dx, 500.0};
  cloud c = make_cloud(&m, 2, even_field, coef, fill_left_three, 17u);
  mpm_nonlocal *ws = run(&m, edge, &c);
  for (int j = 0; j < m.ny; j++) {
    ck_assert_double_eq_tol(ws->lap[2 + m.nx * j], 2.0 * coef[2], lap_tol(6.0, m.dx, m.dy));
    ck_assert_double_eq_tol(ws->lap[1 + m.nx * j], 2.0 * coef[2], lap_tol(6.0, m.dx, m.dy));
    ck_assert_double_eq(ws->lap[3 + m.nx * j], 0.0);     /* empty */
    ck_assert_double_eq(ws->lap[4 + m.nx * j], 0.0);
    ck_assert_double_eq_tol(ws->lap[5 + m.nx * j], 0.0,  /* isolated: both ghosts = g_e */
                            lap_tol(6.0, m.dx, m.dy));
    ck_assert_double_eq(ws->ge[3 + m.nx * j], 0.0);
  }
  /* points that are not dense do not count: mark unit 2 not dense */
  for (size_t p = 0; p < c.n; p++)
    if (c.x[p] > m.x0 + 2.0 * m.dx && c.x[p] < m.x0 + 3.0 * m.dx)
      c.dense[p] = 0;
  mpm_nonlocal_average(ws, c.n, c.m, c.g, c.dense);
  mpm_nonlocal_laplacian(ws);
  for (int j = 0; j < m.ny; j++) {
    ck_assert(!filled(ws, 2, j));
    double g0 = ws->ge[1 + m.nx * j], g1 = ws->ge[m.nx * j];
    ck_assert_double_eq_tol(ws->lap[1 + m.nx * j], (g1 - g0) / (m.dx * m.dx),
                            lap_tol(6.0, m.dx, m.dy));
  }
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}
END_TEST

/* Periodic wrap: g = 2 + cos(2 pi x/Lx) + sin(2 pi y/Ly) on a doubly periodic
 * mesh has the discrete Laplacian -(2 - 2cos(2 pi dx/Lx))/dx^2 (cos part)
 * -(2 - 2cos(2 pi dy/Ly))/dy^2 (sin part) at every unit, edges included. */
static double wave_field(const double *c, double x, double y)
{
  return 2.0 + cos(2.0 * M_PI * (x - c[0]) / c[1]) + sin(2.0 * M_PI * (y - c[2]) / c[3]);
}

START_TEST(t_periodic_wrap)
{
  mpm_mesh m = make_mesh(8, 5, 0.1, 0.3, 1, 1);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  const double coef[4] = {m.x0, m.lx, m.y0, m.ly};
  cloud c = make_cloud(&m, 2, wave_field, coef, NULL, 23u);
  mpm_nonlocal *ws = run(&m, edge, &c);
  double lx = -(2.0 - 2.0 * cos(2.0 * M_PI * m.dx / m.lx)) / (m.dx * m.dx);
  double ly = -(2.0 - 2.0 * cos(2.0 * M_PI * m.dy / m.ly)) / (m.dy * m.dy);
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++) {
      double xc = m.x0 + (i + 0.5) * m.dx, yc = m.y0 + (j + 0.5) * m.dy;
      double want = lx * cos(2.0 * M_PI * (xc - m.x0) / m.lx)
                  + ly * sin(2.0 * M_PI * (yc - m.y0) / m.ly);
      ck_assert_double_eq_tol(ws->lap[i + m.nx * j], want, lap_tol(4.0, m.dx, m.dy));
    }
  mpm_nonlocal_free(ws);
  cloud_free(&c);
  /* two units: each is the other's neighbour on both sides */
  mpm_mesh m2 = make_mesh(2, 1, 0.1, 0.1, 1, 0);
  int e2[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_FREE, MPM_BC_FREE};
  double x[2] = {m2.x0 + 0.05, m2.x0 + 0.15}, y[2] = {m2.y0 + 0.05, m2.y0 + 0.05};
  double ms[2] = {1.0, 1.0}, g[2] = {1.0, 3.0};
  unsigned char d[2] = {1, 1};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m2, e2, MPM_NONLOCAL_CENTRE, 2, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(ws, &m2, 2, x, y, NULL, &err), MPM_OK);
  mpm_nonlocal_average(ws, 2, ms, g, d);
  mpm_nonlocal_laplacian(ws);
  ck_assert_double_eq_tol(ws->lap[0], (3.0 - 2.0 + 3.0) / 0.01, 1e-10);
  ck_assert_double_eq_tol(ws->lap[1], (1.0 - 6.0 + 1.0) / 0.01, 1e-10);
  mpm_nonlocal_free(ws);
}
END_TEST

/* Explicit diffusion through the real pipeline (points -> g_e -> lap_e ->
 * g* = g + (dt/t0) A^2 d^2 lap): the checkerboard mode of a doubly periodic
 * grid is multiplied by 1 - 2r per step, r the diffusion number, so r = 1 is
 * neutral and r = 1.05 grows by 1.1 per step: the limit r <= 1 is sharp. */
static double checker_amplitude(double r_target, int steps)
{
  mpm_material_params par = {.A = 0.5, .d = 0.005, .t0 = 1e-3};
  mpm_mesh m = make_mesh(6, 4, 0.002, 0.003, 1, 1);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  double r1 = mpm_material_ngf_diffusion_number(&par, 1.0, 1, m.dx, m.dy, 0.0);
  double dt = r_target / r1, k = dt / par.t0 * par.A * par.A * par.d * par.d;
  ck_assert_double_eq_tol(mpm_material_ngf_diffusion_number(&par, dt, 1, m.dx, m.dy, 0.0), r_target,
                          1e-12);
  enum { N = 24 };
  double x[N], y[N], ms[N], g[N];
  for (int j = 0, p = 0; j < 4; j++)
    for (int i = 0; i < 6; i++, p++) {
      x[p] = m.x0 + (i + 0.5) * m.dx;
      y[p] = m.y0 + (j + 0.5) * m.dy;
      ms[p] = 1.0;
      g[p] = 1.0 + 1e-6 * ((i + j) % 2 ? -1.0 : 1.0);
    }
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_CENTRE, N, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(ws, &m, N, x, y, NULL, &err), MPM_OK);
  for (int p = 0; p < N; p++)
    ws->dense[p] = 1;                                   /* the workspace's flag array */
  for (int s = 0; s < steps; s++) {
    mpm_nonlocal_average(ws, N, ms, g, ws->dense);
    mpm_nonlocal_laplacian(ws);
    for (int p = 0; p < N; p++)
      g[p] = fmax(0.0, g[p] + k * mpm_nonlocal_point_lap(ws, (size_t)p));
  }
  mpm_nonlocal_free(ws);
  return fabs(g[0] - 1.0);
}

START_TEST(t_diffusion_limit_sharp)
{
  ck_assert_double_eq_tol(checker_amplitude(1.0, 100), 1e-6, 1e-12);
  ck_assert_double_eq_tol(checker_amplitude(0.5, 1), 0.0, 1e-14);      /* 1 - 2r = 0 */
  double grown = checker_amplitude(1.05, 100);
  ck_assert_double_eq_tol(grown, 1e-6 * pow(1.1, 100), 1e-6 * pow(1.1, 100) * 1e-6);
}
END_TEST

/* Mean of q^-1/2 over s, t in [-1, 1], q = p0 + a s + c t, by the product
 * midpoint rule on n x n cells (error O(1/n^2) away from q = 0). */
static double midpoint_mean_isqrt(double p0, double a, double c, int n)
{
  double sum = 0.0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      sum += 1.0 / sqrt(p0 + a * (-1.0 + (i + 0.5) * 2.0 / n) + c * (-1.0 + (j + 0.5) * 2.0 / n));
  return sum / ((double)n * n);
}

START_TEST(t_mean_isqrt)
{
  const double p0 = 7.3;
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, 0.0, 0.0), 1.0 / sqrt(p0), 1e-16);
  /* 1D: int_{-1}^{1} (p0 + a s)^-1/2 ds / 2 = 2 / (sqrt(p0 + a) + sqrt(p0 - a)),
   * across the Taylor / closed-form switch, up to q = 0 at one end */
  for (double r = 1e-9; r <= 1.0; r *= 1.7) {
    double a = r * p0, want = 2.0 / (sqrt(p0 + a) + sqrt(p0 - a));
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, a, 0.0), want, 1e-12 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, 0.0, -a), want, 1e-12 * want);
  }
  double top = 2.0 / sqrt(2.0 * p0);                     /* q from 0 to 2 p0 */
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, p0, 0.0), top, 1e-14 * top);
  /* 2D against quadrature (4000^2 cells: relative error below 1e-8 here) */
  const double ac[][2] = {{0.3, 0.2}, {-1.1, 2.4}, {3.0, 1e-5}, {1e-3, 5e-4}};
  for (size_t k = 0; k < sizeof ac / sizeof ac[0]; k++) {
    double want = midpoint_mean_isqrt(p0, ac[k][0], ac[k][1], 4000);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, ac[k][0], ac[k][1]), want, 1e-8 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt(p0, ac[k][1], -ac[k][0]), want, 1e-8 * want);
  }
}
END_TEST

/* Mean of q^-1/2 over s, t, u in [-1, 1], q = p0 + a s + b t + c u, by the
 * product midpoint rule on n^3 cells. */
static double midpoint_mean_isqrt3(double p0, double a, double b, double c, int n)
{
  double sum = 0.0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int k = 0; k < n; k++)
        sum += 1.0 / sqrt(p0 + a * (-1.0 + (i + 0.5) * 2.0 / n) +
                          b * (-1.0 + (j + 0.5) * 2.0 / n) + c * (-1.0 + (k + 0.5) * 2.0 / n));
  return sum / ((double)n * n * n);
}

/* The box mean (mpm_nonlocal_mean_isqrt3): with one or two half-ranges 0 it
 * is the square's or the segment's mean (the z-invariant column of a 3D run
 * must read the plane's p^-1/2), in any order of its arguments, across the
 * Taylor / closed-form switches, up to q = 0 at one corner or along one
 * face, where a free surface's limiter puts it (a unit with p0 = |a|: the
 * 1D mean 2 / sqrt(2 p0)); and the 3D mean against quadrature (400^3 cells:
 * relative error below 1e-5 away from q = 0, 1e-3 with q = 0 at a corner,
 * where q^-1/2 is integrable but the midpoint rule converges slowly). */
START_TEST(t_mean_isqrt3)
{
  const double p0 = 7.3;
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, 0.0, 0.0), 1.0 / sqrt(p0), 1e-16);
  for (double r = 1e-9; r <= 1.0; r *= 1.7) {
    const double a = r * p0, want = 2.0 / (sqrt(p0 + a) + sqrt(p0 - a));
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, a, 0.0, 0.0), want, 1e-12 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, -a, 0.0), want, 1e-12 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, 0.0, a), want, 1e-12 * want);
  }
  const double top = 2.0 / sqrt(2.0 * p0);                 /* q from 0 to 2 p0 */
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, -p0, 0.0), top, 1e-14 * top);
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, p0, 0.0, 0.0), top, 1e-14 * top);
  /* the limiter's scaling can leave the range an ulp past q = 0 */
  const double past = nextafter(p0, 2.0 * p0);
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, past, 0.0), top, 1e-14 * top);
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, past, 0.0),
                          mpm_nonlocal_mean_isqrt(p0, past, 0.0), 1e-14 * top);
  const double ac[][2] = {{0.3, 0.2}, {-1.1, 2.4}, {3.0, 1e-5}, {1e-3, 5e-4}, {-4.0, 3.3}};
  for (size_t k = 0; k < sizeof ac / sizeof ac[0]; k++) {
    const double a = ac[k][0], c = ac[k][1], want = mpm_nonlocal_mean_isqrt(p0, a, c);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, a, c, 0.0), want, 1e-12 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 0.0, a, c), want, 1e-12 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, c, 0.0, -a), want, 1e-12 * want);
  }
  const double abc[][3] = {{0.3, 0.2, 0.1}, {-1.1, 2.4, 0.7}, {3.0, 1e-5, -2.0}};
  for (size_t k = 0; k < sizeof abc / sizeof abc[0]; k++) {
    const double a = abc[k][0], b = abc[k][1], c = abc[k][2];
    const double want = midpoint_mean_isqrt3(p0, a, b, c, 400);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, a, b, c), want, 1e-5 * want);
    ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, -c, a, b), want, 1e-5 * want);
  }
  const double corner = midpoint_mean_isqrt3(p0, 2.0, 3.0, -2.3, 400);   /* q = 0 at a corner */
  ck_assert_double_eq_tol(mpm_nonlocal_mean_isqrt3(p0, 2.0, 3.0, -2.3), corner, 1e-3 * corner);
}
END_TEST

/* mpm_nonlocal_pressure on a chute-like column (periodic along x, no-slip
 * bottom, free top) with p linear in y, p = kap (H - y), 4 points per unit at
 * random masses and the p of their unit centre: every unit gets the exact
 * mean of p^-1/2 over its extent, the top one 2 / sqrt(p at its bottom face)
 * (the limiter holds the reconstruction at 0 on the free surface); a unit
 * whose one-sided extrapolation would go negative is limited to 0 there;
 * empty units get 0. */
static double linear_p(const double *c, double x, double y)
{
  (void)x;
  return c[0] * (c[1] - y);
}

static int lower_six(int i, int j)
{
  (void)i;
  return j < 6;
}

START_TEST(t_unit_pressure_column)
{
  mpm_mesh m = make_mesh(2, 8, 0.01, 0.02, 1, 0);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE};
  const double coef[2] = {150.0, m.y0 + 6 * m.dy};       /* kap, H: six filled units */
  cloud c = make_cloud(&m, 2, linear_p, coef, lower_six, 5u);
  mpm_nonlocal *ws = run(&m, edge, &c);
  mpm_nonlocal_pressure(ws, c.n, c.m, c.g, c.dense);     /* c.g holds p here */
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++) {
      double lo = linear_p(coef, 0.0, m.y0 + j * m.dy), hi = linear_p(coef, 0.0, m.y0 + (j + 1) * m.dy);
      double want = j < 6 ? 2.0 / (sqrt(lo) + sqrt(hi)) : 0.0;
      /* top unit: a round-off delta in the reconstructed surface value moves
       * the mean by ~ sqrt(delta / p); elsewhere round-off only */
      double tol = (j == 5 ? 1e-7 : 1e-13) * want;
      ck_assert_msg(fabs(ws->isp[i + m.nx * j] - want) <= tol,
                    "unit (%d, %d): isp %.17g, want %.17g", i, j, ws->isp[i + m.nx * j], want);
    }
  ck_assert_double_eq_tol(ws->isp[5 * m.nx], 2.0 / sqrt(coef[0] * m.dy), 1e-7);
  mpm_nonlocal_free(ws);
  /* two units, p = 1 above p = 5: the top one extrapolates to 1 - 2 < 0 at its
   * top face, limited to 0 there: the mean over q in [0, 2] is 2 / sqrt(2) */
  mpm_mesh m2 = make_mesh(1, 3, 0.1, 0.1, 0, 0);
  int e2[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FREE};
  double x[2] = {m2.x0 + 0.05, m2.x0 + 0.05}, y[2] = {m2.y0 + 0.05, m2.y0 + 0.15};
  double ms[2] = {1.0, 1.0}, g[2] = {0.0, 0.0}, pr[2] = {5.0, 1.0};
  unsigned char d[2] = {1, 1};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m2, e2, MPM_NONLOCAL_CENTRE, 2, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(ws, &m2, 2, x, y, NULL, &err), MPM_OK);
  mpm_nonlocal_average(ws, 2, ms, g, d);
  mpm_nonlocal_pressure(ws, 2, ms, pr, d);
  ck_assert_double_eq_tol(ws->isp[1], sqrt(2.0), 1e-14);
  /* the bottom one: one-sided 5 -> 1 gives q in [3, 7] (the wall does not count) */
  ck_assert_double_eq_tol(ws->isp[0], 2.0 / (sqrt(3.0) + sqrt(7.0)), 1e-14);
  ck_assert_double_eq(ws->isp[2], 0.0);                 /* empty */
  ck_assert_double_eq_tol(mpm_nonlocal_point_isp(ws, 1), sqrt(2.0), 1e-14);
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}
END_TEST

/* A plane p = p0 + gx x + gy y on a 3 x 3 block surrounded by empty units:
 * central differences in the middle unit, one-sided at the block's sides,
 * each the exact mean of p^-1/2 of the plane over its unit (quadrature). */
static double plane_p(const double *c, double x, double y)
{
  return c[0] + c[1] * x + c[2] * y;
}

static int block3(int i, int j)
{
  return i >= 1 && i <= 3 && j >= 1 && j <= 3;
}

START_TEST(t_unit_pressure_plane)
{
  mpm_mesh m = make_mesh(5, 5, 0.1, 0.08, 0, 0);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  const double coef[3] = {200.0, 60.0, -90.0};           /* p >= 42 on the block */
  cloud c = make_cloud(&m, 3, plane_p, coef, block3, 9u);
  mpm_nonlocal *ws = run(&m, edge, &c);
  mpm_nonlocal_pressure(ws, c.n, c.m, c.g, c.dense);
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++) {
      double xc = m.x0 + (i + 0.5) * m.dx, yc = m.y0 + (j + 0.5) * m.dy;
      double want = block3(i, j) ? midpoint_mean_isqrt(plane_p(coef, xc, yc), coef[1] * m.dx / 2,
                                                       coef[2] * m.dy / 2, 2000) : 0.0;
      ck_assert_double_eq_tol(ws->pe[i + m.nx * j], block3(i, j) ? plane_p(coef, xc, yc) : 0.0,
                              1e-12);
      ck_assert_msg(fabs(ws->isp[i + m.nx * j] - want) <= 1e-7 * want,
                    "unit (%d, %d): isp %.17g, want %.17g", i, j, ws->isp[i + m.nx * j], want);
    }
  mpm_nonlocal_free(ws);
  cloud_free(&c);
}
END_TEST

/* Errors: mismatched periodic edges, unknown kinds, an unknown rule,
 * a point outside the mesh; free(NULL). */
START_TEST(t_errors)
{
  mpm_mesh m = make_mesh(3, 3, 0.1, 0.1, 1, 0);
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  int e1[4] = {MPM_BC_PERIODIC, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, e1, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  ck_assert_ptr_null(ws);
  int e2[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, e2, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  int e3[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, 42, MPM_BC_FREE};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, e3, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  ck_assert_msg(strstr(err.msg, "bottom") != NULL, "%s", err.msg);
  int ok[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, ok, MPM_NONLOCAL_EXTENT + 1, 1, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, ok, MPM_NONLOCAL_CENTRE, 0, &err), MPM_OK);
  double x[2] = {0.0, 0.0}, y[2] = {1.3, 1.0};   /* y0 = 1.25: the second is below */
  ck_assert_int_eq(locate_xy(ws, &m, 2, x, y, NULL, &err), MPM_EOUTSIDE);
  ck_assert_msg(strstr(err.msg, "point 1 at") != NULL, "%s", err.msg);
  mpm_nonlocal_free(ws);
  mpm_nonlocal_free(NULL);
}
END_TEST

/* ---- extent rule (material.g_average = "extent") ------------------- */

/* Workspace under the extent rule, n points located with half-vectors
 * r1 = (r1x, r1y), r2 = (r2x, r2y). */
static mpm_nonlocal *extent_ws(const mpm_mesh *m, const int edge[4], size_t n, const double *x,
                               const double *y, const double *r1x, const double *r1y,
                               const double *r2x, const double *r2y)
{
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, m, edge, MPM_NONLOCAL_EXTENT, 1, &err), MPM_OK);
  const double *const r[4] = {r1x, r1y, r2x, r2y};
  ck_assert_msg(locate_xy(ws, m, n, x, y, r, &err) == MPM_OK, "%s", err.msg);
  return ws;
}

/* Weight of unit e in the pairs of point p (0 if it is not among them). */
static double weight_of(const mpm_nonlocal *ws, size_t p, int e)
{
  double w = 0.0;
  for (int k = 0; k < ws->nparts; k++)
    if (ws->part[ws->nparts * p + k] == e)
      w += ws->w[ws->nparts * p + k];
  return w;
}

/* Points whose extents lie inside their units (2 x 2 points per unit with
 * the fill's half-widths dx/4, dy/4, jittered by less than the gap to the
 * faces): g_e, lap_e, point_lap and the unit pressures equal the centre
 * rule's bitwise, and a uniform g stays uniform. */
START_TEST(t_extent_inside_is_centre)
{
  mpm_mesh m = make_mesh(6, 5, 0.02, 0.03, 1, 0);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE};
  enum { N = 6 * 5 * 4 };
  double x[N], y[N], ms[N], g[N], gu[N], pr[N], r1x[N], r1y[N], r2x[N], r2y[N];
  unsigned char d[N];
  unsigned long sd = 29u;
  size_t n = 0;
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++)
      for (int q = 0; q < 4; q++, n++) {
        /* centre 1/4 or 3/4 of the unit +- 0.1 unit, half-width 0.12 unit: inside */
        x[n] = m.x0 + (i + 0.25 + 0.5 * (q % 2) + 0.2 * (lcg(&sd) - 0.5)) * m.dx;
        y[n] = m.y0 + (j + 0.25 + 0.5 * (q / 2) + 0.2 * (lcg(&sd) - 0.5)) * m.dy;
        r1x[n] = 0.12 * m.dx;
        r1y[n] = 0.0;
        r2x[n] = 0.0;
        r2y[n] = -0.12 * m.dy;                          /* signs do not matter */
        ms[n] = 0.5 + lcg(&sd);
        g[n] = 10.0 * lcg(&sd);
        gu[n] = 3.25;
        pr[n] = 100.0 + 50.0 * lcg(&sd);
        d[n] = lcg(&sd) < 0.8;
      }
  mpm_nonlocal *we = extent_ws(&m, edge, N, x, y, r1x, r1y, r2x, r2y), *wc = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&wc, &m, edge, MPM_NONLOCAL_CENTRE, N, &err), MPM_OK);
  ck_assert_int_eq(locate_xy(wc, &m, N, x, y, NULL, &err), MPM_OK);
  for (size_t p = 0; p < N; p++) {
    ck_assert_int_eq(we->unit[p], wc->unit[p]);
    ck_assert(weight_of(we, p, wc->unit[p]) == 1.0);   /* exactly one pair, weight 1 */
  }
  mpm_nonlocal *both[2] = {we, wc};
  for (int k = 0; k < 2; k++) {
    mpm_nonlocal_average(both[k], N, ms, g, d);
    mpm_nonlocal_laplacian(both[k]);
    mpm_nonlocal_pressure(both[k], N, ms, pr, d);
  }
  for (int e = 0; e < m.nx * m.ny; e++) {
    ck_assert(we->sm[e] == wc->sm[e] && we->ge[e] == wc->ge[e] && we->lap[e] == wc->lap[e]);
    ck_assert(we->pe[e] == wc->pe[e] && we->isp[e] == wc->isp[e]);
  }
  for (size_t p = 0; p < N; p++) {
    ck_assert(mpm_nonlocal_point_lap(we, p) == mpm_nonlocal_point_lap(wc, p));
    ck_assert(mpm_nonlocal_point_isp(we, p) == mpm_nonlocal_point_isp(wc, p));
  }
  /* uniform g: every filled unit holds 3.25 (a mean of 4 equal values: a
   * few eps), so lap_e = 0 but in the bottom row, next to the no-slip wall:
   * (g - 2g - g)/dy^2 */
  mpm_nonlocal_average(we, N, ms, gu, d);
  mpm_nonlocal_laplacian(we);
  for (int e = 0; e < m.nx * m.ny; e++)
    if (we->sm[e] > 0.0) {
      ck_assert_double_eq_tol(we->ge[e], 3.25, 16.0 * DBL_EPSILON * 3.25);
      double want = e < m.nx ? -2.0 * 3.25 / (m.dy * m.dy) : 0.0;
      ck_assert_double_eq_tol(we->lap[e], want, lap_tol(3.25, m.dx, m.dy));
    }
  mpm_nonlocal_free(we);
  mpm_nonlocal_free(wc);
}
END_TEST

/* A point centred on the common corner of four units with a square extent
 * (half-width a quarter unit; given once as r1 = (h, 0), r2 = (0, h), once as
 * the rotated diamond r1 = (h/2, h/2), r2 = (-h/2, h/2), whose bounding box is
 * the same square) gives 1/4 to each; one straddling a vertical face with 30%
 * of its width on the left gives 0.3 / 0.7. */
START_TEST(t_extent_corner_and_face)
{
  mpm_mesh m = make_mesh(4, 4, 0.1, 0.1, 0, 0);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  const double h = 0.025, xc = m.x0 + 2 * m.dx, yc = m.y0 + 2 * m.dy;
  /* face between units (1, 1) and (2, 1) at x = x0 + 0.2; width 2h = 0.05:
   * 0.015 left of it, 0.035 right; vertically inside row 1 */
  double x[3] = {xc, xc, m.x0 + 0.2 + 0.01}, y[3] = {yc, yc, m.y0 + 0.15};
  double r1x[3] = {h, h / 2, h}, r1y[3] = {0.0, h / 2, 0.0};
  double r2x[3] = {0.0, -h / 2, 0.0}, r2y[3] = {h, h / 2, 0.03};
  mpm_nonlocal *ws = extent_ws(&m, edge, 3, x, y, r1x, r1y, r2x, r2y);
  const int four[4] = {1 + 4 * 1, 2 + 4 * 1, 1 + 4 * 2, 2 + 4 * 2};
  for (size_t p = 0; p < 2; p++)
    for (int k = 0; k < 4; k++)
      ck_assert_double_eq_tol(weight_of(ws, p, four[k]), 0.25, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 2, 1 + 4 * 1), 0.3, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 2, 2 + 4 * 1), 0.7, 1e-13);
  /* the sums: masses 2, 1, 10 and g 4, 8, 1; only the third point in
   * unit (1, 1) beside the first two's quarters:
   * g_(1,1) = (0.25*2*4 + 0.25*1*8 + 0.3*10*1) / (0.25*2 + 0.25*1 + 0.3*10) */
  double ms[3] = {2.0, 1.0, 10.0}, g[3] = {4.0, 8.0, 1.0};
  unsigned char d[3] = {1, 1, 1};
  mpm_nonlocal_average(ws, 3, ms, g, d);
  ck_assert_double_eq_tol(ws->sm[1 + 4 * 1], 0.75 + 3.0, 1e-13);
  ck_assert_double_eq_tol(ws->ge[1 + 4 * 1], (2.0 + 2.0 + 3.0) / 3.75, 1e-13);
  ck_assert_double_eq_tol(ws->ge[2 + 4 * 1], (2.0 + 2.0 + 7.0) / 7.75, 1e-13);
  ck_assert_double_eq_tol(ws->ge[1 + 4 * 2], 4.0 / 0.75, 1e-13);       /* quarters only */
  ck_assert_double_eq(ws->sm[0], 0.0);
  /* a point reads the weighted mean of the lap_e of its filled units */
  for (int e = 0; e < 16; e++)
    ws->lap[e] = 100.0 * e;
  double want = 0.3 * ws->lap[5] + 0.7 * ws->lap[6];
  ck_assert_double_eq_tol(mpm_nonlocal_point_lap(ws, 2), want, 1e-10);
  ck_assert_double_eq_tol(mpm_nonlocal_point_lap(ws, 0), (500.0 + 600.0 + 900.0 + 1000.0) / 4,
                          1e-10);
  for (int e = 0; e < 16; e++)
    ws->isp[e] = 0.01 * (e + 1);
  ck_assert_double_eq_tol(mpm_nonlocal_point_isp(ws, 2), 0.3 * 0.06 + 0.7 * 0.07, 1e-15);
  mpm_nonlocal_free(ws);
}
END_TEST

/* point_lap over filled units only: with unit (2, 1) empty (the straddling
 * point not dense, the others absent), a point 30/70 across the face reads
 * unit (1, 1)'s lap_e alone; with neither filled, 0. */
START_TEST(t_extent_point_lap_filled_only)
{
  mpm_mesh m = make_mesh(4, 3, 0.1, 0.1, 0, 0);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  double x[2] = {m.x0 + 0.2 + 0.01, m.x0 + 0.15}, y[2] = {m.y0 + 0.15, m.y0 + 0.15};
  double r1x[2] = {0.025, 0.025}, r1y[2] = {0, 0}, r2x[2] = {0, 0}, r2y[2] = {0.025, 0.025};
  mpm_nonlocal *ws = extent_ws(&m, edge, 2, x, y, r1x, r1y, r2x, r2y);
  double ms[2] = {1.0, 1.0}, g[2] = {2.0, 5.0};
  unsigned char d[2] = {0, 1};                          /* only the inside point is dense */
  mpm_nonlocal_average(ws, 2, ms, g, d);
  ck_assert(filled(ws, 1, 1) && !filled(ws, 2, 1));
  ws->lap[5] = 7.0;
  ws->lap[6] = 1e6;                                     /* must not be read: empty */
  ck_assert_double_eq_tol(mpm_nonlocal_point_lap(ws, 0), 7.0, 1e-14);
  d[1] = 0;
  mpm_nonlocal_average(ws, 2, ms, g, d);
  ck_assert_double_eq(mpm_nonlocal_point_lap(ws, 0), 0.0);
  mpm_nonlocal_free(ws);
}
END_TEST

/* Mesh edges: a point 30% beyond a non-periodic edge keeps only its inside
 * part (weight 1 on its unit); at a corner of the mesh too. Across periodic
 * edges the part wraps to the opposite unit: 0.3 / 0.7 horizontally, and at
 * a doubly periodic corner the four corner units get 0.09, 0.21, 0.21, 0.49. */
START_TEST(t_extent_mesh_edges)
{
  const double h = 0.025;                               /* extent 0.05 = half a unit */
  double r1x[2] = {h, h}, r1y[2] = {0, 0}, r2x[2] = {0, 0}, r2y[2] = {h, h};
  /* left edge at x0: 0.015 of the width outside; bottom-left corner likewise */
  mpm_mesh m = make_mesh(4, 3, 0.1, 0.1, 0, 0);
  int fr[4] = {MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_SYMMETRY, MPM_BC_FREE};
  double x[2] = {m.x0 + 0.01, m.x0 + 0.01}, y[2] = {m.y0 + 0.15, m.y0 + 0.01};
  mpm_nonlocal *ws = extent_ws(&m, fr, 2, x, y, r1x, r1y, r2x, r2y);
  ck_assert(weight_of(ws, 0, 0 + 4 * 1) == 1.0);
  ck_assert(weight_of(ws, 1, 0) == 1.0);
  mpm_nonlocal_free(ws);
  /* the same on a non-periodic right edge, 30% outside */
  double xr[1] = {m.x0 + m.lx - 0.01}, yr[1] = {m.y0 + 0.25};
  ws = extent_ws(&m, fr, 1, xr, yr, r1x, r1y, r2x, r2y);
  ck_assert(weight_of(ws, 0, 3 + 4 * 2) == 1.0);
  mpm_nonlocal_free(ws);
  /* periodic in x: 0.015 left of x0 wraps to unit nx - 1 */
  mpm_mesh mp = make_mesh(4, 3, 0.1, 0.1, 1, 0);
  int pe[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_FREE, MPM_BC_FREE};
  ws = extent_ws(&mp, pe, 1, x, y, r1x, r1y, r2x, r2y);
  ck_assert_double_eq_tol(weight_of(ws, 0, 3 + 4 * 1), 0.3, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 0, 0 + 4 * 1), 0.7, 1e-13);
  mpm_nonlocal_free(ws);
  /* doubly periodic, centre 0.01 inside the top-right corner: 70% of each
   * side in the corner unit, 30% wrapped */
  mpm_mesh m2 = make_mesh(4, 3, 0.1, 0.1, 1, 1);
  int pp[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  double xc[1] = {m2.x0 + m2.lx - 0.01}, yc[1] = {m2.y0 + m2.ly - 0.01};
  ws = extent_ws(&m2, pp, 1, xc, yc, r1x, r1y, r2x, r2y);
  ck_assert_double_eq_tol(weight_of(ws, 0, 3 + 4 * 2), 0.49, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 0, 0 + 4 * 2), 0.21, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 0, 3 + 4 * 0), 0.21, 1e-13);
  ck_assert_double_eq_tol(weight_of(ws, 0, 0 + 4 * 0), 0.09, 1e-13);
  mpm_nonlocal_free(ws);
}
END_TEST

/* A quadratic g sampled by points whose extents lie well inside their units
 * keeps the exact interior Laplacian 2e + 2f. A uniform g stays uniform when
 * every point has the largest extent (half-widths dx/2, dy/2), most of them
 * straddling faces and the mesh edges: the weights of each point sum to 1 and
 * the units hold all the dense mass. */
START_TEST(t_extent_quadratic_and_uniform)
{
  mpm_mesh m = make_mesh(9, 7, 0.013, 0.021, 0, 0);
  int edge[4] = {MPM_BC_NOSLIP, MPM_BC_FREE, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY};
  const double coef[5] = {2.0, -3.0, 1.5, 40.0, -25.0};
  cloud c = make_cloud(&m, 3, quad_field, coef, NULL, 11u);
  /* make_cloud puts centres >= 0.05 unit from the faces: half-width 0.04 unit */
  double *r1x = malloc(c.n * sizeof(double)), *r2y = malloc(c.n * sizeof(double));
  double *zero = calloc(c.n, sizeof(double));
  for (size_t p = 0; p < c.n; p++) {
    r1x[p] = 0.04 * m.dx;
    r2y[p] = 0.04 * m.dy;
  }
  mpm_nonlocal *ws = extent_ws(&m, edge, c.n, c.x, c.y, r1x, zero, zero, r2y);
  mpm_nonlocal_average(ws, c.n, c.m, c.g, c.dense);
  mpm_nonlocal_laplacian(ws);
  double gmax = 0.0;
  for (size_t p = 0; p < c.n; p++)
    gmax = fmax(gmax, fabs(c.g[p]));
  for (int j = 1; j < m.ny - 1; j++)
    for (int i = 1; i < m.nx - 1; i++)
      ck_assert_double_eq_tol(ws->lap[i + m.nx * j], 2.0 * coef[3] + 2.0 * coef[4],
                              lap_tol(gmax, m.dx, m.dy));
  mpm_nonlocal_free(ws);
  /* uniform g = 1.75 with every point at the largest extent (half a unit),
   * most straddling faces and edges: g_e stays 1.75 everywhere */
  for (size_t p = 0; p < c.n; p++) {
    r1x[p] = 0.5 * m.dx;
    r2y[p] = 0.5 * m.dy;
    c.g[p] = 1.75;
  }
  ws = extent_ws(&m, edge, c.n, c.x, c.y, r1x, zero, zero, r2y);
  mpm_nonlocal_average(ws, c.n, c.m, c.g, c.dense);
  mpm_nonlocal_laplacian(ws);
  /* g_e is a ratio of sums of at most ~40 positive terms w m g and w m, each
   * rounded: 64 eps covers it; the 5-point stencil then sees 4 such errors */
  const double gtol = 64.0 * DBL_EPSILON * 1.75;
  double sw = 0.0, smass = 0.0;
  for (int e = 0; e < m.nx * m.ny; e++) {
    ck_assert_double_eq_tol(ws->ge[e], 1.75, gtol);
    sw += ws->sm[e];
  }
  for (size_t p = 0; p < c.n; p++) {
    smass += c.m[p];
    double s = 0.0;
    for (int k = 0; k < ws->nparts; k++)
      s += ws->w[ws->nparts * p + k];
    ck_assert_double_eq_tol(s, 1.0, 4.0 * DBL_EPSILON);   /* weights sum to 1 */
  }
  ck_assert_double_eq_tol(sw, smass, 1e-12 * smass);      /* mass is conserved */
  for (int j = 0; j < m.ny; j++)
    for (int i = 0; i < m.nx; i++) {
      double want = i == 0 ? -2.0 * 1.75 / (m.dx * m.dx) : 0.0;  /* no-slip left edge */
      ck_assert_double_eq_tol(ws->lap[i + m.nx * j], want,
                              4.0 * gtol * (1.0 / (m.dx * m.dx) + 1.0 / (m.dy * m.dy)));
    }
  mpm_nonlocal_free(ws);
  free(r1x);
  free(r2y);
  free(zero);
  cloud_free(&c);
}
END_TEST

/* Extent errors: wider than a unit, unknown rule names. */
START_TEST(t_extent_errors)
{
  mpm_mesh m = make_mesh(3, 3, 0.1, 0.2, 0, 0);
  int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE, MPM_BC_FREE};
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_EXTENT, 2, &err), MPM_OK);
  double x[2] = {m.x0 + 0.15, m.x0 + 0.15}, y[2] = {m.y0 + 0.3, m.y0 + 0.3};
  double r1x[2] = {0.03, 0.03}, r1y[2] = {0.0, 0.0}, r2x[2] = {0.0, 0.021}, r2y[2] = {0.1, 0.1};
  const double *const r[4] = {r1x, r1y, r2x, r2y};
  ck_assert_int_eq(locate_xy(ws, &m, 2, x, y, r, &err), MPM_EINVAL);
  ck_assert_msg(strstr(err.msg, "point 1 at") != NULL, "%s", err.msg);   /* 0.051 > dx/2 */
  ck_assert_int_eq(locate_xy(ws, &m, 1, x, y, r, &err), MPM_OK);
  mpm_nonlocal_free(ws);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, 2, 1, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_rule_from_name("centre"), MPM_NONLOCAL_CENTRE);
  ck_assert_int_eq(mpm_nonlocal_rule_from_name("extent"), MPM_NONLOCAL_EXTENT);
  ck_assert_int_eq(mpm_nonlocal_rule_from_name("center"), -1);
  ck_assert_str_eq(mpm_nonlocal_rule_name(MPM_NONLOCAL_EXTENT), "extent");
  ck_assert_ptr_null(mpm_nonlocal_rule_name(2));
}
END_TEST

int main(void)
{
  Suite *s = suite_create("nonlocal");
  TCase *tc = tcase_create("nonlocal");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_average_mass_weighted);
  tcase_add_test(tc, t_quadratic_interior_exact);
  tcase_add_test(tc, t_ghost_rules_each_edge);
  tcase_add_test(tc, t_single_unit_corners);
  tcase_add_test(tc, t_empty_neighbour_neumann);
  tcase_add_test(tc, t_periodic_wrap);
  tcase_add_test(tc, t_diffusion_limit_sharp);
  tcase_add_test(tc, t_mean_isqrt);
  tcase_add_test(tc, t_mean_isqrt3);
  tcase_add_test(tc, t_unit_pressure_column);
  tcase_add_test(tc, t_unit_pressure_plane);
  tcase_add_test(tc, t_errors);
  tcase_add_test(tc, t_extent_inside_is_centre);
  tcase_add_test(tc, t_extent_corner_and_face);
  tcase_add_test(tc, t_extent_point_lap_filled_only);
  tcase_add_test(tc, t_extent_mesh_edges);
  tcase_add_test(tc, t_extent_quadratic_and_uniform);
  tcase_add_test(tc, t_extent_errors);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
