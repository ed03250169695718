/* test_steady.c: the Galerkin solve of the steady fluidity on the mesh nodes
 * (src/nonlocal/steady.c, MODEL.md section 6), from the discrete equations.
 *
 * With 2 x 2 points per Q4 unit at the Gauss positions x = x_i + dx (1 +- 3^-1/2)/2
 * and V_p = dx dy / 4, point quadrature integrates S_i S_j and
 * gradS_i . gradS_j exactly, so the solve must give the finite element
 * solution to round-off:
 *  1. On a grid periodic in x and y, a nodal cosine c_i = cos(k x_i) with
 *     g_loc the bilinear interpolant of c is an eigenvector of both the 1D
 *     consistent mass (dx/6)(1, 4, 1) and stiffness (1/dx)(-1, 2, -1); the
 *     solution is g = G c with
 *       consistent: G = w M / (w M + K),   lumped: G = w M / (w + K),
 *       M = (2 + cos k dx)/3, K = (2 - 2 cos k dx)/dx^2.
 *     With w < 0 the matrix is indefinite (w M + K changes sign with k):
 *     Cholesky stops, the QR fallback must still give G c.
 *  2. g = 0 held on the left and right edges (no-slip, Dirichlet), g_loc = 1:
 *     the interior rows w dx (g_{i-1} + 4 g_i + g_{i+1})/6 + (2 g_i - g_{i-1}
 *     - g_{i+1})/dx = w dx, solved here by the Thomas algorithm; with free
 *     edges (zero flux) g = g_loc = 1 exactly.
 *  3. A point reads the mean of its unit's four nodal values (element) or
 *     sum S g (linear), as written out here for the cosine.
 *  4. The analysis is redone only when a point comes to touch a new pair of
 *     nodes; the factorisation every solve.
 *  5. One point per unit at the unit centres leaves the hourglass vector
 *     invisible: consistent mass is singular (an error naming the unknowns),
 *     lumped mass is not (and gives g = g_loc for uniform g_loc).
 *  6. The held nodes of the edge rules: Dirichlet edges held, an open outlet's
 *     nodes not; material.g_wall = "neumann" holds none.
 *  7. The field of one step through the NGF model: A = 0 gives the local
 *     fluidity g_loc = sqrt(p/(rho_s d^2)) (mu - mu_s)/(b mu) point by point. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/field.h"
#include "nonlocal/nonlocal.h"
#include "nonlocal/steady.h"
#include "shape/shape.h"
#include "plane.h"

#define TOL 1e-12

static mpm_mesh make_mesh(int nx, int ny, double dx, double dy, int px, int py)
{
  mpm_mesh m = {.nx = nx, .ny = ny, .dx = dx, .dy = dy, .topology = MPM_TOPO_Q4,
                .periodic_x = px, .periodic_y = py};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

/* n x n points per unit: Gauss positions (n = 2) or unit centres (n = 1). */
static mpm_points *make_points(const mpm_mesh *m, int n)
{
  mpm_points *P = mpm_points_alloc(16);
  const double g = 0.5 / sqrt(3.0);
  const double off2[2] = {0.5 - g, 0.5 + g}, off1[1] = {0.5};
  const double *off = n == 2 ? off2 : off1;
  for (int j = 0; j < m->ny; j++)
    for (int i = 0; i < m->nx; i++)
      for (int b = 0; b < n; b++)
        for (int a = 0; a < n; a++) {
          size_t p;
          ck_assert_int_eq(mpm_points_push(P, &p), MPM_OK);
          P->x[p] = m->x0 + (i + off[a]) * m->dx;
          P->y[p] = m->y0 + (j + off[b]) * m->dy;
          P->vol[p] = m->dx * m->dy / (n * n);
          P->mass[p] = 1500.0 * P->vol[p];
          P->r1x[p] = 0.5 * m->dx / n;
          P->r2y[p] = 0.5 * m->dy / n;
        }
  return P;
}

static mpm_shape_stencil *make_stencil(const mpm_mesh *m, const mpm_points *P)
{
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(P->n);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_delta, m, P, 0.0, &err), MPM_OK);
  return st;
}

/* Inputs of one solve: w, g_loc, all dense, nothing held. */
typedef struct inputs {
  double *w, *gloc;
  unsigned char *dense, *held;
} inputs;

static inputs make_inputs(size_t n, int nnodes, double w)
{
  inputs in = {malloc(n * sizeof(double)), malloc(n * sizeof(double)), malloc(n),
               calloc((size_t)nnodes, 1)};
  for (size_t p = 0; p < n; p++) {
    in.w[p] = w;
    in.gloc[p] = 0.0;
    in.dense[p] = 1;
  }
  return in;
}

