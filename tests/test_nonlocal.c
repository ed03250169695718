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
 * falls to 0. */
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
  ck_assert_int_eq(mpm_nonlocal_locate(ws, m, c->n, c->x, c->y, &err), MPM_OK);
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
  ck_assert_int_eq(mpm_nonlocal_locate(ws, &m, N, x, y, &err), MPM_OK);  /* grows */
  mpm_nonlocal_average(ws, N, ms, g, dense);
  mpm_nonlocal_laplacian(ws);
  for (int j = 0; j < 4; j++)
    for (int i = 0; i < 5; i++) {
      int e = i + 5 * j;
      ck_assert_int_eq(mpm_nonlocal_filled(ws, i, j), sm[e] > 0.0);
      if (sm[e] > 0.0)
        ck_assert_double_eq_tol(ws->ge[e], smg[e] / sm[e], 1e-14 * 10.0);
      else {
        ck_assert_double_eq(ws->ge[e], 0.0);
        ck_assert_double_eq(ws->lap[e], 0.0);
      }
    }
  for (int j = 3, i = 0; i < 5; i++)
    ck_assert(!mpm_nonlocal_filled(ws, i, j));
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
    ck_assert(!mpm_nonlocal_filled(ws, 2, j));
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
  ck_assert_int_eq(mpm_nonlocal_locate(ws, &m2, 2, x, y, &err), MPM_OK);
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
  double r1 = mpm_ngf_diffusion_number(&par, 1.0, 1, m.dx, m.dy);
  double dt = r_target / r1, k = dt / par.t0 * par.A * par.A * par.d * par.d;
  ck_assert_double_eq_tol(mpm_ngf_diffusion_number(&par, dt, 1, m.dx, m.dy), r_target, 1e-12);
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
  ck_assert_int_eq(mpm_nonlocal_locate(ws, &m, N, x, y, &err), MPM_OK);
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
  ck_assert_int_eq(mpm_nonlocal_locate(ws, &m2, 2, x, y, &err), MPM_OK);
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

/* Errors: mismatched periodic edges, unknown kinds, the unimplemented rule,
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
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, ok, MPM_NONLOCAL_EXTENT, 1, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, ok, MPM_NONLOCAL_CENTRE, 0, &err), MPM_OK);
  double x[2] = {0.0, 0.0}, y[2] = {1.3, 1.0};   /* y0 = 1.25: the second is below */
  ck_assert_int_eq(mpm_nonlocal_locate(ws, &m, 2, x, y, &err), MPM_EOUTSIDE);
  ck_assert_msg(strstr(err.msg, "point index 1") != NULL, "%s", err.msg);
  mpm_nonlocal_free(ws);
  mpm_nonlocal_free(NULL);
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
  tcase_add_test(tc, t_unit_pressure_column);
  tcase_add_test(tc, t_unit_pressure_plane);
  tcase_add_test(tc, t_errors);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