static void free_inputs(inputs *in)
{
  free(in->w);
  free(in->gloc);
  free(in->dense);
  free(in->held);
}

/* ---- 1. cosine modes on a periodic grid --------------------------------- */

/* Solve for the mode m of a periodic 8 x 2 grid with weight w and mass rule
 * mass; check g = G c at every node; returns the solver statistics. */
static mpm_linalg_stats cosine_case(int mode, double w, int mass)
{
  const int nx = 8, ny = 2;
  const double dx = 0.1, dy = 0.05, pi = acos(-1.0);
  mpm_mesh m = make_mesh(nx, ny, dx, dy, 1, 1);
  mpm_points *P = make_points(&m, 2);
  mpm_shape_stencil *st = make_stencil(&m, P);
  inputs in = make_inputs(P->n, m.nnodes, w);
  const double k = 2.0 * pi * mode / (nx * dx);
  double *c = malloc((size_t)m.nnodes * sizeof *c);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      c[plane_node(&m, i, j)] = cos(k * i * dx);
  for (size_t p = 0; p < P->n; p++) {                  /* g_loc: the interpolant of c */
    in.gloc[p] = 0.0;
    for (int q = 0; q < st->count[p]; q++)
      in.gloc[p] += st->S[p * (size_t)st->w + q] * c[st->node[p * (size_t)st->w + q]];
  }
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&m, &err);
  ck_assert_ptr_nonnull(ss);
  int rc = mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense, in.held, mass,
                                     &err);
  ck_assert_msg(rc == MPM_OK, "mode %d, w %g: %s", mode, w, err.msg);
  const double M = (2.0 + cos(k * dx)) / 3.0, K = (2.0 - 2.0 * cos(k * dx)) / (dx * dx);
  const double G = mass == MPM_STEADY_LUMPED ? w * M / (w + K) : w * M / (w * M + K);
  const double *g = mpm_nonlocal_steady_nodal(ss);
  ck_assert_int_eq(mpm_nonlocal_steady_unknowns(ss), m.nnodes);
  for (int i = 0; i < m.nnodes; i++)
    ck_assert_msg(fabs(g[i] - G * c[i]) <= TOL * fabs(G),
                  "mode %d, w %g, %s: node %d: g = %.17g, want %.17g", mode, w,
                  mpm_nonlocal_steady_mass_name(mass), i, g[i], G * c[i]);
  /* 3. what the points read: element mean and interpolant */
  for (size_t p = 0; p < P->n; p++) {
    int i = (int)floor(P->x[p] / dx);
    double xl = i * dx, xr = (i + 1) * dx;
    double el = 0.5 * G * (cos(k * xl) + cos(k * xr));        /* mean of the 4 corners */
    double xi = (P->x[p] - xl) / dx, li = G * ((1.0 - xi) * cos(k * xl) + xi * cos(k * xr));
    double ge = mpm_nonlocal_steady_point(ss, &m, st, P, p, MPM_STEADY_ELEMENT);
    double gl = mpm_nonlocal_steady_point(ss, &m, st, P, p, MPM_STEADY_LINEAR);
    ck_assert(fabs(ge - fmax(el, 0.0)) <= TOL * fabs(G));
    ck_assert(fabs(gl - fmax(li, 0.0)) <= TOL * fabs(G));
  }
  mpm_linalg_stats s = mpm_nonlocal_steady_stats(ss);
  mpm_nonlocal_steady_free(ss);
  free(c);
  free_inputs(&in);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
  return s;
}

/* ---- a periodic column of one unit ---------------------------------------- */

/* On a periodic x axis of one unit a point lists each node twice (its two
 * node columns are one node): the solve must be the one of a wider periodic
 * mesh with the same points in every column, whose solution does not vary
 * along x. g_loc varies along y; zero flux at the bottom and top. */
static double *column_solve(int nx, int *nrows)
{
  const int ny = 6;
  mpm_mesh m = make_mesh(nx, ny, 0.1, 0.05, 1, 0);
  mpm_points *P = make_points(&m, 2);
  mpm_shape_stencil *st = make_stencil(&m, P);
  inputs in = make_inputs(P->n, m.nnodes, 40.0);
  for (size_t p = 0; p < P->n; p++)
    in.gloc[p] = 1.0 + 0.5 * cos(acos(-1.0) * P->y[p] / (ny * 0.05));
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&m, &err);
  ck_assert_ptr_nonnull(ss);
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  const double *g = mpm_nonlocal_steady_nodal(ss);
  double *rows = malloc((ny + 1) * sizeof *rows);
  for (int j = 0; j <= ny; j++) {
    rows[j] = g[plane_node(&m, 0, j)];
    for (int i = 1; i < nx; i++)                      /* nothing varies along x */
      ck_assert_double_eq_tol(g[plane_node(&m, i, j)], rows[j], TOL);
  }
  *nrows = ny + 1;
  mpm_nonlocal_steady_free(ss);
  free_inputs(&in);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
  return rows;
}

START_TEST(t_one_unit_column)
{
  int n1, n3;
  double *one = column_solve(1, &n1), *three = column_solve(3, &n3);
  ck_assert_int_eq(n1, n3);
  for (int j = 0; j < n1; j++)
    ck_assert_msg(fabs(one[j] - three[j]) <= TOL * fabs(three[j]),
                  "row %d: g = %.17g on one unit, %.17g on three", j, one[j], three[j]);
  ck_assert(three[0] > three[n3 - 1] + 0.1);          /* g follows g_loc along y */
  free(one);
  free(three);
}
END_TEST

START_TEST(t_cosine_modes)
{
  for (int mode = 1; mode <= 3; mode++) {
    mpm_linalg_stats s = cosine_case(mode, 50.0, MPM_STEADY_CONSISTENT);
    ck_assert_int_eq(s.fallback, 0);
    s = cosine_case(mode, 50.0, MPM_STEADY_LUMPED);
    ck_assert_int_eq(s.fallback, 0);
  }
}
END_TEST

/* w = -30 1/m^2: w M + K < 0 for the constant mode and > 0 for mode 3
 * (K = 200 (1 - cos(3 pi/4)) = 341 1/m^2 at dx = 0.1), so the matrix is
 * indefinite and regular: the QR fallback solves it. */
START_TEST(t_indefinite_qr)
{
  const double dx = 0.1, pi = acos(-1.0), k = 2.0 * pi * 3 / 0.8;
  ck_assert_double_gt(-30.0 * (2.0 + cos(k * dx)) / 3.0 + (2.0 - 2.0 * cos(k * dx)) / (dx * dx),
                      0.0);
  mpm_linalg_stats s = cosine_case(3, -30.0, MPM_STEADY_CONSISTENT);
  ck_assert_int_eq(s.fallback, 1);
  ck_assert_int_eq(s.fallbacks, 1);
  s = cosine_case(1, -30.0, MPM_STEADY_CONSISTENT);
  ck_assert_int_eq(s.fallback, 1);
}
END_TEST

/* ---- 2. held edges ------------------------------------------------------ */

START_TEST(t_dirichlet_rows)
{
  const int nx = 10, ny = 2;
  const double dx = 0.1, dy = 0.1, w = 30.0;
  mpm_mesh m = make_mesh(nx, ny, dx, dy, 0, 1);
  mpm_points *P = make_points(&m, 2);
  mpm_shape_stencil *st = make_stencil(&m, P);
  inputs in = make_inputs(P->n, m.nnodes, w);
  for (size_t p = 0; p < P->n; p++)
    in.gloc[p] = 1.0;
  for (int j = 0; j < ny; j++) {
    in.held[plane_node(&m, 0, j)] = 1;
    in.held[plane_node(&m, nx, j)] = 1;
  }
  /* the rows by hand, Thomas: a = w dx/6 - 1/dx, d = 4 w dx/6 + 2/dx, rhs w dx */
  const int n = nx - 1;
  double a = w * dx / 6.0 - 1.0 / dx, d[16], r[16], x[16];
  for (int i = 0; i < n; i++) {
    d[i] = 4.0 * w * dx / 6.0 + 2.0 / dx;
    r[i] = w * dx;
  }
  for (int i = 1; i < n; i++) {
    double f = a / d[i - 1];
    d[i] -= f * a;
    r[i] -= f * r[i - 1];
  }
  x[n - 1] = r[n - 1] / d[n - 1];
  for (int i = n - 2; i >= 0; i--)
    x[i] = (r[i] - a * x[i + 1]) / d[i];
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&m, &err);
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_steady_unknowns(ss), n * ny);
  const double *g = mpm_nonlocal_steady_nodal(ss);
  for (int j = 0; j < ny; j++) {
    ck_assert(g[plane_node(&m, 0, j)] == 0.0 && g[plane_node(&m, nx, j)] == 0.0);
    for (int i = 1; i < nx; i++)
      ck_assert_msg(fabs(g[plane_node(&m, i, j)] - x[i - 1]) <= TOL,
                    "node (%d, %d): %.17g, Thomas %.17g", i, j, g[plane_node(&m, i, j)],
                    x[i - 1]);
  }
  /* zero flux everywhere: the constant g_loc is the solution */
  memset(in.held, 0, (size_t)m.nnodes);
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  for (int i = 0; i < m.nnodes; i++)
    ck_assert_msg(fabs(g[i] - 1.0) <= TOL, "free: node %d: %.17g", i, g[i]);
  mpm_nonlocal_steady_free(ss);
  free_inputs(&in);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
}
END_TEST

/* ---- 4. analysis only when the pattern changes -------------------------- */

START_TEST(t_reuse_counts)
{
  mpm_mesh m = make_mesh(6, 4, 0.1, 0.1, 0, 0);
  mpm_points *P = make_points(&m, 2);
  mpm_points *Q = mpm_points_alloc(16);             /* only the left half */
  for (size_t p = 0; p < P->n; p++)
    if (P->x[p] < 0.3) {
      size_t q;
      mpm_points_push(Q, &q);
      Q->x[q] = P->x[p];
      Q->y[q] = P->y[p];
      Q->vol[q] = P->vol[p];
    }
  mpm_shape_stencil *st = make_stencil(&m, Q);
  inputs in = make_inputs(Q->n, m.nnodes, 20.0);
  for (size_t p = 0; p < Q->n; p++)
    in.gloc[p] = 1.0 + Q->y[p];
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&m, &err);
  for (int k = 0; k < 3; k++) {
    in.gloc[0] = 1.0 + 0.1 * k;                       /* new values, same pattern */
    ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, Q->n, Q->vol, in.w, in.gloc, in.dense,
                                               in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  }
  mpm_linalg_stats s = mpm_nonlocal_steady_stats(ss);
  ck_assert_int_eq(s.analyses, 1);
  ck_assert_int_eq(s.factors, 3);
  ck_assert_int_eq(s.solves, 3);
  ck_assert_int_eq(mpm_nonlocal_steady_unknowns(ss), 4 * 5);  /* nodes x = 0 .. 0.3 */
  Q->x[0] = 0.35;                                     /* into an empty unit: new nodes */
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_delta, &m, Q, 0.0, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, Q->n, Q->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  s = mpm_nonlocal_steady_stats(ss);
  ck_assert_int_eq(s.analyses, 2);
  ck_assert_int_eq(s.factors, 4);
  ck_assert_int_eq(mpm_nonlocal_steady_unknowns(ss), 4 * 5 + 2);
  for (size_t p = 0; p < Q->n; p++)                   /* nothing dense: g = 0, no solve */
    in.dense[p] = 0;
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, Q->n, Q->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_CONSISTENT, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_steady_unknowns(ss), 0);
  ck_assert_int_eq(mpm_nonlocal_steady_stats(ss).solves, 4);
  mpm_nonlocal_steady_free(ss);
  free_inputs(&in);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
  mpm_points_free(Q);
}
END_TEST

/* ---- 5. the hourglass vector at one point per unit ---------------------- */

START_TEST(t_hourglass)
{
  mpm_mesh m = make_mesh(4, 4, 0.1, 0.1, 1, 1);
  mpm_points *P = make_points(&m, 1);
  mpm_shape_stencil *st = make_stencil(&m, P);
  inputs in = make_inputs(P->n, m.nnodes, 20.0);
  for (size_t p = 0; p < P->n; p++)
    in.gloc[p] = 0.7;
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&m, &err);
  int rc = mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense, in.held,
                                     MPM_STEADY_CONSISTENT, &err);
  ck_assert_int_eq(rc, MPM_ESOLVE);
  ck_assert_msg(strstr(err.msg, "steady fluidity on 16 nodes") &&
                strstr(err.msg, "(material.g_mass = \"lumped\", or fill.ppu >= 2)"),
                "message: %s", err.msg);
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_LUMPED, &err), MPM_OK);
  const double *g = mpm_nonlocal_steady_nodal(ss);
  for (int i = 0; i < m.nnodes; i++)
    ck_assert(fabs(g[i] - 0.7) <= TOL);
  in.w[3] = NAN;                                      /* a bad point is named */
  ck_assert_int_eq(mpm_nonlocal_steady_solve(ss, st, &m, P->n, P->vol, in.w, in.gloc, in.dense,
                                             in.held, MPM_STEADY_LUMPED, &err), MPM_EINVAL);
  ck_assert_msg(strstr(err.msg, "point 3"), "message: %s", err.msg);
  mpm_nonlocal_steady_free(ss);
  free_inputs(&in);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
}
END_TEST

/* ---- 6. held nodes from the edge rules ---------------------------------- */

START_TEST(t_held_nodes)
{
  mpm_mesh m = make_mesh(6, 3, 0.1, 0.1, 0, 0);
  const int edge[4] = {MPM_BC_FRICTIONLESS, MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_CENTRE, 8, &err), MPM_OK);
  unsigned char *held = malloc((size_t)m.nnodes);
  mpm_nonlocal_held_nodes(ws, &m, held);
  for (int j = 0; j <= m.ny; j++)
    for (int i = 0; i <= m.nx; i++)
      ck_assert_int_eq(held[plane_node(&m, i, j)], j == 0);  /* the no-slip floor */
  const int lo[3] = {2, 0, 0}, hi[3] = {4, 0, 0};
  mpm_nonlocal_open_faces(ws, 2, lo, hi, NULL, &err);  /* outlet: faces 2, 3: nodes 2 .. 4 */
  mpm_nonlocal_held_nodes(ws, &m, held);
  for (int i = 0; i <= m.nx; i++)
    ck_assert_int_eq(held[plane_node(&m, i, 0)], i < 2 || i > 4);
  mpm_nonlocal_walls_neumann(ws);                     /* material.g_wall = "neumann" */
  mpm_nonlocal_held_nodes(ws, &m, held);
  for (int i = 0; i < m.nnodes; i++)
    ck_assert_int_eq(held[i], 0);
  free(held);
  mpm_nonlocal_free(ws);
}
END_TEST

/* ---- 7. the field of one step: A = 0 is the local fluidity -------------- */

START_TEST(t_field_local)
{
  mpm_mesh m = make_mesh(4, 2, 0.1, 0.1, 0, 0);
  mpm_points *P = make_points(&m, 2);
  mpm_shape_stencil *st = make_stencil(&m, P);
  mpm_config cfg = {0};
  mpm_material_config_dk15(&cfg);
  cfg.material.E = 1e6;
  cfg.material.A = 0.0;
  cfg.material.t0 = 1e-3;
  cfg.material.form = MPM_NGF_HS21;
  mpm_material_params par;
  mpm_material_params_from_config(&par, &cfg);
  for (size_t p = 0; p < P->n; p++) {                 /* p = 1 kPa, mu from 0 to 0.9 */
    const double mu = 0.9 * p / (P->n - 1.0);
    P->sxx[p] = P->syy[p] = P->szz[p] = -1000.0;
    P->sxy[p] = mu * 1000.0;                          /* tau = |sxy| for this state */
    P->state[p] = p == 5 ? MPM_STATE_DISCONNECTED : MPM_STATE_DENSE;
    P->g[p] = -1.0;
  }
  const int edge[4] = {MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_CENTRE, P->n, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_set_diffusion(ws, MPM_DIFFUSION_STEADY, &err), MPM_OK);
  ck_assert(mpm_nonlocal_is_steady(ws));
  ck_assert_int_eq(mpm_nonlocal_steady_field(ws, &mpm_material_ngf, &par, P, st, &m,
                                             MPM_STEADY_ELEMENT, MPM_STEADY_CONSISTENT, &err),
                   MPM_OK);
  const double b = (MPM_DK15_MU_2 - MPM_DK15_MU_S) / MPM_DK15_I0;
  for (size_t p = 0; p < P->n; p++) {
    const double mu = 0.9 * p / (P->n - 1.0);
    double want = mu > MPM_DK15_MU_S && p != 5
                      ? sqrt(1000.0 / MPM_DK15_RHO_S) / MPM_DK15_D * (mu - MPM_DK15_MU_S) / (b * mu)
                      : 0.0;
    ck_assert_msg(fabs(P->g[p] - want) <= TOL * fmax(want, 1.0), "point %zu: g %.17g, want %.17g",
                  p, P->g[p], want);
  }
  /* the (sub)step field of the dynamic solvers is not the steady solver's */
  ck_assert_int_eq(mpm_nonlocal_field(ws, &mpm_material_ngf, &par, P, NULL, 1e-4, 0, &err),
                   MPM_EINVAL);
  mpm_nonlocal_free(ws);
  mpm_shape_stencil_free(st);
  mpm_points_free(P);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("steady");
  TCase *tc = tcase_create("steady");
  tcase_add_test(tc, t_cosine_modes);
  tcase_add_test(tc, t_one_unit_column);
  tcase_add_test(tc, t_indefinite_qr);
  tcase_add_test(tc, t_dirichlet_rows);
  tcase_add_test(tc, t_reuse_counts);
  tcase_add_test(tc, t_hourglass);
  tcase_add_test(tc, t_held_nodes);
  tcase_add_test(tc, t_field_local);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
